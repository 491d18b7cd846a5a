r"""Barometric altitude: the ISA troposphere and the BMP180 datasheet formula.

* ISA (ICAO Doc 7488 = US Standard Atmosphere 1976, troposphere):
  :math:`h = \frac{T_0}{L} \big(1 - (p/p_0)^{R L / g_0}\big)` with T0 = 288.15 K, L = 0.0065 K/m,
  R = 287.05287 J/(kg K), g0 = 9.80665 m/s^2 (exponent 0.190263).
* BMP180 datasheet (BST-BMP180-DS000-09 sec. 3.6), with rounded constants:
  :math:`h = 44330\, \big(1 - (p/p_0)^{1/5.255}\big)`. It differs from ISA by +0.14 m at
  1 km. The datasheet's "1 hPa = 8.43 m" does not follow from its own
  formula (dh/dp at p0 is 8.33 m/hPa).
* Hypsometric relative height with a measured temperature:
  :math:`\Delta h = \frac{R T}{g_0} \ln(p_{ref} / p)` (paper 004 §"barometer"; the
  hypsometric equation of any meteorology text).

Heights are geopotential metres, pressures Pa, temperatures K.
"""

from __future__ import annotations

from typing import Annotated

import numpy as np

from . import _atmosphere
from ._typing import Array, ArrayLike, Times
from ._validate import (
    Check,
    Is,
    Positive,
    Real,
    as_array,
    booleans,
    boundary,
    broadcast,
    in_range,
    integer,
    last_axis,
    positive,
    time_axis,
)
from .analysis import segments
from .units import G0

__all__ = [
    "P0",
    "T0",
    "LAPSE",
    "R_AIR",
    "isa_altitude",
    "isa_pressure",
    "bmp180_altitude",
    "bmp180_pressure",
    "hypsometric_height",
    "bmp180_compensate",
    "baro_height",
    "reference_pressure",
    "classify_floor",
    "segment_floors",
]

P0 = _atmosphere.P0
"""ISA sea-level pressure (Pa)."""
T0 = _atmosphere.T0
"""ISA sea-level temperature (K)."""
LAPSE = _atmosphere.LAPSE
"""ISA tropospheric lapse rate (K/m)."""
R_AIR = _atmosphere.R_AIR
"""Specific gas constant of dry air (J/(kg K))."""


def isa_altitude(p: ArrayLike, p0: ArrayLike = P0) -> Array:
    """ISA geopotential altitude (m) from pressure ``p`` (Pa) with reference ``p0`` (Pa).

    Valid in the troposphere (below 11 km, p > 22632 Pa for p0 = 101325).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import atmosphere
    >>> np.round(atmosphere.isa_altitude([101325.0, 89874.6]), 1)
    array([   0., 1000.])
    """
    p, p0 = positive(p, "p"), positive(p0, "p0")
    in_range(p / p0, "p", _atmosphere.P_11KM / P0 * (1 - 1e-12), 1.2, "(fraction of p0)")
    return _atmosphere.isa_altitude(p, p0)


def isa_pressure(h: ArrayLike, p0: ArrayLike = P0) -> Array:
    """ISA pressure (Pa) at geopotential altitude ``h`` (m, -1 km to 11 km).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import atmosphere
    >>> np.round(atmosphere.isa_pressure([0.0, 1000.0]), 1)
    array([101325. ,  89874.6])
    """
    h = in_range(as_array(h, "h"), "h", _atmosphere.H_MIN, _atmosphere.H_MAX, "m")
    return _atmosphere.isa_pressure(h, positive(p0, "p0"))


def bmp180_altitude(p: ArrayLike, p0: ArrayLike = P0) -> Array:
    """Altitude (m) by the BMP180 datasheet formula ``44330 (1 - (p/p0)^(1/5.255))``.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import atmosphere
    >>> np.round(atmosphere.bmp180_altitude([101325.0, 90000.0]), 1)
    array([  0. , 988.6])
    """
    return _bmp180_altitude(positive(p, "p"), positive(p0, "p0"))


def _bmp180_altitude(p: np.ndarray, p0: np.ndarray) -> Array:
    return 44330.0 * (1 - (p / p0) ** (1 / 5.255))


def bmp180_pressure(h: ArrayLike, p0: ArrayLike = P0) -> Array:
    """Inverse of :func:`bmp180_altitude`: ``p0 (1 - h/44330)^5.255`` (Pa).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import atmosphere
    >>> np.round(atmosphere.bmp180_pressure([0.0, 1000.0]), 1)
    array([101325. ,  89876.2])
    """
    h = in_range(as_array(h, "h"), "h", -1000.0, 11000.0, "m")
    return positive(p0, "p0") * (1 - h / 44330.0) ** 5.255


def hypsometric_height(p: ArrayLike, p_ref: ArrayLike, temperature: ArrayLike) -> Array:
    r"""Height above the reference level (m): :math:`\frac{R T}{g_0} \ln(p_{ref} / p)`.

    Parameters
    ----------
    p, p_ref : array_like
        Pressure and reference pressure (Pa).
    temperature : array_like
        Mean air temperature of the layer (K).

    Examples
    --------
    >>> from navlib import atmosphere
    >>> round(float(atmosphere.hypsometric_height(90000.0, 101325.0, 288.15)), 1)
    999.7
    """
    p, p_ref = positive(p, "p"), positive(p_ref, "p_ref")
    return _hypsometric_height(p, p_ref, _temperature(temperature, p, p_ref))


def _temperature(temperature: ArrayLike, p: np.ndarray, p_ref: np.ndarray) -> np.ndarray:
    """The air temperature (K) of a layer between checked pressures ``p`` and ``p_ref``."""
    T = in_range(as_array(temperature, "temperature"), "temperature", 150.0, 350.0, "K")
    broadcast(p, p_ref, T, name="temperature", of="p, p_ref, temperature")
    return T


def _hypsometric_height(p: np.ndarray, p_ref: np.ndarray, T: np.ndarray) -> Array:
    return R_AIR * T / G0 * np.log(p_ref / p)


def _cdiv(a: int, b: int) -> int:
    """C integer division (truncates toward zero; Python's // floors)."""
    q = abs(a) // abs(b)
    return q if (a >= 0) == (b >= 0) else -q


@boundary
def bmp180_compensate(
    UT: Annotated[int, Check("integer", minimum=0)],
    UP: Annotated[int, Check("integer", minimum=0)],
    calib: Is[dict[str, int]],
    oss: Annotated[int, Check("choice", options=(0, 1, 2, 3))] = 0,
) -> tuple[int, int]:
    """BMP180 datasheet integer compensation (sec. 3.5).

    Parameters
    ----------
    UT, UP : int
        Raw temperature (16-bit) and pressure (16 + oss bits) ADC readings, non-negative.
    calib : dict
        Calibration coefficients AC1..AC6, B1, B2, MB, MC, MD.
    oss : {0, 1, 2, 3}
        Oversampling setting.

    Returns
    -------
    T, p : int
        Temperature in 0.1 degC and pressure in Pa, as the device computes them
        (C semantics: divisions truncate toward zero, right shifts are arithmetic).

    Examples
    --------
    >>> from navlib import atmosphere
    >>> calib = dict(AC1=408, AC2=-72, AC3=-14383, AC4=32741, AC5=32757, AC6=23153, B1=6190, B2=4, MB=-32768, MC=-8711, MD=2868)
    >>> atmosphere.bmp180_compensate(27898, 23843, calib, oss=0)     # the datasheet's worked example: 15.0 degC, 69964 Pa
    (150, 69964)
    """
    missing = {"AC1", "AC2", "AC3", "AC4", "AC5", "AC6", "B1", "B2", "MB", "MC", "MD"} - set(calib)
    if missing:
        raise ValueError(f"calib: missing coefficients {sorted(missing)}")
    c = {k: integer(v, f"calib[{k!r}]", minimum=None) for k, v in calib.items()}
    if UT >= 1 << 16:
        raise ValueError(f"UT: expected a 16-bit raw reading (0 ... 65535), got {UT}")
    if UP >= 1 << (16 + oss):
        raise ValueError(f"UP: expected a {16 + oss}-bit raw reading at oss={oss} (0 ... {(1 << (16 + oss)) - 1}), got {UP}")
    X1 = (UT - c["AC6"]) * c["AC5"] >> 15
    X2 = _cdiv(c["MC"] << 11, X1 + c["MD"])
    B5 = X1 + X2
    T = (B5 + 8) >> 4
    B6 = B5 - 4000
    X1 = (c["B2"] * (B6 * B6 >> 12)) >> 11
    X2 = c["AC2"] * B6 >> 11
    X3 = X1 + X2
    B3 = _cdiv(((c["AC1"] * 4 + X3) << oss) + 2, 4)
    X1 = c["AC3"] * B6 >> 13
    X2 = (c["B1"] * (B6 * B6 >> 12)) >> 16
    X3 = ((X1 + X2) + 2) >> 2
    B4 = c["AC4"] * (X3 + 32768) >> 15
    B7 = (UP - B3) * (50000 >> oss)
    p = _cdiv(B7 * 2, B4) if B7 < 0x80000000 else _cdiv(B7, B4) * 2
    X1 = (p >> 8) * (p >> 8)
    X1 = (X1 * 3038) >> 16
    X2 = (-7357 * p) >> 16
    p = p + ((X1 + X2 + 3791) >> 4)
    return T, p


# --------------------------------------------------------------------------
# Barometric height and floors
# --------------------------------------------------------------------------


def baro_height(p: ArrayLike, p_ref: ArrayLike, temperature: ArrayLike | None = None) -> Array:
    """Height above the reference level from pressure (m).

    BMP180 formula ``44330 (1 - (p/p_ref)^(1/5.255))`` with the reference
    pressure of the start floor, or, given a temperature, the hypsometric
    ``R T / g0 ln(p_ref / p)``.

    Parameters
    ----------
    p : array_like
        Pressure (Pa), finite and positive.
    p_ref : float or array_like
        Reference pressure (Pa), e.g. :func:`reference_pressure`; broadcasts against ``p``
        (one per trial of a (T, N) batch: shape (T, 1)).
    temperature : array_like, optional
        Air temperature (K).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import atmosphere
    >>> np.round(atmosphere.baro_height([101325.0, 101289.0], p_ref=101325.0), 2)   # one floor up: about 36 Pa less
    array([0., 3.])
    >>> np.round(atmosphere.baro_height([101325.0, 101289.0], p_ref=101325.0, temperature=293.15), 2)
    array([0.  , 3.05])
    """
    p = positive(p, "p", nonempty=True)
    p, p_ref = broadcast(p, positive(p_ref, "p_ref"), name="p_ref", of="p")
    if temperature is None:
        return _bmp180_altitude(p, p_ref)
    return _hypsometric_height(p, p_ref, _temperature(temperature, p, p_ref))


@boundary
def reference_pressure(p: ArrayLike, time: Times, until: Real) -> float | Array:
    """Mean pressure (Pa) over ``time <= until`` (the initial stand on the start floor).

    Parameters
    ----------
    p : array_like, shape (N,) or (..., N)
        Pressure (Pa); NaN samples (no reading) are ignored.
    time : array_like, shape (N,)  (s)
    until : float  (s)

    Returns
    -------
    float, or ndarray of shape (...) for a batch of series

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import atmosphere
    >>> time = np.arange(5.0)
    >>> atmosphere.reference_pressure([100000.0, 100002.0, np.nan, 99960.0, 99950.0], time, until=2.0)   # NaN ignored
    100001.0
    """
    t = time_axis(time, "time", min_samples=1)
    p = last_axis(as_array(p, "p", allow_nan=True), "p", t.size, of="time")
    window = p[..., t <= until]
    valid = np.isfinite(window)
    if not valid.any(axis=-1).all():
        raise ValueError(f"until: no pressure sample at or before {until} s")
    if np.any(window[valid] <= 0):
        raise ValueError("p: expected positive pressures (Pa)")
    if valid.all():
        ref = window.mean(axis=-1)
    else:  # each series' valid samples alone, summed as a 1-D mean sums them
        ref = np.array(
            [w[v].mean() for w, v in zip(window.reshape(-1, window.shape[-1]), valid.reshape(-1, window.shape[-1]), strict=True)]
        )
        ref = ref.reshape(window.shape[:-1])
    return float(ref) if ref.ndim == 0 else ref


Floor = Annotated[int, Check("integer", minimum=None)]
"""A floor index (any integer)."""


@boundary
def classify_floor(h: ArrayLike, floor_height: Positive = 3.0, ref_floor: Floor = 0) -> np.ndarray:
    """Floor index ``ref_floor + round(h / floor_height)`` from a relative height (m).

    Examples
    --------
    >>> from navlib import atmosphere
    >>> atmosphere.classify_floor([0.2, 3.1, 5.8, -2.9], floor_height=3.0)
    array([ 0,  1,  2, -1])
    """
    h = as_array(h, "h")
    return _floors(h, floor_height, ref_floor)


def _floors(h: Array, floor_height: float, ref_floor: int) -> np.ndarray:
    """:func:`classify_floor` of checked arguments."""
    return ref_floor + np.round(h / floor_height).astype(int)


@boundary
def segment_floors(
    h: ArrayLike, static: ArrayLike, floor_height: Positive = 3.0, ref_floor: Floor = 0
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Floor of every static segment from the median height over the segment.

    Parameters
    ----------
    h : array_like, shape (N,) or (..., N)
        Relative height (m); NaN samples are ignored.
    static : array_like of bool, shape (N,)

    Returns
    -------
    starts, ends : ndarray of int, shape (K,)
        Sample index of each segment's first sample and one past its last.
    floors : ndarray of int, shape (..., K)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import atmosphere
    >>> h = np.array([0.1, 0.0, 1.5, 3.1, 3.0, 2.9])
    >>> static = np.array([True, True, False, True, True, True])
    >>> atmosphere.segment_floors(h, static)
    (array([0, 3]), array([2, 6]), array([0, 1]))
    """
    h = as_array(h, "h", allow_nan=True)
    s = booleans(static, "static", shape=h.shape[-1:] or (None,), of="the last axis of h")
    h = last_axis(h, "h", s.size, of="static")  # refuses a scalar h
    starts, ends = segments(s)
    if starts.size == 0:
        return starts, ends, np.zeros(h.shape[:-1] + (0,), dtype=int)
    med = np.stack([np.nanmedian(h[..., a:b], axis=-1) for a, b in zip(starts, ends, strict=True)], -1)
    return starts, ends, _floors(med, floor_height, ref_floor)
