"""Starting settings for a foot-mounted ZUPT filter, scaled to the IMU and learned from a still start.

:func:`navlib.filters.zupt_ins.run_filter` was built for paper 004's shoulder-worn IMU; on a foot its
defaults detect no stance. :func:`foot_mounted` builds the records it takes from the recording itself:

* **Stance window**: 0.05 s (a foot stands still for 0.2-0.4 s per stride, so the window must be much
  shorter), at least 5 samples so that a slow IMU still has statistics.
* **Detector thresholds** (:func:`navlib.filters.zupt.detect_static`): :data:`FOOT_THRESHOLD_FACTOR` times the
  median of each detector statistic over the still start (``rms|w - b_g|``, ``std|f|``; the magnitude test
  ``|mean|f| - g|`` gets the still start's offset plus the same margin on ``std|f|``). A foot on the ground
  is far less still than a sensor on a table, hence the large factor; the noise floor the still start
  measures makes it a property of the sensor, not a number to guess.
* **Update rate**: the IMU rate (a zero-velocity update at every stance sample); **gyro process noise**
  :data:`FOOT_GYRO_NOISE`, inflated over a MEMS gyro's white noise for the swing phase's errors; no
  innovation gate (during a stance the whole velocity error is what the update must remove).

The settings that matter, in order: the detector thresholds (too low: stances missed, the track drifts
between the few detected; too high: swing samples called stance, strides shortened), the stance window,
the gyro process noise. The factor and the noise were chosen on x-io's short Gait-Tracking walk (closing
error over factors 5, 10, 20, 40 and noises 0.02, 0.1, 0.5 deg/s/sqrt(Hz)) and tested on the long walk,
which they close to 0.9 % (``tests/test_presets.py``); two walks of one wearer and one sensor are thin
evidence: check the closing error of a loop of your own.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from .. import analysis
from .._typing import Array, ArrayLike
from .._validate import booleans, instance
from ..imu import ImuSamples
from ..units import G0
from . import zupt, zupt_ins

__all__ = ["FOOT_THRESHOLD_FACTOR", "FOOT_GYRO_NOISE", "FOOT_WINDOW", "FootMounted", "foot_mounted"]

FOOT_THRESHOLD_FACTOR = 40.0
"""Detector thresholds as multiples of the still start's median detector statistics."""
FOOT_GYRO_NOISE = np.deg2rad(0.1)
"""Gyro process noise of the foot-mounted filter (rad/s/sqrt(Hz))."""
FOOT_WINDOW = 0.05
"""Stance-detector window (s); at least 5 samples."""


@dataclass(frozen=True)
class FootMounted:
    """A foot-mounted set-up: what :func:`foot_mounted` learned and the filter configuration it built.

    Attributes
    ----------
    window : float
        Stance-detector window (s).
    thresholds : tuple of 3 float
        Detector thresholds ``(tau_w rad/s, tau_f m/s^2, tau_g m/s^2)``.
    gyro_bias : ndarray, shape (3,)
        Gyro bias over the still start (rad/s); give it to :class:`navlib.filters.zupt_ins.Start` too.
    config : navlib.filters.zupt_ins.FilterConfig
    """

    window: float
    thresholds: tuple[float, float, float]
    gyro_bias: np.ndarray
    config: zupt_ins.FilterConfig

    def stance(self, imu: ImuSamples) -> NDArray[np.bool_]:
        """Stance flags, shape (N,), from :func:`navlib.filters.zupt.detect_static` with these settings."""
        return zupt.detect_static(imu, window=self.window, gyro_bias=self.gyro_bias, thresholds=self.thresholds)


def _statistics(w: np.ndarray, f: np.ndarray, n: int) -> tuple[Array, Array, Array]:
    """The detector's statistics over centred windows of n samples: rms|w|, std|f|, |mean|f| - g|."""
    f_norm = np.linalg.norm(f, axis=1)
    mean = analysis.moving_mean(f_norm, n)
    std = np.sqrt(np.maximum(analysis.moving_mean(f_norm**2, n) - mean**2, 0.0))
    return np.sqrt(analysis.moving_mean(np.sum(w**2, axis=1), n)), std, np.abs(mean - G0)


def foot_mounted(imu: ImuSamples, still: ArrayLike) -> FootMounted:
    """The foot-mounted set-up (module docstring) learned from ``imu``'s still start.

    Parameters
    ----------
    imu : ImuSamples
        The recording (rad/s, m/s^2).
    still : array_like of bool, shape (N,)
        Samples during which the foot stood untouched (e.g. the first seconds), at least 2 windows long.

    Returns
    -------
    FootMounted
    """
    instance(imu, "imu", ImuSamples, "a navlib.imu.ImuSamples")
    mask = booleans(still, "still", shape=(imu.n,))
    rate = 1.0 / float(np.median(imu.dt))
    n = max(5, int(round(FOOT_WINDOW * rate)))
    if np.count_nonzero(mask) < 2 * n:
        raise ValueError(
            f"still: {np.count_nonzero(mask)} still samples, fewer than two detector windows "
            f"({2 * n}); stand still for 2 s at the start of the recording"
        )
    w, f = imu.w_ib_b[mask], imu.f_b[mask]
    bias = np.nanmean(w, axis=0)
    s_w, s_f, s_g = (float(np.nanmedian(s)) for s in _statistics(w - bias, f, n))
    thresholds = (FOOT_THRESHOLD_FACTOR * s_w, FOOT_THRESHOLD_FACTOR * s_f, s_g + FOOT_THRESHOLD_FACTOR * s_f)
    config = zupt_ins.FilterConfig(
        process=zupt_ins.ProcessNoise(gyro=FOOT_GYRO_NOISE), gates=zupt_ins.Gates(zupt=np.inf), update_rate=rate
    )
    return FootMounted(n / rate, thresholds, bias, config)
