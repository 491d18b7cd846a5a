"""Earth models: ellipsoids, Earth rate, normal gravity, radii, magnetic field.

Constants follow NIMA TR8350.2 (WGS84), the CGCS2000 definition and Moritz
(1980, GRS80). Derived constants (b, e^2, gamma_e, gamma_p) are computed from
the defining ones with the closed-form level-ellipsoid formulas, which
reproduce the printed WGS84 and GRS80 values to 1e-10 m/s^2 (tested against
``data/reference/``).

Vectors are in the ENU navigation frame. Latitude is ``lat``, longitude
``lon`` (rad unless ``deg=True``), height ``h`` above the ellipsoid (m).

Each function checks its arguments, then calls its unchecked core in :mod:`navlib._earth`; another module
that has checked a latitude or height itself calls the core.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import Annotated, Any

import numpy as np

from . import _earth
from ._typing import Array, ArrayLike, Dcm, Vec3
from ._validate import (
    Check,
    Real,
    Text,
    as_array,
    as_dcm,
    boundary,
    broadcast,
    fields_checked,
    flag,
    in_range,
    latitude,
    positive,
)

__all__ = [
    "Ellipsoid",
    "WGS84",
    "CGCS2000",
    "GRS80",
    "KRASSOVSKY",
    "OMEGA_IE",
    "earth_rate_n",
    "earth_rate_b",
    "gravity",
    "gravity_n",
    "radii",
    "transport_rate_n",
    "magnetic_field",
    "field_from_angles",
    "field_angles",
]


@dataclass(frozen=True)
class Ellipsoid:
    """A reference ellipsoid with its gravity-defining constants.

    Attributes
    ----------
    name : str
    a : float
        Semi-major axis (m).
    f : float
        Flattening.
    GM : float
        Geocentric gravitational constant (m^3/s^2).
    omega : float
        Angular velocity (rad/s).

    Examples
    --------
    >>> from navlib import earth
    >>> grs80 = earth.Ellipsoid("GRS80", a=6378137.0, f=1 / 298.257222101, GM=3.986005e14, omega=7.292115e-5)
    >>> round(float(earth.gravity(45.0, deg=True, ellipsoid=grs80)), 5)
    9.8062
    """

    name: Text
    a: Annotated[float, Check("scalar", within=(6e6, 7e6))]  # Earth-like values
    f: Annotated[float, Check("scalar", within=(0.0, 0.01))]
    GM: Annotated[float, Check("scalar", within=(3e14, 5e14))]
    omega: Annotated[float, Check("scalar", within=(0.0, 1e-4))]

    def __post_init__(self) -> None:
        fields_checked(self)

    @property
    def b(self) -> float:
        """Semi-minor axis (m)."""
        return self.a * (1 - self.f)

    @property
    def e2(self) -> float:
        """First eccentricity squared."""
        return self.f * (2 - self.f)

    @functools.cached_property
    def _normal_gravity(self) -> tuple[float, float]:
        # Moritz closed form (Heiskanen & Moritz 2-61/2-62; TR8350.2 ch. 4).
        a, b = self.a, self.b
        ep = np.sqrt(a * a - b * b) / b
        m = self.omega**2 * a * a * b / self.GM
        q0 = 0.5 * ((1 + 3 / ep**2) * np.arctan(ep) - 3 / ep)
        q0p = 3 * (1 + 1 / ep**2) * (1 - np.arctan(ep) / ep) - 1
        gamma_e = self.GM / (a * b) * (1 - m - m / 6 * ep * q0p / q0)
        gamma_p = self.GM / (a * a) * (1 + m / 3 * ep * q0p / q0)
        return float(gamma_e), float(gamma_p)

    @property
    def gamma_e(self) -> float:
        """Normal gravity at the equator (m/s^2)."""
        return self._normal_gravity[0]

    @property
    def gamma_p(self) -> float:
        """Normal gravity at the poles (m/s^2)."""
        return self._normal_gravity[1]

    @property
    def gravity_constants(self) -> tuple[float, ...]:
        """``(a, f, e2, m, gamma_e, k)`` for the compiled gravity kernel."""
        k = self.b * self.gamma_p / (self.a * self.gamma_e) - 1
        return (self.a, self.f, self.e2, self.m, self.gamma_e, k)

    @property
    def m(self) -> float:
        """omega^2 a^2 b / GM."""
        return self.omega**2 * self.a**2 * self.b / self.GM


OMEGA_IE = 7.292115e-5
"""Earth rotation rate (rad/s), WGS84/CGCS2000 defining value (15.041 deg/h)."""

EllipsoidArg = Annotated[Ellipsoid, Check("instance")]
"""An ellipsoid argument (e.g. ``WGS84``), checked by :func:`navlib._validate.boundary`."""

WGS84 = Ellipsoid("WGS84", 6378137.0, 1 / 298.257223563, 3.986004418e14, OMEGA_IE)
GRS80 = Ellipsoid("GRS80", 6378137.0, 1 / 298.257222101, 3.986005e14, OMEGA_IE)
CGCS2000 = Ellipsoid("CGCS2000", 6378137.0, 1 / 298.257222101, 3.986004418e14, OMEGA_IE)
# Krassovsky 1940 (Beijing 1954 grids) defines no gravity field; GM and omega
# are WGS84's so that gravity() still runs, but only a and f are meaningful.
KRASSOVSKY = Ellipsoid("Krassovsky1940", 6378245.0, 1 / 298.3, 3.986004418e14, OMEGA_IE)


@boundary
def earth_rate_n(lat: ArrayLike, deg: bool = False, ellipsoid: EllipsoidArg = WGS84) -> Array:
    """Earth rotation rate in ENU, ``[0, w cos(lat), w sin(lat)]`` (rad/s).

    Parameters
    ----------
    lat : array_like, shape (...)
        Geodetic latitude (rad, or deg with ``deg=True``).

    Returns
    -------
    w_ie_n : ndarray, shape (..., 3)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import earth
    >>> np.round(earth.earth_rate_n(60.0, deg=True) * 180 / np.pi * 3600, 3)   # deg/h: [east, north, up]
    array([ 0.   ,  7.521, 13.026])
    """
    lat = latitude(lat, "lat", deg=deg)
    return _earth.earth_rate_n(lat, ellipsoid)


@boundary
def earth_rate_b(C_bn: Dcm, lat: Real, deg: bool = False, ellipsoid: EllipsoidArg = WGS84) -> Array:
    r"""Earth rotation rate in the body frame, :math:`(C_b^n)^T \omega_{ie}^n` (rad/s), e.g. what a static gyro triad reads.

    Parameters
    ----------
    C_bn : array_like, shape (..., 3, 3)
        Attitude(s) (body to ENU).
    lat : float
        Geodetic latitude (rad, or deg with ``deg=True``).

    Returns
    -------
    w_ie_b : ndarray, shape (..., 3)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude, earth
    >>> C_bn = attitude.euler_to_dcm([90.0, 0.0, 0.0], deg=True)   # level, facing east
    >>> np.round(earth.earth_rate_b(C_bn, 60.0, deg=True) * 180 / np.pi * 3600, 3)   # deg/h: [right, forward, up]
    array([-7.521,  0.   , 13.026])
    """
    C = as_dcm(C_bn, "C_bn")
    lat_rad = latitude(lat, "lat", deg=deg)
    return np.einsum("...ji,j->...i", C, _earth.earth_rate_n(lat_rad, ellipsoid))


@boundary
def gravity(lat: ArrayLike, h: ArrayLike = 0.0, deg: bool = False, ellipsoid: EllipsoidArg = WGS84) -> Array:
    r"""Normal gravity magnitude (m/s^2): Somigliana with the TR8350.2 height series.

    .. math::

        \gamma &= \gamma_e \frac{1 + k \sin^2\varphi}{\sqrt{1 - e^2 \sin^2\varphi}}, \qquad
        k = \frac{b \gamma_p}{a \gamma_e} - 1 \\
        \gamma_h &= \gamma \Big[1 - \frac{2}{a}\big(1 + f + m - 2 f \sin^2\varphi\big) h + \frac{3 h^2}{a^2}\Big]

    at latitude :math:`\varphi` and height :math:`h`.

    Parameters
    ----------
    lat : array_like, shape (...)
        Geodetic latitude (rad, or deg with ``deg=True``).
    h : array_like, shape (...)
        Height above the ellipsoid (m), within [-12 km, 100 km].

    Returns
    -------
    ndarray, shape (...)

    Examples
    --------
    >>> from navlib import earth
    >>> round(float(earth.gravity(45.0, deg=True)), 4)   # m/s^2 at sea level
    9.8062
    """
    lat = latitude(lat, "lat", deg=deg)
    h = in_range(as_array(h, "h"), "h", -12e3, 100e3, "m")
    return _earth.gravity(lat, h, ellipsoid)


def gravity_n(lat: ArrayLike, h: ArrayLike = 0.0, deg: bool = False, ellipsoid: Ellipsoid = WGS84) -> Array:
    """Normal gravity vector in ENU, ``[0, 0, -gamma]`` (m/s^2); shape (..., 3).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import earth
    >>> np.round(earth.gravity_n(45.0, deg=True), 5)
    array([ 0.    ,  0.    , -9.8062])
    """
    return _earth.gravity_n(gravity(lat, h, deg=deg, ellipsoid=ellipsoid))


@boundary
def radii(lat: ArrayLike, deg: bool = False, ellipsoid: EllipsoidArg = WGS84) -> tuple[Array, Array]:
    r"""Meridian and prime-vertical radii of curvature (m).

    Returns
    -------
    R_M, R_N : ndarray, shape (...)
        :math:`R_N = a / \sqrt{1 - e^2 \sin^2\varphi}`, :math:`R_M = R_N (1 - e^2) / (1 - e^2 \sin^2\varphi)`.

    Examples
    --------
    >>> from navlib import earth
    >>> R_M, R_N = earth.radii(45.0, deg=True)
    >>> round(float(R_M), 1), round(float(R_N), 1)
    (6367381.8, 6388838.3)
    """
    lat = latitude(lat, "lat", deg=deg)
    return _earth.radii(lat, ellipsoid)


@boundary
def transport_rate_n(lat: ArrayLike, h: ArrayLike, vel_n: Vec3, ellipsoid: EllipsoidArg = WGS84) -> Array:
    r"""Transport rate of the ENU frame over the ellipsoid (rad/s).

    .. math::

        \omega_{en}^n = \Big[-\frac{v_N}{R_M + h},\ \frac{v_E}{R_N + h},\ \frac{v_E \tan\varphi}{R_N + h}\Big]

    Parameters
    ----------
    lat : array_like, shape (...)  (rad)
    h : array_like, shape (...)  (m)
    vel_n : array_like, shape (..., 3)  ENU velocity (m/s)

    Returns
    -------
    ndarray, shape (..., 3)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import earth
    >>> np.round(earth.transport_rate_n(0.0, 0.0, [0.0, 10.0, 0.0]) * 1e6, 4)   # 10 m/s north at the equator (urad/s)
    array([-1.5784,  0.    ,  0.    ])
    """
    lat = latitude(lat)
    if np.any(np.cos(lat) < 1e-9):
        raise ValueError(
            "lat: the ENU transport rate is singular at the poles (east is undefined there); expected |lat| < 90 deg"
        )
    h = in_range(as_array(h, "h"), "h", -12e3, 1e6, "m")
    vel_n = as_array(vel_n, "vel_n", tail=(3,))
    return _earth.transport_rate_n(lat, h, vel_n, ellipsoid)


# --------------------------------------------------------------------------
# Geomagnetic field
# --------------------------------------------------------------------------

# World Magnetic Model epochs shipped with pygeomag: (first year, file).
_WMM_MODELS = [
    (2010.0, "wmm/WMM_2010.COF"),
    (2015.0, "wmm/WMM_2015v2.COF"),
    (2020.0, "wmm/WMM_2020.COF"),
    (2025.0, "wmm/WMM_2025.COF"),
]


@functools.cache
def _geomag(coefficients_file: str) -> Any:
    from pygeomag import GeoMag  # imported lazily: only magnetometer users need it

    return GeoMag(coefficients_file=coefficients_file)


def _wmm_file(year: float) -> str:
    """The model file of a checked year."""
    return [f for start, f in _WMM_MODELS if year >= start][-1]


WmmYear = Annotated[float, Check("scalar", within=(2010.0, 2030.0), open_ends=(False, True))]
"""A decimal year the World Magnetic Model epochs shipped with pygeomag cover."""


@boundary
def magnetic_field(lat: ArrayLike, lon: ArrayLike, h: ArrayLike = 0.0, year: WmmYear = 2025.0, deg: bool = True) -> Array:
    """Main geomagnetic field from the World Magnetic Model (through pygeomag).

    The WMM epoch (2010, 2015v2, 2020, 2025) is chosen from ``year``; each is
    valid for five years. Tested against NOAA's official WMM test values.

    Parameters
    ----------
    lat, lon : array_like, shape (...)
        Geodetic latitude and longitude (deg by default; rad with ``deg=False``).
    h : array_like, shape (...)
        Height above the WGS84 ellipsoid (m).
    year : float
        Decimal year, e.g. 2016.5.

    Returns
    -------
    B_n : ndarray, shape (..., 3)
        Field in ENU (uT): ``[east, north, up]``. In the northern hemisphere
        the up component is negative (the field dips into the ground).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import earth
    >>> np.round(earth.magnetic_field(45.0, 10.0, 0.0, year=2025.0), 1)   # ENU (uT)
    array([  1.5,  22.8, -41.8])
    """
    lat = latitude(lat, "lat", deg=deg)
    lon = as_array(lon, "lon")
    in_range(lon, "lon", -2 * np.pi, 2 * np.pi, "rad") if not deg else in_range(lon, "lon", -360, 360, "deg")
    lon = np.deg2rad(lon) if deg else lon
    h = in_range(as_array(h, "h"), "h", -1e3, 850e3, "m")
    gm = _geomag(_wmm_file(year))
    lat, lon, h = np.broadcast_arrays(lat, lon, h)
    out = np.empty(lat.shape + (3,))
    for idx in np.ndindex(lat.shape):
        r = gm.calculate(
            glat=float(np.rad2deg(lat[idx])), glon=float(np.rad2deg(lon[idx])), alt=float(h[idx]) / 1000.0, time=float(year)
        )
        out[idx] = (r.y / 1000.0, r.x / 1000.0, -r.z / 1000.0)  # NED nT -> ENU uT
    return out


def field_from_angles(declination: ArrayLike, inclination: ArrayLike, intensity: ArrayLike, deg: bool = True) -> Array:
    """Field vector in ENU from declination, inclination and intensity.

    Parameters
    ----------
    declination : array_like
        D, east of true north positive (deg by default).
    inclination : array_like
        I, positive when the field points down (deg by default).
    intensity : array_like
        Total intensity F (uT).

    Returns
    -------
    B_n : ndarray, shape (..., 3)  (uT)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import earth
    >>> np.round(earth.field_from_angles(0.0, 60.0, 50.0), 3)       # ENU (uT): north and down
    array([  0.   ,  25.   , -43.301])
    """
    D = as_array(declination, "declination")
    I = as_array(inclination, "inclination")
    F = positive(intensity, "intensity", allow_zero=True)
    D, I, F = broadcast(D, I, F, name="declination", of="declination, inclination, intensity")
    if flag(deg, "deg"):
        D, I = np.deg2rad(D), np.deg2rad(I)
    in_range(I, "inclination", -np.pi / 2, np.pi / 2, "rad")
    H = F * np.cos(I)
    return np.stack([H * np.sin(D), H * np.cos(D), -F * np.sin(I)], -1)


def field_angles(B_n: Vec3, deg: bool = True) -> tuple[Array, Array, Array]:
    """Declination, inclination and intensity of ENU field vectors.

    Parameters
    ----------
    B_n : array_like, shape (..., 3)

    Returns
    -------
    declination, inclination, intensity : ndarray, shape (...)

    Examples
    --------
    >>> from navlib import earth
    >>> D, I, F = earth.field_angles([0.0, 20.0, -40.0])             # ENU field (uT)
    >>> round(float(D), 3), round(float(I), 3), round(float(F), 3)
    (0.0, 63.435, 44.721)
    """
    D, I, F = _earth.field_angles(as_array(B_n, "B_n", tail=(3,)))
    if flag(deg, "deg"):
        D, I = np.rad2deg(D), np.rad2deg(I)
    return D, I, F
