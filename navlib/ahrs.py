"""Attitude from a MEMS IMU, a magnetometer and dual-antenna RTK heading (paper 003).

Zhang Q., Wu Z., Yun Q. (2023). Research on attitude measurement method based
on MIMU/magnetic sensor/dual antenna RTK. *Journal of Electronic Measurement
and Instrumentation* 37(5): 230-239. doi:10.13382/j.jemi.B2206027

Conventions are navlib's (ENU, right-front-up, ``q = q_b^n`` scalar first,
``hpr = [heading, pitch, roll]`` with heading clockwise from north). The
paper's counter-clockwise yaw is ``-heading``; its z-x-y Euler order is
navlib's, so Eq. (1) is :func:`navlib.attitude.euler_to_quat` and the
corrected Eq. (2) is :func:`navlib.attitude.quat_to_euler`.

Equations implemented (paper numbering, errata of guide 003 corrected)
-----------------------------------------------------------------------
Eq. (3)   reference directions ``a_n = [0, 0, 1]``, ``b = [0, cos I, -sin I]``
          (magnetic north; b normalised, ``b_u < 0`` in the north; E7):
          :func:`magnetic_reference`.
Eq. (4)   ``a = C_nb [0, 0, 1]`` with ``q0**2`` in the third row (E4), and
Eq. (6)   ``m = C_nb b`` with ``(q0^2 - q1^2 - q2^2 + q3^2) b_z`` in row 3 (E6):
          :func:`measurement_model`.
Eq. (5)   ``roll = atan2(-a_x, a_z)``, ``pitch = atan2(a_y, hypot(a_x, a_z))`` (E5);
Eq. (7)   levelled field ``m_h = R_x(pitch) R_y(roll) m_b`` and
          ``heading = atan2(-m_h,x, m_h,y)`` (E8);
Eq. (8)   replaced by Eq. (1) (E1): :func:`tilt_heading`, :func:`initial_attitude`.
Eqs. (9)-(15)  Mahony PI filter: ``e = a_meas x a_est + m_meas x m_est``
          (measured x estimated, hats restored, E9), ``m_est = C_nb [0, |h_xy|, h_z]``
          with ``h = C_bn m_meas`` (the magnetometer corrects heading only),
          ``w = w_m + Kp e + Ki sum(e dt)`` with Kp in rad/s and Ki in rad/s^2
          (the full cross product, not MahonyAHRS.c's half error "twoKp", E10):
          :func:`mahony`.
Eqs. (16)-(17) ``Phi = I + dt/2 Omega(w)`` with the PI-corrected rate: :func:`transition`.
Eq. (18)  ``Gamma = dt/2 Xi(q)`` (printed ``-dt Xi``, E11): :func:`noise_input`.
Eq. (19)  ``z = h(q) + v`` with innovation ``z - h(q_pred)``; the printed
          ``z - H q`` is wrong because ``H q = 2 h(q)`` (E12).
Eq. (20)  Jacobian with ``H44 = 2(q0 b_y + q1 b_z)`` (E13): :func:`measurement_jacobian`;
          the filter is :func:`quaternion_kf` (Joseph update from :mod:`navlib.kalman`).
Sec. 2.5  heading fusion, reconstructed (guide R1/R2, E15, E16): while RTK is
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

from . import attitude, earth, kalman
from ._validate import as_array, in_range, positive
from .attitude import quat_mult_t

__all__ = ["MagGate", "AttitudeResult", "COUNT_NAMES", "magnetic_reference", "tilt_heading",
           "initial_attitude", "settling_time", "transition", "noise_input", "measurement_model", "measurement_jacobian",
           "mahony", "quaternion_kf", "fuse_rtk_heading", "rtk_at_imu_rate",
           "printed_eq2_roll", "printed_eq4", "printed_eq5_tilt", "printed_eq7_heading", "printed_eq8_quat",
           "printed_eq18_gamma", "printed_eq20_jacobian"]

COUNT_NAMES = ("gyro_held", "accel_skipped", "accel_gated", "mag_skipped", "mag_gated")
"""Columns of the update counters: NaN gyro samples replaced by the last valid
one; accelerometer samples unusable (NaN, inf, zero) or gated; heading
reference samples unusable (magnetometer NaN/zero/parallel to gravity, or no
valid RTK epoch) or gated (field norm or dip angle)."""


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
    B = as_array(B_n, "B_n", tail=(3,))
    if B.shape != (3,) or np.linalg.norm(B) == 0:
        raise ValueError(f"B_n: expected one non-zero field vector of shape (3,), got {B.tolist()}")
    D, I, F = earth.field_angles(B, deg=False)
    return np.array([0.0, np.cos(I), -np.sin(I)]), float(D), float(I), float(F)


def _unit_vectors(v, name):
    n = np.linalg.norm(v, axis=-1, keepdims=True)
    if np.any(n == 0):
        raise ValueError(f"{name}: expected non-zero vectors")
    return v / n


def tilt_heading(f_b, m_b):
    """Heading, pitch and roll from one accelerometer and magnetometer reading (Eqs. 5, 7).

    Parameters
    ----------
    f_b : array_like, shape (..., 3)
        Specific force (any unit; the vehicle must be static), e.g. a 1-s mean.
    m_b : array_like, shape (..., 3)
        Magnetic field (any unit).

    Returns
    -------
    hpr : ndarray, shape (..., 3)
        Magnetic heading (clockwise from magnetic north, [0, 2 pi)), pitch, roll (rad).
    """
    a = _unit_vectors(as_array(f_b, "f_b", tail=(3,)), "f_b")
    m = _unit_vectors(as_array(m_b, "m_b", tail=(3,)), "m_b")
    if np.any(np.linalg.norm(np.cross(a, m), axis=-1) < 1e-6):
        raise ValueError("m_b: magnetometer parallel to gravity; heading is undefined")
    ax, ay, az = np.moveaxis(a, -1, 0)
    mx, my, mz = np.moveaxis(m, -1, 0)
    roll = np.arctan2(-ax, az)                                  # Eq. (5), corrected
    pitch = np.arctan2(ay, np.hypot(ax, az))
    mhx = mx * np.cos(roll) + mz * np.sin(roll)                 # Eq. (7), corrected
    mhy = my * np.cos(pitch) + mx * np.sin(pitch) * np.sin(roll) - mz * np.sin(pitch) * np.cos(roll)
    heading = attitude.wrap_2pi(np.arctan2(-mhx, mhy))
    return np.stack([heading, pitch, roll], -1)


def initial_attitude(f_b, m_b):
    """Initial quaternion q_b^n (magnetic north) from accelerometer and magnetometer.

    Eqs. (5) and (7) corrected, then Eq. (1) (:func:`navlib.attitude.euler_to_quat`)
    instead of the inconsistent Eq. (8) (E1). Shapes (..., 3) -> (..., 4).
    """
    return attitude.euler_to_quat(tilt_heading(f_b, m_b))


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
    q = as_array(q, "q", tail=(4,))
    b = as_array(b, "b", tail=(3,))
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
    w = as_array(w, "w", tail=(3,))
    dt = float(positive(dt, "dt"))
    c = 0.5 * dt
    wx, wy, wz = np.moveaxis(w, -1, 0)
    o = np.ones_like(wx)
    rows = [[o, -c * wx, -c * wy, -c * wz], [c * wx, o, c * wz, -c * wy],
            [c * wy, -c * wz, o, c * wx], [c * wz, c * wy, -c * wx, o]]
    return np.stack([np.stack(r, -1) for r in rows], -2)


def noise_input(q, dt: float):
    """Gyro-noise input matrix ``Gamma = dt/2 Xi(q)`` (Eq. 18 corrected, E11); (..., 4) -> (..., 4, 3)."""
    q = as_array(q, "q", tail=(4,))
    dt = float(positive(dt, "dt"))
    q0, q1, q2, q3 = np.moveaxis(q, -1, 0)
    rows = [[-q1, -q2, -q3], [q0, -q3, q2], [q3, q0, -q1], [-q2, q1, q0]]
    return dt / 2 * np.stack([np.stack(r, -1) for r in rows], -2)


# --------------------------------------------------------------------------
# The printed equations, kept to show the errata (never used by the filters)
# --------------------------------------------------------------------------

def printed_eq2_roll(q):
    """Roll as printed in Eq. (2): ``atan(-2(q1 q3 + q0 q2) / (1 - 2(q1^2 + q2^2)))`` (E2)."""
    q0, q1, q2, q3 = np.moveaxis(as_array(q, "q", tail=(4,)), -1, 0)
    return np.arctan(-2 * (q1 * q3 + q0 * q2) / (1 - 2 * (q1 ** 2 + q2 ** 2)))


def printed_eq4(q):
    """Eq. (4) as printed, with ``q0`` instead of ``q0**2`` in the third row (E4); (..., 4) -> (..., 3)."""
    q0, q1, q2, q3 = np.moveaxis(as_array(q, "q", tail=(4,)), -1, 0)
    return np.stack([2 * (q1 * q3 - q0 * q2), 2 * (q2 * q3 + q0 * q1), q0 + q3 ** 2 - q1 ** 2 - q2 ** 2], -1)


def printed_eq5_tilt(f_b):
    """Eq. (5) as printed: ``roll = atan(a_x / hypot(a_y, a_z))``, ``pitch = atan(-a_y / a_z)`` (E5); returns (pitch, roll)."""
    a = as_array(f_b, "f_b", tail=(3,))
    return np.arctan(-a[..., 1] / a[..., 2]), np.arctan(a[..., 0] / np.hypot(a[..., 1], a[..., 2]))


def printed_eq7_heading(m_h):
    """Eq. (7) as printed, ``atan(m_x / m_y)`` of the levelled field (the CCW yaw, E8)."""
    m = as_array(m_h, "m_h", tail=(3,))
    return np.arctan(m[..., 0] / m[..., 1])


def printed_eq8_quat(hpr):
    """Eq. (8) as printed, with its yaw psi = -heading: ``q_z(psi) q_y(roll) q_x(pitch)`` (E1)."""
    h, p, r = np.moveaxis(as_array(hpr, "hpr", tail=(3,)), -1, 0)
    axis_quat = lambda a, i: np.stack([np.cos(a / 2)] + [np.sin(a / 2) * (i == j) for j in range(3)], -1)
    return attitude.quat_mult(attitude.quat_mult(axis_quat(-h, 2), axis_quat(r, 1)), axis_quat(p, 0))


def printed_eq18_gamma(q, dt: float):
    """Gamma as printed in Eq. (18): ``-dt Xi(q)`` (E11)."""
    return -2 * noise_input(q, dt)


def printed_eq20_jacobian(q, b):
    """Eq. (20) as printed: H44 = 2(q0 b_y - q1 b_z) (E13)."""
    H = measurement_jacobian(q, b).copy()
    q, b = as_array(q, "q", tail=(4,)), as_array(b, "b", tail=(3,))
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
    """Guide 4.6(a): body-frame north ``C_nb(H_rtk, pitch_est, roll_est) [0, 1, 0]``."""
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
def _observe(t, k, q0, q1, q2, q3, f, m, hdg, hdg_ok, use_rtk, gates, hold, rtk, counts):
    """Read sample k of trial t: unit accelerometer vector and unit heading reference, counting skips.

    The heading reference is the magnetometer, or with ``use_rtk`` the RTK
    north pseudo-vector; ``rtk = [sin H, cos H, heading estimate at the epoch,
    age in samples]`` of the last valid RTK epoch is updated in place. Returns
    (ax, ay, az, a_ok, mx, my, mz, m_ok, C) with C the nine elements of C_b^n(q).
    """
    C = _dcm_t(q0, q1, q2, q3)
    ax, ay, az, ca = _accel_obs(f[t, k, 0], f[t, k, 1], f[t, k, 2], gates[0], gates[1])
    if ca > 0:
        counts[t, ca] += 1
    if use_rtk:
        rtk[3] += 1.0
        if hdg_ok[t, k]:
            rtk[0], rtk[1], rtk[2], rtk[3] = np.sin(hdg[t, k]), np.cos(hdg[t, k]), _heading_of(C[1], C[4]), 0.0
        if rtk[3] <= hold and C[6] * C[6] + C[8] * C[8] > 1e-12:     # (no heading at pitch +-90 deg)
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
def _gyro(t, k, w, gx, gy, gz, counts):
    """Gyro sample k, or the last valid one (gx, gy, gz) if it is NaN/inf (counted)."""
    wx, wy, wz = w[t, k, 0], w[t, k, 1], w[t, k, 2]
    if np.isfinite(wx) and np.isfinite(wy) and np.isfinite(wz):
        return wx, wy, wz
    counts[t, 0] += 1
    return gx, gy, gz


# --------------------------------------------------------------------------
# Kernels
# --------------------------------------------------------------------------

@njit(cache=True, nogil=True)
def _mahony_kernel(t0, t1, q_init, w, f, m, hdg, hdg_ok, use_rtk, dt, kp, ki, gates, hold, q_out, bias_out, counts):
    for t in range(t0, t1):
        _mahony_trial(t, q_init, w, f, m, hdg, hdg_ok, use_rtk, dt, kp, ki, gates, hold, q_out, bias_out, counts)


@njit(cache=True)
def _mahony_trial(t, q_init, w, f, m, hdg, hdg_ok, use_rtk, dt, kp, ki, gates, hold, q_out, bias_out, counts):
    q0, q1, q2, q3 = q_init[t, 0], q_init[t, 1], q_init[t, 2], q_init[t, 3]
    gx = gy = gz = 0.0
    ix = iy = iz = 0.0
    rtk = np.array([0.0, 1.0, 0.0, np.inf])
    for k in range(w.shape[1]):
        gx, gy, gz = _gyro(t, k, w, gx, gy, gz, counts)
        ax, ay, az, a_ok, mx, my, mz, m_ok, C = _observe(t, k, q0, q1, q2, q3, f, m, hdg, hdg_ok, use_rtk,
                                                       gates, hold, rtk, counts)
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
def _kf_kernel(t0, t1, q_init, w, f, m, hdg, hdg_ok, use_rtk, dt, kp, ki, gates, hold, b_ref, sigmas, p0,
               linear_innovation, q_out, bias_out, counts):
    for t in range(t0, t1):
        _kf_trial(t, q_init, w, f, m, hdg, hdg_ok, use_rtk, dt, kp, ki, gates, hold, b_ref, sigmas, p0,
                  linear_innovation, q_out, bias_out, counts)


@njit(cache=True)
def _kf_trial(t, q_init, w, f, m, hdg, hdg_ok, use_rtk, dt, kp, ki, gates, hold, b_ref, sigmas, p0,
              linear_innovation, q_out, bias_out, counts):
    N = w.shape[1]
    sg, sa, sm = sigmas[0], sigmas[1], sigmas[2]
    by, bz = b_ref[1], b_ref[2]
    x = q_init[t].copy()
    P = p0 * np.eye(4)
    Qg = sg * sg * np.eye(3)
    R = np.diag(np.array([sa * sa, sa * sa, sa * sa, sm * sm, sm * sm, sm * sm]))
    Phi, G, z, h, H = np.empty((4, 4)), np.empty((4, 3)), np.empty(6), np.empty(6), np.empty((6, 4))
    no_angles = np.zeros(6, dtype=np.bool_)
    gx = gy = gz = 0.0
    rtk = np.array([0.0, 1.0, 0.0, np.inf])
    ix = iy = iz = 0.0
    for k in range(N):
        gx, gy, gz = _gyro(t, k, w, gx, gy, gz, counts)
        ax, ay, az, a_ok, mx, my, mz, m_ok, C = _observe(t, k, x[0], x[1], x[2], x[3], f, m, hdg, hdg_ok,
                                                       use_rtk, gates, hold, rtk, counts)
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
            h[:] = H @ x                                                    # printed Eq. (19): wrong (E12)
        else:
            _h_into(h, x, by, bz)                                           # z - h(q), Eq. (19) corrected
        x, P, _, _, _ = kalman.update(x, P, z, h, H, R, no_angles)
        x = x / np.sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2] + x[3] * x[3])
        q_out[t, k, 0], q_out[t, k, 1], q_out[t, k, 2], q_out[t, k, 3] = x[0], x[1], x[2], x[3]
    bias_out[t, 0], bias_out[t, 1], bias_out[t, 2] = -ki * ix, -ki * iy, -ki * iz


@njit(cache=True)
def _wrap(a):
    return (a + np.pi) % (2 * np.pi) - np.pi


@njit(cache=True)
def _fuse_kernel(h_mag, h_rtk, ok, alpha, hold, out, delta_out, counts):
    T, N = h_mag.shape
    for t in range(T):
        delta, age, anchor_rtk, anchor_mag = np.nan, np.inf, 0.0, 0.0
        for k in range(N):
            age += 1.0
            if ok[t, k]:                                   # R1: RTK valid
                d = _wrap(h_rtk[t, k] - h_mag[t, k])
                delta = d if np.isnan(delta) else delta + alpha * _wrap(d - delta)
                anchor_rtk, anchor_mag, age = h_rtk[t, k], h_mag[t, k], 0.0
            if age <= hold:                                # output the RTK heading, carried between epochs
                out[t, k] = anchor_rtk + _wrap(h_mag[t, k] - anchor_mag)
                counts[t, 0] += 1
            elif not np.isnan(delta):                      # R2: outage, hold delta
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
        positive(self.norm_tol, "norm_tol")
        positive(self.dip_tol, "dip_tol")


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
        Skipped or gated updates, keys :data:`COUNT_NAMES`.
    """
    q_bn: np.ndarray
    gyro_bias: np.ndarray
    counts: dict

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
    h = as_array(heading_rtk, name, finite=False)
    try:
        h, v = np.broadcast_to(h, shape), np.broadcast_to(v, shape)
    except ValueError:
        raise ValueError(f"{name}, rtk_valid: expected shapes broadcastable to {shape}, got "
                         f"{np.shape(heading_rtk)}, {np.shape(rtk_valid)}") from None
    used = h[v]
    bad = ~(np.isfinite(used) & (used >= 0) & (used < 2 * np.pi))
    if bad.any():
        raise ValueError(f"{name}: valid epochs must hold finite headings in [0, 2 pi) rad; {int(bad.sum())} "
                         f"do not (first: {used[bad][0]!r})")
    return np.ascontiguousarray(h.reshape(-1, shape[-1])), np.ascontiguousarray(v.reshape(-1, shape[-1]))


def _prepare(w_ib_b, f_b, dt, q0, m_b, heading_rtk, rtk_valid, kp, ki, B_n, gate, accel_tol, g, rtk_hold):
    w = as_array(w_ib_b, "w_ib_b", tail=(3,), min_ndim=1, allow_nan=True)
    f = as_array(f_b, "f_b", tail=(3,), finite=False)
    if f.shape != w.shape:
        raise ValueError(f"f_b: expected the shape of w_ib_b {w.shape}, got {f.shape}")
    dt = float(positive(dt, "dt"))
    kp, ki = float(positive(kp, "kp", allow_zero=True)), float(positive(ki, "ki", allow_zero=True))
    lead, N = w.shape[:-2], w.shape[-2]
    T = int(np.prod(lead))
    q = attitude._as_quat(q0, "q0")
    q = np.ascontiguousarray(np.broadcast_to(q, lead + (4,)).reshape(T, 4))
    use_rtk = heading_rtk is not None
    if use_rtk == (m_b is not None):
        raise ValueError("m_b, heading_rtk: give exactly one heading reference (magnetometer or RTK)")
    if use_rtk:
        hdg, ok = _heading_input(heading_rtk, rtk_valid, lead + (N,))
        m = np.zeros((1, 1, 3))
    else:
        m = as_array(m_b, "m_b", tail=(3,), finite=False)
        if m.shape != w.shape:
            raise ValueError(f"m_b: expected the shape of w_ib_b {w.shape}, got {m.shape}")
        m = m.reshape(T, N, 3)
        hdg, ok = np.zeros((1, 1)), np.zeros((1, 1), dtype=bool)
    gates = np.array([0.0, np.inf, 0.0, np.inf, -2.0, 2.0])
    if accel_tol is not None:
        tol = float(positive(accel_tol, "accel_tol"))
        gates[0:2] = (g * max(1 - tol, 0.0)) ** 2, (g * (1 + tol)) ** 2
    if gate is not None:
        if not isinstance(gate, MagGate):
            raise ValueError(f"gate: expected a MagGate, got {type(gate).__name__}")
        if B_n is None:
            raise ValueError("B_n: the magnetometer gate needs the local field")
        _, _, I, F = magnetic_reference(B_n)
        gates[2:4] = (F * max(1 - gate.norm_tol, 0.0)) ** 2, (F * (1 + gate.norm_tol)) ** 2
        gates[4:6] = np.sin(max(I - gate.dip_tol, -np.pi / 2)), np.sin(min(I + gate.dip_tol, np.pi / 2))
    hold = float(positive(rtk_hold, "rtk_hold", allow_zero=True)) / dt
    return (lead, T, N, q, np.ascontiguousarray(w.reshape(T, N, 3)), np.ascontiguousarray(f.reshape(T, N, 3)),
            np.ascontiguousarray(m), hdg, ok, use_rtk, dt, kp, ki, gates, hold)


def _run_trials(kernel, n_trials, *args):
    """Run ``kernel(t0, t1, *args)`` over trial chunks, one thread per core (the kernels release the GIL)."""
    workers = min(n_trials, os.cpu_count() or 1)
    bounds = np.linspace(0, n_trials, workers + 1).astype(int)
    if workers <= 1:
        kernel(0, n_trials, *args)
        return
    with ThreadPoolExecutor(workers) as pool:
        list(pool.map(lambda i: kernel(bounds[i], bounds[i + 1], *args), range(workers)))


def _result(lead, q_out, bias, counts):
    N = q_out.shape[1]
    return AttitudeResult(q_out.reshape(lead + (N, 4)), bias.reshape(lead + (3,)),
                          {name: counts[:, i].reshape(lead) for i, name in enumerate(COUNT_NAMES)})


_COMMON_DOC = """
    Parameters
    ----------
    w_ib_b : array_like, shape (..., N, 3)
        Gyro samples (rad/s); NaN samples are replaced by the last valid one (counted).
        Earth rate is neglected, as in the paper.
    f_b : array_like, shape (..., N, 3)
        Accelerometer samples (m/s^2); NaN, infinite or zero samples are skipped (counted).
    dt : float
        Sample interval (s).
    q0 : array_like, shape (4,) or (..., 4)
        Attitude before the first sample, e.g. :func:`initial_attitude`.
    m_b : array_like, shape (..., N, 3), optional
        Magnetometer samples (uT); unusable samples are skipped and gated ones counted.
    heading_rtk : array_like, shape (N,) or (..., N), optional
        Instead of ``m_b``: dual-antenna heading (rad, [0, 2 pi)) at the IMU rate,
        used as a north pseudo-vector (guide 4.6, mode a). Only samples with
        ``rtk_valid`` are read; each is held for ``rtk_hold`` seconds.
    rtk_valid : array_like of bool, same shape as ``heading_rtk``
        True where a valid RTK epoch arrives (the receiver's status flag).
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

    Returns
    -------
    AttitudeResult
"""


def mahony(w_ib_b, f_b, dt: float, q0, *, m_b=None, heading_rtk=None, rtk_valid=None, kp: float = 1.0,
           ki: float = 0.02, B_n=None, gate: MagGate | None = None, accel_tol: float | None = None,
           g: float = 9.80665, rtk_hold: float = 0.25) -> AttitudeResult:
    prep = _prepare(w_ib_b, f_b, dt, q0, m_b, heading_rtk, rtk_valid, kp, ki, B_n, gate, accel_tol, g, rtk_hold)
    lead, T, N = prep[:3]
    q_out, bias, counts = np.empty((T, N, 4)), np.empty((T, 3)), np.zeros((T, len(COUNT_NAMES)), dtype=np.int64)
    _run_trials(_mahony_kernel, T, *prep[3:], q_out, bias, counts)
    return _result(lead, q_out, bias, counts)


mahony.__doc__ = """Mahony PI complementary filter (Eqs. 9-15), per sample:
``e = a x a_est + m x m_est``, ``w = w_m + kp e + ki sum(e dt)``,
``q <- normalise(q + dt/2 q (x) [0, w])``.

Identical to ``ahrs.filters.Mahony.updateMARG`` (AHRS 0.4.0, same frames and
first-order update) except that ahrs skips samples whose gyro norm is exactly 0.
""" + _COMMON_DOC.format(b_ref="")


def quaternion_kf(w_ib_b, f_b, dt: float, q0, *, m_b=None, heading_rtk=None, rtk_valid=None, kp: float = 1.0,
                  ki: float = 0.02, B_n=None, gate: MagGate | None = None, accel_tol: float | None = None,
                  g: float = 9.80665, rtk_hold: float = 0.25, sigma_gyro: float = 1e-3,
                  sigma_accel: float = 0.02, sigma_mag: float = 0.08, p0: float = 1e-4,
                  linear_innovation: bool = False) -> AttitudeResult:
    prep = list(_prepare(w_ib_b, f_b, dt, q0, m_b, heading_rtk, rtk_valid, kp, ki, B_n, gate, accel_tol, g,
                         rtk_hold))
    lead, T, N = prep[:3]
    if prep[9]:
        b = np.array([0.0, 1.0, 0.0])                       # RTK pseudo-vector points north
    elif B_n is None:
        raise ValueError("B_n: the quaternion KF needs the local field for its magnetometer reference")
    else:
        b = magnetic_reference(B_n)[0]
    sig = np.array([float(positive(s, n)) for s, n in ((sigma_gyro, "sigma_gyro"), (sigma_accel, "sigma_accel"),
                                                         (sigma_mag, "sigma_mag"))])
    p0 = float(positive(p0, "p0"))
    q_out, bias, counts = np.empty((T, N, 4)), np.empty((T, 3)), np.zeros((T, len(COUNT_NAMES)), dtype=np.int64)
    _run_trials(_kf_kernel, T, *prep[3:], b, sig, p0, bool(linear_innovation), q_out, bias, counts)
    return _result(lead, q_out, bias, counts)


quaternion_kf.__doc__ = """Quaternion Kalman filter driven by the PI-corrected rate (Eqs. 16-20, Fig. 2).

Per sample: the Mahony error of the current estimate gives the rate (Eq. 15);
``Phi = I + dt/2 Omega(w)``, ``Gamma = dt/2 Xi(q)``, ``Q = sigma_gyro^2 I``;
measurement ``z = [a; m]`` (unit vectors) against ``h(q) = [C_nb [0,0,1]; C_nb b]``
with ``b`` from the local field (or north for RTK), ``R = diag(sigma_accel^2 I,
sigma_mag^2 I)``; Joseph update of :func:`navlib.kalman.update` skipping
missing rows; normalise. ``linear_innovation=True`` uses the printed
``z - H q`` (E12), only to show that it fails.
""" + _COMMON_DOC.format(b_ref=" and by the KF (reference b, Eq. 3)") + """
    sigma_gyro : float
        Gyro white-noise sigma per sample (rad/s).
    sigma_accel, sigma_mag : float
        Noise of the normalised accelerometer and magnetometer vectors.
    p0 : float
        Initial covariance ``p0 I``.
    linear_innovation : bool
        Use the printed innovation ``z - H q`` (wrong; for the erratum demonstration).
"""


def fuse_rtk_heading(heading_mag, heading_rtk, rtk_valid, dt: float, alpha: float = 0.01,
                     rtk_hold: float = 0.25):
    """Fuse the magnetic heading with dual-antenna RTK heading (Sec. 2.5, guide R1/R2).

    Parameters
    ----------
    heading_mag : array_like, shape (..., N)
        Heading of the MIMU + magnetometer filter (rad, magnetic north).
    heading_rtk : array_like, shape (N,) or (..., N)
        RTK heading (rad, [0, 2 pi)) at the IMU rate; read only where ``rtk_valid``.
    rtk_valid : array_like of bool
        True where a valid RTK epoch arrives. An invalid epoch's value (the
        paper's 0) is never used.
    dt : float
        Sample interval (s).
    alpha : float
        Smoothing of the offset per RTK epoch (guide: 0.01 at 5 Hz).
    rtk_hold : float
        How long after an epoch its heading is output (carried by the magnetic
        heading's increments) before falling back to ``H_mag + delta`` (s).

    Returns
    -------
    heading : ndarray, shape (..., N)
        Fused heading (rad, [0, 2 pi)).
    delta : ndarray, shape (..., N)
        Offset estimate ``H_rtk - H_mag`` (rad); NaN before the first valid epoch.
    counts : dict of str -> ndarray of int
        ``rtk`` (samples output from RTK), ``held`` (outage samples using the
        held delta), ``uncalibrated`` (samples before any valid RTK epoch).
    """
    hm = as_array(heading_mag, "heading_mag", min_ndim=1)
    dt = float(positive(dt, "dt"))
    alpha = float(in_range(as_array(alpha, "alpha"), "alpha", 0.0, 1.0, lo_open=True))
    hold = float(positive(rtk_hold, "rtk_hold", allow_zero=True)) / dt
    hr, ok = _heading_input(heading_rtk, rtk_valid, hm.shape)
    T, N = hr.shape
    out, delta, counts = np.empty((T, N)), np.empty((T, N)), np.zeros((T, 3), dtype=np.int64)
    _fuse_kernel(np.ascontiguousarray(hm.reshape(T, N)), hr, ok, alpha, hold, out, delta, counts)
    lead = hm.shape[:-1]
    return (out.reshape(hm.shape), delta.reshape(hm.shape),
            {name: counts[:, i].reshape(lead) for i, name in enumerate(("rtk", "held", "uncalibrated"))})


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
    t = as_array(time, "time")
    h = as_array(heading, "heading", finite=False)
    v = np.asarray(valid, dtype=bool)
    if not isinstance(step, (int, np.integer)) or step < 1:
        raise ValueError(f"step: expected a positive integer, got {step!r}")
    if v.shape != t.shape or h.shape[-1:] != t.shape:
        raise ValueError(f"heading, valid: expected last axis of length {t.size}, got {h.shape}, {v.shape}")
    epoch = np.zeros(t.shape, dtype=bool)
    epoch[::step] = True
    ok = epoch & v
    return np.where(ok, h, np.nan), ok


def settling_time(time, error, start: float, tol: float, end: float | None = None):
    """Time after ``start`` until ``|error|`` stays within ``tol`` up to ``end`` (s); inf if it never does.

    Parameters
    ----------
    time : array_like, shape (N,)  (s)
    error : array_like, shape (..., N)
        Error history (any unit, the unit of ``tol``), e.g. heading error after an outage ends.
    start : float
        When the clock starts (s), e.g. the end of an RTK outage.
    tol : float
        Band that counts as converged.
    end : float, optional
        Last time considered (s), e.g. the start of the next outage; default the end of the record.
    """
    t = as_array(time, "time")
    e = as_array(error, "error", min_ndim=1)
    tol = float(positive(tol, "tol"))
    stop = np.inf if end is None else float(end)
    window = (t >= start) & (t < stop)
    if e.shape[-1] != t.size or not window.any():
        raise ValueError(f"error, start, end: expected last axis of length {t.size} and samples in [start, end)")
    outside = np.abs(e[..., window]) > tol
    n = outside.shape[-1]
    last = np.where(outside.any(-1), n - 1 - np.argmax(outside[..., ::-1], -1), -1)
    tw = t[window]
    return np.where(last == n - 1, np.inf, tw[np.minimum(last + 1, n - 1)] - start)
