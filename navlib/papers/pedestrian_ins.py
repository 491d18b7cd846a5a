r"""Indoor pedestrian navigation with a shoulder-mounted MEMS IMU (paper 004).

Wen Zeyang, Xu Jiangning, Yu Mengqi, "Design of Indoor Navigation System
Based on Double MEMS IMU" (基于MEMS IMU的室内导航系统设计), *Ship Electronic
Engineering* 2016 (12). doi:10.3969/j.issn.1672-9730.2016.12.018

A shoulder-worn board (MPU-6050 IMU, HMC5983 magnetometer, BMP180
barometer) runs a strapdown INS at all times. While the pedestrian stands
still a Kalman filter uses zero velocity and zero angular rate (ZUPT/ZARU)
to estimate and feed back the INS errors; while walking the INS height and
heading are overwritten ("direct binding") by barometric altitude and
tilt-compensated magnetic heading.

Implemented here, in navlib's ENU / right-front-up convention (the paper
prints NED / forward-right-down; ``C_enu = M C_ned M`` with
:data:`navlib.attitude.M_NED_ENU`, the same (heading, pitch, roll) in both):

* Static detector (the paper gives none): the ARE + MV + MAG tests of Skog et al.
  2010, :func:`navlib.filters.zupt.detect_static`, with our starting thresholds
  (:data:`navlib.filters.zupt.STATIC_THRESHOLDS`) and the site's gravity :data:`G_LOCAL`.
* Eq. (1), the 15-state error model, and Eq. (2), the ZUPT/ZARU measurement,
  are missing from the paper (erratum E004-03); they are reconstructed as the
  standard local-level error model and static measurement of
  :mod:`navlib.filters.zupt` (states ``[dr_n, dv_n, dpsi, db_a, db_g]``, dr in
  metres E, N, U). Its H adds the exact first-order Earth-rate block
  ``-C^T [w_ie x]`` (coefficient 7e-5) that the simplified
  ``H = [[0, I, 0, 0, 0], [0, 0, 0, 0, I]]`` leaves out.
* Eq. (3), Kalman recursion with closed-loop feedback
  ``r -= dr, v -= dv, C <- (I - [dpsi x]) C, b += db, dx = 0``; the covariance
  update is the Joseph form of :func:`navlib.kalman.update`, equal to the
  printed ``P = (I - K H) P`` for the optimal gain (:func:`simple_covariance_update`).
* Barometric altitude (formula not printed in the paper, erratum E004-03):
  the BMP180 datasheet form ``h = 44330 (1 - (p/p_ref)^(1/5.255))`` with
  ``p_ref`` the mean pressure of the initial stand (relative height; the
  weather's sea-level pressure cancels), or the hypsometric
  ``R T/g ln(p_ref/p)`` with temperature.
  Floors: ``n = n_ref + round(h / h_floor)``.
* Eq. (4), tilt compensation, CORRECTED (erratum E004-01; the printed form
  mixes up axes and angles, :func:`tilt_compensate_printed`). NED/FRD, pitch :math:`\theta`, roll :math:`\gamma`:

  .. math::

      H_X &= H_x \cos\theta + H_y \sin\theta \sin\gamma + H_z \sin\theta \cos\gamma \\
      H_Y &= H_y \cos\gamma - H_z \sin\gamma

  ENU/RFU (used by the filter), ``m_b = (m_x, m_y, m_z) = (H_y, H_x, -H_z)``:

  .. math::

      m^h_x &= m_x \cos\gamma + m_z \sin\gamma \\
      m^h_y &= m_y \cos\theta + m_x \sin\theta \sin\gamma - m_z \sin\theta \cos\gamma

* Eq. (5) (missing, reconstructed; erratum E004-03):
  ``angle = atan2(-H_Y, H_X) = atan2(-mh_x, mh_y)`` plus 2 pi when negative,
  i.e. in **[0, 2 pi)** (erratum E004-04: the paper says (0, 2 pi]).
* Eq. (6): ``alpha = angle + D`` wrapped to [0, 2 pi), D the declination
  (east positive; the paper calls it lambda, erratum E004-05).
* Walking phase (the paper's "direct binding"): height and vertical rate
  from an alpha-beta tracker on the barometric height, heading reset
  ``C <- rot(z, H_hat - alpha) C`` (ENU sign; the NED form is
  ``rot(z, alpha - H_hat)``), their covariance rows reset.
  Horizontal position and velocity are *not* corrected while walking
  (erratum E004-13): they drift until the next stop. As a documented
  alternative (``walk_aiding="filter"``) the same height and heading are
  Kalman measurements instead of resets.

The filter is :func:`navlib.filters.zupt_ins.run_filter` (its defaults are this paper's sensors; its
fault contract is documented there): Eq. (1)-(3) from :mod:`navlib.filters.zupt`, the walking aids
(Eqs. 4-6) built in.

Not in the paper: the Earth-rate block ``-C^T [w_ie x]`` of H (above), and
an accelerometer process noise five times the MPU-6050 density to cover the
scale-factor and cross-axis errors the 15-state model leaves out
(:class:`navlib.filters.zupt_ins.FilterConfig`).

Also here: the paper's walks (:func:`carpark_legs`, :func:`floor_test_legs`) for the walking-trajectory
generator :func:`navlib.trajectory.walk`, and the HVAC pressure steps of its building.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from .. import attitude
from .._records import unchecked
from .._typing import Array, ArrayLike, Times
from .._validate import (
    Count,
    NonNegative,
    Positive,
    Rng,
    as_array,
    boundary,
    integer,
    pitch_roll,
    positive,
    same_shape,
    scalar,
    time_axis,
)
from ..trajectory import Leg

if TYPE_CHECKING:
    from matplotlib.axes import Axes

__all__ = [
    "G_LOCAL",
    "carpark_legs",
    "floor_test_legs",
    "tilt_compensate_ned",
    "tilt_compensate_printed",
    "heading_from_horizontal",
    "hvac_pressure_steps",
    "simple_covariance_update",
    "draw_system",
]


G_LOCAL = 9.7936
"""Gravity (m/s^2) at the paper's test site (Wuhan): pass it as ``g`` to :func:`navlib.filters.zupt.detect_static`
and :func:`navlib.pdr.detect_steps` for the paper's detectors."""

# --------------------------------------------------------------------------
# The paper's walks
# --------------------------------------------------------------------------


@boundary
def carpark_legs(
    speed: Positive = 1.2,
    stops: ArrayLike = (8.0, 5.0, 20.0, 10.0, 6.0, 15.0, 30.0, 4.0, 12.0, 25.0),
    side: ArrayLike = (40.0, 24.0),
    n_loops: Count = 1,
    initial_stand: float = 30.0,
) -> list[Leg]:
    """A rectangular walk in an underground car park with stops between the pillars.

    Each side is walked in two halves with a stop after each half (the stop
    lengths cycle through ``stops``, s); each corner is a 90-degree right turn
    taken at 2/3 of the speed over 3 s. Starts with ``initial_stand``
    seconds of standing (calibration, pressure reference).

    Examples
    --------
    >>> from navlib.papers import pedestrian_ins as pins
    >>> legs = pins.carpark_legs()
    >>> len(legs), legs[0]                                            # the initial stand first
    (22, Leg(duration=30.0, speed=0.0, turn=0.0, climb=0.0))
    """
    stops = positive(stops, "stops", shape=(None,), min_ndim=1)
    a, b = positive(side, "side", shape=(2,))
    corner = 3.0 * 2 / 3 * speed  # path length of a corner (m)
    if min(a, b) <= corner:
        raise ValueError(
            f"side: expected sides longer than a corner's path ({corner:g} m at speed {speed:g} m/s), got {a:g} x {b:g} m"
        )
    legs, k = [unchecked(Leg, duration=scalar(initial_stand, "initial_stand", positive=True))], 0
    for _ in range(n_loops):
        for length in (a, b, a, b):
            for _ in range(2):
                legs.append(unchecked(Leg, duration=(length - corner) / 2 / speed, speed=speed))
                legs.append(unchecked(Leg, duration=float(stops[k % stops.size])))
                k += 1
            legs.append(unchecked(Leg, duration=3.0, speed=2 / 3 * speed, turn=np.pi / 2))
    legs.append(unchecked(Leg, duration=float(stops[k % stops.size])))
    return legs


@boundary
def floor_test_legs(
    stand: Positive = 60.0, stairs: Positive = 15.0, floor_height: Positive = 3.0, n_round_trips: Count = 2
) -> list[Leg]:
    """The paper's floor test 2F -> 1F -> 2F (x ``n_round_trips``): stands, corridor walks and stairs.

    Each transition: 8 m of corridor at 1.2 m/s, the stairs (``stairs`` s at
    0.35 m/s, ``floor_height`` down or up, with a U-turn at the landing) and
    4 m of corridor; then a stand of ``stand`` seconds. The first stand is
    on 2F.

    Examples
    --------
    >>> from navlib.papers import pedestrian_ins as pins
    >>> legs = pins.floor_test_legs(n_round_trips=1)
    >>> round(sum(leg.climb for leg in legs), 6), len(legs)           # down a floor and back up
    (0.0, 9)
    """
    legs = [unchecked(Leg, duration=stand)]
    for trip in range(2 * n_round_trips):
        climb = -floor_height if trip % 2 == 0 else floor_height
        legs += [
            unchecked(Leg, duration=8 / 1.2, speed=1.2),
            unchecked(Leg, duration=stairs, speed=0.35, turn=np.pi, climb=climb),
            unchecked(Leg, duration=4 / 1.2, speed=1.2, turn=np.pi),
            unchecked(Leg, duration=stand),
        ]
    return legs


# --------------------------------------------------------------------------
# Magnetic heading (Eqs. 4-6)
# --------------------------------------------------------------------------


def tilt_compensate_ned(H_b: ArrayLike, pitch: ArrayLike, roll: ArrayLike) -> tuple[Array, Array]:
    """Corrected Eq. (4) in the paper's NED / forward-right-down frame.

    Parameters
    ----------
    H_b : array_like, shape (..., 3)
        ``[H_x forward, H_y right, H_z down]``.
    pitch, roll : array_like  (rad)

    Returns
    -------
    H_X, H_Y : ndarray
        Horizontal components along magnetic-north-of-heading and its right.

    Examples
    --------
    >>> from navlib.papers import pedestrian_ins as pins
    >>> H_X, H_Y = pins.tilt_compensate_ned([20.0, 0.0, 40.0], 0.0, 0.0)   # level, facing magnetic north (NED, FRD)
    >>> float(H_X), float(H_Y)
    (20.0, 0.0)
    """
    H = as_array(H_b, "H_b", tail=(3,))
    th, ga = pitch_roll(pitch, roll)
    Hx, Hy, Hz = H[..., 0], H[..., 1], H[..., 2]
    HX = Hx * np.cos(th) + Hy * np.sin(th) * np.sin(ga) + Hz * np.sin(th) * np.cos(ga)
    HY = Hy * np.cos(ga) - Hz * np.sin(ga)
    return HX, HY


def tilt_compensate_printed(H_b: ArrayLike, pitch: ArrayLike, roll: ArrayLike) -> tuple[Array, Array]:
    """Eq. (4) as printed (errata E004-01, E004-02), with theta = pitch and phi = roll.

    ``H_X = H_x sin(th) sin(ph) + H_y cos(ph) - H_z cos(th) sin(ph)``,
    ``H_Y = H_x cos(th) + H_z sin(th)``. Kept to show that it does not
    recover the heading under the stated axes.

    Examples
    --------
    >>> from navlib.papers import pedestrian_ins as pins
    >>> H_X, H_Y = pins.tilt_compensate_printed([20.0, 0.0, 40.0], 0.0, 0.0)   # the same level sensor
    >>> float(H_X), float(H_Y)                                        # the printed Eq. (4) swaps the components
    (0.0, 20.0)
    """
    H = as_array(H_b, "H_b", tail=(3,))
    th, ph = pitch_roll(pitch, roll)
    Hx, Hy, Hz = H[..., 0], H[..., 1], H[..., 2]
    return (Hx * np.sin(th) * np.sin(ph) + Hy * np.cos(ph) - Hz * np.cos(th) * np.sin(ph), Hx * np.cos(th) + Hz * np.sin(th))


def heading_from_horizontal(H_X: ArrayLike, H_Y: ArrayLike, declination: float = 0.0) -> Array:
    """Eqs. (5)-(6): ``atan2(-H_Y, H_X) + D`` wrapped to [0, 2 pi) (erratum E004-04).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.papers import pedestrian_ins as pins
    >>> np.round(np.rad2deg(pins.heading_from_horizontal([1.0, 0.0], [0.0, -1.0])), 6)   # NED: north, then east
    array([ 0., 90.])
    """
    X, Y = as_array(H_X, "H_X"), as_array(H_Y, "H_Y")
    if np.any((X == 0) & (Y == 0)):
        raise ValueError("H_X, H_Y: heading undefined for a zero horizontal field")
    return attitude.wrap_2pi(np.arctan2(-Y, X) + scalar(declination, "declination"))


# --------------------------------------------------------------------------
# Barometer and floors
# --------------------------------------------------------------------------


@boundary
def hvac_pressure_steps(
    time: Times, door_times: ArrayLike, rng: Rng, amplitude: NonNegative = 10.0, n_trials: int | None = None
) -> Array:
    """Pressure offsets of ventilated zones: a new offset in [-a, a] after each door (Pa).

    Returns shape (N,), or (n_trials, N) with ``n_trials`` (each trial's offsets drawn in turn: the same
    numbers as ``n_trials`` calls without it).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.papers import pedestrian_ins as pins
    >>> time = np.arange(6.0)
    >>> np.round(pins.hvac_pressure_steps(time, [2.0, 4.0], np.random.default_rng(0)), 3)   # a new offset after each door (Pa)
    array([ 0.   ,  0.   ,  2.739,  2.739, -4.604, -4.604])
    """
    t = time_axis(time, "time", min_samples=1)
    doors = np.sort(as_array(door_times, "door_times", shape=(None,)))
    shape = () if n_trials is None else (integer(n_trials, "n_trials"),)
    levels = np.concatenate([np.zeros(shape + (1,)), rng.uniform(-amplitude, amplitude, shape + (doors.size,))], -1)
    return levels[..., np.searchsorted(doors, t, side="right")]


# --------------------------------------------------------------------------
# Error-state filter: the printed covariance update (Eq. 3)
# --------------------------------------------------------------------------


def simple_covariance_update(P: ArrayLike, H: ArrayLike, R: ArrayLike) -> tuple[Array, Array]:
    """The printed last line of Eq. (3): optimal gain K and ``(I - K H) P``.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.papers import pedestrian_ins as pins
    >>> K, P = pins.simple_covariance_update(np.eye(2), np.eye(2), np.eye(2))
    >>> K, P                                                          # equal variances: half-way
    (array([[0.5, 0. ],
           [0. , 0.5]]), array([[0.5, 0. ],
           [0. , 0.5]]))
    """
    P = as_array(P, "P", shape=(None, None))
    same_shape(P, "P", (len(P), len(P)))  # square (n, n)
    H = as_array(H, "H", shape=(None, len(P)), of="P")  # (m, n)
    R = as_array(R, "R", shape=(len(H), len(H)), of="H")  # (m, m)
    K = P @ H.T @ np.linalg.inv(H @ P @ H.T + R)
    return K, (np.eye(P.shape[0]) - K @ H) @ P


# --------------------------------------------------------------------------
# The paper's block diagram, redrawn
# --------------------------------------------------------------------------

SENSOR_COLOR = "#dbe9f6"
"""Face colour of the sensor boxes in the redrawn block diagram."""


def draw_system(ax: Axes) -> None:
    """Redraw the paper's system block diagram (its Fig. 2) on ``ax``.

    The strapdown INS runs on the MPU-6050 at all times. The static detector splits standing from
    walking: standing, the ZUPT/ZARU Kalman filter (Eqs. 1-3, reconstructed) measures the INS velocity
    and the bias-corrected gyro rate and feeds the estimated errors back; walking, the barometric height
    (BMP180 formula) and the tilt-compensated magnetic heading (Eqs. 4-6, corrected) overwrite the INS
    height and heading ("direct binding"). Drawn in axes coordinates with
    :func:`navlib.plots.block_diagram`; ``ax`` is turned into a schematic (no axes).

    Examples
    --------
    >>> import matplotlib.pyplot as plt
    >>> from navlib.papers import pedestrian_ins as pins
    >>> fig, ax = plt.subplots()
    >>> pins.draw_system(ax)
    >>> len(ax.texts) > 0
    True
    >>> plt.close(fig)
    """
    from .. import plots  # noqa: PLC0415 -- navlib.papers imports without matplotlib

    blocks = {
        "imu": (0.13, 0.84, "MPU-6050\ngyro $\\tilde\\omega$, accel. $\\tilde f$"),
        "det": (0.13, 0.6, "static detector\nstanding / walking"),
        "mag": (0.13, 0.36, "HMC5983\nmagnetometer"),
        "baro": (0.13, 0.12, "BMP180\nbarometer $p$"),
        "ins": (0.45, 0.84, "strapdown INS\n(always running)"),
        "kf": (0.45, 0.6, "ZUPT/ZARU Kalman filter\nEqs. (1)–(3)"),
        "compass": (0.45, 0.36, "tilt-compensated compass\nEqs. (4)–(6)"),
        "height": (0.45, 0.12, "barometric height\n$h = 44330\\,[1-(p/p_0)^{1/5.255}]$"),
        "reset": (0.82, 0.36, "walking: reset $h$ and $H$\n(direct binding)"),
        "out": (0.82, 0.84, "position, velocity,\nattitude, floor"),
    }
    arrows = [
        ("imu", "ins", "$\\tilde\\omega, \\tilde f$"),
        ("imu", "det"),
        ("det", "kf", "standing"),
        ("mag", "compass", "$m$"),
        ("baro", "height", "$p$"),
        ("compass", "reset", "$\\alpha$"),
        ("height", "reset", "$h$"),
        ("reset", "ins"),
        ("ins", "out"),
    ]
    colors = {k: SENSOR_COLOR for k in ("imu", "mag", "baro")}
    plots.block_diagram(ax, blocks, arrows, width=0.23, height=0.13, colors=colors)
    # INS <-> filter: the measurement down, the error feedback up (two parallel arrows)
    for dx, (y0, y1), label in ((0.04, (0.77, 0.675), "$z$"), (-0.04, (0.675, 0.77), "feedback $\\delta\\hat x$")):
        x = 0.45 + dx
        ax.annotate(
            "", (x, y1), (x, y0), xycoords="axes fraction", arrowprops={"arrowstyle": "-|>", "color": "0.25", "linewidth": 1.1}
        )
        ax.text(
            x + (0.012 if dx > 0 else -0.012),
            (y0 + y1) / 2,
            label,
            transform=ax.transAxes,
            fontsize=7.5,
            ha="left" if dx > 0 else "right",
            va="center",
            color="0.2",
        )
