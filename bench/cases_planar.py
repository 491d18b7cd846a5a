"""Paper 002 cases: Gauss–Krüger projection vs pyproj, the 5-state EKF step vs filterpy."""

from __future__ import annotations

import numpy as np

from bench.run import Result, best_time, best_times
from navlib.earth import CGCS2000
from navlib.filters import planar_ekf
from navlib.geodesy import geodetic2gk
from navlib.papers import gauss_kruger_ekf as planar


def gauss_kruger(quick: bool):
    """Forward GK (CGCS2000, 3° zone 40) of random points in the zone at 0-70° N; goal 5x pyproj (issue 38)."""
    n = 100_000 if quick else 1_000_000
    rng = np.random.default_rng(10)
    lat, lon = rng.uniform(0.0, 70.0, n), rng.uniform(118.5, 121.5, n)

    def navlib_run():
        geodetic2gk(lat, lon, zone=40, ellipsoid=CGCS2000, deg=True)

    try:
        import pyproj

        proj = pyproj.Proj("+proj=tmerc +ellps=GRS80 +lon_0=120 +k=1 +x_0=0 +y_0=0 +units=m")
    except ImportError:
        proj = None
    t_nav, t_proj = best_times(navlib_run, None if proj is None else lambda: proj.transform(lon, lat))
    rows = [Result("Gauss-Kruger forward, 3° zone", "navlib.geodesy (numba series)", n / t_nav, "points/s", t_nav)]
    if t_proj is not None:
        rows[0].goal = 5 * n / t_proj
        rows[0].note = "goal: ≥ 5× pyproj, this run"
        rows.append(Result("Gauss-Kruger forward, 3° zone", "pyproj (PROJ tmerc)", n / t_proj, "points/s", t_proj))
    return rows


def _filterpy_ekf(t, z, x0, Q, R):
    """The same EKF with filterpy's ExtendedKalmanFilter (nonlinear f, Jacobian, wrapped heading)."""
    from filterpy.kalman import ExtendedKalmanFilter

    class Unicycle(ExtendedKalmanFilter):
        def predict_x(self, u=0):
            self.x = planar_ekf.motion_model(self.x, self.T)

    kf = Unicycle(dim_x=5, dim_z=5)
    kf.x, kf.P, kf.Q, kf.R = x0.copy(), np.eye(5), Q, R

    def residual(a, b):
        y = a - b
        y[2] = (y[2] + np.pi) % (2 * np.pi) - np.pi
        return y

    eye = np.eye(5)
    for k in range(1, len(t)):
        kf.T = t[k] - t[k - 1]
        kf.F = planar_ekf.jacobian(kf.x, kf.T)
        kf.predict()
        kf.update(z[k], lambda x: eye, lambda x: x, residual=residual)
    return kf.x


def ekf_step(quick: bool):
    """The paper's 5-state EKF (Eqs. 13-18), one predict + update per step; goal 0.5 M/s and 10x filterpy."""
    n = 100_000 if quick else 1_000_000
    T = 0.5
    truth = planar_ekf.propagate([0.0, 0.0, np.pi / 4, 1.0, np.deg2rad(5)], T, n - 1)
    rng = np.random.default_rng(11)
    z = truth + rng.standard_normal(truth.shape) * np.sqrt(np.diag(planar.R_PAPER))
    t = np.arange(n) * T
    x0 = truth[0]
    config = planar_ekf.EkfConfig(planar.Q_PAPER, planar.R_PAPER, np.eye(5))
    t_nav = best_time(lambda: planar_ekf.filter_grid(t, z, x0, config))
    rows = [
        Result(
            "EKF step, 5 states (paper 002)",
            "navlib.filters.planar_ekf (numba)",
            n / t_nav,
            "steps/s",
            t_nav,
            goal=5e5,
            note="goal 0.5 M/s and 10x filterpy",
        )
    ]
    try:
        import filterpy  # noqa: F401
    except ImportError:
        return rows
    m = 5_000 if quick else 20_000
    t_fp = best_time(lambda: _filterpy_ekf(t[:m], z[:m], x0, planar.Q_PAPER, planar.R_PAPER), repeat=1)
    rows[0].goal = max(5e5, 10 * m / t_fp)
    rows.append(
        Result(
            "EKF step, 5 states (paper 002)",
            "filterpy ExtendedKalmanFilter",
            m / t_fp,
            "steps/s",
            t_fp * n / m,
            note=f"timed on {m} steps, scaled",
        )
    )
    return rows


CASES = [gauss_kruger, ekf_step]
