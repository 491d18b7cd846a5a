"""navlib.io: readers put real logs into navlib's conventions (rad/s, m/s^2 specific force, uT, Pa, s, RFU).

Each reader is run on a small file written here in the source's exact layout (header lines as the
sources publish them), filled with navlib-simulated samples whose true values are known.
"""

import numpy as np
import pandas as pd
import pytest

from navlib import attitude, io, trajectory, units
from navlib.filters import mahony
from navlib.filters.observations import RtkHeading

G = units.G0
# A file written with 17 significant digits round-trips exactly through a correctly rounded parser (pandas 3),
# but pandas 2.2's default C parser ("high" precision) is not correctly rounded: relative errors up to 8e-13
# measured at pandas 2.2.2, the floor. 1e-12 bounds that and is far below any IMU's resolution.
PARSE_RTOL = 1e-12
LLA0 = np.array([units.deg(45.0), units.deg(7.0), 100.0])


@pytest.fixture
def motion():
    """Ideal IMU samples of a rotating static IMU at 100 Hz (known rates and specific force)."""
    traj = trajectory.reciprocating_rotation(6.0, 0.01, LLA0, units.deg([30.0, 5.0, -3.0]), [0, 0, 1], units.deg(40), 2.0)
    w, f = trajectory.ideal_imu(traj)
    return traj.time[1:], w, f


def write_xio(path, t, w, f, m=None):
    df = pd.DataFrame({"Time (s)": t})
    for i, a in enumerate("XYZ"):
        df[f"Gyroscope {a} (deg/s)"] = np.rad2deg(w[:, i])
    for i, a in enumerate("XYZ"):
        df[f"Accelerometer {a} (g)"] = f[:, i] / G
    if m is not None:
        for i, a in enumerate("XYZ"):
            df[f"Magnetometer {a} (uT)"] = m[:, i]
    df.to_csv(path, index=False, float_format="%.17g")


def test_xio_columns_are_converted_to_si(tmp_path, motion):
    t, w, f = motion
    m = np.tile([15.0, 20.0, -40.0], (t.size, 1))
    write_xio(tmp_path / "sensor_data.csv", t, w, f, m)
    rec = io.read_xio(tmp_path / "sensor_data.csv")
    np.testing.assert_allclose(rec.w_ib_b, w, rtol=PARSE_RTOL, atol=1e-18)
    np.testing.assert_allclose(rec.f_b, f, rtol=PARSE_RTOL)
    np.testing.assert_allclose(rec.m_b, m)
    np.testing.assert_allclose(rec.time, t - t[0], atol=1e-12)
    assert rec.start == pytest.approx(t[0])
    text = str(rec)
    assert "deg/s" in text and "rad/s" in text and "gyro, accel, mag" in text


def test_axes_mapping_rotates_every_vector_sensor(tmp_path, motion):
    t, w, f = motion
    write_xio(tmp_path / "a.csv", t, w, f)
    rec = io.read_xio(tmp_path / "a.csv", axes="-y,x,z")
    np.testing.assert_allclose(rec.w_ib_b, np.stack([-w[:, 1], w[:, 0], w[:, 2]], -1), rtol=PARSE_RTOL, atol=1e-18)
    np.testing.assert_allclose(rec.f_b, np.stack([-f[:, 1], f[:, 0], f[:, 2]], -1), rtol=PARSE_RTOL)


def test_recording_feeds_the_filters(tmp_path, motion):
    t, w, f = motion
    write_xio(tmp_path / "a.csv", t, w, f)
    rec = io.read_xio(tmp_path / "a.csv")
    imu = rec.imu()
    assert imu.n == t.size and np.allclose(imu.dt, 0.01)
    res = mahony.mahony(
        imu,
        q0=attitude.euler_to_quat(units.deg([30.0, 5.0, -3.0])),
        rtk=RtkHeading(np.full(t.size, units.deg(30.0)), np.zeros(t.size, bool)),
    )
    assert np.all(np.isfinite(res.q_bn))


def table(t, w, f):
    return pd.DataFrame({"t": t, "gx": w[:, 0], "gy": w[:, 1], "gz": w[:, 2], "ax": f[:, 0], "ay": f[:, 1], "az": f[:, 2]})


COLS = {"time": "t", "gyro": ("gx", "gy", "gz"), "accel": ("ax", "ay", "az")}


@pytest.mark.parametrize("time_unit, scale", [("s", 1.0), ("ms", 1e3), ("us", 1e6)])
def test_time_units(motion, time_unit, scale):
    t, w, f = motion
    rec = io.from_dataframe(table(t * scale, w, f), time_unit=time_unit, units={"gyro": "rad/s", "accel": "m/s^2"}, **COLS)
    np.testing.assert_allclose(rec.time, t - t[0], atol=1e-9)


def test_iso_timestamps(motion):
    t, w, f = motion
    stamps = pd.Timestamp("2026-11-26T10:00:00") + pd.to_timedelta(t, unit="s")
    df = table(t, w, f).assign(t=stamps.astype(str))
    rec = io.from_dataframe(df, time_unit="iso", units={"gyro": "rad/s", "accel": "m/s^2"}, **COLS)
    np.testing.assert_allclose(rec.time, t - t[0], atol=1e-6)


def test_repeated_and_out_of_order_times_are_counted(motion):
    t, w, f = motion
    df = table(t, w, f)
    df.loc[10, "t"] = df.loc[9, "t"]  # a repeat
    df = pd.concat([df, df.iloc[[5]]])  # a late, repeated sample
    kw = dict(units={"gyro": "rad/s", "accel": "m/s^2"}, **COLS)
    with pytest.raises(ValueError, match=r"time: 2 repeated and 1 out-of-order"):
        io.from_dataframe(df, **kw)
    rec = io.from_dataframe(df, timing="sanitize", **kw)
    assert rec.timing.n_duplicate == 2 and rec.n == t.size - 1
    assert any("2 repeated timestamps dropped" in c for c in rec.conversions)


@pytest.mark.parametrize(
    "change, message",
    [
        (dict(units={"gyro": "rad/s", "accel": "furlong"}), r"units\['accel'\]: unknown unit 'furlong'"),
        (dict(units={"gyro": "g", "accel": "m/s^2"}), r"units\['gyro'\]: unknown unit 'g' for the gyro"),
        (dict(units={"gyro": "rad/s"}), r"units: no unit given for the accel"),
        (dict(gyro=("gx", "gy", "wz")), r"columns: \['wz'\] not in the table"),
        (dict(time="time"), r"columns: \['time'\] not in the table"),
        (dict(axes="y,x,z"), r"axes: .* mirror"),
        (dict(timing="fix"), r"timing"),
    ],
)
def test_clear_errors(motion, change, message):
    t, w, f = motion
    kw = {**dict(units={"gyro": "rad/s", "accel": "m/s^2"}, **COLS), **change}
    with pytest.raises(ValueError, match=message):
        io.from_dataframe(table(t, w, f), **kw)


def test_non_numeric_cells_are_refused_and_empty_cells_are_missing(motion):
    t, w, f = motion
    df = table(t, w, f).astype({"gx": object})
    df.loc[3, "gx"] = "np.float64(0.1)"
    kw = dict(units={"gyro": "rad/s", "accel": "m/s^2"}, **COLS)
    with pytest.raises(ValueError, match=r"columns: 1 non-numeric cells in 'gx'"):
        io.from_dataframe(df, **kw)
    df.loc[3, "gx"] = None
    assert np.isnan(io.from_dataframe(df, **kw).w_ib_b[3, 0])


def test_implausible_magnitudes_say_what_was_probably_meant(motion):
    t, w, f = motion
    fast = np.rad2deg(w * 30)  # a 30x faster turn logged in deg/s (up to ~150 deg/s)
    with pytest.raises(ValueError, match=r"units\['gyro'\].*deg/s"):
        io.from_dataframe(table(t, fast, f), units={"gyro": "rad/s", "accel": "m/s^2"}, **COLS)
    with pytest.raises(ValueError, match=r"units\['accel'\].*g or m/s\^2"):
        io.from_dataframe(table(t, w, f), units={"gyro": "rad/s", "accel": "g"}, **COLS)
    with pytest.raises(ValueError, match=r"gravity removed"):
        io.from_dataframe(table(t, w, f - f.mean(0)), units={"gyro": "rad/s", "accel": "m/s^2"}, **COLS)
    rec = io.from_dataframe(table(t, w, f), units={"gyro": "rad/s", "accel": "g"}, check_units=False, **COLS)
    np.testing.assert_allclose(rec.f_b, f * G)


def test_euroc_layout(tmp_path, motion):
    t, w, f = motion
    ns = 1403715523912140000 + np.round(t * 1e9).astype(np.int64)
    lines = [
        "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
        "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]"
    ]
    lines += [",".join([str(n)] + [f"{v:.17g}" for v in (*wi, *fi)]) for n, wi, fi in zip(ns, w, f, strict=True)]
    (tmp_path / "data.csv").write_text("\n".join(lines) + "\n")
    rec = io.read_euroc(tmp_path / "data.csv")
    np.testing.assert_allclose(rec.w_ib_b, w, rtol=PARSE_RTOL, atol=0)
    np.testing.assert_allclose(rec.time, (ns - ns[0]) * 1e-9)
    assert rec.start == np.datetime64(int(ns[0]), "ns")


def write_logger(d, t0_ns, t, x, name, cols=("x", "y", "z")):
    ns = t0_ns + np.round(t * 1e9).astype(np.int64)
    df = pd.DataFrame({"time": ns, "seconds_elapsed": t})
    for c, i in zip(("z", "y", "x"), (2, 1, 0), strict=True):  # the app writes z, y, x
        if c in cols:
            df[c] = x[:, i]
    if cols == ("pressure",):
        df = pd.DataFrame({"time": ns, "seconds_elapsed": t, "relativeAltitude": 0.0, "pressure": x})
    df.to_csv(d / name, index=False, float_format="%.17g")


def test_sensor_logger_export_is_aligned_on_the_gyro_clock(tmp_path, motion):
    t, w, f = motion
    t0 = 1_700_000_000_000_000_000
    write_logger(tmp_path, t0, t, w, "Gyroscope.csv")
    write_logger(tmp_path, t0, t[1::2], f[1::2], "TotalAcceleration.csv")  # 50 Hz, starts later
    m_t = t[::10] + 0.003
    write_logger(tmp_path, t0, m_t, np.tile([1.0, 30.0, -30.0], (m_t.size, 1)), "Magnetometer.csv")
    write_logger(tmp_path, t0, t[::25], np.full(t[::25].size, 1000.0), "Barometer.csv", cols=("pressure",))
    rec = io.read_sensor_logger(tmp_path)
    assert rec.n == t.size
    assert np.isnan(rec.f_b[0]).all() and np.allclose(rec.f_b[1:3], f[[1, 1]])  # held, NaN before the first
    np.testing.assert_allclose(rec.m_b[np.isfinite(rec.m_b[:, 0])][0], [1.0, 30.0, -30.0])
    np.testing.assert_allclose(rec.pressure[0], 1e5)
    assert rec.start == np.datetime64(t0 + round(t[0] * 1e9), "ns")
    (tmp_path / "TotalAcceleration.csv").rename(tmp_path / "Accelerometer.csv")
    with pytest.raises(ValueError, match="no Metadata.csv.*platform="):
        io.read_sensor_logger(tmp_path)
    with pytest.raises(ValueError, match="Accelerometer.csv: gravity is removed.*Gravity"):
        io.read_sensor_logger(tmp_path, platform="android")


def test_align_hold_and_interpolate():
    ts = np.array([0.0, 1.0, 2.0, 5.0])
    x = np.array([0.0, 10.0, 20.0, 50.0])
    tt = np.array([-0.5, 0.0, 0.5, 1.9, 2.2, 4.0, 5.0, 5.2])
    hold = io.align(tt, ts, x, max_gap=1.5)
    np.testing.assert_array_equal(hold, [np.nan, 0, 0, 10, 20, np.nan, 50, 50])
    lin = io.align(tt, ts, x, method="interpolate", max_gap=1.5)
    np.testing.assert_allclose(lin, [np.nan, 0, 5, 19, np.nan, np.nan, 50, np.nan])
    with pytest.raises(ValueError, match="x_source"):
        io.align(tt, ts, x[:3])
    with pytest.raises(ValueError, match="method"):
        io.align(tt, ts, x, method="spline")


def test_a_file_with_a_header_and_no_samples_is_refused_by_name(tmp_path):
    header = ",".join(["Time (s)"] + [f"Gyroscope {a} (deg/s)" for a in "XYZ"] + [f"Accelerometer {a} (g)" for a in "XYZ"])
    path = tmp_path / "empty.csv"
    path.write_text(header + "\n")
    with pytest.raises(ValueError, match="^path: .*has a header but no samples"):  # was a bare IndexError
        io.read_xio(path)
