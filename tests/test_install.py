"""A non-editable install works on its own (issue: a newcomer's clone works).

``pip install .`` of this checkout into a fresh virtual environment (dependencies pinned by
environment.txt), then ``tests/data/installed_smoke.py`` runs with
that environment's Python from an empty directory outside the checkout: core API, sensor presets
shipped as package data, a filter, and repro's refusal to write beside the installed package.
Needs the package index (or the installer's cache) during set-up only.

The installer is ``uv pip`` (pinned in environment.txt) when it is on the path beside this Python:
the same PEP 517 build and non-editable install as ``pip install .``, in about 5 s instead of about
60 s with a warm cache. Without uv it falls back to pip.
"""
from __future__ import annotations

import os
import shutil
import subprocess
import sys
import venv
from pathlib import Path

import pytest
from helpers import project_files

ROOT = Path(__file__).resolve().parents[1]
SMOKE = ROOT / "tests" / "data" / "installed_smoke.py"


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    env_dir = tmp_path_factory.mktemp("fresh") / "venv"
    uv = shutil.which("uv", path=str(Path(sys.executable).parent))
    venv.create(env_dir, with_pip=uv is None)
    py = env_dir / "bin" / "python"
    # A copy of the checkout's tracked files, so nothing the build writes (build/, *.egg-info) lands
    # in the checkout and untracked local files cannot leak into the wheel.
    src = tmp_path_factory.mktemp("src")
    for path in project_files():
        (src / path.relative_to(ROOT)).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(path, src / path.relative_to(ROOT))
    pip = ([uv, "pip", "install", "--quiet", "--python", str(py)] if uv else
           [str(py), "-m", "pip", "install", "--quiet", "--disable-pip-version-check"])
    subprocess.run([*pip, "-c", str(ROOT / "environment.txt"), str(src)], check=True)
    return py


def test_non_editable_install_runs_outside_checkout(installed, tmp_path):
    work = tmp_path / "elsewhere"
    work.mkdir()
    env = {k: v for k, v in os.environ.items() if k not in ("NAVLIB_ROOT", "PYTHONPATH")}
    out = subprocess.run([str(installed), str(SMOKE)], cwd=work, env=env, capture_output=True, text=True)
    assert out.returncode == 0, out.stdout + out.stderr
    assert out.stdout.rstrip().endswith("ok"), out.stdout
    assert not any(work.iterdir()), "the smoke run wrote into its working directory"


def test_installed_distribution_metadata(installed):
    code = ("import importlib.metadata as m; d = m.distribution('navlib-repro'); "
            "print(d.version, d.metadata['Requires-Python'], sorted(set(d.metadata.get_all('Provides-Extra'))))")
    out = subprocess.run([str(installed), "-c", code], capture_output=True, text=True, check=True).stdout.split(maxsplit=2)
    assert out[0] == "0.1.0" and out[1] == ">=3.11"
    assert out[2].strip() == "['bench', 'docs', 'notebooks', 'test']"
