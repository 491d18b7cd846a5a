"""Deprecated alias of :mod:`navlib.papers.gauss_kruger_ekf` and of core modules:
navlib.analysis.

``navlib.planar`` was the module of this paper before the split into a paper companion
and core homes (see CONTRIBUTING.md). Every old name still resolves here; importing this
module warns. It will be removed in navlib 0.3.
"""
# ruff: noqa: F405  (the names come from the star import)
import warnings

from .analysis import position_error  # noqa: F401
from .papers.gauss_kruger_ekf import *  # noqa: F403

__all__ = ["CHANNELS", "Q_PAPER", "R_PAPER", "motion_model", "jacobian", "propagate", "waypoint_path", "dead_reckoning",
           "filter_grid", "ekf", "EkfResult", "simulate_sensors", "Sensors", "position_error"]

warnings.warn("navlib.planar is deprecated and will be removed in navlib 0.3; use navlib.papers.gauss_kruger_ekf"
              " and the core modules named in the README", DeprecationWarning, stacklevel=2)
