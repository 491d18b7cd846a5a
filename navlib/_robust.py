"""Unchecked cores of :mod:`navlib.robust`: the hold of NaN samples and the stuck-sample tests.

The checked public functions live in :mod:`navlib.robust`; each checks its arguments, then calls its core here.
A function of another module that has already checked its samples (e.g. the yaw-rate screening of
:func:`navlib.filters.planar_ekf.filter_grid`) calls the core directly, so that nothing is checked twice on one
call. Samples are float arrays of shape (..., N, k) (time on axis -2), NaN allowed, never infinite; ``run`` is an
integer >= 2.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from ._kernels import stuck_runs
from ._validate import kernel_array


def last_valid(valid: np.ndarray, fill: int) -> np.ndarray:
    """Index of the last valid sample at or before each sample (along the last axis); ``fill`` before the first."""
    idx = np.where(valid, np.arange(valid.shape[-1]), fill)
    np.maximum.accumulate(idx, axis=-1, out=idx)
    return idx


def hold(a: np.ndarray, leading: str, name: str, axis: int) -> tuple[np.ndarray, np.ndarray]:
    """:func:`navlib.robust.hold` of samples ``a`` with time on ``axis`` (-2, or -1 for scalar series);
    ``name`` names ``a`` in the errors (a series with nothing to hold)."""
    vector = axis == -2
    bad = np.any(np.isnan(a), axis=-1) if vector else np.isnan(a)
    if not bad.any():
        return a, bad
    n = bad.shape[-1]
    first = np.argmax(~bad, axis=-1)
    if np.any(bad.all(axis=-1)):
        raise ValueError(f"{name}: a series has no valid sample to hold")
    if leading == "raise" and np.any(bad[..., 0]):
        raise ValueError(f"{name}: the first sample of a series is NaN and there is nothing before it to hold")
    idx = last_valid(~bad, fill=0)
    before = bad & (np.arange(n) < first[..., None])
    idx = np.where(before, first[..., None], idx)
    filled = np.take_along_axis(a, idx[..., None] if vector else idx, axis=axis)
    if leading == "zero" and before.any():
        filled = np.where(before[..., None] if vector else before, 0.0, filled)
    return filled, bad


def stuck_mask(a: np.ndarray, run: int, rail: float = np.inf) -> NDArray[np.bool_]:
    """:func:`navlib.robust.stuck_mask` of samples ``a`` (..., N, k); values with ``|a| >= rail`` never repeat."""
    lead, (n, k) = a.shape[:-2], a.shape[-2:]
    flat = kernel_array(a.reshape((math.prod(lead), n, k)))  # writable: one kernel signature
    out = np.zeros(flat.shape, dtype=bool)
    stuck_runs(0, flat.shape[0], flat, run, rail, out)
    return np.any(out, axis=-1).reshape(lead + (n,))


def stuck_samples(a: np.ndarray, run: int | None, rail: float = np.inf) -> NDArray[np.bool_]:
    """:func:`navlib.robust.stuck_samples` of samples ``a`` (..., N, k) (``run`` None: no check), with the rails
    ``|a| >= rail``."""
    if run is None:
        return np.zeros(a.shape[:-1], dtype=bool)
    noisy = np.logical_and.accumulate(a == a[..., :1, :], axis=-2).sum(-2).max(-1) < run
    return stuck_mask(a, run, rail) & noisy[..., None]
