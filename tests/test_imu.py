"""navlib.imu.ImuSamples: validated once with its SensorLimits; taken by the attitude filters, and by the other IMU
filters beside raw arrays with the same results."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from navlib import alignment, attitude, earth, euler, imu, robust, strapdown, trajectory
from navlib.filters import mahony, quaternion_kf, zupt, zupt_ins
from navlib.papers import north_finding, rotation_bias

DT = 0.01
LLA0 = [0.5, 0.2, 10.0]


@pytest.fixture(scope="module")
def walk():
    legs = [trajectory.Leg(3.0), trajectory.Leg(2.0, 1.0), trajectory.Leg(3.0)]
    traj = trajectory.walk(legs, DT, LLA0, 0.3)
    w, f = trajectory.ideal_imu(traj)
    w = w + 0.01 * np.sin(np.arange(len(w)))[:, None]  # some signal for the range test
    return traj, w, f, trajectory.stance_mask(legs, DT)[:-1]


def test_construction_validates_and_stores_arrays():
    s = imu.ImuSamples(np.zeros((2, 5, 3)), np.ones((2, 5, 3)), 0.1, limits=imu.SensorLimits(full_scale_gyro=3.0))
    assert s.n == 5 and s.dt.shape == (5,) and np.all(s.dt == 0.1)
    assert s.limits.full_scale_gyro == 3.0 and np.isinf(s.limits.full_scale_accel)
    assert imu.ImuSamples(np.zeros((5, 3)), np.ones((5, 3)), 0.1).limits == imu.SensorLimits()  # default limits
    t = np.array([0.0, 0.1, 0.25, 0.3, 0.5, 0.6])
    np.testing.assert_array_equal(imu.ImuSamples.from_times(t, np.zeros((5, 3)), np.ones((5, 3))).dt, np.diff(t))


def test_attitude_filters_give_the_same_result_with_a_scalar_or_per_sample_dt(walk):
    traj, w, f, _ = walk
    dts = np.full(len(w), DT)
    limits = imu.SensorLimits(full_scale_gyro=0.5, full_scale_accel=20.0)
    m = np.tile([0.0, 20.0, -40.0], (len(w), 1))
    raw = mahony.mahony(imu.ImuSamples(w, f, dts, limits), traj.q_bn[0], m_b=m)
    new = mahony.mahony(imu.ImuSamples(w, f, DT, limits), q0=traj.q_bn[0], m_b=m)
    np.testing.assert_array_equal(raw.q_bn, new.q_bn)
    assert raw.faults.as_dict() == new.faults.as_dict()
    raw = quaternion_kf.quaternion_kf(imu.ImuSamples(w, f, dts), traj.q_bn[0], m_b=m, B_n=[0.0, 20.0, -40.0])
    new = quaternion_kf.quaternion_kf(imu.ImuSamples(w, f, DT), q0=traj.q_bn[0], m_b=m, B_n=[0.0, 20.0, -40.0])
    np.testing.assert_array_equal(raw.q_bn, new.q_bn)


def test_filters_give_the_same_result_with_samples_or_arrays(walk):
    traj, w, f, static = walk
    dts = np.full(len(w), DT)
    samples = imu.ImuSamples(w, f, DT, imu.SensorLimits(full_scale_gyro=0.5, full_scale_accel=20.0))
    raw = strapdown.integrate(traj.lla[0], traj.vel_n[0], traj.q_bn[0], w, f, dts)
    new = strapdown.integrate(traj.lla[0], traj.vel_n[0], traj.q_bn[0], samples)
    np.testing.assert_array_equal(raw.lla, new.lla)
    start = zupt_ins.Start(traj.lla[0], traj.q_bn[0], traj.vel_n[0])
    raw = zupt_ins.run_filter(imu.ImuSamples(w, f, dts, samples.limits), start, static)  # per-sample intervals
    new = zupt_ins.run_filter(samples, start, static)
    np.testing.assert_array_equal(raw.nav.lla, new.nav.lla)
    assert {k: int(v) for k, v in raw.faults.counts.items()} == {k: int(v) for k, v in new.faults.counts.items()}


def test_the_attitude_filters_take_samples_ranges_and_intervals_once(walk):
    """Only an ImuSamples: the accelerometer, the intervals and the ranges cannot be given beside it."""
    _, w, f, _ = walk
    samples = imu.ImuSamples(w, f, DT, imu.SensorLimits(full_scale_gyro=0.5))
    for filt in (mahony.mahony, quaternion_kf.quaternion_kf):
        with pytest.raises(TypeError, match="full_scale_gyro"):
            filt(samples, q0=[1.0, 0, 0, 0], full_scale_gyro=0.4)
        with pytest.raises(TypeError):
            filt(samples, f, q0=[1.0, 0, 0, 0])
        with pytest.raises(ValueError, match="^imu: "):
            filt(w, [1.0, 0, 0, 0])
    with pytest.raises(TypeError, match="^limits: "):
        imu.ImuSamples(w, f, DT, 0.5)


def assert_same(a, b):
    """Every field of two result records equal, bit for bit (a FaultReport: its keys, counts and flags)."""
    for field in dataclasses.fields(a):
        x, y = getattr(a, field.name), getattr(b, field.name)
        if isinstance(x, robust.FaultReport):
            assert x.counts.keys() == y.counts.keys() and x.flags.keys() == y.flags.keys(), field.name
            for key in x.counts:
                np.testing.assert_array_equal(x[key], y[key], err_msg=f"{field.name}{key}")
            for key in x.flags:
                np.testing.assert_array_equal(x.flags[key], y.flags[key], err_msg=f"{field.name}.flags{key}")
        else:
            np.testing.assert_array_equal(x, y, err_msg=field.name)


@pytest.fixture(scope="module")
def rig():
    """A noisy reciprocating-rotation rig (paper 001) with its dwell windows."""
    lat, period, rotation_time, hpr0 = LLA0[0], 5.0, 0.5, np.deg2rad([0.0, 30.0, 0.0])
    traj = trajectory.reciprocating_rotation(30.0, DT, [lat, 0, 0], hpr0, [0, 1, 0], np.pi / 2, period, rotation_time)
    w, f = trajectory.ideal_imu(traj)
    rng = np.random.default_rng(1)
    w, f = w + 1e-4 + 1e-3 * rng.standard_normal(w.shape), f + 1e-2 * rng.standard_normal(f.shape)
    starts, length = rotation_bias.dwell_windows(len(w), DT, period, rotation_time)
    f[starts[1] + 10, 0] = 45.0  # a shock: at the rails of a 40 m/s^2 accelerometer
    hpr = rotation_bias.dwell_attitudes(hpr0, [0, 1, 0], np.pi / 2, starts.size)
    return w, f, starts, length, earth.earth_rate_b(attitude.euler_to_dcm(hpr), lat)


def test_detect_static_gives_the_same_flags_with_samples_or_arrays(walk):
    _, w, f, _ = walk
    raw = zupt.detect_static(w, f, DT, 0.3, g=9.8)
    assert raw.any() and not raw.all()
    np.testing.assert_array_equal(zupt.detect_static(imu.ImuSamples(w, f, DT), window=0.3, g=9.8), raw)
    # per-sample intervals: the window is a number of samples, set by the median interval
    jitter = DT * (1 + 0.01 * np.sin(np.arange(len(w))))
    np.testing.assert_array_equal(
        zupt.detect_static(imu.ImuSamples(w, f, jitter), window=0.3, g=9.8),
        zupt.detect_static(w, f, float(np.median(jitter)), 0.3, g=9.8),
    )


def test_static_means_gives_the_same_window_with_samples_or_arrays(walk):
    _, w, f, static = walk
    first = slice(0, int(np.argmin(static)))  # the stance before the first step
    w, f = w[first], f[first]
    for ranges in ({}, dict(full_scale_gyro=0.5, full_scale_accel=9.0)):  # 9 m/s^2: the accelerometer saturates
        raw = alignment.static_means(w, f, LLA0[0], LLA0[2], 0.5, strict=False, **ranges)
        new = alignment.static_means(
            imu.ImuSamples(w, f, DT, imu.SensorLimits(**ranges)), lat=LLA0[0], h=LLA0[2], accel_tol=0.5, strict=False
        )
        assert_same(raw, new)
        # accepted without the ranges; with them refused, for the saturated accelerometer samples
        assert raw.faults["window", "refused"] == (1 if ranges else 0)
        assert (raw.faults["accel", "saturated"] > 0) == bool(ranges) and raw.faults["gyro", "saturated"] == 0


def test_tilt_residuals_give_the_same_residuals_with_samples_or_arrays(rig):
    w, f, starts, length, w_ie_b = rig
    dts = np.full(len(w), DT)
    for ranges in ({}, dict(full_scale_gyro=10.0, full_scale_accel=40.0)):
        raw = rotation_bias.tilt_residuals(w, f, dts, starts, length, w_ie_b, outlier_k=6.0, **ranges)
        new = rotation_bias.tilt_residuals(
            imu.ImuSamples(w, f, DT, imu.SensorLimits(**ranges)), starts=starts, length=length, w_ie_b=w_ie_b, outlier_k=6.0
        )
        assert_same(raw, new)
    assert raw.faults["dwell", "refused"] == 1 and raw.faults["imu", "saturated"] == 1  # the shock's dwell
    # a fixed interval given as a scalar fits the slope against the sample index: equal to rounding
    fixed = rotation_bias.tilt_residuals(w, f, DT, starts, length, w_ie_b, outlier_k=6.0)
    np.testing.assert_allclose(
        fixed.r,
        rotation_bias.tilt_residuals(imu.ImuSamples(w, f, DT), starts=starts, length=length, w_ie_b=w_ie_b, outlier_k=6.0).r,
        rtol=1e-9,
        atol=1e-15,
    )


def test_the_new_functions_take_f_b_and_dt_once(walk, rig):
    _, w, f, _ = walk
    samples = imu.ImuSamples(w, f, DT, imu.SensorLimits(full_scale_accel=20.0))
    with pytest.raises(ValueError, match="^f_b: given twice"):
        zupt.detect_static(samples, f)
    with pytest.raises(ValueError, match="^dt: given twice"):
        zupt.detect_static(samples, dt=DT)
    with pytest.raises(ValueError, match="^dt: required"):
        zupt.detect_static(w, f)
    with pytest.raises(ValueError, match="^f_b: given twice"):
        alignment.static_means(samples, f, LLA0[0])
    with pytest.raises(ValueError, match="^full_scale_accel: given twice"):
        alignment.static_means(samples, lat=LLA0[0], full_scale_accel=20.0)
    with pytest.raises(ValueError, match="^f_b: required"):
        alignment.static_means(w, lat=LLA0[0])
    with pytest.raises(ValueError, match="^lat: required"):
        alignment.static_means(samples)
    wr, fr, starts, length, _ = rig
    rig_samples = imu.ImuSamples(wr, fr, DT, imu.SensorLimits(full_scale_gyro=3.0))
    with pytest.raises(ValueError, match="^f_b: given twice"):
        rotation_bias.tilt_residuals(rig_samples, fr, starts=starts, length=length)
    with pytest.raises(ValueError, match="^dt: given twice"):
        rotation_bias.tilt_residuals(rig_samples, dt=DT, starts=starts, length=length)
    with pytest.raises(ValueError, match="^full_scale_gyro: given twice"):
        rotation_bias.tilt_residuals(rig_samples, starts=starts, length=length, full_scale_gyro=3.0)
    with pytest.raises(ValueError, match="^starts: required"):
        rotation_bias.tilt_residuals(rig_samples, length=length)
    with pytest.raises(ValueError, match="^length: required"):
        rotation_bias.tilt_residuals(rig_samples, starts=starts)


def test_integrate_euler_takes_samples(walk):
    traj, w, f, _ = walk
    dts = DT * (1 + 0.1 * np.sin(np.arange(len(w))))
    samples = imu.ImuSamples(w, f, dts, imu.SensorLimits(full_scale_gyro=0.5))
    raw = euler.integrate_euler(traj.hpr[0], w, dts)
    np.testing.assert_array_equal(euler.integrate_euler(traj.hpr[0], samples), raw)
    with pytest.raises(ValueError, match="^dt: given twice"):
        euler.integrate_euler(traj.hpr[0], samples, DT)
    with pytest.raises(ValueError, match="^dt: "):
        euler.integrate_euler(traj.hpr[0], w)  # arrays need dt


def test_ins_heading_change_takes_samples(walk):
    _, w, f, _ = walk
    dts = DT * (1 + 0.1 * np.sin(np.arange(len(w))))
    samples = imu.ImuSamples(w, f, dts, imu.SensorLimits(full_scale_gyro=0.5))
    raw = north_finding.ins_heading_change(w, f[0], dts, 0.5, full_scale_gyro=0.5)
    np.testing.assert_array_equal(north_finding.ins_heading_change(samples, f[0], lat=0.5), raw)
    clipped = imu.ImuSamples(w, f, dts, imu.SensorLimits(full_scale_gyro=0.01))  # the range is used: refused
    assert np.isnan(north_finding.ins_heading_change(clipped, f[0], lat=0.5))
    with pytest.raises(ValueError, match="^dt: given twice"):
        north_finding.ins_heading_change(samples, f[0], DT, 0.5)
    with pytest.raises(ValueError, match="^full_scale_gyro: given twice"):
        north_finding.ins_heading_change(samples, f[0], lat=0.5, full_scale_gyro=0.4)


def test_stop_solutions_take_samples(walk):
    _, w, f, _ = walk
    win = np.array([[0, 250], [550, 800]])
    raw = north_finding.stop_solutions(w, f, win, 0.5, strict=False, full_scale_gyro=0.5, full_scale_accel=20.0)
    new = north_finding.stop_solutions(
        imu.ImuSamples(w, f, DT, imu.SensorLimits(full_scale_gyro=0.5, full_scale_accel=20.0)), windows=win, lat=0.5, strict=False
    )
    np.testing.assert_array_equal(new.candidates, raw.candidates)
    np.testing.assert_array_equal(new.triad, raw.triad)
    assert new.faults.as_dict() == raw.faults.as_dict()
    # the second window is not a stance: refused for motion (no sample saturated, frozen or left out)
    np.testing.assert_array_equal(new.faults["window", "refused"], [0, 1])
    assert not np.any(new.faults["accel", "saturated"]) and not np.any(new.faults["gyro", "stuck"])
    assert new.windows[1].n_used_accel == 250
    sat = north_finding.stop_solutions(
        imu.ImuSamples(w, f, DT, imu.SensorLimits(full_scale_accel=9.0)), windows=win, lat=0.5, strict=False
    )  # the range reaches static_means
    assert np.isnan(sat.triad).all() and np.all(sat.faults["window", "refused"] == 1)
    assert np.all(sat.faults["accel", "saturated"] > 0) and all(s.faults["accel", "saturated"] > 0 for s in sat.windows)
    with pytest.raises(ValueError, match="^f_b: given twice"):
        north_finding.stop_solutions(imu.ImuSamples(w, f, DT), f, win, 0.5)
    with pytest.raises(ValueError, match="^full_scale_accel: given twice"):
        north_finding.stop_solutions(
            imu.ImuSamples(w, f, DT, imu.SensorLimits(full_scale_accel=20.0)), windows=win, lat=0.5, full_scale_accel=30.0
        )
