"""Tests of navlib.papers.north_finding (paper 000, Tan & Xie): identities, error theory, bad input."""

from __future__ import annotations

import numpy as np
import pytest

from navlib import alignment, attitude, sensors, trajectory, units
from navlib.papers import north_finding as nf

LAT = units.deg(28.361735)


def ideal(hpr, lat=LAT):
    """Ideal averaged outputs of a static IMU (no noise)."""
    w, f = nf.simulate_static_outputs(hpr, lat, 1, 0.0, 0.0, np.random.default_rng(0))
    return w[..., 0, :], f[..., 0, :]


def random_hpr(rng, n):
    return np.stack([rng.uniform(0, 2 * np.pi, n), rng.uniform(-1.2, 1.2, n), rng.uniform(-3, 3, n)], -1)


def test_triad_recovers_attitude_from_ideal_outputs():
    rng = np.random.default_rng(1)
    hpr = random_hpr(rng, 200)
    for lat in (LAT, units.deg(-60.0), 0.0):
        w, f = ideal(hpr, lat)
        C_true = attitude.euler_to_dcm(hpr)
        assert np.abs(alignment.triad(f, w, lat) - C_true).max() < 1e-12
        assert np.abs(alignment.triad(f, w, lat, orthonormal=False) - C_true).max() < 1e-12
        assert np.abs(attitude.wrap_pi(alignment.triad_heading(C_true) - hpr[:, 0])).max() < 1e-12


def test_tilt_recovers_pitch_and_roll():
    rng = np.random.default_rng(2)
    hpr = random_hpr(rng, 500)
    _, f = ideal(hpr)
    pitch, roll = nf.pitch_roll_from_accel(f)
    assert np.abs(pitch - hpr[:, 1]).max() < 1e-12
    assert np.abs(attitude.wrap_pi(roll - hpr[:, 2])).max() < 1e-12


def test_candidates_contain_true_heading_and_ignore_roll():
    rng = np.random.default_rng(3)
    hpr = random_hpr(rng, 500)
    w, f = ideal(hpr)
    c = nf.heading_candidates(w[:, 1], f, LAT)
    err = np.abs(attitude.wrap_pi(c.pair - hpr[:, :1])).min(-1)
    assert err.max() < 1e-9
    assert np.abs(attitude.wrap_pi(c.pair.sum(-1))).max() < 1e-12  # the pair sums to 2 pi
    assert np.all((c.alpha >= 0) & (c.alpha <= np.pi))
    hpr2 = hpr.copy()
    hpr2[:, 2] += 0.3
    w2, f2 = ideal(hpr2)
    c2 = nf.heading_candidates(w2[:, 1], f2, LAT)
    assert np.abs(c2.pair - c.pair).max() < 1e-9


def test_clipping_is_reported():
    w, f = ideal([[0.0, 0.0, 0.0]])
    c = nf.heading_candidates(w[:, 1] * 1.001, f, LAT)
    assert c.clipped.all() and c.n_clipped == 1 and c.cos_heading[0] > 1
    assert np.allclose(c.pair, 0.0)


def test_resolution_reproduces_table_1():
    d = np.deg2rad
    tests = [
        ((121.34, 238.66), (163.75, 196.25), 69.48, 196.25),
        ((163.75, 196.25), (180.00, 180.00), -8.0, 180.00),
        ((180.00, 180.00), (127.97, 232.03), 51.20, 232.03),
        ((127.97, 232.03), (114.03, 245.97), -120.41, 114.03),
    ]
    for p1, p2, ins, want in tests:
        r = nf.resolve(d(p1), d(p2), d(ins))
        assert np.rad2deg(r.heading) == pytest.approx(want, abs=1e-9)
        assert r.margin > 0
    # vectorised over tests gives the same
    r = nf.resolve(d([t[0] for t in tests]), d([t[1] for t in tests]), d([t[2] for t in tests]))
    assert np.allclose(np.rad2deg(r.heading), [t[3] for t in tests])


def test_resolution_candidates_follow_eq12():
    rng = np.random.default_rng(4)
    a, b = rng.uniform(0, np.pi, (2, 100))
    r = nf.resolve(np.stack([a, 2 * np.pi - a], -1), np.stack([b, 2 * np.pi - b], -1), np.zeros(100))
    want = np.stack([b - a, a + b - 2 * np.pi, 2 * np.pi - a - b, a - b], -1)
    assert np.abs(r.dpsi_candidates - want).max() < 1e-12


def test_wrapping_matters():
    d = np.deg2rad
    # true pair (100, 281): raw candidate +181 deg; the INS reports -178.5 deg
    p1, p2, ins = d([100.0, 260.0]), d([79.0, 281.0]), d(-178.5)
    assert np.rad2deg(nf.resolve(p1, p2, ins).heading) == pytest.approx(281.0)
    assert np.rad2deg(nf.resolve(p1, p2, ins, wrap=False).heading) == pytest.approx(79.0)


def test_margin_infinite_when_all_candidates_coincide():
    r = nf.resolve([np.pi, np.pi], [np.pi, np.pi], 0.1)
    assert np.isinf(r.margin) and r.heading == pytest.approx(np.pi)


def test_eq13_sign_by_perturbation():
    for psi in np.deg2rad([0.0, 40.0, 100.0, 200.0]):
        hpr = np.array([psi, 0.0, 0.0])
        w, f = ideal(hpr, units.deg(30.0))
        dw = np.array([2e-9, -1e-9, 3e-9])
        h1 = alignment.triad_heading(alignment.triad(f, w + dw, units.deg(30.0)))
        pred = nf.triad_heading_error(attitude.euler_to_dcm(hpr), dw, units.deg(30.0))
        assert attitude.wrap_pi(h1 - psi) == pytest.approx(pred, rel=1e-4)


def test_eq16_eq20_values():
    s = units.deg_per_h(0.01)
    assert np.rad2deg(nf.triad_heading_std(s, LAT)) == pytest.approx(0.04329, abs=1e-4)
    eq20 = np.rad2deg(nf.single_axis_heading_std(np.deg2rad([90, 11, 171, 1]), s, LAT))
    assert eq20 == pytest.approx(0.04329 / np.abs(np.sin(np.deg2rad([90, 11, 171, 1]))), rel=1e-3)
    assert nf.four_position_heading_std(s, LAT) == pytest.approx(nf.triad_heading_std(s, LAT) / np.sqrt(2))


def test_full_linearisation_matches_finite_differences():
    """Perturb the y gyro and y accelerometer through the nonlinear estimator."""
    for hpr in ([40.0, 5.0, 5.0], [120.0, -8.0, 2.0], [300.0, 12.0, -4.0]):
        hpr = np.deg2rad(hpr)
        w, f = ideal(hpr)
        dw, df = 1e-9, 2e-5
        w2, f2 = w.copy(), f.copy()
        w2[1] += dw
        f2[1] += df
        c = nf.heading_candidates(w2[1], f2, LAT)
        errs = attitude.wrap_pi(c.pair - hpr[0])
        got = errs[np.argmin(np.abs(errs))]
        g = np.linalg.norm(f)
        pred = nf.single_axis_heading_error(hpr[0], hpr[1], LAT, dw, df, g=g)
        assert got == pytest.approx(pred, rel=2e-3)


def test_monte_carlo_follows_theory():
    rng = np.random.default_rng(5)
    s_g, s_a = units.deg_per_h(0.01), units.ug(100)
    mc = nf.monte_carlo(np.deg2rad([45.0, 91.0]), np.deg2rad(5), np.deg2rad(5), LAT, 4000, s_g, s_a, rng)
    rms = np.sqrt((mc.single**2).mean(-1))
    theory = nf.single_axis_heading_std(mc.heading, s_g, LAT, np.deg2rad(5), s_a)
    assert np.all(np.abs(rms / theory - 1) < 4 / np.sqrt(8000))
    rms_t = np.sqrt((mc.triad**2).mean(-1))
    assert np.all(np.abs(rms_t / nf.triad_heading_std(s_g, LAT) - 1) < 4 / np.sqrt(8000))


def test_clipped_theory_limits_and_monte_carlo():
    """Away from 0/180 deg it is Eq. (20) with its pitch term; at 0 deg it has a closed form; near 0 deg the Monte Carlo."""
    s_g, s_a, th = units.deg_per_h(0.01), units.ug(100), np.deg2rad(5)
    far = np.deg2rad([30.0, 91.0, 250.0])
    ct = nf.clipped_single_axis_theory(far, s_g, LAT, th, s_a)
    assert np.allclose(ct.rmse, nf.single_axis_heading_std(far, s_g, LAT, th, s_a), rtol=1e-3)
    assert np.allclose(ct.rel_sd, 1 / np.sqrt(2), rtol=1e-2) and np.all(ct.p_clip < 1e-12)
    # psi = 0, gyro noise only: the cosine is 1 + s z; half the trials clip to 0, the rest give acos(1 - s|z|)^2 ~ 2 s|z|
    at0 = nf.clipped_single_axis_theory(0.0, s_g, LAT)
    s_c = s_g / (nf.OMEGA_IE * np.cos(LAT))
    assert at0.rmse == pytest.approx(np.sqrt(s_c * np.sqrt(2 / np.pi)), rel=1e-3)
    assert at0.p_clip == pytest.approx(0.5, abs=1e-12)
    mc = nf.monte_carlo(np.deg2rad([1.0, 181.0]), th, th, LAT, 20000, s_g, s_a, np.random.default_rng(11))
    ct = nf.clipped_single_axis_theory(mc.heading, s_g, LAT, th, s_a)
    rms = np.sqrt((mc.single**2).mean(-1))
    assert np.all(np.abs(rms / ct.rmse - 1) < 4 * ct.rel_sd / np.sqrt(20000))
    assert np.all(np.abs(mc.clipped.mean(-1) - ct.p_clip) < 4 * np.sqrt(ct.p_clip * (1 - ct.p_clip) / 20000))


def test_monte_carlo_reproducible_with_seed():
    args = (np.deg2rad([1.0, 91.0]), 0.05, 0.05, LAT, 50, units.deg_per_h(0.01), units.ug(100))
    a = nf.monte_carlo(*args, np.random.default_rng(9))
    b = nf.monte_carlo(*args, np.random.default_rng(9))
    assert np.array_equal(a.single, b.single) and np.array_equal(a.triad, b.triad)


def test_pair_probabilities_match_monte_carlo():
    rng = np.random.default_rng(6)
    d = np.deg2rad
    for p1, p2, s in ((30.0, 25.0, 5.0), (100.0, 200.0, 60.0), (170.0, 5.0, 10.0)):
        p1, p2, s = d(p1), d(p2), d(s)
        prob = nf.pair_probabilities(p1, p2, s)
        assert prob.sum() == pytest.approx(1.0, abs=1e-9)
        e = s * rng.standard_normal(100_000)
        r = nf.resolve([p1, 2 * np.pi - p1], [p2, 2 * np.pi - p2], attitude.wrap_pi(p2 - p1 + e))
        freq = np.bincount(r.index, minlength=4) / e.size
        assert np.abs(freq - prob).max() < 5 * np.sqrt(0.25 / e.size)


def test_four_position_cancels_bias():
    psi = np.deg2rad([0.0, 37.0, 181.0, 300.0])
    hpr = np.stack([psi[:, None] + np.arange(4) * np.pi / 2, np.zeros((4, 4)), np.zeros((4, 4))], -1)
    w, _ = ideal(hpr)
    assert np.abs(attitude.wrap_pi(alignment.four_position_heading(w[..., 1] + 1e-7) - psi)).max() < 1e-9


def test_window_mean_std_white_and_gm():
    e = sensors.TriadErrors(noise_density=units.deg_per_sqrt_h(0.00224))
    assert units.to_deg_per_h(sensors.window_mean_std(e, 180.0, 0.01)) == pytest.approx(0.01, rel=0.01)
    gm = sensors.TriadErrors(bias_instability=1e-6, correlation_time=1e6)
    assert sensors.window_mean_std(gm, 180.0, 0.01) == pytest.approx(gm.gauss_markov_sigma, rel=1e-3)


def test_vehicle_stand_in_end_to_end():
    """Noise-free drive: stops solve exactly and the INS heading change is the true one."""
    d = np.deg2rad
    heads = d([122.0, 191.47, 232.93])
    segs, stops = nf.stop_and_go(heads, 20.0, 40.0, 5.0, d([0.0, 1.5, -1.0]), d([0.0, -1.0, 2.0]))
    traj = trajectory.vehicle(segs, 0.01, [LAT, 2.0, 50.0], heads[0])
    w, f = trajectory.ideal_imu(traj)
    win = np.round(stops / 0.01).astype(int)
    with pytest.raises(ValueError, match="^w_ib_b: one reading repeated"):  # noise-free: looks frozen
        nf.stop_solutions(w, f, win, LAT, 50.0)
    sol = nf.stop_solutions(w, f, win, LAT, 50.0, stuck_fraction=None)
    assert np.abs(attitude.wrap_pi(sol.triad - heads)).max() < 1e-6
    assert np.abs(attitude.wrap_pi(sol.candidates - heads[:, None])).min(-1).max() < 1e-4
    for k in range(2):
        a, b = win[k, 1] - 1000, win[k + 1, 0]
        f0 = f[a : a + 1000].mean(0)
        dpsi = nf.ins_heading_change(w[a + 1000 : b], f0, 0.01, LAT, "vertical")
        assert np.rad2deg(attitude.wrap_pi(dpsi - (heads[k + 1] - heads[k]))) == pytest.approx(0.0, abs=0.01)
    r = nf.resolve(sol.candidates[:-1], sol.candidates[1:], attitude.wrap_pi(np.diff(heads)))
    assert np.abs(attitude.wrap_pi(r.heading - heads[1:])).max() < 1e-4


# ---------------------------------------------------------------- bad input

GOOD_W = np.tile(ideal([1.0, 0.0, 0.0])[0], (10, 1))
GOOD_F = np.tile(ideal([1.0, 0.0, 0.0])[1], (10, 1))


def test_stop_solutions_stack_each_stops_faults():
    w = GOOD_W.copy()
    w[2] = np.nan  # one dropout in the first stop
    sol = nf.stop_solutions(np.stack([w, GOOD_W]), np.stack([GOOD_F, GOOD_F]), [[0, 5], [5, 10]], LAT, stuck_fraction=None)
    np.testing.assert_array_equal(sol.faults["gyro", "nan"], [[1, 0], [0, 0]])  # (trials, stops)
    np.testing.assert_array_equal(sol.faults["window", "refused"], 0)
    for key, count in sol.faults.counts.items():
        np.testing.assert_array_equal(count, np.stack([np.broadcast_to(s.faults[key], (2,)) for s in sol.windows], -1))
    assert not hasattr(sol, "status")


def test_ins_heading_change_old_options_are_gone():
    with pytest.raises(TypeError):
        nf.ins_heading_change(GOOD_W, GOOD_F[0], 0.01, LAT, report=True)
    with pytest.raises(TypeError):
        nf.ins_heading_change(GOOD_W, GOOD_F[0], 0.01, LAT, full_scale=1.0)


@pytest.mark.parametrize(
    "call, arg",
    [
        (lambda: alignment.triad([0, 0, 9.8], [0, 1e-5, 1e-5], units.deg(95.0)), "lat"),
        (lambda: alignment.triad([0, 0, 9.8], [0, 1e-5, 1e-5], units.deg(89.5)), "lat"),
        (lambda: alignment.triad([0, 0, np.nan], [0, 1e-5, 1e-5], LAT), "f_b"),
        (lambda: alignment.triad([0, 0, 9.8], [0, 1e-5], LAT), "w_ib_b"),
        (lambda: nf.heading_candidates(1e-5, [0, 0, 9.8], units.deg(-90.0)), "lat"),
        (lambda: nf.heading_candidates(np.inf, [0, 0, 9.8], LAT), "w_y"),
        (lambda: nf.pitch_roll_from_accel([0.0, 0.0, 0.0]), "f_b"),
        (lambda: nf.pitch_roll_from_accel([0.0, 0.0, 9.8], g=[9.8, 9.8, 9.8]), "g"),  # one gravity, not three trials
        (lambda: alignment.static_means(np.zeros((0, 3)), np.zeros((0, 3)), LAT), "w_ib_b"),
        (lambda: alignment.static_means(GOOD_W[:1], GOOD_F[:1], LAT), "w_ib_b"),
        (lambda: alignment.static_means(GOOD_W, GOOD_F * 1.2, LAT), "f_b"),
        (lambda: alignment.static_means(GOOD_W, GOOD_F + np.linspace(-1, 1, 10)[:, None] * [1, 0, 0], LAT), "f_b"),
        (lambda: alignment.static_means(GOOD_W, np.where((np.arange(10) < 6)[:, None], np.nan, GOOD_F), LAT), "f_b"),
        (lambda: alignment.static_means(GOOD_W, GOOD_F[:5], LAT), "f_b"),
        (lambda: alignment.static_means(GOOD_W, GOOD_F, LAT, accel_tol=-1), "accel_tol"),
        (lambda: nf.resolve([1.0, 2.0, 3.0], [1.0, 2.0], 0.0), "pair1"),
        (lambda: nf.resolve([1.0, 2.0], [1.0, np.nan], 0.0), "pair2"),
        (lambda: nf.resolve([1.0, 2.0], [1.0, 2.0], np.nan), "dpsi_ins"),
        (lambda: alignment.triad_heading(np.eye(2)), "C_bn"),
        (lambda: nf.triad_heading_error(2 * np.eye(3), [0, 0, 0], LAT), "C_bn"),
        (lambda: nf.triad_heading_error(np.eye(3), [0, 0], LAT), "dw_b"),
        (lambda: nf.triad_heading_std(-1.0, LAT), "sigma_gyro"),
        (lambda: nf.single_axis_heading_std(1.0, 1e-7, LAT, pitch=2.0), "pitch"),
        (lambda: nf.single_axis_heading_std(1.0, 1e-7, LAT, sigma_accel=-1), "sigma_accel"),
        (lambda: nf.single_axis_heading_std("x", 1e-7, LAT), "heading"),
        (lambda: nf.single_axis_heading_error(1.0, 0.0, LAT, np.nan), "dw_y"),
        (lambda: nf.single_axis_heading_error(1.0, 0.0, LAT, 0.0, g=0.0), "g"),
        (lambda: nf.simulate_static_outputs([0, 0, 0], LAT, 0, 1e-7, 1e-3, np.random.default_rng(0)), "n_trials"),
        (lambda: nf.simulate_static_outputs([0, 0, 0], LAT, 3, 1e-7, 1e-3, 1), "rng"),
        (lambda: nf.simulate_static_outputs([0, 0, 0], LAT, 3, -1e-7, 1e-3, np.random.default_rng(0)), "sigma_gyro"),
        (lambda: nf.monte_carlo([0.0], 0.0, 4.0, LAT, 3, 1e-7, 1e-3, np.random.default_rng(0)), "roll"),
        (lambda: nf.monte_carlo([0.0], 0.0, 0.0, units.deg(-89.9), 3, 1e-7, 1e-3, np.random.default_rng(0)), "lat"),
        (lambda: nf.pair_probabilities(1.0, 2.0, 0.0), "sigma_ins"),
        (lambda: nf.pair_probabilities(np.nan, 2.0, 0.1), "heading1"),
        (lambda: alignment.four_position_heading([1.0, 2.0, 3.0]), "w_y"),
        (lambda: nf.four_position_heading_std(1e-7, units.deg(91.0)), "lat"),
        (lambda: sensors.window_mean_std("NAV-FOG", 180.0, 0.01), "errors"),
        (lambda: sensors.window_mean_std(sensors.TriadErrors(), 0.0, 0.01), "duration"),
        (lambda: nf.stop_and_go([1.0], 10, 40, 5, [0.0], [0.0]), "headings"),
        (lambda: nf.stop_and_go([1.0, 2.0], 10, 20, 5, [0.0, 0.0], [0.0, 0.0]), "drive_duration"),
        (lambda: nf.stop_and_go([1.0, 2.0], 10, 40, -5, [0.0, 0.0], [0.0, 0.0]), "speed"),
        (lambda: nf.stop_solutions(GOOD_W, GOOD_F, [[0, 20]], LAT), "windows"),
        (lambda: nf.stop_solutions(GOOD_W, GOOD_F, [[0.0, 5.0]], LAT), "windows"),
        (lambda: nf.ins_heading_change(GOOD_W, GOOD_F[0], 0.01, LAT, earth_rate="half"), "earth_rate"),
        (lambda: nf.ins_heading_change(GOOD_W, GOOD_F[0], -0.01, LAT), "dt"),
        (lambda: nf.ins_heading_change(GOOD_W, GOOD_F[0], np.full(9, 0.01), LAT), "dt"),
        (lambda: nf.ins_heading_change(GOOD_W, GOOD_F[0], 0.01, LAT, max_gap=-1.0), "max_gap"),
        (lambda: nf.ins_heading_change(GOOD_W, GOOD_F[0], 0.01, LAT, full_scale_gyro=0.0), "full_scale_gyro"),
        (lambda: alignment.static_means(GOOD_W, GOOD_F, LAT, min_fraction=0.0), "min_fraction"),
        (lambda: alignment.static_means(GOOD_W, GOOD_F, LAT, min_fraction=1.5), "min_fraction"),
        (lambda: alignment.static_means(GOOD_W, GOOD_F, LAT, outlier_k=-3.0), "outlier_k"),
        (lambda: alignment.static_means(GOOD_W, GOOD_F, LAT, stuck_fraction=0.0), "stuck_fraction"),
        (lambda: alignment.static_means(GOOD_W, GOOD_F, LAT, stuck_fraction=np.nan), "stuck_fraction"),
        (lambda: nf.stop_solutions(GOOD_W, GOOD_F, [[0, 5]], LAT, stuck_fraction=-0.5), "stuck_fraction"),
        (lambda: alignment.static_means(GOOD_W, GOOD_F, LAT, full_scale_gyro=0.0), "full_scale_gyro"),
        (lambda: alignment.static_means(GOOD_W, GOOD_F, LAT, full_scale_accel=-1.0), "full_scale_accel"),
        (lambda: alignment.static_means(GOOD_W, np.full((10, 3), np.nan), LAT), "f_b"),
        (lambda: nf.stop_solutions(GOOD_W, GOOD_F, [[0.0, 0.05]], LAT, time=np.arange(9) * 0.01), "time"),
        (lambda: nf.stop_solutions(GOOD_W, GOOD_F, [[0.0, 0.05]], LAT, time=np.zeros(10)), "time"),
        (lambda: nf.stop_solutions(GOOD_W, GOOD_F, [[0.05, 0.0]], LAT, time=np.arange(10) * 0.01), "windows"),
        (lambda: nf.stop_solutions(GOOD_W, GOOD_F, [[0.0, 0.005]], LAT, time=np.arange(10) * 0.01), "windows"),
        # found by tools/fuzz.py (issue 15, item 4): accepted silently, or an error naming no argument
        (lambda: nf.resolve(np.zeros((2, 2)), np.zeros((3, 2)), 0.0), "pair2"),
        (lambda: nf.resolve([1.0, 2.0], [1.0, 2.0], 0.0, wrap=None), "wrap"),
        (lambda: nf.monte_carlo(np.zeros((2, 2)), 0.0, 0.0, LAT, 3, 1e-7, 1e-3, np.random.default_rng(0)), "headings"),
        (lambda: nf.monte_carlo([0.0], [0.0, 0.1], 0.0, LAT, 3, 1e-7, 1e-3, np.random.default_rng(0)), "pitch"),
        (lambda: nf.simulate_static_outputs([0, 0, 0], [LAT, LAT], 3, 1e-7, 1e-3, np.random.default_rng(0)), "lat"),
        (lambda: nf.ins_heading_change(GOOD_W, GOOD_F[0], 0.01, [LAT, LAT]), "lat"),
        (lambda: nf.ins_heading_change(GOOD_W, np.tile(GOOD_F[0], (2, 1)), 0.01, LAT), "f_start"),
        (lambda: nf.stop_and_go(np.zeros((2, 2)), 10, 40, 5, np.zeros((2, 2)), np.zeros((2, 2))), "headings"),
        (lambda: nf.stop_solutions(GOOD_W, GOOD_F, [[0, 5]], LAT, strict="no"), "strict"),
    ],
)
def test_bad_input_names_argument(call, arg):
    # (static_means with 3 of 10 samples NaN was refused before issue 9; NaN now marks dropouts, left out and
    # counted, and only a window with fewer than min_fraction of its samples left is refused -- 6 of 10 NaN above)
    with pytest.raises(ValueError) as exc:
        call()
    assert str(exc.value).split(":")[0].strip().startswith(arg), str(exc.value)


def test_resolve_reports_no_margin_where_the_hypotheses_cannot_be_separated():
    """When position 1's pair mirrors position 2's (alpha1 + alpha2 = 180 deg: a U-turn or a straight drive), two
    candidates give the same heading change but point position 2 in opposite directions: no INS measurement can
    separate them, and the margin is 0 (it was 178 deg). Off the mirror, the margin is what the INS can tell."""
    p2 = np.deg2rad([89.0, 271.0])
    for dpsi in (180.0, 179.5, 175.0):
        assert nf.resolve(np.deg2rad([91.0, 269.0]), p2, np.deg2rad(dpsi)).margin == 0.0
    near = nf.resolve(np.deg2rad([91.5, 268.5]), p2, np.deg2rad(179.8))  # candidates -179.5 and 179.5 deg
    np.testing.assert_allclose(np.rad2deg(near.margin), 0.4, atol=1e-9)
    clear = nf.resolve(np.deg2rad([10.0, 350.0]), np.deg2rad([100.0, 260.0]), np.deg2rad(90.0))
    assert np.rad2deg(clear.margin) > 100.0 and np.isclose(np.rad2deg(clear.heading), 100.0)
