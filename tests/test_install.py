"""The distributions as they would be published: built, checked, installed and tested away from the checkout.

From a copy of the checkout's tracked files: the sdist is built, then the wheel from the unpacked sdist
(as ``python -m build`` and the publish workflow do); ``twine check --strict`` passes both; the sdist holds
exactly the tracked files (what check-manifest compares); the wheel holds the package, its data and
``py.typed``. The wheel goes into a fresh virtual environment (dependencies pinned by environment.txt):
without extras navlib imports and runs with no matplotlib; with ``[plots]`` ``tests/data/installed_smoke.py``
runs from an empty directory outside the checkout. The sdist's own tests are collected and a sample run
from the unpacked archive; that run is recorded (``build/install/sdist-tests.json``) with the digest of what it
depends on (every file of the sdist, the Python, the installed packages, the environment, this file) and read
instead of run again while that is unchanged and it passed. Needs the package index (or the installer's cache)
during set-up only.

The builder and installer are ``uv`` (pinned in environment.txt) when it is on the path beside this Python:
the same PEP 517 build and non-editable install as ``python -m build`` and ``pip install``, in seconds.
Without uv they fall back to ``python -m build`` and pip.
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import subprocess
import sys
import tarfile
import venv
import zipfile
from pathlib import Path

import pytest
from helpers import project_files

import navlib

ROOT = Path(__file__).resolve().parents[1]
SMOKE = ROOT / "tests" / "data" / "installed_smoke.py"
UV = shutil.which("uv", path=str(Path(sys.executable).parent))
CLEAN_ENV = {k: v for k, v in os.environ.items() if k not in ("NAVLIB_ROOT", "PYTHONPATH")}


@pytest.fixture(scope="module")
def dist(tmp_path_factory) -> dict[str, Path]:
    """sdist and wheel built from a copy of the tracked files (nothing the build writes lands in the checkout)."""
    src = tmp_path_factory.mktemp("src")
    for path in project_files():
        (src / path.relative_to(ROOT)).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(path, src / path.relative_to(ROOT))
    out = tmp_path_factory.mktemp("dist")
    build = [UV, "build", "--quiet"] if UV else [sys.executable, "-m", "build"]
    subprocess.run([*build, "--out-dir" if UV else "--outdir", str(out), str(src)], check=True, capture_output=True)
    files = {p.suffix: p for p in out.iterdir()}
    return {"sdist": files[".gz"], "wheel": files[".whl"]}


@pytest.fixture(scope="module")
def installed(dist, tmp_path_factory):
    env_dir = tmp_path_factory.mktemp("fresh") / "venv"
    venv.create(env_dir, with_pip=UV is None)
    py = env_dir / ("Scripts/python.exe" if os.name == "nt" else "bin/python")
    pip = (
        [UV, "pip", "install", "--quiet", "--python", str(py)]
        if UV
        else [str(py), "-m", "pip", "install", "--quiet", "--disable-pip-version-check"]
    )
    subprocess.run([*pip, "-c", str(ROOT / "environment.txt"), str(dist["wheel"])], check=True)
    return py, pip


def test_twine_check_strict(dist):
    out = subprocess.run(
        [sys.executable, "-m", "twine", "check", "--strict", str(dist["sdist"]), str(dist["wheel"])],
        capture_output=True,
        text=True,
    )
    assert out.returncode == 0, out.stdout + out.stderr


def test_sdist_holds_exactly_the_tracked_files(dist):
    """The check-manifest comparison: every file in version control is in the sdist, and nothing else but the
    metadata the build adds. CITATION.cff, LICENSE, the tests and their data are in it."""
    with tarfile.open(dist["sdist"]) as tar:
        names = {m.name.split("/", 1)[1] for m in tar.getmembers() if m.isfile()}
    added = {n for n in names if n in ("PKG-INFO", "setup.cfg") or ".egg-info/" in n}
    tracked = {p.relative_to(ROOT).as_posix() for p in project_files()}
    assert names - added == tracked, (sorted(tracked - names), sorted(names - added - tracked))
    assert {"CITATION.cff", "LICENSE", "tests/conftest.py", "tests/helpers.py", "conftest.py"} <= names


def test_wheel_holds_the_package_only(dist):
    names = zipfile.ZipFile(dist["wheel"]).namelist()
    assert {"navlib/__init__.py", "navlib/py.typed", "navlib/data/sensor_presets.csv"} <= set(names)
    assert all(n.startswith(("navlib/", "navlib_repro-")) for n in names), [n for n in names if not n.startswith("navlib")]
    assert not [n for n in names if "__pycache__" in n or n.endswith((".pyc", ".nbi", ".nbc"))]
    assert f"navlib_repro-{navlib.__version__}-py3-none-any.whl" == dist["wheel"].name


def test_runs_without_the_plots_extra(installed, tmp_path):
    py, _ = installed
    code = (
        "import importlib.util, numpy as np, navlib; from navlib.filters import mahony; from navlib.imu import ImuSamples; "
        "assert importlib.util.find_spec('matplotlib') is None, 'matplotlib was installed without [plots]'; "
        "n = 50; f = np.tile([0.0, 0.0, 9.8], (n, 1)); "
        "res = mahony.mahony(ImuSamples(np.zeros((n, 3)), f, 0.01), np.array([1.0, 0, 0, 0])); "
        "assert np.all(np.isfinite(res.q_bn)); print(navlib.__version__)"
    )
    out = subprocess.run([str(py), "-c", code], cwd=tmp_path, env=CLEAN_ENV, capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == navlib.__version__


def test_non_editable_install_runs_outside_checkout(installed, dist, tmp_path):
    py, pip = installed
    subprocess.run([*pip, "-c", str(ROOT / "environment.txt"), f"{dist['wheel']}[plots]"], check=True)
    work = tmp_path / "elsewhere"
    work.mkdir()
    out = subprocess.run([str(py), str(SMOKE)], cwd=work, env=CLEAN_ENV, capture_output=True, text=True)
    assert out.returncode == 0, out.stdout + out.stderr
    assert out.stdout.rstrip().endswith("ok"), out.stdout
    assert not any(work.iterdir()), "the smoke run wrote into its working directory"


TYPED_USER_SCRIPT = """
import numpy as np
from navlib.filters.mahony import mahony
from navlib.imu import ImuSamples

imu = ImuSamples(np.zeros((50, 3)), np.tile([0.0, 0.0, 9.8], (50, 1)), 0.01)
res = mahony(imu, np.array([1.0, 0.0, 0.0, 0.0]))
reveal_type(res)
reveal_type(res.q_bn)
res.q_nb
"""


def test_user_script_type_checks_against_the_installed_package(installed, tmp_path):
    """A user's ``mypy --strict`` sees the installed navlib's annotations (py.typed): the filter's result is an
    ``AttitudeResult`` whose ``q_bn`` is a float64 ndarray (what an editor completes), and a misspelt field is an error
    rather than ``Any``. The checker is this environment's mypy, reading the fresh venv's site-packages."""
    pytest.importorskip("mypy.api")
    py, _ = installed
    script, config = tmp_path / "user.py", tmp_path / "empty.ini"
    script.write_text(TYPED_USER_SCRIPT, encoding="utf-8")
    config.write_text("[mypy]\n", encoding="utf-8")
    argv = ["--strict", "--python-executable", str(py), "--config-file", str(config), "--cache-dir", str(tmp_path / "cache")]
    out = subprocess.run(
        [sys.executable, "-m", "mypy", *argv, str(script)], cwd=tmp_path, env=CLEAN_ENV, capture_output=True, text=True
    ).stdout
    assert 'Revealed type is "navlib.filters.observations.AttitudeResult"' in out, out
    assert 'Revealed type is "numpy.ndarray[tuple[Any, ...], numpy.dtype[numpy.float64]]"' in out, out
    assert 'error: "AttitudeResult" has no attribute "q_nb"' in out, out
    assert out.rstrip().endswith("Found 1 error in 1 file (checked 1 source file)"), out


def test_installed_distribution_metadata(installed):
    py, _ = installed
    code = (
        "import importlib.metadata as m; d = m.distribution('navlib-repro'); "
        "print(d.version, d.metadata['Requires-Python'], sorted(set(d.metadata.get_all('Provides-Extra'))))"
    )
    out = subprocess.run([str(py), "-c", code], capture_output=True, text=True, check=True).stdout.split(maxsplit=2)
    assert out[0] == navlib.__version__ and out[1] == ">=3.11"
    assert out[2].strip() == "['bench', 'docs', 'notebooks', 'plots', 'test']"


SDIST_RECORD = ROOT / "build" / "install" / "sdist-tests.json"
SAMPLE = ["test_units.py", "test_notebooks.py", "test_ledger.py", "test_self_contained.py"]


def sdist_inputs(sdist: Path) -> str:
    """SHA-256 of what the unpacked sdist's test run depends on: the name and content of every file in it, the Python,
    the installed packages (as tools/reproduce.py lists them for its records), the environment's NAVLIB_, NUMBA_ and
    PYTHON variables and this file."""
    sys.path.insert(0, str(ROOT / "tools"))
    import reproduce  # tools/reproduce.py

    env = sorted((k, v) for k, v in CLEAN_ENV.items() if k.startswith(("NAVLIB_", "NUMBA_", "PYTHON")))
    digest = hashlib.sha256(f"{sys.version} {reproduce.installed_distributions()} {env}".encode())
    digest.update(Path(__file__).read_bytes())
    with tarfile.open(sdist) as tar:
        for member in sorted((m for m in tar.getmembers() if m.isfile()), key=lambda m: m.name):
            digest.update(f"\n{member.name} {hashlib.sha256(tar.extractfile(member).read()).hexdigest()}".encode())
    return digest.hexdigest()


def sdist_tests(sdist: Path, tmp_path: Path) -> dict:
    """Unpack the sdist, say where its navlib is imported from, collect all its tests and run the sample."""
    with tarfile.open(sdist) as tar:
        tar.extractall(tmp_path, filter="data")
    unpacked = next(tmp_path.iterdir())
    env = {**CLEAN_ENV, "PYTHONPATH": str(unpacked), "NUMBA_DISABLE_JIT": "1"}
    where = subprocess.run(
        [sys.executable, "-c", "import navlib; print(navlib.__file__)"],
        cwd=unpacked,
        env=env,
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    # One pytest run: every test collected (an error collecting any file fails it), the sample run; nbmake not loaded
    pytest_ = [sys.executable, "-m", "pytest", "-p", "no:cacheprovider", "-p", "no:nbmake", "-n", "0", "-q", "-rN"]
    run = subprocess.run([*pytest_, "tests", "-k", " or ".join(SAMPLE)], cwd=unpacked, env=env, capture_output=True, text=True)
    return {
        "navlib_from_unpacked": Path(where.strip()).is_relative_to(unpacked),
        "navlib": where.strip(),
        "returncode": run.returncode,
        "last_line": (run.stdout.splitlines() or [""])[-1],
        "output": run.stdout[-3000:] + run.stderr[-3000:],
    }


def test_sdist_tests_run_unpacked(dist, tmp_path):
    """The unpacked sdist's tests import the sdist's navlib: all of them collect, and a sample reading the data,
    notebooks and ledger passes. Plain Python kernels (NUMBA_DISABLE_JIT): compiling them for a copy of navlib
    would double the cost of collecting. Read from its record while its inputs are unchanged and it passed."""
    inputs = sdist_inputs(dist["sdist"])
    record = json.loads(SDIST_RECORD.read_text()) if SDIST_RECORD.is_file() else {}
    if record.get("inputs") != inputs or record.get("returncode") != 0:
        record = {"inputs": inputs, **sdist_tests(dist["sdist"], tmp_path)}
        SDIST_RECORD.parent.mkdir(parents=True, exist_ok=True)
        SDIST_RECORD.write_text(json.dumps(record, indent=1) + "\n")
    assert record["navlib_from_unpacked"], record["navlib"]
    assert record["returncode"] == 0, record["output"]
    assert " deselected" in record["last_line"], record["output"]  # the rest was collected, not run
