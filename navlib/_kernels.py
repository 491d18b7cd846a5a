"""Compiled per-sample primitives shared by navlib's modules and their numba kernels.

Each is the one implementation of its formula: the public, validated functions
(:func:`navlib.earth.gravity`, :func:`navlib.earth.radii`, :func:`navlib.kalman.predict`,
:func:`navlib.kalman.update`, :func:`navlib.strapdown.nav_step`, :func:`navlib.robust.stuck_mask`) and the
compiled filters (strapdown, Kalman filters, pedestrian, attitude and planar filters) call these. Arguments are plain
floats or float arrays in SI units, unvalidated: validate at the public boundary. A compiled
kernel calls the primitive (e.g. :func:`kalman_update`), never the public validated wrapper.
"""
from __future__ import annotations

import numpy as np
from numba import njit

from .attitude import quat_mult_1, quat_normalize_1, quat_to_dcm_1, rotvec_to_quat_1

BORROW = {"cache": True, "_nrt": False}
"""numba options of a compiled helper that only reads and writes arrays its caller owns (it allocates and
returns none): no reference counting. Otherwise every call of a per-sample helper may increment and
decrement the reference count of each array it is passed (or reads from a record), atomically, wherever
numba cannot pair them away (branches that last use different arrays, callees that may raise): tens of
nanoseconds per array, more than the helper's arithmetic (two thirds of the Mahony filter's time)."""


@njit(cache=True)
def normal_gravity(lat, h, a, f, e2, m, gamma_e, k):
    """Normal gravity (m/s^2): Somigliana's closed form with the second-order height series."""
    s2 = np.sin(lat) ** 2
    g0 = gamma_e * (1 + k * s2) / np.sqrt(1 - e2 * s2)
    return g0 * (1 - 2 / a * (1 + f + m - 2 * f * s2) * h + 3 * h * h / (a * a))


@njit(cache=True)
def radii_mn(lat, a, e2):
    """Meridian and prime-vertical radii of curvature ``(R_M, R_N)`` (m)."""
    w = 1 - e2 * np.sin(lat) ** 2
    R_N = a / np.sqrt(w)
    return R_N * (1 - e2) / w, R_N


@njit(cache=True)
def wrap_pi(a):
    """A scalar angle wrapped to (-pi, pi] (rad)."""
    w = np.mod(a + np.pi, 2 * np.pi) - np.pi
    return np.pi if w == -np.pi else w


@njit(cache=True, inline="always")
def dcm_heading(c12, c22):
    """Heading (rad, (-pi, pi]) of ``C_bn`` from its elements ``C[0, 1]`` and ``C[1, 1]`` (hpr convention)."""
    return np.arctan2(c12, c22)


@njit(cache=True, inline="always")
def level(ax, ay, az):
    """Pitch and roll (rad) from one specific-force sample: :func:`navlib.alignment.level`, compiled."""
    return np.arctan2(ay, np.sqrt(ax * ax + az * az)), np.arctan2(-ax, az)


@njit(cache=True, inline="always")
def euler_to_quat(h, p, r):
    """q_b^n of heading, pitch, roll (rad): :func:`navlib.attitude.euler_to_quat`, compiled (no sign fix-up)."""
    ch, sh, cp, sp, cr, sr = np.cos(h / 2), np.sin(h / 2), np.cos(p / 2), np.sin(p / 2), np.cos(r / 2), np.sin(r / 2)
    return (ch * cp * cr + sh * sp * sr, ch * sp * cr + sh * cp * sr, ch * cp * sr - sh * sp * cr,
            -sh * cp * cr + ch * sp * sr)


@njit(cache=True)
def tilt_heading(mx, my, mz, pitch, roll):
    """Tilt-compensated magnetic heading in [0, 2 pi) (rad) of a right-front-up magnetometer reading.

    The field is levelled with ``pitch`` and ``roll`` (hpr convention of :mod:`navlib`); the heading is
    ``atan2(-m_h,x, m_h,y)``, clockwise from magnetic north. Works on floats and arrays alike.
    """
    sp, cp, sr, cr = np.sin(pitch), np.cos(pitch), np.sin(roll), np.cos(roll)
    mhx = mx * cr + mz * sr
    mhy = my * cp + mx * sp * sr - mz * sp * cr
    a = np.mod(np.arctan2(-mhx, mhy), 2 * np.pi)
    return a * (a < 2 * np.pi)                               # [0, 2 pi): a rounded-up 2 pi is north


@njit(cache=True)
def kalman_predict(x, P, F, Q):
    """Linear prediction ``x = F x``, ``P = F P F^T + Q`` (symmetrised); :func:`navlib.kalman.predict` unvalidated."""
    Pn = F @ P @ np.ascontiguousarray(F.T) + Q
    return F @ x, (Pn + Pn.T) / 2


@njit(cache=True)
def kalman_update(x, P, z, h, H, R, angle_mask, gate=np.inf):
    """Joseph-form update skipping NaN components; :func:`navlib.kalman.update` unvalidated.

    Returns ``(x, P, y, nis, status)`` with status 1 (accepted), 0 (no data) or -1 (rejected by ``gate``).
    """
    m = z.shape[0]
    finite = np.isfinite(z)
    n_used = int(finite.sum())
    if n_used == 0:
        return x.copy(), P.copy(), np.full(m, np.nan), np.nan, 0
    y = z - h
    for j in range(m):
        if angle_mask[j] and finite[j]:
            y[j] = wrap_pi(y[j])
    if n_used == m:                      # common case: no dropout, no copies
        Hs, Rs, ys = H, R, y
    else:
        idx = np.nonzero(finite)[0]
        Hs = np.ascontiguousarray(H[idx, :])
        Rs = np.ascontiguousarray(R[idx][:, idx])
        ys = y[idx]
    PHt = P @ np.ascontiguousarray(Hs.T)
    S = Hs @ PHt + Rs
    S_inv = np.linalg.inv((S + S.T) / 2)
    nis = ys @ S_inv @ ys
    if nis > gate:
        return x.copy(), P.copy(), y, nis, -1
    K = PHt @ S_inv
    IKH = np.eye(x.shape[0]) - K @ Hs
    Pn = IKH @ P @ np.ascontiguousarray(IKH.T) + K @ Rs @ np.ascontiguousarray(K.T)
    return x + K @ ys, (Pn + Pn.T) / 2, y, nis, 1


@njit(cache=True)
def nav_step(lla, vel, q, w, f, dt, earth_consts, hold_height=False):
    """One ENU strapdown step updating ``lla``, ``vel``, ``q`` in place; :func:`navlib.strapdown.nav_step` unvalidated."""
    a, flat, e2, m, gamma_e, k_som, omega = (earth_consts[0], earth_consts[1], earth_consts[2], earth_consts[3],
                                            earth_consts[4], earth_consts[5], earth_consts[6])
    lat, h = lla[0], lla[2]
    sl, cl = np.sin(lat), np.cos(lat)
    R_M, R_N = radii_mn(lat, a, e2)
    w_ie = np.array([0.0, omega * cl, omega * sl])
    w_en = np.array([-vel[1] / (R_M + h), vel[0] / (R_N + h), vel[0] * sl / cl / (R_N + h)])
    w_in = w_ie + w_en
    q_mid = quat_mult_1(quat_mult_1(rotvec_to_quat_1(-w_in * (dt / 2)), q), rotvec_to_quat_1(w * (dt / 2)))
    f_n = quat_to_dcm_1(q_mid) @ f
    g = normal_gravity(lat, h, a, flat, e2, m, gamma_e, k_som)
    v_new = vel + (f_n - np.cross(2 * w_ie + w_en, vel)) * dt
    v_new[2] -= g * dt
    if hold_height:
        v_new[2] = 0.0
    q[:] = quat_normalize_1(quat_mult_1(quat_mult_1(rotvec_to_quat_1(-w_in * dt), q), rotvec_to_quat_1(w * dt)))
    vm = (vel + v_new) / 2
    lla[0] = lat + vm[1] / (R_M + h) * dt
    lla[1] += vm[0] / ((R_N + h) * cl) * dt
    lla[2] = h + vm[2] * dt
    vel[:] = v_new


@njit(cache=True, nogil=True)
def stuck_runs(t0, t1, x, run, rail, out):
    """Compiled :func:`navlib.robust.stuck_mask` of series t0 to t1 - 1 of ``x`` (T, N, k): set ``out`` (T, N).

    A maximal run of ``run`` or more exactly equal values of one component marks all its samples.
    NaN, and values with ``|x| >= rail`` (saturated, not stuck), are never part of a run.
    """
    n = x.shape[1]
    for t in range(t0, t1):
        for c in range(x.shape[2]):
            start = 0
            for i in range(1, n + 1):
                v = x[t, i - 1, c]
                if i < n and x[t, i, c] == v and abs(v) < rail:
                    continue                                # the run goes on
                if i - start >= run:
                    out[t, start:i] = True
                start = i
