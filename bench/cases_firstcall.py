"""The first call of the main entry points in a fresh interpreter with an empty numba cache: compiled on the
call, and after ``python -m navlib.warmup`` (each in its own interpreter, one cache directory per case)."""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile

from bench.run import Result

# One call each, timed inside a fresh interpreter (the import is not counted).
CALLS = {
    "filters.mahony": "mahony.mahony(imu, q0, m_b=m_b)",
    "filters.quaternion_kf": "quaternion_kf.quaternion_kf(imu, q0, m_b=m_b, B_n=B_n)",
    "sensors.simulate_imu": "sensors.simulate_imu(w, f, 0.01, sensors.imu_model('MPU-6050'), np.random.default_rng(0))",
    "strapdown.integrate": "strapdown.integrate(np.array([0.5, 0.1, 0.0]), np.zeros(3), q0, w, f, 0.01)",
}
SETUP = """import time
import numpy as np
from navlib import sensors, strapdown
from navlib.filters import mahony, quaternion_kf
from navlib.imu import ImuSamples
w, f = np.zeros((1000, 3)), np.tile([0.0, 0.0, 9.81], (1000, 1))
m_b, B_n = np.tile([0.0, 20.0, -40.0], (1000, 1)), np.array([0.0, 20.0, -40.0])
imu, q0 = ImuSamples(w, f, 0.01), np.array([1.0, 0.0, 0.0, 0.0])
start = time.perf_counter()
{call}
print(time.perf_counter() - start)
"""
GOAL_S = 1.0  # issue 38: each first call within 1 s


def _run(code: str, cache: str) -> float:
    env = dict(os.environ, NUMBA_CACHE_DIR=cache)
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True, cwd=cache)
    return float(out.stdout.strip().splitlines()[-1])


def first_calls(quick: bool = False) -> list[Result]:
    rows = []
    for name, call in CALLS.items():
        with tempfile.TemporaryDirectory() as cache:
            cold = _run(SETUP.format(call=call), cache)
            subprocess.run(
                [sys.executable, "-m", "navlib.warmup"],
                env=dict(os.environ, NUMBA_CACHE_DIR=cache),
                capture_output=True,
                check=True,
                cwd=cache,
            )
            warm = _run(SETUP.format(call=call), cache)
        rows += [
            Result(
                f"first call: {name}",
                "navlib, after python -m navlib.warmup",
                1 / warm,
                "calls/s",
                warm,
                goal=1 / GOAL_S,
                note=f"{warm:.2f} s in a fresh interpreter (goal <= {GOAL_S:g} s)",
            ),
            Result(f"first call: {name}", "navlib, empty cache (compiles)", 1 / cold, "calls/s", cold, note=f"{cold:.2f} s"),
        ]
    return rows


CASES = [first_calls]
