"""Bad input to every public navlib function fails loudly (project rule; issue 9, item 3).

Rule (navlib/__init__.py, "Bad input"): every public function rejects wrong
shapes, wrong dtypes, non-finite values, empty arrays and out-of-range values
with a ``ValueError`` (or ``TypeError`` for a wrong kind of value) naming the
argument and what was expected.

``CASES`` is a table of bad calls, one or more per public function or class
in the modules' ``__all__``. Each case names the argument the error must
name; "naming" means the message *starts* with the argument name, as in
navlib's ``"<arg>: expected ..."`` convention (``"<arg>[..., 1] (pitch): ..."``
for a part of an array argument). ``DTYPE_CASES`` adds, per argument, values
that are not real numbers: complex (numpy would silently drop the imaginary
part), object arrays, booleans (a mask where numbers belong) and numeric
strings (numpy would parse ``"1.5"``); navlib raises
``navlib._validate.InputTypeError``, which is a ``TypeError`` and a
``ValueError``. Cases where
navlib does not (yet) follow the rule are marked ``xfail(strict=True)`` with
the reason "navlib gap: ...", so the suite stays green, the gap stays
recorded, and fixing it turns the xfail into an XPASS that forces the mark
to be removed. ``test_every_public_callable_is_covered`` fails when a new
public function or class appears without an entry here.

Exceptions to the rule, by design (not tested as failures):

* ``attitude.wrap_pi`` / ``attitude.wrap_2pi`` and the ``units.*``
  converters propagate NaN: NaN marks sensor dropouts throughout navlib.
  (Their other bad inputs -- inf for the wraps, strings -- are in the table.)
  The unit converters also pass inf through, because ``full_scale = inf``
  ("no saturation") is a legitimate datasheet value.
* ``kalman.update`` skips NaN measurement components by design (its other
  bad inputs are in the table). Tested instead: an all-NaN ``z`` gives
  status ``kalman.NO_DATA``.
* ``repro.check`` / ``repro.check_range`` with a NaN *value* must fail the
  claim (``ClaimCheckFailed``), not raise ValueError.
* NaN accepted where a docstring says so: ``analysis.rmse`` ("NaN
  propagates: no silent dropping"), ``trajectory.Trajectory`` positions and
  velocities (GNSS outages are NaN) and ``repro.Check.value`` (a failed NaN
  check is recorded with its NaN value). Only their other bad inputs are in
  the table.
* Empty *batches* are valid for the elementwise (broadcasting) functions of
  attitude, earth, units, atmosphere, ``trajectory.smooth_ramp`` and
  ``plots.heading_deg``: a ``(0, 3)`` array of vectors is zero vectors, and
  the result is an empty array of the right shape (numpy semantics; tested
  by ``test_empty_batch_gives_empty_result``). Empty *series* (time axes,
  sensor records, Allan inputs, fault-injection inputs) are errors and are in
  the table.
* ``trajectory.Trajectory`` accepts NaN in ``q_bn`` as in ``lla`` and
  ``vel_n``: it also holds filter outputs, which mark unavailable epochs NaN.
* No bad input exists for ``repro.root``, ``repro.results`` and
  ``sensors.devices`` (they take no arguments) or for the exception class
  ``repro.ClaimCheckFailed``. The records ``sensors.ImuOutput`` and
  ``repro.Check`` are built by navlib from validated values.
"""
import importlib
import re

import numpy as np
import pytest

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from navlib import (  # noqa: E402
    alignment,
    analysis,
    atmosphere,
    attitude,
    calibration,
    earth,
    euler,
    faults,
    imu,
    io,
    kalman,
    montecarlo,
    pdr,
    plots,
    repro,
    robust,
    sensors,
    strapdown,
    timing,
    trajectory,
    units,
)
from navlib.filters import heading_fusion, mahony, observations, planar_ekf, quaternion_kf, zupt  # noqa: E402

IO_TABLE = __import__("pandas").DataFrame({"t": [0.0, 0.01, 0.02], "gx": [0.0] * 3, "gy": [0.0] * 3, "gz": [0.0] * 3})

MODULES = ["attitude", "earth", "units", "sensors", "atmosphere", "trajectory", "strapdown",
           "kalman", "analysis", "repro", "plots", "montecarlo", "faults", "timing", "alignment", "robust",
           "euler", "pdr", "imu", "filters.zupt", "filters.mahony", "filters.quaternion_kf", "filters.observations",
           "filters.planar_ekf", "filters.heading_fusion", "calibration", "io"]

NAN, INF = np.nan, np.inf
STR = "abc"                      # a string where numbers are expected
Q1 = [1.0, 0.0, 0.0, 0.0]        # identity quaternion
LLA0 = [0.6, 0.2, 50.0]          # lat, lon (rad), h (m)
W = np.zeros((10, 3))            # gyro samples (rad/s)
F = np.tile([0.0, 0.0, 9.8], (10, 1))  # accelerometer samples (m/s^2)
T10 = np.arange(10.0)            # a valid time axis (s)
TRAJ = trajectory.static(1.0, 0.1, LLA0, [0.0, 0.0, 0.0])
CALIB = dict(AC1=408, AC2=-72, AC3=-14383, AC4=32741, AC5=32757, AC6=23153,  # BMP180 datasheet example
             B1=6190, B2=4, MB=-32768, MC=-8711, MD=2868)


def rng():
    return np.random.default_rng(0)


def legacy_rng():
    """A random source that is not a numpy.random.Generator."""
    return np.random.RandomState(0)


def with_nan(a, index):
    a = np.array(a, dtype=float)
    a[index] = np.nan
    return a


def kf_predict(**kw):
    """``kalman.predict`` on a valid 2-state problem, with the arguments in ``kw`` replaced."""
    args = dict(x=[1.0, 2.0], P=np.eye(2), F=np.eye(2), Q=0.01 * np.eye(2))
    return kalman.predict(**{**args, **kw})


def kf_update(**kw):
    """``kalman.update`` on a valid 2-state, 2-row problem, with the arguments in ``kw`` replaced."""
    args = dict(x=[1.0, 2.0], P=np.eye(2), z=[1.5, 2.5], h=[1.0, 2.0], H=np.eye(2), R=np.eye(2),
                angle_mask=np.zeros(2, dtype=bool), gate=INF)
    return kalman.update(**{**args, **kw})


def nav_step(**kw):
    """``strapdown.nav_step`` on a valid state and sample, with the arguments in ``kw`` replaced."""
    args = dict(lla=np.array(LLA0), vel=np.zeros(3), q=np.array(Q1), w=np.zeros(3), f=[0.0, 0.0, 9.8], dt=0.01,
                earth_consts=strapdown.earth_constants())
    return strapdown.nav_step(**{**args, **kw})


def with_lat(lat, n=11):
    """A position history of ``n`` epochs whose latitudes are ``lat`` (rad)."""
    lla = np.tile(LLA0, (n, 1))
    lla[:, 0] = lat
    return lla


def _env_flag_with(name, value):
    """repro.env_flag with the environment variable set to ``value`` for the call."""
    import os
    old = os.environ.get(name)
    os.environ[name] = value
    try:
        return repro.env_flag(name)
    finally:
        os.environ.pop(name) if old is None else os.environ.__setitem__(name, old)


def axes2d():
    return plt.figure().add_subplot()


def axes3d():
    return plt.figure().add_subplot(projection="3d")



# Known violations of the rule: case id -> what navlib does instead. Each
# becomes an xfail(strict=True); remove the entry when navlib is fixed.
# (The 89 gaps this sweep first found were all fixed in navlib.)
KNOWN_GAPS: dict[str, str] = {}


def bad(target, arg, what, call, gap=None):
    """One table row: ``call()`` must raise ValueError naming ``arg``.

    ``target`` is "module.name" of the public function or class under test;
    a known violation (``gap`` or an entry of KNOWN_GAPS) is marked xfail.
    """
    case_id = f"{target}-{arg}-{what}"
    gap = gap or KNOWN_GAPS.get(case_id)
    marks = [pytest.mark.xfail(strict=True, reason=f"navlib gap: {gap}")] if gap else []
    return pytest.param(target, arg, call, id=case_id, marks=marks)


CASES = [
    # ------------------------------------------------------------------ attitude
    bad("attitude.wrap_pi", "angle", "inf", lambda: attitude.wrap_pi(INF)),
    bad("attitude.wrap_pi", "angle", "str", lambda: attitude.wrap_pi(STR)),
    bad("attitude.wrap_2pi", "angle", "inf", lambda: attitude.wrap_2pi([0.0, -INF])),
    bad("attitude.wrap_2pi", "angle", "str", lambda: attitude.wrap_2pi(STR)),
    bad("attitude.skew", "v", "shape2", lambda: attitude.skew([1.0, 2.0])),
    bad("attitude.skew", "v", "nan", lambda: attitude.skew([1.0, NAN, 0.0])),
    bad("attitude.skew", "v", "str", lambda: attitude.skew(STR)),
    bad("attitude.rot", "axis", "axis_w", lambda: attitude.rot("w", 0.1)),
    bad("attitude.rot", "angle", "nan", lambda: attitude.rot("x", NAN)),
    bad("attitude.rot", "angle", "inf", lambda: attitude.rot("z", [0.0, INF], deg=True)),
    bad("attitude.rot", "angle", "str", lambda: attitude.rot("y", STR)),
    bad("attitude.orthonormalize", "C", "shape3x2", lambda: attitude.orthonormalize(np.ones((3, 2)))),
    bad("attitude.orthonormalize", "C", "nan", lambda: attitude.orthonormalize(with_nan(np.eye(3), (0, 1)))),
    bad("attitude.euler_to_dcm", "hpr", "shape2", lambda: attitude.euler_to_dcm([0.1, 0.2])),
    bad("attitude.euler_to_dcm", "hpr", "nan", lambda: attitude.euler_to_dcm([NAN, 0.0, 0.0])),
    bad("attitude.euler_to_dcm", "hpr", "pitch91deg", lambda: attitude.euler_to_dcm([0, 91, 0], deg=True)),
    bad("attitude.euler_to_dcm", "hpr", "pitch2rad", lambda: attitude.euler_to_dcm([0.0, -2.0, 0.0])),
    bad("attitude.dcm_to_euler", "C_bn", "shape3x2", lambda: attitude.dcm_to_euler(np.ones((3, 2)))),
    bad("attitude.dcm_to_euler", "C_bn", "nan", lambda: attitude.dcm_to_euler(with_nan(np.eye(3), (2, 2)))),
    bad("attitude.dcm_to_euler", "C_bn", "not_rotation", lambda: attitude.dcm_to_euler(2 * np.eye(3))),
    bad("attitude.euler_to_quat", "hpr", "shape4", lambda: attitude.euler_to_quat([0.0, 0.0, 0.0, 0.0])),
    bad("attitude.euler_to_quat", "hpr", "inf", lambda: attitude.euler_to_quat([0.0, 0.0, INF])),
    bad("attitude.euler_to_quat", "hpr", "pitch100deg", lambda: attitude.euler_to_quat([0, 100, 0], deg=True)),
    bad("attitude.quat_to_euler", "q", "shape3", lambda: attitude.quat_to_euler([1.0, 0.0, 0.0])),
    bad("attitude.quat_to_euler", "q", "nan", lambda: attitude.quat_to_euler([NAN, 0.0, 0.0, 0.0])),
    bad("attitude.quat_to_euler", "q", "zero", lambda: attitude.quat_to_euler([0.0, 0.0, 0.0, 0.0])),
    bad("attitude.quat_to_dcm", "q", "shape3", lambda: attitude.quat_to_dcm(np.ones((5, 3)))),
    bad("attitude.quat_to_dcm", "q", "inf", lambda: attitude.quat_to_dcm([1.0, INF, 0.0, 0.0])),
    bad("attitude.quat_to_dcm", "q", "zero", lambda: attitude.quat_to_dcm(np.zeros(4))),
    bad("attitude.dcm_to_quat", "C_bn", "shape2x3", lambda: attitude.dcm_to_quat(np.ones((2, 3)))),
    bad("attitude.dcm_to_quat", "C_bn", "nan", lambda: attitude.dcm_to_quat(with_nan(np.eye(3), (1, 0)))),
    bad("attitude.dcm_to_quat", "C_bn", "reflection", lambda: attitude.dcm_to_quat(-np.eye(3))),
    bad("attitude.quat_mult", "p", "shape3", lambda: attitude.quat_mult([1.0, 0.0, 0.0], Q1)),
    bad("attitude.quat_mult", "q", "nan", lambda: attitude.quat_mult(Q1, [1.0, NAN, 0.0, 0.0])),
    bad("attitude.quat_conj", "q", "shape3", lambda: attitude.quat_conj([1.0, 0.0, 0.0])),
    bad("attitude.quat_conj", "q", "nan", lambda: attitude.quat_conj([NAN, 0.0, 0.0, 0.0])),
    bad("attitude.quat_normalize", "q", "shape5", lambda: attitude.quat_normalize(np.ones(5))),
    bad("attitude.quat_normalize", "q", "inf", lambda: attitude.quat_normalize([INF, 0.0, 0.0, 0.0])),
    bad("attitude.quat_normalize", "q", "zero", lambda: attitude.quat_normalize(np.zeros(4))),
    bad("attitude.ned_to_enu", "v", "shape2", lambda: attitude.ned_to_enu([1.0, 2.0])),
    bad("attitude.ned_to_enu", "v", "inf", lambda: attitude.ned_to_enu([1.0, INF, 0.0])),
    bad("attitude.ned_to_enu_quat", "q_ned", "zero", lambda: attitude.ned_to_enu_quat(np.zeros(4))),
    bad("attitude.ned_to_enu_quat", "q_ned", "shape3", lambda: attitude.ned_to_enu_quat([1.0, 0.0, 0.0])),
    bad("attitude.ypr_to_hpr", "ypr", "pitch2rad", lambda: attitude.ypr_to_hpr([0.0, 2.0, 0.0])),
    bad("attitude.hpr_to_ypr", "hpr", "nan", lambda: attitude.hpr_to_ypr([NAN, 0.0, 0.0])),
    bad("attitude.mount_matrix", "axes", "repeated", lambda: attitude.mount_matrix("x,x,z")),
    bad("attitude.mount_matrix", "axes", "mirror", lambda: attitude.mount_matrix("y,x,z")),
    bad("attitude.mount_matrix", "axes", "not_rotation", lambda: attitude.mount_matrix(2 * np.eye(3))),
    bad("attitude.mount_matrix", "axes", "shape", lambda: attitude.mount_matrix(np.eye(2))),
    bad("attitude.quat_rotate", "q", "shape3", lambda: attitude.quat_rotate([1.0, 0.0, 0.0], [1.0, 0.0, 0.0])),
    bad("attitude.quat_rotate", "v_b", "shape2", lambda: attitude.quat_rotate(Q1, [1.0, 0.0])),
    bad("attitude.quat_rotate", "v_b", "nan", lambda: attitude.quat_rotate(Q1, [1.0, NAN, 0.0])),
    bad("attitude.rotvec_to_dcm", "rv", "shape4", lambda: attitude.rotvec_to_dcm(np.zeros(4))),
    bad("attitude.rotvec_to_dcm", "rv", "nan", lambda: attitude.rotvec_to_dcm([0.0, 0.0, NAN])),
    bad("attitude.dcm_to_rotvec", "C", "shape3x2", lambda: attitude.dcm_to_rotvec(np.ones((3, 2)))),
    bad("attitude.dcm_to_rotvec", "C", "nan", lambda: attitude.dcm_to_rotvec(with_nan(np.eye(3), (0, 0)))),
    bad("attitude.dcm_to_rotvec", "C", "not_rotation", lambda: attitude.dcm_to_rotvec(np.ones((3, 3)))),
    bad("attitude.rotvec_to_quat", "rv", "shape2", lambda: attitude.rotvec_to_quat([0.1, 0.2])),
    bad("attitude.rotvec_to_quat", "rv", "inf", lambda: attitude.rotvec_to_quat([INF, 0.0, 0.0])),
    bad("attitude.quat_to_rotvec", "q", "shape3", lambda: attitude.quat_to_rotvec([1.0, 0.0, 0.0])),
    bad("attitude.quat_to_rotvec", "q", "nan", lambda: attitude.quat_to_rotvec([1.0, 0.0, NAN, 0.0])),

    # --------------------------------------------------------------------- earth
    bad("earth.Ellipsoid", "a", "negative", lambda: earth.Ellipsoid("bad", -6378137.0, 1 / 298.257, 3.986e14, 7.29e-5)),
    bad("earth.Ellipsoid", "f", "nan", lambda: earth.Ellipsoid("bad", 6378137.0, NAN, 3.986e14, 7.29e-5)),
    bad("earth.earth_rate_n", "lat", "lat91deg", lambda: earth.earth_rate_n(91.0, deg=True)),
    bad("earth.earth_rate_n", "lat", "lat2rad", lambda: earth.earth_rate_n(2.0)),
    bad("earth.earth_rate_n", "lat", "nan", lambda: earth.earth_rate_n([0.1, NAN])),
    bad("earth.earth_rate_n", "lat", "str", lambda: earth.earth_rate_n(STR)),
    bad("earth.gravity", "lat", "lat91deg", lambda: earth.gravity(-91.0, deg=True)),
    bad("earth.gravity", "lat", "str", lambda: earth.gravity(STR)),
    bad("earth.gravity", "h", "nan", lambda: earth.gravity(0.5, NAN)),
    bad("earth.gravity", "h", "h_1e7", lambda: earth.gravity(0.5, 1e7)),
    bad("earth.gravity_n", "lat", "lat2rad", lambda: earth.gravity_n(2.0)),
    bad("earth.gravity_n", "h", "inf", lambda: earth.gravity_n(0.5, INF)),
    bad("earth.radii", "lat", "lat-91deg", lambda: earth.radii(-91.0, deg=True)),
    bad("earth.radii", "lat", "nan", lambda: earth.radii(NAN)),
    bad("earth.transport_rate_n", "lat", "lat2rad", lambda: earth.transport_rate_n(2.0, 0.0, [1.0, 0.0, 0.0])),
    bad("earth.transport_rate_n", "h", "nan", lambda: earth.transport_rate_n(0.5, NAN, [1.0, 0.0, 0.0])),
    bad("earth.transport_rate_n", "vel_n", "shape2", lambda: earth.transport_rate_n(0.5, 0.0, [1.0, 0.0])),
    bad("earth.transport_rate_n", "vel_n", "inf", lambda: earth.transport_rate_n(0.5, 0.0, [INF, 0.0, 0.0])),
    bad("earth.magnetic_field", "lat", "lat91deg", lambda: earth.magnetic_field(91.0, 10.0)),
    bad("earth.magnetic_field", "lat", "lat2rad", lambda: earth.magnetic_field(2.0, 0.1, deg=False)),
    bad("earth.magnetic_field", "lon", "nan", lambda: earth.magnetic_field(45.0, NAN)),
    bad("earth.magnetic_field", "h", "nan", lambda: earth.magnetic_field(45.0, 10.0, NAN)),
    bad("earth.magnetic_field", "year", "year1990", lambda: earth.magnetic_field(45.0, 10.0, year=1990.0)),
    bad("earth.magnetic_field", "year", "nan", lambda: earth.magnetic_field(45.0, 10.0, year=NAN)),
    bad("earth.magnetic_field", "year", "str", lambda: earth.magnetic_field(45.0, 10.0, year=STR)),
    bad("earth.field_from_angles", "inclination", "incl91deg", lambda: earth.field_from_angles(0.0, 91.0, 50.0)),
    bad("earth.field_from_angles", "declination", "nan", lambda: earth.field_from_angles(NAN, 60.0, 50.0)),
    bad("earth.field_from_angles", "intensity", "inf", lambda: earth.field_from_angles(0.0, 60.0, INF)),
    bad("earth.field_from_angles", "intensity", "negative", lambda: earth.field_from_angles(0.0, 60.0, -50.0)),
    bad("earth.field_angles", "B_n", "shape2", lambda: earth.field_angles([20.0, -40.0])),
    bad("earth.field_angles", "B_n", "nan", lambda: earth.field_angles([NAN, 20.0, -40.0])),

    # ------------------------------------------------------------------- units
    bad("units.to_si", "unit", "unknown_unit", lambda: units.to_si(1.0, "furlong")),
    bad("units.to_si", "unit", "unit_not_str", lambda: units.to_si(1.0, 5)),
    bad("units.to_si", "value", "str", lambda: units.to_si(STR, "deg")),
    # the one-argument converters are added below the table (wrong type only)

    # ----------------------------------------------------------------- sensors
    bad("sensors.TriadErrors", "noise_density", "negative", lambda: sensors.TriadErrors(noise_density=-1.0)),
    bad("sensors.TriadErrors", "bias", "nan", lambda: sensors.TriadErrors(bias=NAN)),
    bad("sensors.TriadErrors", "bias", "inf", lambda: sensors.TriadErrors(bias=INF)),
    bad("sensors.TriadErrors", "scale_factor", "str", lambda: sensors.TriadErrors(scale_factor=STR)),
    bad("sensors.TriadErrors", "correlation_time", "zero", lambda: sensors.TriadErrors(correlation_time=0.0)),
    bad("sensors.TriadErrors", "full_scale", "zero", lambda: sensors.TriadErrors(full_scale=0.0)),
    bad("sensors.ImuModel", "gyro", "str", lambda: sensors.ImuModel(gyro=STR)),
    bad("sensors.simulate_imu", "w_ib_b", "shape2", lambda: sensors.simulate_imu(W[:, :2], F, 0.01, sensors.ImuModel(), rng())),
    bad("sensors.simulate_imu", "w_ib_b", "empty",
        lambda: sensors.simulate_imu(np.zeros((0, 3)), np.zeros((0, 3)), 0.01, sensors.ImuModel(), rng())),
    bad("sensors.simulate_imu", "f_b", "nan", lambda: sensors.simulate_imu(W, with_nan(F, (3, 2)), 0.01, sensors.ImuModel(), rng())),
    bad("sensors.simulate_imu", "f_b", "shape_mismatch", lambda: sensors.simulate_imu(W, F[:5], 0.01, sensors.ImuModel(), rng())),
    bad("sensors.simulate_imu", "dt", "zero", lambda: sensors.simulate_imu(W, F, 0.0, sensors.ImuModel(), rng())),
    bad("sensors.simulate_imu", "dt", "nan", lambda: sensors.simulate_imu(W, F, NAN, sensors.ImuModel(), rng())),
    bad("sensors.simulate_imu", "model", "str", lambda: sensors.simulate_imu(W, F, 0.01, STR, rng())),
    bad("sensors.simulate_imu", "rng", "legacy_rng", lambda: sensors.simulate_imu(W, F, 0.01, sensors.ImuModel(), legacy_rng())),
    bad("sensors.simulate_imu", "rng", "int", lambda: sensors.simulate_imu(W, F, 0.01, sensors.ImuModel(), 42)),
    bad("sensors.simulate_imu", "n_trials", "zero", lambda: sensors.simulate_imu(W, F, 0.01, sensors.ImuModel(), rng(), n_trials=0)),
    bad("sensors.simulate_imu", "n_trials", "str", lambda: sensors.simulate_imu(W, F, 0.01, sensors.ImuModel(), rng(), n_trials=STR)),
    bad("sensors.imu_model", "device", "unknown", lambda: sensors.imu_model("NO-SUCH-IMU")),
    bad("sensors.imu_model", "device", "no_imu_preset", lambda: sensors.imu_model("BMP180")),
    bad("sensors.preset", "device", "unknown", lambda: sensors.preset("NO-SUCH-DEVICE")),
    bad("sensors.preset", "device", "list", lambda: sensors.preset(["MTi-100"])),
    bad("sensors.MagnetometerModel", "noise", "negative", lambda: sensors.MagnetometerModel(noise=-1.0)),
    bad("sensors.MagnetometerModel", "hard_iron", "nan", lambda: sensors.MagnetometerModel(hard_iron=NAN)),
    bad("sensors.simulate_magnetometer", "q_bn", "shape3",
        lambda: sensors.simulate_magnetometer(np.ones((10, 3)), [0.0, 20.0, -40.0], sensors.MagnetometerModel(), rng())),
    bad("sensors.simulate_magnetometer", "q_bn", "empty",
        lambda: sensors.simulate_magnetometer(np.zeros((0, 4)), [0.0, 20.0, -40.0], sensors.MagnetometerModel(), rng())),
    bad("sensors.simulate_magnetometer", "q_bn", "zero_quat",
        lambda: sensors.simulate_magnetometer(np.zeros((10, 4)), [0.0, 20.0, -40.0], sensors.MagnetometerModel(), rng())),
    bad("sensors.simulate_magnetometer", "B_n", "shape2",
        lambda: sensors.simulate_magnetometer(np.tile(Q1, (10, 1)), [20.0, -40.0], sensors.MagnetometerModel(), rng())),
    bad("sensors.simulate_magnetometer", "B_n", "nan",
        lambda: sensors.simulate_magnetometer(np.tile(Q1, (10, 1)), [NAN, 20.0, -40.0], sensors.MagnetometerModel(), rng())),
    bad("sensors.simulate_magnetometer", "disturbance_n", "inf",
        lambda: sensors.simulate_magnetometer(np.tile(Q1, (10, 1)), [0.0, 20.0, -40.0], sensors.MagnetometerModel(), rng(),
                                              disturbance_n=np.full((10, 3), INF))),
    bad("sensors.simulate_magnetometer", "model", "str",
        lambda: sensors.simulate_magnetometer(np.tile(Q1, (10, 1)), [0.0, 20.0, -40.0], STR, rng())),
    bad("sensors.simulate_magnetometer", "rng", "legacy_rng",
        lambda: sensors.simulate_magnetometer(np.tile(Q1, (10, 1)), [0.0, 20.0, -40.0], sensors.MagnetometerModel(), legacy_rng())),
    bad("sensors.magnetic_disturbances", "time", "one_sample", lambda: sensors.magnetic_disturbances([0.0], rng(), 0.1)),
    bad("sensors.magnetic_disturbances", "time", "decreasing", lambda: sensors.magnetic_disturbances(T10[::-1], rng(), 0.1)),
    bad("sensors.magnetic_disturbances", "time", "nan", lambda: sensors.magnetic_disturbances(with_nan(T10, 3), rng(), 0.1)),
    bad("sensors.magnetic_disturbances", "rate", "negative", lambda: sensors.magnetic_disturbances(T10, rng(), -0.1)),
    bad("sensors.magnetic_disturbances", "rate", "nan", lambda: sensors.magnetic_disturbances(T10, rng(), NAN)),
    bad("sensors.magnetic_disturbances", "rng", "legacy_rng", lambda: sensors.magnetic_disturbances(T10, legacy_rng(), 0.1)),
    bad("sensors.magnetic_disturbances", "duration", "negative",
        lambda: sensors.magnetic_disturbances(T10, rng(), 1.0, duration=(-5.0, -2.0))),
    bad("sensors.magnetic_disturbances", "amplitude", "nan",
        lambda: sensors.magnetic_disturbances(T10, rng(), 1.0, amplitude=(NAN, NAN))),
    bad("sensors.BarometerModel", "noise", "negative", lambda: sensors.BarometerModel(noise=-1.0)),
    bad("sensors.BarometerModel", "bias", "nan", lambda: sensors.BarometerModel(bias=NAN)),
    bad("sensors.simulate_barometer", "h", "nan", lambda: sensors.simulate_barometer(with_nan(T10, 2), T10, sensors.BarometerModel(), rng())),
    bad("sensors.simulate_barometer", "h", "length_mismatch", lambda: sensors.simulate_barometer(T10[:5], T10, sensors.BarometerModel(), rng())),
    bad("sensors.simulate_barometer", "h", "h_20km", lambda: sensors.simulate_barometer(T10 + 20e3, T10, sensors.BarometerModel(), rng())),
    bad("sensors.simulate_barometer", "time", "one_sample", lambda: sensors.simulate_barometer([0.0], [0.0], sensors.BarometerModel(), rng())),
    bad("sensors.simulate_barometer", "p0", "negative", lambda: sensors.simulate_barometer(T10, T10, sensors.BarometerModel(), rng(), p0=-1.0)),
    bad("sensors.simulate_barometer", "p0", "nan", lambda: sensors.simulate_barometer(T10, T10, sensors.BarometerModel(), rng(), p0=NAN)),
    bad("sensors.simulate_barometer", "model", "str", lambda: sensors.simulate_barometer(T10, T10, STR, rng())),
    bad("sensors.simulate_barometer", "rng", "legacy_rng", lambda: sensors.simulate_barometer(T10, T10, sensors.BarometerModel(), legacy_rng())),
    bad("sensors.outage_mask", "time", "nan", lambda: sensors.outage_mask(with_nan(T10, 0), [(2.0, 3.0)])),
    bad("sensors.outage_mask", "time", "empty", lambda: sensors.outage_mask([], [(2.0, 3.0)])),
    bad("sensors.outage_mask", "outages", "end_before_start", lambda: sensors.outage_mask(T10, [(5.0, 1.0)])),
    bad("sensors.outage_mask", "outages", "not_pairs", lambda: sensors.outage_mask(T10, [(5.0,)])),
    bad("sensors.outage_mask", "outages", "nan", lambda: sensors.outage_mask(T10, [(NAN, 5.0)])),
    bad("sensors.simulate_gnss_position", "lla", "shape2", lambda: sensors.simulate_gnss_position(np.zeros((10, 2)), rng(), 3.0)),
    bad("sensors.simulate_gnss_position", "lla", "empty", lambda: sensors.simulate_gnss_position(np.zeros((0, 3)), rng(), 3.0)),
    bad("sensors.simulate_gnss_position", "lla", "nan", lambda: sensors.simulate_gnss_position(with_nan(with_lat(0.6), (1, 2)), rng(), 3.0)),
    bad("sensors.simulate_gnss_position", "lla", "lat2rad", lambda: sensors.simulate_gnss_position(with_lat(2.0), rng(), 3.0)),
    bad("sensors.simulate_gnss_position", "sigma_horizontal", "negative", lambda: sensors.simulate_gnss_position(with_lat(0.6), rng(), -3.0)),
    bad("sensors.simulate_gnss_position", "sigma_vertical", "nan", lambda: sensors.simulate_gnss_position(with_lat(0.6), rng(), 3.0, NAN)),
    bad("sensors.simulate_gnss_position", "rng", "legacy_rng", lambda: sensors.simulate_gnss_position(with_lat(0.6), legacy_rng(), 3.0)),
    bad("sensors.simulate_gnss_position", "valid", "length_mismatch",
        lambda: sensors.simulate_gnss_position(with_lat(0.6), rng(), 3.0, valid=np.ones(4, dtype=bool))),
    bad("sensors.simulate_heading", "heading", "nan", lambda: sensors.simulate_heading(with_nan(T10, 4), rng(), 0.01)),
    bad("sensors.simulate_heading", "heading", "empty", lambda: sensors.simulate_heading([], rng(), 0.01)),
    bad("sensors.simulate_heading", "sigma", "negative", lambda: sensors.simulate_heading(T10, rng(), -0.01)),
    bad("sensors.simulate_heading", "sigma", "inf", lambda: sensors.simulate_heading(T10, rng(), INF)),
    bad("sensors.simulate_heading", "valid", "length_mismatch", lambda: sensors.simulate_heading(T10, rng(), 0.01, valid=[True] * 3)),
    bad("sensors.simulate_heading", "rng", "legacy_rng", lambda: sensors.simulate_heading(T10, legacy_rng(), 0.01)),
    bad("sensors.gauss_markov", "shape", "1d", lambda: sensors.gauss_markov((10,), 0.1, 1.0, 10.0, rng())),
    bad("sensors.gauss_markov", "dt", "zero", lambda: sensors.gauss_markov((10, 3), 0.0, 1.0, 10.0, rng())),
    bad("sensors.gauss_markov", "correlation_time", "negative", lambda: sensors.gauss_markov((10, 3), 0.1, 1.0, -10.0, rng())),
    bad("sensors.gauss_markov", "sigma", "negative", lambda: sensors.gauss_markov((10, 3), 0.1, -1.0, 10.0, rng())),
    bad("sensors.gauss_markov", "sigma", "nan", lambda: sensors.gauss_markov((10, 3), 0.1, NAN, 10.0, rng())),
    bad("sensors.gauss_markov", "rng", "legacy_rng", lambda: sensors.gauss_markov((10, 3), 0.1, 1.0, 10.0, legacy_rng())),

    # -------------------------------------------------------------- atmosphere
    bad("atmosphere.isa_altitude", "p", "nan", lambda: atmosphere.isa_altitude(NAN)),
    bad("atmosphere.isa_altitude", "p", "negative", lambda: atmosphere.isa_altitude(-100.0)),
    bad("atmosphere.isa_altitude", "p", "above_troposphere", lambda: atmosphere.isa_altitude(1000.0)),
    bad("atmosphere.isa_altitude", "p", "str", lambda: atmosphere.isa_altitude(STR)),
    bad("atmosphere.isa_altitude", "p0", "zero", lambda: atmosphere.isa_altitude(9e4, 0.0)),
    bad("atmosphere.isa_pressure", "h", "h_20km", lambda: atmosphere.isa_pressure(20e3)),
    bad("atmosphere.isa_pressure", "h", "nan", lambda: atmosphere.isa_pressure(NAN)),
    bad("atmosphere.isa_pressure", "p0", "negative", lambda: atmosphere.isa_pressure(100.0, -1.0)),
    bad("atmosphere.bmp180_altitude", "p", "zero", lambda: atmosphere.bmp180_altitude(0.0)),
    bad("atmosphere.bmp180_altitude", "p0", "inf", lambda: atmosphere.bmp180_altitude(9e4, INF)),
    bad("atmosphere.bmp180_pressure", "h", "nan", lambda: atmosphere.bmp180_pressure(NAN)),
    bad("atmosphere.bmp180_pressure", "h", "h_50km", lambda: atmosphere.bmp180_pressure(50e3)),
    bad("atmosphere.bmp180_pressure", "p0", "nan", lambda: atmosphere.bmp180_pressure(100.0, NAN)),
    bad("atmosphere.hypsometric_height", "p", "negative", lambda: atmosphere.hypsometric_height(-1.0, 1e5, 288.0)),
    bad("atmosphere.hypsometric_height", "p_ref", "nan", lambda: atmosphere.hypsometric_height(9e4, NAN, 288.0)),
    bad("atmosphere.hypsometric_height", "temperature", "400K", lambda: atmosphere.hypsometric_height(9e4, 1e5, 400.0)),
    bad("atmosphere.hypsometric_height", "temperature", "nan", lambda: atmosphere.hypsometric_height(9e4, 1e5, NAN)),
    bad("atmosphere.bmp180_compensate", "oss", "oss4", lambda: atmosphere.bmp180_compensate(27898, 23843, CALIB, oss=4)),
    bad("atmosphere.bmp180_compensate", "calib", "missing_key",
        lambda: atmosphere.bmp180_compensate(27898, 23843, {k: v for k, v in CALIB.items() if k != "MD"})),
    bad("atmosphere.bmp180_compensate", "calib", "nan_coefficient",
        lambda: atmosphere.bmp180_compensate(27898, 23843, {**CALIB, "AC1": NAN})),
    bad("atmosphere.bmp180_compensate", "UT", "nan", lambda: atmosphere.bmp180_compensate(NAN, 23843, CALIB)),
    bad("atmosphere.bmp180_compensate", "UP", "str", lambda: atmosphere.bmp180_compensate(27898, STR, CALIB)),

    # -------------------------------------------------------------- trajectory
    bad("trajectory.Trajectory", "time", "one_sample", lambda: trajectory.Trajectory([0.0], [LLA0], [[0, 0, 0]], [Q1])),
    bad("trajectory.Trajectory", "lla", "shape2", lambda: trajectory.Trajectory(TRAJ.time, TRAJ.lla[:, :2], TRAJ.vel_n, TRAJ.q_bn)),
    bad("trajectory.Trajectory", "q_bn", "epoch_mismatch", lambda: trajectory.Trajectory(TRAJ.time, TRAJ.lla, TRAJ.vel_n, TRAJ.q_bn[:5])),
    bad("trajectory.Trajectory", "vel_n", "inf", lambda: trajectory.Trajectory(TRAJ.time, TRAJ.lla, TRAJ.vel_n + INF, TRAJ.q_bn)),
    bad("trajectory.Trajectory", "lla", "lat2rad", lambda: trajectory.Trajectory(TRAJ.time, with_lat(2.0), TRAJ.vel_n, TRAJ.q_bn)),
    bad("trajectory.Trajectory", "faults", "dict", lambda: trajectory.Trajectory(TRAJ.time, TRAJ.lla, TRAJ.vel_n, TRAJ.q_bn, {})),
    bad("trajectory.Segment", "duration", "negative", lambda: trajectory.Segment(duration=-1.0)),
    bad("trajectory.Segment", "speed", "nan", lambda: trajectory.Segment(duration=1.0, speed=NAN)),
    bad("trajectory.Segment", "pitch", "pitch2rad", lambda: trajectory.Segment(duration=1.0, pitch=2.0)),
    bad("trajectory.static", "duration", "zero", lambda: trajectory.static(0.0, 0.1, LLA0, [0, 0, 0])),
    bad("trajectory.static", "duration", "str", lambda: trajectory.static(STR, 0.1, LLA0, [0, 0, 0])),
    bad("trajectory.static", "dt", "negative", lambda: trajectory.static(1.0, -0.1, LLA0, [0, 0, 0])),
    bad("trajectory.static", "dt", "nan", lambda: trajectory.static(1.0, NAN, LLA0, [0, 0, 0])),
    bad("trajectory.static", "lla0", "shape2", lambda: trajectory.static(1.0, 0.1, LLA0[:2], [0, 0, 0])),
    bad("trajectory.static", "lla0", "lat2rad", lambda: trajectory.static(1.0, 0.1, [2.0, 0.0, 0.0], [0, 0, 0])),
    bad("trajectory.static", "hpr", "shape2", lambda: trajectory.static(1.0, 0.1, LLA0, [0, 0])),
    bad("trajectory.static", "hpr", "pitch2rad", lambda: trajectory.static(1.0, 0.1, LLA0, [0.0, 2.0, 0.0])),
    bad("trajectory.from_profiles", "time", "non_uniform",
        lambda: trajectory.from_profiles(T10 ** 2, LLA0, np.zeros((10, 3)), np.zeros((10, 3)))),
    bad("trajectory.from_profiles", "time", "empty",
        lambda: trajectory.from_profiles([], LLA0, np.zeros((0, 3)), np.zeros((0, 3)))),
    bad("trajectory.from_profiles", "hpr", "epoch_mismatch",
        lambda: trajectory.from_profiles(T10, LLA0, np.zeros((9, 3)), np.zeros((10, 3)))),
    bad("trajectory.from_profiles", "hpr", "nan",
        lambda: trajectory.from_profiles(T10, LLA0, with_nan(np.zeros((10, 3)), (4, 0)), np.zeros((10, 3)))),
    bad("trajectory.from_profiles", "hpr", "pitch2rad",
        lambda: trajectory.from_profiles(T10, LLA0, np.tile([0.0, 2.0, 0.0], (10, 1)), np.zeros((10, 3)))),
    bad("trajectory.from_profiles", "vel_n", "nan",
        lambda: trajectory.from_profiles(T10, LLA0, np.zeros((10, 3)), with_nan(np.zeros((10, 3)), (4, 1)))),
    bad("trajectory.from_profiles", "lla0", "lat91deg_in_rad_call",
        lambda: trajectory.from_profiles(T10, [np.deg2rad(91.0), 0.0, 0.0], np.zeros((10, 3)), np.zeros((10, 3)))),
    bad("trajectory.reciprocating_rotation", "duration", "negative",
        lambda: trajectory.reciprocating_rotation(-10.0, 0.1, LLA0, [0, 0, 0], [0, 0, 1], np.pi / 2, 4.0)),
    bad("trajectory.reciprocating_rotation", "axis_b", "not_unit",
        lambda: trajectory.reciprocating_rotation(10.0, 0.1, LLA0, [0, 0, 0], [0, 0, 2], np.pi / 2, 4.0)),
    bad("trajectory.reciprocating_rotation", "axis_b", "shape2",
        lambda: trajectory.reciprocating_rotation(10.0, 0.1, LLA0, [0, 0, 0], [0, 1], np.pi / 2, 4.0)),
    bad("trajectory.reciprocating_rotation", "period", "zero",
        lambda: trajectory.reciprocating_rotation(10.0, 0.1, LLA0, [0, 0, 0], [0, 0, 1], np.pi / 2, 0.0)),
    bad("trajectory.reciprocating_rotation", "rotation_time", "longer_than_period",
        lambda: trajectory.reciprocating_rotation(10.0, 0.1, LLA0, [0, 0, 0], [0, 0, 1], np.pi / 2, 4.0, 5.0)),
    bad("trajectory.reciprocating_rotation", "hpr0", "pitch2rad",
        lambda: trajectory.reciprocating_rotation(10.0, 0.1, LLA0, [0, 2.0, 0], [0, 0, 1], np.pi / 2, 4.0)),
    bad("trajectory.reciprocating_rotation", "amplitude", "nan",
        lambda: trajectory.reciprocating_rotation(10.0, 0.1, LLA0, [0, 0, 0], [0, 0, 1], NAN, 4.0)),
    bad("trajectory.reciprocating_rotation", "amplitude", "str",
        lambda: trajectory.reciprocating_rotation(10.0, 0.1, LLA0, [0, 0, 0], [0, 0, 1], STR, 4.0)),
    bad("trajectory.vehicle", "segments", "empty", lambda: trajectory.vehicle([], 0.1, LLA0, 0.0)),
    bad("trajectory.vehicle", "segments", "not_segments", lambda: trajectory.vehicle([(10.0, 5.0)], 0.1, LLA0, 0.0)),
    bad("trajectory.vehicle", "dt", "zero", lambda: trajectory.vehicle([trajectory.Segment(2.0, speed=5.0)], 0.0, LLA0, 0.0)),
    bad("trajectory.vehicle", "lla0", "lat2rad",
        lambda: trajectory.vehicle([trajectory.Segment(2.0, speed=5.0)], 0.1, [2.0, 0.0, 0.0], 0.0)),
    bad("trajectory.vehicle", "heading0", "nan", lambda: trajectory.vehicle([trajectory.Segment(2.0, speed=5.0)], 0.1, LLA0, NAN)),
    bad("trajectory.ideal_imu", "traj", "none", lambda: trajectory.ideal_imu(None)),
    bad("trajectory.ideal_imu", "traj", "nan_position",
        lambda: trajectory.ideal_imu(trajectory.Trajectory(TRAJ.time, with_nan(TRAJ.lla, (3, 0)), TRAJ.vel_n, TRAJ.q_bn))),
    bad("trajectory.smooth_ramp", "x", "nan", lambda: trajectory.smooth_ramp([0.2, NAN])),
    bad("trajectory.smooth_ramp", "x", "str", lambda: trajectory.smooth_ramp(STR)),

    # --------------------------------------------------------------- strapdown
    bad("strapdown.integrate_attitude", "q0", "shape3", lambda: strapdown.integrate_attitude([1.0, 0.0, 0.0], W, 0.01)),
    bad("strapdown.integrate_attitude", "q0", "zero", lambda: strapdown.integrate_attitude(np.zeros(4), W, 0.01)),
    bad("strapdown.integrate_attitude", "w_ib_b", "shape2", lambda: strapdown.integrate_attitude(Q1, W[:, :2], 0.01)),
    bad("strapdown.integrate_attitude", "w_ib_b", "nan", lambda: strapdown.integrate_attitude(Q1, with_nan(W, (5, 1)), 0.01)),
    bad("strapdown.integrate_attitude", "w_ib_b", "empty", lambda: strapdown.integrate_attitude(Q1, np.zeros((0, 3)), 0.01)),
    bad("strapdown.integrate_attitude", "dt", "zero", lambda: strapdown.integrate_attitude(Q1, W, 0.0)),
    bad("strapdown.integrate_attitude", "dt", "str", lambda: strapdown.integrate_attitude(Q1, W, STR)),
    bad("strapdown.integrate_attitude", "w_in_n", "shape2", lambda: strapdown.integrate_attitude(Q1, W, 0.01, [0.0, 1e-5])),
    bad("strapdown.integrate_attitude", "w_in_n", "nan", lambda: strapdown.integrate_attitude(Q1, W, 0.01, [0.0, NAN, 0.0])),
    bad("strapdown.integrate", "lla0", "lat2rad", lambda: strapdown.integrate([2.0, 0.0, 0.0], [0, 0, 0], Q1, W, F, 0.01)),
    bad("strapdown.integrate", "lla0", "pole", lambda: strapdown.integrate([np.deg2rad(89.95), 0.0, 0.0], [0, 0, 0], Q1, W, F, 0.01)),
    bad("strapdown.integrate", "lla0", "nan", lambda: strapdown.integrate([0.6, NAN, 0.0], [0, 0, 0], Q1, W, F, 0.01)),
    bad("strapdown.integrate", "vel0", "nan", lambda: strapdown.integrate(LLA0, [NAN, 0, 0], Q1, W, F, 0.01)),
    bad("strapdown.integrate", "vel0", "shape2", lambda: strapdown.integrate(LLA0, [0, 0], Q1, W, F, 0.01)),
    bad("strapdown.integrate", "q0", "shape3", lambda: strapdown.integrate(LLA0, [0, 0, 0], [1.0, 0, 0], W, F, 0.01)),
    bad("strapdown.integrate", "w_ib_b", "nan", lambda: strapdown.integrate(LLA0, [0, 0, 0], Q1, with_nan(W, (2, 2)), F, 0.01)),
    bad("strapdown.integrate", "w_ib_b", "empty", lambda: strapdown.integrate(LLA0, [0, 0, 0], Q1, np.zeros((0, 3)), np.zeros((0, 3)), 0.01)),
    bad("strapdown.integrate", "f_b", "shape2", lambda: strapdown.integrate(LLA0, [0, 0, 0], Q1, W, F[:, :2], 0.01)),
    bad("strapdown.integrate", "f_b", "epoch_mismatch", lambda: strapdown.integrate(LLA0, [0, 0, 0], Q1, W, F[:7], 0.01)),
    bad("strapdown.integrate", "dt", "negative", lambda: strapdown.integrate(LLA0, [0, 0, 0], Q1, W, F, -0.01)),
    bad("strapdown.integrate", "t0", "nan", lambda: strapdown.integrate(LLA0, [0, 0, 0], Q1, W, F, 0.01, t0=NAN)),
    bad("strapdown.error_model", "lat", "lat2rad", lambda: strapdown.error_model(2.0, 0.0, [0, 0, 0], [0, 0, 9.8])),
    bad("strapdown.error_model", "lat", "nan", lambda: strapdown.error_model(NAN, 0.0, [0, 0, 0], [0, 0, 9.8])),
    bad("strapdown.error_model", "h", "nan", lambda: strapdown.error_model(0.6, NAN, [0, 0, 0], [0, 0, 9.8])),
    bad("strapdown.error_model", "h", "str", lambda: strapdown.error_model(0.6, STR, [0, 0, 0], [0, 0, 9.8])),
    bad("strapdown.error_model", "vel_n", "shape2", lambda: strapdown.error_model(0.6, 0.0, [0, 0], [0, 0, 9.8])),
    bad("strapdown.error_model", "f_n", "inf", lambda: strapdown.error_model(0.6, 0.0, [0, 0, 0], [0, 0, INF])),
    bad("strapdown.error_input", "C_bn", "shape3x2", lambda: strapdown.error_input(np.ones((3, 2)))),
    bad("strapdown.error_input", "C_bn", "nan", lambda: strapdown.error_input(with_nan(np.eye(3), (1, 1)))),
    bad("strapdown.nav_step", "lla", "empty", lambda: nav_step(lla=np.zeros(0))),
    bad("strapdown.nav_step", "lla", "shape2", lambda: nav_step(lla=[0.6, 0.2])),
    bad("strapdown.nav_step", "lla", "lat45rad", lambda: nav_step(lla=[45.0, 0.2, 50.0])),
    bad("strapdown.nav_step", "lla", "nan", lambda: nav_step(lla=[0.6, NAN, 50.0])),
    bad("strapdown.nav_step", "lla", "none", lambda: nav_step(lla=None)),
    bad("strapdown.nav_step", "vel", "empty", lambda: nav_step(vel=[])),
    bad("strapdown.nav_step", "vel", "inf", lambda: nav_step(vel=[INF, 0.0, 0.0])),
    bad("strapdown.nav_step", "vel", "str", lambda: nav_step(vel=STR)),
    bad("strapdown.nav_step", "q", "shape3", lambda: nav_step(q=[1.0, 0.0, 0.0])),
    bad("strapdown.nav_step", "q", "zero", lambda: nav_step(q=np.zeros(4))),
    bad("strapdown.nav_step", "q", "none", lambda: nav_step(q=None)),
    bad("strapdown.nav_step", "w", "empty", lambda: nav_step(w=np.zeros(0))),
    bad("strapdown.nav_step", "w", "nan", lambda: nav_step(w=[0.0, NAN, 0.0])),
    bad("strapdown.nav_step", "w", "shape2x3", lambda: nav_step(w=np.zeros((2, 3)))),
    bad("strapdown.nav_step", "f", "shape2", lambda: nav_step(f=[0.0, 9.8])),
    bad("strapdown.nav_step", "f", "none", lambda: nav_step(f=None)),
    bad("strapdown.nav_step", "dt", "negative", lambda: nav_step(dt=-0.01)),
    bad("strapdown.nav_step", "dt", "zero", lambda: nav_step(dt=0.0)),
    bad("strapdown.nav_step", "dt", "nan", lambda: nav_step(dt=NAN)),
    bad("strapdown.nav_step", "dt", "array", lambda: nav_step(dt=[0.01, 0.01])),
    bad("strapdown.nav_step", "dt", "str", lambda: nav_step(dt=STR)),
    bad("strapdown.nav_step", "earth_consts", "shape6", lambda: nav_step(earth_consts=strapdown.earth_constants()[:6])),
    bad("strapdown.nav_step", "earth_consts", "negative_a", lambda: nav_step(earth_consts=-strapdown.earth_constants())),
    bad("strapdown.nav_step", "earth_consts", "none", lambda: nav_step(earth_consts=None)),
    bad("strapdown.nav_step", "hold_height", "int", lambda: nav_step(hold_height=1)),
    bad("strapdown.nav_step", "hold_height", "str", lambda: nav_step(hold_height=STR)),

    # ------------------------------------------------------------------ kalman
    bad("kalman.discretize", "F", "not_square", lambda: kalman.discretize(np.zeros((2, 3)), np.eye(2), np.eye(2), 0.1)),
    bad("kalman.discretize", "F", "nan", lambda: kalman.discretize(with_nan(np.zeros((2, 2)), (0, 1)), np.eye(2), np.eye(2), 0.1)),
    bad("kalman.discretize", "G", "row_mismatch", lambda: kalman.discretize(np.zeros((2, 2)), np.eye(3), np.eye(3), 0.1)),
    bad("kalman.discretize", "Qc", "shape_mismatch", lambda: kalman.discretize(np.zeros((2, 2)), np.eye(2), np.eye(3), 0.1)),
    bad("kalman.discretize", "Qc", "inf", lambda: kalman.discretize(np.zeros((2, 2)), np.eye(2), np.eye(2) * INF, 0.1)),
    bad("kalman.discretize", "dt", "zero", lambda: kalman.discretize(np.zeros((2, 2)), np.eye(2), np.eye(2), 0.0)),
    bad("kalman.discretize", "dt", "nan", lambda: kalman.discretize(np.zeros((2, 2)), np.eye(2), np.eye(2), NAN)),
    bad("kalman.predict", "x", "empty", lambda: kf_predict(x=[], P=np.zeros((0, 0)), F=np.zeros((0, 0)), Q=np.zeros((0, 0)))),
    bad("kalman.predict", "x", "shape2x1", lambda: kf_predict(x=[[1.0], [2.0]])),
    bad("kalman.predict", "x", "nan", lambda: kf_predict(x=[1.0, NAN])),
    bad("kalman.predict", "x", "none", lambda: kf_predict(x=None)),
    bad("kalman.predict", "x", "str", lambda: kf_predict(x=STR)),
    bad("kalman.predict", "P", "shape3x3", lambda: kf_predict(P=np.eye(3))),
    bad("kalman.predict", "P", "inf", lambda: kf_predict(P=np.eye(2) * INF)),
    bad("kalman.predict", "F", "shape2x3", lambda: kf_predict(F=np.ones((2, 3)))),
    bad("kalman.predict", "F", "none", lambda: kf_predict(F=None)),
    bad("kalman.predict", "Q", "scalar", lambda: kf_predict(Q=0.01)),
    bad("kalman.predict", "Q", "shape2x1", lambda: kf_predict(Q=np.full((2, 1), 0.01))),
    bad("kalman.predict", "Q", "vector", lambda: kf_predict(Q=[0.01, 0.01])),
    bad("kalman.predict", "Q", "empty", lambda: kf_predict(Q=np.zeros((0, 0)))),
    bad("kalman.predict", "Q", "nan", lambda: kf_predict(Q=with_nan(np.eye(2), (0, 0)))),
    bad("kalman.predict", "Q", "str", lambda: kf_predict(Q=STR)),
    bad("kalman.update", "x", "empty", lambda: kf_update(x=np.zeros(0))),
    bad("kalman.update", "x", "none", lambda: kf_update(x=None)),
    bad("kalman.update", "P", "shape1x1", lambda: kf_update(P=[[1.0]])),
    bad("kalman.update", "P", "nan", lambda: kf_update(P=with_nan(np.eye(2), (1, 0)))),
    bad("kalman.update", "z", "shape2x1", lambda: kf_update(z=[[1.5], [2.5]])),
    bad("kalman.update", "z", "inf", lambda: kf_update(z=[1.5, INF])),
    bad("kalman.update", "z", "str", lambda: kf_update(z=STR)),
    bad("kalman.update", "h", "shape3", lambda: kf_update(h=[1.0, 2.0, 3.0])),
    bad("kalman.update", "h", "empty", lambda: kf_update(h=[])),
    bad("kalman.update", "h", "nan", lambda: kf_update(h=[1.0, NAN])),
    bad("kalman.update", "H", "shape2x3", lambda: kf_update(H=np.ones((2, 3)))),
    bad("kalman.update", "H", "none", lambda: kf_update(H=None)),
    bad("kalman.update", "R", "scalar", lambda: kf_update(R=1.0)),
    bad("kalman.update", "R", "shape2x1", lambda: kf_update(R=np.ones((2, 1)))),
    bad("kalman.update", "R", "inf", lambda: kf_update(R=np.eye(2) * INF)),
    bad("kalman.update", "angle_mask", "empty", lambda: kf_update(angle_mask=np.zeros(0, dtype=bool))),
    bad("kalman.update", "angle_mask", "float", lambda: kf_update(angle_mask=[0.0, 1.0])),
    bad("kalman.update", "angle_mask", "none", lambda: kf_update(angle_mask=None)),
    bad("kalman.update", "angle_mask", "str", lambda: kf_update(angle_mask=STR)),
    bad("kalman.update", "gate", "nan", lambda: kf_update(z=[1.0 + 100 * np.sqrt(2.0), 2.0], gate=NAN)),
    bad("kalman.update", "gate", "negative", lambda: kf_update(gate=-1.0)),
    bad("kalman.update", "gate", "zero", lambda: kf_update(gate=0.0)),
    bad("kalman.update", "gate", "array", lambda: kf_update(gate=[9.0, 9.0])),
    bad("kalman.update", "gate", "none", lambda: kf_update(gate=None)),
    bad("kalman.update", "gate", "str", lambda: kf_update(gate=STR)),

    # ---------------------------------------------------------------- analysis
    bad("analysis.rmse", "err", "inf", lambda: analysis.rmse([1.0, INF])),
    bad("analysis.rmse", "err", "str", lambda: analysis.rmse(STR)),
    bad("analysis.rmse", "err", "empty", lambda: analysis.rmse([])),
    bad("analysis.rmse", "axis", "out_of_bounds", lambda: analysis.rmse([1.0, 2.0], axis=3)),
    bad("analysis.attitude_errors", "hpr", "shape", lambda: analysis.attitude_errors([0.0, 1.0], [0.0, 0.0, 0.0])),
    bad("analysis.attitude_errors", "hpr_true", "str", lambda: analysis.attitude_errors([0.0, 0.0, 0.0], STR)),
    bad("analysis.error_statistics", "hpr_true", "shape",
        lambda: analysis.error_statistics(np.zeros((2, 5, 3)), np.zeros((4, 3)))),
    bad("analysis.horizontal_error", "lla", "inf", lambda: analysis.horizontal_error([INF, 0.0, 0.0], [0.0, 0.0, 0.0])),
    bad("analysis.position_error", "truth", "nan", lambda: analysis.position_error([[0.0, 0.0]], [[NAN, 0.0]])),
    bad("analysis.expanding_std", "x", "empty", lambda: analysis.expanding_std([])),
    bad("analysis.detection_rates", "detected", "str", lambda: analysis.detection_rates(STR, [True, False])),
    bad("analysis.settling_time", "tol", "zero", lambda: analysis.settling_time([0.0, 1.0], [1.0, 0.0], 0.0, 0.0)),
    bad("alignment.level", "f_b", "zero", lambda: alignment.level([0.0, 0.0, 0.0])),
    bad("alignment.magnetic_heading", "m_b", "nan", lambda: alignment.magnetic_heading([NAN, 1.0, 0.0], 0.0, 0.0)),
    bad("alignment.tilt_heading", "m_b", "parallel", lambda: alignment.tilt_heading([0.0, 0.0, 9.8], [0.0, 0.0, 1.0])),
    bad("alignment.initial_attitude", "f_b", "str", lambda: alignment.initial_attitude(STR, [0.0, 1.0, 0.0])),
    bad("alignment.gyrocompass_latitude", "lat", "polar", lambda: alignment.gyrocompass_latitude(89.5, deg=True)),
    bad("alignment.static_means", "f_b", "shape", lambda: alignment.static_means(np.zeros((10, 3)), np.zeros((10, 2)), 0.5)),
    bad("alignment.static_means", "stuck_fraction", "negative", lambda: alignment.static_means(W, F, 0.5, stuck_fraction=-0.5)),
    bad("alignment.static_means", "stuck_fraction", "nan", lambda: alignment.static_means(W, F, 0.5, stuck_fraction=NAN)),
    bad("alignment.static_means", "stuck_fraction", "above_one", lambda: alignment.static_means(W, F, 0.5, stuck_fraction=1.5)),
    bad("alignment.triad", "lat", "str", lambda: alignment.triad([0.0, 0.0, 9.8], [0.0, 5e-5, 5e-5], STR)),
    bad("alignment.triad_heading", "C_bn", "shape", lambda: alignment.triad_heading(np.eye(2))),
    bad("alignment.four_position_heading", "w_y", "shape", lambda: alignment.four_position_heading([1.0, 2.0, 3.0])),
    bad("alignment.static_gyro_bias", "C_bn", "shape", lambda: alignment.static_gyro_bias(np.zeros((5, 3)), np.eye(2), 0.5)),
    bad("analysis.segments", "mask", "not_bool", lambda: analysis.segments([0.0, 1.0])),
    bad("atmosphere.baro_height", "p", "negative", lambda: atmosphere.baro_height([100000.0, -5.0], 101325.0)),
    bad("atmosphere.reference_pressure", "until", "no_sample", lambda: atmosphere.reference_pressure([NAN, NAN], [0.0, 1.0], 5.0)),
    bad("atmosphere.classify_floor", "floor_height", "zero", lambda: atmosphere.classify_floor([1.0], floor_height=0.0)),
    bad("atmosphere.segment_floors", "h", "str", lambda: atmosphere.segment_floors(STR, np.ones(3, bool))),
    bad("attitude.ned_to_enu_dcm", "C_ned", "shape", lambda: attitude.ned_to_enu_dcm(np.eye(2))),
    bad("euler.check_pitch", "pitch", "at_90_deg", lambda: euler.check_pitch(np.pi / 2)),
    bad("euler.euler_rates", "w_nb_b", "shape", lambda: euler.euler_rates([0.0, 0.0, 0.0], [1.0, 2.0])),
    bad("euler.integrate_euler", "dt", "negative", lambda: euler.integrate_euler([0.0, 0.0, 0.0], np.zeros((4, 3)), -0.1)),
    bad("analysis.moving_mean", "n", "too_long", lambda: analysis.moving_mean(np.ones(3), 5)),
    bad("pdr.detect_steps", "threshold", "zero", lambda: pdr.detect_steps(np.ones((10, 3)), 0.01, threshold=0.0)),
    bad("pdr.weinberg_step_length", "K", "negative", lambda: pdr.weinberg_step_length([1.0], K=-1.0)),
    bad("pdr.pdr", "step_headings", "shape", lambda: pdr.pdr([1.0, 2.0], [0.0])),
    bad("pdr.pdr_headings", "m_b", "str", lambda: pdr.pdr_headings(np.ones((10, 3)), STR, [3, 6])),
    bad("robust.hold", "leading", "unknown", lambda: robust.hold(np.ones((3, 3)), leading="back")),
    bad("robust.hold", "x", "all_nan", lambda: robust.hold(np.full((3, 3), NAN), leading="first")),
    bad("robust.despike", "spike_gyro", "zero", lambda: robust.despike(W, F, 0.0, 1.0)),
    bad("robust.despike", "f_b", "shape", lambda: robust.despike(W, F[:5], 0.1, 1.0)),
    bad("robust.fault_report", "x", "inf", lambda: robust.fault_report(np.full((4, 3), INF), "gyro")),
    bad("robust.fault_report", "x", "shape1", lambda: robust.fault_report(np.zeros(5), "gyro")),
    bad("robust.fault_report", "sensor", "not_str", lambda: robust.fault_report(W, 1)),
    bad("robust.fault_report", "full_scale", "negative", lambda: robust.fault_report(W, "gyro", full_scale=-1.0)),
    bad("robust.fault_report", "flags", "not_bool", lambda: robust.fault_report(W, "gyro", flags=1)),
    bad("robust.stuck_mask", "x", "inf", lambda: robust.stuck_mask(np.full((4, 3), INF), 3)),
    bad("robust.stuck_mask", "x", "shape1", lambda: robust.stuck_mask(np.zeros(5), 3)),
    bad("robust.stuck_mask", "run", "one", lambda: robust.stuck_mask(W, 1)),
    bad("robust.stuck_mask", "run", "bool", lambda: robust.stuck_mask(W, True)),
    bad("robust.stuck_mask", "axis", "zero", lambda: robust.stuck_mask(W, 3, axis=0)),
    bad("robust.stuck_samples", "x", "inf", lambda: robust.stuck_samples(np.full((4, 3), INF), 3)),
    bad("robust.stuck_samples", "run", "one", lambda: robust.stuck_samples(W, 1)),
    bad("robust.stuck_samples", "full_scale", "zero", lambda: robust.stuck_samples(W, 3, full_scale=0.0)),
    bad("robust.stuck_samples", "axis", "zero", lambda: robust.stuck_samples(W, 3, axis=0)),
    bad("robust.stuck_run_samples", "stuck_run", "one", lambda: robust.stuck_run_samples(1, 0.01)),
    bad("robust.stuck_run_samples", "stuck_run", "str", lambda: robust.stuck_run_samples("Auto", 0.01)),
    bad("robust.longest_repeat", "x", "1-D", lambda: robust.longest_repeat([1.0, 2.0, 3.0])),
    bad("robust.longest_repeat", "x", "inf", lambda: robust.longest_repeat(np.full((4, 3), np.inf))),
    bad("robust.longest_repeat", "valid", "shape", lambda: robust.longest_repeat(W, np.ones(3, bool))),
    bad("robust.longest_repeat", "valid", "numbers", lambda: robust.longest_repeat(W, np.ones(len(W)))),
    bad("filters.zupt.detect_static", "g", "negative", lambda: zupt.detect_static(W, F, 0.01, window=0.05, g=-9.8)),
    bad("filters.zupt.error_state_matrix", "C_bn", "not_rotation", lambda: zupt.error_state_matrix(np.ones((3, 3)), F[0])),
    bad("filters.zupt.error_model_fd", "eps", "zero", lambda: zupt.error_model_fd(np.eye(3), F[0], eps=0.0)),
    bad("filters.zupt.zupt_zaru_matrix", "w_ie_n", "nan", lambda: zupt.zupt_zaru_matrix(np.eye(3), [0.0, NAN, 0.0])),
    bad("filters.zupt.zupt_zaru_innovation", "vel_n", "shape", lambda: zupt.zupt_zaru_innovation(
        [0.0, 0.0], W[0], W[0], np.eye(3), W[0])),
    bad("filters.mahony.mahony", "kp", "negative", lambda: mahony.mahony(W, F, 0.01, Q1, m_b=F, kp=-1.0)),
    bad("filters.mahony.mahony", "max_dt", "negative", lambda: mahony.mahony(W, F, 0.01, Q1, max_dt=-1.0)),
    bad("filters.mahony.mahony", "max_dt", "nan", lambda: mahony.mahony(W, F, 0.01, Q1, max_dt=NAN)),
    bad("filters.mahony.mahony", "stuck_run", "zero", lambda: mahony.mahony(W, F, 0.01, Q1, stuck_run=0)),
    bad("filters.mahony.mahony", "stuck_run", "bool", lambda: mahony.mahony(W, F, 0.01, Q1, stuck_run=True)),
    bad("filters.mahony.mahony", "stuck_run", "str", lambda: mahony.mahony(W, F, 0.01, Q1, stuck_run="on")),
    bad("filters.mahony.mahony", "m_b", "both_references", lambda: mahony.mahony(
        W, F, 0.01, Q1, m_b=F, heading_rtk=np.zeros(10), rtk_valid=np.ones(10, bool))),
    bad("filters.quaternion_kf.quaternion_kf", "B_n", "missing", lambda: quaternion_kf.quaternion_kf(W, F, 0.01, Q1, m_b=F)),
    bad("filters.quaternion_kf.quaternion_kf", "max_dt", "negative", lambda: quaternion_kf.quaternion_kf(W, F, 0.01, Q1, max_dt=-1.0)),
    bad("filters.quaternion_kf.quaternion_kf", "max_dt", "nan", lambda: quaternion_kf.quaternion_kf(W, F, 0.01, Q1, max_dt=NAN)),
    bad("filters.quaternion_kf.quaternion_kf", "stuck_run", "zero", lambda: quaternion_kf.quaternion_kf(W, F, 0.01, Q1, stuck_run=0)),
    bad("filters.quaternion_kf.quaternion_kf", "stuck_run", "bool",
        lambda: quaternion_kf.quaternion_kf(W, F, 0.01, Q1, stuck_run=False)),
    bad("filters.quaternion_kf.measurement_model", "b", "east_component", lambda: quaternion_kf.measurement_model(
        Q1, [1.0, 0.0, 0.0])),
    bad("filters.quaternion_kf.measurement_jacobian", "q", "str", lambda: quaternion_kf.measurement_jacobian(STR, [0, 1, 0])),
    bad("filters.quaternion_kf.transition", "dt", "zero", lambda: quaternion_kf.transition(W[0], 0.0)),
    bad("filters.quaternion_kf.noise_input", "q", "nan", lambda: quaternion_kf.noise_input([NAN, 0, 0, 0], 0.01)),
    bad("sensors.window_mean_std", "errors", "wrong_type", lambda: sensors.window_mean_std("NAV-FOG", 180.0, 0.01)),
    bad("sensors.window_mean_std", "duration", "zero", lambda: sensors.window_mean_std(sensors.TriadErrors(), 0.0, 0.01)),
    bad("analysis.normal_condition", "A", "scalar", lambda: analysis.normal_condition(1.0)),
    bad("analysis.condition_number", "V", "no_blocks", lambda: analysis.condition_number(np.ones((2, 3)))),
    bad("analysis.lsq_covariance", "R", "shape", lambda: analysis.lsq_covariance(np.ones((4, 2, 3)), np.ones((4, 3, 3)))),
    bad("analysis.lsq_covariance", "V", "unobservable", lambda: analysis.lsq_covariance(np.zeros((4, 2, 3)), np.ones((4, 2, 2)))),
    bad("analysis.cramer_rao_bound", "V", "nan", lambda: analysis.cramer_rao_bound(np.full((4, 2, 3), NAN), np.ones((4, 2, 2)))),
    bad("imu.ImuSamples", "f_b", "shape", lambda: imu.ImuSamples(W, F[:5], 0.01)),
    bad("imu.ImuSamples", "dt", "negative", lambda: imu.ImuSamples(W, F, -0.01)),
    bad("imu.ImuSamples", "full_scale_gyro", "zero", lambda: imu.ImuSamples(W, F, 0.01, full_scale_gyro=0.0)),
    bad("imu.ImuSamples", "time", "repeated_times", lambda: imu.ImuSamples.from_times(np.zeros(11), W, F)),
    bad("imu.unpack", "dt", "given_twice", lambda: imu.unpack(imu.ImuSamples(W, F, 0.01), dt=0.01)),
    bad("imu.unpack", "f_b", "missing", lambda: imu.unpack(W)),
    bad("earth.earth_rate_b", "C_bn", "shape", lambda: earth.earth_rate_b(np.eye(2), 0.5)),
    bad("earth.earth_rate_b", "lat", "array", lambda: earth.earth_rate_b(np.eye(3), [0.5, 0.6])),
    bad("trajectory.Leg", "duration", "zero", lambda: trajectory.Leg(0.0)),
    bad("trajectory.Leg", "turn, climb", "turn_on_a_stop", lambda: trajectory.Leg(5.0, 0.0, turn=1.0)),
    bad("trajectory.Gait", "ramp", "negative", lambda: trajectory.Gait(ramp=-1.0)),
    bad("trajectory.walk", "legs", "empty", lambda: trajectory.walk([], 0.01, LLA0, 0.0)),
    bad("trajectory.walk", "heading0", "nan", lambda: trajectory.walk([trajectory.Leg(1.0)], 0.01, LLA0, NAN)),
    bad("trajectory.stance_mask", "gait", "wrong_type", lambda: trajectory.stance_mask([trajectory.Leg(1.0)], 0.01, gait=1.0)),
    bad("filters.planar_ekf.motion_model", "X", "shape", lambda: planar_ekf.motion_model(np.zeros(4), 0.5)),
    bad("filters.planar_ekf.jacobian", "T", "zero", lambda: planar_ekf.jacobian(np.zeros(5), 0.0)),
    bad("filters.planar_ekf.propagate", "n_steps", "float", lambda: planar_ekf.propagate(np.zeros(5), 0.5, 2.5)),
    bad("filters.planar_ekf.dead_reckoning", "speed", "shape", lambda: planar_ekf.dead_reckoning(
        T10, np.ones(9), np.zeros(10), np.zeros(5))),
    bad("filters.planar_ekf.filter_grid", "Q", "missing", lambda: planar_ekf.filter_grid(
        T10, np.zeros((10, 5)), np.zeros(5), R=np.eye(5))),
    bad("filters.planar_ekf.covariance", "P0", "not_psd", lambda: planar_ekf.covariance(-np.eye(5), "P0")),
    bad("filters.heading_fusion.fuse_rtk_heading", "alpha", "zero", lambda: heading_fusion.fuse_rtk_heading(
        np.zeros(10), np.zeros(10), np.ones(10, bool), 0.01, alpha=0.0)),
    bad("filters.heading_fusion.rtk_at_imu_rate", "step", "zero", lambda: heading_fusion.rtk_at_imu_rate(
        T10, np.zeros(10), np.ones(10, bool), 0)),
    bad("filters.observations.MagGate", "norm_tol", "negative", lambda: observations.MagGate(norm_tol=-0.1)),
    bad("filters.observations.magnetic_reference", "B_n", "zero", lambda: observations.magnetic_reference([0.0, 0.0, 0.0])),
    bad("filters.observations.prepare_inputs", "f_b", "shape", lambda: observations.prepare_inputs(
        W, F[:5], 0.01, Q1, F, None, None, None, None, None, 9.8, 0.25, None, 5, None, None, None, None)),
    bad("analysis.allan_deviation", "x", "too_short", lambda: analysis.allan_deviation(np.ones(5), 0.1)),
    bad("analysis.allan_deviation", "x", "empty", lambda: analysis.allan_deviation([], 0.1)),
    bad("analysis.allan_deviation", "x", "nan", lambda: analysis.allan_deviation(with_nan(np.ones(100), 7), 0.1)),
    bad("analysis.allan_deviation", "x", "str", lambda: analysis.allan_deviation(STR, 0.1)),
    bad("analysis.allan_deviation", "dt", "zero", lambda: analysis.allan_deviation(np.ones(100), 0.0)),
    bad("analysis.allan_deviation", "taus", "negative", lambda: analysis.allan_deviation(np.ones(100), 0.1, taus=[-1.0])),
    bad("analysis.allan_deviation", "taus", "too_long", lambda: analysis.allan_deviation(np.ones(100), 0.1, taus=[100.0])),
    bad("analysis.allan_deviation_theory", "taus", "zero", lambda: analysis.allan_deviation_theory([0.0, 1.0], white=1e-3)),
    bad("analysis.allan_deviation_theory", "taus", "nan", lambda: analysis.allan_deviation_theory([NAN], white=1e-3)),
    bad("analysis.allan_deviation_theory", "white", "nan", lambda: analysis.allan_deviation_theory([1.0, 10.0], white=NAN)),
    bad("analysis.allan_deviation_theory", "bias_instability", "negative",
        lambda: analysis.allan_deviation_theory([1.0, 10.0], bias_instability=-1e-4)),
    bad("analysis.allan_deviation_theory", "correlation_time", "zero",
        lambda: analysis.allan_deviation_theory([1.0, 10.0], bias_instability=1e-4, correlation_time=0.0)),
    bad("analysis.fit_allan", "taus", "negative", lambda: analysis.fit_allan([-1.0, 2.0], [1e-3, 1e-3], 1000, 0.1)),
    bad("analysis.fit_allan", "taus", "empty", lambda: analysis.fit_allan([], [], 1000, 0.1)),
    bad("analysis.fit_allan", "adev", "zero", lambda: analysis.fit_allan([1.0, 2.0], [0.0, 1e-3], 1000, 0.1)),
    bad("analysis.fit_allan", "adev", "nan", lambda: analysis.fit_allan([1.0, 2.0], [NAN, 1e-3], 1000, 0.1)),
    bad("analysis.fit_allan", "adev", "length_mismatch", lambda: analysis.fit_allan([1.0, 2.0, 4.0], [1e-3, 1e-3], 1000, 0.1)),
    bad("analysis.fit_allan", "n_samples", "zero", lambda: analysis.fit_allan([1.0, 2.0, 4.0], [3e-3, 2e-3, 1.5e-3], 0, 0.1)),
    bad("analysis.fit_allan", "dt", "negative", lambda: analysis.fit_allan([1.0, 2.0, 4.0], [3e-3, 2e-3, 1.5e-3], 1000, -0.1)),

    # ------------------------------------------------------------------- repro
    # (run inside the ``sandbox`` fixture: throw-away root and module state)
    bad("repro.build_dir", "notebook", "int", lambda: repro.build_dir(123)),
    bad("repro.setup", "notebook", "empty", lambda: repro.setup("", style=False)),
    bad("repro.setup", "notebook", "path", lambda: repro.setup("a/b", style=False)),
    bad("repro.setup", "notebook", "int", lambda: repro.setup(123, style=False)),
    bad("repro.savefig", "fig", "str", lambda: (repro.setup("zz_bad_input", style=False), repro.savefig(STR, "x"))),
    bad("repro.savefig", "name", "path",
        lambda: (repro.setup("zz_bad_input", style=False), repro.savefig(plt.figure(), "no/such/dir"))),
    bad("repro.check", "value", "shape2", lambda: repro.check("T/x", [1.0, 2.0], 1.0, 0.1, "src")),
    bad("repro.check", "value", "str", lambda: repro.check("T/x", STR, 1.0, 0.1, "src")),
    bad("repro.check", "expected", "shape2", lambda: repro.check("T/x", 1.0, [1.0, 2.0], 0.1, "src")),
    bad("repro.check", "expected", "nan", lambda: repro.check("T/x", 1.0, NAN, 0.1, "src")),
    bad("repro.check", "tol", "negative", lambda: repro.check("T/x", 1.0, 1.0, -0.1, "src")),
    bad("repro.check", "tol", "nan", lambda: repro.check("T/x", 1.0, 1.0, NAN, "src")),
    bad("repro.check", "tol", "inf", lambda: repro.check("T/x", 1.0, 2.0, INF, "src")),
    bad("repro.check_range", "lower", "no_bounds", lambda: repro.check_range("T/x", 1.0, "src")),
    bad("repro.check_range", "value", "shape2", lambda: repro.check_range("T/x", [1.0, 2.0], "src", upper=3.0)),
    bad("repro.check_range", "lower", "shape2", lambda: repro.check_range("T/x", 1.0, "src", lower=[0.0, 0.5])),
    bad("repro.check_range", "upper", "nan", lambda: repro.check_range("T/x", 1.0, "src", upper=NAN)),
    bad("repro.check_outside", "value", "shape2", lambda: repro.check_outside("T/x", [1.0, 2.0], "src", upper=3.0)),
    bad("repro.check_outside", "lower", "no_bounds", lambda: repro.check_outside("T/x", 1.0, "src")),
    bad("repro.check_outside", "source", "none", lambda: repro.check_outside("T/x", 5.0, None, upper=3.0)),
    bad("repro.env_flag", "name", "none", lambda: repro.env_flag(None)),
    bad("repro.caption", "markdown", "empty", lambda: repro.caption("  ")),
    bad("repro.explorer", "draw", "not_callable",
        lambda: (repro.setup("zz_bad_input", style=False), repro.explorer(3.0, "x", {}))),
    bad("repro.explorer", "controls", "list",
        lambda: (repro.setup("zz_bad_input", style=False), repro.explorer(lambda: None, "x", [1.0]))),
    bad("repro.answer", "markdown", "none", lambda: repro.answer(None)),
    bad("repro.answer", "label", "empty", lambda: repro.answer("42", label="")),
    bad("repro.env_flag", "NAVLIB_TEST_BAD_FLAG", "text", lambda: _env_flag_with("NAVLIB_TEST_BAD_FLAG", "maybe")),
    bad("repro.mode", "teaching", "str", lambda: (repro.setup("zz_bad_input", style=False),
                                                  repro.mode(teaching="yes", fast=False))),
    bad("repro.mode", "fast", "int", lambda: (repro.setup("zz_bad_input", style=False),
                                              repro.mode(teaching=False, fast=2))),
    bad("repro.verdict", "claim", "no_paper",
        lambda: (repro.setup("zz_bad_input", style=False), repro.verdict("P000-EQ3-EULER", "reproduced"))),

    # ------------------------------------------------------------------- plots
    bad("plots.body_axes", "ax", "str", lambda: plots.body_axes(STR, np.eye(3))),
    bad("plots.body_axes", "C_bn", "shape2x2", lambda: plots.body_axes(axes3d(), np.eye(2))),
    bad("plots.body_axes", "C_bn", "nan", lambda: plots.body_axes(axes3d(), with_nan(np.eye(3), (0, 0)))),
    bad("plots.allan", "adev_rad_s", "length_mismatch", lambda: plots.allan(axes2d(), [1.0, 2.0, 4.0], [1e-5, 1e-5])),
    bad("plots.allan", "adev_rad_s", "nan", lambda: plots.allan(axes2d(), [1.0, 2.0], [1e-5, NAN])),
    bad("plots.allan", "taus", "negative", lambda: plots.allan(axes2d(), [-1.0, 2.0], [1e-5, 1e-5])),
    bad("plots.heading_deg", "hpr", "shape2", lambda: plots.heading_deg(np.zeros((5, 2)))),
    bad("plots.paper_value", "value", "nan", lambda: plots.paper_value(axes2d(), NAN, "paper")),
    bad("plots.paper_value", "axis", "z", lambda: plots.paper_value(axes2d(), 1.0, "paper", axis="z")),
    bad("plots.paper_value", "label", "none", lambda: plots.paper_value(axes2d(), 1.0, None)),
    bad("plots.block_diagram", "arrows", "unknown_block",
        lambda: plots.block_diagram(axes2d(), {"a": (0.2, 0.5, "A")}, [("a", "b")])),
    bad("plots.block_diagram", "blocks", "short_spec", lambda: plots.block_diagram(axes2d(), {"a": (0.2, 0.5)}, [])),
    bad("plots.block_diagram", "width", "above_one",
        lambda: plots.block_diagram(axes2d(), {"a": (0.2, 0.5, "A")}, [], width=2.0)),
    bad("plots.plane_frame", "origin", "shape3", lambda: plots.plane_frame(axes2d(), (0.0, 0.0, 0.0), 30.0, ("x", "y"))),
    bad("plots.plane_frame", "labels", "one", lambda: plots.plane_frame(axes2d(), (0.0, 0.0), 30.0, ("x",))),
    bad("plots.plane_frame", "length", "negative",
        lambda: plots.plane_frame(axes2d(), (0.0, 0.0), 30.0, ("x", "y"), length=-1.0)),
    bad("plots.angle_arc", "radius", "zero", lambda: plots.angle_arc(axes2d(), (0.0, 0.0), 0.0, 0.0, 90.0)),
    bad("plots.angle_arc", "end_deg", "inf", lambda: plots.angle_arc(axes2d(), (0.0, 0.0), 1.0, 0.0, INF)),
    bad("plots.angle_arc", "color", "none", lambda: plots.angle_arc(axes2d(), (0.0, 0.0), 1.0, 0.0, 90.0, color=None)),
    bad("plots.heading_deg", "hpr", "str", lambda: plots.heading_deg(STR)),
    bad("plots.heading_deg", "hpr", "inf", lambda: plots.heading_deg([INF, 0.0, 0.0])),
]


# The one-argument unit converters (units has no __all__: its public functions).
def _mc_batch(ids, streams):
    return {"x": streams.normal()}


CASES += [
    bad("montecarlo.run", "n_trials", "zero", lambda: montecarlo.run(_mc_batch, 0, 1, progress=False)),
    bad("montecarlo.run", "seed", "str", lambda: montecarlo.run(_mc_batch, 5, STR, progress=False)),
    bad("montecarlo.run", "batch_size", "negative", lambda: montecarlo.run(_mc_batch, 5, 1, batch_size=-2)),
    bad("montecarlo.run", "batch_fn", "not_callable", lambda: montecarlo.run(None, 5, 1)),
    bad("montecarlo.run", "executor", "str", lambda: montecarlo.run(_mc_batch, 5, 1, executor=STR)),
    bad("montecarlo.TrialStreams", "seed", "nan", lambda: montecarlo.TrialStreams(NAN, [0, 1])),
    bad("montecarlo.TrialStreams", "ids", "negative", lambda: montecarlo.TrialStreams(1, [0, -1])),
    bad("montecarlo.TrialStreams", "ids", "empty", lambda: montecarlo.TrialStreams(1, [])),
]


def _unit_converters():
    return sorted(name for name, obj in vars(units).items()
                  if callable(obj) and not name.startswith("_") and getattr(obj, "__module__", "") == units.__name__
                  and name != "to_si")


CASES += [bad(f"units.{name}", "x", "str", lambda f=getattr(units, name): f(STR))
          for name in _unit_converters()]


# ------------------------------------------------------- wrong dtypes (issue 9)
# Values that are not real numbers where navlib expects reals: complex
# (numpy would silently drop the imaginary part), object arrays, booleans
# (a mask passed where numbers belong) and numeric strings (numpy would parse
# "1.5"). navlib raises _validate.InputTypeError, a TypeError that is also a
# ValueError; the message starts with the argument name.
def as_complex(good):
    return np.asarray(good, dtype=float) + 1j


def as_object(good):
    return np.asarray(good, dtype=float).astype(object)


def as_bool(good):
    return np.ones(np.shape(good), dtype=bool)


KINDS = {"complex": as_complex, "object": as_object, "bool": as_bool, "numeric_str": lambda good: "1.5"}


def dtype_rows(target, arg, call, good, kinds=("complex", "object", "bool")):
    """Rows calling ``call(value)`` with ``good`` turned into each wrong kind of value."""
    return [bad(target, arg, kind, lambda f=KINDS[kind]: call(f(good))) for kind in kinds]


_ALL4 = ("complex", "object", "bool", "numeric_str")
FS = np.tile([0.0, 0.0, 1.0], (20, 1))
T20 = np.arange(20.0)
HPR0 = [0.1, 0.2, 0.3]


def _traj_with(**kw):
    args = dict(time=TRAJ.time, lla=TRAJ.lla, vel_n=TRAJ.vel_n, q_bn=TRAJ.q_bn)
    args.update(kw)
    return trajectory.Trajectory(**args)


DTYPE_CASES = [
    # attitude
    *dtype_rows("attitude.wrap_pi", "angle", attitude.wrap_pi, [0.1, 0.2], _ALL4),
    *dtype_rows("attitude.wrap_2pi", "angle", attitude.wrap_2pi, 0.1),
    *dtype_rows("attitude.skew", "v", attitude.skew, [1.0, 2.0, 3.0], _ALL4),
    *dtype_rows("attitude.rot", "angle", lambda a: attitude.rot("x", a), 0.1),
    *dtype_rows("attitude.orthonormalize", "C", attitude.orthonormalize, np.eye(3)),
    *dtype_rows("attitude.euler_to_dcm", "hpr", attitude.euler_to_dcm, HPR0, _ALL4),
    *dtype_rows("attitude.dcm_to_euler", "C_bn", attitude.dcm_to_euler, np.eye(3)),
    *dtype_rows("attitude.euler_to_quat", "hpr", attitude.euler_to_quat, HPR0),
    *dtype_rows("attitude.quat_to_euler", "q", attitude.quat_to_euler, Q1),
    *dtype_rows("attitude.quat_to_dcm", "q", attitude.quat_to_dcm, Q1, _ALL4),
    *dtype_rows("attitude.dcm_to_quat", "C_bn", attitude.dcm_to_quat, np.eye(3)),
    *dtype_rows("attitude.quat_mult", "p", lambda p: attitude.quat_mult(p, Q1), Q1),
    *dtype_rows("attitude.quat_mult", "q", lambda q: attitude.quat_mult(Q1, q), Q1),
    *dtype_rows("attitude.quat_conj", "q", attitude.quat_conj, Q1),
    *dtype_rows("attitude.quat_normalize", "q", attitude.quat_normalize, Q1),
    *dtype_rows("attitude.quat_rotate", "v_b", lambda v: attitude.quat_rotate(Q1, v), [1.0, 0.0, 0.0]),
    *dtype_rows("attitude.rotvec_to_dcm", "rv", attitude.rotvec_to_dcm, [0.1, 0.0, 0.0]),
    *dtype_rows("attitude.dcm_to_rotvec", "C", attitude.dcm_to_rotvec, np.eye(3)),
    *dtype_rows("attitude.rotvec_to_quat", "rv", attitude.rotvec_to_quat, [0.1, 0.0, 0.0]),
    *dtype_rows("attitude.quat_to_rotvec", "q", attitude.quat_to_rotvec, Q1),
    bad("attitude.rot", "axis", "int", lambda: attitude.rot(1, 0.1)),
    bad("attitude.quat_rotate", "q", "empty_batch_mismatch", lambda: attitude.quat_rotate(np.zeros((0, 4)), np.ones((2, 3)))),
    # earth
    *dtype_rows("earth.earth_rate_n", "lat", earth.earth_rate_n, 0.5),
    *dtype_rows("earth.gravity", "lat", earth.gravity, 0.5, _ALL4),
    *dtype_rows("earth.gravity", "h", lambda h: earth.gravity(0.5, h), 10.0),
    *dtype_rows("earth.gravity_n", "lat", earth.gravity_n, 0.5),
    *dtype_rows("earth.radii", "lat", earth.radii, 0.5, _ALL4),
    *dtype_rows("earth.transport_rate_n", "vel_n", lambda v: earth.transport_rate_n(0.5, 0.0, v), [1.0, 2.0, 0.0]),
    *dtype_rows("earth.magnetic_field", "lat", lambda lat: earth.magnetic_field(lat, 10.0), 45.0),
    *dtype_rows("earth.magnetic_field", "year", lambda y: earth.magnetic_field(45.0, 10.0, year=y), 2024.0),
    *dtype_rows("earth.field_from_angles", "intensity", lambda F: earth.field_from_angles(0.0, 60.0, F), 50.0),
    *dtype_rows("earth.field_angles", "B_n", earth.field_angles, [1.0, 20.0, -40.0], _ALL4),
    bad("earth.Ellipsoid", "a", "complex", lambda: earth.Ellipsoid("bad", 6378137.0 + 1j, 1 / 298.257, 3.986e14, 7.29e-5)),
    bad("earth.Ellipsoid", "f", "str", lambda: earth.Ellipsoid("bad", 6378137.0, "0.0033", 3.986e14, 7.29e-5)),
    bad("earth.Ellipsoid", "omega", "inf", lambda: earth.Ellipsoid("bad", 6378137.0, 1 / 298.257, 3.986e14, INF)),
    bad("earth.Ellipsoid", "f", "f_one", lambda: earth.Ellipsoid("bad", 6378137.0, 1.0, 3.986e14, 7.29e-5)),
    # units
    bad("units.to_si", "value", "complex", lambda: units.to_si(1 + 1j, "deg")),
    bad("units.to_si", "value", "object", lambda: units.to_si(as_object([1.0, 2.0]), "g")),
    bad("units.to_si", "value", "bool", lambda: units.to_si(True, "deg/h")),
    bad("units.to_si", "value", "numeric_str", lambda: units.to_si("1.5", "deg/h")),
    # sensors
    bad("sensors.TriadErrors", "bias", "complex", lambda: sensors.TriadErrors(bias=1e-3 + 1j)),
    bad("sensors.TriadErrors", "noise_density", "bool", lambda: sensors.TriadErrors(noise_density=True)),
    bad("sensors.ImuModel", "accel", "none", lambda: sensors.ImuModel(accel=None)),
    *dtype_rows("sensors.simulate_imu", "w_ib_b", lambda w: sensors.simulate_imu(w, F, 0.01, sensors.ImuModel(), rng()), W),
    *dtype_rows("sensors.simulate_imu", "f_b", lambda f: sensors.simulate_imu(W, f, 0.01, sensors.ImuModel(), rng()), F),
    *dtype_rows("sensors.simulate_imu", "dt", lambda dt: sensors.simulate_imu(W, F, dt, sensors.ImuModel(), rng()), 0.01, _ALL4),
    bad("sensors.simulate_imu", "w_ib_b", "inf", lambda: sensors.simulate_imu(W + INF, F, 0.01, sensors.ImuModel(), rng())),
    bad("sensors.imu_model", "device", "int", lambda: sensors.imu_model(7)),
    bad("sensors.preset", "device", "empty", lambda: sensors.preset("")),
    bad("sensors.MagnetometerModel", "soft_iron", "complex", lambda: sensors.MagnetometerModel(soft_iron=0.01j)),
    bad("sensors.MagnetometerModel", "full_scale", "zero", lambda: sensors.MagnetometerModel(full_scale=0.0)),
    *dtype_rows("sensors.simulate_magnetometer", "q_bn",
                lambda q: sensors.simulate_magnetometer(q, [0.0, 20.0, -40.0], sensors.MagnetometerModel(), rng()),
                np.tile(Q1, (10, 1))),
    *dtype_rows("sensors.simulate_magnetometer", "B_n",
                lambda B: sensors.simulate_magnetometer(np.tile(Q1, (10, 1)), B, sensors.MagnetometerModel(), rng()),
                [0.0, 20.0, -40.0]),
    *dtype_rows("sensors.magnetic_disturbances", "time", lambda t: sensors.magnetic_disturbances(t, rng(), 0.1), T10),
    bad("sensors.magnetic_disturbances", "rate", "str", lambda: sensors.magnetic_disturbances(T10, rng(), STR)),
    bad("sensors.magnetic_disturbances", "time", "empty", lambda: sensors.magnetic_disturbances([], rng(), 0.1)),
    bad("sensors.BarometerModel", "drift_rate", "complex", lambda: sensors.BarometerModel(drift_rate=1j)),
    bad("sensors.BarometerModel", "noise", "str", lambda: sensors.BarometerModel(noise=STR)),
    *dtype_rows("sensors.simulate_barometer", "h", lambda h: sensors.simulate_barometer(h, T10, sensors.BarometerModel(), rng()), T10),
    bad("sensors.simulate_barometer", "time", "empty", lambda: sensors.simulate_barometer([], [], sensors.BarometerModel(), rng())),
    bad("sensors.simulate_barometer", "h", "inf", lambda: sensors.simulate_barometer(T10 + INF, T10, sensors.BarometerModel(), rng())),
    *dtype_rows("sensors.outage_mask", "time", lambda t: sensors.outage_mask(t, [(2.0, 3.0)]), T10),
    bad("sensors.outage_mask", "outages", "str", lambda: sensors.outage_mask(T10, STR)),
    bad("sensors.outage_mask", "outages", "complex", lambda: sensors.outage_mask(T10, [(2.0 + 1j, 3.0)])),
    *dtype_rows("sensors.simulate_gnss_position", "lla", lambda lla: sensors.simulate_gnss_position(lla, rng(), 3.0), with_lat(0.6)),
    bad("sensors.simulate_gnss_position", "lla", "inf", lambda: sensors.simulate_gnss_position(with_lat(0.6) + INF, rng(), 3.0)),
    bad("sensors.simulate_gnss_position", "sigma_horizontal", "str", lambda: sensors.simulate_gnss_position(with_lat(0.6), rng(), STR)),
    *dtype_rows("sensors.simulate_heading", "heading", lambda h: sensors.simulate_heading(h, rng(), 0.01), T10),
    bad("sensors.simulate_heading", "heading", "inf", lambda: sensors.simulate_heading(T10 + INF, rng(), 0.01)),
    bad("sensors.simulate_heading", "sigma", "complex", lambda: sensors.simulate_heading(T10, rng(), 0.01j)),
    bad("sensors.gauss_markov", "shape", "str", lambda: sensors.gauss_markov(STR, 0.1, 1.0, 10.0, rng())),
    bad("sensors.gauss_markov", "shape", "empty", lambda: sensors.gauss_markov((0, 3), 0.1, 1.0, 10.0, rng())),
    bad("sensors.gauss_markov", "dt", "complex", lambda: sensors.gauss_markov((10, 3), 0.1j, 1.0, 10.0, rng())),
    bad("sensors.gauss_markov", "correlation_time", "inf", lambda: sensors.gauss_markov((10, 3), 0.1, 1.0, INF, rng())),
    # atmosphere
    *dtype_rows("atmosphere.isa_altitude", "p", atmosphere.isa_altitude, 9e4, _ALL4),
    *dtype_rows("atmosphere.isa_pressure", "h", atmosphere.isa_pressure, 100.0, _ALL4),
    *dtype_rows("atmosphere.bmp180_altitude", "p", atmosphere.bmp180_altitude, 9e4),
    *dtype_rows("atmosphere.bmp180_pressure", "h", atmosphere.bmp180_pressure, 100.0),
    bad("atmosphere.bmp180_pressure", "h", "inf", lambda: atmosphere.bmp180_pressure(INF)),
    bad("atmosphere.isa_pressure", "p0", "complex", lambda: atmosphere.isa_pressure(100.0, 101325.0j)),
    *dtype_rows("atmosphere.hypsometric_height", "temperature", lambda T: atmosphere.hypsometric_height(9e4, 1e5, T), 288.0),
    bad("atmosphere.hypsometric_height", "p", "inf", lambda: atmosphere.hypsometric_height(INF, 1e5, 288.0)),
    bad("atmosphere.bmp180_compensate", "UT", "complex", lambda: atmosphere.bmp180_compensate(27898 + 1j, 23843, CALIB)),
    bad("atmosphere.bmp180_compensate", "UT", "fractional", lambda: atmosphere.bmp180_compensate(27898.5, 23843, CALIB)),
    bad("atmosphere.bmp180_compensate", "UP", "inf", lambda: atmosphere.bmp180_compensate(27898, INF, CALIB)),
    bad("atmosphere.bmp180_compensate", "oss", "str", lambda: atmosphere.bmp180_compensate(27898, 23843, CALIB, oss=STR)),
    bad("atmosphere.bmp180_compensate", "calib", "not_dict", lambda: atmosphere.bmp180_compensate(27898, 23843, [1, 2, 3])),
    # trajectory
    bad("trajectory.Trajectory", "time", "complex", lambda: _traj_with(time=as_complex(TRAJ.time))),
    bad("trajectory.Trajectory", "lla", "object", lambda: _traj_with(lla=as_object(TRAJ.lla))),
    bad("trajectory.Trajectory", "q_bn", "bool", lambda: _traj_with(q_bn=as_bool(TRAJ.q_bn))),
    bad("trajectory.Trajectory", "time", "nan", lambda: _traj_with(time=with_nan(TRAJ.time, 2))),
    # robust
    *dtype_rows("robust.fault_report", "x", lambda x: robust.fault_report(x, "gyro"), W, _ALL4),
    *dtype_rows("robust.stuck_mask", "x", lambda x: robust.stuck_mask(x, 3), W, _ALL4),
    bad("trajectory.Segment", "duration", "complex", lambda: trajectory.Segment(duration=1.0 + 1j)),
    bad("trajectory.Segment", "turn", "str", lambda: trajectory.Segment(duration=1.0, turn=STR)),
    bad("trajectory.Segment", "speed", "inf", lambda: trajectory.Segment(duration=1.0, speed=INF)),
    *dtype_rows("trajectory.static", "lla0", lambda lla0: trajectory.static(1.0, 0.1, lla0, [0, 0, 0]), LLA0),
    *dtype_rows("trajectory.static", "hpr", lambda hpr: trajectory.static(1.0, 0.1, LLA0, hpr), [0.0, 0.0, 0.0]),
    bad("trajectory.static", "dt", "complex", lambda: trajectory.static(1.0, 0.1j, LLA0, [0, 0, 0])),
    *dtype_rows("trajectory.from_profiles", "vel_n", lambda v: trajectory.from_profiles(T10, LLA0, np.zeros((10, 3)), v),
                np.zeros((10, 3))),
    bad("trajectory.from_profiles", "time", "complex",
        lambda: trajectory.from_profiles(as_complex(T10), LLA0, np.zeros((10, 3)), np.zeros((10, 3)))),
    bad("trajectory.reciprocating_rotation", "axis_b", "complex",
        lambda: trajectory.reciprocating_rotation(10.0, 0.1, LLA0, [0, 0, 0], as_complex([0, 0, 1]), np.pi / 2, 4.0)),
    bad("trajectory.reciprocating_rotation", "axis_b", "bool",
        lambda: trajectory.reciprocating_rotation(10.0, 0.1, LLA0, [0, 0, 0], [False, False, True], np.pi / 2, 4.0)),
    bad("trajectory.reciprocating_rotation", "period", "inf",
        lambda: trajectory.reciprocating_rotation(10.0, 0.1, LLA0, [0, 0, 0], [0, 0, 1], np.pi / 2, INF)),
    bad("trajectory.vehicle", "dt", "complex", lambda: trajectory.vehicle([trajectory.Segment(2.0, speed=5.0)], 0.1j, LLA0, 0.0)),
    bad("trajectory.vehicle", "heading0", "str", lambda: trajectory.vehicle([trajectory.Segment(2.0, speed=5.0)], 0.1, LLA0, STR)),
    bad("trajectory.vehicle", "lla0", "object",
        lambda: trajectory.vehicle([trajectory.Segment(2.0, speed=5.0)], 0.1, as_object(LLA0), 0.0)),
    bad("trajectory.ideal_imu", "traj", "str", lambda: trajectory.ideal_imu(STR)),
    *dtype_rows("trajectory.smooth_ramp", "x", trajectory.smooth_ramp, [0.2, 0.5]),
    bad("trajectory.smooth_ramp", "x", "inf", lambda: trajectory.smooth_ramp([0.2, INF])),
    # strapdown (owned by its module's helper; only the row the coverage test needs)
    bad("strapdown.earth_constants", "ellipsoid", "str", lambda: strapdown.earth_constants(STR)),
    # kalman
    *dtype_rows("kalman.discretize", "F", lambda F_: kalman.discretize(F_, np.eye(2), np.eye(2), 0.1), np.zeros((2, 2))),
    bad("kalman.discretize", "G", "complex", lambda: kalman.discretize(np.zeros((2, 2)), as_complex(np.eye(2)), np.eye(2), 0.1)),
    bad("kalman.discretize", "Qc", "object", lambda: kalman.discretize(np.zeros((2, 2)), np.eye(2), as_object(np.eye(2)), 0.1)),
    bad("kalman.discretize", "dt", "str", lambda: kalman.discretize(np.zeros((2, 2)), np.eye(2), np.eye(2), STR)),
    bad("kalman.discretize", "F", "empty", lambda: kalman.discretize(np.zeros((0, 0)), np.zeros((0, 0)), np.zeros((0, 0)), 0.1)),
    bad("kalman.discretize", "dt", "inf", lambda: kalman.discretize(np.zeros((2, 2)), np.eye(2), np.eye(2), INF)),
    *dtype_rows("kalman.predict", "F", lambda F_: kf_predict(F=F_), np.eye(2), _ALL4),
    *dtype_rows("kalman.update", "R", lambda R_: kf_update(R=R_), np.eye(2), _ALL4),
    *dtype_rows("strapdown.nav_step", "w", lambda w_: nav_step(w=w_), np.zeros(3), _ALL4),
    # analysis
    *dtype_rows("analysis.rmse", "err", analysis.rmse, [1.0, 2.0], ("complex", "object", "bool")),
    *dtype_rows("analysis.allan_deviation", "x", lambda x: analysis.allan_deviation(x, 0.1), np.ones(100)),
    bad("analysis.allan_deviation", "dt", "str", lambda: analysis.allan_deviation(np.ones(100), STR)),
    bad("analysis.allan_deviation", "dt", "inf", lambda: analysis.allan_deviation(np.ones(100), INF)),
    bad("analysis.allan_deviation", "taus", "complex", lambda: analysis.allan_deviation(np.ones(100), 0.1, taus=[1j])),
    *dtype_rows("analysis.allan_deviation_theory", "taus", lambda t: analysis.allan_deviation_theory(t, white=1e-3), [1.0, 10.0]),
    bad("analysis.allan_deviation_theory", "taus", "empty", lambda: analysis.allan_deviation_theory([], white=1e-3)),
    bad("analysis.allan_deviation_theory", "white", "str", lambda: analysis.allan_deviation_theory([1.0], white=STR)),
    bad("analysis.fit_allan", "taus", "complex", lambda: analysis.fit_allan(as_complex([1.0, 2.0]), [1e-3, 1e-3], 1000, 0.1)),
    bad("analysis.fit_allan", "adev", "object", lambda: analysis.fit_allan([1.0, 2.0], as_object([1e-3, 1e-3]), 1000, 0.1)),
    bad("analysis.fit_allan", "n_samples", "str", lambda: analysis.fit_allan([1.0, 2.0, 4.0], [3e-3, 2e-3, 1.5e-3], STR, 0.1)),
    bad("analysis.fit_allan", "n_samples", "fractional", lambda: analysis.fit_allan([1.0, 2.0, 4.0], [3e-3, 2e-3, 1.5e-3], 10.5, 0.1)),
    bad("analysis.fit_allan", "dt", "complex", lambda: analysis.fit_allan([1.0, 2.0, 4.0], [3e-3, 2e-3, 1.5e-3], 1000, 0.1j)),
    # repro
    bad("repro.check", "value", "complex", lambda: repro.check("T/x", 1.0 + 1j, 1.0, 0.1, "src")),
    bad("repro.check", "value", "bool", lambda: repro.check("T/x", True, 1.0, 0.1, "src")),
    bad("repro.check", "expected", "numeric_str", lambda: repro.check("T/x", 1.0, "1.0", 0.1, "src")),
    bad("repro.check", "tol", "object", lambda: repro.check("T/x", 1.0, 1.0, as_object(0.1), "src")),
    bad("repro.check", "name", "int", lambda: repro.check(5, 1.0, 1.0, 0.1, "src")),
    bad("repro.check", "name", "empty", lambda: repro.check("", 1.0, 1.0, 0.1, "src")),
    bad("repro.check_range", "value", "complex", lambda: repro.check_range("T/x", 1j, "src", upper=3.0)),
    bad("repro.check_range", "upper", "numeric_str", lambda: repro.check_range("T/x", 1.0, "src", upper="3")),
    bad("repro.check_range", "lower", "inf_above_upper", lambda: repro.check_range("T/x", 1.0, "src", lower=5.0, upper=3.0)),
    bad("repro.savefig", "name", "empty", lambda: (repro.setup("zz_bad_input", style=False), repro.savefig(plt.figure(), ""))),
    bad("repro.savefig", "fig", "none", lambda: (repro.setup("zz_bad_input", style=False), repro.savefig(None, "x"))),
    bad("repro.build_dir", "notebook", "path", lambda: repro.build_dir("../x")),
    # plots
    *dtype_rows("plots.body_axes", "C_bn", lambda C: plots.body_axes(axes3d(), C), np.eye(3)),
    *dtype_rows("plots.allan", "taus", lambda t: plots.allan(axes2d(), t, [1e-5, 1e-5]), [1.0, 2.0]),
    bad("plots.allan", "ax", "str", lambda: plots.allan(STR, [1.0, 2.0], [1e-5, 1e-5])),
    bad("plots.allan", "taus", "empty", lambda: plots.allan(axes2d(), [], [])),
    *dtype_rows("plots.heading_deg", "hpr", plots.heading_deg, HPR0),
    # montecarlo
    bad("montecarlo.run", "n_trials", "float", lambda: montecarlo.run(_mc_batch, 2.5, 1, progress=False)),
    bad("montecarlo.run", "n_trials", "bool", lambda: montecarlo.run(_mc_batch, True, 1, progress=False)),
    bad("montecarlo.run", "seed", "complex", lambda: montecarlo.run(_mc_batch, 5, 1j, progress=False)),
    bad("montecarlo.run", "seed", "negative", lambda: montecarlo.run(_mc_batch, 5, -1, progress=False)),
    bad("montecarlo.run", "batch_size", "str", lambda: montecarlo.run(_mc_batch, 5, 1, batch_size=STR, progress=False)),
    bad("montecarlo.TrialStreams", "ids", "str", lambda: montecarlo.TrialStreams(1, STR)),
    bad("montecarlo.TrialStreams", "ids", "float", lambda: montecarlo.TrialStreams(1, [0.5, 1.5])),
    bad("montecarlo.TrialStreams", "seed", "str", lambda: montecarlo.TrialStreams(STR, [0, 1])),
    # faults
    *dtype_rows("faults.dropouts", "x", lambda x: faults.dropouts(x, 0.1, rng()), FS, _ALL4),
    bad("faults.dropouts", "x", "empty", lambda: faults.dropouts(np.zeros((0, 3)), 0.1, rng())),
    bad("faults.dropouts", "x", "inf", lambda: faults.dropouts(FS + INF, 0.1, rng())),
    bad("faults.dropouts", "fraction", "above_one", lambda: faults.dropouts(FS, 1.5, rng())),
    bad("faults.dropouts", "fraction", "nan", lambda: faults.dropouts(FS, NAN, rng())),
    bad("faults.dropouts", "fraction", "shape2", lambda: faults.dropouts(FS, [0.1, 0.2], rng())),
    bad("faults.dropouts", "rng", "legacy_rng", lambda: faults.dropouts(FS, 0.1, legacy_rng())),
    bad("faults.gap", "x", "complex", lambda: faults.gap(as_complex(FS), T20, 2.0, 3.0)),
    bad("faults.gap", "time", "length_mismatch", lambda: faults.gap(FS, T10, 2.0, 3.0)),
    bad("faults.gap", "time", "nan", lambda: faults.gap(FS, with_nan(T20, 3), 2.0, 3.0)),
    bad("faults.gap", "start", "nan", lambda: faults.gap(FS, T20, NAN, 3.0)),
    bad("faults.gap", "start", "str", lambda: faults.gap(FS, T20, STR, 3.0)),
    bad("faults.gap", "duration", "negative", lambda: faults.gap(FS, T20, 2.0, -3.0)),
    bad("faults.gap", "duration", "inf", lambda: faults.gap(FS, T20, 2.0, INF)),
    bad("faults.spikes", "x", "object", lambda: faults.spikes(as_object(FS), 0.1, 0.01, rng())),
    bad("faults.spikes", "x", "empty", lambda: faults.spikes([], 0.1, 0.01, rng())),
    bad("faults.spikes", "fraction", "negative", lambda: faults.spikes(FS, -0.1, 0.01, rng())),
    bad("faults.spikes", "sigma", "negative", lambda: faults.spikes(FS, 0.1, -0.01, rng())),
    bad("faults.spikes", "sigma", "shape2", lambda: faults.spikes(FS, 0.1, [0.01, 0.02], rng())),
    bad("faults.spikes", "k", "nan", lambda: faults.spikes(FS, 0.1, 0.01, rng(), k=NAN)),
    bad("faults.spikes", "rng", "int", lambda: faults.spikes(FS, 0.1, 0.01, 3)),
    bad("faults.position_jumps", "lla", "shape2", lambda: faults.position_jumps(np.zeros((10, 2)), 0.1, rng())),
    bad("faults.position_jumps", "lla", "complex", lambda: faults.position_jumps(as_complex(with_lat(0.6)), 0.1, rng())),
    bad("faults.position_jumps", "lla", "lat2rad", lambda: faults.position_jumps(with_lat(2.0), 0.1, rng())),
    bad("faults.position_jumps", "lla", "empty", lambda: faults.position_jumps(np.zeros((0, 3)), 0.1, rng())),
    bad("faults.position_jumps", "fraction", "str", lambda: faults.position_jumps(with_lat(0.6), STR, rng())),
    bad("faults.position_jumps", "size_m", "negative", lambda: faults.position_jumps(with_lat(0.6), 0.1, rng(), size_m=-5.0)),
    bad("faults.position_jumps", "rng", "legacy_rng", lambda: faults.position_jumps(with_lat(0.6), 0.1, legacy_rng())),
    bad("faults.heading_flips", "heading", "complex", lambda: faults.heading_flips(as_complex(T10), 0.1, rng())),
    bad("faults.heading_flips", "heading", "empty", lambda: faults.heading_flips([], 0.1, rng())),
    bad("faults.heading_flips", "heading", "inf", lambda: faults.heading_flips(T10 + INF, 0.1, rng())),
    bad("faults.heading_flips", "fraction", "above_one", lambda: faults.heading_flips(T10, 2.0, rng())),
    bad("faults.heading_flips", "rng", "legacy_rng", lambda: faults.heading_flips(T10, 0.1, legacy_rng())),
    bad("faults.duplicate_timestamps", "time", "decreasing", lambda: faults.duplicate_timestamps(T10[::-1], 0.1, rng())),
    bad("faults.duplicate_timestamps", "time", "complex", lambda: faults.duplicate_timestamps(as_complex(T10), 0.1, rng())),
    bad("faults.duplicate_timestamps", "time", "empty", lambda: faults.duplicate_timestamps([], 0.1, rng())),
    bad("faults.duplicate_timestamps", "fraction", "nan", lambda: faults.duplicate_timestamps(T10, NAN, rng())),
    bad("faults.duplicate_timestamps", "rng", "int", lambda: faults.duplicate_timestamps(T10, 0.1, 1)),
    bad("faults.swap_timestamps", "time", "one_sample", lambda: faults.swap_timestamps([0.0], 0.1, rng())),
    bad("faults.swap_timestamps", "time", "nan", lambda: faults.swap_timestamps(with_nan(T10, 2), 0.1, rng())),
    bad("faults.swap_timestamps", "time", "object", lambda: faults.swap_timestamps(as_object(T10), 0.1, rng())),
    bad("faults.swap_timestamps", "fraction", "negative", lambda: faults.swap_timestamps(T10, -0.5, rng())),
    bad("faults.swap_timestamps", "rng", "legacy_rng", lambda: faults.swap_timestamps(T10, 0.1, legacy_rng())),
    bad("faults.irregular_times", "n", "one", lambda: faults.irregular_times(1, 0.1, 0.2, rng())),
    bad("faults.irregular_times", "n", "float", lambda: faults.irregular_times(10.0, 0.1, 0.2, rng())),
    bad("faults.irregular_times", "n", "bool", lambda: faults.irregular_times(True, 0.1, 0.2, rng())),
    bad("faults.irregular_times", "dt", "zero", lambda: faults.irregular_times(10, 0.0, 0.2, rng())),
    bad("faults.irregular_times", "dt", "complex", lambda: faults.irregular_times(10, 0.1j, 0.2, rng())),
    bad("faults.irregular_times", "jitter", "one", lambda: faults.irregular_times(10, 0.1, 1.0, rng())),
    bad("faults.irregular_times", "jitter", "nan", lambda: faults.irregular_times(10, 0.1, NAN, rng())),
    bad("faults.irregular_times", "t0", "nan", lambda: faults.irregular_times(10, 0.1, 0.2, rng(), t0=NAN)),
    bad("faults.irregular_times", "rng", "legacy_rng", lambda: faults.irregular_times(10, 0.1, 0.2, legacy_rng())),
    bad("faults.saturate", "x", "complex", lambda: faults.saturate(as_complex(FS), 1.0)),
    bad("faults.saturate", "x", "empty", lambda: faults.saturate(np.zeros((0, 3)), 1.0)),
    bad("faults.saturate", "x", "inf", lambda: faults.saturate(FS + INF, 1.0)),
    bad("faults.saturate", "full_scale", "zero", lambda: faults.saturate(FS, 0.0)),
    bad("faults.saturate", "full_scale", "nan", lambda: faults.saturate(FS, NAN)),
    bad("faults.saturate", "full_scale", "str", lambda: faults.saturate(FS, STR)),
    # timing
    bad("timing.sanitize", "time", "nan", lambda: timing.sanitize(with_nan(T10, 4), FS[:10])),
    bad("timing.sanitize", "time", "inf", lambda: timing.sanitize(T10 + INF)),
    bad("timing.sanitize", "time", "complex", lambda: timing.sanitize(as_complex(T10))),
    bad("timing.sanitize", "time", "empty", lambda: timing.sanitize([])),
    bad("timing.sanitize", "time", "2d", lambda: timing.sanitize(np.zeros((10, 2)))),
    bad("timing.sanitize", "time", "all_equal", lambda: timing.sanitize(np.zeros(10))),
    bad("timing.jump_limit", "max_dt", "zero", lambda: timing.jump_limit(np.ones(3), 0.0)),
    bad("timing.jump_limit", "max_dt", "nan", lambda: timing.jump_limit(np.ones(3), NAN)),
    bad("timing.sanitize", "series[0]", "length_mismatch", lambda: timing.sanitize(T10, FS)),
    bad("timing.sanitize", "series[1]", "object", lambda: timing.sanitize(T10, FS[:10], as_object(T10))),
    bad("timing.intervals", "time", "decreasing", lambda: timing.intervals(T10[::-1])),
    bad("timing.intervals", "time", "nan", lambda: timing.intervals(with_nan(T10, 2))),
    bad("timing.intervals", "time", "bool", lambda: timing.intervals(as_bool(T10))),
    bad("timing.intervals", "time", "empty", lambda: timing.intervals([])),
    bad("timing.intervals", "time", "length_mismatch", lambda: timing.intervals(T10, n_samples=5)),
    bad("timing.intervals", "n_samples", "str", lambda: timing.intervals(T10, n_samples=STR)),
    bad("timing.intervals", "n_samples", "negative", lambda: timing.intervals(T10, n_samples=-1)),
]
CASES += DTYPE_CASES
CASES += [bad(f"units.{name}", "x", kind, lambda f=getattr(units, name), v=KINDS[kind]([1.0, 2.0]): f(v))
          for name in _unit_converters() for kind in ("complex", "object", "bool", "numeric_str")]


# ------------------------------------------------------------- calibration
M_SPHERE = 40.0 * attitude.quat_rotate(np.random.default_rng(0).standard_normal((30, 4)), [0.0, 0.0, 1.0])
F_SIX = 9.8 * np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], dtype=float)
W_REC, F_REC = np.zeros((200, 3)), np.tile([0.0, 0.0, 9.8], (200, 1))
CASES += [
    bad("calibration.fit_magnetometer", "m_b", "too_few", lambda: calibration.fit_magnetometer(M_SPHERE[:8])),
    bad("calibration.fit_magnetometer", "m_b", "shape", lambda: calibration.fit_magnetometer(M_SPHERE[:, :2])),
    bad("calibration.fit_magnetometer", "m_b", "nan", lambda: calibration.fit_magnetometer(with_nan(M_SPHERE, (3, 1)))),
    bad("calibration.fit_magnetometer", "m_b", "planar", lambda: calibration.fit_magnetometer(M_SPHERE * [1.0, 1.0, 0.0])),
    bad("calibration.fit_magnetometer", "field_strength", "zero", lambda: calibration.fit_magnetometer(M_SPHERE, 0.0)),
    *dtype_rows("calibration.fit_magnetometer", "m_b", calibration.fit_magnetometer, M_SPHERE),
    bad("calibration.MagCalibration", "offset", "shape", lambda: calibration.MagCalibration([0.0, 0.0], np.eye(3), 50.0)),
    bad("calibration.MagCalibration", "soft_iron", "not_spd", lambda: calibration.MagCalibration(np.zeros(3), -np.eye(3), 50.0)),
    bad("calibration.MagCalibration", "field_strength", "nan", lambda: calibration.MagCalibration(np.zeros(3), np.eye(3), NAN)),
    bad("calibration.fit_accelerometer", "f_means", "too_few", lambda: calibration.fit_accelerometer(F_SIX[:5])),
    bad("calibration.fit_accelerometer", "f_means", "inf", lambda: calibration.fit_accelerometer(F_SIX + [0.0, 0.0, INF])),
    bad("calibration.fit_accelerometer", "f_means", "all_level", lambda: calibration.fit_accelerometer(np.tile(F_SIX[4], (6, 1)))),
    bad("calibration.fit_accelerometer", "g", "negative", lambda: calibration.fit_accelerometer(F_SIX, g=-9.8)),
    *dtype_rows("calibration.fit_accelerometer", "f_means", calibration.fit_accelerometer, F_SIX),
    bad("calibration.AccelCalibration", "matrix", "upper", lambda: calibration.AccelCalibration(np.zeros(3), np.ones((3, 3)))),
    bad("calibration.AccelCalibration", "bias", "nan", lambda: calibration.AccelCalibration([NAN, 0.0, 0.0], np.eye(3))),
    bad("calibration.gyro_bias_at_rest", "w_ib_b", "one_sample", lambda: calibration.gyro_bias_at_rest(W[:1])),
    bad("calibration.gyro_bias_at_rest", "w_ib_b", "nan", lambda: calibration.gyro_bias_at_rest(with_nan(W, (2, 0)))),
    bad("calibration.gyro_bias_at_rest", "C_bn", "missing", lambda: calibration.gyro_bias_at_rest(W, lat=0.5)),
    bad("calibration.gyro_bias_at_rest", "lat", "out_of_range", lambda: calibration.gyro_bias_at_rest(W, 2.0, np.eye(3))),
    *dtype_rows("calibration.gyro_bias_at_rest", "w_ib_b", calibration.gyro_bias_at_rest, W),
    bad("calibration.characterise", "w_ib_b", "too_short", lambda: calibration.characterise(W, F, 0.01)),
    bad("calibration.characterise", "w_ib_b", "nan", lambda: calibration.characterise(with_nan(W_REC, (5, 0)), F_REC, 0.1)),
    bad("calibration.characterise", "f_b", "shape", lambda: calibration.characterise(W_REC, F_REC[:150], 0.1)),
    bad("calibration.characterise", "dt", "irregular", lambda: calibration.characterise(W_REC, F_REC, np.linspace(0.09, 0.11, 200))),
    bad("calibration.characterise", "confidence", "one", lambda: calibration.characterise(W_REC, F_REC, 0.1, confidence=1.0)),
    *dtype_rows("calibration.characterise", "f_b", lambda f: calibration.characterise(W_REC, f, 0.1), F_REC),
    bad("io.from_dataframe", "df", "not_a_frame", lambda: io.from_dataframe({"t": [0, 1]}, time="t", units={})),
    bad("io.from_dataframe", "columns", "missing", lambda: io.from_dataframe(IO_TABLE, time="t", units={"gyro": "rad/s"},
                                                                             gyro=("gx", "gy", "nope"))),
    bad("io.from_dataframe", "units['gyro']", "unknown", lambda: io.from_dataframe(IO_TABLE, time="t", units={"gyro": "rpm"},
                                                                                   gyro=("gx", "gy", "gz"))),
    bad("io.from_dataframe", "time_unit", "unknown", lambda: io.from_dataframe(IO_TABLE, time="t", time_unit="min",
                                                                               units={"gyro": "rad/s"}, gyro=("gx", "gy", "gz"))),
    bad("io.from_dataframe", "axes", "mirror", lambda: io.from_dataframe(IO_TABLE, time="t", units={"gyro": "rad/s"},
                                                                         gyro=("gx", "gy", "gz"), axes="y,x,z")),
    bad("io.read_csv", "path", "missing", lambda: io.read_csv("no/such/file.csv", time="t", units={})),
    bad("io.read_xio", "path", "missing", lambda: io.read_xio("no/such/file.csv")),
    bad("io.read_euroc", "path", "missing", lambda: io.read_euroc("no/such/data.csv")),
    bad("io.read_sensor_logger", "directory", "missing", lambda: io.read_sensor_logger("no/such/dir")),
    bad("io.align", "t_target", "decreasing", lambda: io.align([1.0, 0.0], [0.0, 1.0], [1.0, 2.0])),
    bad("io.align", "x_source", "length", lambda: io.align([0.0, 1.0], [0.0, 1.0], [1.0, 2.0, 3.0])),
    bad("io.align", "max_gap", "negative", lambda: io.align([0.0, 1.0], [0.0, 1.0], [1.0, 2.0], max_gap=-1.0)),
    bad("io.align", "method", "unknown", lambda: io.align([0.0, 1.0], [0.0, 1.0], [1.0, 2.0], method="cubic")),
]

# --------------------------------------------- found by tools/fuzz.py (issue 15, item 4)
# Each row failed before its fix: the call was accepted (silently, or with a wrong answer), or raised an
# error that named no argument (a numpy/Python message, or another argument's name).
MIRROR = np.diag([1.0, 1.0, -1.0])                   # orthonormal, det -1: not a rotation
TAUS5 = np.array([0.1, 0.2, 0.4, 0.8, 1.6])
ADEV5 = analysis.allan_deviation_theory(TAUS5, white=1e-3, bias_instability=1e-4, correlation_time=10.0)
V4 = np.stack([np.eye(3)[:2], np.eye(3)[1:], np.eye(3)[[0, 2]], np.eye(3)[:2]]) + 0.01
R4 = np.tile(np.eye(2), (4, 1, 1))
CASES += [
    # flags and texts that were used without a check ("yes" counted as True, None as False)
    bad("attitude.euler_to_dcm", "deg", "str", lambda: attitude.euler_to_dcm(HPR0, deg="yes")),
    bad("attitude.rot", "deg", "none", lambda: attitude.rot("x", 0.1, deg=None)),
    bad("attitude.dcm_to_euler", "deg", "str", lambda: attitude.dcm_to_euler(np.eye(3), deg="no")),
    bad("earth.gravity", "deg", "none", lambda: earth.gravity(0.5, deg=None)),
    bad("earth.field_angles", "deg", "int", lambda: earth.field_angles([1.0, 20.0, -40.0], deg=1)),
    bad("earth.Ellipsoid", "name", "none", lambda: earth.Ellipsoid(None, 6378137.0, 1 / 298.257, 3.986e14, 7.29e-5)),
    bad("sensors.ImuModel", "name", "none", lambda: sensors.ImuModel(name=None)),
    bad("alignment.triad", "orthonormal", "none", lambda: alignment.triad([0.0, 0.0, 9.8], [0.0, 5e-5, 5e-5], 0.5,
                                                                           orthonormal=None)),
    bad("alignment.static_means", "strict", "str", lambda: alignment.static_means(W, F, 0.5, strict="no")),
    bad("analysis.fit_allan", "rate_random_walk", "str", lambda: analysis.fit_allan(TAUS5, ADEV5, 1000, 0.1,
                                                                                    rate_random_walk="yes")),
    bad("filters.planar_ekf.filter_grid", "fast", "none", lambda: planar_ekf.filter_grid(
        T10, np.zeros((10, 5)), np.zeros(5), Q=np.eye(5), R=np.eye(5), fast=None)),
    bad("filters.planar_ekf.covariance", "name", "none", lambda: planar_ekf.covariance(np.eye(5), None)),
    bad("montecarlo.run", "progress", "str", lambda: montecarlo.run(_mc_batch, 5, 1, progress="no")),
    bad("montecarlo.run", "label", "none", lambda: montecarlo.run(_mc_batch, 5, 1, progress=False, label=None)),
    bad("strapdown.integrate", "hold_height", "str", lambda: strapdown.integrate(LLA0, [0, 0, 0], Q1, W, F, 0.01,
                                                                               hold_height="no")),
    bad("robust.hold", "name", "none", lambda: robust.hold(np.ones((3, 3)), name=None)),
    bad("robust.hold", "axis", "zero", lambda: robust.hold(np.ones((3, 3)), axis=0)),
    bad("euler.check_pitch", "name", "none", lambda: euler.check_pitch(0.1, name=None)),
    bad("repro.check", "source", "none", lambda: repro.check("T/x", 1.0, 1.0, 0.1, None)),
    bad("repro.check", "rel", "str", lambda: repro.check("T/x", 1.0, 1.0, 0.1, "src", rel="yes")),
    bad("repro.check_range", "unit", "none", lambda: repro.check_range("T/x", 1.0, "src", upper=2.0, unit=None)),
    bad("repro.setup", "style", "str", lambda: repro.setup("zz_bad_input", style="no")),
    bad("plots.body_axes", "title", "none", lambda: plots.body_axes(axes3d(), np.eye(3), title=None)),
    bad("plots.allan", "label", "none", lambda: plots.allan(axes2d(), [1.0, 2.0], [1e-5, 1e-5], label=None)),
    bad("plots.allan", "color", "unknown", lambda: plots.allan(axes2d(), [1.0, 2.0], [1e-5, 1e-5], color="abc")),
    bad("io.from_dataframe", "time", "none", lambda: io.from_dataframe(IO_TABLE, time=None, units={"gyro": "rad/s"},
                                                                       gyro=("gx", "gy", "gz"))),
    bad("io.from_dataframe", "units", "none", lambda: io.from_dataframe(IO_TABLE, time="t", units=None,
                                                                        gyro=("gx", "gy", "gz"))),
    bad("io.from_dataframe", "gyro", "one_string", lambda: io.from_dataframe(IO_TABLE, time="t", units={"gyro": "rad/s"},
                                                                             gyro="abc")),
    bad("io.from_dataframe", "source", "none", lambda: io.from_dataframe(IO_TABLE, time="t", units={"gyro": "rad/s"},
                                                                         gyro=("gx", "gy", "gz"), source=None)),
    bad("io.read_xio", "path", "none", lambda: io.read_xio(None)),
    bad("io.read_sensor_logger", "directory", "none", lambda: io.read_sensor_logger(None)),
    bad("atmosphere.bmp180_compensate", "oss", "bool", lambda: atmosphere.bmp180_compensate(27898, 23843, CALIB, oss=True)),
    # an Earth model that is not one
    bad("earth.earth_rate_n", "ellipsoid", "none", lambda: earth.earth_rate_n(0.5, ellipsoid=None)),
    bad("earth.radii", "ellipsoid", "str", lambda: earth.radii(0.5, ellipsoid="WGS84")),
    bad("trajectory.from_profiles", "ellipsoid", "none", lambda: trajectory.from_profiles(
        T10, LLA0, np.zeros((10, 3)), np.zeros((10, 3)), ellipsoid=None)),
    # rotation matrices and quaternions that are none (one check in navlib._validate: as_dcm, as_quat)
    bad("earth.earth_rate_b", "C_bn", "mirror", lambda: earth.earth_rate_b(MIRROR, 0.5)),
    bad("attitude.ned_to_enu_dcm", "C_ned", "mirror", lambda: attitude.ned_to_enu_dcm(MIRROR)),
    bad("alignment.static_gyro_bias", "C_bn", "mirror", lambda: alignment.static_gyro_bias(W, MIRROR, 0.5)),
    bad("strapdown.error_input", "C_bn", "not_rotation", lambda: strapdown.error_input(2 * np.eye(3))),
    bad("filters.quaternion_kf.measurement_model", "q", "zero", lambda: quaternion_kf.measurement_model(
        np.zeros(4), [0.0, 20.0, -40.0])),
    bad("filters.quaternion_kf.measurement_jacobian", "q", "zero", lambda: quaternion_kf.measurement_jacobian(
        np.zeros(4), [0.0, 20.0, -40.0])),
    bad("filters.quaternion_kf.noise_input", "q", "zero", lambda: quaternion_kf.noise_input(np.zeros(4), 0.01)),
    bad("trajectory.Trajectory", "q_bn", "zero_row", lambda: _traj_with(q_bn=np.where(
        np.arange(len(TRAJ.time))[:, None] == 3, 0.0, TRAJ.q_bn))),
    # a scalar given as an array ("only 0-dimensional arrays can be converted to Python scalars")
    bad("analysis.allan_deviation", "dt", "array", lambda: analysis.allan_deviation(np.ones(100), [0.1, 0.1])),
    bad("atmosphere.classify_floor", "floor_height", "array", lambda: atmosphere.classify_floor([1.0], [3.0, 3.0])),
    bad("faults.saturate", "full_scale", "array", lambda: faults.saturate(FS, [1.0, 2.0])),
    bad("filters.zupt.detect_static", "window", "array", lambda: zupt.detect_static(W, F, 0.01, window=[0.05, 0.05])),
    bad("pdr.detect_steps", "threshold", "array", lambda: pdr.detect_steps(np.ones((10, 3)), 0.01, threshold=[1.0, 2.0])),
    bad("robust.despike", "spike_gyro", "array", lambda: robust.despike(W, F, [0.1, 0.1], 1.0)),
    bad("sensors.gauss_markov", "sigma", "array", lambda: sensors.gauss_markov((10, 3), 0.1, [1.0, 1.0], 10.0, rng())),
    bad("sensors.simulate_barometer", "p0", "array", lambda: sensors.simulate_barometer(
        T10, T10, sensors.BarometerModel(), rng(), p0=[1e5, 1e5, 1e5])),
    bad("trajectory.static", "duration", "array", lambda: trajectory.static([1.0, 2.0], 0.1, LLA0, [0, 0, 0])),
    bad("trajectory.Segment", "duration", "array", lambda: trajectory.Segment(duration=[1.0, 2.0])),
    bad("trajectory.Leg", "speed", "array", lambda: trajectory.Leg(1.0, speed=[1.0, 2.0])),
    bad("trajectory.Gait", "ramp", "array", lambda: trajectory.Gait(ramp=[1.0, 2.0])),
    bad("analysis.allan_deviation_theory", "white", "array", lambda: analysis.allan_deviation_theory(
        [1.0, 10.0], white=[1e-3, 1e-3, 1e-3])),
    bad("analysis.cramer_rao_bound", "max_cond", "str", lambda: analysis.cramer_rao_bound(V4, R4, max_cond=STR)),
    bad("analysis.lsq_covariance", "max_cond", "nan", lambda: analysis.lsq_covariance(V4, R4, max_cond=NAN)),
    bad("atmosphere.reference_pressure", "until", "none", lambda: atmosphere.reference_pressure(
        [1e5, 1e5], [0.0, 1.0], None)),
    bad("sensors.magnetic_disturbances", "amplitude", "scalar", lambda: sensors.magnetic_disturbances(
        T10, rng(), 0.1, amplitude=5.0)),
    bad("sensors.outage_mask", "outages", "none", lambda: sensors.outage_mask(T10, None)),
    bad("euler.check_pitch", "pitch", "nan", lambda: euler.check_pitch(NAN)),
    # arrays of the wrong shape or of several trials where one is expected
    bad("alignment.static_gyro_bias", "lat", "array", lambda: alignment.static_gyro_bias(W, np.eye(3), [0.5, 0.6])),
    bad("alignment.static_gyro_bias", "w_ib_b", "batch", lambda: alignment.static_gyro_bias(
        np.zeros((2, 10, 3)), np.eye(3), 0.5)),
    bad("alignment.triad", "w_ib_b", "batch_mismatch", lambda: alignment.triad(
        np.tile([0.0, 0.0, 9.8], (2, 1)), np.zeros((3, 3)), 0.5)),
    bad("analysis.normal_condition", "A", "not_square", lambda: analysis.normal_condition(np.ones((2, 3)))),
    bad("analysis.lsq_covariance", "R", "none", lambda: analysis.lsq_covariance(V4, None)),
    bad("analysis.horizontal_error", "lla_true", "epoch_mismatch", lambda: analysis.horizontal_error(
        np.zeros((0, 3)), with_lat(0.6))),
    bad("atmosphere.baro_height", "temperature", "shape", lambda: atmosphere.baro_height(
        [1e5, 9.9e4], 101325.0, [288.0, 288.0, 288.0])),
    bad("filters.zupt.error_state_matrix", "C_bn", "batch", lambda: zupt.error_state_matrix(
        np.stack([np.eye(3)] * 2), F[0])),
    bad("filters.zupt.zupt_zaru_matrix", "w_ie_n", "batch", lambda: zupt.zupt_zaru_matrix(np.eye(3), np.zeros((2, 3)))),
    bad("filters.mahony.mahony", "q0", "batch_mismatch", lambda: mahony.mahony(W, F, 0.01, np.tile(Q1, (2, 1)))),
    bad("filters.planar_ekf.propagate", "speed, yaw_rate", "yaw_rate_alone", lambda: planar_ekf.propagate(
        np.zeros(5), 0.5, yaw_rate=[0.1, 0.1, 0.1])),
    bad("pdr.pdr", "start_en", "batch", lambda: pdr.pdr([1.0, 2.0], [0.0, 0.0], start_en=[[0.0, 0.0], [0.0, 0.0]])),
    bad("sensors.simulate_magnetometer", "B_n", "epoch_mismatch", lambda: sensors.simulate_magnetometer(
        np.tile(Q1, (10, 1)), np.tile([0.0, 20.0, -40.0], (3, 1)), sensors.MagnetometerModel(), rng())),
    bad("strapdown.integrate", "q0", "batch_mismatch", lambda: strapdown.integrate(
        LLA0, [0, 0, 0], np.tile(Q1, (2, 1)), W, F, 0.01)),
    bad("strapdown.integrate_attitude", "q0", "batch_mismatch", lambda: strapdown.integrate_attitude(
        np.tile(Q1, (2, 1)), W, 0.01)),
    bad("trajectory.static", "hpr", "batch", lambda: trajectory.static(1.0, 0.1, LLA0, np.zeros((2, 3)))),
    bad("trajectory.walk", "legs", "none", lambda: trajectory.walk(None, 0.01, LLA0, 0.0)),
    bad("trajectory.vehicle", "segments", "none", lambda: trajectory.vehicle(None, 0.1, LLA0, 0.0)),
    # values that were used without a check
    bad("filters.observations.prepare_inputs", "g", "none", lambda: observations.prepare_inputs(
        W, F, 0.01, Q1, None, None, None, None, None, None, None, 0.25, None, 5, None, None, None, None)),
    bad("filters.observations.prepare_inputs", "rtk_valid", "without_heading_rtk", lambda: observations.prepare_inputs(
        W, F, 0.01, Q1, None, None, np.ones(10, bool), None, None, None, 9.8, 0.25, None, 5, None, None, None, None)),
    bad("filters.heading_fusion.rtk_at_imu_rate", "time", "decreasing", lambda: heading_fusion.rtk_at_imu_rate(
        T10[::-1], np.zeros(10), np.ones(10, bool), 2)),
    bad("filters.heading_fusion.rtk_at_imu_rate", "heading", "inf", lambda: heading_fusion.rtk_at_imu_rate(
        T10, np.full(10, INF), np.ones(10, bool), 2)),
    bad("faults.gap", "time", "decreasing", lambda: faults.gap(FS, T20[::-1], 2.0, 3.0)),
    bad("atmosphere.reference_pressure", "time", "decreasing", lambda: atmosphere.reference_pressure(
        [1e5, 1e5, 1e5], [2.0, 1.0, 0.0], 5.0)),
    bad("euler.integrate_euler", "bias_from", "without_bias_b", lambda: euler.integrate_euler(
        [0.0, 0.0, 0.0], np.zeros((4, 3)), 0.1, bias_from=[0])),
    bad("euler.integrate_euler", "dt", "time_jump", lambda: euler.integrate_euler(
        [0.0, 0.0, 0.0], np.full((4, 3), 1e-3), [0.01, 3600.0, 0.01, 0.01])),
    bad("sensors.simulate_heading", "valid", "numbers", lambda: sensors.simulate_heading(T10, rng(), 0.01,
                                                                                        valid=np.ones(10))),
    bad("calibration.MagCalibration", "residual", "negative", lambda: calibration.MagCalibration(
        np.zeros(3), np.eye(3), 50.0, residual=-1.0)),
    bad("calibration.AccelCalibration", "condition", "str", lambda: calibration.AccelCalibration(
        np.zeros(3), np.eye(3), condition=STR)),
]


def names_arg(arg):
    """Regex: the message starts with the argument name ``arg``: "<arg>: expected ...",
    or "<arg>[...] (<part>): ..." for a part of an array argument."""
    return rf"^{re.escape(arg)}(?!\w)"


@pytest.fixture
def sandbox(tmp_path, monkeypatch):
    """Throw-away repository root and repro state; figures and rcParams restored."""
    (tmp_path / "pyproject.toml").write_text("[project]\nname = 'x'\n")
    (tmp_path / "navlib").mkdir()
    monkeypatch.setenv("NAVLIB_ROOT", str(tmp_path))
    monkeypatch.setattr(repro, "_state", repro._State())
    with matplotlib.rc_context():
        yield tmp_path
    plt.close("all")


@pytest.mark.filterwarnings("ignore::RuntimeWarning")
@pytest.mark.parametrize("target, arg, call", CASES)
def test_bad_input_raises_value_error_naming_argument(target, arg, call, request):
    if target.startswith(("repro.", "plots.")):
        request.getfixturevalue("sandbox")
    try:
        with pytest.raises((ValueError, TypeError), match=names_arg(arg)):
            call()
        return
    except (Exception, pytest.fail.Exception) as exc:
        failure = f"{type(exc).__name__}: {exc}"
    # A report without traceback: formatting a traceback into this long file
    # costs ~40 ms per failure, which would dominate the run time of the xfails.
    pytest.fail(failure, pytrace=False)


# ---------------------------------------------------------------- by design

def _e(*shape):
    return np.zeros(shape)


EMPTY_BATCH = {  # call on an empty batch -> expected result shape(s)
    "attitude.wrap_pi": (lambda: attitude.wrap_pi(_e(0)), (0,)),
    "attitude.skew": (lambda: attitude.skew(_e(0, 3)), (0, 3, 3)),
    "attitude.rot": (lambda: attitude.rot("x", _e(0)), (0, 3, 3)),
    "attitude.orthonormalize": (lambda: attitude.orthonormalize(_e(0, 3, 3)), (0, 3, 3)),
    "attitude.euler_to_dcm": (lambda: attitude.euler_to_dcm(_e(0, 3)), (0, 3, 3)),
    "attitude.dcm_to_euler": (lambda: attitude.dcm_to_euler(_e(0, 3, 3)), (0, 3)),
    "attitude.euler_to_quat": (lambda: attitude.euler_to_quat(_e(0, 3)), (0, 4)),
    "attitude.quat_to_euler": (lambda: attitude.quat_to_euler(_e(0, 4)), (0, 3)),
    "attitude.quat_to_dcm": (lambda: attitude.quat_to_dcm(_e(0, 4)), (0, 3, 3)),
    "attitude.dcm_to_quat": (lambda: attitude.dcm_to_quat(_e(0, 3, 3)), (0, 4)),
    "attitude.quat_mult": (lambda: attitude.quat_mult(_e(0, 4), Q1), (0, 4)),
    "attitude.quat_rotate": (lambda: attitude.quat_rotate(_e(0, 4), _e(0, 3)), (0, 3)),
    "attitude.rotvec_to_quat": (lambda: attitude.rotvec_to_quat(_e(0, 3)), (0, 4)),
    "attitude.quat_to_rotvec": (lambda: attitude.quat_to_rotvec(_e(0, 4)), (0, 3)),
    "earth.gravity_n": (lambda: earth.gravity_n(_e(0)), (0, 3)),
    "earth.radii": (lambda: earth.radii(_e(0)), ((0,), (0,))),
    "earth.field_angles": (lambda: earth.field_angles(_e(0, 3)), ((0,), (0,), (0,))),
    "units.to_si": (lambda: units.to_si(_e(0), "deg/h"), (0,)),
    "atmosphere.isa_altitude": (lambda: atmosphere.isa_altitude(_e(0)), (0,)),
    "trajectory.smooth_ramp": (lambda: trajectory.smooth_ramp(_e(0)), (0,)),
    "plots.heading_deg": (lambda: plots.heading_deg(_e(0, 3)), (0,)),
}


@pytest.mark.parametrize("name", sorted(EMPTY_BATCH))
def test_empty_batch_gives_empty_result(name):
    """Elementwise functions map an empty batch to an empty result of the documented shape."""
    call, shape = EMPTY_BATCH[name]
    out = call()
    got = tuple(o.shape for o in out) if isinstance(out, tuple) else out.shape
    assert got == shape


def test_wrong_dtype_error_is_type_and_value_error():
    """InputTypeError is a TypeError (Python convention) and a ValueError (navlib's documented error)."""
    with pytest.raises(TypeError, match="^q: expected a real numeric array, got a complex array"):
        attitude.quat_to_dcm(np.array(Q1) + 1j)
    with pytest.raises(ValueError, match="^lat: expected a real numeric array, got a boolean value"):
        earth.gravity(True)


@pytest.mark.parametrize("func", [attitude.wrap_pi, attitude.wrap_2pi]
                         + [getattr(units, n) for n in _unit_converters()], ids=lambda f: f.__name__)
def test_nan_propagates_by_design(func):
    """NaN marks sensor dropouts: wraps and unit converters pass it through."""
    out = func(np.array([0.5, np.nan]))
    assert np.isnan(out[1]) and np.isfinite(out[0])


def test_units_to_si_propagates_nan_by_design():
    assert np.isnan(units.to_si(np.nan, "deg/h"))


def test_kalman_update_all_nan_measurement_is_no_data():
    """The update skips NaN components; with none left it reports NO_DATA."""
    x, P = np.zeros(2), np.eye(2)
    z = np.array([np.nan, np.nan])
    H = np.eye(2)
    xn, Pn, y, nis, status = kalman.update(x, P, z, H @ x, H, np.eye(2), np.zeros(2, dtype=bool), np.inf)
    assert status == kalman.NO_DATA
    assert np.all(np.isnan(y)) and np.isnan(nis)
    np.testing.assert_array_equal(xn, x)
    np.testing.assert_array_equal(Pn, P)


@pytest.mark.parametrize("call", [
    lambda: repro.check("T/nan", np.nan, 1.0, 0.1, "src"),
    lambda: repro.check_range("T/nan", np.nan, "src", upper=1.0),
], ids=["check", "check_range"])
def test_repro_nan_value_fails_the_claim(call, sandbox):
    """A NaN reproduced value is a failed claim, not a usage error."""
    with pytest.raises(repro.ClaimCheckFailed):
        call()


# ----------------------------------------------------------------- coverage

NOT_APPLICABLE = {
    "io.Recording": "a result record, built by the readers",
    "robust.FaultReport": "a plain record of counts; nothing to validate",
    "alignment.StaticWindow": "a result record, built by static_means",
    "euler.EulerReport": "a result record, built by integrate_euler",
    "pdr.StepResult": "a result record, built by detect_steps",
    "repro.root": "takes no arguments",
    "repro.results": "takes no arguments",
    "repro.verdicts": "takes no arguments",
    "repro.summary": "takes no arguments",
    "repro.ClaimCheckWarning": "warning class, issued by navlib itself",
    "repro.Verdict": "record of a verdict, built by verdict() from validated values",
    "sensors.devices": "takes no arguments",
    "repro.ClaimCheckFailed": "exception class, raised by navlib itself",
    "repro.NoOutputDirectory": "exception class, raised by navlib itself",
    "sensors.ImuOutput": "record returned by simulate_imu, not constructed by users",
    "repro.Check": "record of a check, built by check()/check_range() from validated values",
    "timing.TimingReport": "record returned by timing.sanitize, built from validated values",
    "filters.observations.AttitudeResult": "a result record, built by the attitude filters",
    "filters.planar_ekf.EkfResult": "a result record, built by filter_grid",
    "filters.heading_fusion.FusionResult": "a result record, built by fuse_rtk_heading",
    "filters.observations.AttitudeInputs": "the kernel record, built by prepare_inputs from validated values",
    "filters.observations.Screened": "a record of what prepare_inputs found, built from validated values",
    "filters.observations.attitude_result": "assembles kernel outputs (validated by prepare_inputs)",
    "filters.observations.run_trials": "runs a compiled kernel on validated inputs",
    "calibration.TriadNoise": "a result record, built by characterise",
    "calibration.NoiseCharacterisation": "a result record, built by characterise",
}


def public_callables():
    """``module.name`` of every function or class a module makes public."""
    out = set()
    for modname in MODULES:
        mod = importlib.import_module(f"navlib.{modname}")
        names = getattr(mod, "__all__", None)
        if names is None:  # fall back to the functions and classes defined in the module
            names = [n for n, o in vars(mod).items()
                     if not n.startswith("_") and getattr(o, "__module__", "") == mod.__name__]
        out |= {f"{modname}.{n}" for n in names if callable(getattr(mod, n))}
    return out


@pytest.mark.parametrize("modname", MODULES)
def test_every_module_declares_all(modname):
    assert hasattr(importlib.import_module(f"navlib.{modname}"), "__all__")


def test_every_public_callable_is_covered():
    """A new public function or class needs a row in CASES (or a documented exception)."""
    tested = {p.values[0] for p in CASES}
    missing = public_callables() - tested - set(NOT_APPLICABLE)
    assert not missing, f"public callables without a bad-input case: {sorted(missing)}"
    stale = (tested | set(NOT_APPLICABLE)) - public_callables()
    assert not stale, f"table rows for names that are not public: {sorted(stale)}"


def test_known_gaps_name_existing_cases():
    unknown = set(KNOWN_GAPS) - {p.id for p in CASES}
    assert not unknown, f"KNOWN_GAPS entries without a table row: {sorted(unknown)}"
