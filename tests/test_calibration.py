"""navlib.calibration: magnetometer ellipsoid fit, multi-position accelerometer fit, gyro bias at rest and
Allan-deviation noise characterisation, each on simulated data with known errors (navlib's simulators).

Tolerances are a few standard errors of each estimate, derived in the comments from the simulated noise and
sample counts; the empirical spreads quoted were measured over 40-100 seeds when the tests were written.
"""

from __future__ import annotations

import numpy as np
import pytest

from navlib import analysis, attitude, calibration, earth, sensors, units
from navlib.imu import ImuSamples

B_N = np.array([0.0, 20.0, -45.0])  # local field, ENU (uT); |B_N| = 49.2 uT
MAG = sensors.MagnetometerModel(noise=0.3, hard_iron=20.0, soft_iron=0.1)
SIX = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], dtype=float)


def random_quats(rng, n):
    q = rng.standard_normal((n, 4))
    return q / np.linalg.norm(q, axis=-1, keepdims=True)  # uniform over rotations


def tilted_quats(rng, n, max_tilt):
    """Any heading, pitch and roll within +-max_tilt (rad)."""
    hpr = np.stack([rng.uniform(0, 2 * np.pi, n), rng.uniform(-max_tilt, max_tilt, n), rng.uniform(-max_tilt, max_tilt, n)], -1)
    return attitude.euler_to_quat(hpr)


# --------------------------------------------------------------------------
# Magnetometer
# --------------------------------------------------------------------------


@pytest.fixture(scope="module")
def mag():
    rng = np.random.default_rng(11)
    r_att, r_mag = rng.spawn(2)
    return sensors.simulate_magnetometer(random_quats(r_att, 400), B_N, MAG, r_mag)


def test_magnetometer_recovers_hard_and_soft_iron(mag):
    F = np.linalg.norm(B_N)
    cal = calibration.fit_magnetometer(mag.m_b, field_strength=F)
    # 400 samples all over the sphere with noise sigma = 0.3 uT: the offset's standard error is about
    # sigma sqrt(3 / N) ~ 0.026 uT per axis and the soft iron's about (sigma / F) sqrt(6 / N) ~ 8e-4;
    # 0.15 uT and 4e-3 are about 5 of them (measured errors: 0.03 uT, 5e-4).
    np.testing.assert_allclose(cal.offset, mag.hard_iron, atol=0.15)
    np.testing.assert_allclose(cal.soft_iron @ mag.soft_iron, np.eye(3), atol=4e-3)
    assert cal.field_strength == F
    # |m_cal| - F is the sensor noise along the field after the correction S^-1: RMS
    # sigma sqrt(mean |S^-1 u|^2) for the field directions u; 400 samples give a 3.5 % sd, so 10 %.
    u = cal.apply(mag.m_b) / np.linalg.norm(cal.apply(mag.m_b), axis=-1, keepdims=True)
    expected = MAG.noise * np.sqrt(np.mean(np.sum((u @ np.linalg.inv(mag.soft_iron).T) ** 2, -1)))
    assert cal.residual == pytest.approx(expected, rel=0.1)
    assert cal.norm_spread_after == pytest.approx(expected, rel=0.1)
    assert cal.norm_spread_before > 10 * cal.norm_spread_after  # about 60 here
    assert cal.condition < 5  # a full sphere: about 2
    norm = np.linalg.norm(cal.apply(mag.m_b), axis=-1)
    assert np.sqrt(np.mean((norm - F) ** 2)) == pytest.approx(cal.residual, rel=1e-12)


def test_magnetometer_without_field_strength_keeps_det_one(mag):
    cal = calibration.fit_magnetometer(mag.m_b)
    scale = np.linalg.det(mag.soft_iron) ** (1 / 3)  # W = S / scale has det 1
    assert np.linalg.det(cal.soft_iron) == pytest.approx(1.0, abs=1e-12)
    assert cal.field_strength == pytest.approx(np.linalg.norm(B_N) * scale, rel=2e-3)
    np.testing.assert_allclose(cal.soft_iron @ mag.soft_iron, scale * np.eye(3), atol=4e-3)
    np.testing.assert_allclose(cal.offset, mag.hard_iron, atol=0.15)


def test_mag_calibration_from_stored_values_applies_to_any_batch():
    W = np.array([[1.1, 0.05, 0.0], [0.05, 0.9, 0.0], [0.0, 0.0, 1.0]])
    cal = calibration.MagCalibration([1.0, 2.0, 3.0], W, 50.0)
    m = np.arange(24.0).reshape(2, 4, 3)
    np.testing.assert_allclose(cal.apply(m), np.einsum("ij,...j->...i", W, m - [1.0, 2.0, 3.0]))
    assert np.isnan(cal.residual)
    out = cal.apply([[np.nan, 0.0, 0.0], [1.0, 2.0, 3.0]])  # NaN (a dropout) propagates
    assert np.isnan(out[0]).all() and np.all(out[1] == 0.0)


def test_magnetometer_refuses_planar_and_small_cap_coverage():
    rng = np.random.default_rng(12)
    heading_only = attitude.euler_to_quat(np.stack([np.linspace(0, 4 * np.pi, 300), np.zeros(300), np.zeros(300)], -1))
    flat = sensors.simulate_magnetometer(heading_only, B_N, MAG, rng).m_b
    with pytest.raises(ValueError, match=r"^m_b: .*one plane.*turn the sensor through all orientations"):
        calibration.fit_magnetometer(flat)
    cap = sensors.simulate_magnetometer(tilted_quats(rng, 300, np.deg2rad(30)), B_N, MAG, rng).m_b
    with pytest.raises(ValueError, match=r"^m_b: the orientations cover too little of the sphere"):
        calibration.fit_magnetometer(cap)
    # Tilts within +-90 deg (any heading) are enough.
    wide = sensors.simulate_magnetometer(tilted_quats(rng, 300, np.deg2rad(90)), B_N, MAG, rng)
    assert calibration.fit_magnetometer(wide.m_b).condition < calibration.MAX_MAG_CONDITION


# --------------------------------------------------------------------------
# Accelerometer
# --------------------------------------------------------------------------

VRW = units.ug_per_sqrt_hz(100.0)  # 9.8e-4 m/s^2/sqrt(Hz)
DT_ACC, N_POS = 0.01, 1000  # 10 s per position at 100 Hz


def positions(directions, model, seed):
    """Static means of an IMU held still with -gravity along each body direction, one simulated record."""
    up_b = directions / np.linalg.norm(directions, axis=-1, keepdims=True)
    f_ideal = np.repeat(units.G0 * up_b, N_POS, axis=0)
    out = sensors.simulate_imu(
        np.zeros_like(f_ideal), f_ideal, DT_ACC, sensors.ImuModel(accel=model), np.random.default_rng(seed)
    )
    return out.f_b.reshape(len(up_b), N_POS, 3).mean(1), out.accel_bias[0], out.accel_matrix


def test_accelerometer_six_position_bias_and_scale():
    model = sensors.TriadErrors(noise_density=VRW, bias=0.05, scale_factor=0.01)
    f_means, bias, M = positions(SIX, model, 21)
    cal = calibration.fit_accelerometer(f_means)
    # Each mean has sigma = VRW / sqrt(10 s) = 3.1e-4 m/s^2; the six-position bias is (up + down) / 2
    # (sd 2.2e-4) and the scale (up - down) / 2g (sd 2.2e-5): 1e-3 and 1e-4 are about 4.5 sd.
    np.testing.assert_allclose(cal.bias, bias, atol=1e-3)
    np.testing.assert_allclose(cal.scale_factor, np.diag(M) - 1, atol=1e-4)
    np.testing.assert_allclose(cal.matrix, np.diag(1 / np.diag(M)), atol=1e-4)
    assert cal.condition == pytest.approx(1.0, abs=0.1)
    # Six positions and six unknowns: an exact fit.
    assert cal.residual < 1e-9
    np.testing.assert_allclose(np.linalg.norm(cal.apply(f_means), axis=-1), units.G0, atol=1e-9)


def test_accelerometer_lower_triangular_with_misalignment():
    model = sensors.TriadErrors(noise_density=VRW, bias=0.05, scale_factor=0.01, misalignment=2e-3)
    directions = np.concatenate([SIX, attitude.quat_rotate(random_quats(np.random.default_rng(22), 12), [0.0, 0.0, 1.0])])
    f_means, bias, M = positions(directions, model, 23)
    cal = calibration.fit_accelerometer(f_means, misalignment=True)
    assert np.all(np.triu(cal.matrix, 1) == 0) and np.all(np.diag(cal.matrix) > 0)
    # Only S^T S (the metric) is observable; it equals M^-T M^-1. 18 positions with sigma 3.1e-4 m/s^2
    # (3.2e-5 g): 4e-4 and 2e-3 m/s^2 are over 5 standard errors (measured: 1.6e-4, 2e-4).
    M_inv = np.linalg.inv(M)
    np.testing.assert_allclose(cal.matrix.T @ cal.matrix, M_inv.T @ M_inv, atol=4e-4)
    np.testing.assert_allclose(cal.bias, bias, atol=2e-3)
    # Residual: the noise left after fitting 9 unknowns to 18 norms, about sigma sqrt(9/18).
    assert cal.residual < 3.1e-4
    # The diagonal fit cannot absorb the misalignment: a larger residual.
    assert calibration.fit_accelerometer(f_means).residual > 2 * cal.residual


def test_accelerometer_refuses_orientations_near_level():
    rng = np.random.default_rng(24)
    directions = attitude.quat_rotate(tilted_quats(rng, 8, 0.2), [0.0, 0.0, 1.0])
    f_means, _, _ = positions(directions, sensors.TriadErrors(noise_density=VRW), 25)
    with pytest.raises(ValueError, match=r"^f_means: the orientations do not determine bias and scale"):
        calibration.fit_accelerometer(f_means)


def test_accel_calibration_from_stored_values():
    cal = calibration.AccelCalibration([0.1, 0.0, -0.1], np.diag([1.01, 0.99, 1.0]))
    np.testing.assert_allclose(cal.apply([[0.1, 0.0, 9.7]]), [[0.0, 0.0, 9.8]])
    np.testing.assert_allclose(cal.scale_factor, [1 / 1.01 - 1, 1 / 0.99 - 1, 0.0])
    with pytest.raises(ValueError, match="^matrix: "):
        calibration.AccelCalibration(np.zeros(3), np.ones((3, 3)))  # not triangular: not a calibration


# --------------------------------------------------------------------------
# Gyro bias at rest
# --------------------------------------------------------------------------


def test_gyro_bias_at_rest_removes_earth_rate():
    lat, hpr = np.deg2rad(48.0), np.array([1.0, 0.1, -0.2])
    C_bn = attitude.euler_to_dcm(hpr)
    n, dt, arw = 6000, 0.01, units.deg_per_sqrt_h(0.3)
    w_ideal = np.broadcast_to(earth.earth_rate_b(C_bn, lat), (n, 3))
    model = sensors.ImuModel(gyro=sensors.TriadErrors(noise_density=arw, bias=units.deg_per_h(20.0)))
    out = sensors.simulate_imu(w_ideal, np.zeros((n, 3)), dt, model, np.random.default_rng(31))
    bias, se = calibration.gyro_bias_at_rest(out.w_ib_b, lat, C_bn)
    # The standard error of a 60-s mean is N / sqrt(T); estimated from the samples to within 4 % (sd 1 %).
    np.testing.assert_allclose(se, arw / np.sqrt(n * dt), rtol=0.04)
    assert np.all(np.abs(bias - out.gyro_bias[0]) < 4 * se)
    # Without attitude and latitude: the plain mean, Earth rate included.
    mean, _ = calibration.gyro_bias_at_rest(out.w_ib_b)
    np.testing.assert_allclose(mean - bias, earth.earth_rate_b(C_bn, lat), atol=1e-15)
    # Trials on leading axes.
    b2, se2 = calibration.gyro_bias_at_rest(np.stack([out.w_ib_b, out.w_ib_b]), lat, C_bn)
    assert b2.shape == se2.shape == (2, 3)


# --------------------------------------------------------------------------
# Characterise my IMU
# --------------------------------------------------------------------------

DT, N = 0.1, 100_000  # 2.8 h at 10 Hz
TRUTH = sensors.ImuModel(
    gyro=sensors.TriadErrors(
        noise_density=units.deg_per_sqrt_h(0.3), bias_instability=units.deg_per_h(10.0), correlation_time=30.0
    ),
    accel=sensors.TriadErrors(noise_density=units.ug_per_sqrt_hz(100.0), bias_instability=units.ug(50.0), correlation_time=30.0),
)


def static_record(model, seed):
    f_ideal = np.tile([0.0, 0.0, units.G0], (N, 1))
    return sensors.simulate_imu(np.zeros((N, 3)), f_ideal, DT, model, np.random.default_rng(seed))


@pytest.fixture(scope="module")
def record():
    return static_record(TRUTH, 41)


@pytest.fixture(scope="module")
def noise(record):
    return calibration.characterise(record.w_ib_b, record.f_b, DT)


def test_characterise_recovers_the_noise_model(noise):
    for tri, truth in ((noise.gyro, TRUTH.gyro), (noise.accel, TRUTH.accel)):
        # White noise: the Allan deviation at m <= 10 samples has edf > 1.4e4 (relative sd < 0.6 %);
        # 5 % is 8 sd (measured over 100 seeds: max error 0.9 %).
        np.testing.assert_allclose(tri.noise_density, truth.noise_density, rtol=0.05)
        # Bias instability: read at its peak, tau = 1.89 T_c = 57 s, m = 568 samples, n/m = 176 clusters,
        # flicker edf ~ 220: relative sd of the deviation 1/sqrt(2 edf) = 4.8 %; 25 % is 5 sd
        # (measured over 100 seeds: max error 13 %, rms 4 %).
        np.testing.assert_allclose(tri.bias_instability, truth.bias_instability, rtol=0.25)
        # Correlation time: flat near the peak, so looser (measured 25 to 37 s for 30 s).
        assert np.all((tri.correlation_time > truth.correlation_time / 2) & (tri.correlation_time < 2 * truth.correlation_time))
        assert np.all(tri.rate_random_walk == 0.0)  # not fitted
        assert tri.adev.shape == (tri.taus.size, 3)
    np.testing.assert_array_equal(noise.angle_random_walk, noise.gyro.noise_density)
    np.testing.assert_array_equal(noise.velocity_random_walk, noise.accel.noise_density)
    # dt is derived from the time stamps; its last bit depends on numpy's reductions (0.1 + 1 ulp at numpy 2.0).
    assert noise.n_samples == N and noise.dt == pytest.approx(DT, rel=1e-15) and noise.confidence == 0.95


@pytest.fixture(scope="module")
def noise99(record):
    return calibration.characterise(record.w_ib_b, record.f_b, DT, confidence=0.99)


def test_characterise_intervals_contain_the_truth(noise, noise99):
    # Six intervals per term here: at 95 % all six would miss the truth now and then by design. Measured
    # coverage over 100 seeds (600 axes): at 95 %, 100 % for the white noise (its edf is conservative for
    # a fitted value) and 96-97 % for the bias instability; at 99 %, 100 % for both. So 99 % here.
    for tri, truth in ((noise99.gyro, TRUTH.gyro), (noise99.accel, TRUTH.accel)):
        for ci, value, true in (
            (tri.noise_density_ci, tri.noise_density, truth.noise_density),
            (tri.bias_instability_ci, tri.bias_instability, truth.bias_instability),
        ):
            assert ci.shape == (3, 2)
            assert np.all(ci[:, 0] < value) and np.all(value < ci[:, 1])
            assert np.all(ci[:, 0] <= true) and np.all(true <= ci[:, 1])
        # K not fitted: 0, with the upper limit the longest averaging time allows.
        assert np.all(tri.rate_random_walk_ci[:, 0] == 0) and np.all(np.isfinite(tri.rate_random_walk_ci[:, 1]))
    # Higher confidence, wider intervals around the same estimates.
    for narrow, wide in ((noise.gyro, noise99.gyro), (noise.accel, noise99.accel)):
        np.testing.assert_array_equal(wide.bias_instability, narrow.bias_instability)
        for a, b in ((narrow.noise_density_ci, wide.noise_density_ci), (narrow.bias_instability_ci, wide.bias_instability_ci)):
            assert np.all(b[:, 0] < a[:, 0]) and np.all(b[:, 1] > a[:, 1])


def test_to_imu_model_feeds_the_simulator(noise):
    model = noise.to_imu_model()
    assert isinstance(model, sensors.ImuModel) and model.name == "characterised"
    for triad, tri, truth in ((model.gyro, noise.gyro, TRUTH.gyro), (model.accel, noise.accel, TRUTH.accel)):
        assert triad.noise_density == pytest.approx(np.sqrt(np.mean(tri.noise_density**2)))
        assert triad.noise_density == pytest.approx(truth.noise_density, rel=0.05)
        assert triad.bias_instability == pytest.approx(truth.bias_instability, rel=0.25)
        assert triad.correlation_time == pytest.approx(np.exp(np.mean(np.log(tri.correlation_time))))
        # Not observable from one static record: left at the defaults.
        assert triad.bias == triad.scale_factor == triad.misalignment == 0.0
        assert triad.rate_random_walk == 0.0 and triad.full_scale == np.inf
    worst = noise.to_imu_model("worst axis", combine="max")
    assert worst.name == "worst axis"
    assert worst.gyro.noise_density == noise.gyro.noise_density.max() >= model.gyro.noise_density
    # The model runs in the simulator.
    out = sensors.simulate_imu(np.zeros((10, 3)), np.zeros((10, 3)), DT, model, np.random.default_rng(0))
    assert out.w_ib_b.shape == (10, 3)


def test_characterise_takes_imu_samples(record, noise):
    via_samples = calibration.characterise(ImuSamples(record.w_ib_b, record.f_b, DT))
    np.testing.assert_array_equal(via_samples.gyro.noise_density, noise.gyro.noise_density)
    np.testing.assert_array_equal(via_samples.accel.bias_instability_ci, noise.accel.bias_instability_ci)


def test_characterise_rate_random_walk():
    truth = sensors.ImuModel(
        gyro=sensors.TriadErrors(
            noise_density=units.deg_per_sqrt_h(0.3),
            bias_instability=units.deg_per_h(10.0),
            correlation_time=30.0,
            rate_random_walk=3e-6,
        ),
        accel=sensors.TriadErrors(noise_density=units.ug_per_sqrt_hz(100.0), rate_random_walk=3e-5),
    )
    rec = static_record(truth, 42)
    res = calibration.characterise(rec.w_ib_b, rec.f_b, DT, rate_random_walk=True)
    for tri, tr in ((res.gyro, truth.gyro), (res.accel, truth.accel)):
        np.testing.assert_allclose(tri.noise_density, tr.noise_density, rtol=0.05)
        ci = tri.rate_random_walk_ci
        assert np.all(ci[:, 0] <= tr.rate_random_walk) and np.all(tr.rate_random_walk <= ci[:, 1])
    # K shows only at the longest averaging times, where the random-walk edf is 1.3 to ~10: over 40 seeds
    # the gyro's K/K_true ranged 0.15 to 1.7 (5-95 %: 0.4 to 1.3), so a factor 2.5 either way.
    # Where the data fit without K (a Gauss-Markov bias explains the last decade as well), K is left out and
    # its interval, from 0, still holds the truth (above).
    ratio = res.gyro.rate_random_walk / truth.gyro.rate_random_walk
    kept = ratio > 0
    assert np.all((ratio[kept] > 1 / 2.5) & (ratio[kept] < 2.5))
    assert np.all(res.gyro.evidence[~kept, 1] <= analysis.ALLAN_EVIDENCE)
    np.testing.assert_allclose(res.gyro.bias_instability, truth.gyro.bias_instability, rtol=0.25)
    # The accelerometer has no Gauss-Markov bias: any fitted with its peak beyond the record became K.
    assert np.all(np.isinf(res.accel.bias_instability_ci[res.accel.bias_instability == 0, 1]))


# --------------------------------------------------------------------------
# Bad input
# --------------------------------------------------------------------------

M9 = np.random.default_rng(0).standard_normal((20, 3)) * 40
W_REC = np.zeros((200, 3))
F_REC = np.tile([0.0, 0.0, 9.8], (200, 1))


@pytest.mark.parametrize(
    "arg, call",
    [
        ("m_b", lambda: calibration.fit_magnetometer(M9[:8])),
        ("m_b", lambda: calibration.fit_magnetometer(M9[:, :2])),
        ("m_b", lambda: calibration.fit_magnetometer(np.where(np.arange(60).reshape(20, 3) == 7, np.nan, M9))),
        ("field_strength", lambda: calibration.fit_magnetometer(M9, field_strength=-1.0)),
        ("offset", lambda: calibration.MagCalibration([0.0, 0.0], np.eye(3), 50.0)),
        ("soft_iron", lambda: calibration.MagCalibration(np.zeros(3), [[1.0, 0.2, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], 50.0)),
        ("m_raw", lambda: calibration.MagCalibration(np.zeros(3), np.eye(3), 50.0).apply([1.0, 2.0])),
        ("f_means", lambda: calibration.fit_accelerometer(units.G0 * SIX[:5])),
        ("f_means", lambda: calibration.fit_accelerometer(units.G0 * np.concatenate([SIX, SIX[:2]]), misalignment=True)),
        ("f_means", lambda: calibration.fit_accelerometer(np.where(SIX == 1, np.nan, SIX))),
        ("f_means", lambda: calibration.fit_accelerometer(units.G0 * SIX[:, :2])),
        ("g", lambda: calibration.fit_accelerometer(units.G0 * SIX, g=0.0)),
        ("misalignment", lambda: calibration.fit_accelerometer(units.G0 * SIX, misalignment=1)),
        ("w_ib_b", lambda: calibration.gyro_bias_at_rest(np.zeros((1, 3)))),
        ("w_ib_b", lambda: calibration.gyro_bias_at_rest([[0.0, np.nan, 0.0], [0.0, 0.0, 0.0]])),
        ("C_bn", lambda: calibration.gyro_bias_at_rest(np.zeros((5, 3)), lat=0.5)),
        ("lat", lambda: calibration.gyro_bias_at_rest(np.zeros((5, 3)), C_bn=np.eye(3))),
        ("lat", lambda: calibration.gyro_bias_at_rest(np.zeros((5, 3)), lat=2.0, C_bn=np.eye(3))),
        ("C_bn", lambda: calibration.gyro_bias_at_rest(np.zeros((5, 3)), lat=0.5, C_bn=2 * np.eye(3))),
        ("w_ib_b", lambda: calibration.characterise(W_REC[:50], F_REC[:50], 0.1)),
        ("w_ib_b", lambda: calibration.characterise(np.where(np.arange(600).reshape(200, 3) == 5, np.nan, W_REC), F_REC, 0.1)),
        ("w_ib_b", lambda: calibration.characterise(np.stack([W_REC, W_REC]), np.stack([F_REC, F_REC]), 0.1)),
        ("f_b", lambda: calibration.characterise(W_REC, F_REC[:100], 0.1)),
        ("f_b", lambda: calibration.characterise(W_REC, None, 0.1)),
        ("f_b", lambda: calibration.characterise(ImuSamples(W_REC, F_REC, 0.1), F_REC)),
        ("dt", lambda: calibration.characterise(W_REC, F_REC, 0.0)),
        ("dt", lambda: calibration.characterise(W_REC, F_REC, np.linspace(0.09, 0.11, 200))),
        ("confidence", lambda: calibration.characterise(W_REC, F_REC, 0.1, confidence=1.0)),
        ("rate_random_walk", lambda: calibration.characterise(W_REC, F_REC, 0.1, rate_random_walk="yes")),
    ],
)
def test_bad_input_names_the_argument(arg, call):
    with pytest.raises(ValueError, match=f"^{arg}: "):
        call()


def test_to_imu_model_bad_input(noise):
    with pytest.raises(ValueError, match="^combine: "):
        noise.to_imu_model(combine="mean")
    with pytest.raises(ValueError, match="^name: "):
        noise.to_imu_model(name=3)


def test_fit_magnetometer_refuses_a_degenerate_or_implausible_fit():
    """Issue 34: a fit giving 3.3 uT, spread worse after than before, was accepted. A sphere of 3 uT is refused
    by the plausible range; a noisy cap (the sensor tilted less than 73 deg from one pose, 6 uT of disturbance)
    fits an ellipsoid that makes |m| no more constant than it was, and is refused too."""
    rng = np.random.default_rng(3434)
    dirs = attitude.quat_rotate(rng.standard_normal((400, 4)), [0.0, 0.0, 1.0])
    small = 3.0 * dirs + 0.05 * rng.standard_normal((400, 3))
    with pytest.raises(ValueError, match=r"m_b: fitted field strength 3.* outside the plausible 15\.\.80.*record again"):
        calibration.fit_magnetometer(small)
    assert calibration.fit_magnetometer(small, field_range=None).field_strength == pytest.approx(3.0, rel=0.02)
    good = 45.0 * dirs + 0.3 * rng.standard_normal((400, 3)) + [5.0, -8.0, 3.0]
    cal = calibration.fit_magnetometer(good)
    assert cal.norm_spread_after < cal.norm_spread_before and 40 < cal.field_strength < 50
    cap = dirs[:, 2] > 0.3
    disturbed = 45.0 * dirs[cap] + 6.0 * rng.standard_normal((int(cap.sum()), 3))
    with pytest.raises(ValueError, match=r"m_b: the fit leaves \|m\| no more constant .*each axis up and down"):
        calibration.fit_magnetometer(disturbed)
