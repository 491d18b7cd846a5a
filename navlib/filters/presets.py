"""Starting settings measured on real and simulated recordings: Mahony gains for a hand-held sensor and for a
vehicle, and a foot-mounted ZUPT filter scaled to the IMU and learned from a still start.

**Mahony gains** (:class:`MahonyGains`, :data:`HAND_HELD`, :data:`VEHICLE`). Both assume the gyro bias was
removed at rest first (:func:`navlib.io.start_at_rest`, or :func:`navlib.calibration.gyro_bias_at_rest`):
that is the setting that matters most. On a simulated MPU-6050 in a car the inclination error was 4.6-57 deg
with the turn-on bias in (the smaller the gain, the worse), 1.2-3.8 deg with it removed. Then, in order:

* ``kp`` (rad/s): the accelerometer pulls the tilt back with time constant ``1/kp``. Accelerations shorter
  than it are averaged out; a residual gyro bias ``b`` tilts the estimate by about ``b/kp``. A hand moves in
  gestures of a second or two, a car turns and brakes for ten seconds and more, hence 0.1 and 0.03 instead
  of the signature's 1.0 (the paper's gain, for a slow robot).
* ``ki`` (rad/s^2): 0 in both. The integral learns whatever the correction cannot remove, and on real
  hand-held motion that is the motion's own acceleration (and in 9D the magnetic disturbances) more than the
  bias: every ``ki > 0`` tried was worse on the trials below. Use it for long runs with a clean heading
  reference (e.g. dual-antenna RTK), where a drifting bias is what is left.
* An accelerometer-norm gate (``AttitudeGates(accel_tol=...)``) did not help at these gains (it cost
  1.3-2.2 deg on the held-out hand-held trials): a hand's accelerations change the direction more than the norm.

How they were chosen (``tools/preset_study.py`` prints every number; errors in deg):

* hand-held: a grid ``kp`` 0.01-2, ``ki`` 0-0.02, gate none/5/10/20 % on the even-numbered BROAD trials of
  :mod:`navlib.datasets` (optical reference); its best, ``kp = 0.1, ki = 0``, gives on the odd-numbered,
  held-out trials a mean total error of 3.96 (6D) and 4.69 (9D), against 9.27 and 18.04 with the signature's
  gains (bias removed as well) and 10.40 and 18.05 with neither;
* vehicle: the same grid on a simulated 679-s drive (MPU-6050 and ADIS16475 models, 5 seeds each) and on
  comma2k19's real highway minute: inclination error 1.39 / 0.81 (simulated, 6D) and 1.23 (real, 6D) at
  ``kp = 0.03``, against 3.61 / 3.30 and 3.75 at ``kp = 1``. ``kp = 0.01`` was 0.03-0.25 better still on
  these short drives; 0.03 is kept because a 100-s time constant would leave a wrong initial tilt or a change
  of bias uncorrected for minutes.

Nine hand-held trials of one sensor and one real minute of driving are thin evidence: check against a
reference of your own when you can.

**Foot-mounted ZUPT filter** (:func:`foot_mounted`). :func:`navlib.filters.zupt_ins.run_filter` was built for
paper 004's shoulder-worn IMU; on a foot its defaults detect no stance. :func:`foot_mounted` builds the records
it takes from the recording itself:

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
from .._validate import Is, NonNegative, Positive, booleans, boundary, fields_checked
from ..imu import ImuSamples
from ..units import G0
from . import zupt, zupt_ins

__all__ = [
    "HAND_HELD",
    "VEHICLE",
    "FOOT_THRESHOLD_FACTOR",
    "FOOT_GYRO_NOISE",
    "FOOT_WINDOW",
    "MahonyGains",
    "FootMounted",
    "foot_mounted",
]


@dataclass(frozen=True)
class MahonyGains:
    """Gains of :func:`navlib.filters.mahony.mahony` for one kind of motion (module docstring).

    Attributes
    ----------
    kp : float
        Proportional gain (rad/s): the tilt correction's time constant is ``1/kp``.
    ki : float
        Integral gain (rad/s^2); 0: no gyro-bias learning (remove the bias at rest instead).

    Examples
    --------
    >>> from navlib.filters import presets
    >>> presets.HAND_HELD.kwargs()
    {'kp': 0.1, 'ki': 0.0}

    ``mahony(imu, q0, m_b=m_b, **presets.HAND_HELD.kwargs())`` runs the filter with them.
    """

    kp: Positive
    ki: NonNegative

    def __post_init__(self) -> None:
        fields_checked(self)

    def kwargs(self) -> dict[str, float]:
        """``{"kp": ..., "ki": ...}``, to pass to :func:`navlib.filters.mahony.mahony` with ``**``."""
        return {"kp": self.kp, "ki": self.ki}


HAND_HELD = MahonyGains(kp=0.1, ki=0.0)
"""A phone or sensor moved by hand, gyro bias removed at rest (BROAD's hand-held trials)."""
VEHICLE = MahonyGains(kp=0.03, ki=0.0)
"""A sensor fixed in a car, gyro bias removed at rest (a simulated drive and comma2k19's highway minute)."""

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

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import imu, trajectory
    >>> from navlib.filters import presets
    >>> traj = trajectory.static(2.0, 0.01, [0.6, 0.2, 50.0], [0.0, 0.0, 0.0])
    >>> w_ib_b, f_b = trajectory.ideal_imu(traj)
    >>> rng = np.random.default_rng(0)
    >>> samples = imu.ImuSamples(w_ib_b + 1e-3 * rng.standard_normal((200, 3)), f_b + 0.02 * rng.standard_normal((200, 3)), 0.01)
    >>> setup = presets.foot_mounted(samples, still=np.ones(200, bool))
    >>> setup.window, np.round(setup.thresholds, 3)
    (0.05, array([0.068, 0.632, 0.642]))
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


@boundary
def foot_mounted(imu: Is[ImuSamples], still: ArrayLike) -> FootMounted:
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

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import imu, trajectory
    >>> from navlib.filters import presets
    >>> traj = trajectory.static(2.0, 0.01, [0.6, 0.2, 50.0], [0.0, 0.0, 0.0])
    >>> w_ib_b, f_b = trajectory.ideal_imu(traj)
    >>> rng = np.random.default_rng(0)
    >>> w_ib_b = w_ib_b + [1e-3, 0.0, 0.0] + 1e-3 * rng.standard_normal((200, 3))   # a gyro bias of 1e-3 rad/s on x
    >>> samples = imu.ImuSamples(w_ib_b, f_b + 0.02 * rng.standard_normal((200, 3)), 0.01)
    >>> setup = presets.foot_mounted(samples, still=np.ones(200, bool))
    >>> np.round(setup.gyro_bias * 1e3, 1) + 0.0                       # learned from the still start (1e-3 rad/s)
    array([0.9, 0.1, 0. ])
    """
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
