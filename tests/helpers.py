"""Helpers shared by the test modules: reference values and argument fuzzing."""
import csv
import subprocess
from pathlib import Path

import numpy as np
import pytest

REFERENCE = Path(__file__).resolve().parents[1] / "data" / "reference"
"""Published reference values committed with the project (each file names its source and tolerance)."""


def read_vectors(name):
    """Rows of a ``data/reference`` CSV (lines starting with '#' are comments) as dicts of strings.

    A missing or empty file fails the test: the cross-checks must never be skipped.
    """
    path = REFERENCE / name
    assert path.is_file(), f"reference file missing: {path}"
    with open(path, newline="", encoding="utf-8") as fh:
        rows = list(csv.DictReader(line for line in fh if not line.startswith("#")))
    assert rows, f"{path} has no data rows"
    return rows


ROOT = Path(__file__).resolve().parents[1]
_NOT_SOURCE = {".git", ".venv", "build", "__pycache__", ".pytest_cache", ".hypothesis", ".ipynb_checkpoints"}


def project_files() -> list[Path]:
    """The project's files: ``git ls-files`` in a checkout; in an unpacked archive, every file
    outside virtual environments, caches and ``build/``."""
    try:
        out = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True, check=True).stdout
        return [ROOT / p for p in out.decode().split("\0") if p]
    except (OSError, subprocess.CalledProcessError):
        return [p for p in sorted(ROOT.rglob("*"))
                if p.is_file() and not _NOT_SOURCE & set(p.relative_to(ROOT).parts) and p.suffix != ".egg-info"
                and not any(part.endswith(".egg-info") for part in p.relative_to(ROOT).parts)]


# ---------------------------------------------------------------- API fuzzing
# Every public function is called with each of its numeric arguments replaced by a string, a complex
# value, an object array, a boolean, NaN, inf, an empty array and (for vector arguments) a wrong trailing shape;
# each call must raise ValueError/TypeError whose message starts with the argument's name. NaN is
# skipped where the docstring makes it a dropout marker.

MUTATIONS = ("str", "complex", "object", "bool", "nan", "inf", "empty", "shape")


def mutate(value, how):
    v = np.asarray(value, dtype=float)
    if how == "str":
        return "abc"
    if how == "complex":
        return v + 1j
    if how == "object":
        return v.astype(object)
    if how == "bool":
        return True if v.ndim == 0 else np.ones(v.shape, dtype=bool)
    if how in ("nan", "inf"):
        v = v.copy()
        v.reshape(-1)[0] = np.nan if how == "nan" else np.inf
        return v
    if how == "empty":
        return np.zeros((0,) + v.shape[1:]) if v.ndim > 1 else np.zeros(0)
    if how == "shape":
        return np.zeros(v.shape[:-1] + (v.shape[-1] + 1,)) if v.ndim >= 1 else None
    raise AssertionError(how)


def fuzz_cases(table):
    cases = []
    for name, (func, good, nan_ok, *free) in table.items():
        for arg, value in good.items():
            if not isinstance(value, (int, float, list, np.ndarray)) or isinstance(value, bool):
                continue                                   # generators, records, options: not numeric
            for how in MUTATIONS:
                if how == "nan" and arg in nan_ok:
                    continue
                if how == "shape" and (np.ndim(value) == 0 or (free and arg in free[0])):
                    continue                               # scalars and free-length 1-D arrays have no wrong tail
                cases.append(pytest.param(func, good, arg, how, id=f"{name}-{arg}-{how}"))
    return cases


def check_fuzz(func, good, arg, how):
    func(**good)                                           # the unmutated call works
    kwargs = dict(good)
    kwargs[arg] = mutate(good[arg], how)
    with pytest.raises((ValueError, TypeError)) as exc:
        func(**kwargs)
    assert str(exc.value).startswith(arg), str(exc.value)
