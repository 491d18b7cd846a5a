"""navlib.papers.pedestrian_ins (paper 004): conventions, Eqs. (1)-(6), detector, filter, barometer, PDR."""

import json
import os
import subprocess
import sys

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from navlib import alignment, analysis, atmosphere, attitude, earth, kalman, pdr, sensors, strapdown, trajectory, units
from navlib.filters import zupt, zupt_ins
from navlib.imu import ImuSamples
from navlib.papers import pedestrian_ins as pd

LAT = units.deg(30.55)
LLA0 = [LAT, units.deg(114.30), 20.0]
DT = 0.01
RESIDUAL = sensors.imu_model("MPU-6050").replace(gyro={"bias": units.deg_per_s(0.05)}, accel={"bias": units.mg(10)})


MAX_TILT = np.deg2rad(40)


def random_hpr(rng, n, max_tilt=MAX_TILT):
    return np.stack([rng.uniform(0, 2 * np.pi, n), rng.uniform(-max_tilt, max_tilt, n), rng.uniform(-max_tilt, max_tilt, n)], -1)


# ---------------------------------------------------------------- conventions


def test_ned_frd_to_enu_rfu_is_the_same_euler_triplet():
    rng = np.random.default_rng(0)
    hpr = random_hpr(rng, 1000, np.deg2rad(85))
    C_ned = Rotation.from_euler("ZYX", hpr).as_matrix()  # R_z(H) R_y(theta) R_x(gamma), FRD -> NED
    np.testing.assert_allclose(attitude.ned_to_enu_dcm(C_ned), attitude.euler_to_dcm(hpr), atol=1e-14)
    assert np.isclose(np.linalg.det(attitude.M_NED_ENU), 1.0)


# ---------------------------------------------------------------- Eqs. (4)-(6)


def field_in_body(hpr, B_n):
    return np.einsum("nji,j->ni", attitude.euler_to_dcm(hpr), B_n)  # C_nb B_n


def test_corrected_tilt_compensation_recovers_heading_in_both_frames():
    rng = np.random.default_rng(1)
    hpr = random_hpr(rng, 300)
    B_n = earth.field_from_angles(0.0, 47.0, 49.7)  # magnetic north: heading = magnetic heading
    m_b = field_in_body(hpr, B_n)
    enu = alignment.magnetic_heading(m_b, hpr[:, 1], hpr[:, 2])
    assert np.abs(attitude.wrap_pi(enu - hpr[:, 0])).max() < 1e-12
    H_frd = np.stack([m_b[:, 1], m_b[:, 0], -m_b[:, 2]], -1)  # (H_x, H_y, H_z) = (m_y, m_x, -m_z)
    HX, HY = pd.tilt_compensate_ned(H_frd, hpr[:, 1], hpr[:, 2])
    ned = pd.heading_from_horizontal(HX, HY)
    assert np.abs(attitude.wrap_pi(ned - hpr[:, 0])).max() < 1e-12
    np.testing.assert_allclose(attitude.wrap_pi(ned - enu), 0.0, atol=1e-14)
    PX, PY = pd.tilt_compensate_printed(H_frd, hpr[:, 1], hpr[:, 2])
    printed = pd.heading_from_horizontal(PX, PY)
    assert np.median(np.abs(attitude.wrap_pi(printed - hpr[:, 0]))) > np.deg2rad(10)


def test_heading_range_is_zero_to_two_pi_and_declination_added():
    assert pd.heading_from_horizontal(1.0, 0.0) == 0.0  # north maps to 0, never 2 pi
    assert pd.heading_from_horizontal(1.0, -0.0) == 0.0
    a = pd.heading_from_horizontal(np.cos(np.linspace(0, 6.28, 50)), -np.sin(np.linspace(0, 6.28, 50)))
    assert np.all((a >= 0) & (a < 2 * np.pi))
    assert np.isclose(pd.heading_from_horizontal(1.0, 0.0, declination=units.deg(-4.3)), units.deg(355.7))
    D = np.rad2deg(earth.field_angles(earth.magnetic_field(30.55, 114.30, 0.0, 2016.5), deg=False)[0])
    assert abs(D + 4.3) < 0.3


# ---------------------------------------------------------------- Eqs. (1)-(3)


def test_error_model_matches_finite_differences_of_the_mechanisation():
    rng = np.random.default_rng(2)
    for _ in range(5):
        C = attitude.euler_to_dcm(random_hpr(rng, 1)[0])
        f = np.array([0.3, -0.5, 9.8]) + rng.normal(0, 2, 3)
        F_fd = zupt.error_model_fd(C, f)
        F = zupt.error_state_matrix(C, f)
        np.testing.assert_allclose(F_fd, F, atol=1e-6 * np.abs(F).max())


def _random_covariance(rng, n):
    """A symmetric positive definite n x n covariance whose states' sigmas span three decades (as the INS's)."""
    A = rng.standard_normal((n, n)) * np.exp(rng.uniform(-7.0, 0.0, n))[:, None]
    P = A @ A.T + 1e-12 * np.eye(n)
    return (P + P.T) / 2


def test_block_covariance_predict_is_the_dense_product():
    """error_state_predict_into multiplies only Phi's non-zero blocks (and one triangle of the result) yet equals
    the dense Phi P Phi^T + Q to rounding, exactly symmetric; Phi = I + F dt from error_state_into, the model's
    one definition. A zero row and column of P and dt = 0 (a clock jump) included."""
    rng = np.random.default_rng(3)
    work = np.empty((15, 15))
    for dt in (0.01, 0.0, 1.3, 0.005, 0.01, 0.02):
        P = _random_covariance(rng, 15)
        if dt == 0.01:
            P[4] = P[:, 4] = 0.0
        C = attitude.euler_to_dcm(random_hpr(rng, 1)[0])
        C_dt, f_dt = C * dt, C @ (np.array([0.1, 0.0, 9.8]) + rng.normal(0, 2, 3)) * dt
        Phi = np.eye(15)
        Phi[[0, 1, 2], [3, 4, 5]] = dt
        zupt.error_state_into(Phi, C_dt, f_dt)
        q = rng.uniform(0.0, 1e-4, 15) * dt
        got = P.copy()
        zupt.error_state_predict_into(got, C_dt, f_dt, dt, q, work)
        want = Phi @ P @ Phi.T + np.diag(q)
        np.testing.assert_array_equal(got, got.T)
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-13 * np.abs(want).max())
        if dt == 0.0:
            np.testing.assert_array_equal(got, P + np.diag(q))


def test_structured_zupt_zaru_update_is_the_generic_joseph_update():
    """zupt_zaru_update_into (H's structure, Cholesky, one triangle) equals kalman_update with the same H and R to
    rounding: dx, P, NIS, status; rejects by the gate without writing; a NaN measurement is no measurement."""
    from navlib import _kernels

    rng = np.random.default_rng(5)
    for _ in range(50):
        P0 = _random_covariance(rng, 15)
        H = zupt.zupt_zaru_matrix(attitude.euler_to_dcm(random_hpr(rng, 1)[0]), earth.earth_rate_n(rng.uniform(-1.5, 1.5)))
        r = np.concatenate([np.full(3, 10 ** rng.uniform(-6, -2)), np.full(3, 10 ** rng.uniform(-9, -5))])
        z = rng.normal(0, 0.01, 6)
        P, dx = P0.copy(), np.zeros(15)
        nis, status = zupt.zupt_zaru_update_into(P, dx, z, H, r, np.inf)
        x_want, P_want, _, nis_want, status_want = _kernels.kalman_update(
            np.zeros(15), P0, z, np.zeros(6), H, np.diag(r), np.zeros(6, bool)
        )
        assert status == status_want == 1
        np.testing.assert_array_equal(P, P.T)
        np.testing.assert_allclose(P, P_want, rtol=0, atol=1e-12 * np.abs(P_want).max())
        np.testing.assert_allclose(dx, x_want, rtol=0, atol=1e-12 * np.abs(x_want).max())
        assert nis == pytest.approx(nis_want, rel=1e-12)
        P, dx = P0.copy(), np.zeros(15)
        assert zupt.zupt_zaru_update_into(P, dx, z, H, r, nis_want / 2)[1] == -1  # gated: nothing written
        np.testing.assert_array_equal(P, P0)
        z[4] = np.nan
        assert zupt.zupt_zaru_update_into(P, dx, z, H, r, np.inf)[1] == 0
        np.testing.assert_array_equal(P, P0)
        assert not dx.any()


def test_scalar_update_is_the_generic_joseph_update():
    """_kernels.scalar_update (one measurement row, its non-zero columns) equals kalman_update to rounding."""
    from navlib import _kernels

    rng = np.random.default_rng(6)
    for cols in ([2], [6, 7, 8], [0, 5, 14]):
        P0 = _random_covariance(rng, 15)
        h = np.zeros(15)
        h[cols] = rng.normal(size=len(cols))
        y, r = rng.normal(), 10 ** rng.uniform(-4, 0)
        P, dx = P0.copy(), np.zeros(15)
        _kernels.scalar_update(P, dx, y, h, np.array(cols), r)
        x_want, P_want, *_ = _kernels.kalman_update(
            np.zeros(15), P0, np.array([y]), np.zeros(1), h[None], np.array([[r]]), np.zeros(1, bool)
        )
        np.testing.assert_array_equal(P, P.T)
        np.testing.assert_allclose(P, P_want, rtol=0, atol=1e-12 * np.abs(P_want).max())
        np.testing.assert_allclose(dx, x_want, rtol=0, atol=1e-12 * np.abs(x_want).max())


def test_spd_solve_is_the_inverse():
    from navlib import _kernels

    rng = np.random.default_rng(7)
    for m in (1, 3, 6, 9):
        S = _random_covariance(rng, m) + np.eye(m)
        B = rng.normal(size=(m, 4))
        X, F = B.copy(), S.copy()
        assert _kernels.spd_solve_into(F, X)
        np.testing.assert_allclose(S @ X, B, rtol=0, atol=1e-12 * np.abs(B).max())
        assert not _kernels.spd_solve_into(-S, B.copy())  # not positive definite: not solved


def test_zupt_zaru_innovation_is_H_dx_to_second_order():
    rng = np.random.default_rng(3)
    C = attitude.euler_to_dcm([0.7, 0.05, -0.03])
    w_ie = earth.earth_rate_n(LAT)
    b_g = units.deg_per_s(np.array([0.04, -0.03, 0.05]))
    w_meas = C.T @ w_ie + b_g  # static, noise-free
    d = rng.standard_normal(15)
    res = []
    for eps in (1e-3, 5e-4):
        dx = eps * d
        C_hat = attitude.rotvec_to_dcm(dx[6:9]) @ C
        z = zupt.zupt_zaru_innovation(dx[3:6], w_meas, b_g - dx[12:15], C_hat, w_ie)
        res.append(np.abs(z - zupt.zupt_zaru_matrix(C_hat, w_ie) @ dx).max())
    assert res[0] / res[1] == pytest.approx(4.0, rel=0.05)  # residual proportional to error^2


def test_printed_covariance_update_equals_joseph_form():
    rng = np.random.default_rng(4)
    A = rng.standard_normal((15, 15))
    P = A @ A.T + np.eye(15)
    H = zupt.zupt_zaru_matrix(np.eye(3), earth.earth_rate_n(LAT))
    R = np.diag([1e-4] * 3 + [1e-6] * 3)
    K, P_simple = pd.simple_covariance_update(P, H, R)
    _, P_joseph, *_ = kalman.update(np.zeros(15), P, np.zeros(6), np.zeros(6), H, R, np.zeros(6, bool))
    np.testing.assert_allclose(P_simple, P_joseph, atol=1e-12 * np.abs(P).max())
    assert np.linalg.eigvalsh(P_joseph).min() > 0


# ---------------------------------------------------------------- walk and detector


@pytest.fixture(scope="module")
def carpark():
    legs = pd.carpark_legs(stops=(8.0, 5.0, 12.0))
    traj = trajectory.walk(legs, DT, LLA0, 0.0)
    return legs, traj, trajectory.stance_mask(legs, DT)


def test_walk_is_exact_for_ideal_imu_and_has_the_gait(carpark):
    legs, traj, static = carpark
    w, f = trajectory.ideal_imu(traj)
    nav = strapdown.integrate(traj.lla[0], traj.vel_n[0], traj.q_bn[0], w, f, DT)
    np.testing.assert_allclose(nav.lla[:, :2], traj.lla[:, :2], atol=1e-11)
    np.testing.assert_allclose(nav.vel_n, traj.vel_n, atol=1e-6)
    assert np.abs(traj.vel_n[static]).max() < 0.01
    straight = trajectory.walk([trajectory.Leg(5.0), trajectory.Leg(30.0, 1.2), trajectory.Leg(5.0)], DT, LLA0, 0.0)
    up = straight.vel_n[1000:3000, 2]  # 20 s of steady walking
    spec = np.abs(np.fft.rfft(up - up.mean()))
    freq = np.fft.rfftfreq(up.size, DT)
    assert abs(freq[spec.argmax()] - trajectory.Gait().step_frequency) < 0.05
    assert np.ptp(traj.lla[:, 2]) == pytest.approx(2 * trajectory.Gait().bounce, rel=0.05)
    assert np.rad2deg(attitude.wrap_pi(traj.hpr[-1, 0] - traj.hpr[0, 0])) == pytest.approx(0.0, abs=0.5)


def test_detector_rates_on_labelled_walk(carpark):
    _, traj, static = carpark
    w, f = trajectory.ideal_imu(traj)
    imu = sensors.simulate_imu(w, f, DT, RESIDUAL, np.random.default_rng(5))
    det = zupt.detect_static(imu.w_ib_b, imu.f_b, DT)
    p_d, p_fa = analysis.detection_rates(det, static[:-1])
    assert p_d > 0.95 and p_fa < 0.01
    with pytest.raises(ValueError, match="^window: "):
        zupt.detect_static(imu.w_ib_b[:30], imu.f_b[:30], DT, window=0.5)


def test_detector_ignores_dropouts_and_needs_half_a_window(carpark):
    _, traj, static = carpark
    w, f = trajectory.ideal_imu(traj)
    imu = sensors.simulate_imu(w, f, DT, RESIDUAL, np.random.default_rng(5))
    clean = zupt.detect_static(imu.w_ib_b, imu.f_b, DT)
    wn, fn = imu.w_ib_b.copy(), imu.f_b.copy()
    drop = np.random.default_rng(6).random(len(wn)) < 0.1
    wn[drop], fn[drop] = np.nan, np.nan
    wn[2000:2100] = np.nan  # 1 s without data: never static
    det = zupt.detect_static(wn, fn, DT)
    assert not det[2000 + 25 : 2100 - 25].any()
    other = np.ones(len(det), bool)
    other[1950:2150] = False
    assert np.mean(det[other] == clean[other]) > 0.99  # 10 % dropouts barely matter


def test_floor_test_legs_round_trip():
    legs = pd.floor_test_legs()
    traj = trajectory.walk(legs, 0.05, LLA0, 0.0)
    static = trajectory.stance_mask(legs, 0.05)
    _, _, floors = atmosphere.segment_floors(traj.lla[:, 2] - 20.0, static, ref_floor=2)
    assert floors.tolist() == [2, 1, 2, 1, 2]


# ---------------------------------------------------------------- filter


def run(w, f, q0, static, vel_n=(0.0, 0.0, 0.0), **kw):
    """The ZUPT/ZARU filter on samples at DT from LLA0."""
    return zupt_ins.run_filter(ImuSamples(w, f, DT), zupt_ins.Start(LLA0, q0, vel_n), static, **kw)


@pytest.fixture(scope="module")
def static_run():
    traj = trajectory.static(120.0, DT, LLA0, [0.3, 0.0, 0.0])
    w, f = trajectory.ideal_imu(traj)
    imu = sensors.simulate_imu(w, f, DT, RESIDUAL, np.random.default_rng(6))
    pitch, roll = alignment.level(imu.f_b[:100].mean(0))
    q0 = attitude.euler_to_quat([0.3, float(pitch), float(roll)])
    return traj, imu, q0


def test_static_zupt_zaru_holds_position_and_finds_gyro_bias(static_run):
    traj, imu, q0 = static_run
    res = run(imu.w_ib_b, imu.f_b, q0, np.ones(len(imu.f_b), bool))
    R_M, _ = earth.radii(LAT)
    assert res.updated and res.zupt_updates == 1200
    assert np.std(res.nav.lla[:, 0]) * R_M < 0.01
    assert np.abs(res.gyro_bias[-1] - imu.gyro_bias[-1]).max() < units.deg_per_s(0.005)
    free = strapdown.integrate(LLA0, np.zeros(3), q0, imu.w_ib_b, imu.f_b, DT)
    assert np.std(free.lla[:, 0]) * R_M > 100.0


def test_no_static_interval_is_reported_not_hidden(static_run):
    traj, imu, q0 = static_run
    with pytest.warns(RuntimeWarning, match="no ZUPT/ZARU update"):
        res = run(imu.w_ib_b, imu.f_b, q0, np.zeros(len(imu.f_b), bool))
    assert not res.updated
    free = strapdown.integrate(LLA0, np.zeros(3), q0, imu.w_ib_b, imu.f_b, DT)
    np.testing.assert_array_equal(res.nav.lla, free.lla)  # exactly the free INS: same mechanisation


def test_repeated_rejections_force_an_update_instead_of_locking_out(static_run):
    traj, imu, q0 = static_run
    res = run(imu.w_ib_b, imu.f_b, q0, np.ones(len(imu.f_b), bool), vel_n=[3.0, 0.0, 0.0])
    assert res.faults["zupt", "outlier"] == zupt_ins.Gates().max_rejected
    assert res.faults["zupt", "reacquired"] == 1
    assert np.abs(res.nav.vel_n[-1]).max() < 0.01


def test_filter_survives_dropouts_and_gates_false_zupts(static_run):
    traj, imu, q0 = static_run
    w, f = imu.w_ib_b.copy(), imu.f_b.copy()
    w[500:520] = np.nan
    f[700] = np.nan
    static = np.ones(len(f), bool)
    res = run(w, f, q0, static)
    assert res.faults["gyro", "nan"] == 20 and res.faults["accel", "nan"] == 1
    assert np.all(np.isfinite(res.nav.lla))
    # a walker flagged static for 1 s in the middle of a walk: the NIS gate rejects most of those updates
    legs = [trajectory.Leg(20.0), trajectory.Leg(20.0, 1.2), trajectory.Leg(10.0)]
    walk = trajectory.walk(legs, DT, LLA0, 0.0)
    ww, fw = trajectory.ideal_imu(walk)
    imu_w = sensors.simulate_imu(ww, fw, DT, RESIDUAL, np.random.default_rng(7))
    flags = trajectory.stance_mask(legs, DT)[:-1].copy()
    flags[3000:3100] = True
    res = run(imu_w.w_ib_b, imu_w.f_b, walk.q_bn[0], flags)
    assert res.faults["zupt", "outlier"] >= 5


def test_walking_aids_bound_heading_and_height(carpark):
    legs, traj, static = carpark
    ss = np.random.SeedSequence(8).spawn(3)
    w, f = trajectory.ideal_imu(traj)
    imu = sensors.simulate_imu(w, f, DT, RESIDUAL, np.random.default_rng(ss[0]))
    B = earth.magnetic_field(30.55, 114.30, 20.0, 2016.5)
    D = earth.field_angles(B, deg=False)[0]
    m = sensors.simulate_magnetometer(
        traj.q_bn[:-1], B, sensors.MagnetometerModel.from_preset("HMC5983"), np.random.default_rng(ss[1])
    ).m_b
    p = sensors.simulate_barometer(
        traj.lla[:-1, 2], traj.time[:-1], sensors.BarometerModel.from_preset("BMP180"), np.random.default_rng(ss[2])
    )
    h = 20.0 + atmosphere.baro_height(p, atmosphere.reference_pressure(p, traj.time[:-1], 20.0))
    h[np.arange(h.size) % 10 != 0] = np.nan  # 10 Hz barometer and magnetometer
    m[np.arange(h.size) % 10 != 0] = np.nan
    det = zupt.detect_static(imu.w_ib_b, imu.f_b, DT)
    out = {}
    for mode in ("reset", "filter", "none"):
        res = run(imu.w_ib_b, imu.f_b, traj.q_bn[0], det, h_baro=h, m_b=m, aiding=zupt_ins.Aiding(mode, declination=float(D)))
        out[mode] = (
            np.abs(attitude.wrap_pi(res.nav.hpr[:, 0] - traj.hpr[:, 0])).max(),
            np.abs(res.nav.lla[:, 2] - traj.lla[:, 2]).max(),
            res,
        )
    assert out["reset"][0] < np.deg2rad(3) and out["filter"][0] < np.deg2rad(3)
    assert out["reset"][1] < 1.0 and out["filter"][1] < 1.0
    assert out["reset"][2].mag_aidings > 1000
    assert out["none"][2].mag_aidings == 0
    # ENU sign of the heading reset: a 10-degree initial heading error is removed while walking
    q_off = attitude.euler_to_quat(traj.hpr[0] + [np.deg2rad(10.0), 0.0, 0.0])
    res = run(imu.w_ib_b, imu.f_b, q_off, det, h_baro=h, m_b=m, aiding=zupt_ins.Aiding(declination=float(D)))
    err = np.abs(attitude.wrap_pi(res.nav.hpr[:, 0] - traj.hpr[:, 0]))
    assert err[0] > np.deg2rad(9.9) and err[int(40 / DT) :].max() < np.deg2rad(3)
    # a strong disturbance everywhere: the gate on field magnitude and dip rejects it
    cfg = zupt_ins.FilterConfig(gates=zupt_ins.Gates(mag_field=5.0, mag_dip=np.deg2rad(5)))
    res = run(
        imu.w_ib_b,
        imu.f_b,
        traj.q_bn[0],
        det,
        h_baro=h,
        m_b=m + np.array([0.0, 0.0, 30.0]),
        aiding=zupt_ins.Aiding(declination=float(D), B_n=B),
        config=cfg,
    )
    assert res.faults["mag", "outlier"] > 0 and res.mag_aidings == 0


def test_kernel_runs_uncompiled_with_the_same_result():
    script = r"""
import json, numpy as np, warnings
from navlib import trajectory, units
from navlib.filters import zupt, zupt_ins
from navlib.imu import ImuSamples, SensorLimits
legs = [trajectory.Leg(3.0), trajectory.Leg(3.0, 1.0, turn=0.5), trajectory.Leg(2.0)]
traj = trajectory.walk(legs, 0.02, [0.5, 1.9, 10.0], 0.2)
w, f = trajectory.ideal_imu(traj)
static = trajectory.stance_mask(legs, 0.02)[:-1]
m = np.tile([10.0, 20.0, -30.0], (len(w), 1))
start = zupt_ins.Start(traj.lla[0], traj.q_bn[0], traj.vel_n[0])
res = zupt_ins.run_filter(ImuSamples(w + 1e-3, f, 0.02), start, static, h_baro=traj.lla[:-1, 2], m_b=m)
# the fault paths: a dropout, a spike, clipping, a baro spike, per-sample intervals, a time jump, free fall
w2, f2, h2 = w + 1e-3, f.copy(), traj.lla[:-1, 2].copy()
w2[50] = np.nan
f2[120, 2] += 5.0
f2[250:255] = 0.0
h2[300] += 50.0
dt = 0.02 * (1 + 0.1 * np.sin(np.arange(len(w))))
dt[200] = 5.0
limits = SensorLimits(full_scale_gyro=0.3, full_scale_accel=11.0, spike_gyro=0.02, spike_accel=0.5)
res2 = zupt_ins.run_filter(ImuSamples(w2, f2, dt, limits), start, static, h_baro=h2, m_b=m)
counts = lambda r: dict(r.faults.as_dict(), zupt=r.zupt_updates, baro=r.baro_aidings, mag=r.mag_aidings)
print(json.dumps({"lla": res.nav.lla.tolist(), "counts": counts(res), "lla2": res2.nav.lla.tolist(),
                  "counts2": counts(res2), "flags2": {f"{s}.{k}": v.tolist() for (s, k), v in res2.faults.flags.items()}}))
"""
    runs = []
    for flag in ("0", "1"):
        env = dict(os.environ, NUMBA_DISABLE_JIT=flag)
        out = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True, text=True, check=True)
        runs.append(json.loads(out.stdout))
    np.testing.assert_allclose(runs[0]["lla"], runs[1]["lla"], rtol=0, atol=1e-12)
    assert runs[0]["counts"] == runs[1]["counts"]
    np.testing.assert_allclose(runs[0]["lla2"], runs[1]["lla2"], rtol=0, atol=1e-12)
    assert runs[0]["counts2"] == runs[1]["counts2"] and runs[0]["flags2"] == runs[1]["flags2"]
    c = runs[0]["counts2"]
    assert c["gyro.nan"] == 1 and c["accel.spike"] == 1 and c["baro.outlier"] == 1
    assert c["gyro.saturated"] + c["accel.saturated"] > 0 and c["clock.jump"] == 1 and c["accel.freefall"] == 5


# ---------------------------------------------------------------- barometer and floors


def test_baro_height_formula_and_floors():
    p_ref = 100500.0
    h = np.array([-3.0, 0.0, 3.0, 6.1])
    from navlib import atmosphere

    p = atmosphere.bmp180_pressure(h, p_ref)
    np.testing.assert_allclose(atmosphere.baro_height(p, p_ref), h, atol=1e-9)
    assert np.allclose(atmosphere.baro_height(p, p_ref, temperature=288.15), h, atol=0.05)
    assert atmosphere.classify_floor(h, 3.0, 2).tolist() == [1, 2, 3, 4]
    t = np.arange(10.0)
    assert atmosphere.reference_pressure(np.r_[np.full(5, 1e5), np.full(5, 2e5)], t, 4.0) == 1e5
    steps = pd.hvac_pressure_steps(t, [2.5, 6.5], np.random.default_rng(0), 10.0)
    assert steps[0] == 0 and np.all(np.abs(steps) <= 10) and len(np.unique(steps)) == 3


def test_barometer_batches_equal_their_series_bit_for_bit():
    # A (trials, N) batch through the floor chain gives each trial's 1-D result exactly (notebook 05's
    # floor Monte Carlo runs as one batch per cell).
    rng = np.random.default_rng(3)
    t = np.arange(0.0, 120.0, 0.1)
    static = (t % 40.0) < 25.0
    h_true = np.where(t < 40.0, 0.0, np.where(t < 80.0, -3.0, 3.0))
    p = atmosphere.bmp180_pressure(h_true, 100500.0) + rng.normal(0.0, 6.0, (7, t.size))
    p[2, [0, 3, 40]] = np.nan  # a series with dropouts in the reference window
    doors = [30.0, 70.0]
    steps = pd.hvac_pressure_steps(t, doors, np.random.default_rng(4), 10.0, n_trials=7)
    one_by_one = np.random.default_rng(4)
    assert np.array_equal(steps, [pd.hvac_pressure_steps(t, doors, one_by_one, 10.0) for _ in range(7)])
    p = p + steps
    p_ref = atmosphere.reference_pressure(p, t, 20.0)
    assert p_ref.shape == (7,)
    assert np.array_equal(p_ref, [atmosphere.reference_pressure(row, t, 20.0) for row in p])
    h = atmosphere.baro_height(np.nan_to_num(p, nan=1e5), p_ref[:, None])
    assert np.array_equal(h, [atmosphere.baro_height(np.nan_to_num(row, nan=1e5), r) for row, r in zip(p, p_ref, strict=True)])
    h[4, 50:60] = np.nan
    starts, ends, floors = atmosphere.segment_floors(h, static, ref_floor=2)
    assert floors.shape == (7, starts.size) and floors.dtype.kind == "i"
    for row, f in zip(h, floors, strict=True):
        assert np.array_equal(atmosphere.segment_floors(row, static, ref_floor=2)[2], f)
    assert atmosphere.segment_floors(h, np.zeros(t.size, bool))[2].shape == (7, 0)


# ---------------------------------------------------------------- PDR


def test_step_detection_and_pdr(carpark):
    legs, traj, static = carpark
    w, f = trajectory.ideal_imu(traj)
    imu = sensors.simulate_imu(w, f, DT, RESIDUAL, np.random.default_rng(9))
    steps = pdr.detect_steps(imu.f_b, DT, g=pd.G_LOCAL)
    a_up = np.diff(traj.vel_n[:, 2]) / DT  # true vertical acceleration
    true_steps = np.sum((a_up[1:-1] > a_up[:-2]) & (a_up[1:-1] >= a_up[2:]) & (a_up[1:-1] > 1.0))
    assert steps.index.size == pytest.approx(true_steps, rel=0.03)
    en = pdr.pdr(np.ones(4), np.array([0, np.pi / 2, np.pi, 3 * np.pi / 2]))
    np.testing.assert_allclose(en[-1], [0.0, 0.0], atol=1e-12)
    np.testing.assert_allclose(en[1], [0.0, 1.0], atol=1e-12)


# ---------------------------------------------------------------- bad input


@pytest.mark.parametrize(
    "call, arg",
    [
        (lambda: atmosphere.baro_height([100000.0, 0.0], 101325.0), "p"),
        (lambda: atmosphere.baro_height([100000.0, -5.0], 101325.0), "p"),
        (lambda: atmosphere.baro_height([np.nan], 101325.0), "p"),
        (lambda: atmosphere.baro_height([np.inf], 101325.0), "p"),
        (lambda: atmosphere.baro_height([1e5], 0.0), "p_ref"),
        (lambda: alignment.magnetic_heading([0.0, 0.0, 0.0], 0.0, 0.0), "m_b"),
        (lambda: alignment.magnetic_heading([np.nan, 1.0, 0.0], 0.0, 0.0), "m_b"),
        (lambda: pd.heading_from_horizontal(0.0, 0.0), "H_X, H_Y"),
        (lambda: zupt.detect_static(np.zeros((10, 3)), np.zeros((10, 3)), 0.01, window=1.0), "window"),
        (lambda: zupt.detect_static(np.zeros((10, 3)), np.zeros((9, 3)), 0.01), "f_b"),
        (lambda: analysis.detection_rates(np.ones(5, bool), np.ones(5, bool)), "truth"),
        (lambda: trajectory.walk([], 0.01, LLA0, 0.0), "legs"),
        (lambda: trajectory.Leg(-1.0), "duration"),
        (lambda: trajectory.Leg(5.0, 0.0, turn=1.0), "turn, climb"),
        (lambda: trajectory.Gait(step_frequency=0.0), "step_frequency"),
        (lambda: zupt_ins.MeasurementNoise(zupt=0.0), "zupt"),
        (lambda: alignment.level([0.0, 0.0, 0.0]), "f_b"),
        (lambda: atmosphere.reference_pressure([np.nan, np.nan], [0.0, 1.0], 5.0), "until"),
        (lambda: atmosphere.classify_floor([1.0], floor_height=0.0), "floor_height"),
        (lambda: run(np.zeros((5, 3)), np.tile([0, 0, 9.8], (5, 1)), [1, 0, 0, 0], np.ones(4, bool)), "static"),
        (
            lambda: run(np.zeros((5, 3)), np.tile([0, 0, 9.8], (5, 1)), [1, 0, 0, 0], np.ones(5, bool), m_b=np.zeros((5, 3))),
            "m_b",
        ),
        (lambda: zupt_ins.Aiding(walk="magic"), "walk"),
        (lambda: pdr.detect_steps(np.zeros((5, 3)), 0.01), "f_b"),
        (lambda: pdr.weinberg_step_length([1.0], K=-1.0), "K"),
        (lambda: pdr.pdr([1.0, 2.0], [0.0]), "step_headings"),
        # found by tools/fuzz.py (issue 15, item 4): accepted silently, or an error naming no argument
        (lambda: pd.carpark_legs(stops=[[8.0, 5.0]]), "stops"),
        (lambda: pd.carpark_legs(side=[[40.0, 24.0]] * 2), "side"),
        (lambda: pd.hvac_pressure_steps([2.0, 1.0, 0.0], [1.0], np.random.default_rng(0)), "time"),
        (lambda: pd.hvac_pressure_steps([0.0, 1.0], np.zeros((2, 2)), np.random.default_rng(0)), "door_times"),
    ],
)
def test_bad_input_names_the_argument(call, arg):
    with pytest.raises(ValueError, match=f"^{arg}: "):
        call()
