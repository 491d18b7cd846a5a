"""Every filter result reports its faults in the one vocabulary of navlib.robust.FaultReport.

``result.faults`` is the one place a filter reports what it held, rejected or refused, under
``(sensor, kind)`` keys, so code that inspects faults works across filters.
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from navlib import imu, robust, strapdown, trajectory
from navlib.filters import mahony, planar_ekf, zupt_ins
from navlib.imu import ImuSamples, SensorLimits
from navlib.papers import gauss_kruger_ekf, rotation_bias

KINDS = {"nan", "saturated", "spike", "outlier", "reacquired", "refused", "jump", "freefall", "stuck"}


def check_vocabulary(report):
    assert isinstance(report, robust.FaultReport)
    assert {kind for _, kind in report.counts} <= KINDS
    for key, mask in report.flags.items():
        assert int(np.sum(mask)) >= int(np.sum(report[key])) - 1  # flags and counts agree (EKF: epoch 0 aside)


def test_attitude_filters():
    rng = np.random.default_rng(1)
    n = 400
    w = rng.normal(0, 0.01, (n, 3))
    f = np.tile([0.0, 0.0, 9.8], (n, 1))
    m = np.tile([0.0, 20.0, -40.0], (n, 1))
    w[10], f[20], m[30] = np.nan, np.nan, np.nan
    res = mahony.mahony(imu.ImuSamples(w, f, 0.01, imu.SensorLimits(full_scale_gyro=0.02)), [1.0, 0, 0, 0], m_b=m)
    check_vocabulary(res.faults)
    assert set(res.faults.counts) == set(res.faults.flags)  # every key flagged per sample (no RTK here)
    for key, mask in res.faults.flags.items():
        assert res.faults[key] == mask.sum()
    assert res.faults["gyro", "nan"] == 1 and res.faults["accel", "nan"] == 1 and res.faults["mag", "nan"] == 1
    assert res.faults["gyro", "saturated"] == np.sum(np.any(np.abs(w) >= 0.02, axis=-1) & np.isfinite(w).all(-1))


def test_planar_ekf():
    t = np.arange(20.0)
    z = np.tile([0.0, 0.0, 0.3, 1.0, 0.0], (20, 1))
    z[5, :2] = np.nan
    z[8, 0] += 500.0
    z[12, 4] = 0.6
    config = planar_ekf.EkfConfig(
        gauss_kruger_ekf.Q_PAPER, gauss_kruger_ekf.R_PAPER, np.eye(5), 15.0, limits=SensorLimits(full_scale_gyro=0.5)
    )
    res = planar_ekf.filter_grid(t, z, z[0], config)
    check_vocabulary(res.faults)
    assert res.faults["gnss", "nan"] == 1 and res.faults["gnss", "outlier"] >= 1
    assert res.faults["yaw_rate", "saturated"] == 1 and res.faults.flags["yaw_rate", "saturated"][12]


def test_pedestrian_filter():
    legs = [trajectory.Leg(3.0), trajectory.Leg(2.0, 1.0), trajectory.Leg(3.0)]
    traj = trajectory.walk(legs, 0.01, [0.5, 0.2, 10.0], 0.0)
    w, f = trajectory.ideal_imu(traj)
    w[50] = np.nan
    static = trajectory.stance_mask(legs, 0.01)[:-1]
    res = zupt_ins.run_filter(ImuSamples(w, f, 0.01), zupt_ins.Start(traj.lla[0], traj.q_bn[0], traj.vel_n[0]), static)
    check_vocabulary(res.faults)
    for key, mask in res.faults.flags.items():
        assert res.faults[key] == mask.sum(), key
    assert res.faults["gyro", "nan"] == 1 and res.faults.flags["gyro", "nan"][50]


def test_rotation_bias_residuals():
    res = rotation_bias.Residuals(
        np.zeros((1, 2)),
        np.zeros((1, 2, 3)),
        np.zeros((1, 2)),
        np.array([10]),
        1.0,
        robust.FaultReport({("dwell", "refused"): 3, ("imu", "nan"): 5}),
    )
    check_vocabulary(res.faults)
    assert res.faults["dwell", "refused"] == 3 and res.faults["imu", "nan"] == 5


def test_static_window_and_ins_report():
    from navlib import alignment
    from navlib.papers import north_finding

    w = np.tile([1e-5, 2e-5, 3e-5], (100, 1))
    f = np.tile([0.0, 0.0, 9.8], (100, 1))
    w[3] = np.nan
    win = alignment.static_means(w, f, 0.5)
    check_vocabulary(win.faults)
    assert win.faults["gyro", "nan"] == 1 and win.faults["window", "refused"] == 0
    assert {key for key in win.faults.counts} == {
        (s, k) for s in ("gyro", "accel") for k in ("nan", "outlier", "saturated", "stuck")
    } | {("window", "refused")}
    assert not any(
        name.startswith(("n_dropped", "n_outliers", "n_saturated", "n_stuck")) or name == "status" for name in vars(win)
    )  # faults only: no second set of counters
    assert win.n_used_gyro == 99 and win.n_used_accel == 100  # what was used: results, not faults
    dpsi = north_finding.ins_heading_change(w, f[0], 0.01, 0.5)
    rep = robust.fault_report(w, "gyro")
    check_vocabulary(rep)
    assert rep["gyro", "nan"] == 1 and np.isfinite(dpsi)  # held, not refused


def test_strapdown_trajectory():
    traj = trajectory.static(2.0, 0.01, [0.5, 0.2, 10.0], [0.3, 0.0, 0.0])
    w, f = trajectory.ideal_imu(traj)
    w[[5, 9]], f[7] = np.nan, np.nan
    nav = strapdown.integrate(traj.lla[0], traj.vel_n[0], traj.q_bn[0], w, f, 0.01, nan_policy="hold")
    check_vocabulary(nav.faults)
    assert nav.faults["gyro", "nan"] == 2 and nav.faults["accel", "nan"] == 1
    assert np.flatnonzero(nav.faults.flags["gyro", "nan"]).tolist() == [5, 9]
    assert nav.faults.flags["accel", "nan"].shape == (len(w),)
    samples = imu.ImuSamples(np.stack([w, w]), np.stack([f, f]), 0.01)
    nav = strapdown.integrate(traj.lla[0], traj.vel_n[0], traj.q_bn[0], samples, nan_policy="hold")
    np.testing.assert_array_equal(nav.faults["gyro", "nan"], [2, 2])  # per trial
    clean = strapdown.integrate(traj.lla[0], traj.vel_n[0], traj.q_bn[0], *trajectory.ideal_imu(traj), 0.01)
    check_vocabulary(clean.faults)
    assert clean.faults["gyro", "nan"] == 0 and not clean.faults  # default: raise, nothing held
    assert isinstance(traj.faults, robust.FaultReport) and not traj.faults  # generated: no faults


# ----------------------------------------------------------------------------- robust.fault_report


def test_fault_report_counts_nan_rows_per_trial():
    x = np.zeros((2, 6, 3))
    x[0, 1, 2] = np.nan  # one NaN component makes the row a dropout
    x[1, [0, 4]] = np.nan
    rep = robust.fault_report(x, "gyro")
    check_vocabulary(rep)
    np.testing.assert_array_equal(rep["gyro", "nan"], [1, 2])
    assert set(rep.counts) == {("gyro", "nan")} and rep.flags == {}  # no full_scale, no flags
    assert rep["gyro", "saturated"] == 0
    assert robust.fault_report(x[0], "accel")["accel", "nan"] == 1  # no batch axis: a scalar count


def test_fault_report_flags_and_saturation():
    x = np.zeros((5, 3))
    x[1, 0] = 2.0  # at the rails (>=)
    x[2, 1] = -3.0  # beyond, negative
    x[3] = [np.nan, 5.0, 0.0]  # a dropout is not also counted as saturated
    rep = robust.fault_report(x, "gyro", full_scale=2.0, flags=True)
    check_vocabulary(rep)
    assert rep["gyro", "nan"] == 1 and rep["gyro", "saturated"] == 2
    np.testing.assert_array_equal(rep.flags["gyro", "saturated"], [False, True, True, False, False])
    np.testing.assert_array_equal(rep.flags["gyro", "nan"], [False, False, False, True, False])
    assert robust.fault_report(x, "gyro", full_scale=np.inf)["gyro", "saturated"] == 0


def test_fault_report_batch_axes():
    rng = np.random.default_rng(0)
    x = rng.normal(0, 1, (3, 4, 50, 2))
    x[rng.random(x.shape) < 0.05] = np.nan
    rep = robust.fault_report(x, "mag", full_scale=1.5, flags=True)
    assert rep["mag", "nan"].shape == (3, 4) and rep.flags["mag", "nan"].shape == (3, 4, 50)
    np.testing.assert_array_equal(rep["mag", "nan"], np.isnan(x).any(-1).sum(-1))
    valid = ~np.isnan(x).any(-1)
    np.testing.assert_array_equal(rep["mag", "saturated"], (valid & (np.abs(x) >= 1.5).any(-1)).sum(-1))
    np.testing.assert_array_equal(rep.total(), rep["mag", "nan"] + rep["mag", "saturated"])


def test_fault_report_matches_what_strapdown_holds():
    traj = trajectory.static(1.0, 0.01, [0.5, 0.2, 10.0], [0.3, 0.0, 0.0])
    w, f = trajectory.ideal_imu(traj)
    w[[3, 4, 60]], f[20] = np.nan, np.nan
    nav = strapdown.integrate(traj.lla[0], traj.vel_n[0], traj.q_bn[0], w, f, 0.01, nan_policy="hold")
    for x, sensor in ((w, "gyro"), (f, "accel")):
        rep = robust.fault_report(x, sensor, flags=True)
        assert rep[sensor, "nan"] == nav.faults[sensor, "nan"]
        np.testing.assert_array_equal(rep.flags[sensor, "nan"], nav.faults.flags[sensor, "nan"])


@pytest.mark.parametrize(
    "arg, call",
    [
        ("x", lambda: robust.fault_report(np.zeros(5), "gyro")),  # no sample axis
        ("x", lambda: robust.fault_report(np.zeros((0, 3)), "gyro")),  # empty
        ("x", lambda: robust.fault_report(np.full((4, 3), np.inf), "gyro")),  # inf is not a dropout
        ("x", lambda: robust.fault_report("abc", "gyro")),
        ("x", lambda: robust.fault_report(np.zeros((4, 3), complex), "gyro")),
        ("sensor", lambda: robust.fault_report(np.zeros((4, 3)), 1)),
        ("full_scale", lambda: robust.fault_report(np.zeros((4, 3)), "gyro", full_scale=0.0)),
        ("full_scale", lambda: robust.fault_report(np.zeros((4, 3)), "gyro", full_scale=np.nan)),
        ("full_scale", lambda: robust.fault_report(np.zeros((4, 3)), "gyro", full_scale=[1.0, 2.0])),
        ("flags", lambda: robust.fault_report(np.zeros((4, 3)), "gyro", flags="yes")),
    ],
)
def test_fault_report_bad_input_names_the_argument(arg, call):
    with pytest.raises(ValueError, match=f"^{arg}: "):
        call()


# ----------------------------------------------------------------------------- robust.stuck_mask


def test_stuck_mask_marks_whole_runs_of_exact_repeats():
    x = np.array([1.0, 2, 2, 2, 3, 3, np.nan, np.nan, np.nan, 4, 4, 4, 4])
    #              -  ---------  ----  NaN is never a repeat  ----------
    np.testing.assert_array_equal(robust.stuck_mask(x, 3, axis=-1), [0, 1, 1, 1, 0, 0, 0, 0, 0, 1, 1, 1, 1])
    np.testing.assert_array_equal(robust.stuck_mask(x, 2, axis=-1), [0, 1, 1, 1, 1, 1, 0, 0, 0, 1, 1, 1, 1])
    np.testing.assert_array_equal(robust.stuck_mask(x, 4, axis=-1), [0] * 9 + [1] * 4)
    assert not robust.stuck_mask(x[:3], 4, axis=-1).any()  # shorter than a run


def test_stuck_mask_any_axis_and_batch_axes():
    rng = np.random.default_rng(0)
    x = rng.normal(size=(2, 3, 40, 3))
    x[0, 1, 5:12, 2] = 0.7  # one axis latched for 7 samples
    x[1, 2, 30:40] = x[1, 2, 30]  # all axes frozen to the end
    x[1, 0, 10:14, 0] = 0.1  # 4 repeats: below run = 5
    mask = robust.stuck_mask(x, 5)
    assert mask.shape == (2, 3, 40)
    expected = np.zeros((2, 3, 40), bool)
    expected[0, 1, 5:12] = expected[1, 2, 30:40] = True
    np.testing.assert_array_equal(mask, expected)
    for i in range(2):
        for j in range(3):
            np.testing.assert_array_equal(robust.stuck_mask(x[i, j], 5), mask[i, j])


@pytest.mark.parametrize(
    "kwargs, arg",
    [
        (dict(x=np.full((5, 3), np.inf), run=3), "x"),
        (dict(x=np.zeros((5, 3)), run=1), "run"),
        (dict(x=np.zeros((5, 3)), run=True), "run"),
        (dict(x=np.zeros((5, 3)), run=3.0), "run"),
        (dict(x=np.zeros((5, 3)), run=3, axis=0), "axis"),
        (dict(x=np.zeros(5), run=3), "w_ib_b"),
    ],
)
def test_stuck_mask_bad_input_names_the_argument(kwargs, arg):
    with pytest.raises(ValueError, match=f"^{arg}: "):
        robust.stuck_mask(**kwargs, **({"name": "w_ib_b"} if arg == "w_ib_b" else {}))


def test_attitude_filters_flag_stuck_and_jump_samples():
    rng = np.random.default_rng(2)
    w = rng.normal(0, 0.01, (2, 300, 3))
    w[0, 100:120] = w[0, 100]
    dt = np.full(300, 0.01)
    dt[250] = 2.0
    res = mahony.mahony(imu.ImuSamples(w, np.tile([0.0, 0.0, 9.8], (2, 300, 1)), dt), [1.0, 0, 0, 0])
    check_vocabulary(res.faults)
    np.testing.assert_array_equal(res.faults["gyro", "stuck"], [20, 0])
    np.testing.assert_array_equal(res.faults["clock", "jump"], [1, 1])
    for key in (("gyro", "stuck"), ("clock", "jump")):
        np.testing.assert_array_equal(res.faults.flags[key].sum(-1), res.faults[key])
    assert res.faults["gyro", "nan"].tolist() == [0, 0]  # stuck is not counted as a dropout


def test_longest_repeat_equals_a_plain_loop():
    """The compiled runs against the definition, on random readings with repeats, NaN and invalid rows."""
    rng = np.random.default_rng(1)
    for _ in range(200):
        x = rng.integers(0, 3, (2, int(rng.integers(1, 30)), 2)).astype(float)
        x[rng.random(x.shape) < 0.1] = np.nan
        valid = rng.random(x.shape[:-1]) < 0.8
        want = np.zeros((2, 2), int)
        for b, j in np.ndindex(2, 2):
            seq = [v for v, ok in zip(x[b, :, j], valid[b], strict=True) if ok]
            want[b, j] = max(
                (len(list(g)) for _, g in itertools.groupby(seq, key=lambda v: v if v == v else object())), default=0
            )
        np.testing.assert_array_equal(robust.longest_repeat(x, valid), want)


def test_longest_repeat_counts_runs_over_valid_samples():
    x = np.array([[1.0, 2.0], [1.0, 3.0], [np.nan, 3.0], [1.0, 3.0], [2.0, 4.0]])
    np.testing.assert_array_equal(robust.longest_repeat(x), [3, 2])  # the NaN row is skipped, not a break
    valid = np.array([True, True, False, True, True])
    np.testing.assert_array_equal(robust.longest_repeat(np.nan_to_num(x), valid), [3, 2])  # an invalid row likewise
    np.testing.assert_array_equal(robust.longest_repeat(np.stack([x, x + 0.5])), [[3, 2], [3, 2]])
    with pytest.raises(ValueError, match="^x: "):
        robust.longest_repeat([1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match="^valid: "):
        robust.longest_repeat(x, valid[:3])
