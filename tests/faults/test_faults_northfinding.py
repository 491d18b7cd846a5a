"""Fault injection: north finding of paper 000 (navlib.papers.north_finding).

Data: the paper's stop-and-go drive, small: three 3-min stops (headings 122,
191.47, 232.93 deg, tilted by up to 2 deg) joined by 40-s drives, 100 Hz,
28.36 deg N, four NAV-FOG runs for the stops (TRIAD and single-axis) and the
ADIS16475-1 MEMS gyro for the INS heading change (stop_solutions,
static_means, ins_heading_change).

Bounds. Leaving m of a stop's N samples out moves its mean by a random
amount of std ``sigma_s sqrt(1/(N-m) - 1/N)`` (sigma_s the per-sample white
noise); the heading moves by that through Eq. (16) (TRIAD) or the full
Eq. (20) linearisation (single-axis). The tests assert 5 times that
(``leave_out_bound``); with 24 headings compared per test a 5-sigma bound
fails by chance with p ~ 1e-5.
"""

import numpy as np
import pytest

from navlib import alignment, attitude, faults, robust, sensors, timing, trajectory, units
from navlib.papers import north_finding as nf

DT = 0.01
LAT = units.deg(28.361735)
HEADS = units.deg(np.array([122.0, 191.47, 232.93]))
PITCH, ROLL = units.deg([0.0, 1.5, -1.0]), units.deg([0.0, -1.0, 2.0])
FOG = sensors.imu_model("NAV-FOG")
SIG_G = FOG.gyro.noise_density / np.sqrt(DT)
SIG_A = FOG.accel.noise_density / np.sqrt(DT)

SEGS, STOPS = nf.stop_and_go(HEADS, 180.0, 40.0, 5.0, PITCH, ROLL)
TRAJ = trajectory.vehicle(SEGS, DT, [LAT, units.deg(112.9), 50.0], HEADS[0])
W_TRUE, F_TRUE = trajectory.ideal_imu(TRAJ)
T = TRAJ.time[:-1]  # time of each sample
WIN = np.round(STOPS / DT).astype(int)
IMU = sensors.simulate_imu(W_TRUE, F_TRUE, DT, FOG, np.random.default_rng(0), n_trials=4)
CLEAN = nf.stop_solutions(IMU.w_ib_b, IMU.f_b, WIN, LAT, 50.0)


def window_counts(mask):
    return np.array([mask[a:b].sum() for a, b in WIN])


def leave_out_bound(n_left_out, sig_g=SIG_G, sig_a=SIG_A):
    """5-sigma bound on the heading change (TRIAD, single-axis) when n_left_out samples per stop are dropped."""
    N = np.diff(WIN, axis=1)[:, 0]
    scale = np.sqrt(1.0 / (N - n_left_out) - 1.0 / N)
    g, a = sig_g * scale, sig_a * scale
    triad = np.hypot(nf.triad_heading_std(g, LAT), np.tan(LAT) * a / 9.79)  # gyro + levelling term
    single = nf.single_axis_heading_std(HEADS, g, LAT, PITCH, a)
    return 5 * triad, 5 * single


def heading_change(sol, ref=CLEAN):
    d_triad = np.abs(attitude.wrap_pi(sol.triad - ref.triad))
    return d_triad, np.abs(attitude.wrap_pi(sol.candidates - ref.candidates)).max(-1)


def counts(sol, name):
    return np.stack([getattr(s, name) for s in sol.windows], -1)  # (trials, stops)


def test_fault_free_baseline():
    assert np.all(CLEAN.faults["window", "refused"] == 0)
    assert np.all(CLEAN.faults["gyro", "nan"] == 0) and np.all(counts(CLEAN, "n_used_gyro") == np.diff(WIN)[:, 0])
    assert IMU.gyro_saturated == IMU.accel_saturated == 0


def test_random_dropouts_are_left_out_and_counted():
    w, drop_w = faults.dropouts(IMU.w_ib_b, 0.1, np.random.default_rng(1))
    f, drop_f = faults.dropouts(IMU.f_b, 0.1, np.random.default_rng(2))
    sol = nf.stop_solutions(w, f, WIN, LAT, 50.0)
    np.testing.assert_array_equal(sol.faults["gyro", "nan"], np.broadcast_to(window_counts(drop_w), (4, 3)))
    np.testing.assert_array_equal(sol.faults["accel", "nan"], np.broadcast_to(window_counts(drop_f), (4, 3)))
    assert np.isfinite(sol.candidates).all() and np.isfinite(sol.triad).all()
    d_triad, d_single = heading_change(sol)
    b_triad, b_single = leave_out_bound(np.maximum(window_counts(drop_w), window_counts(drop_f)))
    assert np.all(d_triad <= b_triad) and np.all(d_single <= b_single), (d_triad, b_triad, d_single, b_single)


def test_gap_of_30_s_inside_a_stop():
    w, gap = faults.gap(IMU.w_ib_b, T, STOPS[1, 0] + 60.0, 30.0)
    f = np.where(gap[:, None], np.nan, IMU.f_b)
    sol = nf.stop_solutions(w, f, WIN, LAT, 50.0)
    np.testing.assert_array_equal(sol.faults["gyro", "nan"][0], [0, 3000, 0])
    np.testing.assert_array_equal(counts(sol, "n_used_accel")[0], [18000, 15000, 18000])
    d_triad, d_single = heading_change(sol)
    b_triad, b_single = leave_out_bound(window_counts(gap))
    assert np.all(d_triad <= b_triad) and np.all(d_single <= b_single)
    assert np.all(d_triad[:, [0, 2]] == 0)  # the other stops are untouched


def test_a_stop_mostly_lost_is_refused():
    w, gap = faults.gap(IMU.w_ib_b, T, STOPS[1, 0] + 30.0, 120.0)  # 60 s of 180 s left
    with pytest.raises(ValueError, match="^w_ib_b: only 6000 of 18000 samples"):
        nf.stop_solutions(w, IMU.f_b, WIN, LAT, 50.0)
    sol = nf.stop_solutions(w, IMU.f_b, WIN, LAT, 50.0, strict=False)
    assert np.all(sol.faults["window", "refused"] == [0, 1, 0])
    # why, from the counts: 6000 gyro samples used, below max(2, ceil(min_fraction N)) = 9000
    np.testing.assert_array_equal(counts(sol, "n_used_gyro")[:, 1], 6000)
    assert np.all(sol.faults["gyro", "nan"][:, 1] == 12000) and not np.any(sol.faults["gyro", "stuck"])
    assert np.isnan(sol.candidates[:, 1]).all() and np.isnan(sol.triad[:, 1]).all()
    np.testing.assert_array_equal(sol.triad[:, [0, 2]], CLEAN.triad[:, [0, 2]])
    # a lower min_fraction accepts it, counted
    sol = nf.stop_solutions(w, IMU.f_b, WIN, LAT, 50.0, min_fraction=0.3)
    assert np.all(sol.faults["gyro", "nan"][:, 1] == 12000)


def test_spikes_are_rejected_by_mad_and_counted():
    w, hit_w = faults.spikes(IMU.w_ib_b, 0.01, SIG_G, np.random.default_rng(3))
    f, hit_f = faults.spikes(IMU.f_b, 0.01, SIG_A, np.random.default_rng(4))
    sol = nf.stop_solutions(w, f, WIN, LAT, 50.0, outlier_k=6.0)
    # exact: 100-sigma spikes are always beyond 6 MAD-sigma, Gaussian samples practically never (p ~ 2e-9)
    np.testing.assert_array_equal(sol.faults["gyro", "outlier"], np.broadcast_to(window_counts(hit_w), (4, 3)))
    np.testing.assert_array_equal(sol.faults["accel", "outlier"], np.broadcast_to(window_counts(hit_f), (4, 3)))
    d_triad, d_single = heading_change(sol)
    b_triad, b_single = leave_out_bound(np.maximum(window_counts(hit_w), window_counts(hit_f)))
    assert np.all(d_triad <= b_triad) and np.all(d_single <= b_single)
    # without outlier_k the spikes enter the mean: the documented bound is 100 sigma sqrt(n_hit) / N per
    # component (10x the mean's own white noise); 5 times that, and the error is indeed much larger
    raw = nf.stop_solutions(w, f, WIN, LAT, 50.0)
    N = np.diff(WIN)[:, 0]
    spike_g = 100 * SIG_G * np.sqrt(window_counts(hit_w)) / N
    spike_a = 100 * SIG_A * np.sqrt(window_counts(hit_f)) / N
    r_triad, _ = heading_change(raw)
    bound = 5 * np.hypot(nf.triad_heading_std(spike_g, LAT), np.tan(LAT) * spike_a / 9.79)
    assert np.all(r_triad < bound)
    assert np.sqrt(np.mean(r_triad**2)) > 3 * np.sqrt(np.mean(d_triad**2))
    # and outlier rejection leaves clean stops alone
    rob = nf.stop_solutions(IMU.w_ib_b, IMU.f_b, WIN, LAT, 50.0, outlier_k=6.0)
    assert np.all(rob.faults["gyro", "outlier"] == 0) and np.all(rob.faults["accel", "outlier"] == 0)
    np.testing.assert_array_equal(rob.triad, CLEAN.triad)


def test_duplicated_and_out_of_order_timestamps_through_sanitize():
    t_dup, _ = faults.duplicate_timestamps(T, 0.01, np.random.default_rng(5))
    t_bad, order = faults.swap_timestamps(t_dup, 0.01, np.random.default_rng(6))
    t_ok, w, f, rep = timing.sanitize(t_bad, IMU.w_ib_b[..., order, :], IMU.f_b[..., order, :])
    vals, reps = np.unique(t_dup, return_counts=True)
    assert rep.n_duplicate == (reps - 1).sum() and rep.n_out_of_order > 0
    ref = nf.stop_solutions(IMU.w_ib_b, IMU.f_b, STOPS, LAT, 50.0, time=T)  # windows cut by time
    sol = nf.stop_solutions(w, f, STOPS, LAT, 50.0, time=t_ok)
    lost = np.array([(reps - 1)[(vals >= a - 1e-9) & (vals < b - 1e-9)].sum() for a, b in STOPS])
    n_ref = np.array([s.n_samples for s in ref.windows])
    n_sol = np.array([s.n_samples for s in sol.windows])
    np.testing.assert_array_equal(n_ref - n_sol, lost)  # every removed sample accounted for
    d_triad, d_single = heading_change(sol, ref)
    b_triad, b_single = leave_out_bound(lost)
    assert np.all(d_triad <= b_triad) and np.all(d_single <= b_single)


def test_saturated_stop_is_refused_and_counted():
    """A 30-g knock (3 samples) during stop 2, clipped at the NAV-FOG's 20-g range."""
    f = IMU.f_b.copy()
    f[..., WIN[1, 0] + 5000 : WIN[1, 0] + 5003, 2] += 30 * 9.80665
    fs = FOG.accel.full_scale
    f, clipped = faults.saturate(f, fs)
    opts = dict(full_scale_gyro=FOG.gyro.full_scale, full_scale_accel=fs)
    with pytest.raises(ValueError, match="^f_b: 12 samples at the full-scale range"):
        nf.stop_solutions(IMU.w_ib_b, f, WIN, LAT, 50.0, **opts)
    sol = nf.stop_solutions(IMU.w_ib_b, f, WIN, LAT, 50.0, strict=False, **opts)
    np.testing.assert_array_equal(sol.faults["accel", "saturated"], [[0, 3, 0]] * 4)
    assert clipped[:, WIN[1, 0] : WIN[1, 1]].sum() == 12
    assert np.all(sol.faults["window", "refused"] == [0, 1, 0]) and np.isnan(sol.triad[:, 1]).all()
    np.testing.assert_array_equal(sol.triad[:, [0, 2]], CLEAN.triad[:, [0, 2]])
    # with the device ranges and no clipping nothing changes
    same = nf.stop_solutions(IMU.w_ib_b, IMU.f_b, WIN, LAT, 50.0, **opts)
    assert np.all(same.faults["gyro", "saturated"] == 0) and np.all(same.faults["accel", "saturated"] == 0)
    np.testing.assert_array_equal(same.triad, CLEAN.triad)


def test_frozen_gyro_stop_is_refused_and_counted():
    """Stop 2's gyro repeats its first sample (campaign: accepted, heading 19.5 deg off; here 13 deg)."""
    a, b = WIN[1]
    w = IMU.w_ib_b.copy()
    w[..., a:b, :] = w[..., a : a + 1, :]
    with pytest.raises(ValueError, match="^w_ib_b: one reading repeated over 18000 consecutive samples"):
        nf.stop_solutions(w, IMU.f_b, WIN, LAT, 50.0)
    sol = nf.stop_solutions(w, IMU.f_b, WIN, LAT, 50.0, strict=False)
    assert np.all(sol.faults["window", "refused"] == [0, 1, 0]) and np.isnan(sol.triad[:, 1]).all()
    np.testing.assert_array_equal(sol.faults["gyro", "stuck"], [[0, 18000, 0]] * 4)
    np.testing.assert_array_equal(sol.windows[1].faults["gyro", "stuck"], [18000] * 4)
    assert np.all(sol.faults["accel", "stuck"] == 0)
    np.testing.assert_array_equal(sol.triad[:, [0, 2]], CLEAN.triad[:, [0, 2]])
    # why: accepted, the frozen stop is many degrees off (the mean is one noisy sample)
    raw = nf.stop_solutions(w, IMU.f_b, WIN, LAT, 50.0, stuck_fraction=None)
    assert np.all(raw.faults["window", "refused"] == 0) and np.abs(attitude.wrap_pi(raw.triad - CLEAN.triad)).max() > 0.1
    # frozen on one axis after 60 s of the 180 s (2/3 of the stop), with 10 % dropouts: still refused
    w = IMU.w_ib_b.copy()
    w[..., a + 6000 : b, 0] = w[..., a + 6000 : a + 6001, 0]
    w, drop = faults.dropouts(w, 0.1, np.random.default_rng(12))
    sol = nf.stop_solutions(w, IMU.f_b, WIN, LAT, 50.0, strict=False)
    assert np.all(sol.faults["window", "refused"][:, 1] == 1)
    np.testing.assert_array_equal(sol.faults["gyro", "stuck"][:, 1], 12000 - drop[a + 6000 : b].sum())
    # below stuck_fraction (0.5 by default) a frozen stretch is not refused: 1/4 of the stop here
    w = IMU.w_ib_b.copy()
    w[..., a : a + 4500, :] = w[..., a : a + 1, :]
    assert np.all(nf.stop_solutions(w, IMU.f_b, WIN, LAT, 50.0).faults["window", "refused"] == 0)


def test_quantised_gyro_keeps_its_good_samples_under_mad_rejection():
    """A gyro quantised at 2 sigma: MAD = 0 (68 % of the samples on the median code).

    Campaign: with outlier_k=5, 1,647 of 3,000 samples were "outliers" and the stop was refused; the
    robust sigma is now 1.4826 max(MAD, q/2).
    """
    q = 2 * SIG_G
    a = WIN[1, 0]
    w, f = IMU.w_ib_b[..., a : a + 3000, :], IMU.f_b[..., a : a + 3000, :]
    wq = np.round(w / q) * q
    assert np.all(np.median(np.abs(wq - np.median(wq, axis=-2, keepdims=True)), axis=-2) == 0)
    win = alignment.static_means(wq, f, LAT, 50.0, outlier_k=5.0)
    assert np.all(win.faults["window", "refused"] == 0) and np.all(win.faults["gyro", "outlier"] == 0)
    # the quantised mean differs from the exact one by the mean rounding error: 5 sigma = 5 q / sqrt(12 N)
    exact = alignment.static_means(w, f, LAT, 50.0)
    assert np.abs(win.w_mean - exact.w_mean).max() < 5 * q / np.sqrt(12 * 3000)
    # whole stops: no sample rejected, no stop refused or stuck
    sol = nf.stop_solutions(np.round(IMU.w_ib_b / q) * q, IMU.f_b, WIN, LAT, 50.0, outlier_k=5.0)
    assert np.all(sol.faults["window", "refused"] == 0) and np.all(sol.faults["gyro", "outlier"] == 0)
    # and quantised spikes (100 sigma) are still rejected, exactly
    ws, hit = faults.spikes(IMU.w_ib_b, 0.01, SIG_G, np.random.default_rng(3))
    sol = nf.stop_solutions(np.round(ws / q) * q, IMU.f_b, WIN, LAT, 50.0, outlier_k=5.0)
    np.testing.assert_array_equal(sol.faults["gyro", "outlier"], np.broadcast_to(window_counts(hit), (4, 3)))


# ----------------------------------------------------------------------------- MEMS INS heading change

MEMS = sensors.imu_model("ADIS16475-1").replace(gyro={"bias": units.deg_per_s(0.005), "scale_factor": 0.0015})
PRE = int(10 / DT)
DRIVE = np.arange(WIN[0, 1] - PRE, WIN[1, 0])
MEMS_OUT = sensors.simulate_imu(W_TRUE[DRIVE], F_TRUE[DRIVE], DT, MEMS, np.random.default_rng(7), n_trials=4)
W_DRIVE, F_START = MEMS_OUT.w_ib_b[..., PRE:, :], MEMS_OUT.f_b[..., :PRE, :].mean(-2)
DPSI_CLEAN = nf.ins_heading_change(W_DRIVE, F_START, DT, LAT)


def test_ins_dropouts_are_held_within_a_stated_bound():
    w, drop = faults.dropouts(W_DRIVE, 0.1, np.random.default_rng(8))
    dpsi = nf.ins_heading_change(w, F_START, DT, LAT)
    assert np.all(robust.fault_report(w, "gyro")["gyro", "nan"] == drop.sum()) and np.isfinite(dpsi).all()
    # bound (first order): |d heading| <= sum over held samples of |w_held - w| dt, times 1/cos(pitch) <= 1.001
    idx = np.maximum.accumulate(np.where(drop, 0, np.arange(drop.size)))
    bound = 1.001 * np.linalg.norm(W_DRIVE[..., idx, :] - W_DRIVE, axis=-1).sum(-1) * DT
    assert np.all(np.abs(attitude.wrap_pi(dpsi - DPSI_CLEAN)) < bound)


def test_ins_gap_of_30_s_is_refused():
    w, gap = faults.gap(W_DRIVE, np.arange(W_DRIVE.shape[-2]) * DT, 5.0, 30.0)
    dpsi = nf.ins_heading_change(w, F_START, DT, LAT)
    assert np.isnan(dpsi).all() and np.all(robust.fault_report(w, "gyro")["gyro", "nan"] == 3000)
    with pytest.raises(ValueError, match="^dpsi_ins: "):  # cannot be used by mistake
        nf.resolve(CLEAN.candidates[:, 0], CLEAN.candidates[:, 1], dpsi)


def test_ins_saturation_is_refused_and_counted():
    """The 69-deg turn runs at 3.5 deg/s: within the ADIS16475-1's 125 deg/s, clipped by a 2-deg/s range."""
    dpsi = nf.ins_heading_change(W_DRIVE, F_START, DT, LAT, full_scale_gyro=MEMS.gyro.full_scale)
    assert np.all(robust.fault_report(W_DRIVE, "gyro", full_scale=MEMS.gyro.full_scale)["gyro", "saturated"] == 0)
    assert np.array_equal(dpsi, DPSI_CLEAN)
    fs = units.deg_per_s(2.0)
    w, clipped = faults.saturate(W_DRIVE, fs)
    dpsi = nf.ins_heading_change(w, F_START, DT, LAT, full_scale_gyro=fs)
    n_sat = robust.fault_report(w, "gyro", full_scale=fs)["gyro", "saturated"]
    np.testing.assert_array_equal(n_sat, clipped.sum(-1))
    assert np.all(n_sat > 0) and np.isnan(dpsi).all()
    # why: the clipped turn is short by tens of degrees
    wrong = nf.ins_heading_change(w, F_START, DT, LAT)
    assert np.all(np.abs(attitude.wrap_pi(wrong - DPSI_CLEAN)) > units.deg(10.0))


def _irregular_drive(jitter, seed):
    """Noise-free drive sampled at irregular times; each sample the exact mean rate over its interval."""
    fine = 0.001
    segs, stops = nf.stop_and_go(HEADS[:2], 20.0, 40.0, 5.0, PITCH[:2], ROLL[:2])
    traj = trajectory.vehicle(segs, fine, [LAT, units.deg(112.9), 50.0], HEADS[0])
    wf, ff = trajectory.ideal_imu(traj)
    a, b = int(round(stops[0, 1] / fine)), int(round(stops[1, 0] / fine))
    t = faults.irregular_times(int((b - a) * fine / DT) + 10, DT, jitter, np.random.default_rng(seed))
    k = np.unique(np.round(t / fine).astype(int)) + a
    k = k[k <= b]
    cw = np.concatenate([np.zeros((1, 3)), np.cumsum(wf, 0)])
    w = (cw[k[1:]] - cw[k[:-1]]) / np.diff(k)[:, None]
    return w, (k[1:] - k[:-1]) * fine, ff[a - 10000 : a].mean(0), attitude.wrap_pi(HEADS[1] - HEADS[0])


def test_ins_irregular_sampling_with_per_sample_intervals():
    """+-20 % jitter: bound 0.01 deg, the noise-free accuracy of the regular drive (test_northfinding)."""
    w, dts, f0, true = _irregular_drive(0.2, 9)
    err = np.rad2deg(abs(attitude.wrap_pi(nf.ins_heading_change(w, f0, dts, LAT) - true)))
    assert err < 0.01
    err_mean_dt = np.rad2deg(abs(attitude.wrap_pi(nf.ins_heading_change(w, f0, float(dts.mean()), LAT) - true)))
    assert err_mean_dt > 5 * err  # pretending the samples were regular costs accuracy
