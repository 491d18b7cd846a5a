"""navlib.alignment: levelling and tilt-compensated magnetic heading, the one implementation of each.

Bad-input cases of these functions are also run by tests/test_ahrs.py and
tests/faults/test_faults_pedestrian.py (their former homes).
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navlib import alignment, attitude

angles = st.tuples(st.floats(0.0, 2 * np.pi - 1e-9), st.floats(-1.5, 1.5), st.floats(-3.1, 3.1))


def static_readings(hpr, B_n=(0.0, 22.0, -40.0)):
    C_bn = attitude.euler_to_dcm(hpr)
    return C_bn.T @ np.array([0.0, 0.0, 9.8]), C_bn.T @ np.asarray(B_n)


@settings(deadline=None)  # the first call compiles the heading kernel
@given(angles)
def test_level_and_heading_recover_the_attitude(hpr):
    f_b, m_b = static_readings(np.array(hpr))
    pitch, roll = alignment.level(f_b)
    np.testing.assert_allclose([pitch, roll], hpr[1:], atol=1e-12)
    heading = alignment.magnetic_heading(m_b, pitch, roll)
    assert abs(attitude.wrap_pi(heading - hpr[0])) < 1e-9
    np.testing.assert_allclose(attitude.wrap_pi(alignment.tilt_heading(f_b, m_b) - hpr), 0.0, atol=1e-9)


def test_declination_rotates_the_heading_and_wraps():
    f_b, m_b = static_readings(np.array([0.1, 0.0, 0.0]))
    assert alignment.magnetic_heading(m_b, 0.0, 0.0, declination=-0.3) == pytest.approx(2 * np.pi - 0.2)


def test_broadcasting_and_quaternion():
    hpr = np.array([[0.3, 0.1, -0.2], [4.0, -0.5, 1.0]])
    f_b, m_b = zip(*(static_readings(h) for h in hpr), strict=True)
    q = alignment.initial_attitude(np.array(f_b), np.array(m_b))
    assert q.shape == (2, 4)
    np.testing.assert_allclose(np.abs(np.sum(q * attitude.euler_to_quat(hpr), -1)), 1.0, atol=1e-12)
    pitch, roll = alignment.level(np.array(f_b))
    assert pitch.shape == roll.shape == (2,)


@pytest.mark.parametrize(
    "call, arg",
    [
        (lambda: alignment.level([0.0, 0.0, 0.0]), "f_b"),
        (lambda: alignment.level([1.0, 2.0]), "f_b"),
        (lambda: alignment.magnetic_heading([0.0, 0.0, 0.0], 0.0, 0.0), "m_b"),
        (lambda: alignment.magnetic_heading([1.0, 0.0, 0.0], "flat", 0.0), "pitch"),
        (lambda: alignment.magnetic_heading([1.0, 0.0, 0.0], 0.0, 0.0, declination=[0.1, 0.2]), "declination"),
        (lambda: alignment.tilt_heading([0.0, 0.0, 9.8], [0.0, 0.0, 40.0]), "m_b"),
        (lambda: alignment.initial_attitude([0.0, 0.0, np.nan], [0.0, 20.0, 0.0]), "f_b"),
    ],
)
def test_bad_input_names_the_argument(call, arg):
    with pytest.raises(ValueError, match=f"^{arg}: "):
        call()
