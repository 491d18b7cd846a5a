"""Unchecked cores of :mod:`navlib.filters.planar_ekf`: the planar motion model (the paper's Eq. 13) and its
propagation over commanded inputs.

The checked public functions live in :mod:`navlib.filters.planar_ekf`; a function of another module that has
already checked its step and inputs (e.g. :func:`navlib.papers.gauss_kruger_ekf.waypoint_path`) calls the core
here, so that nothing is checked twice on one call. States are ``[x, y, theta, v, omega]`` (m, m, rad, m/s,
rad/s) as float64 arrays, the step ``T`` (s) positive.
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def motion(X, T):
    """``f(X)`` of Eq. (13) for one state (5,) and step ``T``."""
    out = X.copy()
    out[0] = X[0] + X[3] * T * np.cos(X[2])
    out[1] = X[1] + X[3] * T * np.sin(X[2])
    out[2] = X[2] + X[4] * T
    return out


@njit(cache=True)
def propagate(x0, T, speed, yaw_rate):
    """States (n + 1, 5) from ``x0`` (5,) over ``n`` steps of ``T`` (s) with the commanded ``speed`` and
    ``yaw_rate`` (n,) (m/s, rad/s): Eq. (13) step by step."""
    X = np.empty((speed.shape[0] + 1, 5))
    for i in range(5):  # element by element: an array assignment compiles numba's shape messages
        X[0, i] = x0[i]
    X[0, 3], X[0, 4] = speed[0], yaw_rate[0]
    for k in range(speed.shape[0]):
        x = motion(X[k], T)
        for i in range(5):
            X[k + 1, i] = x[i]
        if k + 1 < speed.shape[0]:
            X[k + 1, 3], X[k + 1, 4] = speed[k + 1], yaw_rate[k + 1]
    return X
