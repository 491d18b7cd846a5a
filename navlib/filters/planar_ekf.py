"""Planar vehicle model, dead reckoning and the 5-state EKF on grid position, heading, speed and yaw rate.

The filter of Zhao Y., Nie X., Fang S., Wu H. (2023), "Research on inertial navigation/GPS robot
combined positioning based on Gaussian projection", *Machine Building & Automation* 52(1): 173–176,
doi:10.19344/j.cnki.issn1671-5276.2023.01.043 (paper 002, :mod:`navlib.papers.gauss_kruger_ekf`,
which projects GPS fixes and assembles its scenario); its equation numbers are quoted.

Frame and state
---------------
The state is ``X = [x, y, theta, v, omega]`` in the Gauss–Krüger grid of
:mod:`navlib.geodesy`: **x grid north, y grid east** (m), as in the paper,
``theta`` the heading measured from x toward y, i.e. **clockwise from grid
north** — navlib's heading convention, referenced to grid north instead of
true north — ``v`` the forward speed (m/s) and ``omega`` the yaw rate,
positive clockwise seen from above (rad/s; ``omega = -w_z`` of a right-front-up
gyro). An IMU heading (clockwise from true north) becomes a grid heading by
subtracting the grid convergence gamma (``geodesy.convergence``), which the
paper omits (erratum E002-09; -0.35° at Fuzhou, 0.66° at a 3° zone edge).

Equations
---------
Eq. (13), lost in the source and reconstructed as the
short-step unicycle model::

    f(X) = [x + v T cos(theta), y + v T sin(theta), theta + omega T, v, omega]

Eq. (16), its Jacobian ``Phi = df/dX``; Eq. (12) ``X_k = f(X_k-1) + Gamma w``
with ``Gamma = I5`` (not given); Eqs. (14)–(15) ``Z = H X + v`` with
``H = I5`` and ``Z = [x_GPS, y_GPS, theta_IMU, v_IMU, omega_IMU]`` (erratum E002-07:
the printed ``X_m`` is the measurement); the heading innovation is wrapped to
(-pi, pi]. Noise, Eqs. (17)–(18), per step::

    Q = diag(1, 1, 0.01, 0.0001, 0.0016)      R = diag(6.25, 6.25, 0.01, 0.0004, 0.0025)

in SI units (m², rad², m²/s², rad²/s²) in the paper (``gauss_kruger_ekf.Q_PAPER``, ``R_PAPER``);
:func:`filter_grid` has no default noise. ``theta_IMU`` must be an absolute heading and ``omega_IMU``
the vertical gyro rate.

The predict/update cycle is one compiled kernel (:func:`filter_grid`) that calls
:func:`navlib.kalman.update` (and a specialised, allocation-free Joseph update for H = I5 when every
component is present).

Faults (what the filters do, and which counter of :class:`EkfResult` says so)
-----------------------------------------------------------------------------
============================  ====================================================  =====================================
fault                         EKF                                                   counter
============================  ====================================================  =====================================
NaN sample / outage / gap     skip that component; nothing at all: predict          ``n_missing_channels``,
                              only (P grows, recovers at the next fix)              ``n_gps_missing``, ``n_predict_only``
outlier (spike, GPS jump)     with a finite ``gate``: gate each channel             ``rejected``, ``n_rejected_channels``,
                              (GPS 2 dof, heading, speed, yaw rate 1 dof) on        ``n_rejected`` (status ``REJECTED``)
                              its marginal NIS; fuse the channels that pass;
                              after ``reacquire`` rejections in a row inflate       ``reacquired``, ``n_reacquired_channels``
                              P by the squared innovation and fuse the next
                              sample ungated
yaw rate at the gyro rails    with ``full_scale_gyro``: a censored sample:          ``saturated``, ``n_saturated``
                              fuse the rail value while the prediction is
                              inside the rails, else skip; never gated
repeated / out-of-order t     ``ValueError`` (run ``timing.sanitize`` first,        ``timing.TimingReport``
                              which sorts, drops repeats and counts them)
irregular sampling            step ``T = t[k] - t[k-1]`` per epoch                  --
clock jump (``T > max_dt``,   nothing integrated over it: the state is held,        ``faults["clock", "jump"]``
default 10 median steps)      P grows by the process noise of the whole             (flags per epoch)
                              interval, ``Q T / T_median``; the epoch's
                              measurements then take over (see below)
stuck yaw rate (a gyro        skipped like a NaN sample, from the first             ``faults["yaw_rate", "stuck"]``
repeating one value over      sample of the run (``robust.stuck_samples``:          (flags per epoch)
``stuck_run`` samples)        noisy series only, rail values are saturated)
============================  ====================================================  =====================================

Why the EKF propagates over a clock jump with inflated uncertainty rather than restarting: Eq. (13) is a
first-order step (over 3600 s at 1 m/s it moves the robot 3.6 km in a straight line, which is what the EKF
did before it had the rule: gated, the next fixes were then rejected as outliers), so nothing is integrated
over the interval, but the state is not discarded either. Its covariance grows by the per-step ``Q`` for
every nominal step of the interval: the random walk the filter already assumes between epochs, e.g.
+7200 m^2 of position variance for a 3600 s jump at T = 0.5 s. Because every state is measured (H = I5),
the first update after the jump then puts each measured state at its measurement (the gain is
1 - R / (P + R), about 0.999), which is the re-initialisation from the next measurement in effect, while a
channel missing at that epoch keeps its last value with a grown, consistent variance (a hard reset would
need a made-up one) and the gates stay meaningful. A jump that was only a wrong timestamp (the vehicle
moved one step) costs the same: the measurements take over. The yaw rate is the filter's only gyro input,
checked for a stuck output as in the attitude filters; heading and speed come from upstream estimators.

:func:`dead_reckoning` holds the previous speed and yaw rate over NaN and
saturated samples (counted in ``held``); it has no redundancy to detect an
in-range outlier, and it integrates every interval as given (no clock-jump or
stuck check: it returns no fault report).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numba import njit

from .. import _kernels, kalman
from .._deprecate import renamed_keywords
from .._kernels import wrap_pi
from .._typing import Array, ArrayLike, Times
from .._validate import as_array, flag, integer, kernel_array, range_limit, same_shape, scalar, text, time_axis
from ..robust import FaultReport, stuck_run_samples, stuck_samples
from ..timing import jump_limit

__all__ = ["CHANNELS", "motion_model", "jacobian", "propagate", "dead_reckoning", "filter_grid", "EkfResult",
           "covariance"]

_HEADING = 2
_FAULT_SENSORS = ("gnss", "heading", "speed", "yaw_rate")        # CHANNELS in the FaultReport vocabulary
_ANGLE_MASK = np.array([False, False, True, False, False])


# --------------------------------------------------------------------------
# Motion model, Eqs. (13) and (16)
# --------------------------------------------------------------------------

@njit(cache=True)
def _f(X, T):
    out = X.copy()
    out[0] = X[0] + X[3] * T * np.cos(X[2])
    out[1] = X[1] + X[3] * T * np.sin(X[2])
    out[2] = X[2] + X[4] * T
    return out


@njit(cache=True)
def _phi(X, T):
    Phi = np.eye(5)
    s, c = np.sin(X[2]), np.cos(X[2])
    Phi[0, 2] = -X[3] * T * s
    Phi[0, 3] = T * c
    Phi[1, 2] = X[3] * T * c
    Phi[1, 3] = T * s
    Phi[2, 4] = T
    return Phi


def _state(X, name="X"):
    return as_array(X, name, tail=(5,))


def motion_model(X: ArrayLike, T: float) -> Array:
    """The motion model ``f(X)`` (Eq. 13) for states of shape (..., 5) and step ``T`` (s)."""
    X = _state(X)
    T = scalar(T, "T", positive=True)
    x, y, th, v, w = np.moveaxis(X, -1, 0)
    return np.stack([x + v * T * np.cos(th), y + v * T * np.sin(th), th + w * T, v, w], -1)


def jacobian(X: ArrayLike, T: float) -> Array:
    """Eq. (16): ``Phi = df/dX`` at states (..., 5); returns shape (..., 5, 5)."""
    X = _state(X)
    T = scalar(T, "T", positive=True)
    Phi = np.broadcast_to(np.eye(5), X.shape[:-1] + (5, 5)).copy()
    s, c = np.sin(X[..., 2]), np.cos(X[..., 2])
    Phi[..., 0, 2] = -X[..., 3] * T * s
    Phi[..., 0, 3] = T * c
    Phi[..., 1, 2] = X[..., 3] * T * c
    Phi[..., 1, 3] = T * s
    Phi[..., 2, 4] = T
    return Phi


# --------------------------------------------------------------------------
# Propagation
# --------------------------------------------------------------------------

@njit(cache=True)
def _propagate(x0, T, speed, yaw_rate):
    X = np.empty((speed.shape[0] + 1, 5))
    for i in range(5):                  # element by element: an array assignment compiles numba's shape messages
        X[0, i] = x0[i]
    X[0, 3], X[0, 4] = speed[0], yaw_rate[0]
    for k in range(speed.shape[0]):
        x = _f(X[k], T)
        for i in range(5):
            X[k + 1, i] = x[i]
        if k + 1 < speed.shape[0]:
            X[k + 1, 3], X[k + 1, 4] = speed[k + 1], yaw_rate[k + 1]
    return X


def propagate(x0: ArrayLike, T: float, n_steps: int | None = None, speed: ArrayLike | None = None,
              yaw_rate: ArrayLike | None = None) -> Array:
    """Noise-free states from Eq. (13): ``X_k+1 = f(X_k)``.

    Parameters
    ----------
    x0 : array_like, shape (5,)
        Initial state ``[x, y, theta, v, omega]`` (m, m, rad, m/s, rad/s).
    T : float
        Step (s).
    n_steps : int, optional
        Number of steps with constant v, omega (from ``x0``).
    speed, yaw_rate : array_like, shape (n,), optional
        Commanded v and omega for each step instead (overriding ``x0[3:]``).

    Returns
    -------
    X : ndarray, shape (n_steps + 1, 5)
    """
    x0 = as_array(x0, "x0", shape=(5,))
    T = scalar(T, "T", positive=True)
    if (speed is None) != (yaw_rate is None):
        raise ValueError("speed, yaw_rate: give both (the measured inputs) or neither (n_steps of constant motion)")
    if speed is None and yaw_rate is None:
        n_steps = integer(n_steps, "n_steps")
        speed, yaw_rate = np.full(n_steps, x0[3]), np.full(n_steps, x0[4])
    else:
        speed = as_array(speed, "speed", shape=(None,), min_ndim=1)
        yaw_rate = same_shape(as_array(yaw_rate, "yaw_rate"), "yaw_rate", speed.shape, of="speed")
    return _propagate(x0, T, speed, yaw_rate)


# --------------------------------------------------------------------------
# Dead reckoning
# --------------------------------------------------------------------------

@njit(cache=True)
def _dead_reckon(t, speed, yaw_rate, x0, velocity_bias, full_scale_gyro):
    n = t.shape[0]
    out = np.empty((n, 3))
    out[0, 0], out[0, 1], out[0, 2] = x0[0], x0[1], x0[2]
    v, w = x0[3], x0[4]
    held = 0
    for k in range(1, n):
        if np.isfinite(speed[k - 1]) and np.isfinite(yaw_rate[k - 1]) and abs(yaw_rate[k - 1]) < full_scale_gyro:
            v, w = speed[k - 1], yaw_rate[k - 1]
        else:
            held += 1
        T = t[k] - t[k - 1]
        out[k, 0] = out[k - 1, 0] + (v * np.cos(out[k - 1, 2]) + velocity_bias[0]) * T
        out[k, 1] = out[k - 1, 1] + (v * np.sin(out[k - 1, 2]) + velocity_bias[1]) * T
        out[k, 2] = out[k - 1, 2] + w * T
    return out, held


@renamed_keywords(yaw_rate_range="full_scale_gyro")
def dead_reckoning(t: Times, speed: ArrayLike, yaw_rate: ArrayLike, x0: ArrayLike,
                   velocity_bias: ArrayLike = (0.0, 0.0), full_scale_gyro: float | None = None) -> tuple[Array, int]:
    """Integrate measured speed and yaw rate from ``x0`` with the motion model (no GPS).

    Dead reckoning has no redundancy, so it cannot detect an outlier inside
    the sensor's range: a speed spike moves the track by ``spike * T``, a
    yaw-rate spike turns it by ``spike * T`` for good. What it can tell is
    held and counted: NaN samples (dropouts, gaps) and, given the gyro range,
    yaw-rate samples at the rails. Times must be strictly increasing
    (``ValueError``; :func:`navlib.timing.sanitize` first); the step follows ``t``.

    Parameters
    ----------
    t : array_like, shape (N,)
        Strictly increasing times (s).
    speed, yaw_rate : array_like, shape (N,)
        Measured v (m/s) and omega (rad/s, clockwise positive); a NaN sample
        holds the previous value (counted in ``held``).
    x0 : array_like, shape (5,)
        Initial state.
    velocity_bias : array_like, shape (2,)
        A constant velocity error in the grid (north, east; m/s) added at every
        step: an error model for simulations (the frame-fixed drift of the
        paper's Table 1), zero for plain dead reckoning.
    full_scale_gyro : float, optional  (formerly ``yaw_rate_range``, which warns)
        Gyro full-scale range (rad/s): a sample with ``|omega| >= full_scale_gyro``
        is at the rails, not a measurement, and holds the previous speed and
        yaw rate (counted in ``held``). Default: no range.

    Returns
    -------
    pose : ndarray, shape (N, 3)
        ``[x, y, theta]``.
    held : int
        Steps that reused an earlier measurement (NaN or saturated sample at
        the start of the step; samples ``0 .. N-2`` drive the steps).
    """
    t = time_axis(t, "t")
    speed = same_shape(as_array(speed, "speed", allow_nan=True), "speed", t.shape, of="t")
    yaw_rate = same_shape(as_array(yaw_rate, "yaw_rate", allow_nan=True), "yaw_rate", t.shape, of="t")
    x0 = as_array(x0, "x0", shape=(5,))
    bias = as_array(velocity_bias, "velocity_bias", shape=(2,))
    fs = range_limit(full_scale_gyro, "full_scale_gyro")
    return _dead_reckon(t, speed, yaw_rate, x0, bias, fs)


# --------------------------------------------------------------------------
# EKF
# --------------------------------------------------------------------------

# A specialised update for the common epoch (H = I5, every component present): the same
# Joseph-form update as kalman.update, written with fixed-size loops and preallocated work
# arrays (about 5x faster than the general kernel, which handles dropouts and any H).

@njit(cache=True)
def _mul(A, B, out):
    """out = A @ B for 5x5 matrices (no allocation)."""
    for i in range(5):
        for j in range(5):
            acc = 0.0
            for m in range(5):
                acc += A[i, m] * B[m, j]
            out[i, j] = acc


@njit(cache=True)
def _mul_bt(A, B, out):
    """out = A @ B.T for 5x5 matrices."""
    for i in range(5):
        for j in range(5):
            acc = 0.0
            for m in range(5):
                acc += A[i, m] * B[j, m]
            out[i, j] = acc


@njit(cache=True)
def _cholesky_solve(S, B, L, out):
    """out = S^-1 B for symmetric positive definite S (5x5) and B (5 x m), via S = L L^T."""
    for j in range(5):
        d = S[j, j]
        for m in range(j):
            d -= L[j, m] * L[j, m]
        L[j, j] = np.sqrt(d)
        for i in range(j + 1, 5):
            acc = S[i, j]
            for m in range(j):
                acc -= L[i, m] * L[j, m]
            L[i, j] = acc / L[j, j]
    for c in range(B.shape[1]):
        for i in range(5):                  # forward: L w = b
            acc = B[i, c]
            for m in range(i):
                acc -= L[i, m] * out[m, c]
            out[i, c] = acc / L[i, i]
        for i in range(4, -1, -1):          # back: L^T u = w
            acc = out[i, c]
            for m in range(i + 1, 5):
                acc -= L[m, i] * out[m, c]
            out[i, c] = acc / L[i, i]


@njit(cache=True)
def _update_identity_h(x, P, z, R, gate, w):
    """Joseph-form update with H = I5 in place on x, P; returns (nis, status). w: work arrays (7, 5, 5)."""
    S, L, Kt, A, tmp, KR, y = w[0], w[1], w[2], w[3], w[4], w[5], w[6]
    for i in range(5):
        y[i, 0] = z[i] - x[i]
        for j in range(5):
            S[i, j] = 0.5 * (P[i, j] + P[j, i]) + R[i, j]
    y[_HEADING, 0] = wrap_pi(y[_HEADING, 0])
    _cholesky_solve(S, y[:, :1], L, tmp)                 # S^-1 y
    nis = 0.0
    for i in range(5):
        nis += y[i, 0] * tmp[i, 0]
    if nis > gate:
        return nis, kalman.REJECTED
    _cholesky_solve(S, P, L, Kt)                         # K^T = S^-1 P  (K = P S^-1)
    for i in range(5):
        for j in range(5):
            x[i] += Kt[j, i] * y[j, 0]
            A[i, j] = (1.0 if i == j else 0.0) - Kt[j, i]  # I - K
    _mul(A, P, tmp)
    _mul_bt(tmp, A, P)                                   # (I - K) P (I - K)^T
    for i in range(5):
        for j in range(5):
            acc = 0.0
            for m in range(5):
                acc += Kt[m, i] * R[m, j]
            KR[i, j] = acc                               # K R
    for i in range(5):
        for j in range(5):
            acc = 0.0
            for m in range(5):
                acc += KR[i, m] * Kt[m, j]
            tmp[i, j] = acc                              # K R K^T
    for i in range(5):
        for j in range(i, 5):
            v = 0.5 * (P[i, j] + P[j, i] + tmp[i, j] + tmp[j, i])
            P[i, j] = v
            P[j, i] = v
    return nis, kalman.ACCEPTED


@njit(cache=True)
def _gate_groups(x, P, z, R, gate, zu, rejected_row, streak, reacquire, reacquired_row):
    """Test each measurement group on its own marginal innovation (GPS: 2 dof, others 1 dof).

    Copies ``z`` into ``zu`` with the rejected groups set to NaN, marks them in
    ``rejected_row`` (4,) and returns how many groups were rejected. A group
    rejected on ``reacquire`` consecutive epochs with data is fused without the
    test at its next sample (marked in ``reacquired_row``), with the variance of
    its states inflated by the squared innovation so that the sample takes
    over: a lasting change is the state's error, not an outlier, and must not
    lock the channel out.
    """
    for i in range(5):
        zu[i] = z[i]
    n_rej = 0
    f0, f1 = np.isfinite(z[0]), np.isfinite(z[1])
    if f0 or f1:
        y0, y1 = z[0] - x[0], z[1] - x[1]
        s00, s11 = P[0, 0] + R[0, 0], P[1, 1] + R[1, 1]
        s01 = 0.5 * (P[0, 1] + P[1, 0]) + 0.5 * (R[0, 1] + R[1, 0])
        if f0 and f1:
            nis = (s11 * y0 * y0 - 2.0 * s01 * y0 * y1 + s00 * y1 * y1) / (s00 * s11 - s01 * s01)
        elif f0:
            nis = y0 * y0 / s00
        else:
            nis = y1 * y1 / s11
        if nis <= gate[0]:
            streak[0] = 0
        elif streak[0] >= reacquire:                       # inflate P so the sample takes over
            streak[0] = 0
            reacquired_row[0] = True
            if f0:
                P[0, 0] += y0 * y0
            if f1:
                P[1, 1] += y1 * y1
        else:
            zu[0] = np.nan
            zu[1] = np.nan
            rejected_row[0] = True
            streak[0] += 1
            n_rej += 1
    for g in range(1, 4):
        i = g + 1
        if np.isfinite(z[i]):
            y = z[i] - x[i]
            if i == _HEADING:
                y = wrap_pi(y)
            if y * y / (P[i, i] + R[i, i]) <= gate[g]:
                streak[g] = 0
            elif streak[g] >= reacquire:
                streak[g] = 0
                reacquired_row[g] = True
                P[i, i] += y * y
            else:
                zu[i] = np.nan
                rejected_row[g] = True
                streak[g] += 1
                n_rej += 1
    return n_rej


@njit(cache=True)
def _screen(x, P, z, R, gate, gate_on, w_range, zu, rejected_row, streak, reacquire, reacquired_row):
    """Gate the channels and handle a yaw rate at the rails; fills ``zu``. Returns (n_rejected, saturated)."""
    sat = np.isfinite(w_range) and abs(z[4]) >= w_range   # NaN: False
    n_rej = 0
    if not (gate_on or sat):
        return n_rej, sat
    for i in range(5):
        zu[i] = z[i]
    if sat:
        zu[4] = np.nan                                     # a rail sample is not gated ...
    if gate_on:                                            # gate each group, fuse the rest
        n_rej = _gate_groups(x, P, zu, R, gate, zu, rejected_row, streak, reacquire, reacquired_row)
    if sat:                                                # ... it only says |omega| >= range:
        sign = 1.0 if z[4] > 0 else -1.0
        if sign * x[4] < w_range:                          # pull a prediction inside the rails to the rail,
            zu[4] = sign * w_range                         # skip it when the prediction is beyond already
    return n_rej, sat


@njit(cache=True)
def _add_scaled(P, Q, s):
    """P += Q * s, element by element (an array expression compiles numba's shape-error message: seconds)."""
    for i in range(5):
        for j in range(5):
            P[i, j] += Q[i, j] * s                   # (x * 1.0 is x: the plain sum's bits)


@njit(cache=True)
def _store(X, Ps, k, x, P):
    """X[k], Ps[k] = x, P element by element."""
    for i in range(5):
        X[k, i] = x[i]
        for j in range(5):
            Ps[k, i, j] = P[i, j]


@njit(cache=True)
def _ekf_kernel(t, Z, x0, P0, Q, R, gate, fast, w_range, reacquire, jump, t_nominal):
    n = t.shape[0]
    X = np.empty((n, 5))
    Ps = np.empty((n, 5, 5))
    nis = np.full(n, np.nan)
    status = np.zeros(n, dtype=np.int64)
    rejected = np.zeros((n, 4), dtype=np.bool_)
    reacquired = np.zeros((n, 4), dtype=np.bool_)
    streak = np.zeros(4, dtype=np.int64)
    gate_on = False
    for g in range(4):
        if np.isfinite(gate[g]):
            gate_on = True
    sat_on = np.isfinite(w_range)
    robust = gate_on or sat_on
    H = np.eye(5)
    w = np.zeros((7, 5, 5))
    Phi_P = np.empty((5, 5))
    zu = np.empty(5)
    x, P = x0.copy(), P0.copy()
    _store(X, Ps, 0, x, P)
    for k in range(1, n):
        T = t[k] - t[k - 1]
        if jump[k]:                                        # clock jump: state held, Q for every nominal step
            _add_scaled(P, Q, T / t_nominal)
        else:
            Phi = _phi(x, T)                               # Eq. (16) at the previous estimate
            _mul(Phi, P, Phi_P)
            _mul_bt(Phi_P, Phi, P)
            _add_scaled(P, Q, 1.0)                         # P = Phi P Phi^T + Gamma Q Gamma^T, Gamma = I
            x = _f(x, T)                                   # Eq. (13)
        z = Z[k]
        n_rej, sat = 0, False
        if robust:                                         # gate and/or gyro range given
            n_rej, sat = _screen(x, P, z, R, gate, gate_on, w_range, zu, rejected[k], streak, reacquire, reacquired[k])
        if n_rej > 0 or sat:                               # gated or saturated: the general kernel on zu
            x, P, _, nis[k], status[k] = _kernels.kalman_update(x, P, zu, x, H, R, _ANGLE_MASK, np.inf)
            if n_rej > 0:
                status[k] = kalman.REJECTED
        elif fast and np.all(np.isfinite(z)):
            nis[k], status[k] = _update_identity_h(x, P, z, R, np.inf, w)
        else:                                              # dropouts: the general kernel
            x, P, _, nis[k], status[k] = _kernels.kalman_update(x, P, z, x, H, R, _ANGLE_MASK, np.inf)
        x[_HEADING] = np.mod(x[_HEADING], 2 * np.pi)
        _store(X, Ps, k, x, P)
    return X, Ps, nis, status, rejected, reacquired


CHANNELS = ("gps", "heading", "speed", "yaw_rate")
"""Measurement groups of the EKF, in the order of ``gate`` and of the per-channel counters."""


@dataclass
class EkfResult:
    """Output of :func:`filter_grid` (and of the paper pipeline :func:`navlib.papers.gauss_kruger_ekf.ekf`).

    Every epoch after the first is accounted for: each channel of it was fused,
    missing (NaN), gated out (``rejected``) or at the gyro rails
    (``saturated``); the counters below count these epochs.

    Attributes
    ----------
    t : ndarray, shape (N,)  (s)
    x : ndarray, shape (N, 5)
        Filtered states ``[x north, y east, heading (grid, rad), v, omega]``.
    P : ndarray, shape (N, 5, 5)
    nis : ndarray, shape (N,)
        Normalised innovation squared of the components fused (NaN where
        nothing was fused).
    status : ndarray of int, shape (N,)
        ``kalman.ACCEPTED``; ``NO_DATA`` (nothing measured: prediction only);
        ``REJECTED`` (at least one channel gated out; the others were fused).
    z : ndarray, shape (N, 5)
        Measurements in the grid frame as given to the filter (projected GPS,
        grid heading); saturated or gated samples are still shown here.
    n_predict_only, n_gps_missing, n_rejected : int
        Epochs (after the first) with no measurement at all, without a GPS
        fix, and with at least one channel rejected by the gate.
    zone : int or None
        Zone held by :func:`navlib.papers.gauss_kruger_ekf.ekf` (None from :func:`filter_grid`).
    origin_gk : ndarray, shape (2,)
        GK coordinates (north, east; m) subtracted from the projected fixes.
    rejected : ndarray of bool, shape (N, 4)
        Channel (``CHANNELS``: GPS position, heading, speed, yaw rate) gated out at each epoch.
    n_rejected_channels : ndarray of int, shape (4,)
        ``rejected.sum(axis=0)``: gated samples per channel.
    n_missing_channels : ndarray of int, shape (4,)
        Epochs after the first with the channel missing (NaN; GPS: either coordinate).
    reacquired : ndarray of bool, shape (N, 4)
        Channel fused without the gate after ``reacquire`` consecutive rejections.
    n_reacquired_channels : ndarray of int, shape (4,)
        ``reacquired.sum(axis=0)``.
    saturated : ndarray of bool, shape (N,)
        Yaw-rate samples at or beyond the gyro rails (``|omega| >= full_scale_gyro``),
        never fused at face value (see :func:`filter_grid`).
    n_saturated : int
        Saturated yaw-rate samples in epochs after the first (``saturated[1:].sum()``).
    faults : FaultReport
        The same counts in navlib's one fault vocabulary, sensors ``gnss``, ``heading``, ``speed``,
        ``yaw_rate`` (:data:`CHANNELS` order) and kinds ``nan``, ``outlier``, ``reacquired``,
        ``saturated``; flags per epoch for the last three. Only here: clock jumps
        ``("clock", "jump")`` and stuck yaw-rate samples ``("yaw_rate", "stuck")`` (epochs after
        the first), with flags per epoch.
    """
    t: np.ndarray
    x: np.ndarray
    P: np.ndarray
    nis: np.ndarray
    status: np.ndarray
    z: np.ndarray
    n_predict_only: int
    n_gps_missing: int
    n_rejected: int
    zone: int | None = None
    origin_gk: np.ndarray | None = None
    rejected: np.ndarray | None = None
    n_rejected_channels: np.ndarray | None = None
    n_missing_channels: np.ndarray | None = None
    reacquired: np.ndarray | None = None
    n_reacquired_channels: np.ndarray | None = None
    saturated: np.ndarray | None = None
    n_saturated: int = 0
    faults: FaultReport = field(default_factory=FaultReport)


def covariance(M: ArrayLike, name: str) -> Array:
    """A validated (5, 5) symmetric positive semi-definite matrix from itself or its diagonal (5,)."""
    M = as_array(M, text(name, "name", empty=False))
    if M.shape == (5,):
        M = np.diag(M)
    if M.shape != (5, 5) or not np.allclose(M, M.T) or np.any(np.linalg.eigvalsh(M) < 0):
        raise ValueError(f"{name}: expected a symmetric positive semi-definite (5, 5) matrix or a diagonal (5,)")
    return kernel_array(M)


def _gate(gate):
    g = as_array(gate, "gate", finite=False)
    if g.shape not in ((), (4,)) or np.any(np.isnan(g)) or not np.all(g > 0):
        raise ValueError(f"gate: expected a positive NIS threshold (inf for none) or 4 of them "
                         f"(gps, heading, speed, yaw_rate), got {gate!r}")
    return kernel_array(np.broadcast_to(g, (4,)), dtype=float)


@renamed_keywords(yaw_rate_range="full_scale_gyro")
def filter_grid(t: Times, z: ArrayLike, x0: ArrayLike, P0: ArrayLike | None = None, Q: ArrayLike | None = None,
                R: ArrayLike | None = None, gate: float | ArrayLike = np.inf, fast: bool = True,
                full_scale_gyro: float | None = None, reacquire: int = 3, max_dt: float | None = None,
                stuck_run: int | str | None = "auto") -> EkfResult:
    """The EKF on measurements already in the grid frame.

    Faults: a NaN component is missing and left out of the update (an epoch
    with nothing is prediction only); with a finite ``gate`` each channel
    whose innovation fails its own NIS test is left out and the others are
    fused; yaw-rate samples at the gyro rails are treated as censored (see
    ``full_scale_gyro``); a clock jump is not integrated (``max_dt``) and a
    stuck yaw rate is skipped (``stuck_run``). All are
    counted in the :class:`EkfResult`. Times must be strictly increasing
    (``ValueError`` otherwise: run :func:`navlib.timing.sanitize` first); the
    step ``T = t[k] - t[k-1]`` may vary from epoch to epoch (``Q`` stays per step).

    Parameters
    ----------
    t : array_like, shape (N,)
        Strictly increasing times (s); step ``T = t[k] - t[k-1]``.
    z : array_like, shape (N, 5)
        ``[x_GPS, y_GPS, theta, v, omega]`` per epoch; NaN components are
        missing (the row of ``t[0]`` is not used: ``x0`` holds there).
    x0 : array_like, shape (5,)
    P0 : array_like, shape (5, 5) or (5,), optional
        Initial covariance; default zeros (the paper's P(0)).
    Q, R : array_like, shape (5, 5) or (5,)
        Per-step process noise and measurement noise (required; e.g. the values of Zhao et al. 2023,
        ``navlib.papers.gauss_kruger_ekf.Q_PAPER`` and ``R_PAPER``).
    gate : float or array_like, shape (4,)
        NIS thresholds per channel (``CHANNELS``: GPS position, 2 dof; heading,
        speed, yaw rate, 1 dof each), each tested on its marginal innovation
        ``y_g^T S_gg^-1 y_g``; a scalar applies to all; ``inf``: never gate.
        E.g. ``[18.4, 15.1, 15.1, 15.1]`` (chi-square, 1e-4 false alarms).
        A manoeuvre the process noise ``Q`` does not allow for (the paper's Q:
        0.04 rad/s and 0.01 m/s per step) fails the test like an outlier; see
        ``reacquire``.
    fast : bool
        Use the specialised H = I5 update when every component is present
        (False: :func:`navlib.kalman.update` at every epoch; same result).
    full_scale_gyro : float, optional  (formerly ``yaw_rate_range``, which warns)
        Gyro full-scale range (rad/s): a yaw-rate sample with ``|omega| >=
        full_scale_gyro`` is at the rails and only says ``|omega| >= range``.
        It is never gated and never fused at face value: while the predicted
        omega is inside the rails the rail value ``±range`` is fused (the
        nearest rate the sample allows), once the prediction is beyond the
        rail the sample is skipped. Counted in ``saturated``, ``n_saturated``.
        Default: no range.
    reacquire : int
        A channel gated out on this many consecutive epochs (with data) is
        fused without the test at its next sample, its states' variance
        inflated by the squared innovation (the sample takes over), and the
        streak restarts (``reacquired``, ``n_reacquired_channels``): isolated outliers stay
        out, a lasting change of the truth (a real step in speed or yaw rate,
        a filter that has lost the heading) cannot lock the channel out.
    max_dt : float, optional
        Longest step integrated (s); a longer one is a clock jump (a time-stamp
        jump or a recording gap; ``faults["clock", "jump"]``): the state is not
        propagated over it and ``P`` grows by ``Q`` for every median step it
        spans (module docstring: why not a restart). Default None:
        ``timing.JUMP_FACTOR`` = 10 median steps, the rule of the attitude
        filters; inf: off.
    stuck_run : int, "auto" or None
        A yaw-rate sample repeating exactly over this many epochs or more is a
        stuck gyro (``robust.stuck_samples``: checked only when the series is
        noisy from the start; rail values are saturated): skipped like a NaN
        sample, counted in ``faults["yaw_rate", "stuck"]``. Default "auto":
        ``robust.STUCK_DURATION`` (0.1 s) of epochs, at least 5, as in the
        attitude filters; None: off.

    Returns
    -------
    EkfResult
    """
    t = time_axis(t, "t")
    z = as_array(z, "z", allow_nan=True, shape=(t.size, 5))
    x0 = as_array(x0, "x0", shape=(5,))
    P0 = np.zeros((5, 5)) if P0 is None else covariance(P0, "P0")
    for name, M in (("Q", Q), ("R", R)):
        if M is None:
            raise ValueError(f"{name}: required (the filter has no default noise; e.g. gauss_kruger_ekf.{name}_PAPER)")
    Q, R = covariance(Q, "Q"), covariance(R, "R")
    gate = _gate(gate)
    fs = range_limit(full_scale_gyro, "full_scale_gyro")
    with np.errstate(invalid="ignore"):
        saturated = np.abs(z[:, 4]) >= fs                   # NaN compares False
    reacquire = integer(reacquire, "reacquire")
    dts = np.diff(t)
    t_nominal = float(np.median(dts))
    jump = np.concatenate([[False], dts > jump_limit(dts, max_dt, "t")])
    stuck = stuck_samples(z[:, 4], stuck_run_samples(stuck_run, t_nominal), full_scale=full_scale_gyro,
                          name="z", axis=-1)
    z_used = z
    if stuck.any():                                         # stuck yaw rate: skipped like a NaN sample
        z_used = z.copy()
        z_used[stuck, 4] = np.nan
    X, P, nis, status, rejected, reacquired = _ekf_kernel(t, kernel_array(z_used), x0, P0, Q, R, gate,
                                                          flag(fast, "fast"), fs, reacquire, jump, t_nominal)
    later = z[1:]
    missing = np.stack([~np.all(np.isfinite(later[:, :2]), axis=1), np.isnan(later[:, 2]),
                        np.isnan(later[:, 3]), np.isnan(later[:, 4])], -1)
    return EkfResult(t, X, P, nis, status, z, int(np.sum(status[1:] == kalman.NO_DATA)),
                     int(missing[:, 0].sum()), int(np.sum(status == kalman.REJECTED)),
                     rejected=rejected, n_rejected_channels=rejected.sum(axis=0),
                     n_missing_channels=missing.sum(axis=0), reacquired=reacquired,
                     n_reacquired_channels=reacquired.sum(axis=0), saturated=saturated,
                     n_saturated=int(saturated[1:].sum()),
                     faults=_fault_report(missing, rejected, reacquired, saturated, stuck, jump))


def _fault_report(missing, rejected, reacquired, saturated, stuck, jump):
    counts, flags = {}, {}
    for i, sensor in enumerate(_FAULT_SENSORS):
        counts[sensor, "nan"] = int(missing[:, i].sum())
        for kind, mask in (("outlier", rejected[:, i]), ("reacquired", reacquired[:, i])):
            counts[sensor, kind], flags[sensor, kind] = int(mask.sum()), mask
    for key, mask in ((("yaw_rate", "saturated"), saturated), (("yaw_rate", "stuck"), stuck), (("clock", "jump"), jump)):
        counts[key], flags[key] = int(mask[1:].sum()), mask
    return FaultReport(counts, flags)
