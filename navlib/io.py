"""Real sensor logs into navlib's conventions: ENU navigation frame, right-front-up body frame, SI units, seconds.

Every reader returns a :class:`Recording` whose arrays are already converted -- gyro ``w_ib_b`` in rad/s,
accelerometer ``f_b`` as specific force in m/s^2 (about +9.8 on the up axis at rest), magnetometer
``m_b`` in uT, pressure in Pa, time in s from the first sample -- and which lists what was done to each
column in ``conversions`` (unit factor, axis mapping, timing repairs). ``recording.imu()`` gives the
:class:`navlib.imu.ImuSamples` the filters take.

* :func:`read_csv` / :func:`from_dataframe`: any table, columns named per sensor, a unit per sensor
  (:data:`UNITS`), the time column in s, ms, us, ns or ISO timestamps, and the sensor-to-body axes as a
  signed mapping (``"-y,x,z"``) or a matrix (:func:`navlib.attitude.mount_matrix`).
* :func:`read_xio`: x-io Technologies CSV (Fusion examples, NGIMU / Gait-Tracking): ``Time (s)``,
  ``Gyroscope X (deg/s)``, ``Accelerometer X (g)``, optional ``Magnetometer X (uT)``.
* :func:`read_sensor_logger`: the Sensor Logger phone app's per-sensor CSV export (``Gyroscope.csv``,
  ``TotalAcceleration.csv`` or ``Accelerometer.csv``, ``Magnetometer.csv``, ``Barometer.csv``; columns
  ``time`` (ns since the epoch), ``seconds_elapsed``, ``z``, ``y``, ``x``). The Android convention is
  supported: specific force in m/s^2 including gravity (``TotalAcceleration.csv``), rad/s, uT, hPa; the
  phone's axes (x right, y up the screen, z out of the screen) are right-front-up for a phone lying
  face up with its top pointing forward. ``Accelerometer.csv`` without gravity is refused. iOS exports
  are read the same way; check the accelerometer's sign at rest (+9.8 on the up axis) before trusting them.
* :func:`read_euroc`: the EuRoC MAV dataset's ``imu0/data.csv`` (ns timestamps, rad/s, m/s^2).
* :func:`align`: a sensor logged at its own rate put on the IMU clock, NaN where there is no reading
  (the filters skip NaN samples), with the hold or interpolation made explicit.

Readers refuse, with the column named: a missing column, an unknown unit, repeated or out-of-order
timestamps (with counts; ``timing="sanitize"`` sorts and drops repeats instead, reported), and a unit
that the magnitudes contradict (e.g. a gyro in deg/s declared as rad/s: the message says what was
probably meant; ``check_units=False`` skips this).
"""
from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd

from . import attitude
from ._typing import Array, ArrayLike, Dcm, Times
from ._validate import as_array, choice, flag, instance, scalar, text, time_axis
from .imu import ImuSamples, SensorLimits
from .timing import TimingReport, intervals, sanitize
from .units import G0

__all__ = ["UNITS", "TIME_UNITS", "Recording", "read_csv", "from_dataframe", "read_xio", "read_sensor_logger",
           "read_euroc", "align"]

UNITS: dict[str, tuple[str, float]] = {
    "rad/s": ("gyro", 1.0), "deg/s": ("gyro", np.pi / 180), "dps": ("gyro", np.pi / 180),
    "m/s^2": ("accel", 1.0), "m/s2": ("accel", 1.0), "g": ("accel", G0), "mg": ("accel", G0 / 1000),
    "uT": ("mag", 1.0), "µT": ("mag", 1.0), "nT": ("mag", 1e-3), "mT": ("mag", 1e3), "gauss": ("mag", 100.0),
    "G": ("mag", 100.0), "mG": ("mag", 0.1),
    "Pa": ("baro", 1.0), "hPa": ("baro", 100.0), "mbar": ("baro", 100.0), "kPa": ("baro", 1000.0),
}
"""Unit name -> (sensor it belongs to, factor to navlib's unit: rad/s, m/s^2, uT, Pa)."""
TIME_UNITS: dict[str, float | None] = {"s": 1.0, "ms": 1e-3, "us": 1e-6, "ns": 1e-9, "iso": None}
"""Time column units -> factor to seconds (``"iso"``: date-time strings)."""

_FIELDS = {"gyro": "w_ib_b", "accel": "f_b", "mag": "m_b", "baro": "pressure"}
# Plausible medians of |x| in navlib units, and the largest physical value (MEMS ranges, Earth's surface).
_MEDIAN = {"accel": (3.0, 30.0), "mag": (5.0, 500.0), "baro": (3e4, 1.2e5)}
_MAX = {"gyro": 40.0}          # rad/s: the widest MEMS gyro range, +-2000 deg/s, is 34.9 rad/s


@dataclass(frozen=True)
class Recording:
    """A sensor log in navlib's conventions (see the module docstring).

    Attributes
    ----------
    time : ndarray, shape (N,)
        Sample times (s) from the first sample.
    w_ib_b, f_b, m_b : ndarray, shape (N, 3), or None
        Gyro (rad/s), specific force (m/s^2), magnetic field (uT) in the right-front-up body frame;
        NaN where a sensor has no reading at that time.
    pressure : ndarray, shape (N,), or None
        Static pressure (Pa).
    start : float or numpy.datetime64 or None
        The first sample's time on the source's clock (s, or a date-time for ISO/epoch stamps).
    source : str
        Where the data came from (a path or a description).
    conversions : tuple of str
        What was done to the columns, one line each (printed by ``str(recording)``).
    timing : navlib.timing.TimingReport or None
        With ``timing="sanitize"``: the repeated and out-of-order samples found and removed.
    """
    time: np.ndarray
    w_ib_b: np.ndarray | None = None
    f_b: np.ndarray | None = None
    m_b: np.ndarray | None = None
    pressure: np.ndarray | None = None
    start: float | np.datetime64 | None = None
    source: str = ""
    conversions: tuple[str, ...] = ()
    timing: TimingReport | None = field(default=None, repr=False)

    @property
    def n(self) -> int:
        """Number of samples N."""
        return self.time.size

    @property
    def dt(self) -> Array:
        """Interval covered by each sample (s), shape (N,): ``t[k] - t[k-1]``, the first one repeating the second."""
        dt = intervals(self.time)
        return np.concatenate([dt[:1], dt])

    def imu(self, limits: SensorLimits | None = None) -> ImuSamples:
        """The gyro and accelerometer samples with their intervals as :class:`navlib.imu.ImuSamples`, with the
        sensors' ``limits`` (:class:`navlib.imu.SensorLimits`; default: no ranges, navlib's fault tests)."""
        if self.w_ib_b is None or self.f_b is None:
            raise ValueError(f"recording: has no {'gyro' if self.w_ib_b is None else 'accelerometer'} samples")
        return ImuSamples(self.w_ib_b, self.f_b, self.dt, limits)

    def __str__(self) -> str:
        rate = 1.0 / np.median(np.diff(self.time))
        sensors = ", ".join(k for k, v in _FIELDS.items() if getattr(self, v) is not None)
        lines = [f"Recording of {self.n} samples over {self.time[-1]:.3f} s (median {rate:.4g} Hz): {sensors}",
                 f"  source: {self.source}"] + [f"  {c}" for c in self.conversions]
        return "\n".join(lines)


def _unit(sensor: str, unit: str) -> float:
    if unit not in UNITS or UNITS[unit][0] != sensor:
        known = [u for u, (s, _) in UNITS.items() if s == sensor]
        raise ValueError(f"units[{sensor!r}]: unknown unit {unit!r} for the {sensor}; known: {known}")
    return UNITS[unit][1]


def _check_magnitude(sensor: str, x: np.ndarray, unit: str) -> None:
    """Refuse values that the declared unit makes physically implausible, saying what was probably meant."""
    norm = np.abs(x) if x.ndim == 1 else np.linalg.norm(x, axis=-1)
    norm = norm[np.isfinite(norm)]
    if norm.size == 0:
        return
    if sensor == "gyro" and norm.max() > _MAX["gyro"]:
        raise ValueError(f"units['gyro']: |w| reaches {norm.max():.4g} rad/s read as {unit!r}, beyond any MEMS "
                         f"gyro (+-2000 deg/s = 34.9 rad/s); is the column in deg/s? (check_units=False to accept)")
    if sensor in _MEDIAN:
        lo, hi = _MEDIAN[sensor]
        med = float(np.median(norm))
        if not lo <= med <= hi:
            hint = {"accel": "g or m/s^2 (or gravity removed: navlib needs specific force including gravity)",
                    "mag": "uT, nT or gauss", "baro": "Pa or hPa"}[sensor]
            raise ValueError(f"units[{sensor!r}]: median magnitude {med:.4g} in navlib units after reading the "
                             f"column as {unit!r}, expected {lo:g}..{hi:g}; check the unit ({hint}); "
                             f"check_units=False to accept")


def _seconds(values: pd.Series, unit: str) -> tuple[np.ndarray, float | np.datetime64]:
    """Time column -> (seconds from the first sample, the first sample's stamp)."""
    factor = TIME_UNITS[choice(unit, "time_unit", tuple(TIME_UNITS))]
    if factor is None:
        stamps = pd.to_datetime(values, errors="raise").to_numpy(dtype="datetime64[ns]")
        return (stamps - stamps[0]).astype(np.int64) * 1e-9, stamps[0]
    raw = pd.to_numeric(values, errors="coerce").to_numpy(dtype=float)
    if not np.all(np.isfinite(raw)):
        raise ValueError(f"time: {int(np.sum(~np.isfinite(raw)))} non-numeric or missing timestamps")
    if unit == "ns":                                   # epoch nanoseconds: subtract in integers, keep precision
        stamps = pd.to_numeric(values).to_numpy(dtype=np.int64)
        return (stamps - stamps[0]) * 1e-9, np.datetime64(int(stamps[0]), "ns")
    return (raw - raw[0]) * factor, float(raw[0] * factor)


def _check_timing(t: np.ndarray, policy: str, name: str = "time") -> None:
    """With ``policy="raise"``, refuse repeated or out-of-order timestamps, with their counts."""
    n_back = int(np.count_nonzero(np.diff(t) < 0))
    n_same = int(np.count_nonzero(np.diff(np.sort(t)) == 0))
    if policy == "raise" and (n_back or n_same):
        raise ValueError(f"{name}: {n_same} repeated and {n_back} out-of-order timestamps in {t.size} samples; "
                         f"timing='sanitize' sorts them and drops repeats (keeping the first), reported in "
                         f"Recording.timing")


def from_dataframe(df: pd.DataFrame, *, time: str, time_unit: str = "s", units: Mapping[str, str],
                   gyro: Sequence[str] | None = None, accel: Sequence[str] | None = None,
                   mag: Sequence[str] | None = None, baro: str | None = None, axes: str | Dcm = "x,y,z",
                   timing: str = "raise", check_units: bool = True, source: str = "DataFrame") -> Recording:
    """A :class:`Recording` from a table with one row per sample.

    Parameters
    ----------
    df : pandas.DataFrame
    time : str
        Name of the time column.
    time_unit : {"s", "ms", "us", "ns", "iso"}
        Unit of the time column (``"ns"``: integer nanoseconds, e.g. since the epoch; ``"iso"``: date-time strings).
    units : mapping
        Unit per sensor present, e.g. ``{"gyro": "deg/s", "accel": "g", "mag": "uT"}``; see :data:`UNITS`.
    gyro, accel, mag : sequence of 3 str, optional
        Column names of the sensor's x, y, z axes (at least gyro and accelerometer for the IMU filters).
    baro : str, optional
        Column name of the static pressure.
    axes : str or array_like, shape (3, 3)
        Sensor-to-body mapping for the vector sensors (:func:`navlib.attitude.mount_matrix`): which sensor
        axis is body right, front, up, e.g. ``"-y,x,z"``; default: the sensor's axes are right-front-up.
    timing : {"raise", "sanitize"}
        Repeated or out-of-order timestamps raise (with counts), or are sorted and de-duplicated.
    check_units : bool
        Refuse magnitudes the declared unit makes implausible (default True).
    source : str
        Description kept on the recording.

    Returns
    -------
    Recording
    """
    instance(df, "df", pd.DataFrame, "a pandas.DataFrame")
    choice(timing, "timing", ("raise", "sanitize"))
    check_units = flag(check_units, "check_units")
    C_bs = attitude.mount_matrix(axes)
    text(time, "time", empty=False)
    instance(units, "units", Mapping, "a mapping of sensor to unit, e.g. {'gyro': 'deg/s'}")
    columns = {"gyro": gyro, "accel": accel, "mag": mag, "baro": baro}
    present = {s: c for s, c in columns.items() if c is not None}
    for sensor, cols in present.items():
        if sensor == "baro":
            text(cols, "baro", empty=False)
        elif isinstance(cols, str) or not isinstance(cols, Sequence) or len(cols) != 3 or \
                not all(isinstance(c, str) for c in cols):
            raise ValueError(f"{sensor}: expected the names of its x, y, z columns (3 strings), got {cols!r}")
    if not present:
        raise ValueError("gyro, accel, mag, baro: give the columns of at least one sensor")
    missing = [c for c in [time, *[x for c in present.values() for x in ([c] if isinstance(c, str) else c)]]
               if c not in df.columns]
    if missing:
        raise ValueError(f"columns: {missing} not in the table; it has {list(df.columns)}")
    t, start = _seconds(df[time], time_unit)
    _check_timing(t, timing)
    data, notes = {}, [f"time: column {time!r} in {time_unit} -> s from the first sample"]
    for sensor, cols in present.items():
        if sensor not in units:
            raise ValueError(f"units: no unit given for the {sensor} (e.g. units={{{sensor!r}: ...}})")
        factor = _unit(sensor, units[sensor])
        if sensor == "baro":
            x = _numeric(df, [cols])[:, 0] * factor
        else:                                   # three column names, checked above
            x = _numeric(df, list(cols)) * factor @ C_bs.T
        if check_units:
            _check_magnitude(sensor, x, units[sensor])
        data[_FIELDS[sensor]] = x
        notes.append(f"{sensor}: columns {cols} in {units[sensor]} x {factor:.6g} -> {_target(sensor)}"
                     + ("" if sensor == "baro" else f", axes {axes if isinstance(axes, str) else 'by matrix'}"))
    report = None
    if timing == "sanitize":
        keys = list(data)
        t, *values, report = sanitize(t, *(data[k] for k in keys))
        data = dict(zip(keys, values, strict=True))
        t = t - t[0]
        notes.append(f"timing: {report.n_duplicate} repeated timestamps dropped, {report.n_out_of_order} "
                     f"out-of-order samples moved ({report.n_in} -> {report.n_out} samples)")
    time_axis(t, "time")
    return Recording(t, **data, start=start, source=text(source, "source"), conversions=tuple(notes), timing=report)


def _numeric(df: pd.DataFrame, cols: list[str]) -> np.ndarray:
    """Columns as floats; empty cells are NaN (no reading), any other non-number is an error."""
    x = df[cols].apply(pd.to_numeric, errors="coerce")
    bad = x.isna() & df[cols].notna()
    if bad.any().any():
        col = bad.any().idxmax()
        raise ValueError(f"columns: {int(bad[col].sum())} non-numeric cells in {col!r}, e.g. {df[col][bad[col]].iloc[0]!r}")
    arr = x.to_numpy(dtype=float)
    if np.isinf(arr).any():
        raise ValueError(f"columns: infinite values in {cols}")
    return arr


def _target(sensor: str) -> str:
    return {"gyro": "rad/s", "accel": "m/s^2 (specific force)", "mag": "uT", "baro": "Pa"}[sensor]


def read_csv(path: str | Path, *, sep: str = ",", comment: str | None = None, **kwargs) -> Recording:
    """A :class:`Recording` from a CSV file: ``pandas.read_csv(path, sep, comment)`` then :func:`from_dataframe`.

    Parameters
    ----------
    path : str or Path
    sep, comment : str
        Passed to :func:`pandas.read_csv`.
    **kwargs
        The column, unit, axes and timing arguments of :func:`from_dataframe`.
    """
    df, source = _read_table(path, sep=text(sep, "sep", empty=False), comment=comment)
    return from_dataframe(df, source=source, **kwargs)


def read_xio(path: str | Path, *, axes: str | Dcm = "x,y,z", timing: str = "raise",
             check_units: bool = True) -> Recording:
    """An x-io Technologies CSV (Fusion example data, NGIMU; e.g. the Gait-Tracking walks).

    Columns ``Time (s)``, ``Gyroscope X/Y/Z (deg/s)``, ``Accelerometer X/Y/Z (g)`` and, when present,
    ``Magnetometer X/Y/Z (uT)``. The accelerometer is specific force in g (+1 g on z lying flat).

    Parameters
    ----------
    path : str or Path
    axes, timing, check_units
        As in :func:`from_dataframe`. x-io's axes are used as the body axes unless ``axes`` maps them.
    """
    df, source = _read_table(path)
    cols = {"gyro": [f"Gyroscope {a} (deg/s)" for a in "XYZ"], "accel": [f"Accelerometer {a} (g)" for a in "XYZ"]}
    units = {"gyro": "deg/s", "accel": "g"}
    if "Magnetometer X (uT)" in df.columns:
        cols["mag"], units["mag"] = [f"Magnetometer {a} (uT)" for a in "XYZ"], "uT"
    return from_dataframe(df, time="Time (s)", units=units, axes=axes, timing=timing, check_units=check_units,
                          source=source, **cols)


def _path(path: str | os.PathLike, name: str) -> Path:
    return Path(instance(path, name, (str, os.PathLike), "a file system path (str or pathlib.Path)"))


def _read_table(path: str | Path, **read_csv) -> tuple[pd.DataFrame, str]:
    """A CSV file as a DataFrame (spaces after separators ignored), and its path for ``Recording.source``."""
    path = _path(path, "path")
    if not path.is_file():
        raise ValueError(f"path: no such file {str(path)!r}")
    df = pd.read_csv(path, skipinitialspace=True, **read_csv)
    if df.empty:
        raise ValueError(f"path: {str(path)!r} has a header but no samples")
    return df, str(path)


def _stamps(df: pd.DataFrame) -> np.ndarray:
    """A Sensor Logger file's ``time`` column: integer nanoseconds since the epoch."""
    return pd.to_numeric(df["time"]).to_numpy(dtype=np.int64)


def _logger_file(directory: Path, name: str) -> pd.DataFrame:
    df = pd.read_csv(directory / name)
    missing = [c for c in ("time", "x", "y", "z") if c not in df.columns]
    if missing:
        raise ValueError(f"directory: {name} lacks the columns {missing} of a Sensor Logger export")
    return df


def read_sensor_logger(directory: str | Path, *, axes: str | Dcm = "x,y,z", method: str = "hold",
                       max_gap: float | None = None, timing: str = "raise", check_units: bool = True) -> Recording:
    """A Sensor Logger (phone app) CSV export: one file per sensor, put on the gyroscope's clock.

    Reads ``Gyroscope.csv`` (rad/s), ``TotalAcceleration.csv`` (m/s^2 with gravity; ``Accelerometer.csv``
    alone, which has gravity removed, is refused), and when present ``Magnetometer.csv`` (uT) and
    ``Barometer.csv`` (``pressure`` in hPa). Timestamps are ``time`` in ns since the epoch. The other
    sensors are aligned to the gyroscope's samples with :func:`align` (``method``, ``max_gap``).

    Parameters
    ----------
    directory : str or Path
        The unzipped export.
    axes : str or array_like, shape (3, 3)
        Phone-to-body mapping (default: the phone's x right, y up the screen, z out of the screen are
        right-front-up, i.e. the phone lies face up, top forward).
    method : {"hold", "interpolate"}
    max_gap : float, optional
        Longest time (s) a reading is held or interpolated across; None: 1.5 of that sensor's median interval.
    timing, check_units
        As in :func:`from_dataframe`.
    """
    d = _path(directory, "directory")
    if not d.is_dir():
        raise ValueError(f"directory: no such directory {str(d)!r}")
    if not (d / "Gyroscope.csv").is_file():
        raise ValueError(f"directory: no Gyroscope.csv in {str(d)!r}")
    if not (d / "TotalAcceleration.csv").is_file():
        raise ValueError("directory: no TotalAcceleration.csv (Accelerometer.csv has gravity removed; "
                         "navlib needs specific force including gravity)")
    gyro = _logger_file(d, "Gyroscope.csv")
    _check_timing(_stamps(gyro), timing, "Gyroscope.csv")
    if timing == "sanitize":                 # the other sensors are put on this clock: repair it first
        gyro = gyro.sort_values("time", kind="stable").drop_duplicates("time")
    frame = pd.DataFrame({"time": gyro["time"], "gx": gyro["x"], "gy": gyro["y"], "gz": gyro["z"]})
    t_ns = _stamps(gyro)
    t_gyro = (t_ns - t_ns[0]) * 1e-9
    kw = {"gyro": ("gx", "gy", "gz")}
    units = {"gyro": "rad/s"}
    sources = {"accel": ("TotalAcceleration.csv", "m/s^2"), "mag": ("Magnetometer.csv", "uT"),
               "baro": ("Barometer.csv", "hPa")}
    for sensor, (name, unit) in sources.items():
        if not (d / name).is_file():
            continue
        df = pd.read_csv(d / name) if sensor == "baro" else _logger_file(d, name)
        cols = ["pressure"] if sensor == "baro" else ["x", "y", "z"]
        if sensor == "baro" and "pressure" not in df.columns:
            raise ValueError(f"directory: {name} lacks the column 'pressure'")
        stamps = _stamps(df)
        _check_timing(stamps, timing, name)
        t_s, x = (stamps - t_ns[0]) * 1e-9, df[cols].to_numpy(dtype=float)
        if timing == "sanitize":
            t_s, x, _ = sanitize(t_s, x)
        x = align(t_gyro, t_s, x, method=method, max_gap=max_gap)
        names = [f"{sensor}_{c}" for c in cols]
        frame[names] = x
        kw[sensor] = names[0] if sensor == "baro" else tuple(names)
        units[sensor] = unit
    return from_dataframe(frame, time="time", time_unit="ns", units=units, axes=axes, timing=timing,
                          check_units=check_units, source=str(d), **kw)


def read_euroc(path: str | Path, *, axes: str | Dcm = "x,y,z", timing: str = "raise",
               check_units: bool = True) -> Recording:
    """The EuRoC MAV dataset's IMU file (``mav0/imu0/data.csv``): ns timestamps, rad/s, m/s^2.

    Columns ``#timestamp [ns]``, ``w_RS_S_x [rad s^-1]`` ... ``a_RS_S_z [m s^-2]`` in the sensor frame S;
    give ``axes`` to map it to right-front-up.
    """
    df, source = _read_table(path)
    df.columns = [c.strip() for c in df.columns]
    gyro = [f"w_RS_S_{a} [rad s^-1]" for a in "xyz"]
    accel = [f"a_RS_S_{a} [m s^-2]" for a in "xyz"]
    return from_dataframe(df, time="#timestamp [ns]", time_unit="ns", units={"gyro": "rad/s", "accel": "m/s^2"},
                          gyro=gyro, accel=accel, axes=axes, timing=timing, check_units=check_units, source=source)


def align(t_target: Times, t_source: ArrayLike, x_source: ArrayLike, *, method: str = "hold",
          max_gap: float | None = None) -> Array:
    """Readings of one sensor on another sensor's clock; NaN where there is no reading to use.

    Parameters
    ----------
    t_target : array_like, shape (M,)
        Times to put the readings on (s, strictly increasing), e.g. the IMU's.
    t_source : array_like, shape (N,)
        Times of the readings (s, strictly increasing; same clock).
    x_source : array_like, shape (N,) or (N, k)
        The readings; NaN marks a missing one.
    method : {"hold", "interpolate"}
        ``"hold"``: the latest reading at or before each target time (zero-order hold; causal, what a
        filter running in real time would have). ``"interpolate"``: linear between the readings around it.
    max_gap : float, optional
        Longest time (s) a reading is held, or the longest interval interpolated across; beyond it the
        result is NaN. Default: 1.5 times the median interval of ``t_source``.

    Returns
    -------
    x : ndarray, shape (M,) or (M, k)
        NaN before the first reading, after ``max_gap`` without one, and (interpolation) after the last.
    """
    method = choice(method, "method", ("hold", "interpolate"))
    tt = time_axis(t_target, "t_target")
    ts = time_axis(t_source, "t_source")
    x = as_array(x_source, "x_source", allow_nan=True, min_ndim=1)
    if x.shape[0] != ts.size:
        raise ValueError(f"x_source: expected {ts.size} readings on axis 0 (one per t_source), got shape {x.shape}")
    gap = 1.5 * float(np.median(np.diff(ts))) if max_gap is None else scalar(max_gap, "max_gap", positive=True)
    x2 = x.reshape(ts.size, -1)
    k = np.searchsorted(ts, tt, side="right") - 1           # latest reading at or before each target time
    before = k < 0
    k = np.clip(k, 0, ts.size - 1)
    if method == "hold":
        out = x2[k]
        stale = before | (tt - ts[k] > gap)
    else:
        k1 = np.minimum(k + 1, ts.size - 1)
        span = ts[k1] - ts[k]
        w = np.where(span > 0, (tt - ts[k]) / np.where(span > 0, span, 1.0), 0.0)
        out = x2[k] + (x2[k1] - x2[k]) * w[:, None]
        stale = before | (tt > ts[-1]) | (span > gap)
    out = np.where(stale[:, None], np.nan, out)
    return out.reshape((tt.size,) + x.shape[1:])
