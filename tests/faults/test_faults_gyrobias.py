"""Fault injection: the rotation bias estimator of paper 001 (navlib.papers.rotation_bias).

Data: the paper's rig, small: an MTi-100 rotated +-90 deg about y_b every 5 s
(0.5-s rotations, 4.5-s dwells) at 30 deg pitch, 40 deg N, 100 Hz, 300 s
(60 dwells). For every fault the counters must equal what was injected, the
Kalman covariance must stay symmetric positive definite, and the bias
estimate must stay within a stated bound of the fault-free run on the same
samples. ``SIGMA`` below is the predicted std of the fault-free least-squares
estimate (``lsq_covariance``), about 3.3 deg/h per axis here.
"""

import numpy as np
import pytest

from navlib import analysis, attitude, earth, euler, faults, robust, sensors, timing, trajectory, units
from navlib.papers import rotation_bias as gb

DT, PERIOD, ROT = 0.01, 5.0, 0.5
LAT = units.deg(40.0)
HPR0 = units.deg([0.0, 30.0, 0.0])
EY = [0.0, 1.0, 0.0]
W_IE_N = earth.earth_rate_n(LAT)
MODEL = sensors.imu_model("MTi-100")
SIG_G = MODEL.gyro.noise_density / np.sqrt(DT)  # per-sample white noise (rad/s)
SIG_A = MODEL.accel.noise_density / np.sqrt(DT)  # (m/s^2)
B_SIGMA0 = units.deg_per_h(50.0)


def _rig(duration=300.0, seed=7):
    traj = trajectory.reciprocating_rotation(duration, DT, [LAT, 0, 0], HPR0, EY, np.pi / 2, PERIOD, ROT)
    w, f = trajectory.ideal_imu(traj)
    imu = sensors.simulate_imu(w, f, DT, MODEL, np.random.default_rng(seed))
    starts, length = gb.dwell_windows(w.shape[0], DT, PERIOD, ROT)
    w_ie_b = earth.earth_rate_b(attitude.euler_to_dcm(gb.dwell_attitudes(HPR0, EY, np.pi / 2, starts.size)), LAT)
    in_dwell = np.zeros(w.shape[0], bool)
    for s in starts:
        in_dwell[s : s + length] = True
    return traj, w, f, imu, starts, length, w_ie_b, in_dwell


TRAJ, W_TRUE, F_TRUE, IMU, STARTS, LENGTH, W_IE_B, IN_DWELL = _rig()
CLEAN = gb.tilt_residuals(IMU.w_ib_b, IMU.f_b, DT, STARTS, LENGTH, W_IE_B)
R = gb.residual_covariance(CLEAN.tilt, LENGTH, DT, MODEL.gyro.noise_density, MODEL.accel.noise_density)
B_CLEAN = gb.lsq_bias(CLEAN.r, CLEAN.V)
SIGMA = np.sqrt(np.diag(analysis.lsq_covariance(CLEAN.V, R)))


def assert_spd(P):
    """Symmetric to rounding and positive definite, for every dwell."""
    np.testing.assert_allclose(P, np.swapaxes(P, -1, -2), rtol=0, atol=1e-12 * np.abs(P).max())
    assert np.linalg.eigvalsh(P).min() > 0


def kalman(res, interval=PERIOD):
    Rk = gb.residual_covariance(
        np.where(np.isfinite(res.tilt), res.tilt, 0.0), LENGTH, DT, MODEL.gyro.noise_density, MODEL.accel.noise_density
    )
    kf = gb.kalman_bias(res.r, res.V, Rk, interval, 0.0, B_SIGMA0)
    assert np.isfinite(kf.b).all() and np.isfinite(kf.sigma).all()
    assert_spd(kf.P)
    return kf


def dwells_hit(mask):
    return np.array([mask[s : s + LENGTH].any() for s in STARTS])


def test_fault_free_baseline():
    assert CLEAN.faults["dwell", "refused"] == CLEAN.faults["imu", "nan"] == 0
    kf = kalman(CLEAN)
    assert kf.faults["dwell", "nan"] == 0 and kf.faults["dwell", "outlier"] == 0
    # the 300-s estimate is within 4 predicted sigma of the mean true bias over the dwells
    assert np.all(np.abs(B_CLEAN - IMU.gyro_bias[IN_DWELL].mean(0)) < 4 * SIGMA)


def test_random_dropouts_are_filled_or_skipped_and_counted():
    """10 % of IMU samples NaN (gyro and accelerometer together)."""
    w, drop = faults.dropouts(IMU.w_ib_b, 0.1, np.random.default_rng(1))
    f = np.where(drop[:, None], np.nan, IMU.f_b)
    # default (max_missing = 0): every dwell with a dropout is skipped -- here all of them -- and counted
    strict = gb.tilt_residuals(w, f, DT, STARTS, LENGTH, W_IE_B)
    assert strict.faults["dwell", "refused"] == dwells_hit(drop).sum() == STARTS.size
    assert strict.faults["imu", "nan"] == (drop & IN_DWELL).sum() and np.isnan(strict.r).all()
    with pytest.raises(ValueError, match="^V: "):  # says so instead of guessing
        gb.lsq_bias(strict.r, strict.V)
    assert kalman(strict).faults["dwell", "nan"] == STARTS.size
    # max_missing = 0.5: dropouts filled with the dwell median, every one counted
    res = gb.tilt_residuals(w, f, DT, STARTS, LENGTH, W_IE_B, max_missing=0.5)
    assert res.faults["dwell", "refused"] == 0 and res.faults["imu", "nan"] == (drop & IN_DWELL).sum()
    # bound: filling ~10 % of a dwell's samples removes their noise increments; the estimate moves by
    # about sqrt(0.1) SIGMA at most -> 1 SIGMA per axis (measured 0.19, 0.03, 0.17 SIGMA)
    assert np.all(np.abs(gb.lsq_bias(res.r, res.V) - B_CLEAN) < SIGMA)
    b_run, skipped = gb.running_lsq_bias(res.r, res.V)
    assert skipped["dwell", "nan"] == 0 and np.all(np.abs(b_run[-1] - B_CLEAN) < SIGMA)
    kf = kalman(res)
    assert kf.faults["dwell", "nan"] == 0


def test_gap_of_30_s_skips_the_dwells_it_covers():
    w, gap = faults.gap(IMU.w_ib_b, TRAJ.time[:-1], 100.0, 30.0)
    f = np.where(gap[:, None], np.nan, IMU.f_b)
    res = gb.tilt_residuals(w, f, DT, STARTS, LENGTH, W_IE_B, max_missing=0.5)
    missing = np.array([gap[s : s + LENGTH].sum() for s in STARTS])
    skipped = missing > 0.5 * LENGTH
    assert res.faults["dwell", "refused"] == skipped.sum() == 6  # 30 s = 6 periods
    assert res.faults["imu", "nan"] == (gap & IN_DWELL).sum()
    assert res.faults["imu", "nan"] - missing[skipped].sum() == missing[~skipped].sum()
    assert np.isnan(res.r[skipped]).all() and np.isfinite(res.r[~skipped]).all()
    # bound: least squares on a subset of the dwells; b_sub - b_all has covariance P_sub - P_all (nested OLS,
    # R ~ equal per dwell) -> 5 sigma of that difference per axis
    b = gb.lsq_bias(res.r, res.V)
    P_sub = analysis.lsq_covariance(CLEAN.V[~skipped], R[~skipped])
    d_sigma = np.sqrt(np.clip(np.diag(P_sub) - SIGMA**2, 0, None))
    assert np.all(np.abs(b - B_CLEAN) < 5 * d_sigma + 0.05 * SIGMA)
    kf = kalman(res)
    assert kf.faults["dwell", "nan"] == skipped.sum()
    # the integrator refuses to bridge 30 s of unknown rotation
    with pytest.raises(ValueError, match="^w_ib_b: .*max_gap"):
        euler.integrate_euler(HPR0, w, DT, W_IE_N, max_gap=0.1)


def test_spikes_are_replaced_and_counted_with_outlier_k():
    """1 % of samples with 100-sigma spikes on the gyro and (independently) on the accelerometer."""
    w, hit_w = faults.spikes(IMU.w_ib_b, 0.01, SIG_G, np.random.default_rng(2))
    f, hit_f = faults.spikes(IMU.f_b, 0.01, SIG_A, np.random.default_rng(3))
    res = gb.tilt_residuals(w, f, DT, STARTS, LENGTH, W_IE_B, outlier_k=6.0)
    # exact: a 100-sigma spike is always beyond 6 MAD-sigma; a Gaussian sample almost never (p ~ 2e-9)
    assert res.faults["gyro", "outlier"] == (hit_w & IN_DWELL).sum()
    assert res.faults["accel", "outlier"] == (hit_f & IN_DWELL).sum()
    # bound: replacing 1 % of the samples moves the estimate by ~0.1 SIGMA at most -> 0.5 SIGMA
    assert np.all(np.abs(gb.lsq_bias(res.r, res.V) - B_CLEAN) < 0.5 * SIGMA)
    kf = kalman(res)
    assert kf.faults["dwell", "outlier"] == 0
    # without outlier_k the spikes reach the residuals; the Kalman gate reports it (it rejects most dwells)
    raw = gb.tilt_residuals(w, f, DT, STARTS, LENGTH, W_IE_B)
    assert raw.faults["gyro", "outlier"] == raw.faults["accel", "outlier"] == 0
    assert kalman(raw).faults["dwell", "outlier"] > STARTS.size // 2


def test_outlier_detection_leaves_clean_data_alone():
    res = gb.tilt_residuals(IMU.w_ib_b, IMU.f_b, DT, STARTS, LENGTH, W_IE_B, outlier_k=6.0)
    assert res.faults["gyro", "outlier"] == res.faults["accel", "outlier"] == 0
    np.testing.assert_array_equal(res.r, CLEAN.r)


def test_quantised_gyro_is_not_mostly_rejected():
    """A gyro on a 1e-4 rad/s grid with 0.5e-4 rad/s noise (below 0.74 steps: the dwell's MAD reads 0).

    The MAD is floored at half the step (``_kernels.robust_sigma``, the floor of ``alignment.static_means``):
    no good sample is rejected (the compiled MAD without the floor rejected 18,819 of the 27,000 dwell
    samples, 70 %, and moved the bias estimate by up to 8 deg/h), the residuals equal those without
    outlier detection, and a 100-step spike is still replaced and counted.
    """
    rng = np.random.default_rng(3)
    w = np.round((W_TRUE + units.deg_per_h(10.0) + rng.normal(0.0, 0.5e-4, W_TRUE.shape)) / 1e-4) * 1e-4
    raw = gb.tilt_residuals(w, IMU.f_b, DT, STARTS, LENGTH, W_IE_B)
    res = gb.tilt_residuals(w, IMU.f_b, DT, STARTS, LENGTH, W_IE_B, outlier_k=6.0)
    assert res.faults["gyro", "outlier"] == res.faults["accel", "outlier"] == 0
    np.testing.assert_array_equal(res.r, raw.r)
    k = STARTS[3] + LENGTH // 2
    w[k, 1] += 100 * 1e-4
    assert gb.tilt_residuals(w, IMU.f_b, DT, STARTS, LENGTH, W_IE_B, outlier_k=6.0).faults["gyro", "outlier"] == 1


def _irregular_rig(jitter, seed=5, duration=60.0):
    """Noise-free rig sampled at irregular times: each sample is the exact mean over its own interval."""
    fine = 0.001
    traj = trajectory.reciprocating_rotation(duration, fine, [LAT, 0, 0], HPR0, EY, np.pi / 2, PERIOD, ROT)
    wf, ff = trajectory.ideal_imu(traj)
    t = faults.irregular_times(int(duration / DT) + 10, DT, jitter, np.random.default_rng(seed))
    k = np.unique(np.round(t / fine).astype(int))
    k = k[k <= wf.shape[0]]
    cw, cf = (np.concatenate([np.zeros((1, 3)), np.cumsum(x, 0)]) for x in (wf, ff))
    n = np.diff(k)[:, None]
    w, f = (cw[k[1:]] - cw[k[:-1]]) / n, (cf[k[1:]] - cf[k[:-1]]) / n
    return traj.hpr[k], k * fine, w, f


def test_irregular_sampling_is_integrated_exactly_with_per_sample_intervals():
    """+-20 % jitter: with dt as an array the noise-free rig recovers the bias and the attitude."""
    B = units.deg_per_h(np.array([10.0, -7.0, 12.0]))
    hpr_true, t, w, f = _irregular_rig(0.2)
    dts = np.diff(t)
    starts = np.searchsorted(t, np.arange(0, 55, PERIOD) + 0.05)  # first sample inside each dwell
    length = int(min(np.searchsorted(t, t[s] + 4.35) - s for s in starts))  # ends before the rotation
    w_ie_b = earth.earth_rate_b(attitude.euler_to_dcm(gb.dwell_attitudes(HPR0, EY, np.pi / 2, starts.size)), LAT)
    res = gb.tilt_residuals(w + B, f, dts, starts, length, w_ie_b)
    # bound: exact up to the linear-trend model of the dwell (noise-free), 1e-3 deg/h
    assert units.to_deg_per_h(np.abs(gb.lsq_bias(res.r, res.V) - B).max()) < 1e-3
    # (a still dwell under a constant rate is self-consistent with the mean interval too: the jitter
    # matters for the integration through the rotations, below)
    # integration with per-sample intervals follows the true attitude; bound 1e-6 rad (RK4 with each
    # interval's mean rate held; the regular 100-Hz run of the same rig reaches 1e-8)
    hpr = euler.integrate_euler(hpr_true[0], w, dts, W_IE_N)
    assert np.abs(analysis.attitude_errors(hpr, hpr_true)).max() < 1e-6
    hpr_reg = euler.integrate_euler(hpr_true[0], w, float(dts.mean()), W_IE_N)
    assert np.abs(analysis.attitude_errors(hpr_reg, hpr_true)).max() > 1e-3


def test_duplicated_and_out_of_order_timestamps_through_sanitize():
    t = TRAJ.time[:-1]
    t_dup, dup = faults.duplicate_timestamps(t, 0.01, np.random.default_rng(8))
    t_bad, order = faults.swap_timestamps(t_dup, 0.01, np.random.default_rng(9))
    t_ok, w, f, rep = timing.sanitize(t_bad, IMU.w_ib_b[order], IMU.f_b[order])
    n_dup = t_dup.size - np.unique(t_dup).size  # runs of hits repeat one time once (dup.sum() >= n_dup)
    assert rep.n_duplicate == n_dup and rep.n_out_of_order > 0 and rep.n_out == t.size - n_dup
    dts = np.append(timing.intervals(t_ok), DT)  # interval after each sample
    starts = np.searchsorted(t_ok, TRAJ.time[STARTS] - 1e-9)
    length = int(np.min(np.searchsorted(t_ok, TRAJ.time[STARTS + LENGTH] - 1e-9) - starts))
    res = gb.tilt_residuals(w, f, dts, starts, length, W_IE_B)
    assert res.faults["dwell", "refused"] == 0 and LENGTH - length <= 15
    # bound: ~1 % of the dwell samples lost (their interval joins the previous sample's) -> 0.5 SIGMA
    assert np.all(np.abs(gb.lsq_bias(res.r, res.V) - B_CLEAN) < 0.5 * SIGMA)
    end_t = t_ok[np.minimum(res.end, t_ok.size - 1)]
    kf = kalman(res, np.diff(end_t, prepend=end_t[0] - PERIOD))  # per-dwell intervals from the timestamps
    assert kf.faults["dwell", "nan"] == 0


def test_integrator_fills_dropouts_by_interpolation_within_a_stated_bound():
    w, drop = faults.dropouts(IMU.w_ib_b, 0.1, np.random.default_rng(1))
    clean = euler.integrate_euler(HPR0, IMU.w_ib_b, DT, W_IE_N)
    hpr = euler.integrate_euler(HPR0, w, DT, W_IE_N, max_gap=0.1)
    rep = robust.fault_report(w, "gyro", full_scale=MODEL.gyro.full_scale, flags=True)  # what it filled
    assert rep["gyro", "nan"] == drop.sum() and rep["gyro", "saturated"] == 0 and np.isfinite(hpr).all()
    np.testing.assert_array_equal(rep.flags["gyro", "nan"], drop)
    # bound (first order): the attitude error is the integral of the interpolation error, mapped by Eq. (2)
    # (|Euler rate| <= |w| (1 + tan p) / cos p... <= 2.5 |w| at 30 deg pitch)
    idx = np.arange(w.shape[0])
    interp = np.stack([np.interp(idx, idx[~drop], IMU.w_ib_b[~drop, a]) for a in range(3)], -1)
    bound = 2.5 * np.sum(np.linalg.norm(interp - IMU.w_ib_b, axis=-1)) * DT
    err = np.abs(analysis.attitude_errors(hpr, clean)).max()
    assert err < bound, (err, bound)


def test_gyro_saturation_is_counted_by_the_integrator():
    """The rig's rotations peak at 360 deg/s: within the MTi-100's 450 deg/s, beyond the ADIS16475-1's 125."""
    fs_mti = MODEL.gyro.full_scale
    rep = robust.fault_report(IMU.w_ib_b, "gyro", full_scale=fs_mti, flags=True)
    assert rep["gyro", "saturated"] == 0 and not rep.flags["gyro", "saturated"].any()
    fs = sensors.imu_model("ADIS16475-1").gyro.full_scale
    w, clipped = faults.saturate(IMU.w_ib_b, fs)
    hpr = euler.integrate_euler(HPR0, w, DT, W_IE_N)
    rep = robust.fault_report(w, "gyro", full_scale=fs, flags=True)
    assert rep["gyro", "saturated"] == clipped.sum() > 0
    np.testing.assert_array_equal(rep.flags["gyro", "saturated"], clipped)
    # why it must be reported: every clipped rotation falls short by tens of degrees (the return
    # rotation undoes it, so only the attitude in between shows it)
    assert np.abs(analysis.attitude_errors(hpr, TRAJ.hpr)).max() > units.deg(10.0)
    # the dwells are still: the estimator is unaffected and counts nothing
    res = gb.tilt_residuals(w, IMU.f_b, DT, STARTS, LENGTH, W_IE_B, full_scale_gyro=fs)
    assert res.faults["imu", "saturated"] == res.faults["dwell", "refused"] == 0
    np.testing.assert_array_equal(res.r, CLEAN.r)


def test_accelerometer_saturation_skips_the_dwell():
    """Knocks of 30 g (0.03 s) in three dwells, clipped at the MTi-100's 20 g range."""
    f = IMU.f_b.copy()
    knocked = [4, 17, 40]
    for k in knocked:
        f[STARTS[k] + 100 : STARTS[k] + 103, 0] += 30 * 9.80665
    fs = MODEL.accel.full_scale
    f, clipped = faults.saturate(f, fs)
    res = gb.tilt_residuals(IMU.w_ib_b, f, DT, STARTS, LENGTH, W_IE_B, full_scale_accel=fs, full_scale_gyro=MODEL.gyro.full_scale)
    assert res.faults["imu", "saturated"] == (clipped & IN_DWELL).sum() == 9 and res.faults["dwell", "refused"] == len(knocked)
    assert np.isnan(res.r[knocked]).all()
    kf = kalman(res)
    assert kf.faults["dwell", "nan"] == len(knocked)
    keep = np.setdiff1d(np.arange(STARTS.size), knocked)
    np.testing.assert_array_equal(res.r[keep], CLEAN.r[keep])  # other dwells untouched


def test_kalman_covariance_stays_spd_under_all_faults_at_once():
    w, drop = faults.dropouts(IMU.w_ib_b, 0.1, np.random.default_rng(11))
    f = np.where(drop[:, None], np.nan, IMU.f_b)
    w, _ = faults.gap(w, TRAJ.time[:-1], 200.0, 30.0)
    w, _ = faults.spikes(w, 0.01, SIG_G, np.random.default_rng(12))
    res = gb.tilt_residuals(w, f, DT, STARTS, LENGTH, W_IE_B, max_missing=0.5, outlier_k=6.0)
    kf = kalman(res)
    assert kf.faults["dwell", "nan"] == res.faults["dwell", "refused"] > 0
    assert np.all(np.abs(kf.b[-1] - B_CLEAN) < 4 * kf.sigma[-1])
