#!/usr/bin/env python3
"""navlib's own fuzzing harness: every public callable, every argument, every kind of bad value (issue 15, item 4).

For every name in ``__all__`` of every module under ``navlib`` (the deprecated alias modules and the private
``_`` modules excepted) the registry ``tools/fuzz_calls.py`` holds one valid call (tests/test_bad_input.py
reads the same registry). A public callable without an entry fails the run. Each argument of each valid
call is then replaced in turn by every mutation of :data:`MUTATIONS` that applies to it (:func:`applies` decides from the
argument's name, annotation and valid value; nothing is decided per call), and each call runs in a forked
worker with a timeout.

A bad call is classified as

* ``clean``: ``ValueError``/``TypeError`` whose message starts with the argument's name (navlib's
  ``"<arg>: expected ..."`` convention; ``"hpr[..., 1] (pitch): ..."`` and ``"lat, h: ..."`` name it too),
* ``unnamed``: ``ValueError``/``TypeError`` whose message does not start with the argument's name,
* ``other_exception``: any other exception type,
* ``silent_nan``: returns non-finite values where the valid call's result is finite,
* ``silent_accept``: returns a finite result,
* ``hang`` (no answer within ``--timeout``) or ``crash`` (the worker died).

A valid-unusual call (a list, float32, integers, a batch on a leading axis, N = 1 sample) is compared with
the float64 result of the same values (the first sample of the full result for N = 1) and classified as
``equal``, ``differs``, ``refused`` (a clean error naming an argument: acceptable for a batch or N = 1,
not for the other variants) or ``error``.

Every non-clean case goes to ``build/fuzz.json``. The run fails (exit 1) when a bad class is non-zero,
except for the cases listed in :data:`BY_DESIGN`, each with its reason, and the registry's ``KNOWN_GAPS``;
a full run also fails when a :data:`BY_DESIGN` rule or a known gap matches nothing (stale documentation).

Usage: python tools/fuzz.py [--only MODULE_OR_CALLABLE ...] [--jobs 2] [--timeout S] [--verbose] [--out PATH]
"""

from __future__ import annotations

import argparse
import contextlib
import copy
import dataclasses
import inspect
import io
import json
import multiprocessing
import os
import re
import shutil
import sys
import tempfile
import time
import traceback
import warnings
from collections import Counter
from multiprocessing.connection import wait
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))
sys.path.insert(0, str(REPO / "tools"))

import fuzz_calls  # noqa: E402  (the registry)
from fuzz_calls import KNOWN_GAPS, Call, Fresh, Skip, public_callables  # noqa: E402

from navlib.imu import ImuSamples  # noqa: E402
from navlib.robust import FaultReport  # noqa: E402

BAD_CLASSES = ("unnamed", "other_exception", "silent_nan", "silent_accept", "hang", "crash", "modifies_input")
UNUSUAL_BAD = ("differs", "error")
BATCH = 3  # copies on the new leading axis (not 2: no fixture has a leading axis of 3)


# ----------------------------------------------------------------------------------------------------------
# What each mutation means and where it applies: one table, decided from argument names and annotations.
# ----------------------------------------------------------------------------------------------------------

QUAT_NAMES = {"q", "p", "q0", "q_bn", "q_ned"}
DCM_NAMES = {"C", "C_bn", "C_ned"}
TIME_NAMES = {"time", "t", "t_target", "t_source", "door_times"}
COUNT_NAMES = {
    "n",
    "n_trials",
    "n_steps",
    "n_samples",
    "n_dwells",
    "length",
    "step",
    "run",
    "rtk_confirm",
    "reacquire",
    "oss",
    "width",
    "ref_floor",
    "max_rejected",
    "n_loops",
    "n_round_trips",
    "batch_size",
    "seed",
    "stuck_run",
}
# Angles in radians that a value in degrees would most likely be mistaken for: argument -> the component of
# an (..., 3) triplet that holds it (None: the whole argument). Not where the function takes degrees (deg=True).
DEGREE_ARGS = {
    "pitch": None,
    "roll": None,
    "pitches": None,
    "rolls": None,
    "lat": None,
    "lat0": None,
    "heading": None,
    "headings": None,
    "heading0": None,
    "heading1": None,
    "heading2": None,
    "heading_mag": None,
    "heading_rtk": None,
    "hpr": 1,
    "hpr0": 1,
    "hpr_true": 1,
    "ypr": 1,
    "lla": 0,
    "lla0": 0,
    "lla_true": 0,
}
DT_NAMES = {"dt", "dts", "dt_gyro", "dt_imu", "time_step"}
NUMERIC = {"number", "quat", "dcm", "time", "interval"}
NUMBERS = NUMERIC | {"count"}  # the kinds held as numbers (counts too)

MUTATIONS = {
    # name: (kinds it applies to, what it is)
    "wrong_shape": (NUMERIC, "the last axis one longer (a scalar becomes shape (3,), a series of N > 4 values (N, 2))"),
    "transposed": (NUMERIC, "(N, k) given as (k, N)"),
    "0d": (NUMERIC, "a scalar where an array is expected"),
    "empty": (NUMBERS, "no samples: shape (0,) or (..., 0, k); a (3,) or (4,) vector without components"),
    "nan": (NUMBERS, "one element NaN"),
    "inf": (NUMBERS, "one element inf (not where inf means 'no limit': INF_MEANS_NO_LIMIT)"),
    "1e300": (NUMERIC, "one element 1e300"),
    "none": (
        {"number", "quat", "dcm", "time", "interval", "count", "flag", "text", "object"},
        "None (not where None is a documented value)",
    ),
    "string": ({"number", "quat", "dcm", "time", "interval", "count", "flag", "object"}, "the string 'abc'"),
    "numeric_str": (NUMBERS, "the string '1.5' (numpy would parse it)"),
    "complex": (NUMBERS, "the values plus 1j (numpy would drop the imaginary part)"),
    "object": (NUMBERS, "the values as an object array"),
    "ragged": (NUMBERS, "a ragged nested list, [1.0, [2.0, 3.0]] (no array can hold it)"),
    "bool": (NUMBERS, "True, or an all-True mask of the value's shape"),
    "true_count": ({"count"}, "True where a count is expected"),
    "degrees": ({"number"}, "45 for an angle in radians (DEGREE_ARGS)"),
    "non_monotonic": ({"time"}, "two epochs swapped"),
    "time_jump": ({"time", "interval"}, "a one-hour jump in the middle of the time axis (one 3600 s interval)"),
    "empty_elementwise": (
        NUMBERS,
        "no elements for an elementwise argument: shape (0,), or (0, k) with its vector "
        "axis (valid: an empty result, or refused by name)",
    ),
    "tiny_dt": (
        {"interval", "number"},
        "a sample interval of 1e-300 s (DT_NAMES and Interval arguments; valid if the "
        "result stays below 1e100, else a named refusal is expected)",
    ),
    "negative_count": ({"count"}, "-4 where a count is expected"),
    "stuck_axis": (
        {"object"},
        "an ImuSamples turning at 1 rad/s whose x gyro repeats one value over 7 of its samples "
        "(stuck_run 5): valid, but the result's faults must count ('gyro', 'stuck')",
    ),
    "zero_quat": ({"quat"}, "the zero quaternion"),
    "not_rotation": ({"dcm"}, "a mirror image (orthonormal, det -1)"),
}
UNUSUAL = {
    "list": "nested Python lists",
    "float32": "float32",
    "int": "integers (the rounded values)",
    "batch": "copies on a new leading axis (BATCH)",
    "n1": "every series cut to its first sample",
}
# Arguments for which inf is a documented value ("no limit", "no gate", "off", a singular fit's condition).
INF_MEANS_NO_LIMIT = re.compile(
    r"^(full_scale\w*|gate|rtk_gate|max_gap|max_cond|mag_field_tol|mag_dip_tol|"
    r"spike_gyro|spike_accel|baro_gate|correlation_time|max_dt|norm_tol|dip_tol|lower|upper|"
    r"freefall_time|condition)$"
)


def kind(name: str, annotation: str, value) -> str:
    """The kind of an argument: number, quat, dcm, time, interval, count, flag, text or object."""
    if isinstance(value, str) or annotation.startswith("str"):
        return "text"
    if isinstance(value, (bool, np.bool_)) or annotation.startswith("bool"):
        return "flag"
    if not _numeric(value):
        return "object"
    if "Quat" in annotation or name in QUAT_NAMES:
        return "quat"
    if "Dcm" in annotation or name in DCM_NAMES:
        return "dcm"
    if "Times" in annotation or name in TIME_NAMES:
        return "time"
    if "Interval" in annotation:
        return "interval"
    if annotation.startswith("int") or name in COUNT_NAMES and isinstance(value, (int, np.integer)):
        return "count"
    return "number"


def _numeric(value) -> bool:
    if isinstance(value, (bool, np.bool_, str)) or value is None:
        return False
    try:
        arr = np.asarray(value)
    except (TypeError, ValueError):
        return False
    return arr.dtype.kind in "fiu"


def applies(mutation: str, arg: Arg) -> bool:
    """Whether ``mutation`` makes sense for ``arg`` (MUTATIONS' kinds, refined by the valid value's shape)."""
    kinds, _ = MUTATIONS[mutation]
    if arg.kind not in kinds:
        return False
    v = np.asarray(arg.value) if arg.kind in NUMBERS else None
    if mutation in ("wrong_shape", "0d", "empty") and arg.elementwise and v.shape[-1:] not in ((3,), (4,)):
        return False  # any shape is valid for an elementwise argument without a vector axis
    if mutation == "empty" and arg.elementwise and v.ndim != 1:
        return False  # an empty batch is valid for elementwise functions (tests/test_bad_input.py);
        # a (0,) vector, a vector without components, is none
    if mutation == "empty_elementwise":
        return arg.elementwise and not (v.ndim == 1 and v.shape[-1:] not in ((3,), (4,)))  # not "empty" already
    if mutation == "tiny_dt":
        return arg.kind == "interval" or arg.name in DT_NAMES
    if mutation == "stuck_axis":
        return isinstance(arg.value, ImuSamples) and arg.value.n >= 10 and arg.value.w_ib_b.ndim == 2
    if mutation in ("wrong_shape", "transposed") and arg.any_shape:
        return False  # data of any width: (N, k) for every k, also (k, N)
    if mutation == "transposed":
        return v.ndim >= 2 and v.shape[-1] != v.shape[-2]
    if mutation == "0d":
        return v.ndim >= 1
    if mutation == "inf":
        return not INF_MEANS_NO_LIMIT.match(arg.name)
    if mutation == "none":
        return not arg.none_ok
    if mutation == "string":
        return "str" not in arg.annotation
    if mutation == "degrees":
        return arg.name in DEGREE_ARGS and not arg.deg
    if mutation == "non_monotonic":
        return v.ndim == 1 and v.size >= 4
    if mutation == "time_jump":
        return arg.kind == "time" and v.ndim == 1 and v.size >= 2 or arg.kind == "interval" and arg.n is not None
    return True


def mutate(mutation: str, arg: Arg):
    """The mutated value of ``arg``."""
    v = arg.value
    a = np.array(v, dtype=float) if arg.kind in NUMBERS else None
    if mutation == "wrong_shape":  # a 1-D value of up to 4 entries is a vector (pair, xyz, quaternion)
        if a.ndim == 0:
            return np.full(3, float(a))
        if a.ndim == 1 and a.size > 4:
            return np.stack([a, a], -1)
        return np.concatenate([a, a[..., -1:]], -1)
    if mutation == "transposed":
        return np.swapaxes(a, -1, -2)
    if mutation == "0d":
        return a.flat[0]
    if mutation == "empty":
        return np.zeros(a.shape[:-2] + (0, a.shape[-1])) if a.ndim >= 2 else np.zeros(0)
    if mutation in ("nan", "inf", "1e300"):
        x = {"nan": np.nan, "inf": np.inf, "1e300": 1e300}[mutation]
        if a.ndim == 0:
            return x
        a.flat[a.size // 2] = x
        return a
    if mutation == "none":
        return None
    if mutation == "string":
        return "abc"
    if mutation == "numeric_str":
        return "1.5"
    if mutation == "complex":
        return a + 1j
    if mutation == "object":
        return a.astype(object)
    if mutation == "ragged":
        return [1.0, [2.0, 3.0]]
    if mutation == "bool":
        return True if a.ndim == 0 else np.ones(a.shape, dtype=bool)
    if mutation == "true_count":
        return True
    if mutation == "degrees":
        comp = DEGREE_ARGS[arg.name]
        if comp is None:
            return np.full_like(a, 45.0)
        a[..., comp] = 45.0
        return a
    if mutation == "non_monotonic":
        a[[1, 2]] = a[[2, 1]]
        return a
    if mutation == "time_jump":
        if arg.kind == "time":
            a[a.size // 2 :] += 3600.0
            return a
        d = np.full(arg.n, float(a)) if a.ndim == 0 else a
        d[d.size // 2] = 3600.0
        return d
    if mutation == "empty_elementwise":
        return np.zeros((0,) + a.shape[-1:]) if a.shape[-1:] in ((3,), (4,)) else np.zeros(0)
    if mutation == "tiny_dt":
        return 1e-300 if a.ndim == 0 else np.full_like(a, 1e-300)
    if mutation == "negative_count":
        return -4
    if mutation == "stuck_axis":
        return stuck_inside_motion(v)
    if mutation == "zero_quat":
        return np.zeros_like(a)
    if mutation == "not_rotation":
        return a * np.array([1.0, 1.0, -1.0])  # last column negated: a mirror image
    raise KeyError(mutation)


def stuck_inside_motion(imu: ImuSamples) -> ImuSamples:
    """``imu`` turning at 1 rad/s about every axis (a moving record, noisy from the start), its x gyro frozen over 7
    samples in the middle, with ``stuck_run = 5`` so that a short record holds a stuck run."""
    k = np.arange(imu.n)
    w = imu.w_ib_b + 1.0 + 0.01 * np.sin(1.7 * k)[:, None] * np.array([1.0, -1.0, 0.5])
    lo = max(1, imu.n // 2 - 3)
    w[lo : lo + 7, 0] = w[lo, 0]
    return ImuSamples(w, imu.f_b, imu.dt, dataclasses.replace(imu.limits, stuck_run=5))


def counted_stuck(out) -> bool | None:
    """Whether a result's FaultReport counts a stuck gyro (None: the result carries no FaultReport)."""
    fields = [getattr(out, f.name) for f in dataclasses.fields(out)] if dataclasses.is_dataclass(out) else []
    parts = [out, *fields, *(out if isinstance(out, tuple) else ())]
    reports = [x for x in parts if isinstance(x, FaultReport)]
    return bool(np.any(reports[0]["gyro", "stuck"])) if reports else None


def unusual(variant: str, arg: Arg):
    """(value given, the same values in float64) for a valid-unusual variant of ``arg``, or None if it does not apply."""
    if arg.kind not in NUMERIC:
        return None
    a = np.array(arg.value, dtype=float)
    if variant == "list":
        return (a.tolist(), a) if a.ndim >= 1 else None
    if variant == "float32":
        a32 = a.astype(np.float32)
        return a32, a32.astype(float)
    if variant == "int":
        if not np.all(np.isfinite(a)):
            return None
        r = np.round(a)
        return r.astype(np.int64), r
    if variant == "batch":
        return (np.stack([a] * BATCH), a) if a.ndim >= 1 or arg.elementwise else None
    raise KeyError(variant)


# ----------------------------------------------------------------------------------------------------------
# By design: non-clean cases that are the documented behaviour, each with its reason.
# (callable, argument, mutation, outcome) regular expressions (whole match) -> reason.
# ----------------------------------------------------------------------------------------------------------

_SENSORS = r"w_ib_b|f_b|m_b"
_FILTERS = (
    r"filters\.(mahony\.mahony|quaternion_kf\.quaternion_kf|inertial_lowpass\.inertial_lowpass|zupt_ins\.run_filter|"
    r"zupt\.detect_static)|"
    r"alignment\.static_(means|windows)|papers\.north_finding\.(ins_heading_change|stop_solutions)|pdr\.pdr_headings"
)
_HEADINGS = r"heading\w*"
BY_DESIGN: list[tuple[str, str, str, str, str]] = [
    (
        r"filters\.presets\.foot_mounted",
        "imu",
        "stuck_axis",
        "silent_accept",
        "a preset reads only the still start's noise floor and runs no filter: the stuck axis is screened and counted by "
        "the filter that gets these settings (zupt_ins.run_filter)",
    ),
    # NaN marks a dropout (navlib/__init__.py, "Bad input"; tests/test_bad_input.py)
    (
        r"units\..*",
        r"x|value",
        r"nan|inf|1e300",
        r"silent_nan|silent_accept",
        "unit converters pass NaN (dropout) and inf (full_scale = inf) through; a linear conversion is exact at any magnitude",
    ),
    (r"attitude\.wrap_2?pi", "angle", "nan", "silent_nan", "NaN (a dropout) stays NaN (the wraps' docstrings)"),
    (r"attitude\.ned_to_enu", "v", "nan", "silent_nan", "a frame swap of logged vectors: a NaN reading stays NaN"),
    (_FILTERS, _SENSORS, "nan", "silent_accept", "NaN marks a sensor dropout: held or skipped, and counted in the result"),
    (
        r"filters\.(mahony\.mahony|quaternion_kf\.quaternion_kf|inertial_lowpass\.inertial_lowpass)",
        r"f_b|m_b",
        "inf",
        "silent_accept",
        "a non-finite accelerometer or magnetometer sample is skipped like a dropout (counted)",
    ),
    (
        r"filters\.observations\.(pack|screened)|robust\.screen",
        "m_b",
        r"nan|inf",
        "silent_nan",
        "the screened record holds the samples; NaN/inf ones are skipped by the kernel and counted",
    ),
    (
        r"filters\.observations\.RtkHeading",
        "heading",
        "nan",
        "silent_nan",
        "NaN in a valid epoch is a dropout (RtkHeading docstring)",
    ),
    (r"imu\.ImuSamples", r"w_ib_b|f_b", "nan", "silent_nan", "the record holds the samples; NaN marks a dropout"),
    (
        r"euler\.integrate_euler",
        "bias_b",
        "nan",
        "silent_nan",
        "a NaN bias estimate means 'not yet observable' (docstring); a constant one has no earlier estimate to keep",
    ),
    (
        r"trajectory\.Trajectory",
        r"lla|vel_n|q_bn",
        "nan",
        "silent_nan",
        "a trajectory also holds filter output, which marks epochs without a solution NaN (tests/test_bad_input.py)",
    ),
    (
        r"robust\.(despike|fault_report|hold|longest_repeat|stuck_(mask|samples))",
        r"x|w_ib_b|f_b",
        "nan",
        r"silent_nan|silent_accept",
        "robust-input functions exist to find, count and hold NaN samples",
    ),
    (
        r"faults\.(dropouts|gap|heading_flips|position_jumps|saturate|spikes)",
        r"x|heading|lla",
        "nan",
        r"silent_nan|silent_accept",
        "fault injectors corrupt any record, also one with dropouts already (NaN passes)",
    ),
    (
        r"filters\.planar_ekf\.(dead_reckoning|filter_grid)|papers\.gauss_kruger_ekf\.ekf|kalman\.update",
        r"speed|yaw_rate|z|gps|heading",
        "nan",
        r"silent_nan|silent_accept",
        "a NaN measurement component is skipped (predict only / held); its innovation is NaN (documented)",
    ),
    (
        r"filters\.heading_fusion\.(fuse_rtk_heading|rtk_at_imu_rate)",
        r"heading_rtk|heading",
        "nan",
        "silent_accept",
        "NaN RTK heading: no fix at that epoch (held, then dropped)",
    ),
    (
        r"papers\.rotation_bias\.(tilt_residuals|lsq_bias|running_lsq_bias|kalman_bias)",
        r"w_ib_b|f_b|r|V",
        "nan",
        r"silent_nan|silent_accept",
        "a dwell with dropouts is skipped (NaN residual, counted); NaN residuals are left out",
    ),
    (
        r"analysis\.(rmse|position_error)",
        r"err|estimate",
        "nan",
        "silent_nan",
        "NaN propagates: no silent dropping (docstrings; tests/test_bad_input.py)",
    ),
    (r"analysis\.condition_number", "V", "nan", "silent_accept", "blocks holding NaN are left out (docstring)"),
    (
        r"analysis\.orientation_errors",
        "q_ref",
        "nan",
        "silent_accept",
        "a NaN reference row is a gap of the reference: left out and counted in OrientationErrors.missing_reference",
    ),
    (r"analysis\.time_offset", "x", "nan", "silent_accept", "a NaN row of x is a missing sample, left out (docstring)"),
    (
        r"analysis\.time_offset",
        "t",
        "time_jump",
        "silent_accept",
        "each sample of x is compared with the reference at its own time: a gap between samples only leaves fewer "
        "(a gap of the reference is refused)",
    ),
    (
        r"atmosphere\.(reference_pressure|segment_floors)",
        r"p|h",
        "nan",
        "silent_accept",
        "NaN samples (no reading) are ignored (docstrings)",
    ),
    (r"io\.align", "x_source", "nan", "silent_accept", "NaN marks a missing reading (docstring)"),
    (
        r"calibration\.(Mag|Accel)Calibration",
        r"residual|norm_spread_\w+|condition",
        "nan",
        "silent_accept",
        "a fit's quality figure is NaN when it was not computed (the field's default)",
    ),
    # inf and huge values with a meaning
    (
        r"analysis\.(condition_number|cramer_rao_bound)",
        "V",
        "wrong_shape",
        "silent_nan",
        "inf: the unknowns are not observable from these blocks (docstrings)",
    ),
    (
        r"attitude\.(quat_\w+|ned_to_enu_quat)|filters\.(mahony\.mahony|quaternion_kf\.quaternion_kf|observations\.pack)|"
        r"strapdown\.integrate(_attitude)?|sensors\.simulate_magnetometer",
        r"q|q0|q_ned|q_bn",
        "1e300",
        "silent_accept",
        "quaternions of any finite magnitude are normalised exactly (tests/test_magnitudes.py)",
    ),
    (
        r"papers\.rotation_bias\.draw_rotation_schedule",
        r"time|starts",
        r"time_jump|wrong_shape",
        "silent_accept",
        "a drawing: any increasing time axis is drawn as given, any number of dwell windows shaded",
    ),
    (
        r"imu\.ImuSamples",
        "dt",
        r"1e300|time_jump",
        "silent_accept",
        "the record only holds the intervals; an interval too long to integrate is refused (small_turns) or counted as a "
        "clock jump by the filter that screens it",
    ),
    (
        r"filters\.heading_fusion\.fuse_rtk_heading",
        "dt",
        r"1e300|time_jump",
        "silent_accept",
        "dt only ages the last RTK epoch: a long interval is a clock jump, counted in faults['clock', 'jump'], over which "
        "the carried epoch is dropped (tests/faults/test_faults_ahrs.py)",
    ),
    (
        r"filters\.zupt_ins\.Gates",
        r"zupt|baro|mag_field|mag_dip",
        r"inf|1e300",
        r"silent_nan|silent_accept",
        "inf disables a gate, any finite value is one (Gates docstring)",
    ),
    (
        r"repro\.check(_range|_outside)?",
        r"value|expected|tol|lower|upper",
        r"nan|inf|1e300",
        r"other_exception|silent_accept",
        "any finite target is a claim; a reproduced value outside it fails the claim (ClaimCheckFailed, tests/test_bad_input.py)",
    ),
    # quaternion algebra and matrices that need not be rotations
    (
        r"attitude\.quat_(mult|conj)",
        r"p|q",
        "zero_quat",
        "silent_accept",
        "Hamilton algebra on any quaternion: the pure quaternion [0, w] of the kinematics is zero at rest (notebook 04)",
    ),
    (
        r"attitude\.orthonormalize|alignment\.triad_heading",
        r"C|C_bn",
        "not_rotation",
        "silent_accept",
        "made for raw TRIAD matrices, which noise makes non-orthonormal (orthonormalize handles det < 0 on purpose)",
    ),
    (
        r"strapdown\.nav_step",
        r"lla|vel|q",
        "valid",
        "modifies_input",
        "nav_step updates a writeable float64 state in place (documented), the per-sample API of the kernels",
    ),
    # periodic headings, clock jumps and time axes
    (r".*", _HEADINGS, "degrees", "silent_accept", "a heading is periodic: 45 rad is a valid unwrapped heading"),
    (
        r"analysis\.(attitude_errors|error_statistics)",
        r"hpr|hpr_true",
        "degrees",
        "silent_accept",
        "compares any angle triples component by component (wrapped), not rotations (tests/test_gyrobias.py: [-4, 4] rad)",
    ),
    (
        r"filters\.planar_ekf\.filter_grid|papers\.gauss_kruger_ekf\.ekf",
        "t",
        "time_jump",
        "silent_accept",
        "a clock jump in t is not propagated over (the state is held, P grows) and is reported in "
        "faults['clock', 'jump'] (tests/faults/test_faults_planar.py)",
    ),
    (
        r"filters\.planar_ekf\.dead_reckoning",
        "t",
        "time_jump",
        "silent_accept",
        "a clock jump in t is integrated as one typical step (a stamp glitch costs nothing, a gap adds no unmeasured "
        "motion) and reported in faults['clock', 'jump'] (tests/faults/test_faults_planar.py)",
    ),
    (
        r"atmosphere\.(classify_floor|segment_floors)",
        "ref_floor",
        "negative_count",
        "silent_accept",
        "a floor number, not a count: basements are negative floors",
    ),
    (
        r"analysis\.settling_time|atmosphere\.reference_pressure|faults\.\w+|timing\.(intervals|sanitize)|"
        r"sensors\.(magnetic_disturbances|outage_mask|simulate_barometer)|trajectory\.Trajectory|io\.align|"
        r"papers\.pedestrian_ins\.hvac_pressure_steps|filters\.heading_fusion\.rtk_at_imu_rate",
        r"time|t_target|t_source|door_times",
        "time_jump",
        "silent_accept",
        "any increasing time axis is valid here: nothing assumes uniform sampling (timing reports the gap)",
    ),
    (
        r"faults\.swap_timestamps|timing\.sanitize",
        "time",
        "non_monotonic",
        "silent_accept",
        "made for faulty clocks: swap_timestamps composes with other injections, sanitize sorts",
    ),
    (
        r"papers\.pedestrian_ins\.hvac_pressure_steps",
        "door_times",
        r"empty|non_monotonic",
        "silent_accept",
        "door times are a set: none means no offset, any order is sorted",
    ),
    (r"sensors\.outage_mask", "outages", "empty", "silent_accept", "no outages: every epoch valid"),
    (
        r"papers\.north_finding\.simulate_static_outputs",
        r"gyro_bias|accel_bias",
        "wrong_shape",
        "silent_accept",
        "a bias is one value for every axis or a per-axis (3,) vector (documented)",
    ),
    (
        r"imu\.SensorLimits",
        r"full_scale_\w+",
        "none",
        "silent_nan",
        "None is no range, as everywhere a full_scale_* is taken (range_limit)",
    ),
    (
        r"filters\.observations\.RtkHeading",
        "heading",
        "0d",
        "silent_accept",
        "the RTK heading broadcasts against the filter's samples (documented (..., N) broadcasting)",
    ),
    # valid-unusual calls
    (
        r"sensors\.simulate_\w+|faults\.\w+|papers\.north_finding\.simulate_static_outputs",
        ".*",
        "batch",
        "differs",
        "random draws are made over the whole batch: every trial gets its own noise",
    ),
    (r"analysis\.rmse", "err", "batch", "differs", "rmse reduces along axis (default 0): a leading batch axis is that axis"),
    (r"analysis\.moving_mean", "x", "batch", "differs", "the mean moves along axis 0 (documented (N, ...)): a leading axis is N"),
    (
        r"imu\.unpack",
        ".*",
        ".*",
        r"silent_accept|silent_nan|differs",
        "unpack only splits ImuSamples; plain arrays go through unchanged to the filter that calls it, which validates them",
    ),
]


def by_design(case: dict) -> str | None:
    """The reason of the first BY_DESIGN rule that matches ``case``, or None."""
    return next((rule[4] for rule in BY_DESIGN if _matches(rule, case)), None)


def _matches(rule, case) -> bool:
    return all(re.fullmatch(p, case[k]) for k, p in zip(("callable", "arg", "mutation", "outcome"), rule[:4], strict=True))


# ----------------------------------------------------------------------------------------------------------
# The table of valid calls and the public callables it must cover
# ----------------------------------------------------------------------------------------------------------


@dataclasses.dataclass
class Arg:
    name: str
    value: object
    annotation: str
    kind: str
    none_ok: bool
    elementwise: bool
    any_shape: bool
    deg: bool
    n: int | None


def with_defaults(func, call: Call) -> Call:
    """``call`` with every keyword parameter it leaves out given its default, so that every argument is fuzzed."""
    params = inspect.signature(func).parameters.values()
    defaults = {
        p.name: p.default
        for p in params
        if p.default is not inspect.Parameter.empty
        and repr(p.default) != "<factory>"  # a dataclass field's default_factory
        and p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY)
        and p.name not in call.kwargs
    }
    return dataclasses.replace(call, kwargs={**call.kwargs, **defaults})


def arguments(key: str, func, call) -> list[Arg]:
    """The arguments of a valid call, with their kinds."""
    sig = inspect.signature(func)
    n = call.n if call.n is not None else _samples(call.kwargs)
    deg = call.kwargs.get("deg", sig.parameters["deg"].default if "deg" in sig.parameters else False) is True
    out = []
    for name, value in call.kwargs.items():
        p = sig.parameters.get(name)
        ann = "" if p is None or p.annotation is inspect.Parameter.empty else str(p.annotation)
        none_ok = p is not None and (p.default is None or "None" in ann)
        v = value.make() if isinstance(value, Fresh) else value
        out.append(
            Arg(
                name,
                v,
                ann,
                "object" if isinstance(value, Fresh) else kind(name, ann, v),
                none_ok,
                name in call.elementwise or call.elementwise == ("*",),
                name in call.any_shape,
                deg,
                n,
            )
        )
    return out


def _samples(kwargs: dict) -> int | None:
    """N, the number of samples of the call's series: the length of its first (N, 3) array or time axis."""
    for name, v in kwargs.items():
        if isinstance(v, np.ndarray) and v.dtype.kind == "f":
            if v.ndim >= 2 and v.shape[-1] == 3 or name in TIME_NAMES and v.ndim == 1:
                return v.shape[-2] if v.ndim >= 2 else v.shape[0]
    return None


# ----------------------------------------------------------------------------------------------------------
# Running one case
# ----------------------------------------------------------------------------------------------------------


def leaves(obj, path="", depth=0) -> dict[str, np.ndarray]:
    """Numeric leaves of a result (arrays, numbers, fields of tuples, dicts, dataclasses), by path."""
    if depth > 5:
        return {}
    if isinstance(obj, (bool, np.bool_, int, float, np.number)):
        return {path: np.asarray(obj)}
    if isinstance(obj, np.ndarray):
        return {path: obj} if obj.dtype.kind in "biufc" else {}
    if isinstance(obj, dict) or hasattr(obj, "items") and hasattr(obj, "keys"):
        out = {}
        for k in list(obj.keys()):
            out.update(leaves(obj[k], f"{path}[{k!r}]", depth + 1))
        return out
    if isinstance(obj, (tuple, list)):
        out = {}
        for i, x in enumerate(obj):
            out.update(leaves(x, f"{path}[{i}]", depth + 1))
        return out
    if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        out = {}
        for f in dataclasses.fields(obj):
            out.update(leaves(getattr(obj, f.name), f"{path}.{f.name}", depth + 1))
        return out
    return {}


def nonfinite(result: dict[str, np.ndarray], baseline: dict[str, np.ndarray]) -> list[str]:
    """Paths of float leaves with non-finite values where the valid call's leaf is all finite."""
    bad = []
    for p, x in result.items():
        if x.dtype.kind in "fc" and not np.all(np.isfinite(x)):
            b = baseline.get(p)
            if b is None or b.dtype.kind not in "fc" or np.all(np.isfinite(b)):
                bad.append(p)
    return bad


def same(a: dict[str, np.ndarray], b: dict[str, np.ndarray]) -> str:
    """'' if the two results hold the same values, else where they differ."""
    if a.keys() != b.keys():
        return f"fields {sorted(set(a) ^ set(b))[:3]}"
    for p in a:
        x, y = a[p], b[p]
        if x.shape != y.shape:
            return f"{p}: shape {x.shape} vs {y.shape}"
        if x.dtype.kind in "fc" or y.dtype.kind in "fc":
            if not np.allclose(x, y, rtol=1e-9, atol=1e-12, equal_nan=True):
                return f"{p}: max |diff| {np.nanmax(np.abs(np.asarray(x, float) - y)):.3g}"
        elif not np.array_equal(x, y):
            return f"{p}: values differ"
    return ""


def prefix(n1: dict[str, np.ndarray], full: dict[str, np.ndarray], n: int) -> str:
    """'' if every per-sample leaf of the N = 1 result is the start of the full result's; else where not.

    A leaf is per-sample when one axis has N (or N + 1) entries in the full result and fewer in the N = 1
    result, all other axes equal. Leaves without such an axis (aggregates) are not compared.
    """
    compared = 0
    for p, x in n1.items():
        y = full.get(p)
        if y is None or x.ndim != y.ndim:
            continue
        axes = [i for i in range(x.ndim) if x.shape[i] != y.shape[i]]
        if len(axes) != 1 or y.shape[axes[0]] not in (n, n + 1) or x.shape[axes[0]] > y.shape[axes[0]]:
            continue
        ref = np.take(y, np.arange(x.shape[axes[0]]), axis=axes[0])
        d = same({p: x}, {p: ref})
        if d:
            return d
        compared += 1
    return "" if compared else "not compared"


def names(message: str, arg: str, others=()) -> bool:
    """Whether an error message names ``arg``.

    It does when it starts with ``arg`` (alone, indexed as in ``"hpr[..., 1] (pitch): ..."``, or in a leading
    list such as ``"lat, h: ..."``), or when it starts with another argument of the call (``others``) and
    mentions ``arg`` as the one it must agree with (``"f_b: expected the shape of w_ib_b ..."``).
    """
    head = message.split(":", 1)[0]
    if re.match(rf"^{re.escape(arg)}(?!\w)", message) or arg in [h.strip() for h in head.split(",")]:
        return True
    starts_with_other = any(re.match(rf"^{re.escape(o)}(?!\w)", message) for o in others if o != arg)
    return starts_with_other and re.search(rf"(?<![\w.]){re.escape(arg)}(?!\w)", message.split(":", 1)[-1]) is not None


def call_once(func, kwargs: dict, before=None):
    """``func(**kwargs)`` on fresh copies of the arguments (a function may update an argument in place)."""
    if before is not None:
        before()
    return func(**{k: (v.make() if isinstance(v, Fresh) else copy.deepcopy(v)) for k, v in kwargs.items()})


def modified_inputs(func, kwargs: dict, before=None) -> list[str]:
    """Names of the array arguments that the call changes in place."""
    work = {k: v.copy() for k, v in kwargs.items() if isinstance(v, np.ndarray)}
    if before is not None:
        before()
    func(**{k: (v.make() if isinstance(v, Fresh) else work.get(k, v)) for k, v in kwargs.items()})
    return [k for k in work if not np.array_equal(work[k], kwargs[k], equal_nan=True)]


def run_case(case: tuple, table: dict, funcs: dict, baselines: dict) -> dict:
    """Run one case in this process: ``(callable, arg, mutation)``; returns its record."""
    key, argname, mutation = case
    call, func = table[key], funcs[key]
    args = {a.name: a for a in arguments(key, func, call)}
    rec = {"callable": key, "arg": argname, "mutation": mutation}
    with warnings.catch_warnings(), np.errstate(all="ignore"):
        warnings.simplefilter("ignore")
        try:
            if mutation in MUTATIONS:
                kwargs = dict(call.kwargs, **{argname: mutate(mutation, args[argname])})
                rec.update(_bad(func, kwargs, call, argname, baselines[key], tuple(args), mutation))
            else:
                rec.update(_unusual(func, call, args, argname, mutation, baselines[key]))
        finally:
            _close_figures()
    return rec


def _bad(func, kwargs, call, argname, baseline, others, mutation) -> dict:
    try:
        out = call_once(func, kwargs, call.before)
    except (ValueError, TypeError) as exc:
        msg = str(exc)
        return {
            "outcome": "clean" if names(msg, argname, others) else "unnamed",
            "error": type(exc).__name__,
            "message": msg[:300],
        }
    except Exception as exc:  # noqa: BLE001 -- any other exception is the finding
        return {"outcome": "other_exception", "error": type(exc).__name__, "message": str(exc)[:300], "where": _where(exc)}
    if mutation == "empty_elementwise" and not any(x.size for x in leaves(out).values() if x.ndim):
        return {"outcome": "clean", "message": "accepted: an empty result"}  # an empty batch is valid
    if mutation == "stuck_axis":
        counted = counted_stuck(out)
        if counted:
            return {"outcome": "clean", "message": "accepted: the stuck axis is counted in faults"}
        return {
            "outcome": "silent_accept",
            "message": "stuck gyro axis " + ("not counted in faults" if counted is False else "and no FaultReport returned"),
        }
    found = leaves(out)
    bad = nonfinite(found, baseline)
    if bad:
        return {"outcome": "silent_nan", "message": f"non-finite in {', '.join(bad[:3])}"}
    if mutation == "tiny_dt":  # a positive interval, however short, is valid if the result stays physical
        huge = [p for p, x in found.items() if x.dtype.kind in "fc" and x.size and np.max(np.abs(x)) > 1e100]
        if not huge:
            return {"outcome": "clean", "message": "accepted: a short interval, a finite result"}
        return {"outcome": "silent_accept", "message": f"values beyond 1e100 in {', '.join(huge[:3])}"}
    return {"outcome": "silent_accept"}


def _unusual(func, call, args, argname, variant, baseline) -> dict:
    try:
        if variant == "n1":
            n = next(iter(args.values())).n
            kwargs = {k: _first(v, n) for k, v in call.kwargs.items()}
            out = leaves(call_once(func, kwargs, call.before))
            d = prefix(out, baseline, n)
            return {"outcome": "equal" if d in ("", "not compared") else "differs", "message": d}
        if variant == "batch" and argname == "*":
            stacked = {k: unusual("batch", a)[0] if unusual("batch", a) is not None else call.kwargs[k] for k, a in args.items()}
            return _batch_outcome(func, call, stacked, baseline)
        given, ref = unusual(variant, args[argname])
        if variant == "batch":
            return _batch_outcome(func, call, dict(call.kwargs, **{argname: given}), baseline)
        try:
            expected = leaves(call_once(func, dict(call.kwargs, **{argname: ref}), call.before))
        except Exception as exc:  # noqa: BLE001 -- the same values in float64 are no valid call
            return {"outcome": "n/a", "message": f"float64 reference: {type(exc).__name__}: {exc}"[:300]}
        out = leaves(call_once(func, dict(call.kwargs, **{argname: given}), call.before))
    except Exception as exc:  # noqa: BLE001
        return _refusal(exc, args)
    d = same(out, expected)
    return {"outcome": "differs" if d else "equal", "message": d}


def _batch_outcome(func, call, kwargs, baseline) -> dict:
    try:
        out = leaves(call_once(func, kwargs, call.before))
    except Exception as exc:  # noqa: BLE001
        return _refusal(exc, kwargs)
    d = _batch(out, baseline)
    return {"outcome": "differs" if d else "equal", "message": d}


def _refusal(exc: Exception, argnames) -> dict:
    """Outcome of a valid-unusual call that raised: refused (a ValueError/TypeError naming an argument) or error."""
    msg = str(exc)
    if isinstance(exc, (ValueError, TypeError)):
        named = any(names(msg, a) for a in argnames)
        return {"outcome": "refused" if named else "error", "error": type(exc).__name__, "message": msg[:300]}
    return {"outcome": "error", "error": type(exc).__name__, "message": msg[:300], "where": _where(exc)}


def _batch(out: dict, baseline: dict) -> str:
    """'' if every leaf of the batched result is BATCH copies of the valid result's leaf.

    A leaf of the valid result's shape (one that does not depend on the batched argument, e.g. a time axis)
    is compared as it is.
    """
    if out.keys() != baseline.keys():
        return f"fields {sorted(set(out) ^ set(baseline))[:3]}"
    for p, x in out.items():
        if x.shape == baseline[p].shape:
            d = same({p: x}, {p: baseline[p]})
        elif x.shape == (BATCH,) + baseline[p].shape:
            d = next((e for e in (same({p: x[i]}, {p: baseline[p]}) for i in range(BATCH)) if e), "")
        else:
            d = f"{p}: shape {x.shape}, expected {(BATCH,) + baseline[p].shape}"
        if d:
            return d
    return ""


def _first(value, n):
    """``value`` cut to its first sample if it is a series of ``n`` samples."""
    if isinstance(value, np.ndarray) and value.ndim == 1 and value.shape[0] == n:
        return value[:1]
    if isinstance(value, np.ndarray) and value.ndim >= 2 and value.shape[-2] == n:
        return value[..., :1, :]
    return value


def _where(exc: BaseException) -> str:
    tb = traceback.extract_tb(exc.__traceback__)
    return f"{Path(tb[-1].filename).name}:{tb[-1].lineno}" if tb else ""


def _close_figures():
    if "matplotlib.pyplot" in sys.modules:
        sys.modules["matplotlib.pyplot"].close("all")


# ----------------------------------------------------------------------------------------------------------
# Forked workers with a timeout
# ----------------------------------------------------------------------------------------------------------


def _worker(conn, table, funcs, baselines, cases):
    sys.stdout = sys.stderr = open(os.devnull, "w")  # noqa: SIM115 -- a worker's prints are noise here
    while True:
        i = conn.recv()
        if i is None:
            return
        conn.send(run_case(cases[i], table, funcs, baselines))


def run_all(cases: list, table: dict, funcs: dict, baselines: dict, jobs: int, timeout: float) -> list[dict]:
    """Run every case in ``jobs`` forked workers; a case without an answer within ``timeout`` s is a hang."""
    ctx = multiprocessing.get_context("fork")
    results: list[dict | None] = [None] * len(cases)
    todo = list(range(len(cases)))[::-1]
    workers: dict = {}  # connection -> [process, case index or None, start time]

    def start():
        parent, child = ctx.Pipe()
        proc = ctx.Process(target=_worker, args=(child, table, funcs, baselines, cases), daemon=True)
        proc.start()
        child.close()
        workers[parent] = [proc, None, 0.0]

    def assign(conn):
        if todo:
            i = todo.pop()
            conn.send(i)
            workers[conn][1:] = [i, time.monotonic()]
        else:
            workers[conn][1] = None

    for _ in range(jobs):
        start()
    for conn in list(workers):
        assign(conn)
    while any(w[1] is not None for w in workers.values()):
        busy = [c for c, w in workers.items() if w[1] is not None]
        for conn in wait(busy, timeout=0.2):
            proc, i, _ = workers[conn]
            try:
                results[i] = conn.recv()
                assign(conn)
            except (EOFError, OSError):
                results[i] = dict(
                    zip(("callable", "arg", "mutation"), cases[i], strict=True),
                    outcome="crash",
                    message=f"worker exit code {proc.exitcode}",
                )
                _replace(workers, conn, start, assign)
        now = time.monotonic()
        for conn, (_, i, t0) in list(workers.items()):
            if i is not None and now - t0 > timeout:
                results[i] = dict(
                    zip(("callable", "arg", "mutation"), cases[i], strict=True),
                    outcome="hang",
                    message=f"no answer within {timeout:g} s",
                )
                _replace(workers, conn, start, assign)
    for conn, (proc, _, _) in workers.items():
        conn.send(None)
        proc.join(5)
    return results


def _replace(workers, conn, start, assign):
    """Kill a hung or dead worker (ours, by its process id) and start a fresh one on the next case."""
    proc = workers.pop(conn)[0]
    proc.kill()
    proc.join()
    conn.close()
    start()
    assign(next(c for c, w in workers.items() if w[1] is None and c is not conn))


# ----------------------------------------------------------------------------------------------------------
# Main
# ----------------------------------------------------------------------------------------------------------


def cases_of(key: str, call: Call, func) -> list[tuple]:
    out = []
    args = arguments(key, func, call)
    for arg in args:
        out += [(key, arg.name, m) for m in MUTATIONS if applies(m, arg)]
        out += [
            (key, arg.name, v)
            for v in ("list", "float32", "int", "batch")
            if unusual(v, arg) is not None and not (v == "batch" and call.elementwise == ("*",))
        ]
    if call.elementwise == ("*",):
        out.append((key, "*", "batch"))
    if args and args[0].n is not None:
        out.append((key, "*", "n1"))
    return out


def select(keys, only: list[str] | None):
    if not only:
        return sorted(keys)
    return sorted(k for k in keys if any(k == o or k.startswith(o + ".") for o in only))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--only", nargs="+", help="modules (e.g. attitude, filters.mahony) or callables to fuzz")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--timeout", type=float, default=60.0, help="seconds before a call counts as a hang")
    ap.add_argument("--verbose", action="store_true", help="counts per module too")
    ap.add_argument("--out", default=str(REPO / "build" / "fuzz.json"))
    opts = ap.parse_args(argv)
    t_start = time.monotonic()

    import matplotlib

    matplotlib.use("Agg")
    root = os.environ.get("NAVLIB_ROOT")
    os.environ["NAVLIB_ROOT"] = _sandbox()  # navlib.repro writes there, not to build/
    try:
        return _run(opts, t_start)
    finally:
        if root is None:
            del os.environ["NAVLIB_ROOT"]
        else:
            os.environ["NAVLIB_ROOT"] = root


def _run(opts, t_start: float) -> int:
    funcs = public_callables()
    listed = fuzz_calls.table()
    missing = sorted(set(funcs) - set(listed))
    stale = sorted(set(listed) - set(funcs))
    if missing or stale:
        print(
            f"fuzz: public callables without a valid call in tools/fuzz_calls.py: {missing}" if missing else "",
            f"fuzz: entries for names that are not public: {stale}" if stale else "",
            sep="\n",
            file=sys.stderr,
        )
        return 2
    table = {k: c if isinstance(c, Skip) else with_defaults(funcs[k], c) for k, c in listed.items()}
    keys = select(table, opts.only)
    if not keys:
        print(f"fuzz: nothing matches --only {opts.only}", file=sys.stderr)
        return 2
    skipped = [k for k in keys if isinstance(table[k], Skip)]
    keys = [k for k in keys if not isinstance(table[k], Skip)]

    baselines, broken, inplace = {}, [], []
    with warnings.catch_warnings(), contextlib.redirect_stdout(io.StringIO()):
        warnings.simplefilter("ignore")
        for k in keys:  # the valid calls (also compiles the kernels before the fork)
            try:
                baselines[k] = leaves(call_once(funcs[k], table[k].kwargs, table[k].before))
                changed = modified_inputs(funcs[k], table[k].kwargs, table[k].before)
            except Exception as exc:  # noqa: BLE001
                broken.append(f"{k}: {type(exc).__name__}: {exc}")
                changed = []
            inplace += [
                {
                    "callable": k,
                    "arg": a,
                    "mutation": "valid",
                    "outcome": "modifies_input",
                    "message": "the valid call changes this argument in place",
                }
                for a in changed
            ]
            _close_figures()
    if broken:
        print("fuzz: valid calls that fail:\n  " + "\n  ".join(broken), file=sys.stderr)
        return 2
    cases = [c for k in keys for c in cases_of(k, table[k], funcs[k])]
    results = inplace + run_all(cases, table, funcs, baselines, opts.jobs, opts.timeout)
    return report(results, keys, skipped, opts, full=not opts.only, seconds=time.monotonic() - t_start)


def report(results: list[dict], keys, skipped, opts, full: bool, seconds: float) -> int:
    for r in results:
        r["by_design"] = by_design(r) if r["outcome"] not in ("clean", "equal", "n/a") else None
    bad_calls = [r for r in results if r["mutation"] not in UNUSUAL]
    odd_calls = [r for r in results if r["mutation"] in UNUSUAL]
    fails = [r for r in results if _fails(r) and not r["by_design"]]
    gaps = [r for r in fails if case_id(r) in KNOWN_GAPS]
    fails = [r for r in fails if case_id(r) not in KNOWN_GAPS]

    def line(rs, classes):
        c = Counter(r["outcome"] for r in rs)
        d = Counter(r["outcome"] for r in rs if r["by_design"])
        return "  ".join(f"{k} {c[k]}" + (f" ({d[k]} by design)" if d[k] else "") for k in classes)

    print(f"fuzz: {len(keys)} callables ({len(skipped)} records not fuzzed), {len(results)} calls, {seconds:.0f} s")
    print("  bad calls:     " + line(bad_calls, ("clean",) + BAD_CLASSES))
    print("  valid-unusual: " + line(odd_calls, ("equal", "refused") + UNUSUAL_BAD + ("n/a",)))
    if opts.verbose:
        for mod in sorted({k.rsplit(".", 1)[0] for k in keys}):
            rs = [r for r in results if r["callable"].rsplit(".", 1)[0] == mod]
            print(f"  {mod}:")
            print(f"    bad calls:     {line([r for r in rs if r['mutation'] not in UNUSUAL], ('clean',) + BAD_CLASSES)}")
            print(f"    valid-unusual: {line([r for r in rs if r['mutation'] in UNUSUAL], ('equal', 'refused') + UNUSUAL_BAD)}")
    unused = [r for r in BY_DESIGN if not any(r[4] == x["by_design"] and _matches(r, x) for x in results)] if full else []
    for r in unused:
        print(f"  stale by-design rule (matches nothing): {r[:4]}")
    if gaps:
        print(f"  known gaps (tools/fuzz_calls.py KNOWN_GAPS): {', '.join(sorted(case_id(r) for r in gaps))}")
    fixed = sorted(set(KNOWN_GAPS) - {case_id(r) for r in gaps}) if full else []
    fixed = [g for g in fixed if g.rsplit("-", 1)[1] in {*MUTATIONS, *UNUSUAL}]  # the others are rows of the tests
    for g in fixed:
        print(f"  stale known gap (navlib refuses it now; remove it from KNOWN_GAPS): {g}")
    out = Path(opts.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    noteworthy = [r for r in results if r["outcome"] not in ("clean", "equal", "n/a")]
    out.write_text(
        json.dumps(
            {"seconds": round(seconds, 1), "callables": len(keys), "calls": len(results), "cases": noteworthy},
            indent=1,
            default=str,
        )
        + "\n"
    )
    for r in fails[:40]:
        print(
            f"  FAIL {r['callable']}({r['arg']}) {r['mutation']}: {r['outcome']}"
            f"{' -- ' + r['message'][:140] if r.get('message') else ''}"
        )
    if len(fails) > 40:
        print(f"  ... {len(fails) - 40} more in {out}")
    return 1 if fails or unused or fixed else 0


def case_id(r: dict) -> str:
    """``callable-arg-mutation``, the id of a case in KNOWN_GAPS and in the tests."""
    return f"{r['callable']}-{r['arg']}-{r['mutation']}"


def failing(r: dict) -> bool:
    """Whether a case's outcome is a finding: a bad class that is not by design."""
    return _fails(r) and by_design(r) is None


def _fails(r: dict) -> bool:
    if r["mutation"] not in UNUSUAL:
        return r["outcome"] in BAD_CLASSES
    return r["outcome"] in UNUSUAL_BAD or r["outcome"] == "refused" and r["mutation"] in ("list", "float32", "int")


def _sandbox() -> str:
    """A throw-away repository root for navlib.repro (its build/ folder)."""
    root = Path(tempfile.mkdtemp(prefix="navlib-fuzz-"))
    (root / "pyproject.toml").write_text("[project]\nname = 'x'\n")
    (root / "navlib").mkdir()
    (root / "data").mkdir()
    for name in ("claims.csv", "errata.csv"):  # repro.verdict reads the catalogue
        shutil.copy(REPO / "data" / name, root / "data")
    return str(root)


if __name__ == "__main__":
    sys.exit(main())
