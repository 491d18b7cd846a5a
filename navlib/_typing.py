"""Shape aliases for navlib's type hints (documentation for readers and IDEs; not enforced).

Trailing dimensions follow the conventions in :mod:`navlib`: vectors on the
last axis, time on the axis before it, leading axes free (trials).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["ArrayLike", "Array", "Scalar", "Vec3", "Vec3Series", "Quat", "Dcm", "Angles", "Times", "Interval"]

Array = NDArray[np.float64]
"""A float64 result array."""
Scalar = float | np.floating
Vec3 = ArrayLike
"""(..., 3): a vector such as ``f_b`` or ``vel_n``."""
Vec3Series = ArrayLike
"""(..., N, 3): vectors sampled in time (N samples)."""
Quat = ArrayLike
"""(..., 4): scalar-first unit quaternions."""
Dcm = ArrayLike
"""(..., 3, 3): rotation matrices."""
Angles = ArrayLike
"""(...,) angles in rad, or (..., 3) ``hpr`` = [heading, pitch, roll] (rad)."""
Times = ArrayLike
"""(N,) epoch times (s), strictly increasing."""
Interval = float | ArrayLike
"""A fixed sample interval (s) or per-sample intervals of shape (N,)."""
