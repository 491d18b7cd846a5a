#!/usr/bin/env -S uv run --script
# /// script
# dependencies = ["nox>=2025.2"]
# ///
"""Task sessions that run the same on Linux, macOS and Windows (CI calls these; the Makefile is POSIX-only).

    nox -s tests-3.11       the pinned environment (environment.txt), unit tests + every notebook (tests/test_notebook_runs.py)
    nox -s tests_latest     the newest releases every declared requirement allows, unit tests
    nox -s tests_min        the declared floors (uv --resolution lowest-direct), unit tests
    nox -s build            sdist + wheel, twine check --strict, check-manifest
    nox -s lint             the pre-commit hooks (local, offline) over every file
    nox -s typecheck        mypy at the level configured in pyproject.toml (a CI gate: 0 errors)

Environments are made with uv (``pip install nox uv``); extra arguments after ``--`` go to pytest.
"""

from __future__ import annotations

import tomllib
from pathlib import Path

import nox

nox.needs_version = ">=2025.2"
nox.options.default_venv_backend = "uv"

ROOT = Path(__file__).parent
PYTHONS = ["3.11", "3.12", "3.13"]
ENV = {"PYTHONHASHSEED": "0", "MPLBACKEND": "Agg", "NAVLIB_PROGRESS": "0"}
# Unit tests only: the notebooks (test_notebook_runs, test_teaching, test_isolation) are checked against
# the pins, whose results the README quotes; test_install installs the pins; test_site needs the built site;
# test_packaging checks the repository's configuration against the pins and runs the contributor tools.
UNIT = [
    "tests",
    "--ignore=tests/test_notebook_runs.py",
    "--ignore=tests/test_teaching.py",
    "--ignore=tests/test_isolation.py",
    "--ignore=tests/test_install.py",
    "--ignore=tests/test_site.py",
    "--ignore=tests/test_packaging.py",
]


def own_numba_cache(session: nox.Session) -> dict[str, str]:
    """Another numba version must not overwrite the compiled kernels cached beside the sources for .venv."""
    return {**ENV, "NUMBA_CACHE_DIR": str(Path(session.virtualenv.location) / "numba-cache")}


def pinned(*names: str) -> list[str]:
    """``name==version`` of each named package as environment.txt pins it."""
    pins = {}
    for line in (ROOT / "environment.txt").read_text().splitlines():
        name, sep, version = line.partition("==")
        if sep and not line.startswith("#"):
            pins[name.lower()] = version.split("#")[0].strip()
    return [f"{n}=={pins[n.lower()]}" for n in names]


def dev_tools() -> list[str]:
    """The contributor tools of pyproject.toml's ``dev`` group, at environment.txt's pins."""
    group = tomllib.loads((ROOT / "pyproject.toml").read_text())["dependency-groups"]["dev"]
    return pinned(*(req.split(">")[0].split("=")[0] for req in group))


@nox.session(python=PYTHONS)
def tests(session: nox.Session) -> None:
    """The pinned environment of `make test`: unit tests and every notebook."""
    session.install("-r", "environment.txt")
    session.install("--no-deps", "-e", ".")
    session.run(
        "python",
        "-m",
        "pytest",
        "tests",
        "-n",
        "2",
        "--dist",
        "loadgroup",
        *session.posargs,
        env=ENV,
    )


@nox.session(python=PYTHONS[-1], default=False)
def tests_latest(session: nox.Session) -> None:
    """The newest versions the declared requirements allow (what `pip install navlib-repro[test]` gets today)."""
    session.install("-e", ".[test]")
    session.run("python", "-m", "pytest", *UNIT, "-n", "2", *session.posargs, env=own_numba_cache(session))


@nox.session(python=PYTHONS[0], default=False)
def tests_min(session: nox.Session) -> None:
    """The declared floors: every direct requirement of navlib and of [test] at its lowest allowed version."""
    session.install("--resolution=lowest-direct", "-e", ".[test]")
    session.run("uv", "pip", "list", "--python", session.virtualenv.location, external=True)  # the floors, in the log
    session.run("python", "-m", "pytest", *UNIT, "-n", "2", *session.posargs, env=own_numba_cache(session))


@nox.session(python=PYTHONS[0])
def build(session: nox.Session) -> None:
    """The distributions as the publish workflow builds them, checked as the package index will."""
    session.install(*pinned("build", "twine", "check-manifest", "uv"))
    dist = ROOT / "dist"
    for old in dist.glob("*"):
        old.unlink()
    session.run("python", "-m", "build", "--installer=uv", "--outdir", str(dist), ".")
    session.run("twine", "check", "--strict", *map(str, sorted(dist.glob("*"))))
    session.run("check-manifest")


@nox.session(python=PYTHONS[0])
def lint(session: nox.Session) -> None:
    """Every pre-commit hook over every file (the hooks are local: pre-commit clones nothing)."""
    session.install(*dev_tools())
    session.run("pre-commit", "run", "--all-files", "--show-diff-on-failure", *session.posargs)


@nox.session(python=PYTHONS[0], default=False)
def typecheck(session: nox.Session) -> None:
    """mypy over navlib/ at the level configured in pyproject.toml."""
    session.install("-r", "environment.txt")
    session.install("--no-deps", "-e", ".")
    session.run("mypy", *session.posargs)


if __name__ == "__main__":
    nox.main()
