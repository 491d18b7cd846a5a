"""Notebook 02's chapter helpers in navlib.papers.rotation_bias: the experiment driver and the redrawn Figs. 3-4.

They are kept out of the module's ``__all__`` (they serve the notebook); tested here: figures drawn without
error, bad input named, the driver's output shapes, its determinism and its refusals.
"""

import matplotlib

matplotlib.use("Agg")
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from navlib import attitude, earth, sensors, trajectory, units  # noqa: E402
from navlib.papers import rotation_bias  # noqa: E402

DT = 0.01
LAT = units.deg(40.0)
EY = np.array([0.0, 1.0, 0.0])


def rig(duration=30.0, period=5.0, rotation_time=0.5, pitch_deg=30.0):
    hpr0 = units.deg([0.0, pitch_deg, 0.0])
    traj = trajectory.reciprocating_rotation(duration, DT, [LAT, 0, 0], hpr0, EY, np.pi / 2, period, rotation_time)
    w, f = trajectory.ideal_imu(traj)
    starts, length = rotation_bias.dwell_windows(w.shape[0], DT, period, rotation_time)
    w_ie_b = earth.earth_rate_b(attitude.euler_to_dcm(rotation_bias.dwell_attitudes(hpr0, EY, np.pi / 2, starts.size)), LAT)
    return rotation_bias.Rig(traj, w, f, starts, length, w_ie_b)


@pytest.mark.parametrize("alpha, pitch", [(90.0, 30.0), (30.0, 0.0), (180.0, -60.0)])
def test_rotation_scheme_draws(ax, alpha, pitch):
    rotation_bias.draw_rotation_scheme(ax, alpha, pitch)
    assert len(ax.lines) >= 6 and ax.texts  # two frames, their verticals and labels
    assert not ax.axison


@pytest.mark.parametrize(
    "kwargs, name",
    [
        ({"amplitude_deg": 0.0}, "amplitude_deg"),
        ({"amplitude_deg": 190.0}, "amplitude_deg"),
        ({"amplitude_deg": np.nan}, "amplitude_deg"),
        ({"pitch_deg": 90.0}, "pitch_deg"),
        ({"pitch_deg": "30"}, "pitch_deg"),
    ],
)
def test_rotation_scheme_names_bad_input(ax, kwargs, name):
    with pytest.raises((ValueError, TypeError), match=f"^{name}"):
        rotation_bias.draw_rotation_scheme(ax, **kwargs)


def test_rotation_scheme_needs_axes():
    with pytest.raises(ValueError, match="^ax"):
        rotation_bias.draw_rotation_scheme(object())


def test_schedule_draws_the_dwells(ax):
    r = rig(duration=15.0)
    traj, starts, length = r.traj, r.starts, r.length
    angle = units.to_deg(rotation_bias.rotation_angle(attitude.quat_to_dcm(traj.q_bn)))
    rotation_bias.draw_rotation_schedule(ax, traj.time, angle, starts, length, DT)
    assert len(ax.patches) == starts.size  # one shaded window per dwell
    np.testing.assert_allclose(angle[[0, -1]], [0.0, 90.0], atol=1e-9)  # 3 periods: still, turned, still, turning
    with pytest.raises(ValueError, match="^angle_deg"):
        rotation_bias.draw_rotation_schedule(ax, traj.time, angle[:-1], starts, length, DT)
    with pytest.raises(ValueError, match="^dt"):
        rotation_bias.draw_rotation_schedule(ax, traj.time, angle, starts, length, 0.0)


def test_rotation_angle_of_known_turns():
    C = np.stack([rotation_bias.rodrigues(EY, a) for a in (0.0, 0.3, np.pi / 2, np.pi)])
    np.testing.assert_allclose(rotation_bias.rotation_angle(C), [0.0, 0.3, np.pi / 2, np.pi], atol=1e-7)
    with pytest.raises(ValueError, match="^C_bn"):
        rotation_bias.rotation_angle(np.eye(3))


def test_flow_chart_draws(ax):
    rotation_bias.draw_flow(ax)
    assert len(ax.patches) == 7 and len(ax.texts) >= 7
    with pytest.raises(ValueError, match="^ax"):
        rotation_bias.draw_flow("not an axes")


def test_rig_experiment_shapes_and_determinism():
    model = sensors.imu_model("MTi-100")
    args = (rig(), DT, LAT, model)
    kw = dict(n_runs=2, period=5.0, memory=60.0)
    a = rotation_bias.rig_experiment(*args, np.random.default_rng(1), extensions=True, **kw)
    b = rotation_bias.rig_experiment(*args, np.random.default_rng(1), extensions=True, **kw)
    assert set(a["stats"]) == {"uncorrected", "corrected", "Kalman", "no rotation", "paper uncorrected", "paper corrected"}
    for case, st in a["stats"].items():
        assert {k: v.shape for k, v in st.items()} == {"max": (2, 3), "mean": (2, 3), "final": (2, 3)}, case
        np.testing.assert_array_equal(st["max"], b["stats"][case]["max"])
    assert a["b_lsq"].shape == (2, a["t_est"].size, 3) and a["heading_err"]["corrected"].shape == (2, a["time"].size)
    assert a["faults"]["dwell", "refused"] == 0 and a["kf_faults"]["dwell", "nan"] == 0


@pytest.mark.parametrize(
    "change, name",
    [
        ({"n_runs": 0}, "n_runs"),
        ({"period": -5.0}, "period"),
        ({"memory": 0.0}, "memory"),
        ({"decimate": 0}, "decimate"),
        ({"extensions": 1}, "extensions"),
    ],
)
def test_rig_experiment_names_bad_input(change, name):
    kw = {"n_runs": 1, "period": 5.0, "memory": 60.0, **change}
    with pytest.raises(ValueError, match=f"^{name}"):
        rotation_bias.rig_experiment(rig(duration=10.0), DT, LAT, sensors.imu_model("MTi-100"), np.random.default_rng(0), **kw)


def test_rig_experiment_refuses_a_static_case_it_cannot_build():
    model = sensors.imu_model("MTi-100").replace(gyro={"scale_factor": 1e-3})
    with pytest.raises(ValueError, match="^model"):
        rotation_bias.rig_experiment(
            rig(duration=10.0), DT, LAT, model, np.random.default_rng(0), n_runs=1, period=5.0, memory=60.0, extensions=True
        )
    with pytest.raises((ValueError, TypeError), match="^rng"):
        rotation_bias.rig_experiment(rig(duration=10.0), DT, LAT, model, 0, n_runs=1, period=5.0, memory=60.0)


def white_mti():
    return sensors.imu_model("MTi-100").replace(
        gyro={"bias": 0.0, "bias_instability": 0.0}, accel={"bias": 0.0, "bias_instability": 0.0}
    )


def test_pair_spread_follows_the_cramer_rao_bound():
    hpr0 = units.deg([0.0, 30.0, 0.0])
    model = white_mti()
    spread = rotation_bias.pair_spread(
        hpr0, EY, np.pi / 2, 5.0, 0.5, DT, LAT, model, np.zeros(3), np.random.default_rng(3), n_runs=10, duration=120.0
    )
    crb = rotation_bias.design(hpr0, EY, np.pi / 2, 4.5, DT, model.gyro.noise_density, model.accel.noise_density)[1]
    np.testing.assert_allclose(spread, np.sqrt(np.diag(crb)), rtol=0.25)  # 120 pairs: about 6.5 % sd, a 4-sd margin


def test_pair_spread_is_nan_where_the_bias_is_unobservable():
    model, rng = white_mti(), np.random.default_rng(0)
    vertical = [0.0, np.cos(np.pi / 3), np.sin(np.pi / 3)]  # θ0 = 30°: this axis is vertical
    kw = dict(n_runs=1, duration=20.0)
    assert np.isnan(
        rotation_bias.pair_spread(units.deg([0, 30, 0]), vertical, np.pi / 2, 5.0, 0.5, DT, LAT, model, np.zeros(3), rng, **kw)
    ).all()
    assert np.isnan(
        rotation_bias.pair_spread([0, 0, 0], [1.0, 0, 0], np.pi / 2, 5.0, 0.5, DT, LAT, model, np.zeros(3), rng, **kw)
    ).all()  # pitch driven to 90°
    with pytest.raises(ValueError, match="^duration"):
        rotation_bias.pair_spread(
            units.deg([0, 30, 0]), EY, np.pi / 2, 5.0, 0.5, DT, LAT, model, np.zeros(3), rng, n_runs=1, duration=12.0
        )
    with pytest.raises((ValueError, TypeError), match="^rng"):
        rotation_bias.pair_spread(units.deg([0, 30, 0]), EY, np.pi / 2, 5.0, 0.5, DT, LAT, model, np.zeros(3), 1, **kw)
