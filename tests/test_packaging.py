"""The project's own files: packaging metadata, pins, Binder, CI, lint, licence and citation.

None of the configuration files here can be exercised on this machine (no Binder, no hosted CI),
so these tests check what can be checked: that each file parses, says what it must, and agrees with
the single source of truth for versions, ``environment.txt``.
"""
from __future__ import annotations

import importlib.metadata as md
import re
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest
import yaml
from packaging.markers import default_environment
from packaging.requirements import Requirement
from packaging.specifiers import SpecifierSet
from packaging.utils import canonicalize_name

ROOT = Path(__file__).resolve().parents[1]
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
PROJECT = PYPROJECT["project"]


def pins(path: Path) -> dict[str, str]:
    """``name==version`` lines of a requirements file, keyed by canonical name."""
    out = {}
    for line in path.read_text(encoding="utf-8").splitlines():
        line = line.split("#", 1)[0].strip()
        if line:
            name, sep, version = line.partition("==")
            assert sep, f"{path.name}: not an exact pin: {line!r}"
            out[canonicalize_name(name)] = version.strip()
    return out


ENV = pins(ROOT / "environment.txt")
BENCH = pins(ROOT / "requirements-bench.txt")


def declared() -> list[Requirement]:
    reqs = [Requirement(r) for r in PROJECT["dependencies"]]
    for group in PROJECT["optional-dependencies"].values():
        reqs += [Requirement(r) for r in group]
    return reqs


# ---------------------------------------------------------------- metadata and pins

def test_distribution_name_and_metadata():
    assert PROJECT["name"] == "navlib-repro"        # `navlib` on the package index is another project
    assert PROJECT["requires-python"] == ">=3.11"
    assert PROJECT["license"] == "MIT" and (ROOT / "LICENSE").read_text().startswith("MIT License")
    assert set(PROJECT["optional-dependencies"]) == {"test", "notebooks", "docs", "bench"}
    for key in ("authors", "urls", "classifiers", "readme", "description"):
        assert PROJECT[key], key
    versions = {c.rsplit(":: ", 1)[1] for c in PROJECT["classifiers"] if c.startswith("Programming Language :: Python :: 3.")}
    assert versions and all(SpecifierSet(PROJECT["requires-python"]).contains(v) for v in versions)


def test_package_data_is_shipped():
    assert "data/*.csv" in PYPROJECT["tool"]["setuptools"]["package-data"]["navlib"]
    assert (ROOT / "navlib" / "data" / "sensor_presets.csv").is_file()


@pytest.mark.parametrize("req", declared(), ids=str)
def test_declared_requirement_is_pinned_and_satisfied(req):
    name = canonicalize_name(req.name)
    version = ENV.get(name) or BENCH.get(name)
    assert version, f"{req.name} is declared in pyproject.toml but pinned in neither environment.txt nor requirements-bench.txt"
    assert req.specifier.contains(version, prereleases=True), f"{req.name}=={version} does not satisfy {req}"


def test_every_top_level_pin_is_declared():
    """Pins that no other pinned package requires are the project's own choices: each must be in a group."""
    # Markers are evaluated for Python 3.11, the interpreter environment.txt was frozen with: some pins
    # (e.g. importlib-metadata) are required only there, and the freeze is exact for that version.
    frozen_for = {"python_version": "3.11", "python_full_version": "3.11.7"}

    def active(dist: str, extra: str = "") -> list[Requirement]:
        env = {**default_environment(), **frozen_for, "extra": extra}
        return [r for r in map(Requirement, md.requires(dist) or []) if r.marker is None or r.marker.evaluate(env)]

    required = set()
    for name in ENV:
        for r in active(name):
            required.add(canonicalize_name(r.name))
            for extra in r.extras:                  # e.g. jsonschema[format-nongpl] brings its own pins
                required.update(canonicalize_name(x.name) for x in active(r.name, extra))
    top_level = set(ENV) - required
    missing = top_level - {canonicalize_name(r.name) for r in declared()}
    assert not missing, f"pinned in environment.txt, required by nothing, declared nowhere in pyproject.toml: {sorted(missing)}"


def test_environment_matches_running_interpreter():
    """environment.txt is exact for the Python it is installed with (its header says which)."""
    for name, version in ENV.items():
        assert md.version(name) == version, f"{name}: installed {md.version(name)}, pinned {version} (run `make venv`)"


# ---------------------------------------------------------------- Binder

def test_binder_pins_agree_with_environment():
    binder = ROOT / "binder"
    assert pins(binder / "requirements.txt") == ENV
    runtime = (binder / "runtime.txt").read_text().strip()
    assert re.fullmatch(r"python-3\.\d+", runtime) and SpecifierSet(PROJECT["requires-python"]).contains(runtime[7:])
    post = binder / "postBuild"
    assert post.stat().st_mode & 0o111, "binder/postBuild must be executable"
    assert "pip install --no-deps ." in post.read_text()


def test_readme_has_binder_badge():
    assert "mybinder.org/badge_logo.svg" in (ROOT / "README.md").read_text(encoding="utf-8")


# ---------------------------------------------------------------- CI, pre-commit, lint

def test_ci_workflow_runs_make_test_on_supported_versions():
    wf = yaml.safe_load((ROOT / ".github" / "workflows" / "ci.yml").read_text())
    steps = [s for job in wf["jobs"].values() for s in job["steps"]]
    assert any("make test" in s.get("run", "") for s in steps)
    versions = [str(v) for job in wf["jobs"].values() for v in job["strategy"]["matrix"]["python-version"]]
    assert versions and all(SpecifierSet(PROJECT["requires-python"]).contains(v) for v in versions)


def test_docs_workflow_builds_with_make_docs_and_deploys_the_site():
    """The site's publishing workflow (it cannot run here): valid YAML, builds with make docs from main,
    uploads build/site and deploys it to GitHub Pages, the address the README links to."""
    wf = yaml.safe_load((ROOT / ".github" / "workflows" / "docs.yml").read_text())
    on = wf.get("on", wf.get(True))                 # YAML 1.1 reads a bare `on` key as True
    assert on["push"]["branches"] == ["main"]
    steps = [s for job in wf["jobs"].values() for s in job.get("steps", [])]
    assert any(s.get("run", "").startswith("make docs") for s in steps)
    upload = next(s for s in steps if s.get("uses", "").startswith("actions/upload-pages-artifact"))
    assert upload["with"]["path"] == "build/site"
    assert any(s.get("uses", "").startswith("actions/deploy-pages") for s in steps)
    assert wf["permissions"]["pages"] == "write"
    site = yaml.safe_load((ROOT / "CITATION.cff").read_text(encoding="utf-8"))["url"]
    assert site in (ROOT / "README.md").read_text(encoding="utf-8")


def test_ci_entry_point_calls_make_test_in_a_fresh_clone():
    run = (ROOT / ".ci" / "run").read_text()
    assert "git clone" in run and "make test" in run


def test_pre_commit_config():
    cfg = yaml.safe_load((ROOT / ".pre-commit-config.yaml").read_text())
    hooks = {h["id"]: repo for repo in cfg["repos"] for h in repo["hooks"]}
    assert "ruff-check" in hooks and "strip-notebooks" in hooks
    assert hooks["ruff-check"]["rev"] == "v" + ENV["ruff"], "the pre-commit ruff must be the pinned ruff"


def test_ruff_passes():
    out = subprocess.run([sys.executable, "-m", "ruff", "check", "--no-cache", "."], cwd=ROOT,
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stdout + out.stderr


# ---------------------------------------------------------------- licence and citation

def test_citation_file():
    cff = yaml.safe_load((ROOT / "CITATION.cff").read_text(encoding="utf-8"))
    assert cff["cff-version"] == "1.2.0" and cff["type"] == "software"
    assert str(cff["version"]) == PROJECT["version"] and cff["license"] == "MIT"
    refs = cff["references"]
    assert len(refs) == 5 and all(r["type"] == "article" and r["title"] and r["authors"] for r in refs)
    dois = [r["doi"] for r in refs if "doi" in r]
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert all(d in readme for d in dois), "the README's paper list and CITATION.cff disagree"
