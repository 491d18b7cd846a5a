"""Vector observations for attitude filters, their gates, and the filters' shared input/output.

An attitude filter (Mahony, the quaternion KF, a Madgwick filter) corrects gyro integration with
two directions: gravity from the accelerometer, and a horizontal reference from the magnetometer
(its field levelled with the current attitude) or, with a dual-antenna GNSS receiver, the RTK
heading as a north pseudo-vector ``C_nb(H_rtk, pitch_est, roll_est) [0, 1, 0]`` (mode (a) of
Fig. 4 of Zhang et al. 2023, :mod:`navlib.papers.mimu_mag_rtk`). This module owns, once for all
such filters:

* the option records :class:`AttitudeGates` (accelerometer-norm and :class:`MagGate` gates) and
  :class:`RtkHeading` (the RTK heading reference with its hold, gate and re-acquisition);
* :func:`screened` and :func:`pack` -- the samples screened once (:func:`navlib.robust.screen`; screen once, filter
  many: every filter takes the screen's result in place of its ``ImuSamples``) as the :class:`AttitudeInputs` record
  of the compiled kernels (trials flattened), with the gates' limits;
* :func:`observe`, :func:`rtk_north`, :func:`pi_error`, :func:`rtk_gate`, :func:`learning`, :func:`jump_step`,
  :func:`relock` -- the compiled per-sample steps: unit vectors gated (the accelerometer's and magnetometer's
  gates; the RTK pseudo-vector with its state-dependent gate), Mahony's error ``e = a_meas x a_est + m_meas x m_est``,
  when the gyro-bias integral may learn, and what follows a clock jump (re-initialisation only when earned);
* :class:`AttitudeResult` and :func:`run_trials` (Monte Carlo trials in parallel; the kernels release
  the GIL).

What the filters do with bad samples, once for all of them: the gyro is held over dropouts and spikes,
and a stuck axis over its stuck run while the live axes go on measuring (:func:`navlib.robust.screen`;
the gyro-bias integral is frozen while nothing is measured and, after a hold of ``stuck_run`` samples or
more or a clock jump, for :data:`SETTLE_TIME_CONSTANTS` / kp seconds, unless the jump was a stamp glitch:
:func:`learning`);
saturated gyro samples are used (the best reading available) and flagged; accelerometer and
magnetometer samples that are missing, at the rails, in free fall, spikes or outside their gate are
skipped: the attitude is propagated by the gyro alone over them. A clock jump is integrated as one typical
interval (a stamp glitch leaves the samples contiguous); the attitude is re-initialised only if the next
quasi-static window shows it is lost, and then from that window's means (:func:`relock`). Every case is counted in the
result's ``faults`` (:class:`navlib.robust.FaultReport`): the screen's keys, plus ``("accel" | "mag",
"outlier")`` for gated samples and ``("heading", "nan" | "outlier" | "reacquired")`` for RTK epochs
(``mag`` is the heading reference: the RTK pseudo-vector in RTK mode).

A new attitude filter is a module next to :mod:`navlib.filters.mahony` that calls these.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np
from numba import njit

from .. import _earth, attitude
from .._kernels import count_flags, dcm_heading, euler_to_quat, level, tilt_heading, wrap_pi
from .._threads import run_chunks
from .._typing import Array, ArrayLike, Quat, Vec3
from .._validate import (
    Is,
    NonNegative,
    Positive,
    as_array,
    as_quat,
    booleans,
    boundary,
    broadcast_to,
    fields_checked,
    flag,
    instance,
    integer,
    kernel_array,
    scalar,
)
from ..imu import ImuSamples, SensorLimits
from ..robust import FaultReport, Screened, screen
from ..units import G0

__all__ = [
    "MagGate",
    "AttitudeGates",
    "RtkHeading",
    "AttitudeResult",
    "AttitudeInputs",
    "SETTLE_TIME_CONSTANTS",
    "KI_WITH_REFERENCE",
    "integral_gain",
    "magnetic_reference",
    "screened",
    "pack",
    "unit_vectors",
    "attitude_result",
    "run_trials",
]

KI_WITH_REFERENCE = 0.02
"""Default integral gain ``ki`` (rad/s^2) of the attitude filters' PI loop when they have a heading reference
(magnetometer or RTK heading); without one the default is 0 (:func:`integral_gain`)."""

SETTLE_TIME_CONSTANTS = 15.0
"""After a clock jump or a gyro hold of ``stuck_run`` samples or more, the gyro-bias integral of the attitude
filters stays frozen for this many time constants ``1 / kp`` of the PI loop (15 s at kp = 1 rad/s) while the
reference removes the attitude error the fault left: learning from that transient would shift the bias
estimate by ``ki`` times the integral of the error. The magnetometer loop is the slowest (time constant
about 3.5 / kp); a gyro frozen through a 90 deg turn leaves 55 deg, a re-initialisation from one sample
with 0.04 G noise up to ~15 deg (tests/faults/test_sensor_health.py: 10 / kp is too short for the latter)."""

STILL_WINDOW = 0.5
"""Length (s) of the quasi-static window from which :func:`relock` judges and re-initialises the attitude after a clock
jump: 50 samples at 100 Hz average the accelerometer noise down sevenfold."""

STILL_RATE = 0.1
"""A quasi-static sample (:func:`relock`): gyro norm below this (rad/s, 5.7 deg/s: hand-held at rest, not turning) ..."""

STILL_ACCEL = 0.05
"""... and accelerometer norm within this fraction of g (no linear acceleration to mistake for tilt)."""

LOST_TILT = np.deg2rad(5.0)
"""Tilt error (rad) above which :func:`relock` takes the attitude to be lost: a tracking filter stays within about
1 deg at rest, a quasi-static window's mean is good to about 0.1 deg (0.01 g noise over 50 samples)."""

LOST_HEADING = np.deg2rad(15.0)
"""Heading error (rad) against the window's magnetic (or RTK) heading above which the attitude is lost: wider than the
tilt's, for the field disturbances of everyday places (a few degrees to ten)."""

_TINY, _HUGE = 5e-324, float(np.finfo(float).max)
"""The smallest positive and the largest finite float: squared norms within them are usable (:func:`observe`)."""

_RTK_COUNTS = (("mag", "nan"), ("heading", "nan"), ("heading", "outlier"), ("heading", "reacquired"))
"""What the kernels count themselves (the RTK reference's state-dependent gate), in this order."""


class AttitudeInputs(NamedTuple):
    """Inputs of the attitude kernels, T trials of N samples (from :func:`pack`).

    Examples
    --------
    >>> from navlib import imu, trajectory
    >>> from navlib.filters import observations
    >>> traj = trajectory.static(0.1, 0.01, [0.6, 0.2, 50.0], [0.0, 0.0, 0.0])
    >>> samples = imu.ImuSamples(*trajectory.ideal_imu(traj), 0.01)
    >>> lead, inputs, found = observations.pack(samples, traj.q_bn[0], None, None, None, observations.AttitudeGates(), 1.0)
    >>> lead, inputs.w.shape, inputs.use_mag                         # one trial of 10 samples, no magnetometer
    ((), (1, 10, 3), False)
    """

    q_init: np.ndarray  # (T, 4) attitude before the first sample
    w: np.ndarray  # (T, N, 3) gyro (rad/s), held over unusable samples
    fresh: np.ndarray  # (T, N) bool: the gyro sample is used as measured
    f: np.ndarray  # (T, N, 3) accelerometer (m/s^2) as measured
    m: np.ndarray  # (T, N, 3) magnetometer (uT) as measured, or (1, 1, 3) unused
    limits: tuple[float, ...]  # gates: |f|^2 low, high, |m|^2 low, high (finite, > 0), sin(dip) low, high (see pack)
    skip: np.ndarray  # (2, T, N) bool: accelerometer, magnetometer skipped by the screen (or none)
    gated: np.ndarray  # (4, T, N) bool, set by the kernels: accelerometer unusable, outside its gate; magnetometer same
    hdg: np.ndarray  # (T, N) RTK heading (rad), or (1, 1) unused
    hdg_ok: np.ndarray  # (T, N) bool: a valid RTK epoch, or (1, 1) unused
    use_rtk: bool  # heading reference: RTK (True) or magnetometer
    use_mag: bool  # False with RTK or without a heading reference (gyro + accelerometer only)
    dts: np.ndarray  # (N,) interval covered by each sample (s)
    jump: np.ndarray  # (N,) bool: clock jump (integrated as typical_dt; relock checks the state)
    typical_dt: float  # median interval (s)
    still: np.ndarray  # (T, N) bool quasi-static samples (STILL_RATE, STILL_ACCEL), or (1, 1) without a jump
    window: int  # quasi-static samples that relock needs (STILL_WINDOW)
    rtk_par: np.ndarray  # (3,) hold (s), gate (rad), confirm (epochs)
    long_hold: int  # gyro holds of at least this many samples are followed by settling
    settle: float  # bias integral frozen this long (s) after a long hold or a clock jump


# --------------------------------------------------------------------------
# Reference field
# --------------------------------------------------------------------------


def integral_gain(ki: float | None, heading_reference: bool) -> float:
    """The PI loop's integral gain (rad/s^2): ``ki`` as given, or by default (None) :data:`KI_WITH_REFERENCE` with a
    heading reference (a magnetometer or RTK heading: ``heading_reference``) and 0 without one.

    Why off without a heading reference: the integral then learns only from the accelerometer's tilt error, which
    during hand or vehicle motion is mostly linear acceleration, not gyro bias; the vertical-axis bias is not
    observable at all. On the x-io hand-motion recording (data/real/xio-fusion, no magnetometer) ``ki = 0.02``
    learns (-0.27, 0.89, 0.70) deg/s where the true bias is about 0.01 deg/s, and the heading then drifts 10 deg in
    15 s at rest. With a heading reference every axis is observed and the default learns the bias.

    Examples
    --------
    >>> from navlib.filters import observations
    >>> observations.integral_gain(None, heading_reference=False), observations.integral_gain(0.05, heading_reference=False)
    (0.0, 0.05)
    """
    if ki is None:
        return KI_WITH_REFERENCE if flag(heading_reference, "heading_reference") else 0.0
    return scalar(ki, "ki", positive=True, allow_zero=True)


def magnetic_reference(B_n: Vec3) -> tuple[Array, float, float, float]:
    """Normalised magnetic reference ``b = [0, cos I, -sin I]`` (Eq. 3) and the field's angles.

    Parameters
    ----------
    B_n : array_like, shape (3,)
        Local field in ENU (uT), e.g. :func:`navlib.earth.magnetic_field`.

    Returns
    -------
    b : ndarray, shape (3,)
        Unit field in the magnetic-north frame.
    declination, inclination, intensity : float
        D (rad, east positive), I (rad, down positive), F (uT).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.filters import observations
    >>> b, D, I, F = observations.magnetic_reference([0.0, 20.0, -40.0])
    >>> np.round(b, 4), round(float(np.rad2deg(I)), 3), round(float(F), 3)   # normalised [0, cos I, -sin I]
    (array([ 0.    ,  0.4472, -0.8944]), 63.435, 44.721)
    """
    B = as_array(B_n, "B_n", shape=(3,))
    if np.linalg.norm(B) == 0:
        raise ValueError(f"B_n: expected a non-zero field vector, got {B.tolist()}")
    D, I, F = _earth.field_angles(B)
    return np.array([0.0, np.cos(I), -np.sin(I)]), float(D), float(I), float(F)


# --------------------------------------------------------------------------
# Per-sample kernel helpers (scalar tuples, allocation-free)
# --------------------------------------------------------------------------


@njit(cache=True, inline="always")
def dcm_elements(q0, q1, q2, q3):
    """The nine elements of C_b^n(q), row by row (a tuple: the kernels' per-sample form)."""
    return (
        q0 * q0 + q1 * q1 - q2 * q2 - q3 * q3,
        2 * (q1 * q2 - q0 * q3),
        2 * (q1 * q3 + q0 * q2),
        2 * (q1 * q2 + q0 * q3),
        q0 * q0 - q1 * q1 + q2 * q2 - q3 * q3,
        2 * (q2 * q3 - q0 * q1),
        2 * (q1 * q3 - q0 * q2),
        2 * (q2 * q3 + q0 * q1),
        q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3,
    )


@njit(cache=True, inline="always")
def _rtk_north(C31, C32, C33, sh, ch):
    """Mode (a) of Fig. 4: RTK heading as body-frame north ``C_nb(H_rtk, pitch_est, roll_est) [0, 1, 0]``."""
    cp = np.sqrt(C31 * C31 + C33 * C33)
    sr, cr = -C31 / cp, C33 / cp
    return -sh * cr + ch * C32 * sr, ch * cp, -sh * sr - ch * C32 * cr


@njit(cache=True, inline="always")
def pi_error(C, ax, ay, az, mx, my, mz):
    """Eqs. (12)-(14): e = a_meas x a_est + m_meas x m_est (measured x estimated); a NaN vector is skipped."""
    C11, C12, C13, C21, C22, C23, C31, C32, C33 = C
    ex = ey = ez = 0.0
    if not np.isnan(ax):
        ex += ay * C33 - az * C32
        ey += az * C31 - ax * C33
        ez += ax * C32 - ay * C31
    if not np.isnan(mx):
        hx = C11 * mx + C12 * my + C13 * mz  # h = C_bn m (Mahony: rebuild b from h)
        hy = C21 * mx + C22 * my + C23 * mz
        hz = C31 * mx + C32 * my + C33 * mz
        bn = np.sqrt(hx * hx + hy * hy)
        vx = bn * C21 + hz * C31  # m_est = C_nb [0, bn, hz]
        vy = bn * C22 + hz * C32
        vz = bn * C23 + hz * C33
        ex += my * vz - mz * vy
        ey += mz * vx - mx * vz
        ez += mx * vy - my * vx
    return ex, ey, ez


@njit(cache=True, inline="always")
def rtk_gate(h, predicted, gate, confirm, state):
    """Gate one RTK epoch against the predicted heading: 0 use, 1 reject, 2 use (re-acquired).

    An epoch within ``gate`` (rad) of ``predicted`` is used. One outside is
    rejected (a 180 deg ambiguity flip, a wrong fix) unless it is the
    ``confirm``-th in a row of rejected epochs that agree with each other
    within ``gate``: then the reference, not the epoch, is taken to be wrong
    and the epoch is used. ``state = [run length, heading of the last rejected epoch]``.
    """
    if abs(wrap_pi(h - predicted)) <= gate:
        state[0] = 0.0
        return 0
    if state[0] > 0.0 and abs(wrap_pi(h - state[1])) <= gate:
        state[0] += 1.0
    else:
        state[0] = 1.0
    state[1] = h
    return 2 if state[0] >= confirm else 1


@njit(cache=True, inline="always", error_model="numpy")  # (1 / 0 is inf: never used)
def observe(fx, fy, fz, mx, my, mz, skip_a, skip_m, limits):
    """Unit accelerometer and magnetometer vectors of one sample (NaN where skipped or absent) and why each was
    dropped: ``(ax, ay, az, mx, my, mz, gate_a, gate_m)``, a gate code 0 (used), 1 (unusable) or 2 (outside its gate).

    ``f``, ``m``: the sample as measured (``m`` any value where ``skip_m``); ``skip_a``, ``skip_m``: the screen's skips
    (:attr:`AttitudeInputs.skip`); ``limits``: :attr:`AttitudeInputs.limits`. A sample the screen kept is normalised
    and tested here: unusable (zero or not finite; a field parallel to gravity) or outside the gates (the norm's, and
    the magnetometer's dip angle against the accelerometer's up direction when that is used). The caller flags a
    dropped sample in :attr:`AttitudeInputs.gated` (``gated[gate_a - 1]``, ``gated[gate_m + 1]``). A used sample passes
    one range test per norm (the limits hold the finiteness test, :func:`pack`) and the dip's tests; only a sample that
    fails one is examined for its code. Scalars in, scalars out: a kernel that inlines it counts no array references.
    """
    n2 = fx * fx + fy * fy + fz * fz
    s = 1.0 / np.sqrt(n2)  # (used only where n2 is finite and positive)
    ax, ay, az = fx * s, fy * s, fz * s
    used_a, gate_a = not skip_a, 0
    if used_a and not limits[0] <= n2 <= limits[1]:
        used_a, gate_a = False, 1 if not 0.0 < n2 < np.inf else 2
    if not used_a:
        ax = ay = az = np.nan
    gate_m = 0
    if skip_m:
        mx = my = mz = np.nan
    else:
        n2 = mx * mx + my * my + mz * mz
        s = 1.0 / np.sqrt(n2)
        mx, my, mz = mx * s, my * s, mz * s
        sin_dip = -(ax * mx + ay * my + az * mz)  # (NaN without the accelerometer: no dip test)
        dip_ok = limits[4] <= sin_dip <= limits[5] and 1.0 - sin_dip * sin_dip >= 1e-12
        if not limits[2] <= n2 <= limits[3] or used_a and not dip_ok:
            gate_m = _mag_code(n2, sin_dip, used_a)
            mx = my = mz = np.nan
    return ax, ay, az, mx, my, mz, gate_a, gate_m


@njit(cache=True, inline="always")
def _mag_code(n2, sin_dip, used_a):
    """Why :func:`observe` drops a magnetometer sample of squared norm ``n2``: 1 unusable (zero or not finite, or
    parallel to gravity), 2 outside the gate (the dip's or the norm's)."""
    if not 0.0 < n2 < np.inf:
        return 1
    if used_a and 1.0 - sin_dip * sin_dip < 1e-12:
        return 1
    return 2


@njit(cache=True, inline="always")
def rtk_north(inp, t, k, C, dt, rtk, counts):
    """Mode (a) of Fig. 4: the RTK heading as a north pseudo-vector in the body frame (NaN without a used epoch
    within ``inp.rtk_par[0]`` s), at the attitude whose C_b^n elements are ``C``.

    ``rtk = [sin H, cos H, heading estimate at the epoch, age (s), gate run length, last rejected heading]``
    of the last used RTK epoch is updated in place and the gate's outcomes counted in ``counts[t]``
    (:data:`_RTK_COUNTS`).
    """
    hdg, hdg_ok, rtk_par = inp.hdg, inp.hdg_ok, inp.rtk_par
    rtk[3] += dt
    if hdg_ok[t, k]:
        hk = hdg[t, k]
        if np.isnan(hk):  # valid flag but no value: dropout
            counts[t, 1] += 1
        else:
            est = dcm_heading(C[1], C[4])
            code = rtk_gate(hk, est, rtk_par[1], rtk_par[2], rtk[4:6])
            if code == 1:
                counts[t, 2] += 1
            else:
                if code == 2:
                    counts[t, 3] += 1
                rtk[0], rtk[1], rtk[2], rtk[3] = np.sin(hk), np.cos(hk), est, 0.0
    if rtk[3] <= rtk_par[0] and C[6] * C[6] + C[8] * C[8] > 1e-12:  # (no heading at pitch +-90 deg)
        # carry the epoch's heading forward with the estimate's own heading change
        d = dcm_heading(C[1], C[4]) - rtk[2]
        sd, cd = np.sin(d), np.cos(d)
        return _rtk_north(C[6], C[7], C[8], rtk[0] * cd + rtk[1] * sd, rtk[1] * cd - rtk[0] * sd)
    counts[t, 0] += 1
    return np.nan, np.nan, np.nan


@njit(cache=True, inline="always")
def learning(fresh, dt, held, since, long_hold, settle):
    """May the gyro-bias (PI) integral learn from this sample? Not while the gyro is held (``fresh`` False),
    nor for ``settle`` seconds after a hold of ``long_hold`` samples or more or a clock jump (unless
    :func:`relock` finds the attitude kept: a stamp glitch left no transient).

    ``held``: samples held in a row, ``since``: time since the last long hold or jump (s) (start 0 and inf; a clock
    jump sets ``since = 0``), carried by the caller in locals (not an array: the per-sample state stays in
    registers). Returns ``(learn, held, since)``.
    """
    if not fresh:
        return False, held + 1.0, since
    if held >= long_hold:
        since = 0.0
    since += dt
    return since >= settle, 0.0, since


@njit(cache=True)
def relock(inp, t, k, q0, q1, q2, q3, u, state, rtk, since):
    """After a clock jump: re-initialise the attitude only once the data show it is lost, from a quasi-static window.

    A clock jump may be a pure stamp glitch (the samples on either side are contiguous: the filter has already
    propagated through it as one typical interval) or a real gap, over which the device may have turned. The
    filter cannot tell at the jump; it keeps propagating and collects the next quasi-static samples
    (:attr:`AttitudeInputs.still`). When :data:`STILL_WINDOW` seconds of them in a row are at hand, their mean
    accelerometer (and magnetometer) direction is compared with the estimate: a tilt off by more than
    :data:`LOST_TILT` or a magnetic heading off by more than :data:`LOST_HEADING` means the state is lost, and the
    attitude is re-initialised from the window's means (tilt, tilt-compensated magnetic heading; in RTK mode the
    heading of a valid epoch in the window, else the estimate's) and the settling of :func:`learning` restarts;
    otherwise the attitude is kept and the bias integral learns again at once (``since``, the state of
    :func:`learning`): there is no transient to keep out of it. Either way the check ends.

    ``state = [checking (1/0), samples in the window, sum of the unit accelerometer (3), of the unit magnetometer (3),
    magnetometer samples, last valid RTK heading in the window (NaN: none)]`` (10 values; a jump sets ``state[0] = 1``
    and clears the rest: :func:`start_relock`); ``u``: the sample's unit accelerometer and magnetometer vectors of
    :func:`observe` (6 values). Returns ``(q0, q1, q2, q3, re-initialised, since)``. Callers test
    ``state[0]`` first: a call passing ``inp`` counts a reference to each of its arrays (atomic operations costing more
    than a filter's arithmetic), not to be paid per sample.
    """
    if state[0] == 0.0:
        return q0, q1, q2, q3, False, since
    if not inp.still[t, k] or np.isnan(u[0]):
        start_relock(state)  # the window must be quasi-static throughout
        return q0, q1, q2, q3, False, since
    state[1] += 1.0
    state[2], state[3], state[4] = state[2] + u[0], state[3] + u[1], state[4] + u[2]
    if not np.isnan(u[3]):
        state[5], state[6], state[7] = state[5] + u[3], state[6] + u[4], state[7] + u[5]
        state[8] += 1.0
    if inp.use_rtk and inp.hdg_ok[t, k] and not np.isnan(inp.hdg[t, k]):
        state[9] = inp.hdg[t, k]
    if state[1] < inp.window:
        return q0, q1, q2, q3, False, since
    state[0] = 0.0  # one verdict per jump
    pitch, roll = level(state[2], state[3], state[4])
    C = dcm_elements(q0, q1, q2, q3)
    h_est = dcm_heading(C[1], C[4])
    n = np.sqrt(state[2] * state[2] + state[3] * state[3] + state[4] * state[4])
    cos_tilt = (state[2] * C[6] + state[3] * C[7] + state[4] * C[8]) / n  # measured vs estimated up, body frame
    lost = cos_tilt < np.cos(LOST_TILT)
    h = h_est
    if inp.use_rtk:
        if not np.isnan(state[9]):
            h = state[9]
            lost = lost or abs(wrap_pi(h - h_est)) > LOST_HEADING
    elif state[8] >= inp.window:  # a magnetometer sample at every window sample
        h = tilt_heading(state[5], state[6], state[7], pitch, roll)
        lost = lost or abs(wrap_pi(h - h_est)) > LOST_HEADING
    if not lost:
        return q0, q1, q2, q3, False, np.inf
    if inp.use_rtk and not np.isnan(state[9]):
        rtk[0], rtk[1], rtk[2], rtk[3], rtk[4] = np.sin(h), np.cos(h), h, 0.0, 0.0
    r0, r1, r2, r3 = euler_to_quat(h, pitch, roll)
    return r0, r1, r2, r3, True, 0.0


@njit(cache=True, inline="always")
def start_relock(state):
    """(Re)start the quasi-static window of :func:`relock`: checking, nothing collected."""
    state[0] = 1.0
    for i in range(1, 9):
        state[i] = 0.0
    state[9] = np.nan


@njit(cache=True, inline="always")
def jump_step(inp, state, rtk):
    """At a clock jump: the interval integrated (one typical interval: the samples of a stamp glitch are contiguous,
    and over a real gap nothing is known), the check of :func:`relock` started and the last RTK epoch stale. (The
    caller restarts the settling of :func:`learning`: ``since = 0``.)"""
    start_relock(state)
    rtk[3], rtk[4] = np.inf, 0.0
    return inp.typical_dt


# --------------------------------------------------------------------------
# Input and output
# --------------------------------------------------------------------------


@dataclass(frozen=True)
class MagGate:
    """Magnetometer gate: skip samples whose field disagrees with the local field.

    A sample is used only if ``| |m| / F - 1 | <= norm_tol`` and its dip angle
    (against the accelerometer's up direction) is within ``dip_tol`` (rad) of
    the local inclination I. F and I come from the ``B_n`` given to the filter.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.filters import observations
    >>> gate = observations.MagGate(norm_tol=0.05, dip_tol=np.deg2rad(3.0))   # 5 % on |m|, 3 deg on the dip
    >>> gate.norm_tol, round(float(np.rad2deg(gate.dip_tol)), 6)
    (0.05, 3.0)
    """

    norm_tol: Positive = 0.1
    dip_tol: Positive = np.deg2rad(5.0)

    def __post_init__(self) -> None:
        fields_checked(self)


@dataclass(frozen=True)
class AttitudeGates:
    """Which accelerometer and magnetometer samples an attitude filter uses.

    Attributes
    ----------
    accel_tol : float, optional
        Skip accelerometer samples whose norm differs from ``g`` by more than this fraction
        (``("accel", "outlier")``); None (default): no norm test.
    g : float
        Gravity for ``accel_tol`` (m/s^2).
    mag : MagGate, optional
        Field-norm and dip-angle gate for the magnetometer (``("mag", "outlier")``); needs the filter's
        ``B_n``. None (default): no gate.

    Examples
    --------
    >>> from navlib.filters import observations
    >>> gates = observations.AttitudeGates(accel_tol=0.1, mag=observations.MagGate(norm_tol=0.1))
    >>> gates.accel_tol, gates.mag.norm_tol
    (0.1, 0.1)
    """

    accel_tol: Positive | None = None
    g: Positive = G0
    mag: Is[MagGate] | None = None

    def __post_init__(self) -> None:
        fields_checked(self)


@dataclass(frozen=True)
class RtkHeading:
    """Dual-antenna RTK heading at the IMU rate: the heading reference of mode (a) of Fig. 4.

    Attributes
    ----------
    heading : array_like, shape (N,) or (..., N)
        Heading (rad, [0, 2 pi)); read only where ``valid``; a valid epoch holding NaN is a dropout
        (``("heading", "nan")``).
    valid : array_like of bool, same shape
        True where a valid RTK epoch arrives (the receiver's status flag; never inferred from the value).
    hold : float
        How long an epoch is used (s).
    gate : float, optional
        Reject epochs whose heading differs from the current estimate by more than this (rad, in (0, pi)),
        e.g. 180 deg ambiguity flips (``("heading", "outlier")``); None (default) uses every valid epoch.
    confirm : int
        With ``gate``: after this many consecutive rejected epochs that agree with each other (within
        ``gate``), use them (``("heading", "reacquired")``), so that an estimate that drifted in an outage
        is pulled back.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.filters import observations
    >>> rtk = observations.RtkHeading(heading=np.array([0.5, 0.0, 0.52]), valid=np.array([True, False, True]), gate=0.1)
    >>> int(rtk.valid.sum()), rtk.hold, rtk.gate
    (2, 0.25, 0.1)
    """

    heading: ArrayLike
    valid: ArrayLike
    hold: float = 0.25
    gate: float | None = None
    confirm: int = 5

    def __post_init__(self) -> None:
        h = as_array(self.heading, "heading", finite=False, nonempty=True)
        v = booleans(self.valid, "valid")
        try:
            shape = np.broadcast_shapes(h.shape, v.shape)
        except ValueError:
            raise ValueError(f"valid: expected a shape broadcastable to that of heading {h.shape}, got {v.shape}") from None
        used = np.broadcast_to(h, shape)[np.broadcast_to(v, shape)]
        bad = ~np.isnan(used) & ~((used >= 0) & (used < 2 * np.pi))
        if bad.any():
            raise ValueError(
                f"heading: valid epochs must hold headings in [0, 2 pi) rad (or NaN for a dropout); "
                f"{int(bad.sum())} do not (first: {used[bad][0]!r})"
            )
        object.__setattr__(self, "heading", h)
        object.__setattr__(self, "valid", v)
        scalar(self.hold, "hold", positive=True, allow_zero=True)
        if self.gate is not None and not 0 < scalar(self.gate, "gate", positive=True) < np.pi:
            raise ValueError(f"gate: expected a value in (0, pi) rad, got {self.gate!r}")
        integer(self.confirm, "confirm")

    def params(self) -> np.ndarray:
        """``[hold (s, + 1 ns rounding allowance), gate (rad, inf = off), confirm (epochs)]`` for the kernels."""
        return np.array([float(self.hold) + 1e-9, np.inf if self.gate is None else float(self.gate), float(self.confirm)])

    def at(self, shape: tuple[int, ...], of: str) -> tuple[np.ndarray, np.ndarray]:
        """Heading and validity broadcast to ``shape`` (..., N) of the samples ``of``, flattened to (T, N) for the
        kernels."""
        try:
            h, v = np.broadcast_to(self.heading, shape), np.broadcast_to(self.valid, shape)
        except ValueError:
            raise ValueError(
                f"rtk: expected heading and valid broadcastable to the shape {shape} of {of}, got "
                f"{np.shape(self.heading)} and {np.shape(self.valid)}"
            ) from None
        return kernel_array(h.reshape(-1, shape[-1])), kernel_array(v.reshape(-1, shape[-1]))  # writable


@dataclass(frozen=True)
class AttitudeResult:
    """Output of the attitude filters (:mod:`navlib.filters.mahony`, :mod:`navlib.filters.quaternion_kf`).

    Attributes
    ----------
    q_bn : ndarray, shape (..., N, 4)
        Attitude after each sample (magnetic north with a magnetometer, true
        north with RTK heading).
    gyro_bias : ndarray, shape (..., 3)
        Final gyro-bias estimate ``-Ki sum(e dt)`` (rad/s).
    faults : FaultReport
        What was held, skipped, gated or re-initialised (module docstring), counts of shape (...) and
        per-sample flags of shape (..., N), e.g. ``result.faults["mag", "outlier"]``,
        ``result.faults.flags["gyro", "stuck"]``.
    P : ndarray, shape (..., 4, 4) or None
        Final quaternion covariance (the quaternion KF; None for Mahony).
    P_history : ndarray, shape (..., N, 4, 4) or None
        Covariance after every sample (``quaternion_kf(..., keep_cov=True)``).

    Examples
    --------
    >>> from navlib import attitude, imu, trajectory
    >>> from navlib.filters import mahony
    >>> traj = trajectory.static(0.5, 0.01, [0.6, 0.2, 50.0], [0.0, 0.0, 0.0])
    >>> res = mahony.mahony(imu.ImuSamples(*trajectory.ideal_imu(traj), 0.01), traj.q_bn[0])
    >>> res.q_bn.shape, res.gyro_bias.shape                          # one attitude and bias per sample
    ((50, 4), (3,))
    """

    q_bn: Array
    gyro_bias: Array
    faults: FaultReport
    P: Array | None = None
    P_history: Array | None = None

    @property
    def hpr(self) -> np.ndarray:
        """Heading, pitch, roll (rad), shape (..., N, 3)."""
        return attitude.quat_to_euler(self.q_bn)


def screened(imu: ImuSamples | Screened, m_b: ArrayLike | None = None) -> Screened:
    """The samples an attitude filter consumes: ``imu`` screened (:func:`navlib.robust.screen`), or ``imu`` itself
    when it is already the result of :func:`navlib.robust.screen`.

    Screen once, filter many: every filter of :mod:`navlib.filters` that takes ``imu`` also takes
    ``robust.screen(imu, m_b)`` (the magnetometer then given to the screen only), and screens nothing again; the
    screen's faults are those of each filter's result. Several filters, or several gains, run on one record then
    pay for the screening once.

    Raises
    ------
    ValueError
        If ``m_b`` is given with screened samples (the magnetometer is screened with them: give it to
        :func:`navlib.robust.screen` only).

    Examples
    --------
    >>> from navlib import imu, robust, trajectory
    >>> from navlib.filters import mahony, observations, quaternion_kf
    >>> traj = trajectory.static(0.1, 0.01, [0.6, 0.2, 50.0], [0.0, 0.0, 0.0])
    >>> s = robust.screen(imu.ImuSamples(*trajectory.ideal_imu(traj), 0.01))
    >>> observations.screened(s) is s                                # already screened: used as it is
    True
    >>> a, b = mahony.mahony(s, traj.q_bn[0]), quaternion_kf.quaternion_kf(s, traj.q_bn[0])   # one screen, two filters
    >>> a.q_bn.shape, b.q_bn.shape, bool(a.faults), bool(b.faults)
    ((10, 4), (10, 4), False, False)
    """
    if isinstance(imu, Screened):
        if m_b is not None:
            raise ValueError(
                "m_b: imu is already screened (robust.screen(imu, m_b)), with its magnetometer if it has one; "
                "give m_b to robust.screen only, not again to the filter"
            )
        return imu
    return screen(imu, m_b)  # which checks that imu is an ImuSamples


@boundary
def pack(
    imu: ImuSamples | Screened,
    q0: Quat,
    m_b: ArrayLike | None,
    rtk: RtkHeading | None,
    B_n: Vec3 | None,
    gates: Is[AttitudeGates],
    kp: NonNegative,
) -> tuple[tuple[int, ...], AttitudeInputs, FaultReport]:
    """The kernels' record of the samples, screened once (:func:`screened`), and the gates the kernels apply.

    The arguments are those of :func:`navlib.filters.mahony.mahony`. Returns ``(lead, inputs, faults)``:
    the leading (trial) shape, the kernel record with trials flattened to T, and the screen's faults (the
    kernels' gates and RTK reference add theirs, :func:`attitude_result`).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import imu, trajectory
    >>> from navlib.filters import observations
    >>> traj = trajectory.static(0.1, 0.01, [0.6, 0.2, 50.0], [0.0, 0.0, 0.0])
    >>> w_ib_b, f_b = trajectory.ideal_imu(traj)
    >>> w_ib_b[3] = np.nan                                           # a gyro dropout
    >>> samples = imu.ImuSamples(w_ib_b, f_b, 0.01)
    >>> lead, inputs, found = observations.pack(samples, traj.q_bn[0], None, None, None, observations.AttitudeGates(), 1.0)
    >>> int(found["gyro", "nan"])
    1
    """
    s = screened(imu, m_b)
    use_mag = s.m_b is not None
    if rtk is not None:
        instance(rtk, "rtk", RtkHeading, "an RtkHeading")
        if use_mag:
            raise ValueError("m_b, rtk: give at most one heading reference (magnetometer or RTK)")
    if gates.mag is not None and not use_mag:
        raise ValueError("gates: a magnetometer gate needs m_b")
    if gates.mag is not None and B_n is None:
        raise ValueError("B_n: the magnetometer gate needs the local field")
    if B_n is not None:
        _, _, incl, field = magnetic_reference(B_n)
    lead, (N, T) = s.w_ib_b.shape[:-2], (s.imu.n, int(np.prod(s.w_ib_b.shape[:-2])))
    q = broadcast_to(as_quat(q0, "q0"), "q0", lead + (4,), of="the trials of imu")
    q = np.array(q.reshape(T, 4), order="C")  # a writable copy: one kernel signature
    limits = np.array([0.0, np.inf, 0.0, np.inf, -2.0, 2.0])  # |f|^2 low/high, |m|^2 low/high, sin(dip) low/high
    if gates.accel_tol is not None:
        limits[0:2] = (gates.g * max(1 - gates.accel_tol, 0.0)) ** 2, (gates.g * (1 + gates.accel_tol)) ** 2
    if gates.mag is not None:
        limits[2:4] = (field * max(1 - gates.mag.norm_tol, 0.0)) ** 2, (field * (1 + gates.mag.norm_tol)) ** 2
        limits[4:6] = np.sin(max(incl - gates.mag.dip_tol, -np.pi / 2)), np.sin(min(incl + gates.mag.dip_tol, np.pi / 2))
    limits[0:4] = np.clip(limits[0:4], _TINY, _HUGE)  # a norm within them is also finite and non-zero (observe)
    flags = s.faults.flags
    skip = np.empty((2, T, N), dtype=bool)  # the screen's skips
    sat, free, spike = (kernel_array(flags["accel", kind].reshape(T, N)) for kind in ("saturated", "freefall", "spike"))
    mag = kernel_array(flags["mag", "saturated"].reshape(T, N)) if use_mag else np.ones((1, 1), dtype=bool)
    run_chunks(lambda t0, t1: _skips(t0, t1, sat, free, spike, mag, skip), T)
    jump = kernel_array(flags["clock", "jump"].reshape(-1, N)[0])
    if rtk is not None:
        hdg, ok = rtk.at(lead + (N,), "imu's samples")
        rtk_par = rtk.params()
    else:
        hdg, ok, rtk_par = np.zeros((1, 1)), np.zeros((1, 1), dtype=bool), np.array([0.0, np.inf, 0.0])
    long_hold = s.imu.limits.stuck_samples(s.typical_dt) or SensorLimits().stuck_samples(s.typical_dt)
    w, f = kernel_array(s.w_ib_b.reshape(T, N, 3)), kernel_array(s.imu.f_b.reshape(T, N, 3))
    inputs = AttitudeInputs(
        q,
        w,
        kernel_array(s.fresh.reshape(T, N)),
        f,
        kernel_array(s.m_b.reshape(T, N, 3)) if s.m_b is not None else np.zeros((1, 1, 3)),
        tuple(limits.tolist()),
        skip,
        np.zeros((4, T, N), dtype=bool),
        hdg,
        ok,
        rtk is not None,
        use_mag,
        s.dt,
        jump,
        s.typical_dt,
        _still(w, f, gates.g) if jump.any() else np.zeros((1, 1), dtype=bool),
        max(1, round(STILL_WINDOW / s.typical_dt)),
        rtk_par,
        long_hold,
        SETTLE_TIME_CONSTANTS / kp if kp > 0 else 0.0,
    )
    return lead, inputs, s.faults


@njit(cache=True, nogil=True)
def _skips(t0, t1, saturated, freefall, spike, mag_saturated, skip):
    """Trials t0 to t1 - 1 of ``skip`` (2, T, N): the accelerometer samples the screen skips (saturated, free fall,
    spike: (T, N) each) and the magnetometer's (saturated (T, N), or (1, 1) without a magnetometer: all)."""
    use_mag = mag_saturated.shape[1] == skip.shape[2]
    for t in range(t0, t1):
        for k in range(skip.shape[2]):
            skip[0, t, k] = saturated[t, k] or freefall[t, k] or spike[t, k]
            skip[1, t, k] = mag_saturated[t, k] if use_mag else True


def _still(w: np.ndarray, f: np.ndarray, g: float) -> np.ndarray:
    """Quasi-static samples (T, N) of the held gyro ``w`` and the accelerometer ``f`` (T, N, 3): :data:`STILL_RATE`,
    :data:`STILL_ACCEL` (NaN is not still)."""
    rate, norm = np.linalg.norm(w, axis=-1), np.linalg.norm(f, axis=-1)
    return np.ascontiguousarray((rate < STILL_RATE) & (np.abs(norm - g) < STILL_ACCEL * g))


def unit_vectors(inputs: AttitudeInputs) -> np.ndarray:
    """The unit accelerometer and magnetometer vectors of every sample, (T, N, 6), NaN where skipped (screened out,
    unusable or gated), the gates' flags set in ``inputs.gated``: the :func:`observe` step of the compiled kernels for
    all samples at once, for a filter written with numpy (one that reads ``inputs`` from :func:`pack`).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import imu, trajectory
    >>> from navlib.filters import observations
    >>> traj = trajectory.static(0.1, 0.01, [0.6, 0.2, 50.0], [0.0, 0.0, 0.0])
    >>> w_ib_b, f_b = trajectory.ideal_imu(traj)
    >>> f_b[2] = 0.0                                                 # an unusable accelerometer sample
    >>> samples = imu.ImuSamples(w_ib_b, f_b, 0.01)
    >>> lead, inputs, found = observations.pack(samples, traj.q_bn[0], None, None, None, observations.AttitudeGates(), 1.0)
    >>> z = observations.unit_vectors(inputs)
    >>> z.shape, np.round(z[0, 0, :3], 3) + 0.0, bool(np.isnan(z[0, 2, 0])), int(inputs.gated[0].sum())
    ((1, 10, 6), array([0., 0., 1.]), True, 1)
    """
    T, N = inputs.w.shape[0], inputs.w.shape[1]
    z = np.empty((T, N, 6))
    run_trials(_unit_vectors, T, inputs.f, inputs.m, inputs.skip, inputs.gated, inputs.limits, z)
    return z


@njit(cache=True, nogil=True, error_model="numpy")
def _unit_vectors(t0, t1, f, m, skip, gated, limits, z):
    for t in range(t0, t1):
        for k in range(f.shape[1]):
            sm = skip[1, t, k]
            mx, my, mz = (m[t, k, 0], m[t, k, 1], m[t, k, 2]) if not sm else (0.0, 0.0, 0.0)  # (none where skipped)
            ax, ay, az, mx, my, mz, gate_a, gate_m = observe(
                f[t, k, 0], f[t, k, 1], f[t, k, 2], mx, my, mz, skip[0, t, k], sm, limits
            )
            if gate_a:
                gated[gate_a - 1, t, k] = True
            if gate_m:
                gated[gate_m + 1, t, k] = True
            z[t, k, 0], z[t, k, 1], z[t, k, 2], z[t, k, 3], z[t, k, 4], z[t, k, 5] = ax, ay, az, mx, my, mz


def run_trials(kernel: Callable[..., None], n_trials: int, *args: Any) -> None:
    """Run ``kernel(t0, t1, *args)`` over trials 0 to ``n_trials`` - 1 in parallel
    (:func:`navlib._threads.run_chunks`). The compiled kernels release the GIL; each trial writes only its
    own outputs, so the results do not depend on the number of threads.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.filters import observations
    >>> out = np.zeros(4)
    >>> def kernel(t0, t1, out):
    ...     out[t0:t1] = np.arange(t0, t1) ** 2                  # each trial writes only its own outputs
    ...
    >>> observations.run_trials(kernel, 4, out)
    >>> out
    array([0., 1., 4., 9.])
    """
    run_chunks(lambda t0, t1: kernel(t0, t1, *args), integer(n_trials, "n_trials"))


def attitude_result(
    lead: tuple[int, ...],
    inputs: AttitudeInputs,
    q_out: np.ndarray,
    bias: np.ndarray,
    counts: np.ndarray,
    screened_faults: FaultReport,
    P: np.ndarray | None = None,
    P_hist: np.ndarray | None = None,
) -> AttitudeResult:
    """Assemble an :class:`AttitudeResult` from kernel outputs over T flattened trials (leading shape ``lead``):
    the screen's faults (:func:`pack`), the gates' (``inputs.gated``, as the kernel left them), and the kernel's RTK
    ``counts`` (T, 4).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import imu, trajectory
    >>> from navlib.filters import observations
    >>> traj = trajectory.static(0.1, 0.01, [0.6, 0.2, 50.0], [0.0, 0.0, 0.0])
    >>> samples = imu.ImuSamples(*trajectory.ideal_imu(traj), 0.01)
    >>> lead, inputs, found = observations.pack(samples, traj.q_bn[0], None, None, None, observations.AttitudeGates(), 1.0)
    >>> q_out, bias, counts = traj.q_bn[None, 1:], np.zeros((1, 3)), np.zeros((1, 4), np.int64)   # one trial's kernel outputs
    >>> res = observations.attitude_result(lead, inputs, q_out, bias, counts, found)
    >>> res.q_bn.shape
    (10, 4)
    """
    N = q_out.shape[1]
    flags, counted = screened_faults.flags, screened_faults.counts
    found = {key: v for key, v in flags.items() if key not in (("accel", "nan"), ("mag", "nan"))}
    total = {key: counted[key] for key in found}
    # the gates' counts (the screen's skips are its own), over the trials in parallel
    n_gated = np.empty((4, q_out.shape[0]), dtype=np.int64)
    run_chunks(lambda t0, t1: count_flags(t0, t1, inputs.gated, n_gated), q_out.shape[0])
    n_gated = n_gated.reshape((4,) + lead)
    for i, sensor in enumerate(("accel", "mag")[: 1 + inputs.use_mag]):
        for j, kind in enumerate(("nan", "outlier")):
            found[sensor, kind], total[sensor, kind] = inputs.gated[2 * i + j].reshape(lead + (N,)), n_gated[2 * i + j][()]
    for i, key in enumerate(_RTK_COUNTS):
        if counts[:, i].any():
            total[key] = total.get(key, 0) + counts[:, i].reshape(lead)
    return AttitudeResult(
        q_out.reshape(lead + (N, 4)),
        bias.reshape(lead + (3,)),
        FaultReport(total, found),
        None if P is None else P.reshape(lead + (4, 4)),
        None if P_hist is None else P_hist.reshape(lead + (N, 4, 4)),
    )
