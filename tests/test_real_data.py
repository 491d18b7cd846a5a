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
    assert "The MIT License" in (path.parent / "LICENSE.md").read_text()
    assert name.split("/")[-1] in (REAL / "README.md").read_text()


@pytest.fixture(scope="module")
def fusion():
    return io.read_xio(REAL / "xio-fusion/sensor_data.csv")


def test_fusion_recording_reads_in_si(fusion):
    assert fusion.n == 13514 and fusion.time[-1] == pytest.approx(135.33, abs=0.01)
    still = fusion.time < 10.0
    assert np.linalg.norm(fusion.f_b[still].mean(0)) == pytest.approx(9.8, abs=0.15)   # specific force, m/s^2
    assert 25 < np.median(np.linalg.norm(fusion.m_b, axis=1)) < 65                     # Earth's field, uT


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
    assert 0.2 < static.mean() < 0.9            # the foot stands still for part of every stride...
    assert static[rec.time < 10].mean() > 0.95  # ...and the subject stands still for the first 10 s
