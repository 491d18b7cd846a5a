"""The examples in navlib's docstrings run and print what they show (doctest over every public module)."""

from __future__ import annotations

import doctest
import importlib
import pkgutil

import numpy as np
import pytest

import navlib

MODULES = sorted(
    m.name
    for m in pkgutil.walk_packages(navlib.__path__, "navlib.")
    if not any(part.startswith("_") for part in m.name.split("."))
)


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name):
    module = importlib.import_module(name)
    with np.printoptions(legacy=False):
        result = doctest.testmod(module, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE, verbose=False)
    assert result.failed == 0, f"{result.failed} of {result.attempted} examples in {name} failed (run doctest for details)"


def test_the_main_entry_points_have_examples():
    """Each main entry point shows a short example (ahrs-style), so the API pages open with one."""
    from navlib import alignment, attitude, earth, geodesy, sensors, strapdown, trajectory, units

    entry = [
        attitude.euler_to_quat,
        attitude.quat_rotate,
        earth.gravity,
        earth.earth_rate_n,
        geodesy.geodetic2gk,
        geodesy.zone,
        sensors.simulate_imu,
        trajectory.static,
        alignment.tilt_heading,
        units.deg_per_h,
        strapdown.integrate,
    ]
    missing = [f.__qualname__ for f in entry if ">>>" not in (f.__doc__ or "")]
    assert not missing, f"no example in: {missing}"
