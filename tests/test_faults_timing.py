"""navlib.faults (fault injection) and navlib.timing (timestamp sanitising)."""

import numpy as np
import pytest

from navlib import earth, faults, timing


def rng():
    return np.random.default_rng(11)


def test_dropouts_and_gap_mark_exactly_what_they_change():
    x = np.ones((1000, 3))
    y, dropped = faults.dropouts(x, 0.1, rng())
    assert np.array_equal(np.isnan(y).all(axis=1), dropped) and not np.isnan(y[~dropped]).any()
    assert abs(dropped.mean() - 0.1) < 4 * np.sqrt(0.1 * 0.9 / 1000)  # binomial, 4 sigma
    t = np.arange(1000) * 0.1
    z, gap = faults.gap(x, t, 20.0, 30.0)
    assert gap.sum() == 300 and np.isnan(z[gap]).all() and x[0, 0] == 1.0  # input untouched


def test_spikes_are_k_sigma():
    x = np.zeros((2000, 3))
    y, hit = faults.spikes(x, 0.01, [1.0, 2.0, 3.0], rng())
    np.testing.assert_array_equal(np.abs(y[hit]), np.broadcast_to([100.0, 200.0, 300.0], (hit.sum(), 3)))
    assert not y[~hit].any()


def test_position_jumps_and_heading_flips():
    lla = np.tile([0.5, 2.0, 10.0], (400, 1))
    y, hit = faults.position_jumps(lla, 0.05, rng(), size_m=50.0)
    R_M, R_N = earth.radii(0.5)
    d = np.hypot((y[:, 0] - 0.5) * (R_M + 10), (y[:, 1] - 2.0) * (R_N + 10) * np.cos(0.5))
    np.testing.assert_allclose(d[hit], 50.0, rtol=1e-6)
    assert not d[~hit].any()
    h, flipped = faults.heading_flips(np.full(100, 0.2), 0.5, rng())
    np.testing.assert_allclose(h[flipped], 0.2 + np.pi)
    np.testing.assert_array_equal(h[~flipped], 0.2)


def test_timestamp_faults_are_found_and_repaired_by_sanitize():
    t = np.arange(200) * 0.01
    data = np.stack([t, 2 * t], -1)
    t_dup, dup = faults.duplicate_timestamps(t, 0.05, rng())
    t_bad, order = faults.swap_timestamps(t_dup, 0.05, np.random.default_rng(3))
    t_ok, data_ok, report = timing.sanitize(t_bad, data[order])
    assert np.all(np.diff(t_ok) > 0)
    assert report.n_in == 200 and report.n_out == 200 - report.n_duplicate
    assert report.n_duplicate == np.unique(t_dup, return_counts=True)[1].sum() - np.unique(t_dup).size
    assert report.n_out_of_order > 0 and report.irregular
    ti = faults.irregular_times(1000, 0.01, 0.2, rng())
    assert np.all(np.diff(ti) >= 0.008 - 1e-12) and np.all(np.diff(ti) <= 0.012 + 1e-12)
    np.testing.assert_allclose(timing.intervals(ti), np.diff(ti))


def test_saturate():
    x = np.array([[1.0, 5.0, -7.0], [0.0, 0.0, 0.0]])
    y, clipped = faults.saturate(x, 4.0)
    np.testing.assert_array_equal(y, [[1.0, 4.0, -4.0], [0, 0, 0]])
    np.testing.assert_array_equal(clipped, [True, False])


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda: faults.dropouts(np.ones(5), 1.5, rng()), "fraction"),
        (lambda: faults.dropouts(np.ones(5), 0.1, None), "rng"),
        (lambda: faults.gap(np.ones(5), np.arange(4.0), 0.0, 1.0), "time"),
        (lambda: faults.spikes(np.ones(5), 0.1, -1.0, rng()), "sigma"),
        (lambda: faults.position_jumps(np.ones((5, 2)), 0.1, rng()), "lla"),
        (lambda: faults.irregular_times(1, 0.1, 0.2, rng()), "n"),
        (lambda: faults.irregular_times(10, 0.1, 1.5, rng()), "jitter"),
        (lambda: faults.saturate(np.ones(3), 0.0), "full_scale"),
        (lambda: timing.sanitize([1.0]), "time"),
        (lambda: timing.sanitize([0.0, 1.0], np.ones(3)), "series"),
        (lambda: timing.intervals([0.0, 0.0, 1.0]), "time"),
    ],
)
def test_bad_input(call, match):
    with pytest.raises(ValueError, match=match):
        call()
