"""Robust input handling and the one fault vocabulary of navlib's filters.

:class:`FaultReport` is what every filter result carries in its ``faults`` field:
counts per ``(sensor, kind)`` (arrays over Monte Carlo trials where a filter runs a
batch) and, when asked for, per-sample boolean flags. Sensors are named ``"gyro"``,
``"accel"``, ``"mag"``, ``"baro"``, ``"gnss"``, ``"heading"``...; kinds are

``"nan"``
    a dropout or unusable sample (NaN; inf or zero where a filter cannot use it),
    replaced by :func:`hold` or skipped;
``"saturated"``
    a sample at or beyond the device's full-scale range (rails);
``"spike"``
    an isolated jump replaced by a hold;
``"outlier"``
    a sample rejected by a MAD or innovation (chi-square) gate;
``"reacquired"``
    a sample used although it failed its gate, because a run of them agreed (the
    estimate, not the sensor, was wrong), or a forced update after repeated rejections;
``"refused"``
    a quantity that could not be formed (e.g. a static window with too few samples,
    a dwell skipped for dropouts);
``"jump"``
    a time jump (sensor ``"clock"``): a sample interval too long to integrate as motion
    (:attr:`navlib.imu.SensorLimits.max_dt`, default :meth:`navlib.imu.SensorLimits.jump_limit`; the heading
    fusion's ``max_dt``); nothing is integrated over it;
``"freefall"``
    accelerometer samples reading ``|f|`` near 0 for a while (free fall or a dead sensor:
    ``("accel", "freefall")``), held from the last good sample;
``"stuck"``
    a sensor that stopped updating: a component repeating exactly the same value over a run
    of samples (:func:`stuck_mask`; the stuck axis held, the live ones used), or over most of a static window
    (:func:`navlib.alignment.static_means` ``stuck_fraction``; the window refused).

:func:`screen` is the one pass over a filter's IMU samples before any filter equation runs: it finds
every fault the samples' :class:`navlib.imu.SensorLimits` describe, flags and counts it, and holds the
unusable gyro samples. The filters consume its :class:`Screened` record.

Every filter result carries one: :class:`navlib.filters.observations.AttitudeResult` (Mahony,
quaternion KF), :class:`navlib.filters.planar_ekf.EkfResult`, :class:`navlib.filters.heading_fusion.FusionResult`,
:class:`navlib.filters.zupt_ins.FilterResult`, and the paper method's ``rotation_bias.Residuals``.

:func:`fault_report` counts the NaN and saturated samples of a raw series, e.g. what an
integrator that returns a plain array (:func:`navlib.strapdown.integrate_attitude`,
:func:`navlib.euler.integrate_euler`) held, filled or integrated at the rails.

:func:`hold` is the one zero-order hold of NaN samples, with an explicit policy for
leading NaN samples (there is nothing before them to hold). :func:`despike` marks isolated
IMU spikes as NaN with the test of :func:`is_spike` (:func:`screen` applies it with the limits' thresholds).
:func:`stuck_mask` finds the samples of a sensor that stopped updating (exact repeats); :func:`stuck_samples`
is that test as the filters apply it to their inputs (``stuck_run`` from
:meth:`navlib.imu.SensorLimits.stuck_samples`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Annotated, Any, NamedTuple

import numpy as np
from numba import njit
from numpy.typing import NDArray

from . import _robust
from ._kernels import count_flags, stuck_runs
from ._threads import run_chunks
from ._typing import Array, ArrayLike, Vec3Series
from ._validate import (
    MAX_MAGNITUDE,
    Check,
    Is,
    as_array,
    booleans,
    boundary,
    choice,
    flag,
    integer,
    kernel_array,
    range_limit,
    real,
    refuse_turn,
    same_shape,
    text,
)
from .imu import ImuSamples

__all__ = [
    "FaultReport",
    "Screened",
    "screen",
    "fault_report",
    "hold",
    "despike",
    "stuck_mask",
    "stuck_samples",
    "longest_repeat",
    "LEADING",
]

LEADING = ("raise", "first", "zero")
"""Policies for NaN samples before the first valid one: raise, take the first valid sample, or 0."""


@dataclass(frozen=True)
class FaultReport:
    """Fault counts per ``(sensor, kind)``, and optional per-sample flags under the same keys.

    ``report["gyro", "nan"]`` is the count (0 when the key is absent); ``report.flags[...]`` a
    boolean mask over samples where the filter was asked to keep flags.

    Examples
    --------
    >>> from navlib import robust
    >>> report = robust.FaultReport({("gyro", "nan"): 2})
    >>> report["gyro", "nan"], report["accel", "nan"]                 # 0 for an absent key
    (2, 0)
    """

    counts: Mapping[tuple[str, str], np.ndarray | int] = field(default_factory=dict)
    flags: Mapping[tuple[str, str], np.ndarray] = field(default_factory=dict)

    def __getitem__(self, key: tuple[str, str]) -> np.ndarray | int:
        return self.counts.get(key, 0)

    def total(self) -> np.ndarray | np.int64:
        """Sum of all counts (an array over trials for batched filters)."""
        return sum((np.asarray(c) for c in self.counts.values()), start=np.int64(0))

    def __bool__(self) -> bool:
        return bool(np.any(self.total()))

    def as_dict(self) -> dict[str, int | list[Any]]:
        """``{"sensor.kind": count}`` with plain Python numbers (e.g. for results.json)."""
        return {f"{s}.{k}": np.asarray(c).tolist() for (s, k), c in self.counts.items()}

    def __str__(self) -> str:
        rows = [f"{s}.{k}: {np.asarray(c).tolist()}" for (s, k), c in self.counts.items() if np.any(c)]
        return "FaultReport(" + (", ".join(rows) if rows else "no faults") + ")"


@boundary
def fault_report(x: ArrayLike, sensor: Is[str], *, full_scale: float | None = None, flags: bool = False) -> FaultReport:
    """Count the NaN and saturated samples of a series, per trial.

    E.g. ``fault_report(w_ib_b, "gyro", full_scale=fs)`` before an integrator that returns a plain array
    says which samples it will hold or fill (the NaN rows) and which were at the rails.

    Parameters
    ----------
    x : array_like, shape (..., N, k)
        Samples (e.g. rad/s or m/s^2); leading axes are trials, a row with any NaN is a dropout.
        Infinity is rejected.
    sensor : str
        Sensor name of the keys, e.g. ``"gyro"``.
    full_scale : float, optional
        Device range (same unit as ``x``): a valid row with any ``|x| >= full_scale`` is saturated.
        None (default): saturation is not counted.
    flags : bool
        Also keep the per-sample masks.

    Returns
    -------
    FaultReport
        ``counts[(sensor, "nan")]`` and, with ``full_scale``, ``counts[(sensor, "saturated")]``: int
        arrays of shape (...); with ``flags=True`` the boolean masks, shape (..., N), under the same keys.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import robust
    >>> w_ib_b = np.array([[0.1, 0.0, 0.0], [np.nan, 0.0, 0.0], [5.0, 0.0, 0.0]])
    >>> report = robust.fault_report(w_ib_b, "gyro", full_scale=4.0)
    >>> int(report["gyro", "nan"]), int(report["gyro", "saturated"])
    (1, 1)
    """
    a = as_array(x, "x", allow_nan=True, min_ndim=2)
    fs = range_limit(full_scale, "full_scale")
    masks = {(sensor, "nan"): np.any(np.isnan(a), axis=-1)}
    if full_scale is not None:
        masks[sensor, "saturated"] = ~masks[sensor, "nan"] & np.any(np.abs(a) >= fs, axis=-1)
    return FaultReport({key: m.sum(axis=-1) for key, m in masks.items()}, masks if flag(flags, "flags") else {})


@boundary
def hold(
    x: ArrayLike,
    *,
    leading: Annotated[str, Check("choice", options=LEADING)] = "raise",
    name: str = "x",
    axis: int = -2,
) -> tuple[np.ndarray, np.ndarray]:
    """Zero-order hold of NaN samples along the time axis.

    Parameters
    ----------
    x : array_like, shape (..., N, k) (or (..., N) with ``axis=-1``)
        Samples; a sample (row) with any NaN is a dropout. Infinity is rejected.
    leading : {"raise", "first", "zero"}
        NaN samples before the first valid one: raise ``ValueError``, take the first valid
        sample (back-fill), or set them to 0. A series with no valid sample raises.
    name : str
        Argument name in error messages.
    axis : int
        Time axis: -2 for vector series (default), -1 for scalar series.

    Returns
    -------
    filled : ndarray, same shape as ``x``
    held : ndarray of bool, shape of ``x`` without the vector axis
        True where a sample was replaced.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import robust
    >>> x, held = robust.hold(np.array([[1.0], [np.nan], [np.nan], [4.0]]))
    >>> x[:, 0], held
    (array([1., 1., 1., 4.]), array([False,  True,  True, False]))
    """
    choice(axis, "axis", (-1, -2))
    return _robust.hold(as_array(x, text(name, "name", empty=False), allow_nan=True, min_ndim=1), leading, name, axis)


@njit(cache=True)
def is_spike(x, k, thr):
    """Sample k is an isolated spike on some axis (needs 2 <= k < N - 2).

    With ``r_j = x_j - (x_j-1 + x_j+1) / 2`` (the deviation from the line
    through the neighbours): ``|r_k| > thr`` and ``|r_k| > 1.5 |r_k-+1|``. A
    spike S gives ``r_k = S`` and ``r_k-+1 = -S/2``, so its neighbours never
    qualify; smooth motion gives ``r ~ a w^2 dt^2``, a few mrad/s or cm/s^2
    at 100 Hz. NaN nearby never flags a spike.
    """
    for i in range(3):
        r0 = x[k, i] - (x[k - 1, i] + x[k + 1, i]) / 2
        rm = x[k - 1, i] - (x[k - 2, i] + x[k, i]) / 2
        rp = x[k + 1, i] - (x[k, i] + x[k + 2, i]) / 2
        if abs(r0) > thr and abs(r0) > 1.5 * abs(rm) and abs(r0) > 1.5 * abs(rp):
            return True
    return False


@njit(cache=True)
def _spike_mask(w, f, spike_gyro, spike_accel):
    n = w.shape[0]
    hit = np.zeros(n, dtype=np.bool_)
    for k in range(2, n - 2):
        hit[k] = is_spike(w, k, spike_gyro) or is_spike(f, k, spike_accel)
    return hit


@boundary
def despike(
    w_ib_b: Vec3Series,
    f_b: Vec3Series,
    spike_gyro: Annotated[float, Check("scalar", positive=True, allow_inf=True)],
    spike_accel: Annotated[float, Check("scalar", positive=True, allow_inf=True)],
) -> tuple[Array, Array, NDArray[np.bool_]]:
    """Mark isolated IMU spikes as dropouts (NaN), e.g. before :func:`navlib.filters.zupt.detect_static`.

    The test of :func:`is_spike` (also applied by :func:`screen`): a sample deviating from the line through its neighbours by more
    than the threshold, and by 1.5 times more than either neighbour does.
    Two adjacent spikes are not found (each hides the other). Spiky samples
    inflate the detector's variance test and hide stances; as NaN they are
    left out of it and held by the filters that hold dropouts.

    Parameters
    ----------
    w_ib_b, f_b : array_like, shape (N, 3)
        Gyro (rad/s) and accelerometer (m/s^2) samples; NaN allowed.
    spike_gyro, spike_accel : float
        Thresholds (rad/s, m/s^2); inf disables a sensor's test.

    Returns
    -------
    w_ib_b, f_b : ndarray, shape (N, 3)
        Copies with the spiky samples (both sensors) set to NaN.
    spikes : ndarray of bool, shape (N,)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import robust
    >>> f_b = np.tile([0.0, 0.0, 9.8], (6, 1))
    >>> w_ib_b = np.zeros((6, 3))
    >>> w_ib_b[3, 0] = 5.0                                            # one isolated gyro spike (rad/s)
    >>> w, f, spiked = robust.despike(w_ib_b, f_b, spike_gyro=1.0, spike_accel=np.inf)
    >>> spiked, w[3]
    (array([False, False, False,  True, False, False]), array([nan, nan, nan]))
    """
    w = as_array(w_ib_b, "w_ib_b", tail=(3,), min_ndim=1, allow_nan=True)
    f = as_array(f_b, "f_b", tail=(3,), min_ndim=1, allow_nan=True)
    if w.ndim != 2 or f.shape != w.shape:
        raise ValueError(f"f_b: expected the shape (N, 3) of w_ib_b {w.shape}, got {f.shape}")
    hit = _spike_mask(kernel_array(w), kernel_array(f), spike_gyro, spike_accel)
    w, f = w.copy(), f.copy()
    w[hit], f[hit] = np.nan, np.nan
    return w, f, hit


def longest_repeat(x: ArrayLike, valid: ArrayLike | None = None) -> NDArray[np.int64]:
    """Length of the longest run of one repeated reading, per component, over the valid samples.

    The window-level companion of :func:`stuck_mask`: a static window whose output repeats one value
    over most of its samples comes from a frozen sensor. A dropout (invalid sample) neither breaks nor
    extends a run.

    Parameters
    ----------
    x : array_like, shape (..., N, k)
        Samples; leading axes are trials.
    valid : array_like of bool, shape (..., N), optional
        Samples to consider (default: those without NaN).

    Returns
    -------
    run : ndarray of int, shape (..., k)
        1 where no reading repeats; 0 for a component with no valid sample.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import robust
    >>> robust.longest_repeat(np.array([[1.0, 0.1], [1.0, 0.2], [1.0, 0.3], [2.0, 0.3]]))
    array([3, 2])
    """
    x = as_array(x, "x", allow_nan=True)
    if x.ndim < 2 or x.shape[-2] == 0:
        raise ValueError(f"x: expected samples of shape (..., N, k), got {x.shape}")
    valid = np.all(np.isfinite(x), -1) if valid is None else booleans(valid, "valid", shape=x.shape[:-1], of="x")
    n, k = x.shape[-2:]
    runs = _longest_runs(kernel_array(x.reshape(-1, n, k)), kernel_array(valid.reshape(-1, n)))
    return runs.reshape(x.shape[:-2] + (k,))


@njit(cache=True)
def _longest_runs(x, valid):
    """:func:`longest_repeat` of ``x`` (B, N, k) over the samples where ``valid`` (B, N)."""
    out = np.zeros((x.shape[0], x.shape[2]), dtype=np.int64)
    for b in range(x.shape[0]):
        for j in range(x.shape[2]):
            run = longest = 0
            last = 0.0
            for i in range(x.shape[1]):
                if not valid[b, i]:
                    continue  # a dropout neither breaks nor extends a run
                run = run + 1 if run > 0 and x[b, i, j] == last else 1
                last = x[b, i, j]
                longest = max(longest, run)
            out[b, j] = longest
    return out


@boundary
def stuck_mask(
    x: ArrayLike, run: Annotated[int, Check("integer", minimum=2)], *, name: str = "x", axis: int = -2
) -> NDArray[np.bool_]:
    """Samples of a sensor that stopped updating: some component repeats exactly over ``run`` samples.

    Real sensor noise makes an exact repeat of a floating-point reading over a
    few samples essentially impossible, so such a run is a frozen or latched
    output (a stalled bus, a driver re-sending its last value). Every sample of
    the run is marked, from its first sample until the value changes. NaN is
    never a repeat. Quantised sensors whose noise is below one count repeat by
    chance: choose ``run`` long enough that chance runs are negligible.

    Parameters
    ----------
    x : array_like, shape (..., N, k) (or (..., N) with ``axis=-1``)
        Samples; leading axes are trials. Infinity is rejected.
    run : int
        Shortest run of equal values that counts (>= 2).
    name : str
        Argument name in error messages.
    axis : int
        Time axis: -2 for vector series (default), -1 for scalar series.

    Returns
    -------
    stuck : ndarray of bool, shape (..., N)
        True where some component of the sample belongs to such a run.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import robust
    >>> x = np.array([[0.1], [0.2], [0.2], [0.2], [0.2], [0.5]])
    >>> robust.stuck_mask(x, run=3)                                   # the frozen run of 0.2
    array([False,  True,  True,  True,  True, False])
    """
    return _robust.stuck_mask(_series(x, name, axis), run)


def _series(x: ArrayLike, name: str, axis: int) -> np.ndarray:
    """``x`` validated as samples (..., N, k) with time on ``axis`` (-1: a scalar series, given a k = 1 axis)."""
    choice(axis, "axis", (-1, -2))
    a = as_array(x, text(name, "name", empty=False), allow_nan=True, min_ndim=-axis)
    return a[..., None] if axis == -1 else a


def stuck_samples(
    x: ArrayLike, run: int | None, *, full_scale: float | None = None, name: str = "x", axis: int = -2
) -> NDArray[np.bool_]:
    """Stuck samples of a filter's sensor input: :func:`stuck_mask`, as every navlib filter applies it.

    Only series (trials) that are noisy from the start are checked: a series whose first value repeats
    ``run`` times on some component is a noise-free simulation or a quantised sensor at rest, not a
    frozen one. Values at the rails (``|x| >= full_scale``) are saturated, never stuck.

    Parameters
    ----------
    x : array_like, shape (..., N, k) (or (..., N) with ``axis=-1``)
        Samples; leading axes are trials; NaN is never a repeat. Infinity is rejected.
    run : int or None
        Shortest run of equal values that counts (>= 2, e.g. from :meth:`navlib.imu.SensorLimits.stuck_samples`); None: no check.
    full_scale : float, optional
        Device range (same unit as ``x``).
    name : str
        Argument name in error messages.
    axis : int
        Time axis: -2 for vector series (default), -1 for scalar series.

    Returns
    -------
    stuck : ndarray of bool, shape (..., N)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import robust
    >>> rng = np.random.default_rng(0)
    >>> x = rng.standard_normal((8, 3))
    >>> x[3:7] = x[3]                                                 # frozen for four samples
    >>> robust.stuck_samples(x, run=3)
    array([False, False, False,  True,  True,  True,  True, False])
    """
    a = _series(x, name, axis)
    if run is None:
        return _robust.stuck_samples(a, None)
    return _robust.stuck_samples(a, integer(run, "run", minimum=2), range_limit(full_scale, "full_scale"))


class Screened(NamedTuple):
    """IMU samples after :func:`screen`: what a filter's equations consume.

    Attributes
    ----------
    imu : ImuSamples
        The samples as given (the accelerometer is read from ``imu.f_b``, with the flags below).
    w_ib_b : ndarray, shape (..., N, 3)
        Gyro with every unusable sample (``("gyro", "nan" | "spike")``) replaced by the last used one, 0
        before the first, and the stuck axes of a stuck sample (``("gyro", "stuck")``) held alone, at the run's
        value when the run continues the signal (frozen at its last reading), else at the last used value
        (latched elsewhere): the attitude filters' hold. With nothing to hold, the gyro as given (``imu.w_ib_b``,
        or its contiguous copy).
    fresh : ndarray of bool, shape (..., N)
        The gyro sample measures the motion (at least one live axis); saturated samples are used.
    m_b : ndarray, shape (..., N, 3), or None
        Magnetometer (uT) as given, or None.
    dt : ndarray, shape (N,)
        Sample intervals (s).
    typical_dt : float
        Their median (s): the interval the limits' defaults are scaled by.
    max_dt : float
        Longest interval integrated (s); ``faults.flags["clock", "jump"]`` marks the longer ones.
    faults : FaultReport
        Counts, shape (...), and per-sample flags, shape (..., N), of every fault found: ``gyro``
        ``nan``/``stuck``/``spike``/``saturated``, ``accel`` ``nan``/``spike``/``freefall``/``saturated``, ``mag``
        ``nan``/``saturated`` (with ``m_b``), ``clock`` ``jump``. Each gyro sample has at most one of
        stuck, nan, spike (in that order); each accelerometer sample at most one of nan, spike, free fall.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import imu, robust
    >>> w_ib_b = 1e-3 * np.sin(np.arange(30.0))[:, None] + np.zeros((30, 3))
    >>> f_b = [0.0, 0.0, 9.8] + 1e-2 * np.cos(np.arange(30.0))[:, None]
    >>> s = robust.screen(imu.ImuSamples(w_ib_b, f_b, 0.01))
    >>> s.w_ib_b.shape, s.dt.shape, s.max_dt
    ((30, 3), (30,), 0.1)
    """

    imu: ImuSamples
    w_ib_b: np.ndarray
    fresh: np.ndarray
    m_b: np.ndarray | None
    dt: np.ndarray
    typical_dt: float
    max_dt: float
    faults: FaultReport


@boundary
def screen(imu: Is[ImuSamples], m_b: Vec3Series | None = None) -> Screened:
    """Find the faults of IMU samples, per their :class:`~navlib.imu.SensorLimits`, before any filter runs.

    Parameters
    ----------
    imu : ImuSamples
        Gyro and accelerometer samples, shape (..., N, 3), with their intervals and limits.
    m_b : array_like, shape (..., N, 3), optional
        Magnetometer samples (uT); NaN marks a missing sample.

    Returns
    -------
    Screened
        The held gyro, the magnetometer and the :class:`FaultReport` of the faults found.

    Raises
    ------
    ValueError
        If the gyro turns more than :data:`navlib._validate.MAX_TURN_PER_SAMPLE` within one integrated
        interval (``dt`` in the wrong unit).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import imu, robust
    >>> w_ib_b = 1e-3 * np.sin(np.arange(30.0))[:, None] + np.zeros((30, 3))
    >>> f_b = [0.0, 0.0, 9.8] + 1e-2 * np.cos(np.arange(30.0))[:, None]
    >>> w_ib_b[10] = np.nan                                           # a gyro dropout
    >>> s = robust.screen(imu.ImuSamples(w_ib_b, f_b, 0.01))
    >>> int(s.faults["gyro", "nan"]), bool(s.fresh[10]), s.typical_dt
    (1, False, 0.01)
    """
    lim, w, f, dts = imu.limits, imu.w_ib_b, imu.f_b, imu.dt
    lead, n = w.shape[:-2], w.shape[-2]
    T = math.prod(lead)
    if m_b is not None:  # of the right shape, its magnitudes are checked in the scan (as_array's, in parallel)
        m_b = real(m_b, "m_b")
        if m_b.shape != w.shape:
            m_b = same_shape(as_array(m_b, "m_b", tail=(3,), finite=False), "m_b", w.shape, of="w_ib_b")
    typical = float(np.median(dts))
    max_dt, run = lim.jump_limit(typical), lim.stuck_samples(typical)
    tests = np.array(
        [
            max_dt,
            run,
            lim.full_scale_gyro,
            lim.full_scale_accel,
            lim.full_scale_mag,
            lim.spike_gyro,
            lim.spike_accel,
            lim.freefall_accel,
        ]
    )
    wf, ff = kernel_array(w.reshape(T, n, 3)), kernel_array(f.reshape(T, n, 3))
    mf = np.zeros((1, 1, 3)) if m_b is None else kernel_array(m_b.reshape(T, n, 3))
    flags, stuck_axes = np.zeros((len(_KEYS), T, n), dtype=bool), np.zeros((T, n, 3), dtype=bool)
    turn, huge_m = np.zeros(T), np.zeros(T, dtype=bool)
    held, fresh, gate = np.empty_like(wf), np.empty((T, n), dtype=bool), lim.gyro_jump or 0.0
    as_given = np.zeros(T, dtype=bool)
    run_chunks(
        lambda t0, t1: _scan_and_hold(
            t0, t1, (wf, ff, mf, dts), tests, gate, flags, turn, stuck_axes, huge_m, held, fresh, as_given
        ),
        T,
    )
    if as_given.all():  # nothing held: the gyro as given (held's memory was never touched)
        held = wf
    else:
        for t in np.flatnonzero(as_given):
            held[t] = wf[t]
    if huge_m.any():
        as_array(m_b, "m_b", tail=(3,), finite=False)  # raises naming the fault
    refuse_turn(float(turn.max()))  # (clock jumps are not integrated)
    _freefall_runs(flags[6], dts, lim.freefall_time)
    counts = np.zeros((len(_KEYS), T), dtype=np.int64)
    run_chunks(lambda t0, t1: _spikes_and_counts(t0, t1, flags, counts), T)  # (numpy would do it serially)
    keys = _KEYS if m_b is not None else [key for key in _KEYS if key[0] != "mag"]
    found = {key: flags[_KEYS.index(key)].reshape(lead + (n,)) for key in keys}
    counted = {key: counts[_KEYS.index(key)].reshape(lead) for key in keys}
    report = FaultReport({key: c if lead else c[()] for key, c in counted.items()}, found)
    return Screened(imu, held.reshape(w.shape), fresh.reshape(lead + (n,)), m_b, dts, typical, max_dt, report)


_KEYS = [
    ("gyro", "stuck"),
    ("gyro", "nan"),
    ("gyro", "spike"),
    ("gyro", "saturated"),
    ("accel", "nan"),
    ("accel", "spike"),
    ("accel", "freefall"),
    ("accel", "saturated"),
    ("mag", "nan"),
    ("mag", "saturated"),
    ("clock", "jump"),
]
"""What :func:`screen` flags, in the order of its flag array."""


@njit(cache=True, nogil=True)
def _spikes_and_counts(t0, t1, flags, counts):
    """Trials t0 to t1 - 1 of ``flags`` (:data:`_KEYS`): an accelerometer spike is a spike, not free fall; then
    ``counts`` of every flag (:func:`navlib._kernels.count_flags`)."""
    for t in range(t0, t1):
        for k in range(flags.shape[2]):
            if flags[5, t, k]:
                flags[6, t, k] = False
    count_flags(t0, t1, flags, counts)


def _freefall_runs(low: np.ndarray, dts: np.ndarray, min_time: float) -> None:
    """Keep, in place, only the runs of ``low`` (T, N) samples whose intervals sum to at least ``min_time``."""
    for t in np.flatnonzero(low.any(-1)):
        edges = np.flatnonzero(np.diff(np.concatenate([[0], low[t].astype(np.int8), [0]])))
        for a, b in zip(edges[::2], edges[1::2], strict=True):
            if dts[a:b].sum() < min_time:
                low[t, a:b] = False


@njit(cache=True, nogil=True)
def _scan_and_hold(t0, t1, samples, tests, gate, flags, turn, stuck_axes, huge_m, held, fresh, as_given):
    """Trials t0 to t1 - 1 of ``samples = (w, f, m, dts)``, one at a time: scanned (:func:`_scan`), then its gyro
    held (:func:`_gyro_hold`, which needs only the trial's gyro flags) while its samples are still in cache: a batch
    too large for the cache is read from memory once, not once per pass. A trial with nothing to hold (no stuck, NaN
    or spike sample, no step gate) is used as given: ``fresh[t]`` all True, ``as_given[t]`` True and ``held[t]`` left
    to the caller (no copy of the gyro written, and read again, for nothing)."""
    w, f, m, dts = samples
    for t in range(t0, t1):
        _scan(t, t + 1, w, f, m, dts, tests, flags, turn, stuck_axes, huge_m)
        if gate > 0.0 or _any_gyro_fault(flags, t):
            _gyro_hold(t, t + 1, w, flags, stuck_axes, gate, held, fresh)
        else:
            fresh[t, :] = True
            as_given[t] = True


@njit(cache=True, inline="always")
def _any_gyro_fault(flags, t):
    """Has trial t a stuck, NaN or spike gyro sample (:data:`_KEYS` 0 to 2)?"""
    for k in range(flags.shape[2]):
        if flags[0, t, k] or flags[1, t, k] or flags[2, t, k]:
            return True
    return False


@njit(cache=True, nogil=True)
def _scan(t0, t1, w, f, m, dts, tests, flags, turn, stuck_axes, huge_m):
    """Trials t0 to t1 - 1 of the samples ``w``, ``f`` (T, N, 3) and ``m`` ((T, N, 3), or (1, 1, 3): none):
    every flag of :data:`_KEYS` into ``flags`` (K, T, N), but for free fall the samples of low norm (the
    caller keeps the long runs), ``stuck_axes`` (T, N, 3): which gyro axes are stuck, and ``turn[t]``, the
    largest turn ``|w| dt`` over an integrated interval; ``huge_m[t]``: a finite magnetometer component of
    ``MAX_MAGNITUDE`` or more (:func:`navlib._validate.as_array`'s limit).
    ``tests = [max_dt, stuck run (0: off), full scales (gyro, accel, mag), spike thresholds (gyro, accel),
    free-fall threshold]``."""
    max_dt, run, fs_w, fs_f, fs_m, low = tests[0], int(tests[1]), tests[2], tests[3], tests[4], tests[7]
    N, use_mag, spikes = w.shape[1], m.shape[1] == w.shape[1], tests[5] < np.inf or tests[6] < np.inf
    for t in range(t0, t1):
        _gyro_scan(t, w, dts, max_dt, run, fs_w, stuck_axes, turn)
        wt, ft, mt = w[t], f[t], m[t if use_mag else 0]
        stuck, nan_w, spike_w, rails_w = flags[0, t], flags[1, t], flags[2, t], flags[3, t]
        nan_f, spike_f, free, rails_f = flags[4, t], flags[5, t], flags[6, t], flags[7, t]
        nan_m, rails_m, jump = flags[8, t], flags[9, t], flags[10, t]
        axes = stuck_axes[t]
        for k in range(N):
            stuck[k] = axes[k, 0] or axes[k, 1] or axes[k, 2]
            wx, wy, wz, fx, fy, fz = wt[k, 0], wt[k, 1], wt[k, 2], ft[k, 0], ft[k, 1], ft[k, 2]
            ok_w, ok_f = _finite3(wx, wy, wz), _finite3(fx, fy, fz)
            nan_w[k], nan_f[k] = not ok_w and not stuck[k], not ok_f
            rails_w[k], rails_f[k] = ok_w and _at_rails(wx, wy, wz, fs_w), ok_f and _at_rails(fx, fy, fz, fs_f)
            if spikes and ok_w and ok_f and 2 <= k < N - 2:
                spike_w[k] = is_spike(wt, k, tests[5])
                spike_f[k] = is_spike(ft, k, tests[6]) and not spike_w[k]
            free[k] = np.sqrt(fx * fx + fy * fy + fz * fz) < low  # NaN compares False
            if use_mag:
                mx, my, mz = mt[k, 0], mt[k, 1], mt[k, 2]
                ok_m = _finite3(mx, my, mz)
                nan_m[k], rails_m[k] = not ok_m, ok_m and _at_rails(mx, my, mz, fs_m)
                if ok_m and _at_rails(mx, my, mz, MAX_MAGNITUDE):
                    huge_m[t] = True
            jump[k] = dts[k] > max_dt


@njit(cache=True, inline="always")
def _finite3(x, y, z):
    return np.isfinite(x) and np.isfinite(y) and np.isfinite(z)


@njit(cache=True, inline="always")
def _at_rails(x, y, z, full_scale):
    return abs(x) >= full_scale or abs(y) >= full_scale or abs(z) >= full_scale


@njit(cache=True, inline="always")
def _gyro_scan(t, w, dts, max_dt, run, rail, stuck, turn):
    """Trial t of the gyro ``w`` (T, N, 3): ``turn[t]``, the largest turn ``|w| dt`` over an integrated interval
    (``dt <= max_dt``; NaN ignored), and with ``run > 0`` the stuck axes ``stuck[t]`` (N, 3) (values at ``rail``
    excepted) of a trial whose gyro is noisy from the start (no axis repeats its first value ``run`` times)."""
    N = w.shape[1]
    big = 0.0
    for k in range(N):
        if dts[k] <= max_dt:
            a = np.sqrt(w[t, k, 0] * w[t, k, 0] + w[t, k, 1] * w[t, k, 1] + w[t, k, 2] * w[t, k, 2]) * dts[k]
            if a > big:
                big = a
    turn[t] = big
    if run == 0:
        return
    noisy = True
    for c in range(3):
        k = 0
        while k < N and w[t, k, c] == w[t, 0, c]:
            k += 1
        noisy = noisy and k < run
    if noisy:
        stuck_runs(t, t + 1, w, run, rail, stuck)


@njit(cache=True, inline="always")
def _axis(v, stuck, starts, g, p):
    """One gyro axis of a stuck sample: (value held, the one before it) from the last used ``g`` and the one before,
    ``p``. A live axis is used. A stuck run that continues the signal (its first value within 3 times the last step
    of ``g``: an output frozen at its last reading) keeps that reading; one that starts with a step (an output
    latched at another value) is held at ``g``."""
    if not np.isfinite(v):
        return g, p
    if not stuck or starts and abs(v - g) <= 3.0 * abs(g - p):
        return v, g
    return g, p


@njit(cache=True, nogil=True)
def _gyro_hold(t0, t1, w, flags, stuck_axes, gate, held, fresh):
    """Trials t0 to t1 - 1: hold the last used gyro sample (0 before the first) over the NaN and spike samples
    of ``flags`` (:data:`_KEYS`) and over steps larger than ``gate`` on some axis (flagged as spikes;
    ``gate = 0``: off), unless the previous sample was such a step already (a sustained change is motion).
    A stuck sample holds only its stuck axes (``stuck_axes``; :func:`_axis`): the live axes still measure the
    motion."""
    for t in range(t0, t1):
        gx = gy = gz = px = py = pz = 0.0
        was_step = False
        for k in range(w.shape[1]):
            wx, wy, wz = w[t, k, 0], w[t, k, 1], w[t, k, 2]
            if flags[0, t, k]:  # stuck: keep the live axes
                new = k == 0 or not flags[0, t, k - 1]
                sx, sy, sz = stuck_axes[t, k, 0], stuck_axes[t, k, 1], stuck_axes[t, k, 2]
                gx, px = _axis(wx, sx, new or not stuck_axes[t, k - 1, 0], gx, px)
                gy, py = _axis(wy, sy, new or not stuck_axes[t, k - 1, 1], gy, py)
                gz, pz = _axis(wz, sz, new or not stuck_axes[t, k - 1, 2], gz, pz)
                held[t, k, 0], held[t, k, 1], held[t, k, 2] = gx, gy, gz
                fresh[t, k] = not (sx and sy and sz)  # all stuck: nothing measured
                continue
            use = not (flags[0, t, k] or flags[1, t, k] or flags[2, t, k])
            if (
                use
                and gate > 0.0
                and not was_step
                and k > 0
                and (abs(wx - gx) > gate or abs(wy - gy) > gate or abs(wz - gz) > gate)
            ):
                flags[2, t, k], was_step, use = True, True, False
            if use:
                gx, gy, gz, px, py, pz, was_step = wx, wy, wz, gx, gy, gz, False
            held[t, k, 0], held[t, k, 1], held[t, k, 2] = gx, gy, gz
            fresh[t, k] = use
