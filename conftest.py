"""Session hooks: tests that share a module-scoped fixture run on one xdist worker; after the notebooks' tests
passed, the README's results section must match.

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

import pytest

ROOT = Path(__file__).resolve().parent

# jsonschema (nbformat's validator, imported by the notebook tests) imports its optional IRI format checker,
# rfc3987_syntax, which builds ~35 Earley parsers: ~1 s in every test worker. The notebook schema has no IRI
# fields; marked absent, jsonschema skips that checker (as tools/reproduce.py does).
sys.modules.setdefault("rfc3987_syntax", None)


@pytest.hookimpl(tryfirst=True)  # before pytest-xdist reads the groups (it appends them to the test ids)
def pytest_collection_modifyitems(config, items):
    """Under ``--dist loadgroup`` (make test), the tests of a module that defines a module- or class-scoped fixture
    share one worker (an ``xdist_group`` named after the module), so that fixture (a whole filter run, a built
    wheel) is computed once per run instead of once on each worker that gets some of the module's tests."""
    for item in items:
        module = getattr(item, "module", None)
        info = getattr(item, "_fixtureinfo", None)
        if module is None or info is None:
            continue
        fixtures = [d for defs in info.name2fixturedefs.values() for d in defs]
        if any(d.scope in ("module", "class") and getattr(d.func, "__module__", None) == module.__name__ for d in fixtures):
            item.add_marker(pytest.mark.xdist_group(module.__name__))


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
