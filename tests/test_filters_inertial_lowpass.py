"""navlib.filters.inertial_lowpass on synthetic motion with known truth (the real-data comparison is notebook 07)."""

from __future__ import annotations

import numpy as np
import pytest

from navlib import analysis, attitude
from navlib.filters.inertial_lowpass import InertialLowpassSettings, inertial_lowpass
from navlib.imu import ImuSamples

DT, G = 0.01, 9.81
B_N = np.array([0.0, 20.0, -40.0])  # uT, ENU: north and down
HPR = np.deg2rad([70.0, -10.0, 20.0])


def _static(n, bias=(0.0, 0.0, 0.0), seed=0, hpr=HPR):
    rng = np.random.default_rng(seed)
    C_nb = attitude.euler_to_dcm(hpr).T
    w = np.asarray(bias) + rng.normal(0, 0.002, (n, 3))
    f = C_nb @ [0, 0, G] + rng.normal(0, 0.02, (n, 3))
    m = C_nb @ B_N + rng.normal(0, 0.3, (n, 3))
    return w, f, m, attitude.euler_to_quat(hpr)


def _angle(q, q_true):
    return np.rad2deg(analysis.orientation_errors(q, np.broadcast_to(q_true, q.shape), remove_heading_offset=False).total)


def test_starts_at_the_right_attitude_and_learns_the_bias_at_rest():
    bias = np.deg2rad([0.3, -0.2, 0.4])
    w, f, m, q_true = _static(3000, bias)
    res = inertial_lowpass(ImuSamples(w, f, DT), m)
    assert _angle(res.q_bn[10:20], q_true) < 0.5  # automatic initial attitude, 9D
    assert np.abs(np.rad2deg(res.gyro_bias - bias)).max() < 0.03  # deg/s, a tenth of the bias
    assert res.faults.flags["imu", "rest"][500:].all()
    assert res.faults["mag", "rejected"] == 0


def test_declination_turns_the_heading_only():
    w, f, m, _ = _static(500)
    mag = inertial_lowpass(ImuSamples(w, f, DT), m).q_bn
    true = inertial_lowpass(ImuSamples(w, f, DT), m, declination=np.deg2rad(5.0)).q_bn
    dh = attitude.wrap_pi(attitude.quat_to_euler(true)[:, 0] - attitude.quat_to_euler(mag)[:, 0])
    assert np.rad2deg(dh) == pytest.approx(np.full(500, 5.0), abs=1e-9)
    with pytest.raises(ValueError, match="declination"):
        inertial_lowpass(ImuSamples(w, f, DT), declination=0.1)


def test_inclination_holds_under_horizontal_acceleration():
    """A sensor shaken sideways at 3 m/s^2 (17 deg of apparent tilt) keeps its inclination within 1 deg."""
    n = 6000
    w, f, m, q_true = _static(n, hpr=np.zeros(3))
    t = np.arange(n) * DT
    f[:, 0] += 3.0 * np.sin(2 * np.pi * 1.0 * t) * (t > 10)
    res = inertial_lowpass(ImuSamples(w, f, DT))
    e = analysis.orientation_errors(res.q_bn, np.broadcast_to(q_true, (n, 4)), t > 10)
    assert np.rad2deg(e.inclination) < 1.0


def test_a_disturbed_field_is_rejected_and_reported():
    n = 4000
    w, f, m, q_true = _static(n)
    disturbed = (np.arange(n) >= 2000) & (np.arange(n) < 3000)
    m[disturbed] += [25.0, -10.0, 0.0]  # a magnet near the sensor: 10 s
    res = inertial_lowpass(ImuSamples(w, f, DT), m)
    rejected = res.faults.flags["mag", "rejected"]
    assert rejected[disturbed].mean() > 0.95 and rejected[:2000].sum() == 0
    assert res.faults["mag", "rejected"] == rejected.sum()
    # the heading held on the gyro; before the field's low-pass norm (mag_current_tau = 0.05 s) leaves the
    # tolerance, 3 samples pass, each moving the heading by at most k_mag * 180 deg = 0.2 deg
    assert _angle(res.q_bn[2000:3000], q_true) < 0.6


@pytest.mark.parametrize("bad", [np.nan, np.inf])
def test_a_non_finite_magnetometer_sample_is_skipped_and_counted(bad):
    w, f, m, q_true = _static(1000)
    m[[300, 600], 1] = bad
    res = inertial_lowpass(ImuSamples(w, f, DT), m)
    assert res.faults["mag", "nan"] == 2
    assert np.flatnonzero(res.faults.flags["mag", "nan"]).tolist() == [300, 600]
    assert _angle(res.q_bn[-100:], q_true) < 0.5  # the heading did not jump on it


def test_6d_has_no_magnetometer_faults_and_batches_match():
    w, f, m, _ = _static(800)
    w2, f2, _, _ = _static(800, seed=1)
    one = inertial_lowpass(ImuSamples(w, f, DT))
    both = inertial_lowpass(ImuSamples(np.stack([w, w2]), np.stack([f, f2]), DT))
    assert ("mag", "rejected") not in one.faults.counts
    np.testing.assert_array_equal(both.q_bn[0], one.q_bn)
    assert both.q_bn.shape == (2, 800, 4) and both.gyro_bias.shape == (2, 3)


def test_settings_are_validated():
    with pytest.raises(ValueError, match="tau_acc"):
        InertialLowpassSettings(tau_acc=-1.0)
    with pytest.raises(ValueError, match="settings"):
        inertial_lowpass(ImuSamples(np.zeros((10, 3)), np.tile([0, 0, G], (10, 1)), DT), settings={"tau_acc": 1.0})
