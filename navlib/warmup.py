"""Compile navlib's kernels once, ahead of their first call: ``python -m navlib.warmup``.

navlib's filters and simulators are numba kernels compiled on their first call and cached on disk (in the
package's ``__pycache__``, or numba's user cache when that is not writable; ``NUMBA_CACHE_DIR`` moves it).
In a fresh environment that first call waits for the compiler: seconds (about 4 s for Mahony, 8 s for the
quaternion Kalman filter on this project's reference machine). Running this module once after installing (about a minute) compiles
the main entry points in the forms their public functions call them, so that a later first call in any
process loads the compiled code instead (a fraction of a second). ``make reproduce`` runs it first when the
notebooks would compile, so that kernels several notebooks share are compiled once.
"""

from __future__ import annotations

import time
from collections.abc import Callable

import numpy as np

__all__ = ["warmup"]


def _calls() -> dict[str, Callable[[], object]]:
    """One small call of each main entry point, with and without its optional sensors."""
    from . import sensors, strapdown
    from .filters import mahony, quaternion_kf, zupt_ins
    from .imu import ImuSamples

    n = 200
    w_ib_b, f_b = np.zeros((n, 3)), np.tile([0.0, 0.0, 9.81], (n, 1))
    m_b, B_n = np.tile([0.0, 20.0, -40.0], (n, 1)), np.array([0.0, 20.0, -40.0])
    imu, q0 = ImuSamples(w_ib_b, f_b, 0.01), np.array([1.0, 0.0, 0.0, 0.0])
    return {
        "filters.mahony (IMU)": lambda: mahony.mahony(imu, q0),
        "filters.mahony (MARG)": lambda: mahony.mahony(imu, q0, m_b=m_b),
        "filters.quaternion_kf (MARG)": lambda: quaternion_kf.quaternion_kf(imu, q0, m_b=m_b, B_n=B_n),
        "sensors.simulate_imu": lambda: sensors.simulate_imu(
            w_ib_b, f_b, 0.01, sensors.imu_model("MPU-6050"), np.random.default_rng(0)
        ),
        "strapdown.integrate": lambda: strapdown.integrate(np.array([0.5, 0.1, 0.0]), np.zeros(3), q0, w_ib_b, f_b, 0.01),
        # one specialisation serves every option (notebooks 05, 05b and 06 share it)
        "filters.zupt_ins.run_filter": lambda: zupt_ins.run_filter(
            imu, zupt_ins.Start(np.array([0.5, 0.1, 0.0]), q0), np.ones(n, bool)
        ),
    }


def warmup(verbose: bool = True) -> dict[str, float]:
    """Call each main entry point once on a small input; return the seconds each took (compiling or loading).

    Parameters
    ----------
    verbose : bool
        Print each entry point and its time as it finishes.

    Examples
    --------
    >>> from navlib import warmup
    >>> seconds = warmup.warmup(verbose=False)                        # fast once numba's cache holds the kernels
    >>> len(seconds), sorted(seconds)[-1]                          # seconds per entry point
    (6, 'strapdown.integrate')
    """
    seconds = {}
    for name, call in _calls().items():
        start = time.perf_counter()
        call()
        seconds[name] = time.perf_counter() - start
        if verbose:
            print(f"{name:32s} {seconds[name]:6.2f} s", flush=True)
    return seconds


if __name__ == "__main__":
    total = sum(warmup().values())
    print(f"compiled and cached in {total:.0f} s; later first calls load the compiled code")
