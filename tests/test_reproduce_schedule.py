"""tools/reproduce.py's notebook order: the submission order that finishes first by the last run's times."""
import itertools
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tools"))
reproduce = pytest.importorskip("reproduce")  # tools/reproduce.py (needs nbclient)


def test_makespan_of_a_list_schedule():
    assert reproduce.makespan([3.0, 2.0, 2.0], 2) == 4.0       # 3 | 2 + 2
    assert reproduce.makespan([2.0, 2.0, 3.0], 2) == 5.0       # 2 + 3 | 2
    assert reproduce.makespan([1.0, 1.0], 1) == 2.0


def test_schedule_beats_longest_first_and_is_optimal_for_seven_notebooks():
    seconds = dict(zip((Path(f"{i:02d}") for i in range(7)), (14.0, 24.1, 30.7, 12.4, 18.2, 23.4, 10.5), strict=True))
    order = reproduce.schedule(list(seconds), seconds, 2)
    assert sorted(order) == sorted(seconds)
    span = reproduce.makespan([seconds[p] for p in order], 2)
    longest_first = reproduce.makespan(sorted(seconds.values(), reverse=True), 2)
    best = min(reproduce.makespan(list(o), 2) for o in itertools.permutations(seconds.values()))
    assert span == best == pytest.approx(66.8) and longest_first == pytest.approx(71.8)


def test_schedule_without_times_or_with_one_worker_is_longest_first():
    paths = [Path("a"), Path("b"), Path("c")]
    assert reproduce.schedule(paths, {p: 0.0 for p in paths}, 2) == paths
    assert reproduce.schedule(paths, {Path("a"): 1.0, Path("b"): 3.0, Path("c"): 2.0}, 1) == [paths[1], paths[2], paths[0]]


def test_a_warm_run_is_planned_without_the_last_runs_compilation():
    summary = {"00_a": {"seconds": 50.0, "compile_seconds": 30.0}, "01_b": {"seconds": 25.0}}
    paths = [Path("00_a.ipynb"), Path("01_b.ipynb"), Path("02_new.ipynb")]
    assert reproduce.expected_seconds(summary, paths) == {paths[0]: 20.0, paths[1]: 25.0, paths[2]: 0.0}
