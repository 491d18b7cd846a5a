"""Every chapter in one frame (issue 39): it opens with the question, what you will learn, prerequisites and time,
closes with key points apart from the discussion, and has a coding exercise whose collapsed solution is checked."""

from __future__ import annotations

from pathlib import Path

import nbformat
import pytest

ROOT = Path(__file__).resolve().parents[1]
PATHS = sorted((ROOT / "notebooks").glob("[0-9][0-9]_*.ipynb"))


@pytest.mark.parametrize("path", PATHS, ids=[p.stem for p in PATHS])
def test_chapter_frame(path):
    cells = nbformat.read(path, as_version=4).cells
    text = [c.source for c in cells if c.cell_type == "markdown"]
    opening = text[1]
    for part in ("**The question.**", "**What you will learn**", "**Prerequisites.**", "**Time.**"):
        assert part in opening, f"the cell after the title has no {part}"
    assert any(t.startswith("## Key points") for t in text), "no '## Key points' section"


@pytest.mark.parametrize("path", PATHS, ids=[p.stem for p in PATHS])
def test_a_coding_exercise_with_a_checked_solution(path):
    cells = nbformat.read(path, as_version=4).cells
    stubs = [c for c in cells if c.cell_type == "code" and "return None   # your code here" in c.source]
    solutions = [c for c in cells if "solution" in c.metadata.get("tags", [])]
    assert stubs, "no coding exercise (a stub returning None)"
    assert solutions and all("assert repro.exercise(" in c.source and ").passed" in c.source for c in solutions)
    assert all(c.metadata.get("jupyter", {}).get("source_hidden") for c in solutions), "a solution is not collapsed"
