"""Unchecked cores of :mod:`navlib.geodesy`: zone numbers, central meridians and the Gauss–Krüger series.

The checked public functions live in :mod:`navlib.geodesy`; each checks its arguments, then calls its core here.
A function of another module that has already checked its points, zone and ellipsoid (e.g.
:func:`navlib.papers.gauss_kruger_ekf.ekf`) calls the core directly, so that nothing is checked twice on one call.
Inputs are arrays of float64 within their ranges: latitudes in rad, longitudes and longitude offsets from the
central meridian in deg (offsets within the series' 60°), zone widths 3 or 6; ``ellipsoid`` is an
:class:`navlib.earth.Ellipsoid`.

The series is Krüger's in the third flattening n to order n^6 (Karney 2011, "Transverse Mercator with an
accuracy of a few nanometers", J. Geodesy 85:475, eqs. 7–11, 35–36), evaluated with Clenshaw summation on
complex numbers (see :mod:`navlib.geodesy`).
"""

from __future__ import annotations

import functools
from typing import TYPE_CHECKING

import numpy as np
from numba import njit

from ._kernels import fma
from ._typing import Array

if TYPE_CHECKING:
    from .earth import Ellipsoid

MAX_ETA = 1.2
"""Largest ``|eta|`` (easting over the rectifying radius and k0) the inverse series is used for."""


# --------------------------------------------------------------------------
# Zones
# --------------------------------------------------------------------------


def zone(lon_deg: Array, w: int) -> np.ndarray:
    """:func:`navlib.geodesy.zone` of checked longitudes (deg) and zone width ``w`` (3 or 6)."""
    L = np.mod(lon_deg, 360.0)
    n = np.floor((L + 1.5) / 3.0) if w == 3 else np.floor(L / 6.0) + 1
    n = n.astype(int)
    return np.where(n == 0, 360 // w, np.where(n > 360 // w, n - 360 // w, n))


def meridian(n: np.ndarray, w: int) -> np.ndarray:
    """Central meridians (deg, in (-180, 180]) of checked zone numbers ``n`` (float) of width ``w``."""
    L0 = w * n if w == 3 else 6 * n - 3
    return np.where(L0 > 180, L0 - 360, L0)


def normalised(
    x: Array, y: Array, ellipsoid: Ellipsoid, k0: float = 1.0, fn: float = 0.0, fe: float = 0.0
) -> tuple[Array, Array]:
    """xi, eta: northing and easting (m) less the false northing ``fn`` and easting ``fe``, over ``k0`` and the
    rectifying radius A; :func:`geodetic` takes them where ``|eta| <= MAX_ETA``."""
    A = kruger(ellipsoid.a, ellipsoid.f)[0]
    return (x - fn) / (k0 * A), (y - fe) / (k0 * A)


def geodetic(xi: Array, eta: Array, L0: Array, ellipsoid: Ellipsoid) -> tuple[Array, Array]:
    """Latitude (rad) and longitude (deg, in (-180, 180]) of normalised GK coordinates (:func:`normalised`)
    about the central meridian ``L0`` (deg)."""
    _, e, _, beta = kruger(ellipsoid.a, ellipsoid.f)
    lat, dlon = inverse(xi, eta, e, beta)
    lon_deg = L0 + np.rad2deg(dlon)
    lon_deg = np.mod(lon_deg + 180.0, 360.0) - 180.0
    return lat, np.where(lon_deg == -180.0, 180.0, lon_deg)


# --------------------------------------------------------------------------
# Krüger n-series (Karney 2011)
# --------------------------------------------------------------------------


@functools.lru_cache(maxsize=16)
def kruger(a: float, f: float) -> tuple[float, float, tuple[float, ...], tuple[float, ...]]:
    """Rectifying radius A, eccentricity e and the alpha/beta coefficients to order n^6 (tuples of 6 floats)."""
    n = f / (2 - f)
    n2, n3, n4, n5, n6 = n**2, n**3, n**4, n**5, n**6
    A = a / (1 + n) * (1 + n2 / 4 + n4 / 64 + n6 / 256)
    alpha = tuple(
        float(c)
        for c in (
            n / 2 - 2 * n2 / 3 + 5 * n3 / 16 + 41 * n4 / 180 - 127 * n5 / 288 + 7891 * n6 / 37800,
            13 * n2 / 48 - 3 * n3 / 5 + 557 * n4 / 1440 + 281 * n5 / 630 - 1983433 * n6 / 1935360,
            61 * n3 / 240 - 103 * n4 / 140 + 15061 * n5 / 26880 + 167603 * n6 / 181440,
            49561 * n4 / 161280 - 179 * n5 / 168 + 6601661 * n6 / 7257600,
            34729 * n5 / 80640 - 3418889 * n6 / 1995840,
            212378941 * n6 / 319334400,
        )
    )
    beta = tuple(
        float(c)
        for c in (
            n / 2 - 2 * n2 / 3 + 37 * n3 / 96 - n4 / 360 - 81 * n5 / 512 + 96199 * n6 / 604800,
            n2 / 48 + n3 / 15 - 437 * n4 / 1440 + 46 * n5 / 105 - 1118711 * n6 / 3870720,
            17 * n3 / 480 - 37 * n4 / 840 - 209 * n5 / 4480 + 5569 * n6 / 90720,
            4397 * n4 / 161280 - 11 * n5 / 504 - 830251 * n6 / 7257600,
            4583 * n5 / 161280 - 108847 * n6 / 3991680,
            20648693 * n6 / 638668800,
        )
    )
    return A, np.sqrt(f * (2 - f)), alpha, beta


# The compiled series works on (re, im) pairs. Complex products round as numpy's vectorised complex
# multiply does (one fused multiply-add per component) and zero signs follow numpy's complex arithmetic
# (the 0.0 terms below), so the results are those of the former all-numpy evaluation, bit for bit.


@njit(cache=True, inline="always")
def _cmul(ar, ai, br, bi):
    """(ar + i ai)(br + i bi) as (re, im), each component rounded once."""
    return fma(ar, br, -(ai * bi)), fma(ar, bi, ai * br)


@njit(cache=True, inline="always")
def _zeta2(sin2xi, cos2xi, sinh2eta, cosh2eta):
    """sin 2zeta and cos 2zeta of zeta = xi + i eta as (re, im) pairs, from the real double-angle functions."""
    v, w = cos2xi * sinh2eta, sin2xi * sinh2eta
    return sin2xi * cosh2eta + 0.0 * v, 0.0 + v, cos2xi * cosh2eta - 0.0 * w, 0.0 - w


@njit(cache=True, inline="always")
def _clenshaw(coef, c2r, c2i, weighted):
    """Clenshaw recurrence ``b_j = 2 cos(2 zeta) b_j+1 - b_j+2 + w_j coef[j]`` (complex), down to (b_1, b_2).

    ``w_j = 2(j+1)`` when ``weighted`` (the derivative's cosine sum), else 1. Then
    ``sum_j coef[j] sin(2(j+1) zeta) = sin(2 zeta) b_1`` and
    ``sum_j 2(j+1) coef[j] cos(2(j+1) zeta) = cos(2 zeta) b_1 - b_2``: one complex sine and
    cosine of 2 zeta and a recurrence replace six complex sines.
    """
    tr, ti = 2 * c2r, 2 * c2i
    b1r, b1i, b2r, b2i = 0.0, 0.0, 0.0, 0.0
    for j in range(len(coef) - 1, -1, -1):
        pr, pi = _cmul(tr, ti, b1r, b1i)
        w = 2 * (j + 1) * coef[j] if weighted else coef[j]
        b1r, b1i, b2r, b2i = pr - b2r + w, pi - b2i + 0.0, b1r, b1i
    return b1r, b1i, b2r, b2i


@njit(cache=True, inline="always")
def _gauss_schreiber(taup, u):
    """cos l, sin l (from u = tan(l/2)) and D = tau'^2 + cos^2 l of the Gauss-Schreiber zeta' (Karney eq. 10).

    Gauss-Schreiber: the spherical transverse Mercator of the conformal sphere, ``xi' = atan2(tau', cos l)``,
    ``eta' = asinh(sin l / sqrt(D))``.
    """
    cos_l = (1 - u * u) / (1 + u * u)
    sin_l = 2 * u / (1 + u * u)
    return cos_l, sin_l, taup * taup + cos_l * cos_l


@njit(cache=True, inline="always")
def _double_angles(taup, cos_l, sin_l, D):
    """sin 2xi', cos 2xi', sinh 2eta', cosh 2eta' of the Gauss-Schreiber zeta', algebraically."""
    return (
        2 * taup * cos_l / D,
        (cos_l * cos_l - taup * taup) / D,
        2 * sin_l * np.sqrt(1 + taup * taup) / D,
        1 + 2 * sin_l * sin_l / D,
    )


@njit(cache=True, error_model="numpy")
def _gauss_schreiber_args(tau, sig, u, taup, cos_l, r):
    """tau' (:func:`_conformal_from`), ``cos l`` and ``r = sin l / sqrt(D)`` into ``taup``, ``cos_l``, ``r``:
    then xi' = atan2(tau', cos l), eta' = asinh(r)."""
    for i in range(tau.shape[0]):
        tp = _conformal_from(tau[i], sig[i])
        c, s, D = _gauss_schreiber(tp, u[i])
        taup[i], cos_l[i], r[i] = tp, c, s / np.sqrt(D)


@njit(cache=True, error_model="numpy")
def _series_xy(taup, u, xi_p, eta_p, alpha, A, k0, fn, fe, x, y):
    """Northing ``x = k0 A (xi' + Re S) + fn`` and easting ``y = k0 A (eta' + Im S) + fe`` into ``x``, ``y`` (m).

    S = sum_j alpha[j] sin(2(j+1) zeta'), Karney eq. 11; all arrays 1-D of one length.
    """
    for i in range(taup.shape[0]):
        cos_l, sin_l, D = _gauss_schreiber(taup[i], u[i])
        sin2xi, cos2xi, sinh2eta, cosh2eta = _double_angles(taup[i], cos_l, sin_l, D)
        s2r, s2i, c2r, c2i = _zeta2(sin2xi, cos2xi, sinh2eta, cosh2eta)
        b1r, b1i, _, _ = _clenshaw(alpha, c2r, c2i, False)
        sr, si = _cmul(s2r, s2i, b1r, b1i)
        x[i] = k0 * (A * (xi_p[i] + sr)) + fn
        y[i] = k0 * (A * (eta_p[i] + si)) + fe


@njit(cache=True, error_model="numpy")
def _series_slope(taup, u, alpha, slope, cos_l, sin_l, D):
    """``slope = d zeta / d zeta' = 1 + sum_j 2(j+1) alpha[j] cos(2(j+1) zeta')`` (complex; Karney eqs. 13, 14),
    with the ``cos_l``, ``sin_l``, ``D`` of :func:`_gauss_schreiber`."""
    for i in range(taup.shape[0]):
        c, s, d = _gauss_schreiber(taup[i], u[i])
        cos_l[i], sin_l[i], D[i] = c, s, d
        sin2xi, cos2xi, sinh2eta, cosh2eta = _double_angles(taup[i], c, s, d)
        _, _, c2r, c2i = _zeta2(sin2xi, cos2xi, sinh2eta, cosh2eta)
        d1r, d1i, d2r, d2i = _clenshaw(alpha, c2r, c2i, True)
        pr, pi = _cmul(c2r, c2i, d1r, d1i)
        slope[i] = complex(1 + (pr - d2r), 0.0 + (pi - d2i))


@njit(cache=True, error_model="numpy")
def _series_inverse(xi, eta, sin2xi, cos2xi, sinh2eta, cosh2eta, beta, xi_p, eta_p):
    """``zeta' = zeta - sum_j beta[j] sin(2(j+1) zeta)`` into ``xi_p``, ``eta_p`` (Karney eq. 11 inverted)."""
    for i in range(xi.shape[0]):
        s2r, s2i, c2r, c2i = _zeta2(sin2xi[i], cos2xi[i], sinh2eta[i], cosh2eta[i])
        b1r, b1i, _, _ = _clenshaw(beta, c2r, c2i, False)
        sr, si = _cmul(s2r, s2i, b1r, b1i)
        xi_p[i] = xi[i] - sr
        eta_p[i] = eta[i] - si


@njit(cache=True, inline="always")
def _conformal_s(tau, e):
    """``s = e tau / sqrt(1 + tau^2)`` (e sin lat), whence ``sigma = sinh(e atanh(s))`` of Karney eq. 7."""
    return e * tau / np.sqrt(1 + tau * tau)


@njit(cache=True, error_model="numpy")
def _conformal_arg(tau, e, s):
    for i in range(tau.shape[0]):
        s[i] = _conformal_s(tau[i], e)


@njit(cache=True, error_model="numpy")
def _forward_args(tau, l_deg, e, s, h):
    """``s`` (:func:`_conformal_s`) and ``h = l / 2`` (rad, from l in deg) into ``s``, ``h``: then numpy's
    vectorised atanh, sinh and tan give sigma and u = tan(l/2)."""
    for i in range(tau.shape[0]):
        s[i] = _conformal_s(tau[i], e)
        h[i] = l_deg[i] * (np.pi / 180) / 2  # np.deg2rad(l_deg) / 2


@njit(cache=True, inline="always")
def _conformal_from(tau, sig):
    """tau' = tan of the conformal latitude from tau = tan(lat) and its sigma (Karney eq. 7)."""
    return np.sqrt(1 + sig * sig) * tau - sig * np.sqrt(1 + tau * tau)


@njit(cache=True, error_model="numpy")
def _conformal_into(tau, sig, taup):
    for i in range(tau.shape[0]):
        taup[i] = _conformal_from(tau[i], sig[i])


def _sigma(s, e):
    """sigma = sinh(e atanh(s)) of Karney eq. 7 (numpy's vectorised atanh and sinh), s from :func:`_conformal_s`."""
    return np.sinh(e * np.arctanh(s))


def _conformal_tan(tau, e):
    """tau' = tan of the conformal latitude, from tau = tan(lat) (Karney eq. 7); any shape."""
    t = np.reshape(tau, -1)
    s, taup = np.empty(t.shape), np.empty(t.shape)
    _conformal_arg(t, e, s)
    _conformal_into(t, _sigma(s, e), taup)
    return taup.reshape(np.shape(tau))[()]


def _geodetic_tan(taup: Array, e: float, iterations: int = 4) -> Array:
    """Invert :func:`_conformal_tan` by Newton's method (Karney eqs. 19–21); 4 steps reach 1e-16."""
    e2m = 1 - e * e
    tau = taup / e2m
    for _ in range(iterations):
        taupa = _conformal_tan(tau, e)
        tau = tau + (taup - taupa) * (1 + e2m * tau * tau) / (e2m * np.sqrt((1 + tau * tau) * (1 + taupa * taupa)))
    return tau


CHUNK = 1 << 15  # points per block: keeps the temporaries in cache


def forward(lat, l_deg, ellipsoid, k0=1.0, fn=-0.0, fe=-0.0, out=None):
    """GK northing and easting (m), ``k0 x + fn`` and ``k0 y + fe`` (:func:`navlib.geodesy.geodetic2gk`); ``out``: the
    (x, y) arrays to fill.

    lat (rad) and l_deg (longitude minus central meridian, deg) of one shape. (The default -0.0 adds
    nothing, not even to the sign of a zero.)
    """
    if lat.size > CHUNK:
        x, y = np.empty(lat.shape), np.empty(lat.shape)
        fx, fy, fl, fo = x.reshape(-1), y.reshape(-1), lat.reshape(-1), l_deg.reshape(-1)
        for i in range(0, lat.size, CHUNK):
            forward(fl[i : i + CHUNK], fo[i : i + CHUNK], ellipsoid, k0, fn, fe, (fx[i : i + CHUNK], fy[i : i + CHUNK]))
        return x, y
    A, e, alpha, _ = kruger(ellipsoid.a, ellipsoid.f)
    tau = np.tan(lat).reshape(-1)
    s, h = np.empty(tau.shape), np.empty(tau.shape)
    _forward_args(tau, l_deg.reshape(-1), e, s, h)
    u = np.tan(h)  # cos l and sin l from one tangent
    taup, cos_l, r = np.empty(u.shape), np.empty(u.shape), np.empty(u.shape)
    _gauss_schreiber_args(tau, _sigma(s, e), u, taup, cos_l, r)
    x, y = (np.empty(lat.shape), np.empty(lat.shape)) if out is None else out
    _series_xy(taup, u, np.arctan2(taup, cos_l), np.arcsinh(r), alpha, A, k0, fn, fe, x.reshape(-1), y.reshape(-1))
    return x[()], y[()]  # a 0-d input gives scalars, as numpy's arithmetic does


def factors(lat, l_deg, ellipsoid):
    """Grid convergence (rad) and point scale (k0 = 1) at lat (rad), l_deg (deg), of one shape."""
    A, e, alpha, _ = kruger(ellipsoid.a, ellipsoid.f)
    tau = np.tan(lat)
    taup = _conformal_tan(tau, e)
    slope, cos_l, sin_l, D = (np.empty(lat.shape, dtype=complex), np.empty(lat.shape), np.empty(lat.shape), np.empty(lat.shape))
    _series_slope(
        taup.reshape(-1), np.tan(np.deg2rad(l_deg) / 2).reshape(-1), alpha, *(a.reshape(-1) for a in (slope, cos_l, sin_l, D))
    )
    gamma = np.arctan2(sin_l * taup, cos_l * np.sqrt(1 + taup * taup)) - np.angle(slope)
    k = (A / ellipsoid.a) * np.abs(slope) * np.sqrt(1 - e * e * tau * tau / (1 + tau * tau)) * np.sqrt(1 + tau * tau) / np.sqrt(D)
    return gamma, k


def inverse(xi, eta, e, beta):
    """Geodetic latitude and longitude offset (rad) from the normalised GK coordinates xi + i eta."""
    if xi.size > CHUNK:
        lat, dlon = np.empty(xi.shape), np.empty(xi.shape)
        fl, fd, fx, fe = lat.reshape(-1), dlon.reshape(-1), xi.reshape(-1), eta.reshape(-1)
        for i in range(0, xi.size, CHUNK):
            fl[i : i + CHUNK], fd[i : i + CHUNK] = inverse(fx[i : i + CHUNK], fe[i : i + CHUNK], e, beta)
        return lat, dlon
    xip, etap = np.empty(xi.shape), np.empty(xi.shape)
    xi_f, eta_f, sin2xi, cos2xi, sinh2eta, cosh2eta = (
        a.reshape(-1) for a in (xi, eta, np.sin(2 * xi), np.cos(2 * xi), np.sinh(2 * eta), np.cosh(2 * eta))
    )
    _series_inverse(xi_f, eta_f, sin2xi, cos2xi, sinh2eta, cosh2eta, beta, xip.reshape(-1), etap.reshape(-1))
    sinh_etap, cos_xip = np.sinh(etap), np.cos(xip)
    taup = np.sin(xip) / np.sqrt(sinh_etap * sinh_etap + cos_xip * cos_xip)
    return np.arctan(_geodetic_tan(taup, e)), np.arctan2(sinh_etap, cos_xip)
