"""Benchmark datasets with an independent orientation reference, read into navlib's records and frames.

* :func:`read_broad`: one trial of BROAD, the Berlin Robust Orientation Evaluation dataset (Laidig, Caruso,
  Cereatti & Seel, "BROAD -- A Benchmark for Robust Inertial Orientation Estimation", *Data* 6(7):72, 2021):
  a MARG IMU at 285.7 Hz with an optical (motion-capture) orientation reference, in the ``.npz`` form of
  ``tools/broad_to_npz.py`` (data/real/broad/, data/real/README.md).
* :func:`broad_split`: the trial names split into tuning and held-out trials by the parity of their number.
* :func:`read_comma2k19`: one segment of comma.ai's comma2k19 driving dataset (Schafer, Santana, Haden & Biasini,
  "A Commute in Data: The comma2k19 Dataset", arXiv:1812.05752, 2018; MIT): phone-grade IMU, magnetometer,
  u-blox fixes, CAN speeds and a reference pose from the authors' offline fusion (data/real/comma2k19/).

Frames. BROAD gives the IMU's samples in the sensor's own axes and the reference as the scalar-first unit
quaternion from the sensor axes to an east-north-up frame whose north is magnetic north. navlib's body frame
is the frame of the samples (x, y, z called right, front, up; BROAD's sensor lies with z up at rest) and its
navigation frame is ENU, so the reference is already navlib's ``q_bn`` (``v_n = q (x) v_b (x) q*``) and the
samples need no axis change: gyro in rad/s, specific force in m/s^2 (+9.8 on the up axis at rest), field in
uT. The reference's heading therefore agrees with a magnetometer-based estimate up to a constant offset (the
optical frame's alignment), which :func:`navlib.analysis.orientation_errors` removes per trial.

comma2k19 gives the IMU in forward-right-down axes (specific force -9.8 on down at rest) and the reference
orientation as the quaternion whose rotation takes camera forward-right-down vectors into ECEF (checked: the
camera's forward axis so rotated points along the reference velocity). navlib's body axes are right-front-up, so
``v_rfu = (v_frd[1], v_frd[0], -v_frd[2])`` for every body vector, and ``C_bn = C_en C_ecef,frd M`` with ``M`` that
axis swap and ``C_en`` ECEF to the local ENU frame of each reference point. All times are the logs' boot clock
less the first IMU sample's time.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from . import attitude, geodesy
from ._validate import FilePath, boundary, text, time_axis
from .imu import ImuSamples
from .io import Recording, align

__all__ = ["ReferenceTrial", "read_broad", "broad_split", "DriveLog", "read_comma2k19"]


@dataclass(frozen=True)
class ReferenceTrial:
    """A recording with an independent orientation reference.

    Attributes
    ----------
    name : str
        The trial's name, e.g. ``"07_undisturbed_fast_rotation_B"``.
    recording : Recording
        Time (s), gyro ``w_ib_b`` (rad/s), specific force ``f_b`` (m/s^2), field ``m_b`` (uT), shape (N, 3).
    q_ref : ndarray, shape (N, 4)
        Reference attitude ``q_bn`` (scalar first, body to ENU; magnetic north); NaN rows where the
        reference has no sample.
    movement : ndarray, shape (N,), bool
        The samples over which the benchmark's errors are taken (its movement phases).

    Examples
    --------
    >>> from navlib import repro, datasets
    >>> trial = datasets.read_broad(repro.root() / "data" / "real" / "broad" / "07_undisturbed_fast_rotation_B.npz")
    >>> trial.name, trial.q_ref.shape[1], trial.movement.dtype
    ('07_undisturbed_fast_rotation_B', 4, dtype('bool'))
    """

    name: str
    recording: Recording
    q_ref: np.ndarray
    movement: np.ndarray

    @property
    def imu(self) -> ImuSamples:
        """Gyro and accelerometer samples with their intervals (:class:`navlib.imu.ImuSamples`)."""
        return self.recording.imu()

    @property
    def m_b(self) -> np.ndarray:
        """Magnetometer samples (uT), shape (N, 3)."""
        assert self.recording.m_b is not None  # the loader requires the "mag" array
        return self.recording.m_b

    @property
    def rate(self) -> float:
        """Sampling rate (Hz): one over the median interval."""
        return 1.0 / float(np.median(self.recording.dt))


@boundary
def read_broad(path: FilePath) -> ReferenceTrial:
    """Read one BROAD trial converted by ``tools/broad_to_npz.py``.

    Parameters
    ----------
    path : str or path-like
        The trial's ``.npz`` file, e.g. ``data/real/broad/07_undisturbed_fast_rotation_B.npz``.

    Returns
    -------
    ReferenceTrial
        In navlib's frames (module docstring): no axis change, units already SI and uT.

    Raises
    ------
    FileNotFoundError
        If there is no such file.
    ValueError
        If the file lacks one of BROAD's arrays or their lengths differ.

    Examples
    --------
    >>> from navlib import repro, datasets
    >>> trial = datasets.read_broad(repro.root() / "data" / "real" / "broad" / "07_undisturbed_fast_rotation_B.npz")
    >>> trial.recording.w_ib_b.shape == trial.q_ref.shape[:1] + (3,)
    True
    """
    with np.load(path, allow_pickle=False) as z:
        missing = {"gyr", "acc", "mag", "opt_quat", "movement", "sampling_rate"} - set(z.files)
        if missing:
            raise ValueError(
                f"path: {path.name} is not a converted BROAD trial (no {sorted(missing)}); "
                f"convert the source .mat with tools/broad_to_npz.py"
            )
        w, f, m = (np.ascontiguousarray(z[k], dtype=float) for k in ("gyr", "acc", "mag"))
        q, movement, rate = z["opt_quat"].astype(float), z["movement"].astype(bool), float(z["sampling_rate"].reshape(-1)[0])
    n = w.shape[0]
    if not (f.shape == m.shape == (n, 3) and q.shape == (n, 4) and movement.shape == (n,)):
        raise ValueError(f"path: {path.name} has arrays of different lengths")
    q /= np.linalg.norm(q, axis=1, keepdims=True)  # float32-rounded in the file; NaN rows stay NaN
    q *= np.where(q[:, :1] < 0, -1.0, 1.0)  # navlib's sign: q0 >= 0
    recording = Recording(
        time_axis(np.arange(n) / rate, "path"),  # the recording's times, checked once (a rate <= 0 or NaN in the file)
        w,
        f,
        m,
        source=str(path),
        conversions=("BROAD sensor axes = body axes, reference sensor-to-ENU = q_bn; rad/s, m/s^2, uT as stored",),
    )
    return ReferenceTrial(path.stem, recording, q, movement)


def broad_split(names: list[str]) -> tuple[list[str], list[str]]:
    """Split BROAD trial names into ``(tuning, held_out)``: even trial numbers tune, odd ones are held out.

    On the 30 trials of the source repository this gives 16 and 14 (4 of them with a magnetic disturbance).

    Examples
    --------
    >>> from navlib import datasets
    >>> datasets.broad_split(["02_undisturbed_slow_rotation_B", "07_undisturbed_fast_rotation_B"])   # even tune, odd held out
    (['02_undisturbed_slow_rotation_B'], ['07_undisturbed_fast_rotation_B'])
    """
    if not isinstance(names, (list, tuple)):
        raise ValueError(
            f"names: expected a list of trial names such as ['07_undisturbed_fast_rotation_B'], got {type(names).__name__}"
        )
    numbers = []
    for name in names:
        match = re.match(r"(\d+)_", text(name, "names"))
        if match is None:
            raise ValueError(f"names: {name!r} does not start with a BROAD trial number like '07_'")
        numbers.append(int(match.group(1)))
    return (
        [n for n, k in zip(names, numbers, strict=True) if k % 2 == 0],
        [n for n, k in zip(names, numbers, strict=True) if k % 2 == 1],
    )


_FRD_TO_RFU = np.array([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]])  # v_rfu = M v_frd (and back)


@dataclass(frozen=True)
class DriveLog:
    """A car drive with a reference trajectory, every series on its own clock (s from the first IMU sample).

    Attributes
    ----------
    imu : Recording
        Gyro ``w_ib_b`` (rad/s) and specific force ``f_b`` (m/s^2), right-front-up, shape (N, 3).
    mag_time, m_b : ndarray, shapes (M,), (M, 3)
        Magnetometer times and readings (uT, right-front-up, as logged: the source's unit label says T).
    gnss_time, gnss : ndarray, shapes (K,), (K, 6)
        u-blox fixes: latitude, longitude (deg), speed (m/s), UTC (ms since the epoch), height (m), bearing (deg).
    can_time, can_speed, wheel_speeds : ndarray, shapes (L,), (L,), (L, 4)
        CAN vehicle speed and wheel speeds (front left, front right, rear left, rear right; m/s).
    ref_time, ref_lla, ref_v_n, ref_q_bn : ndarray, shapes (R,), (R, 3), (R, 3), (R, 4)
        Reference pose: latitude, longitude (rad), height (m, WGS84); ENU velocity (m/s); attitude ``q_bn``
        of the right-front-up body (camera axes) in the local ENU frame.

    Examples
    --------
    >>> from navlib import repro, datasets
    >>> log = datasets.read_comma2k19(repro.root() / "data" / "real" / "comma2k19")
    >>> log.imu.w_ib_b.shape[1], log.ref_lla.shape[1], log.ref_q_bn.shape[1]
    (3, 3, 4)
    """

    imu: Recording
    mag_time: np.ndarray
    m_b: np.ndarray
    gnss_time: np.ndarray
    gnss: np.ndarray
    can_time: np.ndarray
    can_speed: np.ndarray
    wheel_speeds: np.ndarray
    ref_time: np.ndarray
    ref_lla: np.ndarray
    ref_v_n: np.ndarray
    ref_q_bn: np.ndarray

    def attitude_trial(self) -> ReferenceTrial:
        """The drive as an attitude benchmark: the IMU with the magnetometer held between its readings (the
        latest reading, as a real-time filter has it; the first reading also before it) and the reference
        attitude interpolated to the IMU's times (component-wise, normalised: 20 Hz against a car's rates);
        scored over the reference's time span."""
        t = self.imu.time
        held = align(t, self.mag_time, self.m_b, max_gap=float(t[-1] - t[0]) + 1.0)
        held[np.isnan(held[:, 0])] = self.m_b[0]
        q = np.stack([np.interp(t, self.ref_time, self.ref_q_bn[:, i]) for i in range(4)], -1)
        recording = Recording(
            t,
            self.imu.w_ib_b,
            self.imu.f_b,
            held,
            start=self.imu.start,
            source=self.imu.source,
            conversions=self.imu.conversions + ("magnetometer held between readings",),
        )
        inside = (t >= self.ref_time[0]) & (t <= self.ref_time[-1])
        return ReferenceTrial("comma2k19 Example_1", recording, attitude.quat_normalize(q), inside)


def _ecef_to_enu(lat: np.ndarray, lon: np.ndarray) -> np.ndarray:
    """C_en (..., 3, 3): ECEF vectors to the local ENU frame at (lat, lon) (rad)."""
    sl, cl, so, co = np.sin(lat), np.cos(lat), np.sin(lon), np.cos(lon)
    z = np.zeros_like(lat)
    return np.stack(
        [np.stack([-so, co, z], -1), np.stack([-sl * co, -sl * so, cl], -1), np.stack([cl * co, cl * so, sl], -1)], -2
    )


@boundary
def read_comma2k19(folder: FilePath) -> DriveLog:
    """Read one comma2k19 segment as committed in data/real/comma2k19/ (the source's ``.npy`` logs, renamed
    ``<sensor>.<log>.<t|value>.npy`` and ``global_pose.<name>.npy``).

    Parameters
    ----------
    folder : str or path-like

    Returns
    -------
    DriveLog
        In navlib's frames and units (module docstring).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import repro, datasets
    >>> log = datasets.read_comma2k19(repro.root() / "data" / "real" / "comma2k19")
    >>> round(float(np.nanmax(log.can_speed)), 1) > 0                  # the car moves (m/s)
    True
    """

    def load(name: str) -> NDArray[Any]:
        path = folder / f"{name}.npy"
        if not path.is_file():
            raise FileNotFoundError(f"folder: {folder} has no {path.name} (a comma2k19 segment as in data/real/comma2k19/)")
        return np.load(path, allow_pickle=False)

    t_imu = load("IMU.gyro.t")
    if not np.array_equal(t_imu, load("IMU.accelerometer.t")):
        raise ValueError("folder: gyro and accelerometer logs have different times")
    t0 = float(t_imu[0])
    imu = Recording(
        time_axis(t_imu - t0, "folder"),  # the recording's times, checked once
        load("IMU.gyro.value") @ _FRD_TO_RFU.T,
        load("IMU.accelerometer.value") @ _FRD_TO_RFU.T,
        start=t0,
        source=str(folder),
        conversions=("forward-right-down -> right-front-up: (x, y, z) -> (y, x, -z)",),
    )
    pos = load("global_pose.frame_positions")
    lat, lon, h = geodesy.ecef2geodetic(pos[:, 0], pos[:, 1], pos[:, 2])
    C_en = _ecef_to_enu(lat, lon)
    C_bn = C_en @ attitude.quat_to_dcm(load("global_pose.frame_orientations")) @ _FRD_TO_RFU
    return DriveLog(
        imu,
        load("IMU.magnetometer.t") - t0,
        load("IMU.magnetometer.value") @ _FRD_TO_RFU.T,
        load("GNSS.live_gnss_ublox.t") - t0,
        load("GNSS.live_gnss_ublox.value"),
        load("CAN.speed.t") - t0,
        load("CAN.speed.value")[:, 0],
        load("CAN.wheel_speed.value"),
        load("global_pose.frame_times") - t0,
        np.stack([lat, lon, h], -1),
        np.einsum("kij,kj->ki", C_en, load("global_pose.frame_velocities")),
        attitude.dcm_to_quat(C_bn),
    )
