r"""Quaternion Kalman filter on gravity and a heading reference, driven by the Mahony PI-corrected rate.

The filter of Zhang et al. 2023 (paper 003, :mod:`navlib.papers.mimu_mag_rtk`; its equation
numbers are quoted, errata corrected). State: the quaternion ``q = q_b^n`` (4,).

* Eq. (15): the rate is the gyro corrected by the Mahony PI error of the current estimate
  (:func:`navlib.filters.observations.pi_error`, as in :mod:`navlib.filters.mahony`);
* Eqs. (16)-(17): :math:`\Phi = I + \tfrac{\Delta t}{2}\, \Omega(\omega)` (:func:`transition`);
* Eq. (18): :math:`\Gamma = \tfrac{\Delta t}{2}\, \Xi(q)` (:func:`noise_input`), :math:`Q = \sigma_{gyro}^2 I`;
* Eqs. (4), (6), (19): measurement ``z = [a; m]`` of unit vectors against
  ``h(q) = [C_nb [0, 0, 1]; C_nb b]`` with ``b = [0, cos I, -sin I]`` (Eq. 3,
  :func:`navlib.filters.observations.magnetic_reference`; north for RTK heading), innovation
  ``z - h(q)`` (:func:`measurement_model`);
* Eq. (20): Jacobian ``H = dh/dq`` (:func:`measurement_jacobian`); the Kalman update in Joseph form
  skipping missing rows, processed one scalar row at a time (below); normalise.

Without a heading reference the magnetometer rows are missing at every sample: the gravity rows
alone correct tilt. The samples arrive screened and gated (:mod:`navlib.filters.observations`, which also
says what is done with bad samples): a skipped measurement is a missing row, so a fault never enters P.

R is diagonal, so the update is sequential Kalman filtering (Simon 2006, "Optimal State Estimation", Sec. 6.1;
Brown and Hwang 2012, "Introduction to Random Signals and Applied Kalman Filtering"): the 3 or 6 rows are processed
one at a time, each a scalar Joseph update whose innovation is corrected by ``H_i (x - x_pred)`` for the rows before
it, so that the sequence is the batch update of :func:`navlib.kalman.update` rewritten, with no matrix inverted. It
equals that update to rounding (tests/test_filters_attitude.py: within 1e-12 over 5,000 steps with 0, 3 and 6 rows),
not bit for bit. The steps are written at their fixed size (4 states) without library calls or temporary arrays.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numba import njit

from .._typing import Array, Quat, Vec3, Vec3Series
from .._validate import Flag, Is, Positive, Step, as_array, as_quat, boundary, broadcast, fields_checked, flag
from ..imu import ImuSamples
from ..robust import Screened
from .observations import (
    AttitudeGates,
    AttitudeResult,
    RtkHeading,
    attitude_result,
    dcm_elements,
    integral_gain,
    jump_step,
    learning,
    magnetic_reference,
    observe,
    pack,
    pi_error,
    relock,
    rtk_north,
    run_trials,
)

__all__ = ["quaternion_kf", "KfNoise", "measurement_model", "measurement_jacobian", "transition", "noise_input"]


@dataclass(frozen=True)
class KfNoise:
    """Noise model of the quaternion KF.

    Attributes
    ----------
    sigma_gyro : float
        Gyro white-noise sigma per sample (rad/s): ``Q = sigma_gyro^2 I``.
    sigma_accel, sigma_mag : float
        Noise of the normalised accelerometer and magnetometer vectors: ``R = diag(sigma_accel^2 I,
        sigma_mag^2 I)``.
    p0 : float
        Initial covariance ``p0 I`` (also after a re-initialisation following a clock jump).

    Examples
    --------
    >>> from navlib.filters import quaternion_kf
    >>> noise = quaternion_kf.KfNoise(sigma_gyro=2e-3)               # a noisier gyro than the default
    >>> noise.sigma_gyro, noise.sigma_accel
    (0.002, 0.02)
    """

    sigma_gyro: Positive = 1e-3
    sigma_accel: Positive = 0.02
    sigma_mag: Positive = 0.08
    p0: Positive = 1e-4

    def __post_init__(self) -> None:
        fields_checked(self)


class _Model(NamedTuple):
    """Measurement and noise model of the kernel."""

    b_ref: np.ndarray  # (3,) reference [0, b_y, b_z]
    sigmas: np.ndarray  # (3,) gyro, accelerometer, magnetometer noise
    p0: float  # initial covariance p0 I
    linear_innovation: bool  # the printed z - H q (erratum E003-12), for its demonstration only


@njit(cache=True)
def _phi_into(Phi, wx, wy, wz, dt):
    """Eq. (17): Phi = I + dt/2 Omega(w)."""
    c = 0.5 * dt
    Phi[0, 0], Phi[0, 1], Phi[0, 2], Phi[0, 3] = 1.0, -c * wx, -c * wy, -c * wz
    Phi[1, 0], Phi[1, 1], Phi[1, 2], Phi[1, 3] = c * wx, 1.0, c * wz, -c * wy
    Phi[2, 0], Phi[2, 1], Phi[2, 2], Phi[2, 3] = c * wy, -c * wz, 1.0, c * wx
    Phi[3, 0], Phi[3, 1], Phi[3, 2], Phi[3, 3] = c * wz, c * wy, -c * wx, 1.0


@njit(cache=True)
def _gamma_into(G, q, dt):
    """Eq. (18) corrected: Gamma = dt/2 Xi(q)."""
    c = 0.5 * dt
    q0, q1, q2, q3 = q[0], q[1], q[2], q[3]
    G[0, 0], G[0, 1], G[0, 2] = -c * q1, -c * q2, -c * q3
    G[1, 0], G[1, 1], G[1, 2] = c * q0, -c * q3, c * q2
    G[2, 0], G[2, 1], G[2, 2] = c * q3, c * q0, -c * q1
    G[3, 0], G[3, 1], G[3, 2] = -c * q2, c * q1, c * q0


@njit(cache=True)
def _h_into(h, q, by, bz):
    """Eqs. (4), (6) corrected: h(q) = [C_nb [0,0,1]; C_nb [0, by, bz]]."""
    q0, q1, q2, q3 = q[0], q[1], q[2], q[3]
    h[0] = 2 * (q1 * q3 - q0 * q2)
    h[1] = 2 * (q2 * q3 + q0 * q1)
    h[2] = q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3
    h[3] = 2 * (q1 * q2 + q0 * q3) * by + 2 * (q1 * q3 - q0 * q2) * bz
    h[4] = (q0 * q0 - q1 * q1 + q2 * q2 - q3 * q3) * by + 2 * (q2 * q3 + q0 * q1) * bz
    h[5] = 2 * (q2 * q3 - q0 * q1) * by + (q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3) * bz


@njit(cache=True)
def _jacobian_into(H, q, by, bz):
    """Eq. (20) with the corrected H44 = 2(q0 by + q1 bz)."""
    q0, q1, q2, q3 = q[0], q[1], q[2], q[3]
    H[0, 0], H[0, 1], H[0, 2], H[0, 3] = -2 * q2, 2 * q3, -2 * q0, 2 * q1
    H[1, 0], H[1, 1], H[1, 2], H[1, 3] = 2 * q1, 2 * q0, 2 * q3, 2 * q2
    H[2, 0], H[2, 1], H[2, 2], H[2, 3] = 2 * q0, -2 * q1, -2 * q2, 2 * q3
    u, v, s, r = q3 * by - q2 * bz, q2 * by + q3 * bz, q1 * by - q0 * bz, q0 * by + q1 * bz
    H[3, 0], H[3, 1], H[3, 2], H[3, 3] = 2 * u, 2 * v, 2 * s, 2 * r
    H[4, 0], H[4, 1], H[4, 2], H[4, 3] = 2 * r, -2 * s, 2 * v, -2 * u
    H[5, 0], H[5, 1], H[5, 2], H[5, 3] = -2 * s, -2 * r, 2 * u, 2 * v


@njit(cache=True)
def _model_rows(q, b, out_h, out_H):
    for i in range(q.shape[0]):
        _h_into(out_h[i], q[i], b[i, 1], b[i, 2])
        _jacobian_into(out_H[i], q[i], b[i, 1], b[i, 2])


def _model(q, b):
    q = as_quat(q, "q", normalize=False, nonempty=True)
    b = as_array(b, "b", tail=(3,), nonempty=True)
    if np.any(b[..., 0] != 0):
        raise ValueError("b: expected reference vectors [0, b_y, b_z] (Eq. 3, magnetic north)")
    lead = broadcast(q[..., 0], b[..., 0], name="b", of="q, b")[0].shape
    qf = np.ascontiguousarray(np.broadcast_to(q, lead + (4,)).reshape(-1, 4))
    bf = np.ascontiguousarray(np.broadcast_to(b, lead + (3,)).reshape(-1, 3))
    h, H = np.empty((qf.shape[0], 6)), np.empty((qf.shape[0], 6, 4))
    _model_rows(qf, bf, h, H)
    return h.reshape(lead + (6,)), H.reshape(lead + (6, 4))


def measurement_model(q: Quat, b: Vec3) -> Array:
    """Predicted normalised measurement h(q) (Eqs. 4, 6 corrected; Eq. 19).

    Parameters
    ----------
    q : array_like, shape (..., 4)
        Quaternion q_b^n (the magnetic-north frame for the magnetometer rows).
    b : array_like, shape (..., 3)
        Reference ``[0, b_y, b_z]`` (Eq. 3).

    Returns
    -------
    h : ndarray, shape (..., 6)
        ``[C_nb [0, 0, 1]; C_nb b]``.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.filters import quaternion_kf
    >>> np.round(quaternion_kf.measurement_model([1.0, 0.0, 0.0, 0.0], [0.0, 0.5, -0.866]), 3)   # level: up, then b
    array([ 0.   ,  0.   ,  1.   ,  0.   ,  0.5  , -0.866])
    """
    return _model(q, b)[0]


def measurement_jacobian(q: Quat, b: Vec3) -> Array:
    """Jacobian ``H = dh/dq`` of :func:`measurement_model` (Eq. 20, H44 corrected); (..., 6, 4).

    Examples
    --------
    >>> from navlib.filters import quaternion_kf
    >>> quaternion_kf.measurement_jacobian([1.0, 0.0, 0.0, 0.0], [0.0, 0.5, -0.866]).shape
    (6, 4)
    """
    return _model(q, b)[1]


@boundary
def transition(w: Vec3, dt: Step) -> Array:
    r"""Quaternion transition :math:`\Phi = I + \tfrac{\Delta t}{2}\, \Omega(\omega)` (Eq. 17); w (..., 3) rad/s -> (..., 4, 4).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.filters import quaternion_kf
    >>> np.round(quaternion_kf.transition([0.0, 0.0, 1.0], 0.01), 3) + 0.0
    array([[ 1.   ,  0.   ,  0.   , -0.005],
           [ 0.   ,  1.   ,  0.005,  0.   ],
           [ 0.   , -0.005,  1.   ,  0.   ],
           [ 0.005,  0.   ,  0.   ,  1.   ]])
    """
    w = as_array(w, "w", tail=(3,), nonempty=True)
    c = 0.5 * dt
    wx, wy, wz = np.moveaxis(w, -1, 0)
    o = np.ones_like(wx)
    rows = [
        [o, -c * wx, -c * wy, -c * wz],
        [c * wx, o, c * wz, -c * wy],
        [c * wy, -c * wz, o, c * wx],
        [c * wz, c * wy, -c * wx, o],
    ]
    return np.stack([np.stack(r, -1) for r in rows], -2)


@boundary
def noise_input(q: Quat, dt: Step) -> Array:
    r"""Gyro-noise input matrix :math:`\Gamma = \tfrac{\Delta t}{2} \Xi(q)` (Eq. 18 corrected, E003-11); (..., 4) -> (..., 4, 3).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.filters import quaternion_kf
    >>> np.round(quaternion_kf.noise_input([1.0, 0.0, 0.0, 0.0], 0.01), 4) + 0.0
    array([[0.   , 0.   , 0.   ],
           [0.005, 0.   , 0.   ],
           [0.   , 0.005, 0.   ],
           [0.   , 0.   , 0.005]])
    """
    q = as_quat(q, "q", normalize=False, nonempty=True)
    q0, q1, q2, q3 = np.moveaxis(q, -1, 0)
    rows = [[-q1, -q2, -q3], [q0, -q3, q2], [q3, q0, -q1], [-q2, q1, q0]]
    return dt / 2 * np.stack([np.stack(r, -1) for r in rows], -2)


@njit(cache=True)
def _output(t, k, x, P, q_out, P_hist, keep):
    q_out[t, k, 0], q_out[t, k, 1], q_out[t, k, 2], q_out[t, k, 3] = x[0], x[1], x[2], x[3]
    if keep:
        _copy4(P_hist[t, k], P)


@njit(cache=True)
def _reset_cov(P, p0):
    """``P = p0 I`` (4 x 4) in place."""
    for i in range(4):
        for j in range(4):
            P[i, j] = p0 if i == j else 0.0


@njit(cache=True)
def _copy4(dst, src):
    """``dst[:4, :4] = src[:4, :4]`` element by element (an array assignment compiles numba's shape-mismatch
    messages, seconds of a cold start)."""
    for i in range(4):
        for j in range(4):
            dst[i, j] = src[i, j]


# --------------------------------------------------------------------------
# The Kalman steps at fixed size (4 states, 6 measurement rows), allocation-free
# --------------------------------------------------------------------------
# The per-sample cost is arithmetic, not library calls and temporary arrays. Nor reference counts: numba counts a
# reference to each array argument of a function (an atomic operation, dearer than a 4 x 4 product) unless it can
# prove the function never raises, so the per-sample steps take their arrays directly (never a tuple or record).


@njit(cache=True)
def _predict(x, P, Phi, G, q_gyro):
    """Eqs. (16)-(18) in place: ``x = Phi x``, ``P = Phi P Phi^T + Gamma Q Gamma^T`` (``Q = q_gyro I``; each
    element computed once and mirrored: symmetric exactly)."""
    A = (  # Phi P, row by row
        _row_times(Phi[0, 0], Phi[0, 1], Phi[0, 2], Phi[0, 3], P),
        _row_times(Phi[1, 0], Phi[1, 1], Phi[1, 2], Phi[1, 3], P),
        _row_times(Phi[2, 0], Phi[2, 1], Phi[2, 2], Phi[2, 3], P),
        _row_times(Phi[3, 0], Phi[3, 1], Phi[3, 2], Phi[3, 3], P),
    )
    x0, x1, x2, x3 = x[0], x[1], x[2], x[3]
    for i in range(4):
        x[i] = Phi[i, 0] * x0 + Phi[i, 1] * x1 + Phi[i, 2] * x2 + Phi[i, 3] * x3
        a = A[i]
        for j in range(i + 1):
            p = a[0] * Phi[j, 0] + a[1] * Phi[j, 1] + a[2] * Phi[j, 2] + a[3] * Phi[j, 3]
            P[i, j] = P[j, i] = p + q_gyro * (G[i, 0] * G[j, 0] + G[i, 1] * G[j, 1] + G[i, 2] * G[j, 2])


@njit(cache=True)
def _row_times(a0, a1, a2, a3, B):
    """The row ``[a0, a1, a2, a3] @ B`` (B 4 x 4), as a tuple. (Scalars, not a row index: an index given as a
    constant would compile one specialisation per row.)"""
    return (
        a0 * B[0, 0] + a1 * B[1, 0] + a2 * B[2, 0] + a3 * B[3, 0],
        a0 * B[0, 1] + a1 * B[1, 1] + a2 * B[2, 1] + a3 * B[3, 1],
        a0 * B[0, 2] + a1 * B[1, 2] + a2 * B[2, 2] + a3 * B[3, 2],
        a0 * B[0, 3] + a1 * B[1, 3] + a2 * B[2, 3] + a3 * B[3, 3],
    )


@njit(cache=True, error_model="numpy")
def _update(x, P, z, h, H, r_diag, x_pred):
    """Eq. (20)'s update of ``x``, ``P`` in place with the finite rows of ``z`` (R diagonal, ``r_diag``), one scalar
    row at a time (sequential Kalman filtering: Simon 2006, Sec. 6.1; Brown and Hwang 2012). Row i's innovation is
    ``y = z_i - h_i - H_i (x - x_pred)``, at the state the rows before it left, linearised at the predicted state
    ``x_pred`` like the batch update, of which the sequence is an exact rewriting; no matrix is inverted.

    Each row ``H_i`` updates ``x += K y`` and ``P`` in Joseph form ``P = (I - K H_i) P (I - K H_i)^T + K r K^T``, which
    for one row expands to ``P - K u^T - u K^T + s K K^T`` (``u = P H_i^T``, ``s = H_i u + r``; for any gain, and
    symmetric exactly), with ``K = u / s``. (One function: a call per row cost more than the row's arithmetic.)"""
    x_pred[0], x_pred[1], x_pred[2], x_pred[3] = x[0], x[1], x[2], x[3]
    for i in range(6):
        if not np.isfinite(z[i]):  # NaN: a skipped row
            continue
        h0, h1, h2, h3 = H[i, 0], H[i, 1], H[i, 2], H[i, 3]
        y = z[i] - h[i]
        y -= h0 * (x[0] - x_pred[0]) + h1 * (x[1] - x_pred[1]) + h2 * (x[2] - x_pred[2]) + h3 * (x[3] - x_pred[3])
        u = (
            P[0, 0] * h0 + P[0, 1] * h1 + P[0, 2] * h2 + P[0, 3] * h3,
            P[1, 0] * h0 + P[1, 1] * h1 + P[1, 2] * h2 + P[1, 3] * h3,
            P[2, 0] * h0 + P[2, 1] * h1 + P[2, 2] * h2 + P[2, 3] * h3,
            P[3, 0] * h0 + P[3, 1] * h1 + P[3, 2] * h2 + P[3, 3] * h3,
        )
        s = r_diag[i] + (h0 * u[0] + h1 * u[1] + h2 * u[2] + h3 * u[3])
        inv_s = 1.0 / s
        K = (u[0] * inv_s, u[1] * inv_s, u[2] * inv_s, u[3] * inv_s)
        for j in range(4):
            x[j] += K[j] * y
            for m in range(j + 1):
                P[j, m] = P[m, j] = P[j, m] - (K[j] * u[m] + u[j] * K[m]) + s * K[j] * K[m]


@njit(cache=True, nogil=True)
def _kernel(t0, t1, inp, kp, ki, model, q_out, bias_out, counts, P_out, P_hist):
    """Trials t0 to t1 - 1 of ``inp`` (:class:`~navlib.filters.observations.AttitudeInputs`); ``model``: :class:`_Model`."""
    for t in range(t0, t1):
        _trial(t, inp, kp, ki, model, q_out, bias_out, counts, P_out, P_hist)


@njit(cache=True, error_model="numpy")
def _trial(t, inp, kp, ki, model, q_out, bias_out, counts, P_out, P_hist):
    # Arrays are taken out of the records once, before the loop (see the note on reference counts above).
    w, dts, jump, fresh, b_ref, sigmas = inp.w, inp.dts, inp.jump, inp.fresh, model.b_ref, model.sigmas
    f, m, skip, gated, limits = inp.f, inp.m, inp.skip, inp.gated, inp.limits
    N = w.shape[1]
    keep = P_hist.shape[1] == N
    sg, sa, sm = sigmas[0], sigmas[1], sigmas[2]
    by, bz = b_ref[1], b_ref[2]
    x = inp.q_init[t].copy()
    P = np.empty((4, 4))
    _reset_cov(P, model.p0)
    r_diag = np.array([sa * sa, sa * sa, sa * sa, sm * sm, sm * sm, sm * sm])
    Phi, G, z, h, H = np.empty((4, 4)), np.empty((4, 3)), np.empty(6), np.empty(6), np.empty((6, 4))
    x_pred = np.empty(4)
    rtk = np.array([0.0, 1.0, 0.0, np.inf, 0.0, 0.0])
    held, since, checking = 0.0, np.inf, False  # learning's state; relock's check under way (its state: check)
    check = np.zeros(10)
    ix = iy = iz = 0.0
    for k in range(N):
        dt, gx, gy, gz = dts[k], w[t, k, 0], w[t, k, 1], w[t, k, 2]
        if jump[k]:  # clock jump: one typical interval, then check
            dt, since, checking = jump_step(inp, check, rtk), 0.0, True
        sm = skip[1, t, k]
        mx, my, mz = (m[t, k, 0], m[t, k, 1], m[t, k, 2]) if not sm else (0.0, 0.0, 0.0)  # (none where skipped)
        ax, ay, az, mx, my, mz, gate_a, gate_m = observe(
            f[t, k, 0], f[t, k, 1], f[t, k, 2], mx, my, mz, skip[0, t, k], sm, limits
        )
        if gate_a:  # unit vectors above, NaN where skipped; record the gates' drops
            gated[gate_a - 1, t, k] = True
        if gate_m:
            gated[gate_m + 1, t, k] = True
        C = dcm_elements(x[0], x[1], x[2], x[3])
        hx, hy, hz = rtk_north(inp, t, k, C, dt, rtk, counts) if inp.use_rtk else (mx, my, mz)
        ex, ey, ez = pi_error(C, ax, ay, az, hx, hy, hz)  # PI-corrected rate, Eq. (15)
        learn, held, since = learning(fresh[t, k], dt, held, since, inp.long_hold, inp.settle)
        if learn:  # Eq. (15), unless settling after a fault
            ix += ex * dt
            iy += ey * dt
            iz += ez * dt
        _phi_into(Phi, gx + kp * ex + ki * ix, gy + kp * ey + ki * iy, gz + kp * ez + ki * iz, dt)
        _gamma_into(G, x, dt)
        _predict(x, P, Phi, G, sg * sg)  # Eqs. (16)-(18)
        z[0], z[1], z[2], z[3], z[4], z[5] = ax, ay, az, hx, hy, hz  # NaN rows: skipped
        _jacobian_into(H, x, by, bz)  # Eq. (20)
        if model.linear_innovation:
            _linear_h(h, H, x)  # printed Eq. (19): wrong (E003-12)
        else:
            _h_into(h, x, by, bz)  # z - h(q), Eq. (19) corrected
        _update(x, P, z, h, H, r_diag, x_pred)
        s = np.sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2] + x[3] * x[3])
        x[0], x[1], x[2], x[3] = x[0] / s, x[1] / s, x[2] / s, x[3] / s
        if checking:  # after a clock jump: re-initialised only if the state is lost
            x[0], x[1], x[2], x[3], lost, since = relock(
                inp, t, k, x[0], x[1], x[2], x[3], (ax, ay, az, mx, my, mz), check, rtk, since
            )
            checking = check[0] != 0.0
            if lost:  # covariance back to p0 I
                _reset_cov(P, model.p0)
        _output(t, k, x, P, q_out, P_hist, keep)
    bias_out[t, 0], bias_out[t, 1], bias_out[t, 2] = -ki * ix, -ki * iy, -ki * iz
    _copy4(P_out[t], P)


@njit(cache=True)
def _linear_h(h, H, x):
    """``h = H x`` (the printed Eq. 19's prediction)."""
    for i in range(6):
        h[i] = H[i, 0] * x[0] + H[i, 1] * x[1] + H[i, 2] * x[2] + H[i, 3] * x[3]


@boundary
def quaternion_kf(
    imu: ImuSamples | Screened,
    q0: Quat,
    *,
    m_b: Vec3Series | None = None,
    rtk: RtkHeading | None = None,
    B_n: Vec3 | None = None,
    kp: float = 1.0,
    ki: float | None = None,
    gates: AttitudeGates = AttitudeGates(),
    noise: Is[KfNoise] = KfNoise(),
    keep_cov: Flag = False,
    linear_innovation: bool = False,
) -> AttitudeResult:
    """Quaternion Kalman filter driven by the PI-corrected rate (Eqs. 16-20, Fig. 2 of Zhang et al. 2023).

    Per sample: the Mahony error of the current estimate gives the rate (Eq. 15);
    ``Phi = I + dt/2 Omega(w)``, ``Gamma = dt/2 Xi(q)``, ``Q = sigma_gyro^2 I``;
    measurement ``z = [a; m]`` (unit vectors) against ``h(q) = [C_nb [0,0,1]; C_nb b]``
    with ``b`` from the local field (or north for RTK), ``R = diag(sigma_accel^2 I,
    sigma_mag^2 I)``; the update of :func:`navlib.kalman.update` skipping missing rows, as sequential
    scalar Joseph updates (module docstring); normalise. The covariance is predicted with
    ``Phi P Phi^T + Gamma Q Gamma^T`` and updated in Joseph form (both symmetric exactly). When the attitude is
    re-initialised after a clock jump (:func:`navlib.filters.observations.relock`) the covariance restarts at
    ``p0 I``.

    Parameters
    ----------
    imu, q0, m_b, rtk, kp, ki, gates
        As for :func:`navlib.filters.mahony.mahony`.
    B_n : array_like, shape (3,)
        Local field (uT, ENU): the KF's magnetometer reference b (Eq. 3); needed with ``m_b``.
    noise : KfNoise
        Process and measurement noise, initial covariance.
    keep_cov : bool
        Also return the covariance after every sample (``P_history``).
    linear_innovation : bool
        Use the printed innovation ``z - H q`` (E003-12: wrong; only to show that it fails).

    Returns
    -------
    AttitudeResult
        With the final covariance ``P`` (and ``P_history`` with ``keep_cov``).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude, imu, trajectory
    >>> from navlib.filters import quaternion_kf
    >>> traj = trajectory.static(3.0, 0.01, [0.6, 0.2, 50.0], np.deg2rad([30.0, 0.0, 0.0]))
    >>> B_n = np.array([0.0, 20.0, -40.0])
    >>> m_b = attitude.quat_rotate(attitude.quat_conj(traj.q_bn[1:]), B_n)   # the magnetometer's readings
    >>> q0 = attitude.euler_to_quat(np.deg2rad([25.0, 0.0, 0.0]))    # starts 5 deg off in heading
    >>> res = quaternion_kf.quaternion_kf(imu.ImuSamples(*trajectory.ideal_imu(traj), 0.01), q0, m_b=m_b, B_n=B_n)
    >>> np.round(np.rad2deg(attitude.quat_to_euler(res.q_bn[[0, -1]])), 1) + 0.0   # the heading error shrinks
    array([[25.1,  0. , -0.1],
           [29.3,  0.1, -0.1]])
    """
    lead, inp, found = pack(imu, q0, m_b, rtk, B_n, gates, kp)
    kp = float(kp)  # checked by pack
    if inp.use_mag and B_n is None:
        raise ValueError("B_n: the quaternion KF needs the local field for its magnetometer reference")
    ki = integral_gain(ki, inp.use_mag or inp.use_rtk)
    T, N = inp.w.shape[:2]
    b = magnetic_reference(B_n)[0] if inp.use_mag and B_n is not None else np.array([0.0, 1.0, 0.0])  # RTK: north
    sig = np.array([noise.sigma_gyro, noise.sigma_accel, noise.sigma_mag], dtype=float)
    model = _Model(b, sig, float(noise.p0), flag(linear_innovation, "linear_innovation"))
    q_out, bias, counts = np.empty((T, N, 4)), np.empty((T, 3)), np.zeros((T, 4), dtype=np.int64)
    P_out, P_hist = np.empty((T, 4, 4)), np.empty((T, N if keep_cov else 0, 4, 4))
    run_trials(_kernel, T, inp, kp, ki, model, q_out, bias, counts, P_out, P_hist)
    return attitude_result(lead, inp, q_out, bias, counts, found, P_out, P_hist if keep_cov else None)
