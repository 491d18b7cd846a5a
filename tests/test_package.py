"""navlib's module attributes: submodules load on first use, importing warns of nothing, no old names."""
from __future__ import annotations

import subprocess
import sys

import pytest

import navlib


def test_importing_navlib_does_not_warn():
    out = subprocess.run([sys.executable, "-W", "error::DeprecationWarning", "-c", "import navlib, navlib.papers"],
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stderr


@pytest.mark.parametrize("old", ["northfinding", "gyrobias", "planar", "ahrs", "pedestrian"])
def test_the_unreleased_alias_modules_are_gone(old):
    with pytest.raises(AttributeError, match=old):
        getattr(navlib, old)


def test_submodules_load_on_first_use():
    """``import navlib`` loads no submodule; ``navlib.X`` and ``from navlib import X`` load X (and what it imports)."""
    code = ("import sys, navlib; assert not [m for m in sys.modules if m.startswith('navlib.')], sys.modules.keys(); "
            "from navlib import units; assert 'scipy.stats' not in sys.modules and 'numba' not in sys.modules; "
            "assert all(hasattr(navlib, name) for name in navlib.__all__); assert set(navlib.__all__) <= set(dir(navlib))")
    subprocess.run([sys.executable, "-c", code], check=True)
