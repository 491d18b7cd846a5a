"""Count arguments take integers >= 1 only: ``True`` is not a count (``navlib._validate.integer``).

One row per count argument that used a hand-written check; ``simulate_imu(n_trials=True)``,
``fit_allan(n_samples=True)``, ``carpark_legs(n_loops=True)`` and ``floor_test_legs(n_round_trips=True)``
used to run as a count of 1, ``Gates(max_rejected=2.0)`` used to be accepted as a float.
"""

import numpy as np
import pytest

from navlib import analysis, sensors
from navlib.filters import heading_fusion, planar_ekf, zupt_ins
from navlib.filters.observations import RtkHeading
from navlib.papers import pedestrian_ins

W = np.zeros((10, 3))
F = np.tile([0.0, 0.0, 9.8], (10, 1))
T10 = np.arange(10.0)
H10 = np.zeros(10)
VALID = np.ones(10, dtype=bool)
X5 = np.zeros(5)
Z = np.zeros((10, 5))

COUNTS = {  # (function, count argument) -> call with the count n
    ("sensors.simulate_imu", "n_trials"): lambda n: sensors.simulate_imu(
        W, F, 0.01, sensors.ImuModel(), np.random.default_rng(0), n_trials=n
    ),
    ("sensors.gauss_markov", "shape"): lambda n: sensors.gauss_markov((n, 3), 0.1, 1.0, 10.0, np.random.default_rng(0)),
    ("analysis.fit_allan", "n_samples"): lambda n: analysis.fit_allan([1.0, 2.0, 4.0], [3e-3, 2e-3, 1.5e-3], n, 0.1),
    ("observations.RtkHeading", "confirm"): lambda n: heading_fusion.fuse_rtk_heading(
        H10, RtkHeading(H10, VALID, confirm=n), 0.1
    ),
    ("heading_fusion.rtk_at_imu_rate", "step"): lambda n: heading_fusion.rtk_at_imu_rate(T10, H10, VALID, n),
    ("planar_ekf.propagate", "n_steps"): lambda n: planar_ekf.propagate(X5, 0.5, n),
    ("planar_ekf.EkfConfig", "reacquire"): lambda n: planar_ekf.EkfConfig(np.eye(5), np.eye(5), reacquire=n),
    ("zupt_ins.Gates", "max_rejected"): lambda n: zupt_ins.Gates(max_rejected=n),
    ("pedestrian_ins.carpark_legs", "n_loops"): lambda n: pedestrian_ins.carpark_legs(n_loops=n),
    ("pedestrian_ins.floor_test_legs", "n_round_trips"): lambda n: pedestrian_ins.floor_test_legs(n_round_trips=n),
}
KEYS = sorted(COUNTS)
IDS = [f"{func}-{arg}" for func, arg in KEYS]


@pytest.mark.parametrize("value", [True, np.True_, False, 2.0, 0], ids=["True", "np.True_", "False", "float", "zero"])
@pytest.mark.parametrize("key", KEYS, ids=IDS)
def test_count_refuses_bool_float_and_zero(key, value):
    with pytest.raises(ValueError, match=rf"^{key[1]}: expected an integer >= 1, got "):
        COUNTS[key](value)


@pytest.mark.parametrize("key", KEYS, ids=IDS)
def test_count_accepts_python_and_numpy_integers(key):
    COUNTS[key](2)
    COUNTS[key](np.int64(2))
