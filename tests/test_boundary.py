"""The declarative argument boundary (navlib._validate.boundary): what an annotation asks is checked before the
function runs, naming the parameter; every decorated public function checks what its annotations say."""

from __future__ import annotations

import inspect
import re
import sys
from pathlib import Path
from typing import Annotated

import numpy as np
import pytest

from navlib import _validate
from navlib._validate import Check, Count, Is, NonNegative, Positive, Rng, boundary, fields_checked

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tools"))
import fuzz_calls  # noqa: E402  (the registry of public callables)


class Options:
    pass


@boundary
def _example(
    x: object,
    speed: Positive,
    n: Count = 3,
    *,
    rng: Rng | None = None,
    frac: Annotated[float, Check("scalar", within=(0.0, 1.0))] = 0.5,
    options: Is[Options] | None = None,
) -> tuple:
    return x, speed, n, rng, frac, options


def test_converts_checked_arguments_and_defaults():
    x, speed, n, rng, frac, options = _example("raw", np.float32(2.0))
    assert x == "raw" and type(speed) is float and speed == 2.0 and n == 3 and rng is None and frac == 0.5
    assert _example("raw", 1, n=np.int64(4), frac=1.0)[2:5:2] == (4, 1.0)
    assert type(_example(None, 1, np.int64(4))[2]) is int


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        ({"speed": -1.0}, "speed"),
        ({"speed": "fast"}, "speed"),
        ({"speed": 1.0, "n": 0}, "n"),
        ({"speed": 1.0, "n": True}, "n"),
        ({"speed": 1.0, "rng": 42}, "rng"),
        ({"speed": 1.0, "frac": 2.0}, "frac"),
        ({"speed": 1.0, "options": {}}, "options"),
    ],
)
def test_refuses_naming_the_parameter(kwargs, name):
    with pytest.raises(ValueError, match=rf"^{name}: expected"):
        _example(None, **kwargs)
    if len(kwargs) == 1:  # the same given positionally
        with pytest.raises(ValueError, match=rf"^{name}: expected"):
            _example(None, *kwargs.values())


def test_a_boundary_without_a_checked_parameter_is_refused():
    @boundary
    def unchecked(x: float) -> float:
        return x

    with pytest.raises(TypeError, match="without a checked parameter"):
        unchecked(1.0)


_KINDS = re.compile(r"\b(Check|Real|Positive|NonNegative|Count|Flag|Rng|Text|Step|Is|EllipsoidArg)\b")


def _decorated():
    return {name: obj for name, obj in fuzz_calls.public_callables().items() if hasattr(obj, "__wrapped__")}


def test_every_checked_annotation_of_a_public_function_is_checked():
    """An annotation naming a checked kind resolves to a check (not skipped as a name the type checker alone sees)."""
    decorated = _decorated()
    assert len(decorated) > 100
    for name, fn in decorated.items():
        for p in inspect.signature(fn).parameters.values():
            if isinstance(p.annotation, str) and _KINDS.search(p.annotation):
                check = _validate._annotated_check(p.annotation, inspect.unwrap(fn).__globals__, p.name)
                assert check is not None, f"{name}({p.name}: {p.annotation}) is not checked"


def test_records_check_their_annotated_fields():
    from dataclasses import dataclass

    @dataclass(frozen=True)
    class Gains:
        kp: Positive
        ki: NonNegative | None = None
        note: str = ""

        def __post_init__(self) -> None:
            fields_checked(self)

    assert Gains(1.0).ki is None and Gains(1.0, 0.0).ki == 0.0
    for bad, name in (({"kp": 0.0}, "kp"), ({"kp": 1.0, "ki": -1.0}, "ki"), ({"kp": "1"}, "kp")):
        with pytest.raises(ValueError, match=rf"^{name}: expected"):
            Gains(**bad)


def test_a_checked_kind_missing_from_the_namespace_is_refused_not_skipped():
    with pytest.raises(TypeError, match="Positive is not imported"):
        _validate._annotated_check("Positive", {}, "x")
