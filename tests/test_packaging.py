"""The project's own files: packaging metadata, pins, Binder, CI, lint, licence and citation.

None of the configuration files here can be exercised on this machine (no Binder, no hosted CI),
so these tests check what can be checked: that each file parses, says what it must, and agrees with
the single source of truth for versions, ``environment.txt``.
"""

from __future__ import annotations

import ast
import importlib.metadata as md
import json
import re
import shlex
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
    """Every requirement of pyproject.toml: run time, extras and dependency groups (not an extra naming another)."""
    groups = [PROJECT["dependencies"], *PROJECT["optional-dependencies"].values(), *PYPROJECT["dependency-groups"].values()]
    return [r for r in map(Requirement, (x for g in groups for x in g)) if canonicalize_name(r.name) != PROJECT["name"]]


def extra(name: str) -> set[str]:
    """The distributions an install of ``navlib-repro[name]`` requests directly (run time + the extra, recursively)."""
    out = {canonicalize_name(Requirement(r).name) for r in PROJECT["dependencies"]}
    for r in map(Requirement, PROJECT["optional-dependencies"][name]):
        if canonicalize_name(r.name) == PROJECT["name"]:
            out |= set().union(*map(extra, r.extras))
        else:
            out.add(canonicalize_name(r.name))
    return out


# ---------------------------------------------------------------- metadata and pins


def test_distribution_name_and_metadata():
    assert PROJECT["name"] == "navlib-repro"  # `navlib` on the package index is another project
    assert PROJECT["requires-python"] == ">=3.11"
    assert PROJECT["license"] == "MIT" and (ROOT / "LICENSE").read_text().startswith("MIT License")
    assert set(PROJECT["optional-dependencies"]) == {"plots", "test", "notebooks", "docs", "bench"}
    for key in ("authors", "urls", "classifiers", "readme", "description"):
        assert PROJECT[key], key
    versions = {c.rsplit(":: ", 1)[1] for c in PROJECT["classifiers"] if c.startswith("Programming Language :: Python :: 3.")}
    assert versions and all(SpecifierSet(PROJECT["requires-python"]).contains(v) for v in versions)


def test_package_data_is_shipped():
    assert {"data/*.csv", "py.typed"} <= set(PYPROJECT["tool"]["setuptools"]["package-data"]["navlib"])
    assert (ROOT / "navlib" / "data" / "sensor_presets.csv").is_file() and (ROOT / "navlib" / "py.typed").is_file()


# ---------------------------------------------------------------- one version, release notes, package page


def test_version_is_written_once():
    """navlib.__version__ is the only version; pyproject reads it, CITATION.cff must repeat it."""
    import navlib

    assert "version" not in PROJECT and PROJECT["dynamic"] == ["version"]
    assert PYPROJECT["tool"]["setuptools"]["dynamic"]["version"] == {"attr": "navlib.__version__"}
    assert re.fullmatch(r"\d+\.\d+\.\d+", navlib.__version__)
    cff = yaml.safe_load((ROOT / "CITATION.cff").read_text(encoding="utf-8"))
    assert str(cff["version"]) == navlib.__version__, "CITATION.cff's version is not navlib.__version__"


def test_changelog_follows_keep_a_changelog():
    """An [Unreleased] section first, then released versions newest first, each dated, with the standard
    subsections only, and a link for every version heading."""
    text = (ROOT / "CHANGELOG.md").read_text(encoding="utf-8")
    versions = re.findall(r"^## \[([^\]]+)\](.*)$", text, flags=re.M)
    assert versions and versions[0] == ("Unreleased", ""), "the first section is ## [Unreleased]"
    released = [v for v, _ in versions[1:]]
    for version, date in versions[1:]:
        assert re.fullmatch(r"\d+\.\d+\.\d+", version) and re.fullmatch(r" - \d{4}-\d{2}-\d{2}", date), (version, date)
    assert released == sorted(released, key=lambda v: tuple(map(int, v.split("."))), reverse=True)
    kinds = set(re.findall(r"^### (.+)$", text, flags=re.M))
    assert kinds <= {"Added", "Changed", "Deprecated", "Removed", "Fixed", "Security"}, kinds
    for version, _ in versions:
        assert re.search(rf"^\[{re.escape(version)}\]: https://", text, flags=re.M), f"no link for [{version}]"


PYPI_PAGE = ROOT / PROJECT["readme"]["file"]


def test_package_index_page_is_short_with_absolute_links():
    """The package index renders the readme without the repository: every link and image must be absolute."""
    assert PROJECT["readme"]["content-type"] == "text/markdown"
    text = PYPI_PAGE.read_text(encoding="utf-8")
    assert len(text) < 5000, "the package page is an overview; the README and the site hold the rest"
    targets = re.findall(r"\]\(([^)\s]+)", text) + re.findall(r"<(https?://[^>]+)>", text) + re.findall(r'src="([^"]+)"', text)
    assert targets and all(t.startswith("https://") for t in targets), [t for t in targets if not t.startswith("https://")]
    assert PROJECT["name"] in text and "import" in text


def test_package_index_page_example_runs(tmp_path):
    """The example on the package page runs as written, from a directory outside the checkout."""
    code = re.search(r"```python\n(.*?)```", PYPI_PAGE.read_text(encoding="utf-8"), flags=re.S).group(1)
    out = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True, text=True)
    assert out.returncode == 0, out.stderr


@pytest.mark.parametrize("req", declared(), ids=str)
def test_declared_requirement_is_pinned_and_satisfied(req):
    name = canonicalize_name(req.name)
    version = ENV.get(name) or BENCH.get(name)
    assert version, f"{req.name} is declared in pyproject.toml but pinned in neither environment.txt nor requirements-bench.txt"
    assert req.specifier.contains(version, prereleases=True), f"{req.name}=={version} does not satisfy {req}"


def test_every_top_level_pin_is_declared():
    """Pins that no other pinned package requires are the project's own choices: each must be declared."""
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
            for extra in r.extras:  # e.g. jsonschema[format-nongpl] brings its own pins
                required.update(canonicalize_name(x.name) for x in active(r.name, extra))
    top_level = set(ENV) - required
    missing = top_level - {canonicalize_name(r.name) for r in declared()}
    assert not missing, f"pinned in environment.txt, required by nothing, declared nowhere in pyproject.toml: {sorted(missing)}"


def test_environment_matches_running_interpreter():
    """environment.txt is exact for the Python it is installed with (its header says which)."""
    for name, version in ENV.items():
        assert md.version(name) == version, f"{name}: installed {md.version(name)}, pinned {version} (run `make venv`)"


def imported_distributions(sources: list[str]) -> set[str]:
    """Distributions providing the top-level modules these sources import (standard library and navlib left out)."""
    modules = set()
    for src in sources:
        code = "\n".join(line for line in src.splitlines() if not line.lstrip().startswith(("%", "!")))
        for node in ast.walk(ast.parse(code)):
            if isinstance(node, ast.Import):
                modules |= {a.name.split(".")[0] for a in node.names}
            elif isinstance(node, ast.ImportFrom) and node.level == 0:
                modules.add(node.module.split(".")[0])
    providers = md.packages_distributions()
    third_party = modules - set(sys.stdlib_module_names) - {"navlib"}
    unknown = {m for m in third_party if m not in providers}
    assert not unknown, f"imported but installed by no distribution here: {sorted(unknown)}"
    return {canonicalize_name(d) for m in third_party for d in providers[m]}


def test_notebooks_extra_covers_every_notebook_import():
    """`pip install navlib-repro[notebooks]` must be enough to run every notebook."""
    cells = [
        "".join(c["source"])
        for p in sorted((ROOT / "notebooks").glob("*.ipynb"))
        for c in json.loads(p.read_text(encoding="utf-8"))["cells"]
        if c["cell_type"] == "code"
    ]
    needed = imported_distributions(cells)
    # ipykernel brings IPython; the notebooks display through it.
    missing = needed - extra("notebooks") - {"ipython"}
    assert not missing, f"the notebooks import {sorted(missing)}, which [notebooks] does not declare"
    assert {"ahrs", "imufusion", "pyproj", "matplotlib"} <= needed  # the check cannot pass vacuously


def test_extras_exclude_the_ipykernel_that_hung():
    """environment.txt's header: ipykernel 7 hung `make reproduce`. No extra may resolve to it."""
    assert "7.x hung make reproduce" in (ROOT / "environment.txt").read_text(encoding="utf-8")
    for group, reqs in PROJECT["optional-dependencies"].items():
        for r in map(Requirement, reqs):
            if canonicalize_name(r.name) == "ipykernel":
                assert not r.specifier.contains("7.0") and not r.specifier.contains("7.4"), f"[{group}] allows ipykernel 7"


def test_matplotlib_is_an_extra():
    """Library users need no plotting stack (tests/test_package.py imports every module without it)."""
    assert "matplotlib" not in {canonicalize_name(Requirement(r).name) for r in PROJECT["dependencies"]}
    assert "matplotlib" in extra("plots") and extra("plots") <= extra("notebooks") <= extra("test")


# ---------------------------------------------------------------- Binder


def test_binder_pins_agree_with_environment():
    """Binder runs the notebooks: its pins are environment.txt's (contributor tools may be left out), and every
    package of `[notebooks]` is there."""
    binder = ROOT / "binder"
    binder_pins = pins(binder / "requirements.txt")
    differ = {name for name, version in binder_pins.items() if ENV.get(name) != version}
    assert not differ, f"binder/requirements.txt and environment.txt differ for {sorted(differ)}"
    assert extra("notebooks") <= set(binder_pins)
    runtime = (binder / "runtime.txt").read_text().strip()
    assert re.fullmatch(r"python-3\.\d+", runtime) and SpecifierSet(PROJECT["requires-python"]).contains(runtime[7:])
    post = binder / "postBuild"
    assert post.stat().st_mode & 0o111, "binder/postBuild must be executable"
    assert "pip install --no-deps ." in post.read_text()


def test_readme_has_binder_badge():
    assert "mybinder.org/badge_logo.svg" in (ROOT / "README.md").read_text(encoding="utf-8")


# ---------------------------------------------------------------- CI, pre-commit, lint

WORKFLOWS = {p.name: yaml.safe_load(p.read_text(encoding="utf-8")) for p in (ROOT / ".github" / "workflows").glob("*.yml")}


def steps(wf: dict) -> list[dict]:
    return [s for job in wf["jobs"].values() for s in job.get("steps", [])]


def on(wf: dict) -> dict:
    return wf.get("on", wf.get(True))  # YAML 1.1 reads a bare `on` key as True


def nox_sessions() -> set[str]:
    return set(re.findall(r"^def (\w+)\(session", (ROOT / "noxfile.py").read_text(encoding="utf-8"), flags=re.M))


def test_ci_runs_nox_sessions_on_three_systems_and_at_the_bounds():
    """Pinned on Linux, macOS and Windows for every supported Python; latest and lowest versions; build; lint;
    typecheck (mypy at the configured level)."""
    wf = WORKFLOWS["ci.yml"]
    pinned = wf["jobs"]["pinned"]["strategy"]["matrix"]
    assert set(pinned["os"]) == {"ubuntu-latest", "macos-latest", "windows-latest"}
    classifiers = {c.rsplit(":: ", 1)[1] for c in PROJECT["classifiers"] if c.startswith("Programming Language :: Python :: 3.")}
    assert set(pinned["python"]) == classifiers
    runs = " ".join(s.get("run", "") for s in steps(wf))
    assert "make" not in runs.split(), "CI calls nox sessions, not the POSIX Makefile"
    sessions = {*wf["jobs"]["bounds"]["strategy"]["matrix"]["session"], *wf["jobs"]["checks"]["strategy"]["matrix"]["session"]}
    assert sessions == {"tests_latest", "tests_min", "build", "lint", "typecheck"} and sessions | {"tests"} <= nox_sessions()
    assert f"nox=={ENV['nox']}" in wf["env"]["NOX"], "CI's nox is the pinned nox"


def test_ci_caches_what_the_installer_uses():
    """uv makes every environment, so uv's cache is the one cached (setup-python's `cache: pip` would not apply)."""
    for name, wf in WORKFLOWS.items():
        for step in steps(wf):
            assert "cache" not in step.get("with", {}) or not step["uses"].startswith("actions/setup-python"), name
            if step.get("uses", "").startswith("astral-sh/setup-uv") and name == "ci.yml":
                assert step["with"]["enable-cache"] is True


def test_actions_are_pinned_and_least_privileged():
    """What zizmor checks offline (`nox -s lint`): actions pinned by commit, no workflow-wide write permission,
    no checkout credentials left on disk."""
    for name, wf in WORKFLOWS.items():
        assert "permissions" in wf, f"{name}: no top-level permissions block"
        assert all(v in ("read", "none") for v in (wf["permissions"] or {}).values()), f"{name}: write permission for every job"
        for step in steps(wf):
            if "uses" in step:
                pinned = re.fullmatch(r"[\w.-]+/[\w./-]+@[0-9a-f]{40}", step["uses"])
                assert pinned, f"{name}: {step['uses']} is not pinned by commit"
            if step.get("uses", "").startswith("actions/checkout"):
                assert step["with"]["persist-credentials"] is False, f"{name}: checkout persists credentials"
    dependabot = yaml.safe_load((ROOT / ".github" / "dependabot.yml").read_text(encoding="utf-8"))
    assert [u["package-ecosystem"] for u in dependabot["updates"]] == ["github-actions"]


def test_publish_workflow_uses_trusted_publishing_on_version_tags():
    """It cannot run here: a version tag triggers it, the tag must match the version everywhere, the
    distributions are built and checked by `nox -s build`, and only the upload job may mint an OIDC token,
    in the `pypi` environment, with no stored password."""
    wf = WORKFLOWS["publish.yml"]
    assert on(wf) == {"push": {"tags": ["v*"]}} and wf["permissions"] == {}
    build, publish = wf["jobs"]["build"], wf["jobs"]["publish"]
    assert build["permissions"] == {"contents": "read"}
    check = next(s["run"] for s in build["steps"] if "navlib/__init__.py" in s.get("run", ""))
    assert "CITATION.cff" in check and "CHANGELOG.md" in check and "$TAG" in check
    assert any(f'"nox=={ENV["nox"]}" nox -s build' in s.get("run", "") for s in build["steps"]), "the pinned nox builds"
    assert publish["needs"] == "build" and publish["environment"]["name"] == "pypi"
    assert publish["permissions"] == {"id-token": "write"}
    upload = publish["steps"][-1]
    assert upload["uses"].startswith("pypa/gh-action-pypi-publish@") and not upload.get("with", {}).get("password")
    session = (ROOT / "noxfile.py").read_text(encoding="utf-8").split("def build(", 1)[1].split("@nox.session", 1)[0]
    assert '"twine", "check", "--strict"' in session and '"check-manifest"' in session


def test_docs_workflow_builds_with_make_docs_and_deploys_the_site():
    """The site's publishing workflow (it cannot run here): valid YAML, builds with make docs from main,
    uploads build/site and deploys it to GitHub Pages, the address the README links to."""
    wf = WORKFLOWS["docs.yml"]
    assert on(wf)["push"]["branches"] == ["main"]
    assert any(s.get("run", "").startswith("make docs") for s in steps(wf))
    upload = next(s for s in steps(wf) if s.get("uses", "").startswith("actions/upload-pages-artifact"))
    assert upload["with"]["path"] == "build/site"
    assert any(s.get("uses", "").startswith("actions/deploy-pages") for s in wf["jobs"]["deploy"]["steps"])
    assert wf["jobs"]["deploy"]["permissions"]["pages"] == "write"
    site = yaml.safe_load((ROOT / "CITATION.cff").read_text(encoding="utf-8"))["url"]
    assert site in (ROOT / "README.md").read_text(encoding="utf-8")


def test_ci_entry_point_calls_make_test_in_a_fresh_clone():
    run = (ROOT / ".ci" / "run").read_text()
    assert "git clone" in run and "make test" in run


def test_pre_commit_hooks_are_local():
    """Every hook runs a tool pinned in environment.txt (nothing to clone: pre-commit works offline), and the
    notebook stripper has the flags of `make strip`."""
    cfg = yaml.safe_load((ROOT / ".pre-commit-config.yaml").read_text(encoding="utf-8"))
    assert [r["repo"] for r in cfg["repos"]] == ["local"]
    hooks = {h["id"]: h for h in cfg["repos"][0]["hooks"]}
    assert {"ruff-check", "ruff-format", "nbstripout", "zizmor"} <= set(hooks)
    for hook in hooks.values():
        assert hook["language"] == "system" and "additional_dependencies" not in hook, hook["id"]
        tool = hook["entry"].split()[0]
        dist = {
            "check-yaml": "pre-commit-hooks",
            "check-toml": "pre-commit-hooks",
            "end-of-file-fixer": "pre-commit-hooks",
            "check-added-large-files": "pre-commit-hooks",
        }.get(tool, tool)
        assert canonicalize_name(dist) in ENV, f"{hook['id']}: {dist} is not pinned in environment.txt"
    flags = re.search(r"^NBSTRIPOUT_FLAGS := (.*)$", (ROOT / "Makefile").read_text(encoding="utf-8"), flags=re.M).group(1)
    assert hooks["nbstripout"]["entry"] == f"nbstripout {flags}"


def test_committed_notebooks_are_stripped_as_the_hook_strips():
    out = subprocess.run(
        [
            sys.executable,
            "-m",
            "nbstripout",
            "--verify",
            *shlex.split(
                re.search(r"^NBSTRIPOUT_FLAGS := (.*)$", (ROOT / "Makefile").read_text(encoding="utf-8"), flags=re.M).group(1)
            ),
            *map(str, sorted((ROOT / "notebooks").glob("*.ipynb"))),
        ],
        capture_output=True,
        text=True,
    )
    assert out.returncode == 0, "run `make strip`: " + out.stdout + out.stderr


def test_ruff_passes():
    out = subprocess.run([sys.executable, "-m", "ruff", "check", "--no-cache", "."], cwd=ROOT, capture_output=True, text=True)
    assert out.returncode == 0, out.stdout + out.stderr


# ---------------------------------------------------------------- licence and citation


def test_citation_file():
    cff = yaml.safe_load((ROOT / "CITATION.cff").read_text(encoding="utf-8"))
    assert cff["cff-version"] == "1.2.0" and cff["type"] == "software"
    assert cff["license"] == "MIT"  # its version: test_version_is_written_once
    refs = cff["references"]
    assert len(refs) == 5 and all(r["type"] == "article" and r["title"] and r["authors"] for r in refs)
    dois = [r["doi"] for r in refs if "doi" in r]
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert all(d in readme for d in dois), "the README's paper list and CITATION.cff disagree"
