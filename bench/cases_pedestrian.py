"""Pedestrian case: the 15-state ZUPT/ZARU error-state filter of paper 004, per IMU step."""

from __future__ import annotations

import numpy as np

from bench.run import Result, best_times
from navlib import attitude, sensors, trajectory, units
from navlib.filters import zupt, zupt_ins
from navlib.imu import ImuSamples

LLA0 = [units.deg(30.55), units.deg(114.30), 20.0]
DT = 0.01


def _static_imu(n):
    traj = trajectory.static(n * DT, DT, LLA0, [0.3, 0.0, 0.0])
    w, f = trajectory.ideal_imu(traj)
    model = sensors.imu_model("MPU-6050").replace(gyro={"bias": units.deg_per_s(0.05)}, accel={"bias": units.mg(10)})
    imu = sensors.simulate_imu(w, f, DT, model, np.random.default_rng(4))
    return imu.w_ib_b, imu.f_b, traj.q_bn[0]


def error_state_filter(quick: bool):
    """Strapdown step + 15-state predict every sample, ZUPT/ZARU update at 10 Hz (always static); goal 5x filterpy (issue 38)."""
    n = 30_000 if quick else 300_000
    w, f, q0 = _static_imu(n)
    static = np.ones(n, dtype=bool)
    try:
        from filterpy.kalman import KalmanFilter
    except ImportError:
        KalmanFilter = None
    m = 5_000
    C = attitude.quat_to_dcm(q0)
    F = np.eye(15) + DT * zupt.error_state_matrix(C, f[0])
    H = zupt.zupt_zaru_matrix(C, np.zeros(3))
    Q, R = 1e-6 * np.eye(15), np.diag([1e-4] * 3 + [3e-6] * 3)

    start = zupt_ins.Start(LLA0, q0)

    def navlib_run():  # validation and screening included, as a user calls it
        zupt_ins.run_filter(ImuSamples(w, f, DT), start, static)

    def filterpy_loop():
        # The same linear algebra per step (predict every step, update every 10th); the
        # mechanisation is left out, which favours filterpy.
        kf = KalmanFilter(dim_x=15, dim_z=6)
        kf.F, kf.Q, kf.H, kf.R, kf.P = F, Q, H, R, np.eye(15)
        for k in range(m):
            kf.predict()
            if k % 10 == 9:
                kf.update(np.zeros(6))

    t_nav, t_fp = best_times(navlib_run, filterpy_loop if KalmanFilter else None)
    rows = [
        Result(
            "15-state error-state INS step",
            "navlib.filters.zupt_ins (numba)",
            n / t_nav,
            "steps/s",
            t_nav,
            note="strapdown + predict each step, 6-component update every 10th",
        )
    ]
    if t_fp is not None:
        rows[0].goal = 5 * m / t_fp
        rows[0].note = "goal: ≥ 5× filterpy, this run; " + rows[0].note
        rows.append(
            Result(
                "15-state error-state INS step",
                "filterpy (KF only, no INS)",
                m / t_fp,
                "steps/s",
                t_fp * n / m,
                note=f"timed on {m} steps",
            )
        )
    return rows


CASES = [error_state_filter]
