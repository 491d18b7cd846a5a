"""Session hook: after the notebooks' tests passed, the README's results section must match.

Each notebook writes ``build/<notebook>/results.json``; ``tools/readme.py``
turns those into the README's results section (claims by verdict, the per-paper
matrices) and the numbers its prose quotes. When a pytest session passed, this hook
re-renders the parts of the notebooks whose execution into build/ is up to date and
passed (``tools/reproduce.py``'s record of it, as ``tests/test_notebook_runs.py`` uses it)
and fails the session if the committed README disagrees (run ``make readme`` and
commit). Enabled by ``make test`` (NAVLIB_CHECK_README=1), so a developer running
one notebook by hand is not stopped by it.
"""

import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent


def pytest_sessionfinish(session, exitstatus):
    if hasattr(session.config, "workerinput"):  # an xdist worker: the controller checks
        return
    if exitstatus != 0 or os.environ.get("NAVLIB_CHECK_README") != "1":  # set by `make test`
        return
    sys.path.insert(0, str(ROOT / "tools"))
    import readme
    import reproduce

    build = ROOT / "build"
    notebooks = sorted((ROOT / "notebooks").glob("[0-9][0-9]_*.ipynb"))
    fresh = {p.stem for p in notebooks if (reproduce.last_execution(p, build)[0] or {}).get("ok")}
    if not fresh:
        return
    stale = readme.stale((ROOT / "README.md").read_text(encoding="utf-8"), build, fresh)
    if stale:
        print(f"\nREADME is stale ({'; '.join(stale)}): run `make readme` and commit README.md", file=sys.stderr)
        session.exitstatus = 1
