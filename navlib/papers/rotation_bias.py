r"""Gyro bias estimation by rotating the IMU (paper 001).

Wu Z., Sun Z., Zhang W., Chen Q. (2014). Gyroscope bias estimation and
compensation by rotation of the inertial measurement unit. *Journal of
Tsinghua University (Science and Technology)* 54(9): 1143-1147
(ISSN 1000-0054; no DOI). The only text of the paper available to the project
is OCR-damaged; the equations below were reconstructed from its legible parts,
corrected as listed under "Errata" (project ids, ``data/errata.csv``) and
written in navlib's conventions.

Conventions
-----------
The paper's Euler angles (psi, theta, phi) are navlib's ``hpr = [heading,
pitch, roll]`` (z-x-y order, heading clockwise from north), and its matrix
R (n -> b) is ``C_bn.T``. Pairs of tilt angles are ordered as in the paper,
``tilt = [roll, pitch]``. Gyros measure ``w_ib_b``; accelerometers measure
specific force ``f_b`` (+g up); the paper's gravity vector is ``a_m = -f_b``.

Equations (paper numbering)
---------------------------
* Eq. (1)  :math:`R = R_y(\phi) R_x(\theta) R_z(-\psi) = (C_b^n)^T`  :func:`eq1_matrix`
* Eq. (2)  Euler-angle kinematics, Omega = body rate relative to n, :func:`euler_rates`; integrated sample
  by sample (RK4 with the rate held over each sample) by :func:`integrate_euler`:

  .. math::

      \dot\phi &= \sin\phi \tan\theta\, \Omega_x + \Omega_y - \cos\phi \tan\theta\, \Omega_z \\
      \dot\theta &= \cos\phi\, \Omega_x + \sin\phi\, \Omega_z \\
      \dot\psi &= (\sin\phi\, \Omega_x - \cos\phi\, \Omega_z) / \cos\theta

  (roll :math:`\phi`, pitch :math:`\theta`, heading :math:`\psi`)

* Eq. (3)  measured rate = Omega + b.
* Eq. (4)  :math:`a_m = R\, [0, 0, -g]^T = g\, [\cos\theta \sin\phi,\ -\sin\theta,\ -\cos\theta \cos\phi]^T`  :func:`gravity_body`
* Eq. (5)  ``phi = atan2(a_mx, -a_mz)``, ``theta = atan2(-a_my, hypot(a_mx, a_mz))``  :func:`roll_pitch_from_accel`
* Eqs. (6)-(9)  per dwell k, ``delta_k = (gyro tilt change) - (accelerometer tilt
  change) = M(phi_k, theta_k) dT b = V_k b`` with M the first two rows
  of Eq. (2): :func:`tilt_matrix`, :func:`tilt_residuals`
* Eq. (10) :math:`\Delta R = I \cos\Delta\alpha + \sin\Delta\alpha [u\times] + (1 - \cos\Delta\alpha) u u^T`  :func:`rodrigues`
* Eq. (11) ``R' = dR^T R`` (``C_bn' = C_bn dR``)  :func:`rotate_attitude`
* Eqs. (12)-(14) stacked :math:`r = V b`, :math:`\hat b = (V^T V)^{-1} V^T r`  :func:`lsq_bias`,
  :func:`running_lsq_bias` (recursive, optional forgetting)

Paper's numbers: MTi-100 (bias stability 10 deg/h, noise 0.01 deg/s/sqrt(Hz)),
Delta alpha = 90 deg reciprocating every 5 s, 100 Hz, 3600 s, pitch 0/30/60 deg.

Errata (ids of ``data/errata.csv``)
-----------------------------------
* E001-01  Heading is clockwise: the first rotation is -psi.
* E001-02  The third row of Eq. (2) is ``(sin(phi) Wx - cos(phi) Wz) / cos(theta)``.
* E001-03  Row 2 of Eq. (4) is ``-g sin(theta)``; a_m is gravity, i.e. ``-f_b``.
* E001-04  Eq. (11) is ``R' = dR^T R`` (``dR R`` flips the sign of Delta alpha).
* E001-05  ``u (x) u`` in Eq. (10) is the outer product ``u u^T``.
* E001-06  Earth rate (15.04 deg/h) is not negligible against a 10 deg/h bias: with
  ``w_ie_b`` given, :func:`tilt_residuals` subtracts ``R w_ie_n`` and
  :func:`integrate_euler` integrates the rate relative to the ENU frame.
* E001-07  Eq. (6) is a first-order step; here each dwell's tilt residual is the
  least-squares slope of (integrated gyro tilt - accelerometer tilt).
* E001-08  Two attitudes suffice only if their body verticals differ (axis not
  vertical) and pitch stays away from +-90 deg; violations raise ValueError.
* E001-09  Unstated details (rotation axis, dwell timing, estimator window) are
  arguments here; E001-10 (Fig. 5 axis) does not affect the module.

Faulty data in rotation bias estimation (every fault is counted; nothing is dropped silently)
---------------------------------------------------------------------------------------------
=================  =================================================  ======================================
fault              what happens                                       reported by (``faults`` keys)
=================  =================================================  ======================================
NaN dropouts       residuals: a dwell with > ``max_missing`` of       ``Residuals.faults``: ``("imu", "nan")``
                   its samples NaN is skipped (default: any),         samples, ``("dwell", "refused")``;
                   else filled with the dwell median; LSQ and         ``KalmanBias.faults`` and
                   Kalman skip / predict through NaN dwells           ``running_lsq_bias``: ``("dwell", "nan")``
                   integration: linear interpolation, a gap           ``robust.fault_report(w, "gyro")``;
                   longer than ``max_gap`` raises                     ValueError
outliers (spikes)  residuals: ``outlier_k`` robust sigmas (1.4826     ``("gyro", "outlier")``,
                   MAD, at least 1.4826 q/2 for a quantised           ``("accel", "outlier")``;
                   sensor of step q) from the dwell median            ``KalmanBias.faults``
                   replaced (opt-in); Kalman gate rejects             ``("dwell", "outlier")``
                   corrupted dwells
saturation         residuals: dwell with samples at the rails         ``("imu", "saturated")`` samples,
                   skipped; integration: unreliable after it          ``("dwell", "refused")``;
                                                                      ``fault_report(..., full_scale=)``
timing             per-sample ``dt`` arrays in                        ``TimingReport`` from
                   :func:`tilt_residuals`, :func:`integrate_euler`;   ``timing.sanitize``
                   per-dwell intervals in :func:`kalman_bias`
=================  =================================================  ======================================

Extensions: a Kalman filter with a random-walk bias state (:func:`kalman_bias`),
the residual noise model (:func:`residual_covariance`) and the Cramer-Rao
bound (:func:`navlib.analysis.cramer_rao_bound`, :func:`design`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Annotated, Any

import numpy as np
import scipy.linalg
from llvmlite import binding
from numba import njit, types
from numba.extending import get_cython_function_address, overload

from .. import _attitude, _kernels, _lsq, _plots, attitude, earth, kalman, robust
from .._kernels import wrap_pi
from .._typing import Angles, Array, ArrayLike, Dcm, Interval, Times, Vec3, Vec3Series
from .._validate import (
    Check,
    Count,
    NonNegative,
    Positive,
    Real,
    Step,
    as_array,
    axes,
    boundary,
    broadcast_to,
    euler_angles,
    flag,
    imu_samples,
    indices,
    interval,
    kernel_array,
    positive,
    range_limit,
    same_shape,
    sample_intervals,
    scalar,
    small_turns,
    time_axis,
)
from ..alignment import level
from ..analysis import normal_condition
from ..euler import PITCH_LIMIT, check_pitch
from ..imu import ImuSamples, unpack
from ..units import G0

if TYPE_CHECKING:
    from matplotlib.axes import Axes

    from ..sensors import ImuModel, ImuOutput
    from ..trajectory import Trajectory

__all__ = [
    "eq1_matrix",
    "gravity_body",
    "roll_pitch_from_accel",
    "tilt_matrix",
    "rodrigues",
    "rotate_attitude",
    "dwell_attitudes",
    "dwell_windows",
    "Residuals",
    "tilt_residuals",
    "residual_covariance",
    "lsq_bias",
    "running_lsq_bias",
    "KalmanBias",
    "kalman_bias",
    "design",
    "MIN_DWELL_SAMPLES",
    "draw_rotation_scheme",
    "draw_rotation_schedule",
    "draw_flow",
]

MIN_DWELL_SAMPLES = 10
"""Fewest samples in a dwell window for a tilt-rate fit."""
_MAX_COND = 1e6


# --------------------------------------------------------------------------
# Eqs. (4)-(5): accelerometer tilt
# --------------------------------------------------------------------------


@boundary
def gravity_body(tilt: ArrayLike, g: Positive = G0) -> Array:
    """Eq. (4): gravity vector in the body frame, ``a_m = R [0, 0, -g]``.

    Parameters
    ----------
    tilt : array_like, shape (..., 2)
        ``[roll, pitch]`` (rad).
    g : float
        Gravity (m/s^2).

    Returns
    -------
    a_m : ndarray, shape (..., 3)
        Equals ``-f_b`` of a static accelerometer (erratum E001-03).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.papers import rotation_bias as rb
    >>> np.round(rb.gravity_body(np.deg2rad([0.0, 30.0])), 4)         # pitched 30 deg: [roll, pitch] -> a_m
    array([ 0.    , -4.9033, -8.4928])
    """
    tilt = as_array(tilt, "tilt", tail=(2,), nonempty=True)
    r, p = tilt[..., 0], tilt[..., 1]
    return g * np.stack([np.cos(p) * np.sin(r), -np.sin(p), -np.cos(p) * np.cos(r)], -1)


def roll_pitch_from_accel(f_b: Vec3) -> Array:
    """Eq. (5) on specific force: ``[roll, pitch]`` of a static IMU (rad).

    With ``a_m = -f_b`` this is the accelerometer levelling :func:`navlib.alignment.level`
    (the atan2 form of the arcsine) in the paper's order ``[roll, pitch]``.

    Parameters
    ----------
    f_b : array_like, shape (..., 3)
        Specific force (m/s^2), +g up when level.

    Returns
    -------
    tilt : ndarray, shape (..., 2)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude
    >>> from navlib.papers import rotation_bias as rb
    >>> f_b = attitude.euler_to_dcm(np.deg2rad([0.0, 10.0, -5.0])).T @ [0.0, 0.0, 9.8]
    >>> np.round(np.rad2deg(rb.roll_pitch_from_accel(f_b)), 6)        # [roll, pitch]
    array([-5., 10.])
    """
    pitch, roll = level(f_b)
    return np.stack([roll, pitch], -1)


def tilt_matrix(tilt: ArrayLike) -> Array:
    """M(roll, pitch): the first two rows of Eq. (2), ``[roll', pitch'] = M Omega``.

    Parameters
    ----------
    tilt : array_like, shape (..., 2)
        ``[roll, pitch]`` (rad); |pitch| <= 89 deg.

    Returns
    -------
    M : ndarray, shape (..., 2, 3)
        Its null space is the body vertical ``a_m`` (section 3.1).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.papers import rotation_bias as rb
    >>> np.round(rb.tilt_matrix(np.zeros(2)), 6) + 0.0                 # level: roll' = w_y, pitch' = w_x
    array([[0., 1., 0.],
           [1., 0., 0.]])
    """
    tilt = as_array(tilt, "tilt", tail=(2,), nonempty=True)
    check_pitch(tilt[..., 1], "tilt[..., 1] (pitch)")
    r, p = tilt[..., 0], tilt[..., 1]
    tp, cr, sr = np.tan(p), np.cos(r), np.sin(r)
    rows = [[sr * tp, np.ones_like(r), -cr * tp], [cr, np.zeros_like(r), sr]]
    return np.stack([np.stack(row, -1) for row in rows], -2)


# --------------------------------------------------------------------------
# Eqs. (10)-(11): rotation of the IMU
# --------------------------------------------------------------------------


def rodrigues(axis_b: Vec3, angle: Angles) -> Array:
    r"""Eq. (10): :math:`\Delta R = I \cos a + \sin a\, [u\times] + (1 - \cos a)\, u u^T` (b' -> b).

    Parameters
    ----------
    axis_b : array_like, shape (3,)
        Unit rotation axis u in the body frame.
    angle : array_like, shape (...)
        Rotation angle Delta alpha (rad).

    Returns
    -------
    dR : ndarray, shape (..., 3, 3)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.papers import rotation_bias as rb
    >>> np.round(rb.rodrigues([0.0, 0.0, 1.0], np.pi / 2), 12) + 0.0   # a quarter turn about z
    array([[ 0., -1.,  0.],
           [ 1.,  0.,  0.],
           [ 0.,  0.,  1.]])
    """
    u = as_array(axis_b, "axis_b", shape=(3,))
    if abs(np.linalg.norm(u) - 1) > 1e-9:
        raise ValueError(f"axis_b: expected a unit vector, got norm {np.linalg.norm(u):.6g}")
    a = as_array(angle, "angle", nonempty=True)[..., None, None]
    return np.cos(a) * np.eye(3) + np.sin(a) * attitude.skew(u) + (1 - np.cos(a)) * np.outer(u, u)


def rotate_attitude(hpr: Angles, axis_b: Vec3, angle: Angles) -> Array:
    """Eq. (11): attitude after rotating the IMU by ``angle`` about ``axis_b``.

    ``R' = dR^T R`` (erratum E001-04), i.e. ``C_bn' = C_bn dR``.

    Parameters
    ----------
    hpr : array_like, shape (..., 3)
        Attitude before the rotation (rad).
    axis_b : array_like, shape (3,)
    angle : array_like, shape (...)

    Returns
    -------
    hpr : ndarray, shape (..., 3)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.papers import rotation_bias as rb
    >>> np.round(np.rad2deg(rb.rotate_attitude([0.0, 0.0, 0.0], [0.0, 1.0, 0.0], np.pi / 2)), 6) + 0.0   # a quarter turn: roll 90
    array([ 0.,  0., 90.])
    """
    return _attitude.dcm_to_euler(attitude.euler_to_dcm(hpr) @ rodrigues(axis_b, angle))  # a rotation matrix


@boundary
def dwell_attitudes(hpr0: Angles, axis_b: Vec3, amplitude: float, n_dwells: Count) -> Array:
    """Attitudes of a reciprocating schedule: hpr0, rotated, hpr0, rotated, ...

    Parameters
    ----------
    hpr0 : array_like, shape (3,)
        Initial attitude (rad).
    axis_b : array_like, shape (3,)
    amplitude : float
        Delta alpha (rad).
    n_dwells : int

    Returns
    -------
    hpr : ndarray, shape (n_dwells, 3)

    Raises
    ------
    ValueError
        If a dwell's pitch is within 1 deg of +-90 deg (erratum E001-08).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.papers import rotation_bias as rb
    >>> np.round(np.rad2deg(rb.dwell_attitudes([0.0, 0.0, 0.0], [0.0, 1.0, 0.0], np.pi / 2, 3)), 6) + 0.0
    array([[ 0.,  0.,  0.],
           [ 0.,  0., 90.],
           [ 0.,  0.,  0.]])
    """
    hpr0 = euler_angles(hpr0, "hpr0", shape=(3,))
    pair = np.stack([hpr0, rotate_attitude(hpr0, axis_b, scalar(amplitude, "amplitude"))])
    if np.any(np.abs(pair[:, 1]) > PITCH_LIMIT):
        raise ValueError(
            f"axis_b: rotating by {np.rad2deg(amplitude):g} deg about {np.round(np.asarray(axis_b), 6)} drives "
            f"pitch to {np.rad2deg(pair[1, 1]):.1f} deg, where Eq. (2) is singular"
        )
    return pair[np.arange(n_dwells) % 2]


@boundary
def dwell_windows(
    n_samples: Count, dt: float, period: float, rotation_time: NonNegative, settle: NonNegative = 0.0
) -> tuple[np.ndarray, int]:
    """Dwell windows of :func:`navlib.trajectory.reciprocating_rotation`.

    Period k holds still over ``[k period, (k+1) period - rotation_time)``;
    the first ``settle`` seconds of each dwell are skipped.

    Parameters
    ----------
    n_samples : int
        Number of IMU samples.
    dt, period, rotation_time, settle : float  (s)

    Returns
    -------
    starts : ndarray of int, shape (K,)
        First sample of each complete dwell.
    length : int
        Samples per dwell (at least :data:`MIN_DWELL_SAMPLES`).

    Examples
    --------
    >>> from navlib.papers import rotation_bias as rb
    >>> starts, length = rb.dwell_windows(400, 0.1, period=10.0, rotation_time=1.0, settle=0.5)
    >>> starts, length                                                # 8.5 s of every 10 s period
    (array([  5, 105, 205, 305]), 85)
    """
    dt, period = interval(dt), scalar(period, "period", positive=True)
    per = int(round(period / dt))
    first = int(round(settle / dt))
    length = int(np.floor((period - rotation_time) / dt + 1e-9)) - first
    if length < MIN_DWELL_SAMPLES:
        raise ValueError(
            f"period, rotation_time, settle: dwell windows too short ({length} samples); expected at least {MIN_DWELL_SAMPLES}"
        )
    starts = np.arange(0, n_samples - length - first + 1, per) + first
    return starts.astype(np.int64), length


# --------------------------------------------------------------------------
# Eqs. (6)-(9): tilt-difference residuals per dwell
# --------------------------------------------------------------------------


@dataclass(frozen=True)
class Residuals:
    """Tilt-difference residuals of the dwells (Eqs. 6-9).

    Attributes
    ----------
    r : ndarray, shape (..., K, 2)
        ``delta_k = [d roll, d pitch]`` (rad) over each dwell; NaN for skipped dwells.
    V : ndarray, shape (..., K, 2, 3)
        ``V_k = M(roll_k, pitch_k) T`` (s); NaN for skipped dwells.
    tilt : ndarray, shape (..., K, 2)
        Dwell tilt ``[roll, pitch]`` from the mean specific force (rad).
    end : ndarray of int, shape (K,)
        Sample index after each dwell (when its residual becomes available).
    duration : float
        Dwell length T (s); with per-sample intervals, the mean over the dwells
        (each dwell's own length is in its ``V``).
    faults : FaultReport
        Counts over all trials (ints): ``("imu", "nan")`` samples inside dwell windows with a NaN gyro
        or accelerometer reading (those of refused dwells included; the others were filled with the
        dwell median); ``("gyro", "outlier")``, ``("accel", "outlier")`` samples of kept dwells more
        than ``outlier_k`` x MAD from the dwell median, replaced by it (0 without ``outlier_k``);
        ``("imu", "saturated")`` samples inside dwell windows at the device rails (``full_scale_*``);
        ``("dwell", "refused")`` dwells skipped, for dropouts (more than ``max_missing`` of their
        samples NaN) or for saturated samples.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude, earth, trajectory
    >>> from navlib.papers import rotation_bias as rb
    >>> traj = trajectory.reciprocating_rotation(40.0, 0.1, [0.5, 2.0, 0.0], [0.0, 0.0, 0.0], [0.0, 1.0, 0.0], np.pi / 2, 10.0)
    >>> w_ib_b, f_b = trajectory.ideal_imu(traj)
    >>> starts, length = rb.dwell_windows(len(w_ib_b), 0.1, period=10.0, rotation_time=1.0)
    >>> w_ie_b = earth.earth_rate_b(attitude.quat_to_dcm(traj.q_bn[starts]), 0.5)   # Earth rate at each dwell
    >>> res = rb.tilt_residuals(w_ib_b + [1e-4, 2e-4, -1e-4], f_b, 0.1, starts, length, w_ie_b)
    >>> res.r.shape, res.V.shape, res.duration                        # four dwells: [d roll, d pitch] each
    ((4, 2), (4, 2, 3), 9.0)
    """

    r: np.ndarray
    V: np.ndarray
    tilt: np.ndarray
    end: np.ndarray
    duration: float
    faults: robust.FaultReport


@njit(cache=True)
def _median(v):
    """``np.median(v)`` of a 1-D array without NaN (the same bits), from a sorted copy: numba compiles ``np.sort``
    once for :func:`navlib._kernels.quant_step` anyway, and its ``np.median`` took a second more of a cold start."""
    s = np.sort(v)
    half = s.shape[0] >> 1
    return (s[half - 1] + s[half]) / 2 if s.shape[0] % 2 == 0 else s[half]


@njit(cache=True)
def _median_sigma(buf, ok, n, a, want_sigma):
    """Median (and robust sigma: :func:`navlib._kernels.robust_sigma`, 1.4826 MAD floored at half the
    quantisation step) of column ``a`` of ``buf[:n]`` over rows where ``ok``; NaN when none."""
    m = 0
    vals = np.empty(n)
    for j in range(n):
        if ok[j]:
            vals[m] = buf[j, a]
            m += 1
    if m == 0:
        return np.nan, np.nan
    med = _median(vals[:m])
    if not want_sigma:
        return med, 0.0
    q = _kernels.quant_step(vals[:m])
    for j in range(m):
        vals[j] = abs(vals[j] - med)
    return med, _kernels.robust_sigma(_median(vals[:m]), q)


_RESIDUAL_FAULTS = (("dwell", "refused"), ("imu", "nan"), ("gyro", "outlier"), ("accel", "outlier"), ("imu", "saturated"))
"""The keys of ``Residuals.faults``, in the order of the residual kernel's ``counts``."""
_N_RESIDUAL_FAULTS = len(_RESIDUAL_FAULTS)


@njit(cache=True)
def _clean_dwell(wb, fb, n, max_missing, outlier_k, fs_gyro, fs_accel, counts):
    """Fill dropouts and replace outliers of one dwell in place; False when the dwell must be skipped.

    counts (added to): the faults of :data:`_RESIDUAL_FAULTS`, in that order (dwells for the first, samples else)
    """
    ok_w = np.ones(n, dtype=np.bool_)
    ok_f = np.ones(n, dtype=np.bool_)
    missing = 0
    saturated = 0
    for j in range(n):
        for a in range(3):
            if not np.isfinite(wb[j, a]):
                ok_w[j] = False
            if not np.isfinite(fb[j, a]):
                ok_f[j] = False
        if not (ok_w[j] and ok_f[j]):
            missing += 1
        elif (
            abs(wb[j, 0]) >= fs_gyro
            or abs(wb[j, 1]) >= fs_gyro
            or abs(wb[j, 2]) >= fs_gyro
            or abs(fb[j, 0]) >= fs_accel
            or abs(fb[j, 1]) >= fs_accel
            or abs(fb[j, 2]) >= fs_accel
        ):
            saturated += 1
    counts[1] += missing
    if saturated > 0:  # at the rails: the IMU was not still, or the reading is unknown
        counts[4] += saturated
        counts[0] += 1
        return False
    if missing > max_missing * n or missing == n:
        counts[0] += 1
        return False
    if missing == 0 and outlier_k <= 0:
        return True  # the common case: untouched
    detect = outlier_k > 0
    for buf, ok, c in ((wb, ok_w, 2), (fb, ok_f, 3)):
        bad = np.zeros(n, dtype=np.bool_)
        med = np.empty(3)
        for a in range(3):
            med[a], sigma = _median_sigma(buf, ok, n, a, detect)
            if detect:
                thresh = outlier_k * sigma
                for j in range(n):
                    if ok[j] and abs(buf[j, a] - med[a]) > thresh:
                        bad[j] = True
        for j in range(n):
            if bad[j]:
                counts[c] += 1
            if bad[j] or not ok[j]:
                buf[j, 0], buf[j, 1], buf[j, 2] = med[0], med[1], med[2]
    return True


@njit(cache=True)
def _residual_kernel(w, f, dts, regular, starts, n, w_ie, pitch_limit, max_missing, outlier_k, fs_gyro, fs_accel):
    T, K = w.shape[0], starts.shape[0]
    r = np.full((T, K, 2), np.nan)
    V = np.full((T, K, 2, 3), np.nan)
    tilt = np.full((T, K, 2), np.nan)
    counts = np.zeros(_N_RESIDUAL_FAULTS, dtype=np.int64)
    singular = False
    jbar = (n - 1) / 2
    s_jj = n * (n * n - 1) / 12.0  # sum of (j - jbar)^2
    dt = dts[0]
    wb = np.empty((n, 3))
    fb = np.empty((n, 3))
    tj = np.empty(n)
    for t in range(T):
        for k in range(K):
            s = starts[k]
            for j in range(n):
                for a in range(3):
                    wb[j, a] = w[t, s + j, a]
                    fb[j, a] = f[t, s + j, a]
            if not _clean_dwell(wb, fb, n, max_missing, outlier_k, fs_gyro, fs_accel, counts):
                continue
            fx = fy = fz = 0.0
            for j in range(n):
                fx += fb[j, 0]
                fy += fb[j, 1]
                fz += fb[j, 2]
            roll_k, pitch_k = np.arctan2(-fx, fz), np.arctan2(fy, np.hypot(fx, fz))
            if abs(pitch_k) > pitch_limit:
                singular = True
                continue
            tp, cr, sr = np.tan(pitch_k), np.cos(roll_k), np.sin(roll_k)
            m00, m01, m02, m10, m12 = sr * tp, 1.0, -cr * tp, cr, sr  # M (m11 = 0)
            wex, wey, wez = w_ie[t, k, 0], w_ie[t, k, 1], w_ie[t, k, 2]
            if regular:
                Td = n * dt
            else:  # sample times within the dwell for the slope fit
                Td = 0.0
                for j in range(n):
                    tj[j] = Td
                    Td += dts[s + j]
                tbar = 0.0
                for j in range(n):
                    tbar += tj[j]
                tbar /= n
                s_tt = 0.0
                for j in range(n):
                    s_tt += (tj[j] - tbar) ** 2
            g_r = g_p = 0.0  # gyro tilt change since the dwell start, M sum(w dt) (Eq. 6)
            sum_r = sum_p = 0.0  # sum (j - jbar) d_j for the slope fit
            for j in range(n):
                a_r = np.arctan2(-fb[j, 0], fb[j, 2]) - roll_k  # Eq. (5), about the dwell tilt
                a_r = wrap_pi(a_r)
                a_p = np.arctan2(fb[j, 1], np.hypot(fb[j, 0], fb[j, 2])) - pitch_k
                x = (j - jbar) if regular else (tj[j] - tbar)
                sum_r += x * (g_r - a_r)  # Eq. (7)
                sum_p += x * (g_p - a_p)
                wx, wy, wz = wb[j, 0] - wex, wb[j, 1] - wey, wb[j, 2] - wez
                h = dt if regular else dts[s + j]
                g_r += (m00 * wx + m01 * wy + m02 * wz) * h
                g_p += (m10 * wx + m12 * wz) * h
            if regular:
                # slope (rad/s) times the dwell length T = n dt gives delta_k (Eq. 9: delta_k = M T b)
                r[t, k, 0] = sum_r / s_jj * n
                r[t, k, 1] = sum_p / s_jj * n
            else:
                r[t, k, 0] = sum_r / s_tt * Td
                r[t, k, 1] = sum_p / s_tt * Td
            tilt[t, k, 0], tilt[t, k, 1] = roll_k, pitch_k
            V[t, k, 0, 0], V[t, k, 0, 1], V[t, k, 0, 2] = m00 * Td, m01 * Td, m02 * Td
            V[t, k, 1, 0], V[t, k, 1, 1], V[t, k, 1, 2] = m10 * Td, 0.0, m12 * Td
    return r, V, tilt, counts, singular


@boundary
def tilt_residuals(
    w_ib_b: Vec3Series | ImuSamples,
    f_b: Vec3Series | None = None,
    dt: Interval | None = None,
    starts: ArrayLike | None = None,
    length: Annotated[int, Check("integer", minimum=MIN_DWELL_SAMPLES)] | None = None,
    w_ie_b: Vec3Series | None = None,
    *,
    max_missing: Annotated[float, Check("scalar", within=(0.0, 0.5))] = 0.0,
    outlier_k: float | None = None,
    full_scale_gyro: float | None = None,
    full_scale_accel: float | None = None,
) -> Residuals:
    """Eqs. (6)-(9): gyro-minus-accelerometer tilt change over each dwell.

    Over dwell k the sequence ``d_j = M_k sum_{i<j} w_i dt - (tilt_j - tilt_k)``
    (integrated gyro tilt minus Eq. (5) accelerometer tilt) grows at the
    rate ``M_k b``; its least-squares slope times the dwell length T is the
    residual ``delta_k = V_k b + noise`` with ``V_k = M_k T``. M_k is taken
    at the dwell's mean accelerometer tilt. On a static rig Eq. (6) is exact.

    Faults (every one counted in ``Residuals.faults``; the IMU is still during a
    dwell, so its median reading is a good stand-in for a lost sample):

    * dropouts (NaN samples): a dwell with more than ``max_missing`` of its
      samples NaN is skipped (``("dwell", "refused")``, residual NaN); otherwise its
      NaN samples (``("imu", "nan")``) are filled with the dwell median. The default 0
      skips any dwell with a NaN, as before; a 30-s gap skips the dwells it
      covers.
    * outliers: with ``outlier_k``, samples more than ``outlier_k`` x
      1.4826 MAD from the dwell median in any component are replaced by the
      median (``("gyro", "outlier")``, ``("accel", "outlier")``). The MAD is floored at half the
      quantisation step q (the smallest non-zero difference between two of the
      dwell's readings; :func:`navlib._kernels.robust_sigma`, as in
      :func:`navlib.alignment.static_means`): a quantised gyro at rest has a
      MAD of 0, and without the floor every sample off the median code was an
      outlier. Without ``outlier_k`` a gyro spike of
      size s on one sample shifts the integrated tilt by s dt and the residual
      by up to 1.5 s dt (the slope-fit weight), unreported unless a later
      gate (:func:`kalman_bias`) rejects the dwell.
    * saturation: with ``full_scale_gyro``/``full_scale_accel`` (the device
      range, rad/s and m/s^2), a dwell with a sample at the rails
      (``|x| >= full_scale``) is skipped (``("imu", "saturated")`` samples,
      ``("dwell", "refused")``): the IMU was not still, or its reading is unknown.
    * timing: ``dt`` may be per-sample intervals (``timing.intervals`` of
      timestamps cleaned by ``timing.sanitize``); the gyro is integrated with
      each interval and the slope is fitted against sample time.

    Parameters
    ----------
    w_ib_b, f_b : array_like, shape (..., N, 3)
        Gyro (rad/s) and accelerometer (m/s^2) samples; NaN marks dropouts. An
        :class:`navlib.imu.ImuSamples` as ``w_ib_b`` supplies ``f_b``, ``dt`` (as per-sample
        intervals) and the gyro and accelerometer ranges.
    dt : float or array_like, shape (N,)
        Sample interval (s), or the interval after each sample.
    starts : array_like of int, shape (K,)
        First sample of each dwell (e.g. from :func:`dwell_windows`); required.
    length : int
        Samples per dwell, at least :data:`MIN_DWELL_SAMPLES`; required.
    w_ie_b : array_like, shape (K, 3) or (..., K, 3), optional
        Earth rate in the body frame during each dwell, subtracted from the
        gyros (erratum E001-06; :func:`navlib.earth.earth_rate_b`). Default: neglected, as in
        the paper.
    max_missing : float
        Largest fraction of a dwell's samples, in [0, 0.5], that may be NaN
        and filled (default 0: skip any dwell with a NaN).
    outlier_k : float, optional
        MAD outlier threshold (e.g. 6); None (default) detects no outliers.
    full_scale_gyro, full_scale_accel : float, optional
        Device ranges (rad/s, m/s^2); None: no saturation check.

    Returns
    -------
    Residuals

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude, earth, trajectory
    >>> from navlib.papers import rotation_bias as rb
    >>> traj = trajectory.reciprocating_rotation(40.0, 0.1, [0.5, 2.0, 0.0], [0.0, 0.0, 0.0], [0.0, 1.0, 0.0], np.pi / 2, 10.0)
    >>> w_ib_b, f_b = trajectory.ideal_imu(traj)
    >>> starts, length = rb.dwell_windows(len(w_ib_b), 0.1, period=10.0, rotation_time=1.0)
    >>> w_ie_b = earth.earth_rate_b(attitude.quat_to_dcm(traj.q_bn[starts]), 0.5)   # Earth rate at each dwell
    >>> res = rb.tilt_residuals(w_ib_b + [1e-4, 2e-4, -1e-4], f_b, 0.1, starts, length, w_ie_b)   # a gyro bias (rad/s)
    >>> np.round(rb.lsq_bias(res.r, res.V) * 1e4, 3)                  # Eq. (14) recovers it (1e-4 rad/s)
    array([ 1.,  2., -1.])
    """
    if isinstance(w_ib_b, ImuSamples):  # samples and intervals checked by the record
        w, f, dts, full_scale_gyro, full_scale_accel = unpack(w_ib_b, f_b, dt, full_scale_gyro, full_scale_accel)
        regular = False
    else:
        w_ib_b, f_b, dt, _, _ = unpack(w_ib_b, f_b, dt)  # f_b and dt required
        w, f = imu_samples(w_ib_b, f_b)
        dts, regular = sample_intervals(dt, w.shape[-2]), np.ndim(dt) == 0
    if starts is None or length is None:
        raise ValueError(f"{'starts' if starts is None else 'length'}: required")
    lead, n = w.shape[:-2], w.shape[-2]
    small_turns(w, dts)
    starts = indices(starts, "starts")
    if (
        starts.ndim != 1
        or starts.size == 0
        or not np.issubdtype(starts.dtype, np.integer)
        or starts.min() < 0
        or starts.max() + length > n
    ):
        raise ValueError(f"starts: expected a 1-D array of dwell start indices within [0, {n - length}]")
    k_out = 0.0 if outlier_k is None else scalar(outlier_k, "outlier_k", positive=True)
    fs_g, fs_a = range_limit(full_scale_gyro, "full_scale_gyro"), range_limit(full_scale_accel, "full_scale_accel")
    K = starts.size
    w_ie = np.zeros((K, 3)) if w_ie_b is None else as_array(w_ie_b, "w_ie_b", tail=(3,), nonempty=True)
    w_ie = broadcast_to(w_ie, "w_ie_b", lead + (K, 3), of="K = starts.size dwells and the trials of w_ib_b")

    def flat(x: Array) -> Array:
        return kernel_array(x.reshape((-1, n, 3)))

    r, V, tilt, c, singular = _residual_kernel(
        flat(w),
        flat(f),
        dts,
        regular,
        starts.astype(np.int64),
        length,
        kernel_array(w_ie.reshape(-1, K, 3)),
        PITCH_LIMIT,
        max_missing,
        k_out,
        fs_g,
        fs_a,
    )
    if singular:
        raise ValueError(
            f"f_b: a dwell's pitch is beyond +-{np.rad2deg(PITCH_LIMIT):g} deg, where Eq. (2) is "
            "singular; choose a rotation that keeps pitch away from +-90 deg"
        )
    if regular:
        duration = length * float(dts[0])
    else:
        duration = float(np.mean([dts[s : s + length].sum() for s in starts]))
    faults = robust.FaultReport({key: int(count) for key, count in zip(_RESIDUAL_FAULTS, c, strict=True)})
    return Residuals(
        r.reshape(lead + (K, 2)), V.reshape(lead + (K, 2, 3)), tilt.reshape(lead + (K, 2)), starts + length, duration, faults
    )


@boundary
def residual_covariance(
    tilt: ArrayLike,
    length: Annotated[int, Check("integer", minimum=MIN_DWELL_SAMPLES)],
    dt: Step,
    gyro_noise: NonNegative,
    accel_noise: NonNegative = 0.0,
    g: float = G0,
) -> Array:
    """Covariance of each dwell residual of :func:`tilt_residuals` from white sensor noise.

    Gyro white noise of density N integrates into a random walk; the slope
    fit weights it by ``c_i = dt sum_{j>i} (j - jbar) / S_jj``, giving
    ``cov = (N^2/dt) sum c_i^2 T^2 / dt^2 M M^T``, close to ``(6/5) N^2 T M M^T``.
    Accelerometer noise of density A gives tilt noise of variance
    ``(A^2/dt/g^2) diag(1/cos^2 pitch, 1)`` per sample and adds
    ``12/n`` times that (for n >> 1).

    Parameters
    ----------
    tilt : array_like, shape (..., 2)
        Dwell tilts ``[roll, pitch]`` (rad).
    length : int
        Samples per dwell.
    dt : float  (s)
    gyro_noise : float
        Gyro white-noise density (rad/s/sqrt(Hz)).
    accel_noise : float
        Accelerometer white-noise density (m/s^2/sqrt(Hz)).
    g : float  (m/s^2)

    Returns
    -------
    R : ndarray, shape (..., 2, 2)  (rad^2)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.papers import rotation_bias as rb
    >>> np.round(rb.residual_covariance(np.zeros(2), length=100, dt=0.1, gyro_noise=1e-4) * 1e12, 1)   # (1e-12 rad^2)
    array([[120024.,      0.],
           [     0., 120024.]])
    """
    M = tilt_matrix(tilt)  # validates tilt
    return _residual_cov(
        M, np.asarray(tilt, dtype=float)[..., 1], length, dt, gyro_noise, accel_noise, scalar(g, "g", positive=True)
    )


def _residual_cov(M, pitch, n, dt, N, A, g):
    """:func:`residual_covariance` of validated arguments, from the tilt matrices M and the dwell pitches."""
    j = np.arange(n)
    wts = (j - (n - 1) / 2) / (n * (n * n - 1) / 12.0)  # slope weights per sample index
    c = np.cumsum(wts[::-1])[::-1][1:]  # sum_{j>i} w_j, i = 0..n-2
    gyro_var = N**2 * dt * np.sum(c**2) * n**2  # (N^2/dt)(dt c)^2 summed, times n^2
    accel_var = A**2 / dt / g**2 * np.sum(wts**2) * n**2
    D = np.zeros(pitch.shape + (2, 2))
    D[..., 0, 0] = 1 / np.cos(pitch) ** 2
    D[..., 1, 1] = 1.0
    return gyro_var * M @ np.swapaxes(M, -1, -2) + accel_var * D


# --------------------------------------------------------------------------
# Eqs. (12)-(14): stacked least squares, batch and running
# --------------------------------------------------------------------------


def _rv(r: ArrayLike, V: ArrayLike) -> tuple[Array, Array]:
    r = as_array(r, "r", tail=(2,), min_ndim=1, allow_nan=True)
    V = as_array(V, "V", tail=(2, 3), min_ndim=1, allow_nan=True)
    if V.shape[:-2] != r.shape[:-1]:
        raise ValueError(f"V: expected shape {r.shape[:-1] + (2, 3)} to match r {r.shape}, got {V.shape}")
    return r, V


def lsq_bias(r: ArrayLike, V: ArrayLike) -> Array:
    r"""Eq. (14): :math:`\hat b = (V^T V)^{-1} V^T r` over all valid dwells.

    Parameters
    ----------
    r : array_like, shape (..., K, 2)
        Residuals (rad); NaN dwells (dropouts) are left out.
    V : array_like, shape (..., K, 2, 3)

    Returns
    -------
    b : ndarray, shape (..., 3)
        Bias estimate (rad/s).

    Raises
    ------
    ValueError
        If the valid dwells leave the bias unobservable (cond(V) > 1e6): the
        body verticals do not differ, e.g. a vertical rotation axis.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.papers import rotation_bias as rb
    >>> V = np.stack([np.eye(3)[:2], np.eye(3)[1:]])                 # two dwells that together see all three axes
    >>> b = np.array([1e-4, 2e-4, -1e-4])
    >>> np.round(rb.lsq_bias(V @ b, V) * 1e4, 6)
    array([ 1.,  2., -1.])
    """
    r, V = _rv(r, V)
    ok = np.all(np.isfinite(r), -1) & np.all(np.isfinite(V), (-2, -1))
    rz = np.where(ok[..., None], r, 0.0)
    Vz = np.where(ok[..., None, None], V, 0.0)
    A = np.einsum("...kij,...kil->...jl", Vz, Vz)
    y = np.einsum("...kij,...ki->...j", Vz, rz)
    cond = normal_condition(A)
    if np.any(cond > _MAX_COND):
        raise ValueError(
            f"V: the bias is not observable from these dwells (cond(V) = {np.max(cond):.3g}): their "
            "body verticals do not differ (is the rotation axis vertical?) or all dwells were dropped"
        )
    return np.linalg.solve(A, y[..., None])[..., 0]


def _lu_solve_into(a, b, ipiv):
    """``b = A^-1 b`` in place by LAPACK's dgesv (LU with partial pivoting): numba's ``np.linalg.solve(A, b)`` for a
    vector ``b``, the same routine on the same arguments (the same bits), without its generic implementation, whose
    slice assignment compiles numba's shape messages into the caller (2 s of a cold start).

    ``a`` (n, n): A in Fortran order (``np.empty((n, n)).T`` filled), ``b`` (n,); ``a`` and ``ipiv`` (n,) int32 are
    work (the LU factors and pivots). Raises ``LinAlgError`` if A is exactly singular, as ``np.linalg.solve`` does.
    Uncompiled (``NUMBA_DISABLE_JIT=1``) it calls the routine through scipy's wrapper.
    """
    _, _, b[:], info = scipy.linalg.lapack.dgesv(a, b)
    if info != 0:
        raise np.linalg.LinAlgError("Matrix is singular to machine precision.")


# dgesv from scipy.linalg.cython_lapack, where numba's np.linalg.solve takes it too. Called by name: the cached kernel
# holds the symbol, which this import binds in every process (a ctypes pointer would make the kernel uncachable).
binding.add_symbol("navlib_dgesv", get_cython_function_address("scipy.linalg.cython_lapack", "dgesv"))
_dgesv = types.ExternalFunction("navlib_dgesv", types.void(*(types.voidptr,) * 8))


@overload(_lu_solve_into)
def _lu_solve_into_compiled(a, b, ipiv):
    def impl(a, b, ipiv):
        dims = np.empty(3, dtype=np.int32)  # Fortran's integers by reference
        dims[0], dims[1], dims[2] = a.shape[0], 1, 0
        n, nrhs, info = dims.ctypes, dims[1:].ctypes, dims[2:].ctypes  # n is also both leading dimensions
        _dgesv(n, nrhs, a.ctypes, n, ipiv.ctypes, b.ctypes, n, info)  # type: ignore[call-overload]  # compiled only
        if dims[2] != 0:
            raise np.linalg.LinAlgError("Matrix is singular to machine precision.")

    return impl


@njit(cache=True)
def _running_kernel(r, V, lam, max_cond):
    T, K = r.shape[0], r.shape[1]
    out = np.full((T, K, 3), np.nan)
    skipped = 0
    a, b, ipiv = np.empty((3, 3)).T, np.empty(3), np.empty(3, dtype=np.int32)  # np.linalg.solve's work, by hand
    for t in range(T):
        A = np.zeros((3, 3))
        y = np.zeros(3)
        for k in range(K):
            A *= lam
            y *= lam
            Vk = V[t, k]
            if np.all(np.isfinite(r[t, k])) and np.all(np.isfinite(Vk)):
                A += Vk.T @ Vk
                y += Vk.T @ r[t, k]
            else:
                skipped += 1
            ev = np.linalg.eigvalsh(A)
            if ev[0] > 0 and ev[2] / ev[0] < max_cond * max_cond:
                for i in range(3):  # element by element: an array assignment compiles numba's shape messages
                    b[i] = y[i]
                    for j in range(3):
                        a[i, j] = A[i, j]
                _lu_solve_into(a, b, ipiv)
                for i in range(3):
                    out[t, k, i] = b[i]
    return out, skipped


@boundary
def running_lsq_bias(r: ArrayLike, V: ArrayLike, forgetting: Real = 1.0) -> tuple[Array, robust.FaultReport]:
    """Eq. (14) updated dwell by dwell (recursive least squares).

    After dwell k, ``b_k = (sum_i l^(k-i) V_i^T V_i)^-1 sum_i l^(k-i) V_i^T r_i``
    with forgetting factor ``l``; ``l = 1`` reproduces :func:`lsq_bias` on
    the first k dwells, ``l < 1`` tracks a slowly varying bias with a memory
    of about ``1 / (1 - l)`` dwells.

    Parameters
    ----------
    r : array_like, shape (..., K, 2)
        Residuals (rad); NaN dwells are skipped (counted).
    V : array_like, shape (..., K, 2, 3)
    forgetting : float
        In (0, 1].

    Returns
    -------
    b : ndarray, shape (..., K, 3)
        Estimate after each dwell (rad/s); NaN until the dwells so far make
        the bias observable (cond(V) <= 1e6).
    faults : FaultReport
        ``("dwell", "nan")``: dwells skipped for a NaN residual (int, over all trials).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.papers import rotation_bias as rb
    >>> V = np.stack([np.eye(3)[:2], np.eye(3)[1:], np.eye(3)[:2]])
    >>> b = np.array([1e-4, 2e-4, -1e-4])
    >>> est, found = rb.running_lsq_bias(V @ b, V)
    >>> np.round(est * 1e4, 6)                                        # NaN until the dwells observe every axis
    array([[nan, nan, nan],
           [ 1.,  2., -1.],
           [ 1.,  2., -1.]])
    """
    r, V = _rv(r, V)
    if not 0 < forgetting <= 1:
        raise ValueError(f"forgetting: expected a value in (0, 1], got {forgetting}")
    lead, K = r.shape[:-2], r.shape[-2]
    out, skipped = _running_kernel(kernel_array(r.reshape(-1, K, 2)), kernel_array(V.reshape(-1, K, 2, 3)), forgetting, _MAX_COND)
    return out.reshape(lead + (K, 3)), robust.FaultReport({("dwell", "nan"): int(skipped)})


# --------------------------------------------------------------------------
# Extension: Kalman filter with a random-walk bias state
# --------------------------------------------------------------------------


@dataclass(frozen=True)
class KalmanBias:
    """Output of :func:`kalman_bias`.

    Attributes
    ----------
    b : ndarray, shape (..., K, 3)
        Bias estimate after each dwell (rad/s).
    sigma : ndarray, shape (..., K, 3)
        Its standard deviation from the filter covariance (rad/s).
    faults : FaultReport
        Counts over all trials (ints): ``("dwell", "nan")`` dwells without a residual (dropouts,
        skipped dwells), predicted through; ``("dwell", "outlier")`` residuals rejected by the
        innovation gate.
    P : ndarray, shape (..., K, 3, 3)
        Covariance after each dwell (rad^2/s^2); symmetric positive definite
        (Joseph-form update, symmetrised predict).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.papers import rotation_bias as rb
    >>> V = np.stack([np.eye(3)[:2], np.eye(3)[1:]] * 3)            # six dwells
    >>> b = np.array([1e-4, 2e-4, -1e-4])
    >>> R = np.tile(1e-12 * np.eye(2), (6, 1, 1))
    >>> kb = rb.kalman_bias(V @ b, V, R, interval=10.0, rate_random_walk=1e-9, bias_sigma=1e-3)
    >>> kb.b.shape, np.round(kb.b[-1] * 1e4, 3)
    ((6, 3), array([ 1.,  2., -1.]))
    """

    b: np.ndarray
    sigma: np.ndarray
    faults: robust.FaultReport
    P: np.ndarray | None = None


@njit(cache=True)
def _kalman_kernel(r, V, R, qq, intervals, p0, gate):
    T, K = r.shape[0], r.shape[1]
    b = np.empty((T, K, 3))
    sig = np.empty((T, K, 3))
    Ps = np.empty((T, K, 3, 3))
    mask = np.zeros(2, dtype=np.bool_)
    no_data = rejected = 0
    for t in range(T):
        x = np.zeros(3)
        P = p0.copy()
        for k in range(K):
            if k > 0:  # random-walk bias, Phi = I: x stays, P += Q (kalman_predict's bits: I P I^T is exact, P symmetric)
                q = qq * intervals[k]
                for i in range(3):
                    for j in range(3):
                        P[i, j] += q if i == j else 0.0
            H = V[t, k]
            if np.all(np.isfinite(H)):
                x, P, _, _, status = _kernels.kalman_update(x, P, r[t, k], H @ x, H, R[t, k], mask, gate)
            else:  # a skipped dwell: no V either
                status = kalman.NO_DATA
            if status == kalman.NO_DATA:
                no_data += 1
            elif status == kalman.REJECTED:
                rejected += 1
            for i in range(3):  # element by element: an array assignment compiles numba's shape messages
                b[t, k, i] = x[i]
                sig[t, k, i] = np.sqrt(P[i, i])
                for j in range(3):
                    Ps[t, k, i, j] = P[i, j]
    return b, sig, no_data, rejected, Ps


@boundary
def kalman_bias(
    r: ArrayLike,
    V: ArrayLike,
    R: ArrayLike,
    interval: Interval,
    rate_random_walk: NonNegative,
    bias_sigma: Positive,
    gate: Positive = 13.8,
) -> KalmanBias:
    """Kalman filter on the dwell residuals with a random-walk bias state.

    State ``b`` (3); between dwells ``b_k = b_k-1 + w`` with
    ``cov(w) = K^2 interval_k I``; measurement ``delta_k = V_k b + v`` with
    ``cov(v) = R_k`` (:func:`residual_covariance`). NaN residuals (dropouts,
    skipped dwells) are predicted through and counted (``("dwell", "nan")``);
    residuals whose NIS exceeds ``gate`` are rejected and counted
    (``("dwell", "outlier")``), e.g. dwells hit by spikes when :func:`tilt_residuals`
    ran without ``outlier_k``. The covariance stays symmetric positive
    definite (Joseph form, symmetrised; returned as ``P``).

    Parameters
    ----------
    r : array_like, shape (..., K, 2)
    V : array_like, shape (..., K, 2, 3)
        NaN for skipped dwells.
    R : array_like, shape (..., K, 2, 2) or (K, 2, 2)
        Residual covariances (rad^2); NaN allowed only where r is NaN.
    interval : float or array_like, shape (K,)
        Time between dwells (s); an array gives the time from dwell k-1 to
        dwell k (entry 0 unused), e.g. ``np.diff(time[res.end], prepend=0)``
        for irregular or gappy timing.
    rate_random_walk : float
        Random-walk density K of the bias (rad/s/sqrt(s)).
    bias_sigma : float
        Initial standard deviation of each bias component (rad/s).
    gate : float
        NIS threshold (default: chi-square, 2 dof, 99.9 %).

    Returns
    -------
    KalmanBias

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.papers import rotation_bias as rb
    >>> V = np.stack([np.eye(3)[:2], np.eye(3)[1:]] * 3)            # six dwells
    >>> b = np.array([1e-4, 2e-4, -1e-4])
    >>> R = np.tile(1e-12 * np.eye(2), (6, 1, 1))                    # residual noise (rad^2)
    >>> kb = rb.kalman_bias(V @ b, V, R, interval=10.0, rate_random_walk=1e-9, bias_sigma=1e-3)
    >>> np.round(kb.b[-1] * 1e4, 3), bool((kb.sigma[-1] < kb.sigma[0]).all())   # the uncertainty shrinks
    (array([ 1.,  2., -1.]), True)
    """
    r, V = _rv(r, V)
    lead, K = r.shape[:-2], r.shape[-2]
    R = broadcast_to(as_array(R, "R", tail=(2, 2), allow_nan=True, nonempty=True), "R", lead + (K, 2, 2), of="r")
    ok = np.all(np.isfinite(r), -1)
    if np.any(~np.isfinite(R[ok])):
        raise ValueError("R: expected finite covariances wherever r is finite")
    gaps = positive(interval, "interval", nonempty=True)  # not sample_intervals(): it accepts huge values
    if gaps.ndim == 0:
        gaps = np.full(K, float(gaps))
    elif gaps.shape != (K,):
        raise ValueError(f"interval: expected a float or shape ({K},), got {gaps.shape}")
    b, sig, no_data, rejected, P = _kalman_kernel(
        kernel_array(r.reshape(-1, K, 2)),
        kernel_array(V.reshape(-1, K, 2, 3)),
        kernel_array(R.reshape(-1, K, 2, 2)),
        rate_random_walk * rate_random_walk,
        kernel_array(gaps),
        bias_sigma * bias_sigma * np.eye(3),
        gate,
    )
    faults = robust.FaultReport({("dwell", "nan"): int(no_data), ("dwell", "outlier"): int(rejected)})
    return KalmanBias(b.reshape(lead + (K, 3)), sig.reshape(lead + (K, 3)), faults, P.reshape(lead + (K, 3, 3)))


# --------------------------------------------------------------------------
# Observability
# --------------------------------------------------------------------------


@boundary
def design(
    hpr0: Angles,
    axis_b: Vec3,
    amplitude: float,
    dwell_time: float,
    dt: Step,
    gyro_noise: NonNegative,
    accel_noise: NonNegative = 0.0,
    n_dwells: int = 2,
) -> tuple[float, Array, Array]:
    """Observability of a rotation schedule without simulation.

    Builds V (Eq. 13) for ``n_dwells`` dwells of :func:`dwell_attitudes` and
    the residual covariances of :func:`residual_covariance`.

    Parameters
    ----------
    hpr0 : array_like, shape (3,)  (rad)
    axis_b : array_like, shape (3,)
        Unit rotation axis.
    amplitude : float
        Delta alpha (rad).
    dwell_time, dt : float  (s)
    gyro_noise, accel_noise : float
        White-noise densities (rad/s/sqrt(Hz), m/s^2/sqrt(Hz)).
    n_dwells : int

    Returns
    -------
    cond : float
        cond(V).
    crb : ndarray, shape (3, 3)
        Cramer-Rao bound (rad^2/s^2).
    V : ndarray, shape (n_dwells, 2, 3)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.papers import rotation_bias as rb
    >>> cond, V, R = rb.design([0.0, 0.0, 0.0], [0.0, 1.0, 0.0], np.pi / 2, 10.0, 0.01, 1e-4)
    >>> round(float(cond), 3), V.shape, R.shape                       # two dwells, 90 deg apart about y
    (1.414, (3, 3), (2, 2, 3))
    """
    hpr = dwell_attitudes(hpr0, axis_b, amplitude, n_dwells)
    n = int(round(scalar(dwell_time, "dwell_time", positive=True) / dt))
    if n < MIN_DWELL_SAMPLES:
        raise ValueError(f"dwell_time: dwell windows too short ({n} samples); expected at least {MIN_DWELL_SAMPLES}")
    M = tilt_matrix(hpr[:, [2, 1]])
    V = M * (n * dt)
    R = _residual_cov(M, hpr[:, 1], n, dt, gyro_noise, accel_noise, G0)
    return float(_lsq.condition_number(V)), _lsq.cramer_rao_bound(V, R, _MAX_COND), V


def eq1_matrix(hpr: Angles) -> Array:
    """Paper Eq. (1) as printed (reconstructed signs): R, mapping n to b.

    Parameters
    ----------
    hpr : array_like, shape (..., 3)
        ``[heading, pitch, roll]`` (rad).

    Returns
    -------
    R : ndarray, shape (..., 3, 3)
        Equals ``attitude.euler_to_dcm(hpr).T`` (erratum E001-01: heading clockwise).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude
    >>> from navlib.papers import rotation_bias as rb
    >>> hpr = np.deg2rad([30.0, 10.0, 5.0])
    >>> bool(np.allclose(rb.eq1_matrix(hpr), attitude.euler_to_dcm(hpr).T))   # R maps n to b: C_bn transposed
    True
    """
    h, p, r = np.moveaxis(euler_angles(as_array(hpr, "hpr", tail=(3,), nonempty=True)), -1, 0)
    ch, sh, cp, sp, cr, sr = np.cos(h), np.sin(h), np.cos(p), np.sin(p), np.cos(r), np.sin(r)
    rows = [
        [cr * ch + sr * sp * sh, -cr * sh + sr * sp * ch, -sr * cp],
        [cp * sh, cp * ch, sp],
        [sr * ch - cr * sp * sh, -sr * sh - cr * sp * ch, cr * cp],
    ]
    return np.stack([np.stack(row, -1) for row in rows], -2)


# --------------------------------------------------------------------------
# The chapter's experiment driver and schematics (notebook 02). Kept out of __all__: they serve the
# notebook (one pitch group of §4, the redrawn Figs. 3-4), not a reader's own data.
# --------------------------------------------------------------------------


@dataclass(frozen=True)
class Rig:
    """One simulated rig of the experiment: its motion, exact IMU samples and dwells (for :func:`rig_experiment`).

    Attributes
    ----------
    traj : navlib.trajectory.Trajectory
        The rig's motion (:func:`navlib.trajectory.reciprocating_rotation`).
    w_ib_b, f_b : array_like, shape (N, 3)
        Its exact IMU samples (:func:`navlib.trajectory.ideal_imu`).
    starts, length
        Dwell windows (:func:`dwell_windows`).
    w_ie_b : array_like, shape (K, 3)
        Earth rate in the body frame at each dwell (rad/s).
    """

    traj: Trajectory
    w_ib_b: Vec3Series
    f_b: Vec3Series
    starts: ArrayLike
    length: int
    w_ie_b: Vec3Series


@boundary
def rig_experiment(
    rig: Rig,
    dt: float,
    lat: float,
    model: ImuModel,
    rng: np.random.Generator,
    *,
    n_runs: Count,
    period: float,
    memory: float,
    extensions: bool = False,
    decimate: Count = 100,
) -> dict[str, Any]:
    """One pitch group of the paper's experiment (§4): ``n_runs`` noisy runs on one rig trajectory.

    Simulates ``model`` on the exact samples of ``traj`` (a few runs at a time, the same draws as all at once:
    :func:`navlib.sensors.simulate_imu_batches`, so the memory is that of a few runs), estimates
    the bias dwell by dwell with a running least squares of memory ``memory`` (s; forgetting factor
    ``exp(-period / memory)``) and integrates Eq. (2) with the raw gyros (*uncorrected*) and with each
    estimate subtracted from the end of its dwell on (*corrected*), both with Earth rate removed
    (E001-06). ``extensions`` adds a Kalman filter on the same residuals, the paper's own version
    (Earth rate neglected everywhere) and the same sensor errors on a static IMU (*no rotation*).

    Parameters
    ----------
    rig : Rig
        The rig's trajectory, exact samples and dwells.
    dt, lat : float
        Sample interval (s) and latitude (rad).
    model : navlib.sensors.ImuModel
        Sensor errors; the no-rotation case needs a model without scale-factor and misalignment errors.
    rng : numpy.random.Generator
    n_runs : int
    period, memory : float  (s)
    decimate : int
        Keep every ``decimate``-th sample of the error series returned for figures.

    Returns
    -------
    dict
        ``stats[case]`` with per-run ``max``, ``mean`` and ``final`` errors (°, runs x [heading, pitch, roll]),
        ``heading_err[case]`` (°, decimated), the estimates ``b_lsq`` at ``t_est``, the true bias, ``faults``
        of the residuals (:class:`Residuals`) and, with ``extensions``, ``kf_faults`` of the Kalman filter.
    """
    from .. import sensors, trajectory  # noqa: PLC0415 -- the driver alone needs them

    period, memory = scalar(period, "period", positive=True), scalar(memory, "memory", positive=True)
    if flag(extensions, "extensions") and (model.gyro.scale_factor != 0 or model.gyro.misalignment != 0):
        raise ValueError(
            "model: the no-rotation case reuses the sensor errors on a static IMU, which needs a gyro "
            "model without scale-factor and misalignment errors"
        )
    traj = rig.traj
    still = None  # the no-rotation case: a still IMU's exact gyro and attitude
    if extensions:
        static = trajectory.static(traj.time[-1], dt, [lat, 0, 0], traj.hpr[0])
        still = (trajectory.ideal_imu(static)[0], static.hpr)
    # The runs in batches of _RIG_BATCH, each simulated (the same draws as all at once), estimated, integrated
    # and reduced before the next: the memory of a batch of 1-h runs, not of all of them.
    batches = sensors.simulate_imu_batches(rig.w_ib_b, rig.f_b, dt, model, rng, n_runs, _RIG_BATCH)
    hpr_true = traj.hpr  # converted from the quaternions once, not per batch
    parts = [_rig_runs(rig, hpr_true, imu, dt, lat, model, np.exp(-period / memory), period, still, decimate) for imu in batches]
    out = {key: _joined([part[key] for part in parts]) for key in parts[0] if key != "t_est"}
    out.update(time=traj.time[::decimate], time_b=traj.time[:-1:decimate], t_est=parts[0]["t_est"])
    return out


_RIG_BATCH = 2
"""Runs per batch of :func:`rig_experiment` (its result does not depend on it)."""


def _rig_runs(
    rig: Rig,
    hpr_true: Array,
    imu: ImuOutput,
    dt: float,
    lat: float,
    model: ImuModel,
    forgetting: float,
    period: float,
    still: tuple[Array, Array] | None,
    decimate: int,
) -> dict[str, Any]:
    """:func:`rig_experiment` for the runs of one simulated batch ``imu`` (no time axes; ``t_est`` of the dwells);
    ``hpr_true`` is ``rig.traj.hpr``."""
    from .. import analysis, euler, units  # noqa: PLC0415 -- the driver alone needs them

    hpr0 = hpr_true[0]
    w_ie_n = earth.earth_rate_n(lat)
    res = tilt_residuals(imu.w_ib_b, imu.f_b, dt, rig.starts, rig.length, rig.w_ie_b)
    b_lsq, _ = running_lsq_bias(res.r, res.V, forgetting)
    gyro = imu.w_ib_b
    cases: dict[str, tuple[Array, Array | None, Array | None, Array]] = {
        "uncorrected": (gyro, w_ie_n, None, hpr_true),
        "corrected": (gyro, w_ie_n, b_lsq, hpr_true),
    }
    out: dict[str, Any] = {"faults": res.faults}
    if still is not None:
        R = residual_covariance(res.tilt, rig.length, dt, model.gyro.noise_density, model.accel.noise_density)
        rrw = np.sqrt(2 / model.gyro.correlation_time) * model.gyro.gauss_markov_sigma  # RW matching the GM drift
        kf = kalman_bias(res.r, res.V, R, period, rrw, np.hypot(model.gyro.bias, model.gyro.gauss_markov_sigma))
        res_paper = tilt_residuals(imu.w_ib_b, imu.f_b, dt, rig.starts, rig.length)  # Earth rate neglected
        b_paper, _ = running_lsq_bias(res_paper.r, res_paper.V, forgetting)
        w_still = gyro - np.asarray(rig.w_ib_b, dtype=float)  # the same sensor errors on a still IMU, summed in place (same bits)
        w_still += still[0]
        cases.update(
            {
                "Kalman": (gyro, w_ie_n, kf.b, hpr_true),
                "no rotation": (w_still, w_ie_n, None, still[1]),
                "paper uncorrected": (gyro, None, None, hpr_true),
                "paper corrected": (gyro, None, b_paper, hpr_true),
            }
        )
        out.update(kf_faults=kf.faults, b_kf=kf.b)
    out["stats"], out["heading_err"] = {}, {}
    for name, (w_case, w_in, b_hat, truth) in cases.items():
        hpr = euler.integrate_euler(hpr0, w_case, dt, w_in, b_hat, None if b_hat is None else res.end)
        mx, mean = analysis.error_statistics(hpr, truth)
        final = analysis.attitude_errors(hpr[:, -1], truth[-1])
        out["stats"][name] = {"max": units.to_deg(mx), "mean": units.to_deg(mean), "final": units.to_deg(final)}
        out["heading_err"][name] = units.to_deg(analysis.attitude_errors(hpr[:, ::decimate], truth[::decimate])[..., 0])
    out.update(
        b_lsq=b_lsq,
        t_est=rig.traj.time[res.end],
        b_true_at_est=imu.gyro_bias[:, res.end - 1],
        b_true=imu.gyro_bias[:, ::decimate].copy(),  # a copy: a view would keep the batch's bias alive
    )
    return out


def _joined(values: list[Any]) -> Any:
    """Per-batch results of :func:`_rig_runs` joined: arrays along the runs, fault counts summed, dicts per key."""
    first = values[0]
    if isinstance(first, dict):
        return {key: _joined([v[key] for v in values]) for key in first}
    if isinstance(first, robust.FaultReport):
        return robust.FaultReport({key: sum(v[key] for v in values) for key in first.counts})
    return np.concatenate(values, axis=0)


@boundary
def pair_spread(
    hpr0: Angles,
    axis_b: Vec3,
    amplitude: float,
    period: float,
    rotation_time: float,
    dt: float,
    lat: float,
    model: ImuModel,
    bias_b: Vec3,
    rng: np.random.Generator,
    *,
    n_runs: Count,
    duration: float,
) -> Array:
    """Per-axis standard deviation (rad/s) of the least-squares bias from each pair of dwells, by Monte Carlo.

    Simulates ``n_runs`` runs of ``duration`` seconds of the rig (:func:`navlib.trajectory.reciprocating_rotation`)
    with ``model``'s errors on top of a constant ``bias_b``, removes Earth rate, solves Eq. (14) for every
    consecutive pair of dwells and returns the spread of those estimates about ``bias_b``. Where the schedule
    cannot be estimated (pitch driven to ±90°, or V singular because the axis is vertical) it returns NaN:
    the quick counterpart of the Cramér–Rao bound of :func:`design` for the chapter's explorer.
    """
    from .. import sensors, trajectory  # noqa: PLC0415 -- the driver alone needs them

    bias_b = as_array(bias_b, "bias_b", shape=(3,))
    try:
        hpr_dw = dwell_attitudes(hpr0, axis_b, amplitude, 2)
        cond = design(hpr0, axis_b, amplitude, period - rotation_time, dt, model.gyro.noise_density)[0]
    except ValueError:  # pitch driven to ±90°: Eq. (2) is singular
        return np.full(3, np.nan)
    if not cond < _MAX_COND:  # the axis is vertical: the bias along it is unobservable
        return np.full(3, np.nan)
    traj = trajectory.reciprocating_rotation(duration, dt, [lat, 0, 0], hpr_dw[0], axis_b, amplitude, period, rotation_time)
    w, f = trajectory.ideal_imu(traj)
    starts, length = dwell_windows(w.shape[-2], dt, period, rotation_time)
    w_ie = earth.earth_rate_b(attitude.euler_to_dcm(hpr_dw[np.arange(starts.size) % 2]), lat)
    imu = sensors.simulate_imu(w + bias_b, f, dt, model, rng, n_trials=n_runs)
    res = tilt_residuals(imu.w_ib_b, imu.f_b, dt, starts, length, w_ie)
    k = res.r.shape[-2] // 2
    if k < 2:
        raise ValueError(f"duration: expected at least two pairs of dwells, got {k}")
    try:
        b = lsq_bias(res.r[:, : 2 * k].reshape(n_runs, k, 2, 2), res.V[:, : 2 * k].reshape(n_runs, k, 2, 2, 3))
    except ValueError:  # every dwell dropped (a faulty model)
        return np.full(3, np.nan)
    return (b - bias_b).reshape(-1, 3).std(axis=0)


def rotation_angle(C_bn: Dcm) -> Array:
    """Angle (rad) by which each attitude of ``C_bn`` (..., 3, 3) is turned from the first one (for the schedule figure)."""
    C = as_array(C_bn, "C_bn", shape=(None, 3, 3), nonempty=True)
    rel = np.swapaxes(C[:1], -1, -2) @ C
    return np.arccos(np.clip((np.trace(rel, axis1=-2, axis2=-1) - 1) / 2, -1.0, 1.0))


@boundary
def draw_rotation_scheme(
    ax: Axes,
    amplitude_deg: Annotated[float, Check("scalar", within=(0.0, 180.0), open_ends=(True, False))] = 90.0,
    pitch_deg: Annotated[float, Check("scalar", within=(-90.0, 90.0), open_ends=(True, True))] = 30.0,
) -> None:
    """Paper Fig. 3 redrawn: the IMU turned by Δα about u = y_b, seen along u.

    The plane of the drawing is perpendicular to u (u points into the page). Left, the body axes of
    dwell k (x_b, z_b, blue); right, those of the next dwell k' after the rotation (x_b', z_b', orange).
    The vertical (grey, dashed) is fixed in space, so the two dwells see it along body directions Δα
    apart: the bias component that one dwell cannot observe (along its body vertical) is seen by the other.

    Parameters
    ----------
    ax : matplotlib Axes
    amplitude_deg : float
        Δα (°), in (0, 180].
    pitch_deg : float
        θ0 (°), in (-90, 90): how far u = y_b is pitched out of the horizontal (only written on the figure).

    Examples
    --------
    >>> import matplotlib.pyplot as plt
    >>> from navlib.papers import rotation_bias as rb
    >>> fig, ax = plt.subplots()
    >>> rb.draw_rotation_scheme(ax, amplitude_deg=90.0)
    >>> len(ax.lines) + len(ax.patches) > 0
    True
    >>> plt.close(fig)
    """
    axes(ax)
    views = (
        ((0.0, 0.0), 0.0, ("$x_b$", "$z_b$"), "tab:blue", "dwell k"),
        ((3.0, 0.0), -amplitude_deg, ("$x_b'$", "$z_b'$"), "tab:orange", "dwell k′: turned by Δα"),
    )
    for (ox, oy), angle, names, color, title in views:
        ax.plot([ox, ox], [oy - 1.2, oy + 1.2], color="0.55", ls="--", lw=1)
        ax.text(ox, oy + 1.32, "vertical", color="0.45", ha="center", fontsize=8)
        _plots.plane_frame(ax, (ox, oy), angle, names, 1.0, color)
        ax.plot(ox, oy, "o", ms=11, mfc="white", mec="k", zorder=5)
        ax.plot(ox, oy, "x", ms=7, color="k", zorder=6)
        ax.text(ox, oy - 1.55, title, ha="center", fontsize=9, color=color)
    _plots.angle_arc(ax, views[1][0], 0.5, 90.0 - amplitude_deg, 90.0, "Δα", "0.25")
    ax.annotate("", (2.2, 0.9), (0.8, 0.9), arrowprops={"arrowstyle": "-|>", "color": "0.3", "connectionstyle": "arc3,rad=-0.3"})
    ax.text(1.5, 1.35, "rotate by Δα\nabout u", ha="center", fontsize=8)
    ax.text(1.5, -0.25, f"u = $y_b$ into the page\n(pitched up θ0 = {pitch_deg:g}°)", ha="center", va="top", fontsize=8)
    ax.set(xlim=(-1.4, 4.4), ylim=(-1.8, 2.0), aspect="equal")
    ax.set_axis_off()


@boundary
def draw_rotation_schedule(ax: Axes, time: Times, angle_deg: ArrayLike, starts: ArrayLike, length: Count, dt: Step) -> None:
    """The reciprocating schedule: rotation angle against time with the dwell windows shaded.

    Parameters
    ----------
    ax : matplotlib Axes
    time, angle_deg : array_like, shape (N,)
        Sample times (s) and the rig's rotation angle (°), e.g. from :func:`rotation_angle`.
    starts, length
        Dwell windows (:func:`dwell_windows`); alternate dwells are the two attitudes k and k'.
    dt : float
        Sample interval (s).

    Examples
    --------
    >>> import matplotlib.pyplot as plt
    >>> import numpy as np
    >>> from navlib import attitude, trajectory
    >>> from navlib.papers import rotation_bias as rb
    >>> traj = trajectory.reciprocating_rotation(40.0, 0.1, [0.5, 2.0, 0.0], [0.0, 0.0, 0.0], [0.0, 1.0, 0.0], np.pi / 2, 10.0)
    >>> angle = np.rad2deg(attitude.quat_to_euler(traj.q_bn)[:, 2])  # the roll angle follows the rotation about y
    >>> starts, length = rb.dwell_windows(len(traj) - 1, 0.1, period=10.0, rotation_time=1.0)
    >>> fig, ax = plt.subplots()
    >>> rb.draw_rotation_schedule(ax, traj.time, angle, starts, length, 0.1)
    >>> len(ax.patches)                                               # one shaded window per dwell
    4
    >>> plt.close(fig)
    """
    axes(ax)
    t = time_axis(time, "time")
    a = same_shape(as_array(angle_deg, "angle_deg"), "angle_deg", t.shape, of="time")
    starts = as_array(starts, "starts", nonempty=True)
    if starts.ndim != 1 or np.any(starts < 0) or np.any(starts != np.round(starts)):
        raise ValueError(f"starts: expected a 1-D array of sample indices >= 0 (dwell_windows), got shape {starts.shape}")
    ax.plot(t, a, color="k", lw=1.5)
    for k, s in enumerate(starts.astype(int)):
        ax.axvspan(s * dt, (s + length) * dt, color="tab:blue" if k % 2 == 0 else "tab:orange", alpha=0.15, lw=0)
        ax.text(
            (s + length / 2) * dt, a.max() * 1.06, f"dwell {k + 1}" + ("" if k % 2 == 0 else " (turned)"), ha="center", fontsize=8
        )
    ax.set(xlabel="time (s)", ylabel="rotation angle α (°)", ylim=(-0.1 * a.max(), 1.2 * a.max()))


def draw_flow(ax: Axes) -> None:
    """Paper Fig. 4 redrawn: the estimation and compensation loop (§3.3) as a block diagram.

    Examples
    --------
    >>> import matplotlib.pyplot as plt
    >>> from navlib.papers import rotation_bias as rb
    >>> fig, ax = plt.subplots()
    >>> rb.draw_flow(ax)
    >>> len(ax.texts) > 0
    True
    >>> plt.close(fig)
    """
    from ..plots import block_diagram  # noqa: PLC0415 -- plotting only (it validates ax)

    blocks = {
        "imu": (0.12, 0.72, "IMU\ngyros $\\tilde\\Omega$,\naccelerometers"),
        "dwell": (0.37, 0.72, "dwell k: tilt residual\n$r_k = V_k b$ (Eqs. 6–9)"),
        "rotate": (0.12, 0.25, "rig: rotate by ±Δα\nabout u every 5 s\n(Eqs. 10–11)"),
        "stack": (0.62, 0.72, "stack $r$, $V$\n(Eq. 13)"),
        "lsq": (0.87, 0.72, "least squares\n$\\hat b = (V^TV)^{-1}V^Tr$\n(Eq. 14)"),
        "int": (0.87, 0.25, "integrate Eq. (2)\nwith $\\tilde\\Omega - \\hat b$"),
        "att": (0.62, 0.25, "attitude\nψ, θ, φ"),
    }
    arrows = [
        ("imu", "dwell"),
        ("dwell", "stack"),
        ("stack", "lsq"),
        ("lsq", "int", "$\\hat b$"),
        ("int", "att"),
        ("rotate", "imu", "turns"),
    ]
    block_diagram(ax, blocks, arrows, width=0.2, height=0.2, colors={"imu": "#dbe9f6", "att": "#e3f1dc"})


def _warm_up() -> None:
    """Compile this module's kernels on a small rig, in the forms notebook 02 calls them (``python -m navlib.warmup
    --also navlib.papers.rotation_bias``, run by ``make reproduce`` before the notebooks)."""
    from .. import trajectory  # noqa: PLC0415 -- the warm-up alone needs it

    rig = trajectory.reciprocating_rotation(40.0, 0.1, [0.5, 2.0, 0.0], [0.0] * 3, [0.0, 1.0, 0.0], np.pi / 2, 10.0)
    w_ib_b, f_b = trajectory.ideal_imu(rig)
    starts, length = dwell_windows(len(w_ib_b), 0.1, period=10.0, rotation_time=1.0)
    w_ie_b = earth.earth_rate_b(attitude.quat_to_dcm(rig.q_bn[starts]), 0.5)
    res = tilt_residuals(w_ib_b, f_b, 0.1, starts, length, w_ie_b)
    running_lsq_bias(res.r, res.V)
    kalman_bias(res.r, res.V, np.tile(1e-12 * np.eye(2), (len(starts), 1, 1)), 10.0, 1e-9, 1e-3)
