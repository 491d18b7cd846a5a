r"""Kalman filter building blocks: predict, Joseph-form update, discretisation.

The predict and update are written once as compiled per-sample primitives (numba),
:func:`navlib._kernels.kalman_predict` and :func:`navlib._kernels.kalman_update`, which
navlib's filters call inside their own compiled loops (and which run as plain Python with
``NUMBA_DISABLE_JIT=1``). :func:`predict` and :func:`update` here are their public,
validated Python wrappers: arguments are converted to float64 (lists, float32 and integer
arrays are accepted; the caller's arrays are never modified) and every shape is checked,
so a wrong argument raises ``ValueError`` naming it instead of being broadcast or read past
its end.

The update is the standard (E)KF update with the covariance in Joseph form,
:math:`P \leftarrow (I - K H) P (I - K H)^T + K R K^T`, which stays symmetric positive
definite under rounding and suboptimal gains. It takes the *predicted
measurement* ``h`` (``H x`` for a linear filter, ``h(x)`` for an EKF), so the
innovation is ``z - h``, with angle components wrapped to (-pi, pi].
Measurement components that are NaN (sensor dropouts) are left out of the
update; an innovation whose normalised squared size (NIS) exceeds ``gate``
is rejected and reported, never silently applied.
"""

from __future__ import annotations

from typing import Annotated, Any

import numpy as np
from scipy.linalg import expm

from . import _kernels
from ._typing import Array, ArrayLike
from ._validate import Check, Step, as_array, booleans, boundary, kernel_array, same_shape

__all__ = ["predict", "update", "discretize", "ACCEPTED", "NO_DATA", "REJECTED"]

ACCEPTED, NO_DATA, REJECTED = 1, 0, -1
"""Status codes returned by :func:`update`."""


def _matrix(a: ArrayLike, name: str, shape: tuple[int | None, ...], **kwargs: Any) -> np.ndarray:
    """``a`` as a C-contiguous float64 array of exactly ``shape``, finite unless ``kwargs`` say otherwise."""
    return kernel_array(as_array(a, name, shape=shape, **kwargs))


def _state(x: ArrayLike, P: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """A non-empty state vector ``x`` (n,) and its covariance ``P`` (n, n)."""
    x = kernel_array(as_array(x, "x", shape=(None,), nonempty=True))
    return x, _matrix(P, "P", (x.shape[0], x.shape[0]), of="x")


def predict(x: ArrayLike, P: ArrayLike, F: ArrayLike, Q: ArrayLike) -> tuple[Array, Array]:
    r"""Linear prediction :math:`x \leftarrow F x`, :math:`P \leftarrow F P F^T + Q` (symmetrised).

    Validates its arguments, then runs the compiled primitive
    :func:`navlib._kernels.kalman_predict` (which navlib's own compiled filters call directly).

    Parameters
    ----------
    x : array_like, shape (n,)
        State, n >= 1.
    P, F, Q : array_like, shape (n, n)
        Covariance, transition matrix and process noise; a scalar or otherwise
        shaped ``Q`` is an error, not broadcast.

    Returns
    -------
    x, P : ndarray
        Float64 arrays of shapes (n,) and (n, n) (new arrays; the arguments are not modified).

    Raises
    ------
    ValueError
        Naming the argument: wrong shape, empty ``x``, non-finite values, or not real numbers.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import kalman
    >>> x, P = kalman.predict(np.array([0.0, 1.0]), np.eye(2), np.array([[1.0, 0.1], [0.0, 1.0]]), 0.01 * np.eye(2))
    >>> x, np.round(P, 3)
    (array([0.1, 1. ]), array([[1.02, 0.1 ],
           [0.1 , 1.01]]))
    """
    x, P = _state(x, P)
    n = x.shape[0]
    return _kernels.kalman_predict(x, P, _matrix(F, "F", (n, n), of="x"), _matrix(Q, "Q", (n, n), of="x"))


@boundary
def update(
    x: ArrayLike,
    P: ArrayLike,
    z: ArrayLike,
    h: ArrayLike,
    H: ArrayLike,
    R: ArrayLike,
    angle_mask: ArrayLike,
    gate: Annotated[float, Check("scalar", positive=True, allow_inf=True)] = np.inf,
) -> tuple[Array, Array, Array, float, int]:
    """Joseph-form measurement update that skips NaN components.

    Validates its arguments, then runs the compiled primitive
    :func:`navlib._kernels.kalman_update` (which navlib's own compiled filters call directly).

    Parameters
    ----------
    x : array_like, shape (n,)
        Prior state, n >= 1.
    P : array_like, shape (n, n)
        Prior covariance.
    z : array_like, shape (m,)
        Measurement; NaN components are not used (m = 0 or all NaN: nothing to
        update, status ``NO_DATA``). Infinite values are an error.
    h : array_like, shape (m,)
        Predicted measurement (``H x`` or ``h(x)``).
    H : array_like, shape (m, n)
        Measurement matrix or Jacobian.
    R : array_like, shape (m, m)
        Measurement noise covariance.
    angle_mask : array_like of bool, shape (m,)
        Components whose innovation is an angle to wrap into (-pi, pi].
    gate : float
        Reject the update when the NIS ``y^T S^-1 y`` exceeds this value
        (e.g. a chi-square quantile); ``inf`` accepts everything. Must be
        positive (NaN is an error: it would switch the gate off).

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

    Raises
    ------
    ValueError
        Naming the argument: shapes that do not agree with ``x`` and ``z``, empty
        ``x``, non-finite values (other than NaN in ``z``), a mask that is not
        boolean, a gate that is not positive, or values that are not real numbers.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import kalman
    >>> x, P = np.array([0.0, 1.0]), np.eye(2)
    >>> H = np.array([[1.0, 0.0]])
    >>> x, P, nu, nis, used = kalman.update(x, P, np.array([0.5]), H @ x, H, np.array([[1.0]]), np.array([False]))
    >>> np.round(x, 3), np.round(np.diag(P), 3), used                  # half-way to the measurement: equal variances
    (array([0.25, 1.  ]), array([0.5, 1. ]), 1)
    """
    x, P = _state(x, P)
    z = _matrix(z, "z", (None,), allow_nan=True)
    m, n = z.shape[0], x.shape[0]
    h = _matrix(h, "h", (m,), of="z")
    H = _matrix(H, "H", (m, n), of="z, x")
    R = _matrix(R, "R", (m, m), of="z")
    angle_mask = kernel_array(booleans(angle_mask, "angle_mask", shape=(m,)))
    return _kernels.kalman_update(x, P, z, h, H, R, angle_mask, gate)


@boundary
def discretize(F: ArrayLike, G: ArrayLike, Qc: ArrayLike, dt: Step) -> tuple[Array, Array]:
    r"""Discretise a continuous linear model by Van Loan's method.

    For :math:`\dot x = F x + G w` with white noise of spectral density :math:`Q_c`, returns

    .. math::

        \Phi = e^{F \Delta t}, \qquad Q_d = \int_0^{\Delta t} e^{F s}\, G Q_c G^T\, e^{F^T s}\, ds.

    Parameters
    ----------
    F : array_like, shape (n, n)
    G : array_like, shape (n, p)
    Qc : array_like, shape (p, p)
    dt : float  (s)

    Returns
    -------
    Phi, Qd : ndarray, shape (n, n)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import kalman
    >>> F = np.array([[0.0, 1.0], [0.0, 0.0]])                      # position, velocity
    >>> G = np.array([[0.0], [1.0]])                                 # white acceleration noise
    >>> Phi, Qd = kalman.discretize(F, G, np.array([[1.0]]), dt=0.1)
    >>> Phi, np.round(Qd, 6)                                          # Qd = [[dt^3/3, dt^2/2], [dt^2/2, dt]]
    (array([[1. , 0.1],
           [0. , 1. ]]), array([[0.000333, 0.005   ],
           [0.005   , 0.1     ]]))
    """
    F = as_array(F, "F", shape=(None, None), nonempty=True)
    n = len(F)
    same_shape(F, "F", (n, n))  # square
    G = as_array(G, "G", shape=(n, None), of="F")  # n rows
    Qc = as_array(Qc, "Qc", shape=(G.shape[1], G.shape[1]), of="G")  # (p, p), p the columns of G
    M = np.zeros((2 * n, 2 * n))
    M[:n, :n] = -F
    M[:n, n:] = G @ Qc @ G.T
    M[n:, n:] = F.T
    E = expm(M * dt)
    Phi = kernel_array(E[n:, n:].T)
    Qd = Phi @ E[:n, n:]
    return Phi, (Qd + Qd.T) / 2
