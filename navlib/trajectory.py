"""Motion: trajectories and the ideal IMU outputs they imply.

A :class:`Trajectory` holds time, geodetic position, ENU velocity and
attitude on a uniform time grid. Generators build the motions the papers
need (static, reciprocating rotation of an IMU, vehicles with stops and
turns, a pedestrian walking with a shoulder-worn IMU), integrating position from velocity with the same trapezoid rule as
:func:`navlib.strapdown.integrate`. :func:`ideal_imu` inverts the strapdown
step exactly, so error-free samples integrate back to the trajectory to
rounding error and every simulated error is due to the sensor model alone.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field
from typing import Annotated, Any

import numpy as np
from numba import njit
from numpy.typing import NDArray

from . import _attitude, _earth, attitude, earth
from ._kernels import radii_mn
from ._records import unchecked
from ._typing import Angles, Array, ArrayLike, Times, Vec3, Vec3Series
from ._validate import (
    Check,
    Is,
    NonNegative,
    Positive,
    Real,
    Step,
    as_array,
    as_quat,
    boundary,
    fields_checked,
    in_range,
    instance,
    kernel_array,
    latitude,
    time_axis,
)
from .robust import FaultReport

__all__ = [
    "Trajectory",
    "Segment",
    "static",
    "from_profiles",
    "reciprocating_rotation",
    "vehicle",
    "Leg",
    "Gait",
    "walk",
    "stance_mask",
    "ideal_imu",
    "smooth_ramp",
]


@dataclass(frozen=True)
class Trajectory:
    """Time history of position, velocity and attitude.

    Attributes
    ----------
    time : ndarray, shape (N,)
        Uniformly spaced sample times (s).
    lla : ndarray, shape (..., N, 3)
        ``[lat (rad), lon (rad), h (m)]``.
    vel_n : ndarray, shape (..., N, 3)
        ENU velocity (m/s).
    q_bn : ndarray, shape (..., N, 4)
        Attitude quaternion q_b^n (scalar first).
    faults : navlib.robust.FaultReport
        What the integrator did with faulty samples, e.g. :func:`navlib.strapdown.integrate`'s held
        dropouts (``faults["gyro", "nan"]``, counts of shape (...), flags of shape (..., N - 1));
        empty for generated trajectories.

    Examples
    --------
    >>> from navlib import trajectory
    >>> traj = trajectory.static(1.0, 0.1, [0.6, 0.2, 50.0], [0.0, 0.0, 0.0])
    >>> len(traj), traj.time[:3], traj.lla.shape, traj.q_bn.shape
    (11, array([0. , 0.1, 0.2]), (11, 3), (11, 4))
    """

    time: np.ndarray
    lla: np.ndarray
    vel_n: np.ndarray
    q_bn: np.ndarray
    faults: FaultReport = field(default_factory=FaultReport)

    def __post_init__(self) -> None:
        instance(self.faults, "faults", FaultReport, "a navlib.robust.FaultReport")
        t = time_axis(self.time)
        n = t.size
        object.__setattr__(self, "time", t)
        for name, tail in (("lla", 3), ("vel_n", 3), ("q_bn", 4)):
            a = as_array(getattr(self, name), name, tail=(tail,), min_ndim=1, allow_nan=True)
            if a.shape[-2] != n:
                raise ValueError(f"{name}: expected {n} epochs on axis -2, got shape {a.shape}")
            object.__setattr__(self, name, a)
        norm = np.linalg.norm(self.q_bn, axis=-1)
        as_quat(self.q_bn[np.isfinite(norm)], "q_bn", normalize=False)  # NaN rows: epochs without attitude
        lat = np.asarray(self.lla)[..., 0]
        if np.any(np.abs(lat[np.isfinite(lat)]) > np.pi / 2):
            raise ValueError("lla: expected latitudes (lla[..., 0]) within [-pi/2, pi/2] rad")

    @property
    def dt(self) -> float:
        """Sample interval (s)."""
        return float(self.time[1] - self.time[0])

    @property
    def C_bn(self) -> np.ndarray:
        """Rotation matrices, shape (..., N, 3, 3)."""
        return attitude.quat_to_dcm(self.q_bn)

    @property
    def hpr(self) -> np.ndarray:
        """``[heading, pitch, roll]`` (rad), shape (..., N, 3)."""
        return attitude.quat_to_euler(self.q_bn)

    def __len__(self) -> int:
        return self.time.size


@njit(cache=True)
def _positions(lla0, vel, dt, a, e2):
    n = vel.shape[0]
    lla = np.empty((n, 3))
    lat, lon, h = lla0[0], lla0[1], lla0[2]
    lla[0, 0], lla[0, 1], lla[0, 2] = lat, lon, h
    for k in range(n - 1):
        R_M, R_N = radii_mn(lat, a, e2)
        vm = (vel[k] + vel[k + 1]) / 2
        lat_new = lat + vm[1] / (R_M + h) * dt
        lon = lon + vm[0] / ((R_N + h) * np.cos(lat)) * dt
        h = h + vm[2] * dt
        lat = lat_new
        lla[k + 1, 0], lla[k + 1, 1], lla[k + 1, 2] = lat, lon, h
    return lla


MAX_SAMPLES = 10**9
"""Most samples one simulated trajectory holds (about 100 GB of states beyond it)."""


def _time_grid(duration: float, dt: float) -> np.ndarray:
    """Sample times ``0, dt, ..., n dt`` with ``n = round(duration / dt) >= 1`` (s) of a checked duration and dt."""
    n = round(duration / dt)
    if n < 1:
        raise ValueError(f"duration: expected at least one sample interval dt={dt}, got {duration}")
    if n > MAX_SAMPLES:
        raise ValueError(
            f"dt: {duration:g} s at dt = {dt:g} s is {n:.3g} samples, more than one trajectory holds "
            f"({MAX_SAMPLES:.0e}); is dt in seconds?"
        )
    return dt * np.arange(n + 1)


def _lla(lla: ArrayLike) -> Array:
    lla = as_array(lla, "lla0", shape=(3,))
    latitude(lla[0], "lla0[0] (lat)")
    return lla


@boundary
def from_profiles(
    time: Times, lla0: Vec3, hpr: Angles, vel_n: Vec3Series, ellipsoid: earth.EllipsoidArg = earth.WGS84
) -> Trajectory:
    """Trajectory from attitude and velocity profiles; position is integrated.

    Parameters
    ----------
    time : array_like, shape (N,)
        Uniform sample times (s).
    lla0 : array_like, shape (3,)
        Initial ``[lat (rad), lon (rad), h (m)]``.
    hpr : array_like, shape (N, 3)
        ``[heading, pitch, roll]`` (rad).
    vel_n : array_like, shape (N, 3)
        ENU velocity (m/s).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import analysis, trajectory
    >>> time = np.arange(0.0, 10.01, 0.1)
    >>> vel_n = np.tile([0.0, 1.0, 0.0], (time.size, 1))            # 1 m/s north
    >>> traj = trajectory.from_profiles(time, [0.6, 0.2, 50.0], np.zeros((time.size, 3)), vel_n)
    >>> round(float(analysis.horizontal_error(traj.lla[-1:], traj.lla[:1])[0, 1]), 3)   # metres north after 10 s
    10.0
    """
    t = time_axis(time)
    if not np.allclose(np.diff(t), t[1] - t[0], rtol=1e-9, atol=0):
        raise ValueError("time: expected a uniform time grid")
    hpr = as_array(hpr, "hpr", shape=(t.size, 3), of="time")
    vel = as_array(vel_n, "vel_n", shape=(t.size, 3), of="time")
    return _from_profiles(t, lla0, hpr, vel, ellipsoid)


def _from_profiles(
    t: Array, lla0: ArrayLike, hpr: Array, vel: Array, ellipsoid: earth.Ellipsoid, source: str = "vel_n"
) -> Trajectory:
    """:func:`from_profiles` on a uniform grid ``t`` and profiles (N, 3) built or checked by the caller;
    ``lla0`` is the user's, checked here; ``source`` names the argument the velocities come from."""
    in_range(hpr[:, 1], "hpr[:, 1] (pitch)", -np.pi / 2 - 1e-12, np.pi / 2 + 1e-12, "rad")  # also of built profiles
    lla = _positions(_lla(lla0), kernel_array(vel), t[1] - t[0], ellipsoid.a, ellipsoid.e2)
    if not np.all(np.abs(lla[:, 0]) <= np.pi / 2):
        raise ValueError(f"{source}: the trajectory passes a pole (latitude beyond +-pi/2 rad); start farther from it")
    return unchecked(Trajectory, time=t, lla=lla, vel_n=vel, q_bn=_attitude.euler_to_quat(hpr))


@boundary
def static(duration: Positive, dt: Step, lla0: Vec3, hpr: Angles) -> Trajectory:
    """A stationary IMU at ``lla0`` with constant attitude ``hpr`` (rad).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import trajectory
    >>> traj = trajectory.static(60.0, 0.01, [np.deg2rad(30.0), np.deg2rad(114.0), 0.0], [0.0, 0.0, 0.0])
    >>> len(traj), traj.lla.shape
    (6001, (6001, 3))
    """
    t = _time_grid(duration, dt)
    lla = np.broadcast_to(_lla(lla0), (t.size, 3)).copy()
    hpr = as_array(hpr, "hpr", shape=(3,))
    in_range(hpr[1], "hpr[1] (pitch)", -np.pi / 2 - 1e-12, np.pi / 2 + 1e-12, "rad")
    q = np.broadcast_to(_attitude.euler_to_quat(hpr), (t.size, 4)).copy()
    return Trajectory(t, lla, np.zeros((t.size, 3)), q)


def smooth_ramp(x: ArrayLike) -> Array:
    """``x - sin(2 pi x) / (2 pi)`` on [0, 1]: 0 to 1 with zero slope at both ends.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import trajectory
    >>> np.round(trajectory.smooth_ramp(np.array([0.0, 0.25, 0.5, 1.0])), 4)
    array([0.    , 0.0908, 0.5   , 1.    ])
    """
    return _ramp(as_array(x, "x"))


def _ramp(x: np.ndarray) -> np.ndarray:
    """:func:`smooth_ramp` of a checked array (the legs' local times)."""
    x = np.clip(x, 0.0, 1.0)
    return x - np.sin(2 * np.pi * x) / (2 * np.pi)


@boundary
def reciprocating_rotation(
    duration: Positive,
    dt: Step,
    lla0: Vec3,
    hpr0: Angles,
    axis_b: Vec3,
    amplitude: Real,
    period: Positive,
    rotation_time: Positive = 1.0,
) -> Trajectory:
    """An IMU rotated back and forth about a body-fixed axis (paper 001 §3.2).

    The rotation angle alternates between 0 and ``amplitude``: each
    ``period`` starts with a dwell and ends with a smooth rotation of length
    ``rotation_time``. The attitude is ``C_bn(t) = C_bn0 exp(alpha(t) [u x])``.

    Parameters
    ----------
    duration, dt : float  (s)
    lla0 : array_like, shape (3,)
    hpr0 : array_like, shape (3,)
        Initial attitude (rad).
    axis_b : array_like, shape (3,)
        Unit rotation axis u in the body frame.
    amplitude : float
        Rotation angle (rad), e.g. pi/2.
    period : float
        Time between the starts of successive rotations (s).
    rotation_time : float
        Duration of each rotation (s), less than ``period``.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude, trajectory
    >>> traj = trajectory.reciprocating_rotation(20.0, 0.1, [0.6, 0.2, 0.0], [0.0, 0.0, 0.0], [0.0, 1.0, 0.0], np.pi / 2, 10.0)
    >>> np.round(np.rad2deg(attitude.quat_to_euler(traj.q_bn[[0, 85, 105, 185]]))[:, 2], 3)   # roll: 0, 0, 90, 90
    array([ 0.,  0., 90., 90.])
    """
    t = _time_grid(duration, dt)
    u = as_array(axis_b, "axis_b", shape=(3,))
    if abs(np.linalg.norm(u) - 1) > 1e-9:
        raise ValueError(f"axis_b: expected a unit vector, got norm {np.linalg.norm(u):.6g}")
    if rotation_time >= period:
        raise ValueError(f"rotation_time: expected less than period={period}, got {rotation_time}")
    k = np.floor(t / period)
    s = _ramp((t - k * period - (period - rotation_time)) / rotation_time)
    start = np.where(k % 2 == 0, 0.0, 1.0)
    alpha = amplitude * (start + (1 - 2 * start) * s)
    hpr0 = as_array(hpr0, "hpr0", shape=(3,))
    in_range(hpr0[..., 1], "hpr0[1] (pitch)", -np.pi / 2, np.pi / 2, "rad")  # named here: euler_to_quat says hpr
    q = _attitude.quat_mult(_attitude.euler_to_quat(hpr0), attitude.rotvec_to_quat(alpha[:, None] * u))
    lla = np.broadcast_to(_lla(lla0), (t.size, 3)).copy()
    return Trajectory(t, lla, np.zeros((t.size, 3)), _attitude.positive_scalar(_attitude.unit(q)))


def _on_grid(t: Array, durations: Sequence[float]) -> Iterator[tuple[NDArray[np.bool_], Array]]:
    """Mask and local time of each of consecutive legs (``durations``, s) on the time grid ``t``.

    The legs of :func:`vehicle` and :func:`walk` both go through here; the last leg also takes
    the samples of a grid that overshoots the total duration, so every sample belongs to a leg.
    """
    t0 = 0.0
    for i, duration in enumerate(durations):
        end = t0 + duration
        m = t >= t0 - 1e-9
        if i < len(durations) - 1:
            m &= t < end - 1e-9
        yield m, t[m] - t0
        t0 = end


@dataclass(frozen=True)
class Segment:
    """One leg of a :func:`vehicle` trajectory.

    Over ``duration`` seconds the speed, pitch and roll move smoothly from
    their values at the end of the previous segment to the values given
    here (``None`` keeps them), and the heading changes by ``turn``.
    Units: s, m/s, rad.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude, trajectory
    >>> Segment = trajectory.Segment
    >>> segs = [Segment(10.0, speed=10.0), Segment(10.0, turn=np.pi / 2), Segment(10.0, speed=0.0)]   # speed up, turn right, stop
    >>> traj = trajectory.vehicle(segs, 0.1, [0.6, 0.2, 50.0], 0.0)
    >>> len(traj), round(float(np.rad2deg(attitude.quat_to_euler(traj.q_bn[-1])[0])), 3)
    (301, 90.0)
    """

    duration: Positive
    speed: NonNegative | None = None
    turn: Real = 0.0
    pitch: Annotated[float, Check("scalar", within=(-np.pi / 2, np.pi / 2, "rad"))] | None = None
    roll: Annotated[float, Check("scalar", within=(-np.pi, np.pi, "rad"))] | None = None

    def __post_init__(self) -> None:
        fields_checked(self)


@boundary
def vehicle(
    segments: Sequence[Segment], dt: Step, lla0: Vec3, heading0: Real, ellipsoid: earth.EllipsoidArg = earth.WGS84
) -> Trajectory:
    """A land vehicle driving along its forward axis through a list of segments.

    The velocity is ``speed * [sin(heading) cos(pitch), cos(heading) cos(pitch), sin(pitch)]``
    (no side slip). Starts at rest, level, with heading ``heading0`` (rad).

    Parameters
    ----------
    segments : sequence of Segment
    dt : float
        Sample interval (s).
    lla0 : array_like, shape (3,)
    heading0 : float  (rad)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import trajectory
    >>> segs = [trajectory.Segment(10.0, speed=10.0), trajectory.Segment(10.0, speed=0.0)]   # accelerate, brake
    >>> traj = trajectory.vehicle(segs, 0.1, [0.6, 0.2, 50.0], np.pi / 2)   # heading east
    >>> np.round(traj.vel_n[[0, 100, -1]], 3) + 0.0
    array([[ 0.,  0.,  0.],
           [10.,  0.,  0.],
           [ 0.,  0.,  0.]])
    """
    segments = _listed(segments)
    if not segments or not all(isinstance(s, Segment) for s in segments):
        raise ValueError("segments: expected a non-empty sequence of Segment")
    total = sum(s.duration for s in segments)
    t = _time_grid(total, dt)
    speed, heading, pitch, roll = (np.empty(t.size) for _ in range(4))
    cur = {"speed": 0.0, "heading": float(heading0), "pitch": 0.0, "roll": 0.0}
    for seg, (m, tau) in zip(segments, _on_grid(t, [s.duration for s in segments]), strict=True):
        r = _ramp(tau / seg.duration)
        targets = {"speed": seg.speed, "heading": cur["heading"] + seg.turn, "pitch": seg.pitch, "roll": seg.roll}
        for key, arr in (("speed", speed), ("heading", heading), ("pitch", pitch), ("roll", roll)):
            new = cur[key] if targets[key] is None else float(targets[key])
            arr[m] = cur[key] + (new - cur[key]) * r
            cur[key] = new
    vel = speed[:, None] * np.stack([np.sin(heading) * np.cos(pitch), np.cos(heading) * np.cos(pitch), np.sin(pitch)], -1)
    hpr = np.stack([attitude.wrap_2pi(heading), pitch, roll], -1)
    return _from_profiles(t, lla0, hpr, vel, ellipsoid, "segments")


@dataclass(frozen=True)
class Leg:
    """One leg of a walk: a stop (``speed == 0``) or walking at ``speed`` (m/s).

    Over ``duration`` (s) the heading changes by ``turn`` (rad, clockwise
    positive) and the height by ``climb`` (m; stairs). The speed moves
    smoothly from the previous leg's within the first ``ramp`` seconds of
    the walk (see :func:`walk`); a stop is static once that ramp is over.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude, trajectory
    >>> legs = [trajectory.Leg(2.0), trajectory.Leg(5.0, speed=1.2, turn=np.pi / 2), trajectory.Leg(2.0)]
    >>> traj = trajectory.walk(legs, 0.05, [0.6, 0.2, 50.0], 0.0)
    >>> len(traj), round(float(np.rad2deg(attitude.quat_to_euler(traj.q_bn[-1])[0])), 0)   # turned 90 deg right
    (181, 90.0)
    """

    duration: Positive
    speed: NonNegative = 0.0
    turn: Real = 0.0
    climb: Real = 0.0

    def __post_init__(self) -> None:
        fields_checked(self)
        if self.speed == 0 and (self.turn != 0 or self.climb != 0):
            raise ValueError("turn, climb: expected 0 on a stop (speed == 0)")


@dataclass(frozen=True)
class Gait:
    """Shoulder motion of a walking pedestrian (amplitudes at full walking speed).

    Attributes
    ----------
    step_frequency : float
        Steps per second (Hz); typical 1.6-2.0.
    bounce : float
        Vertical oscillation amplitude at the step frequency (m); 2-3 cm.
    sway : float
        Lateral oscillation amplitude at half the step frequency (m).
    surge : float
        Fore-aft oscillation amplitude at the step frequency (m).
    heading_wiggle, pitch_bob, roll_sway : float
        Shoulder rotation amplitudes (rad): heading and roll at half the step
        frequency (the shoulders turn with each stride), pitch at the step
        frequency.
    lean : float
        Mean forward lean while walking (rad, nose down negative).
    stand_sway, stand_tilt : float
        Body sway while standing: horizontal amplitude (m) and tilt
        amplitude (rad) at ``stand_frequency``.
    stand_frequency : float
        Standing sway frequency (Hz).
    ramp : float
        Time to start or stop walking (s).

    Examples
    --------
    >>> from navlib import trajectory
    >>> gait = trajectory.Gait(step_frequency=2.0, bounce=0.03)
    >>> gait.step_frequency, gait.sway
    (2.0, 0.02)
    """

    step_frequency: Positive = 1.8
    bounce: NonNegative = 0.025
    sway: NonNegative = 0.02
    surge: NonNegative = 0.01
    heading_wiggle: NonNegative = np.deg2rad(3.0)
    pitch_bob: NonNegative = np.deg2rad(1.5)
    roll_sway: NonNegative = np.deg2rad(2.0)
    lean: Real = np.deg2rad(-3.0)
    stand_sway: NonNegative = 0.002
    stand_tilt: NonNegative = np.deg2rad(0.05)
    stand_frequency: Positive = 0.3
    ramp: Positive = 1.0

    def __post_init__(self) -> None:
        fields_checked(self)


def _listed(items: Any) -> list[Any]:
    """``items`` as a list; [] if it is not iterable (None, a number)."""
    try:
        return list(items)
    except TypeError:
        return []


def _walk_grid(legs: object, gait: Gait, dt: float) -> tuple[list[Leg], np.ndarray]:
    """The legs of :func:`walk` (or :func:`stance_mask`) as a list, and its time grid."""
    legs = _listed(legs)
    if not legs or not all(isinstance(leg, Leg) for leg in legs):
        raise ValueError("legs: expected a non-empty sequence of Leg")
    return legs, _time_grid(sum(leg.duration for leg in legs), dt)


def _schedule(legs: list[Leg], t: Array, ramp: float) -> tuple[Array, Array, Array, NDArray[np.bool_]]:
    """Speed, heading offset, height offset and stance flags on the time grid."""
    speed, turn, climb = (np.zeros(t.size) for _ in range(3))
    static = np.zeros(t.size, dtype=bool)
    v_prev, psi, h = 0.0, 0.0, 0.0
    for leg, (m, tau) in zip(legs, _on_grid(t, [leg.duration for leg in legs]), strict=True):
        r = min(ramp, leg.duration)
        speed[m] = v_prev + (leg.speed - v_prev) * _ramp(tau / r)
        frac = _ramp(tau / leg.duration)
        turn[m] = psi + leg.turn * frac
        climb[m] = h + leg.climb * frac
        static[m] = (leg.speed == 0) & ((v_prev == 0) | (tau >= r - 1e-9))
        v_prev, psi, h = leg.speed, psi + leg.turn, h + leg.climb
    return speed, turn, climb, static


@boundary
def stance_mask(legs: Sequence[Leg], dt: Step, gait: Is[Gait] = Gait()) -> np.ndarray:
    """True-static flags of :func:`walk` on its time grid (stops after their ramp).

    Parameters
    ----------
    legs : sequence of Leg
    dt : float  (s)
    gait : Gait
        The gait given to :func:`walk` (its ``ramp``).

    Returns
    -------
    static : ndarray of bool, shape (N,)
        Same length as the trajectory's ``time``.

    Examples
    --------
    >>> from navlib import trajectory
    >>> legs = [trajectory.Leg(2.0), trajectory.Leg(5.0, speed=1.2), trajectory.Leg(2.0)]
    >>> still = trajectory.stance_mask(legs, 0.05)
    >>> still.shape, bool(still[:10].all()), bool(still[60:100].any())
    ((181,), True, False)
    """
    legs, t = _walk_grid(legs, gait, dt)
    return _schedule(legs, t, gait.ramp)[3]


@boundary
def walk(
    legs: Sequence[Leg],
    dt: Step,
    lla0: Vec3,
    heading0: Real,
    gait: Is[Gait] = Gait(),
    ellipsoid: earth.EllipsoidArg = earth.WGS84,
) -> Trajectory:
    """A pedestrian walking and stopping, as seen by a shoulder-worn IMU.

    The shoulder follows a smooth path (speed ramps, turns, stairs) plus
    the gait oscillations of :class:`Gait`, whose amplitudes scale with the
    speed (relative to the fastest leg); while standing it sways slightly.
    Heading = path heading + wiggle, pitch = lean + bob, roll = sway.
    Built with :func:`from_profiles`, so :func:`ideal_imu` is exact on it.

    Parameters
    ----------
    legs : sequence of Leg
    dt : float
        Sample interval (s).
    lla0 : array_like, shape (3,)
        Start ``[lat (rad), lon (rad), h (m)]``.
    heading0 : float
        Initial path heading (rad).
    gait : Gait

    Returns
    -------
    Trajectory

    Examples
    --------
    >>> from navlib import analysis, trajectory
    >>> legs = [trajectory.Leg(2.0), trajectory.Leg(5.0, speed=1.2), trajectory.Leg(2.0)]   # stand, walk north, stand
    >>> traj = trajectory.walk(legs, 0.05, [0.6, 0.2, 50.0], 0.0)
    >>> round(float(analysis.horizontal_error(traj.lla[-1:], traj.lla[:1])[0, 1]), 1)   # metres north
    6.0
    """
    legs, t = _walk_grid(legs, gait, dt)
    speed, turn, climb, _ = _schedule(legs, t, gait.ramp)
    v_max = max(leg.speed for leg in legs)
    a = speed / v_max if v_max > 0 else np.zeros_like(speed)  # gait envelope, 0 when standing
    psi = heading0 + turn
    fwd = np.stack([np.sin(psi), np.cos(psi), np.zeros_like(psi)], -1)
    right = np.stack([np.cos(psi), -np.sin(psi), np.zeros_like(psi)], -1)
    up = np.array([0.0, 0.0, 1.0])
    step, stride, stand = (
        2 * np.pi * gait.step_frequency * t,
        np.pi * gait.step_frequency * t,
        2 * np.pi * gait.stand_frequency * t,
    )
    still = 1 - np.clip(a, 0, 1)
    osc = (
        (gait.sway * a * np.sin(stride) + gait.stand_sway * still * np.sin(stand))[:, None] * right
        + (gait.surge * a * np.sin(step) + gait.stand_sway * still * np.cos(0.7 * stand))[:, None] * fwd
        + (gait.bounce * a * np.cos(step))[:, None] * up
    )
    vel = speed[:, None] * fwd + np.gradient(climb, dt)[:, None] * up + np.gradient(osc, dt, axis=0)
    hpr = np.stack(
        [
            attitude.wrap_2pi(psi + gait.heading_wiggle * a * np.sin(stride + 0.3)),
            gait.lean * a + gait.pitch_bob * a * np.sin(step + 0.5) + gait.stand_tilt * still * np.sin(stand),
            gait.roll_sway * a * np.sin(stride) + gait.stand_tilt * still * np.cos(0.8 * stand),
        ],
        -1,
    )
    return _from_profiles(t, lla0, hpr, vel, ellipsoid, "legs")


@boundary
def ideal_imu(traj: Is[Trajectory], ellipsoid: earth.EllipsoidArg = earth.WGS84) -> tuple[Array, Array]:
    """Error-free gyro and accelerometer samples along a trajectory.

    Sample k is the mean angular rate and specific force over
    ``[t_k, t_k+1]``, the exact inverse of :func:`navlib.strapdown.integrate`'s
    step, including Earth rate, transport rate, Coriolis and normal gravity.

    Parameters
    ----------
    traj : Trajectory
        N epochs (leading axes allowed).

    Returns
    -------
    w_ib_b : ndarray, shape (..., N - 1, 3)
        Angular rate relative to inertial space (rad/s).
    f_b : ndarray, shape (..., N - 1, 3)
        Specific force (m/s^2).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import trajectory
    >>> traj = trajectory.static(0.05, 0.01, [0.6, 0.2, 50.0], [0.0, 0.0, 0.0])
    >>> w_ib_b, f_b = trajectory.ideal_imu(traj)                      # one sample per interval: N - 1
    >>> w_ib_b.shape, np.round(f_b[0], 4)                             # specific force: up, normal gravity
    ((5, 3), array([0.    , 0.    , 9.7967]))
    """
    if not all(np.isfinite(a).all() for a in (traj.lla, traj.vel_n, traj.q_bn)):
        raise ValueError("traj: expected a finite trajectory (no NaN positions, velocities or attitudes)")
    states = (traj.lla, traj.vel_n, traj.q_bn)
    if len(traj) > 2 and all((a == a[..., :1, :]).all() for a in states):
        # Every epoch the same (a static record): every interval gives the first one's samples, bit for bit.
        first = Trajectory(traj.time[:2], traj.lla[..., :2, :], traj.vel_n[..., :2, :], traj.q_bn[..., :2, :])
        lead_n = traj.lla.shape[:-2] + (len(traj) - 1, 3)
        w_first, f_first = ideal_imu(first, ellipsoid)
        return np.broadcast_to(w_first, lead_n).copy(), np.broadcast_to(f_first, lead_n).copy()
    dt = traj.dt
    lat, h = traj.lla[..., :-1, 0], traj.lla[..., :-1, 2]
    if np.any(np.cos(lat) < 1e-9):
        raise ValueError("traj.lla[..., 0] (lat): the ENU transport rate is singular at the poles; expected |lat| < 90 deg")
    in_range(h, "traj.lla[..., 2] (h)", -12e3, 100e3, "m")  # earth.gravity's heights
    v0, v1 = traj.vel_n[..., :-1, :], traj.vel_n[..., 1:, :]
    q0, q1 = traj.q_bn[..., :-1, :], traj.q_bn[..., 1:, :]
    w_ie = _earth.earth_rate_n(lat, ellipsoid)
    w_en = _earth.transport_rate_n(lat, h, v0, ellipsoid)
    w_in = w_ie + w_en
    # The record's attitudes are checked; the rotations derived from them are below pi.
    dq = _attitude.quat_mult(_attitude.quat_mult(_attitude.quat_conj(q0), _attitude.rotvec_to_quat(w_in * dt)), q1)
    w_ib_b = _attitude.quat_to_rotvec(_attitude.unit(dq)) / dt
    q_mid = _attitude.quat_mult(
        _attitude.quat_mult(_attitude.rotvec_to_quat(-w_in * dt / 2), q0), _attitude.rotvec_to_quat(w_ib_b * dt / 2)
    )
    C_mid = _attitude.quat_to_dcm(_attitude.unit(q_mid))
    a_n = (v1 - v0) / dt - _earth.gravity_n(_earth.gravity(lat, h, ellipsoid)) + np.cross(2 * w_ie + w_en, v0)
    f_b = np.einsum("...ji,...j->...i", C_mid, a_n)
    return w_ib_b, f_b
