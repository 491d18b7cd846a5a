"""Compiled per-sample primitives shared by navlib's modules and their numba kernels.

Each is the one implementation of its formula: the public, validated functions
(:func:`navlib.earth.gravity`, :func:`navlib.earth.radii`) and the compiled filters
(strapdown, Kalman update, pedestrian and planar filters) call these. Arguments are plain
floats or float arrays in SI units, unvalidated: validate at the public boundary.
"""
from __future__ import annotations

import numpy as np
from numba import njit


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
