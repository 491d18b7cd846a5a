"""Trajectory generators: vehicle segments and walking legs share one leg grid (``trajectory._on_grid``)."""
import numpy as np
import pytest

from navlib import attitude, trajectory, units

LLA0 = np.array([units.deg(30.0), units.deg(114.0), 20.0])


@pytest.mark.parametrize("dt", [np.float32(0.05), 0.05, 0.03])
def test_vehicle_defines_every_sample_when_the_grid_overshoots(dt):
    # A float32 interval puts the last epoch a hair past the duration; it belongs to the last segment.
    traj = trajectory.vehicle([trajectory.Segment(10.0, speed=5.0, turn=units.deg(51.6)),
                               trajectory.Segment(10.0)], dt, LLA0, 0.0)
    heading = units.to_deg(attitude.wrap_2pi(traj.hpr[:, 0]))
    assert np.all(np.isfinite(traj.vel_n))
    assert heading[-1] == pytest.approx(51.6, abs=1e-9)
    assert np.linalg.norm(traj.vel_n[-1]) == pytest.approx(5.0, abs=1e-9)


def test_walk_and_vehicle_cover_the_grid_leg_by_leg():
    t = np.arange(0.0, 3.0 + 1e-12, 0.5)
    masks = [m for m, _ in trajectory._on_grid(t, [1.0, 1.0, 1.0])]
    np.testing.assert_array_equal(np.sum(masks, axis=0), 1)          # each sample in exactly one leg
    np.testing.assert_array_equal([m.sum() for m in masks], [2, 2, 3])
