"""Deprecated alias of :mod:`navlib.papers.pedestrian_ins` and of core modules:
navlib.alignment, navlib.analysis, navlib.atmosphere, navlib.attitude, navlib.filters.zupt,
navlib.filters.zupt_ins, navlib.pdr, navlib.robust, navlib.trajectory.

``navlib.pedestrian`` was the module of this paper before the split into a paper companion
and core homes (see CONTRIBUTING.md). Every old name still resolves here; importing this
module warns. It will be removed in navlib 0.3.
"""
# ruff: noqa: F405  (the names come from the star import)
import warnings

from .alignment import level, magnetic_heading, static_gyro_bias  # noqa: F401
from .analysis import detection_rates, expanding_std, horizontal_error, segments  # noqa: F401
from .atmosphere import baro_height, classify_floor, reference_pressure, segment_floors  # noqa: F401
from .attitude import M_NED_ENU, ned_to_enu_dcm  # noqa: F401
from .filters.zupt import (  # noqa: F401
           STATIC_THRESHOLDS,
           detect_static,
           error_model_fd,
           error_state_matrix,
           zupt_zaru_innovation,
           zupt_zaru_matrix,
)
from .filters.zupt_ins import (  # noqa: F401
           FLAG_DROPOUT,
           FLAG_SATURATED,
           FLAG_SPIKE,
           FLAG_STATIC_SKIPPED,
           FilterConfig,
           FilterResult,
           run_filter,
)
from .papers.pedestrian_ins import *  # noqa: F403
from .pdr import StepResult, detect_steps, pdr, pdr_headings, weinberg_step_length  # noqa: F401
from .robust import despike  # noqa: F401
from .trajectory import Gait, Leg, stance_mask, walk  # noqa: F401

__all__ = ["M_NED_ENU", "STATIC_THRESHOLDS", "ned_to_enu_dcm", "Leg", "Gait", "walk", "stance_mask", "carpark_legs",
           "floor_test_legs", "detect_static", "detection_rates", "level", "static_gyro_bias", "magnetic_heading",
           "tilt_compensate_ned", "tilt_compensate_printed", "heading_from_horizontal", "baro_height",
           "reference_pressure", "classify_floor", "segment_floors", "hvac_pressure_steps", "despike",
           "error_state_matrix", "error_model_fd", "zupt_zaru_matrix", "zupt_zaru_innovation",
           "simple_covariance_update", "FilterConfig", "FilterResult", "run_filter", "FLAG_DROPOUT", "FLAG_SPIKE",
           "FLAG_SATURATED", "FLAG_STATIC_SKIPPED", "detect_steps", "weinberg_step_length", "pdr", "StepResult",
           "segments", "pdr_headings", "expanding_std", "horizontal_error"]

warnings.warn("navlib.pedestrian is deprecated and will be removed in navlib 0.3; use navlib.papers.pedestrian_ins"
              " and the core modules named in the README", DeprecationWarning, stacklevel=2)
