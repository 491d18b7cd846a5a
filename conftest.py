"""Session hooks: how make test's two xdist workers share the tests (:func:`pytest_xdist_make_scheduler`); after
the notebooks' tests passed, the README's results section must match.

Each notebook writes ``build/<notebook>/results.json``; ``tools/readme.py``
turns those into the README's results section (claims by verdict, the per-paper
matrices) and the numbers its prose quotes. When a pytest session passed, this hook
re-renders the parts of the notebooks whose execution into build/ is up to date and
passed (``tools/reproduce.py``'s record of it, as ``tests/test_notebook_runs.py`` uses it)
and fails the session if the committed README disagrees (run ``make readme`` and
commit). Enabled by ``make test`` (NAVLIB_CHECK_README=1), so a developer running
one notebook by hand is not stopped by it.
"""

import math
import os
import re
import sys
from collections import OrderedDict
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent

# jsonschema (nbformat's validator, imported by the notebook tests) imports its optional IRI format checker,
# rfc3987_syntax, which builds ~35 Earley parsers: ~1 s in every test worker. The notebook schema has no IRI
# fields; marked absent, jsonschema skips that checker (as tools/reproduce.py does).
sys.modules.setdefault("rfc3987_syntax", None)


SHARED_FIXTURE = re.compile(r"@pytest\.fixture\(scope=\"(module|class)\"")
DURATIONS = "navlib/test-seconds"  # pytest's cache key: each test's seconds in the last run (setup + call + teardown)


@pytest.hookimpl(tryfirst=True)
def pytest_xdist_make_scheduler(config, log):
    """``--dist loadgroup`` (make test), scheduled by this project's rule, because pytest-xdist 3.8 cannot group
    under pytest 9.2 (it renames ``item._nodeid``, which pytest no longer reads): the tests of a file that defines a
    module- or class-scoped fixture (a whole filter run, a built wheel) go to one worker, which computes that fixture
    once instead of once per worker; every other test is a unit of its own. Units start longest first by the last
    run's times (the longest-processing-time rule), so no worker is left idle behind a long test at the end; a unit
    with a test never timed (new, or skipped so far: the site's before `make docs`) starts first, as if longest."""
    if config.getvalue("dist") != "loadgroup":
        return None
    from xdist.scheduler import LoadScopeScheduling

    shared = {
        path.relative_to(ROOT).as_posix()
        for path in (ROOT / "tests").rglob("test_*.py")
        if SHARED_FIXTURE.search(path.read_text(encoding="utf-8"))
    }
    cache = getattr(config, "cache", None)  # absent under -p no:cacheprovider
    last = cache.get(DURATIONS, {}) if cache else {}

    def expected_seconds(nodeids) -> float:
        return sum(last[i] for i in nodeids) if all(i in last for i in nodeids) else math.inf

    class Scheduling(LoadScopeScheduling):
        def _split_scope(self, nodeid):
            file = nodeid.split("::", 1)[0]
            return file if file in shared else nodeid

        # The units, longest first. Reordered where xdist stores them: a worker runs the tests whose indices in its
        # own collection it is sent, so the collections themselves must keep pytest's order.
        @property
        def workqueue(self):
            return self._units

        @workqueue.setter
        def workqueue(self, units):
            self._units = OrderedDict(sorted(units.items(), key=lambda unit: -expected_seconds(unit[1])))

    config.option.loadscopereorder = False  # the order above, not the number of tests per unit
    return Scheduling(config, log)


_seconds: dict[str, float] = {}  # this run's, per test (the controller receives every worker's reports)
_skipped: set[str] = set()  # not timed: a skipped test's few milliseconds say nothing of its next run


def pytest_runtest_logreport(report):
    _seconds[report.nodeid] = _seconds.get(report.nodeid, 0.0) + report.duration
    if report.skipped:
        _skipped.add(report.nodeid)


def pytest_sessionfinish(session, exitstatus):
    if hasattr(session.config, "workerinput"):  # an xdist worker: the controller checks
        return
    cache = getattr(session.config, "cache", None)
    if cache and _seconds:  # the next run's plan (tests not run or skipped this time keep their last time, if any)
        cache.set(DURATIONS, cache.get(DURATIONS, {}) | {i: s for i, s in _seconds.items() if i not in _skipped})
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
