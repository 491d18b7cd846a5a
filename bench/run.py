"""navlib benchmarks: throughput of the kernels, peers side by side in one run.

Each case module ``bench/cases_*.py`` (found automatically) defines ``CASES``, a list of functions that
return :class:`Result` rows (one per implementation). ``make bench`` runs them
all, prints a table with the ratio of every implementation to navlib's and to
the case's performance goal where it has one, and writes ``build/bench.json``.
The goals are the project's own targets, set in each case module beside the
case (e.g. the strapdown batch: 30 trials x 1 h x 100 Hz in 0.5 s); a goal relative to a peer (e.g.
">= 3x pyproj") is computed from the peer's throughput measured in the same run. "vs goal" >= 1 means met.

    .venv/bin/python bench/run.py [--only SUBSTRING] [--quick]
"""

from __future__ import annotations

import argparse
import importlib
import json
import os
import platform
import sys
import time
from dataclasses import asdict, dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
CASE_MODULES = sorted(f"bench.{p.stem}" for p in Path(__file__).parent.glob("cases_*.py"))


@dataclass
class Result:
    case: str
    implementation: str
    throughput: float  # work units per second
    unit: str  # e.g. "samples/s"
    seconds: float  # best wall time of one run
    goal: float | None = None  # the case's goal in the same unit (navlib rows)
    note: str = ""


def best_time(fn, repeat: int = 3) -> float:
    """Best wall time of ``repeat`` calls of ``fn`` (after one warm-up call)."""
    return best_times(fn, rounds=repeat)[0]


def best_times(*fns, rounds: int = 5) -> list[float | None]:
    """Best wall time of each of ``fns`` over ``rounds`` rounds that call each once, in turn (after one
    warm-up call each); None for a ``None`` in ``fns`` (a peer that is not installed). Every ratio to a
    peer or goal uses it: this machine's speed drifts by 10-30 % over seconds, so timing one function and
    then the other compared different moments (in one run navlib's INS step was timed 33 % slower than in
    the run before, filterpy's the same); alternating gives both the same chances."""
    timed = [i for i, fn in enumerate(fns) if fn is not None]
    for i in timed:
        fns[i]()
    best: list[float | None] = [None if fn is None else float("inf") for fn in fns]
    for _ in range(rounds):
        for i in timed:
            t0 = time.perf_counter()
            fns[i]()
            best[i] = min(best[i], time.perf_counter() - t0)
    return best


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", default="", help="run cases whose name contains this (any case)")
    ap.add_argument("--quick", action="store_true", help="smaller problem sizes (smoke test)")
    args = ap.parse_args()
    os.environ.setdefault("NAVLIB_BENCH_QUICK", "1" if args.quick else "0")
    results: list[Result] = []
    for mod_name in CASE_MODULES:
        mod = importlib.import_module(mod_name)
        for case in mod.CASES:
            if args.only and args.only.lower() not in case.__name__.lower():
                continue
            print(f"running {case.__name__} ...", flush=True)
            results.extend(case(quick=args.quick))
    print()
    print(f"{'case':42s} {'implementation':40s} {'throughput':>11s} {'unit':10s} {'vs navlib':>9s} {'vs goal':>8s}  note (goal)")
    for r in results:
        ref = next((x for x in results if x.case == r.case and x.implementation.startswith("navlib")), None)
        ratio = f"{r.throughput / ref.throughput:9.3g}" if ref else " " * 9
        goal = f"{r.throughput / r.goal:8.2f}" if r.goal else " " * 8
        print(f"{r.case:42.42s} {r.implementation:40.40s} {r.throughput:11.4g} {r.unit:10s} {ratio} {goal}  {r.note}")
    out = ROOT / "build" / "bench.json"
    out.parent.mkdir(exist_ok=True)
    out.write_text(
        json.dumps(
            {
                "machine": {"python": platform.python_version(), "cpus": os.cpu_count(), "platform": platform.platform()},
                "quick": args.quick,
                "results": [asdict(r) for r in results],
            },
            indent=1,
        )
        + "\n"
    )
    print(f"\nwrote {out.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
