"""The study behind navlib.filters.presets' Mahony gains: prints every number its docstring quotes.

Mean total orientation error (deg) of navlib.filters.mahony over a grid of kp, ki and accelerometer gate:
* hand-held: BROAD's committed trials (optical reference), grid on the even-numbered (tuning) trials, reported on
  the odd-numbered (held-out) ones, 6D and 9D, with and without the gyro bias removed over the first still second;
* vehicle: a simulated drive (trajectory.vehicle, MPU-6050 and ADIS16475 models, seeds 0-4 of SeedSequence 77;
  inclination error, bias removed over the first 10 s at rest or not) and comma2k19's real highway minute (6D,
  started from the reference attitude: the drive has no still start).

Usage: python tools/preset_study.py  (about 5 minutes on one core)
"""

from __future__ import annotations

import dataclasses
import itertools

import numpy as np

from navlib import alignment, analysis, datasets, earth, sensors, trajectory, units
from navlib.filters import mahony
from navlib.filters.observations import AttitudeGates
from navlib.imu import ImuSamples
from navlib.repro import root

KP = (0.01, 0.03, 0.1, 0.3, 1.0, 2.0)
KI = (0.0, 0.002, 0.02)
ACCEL_TOL = (None, 0.05, 0.1, 0.2)


def total_error(q, q_ref, mask, **kw) -> np.ndarray:
    e = analysis.orientation_errors(q, q_ref, mask, **kw)
    return np.rad2deg([e.total, e.heading, e.inclination])


def hand_held() -> None:
    trials = {p.stem: datasets.read_broad(p) for p in sorted((root() / "data" / "real" / "broad").glob("*.npz"))}
    tuning, held_out = datasets.broad_split(list(trials))
    print(f"BROAD: tuning {tuning}, held out {held_out}")
    print("mode  bias-at-rest  kp     ki     accel_tol  tuning  held-out   (mean total error, deg)")
    for mag, rest in itertools.product((False, True), (False, True)):
        for kp, ki, tol in itertools.product(KP, KI if mag else (0.0,), ACCEL_TOL):
            err = {}
            for name, t in trials.items():
                first = slice(0, int(t.rate))
                r = t.recording
                q0 = alignment.initial_attitude(r.f_b[first].mean(0), r.m_b[first].mean(0))
                imu = t.imu
                if rest:
                    imu = dataclasses.replace(imu, w_ib_b=imu.w_ib_b - r.w_ib_b[first].mean(0))
                gates = AttitudeGates(accel_tol=tol)
                q = mahony.mahony(imu, q0, m_b=t.m_b if mag else None, kp=kp, ki=ki, gates=gates).q_bn
                err[name] = total_error(q, t.q_ref, t.movement)[0]
            print(
                f"{'9D' if mag else '6D'}    {rest!s:12}  {kp:<5}  {ki:<5}  {tol!s:9}  "
                f"{np.mean([err[n] for n in tuning]):6.2f}  {np.mean([err[n] for n in held_out]):6.2f}"
            )


def simulated_drive(rate: float = 100.0) -> trajectory.Trajectory:
    deg, S = units.deg, trajectory.Segment
    bump = [S(0.4, pitch=deg(3.0)), S(0.4, pitch=deg(-3.0)), S(0.4, pitch=0.0)]
    segments = [
        S(30.0, speed=0.0),
        S(10.0, speed=8.0),
        S(20.0),
        S(6.0, turn=deg(90)),
        S(30.0),
        S(6.0, turn=deg(90)),
        S(40.0, roll=deg(2.0)),
        S(6.0, turn=deg(-90)),
        S(30.0, roll=0.0),
        S(6.0, turn=deg(90)),
        S(46.0),
        S(20.0, pitch=deg(2.0)),
        S(20.0, pitch=0.0),
        *bump,
        S(30.0, turn=deg(45)),
        S(40.0, roll=deg(-2.0)),
        S(10.0, turn=deg(90), roll=0.0),
        S(60.0),
        *bump,
        S(20.0, turn=deg(-60)),
        S(50.0, pitch=deg(-2.0)),
        S(30.0, pitch=0.0),
        S(10.0, turn=deg(120)),
        S(60.0, roll=deg(1.5)),
        *bump,
        S(40.0, roll=0.0),
        S(20.0, turn=deg(-45)),
        S(25.6, speed=14.0),
        S(10.0, speed=0.0),
    ]
    return trajectory.vehicle(segments, 1.0 / rate, [deg(32.03), deg(118.85), 20.0], heading0=deg(30.0))


def vehicle() -> None:
    drive = simulated_drive()
    w_ideal, f_ideal = trajectory.ideal_imu(drive)
    q_truth, t = drive.q_bn[1:], drive.time[1:]
    B_n = earth.magnetic_field(32.03, 118.85, 20.0, year=2022.5)
    still, moving = t < 10.0, t > 30.0
    print(f"\nsimulated drive: {t[-1]:.0f} s; mean inclination error (deg) over seeds 0-4 while moving")
    print("device       mode  bias-at-rest  kp     ki     inclination")
    for device in ("MPU-6050", "ADIS16475-1"):
        runs = {}
        for seed in range(5):
            r_imu, r_mag = (np.random.default_rng(s) for s in np.random.SeedSequence([77, seed]).spawn(2))
            imu = sensors.simulate_imu(w_ideal, f_ideal, drive.dt, sensors.imu_model(device), r_imu)
            mag = sensors.MagnetometerModel(noise=0.5, hard_iron=0.4, soft_iron=0.01)
            m_b = sensors.simulate_magnetometer(q_truth, B_n, mag, r_mag).m_b
            q0 = alignment.initial_attitude(imu.f_b[still].mean(0), m_b[still].mean(0))
            for rest in (False, True):
                w = imu.w_ib_b - (imu.w_ib_b[still].mean(0) if rest else 0.0)
                for mag_on in (False, True):
                    for kp, ki in itertools.product(KP, KI if mag_on else (0.0,)):
                        samples = ImuSamples(w, imu.f_b, drive.dt)
                        q = mahony.mahony(samples, q0, m_b=m_b if mag_on else None, kp=kp, ki=ki).q_bn
                        runs.setdefault((mag_on, rest, kp, ki), []).append(total_error(q, q_truth, moving)[2])
        for (mag_on, rest, kp, ki), e in runs.items():
            print(f"{device:12} {'9D' if mag_on else '6D'}    {rest!s:12}  {kp:<5}  {ki:<5}  {np.mean(e):6.2f}")


def real_drive() -> None:
    car = datasets.read_comma2k19(root() / "data" / "real" / "comma2k19").attitude_trial()
    print("\ncomma2k19 highway minute, 6D, from the reference attitude: total / heading / inclination (deg)")
    for kp in KP:
        q = mahony.mahony(car.imu, car.q_ref[0], kp=kp, ki=0.0).q_bn
        print(f"kp {kp:<5}  " + " / ".join(f"{x:.2f}" for x in total_error(q, car.q_ref, car.movement)))


if __name__ == "__main__":
    hand_held()
    vehicle()
    real_drive()
