"""tools/reproduce.py's plan and profile: notebooks longest first by the last run's times less their
compilation, and where a notebook's time went (compile log, cell timing)."""
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


def test_the_compile_log_gives_seconds_per_kernel(tmp_path):
    log = tmp_path / "00_a.compile.log"            # as navlib._kernels.CompileLog writes it
    assert reproduce.read_compile_log(log) == []
    log.write_text("1.500 navlib.strapdown._nav_kernel\n0.250 navlib.kalman.f\n2.000 navlib.strapdown._nav_kernel\n3.0\n")
    compilations = reproduce.read_compile_log(log)
    assert sum(s for s, _ in compilations) == 6.75
    assert reproduce.kernels_by_compile_time(compilations) == [
        ("navlib.strapdown._nav_kernel", 3.5, 2), ("?", 3.0, 1), ("navlib.kalman.f", 0.25, 1)]


def test_cells_are_timed_from_nbclients_metadata():
    nb = nbformat.v4.new_notebook(cells=[
        nbformat.v4.new_code_cell("import numpy as np"), nbformat.v4.new_markdown_cell("# text"),
        nbformat.v4.new_code_cell("\nslow()"), nbformat.v4.new_code_cell("never_run()")])
    for cell, (begin, end) in zip(nb.cells[::2], (("00:00:00.5", "00:00:01.75"), ("00:00:02", "00:00:12")), strict=True):
        cell.metadata["execution"] = {"iopub.execute_input": f"2026-01-01T{begin}Z",
                                      "shell.execute_reply": f"2026-01-01T{end}Z"}
    assert reproduce.cell_seconds(nb) == [(2, 10.0, "slow()"), (0, 1.25, "import numpy as np")]


def test_the_profile_splits_compilation_from_the_rest():
    entry = {"notebook": "02_x", "seconds": 40.0, "compile_seconds": 12.5, "peak_mb": 900,
             "kernels": [("navlib.m.k", 12.5, 3)], "cells": [(4, 30.0, "run()")]}
    assert reproduce.profile(entry).splitlines() == [
        "02_x: 40.0 s = compile 12.5 + other 27.5; peak memory 900 MB",
        "    compile   12.5 s  3 signature(s)  navlib.m.k",
        "    cell   4   30.0 s  run()"]
