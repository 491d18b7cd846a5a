"""Gauss–Krüger projection, zone numbers, meridian arc, geodetic <-> ECEF <-> local ENU/NED.

Generic geodesy: every ``ellipsoid`` defaults to ``earth.WGS84``, as in
other geodesy libraries (pymap3d, PROJ); pass ``earth.CGCS2000`` for China's
national grid. GK is the tangent transverse Mercator (scale 1 on the central
meridian, no 0.9996 as in UTM). As in Chinese practice, **x is the northing**
(meridian arc from the equator) and **y the easting** from the central
meridian; no false easting and no zone prefix unless asked for
(``false_easting=500e3, zone_prefix=True`` gives EPSG:4528-style eastings
such as 40 419 944.950 m on CGCS2000).

Paper 002 (Zhao et al. 2023, :mod:`navlib.papers.gauss_kruger_ekf`) projects
GPS latitude/longitude to GK coordinates in 3° zones before its EKF; that
companion holds the paper's own equations (printed zone number, radii, the
e^8 meridian-arc series and the sixth-order series in l) and their errata.

Implementation
--------------
:func:`geodetic2gk` / :func:`gk2geodetic` use Krüger's series in the third
flattening n to order n^6 (Karney 2011, "Transverse Mercator with an accuracy
of a few nanometers", J. Geodesy 85:475, eqs. 7–11, 35–36), evaluated with
Clenshaw summation on complex numbers: ~nm error within 3900 km of the central
meridian, so 3° and 6° zones are far inside its range. The inverse solves
the conformal latitude by Newton's method. Grid convergence and point scale
come from the derivative of the same series (:func:`convergence`,
:func:`scale_factor`); :func:`meridian_arc` is the same series on the
central meridian. The series is a compiled per-point kernel (numba); the
transcendental functions it needs (tan, atanh, sinh, atan2, asinh, and sin,
cos, sinh, cosh for the inverse) are numpy's vectorised ones rather than scalar calls
inside a loop. The series, zone numbers and central meridians, unchecked, are
:mod:`navlib._geodesy` (for callers that have checked their points themselves).

Zone numbers: 3° zone n covers ``3n ± 1.5°``, so :func:`zone` uses
``n = floor((L + 1.5)/3)`` (0 ≤ L < 1.5° E is zone 120, central meridian 0°;
paper 002 prints ``n = (L - 1.5)/3``, erratum E002-01).

Longitude is ``lon`` and latitude ``lat``. Angles in rad unless ``deg=True``;
distances in m.

Bad input: every public function raises an error whose message starts with
the argument's name -- ``TypeError`` (navlib's ``InputTypeError``, also a
``ValueError``) for strings, complex, boolean, object or ragged input, a
``ellipsoid`` that is not an :class:`navlib.earth.Ellipsoid` and a ``project``
that is not callable; ``ValueError`` for NaN, infinity (no function here takes
NaN as a marker), empty arrays, shapes that do not broadcast, and out-of-range
values (|lat| > 90°, a longitude too far from the zone, zone numbers, ``k0``,
``width``...).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Annotated

import numpy as np

from . import _earth, _geodesy
from ._typing import Array, ArrayLike
from ._validate import (
    Check,
    Real,
    as_array,
    boundary,
    broadcast,
    choice,
    flag,
    in_range,
    lat_lon,
    latitude,
    longitude,
    zone_offset,
)
from .earth import WGS84, Ellipsoid, EllipsoidArg

__all__ = [
    "zone",
    "central_meridian",
    "geodetic2gk",
    "gk2geodetic",
    "convergence",
    "scale_factor",
    "meridian_arc",
    "geodetic2ecef",
    "ecef2geodetic",
    "geodetic2enu",
    "enu2geodetic",
    "geodetic2ned",
    "ned2geodetic",
    "local_scales",
]

ZONE_WIDTHS = (3, 6)
_MAX_OFFSET_DEG = 60.0  # hard limit from the central meridian (series valid to ~ 3900 km at 35° N)
_PREFIX_UNIT = 1e6  # zone number times 1e6 m prefixed to the easting
_K0_RANGE = (0.5, 1.5)  # accepted central-meridian scales k0 (GK 1, UTM 0.9996)
GridScale = Annotated[float, Check("scalar", within=_K0_RANGE)]
"""The central-meridian scale k0 of a grid."""
ZoneWidth = Annotated[int, Check("choice", options=ZONE_WIDTHS)]
"""A zone width (deg): 3 or 6."""
MaxOffset = Annotated[float, Check("scalar", within=(0.0, _MAX_OFFSET_DEG), open_ends=(True, False))]
"""The largest allowed ``|lon - lon0|`` (deg), at most the series' 60°."""


# --------------------------------------------------------------------------
# Zones
# --------------------------------------------------------------------------


def _width(width: object) -> int:
    """The zone width (deg) as an int: 3 or 6."""
    return int(choice(width, "width", ZONE_WIDTHS))


def zone(lon: ArrayLike, width: int = 3, deg: bool = False) -> np.ndarray:
    """Gauss–Krüger zone number (corrected Eq. 1).

    3° zones: ``n = floor((L + 1.5)/3)``, 1–120, with 0 ≤ L < 1.5° E (and
    358.5°–360°) in zone 120. 6° zones: ``n = floor(L/6) + 1``, 1–60. L is
    taken modulo 360° east, so western longitudes get their zone too.

    Parameters
    ----------
    lon : array_like, shape (...)
        Longitude (rad, or deg with ``deg=True``).
    width : {3, 6}
        Zone width (deg).

    Returns
    -------
    ndarray of int, shape (...)

    Examples
    --------
    >>> from navlib import geodesy
    >>> int(geodesy.zone(114.3, deg=True)), int(geodesy.zone(114.3, width=6, deg=True))
    (38, 20)
    """
    return _geodesy.zone(longitude(lon, "lon", deg), _width(width))


def central_meridian(zone_number: ArrayLike, width: int = 3, deg: bool = False) -> np.ndarray:
    """Central meridian of a zone (Eq. 2: ``L0 = 3n`` for 3° zones; ``6n - 3`` for 6°), in (-180°, 180°].

    Parameters
    ----------
    zone_number : array_like of int, shape (...)
        1–120 for 3° zones, 1–60 for 6° zones.
    width : {3, 6}
    deg : bool
        Return degrees instead of rad.

    Examples
    --------
    >>> from navlib import geodesy
    >>> geodesy.central_meridian([39, 40], width=3, deg=True)       # 3 deg zones: L0 = 3 n
    array([117., 120.])
    """
    return _central_meridian(zone_number, _width(width), deg, "zone_number")


def _central_meridian(zone_number: object, w: int, deg: bool, name: str) -> Array:
    n = as_array(zone_number, name, nonempty=True)
    if np.any(n != np.round(n)):
        raise ValueError(f"{name}: expected integer zone numbers")
    in_range(n, name, 1, 360 // w)
    L0 = _geodesy.meridian(n, w)
    return L0 if flag(deg, "deg") else np.deg2rad(L0)


def _resolve_lon0(lon_deg, zone_number, lon0, w, deg, max_offset_deg):
    """Central meridian (deg) for every point and the longitude offset l (deg); ``w`` the checked zone width."""
    if lon0 is not None and zone_number is not None:
        raise ValueError("lon0, zone: give at most one of them")
    if lon0 is None and zone_number is None:
        L0 = _geodesy.meridian(_geodesy.zone(lon_deg, w).astype(float), w)
        limit = np.inf
    else:
        L0 = _central_meridian(zone_number, w, True, "zone") if lon0 is None else longitude(lon0, "lon0", deg)
        limit = float(w if max_offset_deg is None else max_offset_deg)
    return L0, zone_offset(lon_deg - L0, min(limit, _MAX_OFFSET_DEG), w)


@boundary
def geodetic2gk(
    lat: ArrayLike,
    lon: ArrayLike,
    *,
    zone: ArrayLike | None = None,
    lon0: ArrayLike | None = None,
    width: int = 3,
    ellipsoid: EllipsoidArg = WGS84,
    deg: bool = False,
    k0: GridScale = 1.0,
    false_easting: Real = 0.0,
    false_northing: Real = 0.0,
    zone_prefix: bool = False,
    max_offset_deg: MaxOffset | None = None,
) -> tuple[Array, Array]:
    """Gauss–Krüger forward projection (Eq. 9, by Krüger's n-series).

    Parameters
    ----------
    lat, lon : array_like, broadcasting to shape (...)
        Geodetic latitude and longitude (rad, or deg with ``deg=True``).
    zone : int or array_like of int, optional
        Project into this zone (e.g. to hold one zone across a boundary).
    lon0 : float or array_like, optional
        Central meridian instead of a zone (rad, or deg with ``deg=True``).
        Without ``zone`` and ``lon0`` every point uses its own zone.
    width : {3, 6}
        Zone width (deg); the paper uses 3° zones.
    ellipsoid : earth.Ellipsoid
        Default WGS84; pass ``earth.CGCS2000`` for China's national grid
        (``earth.KRASSOVSKY`` for the older Beijing 1954 grid...).
    k0 : float
        Scale on the central meridian: 1 for GK (0.9996 for UTM).
    false_easting, false_northing : float
        Added to easting and northing (m); China uses 500 000 m easting.
    zone_prefix : bool
        Add ``zone * 1e6`` m to the easting (e.g. 40 419 944.950 m); needs
        ``false_easting=500e3`` so that the zone can be read back.
    max_offset_deg : float, optional
        With ``zone`` or ``lon0``: largest allowed ``|lon - lon0|`` (deg);
        default the zone width (the zone plus half of each neighbour). At
        most 60°.

    Returns
    -------
    x, y : ndarray, shape (...)
        Northing x and easting y (m), the paper's order.

    Examples
    --------
    >>> from navlib import geodesy
    >>> x, y = geodesy.geodetic2gk(30.0, 114.3, deg=True)                 # 3-degree zone 38
    >>> round(float(x), 3), round(float(y), 3)
    (3320151.288, 28945.951)
    """
    lat_rad, lon_deg = lat_lon(lat, lon, deg)
    w = _width(width)
    L0, l_deg = _resolve_lon0(lon_deg, zone, lon0, w, deg, max_offset_deg)
    x, y = _geodesy.forward(lat_rad, l_deg, ellipsoid, k0, false_northing, false_easting)
    if flag(zone_prefix, "zone_prefix"):
        if not (y.min(initial=0.0) >= 0 and y.max(initial=0.0) < _PREFIX_UNIT):
            raise ValueError("false_easting: zone_prefix needs eastings in [0, 1e6) m; use false_easting=500e3")
        y = y + _PREFIX_UNIT * _geodesy.zone(L0, w)
    return x, y


@boundary
def gk2geodetic(
    x: ArrayLike,
    y: ArrayLike,
    *,
    zone: ArrayLike | None = None,
    lon0: ArrayLike | None = None,
    width: int = 3,
    ellipsoid: EllipsoidArg = WGS84,
    deg: bool = False,
    k0: GridScale = 1.0,
    false_easting: Real = 0.0,
    false_northing: Real = 0.0,
    zone_prefix: bool = False,
) -> tuple[Array, Array]:
    """Gauss–Krüger inverse projection.

    Parameters
    ----------
    x, y : array_like, broadcasting to shape (...)
        Northing and easting (m), with the same false easting/northing and
        prefix conventions as :func:`geodetic2gk`.
    zone, lon0 : optional
        The zone or central meridian (rad, or deg with ``deg=True``). With
        ``zone_prefix=True`` the zone is read from the easting instead.
    width, ellipsoid, k0, false_easting, false_northing, zone_prefix
        As in :func:`geodetic2gk`.

    Returns
    -------
    lat, lon : ndarray, shape (...)
        rad, or deg with ``deg=True``; lon in (-180°, 180°].

    Examples
    --------
    >>> from navlib import geodesy
    >>> x, y = geodesy.geodetic2gk(26.0, 119.2, zone=40, deg=True)
    >>> lat, lon = geodesy.gk2geodetic(x, y, zone=40, deg=True)
    >>> round(float(lat), 9), round(float(lon), 9)
    (26.0, 119.2)
    """
    x = as_array(x, "x", nonempty=True)
    y = as_array(y, "y", nonempty=True)
    w = _width(width)
    if flag(zone_prefix, "zone_prefix"):
        if zone is not None or lon0 is not None:
            raise ValueError("zone, lon0: not used with zone_prefix=True (the zone is read from the easting)")
        zone = np.floor(y / _PREFIX_UNIT)
        y = y - _PREFIX_UNIT * zone
    if (zone is None) == (lon0 is None):
        raise ValueError("zone, lon0: give exactly one of them (or zone_prefix=True)")
    L0 = _central_meridian(zone, w, True, "y" if zone_prefix else "zone") if lon0 is None else longitude(lon0, "lon0", deg)
    x, y, L0 = broadcast(x, y, L0, name="x, y", of="x, y and the central meridian")
    xi, eta = _geodesy.normalised(x, y, ellipsoid, k0, false_northing, false_easting)
    if np.any(np.abs(eta) > _geodesy.MAX_ETA):
        raise ValueError(f"y: easting too far from the central meridian for the series (|y| > {_geodesy.MAX_ETA:g} A k0)")
    lat, lon_deg = _geodesy.geodetic(xi, eta, L0, ellipsoid)
    return (np.rad2deg(lat), lon_deg) if flag(deg, "deg") else (lat, np.deg2rad(lon_deg))


def _factors(lat, lon, zone, lon0, width, ellipsoid, deg, max_offset_deg):
    lat_rad, lon_deg = lat_lon(lat, lon, deg)
    _, l_deg = _resolve_lon0(lon_deg, zone, lon0, _width(width), deg, max_offset_deg)
    return _geodesy.factors(lat_rad, l_deg, ellipsoid)


@boundary
def convergence(
    lat: ArrayLike,
    lon: ArrayLike,
    *,
    zone: ArrayLike | None = None,
    lon0: ArrayLike | None = None,
    width: int = 3,
    ellipsoid: EllipsoidArg = WGS84,
    deg: bool = False,
    max_offset_deg: MaxOffset | None = None,
) -> Array:
    """Grid (meridian) convergence gamma: the grid bearing of true north is ``-gamma``.

    Positive east of the central meridian in the northern hemisphere
    (``gamma ≈ l sin(lat)``), as PROJ's ``meridian_convergence``. A heading
    clockwise from true north becomes a grid heading by
    ``heading_grid = heading_true - gamma``.

    Parameters are those of :func:`geodetic2gk`.

    Returns
    -------
    gamma : ndarray, shape (...)
        rad, or deg with ``deg=True``.

    Examples
    --------
    >>> from navlib import geodesy
    >>> round(float(geodesy.convergence(26.0, 121.0, lon0=120.0, deg=True)), 4)   # deg; about (L - L0) sin(lat)
    0.4384
    """
    gamma, _ = _factors(lat, lon, zone, lon0, width, ellipsoid, deg, max_offset_deg)
    return np.rad2deg(gamma) if deg else gamma


@boundary
def scale_factor(
    lat: ArrayLike,
    lon: ArrayLike,
    *,
    zone: ArrayLike | None = None,
    lon0: ArrayLike | None = None,
    width: int = 3,
    ellipsoid: EllipsoidArg = WGS84,
    deg: bool = False,
    k0: GridScale = 1.0,
    max_offset_deg: MaxOffset | None = None,
) -> Array:
    """Point scale factor k of the projection (1 on the central meridian for GK).

    Parameters are those of :func:`geodetic2gk`; returns shape (...).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import geodesy
    >>> np.round(geodesy.scale_factor(26.0, [120.0, 121.5], lon0=120.0, deg=True), 7)   # 1 on the central meridian
    array([1.       , 1.0002784])
    """
    _, k = _factors(lat, lon, zone, lon0, width, ellipsoid, deg, max_offset_deg)
    return k0 * k


@boundary
def meridian_arc(lat: ArrayLike, ellipsoid: EllipsoidArg = WGS84, deg: bool = False) -> Array:
    """Meridian arc length S from the equator (m), by Krüger's n^6 series (nm accuracy).

    Parameters
    ----------
    lat : array_like, shape (...)
        Geodetic latitude (rad, or deg with ``deg=True``).
    ellipsoid : earth.Ellipsoid
        Default WGS84; pass ``earth.CGCS2000`` for China's national grid.

    Returns
    -------
    S : ndarray, shape (...)

    Examples
    --------
    >>> from navlib import geodesy
    >>> round(float(geodesy.meridian_arc(90.0, deg=True)), 3)      # equator to pole (m)
    10001965.729
    """
    lat = latitude(lat, "lat", deg=deg, nonempty=True)
    return _geodesy.forward(lat, np.zeros_like(lat), ellipsoid)[0]


def _gk_project(lat, lon, lon0, ellipsoid):
    """:func:`geodetic2gk` of checked points about the central meridian lon0 (all rad), any offset up to the
    series' 60° limit."""
    l_deg = zone_offset(np.rad2deg(lon) - np.rad2deg(lon0), _MAX_OFFSET_DEG, 3)
    return _geodesy.forward(lat, l_deg, ellipsoid, 1.0, 0.0, 0.0)


@boundary
def local_scales(
    lat: ArrayLike,
    lon: ArrayLike,
    lon0: ArrayLike,
    ellipsoid: EllipsoidArg = WGS84,
    deg: bool = False,
    project: Callable[..., tuple[Array, Array]] | None = None,
    step: Annotated[float, Check("scalar", within=(0.0, 0.01), open_ends=(True, False))] = 1e-6,
) -> tuple[Array, Array, Array]:
    """Meridian and parallel scale factors and the angle between their images, by central differences.

    A conformal projection has equal scales ``h = k`` and images of meridian
    and parallel at right angles; this measures both for :func:`geodetic2gk`
    (default) or any other projection passed as ``project``.

    Parameters
    ----------
    lat, lon, lon0 : array_like, broadcasting to shape (...)
        rad, or deg with ``deg=True``.
    ellipsoid : earth.Ellipsoid
        Default WGS84; pass ``earth.CGCS2000`` for China's national grid.
    project : callable, optional
        ``project(lat, lon, lon0, ellipsoid) -> (x, y)`` with angles in rad and
        x, y in m, evaluated on arrays of shape (...); default
        :func:`geodetic2gk` about the central meridian ``lon0``.
    step : float
        Difference step (rad).

    Returns
    -------
    h, k : ndarray, shape (...)
        Meridian scale ``|dP/dlat| / R_M`` and parallel scale ``|dP/dlon| / (R_N cos lat)``
        (radii of curvature from :func:`navlib.earth.radii`).
    angle : ndarray, shape (...)
        Angle between the images of the meridian and the parallel (rad; pi/2 if conformal).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import geodesy
    >>> h, k, angle = geodesy.local_scales(26.0, 121.0, 120.0, deg=True)   # Gauss-Krueger: conformal
    >>> round(abs(float(h - k)), 9), round(float(np.rad2deg(angle)), 6)   # equal scales, right angle
    (0.0, 90.0)
    """
    if project is None:
        project = _gk_project
    elif not callable(project):
        raise TypeError(f"project: expected a callable (lat, lon, lon0, ellipsoid) -> (x, y), got {type(project).__name__}")
    lat_r, lon_d = lat_lon(lat, lon, deg)
    lon0_d = longitude(lon0, "lon0", deg)
    lon_r, lon0_r = np.deg2rad(lon_d), np.deg2rad(lon0_d)

    def xy(la, lo):
        return np.stack(project(la, lo, lon0_r, ellipsoid), -1)

    d_lat = (xy(lat_r + step, lon_r) - xy(lat_r - step, lon_r)) / (2 * step)
    d_lon = (xy(lat_r, lon_r + step) - xy(lat_r, lon_r - step)) / (2 * step)
    R_M, R_N = _earth.radii(lat_r, ellipsoid)
    h = np.linalg.norm(d_lat, axis=-1) / R_M
    k = np.linalg.norm(d_lon, axis=-1) / (R_N * np.cos(lat_r))
    cross = d_lat[..., 0] * d_lon[..., 1] - d_lat[..., 1] * d_lon[..., 0]
    angle = np.arctan2(np.abs(cross), np.sum(d_lat * d_lon, axis=-1))
    return h, k, angle


# --------------------------------------------------------------------------
# Geodetic <-> ECEF <-> local ENU (pymap3d-style)
# --------------------------------------------------------------------------


@boundary
def geodetic2ecef(
    lat: ArrayLike, lon: ArrayLike, h: ArrayLike, ellipsoid: EllipsoidArg = WGS84, deg: bool = False
) -> tuple[Array, Array, Array]:
    """Earth-centred Earth-fixed coordinates (m) of geodetic points; returns x, y, z of shape (...).

    ``ellipsoid``: default WGS84; pass ``earth.CGCS2000`` for China's national grid.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import geodesy
    >>> np.round(geodesy.geodetic2ecef(0.0, 90.0, 0.0, deg=True), 3)   # on the equator, 90 deg east: the y axis
    array([      0., 6378137.,       0.])
    """
    return _ecef(*_geodetic(lat, lon, h, deg), ellipsoid)


def _geodetic(
    lat: ArrayLike, lon: ArrayLike, h: ArrayLike, deg: bool, names: tuple[str, str, str] = ("lat", "lon", "h")
) -> tuple[Array, Array, Array]:
    """Latitude (rad), longitude (rad) and height (m) of geodetic points, each checked under its name."""
    lat_rad, lon_deg = lat_lon(lat, lon, deg, names[:2])
    h = as_array(h, names[2], nonempty=True)
    broadcast(h, lat_rad, name=names[2], of=f"{names[2]} and {names[0]}, {names[1]}")
    return lat_rad, np.deg2rad(lon_deg), h


def _ecef(lat: Array, lon: Array, h: Array, ellipsoid: Ellipsoid) -> tuple[Array, Array, Array]:
    """:func:`geodetic2ecef` of checked points (rad, rad, m)."""
    R_N = ellipsoid.a / np.sqrt(1 - ellipsoid.e2 * np.sin(lat) ** 2)
    r = (R_N + h) * np.cos(lat)
    return r * np.cos(lon), r * np.sin(lon), (R_N * (1 - ellipsoid.e2) + h) * np.sin(lat)


@boundary
def ecef2geodetic(
    x: ArrayLike, y: ArrayLike, z: ArrayLike, ellipsoid: EllipsoidArg = WGS84, deg: bool = False
) -> tuple[Array, Array, Array]:
    """Geodetic latitude, longitude (rad or deg) and height (m) of ECEF points (m).

    Bowring's iteration on the parametric latitude (three steps reach 1e-15
    rad for points within 100 km of the surface). ``ellipsoid``: default WGS84;
    pass ``earth.CGCS2000`` for China's national grid.

    Examples
    --------
    >>> from navlib import geodesy
    >>> lat, lon, h = geodesy.ecef2geodetic(*geodesy.geodetic2ecef(30.0, 114.0, 50.0, deg=True), deg=True)
    >>> round(float(lat), 9), round(float(lon), 9), round(float(h), 6)
    (30.0, 114.0, 50.0)
    """
    x, y, z = broadcast(*(as_array(v, k, nonempty=True) for v, k in ((x, "x"), (y, "y"), (z, "z"))), name="x, y, z")
    return _from_ecef(x, y, z, ellipsoid, deg)


def _from_ecef(x, y, z, ellipsoid, deg):
    """:func:`ecef2geodetic` of checked coordinates (m) of one shape."""
    a, b, e2 = ellipsoid.a, ellipsoid.b, ellipsoid.e2
    ep2 = e2 / (1 - e2)
    p = np.hypot(x, y)
    if np.any(p + np.abs(z) < 1e5):
        raise ValueError("x, y, z: expected points away from the Earth's centre (> 100 km)")
    beta = np.arctan2(z * a, p * b)
    for _ in range(3):
        lat = np.arctan2(z + ep2 * b * np.sin(beta) ** 3, p - e2 * a * np.cos(beta) ** 3)
        beta = np.arctan2(b * np.sin(lat), a * np.cos(lat))
    R_N = a / np.sqrt(1 - e2 * np.sin(lat) ** 2)
    with np.errstate(divide="ignore", invalid="ignore"):  # np.where evaluates both branches
        h = np.where(np.abs(np.cos(lat)) > 0.1, p / np.cos(lat) - R_N, z / np.sin(lat) - R_N * (1 - e2))
    lon = np.arctan2(y, x)
    return (np.rad2deg(lat), np.rad2deg(lon), h) if flag(deg, "deg") else (lat, lon, h)


_ORIGIN = ("lat0", "lon0", "h0")


def _enu_rotation(lat0, lon0):
    sl, cl, so, co = np.sin(lat0), np.cos(lat0), np.sin(lon0), np.cos(lon0)
    # rows: east, north, up written in ECEF
    return np.stack(
        [
            np.stack([-so, co, np.zeros_like(so)], -1),
            np.stack([-sl * co, -sl * so, cl], -1),
            np.stack([cl * co, cl * so, sl], -1),
        ],
        -2,
    )


@boundary
def geodetic2enu(
    lat: ArrayLike,
    lon: ArrayLike,
    h: ArrayLike,
    lat0: ArrayLike,
    lon0: ArrayLike,
    h0: ArrayLike,
    ellipsoid: EllipsoidArg = WGS84,
    deg: bool = False,
) -> tuple[Array, Array, Array]:
    """East, north, up (m) of geodetic points in the local tangent frame at (lat0, lon0, h0).

    All arguments broadcast; angles in rad (deg with ``deg=True``). Returns
    e, n, u of shape (...). ``ellipsoid``: default WGS84; pass ``earth.CGCS2000``
    for China's national grid.

    Examples
    --------
    >>> from navlib import geodesy
    >>> e, n, u = geodesy.geodetic2enu(30.001, 114.0, 10.0, 30.0, 114.0, 0.0, deg=True)   # 0.001 deg north, 10 m up
    >>> round(float(e), 3), round(float(n), 3), round(float(u), 3)
    (0.0, 110.853, 9.999)
    """
    lat0, lon0, h0 = _geodetic(lat0, lon0, h0, deg, _ORIGIN)
    p = np.stack(_ecef(*_geodetic(lat, lon, h, deg), ellipsoid), -1)
    p0 = np.stack(_ecef(lat0, lon0, h0, ellipsoid), -1)
    enu = np.einsum("...ij,...j->...i", _enu_rotation(lat0, lon0), p - p0)
    return enu[..., 0], enu[..., 1], enu[..., 2]


@boundary
def enu2geodetic(
    e: ArrayLike,
    n: ArrayLike,
    u: ArrayLike,
    lat0: ArrayLike,
    lon0: ArrayLike,
    h0: ArrayLike,
    ellipsoid: EllipsoidArg = WGS84,
    deg: bool = False,
) -> tuple[Array, Array, Array]:
    """Inverse of :func:`geodetic2enu`: geodetic lat, lon (rad or deg), h (m) of local ENU points.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import geodesy
    >>> lat, lon, h = geodesy.enu2geodetic(100.0, 200.0, 10.0, 30.0, 114.0, 0.0, deg=True)
    >>> np.round(geodesy.geodetic2enu(lat, lon, h, 30.0, 114.0, 0.0, deg=True), 6)   # back again
    array([100., 200.,  10.])
    """
    return _local2geodetic((e, n, u), ("e", "n", "u"), 1.0, (lat0, lon0, h0), ellipsoid, deg)


def _local2geodetic(
    local: tuple[ArrayLike, ArrayLike, ArrayLike],
    names: tuple[str, str, str],
    up: float,
    origin: tuple[ArrayLike, ArrayLike, ArrayLike],
    ellipsoid: Ellipsoid,
    deg: bool,
) -> tuple[Array, Array, Array]:
    """Geodetic points of local coordinates ``local`` (east, north, up or down: ``up`` = 1.0 or -1.0)
    about ``origin`` (lat0, lon0, h0), each argument checked under its name."""
    e, n, v = broadcast(*(as_array(x, k, nonempty=True) for x, k in zip(local, names, strict=True)), name=", ".join(names))
    enu = np.stack([e, n, v if up == 1.0 else -v], -1)
    lat0, lon0, h0 = _geodetic(*origin, deg, _ORIGIN)
    p0 = np.stack(_ecef(lat0, lon0, h0, ellipsoid), -1)
    p = p0 + np.einsum("...ji,...j->...i", _enu_rotation(lat0, lon0), enu)
    return _from_ecef(p[..., 0], p[..., 1], p[..., 2], ellipsoid, deg)


def geodetic2ned(
    lat: ArrayLike,
    lon: ArrayLike,
    h: ArrayLike,
    lat0: ArrayLike,
    lon0: ArrayLike,
    h0: ArrayLike,
    ellipsoid: EllipsoidArg = WGS84,
    deg: bool = False,
) -> tuple[Array, Array, Array]:
    """North, east, down (m) of geodetic points in the local frame at (lat0, lon0, h0): :func:`geodetic2enu` reordered.

    Examples
    --------
    >>> from navlib import geodesy
    >>> n, e, d = geodesy.geodetic2ned(30.001, 114.0, 10.0, 30.0, 114.0, 0.0, deg=True)
    >>> round(float(n), 3), round(float(e), 3), round(float(d), 3)
    (110.853, 0.0, -9.999)
    """
    e, n, u = geodetic2enu(lat, lon, h, lat0, lon0, h0, ellipsoid, deg)
    return n, e, -u


@boundary
def ned2geodetic(
    n: ArrayLike,
    e: ArrayLike,
    d: ArrayLike,
    lat0: ArrayLike,
    lon0: ArrayLike,
    h0: ArrayLike,
    ellipsoid: EllipsoidArg = WGS84,
    deg: bool = False,
) -> tuple[Array, Array, Array]:
    """Inverse of :func:`geodetic2ned`: geodetic lat, lon (rad or deg), h (m) of local NED points.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import geodesy
    >>> lat, lon, h = geodesy.ned2geodetic(200.0, 100.0, -10.0, 30.0, 114.0, 0.0, deg=True)
    >>> np.round(geodesy.geodetic2ned(lat, lon, h, 30.0, 114.0, 0.0, deg=True), 6)
    array([200., 100., -10.])
    """
    return _local2geodetic((e, n, d), ("e", "n", "d"), -1.0, (lat0, lon0, h0), ellipsoid, deg)
