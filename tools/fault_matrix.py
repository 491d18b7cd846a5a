#!/usr/bin/env python3
"""The fault matrix of issue 33: every fault kind x motion state x filter, handled vs ignored vs fault-free.

Each cell injects one fault into a seeded simulation (and, for the attitude filters, into the real x-io
recording of data/real/xio-fusion) and runs the filter three times: on the fault-free data, on the faulty data
with navlib's handling (the fault detected, counted in ``faults`` and acted on), and on the same faulty data
with the handling off (detection switched off, no gate: what a filter without it would do). The error
after the fault is measured against the truth (simulation) or the fault-free run (real recording).

The rule (tests/faults/test_fault_matrix.py): handling never costs more than ignoring, up to :data:`MARGIN`
of the mean error over the seeds, and every injected fault is counted in the handled run's ``faults``.

Simulation: 100 Hz, 20 s; the rig rotates about a fixed body axis (1, 1, 2)/sqrt(6) at 0 (still), 20 deg/s
(slow) or 200 deg/s (fast turn), starting at heading 90 deg, pitch 5, roll -3 deg; gyro noise 0.005 rad/s
and a bias drawn per seed (0.002 rad/s per axis, 1 sigma), accelerometer noise 0.02 m/s^2, magnetometer
noise 0.3 uT in a field of (0, 20, -40) uT (ENU). Faults start at 4 s; the error is the RMS attitude error
(deg) over the 16 s that follow. The planar EKF and dead reckoning run on the motion model of Zhao et al.
2023 (10 Hz, 60 s; speed 0, 5 or 10 m/s, turn rate 0, 10 or 60 deg/s; the paper's R for the noise); their
error is the RMS position error (m) over the 30 s after the fault. Heading fusion fuses a 100 Hz magnetic heading with 5 Hz RTK
heading; its error is the RMS heading error (deg) over the 16 s after the fault.

Usage: python tools/fault_matrix.py [--seeds 3] [--out build/fault_matrix.md] [--readme]
(``--readme`` also writes the table into README.md between the ``fault-matrix`` markers.)
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
import warnings
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

import functools  # noqa: E402

from navlib import alignment, attitude, io, strapdown, units  # noqa: E402
from navlib.filters import heading_fusion, planar_ekf, zupt_ins  # noqa: E402
from navlib.filters import mahony as mh  # noqa: E402
from navlib.filters import quaternion_kf as qkf  # noqa: E402
from navlib.filters.observations import AttitudeGates, MagGate, RtkHeading  # noqa: E402
from navlib.imu import ImuSamples, SensorLimits  # noqa: E402
from navlib.papers import gauss_kruger_ekf as gk  # noqa: E402

MARGIN = {"deg": float(np.rad2deg(0.005 * 1.0)), "m": 0.02 * 3.0}
"""Allowed excess of the handled error over the ignored one: what holding one noisy sample over the fault can cost
either way (handling and ignoring hold different samples, e.g. the last reading before a stuck run or the run's
own), the gyro noise times the 1 s fault, 0.29 deg, and for the planar filters the speed noise times the 3 s fault,
0.06 m."""

DT, N, K0 = 0.01, 2000, 400  # 100 Hz, 20 s, fault at 4 s
AFTER = slice(K0, N)  # the 16 s after the fault starts
AXIS = np.array([1.0, 1.0, 2.0]) / np.sqrt(6.0)
MOTIONS = {"still": 0.0, "slow": units.deg(20.0), "fast turn": units.deg(200.0)}
B_N = np.array([0.0, 20.0, -40.0])  # uT, ENU (no declination: magnetic north is north)
G = 9.80665
HPR0 = units.deg(np.array([90.0, 5.0, -3.0]))
FULL_SCALE = units.deg(150.0)  # the gyro range of the saturation cells (rad/s)

FAULTS = (
    "stuck 1 axis",
    "stuck 3 axes",
    "dropout",
    "spike",
    "saturation",
    "clock jump +",
    "clock jump -",
    "duplicate stamps",
    "free fall",
    "magnetic disturbance",
)
KEYS = {
    "stuck 1 axis": ("gyro", "stuck"),
    "stuck 3 axes": ("gyro", "stuck"),
    "dropout": ("gyro", "nan"),
    "spike": ("gyro", "spike"),
    "saturation": ("gyro", "saturated"),
    "clock jump +": ("clock", "jump"),
    "free fall": ("accel", "freefall"),
    "magnetic disturbance": ("mag", "outlier"),
}
"""The ``faults`` key that must count each fault (the timing faults - and + are refused by ImuSamples and
repaired by :func:`navlib.timing.sanitize`, which reports them)."""


@dataclasses.dataclass
class Rig:
    """Samples of the rotating rig: gyro, accelerometer, magnetometer (N, 3), intervals (N,), truth q (N, 4)."""

    w: np.ndarray
    f: np.ndarray
    m: np.ndarray
    dt: np.ndarray
    q: np.ndarray


def rig(rate: float, seed: int) -> Rig:
    """The rig rotating at ``rate`` (rad/s) about :data:`AXIS`, with sensor noise drawn from ``seed``."""
    rng = np.random.default_rng(seed)
    k = np.arange(1, N + 1)
    q0 = attitude.euler_to_quat(HPR0)
    q = attitude.quat_mult(q0, attitude.rotvec_to_quat(AXIS * rate * DT * k[:, None]))
    C_nb = np.swapaxes(attitude.quat_to_dcm(q), -1, -2)
    f = C_nb @ [0.0, 0.0, G] + rng.normal(0.0, 0.02, (N, 3))
    m = C_nb @ B_N + rng.normal(0.0, 0.3, (N, 3))
    w = AXIS * rate + rng.normal(0.0, 0.002, 3) + rng.normal(0.0, 0.005, (N, 3))
    return Rig(w, f, m, np.full(N, DT), q)


def angle_deg(q, q_ref) -> np.ndarray:
    """Rotation angle (deg) between attitudes."""
    d = np.abs(np.sum(q * q_ref, -1))
    return np.rad2deg(2 * np.arccos(np.clip(d, 0.0, 1.0)))


def rms(x) -> float:
    return float(np.sqrt(np.mean(np.square(x))))


# ----------------------------------------------------------------------------------------------------------
# Faults: the faulty rig, the limits/gates of the handled and the ignored run, or None where it cannot occur
# ----------------------------------------------------------------------------------------------------------

OFF = dict(stuck_run=None, max_dt=np.inf, freefall_accel=0.0)  # every default detection off


@dataclasses.dataclass
class Injected:
    """A faulty rig with the handled run's limits and gates, and the ignored run's (``ignored_rig``: data as a filter
    without the handling would see them, e.g. dropouts filled with 0)."""

    rig: Rig
    handled: SensorLimits
    ignored: SensorLimits
    gated: bool = False
    ignored_rig: Rig | None = None
    truth: np.ndarray | None = None  # truth after timing repairs (sanitize drops samples)


def inject(fault: str, r: Rig, k0: int = K0) -> Injected | None:
    """``fault`` injected into ``r`` from sample ``k0`` (1 s; dropouts 0.2 s, free fall 0.3 s, disturbance 2 s)."""
    w, f, m, dt = r.w.copy(), r.f.copy(), r.m.copy(), r.dt.copy()
    k1 = k0 + 100
    if fault == "stuck 1 axis":  # the output freezes at its last reading
        w[k0:k1, 0] = w[k0 - 1, 0]
    elif fault == "stuck 3 axes":
        w[k0:k1] = w[k0 - 1]
    elif fault == "dropout":
        w[k0 : k0 + 20], f[k0 : k0 + 20], m[k0 : k0 + 20] = np.nan, np.nan, np.nan
        zero = Rig(np.nan_to_num(w), np.nan_to_num(f), np.nan_to_num(m), dt, r.q)
        return Injected(Rig(w, f, m, dt, r.q), SensorLimits(), SensorLimits(**OFF), ignored_rig=zero)
    elif fault == "spike":
        w[k0:k1:20, 1] += 5.0
        return Injected(Rig(w, f, m, dt, r.q), SensorLimits(spike_gyro=1.0), SensorLimits())
    elif fault == "saturation":
        if np.max(np.abs(w)) < FULL_SCALE:
            return None  # the motion never reaches the rails
        w = np.clip(w, -FULL_SCALE, FULL_SCALE)
        return Injected(Rig(w, f, m, dt, r.q), SensorLimits(full_scale_gyro=FULL_SCALE), SensorLimits())
    elif fault == "clock jump +":
        dt[k0] = 0.2  # a stamp glitch: the samples are contiguous
    elif fault in ("clock jump -", "duplicate stamps"):
        return None  # refused by ImuSamples: see timing_cells
    elif fault == "free fall":
        f[k0 : k0 + 30] = np.random.default_rng(k0).normal(0.0, 0.3, (30, 3))  # |f| ~ 0.5 m/s^2
    elif fault == "magnetic disturbance":
        m[k0 : k0 + 200] += [30.0, 0.0, 0.0]
        return Injected(Rig(w, f, m, dt, r.q), SensorLimits(), SensorLimits(), gated=True)
    return Injected(Rig(w, f, m, dt, r.q), SensorLimits(), SensorLimits(**OFF))


# ----------------------------------------------------------------------------------------------------------
# The IMU filters
# ----------------------------------------------------------------------------------------------------------


def _attitude(filt, **gains):
    def run(r: Rig, limits: SensorLimits, gated: bool):
        gates = AttitudeGates(mag=MagGate()) if gated else AttitudeGates()
        res = filt(ImuSamples(r.w, r.f, r.dt, limits), r.q[0], m_b=r.m, B_n=B_N, gates=gates, **gains)
        return res.q_bn, res.faults

    return run


def _zupt_ins(r: Rig, limits: SensorLimits, gated: bool):
    still = np.linalg.norm(r.w, axis=-1) < 0.05
    with warnings.catch_warnings():  # a rig that never stands still has no ZUPT: the warning says so, as expected
        warnings.filterwarnings("ignore", "run_filter: no ZUPT/ZARU update", RuntimeWarning)
        res = zupt_ins.run_filter(
            ImuSamples(r.w, r.f, r.dt, limits),
            zupt_ins.Start(np.array([0.5, 0.2, 10.0]), r.q[0]),
            np.nan_to_num(still, nan=0.0).astype(bool),
            aiding=zupt_ins.Aiding("none"),
        )
    return res.nav.q_bn[1:], res.faults


def _strapdown(r: Rig, limits: SensorLimits, gated: bool):
    nav = strapdown.integrate(
        np.array([0.5, 0.2, 10.0]), np.zeros(3), r.q[0], ImuSamples(r.w, r.f, r.dt, limits), nan_policy="hold"
    )
    return nav.q_bn[1:], nav.faults


IMU_FILTERS = {
    "Mahony": _attitude(mh.mahony),
    "quaternion KF": _attitude(qkf.quaternion_kf),
    "ZUPT INS": _zupt_ins,
    "strapdown": _strapdown,
}
HANDLES = {"strapdown": ("dropout",)}
"""Faults a filter can act on at all (default: every IMU fault; strapdown.integrate is a free INS that holds
dropouts and uses no limits)."""


def imu_cell(name: str, fault: str, motion: str, seeds) -> dict | None:
    """Errors (deg) fault-free / handled / ignored, averaged over ``seeds``, and whether every run counted the fault."""
    if (
        name in HANDLES
        and fault not in HANDLES[name]
        or fault == "magnetic disturbance"
        and name not in ("Mahony", "quaternion KF")
    ):
        return None
    run = IMU_FILTERS[name]
    out = {"free": [], "handled": [], "ignored": [], "counted": True}
    for seed in seeds:
        r = rig(MOTIONS[motion], seed)
        inj = inject(fault, r)
        if inj is None:
            return None
        q_free, _ = run(r, SensorLimits(), False)
        q_h, faults = run(inj.rig, inj.handled, inj.gated)
        q_i, _ = run(inj.ignored_rig or inj.rig, inj.ignored, False)
        for key, q in (("free", q_free), ("handled", q_h), ("ignored", q_i)):
            out[key].append(rms(angle_deg(q[AFTER], r.q[AFTER])))
        out["counted"] &= bool(np.any(faults[KEYS[fault]]))
    return {k: float(np.mean(v)) if isinstance(v, list) else v for k, v in out.items()}


# ----------------------------------------------------------------------------------------------------------
# Planar EKF and dead reckoning (yaw-rate faults)
# ----------------------------------------------------------------------------------------------------------

PT, PN, PK0 = 0.1, 600, 200  # 10 Hz, 60 s, fault at 20 s
P_AFTER = slice(PK0, PK0 + 300)
PLANAR_MOTIONS = {"still": (0.0, 0.0), "slow": (5.0, units.deg(10.0)), "fast turn": (10.0, units.deg(60.0))}
PLANAR_RANGE = units.deg(50.0)  # yaw-rate gyro range of the saturation cells


def planar_data(motion: str, seed: int):
    v, omega = PLANAR_MOTIONS[motion]
    x0 = np.array([0.0, 0.0, 0.3, v, omega])
    truth = planar_ekf.propagate(x0, PT, PN - 1)
    rng = np.random.default_rng(seed)
    sigma = np.sqrt(np.diag(gk.R_PAPER))
    z = truth + rng.normal(0.0, 1.0, truth.shape) * sigma
    return np.arange(PN) * PT, z, truth, x0


def planar_inject(fault: str, t, z, motion):
    t, z = t.copy(), z.copy()
    k0, k1 = PK0, PK0 + 30
    limits, off = SensorLimits(), SensorLimits(**OFF)
    if fault == "stuck 1 axis":
        z[k0:k1, 4] = z[k0, 4]
    elif fault == "dropout":
        z[k0:k1, 4] = np.nan
        return t, z, limits, limits, np.nan_to_num(z)
    elif fault == "spike":
        z[k0:k1:10, 4] += 2.0
        return t, z, limits, limits, None  # the gate (handled) vs none (ignored)
    elif fault == "saturation":
        if np.max(np.abs(z[:, 4])) < PLANAR_RANGE:
            return None
        z[:, 4] = np.clip(z[:, 4], -PLANAR_RANGE, PLANAR_RANGE)
        limits = SensorLimits(full_scale_gyro=PLANAR_RANGE)
        return t, z, limits, SensorLimits(), None
    elif fault == "clock jump +":
        t[k0:] += 3.0
    else:
        return None
    return t, z, limits, off, None


GATE = [18.4, 15.1, 15.1, 15.1]


def _planar_run(name: str, t, z, x0, limits: SensorLimits, gate):
    """Positions (N, 2) and faults of the planar EKF (with GPS) or of dead reckoning (speed and yaw rate alone)."""
    if name == "planar EKF":
        res = planar_ekf.filter_grid(t, z, x0, planar_ekf.EkfConfig(gk.Q_PAPER, gk.R_PAPER, np.eye(5), gate, 3, limits))
        return res.x[:, :2], res.faults
    full_scale = None if np.isinf(limits.full_scale_gyro) else limits.full_scale_gyro
    x, faults = planar_ekf.dead_reckoning(t, z[:, 3], z[:, 4], x0, full_scale_gyro=full_scale, max_dt=limits.max_dt)
    return x[:, :2], faults


PLANAR_KEYS = {
    "stuck 1 axis": ("yaw_rate", "stuck"),
    "dropout": ("yaw_rate", "nan"),
    "spike": ("yaw_rate", "outlier"),
    "saturation": ("yaw_rate", "saturated"),
    "clock jump +": ("clock", "jump"),
}


def planar_cell(name: str, fault: str, motion: str, seeds) -> dict | None:
    """Position errors (m) fault-free / handled / ignored over ``seeds``, and whether every run counted the fault.
    Dead reckoning has no redundancy to find a spike or a stuck rate with (its docstring): those cells do not apply."""
    if name == "dead reckoning" and fault in ("spike", "stuck 1 axis"):
        return None
    out = {"free": [], "handled": [], "ignored": [], "counted": True}
    for seed in seeds:
        t, z, truth, x0 = planar_data(motion, seed)
        inj = planar_inject(fault, t, z, motion)
        if inj is None:
            return None
        tf, zf, lim_h, lim_i, z_ignored = inj
        p_free, _ = _planar_run(name, t, z, x0, SensorLimits(), np.inf)
        p_h, faults = _planar_run(name, tf, zf, x0, lim_h, GATE if fault == "spike" else np.inf)
        p_i, _ = _planar_run(name, tf, z_ignored if z_ignored is not None else zf, x0, lim_i, np.inf)
        for key, p in (("free", p_free), ("handled", p_h), ("ignored", p_i)):
            out[key].append(rms(np.linalg.norm(p[P_AFTER] - truth[P_AFTER, :2], axis=-1)))
        out["counted"] &= bool(np.any(faults[PLANAR_KEYS[fault]]))
    return {k: float(np.mean(v)) if isinstance(v, list) else v for k, v in out.items()}


# ----------------------------------------------------------------------------------------------------------
# Heading fusion (magnetic heading + RTK heading)
# ----------------------------------------------------------------------------------------------------------


def fusion_cell(fault: str, motion: str, seeds) -> dict | None:
    if fault not in ("spike", "dropout", "clock jump +", "magnetic disturbance"):
        return None
    rate = MOTIONS[motion]
    out = {"free": [], "handled": [], "ignored": [], "counted": True}
    for seed in seeds:
        rng = np.random.default_rng(seed)
        H = attitude.wrap_2pi(1.0 + rate * DT * np.arange(N))
        h_mag = H + 0.05 + rng.normal(0.0, units.deg(1.0), N)  # a magnetic heading 3 deg off, noisy
        epoch = np.arange(N) % 20 == 0
        rtk = attitude.wrap_2pi(H + rng.normal(0.0, units.deg(0.2), N))
        dt = np.full(N, DT)
        hm, hr, ok, dts = h_mag.copy(), rtk.copy(), epoch.copy(), dt.copy()
        gate, key = None, None
        if fault == "spike":
            k = np.arange(N) - K0
            flips = (k % 60 == 0) & (k >= 0) & (k < 200)  # every third epoch: isolated flips
            hr[flips] = attitude.wrap_2pi(hr[flips] + np.pi)
            gate, key = units.deg(20.0), ("heading", "outlier")
        elif fault == "dropout":
            hr[K0 : K0 + 200] = np.nan
            key = ("heading", "nan")
        elif fault == "clock jump +":
            dts[K0] = 0.2
            key = ("clock", "jump")
        else:
            hm[K0 : K0 + 200] += units.deg(30.0)
            gate, key = units.deg(20.0), ("mag", "outlier")

        def run(h, r, v, d, g, max_dt=None):
            return heading_fusion.fuse_rtk_heading(h, RtkHeading(r, v, gate=g), d, max_dt=max_dt)

        free = run(h_mag, rtk, epoch, dt, None)
        handled = run(hm, hr, ok, dts, gate)
        ignored = run(hm, np.nan_to_num(hr), ok, dts, None, np.inf)
        for k, res in (("free", free), ("handled", handled), ("ignored", ignored)):
            err = np.rad2deg(attitude.wrap_pi(res.heading[AFTER] - H[AFTER]))
            out[k].append(rms(err))
        out["counted"] &= key is None or bool(np.any(handled.faults[key]))
    return {k: float(np.mean(v)) if isinstance(v, list) else v for k, v in out.items()}


# ----------------------------------------------------------------------------------------------------------
# The real recording
# ----------------------------------------------------------------------------------------------------------


@functools.lru_cache(maxsize=1)
def _recording():
    return io.read_xio(REPO / "data/real/xio-fusion/sensor_data.csv", timing="sanitize")


@functools.cache
def real_cells(fault: str) -> dict:
    """Mahony (ki = 0) on the x-io recording with its magnetometer: the fault injected at its stillest and at its
    fastest second; error (deg) against the fault-free run over the 16 s after the fault. ki = 0 because with the
    default 0.02 the fault-free run itself learns a bias of (-0.36, 0.79, 0.05) deg/s on this hand motion (about
    0.01 deg/s in truth): no reference to measure a fault's cost against."""
    rec = _recording()
    imu = rec.imu()
    rate = np.convolve(np.linalg.norm(imu.w_ib_b, axis=-1), np.ones(100), "valid")[:-1700]
    at_rest = rec.time < 1.0
    q0 = alignment.initial_attitude(np.nanmean(rec.f_b[at_rest], 0), np.nanmean(rec.m_b[at_rest], 0))
    run = _attitude(mh.mahony, ki=0.0)
    r = Rig(imu.w_ib_b, imu.f_b, rec.m_b, imu.dt, np.broadcast_to(q0, (imu.n, 4)))
    q_free, _ = run(r, SensorLimits(), False)
    out = {}
    for motion, k0 in (("still", int(np.argmin(rate))), ("fast turn", int(np.argmax(rate)))):
        inj = inject(fault, r, k0)
        if inj is None:
            continue
        q_h, faults = run(inj.rig, inj.handled, inj.gated)
        q_i, _ = run(inj.ignored_rig or inj.rig, inj.ignored, False)
        after = slice(k0, k0 + 1600)
        out[motion] = {
            "free": 0.0,
            "handled": rms(angle_deg(q_h[after], q_free[after])),
            "ignored": rms(angle_deg(q_i[after], q_free[after])),
            "counted": bool(np.any(faults[KEYS[fault]])),
        }
    return out


# ----------------------------------------------------------------------------------------------------------
# The table
# ----------------------------------------------------------------------------------------------------------

PLANAR = ("planar EKF", "dead reckoning")
FILTERS = ("Mahony", "quaternion KF", "heading fusion", "planar EKF", "dead reckoning", "ZUPT INS", "strapdown")


def cell(name: str, fault: str, motion: str, seeds) -> dict | None:
    if name in PLANAR:
        return planar_cell(name, fault, motion, seeds)
    if name == "heading fusion":
        return fusion_cell(fault, motion, seeds)
    return imu_cell(name, fault, motion, seeds)


def matrix(seeds) -> list[dict]:
    rows = []
    for fault in FAULTS:
        for name in FILTERS:
            for motion in MOTIONS:
                c = cell(name, fault, motion, seeds)
                if c is not None:
                    rows.append(dict(fault=fault, filter=name, motion=motion, **c))
        if fault in KEYS and fault != "saturation":
            for motion, c in real_cells(fault).items():
                rows.append(dict(fault=fault, filter="Mahony (x-io real)", motion=motion, **c))
    return rows


def unit(name: str) -> str:
    return "m" if name in PLANAR else "deg"


def table(rows: list[dict], seeds) -> str:
    """Every cell: errors fault-free / handled / ignored, the margin ignored - handled, counted."""
    lines = [
        f"Error after the fault (mean over seeds {list(seeds)}; deg, m for the planar filters): fault-free, with "
        "the handling, with it off; margin = ignored - handled (the rule: >= -MARGIN, "
        f"{MARGIN['deg']:.2f} deg / {MARGIN['m']:.2f} m); counted: the fault is in `faults`. "
        "Generated by `tools/fault_matrix.py`.",
        "",
        "| fault | filter | motion | fault-free | handled | ignored | margin | counted |",
        "|---|---|---|---:|---:|---:|---:|:---:|",
    ]
    for r in rows:
        lines.append(
            f"| {r['fault']} | {r['filter']} | {r['motion']} | {r['free']:.2f} | {r['handled']:.2f} | "
            f"{r['ignored']:.2f} | {r['ignored'] - r['handled']:+.2f} {unit(r['filter'])} | "
            f"{'yes' if r['counted'] else 'NO'} |"
        )
    return "\n".join(lines) + "\n"


def summary(rows: list[dict]) -> str:
    """Fault x filter: the smallest margin ignored - handled over the motions (a dash: does not apply)."""
    names = list(FILTERS) + ["Mahony (x-io real)"]
    lines = ["| fault | " + " | ".join(names) + " |", "|---|" + "---:|" * len(names)]
    for fault in FAULTS:
        cells = []
        for name in names:
            rs = [r for r in rows if r["fault"] == fault and r["filter"] == name]
            m = min((r["ignored"] - r["handled"] for r in rs), default=None)
            mark = "" if all(r["counted"] for r in rs) else " (not counted)"
            cells.append("-" if m is None else f"{m:+.2f}{mark}")
        lines.append(f"| {fault} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--out", default=str(REPO / "build" / "fault_matrix.md"))
    ap.add_argument("--readme", action="store_true", help="write the table into README.md between the markers")
    opts = ap.parse_args(argv)
    seeds = range(opts.seeds)
    rows = matrix(seeds)
    out = Path(opts.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(table(rows, seeds))
    print(table(rows, seeds))
    if opts.readme:
        readme = REPO / "README.md"
        s = readme.read_text()
        a, b = "<!-- fault-matrix:start -->\n", "<!-- fault-matrix:end -->"
        if a not in s or b not in s:
            print("README.md has no fault-matrix markers", file=sys.stderr)
            return 1
        readme.write_text(s[: s.index(a) + len(a)] + summary(rows) + s[s.index(b) :])
    return 0


if __name__ == "__main__":
    sys.exit(main())
