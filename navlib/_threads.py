"""Threads for work that releases the GIL: compiled kernels over Monte Carlo trials, numpy reductions.

:func:`run_chunks` splits a range into chunks, about four per thread (so that a thread slowed by other
load takes fewer), and runs them on ``NUMBA_NUM_THREADS`` threads of a pool kept for the next call.
Callers make each chunk write only its own outputs (or return its own partial result), so results do
not depend on the number of threads.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from typing import TypeVar

R = TypeVar("R")

_POOLS: dict[int, ThreadPoolExecutor] = {}
os.register_at_fork(after_in_child=_POOLS.clear)  # a forked child has none of the parent's threads


def run_chunks(fn: Callable[[int, int], R], n: int) -> list[R]:
    """Return ``[fn(i0, i1), ...]`` over consecutive chunks ``[i0, i1)`` covering 0 to ``n`` - 1, in order.

    With one thread (``NUMBA_NUM_THREADS = 1``) or ``n <= 1`` this is ``[fn(0, n)]``, run in the caller.
    """
    from numba import config  # here: navlib._validate imports this module, and navlib.units must not load numba

    workers = min(n, config.NUMBA_NUM_THREADS)  # type: ignore[attr-defined]  # numba sets it through globals()
    if workers <= 1:
        return [fn(0, n)]
    if workers not in _POOLS:
        _POOLS[workers] = ThreadPoolExecutor(workers, thread_name_prefix="navlib")
    step = -(-n // (4 * workers))
    return list(_POOLS[workers].map(lambda i0: fn(i0, min(i0 + step, n)), range(0, n, step)))
