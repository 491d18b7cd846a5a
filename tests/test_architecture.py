"""Module boundaries inside navlib, checked on the source (no import needed).

* Core modules (``navlib/*.py``, ``navlib/filters/``) never import ``navlib.papers``.
* Paper companions (``navlib/papers/<name>.py``) import core only: never another companion.
* No module uses another module's private name (``from .earth import _radii``,
  ``attitude._as_quat(...)``): what two modules share lives in the shared layers
  ``navlib._validate`` (argument validation), ``navlib._kernels`` (compiled primitives) and
  ``navlib._typing`` (shape aliases), or is public.
* The deprecated aliases of the old paper modules are imported by nothing in navlib.
"""
from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "navlib"
DEPRECATED = {"navlib.northfinding", "navlib.gyrobias", "navlib.planar", "navlib.ahrs", "navlib.pedestrian"}


def dotted(path: Path) -> str:
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


MODULES = {dotted(p): p for p in sorted(PACKAGE.rglob("*.py")) if "__pycache__" not in p.parts}
COMPANIONS = {m for m in MODULES if m.startswith("navlib.papers.")}
CORE = {m for m in MODULES if not m.startswith("navlib.papers") and m not in DEPRECATED}


def package_of(module: str) -> str:
    return module if MODULES.get(module, Path()).name == "__init__.py" else module.rpartition(".")[0]


def imports(module: str) -> list[tuple[str, str | None, int]]:
    """``(imported navlib module, name taken from it or None, line)`` for every import of a navlib module."""
    out = []
    for node in ast.walk(ast.parse(MODULES[module].read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            out += [(a.name, None, node.lineno) for a in node.names if a.name.startswith("navlib")]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package_of(module).split(".")
                base = base[:len(base) - (node.level - 1)]
                source = ".".join(base + ([node.module] if node.module else []))
            elif (node.module or "").startswith("navlib"):
                source = node.module
            else:
                continue
            for a in node.names:
                sub = f"{source}.{a.name}"
                out.append((sub, None, node.lineno) if sub in MODULES else (source, a.name, node.lineno))
    return out


def aliases(module: str) -> dict[str, str]:
    """Local names bound to navlib modules (``from . import earth as e`` -> ``{"e": "navlib.earth"}``)."""
    tree = ast.parse(MODULES[module].read_text(encoding="utf-8"))
    out = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            for a in node.names:
                for target, name, _ in imports(module):
                    if name is None and target.endswith("." + a.name):
                        out[a.asname or a.name] = target
    return out


@pytest.mark.parametrize("module", sorted(MODULES))
def test_no_private_names_of_other_modules(module):
    own = {module, package_of(module)}
    bad = [f"line {line}: {name} from {src}" for src, name, line in imports(module)
           if name and name.startswith("_") and src not in own]
    names = aliases(module)
    tree = ast.parse(MODULES[module].read_text(encoding="utf-8"))
    bad += [f"line {node.lineno}: {node.value.id}.{node.attr}" for node in ast.walk(tree)
            if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in names
            and node.attr.startswith("_") and not node.attr.startswith("__")]
    assert not bad, f"{module} uses private names of other modules:\n" + "\n".join(bad)


@pytest.mark.parametrize("module", sorted(CORE))
def test_core_never_imports_a_paper(module):
    bad = [f"line {line}: {src}" for src, _, line in imports(module)
           if src.startswith("navlib.papers.") or src in DEPRECATED]
    assert not bad, f"core module {module} imports paper code:\n" + "\n".join(bad)


@pytest.mark.parametrize("module", sorted(COMPANIONS))
def test_companions_import_core_only(module):
    bad = [f"line {line}: {src}" for src, _, line in imports(module)
           if (src in COMPANIONS and src != module) or src in DEPRECATED]
    assert not bad, f"companion {module} imports another paper's code:\n" + "\n".join(bad)


def test_the_checks_see_imports():
    found = {(src, name) for src, name, _ in imports("navlib.alignment")}
    assert ("navlib.attitude", None) in found and ("navlib._validate", "as_array") in found
    assert aliases("navlib.alignment")["attitude"] == "navlib.attitude"
    assert COMPANIONS and "navlib.filters" in CORE
