"""Kalman filter building blocks: predict, Joseph-form update, discretisation.

Written once as compiled per-sample functions (numba) so that the papers'
filters can call them inside their own compiled loops; they also run from
Python, and as plain Python with ``NUMBA_DISABLE_JIT=1``.

The update is the standard (E)KF update with the covariance in Joseph form,
``P = (I - K H) P (I - K H)^T + K R K^T``, which stays symmetric positive
definite under rounding and suboptimal gains. It takes the *predicted
measurement* ``h`` (``H x`` for a linear filter, ``h(x)`` for an EKF), so the
innovation is ``z - h``, with angle components wrapped to (-pi, pi].
Measurement components that are NaN (sensor dropouts) are left out of the
update; an innovation whose normalised squared size (NIS) exceeds ``gate``
is rejected and reported, never silently applied.
"""
from __future__ import annotations

import numpy as np
from numba import njit
from scipy.linalg import expm

from ._kernels import wrap_pi
from ._typing import Array, ArrayLike
from ._validate import as_array, nonempty_array, positive, same_shape

__all__ = ["predict", "update", "discretize", "ACCEPTED", "NO_DATA", "REJECTED"]

ACCEPTED, NO_DATA, REJECTED = 1, 0, -1
"""Status codes returned by :func:`update`."""


@njit(cache=True)
def predict(x, P, F, Q):
    """Linear prediction ``x = F x``, ``P = F P F^T + Q`` (symmetrised).

    Parameters
    ----------
    x : ndarray, shape (n,)
    P, F, Q : ndarray, shape (n, n)

    Returns
    -------
    x, P : ndarray
    """
    Pn = F @ P @ np.ascontiguousarray(F.T) + Q
    return F @ x, (Pn + Pn.T) / 2


@njit(cache=True)
def update(x, P, z, h, H, R, angle_mask, gate=np.inf):
    """Joseph-form measurement update that skips NaN components.

    Parameters
    ----------
    x : ndarray, shape (n,)
        Prior state.
    P : ndarray, shape (n, n)
        Prior covariance.
    z : ndarray, shape (m,)
        Measurement; NaN components are not used.
    h : ndarray, shape (m,)
        Predicted measurement (``H x`` or ``h(x)``).
    H : ndarray, shape (m, n)
        Measurement matrix or Jacobian.
    R : ndarray, shape (m, m)
        Measurement noise covariance.
    angle_mask : ndarray of bool, shape (m,)
        Components whose innovation is an angle to wrap into (-pi, pi].
    gate : float
        Reject the update when the NIS ``y^T S^-1 y`` exceeds this value
        (e.g. a chi-square quantile); ``inf`` accepts everything.

    Returns
    -------
    x, P : ndarray
        Posterior (the prior, copied, when nothing is used or the gate rejects).
    y : ndarray, shape (m,)
        Innovation (NaN where the component was missing).
    nis : float
        Normalised innovation squared (NaN when no component was available).
    status : int
        ``ACCEPTED`` (1), ``NO_DATA`` (0) or ``REJECTED`` (-1).
    """
    m = z.shape[0]
    finite = np.isfinite(z)
    n_used = int(finite.sum())
    if n_used == 0:
        return x.copy(), P.copy(), np.full(m, np.nan), np.nan, 0
    y = z - h
    for j in range(m):
        if angle_mask[j] and finite[j]:
            y[j] = wrap_pi(y[j])
    if n_used == m:                      # common case: no dropout, no copies
        Hs, Rs, ys = H, R, y
    else:
        idx = np.nonzero(finite)[0]
        Hs = np.ascontiguousarray(H[idx, :])
        Rs = np.ascontiguousarray(R[idx][:, idx])
        ys = y[idx]
    PHt = P @ np.ascontiguousarray(Hs.T)
    S = Hs @ PHt + Rs
    S_inv = np.linalg.inv((S + S.T) / 2)
    nis = ys @ S_inv @ ys
    if nis > gate:
        return x.copy(), P.copy(), y, nis, -1
    K = PHt @ S_inv
    IKH = np.eye(x.shape[0]) - K @ Hs
    Pn = IKH @ P @ np.ascontiguousarray(IKH.T) + K @ Rs @ np.ascontiguousarray(K.T)
    return x + K @ ys, (Pn + Pn.T) / 2, y, nis, 1


def discretize(F: ArrayLike, G: ArrayLike, Qc: ArrayLike, dt: float) -> tuple[Array, Array]:
    """Discretise a continuous linear model by Van Loan's method.

    For ``dx/dt = F x + G w`` with white noise of spectral density ``Qc``,
    returns ``Phi = expm(F dt)`` and
    ``Qd = integral_0^dt expm(F s) G Qc G^T expm(F s)^T ds``.

    Parameters
    ----------
    F : array_like, shape (n, n)
    G : array_like, shape (n, p)
    Qc : array_like, shape (p, p)
    dt : float  (s)

    Returns
    -------
    Phi, Qd : ndarray, shape (n, n)
    """
    F = nonempty_array(F, "F", shape=(None, None))
    n = len(F)
    same_shape(F, "F", (n, n))                                   # square
    G = as_array(G, "G", shape=(n, None))                        # n rows
    Qc = as_array(Qc, "Qc", shape=(G.shape[1], G.shape[1]))      # (p, p), p the columns of G
    dt = float(positive(dt, "dt"))
    M = np.zeros((2 * n, 2 * n))
    M[:n, :n] = -F
    M[:n, n:] = G @ Qc @ G.T
    M[n:, n:] = F.T
    E = expm(M * dt)
    Phi = np.ascontiguousarray(E[n:, n:].T)
    Qd = Phi @ E[:n, n:]
    return Phi, (Qd + Qd.T) / 2
