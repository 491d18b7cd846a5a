"""Tests of navlib.papers.gauss_kruger_ekf: the paper's projection equations (1)-(11), motion model, EKF cycle,
dropouts, zone crossing (bad input: the registry tools/fuzz_calls.py, run by tests/test_bad_input.py)."""

import json
import os
import subprocess
import sys

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose

from navlib import analysis, earth, geodesy
from navlib.filters import planar_ekf
from navlib.imu import SensorLimits
from navlib.papers import gauss_kruger_ekf as planar

PAPER = planar.PAPER_CONFIG  # the paper's noise, Eqs. (17)-(18)
ORIGIN = np.deg2rad([26.06, 119.20])  # paper 002 site (Fuzhou, assumed), GK zone 40
X0_STRAIGHT = np.array([0.0, 0.0, np.pi / 4, 1.0, 0.0])
CGCS = dict(ellipsoid=earth.CGCS2000)  # the paper's datum; navlib.geodesy defaults to WGS84


def config(**kw):
    """The paper's noise with the options ``kw`` (EkfConfig fields)."""
    return planar_ekf.EkfConfig(planar.Q_PAPER, planar.R_PAPER, **kw)


def rejected_epochs(res):
    """Epochs with some channel gated out."""
    return np.any([mask for (_, kind), mask in res.faults.flags.items() if kind == "outlier"], axis=0)


def straight_run(seed, n=2000, T=0.5, R=planar.R_PAPER, **kw):
    truth = planar_ekf.propagate(X0_STRAIGHT, T, n)
    t = np.arange(n + 1) * T
    sens = planar.simulate_sensors(truth, ORIGIN, R, np.random.default_rng(seed), **kw)
    return t, truth, sens


def test_jacobian_equals_finite_differences():
    """Eq. (16) is the Jacobian of the reconstructed Eq. (13) (central differences, 1e-8)."""
    rng = np.random.default_rng(0)
    X = rng.uniform([-50, -50, -np.pi, 0, -1], [50, 50, np.pi, 3, 1], (20, 5))
    T, h = 0.5, 1e-6
    num = np.stack(
        [(planar_ekf.motion_model(X + h * e, T) - planar_ekf.motion_model(X - h * e, T)) / (2 * h) for e in np.eye(5)], -1
    )
    assert_allclose(planar_ekf.jacobian(X, T), num, rtol=0, atol=1e-8)


def test_circle_radius_for_5_deg_per_s():
    """Fig. 5: omega0 = 5 deg/s gives a circle of radius v/omega = 11.459 m; 5 rad/s a 0.53 m polygon."""
    X = planar_ekf.propagate([0, 0, 0, 1, np.deg2rad(5)], 0.5, 144)  # one period, 72 s
    assert abs(np.ptp(X[:, 1]) / 2 - 1 / np.deg2rad(5)) < 0.01
    assert np.hypot(*X[-1, :2]) < 1e-9
    P = planar_ekf.propagate([0, 0, 0, 1, 5.0], 0.5, 200)
    assert np.ptp(P[:, 0]) < 0.6 and np.ptp(P[:, 1]) < 0.6


def test_fast_update_equals_general_kalman_update():
    """The H = I5 specialised update gives the same states, covariances and NIS as kalman.update."""
    t, truth, s = straight_run(1, n=400)
    z = np.column_stack(
        [truth[:, :2] + np.random.default_rng(2).normal(0, 2.5, (401, 2)), truth[:, 2] + np.pi + 0.1, s.speed, s.yaw_rate]
    )  # heading near the wrap
    fast = planar_ekf.filter_grid(t, z, X0_STRAIGHT, config(P0=np.eye(5)))
    slow = planar_ekf.filter_grid(t, z, X0_STRAIGHT, config(P0=np.eye(5), fast=False))
    assert_allclose(fast.x, slow.x, rtol=0, atol=1e-10)
    assert_allclose(fast.P, slow.P, rtol=0, atol=1e-12)
    assert_allclose(fast.nis[1:], slow.nis[1:], rtol=1e-10)


def test_update_with_identity_h_is_the_linear_update_with_wrapped_heading():
    """Eqs. (14)-(15): with H = I5 the EKF update is the linear KF update; a heading innovation near ±pi wraps."""
    P = np.diag([4.0, 4.0, 0.04, 0.01, 0.01])
    x0 = np.array([10.0, -5.0, np.pi - 0.05, 1.0, 0.0])
    z = np.array([11.0, -4.0, -np.pi + 0.05, 1.1, 0.02])  # heading 0.1 rad clockwise of x0
    res = planar_ekf.filter_grid(
        [0.0, 1e-9], np.vstack([np.full(5, np.nan), z]), x0, planar_ekf.EkfConfig(np.zeros(5), planar.R_PAPER, P)
    )
    R = planar.R_PAPER
    K = P @ np.linalg.inv(P + R)
    innov = z - x0
    innov[2] = 0.1
    expected = x0 + K @ innov
    expected[2] = np.mod(expected[2], 2 * np.pi)
    assert_allclose(res.x[1], expected, rtol=0, atol=1e-6)  # 1e-9 s of prediction moves x by 1e-9 m
    assert not res.prediction_only[1] and not res.faults


def test_ekf_beats_dead_reckoning_and_is_consistent_with_R():
    """Fig. 4 set-up (paper Q, R in SI): EKF position RMSE ~1.6 m < GPS sigma 2.5 m; DR drifts away."""
    t, truth, s = straight_run(3, yaw_rate_bias=np.deg2rad(0.05))
    res = planar.ekf(t, s, X0_STRAIGHT, origin=ORIGIN)
    dr, held = planar_ekf.dead_reckoning(t, s.speed, s.yaw_rate, X0_STRAIGHT)
    e_ekf = analysis.position_error(res.x, truth)
    e_dr = analysis.position_error(dr, truth)
    rmse = np.sqrt(np.mean(e_ekf**2))
    assert 1.3 < rmse < 1.9
    assert rmse < np.sqrt(np.mean(e_dr**2)) and not held
    assert res.zone == 40 and not res.prediction_only.any() and res.faults["gnss", "nan"] == 0
    # The truth is noise-free, so the paper's Q overstates the process noise: conservative, NIS < 5 dof.
    nis = np.nanmean(res.nis[100:])
    assert 2.5 < nis < 5.0


def test_gps_outage_is_prediction_only_and_counted():
    valid = np.ones(2001, bool)
    valid[800:920] = False  # 60 s without GPS
    t, truth, s = straight_run(4, gps_valid=valid)
    res = planar.ekf(t, s, X0_STRAIGHT, origin=ORIGIN)
    assert res.faults["gnss", "nan"] == 120 and not res.prediction_only.any()
    assert np.all(np.isfinite(res.x))
    var = res.P[:, 0, 0] + res.P[:, 1, 1]
    assert var[919] > 5 * var[799] and var[1000] < 2 * var[799]  # grows in the gap, recovers after
    s.heading[500:510] = np.nan
    s.speed[500:510] = np.nan
    s.yaw_rate[500:510] = np.nan
    s.gps[500:510] = np.nan
    res = planar.ekf(t, s, X0_STRAIGHT, origin=ORIGIN)
    assert res.prediction_only.sum() == 10 and np.all(res.prediction_only[500:510])


def test_gate_rejects_gps_outlier():
    t, truth, s = straight_run(5, n=400)
    res = planar.ekf(t, s, X0_STRAIGHT, origin=ORIGIN, config=config(P0=np.eye(5)))
    s.gps[300, 0] += 1e-4  # ~640 m north
    gated = planar.ekf(t, s, X0_STRAIGHT, origin=ORIGIN, config=config(P0=np.eye(5), gate=30.0))
    assert gated.faults.flags["gnss", "outlier"][300]
    assert analysis.position_error(gated.x[300], truth[300]) < 5
    assert 1 <= rejected_epochs(gated).sum() <= 2 and np.abs(gated.x[-1, :2] - res.x[-1, :2]).max() < 5


def test_zone_crossing_stays_continuous_and_convergence_corrects_heading():
    """An eastward run across 121.5° E (zone 40 -> 41): one zone held, no jump; grid heading corrected."""
    lat0 = np.deg2rad(26.06)
    x_e, y_e = geodesy.geodetic2gk(lat0, np.deg2rad(121.4), zone=40, **CGCS)
    origin = np.array(geodesy.gk2geodetic(x_e, y_e, zone=40, **CGCS))
    x0 = np.array([0.0, 0.0, np.pi / 2, 20.0, 0.0])  # due grid east at 20 m/s
    n, T = 2000, 0.5
    truth = planar_ekf.propagate(x0, T, n)
    R = np.diag([6.25, 6.25, np.deg2rad(0.5) ** 2, 4e-4, 2.5e-3])
    s = planar.simulate_sensors(truth, origin, R, np.random.default_rng(6))
    assert geodesy.zone(s.gps[-1, 1]) == 41
    t = np.arange(n + 1) * T
    res = planar.ekf(t, s, x0, origin=origin, config=planar_ekf.EkfConfig(planar.Q_PAPER, R))
    assert res.zone == 40 and np.abs(np.diff(res.z[1:, 1])).max() < 30
    err = np.angle(np.exp(1j * (res.x[:, 2] - truth[:, 2])))
    raw = planar.ekf(t, s, x0, origin=origin, config=planar_ekf.EkfConfig(planar.Q_PAPER, R), correct_convergence=False)
    err_raw = np.angle(np.exp(1j * (raw.x[:, 2] - truth[:, 2])))
    gamma = geodesy.convergence(s.gps[:, 0], s.gps[:, 1], zone=40, **CGCS)
    assert abs(np.mean(err)) < 0.05 * np.mean(gamma)
    assert abs(np.mean(err_raw) / np.mean(gamma) - 1) < 0.2


def test_dead_reckoning_holds_through_nan_and_adds_velocity_bias():
    t = np.arange(11.0)
    v, w = np.ones(11), np.zeros(11)
    v[3] = np.nan
    pose, held = planar_ekf.dead_reckoning(t, v, w, [0, 0, 0, 1, 0], velocity_bias=[0.0, 0.1])
    assert held["speed", "nan"] == held.total() == 1 and held.flags["speed", "nan"][3]
    assert_allclose(pose[-1], [10.0, 1.0, 0.0], rtol=0, atol=1e-12)


def test_waypoint_path_reaches_every_mark():
    marks = np.array([[0, 0], [0, 1], [0, 2], [1, 2], [2, 2], [2, 1], [2, 0], [1, 0], [1, 1.0]])
    X, idx = planar.waypoint_path(marks, 0.1, np.deg2rad(15), 0.5)
    assert_allclose(X[idx, :2], marks, rtol=0, atol=1e-12)
    assert np.all(np.diff(idx) > 0)


def test_kernels_run_uncompiled_with_the_same_results():
    script = r"""
import json, numpy as np
from navlib.filters import planar_ekf
from navlib.imu import SensorLimits
from navlib.papers import gauss_kruger_ekf as planar
t = np.arange(50) * 0.5
rng = np.random.default_rng(0)
z = np.column_stack([rng.normal(0, 2, (50, 2)), rng.normal(0.3, 0.1, 50), np.ones(50), np.zeros(50)])
z[10:15, :2] = np.nan
r = planar_ekf.filter_grid(t, z, [0, 0, 0.3, 1, 0], planar_ekf.EkfConfig(planar.Q_PAPER, planar.R_PAPER, np.eye(5)))
d, _ = planar_ekf.dead_reckoning(t, z[:, 3], z[:, 4], [0, 0, 0.3, 1, 0], full_scale_gyro=0.1)
z[20, 0] += 50.0
z[21:25, 3] += 5.0                                  # a 4-epoch step: 3 rejections, reacquired; back: same
z[30, 4] = 0.5                                                      # at the rails
g = planar_ekf.filter_grid(t, z, [0, 0, 0.3, 1, 0], planar_ekf.EkfConfig(
    planar.Q_PAPER, planar.R_PAPER, np.eye(5), [18.4, 15.1, 15.1, 15.1], limits=SensorLimits(full_scale_gyro=0.5)))
count = lambda kind: [g.faults[sensor, kind] for sensor in ("gnss", "heading", "speed", "yaw_rate")]
print(json.dumps({"x": r.x.tolist(), "d": d.tolist(), "g": g.x.tolist(), "rej": count("outlier"),
                  "reacq": count("reacquired"), "sat": g.faults["yaw_rate", "saturated"]}))
"""
    out = {}
    for flag in ("0", "1"):
        env = dict(os.environ, NUMBA_DISABLE_JIT=flag)
        run = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True, text=True, check=True)
        out[flag] = json.loads(run.stdout)
    assert_allclose(out["1"]["x"], out["0"]["x"], rtol=0, atol=1e-9)
    assert_allclose(out["1"]["d"], out["0"]["d"], rtol=0, atol=1e-12)
    assert_allclose(out["1"]["g"], out["0"]["g"], rtol=0, atol=1e-9)
    for key in ("rej", "reacq", "sat"):
        assert out["1"][key] == out["0"][key]
    assert out["0"]["rej"] == [1, 0, 6, 0] and out["0"]["reacq"] == [0, 0, 2, 0] and out["0"]["sat"] == 1


# --------------------------------------------------------------------------
# The paper's projection equations, Eqs. (1)-(11) (moved here from navlib.geodesy)
# --------------------------------------------------------------------------


def test_printed_zone_number_is_not_an_integer():
    """Erratum E002-01: the printed n = (L - 1.5)/3 is 39.23 at 119.2° E (geodesy.zone: 40)."""
    assert abs(planar.printed_zone_number(119.2, deg=True) - 39.2333333) < 1e-6
    assert abs(planar.printed_zone_number(np.deg2rad(119.2)) - 39.2333333) < 1e-6  # radians by default
    assert geodesy.zone(119.2, deg=True) == 40


def arc_by_quadrature(lat, ell, order=64):
    """Integral of the paper's R_M (corrected Eq. 6) from 0 to lat by Gauss-Legendre."""
    nodes, weights = np.polynomial.legendre.leggauss(order)
    w = lat / 2 * (nodes + 1)
    return lat / 2 * np.sum(weights * planar.paper_radii(w, ell)[3])


def test_meridian_arc_series_against_quadrature():
    """Eqs. (7)-(8) are correct (erratum E002-05): 1e-8 m at 26°, 1e-6 m at 45°, 1e-4 m at 89.9°."""
    ell = earth.CGCS2000
    for lat_deg, tol in ((26.0, 1e-8), (45.0, 1e-6), (89.9, 1e-4)):
        exact = arc_by_quadrature(np.deg2rad(lat_deg), ell)
        assert abs(planar.paper_meridian_arc(lat_deg, ell, deg=True) - exact) < tol
        assert abs(geodesy.meridian_arc(lat_deg, ell, deg=True) - exact) < 1e-8
    assert planar.paper_meridian_arc(26.06, deg=True) == planar.paper_meridian_arc(26.06, earth.CGCS2000, deg=True)


@settings(max_examples=200, deadline=None)
@given(a=st.floats(-89.0, 89.0), ell=st.sampled_from([earth.CGCS2000, earth.WGS84, earth.KRASSOVSKY]))
def test_paper_arc_series_equals_kruger(a, ell):
    """The paper's e^8 series equals Krüger's (navlib.geodesy.meridian_arc) to 1e-4 m."""
    assert abs(planar.paper_meridian_arc(a, ell, deg=True) - geodesy.meridian_arc(a, ell, deg=True)) < 1e-4


def test_paper_radii():
    """Eqs. (3)-(6): R_N as in earth.radii; corrected R_M = 6 347 737.10 m at 26.06° N; printed 4.04e13."""
    e1, e2, R_N, R_M = planar.paper_radii(26.06, deg=True)
    R_M_ref, R_N_ref = earth.radii(26.06, deg=True, ellipsoid=earth.CGCS2000)
    assert abs(e1**2 - earth.CGCS2000.e2) < 1e-15
    assert abs(R_N / R_N_ref - 1) < 1e-12 and abs(R_M / R_M_ref - 1) < 1e-12
    assert abs(R_M - 6_347_737.10) < 0.01
    assert 4.0e13 < planar.printed_meridian_radius(26.06, deg=True) < 4.1e13


def test_paper_series_and_its_typos():
    """Erratum E002-03: corrected series within 1 µm of PROJ for |l| <= 1.5° at 26° N; typos 0.31 mm / 19.7 mm."""
    pyproj = pytest.importorskip("pyproj")
    tm = pyproj.Proj("+proj=tmerc +ellps=GRS80 +lon_0=120 +k=1 +x_0=0 +y_0=0 +algo=poder_engsager +units=m")
    l = np.linspace(-1.5, 1.5, 31)
    east, north = tm.transform(120 + l, np.full_like(l, 26.0))
    x, y = planar.paper_series(26.0, 120 + l, 120.0, deg=True)
    assert np.abs(x - north).max() < 1e-6 and np.abs(y - east).max() < 1e-6
    for off, mm in ((1.5, 0.31), (3.0, 19.7)):
        xt, _ = planar.paper_series(26.0, 120 + off, 120.0, deg=True, typos=True)
        assert abs((xt - tm.transform(120 + off, 26.0)[1]) * 1e3 / mm - 1) < 0.05


def test_printed_units_and_a_shorter_arc_series_fail():
    """Errata E002-04 (l and W in degrees) and E002-05 (the printed arc series is right: one order less is not)."""
    x, y = planar.paper_series(26.06, 119.2, 120.0, deg=True)
    x_deg, y_deg = planar.paper_series(26.06, 119.2, 120.0, deg=True, printed_units=True)
    assert y_deg / y > 50 and x_deg / x > 50  # (180/pi)^k on every l^k term; A W in x
    arc = planar.paper_meridian_arc(26.06, deg=True)
    assert 1e-6 < abs(planar.paper_meridian_arc(26.06, deg=True, order=6) - arc) < 1e-5  # the e^8 terms: micrometres
    assert abs(planar.paper_meridian_arc(26.06, deg=True, order=2) - arc) > 1.0


def test_dead_reckoning_error_ms_matches_monte_carlo():
    """The closed-form DR error (heading random walk) against simulated dead reckoning, within 4 standard errors."""
    truth = planar_ekf.propagate([0.0, 0.0, 0.3, 1.0, 0.05], 0.5, 200)
    R = np.diag([1.0, 1.0, 0.01, 0.02**2, 0.05**2])
    ms = planar.dead_reckoning_error_ms(truth, 0.5, R, yaw_rate_bias=0.01)
    rng = np.random.default_rng(7)
    t = 0.5 * np.arange(len(truth))
    sq = []
    for _ in range(400):
        speed = truth[:, 3] + 0.02 * rng.standard_normal(len(truth))
        rate = truth[:, 4] + 0.01 + 0.05 * rng.standard_normal(len(truth))
        dr, _ = planar_ekf.dead_reckoning(t, speed, rate, truth[0])
        sq.append(analysis.position_error(dr, truth)[[50, -1]] ** 2)
    sq = np.array(sq)
    assert np.all(np.abs(sq.mean(0) - ms[[50, -1]]) < 4 * sq.std(0, ddof=1) / np.sqrt(len(sq)))
    no_turn_noise = planar.dead_reckoning_error_ms(truth, 0.5, np.diag([1, 1, 1, 0.02**2, 0.0]))
    assert_allclose(no_turn_noise, 0.25 * 0.02**2 * np.arange(len(truth)), atol=1e-9)  # speed noise alone: k T^2 sigma_v^2


def test_ekf_error_ms_matches_monte_carlo():
    """The linear covariance analysis of the EKF against simulated runs of the paper's pipeline, within 4 standard errors."""
    truth = planar_ekf.propagate([0.0, 0.0, np.pi / 4, 1.0, 0.0], 0.5, 300)
    t, origin = 0.5 * np.arange(len(truth)), np.deg2rad([26.06, 119.2])
    ms = planar.ekf_error_ms(truth, 0.5)
    per_run = []
    for seed in range(60):
        sens = planar.simulate_sensors(truth, origin, planar.R_PAPER, np.random.default_rng(seed))
        est = planar.ekf(t, sens, truth[0], origin=origin)
        per_run.append(np.mean(analysis.position_error(est.x, truth) ** 2))
    assert abs(np.mean(per_run) - ms.mean()) < 4 * np.std(per_run, ddof=1) / np.sqrt(len(per_run))
    assert np.all(planar.ekf_error_ms(truth, 0.5, Q=np.zeros(5), P0=np.zeros(5)) == 0.0)  # no gain: the known start is kept


def test_paper_series_is_conformal_through_local_scales():
    """The corrected Eq. (9) passed to geodesy.local_scales as ``project``: h = k, right angles (1e-8)."""
    lat, lon = np.meshgrid(np.linspace(0, 70, 8), 120 + np.linspace(-3, 3, 7))
    h, k, angle = geodesy.local_scales(lat, lon, 120.0, deg=True, project=planar.paper_series, **CGCS)
    assert np.abs(h / k - 1).max() < 1e-8 and np.abs(angle - np.pi / 2).max() < 1e-8
    assert_allclose(h, geodesy.scale_factor(lat, lon, lon0=120.0, deg=True, max_offset_deg=3.0, **CGCS), rtol=1e-8)


# --------------------------------------------------------------------------
# Bad input: the registry tools/fuzz_calls.py (rows of ekf, filter_grid, dead_reckoning, EkfConfig, the paper's
# equations), run by tests/test_bad_input.py. Here: NaN as the documented dropout marker.
# --------------------------------------------------------------------------

T3 = np.array([0.0, 0.5, 1.0])
X5 = np.array([0.0, 0.0, 0.3, 1.0, 0.0])
NAN3 = np.full(3, np.nan)


def sensors3(**fields):
    """Three epochs at ORIGIN, with ``fields`` of the Sensors record replaced."""
    return planar.Sensors(
        **{**dict(gps=np.tile(ORIGIN, (3, 1)), heading=np.ones(3), speed=np.ones(3), yaw_rate=np.zeros(3)), **fields}
    )


@pytest.mark.parametrize(
    "call, check",
    [
        (lambda: planar_ekf.filter_grid(T3, np.full((3, 5), np.nan), X5, PAPER).x, np.isfinite),
        (lambda: planar.ekf(T3, sensors3(gps=np.full((3, 2), np.nan)), X5, origin=ORIGIN).x, None),  # prediction only
        (lambda: planar.ekf(T3, sensors3(heading=NAN3), X5, origin=ORIGIN).x, np.isfinite),
        (lambda: planar.ekf(T3, sensors3(speed=NAN3), X5, origin=ORIGIN).x, np.isfinite),
        (lambda: planar.ekf(T3, sensors3(yaw_rate=NAN3), X5, origin=ORIGIN).x, np.isfinite),
        (lambda: planar_ekf.dead_reckoning(T3, NAN3, np.zeros(3), X5, [0.0, 0.0], 2.0)[0], np.isfinite),
        (lambda: planar_ekf.dead_reckoning(T3, np.ones(3), NAN3, X5, [0.0, 0.0], 2.0)[0], np.isfinite),
        (lambda: analysis.position_error(np.full((3, 5), np.nan), np.tile(X5, (3, 1))), np.isnan),
    ],
    ids=[
        "filter_grid-z",
        "ekf-gps",
        "ekf-heading",
        "ekf-speed",
        "ekf-yaw_rate",
        "dead_reckoning-speed",
        "dead_reckoning-yaw_rate",
        "position_error-estimate",
    ],
)
def test_all_nan_channel_is_a_dropout(call, check):
    """An all-NaN measurement channel is accepted: held / predicted through, the estimate stays finite (a run
    without any fix is prediction only); position_error passes NaN through."""
    out = call()
    assert check is None or np.all(check(out))


def test_degree_inputs_give_the_same_filter():
    t, truth, s = straight_run(8, n=200)
    rad = planar.ekf(t, s, X0_STRAIGHT, origin=ORIGIN)
    in_deg = planar.Sensors(np.degrees(s.gps), np.degrees(s.heading), s.speed, np.degrees(s.yaw_rate))
    deg = planar.ekf(t, in_deg, X0_STRAIGHT, origin=np.degrees(ORIGIN), deg=True)
    assert_allclose(deg.x, rad.x, rtol=0, atol=1e-9)
    w_fs = np.abs(s.yaw_rate).max() * 0.9  # some samples at the "rails"
    rails = config(limits=SensorLimits(full_scale_gyro=w_fs))  # the config stays SI (rad/s) with deg=True
    rad = planar.ekf(t, s, X0_STRAIGHT, origin=ORIGIN, config=rails)
    deg = planar.ekf(t, in_deg, X0_STRAIGHT, origin=np.degrees(ORIGIN), deg=True, config=rails)
    assert rad.faults["yaw_rate", "saturated"] > 0
    assert deg.faults["yaw_rate", "saturated"] == rad.faults["yaw_rate", "saturated"]
    assert_allclose(deg.x, rad.x, rtol=0, atol=1e-9)


def test_gate_and_range_inf_mean_off():
    """``gate=inf`` and ``full_scale_gyro=inf`` (the defaults) are the documented 'off' values: same result."""
    t, truth, s = straight_run(9, n=100)
    a = planar.ekf(t, s, X0_STRAIGHT, origin=ORIGIN)
    b = planar.ekf(t, s, X0_STRAIGHT, origin=ORIGIN, config=config(gate=np.inf, limits=SensorLimits(full_scale_gyro=np.inf)))
    assert np.array_equal(a.x, b.x) and not b.faults
