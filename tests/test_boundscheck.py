"""The compiled Kalman and strapdown primitives stay inside their arrays (numba bounds checking on).

numba does not check indices by default: a kernel that reads past an array's end returns
garbage instead of failing. This test runs :mod:`navlib._kernels`' ``kalman_predict``,
``kalman_update`` and ``nav_step``, and their validated public wrappers ``kalman.predict``,
``kalman.update`` and ``strapdown.nav_step``, on valid inputs -- also m = 0 measurement rows,
all-NaN and partly NaN measurements, wrapped angles and a rejecting gate --, the 15-state covariance
prediction ``zupt.error_state_predict_into`` and the compiled Gauss-Krüger series (forward, inverse,
convergence; scalars, n-D and blocked arrays) in a subprocess with ``NUMBA_BOUNDSCHECK=1``, where an
out-of-bounds index raises ``IndexError``. A separate ``NUMBA_CACHE_DIR`` (``build/numba-boundscheck``,
holding bounds-checked builds only, so later runs reuse them) keeps the cached builds compiled without
bounds checks out of it. The same for the attitude filters, whose fixed-size Kalman steps index
small scratch matrices by hand (:func:`navlib._kernels.spd_solve_into`, the quaternion KF's update with 3 and 6
rows, the stuck-run screening).
"""

import os
import subprocess
import sys
from pathlib import Path

SCRIPT = r"""
import numpy as np
from navlib import _kernels, kalman, strapdown

rng = np.random.default_rng(5)
for n in (1, 3, 15):
    A = rng.standard_normal((n, n))
    x, P, F, Q = rng.standard_normal(n), A @ A.T + np.eye(n), np.eye(n) + 0.1 * A, 0.01 * np.eye(n)
    for predict in (_kernels.kalman_predict, kalman.predict):
        xp, Pp = predict(x, P, F, Q)
        assert xp.shape == (n,) and Pp.shape == (n, n)
    for m in (0, 1, 2, 6):
        H = rng.standard_normal((m, n))
        B = rng.standard_normal((m, m))
        R = B @ B.T + np.eye(m)
        h = H @ x
        mask = np.arange(m) % 2 == 0
        z_full = h + rng.standard_normal(m)
        z_part = np.where(np.arange(m) % 2 == 1, np.nan, z_full)
        for z in (z_full, z_part, np.full(m, np.nan), h + 1e3):
            for gate in (np.inf, 9.0):
                for update in (_kernels.kalman_update, kalman.update):
                    xu, Pu, y, nis, status = update(x, P, z, h, H, R, mask, gate)
                    assert xu.shape == (n,) and Pu.shape == (n, n) and y.shape == (m,)
                    assert status in (kalman.ACCEPTED, kalman.NO_DATA, kalman.REJECTED)
                    if not np.isfinite(z).any():
                        assert status == kalman.NO_DATA

c = strapdown.earth_constants()
for step in (_kernels.nav_step, strapdown.nav_step):
    for hold in (False, True):
        lla, vel, q = np.array([0.5, 0.2, 30.0]), np.array([1.0, 2.0, 0.1]), np.array([0.9, 0.1, 0.2, 0.3])
        q /= np.linalg.norm(q)
        for k in range(5):
            step(lla, vel, q, np.array([0.01, -0.02, 0.3]), np.array([0.1, 0.2, 9.8]), 0.01, c, hold)
        assert np.all(np.isfinite(lla)) and np.all(np.isfinite(vel)) and np.all(np.isfinite(q))

from navlib import _geodesy, earth, geodesy
for n in ((), (3, 4), (2 * _geodesy.CHUNK + 5,)):           # scalars, n-D, blocks with a partial last one
    lat, lon = np.full(n, 26.06), np.full(n, 121.3)
    x, y = geodesy.geodetic2gk(lat, lon, zone=40, ellipsoid=earth.CGCS2000, deg=True)
    la, lo = geodesy.gk2geodetic(x, y, zone=40, ellipsoid=earth.CGCS2000, deg=True)
    assert np.abs(la - lat).max() < 1e-9 and np.abs(lo - lon).max() < 1e-9
    assert np.all(np.isfinite(geodesy.convergence(lat, lon, zone=40, deg=True)))

from navlib.filters import zupt
P15 = np.eye(15)
zupt.error_state_predict_into(P15, np.eye(3) * 0.01, np.array([0.0, 0.0, 0.098]), 0.01, np.full(15, 1e-8),
                              np.empty((15, 15)))
assert np.all(np.isfinite(P15))

# The primitives are unvalidated: bounds checking is on, so an empty gyro sample is caught here.
try:
    _kernels.nav_step(np.zeros(3), np.zeros(3), np.array([1.0, 0, 0, 0]), np.zeros(0), np.zeros(3), 0.01, c)
except IndexError:
    print("ok")
"""


BOUNDS_CACHE = Path(__file__).resolve().parents[1] / "build" / "numba-boundscheck"


def _run_bounds_checked(script, timeout):
    """Run ``script`` in a subprocess with bounds checking on and its own numba cache; it must print ok."""
    env = dict(os.environ, NUMBA_BOUNDSCHECK="1", NUMBA_CACHE_DIR=str(BOUNDS_CACHE))
    env.pop("NUMBA_DISABLE_JIT", None)
    out = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True, text=True, timeout=timeout)
    assert out.returncode == 0, out.stderr[-3000:]
    assert out.stdout.strip() == "ok", "bounds checking was not active: " + out.stdout + out.stderr[-2000:]


def test_kernels_stay_in_bounds():
    _run_bounds_checked(SCRIPT, timeout=300)


ATTITUDE = r"""
import numpy as np
from navlib import _kernels, earth, robust
from navlib.filters import mahony as mh, quaternion_kf as qkf
from navlib.filters.observations import RtkHeading
from navlib.imu import ImuSamples, SensorLimits

rng = np.random.default_rng(7)
for n in range(1, 10):
    A = rng.standard_normal((n, n))
    assert _kernels.spd_solve_into(A @ A.T + np.eye(n), rng.standard_normal((n, 2)))
B = earth.magnetic_field(32.0, 118.8, 0.0, 2022.5)
N = 300
w = 0.01 * rng.standard_normal((2, N, 3)); w[0, 5] = np.nan; w[1, 20:40, 1] = w[1, 19, 1]
f = np.array([0.1, 0.2, 9.8]) + 0.05 * rng.standard_normal((2, N, 3)); f[0, 50:60] = np.nan
m = B + 0.5 * rng.standard_normal((2, N, 3)); m[1, 70:90] = np.nan
dt = np.full(N, 0.01); dt[200] = 1.0
valid = np.zeros(N, dtype=bool); valid[::10] = True
q0 = [1.0, 0.0, 0.0, 0.0]
for filt in (mh.mahony, qkf.quaternion_kf):
    filt(ImuSamples(w, f, dt, SensorLimits(full_scale_gyro=0.03)), q0, m_b=m, B_n=B)
    filt(ImuSamples(w, f, dt), q0, rtk=RtkHeading(np.full(N, 0.5), valid, gate=0.3))
    filt(ImuSamples(w, f, dt), q0)
qkf.quaternion_kf(ImuSamples(w, f, 0.01), q0, m_b=m, B_n=B, keep_cov=True, linear_innovation=True)
robust.stuck_mask(w, 5)
try:                                            # bounds checking is on: a right-hand side too short for S is caught
    _kernels.spd_solve_into(np.eye(3), np.zeros((2, 1)))
except IndexError:
    print("ok")
"""


def test_attitude_kernels_stay_in_bounds():
    _run_bounds_checked(ATTITUDE, timeout=600)
