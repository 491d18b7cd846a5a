"""Vector observations for attitude filters, their gates and fault counts, and the filters' shared input/output.

An attitude filter (Mahony, the quaternion KF, a Madgwick filter) corrects gyro integration with
two directions: gravity from the accelerometer, and a horizontal reference from the magnetometer
(its field levelled with the current attitude) or, with a dual-antenna GNSS receiver, the RTK
heading as a north pseudo-vector ``C_nb(H_rtk, pitch_est, roll_est) [0, 1, 0]`` (mode (a) of
Fig. 4 of Zhang et al. 2023, :mod:`navlib.papers.mimu_mag_rtk`). This module owns, once for all
such filters:

* :func:`prepare_inputs` -- validation of the samples, gains aside, into an :class:`AttitudeInputs`
  record for the compiled kernels (trials flattened; saturated and stuck gyro samples found, clock
  jumps marked; :data:`STUCK_DURATION` and :data:`JUMP_FACTOR`, the library's defaults from
  :mod:`navlib.robust` and :mod:`navlib.timing`);
* :func:`observe`, :func:`gyro_sample`, :func:`pi_error`, :func:`rtk_gate`, :func:`reinit` -- the compiled
  per-sample steps: unit vectors with their gates (accelerometer norm, :class:`MagGate`, RTK gate with
  re-acquisition), the gyro hold of dropouts, spikes and stuck samples, Mahony's error
  ``e = a_meas x a_est + m_meas x m_est``, and the re-initialisation after a clock jump;
* :class:`AttitudeResult` with the counts :data:`COUNT_NAMES`; :func:`run_trials` (Monte Carlo trials
  in parallel on ``NUMBA_NUM_THREADS`` threads; the kernels release the GIL).

A new attitude filter is a module next to :mod:`navlib.filters.mahony` that calls these.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np
from numba import njit

from .. import attitude, earth
from .._kernels import BORROW, dcm_heading, euler_to_quat, level, stuck_runs, tilt_heading, wrap_pi
from .._threads import run_chunks
from .._typing import Array, ArrayLike, Interval, Quat, Vec3, Vec3Series
from .._validate import (
    as_array,
    as_quat,
    booleans,
    broadcast_to,
    instance,
    integer,
    intervals,
    kernel_array,
    nonempty_array,
    refuse_turn,
    same_shape,
    scalar,
)
from ..robust import STUCK_DURATION, FaultReport, stuck_run_samples
from ..timing import JUMP_FACTOR, jump_limit

__all__ = ["MagGate", "AttitudeResult", "AttitudeInputs", "Screened", "COUNT_NAMES", "FAULT_KEYS", "STUCK_DURATION",
           "JUMP_FACTOR", "SETTLE_TIME_CONSTANTS", "magnetic_reference", "prepare_inputs", "attitude_result", "run_trials"]

COUNT_NAMES = ("gyro_held", "accel_skipped", "accel_gated", "mag_skipped", "mag_gated", "gyro_saturated",
               "accel_saturated", "mag_saturated", "rtk_dropped", "rtk_rejected", "rtk_reacquired", "gyro_gated",
               "gyro_stuck", "clock_jump")
"""Keys of :attr:`AttitudeResult.counts`, one count per trial:

``gyro_held``
    NaN gyro samples, replaced by the last used sample (hold). While the gyro is
    held (here and for ``gyro_gated``, ``gyro_stuck``) the gyro-bias estimate is
    frozen, and after a hold of ``stuck_run`` samples or more it stays frozen for
    :data:`SETTLE_TIME_CONSTANTS` / kp seconds (:func:`learning`).
``accel_skipped``, ``accel_gated``
    Accelerometer samples unusable (NaN, inf, zero: the correction is
    skipped) or outside ``accel_tol`` (skipped).
``mag_skipped``, ``mag_gated``
    Heading-reference samples unusable (magnetometer NaN, inf, zero or
    parallel to gravity; in RTK mode, no used RTK epoch within ``rtk_hold``)
    or outside the :class:`MagGate` (skipped).
``gyro_saturated``
    Gyro samples with a component at the rails (``|w| >= full_scale_gyro``): used
    (unless the spike gate holds them; counted either way), because nothing
    better exists, but the attitude after them is suspect.
``accel_saturated``, ``mag_saturated``
    Accelerometer / magnetometer samples at the rails (``full_scale_accel``,
    ``full_scale_mag``): their correction is skipped (not also counted as skipped).
``rtk_dropped``
    Valid-flagged RTK epochs holding NaN: ignored.
``rtk_rejected``
    RTK epochs further than ``rtk_gate`` from the current heading estimate
    (e.g. 180 deg ambiguity flips): never fused.
``rtk_reacquired``
    RTK epochs used although outside ``rtk_gate``, because ``rtk_confirm``
    consecutive epochs agreed with each other: the estimate, not the RTK, was
    wrong (e.g. after a long outage without bias estimation).
``gyro_gated``
    Gyro spikes: samples differing from the last used one by more than
    ``gyro_jump`` on some axis, replaced by it (hold); a second such sample in a
    row is used (a sustained change is motion).
``gyro_stuck``
    Gyro samples of a stuck (frozen, latched) output: some axis repeats
    exactly the same value over ``stuck_run`` samples or more
    (:func:`navlib.robust.stuck_mask`); held like NaN samples (not also
    counted in ``gyro_held``), from the first sample of the run until the
    value changes.
``clock_jump``
    Samples whose interval exceeds ``max_dt`` (a time-stamp jump or a long
    recording gap): nothing is integrated over it, the attitude is
    re-initialised from that sample (:func:`reinit`), the quaternion KF's
    covariance reset to ``p0 I``, and the gyro-bias estimate frozen for
    :data:`SETTLE_TIME_CONSTANTS` / kp seconds. The same count in every trial
    (``dt`` is shared).
"""

FAULT_KEYS = {"gyro_held": ("gyro", "nan"), "accel_skipped": ("accel", "nan"), "accel_gated": ("accel", "outlier"),
              "mag_skipped": ("mag", "nan"), "mag_gated": ("mag", "outlier"), "gyro_saturated": ("gyro", "saturated"),
              "accel_saturated": ("accel", "saturated"), "mag_saturated": ("mag", "saturated"),
              "rtk_dropped": ("heading", "nan"), "rtk_rejected": ("heading", "outlier"),
              "rtk_reacquired": ("heading", "reacquired"), "gyro_gated": ("gyro", "spike"),
              "gyro_stuck": ("gyro", "stuck"), "clock_jump": ("clock", "jump")}
"""Each counter of :data:`COUNT_NAMES` as a ``(sensor, kind)`` key of :class:`navlib.robust.FaultReport`
(``mag`` is the heading reference: the RTK pseudo-vector in RTK mode)."""

(_GYRO_HELD, _ACCEL_SKIPPED, _ACCEL_GATED, _MAG_SKIPPED, _MAG_GATED, _GYRO_SATURATED, _ACCEL_SATURATED,
 _MAG_SATURATED, _RTK_DROPPED, _RTK_REJECTED, _RTK_REACQUIRED, _GYRO_GATED, _GYRO_STUCK, _CLOCK_JUMP) = range(len(COUNT_NAMES))

SETTLE_TIME_CONSTANTS = 15.0
"""After a clock jump or a gyro hold of ``stuck_run`` samples or more, the gyro-bias integral of the attitude
filters stays frozen for this many time constants ``1 / kp`` of the PI loop (15 s at kp = 1 rad/s) while the
reference removes the attitude error the fault left: learning from that transient would shift the bias
estimate by ``ki`` times the integral of the error. The magnetometer loop is the slowest (time constant
about 3.5 / kp); a gyro frozen through a 90 deg turn leaves 55 deg, a re-initialisation from one sample
with 0.04 G noise up to ~15 deg (tests/faults/test_sensor_health.py: 10 / kp is too short for the latter)."""



class AttitudeInputs(NamedTuple):
    """Validated inputs of the attitude kernels, T trials of N samples (from :func:`prepare_inputs`)."""
    q_init: np.ndarray              # (T, 4) attitude before the first sample
    w: np.ndarray                   # (T, N, 3) gyro (rad/s), NaN = dropout
    f: np.ndarray                   # (T, N, 3) accelerometer (m/s^2), NaN = skip
    m: np.ndarray                   # (T, N, 3) magnetometer (uT), or (1, 1, 3) unused (RTK or no reference)
    hdg: np.ndarray                 # (T, N) RTK heading (rad), or (1, 1) unused
    hdg_ok: np.ndarray              # (T, N) bool: a valid RTK epoch, or (1, 1) unused
    use_rtk: bool                   # heading reference: RTK (True) or magnetometer
    use_mag: bool                   # False with RTK or without a heading reference (gyro + accelerometer only)
    dts: np.ndarray                 # (N,) interval covered by each sample (s)
    gates: np.ndarray               # (6,) |f|^2 low/high, |m|^2 low/high, sin(dip) low/high
    jump: float                     # gyro spike gate (rad/s), 0 = off
    rtk_par: np.ndarray             # (3,) hold (s), gate (rad), confirm (epochs); see rtk_params
    max_dt: float                   # longest interval integrated (s); longer ones are clock jumps (inf = off)
    long_hold: int                  # gyro holds of at least this many samples are followed by settling
    settle: float                   # bias integral frozen this long (s) after a long hold or a clock jump
    stuck: np.ndarray               # (T, N) bool: stuck gyro samples (held like dropouts)


class Screened(NamedTuple):
    """What :func:`prepare_inputs` found before filtering, for :func:`attitude_result`."""
    saturated: np.ndarray           # (T, 3) gyro, accelerometer, magnetometer samples at the rails
    stuck: np.ndarray               # (T, N) bool: stuck gyro samples (also ``AttitudeInputs.stuck``)
    jump: np.ndarray                # (N,) bool: clock jumps (interval > max_dt)


# --------------------------------------------------------------------------
# Reference field
# --------------------------------------------------------------------------

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
    """
    B = as_array(B_n, "B_n", shape=(3,))
    if np.linalg.norm(B) == 0:
        raise ValueError(f"B_n: expected a non-zero field vector, got {B.tolist()}")
    D, I, F = earth.field_angles(B, deg=False)
    return np.array([0.0, np.cos(I), -np.sin(I)]), float(D), float(I), float(F)


# --------------------------------------------------------------------------
# Per-sample kernel helpers (scalar tuples, allocation-free)
# --------------------------------------------------------------------------

@njit(cache=True, inline="always")
def _accel_obs(fx, fy, fz, lo2, hi2):
    """Unit accelerometer vector and a code: 0 used, 1 unusable, 2 gated (norm test)."""
    n2 = fx * fx + fy * fy + fz * fz
    if not (n2 > 0.0 and n2 < np.inf):
        return 0.0, 0.0, 0.0, 1
    if n2 < lo2 or n2 > hi2:
        return 0.0, 0.0, 0.0, 2
    s = 1.0 / np.sqrt(n2)
    return fx * s, fy * s, fz * s, 0


@njit(cache=True, inline="always")
def _mag_obs(mx, my, mz, ax, ay, az, a_code, gate):
    """Unit magnetometer vector and a code (0 used, 1 unusable, 2 gated by norm or dip angle).

    ``gate = [|m|^2 low, |m|^2 high, sin(dip) low, sin(dip) high]``; the dip is
    measured against the accelerometer's up direction when that is usable.
    """
    n2 = mx * mx + my * my + mz * mz
    if not (n2 > 0.0 and n2 < np.inf):
        return 0.0, 0.0, 0.0, 1
    s = 1.0 / np.sqrt(n2)
    ux, uy, uz = mx * s, my * s, mz * s
    if a_code == 0:
        sin_dip = -(ax * ux + ay * uy + az * uz)
        if 1.0 - sin_dip * sin_dip < 1e-12:           # parallel to gravity: no heading
            return 0.0, 0.0, 0.0, 1
        if sin_dip < gate[2] or sin_dip > gate[3]:
            return 0.0, 0.0, 0.0, 2
    if n2 < gate[0] or n2 > gate[1]:
        return 0.0, 0.0, 0.0, 2
    return ux, uy, uz, 0


@njit(cache=True, inline="always")
def _dcm_t(q0, q1, q2, q3):
    """The nine elements of C_b^n, row by row."""
    return (q0 * q0 + q1 * q1 - q2 * q2 - q3 * q3, 2 * (q1 * q2 - q0 * q3), 2 * (q1 * q3 + q0 * q2),
            2 * (q1 * q2 + q0 * q3), q0 * q0 - q1 * q1 + q2 * q2 - q3 * q3, 2 * (q2 * q3 - q0 * q1),
            2 * (q1 * q3 - q0 * q2), 2 * (q2 * q3 + q0 * q1), q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3)


@njit(cache=True, inline="always")
def _rtk_north(C31, C32, C33, sh, ch):
    """Mode (a) of Fig. 4: RTK heading as body-frame north ``C_nb(H_rtk, pitch_est, roll_est) [0, 1, 0]``."""
    cp = np.sqrt(C31 * C31 + C33 * C33)
    sr, cr = -C31 / cp, C33 / cp
    return -sh * cr + ch * C32 * sr, ch * cp, -sh * sr - ch * C32 * cr


@njit(cache=True, inline="always")
def pi_error(C, ax, ay, az, a_ok, mx, my, mz, m_ok):
    """Eqs. (12)-(14): e = a_meas x a_est + m_meas x m_est (measured x estimated)."""
    C11, C12, C13, C21, C22, C23, C31, C32, C33 = C
    ex = ey = ez = 0.0
    if a_ok:
        ex += ay * C33 - az * C32
        ey += az * C31 - ax * C33
        ez += ax * C32 - ay * C31
    if m_ok:
        hx = C11 * mx + C12 * my + C13 * mz           # h = C_bn m (Mahony: rebuild b from h)
        hy = C21 * mx + C22 * my + C23 * mz
        hz = C31 * mx + C32 * my + C33 * mz
        bn = np.sqrt(hx * hx + hy * hy)
        vx = bn * C21 + hz * C31                      # m_est = C_nb [0, bn, hz]
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


@njit(**BORROW)
def observe(inp, t, k, q0, q1, q2, q3, dtk, rtk, counts):
    """Read sample k of trial t of ``inp`` (:class:`AttitudeInputs`): unit accelerometer vector and unit
    heading reference at the attitude ``q``, counting skips.

    The heading reference is the magnetometer, or with ``inp.use_rtk`` the RTK
    north pseudo-vector; ``rtk = [sin H, cos H, heading estimate at the epoch,
    age (s), gate run length, last rejected heading]`` of the last used RTK
    epoch is updated in place; ``rtk_par = [hold (s), gate (rad), confirm
    (epochs)]``. Saturated accelerometer and magnetometer samples arrive here
    as NaN (set by :func:`_prepare`, which counts them). Returns
    (ax, ay, az, a_ok, mx, my, mz, m_ok, C) with C the nine elements of C_b^n(q). Called, not inlined,
    and compiled without reference counting (:data:`navlib._kernels.BORROW`).
    """
    f, m, hdg, hdg_ok, use_rtk, gates, rtk_par = inp.f, inp.m, inp.hdg, inp.hdg_ok, inp.use_rtk, inp.gates, inp.rtk_par
    C = _dcm_t(q0, q1, q2, q3)
    ax, ay, az, ca = _accel_obs(f[t, k, 0], f[t, k, 1], f[t, k, 2], gates[0], gates[1])
    if ca > 0:
        counts[t, _ACCEL_SKIPPED - 1 + ca] += 1           # 1 skipped, 2 gated
    if use_rtk:
        rtk[3] += dtk
        if hdg_ok[t, k]:
            hk = hdg[t, k]
            if np.isnan(hk):                                           # valid flag but no value: dropout
                counts[t, _RTK_DROPPED] += 1
            else:
                est = dcm_heading(C[1], C[4])
                code = rtk_gate(hk, est, rtk_par[1], rtk_par[2], rtk[4:6])
                if code == 1:
                    counts[t, _RTK_REJECTED] += 1
                else:
                    if code == 2:
                        counts[t, _RTK_REACQUIRED] += 1
                    rtk[0], rtk[1], rtk[2], rtk[3] = np.sin(hk), np.cos(hk), est, 0.0
        if rtk[3] <= rtk_par[0] and C[6] * C[6] + C[8] * C[8] > 1e-12:     # (no heading at pitch +-90 deg)
            # carry the epoch's heading forward with the estimate's own heading change
            d = dcm_heading(C[1], C[4]) - rtk[2]
            sd, cd = np.sin(d), np.cos(d)
            mx, my, mz = _rtk_north(C[6], C[7], C[8], rtk[0] * cd + rtk[1] * sd, rtk[1] * cd - rtk[0] * sd)
            cm = 0
        else:
            mx, my, mz, cm = 0.0, 0.0, 0.0, 1
    elif inp.use_mag:
        mx, my, mz, cm = _mag_obs(m[t, k, 0], m[t, k, 1], m[t, k, 2], ax, ay, az, ca, gates[2:])
    else:                                               # no heading reference: nothing to skip or count
        mx, my, mz, cm = 0.0, 0.0, 0.0, -1
    if cm > 0:
        counts[t, _MAG_SKIPPED - 1 + cm] += 1           # 1 skipped, 2 gated
    return ax, ay, az, ca == 0, mx, my, mz, cm == 0, C


@njit(cache=True, inline="always")
def gyro_sample(t, k, inp, gx, gy, gz, held, counts):
    """Gyro sample k of trial t of ``inp``, or the last used one (gx, gy, gz) if it is NaN (a dropout),
    stuck (``inp.stuck``, see :func:`prepare_inputs`) or a spike (counted).

    A spike (only when ``inp.jump > 0``) is a sample differing from the last used
    one by more than ``inp.jump`` on some axis, unless the previous sample was
    already held (``held``): a sustained change is motion, not a spike.
    Returns (wx, wy, wz, held, fresh); ``fresh`` is False when the sample was
    replaced (the kernels then freeze their gyro-bias integral).
    """
    w, jump = inp.w, inp.jump
    wx, wy, wz = w[t, k, 0], w[t, k, 1], w[t, k, 2]
    if inp.stuck[t, k]:
        counts[t, _GYRO_STUCK] += 1
        return gx, gy, gz, held, False
    if not (np.isfinite(wx) and np.isfinite(wy) and np.isfinite(wz)):
        counts[t, _GYRO_HELD] += 1
        return gx, gy, gz, held, False
    if jump > 0.0 and not held and k > 0 and (abs(wx - gx) > jump or abs(wy - gy) > jump or abs(wz - gz) > jump):
        counts[t, _GYRO_GATED] += 1
        return gx, gy, gz, True, False
    return wx, wy, wz, False, True


@njit(cache=True, inline="always")
def learning(fresh, dt, state, inp):
    """May the gyro-bias (PI) integral learn from this sample? Not while the gyro is held (``fresh`` False),
    nor for ``inp.settle`` seconds after a hold of ``inp.long_hold`` samples or more or a clock jump.

    ``state = [samples held in a row, time since the last long hold or jump (s)]`` (start ``[0, inf]``;
    a clock jump sets ``state[1] = 0``).
    """
    if not fresh:
        state[0] += 1.0
        return False
    if state[0] >= inp.long_hold:
        state[1] = 0.0
    state[0] = 0.0
    state[1] += dt
    return state[1] >= inp.settle


@njit(cache=True)
def reinit(inp, t, k, q0, q1, q2, q3, rtk):
    """Attitude after a clock jump at sample k of trial t (nothing is integrated over its interval).

    Tilt from the sample's accelerometer (pitch ``atan2(a_y, |a_xz|)``, roll
    ``atan2(-a_x, a_z)``), heading from its magnetometer (tilt-compensated), or
    in RTK mode from a valid RTK epoch at k, else the current estimate's
    heading. An unusable or gated accelerometer sample keeps the attitude
    ``q``. The RTK hold and gate state ``rtk`` (see :func:`observe`) restarts.
    The caller restarts the settling of :func:`learning`.
    Returns (q0, q1, q2, q3). (Called, not inlined: inlined, it made every sample pay the reference
    counting of ``inp``'s arrays.)
    """
    f, m, gates = inp.f, inp.m, inp.gates
    rtk[3], rtk[4] = np.inf, 0.0                                   # the last epoch is stale
    ax, ay, az, ca = _accel_obs(f[t, k, 0], f[t, k, 1], f[t, k, 2], gates[0], gates[1])
    if ca != 0:
        return q0, q1, q2, q3
    pitch, roll = level(ax, ay, az)
    C = _dcm_t(q0, q1, q2, q3)
    h = dcm_heading(C[1], C[4])
    if inp.use_rtk:
        if inp.hdg_ok[t, k] and not np.isnan(inp.hdg[t, k]):
            h = inp.hdg[t, k]
            rtk[0], rtk[1], rtk[2], rtk[3] = np.sin(h), np.cos(h), h, 0.0
    elif inp.use_mag:
        mx, my, mz, cm = _mag_obs(m[t, k, 0], m[t, k, 1], m[t, k, 2], ax, ay, az, 0, gates[2:])
        if cm == 0:
            h = tilt_heading(mx, my, mz, pitch, roll)
    return euler_to_quat(h, pitch, roll)


# --------------------------------------------------------------------------
# Input and output
# --------------------------------------------------------------------------

@dataclass(frozen=True)
class MagGate:
    """Magnetometer gate: skip samples whose field disagrees with the local field.

    A sample is used only if ``| |m| / F - 1 | <= norm_tol`` and its dip angle
    (against the accelerometer's up direction) is within ``dip_tol`` (rad) of
    the local inclination I. F and I come from the ``B_n`` given to the filter.
    """
    norm_tol: float = 0.1
    dip_tol: float = np.deg2rad(5.0)

    def __post_init__(self):
        scalar(self.norm_tol, "norm_tol", positive=True)
        scalar(self.dip_tol, "dip_tol", positive=True)


@dataclass(frozen=True)
class AttitudeResult:
    """Output of :func:`navlib.filters.mahony.mahony` and :func:`navlib.filters.quaternion_kf.quaternion_kf`.

    Attributes
    ----------
    q_bn : ndarray, shape (..., N, 4)
        Attitude after each sample (magnetic north with a magnetometer, true
        north with RTK heading).
    gyro_bias : ndarray, shape (..., 3)
        Final gyro-bias estimate ``-Ki sum(e dt)`` (rad/s).
    counts : dict of str -> ndarray of int, shape (...)
        Held, skipped, gated, rejected and saturated samples, keys :data:`COUNT_NAMES`.
    P : ndarray, shape (..., 4, 4) or None
        Final quaternion covariance (:func:`navlib.filters.quaternion_kf.quaternion_kf`; None for Mahony).
    P_history : ndarray, shape (..., N, 4, 4) or None
        Covariance after every sample (``quaternion_kf(..., keep_cov=True)``).
    faults : FaultReport
        The same counts in navlib's one fault vocabulary (:data:`FAULT_KEYS`), e.g.
        ``result.faults["gyro", "nan"]``, and per-sample flags, shape (..., N), of the faults found
        before filtering: ``faults.flags["gyro", "stuck"]``, ``faults.flags["clock", "jump"]``.
    """
    q_bn: np.ndarray
    gyro_bias: np.ndarray
    counts: dict
    P: np.ndarray | None = None
    P_history: np.ndarray | None = None
    faults: FaultReport = field(default_factory=FaultReport)

    @property
    def hpr(self) -> np.ndarray:
        """Heading, pitch, roll (rad), shape (..., N, 3)."""
        return attitude.quat_to_euler(self.q_bn)


def heading_input(heading_rtk: ArrayLike, rtk_valid: ArrayLike, shape: tuple[int, ...],
                  name: str = "heading_rtk") -> tuple[np.ndarray, np.ndarray]:
    """Validate RTK heading and validity flags at the IMU rate; broadcast to ``shape`` (..., N)."""
    if rtk_valid is None:
        raise ValueError("rtk_valid: expected validity flags with the RTK heading (never infer validity "
                         "from the value)")
    v = booleans(rtk_valid, "rtk_valid")
    h = nonempty_array(heading_rtk, name, finite=False)
    for arr, label in ((h, name), (v, "rtk_valid")):
        try:
            np.broadcast_to(arr, shape)
        except ValueError:
            raise ValueError(f"{label}: expected a shape broadcastable to {shape} (the samples of heading_mag "
                             f"or w_ib_b), got {arr.shape}") from None
    h, v = np.broadcast_to(h, shape), np.broadcast_to(v, shape)
    used = h[v]
    bad = ~np.isnan(used) & ~((used >= 0) & (used < 2 * np.pi))
    if bad.any():
        raise ValueError(f"{name}: valid epochs must hold headings in [0, 2 pi) rad (or NaN for a dropout); "
                         f"{int(bad.sum())} do not (first: {used[bad][0]!r})")
    return kernel_array(h.reshape(-1, shape[-1])), kernel_array(v.reshape(-1, shape[-1]))   # writable: one signature


def rtk_params(rtk_hold: float, rtk_gate: float | None, rtk_confirm: int) -> np.ndarray:
    """Validated RTK settings ``[hold (s, + 1 ns rounding allowance), gate (rad, inf = off), confirm (epochs)]``."""
    hold = scalar(rtk_hold, "rtk_hold", positive=True, allow_zero=True) + 1e-9
    gate = np.inf if rtk_gate is None else scalar(rtk_gate, "rtk_gate", positive=True)
    if gate != np.inf and gate >= np.pi:
        raise ValueError(f"rtk_gate: expected a value in (0, pi) rad, got {gate!r}")
    return np.array([hold, gate, float(integer(rtk_confirm, "rtk_confirm"))])


def prepare_inputs(w_ib_b: Vec3Series, f_b: Vec3Series, dt: Interval, q0: Quat, m_b: Vec3Series | None,
                   heading_rtk: ArrayLike | None, rtk_valid: ArrayLike | None, B_n: Vec3 | None, gate: MagGate | None,
                   accel_tol: float | None, g: float, rtk_hold: float, rtk_gate: float | None, rtk_confirm: int,
                   full_scale_gyro: float | None, full_scale_accel: float | None, full_scale_mag: float | None,
                   gyro_jump: float | None, max_dt: float | None = None, stuck_run: int | str | None = "auto",
                   kp: float = 1.0) -> tuple[tuple[int, ...], AttitudeInputs, Screened]:
    """Validate the inputs of an attitude filter once (the parameters of :func:`navlib.filters.mahony.mahony`).

    Returns ``(lead, inputs, screened)``: the leading (trial) shape, the kernel record with trials
    flattened to T, and a :class:`Screened` record: the (T, 3) counts of gyro, accelerometer and
    magnetometer samples at the rails (accelerometer and magnetometer samples at the rails are NaN in
    ``inputs``: the kernels skip them like dropouts and :func:`attitude_result` corrects the skip
    counts), the stuck gyro samples (``inputs.stuck``: held like dropouts) and the clock jumps. The
    per-sample screening (stuck runs, the largest turn per interval) runs in parallel over the trials.

    Stuck gyro samples: :func:`navlib.robust.stuck_mask` with ``stuck_run`` samples ("auto":
    :data:`STUCK_DURATION` over the median interval, at least 5; None: off), in the trials whose gyro is
    noisy from the start (no axis repeats its first value ``stuck_run`` times: a noise-free simulation or
    a quantised gyro at rest is not checked); values at the rails (``full_scale_gyro``) are saturated,
    never stuck.
    Clock jumps: intervals longer than ``max_dt`` (s; None: :data:`JUMP_FACTOR` median intervals;
    inf: off). ``kp`` (rad/s) sets the settling time :data:`SETTLE_TIME_CONSTANTS` / kp.
    """
    w = nonempty_array(w_ib_b, "w_ib_b", tail=(3,), min_ndim=1, allow_nan=True)
    f = same_shape(nonempty_array(f_b, "f_b", tail=(3,), finite=False), "f_b", w.shape, of="w_ib_b")
    lead, N = w.shape[:-2], w.shape[-2]
    dts = intervals(dt, N)
    T = int(np.prod(lead))
    q = as_quat(q0, "q0")
    q = broadcast_to(q, "q0", lead + (4,), of="the trials of w_ib_b")
    q = np.array(q.reshape(T, 4), order="C")                  # a writable copy: one kernel signature
    if B_n is not None:
        magnetic_reference(B_n)                              # validate even where it is not needed
    use_rtk, use_mag = heading_rtk is not None, m_b is not None
    if rtk_valid is not None and not use_rtk:
        raise ValueError("rtk_valid: given without heading_rtk")
    if use_rtk and use_mag:
        raise ValueError("m_b, heading_rtk: give at most one heading reference (magnetometer or RTK)")
    if use_rtk:
        hdg, ok = heading_input(heading_rtk, rtk_valid, lead + (N,))
        m = np.zeros((1, 1, 3))
    elif not use_mag:
        if gate is not None:
            raise ValueError("gate: a magnetometer gate needs m_b")
        hdg, ok, m = np.zeros((1, 1)), np.zeros((1, 1), dtype=bool), np.zeros((1, 1, 3))
    else:
        m = same_shape(nonempty_array(m_b, "m_b", tail=(3,), finite=False), "m_b", w.shape, of="w_ib_b").reshape(T, N, 3)
        hdg, ok = np.zeros((1, 1)), np.zeros((1, 1), dtype=bool)
    gates = np.array([0.0, np.inf, 0.0, np.inf, -2.0, 2.0])
    g = scalar(g, "g", positive=True)
    if accel_tol is not None:
        tol = scalar(accel_tol, "accel_tol", positive=True)
        gates[0:2] = (g * max(1 - tol, 0.0)) ** 2, (g * (1 + tol)) ** 2
    if gate is not None:
        instance(gate, "gate", MagGate, "a MagGate")
        if B_n is None:
            raise ValueError("B_n: the magnetometer gate needs the local field")
        _, _, I, F = magnetic_reference(B_n)
        gates[2:4] = (F * max(1 - gate.norm_tol, 0.0)) ** 2, (F * (1 + gate.norm_tol)) ** 2
        gates[4:6] = np.sin(max(I - gate.dip_tol, -np.pi / 2)), np.sin(min(I + gate.dip_tol, np.pi / 2))
    jump = 0.0 if gyro_jump is None else scalar(gyro_jump, "gyro_jump", positive=True)
    rtk_par = rtk_params(rtk_hold, rtk_gate, rtk_confirm)
    typical = float(np.median(dts))
    max_dt = jump_limit(dts, max_dt, "dt")
    auto = stuck_run_samples("auto", typical)
    stuck_run = stuck_run_samples(stuck_run, typical)
    kp = scalar(kp, "kp", positive=True, allow_zero=True)
    settle = SETTLE_TIME_CONSTANTS / kp if kp > 0 else 0.0
    w, f = kernel_array(w.reshape(T, N, 3)), f.reshape(T, N, 3)
    # Saturation: counted here; accelerometer/magnetometer samples at the rails become NaN (skipped by the
    # kernel exactly like a dropout; the kernel's skip counts are corrected in _result), gyro samples are used.
    sat = np.zeros((T, 3), dtype=np.int64)
    rails = [np.inf, np.inf, np.inf]
    ranges = ((full_scale_gyro, "full_scale_gyro"), (full_scale_accel, "full_scale_accel"), (full_scale_mag, "full_scale_mag"))
    for i, (r, name) in enumerate(ranges):
        if r is None:
            continue
        rails[i] = r = scalar(r, name, positive=True)
        if i == 2 and not use_mag:
            continue
        x = (w, f, m)[i]
        rail = (np.abs(x) >= r).any(-1) & np.isfinite(x).all(-1)
        sat[:, i] = rail.sum(-1)
        if i == 1 and sat[:, i].any():
            f = np.where(rail[..., None], np.nan, f)
        elif i == 2 and sat[:, i].any():
            m = np.where(rail[..., None], np.nan, m)
    stuck, turn = np.zeros((T, N), dtype=bool), np.zeros(T)
    run_trials(_screen, T, w, dts, max_dt, stuck_run or 0, rails[0], stuck, turn)       # rails[0]: the gyro's
    refuse_turn(float(turn.max()))                              # (clock jumps are not integrated)
    inputs = AttitudeInputs(q, w, kernel_array(f), kernel_array(m), hdg, ok, use_rtk, use_mag, dts,
                            gates, jump, rtk_par, max_dt, stuck_run or auto, settle, stuck)
    return lead, inputs, Screened(sat, stuck, dts > max_dt)


@njit(cache=True, nogil=True)
def _screen(t0, t1, w, dts, max_dt, run, rail, stuck, turn):
    """Trials t0 to t1 - 1 of the gyro ``w`` (T, N, 3) before filtering: ``turn[t]``, the largest turn
    ``|w| dt`` over an integrated interval (``dt <= max_dt``; NaN samples ignored), and with ``run > 0``
    the stuck samples ``stuck[t]`` (:func:`navlib._kernels.stuck_runs`, values at ``rail`` excepted) of a
    trial whose gyro is noisy from the start (no axis repeats its first value ``run`` times)."""
    N = w.shape[1]
    for t in range(t0, t1):
        big = 0.0
        for k in range(N):
            if dts[k] <= max_dt:
                a = np.sqrt(w[t, k, 0] * w[t, k, 0] + w[t, k, 1] * w[t, k, 1] + w[t, k, 2] * w[t, k, 2]) * dts[k]
                if a > big:
                    big = a
        turn[t] = big
        if run == 0:
            continue
        noisy = True
        for c in range(3):
            k = 0
            while k < N and w[t, k, c] == w[t, 0, c]:
                k += 1
            noisy = noisy and k < run
        if noisy:
            stuck_runs(t, t + 1, w, run, rail, stuck)


def run_trials(kernel: Callable, n_trials: int, *args) -> None:
    """Run ``kernel(t0, t1, *args)`` over trials 0 to ``n_trials`` - 1 in parallel
    (:func:`navlib._threads.run_chunks`). The compiled kernels release the GIL; each trial writes only its
    own outputs, so the results do not depend on the number of threads.
    """
    run_chunks(lambda t0, t1: kernel(t0, t1, *args), n_trials)


def attitude_result(lead: tuple[int, ...], q_out: np.ndarray, bias: np.ndarray, counts: np.ndarray,
                    screened: Screened, P: np.ndarray | None = None, P_hist: np.ndarray | None = None) -> AttitudeResult:
    """Assemble an :class:`AttitudeResult` from kernel outputs over T flattened trials (leading shape ``lead``)."""
    sat, stuck, jump = screened
    counts[:, _GYRO_SATURATED:_MAG_SATURATED + 1] = sat    # saturated samples (see prepare_inputs) ...
    counts[:, _ACCEL_SKIPPED] -= sat[:, 1]                              # ... were skipped as NaN by the kernel
    counts[:, _MAG_SKIPPED] -= sat[:, 2]
    counts[:, _CLOCK_JUMP] = jump.sum()
    N = q_out.shape[1]
    named = {name: counts[:, i].reshape(lead) for i, name in enumerate(COUNT_NAMES)}
    flags = {("gyro", "stuck"): stuck.reshape(lead + (N,)), ("clock", "jump"): np.broadcast_to(jump, lead + (N,))}
    return AttitudeResult(q_out.reshape(lead + (N, 4)), bias.reshape(lead + (3,)), named,
                          None if P is None else P.reshape(lead + (4, 4)),
                          None if P_hist is None else P_hist.reshape(lead + (N, 4, 4)),
                          FaultReport({FAULT_KEYS[name]: c for name, c in named.items()}, flags))
