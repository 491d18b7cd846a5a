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
:func:`error_state_predict_into`, the covariance prediction with ``Phi = I + F dt`` that multiplies only
Phi's non-zero blocks.
Used by paper 004 (Wen et al. 2016, :mod:`navlib.papers.pedestrian_ins`), which assembles them
with barometer and magnetometer aiding into its filter.
"""

from __future__ import annotations

import numpy as np
from numba import njit
from numpy.typing import NDArray

from .. import analysis, attitude
from .._kernels import fma
from .._typing import Array, ArrayLike, Dcm, Vec3, Vec3Series
from .._validate import as_array, as_dcm, imu_samples, interval, positive, scalar
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


def detect_static(
    w_ib_b: Vec3Series | ImuSamples,
    f_b: Vec3Series | None = None,
    dt: float | None = None,
    window: float = 0.5,
    gyro_bias: Vec3 = (0.0, 0.0, 0.0),
    thresholds: ArrayLike = STATIC_THRESHOLDS,
    g: float = G0,
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
    tw, tf, tg = positive(as_array(thresholds, "thresholds", shape=(3,)), "thresholds")
    g = scalar(g, "g", positive=True)
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
def skew_1(v):
    """``[v x]`` of one vector; compiled."""
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])


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
def _transition_into(out, A, C_dt, f_dt, dt):
    """``out = Phi A`` (15 x 15) for ``Phi = I + F dt``, F of :func:`error_state_into` with ``C dt`` and ``f_n dt``.

    Only Phi's non-zero entries are multiplied; each sum keeps the order of a dense product (k ascending,
    the diagonal 1 first, one fused multiply-add per term, as BLAS's dgemm), so that skipping the zero
    terms (exact zeros added) changes no bit for finite A.
    """
    f0, f1, f2 = f_dt[0], f_dt[1], f_dt[2]
    for j in range(15):
        for a in range(3):  # position rows: I, I dt
            out[a, j] = fma(dt, A[3 + a, j], A[a, j] + 0.0)
        # velocity rows: I, -[f_n dt x] (zero diagonal), C dt
        out[3, j] = fma(
            C_dt[0, 2],
            A[11, j],
            fma(C_dt[0, 1], A[10, j], fma(C_dt[0, 0], A[9, j], fma(-f1, A[8, j], fma(f2, A[7, j], A[3, j] + 0.0)))),
        )
        out[4, j] = fma(
            C_dt[1, 2],
            A[11, j],
            fma(C_dt[1, 1], A[10, j], fma(C_dt[1, 0], A[9, j], fma(f0, A[8, j], fma(-f2, A[6, j], A[4, j] + 0.0)))),
        )
        out[5, j] = fma(
            C_dt[2, 2],
            A[11, j],
            fma(C_dt[2, 1], A[10, j], fma(C_dt[2, 0], A[9, j], fma(-f0, A[7, j], fma(f1, A[6, j], A[5, j] + 0.0)))),
        )
        for a in range(3):  # attitude rows: I, C dt
            out[6 + a, j] = fma(C_dt[a, 2], A[14, j], fma(C_dt[a, 1], A[13, j], fma(C_dt[a, 0], A[12, j], A[6 + a, j] + 0.0)))
        for i in range(9, 15):  # bias rows: I
            out[i, j] = A[i, j] + 0.0


@njit(cache=True)
def error_state_predict_into(P, C_dt, f_dt, dt, q, work):
    """``P = Phi P Phi^T + diag(q)`` (symmetrised) in place, ``Phi = I + F dt``; compiled, unvalidated.

    ``C_dt`` = C dt (3 x 3), ``f_dt`` = (C f_b) dt (3,), ``q`` the diagonal process noise (15,), ``work`` a
    (2, 15, 15) scratch: nothing is allocated. Exploits Phi's identity and zero blocks (:func:`_transition_into`)
    and gives :func:`navlib._kernels.kalman_predict`'s covariance for that Phi and ``Q = diag(q)`` bit for bit
    where BLAS's dgemm sums in order with fused multiply-adds (OpenBLAS on x86-64), to rounding elsewhere.
    """
    FP, FPT = work[0], work[1]
    _transition_into(FP, P, C_dt, f_dt, dt)  # Phi P
    for i in range(15):
        for j in range(15):
            FPT[j, i] = FP[i, j]
    MT = work[0]
    _transition_into(MT, FPT, C_dt, f_dt, dt)  # (Phi P Phi^T)^T = Phi (Phi P)^T
    for i in range(15):
        MT[i, i] += q[i]
    for i in range(15):  # (M + M^T) / 2, one half computed
        for j in range(i, 15):
            P[i, j] = P[j, i] = (MT[j, i] + MT[i, j]) / 2


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
    C = as_dcm(as_array(C_bn, "C_bn", shape=(3, 3)))
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


def error_model_fd(C_bn: Dcm, f_b: Vec3, eps: float = 1e-6) -> Array:
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
    C = as_dcm(as_array(C_bn, "C_bn", shape=(3, 3)))
    f = as_array(f_b, "f_b", shape=(3,))
    eps = scalar(eps, "eps", positive=True)
    F = np.empty((15, 15))
    for j in range(15):
        e = np.zeros(15)
        e[j] = eps
        F[:, j] = (_error_rate(e, C, f) - _error_rate(-e, C, f)) / (2 * eps)
    return F


@njit(cache=True)
def zupt_zaru_rows_into(H, C, w_ie_n):
    """ZUPT/ZARU rows into ``H`` (6 x 15): H[0:3, 3:6] = I, H[3:6, 6:9] = -C^T [w_ie x], H[3:6, 12:15] = I."""
    A = -(C.T @ skew_1(w_ie_n))
    for i in range(3):
        H[i, 3 + i] = 1.0
        H[3 + i, 12 + i] = 1.0
        for j in range(3):
            H[3 + i, 6 + j] = A[i, j]


@njit(cache=True)
def zupt_zaru_z_into(z, vel, w_mean, b_g, C, w_ie_n):
    """The static measurement into ``z`` (6,); compiled, unvalidated."""
    ce = C.T @ w_ie_n
    for i in range(3):
        z[i] = vel[i]
        z[3 + i] = w_mean[i] - b_g[i] - ce[i]


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
    C = as_dcm(as_array(C_bn, "C_bn", shape=(3, 3)))
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
    C = as_dcm(as_array(C_bn, "C_bn", shape=(3, 3)))
    z = np.empty(6)
    zupt_zaru_z_into(z, args[0], args[1], args[2], np.ascontiguousarray(C), args[3])
    return z
