"""The examples in navlib's docstrings run and print what they show (doctest over every public module), and every
public callable has one (scikit-learn style: each API entry opens with a short example)."""

from __future__ import annotations

import doctest
import importlib
import inspect
import pkgutil
import re
import sys
from pathlib import Path

import numpy as np
import pytest

import navlib

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tools"))
import fuzz_calls  # noqa: E402  (the registry of public callables)

MODULES = sorted(
    m.name
    for m in pkgutil.walk_packages(navlib.__path__, "navlib.")
    if not any(part.startswith("_") for part in m.name.split("."))
)
# A numpydoc "Examples" section: the heading, its underline, then the doctests.
_EXAMPLES = re.compile(r"^Examples\n-{8,}\n", re.MULTILINE)


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name):
    module = importlib.import_module(name)
    with np.printoptions(legacy=False):
        result = doctest.testmod(module, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE, verbose=False)
    assert result.failed == 0, f"{result.failed} of {result.attempted} examples in {name} failed (run doctest for details)"


def test_every_public_callable_has_an_example():
    """Each callable of a public module's ``__all__`` (functions, records, exceptions) has an ``Examples`` section
    whose doctests :func:`test_docstring_examples` runs, and at least one of them shows an output."""
    finder = doctest.DocTestFinder()
    shown = {
        test.name
        for name in MODULES
        for test in finder.find(importlib.import_module(name))
        if any(example.want for example in test.examples)
    }
    missing = [
        name
        for name, obj in fuzz_calls.public_callables().items()
        if not _EXAMPLES.search(inspect.getdoc(obj) or "") or f"navlib.{name}" not in shown
    ]
    assert not missing, (
        f"{len(missing)} public callables without an Examples section that runs and prints a result: {missing} "
        "(add a numpydoc Examples section: a small input and its rounded output, as in navlib.attitude)"
    )
