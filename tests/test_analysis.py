"""Tests of navlib.analysis: RMSE, Allan deviation (estimator, theory, fit)."""

import subprocess
import sys

import numpy as np
import pytest
from numpy.testing import assert_allclose, assert_array_equal
from scipy.optimize import minimize_scalar

from navlib import analysis as A
from navlib import sensors

# --------------------------------------------------------------------------
# rmse
# --------------------------------------------------------------------------


def test_rmse_basic():
    err = np.array([[3.0, 1.0], [-3.0, -1.0], [3.0, 1.0], [-3.0, 1.0]])
    assert_allclose(A.rmse(err), [3.0, 1.0])
    assert_allclose(A.rmse(err, axis=1), [np.sqrt(5.0)] * 4)
    assert A.rmse([1.0, -2.0, 2.0]) == pytest.approx(np.sqrt(3.0))
    assert A.rmse(np.zeros(5)) == 0.0


def test_rmse_nan_propagates_and_inf_rejected():
    assert np.isnan(A.rmse([1.0, np.nan, 2.0]))
    with pytest.raises(ValueError, match="^err:"):
        A.rmse([1.0, np.inf])


# --------------------------------------------------------------------------
# allan_deviation on white noise
# --------------------------------------------------------------------------


def _white_tol(taus, dt, n):
    """4 standard errors of a white-noise Allan deviation: relative sd <= ~1/sqrt(M)
    with M = n/m clusters (0.87/sqrt(M) non-overlapping; the overlapping
    estimator used here is better)."""
    return 4.0 / np.sqrt(n / np.round(taus / dt))


def test_allan_white_noise_vector_series():
    dt, n, sigma = 0.01, 100_000, 0.2
    x = sigma * np.random.default_rng(1).standard_normal((n, 3))
    taus, adev = A.allan_deviation(x, dt)
    assert taus.ndim == 1 and adev.shape == (taus.size, 3)
    # Default taus: whole multiples of dt from dt to a third of the record, increasing.
    m = taus / dt
    assert_allclose(m, np.round(m), atol=1e-9)
    assert taus[0] == pytest.approx(dt) and taus[-1] <= n // 3 * dt + 1e-9
    assert np.all(np.diff(taus) > 0) and taus.size >= 30
    # White noise of density N = sigma sqrt(dt): adev = N / sqrt(tau).
    N = sigma * np.sqrt(dt)
    sel = taus <= 10.0  # at least 1000 clusters
    ratio = adev[sel] / (N / np.sqrt(taus[sel]))[:, None]
    assert np.all(np.abs(ratio - 1) < _white_tol(taus[sel], dt, n)[:, None])
    # At tau = dt the estimator is the sample sigma of the white noise.
    assert adev[0] == pytest.approx(np.full(3, sigma), rel=4 / np.sqrt(2 * n / 3))


def test_allan_white_noise_scalar_series_and_explicit_taus():
    dt, n, sigma = 0.1, 50_000, 1.5
    x = sigma * np.random.default_rng(2).standard_normal(n)
    taus, adev = A.allan_deviation(x, dt, taus=[0.1, 0.53, 1.0, 10.0])
    assert_allclose(taus, [0.1, 0.5, 1.0, 10.0])  # rounded to whole multiples of dt
    assert adev.shape == (4,)
    N = sigma * np.sqrt(dt)
    assert np.all(np.abs(adev / (N / np.sqrt(taus)) - 1) < _white_tol(taus, dt, n))
    # A scalar series equals one column of a vector series.
    t2, a2 = A.allan_deviation(np.stack([x, 2 * x], -1), dt, taus=[0.1, 0.5, 1.0, 10.0])
    assert_array_equal(t2, taus)
    assert_allclose(a2[:, 0], adev, rtol=1e-12)
    assert_allclose(a2[:, 1], 2 * adev, rtol=1e-12)
    # Leading (trial) axes are kept.
    _, a3 = A.allan_deviation(np.stack([x, x])[..., None], dt, taus=[0.1, 1.0])
    assert a3.shape == (2, 2, 1)


def test_allan_three_axes_equal_each_axis_alone_bit_for_bit():
    """Vector series take two averaging times per pass (odd and even counts of taus); same sums as one axis."""
    x = np.random.default_rng(3).standard_normal((2, 5_000, 3))
    for taus in (None, [0.01, 0.02, 0.05, 0.2, 1.0]):
        _, adev = A.allan_deviation(x, 0.01, taus=taus)
        for j in range(3):
            assert_array_equal(adev[..., j : j + 1], A.allan_deviation(x[..., j : j + 1], 0.01, taus=taus)[1])


def test_allan_of_gauss_markov_matches_theory():
    """The estimator on a simulated Gauss-Markov process follows the theoretical
    curve; 4/sqrt(M) tolerance (empirical sd over 10 seeds was below 1/sqrt(M)).

    Averaging times of >= 20 samples only: at tau << T_c the sampled process is a
    discrete random walk, whose Allan variance exceeds the continuous K^2 tau/3
    by the factor 1 + 1/(2 m^2) (+1 % in deviation at m = 5 samples)."""
    dt, tc, sigma, n = 0.01, 0.5, 1.0, 400_000
    y = sensors.gauss_markov((n, 4), dt, sigma, tc, np.random.default_rng(3))
    taus, adev = A.allan_deviation(y, dt, taus=[0.2, 0.5, tc * A.GM_ALLAN_PEAK_TAU, 5.0])
    theory = A.allan_deviation_theory(taus, bias_instability=sigma * A.GM_ALLAN_PEAK, correlation_time=tc)
    assert np.all(np.abs(adev / theory[:, None] - 1) < (4 / np.sqrt(n / np.round(taus / dt)))[:, None])


# --------------------------------------------------------------------------
# allan_deviation_theory
# --------------------------------------------------------------------------


def _gm_avar_independent(tau, sigma, tc):
    """Allan variance of a Gauss-Markov process from the variance of its integral,
    V(tau) = 2 sigma^2 T^2 (u - 1 + e^-u): AVAR = (4 V(tau) - V(2 tau)) / (2 tau^2)."""

    def V(t):
        u = t / tc
        return 2 * sigma**2 * tc**2 * (u - 1 + np.exp(-u))

    return (4 * V(tau) - V(2 * tau)) / (2 * tau**2)


def test_theory_white_only():
    taus = np.logspace(-2, 4, 25)
    assert_allclose(A.allan_deviation_theory(taus, white=3e-4), 3e-4 / np.sqrt(taus), rtol=1e-14)


def test_theory_rate_random_walk():
    taus = np.logspace(-2, 4, 25)
    assert_allclose(A.allan_deviation_theory(taus, rate_random_walk=2e-6), 2e-6 * np.sqrt(taus / 3), rtol=1e-14)


def test_gm_peak_constants():
    assert A.GM_ALLAN_PEAK == pytest.approx(0.6174, abs=5e-4)
    assert A.GM_ALLAN_PEAK_TAU == pytest.approx(1.893, abs=1e-3)
    # Independent derivation of the peak of a unit Gauss-Markov Allan deviation.
    res = minimize_scalar(
        lambda u: -_gm_avar_independent(u, 1.0, 1.0), bounds=(0.5, 5), method="bounded", options={"xatol": 1e-10}
    )
    assert np.sqrt(-res.fun) == pytest.approx(A.GM_ALLAN_PEAK, rel=1e-9)
    assert res.x == pytest.approx(A.GM_ALLAN_PEAK_TAU, rel=1e-4)
    # The written-out constants are navlib's own maximisation's result, to the last bit with the pinned scipy.
    assert A._peak() == pytest.approx((A.GM_ALLAN_PEAK, A.GM_ALLAN_PEAK_TAU), rel=1e-15, abs=0)


def test_import_navlib_analysis_leaves_scipy_optimize_unimported():
    code = "import sys, navlib.analysis, navlib.sensors; print('scipy.optimize' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "False"


@pytest.mark.parametrize("tc", [0.5, 100.0, 3600.0])
def test_theory_gauss_markov_peak_is_bias_instability(tc):
    B = 4.8e-5
    peak_tau = A.GM_ALLAN_PEAK_TAU * tc
    assert A.allan_deviation_theory(peak_tau, bias_instability=B, correlation_time=tc) == pytest.approx(B, rel=1e-9)
    # It is the maximum of the curve.
    taus = peak_tau * np.logspace(-2, 2, 401)
    curve = A.allan_deviation_theory(taus, bias_instability=B, correlation_time=tc)
    assert curve.max() <= B * (1 + 1e-12)
    # And the whole curve agrees with the independent closed form (sigma = B / peak).
    assert_allclose(curve**2, _gm_avar_independent(taus, B / A.GM_ALLAN_PEAK, tc), rtol=1e-6)


def test_theory_small_tau_series_branch():
    """Below tau = 1e-3 T_c a series replaces the closed form; both agree near the switch."""
    tc = 1.0
    a = A.allan_deviation_theory([0.999e-3, 1.001e-3], bias_instability=1.0, correlation_time=tc)
    assert a[0] == pytest.approx(a[1], rel=2e-3)
    assert A.allan_deviation_theory(1e-6, bias_instability=1.0, correlation_time=tc) ** 2 == pytest.approx(
        (1 / A.GM_ALLAN_PEAK) ** 2 * 2 * 1e-6 / 3, rel=1e-5
    )


def test_theory_terms_add_in_variance():
    taus = np.logspace(-1, 3, 9)
    kw = dict(white=1e-3, bias_instability=2e-4, correlation_time=50.0, rate_random_walk=1e-6)
    total = A.allan_deviation_theory(taus, **kw)
    parts = [
        A.allan_deviation_theory(taus, white=1e-3),
        A.allan_deviation_theory(taus, bias_instability=2e-4, correlation_time=50.0),
        A.allan_deviation_theory(taus, rate_random_walk=1e-6),
    ]
    assert_allclose(total**2, sum(p**2 for p in parts), rtol=1e-13)


# --------------------------------------------------------------------------
# fit_allan
# --------------------------------------------------------------------------


@pytest.mark.parametrize("rrw", [False, True])
def test_fit_allan_noise_free_curve(rrw):
    """White noise with a Gauss-Markov bias, or with rate random walk and no bias: the terms are recovered and the
    one absent is not invented (fit_allan keeps a term only if the data need it)."""
    dt, n = 0.01, 720_000
    taus = np.unique(np.round(np.logspace(0, np.log10(n // 3), 60))) * dt
    p = dict(white=1.7e-4, bias_instability=0.0 if rrw else 4.8e-5, correlation_time=100.0, rate_random_walk=2e-6 if rrw else 0.0)
    fit = A.fit_allan(taus, A.allan_deviation_theory(taus, **p), n, dt, rate_random_walk=rrw)
    assert set(fit) == {
        "white",
        "bias_instability",
        "correlation_time",
        "rate_random_walk",
        "evidence",
        "sensitivity",
        "adequate",
    }
    keys = ("white", "rate_random_walk") if rrw else ("white", "bias_instability", "correlation_time")
    for k in keys:
        assert fit[k] == pytest.approx(p[k], rel=1e-3), k
    assert fit["bias_instability" if rrw else "rate_random_walk"] == 0.0


# --------------------------------------------------------------------------
# Bad input
# --------------------------------------------------------------------------


@pytest.mark.parametrize(
    "arg, call",
    [
        ("x", lambda: A.allan_deviation(np.ones(5), 0.1)),
        ("x", lambda: A.allan_deviation(np.array([1.0, np.nan] * 20), 0.1)),
        ("dt", lambda: A.allan_deviation(np.ones(100), -0.1)),
        ("dt", lambda: A.allan_deviation(np.ones(100), 0.0)),
        ("taus", lambda: A.allan_deviation(np.ones(100), 0.1, taus=[100.0])),
        ("taus", lambda: A.allan_deviation(np.ones(100), 0.1, taus=[-1.0])),
        ("taus", lambda: A.allan_deviation(np.ones(100), 0.1, taus=[0.01])),  # rounds to 0 samples
        ("taus", lambda: A.allan_deviation_theory([-1.0, 1.0], white=1.0)),
        ("taus", lambda: A.fit_allan([0.0, 1.0], [1.0, 1.0], 100, 0.1)),
        ("adev", lambda: A.fit_allan([0.1, 1.0], [1.0, -1.0], 100, 0.1)),
        ("adev", lambda: A.fit_allan([0.1, 1.0, 2.0], [1.0, 0.5], 100, 0.1)),
    ],
    ids=[
        "x-short",
        "x-nan",
        "dt-neg",
        "dt-zero",
        "tau-long",
        "tau-neg",
        "tau-sub-dt",
        "theory-tau",
        "fit-tau",
        "fit-adev-neg",
        "fit-shape",
    ],
)
def test_bad_input(arg, call):
    with pytest.raises(ValueError, match=f"^{arg}:"):
        call()
