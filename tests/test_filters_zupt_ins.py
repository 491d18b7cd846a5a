"""navlib.filters.zupt_ins: screened once, options in small records, one fault vocabulary.

The filter's numbers under faults are tested in tests/faults/test_faults_pedestrian.py; here its interface:
the ImuSamples is screened once and not validated again, every public function and kernel takes at most
12 parameters, every option is documented in its record, and the faults use the per-sensor keys.
"""

from __future__ import annotations

import dataclasses
import inspect
import re
import warnings

import numpy as np
import pytest

from navlib import _validate, earth, robust, sensors, trajectory, units
from navlib.filters import zupt, zupt_ins
from navlib.imu import ImuSamples, SensorLimits

LLA0 = [units.deg(30.55), units.deg(114.30), 20.0]
DT = 0.01
RECORDS = (
    zupt_ins.Start,
    zupt_ins.Aiding,
    zupt_ins.ProcessNoise,
    zupt_ins.MeasurementNoise,
    zupt_ins.InitialSigma,
    zupt_ins.Gates,
    zupt_ins.BaroTracker,
    zupt_ins.FilterConfig,
)
SENSORS = {"gyro", "accel", "mag", "baro", "clock", "zupt"}


@pytest.fixture(scope="module")
def walk():
    legs = [trajectory.Leg(5.0), trajectory.Leg(6.0, 1.2), trajectory.Leg(5.0)]
    traj = trajectory.walk(legs, DT, LLA0, 0.0)
    w, f = trajectory.ideal_imu(traj)
    model = sensors.imu_model("MPU-6050").replace(gyro={"bias": units.deg_per_s(0.05)}, accel={"bias": units.mg(10)})
    imu = sensors.simulate_imu(w, f, DT, model, np.random.default_rng(3))
    static = zupt.detect_static(imu.w_ib_b, imu.f_b, DT)
    return traj, imu.w_ib_b, imu.f_b, static


def run(traj, w, f, static, limits=None, **kw):
    return zupt_ins.run_filter(ImuSamples(w, f, DT, limits or SensorLimits()), zupt_ins.Start(LLA0, traj.q_bn[0]), static, **kw)


def assert_same(a, b):
    for name in ("lla", "vel_n", "q_bn"):
        np.testing.assert_array_equal(getattr(a.nav, name), getattr(b.nav, name), err_msg=name)
    np.testing.assert_array_equal(a.P_diag, b.P_diag)


def test_the_samples_are_screened_once_and_not_validated_again(walk, monkeypatch):
    traj, w, f, static = walk
    imu, start = ImuSamples(w, f, DT), zupt_ins.Start(LLA0, traj.q_bn[0])
    screens = []
    real_screen = robust.screen

    def screen(*args, **kw):
        screens.append(args)
        return real_screen(*args, **kw)

    def refuse(*args, **kw):
        raise AssertionError("the ImuSamples' arrays validated again")

    monkeypatch.setattr(robust, "screen", screen)
    monkeypatch.setattr(_validate, "imu_samples", refuse)
    for module in (zupt_ins, zupt):
        monkeypatch.setattr(module, "imu_samples", refuse, raising=False)
    checked = []
    real_as_array = zupt_ins.as_array
    monkeypatch.setattr(zupt_ins, "as_array", lambda x, name, **kw: checked.append(name) or real_as_array(x, name, **kw))
    res = zupt_ins.run_filter(imu, start, static, h_baro=np.full(len(w), np.nan))
    assert len(screens) == 1 and checked == ["h_baro"] and res.updated
    zupt.detect_static(imu)  # the detector takes the validated arrays as they are


def test_no_public_function_or_kernel_takes_more_than_12_parameters():
    for module in (zupt_ins, zupt):
        for name, obj in vars(module).items():
            func = getattr(obj, "py_func", obj)  # a numba kernel's Python function
            if inspect.isfunction(func) and func.__module__ == module.__name__:
                assert len(inspect.signature(func).parameters) <= 12, f"{module.__name__}.{name}"
    for record in RECORDS:
        assert len(dataclasses.fields(record)) <= 8, record.__name__


def documented(doc: str) -> set[str]:
    """The names of a numpydoc ``name, other : type`` section's entries."""
    return {name for line in doc.splitlines() if re.match(r"^\w+(, \w+)* :", line) for name in line.split(" :")[0].split(", ")}


def test_every_option_is_documented_once_in_its_record():
    again = documented(inspect.getdoc(zupt_ins.run_filter))
    for record in RECORDS:
        names = {field.name for field in dataclasses.fields(record)}
        assert names <= documented(inspect.getdoc(record)), record.__name__
        assert not (names & again - {"imu", "start", "static", "aiding", "config"}), record.__name__


def test_records_are_frozen_and_validate_on_construction():
    s = zupt_ins.Start(LLA0, [2.0, 0.0, 0.0, 0.0], time=np.float32(1.0))
    np.testing.assert_array_equal(s.q_bn, [1.0, 0.0, 0.0, 0.0])
    assert type(s.time) is float and s.vel_n.shape == (3,)
    with pytest.raises(dataclasses.FrozenInstanceError):
        s.time = 2.0
    assert zupt_ins.Gates(max_rejected=np.int64(3)).max_rejected == 3
    B = np.array([-0.5, 33.0, -35.0])
    _, incl, field = earth.field_angles(B, deg=False)
    np.testing.assert_array_equal(zupt_ins.Aiding(B_n=B).field_reference(), [field, incl])


def test_faults_use_the_per_sensor_keys_and_counts_are_the_flags_sums(walk):
    traj, w, f, static = walk
    w, f = w.copy(), f.copy()
    w[300:305] = np.nan
    f[800:810] = 0.0  # free fall
    m = np.tile([0.0, 30.0, -40.0], (len(w), 1))
    m[::2] = np.nan  # a compass at half the IMU rate: NaN is no reading
    res = run(traj, w, f, static, SensorLimits(full_scale_gyro=1.0), m_b=m, h_baro=np.full(len(w), 20.0))
    assert {s for s, _ in res.faults.counts} <= SENSORS and ("mag", "nan") not in res.faults.counts
    for key, mask in res.faults.flags.items():
        assert mask.dtype == bool and mask.shape == (len(w),)
        assert res.faults[key] == mask.sum(), key
    assert res.faults["gyro", "nan"] == 5 and res.faults["accel", "freefall"] == 10
    assert not any(hasattr(res, name) for name in ("counts", "flags"))
    assert isinstance(res.zupt_updates, int) and isinstance(res.baro_aidings, int) and isinstance(res.mag_aidings, int)


def test_a_stuck_gyro_holds_the_gyro_alone_and_a_spike_is_held_exactly_like_a_dropout(walk):
    traj, w, f, static = walk
    stuck = w.copy()
    stuck[400:420] = 0.3  # the gyro latched at 0.3 rad/s
    res = run(traj, stuck, f, static)
    rows = res.faults.flags["gyro", "stuck"]
    assert np.flatnonzero(rows).tolist() == list(range(400, 420))
    held = stuck.copy()
    held[rows] = w[399]  # the last good reading, the accelerometer used
    free = run(traj, held, f, static, SensorLimits(stuck_run=None))
    if static[rows].all():  # in a stance: nothing else is done
        assert_same(res, free)
    else:
        assert not np.array_equal(res.nav.q_bn, free.nav.q_bn)  # outside one: the gyro's uncertainty inflated
        np.testing.assert_allclose(res.nav.q_bn[-1], free.nav.q_bn[-1], atol=1e-3)
    spiky = w.copy()
    spiky[500, 0] += 1.0
    res = run(traj, spiky, f, static, SensorLimits(spike_gyro=0.02))
    np.testing.assert_array_equal(np.flatnonzero(res.faults.flags["gyro", "spike"]), [500])
    dropout = w.copy()
    dropout[500] = np.nan
    assert_same(res, run(traj, dropout, f, static))


def test_zupt_off_runs_a_free_ins_with_the_walking_aids_and_no_warning(walk):
    traj, w, f, static = walk
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        res = run(traj, w, f, static, aiding=zupt_ins.Aiding(zupt=False))
    assert res.zupt_updates == 0 and not res.updated and res.faults["zupt", "refused"] == 0
    with pytest.warns(RuntimeWarning, match="no ZUPT/ZARU update"):
        run(traj, w, f, np.zeros(len(w), bool))


def test_detect_static_takes_samples_or_arrays_alike(walk):
    _, w, f, static = walk
    np.testing.assert_array_equal(zupt.detect_static(ImuSamples(w, f, DT)), static)
    with pytest.raises(ValueError, match="^f_b: given twice"):
        zupt.detect_static(ImuSamples(w, f, DT), f)
    with pytest.raises(ValueError, match="^w_ib_b: expected one record"):
        zupt.detect_static(ImuSamples(np.stack([w, w]), np.stack([f, f]), DT))
    with pytest.raises(ValueError, match="^f_b: "):
        zupt.detect_static(w, f[:-1], DT)
