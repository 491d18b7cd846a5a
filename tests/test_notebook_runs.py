"""Every numbered notebook runs to the end with every check passing, executed once per ``make test``.

``tools/reproduce.py --stale`` (run by ``make test`` before pytest) executes every notebook whose execution
into build/ is missing, failed or out of date, and :func:`test_notebook_runs` reads the record of that
execution (``build/<stem>.run.json``). A record is used only while it stands: the digest of the notebook,
navlib/, data/, the runner and the installed packages is the one it ran with, and its executed notebook,
results and figures in build/ are the ones it wrote; otherwise (a plain ``pytest`` after an edit, say) the
test executes the notebook itself (``tests/test_reproduce_tool.py`` tests that rule).
"""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
NUMBERED = sorted((ROOT / "notebooks").glob("[0-9][0-9]_*.ipynb"))


@pytest.mark.parametrize("path", NUMBERED, ids=[p.stem for p in NUMBERED])
def test_notebook_runs(path):
    sys.path.insert(0, str(ROOT / "tools"))
    import reproduce  # tools/reproduce.py

    entry = reproduce.executed(path)
    assert entry["error"] is None, f"{path.name} stopped: {entry['error']} (see build/{path.stem}.ipynb)"
    failed = [c["name"] for c in entry["checks"] if not c.get("passed")]
    assert not failed, f"{path.name}: {len(failed)} failed checks: {', '.join(failed)}"


def test_the_records_digest_names_every_installed_package_version():
    """The execution records' digest reads the installed packages from their folders' names (not every METADATA file):
    the same packages and versions as importlib.metadata finds, so that an upgrade makes every record stale."""
    import importlib.metadata
    import re

    sys.path.insert(0, str(ROOT / "tools"))
    import reproduce

    def normal(name: str, version: str) -> str:
        return f"{re.sub(r'[-_.]+', '_', name).lower()}=={version}"

    expected = {normal(d.metadata["Name"], d.version) for d in importlib.metadata.distributions()}
    assert {normal(*d.split("==")) for d in reproduce.installed_distributions()} == expected
