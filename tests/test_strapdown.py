"""Trajectories, ideal IMU outputs and the strapdown mechanisation.

Three tiers: analytic invariants (a static IMU senses g and Earth rate),
closed loops (ideal samples integrate back to the trajectory), and error
theory (biased sensors over 1 h follow the linear error model).
"""

import numpy as np
import pytest
from scipy.linalg import expm

from navlib import attitude, earth, strapdown, trajectory, units

LLA0 = np.array([units.deg(28.361735), units.deg(112.9), 60.0])


def test_static_imu_senses_gravity_and_earth_rate():
    hpr = units.deg([123.0, 4.0, -7.0])
    traj = trajectory.static(10.0, 0.01, LLA0, hpr)
    w, f = trajectory.ideal_imu(traj)
    C_nb = attitude.euler_to_dcm(hpr).T
    np.testing.assert_allclose(w, np.broadcast_to(C_nb @ earth.earth_rate_n(LLA0[0]), w.shape), atol=1e-18)
    g = earth.gravity(LLA0[0], LLA0[2])
    np.testing.assert_allclose(f, np.broadcast_to(C_nb @ [0, 0, g], f.shape), atol=1e-12)
    # Level, heading north: the y gyro reads W cos(lat), the z gyro W sin(lat), z accelerometer +g.
    w0, f0 = trajectory.ideal_imu(trajectory.static(1.0, 0.1, LLA0, [0, 0, 0]))
    np.testing.assert_allclose(w0[0], [0, earth.OMEGA_IE * np.cos(LLA0[0]), earth.OMEGA_IE * np.sin(LLA0[0])], atol=1e-18)
    np.testing.assert_allclose(f0[0], [0, 0, g], atol=1e-12)


def _drive():
    segs = [
        trajectory.Segment(20),
        trajectory.Segment(15, speed=12.0),
        trajectory.Segment(25, turn=units.deg(120), pitch=units.deg(3), roll=units.deg(-2)),
        trajectory.Segment(30, speed=20.0, turn=units.deg(-200)),
        trajectory.Segment(15, speed=0.0, pitch=0.0, roll=0.0),
        trajectory.Segment(10),
    ]
    return trajectory.vehicle(segs, 0.01, LLA0, units.deg(30.0))


def test_vehicle_profile():
    traj = _drive()
    hpr = traj.hpr
    assert np.isclose(units.to_deg(attitude.wrap_2pi(hpr[-1, 0])), 30 + 120 - 200 + 360)
    assert np.isclose(np.linalg.norm(traj.vel_n[2000 + 1500]), 12.0)
    np.testing.assert_allclose(traj.vel_n[-1], 0.0, atol=1e-12)
    # Velocity is along the forward body axis (no side slip).
    fwd_n = traj.C_bn[:, :, 1]
    speed = np.linalg.norm(traj.vel_n, axis=-1)
    np.testing.assert_allclose(np.einsum("ni,ni->n", fwd_n, traj.vel_n), speed, atol=1e-9)


def test_ideal_imu_integrates_back_to_the_trajectory():
    traj = _drive()
    w, f = trajectory.ideal_imu(traj)
    nav = strapdown.integrate(traj.lla[0], traj.vel_n[0], traj.q_bn[0], w, f, traj.dt)
    R_M, R_N = earth.radii(LLA0[0])
    assert np.abs(nav.lla[:, 0] - traj.lla[:, 0]).max() * R_M < 1e-6
    assert np.abs(nav.lla[:, 1] - traj.lla[:, 1]).max() * R_N < 1e-6
    assert np.abs(nav.lla[:, 2] - traj.lla[:, 2]).max() < 1e-6
    assert np.abs(nav.vel_n - traj.vel_n).max() < 1e-9
    dq = attitude.quat_mult(attitude.quat_conj(nav.q_bn), traj.q_bn)
    assert np.abs(attitude.quat_to_rotvec(dq)).max() < 1e-12


def _linear_errors(lat, hpr, f_b, dw, df, times, hold_height):
    """Propagate the augmented [error state; constant sensor errors] linear model."""
    C = attitude.euler_to_dcm(hpr)
    F = strapdown.error_model(lat, 0.0, np.zeros(3), C @ f_b)
    A = np.zeros((15, 15))
    A[:9, :9] = F
    A[:9, 9:] = strapdown.error_input(C)
    keep = [0, 1, 2, 3, 4, 6, 7] + list(range(9, 15)) if hold_height else list(range(15))
    A = A[np.ix_(keep, keep)]
    x0 = np.zeros(15)
    x0[9:12], x0[12:] = dw, df
    x0 = x0[keep]
    return np.array([expm(A * t) @ x0 for t in times]), keep


@pytest.mark.parametrize("lat_deg", [0.0, 30.0, 60.0])
@pytest.mark.parametrize("sensor", ["gyro", "accel"])
def test_static_hour_follows_error_theory(lat_deg, sensor):
    """1 h static with constant sensor errors: strapdown = linear error model (height held)."""
    dt, T = 0.1, 3600.0
    lla0 = np.array([units.deg(lat_deg), 0.3, 0.0])
    hpr = units.deg([40.0, 3.0, -2.0])
    traj = trajectory.static(T, dt, lla0, hpr)
    w, f = trajectory.ideal_imu(traj)
    dw = units.deg_per_h([0.01, -0.02, 0.015]) if sensor == "gyro" else np.zeros(3)
    df = units.ug([100.0, -50.0, 30.0]) if sensor == "accel" else np.zeros(3)
    nav = strapdown.integrate(lla0, np.zeros(3), traj.q_bn[0], w + dw, f + df, dt, hold_height=True)
    idx = np.arange(0, len(traj), 1200)
    lin, _ = _linear_errors(lla0[0], hpr, f[0], dw, df, traj.time[idx], hold_height=True)
    # attitude error phi from C_hat = (I - [phi x]) C
    E = np.eye(3) - nav.C_bn[idx] @ np.swapaxes(traj.C_bn[idx], -1, -2)
    phi = np.stack([E[:, 2, 1], E[:, 0, 2], E[:, 1, 0]], -1)
    dpos = nav.lla[idx, :2] - traj.lla[idx, :2]
    # Second-order terms are ~1e-3 of the error itself after 1 h.
    for got, want in ((phi, lin[:, 0:3]), (nav.vel_n[idx, :2], lin[:, 3:5]), (dpos, lin[:, 5:7])):
        assert np.abs(got - want).max() <= 2e-3 * np.abs(want).max()
    # And the errors are large enough for the comparison to mean something:
    assert np.abs(dpos).max() * earth.WGS84.a > 400.0


def test_free_vertical_channel_is_unstable_as_predicted():
    dt, T = 0.1, 1200.0
    traj = trajectory.static(T, dt, LLA0, [0, 0, 0])
    w, f = trajectory.ideal_imu(traj)
    df = units.ug([0.0, 0.0, 1.0])
    nav = strapdown.integrate(LLA0, np.zeros(3), traj.q_bn[0], w, f + df, dt)
    idx = np.arange(0, len(traj), 600)
    lin, keep = _linear_errors(LLA0[0], [0, 0, 0], f[0], np.zeros(3), df, traj.time[idx], hold_height=False)
    dh = nav.lla[idx, 2] - LLA0[2]
    np.testing.assert_allclose(dh[1:], lin[1:, 8], rtol=5e-3)
    # cosh growth: b/(2g/R) (cosh(sqrt(2g/R) t) - 1) is 1.4x the 0.5 b t^2 of a plain double integrator at 1200 s
    assert dh[-1] > 1.3 * 0.5 * df[2] * T**2


def test_integrate_attitude_batches_and_earth_rate():
    traj = trajectory.static(60.0, 0.01, LLA0, units.deg([10, 2, 3]))
    w, _ = trajectory.ideal_imu(traj)
    q = strapdown.integrate_attitude(traj.q_bn[0], w, traj.dt, w_in_n=earth.earth_rate_n(LLA0[0]))
    assert np.abs(attitude.quat_to_rotvec(attitude.quat_mult(attitude.quat_conj(q), traj.q_bn))).max() < 1e-12
    rng = np.random.default_rng(7)
    wb = w + 1e-3 * rng.standard_normal((3,) + w.shape)
    qb = strapdown.integrate_attitude(traj.q_bn[0], wb, traj.dt)
    assert qb.shape == (3, len(traj), 4)
    np.testing.assert_array_equal(qb[1], strapdown.integrate_attitude(traj.q_bn[0], wb[1], traj.dt))


def test_integrate_batch_matches_single_runs():
    traj = trajectory.static(20.0, 0.1, LLA0, [0, 0, 0])
    w, f = trajectory.ideal_imu(traj)
    rng = np.random.default_rng(3)
    wb = w + 1e-4 * rng.standard_normal((2,) + w.shape)
    nav = strapdown.integrate(LLA0, np.zeros(3), traj.q_bn[0], wb, f, traj.dt)
    one = strapdown.integrate(LLA0, np.zeros(3), traj.q_bn[0], wb[1], f, traj.dt)
    np.testing.assert_array_equal(nav.lla[1], one.lla)
    assert nav.lla.shape == (2, len(traj), 3)


def test_reciprocating_rotation_alternates():
    traj = trajectory.reciprocating_rotation(
        20.0, 0.01, LLA0, units.deg([0, 30, 0]), [1, 0, 0], np.pi / 2, period=5.0, rotation_time=1.0
    )
    pitch = units.to_deg(traj.hpr[:, 1])
    t = traj.time
    assert np.allclose(pitch[(t > 0.5) & (t < 3.9)], 30.0)
    assert np.allclose(pitch[(t > 5.5) & (t < 8.9)], 90.0 - (120.0 - 90.0), atol=1e-6)  # 30 + 90 = 120 -> 60 over the top
    assert np.allclose(pitch[(t > 10.5) & (t < 13.9)], 30.0)


@pytest.mark.parametrize(
    "bad, match",
    [
        (dict(w_ib_b=np.full((10, 3), np.nan)), "w_ib_b"),
        (dict(f_b=np.zeros((9, 3))), "f_b"),
        (dict(lla0=[np.pi / 2, 0, 0]), "lat"),
        (dict(dt=-0.1), "dt"),
        (dict(q0=[0, 0, 0, 0]), "q0"),
    ],
)
def test_integrate_rejects_bad_input(bad, match):
    args = dict(lla0=LLA0, vel0=np.zeros(3), q0=[1, 0, 0, 0], w_ib_b=np.zeros((10, 3)), f_b=np.zeros((10, 3)), dt=0.1)
    args.update(bad)
    with pytest.raises(ValueError, match=match):
        strapdown.integrate(**args)


def test_trajectory_generators_reject_bad_input():
    with pytest.raises(ValueError, match="axis_b"):
        trajectory.reciprocating_rotation(10, 0.1, LLA0, [0, 0, 0], [1, 1, 0], 1.0, 5.0)
    with pytest.raises(ValueError, match="rotation_time"):
        trajectory.reciprocating_rotation(10, 0.1, LLA0, [0, 0, 0], [1, 0, 0], 1.0, 5.0, rotation_time=6.0)
    with pytest.raises(ValueError, match="segments"):
        trajectory.vehicle([], 0.1, LLA0, 0.0)
    with pytest.raises(ValueError, match="duration"):
        trajectory.static(-1.0, 0.1, LLA0, [0, 0, 0])
    with pytest.raises(ValueError, match="traj"):
        trajectory.ideal_imu("not a trajectory")


def test_nav_step_is_the_integrate_step():
    """The validated strapdown.nav_step gives integrate's states bit for bit, updating float64 arrays in place."""
    traj = _drive()
    w, f = trajectory.ideal_imu(traj)
    nav = strapdown.integrate(traj.lla[0], traj.vel_n[0], traj.q_bn[0], w[:50], f[:50], traj.dt)
    lla, vel, q = traj.lla[0].copy(), traj.vel_n[0].copy(), traj.q_bn[0].copy()
    consts = strapdown.earth_constants()
    for k in range(50):
        out = strapdown.nav_step(lla, vel, q, w[k], f[k], traj.dt, consts)
        assert out[0] is lla and out[1] is vel and out[2] is q
    np.testing.assert_array_equal(lla, nav.lla[-1])
    np.testing.assert_array_equal(vel, nav.vel_n[-1])
    np.testing.assert_array_equal(q, nav.q_bn[-1])


def test_mat3_vec_is_the_matrix_product():
    """The allocation-free 3 x 3 product of the compiled step equals numba's ``C @ v`` (OpenBLAS's dgemv on
    x86-64 bit for bit, which keeps the notebooks' recorded results; to rounding elsewhere), for arrays and
    tuples of rows alike."""
    from numba import njit

    from navlib import _kernels

    blas = njit(lambda C, v: C @ v)
    rng = np.random.default_rng(8)
    for _ in range(200):
        C, v = rng.standard_normal((3, 3)), rng.standard_normal(3)
        got = np.array(_kernels.mat3_vec(C, v))
        np.testing.assert_allclose(got, blas(C, v), rtol=0, atol=1e-15 * np.abs(C).max() * np.abs(v).max())
        assert got.tolist() == list(_kernels.mat3_vec(tuple(map(tuple, C)), v))


def test_nav_step_integer_state_is_not_modified_and_gives_the_float_result():
    """Integer (or list) state arrays are read as float64 copies: the caller's arrays stay as they were
    (they were truncated in place before), and the returned state is the float64 result."""
    consts = strapdown.earth_constants()
    w, f = [0.01, -0.02, 0.3], [0.5, 0.2, 9.8]
    lla_i, vel_i, q_l = np.array([0, 0, 100]), np.array([3, 4, 0]), [1, 0, 0, 0]
    lla, vel, q = strapdown.nav_step(lla_i, vel_i, q_l, w, f, 0.5, consts)
    want = [np.array([0.0, 0.0, 100.0]), np.array([3.0, 4.0, 0.0]), np.array([1.0, 0.0, 0.0, 0.0])]
    strapdown.nav_step(*want, np.array(w), np.array(f), 0.5, consts)
    for got, ref in zip((lla, vel, q), want, strict=True):
        assert got.dtype == np.float64
        np.testing.assert_array_equal(got, ref)
    np.testing.assert_array_equal(lla_i, [0, 0, 100])
    np.testing.assert_array_equal(vel_i, [3, 4, 0])
    assert q_l == [1, 0, 0, 0] and lla_i.dtype.kind == vel_i.dtype.kind == "i"
    assert abs(lla[0]) > 0 and vel[1] != 4.0  # the step did move the state


@pytest.mark.parametrize(
    "kw, match",
    [
        (dict(w=np.zeros(0)), "^w: expected shape"),
        (dict(lla=[45.0, 0.0, 0.0]), r"^lla\[0\] \(lat\): expected values in"),
        (dict(dt=-0.01), "^dt: expected a positive value"),
        (dict(q=np.zeros(4, dtype=np.float32)), "^q: expected a non-zero quaternion"),
    ],
    ids=["empty-gyro", "lat45", "dt-negative", "q-zero"],
)
def test_nav_step_rejects_what_the_kernel_would_misread(kw, match):
    args = dict(
        lla=LLA0.copy(),
        vel=np.zeros(3),
        q=np.array([1.0, 0, 0, 0]),
        w=np.zeros(3),
        f=[0, 0, 9.8],
        dt=0.01,
        earth_consts=strapdown.earth_constants(),
    )
    with pytest.raises(ValueError, match=match):
        strapdown.nav_step(**{**args, **kw})
