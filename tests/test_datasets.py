"""navlib.datasets (BROAD reader) and navlib.analysis.orientation_errors (BROAD's error measures)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from navlib import analysis, attitude, datasets

BROAD = Path(__file__).resolve().parents[1] / "data" / "real" / "broad"
TRIAL = BROAD / "07_undisturbed_fast_rotation_B.npz"


@pytest.fixture(scope="module")
def trial():
    return datasets.read_broad(TRIAL)


def test_reads_a_trial_in_si_units(trial):
    r = trial.recording
    assert trial.name == "07_undisturbed_fast_rotation_B"
    assert trial.rate == pytest.approx(2000 / 7)
    assert r.w_ib_b.shape == r.f_b.shape == r.m_b.shape == (r.n, 3) and trial.q_ref.shape == (r.n, 4)
    still = slice(0, int(trial.rate))  # every trial starts at rest
    assert np.linalg.norm(r.f_b[still].mean(0)) == pytest.approx(9.81, abs=0.1)
    assert 20 < np.linalg.norm(r.m_b[still].mean(0)) < 70  # uT
    assert np.abs(r.w_ib_b[still]).max() < np.deg2rad(3)  # rad/s
    ok = np.isfinite(trial.q_ref).all(1)
    assert ok.mean() > 0.9 and np.allclose(np.linalg.norm(trial.q_ref[ok], axis=1), 1)
    assert (trial.q_ref[ok, 0] >= 0).all()
    assert trial.movement.dtype == bool and 0 < trial.movement.mean() < 1
    assert trial.imu.n == r.n


def test_reference_is_navlibs_q_bn(trial):
    """At rest the specific force points up: the reference's up axis seen in the body agrees with it."""
    r, ok = trial.recording, np.isfinite(trial.q_ref).all(1)
    rest = np.flatnonzero(ok & ~trial.movement)[:2000]
    up_b = attitude.quat_to_dcm(trial.q_ref[rest])[:, 2, :]  # row 3 of C_bn: ENU up in body axes
    f_b = r.f_b[rest] / np.linalg.norm(r.f_b[rest], axis=1, keepdims=True)
    angle = np.rad2deg(np.arccos(np.clip(np.sum(up_b * f_b, axis=1), -1, 1)))
    assert np.median(angle) < 2.0


def test_refuses_a_file_that_is_not_a_converted_trial(tmp_path):
    path = tmp_path / "01_x.npz"
    np.savez(path, gyr=np.zeros((3, 3)))
    with pytest.raises(ValueError, match="tools/broad_to_npz.py"):
        datasets.read_broad(path)


def test_split_by_trial_number_parity():
    assert datasets.broad_split(["02_a", "07_b", "31_c", "16_d"]) == (["02_a", "16_d"], ["07_b", "31_c"])
    with pytest.raises(ValueError, match="names"):
        datasets.broad_split(["trial_7"])


def _random_q(rng, n):
    return attitude.quat_normalize(rng.standard_normal((n, 4)))


def test_errors_of_a_perfect_and_a_turned_estimate():
    rng = np.random.default_rng(1)
    q_ref = _random_q(rng, 500)
    assert analysis.orientation_errors(q_ref, q_ref).total == pytest.approx(0, abs=1e-7)
    turned = attitude.quat_mult(attitude.rotvec_to_quat([0, 0, 0.3]), q_ref)
    e = analysis.orientation_errors(turned, q_ref)
    assert e.total == pytest.approx(0, abs=1e-7) and abs(e.heading_offset) == pytest.approx(0.3)
    kept = analysis.orientation_errors(turned, q_ref, remove_heading_offset=False)
    assert (kept.total, kept.heading, kept.inclination) == pytest.approx((0.3, 0.3, 0.0), abs=1e-7)


def test_error_rotation_rounds_as_the_full_quaternion_product():
    """orientation_errors forms only the components it needs (the norms summed in order, the product's w and z):
    bit for bit what np.linalg.norm and quat_mult give, so its results do not move."""
    from navlib import _attitude

    rng = np.random.default_rng(4)
    p, q = rng.standard_normal((2, 5000, 4)) * np.exp(rng.uniform(-3, 3, (2, 5000, 1)))
    assert np.array_equal(analysis._row_norms(p), np.linalg.norm(p, axis=1))
    e = _attitude.quat_mult(p, q)
    w, z = analysis._scalar_and_up(p, q)
    assert np.array_equal(w, e[:, 0]) and np.array_equal(z, e[:, 3])


def test_inclination_is_the_angle_between_up_axes():
    rng = np.random.default_rng(2)
    q_ref = _random_q(rng, 400)
    tilt = attitude.rotvec_to_quat(rng.normal(0, 0.05, (400, 3)) * [1, 1, 0])
    q = attitude.quat_mult(tilt, q_ref)
    up_est = attitude.quat_to_dcm(q)[:, 2, :]  # ENU up in body axes
    up_ref = attitude.quat_to_dcm(q_ref)[:, 2, :]
    angle = np.arccos(np.clip(np.sum(up_est * up_ref, axis=1), -1, 1))
    e = analysis.orientation_errors(q, q_ref, remove_heading_offset=False)
    assert e.inclination == pytest.approx(np.sqrt(np.mean(angle**2)), rel=1e-6)


def test_mask_and_missing_reference():
    rng = np.random.default_rng(3)
    q_ref = _random_q(rng, 100)
    q = q_ref.copy()
    q[:50] = attitude.quat_mult(attitude.rotvec_to_quat([0.1, 0, 0]), q_ref[:50])
    mask = np.arange(100) >= 50
    assert analysis.orientation_errors(q, q_ref, mask).total == pytest.approx(0, abs=1e-7)
    q_ref[60:] = np.nan
    e = analysis.orientation_errors(q, q_ref, mask)
    assert (e.samples, e.missing_reference) == (10, 40)  # masked-in rows without a reference are counted
    with pytest.raises(ValueError, match="no sample"):
        analysis.orientation_errors(q, q_ref, np.arange(100) >= 60)
    q[55] = np.nan
    with pytest.raises(ValueError, match="q_bn"):
        analysis.orientation_errors(q, q_ref, mask)


@pytest.fixture(scope="module")
def drive():
    return datasets.read_comma2k19(Path(__file__).resolve().parents[1] / "data" / "real" / "comma2k19")


def test_drive_reference_frames_agree_with_the_motion(drive):
    """The reference attitude's heading follows its velocity, and it rotates the specific force to vertical."""
    heading = attitude.quat_to_euler(drive.ref_q_bn)[:, 0]
    course = np.arctan2(drive.ref_v_n[:, 0], drive.ref_v_n[:, 1])
    assert np.median(np.abs(attitude.wrap_pi(heading - course))) < np.deg2rad(2)
    q = attitude.quat_normalize(np.stack([np.interp(drive.imu.time, drive.ref_time, drive.ref_q_bn[:, i]) for i in range(4)], -1))
    f_n = attitude.quat_rotate(q, drive.imu.f_b).mean(0)
    assert np.rad2deg(np.arctan2(np.hypot(f_n[0], f_n[1]), f_n[2])) < 1.0  # mean tilt of f_n from up


def test_drive_series_agree_with_the_reference(drive):
    assert drive.imu.time[0] == 0 and drive.imu.n == 6256 and 59 < drive.imu.time[-1] < 61
    speed = np.interp(drive.can_time, drive.ref_time, np.linalg.norm(drive.ref_v_n, axis=1))
    assert np.median(np.abs(drive.can_speed - speed)) < 0.3  # m/s
    lat = np.interp(drive.gnss_time, drive.ref_time, drive.ref_lla[:, 0])
    assert np.median(np.abs(np.deg2rad(drive.gnss[:, 0]) - lat)) * 6.4e6 < 5.0  # m north-south
    with pytest.raises(FileNotFoundError, match="comma2k19"):
        datasets.read_comma2k19(BROAD)


def test_drive_as_an_attitude_trial(drive):
    trial = drive.attitude_trial()
    assert trial.recording.n == drive.imu.n and np.isfinite(trial.m_b).all()
    scored = trial.recording.time[trial.movement]
    assert scored[0] >= drive.ref_time[0] and scored[-1] <= drive.ref_time[-1] and trial.movement.mean() > 0.95
    assert np.allclose(np.linalg.norm(trial.q_ref, axis=1), 1)
    assert trial.rate == pytest.approx(104, abs=1)


def test_time_offset_finds_a_known_delay_and_refuses_one_beyond_its_grid():
    t_ref = np.arange(0.0, 30.0, 0.01)
    x_ref = np.stack([np.sin(0.7 * t_ref), np.cos(0.3 * t_ref)], -1)
    t = np.arange(0.5, 29.5, 0.1)
    x = np.stack([np.sin(0.7 * (t - 0.137)), np.cos(0.3 * (t - 0.137))], -1)  # 0.137 s late
    x[5] = np.nan  # left out
    assert analysis.time_offset(t, x, t_ref, x_ref) == pytest.approx(0.137, abs=1e-3)
    assert analysis.time_offset(t, x[:, 0], t_ref, x_ref[:, 0]) == pytest.approx(0.137, abs=1e-3)
    with pytest.raises(ValueError, match="max_offset"):
        analysis.time_offset(t, x, t_ref, x_ref, max_offset=0.1, step=0.01)
    with pytest.raises(ValueError, match="x, x_ref"):
        analysis.time_offset(t, x, t_ref, x_ref[:, 0])
    gap = (t_ref < 10.0) | (t_ref > 12.0)  # a 2-s hole in the reference: refused, not interpolated across
    with pytest.raises(ValueError, match="t_ref: a gap of 2"):
        analysis.time_offset(t, x, t_ref[gap], x_ref[gap])
