"""A throwaway Madgwick filter written against the filter shape of CONTRIBUTING.md: one file, the library's
screening, gates, records and measurement model imported, only the algorithm's equations written here.

Madgwick, Harrison, Vaidyanathan (2011), "Estimation of IMU and MARG orientation using a gradient descent
algorithm", IEEE ICORR: per sample, ``q_dot = 1/2 q (x) [0, w] - beta grad / |grad|`` with
``grad = J^T (h(q) - z)`` the gradient of the objective ``|h(q) - z|^2 / 2`` (Eqs. 20-21, 33-34; gravity
and the field's reference direction in place of his ``d``), then ``q <- normalise(q + q_dot dt)``.
"""

from __future__ import annotations

import numpy as np

from navlib import attitude, strapdown
from navlib.filters import observations
from navlib.filters.observations import AttitudeGates, AttitudeResult
from navlib.filters.quaternion_kf import measurement_jacobian, measurement_model
from navlib.imu import ImuSamples

# ---------------------------------------------------------------- the filter: 25 lines of algorithm code


def madgwick(
    imu: ImuSamples, q0, *, m_b=None, B_n=None, beta: float = 0.1, gates: AttitudeGates = AttitudeGates()
) -> AttitudeResult:
    """Madgwick's gradient-descent filter on screened samples; leading axes of ``imu`` are trials."""
    lead, inp, found = observations.pack(imu, q0, m_b, None, B_n, gates, kp=1.0)
    b = observations.magnetic_reference(B_n)[0] if inp.use_mag else np.zeros(3)
    q, (T, N) = inp.q_init.copy(), inp.w.shape[:2]
    q_out, zs = np.empty((T, N, 4)), observations.unit_vectors(inp)
    for k in range(N):
        if not inp.jump[k]:  # a clock jump: nothing integrated over it
            dt = inp.dts[k]
            q_dot = 0.5 * attitude.quat_mult(q, np.concatenate([np.zeros((T, 1)), inp.w[:, k]], -1))
            z = zs[:, k]  # unit vectors; NaN: skipped (screened or gated)
            used = np.isfinite(z)
            error = np.where(used, measurement_model(q, b) - z, 0.0)
            grad = np.einsum("tij,ti->tj", measurement_jacobian(q, b), error)
            norm = np.linalg.norm(grad, axis=-1, keepdims=True)
            q_dot -= beta * np.divide(grad, norm, out=np.zeros_like(grad), where=norm > 0)
            q = q + q_dot * dt
            q /= np.linalg.norm(q, axis=-1, keepdims=True)
        q_out[:, k] = q
    return observations.attitude_result(lead, inp, q_out, np.zeros((T, 3)), np.zeros((T, 4), np.int64), found)


# ---------------------------------------------------------------- tests


B_N = np.array([0.0, 20.0, -40.0])


def _rotating(duration=60.0, dt=0.01):
    """A slowly tumbling IMU: gyro, accelerometer and magnetometer without noise, and its true attitude."""
    t = np.arange(round(duration / dt)) * dt
    w = np.stack([0.2 * np.sin(0.5 * t), 0.1 * np.cos(0.3 * t), 0.4 * np.sin(0.2 * t)], -1)
    q = strapdown.integrate_attitude(attitude.euler_to_quat([0.7, 0.1, -0.05]), w, dt)[1:]
    C_bn = attitude.quat_to_dcm(q)
    return q, w, np.einsum("tji,j->ti", C_bn, [0.0, 0.0, 9.80665]), np.einsum("tji,j->ti", C_bn, B_N), dt


def _angle_deg(p, q):
    d = attitude.quat_mult(p, attitude.quat_conj(q))
    return np.rad2deg(2 * np.arccos(np.clip(np.abs(d[..., 0]), 0.0, 1.0)))


def test_madgwick_converges_from_a_wrong_start_and_tracks_the_motion():
    q_true, w, f, m, dt = _rotating()
    q0 = attitude.quat_mult(attitude.euler_to_quat([np.deg2rad(30.0), 0.1, -0.1]), q_true[0])
    res = madgwick(ImuSamples(w, f, dt), q0, m_b=m, B_n=B_N, beta=0.1)
    err = _angle_deg(res.q_bn, q_true)
    assert err[0] > 20.0 and err[-1000:].max() < 0.5
    assert not res.faults


def test_madgwick_skips_screened_samples_and_reports_them():
    q_true, w, f, m, dt = _rotating(20.0)
    f[500:600] = np.nan  # accelerometer dropout: the gyro carries the attitude
    w[700:705] = np.nan
    res = madgwick(ImuSamples(w, f, dt), q_true[0], m_b=m, B_n=B_N)
    assert res.faults["accel", "nan"] == 100 and res.faults["gyro", "nan"] == 5
    assert np.isfinite(res.q_bn).all()
