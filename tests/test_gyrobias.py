"""Tests of navlib.papers.rotation_bias (paper 001): equations, closed loops, noise model (bad input: the rows of
the registry tools/fuzz_calls.py, run by tests/test_bad_input.py)."""

import json
import os
import subprocess
import sys

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from navlib import analysis, attitude, earth, euler, sensors, strapdown, trajectory, units
from navlib.papers import rotation_bias as gb

DT = 0.01
LAT = units.deg(40.0)
B = units.deg_per_h(np.array([10.0, -7.0, 12.0]))
EY = np.array([0.0, 1.0, 0.0])

angles = st.tuples(st.floats(0, 2 * np.pi), st.floats(-1.5, 1.5), st.floats(-np.pi, np.pi))


def rig(pitch_deg=30.0, axis=EY, duration=60.0, period=5.0, rotation_time=0.5):
    hpr0 = units.deg([0.0, pitch_deg, 0.0])
    traj = trajectory.reciprocating_rotation(duration, DT, [LAT, 0, 0], hpr0, axis, np.pi / 2, period, rotation_time)
    w, f = trajectory.ideal_imu(traj)
    starts, length = gb.dwell_windows(w.shape[0], DT, period, rotation_time)
    w_ie_b = earth.earth_rate_b(attitude.euler_to_dcm(gb.dwell_attitudes(hpr0, axis, np.pi / 2, starts.size)), LAT)
    return traj, w, f, starts, length, w_ie_b


# --- Eqs. (1)-(2) ----------------------------------------------------------


@given(angles)
@settings(max_examples=50, deadline=None)
def test_eq1_is_the_transpose_of_c_bn(hpr):
    np.testing.assert_allclose(gb.eq1_matrix(hpr), attitude.euler_to_dcm(hpr).T, atol=1e-14)


@given(angles, st.tuples(*[st.floats(-2, 2)] * 3))
@settings(max_examples=50, deadline=None)
def test_euler_rates_match_the_dcm_derivative(hpr, w):
    # C_bn(t + h) = C_bn exp(h [w x]); the Euler angles of that move at the rates of Eq. (2)
    hpr, w = np.array(hpr), np.array(w)
    h = 1e-6
    ahead = attitude.dcm_to_euler(attitude.euler_to_dcm(hpr) @ attitude.rotvec_to_dcm(w * h))
    behind = attitude.dcm_to_euler(attitude.euler_to_dcm(hpr) @ attitude.rotvec_to_dcm(-w * h))
    fd = attitude.wrap_pi(ahead - behind) / (2 * h)
    np.testing.assert_allclose(euler.euler_rates(hpr, w), fd, atol=1e-5 / np.cos(hpr[1]) ** 2)


def test_integration_reproduces_the_rig_with_earth_rate():
    traj, w, *_ = rig(60.0, duration=120.0)
    hpr = euler.integrate_euler(traj.hpr[0], w, DT, earth.earth_rate_n(LAT))
    assert np.abs(analysis.attitude_errors(hpr, traj.hpr)).max() < 1e-8


def test_integration_agrees_with_quaternion_strapdown():
    rng = np.random.default_rng(0)
    w = 0.3 * rng.standard_normal((2, 3000, 3))
    hpr0 = units.deg([10.0, 20.0, -30.0])
    hpr = euler.integrate_euler(hpr0, w, DT)
    q = strapdown.integrate_attitude(attitude.euler_to_quat(hpr0), w, DT)
    assert np.abs(analysis.attitude_errors(hpr, attitude.quat_to_euler(q))).max() < 1e-9


def test_constant_and_scheduled_bias_compensation():
    rng = np.random.default_rng(1)
    w = 0.01 * rng.standard_normal((2, 500, 3))
    b = np.array([[1e-3, -2e-3, 3e-3], [0.0, 1e-3, 0.0]])
    hpr0 = [0.0, 0.2, 0.1]
    np.testing.assert_allclose(
        euler.integrate_euler(hpr0, w, DT, bias_b=b), euler.integrate_euler(hpr0, w - b[:, None], DT), atol=1e-15
    )
    # estimate 0 applies from sample 100, estimate 1 (NaN: not available) keeps it, estimate 2 from 300
    sched = np.array([[1e-3, 0, 0], [np.nan] * 3, [0, 2e-3, 0]])
    hpr = euler.integrate_euler(hpr0, w[0], DT, bias_b=sched, bias_from=np.array([100, 200, 300]))
    b_per_sample = np.zeros((500, 3))
    b_per_sample[100:] = sched[0]
    b_per_sample[300:] = sched[2]
    np.testing.assert_allclose(hpr, euler.integrate_euler(hpr0, w[0] - b_per_sample, DT), atol=1e-15)


# --- Eqs. (4)-(5), (6)-(9) -------------------------------------------------


def test_tilt_round_trip_and_static_specific_force():
    traj = trajectory.static(1.0, DT, [LAT, 0, 0], units.deg([40.0, 25.0, -70.0]))
    _, f = trajectory.ideal_imu(traj)
    np.testing.assert_allclose(gb.roll_pitch_from_accel(f), np.broadcast_to(units.deg([-70.0, 25.0]), (100, 2)), atol=1e-6)
    tilt = np.array([[0.3, -0.4], [-2.5, 1.2]])
    np.testing.assert_allclose(gb.roll_pitch_from_accel(-gb.gravity_body(tilt)), tilt, atol=1e-14)


def test_tilt_matrix_null_space_is_the_vertical():
    tilt = np.random.default_rng(2).uniform([-3, -1.4], [3, 1.4], (100, 2))
    M = gb.tilt_matrix(tilt)
    assert np.all(np.linalg.matrix_rank(M) == 2)
    np.testing.assert_allclose(M @ gb.gravity_body(tilt)[..., None], 0, atol=1e-12)


def test_residuals_equal_v_b_on_a_noise_free_rig():
    traj, w, f, starts, length, w_ie_b = rig(30.0)
    res = gb.tilt_residuals(w + B, f, DT, starts, length, w_ie_b)
    np.testing.assert_allclose(res.r, res.V @ B, atol=1e-13)
    assert res.faults["dwell", "refused"] == 0 and res.duration == pytest.approx(4.5)
    np.testing.assert_array_equal(res.end, starts + length)


def test_dropouts_skip_the_dwell_and_are_counted():
    traj, w, f, starts, length, w_ie_b = rig(30.0)
    w = w + B
    w[starts[3] + 5, 1] = np.nan
    f = f.copy()
    f[starts[6] + 9, 2] = np.nan
    res = gb.tilt_residuals(w, f, DT, starts, length, w_ie_b)
    assert res.faults["dwell", "refused"] == 2 and res.faults["imu", "nan"] == 2
    assert np.isnan(res.r[[3, 6]]).all() and np.isfinite(np.delete(res.r, [3, 6], 0)).all()
    np.testing.assert_allclose(gb.lsq_bias(res.r, res.V), B, atol=1e-12)
    b_run, faults = gb.running_lsq_bias(res.r, res.V)
    assert faults["dwell", "nan"] == 2
    np.testing.assert_allclose(b_run[-1], B, atol=1e-12)


# --- Eqs. (10)-(14) ---------------------------------------------------------


def test_rodrigues_matches_scipy_and_eq11_adds_roll():
    u = np.array([1.0, -2.0, 0.5]) / np.linalg.norm([1.0, -2.0, 0.5])
    np.testing.assert_allclose(gb.rodrigues(u, 0.7), Rotation.from_rotvec(0.7 * u).as_matrix(), atol=1e-15)
    hpr = units.deg([20.0, 30.0, 10.0])
    out = gb.rotate_attitude(hpr, EY, np.pi / 2)
    np.testing.assert_allclose(out, hpr + [0, 0, np.pi / 2], atol=1e-12)


@pytest.mark.parametrize("pitch", [30.0, 60.0])
@pytest.mark.parametrize("axis", [[1.0, 0, 0], [0, 1.0, 0], [0, 0, 1.0]])
def test_noise_free_least_squares_recovers_the_bias(pitch, axis):
    traj, w, f, starts, length, w_ie_b = rig(pitch, np.array(axis))
    res = gb.tilt_residuals(w + B, f, DT, starts, length, w_ie_b)
    np.testing.assert_allclose(gb.lsq_bias(res.r, res.V), B, atol=1e-13)  # B ~ 5e-5 rad/s
    b_run, _ = gb.running_lsq_bias(res.r, res.V)
    np.testing.assert_allclose(b_run[-1], B, atol=1e-13)
    assert np.isnan(b_run[0]).all()  # one dwell: not observable yet
    assert 1.4 <= analysis.condition_number(res.V) <= 4.0


def test_earth_rate_neglected_biases_the_estimate():
    traj, w, f, starts, length, w_ie_b = rig(30.0, duration=120.0)
    res = gb.tilt_residuals(w + B, f, DT, starts, length)  # w_ie_b not given: Earth rate neglected
    b_neglect = gb.lsq_bias(res.r, res.V)
    assert units.to_deg_per_h(b_neglect[1]) == pytest.approx(6.305, abs=0.01)


def test_vertical_axis_is_unobservable():
    traj, w, f, starts, length, w_ie_b = rig(0.0, np.array([0.0, 0, 1.0]))
    res = gb.tilt_residuals(w + B, f, DT, starts, length, w_ie_b)
    assert np.isinf(analysis.condition_number(res.V))
    with pytest.raises(ValueError, match=r"^V: .*not observable"):
        gb.lsq_bias(res.r, res.V)
    cond, crb, _ = gb.design([0, 0, 0], [0, 0, 1.0], np.pi / 2, 4.5, DT, 1e-4)
    assert np.isinf(cond) and np.isinf(np.diag(crb)).any()


def test_forgetting_tracks_a_step_in_the_bias():
    traj, w, f, starts, length, w_ie_b = rig(30.0, duration=300.0)
    w = w + B
    half = w.shape[0] // 2
    w[half:] += 2 * B
    res = gb.tilt_residuals(w, f, DT, starts, length, w_ie_b)
    b_run, _ = gb.running_lsq_bias(res.r, res.V, forgetting=0.5)
    np.testing.assert_allclose(b_run[-1], 3 * B, rtol=1e-6)


# --- noise model, CRB, Kalman filter -----------------------------------------


def test_residual_covariance_matches_monte_carlo():
    traj, w, f, starts, length, w_ie_b = rig(30.0, duration=600.0)
    model = sensors.imu_model("MTi-100").replace(
        gyro={"bias": 0.0, "bias_instability": 0.0}, accel={"bias": 0.0, "bias_instability": 0.0}
    )
    imu = sensors.simulate_imu(w, f, DT, model, np.random.default_rng(3), n_trials=20)
    res = gb.tilt_residuals(imu.w_ib_b, imu.f_b, DT, starts, length, w_ie_b)
    R = gb.residual_covariance(res.tilt[0, :2], length, DT, model.gyro.noise_density, model.accel.noise_density)
    for k in (0, 1):
        r = res.r[:, k::2].reshape(-1, 2)  # 2400 dwells at each attitude
        np.testing.assert_allclose(np.cov(r.T), R[k], rtol=0.15, atol=0.15 * np.sqrt(R[k, 0, 0] * R[k, 1, 1]))


def test_crb_gyro_only_is_n_over_sqrt_t():
    # for gyro noise alone, a pair of dwells 90 deg apart about y_b: sigma = c N / sqrt(T) (x, z), c N / sqrt(2T) (y)
    N, T = units.deg_per_s(0.01), 4.5
    _, crb, V = gb.design([0, 0, 0], EY, np.pi / 2, T, DT, N)
    n = int(round(T / DT))
    c = np.sqrt(gb.residual_covariance(np.zeros((1, 2)), n, DT, N)[0, 1, 1] / (N**2 * T))  # slope-fit factor
    assert c == pytest.approx(np.sqrt(6 / 5), rel=0.01)
    np.testing.assert_allclose(np.sqrt(np.diag(crb)), c * N / np.sqrt(T) * np.array([1, 1 / np.sqrt(2), 1]), rtol=1e-9)
    tilt = gb.dwell_attitudes([0, 0, 0], EY, np.pi / 2, 2)[:, [2, 1]]
    R = gb.residual_covariance(tilt, n, DT, N)
    np.testing.assert_allclose(R, c**2 * N**2 * T * np.broadcast_to(np.eye(2), (2, 2, 2)), rtol=1e-12)
    np.testing.assert_allclose(analysis.lsq_covariance(V, R), crb, rtol=1e-9)  # R ∝ I here: OLS is efficient


def test_kalman_filter_converges_and_survives_dropouts_and_outliers():
    traj, w, f, starts, length, w_ie_b = rig(30.0, duration=600.0)
    model = sensors.imu_model("MTi-100").replace(gyro={"bias": 0.0, "bias_instability": 0.0})
    imu = sensors.simulate_imu(w + B, f, DT, model, np.random.default_rng(4))
    res = gb.tilt_residuals(imu.w_ib_b, imu.f_b, DT, starts, length, w_ie_b)
    r = res.r.copy()
    r[10] = np.nan  # dropout
    r[20] += 0.05  # outlier (0.05 rad over a dwell)
    R = gb.residual_covariance(res.tilt, length, DT, model.gyro.noise_density, model.accel.noise_density)
    kf = gb.kalman_bias(r, res.V, R, 5.0, 0.0, units.deg_per_h(50.0))
    assert kf.faults["dwell", "nan"] == 1 and kf.faults["dwell", "outlier"] == 1
    err = np.abs(kf.b[-1] - B)
    assert np.all(err < 4 * kf.sigma[-1])
    b_ls = gb.lsq_bias(np.delete(r, [10, 20], 0), np.delete(res.V, [10, 20], 0))
    np.testing.assert_allclose(kf.b[-1], b_ls, atol=0.5 * kf.sigma[-1].max())


def test_error_statistics_match_numpy():
    rng = np.random.default_rng(5)
    hpr = rng.uniform(-4, 4, (3, 200, 3))
    truth = rng.uniform(-4, 4, (200, 3))
    mx, mean = analysis.error_statistics(hpr, truth)
    e = np.abs(analysis.attitude_errors(hpr, truth))
    np.testing.assert_allclose(mx, e.max(axis=1), atol=1e-14)
    np.testing.assert_allclose(mean, e.mean(axis=1), atol=1e-14)


def test_the_running_least_squares_solves_with_lapacks_dgesv_bit_for_bit():
    """Its solver compiled (dgesv called by its symbol) gives the bits of the same routine through scipy's wrapper
    (the one numba's np.linalg.solve calls), row exchanges included; a singular A raises."""
    from numba import njit
    from scipy.linalg import lapack

    @njit
    def solve(A, y):
        a, b = np.asfortranarray(A), y.copy()
        gb._lu_solve_into(a, b, np.empty(A.shape[0], dtype=np.int32))
        return b

    rng = np.random.default_rng(3)
    for n in (3, 3, 3, 5):
        A, y = rng.standard_normal((n, n)), rng.standard_normal(n)
        assert solve(A, y).tobytes() == lapack.dgesv(A, y)[2].tobytes()
    with pytest.raises(np.linalg.LinAlgError, match="singular"):
        solve(np.ones((3, 3)), np.ones(3))


# --- compiled kernels run uncompiled ----------------------------------------

SCRIPT = r"""
import json, numpy as np
from navlib import trajectory, units, earth
from navlib import analysis, euler
from navlib.papers import rotation_bias as gb
lat = units.deg(40.0)
traj = trajectory.reciprocating_rotation(20.0, 0.01, [lat, 0, 0], units.deg([0, 30, 0]), [0, 1, 0], np.pi / 2, 5.0, 0.5)
w, f = trajectory.ideal_imu(traj)
w = w + 1e-4 * np.sin(np.arange(w.shape[0]))[:, None]
starts, n = gb.dwell_windows(w.shape[0], 0.01, 5.0, 0.5)
res = gb.tilt_residuals(w, f, 0.01, starts, n)
b, _ = gb.running_lsq_bias(res.r, res.V, 0.9)
R = gb.residual_covariance(res.tilt, n, 0.01, 1e-4, 1e-3)
kf = gb.kalman_bias(res.r, res.V, R, 5.0, 1e-6, 1e-4)
hpr = euler.integrate_euler(traj.hpr[0], w, 0.01, earth.earth_rate_n(lat), b, res.end)
mx, mean = analysis.error_statistics(hpr, traj.hpr)
print(json.dumps({"r": res.r.tolist(), "b": np.nan_to_num(b).tolist(), "kf": kf.b.tolist(), "hpr": hpr[::50].tolist(),
                  "mx": mx.tolist()}))
"""


def test_kernels_run_uncompiled_with_the_same_results():
    def run(disable):
        env = dict(os.environ, NUMBA_DISABLE_JIT="1" if disable else "0")
        out = subprocess.run([sys.executable, "-c", SCRIPT], env=env, capture_output=True, text=True, check=True)
        return json.loads(out.stdout)

    jit, plain = run(False), run(True)
    for key in jit:
        np.testing.assert_allclose(plain[key], jit[key], rtol=1e-12, atol=1e-15)


FAULT_SCRIPT = r"""
import json, numpy as np
from navlib import trajectory, units, earth
from navlib import analysis, euler, robust
from navlib.papers import rotation_bias as gb
lat = units.deg(40.0)
traj = trajectory.reciprocating_rotation(20.0, 0.01, [lat, 0, 0], units.deg([0, 30, 0]), [0, 1, 0], np.pi / 2, 5.0, 0.5)
w, f = trajectory.ideal_imu(traj)
rng = np.random.default_rng(0)
w = w + 1e-3 * rng.standard_normal(w.shape)
f = f + 1e-2 * rng.standard_normal(f.shape)
w[rng.random(w.shape[0]) < 0.05] = np.nan                      # dropouts
f[rng.random(f.shape[0]) < 0.01] += 5.0                        # spikes
f[520:523, 0] = 30.0                                           # at the rails of a 30 m/s^2 range
starts, n = gb.dwell_windows(w.shape[0], 0.01, 5.0, 0.5)
dts = 0.01 * (1 + 0.2 * np.sin(np.arange(w.shape[0])))
res = gb.tilt_residuals(w, f, dts, starts, n, max_missing=0.5, outlier_k=6.0, full_scale_accel=30.0)
R = gb.residual_covariance(np.nan_to_num(res.tilt), n, 0.01, 1e-3, 1e-2)
kf = gb.kalman_bias(res.r, res.V, R, np.full(starts.size, 5.0), 1e-6, 1e-3)
hpr = euler.integrate_euler(traj.hpr[0], w, dts, earth.earth_rate_n(lat), max_gap=0.1)
rep = robust.fault_report(w, "gyro", full_scale=5.0)
print(json.dumps({"r": np.nan_to_num(res.r).tolist(), "counts": [res.faults[key] for key in (("dwell", "refused"), ("imu", "nan"),
                  ("accel", "outlier"), ("imu", "saturated"))] + [kf.faults["dwell", "nan"], int(rep["gyro", "nan"]),
                  int(rep["gyro", "saturated"])],
                  "kf": kf.b.tolist(), "P": kf.P.tolist(), "hpr": hpr[::50].tolist()}))
"""


def test_fault_paths_run_uncompiled_with_the_same_results():
    def run(disable):
        env = dict(os.environ, NUMBA_DISABLE_JIT="1" if disable else "0")
        out = subprocess.run([sys.executable, "-c", FAULT_SCRIPT], env=env, capture_output=True, text=True, check=True)
        return json.loads(out.stdout)

    jit, plain = run(False), run(True)
    assert jit["counts"] == plain["counts"]
    assert jit["counts"][1] > 0 and jit["counts"][2] > 0 and jit["counts"][3] > 0 and jit["counts"][5] > 0
    for key in ("r", "kf", "P", "hpr"):
        np.testing.assert_allclose(plain[key], jit[key], rtol=1e-12, atol=1e-15)
