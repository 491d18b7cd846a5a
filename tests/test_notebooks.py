"""Static checks on notebooks/*.ipynb (their execution: tests/test_notebook_runs.py).

Every notebook is committed stripped (`make strip`), runs on the ``python3``
kernel, has a code cell tagged ``parameters``, and calls
``repro.setup("<its own stem>")``; the paper notebooks 01-05 open with a
markdown cell giving the citation.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from navlib.papers import by_notebook

NOTEBOOKS = Path(__file__).resolve().parents[1] / "notebooks"
PATHS = sorted(NOTEBOOKS.glob("*.ipynb")) if NOTEBOOKS.is_dir() else []
SETUP_CALL = re.compile(r"\bsetup\(\s*(?:notebook\s*=\s*)?[\"']([^\"']*)[\"']")
YEAR = re.compile(r"\b(19|20)\d\d\b")
PAPERS = [p for p in PATHS if by_notebook(p.stem) is not None]


def load(path: Path) -> dict:
    return json.loads(path.read_text(encoding="utf-8"))


def source(cell: dict) -> str:
    s = cell.get("source", "")
    return "".join(s) if isinstance(s, list) else s


def code_cells(nb: dict) -> list[dict]:
    return [c for c in nb["cells"] if c["cell_type"] == "code"]


notebook = pytest.mark.parametrize("path", PATHS, ids=[p.stem for p in PATHS])


def test_notebooks_exist():
    assert NOTEBOOKS.is_dir(), f"{NOTEBOOKS} is missing"
    assert PATHS, f"no notebooks in {NOTEBOOKS}"


@notebook
def test_stripped(path):
    for i, cell in enumerate(code_cells(load(path))):
        assert cell.get("outputs") == [], f"cell {i} has outputs: run `make strip`"
        assert cell.get("execution_count") is None, f"cell {i} has an execution count: run `make strip`"


@notebook
def test_kernel_is_python3(path):
    assert load(path)["metadata"].get("kernelspec", {}).get("name") == "python3"


@notebook
def test_no_widget_state(path):
    assert "widgets" not in load(path)["metadata"], "widget state in metadata: run `make strip`"


@notebook
def test_has_parameters_cell(path):
    tagged = [c for c in code_cells(load(path)) if "parameters" in c.get("metadata", {}).get("tags", [])]
    assert tagged, "no code cell tagged `parameters`"


@notebook
def test_setup_uses_own_name(path):
    names = [m for c in code_cells(load(path)) for m in SETUP_CALL.findall(source(c))]
    assert names, f'no repro.setup("{path.stem}") call'
    assert set(names) == {path.stem}, f"repro.setup() called with {names}, expected {path.stem!r}"


@pytest.mark.parametrize("path", PAPERS, ids=[p.stem for p in PAPERS])
def test_paper_notebook_cites_paper(path):
    cells = load(path)["cells"]
    assert cells and cells[0]["cell_type"] == "markdown", "first cell must be the markdown header"
    header = source(cells[0])
    assert "doi" in header.lower() or YEAR.search(header), "header cell gives no DOI or dated reference"
