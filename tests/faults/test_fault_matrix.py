"""The fault matrix (issue 33): handling a fault never costs more than ignoring it, and every fault is counted.

Each cell of tools/fault_matrix.py (fault kind x motion state x filter, seeded simulation, 3 seeds; and the real x-io
recording) runs a filter fault-free, with navlib's handling and with the handling off. The rule: the handled error
after the fault exceeds the ignored one by at most MARGIN (what holding one noisy sample over the fault can cost
either way: 0.29 deg, 0.06 m), and the handled run's ``faults`` counts the fault. Cells where a fault cannot occur
(a free INS has no limits to act on, the motion never reaches the rails) are skipped with the reason.
"""

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools"))
import fault_matrix as fm  # noqa: E402  (tools/fault_matrix.py)

SEEDS = range(3)


@pytest.mark.parametrize("motion", list(fm.MOTIONS))
@pytest.mark.parametrize("name", fm.FILTERS)
@pytest.mark.parametrize("fault", fm.FAULTS)
def test_handling_costs_no_more_than_ignoring(fault, name, motion):
    cell = fm.cell(name, fault, motion, SEEDS)
    if cell is None:
        pytest.skip(f"{fault} does not apply to {name} ({motion})")
    assert cell["counted"], "the fault is not counted in faults"
    assert cell["handled"] <= cell["ignored"] + fm.MARGIN[fm.unit(name)], cell
    assert cell["handled"] < 2 * cell["free"] + 5.0 or fault == "saturation", cell  # recovered (not lost for good)


@pytest.mark.parametrize("fault", [f for f in fm.FAULTS if f in fm.KEYS and f != "saturation"])
def test_on_the_real_recording(fault):
    cells = fm.real_cells(fault)
    assert set(cells) == {"still", "fast turn"}
    for motion, cell in cells.items():
        assert cell["counted"], motion
        assert cell["handled"] <= cell["ignored"] + fm.MARGIN["deg"], (motion, cell)


def test_a_lasting_latch_is_held_not_used():
    """The hold that makes a stuck axis cost nothing when the output froze at its last reading is not the run's value
    when the output latched elsewhere (a step into the run): 0.3 rad/s latched on z at rest for 1 s."""
    r = fm.rig(0.0, 0)
    r.w[fm.K0 : fm.K0 + 100, 2] = 0.3
    run = fm.IMU_FILTERS["Mahony"]
    q_h, faults = run(r, fm.SensorLimits(), False)
    q_i, _ = run(r, fm.SensorLimits(stuck_run=None), False)
    after = fm.AFTER
    assert faults["gyro", "stuck"] == 100
    assert fm.rms(fm.angle_deg(q_h[after], r.q[after])) < 0.2 * fm.rms(fm.angle_deg(q_i[after], r.q[after]))


@pytest.mark.parametrize("fault", ["clock jump -", "duplicate stamps"])
def test_stamps_that_do_not_increase_are_refused_by_name_and_sanitized(fault):
    """A backward clock jump or a repeated stamp: ImuSamples refuses the time axis by name (no filter integrates an
    interval <= 0); timing.sanitize sorts and drops the repeats and says how many."""
    from navlib import timing

    r = fm.rig(0.0, 0)
    t = fm.DT * fm.np.arange(fm.N + 1)
    if fault == "clock jump -":
        t[fm.K0 :] -= 0.2
    else:
        t[fm.K0] = t[fm.K0 - 1]
    with pytest.raises(ValueError, match="^time: "):
        fm.ImuSamples.from_times(t, r.w, r.f)
    report = timing.sanitize(t)[-1]
    assert report.n_out_of_order + report.n_duplicate > 0
