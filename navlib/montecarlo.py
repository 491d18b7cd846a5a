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
from typing import Annotated, Any

import numpy as np
from numpy.typing import NDArray

from ._typing import ArrayLike
from ._validate import Check, Count, Text, boundary, flag, indices

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

    Examples
    --------
    >>> from navlib import montecarlo
    >>> streams = montecarlo.TrialStreams(seed=1, ids=[0, 1, 2])
    >>> a = streams.normal()
    >>> b = montecarlo.TrialStreams(seed=1, ids=[2]).normal()
    >>> bool(a[2] == b[0])                                            # trial 2's draw does not depend on the batch
    True
    """

    @boundary
    def __init__(self, seed: Seed, ids: ArrayLike) -> None:
        ids = indices(ids, "ids")
        if ids.ndim != 1 or ids.size == 0 or not np.issubdtype(ids.dtype, np.integer) or ids.min() < 0:
            raise ValueError(f"ids: expected a non-empty 1-D array of non-negative trial indices, got {ids!r:.60}")
        self._start(seed, ids)

    @classmethod
    def _of(cls, seed: int, ids: NDArray[np.integer]) -> TrialStreams:
        """The streams of a seed and trial indices that the caller (:func:`run`) has checked or made."""
        streams = cls.__new__(cls)
        streams._start(seed, ids)
        return streams

    def _start(self, seed: int, ids: NDArray[np.integer]) -> None:
        self.ids = ids.astype(np.int64)
        self._seed = int(seed)
        self._rngs: list[np.random.Generator] | None = None  # per-trial generators, made on demand (generators(), many draws)
        self._draws = 0
        if self.ids.max() < 2**32:  # one spawn-key word: the states straight from the seed (see _pcg64_states)
            self._states = [
                {"bit_generator": "PCG64", "state": {"state": s, "inc": c}, "has_uint32": 0, "uinteger": 0}
                for s, c in _pcg64_states(self._seed, self.ids)
            ]
            self._shared = np.random.Generator(np.random.PCG64(0))
        else:
            self._materialize()

    def _materialize(self) -> list[np.random.Generator]:
        rngs = [np.random.default_rng(np.random.SeedSequence(self._seed, spawn_key=(int(i),))) for i in self.ids]
        if self._rngs is None and self._draws:  # continue where the shared generator left each stream
            for r, state in zip(rngs, self._states, strict=True):
                r.bit_generator.state = state
        self._rngs = rngs
        return rngs

    def __len__(self) -> int:
        return self.ids.size

    def _stack(self, method: str, shape: int | tuple[int, ...], **kw: float) -> np.ndarray:
        shape = tuple(np.atleast_1d(shape)) if shape != () else ()
        self._draws += 1
        if self._rngs is None and self._draws > _SHARED_DRAWS:
            self._materialize()
        if self._rngs is not None:
            return np.stack([getattr(r, method)(size=shape, **kw) for r in self._rngs])
        draw, bits, rows = getattr(self._shared, method), self._shared.bit_generator, []
        for j, state in enumerate(self._states):  # each trial's stream in turn on one generator
            bits.state = state
            rows.append(draw(size=shape, **kw))
            self._states[j] = bits.state
        return np.stack(rows)

    def normal(self, shape: int | tuple[int, ...] = (), loc: float = 0.0, scale: float = 1.0) -> np.ndarray:
        """Normal draws, shape ``(B, *shape)``."""
        return self._stack("normal", shape, loc=loc, scale=scale)

    def uniform(self, shape: int | tuple[int, ...] = (), low: float = 0.0, high: float = 1.0) -> np.ndarray:
        """Uniform draws on [low, high), shape ``(B, *shape)``."""
        return self._stack("uniform", shape, low=low, high=high)

    def generators(self) -> list[np.random.Generator]:
        """The per-trial generators, for draws the helpers above do not cover."""
        return list(self._materialize() if self._rngs is None else self._rngs)


_SHARED_DRAWS = 4
"""Draw calls per batch served by one shared generator (its state swapped per trial, a fixed cost per trial
and call); after that each trial gets its own generator (created once, then cheaper per call)."""

_HASH_A, _MULT_A, _HASH_B, _MULT_B = 0x43B0D7E5, 0x931E8875, 0x8B51F9DD, 0x58F38DED
_MIX_L, _MIX_R = 0xCA01F9DD, 0x4973F715
_PCG_MULT = (2549297995355413924 << 64) | 4865540595714422341
_M128 = (1 << 128) - 1


def _pcg64_states(seed: int, ids: np.ndarray) -> list[tuple[int, int]]:
    """``(state, inc)`` of ``PCG64(SeedSequence(seed, spawn_key=(i,)))`` for each id below 2**32.

    numpy's SeedSequence hash (pool of four 32-bit words mixed from the seed's words and the spawn key, then
    eight output words) evaluated for all ids at once in uint32 arithmetic, and PCG64's seeding (two LCG steps
    in 128 bits), without creating a SeedSequence and a PCG64 per trial.
    tests/test_montecarlo.py checks the states against numpy's for many seeds and ids.
    """
    run = []
    while True:
        run.append(seed & 0xFFFFFFFF)
        seed >>= 32
        if seed == 0:
            break
    run += [0] * (4 - len(run))  # the pool size, as SeedSequence pads with a spawn key
    entropy = [np.full(ids.size, w, np.uint32) for w in run] + [ids.astype(np.uint32)]
    const = [_HASH_A]

    def hashmix(v: NDArray[np.uint32]) -> NDArray[np.uint32]:
        v = v ^ np.uint32(const[0])
        const[0] = const[0] * _MULT_A & 0xFFFFFFFF
        v = v * np.uint32(const[0])
        return v ^ (v >> np.uint32(16))

    def mix(x: NDArray[np.uint32], y: NDArray[np.uint32]) -> NDArray[np.uint32]:
        r = np.uint32(_MIX_L) * x - np.uint32(_MIX_R) * y
        return r ^ (r >> np.uint32(16))

    with np.errstate(over="ignore"):  # uint32 arithmetic wraps, as in SeedSequence
        pool = [hashmix(entropy[i]) for i in range(4)]
        for s in range(4):
            for d in range(4):
                if s != d:
                    pool[d] = mix(pool[d], hashmix(pool[s]))
        for s in range(4, len(entropy)):
            for d in range(4):
                pool[d] = mix(pool[d], hashmix(entropy[s]))
        words, h = [], _HASH_B
        for k in range(8):
            v = pool[k % 4] ^ np.uint32(h)
            h = h * _MULT_B & 0xFFFFFFFF
            v = v * np.uint32(h)
            words.append((v ^ (v >> np.uint32(16))).astype(np.uint64))
    w64 = [(words[2 * k] | words[2 * k + 1] << np.uint64(32)).tolist() for k in range(4)]
    out = []
    for s0, s1, i0, i1 in zip(*w64, strict=True):
        inc = ((i0 << 64 | i1) << 1 | 1) & _M128
        out.append((((inc + (s0 << 64 | s1)) * _PCG_MULT + inc) & _M128, inc))
    return out


def _run_batch(
    batch_fn: Callable[..., dict[str, Any]], seed: int, ids: NDArray[np.int64], kwargs: dict[str, Any]
) -> dict[str, Any]:
    return batch_fn(ids, TrialStreams._of(seed, ids), **kwargs)


def _progress_bar(total: int, label: str) -> Any:
    from tqdm.auto import tqdm

    return tqdm(total=total, desc=label, unit="trials", mininterval=1.0, dynamic_ncols=True)


Seed = Annotated[int, Check("integer", minimum=0)]
"""A seed of numpy's SeedSequence (an integer >= 0)."""


@boundary
def run(
    batch_fn: Callable[..., dict[str, np.ndarray]],
    n_trials: Count,
    seed: Seed,
    *,
    batch_size: Count = 1000,
    executor: Executor | None = None,
    progress: bool | None = None,
    label: Text = "trials",
    **kwargs: Any,
) -> dict[str, np.ndarray]:
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

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import montecarlo
    >>> def batch(ids, streams):
    ...     return {"x": streams.normal()}                        # one draw per trial
    ...
    >>> out = montecarlo.run(batch, n_trials=6, seed=1, batch_size=4, progress=False)
    >>> out["x"].shape, bool(np.array_equal(out["x"], montecarlo.run(batch, 6, 1, batch_size=2, progress=False)["x"]))
    ((6,), True)
    """
    if not callable(batch_fn):
        raise ValueError(f"batch_fn: expected a callable, got {type(batch_fn).__name__}")
    progress = os.environ.get("NAVLIB_PROGRESS", "1").strip() != "0" if progress is None else flag(progress, "progress")
    if executor is not None and not hasattr(executor, "submit"):  # an Executor, or one by duck typing
        raise ValueError(f"executor: expected a concurrent.futures.Executor, got {type(executor).__name__}")
    batches = [np.arange(s, min(s + batch_size, n_trials)) for s in range(0, n_trials, batch_size)]
    job = partial(_run_batch, batch_fn, int(seed))
    results: list[dict[str, Any]] = []
    bar = _progress_bar(n_trials, label) if progress else None
    try:
        if executor is None:
            outcomes = (job(ids, kwargs) for ids in batches)
        else:
            futures = [executor.submit(job, ids, kwargs) for ids in batches]
            outcomes = (fut.result() for fut in futures)  # in order: results stay in trial order
        for k, outcome in enumerate(outcomes):
            results.append(outcome)
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
