"""tools/reproduce.py's plan and profile: notebooks longest first by the last run's times less their
compilation, and where a notebook's time went (compile log, cell timing)."""

import importlib
import json
import os
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tools"))
reproduce = pytest.importorskip("reproduce")  # tools/reproduce.py (needs nbclient)
nbformat = pytest.importorskip("nbformat")


def test_notebooks_run_longest_first():
    paths = [Path(f"{i:02d}") for i in range(5)]
    seconds = dict(zip(paths, (14.0, 24.1, 0.0, 24.1, 30.7), strict=True))
    assert reproduce.longest_first(paths, seconds) == [paths[4], paths[1], paths[3], paths[0], paths[2]]


def test_without_times_the_order_is_the_names():
    paths = [Path("a"), Path("b"), Path("c")]
    assert reproduce.longest_first(paths, dict.fromkeys(paths, 0.0)) == paths


def test_a_warm_run_is_planned_without_the_last_runs_compilation():
    summary = {"00_a": {"seconds": 50.0, "compile_seconds": 30.0}, "01_b": {"seconds": 25.0}}
    paths = [Path("00_a.ipynb"), Path("01_b.ipynb"), Path("02_new.ipynb")]
    assert reproduce.expected_seconds(summary, paths) == {paths[0]: 20.0, paths[1]: 25.0, paths[2]: 0.0}


def test_a_fresh_clone_runs_the_longest_notebooks_first():
    paths = [Path(f"{stem}.ipynb") for stem in ("00_conventions_sensors", "02_rotation_bias", "99_new")]
    seconds = reproduce.expected_seconds({}, paths)  # no build/summary.json: the typical times
    assert reproduce.longest_first(paths, seconds) == [paths[1], paths[0], paths[2]]


def test_the_warm_up_runs_in_one_process_per_core():
    from navlib import warmup

    assert reproduce.warm_up_parts(2) == reproduce.warm_up_parts(4) == [1, 2]
    assert reproduce.warm_up_parts(1) == [None]  # one core: all in one process
    for module in reproduce.WARM_UP_ALSO:
        assert callable(importlib.import_module(module)._warm_up)
    names = [name for part in warmup.PARTS for name in part]
    assert sorted(names) == sorted(warmup._calls())  # every entry point in exactly one part
    with pytest.raises(ValueError, match="part"):
        warmup.warmup(part=3)


@pytest.mark.skipif(not hasattr(os, "sched_getaffinity"), reason="the cores a process may use: Linux")
def test_one_notebook_more_than_cores_runs_at_once(monkeypatch):
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: {0, 1})
    assert reproduce.default_jobs() == 3  # the third fills the gaps of the two (kernel start, messages, files)
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: {0})
    assert reproduce.default_jobs() == 1


def test_the_shared_kernels_are_warmed_up_only_when_the_notebooks_would_compile(tmp_path, monkeypatch):
    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)  # numba's cache in navlib/__pycache__
    build, navlib = tmp_path / "build", tmp_path / "navlib"
    for folder in (build, navlib):
        folder.mkdir()
    (navlib / "core.py").write_text("A = 1\n")
    assert reproduce.compilation_expected(build, {}, tmp_path)  # no earlier run: a fresh clone
    (build / "summary.json").write_text("{}")
    warm = {"00_a": {"compile_cpu_seconds": 0.0}, "01_b": {}}
    assert reproduce.compilation_expected(build, warm, tmp_path)  # numba's cache emptied since: compiled again
    (navlib / "__pycache__").mkdir()
    (navlib / "__pycache__" / "core.kernel-1.py311.nbi").write_bytes(b"")
    assert not reproduce.compilation_expected(build, warm, tmp_path)  # numba's cache holds every kernel
    compiled = warm | {"02_c": {"compile_cpu_seconds": 4.5}}
    assert not reproduce.compilation_expected(build, compiled, tmp_path)  # into numba's cache: there now
    (build / reproduce.COLD_MARK).write_text("--cold\n")
    assert reproduce.compilation_expected(build, compiled, tmp_path)  # into a temporary cache, gone
    (build / reproduce.COLD_MARK).unlink()
    later = (build / "summary.json").stat().st_mtime + 10
    os.utime(navlib / "core.py", (later, later))  # navlib edited since: its kernels compile again
    assert reproduce.compilation_expected(build, warm, tmp_path)


def test_a_papers_further_notebook_waits_for_its_first_one():
    paths = [Path(f"{stem}.ipynb") for stem in ("04_mimu_mag_rtk", "05_pedestrian_ins_floors", "05_pedestrian_ins", "06_x")]
    assert reproduce.paper_parts(paths) == {paths[1]: paths[2]}  # they share kernels: compiled once, not twice at once
    assert reproduce.paper_parts(paths[:2]) == {}  # the first one not in this run (up to date): nothing to wait for


def test_the_compile_log_gives_seconds_per_kernel(tmp_path):
    log = tmp_path / "00_a.compile.log"  # as navlib._kernels.CompileLog writes it
    assert reproduce.read_compile_log(log) == []
    log.write_text(
        "1.500 navlib.strapdown._nav_kernel 1.25\n0.250 navlib.kalman.f\n2.000 navlib.strapdown._nav_kernel 0.5\n3.0\n"
    )
    compilations = reproduce.read_compile_log(log)
    assert sum(s for s, _ in compilations) == 6.75
    assert sum(cpu for _, _, cpu in reproduce.read_compile_lines(log)) == 1.75  # CPU where logged
    assert reproduce.kernels_by_compile_time(compilations) == [
        ("navlib.strapdown._nav_kernel", 3.5, 2),
        ("?", 3.0, 1),
        ("navlib.kalman.f", 0.25, 1),
    ]


def test_cells_are_timed_from_nbclients_metadata():
    nb = nbformat.v4.new_notebook(
        cells=[
            nbformat.v4.new_code_cell("import numpy as np"),
            nbformat.v4.new_markdown_cell("# text"),
            nbformat.v4.new_code_cell("\nslow()"),
            nbformat.v4.new_code_cell("never_run()"),
        ]
    )
    for cell, (begin, end) in zip(nb.cells[::2], (("00:00:00.5", "00:00:01.75"), ("00:00:02", "00:00:12")), strict=True):
        cell.metadata["execution"] = {"iopub.execute_input": f"2026-01-01T{begin}Z", "shell.execute_reply": f"2026-01-01T{end}Z"}
    assert reproduce.cell_seconds(nb) == [(2, 10.0, "slow()"), (0, 1.25, "import numpy as np")]


def test_the_profile_splits_compilation_from_the_rest():
    entry = {
        "notebook": "02_x",
        "seconds": 40.0,
        "compile_seconds": 12.5,
        "peak_mb": 900,
        "kernels": [("navlib.m.k", 12.5, 3)],
        "cells": [(4, 30.0, "run()")],
    }
    assert reproduce.profile(entry).splitlines() == [
        "02_x: 40.0 s = compile 12.5 + other 27.5; peak memory 900 MB",
        "    compile   12.5 s  3 signature(s)  navlib.m.k",
        "    cell   4   30.0 s  run()",
    ]


def run(seed, checks, verdicts, error=None):
    return {
        "notebook": "04_x",
        "seed": seed,
        "seconds": 1.0,
        "error": error,
        "checks": {n: {"value": v, "passed": p} for n, (v, p) in checks.items()},
        "verdicts": verdicts,
    }


def test_the_sweep_names_every_failed_check_and_verdict_flip():
    runs = [
        run(11, {"A/x": (1.0, True), "B": (2.0, True)}, {"A": "reproduced", "B": "differs"}),
        run(29, {"A/x": (1.5, False), "B": (2.1, True)}, {"B": "differs"}),
        run(47, {"B": (2.2, True)}, {"A": "reproduced", "B": "differs"}),
    ]
    table = reproduce.sweep_table(runs, [11, 29, 47])
    assert table["checks"]["A/x"]["values"] == [1.0, 1.5, None]
    assert table["failures"] == {"A/x": [29, 47]}  # failed on 29, missing on 47
    assert table["flips"] == {"A": ["reproduced", "no verdict", "reproduced"]}
    assert table["verdicts"]["B"] == ["differs"] * 3


def test_a_stable_sweep_has_no_failure_and_no_flip():
    runs = [run(s, {"A": (s / 10, True)}, {"A": "undecided at this scale"}) for s in (11, 29, 47)]
    table = reproduce.sweep_table(runs, [11, 29, 47])
    assert table["failures"] == {} and table["flips"] == {} and table["errors"] == {}


def test_only_notebooks_that_set_a_seed_are_swept(tmp_path):
    for name, source in (("01_mc", "SEED = 3\nN = 5"), ("02_fixed", "N = 5")):
        nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell("import numpy"), nbformat.v4.new_code_cell(source)])
        nb.cells[1].metadata["tags"] = ["parameters"]
        nbformat.write(nb, tmp_path / f"{name}.ipynb")
    paths = sorted(tmp_path.glob("*.ipynb"))
    assert reproduce.seeded_notebooks(paths) == [paths[0]]


def test_the_sweep_refuses_the_seeds_that_set_a_tolerance():
    used = reproduce.calibration_seeds(ROOT)
    assert used, "data/seed_studies/calibration_seeds.csv lists no calibration seeds"
    for stem, seeds in used.items():
        assert not seeds & set(reproduce.SWEEP_SEEDS), f"{stem}: a default sweep seed set a tolerance"
    stem, seeds = next(iter(used.items()))
    args = reproduce.argparse.Namespace(seeds=None, seed_list=str(min(seeds)), jobs=1, timeout=10)
    paths = sorted((ROOT / "notebooks").glob(f"{stem}.ipynb"))
    assert reproduce.sweep(args, ROOT, paths, ROOT / "build") == 1


# A notebook that writes a results.json with one passed check, as navlib.repro does.
TINY = """import json, pathlib
out = pathlib.Path("../build/00_tiny")
out.mkdir(parents=True, exist_ok=True)
(out / "results.json").write_text(json.dumps({"checks": [{"name": "tiny", "passed": True}]}))"""


def test_an_execution_is_reused_only_while_its_inputs_and_outputs_are_unchanged(tmp_path, monkeypatch):
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(TINY)])
    nb.metadata.kernelspec = {"name": "python3", "display_name": "Python 3", "language": "python"}
    path = tmp_path / "notebooks" / "00_tiny.ipynb"
    for file, text in (
        (path, nbformat.writes(nb)),
        (tmp_path / "navlib" / "core.py", "A = 1\n"),
        (tmp_path / "data" / "a.csv", "a\n1\n"),
    ):
        file.parent.mkdir(parents=True, exist_ok=True)
        file.write_text(text)
    build = tmp_path / "build"
    assert reproduce.last_execution(path, build) == (None, "no execution recorded in build/")

    entry = json.loads(json.dumps(reproduce.executed(path, timeout=300)))  # executed for real: no record yet
    assert entry["ok"] and entry["checks_total"] == 1 and (build / "00_tiny.run.json").is_file()
    if sys.platform.startswith("linux"):  # the kernel's peak memory and CPU time, from /proc
        assert entry["peak_mb"] > 0 and entry["cpu_seconds"] > 0
    runs = []
    monkeypatch.setattr(reproduce, "run_notebook", lambda p, b, t: runs.append(p.name) or {"notebook": p.stem, "new": True})
    assert reproduce.executed(path) == entry and runs == []  # reused

    for changed in (
        path,
        tmp_path / "navlib" / "core.py",
        tmp_path / "data" / "a.csv",
        build / "00_tiny.ipynb",
        build / "00_tiny" / "results.json",
    ):
        original = changed.read_bytes()
        changed.write_bytes(original + b" ")
        assert reproduce.last_execution(path, build)[0] is None, f"an edit of {changed.name} went unnoticed"
        assert reproduce.executed(path)["new"] and runs[-1] == path.name  # executed again
        changed.write_bytes(original)
        assert reproduce.last_execution(path, build)[0] == entry  # the same content stands again
    (tmp_path / "navlib" / "new.py").write_text("")
    assert reproduce.last_execution(path, build)[0] is None, "a new navlib file went unnoticed"
    (tmp_path / "navlib" / "new.py").unlink()
    (build / "00_tiny" / "results.json").unlink()
    assert reproduce.last_execution(path, build)[0] is None, "a deleted results.json went unnoticed"


class _Client:
    """A stand-in for nbclient's client whose kernel start fails ``fails`` times with ``message``."""

    def __init__(self, fails: int, message: str) -> None:
        self.fails, self.message, self.calls = fails, message, 0

    def execute(self, **_):
        self.calls += 1
        if self.calls <= self.fails:
            raise RuntimeError(self.message)


def test_a_kernel_that_died_at_start_is_started_again():
    """The port race of two kernel starts is retried; a notebook's own error, or a start failing every time, is not hidden."""
    died = "Kernel died before replying to kernel_info"
    client = _Client(fails=2, message=died)
    reproduce.execute(client)
    assert client.calls == 3
    with pytest.raises(RuntimeError, match="kernel_info"):
        reproduce.execute(_Client(fails=reproduce.KERNEL_START_TRIES, message=died))
    other = _Client(fails=1, message="a cell failed")
    with pytest.raises(RuntimeError, match="a cell failed"):
        reproduce.execute(other)
    assert other.calls == 1
