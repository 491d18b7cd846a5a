r"""ZUPT/ZARU: static detection and the zero-velocity / zero-angular-rate update of an INS.

A strapdown INS drifts quadratically in position; whenever the IMU is known to stand still,
the velocity must be zero (ZUPT) and the gyros must read the Earth rate only (ZARU). An
error-state Kalman filter turns both into measurements of its 15 error states
``dx = [dr_n, dv_n, dpsi, db_a, db_g]`` (ENU; ``C_hat = (I + [dpsi x]) C``; ``d = estimate -
truth`` for r, v, psi and ``truth - estimate`` for the biases).

* :func:`detect_static` -- the ARE + MV + MAG detector of Skog et al. (2010, "Zero-velocity
  detection: an algorithm evaluation", IEEE T-BME 57(11)): static when, over a centred window,
  ``rms|w - b_g| < tau_w``, ``std|f| < tau_f`` and ``|mean|f| - g| < tau_g``.
* :func:`error_state_matrix` -- the continuous-time F of the standard local-level error model
  without Earth-rate and transport-rate terms:

  .. math::

      \delta\dot r &= \delta v, \qquad \delta\dot v = -[(\hat C f^b) \times]\, \delta\psi + \hat C\, \delta b_a \\
      \delta\dot\psi &= \hat C\, \delta b_g, \qquad \delta\dot b = \text{white noise}

  :func:`error_model_fd` differentiates the exact error dynamics numerically to check it.
* :func:`zupt_zaru_matrix`, :func:`zupt_zaru_innovation` -- the static measurement:

  .. math::

      z = \begin{bmatrix} \hat v \\ \omega_{meas} - \hat b_g - \hat C^T \omega_{ie}^n \end{bmatrix}
        = H\, \delta x + v

  .. math::

      H = \begin{bmatrix} 0 & I & 0 & 0 & 0 \\ 0 & 0 & -\hat C^T [\omega_{ie}^n \times] & 0 & I \end{bmatrix}

  The ``-C^T [w_ie x]`` block is the exact first-order Earth-rate term; with it ``z - H dx``
  is second order.

The ``*_into`` functions are the compiled forms that filter kernels call (no validation), among them
:func:`error_state_predict_into`, the covariance prediction with ``Phi = I + F dt`` by Phi's non-zero blocks.
Used by paper 004 (Wen et al. 2016, :mod:`navlib.papers.pedestrian_ins`), which assembles them
with barometer and magnetometer aiding into its filter.
"""

from __future__ import annotations

import numpy as np
from numba import njit
from numpy.typing import NDArray

from .. import _kernels, analysis, attitude
from .._typing import Array, ArrayLike, Dcm, Vec3, Vec3Series
from .._validate import Positive, as_array, as_dcm, boundary, imu_samples, interval, positive, scalar
from ..imu import ImuSamples, unpack
from ..units import G0

__all__ = [
    "STATIC_THRESHOLDS",
    "detect_static",
    "error_state_matrix",
    "error_model_fd",
    "zupt_zaru_matrix",
    "zupt_zaru_innovation",
]

STATIC_THRESHOLDS = (0.05, 0.1, 0.3)
"""Default static-detector thresholds: gyro rms (rad/s), std of |f| and the distance of mean |f| from g
(m/s^2); starting values to tune per sensor and wearer."""


@boundary
def detect_static(
    w_ib_b: Vec3Series | ImuSamples,
    f_b: Vec3Series | None = None,
    dt: float | None = None,
    window: float = 0.5,
    gyro_bias: Vec3 = (0.0, 0.0, 0.0),
    thresholds: ArrayLike = STATIC_THRESHOLDS,
    g: Positive = G0,
) -> NDArray[np.bool_]:
    """Static (standing) detector from gyro and accelerometer statistics.

    Static when, over a centred window of ``window`` seconds, all hold:
    ``rms |w - b_g| < tau_w`` (angular-rate energy), ``std |f| < tau_f``
    (specific-force variance) and ``|mean |f| - g| < tau_g`` (magnitude).

    NaN samples (dropouts) are left out: the statistics use the valid
    samples of each window, and a window with fewer than half of its
    samples valid is never static (a missing sample is no evidence of
    standing still).

    Parameters
    ----------
    w_ib_b, f_b : array_like, shape (N, 3)
        Gyro (rad/s) and accelerometer (m/s^2) samples; NaN marks dropouts. An
        :class:`navlib.imu.ImuSamples` as ``w_ib_b`` supplies ``f_b`` and ``dt`` (its ranges are not used here).
    dt : float
        Sample interval (s) (nominal; the window is a number of samples). From an ImuSamples: the median of
        its intervals.
    window : float
        Window length (s); at most the record length.
    gyro_bias : array_like, shape (3,)
        Gyro bias to remove first (rad/s), e.g. from :func:`navlib.alignment.static_gyro_bias`.
    thresholds : (float, float, float)
        ``(tau_w rad/s, tau_f m/s^2, tau_g m/s^2)``.
    g : float
        Local gravity (m/s^2); default the standard 9.80665 (pass the local value).

    Returns
    -------
    static : ndarray of bool, shape (N,)

    Examples
    --------
    >>> from navlib import trajectory
    >>> from navlib.filters import zupt
    >>> traj = trajectory.static(1.0, 0.01, [0.6, 0.2, 50.0], [0.0, 0.0, 0.0])
    >>> w_ib_b, f_b = trajectory.ideal_imu(traj)
    >>> w_ib_b[60:] += [0.0, 0.0, 1.0]                                # starts turning at 1 rad/s after 0.6 s
    >>> static = zupt.detect_static(w_ib_b, f_b, 0.01, window=0.1)
    >>> bool(static[:50].all()), bool(static[70:].any())
    (True, False)
    """
    if isinstance(w_ib_b, ImuSamples):  # validated on construction
        w, f, dts, _, _ = unpack(w_ib_b, f_b, dt)
        if w.ndim != 2:
            raise ValueError(f"w_ib_b: expected one record of shape (N, 3), got {w.shape}")
        step = float(np.median(dts))  # the nominal interval of its per-sample intervals
    else:
        w_in, f_in, dt_in, _, _ = unpack(w_ib_b, f_b, dt)
        w, f = imu_samples(w_in, f_in, shape=(None, 3))
        step = interval(dt_in)
    valid = np.all(np.isfinite(w), axis=-1) & np.all(np.isfinite(f), axis=-1)
    if not valid.all():
        w, f = np.where(valid[:, None], w, 0.0), np.where(valid[:, None], f, 0.0)
    n = int(round(scalar(window, "window", positive=True) / step))
    if n < 2 or n > w.shape[0]:
        raise ValueError(
            f"window: expected 2 samples up to the record's {w.shape[0]}, got {window} s at dt = {step:g} s ({n:g} samples)"
        )
    b = as_array(gyro_bias, "gyro_bias", shape=(3,))
    tw, tf, tg = positive(thresholds, "thresholds", shape=(3,))
    w2 = np.sum((w - b) ** 2, -1)
    fn = np.linalg.norm(f, axis=-1)
    share = None if valid.all() else analysis.moving_mean(valid.astype(float), n)  # fraction of valid samples per window

    def mean(x: Array) -> Array:
        if share is None:
            return analysis.moving_mean(x, n)
        return analysis.moving_mean(np.where(valid, x, 0.0), n) / np.maximum(share, 0.5 / n)

    f_mean = mean(fn)
    f_var = np.maximum(mean(fn**2) - f_mean**2, 0.0)
    static = (np.sqrt(mean(w2)) < tw) & (np.sqrt(f_var) < tf) & (np.abs(f_mean - g) < tg)
    if share is not None:  # some samples invalid
        static &= share >= 0.5
    return static


@njit(cache=True)
def error_state_into(F, C, f_n):
    """Write the time-varying blocks of F into ``F`` (15 x 15, constant blocks preset); compiled, unvalidated.

    ``F[3:6, 6:9] = -[f_n x]`` (its diagonal -0.0), ``F[3:6, 9:12] = F[6:9, 12:15] = C``; allocates nothing.
    """
    f0, f1, f2 = f_n[0], f_n[1], f_n[2]
    F[3, 6], F[3, 7], F[3, 8] = -0.0, f2, -f1
    F[4, 6], F[4, 7], F[4, 8] = -f2, -0.0, f0
    F[5, 6], F[5, 7], F[5, 8] = f1, -f0, -0.0
    for i in range(3):
        for j in range(3):
            F[3 + i, 9 + j] = C[i, j]
            F[6 + i, 12 + j] = C[i, j]


@njit(cache=True)
def _phi_row(A, r, C_dt, f_dt, dt):
    """The first nine elements of ``Phi A[r]^T`` for row ``r`` of a 15-column ``A``, ``Phi = I + F dt``, as a tuple.

    By F's blocks: position ``x_r + x_v dt``, velocity ``x_v - [f_n dt x] x_psi + (C dt) x_ba``, attitude
    ``x_psi + (C dt) x_bg``; Phi's last six (bias) rows are the identity. The row is read into locals first:
    nothing written can alias it.
    """
    r0, r1, r2, v0, v1, v2 = A[r, 0], A[r, 1], A[r, 2], A[r, 3], A[r, 4], A[r, 5]
    p0, p1, p2, a0, a1, a2 = A[r, 6], A[r, 7], A[r, 8], A[r, 9], A[r, 10], A[r, 11]
    g0, g1, g2 = A[r, 12], A[r, 13], A[r, 14]
    f0, f1, f2 = f_dt[0], f_dt[1], f_dt[2]
    return (
        r0 + dt * v0,
        r1 + dt * v1,
        r2 + dt * v2,
        v0 + (p1 * f2 - p2 * f1) + (C_dt[0, 0] * a0 + C_dt[0, 1] * a1 + C_dt[0, 2] * a2),
        v1 + (p2 * f0 - p0 * f2) + (C_dt[1, 0] * a0 + C_dt[1, 1] * a1 + C_dt[1, 2] * a2),
        v2 + (p0 * f1 - p1 * f0) + (C_dt[2, 0] * a0 + C_dt[2, 1] * a1 + C_dt[2, 2] * a2),
        p0 + (C_dt[0, 0] * g0 + C_dt[0, 1] * g1 + C_dt[0, 2] * g2),
        p1 + (C_dt[1, 0] * g0 + C_dt[1, 1] * g1 + C_dt[1, 2] * g2),
        p2 + (C_dt[2, 0] * g0 + C_dt[2, 1] * g1 + C_dt[2, 2] * g2),
    )


@njit(cache=True)
def error_state_predict_into(P, C_dt, f_dt, dt, q, work):
    """``P = Phi P Phi^T + diag(q)`` in place, ``Phi = I + F dt`` multiplied by blocks; compiled, unvalidated.

    ``C_dt`` = C dt (3 x 3), ``f_dt`` = (C f_b) dt (3,), ``q`` the diagonal process noise (15,), ``work`` a
    (15, 15) scratch: nothing is allocated. ``P`` must be symmetric; the result is, exactly.

    The transition matrix of the INS error model is block-sparse (Groves 2013, *Principles of GNSS, Inertial,
    and Multisensor Integrated Navigation Systems*, 2nd ed., ch. 14; Sola 2017, *Quaternion kinematics for the
    error-state Kalman filter*, sec. 5.4): identity blocks on the diagonal, ``I dt`` (position from velocity),
    ``-[f_n dt x]`` (velocity from attitude), ``C dt`` (velocity from the accelerometer bias, attitude from the
    gyro bias), nothing else; its bias rows are the identity. So only the first nine rows of ``M = Phi P`` are
    computed, by blocks (:func:`_phi_row` on each column of P, a row as P is symmetric), the bias-bias block of
    the result is P's own, its bias rows are M's bias columns, and of ``Phi M^T`` the first nine rows, by blocks
    again, from the diagonal on (mirrored): about a third of a dense product's multiplications, no
    symmetrisation. Equal to the dense ``Phi P Phi^T + Q`` to rounding (tests/test_pedestrian.py), not bit for
    bit: the sums run in another order.
    """
    M = work
    for j in range(15):  # M[:9] = (Phi P)[:9], column j from row j of P
        m = _phi_row(P, j, C_dt, f_dt, dt)
        for i in range(9):
            M[i, j] = m[i]
    for i in range(9):  # rows 0-8 of Phi P Phi^T = (Phi M^T)^T from the diagonal on; the bias columns are M's
        v = _phi_row(M, i, C_dt, f_dt, dt)
        for j in range(i, 9):
            P[i, j] = P[j, i] = v[j]
        for j in range(9, 15):
            P[i, j] = P[j, i] = M[i, j]
    for i in range(15):
        P[i, i] += q[i]


def error_state_matrix(C_bn: Dcm, f_b: Vec3) -> Array:
    """F of the 15-state error model (15 x 15), ENU.

    Parameters
    ----------
    C_bn : array_like, shape (3, 3)
        Estimated attitude.
    f_b : array_like, shape (3,)
        Bias-corrected specific force (m/s^2).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.filters import zupt
    >>> F = zupt.error_state_matrix(np.eye(3), [0.0, 0.0, 9.8])
    >>> F.shape, np.round(F[3:6, 6:9], 2) + 0.0                       # velocity error from tilt: -skew(f_n)
    ((15, 15), array([[ 0. ,  9.8,  0. ],
           [-9.8,  0. ,  0. ],
           [ 0. ,  0. ,  0. ]]))
    """
    C = as_dcm(C_bn, shape=(3, 3))
    f = as_array(f_b, "f_b", shape=(3,))
    F = np.zeros((15, 15))
    F[0:3, 3:6] = np.eye(3)
    error_state_into(F, np.ascontiguousarray(C), C @ f)
    return F


def _error_rate(dx, C_true, f_true):
    """Exact time derivative of the error state for a static-Earth mechanisation.

    Truth: C' = C [w x], v' = C f + g. Estimate: C_hat = exp([dpsi x]) C,
    driven by the corrected samples f + b_a - b_a_hat = f + db_a and w + db_g.
    Then d/dt exp([dpsi x]) exp([dpsi x])^T = [(C_hat db_g) x], and the
    rotation vector moves with the inverse left Jacobian of SO(3).
    """
    dpsi, dba, dbg = dx[6:9], dx[9:12], dx[12:15]
    C_hat = attitude.rotvec_to_dcm(dpsi) @ C_true
    dv_rate = C_hat @ (f_true + dba) - C_true @ f_true
    th = np.linalg.norm(dpsi)
    c = 1 / 12 + th * th / 720 if th < 1e-4 else 1 / th**2 - (1 + np.cos(th)) / (2 * th * np.sin(th))
    S = attitude.skew(dpsi)
    dpsi_rate = (np.eye(3) - S / 2 + c * S @ S) @ (C_hat @ dbg)
    return np.concatenate([dx[3:6], dv_rate, dpsi_rate, np.zeros(6)])


@boundary
def error_model_fd(C_bn: Dcm, f_b: Vec3, eps: Positive = 1e-6) -> Array:
    """Central-difference Jacobian of the exact error dynamics at dx = 0 (checks :func:`error_state_matrix`).

    Parameters
    ----------
    C_bn : array_like, shape (3, 3)
    f_b : array_like, shape (3,)
        Specific force (m/s^2).
    eps : float
        Perturbation of each error state.

    Returns
    -------
    F : ndarray, shape (15, 15)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.filters import zupt
    >>> C_bn, f_b = np.eye(3), np.array([0.0, 0.0, 9.8])
    >>> bool(np.allclose(zupt.error_model_fd(C_bn, f_b), zupt.error_state_matrix(C_bn, f_b), atol=1e-6))
    True
    """
    C = as_dcm(C_bn, shape=(3, 3))
    f = as_array(f_b, "f_b", shape=(3,))
    F = np.empty((15, 15))
    for j in range(15):
        e = np.zeros(15)
        e[j] = eps
        F[:, j] = (_error_rate(e, C, f) - _error_rate(-e, C, f)) / (2 * eps)
    return F


@njit(cache=True)
def zupt_zaru_rows_into(H, C, w_ie_n):
    """ZUPT/ZARU rows into ``H`` (6 x 15): H[0:3, 3:6] = I, H[3:6, 6:9] = -C^T [w_ie x], H[3:6, 12:15] = I.

    Row i of ``-C^T [w x]`` is ``w x c_i``, c_i the i-th column of C; allocates nothing.
    """
    w0, w1, w2 = w_ie_n[0], w_ie_n[1], w_ie_n[2]
    for i in range(3):
        H[i, 3 + i] = 1.0
        H[3 + i, 12 + i] = 1.0
        c0, c1, c2 = C[0, i], C[1, i], C[2, i]
        H[3 + i, 6], H[3 + i, 7], H[3 + i, 8] = w1 * c2 - w2 * c1, w2 * c0 - w0 * c2, w0 * c1 - w1 * c0


@njit(cache=True)
def zupt_zaru_z_into(z, vel, w_mean, b_g, C, w_ie_n):
    """The static measurement into ``z`` (6,); compiled, unvalidated; allocates nothing."""
    for i in range(3):
        z[i] = vel[i]
        z[3 + i] = w_mean[i] - b_g[i] - (C[0, i] * w_ie_n[0] + C[1, i] * w_ie_n[1] + C[2, i] * w_ie_n[2])


@njit(cache=True)
def zupt_zaru_update_into(P, dx, z, H, r, gate):
    """Joseph-form ZUPT/ZARU update of the closed-loop error state (0 before it) in place; compiled, unvalidated.

    ``P`` (15, 15) symmetric, ``z`` (6,) the static measurement (:func:`zupt_zaru_z_into`; the innovation, the
    state being 0), ``H`` its rows (:func:`zupt_zaru_rows_into`), ``R = diag(r)``. Writes ``dx = K z`` (15,) and
    ``P = (I - K H) P (I - K H)^T + K R K^T`` (symmetric, exactly); returns ``(nis, status)``, status 1
    (accepted), -1 (``nis > gate``, or S not positive definite) or 0 (a non-finite ``z``: no measurement);
    nothing is written but for 1.

    :func:`navlib.kalman.update`'s algebra written for this H: its rows pick the velocity (``I``) and the gyro bias
    plus ``A dpsi`` (``A = H[3:6, 6:9]``), so ``H P`` and ``L H^T`` cost a few products per column instead of
    fifteen; S is solved by Cholesky (:func:`navlib._kernels.spd_solve_into`), ``dx = (H P)^T S^-1 z``, and the
    covariance loops are unrolled over the six components and fill one triangle. Equal to the generic update to
    rounding (tests/test_pedestrian.py), not bit for bit.
    """
    if not (np.isfinite(z[0]) and np.isfinite(z[1]) and np.isfinite(z[2])):
        return np.nan, 0
    if not (np.isfinite(z[3]) and np.isfinite(z[4]) and np.isfinite(z[5])):
        return np.nan, 0
    HP, KT, L, S = np.empty((6, 15)), np.empty((6, 16)), np.empty((15, 15)), np.empty((6, 6))
    a00, a01, a02 = H[3, 6], H[3, 7], H[3, 8]
    a10, a11, a12 = H[4, 6], H[4, 7], H[4, 8]
    a20, a21, a22 = H[5, 6], H[5, 7], H[5, 8]
    for j in range(15):  # H P, and a copy to solve for K^T = S^-1 H P
        p6, p7, p8 = P[6, j], P[7, j], P[8, j]
        HP[0, j], HP[1, j], HP[2, j] = P[3, j], P[4, j], P[5, j]
        HP[3, j] = P[12, j] + (a00 * p6 + a01 * p7 + a02 * p8)
        HP[4, j] = P[13, j] + (a10 * p6 + a11 * p7 + a12 * p8)
        HP[5, j] = P[14, j] + (a20 * p6 + a21 * p7 + a22 * p8)
        for a in range(6):
            KT[a, j] = HP[a, j]
    for a in range(6):  # S = H (H P)^T + R, and z beside H P
        h6, h7, h8 = HP[a, 6], HP[a, 7], HP[a, 8]
        S[a, 0], S[a, 1], S[a, 2] = HP[a, 3], HP[a, 4], HP[a, 5]
        S[a, 3] = HP[a, 12] + (a00 * h6 + a01 * h7 + a02 * h8)
        S[a, 4] = HP[a, 13] + (a10 * h6 + a11 * h7 + a12 * h8)
        S[a, 5] = HP[a, 14] + (a20 * h6 + a21 * h7 + a22 * h8)
        S[a, a] += r[a]
        KT[a, 15] = z[a]
    if not _kernels.spd_solve_into(S, KT):  # [K^T | S^-1 z]
        return np.nan, -1
    nis = 0.0
    for a in range(6):
        nis += z[a] * KT[a, 15]
    if nis > gate:
        return nis, -1
    u0, u1, u2, u3, u4, u5 = KT[0, 15], KT[1, 15], KT[2, 15], KT[3, 15], KT[4, 15], KT[5, 15]
    for j in range(15):  # dx = K z = (H P)^T S^-1 z
        dx[j] = HP[0, j] * u0 + HP[1, j] * u1 + HP[2, j] * u2 + HP[3, j] * u3 + HP[4, j] * u4 + HP[5, j] * u5
    for i in range(15):  # L = (I - K H) P = P - K H P
        k0, k1, k2, k3, k4, k5 = KT[0, i], KT[1, i], KT[2, i], KT[3, i], KT[4, i], KT[5, i]
        for j in range(15):
            L[i, j] = P[i, j] - (k0 * HP[0, j] + k1 * HP[1, j] + k2 * HP[2, j] + k3 * HP[3, j] + k4 * HP[4, j] + k5 * HP[5, j])
    for i in range(15):  # W^T = K R - L H^T, into H P (no longer needed)
        l6, l7, l8 = L[i, 6], L[i, 7], L[i, 8]
        HP[0, i] = r[0] * KT[0, i] - L[i, 3]
        HP[1, i] = r[1] * KT[1, i] - L[i, 4]
        HP[2, i] = r[2] * KT[2, i] - L[i, 5]
        HP[3, i] = r[3] * KT[3, i] - (L[i, 12] + (a00 * l6 + a01 * l7 + a02 * l8))
        HP[4, i] = r[4] * KT[4, i] - (L[i, 13] + (a10 * l6 + a11 * l7 + a12 * l8))
        HP[5, i] = r[5] * KT[5, i] - (L[i, 14] + (a20 * l6 + a21 * l7 + a22 * l8))
    for i in range(15):  # P = L (I - K H)^T + K R K^T = L + W K^T, one triangle
        w0, w1, w2, w3, w4, w5 = HP[0, i], HP[1, i], HP[2, i], HP[3, i], HP[4, i], HP[5, i]
        for j in range(i, 15):
            P[i, j] = P[j, i] = L[i, j] + (
                w0 * KT[0, j] + w1 * KT[1, j] + w2 * KT[2, j] + w3 * KT[3, j] + w4 * KT[4, j] + w5 * KT[5, j]
            )
    return nis, 1


def zupt_zaru_matrix(C_bn: Dcm, w_ie_n: Vec3) -> Array:
    """H of the ZUPT/ZARU measurement (6 x 15) at the estimated attitude, with the Earth-rate block.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import earth
    >>> from navlib.filters import zupt
    >>> zupt.zupt_zaru_matrix(np.eye(3), earth.earth_rate_n(0.6)).shape
    (6, 15)
    """
    C = as_dcm(C_bn, shape=(3, 3))
    H = np.zeros((6, 15))
    zupt_zaru_rows_into(H, np.ascontiguousarray(C), as_array(w_ie_n, "w_ie_n", shape=(3,)))
    return H


def zupt_zaru_innovation(vel_n: Vec3, w_ib_b: Vec3, b_g: Vec3, C_bn: Dcm, w_ie_n: Vec3) -> Array:
    """The static measurement ``[v_hat; w_meas - b_g_hat - C_hat^T w_ie_n]``.

    Parameters
    ----------
    vel_n : array_like, shape (3,)
        Estimated velocity (m/s).
    w_ib_b : array_like, shape (3,)
        Measured (mean) angular rate (rad/s).
    b_g : array_like, shape (3,)
        Estimated gyro bias (rad/s).
    C_bn : array_like, shape (3, 3)
        Estimated attitude.
    w_ie_n : array_like, shape (3,)
        Earth rate in ENU (rad/s).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import earth
    >>> from navlib.filters import zupt
    >>> C_bn, w_ie_n = np.eye(3), earth.earth_rate_n(0.6)
    >>> w_ib_b = C_bn.T @ w_ie_n + [1e-4, 0.0, 0.0]                  # standing still, gyro bias 1e-4 rad/s not yet estimated
    >>> np.round(zupt.zupt_zaru_innovation([0.01, 0.0, 0.0], w_ib_b, np.zeros(3), C_bn, w_ie_n), 6)
    array([0.01  , 0.    , 0.    , 0.0001, 0.    , 0.    ])
    """
    args = [as_array(a, n, shape=(3,)) for a, n in ((vel_n, "vel_n"), (w_ib_b, "w_ib_b"), (b_g, "b_g"), (w_ie_n, "w_ie_n"))]
    C = as_dcm(C_bn, shape=(3, 3))
    z = np.empty(6)
    zupt_zaru_z_into(z, args[0], args[1], args[2], np.ascontiguousarray(C), args[3])
    return z
