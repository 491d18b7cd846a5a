"""Core cases: strapdown attitude and navigation, the Kalman step, IMU simulation."""

from __future__ import annotations

import numpy as np
from numba import njit

from bench.run import Result, best_time
from navlib import _kernels, sensors, strapdown, trajectory, units


def strapdown_attitude(quick: bool):
    """30 trials x 1 h x 100 Hz of gyro samples through the quaternion update (goal: 0.5 s)."""
    trials, n, dt = 30, (36_000 if quick else 360_000), 0.01
    rng = np.random.default_rng(0)
    w = 0.1 * rng.standard_normal((trials, n, 3))
    q0 = np.array([1.0, 0.0, 0.0, 0.0])
    t_nav = best_time(lambda: strapdown.integrate_attitude(q0, w, dt))

    def numpy_over_trials(m):
        # Reference: the same update vectorised over trials, Python loop over time.
        q = np.tile(q0, (trials, 1))
        for k in range(m):
            rv = w[:, k] * dt
            a = np.linalg.norm(rv, axis=-1, keepdims=True)
            dq = np.concatenate([np.cos(a / 2), np.sinc(a / (2 * np.pi)) / 2 * rv], -1)
            q0_, q1, q2, q3 = q.T
            p0, p1, p2, p3 = dq.T
            q = np.stack(
                [
                    q0_ * p0 - q1 * p1 - q2 * p2 - q3 * p3,
                    q0_ * p1 + q1 * p0 + q2 * p3 - q3 * p2,
                    q0_ * p2 - q1 * p3 + q2 * p0 + q3 * p1,
                    q0_ * p3 + q1 * p2 - q2 * p1 + q3 * p0,
                ],
                -1,
            )
            q /= np.linalg.norm(q, axis=-1, keepdims=True)
        return q

    m_ref = n // 20  # a slice is enough to time a Python loop
    t_ref = best_time(lambda: numpy_over_trials(m_ref), repeat=1)
    total = trials * n
    return [
        Result(
            "strapdown attitude, 30 trials",
            "navlib (numba)",
            total / t_nav,
            "samples/s",
            t_nav,
            goal=30 * 360_000 / 0.5,
            note="goal: 30 trials x 1 h x 100 Hz in 0.5 s",
        ),
        Result(
            "strapdown attitude, 30 trials",
            "numpy over trials",
            trials * m_ref / t_ref,
            "samples/s",
            t_ref * n / m_ref,
            note=f"timed on {m_ref} steps, scaled",
        ),
    ]


def strapdown_navigation(quick: bool):
    """Full ENU mechanisation (attitude, velocity, position) on a 1-h drive at 100 Hz."""
    n = 36_000 if quick else 360_000
    rng = np.random.default_rng(1)
    w = 1e-3 * rng.standard_normal((n, 3))
    f = np.array([0.0, 0.0, 9.79]) + 1e-2 * rng.standard_normal((n, 3))
    lla0 = [units.deg(30.0), units.deg(114.0), 20.0]
    t = best_time(lambda: strapdown.integrate(lla0, np.zeros(3), [1, 0, 0, 0], w, f, 0.01))
    return [Result("strapdown navigation, 1 trial", "navlib (numba)", n / t, "samples/s", t)]


@njit(cache=True)
def _kf_loop(z, F, Q, H, R):
    x = np.zeros(F.shape[0])
    P = np.eye(F.shape[0])
    mask = np.zeros(z.shape[1], dtype=np.bool_)
    for k in range(z.shape[0]):
        x, P = _kernels.kalman_predict(x, P, F, Q)
        x, P, _, _, _ = _kernels.kalman_update(x, P, z[k], H @ x, H, R, mask)
    return x


def kalman_step(quick: bool):
    """Linear 5-state predict + Joseph update with 5 measurements, per step."""
    n = 100_000 if quick else 1_000_000
    rng = np.random.default_rng(2)
    F = np.eye(5) + 0.01 * np.diag(np.ones(4), 1)
    Q, H, R = 1e-4 * np.eye(5), np.eye(5), 0.1 * np.eye(5)
    z = rng.standard_normal((n, 5))
    t_nav = best_time(lambda: _kf_loop(z, F, Q, H, R))
    rows = [Result("Kalman step, 5 states", "navlib.kalman (numba loop)", n / t_nav, "steps/s", t_nav)]
    try:
        from filterpy.kalman import KalmanFilter
    except ImportError:
        return rows
    m = 20_000

    def filterpy_loop():
        kf = KalmanFilter(dim_x=5, dim_z=5)
        kf.F, kf.Q, kf.H, kf.R, kf.P = F, Q, H, R, np.eye(5)
        for k in range(m):
            kf.predict()
            kf.update(z[k])

    t_fp = best_time(filterpy_loop, repeat=1)
    rows.append(Result("Kalman step, 5 states", "filterpy", m / t_fp, "steps/s", t_fp * n / m, note=f"timed on {m} steps"))
    return rows


def imu_simulation(quick: bool):
    """MTi-100 error model applied to 1 h of 100 Hz samples."""
    n = 36_000 if quick else 360_000
    traj = trajectory.static(n * 0.01, 0.01, [0.5, 2.0, 0.0], [0.0, 0.0, 0.0])
    w, f = trajectory.ideal_imu(traj)
    model = sensors.imu_model("MTi-100")
    t = best_time(lambda: sensors.simulate_imu(w, f, 0.01, model, np.random.default_rng(3)))
    return [Result("IMU simulation (MTi-100)", "navlib (numpy draws, numba error pass)", n / t, "samples/s", t)]


CASES = [strapdown_attitude, strapdown_navigation, kalman_step, imu_simulation]
