"""Real sensor logs into navlib's conventions: ENU navigation frame, right-front-up body frame, SI units, seconds.

Every reader returns a :class:`Recording` whose arrays are already converted -- gyro ``w_ib_b`` in rad/s,
accelerometer ``f_b`` as specific force in m/s^2 (about +9.8 on the up axis at rest), magnetometer
``m_b`` in uT, pressure in Pa, time in s from the first sample -- and which lists what was done to each
column in ``conversions`` (unit factor, axis mapping, timing repairs). ``recording.imu()`` gives the
:class:`navlib.imu.ImuSamples` the filters take.

* :func:`read_csv` / :func:`from_dataframe`: any table, columns named per sensor, a unit per sensor
  (:data:`UNITS`), the time column in s, ms, us, ns or ISO timestamps, and the sensor-to-body axes as a
  signed mapping (``"-y,x,z"``) or a matrix (:func:`navlib.attitude.mount_matrix`), for all sensors or per
  sensor; a mirror-image mapping only with ``mirror=True``.
* :func:`read_sensor_logger`: the Sensor Logger phone app's export, iOS and Android, every app version
  (platform from ``Metadata.csv`` or ``platform=``; iOS's reversed accelerometer signs and g units turned
  into specific force; ``Orientation.csv`` as the reference attitude ``q_bn_ref``).
* :func:`read_phyphox`: phyphox CSV exports. :func:`read_xio`: x-io NGIMU / Fusion CSV and the older
  x-IMU layout (``Packet number``, gauss; ``rate=``). :func:`read_euroc`: EuRoC's ``imu0/data.csv``.
* :func:`check_axes` (run by every reader): the gyro against the gravity and field directions; names an
  axis that looks flipped. ``str(recording)`` summarises the timing (median and mean rate, 99th-percentile
  interval, largest gap, repaired stamps).
* :func:`align`: a sensor logged at its own rate put on the IMU clock, NaN where there is no reading
  (the filters skip NaN samples). :func:`resample`: a uniform clock by the mean over each interval
  (noise densities survive) or by interpolation.
* :func:`start_at_rest`: gyro bias over a still stretch, magnetometer calibration when the recording
  allows, initial attitude.

Readers refuse, naming the file, the column and the fix: a missing column or file, an unknown unit,
repeated or out-of-order timestamps (with counts; ``timing="sanitize"`` sorts and drops repeats instead,
reported), and a unit that the magnitudes contradict (e.g. a gyro in deg/s declared as rad/s: the message
says what was probably meant; ``check_units=False`` skips this). What a reader had to assume (a platform
guessed from the files) is in ``conversions``.
"""

from __future__ import annotations

import re
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Annotated, Any, ParamSpec, TypeVar

import numpy as np
import pandas as pd

from . import _attitude, alignment, attitude, calibration, strapdown
from ._typing import Array, ArrayLike, Dcm, Times
from ._validate import (
    Check,
    FilePath,
    Flag,
    Is,
    Positive,
    as_array,
    booleans,
    boundary,
    choice,
    flag,
    scalar,
    text,
    time_axis,
)
from .imu import ImuSamples, SensorLimits
from .timing import TimingReport, sanitize
from .units import G0

_P = ParamSpec("_P")
_R = TypeVar("_R")

__all__ = [
    "UNITS",
    "TIME_UNITS",
    "Recording",
    "read_csv",
    "from_dataframe",
    "read_xio",
    "read_sensor_logger",
    "read_phyphox",
    "read_euroc",
    "align",
    "resample",
    "AxisCheck",
    "check_axes",
    "AXIS_CHECK_WINDOW",
    "AXIS_CHECK_RATIO",
    "STILL_LIMITS",
    "start_at_rest",
]

UNITS: dict[str, tuple[str, float]] = {
    "rad/s": ("gyro", 1.0),
    "deg/s": ("gyro", np.pi / 180),
    "dps": ("gyro", np.pi / 180),
    "m/s^2": ("accel", 1.0),
    "m/s2": ("accel", 1.0),
    "g": ("accel", G0),
    "mg": ("accel", G0 / 1000),
    "uT": ("mag", 1.0),
    "µT": ("mag", 1.0),
    "nT": ("mag", 1e-3),
    "mT": ("mag", 1e3),
    "gauss": ("mag", 100.0),
    "G": ("mag", 100.0),
    "mG": ("mag", 0.1),
    "Pa": ("baro", 1.0),
    "hPa": ("baro", 100.0),
    "mbar": ("baro", 100.0),
    "kPa": ("baro", 1000.0),
}
"""Unit name -> (sensor it belongs to, factor to navlib's unit: rad/s, m/s^2, uT, Pa)."""
TIME_UNITS: dict[str, float | None] = {"s": 1.0, "ms": 1e-3, "us": 1e-6, "ns": 1e-9, "iso": None}
"""Time column units -> factor to seconds (``"iso"``: date-time strings)."""

_FIELDS = {"gyro": "w_ib_b", "accel": "f_b", "mag": "m_b", "baro": "pressure"}
# Plausible medians of |x| in navlib units, and the largest physical value (MEMS ranges, Earth's surface).
_MEDIAN = {  # plausible median magnitudes (navlib units), and the units a column outside them was probably in
    "accel": (3.0, 30.0, "g or m/s^2 (or gravity removed: navlib needs specific force including gravity)"),
    "mag": (5.0, 500.0, "uT, nT or gauss"),
    "baro": (3e4, 1.2e5, "Pa or hPa"),
}
_MAX = {"gyro": 40.0}  # rad/s: the widest MEMS gyro range, +-2000 deg/s, is 34.9 rad/s


@dataclass(frozen=True)
class Recording:
    """A sensor log in navlib's conventions (see the module docstring).

    Attributes
    ----------
    time : ndarray, shape (N,)
        Sample times (s) from the first sample, strictly increasing: the readers check them once, and
        ``dt`` and the functions that take a recording use them as they are.
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
    q_bn_ref : ndarray, shape (N, 4), or None
        The source's own attitude estimate (e.g. a phone's ``Orientation.csv``) as navlib's ``q_bn``
        (body right-front-up to ENU, scalar first); which north it refers to is in ``conversions``.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import io
    >>> rec = io.Recording(time=np.array([0.0, 0.01, 0.02]), w_ib_b=np.zeros((3, 3)), f_b=np.tile([0.0, 0.0, 9.81], (3, 1)))
    >>> len(rec.time), rec.m_b is None
    (3, True)
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
    q_bn_ref: np.ndarray | None = field(default=None, repr=False)

    @property
    def n(self) -> int:
        """Number of samples N."""
        return self.time.size

    @property
    def dt(self) -> Array:
        """Interval covered by each sample (s), shape (N,): ``t[k] - t[k-1]``, the first one repeating the second."""
        dt = np.diff(self.time)
        return np.concatenate([dt[:1], dt])

    def imu(self, limits: SensorLimits | None = None) -> ImuSamples:
        """The gyro and accelerometer samples with their intervals as :class:`navlib.imu.ImuSamples`, with the
        sensors' ``limits`` (:class:`navlib.imu.SensorLimits`; default: no ranges, navlib's fault tests)."""
        if self.w_ib_b is None or self.f_b is None:
            raise ValueError(f"recording: has no {'gyro' if self.w_ib_b is None else 'accelerometer'} samples")
        return ImuSamples(self.w_ib_b, self.f_b, self.dt, limits)

    def __str__(self) -> str:
        sensors = ", ".join(k for k, v in _FIELDS.items() if getattr(self, v) is not None)
        lines = [
            f"Recording of {self.n} samples over {self.time[-1]:.3f} s: {sensors}",
            f"  source: {self.source}",
            _timing_summary(self.time, self.timing),
        ] + [f"  {c}" for c in self.conversions]
        return "\n".join(lines)


def _timing_summary(t: np.ndarray, report: TimingReport | None) -> str:
    """Median and mean rate, 99th-percentile interval, largest gap and repaired stamps: a bursty clock shows as
    a mean rate well below the median one and a 99th percentile far above the median interval."""
    dt = np.diff(t)
    k = int(np.argmax(dt))
    repaired = (
        "none" if report is None else (f"{report.n_duplicate} repeated dropped, {report.n_out_of_order} out of order moved")
    )
    return (
        f"  timing: median {1 / np.median(dt):.4g} Hz, mean {(t.size - 1) / (t[-1] - t[0]):.4g} Hz, "
        f"99th-percentile interval {1e3 * np.percentile(dt, 99):.4g} ms, largest gap {1e3 * dt[k]:.4g} ms "
        f"at {t[k]:.3f} s; repaired stamps: {repaired}"
    )


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
        raise ValueError(
            f"units['gyro']: |w| reaches {norm.max():.4g} rad/s read as {unit!r}, beyond any MEMS "
            f"gyro (+-2000 deg/s = 34.9 rad/s); is the column in deg/s? (check_units=False to accept)"
        )
    if sensor in _MEDIAN:
        lo, hi, hint = _MEDIAN[sensor]
        med = float(np.median(norm))
        if not lo <= med <= hi:
            raise ValueError(
                f"units[{sensor!r}]: median magnitude {med:.4g} in navlib units after reading the "
                f"column as {unit!r}, expected {lo:g}..{hi:g}; check the unit ({hint}); "
                f"check_units=False to accept"
            )


def _seconds(values: pd.Series, unit: str) -> tuple[np.ndarray, float | np.datetime64]:
    """Time column -> (seconds from the first sample, the first sample's stamp)."""
    factor = TIME_UNITS[choice(unit, "time_unit", tuple(TIME_UNITS))]
    if factor is None:
        stamps = pd.to_datetime(values, errors="raise").to_numpy(dtype="datetime64[ns]")
        return (stamps - stamps[0]).astype(np.int64) * 1e-9, stamps[0]
    raw = pd.to_numeric(values, errors="coerce").to_numpy(dtype=float)
    if not np.all(np.isfinite(raw)):
        raise ValueError(f"time: {int(np.sum(~np.isfinite(raw)))} non-numeric or missing timestamps")
    if unit == "ns":  # epoch nanoseconds: subtract in integers, keep precision
        stamps = pd.to_numeric(values).to_numpy(dtype=np.int64)
        return (stamps - stamps[0]) * 1e-9, np.datetime64(int(stamps[0]), "ns")
    return (raw - raw[0]) * factor, float(raw[0] * factor)


def _check_timing(t: np.ndarray, policy: str, name: str = "time") -> None:
    """With ``policy="raise"``, refuse repeated or out-of-order timestamps, with their counts."""
    n_back = int(np.count_nonzero(np.diff(t) < 0))
    n_same = int(np.count_nonzero(np.diff(np.sort(t)) == 0))
    if policy == "raise" and (n_back or n_same):
        raise ValueError(
            f"{name}: {n_same} repeated and {n_back} out-of-order timestamps in {t.size} samples; "
            f"timing='sanitize' sorts them and drops repeats (keeping the first), reported in "
            f"Recording.timing"
        )


@boundary
def from_dataframe(
    df: Is[pd.DataFrame],
    *,
    time: Annotated[str, Check("text", empty=False)],
    time_unit: str = "s",
    units: Annotated[Mapping[str, str], Check("instance", what="a mapping of sensor to unit, e.g. {'gyro': 'deg/s'}")],
    gyro: Sequence[str] | None = None,
    accel: Sequence[str] | None = None,
    mag: Sequence[str] | None = None,
    baro: Annotated[str, Check("text", empty=False)] | None = None,
    axes: str | Dcm | Mapping[str, str | Dcm] = "x,y,z",
    mirror: bool = False,
    timing: Annotated[str, Check("choice", options=("raise", "sanitize"))] = "raise",
    check_units: Flag = True,
) -> Recording:
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
    axes : str or array_like, shape (3, 3), or mapping
        Sensor-to-body mapping (:func:`navlib.attitude.mount_matrix`): which sensor axis is body right, front,
        up, e.g. ``"-y,x,z"``; one for all vector sensors, or one per sensor, e.g.
        ``{"gyro": "x,y,z", "accel": "x,y,z", "mag": "y,x,-z"}`` (sensors left out keep ``"x,y,z"``).
        Default: the sensors' axes are right-front-up.
    mirror : bool
        Accept a mapping that is a mirror image (one or three axes negated, determinant -1), as boards whose
        magnetometer is mounted the other way up need. Default False: a mirror is refused as a likely typo.
    timing : {"raise", "sanitize"}
        Repeated or out-of-order timestamps raise (with counts), or are sorted and de-duplicated.
    check_units : bool
        Refuse magnitudes the declared unit makes implausible (default True).

    Returns
    -------
    Recording
        ``source`` is ``"DataFrame"``; readers replace it with the file's path.

    Examples
    --------
    >>> import numpy as np
    >>> import pandas as pd
    >>> from navlib import io
    >>> df = pd.DataFrame({"t": [0.0, 0.01, 0.02], "gx": [0.0, 1.0, 2.0], "gy": 0.0, "gz": 0.0})
    >>> rec = io.from_dataframe(df, time="t", units={"gyro": "deg/s"}, gyro=["gx", "gy", "gz"])
    >>> np.round(rec.w_ib_b[:, 0], 6), rec.conversions[1]
    (array([0.      , 0.017453, 0.034907]), "gyro: columns ['gx', 'gy', 'gz'] in deg/s x 0.0174533 -> rad/s, axes 'x,y,z'")
    """
    mounts = _mounts(axes, flag(mirror, "mirror"))
    columns: dict[str, Any] = {"gyro": gyro, "accel": accel, "mag": mag, "baro": baro}  # checked below
    present = {s: c for s, c in columns.items() if c is not None}
    for sensor, cols in present.items():
        if sensor != "baro" and (
            isinstance(cols, str) or not isinstance(cols, Sequence) or len(cols) != 3 or not all(isinstance(c, str) for c in cols)
        ):
            raise ValueError(f"{sensor}: expected the names of its x, y, z columns (3 strings), got {cols!r}")
    if not present:
        raise ValueError("gyro, accel, mag, baro: give the columns of at least one sensor")
    missing = [
        c for c in [time, *[x for c in present.values() for x in ([c] if isinstance(c, str) else c)]] if c not in df.columns
    ]
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
        else:  # three column names, checked above
            x = _numeric(df, list(cols)) * factor @ mounts[sensor][0].T
        if check_units:
            _check_magnitude(sensor, x, units[sensor])
        data[_FIELDS[sensor]] = x
        notes.append(
            f"{sensor}: columns {cols} in {units[sensor]} x {factor:.6g} -> {_target(sensor)}"
            + ("" if sensor == "baro" else f", axes {mounts[sensor][1]}")
        )
    report = None
    if timing == "sanitize":
        keys = list(data)
        t, *values, report = sanitize(t, *(data[k] for k in keys))
        data = dict(zip(keys, values, strict=True))
        t = t - t[0]
        notes.append(
            f"timing: {report.n_duplicate} repeated timestamps dropped, {report.n_out_of_order} "
            f"out-of-order samples moved ({report.n_in} -> {report.n_out} samples)"
        )
    time_axis(t, "time")
    return Recording(t, **data, start=start, source="DataFrame", conversions=tuple(notes), timing=report)


def _mounts(axes: str | Dcm | Mapping[str, str | Dcm], mirror: bool) -> dict[str, tuple[np.ndarray, str]]:
    """Sensor -> (C_bs, how it reads in ``conversions``) for gyro, accel and mag."""
    per_sensor = axes if isinstance(axes, Mapping) else {s: axes for s in ("gyro", "accel", "mag")}
    unknown = set(per_sensor) - {"gyro", "accel", "mag"}
    if unknown:
        raise ValueError(f"axes: unknown sensors {sorted(unknown)}; give a mapping for 'gyro', 'accel', 'mag'")
    out = {}
    for sensor in ("gyro", "accel", "mag"):
        spec = per_sensor.get(sensor, "x,y,z")
        C = _mount(spec, mirror, f"axes[{sensor!r}]" if isinstance(axes, Mapping) else "axes")
        label = repr(spec) if isinstance(spec, str) else "by matrix"
        out[sensor] = (C, label + (" (a mirror image, mirror=True)" if np.linalg.det(C) < 0 else ""))
    return out


def _mount(spec: str | Dcm, mirror: bool, name: str) -> np.ndarray:
    """C_bs from :func:`navlib.attitude.mount_matrix`; with ``mirror`` a reflection (det -1) is accepted too."""
    try:
        return attitude.mount_matrix(spec)
    except ValueError as err:
        is_mirror = "mirror image" in str(err)
        if not (mirror and is_mirror):
            hint = "; if the board really is mirrored, pass mirror=True" if is_mirror else ""
            raise ValueError(f"{name}: {str(err).split(': ', 1)[-1]}{hint}") from None
    if isinstance(spec, str):  # a mirror string: flip one sign, build, flip the row back
        head, _, rest = spec.partition(",")
        head = head.strip()
        C = attitude.mount_matrix((head[1:] if head.startswith("-") else "-" + head.lstrip("+")) + "," + rest)
        C[0] = -C[0]
        return C
    C = as_array(spec, name, shape=(3, 3))
    if not np.allclose(C @ C.T, np.eye(3), atol=1e-9):
        raise ValueError(f"{name}: not orthonormal (C @ C.T != I); give a signed axis mapping such as '-y,x,z'")
    return C


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


def _finish(rec: Recording, source: str, check: str, notes: Sequence[str] = (), **extra: Any) -> Recording:
    """A reader's last step: its source and conversion notes on the recording, then :func:`check_axes`."""
    rec = replace(rec, source=source, conversions=rec.conversions + tuple(notes), **extra)
    if check != "off" and rec.w_ib_b is not None and (rec.f_b is not None or rec.m_b is not None):
        result = check_axes(rec, on_fail=check)
        rec = replace(rec, conversions=rec.conversions + (f"axis check: {result.message}",))
    return rec


CheckMode = Annotated[str, Check("choice", options=("warn", "raise", "off"))]
"""A reader's axis check (:func:`check_axes`): warn or raise on suspect axes, or ``"off"``: not run."""


@boundary
def read_csv(
    path: FilePath, *, sep: str = ",", comment: str | None = None, check: CheckMode = "warn", **kwargs: Any
) -> Recording:
    """A :class:`Recording` from a CSV file: ``pandas.read_csv(path, sep, comment)`` then :func:`from_dataframe`.

    Parameters
    ----------
    path : str or Path
    sep, comment : str
        Passed to :func:`pandas.read_csv`.
    check : {"warn", "raise", "off"}
        Run :func:`check_axes` on the result: warn about, or refuse, a sensor axis that looks flipped.
    **kwargs
        The column, unit, axes (per sensor, ``mirror``) and timing arguments of :func:`from_dataframe`.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> import numpy as np
    >>> from navlib import io
    >>> tmp = tempfile.TemporaryDirectory()
    >>> path = Path(tmp.name) / "log.csv"
    >>> _ = path.write_text("t,gx,gy,gz\\n0.00,0,0,90\\n0.01,0,0,90\\n")
    >>> rec = io.read_csv(path, time="t", units={"gyro": "deg/s"}, gyro=["gx", "gy", "gz"])
    >>> np.round(rec.w_ib_b, 6)                                       # rad/s
    array([[0.      , 0.      , 1.570796],
           [0.      , 0.      , 1.570796]])
    >>> tmp.cleanup()
    """
    df, source = _read_table(path, sep=text(sep, "sep", empty=False), comment=comment)
    return _finish(_in_file(source, from_dataframe, df, **kwargs), source, check)


def _in_file(source: str, reader: Callable[_P, _R], *args: _P.args, **kwargs: _P.kwargs) -> _R:
    """Run ``reader``; a ValueError also names the file it came from (its message still starts with the
    argument or column at fault)."""
    try:
        return reader(*args, **kwargs)
    except ValueError as err:
        raise ValueError(f"{err} (in {source})") from None


_XIO_OLD = "Packet number"  # x-IMU (older x-io board, CalInertialAndMag.csv): no time column


@boundary
def read_xio(
    path: FilePath,
    *,
    rate: Positive | None = None,
    axes: str | Dcm | Mapping[str, str | Dcm] = "x,y,z",
    mirror: bool = False,
    timing: str = "raise",
    check_units: bool = True,
    check: CheckMode = "warn",
) -> Recording:
    """An x-io Technologies CSV: NGIMU / Fusion examples (``Time (s)``), or the older x-IMU layout.

    * NGIMU and x-io's Fusion example data: ``Time (s)``, ``Gyroscope X/Y/Z (deg/s)``, ``Accelerometer X/Y/Z (g)``,
      optional ``Magnetometer X/Y/Z (uT)`` and ``Barometer (hPa)``.
    * x-IMU (``*_CalInertialAndMag.csv``): ``Packet number`` and no time column, the same gyro and
      accelerometer columns, ``Magnetometer X/Y/Z (G)`` in gauss. Time is the row number divided by ``rate``
      (the inertial data rate the board was set to, e.g. 256 Hz), as x-io's own scripts do: the packet number
      counts every packet the board sends (quaternions, battery, ...), so it skips between inertial rows and
      is not a clock.

    The accelerometer is specific force in g (+1 g on z lying flat).

    Parameters
    ----------
    path : str or Path
    rate : float, optional
        Sample rate (Hz) of an x-IMU file (required for that layout, refused for the others).
    axes, mirror, timing, check_units
        As in :func:`from_dataframe`. x-io's axes are used as the body axes unless ``axes`` maps them.
    check : {"warn", "raise", "off"}
        As in :func:`read_csv`.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import io, repro
    >>> rec = io.read_xio(repro.root() / "data" / "real" / "xio-fusion" / "sensor_data.csv")   # x-io's Fusion example
    >>> rec.w_ib_b.shape, round(float(np.median(np.diff(rec.time))), 4)   # rad/s, about 100 Hz
    ((13514, 3), 0.0101)
    """
    df, source = _read_table(path)
    df.columns = [c.strip() for c in df.columns]
    notes = []
    packet = next((c for c in df.columns if c.lower() == _XIO_OLD.lower()), None)
    if packet is not None:
        if rate is None:
            raise ValueError(
                f"rate: {source} has a column {packet!r} and no 'Time (s)': an x-IMU file, whose "
                f"samples carry no time; pass rate= (the board's sample rate in Hz, e.g. rate=256)"
            )
        df["Time (s)"] = np.arange(len(df)) / rate
        notes.append(
            f"time: x-IMU layout; row number / rate {rate:g} Hz -> s (the x-IMU numbers every packet it "
            f"sends, of all kinds, so column {packet!r} skips numbers between inertial rows: not time)"
        )
    elif rate is not None:
        raise ValueError(f"rate: {source} has its own time column 'Time (s)'; leave rate out")
    cols: dict[str, Any] = {"gyro": [f"Gyroscope {a} (deg/s)" for a in "XYZ"], "accel": [f"Accelerometer {a} (g)" for a in "XYZ"]}
    units = {"gyro": "deg/s", "accel": "g"}
    for unit, name in (("uT", "uT"), ("G", "gauss")):
        if f"Magnetometer X ({unit})" in df.columns:
            cols["mag"], units["mag"] = [f"Magnetometer {a} ({unit})" for a in "XYZ"], name
    if "Barometer (hPa)" in df.columns:
        cols["baro"], units["baro"] = "Barometer (hPa)", "hPa"
    rec = _in_file(
        source,
        from_dataframe,
        df,
        time="Time (s)",
        units=units,
        axes=axes,
        mirror=mirror,
        timing=timing,
        check_units=check_units,
        **cols,
    )
    return _finish(rec, source, check, notes)


def _read_table(path: Path, **read_csv: Any) -> tuple[pd.DataFrame, str]:
    """A CSV file (a checked path) as a DataFrame (spaces after separators ignored), and its path for ``Recording.source``."""
    if not path.is_file():
        raise ValueError(f"path: no such file {str(path)!r}")
    df = pd.read_csv(path, skipinitialspace=True, **read_csv)
    if df.empty:
        raise ValueError(f"path: {str(path)!r} has a header but no samples")
    return df, str(path)


# ----------------------------------------------------------------------------------- phone apps


def _file_xyz(df: pd.DataFrame, path: Path, prefix: str = "") -> np.ndarray:
    """The x, y, z columns of a phone app's per-sensor file: ``x``, ``y``, ``z`` (Sensor Logger), or
    ``<NAME> X (<unit>)`` in any case (older Sensor Logger exports, phyphox), as floats."""
    if all(c in df.columns for c in "xyz"):
        cols = list("xyz")
    else:
        cols = []
        for a in "xyz":
            found = [c for c in df.columns if re.fullmatch(rf"{prefix}.*\b{a} \(.*\)", c.strip(), re.IGNORECASE)]
            if len(found) != 1:
                raise ValueError(
                    f"{path}: no single column for the {a} axis (expected 'x', 'y', 'z' or "
                    f"'<sensor> {a.upper()} (<unit>)'); it has {list(df.columns)}"
                )
            cols += found
    return _in_file(str(path), _numeric, df, cols)


def _phone_file(path: Path) -> pd.DataFrame:
    df = pd.read_csv(path)
    if df.empty:
        raise ValueError(f"{path}: a header but no samples; was the sensor switched on in the app?")
    return df


def _stamps(df: pd.DataFrame, path: Path) -> np.ndarray:
    """A Sensor Logger file's ``time`` column: integer nanoseconds since the epoch."""
    if "time" not in df.columns:
        raise ValueError(f"{path}: no column 'time' (ns since the epoch) of a Sensor Logger export; it has {list(df.columns)}")
    return pd.to_numeric(df["time"]).to_numpy(dtype=np.int64)


_LOGGER_NORTH = {"ios": "true north (iOS)", "android": "magnetic north (Android)"}
# Sensor Logger's Orientation.csv quaternion maps phone axes to its reference frame (checked on real
# exports of both platforms: it turns the measured gravity onto the reference's up axis, and on iOS the
# measured field's horizontal part onto the reference's x axis). iOS: x north, y west, z up; Android: ENU.
_NWU_TO_ENU = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])


def _logger_platform(d: Path, platform: str | None) -> tuple[str, bool, list[str]]:
    """(platform, standardised, notes) from ``Metadata.csv``, the ``platform`` argument, or the files."""
    meta = {}
    if (d / "Metadata.csv").is_file():
        row = pd.read_csv(d / "Metadata.csv", dtype=str, keep_default_na=False)
        meta = {k.strip(): str(v).strip().lower() for k, v in row.iloc[0].items()} if len(row) else {}
    written = meta.get("platform") or None
    if platform is not None and written not in (None, platform):
        raise ValueError(
            f"platform: {platform!r} given, but {d / 'Metadata.csv'} says {written!r}; leave platform out to use the file's"
        )
    if written is not None and written not in ("ios", "android"):
        raise ValueError(f"{d / 'Metadata.csv'}: column 'platform': unknown value {written!r}; pass platform=")
    standardised = meta.get("standardisation", "false") == "true"
    if written:
        notes = [
            f"platform: {written} (Metadata.csv, app {meta.get('appVersion', '?')}"
            f"{', units and frames standardised' if standardised else ''})"
        ]
        return written, standardised, notes
    if platform:
        return platform, False, [f"platform: {platform} (given; no Metadata.csv, assumed not standardised)"]
    if (d / "TotalAcceleration.csv").is_file():
        return (
            "android",
            False,
            ["platform: android GUESSED (no Metadata.csv; only Android writes TotalAcceleration.csv); pass platform= to be sure"],
        )
    raise ValueError(
        f"{d}: no Metadata.csv to tell iOS from Android (their accelerometer signs differ); pass "
        f"platform='ios' or platform='android'"
    )


def _logger_accel(d: Path, ios_signs: bool, ios_g: bool) -> tuple[np.ndarray, np.ndarray, Path, str]:
    """(time ns, specific force m/s^2 in the phone's axes, the file whose clock it is on, note) from the files
    the export has."""
    sign = -1.0 if ios_signs else 1.0
    flipped = "; x -1 (iOS sign convention)" if ios_signs else ""
    if (d / "TotalAcceleration.csv").is_file():
        df = _phone_file(d / "TotalAcceleration.csv")
        return (
            _stamps(df, d / "TotalAcceleration.csv"),
            sign * _file_xyz(df, d / "TotalAcceleration.csv"),
            d / "TotalAcceleration.csv",
            "accel: TotalAcceleration.csv (m/s^2, with gravity)" + flipped,
        )
    if (d / "Accelerometer.csv").is_file() and (d / "Gravity.csv").is_file():
        acc, grav = _phone_file(d / "Accelerometer.csv"), _phone_file(d / "Gravity.csv")
        t, tg = _stamps(acc, d / "Accelerometer.csv"), _stamps(grav, d / "Gravity.csv")
        g = _file_xyz(grav, d / "Gravity.csv")
        g_on_t = np.column_stack([np.interp(t, tg, g[:, i], left=np.nan, right=np.nan) for i in range(3)])
        return (
            t,
            sign * (_file_xyz(acc, d / "Accelerometer.csv") + g_on_t),
            d / "Accelerometer.csv",
            "accel: Accelerometer.csv + Gravity.csv (gravity-free acceleration plus gravity, m/s^2)" + flipped,
        )
    if (d / "AccelerometerUncalibrated.csv").is_file():
        df = _phone_file(d / "AccelerometerUncalibrated.csv")
        scale = G0 if ios_g else 1.0
        return (
            _stamps(df, d / "AccelerometerUncalibrated.csv"),
            sign * scale * _file_xyz(df, d / "AccelerometerUncalibrated.csv"),
            d / "AccelerometerUncalibrated.csv",
            f"accel: AccelerometerUncalibrated.csv ({'g' if ios_g else 'm/s^2'}){flipped}",
        )
    if (d / "Accelerometer.csv").is_file():
        raise ValueError(
            f"{d / 'Accelerometer.csv'}: gravity is removed from it and the export has no "
            f"Gravity.csv, TotalAcceleration.csv or AccelerometerUncalibrated.csv to restore it; "
            f"record again with Gravity (or Uncalibrated Accelerometer) switched on"
        )
    raise ValueError(
        f"{d}: no accelerometer file (TotalAcceleration.csv, Accelerometer.csv with Gravity.csv, or "
        f"AccelerometerUncalibrated.csv)"
    )


def _logger_reference(
    d: Path, platform: str, standardised: bool, t_ns: np.ndarray, C_bs: np.ndarray
) -> tuple[np.ndarray | None, str | None]:
    """Orientation.csv as navlib's q_bn on the gyro clock (body = the mapped axes), and its note."""
    path = d / "Orientation.csv"
    if not path.is_file():
        return None, None
    if platform == "ios" and standardised:
        return None, (
            "reference: Orientation.csv not used (a standardised iOS quaternion's convention is not "
            "documented precisely enough to convert it)"
        )
    if np.linalg.det(C_bs) < 0:
        return None, "reference: Orientation.csv not used (a mirrored body frame has no attitude)"
    df = _phone_file(path)
    missing = [c for c in ("qw", "qx", "qy", "qz") if c not in df.columns]
    if missing:
        raise ValueError(f"{path}: no columns {missing}; the reference attitude needs the quaternion")
    q_ps = _in_file(str(path), _numeric, df, ["qw", "qx", "qy", "qz"])
    q_ps = align(t_ns * 1e-9, _stamps(df, path) * 1e-9, q_ps, method="hold")
    ok = np.all(np.isfinite(q_ps), axis=-1)
    C = np.full((t_ns.size, 3, 3), np.nan)
    C[ok] = attitude.quat_to_dcm(q_ps[ok]) @ C_bs.T  # body -> phone -> the app's reference frame
    if platform == "ios":
        C[ok] = _NWU_TO_ENU @ C[ok]
    q = np.full((t_ns.size, 4), np.nan)
    q[ok] = attitude.dcm_to_quat(C[ok])
    return q, (
        f"reference: Orientation.csv quaternion -> q_bn_ref (ENU, heading from {_LOGGER_NORTH[platform]}"
        f"{'; x-north-y-west-z-up reference turned to ENU' if platform == 'ios' else ''})"
    )


@boundary
def read_sensor_logger(
    directory: FilePath,
    *,
    platform: Annotated[str, Check("choice", options=("ios", "android"))] | None = None,
    axes: str | Dcm | Mapping[str, str | Dcm] = "x,y,z",
    mirror: bool = False,
    method: str = "hold",
    max_gap: float | None = None,
    timing: str = "raise",
    check_units: bool = True,
    check: CheckMode = "warn",
) -> Recording:
    """A Sensor Logger (phone app) CSV export, iOS or Android, any app version: put on the gyroscope's clock.

    The platform (and the app's "Standardise Units & Frames" setting) comes from ``Metadata.csv``, or
    ``platform=`` when the export has none; without either, an export with ``TotalAcceleration.csv`` is
    taken to be Android (noted as a guess in ``conversions``), any other is refused.

    * Gyro: ``Gyroscope.csv`` (rad/s, same axes and signs on both platforms).
    * Specific force, the first the export has: ``TotalAcceleration.csv`` (Android, m/s^2 with gravity);
      ``Accelerometer.csv`` + ``Gravity.csv`` (gravity-free acceleration plus gravity: iOS, older Android);
      ``AccelerometerUncalibrated.csv`` (g on iOS, m/s^2 on Android). iOS writes these with all three
      signs reversed (inertial force) unless standardised; the reader turns them into specific force.
    * Optional: ``Magnetometer.csv`` (uT), ``Barometer.csv`` (``pressure`` in hPa), ``Orientation.csv``
      (the phone's own attitude, returned as ``q_bn_ref`` in navlib's frame: ENU, heading from true north on
      iOS, magnetic north on Android).

    Columns are ``time`` (ns since the epoch) and ``x``, ``y``, ``z`` (or, in older exports,
    ``GYROSCOPE X (rad/s)``-style names). The other sensors are aligned to the gyroscope's samples with
    :func:`align` (``method``, ``max_gap``).

    Parameters
    ----------
    directory : str or Path
        The unzipped export.
    platform : {"ios", "android"}, optional
        Needed only when the export has no ``Metadata.csv``.
    axes : str or array_like, shape (3, 3), or mapping
        Phone-to-body mapping, for all sensors or per sensor (:func:`from_dataframe`); default: the phone's
        x right, y up the screen, z out of the screen are right-front-up (lying face up, top forward).
    mirror : bool
        As in :func:`from_dataframe`.
    method : {"hold", "interpolate"}
    max_gap : float, optional
        Longest time (s) a reading is held or interpolated across (default: :func:`align`'s rule).
    timing, check_units
        As in :func:`from_dataframe`.
    check : {"warn", "raise", "off"}
        As in :func:`read_csv`.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from navlib import io
    >>> tmp = tempfile.TemporaryDirectory()
    >>> folder = Path(tmp.name)
    >>> def write(name, z):                                     # columns as the app writes them: time (ns), z, y, x
    ...     rows = ["time,seconds_elapsed,z,y,x", f"1700000000000000000,0.0,{z},0,0", f"1700000000010000000,0.01,{z},0,0"]
    ...     _ = (folder / name).write_text("\\n".join(rows) + "\\n")
    ...
    >>> write("Gyroscope.csv", 0.5)
    >>> write("TotalAcceleration.csv", 9.81)
    >>> rec = io.read_sensor_logger(folder, platform="android", check="off")
    >>> rec.time, rec.w_ib_b[:, 2]
    (array([0.  , 0.01]), array([0.5, 0.5]))
    >>> tmp.cleanup()
    """
    d = directory
    if not d.is_dir():
        raise ValueError(f"directory: no such directory {str(d)!r}")
    if not (d / "Gyroscope.csv").is_file():
        raise ValueError(f"directory: no Gyroscope.csv in {str(d)!r}; record with the gyroscope switched on")
    platform, standardised, notes = _logger_platform(d, platform)
    ios = platform == "ios" and not standardised
    gyro = _phone_file(d / "Gyroscope.csv")
    t_ns = _stamps(gyro, d / "Gyroscope.csv")
    _check_timing(t_ns, timing, str(d / "Gyroscope.csv"))
    w = _file_xyz(gyro, d / "Gyroscope.csv")
    if timing == "sanitize":  # the other sensors are put on this clock: repair it first
        order = np.unique(t_ns, return_index=True)[1]
        t_ns, w = t_ns[order], w[order]
    t_gyro = (t_ns - t_ns[0]) * 1e-9
    frame = pd.DataFrame({"time": t_ns, "gx": w[:, 0], "gy": w[:, 1], "gz": w[:, 2]})
    kw: dict[str, Any] = {"gyro": ("gx", "gy", "gz")}
    units = {"gyro": "rad/s"}
    t_acc, f_acc, acc_file, note = _logger_accel(d, ios, ios)
    notes.append(note)
    sensors = {"accel": (t_acc, f_acc, acc_file, "m/s^2")}
    if (d / "Magnetometer.csv").is_file():
        df = _phone_file(d / "Magnetometer.csv")
        sensors["mag"] = (
            _stamps(df, d / "Magnetometer.csv"),
            _file_xyz(df, d / "Magnetometer.csv"),
            d / "Magnetometer.csv",
            "uT",
        )
    if (d / "Barometer.csv").is_file():
        df = _phone_file(d / "Barometer.csv")
        if "pressure" not in df.columns:
            raise ValueError(f"{d / 'Barometer.csv'}: no column 'pressure' (hPa); it has {list(df.columns)}")
        sensors["baro"] = (
            _stamps(df, d / "Barometer.csv"),
            _in_file(str(d), _numeric, df, ["pressure"]),
            d / "Barometer.csv",
            "hPa",
        )
    for sensor, (stamps, x, path, unit) in sensors.items():
        _check_timing(stamps, timing, str(path))
        t_s = (stamps - t_ns[0]) * 1e-9
        if timing == "sanitize":
            t_s, x, _ = sanitize(t_s, x)
        names = [f"{sensor}_{c}" for c in "xyz"][: x.shape[1]]
        frame[names] = align(t_gyro, t_s, x, method=method, max_gap=max_gap)
        kw[sensor] = names[0] if sensor == "baro" else tuple(names)
        units[sensor] = unit
    missing = [s for s, f in (("magnetometer", "Magnetometer.csv"), ("barometer", "Barometer.csv")) if not (d / f).is_file()]
    if missing:
        notes.append(f"not in the export: {', '.join(missing)}")
    rec = _in_file(
        str(d),
        from_dataframe,
        frame,
        time="time",
        time_unit="ns",
        units=units,
        axes=axes,
        mirror=mirror,
        timing=timing,
        check_units=check_units,
        **kw,
    )
    q_ref, ref_note = _logger_reference(d, platform, standardised, t_ns, _mounts(axes, mirror)["gyro"][0])
    return _finish(rec, str(d), check, notes + ([ref_note] if ref_note else []), q_bn_ref=q_ref)


_PHYPHOX = {"gyro": ("Gyroscope", "rad/s"), "accel": ("Acceleration", "m/s^2"), "mag": ("Magnetic field", "uT")}


@boundary
def read_phyphox(
    path: FilePath,
    *,
    axes: str | Dcm | Mapping[str, str | Dcm] = "x,y,z",
    mirror: bool = False,
    method: str = "hold",
    max_gap: float | None = None,
    check_units: bool = True,
    check: CheckMode = "warn",
) -> Recording:
    """A phyphox CSV export: one experiment's ``Raw Data.csv``, or the folder of a multi-sensor export
    (``Gyroscope.csv``, ``Accelerometer.csv``, ``Magnetometer.csv``), put on the gyroscope's clock.

    Columns ``Time (s)``, ``Gyroscope x (rad/s)``, ``Acceleration x (m/s^2)`` (with gravity: phyphox's
    "Acceleration with g"), ``Magnetic field x (µT)``; phyphox uses the same phone axes and signs on iOS and
    Android (x right, y up the screen, z out of it; +9.81 on z lying face up). "Linear Acceleration"
    (gravity removed) is refused: navlib needs specific force.

    Parameters
    ----------
    path : str or Path
        A CSV file or the unzipped export folder.
    axes, mirror, check_units
        As in :func:`from_dataframe`.
    method, max_gap
        As in :func:`read_sensor_logger`.
    check : {"warn", "raise", "off"}
        As in :func:`read_csv`.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from navlib import io
    >>> tmp = tempfile.TemporaryDirectory()
    >>> path = Path(tmp.name) / "Raw Data.csv"
    >>> header = "Time (s),Gyroscope x (rad/s),Gyroscope y (rad/s),Gyroscope z (rad/s)"
    >>> _ = path.write_text("\\n".join([header, "0.0,0,0,0.5", "0.01,0,0,0.5"]) + "\\n")
    >>> rec = io.read_phyphox(path, check="off")
    >>> rec.time, rec.w_ib_b[:, 2], rec.f_b is None
    (array([0.  , 0.01]), array([0.5, 0.5]), True)
    >>> tmp.cleanup()
    """
    p = path
    files = sorted(p.glob("*.csv")) if p.is_dir() else [p]
    if not files or not files[0].is_file():
        raise ValueError(f"path: no such file or folder of CSV files {str(p)!r}")
    found = {}
    for f in files:
        df = pd.read_csv(f)
        df.columns = [c.strip() for c in df.columns]
        if "Time (s)" not in df.columns:
            continue
        if any(c.lower().startswith("linear acceleration") for c in df.columns) and len(files) == 1:
            raise ValueError(
                f"{f}: 'Linear Acceleration' has gravity removed; record phyphox's "
                f"'Acceleration with g' (navlib needs specific force)"
            )
        for sensor, (name, _) in _PHYPHOX.items():
            if sensor not in found and f"{name} x" in " ".join(df.columns):
                found[sensor] = (df["Time (s)"].to_numpy(dtype=float), _file_xyz(df, f, name), f)
    if "gyro" not in found:
        raise ValueError(
            f"{p}: no column 'Gyroscope x (rad/s)' with 'Time (s)'; record phyphox's Gyroscope "
            f"(and 'Acceleration with g') and export CSV"
        )
    t_gyro = found["gyro"][0]
    frame = pd.DataFrame({"t": t_gyro})
    kw: dict[str, Any] = {}
    units: dict[str, str] = {}
    notes: list[str] = []
    for sensor, (t_s, x, f) in found.items():
        names = [f"{sensor}_{a}" for a in "xyz"]
        frame[names] = x if sensor == "gyro" else align(t_gyro, t_s, x, method=method, max_gap=max_gap)
        kw[sensor], units[sensor] = tuple(names), _PHYPHOX[sensor][1]
        notes.append(f"{sensor}: {f.name}")
    rec = _in_file(str(p), from_dataframe, frame, time="t", units=units, axes=axes, mirror=mirror, check_units=check_units, **kw)
    return _finish(rec, str(p), check, notes)


@boundary
def read_euroc(
    path: FilePath, *, axes: str | Dcm = "x,y,z", timing: str = "raise", check_units: bool = True, check: CheckMode = "warn"
) -> Recording:
    """The EuRoC MAV dataset's IMU file (``mav0/imu0/data.csv``): ns timestamps, rad/s, m/s^2.

    Columns ``#timestamp [ns]``, ``w_RS_S_x [rad s^-1]`` ... ``a_RS_S_z [m s^-2]`` in the sensor frame S;
    give ``axes`` to map it to right-front-up.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from navlib import io
    >>> tmp = tempfile.TemporaryDirectory()
    >>> path = Path(tmp.name) / "data.csv"
    >>> gyro, accel = ",".join(f"w_RS_S_{a} [rad s^-1]" for a in "xyz"), ",".join(f"a_RS_S_{a} [m s^-2]" for a in "xyz")
    >>> header = f"#timestamp [ns],{gyro},{accel}"
    >>> rows = [f"{1403715523912140000 + k * 5000000},0,0,0.1,0,0,9.81" for k in range(3)]   # 200 Hz
    >>> _ = path.write_text("\\n".join([header, *rows]) + "\\n")
    >>> rec = io.read_euroc(path, check="off")                       # no axis check on a three-sample file
    >>> rec.time, rec.w_ib_b[0]
    (array([0.   , 0.005, 0.01 ]), array([0. , 0. , 0.1]))
    >>> tmp.cleanup()
    """
    df, source = _read_table(path)
    df.columns = [c.strip() for c in df.columns]
    gyro = [f"w_RS_S_{a} [rad s^-1]" for a in "xyz"]
    accel = [f"a_RS_S_{a} [m s^-2]" for a in "xyz"]
    rec = _in_file(
        source,
        from_dataframe,
        df,
        time="#timestamp [ns]",
        time_unit="ns",
        units={"gyro": "rad/s", "accel": "m/s^2"},
        gyro=gyro,
        accel=accel,
        axes=axes,
        timing=timing,
        check_units=check_units,
    )
    return _finish(rec, source, check)


# ----------------------------------------------------------------------------------- clocks


def _default_gap(ts: np.ndarray) -> float:
    """:func:`align`'s default ``max_gap``: 1.5 times the source's 99th-percentile interval. A bursty sensor
    (readings in clumps with regular pauses between them) has a median interval far below its pauses; the
    99th percentile sees the pauses, so they are bridged and only the rarer, longer dropouts become NaN."""
    return 1.5 * float(np.percentile(np.diff(ts), 99))


@boundary
def align(
    t_target: Times,
    t_source: ArrayLike,
    x_source: ArrayLike,
    *,
    method: Annotated[str, Check("choice", options=("hold", "interpolate"))] = "hold",
    max_gap: float | None = None,
) -> Array:
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
        result is NaN. Default: 1.5 times the 99th-percentile interval of ``t_source`` (a bursty sensor's
        regular pauses are bridged, its dropouts are not).

    Returns
    -------
    x : ndarray, shape (M,) or (M, k)
        NaN before the first reading, after ``max_gap`` without one, and (interpolation) after the last.

    Examples
    --------
    >>> from navlib import io
    >>> io.align([0.0, 0.5, 1.0, 1.5], [0.0, 1.0], [[1.0], [2.0]])   # hold the last reading
    array([[1.],
           [1.],
           [2.],
           [2.]])
    >>> io.align([0.0, 0.5, 1.0], [0.0, 1.0], [[1.0], [2.0]], method="interpolate")
    array([[1. ],
           [1.5],
           [2. ]])
    """
    tt = time_axis(t_target, "t_target")
    ts = time_axis(t_source, "t_source")
    x = as_array(x_source, "x_source", allow_nan=True, min_ndim=1)
    if x.shape[0] != ts.size:
        raise ValueError(f"x_source: expected {ts.size} readings on axis 0 (one per t_source), got shape {x.shape}")
    gap = _default_gap(ts) if max_gap is None else scalar(max_gap, "max_gap", positive=True)
    x2 = x.reshape(ts.size, -1)
    k = np.searchsorted(ts, tt, side="right") - 1  # latest reading at or before each target time
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


@boundary
def resample(
    rec: Is[Recording], rate: Positive, *, method: Annotated[str, Check("choice", options=("mean", "interpolate"))] = "mean"
) -> Recording:
    """The recording on a uniform clock of ``rate`` Hz.

    ``"mean"`` (decimation): each new sample is the mean of the readings in its interval
    ``[t_k, t_k + 1/rate)``, so white noise keeps its density (the variance falls as the interval grows) and
    a bursty clock is evened out; an interval without a reading is NaN. Use it for noise analysis
    (:func:`navlib.calibration.characterise`) and whenever the new rate is lower than the old.
    ``"interpolate"``: linear interpolation at the new times (:func:`align`); it does not average, so
    white noise resampled to a lower rate keeps its per-sample variance and its density comes out too
    high (too low when resampled to a higher rate): use it only to add samples, not for noise figures.

    Parameters
    ----------
    rec : Recording
    rate : float
        New sample rate (Hz).
    method : {"mean", "interpolate"}

    Returns
    -------
    Recording
        Same sensors, times ``k / rate``; ``conversions`` says how it was resampled.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import io, repro
    >>> rec = io.read_xio(repro.root() / "data" / "real" / "xio-fusion" / "sensor_data.csv", check="off")
    >>> slow = io.resample(rec, 10.0)                                 # 10 Hz: each sample the mean of its 0.1 s
    >>> round(float(np.diff(slow.time)[0]), 6), len(slow.time) < len(rec.time)
    (0.1, True)
    """
    t_new = np.arange(0.0, rec.time[-1], 1.0 / rate)
    if t_new.size < 2:
        raise ValueError(f"rate: {rate:g} Hz gives fewer than 2 samples over {rec.time[-1]:.3g} s; raise it")
    bins = np.floor(rec.time * rate).astype(np.int64)
    out: dict[str, Any] = {}
    for name in ("w_ib_b", "f_b", "m_b", "pressure"):
        x = getattr(rec, name)
        if x is None:
            continue
        if method == "interpolate":
            out[name] = align(t_new, rec.time, x, method="interpolate", max_gap=2 * rec.time[-1])
            continue
        x2 = x.reshape(rec.n, -1)
        ok = np.all(np.isfinite(x2), axis=1) & (bins < t_new.size)
        sums = np.zeros((t_new.size, x2.shape[1]))
        np.add.at(sums, bins[ok], x2[ok])
        counts = np.bincount(bins[ok], minlength=t_new.size)[: t_new.size]
        with np.errstate(invalid="ignore"):
            mean = sums / counts[:, None]
        out[name] = mean.reshape((t_new.size,) + x.shape[1:])
    note = f"resampled to {rate:g} Hz by {'the mean over each interval' if method == 'mean' else 'interpolation'}"
    return replace(rec, time=t_new, **out, q_bn_ref=None, timing=None, conversions=rec.conversions + (note,))


# ----------------------------------------------------------------------------------- axis check

AXIS_CHECK_WINDOW = 0.5
"""Window (s) over which :func:`check_axes` averages the gravity and field directions (long enough to average
out the linear acceleration of hand-held or vehicle motion)."""
AXIS_CHECK_RATIO = 0.8
"""A flip is named when its residual is below 1 (the gyro explains most of the motion of the directions) and
at most this fraction of the as-read residual."""
_MIN_STEP = np.deg2rad(3.0)  # rotation between two windows below which the noise dominates
_MIN_TURN = np.deg2rad(90.0)  # total rotation over the windows used, needed for a verdict
_MIN_STEPS = 20  # usable window steps needed for a verdict (a short violent log misleads)


@dataclass(frozen=True)
class AxisCheck:
    """What :func:`check_axes` found.

    Attributes
    ----------
    ranking : tuple of (str, float)
        Each hypothesis (``"as read"``, ``"gyro x flipped"``, ... ``"mag z flipped"``, body axes x right, y
        front, z up) with its residual: how much the gravity and field directions, carried into a fixed frame
        by the gyro's attitude, still move from one window to the next, relative to how much they move in the
        body (0: the gyro explains all of it); best first.
    suspect : str or None
        The flip named (``"accel y"``), or None when the data are consistent as read or the check cannot tell.
    turn : float
        Rotation (rad) summed over the window steps the check used: it needs turning to see anything.
    message : str

    Examples
    --------
    >>> from navlib import io, repro
    >>> rec = io.read_xio(repro.root() / "data" / "real" / "xio-fusion" / "sensor_data.csv", check="off")
    >>> result = io.check_axes(rec)
    >>> result.suspect, result.ranking[0][0]                          # no axis looks flipped; "as read" fits best
    (None, 'as read')
    """

    ranking: tuple[tuple[str, float], ...]
    suspect: str | None
    turn: float
    message: str


def _window_means(t: np.ndarray, x: np.ndarray, window: float) -> tuple[np.ndarray, np.ndarray]:
    """Per-window mean of x (NaN rows ignored; NaN for a window without a reading), the window of each sample."""
    k = np.floor((t - t[0]) / window).astype(np.int64)
    ok = np.all(np.isfinite(x), axis=1)
    sums = np.zeros((k[-1] + 1, x.shape[1]))
    np.add.at(sums, k[ok], x[ok])
    counts = np.bincount(k[ok], minlength=k[-1] + 1)
    with np.errstate(invalid="ignore", divide="ignore"):
        return sums / counts[:, None], k


@boundary
def check_axes(
    rec: Is[Recording], *, on_fail: Annotated[str, Check("choice", options=("warn", "raise", "ignore"))] = "warn"
) -> AxisCheck:
    """Test the gyro against the accelerometer and magnetometer kinematically; name an axis that looks flipped.

    The gyro, less its mean over the stillest second when that second is still (:data:`STILL_LIMITS`), is
    integrated into an attitude ``C_bn(t)`` (from an arbitrary start); a dropout adds no rotation. Gravity and the Earth's
    field are fixed in space, so their directions measured in the body and turned by ``C_bn`` must stay put
    from one window (:data:`AXIS_CHECK_WINDOW`, means over it) to the next, while in the body they move. The
    residual of a hypothesis is ``sum |dU_n|^2 / sum |du_b|^2`` over steps that turn by more than 3 deg.
    Every single-axis flip -- each axis of the gyro (re-integrated), the accelerometer, the magnetometer -- is
    tried; one that explains the data much better than as read (residual below :data:`AXIS_CHECK_RATIO` of it)
    is named, with the fix. A flip of all three axes of the accelerometer or the magnetometer turns a
    direction into its opposite, which turns the same way: no kinematic test sees it (the readers' platform
    conventions handle the known case, iOS).

    Parameters
    ----------
    rec : Recording
        With a gyro and an accelerometer and/or a magnetometer.
    on_fail : {"warn", "raise", "ignore"}
        What to do when an axis looks flipped: a ``UserWarning``, a ``ValueError``, or nothing.

    Returns
    -------
    AxisCheck

    Examples
    --------
    >>> from navlib import io, repro
    >>> rec = io.read_xio(repro.root() / "data" / "real" / "xio-fusion" / "sensor_data.csv", check="off")
    >>> flipped = io.Recording(rec.time, rec.w_ib_b * [1.0, 1.0, -1.0], rec.f_b, rec.m_b)   # gyro z wired backwards
    >>> io.check_axes(flipped, on_fail="ignore").suspect
    'gyro z'
    """
    if rec.w_ib_b is None or (rec.f_b is None and rec.m_b is None):
        raise ValueError("rec: the axis check needs the gyro and an accelerometer or magnetometer")
    flips = np.array([np.ones(3), _flip(0), _flip(1), _flip(2)])
    still, moved = _stillest_second(rec)  # a MEMS gyro bias (up to 20 deg/s) would swamp the test
    w = np.nan_to_num(rec.w_ib_b - (0.0 if moved else np.nanmean(rec.w_ib_b[still], axis=0)))
    gap = rec.dt > 5.0 * np.median(rec.dt)  # a pause in the log: no rotation known across it
    w[gap] = 0.0
    q_bn = strapdown.integrate_attitude([1.0, 0.0, 0.0, 0.0], w[None] * flips[:, None], rec.dt)[:, 1:]
    _, k = _window_means(rec.time, rec.w_ib_b, AXIS_CHECK_WINDOW)
    counts = np.bincount(k)
    mid = np.round(np.bincount(k, weights=np.arange(rec.n)) / np.maximum(counts, 1)).astype(np.int64)
    C_bn = _attitude.quat_to_dcm(_attitude.unit(q_bn[:, mid]))  # (gyro hypothesis, window, 3, 3)
    step = np.linalg.norm(attitude.dcm_to_rotvec(np.swapaxes(C_bn[0, :-1], -1, -2) @ C_bn[0, 1:]), axis=-1)
    gap_in = np.bincount(k, weights=gap, minlength=counts.size) > 0
    use = (step > _MIN_STEP) & (counts[1:] > 0) & (counts[:-1] > 0) & ~gap_in[1:] & ~gap_in[:-1]
    scores = dict.fromkeys(["as read"] + [f"{s} {a} flipped" for s in ("gyro", "accel", "mag") for a in "xyz"], 0.0)
    sensors = {s: x for s, x in (("accel", rec.f_b), ("mag", rec.m_b)) if x is not None}
    usable = {}  # sensor -> (body directions, usable steps)
    for sensor, x in sensors.items():
        mean, _ = _window_means(rec.time, x, AXIS_CHECK_WINDOW)
        u_b = mean / np.linalg.norm(mean, axis=1, keepdims=True)
        ok = use & np.all(np.isfinite(u_b[1:]), axis=1) & np.all(np.isfinite(u_b[:-1]), axis=1)
        if sensor == "accel":  # linear acceleration bends the gravity direction: near-1-g windows only
            size = np.linalg.norm(mean, axis=1)
            near_g = np.abs(size - np.nanmedian(size)) < 0.1 * np.nanmedian(size)
            ok &= near_g[1:] & near_g[:-1]
        if np.count_nonzero(ok) >= _MIN_STEPS:
            usable[sensor] = (u_b, ok)
    n_steps = max([int(np.count_nonzero(ok)) for _, ok in usable.values()], default=0)
    for sensor, (u_b, ok) in usable.items():
        moved = np.sum((u_b[1:] - u_b[:-1])[ok] ** 2)
        for hyp in scores:
            words = hyp.split()
            g = "xyz".index(words[1]) + 1 if words[0] == "gyro" else 0
            u = u_b * _flip("xyz".index(words[1])) if words[0] == sensor else u_b
            u_n = np.einsum("nij,nj->ni", C_bn[g], u)
            scores[hyp] += np.sum((u_n[1:] - u_n[:-1])[ok] ** 2) / moved / len(usable)
    sensors = {s: sensors[s] for s in usable} or sensors  # name only the sensors the verdict rests on
    scores = {h: float(v) for h, v in scores.items() if h.split()[0] in ("as", "gyro", *sensors)}
    ranking = tuple(sorted(scores.items(), key=lambda kv: kv[1]))
    best, as_read = ranking[0], scores["as read"]
    turn = float(step[use].sum())
    suspect = None
    if n_steps < _MIN_STEPS:
        message = (
            f"inconclusive: fewer than {_MIN_STEPS} usable window steps (turning, and near 1 g for the "
            f"accelerometer) for any sensor: too little to judge the axes; turn the sensor slowly by hand "
            f"for 15 s to have them checked"
        )
    elif turn < _MIN_TURN:
        message = (
            f"inconclusive: the sensor turned by {np.rad2deg(turn):.0f} deg in steps the check can use, "
            f"too little to compare the gyro with the {' and '.join(sensors)}; turn it by hand through "
            f"a few orientations (in the first seconds, say) to have the axes checked"
        )
    elif best[1] > 1.0:
        message = (
            f"inconclusive: the {' and '.join(sensors)} directions move more than any gyro hypothesis "
            f"explains (best residual {best[1]:.2f}): strong linear acceleration or vibration (e.g. a "
            f"foot-mounted sensor); record a few slow turns by hand to have the axes checked"
        )
    elif best[0] != "as read" and best[1] < AXIS_CHECK_RATIO * as_read:
        sensor, axis = best[0].split()[:2]
        suspect = f"{sensor} {axis}"
        body = {"x": "right (1st)", "y": "front (2nd)", "z": "up (3rd)"}[axis]
        message = (
            f"the {sensor}'s {axis} axis looks flipped: with it reversed the residual is {best[1]:.2f} "
            f"against {as_read:.2f} as read. Fix: reverse the sign of the {body} entry of the "
            f"{sensor}'s mapping, e.g. axes={{'{sensor}': "
            f"'{','.join(('-' if a == axis else '') + a for a in 'xyz')}'}} with mirror=True"
        )
        second = ranking[1]
        if second[0] != "as read" and second[1] < 2 * best[1]:
            message += (
                f". The {second[0].removesuffix(' flipped')} axis flipped fits almost as well "
                f"({second[1]:.2f}): gravity alone cannot tell a mirrored accelerometer from a mirrored "
                f"gyro, nor see turns about the vertical; a magnetometer or a turn about each axis can"
            )
    else:
        runner_up = ranking[1] if best[0] == "as read" else best
        message = (
            f"gyro consistent with the {' and '.join(sensors)} as read (residual {as_read:.2f}; best "
            f"single flip, {runner_up[0]}: {runner_up[1]:.2f})"
        )
    result = AxisCheck(ranking, suspect, turn, message)
    if suspect is not None and on_fail == "raise":
        raise ValueError(f"{rec.source}: {message}; check='off' (or on_fail='ignore') to accept as read")
    if suspect is not None and on_fail == "warn":
        warnings.warn(f"{rec.source}: {message}", UserWarning, stacklevel=3)
    return result


def _flip(axis: int) -> np.ndarray:
    out = np.ones(3)
    out[axis] = -1.0
    return out


# ----------------------------------------------------------------------------------- a still start

STILL_LIMITS = (0.02, 0.35, 0.3)
"""Largest gyro standard deviation (rad/s, about 1 deg/s), gyro mean (rad/s: 20 deg/s, the widest zero-rate
tolerance of common MEMS gyros, the MPU-6050's) and accelerometer standard deviation (m/s^2) accepted over
samples marked still."""


@boundary
def start_at_rest(rec: Is[Recording], still: ArrayLike | None = None) -> tuple[Recording, Array]:
    """Use a still stretch: gyro bias at rest removed, the magnetometer calibrated when the recording allows,
    and the initial attitude from the mean specific force (and field) over the still samples.

    * Gyro bias: :func:`navlib.calibration.gyro_bias_at_rest` over ``still`` (Earth rate included: below
      0.005 deg/s, far under a phone gyro's bias).
    * Magnetometer: :func:`navlib.calibration.fit_magnetometer` over all readings; when it refuses (the sensor
      was not turned through enough orientations, a degenerate fit, an implausible field), the field is used
      as read and ``conversions`` says why.
    * Initial attitude: levelled from the mean specific force; heading from the mean field
      (:func:`navlib.alignment.initial_attitude`, magnetic north), or 0 without a magnetometer (noted).

    Parameters
    ----------
    rec : Recording
        With gyro and accelerometer.
    still : array_like of bool, shape (N,), optional
        The samples during which the sensor lay still (at least 2), e.g. ``rec.time < 2.5``; refused when the
        data show it moving (:data:`STILL_LIMITS`). Default: the stillest second of the recording if it passes
        :data:`STILL_LIMITS` (else the bias is left in, noted), and the initial attitude from the first
        0.5 s (the filter converges from it if the sensor was moving).

    Returns
    -------
    rec : Recording
        Corrected; ``conversions`` lists the corrections.
    q_bn0 : ndarray, shape (4,)
        Initial attitude.

    Examples
    --------
    >>> from navlib import attitude, io, repro
    >>> import numpy as np
    >>> rec = io.read_xio(repro.root() / "data" / "real" / "xio-fusion" / "sensor_data.csv", check="off")
    >>> rec0, q0 = io.start_at_rest(rec, still=rec.time < 1.0)       # the first second is still
    >>> np.round(np.rad2deg(attitude.quat_to_euler(q0)), 1) + 0.0   # heading, pitch, roll (deg) at the start
    array([269.7,  -1.2,   0. ])
    """
    if rec.w_ib_b is None or rec.f_b is None:
        raise ValueError("rec: start_at_rest needs the gyro and the accelerometer")
    notes = []
    if still is None:
        still, moved = _stillest_second(rec)
        start = rec.time < rec.time[0] + 0.5
        if moved:
            notes.append(f"gyro bias left in: no still second in the recording ({moved}); record 2 s untouched at the start")
    else:
        still = booleans(still, "still", shape=(rec.n,))
        if np.count_nonzero(still) < 2:
            raise ValueError("still: fewer than 2 samples marked still; mark the first seconds the sensor lay still")
        moved = _movement(rec, still)
        if moved:
            raise ValueError(
                f"still: the sensor was not still in the samples marked still ({moved}); mark a "
                f"stretch where it lay untouched (e.g. rec.time < 2), or leave still out"
            )
        start = still
    bias = np.zeros(3)
    if not moved:
        w_still = rec.w_ib_b[still]
        bias, _ = calibration.gyro_bias_at_rest(w_still[np.all(np.isfinite(w_still), axis=1)])
        notes.append(
            f"gyro bias at rest removed: {np.round(np.rad2deg(bias), 4).tolist()} deg/s (mean over "
            f"{rec.time[still][0]:.2f}..{rec.time[still][-1]:.2f} s)"
        )
    m_b = rec.m_b
    if m_b is not None:
        try:
            cal = calibration.fit_magnetometer(m_b[np.all(np.isfinite(m_b), axis=1)])
            m_b = cal.apply(m_b)
            notes.append(
                f"magnetometer calibrated: field {cal.field_strength:.1f} uT, |m| spread "
                f"{cal.norm_spread_before:.2f} -> {cal.norm_spread_after:.2f} uT"
            )
        except ValueError as err:
            notes.append(f"magnetometer used as read, not calibrated: {err}")
    f0 = np.nanmean(rec.f_b[start], axis=0)
    if m_b is None:
        pitch, roll = alignment.level(f0)
        q0 = attitude.euler_to_quat([0.0, float(pitch), float(roll)])
        notes.append("initial attitude: levelled; heading 0 at the start (no magnetometer: relative heading)")
    else:
        q0 = alignment.initial_attitude(f0, np.nanmean(m_b[start], axis=0))
        notes.append("initial attitude: levelled, heading from the field (magnetic north)")
    out = replace(rec, w_ib_b=rec.w_ib_b - bias, m_b=m_b, conversions=rec.conversions + tuple(notes))
    return out, q0


def _movement(rec: Recording, still: np.ndarray) -> str:
    """'' when the samples look still (:data:`STILL_LIMITS`), else what moved."""
    assert rec.w_ib_b is not None  # the callers checked it
    w = rec.w_ib_b[still]
    figures = {
        "gyro std": (np.nanmax(np.nanstd(w, axis=0)), STILL_LIMITS[0], "rad/s"),
        "gyro mean": (np.nanmax(np.abs(np.nanmean(w, axis=0))), STILL_LIMITS[1], "rad/s"),
    }
    if rec.f_b is not None:
        figures["accel std"] = (np.nanmax(np.nanstd(rec.f_b[still], axis=0)), STILL_LIMITS[2], "m/s^2")
    return ", ".join(f"{k} {v:.3g} > {lim:g} {u}" for k, (v, lim, u) in figures.items() if not v <= lim)


def _stillest_second(rec: Recording) -> tuple[np.ndarray, str]:
    """The 1-s window (on a 0.5-s grid) with the smallest gyro spread, and '' or what moved in it."""
    starts = np.arange(rec.time[0], max(rec.time[-1] - 1.0, rec.time[0]) + 1e-9, 0.5)
    windows = [(rec.time >= a) & (rec.time < a + 1.0) for a in starts]
    assert rec.w_ib_b is not None  # the callers checked it
    spread = [np.nanmax(np.nanstd(rec.w_ib_b[w], axis=0)) if np.count_nonzero(w) > 1 else np.inf for w in windows]
    best = windows[int(np.argmin(spread))]
    return best, _movement(rec, best)
