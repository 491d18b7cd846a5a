"""Convert BROAD trials (Laidig et al. 2021, github.com/dlaidig/broad, CC BY 4.0) from their MATLAB files into
the compact ``.npz`` files of data/real/broad/ that :func:`navlib.datasets.read_broad` reads.

What is kept, and how (data/real/README.md says the same):

* ``imu_gyr``, ``imu_acc``, ``imu_mag`` (rad/s, m/s^2, uT): float64, bit for bit;
* ``opt_quat`` (scalar-first, sensor to ENU): rounded to float32 (at most 1e-5 deg of rotation, far below the
  optical system's accuracy), NaN rows (marker dropouts) kept;
* ``movement`` (bool) and ``sampling_rate`` unchanged; ``opt_pos`` dropped (the orientation benchmark does not use it);
* samples more than ``--tail`` seconds after the last movement sample dropped (the rest after the motion; the
  benchmark's errors are taken over the movement phases only, and a causal filter never sees later samples).

The arrays are stored column-major in a zip with LZMA compression, which ``numpy.load`` reads as an npz.
Usage: ``python tools/broad_to_npz.py OUT_DIR TRIAL.mat ...`` (prints the SHA-256 of input and output).
"""

from __future__ import annotations

import argparse
import hashlib
import io
import zipfile
from pathlib import Path

import numpy as np
import scipy.io


def convert(mat: Path, out_dir: Path, tail: float) -> Path:
    d = scipy.io.loadmat(mat)
    rate = float(d["sampling_rate"].item())
    movement = d["movement"].ravel().astype(bool)
    end = min(movement.size, int(np.flatnonzero(movement)[-1]) + 1 + int(round(tail * rate)))
    arrays = {
        "gyr": d["imu_gyr"][:end],
        "acc": d["imu_acc"][:end],
        "mag": d["imu_mag"][:end],
        "opt_quat": d["opt_quat"][:end].astype(np.float32),
        "movement": movement[:end],
        "sampling_rate": np.array(rate),
    }
    out = out_dir / (mat.stem + ".npz")
    with zipfile.ZipFile(out, "w", compression=zipfile.ZIP_LZMA) as z:
        for name, a in arrays.items():
            buf = io.BytesIO()
            np.save(buf, np.asfortranarray(a), allow_pickle=False)
            info = zipfile.ZipInfo(name + ".npy", date_time=(1980, 1, 1, 0, 0, 0))  # fixed: byte-identical reruns
            info.compress_type = zipfile.ZIP_LZMA
            z.writestr(info, buf.getvalue())
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out_dir", type=Path)
    parser.add_argument("mats", type=Path, nargs="+")
    parser.add_argument("--tail", type=float, default=5.0, help="seconds kept after the last movement sample")
    args = parser.parse_args()
    args.out_dir.mkdir(parents=True, exist_ok=True)
    for mat in args.mats:
        out = convert(mat, args.out_dir, args.tail)
        print(
            hashlib.sha256(mat.read_bytes()).hexdigest(),
            mat.name,
            "->",
            hashlib.sha256(out.read_bytes()).hexdigest(),
            out.name,
            f"{out.stat().st_size / 1e6:.2f} MB",
        )


if __name__ == "__main__":
    main()
