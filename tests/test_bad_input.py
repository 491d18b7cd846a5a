"""Bad input to every public navlib function fails loudly (project rule; issue 9, item 3).

Rule (navlib/__init__.py, "Bad input"): every public function rejects wrong
shapes, wrong dtypes, non-finite values, empty arrays and out-of-range values
with a ``ValueError`` (or ``TypeError`` for a wrong kind of value) naming the
argument and what was expected: the message *starts* with the argument name
(``"<arg>: expected ..."``, ``"<arg>[..., 1] (pitch): ..."`` for a part of an
array argument).

Every public callable is listed once, in the registry ``tools/fuzz_calls.py``
(also read by ``make fuzz``), with one valid call. From it:

* ``test_registry_call_refuses_bad_values``: the valid call works, and each of
  its arguments replaced by each bad value of tools/fuzz.py's ``MUTATIONS``
  in :data:`IN_PROCESS` (a string, a numeric string, complex, an object array,
  a ragged nested list, a boolean, None, NaN, inf, no samples, a wrong last
  axis) raises an error naming the argument -- unless tools/fuzz.py's ``BY_DESIGN`` documents the
  outcome (NaN as a dropout marker, inf as "no limit", empty batches of the
  elementwise functions, ...).
* ``test_registry_bad_row``: the registry rows' ``bad`` calls (a valid call
  with some arguments changed: a negative gain, two references at once).

``CASES`` below adds bad calls that need their own setup. Cases where navlib
does not (yet) follow the rule are listed in the registry's ``KNOWN_GAPS`` and
marked ``xfail(strict=True)``, so fixing one turns it into an XPASS that
forces the entry to be removed.

Tested here as by design: ``kalman.update`` with an all-NaN ``z`` reports
``kalman.NO_DATA``; ``repro.check`` / ``repro.check_range`` with a NaN value
fail the claim (``ClaimCheckFailed``) rather than raise ValueError; the wraps
and unit converters pass NaN through; empty *batches* give empty results.
"""

import re
import shutil
import sys
from pathlib import Path

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

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tools"))
import fuzz  # noqa: E402  (the mutations, the outcome classes, BY_DESIGN)
import fuzz_calls  # noqa: E402  (the registry: every public callable, one valid call each)

PUBLIC = fuzz_calls.public_callables()
REGISTRY = fuzz_calls.table()
CALLS = {k: fuzz.with_defaults(PUBLIC[k], c) for k, c in REGISTRY.items() if isinstance(c, fuzz_calls.Call) and k in PUBLIC}
IN_PROCESS = ("string", "numeric_str", "complex", "object", "ragged", "bool", "none", "nan", "inf", "empty", "wrong_shape")
"""The mutations run here; ``make fuzz`` runs all, in workers with a timeout (1e300 or a time jump can hang a call)."""

IO_TABLE = __import__("pandas").DataFrame({"t": [0.0, 0.01, 0.02], "gx": [0.0] * 3, "gy": [0.0] * 3, "gz": [0.0] * 3})
NAN, INF = np.nan, np.inf
Q1 = [1.0, 0.0, 0.0, 0.0]  # identity quaternion
LLA0 = [0.6, 0.2, 50.0]  # lat, lon (rad), h (m)
W = np.zeros((10, 3))  # gyro samples (rad/s)
F = np.tile([0.0, 0.0, 9.8], (10, 1))  # accelerometer samples (m/s^2)
T10 = np.arange(10.0)  # a valid time axis (s)
TRAJ = trajectory.static(1.0, 0.1, LLA0, [0.0, 0.0, 0.0])
CALIB = dict(
    AC1=408,
    AC2=-72,
    AC3=-14383,
    AC4=32741,
    AC5=32757,
    AC6=23153,  # BMP180 datasheet example
    B1=6190,
    B2=4,
    MB=-32768,
    MC=-8711,
    MD=2868,
)


def rng():
    return np.random.default_rng(0)


def legacy_rng():
    """A random source that is not a numpy.random.Generator."""
    return np.random.RandomState(0)


def with_nan(a, index):
    a = np.array(a, dtype=float)
    a[index] = np.nan
    return a


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


def gap_marks(case_id):
    """xfail(strict=True) for a known gap of the registry."""
    gap = fuzz_calls.KNOWN_GAPS.get(case_id)
    return [pytest.mark.xfail(strict=True, reason=f"navlib gap: {gap}")] if gap else []


def bad(target, arg, what, call):
    """One table row: ``call()`` must raise ValueError naming ``arg``; ``target`` is the "module.name" under test."""
    case_id = f"{target}-{arg}-{what}"
    return pytest.param(target, arg, call, id=case_id, marks=gap_marks(case_id))


CASES = [
    # ------------------------------------------------------------------ attitude
    bad("attitude.skew", "v", "shape2", lambda: attitude.skew([1.0, 2.0])),
    bad("attitude.rot", "axis", "axis_w", lambda: attitude.rot("w", 0.1)),
    bad("attitude.orthonormalize", "C", "shape3x2", lambda: attitude.orthonormalize(np.ones((3, 2)))),
    bad("attitude.euler_to_dcm", "hpr", "shape2", lambda: attitude.euler_to_dcm([0.1, 0.2])),
    bad("attitude.euler_to_dcm", "hpr", "pitch91deg", lambda: attitude.euler_to_dcm([0, 91, 0], deg=True)),
    bad("attitude.euler_to_dcm", "hpr", "pitch2rad", lambda: attitude.euler_to_dcm([0.0, -2.0, 0.0])),
    bad("attitude.dcm_to_euler", "C_bn", "shape3x2", lambda: attitude.dcm_to_euler(np.ones((3, 2)))),
    bad("attitude.dcm_to_euler", "C_bn", "not_rotation", lambda: attitude.dcm_to_euler(2 * np.eye(3))),
    bad("attitude.euler_to_quat", "hpr", "shape4", lambda: attitude.euler_to_quat([0.0, 0.0, 0.0, 0.0])),
    bad("attitude.euler_to_quat", "hpr", "pitch100deg", lambda: attitude.euler_to_quat([0, 100, 0], deg=True)),
    bad("attitude.quat_to_euler", "q", "shape3", lambda: attitude.quat_to_euler([1.0, 0.0, 0.0])),
    bad("attitude.quat_to_euler", "q", "zero", lambda: attitude.quat_to_euler([0.0, 0.0, 0.0, 0.0])),
    bad("attitude.quat_to_dcm", "q", "shape3", lambda: attitude.quat_to_dcm(np.ones((5, 3)))),
    bad("attitude.quat_to_dcm", "q", "zero", lambda: attitude.quat_to_dcm(np.zeros(4))),
    bad("attitude.dcm_to_quat", "C_bn", "shape2x3", lambda: attitude.dcm_to_quat(np.ones((2, 3)))),
    bad("attitude.dcm_to_quat", "C_bn", "reflection", lambda: attitude.dcm_to_quat(-np.eye(3))),
    bad("attitude.quat_mult", "p", "shape3", lambda: attitude.quat_mult([1.0, 0.0, 0.0], Q1)),
    bad("attitude.quat_conj", "q", "shape3", lambda: attitude.quat_conj([1.0, 0.0, 0.0])),
    bad("attitude.quat_normalize", "q", "shape5", lambda: attitude.quat_normalize(np.ones(5))),
    bad("attitude.quat_normalize", "q", "zero", lambda: attitude.quat_normalize(np.zeros(4))),
    bad("attitude.ned_to_enu", "v", "shape2", lambda: attitude.ned_to_enu([1.0, 2.0])),
    bad("attitude.ned_to_enu_quat", "q_ned", "zero", lambda: attitude.ned_to_enu_quat(np.zeros(4))),
    bad("attitude.ned_to_enu_quat", "q_ned", "shape3", lambda: attitude.ned_to_enu_quat([1.0, 0.0, 0.0])),
    bad("attitude.ypr_to_hpr", "ypr", "pitch2rad", lambda: attitude.ypr_to_hpr([0.0, 2.0, 0.0])),
    bad("attitude.mount_matrix", "axes", "repeated", lambda: attitude.mount_matrix("x,x,z")),
    bad("attitude.mount_matrix", "axes", "mirror", lambda: attitude.mount_matrix("y,x,z")),
    bad("attitude.mount_matrix", "axes", "not_rotation", lambda: attitude.mount_matrix(2 * np.eye(3))),
    bad("attitude.mount_matrix", "axes", "shape", lambda: attitude.mount_matrix(np.eye(2))),
    bad("attitude.quat_rotate", "q", "shape3", lambda: attitude.quat_rotate([1.0, 0.0, 0.0], [1.0, 0.0, 0.0])),
    bad("attitude.quat_rotate", "v_b", "shape2", lambda: attitude.quat_rotate(Q1, [1.0, 0.0])),
    bad("attitude.rotvec_to_dcm", "rv", "shape4", lambda: attitude.rotvec_to_dcm(np.zeros(4))),
    bad("attitude.dcm_to_rotvec", "C", "shape3x2", lambda: attitude.dcm_to_rotvec(np.ones((3, 2)))),
    bad("attitude.dcm_to_rotvec", "C", "not_rotation", lambda: attitude.dcm_to_rotvec(np.ones((3, 3)))),
    bad("attitude.rotvec_to_quat", "rv", "shape2", lambda: attitude.rotvec_to_quat([0.1, 0.2])),
    bad("attitude.quat_to_rotvec", "q", "shape3", lambda: attitude.quat_to_rotvec([1.0, 0.0, 0.0])),
    # --------------------------------------------------------------------- earth
    bad("earth.Ellipsoid", "a", "negative", lambda: earth.Ellipsoid("bad", -6378137.0, 1 / 298.257, 3.986e14, 7.29e-5)),
    bad("earth.earth_rate_n", "lat", "lat91deg", lambda: earth.earth_rate_n(91.0, deg=True)),
    bad("earth.earth_rate_n", "lat", "lat2rad", lambda: earth.earth_rate_n(2.0)),
    bad("earth.gravity", "lat", "lat91deg", lambda: earth.gravity(-91.0, deg=True)),
    bad("earth.gravity", "h", "h_1e7", lambda: earth.gravity(0.5, 1e7)),
    bad("earth.gravity_n", "lat", "lat2rad", lambda: earth.gravity_n(2.0)),
    bad("earth.radii", "lat", "lat-91deg", lambda: earth.radii(-91.0, deg=True)),
    bad("earth.transport_rate_n", "lat", "lat2rad", lambda: earth.transport_rate_n(2.0, 0.0, [1.0, 0.0, 0.0])),
    bad("earth.transport_rate_n", "vel_n", "shape2", lambda: earth.transport_rate_n(0.5, 0.0, [1.0, 0.0])),
    bad("earth.magnetic_field", "lat", "lat91deg", lambda: earth.magnetic_field(91.0, 10.0)),
    bad("earth.magnetic_field", "lat", "lat2rad", lambda: earth.magnetic_field(2.0, 0.1, deg=False)),
    bad("earth.magnetic_field", "year", "year1990", lambda: earth.magnetic_field(45.0, 10.0, year=1990.0)),
    bad("earth.field_from_angles", "inclination", "incl91deg", lambda: earth.field_from_angles(0.0, 91.0, 50.0)),
    bad("earth.field_from_angles", "intensity", "negative", lambda: earth.field_from_angles(0.0, 60.0, -50.0)),
    bad("earth.field_angles", "B_n", "shape2", lambda: earth.field_angles([20.0, -40.0])),
    # ------------------------------------------------------------------- units
    bad("units.to_si", "unit", "unknown_unit", lambda: units.to_si(1.0, "furlong")),
    bad("units.to_si", "unit", "unit_not_str", lambda: units.to_si(1.0, 5)),
    # ----------------------------------------------------------------- sensors
    bad("sensors.TriadErrors", "noise_density", "negative", lambda: sensors.TriadErrors(noise_density=-1.0)),
    bad("sensors.TriadErrors", "correlation_time", "zero", lambda: sensors.TriadErrors(correlation_time=0.0)),
    bad("sensors.TriadErrors", "full_scale", "zero", lambda: sensors.TriadErrors(full_scale=0.0)),
    bad("sensors.simulate_imu", "w_ib_b", "shape2", lambda: sensors.simulate_imu(W[:, :2], F, 0.01, sensors.ImuModel(), rng())),
    bad(
        "sensors.simulate_imu",
        "w_ib_b",
        "empty",
        lambda: sensors.simulate_imu(np.zeros((0, 3)), np.zeros((0, 3)), 0.01, sensors.ImuModel(), rng()),
    ),
    bad("sensors.simulate_imu", "f_b", "shape_mismatch", lambda: sensors.simulate_imu(W, F[:5], 0.01, sensors.ImuModel(), rng())),
    bad("sensors.simulate_imu", "dt", "zero", lambda: sensors.simulate_imu(W, F, 0.0, sensors.ImuModel(), rng())),
    bad("sensors.simulate_imu", "rng", "legacy_rng", lambda: sensors.simulate_imu(W, F, 0.01, sensors.ImuModel(), legacy_rng())),
    bad("sensors.simulate_imu", "rng", "int", lambda: sensors.simulate_imu(W, F, 0.01, sensors.ImuModel(), 42)),
    bad(
        "sensors.simulate_imu",
        "n_trials",
        "zero",
        lambda: sensors.simulate_imu(W, F, 0.01, sensors.ImuModel(), rng(), n_trials=0),
    ),
    bad("sensors.imu_model", "device", "unknown", lambda: sensors.imu_model("NO-SUCH-IMU")),
    bad("sensors.imu_model", "device", "no_imu_preset", lambda: sensors.imu_model("BMP180")),
    bad("sensors.preset", "device", "unknown", lambda: sensors.preset("NO-SUCH-DEVICE")),
    bad("sensors.preset", "device", "list", lambda: sensors.preset(["MTi-100"])),
    bad("sensors.MagnetometerModel", "noise", "negative", lambda: sensors.MagnetometerModel(noise=-1.0)),
    bad(
        "sensors.simulate_magnetometer",
        "q_bn",
        "shape3",
        lambda: sensors.simulate_magnetometer(np.ones((10, 3)), [0.0, 20.0, -40.0], sensors.MagnetometerModel(), rng()),
    ),
    bad(
        "sensors.simulate_magnetometer",
        "q_bn",
        "empty",
        lambda: sensors.simulate_magnetometer(np.zeros((0, 4)), [0.0, 20.0, -40.0], sensors.MagnetometerModel(), rng()),
    ),
    bad(
        "sensors.simulate_magnetometer",
        "q_bn",
        "zero_quat",
        lambda: sensors.simulate_magnetometer(np.zeros((10, 4)), [0.0, 20.0, -40.0], sensors.MagnetometerModel(), rng()),
    ),
    bad(
        "sensors.simulate_magnetometer",
        "B_n",
        "shape2",
        lambda: sensors.simulate_magnetometer(np.tile(Q1, (10, 1)), [20.0, -40.0], sensors.MagnetometerModel(), rng()),
    ),
    bad(
        "sensors.simulate_magnetometer",
        "disturbance_n",
        "inf",
        lambda: sensors.simulate_magnetometer(
            np.tile(Q1, (10, 1)), [0.0, 20.0, -40.0], sensors.MagnetometerModel(), rng(), disturbance_n=np.full((10, 3), INF)
        ),
    ),
    bad(
        "sensors.simulate_magnetometer",
        "rng",
        "legacy_rng",
        lambda: sensors.simulate_magnetometer(
            np.tile(Q1, (10, 1)), [0.0, 20.0, -40.0], sensors.MagnetometerModel(), legacy_rng()
        ),
    ),
    bad("sensors.magnetic_disturbances", "time", "one_sample", lambda: sensors.magnetic_disturbances([0.0], rng(), 0.1)),
    bad("sensors.magnetic_disturbances", "time", "decreasing", lambda: sensors.magnetic_disturbances(T10[::-1], rng(), 0.1)),
    bad("sensors.magnetic_disturbances", "rate", "negative", lambda: sensors.magnetic_disturbances(T10, rng(), -0.1)),
    bad("sensors.magnetic_disturbances", "rng", "legacy_rng", lambda: sensors.magnetic_disturbances(T10, legacy_rng(), 0.1)),
    bad(
        "sensors.magnetic_disturbances",
        "duration",
        "negative",
        lambda: sensors.magnetic_disturbances(T10, rng(), 1.0, duration=(-5.0, -2.0)),
    ),
    bad("sensors.BarometerModel", "noise", "negative", lambda: sensors.BarometerModel(noise=-1.0)),
    bad(
        "sensors.simulate_barometer",
        "h",
        "length_mismatch",
        lambda: sensors.simulate_barometer(T10[:5], T10, sensors.BarometerModel(), rng()),
    ),
    bad(
        "sensors.simulate_barometer",
        "h",
        "h_20km",
        lambda: sensors.simulate_barometer(T10 + 20e3, T10, sensors.BarometerModel(), rng()),
    ),
    bad(
        "sensors.simulate_barometer",
        "time",
        "one_sample",
        lambda: sensors.simulate_barometer([0.0], [0.0], sensors.BarometerModel(), rng()),
    ),
    bad(
        "sensors.simulate_barometer",
        "p0",
        "negative",
        lambda: sensors.simulate_barometer(T10, T10, sensors.BarometerModel(), rng(), p0=-1.0),
    ),
    bad(
        "sensors.simulate_barometer",
        "rng",
        "legacy_rng",
        lambda: sensors.simulate_barometer(T10, T10, sensors.BarometerModel(), legacy_rng()),
    ),
    bad("sensors.outage_mask", "time", "empty", lambda: sensors.outage_mask([], [(2.0, 3.0)])),
    bad("sensors.outage_mask", "outages", "end_before_start", lambda: sensors.outage_mask(T10, [(5.0, 1.0)])),
    bad("sensors.outage_mask", "outages", "not_pairs", lambda: sensors.outage_mask(T10, [(5.0,)])),
    bad("sensors.simulate_gnss_position", "lla", "shape2", lambda: sensors.simulate_gnss_position(np.zeros((10, 2)), rng(), 3.0)),
    bad("sensors.simulate_gnss_position", "lla", "empty", lambda: sensors.simulate_gnss_position(np.zeros((0, 3)), rng(), 3.0)),
    bad("sensors.simulate_gnss_position", "lla", "lat2rad", lambda: sensors.simulate_gnss_position(with_lat(2.0), rng(), 3.0)),
    bad(
        "sensors.simulate_gnss_position",
        "sigma_horizontal",
        "negative",
        lambda: sensors.simulate_gnss_position(with_lat(0.6), rng(), -3.0),
    ),
    bad(
        "sensors.simulate_gnss_position",
        "rng",
        "legacy_rng",
        lambda: sensors.simulate_gnss_position(with_lat(0.6), legacy_rng(), 3.0),
    ),
    bad(
        "sensors.simulate_gnss_position",
        "valid",
        "length_mismatch",
        lambda: sensors.simulate_gnss_position(with_lat(0.6), rng(), 3.0, valid=np.ones(4, dtype=bool)),
    ),
    bad("sensors.simulate_heading", "heading", "empty", lambda: sensors.simulate_heading([], rng(), 0.01)),
    bad("sensors.simulate_heading", "sigma", "negative", lambda: sensors.simulate_heading(T10, rng(), -0.01)),
    bad(
        "sensors.simulate_heading",
        "valid",
        "length_mismatch",
        lambda: sensors.simulate_heading(T10, rng(), 0.01, valid=[True] * 3),
    ),
    bad("sensors.simulate_heading", "rng", "legacy_rng", lambda: sensors.simulate_heading(T10, legacy_rng(), 0.01)),
    bad("sensors.gauss_markov", "shape", "1d", lambda: sensors.gauss_markov((10,), 0.1, 1.0, 10.0, rng())),
    bad("sensors.gauss_markov", "dt", "zero", lambda: sensors.gauss_markov((10, 3), 0.0, 1.0, 10.0, rng())),
    bad("sensors.gauss_markov", "correlation_time", "negative", lambda: sensors.gauss_markov((10, 3), 0.1, 1.0, -10.0, rng())),
    bad("sensors.gauss_markov", "sigma", "negative", lambda: sensors.gauss_markov((10, 3), 0.1, -1.0, 10.0, rng())),
    bad("sensors.gauss_markov", "rng", "legacy_rng", lambda: sensors.gauss_markov((10, 3), 0.1, 1.0, 10.0, legacy_rng())),
    # -------------------------------------------------------------- atmosphere
    bad("atmosphere.isa_altitude", "p", "negative", lambda: atmosphere.isa_altitude(-100.0)),
    bad("atmosphere.isa_altitude", "p", "above_troposphere", lambda: atmosphere.isa_altitude(1000.0)),
    bad("atmosphere.isa_altitude", "p0", "zero", lambda: atmosphere.isa_altitude(9e4, 0.0)),
    bad("atmosphere.isa_pressure", "h", "h_20km", lambda: atmosphere.isa_pressure(20e3)),
    bad("atmosphere.isa_pressure", "p0", "negative", lambda: atmosphere.isa_pressure(100.0, -1.0)),
    bad("atmosphere.bmp180_altitude", "p", "zero", lambda: atmosphere.bmp180_altitude(0.0)),
    bad("atmosphere.bmp180_pressure", "h", "h_50km", lambda: atmosphere.bmp180_pressure(50e3)),
    bad("atmosphere.hypsometric_height", "p", "negative", lambda: atmosphere.hypsometric_height(-1.0, 1e5, 288.0)),
    bad("atmosphere.hypsometric_height", "temperature", "400K", lambda: atmosphere.hypsometric_height(9e4, 1e5, 400.0)),
    bad("atmosphere.bmp180_compensate", "oss", "oss4", lambda: atmosphere.bmp180_compensate(27898, 23843, CALIB, oss=4)),
    bad(
        "atmosphere.bmp180_compensate",
        "calib",
        "missing_key",
        lambda: atmosphere.bmp180_compensate(27898, 23843, {k: v for k, v in CALIB.items() if k != "MD"}),
    ),
    bad(
        "atmosphere.bmp180_compensate",
        "calib",
        "nan_coefficient",
        lambda: atmosphere.bmp180_compensate(27898, 23843, {**CALIB, "AC1": NAN}),
    ),
    bad("atmosphere.bmp180_compensate", "UT", "nan", lambda: atmosphere.bmp180_compensate(NAN, 23843, CALIB)),
    # -------------------------------------------------------------- trajectory
    bad("trajectory.Trajectory", "time", "one_sample", lambda: trajectory.Trajectory([0.0], [LLA0], [[0, 0, 0]], [Q1])),
    bad(
        "trajectory.Trajectory", "lla", "shape2", lambda: trajectory.Trajectory(TRAJ.time, TRAJ.lla[:, :2], TRAJ.vel_n, TRAJ.q_bn)
    ),
    bad(
        "trajectory.Trajectory",
        "q_bn",
        "epoch_mismatch",
        lambda: trajectory.Trajectory(TRAJ.time, TRAJ.lla, TRAJ.vel_n, TRAJ.q_bn[:5]),
    ),
    bad(
        "trajectory.Trajectory", "lla", "lat2rad", lambda: trajectory.Trajectory(TRAJ.time, with_lat(2.0), TRAJ.vel_n, TRAJ.q_bn)
    ),
    bad("trajectory.Trajectory", "faults", "dict", lambda: trajectory.Trajectory(TRAJ.time, TRAJ.lla, TRAJ.vel_n, TRAJ.q_bn, {})),
    bad("trajectory.Segment", "duration", "negative", lambda: trajectory.Segment(duration=-1.0)),
    bad("trajectory.Segment", "pitch", "pitch2rad", lambda: trajectory.Segment(duration=1.0, pitch=2.0)),
    bad("trajectory.static", "duration", "zero", lambda: trajectory.static(0.0, 0.1, LLA0, [0, 0, 0])),
    bad("trajectory.static", "dt", "negative", lambda: trajectory.static(1.0, -0.1, LLA0, [0, 0, 0])),
    bad("trajectory.static", "lla0", "shape2", lambda: trajectory.static(1.0, 0.1, LLA0[:2], [0, 0, 0])),
    bad("trajectory.static", "lla0", "lat2rad", lambda: trajectory.static(1.0, 0.1, [2.0, 0.0, 0.0], [0, 0, 0])),
    bad("trajectory.static", "hpr", "shape2", lambda: trajectory.static(1.0, 0.1, LLA0, [0, 0])),
    bad("trajectory.static", "hpr", "pitch2rad", lambda: trajectory.static(1.0, 0.1, LLA0, [0.0, 2.0, 0.0])),
    bad(
        "trajectory.from_profiles",
        "time",
        "non_uniform",
        lambda: trajectory.from_profiles(T10**2, LLA0, np.zeros((10, 3)), np.zeros((10, 3))),
    ),
    bad(
        "trajectory.from_profiles",
        "time",
        "empty",
        lambda: trajectory.from_profiles([], LLA0, np.zeros((0, 3)), np.zeros((0, 3))),
    ),
    bad(
        "trajectory.from_profiles",
        "hpr",
        "epoch_mismatch",
        lambda: trajectory.from_profiles(T10, LLA0, np.zeros((9, 3)), np.zeros((10, 3))),
    ),
    bad(
        "trajectory.from_profiles",
        "hpr",
        "pitch2rad",
        lambda: trajectory.from_profiles(T10, LLA0, np.tile([0.0, 2.0, 0.0], (10, 1)), np.zeros((10, 3))),
    ),
    bad(
        "trajectory.from_profiles",
        "lla0",
        "lat91deg_in_rad_call",
        lambda: trajectory.from_profiles(T10, [np.deg2rad(91.0), 0.0, 0.0], np.zeros((10, 3)), np.zeros((10, 3))),
    ),
    bad(
        "trajectory.reciprocating_rotation",
        "duration",
        "negative",
        lambda: trajectory.reciprocating_rotation(-10.0, 0.1, LLA0, [0, 0, 0], [0, 0, 1], np.pi / 2, 4.0),
    ),
    bad(
        "trajectory.reciprocating_rotation",
        "axis_b",
        "not_unit",
        lambda: trajectory.reciprocating_rotation(10.0, 0.1, LLA0, [0, 0, 0], [0, 0, 2], np.pi / 2, 4.0),
    ),
    bad(
        "trajectory.reciprocating_rotation",
        "axis_b",
        "shape2",
        lambda: trajectory.reciprocating_rotation(10.0, 0.1, LLA0, [0, 0, 0], [0, 1], np.pi / 2, 4.0),
    ),
    bad(
        "trajectory.reciprocating_rotation",
        "period",
        "zero",
        lambda: trajectory.reciprocating_rotation(10.0, 0.1, LLA0, [0, 0, 0], [0, 0, 1], np.pi / 2, 0.0),
    ),
    bad(
        "trajectory.reciprocating_rotation",
        "rotation_time",
        "longer_than_period",
        lambda: trajectory.reciprocating_rotation(10.0, 0.1, LLA0, [0, 0, 0], [0, 0, 1], np.pi / 2, 4.0, 5.0),
    ),
    bad(
        "trajectory.reciprocating_rotation",
        "hpr0",
        "pitch2rad",
        lambda: trajectory.reciprocating_rotation(10.0, 0.1, LLA0, [0, 2.0, 0], [0, 0, 1], np.pi / 2, 4.0),
    ),
    bad("trajectory.vehicle", "segments", "empty", lambda: trajectory.vehicle([], 0.1, LLA0, 0.0)),
    bad("trajectory.vehicle", "segments", "not_segments", lambda: trajectory.vehicle([(10.0, 5.0)], 0.1, LLA0, 0.0)),
    bad("trajectory.vehicle", "dt", "zero", lambda: trajectory.vehicle([trajectory.Segment(2.0, speed=5.0)], 0.0, LLA0, 0.0)),
    bad(
        "trajectory.vehicle",
        "lla0",
        "lat2rad",
        lambda: trajectory.vehicle([trajectory.Segment(2.0, speed=5.0)], 0.1, [2.0, 0.0, 0.0], 0.0),
    ),
    bad(
        "trajectory.ideal_imu",
        "traj",
        "nan_position",
        lambda: trajectory.ideal_imu(trajectory.Trajectory(TRAJ.time, with_nan(TRAJ.lla, (3, 0)), TRAJ.vel_n, TRAJ.q_bn)),
    ),
    # --------------------------------------------------------------- strapdown
    bad("strapdown.integrate_attitude", "q0", "shape3", lambda: strapdown.integrate_attitude([1.0, 0.0, 0.0], W, 0.01)),
    bad("strapdown.integrate_attitude", "q0", "zero", lambda: strapdown.integrate_attitude(np.zeros(4), W, 0.01)),
    bad("strapdown.integrate_attitude", "w_ib_b", "shape2", lambda: strapdown.integrate_attitude(Q1, W[:, :2], 0.01)),
    bad("strapdown.integrate_attitude", "w_ib_b", "empty", lambda: strapdown.integrate_attitude(Q1, np.zeros((0, 3)), 0.01)),
    bad("strapdown.integrate_attitude", "dt", "zero", lambda: strapdown.integrate_attitude(Q1, W, 0.0)),
    bad("strapdown.integrate_attitude", "w_in_n", "shape2", lambda: strapdown.integrate_attitude(Q1, W, 0.01, [0.0, 1e-5])),
    bad("strapdown.integrate", "lla0", "lat2rad", lambda: strapdown.integrate([2.0, 0.0, 0.0], [0, 0, 0], Q1, W, F, 0.01)),
    bad(
        "strapdown.integrate",
        "lla0",
        "pole",
        lambda: strapdown.integrate([np.deg2rad(89.95), 0.0, 0.0], [0, 0, 0], Q1, W, F, 0.01),
    ),
    bad("strapdown.integrate", "vel0", "shape2", lambda: strapdown.integrate(LLA0, [0, 0], Q1, W, F, 0.01)),
    bad("strapdown.integrate", "q0", "shape3", lambda: strapdown.integrate(LLA0, [0, 0, 0], [1.0, 0, 0], W, F, 0.01)),
    bad(
        "strapdown.integrate",
        "w_ib_b",
        "empty",
        lambda: strapdown.integrate(LLA0, [0, 0, 0], Q1, np.zeros((0, 3)), np.zeros((0, 3)), 0.01),
    ),
    bad("strapdown.integrate", "f_b", "shape2", lambda: strapdown.integrate(LLA0, [0, 0, 0], Q1, W, F[:, :2], 0.01)),
    bad("strapdown.integrate", "f_b", "epoch_mismatch", lambda: strapdown.integrate(LLA0, [0, 0, 0], Q1, W, F[:7], 0.01)),
    bad("strapdown.integrate", "dt", "negative", lambda: strapdown.integrate(LLA0, [0, 0, 0], Q1, W, F, -0.01)),
    bad("strapdown.error_model", "lat", "lat2rad", lambda: strapdown.error_model(2.0, 0.0, [0, 0, 0], [0, 0, 9.8])),
    bad("strapdown.error_model", "vel_n", "shape2", lambda: strapdown.error_model(0.6, 0.0, [0, 0], [0, 0, 9.8])),
    bad("strapdown.error_input", "C_bn", "shape3x2", lambda: strapdown.error_input(np.ones((3, 2)))),
    # ------------------------------------------------------------------ kalman
    # ---------------------------------------------------------------- analysis
    bad("analysis.rmse", "err", "empty", lambda: analysis.rmse([])),
    bad("analysis.rmse", "axis", "out_of_bounds", lambda: analysis.rmse([1.0, 2.0], axis=3)),
    bad("analysis.attitude_errors", "hpr", "shape", lambda: analysis.attitude_errors([0.0, 1.0], [0.0, 0.0, 0.0])),
    bad(
        "analysis.error_statistics", "hpr_true", "shape", lambda: analysis.error_statistics(np.zeros((2, 5, 3)), np.zeros((4, 3)))
    ),
    bad("analysis.expanding_std", "x", "empty", lambda: analysis.expanding_std([])),
    bad("analysis.settling_time", "tol", "zero", lambda: analysis.settling_time([0.0, 1.0], [1.0, 0.0], 0.0, 0.0)),
    bad("alignment.level", "f_b", "zero", lambda: alignment.level([0.0, 0.0, 0.0])),
    bad("alignment.tilt_heading", "m_b", "parallel", lambda: alignment.tilt_heading([0.0, 0.0, 9.8], [0.0, 0.0, 1.0])),
    bad("alignment.gyrocompass_latitude", "lat", "polar", lambda: alignment.gyrocompass_latitude(89.5, deg=True)),
    bad("alignment.static_means", "f_b", "shape", lambda: alignment.static_means(np.zeros((10, 3)), np.zeros((10, 2)), 0.5)),
    bad("alignment.static_means", "stuck_fraction", "negative", lambda: alignment.static_means(W, F, 0.5, stuck_fraction=-0.5)),
    bad("alignment.static_means", "stuck_fraction", "nan", lambda: alignment.static_means(W, F, 0.5, stuck_fraction=NAN)),
    bad("alignment.static_means", "stuck_fraction", "above_one", lambda: alignment.static_means(W, F, 0.5, stuck_fraction=1.5)),
    bad("alignment.triad_heading", "C_bn", "shape", lambda: alignment.triad_heading(np.eye(2))),
    bad("alignment.four_position_heading", "w_y", "shape", lambda: alignment.four_position_heading([1.0, 2.0, 3.0])),
    bad("alignment.static_gyro_bias", "C_bn", "shape", lambda: alignment.static_gyro_bias(np.zeros((5, 3)), np.eye(2), 0.5)),
    bad("analysis.segments", "mask", "not_bool", lambda: analysis.segments([0.0, 1.0])),
    bad("atmosphere.baro_height", "p", "negative", lambda: atmosphere.baro_height([100000.0, -5.0], 101325.0)),
    bad(
        "atmosphere.reference_pressure", "until", "no_sample", lambda: atmosphere.reference_pressure([NAN, NAN], [0.0, 1.0], 5.0)
    ),
    bad("atmosphere.classify_floor", "floor_height", "zero", lambda: atmosphere.classify_floor([1.0], floor_height=0.0)),
    bad("attitude.ned_to_enu_dcm", "C_ned", "shape", lambda: attitude.ned_to_enu_dcm(np.eye(2))),
    bad("euler.check_pitch", "pitch", "at_90_deg", lambda: euler.check_pitch(np.pi / 2)),
    bad("euler.euler_rates", "w_nb_b", "shape", lambda: euler.euler_rates([0.0, 0.0, 0.0], [1.0, 2.0])),
    bad("euler.integrate_euler", "dt", "negative", lambda: euler.integrate_euler([0.0, 0.0, 0.0], np.zeros((4, 3)), -0.1)),
    bad("analysis.moving_mean", "n", "too_long", lambda: analysis.moving_mean(np.ones(3), 5)),
    bad("pdr.detect_steps", "threshold", "zero", lambda: pdr.detect_steps(np.ones((10, 3)), 0.01, threshold=0.0)),
    bad("pdr.weinberg_step_length", "K", "negative", lambda: pdr.weinberg_step_length([1.0], K=-1.0)),
    bad("pdr.pdr", "step_headings", "shape", lambda: pdr.pdr([1.0, 2.0], [0.0])),
    bad("robust.hold", "leading", "unknown", lambda: robust.hold(np.ones((3, 3)), leading="back")),
    bad("robust.hold", "x", "all_nan", lambda: robust.hold(np.full((3, 3), NAN), leading="first")),
    bad("robust.despike", "spike_gyro", "zero", lambda: robust.despike(W, F, 0.0, 1.0)),
    bad("robust.despike", "f_b", "shape", lambda: robust.despike(W, F[:5], 0.1, 1.0)),
    bad("robust.fault_report", "x", "shape1", lambda: robust.fault_report(np.zeros(5), "gyro")),
    bad("robust.fault_report", "sensor", "not_str", lambda: robust.fault_report(W, 1)),
    bad("robust.fault_report", "full_scale", "negative", lambda: robust.fault_report(W, "gyro", full_scale=-1.0)),
    bad("robust.fault_report", "flags", "not_bool", lambda: robust.fault_report(W, "gyro", flags=1)),
    bad("robust.stuck_mask", "x", "shape1", lambda: robust.stuck_mask(np.zeros(5), 3)),
    bad("robust.stuck_mask", "run", "one", lambda: robust.stuck_mask(W, 1)),
    bad("robust.stuck_mask", "axis", "zero", lambda: robust.stuck_mask(W, 3, axis=0)),
    bad("robust.stuck_samples", "run", "one", lambda: robust.stuck_samples(W, 1)),
    bad("robust.stuck_samples", "full_scale", "zero", lambda: robust.stuck_samples(W, 3, full_scale=0.0)),
    bad("robust.stuck_samples", "axis", "zero", lambda: robust.stuck_samples(W, 3, axis=0)),
    bad("imu.SensorLimits", "stuck_run", "one", lambda: imu.SensorLimits(stuck_run=1)),
    bad("imu.SensorLimits", "stuck_run", "str", lambda: imu.SensorLimits(stuck_run="Auto")),
    bad("robust.longest_repeat", "x", "1-D", lambda: robust.longest_repeat([1.0, 2.0, 3.0])),
    bad("robust.longest_repeat", "valid", "shape", lambda: robust.longest_repeat(W, np.ones(3, bool))),
    bad("robust.longest_repeat", "valid", "numbers", lambda: robust.longest_repeat(W, np.ones(len(W)))),
    bad("sensors.window_mean_std", "errors", "wrong_type", lambda: sensors.window_mean_std("NAV-FOG", 180.0, 0.01)),
    bad("sensors.window_mean_std", "duration", "zero", lambda: sensors.window_mean_std(sensors.TriadErrors(), 0.0, 0.01)),
    bad("analysis.normal_condition", "A", "scalar", lambda: analysis.normal_condition(1.0)),
    bad("analysis.condition_number", "V", "no_blocks", lambda: analysis.condition_number(np.ones((2, 3)))),
    bad("analysis.lsq_covariance", "R", "shape", lambda: analysis.lsq_covariance(np.ones((4, 2, 3)), np.ones((4, 3, 3)))),
    bad("analysis.lsq_covariance", "V", "unobservable", lambda: analysis.lsq_covariance(np.zeros((4, 2, 3)), np.ones((4, 2, 2)))),
    bad("imu.ImuSamples", "f_b", "shape", lambda: imu.ImuSamples(W, F[:5], 0.01)),
    bad("imu.ImuSamples", "dt", "negative", lambda: imu.ImuSamples(W, F, -0.01)),
    bad("imu.ImuSamples", "time", "repeated_times", lambda: imu.ImuSamples.from_times(np.zeros(11), W, F)),
    bad("imu.unpack", "dt", "given_twice", lambda: imu.unpack(imu.ImuSamples(W, F, 0.01), dt=0.01)),
    bad("imu.unpack", "f_b", "missing", lambda: imu.unpack(W)),
    bad("earth.earth_rate_b", "C_bn", "shape", lambda: earth.earth_rate_b(np.eye(2), 0.5)),
    bad("earth.earth_rate_b", "lat", "array", lambda: earth.earth_rate_b(np.eye(3), [0.5, 0.6])),
    bad("trajectory.Leg", "duration", "zero", lambda: trajectory.Leg(0.0)),
    bad("trajectory.Leg", "turn, climb", "turn_on_a_stop", lambda: trajectory.Leg(5.0, 0.0, turn=1.0)),
    bad("trajectory.Gait", "ramp", "negative", lambda: trajectory.Gait(ramp=-1.0)),
    bad("trajectory.walk", "legs", "empty", lambda: trajectory.walk([], 0.01, LLA0, 0.0)),
    bad("trajectory.stance_mask", "gait", "wrong_type", lambda: trajectory.stance_mask([trajectory.Leg(1.0)], 0.01, gait=1.0)),
    bad("analysis.allan_deviation", "x", "too_short", lambda: analysis.allan_deviation(np.ones(5), 0.1)),
    bad("analysis.allan_deviation", "x", "empty", lambda: analysis.allan_deviation([], 0.1)),
    bad("analysis.allan_deviation", "dt", "zero", lambda: analysis.allan_deviation(np.ones(100), 0.0)),
    bad("analysis.allan_deviation", "taus", "negative", lambda: analysis.allan_deviation(np.ones(100), 0.1, taus=[-1.0])),
    bad("analysis.allan_deviation", "taus", "too_long", lambda: analysis.allan_deviation(np.ones(100), 0.1, taus=[100.0])),
    bad("analysis.allan_deviation_theory", "taus", "zero", lambda: analysis.allan_deviation_theory([0.0, 1.0], white=1e-3)),
    bad(
        "analysis.allan_deviation_theory",
        "bias_instability",
        "negative",
        lambda: analysis.allan_deviation_theory([1.0, 10.0], bias_instability=-1e-4),
    ),
    bad(
        "analysis.allan_deviation_theory",
        "correlation_time",
        "zero",
        lambda: analysis.allan_deviation_theory([1.0, 10.0], bias_instability=1e-4, correlation_time=0.0),
    ),
    bad("analysis.fit_allan", "taus", "negative", lambda: analysis.fit_allan([-1.0, 2.0], [1e-3, 1e-3], 1000, 0.1)),
    bad("analysis.fit_allan", "taus", "empty", lambda: analysis.fit_allan([], [], 1000, 0.1)),
    bad("analysis.fit_allan", "adev", "zero", lambda: analysis.fit_allan([1.0, 2.0], [0.0, 1e-3], 1000, 0.1)),
    bad("analysis.fit_allan", "adev", "length_mismatch", lambda: analysis.fit_allan([1.0, 2.0, 4.0], [1e-3, 1e-3], 1000, 0.1)),
    bad("analysis.fit_allan", "n_samples", "zero", lambda: analysis.fit_allan([1.0, 2.0, 4.0], [3e-3, 2e-3, 1.5e-3], 0, 0.1)),
    bad("analysis.fit_allan", "dt", "negative", lambda: analysis.fit_allan([1.0, 2.0, 4.0], [3e-3, 2e-3, 1.5e-3], 1000, -0.1)),
    # ------------------------------------------------------------------- repro
    # (run inside the ``sandbox`` fixture: throw-away root and module state)
    bad("repro.build_dir", "notebook", "int", lambda: repro.build_dir(123)),
    bad("repro.setup", "notebook", "empty", lambda: repro.setup("", style=False)),
    bad("repro.setup", "notebook", "path", lambda: repro.setup("a/b", style=False)),
    bad("repro.setup", "notebook", "int", lambda: repro.setup(123, style=False)),
    bad(
        "repro.savefig",
        "name",
        "path",
        lambda: (repro.setup("zz_bad_input", style=False), repro.savefig(plt.figure(), "no/such/dir")),
    ),
    bad("repro.check", "value", "shape2", lambda: repro.check("T/x", [1.0, 2.0], 1.0, 0.1, "src")),
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
    bad("repro.caption", "markdown", "empty", lambda: repro.caption("  ")),
    bad(
        "repro.explorer", "draw", "not_callable", lambda: (repro.setup("zz_bad_input", style=False), repro.explorer(3.0, "x", {}))
    ),
    bad(
        "repro.explorer",
        "controls",
        "list",
        lambda: (repro.setup("zz_bad_input", style=False), repro.explorer(lambda: None, "x", [1.0])),
    ),
    bad("repro.answer", "label", "empty", lambda: repro.answer("42", label="")),
    bad("repro.env_flag", "NAVLIB_TEST_BAD_FLAG", "text", lambda: _env_flag_with("NAVLIB_TEST_BAD_FLAG", "maybe")),
    bad("repro.mode", "fast", "int", lambda: (repro.setup("zz_bad_input", style=False), repro.mode(teaching=False, fast=2))),
    bad(
        "repro.verdict",
        "claim",
        "no_paper",
        lambda: (repro.setup("zz_bad_input", style=False), repro.verdict("P000-EQ3-EULER", "reproduced")),
    ),
    # ------------------------------------------------------------------- plots
    bad("plots.body_axes", "C_bn", "shape2x2", lambda: plots.body_axes(axes3d(), np.eye(2))),
    bad("plots.allan", "adev_rad_s", "length_mismatch", lambda: plots.allan(axes2d(), [1.0, 2.0, 4.0], [1e-5, 1e-5])),
    bad("plots.allan", "taus", "negative", lambda: plots.allan(axes2d(), [-1.0, 2.0], [1e-5, 1e-5])),
    bad("plots.heading_deg", "hpr", "shape2", lambda: plots.heading_deg(np.zeros((5, 2)))),
    bad("plots.paper_value", "axis", "z", lambda: plots.paper_value(axes2d(), 1.0, "paper", axis="z")),
    bad(
        "plots.block_diagram",
        "arrows",
        "unknown_block",
        lambda: plots.block_diagram(axes2d(), {"a": (0.2, 0.5, "A")}, [("a", "b")]),
    ),
    bad("plots.block_diagram", "blocks", "short_spec", lambda: plots.block_diagram(axes2d(), {"a": (0.2, 0.5)}, [])),
    bad(
        "plots.block_diagram", "width", "above_one", lambda: plots.block_diagram(axes2d(), {"a": (0.2, 0.5, "A")}, [], width=2.0)
    ),
    bad("plots.plane_frame", "origin", "shape3", lambda: plots.plane_frame(axes2d(), (0.0, 0.0, 0.0), 30.0, ("x", "y"))),
    bad("plots.plane_frame", "labels", "one", lambda: plots.plane_frame(axes2d(), (0.0, 0.0), 30.0, ("x",))),
    bad(
        "plots.plane_frame", "length", "negative", lambda: plots.plane_frame(axes2d(), (0.0, 0.0), 30.0, ("x", "y"), length=-1.0)
    ),
    bad("plots.angle_arc", "radius", "zero", lambda: plots.angle_arc(axes2d(), (0.0, 0.0), 0.0, 0.0, 90.0)),
]


def _mc_batch(ids, streams):
    return {"x": streams.normal()}


CASES += [
    bad("montecarlo.run", "n_trials", "zero", lambda: montecarlo.run(_mc_batch, 0, 1, progress=False)),
    bad("montecarlo.run", "batch_size", "negative", lambda: montecarlo.run(_mc_batch, 5, 1, batch_size=-2)),
    bad("montecarlo.run", "batch_fn", "not_callable", lambda: montecarlo.run(None, 5, 1)),
    bad("montecarlo.TrialStreams", "seed", "nan", lambda: montecarlo.TrialStreams(NAN, [0, 1])),
    bad("montecarlo.TrialStreams", "ids", "negative", lambda: montecarlo.TrialStreams(1, [0, -1])),
    bad("montecarlo.TrialStreams", "ids", "empty", lambda: montecarlo.TrialStreams(1, [])),
]


# ------------------------------------------------------- more of issue 9
def as_object(good):
    return np.asarray(good, dtype=float).astype(object)


FS = np.tile([0.0, 0.0, 1.0], (20, 1))
T20 = np.arange(20.0)


def _traj_with(**kw):
    args = dict(time=TRAJ.time, lla=TRAJ.lla, vel_n=TRAJ.vel_n, q_bn=TRAJ.q_bn)
    args.update(kw)
    return trajectory.Trajectory(**args)


CASES += [
    # attitude
    bad("attitude.rot", "axis", "int", lambda: attitude.rot(1, 0.1)),
    bad("attitude.quat_rotate", "q", "empty_batch_mismatch", lambda: attitude.quat_rotate(np.zeros((0, 4)), np.ones((2, 3)))),
    # earth
    bad("earth.Ellipsoid", "f", "f_one", lambda: earth.Ellipsoid("bad", 6378137.0, 1.0, 3.986e14, 7.29e-5)),
    # sensors
    bad("sensors.imu_model", "device", "int", lambda: sensors.imu_model(7)),
    bad("sensors.preset", "device", "empty", lambda: sensors.preset("")),
    bad("sensors.MagnetometerModel", "full_scale", "zero", lambda: sensors.MagnetometerModel(full_scale=0.0)),
    bad("sensors.magnetic_disturbances", "time", "empty", lambda: sensors.magnetic_disturbances([], rng(), 0.1)),
    bad(
        "sensors.simulate_barometer", "time", "empty", lambda: sensors.simulate_barometer([], [], sensors.BarometerModel(), rng())
    ),
    bad("sensors.gauss_markov", "shape", "empty", lambda: sensors.gauss_markov((0, 3), 0.1, 1.0, 10.0, rng())),
    bad("sensors.gauss_markov", "correlation_time", "inf", lambda: sensors.gauss_markov((10, 3), 0.1, 1.0, INF, rng())),
    # atmosphere
    bad("atmosphere.bmp180_compensate", "UT", "fractional", lambda: atmosphere.bmp180_compensate(27898.5, 23843, CALIB)),
    bad("atmosphere.bmp180_compensate", "UP", "inf", lambda: atmosphere.bmp180_compensate(27898, INF, CALIB)),
    bad("atmosphere.bmp180_compensate", "calib", "not_dict", lambda: atmosphere.bmp180_compensate(27898, 23843, [1, 2, 3])),
    # analysis
    bad("analysis.allan_deviation", "taus", "complex", lambda: analysis.allan_deviation(np.ones(100), 0.1, taus=[1j])),
    bad("analysis.allan_deviation_theory", "taus", "empty", lambda: analysis.allan_deviation_theory([], white=1e-3)),
    bad(
        "analysis.fit_allan",
        "n_samples",
        "fractional",
        lambda: analysis.fit_allan([1.0, 2.0, 4.0], [3e-3, 2e-3, 1.5e-3], 10.5, 0.1),
    ),
    # repro
    bad("repro.check", "name", "int", lambda: repro.check(5, 1.0, 1.0, 0.1, "src")),
    bad("repro.check", "name", "empty", lambda: repro.check("", 1.0, 1.0, 0.1, "src")),
    bad("repro.check_range", "lower", "inf_above_upper", lambda: repro.check_range("T/x", 1.0, "src", lower=5.0, upper=3.0)),
    bad("repro.savefig", "name", "empty", lambda: (repro.setup("zz_bad_input", style=False), repro.savefig(plt.figure(), ""))),
    bad("repro.build_dir", "notebook", "path", lambda: repro.build_dir("../x")),
    # plots
    bad("plots.allan", "taus", "empty", lambda: plots.allan(axes2d(), [], [])),
    # montecarlo
    bad("montecarlo.run", "n_trials", "float", lambda: montecarlo.run(_mc_batch, 2.5, 1, progress=False)),
    bad("montecarlo.run", "seed", "negative", lambda: montecarlo.run(_mc_batch, 5, -1, progress=False)),
    bad("montecarlo.TrialStreams", "ids", "float", lambda: montecarlo.TrialStreams(1, [0.5, 1.5])),
    # faults
    bad("faults.dropouts", "x", "empty", lambda: faults.dropouts(np.zeros((0, 3)), 0.1, rng())),
    bad("faults.dropouts", "fraction", "above_one", lambda: faults.dropouts(FS, 1.5, rng())),
    bad("faults.dropouts", "fraction", "shape2", lambda: faults.dropouts(FS, [0.1, 0.2], rng())),
    bad("faults.dropouts", "rng", "legacy_rng", lambda: faults.dropouts(FS, 0.1, legacy_rng())),
    bad("faults.gap", "time", "length_mismatch", lambda: faults.gap(FS, T10, 2.0, 3.0)),
    bad("faults.gap", "duration", "negative", lambda: faults.gap(FS, T20, 2.0, -3.0)),
    bad("faults.spikes", "x", "empty", lambda: faults.spikes([], 0.1, 0.01, rng())),
    bad("faults.spikes", "fraction", "negative", lambda: faults.spikes(FS, -0.1, 0.01, rng())),
    bad("faults.spikes", "sigma", "negative", lambda: faults.spikes(FS, 0.1, -0.01, rng())),
    bad("faults.spikes", "sigma", "shape2", lambda: faults.spikes(FS, 0.1, [0.01, 0.02], rng())),
    bad("faults.spikes", "rng", "int", lambda: faults.spikes(FS, 0.1, 0.01, 3)),
    bad("faults.position_jumps", "lla", "shape2", lambda: faults.position_jumps(np.zeros((10, 2)), 0.1, rng())),
    bad("faults.position_jumps", "lla", "lat2rad", lambda: faults.position_jumps(with_lat(2.0), 0.1, rng())),
    bad("faults.position_jumps", "lla", "empty", lambda: faults.position_jumps(np.zeros((0, 3)), 0.1, rng())),
    bad("faults.position_jumps", "size_m", "negative", lambda: faults.position_jumps(with_lat(0.6), 0.1, rng(), size_m=-5.0)),
    bad("faults.position_jumps", "rng", "legacy_rng", lambda: faults.position_jumps(with_lat(0.6), 0.1, legacy_rng())),
    bad("faults.heading_flips", "heading", "empty", lambda: faults.heading_flips([], 0.1, rng())),
    bad("faults.heading_flips", "fraction", "above_one", lambda: faults.heading_flips(T10, 2.0, rng())),
    bad("faults.heading_flips", "rng", "legacy_rng", lambda: faults.heading_flips(T10, 0.1, legacy_rng())),
    bad("faults.duplicate_timestamps", "time", "decreasing", lambda: faults.duplicate_timestamps(T10[::-1], 0.1, rng())),
    bad("faults.duplicate_timestamps", "time", "empty", lambda: faults.duplicate_timestamps([], 0.1, rng())),
    bad("faults.duplicate_timestamps", "rng", "int", lambda: faults.duplicate_timestamps(T10, 0.1, 1)),
    bad("faults.swap_timestamps", "time", "one_sample", lambda: faults.swap_timestamps([0.0], 0.1, rng())),
    bad("faults.swap_timestamps", "fraction", "negative", lambda: faults.swap_timestamps(T10, -0.5, rng())),
    bad("faults.swap_timestamps", "rng", "legacy_rng", lambda: faults.swap_timestamps(T10, 0.1, legacy_rng())),
    bad("faults.irregular_times", "n", "one", lambda: faults.irregular_times(1, 0.1, 0.2, rng())),
    bad("faults.irregular_times", "n", "float", lambda: faults.irregular_times(10.0, 0.1, 0.2, rng())),
    bad("faults.irregular_times", "dt", "zero", lambda: faults.irregular_times(10, 0.0, 0.2, rng())),
    bad("faults.irregular_times", "jitter", "one", lambda: faults.irregular_times(10, 0.1, 1.0, rng())),
    bad("faults.irregular_times", "rng", "legacy_rng", lambda: faults.irregular_times(10, 0.1, 0.2, legacy_rng())),
    bad("faults.saturate", "x", "empty", lambda: faults.saturate(np.zeros((0, 3)), 1.0)),
    bad("faults.saturate", "full_scale", "zero", lambda: faults.saturate(FS, 0.0)),
    # timing
    bad("timing.sanitize", "time", "empty", lambda: timing.sanitize([])),
    bad("timing.sanitize", "time", "2d", lambda: timing.sanitize(np.zeros((10, 2)))),
    bad("timing.sanitize", "time", "all_equal", lambda: timing.sanitize(np.zeros(10))),
    bad("imu.SensorLimits", "max_dt", "zero", lambda: imu.SensorLimits(max_dt=0.0)),
    bad("imu.SensorLimits", "max_dt", "nan", lambda: imu.SensorLimits(max_dt=NAN)),
    bad("timing.sanitize", "series[0]", "length_mismatch", lambda: timing.sanitize(T10, FS)),
    bad("timing.sanitize", "series[1]", "object", lambda: timing.sanitize(T10, FS[:10], as_object(T10))),
    bad("timing.intervals", "time", "decreasing", lambda: timing.intervals(T10[::-1])),
    bad("timing.intervals", "time", "empty", lambda: timing.intervals([])),
    bad("timing.intervals", "time", "length_mismatch", lambda: timing.intervals(T10, n_samples=5)),
    bad("timing.intervals", "n_samples", "negative", lambda: timing.intervals(T10, n_samples=-1)),
]


# ------------------------------------------------------------- calibration
M_SPHERE = 40.0 * attitude.quat_rotate(np.random.default_rng(0).standard_normal((30, 4)), [0.0, 0.0, 1.0])
F_SIX = 9.8 * np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], dtype=float)
W_REC, F_REC = np.zeros((200, 3)), np.tile([0.0, 0.0, 9.8], (200, 1))
CASES += [
    bad("calibration.fit_magnetometer", "m_b", "too_few", lambda: calibration.fit_magnetometer(M_SPHERE[:8])),
    bad("calibration.fit_magnetometer", "m_b", "shape", lambda: calibration.fit_magnetometer(M_SPHERE[:, :2])),
    bad("calibration.fit_magnetometer", "m_b", "planar", lambda: calibration.fit_magnetometer(M_SPHERE * [1.0, 1.0, 0.0])),
    bad("calibration.fit_magnetometer", "field_strength", "zero", lambda: calibration.fit_magnetometer(M_SPHERE, 0.0)),
    bad("calibration.MagCalibration", "offset", "shape", lambda: calibration.MagCalibration([0.0, 0.0], np.eye(3), 50.0)),
    bad("calibration.MagCalibration", "soft_iron", "not_spd", lambda: calibration.MagCalibration(np.zeros(3), -np.eye(3), 50.0)),
    bad("calibration.fit_accelerometer", "f_means", "too_few", lambda: calibration.fit_accelerometer(F_SIX[:5])),
    bad(
        "calibration.fit_accelerometer", "f_means", "all_level", lambda: calibration.fit_accelerometer(np.tile(F_SIX[4], (6, 1)))
    ),
    bad("calibration.fit_accelerometer", "g", "negative", lambda: calibration.fit_accelerometer(F_SIX, g=-9.8)),
    bad("calibration.AccelCalibration", "matrix", "upper", lambda: calibration.AccelCalibration(np.zeros(3), np.ones((3, 3)))),
    bad("calibration.gyro_bias_at_rest", "w_ib_b", "one_sample", lambda: calibration.gyro_bias_at_rest(W[:1])),
    bad("calibration.gyro_bias_at_rest", "C_bn", "missing", lambda: calibration.gyro_bias_at_rest(W, lat=0.5)),
    bad("calibration.gyro_bias_at_rest", "lat", "out_of_range", lambda: calibration.gyro_bias_at_rest(W, 2.0, np.eye(3))),
    bad("calibration.characterise", "w_ib_b", "too_short", lambda: calibration.characterise(W, F, 0.01)),
    bad("calibration.characterise", "f_b", "shape", lambda: calibration.characterise(W_REC, F_REC[:150], 0.1)),
    bad(
        "calibration.characterise",
        "dt",
        "irregular",
        lambda: calibration.characterise(W_REC, F_REC, np.linspace(0.09, 0.11, 200)),
    ),
    bad("calibration.characterise", "confidence", "one", lambda: calibration.characterise(W_REC, F_REC, 0.1, confidence=1.0)),
    bad("io.from_dataframe", "df", "not_a_frame", lambda: io.from_dataframe({"t": [0, 1]}, time="t", units={})),
    bad(
        "io.from_dataframe",
        "columns",
        "missing",
        lambda: io.from_dataframe(IO_TABLE, time="t", units={"gyro": "rad/s"}, gyro=("gx", "gy", "nope")),
    ),
    bad(
        "io.from_dataframe",
        "units['gyro']",
        "unknown",
        lambda: io.from_dataframe(IO_TABLE, time="t", units={"gyro": "rpm"}, gyro=("gx", "gy", "gz")),
    ),
    bad(
        "io.from_dataframe",
        "time_unit",
        "unknown",
        lambda: io.from_dataframe(IO_TABLE, time="t", time_unit="min", units={"gyro": "rad/s"}, gyro=("gx", "gy", "gz")),
    ),
    bad(
        "io.from_dataframe",
        "axes",
        "mirror",
        lambda: io.from_dataframe(IO_TABLE, time="t", units={"gyro": "rad/s"}, gyro=("gx", "gy", "gz"), axes="y,x,z"),
    ),
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
MIRROR = np.diag([1.0, 1.0, -1.0])  # orthonormal, det -1: not a rotation
CASES += [
    # flags and texts that were used without a check ("yes" counted as True, None as False)
    bad("earth.field_angles", "deg", "int", lambda: earth.field_angles([1.0, 20.0, -40.0], deg=1)),
    bad("robust.hold", "axis", "zero", lambda: robust.hold(np.ones((3, 3)), axis=0)),
    bad("plots.allan", "color", "unknown", lambda: plots.allan(axes2d(), [1.0, 2.0], [1e-5, 1e-5], color="abc")),
    bad(
        "io.from_dataframe",
        "gyro",
        "one_string",
        lambda: io.from_dataframe(IO_TABLE, time="t", units={"gyro": "rad/s"}, gyro="abc"),
    ),
    # rotation matrices and quaternions that are none (one check in navlib._validate: as_dcm, as_quat)
    bad("earth.earth_rate_b", "C_bn", "mirror", lambda: earth.earth_rate_b(MIRROR, 0.5)),
    bad("attitude.ned_to_enu_dcm", "C_ned", "mirror", lambda: attitude.ned_to_enu_dcm(MIRROR)),
    bad("alignment.static_gyro_bias", "C_bn", "mirror", lambda: alignment.static_gyro_bias(W, MIRROR, 0.5)),
    bad("strapdown.error_input", "C_bn", "not_rotation", lambda: strapdown.error_input(2 * np.eye(3))),
    bad(
        "trajectory.Trajectory",
        "q_bn",
        "zero_row",
        lambda: _traj_with(q_bn=np.where(np.arange(len(TRAJ.time))[:, None] == 3, 0.0, TRAJ.q_bn)),
    ),
    # a scalar given as an array ("only 0-dimensional arrays can be converted to Python scalars")
    bad("analysis.allan_deviation", "dt", "array", lambda: analysis.allan_deviation(np.ones(100), [0.1, 0.1])),
    bad("atmosphere.classify_floor", "floor_height", "array", lambda: atmosphere.classify_floor([1.0], [3.0, 3.0])),
    bad("faults.saturate", "full_scale", "array", lambda: faults.saturate(FS, [1.0, 2.0])),
    bad("pdr.detect_steps", "threshold", "array", lambda: pdr.detect_steps(np.ones((10, 3)), 0.01, threshold=[1.0, 2.0])),
    bad("robust.despike", "spike_gyro", "array", lambda: robust.despike(W, F, [0.1, 0.1], 1.0)),
    bad("sensors.gauss_markov", "sigma", "array", lambda: sensors.gauss_markov((10, 3), 0.1, [1.0, 1.0], 10.0, rng())),
    bad(
        "sensors.simulate_barometer",
        "p0",
        "array",
        lambda: sensors.simulate_barometer(T10, T10, sensors.BarometerModel(), rng(), p0=[1e5, 1e5, 1e5]),
    ),
    bad("trajectory.static", "duration", "array", lambda: trajectory.static([1.0, 2.0], 0.1, LLA0, [0, 0, 0])),
    bad("trajectory.Segment", "duration", "array", lambda: trajectory.Segment(duration=[1.0, 2.0])),
    bad("trajectory.Leg", "speed", "array", lambda: trajectory.Leg(1.0, speed=[1.0, 2.0])),
    bad("trajectory.Gait", "ramp", "array", lambda: trajectory.Gait(ramp=[1.0, 2.0])),
    bad(
        "analysis.allan_deviation_theory",
        "white",
        "array",
        lambda: analysis.allan_deviation_theory([1.0, 10.0], white=[1e-3, 1e-3, 1e-3]),
    ),
    bad(
        "sensors.magnetic_disturbances",
        "amplitude",
        "scalar",
        lambda: sensors.magnetic_disturbances(T10, rng(), 0.1, amplitude=5.0),
    ),
    # arrays of the wrong shape or of several trials where one is expected
    bad("alignment.static_gyro_bias", "lat", "array", lambda: alignment.static_gyro_bias(W, np.eye(3), [0.5, 0.6])),
    bad(
        "alignment.static_gyro_bias", "w_ib_b", "batch", lambda: alignment.static_gyro_bias(np.zeros((2, 10, 3)), np.eye(3), 0.5)
    ),
    bad(
        "alignment.triad",
        "w_ib_b",
        "batch_mismatch",
        lambda: alignment.triad(np.tile([0.0, 0.0, 9.8], (2, 1)), np.zeros((3, 3)), 0.5),
    ),
    bad("analysis.normal_condition", "A", "not_square", lambda: analysis.normal_condition(np.ones((2, 3)))),
    bad(
        "analysis.horizontal_error",
        "lla_true",
        "epoch_mismatch",
        lambda: analysis.horizontal_error(np.zeros((0, 3)), with_lat(0.6)),
    ),
    bad(
        "atmosphere.baro_height",
        "temperature",
        "shape",
        lambda: atmosphere.baro_height([1e5, 9.9e4], 101325.0, [288.0, 288.0, 288.0]),
    ),
    bad("pdr.pdr", "start_en", "batch", lambda: pdr.pdr([1.0, 2.0], [0.0, 0.0], start_en=[[0.0, 0.0], [0.0, 0.0]])),
    bad(
        "sensors.simulate_magnetometer",
        "B_n",
        "epoch_mismatch",
        lambda: sensors.simulate_magnetometer(
            np.tile(Q1, (10, 1)), np.tile([0.0, 20.0, -40.0], (3, 1)), sensors.MagnetometerModel(), rng()
        ),
    ),
    bad(
        "strapdown.integrate",
        "q0",
        "batch_mismatch",
        lambda: strapdown.integrate(LLA0, [0, 0, 0], np.tile(Q1, (2, 1)), W, F, 0.01),
    ),
    bad(
        "strapdown.integrate_attitude", "q0", "batch_mismatch", lambda: strapdown.integrate_attitude(np.tile(Q1, (2, 1)), W, 0.01)
    ),
    bad("trajectory.static", "hpr", "batch", lambda: trajectory.static(1.0, 0.1, LLA0, np.zeros((2, 3)))),
    # values that were used without a check
    bad("faults.gap", "time", "decreasing", lambda: faults.gap(FS, T20[::-1], 2.0, 3.0)),
    bad(
        "atmosphere.reference_pressure",
        "time",
        "decreasing",
        lambda: atmosphere.reference_pressure([1e5, 1e5, 1e5], [2.0, 1.0, 0.0], 5.0),
    ),
    bad(
        "euler.integrate_euler",
        "bias_from",
        "without_bias_b",
        lambda: euler.integrate_euler([0.0, 0.0, 0.0], np.zeros((4, 3)), 0.1, bias_from=[0]),
    ),
    bad(
        "euler.integrate_euler",
        "dt",
        "time_jump",
        lambda: euler.integrate_euler([0.0, 0.0, 0.0], np.full((4, 3), 1e-3), [0.01, 3600.0, 0.01, 0.01]),
    ),
    bad("sensors.simulate_heading", "valid", "numbers", lambda: sensors.simulate_heading(T10, rng(), 0.01, valid=np.ones(10))),
    bad(
        "calibration.MagCalibration",
        "residual",
        "negative",
        lambda: calibration.MagCalibration(np.zeros(3), np.eye(3), 50.0, residual=-1.0),
    ),
]


def _registry_row(name, row):
    """A row's ``bad`` call of the registry: its valid call with ``row.changes``."""
    call = CALLS[name]
    return bad(name, row.arg, row.what, lambda: fuzz.call_once(PUBLIC[name], {**call.kwargs, **row.changes}, call.before))


CASES += [_registry_row(name, row) for name, call in CALLS.items() for row in call.bad]


def names_arg(arg):
    """Regex: the message starts with the argument name ``arg``: "<arg>: expected ...",
    or "<arg>[...] (<part>): ..." for a part of an array argument."""
    return rf"^{re.escape(arg)}(?!\w)"


@pytest.fixture
def sandbox(tmp_path, monkeypatch):
    """Throw-away repository root and repro state; figures and rcParams restored."""
    (tmp_path / "pyproject.toml").write_text("[project]\nname = 'x'\n")
    (tmp_path / "navlib").mkdir()
    (tmp_path / "data").mkdir()
    for name in ("claims.csv", "errata.csv"):  # repro.verdict reads the catalogue
        shutil.copy(ROOT / "data" / name, tmp_path / "data")
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


@pytest.mark.filterwarnings("ignore::RuntimeWarning")
@pytest.mark.parametrize("name", sorted(CALLS))
def test_registry_call_refuses_bad_values(name, request):
    """The registry's valid call works, and each IN_PROCESS bad value of each argument raises an error naming
    the argument (tools/fuzz.py's outcome "clean"), unless BY_DESIGN documents the outcome or it is a known gap."""
    if name.startswith(("repro.", "plots.")):
        request.getfixturevalue("sandbox")
    call, func = CALLS[name], PUBLIC[name]
    baseline = {name: fuzz.leaves(fuzz.call_once(func, call.kwargs, call.before))}
    cases = [case for case in fuzz.cases_of(name, call, func) if case[2] in IN_PROCESS]
    found = {
        fuzz.case_id(r): f"{r['outcome']} {r.get('message', '')}"
        for r in (fuzz.run_case(case, CALLS, PUBLIC, baseline) for case in cases)
        if fuzz.failing(r)
    }
    gaps = {"-".join(case) for case in cases} & set(fuzz_calls.KNOWN_GAPS)
    assert {k: v for k, v in found.items() if k not in gaps} == {}
    assert gaps <= set(found), f"navlib refuses these now; remove them from KNOWN_GAPS: {sorted(gaps - set(found))}"
    if gaps:
        pytest.xfail(f"navlib gaps: {sorted(gaps)}")


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


@pytest.mark.parametrize(
    "func",
    [attitude.wrap_pi, attitude.wrap_2pi] + [PUBLIC[k] for k in sorted(CALLS) if k.startswith("units.") and k != "units.to_si"],
    ids=lambda f: f.__name__,
)
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


@pytest.mark.parametrize(
    "call",
    [
        lambda: repro.check("T/nan", np.nan, 1.0, 0.1, "src"),
        lambda: repro.check_range("T/nan", np.nan, "src", upper=1.0),
    ],
    ids=["check", "check_range"],
)
def test_repro_nan_value_fails_the_claim(call, sandbox):
    """A NaN reproduced value is a failed claim, not a usage error."""
    with pytest.raises(repro.ClaimCheckFailed):
        call()


# ----------------------------------------------------------------- the registry


def test_registry_lists_every_public_callable():
    """A new public function or class needs a row in tools/fuzz_calls.py (a valid call, or a Skip and why)."""
    missing, stale = set(PUBLIC) - set(REGISTRY), set(REGISTRY) - set(PUBLIC)
    assert not missing, f"public callables without a row in tools/fuzz_calls.py: {sorted(missing)}"
    assert not stale, f"tools/fuzz_calls.py rows for names that are not public: {sorted(stale)}"
    assert all(isinstance(c, fuzz_calls.Skip) and c.reason or isinstance(c, fuzz_calls.Call) for c in REGISTRY.values())


@pytest.mark.parametrize(
    "module", [m for m in fuzz_calls.public_modules() if not hasattr(m, "__path__")], ids=lambda m: m.__name__
)
def test_every_module_declares_all(module):
    assert hasattr(module, "__all__")


def test_rows_name_public_callables():
    stale = {p.values[0] for p in CASES} - set(PUBLIC)
    assert not stale, f"CASES rows for names that are not public: {sorted(stale)}"


def test_known_gaps_name_existing_cases():
    generated = {"-".join(case) for name, call in CALLS.items() for case in fuzz.cases_of(name, call, PUBLIC[name])}
    plt.close("all")
    unknown = set(fuzz_calls.KNOWN_GAPS) - {p.id for p in CASES} - generated
    assert not unknown, f"KNOWN_GAPS entries without a case: {sorted(unknown)}"
