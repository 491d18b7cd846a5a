"""Unchecked cores of :mod:`navlib.analysis`' stacked least squares ``r_k = V_k b + v_k``: condition numbers and
the Cramer-Rao bound.

The checked public functions live in :mod:`navlib.analysis`; a function of another module that builds its blocks
itself (e.g. :func:`navlib.papers.rotation_bias.design`) calls the cores here, so that nothing is checked twice on
one call. ``V`` (..., K, m, n) and ``R`` (..., K, m, m) are float64 arrays (``V`` may hold NaN blocks where a
function says so), ``A`` (..., n, n) symmetric.
"""

from __future__ import annotations

import numpy as np

from ._typing import Array


def normal_condition(A: Array) -> Array:
    """``sqrt(eig_max / eig_min)`` of normal matrices ``A``; inf where singular (:func:`navlib.analysis.normal_condition`)."""
    ev = np.linalg.eigvalsh(A)
    zero = ev[..., 0] <= ev[..., -1] * A.shape[-1] * np.finfo(float).eps
    with np.errstate(divide="ignore", invalid="ignore"):
        c = np.sqrt(ev[..., -1] / ev[..., 0])
    return np.where(~zero & np.isfinite(c), c, np.inf)


def condition_number(V: Array) -> Array:
    """cond(V) of stacked blocks, NaN blocks left out (:func:`navlib.analysis.condition_number`)."""
    ok = np.all(np.isfinite(V), axis=(-2, -1))
    Vz = np.where(ok[..., None, None], V, 0.0)
    A = np.einsum("...kij,...kil->...jl", Vz, Vz)
    return normal_condition(A)


def cramer_rao_bound(V: Array, R: Array, max_cond: float) -> Array:
    """``(sum V_k^T R_k^-1 V_k)^-1``; inf/NaN where ``sqrt(cond) > max_cond`` (:func:`navlib.analysis.cramer_rao_bound`)."""
    n = V.shape[-1]
    info = np.einsum("...kji,...kjl,...klm->...im", V, np.linalg.inv(R), V)
    bad = normal_condition(info) ** 2 > max_cond**2
    safe = np.where(bad[..., None, None], np.eye(n), info)
    P = np.linalg.inv(safe)
    return np.where(bad[..., None, None], np.where(np.eye(n, dtype=bool), np.inf, np.nan), P)
