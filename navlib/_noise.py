"""Unchecked cores of navlib's sensor noise model: the Allan deviation, its theory and fit (:mod:`navlib.analysis`)
and Gauss-Markov sequences (:mod:`navlib.sensors`).

The checked public functions live in :mod:`navlib.analysis` and :mod:`navlib.sensors`; each checks its arguments, then
calls its core here. A function of another module that has already checked its record (e.g.
:func:`navlib.calibration.characterise`) calls the core directly, so that nothing is checked twice on one call.
Inputs are float64 arrays and floats within their ranges: sample intervals and averaging times (s) > 0, noise terms
>= 0, correlation times > 0.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numba import njit

from ._typing import Array

GM_ALLAN_PEAK, GM_ALLAN_PEAK_TAU = 0.6173642831444414, 1.8926178039336263
# Peak Allan deviation of a unit-variance Gauss-Markov process and the tau of the peak in correlation times
# (navlib.analysis documents them).
ALLAN_EVIDENCE = 2.0
# The misses, in standard errors, within which a model fits an Allan-deviation curve (navlib.analysis documents it).


def gm_allan_var_unit(u):
    """Allan variance of a unit-variance Gauss-Markov process at tau = u T_c."""
    u = np.asarray(u, dtype=float)
    small = u < 1e-3
    us = np.where(small, 1.0, u)
    big = (2 / us) * (1 - (3 - 4 * np.exp(-us) + np.exp(-2 * us)) / (2 * us))
    return np.where(small, 2 * u / 3 - u * u / 2, big)  # series avoids cancellation


def cluster_lengths(n: int, dt: float, taus: Array | None = None) -> Array:
    """Cluster lengths (samples, as floats) of the averaging times ``taus`` (s) rounded to whole multiples of ``dt``;
    default about 10 per decade from 1 to a third of the ``n`` samples."""
    if taus is None:
        return np.unique(np.round(np.logspace(0, np.log10(n // 3), 10 * max(1, int(np.log10(n // 3)) + 1))))
    return np.unique(np.round(taus / dt))


def deviation(x: Array, dt: float, m: Array) -> tuple[Array, Array]:
    """:func:`navlib.analysis.allan_deviation` of a checked series ``x`` ((N,) or (..., N, k), N >= 9) at cluster
    lengths ``m`` (:func:`cluster_lengths`, within 1 to (N - 1) // 2)."""
    one_series = x.ndim == 1
    if one_series:
        x = x[:, None]
    n = x.shape[-2]
    m = m.astype(np.int64)
    theta = np.zeros(x.shape[:-2] + (n + 1, x.shape[-1]))  # the integrated series, built in place: one record-sized array
    np.cumsum(x, axis=-2, out=theta[..., 1:, :])
    theta[..., 1:, :] *= dt
    mean_sq = _mean_square_second_difference(theta.reshape(-1, n + 1, x.shape[-1]), m)
    tau = m * dt
    out = np.sqrt(mean_sq / (2 * tau * tau)[:, None]).reshape(x.shape[:-2] + (m.size, x.shape[-1]))
    return tau, (out[:, 0] if one_series else out)


@njit(cache=True)
def _mean_square_second_difference(theta, m):
    """Mean over ``r`` of ``(theta[r + 2m] - 2 theta[r + m] + theta[r])**2`` for each ``m``: shape (B, M, k).

    One pass per averaging time and no temporaries (numpy needs four record-sized arrays per ``m``); the
    sum runs over ``r`` in order, as numpy's reduction over a non-contiguous axis does. Vector series
    (k = 3) take two averaging times per pass with the sums in registers (fewer passes over the record, same sums).
    """
    n_b, length, k = theta.shape
    out = np.empty((n_b, m.size, k))
    for b in range(n_b):
        series = theta[b]
        i = 0
        while i < m.size:
            if k == 3 and i + 1 < m.size:
                _two_taus_xyz(series, m[i], m[i + 1], out[b, i], out[b, i + 1])
                i += 2
                continue
            count = length - 2 * m[i]
            for j in range(k):
                acc = 0.0
                for r in range(count):
                    acc += _second_difference_sq(series, r, m[i], j)
                out[b, i, j] = acc / count
            i += 1
    return out


@njit(cache=True, inline="always")
def _two_taus_xyz(theta, ma, mb, out_a, out_b):
    """The sums of :func:`_mean_square_second_difference` for ``ma < mb`` on three axes in one pass."""
    length = theta.shape[0]
    ca, cb = length - 2 * ma, length - 2 * mb
    ax = ay = az = bx = by = bz = 0.0
    for r in range(cb):
        ax += _second_difference_sq(theta, r, ma, 0)
        ay += _second_difference_sq(theta, r, ma, 1)
        az += _second_difference_sq(theta, r, ma, 2)
        bx += _second_difference_sq(theta, r, mb, 0)
        by += _second_difference_sq(theta, r, mb, 1)
        bz += _second_difference_sq(theta, r, mb, 2)
    for r in range(cb, ca):
        ax += _second_difference_sq(theta, r, ma, 0)
        ay += _second_difference_sq(theta, r, ma, 1)
        az += _second_difference_sq(theta, r, ma, 2)
    out_a[0], out_a[1], out_a[2] = ax / ca, ay / ca, az / ca
    out_b[0], out_b[1], out_b[2] = bx / cb, by / cb, bz / cb


@njit(cache=True, inline="always")
def _second_difference_sq(theta, r, m, j):
    d = theta[r + 2 * m, j] - 2 * theta[r + m, j] + theta[r, j]
    return d * d


def theory(taus, white, bias_instability, correlation_time, rate_random_walk):
    """:func:`navlib.analysis.allan_deviation_theory` of checked arguments (the model :func:`fit` evaluates)."""
    sigma_gm = bias_instability / GM_ALLAN_PEAK
    var = white**2 / taus + sigma_gm**2 * gm_allan_var_unit(taus / correlation_time) + rate_random_walk**2 * taus / 3
    return np.sqrt(var)


def fit(taus: np.ndarray, adev: np.ndarray, n_samples: int, dt: float, rate_random_walk: bool) -> dict[str, Any]:
    """:func:`navlib.analysis.fit_allan` of checked arguments."""
    models = [(gm, rrw) for gm in (False, True) for rrw in ((False, True) if rate_random_walk else (False,))]
    fits = {model: _fit_terms(taus, adev, n_samples, dt, *model) for model in models}
    full = fits[models[-1]]
    peak = np.argmin(np.abs(np.log(taus / (GM_ALLAN_PEAK_TAU * full[2]))))  # where B shows
    at = np.union1d([peak], np.flatnonzero(taus >= taus[-1] / 10) if rate_random_walk else [peak])  # and K
    sigmas = np.sqrt(2 * _edf_random_walk(n_samples + 1.0, taus[at] / dt))  # standard errors of log adev
    from scipy.stats import norm  # noqa: PLC0415 -- imported on first use (see GM_ALLAN_PEAK)

    def miss(model):  # the largest miss of the fit, in standard errors of the measured deviation, ...
        largest = np.max(np.abs(np.log(adev[at] / theory(taus[at], *fits[model]))) * sigmas)
        # ... as the miss of one comparison that is as improbable (Sidak: the largest of at.size misses exceeds z
        # with probability 1 - (1 - 2 Phi(-z))^at.size)
        return float(norm.isf(-np.expm1(at.size * np.log1p(-2 * norm.sf(largest))) / 2))

    def cost(model):  # the weighted least-squares cost over all averaging times
        return float(np.sum((_fit_weights(taus, n_samples, dt) * np.log(adev / theory(taus, *fits[model]))) ** 2))

    adequate = [model for model in models if miss(model) <= ALLAN_EVIDENCE] or models[-1:]
    chosen = min(adequate, key=lambda model: (2 * model[0] + model[1], cost(model)))  # the fewest parameters
    evidence = tuple(min(miss(m) for m in models if not m[term]) if rate_random_walk or term == 0 else -np.inf for term in (0, 1))
    p = fits[chosen]
    return {
        "white": p[0],
        "bias_instability": p[1],
        "correlation_time": p[2] if chosen[0] else full[2],
        "rate_random_walk": p[3],
        "evidence": evidence,
        "sensitivity": _log_sensitivity(taus, p, n_samples, dt),
        "adequate": np.array([fits[model] for model in adequate]),
    }


def _log_sensitivity(taus: np.ndarray, p: np.ndarray, n_samples: int, dt: float) -> np.ndarray:
    """(4, M): the first-order change of the weighted fit's log N, log B, log T_c and log K per change of the
    log-deviations, at the fitted parameters ``p`` (rows of absent terms 0): ``pinv(W J) W`` with ``J`` the
    derivatives of the model's log-deviation by the log-parameters (central differences)."""
    free = np.array([p[0] > 0, p[1] > 0, p[1] > 0, p[3] > 0])
    step = 1e-6

    def log_model(q):
        return np.log(theory(taus, q[0], q[1], q[2], q[3]))

    J = np.stack([(log_model(p * np.exp(step * e)) - log_model(p * np.exp(-step * e))) / (2 * step) for e in np.eye(4)[free]], -1)
    w = _fit_weights(taus, n_samples, dt)
    out = np.zeros((4, taus.size))
    out[free] = np.linalg.pinv(w[:, None] * J) * w
    return out


def _edf_random_walk(big_n: float, m: np.ndarray) -> np.ndarray:
    """Equivalent degrees of freedom of the overlapping Allan variance for random-walk noise (Riley 2008, Table 5;
    ``big_n`` = samples + 1): the smallest of the noise types, so the widest standard error."""
    if big_n <= 3:  # the formula needs more than two samples; one degree of freedom is all two give
        return np.ones_like(m, dtype=float)
    return (big_n - 2) * ((big_n - 1) ** 2 - 3 * m * (big_n - 1) + 4 * m * m) / (m * (big_n - 3) ** 2)


def _fit_weights(taus: np.ndarray, n_samples: int, dt: float) -> np.ndarray:
    """:func:`fit_allan`'s weights of the log-deviations: the square root of the number of clusters, at least 1."""
    return np.sqrt(np.maximum(n_samples * dt / taus, 1.0))


def _fit_terms(taus: np.ndarray, adev: np.ndarray, n_samples: int, dt: float, gm: bool, rrw: bool) -> np.ndarray:
    """Weighted least squares of white noise with (``gm``) a Gauss-Markov bias and (``rrw``) rate random walk:
    parameters ``[N, B, T_c, K]`` (absent terms 0)."""
    from scipy.optimize import least_squares  # noqa: PLC0415 -- imported on first use (see GM_ALLAN_PEAK)

    w = _fit_weights(taus, n_samples, dt)
    i_min = int(np.argmin(adev))
    free = np.array([True, gm, gm, rrw])
    p0 = np.array([adev[0] * np.sqrt(taus[0]), adev[i_min], taus[i_min] / GM_ALLAN_PEAK_TAU, adev[-1] / np.sqrt(taus[-1])])
    lb = np.array([0.0, 0.0, taus[0] / 10, 0.0])

    def full(q):
        p = np.array([0.0, 0.0, p0[2], 0.0])  # without the bias term its correlation time is moot
        p[free] = q
        return p

    def resid(q):
        p = full(q)
        return w * (np.log(theory(taus, p[0], p[1], p[2], p[3])) - np.log(adev))

    sol = least_squares(resid, p0[free], bounds=(lb[free], np.inf), x_scale=np.abs(p0[free]) + 1e-300)
    return full(sol.x)


def gauss_markov(shape: tuple[int, ...], dt: float, sigma: float, tc: float, rng: np.random.Generator) -> Array:
    """:func:`navlib.sensors.gauss_markov` of checked arguments."""
    x0 = sigma * rng.standard_normal(shape[:-2] + (1, shape[-1]))
    return gauss_markov_from(x0, shape, dt, sigma, tc, rng)


def gauss_markov_from(
    x0: np.ndarray, shape: tuple[int, ...], dt: float, sigma: float, tc: float, rng: np.random.Generator
) -> Array:
    """Sequences of ``shape`` whose sample before the first is ``x0`` (shape[:-2] + (1, k)), driven by ``rng``."""
    phi = np.exp(-dt / tc)
    y = rng.standard_normal(out=np.empty(shape))  # the driving noise, filtered in place below
    y *= sigma * np.sqrt(1 - phi * phi)
    _ar1_in_place(y.reshape(-1, shape[-2], shape[-1]), phi, (phi * x0).reshape(-1, shape[-1]))
    return y


@njit(cache=True)
def _ar1_in_place(y, phi, y_before):
    """``y[:, k] += phi * y[:, k-1]`` along axis 1, with ``phi * y[:, -1] = y_before``: a first-order
    recursive filter (scipy's ``lfilter([1], [1, -phi], y, axis=1, zi=y_before)``, same arithmetic) without
    a second array of the size of ``y`` (gigabytes for a Monte Carlo batch)."""
    for b in range(y.shape[0]):
        for j in range(y.shape[2]):
            y[b, 0, j] += y_before[b, j]
            for k in range(1, y.shape[1]):
                y[b, k, j] += phi * y[b, k - 1, j]
