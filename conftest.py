"""Session hook: after notebooks ran under nbmake, the README's results section must match.

Each notebook writes ``build/<notebook>/results.json``; ``tools/readme.py``
turns those into the README's results section (claims by verdict, the per-paper
matrices) and the numbers its prose quotes. When a pytest session executed
notebooks and they all passed, this hook re-renders the parts of the notebooks
that ran and fails the session if the committed README disagrees
(run ``make readme`` and commit). Enabled by ``make test`` (NAVLIB_CHECK_README=1),
so a developer running one notebook by hand is not stopped by it.
"""

import os
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent
_START = time.time()


# Tests that write the same build/ folder must not run at the same time on two pytest-xdist
# workers (`make test` runs `-n 2 --dist loadgroup`): the isolation test executes notebook 03 too.
_SHARED_BUILD = {"03_gauss_kruger_ekf.ipynb": "notebook-03", "test_isolation.py": "notebook-03"}


def pytest_collection_modifyitems(config, items):
    for item in items:
        group = _SHARED_BUILD.get(item.path.name)
        if group:
            item.add_marker(pytest.mark.xdist_group(group))


def pytest_sessionfinish(session, exitstatus):
    if hasattr(session.config, "workerinput"):  # an xdist worker: the controller checks
        return
    if exitstatus != 0 or os.environ.get("NAVLIB_CHECK_README") != "1":  # set by `make test`
        return
    sys.path.insert(0, str(ROOT / "tools"))
    import readme

    build = ROOT / "build"
    fresh = {p.parent.name for p in build.glob("*/results.json") if p.stat().st_mtime >= _START}
    if not fresh:
        return
    stale = readme.stale((ROOT / "README.md").read_text(encoding="utf-8"), build, fresh)
    if stale:
        print(f"\nREADME is stale ({'; '.join(stale)}): run `make readme` and commit README.md", file=sys.stderr)
        session.exitstatus = 1
