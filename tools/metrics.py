#!/usr/bin/env python3
"""Structure metrics of the navlib package, read from the source (nothing is imported).

* ``validation``: share of non-kernel code lines that validate arguments -- statements that
  raise (and the ``if`` that guards them), statements whose value is a validator's result (the
  functions of ``navlib._validate`` and private functions that only validate and return, i.e. clones
  of it, whose bodies count too) and ``_validate.py`` itself -- over all statement lines outside numba
  kernels (docstrings, comments and imports excluded).
* ``hinted``: public parameters (of public functions and public methods, ``self``/``cls`` excluded)
  that carry a type hint.
* ``kernel_params``: the largest parameter count of a numba ``@njit`` kernel.
* ``implementations``: how many places spell out each shared formula (pattern counts).

Usage: python tools/metrics.py [PATH_TO_NAVLIB]  (default: navlib/ of this checkout); prints JSON.
"""

from __future__ import annotations

import ast
import json
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
VALIDATE_NAMES = {
    "real",
    "as_array",
    "in_range",
    "positive",
    "latitude",
    "generator",
    "time_axis",
    "as_dcm",
    "as_quat",
    "scalar",
    "interval",
    "file_path",
    "integer",
    "flag",
    "choice",
    "full_scale",
    "intervals",
    "sample_intervals",
    "imu_samples",
    "nonempty_array",
    "nonempty_positive",
    "nonempty_latitude",
    "instance",
    "same_shape",
    "broadcast",
    "range_limit",
    "unit_interval",
    "booleans",
    "last_axis",
    "pitch_roll",
    "euler_angles",
    "small_turns",
    "text",
    "broadcast_to",
    "ellipsoid",
    "ellipsoid_",
    "numbers",
    "indices",
    "longitude",
    "lat_lon",
    "fields_checked",
    "boundary",
}
# One formula, one place: regular expressions that find where each is written out.
FORMULAS = {
    "levelling": r"arctan2\(\s*-\s*\w+\[\.\.\., 0\]|arctan2\(-ax, az\)|arcsin\(np\.clip\(f\[\.\.\., 1\]",
    "nan_hold": r"maximum\.accumulate\((?:idx|np\.where\([^)]*arange)",
    "dt_reading": r"def _?intervals\(|def _dt\(",
    "wrapping": r"[(%]\s*\(?2 \* np\.pi\)?\s*-\s*np\.pi|np\.mod\(\w+ \+ np\.pi, 2 \* np\.pi\)",
    "tilt_heading": r"arctan2\(-mhx, mhy\)",
}


def is_kernel(node: ast.AST) -> bool:
    return any("njit" in ast.unparse(d) or "vectorize" in ast.unparse(d) for d in getattr(node, "decorator_list", []))


def statement_lines(node: ast.stmt) -> set[int]:
    return set(range(node.lineno, (node.end_lineno or node.lineno) + 1))


def called(node: ast.AST) -> str:
    """The name of a function called by name (``scalar(...)``) or through ``_validate`` (``_validate.scalar(...)``);
    a method of another object (``ax.text(...)``, ``np.broadcast_to(...)``) is not a validator."""
    f = node.func if isinstance(node, ast.Call) else None
    if isinstance(f, ast.Attribute) and isinstance(f.value, ast.Name) and f.value.id == "_validate":
        return f.attr
    return f.id if isinstance(f, ast.Name) else ""


def validates(node: ast.stmt, validators: set[str]) -> bool:
    """A statement that raises on bad input, or whose value is a validator's result."""
    if isinstance(node, ast.Raise):
        return True
    if isinstance(node, ast.If) and node.body and all(isinstance(s, ast.Raise) for s in node.body) and not node.orelse:
        return True
    return called(getattr(node, "value", None)) in validators


def local_validators(tree: ast.Module) -> set[str]:
    """Private module functions whose body only validates and returns (clones of the validation layer)."""
    found = set(VALIDATE_NAMES)
    funcs = [n for n in tree.body if isinstance(n, ast.FunctionDef) and n.name.startswith("_") and not is_kernel(n)]
    changed = True
    while changed:
        changed = False
        for fn in funcs:
            body = [s for s in fn.body if not (isinstance(s, ast.Expr) and isinstance(s.value, ast.Constant))]
            if (
                fn.name not in found
                and body
                and all(validates(s, found) or isinstance(s, ast.Return) for s in body)
                and any(validates(s, found) for s in body)
            ):
                found.add(fn.name)
                changed = True
    return found


def file_metrics(path: Path) -> dict:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    code, check, kernels = set(), set(), []
    whole_file_validates = path.name == "_validate.py"
    validators = local_validators(tree)

    def visit(body, in_kernel=False):
        for node in body:
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                kernel = in_kernel or is_kernel(node)
                if node.name in validators and node.name not in VALIDATE_NAMES:  # a private validator clone
                    check.update(range(node.body[0].lineno, node.end_lineno + 1))
                if is_kernel(node) and isinstance(node, ast.FunctionDef):
                    kernels.append((node.name, len(node.args.args) + len(node.args.kwonlyargs)))
                inner = node.body
                if inner and isinstance(inner[0], ast.Expr) and isinstance(getattr(inner[0], "value", None), ast.Constant):
                    inner = inner[1:]  # docstring
                visit(inner, kernel)
                continue
            if in_kernel or (isinstance(node, ast.Expr) and isinstance(node.value, ast.Constant)):
                continue
            if isinstance(node, (ast.Import, ast.ImportFrom)):
                continue
            lines = statement_lines(node) if not hasattr(node, "body") else {node.lineno}
            code.update(lines)
            if whole_file_validates or validates(node, validators):
                check.update(statement_lines(node))
            for field in ("body", "orelse", "finalbody", "handlers"):
                sub = getattr(node, field, None)
                if sub and not (isinstance(node, ast.If) and validates(node, validators)):
                    visit(sub, in_kernel)

    visit(tree.body)
    hinted = total = 0
    for node in ast.walk(tree):
        if isinstance(node, ast.FunctionDef) and not node.name.startswith("_") and not is_kernel(node):
            params = node.args.posonlyargs + node.args.args + node.args.kwonlyargs
            params = [a for a in params if a.arg not in ("self", "cls")]
            params += [a for a in (node.args.vararg, node.args.kwarg) if a is not None]
            total += len(params)
            hinted += sum(a.annotation is not None for a in params)
    text = path.read_text(encoding="utf-8")
    return {
        "code": len(code),
        "validation": len(check & code),
        "hinted": hinted,
        "params": total,
        "kernels": kernels,
        "formulas": {k: len(re.findall(p, text)) for k, p in FORMULAS.items()},
    }


def metrics(package: Path) -> dict:
    files = {
        p.relative_to(package).as_posix(): file_metrics(p) for p in sorted(package.rglob("*.py")) if "__pycache__" not in p.parts
    }
    code = sum(f["code"] for f in files.values())
    check = sum(f["validation"] for f in files.values())
    hinted = sum(f["hinted"] for f in files.values())
    params = sum(f["params"] for f in files.values())
    kernels = sorted(((n, k, f) for f, m in files.items() for k, n in m["kernels"]), reverse=True)
    return {
        "validation_share": round(check / code, 3),
        "validation_lines": check,
        "code_lines": code,
        "hinted_share": round(hinted / params, 3),
        "hinted": hinted,
        "public_params": params,
        "largest_kernels": [f"{f}:{k} ({n})" for n, k, f in kernels[:5]],
        "implementations": {k: {f: m["formulas"][k] for f, m in files.items() if m["formulas"][k]} for k in FORMULAS},
        "validation_by_file": {f: f"{m['validation']}/{m['code']}" for f, m in files.items() if m["code"]},
    }


if __name__ == "__main__":
    package = Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "navlib"
    print(json.dumps(metrics(package), indent=1, ensure_ascii=False))
