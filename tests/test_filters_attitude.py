"""The attitude filters (navlib.filters: mahony, quaternion_kf, heading_fusion) and navlib.papers.mimu_mag_rtk
(paper 003): equations, filters, bad input, and the cross-check against ahrs (AHRS 0.4.0)."""

import os
import subprocess
import sys

import numpy as np
import pytest
from helpers import run_json_script
from hypothesis import given, settings
from hypothesis import strategies as st
from numba import njit

from navlib import _kernels, alignment, analysis, attitude, earth, kalman, robust, units
from navlib.filters import heading_fusion as hf
from navlib.filters import mahony as mh
from navlib.filters import observations as obs
from navlib.filters import quaternion_kf as qkf
from navlib.filters.observations import AttitudeGates, MagGate, RtkHeading
from navlib.filters.quaternion_kf import KfNoise
from navlib.imu import ImuSamples, SensorLimits
from navlib.papers import mimu_mag_rtk

B_N = earth.magnetic_field(32.03, 118.85, 20.0, 2022.5)  # Nanjing, the paper's site
B_REF, DECL, INCL, INTENSITY = obs.magnetic_reference(B_N)
G = 9.8
DT = 0.01


def random_quats(n, seed=0):
    rng = np.random.default_rng(seed)
    hpr = np.stack([rng.uniform(0, 2 * np.pi, n), rng.uniform(-1.4, 1.4, n), rng.uniform(-np.pi, np.pi, n)], -1)
    return hpr, attitude.euler_to_quat(hpr)


def static_marg(hpr_mag, n, rng, gyro=(0.0, 0.0, 0.0), noise=(1e-3, 0.02, 0.3)):
    """Static gyro/accel/mag samples at a magnetic-north attitude (field in the magnetic frame)."""
    C_nb = attitude.euler_to_dcm(hpr_mag).T
    B_mag = INTENSITY * B_REF
    w = np.asarray(gyro) + noise[0] * rng.standard_normal((n, 3))
    f = C_nb @ [0.0, 0.0, G] + noise[1] * rng.standard_normal((n, 3))
    m = C_nb @ B_mag + noise[2] * rng.standard_normal((n, 3))
    return w, f, m


# --------------------------------------------------------------------------- equations


def test_measurement_model_and_jacobian_match_rotation_and_finite_differences():
    _, q = random_quats(500)
    C_nb = np.swapaxes(attitude.quat_to_dcm(q), -1, -2)
    h = qkf.measurement_model(q, B_REF)
    np.testing.assert_allclose(h[:, :3], C_nb @ [0, 0, 1], atol=1e-15)  # Eq. (4) corrected
    np.testing.assert_allclose(h[:, 3:], C_nb @ B_REF, atol=1e-15)  # Eq. (6) corrected
    eps = 1e-6
    num = np.stack(
        [(qkf.measurement_model(q + eps * e, B_REF) - qkf.measurement_model(q - eps * e, B_REF)) / (2 * eps) for e in np.eye(4)],
        -1,
    )
    np.testing.assert_allclose(qkf.measurement_jacobian(q, B_REF), num, atol=1e-8)  # Eq. (20), H44 corrected
    Hq = np.einsum("nij,nj->ni", qkf.measurement_jacobian(q, B_REF), q)
    np.testing.assert_allclose(Hq, 2 * h, atol=1e-14)  # why z - Hq is wrong (E003-12)


def test_printed_jacobian_differs_only_at_h44():
    _, q = random_quats(200, seed=1)
    d = mimu_mag_rtk.printed_eq20_jacobian(q, B_REF) - qkf.measurement_jacobian(q, B_REF)
    np.testing.assert_allclose(d[:, 3, 3], -4 * q[:, 1] * B_REF[2], atol=1e-15)
    d[:, 3, 3] = 0
    assert np.abs(d).max() == 0


def test_transition_and_noise_input_are_the_quaternion_kinematics():
    _, q = random_quats(300, seed=2)
    w = np.random.default_rng(3).normal(0, 1, (300, 3))
    inc = 0.5 * DT * attitude.quat_mult(q, np.concatenate([np.zeros((300, 1)), w], -1))
    np.testing.assert_allclose(np.einsum("nij,nj->ni", qkf.transition(w, DT), q), q + inc, atol=1e-15)
    np.testing.assert_allclose(np.einsum("nij,nj->ni", qkf.noise_input(q, DT), w), inc, atol=1e-15)
    np.testing.assert_allclose(mimu_mag_rtk.printed_eq18_gamma(q, DT), -2 * qkf.noise_input(q, DT), atol=0)


@settings(max_examples=200, deadline=None)
@given(st.floats(0, 2 * np.pi, exclude_max=True), st.floats(-1.3, 1.3), st.floats(-3.0, 3.0))
def test_tilt_heading_inverts_the_measurement_model(heading, pitch, roll):
    hpr = np.array([heading, pitch, roll])
    q = attitude.euler_to_quat(hpr)
    h = qkf.measurement_model(q, B_REF)
    back = alignment.tilt_heading(3.7 * h[:3], 42.0 * h[3:])  # any scale: Eqs. (5), (7) normalise
    np.testing.assert_allclose(attitude.wrap_pi(back - hpr), 0, atol=1e-9)
    np.testing.assert_allclose(np.abs(alignment.initial_attitude(h[:3], h[3:]) @ q), 1, atol=1e-12)


def test_printed_eq8_is_a_different_rotation():
    q8 = mimu_mag_rtk.printed_eq8_quat(units.deg([30.0, 10.0, 20.0]))
    np.testing.assert_allclose(units.to_deg(attitude.quat_to_euler(q8)), [33.45, 9.39, 20.28], atol=0.01)


# --------------------------------------------------------------------------- bad input
# Bad input to every public callable: its row in tools/fuzz_calls.py, run by tests/test_bad_input.py. Here: what is
# not bad input.


def test_a_nan_rtk_heading_in_a_valid_epoch_is_a_dropout():
    valid = np.ones(100, dtype=bool)
    res = hf.fuse_rtk_heading(np.zeros(100), RtkHeading(np.full(100, np.nan), valid), DT)
    assert int(res.faults["heading", "nan"]) == 100
    assert np.isnan(res.delta).all() and np.array_equal(res.heading, np.zeros(100))  # uncalibrated throughout


@pytest.mark.parametrize("filt", [mh.mahony, qkf.quaternion_kf])
def test_dropouts_are_skipped_and_counted_never_poisoning_the_state(filt):
    rng = np.random.default_rng(1)
    hpr = np.array([1.0, 0.1, -0.2])
    w, f, m = static_marg(hpr, 3000, rng)
    w[100:110] = np.nan  # gyro dropout: last valid sample held
    f[200:205] = np.nan  # accelerometer dropout
    f[300] = 0.0  # zero vector
    m[400:420] = np.nan  # magnetometer dropout
    m[500] = np.inf
    m[600] = 0.0
    m[700] = f[700]  # magnetometer parallel to gravity
    out = filt(ImuSamples(w, f, DT), attitude.euler_to_quat(hpr), m_b=m, B_n=B_N)
    assert np.isfinite(out.q_bn).all()
    assert {k: int(v) for k, v in out.faults.counts.items() if v} == {  # every other count 0
        ("gyro", "nan"): 10,
        ("accel", "nan"): 6,
        ("mag", "nan"): 20 + 3,
    }
    assert abs(attitude.wrap_pi(out.hpr[-1, 0] - hpr[0])) < units.deg(1.0)


def test_magnetic_gate_skips_disturbed_samples_and_counts_them():
    rng = np.random.default_rng(2)
    hpr = np.array([0.3, 0.0, 0.0])
    w, f, m = static_marg(hpr, 2000, rng)
    m[1000:1200] += [10.0, 0.0, -15.0]  # 0.18 G disturbance for 2 s: changes norm and dip
    q0 = attitude.euler_to_quat(hpr)
    plain = mh.mahony(ImuSamples(w, f, DT), q0, m_b=m)
    gated = mh.mahony(
        ImuSamples(w, f, DT), q0, m_b=m, B_n=B_N, gates=AttitudeGates(mag=MagGate(norm_tol=0.1, dip_tol=units.deg(3.0)))
    )
    assert int(plain.faults["mag", "outlier"]) == 0
    assert 195 <= int(gated.faults["mag", "outlier"]) <= 210  # the disturbance, plus a few noisy samples

    def err(r):
        return np.abs(attitude.wrap_pi(r.hpr[1000:1300, 0] - hpr[0])).max()

    assert err(gated) < 0.2 * err(plain)


def test_accelerometer_gate_counts():
    rng = np.random.default_rng(3)
    w, f, m = static_marg([0.0, 0.0, 0.0], 500, rng)
    f[100:150] *= 1.5
    out = mh.mahony(ImuSamples(w, f, DT), [1.0, 0, 0, 0], m_b=m, gates=AttitudeGates(accel_tol=0.1))
    assert int(out.faults["accel", "outlier"]) == 50


# --------------------------------------------------------------------------- filter behaviour


def test_mahony_converges_and_learns_gyro_bias():
    rng = np.random.default_rng(4)
    hpr = np.array([2.0, 0.05, 0.1])
    bias = units.deg_per_s([0.09, -0.05, 0.09])
    w, f, m = static_marg(hpr, 30_000, rng, gyro=bias, noise=(0.0, 0.0, 0.0))
    q0 = attitude.euler_to_quat(hpr + [units.deg(20.0), 0, 0])
    out = mh.mahony(ImuSamples(w, f, DT), q0, m_b=m, kp=1.0, ki=0.02)
    assert abs(attitude.wrap_pi(out.hpr[-1, 0] - hpr[0])) < units.deg(0.01)
    np.testing.assert_allclose(out.gyro_bias, bias, rtol=0.01)


def test_printed_eq2_arctan_loses_the_quadrant_and_the_unclipped_arcsin_fails_at_90_deg():
    hpr, q = random_quats(500)
    out = mimu_mag_rtk.printed_eq2_arctan(q)
    np.testing.assert_allclose(out[:, 1], hpr[:, 1], atol=1e-12)  # pitch below 90 deg: fine
    same = np.abs(attitude.wrap_pi(out[:, [0, 2]] - hpr[:, [0, 2]]))
    assert np.all((same < 1e-9) | (np.abs(same - np.pi) < 1e-9))  # right, or off by 180 deg
    assert same.max() > 3.0 and np.abs(out[:, [0, 2]]).max() <= np.pi / 2
    lock = attitude.euler_to_quat(np.stack([hpr[:, 0], np.full(500, np.pi / 2), hpr[:, 2]], -1))
    assert np.isnan(mimu_mag_rtk.printed_eq2_arctan(lock)[:, 1]).any()
    assert np.isfinite(attitude.quat_to_euler(lock)).all()


def test_printed_eq6_differs_only_in_row_3():
    _, q = random_quats(500)
    d = mimu_mag_rtk.printed_eq6(q, B_REF) - qkf.measurement_model(q, B_REF)[:, 3:]
    assert np.abs(d[:, :2]).max() < 1e-14
    q0, q1, q2, q3 = q.T
    np.testing.assert_allclose(d[:, 2], 2 * (q2**2 - q3**2) * B_REF[2], atol=1e-14)


def test_printed_mahony_order_is_the_corrected_correction_reversed_and_diverges():
    hpr = np.array([0.5, 0.05, -0.1])
    w, f, m = static_marg(hpr, 3000, np.random.default_rng(3), noise=(0.0, 0.0, 0.0))
    q0 = attitude.euler_to_quat(hpr + [units.deg(20.0), 0, 0])
    # one step without gyro: the printed increment is minus the corrected one, up to the normalisation (second order)
    good = mh.mahony(ImuSamples(w[:1], f[:1], DT), q0, m_b=m[:1], kp=1.0, ki=0.0).q_bn[0]
    bad = mimu_mag_rtk.printed_eq12_mahony(w[:1], f[:1], m[:1], DT, q0, kp=1.0, ki=0.0)[0]
    np.testing.assert_allclose(bad - q0, -(good - q0), atol=4 * np.sum((good - q0) ** 2))
    assert np.abs(good - q0).max() > 1e-4
    run = mimu_mag_rtk.printed_eq12_mahony(w, f, m, DT, q0, kp=1.0, ki=0.02)
    err = np.linalg.norm(attitude.quat_to_rotvec(attitude.quat_mult(attitude.quat_conj(attitude.euler_to_quat(hpr)), run[-1])))
    assert units.to_deg(err) > 45.0  # driven away


def test_kf_innovation_z_minus_h_converges_z_minus_Hq_stalls():
    hpr = np.array([0.0, 0.0, 0.0])
    w, f, m = static_marg(hpr, 30_000, np.random.default_rng(5), noise=(0.0, 0.0, 0.0))
    q0 = attitude.euler_to_quat(hpr + [units.deg(20.0), 0, 0])
    kw = dict(kp=0.0, ki=0.0, B_n=B_N, noise=KfNoise(sigma_gyro=1e-3, p0=1e-2))
    good = qkf.quaternion_kf(ImuSamples(w, f, DT), q0, m_b=m, **kw)
    bad = qkf.quaternion_kf(ImuSamples(w, f, DT), q0, m_b=m, linear_innovation=True, **kw)
    assert abs(attitude.wrap_pi(good.hpr[-1, 0])) < units.deg(0.1)
    assert abs(attitude.wrap_pi(bad.hpr[-1, 0])) > units.deg(5.0)


def test_batch_of_trials_equals_single_runs():
    rng = np.random.default_rng(6)
    runs = [static_marg([0.4 * i, 0.0, 0.1], 1000, rng) for i in range(3)]
    w, f, m = (np.stack(x) for x in zip(*runs, strict=True))
    q0 = attitude.euler_to_quat(np.stack([[0.4 * i, 0.0, 0.1] for i in range(3)]))
    for filt in (mh.mahony, qkf.quaternion_kf):
        batch = filt(ImuSamples(w, f, DT), q0, m_b=m, B_n=B_N)
        for i in range(3):
            single = filt(ImuSamples(w[i], f[i], DT), q0[i], m_b=m[i], B_n=B_N)
            np.testing.assert_array_equal(batch.q_bn[i], single.q_bn)


def _faulty_batch(trials, n, seed):
    """A batch of static MARG trials with dropouts, a stuck gyro, a spike and a clock jump in different trials."""
    rng = np.random.default_rng(seed)
    runs = [static_marg([0.3 * i, 0.05, -0.1], n, rng, gyro=(0.0, 0.0, 0.01)) for i in range(trials)]
    w, f, m = (np.stack(x) for x in zip(*runs, strict=True))
    w[1, 100:105] = np.nan
    w[2, 300:340, 1] = w[2, 299, 1]
    w[3, 400, 0] += 2.0
    f[4, 500:520] = np.nan
    m[5, 600:700] *= 1.5
    dts = np.full(n, DT)
    dts[800] = 0.5
    return w, f, m, dts, attitude.euler_to_quat(np.stack([[0.3 * i, 0.05, -0.1] for i in range(trials)]))


def _outputs(r):
    """Every output of an AttitudeResult as bytes (bit-for-bit comparison, NaN included)."""
    arrays = [r.q_bn, r.gyro_bias] + ([] if r.P is None else [r.P]) + [np.asarray(v) for v in r.faults.counts.values()]
    return [np.ascontiguousarray(a).tobytes() for a in arrays + list(r.faults.flags.values())]


def test_batch_outputs_equal_the_per_trial_outputs_bit_for_bit():
    # more trials than threads x chunks, faults in some: the parallel batch is the trials run one by one
    w, f, m, dts, q0 = _faulty_batch(11, 1000, 21)
    limits = SensorLimits(gyro_jump=1.0, stuck_run=10)
    kw = dict(gates=AttitudeGates(mag=MagGate()), B_n=B_N)
    for filt in (mh.mahony, qkf.quaternion_kf):
        batch = filt(ImuSamples(w, f, dts, limits), q0, m_b=m, **kw)
        assert batch.faults["gyro", "stuck"][2] > 0 and batch.faults["gyro", "nan"][1] == 5
        for i in range(len(w)):
            single = filt(ImuSamples(w[i], f[i], dts, limits), q0[i], m_b=m[i], **kw)
            one = lambda a, i=i: a[i] if np.ndim(a) else a  # noqa: E731 (the trial's row of a batch output)
            faults = type(batch.faults)(
                {k: one(v) for k, v in batch.faults.counts.items()}, {k: v[i] for k, v in batch.faults.flags.items()}
            )
            part = type(batch)(one(batch.q_bn), one(batch.gyro_bias), faults, None if batch.P is None else one(batch.P))
            assert _outputs(part) == _outputs(single), (filt.__name__, i)


THREADS = r"""
import hashlib, sys
import numpy as np
sys.path.insert(0, {tests!r})
from test_filters_attitude import _faulty_batch, _outputs, B_N
from navlib.filters import mahony as mh, quaternion_kf as qkf
from navlib.filters.observations import AttitudeGates, MagGate
from navlib.imu import ImuSamples, SensorLimits
w, f, m, dts, q0 = _faulty_batch(9, 1000, 22)
imu = ImuSamples(w, f, dts, SensorLimits(gyro_jump=1.0, stuck_run=10))
h = hashlib.sha256()
for filt in (mh.mahony, qkf.quaternion_kf):
    for chunk in _outputs(filt(imu, q0, m_b=m, gates=AttitudeGates(mag=MagGate()), B_n=B_N)):
        h.update(chunk)
print(h.hexdigest())
"""


def test_batch_results_do_not_depend_on_the_number_of_threads():
    script = THREADS.format(tests=os.path.dirname(__file__))
    digests = []
    for threads in ("1", "2", "3"):
        env = dict(os.environ, NUMBA_NUM_THREADS=threads)
        out = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True, text=True, timeout=600)
        assert out.returncode == 0, out.stderr[-3000:]
        digests.append(out.stdout.strip())
    assert len(set(digests)) == 1, digests


# --------------------------------------------------------------------------- the fixed-size KF == the generic KF


@njit(cache=True)
def _fma_compiled(a, b, c):
    out = np.empty(a.shape)
    for i in range(a.shape[0]):
        out[i] = _kernels.fma(a[i], b[i], c[i])
    return out


def test_fma_rounds_once_compiled_and_uncompiled():
    rng = np.random.default_rng(30)
    a, b = rng.standard_normal((2, 2000)) * 10.0 ** rng.integers(-5, 5, (2, 2000))
    c = -a * b * (1 + 1e-12 * rng.standard_normal(2000))  # near-cancellation: a*b + c differs from fma
    plain = np.array([_kernels.fma(x, y, z) for x, y, z in zip(a, b, c, strict=True)])
    np.testing.assert_array_equal(_fma_compiled(a, b, c), plain)
    assert np.mean(plain != a * b + c) > 0.5
    assert _kernels.fma(0.1, 10.0, -1.0) == 5.551115123125783e-17  # exact 0.1 * 10 - 1, rounded once
    assert np.isnan(_kernels.fma(np.inf, 0.0, 1.0)) and _kernels.fma(-0.0, 1.0, -0.0) == 0.0


SEQUENTIAL_RTOL = 1e-12
"""The quaternion KF's sequential scalar updates against the generic batch update (navlib.kalman.update, one 6 x 6
or 3 x 3 inverse): the same update rewritten (R diagonal), equal to rounding. Measured over the 5,000 steps below:
at most 5e-15 on the unit quaternion and 1.4e-14 on P relative to its largest element."""


def test_sequential_scalar_updates_are_the_batch_update():
    """Two chains of 5,000 predict + update steps, one through the quaternion KF's steps, one through navlib's generic
    Kalman steps, on the same measurements: gravity and heading rows, either one missing, or none."""
    rng = np.random.default_rng(31)
    r_diag = np.array([4e-4] * 3 + [6.4e-3] * 3)
    x, P = random_quats(1, seed=5)[1][0], 1e-3 * np.eye(4)
    x2, P2, x_pred = x.copy(), P.copy(), np.empty(4)
    rows_used = set()
    for step in range(5000):
        Phi, G = qkf.transition(0.5 * rng.standard_normal(3), DT), qkf.noise_input(x, DT)
        x, P = kalman.predict(x, P, Phi, G @ (1e-6 * np.eye(3)) @ G.T)
        qkf._predict(x2, P2, Phi, G, 1e-6)
        h, H = qkf.measurement_model(x, B_REF), qkf.measurement_jacobian(x, B_REF)
        z = h + np.sqrt(r_diag) * rng.standard_normal(6)
        if step % 4 < 3:  # gravity or heading rows missing, or both
            z[[[0, 1, 2], [3, 4, 5], list(range(6))][step % 4]] = np.nan
        rows_used.add(int(np.isfinite(z).sum()))
        x, P, _, _, _ = kalman.update(x, P, z, h, H, np.diag(r_diag), np.zeros(6, dtype=bool))
        h2, H2 = qkf.measurement_model(x2, B_REF), qkf.measurement_jacobian(x2, B_REF)
        qkf._update(x2, P2, z, h2, H2, r_diag, x_pred)
        x, x2 = x / np.linalg.norm(x), x2 / np.linalg.norm(x2)
        np.testing.assert_allclose(x2, x, rtol=0, atol=SEQUENTIAL_RTOL)  # unit quaternions
        np.testing.assert_allclose(P2, P, rtol=0, atol=SEQUENTIAL_RTOL * np.abs(P).max())
        assert np.array_equal(P2, P2.T)
    assert rows_used == {0, 3, 6}


def test_rtk_mode_ignores_the_value_of_invalid_epochs_and_drifts_without_bias_estimation():
    n = 20_000
    w, f, _ = static_marg(
        [np.pi / 2, 0, 0], n, np.random.default_rng(7), gyro=units.deg_per_s([0, 0, 0.09]), noise=(0.0, 0.0, 0.0)
    )
    valid = np.zeros(n, dtype=bool)
    valid[:10_000:20] = True  # 5 Hz RTK, lost after 100 s
    q0 = attitude.euler_to_quat([np.pi / 2, 0, 0])
    zeros = mh.mahony(ImuSamples(w, f, DT), q0, rtk=RtkHeading(np.where(valid, np.pi / 2, 0.0), valid), ki=0.0)
    nans = mh.mahony(ImuSamples(w, f, DT), q0, rtk=RtkHeading(np.where(valid, np.pi / 2, np.nan), valid), ki=0.0)
    np.testing.assert_array_equal(zeros.q_bn, nans.q_bn)
    drift = attitude.wrap_pi(zeros.hpr[-1, 0] - np.pi / 2)
    assert drift == pytest.approx(-units.deg_per_s(0.09) * 100.0, rel=0.02)


def test_fusion_outputs_rtk_when_valid_holds_delta_in_outages():
    n = 5000
    h_mag = np.full(n, 1.0)
    h_rtk = np.full(n, 1.1)
    valid = np.zeros(n, dtype=bool)
    valid[1000:3000:20] = True
    res = hf.fuse_rtk_heading(h_mag, RtkHeading(np.where(valid, h_rtk, 0.0), valid), DT)
    fused, delta = res.heading, res.delta
    assert np.isnan(delta).sum() == 1000 and np.isnan(delta[:1000]).all()  # uncalibrated before the first epoch
    np.testing.assert_array_equal(fused[:1000], h_mag[:1000])
    np.testing.assert_allclose(fused[1000:3000], 1.1, atol=1e-12)
    np.testing.assert_allclose(delta[3000:], 0.1, atol=1e-12)
    np.testing.assert_allclose(fused[3100:], 1.1, atol=1e-12)  # H_mag + held delta
    every = np.zeros(n, dtype=bool)
    every[1000::20] = True  # the paper's 0 fused as a value: wrong
    as_value = hf.fuse_rtk_heading(h_mag, RtkHeading(np.where(valid, h_rtk, 0.0), every), DT).heading
    assert np.abs(as_value[3100:]).max() < 0.01


def test_settling_time():
    t = np.arange(0, 10, 0.1)
    e = np.where(t < 6.0, 5.0, 0.1)
    assert analysis.settling_time(t, e, 2.0, 1.0) == pytest.approx(4.0)
    assert analysis.settling_time(t, np.full(t.size, 5.0), 2.0, 1.0) == np.inf
    with pytest.raises(ValueError, match="^tol: "):
        analysis.settling_time(t, e, 2.0, -1.0)


# --------------------------------------------------------------------------- cross-check


def test_mahony_matches_ahrs_package_to_rounding():
    """ahrs 0.4.0 Mahony.updateMARG: ENU (mag reference [0, |h_xy|, h_z]), q = body->nav (h = R m),
    e = measured x estimated, b -= kI e dt before use, q += 0.5 q (x) [0, w] dt, normalise.
    Identical to navlib's Eqs. (12)-(17) with kp = k_P, ki = k_I; ahrs uses sample 0 only for Q[0]."""
    ahrs_pkg = pytest.importorskip("ahrs")
    rng = np.random.default_rng(8)
    n = 2000
    t = np.arange(n) * DT
    hpr = np.stack([0.5 * t, 0.2 * np.sin(t), 0.3 * np.cos(0.7 * t)], -1)
    C_nb = np.swapaxes(attitude.euler_to_dcm(hpr), -1, -2)
    f = C_nb @ [0, 0, G] + 0.05 * rng.standard_normal((n, 3))
    m = C_nb @ B_N + 0.5 * rng.standard_normal((n, 3))
    w = np.array([0.0, 0.0, 0.5]) + 0.01 * rng.standard_normal((n, 3))
    q0 = attitude.euler_to_quat(hpr[0] + [0.3, 0.05, -0.05])
    peer = ahrs_pkg.filters.Mahony(gyr=w, acc=f, mag=m, frequency=1 / DT, k_P=1.5, k_I=0.1, q0=q0)
    ours = mh.mahony(ImuSamples(w[1:], f[1:], DT), q0, m_b=m[1:], kp=1.5, ki=0.1)
    np.testing.assert_allclose(ours.q_bn, peer.Q[1:], atol=1e-12)


# --------------------------------------------------------------------------- compiled == plain Python

SCRIPT = r"""
import json, numpy as np
from navlib import attitude, earth
from navlib.filters import heading_fusion as hf
from navlib.filters import mahony as mh
from navlib.filters import observations as obs
from navlib.filters import quaternion_kf as qkf
from navlib.imu import ImuSamples, SensorLimits
rng = np.random.default_rng(0)
B = earth.magnetic_field(32.0, 118.8, 0.0, 2022.5)
w = 0.01 * rng.standard_normal((2, 200, 3)); w[0, 5] = np.nan
f = np.array([0.1, 0.2, 9.8]) + 0.05 * rng.standard_normal((2, 200, 3))
m = B + 0.5 * rng.standard_normal((2, 200, 3)); m[1, 7] = 0.0
q0 = [1.0, 0.0, 0.0, 0.0]
a = mh.mahony(ImuSamples(w, f, 0.01), q0, m_b=m, B_n=B, gates=obs.AttitudeGates(mag=obs.MagGate()))
k = qkf.quaternion_kf(ImuSamples(w, f, 0.01), q0, m_b=m, B_n=B)
valid = np.zeros(200, dtype=bool); valid[::20] = True
h = hf.fuse_rtk_heading(k.hpr[..., 0], obs.RtkHeading(np.full(200, 0.5), valid), 0.01).heading
# the robustness paths: per-sample dt, spike gate, saturation, RTK dropouts, flips and re-acquisition
dt = 0.01 * (1 + 0.2 * rng.uniform(-1, 1, 200))
w[1, 50] += 1.0; f[0, 60] = [0.0, 0.0, 80.0]
rtk = np.where(valid, 0.5, np.nan); rtk[40] = 0.5 + np.pi; rtk[60] = np.nan; rtk[100:] = 2.0
limits = SensorLimits(gyro_jump=0.5, full_scale_accel=78.0, full_scale_gyro=0.02)
reference = obs.RtkHeading(rtk, valid, gate=0.3, confirm=2)
r = qkf.quaternion_kf(ImuSamples(w, f, dt, limits), q0, rtk=reference, keep_cov=True)
fr = hf.fuse_rtk_heading(r.hpr[..., 0], reference, dt)
print(json.dumps({"a": a.q_bn.tolist(), "k": k.q_bn.tolist(), "h": h.tolist(), "r": r.q_bn.tolist(),
                  "P": r.P_history.tolist(), "hr": fr.heading.tolist(),
                  "c": a.faults.as_dict(), "cr": r.faults.as_dict(), "cf": fr.faults.as_dict()}))
"""


def _run(disable_jit: bool) -> dict:
    return run_json_script(SCRIPT, disable_jit)


def test_kernels_run_uncompiled_with_the_same_results():
    jit, plain = _run(False), _run(True)
    for key in ("a", "k", "h", "r", "P", "hr"):
        np.testing.assert_allclose(plain[key], jit[key], rtol=0, atol=1e-12)
    for key in ("c", "cr", "cf"):
        assert plain[key] == jit[key]
    cr, cf = jit["cr"], jit["cf"]  # every robustness path was taken
    assert cr["gyro.spike"][1] >= 1 and cr["accel.saturated"][0] == 1 and min(cr["gyro.saturated"]) > 0
    assert min(cr["heading.outlier"]) >= 1 and cr["heading.nan"] == [1, 1] and min(cr["heading.reacquired"]) >= 1
    assert min(cf["heading.outlier"]) >= 1 and cf["heading.nan"] == [1, 1] and min(cf["heading.reacquired"]) >= 1


def test_scalar_dt_and_a_constant_dt_array_give_identical_results():
    rng = np.random.default_rng(9)
    w, f, m = static_marg([0.7, 0.05, -0.1], 500, rng)
    q0 = attitude.euler_to_quat([0.7, 0.05, -0.1])
    for filt in (mh.mahony, qkf.quaternion_kf):
        a = filt(ImuSamples(w, f, DT), q0, m_b=m, B_n=B_N)
        b = filt(ImuSamples(w, f, np.full(500, DT)), q0, m_b=m, B_n=B_N)
        np.testing.assert_array_equal(a.q_bn, b.q_bn)


def test_kf_returns_a_symmetric_positive_definite_covariance():
    rng = np.random.default_rng(10)
    w, f, m = static_marg([0.7, 0.05, -0.1], 2000, rng)
    out = qkf.quaternion_kf(ImuSamples(w, f, DT), attitude.euler_to_quat([0.7, 0.05, -0.1]), m_b=m, B_n=B_N, keep_cov=True)
    P = out.P_history
    assert P.shape == (2000, 4, 4) and np.array_equal(out.P, P[-1])
    assert np.array_equal(P, np.swapaxes(P, -1, -2)) and np.linalg.eigvalsh(P).min() > 0
    assert mh.mahony(ImuSamples(w, f, DT), [1.0, 0, 0, 0], m_b=m).P is None


# --------------------------------------------------------------------------- gyro + accelerometer only


@pytest.mark.parametrize(
    "run",
    [
        lambda w, f, q0: mh.mahony(ImuSamples(w, f, DT), q0, kp=2.0),
        lambda w, f, q0: qkf.quaternion_kf(ImuSamples(w, f, DT), q0, kp=2.0),
    ],
    ids=["mahony", "quaternion_kf"],
)
def test_without_a_heading_reference_tilt_converges_and_heading_drifts_with_the_bias(run):
    rng = np.random.default_rng(7)
    hpr = units.deg([40.0, 8.0, -5.0])
    bias_z = units.deg(0.5)  # deg/s about the body z axis
    w, f, _ = static_marg(hpr, 3000, rng, gyro=(0.0, 0.0, bias_z))
    q0 = attitude.euler_to_quat(units.deg([40.0, 0.0, 0.0]))  # level start: 9.4 deg of tilt error
    res = run(w, f, q0)
    est = attitude.quat_to_euler(res.q_bn[-1])
    tilt = np.hypot(attitude.wrap_pi(est[1] - hpr[1]), attitude.wrap_pi(est[2] - hpr[2]))
    assert units.to_deg(tilt) < 0.3  # levelled by the accelerometer alone
    # heading: no reference, so it integrates the z bias (about 0.5 deg/s * 30 s, projected on the vertical)
    drift = units.to_deg(attitude.wrap_pi(est[0] - hpr[0]))
    assert 10.0 < abs(drift) < 20.0
    assert not res.faults  # nothing skipped: there was nothing to read


@pytest.mark.parametrize("n", [0, 1, 7, 32, 1000])
def test_run_chunks_covers_the_range_in_order(n):
    from navlib._threads import run_chunks

    chunks = run_chunks(lambda i0, i1: (i0, i1), n)
    assert chunks[0][0] == 0 and chunks[-1][1] == n
    assert all(a[1] == b[0] and a[0] < a[1] for a, b in zip(chunks, chunks[1:], strict=False))


# --------------------------------------------------------------------------- screen once, filter many


@pytest.mark.parametrize("filt", [mh.mahony, qkf.quaternion_kf], ids=["mahony", "quaternion_kf"])
def test_screened_samples_give_the_filters_result_without_screening_again(filt, monkeypatch):
    w, f, m, dts, q0 = _faulty_batch(6, 1000, 23)
    imu = ImuSamples(w, f, dts, SensorLimits(gyro_jump=1.0, stuck_run=10))
    kw = dict(gates=AttitudeGates(accel_tol=0.3, mag=MagGate()), B_n=B_N)
    direct = filt(imu, q0, m_b=m, **kw)
    with pytest.raises(TypeError, match="^imu: expected an ImuSamples"):  # checked once, by the screen
        filt((w, f), q0, **kw)
    screened = robust.screen(imu, m)
    monkeypatch.setattr(obs, "screen", None)  # screening again would fail
    once = filt(screened, q0, **kw)
    assert _outputs(once) == _outputs(direct) and once.faults["mag", "outlier"].sum() > 0
    with pytest.raises(ValueError, match="^m_b: imu is already screened"):
        filt(screened, q0, m_b=m, **kw)


def test_observe_codes_each_dropped_sample():
    """observe's one range test per norm (finiteness folded into the limits by pack) drops and codes as the
    separate tests do: 1 unusable (zero, not finite, a field parallel to gravity), 2 outside a gate."""
    gates = AttitudeGates(accel_tol=0.1, mag=MagGate(norm_tol=0.1, dip_tol=np.deg2rad(5.0)))
    imu = ImuSamples(np.zeros((4, 3)), np.tile([0.0, 0.0, G], (4, 1)), DT)
    limits = obs.pack(imu, [1.0, 0.0, 0.0, 0.0], np.tile(B_N, (4, 1)), None, B_N, gates, 1.0)[1].limits
    m_ok = INTENSITY * np.array([0.0, np.cos(INCL), -np.sin(INCL)])  # body = navigation frame
    f_ok = np.array([0.0, 0.0, G])
    cases = [  # (f, m, skip_a, skip_m) -> (accel code, mag code)
        ((f_ok, m_ok, False, False), (0, 0)),
        ((0.0 * f_ok, m_ok, False, False), (1, 0)),  # no accelerometer: no dip test
        ((np.array([np.inf, 0.0, G]), m_ok, False, False), (1, 0)),
        ((1.2 * f_ok, m_ok, False, False), (2, 0)),
        ((f_ok, 0.0 * m_ok, False, False), (0, 1)),
        ((f_ok, np.array([0.0, 0.0, -INTENSITY]), False, False), (0, 1)),  # parallel to gravity
        ((f_ok, np.array([0.0, INTENSITY, 0.0]), False, False), (0, 2)),  # dip 0 deg
        ((f_ok, 1.2 * m_ok, False, False), (0, 2)),
        ((f_ok, 1.2 * m_ok, False, True), (0, 0)),  # skipped by the screen: no code, NaN
        ((1.2 * f_ok, np.array([0.0, INTENSITY, 0.0]), False, False), (2, 0)),  # accelerometer gated: no dip test
    ]
    for (f, m, skip_a, skip_m), codes in cases:
        out = obs.observe(*f, *m, skip_a, skip_m, limits)
        assert out[6:] == codes, (f, m, out)
        assert np.isnan(out[0]) == (skip_a or codes[0] > 0) and np.isnan(out[3]) == (skip_m or codes[1] > 0)


def test_screen_refuses_a_huge_magnetometer_value_in_a_batch():
    """The magnetometer's magnitude limit (navlib._validate.MAX_MAGNITUDE), checked in the screen's parallel scan,
    raises as_array's message; inf and NaN stay dropouts."""
    rng = np.random.default_rng(3)
    w, f, m = 1e-3 * rng.standard_normal((3, 50, 3)), np.tile([0.0, 0.0, G], (3, 50, 1)), np.tile(B_N, (3, 50, 1))
    m[1, 7, 2], m[2, 9, 0] = np.inf, np.nan
    assert int(robust.screen(ImuSamples(w, f, DT), m).faults["mag", "nan"].sum()) == 2
    m[2, 30, 1] = -1e200
    with pytest.raises(ValueError, match=r"^m_b: expected magnitudes up to"):
        robust.screen(ImuSamples(w, f, DT), m)
