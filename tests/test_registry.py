"""The paper registry (navlib/papers/__init__.py) is the one list of reproduced papers.

Every notebook is notebook 00 or a registered paper, so a new notebook cannot be
skipped silently; every registered paper has its notebook, its companion module,
its claims and errata, and a row in the README table.
"""

from __future__ import annotations

import csv
import importlib
import json
import re
from pathlib import Path

import pytest

from navlib.papers import CHAPTERS, PAPERS, by_notebook

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = sorted((ROOT / "notebooks").glob("*.ipynb"))
paper = pytest.mark.parametrize("p", PAPERS, ids=[p.name for p in PAPERS])


def rows(name: str) -> list[dict]:
    with open(ROOT / "data" / name, encoding="utf-8") as fh:
        return list(csv.DictReader(fh))


def test_every_notebook_is_registered():
    stray = [p.name for p in NOTEBOOKS if p.stem not in CHAPTERS and by_notebook(p.stem) is None]
    assert not stray, f"notebooks missing from navlib/papers/__init__.py: {stray}"


def test_names_numbers_and_claim_ids_are_unique():
    for field in ("name", "number", "claims_id"):
        values = [getattr(p, field) for p in PAPERS]
        assert len(set(values)) == len(values), f"duplicate {field} in the registry: {values}"


@paper
def test_notebooks_exist_and_import_their_companion(p):
    for stem in p.notebooks:
        path = ROOT / "notebooks" / f"{stem}.ipynb"
        assert path.is_file(), f"{p.name}: no notebook {path.name}"
        code = "\n".join(
            "".join(c["source"]) for c in json.loads(path.read_text(encoding="utf-8"))["cells"] if c["cell_type"] == "code"
        )
        assert re.search(rf"from navlib\.papers import [^\n]*\b{p.name}\b|import navlib\.papers\.{p.name}\b", code), (
            f"{path.name} does not import its companion navlib.papers.{p.name}"
        )


@paper
def test_companion_is_importable_and_documented(p):
    module = importlib.import_module(p.module)
    assert module.__doc__ and len(module.__doc__.strip()) > 40, f"{p.module} has no module docstring"


@paper
def test_claims_and_errata_carry_the_paper_id(p):
    assert any(r["paper"] == p.claims_id for r in rows("claims.csv")), f"{p.name}: no claims in data/claims.csv"
    for r in rows("claims.csv") + rows("errata.csv"):
        prefix = r["id"].split("-")[0]
        if r["paper"] == p.claims_id:
            assert prefix[1:] == p.claims_id, f"{r['id']}: id does not start with P/E{p.claims_id}"


def test_data_files_name_only_registered_papers():
    known = {p.claims_id for p in PAPERS}
    assert {r["paper"] for r in rows("claims.csv") + rows("errata.csv")} <= known


@paper
def test_readme_lists_the_notebook(p):
    assert f"`{p.notebook}`" in (ROOT / "README.md").read_text(encoding="utf-8"), (
        f"README results table has no row for {p.notebook} (run `make readme`)"
    )
