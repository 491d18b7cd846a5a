#!/usr/bin/env python3
"""Seed study: do ``calibration.characterise``'s intervals hold the simulated truth as often as they say?

    python data/seed_studies/allan_coverage.py --seeds 4001-4200 [--out data/seed_studies/allan_coverage.csv]

Each seed simulates one static record per truth and record length (gyro and accelerometer triads of the same noise
model, independent streams: six axes), runs ``characterise(..., rate_random_walk=True)`` (95 % intervals) and
counts, per term (N, B, K), the axes whose interval holds the truth (an absent term's truth is 0: its interval
must reach down to 0). The table has one row per record length, truth, seed and term (``inside`` of 6 axes,
``kept``: axes where the term came out non-zero); the header states the coverage per cell with its binomial
standard error. tests/faults/test_noise_model_selection.py re-runs the first seeds of the table (they must agree
row for row) and reads the coverage from it.
"""

from __future__ import annotations

import argparse
import csv
import io
from pathlib import Path

import numpy as np
from scipy.signal import lfilter

from navlib import analysis, calibration

HERE = Path(__file__).resolve().parent
DT = 0.1  # 10 Hz
LENGTHS = {"30min": 18_000, "2h": 72_000}
WHITE, SIGMA_GM, TC, RRW = 1e-3, 3e-4, 10.0, 8.7e-6  # N, Gauss-Markov sigma and T_c (peak 19 s), K
TRUTHS = {  # (N, sigma_gm, K): white + Gauss-Markov (B = GM_ALLAN_PEAK sigma) + rate random walk
    "white": (WHITE, 0.0, 0.0),
    "white+rrw": (WHITE, 0.0, RRW),
    "white+bi": (WHITE, SIGMA_GM, 0.0),
    "white+bi+rrw": (WHITE, SIGMA_GM, RRW),
}
TERMS = ("N", "B", "K")


def record(seed: int, n: int, truth: str) -> tuple[np.ndarray, np.ndarray]:
    """Gyro (rad/s) and accelerometer (m/s^2) records of ``n`` samples of one truth, from ``seed``."""
    white, sigma, k = TRUTHS[truth]
    rng = np.random.default_rng(seed)
    x = white / np.sqrt(DT) * rng.standard_normal((2, n, 3))
    if sigma:
        a = np.exp(-DT / TC)
        drive = sigma * np.sqrt(1 - a * a) * rng.standard_normal((2, n, 3))
        drive[:, 0] = sigma * rng.standard_normal((2, 3))  # the stationary start
        x += lfilter([1.0], [1.0, -a], drive, axis=1)  # b[k] = a b[k-1] + drive[k]
    if k:
        x += np.cumsum(k * np.sqrt(DT) * rng.standard_normal((2, n, 3)), axis=1)
    return x[0], x[1] + 9.8


def truth_values(truth: str) -> dict[str, float]:
    white, sigma, k = TRUTHS[truth]
    return {"N": white, "B": analysis.GM_ALLAN_PEAK * sigma, "K": k}


def seed_rows(seed: int, length: str, truth: str) -> list[dict]:
    """The table's rows of one seed, record length and truth."""
    c = calibration.characterise(*record(seed, LENGTHS[length], truth), DT, rate_random_walk=True)
    true = truth_values(truth)
    rows = []
    for term, value, ci in (
        ("N", "noise_density", "noise_density_ci"),
        ("B", "bias_instability", "bias_instability_ci"),
        ("K", "rate_random_walk", "rate_random_walk_ci"),
    ):
        lo = np.concatenate([getattr(t, ci)[:, 0] for t in (c.gyro, c.accel)])
        hi = np.concatenate([getattr(t, ci)[:, 1] for t in (c.gyro, c.accel)])
        est = np.concatenate([getattr(t, value) for t in (c.gyro, c.accel)])
        inside = int(np.sum((lo <= true[term]) & (true[term] <= hi)))
        rows.append(
            {"length": length, "truth": truth, "seed": seed, "term": term, "inside": inside, "kept": int(np.sum(est > 0))}
        )
    return rows


def header(rows: list[dict], seeds: list[int]) -> str:
    lines = [
        "# Seed study of calibration.characterise's 95 % intervals: "
        f"data/seed_studies/allan_coverage.py --seeds {seeds[0]}-{seeds[-1]}",
        f"# {len(seeds)} seeds x 6 axes per cell; 10 Hz; truths (N, B, K) = white {WHITE:g}; Gauss-Markov sigma {SIGMA_GM:g}, "
        f"T_c {TC:g} s (B = {analysis.GM_ALLAN_PEAK * SIGMA_GM:.4g}); K {RRW:g}. Coverage (binomial s.e.), axes kept:",
    ]
    for length in LENGTHS:
        for truth in TRUTHS:
            cells = []
            for term in TERMS:
                sel = [r for r in rows if r["length"] == length and r["truth"] == truth and r["term"] == term]
                n_axes = 6 * len(sel)
                p = sum(r["inside"] for r in sel) / n_axes
                kept = sum(r["kept"] for r in sel) / n_axes
                cells.append(f"{term} {100 * p:.1f} % ({100 * np.sqrt(p * (1 - p) / n_axes):.1f}), kept {100 * kept:.0f} %")
            lines.append(f"# {length} {truth}: " + "; ".join(cells))
    return "\n".join(lines) + "\n"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", required=True, help="FIRST-LAST")
    parser.add_argument("--out", default=str(HERE / "allan_coverage.csv"))
    args = parser.parse_args()
    first, _, last = args.seeds.partition("-")
    seeds = list(range(int(first), int(last or first) + 1))
    rows = [r for length in LENGTHS for truth in TRUTHS for seed in seeds for r in seed_rows(seed, length, truth)]
    out = io.StringIO()
    writer = csv.DictWriter(out, fieldnames=["length", "truth", "seed", "term", "inside", "kept"], lineterminator="\n")
    writer.writeheader()
    writer.writerows(rows)
    Path(args.out).write_text(header(rows, seeds) + out.getvalue(), encoding="utf-8")
    print(header(rows, seeds), end="")


if __name__ == "__main__":
    main()
