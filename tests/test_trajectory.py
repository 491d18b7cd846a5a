"""Trajectory generators: vehicle segments and walking legs share one leg grid (``trajectory._on_grid``)."""

import numpy as np
import pytest

from navlib import attitude, trajectory, units

LLA0 = np.array([units.deg(30.0), units.deg(114.0), 20.0])


@pytest.mark.parametrize("dt", [np.float32(0.05), 0.05, 0.03])
def test_vehicle_defines_every_sample_when_the_grid_overshoots(dt):
    # A float32 interval puts the last epoch a hair past the duration; it belongs to the last segment.
    traj = trajectory.vehicle(
        [trajectory.Segment(10.0, speed=5.0, turn=units.deg(51.6)), trajectory.Segment(10.0)], dt, LLA0, 0.0
    )
    heading = units.to_deg(attitude.wrap_2pi(traj.hpr[:, 0]))
    assert np.all(np.isfinite(traj.vel_n))
    assert heading[-1] == pytest.approx(51.6, abs=1e-9)
    assert np.linalg.norm(traj.vel_n[-1]) == pytest.approx(5.0, abs=1e-9)


def test_walk_and_vehicle_cover_the_grid_leg_by_leg():
    t = np.arange(0.0, 3.0 + 1e-12, 0.5)
    masks = [m for m, _ in trajectory._on_grid(t, [1.0, 1.0, 1.0])]
    np.testing.assert_array_equal(np.sum(masks, axis=0), 1)  # each sample in exactly one leg
    np.testing.assert_array_equal([m.sum() for m in masks], [2, 2, 3])


def test_ideal_imu_static_shortcut_is_the_general_result():
    """A static record's samples (computed from its first interval) are the general computation's, bit for bit."""
    still = trajectory.static(20.0, 0.01, [units.deg(28.4), 0.3, 40.0], units.deg([123.0, 5.0, -5.0]))
    lla, vel, q = (np.stack([a, a]) for a in (still.lla, still.vel_n, still.q_bn))
    lla[1, -1, 2] += 1e-3  # trial 1 moves at the end: the general path
    general = trajectory.ideal_imu(trajectory.Trajectory(still.time, lla, vel, q))
    for fast, slow in zip(trajectory.ideal_imu(still), general, strict=True):
        assert fast.flags.writeable and fast.shape == slow.shape[1:]
        np.testing.assert_array_equal(fast.view(np.int64), slow[0].view(np.int64))
