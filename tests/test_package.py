"""navlib's module attributes: submodules load on first use, importing warns of nothing, no old names."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

import navlib


def test_importing_navlib_does_not_warn():
    out = subprocess.run(
        [sys.executable, "-W", "error::DeprecationWarning", "-c", "import navlib, navlib.papers"], capture_output=True, text=True
    )
    assert out.returncode == 0, out.stderr


@pytest.mark.parametrize("old", ["northfinding", "gyrobias", "planar", "ahrs", "pedestrian"])
def test_the_unreleased_alias_modules_are_gone(old):
    with pytest.raises(AttributeError, match=old):
        getattr(navlib, old)


def test_submodules_load_on_first_use():
    """``import navlib`` loads no submodule; ``navlib.X`` and ``from navlib import X`` load X (and what it imports)."""
    code = (
        "import sys, navlib; assert not [m for m in sys.modules if m.startswith('navlib.')], sys.modules.keys(); "
        "from navlib import units; assert 'scipy.stats' not in sys.modules and 'numba' not in sys.modules; "
        "assert all(hasattr(navlib, name) for name in navlib.__all__); assert set(navlib.__all__) <= set(dir(navlib))"
    )
    subprocess.run([sys.executable, "-c", code], check=True)


# matplotlib is the optional `plots` extra: the rest of navlib must import without it.
_NO_MATPLOTLIB = "import sys; sys.modules['matplotlib'] = None; sys.modules['mpl_toolkits'] = None; "


def test_every_module_imports_without_matplotlib():
    code = _NO_MATPLOTLIB + (
        "import importlib, pkgutil, navlib; "
        "names = [m.name for m in pkgutil.walk_packages(navlib.__path__, 'navlib.')]; "
        "[importlib.import_module(n) for n in names]; print(len(names))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert int(out.stdout) > 30


def test_repro_without_matplotlib_says_which_extra_to_install(tmp_path):
    code = _NO_MATPLOTLIB + f"from navlib import repro; repro.setup('nb', out_dir={str(tmp_path)!r})"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.returncode != 0 and "pip install 'navlib-repro[plots]'" in out.stderr, out.stderr


def test_the_package_is_marked_typed():
    """PEP 561: a user's type checker reads navlib's annotations only when ``py.typed`` ships in the package."""
    assert (Path(navlib.__file__).parent / "py.typed").is_file()
