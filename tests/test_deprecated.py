"""navlib's module attributes: submodules load on first use; the old paper modules are deprecated aliases
for one release (every old name resolves, and they warn)."""
from __future__ import annotations

import importlib
import subprocess
import sys

import numpy as np
import pytest

import navlib

OLD = {"northfinding": "north_finding", "gyrobias": "rotation_bias", "planar": "gauss_kruger_ekf",
       "ahrs": "mimu_mag_rtk", "pedestrian": "pedestrian_ins"}


@pytest.mark.parametrize("old", sorted(OLD))
def test_alias_warns_and_resolves_every_old_name(old):
    sys.modules.pop(f"navlib.{old}", None)
    with pytest.warns(DeprecationWarning, match=f"navlib.{old} is deprecated.*navlib.papers.{OLD[old]}"):
        module = importlib.import_module(f"navlib.{old}")
    missing = [name for name in module.__all__ if not hasattr(module, name)]
    assert not missing, f"navlib.{old} lost {missing}"
    companion = importlib.import_module(f"navlib.papers.{OLD[old]}")
    new_names = {"G_LOCAL", "FAULT_KEYS", "MAX_STEPS",    # names new to a companion need no alias
                 "printed_zone_number", "paper_radii", "printed_meridian_radius", "paper_series", "paper_meridian_arc",
                 "ClippedTheory", "clipped_single_axis_theory", "printed_eq2_arctan", "printed_eq6",
                 "printed_eq12_mahony", "dead_reckoning_error_ms", "ekf_error_ms",
                 # the chapters' schematics (issue 17)
                 "draw_device", "draw_candidate_pairs", "draw_rotation_scheme", "draw_rotation_schedule", "draw_flow",
                 "draw_zones", "draw_zone_grid", "draw_block_diagram", "draw_fusion_structure", "draw_system"}
    assert set(companion.__all__) <= set(module.__all__) | new_names


def test_attribute_access_on_the_package_warns():
    sys.modules.pop("navlib.ahrs", None)
    vars(navlib).pop("ahrs", None)                  # an earlier import binds the submodule on the package
    with pytest.warns(DeprecationWarning, match="navlib.ahrs is deprecated"):
        module = navlib.ahrs
    assert module.mahony is importlib.import_module("navlib.filters.mahony").mahony


def test_importing_navlib_does_not_warn():
    out = subprocess.run([sys.executable, "-W", "error::DeprecationWarning", "-c", "import navlib, navlib.papers"],
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stderr


def test_old_filter_grid_keeps_the_paper_noise_as_defaults():
    from navlib.filters import planar_ekf
    from navlib.papers import gauss_kruger_ekf
    t, z = np.arange(5.0), np.tile([0.0, 0.0, 0.3, 1.0, 0.0], (5, 1))
    sys.modules.pop("navlib.planar", None)
    with pytest.warns(DeprecationWarning):
        old = importlib.import_module("navlib.planar")
    new = planar_ekf.filter_grid(t, z, z[0], Q=gauss_kruger_ekf.Q_PAPER, R=gauss_kruger_ekf.R_PAPER)
    np.testing.assert_array_equal(old.filter_grid(t, z, z[0]).x, new.x)


def test_old_range_keywords_warn_and_mean_the_same():
    from navlib.filters import mahony, planar_ekf
    from navlib.papers import gauss_kruger_ekf
    w, f, m = np.zeros((20, 3)), np.tile([0.0, 0.0, 9.8], (20, 1)), np.tile([0.0, 20.0, -40.0], (20, 1))
    w[5, 2] = 0.5
    with pytest.warns(DeprecationWarning, match="gyro_range"):
        old = mahony.mahony(w, f, 0.01, [1.0, 0, 0, 0], m_b=m, gyro_range=0.4)
    new = mahony.mahony(w, f, 0.01, [1.0, 0, 0, 0], m_b=m, full_scale_gyro=0.4)
    assert old.counts == new.counts and new.counts["gyro_saturated"] == 1
    with pytest.raises(ValueError, match="^gyro_range: "), pytest.warns(DeprecationWarning):
        mahony.mahony(w, f, 0.01, [1.0, 0, 0, 0], m_b=m, gyro_range=0.4, full_scale_gyro=0.4)
    t, z = np.arange(5.0), np.tile([0.0, 0.0, 0.3, 1.0, 0.5], (5, 1))
    with pytest.warns(DeprecationWarning, match="yaw_rate_range"):
        old = planar_ekf.filter_grid(t, z, z[0], Q=gauss_kruger_ekf.Q_PAPER, R=gauss_kruger_ekf.R_PAPER, yaw_rate_range=0.5)
    assert old.n_saturated == 4


# ----------------------------------------------------------------------------- return types that changed with a flag

def _imu_with_dropouts():
    from navlib import trajectory
    traj = trajectory.static(1.0, 0.01, [0.5, 0.2, 10.0], [0.3, 0.1, 0.0])
    w, f = trajectory.ideal_imu(traj)
    w[[3, 50]], f[[3, 70]] = np.nan, np.nan
    return traj, w, f


def test_strapdown_on_nan_keeps_the_tuple_and_warns():
    from navlib import robust, strapdown
    traj, w, f = _imu_with_dropouts()
    args = (traj.lla[0], traj.vel_n[0], traj.q_bn[0], w, f, 0.01)
    new = strapdown.integrate(*args, nan_policy="hold")
    with pytest.warns(DeprecationWarning, match="on_nan is deprecated; use nan_policy=.*traj.faults.*navlib 0.3"):
        nav, held = strapdown.integrate(*args, on_nan="hold")
    np.testing.assert_array_equal(held, np.isnan(w).any(-1) | np.isnan(f).any(-1))
    np.testing.assert_array_equal(nav.lla, new.lla)
    with pytest.warns(DeprecationWarning, match="on_nan is deprecated"):
        nav = strapdown.integrate(*args[:3], w[:3], f[:3], 0.01, on_nan="raise")     # a Trajectory, as before
    assert len(nav) == 4
    q_new = strapdown.integrate_attitude(traj.q_bn[0], w, 0.01, nan_policy="hold")
    with pytest.warns(DeprecationWarning, match="on_nan is deprecated; use nan_policy=.*fault_report"):
        q, held = strapdown.integrate_attitude(traj.q_bn[0], w, 0.01, None, "hold")   # positional, as it was
    np.testing.assert_array_equal(q, q_new)
    np.testing.assert_array_equal(held, robust.fault_report(w, "gyro", flags=True).flags["gyro", "nan"])
    with pytest.raises(ValueError, match="^nan_policy, on_nan: "):
        strapdown.integrate(*args, nan_policy="hold", on_nan="hold")
    with pytest.raises(ValueError, match="^nan_policy, on_nan: "):
        strapdown.integrate_attitude(traj.q_bn[0], w, 0.01, on_nan="hold", nan_policy="hold")
    with pytest.raises(ValueError, match="^on_nan: "), pytest.warns(DeprecationWarning):
        strapdown.integrate_attitude(traj.q_bn[0], w, 0.01, on_nan="skip")


def test_integrate_euler_report_keeps_the_tuple_and_warns():
    from navlib import euler, robust
    w = np.tile([0.0, 0.3, 0.0], (200, 1))
    w[[10, 11, 40]] = np.nan
    w[100:105, 1] = 0.5
    new = euler.integrate_euler([0.0, 0.1, 0.0], w, 0.01, max_gap=0.1, full_scale_gyro=0.5)
    with pytest.warns(DeprecationWarning, match=r"report=.*deprecated.*robust.fault_report\(w_ib_b, \"gyro\""):
        hpr, rep = euler.integrate_euler([0.0, 0.1, 0.0], w, 0.01, max_gap=0.1, full_scale_gyro=0.5, report=True)
    assert isinstance(rep, euler.EulerReport)
    np.testing.assert_array_equal(hpr, new)
    counts = robust.fault_report(w, "gyro", full_scale=0.5, flags=True)
    assert rep.n_filled == counts["gyro", "nan"] == 3 and rep.n_saturated == counts["gyro", "saturated"] == 5
    assert rep.first_saturated == np.flatnonzero(counts.flags["gyro", "saturated"])[0] == 100
    with pytest.warns(DeprecationWarning, match="report="):
        out = euler.integrate_euler([0.0, 0.1, 0.0], w, 0.01, max_gap=0.1, report=False)
    np.testing.assert_array_equal(out, euler.integrate_euler([0.0, 0.1, 0.0], w, 0.01, max_gap=0.1))


def test_ins_heading_change_report_keeps_the_tuple_and_warns():
    from navlib import robust
    from navlib.papers import north_finding
    w = np.tile([0.0, 0.0, 0.01], (3, 300, 1))
    w[0, 20] = np.nan                       # held
    w[1, 50:80] = np.nan                    # 0.3 s gap: refused
    w[2, 200, 2] = 0.05                     # saturated: refused
    f0 = [0.0, 0.0, 9.8]
    new = north_finding.ins_heading_change(w, f0, 0.01, 0.5, full_scale_gyro=0.05)
    with pytest.warns(DeprecationWarning, match="report=.*deprecated.*NaN entries.*fault_report"):
        dpsi, rep = north_finding.ins_heading_change(w, f0, 0.01, 0.5, full_scale_gyro=0.05, report=True)
    assert isinstance(rep, north_finding.InsReport)
    np.testing.assert_array_equal(dpsi, new)
    np.testing.assert_array_equal(rep.refused, np.isnan(dpsi))
    np.testing.assert_array_equal(rep.refused, [False, True, True])
    counts = robust.fault_report(w, "gyro", full_scale=0.05)
    np.testing.assert_array_equal(rep.n_held, counts["gyro", "nan"])
    np.testing.assert_array_equal(rep.n_saturated, counts["gyro", "saturated"])
    np.testing.assert_allclose(rep.longest_gap, [0.01, 0.3, 0.0])


def test_submodules_load_on_first_use():
    """``import navlib`` loads no submodule; ``navlib.X`` and ``from navlib import X`` load X (and what it imports)."""
    code = ("import sys, navlib; assert not [m for m in sys.modules if m.startswith('navlib.')], sys.modules.keys(); "
            "from navlib import units; assert 'scipy.stats' not in sys.modules and 'numba' not in sys.modules; "
            "assert all(hasattr(navlib, name) for name in navlib.__all__); assert set(navlib.__all__) <= set(dir(navlib))")
    subprocess.run([sys.executable, "-c", code], check=True)
