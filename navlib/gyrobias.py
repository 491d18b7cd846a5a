"""Deprecated alias of :mod:`navlib.papers.rotation_bias` and of core modules:
navlib.analysis, navlib.earth, navlib.euler.

``navlib.gyrobias`` was the module of this paper before the split into a paper companion
and core homes (see CONTRIBUTING.md). Every old name still resolves here; importing this
module warns. It will be removed in navlib 0.3.
"""
# ruff: noqa: F405  (the names come from the star import)
import warnings

from . import attitude, earth
from .analysis import attitude_errors, condition_number, cramer_rao_bound, error_statistics, lsq_covariance  # noqa: F401
from .euler import PITCH_LIMIT, EulerReport, euler_rates, integrate_euler  # noqa: F401
from .papers.rotation_bias import *  # noqa: F403

__all__ = ["eq1_matrix", "euler_rates", "integrate_euler", "EulerReport", "gravity_body", "tilt_from_accel", "tilt_matrix",
           "rodrigues", "rotate_attitude", "dwell_attitudes", "dwell_windows", "earth_rate_body", "Residuals",
           "tilt_residuals", "residual_covariance", "lsq_bias", "running_lsq_bias", "KalmanBias", "kalman_bias",
           "condition_number", "lsq_covariance", "cramer_rao_bound", "design", "attitude_errors", "error_statistics",
           "PITCH_LIMIT", "MIN_DWELL_SAMPLES"]


def earth_rate_body(hpr, lat):
    """Earth rate in the body frame at attitudes ``hpr``: :func:`navlib.earth.earth_rate_b` of their DCM."""
    return earth.earth_rate_b(attitude.euler_to_dcm(hpr), lat)


warnings.warn("navlib.gyrobias is deprecated and will be removed in navlib 0.3; use navlib.papers.rotation_bias"
              " and the core modules named in the README", DeprecationWarning, stacklevel=2)
