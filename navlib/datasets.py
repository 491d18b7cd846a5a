"""Benchmark datasets with an independent orientation reference, read into navlib's records and frames.

* :func:`read_broad`: one trial of BROAD, the Berlin Robust Orientation Evaluation dataset (Laidig, Caruso,
  Cereatti & Seel, "BROAD -- A Benchmark for Robust Inertial Orientation Estimation", *Data* 6(7):72, 2021):
  a MARG IMU at 285.7 Hz with an optical (motion-capture) orientation reference, in the ``.npz`` form of
  ``tools/broad_to_npz.py`` (data/real/broad/, data/real/README.md).
* :func:`broad_split`: the trial names split into tuning and held-out trials by the parity of their number.

Frames. BROAD gives the IMU's samples in the sensor's own axes and the reference as the scalar-first unit
quaternion from the sensor axes to an east-north-up frame whose north is magnetic north. navlib's body frame
is the frame of the samples (x, y, z called right, front, up; BROAD's sensor lies with z up at rest) and its
navigation frame is ENU, so the reference is already navlib's ``q_bn`` (``v_n = q (x) v_b (x) q*``) and the
samples need no axis change: gyro in rad/s, specific force in m/s^2 (+9.8 on the up axis at rest), field in
uT. The reference's heading therefore agrees with a magnetometer-based estimate up to a constant offset (the
optical frame's alignment), which :func:`navlib.analysis.orientation_errors` removes per trial.
"""
from __future__ import annotations

import os
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ._validate import text
from .imu import ImuSamples
from .io import Recording

__all__ = ["ReferenceTrial", "read_broad", "broad_split"]


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
        return self.recording.m_b

    @property
    def rate(self) -> float:
        """Sampling rate (Hz)."""
        return 1.0 / float(self.recording.dt[0])


def read_broad(path: str | os.PathLike) -> ReferenceTrial:
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
    """
    path = Path(path)
    with np.load(path, allow_pickle=False) as z:
        missing = {"gyr", "acc", "mag", "opt_quat", "movement", "sampling_rate"} - set(z.files)
        if missing:
            raise ValueError(f"path: {path.name} is not a converted BROAD trial (no {sorted(missing)}); "
                             f"convert the source .mat with tools/broad_to_npz.py")
        w, f, m = (np.ascontiguousarray(z[k], dtype=float) for k in ("gyr", "acc", "mag"))
        q, movement, rate = z["opt_quat"].astype(float), z["movement"].astype(bool), float(z["sampling_rate"].reshape(-1)[0])
    n = w.shape[0]
    if not (f.shape == m.shape == (n, 3) and q.shape == (n, 4) and movement.shape == (n,)):
        raise ValueError(f"path: {path.name} has arrays of different lengths")
    q /= np.linalg.norm(q, axis=1, keepdims=True)     # float32-rounded in the file; NaN rows stay NaN
    q *= np.where(q[:, :1] < 0, -1.0, 1.0)            # navlib's sign: q0 >= 0
    recording = Recording(np.arange(n) / rate, w, f, m, source=str(path),
                          conversions=("BROAD sensor axes = body axes, reference sensor-to-ENU = q_bn; "
                                       "rad/s, m/s^2, uT as stored",))
    return ReferenceTrial(path.stem, recording, q, movement)


def broad_split(names: list[str]) -> tuple[list[str], list[str]]:
    """Split BROAD trial names into ``(tuning, held_out)``: even trial numbers tune, odd ones are held out.

    On the 30 trials of the source repository this gives 16 and 14 (4 of them with a magnetic disturbance).
    """
    numbers = []
    for name in names:
        match = re.match(r"(\d+)_", text(name, "names"))
        if match is None:
            raise ValueError(f"names: {name!r} does not start with a BROAD trial number like '07_'")
        numbers.append(int(match.group(1)))
    return ([n for n, k in zip(names, numbers, strict=True) if k % 2 == 0],
            [n for n, k in zip(names, numbers, strict=True) if k % 2 == 1])
