#!/usr/bin/env python3
"""Seed study: run a notebook at full scale on calibration seeds and table the values its tolerances rest on.

    python data/seed_studies/run.py 04_mimu_mag_rtk --seeds 3001-3012 [--also CHECK ...] [--jobs 2]
    python data/seed_studies/run.py 04_mimu_mag_rtk --rewrite      # the header under the current rule
    python data/seed_studies/run.py 04_mimu_mag_rtk --seeds 3001-3036 --extend   # run only the seeds the table lacks

Each seed is a run of the notebook as ``make seeds`` does it (``tools/reproduce.py``: ``SEED`` injected after the
parameters cell, teaching mode, full scale; outputs in ``build/seed_studies/<seed>/``). From each run's results this
writes ``data/seed_studies/<notebook>.csv``: one row per seed and per ``repro.check_study`` check of the notebook
(and per ``--also`` check, for the record), with the check's value and its target (empty where the value is a
regression of the stand-in rather than a prediction). ``navlib.repro.seed_spread`` reads the table; the tolerance
rule (``navlib.repro.study_k(n)`` x the RMS of value - target, or ``study_k(n, about_mean=True)`` x the sd of a value:
one new seed's prediction interval at the ledger's family-wise level) is stated in the header with each check's mean,
sd, RMS and tolerance. The seeds go to ``calibration_seeds.csv``: the seed sweep refuses them.
"""

from __future__ import annotations

import argparse
import csv
import io
import json
import os
import sys
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(ROOT / "tools"))

import reproduce  # noqa: E402  (tools/reproduce.py: the sweep's runner)

from navlib.repro import CHECK_ALPHA, study_k  # noqa: E402


def seed_range(text: str) -> list[int]:
    first, _, last = text.partition("-")
    return list(range(int(first), int(last or first) + 1))


def run(stem: str, seed: int, timeout: int) -> tuple[int, list[dict]]:
    out = ROOT / "build" / "seed_studies" / str(seed)
    reproduce.run_seed(ROOT / "notebooks" / f"{stem}.ipynb", seed, out, timeout)
    res = json.loads((out / stem / "results.json").read_text())
    return seed, res["checks"]


def table(stem: str, runs: list[tuple[int, list[dict]]], also: list[str]) -> list[dict]:
    rows = []
    for seed, checks in sorted(runs):
        for c in checks:
            study = c.get("study")
            if study and study["name"] == stem or c["name"] in also:
                target = study["target"] if study else None
                rows.append(
                    {
                        "seed": seed,
                        "check": c["name"],
                        "value": repr(c["value"]),
                        "target": "" if target is None else repr(target),
                    }
                )
    return rows


def summary(rows: list[dict]) -> list[str]:
    lines = []
    for name in dict.fromkeys(r["check"] for r in rows):
        x = np.array([float(r["value"]) - float(r["target"] or 0.0) for r in rows if r["check"] == name])
        about_target = any(r["target"] for r in rows if r["check"] == name)
        rms = np.sqrt(np.mean(x**2)) if about_target else x.std(ddof=1)
        what = "value - target" if about_target else "value"
        k = study_k(x.size, about_mean=not about_target)
        lines.append(
            f"# {name}: {what} over {x.size} seeds: mean {x.mean():.5g}, sd {x.std(ddof=1):.4g}, "
            f"min {x.min():.5g}, max {x.max():.5g}; tolerance {k:.3f} x {'RMS' if about_target else 'sd'} "
            f"= {k * rms:.4g}"
        )
    return lines


def record_seeds(stem: str, seeds: list[int]) -> None:
    path = HERE / "calibration_seeds.csv"
    text = path.read_text(encoding="utf-8")
    row = f"{stem},{min(seeds)},{max(seeds)},{stem}.csv (data/seed_studies/run.py)"
    lines = [ln for ln in text.splitlines() if not (ln.startswith(f"{stem},") and ln.endswith("(data/seed_studies/run.py)"))]
    path.write_text("\n".join([*lines, row]) + "\n", encoding="utf-8")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("notebook", help="notebook stem, e.g. 04_mimu_mag_rtk")
    ap.add_argument("--seeds", type=seed_range, help="calibration seeds, FIRST-LAST")
    ap.add_argument("--rewrite", action="store_true", help="rewrite the table's header under the current rule; run nothing")
    ap.add_argument("--extend", action="store_true", help="keep the table's rows and run only the seeds it lacks")
    ap.add_argument("--also", nargs="*", default=[], help="further checks to table (their margins, for the record)")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--timeout", type=int, default=1800)
    args = ap.parse_args(argv)
    if not args.rewrite and not args.seeds:
        ap.error("--seeds FIRST-LAST is required (or --rewrite)")
    clash = set(args.seeds or ()) & set(reproduce.SWEEP_SEEDS)
    if clash:
        print(f"--seeds: {sorted(clash)} are seeds of the sweep (tools/reproduce.py SWEEP_SEEDS)", file=sys.stderr)
        return 1
    os.environ.update(NAVLIB_ROOT=str(ROOT), MPLBACKEND="Agg", NAVLIB_PROGRESS="0")
    os.environ.pop("NAVLIB_FAST", None)
    out = HERE / f"{args.notebook}.csv"
    kept = []  # the recorded rows (--rewrite, --extend)
    if args.rewrite or args.extend:
        kept = list(csv.DictReader(line for line in out.read_text(encoding="utf-8").splitlines() if not line.startswith("#")))
    rows = kept
    if not args.rewrite:
        new = [s for s in args.seeds if s not in {int(r["seed"]) for r in kept}]
        with ProcessPoolExecutor(args.jobs) as pool:
            runs = list(pool.map(run, [args.notebook] * len(new), new, [args.timeout] * len(new)))
        rows = sorted(kept + table(args.notebook, runs, args.also), key=lambda r: int(r["seed"]))
    seeds = sorted({int(r["seed"]) for r in rows})
    if seeds != list(range(seeds[0], seeds[-1] + 1)):
        print(
            f"the study's seeds are not one range ({seeds[0]}-{seeds[-1]}): calibration_seeds.csv records ranges", file=sys.stderr
        )
        return 1
    buf = io.StringIO()
    writer = csv.DictWriter(buf, ["seed", "check", "value", "target"], lineterminator="\n")
    writer.writeheader()
    writer.writerows(rows)
    command = (
        out.read_text(encoding="utf-8").splitlines()[0]
        if args.rewrite
        else f"# Seed study of notebooks/{args.notebook}.ipynb: data/seed_studies/run.py {args.notebook} --seeds "
        f"{min(seeds)}-{max(seeds)}" + (f" --also {' '.join(args.also)}" if args.also else "")
    )
    head = [
        command,
        "# Full scale, one run per seed (SEED injected after the parameters cell); value and target as recorded.",
        "# Rule (navlib.repro.check_study): |value - target| <= t_n x the RMS of value - target over these n seeds;",
        f"# without a target, |value - mean| <= t_(n-1) sqrt(1 + 1/n) x the sd; t at the two-sided level {CHECK_ALPHA:.3g}",
        "# (navlib.repro.study_k: one new seed's prediction interval, the ledger's family-wise level). Per check:",
        *summary(rows),
    ]
    out.write_text("\n".join(head) + "\n" + buf.getvalue(), encoding="utf-8")
    record_seeds(args.notebook, seeds)
    print("\n".join(head[5:]))
    print(f"wrote {out.relative_to(ROOT)} ({len(rows)} rows)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
