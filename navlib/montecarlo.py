"""Monte Carlo at scale: vectorised batches, one random stream per trial, any executor.

A Monte Carlo study is a function of the trial index alone: trial ``i`` draws
from its own stream, ``SeedSequence(seed, spawn_key=(i,))``, the same stream
``SeedSequence(seed).spawn(n)[i]`` would give, without creating all ``n``
children. Trials are grouped into batches so that the work inside a batch is
vectorised numpy; batches are independent, so they can run serially, in a
process pool, or on a cluster through any :class:`concurrent.futures.Executor`
(for dask: ``distributed.Client(...).get_executor()``). Because every number
depends only on the trial index and the seed, the result is bit-identical
whatever the executor and the batch size.

Example::

    def trial_batch(ids, streams, heading):
        noise = streams.normal((3,))              # (len(ids), 3), row j from trial ids[j]
        return {"err": noise.sum(-1) + heading}

    out = montecarlo.run(trial_batch, 10_000, seed=1, batch_size=1000, heading=0.3)
    out["err"].shape   # (10000,)
"""
from __future__ import annotations

import os
from collections.abc import Callable
from concurrent.futures import Executor
from functools import partial
from typing import Any

import numpy as np

from ._typing import ArrayLike
from ._validate import flag, integer, text

__all__ = ["TrialStreams", "run"]


class TrialStreams:
    """Independent random streams for a batch of trials.

    Each draw returns an array with the batch on axis 0; row ``j`` is drawn
    from trial ``ids[j]``'s own generator, so it does not depend on which
    other trials share the batch.

    Parameters
    ----------
    seed : int
        Master seed of the study.
    ids : array_like of int, shape (B,)
        Trial indices of the batch.
    """

    def __init__(self, seed: int, ids: ArrayLike) -> None:
        _check_args(1, seed, 1)
        ids = np.asarray(ids)
        if ids.ndim != 1 or ids.size == 0 or not np.issubdtype(ids.dtype, np.integer) or ids.min() < 0:
            raise ValueError(f"ids: expected a non-empty 1-D array of non-negative trial indices, got {ids!r:.60}")
        self.ids = ids.astype(np.int64)
        self._rngs = [np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(int(i),))) for i in self.ids]

    def __len__(self) -> int:
        return self.ids.size

    def _stack(self, method: str, shape, **kw) -> np.ndarray:
        shape = tuple(np.atleast_1d(shape)) if shape != () else ()
        return np.stack([getattr(r, method)(size=shape, **kw) for r in self._rngs])

    def normal(self, shape: int | tuple[int, ...] = (), loc: float = 0.0, scale: float = 1.0) -> np.ndarray:
        """Normal draws, shape ``(B, *shape)``."""
        return self._stack("normal", shape, loc=loc, scale=scale)

    def uniform(self, shape: int | tuple[int, ...] = (), low: float = 0.0, high: float = 1.0) -> np.ndarray:
        """Uniform draws on [low, high), shape ``(B, *shape)``."""
        return self._stack("uniform", shape, low=low, high=high)

    def generators(self) -> list[np.random.Generator]:
        """The per-trial generators, for draws the helpers above do not cover."""
        return list(self._rngs)


def _run_batch(batch_fn, seed, ids, kwargs):
    return batch_fn(ids, TrialStreams(seed, ids), **kwargs)


def _progress_bar(total: int, label: str):
    from tqdm.auto import tqdm
    return tqdm(total=total, desc=label, unit="trials", mininterval=1.0, dynamic_ncols=True)


def _check_args(n_trials, seed, batch_size):
    for name, v, lo in (("n_trials", n_trials, 1), ("seed", seed, 0), ("batch_size", batch_size, 1)):
        integer(v, name, minimum=lo)


def run(batch_fn: Callable[..., dict[str, np.ndarray]], n_trials: int, seed: int, *, batch_size: int = 1000,
        executor: Executor | None = None, progress: bool | None = None, label: str = "trials",
        **kwargs: Any) -> dict[str, np.ndarray]:
    """Run ``n_trials`` Monte Carlo trials in batches and concatenate the results.

    Parameters
    ----------
    batch_fn : callable
        ``batch_fn(ids, streams, **kwargs) -> dict[str, ndarray]`` computes a
        batch: ``ids`` (B,) are the trial indices, ``streams`` a
        :class:`TrialStreams`; every returned array has the batch on axis 0.
        With a process or cluster executor it must be importable (a module-level
        function), as usual for pickling.
    n_trials : int
    seed : int
        Master seed; trial ``i`` uses ``SeedSequence(seed, spawn_key=(i,))``.
    batch_size : int
        Trials per batch (memory and vectorisation trade-off; does not change
        the result).
    executor : concurrent.futures.Executor, optional
        Runs the batches (e.g. ``ProcessPoolExecutor`` or a dask client's
        ``get_executor()``); default: serially in this process.
    progress : bool, optional
        Show a progress bar (``tqdm.auto``: a widget in Jupyter, a line on stderr elsewhere) as
        batches complete. Default: on, unless the environment variable ``NAVLIB_PROGRESS`` is ``0``
        (set by ``make reproduce`` and the tests, so executed notebooks keep no progress output).
    **kwargs
        Passed to every ``batch_fn`` call (study parameters).

    Returns
    -------
    dict[str, ndarray]
        Each key's arrays concatenated along axis 0, in trial order.
    """
    if not callable(batch_fn):
        raise ValueError(f"batch_fn: expected a callable, got {type(batch_fn).__name__}")
    _check_args(n_trials, seed, batch_size)
    progress = os.environ.get("NAVLIB_PROGRESS", "1").strip() != "0" if progress is None else flag(progress, "progress")
    text(label, "label")
    if executor is not None and not isinstance(executor, Executor) and not hasattr(executor, "submit"):
        raise ValueError(f"executor: expected a concurrent.futures.Executor, got {type(executor).__name__}")
    batches = [np.arange(s, min(s + batch_size, n_trials)) for s in range(0, n_trials, batch_size)]
    job = partial(_run_batch, batch_fn, int(seed))
    results = [None] * len(batches)
    bar = _progress_bar(n_trials, label) if progress else None
    try:
        if executor is None:
            outcomes = (job(ids, kwargs) for ids in batches)
        else:
            futures = [executor.submit(job, ids, kwargs) for ids in batches]
            outcomes = (fut.result() for fut in futures)     # in order: results stay in trial order
        for k, outcome in enumerate(outcomes):
            results[k] = outcome
            if bar is not None:
                bar.update(len(batches[k]))
    finally:
        if bar is not None:
            bar.close()
    keys = results[0].keys()
    for k, r in enumerate(results):
        if r.keys() != keys:
            raise ValueError(f"batch_fn: batch {k} returned keys {sorted(r)}, expected {sorted(keys)}")
    return {key: np.concatenate([np.asarray(r[key]) for r in results], axis=0) for key in keys}
