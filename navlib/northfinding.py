"""Deprecated alias of :mod:`navlib.papers.north_finding` and of core modules:
navlib.alignment, navlib.sensors.

``navlib.northfinding`` was the module of this paper before the split into a paper companion
and core homes (see CONTRIBUTING.md). Every old name still resolves here; importing this
module warns. It will be removed in navlib 0.3.
"""
# ruff: noqa: F405  (the names come from the star import)
import warnings

from .alignment import (  # noqa: F401
           MAX_LAT_DEG,
           MOVING,
           OK,
           SATURATED,
           TOO_FEW,
           StaticWindow,
           four_position_heading,
           static_means,
           triad,
           triad_heading,
)
from .papers.north_finding import *  # noqa: F403
from .sensors import window_mean_std  # noqa: F401

__all__ = ["MAX_LAT_DEG", "OK", "TOO_FEW", "SATURATED", "MOVING", "StaticWindow", "static_means", "triad", "triad_heading",
           "tilt_from_accel", "Candidates", "heading_candidates", "nearest_candidate_error", "Resolution", "resolve",
           "triad_heading_error", "triad_heading_std", "single_axis_heading_std", "single_axis_heading_error",
           "simulate_static_outputs", "MonteCarlo", "monte_carlo", "pair_probabilities", "four_position_heading",
           "four_position_heading_std", "window_mean_std", "stop_and_go", "StopSolutions", "stop_solutions",
           "InsReport", "ins_heading_change"]

warnings.warn("navlib.northfinding is deprecated and will be removed in navlib 0.3; use navlib.papers.north_finding"
              " and the core modules named in the README", DeprecationWarning, stacklevel=2)
