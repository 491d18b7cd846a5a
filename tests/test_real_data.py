"""The committed real recordings (data/real/): checksums, readers, and every filter on each of them."""

import hashlib
from pathlib import Path

import numpy as np
import pytest

from navlib import alignment, io
from navlib.filters import mahony, zupt

REAL = Path(__file__).resolve().parents[1] / "data" / "real"
SUMS = dict(reversed(line.split()) for line in (REAL / "SHA256SUMS").read_text().splitlines())
WALKS = ["xio-gait-tracking/short_walk.csv", "xio-gait-tracking/long_walk.csv"]


@pytest.mark.parametrize("name", sorted(SUMS))
def test_checksum_and_licence(name):
    path = REAL / name
    assert hashlib.sha256(path.read_bytes()).hexdigest() == SUMS[name]
    licence = next(path.parent.glob("LICENSE*")).read_text()
    assert "MIT License" in licence or "Creative Commons Attribution 4.0" in licence
    assert name.split("/")[-1] in (REAL / "README.md").read_text()


@pytest.fixture(scope="module")
def fusion():
    return io.read_xio(REAL / "xio-fusion/sensor_data.csv")


def test_fusion_recording_reads_in_si(fusion):
    assert fusion.n == 13514 and fusion.time[-1] == pytest.approx(135.33, abs=0.01)
    still = fusion.time < 10.0
    assert np.linalg.norm(fusion.f_b[still].mean(0)) == pytest.approx(9.8, abs=0.15)  # specific force, m/s^2
    assert 25 < np.median(np.linalg.norm(fusion.m_b, axis=1)) < 65  # Earth's field, uT


def test_mahony_runs_on_the_real_marg_recording(fusion):
    still = fusion.time < 10.0
    q0 = alignment.initial_attitude(fusion.f_b[still].mean(0), fusion.m_b[still].mean(0))
    res = mahony.mahony(fusion.imu(), q0=q0, m_b=fusion.m_b)
    assert np.all(np.isfinite(res.q_bn))
    np.testing.assert_allclose(np.linalg.norm(res.q_bn, axis=-1), 1.0, atol=1e-12)


@pytest.mark.parametrize("name", WALKS)
def test_walks_read_and_detect_stance(name):
    rec = io.read_xio(REAL / name, timing="sanitize")
    assert rec.timing.n_duplicate > 0 and 395 < 1 / np.median(np.diff(rec.time)) < 401
    static = zupt.detect_static(rec.imu(), window=0.05)
    assert 0.2 < static.mean() < 0.9  # the foot stands still for part of every stride...
    assert static[rec.time < 10].mean() > 0.95  # ...and the subject stands still for the first 10 s


# ------------------------------------------------------------ every filter on every recording (regression inputs)


def still_start(rec, seconds=10.0):
    return rec.time < seconds


def test_attitude_filters_on_the_marg_recording(fusion):
    import imufusion

    from navlib import attitude
    from navlib.filters import observations, quaternion_kf

    st = still_start(fusion)
    q0 = alignment.initial_attitude(fusion.f_b[st].mean(0), fusion.m_b[st].mean(0))
    B_ref = attitude.quat_to_dcm(q0) @ fusion.m_b[st].mean(0)
    gates = observations.AttitudeGates(mag=observations.MagGate())
    runs = {
        "mag": mahony.mahony(fusion.imu(), q0=q0, m_b=fusion.m_b),
        "gated": mahony.mahony(fusion.imu(), q0=q0, m_b=fusion.m_b, B_n=B_ref, gates=gates),
        "none": mahony.mahony(fusion.imu(), q0=q0),
        "qkf": quaternion_kf.quaternion_kf(fusion.imu(), q0=q0, m_b=fusion.m_b, B_n=B_ref, gates=gates),
    }
    for res in runs.values():
        assert np.all(np.isfinite(res.q_bn))
        np.testing.assert_allclose(np.linalg.norm(res.q_bn, axis=-1), 1.0, atol=1e-12)
    assert np.all(np.linalg.eigvalsh(runs["qkf"].P) > -1e-15)  # covariance stays PSD
    ahrs = imufusion.Ahrs()
    settings = imufusion.AhrsSettings()
    settings.convention = imufusion.CONVENTION_ENU
    ahrs.set_settings(settings)
    q_xio = np.empty((fusion.n, 4))
    for k, (w, f, m, dt) in enumerate(zip(np.rad2deg(fusion.w_ib_b), fusion.f_b / 9.80665, fusion.m_b, fusion.dt, strict=True)):
        ahrs.set_sample_period(dt)
        ahrs.update(w, f, m)
        q_xio[k] = ahrs.get_quaternion()
    window = st & (fusion.time > 3.0)
    for name in ("gated", "qkf"):
        d = attitude.wrap_pi(attitude.quat_to_euler(runs[name].q_bn)[window, 0] - attitude.quat_to_euler(q_xio)[window, 0])
        assert np.degrees(np.sqrt(np.mean(d**2))) < 1.0  # notebook 06: 0.13 and 0.07 deg
    assert runs["gated"].faults["mag", "outlier"] > 1000  # the disturbance is gated


@pytest.mark.parametrize("name, bound", [("short", 0.01), ("long", 0.02)])
def test_zupt_filter_closes_the_real_walks(name, bound):
    from navlib import attitude, geodesy
    from navlib.filters import zupt_ins

    rec = io.read_xio(REAL / f"xio-gait-tracking/{name}_walk.csv", timing="sanitize")
    stance = zupt.detect_static(rec.imu(), window=0.05, thresholds=(0.15, 0.2, 0.3))  # notebook 06's choice
    st = rec.time < 5.0
    pitch, roll = alignment.level(rec.f_b[st].mean(0))
    cfg = zupt_ins.FilterConfig(
        process=zupt_ins.ProcessNoise(gyro=np.deg2rad(0.02)), gates=zupt_ins.Gates(zupt=np.inf), update_rate=400.0
    )
    lla0 = [np.deg2rad(51.5), 0.0, 0.0]
    start = zupt_ins.Start(lla0, attitude.euler_to_quat([0.0, pitch, roll]), gyro_bias=rec.w_ib_b[st].mean(0))
    res = zupt_ins.run_filter(rec.imu(), start, stance, aiding=zupt_ins.Aiding("none"), config=cfg)
    assert np.all(np.isfinite(res.nav.lla)) and np.all(res.P_diag >= 0)
    e, n, _ = geodesy.geodetic2enu(*res.nav.lla[-1], *lla0)
    loop = {"short": 25.0, "long": 60.0}[name]  # the source's "about" lengths
    assert np.hypot(e, n) < bound * loop  # notebook 06: 0.23 % and 1.6 %


def test_multi_position_accelerometer_calibration_on_the_real_log():
    import pandas as pd

    from navlib import analysis, calibration

    raw = pd.read_csv(REAL / "mikoff-imu-calib/imu0.log", sep=" ", header=None, names=["ax", "ay", "az", "wx", "wy", "wz"])
    rec = io.from_dataframe(
        raw.assign(t=np.arange(len(raw)) / 100.0),
        time="t",
        units={"gyro": "rad/s", "accel": "m/s^2"},
        gyro=("wx", "wy", "wz"),
        accel=("ax", "ay", "az"),
    )
    still = zupt.detect_static(rec.imu(), window=1.0, gyro_bias=np.median(rec.w_ib_b, 0), thresholds=(np.deg2rad(0.5), 0.1, 1.0))
    f_means = np.array([rec.f_b[a:b].mean(0) for a, b in zip(*analysis.segments(still), strict=True) if b - a >= 200])
    assert len(f_means) == 15
    cal = calibration.fit_accelerometer(f_means)
    raw_err = np.linalg.norm(f_means, axis=1) - 9.80665
    fit_err = np.linalg.norm(cal.apply(f_means), axis=1) - 9.80665
    assert np.sqrt(np.mean(raw_err**2)) > 10 * np.sqrt(np.mean(fit_err**2))  # 0.22 -> 0.012 m/s^2
