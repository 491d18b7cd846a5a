"""Tests of navlib.units (datasheet units <-> SI) and navlib._validate."""

import numpy as np
import pytest
from numpy.testing import assert_allclose

from navlib import _validate as v
from navlib import units as u

DEG = np.pi / 180
G0 = 9.80665

# --------------------------------------------------------------------------
# Converters against hand-computed values
# --------------------------------------------------------------------------
# (function, input, expected SI output)
HAND_VALUES = [
    (u.deg, 180.0, np.pi),
    (u.deg_per_s, 1.0, DEG),
    (u.deg_per_h, 1.0, np.pi / 180 / 3600),
    (u.deg_per_h, 15.041067, 7.2921e-5),  # Earth rate, to 5 digits below
    (u.deg_per_sqrt_h, 1.0, np.pi / 180 / 60),
    (u.deg_per_s_sqrt_hz, 1.0, DEG),
    (u.deg_per_h_sqrt_h, 1.0, np.pi / 180 / 3600 / 60),
    (u.mg, 1.0, 9.80665e-3),
    (u.ug, 1.0, 9.80665e-6),
    (u.ug_per_sqrt_hz, 100.0, 9.80665e-4),
    (u.m_per_s_sqrt_h, 1.0, 1 / 60),
    (u.gauss, 1.0, 100.0),
    (u.gauss, 0.5, 50.0),
    (u.nanotesla, 50000.0, 50.0),
    (u.hpa, 1013.25, 101325.0),
    (u.percent, 5.0, 0.05),
    (u.ppm, 300.0, 3e-4),
]


@pytest.mark.parametrize("func, value, expected", HAND_VALUES, ids=[f"{f.__name__}({x})" for f, x, _ in HAND_VALUES])
def test_hand_values(func, value, expected):
    """Each converter against a value worked out by hand."""
    rtol = 1e-5 if expected == 7.2921e-5 else 1e-15
    assert float(func(value)) == pytest.approx(expected, rel=rtol)


def test_standard_gravity():
    """G0 is the ISO 80000-3 standard gravity."""
    assert u.G0 == 9.80665


def test_converters_keep_shape():
    """Converters are elementwise and return float arrays of the input shape."""
    x = np.arange(6).reshape(2, 3)
    out = u.deg_per_h(x)
    assert out.shape == (2, 3) and out.dtype == np.float64
    assert_allclose(out, x * np.pi / 180 / 3600)


# (inverse, forward) pairs
PAIRS = [
    (u.to_deg, u.deg),
    (u.to_deg_per_s, u.deg_per_s),
    (u.to_deg_per_h, u.deg_per_h),
    (u.to_deg_per_sqrt_h, u.deg_per_sqrt_h),
    (u.to_deg_per_s_sqrt_hz, u.deg_per_s_sqrt_hz),
    (u.to_ug, u.ug),
    (u.to_gauss, u.gauss),
    (u.to_hpa, u.hpa),
]


@pytest.mark.parametrize("inverse, forward", PAIRS, ids=[f.__name__ for _, f in PAIRS])
def test_round_trips(inverse, forward):
    """to_x(x(v)) == v and x(to_x(v)) == v."""
    vals = np.array([-3.5, 0.0, 1e-6, 1.0, 42.0, 1e6])
    assert_allclose(inverse(forward(vals)), vals, rtol=1e-14, atol=0)
    assert_allclose(forward(inverse(vals)), vals, rtol=1e-14, atol=0)


def test_inverse_hand_values():
    """The to_ direction on known values."""
    assert float(u.to_deg(np.pi / 2)) == pytest.approx(90.0, rel=1e-15)
    assert float(u.to_deg_per_h(7.292115e-5)) == pytest.approx(15.041067, rel=1e-7)
    assert float(u.to_deg_per_sqrt_h(np.pi / 180 / 60)) == pytest.approx(1.0, rel=1e-15)
    assert float(u.to_ug(9.80665e-6)) == pytest.approx(1.0, rel=1e-15)
    assert float(u.to_gauss(50.0)) == pytest.approx(0.5, rel=1e-15)
    assert float(u.to_hpa(101325.0)) == pytest.approx(1013.25, rel=1e-15)


# --------------------------------------------------------------------------
# to_si
# --------------------------------------------------------------------------
# SI value of 1 <unit>, by hand
SI_OF_ONE = {
    "rad": 1.0,
    "deg": DEG,
    "deg/s": DEG,
    "deg/h": DEG / 3600,
    "deg/sqrt(h)": DEG / 60,
    "deg/s/sqrt(Hz)": DEG,
    "deg/h/sqrt(h)": DEG / 3600 / 60,
    "m/s^2": 1.0,
    "g": G0,
    "mg": G0 * 1e-3,
    "ug": G0 * 1e-6,
    "ug/sqrt(Hz)": G0 * 1e-6,
    "m/s/sqrt(h)": 1 / 60,
    "m/s^2/sqrt(Hz)": 1.0,
    "uT": 1.0,
    "G": 100.0,
    "mG": 0.1,
    "Pa": 1.0,
    "hPa": 100.0,
    "Pa/s": 1.0,
    "hPa/h": 100 / 3600,
    "%": 0.01,
    "ppm": 1e-6,
    "m": 1.0,
    "s": 1.0,
    "-": 1.0,
}


@pytest.mark.parametrize("unit", sorted(SI_OF_ONE))
def test_to_si(unit):
    """to_si scales linearly by the hand-computed SI value of one unit."""
    x = np.array([1.0, -2.5, 0.0])
    assert_allclose(u.to_si(x, unit), x * SI_OF_ONE[unit], rtol=1e-15, atol=0)
    assert float(u.to_si(3, unit)) == pytest.approx(3 * SI_OF_ONE[unit], rel=1e-15)


def test_every_unit_key_has_a_hand_value():
    """All CONVERTERS keys are covered by SI_OF_ONE above."""
    assert set(u.CONVERTERS) == set(SI_OF_ONE)


@pytest.mark.parametrize("unit", ["furlong", "DEG/H", "", "deg/hr"])
def test_to_si_unknown_unit(unit):
    """Unknown unit strings raise ValueError naming unit."""
    with pytest.raises(ValueError, match="^unit:"):
        u.to_si(1.0, unit)


# --------------------------------------------------------------------------
# navlib._validate
# --------------------------------------------------------------------------
def test_as_array_tail_shape_message():
    """Wrong trailing shape: message names the argument, the expected and the actual shape."""
    with pytest.raises(ValueError, match=r"^vec: expected shape \(\.\.\., 3\), got \(2,\)"):
        v.as_array([1.0, 2.0], "vec", tail=(3,))
    with pytest.raises(ValueError, match=r"^M: expected shape \(\.\.\., 3, 3\), got \(3,\)"):
        v.as_array(np.ones(3), "M", tail=(3, 3))
    out = v.as_array(np.ones((2, 5, 3), dtype=int), "vec", tail=(3,))
    assert out.shape == (2, 5, 3) and out.dtype == np.float64


def test_as_array_min_ndim_and_non_numeric():
    """min_ndim demands leading axes; empty or non-numeric input is rejected."""
    with pytest.raises(ValueError, match="^x:"):
        v.as_array(np.ones(3), "x", tail=(3,), min_ndim=1)
    with pytest.raises(ValueError, match="^x: expected a non-empty"):
        v.as_array(np.ones((0, 3)), "x", tail=(3,), min_ndim=1)
    with pytest.raises(ValueError, match="^x: expected a real numeric array"):
        v.as_array("abc", "x")
    assert v.as_array(np.ones((4, 3)), "x", tail=(3,), min_ndim=1).shape == (4, 3)


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_as_array_rejects_non_finite(bad):
    """NaN and inf are rejected by default."""
    with pytest.raises(ValueError, match="^x: contains non-finite"):
        v.as_array([1.0, bad], "x")


def test_as_array_allow_nan():
    """allow_nan keeps NaN (dropouts) but still rejects inf; finite=False accepts both."""
    out = v.as_array([1.0, np.nan], "x", allow_nan=True)
    assert np.isnan(out[1]) and out[0] == 1.0
    with pytest.raises(ValueError, match="^x: contains infinite"):
        v.as_array([np.nan, np.inf], "x", allow_nan=True)
    assert np.isinf(v.as_array([np.inf], "x", finite=False)).all()


def test_in_range():
    """Closed and open bounds; the message names the argument and the range."""
    a = np.array([0.0, 1.0])
    assert v.in_range(a, "a", 0.0, 1.0) is a
    with pytest.raises(ValueError, match=r"^a: expected values in \(0, 1\]"):
        v.in_range(a, "a", 0.0, 1.0, lo_open=True)
    with pytest.raises(ValueError, match=r"^a: expected values in \[0, 1\) m"):
        v.in_range(a, "a", 0.0, 1.0, "m", hi_open=True)


def test_positive():
    """positive rejects 0 unless allow_zero, and negatives always."""
    assert_allclose(v.positive([1, 2], "s"), [1.0, 2.0])
    assert_allclose(v.positive(0.0, "s", allow_zero=True), 0.0)
    with pytest.raises(ValueError, match="^s: expected positive"):
        v.positive([1.0, 0.0], "s")
    with pytest.raises(ValueError, match="^s: expected non-negative"):
        v.positive(-1.0, "s", allow_zero=True)


def test_latitude():
    """latitude converts degrees and rejects |lat| > 90 deg / pi/2 rad."""
    assert_allclose(v.latitude(90.0, deg=True), np.pi / 2)
    assert_allclose(v.latitude(-0.5), -0.5)
    with pytest.raises(ValueError, match="^lat:"):
        v.latitude(90.0001, deg=True)
    with pytest.raises(ValueError, match="^phi:"):
        v.latitude(1.6, "phi")


def test_time_axis():
    """time_axis accepts strictly increasing 1-D times and rejects the rest."""
    t = v.time_axis([0.0, 0.01, 0.02])
    assert_allclose(t, [0.0, 0.01, 0.02])
    with pytest.raises(ValueError, match="^time: expected strictly increasing"):
        v.time_axis([0.0, 0.02, 0.01])
    with pytest.raises(ValueError, match="^t: expected strictly increasing"):
        v.time_axis([0.0, 1.0, 1.0], "t")
    with pytest.raises(ValueError, match="^time: expected a 1-D array"):
        v.time_axis([0.0])
    with pytest.raises(ValueError, match="^time: expected a 1-D array"):
        v.time_axis(np.zeros((2, 2)))
    with pytest.raises(ValueError, match="^time: contains non-finite"):
        v.time_axis([0.0, np.nan, 2.0])
