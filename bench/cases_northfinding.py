"""North-finding cases (paper 000): single-axis Monte Carlo trials per second."""

from __future__ import annotations

import math

import numpy as np

from bench.run import Result, best_time
from navlib import earth, units
from navlib.papers import north_finding as nf

LAT = units.deg(28.361735)
SIGMA_GYRO, SIGMA_ACCEL = units.deg_per_h(0.01), units.ug(100)


def _python_trial(w_y, f_y, f_norm, psi_true):
    """One single-axis trial in plain Python (the reference a MATLAB-style loop would run)."""
    w = earth.OMEGA_IE
    pitch = math.asin(max(-1.0, min(1.0, f_y / f_norm)))
    c = (w_y - w * math.sin(LAT) * math.sin(pitch)) / (w * math.cos(LAT) * math.cos(pitch))
    a = math.acos(max(-1.0, min(1.0, c)))
    e1 = (a - psi_true + math.pi) % (2 * math.pi) - math.pi
    e2 = (2 * math.pi - a - psi_true + math.pi) % (2 * math.pi) - math.pi
    return e1 if abs(e1) < abs(e2) else e2


def single_axis_monte_carlo(quick: bool):
    """Fig. 4's single-axis Monte Carlo: simulate averaged outputs, candidates, nearest-candidate error."""
    headings = units.deg(np.arange(1, 352, 10.0))
    n_trials = 1000 if quick else 10_000
    hpr = np.stack(np.broadcast_arrays(headings, units.deg(5), units.deg(5)), -1)

    def navlib_run():
        w, f = nf.simulate_static_outputs(hpr, LAT, n_trials, SIGMA_GYRO, SIGMA_ACCEL, np.random.default_rng(0))
        c = nf.heading_candidates(w[..., 1], f, LAT)
        return nf.nearest_candidate_error(c.pair, headings[:, None])

    t_nav = best_time(navlib_run)
    w, f = nf.simulate_static_outputs(hpr, LAT, 1000, SIGMA_GYRO, SIGMA_ACCEL, np.random.default_rng(0))
    norm = np.linalg.norm(f, axis=-1)
    w_y, f_y = w[..., 1].tolist(), f[..., 1].tolist()

    def python_loop():
        return [[_python_trial(w_y[h][k], f_y[h][k], norm[h, k], headings[h]) for k in range(1000)] for h in range(len(headings))]

    t_py = best_time(python_loop, repeat=1)
    total = len(headings) * n_trials
    return [
        Result(
            "single-axis Monte Carlo (Fig. 4)",
            "navlib (numpy, vectorised)",
            total / t_nav,
            "trials/s",
            t_nav,
            note=f"{len(headings)} headings x {n_trials} trials incl. simulation",
        ),
        Result(
            "single-axis Monte Carlo (Fig. 4)",
            "plain Python loop",
            len(headings) * 1000 / t_py,
            "trials/s",
            t_py,
            note="estimation only (outputs pre-simulated)",
        ),
    ]


CASES = [single_axis_monte_carlo]
