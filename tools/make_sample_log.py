#!/usr/bin/env python3
"""Write data/samples/sensor-logger/: a SIMULATED phone log in the Sensor Logger app's CSV export layout.

The README's "Your own data" example reads it with ``navlib.io.read_sensor_logger``. Nothing in it is
real: a phone lying face up on a desk, still for 3 s, turned 90 deg clockwise by hand over 3 s, still
for 4 s; MPU-6050-class IMU at 100 Hz and HMC5983-class magnetometer at 50 Hz (navlib's presets),
seed 2026. The layout follows the app's documentation: one file per sensor, columns ``time`` (ns since
the epoch), ``seconds_elapsed``, ``z``, ``y``, ``x``; rad/s, m/s^2 with gravity (``TotalAcceleration``), uT.

Usage: python tools/make_sample_log.py   (rewrites the folder; byte-identical for the same navlib)
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from navlib import earth, sensors, trajectory, units

OUT = Path(__file__).resolve().parents[1] / "data" / "samples" / "sensor-logger"
T0_NS = 1_764_151_200_000_000_000           # 2025-11-26 10:00:00 UTC
DT = 0.01
LLA0 = np.array([units.deg(51.5), units.deg(-0.1), 20.0])
HEADING0 = units.deg(20.0)


def phone_turned_on_a_desk():
    t = np.arange(0.0, 10.0 + DT / 2, DT)
    turn = units.deg(90.0) * trajectory.smooth_ramp(np.clip((t - 3.0) / 3.0, 0.0, 1.0))
    hpr = np.stack([HEADING0 + turn, np.zeros_like(t), np.zeros_like(t)], -1)
    return trajectory.from_profiles(t, LLA0, hpr, np.zeros((t.size, 3)))


def write(name: str, t: np.ndarray, x: np.ndarray) -> None:
    ns = T0_NS + np.round(t * 1e9).astype(np.int64)
    df = pd.DataFrame({"time": ns, "seconds_elapsed": np.round(t, 6),
                       "z": x[:, 2], "y": x[:, 1], "x": x[:, 0]})
    df.to_csv(OUT / name, index=False, float_format="%.7g")


def main() -> None:
    rng_imu, rng_mag = (np.random.default_rng(s) for s in np.random.SeedSequence(2026).spawn(2))
    traj = phone_turned_on_a_desk()
    w, f = trajectory.ideal_imu(traj)
    imu = sensors.simulate_imu(w, f, DT, sensors.imu_model("MPU-6050"), rng_imu)
    B_n = earth.magnetic_field(units.to_deg(LLA0[0]), units.to_deg(LLA0[1]), LLA0[2], 2025.9)
    mag = sensors.simulate_magnetometer(traj.q_bn[1::2], B_n, sensors.MagnetometerModel(noise=0.3), rng_mag)
    OUT.mkdir(parents=True, exist_ok=True)
    write("Gyroscope.csv", traj.time[1:], imu.w_ib_b)
    write("TotalAcceleration.csv", traj.time[1:] + 0.002, imu.f_b)
    write("Magnetometer.csv", traj.time[1::2] + 0.004, mag.m_b)
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
