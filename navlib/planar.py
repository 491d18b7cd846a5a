"""Deprecated alias of :mod:`navlib.papers.gauss_kruger_ekf` and of core modules:
navlib.analysis, navlib.filters.planar_ekf.

``navlib.planar`` was the module of this paper before the split into a paper companion
and core homes (see CONTRIBUTING.md). Every old name still resolves here; importing this
module warns. It will be removed in navlib 0.3.
"""
# ruff: noqa: F405  (the names come from the star import)
import warnings

from .analysis import position_error  # noqa: F401
from .filters import planar_ekf
from .filters.planar_ekf import CHANNELS, EkfResult, dead_reckoning, jacobian, motion_model, propagate  # noqa: F401
from .papers.gauss_kruger_ekf import *  # noqa: F403

__all__ = ["CHANNELS", "Q_PAPER", "R_PAPER", "motion_model", "jacobian", "propagate", "waypoint_path", "dead_reckoning",
           "filter_grid", "ekf", "EkfResult", "simulate_sensors", "Sensors", "position_error"]



def filter_grid(t, z, x0, P0=None, Q=Q_PAPER, R=R_PAPER, *args, **kwargs):
    """:func:`navlib.filters.planar_ekf.filter_grid` with the paper's noise as defaults (the old signature)."""
    return planar_ekf.filter_grid(t, z, x0, P0, Q, R, *args, **kwargs)


warnings.warn("navlib.planar is deprecated and will be removed in navlib 0.3; use navlib.papers.gauss_kruger_ekf"
              " and the core modules named in the README", DeprecationWarning, stacklevel=2)
