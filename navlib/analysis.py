"""Error statistics and Allan-variance analysis.

Allan deviation follows IEEE Std 952-1997 (overlapping estimator). The
noise model used by :mod:`navlib.sensors` and fitted by :func:`fit_allan` is

    sigma_A^2(tau) = N^2 / tau                       (white rate noise, ARW)
                   + sigma_gm^2 g(tau / T_c)         (first-order Gauss-Markov bias)
                   + K^2 tau / 3                     (rate random walk)

with ``g(u) = (2/u) [1 - (3 - 4 e^-u + e^-2u) / (2u)]``, the Allan variance of
a unit-variance Gauss-Markov process with correlation time T_c (e.g.
El-Sheimy, Hou & Niu 2008). A Gauss-Markov Allan deviation peaks at
``GM_ALLAN_PEAK * sigma_gm`` at ``tau = GM_ALLAN_PEAK_TAU * T_c``; navlib
calls that peak the *bias instability* B, which is how the in-run bias
stability of a datasheet (the flat part of the Allan curve) is mapped onto
a Gauss-Markov process.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Annotated

import numpy as np
from numba import njit

from . import _attitude, _earth, _kernels, _lsq, _noise, attitude, earth
from ._typing import Angles, Array, ArrayLike, Times, Vec3
from ._validate import (
    Check,
    Count,
    Flag,
    Positive,
    Real,
    Step,
    as_array,
    booleans,
    boundary,
    broadcast,
    flag,
    integer,
    kernel_array,
    last_axis,
    latitude,
    positive,
    same_shape,
    scalar,
    time_axis,
)

__all__ = [
    "rmse",
    "allan_deviation",
    "allan_deviation_theory",
    "fit_allan",
    "GM_ALLAN_PEAK",
    "GM_ALLAN_PEAK_TAU",
    "ALLAN_EVIDENCE",
    "attitude_errors",
    "error_statistics",
    "horizontal_error",
    "position_error",
    "expanding_std",
    "detection_rates",
    "settling_time",
    "segments",
    "moving_mean",
    "normal_condition",
    "condition_number",
    "lsq_covariance",
    "cramer_rao_bound",
    "footfall_path_length",
    "OrientationErrors",
    "orientation_errors",
    "time_offset",
]


def rmse(err: ArrayLike, axis: int | tuple[int, ...] | None = 0) -> Array:
    """Root mean square of ``err`` along ``axis`` (NaN propagates: no silent dropping).

    Examples
    --------
    >>> from navlib import analysis
    >>> analysis.rmse([[1.0, -2.0], [-1.0, 2.0]])
    array([1., 2.])
    """
    err = as_array(err, "err", allow_nan=True, nonempty=True)
    if axis is not None:
        for a in axis if isinstance(axis, tuple) else (axis,):
            if not -err.ndim <= integer(a, "axis", minimum=None) < err.ndim:
                raise ValueError(f"axis: expected axes of err (shape {err.shape}), got {axis!r}")
    return np.sqrt(np.mean(err * err, axis=axis))


def _peak():
    from scipy.optimize import minimize_scalar  # noqa: PLC0415 -- tests only (the constants below are its result)

    res = minimize_scalar(lambda u: -_noise.gm_allan_var_unit(u), bounds=(0.1, 10.0), method="bounded", options={"xatol": 1e-10})
    return float(np.sqrt(-res.fun)), float(res.x)


GM_ALLAN_PEAK, GM_ALLAN_PEAK_TAU = _noise.GM_ALLAN_PEAK, _noise.GM_ALLAN_PEAK_TAU
"""Peak Allan deviation of a unit-variance Gauss-Markov process (~0.6174), and
the tau of the peak in units of the correlation time (~1.893): the result of ``_peak()`` (a bounded
maximisation), written out so that ``import navlib`` does not import scipy.optimize
(tests/test_analysis.py recomputes them)."""
ALLAN_EVIDENCE = _noise.ALLAN_EVIDENCE
"""A model fits an Allan-deviation curve if its largest miss, where the terms show, is no more improbable than a miss
of this many standard errors in one comparison; a term is needed if no model without it fits (:func:`fit_allan`)."""


@boundary
def allan_deviation(x: ArrayLike, dt: Step, taus: ArrayLike | None = None) -> tuple[Array, Array]:
    """Overlapping Allan deviation of rate samples.

    Parameters
    ----------
    x : array_like, shape (N,) or (..., N, k)
        Rate samples (e.g. gyro output in rad/s) at interval ``dt``; time on
        axis -2 for vector series.
    dt : float
        Sample interval (s).
    taus : array_like, optional
        Averaging times (s); rounded to whole multiples of ``dt``. Default:
        about 10 per decade from ``dt`` to a third of the record.

    Returns
    -------
    taus : ndarray, shape (M,)
        Averaging times actually used (s).
    adev : ndarray, shape (M,) or (..., M, k)
        Allan deviation in the units of ``x``.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import analysis
    >>> rng = np.random.default_rng(0)
    >>> x = 0.01 * rng.standard_normal(10_000)                      # white noise, 0.01 per sample at dt = 0.1 s
    >>> taus, adev = analysis.allan_deviation(x, 0.1, taus=[0.1, 1.0, 10.0])
    >>> taus, np.round(adev, 4)                                       # falls as 1/sqrt(tau)
    (array([ 0.1,  1. , 10. ]), array([0.01  , 0.0032, 0.0012]))
    """
    x = as_array(x, "x")
    series = x[:, None] if x.ndim == 1 else x
    if series.ndim < 2 or series.shape[-2] < 9:
        raise ValueError(f"x: expected at least 9 samples on axis -2, got shape {series.shape}")
    n = series.shape[-2]
    m = _noise.cluster_lengths(n, dt, None if taus is None else positive(taus, "taus"))
    if taus is not None and (m.min() < 1 or m.max() > (n - 1) // 2):
        raise ValueError(f"taus: expected values between dt and {(n - 1) // 2 * dt:g} s")
    return _noise.deviation(x, dt, m)


@boundary
def allan_deviation_theory(
    taus: ArrayLike,
    white: float = 0.0,
    bias_instability: float = 0.0,
    correlation_time: Positive = 1.0,
    rate_random_walk: float = 0.0,
) -> Array:
    """Allan deviation of navlib's sensor noise model (module docstring).

    Parameters
    ----------
    taus : array_like (s)
    white : float
        White-noise density N (units/sqrt(Hz), e.g. rad/s/sqrt(Hz) = ARW).
    bias_instability : float
        Peak Allan deviation B of the Gauss-Markov bias (units).
    correlation_time : float
        Gauss-Markov correlation time T_c (s).
    rate_random_walk : float
        K (units/s/sqrt(Hz)).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import analysis
    >>> np.round(analysis.allan_deviation_theory([1.0, 100.0], white=1e-3), 6)   # N / sqrt(tau)
    array([0.001 , 0.0001])
    """
    taus = positive(taus, "taus", nonempty=True)
    white, bias_instability, rate_random_walk = (
        scalar(v, name, allow_zero=True)
        for v, name in ((white, "white"), (bias_instability, "bias_instability"), (rate_random_walk, "rate_random_walk"))
    )
    return _noise.theory(taus, white, bias_instability, correlation_time, rate_random_walk)


@boundary
def fit_allan(taus: ArrayLike, adev: ArrayLike, n_samples: Count, dt: Step, *, rate_random_walk: bool = False) -> dict:
    """Fit the noise model to an Allan-deviation curve by weighted least squares.

    The residuals are log-deviations weighted by the approximate number of
    independent clusters, ``sqrt(n_samples / m)``, so long averaging times
    (few clusters, large scatter) count less. Each term beyond white noise is kept only if the data ask for it:
    every model (white noise with or without the bias instability and, with ``rate_random_walk``, with or
    without K) is fitted and compared with the measured deviation where the terms show (the full model's
    bias-instability peak and, with K, the last decade of averaging times). A model *fits* if its largest miss
    there, in standard errors of the measured log-deviation (random-walk edf, the widest), is no more
    improbable than a miss of :data:`ALLAN_EVIDENCE` in one comparison (Sidak's correction for the number
    of averaging times compared). The fitting model of fewest parameters is chosen (white + K, two, before
    white + B, three: a Gauss-Markov bias whose peak sits at the end of the record mimics a random walk),
    the lowest cost between equals; the full model if none fits. A term's ``evidence`` is the smallest miss
    of the models without it: at most :data:`ALLAN_EVIDENCE`, the data do not need the term (it may be
    kept where either of two terms explains the curve; :func:`navlib.calibration.characterise` then
    starts its interval at 0). Without this, a fit of every term trades a random walk or white noise for
    an invented bias instability where their curves are alike.

    Parameters
    ----------
    taus, adev : array_like, shape (M,)
        Output of :func:`allan_deviation` for one axis.
    n_samples : int
        Record length in samples.
    dt : float
        Sample interval (s).
    rate_random_walk : bool
        Also fit a rate-random-walk term.

    Returns
    -------
    dict
        ``white`` (N), ``bias_instability`` (B; 0 when left out), ``correlation_time`` (s; meaningless when B
        is 0: the full model's) and ``rate_random_walk`` (K; 0 unless fitted and chosen), in the units of
        ``adev``; ``evidence``: (B, K), the smallest miss, in Sidak-corrected standard errors, of the models
        without the term (the term is needed above :data:`ALLAN_EVIDENCE`; ``-inf`` for K when it is not
        fitted); ``sensitivity``, shape (4, M): the first-order change of log N, log B, log T_c and log K
        of the chosen model's fit per change of the log-deviations (rows of absent terms 0), through which
        :func:`navlib.calibration.characterise` carries the scatter of the Allan deviation to the terms;
        ``adequate``, shape (A, 4): ``[N, B, T_c, K]`` of every model that fits within :data:`ALLAN_EVIDENCE`
        (the chosen one among them; the full model alone if none does): the terms' model uncertainty.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import analysis
    >>> taus = np.geomspace(0.1, 100.0, 13)
    >>> adev = analysis.allan_deviation_theory(taus, white=1e-3, bias_instability=1e-4, correlation_time=10.0)
    >>> fit = analysis.fit_allan(taus, adev, n_samples=100_000, dt=0.01)
    >>> sorted(fit)
    ['adequate', 'bias_instability', 'correlation_time', 'evidence', 'rate_random_walk', 'sensitivity', 'white']
    >>> round(float(fit["white"]), 6)
    0.001001
    """
    taus = positive(taus, "taus")
    adev = positive(adev, "adev")
    if taus.ndim != 1 or taus.size < 3:
        raise ValueError(f"taus: expected a 1-D array of at least 3 averaging times, got shape {taus.shape}")
    same_shape(adev, "adev", taus.shape, of="taus")
    return _noise.fit(taus, adev, n_samples, dt, flag(rate_random_walk, "rate_random_walk"))


# --------------------------------------------------------------------------
# Error statistics of estimated attitude and position
# --------------------------------------------------------------------------


@njit(cache=True)
def _error_stats_kernel(hpr, truth):
    T, N = hpr.shape[0], hpr.shape[1]
    mx = np.zeros((T, 3))
    mean = np.zeros((T, 3))
    for t in range(T):
        tt = t if truth.shape[0] > 1 else 0  # one truth shared by all runs, or one per run
        for i in range(N):
            for a in range(3):
                e = hpr[t, i, a] - truth[tt, i, a]
                e = abs(_kernels.wrap_pi(e))
                mean[t, a] += e
                if e > mx[t, a]:
                    mx[t, a] = e
        for a in range(3):
            mean[t, a] /= N
    return mx, mean


def attitude_errors(hpr: Angles, hpr_true: Angles) -> Array:
    """Euler-angle errors ``hpr - hpr_true`` wrapped into (-pi, pi] (rad).

    Parameters
    ----------
    hpr, hpr_true : array_like, shape (..., 3)
        ``[heading, pitch, roll]``; shapes broadcast.

    Returns
    -------
    err : ndarray, shape (..., 3)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import analysis
    >>> np.round(analysis.attitude_errors([6.2, 0.1, 0.0], [0.1, 0.1, 0.0]), 6)   # heading wraps across north
    array([-0.183185,  0.      ,  0.      ])
    """
    a = as_array(hpr, "hpr", tail=(3,), nonempty=True)
    b = as_array(hpr_true, "hpr_true", tail=(3,), nonempty=True)
    return attitude.wrap_pi(a - b)


def error_statistics(hpr: Angles, hpr_true: Angles) -> tuple[Array, Array]:
    """Max and mean |attitude error| over time, in one pass (e.g. the statistics of paper 001, Table 2).

    Parameters
    ----------
    hpr : array_like, shape (..., N, 3)
        Estimated ``[heading, pitch, roll]`` (rad).
    hpr_true : array_like, shape (N, 3) or (..., N, 3)
        True attitude (rad); broadcast over the leading axes of ``hpr``.

    Returns
    -------
    max_abs, mean_abs : ndarray, shape (..., 3)
        Largest and mean wrapped |error| over time (rad).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import analysis
    >>> hpr_true = np.zeros((3, 3))
    >>> hpr = np.deg2rad([[1.0, 0.0, 0.0], [-2.0, 0.5, 0.0], [0.0, 0.0, 0.0]])
    >>> max_abs, mean_abs = analysis.error_statistics(hpr, hpr_true)
    >>> np.round(np.rad2deg(max_abs), 6), np.round(np.rad2deg(mean_abs), 6)
    (array([2. , 0.5, 0. ]), array([1.      , 0.166667, 0.      ]))
    """
    a = as_array(hpr, "hpr", tail=(3,), min_ndim=1)
    b = as_array(hpr_true, "hpr_true", tail=(3,), min_ndim=1)
    lead, n = a.shape[:-2], a.shape[-2]
    if b.shape != (n, 3) and b.shape != a.shape:
        raise ValueError(f"hpr_true: expected shape ({n}, 3) or {a.shape}, got {b.shape}")
    mx, mean = _error_stats_kernel(kernel_array(a.reshape(-1, n, 3)), kernel_array(b.reshape(-1, n, 3)))
    return mx.reshape(lead + (3,)), mean.reshape(lead + (3,))


def horizontal_error(lla: Vec3, lla_true: Vec3) -> Array:
    """East and north position error (m) of ``lla`` against ``lla_true`` (local radii).

    Parameters
    ----------
    lla, lla_true : array_like, shape (..., N, 3)

    Returns
    -------
    en : ndarray, shape (..., N, 2)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import analysis
    >>> lla_true = np.array([[0.6, 0.2, 0.0]])
    >>> lla = lla_true + [[1e-6, 0.0, 0.0]]                          # 1 urad north
    >>> np.round(analysis.horizontal_error(lla, lla_true), 3)       # east, north (m)
    array([[0.   , 6.356]])
    """
    a = as_array(lla, "lla", tail=(3,))
    b = as_array(lla_true, "lla_true", tail=(3,))
    broadcast(a, b, name="lla_true", of="lla, lla_true")
    latitude(a[..., 0], "lla[..., 0] (lat)")
    latitude(b[..., 0], "lla_true[..., 0] (lat)")
    R_M, R_N = _earth.radii(b[..., 0], earth.WGS84)
    return np.stack(
        [(a[..., 1] - b[..., 1]) * (R_N + b[..., 2]) * np.cos(b[..., 0]), (a[..., 0] - b[..., 0]) * (R_M + b[..., 2])], -1
    )


def expanding_std(x: ArrayLike) -> Array:
    """Standard deviation of ``x[:k+1]`` for every k (population std), e.g. of latitude over [0, t].

    Examples
    --------
    >>> from navlib import analysis
    >>> analysis.expanding_std([1.0, 3.0, 1.0, 3.0])
    array([0.        , 1.        , 0.94280904, 1.        ])
    """
    x = as_array(x, "x", min_ndim=1, shape=(None,))
    d = x - x[0]  # conditioning
    n = np.arange(1, d.size + 1)
    m1, m2 = np.cumsum(d) / n, np.cumsum(d * d) / n
    return np.sqrt(np.maximum(m2 - m1 * m1, 0.0))


def detection_rates(detected: ArrayLike, truth: ArrayLike) -> tuple[float, float]:
    """Detection and false-alarm rates of a static detector.

    Parameters
    ----------
    detected, truth : array_like of bool, shape (N,)

    Returns
    -------
    p_detect : float
        Fraction of truly static samples declared static.
    p_false : float
        Fraction of moving samples declared static.

    Examples
    --------
    >>> from navlib import analysis
    >>> analysis.detection_rates([True, True, False, True], [True, True, False, False])
    (1.0, 0.5)
    """
    d = booleans(detected, "detected", shape=(None,))
    t = same_shape(booleans(truth, "truth"), "truth", d.shape, of="detected")
    if t.all() or not t.any():
        raise ValueError("truth: expected both static and moving samples")
    return float(d[t].mean()), float(d[~t].mean())


def position_error(estimate: ArrayLike, truth: ArrayLike) -> Array:
    """Horizontal position error (m): ``|estimate[..., :2] - truth[..., :2]|``, shape (...).

    Examples
    --------
    >>> from navlib import analysis
    >>> analysis.position_error([[3.0, 4.0, 9.0]], [[0.0, 0.0, 0.0]])   # height ignored
    array([5.])
    """
    est = as_array(estimate, "estimate", allow_nan=True)
    tru = as_array(truth, "truth")
    for name, arr in (("estimate", est), ("truth", tru)):
        if arr.ndim < 1 or arr.shape[-1] < 2:
            raise ValueError(f"{name}: expected positions on the last axis (at least 2 components), got shape {arr.shape}")
    try:
        np.broadcast_shapes(est.shape[:-1], tru.shape[:-1])
    except ValueError:
        raise ValueError(f"estimate, truth: shapes {est.shape} and {tru.shape} do not broadcast") from None
    d = est[..., :2] - tru[..., :2]
    return np.hypot(d[..., 0], d[..., 1])


@boundary
def settling_time(time: Times, error: ArrayLike, start: Real, tol: Positive, end: float | None = None) -> Array:
    """Time after ``start`` until ``|error|`` stays within ``tol`` up to ``end`` (s); inf if it never does.

    Parameters
    ----------
    time : array_like, shape (N,)  (s)
    error : array_like, shape (..., N)
        Error history (any unit, the unit of ``tol``), e.g. heading error after an outage ends.
    start : float
        When the clock starts (s), e.g. the end of an RTK outage.
    tol : float
        Band that counts as converged.
    end : float, optional
        Last time considered (s), e.g. the start of the next outage; default the end of the record.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import analysis
    >>> time = np.arange(0.0, 10.0, 1.0)
    >>> error = 5.0 * np.exp(-time)                                  # decays after an outage that ends at t = 0
    >>> float(analysis.settling_time(time, error, start=0.0, tol=0.1))
    4.0
    """
    t = time_axis(time, "time")
    e = last_axis(as_array(error, "error", min_ndim=1), "error", t.size, of="time")
    stop = np.inf if end is None else scalar(end, "end")
    window = (t >= start) & (t < stop)
    if not window.any():
        raise ValueError(f"start, end: expected samples in [start, end) = [{start}, {stop})")
    outside = np.abs(e[..., window]) > tol
    n = outside.shape[-1]
    last = np.where(outside.any(-1), n - 1 - np.argmax(outside[..., ::-1], -1), -1)
    tw = t[window]
    return np.where(last == n - 1, np.inf, tw[np.minimum(last + 1, n - 1)] - start)


# --------------------------------------------------------------------------
# Runs of a boolean mask
# --------------------------------------------------------------------------


def segments(mask: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Contiguous runs of True: first index and one-past-last index of each.

    Parameters
    ----------
    mask : array_like of bool, shape (N,)

    Returns
    -------
    starts, ends : ndarray of int

    Examples
    --------
    >>> from navlib import analysis
    >>> analysis.segments([False, True, True, False, True])
    (array([1, 4]), array([3, 5]))
    """
    m = booleans(mask, "mask", shape=(None,))
    edges = np.diff(np.concatenate([[0], m.astype(np.int8), [0]]))
    return np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)


@boundary
def moving_mean(x: ArrayLike, n: Count) -> Array:
    """Centred moving mean over ``n`` samples along axis 0 (edges use the nearest full window).

    ``x`` : array_like, shape (N, ...) with N >= n >= 1. Returns a float array of the same shape.

    Examples
    --------
    >>> from navlib import analysis
    >>> analysis.moving_mean([0.0, 3.0, 0.0, 3.0, 0.0], 3)
    array([1., 1., 2., 1., 1.])
    """
    x = as_array(x, "x", min_ndim=1)
    if n > x.shape[0]:
        raise ValueError(f"n: expected a window of at most {x.shape[0]} samples (the length of x), got {n}")
    return _moving_mean(x, n)


def _moving_mean(x: np.ndarray, n: int) -> np.ndarray:
    """:func:`moving_mean` of a checked series and window (1 <= n <= N)."""
    c = np.cumsum(np.concatenate([np.zeros((1,) + x.shape[1:]), x]), axis=0)
    valid = (c[n:] - c[:-n]) / n  # windows starting at 0 .. N - n
    start = np.clip(np.arange(x.shape[0]) - n // 2, 0, x.shape[0] - n)
    return valid[start]


# --------------------------------------------------------------------------
# Stacked linear least squares: r_k = V_k b + v_k, k = 1..K
# --------------------------------------------------------------------------


def _blocks(V: ArrayLike, R: ArrayLike) -> tuple[Array, Array]:
    V = as_array(V, "V", min_ndim=3)
    m = V.shape[-2]
    R = as_array(R, "R", min_ndim=3)
    if R.shape[-2:] != (m, m):
        raise ValueError(f"R: expected shape (..., {m}, {m}) (m = {m} rows of each block of V {V.shape}), got {R.shape}")
    return V, R


def normal_condition(A: ArrayLike) -> Array:
    """Condition number of normal (information) matrices ``A`` (..., n, n): ``sqrt(eig_max / eig_min)``.

    ``inf`` when ``A`` is singular: an eigenvalue within the eigensolver's rounding of the largest
    (``n eps eig_max``) counts as zero, whatever its sign (which is machine-dependent noise).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import analysis
    >>> float(analysis.normal_condition(np.diag([4.0, 1.0]))), float(analysis.normal_condition(np.diag([1.0, 0.0])))
    (2.0, inf)
    """
    A = as_array(A, "A", min_ndim=2)
    if A.shape[-1] != A.shape[-2]:
        raise ValueError(f"A: expected square matrices (..., n, n), got shape {A.shape}")
    return _lsq.normal_condition(A)


def condition_number(V: ArrayLike) -> Array:
    """cond(V) of stacked blocks ``V_k`` (..., K, m, n): ``sqrt(eig_max / eig_min)`` of ``sum V_k^T V_k``.

    Blocks holding NaN are left out. ``inf`` when ``b`` is not fully observable from the blocks.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import analysis
    >>> V = np.stack([np.eye(3)[:2], np.eye(3)[1:]])                # two blocks, each seeing two axes
    >>> float(analysis.condition_number(V)), float(analysis.condition_number(V[:1]))   # the second alone misses z
    (1.4142135623730951, inf)
    """
    return _lsq.condition_number(as_array(V, "V", min_ndim=3, allow_nan=True))


@boundary
def lsq_covariance(
    V: ArrayLike, R: ArrayLike, max_cond: Annotated[float, Check("scalar", positive=True, allow_inf=True)] = 1e6
) -> Array:
    r"""Covariance of the unweighted least-squares estimate of ``b``.

    :math:`P = A^{-1} \big(\sum_k V_k^T R_k V_k\big) A^{-1}` with :math:`A = \sum_k V_k^T V_k`.

    Parameters
    ----------
    V : array_like, shape (..., K, m, n)
    R : array_like, shape (..., K, m, m)
        Covariance of each block's noise ``v_k``.
    max_cond : float
        ``ValueError`` (naming ``V``) when ``cond(V)`` exceeds this: ``b`` is not observable.

    Returns
    -------
    P : ndarray, shape (..., n, n)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import analysis
    >>> V = np.stack([np.eye(2), np.eye(2)])
    >>> R = np.stack([np.eye(2), 4 * np.eye(2)])
    >>> np.round(analysis.lsq_covariance(V, R), 3)                  # (1 + 4) / 4: worse than the weighted bound 0.8
    array([[1.25, 0.  ],
           [0.  , 1.25]])
    """
    V, R = _blocks(V, R)
    A = np.einsum("...kji,...kjl->...il", V, V)
    if np.any(_lsq.normal_condition(A) > max_cond):
        raise ValueError("V: the unknowns are not observable from these blocks (rank-deficient V)")
    A_inv = np.linalg.inv(A)
    return A_inv @ np.einsum("...kji,...kjl,...klm->...im", V, R, V) @ A_inv


@boundary
def cramer_rao_bound(
    V: ArrayLike, R: ArrayLike, max_cond: Annotated[float, Check("scalar", positive=True, allow_inf=True)] = 1e6
) -> Array:
    r"""Cramer-Rao bound of ``b`` from stacked blocks: :math:`\big(\sum_k V_k^T R_k^{-1} V_k\big)^{-1}`.

    Parameters
    ----------
    V : array_like, shape (..., K, m, n)
    R : array_like, shape (..., K, m, m)
        Covariance of each block's noise.
    max_cond : float
        Information matrices with ``sqrt(cond) > max_cond`` count as singular.

    Returns
    -------
    P : ndarray, shape (..., n, n)
        Lower bound on the covariance of any unbiased estimate; ``inf`` on the diagonal (NaN off it)
        where ``b`` is not observable.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import analysis
    >>> V = np.stack([np.eye(2), np.eye(2)])                       # b observed twice
    >>> R = np.stack([np.eye(2), 4 * np.eye(2)])                    # noise variances 1 and 4
    >>> np.round(analysis.cramer_rao_bound(V, R), 3)               # 1 / (1 + 1/4)
    array([[0.8, 0. ],
           [0. , 0.8]])
    """
    return _lsq.cramer_rao_bound(*_blocks(V, R), max_cond)


@boundary
def footfall_path_length(pos_n: ArrayLike, stance: ArrayLike, *, min_samples: Count = 1) -> tuple[float, Array]:
    """Horizontal path length of a foot-mounted track measured from footfall to footfall.

    The foot stands still during each stance: the track's mean position over a stance is where the foot
    landed. The path is the sum of the horizontal distances between successive footfalls, i.e. the stride
    lengths. Summing the track sample by sample instead adds the swing's sideways and up-down wiggle and
    the filter's small corrections at every update, and comes out longer.

    Parameters
    ----------
    pos_n : array_like, shape (N, 2) or (N, 3)
        Positions (m) in a local level frame (east, north[, up]); only the horizontal part is used.
    stance : array_like of bool, shape (N,)
        Stance samples (e.g. from :func:`navlib.filters.zupt.detect_static`).
    min_samples : int
        Shortest run of stance samples counted as a footfall (shorter runs are ignored).

    Returns
    -------
    length : float
        Sum of the stride lengths (m); 0 with fewer than two footfalls.
    footfalls : ndarray, shape (K, 2)
        Horizontal position of each footfall (m).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import analysis
    >>> pos_n = np.array([[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.5, 0.1, 0.2], [1.2, 0.0, 0.0], [1.2, 0.0, 0.0]])
    >>> stance = np.array([True, True, False, True, True])         # two footfalls, one stride between
    >>> length, footfalls = analysis.footfall_path_length(pos_n, stance)
    >>> round(length, 6), footfalls
    (1.2, array([[0. , 0. ],
           [1.2, 0. ]]))
    """
    p = as_array(pos_n, "pos_n", min_ndim=2)
    if p.ndim != 2 or p.shape[1] not in (2, 3):
        raise ValueError(f"pos_n: expected shape (N, 2) or (N, 3) (east, north[, up]), got {p.shape}")
    m = booleans(stance, "stance", shape=(p.shape[0],))
    starts, ends = segments(m)
    keep = ends - starts >= min_samples
    footfalls = np.array([p[a:b, :2].mean(0) for a, b in zip(starts[keep], ends[keep], strict=True)]).reshape(-1, 2)
    return float(np.sum(np.linalg.norm(np.diff(footfalls, axis=0), axis=1))), footfalls


@dataclass(frozen=True)
class OrientationErrors:
    """RMS orientation errors over the scored samples (rad), as defined by the BROAD benchmark.

    Attributes
    ----------
    total : float
        RMS of the angle of the error rotation ``q_bn (x) q_ref*``.
    heading : float
        RMS of its rotation about the vertical (the twist about ENU's up axis).
    inclination : float
        RMS of the rest (the swing: the angle between estimated and reference up axes).
    heading_offset : float
        The constant heading offset removed before scoring (rad; 0 when not removed).
    samples : int
        Number of samples scored (masked in, with a reference).
    missing_reference : int
        Number of masked-in samples left out because their reference row holds NaN (a gap of the reference).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import analysis, attitude
    >>> q_ref = attitude.euler_to_quat(np.deg2rad([[10.0, 0.0, 0.0], [20.0, 5.0, 0.0]]))
    >>> q_bn = attitude.euler_to_quat(np.deg2rad([[13.0, 0.0, 0.0], [23.0, 5.0, 2.0]]))   # 3 deg heading offset, 2 deg roll error
    >>> err = analysis.orientation_errors(q_bn, q_ref, remove_heading_offset=False)
    >>> round(float(np.rad2deg(err.heading)), 3), round(float(np.rad2deg(err.inclination)), 3), err.samples
    (2.914, 1.409, 2)
    """

    total: float
    heading: float
    inclination: float
    heading_offset: float
    samples: int
    missing_reference: int = 0


@boundary
def orientation_errors(
    q_bn: ArrayLike, q_ref: ArrayLike, mask: ArrayLike | None = None, *, remove_heading_offset: Flag = True
) -> OrientationErrors:
    """Total, heading and inclination RMS errors of an attitude estimate against a reference.

    The error measures of the BROAD benchmark (Laidig et al., *Data* 6(7):72, 2021, Sec. 4): the error
    rotation expressed in the navigation frame, ``e = q_bn (x) q_ref*``, is split into a rotation about
    the vertical (heading error ``2 atan(|e3 / e0|)``) and the remaining tilt of the up axis (inclination
    error ``2 acos(sqrt(e0^2 + e3^2))``); the total error is its angle ``2 acos(|e0|)``. With
    ``remove_heading_offset`` (the usual practice for 6D filters, whose heading is arbitrary, and for
    9D ones whose north differs from the reference's by a constant) the circular mean of the signed
    heading error over the scored samples is first removed from ``e``.

    Parameters
    ----------
    q_bn, q_ref : array_like, shape (N, 4)
        Estimated and reference attitudes (scalar first, body to navigation frame, z up). Reference rows
        with NaN are left out and counted (``OrientationErrors.missing_reference``).
    mask : array_like of bool, shape (N,), optional
        The samples to score (e.g. the benchmark's movement phases); default all.
    remove_heading_offset : bool
        Remove the run's constant heading offset first.

    Returns
    -------
    OrientationErrors

    Raises
    ------
    ValueError
        If no sample is both masked in and has a reference, or ``q_bn`` has NaN there.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import analysis, attitude
    >>> q_ref = attitude.euler_to_quat(np.deg2rad([[10.0, 0.0, 0.0], [20.0, 5.0, 0.0]]))
    >>> q_bn = attitude.euler_to_quat(np.deg2rad([[13.0, 0.0, 0.0], [23.0, 5.0, 0.0]]))   # a constant 3 deg heading offset
    >>> err = analysis.orientation_errors(q_bn, q_ref)               # the offset is removed by default
    >>> round(float(np.rad2deg(err.heading_offset)), 3), round(float(np.rad2deg(err.total)), 3)
    (-3.0, 0.0)
    """
    q_bn = as_array(q_bn, "q_bn", tail=(4,), shape=(None, 4), allow_nan=True)
    q_ref = as_array(q_ref, "q_ref", tail=(4,), shape=(q_bn.shape[0], 4), allow_nan=True, of="q_bn")
    mask = np.ones(q_bn.shape[0], bool) if mask is None else booleans(mask, "mask", shape=(q_bn.shape[0],), of="q_bn")
    use = mask & np.isfinite(q_ref).all(1)
    if not use.any():
        raise ValueError("mask, q_ref: no sample is both masked in and has a reference")
    est, ref = q_bn[use], q_ref[use]
    if not np.isfinite(est).all():
        raise ValueError("q_bn: NaN on scored samples (the estimate must cover every scored sample)")
    n_est, n_ref = _row_norms(est), _row_norms(ref)
    for name, norm in (("q_bn", n_est), ("q_ref", n_ref)):
        if np.any(norm < 1e-12):
            raise ValueError(f"{name}: expected non-zero quaternions on the scored samples, got |q| = 0")
    q_est, q_true = _attitude.positive_scalar(est / n_est[:, None]), _attitude.positive_scalar(ref / n_ref[:, None])
    e0, e3 = _scalar_and_up(q_est, _attitude.quat_conj(q_true))
    offset = 0.0
    if remove_heading_offset:
        twist = 2 * np.arctan2(e3, e0)  # signed heading error
        offset = float(np.arctan2(np.sin(twist).mean(), np.cos(twist).mean()))
        c, s = np.cos(offset / 2), -np.sin(offset / 2)  # [c, 0, 0, s] (x) e, its zero terms left out
        e0, e3 = c * e0 - s * e3, c * e3 + s * e0
    w, z = np.abs(e0), e3
    total = 2 * np.arccos(np.clip(w, 0.0, 1.0))
    heading = 2 * np.arctan2(np.abs(z), w)
    inclination = 2 * np.arccos(np.clip(np.sqrt(w * w + z * z), 0.0, 1.0))
    total_rms, heading_rms, inclination_rms = (float(np.sqrt(np.mean(x * x))) for x in (total, heading, inclination))
    return OrientationErrors(total_rms, heading_rms, inclination_rms, offset, int(use.sum()), int((mask & ~use).sum()))


def _row_norms(q: Array) -> Array:
    """``np.linalg.norm(q, axis=1)`` of (N, 4) rows, the same bits (its sum over a length-4 axis runs in order),
    without the reduction's per-row overhead (5x faster)."""
    s = q * q
    return np.sqrt(((s[:, 0] + s[:, 1]) + s[:, 2]) + s[:, 3])


def _scalar_and_up(p: Array, q: Array) -> tuple[Array, Array]:
    """Components 0 and 3 of the Hamilton product ``p (x) q`` of (N, 4) arrays, rounded as
    :func:`navlib._attitude.quat_mult` rounds them."""
    p0, p1, p2, p3 = p.T
    q0, q1, q2, q3 = q.T
    return p0 * q0 - p1 * q1 - p2 * q2 - p3 * q3, p0 * q3 + p1 * q2 - p2 * q1 + p3 * q0


@boundary
def time_offset(
    t: Times, x: ArrayLike, t_ref: Times, x_ref: ArrayLike, max_offset: Positive = 0.5, step: Positive = 0.005
) -> float:
    """The delay ``tau`` (s) of a series against a reference of the same quantity: ``x(t) ~ x_ref(t - tau)``.

    E.g. a GNSS receiver's fix latency, from its speed against the wheel speed, or from its positions against a
    reference trajectory. Every offset on a grid of ``step`` within ``[-max_offset, max_offset]`` is scored by
    the RMS of ``|x(t) - x_ref(t - tau)|`` (the reference interpolated linearly) over the same samples (those
    whose shifted time stays inside the reference for every offset), and the best is refined by a parabola
    through it and its two neighbours. Positive ``tau``: ``x`` is late.

    Parameters
    ----------
    t, t_ref : array_like, shapes (N,), (M,)
        Strictly increasing times (s) on one clock.
    x, x_ref : array_like, shapes (N,) or (N, k), and (M,) or (M, k)
        The series and its reference; NaN rows of ``x`` are left out, the reference must be finite.
    max_offset : float
        Largest offset tried (s).
    step : float
        Grid step (s), smaller than ``max_offset``.

    Returns
    -------
    float
        The offset (s).

    Raises
    ------
    ValueError
        If no sample of ``x`` stays inside the reference's time span for every offset, the reference has a gap
        longer than 10 median intervals and ``max_offset`` (it cannot be interpolated across), or the best offset
        is at the edge of the grid (the delay may be larger: raise ``max_offset``).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import analysis
    >>> t_ref = np.arange(0.0, 20.0, 0.01)
    >>> t = np.arange(1.0, 19.0, 0.1)
    >>> x = np.sin(t - 0.12)                                      # the reference, 0.12 s late
    >>> round(analysis.time_offset(t, x, t_ref, np.sin(t_ref)), 3)
    0.12
    """
    t, t_ref = time_axis(t, "t"), time_axis(t_ref, "t_ref")
    x = as_array(x, "x", allow_nan=True, min_ndim=1)
    x_ref = as_array(x_ref, "x_ref", min_ndim=1)
    if x.shape[0] != t.size or x_ref.shape[0] != t_ref.size or x.shape[1:] != x_ref.shape[1:]:
        raise ValueError(f"x, x_ref: expected shapes ({t.size}, ...) and ({t_ref.size}, ...) alike, got {x.shape}, {x_ref.shape}")
    if step >= max_offset:
        raise ValueError(f"step: expected a grid step below max_offset ({max_offset} s), got {step}")
    x, x_ref = x.reshape(t.size, -1), x_ref.reshape(t_ref.size, -1)
    d_ref = np.diff(t_ref)
    k = int(np.argmax(d_ref)) if d_ref.size else 0
    if d_ref.size and d_ref[k] > max(10 * np.median(d_ref), max_offset):  # linear interpolation across it would be made up
        raise ValueError(
            f"t_ref: a gap of {d_ref[k]:.3g} s after {t_ref[k]:.6g} s (over 10 median intervals and max_offset); "
            "give the reference without gaps (e.g. the stretch before or after it)"
        )
    use = np.isfinite(x).all(1) & (t - max_offset >= t_ref[0]) & (t + max_offset <= t_ref[-1])
    if not use.any():
        raise ValueError("t, t_ref: no finite sample of x stays inside the reference's time span for every offset")
    taus = step * np.arange(-int(max_offset / step), int(max_offset / step) + 1)
    cost = np.array([_offset_cost(t[use] - tau, x[use], t_ref, x_ref) for tau in taus])
    i = int(np.argmin(cost))
    if i in (0, taus.size - 1):
        raise ValueError(f"max_offset: the best offset is at the edge of the grid ({taus[i]:+.3f} s); try a larger one")
    c0, c1, c2 = cost[i - 1 : i + 2]
    curvature = c0 - 2 * c1 + c2
    return float(taus[i] + (0.5 * step * (c0 - c2) / curvature if curvature > 0 else 0.0))


def _offset_cost(t_shifted, x, t_ref, x_ref) -> float:
    """RMS of |x - x_ref(t_shifted)| (the reference interpolated linearly per column)."""
    ref = np.stack([np.interp(t_shifted, t_ref, col) for col in x_ref.T], -1)
    return float(np.sqrt(np.mean(np.sum((x - ref) ** 2, axis=1))))
