"""Tests of navlib.sensors: error models, presets and the simulated sensors.

Statistical tolerances
----------------------
A sample standard deviation from n independent Gaussian samples has a
relative standard deviation of about 1/sqrt(2 n); the tests allow four of
those (``std_tol(n)``), so a correct implementation fails with probability
~1e-4 per check, and every test uses a fixed seed anyway.
"""

import csv

import numpy as np
import pytest
from numpy.testing import assert_allclose, assert_array_equal

from navlib import analysis, atmosphere, attitude, earth, sensors, units


def std_tol(n):
    """Four standard errors of a sample std relative to the true sigma (n samples)."""
    return 4.0 / np.sqrt(2.0 * n)


def corr_tol(rho, n):
    """Four standard errors of a sample correlation coefficient (n pairs)."""
    return 4.0 * (1.0 - rho * rho) / np.sqrt(n) + 1e-12


def rms(x, axis=None):
    """Root mean square about zero (the true mean is known to be zero)."""
    return np.sqrt(np.mean(np.square(x), axis=axis))


def random_quaternions(rng, shape):
    q = rng.standard_normal(tuple(shape) + (4,))
    return q / np.linalg.norm(q, axis=-1, keepdims=True)


# --------------------------------------------------------------------------
# Gauss-Markov sequences
# --------------------------------------------------------------------------


@pytest.mark.parametrize(
    "dt, n_samples, n_chunks, shape_chunk",
    [
        (1.0, 500, 1, (2000, 3)),  # 500 s = 10 T_c: far into the stationary regime
        (0.01, 20000, 4, (500, 1)),  # 200 s = 4 T_c at 100 Hz (chunked to limit memory)
    ],
)
def test_gauss_markov_std_independent_of_dt(dt, n_samples, n_chunks, shape_chunk):
    """Stationary sigma is the requested sigma at dt = 1 s and 0.01 s, at the
    first sample (stationary from the start) and after several T_c."""
    sigma, tc = 0.3, 50.0
    rng = np.random.default_rng(20240101)
    first, last = [], []
    for _ in range(n_chunks):
        y = sensors.gauss_markov((shape_chunk[0], n_samples, shape_chunk[1]), dt, sigma, tc, rng)
        assert y.shape == (shape_chunk[0], n_samples, shape_chunk[1])
        first.append(y[:, 0, :].ravel())
        last.append(y[:, -1, :].ravel())
    first, last = np.concatenate(first), np.concatenate(last)
    n = first.size  # independent sequences (each trial and column is its own sequence)
    assert n >= 2000
    # Std across sequences at a fixed time index; mean known to be 0.
    assert abs(rms(first) / sigma - 1) < std_tol(n)
    assert abs(rms(last) / sigma - 1) < std_tol(n)


@pytest.mark.parametrize("dt, lag", [(1.0, 1), (1.0, 10), (1.0, 50), (1.0, 100), (0.01, 100), (0.01, 2000)])
def test_gauss_markov_autocorrelation(dt, lag):
    """Lag-k correlation is exp(-k dt / T_c), measured across 6000 sequences
    between the first sample and sample k."""
    sigma, tc = 2.0, 50.0
    rng = np.random.default_rng(7 + lag)
    y = sensors.gauss_markov((2000, lag + 1, 3), dt, sigma, tc, rng)
    a, b = y[:, 0, :].ravel(), y[:, lag, :].ravel()
    rho_hat = np.sum(a * b) / np.sqrt(np.sum(a * a) * np.sum(b * b))
    rho = np.exp(-lag * dt / tc)
    # sd of a sample correlation ~ (1 - rho^2)/sqrt(n)
    assert abs(rho_hat - rho) < corr_tol(rho, a.size)


def test_gauss_markov_reproducible_and_bad_input():
    y1 = sensors.gauss_markov((10, 2), 0.1, 1.0, 5.0, np.random.default_rng(3))
    y2 = sensors.gauss_markov((10, 2), 0.1, 1.0, 5.0, np.random.default_rng(3))
    assert_array_equal(y1, y2)
    with pytest.raises(ValueError, match="^dt:"):
        sensors.gauss_markov((10, 2), -0.1, 1.0, 5.0, np.random.default_rng(3))
    with pytest.raises(ValueError, match="^correlation_time:"):
        sensors.gauss_markov((10, 2), 0.1, 1.0, 0.0, np.random.default_rng(3))
    with pytest.raises(ValueError, match="^shape:"):
        sensors.gauss_markov((10,), 0.1, 1.0, 5.0, np.random.default_rng(3))


# --------------------------------------------------------------------------
# simulate_imu
# --------------------------------------------------------------------------


def _ideal(rng, n, shape=()):
    """Smooth-ish ideal rates (rad/s) and specific forces (m/s^2)."""
    t = np.arange(n)[:, None]
    w = 0.3 * np.sin(0.01 * t + rng.uniform(0, 6, 3)) + np.zeros(shape + (n, 3))
    f = np.array([0.5, -0.2, 9.8]) + 2.0 * np.cos(0.02 * t + rng.uniform(0, 6, 3)) + np.zeros(shape + (n, 3))
    return w, f


@pytest.mark.parametrize("dt", [0.01, 0.2])
def test_imu_white_noise_std(dt):
    """Per-sample sigma of the white noise is noise_density / sqrt(dt)."""
    model = sensors.ImuModel(sensors.TriadErrors(noise_density=2e-3), sensors.TriadErrors(noise_density=5e-4))
    n = 20000
    w, f = _ideal(np.random.default_rng(1), n)
    out = sensors.simulate_imu(w, f, dt, model, np.random.default_rng(11))
    n_samples = n * 3
    assert abs(rms(out.w_ib_b - w) / (2e-3 / np.sqrt(dt)) - 1) < std_tol(n_samples)
    assert abs(rms(out.f_b - f) / (5e-4 / np.sqrt(dt)) - 1) < std_tol(n_samples)
    # No bias or matrix errors configured.
    assert_array_equal(out.gyro_bias, 0.0)
    assert_array_equal(out.gyro_matrix, np.broadcast_to(np.eye(3), (3, 3)))


def test_imu_turn_on_bias():
    """Turn-on bias: constant within a run, sigma `bias` across 2000 trials x 3 axes."""
    b_g, b_a = units.deg_per_h(15.0), units.mg(2.0)
    model = sensors.ImuModel(sensors.TriadErrors(bias=float(b_g)), sensors.TriadErrors(bias=float(b_a)))
    n_trials, n = 2000, 20
    z = np.zeros((n, 3))
    out = sensors.simulate_imu(z, z, 0.01, model, np.random.default_rng(5), n_trials=n_trials)
    assert out.w_ib_b.shape == (n_trials, n, 3)
    for y, bias, sigma in ((out.w_ib_b, out.gyro_bias, b_g), (out.f_b, out.accel_bias, b_a)):
        assert_array_equal(y, bias)  # zero input, no noise: output is the bias
        assert_array_equal(y, np.broadcast_to(y[:, :1, :], y.shape))  # constant within each run
        assert abs(rms(y[:, 0, :]) / sigma - 1) < std_tol(n_trials * 3)


def test_imu_scale_misalignment_and_measurement_equation():
    """Matrix errors have the configured sigmas and the output is exactly M x + bias."""
    sf, mis = 0.01, units.deg(0.5)
    gyro = sensors.TriadErrors(
        bias=1e-3, bias_instability=1e-4, correlation_time=10.0, rate_random_walk=1e-5, scale_factor=sf, misalignment=float(mis)
    )
    accel = sensors.TriadErrors(
        bias=0.02, bias_instability=1e-3, correlation_time=20.0, scale_factor=2 * sf, misalignment=float(2 * mis)
    )
    model = sensors.ImuModel(gyro, accel)
    n_trials, n = 2000, 30
    w, f = _ideal(np.random.default_rng(2), n)
    out = sensors.simulate_imu(w, f, 0.05, model, np.random.default_rng(6), n_trials=n_trials)
    off = ~np.eye(3, dtype=bool)
    for M, s, m in ((out.gyro_matrix, sf, mis), (out.accel_matrix, 2 * sf, 2 * mis)):
        assert M.shape == (n_trials, 3, 3)
        diag = np.diagonal(M, axis1=-2, axis2=-1) - 1.0
        assert abs(rms(diag) / s - 1) < std_tol(diag.size)  # 6000 samples
        assert abs(rms(M[:, off]) / m - 1) < std_tol(M[:, off].size)  # 12000 samples
    # Reconstruct the measurement from the error realisation (noise_density = 0).
    assert_allclose(out.w_ib_b, np.einsum("tij,nj->tni", out.gyro_matrix, w) + out.gyro_bias, rtol=0, atol=1e-15)
    assert_allclose(out.f_b, np.einsum("tij,nj->tni", out.accel_matrix, f) + out.accel_bias, rtol=0, atol=1e-13)
    # The bias varies in time (Gauss-Markov + random walk) but not across the matrix.
    assert np.all(np.std(out.gyro_bias, axis=1) > 0)


def test_error_pass_rounds_as_einsum():
    """The one-pass error kernel gives the bits of the array expressions it replaced (einsum + bias + noise)."""
    rng = np.random.default_rng(11)
    for T, N in ((1, 5000), (7, 300)):
        M = np.eye(3) + 1e-3 * rng.standard_normal((T, 3, 3))
        x = np.broadcast_to(rng.standard_normal((N, 3)), (T, N, 3)).copy()
        x[:, ::5] = 0.0
        x[:, ::7, 1] = -0.0
        bias, white = 1e-3 * rng.standard_normal((T, N, 3)), rng.standard_normal((T, N, 3))
        for scale in (0.0, 0.3):
            ref = np.einsum("...ij,...nj->...ni", M, x) + bias
            ref += scale * white
            y = white.copy()
            assert sensors._apply_errors(M, x, bias, scale, np.inf, y) == 0
            assert_array_equal(y.view(np.int64), ref.view(np.int64))  # signed zeros included


def test_imu_saturation():
    """Outputs are clipped at +-full_scale and the clipped samples are counted."""
    fs_g, fs_a = 1.0, 20.0
    model = sensors.ImuModel(sensors.TriadErrors(full_scale=fs_g), sensors.TriadErrors(full_scale=fs_a))
    t = np.linspace(0, 10, 1001)
    w = np.stack([1.5 * np.sin(t), 0.5 * np.cos(t), np.full_like(t, -1.2)], -1)
    f = np.stack([np.zeros_like(t), 25 * np.sin(2 * t), np.full_like(t, 9.8)], -1)
    out = sensors.simulate_imu(w, f, 0.01, model, np.random.default_rng(0))
    assert out.gyro_saturated == np.count_nonzero(np.abs(w) > fs_g)
    assert out.accel_saturated == np.count_nonzero(np.abs(f) > fs_a)
    assert out.gyro_saturated > 1000 and out.accel_saturated > 100
    assert_array_equal(out.w_ib_b, np.clip(w, -fs_g, fs_g))
    assert_array_equal(out.f_b, np.clip(f, -fs_a, fs_a))
    # Counting covers trials too.
    out3 = sensors.simulate_imu(w, f, 0.01, model, np.random.default_rng(0), n_trials=3)
    assert out3.gyro_saturated == 3 * out.gyro_saturated


def test_imu_reproducible():
    model = sensors.imu_model("MPU-6050")
    w, f = _ideal(np.random.default_rng(3), 200)
    a = sensors.simulate_imu(w, f, 0.01, model, np.random.default_rng(42))
    b = sensors.simulate_imu(w, f, 0.01, model, np.random.default_rng(42))
    c = sensors.simulate_imu(w, f, 0.01, model, np.random.default_rng(43))
    for name in ("w_ib_b", "f_b", "gyro_bias", "accel_bias", "gyro_matrix", "accel_matrix"):
        assert_array_equal(getattr(a, name), getattr(b, name))
        assert not np.array_equal(getattr(a, name), getattr(c, name)), name


def test_imu_streams_independent():
    """Switching one error component leaves the others' realisation unchanged."""
    base = sensors.imu_model("MPU-6050")
    w, f = _ideal(np.random.default_rng(4), 500)
    sim = lambda m: sensors.simulate_imu(w, f, 0.01, m, np.random.default_rng(99))  # noqa: E731
    ref = sim(base)
    # Accelerometer noise off: the gyro output is bit-identical.
    no_acc_noise = sim(base.replace(accel={"noise_density": 0.0}))
    assert_array_equal(no_acc_noise.w_ib_b, ref.w_ib_b)
    assert_array_equal(no_acc_noise.gyro_bias, ref.gyro_bias)
    assert not np.array_equal(no_acc_noise.f_b, ref.f_b)
    # Gyro bias instability off: same white noise, turn-on bias and matrix.
    no_gm = sim(base.replace(gyro={"bias_instability": 0.0}))
    assert not np.array_equal(no_gm.gyro_bias, ref.gyro_bias)
    assert_array_equal(no_gm.gyro_matrix, ref.gyro_matrix)
    scale = np.max(np.abs(ref.w_ib_b))
    assert_allclose(no_gm.w_ib_b - no_gm.gyro_bias, ref.w_ib_b - ref.gyro_bias, rtol=0, atol=1e-14 * scale)
    # Without the Gauss-Markov part only the turn-on bias is left: constant in time.
    assert_array_equal(no_gm.gyro_bias, np.broadcast_to(no_gm.gyro_bias[:1], no_gm.gyro_bias.shape))
    assert_array_equal(no_gm.f_b, ref.f_b)


def test_imu_n_trials_axis():
    model = sensors.imu_model("MPU-6050")
    w, f = _ideal(np.random.default_rng(5), 50)
    out = sensors.simulate_imu(w, f, 0.01, model, np.random.default_rng(1), n_trials=4)
    assert out.w_ib_b.shape == out.f_b.shape == out.gyro_bias.shape == (4, 50, 3)
    assert out.gyro_matrix.shape == out.accel_matrix.shape == (4, 3, 3)
    assert not np.array_equal(out.w_ib_b[0], out.w_ib_b[1])  # independent trials
    # Batched input (2, N, 3) gets the trial axis in front.
    wb, fb = np.stack([w, -w]), np.stack([f, f])
    outb = sensors.simulate_imu(wb, fb, 0.01, model, np.random.default_rng(1), n_trials=4)
    assert outb.w_ib_b.shape == (4, 2, 50, 3)
    assert outb.gyro_matrix.shape == (4, 2, 3, 3)
    # Without n_trials the shape is the input shape.
    assert sensors.simulate_imu(w, f, 0.01, model, np.random.default_rng(1)).w_ib_b.shape == (50, 3)


def _bad_imu_cases():
    w = np.zeros((10, 3))
    w_nan = w.copy()
    w_nan[3, 1] = np.nan
    m = sensors.ImuModel()
    g = np.random.default_rng(0)
    return [
        ("w_ib_b", dict(w_ib_b=np.zeros((10, 2)), f_b=np.zeros((10, 2)), dt=0.01, model=m, rng=g)),
        ("f_b", dict(w_ib_b=w, f_b=np.zeros((9, 3)), dt=0.01, model=m, rng=g)),
        ("w_ib_b", dict(w_ib_b=w_nan, f_b=w, dt=0.01, model=m, rng=g)),
        ("dt", dict(w_ib_b=w, f_b=w, dt=-0.01, model=m, rng=g)),
        ("dt", dict(w_ib_b=w, f_b=w, dt=0.0, model=m, rng=g)),
        ("rng", dict(w_ib_b=w, f_b=w, dt=0.01, model=m, rng=np.random.RandomState(0))),
        ("rng", dict(w_ib_b=w, f_b=w, dt=0.01, model=m, rng=42)),
        ("model", dict(w_ib_b=w, f_b=w, dt=0.01, model=sensors.TriadErrors(), rng=g)),
        ("n_trials", dict(w_ib_b=w, f_b=w, dt=0.01, model=m, rng=g, n_trials=0)),
    ]


@pytest.mark.parametrize(
    "arg, kwargs",
    _bad_imu_cases(),
    ids=["w-shape", "f-shape", "w-nan", "dt-neg", "dt-zero", "rng-RandomState", "rng-int", "model", "n_trials"],
)
def test_imu_bad_input(arg, kwargs):
    with pytest.raises(ValueError, match=f"^{arg}:"):
        sensors.simulate_imu(**kwargs)


def test_triad_errors_reject_negative():
    with pytest.raises(ValueError, match="noise_density"):
        sensors.TriadErrors(noise_density=-1.0)
    with pytest.raises(ValueError, match="bias"):
        sensors.TriadErrors(bias=float("nan"))


# --------------------------------------------------------------------------
# Allan deviation of simulated gyros
# --------------------------------------------------------------------------


def test_allan_of_white_gyro_noise():
    """White noise only: adev(tau) = N / sqrt(tau).

    Tolerance: with M = n/m non-overlapping clusters the relative sd of the
    Allan deviation of white noise is about 0.87/sqrt(M) for the
    non-overlapping estimator (the overlapping one is better); allow 4/sqrt(M).
    """
    N = float(units.deg_per_s_sqrt_hz(0.01))
    model = sensors.ImuModel(sensors.TriadErrors(noise_density=N))
    dt, n = 0.01, 100_000
    z = np.zeros((n, 3))
    out = sensors.simulate_imu(z, z, dt, model, np.random.default_rng(2024))
    taus, adev = analysis.allan_deviation(out.w_ib_b, dt, taus=[0.01, 0.1, 1.0])
    m = np.round(taus / dt)
    tol = 4.0 / np.sqrt(n / m)
    ratio = adev / (N / np.sqrt(taus))[:, None]
    assert np.all(np.abs(ratio - 1) < tol[:, None]), (ratio, tol)


def test_allan_fit_recovers_mti100_gyro():
    """2-h, 100 Hz record of the MTi-100 gyro (turn-on bias, scale and misalignment
    zeroed): the Allan fit recovers the ARW within 5 % and the bias instability
    within 15 % (mean of the three axes). Checked on seeds 0-7 while writing this
    test: ARW errors < 0.1 %, bias-instability errors -0.8 % to -7.7 %."""
    model = sensors.imu_model("MTi-100").replace(gyro={"bias": 0.0, "scale_factor": 0.0, "misalignment": 0.0})
    dt = 0.01
    n = int(round(2 * 3600 / dt))
    z = np.zeros((n, 3))
    out = sensors.simulate_imu(z, z, dt, model, np.random.default_rng(7))
    taus, adev = analysis.allan_deviation(out.w_ib_b, dt)
    fits = [analysis.fit_allan(taus, adev[:, k], n, dt) for k in range(3)]
    white = np.mean([p["white"] for p in fits])
    b = np.mean([p["bias_instability"] for p in fits])
    assert abs(white / model.gyro.noise_density - 1) < 0.05
    assert abs(b / model.gyro.bias_instability - 1) < 0.15


# --------------------------------------------------------------------------
# Presets
# --------------------------------------------------------------------------


def test_devices_listed():
    names = set(sensors.devices())
    assert {"NAV-FOG", "MTi-100", "ADIS16475-1", "MPU-6050", "HMC5983", "BMP180", "UB482"} <= names


def test_preset_values():
    mti = sensors.imu_model("MTi-100")
    assert mti.name == "MTi-100"
    assert mti.gyro.noise_density == pytest.approx(float(units.deg_per_s_sqrt_hz(0.01)), rel=1e-14)
    assert mti.gyro.bias_instability == pytest.approx(float(units.deg_per_h(10)), rel=1e-14)
    assert mti.gyro.correlation_time == 100.0
    mpu = sensors.imu_model("MPU-6050")
    assert mpu.accel.noise_density == pytest.approx(float(units.ug_per_sqrt_hz(400)), rel=1e-14)
    assert mpu.accel.full_scale == pytest.approx(4 * 9.80665, rel=1e-14)
    assert sensors.preset("BMP180")[("baro", "noise")] == pytest.approx(2.0, rel=1e-14)
    # GM sigma is chosen so that the Allan peak equals the bias instability.
    assert mti.gyro.gauss_markov_sigma * analysis.GM_ALLAN_PEAK == pytest.approx(mti.gyro.bias_instability)


def test_preset_csv_every_row_has_source():
    with sensors.PRESETS_CSV.open(encoding="utf-8") as fh:
        rows = list(csv.DictReader(line for line in fh if not line.startswith("#")))
    assert len(rows) > 30
    for r in rows:
        assert r["source"] and r["source"].strip(), r
        assert np.isfinite(float(units.to_si(float(r["value"]), r["unit"]))), r


def test_preset_unknown_device():
    with pytest.raises(ValueError, match="device"):
        sensors.preset("NO-SUCH-IMU")
    with pytest.raises(ValueError, match="device"):
        sensors.imu_model("NO-SUCH-IMU")
    with pytest.raises(ValueError, match="device"):
        sensors.imu_model("UB482")  # not an IMU
    with pytest.raises(ValueError, match="device"):
        sensors.MagnetometerModel.from_preset("BMP180")


# --------------------------------------------------------------------------
# Magnetometer
# --------------------------------------------------------------------------

B_N = np.array([-3.2, 38.5, -34.0])  # uT, ENU, a mid-latitude northern-hemisphere field


def test_magnetometer_ideal_is_rotated_field():
    rng = np.random.default_rng(10)
    q = random_quaternions(rng, (300,))
    out = sensors.simulate_magnetometer(q, B_N, sensors.MagnetometerModel(), np.random.default_rng(1))
    C_nb = np.swapaxes(attitude.quat_to_dcm(q), -1, -2)
    assert_allclose(out.m_b, C_nb @ B_N, rtol=0, atol=1e-12)
    assert_allclose(np.linalg.norm(out.m_b, axis=-1), np.linalg.norm(B_N), rtol=1e-13)
    # Identity attitude: body = ENU.
    out0 = sensors.simulate_magnetometer(
        np.tile([1.0, 0, 0, 0], (5, 1)), B_N, sensors.MagnetometerModel(), np.random.default_rng(1)
    )
    assert_allclose(out0.m_b, np.tile(B_N, (5, 1)), atol=1e-12)


def test_magnetometer_hard_iron_and_noise():
    rng = np.random.default_rng(11)
    q = random_quaternions(rng, (1000, 5))
    ideal = np.einsum("tnji,j->tni", attitude.quat_to_dcm(q), B_N)  # C_nb B_n
    hard = sensors.simulate_magnetometer(q, B_N, sensors.MagnetometerModel(hard_iron=5.0), np.random.default_rng(2))
    offset = hard.m_b - ideal
    assert hard.hard_iron.shape == (1000, 3)
    assert_allclose(offset, np.broadcast_to(hard.hard_iron[:, None, :], offset.shape), atol=1e-12)
    assert abs(rms(hard.hard_iron) / 5.0 - 1) < std_tol(3000)
    noisy = sensors.simulate_magnetometer(q, B_N, sensors.MagnetometerModel(noise=0.3), np.random.default_rng(3))
    e = noisy.m_b - ideal
    assert abs(rms(e) / 0.3 - 1) < std_tol(e.size)  # 15000 samples
    assert_array_equal(noisy.hard_iron, 0.0)


def test_magnetometer_soft_iron_symmetric():
    q = random_quaternions(np.random.default_rng(12), (200,))
    out = sensors.simulate_magnetometer(q, B_N, sensors.MagnetometerModel(soft_iron=0.05), np.random.default_rng(4))
    S = out.soft_iron
    assert_allclose(S, S.T)
    assert not np.allclose(S, np.eye(3))
    C_nb = np.swapaxes(attitude.quat_to_dcm(q), -1, -2)
    assert_allclose(out.m_b, (C_nb @ B_N) @ S.T, atol=1e-12)


def test_hmc5983_preset():
    m = sensors.MagnetometerModel.from_preset("HMC5983")
    assert m.noise == pytest.approx(0.2, rel=1e-12)  # 2 mG = 0.2 uT
    assert m.full_scale == pytest.approx(800.0, rel=1e-12)  # 8 G


def test_magnetic_disturbances():
    dt = 0.1
    t = np.arange(0.0, 4000.0, dt)
    amp, dur = (5.0, 10.0), (2.0, 5.0)
    d = sensors.magnetic_disturbances(t, np.random.default_rng(21), rate=0.005, amplitude=amp, duration=dur)
    assert d.shape == (t.size, 3)
    on = np.any(d != 0, axis=1)
    # Split the 'on' samples into contiguous segments (events).
    edges = np.flatnonzero(np.diff(np.concatenate([[0], on.astype(int), [0]])))
    segments = list(zip(edges[::2], edges[1::2], strict=True))
    assert 5 <= len(segments) <= 40  # Poisson mean 20 events
    assert on.mean() < 0.1  # exactly zero outside the events
    # Single events (no overlap), not cut off by the end of the record.
    single = [(a, b) for a, b in segments if (b - a) * dt <= dur[1] and b < t.size]
    assert len(single) >= 0.8 * len(segments)  # overlaps are rare at this rate
    for a, b in single:
        assert dur[0] - 2 * dt <= (b - a) * dt <= dur[1]  # nonzero only inside the event window
        seg = d[a:b]
        norm = np.linalg.norm(seg, axis=1)
        assert norm.max() <= amp[1] * (1 + 1e-12)
        assert norm.max() >= amp[0] * np.sin(np.pi / 2 - np.pi * dt / dur[0]) ** 2 - 1e-9
        u = seg / norm[:, None]
        assert_allclose(u, np.broadcast_to(u[np.argmax(norm)], u.shape), atol=1e-9)  # one direction per event
    assert np.all(np.linalg.norm(d, axis=1) <= 2 * amp[1])
    zero = sensors.magnetic_disturbances(t, np.random.default_rng(21), rate=0.0)
    assert_array_equal(zero, 0.0)
    with pytest.raises(ValueError, match="^rate:"):
        sensors.magnetic_disturbances(t, np.random.default_rng(21), rate=-1.0)


# --------------------------------------------------------------------------
# Barometer
# --------------------------------------------------------------------------


def test_barometer_ideal_and_drift():
    t = np.arange(100.0, 700.0, 0.5)
    h = 50.0 + 30.0 * np.sin(t / 60.0)
    ideal = sensors.simulate_barometer(h, t, sensors.BarometerModel(), np.random.default_rng(0))
    assert_allclose(ideal, atmosphere.isa_pressure(h), rtol=1e-15)
    p0 = 100500.0
    assert_allclose(
        sensors.simulate_barometer(h, t, sensors.BarometerModel(), np.random.default_rng(0), p0=p0),
        atmosphere.isa_pressure(h, p0),
        rtol=1e-15,
    )
    rate = 0.5 * 100 / 3600  # 0.5 hPa/h
    drift = sensors.simulate_barometer(h, t, sensors.BarometerModel(drift_rate=rate), np.random.default_rng(0))
    assert_allclose(drift - ideal, rate * (t - t[0]), rtol=0, atol=1e-9)


def test_barometer_noise_and_bias():
    t = np.arange(0.0, 500.0, 0.01)
    h = np.zeros((2, t.size))
    noisy = sensors.simulate_barometer(h, t, sensors.BarometerModel(noise=2.0), np.random.default_rng(1))
    e = noisy - atmosphere.P0
    assert abs(rms(e) / 2.0 - 1) < std_tol(e.size)  # 100000 samples
    hb = np.zeros((3000, 4))
    biased = sensors.simulate_barometer(hb, t[:4], sensors.BarometerModel(bias=10.0), np.random.default_rng(2))
    b = biased - atmosphere.P0
    assert_allclose(b, np.broadcast_to(b[:, :1], b.shape), atol=1e-9)  # constant per run
    assert abs(rms(b[:, 0]) / 10.0 - 1) < std_tol(3000)


def test_bmp180_preset():
    m = sensors.BarometerModel.from_preset("BMP180")
    assert m.noise == pytest.approx(2.0, rel=1e-12)  # 0.02 hPa
    assert m.drift_rate == pytest.approx(50.0 / 3600.0, rel=1e-12)  # 0.5 hPa/h
    with pytest.raises(ValueError, match="^h:"):
        sensors.simulate_barometer(np.zeros(5), np.arange(4.0), m, np.random.default_rng(0))


# --------------------------------------------------------------------------
# GNSS position and dual-antenna heading
# --------------------------------------------------------------------------


def test_outage_mask():
    t = np.arange(0.0, 10.0, 0.5)
    v = sensors.outage_mask(t, [(2.0, 4.0), (7.0, 7.5)])
    expected = ~(((t >= 2) & (t < 4)) | ((t >= 7) & (t < 7.5)))
    assert_array_equal(v, expected)
    assert v[t == 4.0][0] and not v[t == 2.0][0]  # [start, end)
    assert_array_equal(sensors.outage_mask(t, []), True)
    with pytest.raises(ValueError, match="^outages:"):
        sensors.outage_mask(t, [(5.0, 5.0)])
    with pytest.raises(ValueError, match="^outages:"):
        sensors.outage_mask(t, [(5.0,)])


def test_gnss_position_noise_and_outages():
    n = 20000
    t = np.arange(n) * 1.0
    lat = np.deg2rad(np.linspace(0.0, 70.0, n))
    lla = np.stack([lat, np.full(n, np.deg2rad(114.3)), np.full(n, 120.0)], -1)
    sigma = 1.5
    meas = sensors.simulate_gnss_position(lla, np.random.default_rng(8), sigma)
    R_M, R_N = earth.radii(lat)
    dn = (meas[:, 0] - lla[:, 0]) * (R_M + lla[:, 2])
    de = (meas[:, 1] - lla[:, 1]) * (R_N + lla[:, 2]) * np.cos(lat)
    du = meas[:, 2] - lla[:, 2]
    assert abs(rms(dn) / sigma - 1) < std_tol(n)
    assert abs(rms(de) / sigma - 1) < std_tol(n)
    # The east noise must not depend on latitude (the cos(lat) is right): split the record.
    assert abs(rms(de[n // 2 :]) / sigma - 1) < std_tol(n // 2)
    assert abs(rms(du) / (1.5 * sigma) - 1) < std_tol(n)  # default vertical sigma
    assert abs(np.mean(dn * de)) / sigma**2 < 4 / np.sqrt(n)  # independent axes
    # Explicit vertical sigma and outages.
    valid = sensors.outage_mask(t, [(100.0, 200.0)])
    m2 = sensors.simulate_gnss_position(lla, np.random.default_rng(9), sigma, sigma_vertical=0.5, valid=valid)
    assert np.all(np.isnan(m2[~valid]))
    assert np.all(np.isfinite(m2[valid]))
    assert (~valid).sum() == 100
    assert abs(rms(m2[valid, 2] - lla[valid, 2]) / 0.5 - 1) < std_tol(valid.sum())
    # Batches: (trials, N, 3) with a shared validity mask.
    mb = sensors.simulate_gnss_position(np.stack([lla, lla]), np.random.default_rng(9), sigma, valid=valid)
    assert mb.shape == (2, n, 3) and np.all(np.isnan(mb[:, ~valid]))
    with pytest.raises(ValueError, match="^sigma_horizontal:"):
        sensors.simulate_gnss_position(lla, np.random.default_rng(9), -1.0)


def test_heading_wrap_noise_and_validity():
    n = 20000
    rng = np.random.default_rng(12)
    truth = np.concatenate([rng.uniform(0, 2 * np.pi, n - 200), np.full(100, 2 * np.pi - 1e-3), np.full(100, 1e-3)])
    sigma = float(units.deg(0.2))
    meas, valid = sensors.simulate_heading(truth, np.random.default_rng(13), sigma)
    assert valid.dtype == bool and valid.all()
    assert np.all((meas >= 0) & (meas < 2 * np.pi))
    e = attitude.wrap_pi(meas - truth)
    assert abs(rms(e) / sigma - 1) < std_tol(n)
    assert np.abs(e).max() < 6 * sigma  # wrap differences are small, never ~2 pi
    # Near north both sides of the wrap occur.
    assert np.any(meas[n - 200 : n - 100] < 1) and np.any(meas[n - 200 : n - 100] > 6)
    # Invalid epochs are NaN (not a fused zero) and the flags are returned.
    mask = np.ones(n, dtype=bool)
    mask[500:800] = False
    meas2, valid2 = sensors.simulate_heading(truth, np.random.default_rng(13), sigma, valid=mask)
    assert_array_equal(valid2, mask)
    assert np.all(np.isnan(meas2[~mask]))
    assert_array_equal(meas2[mask], meas[mask])
    with pytest.raises(ValueError, match="^valid:"):
        sensors.simulate_heading(truth, np.random.default_rng(13), sigma, valid=mask[:-1])
    with pytest.raises(ValueError, match="^sigma:"):
        sensors.simulate_heading(truth, np.random.default_rng(13), -sigma)


# --------------------------------------------------------------------------
# Known navlib convention violations (bad input must raise ValueError naming
# the argument). strict=True: these start failing once navlib is fixed, as a
# reminder to drop the marker.
# --------------------------------------------------------------------------


def test_gnss_position_bad_valid_shape():
    lla = np.zeros((10, 3))
    with pytest.raises(ValueError, match="^valid:"):
        sensors.simulate_gnss_position(lla, np.random.default_rng(0), 1.0, valid=np.ones(9, dtype=bool))


@pytest.mark.parametrize("which", ["magnetometer", "barometer"])
def test_mag_baro_reject_non_generator_rng(which):
    with pytest.raises(ValueError, match="^rng:"):
        if which == "magnetometer":
            sensors.simulate_magnetometer(np.array([[1.0, 0, 0, 0]]), B_N, sensors.MagnetometerModel(), np.random.RandomState(0))
        else:
            sensors.simulate_barometer(np.zeros(3), [0.0, 1.0, 2.0], sensors.BarometerModel(), np.random.RandomState(0))


# ---------------------------------------------------------------- presets are read strictly

_HEADER = "# comment\ndevice,sensor,parameter,value,unit,source\n"


@pytest.mark.parametrize(
    "row, message",
    [
        ("X,gyro,noise_densty,0.01,deg/s/sqrt(Hz),typo", "line 3: unknown gyro parameter 'noise_densty'"),
        ("X,gyroscope,noise_density,0.01,deg/s/sqrt(Hz),typo", "line 3: unknown sensor 'gyroscope'"),
        ("X,gyro,noise_density,0.01,furlong,bad unit", "line 3: bad value or unit"),
        ("X,gyro,noise_density,abc,deg/s/sqrt(Hz),bad value", "line 3: bad value or unit"),
    ],
)
def test_presets_reject_unknown_names_and_bad_values(tmp_path, row, message):
    path = tmp_path / "presets.csv"
    path.write_text(_HEADER + row + "\n", encoding="utf-8")
    with pytest.raises(ValueError, match=message):
        sensors._read_presets(path)


def test_presets_reject_a_repeated_row(tmp_path):
    path = tmp_path / "presets.csv"
    row = "X,gyro,bias,1,deg/h,src\n"
    path.write_text(_HEADER + row + "\n" + row, encoding="utf-8")
    with pytest.raises(ValueError, match="line 5: X gyro bias given twice"):
        sensors._read_presets(path)


def test_shipped_presets_parse_strictly():
    table = sensors._read_presets(sensors.PRESETS_CSV)
    assert set(table) == set(sensors.devices()) and len(table) == 8


@pytest.mark.parametrize(
    "changes",
    [{}, {"gyro": {"rate_random_walk": 1e-4}}, {"gyro": {"bias_instability": 0.0}, "accel": {"noise_density": 0.0}}],
    ids=["preset", "random-walk", "no-gauss-markov"],
)
@pytest.mark.parametrize("n_trials, batch", [(7, 3), (4, 4), (1, 5)])
def test_batches_are_the_bits_of_one_simulation(changes, n_trials, batch):
    rng = np.random.default_rng(5)
    w_ib_b, f_b = rng.normal(0, 0.5, (500, 3)), rng.normal(0, 3, (500, 3)) + [0, 0, 9.8]
    model = sensors.imu_model("MTi-100").replace(**changes)
    whole = sensors.simulate_imu(w_ib_b, f_b, 0.01, model, np.random.default_rng(11), n_trials=n_trials)
    batches = list(sensors.simulate_imu_batches(w_ib_b, f_b, 0.01, model, np.random.default_rng(11), n_trials, batch))
    assert [len(b.w_ib_b) for b in batches] == [min(batch, n_trials - i) for i in range(0, n_trials, batch)]
    for name in ("w_ib_b", "f_b", "gyro_bias", "accel_bias", "gyro_matrix", "accel_matrix"):
        assert_array_equal(np.concatenate([getattr(b, name) for b in batches]), getattr(whole, name), err_msg=name)
    assert sum(b.gyro_saturated for b in batches) == whole.gyro_saturated


def test_batches_need_one_ideal_record():
    with pytest.raises(ValueError, match="w_ib_b"):
        sensors.simulate_imu_batches(
            np.zeros((2, 10, 3)), np.zeros((2, 10, 3)), 0.01, sensors.imu_model("MTi-100"), np.random.default_rng(0), 3, 2
        )
