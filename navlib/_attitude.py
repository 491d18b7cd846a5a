"""Unchecked cores of :mod:`navlib.attitude`: quaternion algebra on checked values.

The checked public functions live in :mod:`navlib.attitude`; each checks its arguments, then calls its core
here. A function of another module that has already checked its quaternions or angles (a
:class:`navlib.trajectory.Trajectory`'s attitudes, its own Euler angles) calls the core directly, so that nothing
is checked twice on one call. Inputs are float64 arrays: quaternions ``(..., 4)`` scalar first, non-zero (unit
where a function says so), Euler angles ``(..., 3)`` in rad with the pitch within [-pi/2, pi/2]; the levelling
and TRIAD cores of :mod:`navlib.alignment` take non-zero specific forces and magnetic fields, the attitude
integration of :mod:`navlib.strapdown` finite gyro samples.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from numba import njit

from . import _earth
from ._kernels import quat_mult_t, quat_to_dcm_into, rotvec_to_quat_t, tilt_heading
from ._typing import Array
from ._validate import kernel_array

if TYPE_CHECKING:
    from .earth import Ellipsoid


def wrap_pi(a: Array) -> Array:
    """:func:`navlib.attitude.wrap_pi` of an angle array (rad)."""
    w = np.mod(a + np.pi, 2 * np.pi) - np.pi
    return np.where(w == -np.pi, np.pi, w)


def wrap_2pi(a: Array) -> Array:
    """:func:`navlib.attitude.wrap_2pi` of an angle array (rad)."""
    w = np.mod(a, 2 * np.pi)
    return np.where(w >= 2 * np.pi, 0.0, w)


def level(f: Array) -> tuple[Array, Array]:
    """:func:`navlib.alignment.level` of non-zero specific forces (..., 3): pitch, roll (rad)."""
    return np.arctan2(f[..., 1], np.hypot(f[..., 0], f[..., 2])), np.arctan2(-f[..., 0], f[..., 2])


def magnetic_heading(m: Array, p: Array, r: Array, D: float) -> Array:
    """:func:`navlib.alignment.magnetic_heading` of non-zero fields ``m``, pitch, roll and declination (rad)."""
    shape = np.broadcast_shapes(m.shape[:-1], p.shape, r.shape)
    m = np.broadcast_to(m, shape + (3,)).reshape(-1, 3)
    p, r = (kernel_array(np.broadcast_to(x, shape).reshape(-1)) for x in (p, r))
    a = tilt_heading(kernel_array(m[:, 0]), kernel_array(m[:, 1]), kernel_array(m[:, 2]), p, r)
    return (wrap_2pi(a + D) if D else a).reshape(shape)


def euler_to_dcm(hpr: Array) -> Array:
    """:func:`navlib.attitude.euler_to_dcm` of checked ``[heading, pitch, roll]`` (rad)."""
    h, p, r = np.moveaxis(hpr, -1, 0)
    ch, sh, cp, sp, cr, sr = np.cos(h), np.sin(h), np.cos(p), np.sin(p), np.cos(r), np.sin(r)
    rows = [
        [cr * ch + sr * sp * sh, cp * sh, sr * ch - cr * sp * sh],
        [-cr * sh + sr * sp * ch, cp * ch, -sr * sh - cr * sp * ch],
        [-sr * cp, sp, cr * cp],
    ]
    return np.stack([np.stack(row, -1) for row in rows], -2)


def dcm_to_euler(C: Array) -> Array:
    """:func:`navlib.attitude.dcm_to_euler` (rad) of rotation matrices."""
    c31, c32, c33 = C[..., 2, 0], C[..., 2, 1], C[..., 2, 2]
    horizontal = np.hypot(c31, c33)
    pitch = np.arctan2(c32, horizontal)
    roll = np.arctan2(-c31, c33)
    heading = np.arctan2(C[..., 0, 1], C[..., 1, 1])
    locked = horizontal < 1e-9
    if locked.any():  # gimbal lock: the whole turn about the vertical as heading
        roll = np.where(locked, 0.0, roll)
        heading = np.where(locked, np.arctan2(-C[..., 1, 0], C[..., 0, 0]), heading)
    return np.stack([wrap_2pi(heading), pitch, wrap_pi(roll)], -1)


def unit(q: Array) -> Array:
    """Non-zero quaternions scaled to unit norm (as :func:`navlib._validate.as_quat` does)."""
    return q / np.linalg.norm(q, axis=-1, keepdims=True)


def positive_scalar(q: Array) -> Array:
    """The sign of each quaternion with ``q0 >= 0`` (the same rotation)."""
    return np.where(q[..., :1] < 0, -q, q)


def euler_to_quat(hpr: Array) -> Array:
    """:func:`navlib.attitude.euler_to_quat` of checked ``[heading, pitch, roll]`` (rad)."""
    h, p, r = np.moveaxis(hpr, -1, 0) / 2
    ch, sh, cp, sp, cr, sr = np.cos(h), np.sin(h), np.cos(p), np.sin(p), np.cos(r), np.sin(r)
    q = np.stack(
        [ch * cp * cr + sh * sp * sr, ch * sp * cr + sh * cp * sr, ch * cp * sr - sh * sp * cr, -sh * cp * cr + ch * sp * sr], -1
    )
    return positive_scalar(q)


def quat_to_dcm(q: Array) -> Array:
    """:func:`navlib.attitude.quat_to_dcm` of unit quaternions."""
    return _quat_to_dcm_batch(np.ascontiguousarray(q).reshape(-1, 4)).reshape(q.shape[:-1] + (3, 3))


@njit(cache=True)
def _quat_to_dcm_batch(q):
    """:func:`quat_to_dcm` of unit quaternions ``q`` (M, 4): (M, 3, 3), one pass with no temporaries."""
    C = np.empty((q.shape[0], 3, 3))
    for i in range(q.shape[0]):
        quat_to_dcm_into(C[i], q[i])
    return C


def quat_mult(p: Array, q: Array) -> Array:
    """:func:`navlib.attitude.quat_mult`: the Hamilton product of quaternion arrays."""
    p0, p1, p2, p3 = np.moveaxis(p, -1, 0)
    q0, q1, q2, q3 = np.moveaxis(q, -1, 0)
    return np.stack(
        [
            p0 * q0 - p1 * q1 - p2 * q2 - p3 * q3,
            p0 * q1 + p1 * q0 + p2 * q3 - p3 * q2,
            p0 * q2 - p1 * q3 + p2 * q0 + p3 * q1,
            p0 * q3 + p1 * q2 - p2 * q1 + p3 * q0,
        ],
        -1,
    )


def quat_conj(q: Array) -> Array:
    """:func:`navlib.attitude.quat_conj` of a quaternion array."""
    return q * np.array([1.0, -1.0, -1.0, -1.0])


def rotvec_to_quat(rv: Array) -> Array:
    """:func:`navlib.attitude.rotvec_to_quat` of checked rotation vectors (rad)."""
    angle = np.linalg.norm(rv, axis=-1, keepdims=True)
    half = angle / 2
    # sin(x/2)/x with its Taylor series near 0 to keep full precision.
    k = np.where(angle > 1e-4, np.sin(half) / np.where(angle > 0, angle, 1.0), 0.5 - angle**2 / 48 + angle**4 / 3840)
    return np.concatenate([np.cos(half), k * rv], -1)


def quat_to_rotvec(q: Array) -> Array:
    """:func:`navlib.attitude.quat_to_rotvec` of unit quaternions."""
    q = positive_scalar(q)
    s = np.linalg.norm(q[..., 1:], axis=-1, keepdims=True)
    angle = 2 * np.arctan2(s, q[..., :1])
    k = np.where(s > 1e-8, angle / np.where(s > 0, s, 1.0), 2 + s**2 / 3)
    return k * q[..., 1:]


@njit(cache=True)
def _integrate_kernel(q0, w, dt, w_in_n):
    """``dt`` has 1 element (regular sampling) or one per sample (irregular)."""
    T, N = w.shape[0], w.shape[1]
    q = np.empty((T, N + 1, 4))
    per_sample = dt.shape[0] > 1
    dtk = dt[0]
    n0, n1, n2, n3 = rotvec_to_quat_t(-w_in_n[0] * dtk, -w_in_n[1] * dtk, -w_in_n[2] * dtk)
    for t in range(T):
        a0, a1, a2, a3 = q0[t, 0], q0[t, 1], q0[t, 2], q0[t, 3]
        q[t, 0, 0], q[t, 0, 1], q[t, 0, 2], q[t, 0, 3] = a0, a1, a2, a3
        for k in range(N):
            if per_sample:
                dtk = dt[k]
                n0, n1, n2, n3 = rotvec_to_quat_t(-w_in_n[0] * dtk, -w_in_n[1] * dtk, -w_in_n[2] * dtk)
            # q_k+1 = q(-w_in dt) (x) q_k (x) q(w_k dt), then renormalise
            b0, b1, b2, b3 = rotvec_to_quat_t(w[t, k, 0] * dtk, w[t, k, 1] * dtk, w[t, k, 2] * dtk)
            a0, a1, a2, a3 = quat_mult_t(n0, n1, n2, n3, a0, a1, a2, a3)
            a0, a1, a2, a3 = quat_mult_t(a0, a1, a2, a3, b0, b1, b2, b3)
            s = 1.0 / np.sqrt(a0 * a0 + a1 * a1 + a2 * a2 + a3 * a3)
            a0, a1, a2, a3 = a0 * s, a1 * s, a2 * s, a3 * s
            q[t, k + 1, 0], q[t, k + 1, 1], q[t, k + 1, 2], q[t, k + 1, 3] = a0, a1, a2, a3
    return q


def integrate(q0: Array, w: Array, dt: Array, w_in_n: Array) -> Array:
    """:func:`navlib.strapdown.integrate_attitude`'s core: unit ``q0`` (..., 4), finite gyro samples ``w``
    (..., N, 3) with the same leading axes, ``dt`` of 1 element (regular sampling) or N (s), ``w_in_n`` (3,)
    (rad/s); returns ``q_bn`` (..., N + 1, 4)."""
    lead = w.shape[:-2]
    q = _integrate_kernel(kernel_array(q0.reshape(-1, 4)), kernel_array(w.reshape(-1, *w.shape[-2:])), dt, w_in_n)
    return q.reshape(lead + q.shape[-2:])


def _reference_triad(g_n: Array, w_ie_n: Array) -> Array:
    a = g_n
    b = np.cross(g_n, w_ie_n)
    return np.stack([a, b, np.cross(b, a)], -1)


def triad(f: Array, w: Array, lat: Array, ellipsoid: Ellipsoid) -> Array:
    """:func:`navlib.alignment.triad`'s core (Eq. 2, not orthonormalised): ``C_bn`` (..., 3, 3) from averaged
    specific force ``f`` and angular rate ``w`` (..., 3) at latitude ``lat`` (rad, within the gyrocompassing
    limit) on ``ellipsoid``."""
    g_n = np.stack(np.broadcast_arrays(0.0, 0.0, -_earth.gravity(lat, np.zeros(()), ellipsoid)), -1)
    body = _reference_triad(-f, w)  # columns: -f, -f x w, (-f x w) x (-f)
    nav = _reference_triad(g_n, _earth.earth_rate_n(lat, ellipsoid))
    C_nb = body @ np.linalg.inv(nav)
    return np.swapaxes(C_nb, -1, -2)
