"""Every assumed or tuned value of a notebook is set in its ``parameters`` cell, and only there.

The code cell tagged ``parameters`` defines the names (papermill's convention, so a run can override
them). A later top-level statement of another code cell that assigns one of those names again —
``=``, ``+=``, an annotated assignment, a ``for``/``with``/``import`` target, a ``def`` or ``class``
of the same name — or that changes its contents in place (``NAME[...] = ...``, ``NAME.attr = ...``,
``NAME.update(...)``, ``del NAME[...]``) would change a parameter outside the parameters cell, where a
reader of that cell cannot see it: this test fails on it. Names bound inside functions are local
and not affected.
"""

from __future__ import annotations

import ast
import json
from pathlib import Path

import pytest

NOTEBOOKS = sorted((Path(__file__).resolve().parents[1] / "notebooks").glob("[0-9][0-9]_*.ipynb"))
MUTATORS = {
    "append",
    "extend",
    "insert",
    "update",
    "setdefault",
    "pop",
    "popitem",
    "remove",
    "clear",
    "sort",
    "reverse",
    "add",
    "discard",
    "fill",
    "resize",
    "put",
    "itemset",
    "sort_values",
    "drop",
    "rename",
    "set_index",
    "reset_index",
    "__setitem__",
}


def parse(src: str) -> ast.Module:
    return ast.parse("\n".join(line for line in src.splitlines() if not line.lstrip().startswith(("%", "!"))))


def base(node: ast.AST) -> str | None:
    """The name a target binds or modifies: ``X``, ``X[...]``, ``X.a.b`` -> ``X``."""
    while isinstance(node, (ast.Subscript, ast.Attribute, ast.Starred)):
        node = node.value
    return node.id if isinstance(node, ast.Name) else None


def targets(node: ast.AST) -> list[ast.AST]:
    """The assignment targets of one top-level statement (tuples unpacked)."""
    if isinstance(node, ast.Assign):
        raw = node.targets
    elif isinstance(node, (ast.AnnAssign, ast.AugAssign, ast.For, ast.AsyncFor)):
        raw = [node.target]
    elif isinstance(node, (ast.With, ast.AsyncWith)):
        raw = [i.optional_vars for i in node.items if i.optional_vars is not None]
    elif isinstance(node, ast.Delete):
        raw = node.targets
    else:
        raw = []
    out = []
    while raw:
        t = raw.pop()
        if isinstance(t, (ast.Tuple, ast.List)):
            raw.extend(t.elts)
        else:
            out.append(t)
    return out


def changed_names(tree: ast.Module) -> list[tuple[str, int, str]]:
    """(name, line, what) for every name a cell's top-level statements bind or modify in place."""
    out = []
    for node in tree.body:
        out += [(n, node.lineno, "assigned") for n in map(base, targets(node)) if n]
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            out.append((node.name, node.lineno, "redefined"))
        elif isinstance(node, (ast.Import, ast.ImportFrom)):
            out += [((a.asname or a.name).split(".")[0], node.lineno, "imported") for a in node.names]
        elif isinstance(node, (ast.For, ast.While, ast.If, ast.With, ast.Try)):
            # statements nested in top-level control flow run at top level too
            body = [s for s in ast.iter_child_nodes(node) if isinstance(s, ast.stmt)]
            body += [s for h in ast.iter_child_nodes(node) if isinstance(h, ast.ExceptHandler) for s in h.body]
            inner = ast.Module(body=body, type_ignores=[])
            out += changed_names(inner)
        # NAME.update(...), NAME.attr.sort(...), ... as a statement: an in-place change
        if isinstance(node, ast.Expr) and isinstance(node.value, ast.Call):
            f = node.value.func
            if isinstance(f, ast.Attribute) and f.attr in MUTATORS and base(f.value):
                out.append((base(f.value), node.lineno, f"changed by .{f.attr}()"))
    return out


def parameter_cells(nb: dict) -> tuple[int, list[tuple[int, str]]]:
    cells = [(i, "".join(c["source"])) for i, c in enumerate(nb["cells"]) if c["cell_type"] == "code"]
    tagged = [i for i, c in enumerate(nb["cells"]) if "parameters" in c.get("metadata", {}).get("tags", [])]
    assert len(tagged) == 1, "exactly one code cell is tagged `parameters`"
    return tagged[0], cells


def violations(nb: dict) -> list[str]:
    tagged, cells = parameter_cells(nb)
    params = {n for n, _, _ in changed_names(parse(dict(cells)[tagged]))}
    return [
        f"cell {i}, line {line}: parameter {name} {what} outside the parameters cell"
        for i, src in cells
        if i > tagged
        for name, line, what in changed_names(parse(src))
        if name in params
    ]


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_parameters_change_only_in_the_parameters_cell(path):
    bad = violations(json.loads(path.read_text(encoding="utf-8")))
    assert not bad, "\n".join(bad)


def _nb(*sources: str, tagged: int = 0) -> dict:
    return {
        "cells": [
            {"cell_type": "code", "source": s, "metadata": {"tags": ["parameters"]} if i == tagged else {}}
            for i, s in enumerate(sources)
        ]
    }


@pytest.mark.parametrize(
    "later",
    [
        "SEED = 3",
        "SEED += 1",
        "SEED: int = 3",
        "A, (B, SEED) = 1, (2, 3)",
        "for SEED in range(3):\n    pass",
        "with open('x') as SEED:\n    pass",
        "import numpy as SEED",
        "def SEED():\n    pass",
        "GRID[0] = 5",
        "GRID.sort()",
        "del GRID[0]",
        "CFG.rate = 2",
        "if True:\n    SEED = 4",
        "try:\n    pass\nexcept ValueError:\n    SEED = 1",
        "for k in range(2):\n    GRID.append(k)",
    ],
)
def test_a_later_change_fails(later):
    assert violations(_nb("SEED = 2000\nGRID = [1, 2]\nCFG = object()", later))


@pytest.mark.parametrize(
    "later",
    [
        "x = SEED + 1",
        "def f(SEED):\n    SEED = 1\n    return SEED",
        "grid = list(GRID)\ngrid[0] = 5",
        "print(GRID.count(1))",
        "lambda SEED: SEED",
        "[SEED for SEED in range(3)]",
    ],
)
def test_uses_and_local_names_pass(later):
    assert not violations(_nb("SEED = 2000\nGRID = [1, 2]", later))


def test_cells_before_the_parameters_cell_are_not_changes():
    """Imports and set-up run before the parameters cell (papermill injects its values after it)."""
    assert not violations(_nb("import numpy as np\nSEED = 0", "SEED = 2000", tagged=1))
