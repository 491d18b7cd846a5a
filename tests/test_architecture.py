"""Module boundaries inside navlib, checked on the source (no import needed).

* No module uses another module's private name (``from .earth import _radii``,
  ``attitude._as_quat(...)``): what two modules share lives in the shared layers
  ``navlib._validate`` (argument validation) and ``navlib._kernels`` (compiled primitives),
  or is public.
* Core modules never import a paper module, and paper modules never import each other.
"""
from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "navlib"
MODULES = {p.stem: p for p in sorted(PACKAGE.glob("*.py")) if p.stem != "__init__"}
PAPER_MODULES = {"northfinding", "gyrobias", "planar", "ahrs", "pedestrian"}    # papers 000, 001, 002, 003, 004


def navlib_imports(tree: ast.Module) -> tuple[dict[str, str], list[tuple[str, str, int]]]:
    """Aliases bound to navlib modules, and ``(module, name, line)`` for every name imported from one."""
    aliases, names = {}, []
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and (node.level == 1 or (node.module or "").startswith("navlib")):
            module = (node.module or "").removeprefix("navlib").lstrip(".")
            for a in node.names:
                if module:                                   # from .earth import x
                    names.append((module, a.name, node.lineno))
                else:                                        # from . import earth
                    aliases[a.asname or a.name] = a.name
    return aliases, names


@pytest.mark.parametrize("stem", sorted(MODULES))
def test_no_private_names_of_other_modules(stem):
    tree = ast.parse(MODULES[stem].read_text(encoding="utf-8"))
    aliases, names = navlib_imports(tree)
    bad = [f"line {line}: from .{mod} import {name}" for mod, name, line in names
           if name.startswith("_") and mod != stem]
    bad += [f"line {node.lineno}: {node.value.id}.{node.attr}" for node in ast.walk(tree)
            if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name)
            and node.value.id in aliases and node.attr.startswith("_") and not node.attr.startswith("__")]
    assert not bad, f"navlib/{stem}.py uses private names of other modules:\n" + "\n".join(bad)


@pytest.mark.parametrize("stem", sorted(MODULES))
def test_paper_modules_stay_apart(stem):
    aliases, names = navlib_imports(ast.parse(MODULES[stem].read_text(encoding="utf-8")))
    imported = set(aliases.values()) | {mod.split(".")[0] for mod, _, _ in names}
    papers = (imported & PAPER_MODULES) - {stem}
    assert not papers, (f"navlib/{stem}.py imports the paper module(s) {sorted(papers)}: "
                        "core code must not depend on a paper, nor a paper on another")


def test_the_checks_see_imports():
    aliases, names = navlib_imports(ast.parse("from . import earth as e\nfrom .kalman import _x\nfrom navlib.units import deg"))
    assert aliases == {"e": "earth"} and ("kalman", "_x", 2) in names and ("units", "deg", 3) in names
