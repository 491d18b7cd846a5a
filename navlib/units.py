"""Datasheet units to SI and back.

navlib works in SI internally (rad, rad/s, m/s^2, m, s, Pa, uT). Sensor
datasheets and papers speak in deg/h, deg/sqrt(h), deg/s/sqrt(Hz), ug, mg,
ug/sqrt(Hz), gauss and hPa; these helpers are the only place those units are
converted. Each ``x_unit(value)`` returns SI, each ``to_x_unit(value)`` goes
back. Noise densities follow the usual identities:

* angle random walk 1 deg/sqrt(h) = (pi/180)/60 rad/sqrt(s) (= rad/s/sqrt(Hz));
* 1 deg/s/sqrt(Hz) = pi/180 rad/s/sqrt(Hz);
* velocity random walk 1 m/s/sqrt(h) = 1/60 m/s/sqrt(s) (= m/s^2/sqrt(Hz)).
"""

from __future__ import annotations

from typing import Annotated

import numpy as np

from ._typing import Array, ArrayLike
from ._validate import Check, boundary, real

__all__ = [
    "G0",
    "CONVERTERS",
    "to_si",
    "deg",
    "to_deg",
    "deg_per_s",
    "to_deg_per_s",
    "deg_per_h",
    "to_deg_per_h",
    "deg_per_sqrt_h",
    "to_deg_per_sqrt_h",
    "deg_per_s_sqrt_hz",
    "to_deg_per_s_sqrt_hz",
    "deg_per_h_sqrt_h",
    "mg",
    "ug",
    "to_ug",
    "ug_per_sqrt_hz",
    "m_per_s_sqrt_h",
    "gauss",
    "to_gauss",
    "nanotesla",
    "hpa",
    "to_hpa",
    "percent",
    "ppm",
]

G0 = 9.80665
"""Standard gravity (m/s^2) used to convert g, mg and ug (ISO 80000-3)."""

_DEG = np.pi / 180.0


def _num(x: ArrayLike, name: str = "x") -> Array:
    """Float array of ``x``; NaN (dropout) and inf (e.g. "no saturation") pass through."""
    return real(x, name)


def deg(x: ArrayLike) -> Array:
    """Degrees to radians.

    Examples
    --------
    >>> from navlib import units
    >>> float(units.deg(180.0))   # deg to rad
    3.141592653589793
    """
    return _num(x) * _DEG


def to_deg(x: ArrayLike) -> Array:
    """Radians to degrees.

    Examples
    --------
    >>> from navlib import units
    >>> float(units.to_deg(0.5))
    28.64788975654116
    """
    return _num(x) / _DEG


def deg_per_s(x: ArrayLike) -> Array:
    """deg/s to rad/s.

    Examples
    --------
    >>> from navlib import units
    >>> float(units.deg_per_s(90.0))   # rad/s
    1.5707963267948966
    """
    return _num(x) * _DEG


def to_deg_per_s(x: ArrayLike) -> Array:
    """rad/s to deg/s.

    Examples
    --------
    >>> from navlib import units
    >>> float(units.to_deg_per_s(1.0))
    57.29577951308232
    """
    return _num(x) / _DEG


def deg_per_h(x: ArrayLike) -> Array:
    """deg/h to rad/s.

    Examples
    --------
    >>> from navlib import units
    >>> float(units.deg_per_h(15.0))   # rad/s
    7.27220521664304e-05
    >>> float(units.to_deg_per_h(units.deg_per_h(15.0)))
    14.999999999999998
    """
    return _num(x) * _DEG / 3600.0


def to_deg_per_h(x: ArrayLike) -> Array:
    """rad/s to deg/h.

    Examples
    --------
    >>> from navlib import units
    >>> float(units.to_deg_per_h(7.292115e-5))                       # Earth rate (rad/s) in deg/h
    15.041066876065452
    """
    return _num(x) * 3600.0 / _DEG


def deg_per_sqrt_h(x: ArrayLike) -> Array:
    """Angle random walk deg/sqrt(h) to rad/s/sqrt(Hz).

    Examples
    --------
    >>> from navlib import units
    >>> float(units.deg_per_sqrt_h(0.15))   # angle random walk -> rad/s/sqrt(Hz)
    4.3633231299858234e-05
    """
    return _num(x) * _DEG / 60.0


def to_deg_per_sqrt_h(x: ArrayLike) -> Array:
    """Angle random walk rad/s/sqrt(Hz) to deg/sqrt(h).

    Examples
    --------
    >>> from navlib import units
    >>> float(units.to_deg_per_sqrt_h(4.4e-5))
    0.15126085791453733
    """
    return _num(x) * 60.0 / _DEG


def deg_per_s_sqrt_hz(x: ArrayLike) -> Array:
    """Rate noise density deg/s/sqrt(Hz) to rad/s/sqrt(Hz).

    Examples
    --------
    >>> from navlib import units
    >>> float(units.deg_per_s_sqrt_hz(0.005))   # MPU-6050 rate noise density -> rad/s/sqrt(Hz)
    8.726646259971648e-05
    """
    return _num(x) * _DEG


def to_deg_per_s_sqrt_hz(x: ArrayLike) -> Array:
    """Rate noise density rad/s/sqrt(Hz) to deg/s/sqrt(Hz).

    Examples
    --------
    >>> from navlib import units
    >>> float(units.to_deg_per_s_sqrt_hz(8.7e-5))
    0.0049847328176381624
    """
    return _num(x) / _DEG


def deg_per_h_sqrt_h(x: ArrayLike) -> Array:
    """Rate random walk deg/h/sqrt(h) to rad/s^2/sqrt(Hz) (= rad/s/sqrt(s)).

    Examples
    --------
    >>> from navlib import units
    >>> float(units.deg_per_h_sqrt_h(1.0))   # rate random walk deg/h/sqrt(h) -> rad/s^2/sqrt(Hz)
    8.080228018492267e-08
    """
    return _num(x) * _DEG / 3600.0 / 60.0


def mg(x: ArrayLike) -> Array:
    """milli-g to m/s^2.

    Examples
    --------
    >>> from navlib import units
    >>> float(units.mg(10.0))   # m/s^2
    0.0980665
    """
    return _num(x) * 1e-3 * G0


def ug(x: ArrayLike) -> Array:
    """micro-g to m/s^2.

    Examples
    --------
    >>> from navlib import units
    >>> float(units.ug(100.0))   # m/s^2
    0.000980665
    """
    return _num(x) * 1e-6 * G0


def to_ug(x: ArrayLike) -> Array:
    """m/s^2 to micro-g.

    Examples
    --------
    >>> from navlib import units
    >>> float(units.to_ug(0.0098))
    999.3218887183698
    """
    return _num(x) / (1e-6 * G0)


def ug_per_sqrt_hz(x: ArrayLike) -> Array:
    """Accelerometer noise density ug/sqrt(Hz) to m/s^2/sqrt(Hz).

    Examples
    --------
    >>> from navlib import units
    >>> float(units.ug_per_sqrt_hz(400.0))   # MPU-6050 accelerometer noise density -> m/s^2/sqrt(Hz)
    0.00392266
    """
    return ug(x)


def m_per_s_sqrt_h(x: ArrayLike) -> Array:
    """Velocity random walk m/s/sqrt(h) to m/s^2/sqrt(Hz).

    Examples
    --------
    >>> from navlib import units
    >>> float(units.m_per_s_sqrt_h(0.06))   # velocity random walk -> m/s^2/sqrt(Hz)
    0.001
    """
    return _num(x) / 60.0


def gauss(x: ArrayLike) -> Array:
    """Gauss to microtesla (1 G = 100 uT).

    Examples
    --------
    >>> from navlib import units
    >>> float(units.gauss(0.5))   # uT
    50.0
    """
    return _num(x) * 100.0


def to_gauss(x: ArrayLike) -> Array:
    """Microtesla to gauss.

    Examples
    --------
    >>> from navlib import units
    >>> float(units.to_gauss(50.0))
    0.5
    """
    return _num(x) / 100.0


def nanotesla(x: ArrayLike) -> Array:
    """Nanotesla to microtesla.

    Examples
    --------
    >>> from navlib import units
    >>> float(units.nanotesla(48000.0))   # uT
    48.0
    """
    return _num(x) * 1e-3


def hpa(x: ArrayLike) -> Array:
    """Hectopascal to pascal.

    Examples
    --------
    >>> from navlib import units
    >>> float(units.hpa(1013.25))   # Pa
    101325.0
    """
    return _num(x) * 100.0


def to_hpa(x: ArrayLike) -> Array:
    """Pascal to hectopascal.

    Examples
    --------
    >>> from navlib import units
    >>> float(units.to_hpa(101325.0))
    1013.25
    """
    return _num(x) / 100.0


def percent(x: ArrayLike) -> Array:
    """Percent to a fraction.

    Examples
    --------
    >>> from navlib import units
    >>> float(units.percent(0.5))   # a fraction
    0.005
    """
    return _num(x) / 100.0


def ppm(x: ArrayLike) -> Array:
    """Parts per million to a fraction.

    Examples
    --------
    >>> from navlib import units
    >>> float(units.ppm(300.0))   # a fraction (scale factor error)
    0.0003
    """
    return _num(x) * 1e-6


# unit string -> SI converter, used to read datasheet tables from data/.
CONVERTERS = {
    "rad": lambda x: _num(x),
    "deg": deg,
    "deg/s": deg_per_s,
    "deg/h": deg_per_h,
    "deg/sqrt(h)": deg_per_sqrt_h,
    "deg/s/sqrt(Hz)": deg_per_s_sqrt_hz,
    "deg/h/sqrt(h)": deg_per_h_sqrt_h,
    "m/s^2": lambda x: _num(x),
    "g": lambda x: _num(x) * G0,
    "mg": mg,
    "ug": ug,
    "ug/sqrt(Hz)": ug_per_sqrt_hz,
    "m/s/sqrt(h)": m_per_s_sqrt_h,
    "m/s^2/sqrt(Hz)": lambda x: _num(x),
    "uT": lambda x: _num(x),
    "G": gauss,
    "mG": lambda x: gauss(_num(x) * 1e-3),
    "Pa": lambda x: _num(x),
    "hPa": hpa,
    "Pa/s": lambda x: _num(x),
    "hPa/h": lambda x: hpa(x) / 3600.0,
    "%": percent,
    "ppm": ppm,
    "m": lambda x: _num(x),
    "s": lambda x: _num(x),
    "-": lambda x: _num(x),
}


@boundary
def to_si(value: ArrayLike, unit: Annotated[str, Check("choice", options=tuple(CONVERTERS))]) -> Array:
    """Convert ``value`` given in ``unit`` (a key of :data:`CONVERTERS`) to SI.

    Examples
    --------
    >>> from navlib import units
    >>> float(units.to_si(15.0, "deg/h"))                 # any unit of units.UNITS
    7.27220521664304e-05
    >>> float(units.to_si(2.0, "mg"))
    0.0196133
    """
    return CONVERTERS[unit](_num(value, "value"))
