"""Pedestrian ZUPT/ZARU error-state filter (navlib.papers.pedestrian_ins, paper 004) under faults and bad input.

Data: paper 004's simulation (notebook 05) shortened to a 118-s walk with
stops, a turn and a flight of stairs: ``pedestrian.walk`` seen by an MPU-6050
with the residual biases of a static calibration, a BMP180 barometer and an
HMC5983 magnetometer at 10 Hz. The reference is the fault-free run on the
same data; bounds are on the horizontal error difference to it (the clean
run itself drifts up to 2.3 m while walking and ends within 0.5 m).

Every fault must be reported: the counts and per-sample flags of
``FilterResult.faults`` are compared with the masks that ``navlib.faults``
returns.
"""

import warnings

import numpy as np
import pytest

from navlib import alignment, analysis, atmosphere, attitude, earth, faults, pdr, robust, sensors, timing, trajectory, units
from navlib.filters import zupt, zupt_ins
from navlib.imu import ImuSamples, SensorLimits
from navlib.papers import pedestrian_ins as pd

LLA0 = [units.deg(30.55), units.deg(114.30), 20.0]
DT = 0.01
MODEL = sensors.imu_model("MPU-6050").replace(gyro={"bias": units.deg_per_s(0.05)}, accel={"bias": units.mg(10)})
Leg = trajectory.Leg
LEGS = [Leg(20.0), Leg(15.0, 1.2), Leg(8.0), Leg(15.0, 1.2, turn=np.pi / 2), Leg(10.0), Leg(10.0, 1.2, climb=-1.0), Leg(40.0)]
SIGMA_GYRO = units.deg_per_s(0.005) / np.sqrt(DT)  # MPU-6050 noise per 100-Hz sample (rad/s)
SIGMA_ACCEL = units.ug(400) / np.sqrt(DT)  # (m/s^2)
SPIKE_GYRO, SPIKE_ACCEL = 0.02, 0.5  # spike-test thresholds: safe on a walking shoulder at 100 Hz


@pytest.fixture(scope="module")
def walk():
    ss = np.random.SeedSequence(2016).spawn(3)
    traj = trajectory.walk(LEGS, DT, LLA0, 0.0)
    w, f = trajectory.ideal_imu(traj)
    imu = sensors.simulate_imu(w, f, DT, MODEL, np.random.default_rng(ss[0]))
    B = earth.magnetic_field(30.55, 114.30, 20.0, 2016.5)
    D = float(earth.field_angles(B, deg=False)[0])
    t = traj.time[:-1]
    m = sensors.simulate_magnetometer(
        traj.q_bn[:-1], B, sensors.MagnetometerModel.from_preset("HMC5983"), np.random.default_rng(ss[1])
    ).m_b
    p = sensors.simulate_barometer(
        traj.lla[:-1, 2], t, sensors.BarometerModel.from_preset("BMP180"), np.random.default_rng(ss[2])
    )
    h = 20.0 + atmosphere.baro_height(p, atmosphere.reference_pressure(p, t, 15.0))
    off = np.arange(t.size) % 10 != 0  # 10 Hz aiding sensors
    h[off], m[off] = np.nan, np.nan
    static = zupt.detect_static(imu.w_ib_b, imu.f_b, DT)
    data = dict(traj=traj, t=t, w=imu.w_ib_b, f=imu.f_b, h=h, m=m, B=B, D=D, static=static)
    data["ref"] = run(data)
    data["e_ref"] = herr(data["ref"], traj)
    return data


def run(d, w=None, f=None, dt=DT, static=None, h=None, m=None, limits=None, B_n=None, config=None):
    """The filter on the walk, with any input replaced (and checked for finiteness and a SPD covariance)."""
    w = d["w"] if w is None else w
    f = d["f"] if f is None else f
    static = zupt.detect_static(w, f, DT) if static is None else static
    res = zupt_ins.run_filter(
        ImuSamples(w, f, dt, limits or SensorLimits()),
        zupt_ins.Start(LLA0, d["traj"].q_bn[0]),
        static,
        h_baro=d["h"] if h is None else h,
        m_b=d["m"] if m is None else m,
        aiding=zupt_ins.Aiding(declination=d["D"], B_n=B_n),
        config=config or zupt_ins.FilterConfig(),
    )
    assert np.isfinite(res.nav.lla).all() and np.isfinite(res.nav.q_bn).all() and np.isfinite(res.P_diag).all()
    np.testing.assert_allclose(res.P, res.P.T, rtol=0, atol=1e-12 * np.abs(res.P).max())
    assert np.linalg.eigvalsh(res.P).min() > 0 and res.P_diag.min() > 0
    return res


def herr(res, traj, idx=slice(None)):
    return np.linalg.norm(analysis.horizontal_error(res.nav.lla, traj.lla[idx]), axis=-1)


def flagged(res, *keys):
    """The samples flagged under any of the ``(sensor, kind)`` keys."""
    return np.any([res.faults.flags[key] for key in keys], axis=0)


# ---------------------------------------------------------------- IMU dropouts


def test_random_dropouts_are_held_counted_and_bounded(walk):
    rng = np.random.default_rng(1)
    w, drop = faults.dropouts(walk["w"], 0.1, rng)
    drop[0] = False
    w[0] = walk["w"][0]
    f = walk["f"].copy()
    f[drop] = np.nan
    static = zupt.detect_static(w, f, DT)  # NaN-tolerant: windows with >= half their samples valid
    res = run(walk, w, f, static=static)
    assert res.faults["gyro", "nan"] == res.faults["accel", "nan"] == drop.sum() > 1000
    np.testing.assert_array_equal(flagged(res, ("gyro", "nan")), drop)
    np.testing.assert_array_equal(flagged(res, ("zupt", "refused")), drop & static)
    assert res.faults["zupt", "refused"] == (drop & static).sum()
    assert res.zupt_updates > 0.8 * walk["ref"].zupt_updates
    # Stated bound: the held samples add a random walk of the MPU-6050 noise while walking and cost ~10 %
    # of the ZUPTs: within 6 m of the clean run at any time (measured 3.6 m, while walking) and within
    # 2.5 m at the end, after the last stance (measured 1.4 m).
    d = np.abs(herr(res, walk["traj"]) - walk["e_ref"])
    assert d.max() < 6.0 and d[-1] < 2.5, (d.max(), d[-1])


def test_30s_gap_in_a_stand_is_held_counted_and_recovered(walk):
    w, gap = faults.gap(walk["w"], walk["t"], 82.0, 30.0)  # inside the final 40-s stand
    f = walk["f"].copy()
    f[gap] = np.nan
    res = run(walk, w, f)
    assert res.faults["gyro", "nan"] == gap.sum() == 3000
    np.testing.assert_array_equal(flagged(res, ("gyro", "nan"), ("accel", "nan")), gap)
    # The detector sees no data (no stance) and the held sample's noise (0.04 m/s^2, 0.05 deg/s) is
    # integrated for 30 s: ~130 m at the end of the gap. The covariance admits it (held samples inflate
    # the process noise by hold_*_sigma): the position sigma then exceeds the actual error. The ZUPTs of
    # the remaining 6 s of stand pull velocity and, through the correlations, position back.
    # Stated bound at the end: within 3 m of the clean run (measured 1.1 m) and velocity < 0.05 m/s
    # (measured 0.001 m/s).
    end = np.flatnonzero(gap)[-1] + 1
    e = herr(res, walk["traj"])
    assert np.sqrt(res.P_diag[end, :2]).min() > e[end] > 10.0, (np.sqrt(res.P_diag[end, :2]), e[end])
    assert abs(e[-1] - walk["e_ref"][-1]) < 3.0, (e[-1], walk["e_ref"][-1])
    assert np.abs(res.nav.vel_n[-1]).max() < 0.05


def test_30s_gap_while_walking_is_reported_not_hidden(walk):
    w, gap = faults.gap(walk["w"], walk["t"], 22.0, 30.0)  # walking, stop, walking
    f = walk["f"].copy()
    f[gap] = np.nan
    res = run(walk, w, f)
    # Holding a walking sample for 30 s cannot be right (the gait is not constant): navigation is lost
    # (measured: 2.3 km off at the end). Not bounded, so it must be reported: every held sample is
    # counted and flagged, and the covariance says so -- velocity sigma at the end of the gap above
    # 30 m/s (measured 70 m/s), and the later stances fail the NIS gate (zupt outlier, reacquired).
    assert res.faults["gyro", "nan"] == 3000
    np.testing.assert_array_equal(flagged(res, ("gyro", "nan")), gap)
    end = np.flatnonzero(gap)[-1] + 1
    assert np.sqrt(res.P_diag[end, 3:5]).min() > 30.0
    assert res.faults["zupt", "reacquired"] > 0 and res.faults["zupt", "outlier"] > walk["ref"].faults["zupt", "outlier"]


def test_first_sample_must_be_valid(walk):
    w = walk["w"].copy()
    w[0] = np.nan
    with pytest.raises(ValueError, match="^imu: expected a valid first sample"):
        run(walk, w, static=walk["static"])


# ---------------------------------------------------------------- IMU spikes


def _spiky(walk, seed=3):
    rng = np.random.default_rng(seed)
    w, hw = faults.spikes(walk["w"], 0.01, SIGMA_GYRO, rng)
    f, hf = faults.spikes(walk["f"], 0.01, SIGMA_ACCEL, rng)
    return w, f, hw | hf


def test_despike_finds_the_spikes_and_the_pipeline_stays_near_the_clean_run(walk):
    w, f, hit = _spiky(walk)
    wd, fd, found = robust.despike(w, f, SPIKE_GYRO, SPIKE_ACCEL)
    # No false alarm; misses only where two spikes are adjacent (each hides the other) or at the ends.
    assert not (found & ~hit).any()
    assert found.sum() >= 0.95 * hit.sum() and hit.sum() > 150, (found.sum(), hit.sum())
    assert not robust.despike(walk["w"], walk["f"], SPIKE_GYRO, SPIKE_ACCEL)[2].any()  # clean data: none
    res = run(walk, wd, fd)  # despike -> detect_static -> run_filter (spikes held)
    assert res.faults["gyro", "nan"] == res.faults["accel", "nan"] == found.sum()
    # Stated bound: the undetected adjacent spikes (2 of 235) and the held samples: within 3 m of the
    # clean run (measured 1.9 m) and 1.5 m at the end (measured 0.8 m). Without the spike test the detector
    # loses half of the stances (a 4 m/s^2 spike raises std|f| over its 0.5-s window) and the error
    # doubles: shown by the counters, not bounded.
    d = np.abs(herr(res, walk["traj"]) - walk["e_ref"])
    assert d.max() < 3.0 and d[-1] < 1.5, (d.max(), d[-1])
    raw = run(walk, w, f)
    assert raw.zupt_updates < 0.7 * walk["ref"].zupt_updates


def test_spike_test_inside_the_filter_flags_the_same_samples(walk):
    w, f, hit = _spiky(walk)
    found = robust.despike(w, f, SPIKE_GYRO, SPIKE_ACCEL)[2]
    limits = SensorLimits(spike_gyro=SPIKE_GYRO, spike_accel=SPIKE_ACCEL)
    res = run(walk, w, f, static=zupt.detect_static(*robust.despike(w, f, SPIKE_GYRO, SPIKE_ACCEL)[:2], DT), limits=limits)
    np.testing.assert_array_equal(flagged(res, ("gyro", "spike"), ("accel", "spike")), found)
    assert res.faults["gyro", "spike"] + res.faults["accel", "spike"] == found.sum()
    assert res.faults["gyro", "nan"] == res.faults["accel", "nan"] == 0
    assert not (res.faults.flags["zupt", "refused"] & ~found).any()  # only the spikes are refused
    clean = run(walk, limits=limits)
    assert clean.faults["gyro", "spike"] == clean.faults["accel", "spike"] == 0  # no false alarm on the walk


# ---------------------------------------------------------------- saturation


def test_saturated_samples_are_counted_and_never_used_for_zupt(walk):
    gyro_fs, accel_fs = 0.3, 12.0  # a range the walk exceeds (turn, gait peaks)
    w, cw = faults.saturate(walk["w"], gyro_fs)
    f, cf = faults.saturate(walk["f"], accel_fs)
    res = run(walk, w, f, limits=SensorLimits(full_scale_gyro=gyro_fs, full_scale_accel=accel_fs))
    assert res.faults["gyro", "saturated"] + res.faults["accel", "saturated"] >= (cw | cf).sum() > 500
    np.testing.assert_array_equal(flagged(res, ("gyro", "saturated")), cw)
    np.testing.assert_array_equal(flagged(res, ("accel", "saturated")), cf)
    # Stated bound: the clipped gait peaks (< 1.5 m/s^2 over ~10 % of the walking samples) bias the
    # velocity while walking only; ZUPTs at the next stop remove it: within 10 m of the clean run during
    # the walk (measured 5.7 m) and 1.5 m at the end (measured 0.6 m).
    d = np.abs(herr(res, walk["traj"]) - walk["e_ref"])
    assert d.max() < 10.0 and d[-1] < 1.5, (d.max(), d[-1])
    # A range below gravity: every sample is at the rails, none may feed ZUPT/ZARU.
    f_low, low = faults.saturate(walk["f"], 9.0)
    with pytest.warns(RuntimeWarning, match="no ZUPT/ZARU update"):
        res = run(walk, walk["w"], f_low, static=walk["static"], limits=SensorLimits(full_scale_gyro=10.0, full_scale_accel=9.0))
    assert res.zupt_updates == 0 and res.faults["accel", "saturated"] == low.sum()
    assert low[walk["static"]].all()
    assert res.faults["zupt", "refused"] == walk["static"].sum()
    # Without full scales nothing is treated as clipped (the paper's filter).
    raw = run(walk, w, f)
    assert raw.faults["gyro", "saturated"] == raw.faults["accel", "saturated"] == 0


def test_saturation_counts_match_the_sensor_model(walk):
    traj = walk["traj"]
    w, f = trajectory.ideal_imu(traj)
    model = MODEL.replace(gyro={"full_scale": 0.3}, accel={"full_scale": 12.0})
    imu = sensors.simulate_imu(w, f, DT, model, np.random.default_rng(4))
    res = run(walk, imu.w_ib_b, imu.f_b, limits=SensorLimits(full_scale_gyro=0.3, full_scale_accel=12.0))
    # the sensor model counts clipped components; the filter counts samples with any component at the rails
    assert (np.abs(imu.w_ib_b) >= 0.3).sum() == imu.gyro_saturated > 0
    assert (np.abs(imu.f_b) >= 12.0).sum() == imu.accel_saturated > 0
    for sensor, x, fs in (("gyro", imu.w_ib_b, 0.3), ("accel", imu.f_b, 12.0)):
        rails = (np.abs(x) >= fs).any(-1)
        assert res.faults[sensor, "saturated"] == rails.sum()
        np.testing.assert_array_equal(flagged(res, (sensor, "saturated")), rails)


# ---------------------------------------------------------------- barometer and magnetometer


def test_baro_spikes_are_gated_and_dropouts_coast(walk):
    rng = np.random.default_rng(5)
    h, hit = faults.spikes(walk["h"], 0.01, units.hpa(0.06) * 8.3, rng)  # 100 x 0.5 m (BMP180)
    hit &= np.isfinite(walk["h"])
    res = run(walk, h=h)
    first = np.flatnonzero(np.isfinite(walk["h"]))[0]  # the tracker starts on it
    assert res.faults["baro", "outlier"] == hit[first + 1 :].sum() > 5 and res.faults["baro", "reacquired"] == 0
    assert res.baro_aidings == walk["ref"].baro_aidings - (hit & ~walk["static"]).sum()
    # Every spike gated: the height differs from the clean run only by the skipped resets (the next
    # reading comes 0.1 s later). Stated bound 0.25 m, half a BMP180 sigma (measured 0.10 m); a 50-m spike
    # let through would move it by 10 m (alpha = 0.2).
    dz = np.abs(res.nav.lla[:, 2] - walk["ref"].nav.lla[:, 2]).max()
    assert dz < 0.25, dz
    # dropouts (10 %) and a 30-s gap over the stairs: the tracker coasts; NaN is "no reading", not a fault
    hd, _ = faults.dropouts(walk["h"], 0.1, rng)
    hg, _ = faults.gap(hd, walk["t"], 50.0, 30.0)
    res = run(walk, h=hg)
    ez = np.abs(res.nav.lla[:, 2] - walk["traj"].lla[:, 2]).max()
    ez_ref = np.abs(walk["ref"].nav.lla[:, 2] - walk["traj"].lla[:, 2]).max()
    # Stated bound: 30 s of walking without the barometer leaves the INS height free, and the gap covers
    # the 1-m stairs descent: 1/2 x 0.01 m/s^2 (residual vertical accelerometer error) x (30 s)^2 + 1 m
    # = 5.5 m; measured 3.1 m. Once readings return the resets restore it: final height within 1 m.
    assert ez < 5.5, (ez, ez_ref)
    assert abs(res.nav.lla[-1, 2] - walk["traj"].lla[-1, 2]) < 1.0
    assert res.baro_aidings < walk["ref"].baro_aidings


def test_baro_step_reinitialises_the_tracker(walk):
    h = walk["h"] + np.where(walk["t"] > 60.0, 20.0, 0.0)  # a real 20-m jump (e.g. a new datum)
    res = run(walk, h=h)
    assert res.faults["baro", "reacquired"] == 1 and res.faults["baro", "outlier"] == zupt_ins.Gates().max_rejected


def test_mag_spikes_are_gated_by_field_and_dip(walk):
    rng = np.random.default_rng(6)
    m, hit = faults.spikes(walk["m"], 0.01, 0.2, rng)  # 100 x 2 mG = 20 uT per axis
    used = np.isfinite(walk["m"][:, 0]) & ~walk["static"]  # compass samples used (walking)
    cfg = zupt_ins.FilterConfig(gates=zupt_ins.Gates(mag_field=3.0, mag_dip=np.deg2rad(3.0)))
    clean = run(walk, B_n=walk["B"], config=cfg)
    assert clean.faults["mag", "outlier"] == 0
    res = run(walk, m=m, B_n=walk["B"], config=cfg)
    # A +-20 uT spike on every axis changes |B| (~50 uT) or the dip by far more than 3 uT / 3 deg:
    # every spike on a used sample is gated.
    assert res.faults["mag", "outlier"] == (hit & used).sum() > 0
    assert res.mag_aidings == clean.mag_aidings - (hit & used).sum()
    # Stated bound: the gated resets are skipped (the next one is 0.1 s later): heading within 1.5 deg of
    # the clean run, below the 2-deg compass sigma (measured 0.8 deg).
    hdg = np.abs(attitude.wrap_pi(res.nav.hpr[:, 0] - clean.nav.hpr[:, 0])).max()
    assert hdg < np.deg2rad(1.5), np.rad2deg(hdg)
    # without the gate a spike resets the heading by tens of degrees: visible, not silent, only in the
    # error -- which is why the docstring tells users to give B_n
    raw = run(walk, m=m)
    assert np.abs(attitude.wrap_pi(raw.nav.hpr[:, 0] - walk["traj"].hpr[:, 0])).max() > np.deg2rad(10)


def test_mag_dropouts_and_gap(walk):
    rng = np.random.default_rng(7)
    md, _ = faults.dropouts(walk["m"], 0.1, rng)
    mg, _ = faults.gap(md, walk["t"], 30.0, 30.0)
    res = run(walk, m=mg)
    assert res.mag_aidings < walk["ref"].mag_aidings
    # Stated bound: the gyro carries the heading through the 30-s gap (0.05 deg/s residual bias, partly
    # removed by ZARU: <= 1.5 deg) from the last compass reset (2-deg sigma): heading within 4 deg of truth
    # (measured 2.4 deg), position within 2 m of the clean run (measured 0.7 m).
    hdg = np.abs(attitude.wrap_pi(res.nav.hpr[:, 0] - walk["traj"].hpr[:, 0])).max()
    assert hdg < np.deg2rad(4.0), np.rad2deg(hdg)
    assert np.abs(herr(res, walk["traj"]) - walk["e_ref"]).max() < 2.0


# ---------------------------------------------------------------- timing


def test_per_sample_dt_equal_to_the_scalar_is_bit_identical(walk):
    res = run(walk, dt=np.full(len(walk["w"]), DT))
    np.testing.assert_array_equal(res.nav.lla, walk["ref"].nav.lla)
    assert res.faults.counts == walk["ref"].faults.counts and res.zupt_updates == walk["ref"].zupt_updates


def test_irregular_sampling_is_integrated_as_well_as_regular():
    fine = 0.002
    traj = trajectory.walk(LEGS, fine, LLA0, 0.0)
    w, f = trajectory.ideal_imu(traj)
    imu = sensors.simulate_imu(w, f, fine, MODEL, np.random.default_rng(8))  # 500 Hz, averaged below
    stance = trajectory.stance_mask(LEGS, fine)[:-1]
    rng = np.random.default_rng(9)
    err = {}
    for name, sizes in (("regular", np.full(len(w) // 5, 5)), ("irregular", rng.integers(4, 7, len(w) // 4))):
        edges = np.concatenate([[0], np.cumsum(sizes)])
        edges = edges[edges <= len(w)]
        n = np.diff(edges)
        W = np.add.reduceat(imu.w_ib_b, edges[:-1], axis=0)[: n.size] / n[:, None]
        F = np.add.reduceat(imu.f_b, edges[:-1], axis=0)[: n.size] / n[:, None]
        dts = n * fine  # 10 ms +-20 %
        start = zupt_ins.Start(LLA0, traj.q_bn[0])
        res = zupt_ins.run_filter(ImuSamples(W, F, dts), start, stance[edges[:-1]])
        np.testing.assert_allclose(res.nav.time, traj.time[edges], atol=1e-9)
        err[name] = herr(res, traj, edges)
        if name == "irregular":
            wrong = zupt_ins.run_filter(ImuSamples(W, F, DT), start, stance[edges[:-1]])
            err["as if regular"] = herr(wrong, traj, edges)
    # Stated bound: with the intervals given, irregular sampling does as well as regular sampling
    # (max error within 10 % + 0.5 m; measured 2.55 vs 2.59 m, INS drift between stops), while
    # ignoring the irregularity is much worse (measured 16.5 m).
    assert err["irregular"].max() < 1.1 * err["regular"].max() + 0.5, (err["irregular"].max(), err["regular"].max())
    assert err["as if regular"].max() > 3 * err["irregular"].max()


def test_out_of_order_and_duplicated_timestamps_via_sanitize(walk):
    t, w, f, h, m, static = walk["t"], walk["w"], walk["f"], walk["h"], walk["m"], walk["static"]
    ts, order = faults.swap_timestamps(t, 0.01, np.random.default_rng(10))
    static = static.astype(float)  # sanitize takes numeric series
    t2, w2, f2, h2, m2, s2, rep = timing.sanitize(ts, w[order], f[order], h[order], m[order], static[order])
    assert rep.n_out_of_order > 50 and rep.n_duplicate == 0
    dts = timing.intervals(np.r_[t2, t2[-1] + DT], len(t2))
    res = run(walk, w2, f2, dt=dts, static=s2.astype(bool), h=h2, m=m2)
    np.testing.assert_allclose(res.nav.lla, walk["ref"].nav.lla, rtol=0, atol=1e-9)  # order restored
    td, hit = faults.duplicate_timestamps(t, 0.01, np.random.default_rng(11))
    t3, w3, f3, h3, m3, s3, rep = timing.sanitize(td, w, f, h, m, static)
    # a repeat right after a repeat copies a different stamp, so duplicates <= hits (all counted)
    assert 50 < rep.n_duplicate <= hit.sum() and len(t3) == len(t) - rep.n_duplicate
    hit = np.isin(np.arange(len(t)), np.flatnonzero(np.diff(td) == 0) + 1)  # the samples sanitize dropped
    dts = timing.intervals(np.r_[t3, t3[-1] + DT], len(t3))
    res = run(walk, w3, f3, dt=dts, static=s3.astype(bool), h=h3, m=m3)
    keep = np.r_[~hit, True]
    d = np.abs(herr(res, walk["traj"], keep) - walk["e_ref"][keep])
    # Stated bound: 1 % of the samples dropped and their intervals given to the previous sample: within
    # 2 m of the clean run (measured 0.6 m).
    assert d.max() < 2.0, d.max()


def test_time_jump_is_held_counted_and_the_filter_goes_on(walk):
    """A clock step of one hour in one interval (campaign: ran to the end, then raised 'lla: expected latitudes')."""
    n = len(walk["w"])
    for k, bound_max, bound_end in ((8200, 0.5, 0.5), (2500, 6.0, 1.5)):  # in the final stand; walking
        dt = np.full(n, DT)
        dt[k] = 3600.0
        res = run(walk, dt=dt)  # finite, SPD covariance (run checks both)
        assert res.faults["clock", "jump"] == 1
        np.testing.assert_array_equal(res.faults.flags["clock", "jump"], np.arange(n) == k)
        assert res.nav.time[-1] == pytest.approx(walk["ref"].nav.time[-1] + 3600.0 - DT)
        np.testing.assert_array_equal(res.nav.lla[: k + 1], walk["ref"].nav.lla[: k + 1])  # untouched before it
        np.testing.assert_array_equal(res.nav.lla[k + 1, :2], res.nav.lla[k, :2])  # held over it
        # the covariance grows by the process noise of the hour: horizontal velocity sigma >= 0.02 sqrt(3600)
        # = 1.2 m/s (the vertical one is reset by the barometer while walking)
        assert np.sqrt(res.P_diag[k + 1, 3:5]).min() >= zupt_ins.ProcessNoise().accel * 60.0
        # Stated bounds, horizontal error difference to the clean run: a jump in a stand loses nothing
        # (0.5 m; measured 0.10 m, 0.06 m at the end); one while walking holds the walker for one sample
        # and the inflated covariance lets the next stance pull the INS back (6 m at most, measured 3.6 m;
        # 1.5 m at the end, measured 0.7 m).
        d = np.abs(herr(res, walk["traj"]) - walk["e_ref"])
        assert d.max() < bound_max and d[-1] < bound_end, (k, d.max(), d[-1])
    # the threshold is SensorLimits.max_dt: inf would integrate the hour (a turn of 1500 rad in one sample: refused)
    with pytest.raises(ValueError, match="^dt: the gyro turns"):
        run(walk, dt=dt, limits=SensorLimits(max_dt=np.inf))


def test_free_fall_in_a_stand_is_held_counted_and_never_used_for_zupt(walk):
    """One second of |f| = 0 in the final stand, no barometer (campaign: 13.2 m height error, not reported)."""
    n = len(walk["w"])
    fall = (np.arange(n) >= 8200) & (np.arange(n) < 8300)
    f = np.where(fall[:, None], 0.0, walk["f"])
    no_baro = np.full(n, np.nan)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        clean = run(walk, h=no_baro, static=walk["static"])
    dz_clean = clean.nav.lla[:, 2] - walk["traj"].lla[:, 2]
    for static in (walk["static"], None):  # a given stance mask (the fall inside it); the detector's
        res = run(walk, f=f, h=no_baro, static=static)
        assert res.faults["accel", "freefall"] == fall.sum()
        np.testing.assert_array_equal(flagged(res, ("accel", "freefall")), fall)
        st = walk["static"] if static is not None else zupt.detect_static(walk["w"], f, DT)
        np.testing.assert_array_equal(flagged(res, ("zupt", "refused")), fall & st)  # never a ZUPT
        # Stated bound: the held accelerometer reads the stance's g, so the height stays within 0.1 m of
        # the clean run's (measured 0.03 m); integrated, the fall costs 12.9 m here (13.2 m in the campaign).
        dz = res.nav.lla[:, 2] - walk["traj"].lla[:, 2]
        assert np.abs(dz - dz_clean).max() < 0.1, np.abs(dz - dz_clean).max()
    raw = run(walk, f=f, h=no_baro, limits=SensorLimits(freefall_accel=0.0))  # test off
    assert raw.faults["accel", "freefall"] == 0 and abs(raw.nav.lla[-1, 2] - walk["traj"].lla[-1, 2]) > 10.0


def test_free_fall_needs_a_run_of_freefall_time(walk):
    """No false alarm on the walk (|f| >= 6.5 m/s^2); a 0.03-s dip is left to the spike test, 0.05 s is held."""
    assert walk["ref"].faults["accel", "freefall"] == 0 and np.linalg.norm(walk["f"], axis=-1).min() > 6.0
    for length, held in ((3, 0), (5, 5)):
        f = walk["f"].copy()
        f[8200 : 8200 + length] = 0.0
        assert run(walk, f=f).faults["accel", "freefall"] == held
    f = walk["f"].copy()
    f[0] = 0.0
    with pytest.raises(ValueError, match="^imu: expected a valid first sample"):
        run(walk, f=f, limits=SensorLimits(freefall_time=DT / 2))


# ---------------------------------------------------------------- bad input (API fuzzing)

Z3 = np.zeros((50, 3))
F3 = np.tile([0.0, 0.0, 9.79], (50, 1))
ST = np.ones(50, bool)
Q1 = [1.0, 0.0, 0.0, 0.0]
CPLX = np.zeros((50, 3), complex)
OBJ = np.array([[None, 0.0, 0.0]] * 50, dtype=object)
IMU = ImuSamples(Z3, F3, DT)
START = zupt_ins.Start(LLA0, Q1)


def RF(**kw):
    return zupt_ins.run_filter(**{**dict(imu=IMU, start=START, static=ST), **kw})


B0 = np.array([0.0, 30.0, -40.0])

FUZZ = [
    ("ned_to_enu_dcm", "C_ned", lambda: attitude.ned_to_enu_dcm(np.eye(3, dtype=complex))),
    ("ned_to_enu_dcm", "C_ned", lambda: attitude.ned_to_enu_dcm(np.zeros((2, 2)))),
    ("ned_to_enu_dcm", "C_ned", lambda: attitude.ned_to_enu_dcm(np.full((3, 3), np.nan))),
    ("Leg", "duration", lambda: trajectory.Leg(np.inf)),
    ("Leg", "speed", lambda: trajectory.Leg(1.0, "fast")),
    ("Leg", "turn", lambda: trajectory.Leg(1.0, 1.0, turn=np.nan)),
    ("Gait", "bounce", lambda: trajectory.Gait(bounce=-0.1)),
    ("Gait", "lean", lambda: trajectory.Gait(lean=1j)),
    ("walk", "legs", lambda: trajectory.walk([1.0], DT, LLA0, 0.0)),
    ("walk", "dt", lambda: trajectory.walk([trajectory.Leg(1.0)], 0.0, LLA0, 0.0)),
    ("walk", "heading0", lambda: trajectory.walk([trajectory.Leg(1.0)], DT, LLA0, np.nan)),
    ("walk", "gait", lambda: trajectory.walk([trajectory.Leg(1.0)], DT, LLA0, 0.0, gait=None)),
    ("walk", "lla0", lambda: trajectory.walk([trajectory.Leg(1.0)], DT, [0.5, 0.5], 0.0)),
    ("stance_mask", "legs", lambda: trajectory.stance_mask("abc", DT)),
    ("stance_mask", "gait", lambda: trajectory.stance_mask([trajectory.Leg(1.0)], DT, gait=1.0)),
    ("carpark_legs", "speed", lambda: pd.carpark_legs(speed=-1.0)),
    ("carpark_legs", "stops", lambda: pd.carpark_legs(stops=[])),
    ("carpark_legs", "n_loops", lambda: pd.carpark_legs(n_loops=0)),
    ("floor_test_legs", "stand", lambda: pd.floor_test_legs(stand=np.inf)),
    ("floor_test_legs", "n_round_trips", lambda: pd.floor_test_legs(n_round_trips=1.5)),
    ("detect_static", "w_ib_b", lambda: zupt.detect_static(CPLX, F3, DT)),
    ("detect_static", "w_ib_b", lambda: zupt.detect_static(np.zeros((0, 3)), np.zeros((0, 3)), DT)),
    ("detect_static", "f_b", lambda: zupt.detect_static(Z3, OBJ, DT)),
    ("detect_static", "thresholds", lambda: zupt.detect_static(Z3, F3, DT, thresholds=(0.1, 0.1))),
    ("detect_static", "g", lambda: zupt.detect_static(Z3, F3, DT, g=np.nan)),
    ("detect_static", "gyro_bias", lambda: zupt.detect_static(Z3, F3, DT, gyro_bias=[0.0, np.inf, 0.0])),
    ("detection_rates", "detected", lambda: analysis.detection_rates(np.ones(5), np.r_[True, False, True, True, True])),
    ("level", "f_b", lambda: alignment.level([0.0, 0.0, np.nan])),
    ("level", "f_b", lambda: alignment.level(np.zeros(3, complex))),
    ("static_gyro_bias", "w_ib_b", lambda: alignment.static_gyro_bias(np.full((5, 3), np.nan), np.eye(3), 0.5)),
    ("static_gyro_bias", "C_bn", lambda: alignment.static_gyro_bias(Z3, np.eye(2), 0.5)),
    ("static_gyro_bias", "lat", lambda: alignment.static_gyro_bias(Z3, np.eye(3), 3.0)),
    ("magnetic_heading", "m_b", lambda: alignment.magnetic_heading(np.zeros(3, complex) + 1, 0.0, 0.0)),
    ("magnetic_heading", "pitch", lambda: alignment.magnetic_heading(B0, np.inf, 0.0)),
    ("magnetic_heading", "declination", lambda: alignment.magnetic_heading(B0, 0.0, 0.0, declination="east")),
    ("tilt_compensate_ned", "H_b", lambda: pd.tilt_compensate_ned([1.0, 2.0], 0.0, 0.0)),
    ("tilt_compensate_ned", "roll", lambda: pd.tilt_compensate_ned(B0, 0.0, np.nan)),
    ("tilt_compensate_printed", "H_b", lambda: pd.tilt_compensate_printed(np.full(3, np.inf), 0.0, 0.0)),
    ("tilt_compensate_printed", "pitch", lambda: pd.tilt_compensate_printed(B0, "up", 0.0)),
    ("heading_from_horizontal", "H_X", lambda: pd.heading_from_horizontal(np.nan, 1.0)),
    ("heading_from_horizontal", "H_Y", lambda: pd.heading_from_horizontal(1.0, 1j)),
    ("baro_height", "p", lambda: atmosphere.baro_height([], 1e5)),
    ("baro_height", "p_ref", lambda: atmosphere.baro_height(1e5, np.inf)),
    ("baro_height", "temperature", lambda: atmosphere.baro_height(1e5, 1e5, temperature=np.nan)),
    ("reference_pressure", "p", lambda: atmosphere.reference_pressure([1e5, 1e5], [0.0], 1.0)),
    ("reference_pressure", "time", lambda: atmosphere.reference_pressure([1e5, 1e5], [0.0, np.nan], 1.0)),
    ("reference_pressure", "until", lambda: atmosphere.reference_pressure([1e5, 1e5], [0.0, 1.0], -1.0)),
    ("classify_floor", "h", lambda: atmosphere.classify_floor(np.nan)),
    ("classify_floor", "floor_height", lambda: atmosphere.classify_floor(1.0, floor_height=-3.0)),
    ("segment_floors", "static", lambda: atmosphere.segment_floors(np.zeros(5), np.ones(4, bool))),
    ("segment_floors", "h", lambda: atmosphere.segment_floors(np.full(5, np.inf), np.ones(5, bool))),
    ("segments", "mask", lambda: analysis.segments(np.ones(5))),
    ("hvac_pressure_steps", "time", lambda: pd.hvac_pressure_steps([np.nan], [1.0], np.random.default_rng(0))),
    ("hvac_pressure_steps", "amplitude", lambda: pd.hvac_pressure_steps([0.0], [1.0], np.random.default_rng(0), -1.0)),
    ("hvac_pressure_steps", "rng", lambda: pd.hvac_pressure_steps([0.0], [1.0], np.random.RandomState(0))),
    ("despike", "w_ib_b", lambda: robust.despike(CPLX, F3, 0.1, 1.0)),
    ("despike", "f_b", lambda: robust.despike(Z3, F3[:10], 0.1, 1.0)),
    ("despike", "spike_gyro", lambda: robust.despike(Z3, F3, 0.0, 1.0)),
    ("despike", "spike_accel", lambda: robust.despike(Z3, F3, 0.1, np.nan)),
    ("error_state_matrix", "C_bn", lambda: zupt.error_state_matrix(np.ones((3, 3)), [0, 0, 9.8])),
    ("error_state_matrix", "f_b", lambda: zupt.error_state_matrix(np.eye(3), [0, 0, np.nan])),
    ("error_model_fd", "eps", lambda: zupt.error_model_fd(np.eye(3), [0, 0, 9.8], eps=0.0)),
    ("error_model_fd", "f_b", lambda: zupt.error_model_fd(np.eye(3), "abc")),
    ("zupt_zaru_matrix", "C_bn", lambda: zupt.zupt_zaru_matrix(np.full((3, 3), np.nan), np.zeros(3))),
    ("zupt_zaru_matrix", "w_ie_n", lambda: zupt.zupt_zaru_matrix(np.eye(3), [0.0, 1j, 0.0])),
    ("zupt_zaru_innovation", "vel_n", lambda: zupt.zupt_zaru_innovation([np.nan] * 3, Z3[0], Z3[0], np.eye(3), Z3[0])),
    ("zupt_zaru_innovation", "b_g", lambda: zupt.zupt_zaru_innovation(Z3[0], Z3[0], [0, 0], np.eye(3), Z3[0])),
    ("simple_covariance_update", "P", lambda: pd.simple_covariance_update(np.full((2, 2), np.nan), np.eye(2), np.eye(2))),
    ("simple_covariance_update", "H", lambda: pd.simple_covariance_update(np.eye(2), np.eye(3), np.eye(2))),
    ("Start", "lla", lambda: zupt_ins.Start([np.pi, 0.0, 0.0], Q1)),
    ("Start", "lla", lambda: zupt_ins.Start([0.5, 0.0], Q1)),
    ("Start", "q_bn", lambda: zupt_ins.Start(LLA0, [0.0, 0.0, 0.0, 0.0])),
    ("Start", "q_bn", lambda: zupt_ins.Start(LLA0, np.array(Q1, complex))),
    ("Start", "vel_n", lambda: zupt_ins.Start(LLA0, Q1, vel_n=[0.0, np.nan, 0.0])),
    ("Start", "accel_bias", lambda: zupt_ins.Start(LLA0, Q1, accel_bias=[0.0, 0.0])),
    ("Start", "gyro_bias", lambda: zupt_ins.Start(LLA0, Q1, gyro_bias=[0.0, 0.0, np.inf])),
    ("Start", "time", lambda: zupt_ins.Start(LLA0, Q1, time=np.nan)),
    ("Aiding", "walk", lambda: zupt_ins.Aiding(walk=None)),
    ("Aiding", "zupt", lambda: zupt_ins.Aiding(zupt=1)),
    ("Aiding", "declination", lambda: zupt_ins.Aiding(declination=np.nan)),
    ("Aiding", "B_n", lambda: zupt_ins.Aiding(B_n=[0.0, np.nan, 1.0])),
    ("ProcessNoise", "accel", lambda: zupt_ins.ProcessNoise(accel=0.0)),
    ("ProcessNoise", "held_gyro", lambda: zupt_ins.ProcessNoise(held_gyro=np.inf)),
    ("MeasurementNoise", "baro", lambda: zupt_ins.MeasurementNoise(baro=np.inf)),
    ("MeasurementNoise", "zupt", lambda: zupt_ins.MeasurementNoise(zupt="low")),
    ("InitialSigma", "pos", lambda: zupt_ins.InitialSigma(pos=-1.0)),
    ("Gates", "zupt", lambda: zupt_ins.Gates(zupt=np.nan)),
    ("Gates", "baro", lambda: zupt_ins.Gates(baro=-1.0)),
    ("Gates", "max_rejected", lambda: zupt_ins.Gates(max_rejected=True)),
    ("Gates", "mag_dip", lambda: zupt_ins.Gates(mag_dip=0.0)),
    ("BaroTracker", "alpha", lambda: zupt_ins.BaroTracker(alpha=np.nan)),
    ("FilterConfig", "gates", lambda: zupt_ins.FilterConfig(gates={"zupt": 1.0})),
    ("FilterConfig", "update_rate", lambda: zupt_ins.FilterConfig(update_rate=0.0)),
    ("run_filter", "imu", lambda: RF(imu=Z3)),
    ("run_filter", "imu", lambda: RF(imu=ImuSamples(np.zeros((2, 50, 3)), np.tile(F3, (2, 1, 1)), DT))),
    ("run_filter", "imu", lambda: RF(imu=ImuSamples(Z3, F3, DT, SensorLimits(max_dt=DT / 2)))),  # every sample a jump
    ("run_filter", "imu", lambda: RF(imu=ImuSamples(np.r_[[[np.nan] * 3], Z3[1:]], F3, DT))),  # first sample held
    ("run_filter", "start", lambda: RF(start=LLA0)),
    ("run_filter", "static", lambda: RF(static=np.ones(50))),
    ("run_filter", "static", lambda: RF(static=ST[1:])),
    ("run_filter", "h_baro", lambda: RF(h_baro=np.full(50, np.inf))),
    ("run_filter", "h_baro", lambda: RF(h_baro=np.zeros(49))),
    ("run_filter", "m_b", lambda: RF(m_b=np.full((50, 3), 1j))),
    ("run_filter", "m_b", lambda: RF(m_b=np.zeros((50, 3)))),
    ("run_filter", "m_b", lambda: RF(m_b=np.full((50, 3), np.inf))),
    ("run_filter", "aiding", lambda: RF(aiding="reset")),
    ("run_filter", "config", lambda: RF(config={"gate": 1.0})),
    ("run_filter", "ellipsoid", lambda: RF(ellipsoid="WGS84")),
    ("detect_steps", "f_b", lambda: pdr.detect_steps(np.full((100, 3), np.nan), DT)),
    ("detect_steps", "threshold", lambda: pdr.detect_steps(F3, DT, threshold=0.0)),
    ("detect_steps", "g", lambda: pdr.detect_steps(np.tile(F3, (4, 1)), DT, g=-9.8)),
    ("weinberg_step_length", "peak_to_peak", lambda: pdr.weinberg_step_length([-1.0])),
    ("weinberg_step_length", "peak_to_peak", lambda: pdr.weinberg_step_length([np.nan])),
    ("pdr", "step_lengths", lambda: pdr.pdr([1j], [0.0])),
    ("pdr", "start_en", lambda: pdr.pdr([1.0], [0.0], start_en=[0.0])),
    ("pdr_headings", "m_b", lambda: pdr.pdr_headings(F3, np.full((49, 3), 1.0), [10, 20])),
    ("pdr_headings", "step_index", lambda: pdr.pdr_headings(F3, np.ones((50, 3)), [20, 10])),
    ("pdr_headings", "step_index", lambda: pdr.pdr_headings(F3, np.ones((50, 3)), [10.0, 20.0])),
    ("expanding_std", "x", lambda: analysis.expanding_std([])),
    ("expanding_std", "x", lambda: analysis.expanding_std(np.ones((2, 2)))),
    ("horizontal_error", "lla", lambda: analysis.horizontal_error([0.5, 0.5], [0.5, 0.5, 0.0])),
    ("horizontal_error", "lla_true", lambda: analysis.horizontal_error([0.5, 0.5, 0.0], [np.nan, 0.5, 0.0])),
]

# Constants and result records: no arguments to fuzz (built by navlib from validated values).
NOT_FUZZED = {
    "G_LOCAL",
    "M_NED_ENU",
    "STATIC_THRESHOLDS",
    "FilterResult",
    "StepResult",
    "draw_system",
}  # a schematic for the chapter: tests/test_chapter_pedestrian_ins.py, tools/fuzz.py


@pytest.mark.parametrize("func, arg, call", FUZZ, ids=[f"{f}-{a}-{i}" for i, (f, a, _) in enumerate(FUZZ)])
def test_bad_input_raises_naming_the_argument(func, arg, call):
    with warnings.catch_warnings():
        warnings.simplefilter("error", np.exceptions.ComplexWarning)
        with pytest.raises((ValueError, TypeError)) as exc:
            call()
    assert str(exc.value).split(":")[0].startswith(arg), str(exc.value)


def test_every_public_function_is_fuzzed():
    covered = {f for f, _, _ in FUZZ}
    # plus the functions that moved to core modules, still fuzzed here
    public = (
        set(pd.__all__)
        | set(zupt_ins.__all__)
        | {
            "walk",
            "Leg",
            "Gait",
            "stance_mask",
            "detect_static",
            "despike",
            "error_state_matrix",
            "error_model_fd",
            "zupt_zaru_matrix",
            "zupt_zaru_innovation",
            "STATIC_THRESHOLDS",
            "level",
            "magnetic_heading",
            "horizontal_error",
            "expanding_std",
            "detection_rates",
            "baro_height",
            "reference_pressure",
            "classify_floor",
            "segment_floors",
            "segments",
            "static_gyro_bias",
            "ned_to_enu_dcm",
            "M_NED_ENU",
            "StepResult",
            "detect_steps",
            "weinberg_step_length",
            "pdr",
            "pdr_headings",
        }
    )
    assert covered | NOT_FUZZED == public, public - covered - NOT_FUZZED
