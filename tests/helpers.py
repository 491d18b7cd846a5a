"""Helpers shared by the test modules: reference values and the project's files.

Bad input to every public callable: the registry tools/fuzz_calls.py, run by tests/test_bad_input.py."""

import csv
import json
import os
import subprocess
import sys
from pathlib import Path

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
        return [
            p
            for p in sorted(ROOT.rglob("*"))
            if p.is_file()
            and not _NOT_SOURCE & set(p.relative_to(ROOT).parts)
            and p.suffix != ".egg-info"
            and not any(part.endswith(".egg-info") for part in p.relative_to(ROOT).parts)
        ]


def run_json_script(script: str, disable_jit: bool) -> dict:
    """Run ``script`` (which prints one JSON object) in a fresh interpreter, compiled or with ``NUMBA_DISABLE_JIT``."""
    env = dict(os.environ, NUMBA_DISABLE_JIT="1" if disable_jit else "0")
    out = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True, text=True, check=True)
    return json.loads(out.stdout)
