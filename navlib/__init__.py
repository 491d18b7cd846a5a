"""navlib: low-cost inertial navigation, reproducibly.

Algorithms and simulated sensors behind the navlib notebooks, which reproduce
five papers on low-cost inertial navigation (see README.md).

Conventions (stated here once; every module follows them)
---------------------------------------------------------
Frames
    n, navigation: East-North-Up (ENU). b, body: right-front-up (x right,
    y forward, z up). The sensor frame equals b unless a notebook says
    otherwise; :func:`navlib.attitude.mount_matrix` maps a sensor's axes to b, and
    :mod:`navlib.io` reads real logs into these conventions.
Attitude
    ``C_bn`` is C_b^n, body to navigation: ``v_n = C_bn @ v_b``.
    Euler angles ``hpr = [heading, pitch, roll]`` as in paper 000 Eq. (3):
    ``C_bn = rot(z, -heading) rot(x, pitch) rot(y, roll)`` with the ordinary
    active rotation ``rot``. Heading in [0, 2 pi) clockwise from north, pitch
    in [-pi/2, pi/2] nose up, roll in (-pi, pi] right side down.
    Quaternions are scalar first ``[q0, q1, q2, q3]`` (Hamilton product) and
    represent C_b^n: ``v_n = q (x) v_b (x) q*``.
Sensors
    Gyros measure ``w_ib_b``, the body rate relative to inertial space,
    including Earth rate. Accelerometers measure specific force
    ``f_b = C_nb (a_n - g_n)``: a level static accelerometer reads +g on z;
    ``g_n = [0, 0, -g]``.
Units
    SI inside navlib: rad, rad/s, m/s^2, m, s, Pa, K, and uT for magnetic
    field. Datasheet units (deg/h, deg/sqrt(h), ug, gauss, hPa) only through
    :mod:`navlib.units`. A function taking degrees says so with ``deg=True``
    or in its name. Latitude is ``lat`` and longitude ``lon``, never a bare L.
Arrays
    Vectors on the last axis, time on the axis before: ``(..., N, 3)``.
    Leading axes are Monte Carlo trials where a function supports batches.
    Names carry their frame: ``f_b``, ``w_ib_b``, ``vel_n``, ``C_bn``, ``q_bn``.
Randomness
    Every function that draws takes ``rng: numpy.random.Generator``; there is
    no global random state. Independent streams per sensor and per trial come
    from ``numpy.random.SeedSequence(seed).spawn(k)``.
Angles that wrap
    Headings and heading innovations are wrapped explicitly with
    :func:`navlib.attitude.wrap_pi` / :func:`navlib.attitude.wrap_2pi`.
Bad input
    Public functions raise ``ValueError`` naming the argument and what was
    expected.
Compiled kernels
    Sequential per-sample loops are compiled with numba (``@njit(cache=True)``)
    and run unchanged as plain Python with ``NUMBA_DISABLE_JIT=1``.
"""

import importlib
from types import ModuleType

__version__ = "0.1.0"

_SUBMODULES = (
    "alignment",
    "analysis",
    "atmosphere",
    "attitude",
    "calibration",
    "earth",
    "euler",
    "faults",
    "filters",
    "geodesy",
    "imu",
    "io",
    "kalman",
    "montecarlo",
    "papers",
    "pdr",
    "plots",
    "repro",
    "robust",
    "sensors",
    "strapdown",
    "timing",
    "trajectory",
    "units",
)
__all__ = [*_SUBMODULES, "__version__"]


def __getattr__(name: str) -> ModuleType:
    # Submodules load on first use (``from navlib import analysis`` or ``navlib.analysis``): a notebook or tool
    # pays only for the modules it needs.
    if name in _SUBMODULES:
        return importlib.import_module(f"{__name__}.{name}")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
