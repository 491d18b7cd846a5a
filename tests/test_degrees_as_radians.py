"""Angles in degrees passed where radians are expected are refused, naming the argument (issue 15, item 6).

A pitch beyond pi/2, a roll beyond pi or a latitude beyond pi/2 "rad" is almost always a value in degrees;
these functions used to return plausible-looking numbers for pitch = 45 "rad".
"""

import numpy as np
import pytest

from navlib import alignment, analysis, attitude, plots
from navlib.papers import mimu_mag_rtk, north_finding, pedestrian_ins, rotation_bias

CASES = [
    ("pitch", lambda: alignment.magnetic_heading([1.0, 20.0, -40.0], 45.0, 0.0)),
    ("roll", lambda: alignment.magnetic_heading([1.0, 20.0, -40.0], 0.1, 45.0)),
    ("pitch", lambda: pedestrian_ins.tilt_compensate_ned([20.0, 1.0, 40.0], 45.0, 0.0)),
    ("roll", lambda: pedestrian_ins.tilt_compensate_printed([20.0, 1.0, 40.0], 0.1, -45.0)),
    (r"hpr\[\.\.\., 1\] \(pitch\)", lambda: rotation_bias.eq1_matrix([0.0, 45.0, 0.0])),
    (r"hpr\[\.\.\., 2\] \(roll\)", lambda: mimu_mag_rtk.printed_eq8_quat([0.0, 0.0, 45.0])),
    (r"lla\[\.\.\., 0\] \(lat\)", lambda: analysis.horizontal_error([45.0, 2.0, 0.0], [0.5, 2.0, 0.0])),
    (r"lla_true\[\.\.\., 0\] \(lat\)", lambda: analysis.horizontal_error([0.5, 2.0, 0.0], [45.0, 2.0, 0.0])),
    # found by tools/fuzz.py (issue 15, item 4): another argument was named, or the call was accepted
    (r"ypr\[\.\.\., 1\] \(pitch\)", lambda: attitude.ypr_to_hpr([0.0, 45.0, 0.0])),  # was "hpr[..., 1]"
    ("pitches", lambda: north_finding.stop_and_go([1.0, 2.0], 10.0, 40.0, 5.0, [0.0, 45.0], [0.0, 0.0])),  # was "pitch"
    ("rolls", lambda: north_finding.stop_and_go([1.0, 2.0], 10.0, 40.0, 5.0, [0.0, 0.0], [0.0, -45.0])),  # was "roll"
    (r"hpr0\[\.\.\., 1\] \(pitch\)", lambda: rotation_bias.dwell_attitudes([0.0, 45.0, 0.0], [0, 0, 1.0], 1.5, 2)),
    (r"hpr0\[\.\.\., 1\] \(pitch\)", lambda: rotation_bias.design([0.0, 45.0, 0.0], [0, 0, 1.0], 1.5, 10.0, 0.01, 1e-3)),
    (r"hpr\[\.\.\., 1\] \(pitch\)", lambda: plots.heading_deg([0.1, 45.0, 0.0])),  # was accepted
]


@pytest.mark.parametrize("arg, call", CASES)
def test_degrees_for_radians_raise_naming_the_argument(arg, call):
    with pytest.raises(ValueError, match=f"^{arg}: "):
        call()


def test_radians_at_the_limits_are_accepted():
    assert np.isfinite(alignment.magnetic_heading([1.0, 20.0, -40.0], np.pi / 2 - 1e-9, np.pi))
    assert np.all(np.isfinite(rotation_bias.eq1_matrix([7.0, -np.pi / 2, -np.pi])))  # heading may be unwrapped
