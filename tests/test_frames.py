"""Frame conventions: NED/FRD <-> ENU/RFU for vectors, matrices, quaternions and Euler angles, and sensor mounts.

Round trips are property-tested; every conversion is cross-checked against independent code: scipy's
``Rotation`` (aerospace ZYX Euler angles, quaternions) and the ``ahrs`` package's ``ned2enu``.
"""

import numpy as np
import pytest
from ahrs.common import frames as ahrs_frames
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from navlib import attitude, earth, geodesy

angle = st.floats(-np.pi, np.pi, allow_nan=False)
pitch = st.floats(-1.5, 1.5, allow_nan=False)
vec = st.lists(st.floats(-1e3, 1e3, allow_nan=False), min_size=3, max_size=3)


def scipy_ned(ypr):
    """C_frd^ned from aerospace yaw, pitch, roll (intrinsic ZYX), by scipy."""
    return Rotation.from_euler("ZYX", ypr).as_matrix()


@settings(max_examples=200, deadline=None)
@given(angle, pitch, angle)
def test_aerospace_angles_are_navlibs_angles(yaw, p, r):
    C_ned = scipy_ned([yaw, p, r])
    hpr = attitude.ypr_to_hpr([yaw, p, r])
    np.testing.assert_allclose(attitude.euler_to_dcm(hpr), attitude.ned_to_enu_dcm(C_ned), atol=1e-12)
    np.testing.assert_allclose(attitude.wrap_pi(attitude.hpr_to_ypr(hpr) - [yaw, p, r]), 0.0, atol=1e-12)
    assert 0 <= hpr[0] < 2 * np.pi


@settings(max_examples=200, deadline=None)
@given(angle, pitch, angle)
def test_quaternion_conversion_matches_the_matrix(yaw, p, r):
    rot = Rotation.from_euler("ZYX", [yaw, p, r])
    q_ned = np.roll(rot.as_quat(), 1)  # scipy is scalar last
    q_bn = attitude.ned_to_enu_quat(q_ned)
    np.testing.assert_allclose(attitude.quat_to_dcm(q_bn), attitude.ned_to_enu_dcm(rot.as_matrix()), atol=1e-12)
    np.testing.assert_allclose(attitude.ned_to_enu_quat(q_bn), q_ned, atol=1e-15)  # its own inverse


@settings(max_examples=100, deadline=None)
@given(vec)
def test_vectors_match_ahrs_and_round_trip(v):
    np.testing.assert_allclose(attitude.ned_to_enu(v), ahrs_frames.ned2enu(np.array(v)), atol=0)
    np.testing.assert_array_equal(attitude.ned_to_enu(attitude.ned_to_enu(v)), v)


def test_a_vector_rotates_consistently_in_both_conventions():
    C_ned = scipy_ned([0.7, -0.2, 0.4])
    v_frd = np.array([1.0, -2.0, 0.5])
    v_ned = C_ned @ v_frd
    np.testing.assert_allclose(
        attitude.ned_to_enu_dcm(C_ned) @ attitude.ned_to_enu(v_frd), attitude.ned_to_enu(v_ned), atol=1e-15
    )


def test_batches_broadcast():
    ypr = np.random.default_rng(1).uniform(-1, 1, (4, 5, 3))
    assert attitude.ypr_to_hpr(ypr).shape == (4, 5, 3)
    assert attitude.ned_to_enu(ypr).shape == (4, 5, 3)
    q = attitude.euler_to_quat(attitude.ypr_to_hpr(ypr))
    assert attitude.ned_to_enu_quat(q).shape == (4, 5, 4)


def test_degrees():
    np.testing.assert_allclose(attitude.ypr_to_hpr([-90.0, 10.0, 5.0], deg=True), [270.0, 10.0, 5.0])
    np.testing.assert_allclose(attitude.hpr_to_ypr([270.0, 10.0, 5.0], deg=True), [-90.0, 10.0, 5.0])


@pytest.mark.parametrize(
    "axes, v_s, v_b",
    [
        ("x,y,z", [1, 2, 3], [1, 2, 3]),
        ("-y,x,z", [1, 2, 3], [-2, 1, 3]),  # sensor x forward, y left (FLU)
        ("y,x,-z", [1, 2, 3], [2, 1, -3]),  # sensor FRD: the NED/FRD swap
        ("+z,x,y", [1, 2, 3], [3, 1, 2]),
    ],
)
def test_mount_matrix_maps_sensor_axes_to_body_axes(axes, v_s, v_b):
    C_bs = attitude.mount_matrix(axes)
    np.testing.assert_array_equal(C_bs @ v_s, v_b)
    np.testing.assert_array_equal(attitude.mount_matrix(C_bs), C_bs)
    assert np.linalg.det(C_bs) == 1


def test_mount_matrix_for_frd_is_the_ned_swap():
    np.testing.assert_array_equal(attitude.mount_matrix("y,x,-z"), attitude.M_NED_ENU)


@settings(max_examples=50, deadline=None)
@given(st.floats(-80, 80), st.floats(-179, 179), st.floats(-1e4, 1e4), st.floats(-2e4, 2e4))
def test_geodetic_ned_round_trip_and_ahrs(lat0, lon0, dn, de):
    lat, lon, h = lat0 + dn * 1e-5, lon0 + de * 1e-5, 120.0
    n, e, d = geodesy.geodetic2ned(lat, lon, h, lat0, lon0, 10.0, earth.WGS84, deg=True)
    enu = ahrs_frames.geodetic2enu(
        lat,
        lon,
        h,
        lat0,
        lon0,
        10.0,  # ahrs takes degrees
        a=earth.WGS84.a,
        b=earth.WGS84.b,
    )
    np.testing.assert_allclose([e, n, -d], np.ravel(enu), atol=1e-6)
    back = geodesy.ned2geodetic(n, e, d, lat0, lon0, 10.0, earth.WGS84, deg=True)
    np.testing.assert_allclose(back, [lat, lon, h], atol=1e-9)
