"""Fault injection for robustness tests and demonstrations.

Each function returns a corrupted *copy* of its input plus the boolean mask
(or index list) of what it changed, so a test can check that a filter
reported exactly the faults it was given. All draws take an explicit
``rng``; nothing here is used by the algorithms themselves.

Faults covered (navlib's robustness suite, ``tests/faults/``):

* dropouts: a random fraction of samples set to NaN (:func:`dropouts`), and
  a contiguous gap (:func:`gap`);
* outliers: spikes of k sigma on a random fraction of samples (:func:`spikes`),
  GNSS position jumps (:func:`position_jumps`), heading flips of 180 deg
  (:func:`heading_flips`);
* timing: duplicated and out-of-order timestamps, irregular sampling
  (:func:`duplicate_timestamps`, :func:`swap_timestamps`, :func:`irregular_times`);
* saturation: clipping at a device's full-scale range (:func:`saturate`).
"""

from __future__ import annotations

from typing import Annotated, Any

import numpy as np
from numpy.typing import NDArray

from . import attitude, earth
from ._typing import Angles, Array, ArrayLike, Times, Vec3Series
from ._validate import Check, Positive, Real, Rng, Step, as_array, boundary, positive, same_shape, time_axis

__all__ = [
    "dropouts",
    "gap",
    "spikes",
    "position_jumps",
    "heading_flips",
    "duplicate_timestamps",
    "swap_timestamps",
    "irregular_times",
    "saturate",
]


def _samples(x: ArrayLike, name: str) -> Array:
    """Series with time on axis 0 of the sample dimension: (..., N) or (..., N, k) -> N on axis -2 if 2-D+."""
    return as_array(x, name, allow_nan=True, min_ndim=1)


def _time_axis_len(a: NDArray[Any]) -> int:
    return a.shape[-2] if a.ndim >= 2 else a.shape[-1]


Probability = Annotated[float, Check("scalar", within=(0.0, 1.0))]
"""The fraction of samples a fault hits, in [0, 1]."""


def _hits(rng: np.random.Generator, fraction: float, n: int) -> NDArray[np.bool_]:
    """Which of ``n`` samples a fault hits, each with probability ``fraction`` (a checked generator and fraction)."""
    return rng.random(n) < fraction


@boundary
def dropouts(x: ArrayLike, fraction: Probability, rng: Rng) -> tuple[Array, np.ndarray]:
    """Set a random ``fraction`` of samples (whole rows) to NaN.

    Parameters
    ----------
    x : array_like, shape (N,) or (..., N, k)
        Samples; time on axis -2 for vector series (axis -1 for 1-D).
    fraction : float
        Fraction of samples to drop, in [0, 1].
    rng : numpy.random.Generator

    Returns
    -------
    x_faulty : ndarray
    dropped : ndarray of bool, shape (N,)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import faults
    >>> x, dropped = faults.dropouts(np.ones((8, 3)), 0.25, np.random.default_rng(0))
    >>> int(dropped.sum()), int(np.isnan(x[:, 0]).sum())             # 2 of 8 rows set to NaN
    (2, 2)
    """
    x = _samples(x, "x").copy()
    dropped = _hits(rng, fraction, _time_axis_len(x))
    if x.ndim == 1:
        x[dropped] = np.nan
    else:
        x[..., dropped, :] = np.nan
    return x, dropped


@boundary
def gap(x: ArrayLike, time: Times, start: Real, duration: Positive) -> tuple[Array, np.ndarray]:
    """NaN over ``[start, start + duration)`` (s): a sensor outage.

    Returns
    -------
    x_faulty : ndarray
    dropped : ndarray of bool, shape (N,)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import faults
    >>> x, dropped = faults.gap(np.ones(6), np.arange(6.0), start=2.0, duration=2.0)
    >>> x
    array([ 1.,  1., nan, nan,  1.,  1.])
    """
    x = _samples(x, "x").copy()
    t = same_shape(time_axis(time, "time"), "time", (_time_axis_len(x),), of="x")
    dropped = (t >= start) & (t < start + duration)
    if x.ndim == 1:
        x[dropped] = np.nan
    else:
        x[..., dropped, :] = np.nan
    return x, dropped


@boundary
def spikes(x: ArrayLike, fraction: Probability, sigma: ArrayLike, rng: Rng, k: Positive = 100.0) -> tuple[Array, np.ndarray]:
    """Add ``±k sigma`` spikes to a random ``fraction`` of samples (each component).

    Parameters
    ----------
    x : array_like, shape (N,) or (..., N, k)
    fraction : float
    sigma : float or array_like, shape (k,)
        Noise standard deviation of the sensor (per component).
    k : float
        Spike size in sigmas (default 100).

    Returns
    -------
    x_faulty : ndarray
    hit : ndarray of bool, shape (N,)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import faults
    >>> x, hit = faults.spikes(np.zeros(6), 0.5, 0.01, np.random.default_rng(0))
    >>> np.abs(x[hit]), int(hit.sum())                                    # 100 sigma spikes
    (array([1., 1., 1.]), 3)
    """
    x = _samples(x, "x").copy()
    sigma = positive(sigma, "sigma")
    k_comp = x.shape[-1] if x.ndim >= 2 else 1
    if sigma.ndim > 1 or sigma.size not in (1, k_comp):
        raise ValueError(f"sigma: expected a scalar or one value per component ({k_comp}), got shape {sigma.shape}")
    hit = _hits(rng, fraction, _time_axis_len(x))
    sign = np.where(rng.random(x.shape) < 0.5, -1.0, 1.0)
    mask = hit if x.ndim == 1 else hit[:, None]
    x = x + np.where(mask, k * sigma * sign, 0.0)
    return x, hit


@boundary
def position_jumps(lla: Vec3Series, fraction: Probability, rng: Rng, size_m: Positive = 50.0) -> tuple[Array, np.ndarray]:
    """Move a random ``fraction`` of GNSS fixes by ``size_m`` metres horizontally.

    Parameters
    ----------
    lla : array_like, shape (N, 3)
        ``[lat (rad), lon (rad), h (m)]``; NaN rows (outages) stay NaN.

    Returns
    -------
    lla_faulty : ndarray, shape (N, 3)
    hit : ndarray of bool, shape (N,)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import analysis, faults
    >>> lla = np.tile([0.6, 0.2, 50.0], (4, 1))
    >>> lla_faulty, hit = faults.position_jumps(lla, 0.5, np.random.default_rng(0), size_m=50.0)
    >>> hit, np.round(np.hypot(*analysis.horizontal_error(lla_faulty, lla).T), 6)   # east-north jump (m)
    (array([False,  True,  True,  True]), array([ 0., 50., 50., 50.]))
    """
    lla = as_array(lla, "lla", tail=(3,), allow_nan=True, min_ndim=1).copy()
    lat_ok = np.isnan(lla[..., 0]) | (np.abs(lla[..., 0]) <= np.pi / 2)
    if not lat_ok.all():
        raise ValueError("lla[..., 0] (lat): expected latitudes in [-pi/2, pi/2] rad")
    hit = _hits(rng, fraction, lla.shape[-2])
    az = rng.uniform(0, 2 * np.pi, lla.shape[-2])
    lat, h = np.nan_to_num(lla[..., 0]), np.nan_to_num(lla[..., 2])
    R_M, R_N = earth.radii(lat)
    lla[..., 0] += np.where(hit, size_m * np.cos(az) / (R_M + h), 0.0)
    lla[..., 1] += np.where(hit, size_m * np.sin(az) / ((R_N + h) * np.cos(lat)), 0.0)
    return lla, hit


@boundary
def heading_flips(heading: Angles, fraction: Probability, rng: Rng) -> tuple[Array, np.ndarray]:
    """Rotate a random ``fraction`` of heading samples by 180 deg (dual-antenna ambiguity).

    Returns
    -------
    heading_faulty : ndarray, shape (N,)  in [0, 2 pi), NaN kept
    hit : ndarray of bool, shape (N,)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import faults
    >>> heading, hit = faults.heading_flips(np.full(4, 0.5), 0.5, np.random.default_rng(0))
    >>> np.round(heading, 6), hit
    (array([0.5     , 3.641593, 3.641593, 3.641593]), array([False,  True,  True,  True]))
    """
    h = as_array(heading, "heading", allow_nan=True, min_ndim=1).copy()
    hit = _hits(rng, fraction, h.shape[-1])
    return np.where(hit, attitude.wrap_2pi(h + np.pi), h), hit


@boundary
def duplicate_timestamps(time: Times, fraction: Probability, rng: Rng) -> tuple[Array, np.ndarray]:
    """Repeat the previous timestamp on a random ``fraction`` of samples.

    Returns
    -------
    time_faulty : ndarray, shape (N,)
    hit : ndarray of bool, shape (N,)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import faults
    >>> time, hit = faults.duplicate_timestamps(np.arange(6.0), 0.4, np.random.default_rng(0))
    >>> time, hit
    (array([0., 0., 1., 2., 4., 5.]), array([False,  True,  True,  True, False, False]))
    """
    t = time_axis(time).copy()
    hit = _hits(rng, fraction, t.size)
    hit[0] = False
    t[hit] = t[np.flatnonzero(hit) - 1]
    return t, hit


@boundary
def swap_timestamps(time: Times, fraction: Probability, rng: Rng) -> tuple[Array, np.ndarray]:
    """Swap a random ``fraction`` of samples with their successor: out-of-order arrival.

    Returns the permutation too, so data can be reordered the same way.

    Returns
    -------
    time_faulty : ndarray, shape (N,)
    order : ndarray of int, shape (N,)
        ``time_faulty = time[order]``; apply it to the data as well.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import faults
    >>> time, order = faults.swap_timestamps(np.arange(6.0), 0.3, np.random.default_rng(0))
    >>> time, order
    (array([0., 2., 3., 4., 1., 5.]), array([0, 2, 3, 4, 1, 5]))
    """
    t = time_axis(time, increasing=False)
    order = np.arange(t.size)
    for i in np.flatnonzero(_hits(rng, fraction, t.size - 1)):
        order[i], order[i + 1] = order[i + 1], order[i]
    return t[order], order


@boundary
def irregular_times(
    n: Annotated[int, Check("integer", minimum=2)],
    dt: Step,
    jitter: Annotated[float, Check("scalar", within=(0.0, 0.99))],
    rng: Rng,
    t0: Real = 0.0,
) -> Array:
    """Sample times with intervals ``dt (1 + u)``, u uniform in ``[-jitter, jitter]``.

    Returns
    -------
    time : ndarray, shape (n,)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import faults
    >>> np.round(faults.irregular_times(4, 0.01, 0.1, np.random.default_rng(0)), 5)
    array([0.     , 0.01027, 0.01981, 0.0289 ])
    """
    steps = dt * (1 + rng.uniform(-jitter, jitter, n - 1))
    return t0 + np.concatenate([[0.0], np.cumsum(steps)])


@boundary
def saturate(x: Vec3Series, full_scale: Positive) -> tuple[Array, np.ndarray]:
    """Clip at ``±full_scale``; returns the clipped copy and the mask of clipped samples.

    Parameters
    ----------
    x : array_like, shape (..., N, 3)
    full_scale : float
        Device range (same units as x).

    Returns
    -------
    x_clipped : ndarray
    clipped : ndarray of bool, shape (..., N)
        True where any component was clipped.

    Examples
    --------
    >>> from navlib import faults
    >>> x, clipped = faults.saturate([[1.0, 2.0, 3.0], [5.0, -9.0, 0.0]], full_scale=4.0)
    >>> x, clipped
    (array([[ 1.,  2.,  3.],
           [ 4., -4.,  0.]]), array([False,  True]))
    """
    x = _samples(x, "x")
    clipped = np.abs(x) > full_scale
    if x.ndim >= 2:
        clipped = np.any(clipped, axis=-1)
    return np.clip(x, -full_scale, full_scale), clipped
