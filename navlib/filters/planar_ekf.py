r"""Planar vehicle model, dead reckoning and the 5-state EKF on grid position, heading, speed and yaw rate.

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
short-step unicycle model:

.. math:: f(X) = \big[x + v T \cos\theta,\ y + v T \sin\theta,\ \theta + \omega T,\ v,\ \omega\big]

Eq. (16), its Jacobian ``Phi = df/dX``; Eq. (12) ``X_k = f(X_k-1) + Gamma w``
with ``Gamma = I5`` (not given); Eqs. (14)–(15) ``Z = H X + v`` with
``H = I5`` and ``Z = [x_GPS, y_GPS, theta_IMU, v_IMU, omega_IMU]`` (erratum E002-07:
the printed ``X_m`` is the measurement); the heading innovation is wrapped to
(-pi, pi]. Noise, Eqs. (17)–(18), per step:

.. math::

    Q &= \mathrm{diag}(1,\ 1,\ 0.01,\ 0.0001,\ 0.0016) \\
    R &= \mathrm{diag}(6.25,\ 6.25,\ 0.01,\ 0.0004,\ 0.0025)

in SI units (m², rad², m²/s², rad²/s²) in the paper (``gauss_kruger_ekf.Q_PAPER``, ``R_PAPER``);
:class:`EkfConfig` has no default noise. ``theta_IMU`` must be an absolute heading and ``omega_IMU``
the vertical gyro rate.

The predict/update cycle is one compiled kernel (:func:`filter_grid`) that calls
:func:`navlib.kalman.update` (and a specialised, allocation-free Joseph update for H = I5 when every
component is present).

Faults (what the filters do, and which key of ``EkfResult.faults`` says so)
---------------------------------------------------------------------------
All tests on the measurements run once, before the first epoch (:func:`filter_grid`); the kernel fuses
what they left. Keys are ``(sensor, kind)`` with the sensors ``gnss``, ``heading``, ``speed``,
``yaw_rate`` (:data:`CHANNELS` order) and ``clock``; every key has its per-epoch flags.

============================  ====================================================  =====================================
fault                         EKF                                                   key
============================  ====================================================  =====================================
NaN sample / outage / gap     skip that component; nothing at all: predict          ``(sensor, "nan")``;
                              only (P grows, recovers at the next fix)              ``EkfResult.prediction_only``
outlier (spike, GPS jump)     with a finite ``gate``: gate each channel             ``(sensor, "outlier")``
                              (GPS 2 dof, heading, speed, yaw rate 1 dof) on
                              its marginal NIS; fuse the channels that pass;
                              after ``reacquire`` rejections in a row inflate       ``(sensor, "reacquired")``
                              P by the squared innovation and fuse the next
                              sample ungated
yaw rate at the gyro rails    with ``full_scale_gyro``: a censored sample:          ``("yaw_rate", "saturated")``
                              fuse the rail value while the prediction is
                              inside the rails, else skip; never gated
repeated / out-of-order t     ``ValueError`` (run ``timing.sanitize`` first,        ``timing.TimingReport``
                              which sorts, drops repeats and counts them)
irregular sampling            step ``T = t[k] - t[k-1]`` per epoch                  --
clock jump (``T > max_dt``,   nothing integrated over it: the state is held,        ``("clock", "jump")``
default 10 median steps)      P grows by the process noise of the whole
                              interval, ``Q T / T_median``; the epoch's
                              measurements then take over (see below)
stuck yaw rate (a gyro        skipped like a NaN sample, from the first             ``("yaw_rate", "stuck")``
repeating one value over      sample of the run (``robust.stuck_samples``:
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
saturated samples (its :class:`~navlib.robust.FaultReport`); it has no redundancy to detect an
in-range outlier, and it integrates every interval as given (no clock-jump or
stuck check).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np
from numba import njit

from .. import _kernels, _planar, _robust, kalman
from .._kernels import wrap_pi
from .._planar import motion
from .._typing import Array, ArrayLike, Times
from .._validate import (
    Is,
    Positive,
    as_array,
    boundary,
    flag,
    instance,
    integer,
    kernel_array,
    same_shape,
    text,
    time_axis,
)
from ..imu import SensorLimits
from ..robust import FaultReport

__all__ = [
    "CHANNELS",
    "motion_model",
    "jacobian",
    "propagate",
    "dead_reckoning",
    "filter_grid",
    "EkfConfig",
    "EkfResult",
    "covariance",
]

_HEADING = 2
_FAULT_SENSORS = ("gnss", "heading", "speed", "yaw_rate")  # CHANNELS in the FaultReport vocabulary


# --------------------------------------------------------------------------
# Motion model, Eqs. (13) and (16)
# --------------------------------------------------------------------------


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


@boundary
def motion_model(X: ArrayLike, T: Positive) -> Array:
    """The motion model ``f(X)`` (Eq. 13) for states of shape (..., 5) and step ``T`` (s).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.filters import planar_ekf
    >>> np.round(planar_ekf.motion_model(np.array([0.0, 0.0, np.pi / 2, 2.0, 0.0]), 0.5), 6)   # heading east, 2 m/s for 0.5 s
    array([0.      , 1.      , 1.570796, 2.      , 0.      ])
    """
    X = as_array(X, "X", tail=(5,))
    x, y, th, v, w = np.moveaxis(X, -1, 0)
    return np.stack([x + v * T * np.cos(th), y + v * T * np.sin(th), th + w * T, v, w], -1)


@boundary
def jacobian(X: ArrayLike, T: Positive) -> Array:
    """Eq. (16): ``Phi = df/dX`` at states (..., 5); returns shape (..., 5, 5).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.filters import planar_ekf
    >>> np.round(planar_ekf.jacobian(np.array([0.0, 0.0, 0.0, 1.0, 0.0]), 1.0), 3) + 0.0
    array([[1., 0., 0., 1., 0.],
           [0., 1., 1., 0., 0.],
           [0., 0., 1., 0., 1.],
           [0., 0., 0., 1., 0.],
           [0., 0., 0., 0., 1.]])
    """
    X = as_array(X, "X", tail=(5,))
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


@boundary
def propagate(
    x0: ArrayLike, T: Positive, n_steps: int | None = None, speed: ArrayLike | None = None, yaw_rate: ArrayLike | None = None
) -> Array:
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

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.filters import planar_ekf
    >>> np.round(planar_ekf.propagate([0.0, 0.0, 0.0, 1.0, 0.0], 1.0, 3)[:, :2], 6)   # 3 steps of 1 s at 1 m/s
    array([[0., 0.],
           [1., 0.],
           [2., 0.],
           [3., 0.]])
    """
    x0 = as_array(x0, "x0", shape=(5,))
    if (speed is None) != (yaw_rate is None):
        raise ValueError("speed, yaw_rate: give both (the measured inputs) or neither (n_steps of constant motion)")
    if speed is None and yaw_rate is None:
        n_steps = integer(n_steps, "n_steps")
        speed, yaw_rate = np.full(n_steps, x0[3]), np.full(n_steps, x0[4])
    else:
        speed = as_array(speed, "speed", shape=(None,), min_ndim=1)
        yaw_rate = same_shape(as_array(yaw_rate, "yaw_rate"), "yaw_rate", speed.shape, of="speed")
    return _planar.propagate(x0, T, speed, yaw_rate)


# --------------------------------------------------------------------------
# Dead reckoning
# --------------------------------------------------------------------------


@njit(cache=True)
def _dead_reckon(t, speed, yaw_rate, usable, x0, velocity_bias, jump, t_nominal):
    n = t.shape[0]
    out = np.empty((n, 3))
    out[0, 0], out[0, 1], out[0, 2] = x0[0], x0[1], x0[2]
    v, w = x0[3], x0[4]
    for k in range(1, n):
        if usable[k - 1]:  # else hold the previous speed and yaw rate
            v, w = speed[k - 1], yaw_rate[k - 1]
        T = t_nominal if jump[k] else t[k] - t[k - 1]  # a clock jump: one typical step, not the jump
        out[k, 0] = out[k - 1, 0] + (v * np.cos(out[k - 1, 2]) + velocity_bias[0]) * T
        out[k, 1] = out[k - 1, 1] + (v * np.sin(out[k - 1, 2]) + velocity_bias[1]) * T
        out[k, 2] = out[k - 1, 2] + w * T
    return out


def dead_reckoning(
    t: Times,
    speed: ArrayLike,
    yaw_rate: ArrayLike,
    x0: ArrayLike,
    velocity_bias: ArrayLike = (0.0, 0.0),
    full_scale_gyro: float | None = None,
    max_dt: float | None = None,
) -> tuple[Array, FaultReport]:
    """Integrate measured speed and yaw rate from ``x0`` with the motion model (no GPS).

    Dead reckoning has no redundancy, so it cannot detect an outlier inside
    the sensor's range: a speed spike moves the track by ``spike * T``, a
    yaw-rate spike turns it by ``spike * T`` for good. What it can tell is
    held and reported: NaN samples (dropouts, gaps) and, given the gyro range,
    yaw-rate samples at the rails. Times must be strictly increasing
    (``ValueError``; :func:`navlib.timing.sanitize` first); the step follows ``t``. A clock jump (a step
    longer than ``max_dt``) is not integrated: it counts as one typical (median) step, so a time-stamp glitch
    between contiguous samples costs nothing and a gap in the data adds no motion that was not measured.

    Parameters
    ----------
    t : array_like, shape (N,)
        Strictly increasing times (s).
    speed, yaw_rate : array_like, shape (N,)
        Measured v (m/s) and omega (rad/s, clockwise positive); sample k drives the
        step from ``t[k]`` to ``t[k+1]``. A NaN sample holds the previous speed and yaw rate.
    x0 : array_like, shape (5,)
        Initial state.
    velocity_bias : array_like, shape (2,)
        A constant velocity error in the grid (north, east; m/s) added at every
        step: an error model for simulations (the frame-fixed drift of the
        paper's Table 1), zero for plain dead reckoning.
    full_scale_gyro : float, optional
        Gyro full-scale range (rad/s): a sample with ``|omega| >= full_scale_gyro``
        is at the rails, not a measurement, and holds the previous speed and
        yaw rate. Default: no range.
    max_dt : float, optional
        Longest step integrated (s); default :data:`navlib.imu.JUMP_FACTOR` median steps; ``inf``: off.

    Returns
    -------
    pose : ndarray, shape (N, 3)
        ``[x, y, theta]``.
    faults : FaultReport
        The held samples among those that drive a step (``0 .. N-2``): ``("speed", "nan")``,
        ``("yaw_rate", "nan")``, ``("yaw_rate", "saturated")``, and the epochs after a clock jump,
        ``("clock", "jump")``, with their flags (shape (N,)).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.filters import planar_ekf
    >>> t = np.arange(5.0)
    >>> x, found = planar_ekf.dead_reckoning(t, speed=np.ones(5), yaw_rate=np.zeros(5), x0=[0.0, 0.0, 0.0, 1.0, 0.0])
    >>> np.round(x[:, :2], 6)                                         # x (north), y (east): 1 m per second
    array([[0., 0.],
           [1., 0.],
           [2., 0.],
           [3., 0.],
           [4., 0.]])
    """
    t = time_axis(t, "t")
    speed = same_shape(as_array(speed, "speed", allow_nan=True), "speed", t.shape, of="t")
    yaw_rate = same_shape(as_array(yaw_rate, "yaw_rate", allow_nan=True), "yaw_rate", t.shape, of="t")
    x0 = as_array(x0, "x0", shape=(5,))
    bias = as_array(velocity_bias, "velocity_bias", shape=(2,))
    limits = SensorLimits(np.inf if full_scale_gyro is None else full_scale_gyro, max_dt=max_dt)  # checks both
    with np.errstate(invalid="ignore"):  # NaN compares False
        flags = {
            ("speed", "nan"): np.isnan(speed),
            ("yaw_rate", "nan"): np.isnan(yaw_rate),
            ("yaw_rate", "saturated"): np.abs(yaw_rate) >= limits.full_scale_gyro,
        }
    for held in flags.values():
        held[-1] = False  # the last sample drives no step
    usable = ~(flags["speed", "nan"] | flags["yaw_rate", "nan"] | flags["yaw_rate", "saturated"])
    dts = np.diff(t)
    t_nominal = float(np.median(dts))
    flags["clock", "jump"] = np.concatenate([[False], dts > limits.jump_limit(t_nominal)])
    pose = _dead_reckon(t, speed, yaw_rate, usable, x0, bias, flags["clock", "jump"], t_nominal)
    return pose, FaultReport({key: int(held.sum()) for key, held in flags.items()}, flags)


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
        for i in range(5):  # forward: L w = b
            acc = B[i, c]
            for m in range(i):
                acc -= L[i, m] * out[m, c]
            out[i, c] = acc / L[i, i]
        for i in range(4, -1, -1):  # back: L^T u = w
            acc = out[i, c]
            for m in range(i + 1, 5):
                acc -= L[m, i] * out[m, c]
            out[i, c] = acc / L[i, i]


@njit(cache=True)
def _update_identity_h(x, P, z, R, gate, w, y):
    """Joseph-form update with H = I5 in place on x, P; returns (nis, status). w: work arrays (6, 5, 5); y: the
    innovation's work column (5, 1), contiguous like P (one specialisation of _cholesky_solve, not two)."""
    S, L, Kt, A, tmp, KR = w[0], w[1], w[2], w[3], w[4], w[5]
    for i in range(5):
        y[i, 0] = z[i] - x[i]
        for j in range(5):
            S[i, j] = 0.5 * (P[i, j] + P[j, i]) + R[i, j]
    y[_HEADING, 0] = wrap_pi(y[_HEADING, 0])
    _cholesky_solve(S, y, L, tmp)  # S^-1 y
    nis = 0.0
    for i in range(5):
        nis += y[i, 0] * tmp[i, 0]
    if nis > gate:
        return nis, kalman.REJECTED
    _cholesky_solve(S, P, L, Kt)  # K^T = S^-1 P  (K = P S^-1)
    for i in range(5):
        for j in range(5):
            x[i] += Kt[j, i] * y[j, 0]
            A[i, j] = (1.0 if i == j else 0.0) - Kt[j, i]  # I - K
    _mul(A, P, tmp)
    _mul_bt(tmp, A, P)  # (I - K) P (I - K)^T
    for i in range(5):
        for j in range(5):
            acc = 0.0
            for m in range(5):
                acc += Kt[m, i] * R[m, j]
            KR[i, j] = acc  # K R
    for i in range(5):
        for j in range(5):
            acc = 0.0
            for m in range(5):
                acc += KR[i, m] * Kt[m, j]
            tmp[i, j] = acc  # K R K^T
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
        elif streak[0] >= reacquire:  # inflate P so the sample takes over
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
def _gate_and_censor(x, P, z, R, gate, gate_on, rail, zu, rejected_row, streak, reacquire, reacquired_row):
    """Gate the channels and fuse a yaw rate at the rails as the rail value ``rail`` (NaN: not at the rails);
    fills ``zu``. Returns the number of channels rejected."""
    at_rail = not np.isnan(rail)
    for i in range(5):
        zu[i] = z[i]
    if at_rail:
        zu[4] = np.nan  # a rail sample is not gated ...
    n_rej = 0
    if gate_on:  # gate each group, fuse the rest
        n_rej = _gate_groups(x, P, zu, R, gate, zu, rejected_row, streak, reacquire, reacquired_row)
    if at_rail and (x[4] < rail if rail > 0 else x[4] > rail):
        zu[4] = rail  # ... it only says |omega| >= range: pull a prediction
    return n_rej  # inside the rails to the rail, skip one beyond already


@njit(cache=True)
def _add_scaled(P, Q, s):
    """P += Q * s, element by element (an array expression compiles numba's shape-error message: seconds)."""
    for i in range(5):
        for j in range(5):
            P[i, j] += Q[i, j] * s  # (x * 1.0 is x: the plain sum's bits)


@njit(cache=True)
def _store(X, Ps, k, x, P):
    """X[k], Ps[k] = x, P element by element."""
    for i in range(5):
        X[k, i] = x[i]
        for j in range(5):
            Ps[k, i, j] = P[i, j]


@njit(cache=True)
def _ekf_kernel(t, Z, x0, P0, Q, R, gate, reacquire, fast, rail, jump_steps):
    """The EKF over the screened measurements ``Z``; ``rail[k]``: the yaw rate's rail value where it is at
    the rails (NaN elsewhere); ``jump_steps[k]``: nominal steps spanned by a clock jump (0: no jump)."""
    n = t.shape[0]
    X = np.empty((n, 5))
    Ps = np.empty((n, 5, 5))
    nis = np.full(n, np.nan)
    status = np.zeros(n, dtype=np.int64)
    rejected = np.zeros((n, 4), dtype=np.bool_)
    reacquired = np.zeros((n, 4), dtype=np.bool_)
    streak = np.zeros(4, dtype=np.int64)
    gate_on = np.isfinite(gate[0])  # any channel gated (a plain bool: a literal False compiled the gate twice)
    for g in range(1, 4):
        gate_on = gate_on or np.isfinite(gate[g])
    H = np.eye(5)
    # the heading wraps; a local array, not a global constant (read-only in a kernel): the general update then has
    # the signature of the paper kernels' and of kalman.update's calls, one compiled function for all of them
    angle_mask = np.zeros(5, dtype=np.bool_)
    angle_mask[_HEADING] = True
    w, y = np.zeros((6, 5, 5)), np.zeros((5, 1))
    Phi_P = np.empty((5, 5))
    zu = np.empty(5)
    x, P = x0.copy(), P0.copy()
    _store(X, Ps, 0, x, P)
    for k in range(1, n):
        T = t[k] - t[k - 1]
        if jump_steps[k] > 0.0:  # clock jump: state held, Q for every nominal step
            _add_scaled(P, Q, jump_steps[k])
        else:
            Phi = _phi(x, T)  # Eq. (16) at the previous estimate
            _mul(Phi, P, Phi_P)
            _mul_bt(Phi_P, Phi, P)
            _add_scaled(P, Q, 1.0)  # P = Phi P Phi^T + Gamma Q Gamma^T, Gamma = I
            x = motion(x, T)  # Eq. (13)
        z = Z[k]
        at_rail = not np.isnan(rail[k])
        n_rej = 0
        if gate_on or at_rail:
            n_rej = _gate_and_censor(x, P, z, R, gate, gate_on, rail[k], zu, rejected[k], streak, reacquire, reacquired[k])
        if n_rej > 0 or at_rail:  # gated or saturated: the general kernel on zu
            x, P, _, nis[k], status[k] = _kernels.kalman_update(x, P, zu, x, H, R, angle_mask, np.inf)
            if n_rej > 0:
                status[k] = kalman.REJECTED
        elif fast and np.all(np.isfinite(z)):
            nis[k], status[k] = _update_identity_h(x, P, z, R, np.inf, w, y)
        else:  # dropouts: the general kernel
            x, P, _, nis[k], status[k] = _kernels.kalman_update(x, P, z, x, H, R, angle_mask, np.inf)
        x[_HEADING] = np.mod(x[_HEADING], 2 * np.pi)
        _store(X, Ps, k, x, P)
    return X, Ps, nis, status, rejected, reacquired


CHANNELS = ("gps", "heading", "speed", "yaw_rate")
"""Measurement groups of the EKF, in the order of ``gate`` (fault sensors ``gnss``, ``heading``, ``speed``, ``yaw_rate``)."""


def covariance(M: ArrayLike, name: str) -> Array:
    """A validated (5, 5) symmetric positive semi-definite matrix from itself or its diagonal (5,).

    Examples
    --------
    >>> from navlib.filters import planar_ekf
    >>> planar_ekf.covariance([1.0, 1.0, 0.1, 0.5, 0.01], "P0").shape   # a diagonal becomes a (5, 5) matrix
    (5, 5)
    """
    M = as_array(M, text(name, "name", empty=False))
    if M.shape == (5,):
        M = np.diag(M)
    if M.shape != (5, 5) or not np.allclose(M, M.T) or np.any(np.linalg.eigvalsh(M) < 0):
        raise ValueError(f"{name}: expected a symmetric positive semi-definite (5, 5) matrix or a diagonal (5,)")
    return kernel_array(M)


def _gate(gate):
    g = as_array(gate, "gate", finite=False)
    if g.shape not in ((), (4,)) or np.any(np.isnan(g)) or not np.all(g > 0):
        raise ValueError(
            f"gate: expected a positive NIS threshold (inf for none) or 4 of them (gps, heading, speed, yaw_rate), got {gate!r}"
        )
    return kernel_array(np.broadcast_to(g, (4,)), dtype=float)


@dataclass(frozen=True, eq=False)
class EkfConfig:
    """Noise model and fault handling of :func:`filter_grid`, validated on construction.

    Attributes
    ----------
    Q, R : array_like, shape (5, 5) or (5,)
        Per-step process noise and measurement noise (required: the filter has no default noise; e.g. the
        values of Zhao et al. 2023, ``navlib.papers.gauss_kruger_ekf.Q_PAPER`` and ``R_PAPER``). Stored (5, 5).
    P0 : array_like, shape (5, 5) or (5,), optional
        Initial covariance; default zeros (the paper's P(0)). Stored (5, 5).
    gate : float or array_like, shape (4,)
        NIS thresholds per channel (:data:`CHANNELS`: GPS position, 2 dof; heading,
        speed, yaw rate, 1 dof each), each tested on its marginal innovation
        ``y_g^T S_gg^-1 y_g``; a scalar applies to all; ``inf`` (default): never gate.
        E.g. ``[18.4, 15.1, 15.1, 15.1]`` (chi-square, 1e-4 false alarms).
        A manoeuvre the process noise ``Q`` does not allow for (the paper's Q:
        0.04 rad/s and 0.01 m/s per step) fails the test like an outlier; see
        ``reacquire``. Stored (4,).
    reacquire : int
        A channel gated out on this many consecutive epochs (with data) is
        fused without the test at its next sample, its states' variance
        inflated by the squared innovation (the sample takes over), and the
        streak restarts (``faults[sensor, "reacquired"]``): isolated outliers stay
        out, a lasting change of the truth (a real step in speed or yaw rate,
        a filter that has lost the heading) cannot lock the channel out. Default 3.
    limits : SensorLimits
        The yaw-rate gyro's limits; the EKF reads three of them (the others concern raw IMU samples).
        ``full_scale_gyro`` (rad/s): a yaw-rate sample with ``|omega| >= full_scale_gyro`` is at the
        rails and only says ``|omega| >= range``; it is never gated and never fused at face value: while
        the predicted omega is inside the rails the rail value ``±range`` is fused (the nearest rate the
        sample allows), once the prediction is beyond the rail the sample is skipped.
        ``stuck_run``: a yaw rate repeating exactly over this many epochs (checked only when the series
        is noisy from the start) is skipped like a NaN sample. ``max_dt``: a longer step is a clock jump
        (a time-stamp jump or a recording gap): the state is not propagated over it and ``P`` grows by
        ``Q`` for every median step it spans (module docstring: why not a restart).
    fast : bool
        Use the specialised H = I5 update when every component is present (default; False:
        :func:`navlib.kalman.update` at every epoch; same result).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.filters import planar_ekf
    >>> config = planar_ekf.EkfConfig(Q=np.full(5, 1e-4), R=np.full(5, 0.01), gate=9.0)   # diagonals
    >>> np.diag(config.Q), config.gate
    (array([0.0001, 0.0001, 0.0001, 0.0001, 0.0001]), array([9., 9., 9., 9.]))
    """

    Q: ArrayLike
    R: ArrayLike
    P0: ArrayLike | None = None
    gate: float | ArrayLike = np.inf
    reacquire: int = 3
    limits: SensorLimits = field(default_factory=SensorLimits)
    fast: bool = True

    def __post_init__(self) -> None:
        for name in ("Q", "R"):
            object.__setattr__(self, name, covariance(getattr(self, name), name))
        object.__setattr__(self, "P0", np.zeros((5, 5)) if self.P0 is None else covariance(self.P0, "P0"))
        object.__setattr__(self, "gate", _gate(self.gate))
        object.__setattr__(self, "reacquire", integer(self.reacquire, "reacquire"))
        instance(self.limits, "limits", SensorLimits, "a SensorLimits (navlib.imu)")
        object.__setattr__(self, "fast", flag(self.fast, "fast"))


@dataclass
class EkfResult:
    """Output of :func:`filter_grid` (and of the paper pipeline :func:`navlib.papers.gauss_kruger_ekf.ekf`).

    Every epoch after the first is accounted for: each channel of it was fused,
    missing (NaN), gated out, reacquired or at the gyro rails, as ``faults`` says.

    Attributes
    ----------
    t : ndarray, shape (N,)  (s)
    x : ndarray, shape (N, 5)
        Filtered states ``[x north, y east, heading (grid, rad), v, omega]``.
    P : ndarray, shape (N, 5, 5)
    nis : ndarray, shape (N,)
        Normalised innovation squared of the components fused (NaN where
        nothing was fused).
    z : ndarray, shape (N, 5)
        Measurements in the grid frame as given to the filter (projected GPS,
        grid heading); saturated or gated samples are still shown here.
    prediction_only : ndarray of bool, shape (N,)
        Epochs with no measurement at all to fuse: the filter only predicted (False at the first epoch).
    faults : FaultReport
        Per ``(sensor, kind)``, counts over the epochs after the first and flags per epoch, shape (N,):
        sensors ``gnss``, ``heading``, ``speed``, ``yaw_rate`` (:data:`CHANNELS` order) with kinds
        ``nan`` (missing; GPS: either coordinate), ``outlier`` (gated out) and ``reacquired`` (fused
        without the gate after ``reacquire`` rejections); ``("yaw_rate", "saturated")`` (at or beyond
        the gyro rails, never fused at face value; its flags also cover the first epoch),
        ``("yaw_rate", "stuck")`` and the clock jumps ``("clock", "jump")``.
    zone : int or None
        Zone held by :func:`navlib.papers.gauss_kruger_ekf.ekf` (None from :func:`filter_grid`).
    origin_gk : ndarray, shape (2,), or None
        GK coordinates (north, east; m) subtracted from the projected fixes (None from :func:`filter_grid`).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.filters import planar_ekf
    >>> t = 0.5 * np.arange(5)
    >>> truth = planar_ekf.propagate([0.0, 0.0, 0.0, 1.0, 0.0], 0.5, 4)   # straight at 1 m/s
    >>> res = planar_ekf.filter_grid(t, truth, truth[0], planar_ekf.EkfConfig(Q=np.full(5, 1e-4), R=np.full(5, 0.01)))
    >>> res.x.shape, res.P.shape, res.nis.shape
    ((5, 5), (5, 5, 5), (5,))
    """

    t: np.ndarray
    x: np.ndarray
    P: np.ndarray
    nis: np.ndarray
    z: np.ndarray
    prediction_only: np.ndarray
    faults: FaultReport
    zone: int | None = None
    origin_gk: np.ndarray | None = None


@boundary
def filter_grid(t: Times, z: ArrayLike, x0: ArrayLike, config: Is[EkfConfig]) -> EkfResult:
    """The EKF on measurements already in the grid frame.

    The measurements are screened once (:class:`EkfConfig`: yaw rate at the rails, stuck
    yaw rate, clock jumps), then filtered: a NaN component is missing and left out of the
    update (an epoch with nothing is prediction only); with a finite ``gate`` each channel
    whose innovation fails its own NIS test is left out and the others are fused. All are
    reported in ``EkfResult.faults``. Times must be strictly increasing (``ValueError``
    otherwise: run :func:`navlib.timing.sanitize` first); the step ``T = t[k] - t[k-1]``
    may vary from epoch to epoch (``Q`` stays per step).

    Parameters
    ----------
    t : array_like, shape (N,)
        Strictly increasing times (s), one per row of ``z``; step ``T = t[k] - t[k-1]``.
    z : array_like, shape (N, 5)
        ``[x_GPS, y_GPS, theta, v, omega]`` per epoch; NaN components are
        missing (the row of ``t[0]`` is not used: ``x0`` holds there).
    x0 : array_like, shape (5,)
    config : EkfConfig
        Noise, gates and the yaw-rate gyro's limits.

    Returns
    -------
    EkfResult

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.filters import planar_ekf
    >>> t = 0.5 * np.arange(5)
    >>> truth = planar_ekf.propagate([0.0, 0.0, 0.0, 1.0, 0.0], 0.5, 4)   # heading 0 (north), 1 m/s
    >>> z = truth.copy()
    >>> z[2, 0] = 50.0                                               # a 50 m jump in x
    >>> res = planar_ekf.filter_grid(t, z, truth[0], planar_ekf.EkfConfig(Q=np.full(5, 1e-4), R=np.full(5, 0.01), gate=9.0))
    >>> np.round(res.x[:, 0], 3), int(res.faults["gnss", "outlier"])   # the jump is gated out
    (array([0. , 0.5, 1. , 1.5, 2. ]), 1)
    """
    z = as_array(z, "z", allow_nan=True, shape=(None, 5))
    t = same_shape(time_axis(t, "t"), "t", (z.shape[0],), of="z")  # z first: ekf hands on its user's t unchecked
    x0 = as_array(x0, "x0", shape=(5,))
    epochs = _screen_epochs(t, z, config.limits)
    X, P, nis, status, rejected, reacquired = _ekf_kernel(
        t, epochs.z, x0, config.P0, config.Q, config.R, config.gate, config.reacquire, config.fast, epochs.rail, epochs.jump_steps
    )
    missing = np.stack([~np.all(np.isfinite(z[:, :2]), axis=1), np.isnan(z[:, 2]), np.isnan(z[:, 3]), np.isnan(z[:, 4])], -1)
    missing[0] = False  # x0 holds at the first epoch
    flags = {}
    for i, sensor in enumerate(_FAULT_SENSORS):
        flags[sensor, "nan"], flags[sensor, "outlier"], flags[sensor, "reacquired"] = (
            missing[:, i],
            rejected[:, i],
            reacquired[:, i],
        )
    flags["yaw_rate", "saturated"], flags["yaw_rate", "stuck"], flags["clock", "jump"] = (
        epochs.saturated,
        epochs.stuck,
        epochs.jump,
    )
    faults = FaultReport({key: int(mask[1:].sum()) for key, mask in flags.items()}, flags)
    prediction_only = status == kalman.NO_DATA
    prediction_only[0] = False
    return EkfResult(t, X, P, nis, z, prediction_only, faults)


class _Epochs(NamedTuple):
    """The measurements after :func:`_screen_epochs`: what the kernel fuses, and the faults found."""

    z: np.ndarray  # stuck yaw-rate samples set to NaN (skipped)
    rail: np.ndarray  # the rail value +-full_scale_gyro where the yaw rate is at the rails, else NaN
    jump_steps: np.ndarray  # nominal steps spanned by a clock jump, 0 elsewhere
    saturated: np.ndarray
    stuck: np.ndarray
    jump: np.ndarray


def _screen_epochs(t: Array, z: Array, limits: SensorLimits) -> _Epochs:
    """The one pass over the validated measurements before the filter runs (yaw-rate rails and stuck
    output, clock jumps)."""
    dts = np.diff(t)
    t_nominal = float(np.median(dts))
    jump = np.concatenate([[False], dts > limits.jump_limit(t_nominal)])
    jump_steps = np.zeros(t.size)
    jump_steps[jump] = dts[jump[1:]] / t_nominal
    fs = limits.full_scale_gyro
    with np.errstate(invalid="ignore"):
        saturated = np.abs(z[:, 4]) >= fs  # NaN compares False
    rail = np.where(saturated, np.copysign(fs, z[:, 4]), np.nan)
    stuck = _robust.stuck_samples(z[:, 4:], limits.stuck_samples(t_nominal) or None, fs)
    z_used = z
    if stuck.any():  # stuck yaw rate: skipped like a NaN sample
        z_used = z.copy()
        z_used[stuck, 4] = np.nan
    return _Epochs(kernel_array(z_used), rail, jump_steps, saturated, stuck, jump)
