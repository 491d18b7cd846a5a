"""Reproduction helpers for the notebooks: paths, figure style, claim checks.

A notebook calls :func:`setup` once with its own name; afterwards

* :func:`savefig` writes deterministic PNGs to ``build/<notebook>/figures/``
  (no timestamps or version strings in the metadata, fixed DPI), and
* :func:`check` compares a reproduced value with its target, records the
  result in ``build/<notebook>/results.json`` and raises
  :class:`ClaimCheckFailed` when it is outside tolerance, so that a failed
  check fails the notebook under nbmake; :func:`check_range` does the same for
  a bound, :func:`check_outside` asserts a disagreement (the value lies
  outside an interval); :func:`check_study` takes its tolerance from a
  recorded seed study (``data/seed_studies/``);
* :func:`verdict` records the one verdict of a claim (:data:`VERDICTS`), resting
  on the checks recorded before it; with ``real_data=True`` a second verdict of the same claim whose
  evidence is a committed real recording (any paper's claim, from any notebook: the recording's);
* :func:`summary` returns the checks and verdicts recorded since the previous
  summary as one compact table (checks record silently; a section of a
  notebook ends with its table).

Two switches, set in a notebook's parameters cell through :func:`env_flag` and
applied by :func:`mode`: *teaching* turns a failed check into a visible
:class:`ClaimCheckWarning` instead of an exception, so that a student can change
any parameter and still run to the end; *fast* is read by the notebook to pick its
smaller parameter set. Results written in either mode carry a ``mode`` entry, and
the ledger (``tools/reproduce.py``) refuses them.

*Checks* and *claims* are different things: a claim is a row of
``data/claims.csv`` (a statement of the paper); a check is one computed
comparison. Check names start with the claim id they support
(e.g. ``P000-FIG4-TRIAD-RMSE/h091``); checks beyond the catalogue use names
that start with no id. ``docs/claims.md`` gives the rules for verdicts.
"""

from __future__ import annotations

import csv
import functools
import json
import math
import os
import platform
import re
import warnings
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path
from statistics import NormalDist
from typing import TYPE_CHECKING, Any

import numpy as np

from ._typing import Scalar
from ._validate import Flag, Is, NonNegative, Text, boundary, choice, flag, real, scalar, text

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = [
    "root",
    "build_dir",
    "setup",
    "savefig",
    "check",
    "check_range",
    "check_outside",
    "check_study",
    "seed_spread",
    "SeedSpread",
    "SWEEP_ALPHA",
    "SWEEP_SEEDS_BUDGET",
    "SEED_DEPENDENT_CHECKS",
    "CHECK_ALPHA",
    "Z",
    "study_k",
    "EXTENSION",
    "NOT_CHECKABLE",
    "verdict",
    "results",
    "verdicts",
    "summary",
    "env_flag",
    "mode",
    "caption",
    "answer",
    "exercise",
    "Exercise",
    "explorer",
    "VERDICTS",
    "ClaimCheckFailed",
    "ClaimCheckWarning",
    "Check",
    "Verdict",
    "NoOutputDirectory",
]

VERDICTS = (
    "reproduced",
    "reproduced with correction",
    "differs",
    "refuted",
    "direction only",
    "undecided at this scale",
    "not checkable here",
    "extension",
)
"""The verdicts a claim can get (``docs/claims.md``), in the ledger's order. The last, *extension*, is the only one
of a catalogue row of kind ``extension`` (the project's own quantity, test vector or reconstruction: no paper
statement to judge) and only it gets it; *undecided at this scale* is a paper claim whose test straddles its cut
within the seed-to-seed spread (both numbers shown), never a coin toss."""
EXTENSION = "extension"
NOT_CHECKABLE = {
    "hardware-only": "hardware only",
    "datasheet": "datasheet",
    "data-not-available": "data not available",
    "paper-too-vague": "paper too vague",
    "not-a-result": "not a result",
}
"""Why a claim is *not checkable here*: its catalogue kind (``data/claims.csv``) as the ledger shows it. A claim of one
of these kinds gets that verdict and only such a claim does (its ``reason`` gives the sentence why): measured on the
authors' hardware or derived from their measured table; a manufacturer's specification (an input of a simulation, never
its result); the paper leaves out, or the source has lost, what a check would need; the paper does not pin the
statement down enough to simulate it; a design choice, setting or unit conversion of the paper, not a finding."""
SWEEP_ALPHA = 0.02
"""The family-wise budget: the chance, at most, that a correct ledger shows any check failure on a sweep of
:data:`SWEEP_SEEDS_BUDGET` fresh seeds (``tools/reproduce.py --seeds``)."""
SWEEP_SEEDS_BUDGET = 10
"""The seeds of the sweep the budget is set for (a reviewer's 5-10)."""
SEED_DEPENDENT_CHECKS = 300
"""An upper bound of the checks whose value changes with the seed (248 on the sweep of seeds 7001-7012:
``data/seed_studies/README.md``); a sweep of :data:`SWEEP_SEEDS_BUDGET` seeds makes 10 x 300 such comparisons."""
CHECK_ALPHA = 1.0 - (1.0 - SWEEP_ALPHA) ** (1.0 / (SWEEP_SEEDS_BUDGET * SEED_DEPENDENT_CHECKS))
"""The level of one seed-dependent check (Šidák): 1 - (1 - 0.02)^(1/3000) = 6.7e-6, two-sided."""
Z = NormalDist().inv_cdf(1.0 - CHECK_ALPHA / 2)
"""The multiplier of a standard-error band (4.50): a correct Gaussian statistic leaves ``expected ± Z se`` with
probability :data:`CHECK_ALPHA`. Notebooks write every seed-dependent standard-error band as ``Z * se``."""


def study_k(n: int, *, about_mean: bool = False) -> float:
    """The multiplier of a seed-study band from ``n`` calibration seeds, at the level :data:`CHECK_ALPHA`.

    A prediction interval of one new seed: about a target, ``|value - target| <= t_n RMS`` (the RMS of ``n`` centred
    Gaussian values has ``n`` degrees of freedom); about the study's mean, ``|value - mean| <= t_{n-1} sqrt(1 + 1/n)
    sd``. With 12 seeds that is 7.5 and 8.3 (Z = 4.50 once the spread is known); with 24, 5.7 and 5.9. ``study_k(m)`` is
    also the t quantile of m degrees of freedom for a standard error estimated from m + 1 values.

    Examples
    --------
    >>> from navlib import repro
    >>> round(repro.study_k(12), 2), round(repro.study_k(12, about_mean=True), 2), round(repro.study_k(24), 2)
    (7.55, 8.3, 5.72)
    """
    from scipy import stats  # noqa: PLC0415 -- scipy loads only where a study is read

    n, about_mean = int(scalar(n, "n")), flag(about_mean, "about_mean")
    if n < 1 + about_mean:
        raise ValueError(
            f"n: a spread {'about its own mean ' if about_mean else ''}needs at least {1 + about_mean} values, got {n}"
        )
    dof = n - 1 if about_mean else n
    return float(stats.t.isf(CHECK_ALPHA / 2, dof)) * (math.sqrt(1.0 + 1.0 / n) if about_mean else 1.0)


_NEEDS_EVIDENCE = ("reproduced with correction", "differs", "refuted")


class ClaimCheckFailed(AssertionError):
    """A reproduced value is outside the tolerance of its target.

    Examples
    --------
    >>> import tempfile
    >>> from navlib import repro
    >>> tmp = tempfile.TemporaryDirectory()
    >>> repro.setup("demo", out_dir=tmp.name, style=False)
    >>> try:
    ...     repro.check("demo/too-far", 1.2, 1.0, 0.05, "a worked example")
    ... except repro.ClaimCheckFailed as e:
    ...     print(type(e).__name__, issubclass(repro.ClaimCheckFailed, AssertionError))
    ...
    ClaimCheckFailed True
    >>> tmp.cleanup()
    """


class ClaimCheckWarning(UserWarning):
    """Teaching mode: a check failed (or a verdict could not be recorded); the notebook goes on.

    Examples
    --------
    >>> import tempfile
    >>> from navlib import repro
    >>> import warnings
    >>> tmp = tempfile.TemporaryDirectory()
    >>> repro.setup("demo", out_dir=tmp.name, style=False)
    >>> repro.mode(teaching=True, fast=False)                         # a failed check warns instead of raising
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     ok = repro.check("demo/too-far", 1.2, 1.0, 0.05, "a worked example").passed
    ...
    >>> ok, caught[0].category.__name__
    (False, 'ClaimCheckWarning')
    >>> repro.mode(teaching=False, fast=False)
    >>> tmp.cleanup()
    """


@dataclass
class Check:
    """One recorded claim check (a row of results.json).

    Examples
    --------
    >>> import tempfile
    >>> from navlib import repro
    >>> tmp = tempfile.TemporaryDirectory()
    >>> repro.setup("demo", paper="000", out_dir=tmp.name, style=False)
    >>> c = repro.check("P000-EQ3-EULER/demo", 1.02, 1.0, 0.05, "a worked example")
    >>> c.passed, c.value, c.expected, c.tol
    (True, 1.02, 1.0, 0.05)
    >>> tmp.cleanup()
    """

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
    outside: bool = False  # check_outside: passes when the value lies outside [lower, upper]
    on_printed: bool = False  # the value is arithmetic on the paper's printed numbers, not a reproduction
    study: dict[str, Any] | None = None  # check_study: {"name": study, "target": target or None}


@dataclass
class Verdict:
    """The verdict on one claim of ``data/claims.csv`` (an entry of results.json's ``verdicts``).

    Examples
    --------
    >>> import tempfile
    >>> from navlib import repro
    >>> tmp = tempfile.TemporaryDirectory()
    >>> repro.setup("demo", paper="000", out_dir=tmp.name, style=False)
    >>> _ = repro.check("P000-EQ3-EULER/demo", 1.0, 1.0, 0.1, "a worked example")
    >>> v = repro.verdict("P000-EQ3-EULER", "reproduced", checks=["P000-EQ3-EULER/demo"])
    >>> v.claim, v.verdict, v.checks
    ('P000-EQ3-EULER', 'reproduced', ['P000-EQ3-EULER/demo'])
    >>> tmp.cleanup()
    """

    claim: str
    verdict: str
    checks: list[str]
    evidence: list[str]
    paper: str | None = None
    ours: str | None = None
    reason: str = ""
    erratum: str = ""
    figure: str = ""
    real_data: bool = False  # the evidence is a committed real recording, not the paper's simulated setting


@dataclass
class _State:
    notebook: str | None = None
    out_dir: Path | None = None
    paper: str | None = None
    checks: list[Check] = field(default_factory=list)
    verdicts: list[Verdict] = field(default_factory=list)
    figures: set[str] = field(default_factory=set)
    catalogue: dict[str, Any] | None = None
    teaching: bool = False
    fast: bool = False
    shown_checks: int = 0  # checks and verdicts already shown by summary()
    shown_verdicts: int = 0
    encoded: dict[tuple[str, str], str] = field(default_factory=dict)  # results.json rows, by check / claim


_state = _State()


class NoOutputDirectory(RuntimeError):
    """navlib.repro runs outside a checkout and was given no output directory.

    Examples
    --------
    >>> from navlib import repro
    >>> issubclass(repro.NoOutputDirectory, Exception)
    True
    >>> import os
    >>> os.environ.get("NAVLIB_ROOT") is None and repro.root().is_dir()   # in a checkout: no exception
    True
    """


def root() -> Path:
    """The project root that holds ``build/`` and ``data/``.

    ``NAVLIB_ROOT`` when set; otherwise the nearest parent of the working
    directory holding ``pyproject.toml`` and ``navlib/`` (notebooks run from
    ``notebooks/``). Outside a checkout there is no such directory, and
    :class:`NoOutputDirectory` is raised rather than writing beside the
    installed package: set ``NAVLIB_ROOT`` or pass ``out_dir`` to :func:`setup`.

    Examples
    --------
    >>> from navlib import repro
    >>> (repro.root() / "pyproject.toml").is_file()
    True
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
        "set the NAVLIB_ROOT environment variable or call repro.setup(notebook, out_dir=...)"
    )


@boundary
def build_dir(notebook: Text | None = None) -> Path:
    """The output directory, or its ``<notebook>/`` folder; created.

    ``setup``'s ``out_dir`` when given, else the ``NAVLIB_BUILD_DIR`` environment variable when set,
    else ``<root>/build``.

    Examples
    --------
    >>> import tempfile
    >>> from navlib import repro
    >>> tmp = tempfile.TemporaryDirectory()
    >>> repro.setup("demo", out_dir=tmp.name, style=False)
    >>> repro.build_dir("demo").name, repro.build_dir("demo").is_dir()
    ('demo', True)
    >>> tmp.cleanup()
    """
    if notebook and ("/" in notebook or "\\" in notebook or notebook in (".", "..")):
        raise ValueError(f"notebook: expected a plain notebook name, got {notebook!r}")
    return _build_dir(notebook)


def _build_dir(notebook: str | None) -> Path:
    """:func:`build_dir` of a checked notebook name (the one :func:`setup` recorded)."""
    env = os.environ.get("NAVLIB_BUILD_DIR")
    d = _state.out_dir if _state.out_dir is not None else Path(env).resolve() if env else root() / "build"
    if notebook:
        d = d / notebook
    d.mkdir(parents=True, exist_ok=True)
    return d


def setup(notebook: str, *, paper: str | None = None, out_dir: str | os.PathLike[str] | None = None, style: bool = True) -> None:
    """Start a notebook's run: reset its results file and set the figure style.

    Parameters
    ----------
    notebook : str
        The notebook's stem, e.g. ``"00_conventions_sensors"``. Outputs go to
        ``<out_dir>/<notebook>/``.
    paper : str, optional
        The paper the notebook reproduces, as its ``claims_id`` in the registry
        (``navlib/papers/__init__.py``), e.g. ``"000"``; :func:`verdict` accepts only
        this paper's claims. Omitted for a notebook that reproduces no paper.
    out_dir : path, optional
        Where outputs go. Default: ``build/`` of the checkout (see :func:`root`);
        required when navlib runs outside a checkout.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from navlib import repro
    >>> tmp = tempfile.TemporaryDirectory()
    >>> repro.setup("demo", paper="000", out_dir=tmp.name, style=False)   # outputs to <tmp>/demo/
    >>> repro.results(), (Path(tmp.name) / "demo").is_dir()
    ([], True)
    >>> tmp.cleanup()
    """
    try:
        import matplotlib
        import matplotlib.pyplot as plt
    except ModuleNotFoundError as e:  # matplotlib is the optional `plots` extra
        raise ModuleNotFoundError(f"navlib.repro draws with matplotlib ({e}): pip install 'navlib-repro[plots]'") from e

    if not isinstance(notebook, str) or not notebook or "/" in notebook:  # type: ignore[redundant-expr]  # the caller's argument, checked
        raise ValueError(f"notebook: expected a plain notebook name, got {notebook!r}")
    if out_dir is not None and not isinstance(out_dir, (str, os.PathLike)):
        raise ValueError(f"out_dir: expected a directory path, got {type(out_dir).__name__}")
    if paper is not None and not (isinstance(paper, str) and re.fullmatch(r"\d{3}", paper)):  # type: ignore[redundant-expr]  # the caller's argument, checked
        raise ValueError(f"paper: expected a paper's claims id of three digits such as '000', got {paper!r}")
    _state.notebook = notebook
    _state.out_dir = None if out_dir is None else Path(out_dir).resolve()
    _state.paper = paper
    _state.checks = []
    _state.verdicts = []
    _state.encoded = {}
    _state.figures = set()
    _state.catalogue = None
    _state.teaching = _state.fast = False
    _state.shown_checks = _state.shown_verdicts = 0
    d = _build_dir(notebook)
    (d / "results.json").unlink(missing_ok=True)
    if flag(style, "style"):
        plt.rcdefaults()
        matplotlib.rcParams.update(
            {
                "figure.figsize": (7.0, 4.0),
                "figure.dpi": 100,
                "savefig.dpi": 110,
                "axes.grid": True,
                "grid.alpha": 0.3,
                "axes.spines.top": False,
                "axes.spines.right": False,
                "legend.frameon": False,
                "font.size": 10,
                "svg.hashsalt": "navlib",
                "image.cmap": "viridis",
            }
        )
    _write()


def versions() -> dict[str, str]:
    """Versions of Python and the numerical stack, for the notebook header."""
    import matplotlib
    import numba
    import scipy

    import navlib

    return {
        "python": platform.python_version(),
        "numpy": np.__version__,
        "scipy": scipy.__version__,
        "matplotlib": matplotlib.__version__,
        "numba": numba.__version__,
        "navlib": navlib.__version__,
    }


def savefig(fig: Figure, name: str) -> Path:
    """Save ``fig`` as ``build/<notebook>/figures/<name>.png`` deterministically.

    The PNG carries no timestamp or software version, so two runs give
    byte-identical files. Under Jupyter's inline backend the cell shows this
    PNG and the figure is closed: it is rendered once, not a second time by
    the backend at the end of the cell. Other backends leave the figure open for ``plt.show()``.

    Examples
    --------
    >>> import tempfile
    >>> import matplotlib.pyplot as plt
    >>> from navlib import repro
    >>> tmp = tempfile.TemporaryDirectory()
    >>> repro.setup("demo", out_dir=tmp.name, style=False)
    >>> fig, ax = plt.subplots()
    >>> _ = ax.plot([0.0, 1.0], [0.0, 1.0])
    >>> path = repro.savefig(fig, "line")
    >>> path.relative_to(tmp.name).as_posix()
    'demo/figures/line.png'
    >>> tmp.cleanup()
    """
    import matplotlib
    import matplotlib.pyplot as plt

    if _state.notebook is None:
        raise RuntimeError("call navlib.repro.setup(notebook) before savefig()")
    if not hasattr(fig, "savefig"):
        raise ValueError(f"fig: expected a matplotlib Figure, got {type(fig).__name__}")
    if not isinstance(name, str) or not name or "/" in name or "\\" in name:  # type: ignore[redundant-expr]  # the caller's argument, checked
        raise ValueError(f"name: expected a plain file name without directories, got {name!r}")
    path = _write_png(fig, name)
    if matplotlib.get_backend() == _INLINE:
        from IPython.display import Image, display  # noqa: PLC0415 -- only notebooks need IPython

        display(Image(data=path.read_bytes(), format="png"))
        plt.close(fig)
    return path


_INLINE = "module://matplotlib_inline.backend_inline"
# No timestamp, no software version.
_PNG: dict[str, Any] = {"format": "png", "metadata": {"Software": None}, "bbox_inches": "tight"}


def _write_png(fig: Figure, name: str) -> Path:
    """Write ``build/<notebook>/figures/<name>.png`` and return its path."""
    d = _build_dir(_state.notebook) / "figures"
    d.mkdir(exist_ok=True)
    path = d / f"{name}.png"
    fig.savefig(path, **_PNG)
    _state.figures.add(name)
    return path


def _png(fig: Figure) -> Any:
    """``fig`` as an IPython PNG image (as :func:`savefig` writes it), the figure closed."""
    import io

    import matplotlib.pyplot as plt
    from IPython.display import Image  # noqa: PLC0415 -- only notebooks need IPython

    buffer = io.BytesIO()
    fig.savefig(buffer, **_PNG)
    plt.close(fig)
    return Image(data=buffer.getvalue(), format="png")


def _as_float(x: object, name: str, finite: bool = False) -> float:
    x = real(x, name)  # strings (also "1.5"), complex, object and bool raise InputTypeError
    if x.size != 1:
        raise ValueError(f"{name}: expected a scalar, got shape {x.shape}")
    v = float(x.reshape(()))
    if finite and not math.isfinite(v):
        raise ValueError(f"{name}: expected a finite number, got {v}")
    return v


def _check_args(name: str, value: Scalar, source: str, unit: str, note: str, on_printed: bool) -> tuple[float, bool]:
    """The arguments every check takes, checked: returns the value as a float and ``on_printed``."""
    text(name, "name", empty=False)
    _texts(source=source, unit=unit, note=note)
    return _as_float(value, "value"), flag(on_printed, "on_printed")


def _texts(**kw: str) -> None:
    for name, value in kw.items():
        text(value, name)


def _target(c: Check) -> str:
    """What a check compares with, as text: ``± tol`` of a target, a range, or outside a range."""
    if c.expected is not None:
        return f"target {c.expected:.6g} ± {c.tol:.3g}"
    lo = "-inf" if c.lower is None else f"{c.lower:.6g}"
    hi = "inf" if c.upper is None else f"{c.upper:.6g}"
    return ("outside " if c.outside else "") + f"range [{lo}, {hi}]"


def _ours(c: Check) -> str:
    """A check's value with the digits its target's tolerance resolves (at least 4 significant), so that a value
    within a tight tolerance never looks like a mismatch (196.25 against target 196.25 +- 1e-9, not 196.2)."""
    digits = 4
    if c.expected is not None and c.tol and np.isfinite(c.tol) and np.isfinite(c.value):
        scale = max(abs(c.value), abs(c.expected))
        digits = int(np.clip(np.ceil(np.log10(scale / c.tol)) + 1, 4, 12)) if scale > c.tol else 4
    return f"{c.value:.{digits}g}{' ' + c.unit if c.unit else ''}"


def _record(c: Check) -> Check:
    """Record a check silently (:func:`summary` shows it); a failure raises, or warns in teaching mode."""
    _state.checks = [k for k in _state.checks if k.name != c.name] + [c]
    _state.encoded["check", c.name] = _encode(_row(c))
    _write()
    if not c.passed:
        message = f"{c.name}: reproduced {c.value:.6g} is {'not ' if c.outside else 'outside '}{_target(c)} ({c.source})"
        if not _state.teaching:
            raise ClaimCheckFailed(message)
        warnings.warn("check failed (teaching mode, the notebook goes on): " + message, ClaimCheckWarning, stacklevel=3)
    return c


def check(
    name: str,
    value: Scalar,
    expected: float,
    tol: float,
    source: str,
    *,
    paper_value: str | float | None = None,
    rel: bool = False,
    unit: str = "",
    note: str = "",
    on_printed: bool = False,
) -> Check:
    """Check ``|value - expected| <= tol`` and record it; raise if it fails.

    Parameters
    ----------
    name : str
        Starts with the claim id from ``data/claims.csv`` when it checks a claim.
    value : float
        Reproduced value, computed by navlib in the notebook from simulated or committed data: never the
        target itself, a rounding of it, a literal or an input (``tests/test_check_values.py`` reads every
        notebook for these; a value that is the very object passed as ``expected`` is refused here).
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
    on_printed : bool
        The value is arithmetic on the paper's own printed numbers (typed in ``data/``), e.g. a
        table column against the total its text prints: legitimate, but a consistency check of the
        paper rather than a reproduction. Recorded in results.json.

    Examples
    --------
    >>> import tempfile
    >>> from navlib import repro
    >>> tmp = tempfile.TemporaryDirectory()
    >>> repro.setup("demo", paper="000", out_dir=tmp.name, style=False)
    >>> repro.check("P000-EQ3-EULER/demo", 1.02, 1.0, 0.05, "a worked example").passed
    True
    >>> repro.check("P000-EQ3-EULER/too-far", 1.2, 1.0, 0.05, "a worked example")
    Traceback (most recent call last):
        ...
    navlib.repro.ClaimCheckFailed: P000-EQ3-EULER/too-far: reproduced 1.2 is outside target 1 ± 0.05 (a ...
    >>> tmp.cleanup()
    """
    v, printed = _check_args(name, value, source, unit, note, on_printed)
    e = _as_float(expected, "expected", finite=True)
    t = _as_float(tol, "tol", finite=True)
    if t < 0:
        raise ValueError(f"tol: expected a non-negative tolerance, got {t}")
    abs_tol = t * abs(e) if flag(rel, "rel") else t
    _not_the_target(value, expected=expected, paper_value=paper_value)
    passed = bool(math.isfinite(v) and abs(v - e) <= abs_tol)
    return _record(
        Check(
            name,
            v,
            e,
            abs_tol,
            passed,
            source,
            None if paper_value is None else str(paper_value),
            unit=unit,
            note=note,
            on_printed=printed,
        )
    )


def check_range(
    name: str,
    value: Scalar,
    source: str,
    *,
    lower: float | None = None,
    upper: float | None = None,
    paper_value: str | float | None = None,
    unit: str = "",
    note: str = "",
    on_printed: bool = False,
) -> Check:
    """Check ``lower <= value <= upper`` (either bound may be omitted); record; raise on failure.

    For directional and bound claims, e.g. "the EKF error is smaller than
    dead reckoning's" as ``check_range(name, rmse_ekf / rmse_dr, upper=1)``. ``value`` and
    ``on_printed`` as for :func:`check`.

    Examples
    --------
    >>> import tempfile
    >>> from navlib import repro
    >>> tmp = tempfile.TemporaryDirectory()
    >>> repro.setup("demo", out_dir=tmp.name, style=False)
    >>> repro.check_range("demo/ratio", 0.4, "a worked example", upper=1.0).passed   # e.g. EKF error / dead-reckoning error
    True
    >>> tmp.cleanup()
    """
    return _interval_check(name, value, source, (lower, upper), paper_value, unit, note, on_printed, outside=False)


def check_outside(
    name: str,
    value: Scalar,
    source: str,
    *,
    lower: float | None = None,
    upper: float | None = None,
    paper_value: str | float | None = None,
    unit: str = "",
    note: str = "",
    on_printed: bool = False,
) -> Check:
    """Check that ``value`` lies *outside* ``[lower, upper]``; record; raise if it lies inside.

    The assertion of a disagreement, which a :func:`verdict` of ``"differs"`` or
    ``"refuted"`` (or the printed form of a ``"reproduced with correction"``)
    rests on: e.g. "our 0.34° lies outside the paper's 4.77° ± 3 × our spread" as
    ``check_outside(name, ours, src, lower=4.77 - 3 * s, upper=4.77 + 3 * s)``.
    ``value`` is computed by navlib; the interval holds the paper's value with its
    stated or derived spread. A non-finite value fails. ``on_printed`` as for :func:`check`.

    Examples
    --------
    >>> import tempfile
    >>> from navlib import repro
    >>> tmp = tempfile.TemporaryDirectory()
    >>> repro.setup("demo", out_dir=tmp.name, style=False)
    >>> repro.check_outside("demo/differs", 5.0, "a worked example", lower=0.0, upper=1.0).passed   # 5 is outside [0, 1]
    True
    >>> tmp.cleanup()
    """
    return _interval_check(name, value, source, (lower, upper), paper_value, unit, note, on_printed, outside=True)


def _interval_check(
    name: str,
    value: Scalar,
    source: str,
    bounds: tuple[float | None, float | None],
    paper_value: str | float | None,
    unit: str,
    note: str,
    on_printed: bool,
    *,
    outside: bool,
) -> Check:
    """:func:`check_range` (``value`` within ``bounds``) or :func:`check_outside` (``value`` outside them)."""
    v, printed = _check_args(name, value, source, unit, note, on_printed)
    lo, hi = _bounds(*bounds)
    _not_the_target(value, lower=bounds[0], upper=bounds[1], paper_value=paper_value)
    inside = (lo is None or v >= lo) and (hi is None or v <= hi)
    passed = bool(math.isfinite(v) and inside != outside)
    return _record(
        Check(
            name,
            v,
            None,
            None,
            passed,
            source,
            None if paper_value is None else str(paper_value),
            lo,
            hi,
            unit,
            note,
            outside=outside,
            on_printed=printed,
        )
    )


@dataclass(frozen=True)
class SeedSpread:
    """One check's spread over a recorded seed study: ``data/seed_studies/<study>.csv`` (its script: ``run.py``).

    Examples
    --------
    >>> from navlib import repro
    >>> s = repro.SeedSpread("demo", "demo/x", seeds=(1, 2, 3), mean=0.1, sd=0.02, rms=0.1)
    >>> s.rms, len(s.seeds)
    (0.1, 3)
    """

    study: str
    check: str
    seeds: tuple[int, ...]
    mean: float  # of value - target (of the value where there is no target)
    sd: float
    rms: float  # root mean square of value - target (the bias included); the sd about the mean
    about_mean: bool = False  # the rows are plain values, spread about their own mean

    @property
    def k(self) -> float:
        """:func:`study_k` of this study's seed count."""
        return study_k(len(self.seeds), about_mean=self.about_mean)

    @property
    def tol(self) -> float:
        """k x the RMS (about a target) or x the sd (about the study's mean)."""
        return self.k * self.rms

    def describe(self) -> str:
        return (
            f"seed study {self.study} ({len(self.seeds)} calibration seeds {min(self.seeds)}-{max(self.seeds)}: mean "
            f"{self.mean:.4g}, sd {self.sd:.3g}, RMS {self.rms:.3g}); tolerance {self.k:.2f} x "
            f"{'sd' if self.about_mean else 'RMS'} (a {len(self.seeds)}-seed prediction interval at level {CHECK_ALPHA:.2g})"
        )


def seed_spread(study: str, check: str, *, about_mean: bool = False) -> SeedSpread | None:
    """The recorded spread of ``check`` in seed study ``study``, or None if the study has no row for it.

    ``about_mean``: the rows are plain values, spread about their own mean (the RMS is then the sd).

    Examples
    --------
    >>> from navlib import repro
    >>> repro.seed_spread("no_such_study_demo", "x") is None          # a study without that check
    True
    """
    rows = _study_rows(text(study, "study", empty=False)).get(text(check, "check", empty=False))
    if not rows:
        return None
    seeds, values = zip(*rows, strict=True)
    x = np.asarray(values, float)
    mean, sd = float(x.mean()), float(x.std(ddof=1)) if x.size > 1 else math.inf
    rms = sd if about_mean else float(np.sqrt(np.mean(x**2)))
    return SeedSpread(study, check, tuple(seeds), mean, sd, rms, about_mean)


def _study_rows(study: str) -> dict[str, list[tuple[int, float]]]:
    """``check -> [(seed, value - target or value)]`` of ``data/seed_studies/<study>.csv`` (empty when absent)."""
    path = root() / "data" / "seed_studies" / f"{study}.csv"
    if not path.is_file():
        return {}
    out: dict[str, list[tuple[int, float]]] = {}
    with open(path, newline="", encoding="utf-8") as fh:
        for r in csv.DictReader(line for line in fh if not line.startswith("#")):
            x = float(r["value"]) - (float(r["target"]) if r["target"] else 0.0)
            out.setdefault(r["check"], []).append((int(r["seed"]), x))
    return out


def check_study(
    name: str,
    value: Scalar,
    target: float | None,
    study: str,
    source: str,
    *,
    unit: str = "",
    note: str = "",
    paper_value: str | float | None = None,
) -> Check:
    """Check ``value`` against ``target`` within the spread a recorded seed study measured; record; raise on failure.

    With a ``target`` (a prediction computed in this run) the tolerance is :func:`study_k` x the RMS of ``value -
    target`` over the study's calibration seeds, and a bias of the prediction shows as the study's mean. With
    ``target=None`` the value is a regression of the stand-in: it must lie within :func:`study_k` sd of the study's mean
    (a prediction interval of one new seed). Both at the level :data:`CHECK_ALPHA`. Two-sided: a value
    too large is as wrong as one too small. Before the study has a row for ``name`` (``data/seed_studies/run.py``
    writes it from these very checks) the check fails: in teaching mode it is recorded with its value.

    Examples
    --------
    >>> import tempfile
    >>> from navlib import repro
    >>> tmp = tempfile.TemporaryDirectory()
    >>> repro.setup("demo", out_dir=tmp.name, style=False)
    >>> repro.check_study("demo/x", 1.0, 1.0, "no_such_study_demo", "a worked example")
    Traceback (most recent call last):
        ...
    navlib.repro.ClaimCheckFailed: demo/x: reproduced 1 is outside target 1 ± nan (a worked example; no ...
    >>> tmp.cleanup()
    """
    v, _ = _check_args(name, value, source, unit, note, False)
    spread = seed_spread(study, name, about_mean=target is None)
    t = None if target is None else _as_float(target, "target", finite=True)
    _not_the_target(value, target=target)
    centre = (spread.mean if spread else math.nan) if t is None else t
    tol = spread.tol if spread else math.nan
    passed = bool(spread is not None and math.isfinite(v) and abs(v - centre) <= tol)
    full = f"{source}; {spread.describe()}" if spread else f"{source}; no seed study row yet (data/seed_studies/run.py)"
    return _record(
        Check(
            name,
            v,
            centre,
            tol,
            passed,
            full,
            None if paper_value is None else str(paper_value),
            unit=unit,
            note=note,
            study={"name": study, "target": t},
        )
    )


def _not_the_target(value: object, **targets: object) -> None:
    """Refuse a value that is the very object passed as its target: such a check cannot fail.

    Only numpy values are compared by identity: Python shares small ints, and equal float literals
    within one code object, so ``check(name, 0.0 if refused else 1.0, 0.0, ...)`` passes the target's
    own object as a legitimate computed outcome (the static reading of tests/test_check_values.py
    judges literals)."""
    if isinstance(value, (np.floating, np.ndarray)):
        for name, target in targets.items():
            if target is value:
                raise ValueError(
                    f"value: is the very object passed as {name}; a check compares a value computed "
                    f"by navlib with an independent target"
                )


def _bounds(lower: float | None, upper: float | None) -> tuple[float | None, float | None]:
    if lower is None and upper is None:
        raise ValueError("lower, upper: give at least one bound")
    lo = None if lower is None else _as_float(lower, "lower")
    hi = None if upper is None else _as_float(upper, "upper")
    for bound, b in (("lower", lo), ("upper", hi)):
        if b is not None and math.isnan(b):
            raise ValueError(f"{bound}: expected a number (infinite for no bound), got {b}")
    if lo is not None and hi is not None and lo > hi:
        raise ValueError(f"lower: expected lower <= upper, got {lo} > {hi}")
    return lo, hi


def results() -> list[Check]:
    """Checks recorded so far in this notebook run.

    Examples
    --------
    >>> import tempfile
    >>> from navlib import repro
    >>> tmp = tempfile.TemporaryDirectory()
    >>> repro.setup("demo", out_dir=tmp.name, style=False)
    >>> _ = repro.check("demo/a", 1.0, 1.0, 0.1, "a worked example")
    >>> [c.name for c in repro.results()]
    ['demo/a']
    >>> tmp.cleanup()
    """
    return list(_state.checks)


def verdicts() -> list[Verdict]:
    """Verdicts recorded so far in this notebook run.

    Examples
    --------
    >>> import tempfile
    >>> from navlib import repro
    >>> tmp = tempfile.TemporaryDirectory()
    >>> repro.setup("demo", paper="000", out_dir=tmp.name, style=False)
    >>> _ = repro.check("P000-EQ3-EULER/demo", 1.0, 1.0, 0.1, "a worked example")
    >>> _ = repro.verdict("P000-EQ3-EULER", "reproduced", checks=["P000-EQ3-EULER/demo"])
    >>> [v.claim for v in repro.verdicts()]
    ['P000-EQ3-EULER']
    >>> tmp.cleanup()
    """
    return list(_state.verdicts)


@boundary
def verdict(
    claim: str,
    verdict: str,
    *,
    checks: Sequence[str] | None = None,
    evidence: Sequence[str] | None = None,
    paper: str | float | None = None,
    ours: str | float | None = None,
    unit: str = "",
    reason: str = "",
    erratum: str = "",
    figure: str = "",
    real_data: Flag = False,
) -> Verdict | None:
    """Record the verdict on a claim of this notebook's paper; raise ``ValueError`` if it is not supported.

    With ``real_data=True`` the verdict is the claim's second one, whose evidence is a committed real recording
    (``data/real/``) instead of the paper's (simulated) setting: it may judge a claim of any paper, from the
    notebook that holds the recording, and the ledger shows it beside the claim's simulation verdict.

    Recorded silently (:func:`summary` shows it). In teaching mode a verdict resting on a failed
    check is not recorded: a :class:`ClaimCheckWarning` says so and ``None`` is returned.

    Parameters
    ----------
    claim : str
        A claim id of ``data/claims.csv`` of the paper given to :func:`setup`.
    verdict : str
        One of :data:`VERDICTS`: ``"reproduced"`` (our number agrees with the paper's within
        the checks' tolerance), ``"reproduced with correction"`` (agrees once the named
        ``erratum`` is fixed, and the printed form is shown to fail), ``"differs"`` (our
        number disagrees: ``reason`` says why), ``"refuted"`` (the paper's statement is
        false in its own setting), ``"direction only"`` (a stand-in can show only the sign
        or ordering), ``"undecided at this scale"`` (the test straddles its cut within the
        seed-to-seed spread: ``paper`` and ``ours`` show both numbers, ``reason`` the cut),
        ``"not checkable here"`` (only and always of a claim whose catalogue kind, one of
        :data:`NOT_CHECKABLE`, says why; ``paper`` gives the paper's number and ``reason`` the
        sentence why), ``"extension"`` (the only verdict of a catalogue row of kind ``extension``:
        the project's own quantity, checked, with no paper statement to judge).
    checks : sequence of str, optional
        Names of the checks, recorded earlier in this run and passed, that the verdict rests
        on. Default: every check named ``claim`` or ``claim/...``. Every verdict but
        ``"not checkable here"`` needs at least one.
    evidence : sequence of str, optional
        The checks among ``checks`` that assert the disagreement: for ``"differs"`` and
        ``"refuted"`` that our value lies outside the paper's, for ``"reproduced with
        correction"`` that the printed form fails. Default: the :func:`check_outside`
        checks among ``checks``. Required (non-empty) for those three verdicts.
    paper, ours : str or float, optional
        The paper's value and ours as the ledger shows them (a float is shown with
        ``unit``). Default: the catalogue's ``paper_value`` and the first check's value.
        ``"differs"`` and ``"refuted"`` need both; ``ours`` must come from a computation.
    reason : str
        Why the values differ, why the statement is false, why only the direction can
        be shown, or what a check would need. Required for every verdict but ``"reproduced"``
        and ``"reproduced with correction"``.
    erratum : str
        For ``"reproduced with correction"``: the erratum id (``data/errata.csv``, listed in
        the claim's ``erratum`` column) whose correction makes the claim hold.
    figure : str
        A figure saved earlier in this run (:func:`savefig` name) shown as the claim's thumbnail.
    real_data : bool
        The evidence is a real recording (the ledger's *real data* verdict); the claim may be of any paper.

    Examples
    --------
    >>> import tempfile
    >>> from navlib import repro
    >>> tmp = tempfile.TemporaryDirectory()
    >>> repro.setup("demo", paper="000", out_dir=tmp.name, style=False)
    >>> _ = repro.check("P000-EQ3-EULER/demo", 1.0, 1.0, 0.1, "a worked example")
    >>> repro.verdict("P000-EQ3-EULER", "reproduced", checks=["P000-EQ3-EULER/demo"]).verdict
    'reproduced'
    >>> repro.verdict("P000-EQ3-EULER", "reproduced", checks=["P000-EQ3-EULER/missing"])
    Traceback (most recent call last):
        ...
    ValueError: checks: 'P000-EQ3-EULER/missing' was not recorded in this run
    >>> tmp.cleanup()
    """
    if _state.notebook is None:
        raise RuntimeError("call navlib.repro.setup(notebook, paper=...) before verdict()")
    if _state.paper is None and not real_data:
        raise ValueError(
            f"claim: notebook {_state.notebook} was set up without a paper, so it records only real-data verdicts "
            "(real_data=True)"
        )
    catalogue = _catalogue()
    row = catalogue["claims"].get(claim)
    if row is None or not (real_data or row["paper"] == _state.paper):
        wanted = "a claim id" if real_data else f"a claim id of paper {_state.paper}"
        raise ValueError(f"claim: expected {wanted} in data/claims.csv, got {claim!r}")
    choice(verdict, "verdict", VERDICTS)
    _texts(unit=unit, reason=reason, erratum=erratum, figure=figure)
    if (row["kind"] == EXTENSION) != (verdict == EXTENSION):
        raise ValueError(
            f"verdict: {claim} is of kind {row['kind']!r} in data/claims.csv; verdict words judge a paper "
            f"statement, and {EXTENSION!r} is the one word of (and only of) the project's own quantities"
        )
    if not real_data and (row["kind"] in NOT_CHECKABLE) != (verdict == "not checkable here"):
        raise ValueError(
            f"verdict: {claim} is of kind {row['kind']!r} in data/claims.csv; 'not checkable here' is the simulation "
            f"verdict of (and only of) the kinds that say why: {', '.join(NOT_CHECKABLE)}"
        )
    names = (
        [c.name for c in _state.checks if c.name == claim or c.name.startswith(claim + "/")] if checks is None else list(checks)
    )
    recorded = {c.name: c for c in _state.checks}
    for n in names:
        if n not in recorded:
            raise ValueError(f"checks: {n!r} was not recorded in this run")
        if not recorded[n].passed:
            if _state.teaching:  # the failure was already shown as a warning
                warnings.warn(
                    f"verdict on {claim} not recorded: its check {n!r} failed (teaching mode)", ClaimCheckWarning, stacklevel=2
                )
                return None
            raise ValueError(f"checks: {n!r} failed; a verdict cannot rest on it")
    if verdict != "not checkable here" and not names:
        raise ValueError(f"checks: a verdict of {verdict!r} rests on at least one check; none is named {claim}[/...]")
    if verdict != "not checkable here" and all(recorded[n].on_printed for n in names):
        raise ValueError(
            f"checks: a verdict of {verdict!r} rests on a computation; the checks of {claim} only re-do "
            "arithmetic on the paper's printed numbers (on_printed)"
        )
    evid = [n for n in names if recorded[n].outside] if evidence is None else list(evidence)
    if not set(evid) <= set(names):
        raise ValueError(f"evidence: expected checks among {names}, got {evid}")
    if verdict in _NEEDS_EVIDENCE and not evid:
        raise ValueError(
            f"evidence: a verdict of {verdict!r} needs a check that asserts the disagreement "
            "(check_outside, or name it in evidence=)"
        )
    if verdict == "reproduced with correction" and not set(names) - set(evid):
        raise ValueError("checks: a verdict of 'reproduced with correction' also rests on a check of the corrected form")
    if verdict in ("differs", "refuted", "undecided at this scale") and (paper is None or ours is None):
        raise ValueError(f"paper, ours: a verdict of {verdict!r} shows both numbers")
    if verdict == "not checkable here" and paper is None and not row["paper_value"]:
        raise ValueError("paper: a claim that is not checkable here shows the paper's number")
    if verdict not in ("reproduced", "reproduced with correction") and not reason.strip():
        raise ValueError(f"reason: a verdict of {verdict!r} says why")
    if verdict == "reproduced with correction":
        listed = row["erratum"].split(";") if row["erratum"] else []
        if erratum not in catalogue["errata"] or erratum not in listed:
            raise ValueError(f"erratum: expected an erratum of data/errata.csv listed for {claim} ({listed}), got {erratum!r}")
    elif erratum and erratum not in catalogue["errata"]:
        raise ValueError(f"erratum: expected an id of data/errata.csv, got {erratum!r}")
    if figure and figure not in _state.figures:
        raise ValueError(f"figure: expected a figure saved in this run ({sorted(_state.figures)}), got {figure!r}")
    if ours is None and names and verdict != "not checkable here":  # (a check's value there is no reproduction)
        first = recorded[names[0]]
        unit = unit or first.unit
        # a check against 0 measures a residual: show it as one
        ours = f"max error {first.value:.1g}{' ' + unit if unit else ''}" if first.expected == 0 else first.value
    v = Verdict(
        claim,
        verdict,
        names,
        evid,
        _shown(paper, unit) if paper is not None else None,
        _shown(ours, unit) if ours is not None else None,
        reason.strip(),
        erratum,
        figure,
        real_data,
    )
    _state.verdicts = [k for k in _state.verdicts if (k.claim, k.real_data) != (claim, real_data)] + [v]
    _state.encoded[_verdict_key(v)] = _encode(_verdict_row(v))
    _write()
    return v


def _verdict_key(v: Verdict) -> tuple[str, str]:
    return ("real-data verdict" if v.real_data else "verdict", v.claim)


def _verdict_row(v: Verdict) -> dict[str, object]:
    row = asdict(v)
    if not row["real_data"]:  # written only when set: the simulation verdicts keep their bytes
        del row["real_data"]
    return row


def _shown(x: object, unit: str) -> str:
    """A value as the ledger shows it: a number to 5 significant digits with its unit, or the text given."""
    if isinstance(x, str):
        return x
    return f"{_as_float(x, 'value'):.5g}{' ' + unit if unit else ''}"


def _catalogue() -> dict[str, dict[str, Any]]:
    """``data/claims.csv`` rows by id and ``data/errata.csv`` ids of the checkout (read once per run)."""
    if _state.catalogue is None:
        data = root() / "data"
        with open(data / "claims.csv", newline="", encoding="utf-8") as fh:
            claims = {r["id"]: r for r in csv.DictReader(line for line in fh if not line.startswith("#"))}
        with open(data / "errata.csv", newline="", encoding="utf-8") as fh:
            errata = {r["id"] for r in csv.DictReader(line for line in fh if not line.startswith("#"))}
        _state.catalogue = {"claims": claims, "errata": errata}
    return _state.catalogue


def _write() -> None:
    if _state.notebook is None:
        return
    # json.dumps(data, indent=1), with the two lists as placeholders for the rows encoded once when
    # recorded (encoding every row at every check was quadratic: 3 s in a notebook of 180 checks). Keys
    # beyond the original format are written only when used, so older results keep their bytes.
    data: dict[str, Any] = {"notebook": _state.notebook, "checks": "\0checks"}
    if _state.teaching or _state.fast:
        data["mode"] = {"teaching": _state.teaching, "fast": _state.fast}
    if _state.paper is not None:
        data["paper"] = _state.paper
    if _state.paper is not None or _state.verdicts:
        data["verdicts"] = "\0verdicts"
    text = json.dumps(data, indent=1, allow_nan=True)
    text = text.replace('"\\u0000checks"', _rows([_state.encoded["check", c.name] for c in _state.checks]))
    text = text.replace('"\\u0000verdicts"', _rows([_state.encoded[_verdict_key(v)] for v in _state.verdicts]))
    (_build_dir(_state.notebook) / "results.json").write_text(text + "\n")


def _encode(row: dict[str, Any]) -> str:
    """A results.json row as ``json.dumps(..., indent=1)`` lays it out inside a top-level list."""
    return json.dumps(row, indent=1, allow_nan=True).replace("\n", "\n  ")


def _rows(encoded: list[str]) -> str:
    return "[\n  " + ",\n  ".join(encoded) + "\n ]" if encoded else "[]"


def _row(c: Check) -> dict[str, Any]:
    row = asdict(c)
    for key in ("outside", "on_printed", "study"):  # written only when set: other rows keep their bytes
        if not row[key]:
            del row[key]
    return row


_TRUE, _FALSE = ("1", "true", "yes", "on"), ("", "0", "false", "no", "off")


@boundary
def env_flag(name: Text, default: bool = False) -> bool:
    """A boolean switch from the environment variable ``name`` (``1/true/yes/on`` or ``0/false/no/off``).

    ``default`` when the variable is unset. For a notebook's parameters cell, e.g.
    ``TEACHING = repro.env_flag("NAVLIB_TEACHING")``; any other text raises ``ValueError`` naming it.

    Examples
    --------
    >>> from navlib import repro
    >>> os.environ["NAVLIB_DEMO_FLAG"] = "yes"
    >>> repro.env_flag("NAVLIB_DEMO_FLAG"), repro.env_flag("NAVLIB_DEMO_UNSET", default=True)
    (True, True)
    >>> del os.environ["NAVLIB_DEMO_FLAG"]
    """
    raw = os.environ.get(name)
    if raw is None:
        return flag(default, "default")
    value = raw.strip().lower()
    if value in _TRUE or value in _FALSE:
        return value in _TRUE
    raise ValueError(f"{name}: expected one of {', '.join(_TRUE + _FALSE[1:])} (environment variable), got {raw!r}")


@boundary
def mode(*, teaching: Flag, fast: Flag) -> None:
    """Apply a notebook's switches (after :func:`setup`): teaching mode and the fast parameter set.

    In teaching mode a failed check warns (:class:`ClaimCheckWarning`) instead of raising. Both are
    recorded in results.json (``mode``), whose results then do not enter the ledger.

    Examples
    --------
    >>> import tempfile
    >>> from navlib import repro
    >>> tmp = tempfile.TemporaryDirectory()
    >>> repro.setup("demo", out_dir=tmp.name, style=False)
    >>> repro.mode(teaching=False, fast=True)                         # recorded in results.json
    >>> repro.check("demo/fast", 1.0, 1.0, 0.1, "a worked example").passed
    True
    >>> tmp.cleanup()
    """
    if _state.notebook is None:
        raise RuntimeError("call navlib.repro.setup(notebook, ...) before mode()")
    _state.teaching, _state.fast = teaching, fast
    _write()


def summary() -> Any:
    """The checks and verdicts recorded since the previous call, as one compact table.

    A ``pandas.DataFrame`` with a row per check (``check``, ``paper`` value, ``ours``, ``tolerance``,
    ``result``, and the ``verdict`` of the claim it supports once recorded) and a row per verdict that
    rests on no check of the table (``not checkable here``). Ends a notebook section: checks record
    silently, and the table is the section's only output about them.

    Examples
    --------
    >>> import tempfile
    >>> from navlib import repro
    >>> tmp = tempfile.TemporaryDirectory()
    >>> repro.setup("demo", out_dir=tmp.name, style=False)
    >>> _ = repro.check("demo/a", 1.02, 1.0, 0.05, "a worked example")
    >>> table = repro.summary()
    >>> list(table.columns)
    ['paper', 'ours', 'tolerance', 'result', 'verdict']
    >>> tmp.cleanup()
    """
    checks = _state.checks[_state.shown_checks :]
    new_verdicts = _state.verdicts[_state.shown_verdicts :]
    _state.shown_checks, _state.shown_verdicts = len(_state.checks), len(_state.verdicts)
    by_check = {n: _shown_verdict(v) for v in _state.verdicts for n in v.checks}
    rows = [
        {
            "check": c.name,
            "paper": c.paper_value if c.paper_value is not None else "",
            "ours": _ours(c),
            "tolerance": _target(c),
            "result": "pass" if c.passed else "FAIL",
            "verdict": by_check.get(c.name, ""),
        }
        for c in checks
    ]
    shown = {c.name for c in checks}
    rows += [
        {
            "check": f"{v.claim} (claim)",
            "paper": v.paper or "",
            "ours": v.ours or "",
            "tolerance": "",
            "result": "",
            "verdict": _shown_verdict(v),
        }
        for v in new_verdicts
        if not set(v.checks) & shown
    ]
    table = _whole_table()(rows, columns=["check", "paper", "ours", "tolerance", "result", "verdict"])
    if not rows:
        return table
    table = table.set_index("check")
    table.index.name, table.columns.name = None, "check"  # one header row: "check" in its corner
    return table


def _shown_verdict(v: Verdict) -> str:
    return f"{v.verdict} (real data)" if v.real_data else v.verdict


@functools.cache
def _whole_table() -> type:
    """A DataFrame shown with all its rows (a check table is never cut to its head and tail)."""
    import pandas as pd

    class CheckTable(pd.DataFrame):
        @property
        def _constructor(self) -> type:
            return CheckTable

        def _repr_html_(self) -> str:
            """The whole table, folded under a one-line count (the reproduction details of a section)."""
            with pd.option_context("display.max_rows", None, "display.max_colwidth", None):
                table = super()._repr_html_()
            results = self["result"].value_counts() if "result" in self else {}
            counts = ", ".join(
                f"{n} {'passed' if r == 'pass' else 'failed' if r == 'FAIL' else r}" for r, n in results.items() if r
            )
            opened = " open" if "FAIL" in results else ""  # a failed check is never folded away
            return (
                f"<details class='checks'{opened}><summary>Reproduction details: {len(self)} checks and claims"
                f"{' (' + counts + ')' if counts else ''}</summary>\n{table}\n</details>"
            )

    return CheckTable


def caption(markdown: str) -> Any:
    """Text with computed numbers (a figure caption, a sentence quoting results) rendered as Markdown.

    A notebook's markdown cells cannot hold numbers that a run computes; typed copies go stale. Build
    the text with an f-string from the run's values and make this the last expression of the cell.

    Examples
    --------
    >>> from navlib import repro
    >>> repro.caption(f"Fig. 1: heading error after {10} s: {0.123:.2f} deg.").data
    'Fig. 1: heading error after 10 s: 0.12 deg.'
    """
    from IPython.display import Markdown  # noqa: PLC0415 -- only notebooks need IPython

    return Markdown(text(markdown, "markdown", empty=False))


@dataclass
class Exercise:
    """The outcome of :func:`exercise`: ``passed`` is None while the stub is not written yet.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import repro
    >>> result = repro.exercise(lambda x: None, np.sin, [(0.1,)])     # a stub not written yet
    >>> result.passed is None, result.message[:27]
    (True, '*`<lambda>` is not written ')
    """

    passed: bool | None
    message: str

    def _repr_markdown_(self) -> str:
        return self.message


@boundary
def exercise(
    student: Callable[..., Any], reference: Callable[..., Any], cases: Sequence[tuple[Any, ...]], tol: NonNegative = 1e-9
) -> Exercise:
    """Check a student's function against navlib's ``reference`` on each argument tuple of ``cases``.

    A coding exercise gives a stub that returns ``None`` ("your code here"); until it is written the result
    says so and nothing fails, so the notebook still runs to the end. Once written, its values must agree
    with ``reference`` within ``tol`` (absolute) on every case; the first case that does not is shown. The
    chapter tests its own hidden solution the same way (``assert exercise(solution, ...).passed``), so an
    exercise whose solution is wrong cannot pass.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import repro
    >>> def my_wrap(a):
    ...     return (a + np.pi) % (2 * np.pi) - np.pi              # a student's wrap into [-pi, pi)
    ...
    >>> from navlib import attitude
    >>> repro.exercise(my_wrap, attitude.wrap_pi, [(0.5,), (4.0,)]).passed
    True
    >>> repro.exercise(my_wrap, attitude.wrap_pi, [(np.pi,)]).passed   # wrap_pi keeps +pi: (-pi, pi]
    False
    """
    if not callable(student) or not callable(reference):  # type: ignore[redundant-expr]  # the caller's argument, checked
        raise ValueError("student, reference: expected functions")
    if not isinstance(cases, (list, tuple)) or not cases or not all(isinstance(c, tuple) for c in cases):
        raise ValueError(f"cases: expected a non-empty list of argument tuples such as [(0.1,), (1.0,)], got {cases!r:.60}")
    name = getattr(student, "__name__", "your function")
    for args in cases:
        got = student(*args)
        if got is None:
            return Exercise(None, f"*`{name}` is not written yet: fill in the stub above and run this cell again.*")
        want = np.asarray(reference(*args), dtype=float)
        got = np.asarray(got, dtype=float)
        if got.shape != want.shape or not np.allclose(got, want, rtol=0.0, atol=tol):
            call = f"{name}({', '.join(map(repr, args))})"
            return Exercise(
                False,
                f"**Not yet:** `{call}` gives {np.array2string(got, precision=6)}, "
                f"navlib gives {np.array2string(want, precision=6)}.",
            )
    return Exercise(True, f"**Correct:** `{name}` agrees with navlib on all {len(cases)} cases (to {tol:g}).")


def answer(markdown: str, label: str = "Answer") -> Any:
    """The answer to a "Try this" exercise, collapsed (an HTML ``<details>`` block) until the reader opens it.

    ``markdown`` is built from values the notebook computed (an f-string), never typed-in results.

    Examples
    --------
    >>> from navlib import repro
    >>> type(repro.answer(f"The heading error is {0.25:.2f} deg.")).__name__   # an IPython Markdown object
    'Markdown'
    >>> repro.answer("42").data.splitlines()[0]
    '<details><summary>Answer</summary>'
    """
    from IPython.display import Markdown  # noqa: PLC0415 -- only notebooks need IPython

    body, title = text(markdown, "markdown", empty=False), text(label, "label", empty=False)
    return Markdown(f"<details><summary>{title}</summary>\n\n{body}\n\n</details>")


@boundary
def explorer(draw: Callable[..., Figure], name: str, controls: Is[dict[str, Any]]) -> None:
    """An interactive explorer with a static fallback: ``draw(**values) -> Figure``.

    The figure at the controls' default values is drawn once, saved as ``name`` (:func:`savefig`) and
    shown: that is all a headless run (``make reproduce``, nbmake, the site) shows. Where ipywidgets is
    installed the controls follow, and moving one redraws that same figure in place (one figure on the page,
    never a stale copy above a live one). Slider readouts show three significant digits.

    Parameters
    ----------
    draw : callable
        Takes the controls' values as keyword arguments, returns a matplotlib Figure.
    name : str
        File name of the static figure.
    controls : dict
        ``argument -> ipywidgets control`` (e.g. ``FloatSlider(value=..., min=..., max=...)``), or
        ``argument -> value`` for a fixed argument; a control's ``value`` is its default.

    Examples
    --------
    >>> import tempfile
    >>> import matplotlib.pyplot as plt
    >>> from navlib import repro
    >>> tmp = tempfile.TemporaryDirectory()
    >>> repro.setup("demo", out_dir=tmp.name, style=False)
    >>> def draw(slope=1.0):
    ...     fig, ax = plt.subplots()
    ...     ax.plot([0.0, 1.0], [0.0, slope])
    ...     return fig
    ...
    >>> repro.explorer(draw, "slope", {"slope": 2.0})                 # headless: saved and shown at its defaults
    >>> sorted(p.name for p in (repro.build_dir("demo") / "figures").iterdir())
    ['slope.png']
    >>> tmp.cleanup()
    """
    import matplotlib
    import matplotlib.pyplot as plt
    from IPython.display import Image, display  # noqa: PLC0415 -- only notebooks need IPython

    if not callable(draw):
        raise ValueError(f"draw: expected a function returning a Figure, got {type(draw).__name__}")
    defaults = {k: getattr(c, "value", c) for k, c in controls.items()}
    fig = draw(**defaults)
    if matplotlib.get_backend() != _INLINE:  # a script or another backend: the saved figure, nothing live
        savefig(fig, name)
        plt.show()
        return
    if _state.notebook is None:
        raise RuntimeError("call navlib.repro.setup(notebook) before explorer()")
    shown = display(Image(data=_write_png(fig, name).read_bytes(), format="png"), display_id=True)
    plt.close(fig)
    try:
        import ipywidgets as widgets
    except ImportError:  # the static figure is all there is
        return
    live = {k: c for k, c in controls.items() if isinstance(c, widgets.ValueWidget)}
    for c in live.values():
        if isinstance(c, (widgets.FloatSlider, widgets.FloatLogSlider)):
            c.readout_format = ".3g"

    def redraw(_change: object = None) -> None:
        shown.update(_png(draw(**{**defaults, **{k: c.value for k, c in live.items()}})))

    for c in live.values():
        c.observe(redraw, names="value")
    display(widgets.VBox(list(live.values())))
