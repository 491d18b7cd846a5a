"""The first call of the main entry points in a fresh interpreter with an empty numba cache: compiled on the
call, and after ``python -m navlib.warmup --part N``, the part that compiles it (each in its own interpreter, one
cache directory per case)."""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile

from bench.run import Result
from navlib import warmup

# The entry points navlib.warmup compiles, each called once in a fresh interpreter (imports and inputs not timed):
# the same calls, so the warm case loads exactly what the warm-up cached.
CALLS = ("filters.mahony (MARG)", "filters.quaternion_kf (MARG)", "sensors.simulate_imu", "strapdown.integrate")
SETUP = """import time
from navlib import warmup
call = warmup._calls()[{name!r}]
start = time.perf_counter()
call()
print(time.perf_counter() - start)
"""
GOAL_S = 1.0  # issue 38: each first call within 1 s


def _run(code: str, cache: str) -> float:
    env = dict(os.environ, NUMBA_CACHE_DIR=cache)
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True, cwd=cache)
    return float(out.stdout.strip().splitlines()[-1])


REPEATS = 3  # each first call measured this many times (a fresh cache each): the median and the spread


def _median(times: list[float]) -> tuple[float, str]:
    times = sorted(times)
    return times[len(times) // 2], f"{len(times)} runs: {times[0]:.2f} to {times[-1]:.2f} s"


def first_calls(quick: bool = False) -> list[Result]:
    rows = []
    for name in CALLS:
        part = next(i for i, names in enumerate(warmup.PARTS, 1) if name in names)  # the warm-up part holding it
        colds, warms = [], []
        for _ in range(REPEATS):
            with tempfile.TemporaryDirectory() as cache:
                colds.append(_run(SETUP.format(name=name), cache))
                subprocess.run(
                    [sys.executable, "-m", "navlib.warmup", "--part", str(part)],
                    env=dict(os.environ, NUMBA_CACHE_DIR=cache),
                    capture_output=True,
                    check=True,
                    cwd=cache,
                )
                warms.append(_run(SETUP.format(name=name), cache))
        (cold, cold_spread), (warm, warm_spread) = _median(colds), _median(warms)
        rows += [
            Result(
                f"first call: {name}",
                f"navlib, after python -m navlib.warmup --part {part}",
                1 / warm,
                "calls/s",
                warm,
                goal=1 / GOAL_S,
                note=f"{warm:.2f} s in a fresh interpreter ({warm_spread}; goal <= {GOAL_S:g} s)",
            ),
            Result(
                f"first call: {name}",
                "navlib, empty cache (compiles)",
                1 / cold,
                "calls/s",
                cold,
                note=f"{cold:.2f} s ({cold_spread})",
            ),
        ]
    return rows


CASES = [first_calls]
