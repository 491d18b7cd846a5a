"""Every notebook runs to the end in teaching + fast mode with one of its parameters changed.

A student changes a parameter (another latitude, another seed, ...) and runs the notebook: with the
teaching switch on, a check that no longer holds becomes a visible ``ClaimCheckWarning`` instead of
stopping the notebook, and the fast switch picks the notebook's small parameter set. The changed
parameter is injected papermill-style: a cell assigning it is inserted right after the cell tagged
``parameters``. Each notebook names the changes it invites in its metadata
(``metadata.navlib.try_parameters``: a mapping of parameter name to a Python literal as text, or a list of
such mappings, one run each: e.g. chapter 04's ``KI = 0.0``, the baseline its text discusses).

Each run is executed once per ``make test``, as the notebooks are: ``tools/reproduce.py --stale`` (run by
``make test`` before pytest) executes the runs whose record is missing, failed or out of date, and
:func:`test_runs_in_teaching_and_fast_mode` reads the record (``build/teaching/<notebook>-<run>.json``) and the
results it wrote (``build/teaching/<notebook>-<run>/``, marked ``mode``, which the ledger refuses anyway). A record
stands while its results and what the run depends on are unchanged (as for a notebook's execution record: the
notebook, its parameter changes included, navlib/, data/, the runner, the installed packages); otherwise (a plain
``pytest`` after an edit, say) the test executes the run itself. Run times are reported (``-rA`` shows them) and
listed on the course page of the site, never asserted.
"""

from __future__ import annotations

import ast
import json
import re
import sys
from pathlib import Path

import nbformat
import pytest

ROOT = Path(__file__).resolve().parents[1]
PATHS = sorted((ROOT / "notebooks").glob("[0-9][0-9]_*.ipynb"))
sys.path.insert(0, str(ROOT / "tools"))
import reproduce  # noqa: E402  (tools/reproduce.py: the teaching runs and their records)

try_parameters = reproduce.try_parameters


def parameter_names(nb) -> set[str]:
    """The names the ``parameters`` cell assigns."""
    params = next(c.source for c in nb.cells if "parameters" in c.metadata.get("tags", []))
    return {
        t.id for node in ast.parse(params).body if isinstance(node, ast.Assign) for t in ast.walk(node) if isinstance(t, ast.Name)
    }


RUNS = reproduce.teaching_runs(PATHS)


@pytest.mark.parametrize("path", PATHS, ids=[p.stem for p in PATHS])
def test_names_a_parameter_to_change(path):
    nb = nbformat.read(path, as_version=4)
    runs = try_parameters(nb)
    assert runs and all(runs), "metadata.navlib.try_parameters names no parameter to change"
    defined = parameter_names(nb)
    for name, value in (item for changes in runs for item in changes.items()):
        assert name in defined, f"{name} is not set in the parameters cell"
        ast.literal_eval(value)  # a plain literal, so that a reader can type it too
    for switch in ("TEACHING", "FAST"):
        assert switch in defined, f"the parameters cell has no {switch} switch"


INVITED = re.compile(r"`([A-Z][A-Z0-9_]*) = ([^`]+)`")
COURSE = (ROOT / "docs" / "course.md").read_text(encoding="utf-8")


@pytest.mark.parametrize("path", PATHS, ids=[p.stem for p in PATHS])
def test_every_invited_value_is_run(path):
    """A `NAME = value` of a parameter in the chapter's text or its row of the course page is one of the runs below."""
    nb = nbformat.read(path, as_version=4)
    defined = parameter_names(nb)
    label = nb.cells[0].source.split(" — ")[0].lstrip("# ")  # "05", "05b": the chapter's row of the course page
    rows = [line for line in COURSE.splitlines() if line.startswith(f"| {label} |")]
    texts = [c.source for c in nb.cells if c.cell_type == "markdown"] + rows
    run = {(name, ast.literal_eval(value)) for changes in try_parameters(nb) for name, value in changes.items()}
    invited = {(m[1], m[2].strip()) for text in texts for m in INVITED.finditer(text) if m[1] in defined}
    missing = sorted(f"{name} = {value}" for name, value in invited if (name, ast.literal_eval(value)) not in run)
    assert not missing, f"invited in the text but never run: {missing}; add them to metadata.navlib.try_parameters"


@pytest.mark.parametrize(("path", "run"), RUNS, ids=[f"{p.stem}-{k}" for p, k in RUNS])
def test_runs_in_teaching_and_fast_mode(path, run):
    record = reproduce.teaching_executed(path, run)
    assert record["error"] is None, f"{path.name} with {record['parameters']} stopped: {record['error']}"
    results = ROOT / "build" / "teaching" / f"{path.stem}-{run}" / path.stem / "results.json"
    assert json.loads(results.read_text())["mode"] == {"teaching": True, "fast": True}
    seconds, held = record["seconds"], record["checks_held"]
    print(f"{path.stem}: teaching + fast with {record['parameters']}: {seconds:.1f} s, {held} checks held")


# A notebook whose one check holds with its invited change (K = 2) and writes its results where navlib.repro would.
TINY = """import json, os, pathlib
out = pathlib.Path(os.environ["NAVLIB_BUILD_DIR"]) / "00_tiny"
out.mkdir(parents=True, exist_ok=True)
mode = {"teaching": os.environ.get("NAVLIB_TEACHING") == "1", "fast": os.environ.get("NAVLIB_FAST") == "1"}
(out / "results.json").write_text(json.dumps({"mode": mode, "checks": [{"name": "k", "passed": K == 2}]}))"""


def tiny_project(root: Path, runs: list[dict[str, str]]) -> Path:
    """A project under ``root`` with one notebook inviting ``runs``, a navlib/ and a data/ file."""
    parameters = nbformat.v4.new_code_cell("TEACHING = False\nFAST = False\nK = 1")
    parameters.metadata["tags"] = ["parameters"]
    nb = nbformat.v4.new_notebook(cells=[parameters, nbformat.v4.new_code_cell(TINY)])
    nb.metadata.kernelspec = {"name": "python3", "display_name": "Python 3", "language": "python"}
    nb.metadata.navlib = {"try_parameters": runs}
    path = root / "notebooks" / "00_tiny.ipynb"
    for file, text in ((path, nbformat.writes(nb)), (root / "navlib" / "core.py", "A = 1\n"), (root / "data" / "a.csv", "a\n")):
        file.parent.mkdir(parents=True, exist_ok=True)
        file.write_text(text)
    return path


def test_a_teaching_run_is_reused_only_while_its_inputs_and_results_are_unchanged(tmp_path, monkeypatch):
    path = tiny_project(tmp_path, [{"K": "2"}])
    build = tmp_path / "build"
    assert reproduce.last_teaching_run(path, 0, build) == (None, "no teaching run recorded in build/teaching/")

    record = reproduce.teaching_executed(path, 0, timeout=300)  # executed for real: no record yet
    assert record["error"] is None and record["checks_held"] == "1/1" and record["parameters"] == {"K": "2"}
    results = build / "teaching" / "00_tiny-0" / "00_tiny" / "results.json"
    assert json.loads(results.read_text())["mode"] == {"teaching": True, "fast": True}
    runs = []
    monkeypatch.setattr(reproduce, "run_teaching", lambda p, k, b, t: runs.append(k) or {"new": True})
    assert reproduce.teaching_executed(path, 0) == record and runs == []  # reused

    for changed in (path, tmp_path / "navlib" / "core.py", tmp_path / "data" / "a.csv", results):
        original = changed.read_bytes()
        changed.write_bytes(original + b" ")
        assert reproduce.last_teaching_run(path, 0, build)[0] is None, f"an edit of {changed.name} went unnoticed"
        assert reproduce.teaching_executed(path, 0)["new"] and runs == [0]  # executed again
        runs.clear()
        changed.write_bytes(original)
        assert reproduce.last_teaching_run(path, 0, build)[0] == record  # the same content stands again


def test_stale_picks_the_missing_failed_and_out_of_date_teaching_runs(tmp_path):
    path = tiny_project(tmp_path, [{"K": "2"}, {"K": "3"}])
    build = tmp_path / "build"
    assert reproduce.stale_teaching_runs([path], build) == [(path, 0), (path, 1)]  # none recorded

    def record(run: int, error: str | None) -> None:  # as reproduce.run_teaching writes it, without a kernel
        results = build / "teaching" / f"00_tiny-{run}" / "00_tiny" / "results.json"
        results.parent.mkdir(parents=True, exist_ok=True)
        results.write_text("{}")
        entry = {"seconds": 1.0, "error": error, "inputs": reproduce.teaching_inputs(path, run)}
        entry["outputs"] = reproduce.teaching_outputs(path, run, build)
        reproduce.teaching_record(path, run, build).write_text(json.dumps(entry))

    record(0, None)
    record(1, "ZeroDivisionError: division by zero")
    assert reproduce.stale_teaching_runs([path], build) == [(path, 1)]  # the failed one is run again
    record(1, None)
    assert reproduce.stale_teaching_runs([path], build) == []
    (tmp_path / "data" / "a.csv").write_text("a\n1\n")
    assert reproduce.stale_teaching_runs([path], build) == [(path, 0), (path, 1)]
