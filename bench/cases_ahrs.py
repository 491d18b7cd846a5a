"""Attitude filters of navlib.filters (Mahony, quaternion KF) against ahrs (AHRS 0.4.0) and imufusion, same data, same run."""

from __future__ import annotations

import numpy as np

from bench.run import Result, best_time, best_times
from navlib import attitude, earth
from navlib.filters import mahony as mh
from navlib.filters import quaternion_kf as qkf
from navlib.imu import ImuSamples

DT = 0.01
B_N = earth.magnetic_field(32.03, 118.85, 20.0, 2022.5)


def _marg_data(n: int, trials: int | None = None, seed: int = 0):
    """Noisy gyro (rad/s), accelerometer (m/s^2) and magnetometer (uT) of a slowly turning, tilted IMU."""
    rng = np.random.default_rng(seed)
    lead = () if trials is None else (trials,)
    t = np.arange(n) * DT
    hpr = np.stack([0.3 * t % (2 * np.pi), 0.1 * np.sin(0.2 * t), 0.1 * np.cos(0.3 * t)], -1)
    C_nb = np.swapaxes(attitude.euler_to_dcm(hpr), -1, -2)
    f = C_nb @ [0.0, 0.0, 9.8] + 0.02 * rng.standard_normal(lead + (n, 3))
    m = C_nb @ B_N + 0.5 * rng.standard_normal(lead + (n, 3))
    w = np.array([0.0, 0.0, 0.3]) + 1e-3 * rng.standard_normal(lead + (n, 3))
    return w, f, m, attitude.euler_to_quat(hpr[0])


def _ahrs_rows(case: str, w, f, m, q0, n_total: int, m_peer: int) -> list[Result]:
    """ahrs's Mahony or EKF on the first ``m_peer`` samples, scaled to ``n_total`` (one timed call: it is slow)."""
    try:
        from ahrs.filters import EKF, Mahony
    except ImportError:
        return []
    peer = Mahony if "Mahony" in case else EKF
    kw = dict(k_P=1.0, k_I=0.02) if "Mahony" in case else dict(frame="ENU")
    t = best_time(lambda: peer(gyr=w[:m_peer], acc=f[:m_peer], mag=m[:m_peer], frequency=1 / DT, q0=q0, **kw), repeat=1)
    return [
        Result(
            case, f"ahrs 0.4.0 {peer.__name__}", m_peer / t, "samples/s", t * n_total / m_peer, note=f"timed on {m_peer} samples"
        )
    ]


def _fusion_loop(w, f, m, m_peer: int):
    """imufusion's AHRS called per sample over the first ``m_peer`` samples (None without imufusion)."""
    try:
        import imufusion
    except ImportError:
        return None
    gyro_dps, acc_g = np.rad2deg(w[:m_peer]), f[:m_peer] / 9.80665

    def fusion_loop():
        filt = imufusion.Ahrs()
        for k in range(m_peer):
            filt.update(gyro_dps[k], acc_g[k], m[k])

    return fusion_loop


def _with_peers(case: str, navlib_run, w, f, m, q0, n: int, m_peer: int) -> tuple[float, list[Result]]:
    """navlib's best time (alternating with imufusion's, see best_times) and the peers' rows."""
    t, t_fusion = best_times(navlib_run, _fusion_loop(w, f, m, m_peer))
    rows = _ahrs_rows(case, w, f, m, q0, n, m_peer)
    if t_fusion is not None:
        rows.append(
            Result(
                case,
                "imufusion (C, per-sample calls)",
                m_peer / t_fusion,
                "samples/s",
                t_fusion * n / m_peer,
                note=f"timed on {m_peer} samples",
            )
        )
    return t, rows


def mahony_single(quick: bool):
    """One Mahony MARG filter over 1 h at 100 Hz (goal: >= 10 M samples/s)."""
    n = 36_000 if quick else 360_000
    w, f, m, q0 = _marg_data(n)
    case = "Mahony MARG, 1 filter"
    t, peers = _with_peers(case, lambda: mh.mahony(ImuSamples(w, f, DT), q0, m_b=m), w, f, m, q0, n, 2_000 if quick else 10_000)
    return [Result(case, "navlib.filters.mahony.mahony (numba)", n / t, "samples/s", t, goal=10e6)] + peers


def mahony_batch(quick: bool):
    """A batch of Mahony filters, trials over the cores (goal: >= 1.8 x one filter's throughput, this run).

    The batch and one filter (its first trial) are timed alternately, best of five rounds each."""
    trials, n = (8, 36_000) if quick else (32, 180_000)
    w, f, m, q0 = _marg_data(n, trials, seed=1)
    t, t_one = best_times(
        lambda: mh.mahony(ImuSamples(w, f, DT), q0, m_b=m), lambda: mh.mahony(ImuSamples(w[0], f[0], DT), q0, m_b=m[0])
    )
    single = n / t_one
    return [
        Result(
            f"Mahony MARG, {trials} trials",
            "navlib.filters.mahony.mahony (numba)",
            trials * n / t,
            "samples/s",
            t,
            goal=1.8 * single,
            note=f"aggregate over the batch; goal: >= 1.8x one filter on 2 cores ({single:.3g} samples/s, this run)",
        )
    ]


def quaternion_kf(quick: bool):
    """The paper's PI + quaternion KF (4 states, 6 measurements) against ahrs's EKF and imufusion."""
    n = 36_000 if quick else 360_000
    w, f, m, q0 = _marg_data(n, seed=2)
    case = "quaternion KF (PI + KF)"
    t, peers = _with_peers(
        case, lambda: qkf.quaternion_kf(ImuSamples(w, f, DT), q0, m_b=m, B_n=B_N), w, f, m, q0, n, 1_000 if quick else 5_000
    )
    fusion = next((r.throughput for r in peers if r.implementation.startswith("imufusion")), None)
    return [
        Result(
            case,
            "navlib.filters.quaternion_kf.quaternion_kf (numba)",
            n / t,
            "samples/s",
            t,
            goal=fusion,
            note="goal: >= 1x imufusion, this run" if fusion else "",
        )
    ] + peers


CASES = [mahony_single, mahony_batch, quaternion_kf]
