"""Deprecated alias of :mod:`navlib.papers.mimu_mag_rtk` and of core modules:
navlib.alignment, navlib.analysis, navlib.filters.heading_fusion, navlib.filters.mahony,
navlib.filters.observations, navlib.filters.quaternion_kf.

``navlib.ahrs`` was the module of this paper before the split into a paper companion
and core homes (see CONTRIBUTING.md). Every old name still resolves here; importing this
module warns. It will be removed in navlib 0.3.
"""
# ruff: noqa: F405  (the names come from the star import)
import warnings

from .alignment import initial_attitude, tilt_heading  # noqa: F401
from .analysis import settling_time  # noqa: F401
from .filters.heading_fusion import fuse_rtk_heading, rtk_at_imu_rate  # noqa: F401
from .filters.mahony import mahony  # noqa: F401
from .filters.observations import COUNT_NAMES, AttitudeResult, MagGate, magnetic_reference  # noqa: F401
from .filters.quaternion_kf import measurement_jacobian, measurement_model, noise_input, quaternion_kf, transition  # noqa: F401
from .papers.mimu_mag_rtk import *  # noqa: F403

__all__ = ["MagGate", "AttitudeResult", "COUNT_NAMES", "magnetic_reference", "tilt_heading", "initial_attitude", "settling_time",
           "transition", "noise_input", "measurement_model", "measurement_jacobian", "mahony", "quaternion_kf",
           "fuse_rtk_heading", "rtk_at_imu_rate", "printed_eq2_roll", "printed_eq4", "printed_eq5_tilt",
           "printed_eq7_heading", "printed_eq8_quat", "printed_eq18_gamma", "printed_eq20_jacobian"]

warnings.warn("navlib.ahrs is deprecated and will be removed in navlib 0.3; use navlib.papers.mimu_mag_rtk"
              " and the core modules named in the README", DeprecationWarning, stacklevel=2)
