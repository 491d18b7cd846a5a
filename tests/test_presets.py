"""filters.presets.foot_mounted on x-io's real foot-mounted walks: its factor and gyro noise were chosen on the
short walk; the long walk is the test (a closed loop: it must end where it started)."""

from pathlib import Path

import numpy as np
import pytest

from navlib import alignment, analysis, attitude, geodesy, io, units
from navlib.filters import presets, zupt_ins

REAL = Path(__file__).resolve().parents[1] / "data" / "real" / "xio-gait-tracking"
LLA0 = [units.deg(51.5), 0.0, 0.0]
LOOP = {"short": 25.0, "long": 60.0}  # m, "about" as the source states them


def walk(name):
    rec = io.read_xio(REAL / f"{name}_walk.csv", timing="sanitize", check="off")
    imu = rec.imu()
    still = rec.time < 10.0  # both walks start with the foot standing for over 11 s
    setup = presets.foot_mounted(imu, still)
    pitch, roll = alignment.level(rec.f_b[still].mean(0))
    start = zupt_ins.Start(LLA0, attitude.euler_to_quat([0.0, pitch, roll]), gyro_bias=setup.gyro_bias)
    stance = setup.stance(imu)
    res = zupt_ins.run_filter(imu, start, stance, aiding=zupt_ins.Aiding("none"), config=setup.config)
    lla = res.nav.lla[-rec.n :]
    enu = np.stack(geodesy.geodetic2enu(lla[:, 0], lla[:, 1], lla[:, 2], *LLA0), -1)
    return setup, enu, stance


@pytest.mark.parametrize("name", ["short", "long"])
def test_foot_mounted_preset_closes_the_real_loops(name):
    setup, enu, stance = walk(name)
    assert setup.window == pytest.approx(0.05, rel=0.01) and setup.config.update_rate == pytest.approx(400.0, rel=0.01)
    closing = np.hypot(*enu[-1, :2])
    assert closing < 0.02 * LOOP[name]  # foot-mounted MEMS systems close within 0.3-2 % of the distance
    assert abs(enu[-1, 2]) < 0.5


def test_foot_mounted_preset_refuses_a_short_still_start():
    rec = io.read_xio(REAL / "short_walk.csv", timing="sanitize", check="off")
    with pytest.raises(ValueError, match="still: .*stand still for 2 s"):
        presets.foot_mounted(rec.imu(), rec.time < 0.03)


def test_footfall_path_of_the_real_walks_is_reported():
    """The footfall path needs a stance per stride; on the long walk the detector finds 15 stances for roughly
    45 strides (most stances there last under 0.05 s), so the footfall figure chords over missed strides and no
    check is made against the stated "about 60 m" -- only that it is shorter than the sample-summed track,
    whose swing wiggle it leaves out."""
    for name in ("short", "long"):
        _, enu, stance = walk(name)
        length, falls = analysis.footfall_path_length(enu, stance, min_samples=1)
        summed = np.sum(np.hypot(*np.diff(enu[::40, :2], axis=0).T))
        assert 0 < length < summed and len(falls) > 5
