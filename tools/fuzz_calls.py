"""The one registry of navlib's public callables, read by tools/fuzz.py and tests/test_bad_input.py.

How to add a public callable: add one row to :func:`table`, ``"module.name": Call(dict(...))`` with the
keyword arguments of a call that succeeds in well under a second (or ``Skip("why")`` for a record that navlib
builds from validated values, an exception class, a function without arguments). That is all:
tests/test_bad_input.py fails for a public name without a row, and then calls the row with the bad values of
tools/fuzz.py's ``MUTATIONS`` that cannot hang (``make fuzz``: all of them, in workers with a timeout). A bad
call that no mutation makes (a negative gain, two references at once) goes in the row's ``bad``:
``Bad(arg, what, **changes)``, the valid call with ``changes``; its error must name ``arg``. The same bad value
for several arguments (an option, a record or a flag that no mutation fuzzes): ``*each(args, whats)``.

The fixtures: a static IMU at 100 Hz, ten samples.
"""

from __future__ import annotations

import dataclasses
import importlib
import inspect
import pkgutil
import tempfile
import warnings
from pathlib import Path

import numpy as np
import pandas as pd

from navlib import (
    alignment,
    analysis,
    attitude,
    earth,
    imu,
    io,
    repro,
    robust,
    sensors,
    strapdown,
    trajectory,
    units,
)
from navlib.filters import observations, planar_ekf, zupt_ins
from navlib.papers import gauss_kruger_ekf

# The alias modules (being deleted): not public API, no rows.
DEPRECATED = {"navlib.northfinding", "navlib.gyrobias", "navlib.planar", "navlib.ahrs", "navlib.pedestrian"}


@dataclasses.dataclass
class Fresh:
    """A value made anew for every call (a random generator, matplotlib axes)."""

    make: object


class Bad:
    """A bad call: the row's valid call with ``changes``; its ValueError/TypeError must name ``arg``."""

    def __init__(self, arg: str, what: str, **changes):
        self.arg, self.what, self.changes = arg, what, changes


# Bad values given where no mutation of tools/fuzz.py applies (an option, a record, a mask, a flag; an empty batch of
# the functions that refuse one), by name: rows built by :func:`each`.
BAD_VALUES = {
    "string": "abc",
    "complex": 1 + 1j,
    "object": np.array([1.0, "a"], dtype=object),
    "bool": True,
    "empty": np.zeros(0),
    "nan": np.nan,
    "minus_inf": -np.inf,
    "ragged": [1.0, [2.0, 3.0]],
}


def each(args, whats, make=None) -> tuple:
    """Bad rows: each of ``args`` given each value of ``whats`` (names in BAD_VALUES); ``make(arg, value)`` -> the
    changes of the valid call (default: ``{arg: value}``)."""
    return tuple(Bad(a, w, **(make(a, BAD_VALUES[w]) if make else {a: BAD_VALUES[w]})) for a in args for w in whats)


@dataclasses.dataclass
class Call:
    """One valid call: keyword arguments and how its arguments behave.

    any_shape : names of data arguments of any width, (..., N, k) for every k (a wrong last axis is none).
    elementwise : names of arguments over which the function broadcasts elementwise (``("*",)``: all):
        any leading shape, also empty, is valid for them.
    n : samples of the series (inferred from the first (N, 3) array or time axis when None).
    before : run before the call (e.g. ``repro.setup``).
    bad : bad calls that no mutation of tools/fuzz.py makes.
    """

    kwargs: dict
    elementwise: tuple = ()
    any_shape: tuple = ()
    n: int | None = None
    before: object = None
    bad: tuple = ()


@dataclasses.dataclass
class Skip:
    """A public callable that is not fuzzed, and why (a record built by navlib, an exception class)."""

    reason: str


# Bad calls that navlib does not refuse yet: "callable-arg-mutation" -> what it does instead. The tests mark
# them xfail(strict=True), make fuzz lists them apart; remove the entry when navlib is fixed.
KNOWN_GAPS: dict[str, str] = {}


def public_callables() -> dict[str, object]:
    """``module.name`` (module relative to navlib) -> object, for every callable in a public module's ``__all__``."""
    out = {}
    for mod in public_modules():
        for name in getattr(mod, "__all__", ()):
            obj = getattr(mod, name)
            if callable(obj) and not inspect.ismodule(obj):
                out[f"{mod.__name__.removeprefix('navlib.')}.{name}"] = obj
    return out


def public_modules() -> list:
    """Every navlib module but the private (``_``) and deprecated alias ones."""
    import navlib

    out = []
    for info in pkgutil.walk_packages(navlib.__path__, "navlib."):
        if info.name in DEPRECATED or any(p.startswith("_") for p in info.name.split(".")):
            continue
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", DeprecationWarning)
            out.append(importlib.import_module(info.name))
    return out


N = 10  # samples of every series
DT = 0.01  # s
T = DT * np.arange(N)  # a valid time axis (s)
LLA0 = np.array([0.6, 0.2, 50.0])  # lat, lon (rad), h (m)
HPR = np.array([0.3, 0.1, -0.2])  # heading, pitch, roll (rad)
Q = attitude.euler_to_quat(HPR)
C = attitude.quat_to_dcm(Q)
B_N = np.array([0.0, 20.0, -40.0])  # ENU field (uT)
REAL = Path(__file__).resolve().parents[1] / "data" / "real"  # committed recordings (the dataset readers)
_STATIC = trajectory.static(N * DT, DT, LLA0, HPR)
_W0, _F0 = trajectory.ideal_imu(_STATIC)
_k = np.arange(N)[:, None]
W = _W0 + 1e-3 * np.sin(_k + np.array([0.0, 1.0, 2.0]))  # gyro (rad/s), deterministic "noise"
F = _F0 + 1e-2 * np.cos(_k + np.array([0.0, 1.0, 2.0]))  # accelerometer (m/s^2)
M = attitude.quat_rotate(attitude.quat_conj(Q), B_N) + 0.1 * np.sin(_k)  # magnetometer (uT)
LLA = LLA0 + np.array([1e-7, 1e-7, 0.1]) * _k  # a short track
HEADINGS = 0.3 + 0.01 * np.arange(N)
VALID = np.array([True] * 4 + [False] + [True] * 5)
DTS = np.full(N, DT)  # an irregular-sampling time step per sample (s)
Q0 = np.zeros(4)  # the zero quaternion
CALIB = dict(AC1=408, AC2=-72, AC3=-14383, AC4=32741, AC5=32757, AC6=23153, B1=6190, B2=4, MB=-32768, MC=-8711, MD=2868)
RNG = Fresh(lambda: np.random.default_rng(0))
IMU = imu.ImuSamples(W, F, DT)
RTK = observations.RtkHeading(HEADINGS + 0.01, VALID)
EKF = planar_ekf.EkfConfig(Q=gauss_kruger_ekf.Q_PAPER, R=gauss_kruger_ekf.R_PAPER, P0=np.eye(5))


def _axes2d():
    import matplotlib.pyplot as plt

    return plt.figure().add_subplot()


def _axes3d():
    import matplotlib.pyplot as plt

    return plt.figure().add_subplot(projection="3d")


def _figure():
    import matplotlib.pyplot as plt

    return plt.figure()


def _setup():
    repro.setup("zz_fuzz", style=False)


def _setup_verdict():
    repro.setup("zz_fuzz", paper="000", style=False)
    repro.check("P000-EQ3-EULER/fuzz", 1.0, 1.05, 0.1, "src")


def _mc_batch(ids, streams):
    return {"x": streams.normal()}


def _files() -> Path:
    """Small logs in each reader's layout, in a temporary folder."""
    d = Path(tempfile.mkdtemp(prefix="navlib-fuzz-io-"))
    df = pd.DataFrame({"Time (s)": T})
    for i, a in enumerate("XYZ"):
        df[f"Gyroscope {a} (deg/s)"] = np.rad2deg(W[:, i])
    for i, a in enumerate("XYZ"):
        df[f"Accelerometer {a} (g)"] = F[:, i] / units.G0
    df.to_csv(d / "xio.csv", index=False)
    ns = 1403715523912140000 + np.round(T * 1e9).astype(np.int64)
    lines = [
        "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
        "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]"
    ]
    lines += [",".join([str(n)] + [f"{v:.17g}" for v in (*wi, *fi)]) for n, wi, fi in zip(ns, W, F, strict=True)]
    (d / "euroc.csv").write_text("\n".join(lines) + "\n")
    (d / "logger").mkdir()
    for name, x in (("Gyroscope.csv", W), ("TotalAcceleration.csv", F)):
        t = pd.DataFrame({"time": ns, "seconds_elapsed": T, "z": x[:, 2], "y": x[:, 1], "x": x[:, 0]})
        t.to_csv(d / "logger" / name, index=False)
    pd.DataFrame({"t": T, "gx": W[:, 0], "gy": W[:, 1], "gz": W[:, 2]}).to_csv(d / "plain.csv", index=False)
    phyphox = {"Time (s)": T} | {f"Gyroscope {a} (rad/s)": W[:, i] for i, a in enumerate("xyz")}
    pd.DataFrame(phyphox | {f"Acceleration {a} (m/s^2)": F[:, i] for i, a in enumerate("xyz")}).to_csv(
        d / "Raw Data.csv", index=False
    )
    return d


def _explorer_figure(a=1.0):
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots()
    ax.plot([0.0, 1.0], [0.0, a])
    return fig


def table() -> dict:
    """``module.name`` (relative to navlib) -> Call or Skip."""
    files = _files()
    io_table = pd.DataFrame({"t": T, "gx": W[:, 0], "gy": W[:, 1], "gz": W[:, 2]})
    static_w, static_f = _W0, _F0
    gk_truth = planar_ekf.propagate(np.array([0.0, 0.0, np.pi / 4, 1.0, 0.0]), 0.5, N - 1)
    gk_origin = np.deg2rad([26.06, 119.20])
    gk = gauss_kruger_ekf.simulate_sensors(gk_truth, gk_origin, gauss_kruger_ekf.R_PAPER, np.random.default_rng(0))
    ones3, t3, x5 = np.ones(3), np.array([0.0, 0.5, 1.0]), np.array([0.0, 0.0, 0.3, 1.0, 0.0])
    gps3 = np.tile(gk_origin, (3, 1))

    def ekf3(**changes):
        """An ekf call of three epochs at the origin, no origin given, with ``changes`` (``gps`` etc.: Sensors fields)."""
        fields = {k: changes.pop(k) for k in ("gps", "heading", "speed", "yaw_rate") if k in changes}
        sensors = dataclasses.replace(gauss_kruger_ekf.Sensors(gps3, ones3, ones3, ones3), **fields)
        return {**dict(t=t3, sensors=sensors, x0=np.zeros(5), origin=None), **changes}

    numeric = ("complex", "object", "bool", "empty", "nan", "minus_inf", "ragged")  # for an option no mutation fuzzes
    taus = np.array([0.1, 0.2, 0.4, 0.8, 1.6])
    adev = analysis.allan_deviation_theory(taus, white=1e-3, bias_instability=1e-4, correlation_time=10.0)
    V = np.stack([np.eye(3)[:2], np.eye(3)[1:], np.eye(3)[[0, 2]], np.eye(3)[:2]]) + 0.01
    R2 = np.tile(np.eye(2), (4, 1, 1))
    dwell = np.concatenate([W, W, W, W]), np.concatenate([F, F, F, F])
    calls = {
        # ---------------------------------------------------------------- alignment
        "alignment.level": Call(dict(f_b=F[0])),
        "alignment.magnetic_heading": Call(
            dict(m_b=M[0], pitch=0.1, roll=-0.05, declination=0.02), elementwise=("pitch", "roll")
        ),
        "alignment.tilt_heading": Call(dict(f_b=F[0], m_b=M[0], declination=0.02)),
        "alignment.initial_attitude": Call(
            dict(f_b=F[0], m_b=M[0], declination=0.02),
            bad=(
                Bad("f_b", "zero", f_b=np.zeros(3)),
                Bad("m_b", "zero", m_b=np.zeros(3)),
                Bad("m_b", "parallel", f_b=np.array([0.0, 0.0, 9.8]), m_b=np.array([0.0, 0.0, -30.0])),
            ),
        ),
        "alignment.gyrocompass_latitude": Call(dict(lat=0.6), elementwise=("*",)),
        "alignment.StaticWindow": Skip("a result record, built by static_means"),
        "alignment.static_means": Call(dict(w_ib_b=static_w, f_b=static_f, lat=0.6, h=50.0, accel_tol=0.2)),
        "alignment.StaticTests": Call(
            dict(accel_tol=0.2, min_fraction=0.5, outlier_k=6.0, full_scale_gyro=8.0, full_scale_accel=160.0, stuck_fraction=0.5)
        ),
        "alignment.static_windows": Call(
            dict(w_ib_b=W, f_b=F, windows=np.array([[0, 5], [5, 10]]), lat=0.6, h=50.0, tests=alignment.StaticTests()),
            bad=(
                Bad("windows", "too_short", windows=np.array([[0, 1]])),
                Bad("windows", "beyond_record", windows=np.array([[0, 5], [5, 11]])),
                Bad("windows", "fractional", windows=np.array([[0.0, 5.5]])),
                Bad("time", "length", time=0.01 * np.arange(9), windows=np.array([[0.0, 0.05]])),
                Bad("windows", "reversed_times", time=0.01 * np.arange(10), windows=np.array([[0.05, 0.0]])),
                Bad("tests", "dict", tests={"accel_tol": 0.2}),
            ),
        ),
        "alignment.triad": Call(dict(f_b=static_f[0], w_ib_b=static_w[0], lat=0.6, orthonormal=True), elementwise=("lat",)),
        "alignment.triad_heading": Call(dict(C_bn=C)),
        "alignment.four_position_heading": Call(dict(w_y=np.array([2e-5, 3e-5, -1e-5, -3e-5]))),
        "alignment.static_gyro_bias": Call(dict(w_ib_b=static_w, C_bn=C, lat=0.6)),
        # ----------------------------------------------------------------- analysis
        "analysis.rmse": Call(dict(err=W, axis=0), any_shape=("err",)),
        "analysis.allan_deviation": Call(dict(x=np.sin(np.arange(100.0)), dt=0.1, taus=None), any_shape=("x",)),
        "analysis.allan_deviation_theory": Call(
            dict(taus=taus, white=1e-3, bias_instability=1e-4, correlation_time=10.0, rate_random_walk=1e-5),
            elementwise=("taus",),
        ),
        "analysis.fit_allan": Call(dict(taus=taus, adev=adev, n_samples=1000, dt=0.1)),
        "analysis.attitude_errors": Call(dict(hpr=HPR + 0.01 * _k, hpr_true=np.tile(HPR, (N, 1)))),
        "analysis.error_statistics": Call(dict(hpr=np.stack([HPR + 0.01 * _k, HPR - 0.01 * _k]), hpr_true=np.tile(HPR, (N, 1)))),
        "analysis.horizontal_error": Call(dict(lla=LLA, lla_true=np.tile(LLA0, (N, 1)))),
        "analysis.position_error": Call(
            dict(estimate=W[:, :2], truth=F[:, :2]),
            any_shape=("estimate", "truth"),
            bad=(
                Bad("estimate", "one_column", estimate=np.zeros((3, 1)), truth=np.zeros((3, 1))),
                Bad("estimate, truth", "length", estimate=np.zeros((3, 2)), truth=np.zeros((2, 2))),
            ),
        ),
        "analysis.expanding_std": Call(dict(x=HEADINGS**2)),
        "analysis.detection_rates": Call(dict(detected=VALID, truth=np.roll(VALID, 1))),
        "analysis.settling_time": Call(
            dict(time=T, error=np.exp(-T * 50), start=0.0, tol=0.5, end=0.08),
            bad=(Bad("start, end", "after_the_data", start=5.0, end=None), Bad("time", "length", time=np.r_[T, 0.0])),
        ),
        "analysis.segments": Call(dict(mask=VALID)),
        "analysis.orientation_errors": Call(dict(q_bn=np.tile(Q, (N, 1)), q_ref=np.tile(Q, (N, 1)))),
        "analysis.time_offset": Call(
            dict(
                t=0.3 + T,
                x=np.sin(5 * (0.28 + T)),
                t_ref=np.linspace(0.0, 1.0, 101),
                x_ref=np.sin(np.linspace(0.0, 5.0, 101)),
                max_offset=0.1,
                step=0.005,
            )
        ),
        "analysis.OrientationErrors": Skip("a result record, built by orientation_errors"),
        "datasets.read_broad": Call(dict(path=str(REAL / "broad" / "07_undisturbed_fast_rotation_B.npz"))),
        "datasets.read_comma2k19": Call(dict(folder=str(REAL / "comma2k19"))),
        "datasets.broad_split": Call(dict(names=["02_undisturbed_slow_rotation_B", "07_undisturbed_fast_rotation_B"])),
        "datasets.ReferenceTrial": Skip("a result record, built by read_broad"),
        "datasets.DriveLog": Skip("a result record, built by read_comma2k19"),
        "filters.inertial_lowpass.inertial_lowpass": Call(dict(imu=IMU, m_b=M)),
        "filters.inertial_lowpass.InertialLowpassSettings": Call(dict()),
        "repro.check_study": Skip("needs a notebook's recorded seed study (data/seed_studies); tests/test_repro.py covers it"),
        "repro.seed_spread": Skip("needs a notebook's recorded seed study (data/seed_studies); tests/test_repro.py covers it"),
        "repro.SeedSpread": Skip("a result record, built by seed_spread"),
        "analysis.footfall_path_length": Call(dict(pos_n=np.column_stack([T, HEADINGS, 0 * T]), stance=VALID, min_samples=1)),
        "analysis.moving_mean": Call(dict(x=HEADINGS**2, n=3), any_shape=("x",)),
        "analysis.normal_condition": Call(dict(A=np.array([[2.0, 0.5], [0.5, 1.0]]))),
        "analysis.condition_number": Call(dict(V=V), any_shape=("V",)),
        "analysis.lsq_covariance": Call(dict(V=V, R=R2, max_cond=1e6)),
        "analysis.cramer_rao_bound": Call(dict(V=V, R=R2, max_cond=1e6)),
        # --------------------------------------------------------------- atmosphere
        "atmosphere.isa_altitude": Call(dict(p=9e4, p0=101325.0), elementwise=("*",)),
        "atmosphere.isa_pressure": Call(dict(h=100.0, p0=101325.0), elementwise=("*",)),
        "atmosphere.bmp180_altitude": Call(dict(p=9e4, p0=101325.0), elementwise=("*",)),
        "atmosphere.bmp180_pressure": Call(dict(h=100.0, p0=101325.0), elementwise=("*",)),
        "atmosphere.hypsometric_height": Call(dict(p=9e4, p_ref=1e5, temperature=288.0), elementwise=("*",)),
        "atmosphere.bmp180_compensate": Call(dict(UT=27898, UP=23843, calib=CALIB, oss=0)),
        "atmosphere.baro_height": Call(dict(p=1e5 - 10 * np.arange(N), p_ref=101325.0, temperature=288.0), elementwise=("p",)),
        "atmosphere.reference_pressure": Call(dict(p=1e5 - 10 * np.arange(N), time=T, until=0.05)),
        "atmosphere.classify_floor": Call(
            dict(h=np.array([0.0, 3.1, 6.2, 3.0, -0.1]), floor_height=3.0, ref_floor=0), elementwise=("h",)
        ),
        "atmosphere.segment_floors": Call(
            dict(h=np.r_[np.zeros(5), np.full(5, 3.1)], static=~VALID | True, floor_height=3.0, ref_floor=0)
        ),
        # ----------------------------------------------------------------- attitude
        "attitude.wrap_pi": Call(dict(angle=np.array([0.5, 4.0, -4.0, 7.0, -9.0])), elementwise=("*",)),
        "attitude.wrap_2pi": Call(dict(angle=np.array([0.5, 7.0, -1.0, 13.0, -9.0])), elementwise=("*",)),
        "attitude.skew": Call(dict(v=np.array([1.0, 2.0, 3.0])), elementwise=("*",)),
        "attitude.rot": Call(dict(axis="x", angle=0.3, deg=False), elementwise=("*",)),
        "attitude.orthonormalize": Call(dict(C=C + 1e-3), elementwise=("*",)),
        "attitude.euler_to_dcm": Call(dict(hpr=HPR, deg=False), elementwise=("*",)),
        "attitude.dcm_to_euler": Call(dict(C_bn=C, deg=False), elementwise=("*",)),
        "attitude.euler_to_quat": Call(dict(hpr=HPR, deg=False), elementwise=("*",)),
        "attitude.quat_to_euler": Call(dict(q=Q, deg=False), elementwise=("*",)),
        "attitude.quat_to_dcm": Call(dict(q=Q), elementwise=("*",)),
        "attitude.dcm_to_quat": Call(dict(C_bn=C), elementwise=("*",)),
        "attitude.quat_mult": Call(dict(p=Q, q=attitude.quat_conj(Q)[[0, 2, 1, 3]]), elementwise=("*",)),
        "attitude.quat_conj": Call(dict(q=Q), elementwise=("*",)),
        "attitude.quat_normalize": Call(dict(q=2 * Q), elementwise=("*",)),
        "attitude.quat_rotate": Call(dict(q=Q, v_b=np.array([1.0, 2.0, 3.0])), elementwise=("*",)),
        "attitude.rotvec_to_dcm": Call(dict(rv=np.array([0.1, -0.2, 0.3])), elementwise=("*",)),
        "attitude.dcm_to_rotvec": Call(dict(C=C), elementwise=("*",)),
        "attitude.rotvec_to_quat": Call(dict(rv=np.array([0.1, -0.2, 0.3])), elementwise=("*",)),
        "attitude.quat_to_rotvec": Call(dict(q=Q), elementwise=("*",)),
        "attitude.ned_to_enu": Call(dict(v=np.array([1.0, 2.0, 3.0])), elementwise=("*",)),
        "attitude.ned_to_enu_dcm": Call(dict(C_ned=C), elementwise=("*",)),
        "attitude.ned_to_enu_quat": Call(dict(q_ned=Q), elementwise=("*",)),
        "attitude.ypr_to_hpr": Call(dict(ypr=HPR, deg=False), elementwise=("*",)),
        "attitude.hpr_to_ypr": Call(dict(hpr=HPR, deg=False), elementwise=("*",)),
        "attitude.mount_matrix": Call(dict(axes="-y,x,z")),
        # -------------------------------------------------------------- calibration
        "calibration.MagCalibration": Call(
            dict(offset=np.array([1.0, 2.0, 3.0]), soft_iron=np.eye(3) * 1.1, field_strength=50.0)
        ),
        "calibration.fit_magnetometer": Call(
            dict(
                m_b=40.0 * attitude.quat_rotate(np.random.default_rng(0).standard_normal((12, 4)), [0.0, 0.0, 1.0])
                + [1.0, 2.0, 3.0],
                field_strength=None,
            )
        ),
        "calibration.AccelCalibration": Call(dict(bias=np.array([0.01, 0.02, 0.03]), matrix=np.eye(3) * 1.01, g=9.80665)),
        "calibration.fit_accelerometer": Call(
            dict(
                f_means=9.8 * np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1.0]]) + 0.01, g=9.80665
            )
        ),
        "calibration.gyro_bias_at_rest": Call(dict(w_ib_b=static_w, lat=0.6, C_bn=C)),
        "calibration.TriadNoise": Skip("a result record, built by characterise"),
        "calibration.NoiseCharacterisation": Skip("a result record, built by characterise"),
        "calibration.characterise": Call(dict(w_ib_b=np.tile(W, (20, 1)), f_b=np.tile(F, (20, 1)), dt=0.1)),
        # -------------------------------------------------------------------- earth
        "earth.Ellipsoid": Call(dict(name="x", a=6378137.0, f=1 / 298.257, GM=3.986e14, omega=7.29e-5)),
        "earth.earth_rate_n": Call(dict(lat=0.6, deg=False), elementwise=("*",)),
        "earth.earth_rate_b": Call(dict(C_bn=C, lat=0.6, deg=False), bad=(Bad("lat", "lat2rad", lat=2.0),)),
        "earth.gravity": Call(dict(lat=0.6, h=50.0, deg=False), elementwise=("*",)),
        "earth.gravity_n": Call(dict(lat=0.6, h=50.0, deg=False), elementwise=("*",)),
        "earth.radii": Call(dict(lat=0.6, deg=False), elementwise=("*",)),
        "earth.transport_rate_n": Call(dict(lat=0.6, h=50.0, vel_n=np.array([1.0, 2.0, 0.1])), elementwise=("*",)),
        "earth.magnetic_field": Call(dict(lat=45.0, lon=10.0, h=100.0, year=2024.0, deg=True), elementwise=("*",)),
        "earth.field_from_angles": Call(dict(declination=2.0, inclination=60.0, intensity=50.0, deg=True), elementwise=("*",)),
        "earth.field_angles": Call(dict(B_n=B_N, deg=True), elementwise=("*",)),
        # -------------------------------------------------------------------- euler
        "euler.check_pitch": Call(dict(pitch=0.3, name="pitch"), elementwise=("*",)),
        "euler.euler_rates": Call(
            dict(hpr=HPR, w_nb_b=np.array([0.01, 0.02, 0.03])),
            elementwise=("*",),
            bad=(Bad("hpr[..., 1] (pitch)", "pitch_90deg", hpr=np.array([0.0, np.pi / 2, 0.0])),),
        ),
        "euler.integrate_euler": Call(
            dict(hpr0=HPR, w_ib_b=W, dt=DT, w_in_n=earth.earth_rate_n(0.6), bias_b=np.array([1e-5, 0.0, 0.0])),
            bad=(
                Bad("hpr0[..., 1] (pitch)", "pitch_90deg", hpr0=np.array([0.0, np.pi / 2, 0.0])),
                Bad("w_ib_b", "through_pitch_90deg", hpr0=np.array([0.0, 1.5, 0.0]), w_ib_b=np.tile([1.0, 0.0, 0.0], (100, 1))),
                Bad("w_ib_b", "all_nan", w_ib_b=np.full((N, 3), np.nan)),
                Bad("dt", "zero", dt=0.0),
                Bad("dt", "length", dt=DTS[1:]),
                Bad("max_gap", "negative", max_gap=-0.1),
                Bad("bias_from", "decreasing", bias_b=np.zeros((2, 3)), bias_from=np.array([3, 1])),
            ),
        ),
        # ------------------------------------------------------------------- faults
        "faults.dropouts": Call(dict(x=F, fraction=0.2, rng=RNG), any_shape=("x",)),
        "faults.gap": Call(dict(x=F, time=T, start=0.02, duration=0.03), any_shape=("x",)),
        "faults.spikes": Call(dict(x=F, fraction=0.2, sigma=0.01, rng=RNG, k=100.0), elementwise=("sigma",), any_shape=("x",)),
        "faults.position_jumps": Call(dict(lla=LLA, fraction=0.2, rng=RNG, size_m=50.0)),
        "faults.heading_flips": Call(dict(heading=HEADINGS, fraction=0.2, rng=RNG), elementwise=("heading",)),
        "faults.duplicate_timestamps": Call(dict(time=T, fraction=0.2, rng=RNG)),
        "faults.swap_timestamps": Call(dict(time=T, fraction=0.2, rng=RNG)),
        "faults.irregular_times": Call(dict(n=N, dt=DT, jitter=0.2, rng=RNG, t0=0.0)),
        "faults.saturate": Call(dict(x=F, full_scale=9.805), any_shape=("x",)),
        # ------------------------------------------------------------ filters.*
        "filters.heading_fusion.fuse_rtk_heading": Call(
            dict(heading_mag=HEADINGS, rtk=RTK, dt=DT, alpha=0.1),
            bad=(
                Bad("alpha", "zero", alpha=0.0),
                Bad("alpha", "above_one", alpha=1.5),
                Bad("rtk", "array", rtk=HEADINGS),
                Bad("rtk", "heading_mag_length", heading_mag=np.r_[HEADINGS, 0.3]),
            ),
        ),
        "filters.heading_fusion.FusionResult": Skip("result record of fuse_rtk_heading, built from validated values"),
        "filters.heading_fusion.rtk_at_imu_rate": Call(
            dict(time=T, heading=HEADINGS, valid=VALID, step=2),
            bad=(
                Bad("step", "zero", step=0),
                Bad("step", "array", step=np.ones(2)),
                Bad("time", "decreasing", time=T[::-1]),
                Bad("valid", "numbers", valid=VALID.astype(float)),
                Bad("valid", "empty", valid=np.zeros(0, bool)),
                Bad("valid", "length", valid=np.ones(N + 1, bool)),
                Bad("heading", "length", heading=np.r_[HEADINGS, 0.3]),
                Bad("time", "length", time=np.r_[T, 0.0]),
            ),
        ),
        "filters.presets.foot_mounted": Call(dict(imu=IMU, still=T < 0.5)),
        "filters.presets.FootMounted": Skip("a result record, built by foot_mounted"),
        "filters.presets.MahonyGains": Call(dict(kp=0.1, ki=0.0)),
        "filters.mahony.mahony": Call(
            dict(imu=IMU, q0=Q, m_b=M, kp=1.0, ki=0.02, B_n=B_N),
            bad=(
                Bad("kp", "negative", kp=-1.0),
                Bad("q0", "batch_mismatch", q0=np.tile(Q, (2, 1))),
                Bad("m_b", "both_references", rtk=RTK, B_n=None),
                Bad("m_b", "length", m_b=M[:5]),
                Bad("q0", "zero", q0=Q0),
                Bad("rtk", "tuple", m_b=None, B_n=None, rtk=(HEADINGS, VALID)),
                Bad("imu", "array", imu=W),
                Bad("gates", "mag_without_m_b", m_b=None, gates=observations.AttitudeGates(mag=observations.MagGate())),
                Bad("B_n", "mag_gate_without_B_n", B_n=None, gates=observations.AttitudeGates(mag=observations.MagGate())),
                Bad("m_b", "given_twice", imu=robust.screen(IMU, M)),
            ),
        ),
        "filters.observations.screened": Call(
            dict(imu=IMU, m_b=M), bad=(Bad("m_b", "given_twice", imu=robust.screen(IMU, M)), Bad("imu", "array", imu=W))
        ),
        "filters.observations.MagGate": Call(
            dict(norm_tol=0.1, dip_tol=0.1),
            bad=(
                Bad("norm_tol", "negative", norm_tol=-0.1),
                Bad("norm_tol", "inf", norm_tol=np.inf),
                Bad("dip_tol", "inf", dip_tol=np.inf),
            ),
        ),
        "filters.observations.AttitudeResult": Skip("a result record, built by the attitude filters"),
        "filters.observations.AttitudeInputs": Skip("the kernel record, built by pack from validated values"),
        "filters.observations.AttitudeGates": Call(
            dict(accel_tol=0.5, g=9.8, mag=observations.MagGate()), bad=(Bad("accel_tol", "negative", accel_tol=-0.1),)
        ),
        "filters.observations.RtkHeading": Call(
            dict(heading=HEADINGS, valid=VALID, hold=0.25, gate=0.1, confirm=5),
            bad=(
                Bad("valid", "numbers", valid=VALID.astype(float)),
                Bad("valid", "empty", valid=np.zeros(0, bool)),
                Bad("valid", "length", valid=np.ones(N + 1, bool)),
                Bad("valid", "heading_length", heading=np.r_[HEADINGS, 0.3]),
                Bad("heading", "above_2pi", heading=np.full(N, 7.0)),
                Bad("hold", "negative", hold=-1.0),
                Bad("gate", "above_pi", gate=4.0),
                Bad("gate", "inf", gate=np.inf),
                Bad("confirm", "zero", confirm=0),
                Bad("confirm", "fractional", confirm=1.5),
            ),
        ),
        "filters.observations.integral_gain": Call(dict(ki=None, heading_reference=True)),
        "filters.observations.magnetic_reference": Call(dict(B_n=B_N), bad=(Bad("B_n", "zero", B_n=np.zeros(3)),)),
        "filters.observations.pack": Call(
            dict(imu=IMU, q0=Q, m_b=M, rtk=None, B_n=None, gates=observations.AttitudeGates(), kp=1.0)
        ),
        "filters.observations.attitude_result": Skip("assembles kernel outputs (validated by pack)"),
        "filters.observations.run_trials": Skip("runs a compiled kernel on validated inputs"),
        "filters.observations.unit_vectors": Skip("reads the kernel record built by pack from validated values"),
        "filters.planar_ekf.motion_model": Call(
            dict(X=np.array([1.0, 2.0, 0.5, 1.0, 0.1]), T=0.5), bad=(Bad("X", "shape", X=np.zeros(4)),)
        ),
        "filters.planar_ekf.jacobian": Call(dict(X=np.array([1.0, 2.0, 0.5, 1.0, 0.1]), T=0.5), bad=(Bad("T", "zero", T=0.0),)),
        "filters.planar_ekf.propagate": Call(
            dict(x0=np.array([0.0, 0.0, 0.5, 1.0, 0.1]), T=0.5, n_steps=N),
            bad=(
                Bad("n_steps", "float", n_steps=2.5),
                Bad("T", "zero", T=0.0),
                Bad("speed, yaw_rate", "yaw_rate_alone", n_steps=None, yaw_rate=np.full(3, 0.1)),
                Bad("yaw_rate", "length", n_steps=None, speed=ones3, yaw_rate=ones3[:2]),
            ),
        ),
        "filters.planar_ekf.dead_reckoning": Call(
            dict(t=0.5 * np.arange(N), speed=np.full(N, 1.0), yaw_rate=np.full(N, 0.01), x0=np.array([0.0, 0.0, 0.5, 1.0, 0.1])),
            bad=(
                Bad("speed", "shape", speed=np.ones(N - 1)),
                Bad("t", "repeated", t=np.array([0.0, 0.0, 1.0]), speed=ones3, yaw_rate=ones3, x0=np.zeros(5)),
                Bad("full_scale_gyro", "negative", full_scale_gyro=-2.0),
                Bad("max_dt", "negative", max_dt=-1.0),
                *each(("full_scale_gyro", "max_dt"), numeric),
            ),
        ),
        "filters.planar_ekf.filter_grid": Call(
            dict(t=0.5 * np.arange(N), z=gk_truth + 0.1, x0=np.array([0.0, 0.0, np.pi / 4, 1.0, 0.0]), config=EKF),
            bad=(
                Bad("t", "repeated", t=np.array([0.0, 1.0, 1.0]), z=np.tile(x5, (3, 1)), x0=x5),
                Bad("t", "one_sample", t=t3[:1], z=x5[None], x0=x5),
                *each(("config",), numeric),
            ),
        ),
        "filters.planar_ekf.EkfConfig": Call(
            dict(Q=gauss_kruger_ekf.Q_PAPER, R=gauss_kruger_ekf.R_PAPER, P0=np.eye(5)),
            bad=(
                Bad("Q", "missing", Q=None),
                Bad("Q", "negative", Q=-np.eye(5)),
                Bad("R", "shape4x4", R=np.ones((4, 4))),
                Bad("P0", "not_psd", P0=np.diag([1.0, 1.0, -1.0, 1.0, 1.0])),
                Bad("gate", "negative", gate=-1.0),
                Bad("gate", "zero", gate=0.0),
                Bad("gate", "minus_inf", gate=-np.inf),
                Bad("reacquire", "zero", reacquire=0),
                Bad("reacquire", "fractional", reacquire=2.5),
                *each(("limits",), ("string", *numeric)),
                Bad("limits", "number", limits=2.0),
            ),
        ),
        "filters.planar_ekf.EkfResult": Skip("a result record, built by filter_grid"),
        "filters.planar_ekf.covariance": Call(dict(M=np.eye(5), name="M"), bad=(Bad("P0", "not_psd", M=-np.eye(5), name="P0"),)),
        "filters.quaternion_kf.quaternion_kf": Call(
            dict(imu=IMU, q0=Q, m_b=M, B_n=B_N),
            bad=(
                Bad("B_n", "missing", B_n=None),
                Bad("noise", "float", noise=1e-3),
                Bad("B_n", "missing_with_screened", imu=robust.screen(IMU, M), m_b=None, B_n=None),
                Bad("m_b", "given_twice", imu=robust.screen(IMU, M)),
            ),
        ),
        "filters.quaternion_kf.KfNoise": Call(
            dict(sigma_gyro=1e-3, sigma_accel=0.02, sigma_mag=0.08, p0=1e-4),
            bad=(Bad("sigma_mag", "zero", sigma_mag=0.0), Bad("p0", "negative", p0=-1.0)),
        ),
        "filters.quaternion_kf.measurement_model": Call(
            dict(q=Q, b=np.array([0.0, 20.0, -40.0])),
            bad=(Bad("b", "east_component", b=np.array([1.0, 0.0, 0.0])), Bad("q", "zero", q=np.zeros(4))),
        ),
        "filters.quaternion_kf.measurement_jacobian": Call(
            dict(q=Q, b=np.array([0.0, 20.0, -40.0])), bad=(Bad("q", "zero", q=np.zeros(4)),)
        ),
        "filters.quaternion_kf.transition": Call(dict(w=W[0], dt=DT), bad=(Bad("dt", "zero", dt=0.0),)),
        "filters.quaternion_kf.noise_input": Call(dict(q=Q, dt=DT), bad=(Bad("q", "zero", q=np.zeros(4)),)),
        "filters.zupt.detect_static": Call(
            dict(w_ib_b=W, f_b=F, dt=DT, window=0.05),
            bad=(Bad("g", "negative", g=-9.8), Bad("window", "array", window=np.full(2, 0.05))),
        ),
        "filters.zupt.error_state_matrix": Call(
            dict(C_bn=C, f_b=F[0]),
            bad=(Bad("C_bn", "not_rotation", C_bn=np.ones((3, 3))), Bad("C_bn", "batch", C_bn=np.stack([np.eye(3)] * 2))),
        ),
        "filters.zupt.error_model_fd": Call(dict(C_bn=C, f_b=F[0], eps=1e-6), bad=(Bad("eps", "zero", eps=0.0),)),
        "filters.zupt.zupt_zaru_matrix": Call(
            dict(C_bn=C, w_ie_n=earth.earth_rate_n(0.6)), bad=(Bad("w_ie_n", "batch", w_ie_n=np.zeros((2, 3))),)
        ),
        "filters.zupt.zupt_zaru_innovation": Call(
            dict(vel_n=np.array([0.01, 0.02, 0.0]), w_ib_b=W[0], b_g=W[1] * 0.5, C_bn=C, w_ie_n=earth.earth_rate_n(0.6)),
            bad=(Bad("vel_n", "shape", vel_n=np.zeros(2)),),
        ),
        "filters.zupt_ins.Start": Call(
            dict(lla=LLA0, q_bn=Q, vel_n=np.zeros(3), accel_bias=np.zeros(3), gyro_bias=np.zeros(3), time=0.0)
        ),
        "filters.zupt_ins.Aiding": Call(dict(walk="reset", zupt=True, declination=0.02, B_n=B_N)),
        "filters.zupt_ins.ProcessNoise": Call(
            dict(accel=0.02, gyro=1e-4, accel_bias_rw=1e-4, gyro_bias_rw=1e-5, held_accel=1.0, held_gyro=0.1)
        ),
        "filters.zupt_ins.MeasurementNoise": Call(dict(zupt=0.01, zaru=0.002, baro=0.17, heading=0.035)),
        "filters.zupt_ins.InitialSigma": Call(dict(pos=0.01, vel=0.01, tilt=0.01, heading=0.035, accel_bias=0.1, gyro_bias=1e-3)),
        "filters.zupt_ins.Gates": Call(dict(zupt=22.5, max_rejected=5, baro=5.0, mag_field=0.1, mag_dip=0.1)),
        "filters.zupt_ins.BaroTracker": Call(dict(alpha=0.2, beta=0.02)),
        "filters.zupt_ins.FilterConfig": Call(
            dict(
                process=zupt_ins.ProcessNoise(),
                measurement=zupt_ins.MeasurementNoise(),
                initial=zupt_ins.InitialSigma(),
                gates=zupt_ins.Gates(),
                tracker=zupt_ins.BaroTracker(),
                update_rate=10.0,
            )
        ),
        "filters.zupt_ins.FilterResult": Skip("a result record, built by run_filter"),
        "filters.zupt_ins.run_filter": Call(dict(imu=IMU, start=zupt_ins.Start(LLA0, Q), static=VALID | True)),
        # ------------------------------------------------------------------ geodesy
        # navlib.geodesy refuses an empty batch (each(..., ("empty",))): its elementwise functions are not EMPTY_BATCH's
        "geodesy.zone": Call(
            dict(lon=2.08, width=3, deg=False),
            elementwise=("lon",),
            bad=(Bad("width", "five", width=5), Bad("width", "array", width=np.array([3, 6])), *each(("lon",), ("empty",))),
        ),
        "geodesy.central_meridian": Call(
            dict(zone_number=40, width=3, deg=False),
            elementwise=("zone_number",),
            bad=(
                Bad("zone_number", "zero", zone_number=0),
                Bad("zone_number", "fractional", zone_number=40.5),
                Bad("zone_number", "61_of_6deg", zone_number=61, width=6),
                Bad("zone_number", "121", zone_number=121),
                *each(("zone_number",), ("empty",)),
            ),
        ),
        "geodesy.geodetic2gk": Call(
            dict(lat=0.45, lon=2.08, zone=40),
            elementwise=("lat", "lon", "zone"),
            bad=(
                Bad("lat", "lat91deg", lat=91.0, lon=120.0, zone=None, deg=True),
                Bad("lat", "lat2rad", lat=2.0, lon=2.0, zone=None),
                Bad("lon", "outside_zone", lat=26.0, lon=130.0, deg=True),
                Bad("lon", "outside_lon0", lat=26.0, lon=123.5, zone=None, lon0=120.0, deg=True),
                Bad("width", "four", lat=26.0, lon=120.0, zone=None, width=4, deg=True),
                Bad("lon0, zone", "both", lat=26.0, lon=120.0, lon0=120.0, deg=True),
                Bad("lat, lon", "shape_mismatch", lat=np.array([1.0, 2.0]), lon=np.array([1.0, 2.0, 3.0]), zone=None, deg=True),
                Bad("false_easting", "zone_prefix_without", lat=26.0, lon=119.2, zone=None, deg=True, zone_prefix=True),
                Bad("zone", "zero", zone=0),
                Bad("zone", "fractional", zone=40.5),
                Bad("max_offset_deg", "negative", max_offset_deg=-1.0),
                Bad("max_offset_deg", "90", max_offset_deg=90.0),
                Bad("k0", "two", zone=None, k0=2.0),
                *each(("lat", "lon", "zone"), ("empty",)),
            ),
        ),
        "geodesy.gk2geodetic": Call(
            dict(x=2.88e6, y=2e4, zone=40),
            elementwise=("x", "y", "zone"),
            bad=(
                Bad("zone, lon0", "missing", x=2.8e6, y=-8e4, zone=None),
                Bad("y", "9e6", x=2.8e6, y=9e6),
                Bad("zone, lon0", "prefix_mismatch", x=2.8e6, y=4e7, zone_prefix=True),
                Bad("zone", "121", zone=121),
                Bad("lon0", "nan", zone=None, lon0=np.nan),
                Bad("x, y", "shape_mismatch", x=np.zeros(3), y=np.zeros(2)),
                *each(("x", "y", "zone"), ("empty",)),
            ),
        ),
        "geodesy.convergence": Call(
            dict(lat=0.45, lon=2.08, zone=40),
            elementwise=("lat", "lon", "zone"),
            bad=(Bad("lon", "outside_zone", lat=26.0, lon=140.0, deg=True), *each(("lat", "lon", "zone"), ("empty",))),
        ),
        "geodesy.scale_factor": Call(
            dict(lat=0.45, lon=2.08, zone=40),
            elementwise=("lat", "lon", "zone"),
            bad=(Bad("k0", "zero", lat=26.0, lon=120.0, zone=None, k0=0.0, deg=True), *each(("lat", "lon", "zone"), ("empty",))),
        ),
        "geodesy.meridian_arc": Call(
            dict(lat=0.45),
            elementwise=("*",),
            bad=(
                Bad("lat", "lat-100deg", lat=-100.0, deg=True),
                Bad("lat", "minus_1.6rad", lat=-1.6),
                Bad("ellipsoid", "number", ellipsoid=6378137.0),
                *each(("lat",), ("empty",)),
            ),
        ),
        "geodesy.geodetic2ecef": Call(
            dict(lat=0.6, lon=0.2, h=50.0),
            elementwise=("*",),
            bad=(
                Bad("lat, lon", "shape_mismatch", lat=np.zeros(3), lon=np.zeros(2), h=0.0),
                Bad("h", "shape_mismatch", lat=np.zeros(3), lon=np.zeros(3), h=np.zeros(2)),
                *each(("lat", "lon", "h"), ("empty",)),
            ),
        ),
        "geodesy.ecef2geodetic": Call(
            dict(x=4e6, y=8e5, z=4.8e6),
            elementwise=("*",),
            bad=(
                Bad("x, y, z", "near_the_centre", x=0.0, y=0.0, z=10.0),
                Bad("x, y, z", "inside_the_earth", x=1e3, y=1e3, z=1e3),
                Bad("x, y, z", "shape_mismatch", x=np.full(3, 7e6), y=np.zeros(2), z=0.0),
                *each(("x", "y", "z"), ("empty",)),
            ),
        ),
        "geodesy.geodetic2enu": Call(
            dict(lat=0.6 + 1e-6, lon=0.2, h=55.0, lat0=0.6, lon0=0.2, h0=50.0),
            elementwise=("*",),
            bad=(
                Bad("lat0", "1.6rad", lat=0.45, lon=2.08, h=0.0, lat0=1.6, lon0=2.08, h0=0.0),
                *each(("lat", "lon", "h", "lat0", "lon0", "h0"), ("empty",)),
            ),
        ),
        "geodesy.enu2geodetic": Call(
            dict(e=10.0, n=20.0, u=3.0, lat0=0.6, lon0=0.2, h0=50.0),
            elementwise=("*",),
            bad=(
                Bad("lat0", "lat95deg", e=0.0, n=0.0, u=0.0, lat0=95.0, lon0=119.0, h0=0.0, deg=True),
                Bad("e, n, u", "shape_mismatch", e=np.zeros(3), n=np.zeros(2), u=0.0, lat0=0.45, lon0=2.08, h0=0.0),
                *each(("e", "n", "u", "lat0", "lon0", "h0"), ("empty",)),
            ),
        ),
        "geodesy.geodetic2ned": Call(
            dict(lat=0.6 + 1e-6, lon=0.2, h=55.0, lat0=0.6, lon0=0.2, h0=50.0),
            elementwise=("*",),
            bad=each(("lat", "lon", "h", "lat0", "lon0", "h0"), ("empty",)),
        ),
        "geodesy.ned2geodetic": Call(
            dict(n=20.0, e=10.0, d=-3.0, lat0=0.6, lon0=0.2, h0=50.0),
            elementwise=("*",),
            bad=each(("n", "e", "d", "lat0", "lon0", "h0"), ("empty",)),
        ),
        "geodesy.local_scales": Call(
            dict(lat=0.45, lon=2.08, lon0=2.0944),
            elementwise=("*",),
            bad=(
                Bad("step", "zero", step=0.0),
                Bad("lat, lon", "shape_mismatch", lat=np.zeros(3), lon=np.zeros(2), lon0=0.0),
                *each(("lat", "lon", "lon0"), ("empty",)),
            ),
        ),
        # ---------------------------------------------------------------------- imu
        "imu.ImuSamples": Call(
            dict(w_ib_b=W, f_b=F, dt=DT),
            bad=(
                Bad("limits", "dict", limits=dict(full_scale_gyro=2.0)),
                Bad("dt", "irregular_negative", dt=-DTS),
                Bad("dt", "irregular_short", dt=DTS[1:]),
                Bad("dt", "irregular_long", dt=np.r_[DTS, DT]),
                Bad("dt", "irregular_complex", dt=DTS + 1j),
                Bad("dt", "irregular_object", dt=np.full(N, None, object)),
                Bad("dt", "irregular_nan", dt=np.full(N, np.nan)),
                Bad("dt", "irregular_inf", dt=np.full(N, np.inf)),
                *(
                    Bad(a, f"{what}_irregular_dt", dt=DTS, **{a: v})
                    for a, x in (("w_ib_b", W), ("f_b", F))
                    for what, v in (
                        ("string", "abc"),
                        ("complex", x + 1j),
                        ("object", np.full(x.shape, None, object)),
                        ("empty", np.zeros((0, 3))),
                        ("shape", np.zeros((N, 4))),
                        ("inf", np.full(x.shape, np.inf)),
                    )
                ),
            ),
        ),
        "imu.SensorLimits": Call(
            dict(full_scale_gyro=10.0, full_scale_accel=80.0, full_scale_mag=800.0, stuck_run=5, gyro_jump=1.0, max_dt=0.1),
            bad=(
                Bad("full_scale_gyro", "zero", full_scale_gyro=0.0),
                Bad("max_dt", "negative", max_dt=-1.0),
                Bad("max_dt", "nan", max_dt=np.nan),
                Bad("stuck_run", "zero", stuck_run=0),
                Bad("stuck_run", "bool", stuck_run=True),
                Bad("stuck_run", "str", stuck_run="on"),
                Bad("full_scale_gyro", "negative", full_scale_gyro=-1.0),
                Bad("gyro_jump", "zero", gyro_jump=0.0),
            ),
        ),
        "imu.unpack": Call(dict(w_ib_b=W, f_b=F, dt=DT)),
        # ----------------------------------------------------------------------- io
        "io.Recording": Skip("a result record, built by the readers"),
        "io.read_csv": Call(dict(path=str(files / "plain.csv"), time="t", units={"gyro": "rad/s"}, gyro=("gx", "gy", "gz"))),
        "io.from_dataframe": Call(dict(df=io_table, time="t", units={"gyro": "rad/s"}, gyro=("gx", "gy", "gz"))),
        "io.read_xio": Call(dict(path=str(files / "xio.csv"))),
        "io.read_sensor_logger": Call(dict(directory=str(files / "logger"))),
        "io.read_euroc": Call(dict(path=str(files / "euroc.csv"))),
        "io.align": Call(
            dict(t_target=T, t_source=T[::2] + 0.001, x_source=HEADINGS[::2], method="hold"), any_shape=("x_source",)
        ),
        "io.read_phyphox": Call(dict(path=str(files / "Raw Data.csv"))),
        "io.resample": Call(dict(rec=io.Recording(T, W, F), rate=20.0)),
        "io.check_axes": Call(dict(rec=io.Recording(T, W, F), on_fail="ignore")),
        "io.AxisCheck": Skip("a result record, built by check_axes"),
        "io.start_at_rest": Call(dict(rec=io.Recording(T, W, F), still=T < 0.5)),
        # ------------------------------------------------------------------- kalman
        "kalman.predict": Call(
            dict(x=np.array([1.0, 2.0]), P=np.eye(2), F=np.array([[1.0, 0.1], [0.0, 1.0]]), Q=0.01 * np.eye(2)),
            bad=(
                Bad("x", "empty", x=np.zeros(0), P=np.zeros((0, 0)), F=np.zeros((0, 0)), Q=np.zeros((0, 0))),
                Bad("x", "shape2x1", x=np.array([[1.0], [2.0]])),
                Bad("P", "shape3x3", P=np.eye(3)),
                Bad("F", "shape2x3", F=np.ones((2, 3))),
                Bad("Q", "scalar", Q=0.01),
                Bad("Q", "shape2x1", Q=np.full((2, 1), 0.01)),
                Bad("Q", "vector", Q=np.full(2, 0.01)),
                Bad("Q", "empty", Q=np.zeros((0, 0))),
            ),
        ),
        "kalman.update": Call(
            dict(
                x=np.array([1.0, 2.0]),
                P=np.eye(2),
                z=np.array([1.5, 2.5]),
                h=np.array([1.0, 2.0]),
                H=np.eye(2),
                R=np.eye(2),
                angle_mask=np.array([False, True]),
                gate=np.inf,
            ),
            bad=(
                Bad("x", "empty", x=np.zeros(0)),
                Bad("P", "shape1x1", P=np.ones((1, 1))),
                Bad("z", "shape2x1", z=np.array([[1.5], [2.5]])),
                Bad("h", "shape3", h=np.array([1.0, 2.0, 3.0])),
                Bad("h", "empty", h=np.zeros(0)),
                Bad("H", "shape2x3", H=np.ones((2, 3))),
                Bad("R", "scalar", R=1.0),
                Bad("R", "shape2x1", R=np.ones((2, 1))),
                Bad("angle_mask", "empty", angle_mask=np.zeros(0, bool)),
                Bad("angle_mask", "float", angle_mask=np.array([0.0, 1.0])),
                Bad("gate", "negative", gate=-1.0),
                Bad("gate", "zero", gate=0.0),
                Bad("gate", "array", gate=np.full(2, 9.0)),
            ),
        ),
        "kalman.discretize": Call(
            dict(F=np.array([[0.0, 1.0], [0.0, 0.0]]), G=np.eye(2), Qc=0.1 * np.eye(2), dt=0.1),
            bad=(
                Bad("F", "not_square", F=np.zeros((2, 3))),
                Bad("G", "row_mismatch", G=np.eye(3), Qc=np.eye(3)),
                Bad("Qc", "shape_mismatch", Qc=np.eye(3)),
                Bad("dt", "zero", dt=0.0),
                Bad("F", "empty", F=np.zeros((0, 0)), G=np.zeros((0, 0)), Qc=np.zeros((0, 0))),
            ),
        ),
        # --------------------------------------------------------------- montecarlo
        "montecarlo.TrialStreams": Call(dict(seed=1, ids=np.arange(5))),
        "montecarlo.run": Call(dict(batch_fn=_mc_batch, n_trials=5, seed=1, batch_size=2, progress=False)),
        # ------------------------------------------------------------------- papers
        "papers.Paper": Call(dict(name="x", number=9, claims_id="009", citation="c", parts=("b",))),
        "papers.by_notebook": Call(dict(stem="01_north_finding")),
        # the paper's equations refuse an empty batch, as navlib.geodesy does
        "papers.gauss_kruger_ekf.printed_zone_number": Call(dict(lon=2.08), elementwise=("*",), bad=each(("lon",), ("empty",))),
        "papers.gauss_kruger_ekf.paper_radii": Call(
            dict(lat=0.45), elementwise=("*",), bad=(Bad("lat", "lat95deg", lat=95.0, deg=True), *each(("lat",), ("empty",)))
        ),
        "papers.gauss_kruger_ekf.printed_meridian_radius": Call(
            dict(lat=0.45),
            elementwise=("*",),
            bad=(
                Bad("lat", "1.6rad", lat=1.6),
                Bad("ellipsoid", "number", ellipsoid=earth.CGCS2000.a),
                *each(("lat",), ("empty",)),
            ),
        ),
        "papers.gauss_kruger_ekf.paper_meridian_arc": Call(
            dict(lat=0.45),
            elementwise=("*",),
            bad=(
                Bad("lat", "lat-100deg", lat=-100.0, deg=True),
                Bad("lat", "minus_1.6rad", lat=-1.6),
                Bad("ellipsoid", "number", ellipsoid=6378137.0),
                *each(("lat",), ("empty",)),
            ),
        ),
        "papers.gauss_kruger_ekf.paper_series": Call(
            dict(lat=0.45, lon=2.08, lon0=2.0944),
            elementwise=("*",),
            bad=(
                Bad("lon", "outside_zone", lat=26.0, lon=127.0, lon0=120.0, deg=True),
                Bad("lat, lon", "shape_mismatch", lat=np.zeros(3), lon=np.zeros(2), lon0=0.0),
                *each(("lat", "lon", "lon0"), ("empty",)),
            ),
        ),
        "papers.gauss_kruger_ekf.waypoint_path": Call(
            dict(waypoints=np.array([[0.0, 0.0], [10.0, 0.0], [10.0, 10.0]]), speed=5.0, turn_rate=0.5, T=0.5),
            bad=(
                Bad("waypoints", "repeated", waypoints=np.array([[0.0, 0.0], [0.0, 0.0]])),
                Bad("speed", "negative", speed=-1.0),
            ),
        ),
        # Sensors is a plain record: ekf validates its fields (a NaN field marks a dropout: tests/test_planar.py)
        "papers.gauss_kruger_ekf.ekf": Call(
            dict(t=0.5 * np.arange(N), sensors=gk, x0=np.array([0.0, 0.0, np.pi / 4, 1.0, 0.0]), origin=gk_origin),
            bad=(
                Bad("t", "non_monotonic", **ekf3(t=np.array([0.0, 1.0, 0.5]))),
                Bad("t", "repeated", **ekf3(t=np.array([0.0, 0.5, 0.5]))),
                Bad("t", "length", **ekf3(t=np.arange(4.0))),  # refused by filter_grid, under the user's name
                Bad("gps", "one_column", **ekf3(gps=gps3[:, :1])),
                Bad("gps", "all_nan", **ekf3(gps=np.full((3, 2), np.nan))),
                Bad("gps", "inf_lat", **ekf3(gps=gps3 + [[np.inf, 0.0]])),
                Bad("lat", "gps_lat2rad", **ekf3(gps=np.full((3, 2), [2.0, 2.1]))),
                Bad("heading", "length", **ekf3(heading=ones3[:2])),
                Bad("lon", "zone51", **ekf3(zone=51)),
                Bad("config", "list", **ekf3(config=[1.0])),
                Bad("sensors", "tuple", **ekf3(sensors=(gps3, ones3, ones3, ones3))),
                Bad("origin", "batch", **ekf3(origin=np.array([[0.45, 2.08]] * 2))),
                Bad("lat", "origin_lat2rad", **ekf3(origin=np.array([2.0, 2.08]))),
                Bad("zone", "200", **ekf3(zone=200)),
                Bad("width", "four", **ekf3(width=4)),
                *each(
                    ("gps", "heading", "speed", "yaw_rate"),
                    ("string", *numeric[:4], "minus_inf", "ragged"),
                    lambda a, v: {"sensors": dataclasses.replace(gk, **{a: v})},
                ),
                *each(("sensors", "config"), numeric),
                *each(("zone",), numeric, lambda a, v: {"zone": v, "origin": None}),
                *each(("correct_convergence", "deg"), ("complex", "object", "empty", "nan", "minus_inf", "ragged")),
            ),
        ),
        "papers.gauss_kruger_ekf.simulate_sensors": Call(
            dict(truth=gk_truth, origin=gk_origin, R=gauss_kruger_ekf.R_PAPER, rng=RNG),
            bad=(
                Bad("rng", "module", rng=Fresh(lambda: np.random)),
                Bad("gps_valid", "length", truth=np.zeros((3, 5)), gps_valid=np.array([True])),
                Bad("gps_valid", "integers", truth=np.tile(x5, (3, 1)), gps_valid=np.array([1, 0, 1])),
                *each(("gps_valid",), ("complex", "object", "empty", "nan", "minus_inf", "ragged")),
            ),
        ),
        "papers.gauss_kruger_ekf.Sensors": Skip("a result record, built by simulate_sensors (ekf validates its fields)"),
        "papers.gauss_kruger_ekf.dead_reckoning_error_ms": Call(dict(truth=gk_truth, T=0.5, R=gauss_kruger_ekf.R_PAPER)),
        "papers.gauss_kruger_ekf.ekf_error_ms": Call(
            dict(truth=gk_truth, T=0.5, Q=gauss_kruger_ekf.Q_PAPER, R=gauss_kruger_ekf.R_PAPER), bad=each(("P0",), numeric)
        ),
        "papers.mimu_mag_rtk.printed_eq2_roll": Call(dict(q=Q), elementwise=("*",), bad=(Bad("q", "zero", q=Q0),)),
        "papers.mimu_mag_rtk.printed_eq4": Call(dict(q=Q), elementwise=("*",), bad=(Bad("q", "zero", q=Q0),)),
        "papers.mimu_mag_rtk.printed_eq5_tilt": Call(dict(f_b=F[0]), elementwise=("*",)),
        "papers.mimu_mag_rtk.printed_eq7_heading": Call(dict(m_h=M[0]), elementwise=("*",)),
        "papers.mimu_mag_rtk.printed_eq8_quat": Call(dict(hpr=HPR), elementwise=("*",)),
        "papers.mimu_mag_rtk.printed_eq18_gamma": Call(
            dict(q=Q, dt=DT), bad=(Bad("dt", "negative", dt=-1.0), Bad("q", "zero", q=Q0))
        ),
        "papers.mimu_mag_rtk.printed_eq20_jacobian": Call(
            dict(q=Q, b=np.array([0.0, 20.0, -40.0])),
            bad=(Bad("b", "east_component", b=np.array([0.5, 1.0, 0.0])), Bad("q", "zero", q=Q0)),
        ),
        "papers.mimu_mag_rtk.printed_eq2_arctan": Call(dict(q=Q), elementwise=("*",), bad=(Bad("q", "zero", q=Q0),)),
        "papers.mimu_mag_rtk.printed_eq6": Call(dict(q=Q, b=np.array([0.0, 0.6, -0.8]))),
        "papers.mimu_mag_rtk.printed_eq12_mahony": Call(
            dict(w_ib_b=W, f_b=F, m_b=M, dt=DT, q0=Q, kp=1.0, ki=0.02),
            bad=(Bad("f_b", "length", f_b=F[:5]), Bad("m_b", "zero", m_b=np.zeros((N, 3))), Bad("dt", "zero", dt=0.0)),
        ),
        "papers.north_finding.Candidates": Skip("a result record, built by heading_candidates"),
        "papers.north_finding.heading_candidates": Call(
            dict(w_y=static_w[0, 1], f_b=static_f[0], lat=0.6, h=50.0), elementwise=("w_y", "lat", "h")
        ),
        "papers.north_finding.nearest_candidate_error": Call(
            dict(pair=np.array([0.3, 2.8]), heading=0.31), elementwise=("heading",)
        ),
        "papers.north_finding.Resolution": Skip("a result record, built by resolve"),
        "papers.north_finding.resolve": Call(
            dict(pair1=np.array([0.3, 2.8]), pair2=np.array([1.3, 1.8]), dpsi_ins=1.0), elementwise=("dpsi_ins",)
        ),
        "papers.north_finding.pitch_roll_from_accel": Call(dict(f_b=F[0], g=9.79)),
        "papers.north_finding.triad_heading_error": Call(
            dict(C_bn=C, dw_b=np.array([1e-6, 2e-6, 0.0]), lat=0.6), elementwise=("lat",)
        ),
        "papers.north_finding.triad_heading_std": Call(dict(sigma_gyro=1e-6, lat=0.6), elementwise=("*",)),
        "papers.north_finding.single_axis_heading_std": Call(
            dict(heading=0.3, sigma_gyro=1e-6, lat=0.6, pitch=0.1, sigma_accel=1e-3, g=9.79), elementwise=("*",)
        ),
        "papers.north_finding.single_axis_heading_error": Call(
            dict(heading=0.3, pitch=0.1, lat=0.6, dw_y=1e-6, df_y=1e-3, g=9.79), elementwise=("*",)
        ),
        "papers.north_finding.ClippedTheory": Skip("a result record, built by clipped_single_axis_theory"),
        "papers.north_finding.clipped_single_axis_theory": Call(
            dict(heading=0.3, sigma_gyro=1e-6, lat=0.6, pitch=0.1, sigma_accel=1e-3, g=9.79), elementwise=("heading", "pitch")
        ),
        "papers.north_finding.simulate_static_outputs": Call(
            dict(hpr=HPR, lat=0.6, n_trials=3, sigma_gyro=1e-6, sigma_accel=1e-3, rng=RNG)
        ),
        "papers.north_finding.MonteCarlo": Skip("a result record, built by monte_carlo"),
        "papers.north_finding.monte_carlo": Call(
            dict(
                headings=HEADINGS[:5] * 10, pitch=0.1, roll=-0.05, lat=0.6, n_trials=5, sigma_gyro=1e-6, sigma_accel=1e-3, rng=RNG
            )
        ),
        "papers.north_finding.pair_probabilities": Call(dict(heading1=0.3, heading2=1.0, sigma_ins=0.1), elementwise=("*",)),
        "papers.north_finding.four_position_heading_std": Call(dict(sigma_gyro=1e-6, lat=0.6), elementwise=("*",)),
        "papers.north_finding.stop_and_go": Call(
            dict(
                headings=HEADINGS[:5],
                stop_duration=2.0,
                drive_duration=30.0,
                speed=5.0,
                pitches=0.01 * np.arange(5.0),
                rolls=-0.01 * np.arange(5.0),
            )
        ),
        "papers.north_finding.StopSolutions": Skip("a result record, built by stop_solutions"),
        "papers.north_finding.stop_solutions": Call(dict(w_ib_b=W, f_b=F, windows=np.array([[0, 5], [5, 10]]), lat=0.6, h=50.0)),
        "papers.north_finding.ins_heading_change": Call(dict(w_ib_b=W, f_start=F[0], dt=DT, lat=0.6)),
        "papers.pedestrian_ins.carpark_legs": Call(
            dict(speed=1.2, stops=(8.0, 5.0, 20.0, 10.0, 6.0), side=(40.0, 24.0), n_loops=1, initial_stand=30.0)
        ),
        "papers.pedestrian_ins.floor_test_legs": Call(dict(stand=60.0, stairs=15.0, floor_height=3.0, n_round_trips=2)),
        "papers.pedestrian_ins.tilt_compensate_ned": Call(
            dict(H_b=np.array([20.0, 1.0, 40.0]), pitch=0.1, roll=-0.05), elementwise=("*",)
        ),
        "papers.pedestrian_ins.tilt_compensate_printed": Call(
            dict(H_b=np.array([20.0, 1.0, 40.0]), pitch=0.1, roll=-0.05), elementwise=("*",)
        ),
        "papers.pedestrian_ins.heading_from_horizontal": Call(dict(H_X=20.0, H_Y=1.0, declination=0.02), elementwise=("*",)),
        "papers.pedestrian_ins.hvac_pressure_steps": Call(
            dict(time=T * 100, door_times=HEADINGS[:5] * 25, rng=RNG, amplitude=10.0, n_trials=2)
        ),
        "papers.pedestrian_ins.simple_covariance_update": Call(
            dict(P=np.eye(3), H=np.array([[1.0, 0.0, 0.0]]), R=np.array([[0.5]]))
        ),
        "papers.rotation_bias.eq1_matrix": Call(dict(hpr=HPR), elementwise=("*",)),
        "papers.rotation_bias.gravity_body": Call(dict(tilt=np.array([0.1, -0.05]), g=9.80665)),
        "papers.rotation_bias.roll_pitch_from_accel": Call(dict(f_b=F[0])),
        "papers.rotation_bias.tilt_matrix": Call(
            dict(tilt=np.array([0.1, -0.05])),
            bad=(Bad("tilt[..., 1] (pitch)", "pitch_-90deg", tilt=np.array([0.0, -np.pi / 2])),),
        ),
        "papers.rotation_bias.rodrigues": Call(
            dict(axis_b=np.array([0.0, 0.0, 1.0]), angle=0.5),
            elementwise=("angle",),
            bad=(
                Bad("angle", "empty", angle=np.zeros(0)),
                Bad("axis_b", "not_unit", axis_b=np.array([1.0, 1.0, 0.0])),
                Bad("axis_b", "batch", axis_b=np.tile([0.0, 0.0, 1.0], (2, 1))),
            ),
        ),
        "papers.rotation_bias.rotate_attitude": Call(
            dict(hpr=HPR, axis_b=np.array([0.0, 0.0, 1.0]), angle=0.5),
            elementwise=("angle",),
            bad=(Bad("angle", "empty", angle=np.zeros(0)), Bad("axis_b", "not_unit", axis_b=np.array([0.0, 0.0, 2.0]))),
        ),
        "papers.rotation_bias.dwell_attitudes": Call(
            dict(hpr0=HPR, axis_b=np.array([0.0, 0.0, 1.0]), amplitude=1.5, n_dwells=2),
            bad=(
                Bad("axis_b", "through_pitch_90deg", hpr0=np.zeros(3), axis_b=np.array([1.0, 0.0, 0.0]), amplitude=np.pi / 2),
                Bad("hpr0", "batch", hpr0=np.zeros((2, 3))),
            ),
        ),
        "papers.rotation_bias.dwell_windows": Call(
            dict(n_samples=400, dt=DT, period=2.0, rotation_time=0.5, settle=0.1),
            bad=(Bad("period, rotation_time, settle", "no_dwell", period=5.0, rotation_time=4.95),),
        ),
        "papers.rotation_bias.Residuals": Skip("a result record, built by tilt_residuals"),
        "papers.rotation_bias.tilt_residuals": Call(
            dict(w_ib_b=dwell[0], f_b=dwell[1], dt=DT, starts=np.array([0, 20]), length=10, w_ie_b=np.zeros((2, 3))),
            bad=(
                Bad("length", "too_short", length=5),
                Bad("starts", "beyond_the_data", starts=np.array([0, 35])),
                Bad("f_b", "length", f_b=dwell[1][:30]),
                Bad("f_b", "pitch_90deg", f_b=np.tile([0.0, 9.8, 0.0], (40, 1))),
                Bad("w_ie_b", "per_dwell", w_ie_b=np.zeros((3, 3))),
                Bad("dt", "length", dt=np.full(39, DT)),
                Bad("max_missing", "above_half", max_missing=0.6),
                Bad("outlier_k", "zero", outlier_k=0.0),
                Bad("full_scale_gyro", "negative", full_scale_gyro=-1.0),
                Bad("full_scale_accel", "zero", full_scale_accel=0.0),
            ),
        ),
        "papers.rotation_bias.residual_covariance": Call(
            dict(tilt=np.array([[0.1, -0.05], [0.2, 0.0]]), length=10, dt=DT, gyro_noise=1e-3, accel_noise=1e-2),
            bad=(Bad("length", "three", length=3),),
        ),
        "papers.rotation_bias.lsq_bias": Call(
            dict(r=np.array([[1e-3, 2e-3]] * 4), V=V),
            bad=(
                Bad("V", "dwell_mismatch", V=V[:3]),
                Bad("V", "all_nan", r=np.full((4, 2), np.nan), V=np.full((4, 2, 3), np.nan)),
            ),
        ),
        "papers.rotation_bias.running_lsq_bias": Call(
            dict(r=np.array([[1e-3, 2e-3]] * 4), V=V, forgetting=0.99), bad=(Bad("forgetting", "zero", forgetting=0.0),)
        ),
        "papers.rotation_bias.KalmanBias": Skip("a result record, built by kalman_bias"),
        "papers.rotation_bias.kalman_bias": Call(
            dict(r=np.array([[1e-3, 2e-3]] * 4), V=V, R=R2 * 1e-6, interval=1.0, rate_random_walk=1e-6, bias_sigma=1e-3),
            bad=(
                Bad("gate", "inf", gate=np.inf),
                Bad("R", "nan", R=np.full((4, 2, 2), np.nan)),
                Bad("interval", "length", interval=np.ones(3)),
                Bad("interval", "zero", interval=0.0),
            ),
        ),
        "papers.rotation_bias.design": Call(
            dict(
                hpr0=HPR,
                axis_b=np.array([0.0, 0.0, 1.0]),
                amplitude=1.5,
                dwell_time=10.0,
                dt=DT,
                gyro_noise=1e-3,
                accel_noise=1e-2,
            ),
            bad=(Bad("dwell_time", "too_short", dwell_time=0.05), Bad("dt", "array", dt=np.array([0.01, 0.01]))),
        ),
        # ---------------------------------------------------------------------- pdr
        "pdr.StepResult": Skip("a result record, built by detect_steps"),
        "pdr.detect_steps": Call(dict(f_b=F + 3 * np.sin(_k), dt=0.2, threshold=1.0, min_interval=0.35)),
        "pdr.weinberg_step_length": Call(dict(peak_to_peak=2.5, K=0.45), elementwise=("peak_to_peak",)),
        "pdr.pdr": Call(
            dict(
                step_lengths=np.array([0.7, 0.8, 0.75, 0.7, 0.6]),
                step_headings=0.1 * np.arange(5.0),
                start_en=np.array([1.0, 2.0]),
            )
        ),
        "pdr.pdr_headings": Call(dict(f_b=F, m_b=M, step_index=np.array([1, 3, 5, 7, 8]), declination=0.02)),
        # -------------------------------------------------------------------- plots
        "plots.body_axes": Call(dict(ax=Fresh(_axes3d), C_bn=C, title="t")),
        "plots.allan": Call(dict(ax=Fresh(_axes2d), taus=taus, adev_rad_s=adev, theory=adev * 1.1), any_shape=("adev_rad_s",)),
        "plots.heading_deg": Call(dict(hpr=HPR), elementwise=("*",)),
        "papers.north_finding.draw_device": Call(dict(ax=Fresh(_axes2d), heading_deg=30.0)),
        "papers.north_finding.draw_candidate_pairs": Call(
            dict(ax=Fresh(_axes2d), heading1_deg=40.0, heading2_deg=130.0, dpsi_ins_error_deg=2.0)
        ),
        "papers.rotation_bias.draw_rotation_scheme": Call(dict(ax=Fresh(_axes2d), amplitude_deg=90.0, pitch_deg=30.0)),
        "papers.rotation_bias.draw_rotation_schedule": Call(
            dict(
                ax=Fresh(_axes2d),
                time=np.arange(0.0, 10.0, 0.1),
                angle_deg=np.where(np.arange(100) < 50, 0.0, 90.0),
                starts=np.array([5, 60]),
                length=30,
                dt=0.1,
            )
        ),
        "papers.rotation_bias.draw_flow": Call(dict(ax=Fresh(_axes2d))),
        "papers.gauss_kruger_ekf.draw_zones": Call(dict(ax=Fresh(_axes2d), lon_min=112.5, lon_max=127.5, mark=(26.06, 119.2))),
        "papers.gauss_kruger_ekf.draw_zone_grid": Call(
            dict(ax=Fresh(_axes2d), zone=40, lat_max=60.0, step_deg=0.5, mark=(26.06, 119.2))
        ),
        "papers.gauss_kruger_ekf.draw_block_diagram": Call(dict(ax=Fresh(_axes2d))),
        "papers.mimu_mag_rtk.draw_fusion_structure": Call(dict(ax=Fresh(_axes2d))),
        "papers.pedestrian_ins.draw_system": Call(dict(ax=Fresh(_axes2d))),
        "plots.paper_value": Call(dict(ax=Fresh(_axes2d), value=1.25, label="paper: 1.25°", axis="y", text_at=0.1)),
        "plots.block_diagram": Call(
            dict(
                ax=Fresh(_axes2d),
                blocks={"a": (0.2, 0.5, "IMU"), "b": (0.7, 0.5, "INS")},
                arrows=[("a", "b", "ω")],
                width=0.2,
                height=0.1,
                colors={"a": "0.8"},
            )
        ),
        "plots.plane_frame": Call(
            dict(ax=Fresh(_axes2d), origin=(0.0, 0.0), angle_deg=30.0, labels=("y", "x"), length=1.0, color="k")
        ),
        "plots.angle_arc": Call(
            dict(ax=Fresh(_axes2d), center=(0.0, 0.0), radius=0.5, start_deg=10.0, end_deg=80.0, label="ψ", color="k")
        ),
        # -------------------------------------------------------------------- repro
        "repro.root": Skip("takes no arguments"),
        "repro.build_dir": Call(dict(notebook="zz_fuzz")),
        "repro.setup": Call(dict(notebook="zz_fuzz", style=False)),
        "repro.savefig": Call(dict(fig=Fresh(_figure), name="fig"), before=_setup),
        "repro.check": Call(dict(name="T/x", value=1.0, expected=1.05, tol=0.1, source="src"), before=_setup),
        "repro.check_range": Call(dict(name="T/y", value=1.0, source="src", lower=0.5, upper=2.0), before=_setup),
        "repro.check_outside": Call(dict(name="T/z", value=3.0, source="src", lower=0.5, upper=2.0), before=_setup),
        "repro.verdict": Call(dict(claim="P000-EQ3-EULER", verdict="reproduced"), before=_setup_verdict),
        "repro.verdicts": Skip("takes no arguments"),
        "repro.summary": Skip("takes no arguments"),
        "repro.explorer": Call(dict(draw=_explorer_figure, name="explore", controls={"a": 1.0}), before=_setup),
        "repro.caption": Call(dict(markdown="**Figure 1** shows 1.25°.")),
        "repro.exercise": Call(dict(student=np.sin, reference=np.sin, cases=[(0.1,), (1.0,)])),
        "repro.Exercise": Skip("a result record, built by exercise"),
        "repro.answer": Call(dict(markdown="The error grows as 1/cos L: 1.7 times at 60°.", label="Answer")),
        "repro.study_k": Call(dict(n=12, about_mean=True)),
        "repro.env_flag": Call(dict(name="NAVLIB_FUZZ_UNSET_FLAG", default=True)),
        "repro.mode": Call(dict(teaching=True, fast=False), before=_setup),
        "repro.ClaimCheckWarning": Skip("warning class, issued by navlib itself"),
        "repro.Verdict": Skip("record of a verdict, built by verdict() from validated values"),
        "repro.results": Skip("takes no arguments"),
        "repro.ClaimCheckFailed": Skip("exception class, raised by navlib itself"),
        "repro.Check": Skip("record of a check, built by check()/check_range() from validated values"),
        "repro.NoOutputDirectory": Skip("exception class, raised by navlib itself"),
        # ------------------------------------------------------------------- robust
        "robust.FaultReport": Skip("a plain record of counts; nothing to validate"),
        "robust.Screened": Skip("a record of what screen found, built from validated values"),
        "robust.screen": Call(dict(imu=IMU, m_b=M)),
        "robust.fault_report": Call(dict(x=W, sensor="gyro", full_scale=1.0, flags=False), any_shape=("x",)),
        "robust.hold": Call(dict(x=np.where(VALID[:, None], W, np.nan), leading="raise"), any_shape=("x",)),
        "robust.despike": Call(dict(w_ib_b=W, f_b=F, spike_gyro=0.1, spike_accel=1.0)),
        "robust.stuck_mask": Call(dict(x=W, run=3), any_shape=("x",)),
        "robust.stuck_samples": Call(dict(x=W, run=3), any_shape=("x",)),
        "robust.longest_repeat": Call(dict(x=W, valid=VALID), any_shape=("x",)),
        # ------------------------------------------------------------------ sensors
        "sensors.TriadErrors": Call(
            dict(
                noise_density=1e-4,
                bias=1e-3,
                bias_instability=1e-5,
                correlation_time=100.0,
                rate_random_walk=1e-6,
                scale_factor=1e-3,
                misalignment=1e-3,
                full_scale=10.0,
            )
        ),
        "sensors.ImuModel": Call(
            dict(gyro=sensors.TriadErrors(noise_density=1e-4), accel=sensors.TriadErrors(bias=1e-3), name="m")
        ),
        "sensors.ImuOutput": Skip("record returned by simulate_imu, not constructed by users"),
        "sensors.window_mean_std": Call(
            dict(errors=sensors.TriadErrors(noise_density=1e-4, bias_instability=1e-5), duration=10.0, dt=DT)
        ),
        "sensors.simulate_imu": Call(dict(w_ib_b=W, f_b=F, dt=DT, model=sensors.imu_model("ADIS16475-1"), rng=RNG)),
        "sensors.simulate_imu_batches": Call(
            dict(w_ib_b=W, f_b=F, dt=DT, model=sensors.imu_model("ADIS16475-1"), rng=RNG, n_trials=3, batch=2)
        ),
        "sensors.imu_model": Call(dict(device="ADIS16475-1")),
        "sensors.preset": Call(dict(device="ADIS16475-1")),
        "sensors.devices": Skip("takes no arguments"),
        "sensors.MagnetometerModel": Call(dict(noise=0.1, hard_iron=1.0, soft_iron=0.01, full_scale=800.0)),
        "sensors.simulate_magnetometer": Call(
            dict(q_bn=np.tile(Q, (N, 1)), B_n=B_N, model=sensors.MagnetometerModel(noise=0.1), rng=RNG)
        ),
        "sensors.magnetic_disturbances": Call(dict(time=T * 100, rng=RNG, rate=0.1)),
        "sensors.BarometerModel": Call(dict(noise=0.1, bias=1.0, drift_rate=0.01)),
        "sensors.simulate_barometer": Call(dict(h=50.0 + T, time=T, model=sensors.BarometerModel(noise=0.1), rng=RNG)),
        "sensors.outage_mask": Call(dict(time=T, outages=[(0.02, 0.04)])),
        "sensors.simulate_gnss_position": Call(dict(lla=LLA, rng=RNG, sigma_horizontal=3.0, sigma_vertical=5.0, valid=VALID)),
        "sensors.simulate_heading": Call(dict(heading=HEADINGS, rng=RNG, sigma=0.01, valid=VALID)),
        "sensors.gauss_markov": Call(dict(shape=(N, 3), dt=DT, sigma=1e-3, correlation_time=10.0, rng=RNG)),
        # ---------------------------------------------------------------- strapdown
        "strapdown.integrate": Call(dict(lla0=LLA0, vel0=np.array([0.1, 0.2, 0.0]), q0=Q, w_ib_b=W, f_b=F, dt=DT)),
        "strapdown.integrate_attitude": Call(dict(q0=Q, w_ib_b=W, dt=DT, w_in_n=earth.earth_rate_n(0.6))),
        "strapdown.nav_step": Call(
            dict(lla=LLA0, vel=np.array([0.1, 0.2, 0.0]), q=Q, w=W[0], f=F[0], dt=DT, earth_consts=strapdown.earth_constants()),
            bad=(
                Bad("lla", "empty", lla=np.zeros(0)),
                Bad("lla", "shape2", lla=LLA0[:2]),
                Bad("lla", "lat45rad", lla=np.array([45.0, 0.2, 50.0])),
                Bad("vel", "empty", vel=np.zeros(0)),
                Bad("q", "shape3", q=np.array([1.0, 0.0, 0.0])),
                Bad("q", "zero", q=np.zeros(4)),
                Bad("w", "empty", w=np.zeros(0)),
                Bad("w", "shape2x3", w=np.zeros((2, 3))),
                Bad("f", "shape2", f=np.array([0.0, 9.8])),
                Bad("dt", "negative", dt=-0.01),
                Bad("dt", "zero", dt=0.0),
                Bad("dt", "array", dt=np.full(2, 0.01)),
                Bad("earth_consts", "shape6", earth_consts=strapdown.earth_constants()[:6]),
                Bad("earth_consts", "negative_a", earth_consts=-strapdown.earth_constants()),
                Bad("hold_height", "int", hold_height=1),
            ),
        ),
        "strapdown.earth_constants": Call(dict(ellipsoid=earth.WGS84)),
        "strapdown.error_model": Call(dict(lat=0.6, h=50.0, vel_n=np.array([1.0, 2.0, 0.0]), f_n=np.array([0.0, 0.1, 9.8]))),
        "strapdown.error_input": Call(dict(C_bn=C)),
        # ------------------------------------------------------------------- timing
        "timing.TimingReport": Skip("record returned by timing.sanitize, built from validated values"),
        "timing.sanitize": Call(dict(time=T)),
        "timing.intervals": Call(dict(time=T, n_samples=N - 1)),
        # --------------------------------------------------------------- trajectory
        "trajectory.Trajectory": Call(dict(time=_STATIC.time, lla=_STATIC.lla, vel_n=_STATIC.vel_n, q_bn=_STATIC.q_bn)),
        "trajectory.Segment": Call(dict(duration=2.0, speed=5.0, turn=0.1, pitch=0.01, roll=0.02)),
        "trajectory.static": Call(dict(duration=N * DT, dt=DT, lla0=LLA0, hpr=HPR)),
        "trajectory.from_profiles": Call(
            dict(time=T, lla0=LLA0, hpr=np.tile(HPR, (N, 1)) + 0.01 * _k, vel_n=np.zeros((N, 3)) + 0.1 * _k)
        ),
        "trajectory.reciprocating_rotation": Call(
            dict(
                duration=2.0,
                dt=0.1,
                lla0=LLA0,
                hpr0=HPR,
                axis_b=np.array([0.0, 0.0, 1.0]),
                amplitude=1.5,
                period=1.0,
                rotation_time=0.5,
            )
        ),
        "trajectory.vehicle": Call(dict(segments=[trajectory.Segment(0.5, speed=5.0)], dt=0.1, lla0=LLA0, heading0=0.3)),
        "trajectory.Leg": Call(dict(duration=2.0, speed=1.0, turn=0.1, climb=0.0)),
        "trajectory.Gait": Call(dict(step_frequency=1.8, bounce=0.025, ramp=1.0)),
        "trajectory.walk": Call(dict(legs=[trajectory.Leg(0.5, 1.0)], dt=0.05, lla0=LLA0, heading0=0.3)),
        "trajectory.stance_mask": Call(dict(legs=[trajectory.Leg(0.5, 1.0)], dt=0.05)),
        "trajectory.ideal_imu": Call(dict(traj=_STATIC)),
        "trajectory.smooth_ramp": Call(dict(x=np.array([0.2, 0.5, 0.9, 0.0, 1.0])), elementwise=("*",)),
        # -------------------------------------------------------------------- units
        "warmup.warmup": Skip("compiles every main kernel (half a minute on an empty cache): bench/cases_firstcall.py runs it"),
        "units.to_si": Call(dict(value=np.array([1.0, 2.0]), unit="deg/h"), elementwise=("value",)),
    }
    for name in units.__all__:  # the one-argument converters share one valid call
        if name not in ("to_si", "G0") and callable(getattr(units, name)):
            calls[f"units.{name}"] = Call(dict(x=np.array([1.0, 2.0])), elementwise=("*",))
    return calls
