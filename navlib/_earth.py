"""Unchecked cores of :mod:`navlib.earth`: Earth rate, normal gravity, radii, transport rate and field angles.

The checked public functions live in :mod:`navlib.earth`; each checks its arguments, then calls its core here.
A function of another module that has already checked a latitude (e.g. :func:`navlib.alignment.triad`) calls
the core directly, so that nothing is checked twice on one call. Inputs are arrays of float64, latitudes in rad,
heights in m, all already within their ranges; ``ellipsoid`` is an :class:`navlib.earth.Ellipsoid`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ._kernels import normal_gravity, radii_mn
from ._typing import Array
from ._validate import kernel_array

if TYPE_CHECKING:
    from .earth import Ellipsoid


def earth_rate_n(lat: Array, ellipsoid: Ellipsoid) -> Array:
    """:func:`navlib.earth.earth_rate_n` of a checked latitude (rad)."""
    w = ellipsoid.omega
    return np.stack([np.zeros_like(lat), w * np.cos(lat), w * np.sin(lat)], -1)


def field_angles(B: Array) -> tuple[Array, Array, Array]:
    """:func:`navlib.earth.field_angles` (rad) of ENU field vectors: declination, inclination, intensity."""
    H = np.hypot(B[..., 0], B[..., 1])
    return np.arctan2(B[..., 0], B[..., 1]), np.arctan2(-B[..., 2], H), np.linalg.norm(B, axis=-1)


def gravity(lat: Array, h: Array, ellipsoid: Ellipsoid) -> Array:
    """:func:`navlib.earth.gravity` of a checked latitude (rad) and height (m)."""
    shape = np.broadcast_shapes(lat.shape, h.shape)
    lat, h = (kernel_array(np.broadcast_to(x, shape)).reshape(-1) for x in (lat, h))
    return normal_gravity(lat, h, *ellipsoid.gravity_constants).reshape(shape)


def gravity_n(g: Array) -> Array:
    """ENU normal gravity vectors ``[0, 0, -g]`` of gravity magnitudes ``g`` (m/s^2); shape (..., 3)."""
    z = np.zeros_like(g)
    return np.stack([z, z, -g], -1)


def radii(lat: Array, ellipsoid: Ellipsoid) -> tuple[Array, Array]:
    """:func:`navlib.earth.radii` of a checked latitude (rad): ``R_M, R_N``."""
    R_M, R_N = radii_mn(kernel_array(lat).reshape(-1), ellipsoid.a, ellipsoid.e2)
    return R_M.reshape(lat.shape), R_N.reshape(lat.shape)


def transport_rate_n(lat: Array, h: Array, vel_n: Array, ellipsoid: Ellipsoid) -> Array:
    """:func:`navlib.earth.transport_rate_n` of a checked latitude (rad, off the poles), height and ENU velocity."""
    R_M, R_N = radii(lat, ellipsoid)
    vE, vN = vel_n[..., 0], vel_n[..., 1]
    return np.stack([-vN / (R_M + h), vE / (R_N + h), vE * np.tan(lat) / (R_N + h)], -1)
