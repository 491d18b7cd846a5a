"""Monte Carlo at scale: 10⁷ north-finding trials through navlib.montecarlo, serial vs 2 workers."""

from __future__ import annotations

import os
import time
from concurrent.futures import ProcessPoolExecutor

import numpy as np

from bench.run import Result
from navlib import earth, montecarlo, units
from navlib.papers import north_finding as nf

SEED, BATCH = 2000, 100_000
GRID = np.stack(
    np.meshgrid([0.0, 20.0, 28.361735, 45.0, 60.0], np.arange(5.0, 360.0, 10.0), [0.003, 0.01, 0.03], indexing="ij"), -1
).reshape(-1, 3)  # latitude (deg) x heading (deg) x gyro (deg/h)
SIGMA_ACCEL = units.ug(100)


def single_axis_batch(ids, streams, reps):
    """Notebook 01's sweep: one averaged static reading per trial at grid point ``ids // reps``; heading error (rad)."""
    lat_d, psi_d, gyro_dph = GRID[ids // reps].T
    lat, psi = units.deg(lat_d), units.deg(psi_d)
    w_y = earth.OMEGA_IE * np.cos(lat) * np.cos(psi) + units.deg_per_h(gyro_dph) * streams.normal()
    g = earth.gravity(lat)
    f_b = np.stack([np.zeros_like(g), np.zeros_like(g), g], -1) + SIGMA_ACCEL * streams.normal((3,))
    return {"err": nf.nearest_candidate_error(nf.heading_candidates(w_y, f_b, lat).pair, psi)}


def _timed(n, executor=None):
    t0 = time.perf_counter()
    out = montecarlo.run(single_axis_batch, n, SEED, batch_size=BATCH, executor=executor, progress=False, reps=-(-n // len(GRID)))
    return out["err"], time.perf_counter() - t0


QUIET = {  # dask's own sampling (default period), each waking the worker's event loop and taking the GIL
    "distributed.worker.profile.enabled": False,  # stacks of the running task (10 ms)
    "distributed.admin.tick.interval": "1s",  # event-loop watchdog (20 ms)
    "distributed.admin.system-monitor.interval": "5s",  # CPU, memory and network metrics (500 ms)
    "distributed.worker.memory.monitor-interval": "1s",  # memory-limit checks (100 ms)
}
"""dask settings for CPU-bound batches on workers that occupy every core: with the defaults the workers'
event loops took 3-10 % of a core beside each task and the tasks ran 15-25 % slower (three alternating
rounds of 2·10⁶ trials here: 14.3, 14.1, 15.5 s with the defaults, 12.3, 11.8, 11.9 s with these)."""


def monte_carlo_scale(quick: bool):
    """10⁷ trials (quick: 2·10⁵) serially, on a 2-process pool, on a 2-worker dask LocalCluster (with dask's
    defaults, then with :data:`QUIET`), and serially again.

    Goal: 2 workers >= 1.7x serial, results bit-identical. One timed run each (no warm-up run: at this
    scale start-up is part of the cost a user pays). The serial run is repeated after the parallel ones and
    the speed-ups are taken against the mean of the two: this machine's speed drifts by 10-30 % over a
    minute (two serial runs of the same trials a minute apart took 45 s and 39 s), so one serial run before
    the others would compare different moments. The dask workers import navlib and load the compiled
    kernels when the cluster starts (reported in the note, 0.6-1.1 s per worker here); the pool's forked
    workers inherit both."""
    n = 200_000 if quick else 10_000_000
    case = f"Monte Carlo, {n:.0e} north-finding trials"
    ref, t_before = _timed(n)
    with ProcessPoolExecutor(2) as pool:
        parallel = [("navlib 2-process pool", *_timed(n, pool), "", True)]
    try:
        import dask
        from distributed import Client, LocalCluster
    except ImportError:
        dask = None
    configs = [("dask defaults", {}), ("QUIET settings", QUIET)] if dask else []
    for name, settings in configs:
        with (
            dask.config.set(settings),
            LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster,
            Client(cluster) as client,
        ):
            # Part of the cluster's start-up, like the workers' own: each worker imports navlib and loads the
            # compiled kernels once (the pool's forked workers inherit both from this process).
            t0 = time.perf_counter()
            client.run(_ready)
            t_ready = time.perf_counter() - t0
            parallel.append(
                (
                    f"navlib dask 2 workers, {name}",
                    *_timed(n, client.get_executor()),
                    f"; LocalCluster; worker start-up (imports, kernel loads) {t_ready:.1f} s, not in the time",
                    settings is QUIET,
                )
            )
    again, t_after = _timed(n)
    serial = 2 * n / (t_before + t_after)
    rows = [
        Result(
            case,
            "navlib serial",
            serial,
            "trials/s",
            (t_before + t_after) / 2,
            note=f"mean of a run before ({n / t_before:.3g} trials/s) and after ({n / t_after:.3g}) the "
            f"parallel ones; bit-identical: {np.array_equal(again, ref)}; {os.cpu_count()} cores",
        )
    ]
    for name, err, t, extra, goal in parallel:
        rows.append(
            Result(
                case,
                name,
                n / t,
                "trials/s",
                t,
                goal=1.7 * serial if goal else None,
                note=f"{'goal: 1.7x serial; ' if goal else ''}bit-identical to serial: {np.array_equal(err, ref)}{extra}",
            )
        )
    return rows


def _ready():
    """Import navlib and load the batch's compiled kernels in a fresh worker (8 trials)."""
    single_axis_batch(np.arange(8), montecarlo.TrialStreams(SEED, np.arange(8)), reps=1)


CASES = [monte_carlo_scale]
