"""Every notebook runs to the end in teaching + fast mode with one of its parameters changed.

A student changes a parameter (another latitude, another seed, ...) and runs the notebook: with the
teaching switch on, a check that no longer holds becomes a visible ``ClaimCheckWarning`` instead of
stopping the notebook, and the fast switch picks the notebook's small parameter set. The changed
parameter is injected papermill-style: a cell assigning it is inserted right after the cell tagged
``parameters``. Each notebook names the changes it invites in its metadata
(``metadata.navlib.try_parameters``: a mapping of parameter name to a Python literal as text, or a list of
such mappings, one run each: e.g. chapter 04's ``KI = 0.0``, the baseline its text discusses).

Results go to a temporary build directory (``NAVLIB_BUILD_DIR``): the ledger's ``build/`` is not
touched, and results written in these modes are marked (``mode``) and refused by the ledger anyway.
Run times are reported (``-rA`` shows them) and written to ``build/teaching/<notebook>.json`` for the
course page of the site, never asserted.
"""

from __future__ import annotations

import ast
import json
import re
import time
from pathlib import Path

import nbformat
import pytest
from nbclient import NotebookClient

ROOT = Path(__file__).resolve().parents[1]
PATHS = sorted((ROOT / "notebooks").glob("[0-9][0-9]_*.ipynb"))


def try_parameters(nb) -> list[dict[str, str]]:
    """The parameter changes a notebook invites: one mapping per run."""
    changes = nb.metadata.get("navlib", {}).get("try_parameters", {})
    return [changes] if isinstance(changes, dict) else list(changes)


def parameter_names(nb) -> set[str]:
    """The names the ``parameters`` cell assigns."""
    params = next(c.source for c in nb.cells if "parameters" in c.metadata.get("tags", []))
    return {
        t.id for node in ast.parse(params).body if isinstance(node, ast.Assign) for t in ast.walk(node) if isinstance(t, ast.Name)
    }


RUNS = [(p, k) for p in PATHS for k in range(len(try_parameters(nbformat.read(p, as_version=4))))]


def inject(nb, assignments: dict[str, str]) -> None:
    """Insert ``NAME = value`` lines after the ``parameters`` cell (papermill's convention)."""
    index = next(i for i, c in enumerate(nb.cells) if "parameters" in c.metadata.get("tags", []))
    code = "\n".join(f"{name} = {value}" for name, value in assignments.items())
    cell = nbformat.v4.new_code_cell("# injected parameters\n" + code)
    cell.metadata["tags"] = ["injected-parameters"]
    nb.cells.insert(index + 1, cell)


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
def test_runs_in_teaching_and_fast_mode(path, run, tmp_path, monkeypatch):
    nb = nbformat.read(path, as_version=4)
    changes = try_parameters(nb)[run]
    inject(nb, changes)
    for name, value in {
        "NAVLIB_TEACHING": "1",
        "NAVLIB_FAST": "1",
        "NAVLIB_PROGRESS": "0",
        "NAVLIB_BUILD_DIR": str(tmp_path),
        "NAVLIB_ROOT": str(ROOT),
        "MPLBACKEND": "Agg",
    }.items():
        monkeypatch.setenv(name, value)
    start = time.perf_counter()
    # killed once the last cell is done (results.json is on disk by then), as tools/reproduce.py does: a graceful shutdown
    # (the interpreter freeing what the notebook computed) made the ten runs 67 s instead of 58 s (61 s CPU instead of 55)
    client = NotebookClient(
        nb, timeout=600, kernel_name="python3", shutdown_kernel="immediate", resources={"metadata": {"path": str(path.parent)}}
    )
    client.execute()
    seconds = time.perf_counter() - start
    results = json.loads((tmp_path / path.stem / "results.json").read_text())
    assert results["mode"] == {"teaching": True, "fast": True}
    held = f"{sum(c['passed'] for c in results['checks'])}/{len(results['checks'])}"
    print(f"{path.stem}: teaching + fast with {changes}: {seconds:.1f} s, {held} checks held")
    record = ROOT / "build" / "teaching" / f"{path.stem}-{run}.json"
    record.parent.mkdir(parents=True, exist_ok=True)
    record.write_text(
        json.dumps({"notebook": path.stem, "parameters": changes, "seconds": round(seconds, 1), "checks_held": held}),
        encoding="utf-8",
    )
