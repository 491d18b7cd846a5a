"""Attitude from a MEMS IMU, a magnetometer and dual-antenna RTK heading (paper 003).

Zhang Q., Wu Z., Yun Q. (2023). Research on attitude measurement method based
on MIMU/magnetic sensor/dual antenna RTK. *Journal of Electronic Measurement
and Instrumentation* 37(5): 230-239. doi:10.13382/j.jemi.B2206027

Conventions are navlib's (ENU, right-front-up, ``q = q_b^n`` scalar first,
``hpr = [heading, pitch, roll]`` with heading clockwise from north). The
paper's counter-clockwise yaw is ``-heading``; its z-x-y Euler order is
navlib's, so Eq. (1) is :func:`navlib.attitude.euler_to_quat` and the
corrected Eq. (2) is :func:`navlib.attitude.quat_to_euler`.

Equations implemented (paper numbering, errata E003-nn corrected; see data/errata.csv)
--------------------------------------------------------------------------------------
Eq. (3)   reference directions ``a_n = [0, 0, 1]``, ``b = [0, cos I, -sin I]``
          (magnetic north; b normalised, ``b_u < 0`` in the north; E003-07):
          :func:`magnetic_reference`.
Eq. (4)   ``a = C_nb [0, 0, 1]`` with ``q0**2`` in the third row (E003-04), and
Eq. (6)   ``m = C_nb b`` with ``(q0^2 - q1^2 - q2^2 + q3^2) b_z`` in row 3 (E003-06):
          :func:`measurement_model`.
Eq. (5)   ``roll = atan2(-a_x, a_z)``, ``pitch = atan2(a_y, hypot(a_x, a_z))`` (E003-05);
Eq. (7)   levelled field ``m_h = R_x(pitch) R_y(roll) m_b`` and
          ``heading = atan2(-m_h,x, m_h,y)`` (E003-08);
Eq. (8)   replaced by Eq. (1) (E003-01): :func:`navlib.alignment.tilt_heading`, :func:`navlib.alignment.initial_attitude`.
Eqs. (9)-(15)  Mahony PI filter: ``e = a_meas x a_est + m_meas x m_est``
          (measured x estimated, hats restored, E003-09), ``m_est = C_nb [0, |h_xy|, h_z]``
          with ``h = C_bn m_meas`` (the magnetometer corrects heading only),
          ``w = w_m + Kp e + Ki sum(e dt)`` with Kp in rad/s and Ki in rad/s^2
          (the full cross product, not MahonyAHRS.c's half error "twoKp", E003-10):
          :func:`mahony`.
Eqs. (16)-(17) ``Phi = I + dt/2 Omega(w)`` with the PI-corrected rate: :func:`transition`.
Eq. (18)  ``Gamma = dt/2 Xi(q)`` (printed ``-dt Xi``, E003-11): :func:`noise_input`.
Eq. (19)  ``z = h(q) + v`` with innovation ``z - h(q_pred)``; the printed
          ``z - H q`` is wrong because ``H q = 2 h(q)`` (E003-12).
Eq. (20)  Jacobian with ``H44 = 2(q0 b_y + q1 b_z)`` (E003-13): :func:`measurement_jacobian`;
          the filter is :func:`quaternion_kf` (Joseph update from :mod:`navlib.kalman`).
Sec. 2.5  heading fusion, reconstructed (the paper gives no rule; E003-15, E003-16): while RTK is
          valid the offset ``delta = wrap(H_rtk - H_mag)`` is smoothed with
          ``delta += alpha wrap(delta_k - delta)`` per epoch and the output is
          the RTK heading (carried between 5 Hz epochs by the filter's heading
          increments); during outages the output is ``H_mag + delta`` with
          delta held. Validity is a flag; the value of an invalid epoch (the
          paper's 0) is never used: :func:`fuse_rtk_heading`.

Extensions: the magnetometer gate (field norm and dip angle against the
local field, :class:`MagGate`) and an accelerometer-norm gate. Every skipped
or gated update is counted in :attr:`AttitudeResult.counts`; NaN gyro samples
are replaced by the last valid one (counted), so a dropout never reaches the
state.

Robustness (what the filters do with bad data; all counted, keys :data:`COUNT_NAMES`)
------------------------------------------------------------------------------------
* dropouts and gaps (NaN): gyro -> hold the last used sample; accelerometer,
  magnetometer, RTK -> skip that correction (a gap is a run of these: the
  gyro alone carries the attitude);
* outliers: accelerometer -> ``accel_tol`` norm gate; magnetometer ->
  :class:`MagGate`; gyro -> ``gyro_jump`` spike gate (hold); RTK heading ->
  ``rtk_gate`` against the current heading estimate, so 180 deg ambiguity
  flips are rejected and never fused, with re-acquisition after
  ``rtk_confirm`` consistent epochs (a drifted estimate is pulled back). The
  gates are opt-in (defaults keep the paper's filter);
* timing: ``dt`` may be per-sample intervals of shape (N,) (irregular
  sampling, used in the compiled kernels); repeated or out-of-order
  timestamps go through :func:`navlib.timing.sanitize` first;
* saturation: with ``gyro_range``/``accel_range``/``mag_range`` samples at the
  rails are counted; accelerometer and magnetometer corrections are skipped
  for them, gyro samples are used (nothing better exists);
* the quaternion KF's covariance stays symmetric positive definite under all
  of these (skipped data never enters it; prediction and Joseph update are
  symmetrised); :func:`quaternion_kf` returns it (``keep_cov`` for every sample).

The filters are compiled per-sample kernels (numba, allocation-free for
Mahony); leading axes of the inputs are Monte Carlo trials, split over one
thread per core (the kernels release the GIL).
"""
from __future__ import annotations

import os
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np
from numba import njit

from .. import attitude, earth, kalman
from .._kernels import wrap_pi
from .._validate import as_quat, flag, in_range, intervals, nonempty_array, scalar
from ..attitude import quat_mult_t

__all__ = ["MagGate", "AttitudeResult", "COUNT_NAMES", "magnetic_reference", "transition", "noise_input",
           "measurement_model", "measurement_jacobian", "mahony", "quaternion_kf", "fuse_rtk_heading",
           "rtk_at_imu_rate", "printed_eq2_roll", "printed_eq4", "printed_eq5_tilt", "printed_eq7_heading",
           "printed_eq8_quat", "printed_eq18_gamma", "printed_eq20_jacobian"]

COUNT_NAMES = ("gyro_held", "accel_skipped", "accel_gated", "mag_skipped", "mag_gated", "gyro_saturated",
               "accel_saturated", "mag_saturated", "rtk_dropped", "rtk_rejected", "rtk_reacquired", "gyro_gated")
"""Keys of :attr:`AttitudeResult.counts`, one count per trial:

``gyro_held``
    NaN gyro samples, replaced by the last used sample (hold).
``accel_skipped``, ``accel_gated``
    Accelerometer samples unusable (NaN, inf, zero: the correction is
    skipped) or outside ``accel_tol`` (skipped).
``mag_skipped``, ``mag_gated``
    Heading-reference samples unusable (magnetometer NaN, inf, zero or
    parallel to gravity; in RTK mode, no used RTK epoch within ``rtk_hold``)
    or outside the :class:`MagGate` (skipped).
``gyro_saturated``
    Gyro samples with a component at the rails (``|w| >= gyro_range``): used
    (unless the spike gate holds them; counted either way), because nothing
    better exists, but the attitude after them is suspect.
``accel_saturated``, ``mag_saturated``
    Accelerometer / magnetometer samples at the rails (``accel_range``,
    ``mag_range``): their correction is skipped (not also counted as skipped).
``rtk_dropped``
    Valid-flagged RTK epochs holding NaN: ignored.
``rtk_rejected``
    RTK epochs further than ``rtk_gate`` from the current heading estimate
    (e.g. 180 deg ambiguity flips): never fused.
``rtk_reacquired``
    RTK epochs used although outside ``rtk_gate``, because ``rtk_confirm``
    consecutive epochs agreed with each other: the estimate, not the RTK, was
    wrong (e.g. after a long outage without bias estimation).
``gyro_gated``
    Gyro spikes: samples differing from the last used one by more than
    ``gyro_jump`` on some axis, replaced by it (hold); a second such sample in a
    row is used (a sustained change is motion).
"""


# --------------------------------------------------------------------------
# Reference field, initial attitude (Eqs. 3-8)
# --------------------------------------------------------------------------

def magnetic_reference(B_n):
    """Normalised magnetic reference ``b = [0, cos I, -sin I]`` (Eq. 3) and the field's angles.

    Parameters
    ----------
    B_n : array_like, shape (3,)
        Local field in ENU (uT), e.g. :func:`navlib.earth.magnetic_field`.

    Returns
    -------
    b : ndarray, shape (3,)
        Unit field in the magnetic-north frame.
    declination, inclination, intensity : float
        D (rad, east positive), I (rad, down positive), F (uT).
    """
    B = nonempty_array(B_n, "B_n", tail=(3,))
    if B.shape != (3,) or np.linalg.norm(B) == 0:
        raise ValueError(f"B_n: expected one non-zero field vector of shape (3,), got {B.tolist()}")
    D, I, F = earth.field_angles(B, deg=False)
    return np.array([0.0, np.cos(I), -np.sin(I)]), float(D), float(I), float(F)


# --------------------------------------------------------------------------
# Quaternion Kalman filter model (Eqs. 16-20): per-sample helpers + public wrappers
# --------------------------------------------------------------------------

@njit(cache=True, inline="always")
def _phi_into(Phi, wx, wy, wz, dt):
    """Eq. (17): Phi = I + dt/2 Omega(w)."""
    c = 0.5 * dt
    Phi[0, 0], Phi[0, 1], Phi[0, 2], Phi[0, 3] = 1.0, -c * wx, -c * wy, -c * wz
    Phi[1, 0], Phi[1, 1], Phi[1, 2], Phi[1, 3] = c * wx, 1.0, c * wz, -c * wy
    Phi[2, 0], Phi[2, 1], Phi[2, 2], Phi[2, 3] = c * wy, -c * wz, 1.0, c * wx
    Phi[3, 0], Phi[3, 1], Phi[3, 2], Phi[3, 3] = c * wz, c * wy, -c * wx, 1.0


@njit(cache=True, inline="always")
def _gamma_into(G, q, dt):
    """Eq. (18) corrected: Gamma = dt/2 Xi(q)."""
    c = 0.5 * dt
    q0, q1, q2, q3 = q[0], q[1], q[2], q[3]
    G[0, 0], G[0, 1], G[0, 2] = -c * q1, -c * q2, -c * q3
    G[1, 0], G[1, 1], G[1, 2] = c * q0, -c * q3, c * q2
    G[2, 0], G[2, 1], G[2, 2] = c * q3, c * q0, -c * q1
    G[3, 0], G[3, 1], G[3, 2] = -c * q2, c * q1, c * q0


@njit(cache=True, inline="always")
def _h_into(h, q, by, bz):
    """Eqs. (4), (6) corrected: h(q) = [C_nb [0,0,1]; C_nb [0, by, bz]]."""
    q0, q1, q2, q3 = q[0], q[1], q[2], q[3]
    h[0] = 2 * (q1 * q3 - q0 * q2)
    h[1] = 2 * (q2 * q3 + q0 * q1)
    h[2] = q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3
    h[3] = 2 * (q1 * q2 + q0 * q3) * by + 2 * (q1 * q3 - q0 * q2) * bz
    h[4] = (q0 * q0 - q1 * q1 + q2 * q2 - q3 * q3) * by + 2 * (q2 * q3 + q0 * q1) * bz
    h[5] = 2 * (q2 * q3 - q0 * q1) * by + (q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3) * bz


@njit(cache=True, inline="always")
def _jacobian_into(H, q, by, bz):
    """Eq. (20) with the corrected H44 = 2(q0 by + q1 bz)."""
    q0, q1, q2, q3 = q[0], q[1], q[2], q[3]
    H[0, 0], H[0, 1], H[0, 2], H[0, 3] = -2 * q2, 2 * q3, -2 * q0, 2 * q1
    H[1, 0], H[1, 1], H[1, 2], H[1, 3] = 2 * q1, 2 * q0, 2 * q3, 2 * q2
    H[2, 0], H[2, 1], H[2, 2], H[2, 3] = 2 * q0, -2 * q1, -2 * q2, 2 * q3
    u, v, s, r = q3 * by - q2 * bz, q2 * by + q3 * bz, q1 * by - q0 * bz, q0 * by + q1 * bz
    H[3, 0], H[3, 1], H[3, 2], H[3, 3] = 2 * u, 2 * v, 2 * s, 2 * r
    H[4, 0], H[4, 1], H[4, 2], H[4, 3] = 2 * r, -2 * s, 2 * v, -2 * u
    H[5, 0], H[5, 1], H[5, 2], H[5, 3] = -2 * s, -2 * r, 2 * u, 2 * v


@njit(cache=True)
def _model_rows(q, b, out_h, out_H):
    for i in range(q.shape[0]):
        _h_into(out_h[i], q[i], b[i, 1], b[i, 2])
        _jacobian_into(out_H[i], q[i], b[i, 1], b[i, 2])


def _model(q, b):
    q = nonempty_array(q, "q", tail=(4,))
    b = nonempty_array(b, "b", tail=(3,))
    if np.any(b[..., 0] != 0):
        raise ValueError("b: expected reference vectors [0, b_y, b_z] (Eq. 3, magnetic north)")
    lead = np.broadcast_shapes(q.shape[:-1], b.shape[:-1])
    qf = np.ascontiguousarray(np.broadcast_to(q, lead + (4,)).reshape(-1, 4))
    bf = np.ascontiguousarray(np.broadcast_to(b, lead + (3,)).reshape(-1, 3))
    h, H = np.empty((qf.shape[0], 6)), np.empty((qf.shape[0], 6, 4))
    _model_rows(qf, bf, h, H)
    return h.reshape(lead + (6,)), H.reshape(lead + (6, 4))


def measurement_model(q, b):
    """Predicted normalised measurement h(q) (Eqs. 4, 6 corrected; Eq. 19).

    Parameters
    ----------
    q : array_like, shape (..., 4)
        Quaternion q_b^n (the magnetic-north frame for the magnetometer rows).
    b : array_like, shape (..., 3)
        Reference ``[0, b_y, b_z]`` (Eq. 3).

    Returns
    -------
    h : ndarray, shape (..., 6)
        ``[C_nb [0, 0, 1]; C_nb b]``.
    """
    return _model(q, b)[0]


def measurement_jacobian(q, b):
    """Jacobian ``H = dh/dq`` of :func:`measurement_model` (Eq. 20, H44 corrected); (..., 6, 4)."""
    return _model(q, b)[1]


def transition(w, dt: float):
    """Quaternion transition ``Phi = I + dt/2 Omega(w)`` (Eq. 17); w (..., 3) rad/s -> (..., 4, 4)."""
    w = nonempty_array(w, "w", tail=(3,))
    dt = scalar(dt, "dt", positive=True)
    c = 0.5 * dt
    wx, wy, wz = np.moveaxis(w, -1, 0)
    o = np.ones_like(wx)
    rows = [[o, -c * wx, -c * wy, -c * wz], [c * wx, o, c * wz, -c * wy],
            [c * wy, -c * wz, o, c * wx], [c * wz, c * wy, -c * wx, o]]
    return np.stack([np.stack(r, -1) for r in rows], -2)


def noise_input(q, dt: float):
    """Gyro-noise input matrix ``Gamma = dt/2 Xi(q)`` (Eq. 18 corrected, E003-11); (..., 4) -> (..., 4, 3)."""
    q = nonempty_array(q, "q", tail=(4,))
    dt = scalar(dt, "dt", positive=True)
    q0, q1, q2, q3 = np.moveaxis(q, -1, 0)
    rows = [[-q1, -q2, -q3], [q0, -q3, q2], [q3, q0, -q1], [-q2, q1, q0]]
    return dt / 2 * np.stack([np.stack(r, -1) for r in rows], -2)


# --------------------------------------------------------------------------
# The printed equations, kept to show the errata (never used by the filters)
# --------------------------------------------------------------------------

def printed_eq2_roll(q):
    """Roll as printed in Eq. (2): ``atan(-2(q1 q3 + q0 q2) / (1 - 2(q1^2 + q2^2)))`` (E003-02)."""
    q0, q1, q2, q3 = np.moveaxis(nonempty_array(q, "q", tail=(4,)), -1, 0)
    return np.arctan(-2 * (q1 * q3 + q0 * q2) / (1 - 2 * (q1 ** 2 + q2 ** 2)))


def printed_eq4(q):
    """Eq. (4) as printed, with ``q0`` instead of ``q0**2`` in the third row (E003-04); (..., 4) -> (..., 3)."""
    q0, q1, q2, q3 = np.moveaxis(nonempty_array(q, "q", tail=(4,)), -1, 0)
    return np.stack([2 * (q1 * q3 - q0 * q2), 2 * (q2 * q3 + q0 * q1), q0 + q3 ** 2 - q1 ** 2 - q2 ** 2], -1)


def printed_eq5_tilt(f_b):
    """Eq. (5) as printed, ``roll = atan(a_x / hypot(a_y, a_z))``, ``pitch = atan(-a_y / a_z)`` (E003-05).

    Returns (pitch, roll).
    """
    a = nonempty_array(f_b, "f_b", tail=(3,))
    return np.arctan(-a[..., 1] / a[..., 2]), np.arctan(a[..., 0] / np.hypot(a[..., 1], a[..., 2]))


def printed_eq7_heading(m_h):
    """Eq. (7) as printed, ``atan(m_x / m_y)`` of the levelled field (the CCW yaw, E003-08)."""
    m = nonempty_array(m_h, "m_h", tail=(3,))
    return np.arctan(m[..., 0] / m[..., 1])


def printed_eq8_quat(hpr):
    """Eq. (8) as printed, with its yaw psi = -heading: ``q_z(psi) q_y(roll) q_x(pitch)`` (E003-01)."""
    h, p, r = np.moveaxis(nonempty_array(hpr, "hpr", tail=(3,)), -1, 0)
    def axis_quat(a, i):
        return np.stack([np.cos(a / 2)] + [np.sin(a / 2) * (i == j) for j in range(3)], -1)

    return attitude.quat_mult(attitude.quat_mult(axis_quat(-h, 2), axis_quat(r, 1)), axis_quat(p, 0))


def printed_eq18_gamma(q, dt: float):
    """Gamma as printed in Eq. (18): ``-dt Xi(q)`` (E003-11)."""
    return -2 * noise_input(q, dt)


def printed_eq20_jacobian(q, b):
    """Eq. (20) as printed: H44 = 2(q0 b_y - q1 b_z) (E003-13)."""
    H = measurement_jacobian(q, b).copy()
    q, b = nonempty_array(q, "q", tail=(4,)), nonempty_array(b, "b", tail=(3,))
    H[..., 3, 3] = 2 * (q[..., 0] * b[..., 1] - q[..., 1] * b[..., 2])
    return H


# --------------------------------------------------------------------------
# Per-sample kernel helpers (scalar tuples, allocation-free)
# --------------------------------------------------------------------------

@njit(cache=True, inline="always")
def _accel_obs(fx, fy, fz, lo2, hi2):
    """Unit accelerometer vector and a code: 0 used, 1 unusable, 2 gated (norm test)."""
    n2 = fx * fx + fy * fy + fz * fz
    if not (n2 > 0.0 and n2 < np.inf):
        return 0.0, 0.0, 0.0, 1
    if n2 < lo2 or n2 > hi2:
        return 0.0, 0.0, 0.0, 2
    s = 1.0 / np.sqrt(n2)
    return fx * s, fy * s, fz * s, 0


@njit(cache=True, inline="always")
def _mag_obs(mx, my, mz, ax, ay, az, a_code, gate):
    """Unit magnetometer vector and a code (0 used, 1 unusable, 2 gated by norm or dip angle).

    ``gate = [|m|^2 low, |m|^2 high, sin(dip) low, sin(dip) high]``; the dip is
    measured against the accelerometer's up direction when that is usable.
    """
    n2 = mx * mx + my * my + mz * mz
    if not (n2 > 0.0 and n2 < np.inf):
        return 0.0, 0.0, 0.0, 1
    s = 1.0 / np.sqrt(n2)
    ux, uy, uz = mx * s, my * s, mz * s
    if a_code == 0:
        sin_dip = -(ax * ux + ay * uy + az * uz)
        if 1.0 - sin_dip * sin_dip < 1e-12:           # parallel to gravity: no heading
            return 0.0, 0.0, 0.0, 1
        if sin_dip < gate[2] or sin_dip > gate[3]:
            return 0.0, 0.0, 0.0, 2
    if n2 < gate[0] or n2 > gate[1]:
        return 0.0, 0.0, 0.0, 2
    return ux, uy, uz, 0


@njit(cache=True, inline="always")
def _dcm_t(q0, q1, q2, q3):
    """The nine elements of C_b^n, row by row."""
    return (q0 * q0 + q1 * q1 - q2 * q2 - q3 * q3, 2 * (q1 * q2 - q0 * q3), 2 * (q1 * q3 + q0 * q2),
            2 * (q1 * q2 + q0 * q3), q0 * q0 - q1 * q1 + q2 * q2 - q3 * q3, 2 * (q2 * q3 - q0 * q1),
            2 * (q1 * q3 - q0 * q2), 2 * (q2 * q3 + q0 * q1), q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3)


@njit(cache=True, inline="always")
def _rtk_north(C31, C32, C33, sh, ch):
    """Mode (a) of Fig. 4: RTK heading as body-frame north ``C_nb(H_rtk, pitch_est, roll_est) [0, 1, 0]``."""
    cp = np.sqrt(C31 * C31 + C33 * C33)
    sr, cr = -C31 / cp, C33 / cp
    return -sh * cr + ch * C32 * sr, ch * cp, -sh * sr - ch * C32 * cr


@njit(cache=True, inline="always")
def _pi_error(C, ax, ay, az, a_ok, mx, my, mz, m_ok):
    """Eqs. (12)-(14): e = a_meas x a_est + m_meas x m_est (measured x estimated)."""
    C11, C12, C13, C21, C22, C23, C31, C32, C33 = C
    ex = ey = ez = 0.0
    if a_ok:
        ex += ay * C33 - az * C32
        ey += az * C31 - ax * C33
        ez += ax * C32 - ay * C31
    if m_ok:
        hx = C11 * mx + C12 * my + C13 * mz           # h = C_bn m (Mahony: rebuild b from h)
        hy = C21 * mx + C22 * my + C23 * mz
        hz = C31 * mx + C32 * my + C33 * mz
        bn = np.sqrt(hx * hx + hy * hy)
        vx = bn * C21 + hz * C31                      # m_est = C_nb [0, bn, hz]
        vy = bn * C22 + hz * C32
        vz = bn * C23 + hz * C33
        ex += my * vz - mz * vy
        ey += mz * vx - mx * vz
        ez += mx * vy - my * vx
    return ex, ey, ez


@njit(cache=True, inline="always")
def _heading_of(C12, C22):
    return np.arctan2(C12, C22)


@njit(cache=True, inline="always")
def _rtk_gate(h, predicted, gate, confirm, state):
    """Gate one RTK epoch against the predicted heading: 0 use, 1 reject, 2 use (re-acquired).

    An epoch within ``gate`` (rad) of ``predicted`` is used. One outside is
    rejected (a 180 deg ambiguity flip, a wrong fix) unless it is the
    ``confirm``-th in a row of rejected epochs that agree with each other
    within ``gate``: then the reference, not the epoch, is taken to be wrong
    and the epoch is used. ``state = [run length, heading of the last rejected epoch]``.
    """
    if abs(wrap_pi(h - predicted)) <= gate:
        state[0] = 0.0
        return 0
    if state[0] > 0.0 and abs(wrap_pi(h - state[1])) <= gate:
        state[0] += 1.0
    else:
        state[0] = 1.0
    state[1] = h
    return 2 if state[0] >= confirm else 1


@njit(cache=True, inline="always")
def _observe(t, k, q0, q1, q2, q3, f, m, hdg, hdg_ok, use_rtk, gates, rtk_par, dtk, rtk, counts):
    """Read sample k of trial t: unit accelerometer vector and unit heading reference, counting skips.

    The heading reference is the magnetometer, or with ``use_rtk`` the RTK
    north pseudo-vector; ``rtk = [sin H, cos H, heading estimate at the epoch,
    age (s), gate run length, last rejected heading]`` of the last used RTK
    epoch is updated in place; ``rtk_par = [hold (s), gate (rad), confirm
    (epochs)]``. Saturated accelerometer and magnetometer samples arrive here
    as NaN (set by :func:`_prepare`, which counts them). Returns
    (ax, ay, az, a_ok, mx, my, mz, m_ok, C) with C the nine elements of C_b^n(q).
    """
    C = _dcm_t(q0, q1, q2, q3)
    ax, ay, az, ca = _accel_obs(f[t, k, 0], f[t, k, 1], f[t, k, 2], gates[0], gates[1])
    if ca > 0:
        counts[t, ca] += 1
    if use_rtk:
        rtk[3] += dtk
        if hdg_ok[t, k]:
            hk = hdg[t, k]
            if np.isnan(hk):                                           # valid flag but no value: dropout
                counts[t, 8] += 1
            else:
                est = _heading_of(C[1], C[4])
                code = _rtk_gate(hk, est, rtk_par[1], rtk_par[2], rtk[4:6])
                if code == 1:
                    counts[t, 9] += 1
                else:
                    if code == 2:
                        counts[t, 10] += 1
                    rtk[0], rtk[1], rtk[2], rtk[3] = np.sin(hk), np.cos(hk), est, 0.0
        if rtk[3] <= rtk_par[0] and C[6] * C[6] + C[8] * C[8] > 1e-12:     # (no heading at pitch +-90 deg)
            # carry the epoch's heading forward with the estimate's own heading change
            d = _heading_of(C[1], C[4]) - rtk[2]
            sd, cd = np.sin(d), np.cos(d)
            mx, my, mz = _rtk_north(C[6], C[7], C[8], rtk[0] * cd + rtk[1] * sd, rtk[1] * cd - rtk[0] * sd)
            cm = 0
        else:
            mx, my, mz, cm = 0.0, 0.0, 0.0, 1
    else:
        mx, my, mz, cm = _mag_obs(m[t, k, 0], m[t, k, 1], m[t, k, 2], ax, ay, az, ca, gates[2:])
    if cm > 0:
        counts[t, 2 + cm] += 1
    return ax, ay, az, ca == 0, mx, my, mz, cm == 0, C


@njit(cache=True, inline="always")
def _gyro(t, k, w, gx, gy, gz, held, jump, counts):
    """Gyro sample k, or the last used one (gx, gy, gz) if it is NaN or a spike (counted).

    A spike (only when ``jump > 0``) is a sample differing from the last used
    one by more than ``jump`` on some axis, unless the previous sample was
    already held (``held``): a sustained change is motion, not a spike.
    Returns (wx, wy, wz, held).
    """
    wx, wy, wz = w[t, k, 0], w[t, k, 1], w[t, k, 2]
    if not (np.isfinite(wx) and np.isfinite(wy) and np.isfinite(wz)):
        counts[t, 0] += 1
        return gx, gy, gz, held
    if jump > 0.0 and not held and k > 0 and (abs(wx - gx) > jump or abs(wy - gy) > jump or abs(wz - gz) > jump):
        counts[t, 11] += 1
        return gx, gy, gz, True
    return wx, wy, wz, False


# --------------------------------------------------------------------------
# Kernels
# --------------------------------------------------------------------------

@njit(cache=True, nogil=True)
def _mahony_kernel(t0, t1, q_init, w, f, m, hdg, hdg_ok, use_rtk, dts, kp, ki, gates, jump, rtk_par,
                   q_out, bias_out, counts):
    for t in range(t0, t1):
        _mahony_trial(t, q_init, w, f, m, hdg, hdg_ok, use_rtk, dts, kp, ki, gates, jump, rtk_par,
                      q_out, bias_out, counts)


@njit(cache=True)
def _mahony_trial(t, q_init, w, f, m, hdg, hdg_ok, use_rtk, dts, kp, ki, gates, jump, rtk_par,
                  q_out, bias_out, counts):
    q0, q1, q2, q3 = q_init[t, 0], q_init[t, 1], q_init[t, 2], q_init[t, 3]
    gx = gy = gz = 0.0
    ix = iy = iz = 0.0
    held = False
    rtk = np.array([0.0, 1.0, 0.0, np.inf, 0.0, 0.0])
    for k in range(w.shape[1]):
        dt = dts[k]
        gx, gy, gz, held = _gyro(t, k, w, gx, gy, gz, held, jump, counts)
        ax, ay, az, a_ok, mx, my, mz, m_ok, C = _observe(t, k, q0, q1, q2, q3, f, m, hdg, hdg_ok, use_rtk,
                                                       gates, rtk_par, dt, rtk, counts)
        ex, ey, ez = _pi_error(C, ax, ay, az, a_ok, mx, my, mz, m_ok)
        ix += ex * dt                                                  # Eq. (15)
        iy += ey * dt
        iz += ez * dt
        wx, wy, wz = gx + kp * ex + ki * ix, gy + kp * ey + ki * iy, gz + kp * ez + ki * iz
        d0, d1, d2, d3 = quat_mult_t(q0, q1, q2, q3, 0.0, wx, wy, wz)  # Eq. (17): q + dt/2 q (x) [0, w]
        q0, q1, q2, q3 = q0 + 0.5 * dt * d0, q1 + 0.5 * dt * d1, q2 + 0.5 * dt * d2, q3 + 0.5 * dt * d3
        s = 1.0 / np.sqrt(q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3)
        q0, q1, q2, q3 = q0 * s, q1 * s, q2 * s, q3 * s
        q_out[t, k, 0], q_out[t, k, 1], q_out[t, k, 2], q_out[t, k, 3] = q0, q1, q2, q3
    bias_out[t, 0], bias_out[t, 1], bias_out[t, 2] = -ki * ix, -ki * iy, -ki * iz


@njit(cache=True, nogil=True)
def _kf_kernel(t0, t1, q_init, w, f, m, hdg, hdg_ok, use_rtk, dts, kp, ki, gates, jump, rtk_par, b_ref, sigmas,
               p0, linear_innovation, q_out, bias_out, counts, P_out, P_hist):
    for t in range(t0, t1):
        _kf_trial(t, q_init, w, f, m, hdg, hdg_ok, use_rtk, dts, kp, ki, gates, jump, rtk_par, b_ref, sigmas, p0,
                  linear_innovation, q_out, bias_out, counts, P_out, P_hist)


@njit(cache=True)
def _kf_trial(t, q_init, w, f, m, hdg, hdg_ok, use_rtk, dts, kp, ki, gates, jump, rtk_par, b_ref, sigmas, p0,
              linear_innovation, q_out, bias_out, counts, P_out, P_hist):
    N = w.shape[1]
    keep = P_hist.shape[1] == N
    sg, sa, sm = sigmas[0], sigmas[1], sigmas[2]
    by, bz = b_ref[1], b_ref[2]
    x = q_init[t].copy()
    P = p0 * np.eye(4)
    Qg = sg * sg * np.eye(3)
    R = np.diag(np.array([sa * sa, sa * sa, sa * sa, sm * sm, sm * sm, sm * sm]))
    Phi, G, z, h, H = np.empty((4, 4)), np.empty((4, 3)), np.empty(6), np.empty(6), np.empty((6, 4))
    no_angles = np.zeros(6, dtype=np.bool_)
    gx = gy = gz = 0.0
    held = False
    rtk = np.array([0.0, 1.0, 0.0, np.inf, 0.0, 0.0])
    ix = iy = iz = 0.0
    for k in range(N):
        dt = dts[k]
        gx, gy, gz, held = _gyro(t, k, w, gx, gy, gz, held, jump, counts)
        ax, ay, az, a_ok, mx, my, mz, m_ok, C = _observe(t, k, x[0], x[1], x[2], x[3], f, m, hdg, hdg_ok,
                                                       use_rtk, gates, rtk_par, dt, rtk, counts)
        ex, ey, ez = _pi_error(C, ax, ay, az, a_ok, mx, my, mz, m_ok)   # PI-corrected rate, Eq. (15)
        ix += ex * dt
        iy += ey * dt
        iz += ez * dt
        _phi_into(Phi, gx + kp * ex + ki * ix, gy + kp * ey + ki * iy, gz + kp * ez + ki * iz, dt)
        _gamma_into(G, x, dt)
        x, P = kalman.predict(x, P, Phi, G @ Qg @ np.ascontiguousarray(G.T))     # Eqs. (16)-(18)
        z[0], z[1], z[2] = (ax, ay, az) if a_ok else (np.nan, np.nan, np.nan)
        z[3], z[4], z[5] = (mx, my, mz) if m_ok else (np.nan, np.nan, np.nan)
        _jacobian_into(H, x, by, bz)                                        # Eq. (20)
        if linear_innovation:
            h[:] = H @ x                                                    # printed Eq. (19): wrong (E003-12)
        else:
            _h_into(h, x, by, bz)                                           # z - h(q), Eq. (19) corrected
        x, P, _, _, _ = kalman.update(x, P, z, h, H, R, no_angles)
        x = x / np.sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2] + x[3] * x[3])
        q_out[t, k, 0], q_out[t, k, 1], q_out[t, k, 2], q_out[t, k, 3] = x[0], x[1], x[2], x[3]
        if keep:
            P_hist[t, k] = P
    bias_out[t, 0], bias_out[t, 1], bias_out[t, 2] = -ki * ix, -ki * iy, -ki * iz
    P_out[t] = P


@njit(cache=True)
def _fuse_kernel(h_mag, h_rtk, ok, dts, alpha, rtk_par, out, delta_out, counts):
    T, N = h_mag.shape
    hold, gate, confirm = rtk_par[0], rtk_par[1], rtk_par[2]
    state = np.zeros(2)
    for t in range(T):
        delta, age, anchor_rtk, anchor_mag = np.nan, np.inf, 0.0, 0.0
        state[0] = 0.0
        for k in range(N):
            age += dts[k]
            if ok[t, k]:                                   # RTK epoch flagged valid
                hk = h_rtk[t, k]
                if np.isnan(hk):                           # valid flag without a value: dropout
                    counts[t, 3] += 1
                    code = 1
                else:
                    if age <= hold:                        # predicted heading: carried RTK, held delta, or none
                        pred = anchor_rtk + wrap_pi(h_mag[t, k] - anchor_mag)
                    elif not np.isnan(delta):
                        pred = h_mag[t, k] + delta
                    else:
                        pred = hk                          # first epoch: nothing to check it against
                    code = _rtk_gate(hk, pred, gate, confirm, state)
                    if code == 1:
                        counts[t, 4] += 1
                    elif code == 2:
                        counts[t, 5] += 1
                if code != 1:
                    d = wrap_pi(hk - h_mag[t, k])
                    delta = d if (np.isnan(delta) or code == 2) else delta + alpha * wrap_pi(d - delta)
                    anchor_rtk, anchor_mag, age = hk, h_mag[t, k], 0.0
            if age <= hold:                                # output the RTK heading, carried between epochs
                out[t, k] = anchor_rtk + wrap_pi(h_mag[t, k] - anchor_mag)
                counts[t, 0] += 1
            elif not np.isnan(delta):                      # outage: hold delta
                out[t, k] = h_mag[t, k] + delta
                counts[t, 1] += 1
            else:                                          # no RTK yet: uncalibrated magnetic heading
                out[t, k] = h_mag[t, k]
                counts[t, 2] += 1
            out[t, k] = out[t, k] % (2 * np.pi)
            delta_out[t, k] = delta


# --------------------------------------------------------------------------
# Public filters
# --------------------------------------------------------------------------

@dataclass(frozen=True)
class MagGate:
    """Magnetometer gate: skip samples whose field disagrees with the local field.

    A sample is used only if ``| |m| / F - 1 | <= norm_tol`` and its dip angle
    (against the accelerometer's up direction) is within ``dip_tol`` (rad) of
    the local inclination I. F and I come from the ``B_n`` given to the filter.
    """
    norm_tol: float = 0.1
    dip_tol: float = np.deg2rad(5.0)

    def __post_init__(self):
        scalar(self.norm_tol, "norm_tol", positive=True)
        scalar(self.dip_tol, "dip_tol", positive=True)


@dataclass(frozen=True)
class AttitudeResult:
    """Output of :func:`mahony` and :func:`quaternion_kf`.

    Attributes
    ----------
    q_bn : ndarray, shape (..., N, 4)
        Attitude after each sample (magnetic north with a magnetometer, true
        north with RTK heading).
    gyro_bias : ndarray, shape (..., 3)
        Final gyro-bias estimate ``-Ki sum(e dt)`` (rad/s).
    counts : dict of str -> ndarray of int, shape (...)
        Held, skipped, gated, rejected and saturated samples, keys :data:`COUNT_NAMES`.
    P : ndarray, shape (..., 4, 4) or None
        Final quaternion covariance (:func:`quaternion_kf`; None for Mahony).
    P_history : ndarray, shape (..., N, 4, 4) or None
        Covariance after every sample (``quaternion_kf(..., keep_cov=True)``).
    """
    q_bn: np.ndarray
    gyro_bias: np.ndarray
    counts: dict
    P: np.ndarray | None = None
    P_history: np.ndarray | None = None

    @property
    def hpr(self) -> np.ndarray:
        """Heading, pitch, roll (rad), shape (..., N, 3)."""
        return attitude.quat_to_euler(self.q_bn)


def _heading_input(heading_rtk, rtk_valid, shape, name="heading_rtk"):
    """Validate RTK heading and validity flags at the IMU rate; broadcast to ``shape`` (..., N)."""
    if rtk_valid is None:
        raise ValueError("rtk_valid: expected validity flags with the RTK heading (never infer validity "
                         "from the value)")
    v = np.asarray(rtk_valid)
    if v.dtype != bool:
        raise ValueError(f"rtk_valid: expected booleans, got dtype {v.dtype}")
    h = nonempty_array(heading_rtk, name, finite=False)
    for arr, label in ((h, name), (v, "rtk_valid")):
        try:
            np.broadcast_to(arr, shape)
        except ValueError:
            raise ValueError(f"{label}: expected a shape broadcastable to {shape} (the samples of heading_mag "
                             f"or w_ib_b), got {arr.shape}") from None
    h, v = np.broadcast_to(h, shape), np.broadcast_to(v, shape)
    used = h[v]
    bad = ~np.isnan(used) & ~((used >= 0) & (used < 2 * np.pi))
    if bad.any():
        raise ValueError(f"{name}: valid epochs must hold headings in [0, 2 pi) rad (or NaN for a dropout); "
                         f"{int(bad.sum())} do not (first: {used[bad][0]!r})")
    return np.ascontiguousarray(h.reshape(-1, shape[-1])), np.ascontiguousarray(v.reshape(-1, shape[-1]))


def _rtk_params(rtk_hold, rtk_gate, rtk_confirm):
    """``[hold (s, + 1 ns rounding allowance), gate (rad, inf = off), confirm (epochs)]``."""
    hold = scalar(rtk_hold, "rtk_hold", positive=True, allow_zero=True) + 1e-9
    gate = np.inf if rtk_gate is None else scalar(rtk_gate, "rtk_gate", positive=True)
    if gate != np.inf and gate >= np.pi:
        raise ValueError(f"rtk_gate: expected a value in (0, pi) rad, got {gate!r}")
    if isinstance(rtk_confirm, (bool, np.bool_)) or not isinstance(rtk_confirm, (int, np.integer)) or rtk_confirm < 1:
        raise ValueError(f"rtk_confirm: expected a positive integer, got {rtk_confirm!r}")
    return np.array([hold, gate, float(rtk_confirm)])


def _prepare(w_ib_b, f_b, dt, q0, m_b, heading_rtk, rtk_valid, kp, ki, B_n, gate, accel_tol, g, rtk_hold,
             rtk_gate, rtk_confirm, gyro_range, accel_range, mag_range, gyro_jump):
    w = nonempty_array(w_ib_b, "w_ib_b", tail=(3,), min_ndim=1, allow_nan=True)
    f = nonempty_array(f_b, "f_b", tail=(3,), finite=False)
    if f.shape != w.shape:
        raise ValueError(f"f_b: expected the shape of w_ib_b {w.shape}, got {f.shape}")
    kp, ki = scalar(kp, "kp", positive=True, allow_zero=True), scalar(ki, "ki", positive=True, allow_zero=True)
    lead, N = w.shape[:-2], w.shape[-2]
    dts = intervals(dt, N)
    T = int(np.prod(lead))
    q = as_quat(q0, "q0")
    q = np.ascontiguousarray(np.broadcast_to(q, lead + (4,)).reshape(T, 4))
    if B_n is not None:
        magnetic_reference(B_n)                              # validate even where it is not needed
    use_rtk = heading_rtk is not None
    if use_rtk == (m_b is not None):
        raise ValueError("m_b, heading_rtk: give exactly one heading reference (magnetometer or RTK)")
    if use_rtk:
        hdg, ok = _heading_input(heading_rtk, rtk_valid, lead + (N,))
        m = np.zeros((1, 1, 3))
    else:
        m = nonempty_array(m_b, "m_b", tail=(3,), finite=False)
        if m.shape != w.shape:
            raise ValueError(f"m_b: expected the shape of w_ib_b {w.shape}, got {m.shape}")
        m = m.reshape(T, N, 3)
        hdg, ok = np.zeros((1, 1)), np.zeros((1, 1), dtype=bool)
    gates = np.array([0.0, np.inf, 0.0, np.inf, -2.0, 2.0])
    if accel_tol is not None:
        tol = scalar(accel_tol, "accel_tol", positive=True)
        g = scalar(g, "g", positive=True)
        gates[0:2] = (g * max(1 - tol, 0.0)) ** 2, (g * (1 + tol)) ** 2
    if gate is not None:
        if not isinstance(gate, MagGate):
            raise ValueError(f"gate: expected a MagGate, got {type(gate).__name__}")
        if B_n is None:
            raise ValueError("B_n: the magnetometer gate needs the local field")
        _, _, I, F = magnetic_reference(B_n)
        gates[2:4] = (F * max(1 - gate.norm_tol, 0.0)) ** 2, (F * (1 + gate.norm_tol)) ** 2
        gates[4:6] = np.sin(max(I - gate.dip_tol, -np.pi / 2)), np.sin(min(I + gate.dip_tol, np.pi / 2))
    jump = 0.0 if gyro_jump is None else scalar(gyro_jump, "gyro_jump", positive=True)
    rtk_par = _rtk_params(rtk_hold, rtk_gate, rtk_confirm)
    w, f = w.reshape(T, N, 3), f.reshape(T, N, 3)
    # Saturation: counted here; accelerometer/magnetometer samples at the rails become NaN (skipped by the
    # kernel exactly like a dropout; the kernel's skip counts are corrected in _result), gyro samples are used.
    sat = np.zeros((T, 3), dtype=np.int64)
    for i, (r, name) in enumerate(((gyro_range, "gyro_range"), (accel_range, "accel_range"), (mag_range, "mag_range"))):
        if r is None:
            continue
        r = scalar(r, name, positive=True)
        if i == 2 and use_rtk:
            continue
        x = (w, f, m)[i]
        rail = (np.abs(x) >= r).any(-1) & np.isfinite(x).all(-1)
        sat[:, i] = rail.sum(-1)
        if i == 1 and sat[:, i].any():
            f = np.where(rail[..., None], np.nan, f)
        elif i == 2 and sat[:, i].any():
            m = np.where(rail[..., None], np.nan, m)
    return (lead, T, N, q, np.ascontiguousarray(w), np.ascontiguousarray(f), np.ascontiguousarray(m), hdg, ok,
            use_rtk, dts, kp, ki, gates, jump, rtk_par, sat)


def _run_trials(kernel, n_trials, *args):
    """Run ``kernel(t0, t1, *args)`` over trial chunks, one thread per core (the kernels release the GIL)."""
    workers = min(n_trials, os.cpu_count() or 1)
    bounds = np.linspace(0, n_trials, workers + 1).astype(int)
    if workers <= 1:
        kernel(0, n_trials, *args)
        return
    with ThreadPoolExecutor(workers) as pool:
        list(pool.map(lambda i: kernel(bounds[i], bounds[i + 1], *args), range(workers)))


def _result(lead, q_out, bias, counts, sat, P=None, P_hist=None):
    counts[:, 5:8] = sat                                   # saturated samples (see _prepare) ...
    counts[:, 1] -= sat[:, 1]                              # ... were skipped as NaN by the kernel
    counts[:, 3] -= sat[:, 2]
    N = q_out.shape[1]
    return AttitudeResult(q_out.reshape(lead + (N, 4)), bias.reshape(lead + (3,)),
                          {name: counts[:, i].reshape(lead) for i, name in enumerate(COUNT_NAMES)},
                          None if P is None else P.reshape(lead + (4, 4)),
                          None if P_hist is None else P_hist.reshape(lead + (N, 4, 4)))


_COMMON_DOC = """
    Parameters
    ----------
    w_ib_b : array_like, shape (..., N, 3)
        Gyro samples (rad/s); NaN samples are replaced by the last used one (counted).
        Earth rate is neglected, as in the paper.
    f_b : array_like, shape (..., N, 3)
        Accelerometer samples (m/s^2); NaN, infinite or zero samples are skipped (counted).
    dt : float or array_like, shape (N,)
        Sample interval (s), or per-sample intervals: sample k covers
        ``dt[k] = t[k] - t[k-1]`` (irregular sampling). Timestamps with
        repeats or out of order go through :func:`navlib.timing.sanitize`
        first; then ``dt = timing.intervals(np.r_[t_before_first, t])``.
    q0 : array_like, shape (4,) or (..., 4)
        Attitude before the first sample, e.g. :func:`navlib.alignment.initial_attitude`.
    m_b : array_like, shape (..., N, 3), optional
        Magnetometer samples (uT); unusable samples are skipped and gated ones counted.
    heading_rtk : array_like, shape (N,) or (..., N), optional
        Instead of ``m_b``: dual-antenna heading (rad, [0, 2 pi)) at the IMU rate,
        used as a north pseudo-vector (mode (a) of the paper's Fig. 4). Only samples with
        ``rtk_valid`` are read; each is held for ``rtk_hold`` seconds.
    rtk_valid : array_like of bool, same shape as ``heading_rtk``
        True where a valid RTK epoch arrives (the receiver's status flag).
        A valid epoch holding NaN is a dropout (ignored, ``rtk_dropped``).
    kp, ki : float
        Proportional (rad/s) and integral (rad/s^2) gains of Eq. (15); ``ki = 0``
        disables gyro-bias estimation.
    B_n : array_like, shape (3,), optional
        Local field (uT, ENU); needed by ``gate``{b_ref}.
    gate : MagGate, optional
        Field-norm and dip-angle gate for the magnetometer.
    accel_tol : float, optional
        Skip accelerometer samples whose norm differs from ``g`` by more than this fraction.
    g : float
        Gravity for ``accel_tol`` (m/s^2).
    rtk_hold : float
        How long an RTK epoch is used (s).
    rtk_gate : float, optional
        Reject RTK epochs whose heading differs from the current estimate by
        more than this (rad, in (0, pi)), e.g. 180 deg ambiguity flips
        (``rtk_rejected``); None (default) uses every valid epoch.
    rtk_confirm : int
        With ``rtk_gate``: after this many consecutive rejected epochs that
        agree with each other (within ``rtk_gate``), use them (``rtk_reacquired``),
        so that an estimate that drifted in an outage is pulled back.
    gyro_range, accel_range, mag_range : float, optional
        Full-scale ranges (rad/s, m/s^2, uT), e.g. ``sensors.imu_model(name).gyro.full_scale``.
        Samples with a component at or beyond the range are counted
        (``*_saturated``); accelerometer and magnetometer corrections are
        skipped for them, gyro samples are used (the clipped rate is the best
        available) and flag the attitude after them as suspect.
    gyro_jump : float, optional
        Spike gate (rad/s): a gyro sample differing from the last used one by
        more than this on some axis is replaced by it (``gyro_gated``) unless
        the previous sample was already replaced. Choose well above the
        per-sample noise and the largest rate change per sample of the motion.

    What the filter does with bad samples
    -------------------------------------
    NaN gyro: hold the last used sample. Gyro spike (``gyro_jump``): hold.
    NaN/inf/zero accelerometer, or outside ``accel_tol``, or saturated: skip
    the accelerometer correction. Magnetometer NaN/inf/zero, parallel to
    gravity, outside the ``gate`` or saturated: skip the heading correction.
    RTK: invalid epochs and NaN values are not read; epochs outside
    ``rtk_gate`` are rejected. A gap (any sensor) is a run of such samples: the
    attitude is propagated by the gyro alone and drifts at the gyro-bias
    error. Every case is counted in :attr:`AttitudeResult.counts`.

    Returns
    -------
    AttitudeResult
"""


def mahony(w_ib_b, f_b, dt, q0, *, m_b=None, heading_rtk=None, rtk_valid=None, kp: float = 1.0,
           ki: float = 0.02, B_n=None, gate: MagGate | None = None, accel_tol: float | None = None,
           g: float = 9.80665, rtk_hold: float = 0.25, rtk_gate: float | None = None, rtk_confirm: int = 5,
           gyro_range: float | None = None, accel_range: float | None = None, mag_range: float | None = None,
           gyro_jump: float | None = None) -> AttitudeResult:
    prep = _prepare(w_ib_b, f_b, dt, q0, m_b, heading_rtk, rtk_valid, kp, ki, B_n, gate, accel_tol, g, rtk_hold,
                    rtk_gate, rtk_confirm, gyro_range, accel_range, mag_range, gyro_jump)
    lead, T, N = prep[:3]
    q_out, bias, counts = np.empty((T, N, 4)), np.empty((T, 3)), np.zeros((T, len(COUNT_NAMES)), dtype=np.int64)
    _run_trials(_mahony_kernel, T, *prep[3:-1], q_out, bias, counts)
    return _result(lead, q_out, bias, counts, prep[-1])


mahony.__doc__ = """Mahony PI complementary filter (Eqs. 9-15), per sample:
``e = a x a_est + m x m_est``, ``w = w_m + kp e + ki sum(e dt)``,
``q <- normalise(q + dt/2 q (x) [0, w])``.

Identical to ``ahrs.filters.Mahony.updateMARG`` (AHRS 0.4.0, same frames and
first-order update) except that ahrs skips samples whose gyro norm is exactly 0.
With per-sample ``dt`` each step uses its own interval (integral term and
quaternion update).
""" + _COMMON_DOC.format(b_ref="")


def quaternion_kf(w_ib_b, f_b, dt, q0, *, m_b=None, heading_rtk=None, rtk_valid=None, kp: float = 1.0,
                  ki: float = 0.02, B_n=None, gate: MagGate | None = None, accel_tol: float | None = None,
                  g: float = 9.80665, rtk_hold: float = 0.25, sigma_gyro: float = 1e-3,
                  sigma_accel: float = 0.02, sigma_mag: float = 0.08, p0: float = 1e-4,
                  linear_innovation: bool = False, rtk_gate: float | None = None, rtk_confirm: int = 5,
                  gyro_range: float | None = None, accel_range: float | None = None, mag_range: float | None = None,
                  gyro_jump: float | None = None, keep_cov: bool = False) -> AttitudeResult:
    prep = list(_prepare(w_ib_b, f_b, dt, q0, m_b, heading_rtk, rtk_valid, kp, ki, B_n, gate, accel_tol, g,
                         rtk_hold, rtk_gate, rtk_confirm, gyro_range, accel_range, mag_range, gyro_jump))
    lead, T, N = prep[:3]
    if prep[9]:
        b = np.array([0.0, 1.0, 0.0])                       # RTK pseudo-vector points north
    elif B_n is None:
        raise ValueError("B_n: the quaternion KF needs the local field for its magnetometer reference")
    else:
        b = magnetic_reference(B_n)[0]
    sig = np.array([scalar(s, n, positive=True) for s, n in ((sigma_gyro, "sigma_gyro"), (sigma_accel, "sigma_accel"),
                                                (sigma_mag, "sigma_mag"))])
    p0 = scalar(p0, "p0", positive=True)
    linear_innovation, keep_cov = flag(linear_innovation, "linear_innovation"), flag(keep_cov, "keep_cov")
    q_out, bias, counts = np.empty((T, N, 4)), np.empty((T, 3)), np.zeros((T, len(COUNT_NAMES)), dtype=np.int64)
    P_out, P_hist = np.empty((T, 4, 4)), np.empty((T, N if keep_cov else 0, 4, 4))
    _run_trials(_kf_kernel, T, *prep[3:-1], b, sig, p0, linear_innovation, q_out, bias, counts, P_out, P_hist)
    return _result(lead, q_out, bias, counts, prep[-1], P_out, P_hist if keep_cov else None)


quaternion_kf.__doc__ = """Quaternion Kalman filter driven by the PI-corrected rate (Eqs. 16-20, Fig. 2).

Per sample: the Mahony error of the current estimate gives the rate (Eq. 15);
``Phi = I + dt/2 Omega(w)``, ``Gamma = dt/2 Xi(q)``, ``Q = sigma_gyro^2 I``;
measurement ``z = [a; m]`` (unit vectors) against ``h(q) = [C_nb [0,0,1]; C_nb b]``
with ``b`` from the local field (or north for RTK), ``R = diag(sigma_accel^2 I,
sigma_mag^2 I)``; Joseph update of :func:`navlib.kalman.update` skipping
missing rows; normalise. ``linear_innovation=True`` uses the printed
``z - H q`` (E003-12), only to show that it fails.
""" + _COMMON_DOC.format(b_ref=" and by the KF (reference b, Eq. 3)") + """
    sigma_gyro : float
        Gyro white-noise sigma per sample (rad/s).
    sigma_accel, sigma_mag : float
        Noise of the normalised accelerometer and magnetometer vectors.
    p0 : float
        Initial covariance ``p0 I``.
    linear_innovation : bool
        Use the printed innovation ``z - H q`` (wrong; for the erratum demonstration).
    keep_cov : bool
        Also return the covariance after every sample (``P_history``).

    The covariance is predicted with ``Phi P Phi^T + Gamma Q Gamma^T`` and
    updated in Joseph form (both symmetrised); skipped, gated, rejected and
    saturated measurements are simply not used, so a fault never enters P.
"""


def fuse_rtk_heading(heading_mag, heading_rtk, rtk_valid, dt, alpha: float = 0.01,
                     rtk_hold: float = 0.25, rtk_gate: float | None = None, rtk_confirm: int = 5):
    """Fuse the magnetic heading with dual-antenna RTK heading (Sec. 2.5, rule reconstructed, E003-15).

    Parameters
    ----------
    heading_mag : array_like, shape (..., N)
        Heading of the MIMU + magnetometer filter (rad, magnetic north).
    heading_rtk : array_like, shape (N,) or (..., N)
        RTK heading (rad, [0, 2 pi)) at the IMU rate; read only where ``rtk_valid``.
    rtk_valid : array_like of bool
        True where a valid RTK epoch arrives. An invalid epoch's value (the
        paper's 0) is never used; a valid epoch holding NaN is a dropout
        (ignored, counted in ``rtk_dropped``).
    dt : float or array_like, shape (N,)
        Sample interval (s), or per-sample intervals ``dt[k] = t[k] - t[k-1]``.
    alpha : float
        Smoothing of the offset per RTK epoch (0.01 at 5 Hz: a time constant of about 20 s).
    rtk_hold : float
        How long after an epoch its heading is output (carried by the magnetic
        heading's increments) before falling back to ``H_mag + delta`` (s).
    rtk_gate : float, optional
        Reject epochs further than this (rad, in (0, pi)) from the predicted
        heading (the carried RTK heading, else ``H_mag + delta``): 180 deg
        ambiguity flips are never fused (``rtk_rejected``). The first epoch
        has nothing to be checked against and is used.
    rtk_confirm : int
        With ``rtk_gate``: the ``rtk_confirm``-th consecutive rejected epoch
        agreeing with the previous rejected ones within ``rtk_gate`` is used and
        restarts delta from it (``rtk_reacquired``): a wrong first epoch or a
        real change of the offset is recovered from.

    Returns
    -------
    heading : ndarray, shape (..., N)
        Fused heading (rad, [0, 2 pi)).
    delta : ndarray, shape (..., N)
        Offset estimate ``H_rtk - H_mag`` (rad); NaN before the first valid epoch.
    counts : dict of str -> ndarray of int
        Per sample: ``rtk`` (output from RTK), ``held`` (outage samples using
        the held delta), ``uncalibrated`` (before any used RTK epoch). Per
        valid epoch: ``rtk_dropped`` (NaN value), ``rtk_rejected`` (outside
        ``rtk_gate``, not fused), ``rtk_reacquired`` (used after ``rtk_confirm``
        agreeing rejections).
    """
    hm = nonempty_array(heading_mag, "heading_mag", min_ndim=1)
    alpha = nonempty_array(alpha, "alpha")
    if alpha.ndim != 0:
        raise ValueError(f"alpha: expected a scalar, got shape {alpha.shape}")
    alpha = float(in_range(alpha, "alpha", 0.0, 1.0, lo_open=True))
    hr, ok = _heading_input(heading_rtk, rtk_valid, hm.shape)
    T, N = hr.shape
    dts = intervals(dt, N)
    rtk_par = _rtk_params(rtk_hold, rtk_gate, rtk_confirm)
    out, delta, counts = np.empty((T, N)), np.empty((T, N)), np.zeros((T, len(_FUSE_COUNTS)), dtype=np.int64)
    _fuse_kernel(np.ascontiguousarray(hm.reshape(T, N)), hr, ok, dts, alpha, rtk_par, out, delta, counts)
    lead = hm.shape[:-1]
    return (out.reshape(hm.shape), delta.reshape(hm.shape),
            {name: counts[:, i].reshape(lead) for i, name in enumerate(_FUSE_COUNTS)})


_FUSE_COUNTS = ("rtk", "held", "uncalibrated", "rtk_dropped", "rtk_rejected", "rtk_reacquired")


def rtk_at_imu_rate(time, heading, valid, step: int):
    """Place RTK epochs on the IMU time axis: every ``step``-th IMU sample carries an epoch.

    Parameters
    ----------
    time : array_like, shape (N,)
        IMU sample times (s).
    heading : array_like, shape (..., N)
        RTK heading at the IMU times (rad), e.g. :func:`navlib.sensors.simulate_heading`.
    valid : array_like of bool, shape (N,)
        Receiver validity at each IMU time (e.g. :func:`navlib.sensors.outage_mask`).
    step : int
        IMU samples per RTK epoch (e.g. 20 for 5 Hz RTK with a 100 Hz IMU).

    Returns
    -------
    heading : ndarray, shape (..., N)
        The heading, NaN between epochs and at invalid epochs.
    epoch_valid : ndarray of bool, shape (N,)
        True at valid epochs.
    """
    t = nonempty_array(time, "time")
    if t.ndim != 1:
        raise ValueError(f"time: expected a 1-D array of sample times, got shape {t.shape}")
    h = nonempty_array(heading, "heading", finite=False)
    v = np.asarray(valid)
    if v.dtype != bool:
        raise ValueError(f"valid: expected booleans, got dtype {v.dtype}")
    if isinstance(step, (bool, np.bool_)) or not isinstance(step, (int, np.integer)) or step < 1:
        raise ValueError(f"step: expected a positive integer, got {step!r}")
    if h.shape[-1:] != t.shape:
        raise ValueError(f"heading: expected a last axis of length {t.size} (that of time), got {h.shape}")
    if v.shape != t.shape:
        raise ValueError(f"valid: expected the shape of time {t.shape}, got {v.shape}")
    epoch = np.zeros(t.shape, dtype=bool)
    epoch[::step] = True
    ok = epoch & v
    return np.where(ok, h, np.nan), ok


