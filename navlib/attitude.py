r"""Attitude representations: rotation matrices, quaternions, Euler angles.

One convention for the whole library (see :mod:`navlib` and notebook 00):

* ``C_bn`` is the body-to-navigation rotation matrix C_b^n: ``v_n = C_bn @ v_b``.
  Its columns are the body axes (right, front, up) expressed in ENU; its rows
  are the ENU axes in body coordinates.
* Euler angles ``hpr = [heading, pitch, roll]`` follow paper 000 Eq. (3),
  ``C_bn = rot(z, -heading) @ rot(x, pitch) @ rot(y, roll)``:

  .. math:: C_b^n = R_z(-\psi)\, R_x(\theta)\, R_y(\gamma)

  with heading :math:`\psi` in [0, 2*pi) clockwise from north, pitch in [-pi/2, pi/2] nose up,
  roll in (-pi, pi] right side down. ``rot`` is the ordinary active rotation.
* Quaternions are scalar first, ``q = [q0, q1, q2, q3]``, Hamilton product,
  and represent the same rotation: :math:`v^n = q \otimes v^b \otimes q^*`.
* Rotation vectors ``rv`` (axis times angle, rad) map through the exponential:
  ``rotvec_to_dcm(rv)`` is :math:`\exp([\mathbf{r}\times])`.

All functions broadcast over leading axes: vectors are ``(..., 3)``, matrices
``(..., 3, 3)``, quaternions ``(..., 4)``, Euler triplets ``(..., 3)``.
Functions taking or returning angles in degrees say so with ``deg=True``.
"""

from __future__ import annotations

from typing import Annotated

import numpy as np

from . import _attitude
from ._typing import Angles, Array, ArrayLike, Dcm, Quat, Vec3
from ._validate import Check, Flag, as_array, as_dcm, as_quat, boundary, flag, in_range

__all__ = [
    "wrap_pi",
    "wrap_2pi",
    "skew",
    "rot",
    "orthonormalize",
    "euler_to_dcm",
    "dcm_to_euler",
    "euler_to_quat",
    "quat_to_euler",
    "quat_to_dcm",
    "dcm_to_quat",
    "quat_mult",
    "quat_conj",
    "quat_normalize",
    "quat_rotate",
    "rotvec_to_dcm",
    "dcm_to_rotvec",
    "rotvec_to_quat",
    "quat_to_rotvec",
    "M_NED_ENU",
    "ned_to_enu",
    "ned_to_enu_dcm",
    "ned_to_enu_quat",
    "ypr_to_hpr",
    "hpr_to_ypr",
    "mount_matrix",
]

_AXES = {"x": 0, "y": 1, "z": 2}
MAX_ROTVEC_ANGLE = 1e12
"""Largest rotation-vector angle (rad) accepted: beyond it a float's spacing exceeds 1e-4 rad."""


def wrap_pi(angle: Angles) -> Array:
    """Wrap angles (rad) into (-pi, pi]; NaN (a dropout) stays NaN.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude
    >>> np.round(attitude.wrap_pi([4.0, -4.0, np.nan]), 6)
    array([-2.283185,  2.283185,       nan])
    """
    return _attitude.wrap_pi(as_array(angle, "angle", allow_nan=True))


def wrap_2pi(angle: Angles) -> Array:
    """Wrap angles (rad) into [0, 2*pi); NaN (a dropout) stays NaN.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude
    >>> np.round(attitude.wrap_2pi([-0.5, 7.0, np.nan]), 6)
    array([5.783185, 0.716815,      nan])
    """
    return _attitude.wrap_2pi(as_array(angle, "angle", allow_nan=True))


def skew(v: Vec3) -> Array:
    """Cross-product matrix: ``skew(a) @ b == cross(a, b)``.

    Parameters
    ----------
    v : array_like, shape (..., 3)

    Returns
    -------
    ndarray, shape (..., 3, 3)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude
    >>> a, b = np.array([1.0, 2.0, 3.0]), np.array([0.0, 1.0, 0.0])
    >>> attitude.skew(a) @ b, np.cross(a, b)
    (array([-3.,  0.,  1.]), array([-3.,  0.,  1.]))
    """
    v = as_array(v, "v", tail=(3,))
    x, y, z = v[..., 0], v[..., 1], v[..., 2]
    o = np.zeros_like(x)
    return np.stack([np.stack([o, -z, y], -1), np.stack([z, o, -x], -1), np.stack([-y, x, o], -1)], -2)


@boundary
def rot(axis: Annotated[str, Check("choice", options=("x", "y", "z"))], angle: Angles, deg: Flag = False) -> Array:
    """Active rotation matrix about a coordinate axis (paper 000's rot(j, phi)).

    Parameters
    ----------
    axis : {'x', 'y', 'z'}
    angle : array_like, shape (...)
        Rotation angle, right-hand rule (rad, or deg with ``deg=True``).

    Returns
    -------
    ndarray, shape (..., 3, 3)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude
    >>> np.round(attitude.rot("z", 90.0, deg=True) @ [1.0, 0.0, 0.0], 12)
    array([0., 1., 0.])
    """
    a = as_array(angle, "angle")
    if deg:
        a = np.deg2rad(a)
    c, s = np.cos(a), np.sin(a)
    o, i = np.zeros_like(a), np.ones_like(a)
    if axis == "x":
        rows = [[i, o, o], [o, c, -s], [o, s, c]]
    elif axis == "y":
        rows = [[c, o, s], [o, i, o], [-s, o, c]]
    else:
        rows = [[c, -s, o], [s, c, o], [o, o, i]]
    return np.stack([np.stack(r, -1) for r in rows], -2)


def orthonormalize(C: Dcm) -> Array:
    """Nearest rotation matrix in the Frobenius norm (SVD projection).

    Parameters
    ----------
    C : array_like, shape (..., 3, 3)
        Approximately orthonormal matrices, e.g. from TRIAD with noisy inputs.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        ``U diag(1, 1, det(U V^T)) V^T``; a proper rotation.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude
    >>> C = attitude.rot("z", 0.3) + 1e-3                           # a noisy rotation matrix
    >>> R = attitude.orthonormalize(C)
    >>> bool(np.allclose(R @ R.T, np.eye(3))), round(float(np.linalg.det(R)), 12)
    (True, 1.0)
    """
    C = as_array(C, "C", tail=(3, 3))
    U, _, Vt = np.linalg.svd(C)
    d = np.linalg.det(U @ Vt)
    D = np.broadcast_to(np.eye(3), U.shape).copy()
    D[..., 2, 2] = d
    return U @ D @ Vt


def _as_hpr(hpr: ArrayLike, deg: bool, name: str = "hpr") -> Array:
    hpr = as_array(hpr, name, tail=(3,))
    if flag(deg, "deg"):
        hpr = np.deg2rad(hpr)
    in_range(hpr[..., 1], f"{name}[..., 1] (pitch)", -np.pi / 2 - 1e-12, np.pi / 2 + 1e-12, "rad")
    return hpr


def euler_to_dcm(hpr: Angles, deg: bool = False) -> Array:
    """C_b^n from heading, pitch, roll (paper 000 Eq. 3).

    Parameters
    ----------
    hpr : array_like, shape (..., 3)
        ``[heading, pitch, roll]``; heading clockwise from north, pitch nose up
        within [-pi/2, pi/2], roll right side down (rad, or deg with ``deg=True``).

    Returns
    -------
    C_bn : ndarray, shape (..., 3, 3)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude
    >>> C_bn = attitude.euler_to_dcm([90.0, 0.0, 0.0], deg=True)   # facing east
    >>> np.round(C_bn @ [0.0, 1.0, 0.0], 12)                      # the forward axis points east (ENU)
    array([1., 0., 0.])
    """
    return _attitude.euler_to_dcm(_as_hpr(hpr, deg))


def dcm_to_euler(C_bn: Dcm, deg: bool = False) -> Array:
    """Heading, pitch, roll from C_b^n (inverse of :func:`euler_to_dcm`).

    Uses pitch = atan2(c32, hypot(c31, c33)), roll = atan2(-c31, c33),
    heading = atan2(c12, c22) mod 2 pi. At gimbal lock (|pitch| = 90 deg to
    1e-9 rad) heading and roll are not separable: roll is set to 0 and the
    whole rotation about the vertical is reported as heading.

    Parameters
    ----------
    C_bn : array_like, shape (..., 3, 3)

    Returns
    -------
    hpr : ndarray, shape (..., 3)
        rad, or deg with ``deg=True``.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude
    >>> C_bn = attitude.euler_to_dcm([30.0, 10.0, -5.0], deg=True)
    >>> np.round(attitude.dcm_to_euler(C_bn, deg=True), 6)
    array([30., 10., -5.])
    """
    hpr = _attitude.dcm_to_euler(as_dcm(C_bn))
    return np.rad2deg(hpr) if flag(deg, "deg") else hpr


def euler_to_quat(hpr: Angles, deg: bool = False) -> Array:
    r"""Quaternion q_b^n from heading, pitch, roll.

    ``q = q_z(-heading) (x) q_x(pitch) (x) q_y(roll)`` with
    :math:`q_a(t) = [\cos(t/2),\ \sin(t/2)\, e_a]` (paper 003 Eq. 1 with its :math:`\phi` = heading).

    Parameters
    ----------
    hpr : array_like, shape (..., 3)

    Returns
    -------
    q : ndarray, shape (..., 4), scalar first, q0 >= 0.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude
    >>> q = attitude.euler_to_quat([30.0, 10.0, 0.0], deg=True)    # heading 30 deg, pitch 10 deg
    >>> np.round(q, 4)
    array([ 0.9623,  0.0842, -0.0226, -0.2578])
    >>> np.round(attitude.quat_to_euler(q, deg=True), 6)
    array([30., 10.,  0.])
    """
    return _attitude.euler_to_quat(_as_hpr(hpr, deg))


def quat_to_euler(q: Quat, deg: bool = False) -> Array:
    """Heading, pitch, roll from a quaternion q_b^n; shape (..., 4) -> (..., 3).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude
    >>> np.round(attitude.quat_to_euler([np.cos(np.pi / 8), 0.0, 0.0, -np.sin(np.pi / 8)], deg=True), 6)
    array([45.,  0.,  0.])
    """
    hpr = _attitude.dcm_to_euler(quat_to_dcm(q))  # a normalised quaternion's matrix is valid
    return np.rad2deg(hpr) if flag(deg, "deg") else hpr


def quat_to_dcm(q: Quat) -> Array:
    """Rotation matrix C_b^n from quaternion q_b^n.

    Parameters
    ----------
    q : array_like, shape (..., 4)
        Scalar first; normalised before use (zero quaternions are rejected).

    Returns
    -------
    C_bn : ndarray, shape (..., 3, 3)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude
    >>> np.round(attitude.quat_to_dcm([np.cos(np.pi / 4), 0.0, 0.0, np.sin(np.pi / 4)]), 12)   # 90 deg about z
    array([[ 0., -1.,  0.],
           [ 1.,  0.,  0.],
           [ 0.,  0.,  1.]])
    """
    return _attitude.quat_to_dcm(as_quat(q))


def dcm_to_quat(C_bn: Dcm) -> Array:
    """Quaternion q_b^n (scalar first, q0 >= 0) from C_b^n (Shepperd's method).

    Parameters
    ----------
    C_bn : array_like, shape (..., 3, 3)

    Returns
    -------
    q : ndarray, shape (..., 4)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude
    >>> np.round(attitude.dcm_to_quat(attitude.rot("z", 90.0, deg=True)), 4)
    array([0.7071, 0.    , 0.    , 0.7071])
    """
    C = as_dcm(C_bn)
    tr = np.trace(C, axis1=-2, axis2=-1)
    d = np.stack([tr, C[..., 0, 0], C[..., 1, 1], C[..., 2, 2]], -1)
    k = np.argmax(d, axis=-1)
    q = np.empty(C.shape[:-2] + (4,))
    # Each branch divides by the largest of the four candidate components.
    cases = {
        0: lambda C, s: (
            s / 4,
            (C[..., 2, 1] - C[..., 1, 2]) / s,
            (C[..., 0, 2] - C[..., 2, 0]) / s,
            (C[..., 1, 0] - C[..., 0, 1]) / s,
        ),
        1: lambda C, s: (
            (C[..., 2, 1] - C[..., 1, 2]) / s,
            s / 4,
            (C[..., 0, 1] + C[..., 1, 0]) / s,
            (C[..., 0, 2] + C[..., 2, 0]) / s,
        ),
        2: lambda C, s: (
            (C[..., 0, 2] - C[..., 2, 0]) / s,
            (C[..., 0, 1] + C[..., 1, 0]) / s,
            s / 4,
            (C[..., 1, 2] + C[..., 2, 1]) / s,
        ),
        3: lambda C, s: (
            (C[..., 1, 0] - C[..., 0, 1]) / s,
            (C[..., 0, 2] + C[..., 2, 0]) / s,
            (C[..., 1, 2] + C[..., 2, 1]) / s,
            s / 4,
        ),
    }
    for case, f in cases.items():
        m = k == case
        if not np.any(m):
            continue
        Cm = C[m]
        if case == 0:
            s = 2 * np.sqrt(1 + Cm[..., 0, 0] + Cm[..., 1, 1] + Cm[..., 2, 2])
        else:
            i = case - 1
            j, l = (i + 1) % 3, (i + 2) % 3
            s = 2 * np.sqrt(1 + Cm[..., i, i] - Cm[..., j, j] - Cm[..., l, l])
        q[m] = np.stack(f(Cm, s), -1)
    q /= np.linalg.norm(q, axis=-1, keepdims=True)
    return _attitude.positive_scalar(q)


def quat_mult(p: Quat, q: Quat) -> Array:
    r"""Hamilton product :math:`p \otimes q`; shapes (..., 4) broadcast.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude
    >>> qz = attitude.rotvec_to_quat([0.0, 0.0, np.pi / 2])        # a quarter turn about z
    >>> np.round(attitude.quat_mult(qz, qz), 12)                   # two of them: a half turn
    array([0., 0., 0., 1.])
    """
    return _attitude.quat_mult(as_array(p, "p", tail=(4,)), as_array(q, "q", tail=(4,)))


def quat_conj(q: Quat) -> Array:
    """Conjugate ``[q0, -q1, -q2, -q3]``; for unit q the inverse rotation.

    Examples
    --------
    >>> from navlib import attitude
    >>> attitude.quat_conj([0.5, 0.5, 0.5, 0.5])
    array([ 0.5, -0.5, -0.5, -0.5])
    """
    return _attitude.quat_conj(as_array(q, "q", tail=(4,)))


def quat_normalize(q: Quat) -> Array:
    """Unit quaternion with q0 >= 0; shape (..., 4).

    Examples
    --------
    >>> from navlib import attitude
    >>> attitude.quat_normalize([-2.0, 0.0, 0.0, 0.0])
    array([ 1., -0., -0., -0.])
    """
    return _attitude.positive_scalar(as_quat(q))


def quat_rotate(q: Quat, v_b: Vec3) -> Array:
    """Rotate body vectors into the navigation frame: ``v_n = q (x) v_b (x) q*``.

    Parameters
    ----------
    q : array_like, shape (..., 4)
    v_b : array_like, shape (..., 3)

    Returns
    -------
    v_n : ndarray, shape (..., 3)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude
    >>> q = attitude.euler_to_quat([90.0, 0.0, 0.0], deg=True)     # facing east
    >>> np.round(attitude.quat_rotate(q, [0.0, 1.0, 0.0]), 12)   # the forward axis, in ENU
    array([1., 0., 0.])
    """
    v_b = as_array(v_b, "v_b", tail=(3,))
    C = quat_to_dcm(q)
    try:
        np.broadcast_shapes(C.shape[:-2], v_b.shape[:-1])
    except ValueError:
        raise ValueError(f"q, v_b: leading shapes {C.shape[:-2]} and {v_b.shape[:-1]} do not broadcast") from None
    return np.einsum("...ij,...j->...i", C, v_b)


def rotvec_to_quat(rv: Vec3) -> Array:
    """Quaternion of the rotation vector ``rv`` (rad), shape (..., 3) -> (..., 4).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude
    >>> np.round(attitude.rotvec_to_quat([0.0, 0.0, np.pi / 2]), 6)
    array([0.707107, 0.      , 0.      , 0.707107])
    """
    rv = as_array(rv, "rv", tail=(3,), huge=True)
    if np.any(np.abs(rv) > MAX_ROTVEC_ANGLE):
        raise ValueError(
            f"rv: rotation angle {np.abs(rv).max():.3g} rad is beyond {MAX_ROTVEC_ANGLE:g} rad, where a "
            f"float no longer resolves the angle modulo 2 pi"
        )
    return _attitude.rotvec_to_quat(rv)


def quat_to_rotvec(q: Quat) -> Array:
    """Rotation vector (rad, angle in [0, pi]) of quaternion q, shape (..., 4) -> (..., 3).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude
    >>> np.round(attitude.quat_to_rotvec([np.cos(0.15), np.sin(0.15), 0.0, 0.0]), 6)
    array([0.3, 0. , 0. ])
    """
    return _attitude.quat_to_rotvec(as_quat(q))


def rotvec_to_dcm(rv: Vec3) -> Array:
    r"""Rotation matrix :math:`\exp([\mathbf{r}\times])` (Rodrigues), shape (..., 3) -> (..., 3, 3).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude
    >>> np.round(attitude.rotvec_to_dcm([0.0, 0.0, np.pi / 2]), 12)
    array([[ 0., -1.,  0.],
           [ 1.,  0.,  0.],
           [ 0.,  0.,  1.]])
    """
    return quat_to_dcm(rotvec_to_quat(rv))


def dcm_to_rotvec(C: Dcm) -> Array:
    """Rotation vector (matrix logarithm) of rotation matrices, (..., 3, 3) -> (..., 3).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude
    >>> np.round(attitude.dcm_to_rotvec(attitude.rot("x", 0.3)), 6)
    array([0.3, 0. , 0. ])
    """
    return quat_to_rotvec(dcm_to_quat(as_dcm(C, "C")))


# --------------------------------------------------------------------------
# Frame conventions: NED / forward-right-down to ENU / right-front-up
# --------------------------------------------------------------------------
#
# One matrix does both swaps: NED -> ENU (east = N-frame y, north = x, up = -z) and
# FRD -> RFU (right = y, front = x, up = -z). It is the half turn about the axis between
# north and east (det +1) and its own inverse, so every conversion below is its own inverse too. Aerospace yaw/pitch/roll
# (ZYX, FRD to NED) are the same physical angles as navlib's heading/pitch/roll; only the
# heading's range differs ((-pi, pi] there, [0, 2 pi) here).

M_NED_ENU = np.array([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]])
"""Swaps N<->E and negates the vertical: ``C_bn(ENU/RFU) = M C_bn(NED/FRD) M``, same (heading, pitch, roll)."""


def ned_to_enu(v: Vec3) -> Array:
    """A navigation-frame vector (..., 3) from NED to ENU; the same swap takes FRD body vectors to RFU.

    Its own inverse: ``ned_to_enu(ned_to_enu(v)) == v`` (so it also maps ENU to NED and RFU to FRD).

    Examples
    --------
    >>> from navlib import attitude
    >>> attitude.ned_to_enu([1.0, 2.0, 3.0])                        # north, east, down -> east, north, up
    array([ 2.,  1., -3.])
    """
    v = as_array(v, "v", tail=(3,), allow_nan=True)
    return np.stack([v[..., 1], v[..., 0], -v[..., 2]], -1)


def ned_to_enu_dcm(C_ned: Dcm) -> Array:
    """Body-to-navigation matrix of the NED/FRD convention in navlib's ENU/RFU one (and back).

    Parameters
    ----------
    C_ned : array_like, shape (..., 3, 3)

    Returns
    -------
    C_bn : ndarray, shape (..., 3, 3)
        ``M C_ned M`` (:data:`M_NED_ENU`); applied to an ENU/RFU matrix it gives the NED/FRD one.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude
    >>> C_ned = attitude.rot("z", 30.0, deg=True)                   # yaw 30 deg in NED/FRD
    >>> np.round(attitude.dcm_to_euler(attitude.ned_to_enu_dcm(C_ned), deg=True), 6)
    array([30.,  0.,  0.])
    """
    C = as_dcm(C_ned, "C_ned")
    return M_NED_ENU @ C @ M_NED_ENU


def ned_to_enu_quat(q_ned: Quat) -> Array:
    """Quaternion of the NED/FRD convention in navlib's ENU/RFU one (and back).

    Conjugation by the half turn :data:`M_NED_ENU` keeps the angle and maps the rotation axis
    ``a`` to ``M a``: ``[q0, q1, q2, q3] -> [q0, q2, q1, -q3]``.

    Parameters
    ----------
    q_ned : array_like, shape (..., 4)
        Scalar-first unit quaternion of C_frd^ned.

    Returns
    -------
    q_bn : ndarray, shape (..., 4)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude
    >>> q_ned = attitude.dcm_to_quat(attitude.rot("z", 30.0, deg=True))
    >>> np.round(attitude.quat_to_euler(attitude.ned_to_enu_quat(q_ned), deg=True), 6)
    array([30.,  0.,  0.])
    """
    q = as_quat(q_ned, "q_ned")
    return np.stack([q[..., 0], q[..., 2], q[..., 1], -q[..., 3]], -1)


def ypr_to_hpr(ypr: Angles, deg: bool = False) -> Array:
    """navlib's ``[heading, pitch, roll]`` from aerospace ``[yaw, pitch, roll]`` (ZYX, FRD to NED).

    The angles are the same; the heading is wrapped to [0, 2 pi) (or [0, 360) deg with ``deg=True``).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude
    >>> np.round(attitude.ypr_to_hpr([-30.0, 10.0, -5.0], deg=True), 6)
    array([330.,  10.,  -5.])
    """
    a = np.array(_as_hpr(ypr, deg, "ypr"), dtype=float)
    a[..., 0] = _attitude.wrap_2pi(a[..., 0])
    return np.rad2deg(a) if deg else a


def hpr_to_ypr(hpr: Angles, deg: bool = False) -> Array:
    """Aerospace ``[yaw, pitch, roll]`` (ZYX, FRD to NED; yaw in (-pi, pi]) from navlib's ``[heading, pitch, roll]``.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude
    >>> np.round(attitude.hpr_to_ypr([30.0, 10.0, -5.0], deg=True), 6)
    array([30., 10., -5.])
    """
    a = np.array(_as_hpr(hpr, deg), dtype=float)
    a[..., 0] = _attitude.wrap_pi(a[..., 0])
    return np.rad2deg(a) if deg else a


def mount_matrix(axes: str | Dcm) -> Array:
    """Sensor-to-body rotation ``C_bs`` (``v_b = C_bs @ v_s``) from a signed axis mapping or a matrix.

    Parameters
    ----------
    axes : str or array_like, shape (3, 3)
        Which sensor axis (with its sign) each body axis -- right, front, up -- is, e.g. ``"-y,x,z"``
        for a sensor whose x points forward and y left (FLU); ``"x,y,z"`` when the sensor's axes are
        already right-front-up. Or a rotation matrix C_bs (orthonormal, det +1; a mirror is refused).

    Returns
    -------
    C_bs : ndarray, shape (3, 3)

    Examples
    --------
    >>> from navlib import attitude
    >>> C_bs = attitude.mount_matrix("-y,x,z")                      # body x is sensor -y, body y is sensor x
    >>> C_bs @ [1.0, 2.0, 3.0]
    array([-2.,  1.,  3.])
    """
    if not isinstance(axes, str):
        return as_dcm(axes, "axes", shape=(3, 3))
    parts = [a.strip().lower() for a in axes.split(",")]
    if len(parts) != 3 or any(a.lstrip("+-") not in _AXES for a in parts) or len({a.lstrip("+-") for a in parts}) != 3:
        raise ValueError(f"axes: expected three signed sensor axes for (right, front, up), e.g. '-y,x,z', got {axes!r}")
    C = np.zeros((3, 3))
    for row, a in enumerate(parts):
        C[row, _AXES[a.lstrip("+-")]] = -1.0 if a.startswith("-") else 1.0
    if np.linalg.det(C) < 0:
        raise ValueError(f"axes: {axes!r} is a mirror image (left-handed); flip the sign of one axis")
    return C
