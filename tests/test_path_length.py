"""analysis.footfall_path_length: the distance walked by a foot-mounted track, from footfall to footfall."""

import numpy as np
import pytest

from navlib import analysis


def foot_track(rng, n_strides=20, stride=1.4, rate=400.0):
    """A foot on a gently curving path: 0.3-s stances at known footfalls (with 5 mm of filter jitter), 0.7-s
    swings that arc 8 cm up and 3 cm sideways between them. Returns positions, stance flags, true length."""
    heading = np.cumsum(rng.normal(0.0, 0.05, n_strides + 1))
    steps = stride * np.stack([np.sin(heading), np.cos(heading)], -1)
    falls = np.vstack([[0.0, 0.0], np.cumsum(steps, 0)])
    pos, stance = [], []
    n_st, n_sw = int(0.3 * rate), int(0.7 * rate)
    for k in range(n_strides + 1):
        pos.append(np.column_stack([falls[k] + 0.005 * rng.standard_normal((n_st, 2)), np.zeros(n_st)]))
        stance.append(np.ones(n_st, bool))
        if k == n_strides:
            break
        s = np.linspace(0, 1, n_sw + 2)[1:-1, None]
        d = falls[k + 1] - falls[k]
        side = np.array([d[1], -d[0]]) / np.linalg.norm(d)
        xy = falls[k] + s * d + 0.03 * np.sin(np.pi * s) * side
        pos.append(np.column_stack([xy, 0.08 * np.sin(np.pi * s[:, 0])]))
        stance.append(np.zeros(n_sw, bool))
    return np.vstack(pos), np.concatenate(stance), float(np.sum(np.linalg.norm(steps[:n_strides], axis=1)))


def test_footfall_path_length_equals_the_strides():
    pos, stance, truth = foot_track(np.random.default_rng(34))
    length, falls = analysis.footfall_path_length(pos, stance, min_samples=20)
    assert falls.shape == (21, 2)
    assert length == pytest.approx(truth, rel=0.005)
    summed = np.sum(np.linalg.norm(np.diff(pos[:, :2], axis=0), axis=1))  # sample by sample: longer
    assert summed > 1.05 * truth


def test_footfall_path_length_ignores_short_stance_flickers_and_refuses_bad_input():
    pos, stance, truth = foot_track(np.random.default_rng(35))
    flicker = stance.copy()
    flicker[np.flatnonzero(~stance)[::97]] = True  # single-sample false stances mid-swing
    assert analysis.footfall_path_length(pos, flicker, min_samples=20)[0] == pytest.approx(truth, rel=0.005)
    assert analysis.footfall_path_length(pos, np.zeros(len(pos), bool))[0] == 0.0
    with pytest.raises(ValueError, match="pos_n"):
        analysis.footfall_path_length(pos[:, 0], stance)
    with pytest.raises(ValueError, match="stance"):
        analysis.footfall_path_length(pos, stance[:-1])
