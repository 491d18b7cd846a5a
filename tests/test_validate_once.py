"""Validation once at the boundary: on one call of a public function, each argument is checked by one function.

A public function checks its arguments (through :mod:`navlib._validate`, by hand or with ``@boundary``) and
then works on the checked values: it hands them to unchecked cores (a private helper of its own module, a
shared core module such as :mod:`navlib._earth`, a compiled formula of :mod:`navlib._kernels`), and what it
hands to a public function of another module unchecked, that function checks. A profile hook records every outermost call of a
``_validate`` function during a registry call (tools/fuzz_calls.py) with the argument name it checks and the
public function (or record's field) it checks it for; an argument name checked for two functions, or for a function
and a record's field, is checked twice. Fields of two records that share a name are two arguments
(``Gates.zupt``, a gate, beside ``MeasurementNoise.zupt``, a sigma). A record checks its fields when the user builds
it; a builder that has checked its arguments builds it with :func:`navlib._records.unchecked`. No registry call
checks an argument twice (no exceptions are listed).
"""

from __future__ import annotations

import inspect
import sys
from collections import defaultdict
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from navlib import _validate, calibration, earth, trajectory  # noqa: E402
from navlib.papers import north_finding, pedestrian_ins  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tools"))
import fuzz  # noqa: E402
import fuzz_calls  # noqa: E402

VALIDATORS = {
    f.__code__: inspect.signature(f)
    for name, f in vars(_validate).items()
    if inspect.isfunction(f)
    and f.__module__ == _validate.__name__
    and not name.startswith("_")
    and name not in ("boundary", "fields_checked", "kernel_array", "refuse_turn")
}
VALIDATE_FILE = _validate.__file__


def owner(frame) -> str:
    """The public function (or record class) a check at ``frame`` is made for."""
    while frame is not None:
        code = frame.f_code
        if code.co_filename == VALIDATE_FILE:
            fn = frame.f_locals.get("fn") if code.co_name == "checked" else None  # @boundary: the function it wraps
            if fn is not None:
                return fn.__qualname__
        elif "navlib" in code.co_filename:
            top = code.co_qualname.split(".<locals>.")[0]
            parts = top.split(".")
            if parts[-1].startswith("__") and len(parts) > 1:  # a record's __post_init__ / __init__
                return f"{parts[-2]}.{parts[-1]}"
            if not parts[-1].startswith("_"):
                return top
        else:
            return "<caller>"
        frame = frame.f_back
    return "<caller>"


def checked_twice(owners: set[str]) -> bool:
    """Two functions check one argument, or a function and a record's field; two records' fields are two arguments."""
    records = {o for o in owners if o.endswith("__")}
    return len(owners - records) + bool(records) > 1


def checks_of(func, kwargs) -> dict[str, set[str]]:
    """Argument name -> the public functions that check it, during ``func(**kwargs)``."""
    seen: dict[str, set[str]] = defaultdict(set)

    def hook(frame, event, arg):
        if event != "call" or frame.f_code not in VALIDATORS or frame.f_back.f_code in VALIDATORS:
            return
        params = VALIDATORS[frame.f_code].parameters
        name = frame.f_locals.get("name", frame.f_locals.get("names")) if ("name" in params or "names" in params) else None
        seen[str(name)].add(owner(frame.f_back))

    sys.setprofile(hook)
    try:
        func(**kwargs)
    finally:
        sys.setprofile(None)
    return seen


PUBLIC = fuzz_calls.public_callables()
REGISTRY = fuzz_calls.table()


def registry_call(key: str):
    call = fuzz.with_defaults(PUBLIC[key], REGISTRY[key])
    if call.before:
        call.before()
    return {k: v.make() if isinstance(v, fuzz_calls.Fresh) else v for k, v in call.kwargs.items()}


CALLS = sorted(k for k, c in REGISTRY.items() if isinstance(c, fuzz_calls.Call) and not k.startswith(("repro.", "plots.")))


@pytest.mark.filterwarnings("ignore::RuntimeWarning")  # as in tests/test_bad_input.py: the registry's tiny records
@pytest.mark.parametrize("key", CALLS)
def test_each_argument_is_checked_once(key):
    func = PUBLIC[key]
    func(**registry_call(key))  # a first call checks @boundary defaults once; the second is the one counted
    twice = {name: sorted(owners) for name, owners in checks_of(func, registry_call(key)).items() if checked_twice(owners)}
    plt.close("all")
    assert not twice, f"{key}: arguments checked by more than one function: {twice}"


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: calibration.fit_accelerometer(np.vstack([9.8 * np.eye(3), -9.8 * np.eye(3)]), g=-1.0), "^g: "),
        (lambda: north_finding.stop_and_go([0.0, 1.0], 60.0, 60.0, 0.0, [0.0, 0.0], [0.0, 0.0]), "^speed: "),
        (lambda: pedestrian_ins.carpark_legs(speed=-1.0), "^speed: "),
        (lambda: pedestrian_ins.carpark_legs(side=(40.0, 2.0)), "^side: expected sides longer than a corner"),
        (lambda: trajectory.from_profiles([0.0, 0.1, 0.3], [0.6, 0.2, 0.0], np.zeros((3, 3)), np.zeros((3, 3))), "^time: "),
        (lambda: trajectory.from_profiles([0.0, 0.1], [0.6, 0.2, 0.0], np.zeros((2, 3)), np.zeros((3, 3))), "^vel_n: "),
        (lambda: trajectory.from_profiles([0.0, 1.0], [1.5, 0.2, 0.0], np.zeros((2, 3)), [[0, 1e6, 0]] * 2), "^vel_n: .* pole"),
    ],
)
def test_a_builder_refuses_what_its_unchecked_record_would(call, message):
    """Builders make their records unchecked (navlib._records): a bad argument is refused by the builder, by its name."""
    with pytest.raises(ValueError, match=message):
        call()


def in_navlib(func, qualname: str) -> None:
    """Let the hook see ``func`` as navlib's ``qualname``."""
    func.__code__ = func.__code__.replace(co_filename=str(ROOT / "navlib" / "x.py"), co_qualname=qualname)


def test_the_hook_sees_a_second_check():
    """A public function that checks ``lat`` and passes it on to another one that checks it again is caught."""

    def twice(lat):
        return earth.gravity(_validate.latitude(lat, "lat"))

    in_navlib(twice, "twice")
    assert checks_of(twice, {"lat": np.float64(0.5)})["lat"] == {"twice", "gravity"}


def test_the_hook_sees_a_record_built_from_a_checked_argument():
    """A builder that checks ``lat`` and builds a record whose field ``lat`` is checked again is caught; two records
    that each have a field ``lat`` are two arguments, each checked once."""

    @dataclass(frozen=True)
    class Fix:
        lat: float

        def __post_init__(self):
            _validate.latitude(self.lat, "lat")

    @dataclass(frozen=True)
    class Site:
        lat: float

        def __post_init__(self):
            _validate.latitude(self.lat, "lat")

    def build(lat):
        return Fix(_validate.latitude(lat, "lat"))

    for func, qualname in (
        (Fix.__post_init__, "Fix.__post_init__"),
        (Site.__post_init__, "Site.__post_init__"),
        (build, "build"),
    ):
        in_navlib(func, qualname)
    built = checks_of(build, {"lat": np.float64(0.5)})["lat"]
    assert built == {"build", "Fix.__post_init__"} and checked_twice(built)
    both = checks_of(lambda lat: (Fix(lat), Site(lat)), {"lat": np.float64(0.5)})["lat"]
    assert both == {"Fix.__post_init__", "Site.__post_init__"} and not checked_twice(both)


def test_stop_windows_cut_by_time_are_checked_once():
    """The registry call cuts stops by sample index; cut by ``time``, each argument is still checked by one function."""
    kwargs = registry_call("papers.north_finding.stop_solutions")
    kwargs.update(time=0.01 * np.arange(kwargs["w_ib_b"].shape[-2]), windows=np.array([[0.0, 0.05], [0.05, 0.1]]))
    seen = checks_of(north_finding.stop_solutions, kwargs)
    assert seen["time"] == {"static_windows"} and not [name for name, owners in seen.items() if checked_twice(owners)]
