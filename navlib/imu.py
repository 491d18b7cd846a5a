"""IMU samples validated once: :class:`ImuSamples` with the sensors' :class:`SensorLimits`.

The filters take an :class:`ImuSamples`, screen it once (:func:`navlib.robust.screen`: dropouts, rails,
stuck outputs, spikes, free fall, clock jumps, per the record's limits) and run their equations on the
clean samples; the integrators and detectors (``strapdown.integrate``, ``euler.integrate_euler``,
``zupt.detect_static``, ``alignment.static_means``, ``calibration.characterise``, the paper companions)
take one in place of ``w_ib_b`` with ``f_b`` and ``dt`` left out (:func:`unpack`).
:meth:`navlib.io.Recording.imu` builds one from a real log. E.g.::

    imu = ImuSamples(w_ib_b, f_b, dt, SensorLimits(full_scale_gyro=model.gyro.full_scale))
    res = mahony.mahony(imu, q0, m_b=m_b)
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import overload

import numpy as np

from ._typing import Array, Interval, Times, Vec3Series
from ._validate import imu_samples, instance, integer, range_limit, sample_intervals, scalar, time_axis

__all__ = ["SensorLimits", "ImuSamples", "unpack", "JUMP_FACTOR", "STUCK_DURATION"]

JUMP_FACTOR = 10.0
"""Default ``max_dt``, in median sample intervals (``max_dt=None``): at 100 Hz, an interval longer than 0.1 s is
a clock jump (a time-stamp jump or a recording gap), which a filter does not integrate as motion. With a fixed
``dt`` no interval can exceed it."""

STUCK_DURATION = 0.1
"""Default ``stuck_run`` (``"auto"``), in seconds of samples at the median interval, at least 5 samples: 5 samples
at 50 Hz, 10 at 100 Hz, 100 at 1 kHz."""


@dataclass(frozen=True)
class SensorLimits:
    """What the sensors can measure and what counts as a fault, read once by :func:`navlib.robust.screen`.

    Attributes
    ----------
    full_scale_gyro, full_scale_accel, full_scale_mag : float
        Device ranges (rad/s, m/s^2, uT), e.g. ``sensors.imu_model(name).gyro.full_scale``; ``inf``
        (default) for none. A sample with a component at or beyond its range is at the rails
        (``"saturated"``): the best reading available, but not a trustworthy one.
    stuck_run : int, "auto" or None
        A gyro whose output stopped updating: some axis repeating exactly the same value over this many
        samples (``("gyro", "stuck")``, :func:`navlib.robust.stuck_mask`): that axis is held -- at the run's
        value if the run continues the signal (an output frozen at its last reading), else at its last used value
        (an output latched at another value) -- while the live axes go on measuring. Sensor noise makes such
        repeats of a real reading essentially impossible; values at the rails are saturated, not stuck;
        a trial whose gyro is not noisy from the start (some axis repeats its first value this often: a
        noise-free simulation, a quantised gyro at rest) is not checked. "auto" (default):
        :data:`STUCK_DURATION` (0.1 s) of samples, at least 5; None: off. Quantised gyros
        whose noise is about one count repeat by chance: use a larger value, or None.
    gyro_jump : float, optional
        Step gate (rad/s): a gyro sample differing from the last used one by more than this on some axis
        is a spike (``("gyro", "spike")``), unless the previous sample was one already (a sustained change
        is motion). Choose well above the per-sample noise and the largest rate change per sample of the
        motion. None (default): off.
    spike_gyro, spike_accel : float
        Isolated-spike thresholds (rad/s, m/s^2) of :func:`navlib.robust.is_spike` (a sample deviating
        from the line through its neighbours); ``inf`` (default): off.
    freefall_accel, freefall_time : float
        Accelerometer samples with ``|f| < freefall_accel`` (m/s^2) in a run lasting at least
        ``freefall_time`` (s) are free fall or a dead sensor (``("accel", "freefall")``); defaults 2 m/s^2
        over 0.05 s; ``freefall_accel = 0``: off.
    max_dt : float, optional
        Longest interval integrated (s); a longer one is a clock jump (``("clock", "jump")``): nothing is
        integrated over it. None (default): :data:`JUMP_FACTOR` median intervals (no jump
        with a fixed ``dt``); ``inf``: off.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import imu
    >>> limits = imu.SensorLimits(full_scale_gyro=np.deg2rad(2000.0), full_scale_accel=16 * 9.80665)   # +-2000 deg/s, +-16 g
    >>> round(float(limits.full_scale_accel), 3), limits.stuck_run
    (156.906, 'auto')
    """

    full_scale_gyro: float = np.inf
    full_scale_accel: float = np.inf
    full_scale_mag: float = np.inf
    stuck_run: int | str | None = "auto"
    gyro_jump: float | None = None
    spike_gyro: float = np.inf
    spike_accel: float = np.inf
    freefall_accel: float = 2.0
    freefall_time: float = 0.05
    max_dt: float | None = None

    def __post_init__(self) -> None:
        for name in ("full_scale_gyro", "full_scale_accel", "full_scale_mag"):
            object.__setattr__(self, name, range_limit(getattr(self, name), name))
        if isinstance(self.stuck_run, str):
            if self.stuck_run != "auto":
                raise ValueError(f"stuck_run: expected 'auto', None or an integer >= 2, got {self.stuck_run!r}")
        elif self.stuck_run is not None:
            object.__setattr__(self, "stuck_run", integer(self.stuck_run, "stuck_run", minimum=2))
        if self.gyro_jump is not None:
            object.__setattr__(self, "gyro_jump", scalar(self.gyro_jump, "gyro_jump", positive=True))
        for name in ("spike_gyro", "spike_accel"):
            object.__setattr__(self, name, scalar(getattr(self, name), name, positive=True, allow_inf=True))
        object.__setattr__(self, "freefall_accel", scalar(self.freefall_accel, "freefall_accel", positive=True, allow_zero=True))
        object.__setattr__(self, "freefall_time", scalar(self.freefall_time, "freefall_time", positive=True, allow_zero=True))
        if self.max_dt is not None:
            object.__setattr__(self, "max_dt", scalar(self.max_dt, "max_dt", positive=True, allow_inf=True))

    def jump_limit(self, typical_dt: float) -> float:
        """The longest interval integrated (s) at the typical (median) interval ``typical_dt`` (s): ``max_dt``, or
        :data:`JUMP_FACTOR` typical intervals."""
        return JUMP_FACTOR * typical_dt if self.max_dt is None else self.max_dt

    def stuck_samples(self, typical_dt: float) -> int:
        """``stuck_run`` in samples at the typical (median) interval ``typical_dt`` (s); 0: no stuck check."""
        if isinstance(self.stuck_run, str):  # "auto", the one string __post_init__ accepts
            return max(5, int(np.ceil(STUCK_DURATION / typical_dt - 1e-6)))  # 1e-6: a float32 dt gives the same run
        return self.stuck_run or 0


@dataclass(frozen=True, init=False)
class ImuSamples:
    """Gyro and accelerometer samples with their intervals and the sensors' limits, validated on construction.

    Attributes
    ----------
    w_ib_b, f_b : ndarray, shape (..., N, 3)
        Angular rate (rad/s) and specific force (m/s^2); leading axes are trials; NaN marks a dropout.
    dt : ndarray, shape (N,)
        Interval covered by each sample (s): ``dt[k] = t[k] - t[k-1]``; a scalar given at construction is
        repeated. Timestamps with repeats or out of order go through :func:`navlib.timing.sanitize` first.
    limits : SensorLimits
        Ranges and fault thresholds (default or None: no ranges, navlib's default fault tests).

    Examples
    --------
    >>> from navlib import imu, trajectory
    >>> traj = trajectory.static(0.05, 0.01, [0.6, 0.2, 50.0], [0.0, 0.0, 0.0])
    >>> samples = imu.ImuSamples(*trajectory.ideal_imu(traj), 0.01)
    >>> samples.w_ib_b.shape, samples.dt                              # a scalar interval is repeated per sample
    ((5, 3), array([0.01, 0.01, 0.01, 0.01, 0.01]))
    """

    w_ib_b: Array
    f_b: Array
    dt: Array
    limits: SensorLimits

    # Written out (init=False) so that it takes array_like samples and an optional limits, while the fields
    # are typed as what they hold: the checked arrays and a SensorLimits.
    def __init__(self, w_ib_b: Vec3Series, f_b: Vec3Series, dt: Interval, limits: SensorLimits | None = None) -> None:
        w, f = imu_samples(w_ib_b, f_b)
        object.__setattr__(self, "w_ib_b", w)
        object.__setattr__(self, "f_b", f)
        object.__setattr__(self, "dt", sample_intervals(dt, w.shape[-2]))
        if limits is not None:
            instance(limits, "limits", SensorLimits, "a SensorLimits", error=TypeError)
        object.__setattr__(self, "limits", SensorLimits() if limits is None else limits)

    @classmethod
    def from_times(cls, time: Times, w_ib_b: Vec3Series, f_b: Vec3Series, limits: SensorLimits | None = None) -> ImuSamples:
        """Samples stamped at ``time`` (N + 1 epochs: the start, then the end of each sample's interval)."""
        return cls(w_ib_b, f_b, np.diff(time_axis(time, "time")), limits)

    @property
    def n(self) -> int:
        """Number of samples N."""
        return self.w_ib_b.shape[-2]


def _one(name: str, given: float | None, held: float) -> float | None:
    if given is not None and np.isfinite(held):
        raise ValueError(f"{name}: given twice (the ImuSamples holds it)")
    return given if given is not None else (None if np.isinf(held) else held)


@overload
def unpack(
    w_ib_b: ImuSamples,
    f_b: Vec3Series | None = None,
    dt: Interval | None = None,
    full_scale_gyro: float | None = None,
    full_scale_accel: float | None = None,
) -> tuple[Array, Array, Array, float | None, float | None]: ...
@overload
def unpack(
    w_ib_b: Vec3Series,
    f_b: Vec3Series | None = None,
    dt: Interval | None = None,
    full_scale_gyro: float | None = None,
    full_scale_accel: float | None = None,
) -> tuple[Vec3Series, Vec3Series, Interval, float | None, float | None]: ...
def unpack(
    w_ib_b: Vec3Series | ImuSamples,
    f_b: Vec3Series | None = None,
    dt: Interval | None = None,
    full_scale_gyro: float | None = None,
    full_scale_accel: float | None = None,
) -> tuple[Vec3Series, Vec3Series, Interval, float | None, float | None]:
    """``(w_ib_b, f_b, dt, full_scale_gyro, full_scale_accel)`` from an :class:`ImuSamples` or raw arguments.

    For the integrators and detectors that take either. With an ImuSamples, ``f_b`` and ``dt`` must be None
    and a range may be given either in its limits or here, not both; raw arguments are returned unchanged
    (``f_b`` and ``dt`` are then required).

    Examples
    --------
    >>> from navlib import imu, trajectory
    >>> traj = trajectory.static(0.05, 0.01, [0.6, 0.2, 50.0], [0.0, 0.0, 0.0])
    >>> w_ib_b, f_b, dt, fs_gyro, fs_accel = imu.unpack(imu.ImuSamples(*trajectory.ideal_imu(traj), 0.01))
    >>> w_ib_b.shape, dt, fs_gyro
    ((5, 3), array([0.01, 0.01, 0.01, 0.01, 0.01]), None)
    """
    if isinstance(w_ib_b, ImuSamples):
        for name, value in (("f_b", f_b), ("dt", dt)):
            if value is not None:
                raise ValueError(f"{name}: given twice (the ImuSamples holds it)")
        lim = w_ib_b.limits
        return (
            w_ib_b.w_ib_b,
            w_ib_b.f_b,
            w_ib_b.dt,
            _one("full_scale_gyro", full_scale_gyro, lim.full_scale_gyro),
            _one("full_scale_accel", full_scale_accel, lim.full_scale_accel),
        )
    if f_b is None or dt is None:
        raise ValueError(f"{'f_b' if f_b is None else 'dt'}: required (or pass an ImuSamples as w_ib_b)")
    return w_ib_b, f_b, dt, full_scale_gyro, full_scale_accel
