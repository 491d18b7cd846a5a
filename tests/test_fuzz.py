"""The fuzzing harness tools/fuzz.py stays usable (issue 15, item 4): it runs on a small fixed subset and tells
the outcome classes apart. The full run is ``make fuzz``; that its registry tools/fuzz_calls.py lists every public
callable is tests/test_bad_input.py's."""

import json
import sys
import time
from pathlib import Path

import numpy as np
import pytest

TOOLS = Path(__file__).resolve().parents[1] / "tools"
sys.path.insert(0, str(TOOLS))
import fuzz  # noqa: E402

SUBSET = [
    "attitude.quat_to_dcm",
    "attitude.dcm_to_euler",
    "kalman.predict",
    "atmosphere.isa_altitude",
    "trajectory.Segment",
    "analysis.settling_time",
]


def test_by_design_rules_have_reasons_and_match_real_outcomes():
    outcomes = set(fuzz.BAD_CLASSES) | set(fuzz.UNUSUAL_BAD)
    for rule in fuzz.BY_DESIGN:
        assert len(rule) == 5 and rule[4].strip(), rule
        assert any(fuzz.re.fullmatch(rule[3], o) for o in outcomes), f"rule for no bad outcome: {rule[:4]}"


def test_subset_runs_clean_and_writes_the_report(tmp_path, capsys):
    out = tmp_path / "fuzz.json"
    t0 = time.monotonic()
    rc = fuzz.main(["--only", *SUBSET, "--jobs", "2", "--out", str(out)])
    printed = capsys.readouterr().out
    assert rc == 0, printed
    report = json.loads(out.read_text())
    assert report["callables"] == len(SUBSET) and report["calls"] > 100
    assert "bad calls:" in printed and "valid-unusual:" in printed
    assert time.monotonic() - t0 < 120


# The classifier on functions whose behaviour is known.
def _silent(x):
    return np.asarray(x, dtype=float) * 2


def _clean(x):
    x = np.asarray(x, dtype=float)
    if x.shape != (3,) or not np.all(np.isfinite(x)):
        raise ValueError(f"x: expected 3 finite values, got {x!r}")
    return x


def _unnamed(x):
    raise ValueError("something is wrong")


def _crashing(x):
    raise ZeroDivisionError("division by zero")


def _slow(x):
    time.sleep(30)


@pytest.mark.parametrize(
    "func, mutation, outcome",
    [
        (_silent, "nan", "silent_nan"),
        (_silent, "wrong_shape", "silent_accept"),
        (_clean, "nan", "clean"),
        (_clean, "wrong_shape", "clean"),
        (_unnamed, "nan", "unnamed"),
        (_crashing, "nan", "other_exception"),
    ],
    ids=lambda v: getattr(v, "__name__", v),
)
def test_outcomes_are_told_apart(func, mutation, outcome):
    call = fuzz.Call(dict(x=np.array([1.0, 2.0, 3.0])))
    baseline = fuzz.leaves(_silent(call.kwargs["x"]))
    rec = fuzz.run_case(("t.f", "x", mutation), {"t.f": call}, {"t.f": func}, {"t.f": baseline})
    assert rec["outcome"] == outcome


def test_a_call_that_does_not_return_is_a_hang_and_the_run_goes_on():
    call = fuzz.Call(dict(x=np.array([1.0, 2.0, 3.0])))
    table, funcs = {"t.slow": call, "t.clean": call}, {"t.slow": _slow, "t.clean": _clean}
    baselines = {k: fuzz.leaves(np.zeros(3)) for k in table}
    results = fuzz.run_all([("t.slow", "x", "nan"), ("t.clean", "x", "nan")], table, funcs, baselines, 2, timeout=1.0)
    assert [r["outcome"] for r in results] == ["hang", "clean"]


def test_a_float32_variant_that_differs_from_float64_is_reported():
    call = fuzz.Call(dict(x=np.array([0.1, 0.2, 0.3])))

    def keeps_dtype(x):
        x = np.asarray(x)
        return x * x.dtype.type(1.1)  # float32 arithmetic for float32 input

    baseline = fuzz.leaves(keeps_dtype(call.kwargs["x"]))
    rec = fuzz.run_case(("t.f", "x", "float32"), {"t.f": call}, {"t.f": keeps_dtype}, {"t.f": baseline})
    assert rec["outcome"] == "differs"
