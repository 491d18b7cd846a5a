"""The compiled kernels run unchanged as plain Python (NUMBA_DISABLE_JIT=1).

The kernels are written once, as readable numeric Python compiled by numba; a
teacher or a debugger can step through them uncompiled. This test runs the
same computations in a subprocess with the JIT disabled and compares.
"""

import numpy as np
from helpers import run_json_script

SCRIPT = r"""
import json, numpy as np
from numba import njit
from navlib import _kernels, earth, geodesy, kalman, strapdown, trajectory, units
traj = trajectory.vehicle([trajectory.Segment(2.0, speed=5.0, turn=0.3), trajectory.Segment(2.0, speed=0.0)],
                          0.05, [units.deg(30.0), 0.0, 10.0], 0.2)
w, f = trajectory.ideal_imu(traj)
nav = strapdown.integrate(traj.lla[0], traj.vel_n[0], traj.q_bn[0], w + 1e-3, f, traj.dt)
q = strapdown.integrate_attitude(traj.q_bn[0], w, traj.dt)
x, P, y, nis, status = kalman.update(np.zeros(2), np.eye(2), np.array([0.5, np.nan]), np.zeros(2),
                                     np.eye(2), 0.1 * np.eye(2), np.array([False, False]))
lat, lon = np.linspace(-80.0, 80.0, 9), np.linspace(118.5, 121.5, 9)
gk = geodesy.geodetic2gk(lat, lon, zone=40, ellipsoid=earth.CGCS2000, deg=True)
gk_back = geodesy.gk2geodetic(*gk, zone=40, ellipsoid=earth.CGCS2000, deg=True)
gamma_k = (geodesy.convergence(lat, lon, zone=40, deg=True), geodesy.scale_factor(lat, lon, zone=40, deg=True))
fused = njit(lambda a, b, c: _kernels.fma(a, b, c))(1 + 2.0 ** -30, 1 - 2.0 ** -30, -1.0)
print(json.dumps({"lla": nav.lla.tolist(), "q": q.tolist(), "x": x.tolist(), "status": int(status),
                  "gk": np.array([gk, gk_back, gamma_k]).tolist(), "fma": fused}))
"""


def _run(disable_jit: bool) -> dict:
    return run_json_script(SCRIPT, disable_jit)


def test_kernels_run_uncompiled_with_the_same_results():
    jit, plain = _run(False), _run(True)
    np.testing.assert_allclose(plain["lla"], jit["lla"], rtol=0, atol=1e-9)
    np.testing.assert_allclose(plain["q"], jit["q"], rtol=0, atol=1e-12)
    np.testing.assert_allclose(plain["x"], jit["x"], rtol=0, atol=1e-15)
    assert plain["status"] == jit["status"] == 1
    np.testing.assert_array_equal(plain["gk"], jit["gk"])  # the GK series, bit for bit
    assert plain["fma"] == jit["fma"] == -(2.0**-60)  # one rounding: a * b + c would give 0
