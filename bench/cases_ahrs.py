"""Attitude filters of navlib.filters (Mahony, quaternion KF) against ahrs (AHRS 0.4.0) and imufusion, same data, same run."""

from __future__ import annotations

import numpy as np
from numba import njit

from bench.run import Result, best_time, best_times
from navlib import attitude, earth, robust
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


def _fusion_row(case: str, t_fusion: float | None, n: int, m_peer: int) -> list[Result]:
    if t_fusion is None:
        return []
    return [
        Result(
            case,
            "imufusion (C, per-sample calls)",
            m_peer / t_fusion,
            "samples/s",
            t_fusion * n / m_peer,
            note=f"timed on {m_peer} samples",
        )
    ]


REPEATS = 3
"""Each figure of these cases is measured this many times (each a best of rounds, :func:`bench.run.best_times`);
the rows show the median run and the spread (lowest to highest) of the figure over the runs."""


def _median_run(runs: list[tuple[float, ...]], figure, fmt: str = ".2f") -> tuple[tuple[float, ...], str]:
    """The run whose ``figure(run)`` is the median of ``runs``, and the spread of the figure as text (format ``fmt``)."""
    values = sorted((figure(r), i) for i, r in enumerate(runs))
    lo, hi = values[0][0], values[-1][0]
    return runs[values[len(values) // 2][1]], f"{len(runs)} runs: {lo:{fmt}} to {hi:{fmt}}"


@njit(cache=True)
def _mahony_bound(w, f, m, q_init, dt, kp, ki, q_out):
    """Mahony's MARG update on clean samples and nothing else: normalise the accelerometer and magnetometer,
    the error of Eqs. (12)-(14), the PI rate (Eq. 15), the first-order update and normalisation (Eq. 17),
    store. No screening, gates, fault branches or records: the latency bound of one filter on this CPU,
    the dependent chain q -> C(q) -> e -> w -> q of each sample plus its loads and stores."""
    q0, q1, q2, q3 = q_init[0], q_init[1], q_init[2], q_init[3]
    ix = iy = iz = 0.0
    for k in range(w.shape[0]):
        sa = 1.0 / np.sqrt(f[k, 0] * f[k, 0] + f[k, 1] * f[k, 1] + f[k, 2] * f[k, 2])
        sm = 1.0 / np.sqrt(m[k, 0] * m[k, 0] + m[k, 1] * m[k, 1] + m[k, 2] * m[k, 2])
        ax, ay, az, mx, my, mz = f[k, 0] * sa, f[k, 1] * sa, f[k, 2] * sa, m[k, 0] * sm, m[k, 1] * sm, m[k, 2] * sm
        C11, C12, C13 = q0 * q0 + q1 * q1 - q2 * q2 - q3 * q3, 2 * (q1 * q2 - q0 * q3), 2 * (q1 * q3 + q0 * q2)
        C21, C22, C23 = 2 * (q1 * q2 + q0 * q3), q0 * q0 - q1 * q1 + q2 * q2 - q3 * q3, 2 * (q2 * q3 - q0 * q1)
        C31, C32, C33 = 2 * (q1 * q3 - q0 * q2), 2 * (q2 * q3 + q0 * q1), q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3
        hx, hy, hz = C11 * mx + C12 * my + C13 * mz, C21 * mx + C22 * my + C23 * mz, C31 * mx + C32 * my + C33 * mz
        bn = np.sqrt(hx * hx + hy * hy)
        vx, vy, vz = bn * C21 + hz * C31, bn * C22 + hz * C32, bn * C23 + hz * C33
        ex = ay * C33 - az * C32 + my * vz - mz * vy
        ey = az * C31 - ax * C33 + mz * vx - mx * vz
        ez = ax * C32 - ay * C31 + mx * vy - my * vx
        ix, iy, iz = ix + ex * dt, iy + ey * dt, iz + ez * dt
        wx, wy, wz = w[k, 0] + kp * ex + ki * ix, w[k, 1] + kp * ey + ki * iy, w[k, 2] + kp * ez + ki * iz
        c = 0.5 * dt
        q0, q1, q2, q3 = (
            q0 + c * (-q1 * wx - q2 * wy - q3 * wz),
            q1 + c * (q0 * wx + q2 * wz - q3 * wy),
            q2 + c * (q0 * wy - q1 * wz + q3 * wx),
            q3 + c * (q0 * wz + q1 * wy - q2 * wx),
        )
        s = 1.0 / np.sqrt(q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3)
        q0, q1, q2, q3 = q0 * s, q1 * s, q2 * s, q3 * s
        q_out[k, 0], q_out[k, 1], q_out[k, 2], q_out[k, 3] = q0, q1, q2, q3


BOUND_SHARE = 0.8  # issue 38: one filter at >= 80 % of the latency bound
BOUND_HOW = (
    "latency bound: bench's _mahony_bound, Mahony's MARG update alone on clean samples (normalise a and m, error "
    "Eqs. 12-14, PI rate, first-order update, normalise, store: the dependent chain of one filter), same data, timed "
    "alternately with the filter (best of 5 rounds each)"
)


def mahony_single(quick: bool):
    """One Mahony MARG filter over 1 h at 100 Hz against the latency bound (:func:`_mahony_bound`, same data, timed
    alternately). The goal row is the filter on screened samples (``robust.screen`` once, outside the timed call:
    screen once, filter many); the screen alone and the filter as a user calls it (screen + filter) have their rows.
    Measured :data:`REPEATS` times: the rows give the run of median share of the bound, and the shares' spread."""
    n = 36_000 if quick else 360_000
    w, f, m, q0 = _marg_data(n)
    case = "Mahony MARG, 1 filter"
    q_bound = np.empty((n, 4))
    screened = robust.screen(ImuSamples(w, f, DT), m)

    def bound():
        _mahony_bound(w, f, m, q0, DT, 1.0, 0.02, q_bound)

    def user():
        return mh.mahony(ImuSamples(w, f, DT), q0, m_b=m)

    bound()
    assert np.abs(user().q_bn - q_bound).max() < 1e-9, "the bound kernel is not Mahony's filter (to rounding)"
    fns = (lambda: mh.mahony(screened, q0), bound, lambda: robust.screen(ImuSamples(w, f, DT), m), user)
    runs = [tuple(best_times(*fns)) for _ in range(REPEATS)]
    (t, t_bound, t_screen, t_user), spread = _median_run(runs, lambda r: r[1] / r[0], ".1%")
    _, user_spread = _median_run(runs, lambda r: r[1] / r[3], ".1%")
    m_peer = 2_000 if quick else 10_000
    peers = _ahrs_rows(case, w, f, m, q0, n, m_peer) + _fusion_row(case, best_times(_fusion_loop(w, f, m, m_peer))[0], n, m_peer)
    return [
        Result(
            case,
            "navlib.filters.mahony.mahony on screened samples (numba)",
            n / t,
            "samples/s",
            t,
            goal=BOUND_SHARE * n / t_bound,
            note=f"{t_bound / t:.1%} of the latency bound ({spread}); goal: >= {BOUND_SHARE:.0%} of it",
        ),
        Result(case, "latency bound (minimal kernel, bench)", n / t_bound, "samples/s", t_bound, note=BOUND_HOW),
        Result(case, "navlib.robust.screen alone", n / t_screen, "samples/s", t_screen, note="gyro, accelerometer, magnetometer"),
        Result(
            case,
            "navlib.filters.mahony.mahony as a user calls it (screen + filter)",
            n / t_user,
            "samples/s",
            t_user,
            note=f"{t_bound / t_user:.1%} of the latency bound ({user_spread})",
        ),
    ] + peers


def mahony_batch(quick: bool):
    """A batch of Mahony filters, trials over the cores (goal: >= 1.9 x one filter's throughput, this run), as a user
    calls it (``ImuSamples`` and screening included).

    The batch and one filter (its first trial) are timed alternately, best of five rounds each; :data:`REPEATS` runs,
    the row gives the run of median ratio and the ratios' spread."""
    trials, n = (8, 36_000) if quick else (32, 180_000)
    w, f, m, q0 = _marg_data(n, trials, seed=1)

    def batch():
        mh.mahony(ImuSamples(w, f, DT), q0, m_b=m)

    def one():
        mh.mahony(ImuSamples(w[0], f[0], DT), q0, m_b=m[0])

    runs = [tuple(best_times(batch, one)) for _ in range(REPEATS)]
    (t, t_one), spread = _median_run(runs, lambda r: trials * r[1] / r[0])
    single = n / t_one
    return [
        Result(
            f"Mahony MARG, {trials} trials",
            "navlib.filters.mahony.mahony (numba)",
            trials * n / t,
            "samples/s",
            t,
            goal=1.9 * single,
            note=f"aggregate over the batch, {trials * n / t / single:.2f}x one filter ({spread}); goal: >= 1.9x one "
            f"filter on 2 cores ({single:.3g} samples/s, this run)",
        )
    ]


def quaternion_kf(quick: bool):
    """The paper's PI + quaternion KF (4 states, 6 measurements) as a user calls it (screening included) against
    ahrs's EKF and imufusion (goal >= 3x it), timed alternately with imufusion; :data:`REPEATS` runs, the rows give the
    run of median ratio and the ratios' spread."""
    n = 36_000 if quick else 360_000
    m_peer = 1_000 if quick else 5_000
    w, f, m, q0 = _marg_data(n, seed=2)
    case = "quaternion KF (PI + KF)"
    fusion = _fusion_loop(w, f, m, m_peer)
    runs = [
        tuple(best_times(lambda: qkf.quaternion_kf(ImuSamples(w, f, DT), q0, m_b=m, B_n=B_N), fusion)) for _ in range(REPEATS)
    ]
    (t, t_fusion), spread = _median_run(runs, lambda r: (n / r[0]) / (m_peer / r[1]) if r[1] else 0.0)
    peers = _ahrs_rows(case, w, f, m, q0, n, m_peer) + _fusion_row(case, t_fusion, n, m_peer)
    ratio = (n / t) / (m_peer / t_fusion) if t_fusion else None
    return [
        Result(
            case,
            "navlib.filters.quaternion_kf.quaternion_kf (numba)",
            n / t,
            "samples/s",
            t,
            goal=3 * m_peer / t_fusion if t_fusion else None,
            note=f"{ratio:.2f}x imufusion ({spread}); goal: >= 3x imufusion, this run" if ratio else "",
        )
    ] + peers


CASES = [mahony_single, mahony_batch, quaternion_kf]
