"""Fault injection for navlib.papers.gauss_kruger_ekf: the 5-state EKF and dead reckoning of paper 002.

Data: paper 002's simulated robot (Fuzhou site, GK zone 40, T = 0.5 s, the
paper's Q and R in SI units: GPS sigma 2.5 m, heading 0.1 rad, speed 0.02 m/s,
yaw rate 0.05 rad/s): the curved run of Fig. 5 (1 m/s, 5 deg/s), shortened to
300 s, and a run with three fast turns (3 rad/s for 2 s) for gyro saturation.

Contract checked for every fault (issue 9): states finite; every covariance
symmetric (to 1e-9 relative) with eigenvalues > 0; the error within a stated
bound of the fault-free run on the same data; every skipped, gated or
saturated sample counted under its key of the result's ``faults`` (``EkfResult.faults``,
the fault report of dead reckoning, ``timing.TimingReport``) equal to what was injected.
The gate used is the chi-square quantile for 1e-4 false alarms per channel
(GPS 2 dof: 18.4; heading, speed, yaw rate 1 dof: 15.1); the fault-free runs
check that it raises no false alarm on this data.
"""

import numpy as np
import pytest

from navlib import analysis, faults, sensors, timing
from navlib.filters import planar_ekf
from navlib.imu import SensorLimits
from navlib.papers import gauss_kruger_ekf as planar

ORIGIN = np.deg2rad([26.06, 119.20])  # Fuzhou, GK zone 40 (notebook 03's site)
T = 0.5
N = 600  # 300 s
X0_CURVE = np.array([0.0, 0.0, np.pi / 4, 1.0, np.deg2rad(5.0)])
P0 = np.diag(np.diag(planar.R_PAPER))  # initialised from the first fix (PD from the start)
GATE = [18.4, 15.1, 15.1, 15.1]
GATE_GPS = [18.4, np.inf, np.inf, np.inf]  # gate the GPS channel only
SIGMA = np.sqrt(np.diag(planar.R_PAPER))  # 2.5 m, 2.5 m, 0.1 rad, 0.02 m/s, 0.05 rad/s
GYRO_RANGE = sensors.imu_model("ADIS16475-1").gyro.full_scale  # ±125 deg/s = 2.18 rad/s (datasheet)


def curve_run(seed=1):
    truth = planar_ekf.propagate(X0_CURVE, T, N)
    t = np.arange(N + 1) * T
    s = planar.simulate_sensors(truth, ORIGIN, planar.R_PAPER, np.random.default_rng(seed))
    return t, truth, s


SENSORS = ("gnss", "heading", "speed", "yaw_rate")  # the channels' fault sensors


def config(gate=np.inf, reacquire=3, **limits):
    """The paper's noise, P0 from the first fix, the gate and the yaw-rate gyro's limits (SensorLimits fields)."""
    return planar_ekf.EkfConfig(planar.Q_PAPER, planar.R_PAPER, P0, gate, reacquire, SensorLimits(**limits))


def ekf(t, gps, heading, speed, yaw_rate, x0=X0_CURVE, **kw):
    return planar.ekf(t, planar.Sensors(gps, heading, speed, yaw_rate), x0, origin=ORIGIN, config=config(**kw))


def counts(res, kind):
    """Counts of one fault kind per channel (CHANNELS order)."""
    return [res.faults[sensor, kind] for sensor in SENSORS]


def rejected(res):
    """Channels gated out per epoch, shape (N, 4)."""
    return np.column_stack([res.faults.flags[sensor, "outlier"] for sensor in SENSORS])


def held_steps(report):
    """Dead-reckoning steps that held the previous speed and yaw rate."""
    return np.any(list(report.flags.values()), axis=0).sum()


def heading_gap(a, b):
    """|heading a - heading b| wrapped to [0, pi] (rad), per epoch."""
    return np.abs(np.angle(np.exp(1j * (a.x[:, 2] - b.x[:, 2]))))


def rmse(res, truth):
    return np.sqrt(np.mean(analysis.position_error(res.x, truth) ** 2))


def assert_healthy(res):
    """Finite states; every covariance symmetric and positive definite."""
    assert np.all(np.isfinite(res.x)) and np.all(np.isfinite(res.P))
    asym = np.abs(res.P - np.swapaxes(res.P, -1, -2)).max(axis=(-1, -2))
    assert np.all(asym <= 1e-9 * np.abs(res.P).max(axis=(-1, -2)))
    assert np.linalg.eigvalsh(res.P).min() > 0


@pytest.fixture(scope="module")
def clean():
    t, truth, s = curve_run()
    res = ekf(t, s.gps, s.heading, s.speed, s.yaw_rate)
    gated = ekf(t, s.gps, s.heading, s.speed, s.yaw_rate, gate=GATE)
    assert_healthy(res)
    # The gate is silent on fault-free data: same result, no rejection.
    assert not rejected(gated).any() and np.array_equal(gated.x, res.x)
    assert rmse(res, truth) < 2.5  # below the GPS sigma
    return t, truth, s, res


# --------------------------------------------------------------------------
# Dropouts
# --------------------------------------------------------------------------


@pytest.mark.parametrize("seed", [10, 11, 12])
def test_ekf_random_dropouts_are_skipped_and_counted(clean, seed):
    """10 % NaN on each channel independently: skipped component by component, counted exactly.

    Bound: position RMSE within 10 % of the fault-free run (measured +3.2 to +4.5 %):
    a tenth fewer fixes raises the steady-state variance by about 1/0.9.
    """
    t, truth, s, ref = clean
    rng = np.random.default_rng(seed)
    gps, m_gps = faults.dropouts(s.gps, 0.1, rng)
    heading, m_h = faults.dropouts(s.heading, 0.1, rng)
    speed, m_v = faults.dropouts(s.speed, 0.1, rng)
    yaw_rate, m_w = faults.dropouts(s.yaw_rate, 0.1, rng)
    res = ekf(t, gps, heading, speed, yaw_rate, gate=GATE)
    assert_healthy(res)
    injected = [m[1:].sum() for m in (m_gps, m_h, m_v, m_w)]
    assert counts(res, "nan") == injected and res.faults["gnss", "nan"] == injected[0]
    assert res.prediction_only.sum() == (m_gps & m_h & m_v & m_w)[1:].sum()
    assert not rejected(res).any()
    assert rmse(res, truth) < 1.10 * rmse(ref, truth)


@pytest.mark.parametrize("channels", ["gps", "imu", "all"])
def test_ekf_30_s_gap_predicts_and_recovers(clean, channels):
    """A 30 s outage (60 epochs) of GPS, of the IMU channels, or of everything.

    Counted: ``faults[sensor, "nan"]`` (and ``prediction_only`` when all are out).
    Bounds: during the gap the error stays inside 3 sigma of the filter's own
    position covariance (measured max 1.8 sigma); 100 s after the gap the RMSE
    equals the fault-free run's to 5 % (the filter forgets the gap).
    """
    t, truth, s, ref = clean
    gps, heading, speed, yaw_rate = s.gps, s.heading, s.speed, s.yaw_rate
    if channels in ("gps", "all"):
        gps, hole = faults.gap(gps, t, 100.0, 30.0)
    if channels in ("imu", "all"):
        heading, hole = faults.gap(heading, t, 100.0, 30.0)
        speed, _ = faults.gap(speed, t, 100.0, 30.0)
        yaw_rate, _ = faults.gap(yaw_rate, t, 100.0, 30.0)
    res = ekf(t, gps, heading, speed, yaw_rate, gate=GATE)
    assert_healthy(res)
    assert hole.sum() == 60
    expect = {"gps": [60, 0, 0, 0], "imu": [0, 60, 60, 60], "all": [60] * 4}[channels]
    assert counts(res, "nan") == expect
    assert res.prediction_only.sum() == (60 if channels == "all" else 0)
    assert np.all(res.prediction_only[hole] == (channels == "all")) and not rejected(res)[hole].any()
    err = analysis.position_error(res.x, truth)
    sigma = np.sqrt(res.P[:, 0, 0] + res.P[:, 1, 1])
    assert np.all(err[1:] < 3 * sigma[1:])
    after = slice(int(230 / T), None)
    e_ref = analysis.position_error(ref.x, truth)
    assert np.sqrt(np.mean(err[after] ** 2)) < 1.05 * np.sqrt(np.mean(e_ref[after] ** 2))


# --------------------------------------------------------------------------
# Outliers
# --------------------------------------------------------------------------


@pytest.mark.parametrize("seed", [20, 21, 22])
def test_ekf_imu_spikes_are_gated_and_counted(clean, seed):
    """1 % of heading, speed and yaw-rate samples get ±100 sigma spikes (per channel).

    With the gate every spike is rejected on its own channel and nothing else
    (the outlier flags equal the injected masks); the other channels of the epoch
    are still fused. Bounds vs the fault-free run: positions within 0.2 m
    (measured < 0.05 m: only the spiked samples are lost), heading within
    0.3 rad (3 sigma of the heading channel).
    """
    t, truth, s, ref = clean
    rng = np.random.default_rng(seed)
    heading, m_h = faults.spikes(s.heading, 0.01, SIGMA[2], rng)
    speed, m_v = faults.spikes(s.speed, 0.01, SIGMA[3], rng)
    yaw_rate, m_w = faults.spikes(s.yaw_rate, 0.01, SIGMA[4], rng)
    res = ekf(t, s.gps, heading, speed, yaw_rate, gate=GATE)
    assert_healthy(res)
    injected = np.column_stack([np.zeros_like(m_h), m_h, m_v, m_w])
    injected[0] = False  # the first row is never fused
    assert np.array_equal(rejected(res), injected)
    assert counts(res, "outlier") == list(injected.sum(axis=0))
    assert np.abs(res.x[:, :2] - ref.x[:, :2]).max() < 0.2
    assert heading_gap(res, ref).max() < 0.3  # measured 0.09-0.14 rad (sigma 0.1 rad)
    assert np.all(np.isfinite(res.nis[1:]))  # GPS always fused here
    # Without the gate a heading spike (10 rad, 2.56 rad after wrapping) is fused silently.
    blind = ekf(t, s.gps, heading, speed, yaw_rate)
    assert not blind.faults and heading_gap(blind, ref).max() > 1.0  # measured 1.6 rad


@pytest.mark.parametrize("seed", [30, 31, 32])
def test_ekf_gps_jumps_of_50_m_are_gated_and_counted(clean, seed):
    """2 % of GPS fixes moved 50 m (20 sigma) in a random direction.

    Gated: every jump rejected (GPS channel only), count = injected. Bound: the
    position stays within 4 m of the fault-free run (measured 1.9-2.1 m: a
    gated fix is a lost fix, and one fix moves the estimate by at most the gain
    ~0.4 times a 3-sigma innovation of ~9 m). Ungated, the same jumps pull the
    track more than 10 m away (measured 16-19 m) without any counter moving.
    """
    t, truth, s, ref = clean
    rng = np.random.default_rng(seed)
    lla = np.column_stack([s.gps, np.zeros(len(t))])
    jumped, hit = faults.position_jumps(lla, 0.02, rng, size_m=50.0)
    hit[0] = False  # the first row is never fused
    res = ekf(t, jumped[:, :2], s.heading, s.speed, s.yaw_rate, gate=GATE)
    assert_healthy(res)
    assert hit.sum() >= 5
    assert np.array_equal(rejected(res)[:, 0], hit) and not rejected(res)[:, 1:].any()
    assert res.faults["gnss", "outlier"] == hit.sum()
    assert np.abs(res.x[:, :2] - ref.x[:, :2]).max() < 4.0
    assert rmse(res, truth) < 1.10 * rmse(ref, truth)
    blind = ekf(t, jumped[:, :2], s.heading, s.speed, s.yaw_rate)
    assert not blind.faults and np.abs(blind.x[:, :2] - ref.x[:, :2]).max() > 10.0


# --------------------------------------------------------------------------
# Timing
# --------------------------------------------------------------------------


def test_ekf_rejects_unsanitised_timestamps_and_sanitize_pipeline_works(clean):
    """Repeated and out-of-order timestamps: ``ekf`` raises ValueError naming ``t``; the
    documented pipeline ``timing.sanitize -> ekf`` sorts them, drops the repeats and counts both.

    Bound: swaps alone are undone exactly (identical result); with the repeats
    dropped (each loses one epoch of data) the RMSE is within 5 % of the fault-free run.
    """
    t, truth, s, ref = clean
    rng = np.random.default_rng(40)
    data = [s.gps, s.heading, s.speed, s.yaw_rate]
    t_swap, order = faults.swap_timestamps(t, 0.02, rng)
    with pytest.raises(ValueError, match="^t: "):
        ekf(t_swap, *[d[order] for d in data])
    t_s, *cols, report = timing.sanitize(t_swap, *[d[order] for d in data])
    assert report.n_out_of_order == np.sum(order != np.arange(len(t))) // 2 and report.n_duplicate == 0
    res = ekf(t_s, *cols)
    assert np.array_equal(res.x, ref.x)

    t_dup, hit = faults.duplicate_timestamps(t, 0.03, rng)
    with pytest.raises(ValueError, match="^t: "):
        ekf(t_dup, *data)
    t_s, *cols, report = timing.sanitize(t_dup, *data)
    assert report.n_duplicate == hit.sum() > 0 and report.n_out == len(t) - hit.sum()
    res = ekf(t_s, *cols, gate=GATE)
    assert_healthy(res)
    assert not rejected(res).any()
    assert rmse(res, truth[~hit]) < 1.05 * rmse(ref, truth)


def _irregular_truth(dt):
    X = np.empty((len(dt) + 1, 5))
    X[0] = X0_CURVE
    for k, step in enumerate(dt):
        X[k + 1] = planar_ekf.motion_model(X[k], step)
    return X


def test_ekf_irregular_sampling_uses_the_per_step_interval(clean):
    """Intervals T (1 + u), u uniform in ±20 %: the step follows ``t``.

    Exact: with no measurements the EKF's prediction, and dead reckoning on
    noise-free samples, reproduce the irregularly sampled truth to 1e-9 m, while
    the same samples on a regular time axis miss it by > 1 m. Bound: with
    noisy sensors the RMSE is within 10 % of the regular run with the same
    noise draw (same number of epochs; Q stays per step).
    """
    t, truth, s, ref = clean
    t_irr = faults.irregular_times(N + 1, T, 0.2, np.random.default_rng(50))
    dt = np.diff(t_irr)
    assert 0.79 * T < dt.min() and dt.max() < 1.21 * T
    truth_irr = _irregular_truth(dt)
    blind = planar_ekf.filter_grid(t_irr, np.full((N + 1, 5), np.nan), X0_CURVE, config())
    assert blind.prediction_only.sum() == N
    np.testing.assert_allclose(blind.x[:, :2], truth_irr[:, :2], rtol=0, atol=1e-9)
    pose, held = planar_ekf.dead_reckoning(t_irr, truth_irr[:, 3], truth_irr[:, 4], X0_CURVE)
    np.testing.assert_allclose(pose[:, :2], truth_irr[:, :2], rtol=0, atol=1e-9)
    pose, _ = planar_ekf.dead_reckoning(t, truth_irr[:, 3], truth_irr[:, 4], X0_CURVE)
    assert analysis.position_error(pose, truth_irr).max() > 1.0
    s_irr = planar.simulate_sensors(truth_irr, ORIGIN, planar.R_PAPER, np.random.default_rng(1))
    res = ekf(t_irr, s_irr.gps, s_irr.heading, s_irr.speed, s_irr.yaw_rate, gate=GATE)
    assert_healthy(res)
    assert not rejected(res).any()
    assert rmse(res, truth_irr) < 1.10 * rmse(ref, truth)


# --------------------------------------------------------------------------
# Sensor health: clock jumps and a stuck yaw-rate gyro
# --------------------------------------------------------------------------

K_FAULT = 200  # epoch of the fault (100 s)
AFTER = slice(K_FAULT + 60, K_FAULT + 120)  # the 30 s that start 30 s after it


def errors(res, truth):
    """Position (m) and heading (rad) error per epoch."""
    return analysis.position_error(res.x, truth), np.abs(np.angle(np.exp(1j * (res.x[:, 2] - truth[:, 2]))))


def other_faults(res, key):
    return {k: c for k, c in res.faults.counts.items() if k != key and c}


@pytest.mark.parametrize("gate", [np.inf, GATE], ids=["ungated", "gated"])
def test_ekf_clock_jump_is_not_integrated_counted_and_recovered_from(clean, gate):
    """One interval of 3600 s at 100 s (the time stamps jump; the data go on, and on this 72 s circle the
    robot is where it would be after a real hour-long gap too).

    Counted once (``faults["clock", "jump"]``) and flagged at its epoch; nothing else is counted. The
    state is held over the jump and P grows by Q for each of its 7200 nominal steps, so the epoch's
    measurements take over: from the jump on the position error stays below 10 m (measured max 3.6 m,
    6.2 m with other seeds; 4 sigma of the GPS). Recovery, the issue's criterion: the RMS position and heading errors over the
    30 s that start 30 s after the jump are within 2x the fault-free run's (measured 1.00x). The old
    EKF integrated the unicycle model over the 3600 s: nothing counted, 14 m off at the jump ungated,
    and gated 3.6 km off for 3 epochs with the GPS fixes counted as 3 outliers and a re-acquisition.
    """
    t, truth, s, _ = clean
    ref = ekf(t, s.gps, s.heading, s.speed, s.yaw_rate, gate=gate)
    t_jump = t.copy()
    t_jump[K_FAULT:] += 3600.0 - T
    res = ekf(t_jump, s.gps, s.heading, s.speed, s.yaw_rate, gate=gate)
    assert_healthy(res)
    assert res.faults["clock", "jump"] == 1 and np.flatnonzero(res.faults.flags["clock", "jump"]).tolist() == [K_FAULT]
    assert not other_faults(res, ("clock", "jump")) and not ref.faults
    np.testing.assert_array_equal(res.x[:K_FAULT], ref.x[:K_FAULT])
    e_pos, e_hdg = errors(res, truth)
    r_pos, r_hdg = errors(ref, truth)
    assert e_pos[K_FAULT:].max() < 10.0
    for e, r in ((e_pos, r_pos), (e_hdg, r_hdg)):
        assert np.sqrt(np.mean(e[AFTER] ** 2)) < 2.0 * np.sqrt(np.mean(r[AFTER] ** 2))


def test_ekf_max_dt_default_is_ten_median_steps():
    t = np.arange(40) * T
    z = np.tile([0.0, 0.0, 0.3, 1.0, 0.0], (40, 1))
    for gap, expected in ((10 * T, 0), (10 * T + 1e-6, 1)):
        t_gap = np.r_[t[:20], t[20:] + gap - T]
        assert planar_ekf.filter_grid(t_gap, z, z[0], config()).faults["clock", "jump"] == expected
    assert planar_ekf.filter_grid(t_gap, z, z[0], config(max_dt=np.inf)).faults["clock", "jump"] == 0
    assert planar_ekf.filter_grid(t_gap, z, z[0], config(max_dt=6.0)).faults["clock", "jump"] == 0
    with pytest.raises(ValueError, match="^max_dt: "):
        config(max_dt=0.0)


@pytest.mark.parametrize("kind", ["latched", "frozen"])
def test_ekf_stuck_yaw_rate_is_skipped_and_counted(clean, kind):
    """The yaw-rate gyro stops updating for 10 s at 100 s: latched at 0.3 rad/s (truth 0.087), or frozen
    at its last sample (a noise draw). Found by ``robust.stuck_samples`` (runs of 5 epochs and more: the
    "auto" 0.1 s is below one 0.5 s step), counted in ``faults["yaw_rate", "stuck"]`` (20 and 21 epochs),
    flagged, skipped like NaN samples; nothing else is counted.

    Bounds: over the run and the 30 s after it the yaw-rate estimate's error stays within 2x the fault-free
    run's largest (measured 1.00x, both); 30 s after, position and heading RMS within 2x (measured 1.00x).
    With the check off (``stuck_run=None``) the latched rate is fused (the 1-dof gate passes it: a
    0.21 rad/s innovation against S = 0.004 rad^2/s^2 is NIS 11 < 15.1) and the estimate is off by
    0.21 rad/s (2.5x), uncounted; a frozen noise draw is harmless either way, but counted only with the check.
    """
    t, truth, s, _ = clean
    ref = ekf(t, s.gps, s.heading, s.speed, s.yaw_rate, gate=GATE)
    yaw_rate = s.yaw_rate.copy()
    stuck = np.zeros(len(t), bool)
    if kind == "latched":
        yaw_rate[K_FAULT : K_FAULT + 20] = 0.3
        stuck[K_FAULT : K_FAULT + 20] = True
    else:
        yaw_rate[K_FAULT : K_FAULT + 20] = yaw_rate[K_FAULT - 1]
        stuck[K_FAULT - 1 : K_FAULT + 20] = True
    res = ekf(t, s.gps, s.heading, s.speed, yaw_rate, gate=GATE)
    assert_healthy(res)
    assert res.faults["yaw_rate", "stuck"] == stuck.sum() and np.array_equal(res.faults.flags["yaw_rate", "stuck"], stuck)
    assert not other_faults(res, ("yaw_rate", "stuck"))
    during = slice(K_FAULT, K_FAULT + 80)

    def w_err(r):
        return np.abs(r.x[during, 4] - truth[during, 4]).max()

    assert w_err(res) < 2.0 * w_err(ref)
    for e, r in zip(errors(res, truth), errors(ref, truth), strict=True):
        assert np.sqrt(np.mean(e[AFTER] ** 2)) < 2.0 * np.sqrt(np.mean(r[AFTER] ** 2))
    off = ekf(t, s.gps, s.heading, s.speed, yaw_rate, gate=GATE, stuck_run=None)
    assert not off.faults
    if kind == "latched":
        assert w_err(off) > 2.0 * w_err(ref)


def test_ekf_fault_free_results_are_unchanged(clean):
    """No jump, no stuck sample: bit-identical to the run with both checks off (notebook 03 relies on it)."""
    t, truth, s, ref = clean
    for gate in (np.inf, GATE):
        on = ekf(t, s.gps, s.heading, s.speed, s.yaw_rate, gate=gate)
        off = ekf(t, s.gps, s.heading, s.speed, s.yaw_rate, gate=gate, max_dt=np.inf, stuck_run=None)
        assert not on.faults and not on.faults.flags["clock", "jump"].any()
        np.testing.assert_array_equal(on.x, off.x)
        np.testing.assert_array_equal(on.P, off.P)


# --------------------------------------------------------------------------
# Saturation
# --------------------------------------------------------------------------


def fast_turns_run(seed=3, spin_steps=4):
    """Drive at 1 m/s with three turns at 3 rad/s (172 deg/s) of ``spin_steps`` epochs each."""
    v, w = np.ones(N), np.zeros(N)
    for k in (120, 300, 450):
        w[k : k + spin_steps], v[k : k + spin_steps] = 3.0, 0.3
    x0 = np.array([0.0, 0.0, 0.3, 1.0, 0.0])
    truth = planar_ekf.propagate(x0, T, speed=v, yaw_rate=w)
    s = planar.simulate_sensors(truth, ORIGIN, planar.R_PAPER, np.random.default_rng(seed))
    return np.arange(N + 1) * T, truth, s, x0


def test_ekf_gyro_saturation_is_counted_and_never_taken_at_face_value():
    """The yaw-rate channel of a ±125 deg/s gyro (ADIS16475-1) through 172 deg/s turns.

    With ``full_scale_gyro`` every sample at the rails is counted
    (``faults["yaw_rate", "saturated"]`` = injected, its flags = the clipped mask) and fused
    only as the bound ``|omega| >= range``. Bounds vs the unclipped run:
    heading error < 0.6 rad (measured 0.44; unclipped 0.26: the rails hide
    0.82 rad/s for 2 s = 1.6 rad, the heading channel recovers most of it),
    positions within 0.5 m (measured 0.03 m). GPS gated (the IMU-channel gates
    are exercised in the next test).
    """
    t, truth, s, x0 = fast_turns_run()
    clipped, at_rail = faults.saturate(s.yaw_rate, GYRO_RANGE)
    assert at_rail[1:].sum() == 12
    ref = ekf(t, s.gps, s.heading, s.speed, s.yaw_rate, x0=x0, gate=GATE_GPS)
    res = ekf(t, s.gps, s.heading, s.speed, clipped, x0=x0, gate=GATE_GPS, full_scale_gyro=GYRO_RANGE)
    assert_healthy(res)
    assert not rejected(ref).any() and not rejected(res).any()
    assert res.faults["yaw_rate", "saturated"] == at_rail[1:].sum()
    assert np.array_equal(res.faults.flags["yaw_rate", "saturated"], at_rail)
    err = np.abs(np.angle(np.exp(1j * (res.x[:, 2] - truth[:, 2]))))
    assert err.max() < 0.6
    assert np.abs(res.x[:, :2] - ref.x[:, :2]).max() < 0.5
    unaware = ekf(t, s.gps, s.heading, s.speed, clipped, x0=x0, gate=GATE_GPS)
    assert unaware.faults["yaw_rate", "saturated"] == 0  # not told the range: nothing to count


def test_ekf_gate_cannot_lock_out_a_manoeuvre_beyond_q():
    """Finding: with the paper's Q (omega may change 0.04 rad/s per step, v 0.01 m/s) a
    3 rad/s turn is a 75-sigma event, so IMU-channel gates reject the true samples of the
    turn. They are counted (``"outlier"``), and ``reacquire`` ends the lock-out (after 3
    rejections in a row P is inflated by the squared innovation and the next sample fused
    ungated, counted as ``"reacquired"``): every rejection lies within 6 s of a turn start
    and the heading error is back below 0.3 rad 10 s after each turn. Without reacquire the
    filter loses the heading for good in this run (> 100 yaw-rate rejections, asserted).
    Saturated rail samples are never gated."""
    t, truth, s, x0 = fast_turns_run()
    clipped, at_rail = faults.saturate(s.yaw_rate, GYRO_RANGE)
    res = ekf(t, s.gps, s.heading, s.speed, clipped, x0=x0, gate=GATE, full_scale_gyro=GYRO_RANGE)
    assert_healthy(res)
    assert res.faults["yaw_rate", "saturated"] == 12 and not rejected(res)[at_rail, 3].any()
    hit = np.flatnonzero(rejected(res).any(axis=1))
    starts = np.array([120, 300, 450])
    assert hit.size > 0 and np.all(np.min(np.abs(hit[:, None] - starts - 6), axis=1) <= 6)
    assert sum(counts(res, "reacquired")) > 0
    assert counts(res, "outlier") == list(rejected(res).sum(axis=0))
    err = np.abs(np.angle(np.exp(1j * (res.x[:, 2] - truth[:, 2]))))
    for k in starts:
        assert err[k + 20 : k + 100].max() < 0.3
    locked = ekf(t, s.gps, s.heading, s.speed, clipped, x0=x0, gate=GATE, full_scale_gyro=GYRO_RANGE, reacquire=10**9)
    assert locked.faults["yaw_rate", "outlier"] > 100 and sum(counts(locked, "reacquired")) == 0


def test_ekf_estimate_can_leave_the_rails_in_a_long_saturated_turn():
    """A 20 s turn at 3 rad/s read by a 2.18 rad/s gyro: once the heading channel has pushed
    the omega estimate beyond the rail the rail samples are skipped, so the estimate is not
    held at the rail (ends > range, within 0.3 rad/s of the truth)."""
    t, truth, s, x0 = fast_turns_run(seed=4, spin_steps=40)
    clipped, at_rail = faults.saturate(s.yaw_rate, GYRO_RANGE)
    res = ekf(t, s.gps, s.heading, s.speed, clipped, x0=x0, full_scale_gyro=GYRO_RANGE)
    assert_healthy(res)
    assert res.faults["yaw_rate", "saturated"] == at_rail[1:].sum() >= 100
    end_of_turn = 120 + 39
    assert GYRO_RANGE < res.x[end_of_turn, 4] and abs(res.x[end_of_turn, 4] - 3.0) < 0.3


def test_accelerometer_saturation_not_applicable():
    """The planar EKF and dead reckoning take speed (odometry/IMU-derived), not specific
    force: there is no accelerometer channel to clip. Recorded here so the suite's fault
    table is complete."""
    assert "accel" not in planar.ekf.__code__.co_varnames


# --------------------------------------------------------------------------
# Dead reckoning
# --------------------------------------------------------------------------


def test_dead_reckoning_dropouts_gap_and_saturation_are_held_and_counted(clean):
    """DR holds the previous speed and yaw rate over NaN and rail samples; its fault report flags
    them (sample k-1 drives step k, so samples 0..N-1 of N+1 count).

    Bound: on the constant-rate curve with noise-free samples holding is exact,
    so the track equals the fault-free one to 1e-9 m."""
    t, truth, s = curve_run()
    rng = np.random.default_rng(60)
    speed, m_v = faults.dropouts(truth[:, 3], 0.1, rng)
    yaw_rate, m_w = faults.dropouts(truth[:, 4], 0.1, rng)
    yaw_rate, m_gap = faults.gap(yaw_rate, t, 100.0, 30.0)
    pose, held = planar_ekf.dead_reckoning(t, speed, yaw_rate, X0_CURVE)
    assert held["speed", "nan"] == m_v[:-1].sum() and held["yaw_rate", "nan"] == (m_w | m_gap)[:-1].sum()
    assert held_steps(held) == (m_v | m_w | m_gap)[:-1].sum()
    np.testing.assert_allclose(pose, truth[:, :3], rtol=0, atol=1e-9)

    t2, truth2, s2, x0 = fast_turns_run()
    clipped, at_rail = faults.saturate(s2.yaw_rate, GYRO_RANGE)
    _, held = planar_ekf.dead_reckoning(t2, s2.speed, clipped, x0, full_scale_gyro=GYRO_RANGE)
    assert held["yaw_rate", "saturated"] == held_steps(held) == at_rail[:-1].sum() == 12


def test_dead_reckoning_spikes_stated_bounds(clean):
    """DR has no redundancy: an in-range spike is integrated. Speed spikes move the track
    by at most sum |spike| T (heading untouched): asserted. Yaw-rate spikes of 100 sigma
    (5 rad/s) exceed a ±125 deg/s gyro's range, so such a device reads them at the rails:
    told the range, DR holds them and reports them (``("yaw_rate", "saturated")``)."""
    t, truth, s = curve_run()
    rng = np.random.default_rng(70)
    ref, _ = planar_ekf.dead_reckoning(t, s.speed, s.yaw_rate, X0_CURVE)
    speed, m_v = faults.spikes(s.speed, 0.01, SIGMA[3], rng)
    pose, held = planar_ekf.dead_reckoning(t, speed, s.yaw_rate, X0_CURVE)
    bound = np.abs(speed - s.speed)[:-1].sum() * T
    assert not held and m_v.sum() > 0
    assert np.all(np.hypot(*(pose[:, :2] - ref[:, :2]).T) <= bound + 1e-9)
    assert np.array_equal(pose[:, 2], ref[:, 2])
    yaw_rate, m_w = faults.spikes(s.yaw_rate, 0.01, SIGMA[4], rng)
    yaw_rate, at_rail = faults.saturate(yaw_rate, GYRO_RANGE)
    assert np.array_equal(at_rail, m_w)
    _, held = planar_ekf.dead_reckoning(t, s.speed, yaw_rate, X0_CURVE, full_scale_gyro=GYRO_RANGE)
    assert held["yaw_rate", "saturated"] == m_w[:-1].sum() > 0


def test_dead_reckoning_counts_a_clock_jump_and_does_not_integrate_it():
    """A 1-h time-stamp jump between contiguous samples (issue 33: before, a 7.2 km position jump, unreported):
    counted, flagged at the epoch after it, integrated as one typical step, so the track is the jump-free one."""
    t = np.arange(0.0, 100.0, 0.1)
    speed, yaw_rate = np.full(t.size, 1.0), np.full(t.size, 0.01)
    x0 = np.array([0.0, 0.0, 0.3, 1.0, 0.01])
    ref, clean = planar_ekf.dead_reckoning(t, speed, yaw_rate, x0)
    t_jump = t.copy()
    t_jump[500:] += 3600.0
    pose, faults = planar_ekf.dead_reckoning(t_jump, speed, yaw_rate, x0)
    assert clean["clock", "jump"] == 0 and faults["clock", "jump"] == 1
    np.testing.assert_array_equal(np.flatnonzero(faults.flags["clock", "jump"]), [500])
    np.testing.assert_allclose(pose, ref, rtol=0, atol=1e-9)
    integrated, off = planar_ekf.dead_reckoning(t_jump, speed, yaw_rate, x0, max_dt=np.inf)  # detection off
    assert off["clock", "jump"] == 0 and np.hypot(*(integrated[-1, :2] - ref[-1, :2])) > 1000.0
