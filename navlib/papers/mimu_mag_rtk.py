"""Attitude from a MEMS IMU, a magnetometer and dual-antenna RTK heading (paper 003).

Zhang Q., Wu Z., Yun Q. (2023). Research on attitude measurement method based
on MIMU/magnetic sensor/dual antenna RTK. *Journal of Electronic Measurement
and Instrumentation* 37(5): 230-239. doi:10.13382/j.jemi.B2206027

Conventions are navlib's (ENU, right-front-up, ``q = q_b^n`` scalar first,
``hpr = [heading, pitch, roll]`` with heading clockwise from north). The
paper's counter-clockwise yaw is ``-heading``; its z-x-y Euler order is
navlib's, so Eq. (1) is :func:`navlib.attitude.euler_to_quat` and the
corrected Eq. (2) is :func:`navlib.attitude.quat_to_euler`.

Equations implemented (paper numbering, errata E003-nn corrected; see data/errata.csv)
--------------------------------------------------------------------------------------
* Eq. (3)  reference directions ``a_n = [0, 0, 1]``, ``b = [0, cos I, -sin I]``
  (magnetic north; b normalised, ``b_u < 0`` in the north; E003-07):
  :func:`navlib.filters.observations.magnetic_reference`.
* Eq. (4)  ``a = C_nb [0, 0, 1]`` with ``q0**2`` in the third row (E003-04), and
* Eq. (6)  ``m = C_nb b`` with ``(q0^2 - q1^2 - q2^2 + q3^2) b_z`` in row 3 (E003-06):
  :func:`navlib.filters.quaternion_kf.measurement_model`.
* Eq. (5)  ``roll = atan2(-a_x, a_z)``, ``pitch = atan2(a_y, hypot(a_x, a_z))`` (E003-05);
* Eq. (7)  levelled field ``m_h = R_x(pitch) R_y(roll) m_b`` and
  ``heading = atan2(-m_h,x, m_h,y)`` (E003-08);
* Eq. (8)  replaced by Eq. (1) (E003-01): :func:`navlib.alignment.tilt_heading`, :func:`navlib.alignment.initial_attitude`.
* Eqs. (9)-(15)  Mahony PI filter: ``e = a_meas x a_est + m_meas x m_est``
  (measured x estimated, hats restored, E003-09), ``m_est = C_nb [0, |h_xy|, h_z]``
  with ``h = C_bn m_meas`` (the magnetometer corrects heading only),
  ``w = w_m + Kp e + Ki sum(e dt)`` with Kp in rad/s and Ki in rad/s^2
  (the full cross product, not MahonyAHRS.c's half error "twoKp", E003-10):
  :func:`navlib.filters.mahony.mahony`.
* Eqs. (16)-(17) ``Phi = I + dt/2 Omega(w)`` with the PI-corrected rate:
  :func:`navlib.filters.quaternion_kf.transition`.
* Eq. (18)  ``Gamma = dt/2 Xi(q)`` (printed ``-dt Xi``, E003-11): :func:`navlib.filters.quaternion_kf.noise_input`.
* Eq. (19)  ``z = h(q) + v`` with innovation ``z - h(q_pred)``; the printed
  ``z - H q`` is wrong because ``H q = 2 h(q)`` (E003-12).
* Eq. (20)  Jacobian with ``H44 = 2(q0 b_y + q1 b_z)`` (E003-13):
  :func:`navlib.filters.quaternion_kf.measurement_jacobian`; the filter is
  :func:`navlib.filters.quaternion_kf.quaternion_kf` (Joseph update from :mod:`navlib.kalman`).
* Sec. 2.5  heading fusion, reconstructed (the paper gives no rule; E003-15, E003-16): while RTK is
  valid the offset ``delta = wrap(H_rtk - H_mag)`` is smoothed with
  ``delta += alpha wrap(delta_k - delta)`` per epoch and the output is
  the RTK heading (carried between 5 Hz epochs by the filter's heading
  increments); during outages the output is ``H_mag + delta`` with
  delta held. Validity is a flag; the value of an invalid epoch (the
  paper's 0) is never used: :func:`navlib.filters.heading_fusion.fuse_rtk_heading`.

Extensions: the magnetometer gate (field norm and dip angle against the
local field, :class:`navlib.filters.observations.MagGate`) and an accelerometer-norm gate, both in
:class:`navlib.filters.observations.AttitudeGates`. Every skipped or gated update is counted in
``AttitudeResult.faults``; NaN gyro samples are replaced by the last used one (counted), so a dropout never
reaches the state.

Robustness (what the filters do with bad data; all counted in ``faults``)
-------------------------------------------------------------------------
* the samples are screened once (:func:`navlib.robust.screen`, with the :class:`navlib.imu.SensorLimits` of
  the ``ImuSamples``): dropouts, stuck axes, spikes, rails, free fall and clock jumps;
* dropouts and gaps (NaN): gyro -> hold the last used sample; accelerometer,
  magnetometer, RTK -> skip that correction (a gap is a run of these: the
  gyro alone carries the attitude);
* outliers: accelerometer -> ``accel_tol`` norm gate; magnetometer ->
  ``MagGate``; gyro -> ``gyro_jump`` step gate (hold); RTK heading ->
  the :class:`navlib.filters.observations.RtkHeading` gate against the current heading estimate, so 180 deg
  ambiguity flips are rejected and never fused, with re-acquisition after ``confirm`` consistent epochs (a
  drifted estimate is pulled back). The gates are opt-in (defaults keep the paper's filter);
* timing: ``dt`` may be per-sample intervals of shape (N,) (irregular
  sampling, used in the compiled kernels); repeated or out-of-order
  timestamps go through :func:`navlib.timing.sanitize` first;
* saturation: with the full scales of ``SensorLimits`` samples at the
  rails are counted; accelerometer and magnetometer corrections are skipped
  for them, gyro samples are used (nothing better exists);
* the quaternion KF's covariance stays symmetric positive definite under all
  of these (skipped data never enters it; prediction and Joseph update are
  symmetrised); ``quaternion_kf`` returns it (``keep_cov`` for every sample).

The filters live in :mod:`navlib.filters` (``mahony``, ``quaternion_kf``, with
the shared ``observations``); this companion holds what only this paper names:
the printed forms of the misprinted equations. The heading fusion reconstructed
for Sec. 2.5 is :mod:`navlib.filters.heading_fusion`.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from .. import attitude
from .._typing import Angles, Array, Quat, Vec3, Vec3Series
from .._validate import NonNegative, Step, as_array, as_quat, boundary, euler_angles
from ..filters.quaternion_kf import measurement_jacobian, noise_input

if TYPE_CHECKING:
    from matplotlib.axes import Axes

__all__ = [
    "printed_eq2_roll",
    "printed_eq2_arctan",
    "printed_eq4",
    "printed_eq5_tilt",
    "printed_eq6",
    "printed_eq7_heading",
    "printed_eq8_quat",
    "printed_eq12_mahony",
    "printed_eq18_gamma",
    "printed_eq20_jacobian",
    "draw_fusion_structure",
]


# --------------------------------------------------------------------------
# The printed equations, kept to show the errata (never used by the filters)
# --------------------------------------------------------------------------


def printed_eq2_roll(q: Quat) -> Array:
    """Roll as printed in Eq. (2): ``atan(-2(q1 q3 + q0 q2) / (1 - 2(q1^2 + q2^2)))`` (E003-02).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude
    >>> from navlib.papers import mimu_mag_rtk
    >>> q = attitude.euler_to_quat(np.deg2rad([30.0, 20.0, 10.0]))
    >>> round(float(np.rad2deg(mimu_mag_rtk.printed_eq2_roll(q))), 3)   # not the 10 deg roll
    1.116
    """
    q0, q1, q2, q3 = np.moveaxis(as_quat(q, "q", normalize=False), -1, 0)
    return np.arctan(-2 * (q1 * q3 + q0 * q2) / (1 - 2 * (q1**2 + q2**2)))


def printed_eq2_arctan(q: Quat) -> Array:
    """Eq. (2) in its printed form, plain ``arctan`` of ratios and an unclipped ``arcsin`` (E003-03); (..., 4) -> (..., 3).

    The roll numerator is the corrected ``2(q0 q2 - q1 q3)`` (E003-02), so that only the quadrant
    loss of ``arctan`` shows: heading and roll come back within (-90 deg, 90 deg), and a pitch argument
    that rounding pushes past 1 (at +-90 deg pitch) gives NaN. Returns ``[heading, pitch, roll]``.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude
    >>> from navlib.papers import mimu_mag_rtk
    >>> q = attitude.euler_to_quat(np.deg2rad([150.0, 0.0, 0.0]))
    >>> np.round(np.rad2deg(mimu_mag_rtk.printed_eq2_arctan(q)), 3) + 0.0   # heading 150 deg comes back as -30
    array([-30.,   0.,   0.])
    """
    q0, q1, q2, q3 = np.moveaxis(as_quat(as_array(q, "q", tail=(4,), nonempty=True), "q"), -1, 0)  # as_array: no huge q
    with np.errstate(invalid="ignore", divide="ignore"):
        pitch = np.arcsin(2 * (q0 * q1 + q2 * q3))
        roll = np.arctan(2 * (q0 * q2 - q1 * q3) / (1 - 2 * (q1**2 + q2**2)))
        heading = np.arctan(2 * (q1 * q2 - q0 * q3) / (1 - 2 * (q1**2 + q3**2)))
    return np.stack([heading, pitch, roll], -1)


def printed_eq4(q: Quat) -> Array:
    """Eq. (4) as printed, with ``q0`` instead of ``q0**2`` in the third row (E003-04); (..., 4) -> (..., 3).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude
    >>> from navlib.papers import mimu_mag_rtk
    >>> np.round(mimu_mag_rtk.printed_eq4(attitude.euler_to_quat(np.deg2rad([0.0, 20.0, 0.0]))), 4)   # cos 20 deg = 0.9397
    array([0.    , 0.342 , 0.9547])
    """
    q0, q1, q2, q3 = np.moveaxis(as_quat(q, "q", normalize=False), -1, 0)
    return np.stack([2 * (q1 * q3 - q0 * q2), 2 * (q2 * q3 + q0 * q1), q0 + q3**2 - q1**2 - q2**2], -1)


def printed_eq5_tilt(f_b: Vec3) -> tuple[Array, Array]:
    """Eq. (5) as printed, ``roll = atan(a_x / hypot(a_y, a_z))``, ``pitch = atan(-a_y / a_z)`` (E003-05).

    Returns (pitch, roll).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude
    >>> from navlib.papers import mimu_mag_rtk
    >>> f_b = attitude.euler_to_dcm(np.deg2rad([0.0, 10.0, 20.0])).T @ [0.0, 0.0, 9.8]
    >>> np.round(np.rad2deg(mimu_mag_rtk.printed_eq5_tilt(f_b)), 3)   # pitch, roll: not 10, 20
    array([-10.628, -19.683])
    """
    a = as_array(f_b, "f_b", tail=(3,), nonempty=True)
    return np.arctan(-a[..., 1] / a[..., 2]), np.arctan(a[..., 0] / np.hypot(a[..., 1], a[..., 2]))


def printed_eq6(q: Quat, b: Vec3) -> Array:
    """Eq. (6) as printed, ``(q0^2 - q1^2 + q2^2 - q3^2) b_z`` in the third row (E003-06); (..., 4), (3,) -> (..., 3).

    ``b = [0, b_y, b_z]`` is the reference field (Eq. 3); its east component is not used, as in the paper.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude
    >>> from navlib.papers import mimu_mag_rtk
    >>> q = attitude.euler_to_quat(np.deg2rad([30.0, 0.0, 0.0]))
    >>> np.round(mimu_mag_rtk.printed_eq6(q, [0.0, 0.5, -0.866]), 4)   # the printed third row (E003-06)
    array([-0.25 ,  0.433, -0.75 ])
    """
    q0, q1, q2, q3 = np.moveaxis(as_quat(q, "q", normalize=False, nonempty=True), -1, 0)
    b = as_array(b, "b", tail=(3,), nonempty=True)
    by, bz = b[..., 1], b[..., 2]
    return np.stack(
        [
            2 * (q1 * q2 + q0 * q3) * by + 2 * (q1 * q3 - q0 * q2) * bz,
            (q0**2 - q1**2 + q2**2 - q3**2) * by + 2 * (q2 * q3 + q0 * q1) * bz,
            2 * (q2 * q3 - q0 * q1) * by + (q0**2 - q1**2 + q2**2 - q3**2) * bz,
        ],
        -1,
    )


def printed_eq7_heading(m_h: Vec3) -> Array:
    """Eq. (7) as printed, ``atan(m_x / m_y)`` of the levelled field (the CCW yaw, E003-08).

    Examples
    --------
    >>> from navlib import alignment
    >>> import numpy as np
    >>> from navlib.papers import mimu_mag_rtk
    >>> round(float(np.rad2deg(mimu_mag_rtk.printed_eq7_heading([0.5, 0.866, -0.5]))), 3)   # counter-clockwise
    30.001
    >>> round(float(np.rad2deg(alignment.magnetic_heading([0.5, 0.866, -0.5], 0.0, 0.0))), 3)   # the clockwise heading
    329.999
    """
    m = as_array(m_h, "m_h", tail=(3,), nonempty=True)
    return np.arctan(m[..., 0] / m[..., 1])


def printed_eq8_quat(hpr: Angles) -> Array:
    """Eq. (8) as printed, with its yaw psi = -heading: ``q_z(psi) q_y(roll) q_x(pitch)`` (E003-01).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude
    >>> from navlib.papers import mimu_mag_rtk
    >>> q = mimu_mag_rtk.printed_eq8_quat(np.deg2rad([30.0, 10.0, 20.0]))
    >>> np.round(np.rad2deg(attitude.quat_to_euler(q)), 3)             # Eq. (8)'s rotation order: other angles
    array([33.451,  9.391, 20.284])
    """
    h, p, r = np.moveaxis(euler_angles(hpr), -1, 0)

    def axis_quat(a: Array, i: int) -> Array:
        return np.stack([np.cos(a / 2)] + [np.sin(a / 2) * (i == j) for j in range(3)], -1)

    return attitude.quat_mult(attitude.quat_mult(axis_quat(-h, 2), axis_quat(r, 1)), axis_quat(p, 0))


@boundary
def printed_eq12_mahony(
    w_ib_b: Vec3Series, f_b: Vec3Series, m_b: Vec3Series, dt: Step, q0: Quat, kp: NonNegative = 1.0, ki: NonNegative = 0.02
) -> Array:
    """Eqs. (12)-(15) with the cross products in the order the printed hat-less ``a x a`` leaves open,
    estimated x measured (E003-09); returns ``q_b^n`` after each sample, shape (N, 4).

    Otherwise the filter of :func:`navlib.filters.mahony.mahony` (same ``m_est``, PI law and
    first-order update), one trial, written per sample in plain Python: the reversed order negates
    the error, so the correction drives the estimate away from the measurements.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude
    >>> from navlib.papers import mimu_mag_rtk
    >>> w, f = np.zeros((100, 3)), np.tile([0.0, 0.0, 9.8], (100, 1))   # level and still
    >>> m = np.tile([0.0, 20.0, -40.0], (100, 1))                     # facing magnetic north
    >>> q = mimu_mag_rtk.printed_eq12_mahony(w, f, m, 0.01, attitude.euler_to_quat([0.0, 0.0, 0.1]))
    >>> np.round(np.rad2deg(attitude.quat_to_euler(q[[0, -1]])), 2) + 0.0   # the printed order drives roll away
    array([[359.98,   0.  ,   5.83],
           [351.01,  -4.67,  34.63]])
    """
    w = as_array(w_ib_b, "w_ib_b", shape=(None, 3), nonempty=True)
    f = as_array(f_b, "f_b", shape=(None, 3), nonempty=True)
    m = as_array(m_b, "m_b", shape=(None, 3), nonempty=True)
    for name, x in (("f_b", f), ("m_b", m)):
        if x.shape != w.shape:
            raise ValueError(f"{name}: expected the shape of w_ib_b {w.shape}, got {x.shape}")
        if not np.all(np.linalg.norm(x, axis=-1) > 0):
            raise ValueError(f"{name}: expected non-zero vectors")
    a, b, c, d = (float(x) for x in as_quat(as_array(q0, "q0", shape=(4,)), "q0"))
    ix = iy = iz = 0.0
    out = np.empty((len(w), 4))
    for k, ((gx, gy, gz), (ax, ay, az), (mx, my, mz)) in enumerate(zip(w.tolist(), f.tolist(), m.tolist(), strict=True)):
        na, nm = math.sqrt(ax * ax + ay * ay + az * az), math.sqrt(mx * mx + my * my + mz * mz)
        ax, ay, az, mx, my, mz = ax / na, ay / na, az / na, mx / nm, my / nm, mz / nm
        c00, c01, c02 = a * a + b * b - c * c - d * d, 2 * (b * c - a * d), 2 * (b * d + a * c)  # C_bn
        c10, c11, c12 = 2 * (b * c + a * d), a * a - b * b + c * c - d * d, 2 * (c * d - a * b)
        c20, c21, c22 = 2 * (b * d - a * c), 2 * (c * d + a * b), a * a - b * b - c * c + d * d
        hx, hy, hz = c00 * mx + c01 * my + c02 * mz, c10 * mx + c11 * my + c12 * mz, c20 * mx + c21 * my + c22 * mz
        bh = math.hypot(hx, hy)
        ux, uy, uz = c10 * bh + c20 * hz, c11 * bh + c21 * hz, c12 * bh + c22 * hz  # m_est = C_nb [0, |h_xy|, h_z]
        ex = (c21 * az - c22 * ay) + (uy * mz - uz * my)  # a_est x a + m_est x m
        ey = (c22 * ax - c20 * az) + (uz * mx - ux * mz)
        ez = (c20 * ay - c21 * ax) + (ux * my - uy * mx)
        ix, iy, iz = ix + ex * dt, iy + ey * dt, iz + ez * dt
        wx, wy, wz = gx + kp * ex + ki * ix, gy + kp * ey + ki * iy, gz + kp * ez + ki * iz
        a, b, c, d = (
            a + 0.5 * dt * (-b * wx - c * wy - d * wz),
            b + 0.5 * dt * (a * wx + c * wz - d * wy),
            c + 0.5 * dt * (a * wy - b * wz + d * wx),
            d + 0.5 * dt * (a * wz + b * wy - c * wx),
        )
        s = 1.0 / math.sqrt(a * a + b * b + c * c + d * d)
        a, b, c, d = a * s, b * s, c * s, d * s
        out[k] = a, b, c, d
    return out


def printed_eq18_gamma(q: Quat, dt: float) -> Array:
    """Gamma as printed in Eq. (18): ``-dt Xi(q)`` (E003-11).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.papers import mimu_mag_rtk
    >>> np.round(mimu_mag_rtk.printed_eq18_gamma([1.0, 0.0, 0.0, 0.0], 0.01), 3) + 0.0   # -dt Xi: twice the size, wrong sign
    array([[ 0.  ,  0.  ,  0.  ],
           [-0.01,  0.  ,  0.  ],
           [ 0.  , -0.01,  0.  ],
           [ 0.  ,  0.  , -0.01]])
    """
    return -2 * noise_input(q, dt)


def printed_eq20_jacobian(q: Quat, b: Vec3) -> Array:
    """Eq. (20) as printed: H44 = 2(q0 b_y - q1 b_z) (E003-13).

    Examples
    --------
    >>> from navlib import attitude
    >>> from navlib.papers import mimu_mag_rtk
    >>> q = attitude.euler_to_quat([0.3, 0.1, 0.2])
    >>> mimu_mag_rtk.printed_eq20_jacobian(q, [0.0, 0.5, -0.866]).shape
    (6, 4)
    """
    H = measurement_jacobian(q, b).copy()  # validates q and b
    q, b = np.asarray(q, dtype=float), np.asarray(b, dtype=float)
    H[..., 3, 3] = 2 * (q[..., 0] * b[..., 1] - q[..., 1] * b[..., 2])
    return H


# --------------------------------------------------------------------------
# The paper's schematic, redrawn
# --------------------------------------------------------------------------

SENSOR_COLOR = "#dbe9f6"
"""Face colour of the sensor boxes in the redrawn schematic."""


def draw_fusion_structure(ax: Axes) -> None:
    """Redraw the paper's fusion structure (its Fig. 3, the four-block framework) on ``ax``.

    Sensors on the left (gyro, accelerometer, magnetometer, dual-antenna RTK with its validity flag);
    the initial attitude from accelerometer and magnetometer (Eqs. 5, 7, 1), the PI correction of the
    gyro rate (Eqs. 12-15), the quaternion Kalman filter with the normalised accelerometer and
    magnetometer as its measurement (Eqs. 16-20, giving the magnetic heading) and the heading fusion
    of Sec. 2.5 (reconstructed, E003-15), which outputs the heading. Drawn in axes coordinates with
    :func:`navlib.plots.block_diagram`; ``ax`` is turned into a schematic (no axes).

    Examples
    --------
    >>> import matplotlib.pyplot as plt
    >>> from navlib.papers import mimu_mag_rtk
    >>> fig, ax = plt.subplots()
    >>> mimu_mag_rtk.draw_fusion_structure(ax)
    >>> len(ax.texts) > 0
    True
    >>> plt.close(fig)
    """
    from .. import plots  # noqa: PLC0415 -- navlib.papers imports without matplotlib

    blocks = {
        "gyro": (0.12, 0.86, "gyro\n$\\omega_m$"),
        "accel": (0.12, 0.62, "accelerometer\n$\\bar{a}$"),
        "mag": (0.12, 0.38, "magnetometer\n$\\bar{m}$"),
        "rtk": (0.12, 0.1, "dual-antenna RTK\n$H_{RTK}$ + valid flag"),
        "init": (0.4, 0.38, "initial attitude $q_0$\nEqs. (5), (7), (1)"),
        "pi": (0.4, 0.86, "PI correction\nEqs. (12)–(15)"),
        "kf": (0.66, 0.62, "quaternion KF\nEqs. (16)–(20)"),
        "fusion": (0.66, 0.1, "heading fusion\n§2.5 (offset $\\delta$)"),
        "out": (0.89, 0.36, "heading $H$\n(attitude)"),
    }
    arrows = [
        ("gyro", "pi", "$\\omega_m$"),
        ("accel", "pi"),
        ("mag", "pi"),
        ("pi", "kf", "$\\omega$"),
        ("accel", "kf", "$z$"),
        ("mag", "kf"),
        ("accel", "init"),
        ("mag", "init"),
        ("init", "kf", "$q_0$"),
        ("kf", "fusion", "$H_{mag}$"),
        ("rtk", "fusion", "$H_{RTK}$ if valid"),
        ("fusion", "out", "$H$"),
    ]
    colors = {k: SENSOR_COLOR for k in ("gyro", "accel", "mag", "rtk")}
    plots.block_diagram(ax, blocks, arrows, width=0.2, height=0.13, colors=colors)
