"""Module boundaries inside navlib, checked on the source (no import needed).

* Core modules (``navlib/*.py``, ``navlib/filters/``) never import ``navlib.papers``.
* Paper companions (``navlib/papers/<name>.py``) import core only: never another companion.
* No module uses another module's private name (``from .earth import _radii``,
  ``attitude._as_quat(...)``): what two modules share lives in the shared layers
  ``navlib._validate`` (argument validation), ``navlib._kernels`` (compiled primitives) and
  ``navlib._typing`` (shape aliases), in a private core module, or is public.
* Checked public functions live in the public modules; their unchecked cores, called with values already
  checked, live in a private core module ``navlib/_<name>.py`` (``navlib._earth``) under public names, where
  a function of another module that has checked the values itself calls them. A public function is thin:
  check, then call the core. A core module imports no public navlib module at run time and nothing from
  ``navlib._validate`` but the ``kernel_array`` conversion: it checks nothing.
* The deprecated aliases of the old paper modules are imported by nothing in navlib.
* No import cycle: the graph of navlib's imports, at module level or inside functions, is acyclic.
* Importing navlib's modules changes nothing process-wide (no numba event listener) unless asked to.
* Kernels are compiled with numba's public options only (no ``_nrt`` or other underscored option).
"""

from __future__ import annotations

import ast
import os
import subprocess
import sys
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "navlib"


def dotted(path: Path) -> str:
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


MODULES = {dotted(p): p for p in sorted(PACKAGE.rglob("*.py")) if "__pycache__" not in p.parts}
COMPANIONS = {m for m in MODULES if m.startswith("navlib.papers.")}
CORE = {m for m in MODULES if not m.startswith("navlib.papers")}


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
                base = base[: len(base) - (node.level - 1)]
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
    bad = [
        f"line {line}: {name} from {src}"
        for src, name, line in imports(module)
        if name and name.startswith("_") and src not in own
    ]
    names = aliases(module)
    tree = ast.parse(MODULES[module].read_text(encoding="utf-8"))
    bad += [
        f"line {node.lineno}: {node.value.id}.{node.attr}"
        for node in ast.walk(tree)
        if isinstance(node, ast.Attribute)
        and isinstance(node.value, ast.Name)
        and node.value.id in names
        and node.attr.startswith("_")
        and not node.attr.startswith("__")
    ]
    assert not bad, f"{module} uses private names of other modules:\n" + "\n".join(bad)


SHARED_LAYERS = {"navlib._validate", "navlib._kernels", "navlib._typing", "navlib._threads"}
CORE_MODULES = {m for m in MODULES if m.rpartition(".")[2].startswith("_") and m not in SHARED_LAYERS}
"""Private modules of unchecked cores (``navlib._earth``)."""


def checking_imports(module: str) -> list[str]:
    """The run-time imports that a core module must not make: a public navlib module, or a checker of _validate."""
    skip = type_checking_lines(ast.parse(MODULES[module].read_text(encoding="utf-8")))
    return [
        f"line {line}: {src}" + (f".{name}" if name else "")
        for src, name, line in imports(module)
        if line not in skip
        and (not src.rpartition(".")[2].startswith("_") or (src == "navlib._validate" and name != "kernel_array"))
    ]


@pytest.mark.parametrize("module", sorted(CORE_MODULES))
def test_core_modules_check_nothing(module):
    bad = checking_imports(module)
    assert not bad, f"core module {module} imports checked code (cores take checked values):\n" + "\n".join(bad)


@pytest.mark.parametrize("module", sorted(CORE))
def test_core_never_imports_a_paper(module):
    bad = [f"line {line}: {src}" for src, _, line in imports(module) if src.startswith("navlib.papers.")]
    assert not bad, f"core module {module} imports paper code:\n" + "\n".join(bad)


@pytest.mark.parametrize("module", sorted(COMPANIONS))
def test_companions_import_core_only(module):
    bad = [f"line {line}: {src}" for src, _, line in imports(module) if src in COMPANIONS and src != module]
    assert not bad, f"companion {module} imports another paper's code:\n" + "\n".join(bad)


def test_the_checks_see_imports():
    found = {(src, name) for src, name, _ in imports("navlib.alignment")}
    assert ("navlib.attitude", None) in found and ("navlib._validate", "as_array") in found
    assert aliases("navlib.alignment")["attitude"] == "navlib.attitude"
    assert COMPANIONS and "navlib.filters" in CORE
    assert "navlib._earth" in CORE_MODULES and "navlib._validate" not in CORE_MODULES
    assert checking_imports("navlib._earth") == [] and checking_imports("navlib.earth")  # earth imports checkers


def type_checking_lines(tree: ast.Module) -> set[int]:
    """Lines of the imports under ``if TYPE_CHECKING:`` (for type checkers only, never run)."""
    guarded = [
        node
        for node in ast.walk(tree)
        if isinstance(node, ast.If)
        and "TYPE_CHECKING" in {n.id if isinstance(n, ast.Name) else getattr(n, "attr", None) for n in ast.walk(node.test)}
    ]
    return {
        n.lineno for node in guarded for stmt in node.body for n in ast.walk(stmt) if isinstance(n, (ast.Import, ast.ImportFrom))
    }


def import_graph() -> dict[str, set[str]]:
    """Each navlib module -> the navlib modules it imports when it runs (at module level or deferred in a function)."""
    graph = {}
    for module, path in MODULES.items():
        skip = type_checking_lines(ast.parse(path.read_text(encoding="utf-8")))
        graph[module] = {src for src, _, line in imports(module) if src in MODULES and src != module and line not in skip}
    return graph


def find_cycle(graph: dict[str, set[str]]) -> list[str]:
    """One cycle of ``graph`` as a path ``[a, b, ..., a]``, or ``[]`` when there is none (depth-first search)."""
    done, path = set(), []

    def visit(node):
        path.append(node)
        for nxt in sorted(graph.get(node, ())):
            if nxt in path:
                return path[path.index(nxt) :] + [nxt]
            if nxt not in done and (cycle := visit(nxt)):
                return cycle
        path.pop()
        done.add(node)
        return []

    for node in sorted(graph):
        if node not in done and (cycle := visit(node)):
            return cycle
    return []


def test_no_import_cycle():
    cycle = find_cycle(import_graph())
    assert not cycle, "import cycle: " + " -> ".join(cycle)


def test_the_cycle_check_sees_cycles_and_deferred_imports():
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b", "c"}, "b": {"c"}, "c": set()}) == []
    graph = import_graph()
    assert "navlib.plots" in graph["navlib.papers.pedestrian_ins"]  # imported inside a function


IMPORT_ALL = """
import importlib, sys, warnings
from numba.core import event

def listeners():
    return {kind: list(found) for kind, found in event._registered.items() if found}

registered, register = [], event.register
event.register = lambda kind, listener: (registered.append(kind), register(kind, listener))[1]
before = listeners()
with warnings.catch_warnings():
    warnings.simplefilter("ignore")                  # the deprecated aliases warn
    for name in sys.argv[1:]:
        importlib.import_module(name)
print(registered, listeners() == before)
"""


def import_all_in_a_fresh_process(**env) -> str:
    """Import every navlib module in a new interpreter; report the numba event kinds registered meanwhile
    (through ``numba.core.event.register``) and whether numba's listener registry is unchanged."""
    environ = {k: v for k, v in os.environ.items() if k != "NAVLIB_COMPILE_LOG"} | env
    done = subprocess.run(
        [sys.executable, "-c", IMPORT_ALL, *sorted(MODULES)],
        env=environ,
        cwd=PACKAGE.parent,
        capture_output=True,
        text=True,
        check=True,
    )
    return done.stdout.strip().splitlines()[-1]


def test_importing_navlib_installs_no_numba_listener():
    """numba's compile events stay the user's: navlib registers a listener only when NAVLIB_COMPILE_LOG asks."""
    assert import_all_in_a_fresh_process() == "[] True"


def test_the_compile_log_is_opt_in(tmp_path):
    assert import_all_in_a_fresh_process(NAVLIB_COMPILE_LOG=str(tmp_path / "compile.log")) == "['numba:compile'] False"


MAX_PARAMETERS = 12
"""No function (public, private or compiled) takes more: options go into small frozen records."""


def njit_options(tree: ast.AST) -> set[str]:
    """Keyword names passed to any ``njit``/``jit``/``vectorize`` call or decorator, ``**dict`` literals included."""
    names: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Call) and ast.unparse(node.func).split(".")[-1] in {"njit", "jit", "vectorize"}:
            for kw in node.keywords:
                if kw.arg is not None:
                    names.add(kw.arg)
                elif isinstance(kw.value, ast.Dict):
                    names |= {k.value for k in kw.value.keys if isinstance(k, ast.Constant)}
                else:
                    names.add("**" + ast.unparse(kw.value))
    return names


@pytest.mark.parametrize("module", sorted(MODULES))
def test_kernels_use_public_numba_options_only(module):
    options = njit_options(ast.parse(MODULES[module].read_text()))
    private = sorted(o for o in options if o.startswith(("_", "**")))
    assert not private, f"{module}: numba options {private}: use numba's public options only (cache, nogil, inline, ...)"


def test_the_option_check_sees_private_options():
    tree = ast.parse("@njit(cache=True, _nrt=False)\ndef f(): pass\n@njit(**OPTS)\ndef g(): pass")
    assert {"_nrt", "**OPTS"} <= njit_options(tree)


def test_no_function_takes_more_than_twelve_parameters():
    wide = []
    for module, path in MODULES.items():
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                a = node.args
                n = len(a.posonlyargs) + len(a.args) + len(a.kwonlyargs) + (a.vararg is not None) + (a.kwarg is not None)
                if n > MAX_PARAMETERS:
                    wide.append(f"{module}.{node.name}: {n}")
    assert not wide, "functions with more than 12 parameters:\n" + "\n".join(wide)


def test_no_public_name_is_defined_twice():
    """A name in the ``__all__`` of two public modules is one concept with two owners (``_kernels``' compiled
    twins are private and do not count)."""
    owners = {}
    for module, path in MODULES.items():
        if any(part.startswith("_") for part in module.split(".")[1:]):
            continue
        tree = ast.parse(path.read_text(encoding="utf-8"))
        defined = {n.name for n in tree.body if isinstance(n, (ast.FunctionDef, ast.ClassDef))}
        defined |= {t.id for n in tree.body if isinstance(n, ast.Assign) for t in n.targets if isinstance(t, ast.Name)}
        exported = next(
            (
                n.value
                for n in tree.body
                if isinstance(n, ast.Assign) and any(isinstance(t, ast.Name) and t.id == "__all__" for t in n.targets)
            ),
            None,
        )
        names = {e.value for e in getattr(exported, "elts", []) if isinstance(e, ast.Constant)}
        for name in names & defined:
            owners.setdefault(name, []).append(module)
    twice = {name: mods for name, mods in owners.items() if len(mods) > 1}
    assert not twice, f"public names defined in more than one module: {twice}"
