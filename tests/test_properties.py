"""Property tests (hypothesis) for navlib's conversions and the Kalman update (issue 9, item 2).

These complement the property tests already in the module test files and do
not repeat them:

* tests/test_attitude.py: scipy cross-checks of every attitude conversion,
  Euler<->DCM, Euler<->quat, quat<->DCM and rotvec<->quat round trips, wraps,
  skew-is-cross, quat_mult associativity and composition, quat_rotate.
* tests/test_units.py: round trips of the unit pairs at fixed values.
* tests/test_earth.py: D/I/F -> field vector -> D/I/F round trip (degrees).
* tests/test_atmosphere.py: h -> p -> h for ISA and the BMP180 formula.
* tests/test_kalman.py: Joseph form == standard form for full, well-conditioned
  measurements; NaN components == the update on the finite rows.

Added here: the consistency *between* conversion paths (quat vs DCM vs Euler
vs rotation vector), sign and degree invariances, output ranges, the
nearest-rotation property of orthonormalize; hypothesis round trips and
linearity of every unit converter; monotonicity/symmetry of Earth radii and
normal gravity, Earth rate, the B -> D/I/F -> B direction; p -> h -> p,
monotonicity and additivity of the barometric formulas; for ``kalman.update``
symmetric positive semi-definite covariance after *any* valid update (random
SPD P over twelve decades of eigenvalues, random H including zero rows, SPD R,
random NaN components, wrapped-angle components, gates), Joseph == standard
form with NaN and wrapped components, the information-form identity, and
``kalman.predict`` keeping P symmetric PSD. Projection properties are in
tests/test_geodesy.py (geodesy owner).

Tolerances are relative to the size of the quantities (float64 rounding,
~1e-16, amplified by the few operations involved); each test states its own.
"""

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose

from navlib import atmosphere, earth, kalman, units
from navlib import attitude as att

PI = np.pi
SETTINGS = settings(max_examples=100, deadline=None)
I3 = np.eye(3)

# --------------------------------------------------------------------------
# strategies
# --------------------------------------------------------------------------
# finite reals away from the subnormal range, where a round trip cannot keep relative precision
finite = st.one_of(st.just(0.0), st.floats(1e-290, 1e6), st.floats(-1e6, -1e-290))
angles = st.floats(-10.0, 10.0)
headings = st.floats(0.0, 2 * PI, exclude_max=True)
pitches_free = st.floats(-PI / 2 + 1e-2, PI / 2 - 1e-2)  # away from gimbal lock
rolls = st.floats(-PI, PI)
lats = st.floats(-PI / 2, PI / 2)


@st.composite
def vec(draw, n=3, lo=-1.0, hi=1.0, min_norm=0.0):
    v = np.array([draw(st.floats(lo, hi)) for _ in range(n)])
    assume(np.linalg.norm(v) > min_norm)
    return v


@st.composite
def quats(draw):
    """Unit quaternions with either sign of q0."""
    q = draw(vec(4, min_norm=0.1))
    return q / np.linalg.norm(q)


@st.composite
def hprs_free(draw):
    return np.array([draw(headings), draw(pitches_free), draw(rolls)])


def assert_rotation(C, atol=1e-12):
    assert_allclose(C @ C.T, I3, atol=atol)
    assert np.linalg.det(C) == pytest.approx(1.0, abs=atol)


# --------------------------------------------------------------------------
# attitude: consistency between conversion paths
# --------------------------------------------------------------------------
@SETTINGS
@given(vec(4, lo=-1e3, hi=1e3, min_norm=1e-3))
def test_quat_normalize_unit_same_direction_idempotent(q):
    """quat_normalize gives |q| = 1, q0 >= 0, +-q/|q| (the same rotation), and is idempotent."""
    u = att.quat_normalize(q)
    assert np.linalg.norm(u) == pytest.approx(1.0, abs=4e-16)
    assert u[0] >= 0
    assert_allclose(u * np.linalg.norm(q) * np.sign(u @ q), q, rtol=1e-13, atol=1e-13 * np.abs(q).max())
    assert_allclose(att.quat_normalize(u), u, atol=4e-16)


@SETTINGS
@given(vec(4, lo=-10, hi=10, min_norm=1e-3))
def test_quat_conj_is_inverse_and_transposes_dcm(q):
    """q (x) q* = [|q|^2, 0, 0, 0]; the DCM of q* is the transpose of the DCM of q."""
    p = att.quat_mult(q, att.quat_conj(q))
    assert_allclose(p, [q @ q, 0, 0, 0], atol=1e-13 * (q @ q))
    u = q / np.linalg.norm(q)
    assert_allclose(att.quat_to_dcm(att.quat_conj(u)), att.quat_to_dcm(u).T, atol=1e-15)


@SETTINGS
@given(quats())
def test_quat_sign_invariance(q):
    """q and -q are the same rotation: same DCM, Euler angles and rotation vector."""
    assert_allclose(att.quat_to_dcm(-q), att.quat_to_dcm(q), atol=0)
    if np.linalg.norm(att.quat_to_rotvec(q)) < PI - 1e-6:  # at pi, +-axis are the same rotation
        assert_allclose(att.quat_to_rotvec(-q), att.quat_to_rotvec(q), atol=1e-12)
    C = att.quat_to_dcm(q)
    assume(abs(C[2, 1]) < 1 - 1e-6)  # pitch away from +-90 deg, where heading/roll are not unique
    assert_allclose(att.quat_to_euler(-q), att.quat_to_euler(q), atol=1e-12)


@SETTINGS
@given(quats())
def test_quat_to_euler_equals_via_dcm(q):
    """quat_to_euler(q) == dcm_to_euler(quat_to_dcm(q)) up to heading wrap (1e-9 rad near gimbal lock)."""
    C = att.quat_to_dcm(q)
    assume(abs(C[2, 1]) < 1 - 1e-6)
    e1, e2 = att.quat_to_euler(q), att.dcm_to_euler(C)
    d = att.wrap_pi(e1 - e2)
    assert_allclose(d, 0.0, atol=1e-9)


@SETTINGS
@given(hprs_free())
def test_euler_to_quat_equals_euler_to_dcm(hpr):
    """Both Euler paths give the same rotation, and dcm_to_quat recovers the quaternion up to sign."""
    q = att.euler_to_quat(hpr)
    assert np.linalg.norm(q) == pytest.approx(1.0, abs=1e-15)
    C = att.euler_to_dcm(hpr)
    assert_allclose(att.quat_to_dcm(q), C, atol=1e-14)
    q2 = att.dcm_to_quat(C)
    assert_allclose(q2 * np.sign(q2 @ q), q, atol=1e-13)


@SETTINGS
@given(vec(3, lo=-3.0, hi=3.0))
def test_rotvec_paths_agree(rv):
    """rotvec_to_dcm == quat_to_dcm(rotvec_to_quat) and both results are proper rotations."""
    C = att.rotvec_to_dcm(rv)
    assert_rotation(C)
    assert_allclose(C, att.quat_to_dcm(att.rotvec_to_quat(rv)), atol=1e-14)
    # the rotation vector is the axis: C rv = rv
    assert_allclose(C @ rv, rv, atol=1e-13)


@SETTINGS
@given(quats())
def test_rotvec_is_principal(q):
    """quat_to_rotvec and dcm_to_rotvec return the principal rotation vector, |rv| <= pi, and agree."""
    rv = att.quat_to_rotvec(q)
    assert np.linalg.norm(rv) <= PI + 1e-12
    assume(np.linalg.norm(rv) < PI - 1e-6)  # at pi the sign of the axis is arbitrary
    assert_allclose(att.dcm_to_rotvec(att.quat_to_dcm(q)), rv, atol=1e-7)
    assert_allclose(att.quat_to_dcm(att.rotvec_to_quat(rv)), att.quat_to_dcm(q), atol=1e-13)


@SETTINGS
@given(quats())
def test_dcm_to_euler_ranges(q):
    """Any rotation maps to heading in [0, 2 pi), pitch in [-pi/2, pi/2], roll in (-pi, pi]."""
    h, p, r = att.dcm_to_euler(att.quat_to_dcm(q))
    assert 0.0 <= h < 2 * PI
    assert -PI / 2 <= p <= PI / 2
    assert -PI < r <= PI
    assert_allclose(att.euler_to_dcm([h, p, r]), att.quat_to_dcm(q), atol=1e-7)


@SETTINGS
@given(st.sampled_from("xyz"), angles, angles)
def test_rot_group_properties(axis, a, b):
    """rot is a proper rotation, rot(a) rot(b) = rot(a + b), rot(-a) = rot(a)^T (atol 1e-14 for |a| <= 10)."""
    A, B = att.rot(axis, a), att.rot(axis, b)
    assert_rotation(A, atol=1e-14)
    assert_allclose(A @ B, att.rot(axis, a + b), atol=1e-14)
    assert_allclose(att.rot(axis, -a), A.T, atol=0)


@SETTINGS
@given(st.sampled_from("xyz"), st.floats(-720.0, 720.0), hprs_free())
def test_deg_flags_equal_radians(axis, a_deg, hpr):
    """deg=True is exactly the radian call on deg2rad(input) (and rad2deg of the output)."""
    assert_allclose(att.rot(axis, a_deg, deg=True), att.rot(axis, np.deg2rad(a_deg)), atol=1e-15)
    hpr_deg = np.rad2deg(hpr)
    assert_allclose(att.euler_to_dcm(hpr_deg, deg=True), att.euler_to_dcm(np.deg2rad(hpr_deg)), atol=1e-15)
    assert_allclose(att.euler_to_quat(hpr_deg, deg=True), att.euler_to_quat(np.deg2rad(hpr_deg)), atol=1e-15)
    C = att.euler_to_dcm(hpr)
    assert_allclose(att.dcm_to_euler(C, deg=True), np.rad2deg(att.dcm_to_euler(C)), rtol=1e-15)
    q = att.euler_to_quat(hpr)
    assert_allclose(att.quat_to_euler(q, deg=True), np.rad2deg(att.quat_to_euler(q)), rtol=1e-15)


@SETTINGS
@given(quats(), st.integers(0, 2**32 - 1), st.floats(1e-9, 1e-2))
def test_orthonormalize_is_nearest_rotation(q, seed, eps):
    """A perturbed rotation M goes to a proper rotation no farther from M than the original (Frobenius),
    and orthonormalize is idempotent."""
    C = att.quat_to_dcm(q)
    M = C + eps * np.random.default_rng(seed).standard_normal((3, 3))
    R = att.orthonormalize(M)
    assert_rotation(R, atol=1e-13)
    assert np.linalg.norm(R - M) <= np.linalg.norm(C - M) + 1e-13
    assert_allclose(att.orthonormalize(R), R, atol=1e-14)


@SETTINGS
@given(vec(3, lo=-1e3, hi=1e3))
def test_skew_antisymmetric_and_annihilates(v):
    S = att.skew(v)
    assert_allclose(S.T, -S, atol=0)
    assert_allclose(S @ v, 0.0, atol=1e-12 * max(1.0, v @ v))


@SETTINGS
@given(st.floats(-1e4, 1e4))
def test_wraps_relation_and_idempotence(a):
    """wrap_2pi - wrap_pi is 0 or 2 pi; wrapping twice changes nothing."""
    w1, w2 = float(att.wrap_pi(a)), float(att.wrap_2pi(a))
    assert min(abs(w2 - w1), abs(w2 - w1 - 2 * PI)) < 1e-12 * max(1.0, abs(a))
    assert float(att.wrap_pi(w1)) == pytest.approx(w1, abs=1e-15)
    assert float(att.wrap_2pi(w2)) == pytest.approx(w2, abs=1e-15)


# --------------------------------------------------------------------------
# units
# --------------------------------------------------------------------------
PAIRS = [
    (units.to_deg, units.deg),
    (units.to_deg_per_s, units.deg_per_s),
    (units.to_deg_per_h, units.deg_per_h),
    (units.to_deg_per_sqrt_h, units.deg_per_sqrt_h),
    (units.to_deg_per_s_sqrt_hz, units.deg_per_s_sqrt_hz),
    (units.to_ug, units.ug),
    (units.to_gauss, units.gauss),
    (units.to_hpa, units.hpa),
]


@settings(max_examples=60, deadline=None)
@given(pair=st.sampled_from(PAIRS), x=finite)
def test_unit_round_trips(pair, x):
    """to_x(x(v)) == v and x(to_x(v)) == v (rtol 4e-16: one multiply and one divide)."""
    inverse, forward = pair
    assert float(inverse(forward(x))) == pytest.approx(x, rel=4e-16, abs=0)
    assert float(forward(inverse(x))) == pytest.approx(x, rel=4e-16, abs=0)


@settings(max_examples=60, deadline=None)
@given(unit=st.sampled_from(sorted(units.CONVERTERS)), x=finite, k=st.floats(-1e3, 1e3))
def test_to_si_is_linear_with_positive_factor(unit, x, k):
    """Every datasheet unit is a positive scale of its SI unit: to_si(k x) = k to_si(x) (rtol 1e-15)."""
    f1 = float(units.to_si(1.0, unit))
    assert f1 > 0
    assert float(units.to_si(x, unit)) == pytest.approx(x * f1, rel=1e-15, abs=0)
    assert float(units.to_si(k * x, unit)) == pytest.approx(k * float(units.to_si(x, unit)), rel=1e-14, abs=1e-300)


# --------------------------------------------------------------------------
# earth
# --------------------------------------------------------------------------
ELLIPSOIDS = [earth.WGS84, earth.CGCS2000, earth.GRS80, earth.KRASSOVSKY]


@SETTINGS
@given(ell=st.sampled_from(ELLIPSOIDS), a=lats, b=lats)
def test_radii_monotonic_and_symmetric(ell, a, b):
    """R_M and R_N grow with |lat| (flattening > 0), R_N >= R_M, both even in lat, a(1-e2) <= R_M <= R_N <= a/sqrt(1-e2)."""
    (Ma, Na), (Mb, Nb) = earth.radii(a, ellipsoid=ell), earth.radii(b, ellipsoid=ell)
    if abs(a) < abs(b):
        assert Ma <= Mb * (1 + 1e-15) and Na <= Nb * (1 + 1e-15)
    assert Na >= Ma * (1 - 1e-15)
    Mm, Nm = earth.radii(-a, ellipsoid=ell)
    assert (Mm, Nm) == (pytest.approx(Ma, rel=1e-15), pytest.approx(Na, rel=1e-15))
    assert ell.a * (1 - ell.e2) * (1 - 1e-15) <= Ma and Na <= ell.a / np.sqrt(1 - ell.e2) * (1 + 1e-15)


@SETTINGS
@given(ell=st.sampled_from(ELLIPSOIDS), a=lats, b=lats, h1=st.floats(-500.0, 9000.0), h2=st.floats(-500.0, 9000.0))
def test_gravity_monotonic_and_symmetric(ell, a, b, h1, h2):
    """Normal gravity never decreases with |lat| and falls with height (strictly for steps > 1 mm);
    gravity_n = [0, 0, -g]; 9.7 < g < 9.84. (Latitude steps can be below rounding near the equator
    and the poles, where d sin^2(lat) / d lat = 0, hence non-strict there.)"""
    lo, hi = sorted([a, b], key=abs)
    assert earth.gravity(lo, h1, ellipsoid=ell) <= earth.gravity(hi, h1, ellipsoid=ell)
    low, high = sorted([h1, h2])
    if high - low > 1e-3:
        assert earth.gravity(a, low, ellipsoid=ell) > earth.gravity(a, high, ellipsoid=ell)
    g = earth.gravity(a, h1, ellipsoid=ell)
    assert earth.gravity(-a, h1, ellipsoid=ell) == pytest.approx(g, rel=1e-15)
    assert 9.7 < g < 9.84
    assert_allclose(earth.gravity_n(a, h1, ellipsoid=ell), [0.0, 0.0, -g], rtol=1e-15)


@SETTINGS
@given(lat=lats)
def test_earth_rate_n_geometry(lat):
    """|w_ie_n| = omega, no east component, up = omega sin(lat); degrees and radians agree."""
    w = earth.earth_rate_n(lat)
    om = earth.WGS84.omega
    assert np.linalg.norm(w) == pytest.approx(om, rel=4e-16)
    assert w[0] == 0.0 and w[2] == pytest.approx(om * np.sin(lat), rel=4e-16, abs=1e-25)
    # deg=True is exactly a deg2rad of the argument. (Comparing with w itself needs a tolerance that
    # grows as tan(lat): rad2deg/deg2rad moves lat by an ulp, and cos is ill-conditioned at the pole.)
    lat_deg = np.rad2deg(lat)
    assert_allclose(earth.earth_rate_n(lat_deg, deg=True), earth.earth_rate_n(np.deg2rad(lat_deg)), rtol=1e-15, atol=0)


@SETTINGS
@given(lat=st.floats(-1.5, 1.5), h=st.floats(-500.0, 9000.0), v=vec(3, lo=-300.0, hi=300.0), k=st.floats(-10.0, 10.0))
def test_transport_rate_linear_in_velocity(lat, h, v, k):
    """w_en_n is linear in velocity and blind to vertical velocity."""
    w = earth.transport_rate_n(lat, h, v)
    assert_allclose(earth.transport_rate_n(lat, h, k * v), k * w, rtol=1e-13, atol=1e-20)
    assert_allclose(earth.transport_rate_n(lat, h, v * [1.0, 1.0, 0.0]), w, rtol=0, atol=0)


@SETTINGS
@given(vec(3, lo=-100.0, hi=100.0, min_norm=1e-3), st.booleans())
def test_field_vector_to_angles_to_vector(B, deg):
    """B -> (D, I, F) -> B (the direction test_earth.py does not check), in degrees and radians."""
    D, I, F = earth.field_angles(B, deg=deg)
    assert F == pytest.approx(np.linalg.norm(B), rel=1e-15)
    assert_allclose(earth.field_from_angles(D, I, F, deg=deg), B, atol=1e-13 * np.linalg.norm(B))


# --------------------------------------------------------------------------
# atmosphere
# --------------------------------------------------------------------------
P_LOW, P_HIGH = float(atmosphere.isa_pressure(11000.0)), float(atmosphere.isa_pressure(-1000.0))


@SETTINGS
@given(frac=st.floats(1e-9, 1.0 - 1e-9), p0=st.floats(95000.0, 105000.0))  # inside the valid range
def test_isa_and_bmp180_pressure_round_trips(frac, p0):
    """p -> h -> p for the ISA and BMP180 formulas, over the -1 km .. 11 km range of each (rtol 1e-12)."""
    p = p0 / atmosphere.P0 * (P_LOW + frac * (P_HIGH - P_LOW))
    assert float(atmosphere.isa_pressure(atmosphere.isa_altitude(p, p0), p0)) == pytest.approx(p, rel=1e-12)
    lo, hi = float(atmosphere.bmp180_pressure(11000.0, p0)), float(atmosphere.bmp180_pressure(-1000.0, p0))
    pb = lo + frac * (hi - lo)
    assert float(atmosphere.bmp180_pressure(atmosphere.bmp180_altitude(pb, p0), p0)) == pytest.approx(pb, rel=1e-12)


@SETTINGS
@given(h1=st.floats(-1000.0, 11000.0), h2=st.floats(-1000.0, 11000.0))
def test_pressure_decreases_with_height(h1, h2):
    assume(abs(h1 - h2) > 1e-6)
    lo, hi = sorted([h1, h2])
    for f in (atmosphere.isa_pressure, atmosphere.bmp180_pressure):
        assert f(lo) > f(hi)


@SETTINGS
@given(p1=st.floats(3e4, 1.1e5), p2=st.floats(3e4, 1.1e5), p3=st.floats(3e4, 1.1e5), T=st.floats(200.0, 330.0))
def test_hypsometric_antisymmetric_and_additive(p1, p2, p3, T):
    """h(p1 | ref p2) = -h(p2 | ref p1), h(p1 | p3) = h(p1 | p2) + h(p2 | p3), h(p | p) = 0 (atol 1e-9 m)."""
    hh = atmosphere.hypsometric_height
    assert float(hh(p1, p2, T)) == pytest.approx(-float(hh(p2, p1, T)), abs=1e-9)
    assert float(hh(p1, p3, T)) == pytest.approx(float(hh(p1, p2, T)) + float(hh(p2, p3, T)), abs=1e-9)
    assert float(hh(p1, p1, T)) == 0.0


# --------------------------------------------------------------------------
# kalman
# --------------------------------------------------------------------------
@st.composite
def update_problems(draw, max_n=6, max_m=5, decades=12):
    """Any valid update: SPD P with eigenvalues over ``decades`` decades, random (even zero-row) H,
    SPD R, NaN components, wrapped-angle components and a gate."""
    seed = draw(st.integers(0, 2**32 - 1))
    n, m = draw(st.integers(1, max_n)), draw(st.integers(1, max_m))
    rng = np.random.default_rng(seed)
    Qp, _ = np.linalg.qr(rng.standard_normal((n, n)))
    P = Qp @ np.diag(10.0 ** rng.uniform(-decades / 2, decades / 2, n)) @ Qp.T
    P = (P + P.T) / 2
    Qr, _ = np.linalg.qr(rng.standard_normal((m, m)))
    R = Qr @ np.diag(10.0 ** rng.uniform(-3, 3, m)) @ Qr.T
    R = (R + R.T) / 2
    H = rng.standard_normal((m, n)) * 10.0 ** rng.uniform(-2, 2, (m, 1))
    H[rng.random(m) < 0.15] = 0.0  # a measurement that sees no state
    x = rng.standard_normal(n)
    z = H @ x + rng.standard_normal(m) * np.sqrt(np.diag(R))
    z[rng.random(m) < draw(st.sampled_from([0.0, 0.3]))] = np.nan
    angle_mask = rng.random(m) < 0.3
    z = np.where(angle_mask, z + 2 * PI * rng.integers(-3, 4, m), z)  # angles off by whole turns
    gate = draw(st.sampled_from([np.inf, 9.0, 1.0]))
    return x, P, z, H @ x, H, R, angle_mask, gate


def _psd_tol(P):
    return 1e-9 * np.abs(P).max()


@settings(max_examples=300, deadline=None)
@given(update_problems())
def test_update_covariance_symmetric_psd(problem):
    """After any valid update P is finite, exactly symmetric and PSD (eigenvalues >= -1e-9 max|P|),
    never larger than the prior, and the status matches what happened."""
    x, P, z, h, H, R, mask, gate = problem
    xn, Pn, y, nis, status = kalman.update(x, P, z, h, H, R, mask, gate)
    assert np.all(np.isfinite(xn)) and np.all(np.isfinite(Pn))
    assert np.array_equal(Pn, Pn.T)
    assert np.linalg.eigvalsh(Pn).min() >= -_psd_tol(P)
    finite = np.isfinite(z)
    assert np.array_equal(np.isnan(y), ~finite)
    assert np.all(np.abs(y[finite & mask]) <= PI)
    if not finite.any():
        assert status == kalman.NO_DATA and np.isnan(nis)
    else:
        assert nis >= -1e-12
        assert status == (kalman.REJECTED if nis > gate else kalman.ACCEPTED)
    if status != kalman.ACCEPTED:
        assert np.array_equal(Pn, P) and np.array_equal(xn, x)
    else:  # information never lost: P - Pn is PSD
        assert np.linalg.eigvalsh(P - Pn).min() >= -_psd_tol(P)


def _standard_update(x, P, z, h, H, R, mask):
    """Textbook (non-Joseph) update on the finite components, angle innovations wrapped."""
    keep = np.isfinite(z)
    y = z - h
    y[mask] = np.mod(y[mask] + PI, 2 * PI) - PI
    Hs, Rs, ys = H[keep], R[np.ix_(keep, keep)], y[keep]
    S = Hs @ P @ Hs.T + Rs
    K = np.linalg.solve(S, Hs @ P).T
    return x + K @ ys, (np.eye(x.size) - K @ Hs) @ P


@settings(max_examples=150, deadline=None)
@given(update_problems(max_n=5, max_m=4, decades=2))
def test_joseph_equals_standard_with_nan_and_angles(problem):
    """On well-conditioned cases (cond P <= 100, cond R <= 1e6) the Joseph update equals the standard form
    (I - K H) P and the information form P+^-1 = P^-1 + H^T R^-1 H, with NaN and wrapped components."""
    x, P, z, h, H, R, mask, _ = problem
    assume(np.isfinite(z).any())
    keep = np.isfinite(z)
    assume(np.linalg.cond(R[np.ix_(keep, keep)]) < 1e4)
    xn, Pn, _, _, status = kalman.update(x, P, z, h, H, R, mask, np.inf)
    assert status == kalman.ACCEPTED
    xs, Ps = _standard_update(x, P, z, h, H, R, mask)
    scale = np.abs(P).max()
    assert_allclose(Pn, Ps, rtol=0, atol=1e-8 * scale)
    assert_allclose(xn, xs, rtol=1e-7, atol=1e-7 * (1 + np.abs(xs).max()))
    Hs, Rs = H[keep], R[np.ix_(keep, keep)]
    info = np.linalg.inv(P) + Hs.T @ np.linalg.solve(Rs, Hs)
    assert_allclose(Pn @ info, np.eye(x.size), atol=1e-6)


@settings(max_examples=100, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), n=st.integers(1, 8))
def test_predict_keeps_covariance_symmetric_psd(seed, n):
    """predict: P+ = F P F^T + Q exactly symmetric and PSD for any F and PSD Q (Q may be singular)."""
    rng = np.random.default_rng(seed)
    A = rng.standard_normal((n, n))
    P = A @ A.T
    F = rng.standard_normal((n, n)) * 10.0 ** rng.uniform(-1, 1)
    B = rng.standard_normal((n, max(1, n // 2)))
    Q = B @ B.T
    x = rng.standard_normal(n)
    xn, Pn = kalman.predict(x, P, F, Q)
    assert_allclose(xn, F @ x, rtol=1e-12, atol=1e-12)
    assert np.array_equal(Pn, Pn.T)
    assert np.linalg.eigvalsh(Pn).min() >= -1e-10 * np.abs(Pn).max()
    assert_allclose(Pn, F @ P @ F.T + Q, rtol=1e-12, atol=1e-12 * np.abs(Pn).max())
