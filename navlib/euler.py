"""Euler-angle kinematics: the attitude matrix, Euler rates and their integration.

In navlib's ``hpr`` convention (:mod:`navlib`): ``C_bn = rot(z, -heading) rot(x, pitch) rot(y, roll)``.
:func:`euler_rates` gives ``[heading', pitch', roll']`` of a body turning at ``w_nb_b`` (Wu et al. 2014,
Eq. (2), in this convention); it divides by cos(pitch), so |pitch| must stay below :data:`PITCH_LIMIT`.
:func:`integrate_euler` integrates gyro samples (RK4 above a step angle, the midpoint rule below) with an
optional bias schedule and the navigation-frame rate ``w_in_n``; it fills dropouts up to ``max_gap``, and
:func:`navlib.robust.fault_report` counts the filled (NaN) and saturated samples.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from . import _kernels
from ._typing import Angles, Array, ArrayLike, Interval, Vec3, Vec3Series
from ._validate import NonNegative, as_array, boundary, broadcast_to, kernel_array, sample_intervals, small_turns, text
from .imu import ImuSamples, unpack

__all__ = ["PITCH_LIMIT", "check_pitch", "euler_rates", "integrate_euler"]

PITCH_LIMIT = np.deg2rad(89.0)
"""Largest |pitch| (rad) accepted where the Euler rates divide by cos(pitch)."""
_RK4_ANGLE2 = 1e-6  # squared step angle (rad^2) above which integrate_euler uses RK4


def _hpr(hpr: ArrayLike, name: str = "hpr") -> Array:
    hpr = as_array(hpr, name, tail=(3,), nonempty=True)
    check_pitch(hpr[..., 1], f"{name}[..., 1] (pitch)")
    return hpr


def check_pitch(pitch: ArrayLike, name: str = "pitch") -> None:
    """Raise ``ValueError`` naming ``name`` if any |pitch| exceeds :data:`PITCH_LIMIT` (Euler rates are singular at 90 deg).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import euler
    >>> euler.check_pitch(np.deg2rad(80.0))                          # fine: returns None
    >>> euler.check_pitch(np.deg2rad(90.0), name="hpr0[1]")
    Traceback (most recent call last):
        ...
    ValueError: hpr0[1]: expected |pitch| <= 89 deg; the Euler rates are singular at +-90 deg (got max ...
    """
    pitch = as_array(pitch, text(name, "name", empty=False), nonempty=True)
    if np.any(np.abs(pitch) > PITCH_LIMIT):
        raise ValueError(
            f"{name}: expected |pitch| <= {np.rad2deg(PITCH_LIMIT):g} deg; the Euler rates are singular "
            f"at +-90 deg (got max |pitch| {np.rad2deg(np.nanmax(np.abs(pitch))):.3f} deg)"
        )


def euler_rates(hpr: Angles, w_nb_b: Vec3) -> Array:
    """Time derivative (Wu et al. 2014 Eq. 2) of ``[heading, pitch, roll]`` from the body rate.

    Parameters
    ----------
    hpr : array_like, shape (..., 3)
        ``[heading, pitch, roll]`` (rad); |pitch| <= 89 deg.
    w_nb_b : array_like, shape (..., 3)
        Body rate relative to the navigation frame (rad/s).

    Returns
    -------
    hpr_dot : ndarray, shape (..., 3)
        ``[heading', pitch', roll']`` (rad/s).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import euler
    >>> np.round(euler.euler_rates([0.0, 0.0, 0.0], [0.0, 0.0, 0.1]), 6)   # level, turning left: heading decreases
    array([-0.1,  0. ,  0. ])
    """
    hpr = _hpr(hpr)
    w = as_array(w_nb_b, "w_nb_b", tail=(3,))
    _, p, r = np.moveaxis(hpr, -1, 0)
    wx, wy, wz = np.moveaxis(w, -1, 0)
    heading_dot = (np.sin(r) * wx - np.cos(r) * wz) / np.cos(p)
    pitch_dot = np.cos(r) * wx + np.sin(r) * wz
    roll_dot = wy + np.sin(p) * heading_dot
    return np.stack(np.broadcast_arrays(heading_dot, pitch_dot, roll_dot), -1)


@njit(cache=True, inline="always")
def _hpr_dot(h, p, r, wx, wy, wz, nE, nN, nU):
    """Euler rates with the navigation-frame rate removed: w_nb_b = w_ib_b - C_nb w_in_n."""
    ch, sh, cp, sp, cr, sr = np.cos(h), np.sin(h), np.cos(p), np.sin(p), np.cos(r), np.sin(r)
    wx -= (cr * ch + sr * sp * sh) * nE + (-cr * sh + sr * sp * ch) * nN - sr * cp * nU
    wy -= cp * sh * nE + cp * ch * nN + sp * nU
    wz -= (sr * ch - cr * sp * sh) * nE + (-sr * sh - cr * sp * ch) * nN + cr * cp * nU
    hd = (sr * wx - cr * wz) / cp
    return hd, cr * wx + sr * wz, wy + sp * hd


@njit(cache=True)
def _euler_kernel(hpr0, w, dts, w_in, bias, bias_from, pitch_limit, max_gap):
    T, N = w.shape[0], w.shape[1]
    K = bias_from.shape[0]
    out = np.empty((T, N + 1, 3))
    singular = False
    gap_too_long = False
    nE, nN, nU = w_in[0], w_in[1], w_in[2]
    for t in range(T):
        h, p, r = hpr0[t, 0], hpr0[t, 1], hpr0[t, 2]
        out[t, 0, 0], out[t, 0, 1], out[t, 0, 2] = _kernels.wrap_2pi(h), p, _kernels.wrap_pi(r)
        k = -1
        bx = by = bz = 0.0
        lx = ly = lz = 0.0  # last valid gyro sample (zero before the first)
        li = -1  # its index
        nj = -1  # next valid sample after a dropout (-1: none found yet / none left)
        gap = 0.0
        for i in range(N):
            dt = dts[i]
            while k + 1 < K and bias_from[k + 1] <= i:  # newest estimate available at sample i
                k += 1
                if np.isfinite(bias[t, k, 0]):
                    bx, by, bz = bias[t, k, 0], bias[t, k, 1], bias[t, k, 2]
            sx, sy, sz = w[t, i, 0], w[t, i, 1], w[t, i, 2]
            if np.isfinite(sx) and np.isfinite(sy) and np.isfinite(sz):
                lx, ly, lz = sx, sy, sz
                li = i
                gap = 0.0
            else:  # dropout: interpolate between valid neighbours
                if nj <= i:
                    nj = i + 1
                    while nj < N and not (np.isfinite(w[t, nj, 0]) and np.isfinite(w[t, nj, 1]) and np.isfinite(w[t, nj, 2])):
                        nj += 1
                if nj >= N:  # trailing dropouts: hold the last valid sample
                    sx, sy, sz = lx, ly, lz
                elif li < 0:  # leading dropouts: the first valid sample
                    sx, sy, sz = w[t, nj, 0], w[t, nj, 1], w[t, nj, 2]
                else:
                    c = (i - li) / (nj - li)
                    sx = lx + c * (w[t, nj, 0] - lx)
                    sy = ly + c * (w[t, nj, 1] - ly)
                    sz = lz + c * (w[t, nj, 2] - lz)
                gap += dt
                if gap > max_gap:
                    gap_too_long = True
            wx, wy, wz = sx - bx, sy - by, sz - bz
            if (wx * wx + wy * wy + wz * wz) * dt * dt > _RK4_ANGLE2:
                # classic RK4 with the sample's rate held over [t_i, t_i + dt]
                k1h, k1p, k1r = _hpr_dot(h, p, r, wx, wy, wz, nE, nN, nU)
                k2h, k2p, k2r = _hpr_dot(h + dt / 2 * k1h, p + dt / 2 * k1p, r + dt / 2 * k1r, wx, wy, wz, nE, nN, nU)
                k3h, k3p, k3r = _hpr_dot(h + dt / 2 * k2h, p + dt / 2 * k2p, r + dt / 2 * k2r, wx, wy, wz, nE, nN, nU)
                k4h, k4p, k4r = _hpr_dot(h + dt * k3h, p + dt * k3p, r + dt * k3r, wx, wy, wz, nE, nN, nU)
                h += dt / 6 * (k1h + 2 * k2h + 2 * k3h + k4h)
                p += dt / 6 * (k1p + 2 * k2p + 2 * k3p + k4p)
                r += dt / 6 * (k1r + 2 * k2r + 2 * k3r + k4r)
            else:
                # small step (a still IMU): the midpoint rule, local error ~ (|w| dt)^3 < 1e-9 rad
                k1h, k1p, k1r = _hpr_dot(h, p, r, wx, wy, wz, nE, nN, nU)
                k2h, k2p, k2r = _hpr_dot(h + dt / 2 * k1h, p + dt / 2 * k1p, r + dt / 2 * k1r, wx, wy, wz, nE, nN, nU)
                h += dt * k2h
                p += dt * k2p
                r += dt * k2r
            if abs(p) > pitch_limit:
                singular = True
            out[t, i + 1, 0], out[t, i + 1, 1], out[t, i + 1, 2] = _kernels.wrap_2pi(h), p, _kernels.wrap_pi(r)
    return out, singular, gap_too_long


@boundary
def integrate_euler(
    hpr0: Angles,
    w_ib_b: Vec3Series | ImuSamples,
    dt: Interval | None = None,
    w_in_n: Vec3 | None = None,
    bias_b: ArrayLike | None = None,
    bias_from: ArrayLike | None = None,
    *,
    max_gap: NonNegative = 0.0,
) -> Array:
    """Integrate Eq. (2) from gyro samples, optionally bias-compensated.

    Each sample is the mean rate over ``[t_k, t_k + dt_k]``; the Euler-angle
    ODE is advanced over the interval with that rate held, by classic RK4
    when the step angle ``|w| dt`` exceeds 1e-3 rad (rotations) and by the
    midpoint rule otherwise (still IMU; local error below 1e-9 rad).

    Faults: NaN samples (dropouts) raise ValueError unless ``max_gap > 0``;
    then each is replaced by linear interpolation between the neighbouring
    valid samples (to first order the attitude error is the integral of the
    interpolation error, at most ``sum |w_interp - w_true| dt`` over the filled
    samples) and a run of dropouts longer than ``max_gap`` seconds raises
    ValueError (the rotation over it is unknown). Samples at the rails of the
    gyro range cannot be corrected: the attitude after them is unreliable.
    ``robust.fault_report(w_ib_b, "gyro", full_scale=..., flags=True)``
    counts and flags the filled (``"nan"``) and saturated samples. Irregular
    sampling: pass per-sample intervals ``dt`` (``timing.intervals`` after
    ``timing.sanitize``).

    Parameters
    ----------
    hpr0 : array_like, shape (3,) or (..., 3)
        Initial ``[heading, pitch, roll]`` (rad).
    w_ib_b : array_like, shape (..., N, 3), or ImuSamples
        Gyro samples (rad/s); NaN only with ``max_gap > 0``. An
        :class:`navlib.imu.ImuSamples` here supplies ``dt`` (its limits are not used here).
    dt : float or array_like, shape (N,)
        Sample interval (s), or the interval after each sample; required with arrays.
    w_in_n : array_like, shape (3,), optional
        Rate of the navigation frame (rad/s), e.g. ``earth.earth_rate_n(lat)``
        for a static host (erratum E001-06); default zero, as in the paper.
    bias_b : array_like, shape (..., 3) or (..., K, 3), optional
        Bias estimates to subtract (rad/s). A (..., 3) array is constant; a
        (..., K, 3) array holds successive estimates, estimate k applying from
        sample ``bias_from[k]`` on (zero before the first; NaN entries, e.g.
        "not yet observable", keep the previous estimate).
    bias_from : array_like of int, shape (K,), optional
        Sample index from which each estimate applies; required with K > 1.
    max_gap : float
        Longest run of dropouts (s) bridged by interpolation; default 0:
        NaN is not accepted.

    Returns
    -------
    hpr : ndarray, shape (..., N + 1, 3)
        Heading wrapped to [0, 2 pi), roll to (-pi, pi].

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import euler
    >>> w_ib_b = np.tile([0.0, 0.0, -np.deg2rad(9.0)], (100, 1))     # 9 deg/s clockwise for 1 s at 100 Hz
    >>> hpr = euler.integrate_euler([0.0, 0.0, 0.0], w_ib_b, 0.01)
    >>> hpr.shape, np.round(np.rad2deg(hpr[-1]), 6)                  # no Earth rate given: w_in_n = 0
    ((101, 3), array([9., 0., 0.]))
    """
    if isinstance(w_ib_b, ImuSamples):  # validated by the record
        w, _, dts, _, _ = unpack(w_ib_b, dt=dt)  # (NaN with max_gap = 0: refused by the gap check)
    else:
        w = as_array(w_ib_b, "w_ib_b", tail=(3,), min_ndim=1, allow_nan=max_gap > 0)
        dts = sample_intervals(dt, w.shape[-2])
    lead, n = w.shape[:-2], w.shape[-2]
    small_turns(w, dts)
    hpr0 = broadcast_to(_hpr(hpr0, "hpr0"), "hpr0", lead + (3,), of="the trials of w_ib_b").reshape(-1, 3)
    w_in = np.zeros(3) if w_in_n is None else as_array(w_in_n, "w_in_n", shape=(3,))
    bias, idx = _bias_schedule(bias_b, bias_from, lead)
    out, singular, gap_long = _euler_kernel(
        kernel_array(hpr0), kernel_array(w.reshape((-1, n, 3))), dts, w_in, bias, idx, PITCH_LIMIT, max_gap
    )
    if gap_long:
        raise ValueError(
            f"w_ib_b: a run of NaN samples (dropouts) is longer than max_gap = {max_gap:g} s; the rotation over it is unknown"
        )
    if singular:
        raise ValueError(
            f"w_ib_b: the integrated pitch passed +-{np.rad2deg(PITCH_LIMIT):g} deg, where Eq. (2) "
            "is singular; integrate this motion with quaternions (strapdown.integrate_attitude)"
        )
    return out.reshape(lead + (n + 1, 3))


def _bias_schedule(bias_b, bias_from, lead):
    n_lead = int(np.prod(lead, dtype=int))
    if bias_b is None:
        if bias_from is not None:
            raise ValueError("bias_from: given without bias_b")
        return np.zeros((n_lead, 1, 3)), np.zeros(1, dtype=np.int64)
    b = as_array(bias_b, "bias_b", tail=(3,), allow_nan=True)
    if bias_from is None:
        idx = np.zeros(1, dtype=np.int64)
        b = b[..., None, :]
    else:
        idx = np.asarray(bias_from)
        if idx.ndim != 1 or not np.issubdtype(idx.dtype, np.integer) or np.any(np.diff(idx) < 0) or np.any(idx < 0):
            raise ValueError("bias_from: expected a non-decreasing 1-D array of non-negative sample indices")
        if b.ndim < 2 or b.shape[-2] != idx.size:
            raise ValueError(f"bias_b: expected shape (..., {idx.size}, 3) to match bias_from, got {b.shape}")
    try:
        b = np.broadcast_to(b, lead + b.shape[-2:])
    except ValueError:
        raise ValueError(f"bias_b: expected leading axes broadcasting to {lead}, got {b.shape}") from None
    return kernel_array(b.reshape((n_lead,) + b.shape[-2:])), idx.astype(np.int64)
