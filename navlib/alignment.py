"""Initial alignment of a static or slowly moving IMU: levelling and magnetic heading.

One implementation of each concept, imported by every paper companion and notebook:

* :func:`level` -- pitch and roll from (mean) specific force, the accelerometer
  levelling ``pitch = atan2(f_y, hypot(f_x, f_z))``, ``roll = atan2(-f_x, f_z)``
  (right-front-up body, ``hpr`` order of :mod:`navlib`). The atan2 form is exact for any
  norm of ``f_b``, so no value of g is needed.
* :func:`magnetic_heading` -- tilt-compensated heading of a magnetometer reading, given
  pitch and roll (from :func:`level` or an INS).
* :func:`tilt_heading` -- both at once from one accelerometer + magnetometer reading,
  ``hpr``; :func:`initial_attitude` returns it as a quaternion.

Conventions are stated once in :mod:`navlib`: ENU navigation frame, right-front-up body,
heading clockwise from north in [0, 2 pi).
"""
from __future__ import annotations

import numpy as np

from . import _kernels, attitude
from ._typing import Angles, Array, Vec3
from ._validate import as_array, scalar

__all__ = ["level", "magnetic_heading", "tilt_heading", "initial_attitude"]


def _nonzero(v: np.ndarray, name: str) -> np.ndarray:
    if np.any(np.linalg.norm(v, axis=-1) == 0):
        raise ValueError(f"{name}: expected non-zero vectors")
    return v


def level(f_b: Vec3) -> tuple[Array, Array]:
    """Pitch and roll (rad) of a static IMU from its (mean) specific force.

    Parameters
    ----------
    f_b : array_like, shape (..., 3)
        Specific force (any unit; +g up when level), e.g. a static mean.

    Returns
    -------
    pitch, roll : ndarray, shape (...)
        Pitch in [-pi/2, pi/2], roll in (-pi, pi] (rad).
    """
    f = _nonzero(as_array(f_b, "f_b", tail=(3,)), "f_b")
    return np.arctan2(f[..., 1], np.hypot(f[..., 0], f[..., 2])), np.arctan2(-f[..., 0], f[..., 2])


def magnetic_heading(m_b: Vec3, pitch: Angles, roll: Angles, declination: float = 0.0) -> Array:
    """Tilt-compensated heading (rad) in [0, 2 pi), clockwise from true north.

    Parameters
    ----------
    m_b : array_like, shape (..., 3)
        Magnetometer reading, right-front-up (any unit).
    pitch, roll : array_like, shape (...)
        Attitude (rad), e.g. from :func:`level` or an INS; broadcast with ``m_b``.
    declination : float
        Magnetic declination D, east of true north positive (rad); 0 gives the magnetic heading.
    """
    m = _nonzero(as_array(m_b, "m_b", tail=(3,)), "m_b")
    p, r = as_array(pitch, "pitch"), as_array(roll, "roll")
    D = scalar(declination, "declination")
    shape = np.broadcast_shapes(m.shape[:-1], p.shape, r.shape)
    m = np.broadcast_to(m, shape + (3,)).reshape(-1, 3)
    p, r = (np.ascontiguousarray(np.broadcast_to(x, shape).reshape(-1)) for x in (p, r))
    a = _kernels.tilt_heading(np.ascontiguousarray(m[:, 0]), np.ascontiguousarray(m[:, 1]),
                              np.ascontiguousarray(m[:, 2]), p, r)
    return (attitude.wrap_2pi(a + D) if D else a).reshape(shape)


def tilt_heading(f_b: Vec3, m_b: Vec3, declination: float = 0.0) -> Array:
    """Heading, pitch and roll ``hpr`` (rad) from one static accelerometer and magnetometer reading.

    Parameters
    ----------
    f_b, m_b : array_like, shape (..., 3)
        Specific force and magnetic field (any units), e.g. 1-s means.
    declination : float
        D (rad, east positive); 0 gives the heading from magnetic north.

    Returns
    -------
    hpr : ndarray, shape (..., 3)
    """
    f = _nonzero(as_array(f_b, "f_b", tail=(3,)), "f_b")
    m = _nonzero(as_array(m_b, "m_b", tail=(3,)), "m_b")
    cross = np.linalg.norm(np.cross(f / np.linalg.norm(f, axis=-1, keepdims=True),
                                    m / np.linalg.norm(m, axis=-1, keepdims=True)), axis=-1)
    if np.any(cross < 1e-6):
        raise ValueError("m_b: magnetometer parallel to gravity; heading is undefined")
    pitch, roll = level(f)
    heading = magnetic_heading(m, pitch, roll, declination)
    return np.stack(np.broadcast_arrays(heading, pitch, roll), -1)


def initial_attitude(f_b: Vec3, m_b: Vec3, declination: float = 0.0) -> Array:
    """Initial quaternion ``q_bn`` (..., 4) from :func:`tilt_heading` (scalar first)."""
    return attitude.euler_to_quat(tilt_heading(f_b, m_b, declination))
