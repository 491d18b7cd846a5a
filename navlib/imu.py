"""IMU samples validated once: :class:`ImuSamples`, accepted by navlib's IMU filters beside raw arrays.

Every navlib function that takes IMU samples ``(w_ib_b, f_b, dt)`` also takes an :class:`ImuSamples`
in place of ``w_ib_b`` with ``f_b`` and ``dt`` left out -- the filters (``mahony``, ``quaternion_kf``,
``zupt_ins.run_filter``, ``strapdown.integrate``), ``euler.integrate_euler``, ``zupt.detect_static``,
``alignment.static_means``, ``calibration.characterise`` and the paper companions' IMU functions; the
device ranges it carries become the function's ``full_scale_gyro`` / ``full_scale_accel`` (where it has
them). :meth:`navlib.io.Recording.imu` builds one from a real log. E.g.::

    imu = ImuSamples(w_ib_b, f_b, dt, full_scale_gyro=model.gyro.full_scale)
    res = mahony.mahony(imu, q0=q0, m_b=m_b)

The filters call :func:`unpack`; raw arrays pass through it unchanged and are validated by the filter as
before.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ._typing import Interval, Times, Vec3Series
from ._validate import imu_samples, intervals, range_limit, time_axis

__all__ = ["ImuSamples", "unpack"]


@dataclass(frozen=True)
class ImuSamples:
    """Gyro and accelerometer samples with their intervals and device ranges, validated on construction.

    Attributes
    ----------
    w_ib_b, f_b : ndarray, shape (..., N, 3)
        Angular rate (rad/s) and specific force (m/s^2); leading axes are trials; NaN marks a dropout.
    dt : ndarray, shape (N,)
        Interval covered by each sample (s); a scalar given at construction is repeated.
    full_scale_gyro, full_scale_accel : float
        Device ranges (rad/s, m/s^2); ``inf`` (default) for none.
    """
    w_ib_b: np.ndarray
    f_b: np.ndarray
    dt: Interval
    full_scale_gyro: float = np.inf
    full_scale_accel: float = np.inf

    def __post_init__(self):
        w, f = imu_samples(self.w_ib_b, self.f_b)
        object.__setattr__(self, "w_ib_b", w)
        object.__setattr__(self, "f_b", f)
        object.__setattr__(self, "dt", intervals(self.dt, w.shape[-2]))
        object.__setattr__(self, "full_scale_gyro", range_limit(self.full_scale_gyro, "full_scale_gyro"))
        object.__setattr__(self, "full_scale_accel", range_limit(self.full_scale_accel, "full_scale_accel"))

    @classmethod
    def from_times(cls, time: Times, w_ib_b: Vec3Series, f_b: Vec3Series, **ranges: float) -> ImuSamples:
        """Samples stamped at ``time`` (N + 1 epochs: the start, then the end of each sample's interval)."""
        return cls(w_ib_b, f_b, np.diff(time_axis(time, "time")), **ranges)

    @property
    def n(self) -> int:
        """Number of samples N."""
        return self.w_ib_b.shape[-2]


def _one(name: str, given, held: float):
    if given is not None and np.isfinite(held):
        raise ValueError(f"{name}: given twice (the ImuSamples holds it)")
    return given if given is not None else (None if np.isinf(held) else held)


def unpack(w_ib_b: Vec3Series | ImuSamples, f_b: Vec3Series | None = None, dt: Interval | None = None,
           full_scale_gyro: float | None = None, full_scale_accel: float | None = None) -> tuple:
    """``(w_ib_b, f_b, dt, full_scale_gyro, full_scale_accel)`` from an :class:`ImuSamples` or raw arguments.

    With an ImuSamples, ``f_b`` and ``dt`` must be None and a range may be given either there or here,
    not both; raw arguments are returned unchanged (``f_b`` and ``dt`` are then required).
    """
    if isinstance(w_ib_b, ImuSamples):
        for name, value in (("f_b", f_b), ("dt", dt)):
            if value is not None:
                raise ValueError(f"{name}: given twice (the ImuSamples holds it)")
        return (w_ib_b.w_ib_b, w_ib_b.f_b, w_ib_b.dt, _one("full_scale_gyro", full_scale_gyro, w_ib_b.full_scale_gyro),
                _one("full_scale_accel", full_scale_accel, w_ib_b.full_scale_accel))
    for name, value in (("f_b", f_b), ("dt", dt)):
        if value is None:
            raise ValueError(f"{name}: required (or pass an ImuSamples as w_ib_b)")
    return w_ib_b, f_b, dt, full_scale_gyro, full_scale_accel
