"""Every check's value is computed: a static reading of the notebooks' check calls (issue 14, item 2).

A check (``repro.check``, ``check_range``, ``check_outside``) compares a value computed by navlib from
simulated or committed data with a target. This test reads every code cell of ``notebooks/*.ipynb`` in
order, without running anything, follows each name to what it was bound to, and fails a check whose
value argument

* is a **literal**, or arithmetic on literals only (``0.5 * 0.1 * 9.80665 * 10 ** 2``);
* comes only from **inputs**: constants of the notebook's ``parameters`` cell, typed data (a table read
  from ``data/``, a sensor preset, an upper-case constant of a paper companion) and literals, through
  any amount of arithmetic or numpy, with no navlib computation, no random draw and no recording in
  between (a drift compared with the drift that was injected; a typed table value checked against the
  same number typed again);
* is the **same expression as its target** (``expected``, ``paper_value``, ``lower``, ``upper``), or a
  rounding of it, or the target a rounding of the value (``check(name, err, round(err, 2), ...)``);
* is a **simulation recovering its own input**: the spread (std, var) of simulated samples, with nothing but
  the truth subtracted (no estimator, filter or other navlib computation in between), against a target built
  from the very input the simulation was given (the sd of an injected 0.04 G noise against 0.04 G);
* asserts a disagreement (``check_outside``) with a **band around the project's own assumed number**: a bound
  built from a constant of the parameters cell, which the paper never stated;
* is checked against a **band that contains every possible value**: a share (the mean of a comparison) within
  [0, 1] or wider.

Arithmetic on the paper's own printed numbers (a column against the total the text prints, a formula's
constant against the published constants it comes from) is legitimate but is not a reproduction: such a
check says so with ``on_printed=True`` (recorded in results.json), and then its value must come from typed
data (a ``data/`` table, a paper or navlib constant) through arithmetic — not from a computation, not from
literals or parameters alone, not a single typed number.

What counts as a computation: a call into navlib other than the unit conversions of ``navlib.units``, ``repro``'s
paths and the sensor presets (``repro.seed_spread``, a recorded seed study of the simulation, is one); a draw from
``numpy.random``; a third-party library (scipy, ahrs, imufusion, ...); data read from ``data/real`` or
``data/samples`` (recordings). numpy, pandas, ``math`` and the builtins only transform what they are given. Calls go
through local aliases (``chk = repro.check``), helper functions and lambdas (their body is read with the caller's
arguments), loops and comprehensions.

A legitimate exception is declared in ``ALLOWED`` — notebook stem, check name (``*`` for the formatted
part of an f-string name) and the reason, one line each; an entry that matches nothing fails, so the
list cannot go stale. ``navlib.repro`` adds the run-time half: ``check`` refuses a value that is the very
object passed as its target.
"""

from __future__ import annotations

import ast
import builtins
import json
import re
from dataclasses import dataclass, field
from fnmatch import fnmatchcase
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = sorted((ROOT / "notebooks").glob("[0-9][0-9]_*.ipynb"))

# Legitimate exceptions: (notebook stem, check name pattern) -> why the value may be an input. Keep it tiny.
ALLOWED: dict[tuple[str, str], str] = {}

LITERAL, PARAMETER, DATA, COMPUTED = range(4)
ORIGIN = {
    LITERAL: "literals only",
    PARAMETER: "parameters-cell constants and literals only",
    DATA: "typed inputs only (data/ tables, sensor presets, paper constants, parameters, literals)",
}

SIGNATURES = {
    "check": ("name", "value", "expected", "tol", "source"),
    "check_range": ("name", "value", "source"),
    "check_outside": ("name", "value", "source"),
    "check_study": ("name", "value", "target", "study", "source"),
}
TARGETS = ("expected", "target", "paper_value", "lower", "upper")
DRAWS = ("numpy.random", "navlib.sensors.simulate_")  # where simulated samples come from
TRUTH = ("navlib.attitude.", "navlib.trajectory.", "navlib.earth.", "navlib.units.", "navlib.repro.")  # no estimator
SPREADS = {"std", "var", "nanstd", "nanvar"}
TRANSPARENT = (
    "numpy.",
    "pandas.",
    "math.",
    "builtins.",
    "statistics.",
    "itertools.",
    "functools.",
    "collections.",
    "operator.",
    "navlib.units.",
    "navlib.repro.",
    "navlib.attitude.wrap_pi",
    "navlib.attitude.wrap_2pi",
)
LOADERS = {
    "pandas.read_csv",
    "pandas.read_table",
    "pandas.read_json",
    "numpy.loadtxt",
    "numpy.genfromtxt",
    "numpy.load",
    "json.load",
    "json.loads",
    "csv.reader",
    "csv.DictReader",
    "builtins.open",
}
PRESETS = {"navlib.sensors.imu_model"}
RECORDINGS = re.compile(r"\b(real|samples)\b")  # data/real, data/samples: committed measurements
ROUNDERS = {
    "builtins.round",
    "builtins.float",
    "builtins.int",
    "builtins.format",
    "numpy.round",
    "numpy.around",
    "numpy.rint",
    "numpy.floor",
    "numpy.ceil",
    "numpy.float64",
    "numpy.float32",
    "numpy.asarray",
    "numpy.array",
    "math.floor",
    "math.ceil",
}
ROUNDING_METHODS = {"round", "item", "astype", "copy", "squeeze"}
ACCESSORS = {"to_numpy", "set_index", "reset_index", "item", "squeeze", "astype", "copy", "loc", "iloc"}
MUTATORS = {"append", "extend", "insert", "update", "setdefault", "add", "fill", "put", "__setitem__"}
BUILTINS = set(dir(builtins))
CONSTANT = re.compile(r"_*[A-Z][A-Z0-9_]*")


# ------------------------------------------------------------------------------------------- bindings


@dataclass
class Value:
    """A name bound to a value: its origin (LITERAL..COMPUTED) and the expression it came from."""

    origin: int
    expr: ast.expr | None = None
    scope: Scope | None = None


@dataclass
class Module:
    """A name bound to a module or to an object imported from one (dotted path)."""

    path: str


@dataclass(eq=False)
class Function:
    node: ast.FunctionDef | ast.AsyncFunctionDef | ast.Lambda
    scope: Scope
    called: bool = False


class Scope:
    def __init__(self, parent: Scope | None = None):
        self.names: dict[str, Value | Module | Function] = {}
        self.parent = parent

    def get(self, name: str):
        s = self
        while s is not None:
            if name in s.names:
                return s.names[name]
            s = s.parent
        return None

    def set(self, name: str, b, merge: bool = False) -> None:
        old = self.names.get(name)
        if merge and isinstance(old, Value) and isinstance(b, Value):  # a branch or loop body may not run
            b = Value(max(old.origin, b.origin), b.expr, b.scope)
        self.names[name] = b


@dataclass
class Finding:
    cell: int
    line: int
    check: str
    reasons: list[str] = field(default_factory=list)

    def __str__(self) -> str:
        return f"cell {self.cell}, line {self.line}: {self.check}: " + "; ".join(self.reasons)


# --------------------------------------------------------------------------------------------- reader


class Reader:
    """Reads a notebook's code cells in order and collects the checks whose value is not computed."""

    def __init__(self):
        self.top = Scope()
        self.findings: dict[tuple, Finding] = {}
        self.n_checks = 0
        self.functions: list[Function] = []
        self.active: list[Function] = []
        self.returns: list[list[int]] = []
        self.cell = self.line = 0
        self.in_parameters = False
        self.parameter_names: set[str] = set()

    # -- driving
    def read(self, cells: list[tuple[int, str, bool]]) -> list[Finding]:
        for index, src, parameters in cells:
            tree = ast.parse("\n".join(line for line in src.splitlines() if not line.lstrip().startswith(("%", "!"))))
            self.cell, self.in_parameters = index, parameters
            for node in tree.body:
                self.line = node.lineno
                self.stmt(node, self.top, merge=False)
        self.in_parameters = False
        for f in self.functions:  # never called (or only handed to widgets): read once
            if not f.called:
                self.call_function(f, None, self.top)
        return list(self.findings.values())

    # -- statements
    def block(self, body, scope, merge):
        for node in body:
            self.stmt(node, scope, merge)

    def stmt(self, node, scope, merge):
        if isinstance(node, ast.Assign):
            origin = self.value(node.value, scope)
            for t in node.targets:
                self.bind(t, node.value, origin, scope, merge)
        elif isinstance(node, ast.AnnAssign):
            if node.value is not None:
                self.bind(node.target, node.value, self.value(node.value, scope), scope, merge)
        elif isinstance(node, ast.AugAssign):
            self.bind(node.target, None, self.value(node.value, scope), scope, merge=True)
        elif isinstance(node, (ast.For, ast.AsyncFor)):
            self.bind(node.target, None, self.value(node.iter, scope), scope, merge)
            self.block(node.body, scope, True)
            self.block(node.orelse, scope, True)
        elif isinstance(node, (ast.While, ast.If)):
            self.value(node.test, scope)
            self.block(node.body, scope, True)
            self.block(node.orelse, scope, True)
        elif isinstance(node, (ast.With, ast.AsyncWith)):
            for item in node.items:
                origin = self.value(item.context_expr, scope)
                if item.optional_vars is not None:
                    self.bind(item.optional_vars, None, origin, scope, merge)
            self.block(node.body, scope, merge)
        elif isinstance(node, ast.Try) or type(node).__name__ == "TryStar":
            self.block(node.body, scope, True)
            for h in node.handlers:
                if h.name:
                    scope.set(h.name, Value(COMPUTED))
                self.block(h.body, scope, True)
            self.block(node.orelse, scope, True)
            self.block(node.finalbody, scope, merge)
        elif isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            for d in node.decorator_list:
                self.value(d, scope)
            f = Function(node, scope)
            self.functions.append(f)
            scope.set(node.name, f)
        elif isinstance(node, ast.ClassDef):
            scope.set(node.name, Value(COMPUTED))
        elif isinstance(node, ast.Import):
            for a in node.names:
                scope.set(a.asname or a.name.split(".")[0], Module(a.name if a.asname else a.name.split(".")[0]))
        elif isinstance(node, ast.ImportFrom):
            for a in node.names:
                if a.name != "*":
                    scope.set(a.asname or a.name, Module(f"{node.module}.{a.name}"))
        elif isinstance(node, ast.Return):
            origin = self.value(node.value, scope) if node.value is not None else LITERAL
            if self.returns:
                self.returns[-1].append(origin)
        elif isinstance(node, ast.Expr):
            self.value(node.value, scope)
            self.mutation(node.value, scope)
        else:
            for child in ast.iter_child_nodes(node):
                if isinstance(child, ast.expr):
                    self.value(child, scope)

    def mutation(self, e, scope):
        """``x.append(v)`` and friends: x now also holds v."""
        if isinstance(e, ast.Call) and isinstance(e.func, ast.Attribute) and e.func.attr in MUTATORS:
            name = base_name(e.func.value)
            old = scope.get(name) if name else None
            if isinstance(old, Value):
                origin = max(
                    [old.origin] + [self.value(a, scope) for a in e.args] + [self.value(k.value, scope) for k in e.keywords]
                )
                scope.set(name, Value(origin, None, scope))

    def bind(self, target, expr, origin, scope, merge):
        if isinstance(target, ast.Name):
            if expr is not None:
                alias = self.alias(expr, scope)
                if alias is not None:
                    scope.set(target.id, alias)
                    return
            if self.in_parameters and scope is self.top:
                self.parameter_names.add(target.id)
                origin = min(origin, PARAMETER) if origin <= PARAMETER else origin
            scope.set(target.id, Value(origin, expr, scope), merge)
        elif isinstance(target, (ast.Tuple, ast.List)):
            parts = expr.elts if isinstance(expr, (ast.Tuple, ast.List)) else None
            if parts is not None and len(parts) == len(target.elts) and not any(isinstance(p, ast.Starred) for p in parts):
                for t, p in zip(target.elts, parts, strict=True):
                    self.bind(t, p, self.value(p, scope), scope, merge)
            else:
                for t in target.elts:
                    self.bind(t, None, origin, scope, merge)
        elif isinstance(target, ast.Starred):
            self.bind(target.value, None, origin, scope, merge)
        elif isinstance(target, (ast.Subscript, ast.Attribute)):
            if isinstance(target, ast.Subscript):
                self.value(target.slice, scope)
            name = base_name(target)
            old = scope.get(name) if name else None
            if isinstance(old, Value):
                scope.set(name, Value(max(old.origin, origin), None, scope))
            elif name and old is None:
                scope.set(name, Value(origin, None, scope))

    def alias(self, expr, scope):
        """A name bound to a module object or to a function: ``chk = repro.check``, ``f = lambda ...``."""
        if isinstance(expr, ast.Lambda):
            f = Function(expr, scope)
            self.functions.append(f)
            return f
        if isinstance(expr, ast.Name) and isinstance(scope.get(expr.id), Function):
            return scope.get(expr.id)
        path = qualname(expr, scope)
        return Module(path) if path is not None else None

    # -- expressions
    def value(self, e, scope) -> int:
        """The origin of an expression: the highest origin among what it depends on."""
        if e is None or isinstance(e, ast.Constant):
            return LITERAL
        if isinstance(e, ast.Name):
            b = scope.get(e.id)
            if isinstance(b, Value):
                return b.origin
            if isinstance(b, Module):
                return module_object(b.path)
            if isinstance(b, Function):
                return LITERAL
            return LITERAL if e.id in BUILTINS else COMPUTED  # unknown names are not held against a check
        if isinstance(e, ast.Attribute):
            path = qualname(e, scope)
            return module_object(path) if path is not None else self.value(e.value, scope)
        if isinstance(e, ast.Subscript):  # a computed index (argmax) makes the selection a result
            return max(self.value(e.value, scope), self.value(e.slice, scope))
        if isinstance(e, ast.Call):
            return self.call(e, scope)
        if isinstance(e, ast.NamedExpr):
            origin = self.value(e.value, scope)
            self.bind(e.target, e.value, origin, scope, merge=False)
            return origin
        if isinstance(e, ast.Lambda):
            return LITERAL
        if isinstance(e, (ast.ListComp, ast.SetComp, ast.GeneratorExp, ast.DictComp)):
            inner = Scope(scope)
            origins = []
            for g in e.generators:
                origins.append(self.value(g.iter, inner))
                self.bind(g.target, None, origins[-1], inner, merge=False)
                for cond in g.ifs:
                    self.value(cond, inner)
            parts = [e.key, e.value] if isinstance(e, ast.DictComp) else [e.elt]
            return max(origins + [self.value(p, inner) for p in parts])
        children = [c for c in ast.iter_child_nodes(e) if isinstance(c, ast.expr)]
        return max([self.value(c, scope) for c in children], default=LITERAL)

    def call(self, e: ast.Call, scope) -> int:
        kind = check_kind(e.func, scope)
        if kind is not None:
            self.check(kind, e, scope)
            return COMPUTED
        b = scope.get(e.func.id) if isinstance(e.func, ast.Name) else None
        if isinstance(b, Function):
            return self.call_function(b, e, scope)
        args = max([self.value(a, scope) for a in e.args] + [self.value(k.value, scope) for k in e.keywords], default=LITERAL)
        path = qualname(e.func, scope)
        if path is None:  # a method of a value (x.mean()) or a call of a computed callable
            return max(args, self.value(e.func.value if isinstance(e.func, ast.Attribute) else e.func, scope))
        if path in LOADERS:
            return COMPUTED if any(RECORDINGS.search(s) for s in strings(e, scope)) else DATA
        if path in PRESETS:
            return max(DATA, args)
        if path.startswith("numpy.random") or path == "navlib.repro.seed_spread":  # a seed study: simulated values
            return COMPUTED
        if path.startswith(TRANSPARENT):
            return args
        return COMPUTED  # navlib, scipy, ahrs, time, ...: a computation

    def call_function(self, f: Function, e: ast.Call | None, scope) -> int:
        """Read a local function's body with the caller's arguments bound to its parameters."""
        if f in self.active or len(self.active) > 8:
            return COMPUTED
        f.called = f.called or e is not None
        inner = Scope(f.scope)
        a = f.node.args
        positional = a.posonlyargs + a.args
        defaults = dict(zip([p.arg for p in positional[len(positional) - len(a.defaults) :]], a.defaults, strict=True))
        defaults.update({p.arg: d for p, d in zip(a.kwonlyargs, a.kw_defaults, strict=True) if d is not None})
        bound: dict[str, Value] = {}
        if e is None:  # no call site: parameters are unknown
            bound = {p.arg: Value(COMPUTED) for p in positional + a.kwonlyargs}
        else:
            rest = []
            for i, arg in enumerate(e.args):
                if isinstance(arg, ast.Starred) or i >= len(positional):
                    rest.append(self.value(arg, scope))
                else:
                    bound[positional[i].arg] = Value(self.value(arg, scope), arg, scope)
            for k in e.keywords:
                if k.arg is None:
                    rest.append(self.value(k.value, scope))
                else:
                    bound[k.arg] = Value(self.value(k.value, scope), k.value, scope)
            for p in positional + a.kwonlyargs:
                if p.arg not in bound:
                    d = defaults.get(p.arg)
                    bound[p.arg] = (
                        Value(max(rest), None, scope)
                        if rest
                        else Value(self.value(d, f.scope), d, f.scope)
                        if d is not None
                        else Value(COMPUTED)
                    )
        for p in (a.vararg, a.kwarg):
            if p is not None:
                bound[p.arg] = Value(COMPUTED)
        for name, v in bound.items():
            inner.set(name, v)
        self.active.append(f)
        self.returns.append([])
        try:
            if isinstance(f.node, ast.Lambda):
                return self.value(f.node.body, inner)
            self.block(f.node.body, inner, merge=False)
            generator = any(isinstance(n, (ast.Yield, ast.YieldFrom)) for n in ast.walk(f.node))
            return COMPUTED if generator else max(self.returns[-1], default=LITERAL)
        finally:
            self.active.pop()
            self.returns.pop()

    # -- the checks
    def check(self, kind: str, e: ast.Call, scope) -> None:
        sig = SIGNATURES[kind]
        args = {}
        for i, a in enumerate(e.args):
            if isinstance(a, ast.Starred):
                return  # unreadable call: nothing to hold against it
            if i < len(sig):
                args[sig[i]] = a
        for k in e.keywords:
            if k.arg is None:
                return
            args[k.arg] = k.value
        self.n_checks += 1
        if "value" not in args:
            return
        reasons = []
        origin = self.value(args["value"], scope)
        printed = isinstance(args.get("on_printed"), ast.Constant) and args["on_printed"].value is True
        if not printed and origin < COMPUTED:
            reasons.append(f"its value comes from {ORIGIN[origin]}, no computation")
        elif printed and origin == COMPUTED:
            reasons.append("on_printed=True, but its value is computed: drop on_printed")
        elif printed and origin < DATA:
            reasons.append(
                f"on_printed=True, but its value comes from {ORIGIN[origin]}: the paper's numbers are read "
                "from data/ (or a paper constant), not typed into the notebook"
            )
        elif printed and bare(args["value"], scope):
            reasons.append("on_printed=True, but its value is one typed number, not arithmetic on printed numbers")
        reasons += self.cannot_fail(kind, args, scope)
        mine = forms(args["value"], scope)
        for key in TARGETS:
            if key in args:
                self.value(args[key], scope)
                if mine & forms(args[key], scope):
                    reasons.append(f"its value is {key} itself (or a rounding of it, or it of the value)")
        if reasons:
            name = name_pattern(args.get("name"), scope)
            key = (self.cell, self.line, name)
            found = self.findings.setdefault(key, Finding(self.cell, self.line, name))
            found.reasons += [r for r in reasons if r not in found.reasons]

    def cannot_fail(self, kind: str, args: dict, scope) -> list[str]:
        """The three patterns of a check that cannot fail whatever navlib computes (module docstring)."""
        reasons = []
        value = Closure(args["value"], scope)
        targets = [Closure(args[k], scope) for k in ("expected", "target", "lower", "upper") if k in args]
        if any(raw.draw_inputs & t.inputs for raw in value.raw_spreads for t in targets):
            reasons.append(
                "a simulation recovering its own input: the spread of simulated samples against the noise it was given"
            )
        centres = {self.centre(args[k], scope) for k in ("lower", "upper") if k in args}
        if kind == "check_outside" and len(centres) == 1 and None not in centres and "lower" in args and "upper" in args:
            reasons.append(
                "a disagreement asserted against a band around the project's own assumed number (a parameters-cell constant)"
            )
        lo, hi = (args.get(k) for k in ("lower", "upper"))
        if (
            kind == "check_range"
            and value.share
            and all(isinstance(b, ast.Constant) for b in (lo, hi))
            and lo.value <= 0
            and hi.value >= 1
        ):
            reasons.append("a band that contains every possible value (a share within [0, 1])")
        return reasons

    def centre(self, e, scope) -> str | None:
        """The parameters-cell constant a bound is built around (``RTK_SIGMA_DEG - band``), or None."""
        e = strip(e, scope)
        if isinstance(e, ast.BinOp) and isinstance(e.op, (ast.Add, ast.Sub)):
            for side in (e.left, e.right):
                if isinstance(side, ast.Name) and side.id in self.parameter_names:
                    return side.id
        return None


class Closure:
    """What an expression depends on, following names: the names, the typed inputs, the draws and their inputs."""

    def __init__(self, e, scope, depth: int = 0):
        self.inputs: set[str] = set()  # parameters-cell names and typed-data subscripts, as source text
        self.draw_inputs: set[str] = set()  # ... of them given to a random draw or a sensor simulation
        self.processing = False  # a navlib computation other than a draw or the truth's geometry
        self.raw_spreads: list[Closure] = []  # std / var taken of simulated samples with no such computation between
        top = strip(e, scope)
        self.share = (
            isinstance(top, ast.Call)
            and (qualname(top.func, scope) or "").endswith(".mean")
            and any(isinstance(n, ast.Compare) for a in top.args for n in ast.walk(a))
        )
        self.walk(e, scope, depth, in_draw=False)

    def walk(self, e, scope, depth: int, in_draw: bool) -> None:
        if e is None or depth > 10:
            return
        if isinstance(e, ast.Call):
            path = qualname(e.func, scope) or ""
            last = e.func.attr if isinstance(e.func, ast.Attribute) else path.rpartition(".")[2]
            if last in SPREADS:
                operand = Closure(
                    e.func.value if isinstance(e.func, ast.Attribute) and not path else (e.args[0] if e.args else None),
                    scope,
                    depth + 1,
                )
                if operand.draw_inputs and not operand.processing:
                    self.raw_spreads.append(operand)
            draw = path.startswith(DRAWS) or last in ("normal", "standard_normal")
            if path.startswith("navlib.") and not path.startswith(TRUTH) and not (draw or in_draw):
                self.processing = True
            for a in [e.func, *e.args, *(k.value for k in e.keywords)]:
                self.walk(a, scope, depth, in_draw or draw)
            return
        if isinstance(e, (ast.Name, ast.Subscript)):
            name = base_name(e)
            b = scope.get(name) if name else None
            if isinstance(b, Value) and b.origin <= DATA:
                self.inputs.add(ast.unparse(e))
                if in_draw:
                    self.draw_inputs.add(ast.unparse(e))
            if isinstance(e, ast.Name) and isinstance(b, Value) and b.expr is not None:
                self.walk(b.expr, b.scope, depth + 1, in_draw)
                return
        for child in ast.iter_child_nodes(e):
            if isinstance(child, ast.expr):
                self.walk(child, scope, depth, in_draw)


# -------------------------------------------------------------------------------------------- helpers


def base_name(node) -> str | None:
    while isinstance(node, (ast.Subscript, ast.Attribute, ast.Starred)):
        node = node.value
    return node.id if isinstance(node, ast.Name) else None


def qualname(e, scope) -> str | None:
    """The dotted path of a module object (``np.round`` -> ``numpy.round``), or None for a value."""
    if isinstance(e, ast.Name):
        b = scope.get(e.id)
        if isinstance(b, Module):
            return b.path
        return f"builtins.{e.id}" if b is None and e.id in BUILTINS else None
    if isinstance(e, ast.Attribute):
        head = qualname(e.value, scope)
        return f"{head}.{e.attr}" if head is not None else None
    return None


def module_object(path: str) -> int:
    """The origin of a module attribute used as a value (``np.pi``, ``gauss_kruger_ekf.Q_PAPER``)."""
    if path.startswith("navlib."):
        return DATA if CONSTANT.fullmatch(path.rsplit(".", 1)[-1]) else LITERAL
    return LITERAL if path.startswith(TRANSPARENT) else COMPUTED


def check_kind(func, scope) -> str | None:
    path = qualname(func, scope)
    if path is not None:
        head, _, last = path.rpartition(".")
        return last if head == "navlib.repro" and last in SIGNATURES else None
    # not resolved (a star import, an unknown object): go by the name, erring on the side of reading it
    last = func.id if isinstance(func, ast.Name) else func.attr if isinstance(func, ast.Attribute) else None
    if isinstance(func, ast.Name) and scope.get(last) is not None:
        return None
    return last if last in SIGNATURES else None


def bare(e, scope, depth: int = 0) -> bool:
    """Is the expression one typed input, only converted (a data-entry check), rather than arithmetic on inputs?"""
    while True:
        e = strip(e, scope)
        if isinstance(e, ast.UnaryOp):
            e = e.operand
        elif (
            isinstance(e, ast.Call)
            and len(e.args) == 1
            and (qualname(e.func, scope) or "").startswith(("navlib.units.", "numpy.abs", "builtins.abs"))
        ):
            e = e.args[0]
        elif (
            isinstance(e, ast.Call)
            and isinstance(e.func, ast.Attribute)
            and e.func.attr in ACCESSORS
            and qualname(e.func, scope) is None
        ):
            e = e.func.value
        else:
            break
    if isinstance(e, ast.Call):
        return qualname(e.func, scope) in LOADERS | PRESETS
    if isinstance(e, ast.Subscript):
        fixed = isinstance(e.slice, ast.Constant) or (
            isinstance(e.slice, ast.Tuple) and all(isinstance(x, ast.Constant) for x in e.slice.elts)
        )
        return fixed and bare(e.value, scope, depth)
    if isinstance(e, ast.Attribute):
        return qualname(e, scope) is not None or bare(e.value, scope, depth)
    if isinstance(e, ast.Name) and depth < 6:
        b = scope.get(e.id)
        if isinstance(b, Module):
            return True
        return isinstance(b, Value) and b.expr is not None and bare(b.expr, b.scope, depth + 1)
    return False


def strings(e, scope, depth: int = 0) -> list[str]:
    """The string constants an expression is built from, following names (a loader's path)."""
    out = []
    for n in ast.walk(e):
        if isinstance(n, ast.Constant) and isinstance(n.value, str):
            out.append(n.value)
        elif isinstance(n, ast.Name) and depth < 6:
            b = scope.get(n.id)
            if isinstance(b, Value) and b.expr is not None:
                out += strings(b.expr, b.scope, depth + 1)
    return out


def strip(e, scope):
    """An expression without its roundings and conversions: ``round(x, 2)``, ``float(f"{x:.2f}")`` -> ``x``."""
    while True:
        if isinstance(e, ast.Call) and e.args and qualname(e.func, scope) in ROUNDERS:
            e = e.args[0]
        elif (
            isinstance(e, ast.Call)
            and isinstance(e.func, ast.Attribute)
            and e.func.attr in ROUNDING_METHODS
            and qualname(e.func, scope) is None
        ):
            e = e.func.value
        elif isinstance(e, ast.JoinedStr) and len(e.values) == 1 and isinstance(e.values[0], ast.FormattedValue):
            e = e.values[0].value
        else:
            return e


def forms(e, scope, depth: int = 0) -> set[str]:
    """The expression, rounding stripped, and what its name was bound to (recursively)."""
    e = strip(e, scope)
    out = {ast.dump(e, annotate_fields=False, include_attributes=False)}
    if isinstance(e, ast.Name) and depth < 6:
        b = scope.get(e.id)
        if isinstance(b, Value) and b.expr is not None:
            out |= forms(b.expr, b.scope, depth + 1)
    return out


def name_pattern(e, scope) -> str:
    """A check's name as a pattern: an f-string's formatted parts become ``*``."""
    if isinstance(e, ast.Constant) and isinstance(e.value, str):
        return e.value
    if isinstance(e, ast.JoinedStr):
        return "".join(v.value if isinstance(v, ast.Constant) else "*" for v in e.values)
    if isinstance(e, ast.BinOp) and isinstance(e.op, ast.Add):
        return name_pattern(e.left, scope) + name_pattern(e.right, scope)
    if isinstance(e, ast.Name):
        b = scope.get(e.id)
        if isinstance(b, Value) and b.expr is not None and not isinstance(b.expr, ast.Name):
            return name_pattern(b.expr, b.scope)
    return "*"


def cells_of(path: Path) -> list[tuple[int, str, bool]]:
    nb = json.loads(path.read_text(encoding="utf-8"))
    return [
        (i, "".join(c["source"]), "parameters" in c.get("metadata", {}).get("tags", []))
        for i, c in enumerate(nb["cells"])
        if c["cell_type"] == "code"
    ]


def read_notebook(path: Path) -> tuple[list[Finding], int]:
    r = Reader()
    found = r.read(cells_of(path))
    return found, r.n_checks


def unexplained(stem: str, found: list[Finding]) -> list[Finding]:
    return [f for f in found if not any(nb == stem and fnmatchcase(f.check, pat) for nb, pat in ALLOWED)]


# ---------------------------------------------------------------------------------------------- tests


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_every_check_value_is_computed(path):
    found, n = read_notebook(path)
    bad = unexplained(path.stem, found)
    assert not bad, f"{len(bad)} of {n} checks in {path.name} can't fail:\n" + "\n".join(map(str, bad))


def test_the_reading_sees_the_checks():
    """The reading must not pass by finding no check: it sees about as many as the notebooks write."""
    for path in NOTEBOOKS:
        _, n = read_notebook(path)
        written = sum(len(re.findall(r"\bcheck(?:_range|_outside)?\(", src)) for _, src, _ in cells_of(path))
        assert n >= written - 1, f"{path.name}: read {n} check calls of {written} written"


def test_allowed_entries_are_used_and_explained():
    assert len(ALLOWED) <= 3, "the allow-list is for rare, argued exceptions"
    for (stem, pattern), reason in ALLOWED.items():
        assert len(reason.split()) >= 5, f"{stem} {pattern}: say why"
        path = ROOT / "notebooks" / f"{stem}.ipynb"
        found, _ = read_notebook(path)
        assert any(fnmatchcase(f.check, pattern) for f in found), f"{stem} {pattern}: allowed but not flagged (remove it)"


def findings(*cells: str, parameters: int | None = None) -> list[Finding]:
    head = (
        "from navlib import repro, units, sensors, earth, attitude\n"
        "from navlib.repro import check, check_range, check_outside, check_study\n"
        "import numpy as np\nimport pandas as pd\n"
    )
    code = [(0, head, False)] + [(i + 1, src, i == parameters) for i, src in enumerate(cells)]
    return Reader().read(code)


BAD = {
    # the patterns the issue found, as they were written
    "own rounding": "err = earth.gravity(0.5)\ncheck('P000-TAB1-T1-ERROR', err, round(err, 2), 0.005, 'paper')",
    "own rounding, np": "err = earth.gravity(0.5)\ncheck('X', np.round(err, 2), err, 0.01, 'paper')",
    "rounding through a name": "err = earth.gravity(0.5)\nshown = float(f'{err:.2f}')\ncheck('X', err, shown, 0.01, 's')",
    "value is the target": "x = earth.gravity(0.5)\ncheck_range('X', x, 's', lower=x)",
    "paper value is ours": "x = earth.gravity(0.5)\ncheck('X', x, 9.8, 0.1, 's', paper_value=f'{x:.3f}')",
    "literal": "check('X', 0.5 * 0.1 * 9.80665 * 10 ** 2, 49.0, 0.05, 'src')",
    "literal through names": "b_up = 0.01 * 9.80665\ncheck('X', 0.5 * b_up * 100 ** 2, 490.0, 1.0, 'src')",
    "injected drift": "drift = DRIFT_DEG_S * (T_END - T_START)\ncheck('X-DRIFT', drift, -90.0, 2.0, 'src')",
    "injected drift, slope of the input": "t = np.arange(0, 1000, 0.1)\n"
    "check('X-DRIFT/slope', np.polyfit(t, DRIFT_DEG_S * t, 1)[0], 0.09, 0.01, 's')",
    "typed table value": "t1 = pd.read_csv('../data/p000_table1.csv')\ncheck('P000-TAB1', t1.loc[0, 'err'], 4.77, 0.01, 's')",
    "preset value": "model = sensors.imu_model('MTi-100')\n"
    "check('P001-TAB1-NOISE', units.to_deg_per_s(model.gyro.noise_density), 0.01, 1e-15, 's')",
    "paper constant": "import navlib.papers.gauss_kruger_ekf as gk\nV = pd.read_csv('../data/v.csv')\n"
    "Q = np.diag(V[['a', 'b']].to_numpy())\ncheck('QR/Q', np.abs(Q - gk.Q_PAPER).max(), 0, 0, 's')",
    "alias": "chk = repro.check\nchk('X', 1.0, 1.0, 0.0, 's')",
    "imported alias": "from navlib.repro import check_range as within\nwithin('X', 3.0, 's', upper=5.0)",
    "module alias": "import navlib.repro as rp\nrp.check_outside('X', 7.0, 's', upper=5.0)",
    "helper passing through": "def close(name, v, t):\n    return check(name, v, t, 0.1, 'src')\n"
    "close('X', DRIFT_DEG_S * 2, 0.18)",
    "helper, f-string name": "def row(k, v):\n    check(f'X/{k}', v, 1.0, 0.1, 's')\nfor k in range(3):\n    row(k, 1.0 + k)",
    "lambda": "f = lambda v: check('X', v, 1.0, 0.1, 's')\nf(DRIFT_DEG_S)",
    "loop over literals": "for k, v in enumerate([1.0, 2.0]):\n    check(f'X/{k}', v, 1.5, 1.0, 's')",
    "comprehension": "vals = [DRIFT_DEG_S * k for k in range(3)]\ncheck('X', max(vals), 0.18, 0.01, 's')",
    # on_printed=True declares arithmetic on the paper's printed numbers; it does not excuse the patterns above
    "printed, but computed": "check('X', earth.gravity(0.5), 9.78, 0.01, 's', on_printed=True)",
    "printed, but literals": "check('X', 0.5 * 0.01 * 9.80665 * 100 ** 2, 490.0, 1.0, 's', on_printed=True)",
    "printed, but parameters": "check('X', DRIFT_DEG_S * (T_END - T_START), 90.0, 1.0, 's', on_printed=True)",
    "printed, one typed number": "t1 = pd.read_csv('../data/p000_table1.csv')\n"
    "check('X', units.deg(t1.loc[0, 'err']), 0.08, 0.01, 's', on_printed=True)",
    "printed, one preset value": "m = sensors.imu_model('MTi-100')\n"
    "check('X', units.to_deg_per_h(m.gyro.bias_instability), 10.0, 1e-9, 's', on_printed=True)",
    "printed, value is the target": "tab = pd.read_csv('../data/t.csv')\n"
    "check('X', tab.dl.max(), tab.dl.max(), 0, 's', on_printed=True)",
    # checks that cannot fail whatever navlib computes (issue 35)
    "recovers its injected noise": "rng = np.random.default_rng(1)\ne = rng.normal(0, DRIFT_DEG_S, 1000)\n"
    "check('X', np.std(e), DRIFT_DEG_S, 0.01, 's')",
    "recovers it, truth removed": "rng = np.random.default_rng(1)\nm = sensors.simulate_magnetometer(q, B, "
    "sensors.MagnetometerModel(noise=units.gauss(DRIFT_DEG_S)), rng).m_b\n"
    "check('X', (m - attitude.quat_to_dcm(q) @ B).std(), units.gauss(DRIFT_DEG_S), 0.1, 's')",
    "band around an assumption": "v = earth.gravity(0.3)\ncheck_outside('X', v, 's', lower=T_START - 0.1, upper=T_START + 0.1)",
    "band holding every share": "e = earth.gravity(np.linspace(0, 1, 9))\n"
    "check_range('X', np.mean(e > 9.8), 's', lower=0, upper=1)",
    "study against its own input": "rng = np.random.default_rng(1)\ne = rng.normal(0, DRIFT_DEG_S, 1000)\n"
    "check_study('X', e.std(), DRIFT_DEG_S, 'nb', 's')",
}
PARAMS = "DRIFT_DEG_S = 0.09\nT_START, T_END = 1000.0, 2000.0\n"


@pytest.mark.parametrize("src", BAD.values(), ids=BAD.keys())
def test_the_bad_patterns_are_caught(src):
    found = findings(PARAMS, src, parameters=0)
    assert len(found) == 1, found


GOOD = {
    "navlib computation": "x = earth.gravity(0.5)\ncheck('X', x, 9.78, 0.01, 'paper')",
    "computed against an input": "g = earth.gravity(0.5)\ncheck('X', g * T_END, 9780.0, 10.0, 's')",
    "simulated": "rng = np.random.default_rng(1)\ne = rng.normal(0, DRIFT_DEG_S, 1000)\n"
    "check('X', np.mean(e), 0.0, 3 * DRIFT_DEG_S / np.sqrt(1000), 's')",
    "noise through an estimator": "from navlib import alignment\nrng = np.random.default_rng(1)\n"
    "e = rng.normal(0, DRIFT_DEG_S, (1000, 3))\n"
    "check('X', np.std(alignment.tilt_heading(e, e)), DRIFT_DEG_S, 0.01, 's')",
    "recording": "raw = pd.read_csv(repro.root() / 'data' / 'real' / 'walk.csv')\n"
    "check_range('X', raw.ax.mean(), 's', upper=1.0)",
    "helper with computed argument": "def close(name, v, t):\n    return check(name, v, t, 0.1, 'src')\n"
    "close('X', earth.gravity(0.1), 9.78)",
    "loop over computed": "errs = [earth.gravity(p) for p in (0.1, 0.2)]\nfor k, e in enumerate(errs):\n"
    "    check(f'X/{k}', e, 9.78, 0.01, 's')",
    "count of a computed mask": "e = earth.gravity(np.linspace(0, 1, 9))\ncheck('X', int((e > 10).sum()), 0, 0, 's')",
    "lambda of computed": "rms = lambda e: np.sqrt(np.mean(e ** 2))\nerr = earth.gravity(np.zeros(3)) - 9.78\n"
    "check_range('X', rms(err), 's', upper=0.1)",
    "third-party reference": "from scipy.spatial.transform import Rotation\n"
    "q = Rotation.from_euler('z', DRIFT_DEG_S).as_quat()\ncheck('X', q[3], 1.0, 0.01, 's')",
    "printed form computed": "x = earth.gravity(0.5)\ncheck('X', x, 9.8, 0.1, 's', paper_value=f'printed {x:.1f}')",
    "rebinding after a computation": "x = 1.0\nx = earth.gravity(x)\ncheck('X', x, 9.8, 0.1, 's')",
    "computed index": "grid = np.arange(0, 360, 10)\nworst = int(np.argmax(earth.gravity(np.radians(grid))))\n"
    "check_range('X', grid[worst] % 180, 's', lower=80, upper=100)",
    "printed columns": "t1 = pd.read_csv('../data/p000_table1.csv')\n"
    "check('X', np.abs(t1.single - t1.triad - t1.err).max(), 0.0, 0.015, 's', on_printed=True)",
    "printed text against its table": "tab = pd.read_csv('../data/t.csv')\nV = pd.read_csv('../data/v.csv')\n"
    "check('X', tab.dl.max(), V.loc['dl_max', 'value'], 0, 's', on_printed=True)",
    "published constants": "from navlib import atmosphere\n"
    "check('X', atmosphere.T0 / atmosphere.LAPSE, 44330.0, 1.0, 's', on_printed=True)",
}


@pytest.mark.parametrize("src", GOOD.values(), ids=GOOD.keys())
def test_computed_values_pass(src):
    assert not findings(PARAMS, src, parameters=0)


def test_a_parameter_is_an_input_only_in_the_parameters_cell():
    assert findings("K = 2.0", "check('X', K * 3, 6.0, 0.1, 's')", parameters=0)
    assert findings("K = 2.0", "check('X', K * 3, 6.0, 0.1, 's')", parameters=None)  # a literal all the same
    assert not findings("K = earth.gravity(0.1)", "check('X', K * 3, 29.3, 0.1, 's')", parameters=0)
