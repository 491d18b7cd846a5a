r"""Strapdown inertial navigation in the ENU frame over the WGS84 ellipsoid.

Discrete mechanisation (Titterton & Weston 2004, ch. 3; Groves 2013, ch. 5),
one step per IMU sample k covering :math:`[t_k, t_k + \Delta t]`:

.. math::

    \omega_{in} &= \omega_{ie}(\varphi_k) + \omega_{en}(\varphi_k, h_k, v_k) \\
    q_{k+1} &= q(-\omega_{in} \Delta t) \otimes q_k \otimes q(\omega_k \Delta t) \\
    f^n &= C\big(q(-\omega_{in} \Delta t / 2) \otimes q_k \otimes q(\omega_k \Delta t / 2)\big)\, f_k \\
    v_{k+1} &= v_k + \big(f^n + g^n(\varphi_k, h_k) - (2 \omega_{ie} + \omega_{en}) \times v_k\big)\, \Delta t

(the second line is the attitude, the third the specific force at the mid-interval attitude); latitude
:math:`\varphi`, longitude and height advance with the mean of :math:`v_k` and :math:`v_{k+1}` (trapezoid),
where :math:`q(\mathbf{r})` is the quaternion of a rotation vector. Gyro and
accelerometer samples are the mean rate and mean specific force over the
interval (``w_k dt`` is the angle increment). :func:`navlib.trajectory.ideal_imu`
is the exact inverse of this scheme, so integrating ideal samples reproduces
the true trajectory to rounding error.

The kernels are compiled with numba and loop over samples; leading axes of
the inputs (Monte Carlo trials) are flattened into one loop. With
``NUMBA_DISABLE_JIT=1`` they run as plain Python. The step is the compiled
primitive :func:`navlib._kernels.nav_step`, which navlib's kernels call;
:func:`nav_step` is its validated public wrapper.

Faults (navlib's robustness contract; tests in ``tests/faults/test_faults_strapdown.py``)
-----------------------------------------------------------------------------------------
Dropouts
    By default (``nan_policy="raise"``) a NaN sample raises ``ValueError``: a free
    INS has no measurement to fall back on, so nothing is guessed silently.
    With ``nan_policy="hold"`` a NaN gyro (accelerometer) sample is replaced by the
    last good gyro (accelerometer) sample of the same trial, zero-order hold.
    :func:`integrate` reports the held samples in ``Trajectory.faults``
    (``("gyro", "nan")``, ``("accel", "nan")``: counts per trial and per-sample
    flags); for :func:`integrate_attitude` they are the NaN rows of its input,
    :func:`navlib.robust.fault_report`. A trial whose first sample is NaN cannot be
    held and raises. The error of a hold grows with the gap like any dead reckoning:
    attitude error ~ |dw| * gap, position error ~ |df| * gap^2 / 2.
Outliers, saturation
    Not detectable by a free INS (no redundancy): spikes and clipped samples are
    integrated as given. Saturation is counted where it happens, in
    :func:`navlib.sensors.simulate_imu` (``ImuOutput.gyro_saturated``,
    ``accel_saturated``) and :func:`navlib.faults.saturate`.
Timing
    ``dt`` is a scalar or a per-sample array of shape (N,) (``dt[k]`` is the
    interval covered by sample k, e.g. :func:`navlib.timing.intervals` of the
    epoch times); the documented pipeline for logs with repeated or
    out-of-order timestamps is :func:`navlib.timing.sanitize` first.
"""

from __future__ import annotations

from typing import Annotated

import numpy as np
from numba import njit
from numpy.typing import NDArray

from . import _attitude, _earth, _kernels, _robust, attitude, earth, robust
from ._typing import Array, ArrayLike, Dcm, Interval, Quat, Vec3, Vec3Series
from ._validate import (
    Check,
    Real,
    Step,
    as_array,
    as_dcm,
    as_quat,
    boundary,
    broadcast,
    broadcast_to,
    flag,
    kernel_array,
    latitude,
    sample_intervals,
    small_turns,
)
from .imu import ImuSamples, unpack
from .trajectory import Trajectory

__all__ = ["integrate", "integrate_attitude", "nav_step", "earth_constants", "error_model", "error_input"]


_NAN_POLICIES = ("raise", "hold")


def _samples(x: ArrayLike, name: str) -> Array:
    """IMU samples ``(..., N, 3)``: real numbers, NaN allowed here (dropouts), inf never."""
    return as_array(x, name, tail=(3,), min_ndim=1, allow_nan=True)


def _dropouts(x: Array, name: str, policy: str) -> tuple[Array, NDArray[np.bool_]]:
    """Apply the dropout policy to validated samples x; return (x, held mask)."""
    if policy == "raise":
        if np.isnan(x).any():
            raise ValueError(f"{name}: contains NaN samples (use nan_policy='hold' to hold the last good sample)")
        return x, np.zeros(x.shape[:-1], dtype=bool)
    return _robust.hold(x, "raise", name, axis=-2)


def _sample_intervals(dt: Interval, n: int) -> Array:
    """``dt`` as the kernels take it: one element for a fixed interval (the time axis is then ``dt * k``),
    else one per sample."""
    dts = sample_intervals(dt, n)
    return dts[:1] if np.ndim(dt) == 0 else dts


@boundary
def integrate_attitude(
    q0: Quat,
    w_ib_b: Vec3Series,
    dt: Interval,
    w_in_n: Vec3 | None = None,
    *,
    nan_policy: Annotated[str, Check("choice", options=_NAN_POLICIES)] = "raise",
) -> Array:
    r"""Integrate gyro samples into an attitude history.

    :math:`q_{k+1} = q(-\omega_{in}^n \Delta t_k) \otimes q_k \otimes q(\omega_k \Delta t_k)` with a constant
    navigation-frame rate ``w_in_n`` (e.g. Earth rate at a fixed latitude for
    a static or slowly moving IMU; zero to neglect it).

    Parameters
    ----------
    q0 : array_like, shape (4,) or (..., 4)
        Initial attitude quaternion q_b^n.
    w_ib_b : array_like, shape (..., N, 3)
        Gyro samples (rad/s). NaN marks a dropout (see ``nan_policy``); inf is rejected.
    dt : float or array_like, shape (N,)
        Sample interval (s), or per-sample intervals (irregular sampling;
        ``dt[k]`` is covered by sample k, shared by all trials).
    w_in_n : array_like, shape (3,), optional
        Rotation rate of the navigation frame (rad/s); default zero.
    nan_policy : {"raise", "hold"}, default "raise"
        Dropout policy: raise ``ValueError`` on NaN samples, or hold the last
        good sample of the trial (:func:`navlib.robust.hold`). The held samples are exactly the NaN
        rows of ``w_ib_b``: ``robust.fault_report(w_ib_b, "gyro", flags=True)`` counts and flags them.

    Returns
    -------
    q_bn : ndarray, shape (..., N + 1, 4)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude, strapdown
    >>> w_ib_b = np.tile([0.0, 0.0, -np.deg2rad(9.0)], (100, 1))     # 9 deg/s clockwise for 1 s
    >>> q = strapdown.integrate_attitude([1.0, 0.0, 0.0, 0.0], w_ib_b, 0.01)
    >>> q.shape, np.round(np.rad2deg(attitude.quat_to_euler(q[-1])), 6) + 0.0
    ((101, 4), array([9., 0., 0.]))
    """
    w, _ = _dropouts(_samples(w_ib_b, "w_ib_b"), "w_ib_b", nan_policy)
    dt = _sample_intervals(dt, w.shape[-2])
    small_turns(w, dt)
    q0 = as_quat(q0, "q0")
    q0 = broadcast_to(q0, "q0", w.shape[:-2] + (4,), of="the trials of w_ib_b")
    w_in = np.zeros(3) if w_in_n is None else as_array(w_in_n, "w_in_n", shape=(3,))
    return _attitude.integrate(q0, w, dt, w_in)


def _state_array(x: ArrayLike, name: str, size: int) -> np.ndarray:
    """A state argument of :func:`nav_step`: the caller's writeable float64 array itself (updated in place),
    else a float64 copy (a list, an integer or float32 array is never modified)."""
    arr = as_array(x, name, shape=(size,))
    return x if arr is x and arr.flags.writeable else arr.copy()


@boundary
def nav_step(
    lla: Vec3, vel: Vec3, q: Quat, w: Vec3, f: Vec3, dt: Step, earth_consts: ArrayLike, hold_height: bool = False
) -> tuple[Array, Array, Array]:
    """One mechanisation step (module docstring), updating ``lla``, ``vel``, ``q`` in place.

    Validates its arguments, then runs the compiled primitive
    :func:`navlib._kernels.nav_step`, which :func:`integrate` and navlib's own compiled
    filters (e.g. :mod:`navlib.filters.zupt_ins`) call directly, sample by sample.

    Parameters
    ----------
    lla : array_like, shape (3,)
        ``[lat (rad), lon (rad), h (m)]``, |lat| <= pi/2.
    vel : array_like, shape (3,)
        ENU velocity (m/s).
    q : array_like, shape (4,)
        Attitude quaternion q_b^n (non-zero).
    w, f : array_like, shape (3,)
        Gyro (rad/s) and accelerometer (m/s^2) sample, finite.
    dt : float
        Interval covered by this sample (s), positive and finite.
    earth_consts : array_like, shape (7,)
        ``Ellipsoid.gravity_constants + (omega,)``; see :func:`earth_constants`.
    hold_height : bool
        Hold vertical velocity at 0 and the height fixed.

    Returns
    -------
    lla, vel, q : ndarray, shapes (3,), (3,), (4,)
        The state after the step. A writeable float64 ndarray argument is updated in
        place and returned; any other (a list, an integer or float32 array) is left
        unchanged and the new state is a float64 copy.

    Raises
    ------
    ValueError
        Naming the argument: wrong shape (also empty), non-finite values, a latitude
        outside [-pi/2, pi/2] rad, a zero quaternion, ``dt <= 0``, a non-bool
        ``hold_height``, or values that are not real numbers.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import strapdown, trajectory
    >>> lla, vel, q = np.array([0.6, 0.2, 50.0]), np.zeros(3), np.array([1.0, 0.0, 0.0, 0.0])
    >>> w_ib_b, f_b = trajectory.ideal_imu(trajectory.static(0.01, 0.01, lla, [0.0, 0.0, 0.0]))
    >>> _ = strapdown.nav_step(lla, vel, q, w_ib_b[0], f_b[0], 0.01, strapdown.earth_constants())   # updates lla, vel, q
    >>> np.round(vel, 12) + 0.0                                       # static input: the state stays put
    array([0., 0., 0.])
    """
    lla = _state_array(lla, "lla", 3)
    latitude(lla[0], "lla[0] (lat)")
    vel = _state_array(vel, "vel", 3)
    q = _state_array(q, "q", 4)
    if not q @ q > 0:
        raise ValueError("q: expected a non-zero quaternion")
    w = kernel_array(as_array(w, "w", shape=(3,)))
    f = kernel_array(as_array(f, "f", shape=(3,)))
    c = kernel_array(as_array(earth_consts, "earth_consts", shape=(7,)))
    if not (c[0] > 0 and 0 <= c[2] < 1):
        raise ValueError(
            "earth_consts: expected [a > 0, f, 0 <= e2 < 1, m, gamma_e, k, omega] "
            f"(strapdown.earth_constants), got a = {c[0]:g}, e2 = {c[2]:g}"
        )
    _kernels.nav_step(lla, vel, q, w, f, dt, c, flag(hold_height, "hold_height"))
    return lla, vel, q


@boundary
def earth_constants(ellipsoid: earth.EllipsoidArg = earth.WGS84) -> np.ndarray:
    """The ``earth_consts`` array of :func:`nav_step` for an ellipsoid.

    Examples
    --------
    >>> from navlib import strapdown
    >>> strapdown.earth_constants().shape
    (7,)
    """
    return _earth_constants(ellipsoid)


def _earth_constants(ellipsoid: earth.Ellipsoid) -> np.ndarray:
    """:func:`earth_constants` of a checked ellipsoid."""
    return np.array(ellipsoid.gravity_constants + (ellipsoid.omega,))


@njit(cache=True)
def _nav_kernel(lla0, vel0, q0, w, f, dt, earth_consts, hold_height):
    T, N = w.shape[0], w.shape[1]
    lla = np.empty((T, N + 1, 3))
    vel = np.empty((T, N + 1, 3))
    q = np.empty((T, N + 1, 4))
    for t in range(T):
        _store(lla[t, 0], vel[t, 0], q[t, 0], lla0[t], vel0[t], q0[t])
        _nav_trial(t, w, f, dt, earth_consts, hold_height, lla, vel, q)
    return lla, vel, q


@njit(cache=True)
def _nav_trial(t, w, f, dt, earth_consts, hold_height, lla, vel, q):
    """Trial t: each epoch's state is the previous one's, copied forward and stepped in place (row views of the
    outputs, free without numba's runtime; with it, each would count a reference)."""
    per_sample = dt.shape[0] > 1
    for k in range(w.shape[1]):
        _store(lla[t, k + 1], vel[t, k + 1], q[t, k + 1], lla[t, k], vel[t, k], q[t, k])
        _kernels.nav_step(
            lla[t, k + 1], vel[t, k + 1], q[t, k + 1], w[t, k], f[t, k], dt[k if per_sample else 0], earth_consts, hold_height
        )


@njit(cache=True)
def _store(lla_out, vel_out, q_out, lla, vel, q):
    """Copy one epoch's state element by element (an array assignment compiles numba's shape-mismatch
    message machinery, seconds of every cold start)."""
    for i in range(3):
        lla_out[i], vel_out[i] = lla[i], vel[i]
    for i in range(4):
        q_out[i] = q[i]


@boundary
def integrate(
    lla0: Vec3,
    vel0: Vec3,
    q0: Quat,
    w_ib_b: Vec3Series | ImuSamples,
    f_b: Vec3Series | None = None,
    dt: Interval | None = None,
    t0: Real = 0.0,
    hold_height: bool = False,
    ellipsoid: earth.EllipsoidArg = earth.WGS84,
    *,
    nan_policy: Annotated[str, Check("choice", options=_NAN_POLICIES)] = "raise",
) -> Trajectory:
    """Full strapdown navigation: attitude, ENU velocity and geodetic position.

    Parameters
    ----------
    lla0 : array_like, shape (3,) or (..., 3)
        Initial ``[lat (rad), lon (rad), h (m)]``.
    vel0 : array_like, shape (3,) or (..., 3)
        Initial ENU velocity (m/s).
    q0 : array_like, shape (4,) or (..., 4)
        Initial attitude quaternion q_b^n.
    w_ib_b, f_b : array_like, shape (..., N, 3)
        Gyro (rad/s) and accelerometer (m/s^2) samples. NaN marks a dropout
        (see ``nan_policy``); inf is rejected. An :class:`navlib.imu.ImuSamples` as
        ``w_ib_b`` supplies ``f_b`` and ``dt`` (its limits are not used here: a free INS has no
        redundancy to act on them).
    dt : float or array_like, shape (N,)
        Sample interval (s), or per-sample intervals for irregular sampling
        (``dt[k]`` is the interval covered by sample k, shared by all trials;
        e.g. :func:`navlib.timing.intervals` of the N + 1 epoch times).
    t0 : float
        Time of the initial state (s).
    hold_height : bool
        Hold the vertical channel (vertical velocity 0, height fixed at its
        initial value), as an INS aided by a known altitude does. The free
        vertical channel is unstable: height errors grow like cosh(sqrt(2 g/R) t).
    nan_policy : {"raise", "hold"}, default "raise"
        Dropout policy. ``"raise"``: NaN samples raise ValueError.
        ``"hold"``: a NaN gyro or accelerometer sample is replaced by the last
        good sample of the same sensor and trial (zero-order hold, :func:`navlib.robust.hold`) and
        reported in ``faults``.

    Returns
    -------
    Trajectory
        N + 1 epochs; arrays carry the leading (trial) axes of the inputs;
        ``time = t0 + [0, cumsum(dt)]``. Its ``faults`` counts the held samples
        per trial under ``("gyro", "nan")`` and ``("accel", "nan")`` (int arrays
        of shape (...), zero with ``"raise"``) with their flags (bool, shape (..., N)).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import strapdown, trajectory
    >>> traj = trajectory.static(10.0, 0.01, [np.deg2rad(30.0), 0.0, 0.0], [0.0, 0.0, 0.0])
    >>> w_ib_b, f_b = trajectory.ideal_imu(traj)
    >>> nav = strapdown.integrate(traj.lla[0], np.zeros(3), traj.q_bn[0], w_ib_b, f_b, 0.01)
    >>> bool(np.abs(nav.lla - traj.lla).max() < 1e-9)   # ideal samples reproduce the trajectory
    True
    """
    w_in, f_in, dt_in, _, _ = unpack(w_ib_b, f_b, dt)
    if isinstance(w_ib_b, ImuSamples):  # validated by the record
        w, f = w_ib_b.w_ib_b, w_ib_b.f_b
    else:
        w, f = broadcast(_samples(w_in, "w_ib_b"), _samples(f_in, "f_b"), name="f_b", of="w_ib_b, f_b")
    w, held_w = _dropouts(w, "w_ib_b", nan_policy)
    f, held_f = _dropouts(f, "f_b", nan_policy)
    lead, n = w.shape[:-2], w.shape[-2]
    dts = w_ib_b.dt if isinstance(w_ib_b, ImuSamples) else _sample_intervals(dt_in, n)
    small_turns(w, dts)
    lla0 = as_array(lla0, "lla0", tail=(3,))
    if np.any(np.abs(lla0[..., 0]) > np.deg2rad(89.9)):  # the one latitude check: also any beyond +-pi/2
        raise ValueError(
            f"lla0[..., 0] (lat): expected radians within +-89.9 deg (the ENU mechanisation is singular at the poles), "
            f"got max |lat| {np.abs(lla0[..., 0]).max():.4g} rad"
        )
    vel0 = as_array(vel0, "vel0", tail=(3,))
    q0 = as_quat(q0, "q0")

    def flat(x: Array, k: int, name: str) -> Array:
        x = broadcast_to(x, name, lead + x.shape[-k:], of="the trials of w_ib_b")
        return kernel_array(x.reshape((-1,) + x.shape[-k:]))

    lla, vel, q = _nav_kernel(
        flat(lla0, 1, "lla0"),
        flat(vel0, 1, "vel0"),
        flat(q0, 1, "q0"),
        flat(w, 2, "w_ib_b"),
        flat(f, 2, "f_b"),
        dts,
        _earth_constants(ellipsoid),
        flag(hold_height, "hold_height"),
    )
    if not (np.all(np.isfinite(lla)) and np.all(np.abs(lla[..., 0]) < np.pi / 2)):
        raise ValueError(
            "w_ib_b, f_b, dt: the integrated position diverges (it reaches a pole or overflows); check "
            "the units of dt and f_b and that f_b is specific force including gravity"
        )
    time = t0 + (dts[0] * np.arange(n + 1) if dts.size == 1 else np.concatenate([[0.0], np.cumsum(dts)]))
    held = {("gyro", "nan"): held_w, ("accel", "nan"): held_f}
    faults = robust.FaultReport({key: m.sum(axis=-1) for key, m in held.items()}, held)
    lla, vel, q = (x.reshape(lead + x.shape[-2:]) for x in (lla, vel, q))
    return Trajectory(time, lla, vel, q, faults)


@boundary
def error_model(
    lat: Real,
    h: Annotated[float, Check("scalar", within=(-12e3, 100e3, "m"))],
    vel_n: Vec3,
    f_n: Vec3,
    ellipsoid: earth.EllipsoidArg = earth.WGS84,
) -> Array:
    """Linear error dynamics of the ENU mechanisation (phi-angle model).

    State ``dx = [phi (3), dv_n (3), dlat, dlon, dh]`` with the attitude
    error defined by ``C_bn_hat = (I - [phi x]) C_bn``, velocity error
    ``dv_n = v_hat - v`` (m/s) and position error in rad, rad, m. Sensor errors
    enter as ``d(phi)/dt += -C_bn dw_b`` and ``d(dv_n)/dt += C_bn df_b`` (see
    :func:`error_input`). Follows the standard local-level model (Titterton &
    Weston 2004, ch. 12; Qin 2006, ch. 7) with the vertical gravity gradient
    ``2 g / R``; the latitude derivative of gravity (about 5e-6 m/s^2 per km)
    is neglected.

    Parameters
    ----------
    lat, h : float
        Latitude (rad) and height (m).
    vel_n : array_like, shape (3,)
        ENU velocity (m/s).
    f_n : array_like, shape (3,)
        Specific force in ENU (m/s^2).

    Returns
    -------
    F : ndarray, shape (9, 9)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import strapdown
    >>> F = strapdown.error_model(0.6, 0.0, np.zeros(3), [0.0, 0.0, 9.8])
    >>> F.shape, np.round(F[3:6, 0:3], 2) + 0.0                       # velocity error from tilt: [f_n x]
    ((9, 9), array([[ 0. , -9.8,  0. ],
           [ 9.8,  0. ,  0. ],
           [ 0. ,  0. ,  0. ]]))
    """
    phi = latitude(lat)
    if np.cos(lat) < 1e-9:
        raise ValueError("lat: the local-level (ENU) error model is singular at the poles; expected |lat| < 90 deg")
    v = as_array(vel_n, "vel_n", shape=(3,))
    f = as_array(f_n, "f_n", shape=(3,))
    R_M, R_N = _earth.radii(phi, ellipsoid)
    RMh, RNh = R_M + h, R_N + h
    sl, cl, tl = np.sin(lat), np.cos(lat), np.tan(lat)
    W = ellipsoid.omega
    vE, vN = v[0], v[1]
    w_ie = _earth.earth_rate_n(phi, ellipsoid)
    w_en = _earth.transport_rate_n(phi, np.asarray(h), v, ellipsoid)
    g = _earth.gravity(phi, np.asarray(h), ellipsoid)
    sk = attitude.skew
    Maa = -sk(w_ie + w_en)
    Mav = np.array([[0, -1 / RMh, 0], [1 / RNh, 0, 0], [tl / RNh, 0, 0]])
    M1 = np.array([[0, 0, 0], [-W * sl, 0, 0], [W * cl, 0, 0]])
    M2 = np.array([[0, 0, vN / RMh**2], [0, 0, -vE / RNh**2], [vE / (cl * cl * RNh), 0, -vE * tl / RNh**2]])
    Map = M1 + M2
    Mva = sk(f)
    Mvv = sk(v) @ Mav - sk(2 * w_ie + w_en)
    Mvp = sk(v) @ (2 * M1 + M2)
    Mvp[2, 2] += 2 * g / RNh
    Mpv = np.array([[0, 1 / RMh, 0], [1 / (cl * RNh), 0, 0], [0, 0, 1]])
    Mpp = np.array([[0, 0, -vN / RMh**2], [vE * tl / (cl * RNh), 0, -vE / (cl * RNh**2)], [0, 0, 0]])
    F = np.zeros((9, 9))
    F[0:3, 0:3], F[0:3, 3:6], F[0:3, 6:9] = Maa, Mav, Map
    F[3:6, 0:3], F[3:6, 3:6], F[3:6, 6:9] = Mva, Mvv, Mvp
    F[6:9, 3:6], F[6:9, 6:9] = Mpv, Mpp
    return F


def error_input(C_bn: Dcm) -> Array:
    """Input matrix of gyro and accelerometer errors for :func:`error_model`.

    ``d(dx)/dt = F dx + G [dw_b; df_b]`` with ``G = [[-C_bn, 0], [0, C_bn], [0, 0]]``.

    Parameters
    ----------
    C_bn : array_like, shape (3, 3)

    Returns
    -------
    G : ndarray, shape (9, 6)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import strapdown
    >>> strapdown.error_input(np.eye(3)).shape                        # 9 error states, 6 sensor errors
    (9, 6)
    """
    C = as_dcm(C_bn, "C_bn", shape=(3, 3))
    G = np.zeros((9, 6))
    G[0:3, 0:3] = -C
    G[3:6, 3:6] = C
    return G
