"""Run by tests/test_install.py with the Python of a fresh venv holding a non-editable navlib.

Uses only the installed package (the working directory is outside the checkout): the core API,
the sensor presets shipped as package data, one filter, and repro's refusal to write beside the
installed package. Prints one line per step; exits non-zero on any failure.
"""

import sys
from pathlib import Path

import numpy as np

import navlib
from navlib import attitude, earth, repro, sensors, strapdown, trajectory
from navlib.filters import mahony as mh
from navlib.imu import ImuSamples

here = Path.cwd()
pkg = Path(navlib.__file__).resolve().parent
assert "site-packages" in pkg.parts, f"navlib imported from {pkg}, not from the venv"
print("navlib", navlib.__version__, "from", pkg)

assert "MTi-100" in sensors.devices(), sensors.devices()
model = sensors.imu_model("MTi-100")
print("imu_model('MTi-100') gyro noise density", model.gyro.noise_density, "rad/s/sqrt(Hz)")

lla0 = [np.deg2rad(40.0), np.deg2rad(116.0), 50.0]
traj = trajectory.static(20.0, 0.01, lla0, [0.3, 0.0, 0.0])
w_ib_b, f_b = trajectory.ideal_imu(traj)
imu = sensors.simulate_imu(w_ib_b, f_b, 0.01, model, np.random.default_rng(1))
print("simulated", imu.w_ib_b.shape[0], "static samples; |f| =", float(np.linalg.norm(imu.f_b, axis=-1).mean()))

B_n = earth.magnetic_field(40.0, 116.0, 50.0, 2024.0)
m_b = np.einsum("nji,j->ni", attitude.quat_to_dcm(traj.q_bn[1:]), B_n)  # one per IMU interval
res = mh.mahony(ImuSamples(imu.w_ib_b, imu.f_b, 0.01), traj.q_bn[0], m_b=m_b, B_n=B_n)
declination = np.arctan2(B_n[0], B_n[1])  # the filter's heading is magnetic
heading_err = np.rad2deg(attitude.wrap_pi(attitude.quat_to_euler(res.q_bn[-1])[0] + declination - 0.3))
print(f"mahony magnetic heading error after 20 s: {heading_err:.3f} deg")
assert abs(heading_err) < 1.0

q = strapdown.integrate_attitude(traj.q_bn[0], imu.w_ib_b, 0.01)
assert np.all(np.isfinite(q))

try:
    repro.setup("smoke")
except repro.NoOutputDirectory as exc:
    print("repro outside a checkout:", exc)
else:
    sys.exit("repro.setup wrote beside the installed package")
assert not (pkg.parent / "build").exists() and not any(here.iterdir()), "something was written"
print("ok")
