"""ZUPT/ZARU-aided strapdown INS with barometer and magnetometer aiding (a pedestrian or any walker).

A strapdown INS runs at all times; while the IMU stands still a 15-state error-state Kalman filter
(:mod:`navlib.filters.zupt`: states, F, ZUPT/ZARU rows) uses zero velocity and zero angular rate to
estimate and feed back the INS errors (closed loop: ``r -= dr, v -= dv, C <- (I - [dpsi x]) C,
b += db, dx = 0``); while walking the height comes from an alpha-beta tracker on the barometric height
and the heading from the tilt-compensated compass, either as direct resets ("direct binding",
``Aiding(walk="reset")``) or as Kalman measurements (``"filter"``). This is the system of Wen, Xu & Yu
(2016), paper 004 (:mod:`navlib.papers.pedestrian_ins`, which holds its equations as printed and its
scenarios); its defaults (:class:`FilterConfig`) are that paper's sensors.

The filter (:func:`run_filter`, a compiled per-sample kernel) reuses navlib's strapdown step, the block
covariance prediction of :mod:`navlib.filters.zupt` (:func:`~navlib.filters.zupt.error_state_predict_into`,
which multiplies only the non-zero blocks of the transition matrix) and the Joseph-form update of
:func:`navlib.kalman.update` written for the error state (0 between updates) and for these measurements
(:func:`~navlib.filters.zupt.zupt_zaru_update_into`, ``navlib._kernels.scalar_update``); a step without a
measurement allocates nothing.

Faults (tests in ``tests/faults/test_faults_pedestrian.py``). The IMU samples are screened once, before the
filter runs (:func:`navlib.robust.screen`, per the :class:`navlib.imu.SensorLimits` of the
:class:`~navlib.imu.ImuSamples`); the filter acts on the screen's flags and reports them in
``FilterResult.faults`` with what it found itself:

* a row with a gyro or accelerometer dropout (``"nan"``) or a spike (``"spike"``): both sensors are held from
  the last good row, the process noise is inflated while holding (:class:`ProcessNoise` ``held_*``), and the row
  never feeds ZUPT/ZARU;
* a stuck gyro (``("gyro", "stuck")``): the stuck axes are held like the attitude filters hold them
  (:func:`navlib.robust.screen`) and the accelerometer is used; with all three axes stuck outside a stance the
  gyro's process noise is inflated and the row never feeds ZUPT/ZARU (in a stance the rate is known to be about
  0). Holding such rows whole cost 0.1-0.5 deg of attitude over 16 s in tools/fault_matrix.py;
* free fall or a dead accelerometer (``("accel", "freefall")``): the accelerometer alone is held;
* a sample at the rails (``"saturated"``): integrated as measured, never used for ZUPT/ZARU;
* a clock jump (``("clock", "jump")``): not integrated as motion: the INS and the barometer tracker are held
  over it (mechanised over a zero interval), the covariance grows by the process noise of the whole interval,
  and the row is left out of ZUPT/ZARU;
* ``("zupt", "refused")``: rows flagged static but left out of ZUPT/ZARU for one of the reasons above;
  ``("zupt", "outlier")`` / ``("zupt", "reacquired")``: static updates rejected by the NIS gate / applied
  ungated after repeated rejections (:class:`Gates`);
* barometer and magnetometer: NaN is "no reading" (they are sampled slower than the IMU), not a fault;
  ``("baro", "outlier")`` / ``("baro", "reacquired")``: readings beyond the tracker's gate / the tracker
  re-initialised on a persistent step; ``("mag", "outlier")``: compass samples failing the field and dip
  gate; ``("mag", "saturated")``: samples at ``full_scale_mag``, not used.

A ``RuntimeWarning`` says when ZUPT/ZARU is on and no static update was ever applied.

Beyond the paper: the Earth-rate block ``-C^T [w_ie x]`` of H (:mod:`navlib.filters.zupt`), and an
accelerometer process noise five times the MPU-6050 density to cover the scale-factor and cross-axis
errors the 15-state model leaves out (:class:`ProcessNoise`).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np
from numba import njit

from .. import _kernels, earth, robust, trajectory
from .._kernels import radii_mn
from .._typing import Array, ArrayLike, Quat, Vec3, Vec3Series
from .._validate import Is, as_array, as_quat, booleans, boundary, choice, flag, instance, integer, kernel_array, scalar
from ..imu import ImuSamples
from ..strapdown import earth_constants
from ..units import G0
from .zupt import error_state_predict_into, zupt_zaru_rows_into, zupt_zaru_update_into, zupt_zaru_z_into

__all__ = [
    "Start",
    "Aiding",
    "ProcessNoise",
    "MeasurementNoise",
    "InitialSigma",
    "Gates",
    "BaroTracker",
    "FilterConfig",
    "FilterResult",
    "run_filter",
]

_MAX_LATITUDE = np.deg2rad(89.9)
"""Largest |latitude| of :class:`Start` (rad): the ENU mechanisation is singular at the poles."""


def _vector(x: ArrayLike, name: str, size: int = 3) -> Array:
    return as_array(x, name, shape=(size,))


@dataclass(frozen=True, init=False)
class Start:
    """The INS state before the first sample.

    Attributes
    ----------
    lla : array_like, shape (3,)
        Latitude, longitude (rad) and ellipsoidal height (m); ``|lat| <= 89.9 deg``.
    q_bn : array_like, shape (4,)
        Attitude quaternion (e.g. from :func:`navlib.alignment.level` and :func:`~navlib.alignment.magnetic_heading`).
    vel_n : array_like, shape (3,)
        ENU velocity (m/s); default at rest.
    accel_bias, gyro_bias : array_like, shape (3,)
        Bias estimates (m/s^2, rad/s), e.g. from :func:`navlib.alignment.static_gyro_bias`; default zero.
    time : float
        Time of the first epoch (s).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude
    >>> from navlib.filters import zupt_ins
    >>> start = zupt_ins.Start(lla=np.array([0.6, 0.2, 50.0]), q_bn=attitude.euler_to_quat([0.3, 0.0, 0.0]))
    >>> start.vel_n, start.time
    (array([0., 0., 0.]), 0.0)
    """

    lla: Array
    q_bn: Array
    vel_n: Array
    accel_bias: Array
    gyro_bias: Array
    time: float

    # Written out (init=False) so that it takes array_like values while the fields are typed as the arrays they hold.
    def __init__(
        self,
        lla: Vec3,
        q_bn: Quat,
        vel_n: Vec3 = (0.0, 0.0, 0.0),
        accel_bias: Vec3 = (0.0, 0.0, 0.0),
        gyro_bias: Vec3 = (0.0, 0.0, 0.0),
        time: float = 0.0,
    ) -> None:
        lla = _vector(lla, "lla")
        if abs(lla[0]) > _MAX_LATITUDE:
            raise ValueError("lla: expected |lat| <= 89.9 deg (ENU mechanisation)")
        object.__setattr__(self, "lla", lla)
        object.__setattr__(self, "q_bn", np.ascontiguousarray(as_quat(_vector(q_bn, "q_bn", 4), "q_bn")))
        for name, value in (("vel_n", vel_n), ("accel_bias", accel_bias), ("gyro_bias", gyro_bias)):
            object.__setattr__(self, name, _vector(value, name))
        object.__setattr__(self, "time", scalar(time, "time"))


_WALK = {"none": 0, "reset": 1, "filter": 2}


@dataclass(frozen=True)
class Aiding:
    """What aids the INS: ZUPT/ZARU while static, the barometer and the compass while walking.

    Attributes
    ----------
    walk : {"reset", "filter", "none"}
        While walking: the paper's direct resets of height and heading, the same as Kalman measurements,
        or nothing.
    zupt : bool
        Apply ZUPT/ZARU updates while static (False: a free INS with the walking aids).
    declination : float
        Magnetic declination (rad, east positive).
    B_n : array_like, shape (3,), optional
        Reference field in ENU (uT, e.g. :func:`navlib.earth.magnetic_field`) of the compass gate
        (:class:`Gates` ``mag_field``, ``mag_dip``).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.filters import zupt, zupt_ins
    >>> aiding = zupt_ins.Aiding(walk="filter", declination=np.deg2rad(-3.0), B_n=np.array([0.0, 20.0, -40.0]))
    >>> aiding.walk, aiding.zupt
    ('filter', True)
    """

    walk: str = "reset"
    zupt: bool = True
    declination: float = 0.0
    B_n: np.ndarray | None = None

    def __post_init__(self) -> None:
        choice(self.walk, "walk", tuple(_WALK))
        object.__setattr__(self, "zupt", flag(self.zupt, "zupt"))
        object.__setattr__(self, "declination", scalar(self.declination, "declination"))
        if self.B_n is not None:
            object.__setattr__(self, "B_n", _vector(self.B_n, "B_n"))

    def field_reference(self) -> np.ndarray:
        """Intensity (uT) and dip (rad) of ``B_n`` (zeros without it), as :func:`navlib.earth.field_angles`."""
        if self.B_n is None:
            return np.array([0.0, 0.0])
        B = self.B_n
        return np.array([float(np.linalg.norm(B, axis=-1)), float(np.arctan2(-B[2], np.hypot(B[0], B[1])))])


def _check(record: object, names: tuple[str, ...], may_be_inf: tuple[str, ...] = ()) -> None:
    """Store each named field of a frozen record as a positive float (inf where allowed)."""
    for name in names:
        object.__setattr__(record, name, scalar(getattr(record, name), name, positive=True, allow_inf=name in may_be_inf))


@dataclass(frozen=True)
class ProcessNoise:
    """Process noise of the error model (SI densities).

    Attributes
    ----------
    accel, gyro : float
        White-noise densities (m/s^2/sqrt(Hz), rad/s/sqrt(Hz)). Defaults: the MPU-6050 gyro (datasheet) and
        0.02 m/s^2/sqrt(Hz), five times the MPU-6050's 400 ug/sqrt(Hz), to cover the scale-factor and
        cross-axis errors (1 %, 0.67 %) that the 15-state model leaves out and that walking's 3 m/s^2
        oscillations excite (with the datasheet density the NIS gate rejects the legitimate ZUPTs after a walk).
    accel_bias_rw, gyro_bias_rw : float
        Bias random-walk densities (m/s^3/sqrt(Hz), rad/s^2/sqrt(Hz)).
    held_accel, held_gyro : float
        Uncertainty of a held sample (m/s^2, rad/s): while a fault is bridged by holding the last good
        sample, the velocity and attitude process noise grow by ``sigma^2 dt`` per held sample, so the
        covariance admits the guess and the next stance's ZUPT/ZARU is not gated out.

    Examples
    --------
    >>> from navlib.filters import zupt_ins
    >>> noise = zupt_ins.ProcessNoise(accel=0.05)
    >>> noise.accel, noise.gyro_bias_rw
    (0.05, 1e-05)
    """

    accel: float = 0.02
    gyro: float = np.deg2rad(0.005)
    accel_bias_rw: float = 1e-4
    gyro_bias_rw: float = 1e-5
    held_accel: float = 1.0
    held_gyro: float = 0.1

    def __post_init__(self) -> None:
        _check(self, ("accel", "gyro", "accel_bias_rw", "gyro_bias_rw", "held_accel", "held_gyro"))


@dataclass(frozen=True)
class MeasurementNoise:
    """Measurement sigmas (SI units).

    Attributes
    ----------
    zupt : float
        ZUPT velocity sigma (m/s); absorbs standing sway.
    zaru : float
        ZARU rate sigma (rad/s) of a single sample; divided by sqrt(n) for the mean of n samples.
    baro : float
        Barometric height sigma (m); default the BMP180's 0.17 m.
    heading : float
        Magnetic heading sigma (rad); default the HMC5983's 2 deg.

    Examples
    --------
    >>> from navlib.filters import zupt, zupt_ins
    >>> noise = zupt_ins.MeasurementNoise(zupt=0.02)
    >>> noise.zupt, noise.baro
    (0.02, 0.17)
    """

    zupt: float = 0.01
    zaru: float = np.deg2rad(0.1)
    baro: float = 0.17
    heading: float = np.deg2rad(2.0)

    def __post_init__(self) -> None:
        _check(self, ("zupt", "zaru", "baro", "heading"))


@dataclass(frozen=True)
class InitialSigma:
    """Initial standard deviations of the error states.

    Attributes
    ----------
    pos, vel, tilt, heading, accel_bias, gyro_bias : float
        (m, m/s, rad, rad, m/s^2, rad/s). The bias defaults are the residual biases after a static
        calibration (10 mg, 0.05 deg/s).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.filters import zupt_ins
    >>> sigma = zupt_ins.InitialSigma(heading=np.deg2rad(10.0))
    >>> round(float(np.rad2deg(sigma.heading)), 6), sigma.pos
    (10.0, 0.01)
    """

    pos: float = 0.01
    vel: float = 0.01
    tilt: float = np.deg2rad(0.5)
    heading: float = np.deg2rad(2.0)
    accel_bias: float = 0.01 * G0
    gyro_bias: float = np.deg2rad(0.05)

    def __post_init__(self) -> None:
        _check(self, ("pos", "vel", "tilt", "heading", "accel_bias", "gyro_bias"))


@dataclass(frozen=True)
class Gates:
    """Measurement gates; inf disables a gate.

    Attributes
    ----------
    zupt : float
        NIS gate of the static update (chi-square, 6 dof; 22.5 is 99.9 %): rejects false stances (a walker
        flagged static), counted ``("zupt", "outlier")``.
    max_rejected : int
        After this many consecutive rejections within one stance the next update is applied ungated, with the
        velocity variances widened to the innovation (``("zupt", "reacquired")``): a stance that keeps failing
        the gate means the INS has drifted beyond its covariance, and gating it forever would lock the filter
        out. Likewise for the barometer gate.
    baro : float
        A barometric height differing from the alpha-beta tracker's prediction by more than this (m) is a
        spike (``("baro", "outlier")``): the tracker coasts over it and no aiding uses it. After
        ``max_rejected`` consecutive rejections the tracker is re-initialised on the measurement
        (``("baro", "reacquired")``): the height really changed while the barometer was missing or the tracker
        diverged. Default 5 m: 10 BMP180 sigmas (0.5 m at 0.06 hPa), far beyond HVAC pressure steps (~1 m) and
        the tracker lag on stairs.
    mag_field, mag_dip : float
        Compass samples whose field intensity differs from that of :class:`Aiding` ``B_n`` by more than this
        (uT), or the dip by more than this (rad), are not used (``("mag", "outlier")``); also the defence
        against magnetometer spikes (a 100-sigma spike changes |m| by tens of uT). Default inf: every sample
        is used.

    Examples
    --------
    >>> from navlib.filters import zupt, zupt_ins
    >>> zupt_ins.Gates(zupt=16.8, mag_field=0.1)                    # chi-square 99 % (6 dof); a 10 % field-norm gate
    Gates(zupt=16.8, max_rejected=5, baro=5.0, mag_field=0.1, mag_dip=inf)
    """

    zupt: float = 22.5
    max_rejected: int = 5
    baro: float = 5.0
    mag_field: float = np.inf
    mag_dip: float = np.inf

    def __post_init__(self) -> None:
        _check(self, ("zupt", "baro", "mag_field", "mag_dip"), may_be_inf=("zupt", "baro", "mag_field", "mag_dip"))
        object.__setattr__(self, "max_rejected", integer(self.max_rejected, "max_rejected"))


@dataclass(frozen=True)
class BaroTracker:
    """The alpha-beta tracker smoothing the barometric height.

    Attributes
    ----------
    alpha, beta : float
        Gains of the height and of its rate (dimensionless).

    Examples
    --------
    >>> from navlib.filters import zupt_ins
    >>> zupt_ins.BaroTracker(alpha=0.1, beta=0.01)
    BaroTracker(alpha=0.1, beta=0.01)
    """

    alpha: float = 0.2
    beta: float = 0.02

    def __post_init__(self) -> None:
        _check(self, ("alpha", "beta"))


@dataclass(frozen=True)
class FilterConfig:
    """Tuning of the ZUPT/ZARU error-state filter; defaults: paper 004's sensors (MPU-6050, BMP180, HMC5983).

    Attributes
    ----------
    process : ProcessNoise
    measurement : MeasurementNoise
    initial : InitialSigma
    gates : Gates
    tracker : BaroTracker
    update_rate : float
        ZUPT/ZARU update rate while static (Hz): the static samples are averaged over ``1 / update_rate``.

    Examples
    --------
    >>> from navlib.filters import zupt, zupt_ins
    >>> config = zupt_ins.FilterConfig(gates=zupt_ins.Gates(zupt=30.0), update_rate=20.0)
    >>> config.gates.zupt, config.update_rate, config.tracker.alpha
    (30.0, 20.0, 0.2)
    """

    process: ProcessNoise = field(default_factory=ProcessNoise)
    measurement: MeasurementNoise = field(default_factory=MeasurementNoise)
    initial: InitialSigma = field(default_factory=InitialSigma)
    gates: Gates = field(default_factory=Gates)
    tracker: BaroTracker = field(default_factory=BaroTracker)
    update_rate: float = 10.0

    def __post_init__(self) -> None:
        for name, cls in (
            ("process", ProcessNoise),
            ("measurement", MeasurementNoise),
            ("initial", InitialSigma),
            ("gates", Gates),
            ("tracker", BaroTracker),
        ):
            instance(getattr(self, name), name, cls, f"a {cls.__name__}")
        _check(self, ("update_rate",))


# --------------------------------------------------------------------------- the compiled filter

_HOLD_ACCEL, _HOLD_GYRO = 1, 2
"""Bits of :attr:`_Samples.hold`: the accelerometer, the gyro held (process noise inflated)."""

(_ZUPT, _ZUPT_REJECTED, _ZUPT_FORCED, _BARO_AIDED, _MAG_AIDED, _MAG_GATED, _BARO_REJECTED, _BARO_REINIT) = range(8)
"""What the kernel counts (its ``counts`` array)."""


class _Samples(NamedTuple):
    """Per-sample inputs of :func:`_filter_kernel`: N rows each, SI units, NaN = no reading."""

    w: np.ndarray  # (N, 3) gyro (rad/s), held over the rows with the _HOLD_GYRO bit
    f: np.ndarray  # (N, 3) accelerometer (m/s^2), held over the rows with hold > 0
    dt: np.ndarray  # (N,) interval covered by each sample (s)
    jump: np.ndarray  # (N,) bool: clock jump, nothing integrated
    hold: np.ndarray  # (N,) int8: _HOLD_ACCEL | _HOLD_GYRO bits (process noise inflated)
    static: np.ndarray  # (N,) bool: standing still (no walking aids)
    zupt: np.ndarray  # (N,) bool: static and usable for ZUPT/ZARU
    h_baro: np.ndarray  # (N,) barometric height (m)
    m_b: np.ndarray  # (N, 3) magnetometer (uT)


class _State(NamedTuple):
    """The INS state before the first sample (:class:`Start`) and its covariance."""

    lla: np.ndarray  # (3,) rad, rad, m
    vel: np.ndarray  # (3,) m/s ENU
    q: np.ndarray  # (4,)
    b: np.ndarray  # (6,) accelerometer then gyro bias
    p0_diag: np.ndarray  # (15,) initial variances


class _Tuning(NamedTuple):
    """The options of :func:`_filter_kernel` (``r_*`` are variances; see the option records)."""

    walk: int  # _WALK code
    declination: float
    field_ref: np.ndarray  # (2,) reference intensity (uT) and dip (rad)
    every: int  # static samples averaged per ZUPT/ZARU update
    q_rate: np.ndarray  # (15,) process-noise densities squared (Q = q_rate dt_k)
    held_accel: float
    held_gyro: float
    r_zupt: float
    r_zaru: float
    r_baro: float
    r_heading: float
    alpha: float
    beta: float
    gate: float
    max_rejected: int
    baro_gate: float
    field_tol: float
    dip_tol: float
    earth_consts: np.ndarray  # (7,) navlib.strapdown.earth_constants


@njit(cache=True)
def _feedback(x, lla, vel, q, b, a, e2):
    """Closed-loop correction of Eq. (3): apply the error state ``x`` to the INS (the filter's state is 0 again)."""
    R_M, R_N = radii_mn(lla[0], a, e2)
    lla[0] -= x[1] / (R_M + lla[2])
    lla[1] -= x[0] / ((R_N + lla[2]) * np.cos(lla[0]))
    lla[2] -= x[2]
    for i in range(3):
        vel[i] -= x[3 + i]
    d0, d1, d2, d3 = _kernels.rotvec_to_quat_t(-x[6], -x[7], -x[8])  # C <- (I - [dpsi x]) C
    m0, m1, m2, m3 = _kernels.quat_mult_t(d0, d1, d2, d3, q[0], q[1], q[2], q[3])
    s = np.sqrt(m0 * m0 + m1 * m1 + m2 * m2 + m3 * m3)
    q[0], q[1], q[2], q[3] = m0 / s, m1 / s, m2 / s, m3 / s
    for i in range(6):
        b[i] += x[9 + i]


@njit(cache=True)
def _finite_row(x, k):
    """``np.isfinite(x[k]).all()`` without a temporary array."""
    for i in range(x.shape[1]):
        if not np.isfinite(x[k, i]):
            return False
    return True


@njit(cache=True)
def _reset_state(P, i, sigma):
    for j in range(P.shape[0]):
        P[i, j] = 0.0
        P[j, i] = 0.0
    P[i, i] = sigma * sigma


class _Work(NamedTuple):
    """Scratch arrays of :func:`_filter_kernel` and its measurement updates: a step without a measurement
    allocates nothing."""

    q_k: np.ndarray  # (15,) process noise (diagonal) of a step
    predict: np.ndarray  # (15, 15) scratch of error_state_predict_into
    C: np.ndarray  # (3, 3) C_bn after the step
    C_dt: np.ndarray  # (3, 3)
    f_dt: np.ndarray  # (3,) f_n dt
    w_k: np.ndarray  # (3,) bias-corrected gyro
    f_k: np.ndarray  # (3,) bias-corrected accelerometer
    w_sum: np.ndarray  # (3,) sum of the static gyro samples since the last ZUPT/ZARU
    w_ie: np.ndarray  # (3,) Earth rate (ENU)
    dx: np.ndarray  # (15,) the error state an update estimates, fed back at once
    H6: np.ndarray  # ZUPT/ZARU: H (6, 15), z, diag(R)
    z6: np.ndarray
    r6: np.ndarray
    h1: np.ndarray  # (15,) the row of a scalar measurement (height, heading)


@njit(cache=True)
def _work(c):
    return _Work(
        np.empty(15),
        np.empty((15, 15)),
        np.empty((3, 3)),
        np.empty((3, 3)),
        np.empty(3),
        np.zeros(3),
        np.zeros(3),
        np.zeros(3),
        np.zeros(3),
        np.zeros(15),
        np.zeros((6, 15)),
        np.zeros(6),
        np.array([c.r_zupt, c.r_zupt, c.r_zupt, c.r_zaru, c.r_zaru, c.r_zaru]),
        np.zeros(15),
    )


_HEIGHT_COLUMN, _ATTITUDE_COLUMNS = np.array([2]), np.array([6, 7, 8])
"""The error states the height and the heading measure (their rows' non-zero columns)."""

# The three measurement steps below are inlined into _filter_kernel (inline="always", each has one call site):
# compiled on their own, each would optimise and emit its callees' code once more (numba links a function's
# callees into its own module), which cost 3 s of the kernel's cold compile.


@njit(cache=True, inline="always")
def _zupt_zaru(P, lla, vel, q, b, n_sum, forced, c, ws):
    """ZUPT + ZARU (Eq. 2) on the mean rate of ``n_sum`` static samples; ``forced``: ungated, the velocity
    variances widened to the innovation first (P was too small). Returns the status of
    :func:`~navlib.filters.zupt.zupt_zaru_update_into`."""
    omega = c.earth_consts[6]
    ws.w_ie[1], ws.w_ie[2] = omega * np.cos(lla[0]), omega * np.sin(lla[0])
    zupt_zaru_rows_into(ws.H6, ws.C, ws.w_ie)
    for i in range(3):  # the mean rate (the caller zeroes the sum after the update)
        ws.w_sum[i] /= n_sum
    zupt_zaru_z_into(ws.z6, vel, ws.w_sum, b[3:6], ws.C, ws.w_ie)
    for i in range(3):
        ws.r6[3 + i] = c.r_zaru / n_sum
    if forced:
        for i in range(3):
            _reset_state(P, 3 + i, max(np.sqrt(P[3 + i, 3 + i]), abs(ws.z6[i])))
    _, status = zupt_zaru_update_into(P, ws.dx, ws.z6, ws.H6, ws.r6, np.inf if forced else c.gate)
    if status == 1:
        _feedback(ws.dx, lla, vel, q, b, c.earth_consts[0], c.earth_consts[2])
    return status


@njit(cache=True)
def _track_baro(h, hb, vb, started, t_since, n_rejected, c):
    """One barometric height into the alpha-beta tracker (height ``hb``, rate ``vb``; ``t_since`` s since the
    last reading used). Returns ``(hb, vb, started, n_rejected, used, event)``, event 1 for a reading beyond
    the gate (a spike: the tracker coasts), 2 for a re-initialisation (the tracker, not the sensor, was off)."""
    if not started:
        return h, 0.0, True, n_rejected, True, 0
    r = h - hb
    if abs(r) > c.baro_gate and n_rejected < c.max_rejected:
        return hb, vb, True, n_rejected + 1, False, 1
    if abs(r) > c.baro_gate:
        return h, 0.0, True, 0, True, 2
    return hb + c.alpha * r, vb + c.beta * r / t_since, True, 0, True, 0


@njit(cache=True, inline="always")
def _height_aid(P, lla, vel, q, b, hb, vb, h, c, ws):
    """The tracked height while walking: a direct reset (the paper's binding) or a Kalman measurement of the
    measured height ``h``."""
    if c.walk == 1:
        lla[2], vel[2] = hb, vb
        _reset_state(P, 2, np.sqrt(c.r_baro))
        _reset_state(P, 5, 0.3)
        return
    ws.h1[:] = 0.0
    ws.h1[2] = 1.0
    _kernels.scalar_update(P, ws.dx, lla[2] - h, ws.h1, _HEIGHT_COLUMN, c.r_baro)
    _feedback(ws.dx, lla, vel, q, b, c.earth_consts[0], c.earth_consts[2])


@njit(cache=True, inline="always")
def _heading_aid(P, lla, vel, q, b, m_b, c, ws):
    """The tilt-compensated compass heading while walking (Eqs. 4-6), gated on the field's intensity and dip:
    a direct reset ``C <- rot(z, H_hat - alpha) C`` or a Kalman measurement. Returns whether it was used."""
    C = ws.C
    m_n = _kernels.mat3_vec(C, m_b)  # (C @ m_b's bits)
    F_m = np.sqrt(m_n[0] ** 2 + m_n[1] ** 2 + m_n[2] ** 2)
    dip = np.arctan2(-m_n[2], np.sqrt(m_n[0] ** 2 + m_n[1] ** 2))
    if abs(F_m - c.field_ref[0]) > c.field_tol or abs(dip - c.field_ref[1]) > c.dip_tol:
        return False
    pitch, roll = np.arcsin(min(1.0, max(-1.0, C[2, 1]))), np.arctan2(-C[2, 0], C[2, 2])
    alpha_h = _kernels.tilt_heading(m_b[0], m_b[1], m_b[2], pitch, roll) + c.declination
    dh = _kernels.wrap_pi(_kernels.dcm_heading(C[0, 1], C[1, 1]) - alpha_h)
    if c.walk == 1:
        m0, m1, m2, m3 = _kernels.quat_mult_t(np.cos(dh / 2), 0.0, 0.0, np.sin(dh / 2), q[0], q[1], q[2], q[3])
        s = np.sqrt(m0 * m0 + m1 * m1 + m2 * m2 + m3 * m3)
        q[0], q[1], q[2], q[3] = m0 / s, m1 / s, m2 / s, m3 / s
        _reset_state(P, 8, np.sqrt(c.r_heading))
        return True
    c1 = C[:, 1]
    hh = c1[0] ** 2 + c1[1] ** 2
    ws.h1[:] = 0.0
    ws.h1[6], ws.h1[7], ws.h1[8] = c1[0] * c1[2] / hh, c1[1] * c1[2] / hh, -1.0
    _kernels.scalar_update(P, ws.dx, _kernels.wrap_pi(dh), ws.h1, _ATTITUDE_COLUMNS, c.r_heading)
    _feedback(ws.dx, lla, vel, q, b, c.earth_consts[0], c.earth_consts[2])
    return True


@njit(cache=True)
def _filter_kernel(samples, s0, c):
    """Run the filter over ``samples`` (:class:`_Samples`) from the state ``s0`` (:class:`_State`) with the
    options ``c`` (:class:`_Tuning`). Returns the outputs per epoch, the counts and the final covariance."""
    w, f, dt, jump, hold, static, zupt_row, h_baro, m_b = samples
    n = w.shape[0]
    counts = np.zeros(8, dtype=np.int64)
    lla_out, vel_out, q_out = np.empty((n + 1, 3)), np.empty((n + 1, 3)), np.empty((n + 1, 4))
    b_out, p_out = np.empty((n + 1, 6)), np.empty((n + 1, 15))
    lla, vel, q, b = s0.lla.copy(), s0.vel.copy(), s0.q.copy(), s0.b.copy()
    P = np.diag(s0.p0_diag)
    ws = _work(c)
    w_k, f_k, C, C_dt, f_dt, q_k = ws.w_k, ws.f_k, ws.C, ws.C_dt, ws.f_dt, ws.q_k
    # read before the loop: a record's array read per sample counts a reference (navlib._kernels)
    q_rate, earth_consts, w_sum, predict = c.q_rate, c.earth_consts, ws.w_sum, ws.predict
    n_sum, n_rejected = 0, 0  # static samples summed, ZUPTs rejected in this stance
    # False as a plain bool, not the literal False: navlib.strapdown's specialisation of nav_step, compiled once
    # (a literal compiled a second one, 0.7 s of a cold start)
    hold_height = n < 0
    hb, vb, tracking, t_baro, n_baro_rejected = 0.0, 0.0, False, 0.0, 0
    _store(0, lla_out, vel_out, q_out, b_out, p_out, lla, vel, q, b, P)
    for k in range(n):
        dtk = 0.0 if jump[k] else dt[k]  # a clock jump: no motion integrated over it
        # --- strapdown INS on the bias-corrected samples ---
        for i in range(3):
            w_k[i] = w[k, i] - b[3 + i]
            f_k[i] = f[k, i] - b[i]
        _kernels.nav_step(lla, vel, q, w_k, f_k, dtk, earth_consts, hold_height)  # the shared mechanisation
        # --- P = Phi P Phi^T + Q, Phi = I + F dt; x = Phi x stays 0 (fed back and reset at each update) ---
        _kernels.quat_to_dcm_into(C, q)
        f_n = _kernels.mat3_vec(C, f_k)
        for i in range(3):
            f_dt[i] = f_n[i] * dtk
            for j in range(3):
                C_dt[i, j] = C[i, j] * dtk
        for i in range(15):
            q_k[i] = q_rate[i] * dtk
        if hold[k] > 0:  # a held sample is a guess: inflate, don't trust
            for i in range(3):
                if hold[k] & _HOLD_ACCEL:
                    q_k[3 + i] += c.held_accel * c.held_accel * dtk
                if hold[k] & _HOLD_GYRO:
                    q_k[6 + i] += c.held_gyro * c.held_gyro * dtk
        error_state_predict_into(P, C_dt, f_dt, dtk, q_k, predict)
        if jump[k]:  # Phi = I, Q = 0 above: add the whole interval's noise
            for i in range(15):
                P[i, i] += q_rate[i] * dt[k]
        # --- standing still: ZUPT/ZARU every `every` usable samples ---
        if zupt_row[k]:
            for i in range(3):
                w_sum[i] += w[k, i]
            n_sum += 1
            if n_sum >= c.every:
                # a stance that keeps failing the gate means the INS, not the stance, is wrong
                forced = n_rejected >= c.max_rejected
                status = _zupt_zaru(P, lla, vel, q, b, n_sum, forced, c, ws)
                if status == 1:
                    counts[_ZUPT] += 1
                    counts[_ZUPT_FORCED] += forced
                    n_rejected = 0
                elif status == -1:
                    counts[_ZUPT_REJECTED] += 1
                    n_rejected += 1
                w_sum[:], n_sum = 0.0, 0
        elif not static[k]:
            w_sum[:], n_sum, n_rejected = 0.0, 0, 0
        # --- barometer: the tracker always, the height aid while walking ---
        if np.isfinite(h_baro[k]):
            hb, vb, tracking, n_baro_rejected, used, event = _track_baro(h_baro[k], hb, vb, tracking, t_baro, n_baro_rejected, c)
            if event == 1:
                counts[_BARO_REJECTED] += 1
            elif event == 2:
                counts[_BARO_REINIT] += 1
            if used:
                t_baro = 0.0
                if c.walk > 0 and not static[k]:
                    counts[_BARO_AIDED] += 1
                    _height_aid(P, lla, vel, q, b, hb, vb, h_baro[k], c, ws)
        hb += vb * dtk
        t_baro += dt[k]  # (dtk but for a jump, 0: keeps t_baro > 0)
        # --- compass heading while walking ---
        if c.walk > 0 and not static[k] and _finite_row(m_b, k):
            used = _heading_aid(P, lla, vel, q, b, m_b[k], c, ws)
            counts[_MAG_AIDED if used else _MAG_GATED] += 1
        _store(k + 1, lla_out, vel_out, q_out, b_out, p_out, lla, vel, q, b, P)
    return lla_out, vel_out, q_out, b_out, p_out, counts, P


@njit(cache=True)
def _store(k, lla_out, vel_out, q_out, b_out, p_out, lla, vel, q, b, P):
    """Row k of the outputs, element by element (cheaper than row assignments, which also compile numba's
    shape-mismatch messages: seconds of a cold start)."""
    for i in range(3):
        lla_out[k, i], vel_out[k, i] = lla[i], vel[i]
    for i in range(4):
        q_out[k, i] = q[i]
    for i in range(6):
        b_out[k, i] = b[i]
    for i in range(15):
        p_out[k, i] = P[i, i]


@dataclass(frozen=True)
class FilterResult:
    """Output of :func:`run_filter`.

    Attributes
    ----------
    nav : Trajectory
        Corrected INS solution, N + 1 epochs.
    accel_bias, gyro_bias : ndarray, shape (N + 1, 3)
        Bias estimates (m/s^2, rad/s).
    P_diag : ndarray, shape (N + 1, 15)
        Diagonal of the error covariance.
    P : ndarray, shape (15, 15)
        Error covariance after the last sample (symmetric positive definite).
    zupt_updates : int
        Static (ZUPT/ZARU) updates applied, forced ones included.
    baro_aidings, mag_aidings : int
        Barometer and compass samples used while walking.
    faults : FaultReport
        The screen's counts and per-sample flags (``gyro``, ``accel``, ``clock``, ``mag`` with ``m_b``) and the
        filter's own (``zupt``, ``baro``, ``mag``; see the module's list), e.g. ``result.faults["gyro", "nan"]``,
        ``result.faults.flags["zupt", "refused"]``.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import imu, trajectory
    >>> from navlib.filters import zupt_ins
    >>> traj = trajectory.static(1.0, 0.01, [0.6, 0.2, 50.0], [0.0, 0.0, 0.0])
    >>> w_ib_b, f_b = trajectory.ideal_imu(traj)
    >>> start = zupt_ins.Start(traj.lla[0], traj.q_bn[0])
    >>> res = zupt_ins.run_filter(imu.ImuSamples(w_ib_b, f_b, 0.01), start, np.ones(100, bool))   # static throughout
    >>> len(res.nav), res.P_diag.shape, res.zupt_updates
    (101, (101, 15), 10)
    """

    nav: trajectory.Trajectory
    accel_bias: np.ndarray
    gyro_bias: np.ndarray
    P_diag: np.ndarray
    P: np.ndarray
    zupt_updates: int
    baro_aidings: int
    mag_aidings: int
    faults: robust.FaultReport

    @property
    def updated(self) -> bool:
        """False when no ZUPT/ZARU update was ever applied (no static interval)."""
        return self.zupt_updates > 0


def _held(x: np.ndarray, keep: np.ndarray) -> np.ndarray:
    """``x`` with every row not kept replaced by the last kept one (``keep[0]`` must be True)."""
    last = np.maximum.accumulate(np.where(keep, np.arange(keep.size), 0))
    return kernel_array(x[last])


def _samples(s: robust.Screened, static: np.ndarray, h_baro: np.ndarray, zupt: bool) -> tuple[_Samples, np.ndarray]:
    """The kernel's samples from the screen's flags, and the static rows refused for ZUPT/ZARU.

    A gyro or accelerometer dropout or spike holds both sensors (the row is one measurement); a gyro with all three
    axes stuck outside a stance holds the gyro (:func:`navlib.robust.screen`'s hold; in a stance the rate is known to
    be about 0), a stuck axis beside a live one is held alone; free fall holds the accelerometer; those rows,
    saturated ones and clock jumps never feed ZUPT/ZARU.
    """
    flags = s.faults.flags
    both = flags["gyro", "nan"] | flags["gyro", "spike"] | flags["accel", "nan"] | flags["accel", "spike"]
    frozen = ~s.fresh & ~both & ~static
    falling = flags["accel", "freefall"] & ~both
    if both[0]:
        raise ValueError("imu: expected a valid first sample (dropouts are held from the last good one)")
    if falling[0]:
        raise ValueError(
            f"imu: expected a valid first sample, got |f| = {np.linalg.norm(s.imu.f_b[0]):.3g} m/s^2 "
            f"< freefall_accel = {s.imu.limits.freefall_accel:g} (free fall is held from the last good one)"
        )
    jump = flags["clock", "jump"]
    usable = ~(both | frozen | falling | flags["gyro", "saturated"] | flags["accel", "saturated"] | jump)
    hold = (np.where(both | frozen, _HOLD_GYRO, 0) | np.where(both | falling, _HOLD_ACCEL, 0)).astype(np.int8)
    samples = _Samples(
        w=_held(s.w_ib_b, ~both),
        f=_held(s.imu.f_b, ~(both | falling)),
        dt=s.dt,
        jump=kernel_array(jump),
        hold=hold,
        static=static,
        zupt=static & usable & zupt,
        h_baro=h_baro,
        m_b=_mag_samples(s),
    )
    return samples, static & ~usable & zupt


def _mag_samples(s: robust.Screened) -> np.ndarray:
    """The compass samples the filter may use: NaN where there is none or it is at the rails."""
    if s.m_b is None:
        return np.full((s.imu.n, 3), np.nan)
    m = s.m_b
    if np.isinf(m).any() or np.any(np.all(m == 0, axis=-1)):
        raise ValueError("m_b: expected finite, non-zero magnetometer vectors (NaN marks a missing sample)")
    return kernel_array(np.where(s.faults.flags["mag", "saturated"][:, None], np.nan, m))


def _faults(s: robust.Screened, refused: np.ndarray, counts: np.ndarray) -> robust.FaultReport:
    """The screen's faults (but ``("mag", "nan")``: NaN is no compass reading) with the filter's own."""
    flags = {key: v for key, v in s.faults.flags.items() if key != ("mag", "nan")}
    flags["zupt", "refused"] = refused
    totals = {key: v.sum(-1) for key, v in flags.items()}
    for key, i in (
        (("zupt", "outlier"), _ZUPT_REJECTED),
        (("zupt", "reacquired"), _ZUPT_FORCED),
        (("baro", "outlier"), _BARO_REJECTED),
        (("baro", "reacquired"), _BARO_REINIT),
        (("mag", "outlier"), _MAG_GATED),
    ):
        totals[key] = int(counts[i])
    return robust.FaultReport(totals, flags)


def _tuning(aiding: Aiding, config: FilterConfig, typical_dt: float, ellipsoid: earth.Ellipsoid) -> _Tuning:
    p, r, g = config.process, config.measurement, config.gates
    return _Tuning(
        walk=_WALK[aiding.walk],
        declination=aiding.declination,
        field_ref=aiding.field_reference(),
        every=max(1, int(round(1.0 / (config.update_rate * typical_dt)))),
        q_rate=np.concatenate(
            [
                np.zeros(3),
                np.full(3, p.accel**2),
                np.full(3, p.gyro**2),
                np.full(3, p.accel_bias_rw**2),
                np.full(3, p.gyro_bias_rw**2),
            ]
        ),
        held_accel=p.held_accel,
        held_gyro=p.held_gyro,
        r_zupt=r.zupt**2,
        r_zaru=r.zaru**2,
        r_baro=r.baro**2,
        r_heading=r.heading**2,
        alpha=config.tracker.alpha,
        beta=config.tracker.beta,
        gate=g.zupt,
        max_rejected=g.max_rejected,
        baro_gate=g.baro,
        field_tol=g.mag_field,
        dip_tol=g.mag_dip,
        earth_consts=earth_constants(ellipsoid),
    )


def _state(start: Start, sigma: InitialSigma) -> _State:
    p0 = (
        np.array(
            [sigma.pos] * 3
            + [sigma.vel] * 3
            + [sigma.tilt] * 2
            + [sigma.heading]
            + [sigma.accel_bias] * 3
            + [sigma.gyro_bias] * 3
        )
        ** 2
    )
    return _State(lla=start.lla, vel=start.vel_n, q=start.q_bn, b=np.concatenate([start.accel_bias, start.gyro_bias]), p0_diag=p0)


@boundary
def run_filter(
    imu: ImuSamples,
    start: Is[Start],
    static: ArrayLike,
    *,
    h_baro: ArrayLike | None = None,
    m_b: Vec3Series | None = None,
    aiding: Is[Aiding] = Aiding(),
    config: Is[FilterConfig] = FilterConfig(),
    ellipsoid: earth.Ellipsoid = earth.WGS84,
) -> FilterResult:
    """The paper's system: strapdown INS + ZUPT/ZARU Kalman filter + walking aids.

    Parameters
    ----------
    imu : ImuSamples
        One record of gyro (rad/s) and accelerometer (m/s^2) samples, shape (N, 3), with their intervals
        (regular or not; :func:`navlib.timing.sanitize` first for repeated or out-of-order timestamps) and
        the sensors' limits, which say what is screened as a fault (module docstring). The first sample must
        be valid. The static update rate uses the median interval.
    start : Start
        The INS state before the first sample.
    static : array_like of bool, shape (N,)
        Static flags, e.g. from :func:`navlib.filters.zupt.detect_static`.
    h_baro : array_like, shape (N,), optional
        Barometric height (m, same datum as ``start.lla[2]``), NaN between readings.
    m_b : array_like, shape (N, 3), optional
        Magnetometer (uT), NaN between readings.
    aiding : Aiding
        What aids the INS (default: ZUPT/ZARU and the paper's resets while walking).
    config : FilterConfig
        Noise, gates and rates.
    ellipsoid : Ellipsoid
        Earth model of the mechanisation.

    Returns
    -------
    FilterResult
        A ``RuntimeWarning`` is issued when ZUPT/ZARU is on and no static update was ever applied (check
        ``result.updated``).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import imu, trajectory
    >>> from navlib.filters import zupt_ins
    >>> traj = trajectory.static(1.0, 0.01, [0.6, 0.2, 50.0], [0.0, 0.0, 0.0])
    >>> w_ib_b, f_b = trajectory.ideal_imu(traj)
    >>> f_b += [0.05, 0.0, 0.0]                                       # an accelerometer bias (m/s^2)
    >>> start = zupt_ins.Start(traj.lla[0], traj.q_bn[0])
    >>> res = zupt_ins.run_filter(imu.ImuSamples(w_ib_b, f_b, 0.01), start, np.ones(100, bool))   # static throughout
    >>> np.round(res.nav.vel_n[-1], 3) + 0.0, res.zupt_updates          # ZUPTs hold the velocity near zero
    (array([0., 0., 0.]), 10)
    """
    s = robust.screen(imu, m_b)
    n, dts = imu.n, imu.dt
    if imu.w_ib_b.ndim != 2:
        raise ValueError(f"imu: expected one record of shape (N, 3), got {imu.w_ib_b.shape}")
    if s.typical_dt > s.max_dt:
        raise ValueError(
            f"imu: expected a median interval below limits.max_dt = {s.max_dt:g} s (longer intervals "
            f"are clock jumps, not integrated), got {s.typical_dt:g} s"
        )
    static = kernel_array(booleans(static, "static", shape=(n,)))
    h_baro = np.full(n, np.nan) if h_baro is None else as_array(h_baro, "h_baro", allow_nan=True, shape=(n,))
    samples, refused = _samples(s, static, kernel_array(h_baro), aiding.zupt)
    lla, vel, q, b, p_diag, counts, P = _filter_kernel(
        samples, _state(start, config.initial), _tuning(aiding, config, s.typical_dt, ellipsoid)
    )
    time = start.time + (dts[0] * np.arange(n + 1) if np.all(dts == dts[0]) else np.concatenate([[0.0], np.cumsum(dts)]))
    result = FilterResult(
        trajectory.Trajectory(time, lla, vel, q),
        b[:, :3],
        b[:, 3:],
        p_diag,
        P,
        zupt_updates=int(counts[_ZUPT]),
        baro_aidings=int(counts[_BARO_AIDED]),
        mag_aidings=int(counts[_MAG_AIDED]),
        faults=_faults(s, refused, counts),
    )
    if aiding.zupt and not result.updated:
        warnings.warn(
            "run_filter: no ZUPT/ZARU update was applied (no static interval detected); "
            "the output is a free INS with walking aids only",
            RuntimeWarning,
            stacklevel=2,
        )
    return result
