"""Reproduction helpers for the notebooks: paths, figure style, claim checks.

A notebook calls :func:`setup` once with its own name; afterwards

* :func:`savefig` writes deterministic PNGs to ``build/<notebook>/figures/``
  (no timestamps or version strings in the metadata, fixed DPI), and
* :func:`check` compares a reproduced value with its target, records the
  result in ``build/<notebook>/results.json`` and raises
  :class:`ClaimCheckFailed` when it is outside tolerance, so that a failed
  claim fails the notebook under nbmake.

Check names start with the claim id from ``data/claims.csv``
(e.g. ``P000-FIG4-TRIAD-RMSE/h091``); checks beyond the catalogue use names
that start with no id.
"""
from __future__ import annotations

import json
import math
import os
import platform
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ._typing import Scalar
from ._validate import flag, real, text

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["root", "build_dir", "setup", "savefig", "check", "check_range", "results",
           "ClaimCheckFailed", "Check", "NoOutputDirectory"]


class ClaimCheckFailed(AssertionError):
    """A reproduced value is outside the tolerance of its target."""


@dataclass
class Check:
    """One recorded claim check (a row of results.json)."""
    name: str
    value: float
    expected: float | None
    tol: float | None
    passed: bool
    source: str
    paper_value: str | None = None
    lower: float | None = None
    upper: float | None = None
    unit: str = ""
    note: str = ""


@dataclass
class _State:
    notebook: str | None = None
    out_dir: Path | None = None
    checks: list[Check] = field(default_factory=list)


_state = _State()


class NoOutputDirectory(RuntimeError):
    """navlib.repro runs outside a checkout and was given no output directory."""


def root() -> Path:
    """The project root that holds ``build/`` and ``data/``.

    ``NAVLIB_ROOT`` when set; otherwise the nearest parent of the working
    directory holding ``pyproject.toml`` and ``navlib/`` (notebooks run from
    ``notebooks/``). Outside a checkout there is no such directory, and
    :class:`NoOutputDirectory` is raised rather than writing beside the
    installed package: set ``NAVLIB_ROOT`` or pass ``out_dir`` to :func:`setup`.
    """
    env = os.environ.get("NAVLIB_ROOT")
    if env:
        return Path(env).resolve()
    here = Path.cwd().resolve()
    for p in (here, *here.parents):
        if (p / "pyproject.toml").is_file() and (p / "navlib").is_dir():
            return p
    raise NoOutputDirectory(
        f"navlib.repro: {here} is not inside a navlib checkout, so there is no build/ to write to; "
        "set the NAVLIB_ROOT environment variable or call repro.setup(notebook, out_dir=...)")


def build_dir(notebook: str | None = None) -> Path:
    """The output directory (``<root>/build`` or ``setup``'s ``out_dir``), or its ``<notebook>/`` folder; created."""
    if notebook is not None and not isinstance(notebook, str):
        raise ValueError(f"notebook: expected a notebook name (str), got {type(notebook).__name__}")
    if notebook and ("/" in notebook or "\\" in notebook or notebook in (".", "..")):
        raise ValueError(f"notebook: expected a plain notebook name, got {notebook!r}")
    d = _state.out_dir if _state.out_dir is not None else root() / "build"
    if notebook:
        d = d / notebook
    d.mkdir(parents=True, exist_ok=True)
    return d


def setup(notebook: str, *, out_dir: str | os.PathLike | None = None, style: bool = True) -> None:
    """Start a notebook's run: reset its results file and set the figure style.

    Parameters
    ----------
    notebook : str
        The notebook's stem, e.g. ``"00_conventions_sensors"``. Outputs go to
        ``<out_dir>/<notebook>/``.
    out_dir : path, optional
        Where outputs go. Default: ``build/`` of the checkout (see :func:`root`);
        required when navlib runs outside a checkout.
    """
    import matplotlib
    import matplotlib.pyplot as plt

    if not isinstance(notebook, str) or not notebook or "/" in notebook:
        raise ValueError(f"notebook: expected a plain notebook name, got {notebook!r}")
    if out_dir is not None and not isinstance(out_dir, (str, os.PathLike)):
        raise ValueError(f"out_dir: expected a directory path, got {type(out_dir).__name__}")
    _state.notebook = notebook
    _state.out_dir = None if out_dir is None else Path(out_dir).resolve()
    _state.checks = []
    d = build_dir(notebook)
    (d / "results.json").unlink(missing_ok=True)
    if flag(style, "style"):
        plt.rcdefaults()
        matplotlib.rcParams.update({
            "figure.figsize": (7.0, 4.0), "figure.dpi": 100, "savefig.dpi": 110,
            "axes.grid": True, "grid.alpha": 0.3, "axes.spines.top": False,
            "axes.spines.right": False, "legend.frameon": False, "font.size": 10,
            "svg.hashsalt": "navlib", "image.cmap": "viridis",
        })
    _write()


def versions() -> dict[str, str]:
    """Versions of Python and the numerical stack, for the notebook header."""
    import matplotlib
    import numba
    import scipy

    import navlib
    return {"python": platform.python_version(), "numpy": np.__version__, "scipy": scipy.__version__,
            "matplotlib": matplotlib.__version__, "numba": numba.__version__, "navlib": navlib.__version__}


def savefig(fig: Figure, name: str) -> Path:
    """Save ``fig`` as ``build/<notebook>/figures/<name>.png`` deterministically.

    The PNG carries no timestamp or software version, so two runs give
    byte-identical files.
    """
    if _state.notebook is None:
        raise RuntimeError("call navlib.repro.setup(notebook) before savefig()")
    if not hasattr(fig, "savefig"):
        raise ValueError(f"fig: expected a matplotlib Figure, got {type(fig).__name__}")
    if not isinstance(name, str) or not name or "/" in name or "\\" in name:
        raise ValueError(f"name: expected a plain file name without directories, got {name!r}")
    d = build_dir(_state.notebook) / "figures"
    d.mkdir(exist_ok=True)
    path = d / f"{name}.png"
    fig.savefig(path, metadata={"Software": None}, bbox_inches="tight")
    return path


def _as_float(x, name: str, finite: bool = False) -> float:
    x = real(x, name)  # strings (also "1.5"), complex, object and bool raise InputTypeError
    if x.size != 1:
        raise ValueError(f"{name}: expected a scalar, got shape {x.shape}")
    v = float(x.reshape(()))
    if finite and not math.isfinite(v):
        raise ValueError(f"{name}: expected a finite number, got {v}")
    return v


def _check_name(name) -> None:
    if not isinstance(name, str) or not name.strip():
        raise ValueError(f"name: expected a non-empty check name (str), got {name!r}")


def _texts(**kw: str) -> None:
    for name, value in kw.items():
        text(value, name)


def _record(c: Check) -> Check:
    _state.checks = [k for k in _state.checks if k.name != c.name] + [c]
    _write()
    status = "PASS" if c.passed else "FAIL"
    if c.expected is not None:
        target = f"target {c.expected:.6g} ± {c.tol:.3g}"
    else:
        target = f"range [{c.lower if c.lower is not None else '-inf'}, {c.upper if c.upper is not None else 'inf'}]"
    print(f"[{status}] {c.name}: {c.value:.6g}{' ' + c.unit if c.unit else ''} ({target}; {c.source})")
    if not c.passed:
        raise ClaimCheckFailed(f"{c.name}: reproduced {c.value:.6g} is outside {target}")
    return c


def check(name: str, value: Scalar, expected: float, tol: float, source: str, *, paper_value: str | float | None = None,
          rel: bool = False, unit: str = "", note: str = "") -> Check:
    """Check ``|value - expected| <= tol`` and record it; raise if it fails.

    Parameters
    ----------
    name : str
        Starts with the claim id from ``data/claims.csv`` when it checks a claim.
    value : float
        Reproduced value, computed by navlib in the notebook.
    expected : float
        Target: the paper's value or, where the paper is wrong, the corrected
        value (then give the printed one as ``paper_value``).
    tol : float
        Tolerance, absolute; relative to ``|expected|`` with ``rel=True``.
    source : str
        Where the target comes from: the paper item (figure, table, equation), a
        published reference, or a project file such as an erratum of ``data/errata.csv``.
    paper_value : str or float, optional
        The printed value when it differs from ``expected``.
    """
    _check_name(name)
    _texts(source=source, unit=unit, note=note)
    v = _as_float(value, "value")
    e = _as_float(expected, "expected", finite=True)
    t = _as_float(tol, "tol", finite=True)
    if t < 0:
        raise ValueError(f"tol: expected a non-negative tolerance, got {t}")
    abs_tol = t * abs(e) if flag(rel, "rel") else t
    passed = bool(math.isfinite(v) and abs(v - e) <= abs_tol)
    return _record(Check(name, v, e, abs_tol, passed, source,
                         None if paper_value is None else str(paper_value), unit=unit, note=note))


def check_range(name: str, value: Scalar, source: str, *, lower: float | None = None, upper: float | None = None,
                paper_value: str | float | None = None, unit: str = "", note: str = "") -> Check:
    """Check ``lower <= value <= upper`` (either bound may be omitted); record; raise on failure.

    For directional and bound claims, e.g. "the EKF error is smaller than
    dead reckoning's" as ``check_range(name, rmse_ekf / rmse_dr, upper=1)``.
    """
    if lower is None and upper is None:
        raise ValueError("lower, upper: give at least one bound")
    _check_name(name)
    _texts(source=source, unit=unit, note=note)
    v = _as_float(value, "value")
    lo = None if lower is None else _as_float(lower, "lower")
    hi = None if upper is None else _as_float(upper, "upper")
    for bound, b in (("lower", lo), ("upper", hi)):
        if b is not None and math.isnan(b):
            raise ValueError(f"{bound}: expected a number (infinite for no bound), got {b}")
    if lo is not None and hi is not None and lo > hi:
        raise ValueError(f"lower: expected lower <= upper, got {lo} > {hi}")
    passed = bool(math.isfinite(v) and (lo is None or v >= lo) and (hi is None or v <= hi))
    return _record(Check(name, v, None, None, passed, source,
                         None if paper_value is None else str(paper_value), lo, hi, unit, note))


def results() -> list[Check]:
    """Checks recorded so far in this notebook run."""
    return list(_state.checks)


def _write() -> None:
    if _state.notebook is None:
        return
    data = {"notebook": _state.notebook, "checks": [asdict(c) for c in _state.checks]}
    path = build_dir(_state.notebook) / "results.json"
    path.write_text(json.dumps(data, indent=1, allow_nan=True) + "\n")
