"""Gauss–Krüger projection + INS/GPS EKF for a ground robot (paper 002).

Zhao Y., Nie X., Fang S., Wu H., "Research on inertial navigation/GPS robot
combined positioning based on Gaussian projection", *Machine Building &
Automation* 52(1): 173–176, 2023, doi:10.19344/j.cnki.issn1671-5276.2023.01.043.

The filter -- state ``X = [x north, y east, theta, v, omega]`` in the Gauss–Krüger grid, the
unicycle model of Eq. (13) (lost in the source and reconstructed, erratum E002-06), its Jacobian
Eq. (16), ``H = I5`` (erratum E002-07: the printed ``X_m`` is the measurement) -- is
:mod:`navlib.filters.planar_ekf`, and the projection :mod:`navlib.geodesy` (Krüger's n^6 series,
nm accuracy; it defaults to WGS84, so everything here passes the paper's datum, CGCS2000). This
companion holds what the paper adds: its noise values (Eqs. 17–18, :data:`Q_PAPER`, :data:`R_PAPER`; units
unstated in the paper, erratum E002-10), its pipeline :func:`ekf` (GPS latitude/longitude projected
in one zone held for the whole run, so a run crossing a zone boundary stays continuous; the IMU
heading turned from true to grid north by the convergence the paper omits, erratum E002-09;
``theta_IMU`` absolute and ``omega_IMU`` the vertical gyro rate, erratum E002-08), the robot's
square loop (:func:`waypoint_path`) and its simulated sensors (:func:`simulate_sensors`).
Faults are handled and reported as in :func:`navlib.filters.planar_ekf.filter_grid`. For the
paper's simulations (Figs. 4-5) the expected errors follow in closed form: of dead reckoning on
those sensors (:func:`dead_reckoning_error_ms`, a heading random walk) and of the EKF (:func:`ekf_error_ms`,
a linear covariance analysis of the printed Q and R), against which the Monte Carlo runs are checked.

The paper's own projection equations, kept to check them and to show its errata (default
ellipsoid ``earth.CGCS2000``, the paper's datum):

* Eq. (1)–(2) zone number: printed ``n = (L - 1.5)/3`` is not an integer
  (erratum E002-01); :func:`navlib.geodesy.zone` uses ``n = floor((L + 1.5)/3)``
  (0 ≤ L < 1.5° E is zone 120, central meridian 0°). :func:`printed_zone_number`
  returns the printed value for the errata demonstration.
* Eq. (3)–(6) eccentricities and radii (:func:`paper_radii`); Eq. (6) as
  printed, ``a^2 (1 - e1^2) / sqrt((1 + e2^2 sin^2 W)^(3/2))``, is wrong by
  seven orders of magnitude (erratum E002-02, :func:`printed_meridian_radius`).
* Eq. (7)–(8) meridian arc ``S`` to e^8 (:func:`paper_meridian_arc`; correct,
  erratum E002-05; ``order`` drops the later terms to show what a missing one would cost).
* Eq. (9)–(11) sixth-order series in l (:func:`paper_series`). As printed,
  the l^6 term of x has ``R_N/72`` and ``270 eta^4``; the correct values are
  ``R_N/720`` and ``270 eta^2`` (erratum E002-03), ``N`` means ``R_N``, and l, W are
  in radians (erratum E002-04). ``typos=True`` keeps the printed typos and
  ``printed_units=True`` substitutes l (and the linear W of Eq. 7) in degrees, only to show
  the error each causes. It is a projection ``(lat, lon, lon0, ellipsoid) -> (x, y)``,
  so :func:`navlib.geodesy.local_scales` takes it as ``project`` to check that it is conformal.

The paper writes L for longitude and W for latitude; the functions take ``lat``, ``lon`` in rad
unless ``deg=True`` and return metres.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Annotated

import numpy as np
from numpy.typing import NDArray

from .. import _geodesy, _planar, _robust, geodesy
from .._typing import Array, ArrayLike, Times
from .._validate import (
    Check,
    Count,
    Flag,
    Is,
    NonNegative,
    Positive,
    Real,
    Rng,
    as_array,
    axes,
    booleans,
    boundary,
    broadcast,
    choice,
    flag,
    lat_lon,
    latitude,
    longitude,
    scalar,
    zone_offset,
)
from ..earth import CGCS2000, Ellipsoid, EllipsoidArg
from ..filters.planar_ekf import EkfConfig, EkfResult, covariance, filter_grid
from ..geodesy import ZoneWidth

if TYPE_CHECKING:
    from matplotlib.axes import Axes

__all__ = [
    "Q_PAPER",
    "R_PAPER",
    "PAPER_CONFIG",
    "MAX_STEPS",
    "printed_zone_number",
    "paper_radii",
    "printed_meridian_radius",
    "paper_meridian_arc",
    "paper_series",
    "waypoint_path",
    "ekf",
    "simulate_sensors",
    "Sensors",
    "dead_reckoning_error_ms",
    "ekf_error_ms",
    "draw_zones",
    "draw_zone_grid",
    "draw_block_diagram",
]

Q_PAPER = np.diag([1.0, 1.0, 0.01, 0.0001, 0.0016])
"""Process noise per step, Eq. (17) (SI reading: m², m², rad², m²/s², rad²/s²)."""
R_PAPER = np.diag([6.25, 6.25, 0.01, 0.0004, 0.0025])
"""Measurement noise, Eq. (18): GPS 2.5 m, heading 0.1 rad, speed 0.02 m/s, yaw rate 0.05 rad/s (sigmas)."""


# --------------------------------------------------------------------------
# The paper's projection equations, Eqs. (1)-(11) (checks and errata demonstrations)
# --------------------------------------------------------------------------


def printed_zone_number(lon: ArrayLike, deg: bool = False) -> Array:
    """Eq. (1) exactly as printed, ``n = (L - 1.5)/3`` (L in deg): not an integer (erratum E002-01).

    Taken literally with Eq. (2), ``L0 = 3n = L - 1.5°``, so l = 1.5° for
    every point. Use :func:`navlib.geodesy.zone` instead.

    Examples
    --------
    >>> from navlib.papers import gauss_kruger_ekf as gk
    >>> float(gk.printed_zone_number(119.2, deg=True))               # not an integer: the zone is 40
    39.233333333333334
    """
    return (longitude(lon, "lon", deg) - 1.5) / 3.0


@boundary
def paper_radii(lat: ArrayLike, ellipsoid: EllipsoidArg = CGCS2000, deg: bool = False) -> tuple[float, float, Array, Array]:
    """Eqs. (3)–(6): first and second eccentricities and the radii R_N, R_M (m).

    ``e1 = sqrt(a^2 - b^2)/a``, ``e2 = sqrt(a^2 - b^2)/b``,
    ``R_N = (a^2/b)/sqrt(1 + e2^2 cos^2 W)`` and the corrected Eq. (6)
    ``R_M = a(1 - e1^2)/(1 - e1^2 sin^2 W)^(3/2)`` (erratum E002-02).
    The same radii in core: :func:`navlib.earth.radii` (returns ``R_M, R_N``).

    Returns
    -------
    e1, e2 : float
    R_N, R_M : ndarray, shape (...)

    Examples
    --------
    >>> from navlib.papers import gauss_kruger_ekf as gk
    >>> e1, e2, R_N, R_M = gk.paper_radii(26.0, deg=True)
    >>> round(float(e1), 9), round(float(R_N), 3), round(float(R_M), 3)
    (0.081819191, 6382243.553, 6347684.393)
    """
    W = latitude(lat, "lat", deg=deg, nonempty=True)
    return _paper_radii(W, ellipsoid)


def _paper_radii(W: float | Array, ellipsoid: Ellipsoid) -> tuple[float, float, Array, Array]:
    """:func:`paper_radii` of a checked latitude (rad)."""
    a, b = ellipsoid.a, ellipsoid.b
    e1 = np.sqrt(a * a - b * b) / a
    e2 = np.sqrt(a * a - b * b) / b
    R_N = (a * a / b) / np.sqrt(1 + e2**2 * np.cos(W) ** 2)
    R_M = a * (1 - e1**2) / (1 - e1**2 * np.sin(W) ** 2) ** 1.5
    return e1, e2, R_N, R_M


@boundary
def printed_meridian_radius(lat: ArrayLike, ellipsoid: EllipsoidArg = CGCS2000, deg: bool = False) -> Array:
    """Eq. (6) exactly as printed, ``a^2 (1 - e1^2)/sqrt((1 + e2^2 sin^2 W)^(3/2))`` (m): wrong (erratum E002-02).

    Examples
    --------
    >>> from navlib.papers import gauss_kruger_ekf as gk
    >>> round(float(gk.printed_meridian_radius(26.0, deg=True)), 1)   # the printed Eq. (6): not a radius in metres
    40369094087287.1
    >>> round(float(gk.paper_radii(26.0, deg=True)[3]), 1)            # the corrected one
    6347684.4
    """
    W = latitude(lat, "lat", deg=deg, nonempty=True)
    e1, e2, _, _ = _paper_radii(0.0, ellipsoid)
    return ellipsoid.a**2 * (1 - e1**2) / np.sqrt((1 + e2**2 * np.sin(W) ** 2) ** 1.5)


@boundary
def paper_meridian_arc(lat: ArrayLike, ellipsoid: EllipsoidArg = CGCS2000, deg: bool = False, order: int = 8) -> Array:
    r"""Eqs. (7)–(8): meridian arc length S from the equator (m), series to e^8 (correct, erratum E002-05).

    :math:`S = a(1-e^2)\big[A W - \tfrac{B}{2} \sin 2W + \tfrac{C}{4} \sin 4W - \tfrac{D}{6} \sin 6W + \tfrac{E}{8} \sin 8W\big]`:
    1e-8 m at 26°, 1e-4 m near the pole. Core's :func:`navlib.geodesy.meridian_arc`
    uses Krüger's n^6 series (nm accuracy).

    Parameters
    ----------
    lat : array_like, shape (...)
        Geodetic latitude (rad, or deg with ``deg=True``).
    order : {8, 6, 4, 2}
        Highest power of e1 kept in A-E: 8 as printed; a lower order drops the later
        terms, only to show what a missing term would cost (millimetres for e^8).

    Examples
    --------
    >>> from navlib.papers import gauss_kruger_ekf as gk
    >>> S = gk.paper_meridian_arc(26.0, deg=True)
    >>> round(float(S), 3)                                            # m, CGCS2000
    2876834.573
    """
    W = latitude(lat, "lat", deg=deg, nonempty=True)
    return _meridian_arc(W, W, ellipsoid, choice(order, "order", (8, 6, 4, 2)))


def _meridian_arc(W: float | Array, W_linear: float | Array, ellipsoid: Ellipsoid, order: int = 8) -> Array:
    """Eq. (7) with the latitude ``W_linear`` in its linear term ``A W`` (W itself unless E002-04's degrees are shown)."""
    e2 = ellipsoid.e2
    e4, e6, e8 = (e2**k if 2 * k <= order else 0.0 for k in (2, 3, 4))
    A = 1 + 3 / 4 * e2 + 45 / 64 * e4 + 175 / 256 * e6 + 11025 / 16384 * e8
    B = 3 / 4 * e2 + 15 / 16 * e4 + 525 / 512 * e6 + 2205 / 2048 * e8
    C = 15 / 64 * e4 + 105 / 256 * e6 + 2205 / 4096 * e8
    D = 35 / 512 * e6 + 315 / 2048 * e8
    E = 315 / 16384 * e8
    return (
        ellipsoid.a
        * (1 - e2)
        * (A * W_linear - B / 2 * np.sin(2 * W) + C / 4 * np.sin(4 * W) - D / 6 * np.sin(6 * W) + E / 8 * np.sin(8 * W))
    )


@boundary
def paper_series(
    lat: ArrayLike,
    lon: ArrayLike,
    lon0: ArrayLike,
    ellipsoid: EllipsoidArg = CGCS2000,
    deg: bool = False,
    typos: Flag = False,
    printed_units: Flag = False,
) -> tuple[Array, Array]:
    r"""The paper's sixth-order GK series, Eqs. (7)–(11): northing x and easting y (m).

    With :math:`t = \tan W`, :math:`\eta^2 = e_2^2 \cos^2 W` and :math:`N = R_N`:

    .. math::

        x &= S + \frac{N}{2} l^2 \sin W \cos W + \frac{N}{24} l^4 \sin W \cos^3 W\, (5 - t^2 + 9\eta^2 + 4\eta^4) \\
          &\quad + \frac{N}{720} l^6 \sin W \cos^5 W\, (61 - 58 t^2 + t^4 + 270\eta^2 - 330\eta^2 t^2) \\
        y &= N l \cos W + \frac{N}{6} l^3 \cos^3 W\, (1 - t^2 + \eta^2) \\
          &\quad + \frac{N}{120} l^5 \cos^5 W\, (5 - 18 t^2 + t^4 + 14\eta^2 - 58\eta^2 t^2)

    ``typos=True`` uses the printed ``N/72`` and ``270 eta^4`` (erratum E002-03) to
    show their effect; l and W in radians (erratum E002-04). ``printed_units=True`` shows
    that erratum's failure instead: l of Eq. (10) and the linear W of Eq. (7) enter in the
    degrees of Eqs. (1)-(2), as the paper leaves them (the sines and cosines still take the
    angle), so the l^k terms are (180/pi)^k too large. The production projection
    is :func:`navlib.geodesy.geodetic2gk`.

    Parameters
    ----------
    lat, lon, lon0 : array_like, broadcasting to shape (...)
        rad, or deg with ``deg=True``; ``|lon - lon0|`` at most 6°.

    Examples
    --------
    >>> from navlib.papers import gauss_kruger_ekf as gk
    >>> x, y = gk.paper_series(26.06, 119.20, 120.0, deg=True)
    >>> round(float(x), 3), round(float(y), 3)                        # northing, easting (m) from the central meridian
    (2883727.417, -80055.05)
    """
    W, lon_deg = lat_lon(lat, lon, deg)
    L0 = longitude(lon0, "lon0", deg)
    l_deg = lon_deg - L0
    if np.any(np.abs(l_deg) > 6.0):
        raise ValueError(f"lon: expected |lon - lon0| <= 6°, got {np.abs(l_deg).max():.4g}°")
    l = l_deg if printed_units else np.deg2rad(l_deg)
    _, e2, N, _ = _paper_radii(W, ellipsoid)
    t2 = np.tan(W) ** 2
    eta2 = e2**2 * np.cos(W) ** 2
    s, c = np.sin(W), np.cos(W)
    sixth = (
        (N / 72 if typos else N / 720)
        * l**6
        * s
        * c**5
        * (61 - 58 * t2 + t2**2 + 270 * (eta2**2 if typos else eta2) - 330 * eta2 * t2)
    )
    x = (
        _meridian_arc(W, np.rad2deg(W) if printed_units else W, ellipsoid)
        + N / 2 * l**2 * s * c
        + N / 24 * l**4 * s * c**3 * (5 - t2 + 9 * eta2 + 4 * eta2**2)
        + sixth
    )
    y = (
        N * l * c
        + N / 6 * l**3 * c**3 * (1 - t2 + eta2)
        + N / 120 * l**5 * c**5 * (5 - 18 * t2 + t2**2 + 14 * eta2 - 58 * eta2 * t2)
    )
    return x, y


# --------------------------------------------------------------------------
# The robot's square loop
# --------------------------------------------------------------------------

MAX_STEPS = 1e8
"""Most steps :func:`waypoint_path` builds (about 4 GB of states)."""


@boundary
def waypoint_path(waypoints: ArrayLike, speed: Positive, turn_rate: Positive, T: Positive) -> tuple[Array, NDArray[np.int_]]:
    """Drive straight between waypoints and turn on the spot at each (a robot square loop).

    Each leg and each turn gets a whole number of steps, with the speed or
    turn rate adjusted (down) so that every waypoint is reached exactly.

    Parameters
    ----------
    waypoints : array_like, shape (M, 2)
        Grid positions ``[x north, y east]`` (m), M >= 2, consecutive points distinct.
    speed : float
        Nominal forward speed (m/s).
    turn_rate : float
        Nominal magnitude of the yaw rate while turning (rad/s).
    T : float
        Step (s).

    Returns
    -------
    X : ndarray, shape (N, 5)
        True states; the first heading points along the first leg.
    at_waypoint : ndarray of int, shape (M,)
        Index into ``X`` where each waypoint is reached (at the end of its turn).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.papers import gauss_kruger_ekf as gk
    >>> X, at = gk.waypoint_path([[0.0, 0.0], [10.0, 0.0], [10.0, 10.0]], speed=1.0, turn_rate=np.pi / 4, T=0.5)
    >>> X.shape, at, np.round(X[at, :2], 6)
    ((45, 5), array([ 0, 24, 44]), array([[ 0.,  0.],
           [10.,  0.],
           [10., 10.]]))
    """
    wp = as_array(waypoints, "waypoints", shape=(None, 2))
    if len(wp) < 2:
        raise ValueError(f"waypoints: expected at least 2 waypoints, got {len(wp)}")
    legs = np.diff(wp, axis=0)
    length = np.hypot(legs[:, 0], legs[:, 1])
    if np.any(length <= 0):
        raise ValueError("waypoints: consecutive waypoints must differ")
    course = np.arctan2(legs[:, 1], legs[:, 0])
    steps = (length.sum() / speed + np.abs(np.angle(np.exp(1j * np.diff(course)))).sum() / turn_rate) / T
    if steps > MAX_STEPS:
        raise ValueError(f"T: a step of {T:g} s needs about {steps:.3g} steps for this path, more than {MAX_STEPS:g}")
    v_cmd, w_cmd, reached = [], [], []
    for i, (L, c) in enumerate(zip(length, course, strict=True)):
        if i > 0:
            turn = np.angle(np.exp(1j * (c - course[i - 1])))
            n_turn = max(1, int(np.ceil(abs(turn) / (turn_rate * T))))
            v_cmd += [0.0] * n_turn
            w_cmd += [turn / (n_turn * T)] * n_turn
        reached.append(len(v_cmd))
        n_leg = max(1, int(np.ceil(L / (speed * T))))
        v_cmd += [L / (n_leg * T)] * n_leg
        w_cmd += [0.0] * n_leg
    reached.append(len(v_cmd))
    x0 = np.array([wp[0, 0], wp[0, 1], course[0], 0.0, 0.0])
    X = _planar.propagate(x0, T, np.array(v_cmd + [0.0]), np.array(w_cmd + [0.0]))[:-1]
    return X, np.array(reached)


# --------------------------------------------------------------------------
# The paper's pipeline: GPS lat/lon -> Gauss–Krüger -> EKF
# --------------------------------------------------------------------------


def _forward_fill(values: Array) -> Array:
    """Replace NaN by the last finite value (the first finite one before it)."""
    if not np.isfinite(values).any():
        return values
    return _robust.hold(values, "first", "values", axis=-1)[0]


PAPER_CONFIG = EkfConfig(Q_PAPER, R_PAPER)
"""The paper's noise, Eqs. (17)-(18), with navlib's default fault handling: the default of :func:`ekf`."""


@boundary
def ekf(
    t: Times,
    sensors: Is[Sensors],
    x0: ArrayLike,
    *,
    origin: ArrayLike | None = None,
    zone: Count | None = None,
    width: ZoneWidth = 3,
    ellipsoid: EllipsoidArg = CGCS2000,
    config: EkfConfig = PAPER_CONFIG,
    correct_convergence: bool = True,
    deg: Flag = False,
) -> EkfResult:
    """The paper's pipeline: GPS lat/lon -> Gauss–Krüger -> EKF with IMU heading, speed, yaw rate.

    Faults are handled as in :func:`navlib.filters.planar_ekf.filter_grid` (NaN: skip the component;
    ``config.gate``: leave out a channel whose innovation fails its NIS test, e.g. a
    50 m GPS jump or an IMU spike; ``config.limits``: censor samples at the
    gyro rails, integrate nothing over a clock jump, skip a stuck yaw rate) and
    reported in the result's ``faults``. Timestamps must be strictly
    increasing: for logs with repeated or out-of-order samples the documented
    pipeline is ``t, gps, heading, speed, yaw_rate, _ = navlib.timing.sanitize(t, gps, heading, speed, yaw_rate)``
    then ``ekf(t, Sensors(gps, heading, speed, yaw_rate), ...)``; unsanitised times raise ``ValueError``.

    Parameters
    ----------
    t : array_like, shape (N,)
        Strictly increasing times (s), one per sample of ``sensors``.
    sensors : Sensors
        The measurements (:class:`Sensors`: GPS fixes, IMU heading from true north, speed, yaw rate; NaN:
        missing; N samples each, as many as ``gps`` has rows), angles in rad, or in deg (deg/s) with ``deg=True``.
    x0 : array_like, shape (5,)
        Initial state in the grid relative to ``origin`` (heading in rad).
    origin : array_like, shape (2,), optional
        ``[lat, lon]`` of the local grid origin; default none (absolute GK coordinates).
    zone : int, optional
        Zone to hold for the whole run; default the zone of ``origin`` or of the first fix.
    width, ellipsoid
        As in :func:`navlib.geodesy.geodetic2gk`, but ``ellipsoid`` defaults to
        ``earth.CGCS2000``, the paper's datum.
    config : EkfConfig
        Noise, gates and the yaw-rate gyro's limits (SI units, whatever ``deg`` says); default
        :data:`PAPER_CONFIG` (Q and R of Eqs. 17–18).
    correct_convergence : bool
        Subtract the grid convergence at the latest fix from the heading (True);
        False fuses the true-north heading with grid coordinates as the paper does.
    deg : bool
        The sensors' angles and ``origin`` in degrees (rates in deg/s).

    Returns
    -------
    EkfResult

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.filters import planar_ekf
    >>> from navlib.papers import gauss_kruger_ekf as gk
    >>> truth = planar_ekf.propagate([0.0, 0.0, np.pi / 4, 1.0, 0.0], 0.5, 20)
    >>> rng = np.random.default_rng(0)
    >>> s = gk.simulate_sensors(truth, np.deg2rad([26.06, 119.20]), gk.R_PAPER, rng)
    >>> res = gk.ekf(0.5 * np.arange(21), s, truth[0], origin=np.deg2rad([26.06, 119.20]))
    >>> rms = lambda e: round(float(np.sqrt(np.mean(np.sum(e**2, -1)))), 2)
    >>> rms(res.x[:, :2] - truth[:, :2]), rms(res.z[:, :2] - truth[:, :2])   # filtered vs raw GPS (m)
    (1.07, 2.89)
    """
    gps = as_array(sensors.gps, "gps", allow_nan=True, shape=(None, 2))  # t: checked by filter_grid
    n = gps.shape[0]
    imu = []
    for name in ("heading", "speed", "yaw_rate"):
        arr = as_array(getattr(sensors, name), name, allow_nan=True, shape=(n,), of="gps")
        imu.append(np.deg2rad(arr) if deg and name != "speed" else arr)
    heading, speed, yaw_rate = imu
    fix = np.all(np.isfinite(gps), axis=1)
    if fix.any():
        lat, lon = lat_lon(gps[fix, 0], gps[fix, 1], deg)  # rad, deg
    if origin is not None:
        lat0, lon0 = as_array(origin, "origin", shape=(2,))
        lat0, lon0 = lat_lon(lat0, lon0, deg)
    elif fix.any():
        lat0, lon0 = lat[0], lon[0]
    else:
        raise ValueError("gps: no valid fix and no origin given; cannot choose a zone")
    zone = int(_geodesy.zone(lon0, width)) if zone is None else _zone_number(zone, width)
    L0 = _geodesy.meridian(np.asarray(zone, dtype=float), width)
    origin_gk = np.array(_grid(lat0, lon0, L0, width, ellipsoid)[:2]) if origin is not None else np.zeros(2)
    z = np.full((n, 5), np.nan)
    gamma = np.full(n, np.nan)
    if fix.any():
        north, east, gamma[fix] = _grid(lat, lon, L0, width, ellipsoid)
        z[fix, 0], z[fix, 1] = north - origin_gk[0], east - origin_gk[1]
    else:
        gamma[:] = _grid(lat0, lon0, L0, width, ellipsoid)[2]
    z[:, 2] = heading - _forward_fill(gamma) if flag(correct_convergence, "correct_convergence") else heading
    z[:, 3], z[:, 4] = speed, yaw_rate
    res = filter_grid(t, z, x0, config)
    res.zone, res.origin_gk = zone, origin_gk
    return res


def _zone_number(zone: int, width: int) -> int:
    """``zone`` (an integer >= 1, checked) within the 360/width zones of its width."""
    if zone > 360 // width:
        raise ValueError(f"zone: expected a {width}° zone number 1-{360 // width}, got {zone!r}")
    return zone


def _grid(lat: Array, lon_deg: Array, L0: Array, width: int, ellipsoid: Ellipsoid) -> tuple[Array, Array, Array]:
    """Gauss–Krüger northing, easting (m) and grid convergence (rad) of checked points (lat in rad, lon in deg)
    in the zone of central meridian ``L0`` (deg): :func:`navlib.geodesy.geodetic2gk` and
    :func:`navlib.geodesy.convergence` of their core, with the same longitude limit (the zone width)."""
    l_deg = zone_offset(lon_deg - L0, float(width), width)
    north, east = _geodesy.forward(lat, l_deg, ellipsoid, 1.0, 0.0, 0.0)
    return north, east, _geodesy.factors(lat, l_deg, ellipsoid)[0]


# --------------------------------------------------------------------------
# Simulated sensors for the paper's scenarios
# --------------------------------------------------------------------------


@dataclass
class Sensors:
    """The robot's measurements, as :func:`ekf` takes them and :func:`simulate_sensors` makes them.

    gps : (N, 2) ``[lat, lon]`` (rad), NaN rows during outages;
    heading : (N,) IMU heading clockwise from true north (rad, [0, 2 pi));
    speed : (N,) (m/s); yaw_rate : (N,) (rad/s, clockwise positive).
    NaN marks a missing sample; :func:`ekf` reads the angles in degrees with ``deg=True``.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.papers import gauss_kruger_ekf as gk
    >>> nan = np.nan
    >>> gps = np.array([[0.455, 2.080], [nan, nan]])                # [lat, lon] (rad); the second fix is an outage
    >>> s = gk.Sensors(gps=gps, heading=np.array([0.5, 0.5]), speed=np.ones(2), yaw_rate=np.zeros(2))
    >>> s.gps.shape, int(np.isnan(s.gps[:, 0]).sum())
    ((2, 2), 1)
    """

    gps: np.ndarray
    heading: np.ndarray
    speed: np.ndarray
    yaw_rate: np.ndarray


@boundary
def simulate_sensors(
    truth: ArrayLike,
    origin: ArrayLike,
    R: ArrayLike,
    rng: Rng,
    *,
    zone: Count | None = None,
    width: ZoneWidth = 3,
    ellipsoid: EllipsoidArg = CGCS2000,
    yaw_rate_bias: Real = 0.0,
    gps_valid: ArrayLike | None = None,
) -> Sensors:
    """GPS, IMU heading, speed and yaw rate from true grid states: truth + N(0, R).

    The GPS noise (sigmas ``sqrt(R[0,0])``, ``sqrt(R[1,1])`` in m) is added in
    the grid before the inverse projection (the scale factor, 1 + 8e-5 at
    80 km, changes it by < 0.01 %); the heading is turned from grid to true
    north with the convergence at the true position.

    Parameters
    ----------
    truth : array_like, shape (N, 5)
        True states in the grid relative to ``origin``.
    origin : array_like, shape (2,)
        ``[lat, lon]`` (rad) of the grid origin.
    R : array_like, shape (5, 5) or (5,)
        Measurement noise covariance (only its diagonal is used).
    rng : numpy.random.Generator
    zone : int, optional
        Zone of the grid; default the zone of ``origin``.
    width, ellipsoid
        As in :func:`ekf` (default ``earth.CGCS2000``).
    yaw_rate_bias : float
        Constant gyro bias added to the yaw rate (rad/s).
    gps_valid : array_like of bool, shape (N,), optional
        False where GPS is out (NaN fixes).

    Returns
    -------
    Sensors

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.filters import planar_ekf
    >>> from navlib.papers import gauss_kruger_ekf as gk
    >>> truth = planar_ekf.propagate([0.0, 0.0, np.pi / 4, 1.0, 0.0], 0.5, 4)   # north-east at 1 m/s
    >>> origin = np.deg2rad([26.06, 119.20])
    >>> s = gk.simulate_sensors(truth, origin, np.zeros(5), np.random.default_rng(0))   # noise-free (R = 0)
    >>> np.round(np.rad2deg(s.gps[-1]) - [26.06, 119.20], 6), np.round(s.speed, 6)   # 2 m north-east of the origin
    (array([1.3e-05, 1.4e-05]), array([1., 1., 1., 1., 1.]))
    """
    truth = as_array(truth, "truth", shape=(None, 5), min_ndim=1)
    origin = as_array(origin, "origin", shape=(2,))
    sigma = np.sqrt(np.diag(covariance(R, "R")))
    lat0, lon0 = lat_lon(origin[0], origin[1])  # rad, deg
    zone = int(_geodesy.zone(lon0, width)) if zone is None else _zone_number(zone, width)
    L0 = _geodesy.meridian(np.asarray(zone, dtype=float), width)
    o_north, o_east, _ = _grid(lat0, lon0, L0, width, ellipsoid)
    noise = sigma * rng.standard_normal(truth.shape)
    gps = np.stack(_geodetic(o_north + truth[:, 0] + noise[:, 0], o_east + truth[:, 1] + noise[:, 1], L0, ellipsoid), -1)
    if gps_valid is not None:
        gps[~booleans(gps_valid, "gps_valid", shape=(len(truth),))] = np.nan
    true_lat, true_lon = _geodetic(o_north + truth[:, 0], o_east + truth[:, 1], L0, ellipsoid)
    gamma = _grid(true_lat, np.rad2deg(true_lon), L0, width, ellipsoid)[2]
    heading = np.mod(truth[:, 2] + gamma + noise[:, 2], 2 * np.pi)
    return Sensors(gps, heading, truth[:, 3] + noise[:, 3], truth[:, 4] + noise[:, 4] + yaw_rate_bias)


def _geodetic(north: Array, east: Array, L0: Array, ellipsoid: Ellipsoid) -> tuple[Array, Array]:
    """Latitude and longitude (rad) of grid points (m) about the central meridian ``L0`` (deg):
    :func:`navlib.geodesy.gk2geodetic` of its core, with the same easting limit."""
    xi, eta = _geodesy.normalised(north, east, ellipsoid)
    if np.any(np.abs(eta) > _geodesy.MAX_ETA):
        raise ValueError("truth: positions too far east or west of the central meridian for the Gauss–Krüger series")
    lat, lon_deg = _geodesy.geodetic(xi, eta, L0, ellipsoid)
    return lat, np.deg2rad(lon_deg)


# --------------------------------------------------------------------------
# Expected errors of the paper's simulations (Figs. 4-5), in closed form
# --------------------------------------------------------------------------


def _sensor_sigmas(R: ArrayLike, name: str = "R") -> np.ndarray:
    return np.sqrt(np.diag(covariance(R, name)))


@boundary
def dead_reckoning_error_ms(truth: ArrayLike, T: Positive, R: ArrayLike, yaw_rate_bias: Real = 0.0) -> Array:
    """Expected squared position error (m²) of dead reckoning on :func:`simulate_sensors`' speed and yaw rate.

    :func:`navlib.filters.planar_ekf.dead_reckoning` integrates the measured speed
    ``v_j + eps_j`` and yaw rate ``w_j + n_j + b`` from the true initial state, with white
    noise of sigmas ``sqrt(R[3, 3])`` and ``sqrt(R[4, 4])`` and a constant ``yaw_rate_bias`` b.
    Its heading error after j steps, ``phi_j = T sum_{m<j} (n_m + b)``, is a Gaussian random
    walk, so with ``a_j = v_j exp(i theta_j)`` (true speed and heading, grid as x + i y),
    ``q = exp(i b T - (sigma_w T)^2 / 2)`` and ``u_j = E exp(i phi_j) = q^j`` the error after K
    steps has, exactly for this discrete model (no small-angle approximation),

        E|e_K|^2 = T^2 [ sum_{j,k<K} a_j conj(a_k) E exp(i(phi_j - phi_k))
                         - |sum a_j u_j|^2 + |sum a_j (1 - u_j)|^2 + K sigma_v^2 ]

    with ``E exp(i(phi_j - phi_k)) = q^(j-k)`` for j >= k: its variance plus the square of its
    mean (the bias and the shrinking mean of a wandering heading). Computed in O(N).

    Parameters
    ----------
    truth : array_like, shape (N, 5)
        True states ``[x north, y east, theta, v, omega]`` (a noise-free path, e.g. from
        :func:`navlib.filters.planar_ekf.propagate`), N >= 2.
    T : float
        Step (s).
    R : array_like, shape (5, 5) or (5,)
        Sensor noise covariance as in :func:`simulate_sensors` (only the speed and yaw-rate
        variances are used).
    yaw_rate_bias : float
        Constant gyro bias (rad/s).

    Returns
    -------
    ms : ndarray, shape (N,)
        ``E|dr_k - truth_k|^2`` (m²) for every step; 0 at the start.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.filters import planar_ekf
    >>> from navlib.papers import gauss_kruger_ekf as gk
    >>> truth = planar_ekf.propagate([0.0, 0.0, 0.0, 1.0, 0.0], 0.5, 4)
    >>> np.round(gk.dead_reckoning_error_ms(truth, 0.5, gk.R_PAPER), 4)   # grows along the track (m^2)
    array([0.    , 0.0001, 0.0004, 0.0011, 0.0026])
    """
    truth = as_array(truth, "truth", shape=(None, 5))
    if len(truth) < 2:
        raise ValueError(f"truth: expected at least 2 states, got {len(truth)}")
    sigma = _sensor_sigmas(R)
    K = len(truth) - 1
    a = truth[:K, 3] * np.exp(1j * truth[:K, 2])
    q = np.exp(1j * yaw_rate_bias * T - (sigma[4] * T) ** 2 / 2)
    u = q ** np.arange(K)
    h = np.zeros(K, complex)  # h_j = sum_{k<j} conj(a_k) q^(j-k)
    for j in range(1, K):
        h[j] = q * (h[j - 1] + np.conj(a[j - 1]))
    both = np.cumsum(np.abs(a) ** 2 + 2 * np.real(a * h))  # sum over j, k < K of a_j conj(a_k) q^(j-k)
    A, Au = np.cumsum(a), np.cumsum(a * u)
    ms = T**2 * (both - np.abs(Au) ** 2 + np.abs(A - Au) ** 2 + np.arange(1, K + 1) * sigma[3] ** 2)
    return np.r_[0.0, np.maximum(ms, 0.0)]


@boundary
def ekf_error_ms(
    truth: ArrayLike,
    T: float,  # checked by planar_ekf.jacobian, its only use
    Q: ArrayLike = Q_PAPER,
    R: ArrayLike = R_PAPER,
    P0: ArrayLike | None = None,
    yaw_rate_bias: Real = 0.0,
) -> Array:
    """Expected squared position error (m²) of :func:`ekf` on :func:`simulate_sensors`: a linear covariance analysis.

    Along the true states the filter's own recursion (Eq. 16's Phi at the truth, ``P = Phi P Phi^T + Q``,
    H = I5, ``K = P (P + R)^-1``) gives its gains; the actual error, on a noise-free path seen
    through truth + N(0, R) sensors whose yaw rate carries ``yaw_rate_bias``, then obeys to first order
    ``e- = Phi e+`` and ``e+ = (I - K) e- + K v``, so its covariance and mean follow
    ``S- = Phi S+ Phi^T``, ``S+ = (I - K) S- (I - K)^T + K R K^T`` and ``m+ = (I - K) Phi m+ + K [0, 0, 0, 0, b]``.
    The start is known exactly (S = 0, m = 0) and the filter's P starts at ``P0``.

    Parameters
    ----------
    truth : array_like, shape (N, 5)
        True states, N >= 2.
    T : float
        Step (s).
    Q, R : array_like, shape (5, 5) or (5,)
        The filter's process noise per step and the sensors' (and filter's) measurement noise.
    P0 : array_like, shape (5, 5) or (5,), optional
        Initial covariance of the filter; default zeros (the paper's P(0) = 0).
    yaw_rate_bias : float
        Constant gyro bias of the sensors (rad/s).

    Returns
    -------
    ms : ndarray, shape (N,)
        ``E|x_k - truth_k|^2`` of the position (m²) at every epoch; 0 at the start.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.filters import planar_ekf
    >>> from navlib.papers import gauss_kruger_ekf as gk
    >>> truth = planar_ekf.propagate([0.0, 0.0, 0.0, 1.0, 0.0], 0.5, 4)
    >>> np.round(gk.ekf_error_ms(truth, 0.5), 3)                       # the paper's Q and R (m^2)
    array([0.   , 0.238, 0.8  , 1.398, 1.844])
    """
    from ..filters.planar_ekf import jacobian

    truth = as_array(truth, "truth", shape=(None, 5))
    if len(truth) < 2:
        raise ValueError(f"truth: expected at least 2 states, got {len(truth)}")
    Q, R = covariance(Q, "Q"), covariance(R, "R")
    P = np.zeros((5, 5)) if P0 is None else covariance(P0, "P0").copy()
    b = np.array([0.0, 0.0, 0.0, 0.0, yaw_rate_bias])
    S, m = np.zeros((5, 5)), np.zeros(5)
    ms = np.zeros(len(truth))
    eye = np.eye(5)
    for k, Phi in enumerate(jacobian(truth[:-1], T), start=1):
        P = Phi @ P @ Phi.T + Q
        gain = np.linalg.solve((P + R).T, P.T).T  # P (P + R)^-1
        A = eye - gain
        P = A @ P @ A.T + gain @ R @ gain.T
        S = A @ (Phi @ S @ Phi.T) @ A.T + gain @ R @ gain.T
        m = A @ (Phi @ m) + gain @ b
        ms[k] = S[0, 0] + S[1, 1] + m[0] ** 2 + m[1] ** 2
    return ms


# --------------------------------------------------------------------------
# The chapter's inverse series and schematics (notebook 03). Kept out of __all__: they serve the
# notebook (the textbook inverse it displays, the redrawn Figs. 1-2), not a reader's own data;
# the production inverse is navlib.geodesy.gk2geodetic.
# --------------------------------------------------------------------------


@boundary
def footpoint_latitude(x: ArrayLike, ellipsoid: EllipsoidArg = CGCS2000, iterations: int = 8) -> Array:
    """Latitude W_f (rad) whose meridian arc S(W_f) of Eq. (7) equals the northing ``x`` (m): Newton on dS/dW = R_M."""
    x = as_array(x, "x", nonempty=True)
    n = int(scalar(iterations, "iterations", positive=True))
    if np.any(np.abs(x) > _meridian_arc(np.pi / 2, np.pi / 2, ellipsoid)):
        raise ValueError("x: expected a northing within the meridian quadrant")
    W = x / ellipsoid.a
    for _ in range(n):
        W = np.clip(W + (x - _meridian_arc(W, W, ellipsoid)) / _paper_radii(W, ellipsoid)[3], -np.pi / 2, np.pi / 2)
    return W


@boundary
def inverse_series(
    x: ArrayLike, y: ArrayLike, lon0: ArrayLike, ellipsoid: EllipsoidArg = CGCS2000, deg: bool = False
) -> tuple[Array, Array]:
    """The textbook sixth-order inverse of Eq. (9): latitude and longitude from GK x (north), y (east).

    At the footpoint latitude ``W_f`` (:func:`footpoint_latitude`) with ``t = tan W_f``,
    ``eta^2 = e2^2 cos^2 W_f``, ``N = R_N(W_f)``, ``M = R_M(W_f)``::

        W = W_f - t/(2MN) y^2 + t/(24MN^3)(5 + 3t^2 + eta^2 - 9 eta^2 t^2) y^4 - t/(720MN^5)(61 + 90t^2 + 45t^4) y^6
        l = y/(N cos W_f) - (1 + 2t^2 + eta^2) y^3/(6N^3 cos W_f) + (5 + 28t^2 + 24t^4 + 6eta^2 + 8eta^2 t^2) y^5/(120N^5 cos W_f)

    The paper prints only the forward series; this is its standard inverse, shown in the chapter and
    compared there with :func:`navlib.geodesy.gk2geodetic` (Krüger's series, nm accuracy).

    Parameters
    ----------
    x, y : array_like, broadcasting to shape (...)
        Northing and easting from the central meridian (m), ``|y|`` at most 1000 km.
    lon0 : array_like
        Central meridian (rad, or deg with ``deg=True``).

    Returns
    -------
    lat, lon : ndarray, shape (...)
        rad, or deg with ``deg=True``.
    """
    x, y = broadcast(as_array(x, "x", nonempty=True), as_array(y, "y", nonempty=True), name="x, y")
    if np.any(np.abs(y) > 1e6):
        raise ValueError(f"y: expected an easting within 1000 km of the central meridian, got {np.abs(y).max():.4g} m")
    L0 = np.deg2rad(longitude(lon0, "lon0", deg))
    try:
        np.broadcast_shapes(x.shape, L0.shape)
    except ValueError:
        raise ValueError(f"lon0: expected a shape that broadcasts with x, y {x.shape}, got {L0.shape}") from None
    Wf = footpoint_latitude(x, ellipsoid)
    _, e2, N, M = _paper_radii(Wf, ellipsoid)
    t, c = np.tan(Wf), np.cos(Wf)
    t2, eta2 = t * t, e2**2 * c * c
    lat = (
        Wf
        - t / (2 * M * N) * y**2
        + t / (24 * M * N**3) * (5 + 3 * t2 + eta2 - 9 * eta2 * t2) * y**4
        - t / (720 * M * N**5) * (61 + 90 * t2 + 45 * t2**2) * y**6
    )
    lon = L0 + (
        y / (N * c)
        - (1 + 2 * t2 + eta2) * y**3 / (6 * N**3 * c)
        + (5 + 28 * t2 + 24 * t2**2 + 6 * eta2 + 8 * eta2 * t2) * y**5 / (120 * N**5 * c)
    )
    return (np.rad2deg(lat), np.rad2deg(lon)) if flag(deg, "deg") else (lat, lon)


@boundary
def draw_zones(
    ax: Axes, lon_min: NonNegative = 112.5, lon_max: Positive = 127.5, *, mark: tuple[float, float] | None = None
) -> None:
    """3° Gauss–Krüger zones on a longitude axis: boundaries at 3n ± 1.5°, central meridians L0 = 3n, zone numbers.

    Parameters
    ----------
    ax : matplotlib Axes
    lon_min, lon_max : float
        Longitude range (° E), 0 <= lon_min < lon_max <= 180, at most 30° wide.
    mark : (lat, lon) in degrees, optional
        A site drawn as a star with its zone.

    Examples
    --------
    >>> import matplotlib.pyplot as plt
    >>> from navlib.papers import gauss_kruger_ekf as gk
    >>> fig, ax = plt.subplots()
    >>> gk.draw_zones(ax, mark=(26.06, 119.20))
    >>> len(ax.texts) > 0
    True
    >>> plt.close(fig)
    """
    axes(ax)
    if not lon_min < lon_max <= 180 or lon_max - lon_min > 30:
        raise ValueError(
            f"lon_min, lon_max: expected 0 <= lon_min < lon_max <= 180 and at most 30° apart, got {lon_min}, {lon_max}"
        )
    first, last = int(np.ceil((lon_min + 1.5) / 3)), int(np.floor((lon_max - 1.5) / 3))
    for n in range(first, last + 1):
        ax.axvspan(3 * n - 1.5, 3 * n + 1.5, color="0.93" if n % 2 else "0.85", lw=0)
        ax.axvline(3 * n, color="tab:green", lw=1.4)
        ax.text(3 * n, 0.93, f"zone {n}", transform=ax.get_xaxis_transform(), ha="center", fontsize=8)
        ax.text(
            3 * n + 0.1,
            0.05,
            f"$L_0$ = {3 * n}°",
            transform=ax.get_xaxis_transform(),
            fontsize=7,
            color="tab:green",
            rotation=90,
            va="bottom",
        )
    if mark is not None:
        lat, lon = as_array(mark, "mark", shape=(2,))
        ax.plot(lon, lat, "*", color="k", ms=12)
        ax.annotate(
            f"site, zone {int(geodesy.zone(lon, deg=True))}", (lon, lat), xytext=(6, 6), textcoords="offset points", fontsize=8
        )
    ax.set(xlim=(lon_min, lon_max), xlabel="longitude L (° E)", ylabel="latitude W (° N)")


@boundary
def draw_zone_grid(
    ax: Axes,
    zone: Count,
    lat_max: Annotated[float, Check("scalar", within=(10.0, 80.0), open_ends=(True, False))] = 60.0,
    *,
    step_deg: Positive = 0.5,
    mark: tuple[float, float] | None = None,
    ellipsoid: EllipsoidArg = CGCS2000,
) -> None:
    """One 3° zone drawn in its Gauss–Krüger plane: meridians every ``step_deg`` and parallels every 10°.

    The central meridian maps to the straight x axis (north) and the equator to the y axis (east);
    the other meridians bend toward it as latitude grows (the grid convergence γ), and the whole
    zone spans ±1.5° of longitude. Eastings in km on the horizontal axis, northings on the vertical.

    Parameters
    ----------
    ax : matplotlib Axes
    zone : int
        3° zone number, 1-120.
    lat_max : float
        Northern limit (°), in (10, 80].
    step_deg : float
        Meridian spacing (°), dividing 1.5.
    mark : (lat, lon) in degrees, optional

    Examples
    --------
    >>> import matplotlib.pyplot as plt
    >>> from navlib.papers import gauss_kruger_ekf as gk
    >>> fig, ax = plt.subplots()
    >>> gk.draw_zone_grid(ax, zone=40, mark=(26.06, 119.20))
    >>> len(ax.lines) > 0
    True
    >>> plt.close(fig)
    """
    axes(ax)
    L0 = float(_geodesy.meridian(np.asarray(_zone_number(zone, 3), dtype=float), 3))

    def grid_km(lat: Array, l_deg: Array) -> tuple[Array, Array]:
        """Northing, easting (km) of latitudes (rad) at longitude offsets ``l_deg`` (deg) from L0."""
        x, y = _geodesy.forward(lat, l_deg, ellipsoid, 1.0, 0.0, 0.0)
        return x / 1e3, y / 1e3

    lats = np.linspace(0.0, lat_max, 121)
    for k, dl in enumerate(np.arange(-1.5, 1.5 + step_deg / 2, step_deg)):
        x, y = grid_km(np.deg2rad(lats), np.full_like(lats, L0 + dl) - L0)
        ax.plot(y, x, color="tab:green" if abs(dl) < 1e-9 else "0.5", lw=1.6 if abs(dl) < 1e-9 else 0.8)
        if k % 2 == 0:
            ax.text(y[0], -250, f"{L0 + dl:g}°", ha="center", va="top", fontsize=7)
    for lat in np.arange(0.0, lat_max + 1e-9, 10.0):
        lons = np.linspace(L0 - 1.5, L0 + 1.5, 31)
        x, y = grid_km(np.deg2rad(np.full_like(lons, lat)), lons - L0)
        ax.plot(y, x, color="0.7", lw=0.8)
        ax.text(y[-1] + 8, x[-1], f"{lat:g}° N", fontsize=7, va="center")
    if mark is not None:
        lat, lon = as_array(mark, "mark", shape=(2,))
        lat, lon = lat_lon(lat, lon, True)
        x, y = grid_km(lat, zone_offset(lon - L0, 3.0, 3))
        ax.plot(y, x, "*", color="k", ms=12)
    top_km = grid_km(np.deg2rad(np.asarray(lat_max)), np.zeros(()))[0]
    ax.annotate(
        f"central meridian $L_0$ = {L0:g}°:\nthe x axis (north)",
        (0, 0.8 * top_km),
        xytext=(-120, 0.6 * top_km),
        fontsize=7,
        ha="center",
        arrowprops={"arrowstyle": "-", "color": "0.5", "lw": 0.6},
    )
    ax.set(xlabel="GK easting y (km)", ylabel="GK northing x (km)", ylim=(-600, None))


def draw_block_diagram(ax: Axes) -> None:
    """Paper Fig. 2 redrawn: GPS through the Gauss–Krüger projection and the IMU into the 5-state EKF.

    Examples
    --------
    >>> import matplotlib.pyplot as plt
    >>> from navlib.papers import gauss_kruger_ekf as gk
    >>> fig, ax = plt.subplots()
    >>> gk.draw_block_diagram(ax)
    >>> len(ax.texts) > 0
    True
    >>> plt.close(fig)
    """
    from ..plots import block_diagram  # noqa: PLC0415 -- plotting only (it validates ax)

    blocks = {
        "gps": (0.1, 0.82, "GPS\nlatitude W, longitude L"),
        "zone": (0.33, 0.82, "zone n, central meridian\n$L_0$ = 3n (Eqs. 1–2)"),
        "gk": (0.57, 0.82, "Gauss–Krüger series\nx north, y east (Eqs. 3–11)"),
        "imu": (0.1, 0.15, "IMU\nheading θ, speed v,\nyaw rate ω"),
        "conv": (0.33, 0.15, "grid heading θ − γ\n(convergence, E002-09)"),
        "predict": (0.57, 0.48, "predict (Eqs. 12–13, 16–17)\n$X^- = f(X)$\n$P^- = \\Phi P \\Phi^T + Q$"),
        "update": (0.86, 0.48, "update (Eqs. 14–15, 18)\n$Z = HX + v$, $H = I_5$\n$K = P^-(P^- + R)^{-1}$"),
        "out": (0.86, 0.82, "$\\hat X = [x, y, θ, v, ω]$\n→ robot frame"),
        "delay": (0.86, 0.14, "next step\nk ← k + 1"),
    }
    arrows = [
        ("gps", "zone"),
        ("zone", "gk"),
        ("gk", "update", "$x_{GPS}, y_{GPS}$"),
        ("imu", "conv"),
        ("conv", "update", "$θ_{IMU}, v_{IMU}, ω_{IMU}$"),
        ("predict", "update"),
        ("update", "out"),
        ("update", "delay"),
        ("delay", "predict"),
    ]
    block_diagram(
        ax,
        blocks,
        arrows,
        width=0.18,
        height=0.17,
        colors={"gps": "#dbe9f6", "imu": "#dbe9f6", "predict": "#e3f1dc", "update": "#e3f1dc"},
    )
