"""navlib.io on the layouts people record: Sensor Logger (iOS and Android, every accelerometer file, older
column names, Orientation.csv), phyphox, x-IMU and NGIMU; per-sensor axes; the axis check on flipped copies of
a real recording; the averaging resampler; align's default for a bursty sensor.

Files are written here with the headers, units and signs the apps and vendors publish (awesome-sensor-logger
UNITS.md / CROSSPLATFORM.md / COORDINATES.md; phyphox's CSV export; x-io's x-IMU GUI), filled with
navlib-simulated samples whose true values are known.
"""

import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from navlib import attitude, io, trajectory, units

G = units.G0
LLA0 = np.array([units.deg(45.0), units.deg(7.0), 100.0])
T0 = 1_700_000_000_000_000_000
FUSION = Path(__file__).resolve().parents[1] / "data/real/xio-fusion/sensor_data.csv"
M_NWU_ENU = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])


@pytest.fixture(scope="module")
def phone():
    """A phone turned about its z axis, tilted: true gyro, specific force, field and attitude at 100 Hz."""
    traj = trajectory.reciprocating_rotation(6.0, 0.01, LLA0, units.deg([30.0, 5.0, -3.0]), [0, 0, 1], units.deg(40), 2.0)
    w, f = trajectory.ideal_imu(traj)
    m_b = attitude.quat_rotate(attitude.quat_conj(traj.q_bn[1:]), [0.0, 20.0, -40.0])
    return traj.time[1:], w, f, m_b, traj.q_bn[1:]


def write_logger(d, name, t, x, header=("z", "y", "x")):
    d.mkdir(exist_ok=True)
    df = pd.DataFrame({"time": T0 + np.round(t * 1e9).astype(np.int64), "seconds_elapsed": t})
    for h in header:  # the app writes z, y, x in that order
        df[h] = x[:, "xyz".index(h[0].lower() if len(h) == 1 else h.split()[-2].lower())]
    df.to_csv(d / name, index=False, float_format="%.17g")


def write_metadata(d, platform, standardisation=None):
    cols = {
        "version": 3,
        "device name": "phone",
        "recording time": "2025-01-01_10-00-00",
        "platform": platform,
        "appVersion": "1.28",
        "device id": "x",
        "sensors": "Accelerometer|Gravity|Gyroscope",
        "sampleRateMs": "10",
    }
    if standardisation is not None:
        cols["standardisation"] = standardisation
    pd.DataFrame([cols]).to_csv(d / "Metadata.csv", index=False)


def write_orientation(d, t, q):
    df = pd.DataFrame(
        {
            "time": T0 + np.round(t * 1e9).astype(np.int64),
            "seconds_elapsed": t,
            "yaw": 0.0,
            "qx": q[:, 1],
            "qz": q[:, 3],
            "roll": 0.0,
            "qw": q[:, 0],
            "qy": q[:, 2],
            "pitch": 0.0,
        }
    )
    df.to_csv(d / "Orientation.csv", index=False, float_format="%.17g")


def same_attitude(q1, q2):
    return np.abs(np.sum(q1 * q2, -1))  # |cos(angle / 2)|: 1 when equal up to sign


def test_sensor_logger_ios_accelerometer_plus_gravity(tmp_path, phone):
    """iOS: gravity-free acceleration + gravity, both with reversed signs; the field as is; Orientation.csv's
    quaternion maps the phone to north-west-up (true north)."""
    t, w, f, m, q = phone
    d = tmp_path / "ios"
    write_logger(d, "Gyroscope.csv", t, w)
    write_logger(d, "Gravity.csv", t, -0.9 * f)
    write_logger(d, "Accelerometer.csv", t, -0.1 * f)
    write_logger(d, "Magnetometer.csv", t, m)
    write_metadata(d, "ios")
    q_nwu = attitude.dcm_to_quat(M_NWU_ENU.T @ attitude.quat_to_dcm(q))
    write_orientation(d, t, q_nwu)
    rec = io.read_sensor_logger(d)
    np.testing.assert_allclose(rec.f_b, f, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(rec.w_ib_b, w, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(rec.m_b, m, rtol=1e-12)
    assert np.min(same_attitude(rec.q_bn_ref, q)) > 1 - 1e-12
    assert any("iOS sign convention" in c for c in rec.conversions)
    assert any("true north" in c for c in rec.conversions)


def test_sensor_logger_ios_uncalibrated_in_g_and_standardised(tmp_path, phone):
    t, w, f, m, q = phone
    d = tmp_path / "ios"
    write_logger(d, "Gyroscope.csv", t, w)
    write_logger(d, "AccelerometerUncalibrated.csv", t, -f / G)
    write_metadata(d, "ios")
    np.testing.assert_allclose(io.read_sensor_logger(d).f_b, f, rtol=1e-12)
    write_logger(d, "AccelerometerUncalibrated.csv", t, f)  # "Standardise Units & Frames": Android's
    write_metadata(d, "ios", "true")
    rec = io.read_sensor_logger(d)
    np.testing.assert_allclose(rec.f_b, f, rtol=1e-12)
    assert any("standardised" in c for c in rec.conversions)


def test_sensor_logger_android_orientation_and_older_layouts(tmp_path, phone):
    """Android: TotalAcceleration.csv, or (older app) Accelerometer.csv + Gravity.csv with upper-case column
    names carrying units; Orientation.csv's quaternion is already phone -> ENU (magnetic north)."""
    t, w, f, m, q = phone
    d = tmp_path / "android"
    write_logger(d, "Gyroscope.csv", t, w, header=("GYROSCOPE Z (rad/s)", "GYROSCOPE Y (rad/s)", "GYROSCOPE X (rad/s)"))
    write_logger(d, "Accelerometer.csv", t, 0.2 * f, header=[f"ACCELEROMETER {a} (m/s²)" for a in "ZYX"])
    write_logger(d, "Gravity.csv", t, 0.8 * f, header=[f"GRAVITY {a} (m/s²)" for a in "ZYX"])
    write_orientation(d, t, q)
    with pytest.raises(ValueError, match="no Metadata.csv.*platform='ios' or platform='android'"):
        io.read_sensor_logger(d)
    rec = io.read_sensor_logger(d, platform="android")
    np.testing.assert_allclose(rec.f_b, f, rtol=1e-12)
    assert rec.m_b is None and "not in the export: magnetometer, barometer" in str(rec)
    assert np.min(same_attitude(rec.q_bn_ref, q)) > 1 - 1e-12
    write_logger(d, "TotalAcceleration.csv", t, f)
    (d / "Orientation.csv").unlink()
    rec = io.read_sensor_logger(d)  # only Android writes TotalAcceleration.csv
    assert any("GUESSED" in c for c in rec.conversions) and rec.q_bn_ref is None
    write_metadata(d, "ios")
    with pytest.raises(ValueError, match="platform: 'android' given, but .*Metadata.csv says 'ios'"):
        io.read_sensor_logger(d, platform="android")


def test_sensor_logger_reference_follows_the_axes_mapping(tmp_path, phone):
    t, w, f, m, q = phone
    d = tmp_path / "a"
    write_logger(d, "Gyroscope.csv", t, w)
    write_logger(d, "TotalAcceleration.csv", t, f)
    write_metadata(d, "android")
    write_orientation(d, t, q)
    rec = io.read_sensor_logger(d, axes="-y,x,z")  # body right = phone -y: turned 90 deg
    C_bs = attitude.mount_matrix("-y,x,z")
    expected = attitude.dcm_to_quat(attitude.quat_to_dcm(q) @ C_bs.T)
    assert np.min(same_attitude(rec.q_bn_ref, expected)) > 1 - 1e-12
    np.testing.assert_allclose(rec.f_b, f @ C_bs.T, rtol=1e-12)


def test_phyphox_folder_and_single_file(tmp_path, phone):
    t, w, f, m, _ = phone
    d = tmp_path / "phyphox"
    d.mkdir()
    for name, x, label, unit in (
        ("Gyroscope.csv", w, "Gyroscope", "rad/s"),
        ("Accelerometer.csv", f, "Acceleration", "m/s^2"),
        ("Magnetometer.csv", m, "Magnetic field", "µT"),
    ):
        df = pd.DataFrame({"Time (s)": t} | {f"{label} {a} ({unit})": x[:, i] for i, a in enumerate("xyz")})
        df.to_csv(d / name, index=False, float_format="%.10E")
    rec = io.read_phyphox(d)
    np.testing.assert_allclose(rec.w_ib_b, w, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(rec.f_b, f, rtol=1e-9)
    np.testing.assert_allclose(rec.m_b, m, rtol=1e-9)
    lin = pd.DataFrame({"Time (s)": t} | {f"Linear Acceleration {a} (m/s^2)": f[:, i] for i, a in enumerate("xyz")})
    lin.to_csv(tmp_path / "Raw Data.csv", index=False)
    with pytest.raises(ValueError, match="gravity removed.*Acceleration with g"):
        io.read_phyphox(tmp_path / "Raw Data.csv")


def write_ximu(path, w, f, m_gauss, packets, header="Packet number"):
    df = pd.DataFrame({header: packets})
    for name, x, unit in (("Gyroscope", np.rad2deg(w), "deg/s"), ("Accelerometer", f / G, "g"), ("Magnetometer", m_gauss, "G")):
        for i, a in enumerate("XYZ"):
            df[f"{name} {a} ({unit})"] = x[:, i]
    df.to_csv(path, index=False, float_format="%.17g")


def test_ximu_rows_give_time_and_gauss_is_converted(tmp_path, phone):
    """x-IMU: no time column; 'Packet number' counts every packet the board sends (here inertial rows are
    every second or third packet, as in x-io's published walks), so time is the row number over the rate."""
    t, w, f, m, _ = phone
    packets = 3 + np.cumsum(np.random.default_rng(34).choice([2, 3], t.size))
    write_ximu(tmp_path / "walk_CalInertialAndMag.csv", w, f, m / 100.0, packets)
    with pytest.raises(ValueError, match="rate: .*Packet number.*rate=256"):
        io.read_xio(tmp_path / "walk_CalInertialAndMag.csv")
    rec = io.read_xio(tmp_path / "walk_CalInertialAndMag.csv", rate=100.0)
    np.testing.assert_allclose(rec.time, np.arange(t.size) / 100.0, atol=1e-12)
    np.testing.assert_allclose(rec.m_b, m, rtol=1e-12)
    np.testing.assert_allclose(rec.w_ib_b, w, rtol=1e-12, atol=1e-15)
    assert "row number / rate 100 Hz" in str(rec) and "median 100 Hz" in str(rec)


def test_ngimu_barometer_and_rate_refused(tmp_path, phone):
    t, w, f, _, _ = phone
    df = pd.DataFrame({"Time (s)": t})
    for name, x, unit in (("Gyroscope", np.rad2deg(w), "deg/s"), ("Accelerometer", f / G, "g")):
        for i, a in enumerate("XYZ"):
            df[f"{name} {a} ({unit})"] = x[:, i]
    df["Barometer (hPa)"] = 1013.25
    df.to_csv(tmp_path / "sensors.csv", index=False, float_format="%.17g")
    rec = io.read_xio(tmp_path / "sensors.csv")
    np.testing.assert_allclose(rec.pressure, 101325.0)
    with pytest.raises(ValueError, match="rate: .*own time column"):
        io.read_xio(tmp_path / "sensors.csv", rate=100.0)


def test_per_sensor_axes_and_explicit_mirror(phone):
    t, w, f, m, _ = phone
    df = pd.DataFrame(
        {"t": t}
        | {f"g{a}": w[:, i] for i, a in enumerate("xyz")}
        | {f"a{a}": f[:, i] for i, a in enumerate("xyz")}
        | {f"m{a}": m[:, i] for i, a in enumerate("xyz")}
    )
    kw = dict(
        time="t",
        units={"gyro": "rad/s", "accel": "m/s^2", "mag": "uT"},
        gyro=("gx", "gy", "gz"),
        accel=("ax", "ay", "az"),
        mag=("mx", "my", "mz"),
    )
    with pytest.raises(ValueError, match=r"axes\['mag'\]: .*mirror image.*mirror=True"):
        io.from_dataframe(df, axes={"mag": "x,y,-z"}, **kw)
    rec = io.from_dataframe(df, axes={"accel": "-y,x,z", "mag": "x,y,-z"}, mirror=True, **kw)
    np.testing.assert_allclose(rec.w_ib_b, w)
    np.testing.assert_allclose(rec.f_b, np.stack([-f[:, 1], f[:, 0], f[:, 2]], -1))
    np.testing.assert_allclose(rec.m_b, m * [1, 1, -1])
    assert "a mirror image, mirror=True" in str(rec)
    with pytest.raises(ValueError, match="axes: unknown sensors"):
        io.from_dataframe(df, axes={"baro": "x,y,z"}, **kw)


# ---------------------------------------------------------------------- axis check on a real recording


def fusion(**kw):
    return io.read_xio(FUSION, timing="sanitize", check="off", **kw)


def test_axis_check_passes_the_real_recording_as_read():
    result = io.check_axes(fusion())
    assert result.suspect is None and result.ranking[0][0] == "as read"
    assert result.turn > np.deg2rad(90)


@pytest.mark.parametrize("sensor", ["gyro", "accel", "mag"])
@pytest.mark.parametrize("axis", "xyz")
def test_axis_check_names_each_flipped_axis_of_a_real_recording(sensor, axis):
    rec = fusion(axes={sensor: ",".join(("-" if a == axis else "") + a for a in "xyz")}, mirror=True)
    with pytest.warns(UserWarning, match=f"the {sensor}'s {axis} axis looks flipped.*mirror=True"):
        result = io.check_axes(rec)
    assert result.suspect == f"{sensor} {axis}"
    with pytest.raises(ValueError, match="looks flipped"):
        io.check_axes(rec, on_fail="raise")


def test_readers_run_the_axis_check_by_default(tmp_path):
    raw = pd.read_csv(FUSION)
    raw["Accelerometer Y (g)"] *= -1
    raw.to_csv(tmp_path / "flipped.csv", index=False)
    with pytest.warns(UserWarning, match="accel's y axis looks flipped"):
        rec = io.read_xio(tmp_path / "flipped.csv", timing="sanitize")
    assert any(c.startswith("axis check: the accel's y axis") for c in rec.conversions)


def test_axis_check_is_inconclusive_without_turning(phone):
    t, w, f, m, _ = phone
    still = io.Recording(t, w * 0.0, np.tile(f[0], (t.size, 1)))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        result = io.check_axes(still)
    assert result.suspect is None and result.message.startswith("inconclusive")


# ---------------------------------------------------------------------- clocks


def test_averaging_resampler_keeps_the_white_noise_density():
    """White noise of a 400-Hz sensor delivered in bursts (four stamps 0.5 ms apart, then an 8.5-ms pause, with
    0.1 ms jitter: a median rate of 2000 Hz) resampled to 50 Hz: the mean keeps sigma^2 * dt within 5 %,
    interpolation does not (it keeps the per-sample variance, so the density grows with the interval)."""
    rng = np.random.default_rng(34)
    dt = np.tile([0.0005, 0.0005, 0.0005, 0.0085], 50_000) + rng.uniform(-1e-4, 1e-4, 200_000)
    t = np.cumsum(dt) - dt[0]
    sigma = 0.01
    x = sigma * rng.standard_normal((t.size, 3))
    rec = io.Recording(t, x, x.copy())
    density = sigma**2 * np.mean(np.diff(t))
    out = io.resample(rec, 50.0)
    measured = np.nanvar(out.w_ib_b, axis=0) / 50.0
    np.testing.assert_allclose(measured, density, rtol=0.05)
    interpolated = np.nanvar(io.resample(rec, 50.0, method="interpolate").w_ib_b, axis=0) / 50.0
    assert np.all(interpolated > 3 * density)
    assert "mean over each interval" in str(out)


def test_align_default_keeps_a_bursty_sensors_samples():
    """Readings in bursts of five 2-ms steps then a 40-ms pause: the median interval (2 ms) would drop most of
    the IMU samples as stale; the default (1.5 x the 99th-percentile interval) bridges the pauses and still
    leaves a real dropout (0.5 s) as NaN."""
    steps = np.tile([0.002, 0.002, 0.002, 0.002, 0.040], 40)
    steps[100] = 0.5
    ts = np.cumsum(steps)
    tt = np.arange(ts[0], ts[-1], 0.01)
    x = io.align(tt, ts, np.arange(ts.size, dtype=float))
    lost = np.isnan(x)
    in_dropout = (tt > ts[99]) & (tt < ts[100])
    assert np.all(lost == (in_dropout & (tt - ts[99] > 1.5 * 0.040 + 1e-12))) and lost.any()
    assert np.isnan(io.align(tt, ts, np.arange(ts.size, dtype=float), max_gap=0.003)).mean() > 0.5


def test_recording_prints_its_timing():
    t = np.concatenate([np.arange(0, 1, 0.01), 1.5 + np.arange(0, 1, 0.01)])
    text = str(io.Recording(t, np.zeros((t.size, 3))))
    assert "median 100 Hz" in text and "largest gap 510 ms at 0.990 s" in text and "99th-percentile" in text
