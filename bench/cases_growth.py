"""Cost growth: each main kernel timed at sizes from 10^3 to 10^7 samples (10^5 with --quick), each size in its
own interpreter so that its peak memory (maximum resident set) is its own. Reports the exponent of time against
size fitted over the sizes >= 10^4 (1 = linear in the work; the smallest size is mostly call overhead) and the
peak memory beyond the interpreter's after import and a warm-up call, in bytes per sample (the call's inputs, about
100 B per sample, included). The curves go to build/bench-growth.json, which the site's benchmarks page draws."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import numpy as np

from bench.run import ROOT, Result

SETUP = """import json, resource, time
import numpy as np
from navlib import analysis, geodesy, montecarlo, strapdown
from navlib.filters import mahony, quaternion_kf, zupt_ins
from navlib.imu import ImuSamples

def inputs(n):
    rng = np.random.default_rng(0)
    w = rng.normal(0.0, 0.01, (n, 3))
    f = np.tile([0.0, 0.0, 9.81], (n, 1)) + rng.normal(0.0, 0.01, (n, 3))
    return w, f, np.tile([0.0, 20.0, -40.0], (n, 1))

def batch(ids, streams):                           # one trial: ten normal draws from its own stream
    return {{"x": streams.normal(10).sum(axis=1)}}

q0, B_n, lla0 = np.array([1.0, 0.0, 0.0, 0.0]), np.array([0.0, 20.0, -40.0]), np.array([0.5, 0.1, 0.0])

def call(n):
    w, f, m_b = inputs(n)
    {call}

call(1000)                                          # compile or load the kernel, touch every code path
base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
start = time.perf_counter()
call({n})
seconds = time.perf_counter() - start
peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
print(json.dumps({{"seconds": seconds, "extra_kb": peak - base}}))
"""
KERNELS = {
    "filters.mahony (MARG)": "mahony.mahony(ImuSamples(w, f, 0.01), q0, m_b=m_b)",
    "filters.quaternion_kf (MARG)": "quaternion_kf.quaternion_kf(ImuSamples(w, f, 0.01), q0, m_b=m_b, B_n=B_n)",
    "filters.zupt_ins.run_filter": "zupt_ins.run_filter(ImuSamples(w, f, 0.01), zupt_ins.Start(lla0, q0), "
    "np.arange(n) % 100 < 30)",
    "strapdown.integrate": "strapdown.integrate(lla0, np.zeros(3), q0, w, f, 0.01)",
    "geodesy.geodetic2gk": "geodesy.geodetic2gk(np.full(n, 30.0) + w[:, 0], np.full(n, 114.3) + w[:, 1], deg=True)",
    "analysis.allan_deviation": "analysis.allan_deviation(w[:, 0], 0.01)",
    "montecarlo.run (trials)": "montecarlo.run(batch, n, 1, batch_size=10_000, progress=False)",
}
# zupt_ins keeps per-sample states and covariance diagonals (~2 GB at 10^7); a Monte Carlo trial owns a seed sequence
MAX_SIZE = {"filters.zupt_ins.run_filter": 10**6, "montecarlo.run (trials)": 10**6}


def _one(call: str, n: int) -> dict:
    code = SETUP.format(call=call, n=n)
    out = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        check=True,
        cwd=ROOT,
        env=dict(os.environ, NAVLIB_PROGRESS="0"),
    )
    return json.loads(out.stdout.strip().splitlines()[-1])


def growth(quick: bool = False) -> list[Result]:
    top = 5 if quick else 7
    rows, curves = [], {}
    for name, call in KERNELS.items():
        sizes = [10**k for k in range(3, top + 1) if 10**k <= MAX_SIZE.get(name, 10**7)]
        runs = [_one(call, n) for n in sizes]
        t = np.array([r["seconds"] for r in runs])
        fit = np.array(sizes) >= 10**4
        exponent = float(np.polyfit(np.log(np.array(sizes)[fit]), np.log(t[fit]), 1)[0])
        per_sample = max(r["extra_kb"] for r in runs) * 1024 / sizes[-1]
        curves[name] = {"sizes": sizes, "seconds": t.tolist(), "extra_kb": [r["extra_kb"] for r in runs], "exponent": exponent}
        rows.append(
            Result(
                f"growth: {name}",
                "navlib",
                sizes[-1] / t[-1],
                "samples/s",
                float(t[-1]),
                note=f"time ~ N^{exponent:.2f} over 1e4..{sizes[-1]:.0e}; peak +{per_sample:.0f} B/sample at N = {sizes[-1]:.0e}",
            )
        )
    (ROOT / "build").mkdir(exist_ok=True)
    (ROOT / "build" / "bench-growth.json").write_text(json.dumps(curves, indent=1) + "\n", encoding="utf-8")
    return rows


CASES = [growth]
