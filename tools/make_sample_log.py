#!/usr/bin/env python3
"""Write data/samples/: SIMULATED phone and board logs in the exact layouts of real exports.

The README's "Your own data" example runs on each of them (tests/test_readme.py). Nothing in them is real:
a phone lying face up on a desk at 51.5 deg N, still for 3 s, turned 90 deg clockwise by hand over 3 s
while tilted up to 15 deg, still for 4 s; MPU-6050-class IMU at 100 Hz and HMC5983-class magnetometer at
50 Hz (navlib's presets), seed 2026. Layouts (awesome-sensor-logger UNITS.md, CROSSPLATFORM.md):

* ``sensor-logger/``: Android export: ``Metadata.csv``, ``Gyroscope.csv``, ``TotalAcceleration.csv`` (m/s^2 with
  gravity), ``Magnetometer.csv``, ``Orientation.csv`` (quaternion phone -> ENU); columns ``time`` (ns since the
  epoch), ``seconds_elapsed``, ``z``, ``y``, ``x``.
* ``sensor-logger-ios/``: iOS export: ``Accelerometer.csv`` (gravity removed) + ``Gravity.csv``, both with the
  iOS signs (minus specific force), ``Magnetometer.csv``, ``Orientation.csv`` (quaternion phone ->
  north-west-up).
* ``sensor-logger-ios-nomag/``: iOS export without magnetometer, accelerometer only as
  ``AccelerometerUncalibrated.csv`` (g, iOS signs).
* ``board.csv``: a generic logger table: ``t_ms``, gyro in deg/s, accelerometer in g, magnetometer in uT, from a
  board mounted front-left-up (body right = -y), its magnetometer's z axis reversed (a mirrored mount).

Usage: python tools/make_sample_log.py   (rewrites data/samples/; byte-identical for the same navlib)
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from navlib import attitude, earth, sensors, trajectory, units

OUT = Path(__file__).resolve().parents[1] / "data" / "samples"
T0_NS = 1_764_151_200_000_000_000  # 2025-11-26 10:00:00 UTC
DT = 0.01
LLA0 = np.array([units.deg(51.5), units.deg(-0.1), 20.0])
HEADING0 = units.deg(20.0)
M_ENU_NWU = np.array([[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])  # ENU vector -> NWU vector


def phone_turned_on_a_desk():
    t = np.arange(0.0, 10.0 + DT / 2, DT)
    ramp = trajectory.smooth_ramp(np.clip((t - 3.0) / 3.0, 0.0, 1.0))
    tilt = units.deg(15.0) * np.sin(np.pi * ramp)
    hpr = np.stack([HEADING0 + units.deg(90.0) * ramp, tilt, -0.5 * tilt], -1)
    return trajectory.from_profiles(t, LLA0, hpr, np.zeros((t.size, 3)))


def write(folder: Path, name: str, t: np.ndarray, x: np.ndarray) -> None:
    ns = T0_NS + np.round(t * 1e9).astype(np.int64)
    df = pd.DataFrame({"time": ns, "seconds_elapsed": np.round(t, 6), "z": x[:, 2], "y": x[:, 1], "x": x[:, 0]})
    df.to_csv(folder / name, index=False, float_format="%.7g")


def write_orientation(folder: Path, t: np.ndarray, q: np.ndarray) -> None:
    """Sensor Logger's Orientation.csv columns, in the app's order (Euler columns left at 0: unused)."""
    ns = T0_NS + np.round(t * 1e9).astype(np.int64)
    df = pd.DataFrame(
        {
            "time": ns,
            "seconds_elapsed": np.round(t, 6),
            "yaw": 0.0,
            "qx": q[:, 1],
            "qz": q[:, 3],
            "roll": 0.0,
            "qw": q[:, 0],
            "qy": q[:, 2],
            "pitch": 0.0,
        }
    )
    df.to_csv(folder / "Orientation.csv", index=False, float_format="%.9g")


def write_metadata(folder: Path, platform: str, sensors_: str) -> None:
    pd.DataFrame(
        [
            {
                "version": 3,
                "device name": "simulated",
                "recording time": "2025-11-26_10-00-00",
                "platform": platform,
                "appVersion": "1.28",
                "device id": "simulated",
                "sensors": sensors_,
                "sampleRateMs": "10",
            }
        ]
    ).to_csv(folder / "Metadata.csv", index=False)


def main() -> None:
    rng_imu, rng_mag = (np.random.default_rng(s) for s in np.random.SeedSequence(2026).spawn(2))
    traj = phone_turned_on_a_desk()
    w, f = trajectory.ideal_imu(traj)
    imu = sensors.simulate_imu(w, f, DT, sensors.imu_model("MPU-6050"), rng_imu)
    B_n = earth.magnetic_field(units.to_deg(LLA0[0]), units.to_deg(LLA0[1]), LLA0[2], 2025.9)
    mag = sensors.simulate_magnetometer(traj.q_bn[1::2], B_n, sensors.MagnetometerModel(noise=0.3), rng_mag)
    t, t_mag, q = traj.time[1:], traj.time[1::2] + 0.004, traj.q_bn[1:]
    gravity = attitude.quat_rotate(attitude.quat_conj(q), [0.0, 0.0, units.G0])  # what a phone calls gravity

    android = OUT / "sensor-logger"
    android.mkdir(parents=True, exist_ok=True)
    write_metadata(android, "android", "Gyroscope|TotalAcceleration|Magnetometer|Orientation")
    write(android, "Gyroscope.csv", t, imu.w_ib_b)
    write(android, "TotalAcceleration.csv", t + 0.002, imu.f_b)
    write(android, "Magnetometer.csv", t_mag, mag.m_b)
    write_orientation(android, t, q)

    ios = OUT / "sensor-logger-ios"
    ios.mkdir(exist_ok=True)
    write_metadata(ios, "ios", "Accelerometer|Gravity|Gyroscope|Orientation|Magnetometer")
    write(ios, "Gyroscope.csv", t, imu.w_ib_b)
    write(ios, "Accelerometer.csv", t, -(imu.f_b - gravity))
    write(ios, "Gravity.csv", t, -gravity)
    write(ios, "Magnetometer.csv", t_mag, mag.m_b)
    write_orientation(ios, t, attitude.dcm_to_quat(M_ENU_NWU @ attitude.quat_to_dcm(q)))

    ios_nomag = OUT / "sensor-logger-ios-nomag"
    ios_nomag.mkdir(exist_ok=True)
    write_metadata(ios_nomag, "ios", "Gyroscope|AccelerometerUncalibrated")
    write(ios_nomag, "Gyroscope.csv", t, imu.w_ib_b)
    write(ios_nomag, "AccelerometerUncalibrated.csv", t, -imu.f_b / units.G0)

    C_sb = attitude.mount_matrix("-y,x,z").T  # body -> board axes (board x forward, y left)
    m_board = np.full((t.size, 3), np.nan)
    m_board[1::2] = mag.m_b[: t[1::2].size] @ C_sb.T * [1.0, 1.0, -1.0]
    board = pd.DataFrame({"t_ms": np.round(1000 * t, 3)})
    for name, x in (("gyro", np.rad2deg(imu.w_ib_b @ C_sb.T)), ("acc", imu.f_b @ C_sb.T / units.G0), ("mag", m_board)):
        for i, a in enumerate("xyz"):
            board[f"{name}_{a}"] = x[:, i]
    board.to_csv(OUT / "board.csv", index=False, float_format="%.7g")
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
