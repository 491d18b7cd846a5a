"""Timestamps: sort, de-duplicate and describe irregular sampling before filtering.

Real logs arrive with repeated timestamps (a driver re-sending a sample),
out-of-order samples (buffered packets) and jittered intervals. navlib's
filters never guess: :func:`sanitize` puts samples in time order, drops
exact repeats, and returns a :class:`TimingReport` that says how many of
each fault it found and how irregular the intervals are. Filters that accept
per-sample intervals take ``dt = np.diff(time)``-style arrays from
:func:`intervals`. A clock jump (an interval too long to integrate: :data:`navlib.imu.JUMP_FACTOR` median intervals
by default) is the rule of :meth:`navlib.imu.SensorLimits.jump_limit`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ._typing import Array, ArrayLike, Times
from ._validate import as_array, integer, time_axis

__all__ = ["TimingReport", "sanitize", "intervals"]


@dataclass(frozen=True)
class TimingReport:
    """What :func:`sanitize` found and did.

    Attributes
    ----------
    n_in, n_out : int
        Samples before and after.
    n_out_of_order : int
        Samples whose timestamp was earlier than one already received (moved
        into time order, not dropped).
    n_duplicate : int
        Samples with a timestamp equal to an earlier one (dropped; the first
        is kept).
    dt_median, dt_min, dt_max : float
        Interval statistics after cleaning (s).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import timing
    >>> time, x, report = timing.sanitize(np.array([0.0, 0.02, 0.01, 0.02, 0.03]), np.arange(5.0))
    >>> report.n_in, report.n_out, report.n_out_of_order, report.n_duplicate
    (5, 4, 1, 1)
    """

    n_in: int
    n_out: int
    n_out_of_order: int
    n_duplicate: int
    dt_median: float
    dt_min: float
    dt_max: float

    @property
    def irregular(self) -> bool:
        """True when intervals vary by more than 1 % of the median."""
        return bool(self.dt_max - self.dt_min > 0.01 * self.dt_median)


def _reindex(x: ArrayLike, keep: NDArray[np.intp], n: int, name: str) -> Array:
    a = as_array(x, name, allow_nan=True, min_ndim=1)
    axis = -2 if a.ndim >= 2 else -1
    if a.shape[axis] != n:
        raise ValueError(f"{name}: expected {n} samples on axis {axis}, got shape {a.shape}")
    return np.take(a, keep, axis=axis)


# (t, *series, report): Any, as a type of each element per number of series would take an overload per count.
def sanitize(time: ArrayLike, *series: ArrayLike) -> tuple[Any, ...]:
    """Sort samples by time, drop repeated timestamps, report what was found.

    Parameters
    ----------
    time : array_like, shape (N,)
        Sample times (s); finite.
    *series : array_like, shape (N,) or (..., N, k)
        Data reordered the same way (time on axis -2 for vector series).

    Returns
    -------
    time : ndarray, shape (M,)
        Strictly increasing.
    *series : ndarray
        The series, reordered and de-duplicated.
    report : TimingReport

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import timing
    >>> time, x, report = timing.sanitize(np.array([0.0, 0.02, 0.01, 0.02, 0.03]), np.arange(5.0))
    >>> time, x                                                       # sorted, the repeated 0.02 dropped
    (array([0.  , 0.01, 0.02, 0.03]), array([0., 2., 1., 4.]))
    """
    t = time_axis(time, increasing=False)
    running_max = np.maximum.accumulate(t)
    n_late = int(np.count_nonzero(t[1:] < running_max[:-1]))
    order = np.argsort(t, kind="stable")
    ts = t[order]
    first = np.concatenate([[True], np.diff(ts) > 0])
    keep = order[first]
    dt = np.diff(t[keep])
    if dt.size == 0:
        raise ValueError("time: all timestamps are equal")
    report = TimingReport(
        t.size, int(keep.size), n_late, int(np.count_nonzero(~first)), float(np.median(dt)), float(dt.min()), float(dt.max())
    )
    out = [_reindex(x, keep, t.size, f"series[{i}]") for i, x in enumerate(series)]
    return (t[keep], *out, report)


def intervals(time: Times, n_samples: int | None = None) -> Array:
    """Per-sample intervals ``dt[k] = t[k+1] - t[k]`` of a strictly increasing time axis.

    Parameters
    ----------
    time : array_like, shape (N + 1,)
        Epoch times (s).
    n_samples : int, optional
        Expected number of intervals (checks the length).

    Returns
    -------
    dt : ndarray, shape (N,)

    Examples
    --------
    >>> from navlib import timing
    >>> timing.intervals([0.0, 0.01, 0.03, 0.04])
    array([0.01, 0.02, 0.01])
    """
    t = time_axis(time)
    dt = np.diff(t)
    if n_samples is not None and dt.size != integer(n_samples, "n_samples"):
        raise ValueError(f"time: expected {n_samples + 1} epochs for {n_samples} samples, got {t.size}")
    return dt
