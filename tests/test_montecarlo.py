"""navlib.montecarlo: results depend only on the seed and the trial index."""

from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor

import numpy as np
import pytest

from navlib import montecarlo


def heading_error_batch(ids, streams, sigma):
    """A small vectorised study: mean of 3 noisy samples per trial."""
    x = streams.normal((3,), scale=sigma)
    return {"mean": x.mean(axis=1), "ids": ids}


def test_trial_streams_match_seedsequence_spawn():
    seed, n = 42, 5
    children = np.random.SeedSequence(seed).spawn(n)
    direct = np.stack([np.random.default_rng(c).normal(size=4) for c in children])
    streams = montecarlo.TrialStreams(seed, np.arange(n))
    np.testing.assert_array_equal(streams.normal((4,)), direct)


@pytest.mark.parametrize("seed", [0, 1, 2000, 2**32 + 5, 2**70 + 3])
def test_trial_states_are_numpys(seed):
    """The vectorised SeedSequence hash gives the PCG64 states numpy's SeedSequence + PCG64 give."""
    ids = np.r_[0:200, 10**7, 2**32 - 1]
    got = montecarlo._pcg64_states(seed, ids)
    want = [np.random.PCG64(np.random.SeedSequence(seed, spawn_key=(int(i),))).state["state"] for i in ids]
    assert [{"state": s, "inc": c} for s, c in got] == want


def test_streams_continue_across_draw_modes():
    """Shared-generator draws, the switch to per-trial generators and generators() continue each trial's
    stream exactly as per-trial generators from the start would; ids beyond 2**32 take the direct path."""
    for ids in (np.array([3, 0, 17, 5]), np.array([1, 2**33])):
        direct = [np.random.default_rng(np.random.SeedSequence(7, spawn_key=(int(i),))) for i in ids]
        streams = montecarlo.TrialStreams(7, ids)
        for k in range(montecarlo._SHARED_DRAWS + 2):
            want = np.stack([g.normal(size=(2,)) if k % 2 else g.uniform(size=()) for g in direct])
            got = streams.normal((2,)) if k % 2 else streams.uniform()
            np.testing.assert_array_equal(got, want)
        fresh = montecarlo.TrialStreams(7, ids)
        fresh.normal(3)
        gens = fresh.generators()
        for g, d in zip(gens, [np.random.default_rng(np.random.SeedSequence(7, spawn_key=(int(i),))) for i in ids], strict=True):
            d.normal(size=3)
            assert g.integers(1 << 40) == d.integers(1 << 40)


@pytest.mark.parametrize("batch_size", [1, 7, 64, 1000])
def test_result_independent_of_batch_size(batch_size):
    ref = montecarlo.run(heading_error_batch, 200, seed=3, batch_size=200, progress=False, sigma=0.1)
    out = montecarlo.run(heading_error_batch, 200, seed=3, batch_size=batch_size, progress=False, sigma=0.1)
    np.testing.assert_array_equal(out["mean"], ref["mean"])
    np.testing.assert_array_equal(out["ids"], np.arange(200))


def test_result_independent_of_executor():
    ref = montecarlo.run(heading_error_batch, 300, seed=9, batch_size=50, progress=False, sigma=2.0)
    with ThreadPoolExecutor(2) as ex:
        threads = montecarlo.run(heading_error_batch, 300, seed=9, batch_size=17, executor=ex, progress=False, sigma=2.0)
    with ProcessPoolExecutor(2) as ex:
        procs = montecarlo.run(heading_error_batch, 300, seed=9, batch_size=100, executor=ex, progress=False, sigma=2.0)
    np.testing.assert_array_equal(threads["mean"], ref["mean"])
    np.testing.assert_array_equal(procs["mean"], ref["mean"])


def test_dask_local_cluster_gives_identical_results():
    distributed = pytest.importorskip("distributed")
    ref = montecarlo.run(heading_error_batch, 120, seed=5, batch_size=40, progress=False, sigma=1.0)
    with (
        distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=False, dashboard_address=None) as cluster,
        distributed.Client(cluster) as client,
    ):
        out = montecarlo.run(
            heading_error_batch, 120, seed=5, batch_size=13, executor=client.get_executor(), progress=False, sigma=1.0
        )
    np.testing.assert_array_equal(out["mean"], ref["mean"])


def test_statistics_and_progress(capsys, monkeypatch):
    monkeypatch.delenv("NAVLIB_PROGRESS", raising=False)
    out = montecarlo.run(heading_error_batch, 4000, seed=1, batch_size=1000, sigma=1.0, label="demo")
    # mean of 3 unit normals has variance 1/3; std of the estimate from n=4000 draws ~ 1/sqrt(2n)
    assert abs(out["mean"].std() / np.sqrt(1 / 3) - 1) < 4 / np.sqrt(2 * 4000)
    err = capsys.readouterr().err
    assert "demo: 100%" in err and "4000/4000" in err


def test_progress_off_by_environment(capsys, monkeypatch):
    """make reproduce and the tests set NAVLIB_PROGRESS=0: executed notebooks keep no progress output."""
    monkeypatch.setenv("NAVLIB_PROGRESS", "0")
    quiet = montecarlo.run(heading_error_batch, 2000, seed=1, batch_size=500, sigma=1.0)
    assert capsys.readouterr().err == ""
    shown = montecarlo.run(heading_error_batch, 2000, seed=1, batch_size=500, sigma=1.0, progress=True)
    assert "2000/2000" in capsys.readouterr().err
    assert all(np.array_equal(quiet[k], shown[k]) for k in quiet)


@pytest.mark.parametrize(
    "kw, match",
    [
        (dict(n_trials=0), "n_trials"),
        (dict(seed=-1), "seed"),
        (dict(batch_size=0), "batch_size"),
        (dict(batch_fn=3), "batch_fn"),
        (dict(executor="pool"), "executor"),
    ],
)
def test_bad_input(kw, match):
    args = dict(batch_fn=heading_error_batch, n_trials=10, seed=1, sigma=1.0, progress=False)
    args.update(kw)
    with pytest.raises(ValueError, match=match):
        montecarlo.run(**args)
