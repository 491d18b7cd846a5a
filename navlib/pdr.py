"""Pedestrian dead reckoning (PDR): step detection, step length and step-by-step position.

* :func:`detect_steps` -- steps as peaks of the smoothed specific-force magnitude above ``g +
  threshold`` with a minimum interval between steps; returns each step's end and the accelerometer
  peak-to-peak within it (:class:`StepResult`).
* :func:`weinberg_step_length` -- Weinberg's (2002) model ``K (a_max - a_min)^(1/4)``, K calibrated
  per walker.
* :func:`pdr_headings` -- one tilt-compensated magnetic heading per step
  (:func:`navlib.alignment.magnetic_heading` on the step's mean accelerometer and magnetometer).
* :func:`pdr` -- east/north positions from step lengths and headings.

Used by paper 004 (Wen et al. 2016) as the baseline its INS is compared with.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import _attitude, analysis
from ._typing import Array, ArrayLike, Vec3Series
from ._validate import Positive, Real, Step, as_array, boundary, indices, positive, same_shape, scalar
from .units import G0

__all__ = ["StepResult", "detect_steps", "weinberg_step_length", "pdr", "pdr_headings"]


@dataclass(frozen=True)
class StepResult:
    """Detected steps: sample index of each step's end, and the accelerometer
    peak-to-peak of |f| within it (m/s^2), the input of Weinberg's model.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import pdr
    >>> t = np.arange(0.0, 4.0, 0.01)
    >>> f_b = np.zeros((400, 3)) + [0.0, 0.0, 9.80665]
    >>> f_b[:, 2] += 3.0 * np.maximum(np.sin(2 * np.pi * 1.0 * t), 0.0) ** 4   # one impact per second
    >>> steps = pdr.detect_steps(f_b, 0.01)
    >>> steps.index, np.round(steps.peak_to_peak, 2)
    (array([ 26, 125, 225, 325]), array([2.75, 2.81, 2.81, 2.81]))
    """

    index: np.ndarray
    peak_to_peak: np.ndarray


@boundary
def detect_steps(f_b: Vec3Series, dt: Step, threshold: Positive = 1.0, min_interval: float = 0.35, g: float = G0) -> StepResult:
    """Steps as peaks of the smoothed specific-force magnitude above ``g + threshold``.

    Parameters
    ----------
    f_b : array_like, shape (N, 3)
        Accelerometer samples (m/s^2).
    dt : float  (s)
    threshold : float
        Peak height above g (m/s^2).
    min_interval : float
        Minimum time between steps (s).
    g : float
        Local gravity (m/s^2).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import pdr
    >>> t = np.arange(0.0, 4.0, 0.01)
    >>> f_b = np.zeros((400, 3)) + [0.0, 0.0, 9.80665]
    >>> f_b[:, 2] += 3.0 * np.maximum(np.sin(2 * np.pi * 1.0 * t), 0.0) ** 4   # one impact per second
    >>> len(pdr.detect_steps(f_b, 0.01).index)
    4
    """
    f = as_array(f_b, "f_b", shape=(None, 3), min_ndim=1)
    gap = int(round(scalar(min_interval, "min_interval", positive=True) / dt))
    n_smooth = max(2, int(round(0.1 / dt)))
    if f.shape[0] < max(gap, n_smooth) + 2:
        raise ValueError(f"f_b: expected (N, 3) with N > {max(gap, n_smooth) + 2} samples, got {f.shape}")
    a = analysis.moving_mean(np.linalg.norm(f, axis=-1), n_smooth) - scalar(g, "g", positive=True)  # N > n_smooth
    peak = (a[1:-1] > a[:-2]) & (a[1:-1] >= a[2:]) & (a[1:-1] > threshold)
    steps: list[int] = []
    for i in np.flatnonzero(peak) + 1:
        if not steps or i - steps[-1] >= gap:
            steps.append(int(i))
    idx = np.array(steps, dtype=int)
    bounds = np.concatenate([[max(0, idx[0] - gap)], idx]) if idx.size else np.zeros(1, dtype=int)
    p2p = np.array([a[lo : hi + 1].max() - a[lo : hi + 1].min() for lo, hi in zip(bounds[:-1], bounds[1:], strict=True)])
    return StepResult(idx, p2p)


def weinberg_step_length(peak_to_peak: ArrayLike, K: float = 0.45) -> Array:
    r"""Weinberg (2002) step length :math:`K\, (a_{max} - a_{min})^{1/4}` (m); K is calibrated per person.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import pdr
    >>> np.round(pdr.weinberg_step_length([4.0, 8.0]), 3)              # K (a_max - a_min)^(1/4), m
    array([0.636, 0.757])
    """
    a = positive(peak_to_peak, "peak_to_peak", allow_zero=True)
    return scalar(K, "K", positive=True) * a**0.25


def pdr(step_lengths: ArrayLike, step_headings: ArrayLike, start_en: ArrayLike = (0.0, 0.0)) -> Array:
    """Dead reckoning from step lengths (m) and headings (rad): East/North after each step.

    Returns
    -------
    en : ndarray, shape (n_steps + 1, 2)
        Positions (m), starting at ``start_en``.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import pdr
    >>> np.round(pdr.pdr([0.7, 0.7, 0.7], np.deg2rad([0.0, 90.0, 90.0])), 6) + 0.0   # north, then east twice (m)
    array([[0. , 0. ],
           [0. , 0.7],
           [0.7, 0.7],
           [1.4, 0.7]])
    """
    L = positive(step_lengths, "step_lengths", allow_zero=True, shape=(None,))
    psi = same_shape(as_array(step_headings, "step_headings"), "step_headings", L.shape, of="step_lengths")
    start = as_array(start_en, "start_en", shape=(2,))
    d = np.stack([L * np.sin(psi), L * np.cos(psi)], -1)
    return start + np.concatenate([np.zeros((1, 2)), np.cumsum(d, 0)])


@boundary
def pdr_headings(f_b: Vec3Series, m_b: Vec3Series, step_index: ArrayLike, declination: Real = 0.0) -> Array:
    """Heading of every step: tilt-compensated magnetic heading from the step's mean samples.

    Pitch and roll come from the mean specific force over the step
    (:func:`navlib.alignment.level`; the gait accelerations average out over a step), the
    field from the mean magnetometer reading (NaN samples ignored).

    Parameters
    ----------
    f_b : array_like, shape (N, 3)
        Accelerometer (m/s^2).
    m_b : array_like, shape (N, 3)
        Magnetometer (uT), NaN between samples.
    step_index : array_like of int, shape (n_steps,)
        End sample of each step (:func:`detect_steps`); a step starts where the previous ended.
    declination : float  (rad)

    Returns
    -------
    heading : ndarray, shape (n_steps,)  (rad)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import pdr
    >>> f_b = np.tile([0.0, 0.0, 9.8], (10, 1))                      # level
    >>> m_b = np.tile([20.0 * np.sin(-0.5), 20.0 * np.cos(-0.5), -40.0], (10, 1))   # facing 0.5 rad east of magnetic north
    >>> np.round(pdr.pdr_headings(f_b, m_b, [4, 9]), 6)
    array([0.5, 0.5])
    """
    f = as_array(f_b, "f_b", shape=(None, 3), min_ndim=1)
    m = same_shape(as_array(m_b, "m_b", allow_nan=True), "m_b", f.shape, of="f_b")
    idx = indices(step_index, "step_index")
    if (
        idx.ndim != 1
        or idx.size < 2
        or not np.issubdtype(idx.dtype, np.integer)
        or np.any(np.diff(idx) <= 0)
        or idx[0] < 1
        or idx[-1] > f.shape[0]
    ):
        raise ValueError("step_index: expected at least two increasing sample indices within the record")
    starts = np.concatenate([[max(0, idx[0] - (idx[1] - idx[0]))], idx[:-1]])
    f_mean = np.stack([f[a:b].mean(0) for a, b in zip(starts, idx, strict=True)])
    m_mean = np.stack(
        [np.nanmean(m[a:b], 0) if np.isfinite(m[a:b, 0]).any() else np.full(3, np.nan) for a, b in zip(starts, idx, strict=True)]
    )
    if not np.isfinite(m_mean).all():
        raise ValueError("m_b: a step without any magnetometer sample")
    for name, mean in (("f_b", f_mean), ("m_b", m_mean)):
        if np.any(np.linalg.norm(mean, axis=-1) == 0):
            raise ValueError(f"{name}: expected non-zero vectors (a step's mean is zero)")
    pitch, roll = _attitude.level(f_mean)
    return _attitude.magnetic_heading(m_mean, pitch, roll, declination)
