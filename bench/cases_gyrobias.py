"""Paper 001 cases: IMU samples per second through the rotation bias estimator and Eq. (2) integration."""

from __future__ import annotations

import numpy as np

from bench.run import Result, best_time
from navlib import attitude, earth, euler, sensors, strapdown, trajectory, units
from navlib.papers import rotation_bias as gyrobias

DT, PERIOD, ROTATION_TIME = 0.01, 5.0, 0.5
LAT = units.deg(40.0)


def _rig(trials: int, duration: float):
    """MTi-100 on the reciprocating rig of paper 001 (pitch 30 deg, u = y_b), `trials` runs."""
    hpr0 = units.deg([0.0, 30.0, 0.0])
    traj = trajectory.reciprocating_rotation(duration, DT, [LAT, 0, 0], hpr0, [0, 1, 0], np.pi / 2, PERIOD, ROTATION_TIME)
    w, f = trajectory.ideal_imu(traj)
    imu = sensors.simulate_imu(w, f, DT, sensors.imu_model("MTi-100"), np.random.default_rng(0), n_trials=trials)
    starts, length = gyrobias.dwell_windows(w.shape[0], DT, PERIOD, ROTATION_TIME)
    attitudes = gyrobias.dwell_attitudes(hpr0, [0, 1, 0], np.pi / 2, starts.size)
    w_ie_b = earth.earth_rate_b(attitude.euler_to_dcm(attitudes), LAT)
    return hpr0, imu, starts, length, w_ie_b


def _euler_numpy(hpr0, w, dt, steps):
    """Reference: Eq. (2) by RK4, vectorised over trials, Python loop over time."""
    x = np.broadcast_to(hpr0, (w.shape[0], 3)).copy()

    def rates(x, w):
        p, r = x[:, 1], x[:, 2]
        hd = (np.sin(r) * w[:, 0] - np.cos(r) * w[:, 2]) / np.cos(p)
        return np.stack([hd, np.cos(r) * w[:, 0] + np.sin(r) * w[:, 2], w[:, 1] + np.sin(p) * hd], -1)

    for k in range(steps):
        wk = w[:, k]
        k1 = rates(x, wk)
        k2 = rates(x + dt / 2 * k1, wk)
        k3 = rates(x + dt / 2 * k2, wk)
        k4 = rates(x + dt * k3, wk)
        x = x + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
    return x


def estimator_and_integration(quick: bool):
    """30 runs x 1 h x 100 Hz (paper 001 scale): residuals + running LSQ + compensated Eq. (2) integration."""
    trials, duration = 30, (360.0 if quick else 3600.0)
    hpr0, imu, starts, length, w_ie_b = _rig(trials, duration)
    w_ie_n = earth.earth_rate_n(LAT)
    total = imu.w_ib_b.shape[0] * imu.w_ib_b.shape[1]

    def estimate():
        res = gyrobias.tilt_residuals(imu.w_ib_b, imu.f_b, DT, starts, length, w_ie_b)
        return res, gyrobias.running_lsq_bias(res.r, res.V, np.exp(-PERIOD / 60.0))[0]

    res, b = estimate()
    t_est = best_time(estimate)
    t_int = best_time(lambda: euler.integrate_euler(hpr0, imu.w_ib_b, DT, w_ie_n, b, res.end))
    t_all = best_time(lambda: euler.integrate_euler(hpr0, imu.w_ib_b, DT, w_ie_n, estimate()[1], res.end))
    q0 = np.array([1.0, 0.0, 0.0, 0.0])
    t_quat = best_time(lambda: strapdown.integrate_attitude(q0, imu.w_ib_b, DT, w_ie_n))
    m = 2000  # a slice is enough to time Python loops
    t_np = best_time(lambda: _euler_numpy(hpr0, imu.w_ib_b, DT, m), repeat=1)
    case = f"gyrobias, 30 runs x {duration / 3600:g} h"
    rows = [
        Result(
            case,
            "navlib estimator + integration",
            total / t_all,
            "samples/s",
            t_all,
            note="tilt_residuals + running_lsq_bias + integrate_euler (bias-compensated)",
        ),
        Result(case, "navlib estimator only", total / t_est, "samples/s", t_est),
        Result(case, "navlib Eq. (2) integration only", total / t_int, "samples/s", t_int),
        Result(
            case,
            "navlib quaternion strapdown",
            total / t_quat,
            "samples/s",
            t_quat,
            note="strapdown.integrate_attitude, same samples (reference)",
        ),
        Result(
            case,
            "numpy Eq. (2) RK4 over trials",
            trials * m / t_np,
            "samples/s",
            t_np * imu.w_ib_b.shape[1] / m,
            note=f"timed on {m} steps, scaled",
        ),
    ]
    try:
        from ahrs.filters import AngularRate
    except ImportError:
        return rows
    n_ahrs = 20_000
    gyr = np.ascontiguousarray(imu.w_ib_b[0, :n_ahrs])
    t_ahrs = best_time(lambda: AngularRate(gyr=gyr, q0=q0, frequency=1 / DT), repeat=1)
    rows.append(
        Result(
            case,
            "ahrs AngularRate (quaternion)",
            n_ahrs / t_ahrs,
            "samples/s",
            t_ahrs * total / n_ahrs,
            note=f"one run, {n_ahrs} samples, scaled",
        )
    )
    return rows


CASES = [estimator_and_integration]
