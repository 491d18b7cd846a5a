"""Tests of navlib.attitude: conventions, scipy cross-checks, round trips, bad input."""

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose, assert_array_equal
from scipy.spatial.transform import Rotation

from navlib import _kernels
from navlib import attitude as att
from navlib._validate import as_quat

PI = np.pi
SETTINGS = settings(max_examples=200, deadline=None)

# --------------------------------------------------------------------------
# Strategies
# --------------------------------------------------------------------------
headings = st.floats(0.0, 2 * PI, exclude_max=True)
pitches = st.floats(-PI / 2, PI / 2)
pitches_free = st.floats(-PI / 2 + 1e-2, PI / 2 - 1e-2)  # away from gimbal lock
rolls = st.floats(-PI, PI)


@st.composite
def hprs(draw, pitch=pitches):
    return np.array([draw(headings), draw(pitch), draw(rolls)])


@st.composite
def quats(draw):
    """Unit quaternions, any sign of q0."""
    q = np.array([draw(st.floats(-1, 1)) for _ in range(4)])
    assume(np.linalg.norm(q) > 0.1)
    return q / np.linalg.norm(q)


@st.composite
def rotvecs(draw, max_angle=PI):
    """Rotation vectors with angle in [0, max_angle)."""
    axis = np.array([draw(st.floats(-1, 1)) for _ in range(3)])
    assume(np.linalg.norm(axis) > 0.1)
    angle = draw(st.floats(0.0, max_angle, exclude_max=True))
    return axis / np.linalg.norm(axis) * angle


def same_quat(p, q, atol=1e-12):
    """Quaternions equal up to sign (both represent the same rotation)."""
    p, q = np.asarray(p), np.asarray(q)
    return min(np.abs(p - q).max(), np.abs(p + q).max()) <= atol


def scipy_quat_first(r: Rotation):
    """scipy quaternion (scalar last) reordered scalar first."""
    x, y, z, w = r.as_quat()
    return np.array([w, x, y, z])


# --------------------------------------------------------------------------
# wrap_pi / wrap_2pi
# --------------------------------------------------------------------------
def test_wrap_pi_endpoints():
    """pi and -pi both map to +pi; 0 stays 0; 3 pi -> pi."""
    assert att.wrap_pi(PI) == PI
    assert att.wrap_pi(-PI) == PI
    assert att.wrap_pi(0.0) == 0.0
    assert_allclose(att.wrap_pi(3 * PI), PI)
    assert_allclose(att.wrap_pi([-1.5 * PI, 1.5 * PI]), [0.5 * PI, -0.5 * PI])


def test_wrap_2pi_endpoints():
    """2 pi maps to 0, -tiny maps into [0, 2 pi)."""
    assert att.wrap_2pi(2 * PI) == 0.0
    assert att.wrap_2pi(0.0) == 0.0
    w = att.wrap_2pi(-1e-20)
    assert 0.0 <= w < 2 * PI
    assert_allclose(att.wrap_2pi(-PI / 2), 1.5 * PI)


def test_compiled_wraps_equal_the_numpy_wraps_bit_for_bit():
    """The kernels' scalar wraps (a shortcut inside [0, 2 pi) that skips fmod) give numpy's bits, -0 and NaN included."""
    from navlib import _kernels

    edges = [0.0, -0.0, PI, -PI, 2 * PI, -2 * PI, 3 * PI, 1e-300, -1e-300, 5e-324, -5e-324, 1e6, -1e6, np.nan]
    edges += [np.nextafter(e, d) for e in (PI, -PI, 2 * PI, 0.0) for d in (-9.0, 9.0)]
    x = np.concatenate(
        [
            edges,
            np.random.default_rng(0).uniform(-10, 10, 20_000),
            PI + 1e-15 * np.arange(-50, 51),
            -PI + 1e-15 * np.arange(-50, 51),
        ]
    )
    for compiled, vectorised in ((_kernels.wrap_pi, att.wrap_pi), (_kernels.wrap_2pi, att.wrap_2pi)):
        ours = np.array([compiled(v) for v in x])
        assert np.array_equal(ours.view(np.int64)[~np.isnan(x)], vectorised(x).view(np.int64)[~np.isnan(x)])
        assert np.isnan(ours[np.isnan(x)]).all()


@SETTINGS
@given(st.floats(-1e4, 1e4))
def test_wrap_ranges(a):
    """wrap_pi lands in (-pi, pi], wrap_2pi in [0, 2 pi), both congruent to a mod 2 pi."""
    w1, w2 = float(att.wrap_pi(a)), float(att.wrap_2pi(a))
    assert -PI < w1 <= PI
    assert 0.0 <= w2 < 2 * PI
    tol = 1e-12 * max(1.0, abs(a))
    assert abs(np.sin(w1) - np.sin(a)) < tol and abs(np.cos(w1) - np.cos(a)) < tol
    assert abs(np.sin(w2) - np.sin(a)) < tol and abs(np.cos(w2) - np.cos(a)) < tol


# --------------------------------------------------------------------------
# skew, rot, orthonormalize
# --------------------------------------------------------------------------
vec3 = st.lists(st.floats(-1e3, 1e3), min_size=3, max_size=3).map(np.array)


@SETTINGS
@given(vec3, vec3)
def test_skew_is_cross(a, b):
    """skew(a) @ b equals cross(a, b), and skew is antisymmetric."""
    S = att.skew(a)
    assert_allclose(S @ b, np.cross(a, b), atol=1e-9 * (1 + np.abs(a).max() * np.abs(b).max()))
    assert_allclose(S, -S.T)


def test_skew_broadcasts():
    """skew works on (..., 3) stacks."""
    a = np.random.default_rng(0).normal(size=(4, 5, 3))
    b = np.random.default_rng(1).normal(size=(4, 5, 3))
    S = att.skew(a)
    assert S.shape == (4, 5, 3, 3)
    assert_allclose(np.einsum("...ij,...j->...i", S, b), np.cross(a, b), atol=1e-14)


@pytest.mark.parametrize("axis", ["x", "y", "z"])
def test_rot_matches_scipy(axis):
    """rot(axis, t) is the active right-handed rotation, as scipy's from_euler(axis, t)."""
    t = np.array([-2.0, -0.3, 0.0, 0.7, 3.0])
    assert_allclose(att.rot(axis, t), Rotation.from_euler(axis, t[:, None]).as_matrix(), atol=1e-15)
    assert_allclose(att.rot(axis, 30.0, deg=True), Rotation.from_euler(axis, 30, degrees=True).as_matrix(), atol=1e-15)


def test_rot_z_turns_x_into_y():
    """Active rotation by +90 deg about z maps e_x to e_y."""
    assert_allclose(att.rot("z", PI / 2) @ [1.0, 0, 0], [0, 1, 0], atol=1e-15)


def test_orthonormalize_proper_and_idempotent():
    """orthonormalize returns a proper rotation and leaves rotations unchanged."""
    C = Rotation.random(20, random_state=1).as_matrix()
    assert_allclose(att.orthonormalize(C), C, atol=1e-14)
    M = C + 1e-3 * np.random.default_rng(2).normal(size=C.shape)
    R = att.orthonormalize(M)
    assert_allclose(np.swapaxes(R, -1, -2) @ R, np.broadcast_to(np.eye(3), R.shape), atol=1e-14)
    assert_allclose(np.linalg.det(R), 1.0, atol=1e-14)
    assert_allclose(att.orthonormalize(R), R, atol=1e-14)


def test_orthonormalize_is_nearest_rotation():
    """The SVD projection beats nearby rotations in Frobenius distance and recovers the truth."""
    rng = np.random.default_rng(3)
    C = Rotation.from_euler("ZXY", [0.4, -0.2, 1.1]).as_matrix()
    M = C + 1e-4 * rng.normal(size=(3, 3))
    R = att.orthonormalize(M)
    assert np.abs(R - C).max() < 1e-3
    d_best = np.linalg.norm(M - R)
    for rv in 1e-3 * rng.normal(size=(50, 3)):
        other = Rotation.from_rotvec(rv).as_matrix() @ R
        assert np.linalg.norm(M - other) >= d_best - 1e-15


def test_orthonormalize_reflection_gives_proper_rotation():
    """A reflection (det -1) is projected onto a proper rotation, det +1."""
    R = att.orthonormalize(np.diag([1.0, 1.0, -1.0]))
    assert_allclose(np.linalg.det(R), 1.0)
    assert_allclose(R.T @ R, np.eye(3), atol=1e-15)


# --------------------------------------------------------------------------
# The Euler convention itself
# --------------------------------------------------------------------------
def test_euler_to_dcm_is_rot_product():
    """C_bn = rot(z, -heading) rot(x, pitch) rot(y, roll)."""
    h, p, r = 0.7, -0.4, 2.2
    C = att.rot("z", -h) @ att.rot("x", p) @ att.rot("y", r)
    assert_allclose(att.euler_to_dcm([h, p, r]), C, atol=1e-15)


@SETTINGS
@given(hprs())
def test_euler_to_dcm_matches_scipy(hpr):
    """navlib C_bn equals scipy intrinsic Z-X-Y with angles [-heading, pitch, roll]."""
    h, p, r = hpr
    C_ref = Rotation.from_euler("ZXY", [-h, p, r]).as_matrix()
    assert_allclose(att.euler_to_dcm(hpr), C_ref, atol=1e-14)


@SETTINGS
@given(hprs())
def test_euler_to_quat_matches_scipy(hpr):
    """euler_to_quat equals scipy's quaternion up to sign, with q0 >= 0."""
    h, p, r = hpr
    q = att.euler_to_quat(hpr)
    assert q[0] >= 0
    assert same_quat(q, scipy_quat_first(Rotation.from_euler("ZXY", [-h, p, r])), atol=1e-14)


@SETTINGS
@given(quats())
def test_quat_to_dcm_matches_scipy(q):
    """quat_to_dcm equals scipy Rotation.from_quat (scalar last) as_matrix."""
    C_ref = Rotation.from_quat(np.r_[q[1:], q[0]]).as_matrix()
    assert_allclose(att.quat_to_dcm(q), C_ref, atol=1e-14)


def test_quat_to_dcm_batch_equals_the_elementwise_formula_bit_for_bit():
    # The compiled pass rounds as the numpy expressions it replaced (same operations, same order).
    q = np.random.default_rng(11).normal(size=(3, 500, 4))
    q0, q1, q2, q3 = np.moveaxis(as_quat(q), -1, 0)  # normalised as quat_to_dcm does
    rows = [
        [q0 * q0 + q1 * q1 - q2 * q2 - q3 * q3, 2 * (q1 * q2 - q0 * q3), 2 * (q1 * q3 + q0 * q2)],
        [2 * (q1 * q2 + q0 * q3), q0 * q0 - q1 * q1 + q2 * q2 - q3 * q3, 2 * (q2 * q3 - q0 * q1)],
        [2 * (q1 * q3 - q0 * q2), 2 * (q2 * q3 + q0 * q1), q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3],
    ]
    assert_array_equal(att.quat_to_dcm(q), np.stack([np.stack(r, -1) for r in rows], -2))
    assert att.quat_to_dcm(q[0, 0]).shape == (3, 3) and att.quat_to_dcm(np.zeros((2, 0, 4))).shape == (2, 0, 3, 3)


@SETTINGS
@given(quats())
def test_dcm_to_quat_matches_scipy(q):
    """dcm_to_quat equals scipy's as_quat up to sign and returns q0 >= 0."""
    C = Rotation.from_quat(np.r_[q[1:], q[0]]).as_matrix()
    q_nav = att.dcm_to_quat(C)
    assert q_nav[0] >= 0
    assert_allclose(np.linalg.norm(q_nav), 1.0, atol=1e-15)
    assert same_quat(q_nav, q, atol=1e-13)


@SETTINGS
@given(rotvecs())
def test_rotvec_to_dcm_matches_scipy(rv):
    """rotvec_to_dcm equals scipy Rotation.from_rotvec."""
    assert_allclose(att.rotvec_to_dcm(rv), Rotation.from_rotvec(rv).as_matrix(), atol=1e-14)


@SETTINGS
@given(rotvecs(max_angle=PI - 1e-6))
def test_dcm_to_rotvec_matches_scipy(rv):
    """dcm_to_rotvec equals scipy as_rotvec (angles below pi, where it is unique)."""
    C = Rotation.from_rotvec(rv).as_matrix()
    assert_allclose(att.dcm_to_rotvec(C), Rotation.from_matrix(C).as_rotvec(), atol=1e-12)


@pytest.mark.parametrize("heading_deg", [0.0, 30.0, 90.0, 135.0, 180.0, 270.0, 359.0])
def test_forward_axis_azimuth_is_heading(heading_deg):
    """Body forward axis (y) has azimuth atan2(E, N) = heading, clockwise from north."""
    C = att.euler_to_dcm([heading_deg, 10.0, -20.0], deg=True)
    fwd_enu = C.T[1]  # row i of C_bn.T = body axis i in ENU
    az = np.rad2deg(np.arctan2(fwd_enu[0], fwd_enu[1])) % 360
    assert az == pytest.approx(heading_deg, abs=1e-9)


def test_heading_90_points_east():
    """Level, heading 90 deg: forward is East, right is South."""
    C = att.euler_to_dcm([90.0, 0.0, 0.0], deg=True)
    assert_allclose(C @ [0, 1, 0], [1, 0, 0], atol=1e-15)
    assert_allclose(C @ [1, 0, 0], [0, -1, 0], atol=1e-15)
    assert_allclose(C @ [0, 0, 1], [0, 0, 1], atol=1e-15)


@pytest.mark.parametrize("pitch_deg", [-60.0, -10.0, 0.0, 25.0, 80.0])
def test_positive_pitch_raises_nose(pitch_deg):
    """Forward-axis Up component = sin(pitch)."""
    p = np.deg2rad(pitch_deg)
    C = att.euler_to_dcm([0.3, p, 0.5])
    assert C.T[1][2] == pytest.approx(np.sin(p), abs=1e-15)


@pytest.mark.parametrize("roll_deg", [-120.0, -30.0, 0.0, 15.0, 170.0])
def test_positive_roll_lowers_right_side(roll_deg):
    """Right-axis Up component = -sin(roll) cos(pitch)."""
    p, r = 0.3, np.deg2rad(roll_deg)
    C = att.euler_to_dcm([1.0, p, r])
    assert C.T[0][2] == pytest.approx(-np.sin(r) * np.cos(p), abs=1e-15)
    if roll_deg > 0:
        assert C.T[0][2] < 0


def test_deg_flag():
    """deg=True in and out agrees with radians."""
    hpr_deg = np.array([200.0, -35.0, 120.0])
    assert_allclose(att.euler_to_dcm(hpr_deg, deg=True), att.euler_to_dcm(np.deg2rad(hpr_deg)))
    assert_allclose(att.dcm_to_euler(att.euler_to_dcm(hpr_deg, deg=True), deg=True), hpr_deg, atol=1e-10)


# --------------------------------------------------------------------------
# Round trips
# --------------------------------------------------------------------------
@SETTINGS
@given(hprs(pitch=pitches_free))
def test_euler_dcm_euler_round_trip(hpr):
    """Euler -> DCM -> Euler recovers the angles (wrapped) and the matrix."""
    C = att.euler_to_dcm(hpr)
    back = att.dcm_to_euler(C)
    assert 0.0 <= back[0] < 2 * PI
    assert -PI < back[2] <= PI
    assert np.abs(att.wrap_pi(back - hpr)).max() < 1e-9
    assert_allclose(att.euler_to_dcm(back), C, atol=1e-14)


@SETTINGS
@given(hprs(pitch=pitches_free))
def test_euler_quat_euler_round_trip(hpr):
    """Euler -> quaternion -> Euler recovers the angles."""
    back = att.quat_to_euler(att.euler_to_quat(hpr))
    assert np.abs(att.wrap_pi(back - hpr)).max() < 1e-9


@SETTINGS
@given(quats())
def test_quat_dcm_round_trip(q):
    """quat -> DCM -> quat returns the same rotation, q0 >= 0."""
    back = att.dcm_to_quat(att.quat_to_dcm(q))
    assert back[0] >= 0
    assert same_quat(back, q, atol=1e-13)
    assert_allclose(att.quat_to_dcm(back), att.quat_to_dcm(q), atol=1e-14)


@SETTINGS
@given(quats(), quats(), quats())
def test_quat_mult_associative(p, q, r):
    """(p q) r == p (q r)."""
    assert_allclose(att.quat_mult(att.quat_mult(p, q), r), att.quat_mult(p, att.quat_mult(q, r)), atol=1e-14)


@SETTINGS
@given(quats(), quats())
def test_quat_mult_composes_dcms(p, q):
    """quat_to_dcm(p (x) q) == quat_to_dcm(p) @ quat_to_dcm(q)."""
    assert_allclose(att.quat_to_dcm(att.quat_mult(p, q)), att.quat_to_dcm(p) @ att.quat_to_dcm(q), atol=1e-14)


@SETTINGS
@given(quats(), vec3)
def test_quat_rotate_and_conj(q, v):
    """quat_rotate equals q (x) v (x) q*, and q* undoes q."""
    v_n = att.quat_rotate(q, v)
    pure = att.quat_mult(att.quat_mult(q, np.r_[0.0, v]), att.quat_conj(q))
    scale = 1 + np.abs(v).max()
    assert_allclose(v_n, pure[1:], atol=1e-12 * scale)
    assert_allclose(att.quat_rotate(att.quat_conj(q), v_n), v, atol=1e-12 * scale)


@SETTINGS
@given(rotvecs())
def test_rotvec_quat_round_trip(rv):
    """rotvec -> quat -> rotvec for angles in [0, pi)."""
    q = att.rotvec_to_quat(rv)
    assert_allclose(np.linalg.norm(q), 1.0, atol=1e-15)
    assert_allclose(att.quat_to_rotvec(q), rv, atol=1e-12)


@pytest.mark.parametrize("angle", [0.0, 1e-12, 1e-8, 1e-5, 1e-4, 1.0001e-4, 1e-3])
def test_small_rotvec_precision(angle):
    """Small rotation vectors keep full relative precision both ways."""
    rv = angle * np.array([0.6, -0.8, 0.0])
    q = att.rotvec_to_quat(rv)
    ref = scipy_quat_first(Rotation.from_rotvec(rv))
    assert_allclose(q, ref, rtol=1e-15, atol=1e-300)
    assert_allclose(att.quat_to_rotvec(q), rv, rtol=1e-13, atol=1e-300)


@SETTINGS
@given(headings, st.sampled_from([-1.0, 1.0]), st.floats(0.0, 1e-7), rolls)
def test_gimbal_lock_matrix_round_trip(h, sign, dp, r):
    """At/near pitch = +-90 deg the angles are not unique but the matrix round trip is."""
    p = sign * (PI / 2 - dp)
    C = att.euler_to_dcm([h, p, r])
    back = att.dcm_to_euler(C)
    assert abs(back[1]) <= PI / 2
    assert_allclose(att.euler_to_dcm(back), C, atol=1e-6)


@pytest.mark.parametrize("pitch", [PI / 2, -PI / 2])
def test_exact_gimbal_lock(pitch):
    """Exactly at +-90 deg: roll is reported as 0 and the matrix is reproduced."""
    C = att.euler_to_dcm([0.4, pitch, 0.3])
    back = att.dcm_to_euler(C)
    assert back[2] == 0.0
    assert back[1] == pytest.approx(pitch, abs=1e-12)
    assert_allclose(att.euler_to_dcm(back), C, atol=1e-12)


@settings(max_examples=100, deadline=None)
@given(st.sampled_from([np.deg2rad(359.9999), 2 * PI - 1e-12, 2 * PI - 1e-15, 0.0, 1e-9, 1e-15, -1e-9]), pitches_free, rolls)
def test_heading_wrap(h, p, r):
    """Headings just below 2 pi and just above 0 come back in [0, 2 pi), wrap-close to truth."""
    back = att.dcm_to_euler(att.euler_to_dcm([h, p, r]))
    assert 0.0 <= back[0] < 2 * PI
    assert abs(att.wrap_pi(back[0] - h)) < 1e-12


# --------------------------------------------------------------------------
# Compiled per-sample helpers
# --------------------------------------------------------------------------
@SETTINGS
@given(quats(), quats(), rotvecs())
def test_compiled_helpers_agree(p, q, rv):
    """quat_mult_1, rotvec_to_quat_1, quat_normalize_1, quat_to_dcm_1 match the vectorised versions."""
    assert_allclose(_kernels.quat_mult_1(p, q), att.quat_mult(p, q), atol=1e-15)
    assert_allclose(_kernels.rotvec_to_quat_1(rv), att.rotvec_to_quat(rv), atol=1e-15)
    assert_allclose(_kernels.quat_to_dcm_1(q), att.quat_to_dcm(q), atol=1e-15)
    s = 3.7 * q
    n1 = _kernels.quat_normalize_1(s)
    assert_allclose(n1, q, atol=1e-15)
    assert same_quat(n1, att.quat_normalize(s), atol=1e-15)


@pytest.mark.parametrize("angle", [0.0, 1e-6, 1e-4, 2e-4, 3.0])
def test_rotvec_to_quat_1_small_angles(angle):
    """Compiled rotvec_to_quat_1 uses the same small-angle series as the vectorised version."""
    rv = angle * np.array([0.0, 0.6, 0.8])
    assert_allclose(_kernels.rotvec_to_quat_1(rv), att.rotvec_to_quat(rv), rtol=1e-15, atol=0)


# --------------------------------------------------------------------------
# Broadcasting over leading axes
# --------------------------------------------------------------------------
@pytest.fixture
def hpr_stack():
    rng = np.random.default_rng(42)
    return np.stack([rng.uniform(0, 2 * PI, (4, 5)), rng.uniform(-1.5, 1.5, (4, 5)), rng.uniform(-PI, PI, (4, 5))], -1)


def test_broadcast_euler(hpr_stack):
    """(4, 5, 3) Euler stacks give (4, 5, 3, 3) matrices, each equal to the single-sample result."""
    C = att.euler_to_dcm(hpr_stack)
    assert C.shape == (4, 5, 3, 3)
    assert_allclose(C[2, 3], att.euler_to_dcm(hpr_stack[2, 3]))
    back = att.dcm_to_euler(C)
    assert back.shape == (4, 5, 3)
    assert_allclose(back, hpr_stack, atol=1e-10)


def test_broadcast_quat(hpr_stack):
    """Quaternion functions keep leading axes and match per-sample results."""
    q = att.euler_to_quat(hpr_stack)
    assert q.shape == (4, 5, 4)
    C = att.quat_to_dcm(q)
    assert C.shape == (4, 5, 3, 3)
    assert_allclose(C, att.euler_to_dcm(hpr_stack), atol=1e-14)
    q2 = att.dcm_to_quat(C)
    assert q2.shape == (4, 5, 4)
    assert_allclose(q2, q, atol=1e-13)
    assert att.quat_to_euler(q).shape == (4, 5, 3)
    # (4, 5, 4) x (4,) broadcasts
    r = att.euler_to_quat([0.1, 0.2, 0.3])
    pq = att.quat_mult(q, r)
    assert pq.shape == (4, 5, 4)
    assert_allclose(pq[1, 2], att.quat_mult(q[1, 2], r))
    rv = att.quat_to_rotvec(q)
    assert rv.shape == (4, 5, 3)
    assert_allclose(att.rotvec_to_quat(rv), q, atol=1e-12)
    v = att.quat_rotate(q, [1.0, 2.0, 3.0])
    assert v.shape == (4, 5, 3)
    assert_allclose(v[0, 0], att.quat_to_dcm(q[0, 0]) @ [1.0, 2.0, 3.0])


def test_dcm_to_quat_mixed_branches():
    """A stack needing every Shepperd branch (trace and each diagonal largest) is handled."""
    C = np.stack([np.eye(3), att.rot("x", 3.0), att.rot("y", 3.0), att.rot("z", 3.0)])
    q = att.dcm_to_quat(C)
    for Ci, qi in zip(C, q, strict=True):
        assert same_quat(qi, scipy_quat_first(Rotation.from_matrix(Ci)), atol=1e-15)


# --------------------------------------------------------------------------
# Bad input
# --------------------------------------------------------------------------
@pytest.mark.parametrize("hpr", [np.zeros(2), np.zeros((5, 4)), np.zeros((3, 3, 2))])
def test_bad_hpr_shape(hpr):
    """Wrong trailing shape names hpr."""
    with pytest.raises(ValueError, match="^hpr:"):
        att.euler_to_dcm(hpr)
    with pytest.raises(ValueError, match="^hpr:"):
        att.euler_to_quat(hpr)


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_non_finite_hpr(bad):
    """NaN/inf angles are rejected naming hpr."""
    with pytest.raises(ValueError, match="^hpr:"):
        att.euler_to_dcm([0.1, bad, 0.2])
    with pytest.raises(ValueError, match="^hpr:"):
        att.euler_to_quat([bad, 0.1, 0.2])


@pytest.mark.parametrize("pitch_deg", [90.001, -90.001, 180.0])
def test_pitch_out_of_range(pitch_deg):
    """Pitch beyond +-90 deg is rejected naming pitch."""
    with pytest.raises(ValueError, match="pitch"):
        att.euler_to_dcm([0.0, pitch_deg, 0.0], deg=True)
    with pytest.raises(ValueError, match="pitch"):
        att.euler_to_quat(np.deg2rad([0.0, pitch_deg, 0.0]))


def test_non_orthonormal_dcm():
    """Scaled, sheared or reflected matrices are rejected naming C_bn (or C)."""
    for M in [2 * np.eye(3), np.eye(3) + 1e-3 * np.triu(np.ones((3, 3)), 1), np.diag([1.0, 1.0, -1.0])]:
        with pytest.raises(ValueError, match="^C_bn:"):
            att.dcm_to_euler(M)
        with pytest.raises(ValueError, match="^C_bn:"):
            att.dcm_to_quat(M)
        with pytest.raises(ValueError, match="^C:"):
            att.dcm_to_rotvec(M)


def test_bad_dcm_shape_and_nan():
    """Wrong matrix shape and NaN entries name C_bn."""
    with pytest.raises(ValueError, match="^C_bn:"):
        att.dcm_to_euler(np.eye(4))
    C = np.eye(3)
    C[0, 0] = np.nan
    with pytest.raises(ValueError, match="^C_bn:"):
        att.dcm_to_quat(C)


def test_zero_quaternion():
    """The zero quaternion is rejected naming q."""
    with pytest.raises(ValueError, match="^q:"):
        att.quat_to_dcm(np.zeros(4))
    with pytest.raises(ValueError, match="^q:"):
        att.quat_normalize(np.zeros((2, 4)))


def test_bad_quat_shape():
    """Quaternions with 3 components are rejected naming p or q."""
    with pytest.raises(ValueError, match="^q:"):
        att.quat_to_dcm(np.ones(3))
    with pytest.raises(ValueError, match="^p:"):
        att.quat_mult(np.ones(3), np.ones(4))


def test_rot_bad_axis():
    """rot with axis 'w' names axis."""
    with pytest.raises(ValueError, match="^axis:"):
        att.rot("w", 0.1)


def test_bad_vector_shapes():
    """skew and rotvec functions name their vector argument."""
    with pytest.raises(ValueError, match="^v:"):
        att.skew(np.ones(4))
    with pytest.raises(ValueError, match="^rv:"):
        att.rotvec_to_quat(np.ones((2, 2)))
    with pytest.raises(ValueError, match="^v_b:"):
        att.quat_rotate([1.0, 0, 0, 0], [1.0, 2.0])
