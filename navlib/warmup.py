"""Compile navlib's kernels once, ahead of their first call: ``python -m navlib.warmup``.

navlib's filters and simulators are numba kernels compiled on their first call and cached on disk (in the
package's ``__pycache__``, or numba's user cache when that is not writable; ``NUMBA_CACHE_DIR`` moves it).
In a fresh environment that first call waits for the compiler: seconds (about 4 s for Mahony, 8 s for the
quaternion Kalman filter on this project's reference machine). Running this module once after installing (about a minute) compiles
the main entry points in the forms their public functions call them, so that a later first call in any
process loads the compiled code instead (a fraction of a second). ``make reproduce`` runs it first when the
notebooks would compile, in two processes at once (``python -m navlib.warmup --part 1`` and ``--part 2``), so that
every kernel the notebooks call is compiled once, before its notebooks start. ``--also MODULE`` also runs
``MODULE._warm_up()``: a paper's companion module compiles its own kernels there (the core names no paper).
"""

from __future__ import annotations

import importlib
import time
from collections.abc import Callable

import numpy as np

__all__ = ["warmup"]


def _calls() -> dict[str, Callable[[], object]]:
    """One small call of each kernel the notebooks use, in the forms they call it (with and without optional
    sensors), grouped by :data:`PARTS`."""
    from . import alignment, analysis, euler, geodesy, robust, sensors, strapdown, trajectory
    from .filters import heading_fusion, inertial_lowpass, mahony, observations, planar_ekf, quaternion_kf, zupt, zupt_ins
    from .imu import ImuSamples

    n = 200
    w_ib_b, f_b = np.zeros((n, 3)), np.tile([0.0, 0.0, 9.81], (n, 1))
    m_b, B_n = np.tile([0.0, 20.0, -40.0], (n, 1)), np.array([0.0, 20.0, -40.0])
    imu, q0 = ImuSamples(w_ib_b, f_b, 0.01), np.array([1.0, 0.0, 0.0, 0.0])
    t, x0 = 0.5 * np.arange(n), np.array([0.0, 0.0, 0.0, 1.0, 0.0])

    def planar() -> object:
        truth = planar_ekf.propagate(x0, 0.5, n - 1)
        config = planar_ekf.EkfConfig(Q=np.full(5, 1e-4), R=np.full(5, 0.01), gate=9.0)
        planar_ekf.dead_reckoning(t, truth[:, 3], truth[:, 4], x0)
        planar_ekf.dead_reckoning(t, truth[:, 3].copy(), truth[:, 4].copy(), x0)  # columns and contiguous inputs
        return planar_ekf.filter_grid(t, truth, x0, config)

    return {
        "euler.integrate_euler": lambda: euler.integrate_euler(np.zeros(3), w_ib_b, 0.01),
        "strapdown.integrate_attitude": lambda: strapdown.integrate_attitude(q0, w_ib_b, 0.01),
        "analysis.allan_deviation": lambda: analysis.allan_deviation(w_ib_b, 0.01),
        "filters.mahony (IMU)": lambda: mahony.mahony(imu, q0),
        "filters.mahony (MARG)": lambda: mahony.mahony(imu, q0, m_b=m_b),
        "filters.heading_fusion": lambda: heading_fusion.fuse_rtk_heading(
            np.full(n, 0.3), observations.RtkHeading(np.full(n, 0.5), np.arange(n) % 5 == 0), 0.01
        ),
        "filters.quaternion_kf (MARG)": lambda: quaternion_kf.quaternion_kf(imu, q0, m_b=m_b, B_n=B_n),
        "filters.planar_ekf": planar,
        "filters.inertial_lowpass": lambda: (
            inertial_lowpass.inertial_lowpass(imu),
            inertial_lowpass.inertial_lowpass(imu, m_b),
        ),
        "sensors.simulate_imu": lambda: (
            sensors.simulate_imu(w_ib_b, f_b, 0.01, sensors.imu_model("MPU-6050"), np.random.default_rng(0)),
            # the runs in batches of two: each batch reads the broadcast exact samples (another specialisation)
            list(sensors.simulate_imu_batches(w_ib_b, f_b, 0.01, sensors.imu_model("MTi-100"), np.random.default_rng(0), 2, 2)),
        ),
        "strapdown.integrate": lambda: strapdown.integrate(np.array([0.5, 0.1, 0.0]), np.zeros(3), q0, w_ib_b, f_b, 0.01),
        "analysis.error_statistics": lambda: analysis.error_statistics(np.zeros((n, 3)), np.zeros((n, 3))),
        "robust.longest_repeat": lambda: robust.longest_repeat(f_b),
        "trajectory.from_profiles": lambda: trajectory.from_profiles(t, [0.5, 0.1, 0.0], w_ib_b, w_ib_b),
        "alignment.tilt_heading": lambda: alignment.tilt_heading(f_b, m_b),
        "geodesy": lambda: (
            geodesy.gk2geodetic(*geodesy.geodetic2gk(np.full(n, 0.5), np.full(n, 2.0)), zone=39),
            geodesy.convergence(np.full(n, 0.5), np.full(n, 2.0)),
        ),
        "filters.quaternion_kf.measurement_model": lambda: quaternion_kf.measurement_model(np.tile(q0, (n, 1)), B_n),
        "filters.zupt.error_state_matrix": lambda: zupt.error_state_matrix(np.eye(3), f_b[0]),
        # one specialisation serves every option (notebooks 05, 05b and 06 share it)
        "filters.zupt_ins.run_filter": lambda: zupt_ins.run_filter(
            imu, zupt_ins.Start(np.array([0.5, 0.1, 0.0]), q0), np.ones(n, bool)
        ),
    }


PARTS = (
    (
        "filters.mahony (IMU)",
        "filters.mahony (MARG)",
        "filters.quaternion_kf (MARG)",
        "filters.quaternion_kf.measurement_model",
        "euler.integrate_euler",
        "analysis.error_statistics",
        "trajectory.from_profiles",
        "robust.longest_repeat",
        "alignment.tilt_heading",
        "strapdown.integrate_attitude",
        "analysis.allan_deviation",
        "filters.heading_fusion",
        "sensors.simulate_imu",
    ),
    (
        "filters.planar_ekf",  # first: the paper kernels of part 1 load its Kalman update from the cache
        "filters.inertial_lowpass",
        "strapdown.integrate",
        "filters.zupt_ins.run_filter",
        "filters.zupt.error_state_matrix",
        "geodesy",
    ),
)
"""The entry points in two parts, compiled in two processes at once on two cores (``--part 1``, ``--part 2``); the
first also compiles a paper's own kernels (``--also navlib.papers.rotation_bias``; ~26 s of CPU each on an empty
cache, within about a second of each other: the wait before the notebooks start)."""


def warmup(verbose: bool = True, part: int | None = None) -> dict[str, float]:
    """Call each kernel's entry point once on a small input; return the seconds each took (compiling or loading).

    Parameters
    ----------
    verbose : bool
        Print each entry point and its time as it finishes.
    part : int, optional
        Only the entry points of ``PARTS[part - 1]`` (1 or 2: two processes compile the two at once); default all.

    Examples
    --------
    >>> from navlib import warmup
    >>> seconds = warmup.warmup(verbose=False, part=1)                # fast once numba's cache holds the kernels
    >>> len(seconds), sorted(seconds)[-1]                          # seconds per entry point
    (13, 'trajectory.from_profiles')
    """
    if part is not None and part not in range(1, len(PARTS) + 1):
        raise ValueError(f"part: expected None or an integer from 1 to {len(PARTS)}, got {part!r}")
    calls = _calls()
    names = list(calls) if part is None else PARTS[part - 1]
    seconds = {}
    for name in names:
        start = time.perf_counter()
        calls[name]()
        seconds[name] = time.perf_counter() - start
        if verbose:
            print(f"{name:32s} {seconds[name]:6.2f} s", flush=True)
    return seconds


def _also(module: str) -> float:
    """Run ``module._warm_up()``, the calls that compile the kernels of a module outside the core (a paper's
    companion, named by the caller: the core names no paper); its seconds."""
    start = time.perf_counter()
    importlib.import_module(module)._warm_up()
    return time.perf_counter() - start


if __name__ == "__main__":
    import argparse

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--part", type=int, choices=range(1, len(PARTS) + 1), help="only this part of PARTS")
    ap.add_argument("--also", action="append", default=[], metavar="MODULE", help="also run MODULE._warm_up()")
    args = ap.parse_args()
    total = sum(warmup(part=args.part).values())
    for module in args.also:
        seconds = _also(module)
        print(f"{module:32s} {seconds:6.2f} s", flush=True)
        total += seconds
    print(f"compiled and cached in {total:.0f} s; later first calls load the compiled code")
