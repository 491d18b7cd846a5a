"""Tests of navlib.kalman: predict, Joseph-form update, discretisation, and a
closed-loop consistency (NEES) check."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose, assert_array_equal
from scipy.stats import chi2

from navlib import kalman


def _random_problem(seed, n, m):
    """A well-conditioned random update problem (eigenvalues of P and R in ~[0.1, 10])."""
    rng = np.random.default_rng(seed)
    A = rng.standard_normal((n, n))
    P = A @ A.T / n + 0.1 * np.eye(n)
    B = rng.standard_normal((m, m))
    R = B @ B.T / m + 0.1 * np.eye(m)
    H = rng.standard_normal((m, n))
    x = rng.standard_normal(n)
    z = H @ x + rng.standard_normal(m)
    return x, P, z, H @ x, H, R


def _update(x, P, z, h, H, R, angle_mask=None, gate=np.inf):
    if angle_mask is None:
        angle_mask = np.zeros(z.shape[0], dtype=bool)
    return kalman.update(x, P, z, h, H, R, angle_mask, gate)


@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), n=st.integers(1, 6), m=st.integers(1, 4))
def test_joseph_equals_standard_form(seed, n, m):
    """With the optimal gain the Joseph form equals P = (I - K H) P, and it is symmetric PSD."""
    x, P, z, h, H, R = _random_problem(seed, n, m)
    xn, Pn, y, nis, status = _update(x, P, z, h, H, R)
    S = H @ P @ H.T + R
    K = P @ H.T @ np.linalg.inv(S)
    assert status == kalman.ACCEPTED
    assert_allclose(y, z - h, atol=1e-12)
    assert_allclose(xn, x + K @ (z - h), rtol=1e-9, atol=1e-9)
    assert_allclose(Pn, (np.eye(n) - K @ H) @ P, rtol=1e-8, atol=1e-9)
    assert nis == pytest.approx((z - h) @ np.linalg.solve(S, z - h), rel=1e-9)
    assert_array_equal(Pn, Pn.T)
    assert np.linalg.eigvalsh(Pn).min() > -1e-12
    # The update never increases uncertainty.
    assert np.linalg.eigvalsh(P - Pn).min() > -1e-10


@settings(max_examples=30, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), n=st.integers(1, 5), m=st.integers(2, 5))
def test_nan_components_skipped(seed, n, m):
    """The update with NaN measurement components equals the update with only the finite rows."""
    x, P, z, h, H, R = _random_problem(seed, n, m)
    rng = np.random.default_rng(seed + 1)
    missing = rng.random(m) < 0.5
    missing[rng.integers(m)] = False  # keep at least one component
    z_nan = np.where(missing, np.nan, z)
    keep = ~missing
    xa, Pa, ya, nisa, sa = _update(x, P, z_nan, h, H, R)
    xb, Pb, yb, nisb, sb = _update(x, P, z[keep], h[keep], H[keep], R[np.ix_(keep, keep)])
    assert sa == sb == kalman.ACCEPTED
    assert_allclose(xa, xb, rtol=1e-12, atol=1e-12)
    assert_allclose(Pa, Pb, rtol=1e-12, atol=1e-12)
    assert nisa == pytest.approx(nisb, rel=1e-12)
    assert np.all(np.isnan(ya[missing]))
    assert_allclose(ya[keep], yb)


def test_angle_mask_wraps_innovation():
    x = np.array([np.pi - 0.02])
    P = np.eye(1)
    z = np.array([np.pi - 0.01, 5.0])
    h = np.array([-np.pi + 0.01, 4.0])
    H = np.array([[1.0], [0.0]])
    R = np.eye(2)
    _, _, y, _, _ = _update(x, P, z, h, H, R, angle_mask=np.array([True, False]))
    assert y[0] == pytest.approx(-0.02, abs=1e-12)
    assert y[1] == pytest.approx(1.0)
    # Without the mask the raw difference ~ 2 pi is used.
    _, _, y_raw, _, _ = _update(x, P, z, h, H, R)
    assert y_raw[0] == pytest.approx(2 * np.pi - 0.02, abs=1e-12)
    # pi exactly stays pi (interval (-pi, pi]); -pi maps to pi.
    _, _, y_pi, _, _ = _update(x, P, np.array([np.pi, 0.0]), np.array([0.0, 0.0]), H, R, angle_mask=np.array([True, False]))
    _, _, y_mpi, _, _ = _update(x, P, np.array([-np.pi, 0.0]), np.array([0.0, 0.0]), H, R, angle_mask=np.array([True, False]))
    assert y_pi[0] == pytest.approx(np.pi) and y_mpi[0] == pytest.approx(np.pi)


def test_gate_rejects_outlier_and_accepts_normal():
    x = np.array([1.0, 2.0])
    P = np.diag([4.0, 1.0])
    H = np.array([[1.0, 0.0], [0.0, 1.0]])
    R = np.eye(2)
    gate = chi2.ppf(0.999, 2)  # 13.8
    # Outlier: 100 sigma of S = P + R away.
    z_out = H @ x + np.array([100 * np.sqrt(5.0), 0.0])
    xo, Po, yo, niso, so = _update(x, P, z_out, H @ x, H, R, gate=gate)
    assert so == kalman.REJECTED
    assert niso > gate and niso == pytest.approx(100.0**2)
    assert_array_equal(xo, x)
    assert_array_equal(Po, P)
    assert_allclose(yo, z_out - H @ x)  # the innovation is still reported
    # Normal measurement: 1 sigma.
    z_ok = H @ x + np.array([np.sqrt(5.0), -np.sqrt(2.0)])
    xa, Pa, _, nisa, sa = _update(x, P, z_ok, H @ x, H, R, gate=gate)
    assert sa == kalman.ACCEPTED
    assert nisa == pytest.approx(2.0)
    assert not np.array_equal(xa, x)
    assert np.trace(Pa) < np.trace(P)


def test_all_nan_is_no_data():
    x, P, z, h, H, R = _random_problem(3, 3, 2)
    xn, Pn, y, nis, status = _update(x, P, np.full(2, np.nan), h, H, R)
    assert status == kalman.NO_DATA
    assert_array_equal(xn, x)
    assert_array_equal(Pn, P)
    assert np.all(np.isnan(y)) and np.isnan(nis)
    assert xn is not x  # a copy, not the caller's array
    assert (kalman.ACCEPTED, kalman.NO_DATA, kalman.REJECTED) == (1, 0, -1)


def test_predict():
    rng = np.random.default_rng(4)
    n = 4
    F = rng.standard_normal((n, n))
    A = rng.standard_normal((n, n))
    P = A @ A.T
    Q = np.diag(rng.random(n))
    x = rng.standard_normal(n)
    xp, Pp = kalman.predict(x, P, F, Q)
    assert_allclose(xp, F @ x, rtol=1e-13)
    assert_allclose(Pp, F @ P @ F.T + Q, rtol=1e-12, atol=1e-12)
    assert_array_equal(Pp, Pp.T)


@pytest.mark.parametrize("dt", [0.01, 0.5, 3.0])
def test_discretize_double_integrator(dt):
    q = 0.7
    F = np.array([[0.0, 1.0], [0.0, 0.0]])
    G = np.array([[0.0], [1.0]])
    Phi, Qd = kalman.discretize(F, G, [[q]], dt)
    assert_allclose(Phi, [[1.0, dt], [0.0, 1.0]], rtol=1e-12, atol=1e-14)
    assert_allclose(Qd, q * np.array([[dt**3 / 3, dt**2 / 2], [dt**2 / 2, dt]]), rtol=1e-10, atol=1e-16)


def test_discretize_first_order_markov():
    """Scalar Gauss-Markov: Phi = e^{-dt/T}, Qd = q T/2 (1 - e^{-2 dt/T})."""
    T, q, dt = 20.0, 0.3, 1.5
    Phi, Qd = kalman.discretize([[-1 / T]], [[1.0]], [[q]], dt)
    assert Phi[0, 0] == pytest.approx(np.exp(-dt / T), rel=1e-12)
    assert Qd[0, 0] == pytest.approx(q * T / 2 * (1 - np.exp(-2 * dt / T)), rel=1e-10)


@pytest.mark.parametrize(
    "F, G, Qc, dt, match",
    [
        (np.zeros((2, 3)), np.zeros((2, 1)), np.eye(1), 0.1, "F"),
        (np.zeros((2, 2)), np.zeros((3, 1)), np.eye(1), 0.1, "G"),
        (np.zeros((2, 2)), np.zeros((2, 1)), np.eye(2), 0.1, "Qc"),
        (np.zeros((2, 2)), np.zeros(2), np.eye(1), 0.1, "G"),
        (np.zeros((2, 2)), np.zeros((2, 1)), np.eye(1), -0.1, "^dt:"),
        (np.full((2, 2), np.nan), np.zeros((2, 1)), np.eye(1), 0.1, "^F:"),
    ],
    ids=["F-not-square", "G-rows", "Qc-size", "G-1d", "dt-neg", "F-nan"],
)
def test_discretize_bad_input(F, G, Qc, dt, match):
    with pytest.raises(ValueError, match=match):
        kalman.discretize(F, G, Qc, dt)


def _run_cv_filter(seed, n_runs, n_steps, dt, q, r, r_filter):
    """Constant-velocity KF on simulated 1-D targets; returns NEES, shape (n_runs, n_steps)."""
    F = np.array([[0.0, 1.0], [0.0, 0.0]])
    G = np.array([[0.0], [1.0]])
    Phi, Qd = kalman.discretize(F, G, [[q]], dt)
    Phi = np.ascontiguousarray(Phi)  # discretize returns a transposed view; keep numba on C arrays
    L = np.linalg.cholesky(Qd)
    H = np.array([[1.0, 0.0]])
    R = np.array([[r_filter]])
    mask = np.zeros(1, dtype=bool)
    nees = np.empty((n_runs, n_steps))
    for run, ss in enumerate(np.random.SeedSequence(seed).spawn(n_runs)):
        rng = np.random.default_rng(ss)
        P0 = np.diag([10.0, 1.0])
        truth = np.sqrt(np.diag(P0)) * rng.standard_normal(2)  # x0 ~ N(0, P0), the filter's prior
        x, P = np.zeros(2), P0.copy()
        for k in range(n_steps):
            truth = Phi @ truth + L @ rng.standard_normal(2)
            z = H @ truth + np.sqrt(r) * rng.standard_normal(1)
            x, P = kalman.predict(x, P, Phi, Qd)
            x, P, _, _, status = kalman.update(x, P, z, H @ x, H, R, mask, np.inf)
            assert status == kalman.ACCEPTED
            e = truth - x
            nees[run, k] = e @ np.linalg.solve(P, e)
    return nees


def test_closed_loop_nees_consistent():
    """Filter consistency: the NEES e^T P^-1 e of a correctly tuned KF is chi-square
    with n = 2 degrees of freedom.

    * At a fixed step, the sum over M independent runs is chi2(2M): two-sided
      99.9 % bounds on the run average at the final step.
    * The time average of the run-averaged NEES has mean 2 and, whatever the
      time correlation, a variance at most that of one run average, 4/M:
      tolerance 4 sd = 8/sqrt(M); and, tighter, 4 standard errors of the M
      independent per-run time averages.
    A mistuned filter (R 10x too small) fails the same bounds.
    """
    M, K, n = 200, 100, 2
    nees = _run_cv_filter(seed=2024, n_runs=M, n_steps=K, dt=0.1, q=0.5, r=1.0, r_filter=1.0)
    anees = nees.mean(axis=0)  # average over runs, per step
    lo, hi = chi2.ppf([0.0005, 0.9995], n * M) / M
    assert lo < anees[-1] < hi, (anees[-1], lo, hi)
    assert abs(anees.mean() - n) < 8 / np.sqrt(M), anees.mean()
    # Tighter: the per-run time averages are independent across runs, so their
    # mean is within 4 standard errors (estimated from the runs) of n.
    run_means = nees.mean(axis=1)
    assert abs(run_means.mean() - n) < 4 * run_means.std(ddof=1) / np.sqrt(M)
    # Fraction of steps whose run average is inside the 99 % interval (expected 0.99).
    lo99, hi99 = chi2.ppf([0.005, 0.995], n * M) / M
    assert np.mean((anees > lo99) & (anees < hi99)) > 0.9
    # Power check: an overconfident filter is detected.
    bad = _run_cv_filter(seed=2024, n_runs=50, n_steps=K, dt=0.1, q=0.5, r=1.0, r_filter=0.1)
    assert bad.mean() > n + 8 / np.sqrt(50)


def test_discretize_scalar_F_is_value_error():
    with pytest.raises(ValueError, match="F"):
        kalman.discretize(1.0, [[1.0]], [[1.0]], 0.1)


def test_wrappers_equal_the_compiled_primitives():
    """kalman.predict / update validate and then give exactly what navlib's kernels get from _kernels."""
    from navlib import _kernels

    x, P, z, h, H, R = _random_problem(7, 4, 3)
    F, Q = np.eye(4) + 0.1 * np.ones((4, 4)), 0.01 * np.eye(4)
    for a, b in zip(kalman.predict(x, P, F, Q), _kernels.kalman_predict(x, P, F, Q), strict=True):
        assert_array_equal(a, b)
    mask = np.array([True, False, False])
    z[1] = np.nan
    for gate in (np.inf, 1e-3):
        got, want = _update(x, P, z, h, H, R, mask, gate), _kernels.kalman_update(x, P, z, h, H, R, mask, gate)
        for a, b in zip(got, want, strict=True):
            assert_array_equal(a, b)


def test_integer_and_list_arguments_give_the_float_result_and_are_not_modified():
    """Integer arrays, lists and float32 are read as float64 copies: same result, caller's arrays untouched."""
    x_i, P_i = np.array([1, -2, 3]), np.array([[4, 1, 0], [1, 3, 0], [0, 0, 2]])
    F_i, Q_f32 = np.array([[1, 1, 0], [0, 1, 0], [0, 0, 1]]), np.eye(3, dtype=np.float32)
    H_l, R_l, z_l, h_l = [[1, 0, 0], [0, 0, 1]], [[2, 0], [0, 1]], [3, -1], [1, 3]
    copies = [a.copy() for a in (x_i, P_i, F_i, Q_f32)]
    xp, Pp = kalman.predict(x_i, P_i, F_i, Q_f32)
    xf, Pf = kalman.predict(x_i.astype(float), P_i.astype(float), F_i.astype(float), np.eye(3))
    assert xp.dtype == Pp.dtype == np.float64
    assert_array_equal(xp, xf)
    assert_array_equal(Pp, Pf)
    assert_array_equal(xp, [-1.0, -2.0, 3.0])
    xu, Pu, y, nis, status = kalman.update(x_i, P_i, z_l, h_l, H_l, R_l, [False, False])
    want = kalman.update(
        x_i.astype(float),
        P_i.astype(float),
        np.array(z_l, float),
        np.array(h_l, float),
        np.array(H_l, float),
        np.array(R_l, float),
        np.zeros(2, bool),
    )
    assert status == want[4] == kalman.ACCEPTED and nis == want[3]
    for a, b in zip((xu, Pu, y), want[:3], strict=True):
        assert a.dtype == np.float64
        assert_array_equal(a, b)
    assert not np.array_equal(xu, x_i)  # a real (non-integer) update ...
    for a, b in zip((x_i, P_i, F_i, Q_f32), copies, strict=True):
        assert a.dtype == b.dtype  # ... of which the caller's arrays see nothing
        assert_array_equal(a, b)
    assert H_l == [[1, 0, 0], [0, 0, 1]] and z_l == [3, -1]


def test_shape_mistakes_are_errors_not_broadcasts():
    """A scalar or (n, 1) Q used to be broadcast onto the off-diagonal terms; a NaN gate switched gating off."""
    x, P = np.zeros(2), np.eye(2)
    for Q in (0.01, np.full((2, 1), 0.01), [0.01, 0.01]):
        with pytest.raises(ValueError, match="^Q: expected shape"):
            kalman.predict(x, P, np.eye(2), Q)
    z_out = np.array([100 * np.sqrt(2.0), 0.0])  # a 100-sigma outlier
    with pytest.raises(ValueError, match="^gate:"):
        _update(x, P, z_out, np.zeros(2), np.eye(2), np.eye(2), gate=np.nan)
    assert _update(x, P, z_out, np.zeros(2), np.eye(2), np.eye(2), gate=13.8)[4] == kalman.REJECTED
    with pytest.raises(ValueError, match="^angle_mask: expected shape"):
        _update(x, P, z_out, np.zeros(2), np.eye(2), np.eye(2), angle_mask=np.zeros(0, bool))


def test_no_rows_is_no_data():
    """m = 0 measurement rows (and an all-NaN z) are valid: nothing to update."""
    x, P = np.array([1.0, 2.0]), np.eye(2)
    xn, Pn, y, nis, status = _update(x, P, np.zeros(0), np.zeros(0), np.zeros((0, 2)), np.zeros((0, 0)))
    assert status == kalman.NO_DATA and y.shape == (0,) and np.isnan(nis)
    assert_array_equal(xn, x)
    assert_array_equal(Pn, P)
