"""Mahony's nonlinear complementary filter on SO(3) with a PI correction (gyro + accelerometer + heading reference).

Mahony, Hamel, Pflimlin (2008), "Nonlinear complementary filters on the special orthogonal
group", IEEE T-AC 53(5), in the explicit form used by Zhang et al. 2023 (paper 003,
:mod:`navlib.papers.mimu_mag_rtk`), whose equation numbers are quoted:

* Eqs. (12)-(14): error ``e = a_meas x a_est + m_meas x m_est`` (measured x estimated), with
  ``m_est = C_nb [0, |h_xy|, h_z]`` and ``h = C_bn m_meas`` (:func:`navlib.filters.observations.pi_error`).
  The magnetometer term is mostly a heading correction, but not only: in the navigation frame it is
  ``h x [0, |h_xy|, h_z] = [h_z (h_y - |h_xy|), -h_x h_z, h_x |h_xy|]``, whose horizontal part grows with
  the vertical field times the heading error. A large heading error -- a magnetic disturbance -- therefore
  also tilts the estimate (13 deg on the real recording of notebook 06, where x-io's Fusion, which
  corrects heading only, stays within 0.2 deg); the field-norm and dip ``gate`` is the defence;
* Eq. (15): ``w = w_m + kp e + ki sum(e dt)`` with kp in rad/s and ki in rad/s^2 (the full cross
  product, not MahonyAHRS.c's half error "twoKp");
* Eq. (17): first-order update ``q <- normalise(q + dt/2 q (x) [0, w])``.

The heading reference is a magnetometer, a dual-antenna RTK heading, or none (gyro + accelerometer:
heading free); gates, holds and their
fault counts are those of :mod:`navlib.filters.observations`. Compiled and allocation-free per
sample; leading axes of the inputs are Monte Carlo trials, run in parallel (``NUMBA_NUM_THREADS``).
"""
from __future__ import annotations

import numpy as np
from numba import njit

from .._deprecate import renamed_keywords
from .._typing import ArrayLike, Interval, Quat, Vec3, Vec3Series
from .._validate import scalar
from ..attitude import quat_mult_t
from ..imu import ImuSamples, unpack
from ..units import G0
from .observations import (
    COUNT_NAMES,
    AttitudeResult,
    MagGate,
    attitude_result,
    gyro_sample,
    learning,
    observe,
    pi_error,
    prepare_inputs,
    reinit,
    run_trials,
)

__all__ = ["mahony"]


@njit(cache=True, nogil=True)
def _kernel(t0, t1, inp, kp, ki, q_out, bias_out, counts):
    """Trials t0 to t1 - 1 of ``inp`` (:class:`~navlib.filters.observations.AttitudeInputs`)."""
    for t in range(t0, t1):
        _trial(t, inp, kp, ki, q_out, bias_out, counts)


@njit(cache=True)
def _trial(t, inp, kp, ki, q_out, bias_out, counts):
    w, dts = inp.w, inp.dts
    q0, q1, q2, q3 = inp.q_init[t, 0], inp.q_init[t, 1], inp.q_init[t, 2], inp.q_init[t, 3]
    gx = gy = gz = 0.0
    ix = iy = iz = 0.0
    held = False
    rtk = np.array([0.0, 1.0, 0.0, np.inf, 0.0, 0.0])
    health = np.array([0.0, np.inf])
    for k in range(w.shape[1]):
        dt = dts[k]
        gx, gy, gz, held, fresh = gyro_sample(t, k, inp, gx, gy, gz, held, counts)
        if dt > inp.max_dt:                                            # clock jump: integrate nothing
            q0, q1, q2, q3 = reinit(inp, t, k, q0, q1, q2, q3, rtk)
            health[1] = 0.0
        else:
            ax, ay, az, a_ok, mx, my, mz, m_ok, C = observe(inp, t, k, q0, q1, q2, q3, dt, rtk, counts)
            ex, ey, ez = pi_error(C, ax, ay, az, a_ok, mx, my, mz, m_ok)
            if learning(fresh, dt, health, inp):                       # Eq. (15), unless settling after a fault
                ix += ex * dt
                iy += ey * dt
                iz += ez * dt
            wx, wy, wz = gx + kp * ex + ki * ix, gy + kp * ey + ki * iy, gz + kp * ez + ki * iz
            d0, d1, d2, d3 = quat_mult_t(q0, q1, q2, q3, 0.0, wx, wy, wz)  # Eq. (17): q + dt/2 q (x) [0, w]
            q0, q1, q2, q3 = q0 + 0.5 * dt * d0, q1 + 0.5 * dt * d1, q2 + 0.5 * dt * d2, q3 + 0.5 * dt * d3
            s = 1.0 / np.sqrt(q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3)
            q0, q1, q2, q3 = q0 * s, q1 * s, q2 * s, q3 * s
        q_out[t, k, 0], q_out[t, k, 1], q_out[t, k, 2], q_out[t, k, 3] = q0, q1, q2, q3
    bias_out[t, 0], bias_out[t, 1], bias_out[t, 2] = -ki * ix, -ki * iy, -ki * iz


@renamed_keywords(gyro_range="full_scale_gyro", accel_range="full_scale_accel", mag_range="full_scale_mag")
def mahony(w_ib_b: Vec3Series | ImuSamples, f_b: Vec3Series | None = None, dt: Interval | None = None,
           q0: Quat | None = None, *, m_b: Vec3Series | None = None,
           heading_rtk: ArrayLike | None = None, rtk_valid: ArrayLike | None = None, kp: float = 1.0,
           ki: float = 0.02, B_n: Vec3 | None = None, gate: MagGate | None = None, accel_tol: float | None = None,
           g: float = G0, rtk_hold: float = 0.25, rtk_gate: float | None = None, rtk_confirm: int = 5,
           full_scale_gyro: float | None = None, full_scale_accel: float | None = None, full_scale_mag: float | None = None,
           gyro_jump: float | None = None, max_dt: float | None = None,
           stuck_run: int | str | None = "auto") -> AttitudeResult:
    """Mahony PI complementary filter (Eqs. 9-15 of Zhang et al. 2023), per sample:
    ``e = a x a_est + m x m_est``, ``w = w_m + kp e + ki sum(e dt)``,
    ``q <- normalise(q + dt/2 q (x) [0, w])``.

    Identical to ``ahrs.filters.Mahony.updateMARG`` (AHRS 0.4.0, same frames and
    first-order update) except that ahrs skips samples whose gyro norm is exactly 0.
    With per-sample ``dt`` each step uses its own interval (integral term and
    quaternion update).

    Parameters
    ----------
    w_ib_b : array_like, shape (..., N, 3), or ImuSamples
        Gyro samples (rad/s); NaN samples are replaced by the last used one (counted). An
        :class:`navlib.imu.ImuSamples` here supplies ``f_b``, ``dt`` and the gyro and accelerometer ranges.
        Earth rate is neglected, as in the paper.
    f_b : array_like, shape (..., N, 3)
        Accelerometer samples (m/s^2); NaN, infinite or zero samples are skipped (counted).
    dt : float or array_like, shape (N,)
        Sample interval (s), or per-sample intervals: sample k covers
        ``dt[k] = t[k] - t[k-1]`` (irregular sampling). Timestamps with
        repeats or out of order go through :func:`navlib.timing.sanitize`
        first; then ``dt = timing.intervals(np.r_[t_before_first, t])``.
    q0 : array_like, shape (4,) or (..., 4)
        Attitude before the first sample, e.g. :func:`navlib.alignment.initial_attitude`.
    m_b : array_like, shape (..., N, 3), optional
        Magnetometer samples (uT); unusable samples are skipped and gated ones counted. With neither
        ``m_b`` nor ``heading_rtk`` the filter runs on gyro and accelerometer alone: tilt is corrected,
        the heading is free (it starts at ``q0``'s heading and drifts with the gyro bias about the
        vertical, which the accelerometer cannot observe).
    heading_rtk : array_like, shape (N,) or (..., N), optional
        Instead of ``m_b``: dual-antenna heading (rad, [0, 2 pi)) at the IMU rate,
        used as a north pseudo-vector (mode (a) of the paper's Fig. 4). Only samples with
        ``rtk_valid`` are read; each is held for ``rtk_hold`` seconds.
    rtk_valid : array_like of bool, same shape as ``heading_rtk``
        True where a valid RTK epoch arrives (the receiver's status flag).
        A valid epoch holding NaN is a dropout (ignored, ``rtk_dropped``).
    kp, ki : float
        Proportional (rad/s) and integral (rad/s^2) gains of Eq. (15); ``ki = 0``
        disables gyro-bias estimation.
    B_n : array_like, shape (3,), optional
        Local field (uT, ENU); needed by ``gate``.
    gate : MagGate, optional
        Field-norm and dip-angle gate for the magnetometer.
    accel_tol : float, optional
        Skip accelerometer samples whose norm differs from ``g`` by more than this fraction.
    g : float
        Gravity for ``accel_tol`` (m/s^2).
    rtk_hold : float
        How long an RTK epoch is used (s).
    rtk_gate : float, optional
        Reject RTK epochs whose heading differs from the current estimate by
        more than this (rad, in (0, pi)), e.g. 180 deg ambiguity flips
        (``rtk_rejected``); None (default) uses every valid epoch.
    rtk_confirm : int
        With ``rtk_gate``: after this many consecutive rejected epochs that
        agree with each other (within ``rtk_gate``), use them (``rtk_reacquired``),
        so that an estimate that drifted in an outage is pulled back.
    full_scale_gyro, full_scale_accel, full_scale_mag : float, optional
        Full-scale ranges (rad/s, m/s^2, uT), e.g. ``sensors.imu_model(name).gyro.full_scale``.
        Samples with a component at or beyond the range are counted
        (``*_saturated``); accelerometer and magnetometer corrections are
        skipped for them, gyro samples are used (the clipped rate is the best
        available) and flag the attitude after them as suspect. (Formerly ``gyro_range``,
        ``accel_range``, ``mag_range``: the old names warn.)
    gyro_jump : float, optional
        Spike gate (rad/s): a gyro sample differing from the last used one by
        more than this on some axis is replaced by it (``gyro_gated``) unless
        the previous sample was already replaced. Choose well above the
        per-sample noise and the largest rate change per sample of the motion.
    max_dt : float, optional
        Longest interval integrated (s). A sample whose ``dt`` exceeds it is a
        clock jump (``clock_jump``): nothing is integrated over it (gyro, PI
        integral) and the attitude is re-initialised from that sample's
        accelerometer (tilt) and magnetometer or RTK epoch (heading; else the
        heading is kept), or kept if the accelerometer sample is unusable.
        Default None: ``JUMP_FACTOR`` = 10 median intervals (no jump with a scalar
        ``dt``); ``inf``: off.
    stuck_run : int, "auto" or None
        A gyro whose output stopped updating: a sample where some axis repeats
        exactly the same value over ``stuck_run`` samples or more is stuck
        (``gyro_stuck``, from the first sample of the run until the value
        changes) and held like a NaN sample. Sensor noise makes such repeats of a
        real reading essentially impossible. Values at the ``full_scale_gyro``
        rails are saturated, not stuck; a trial whose gyro is not noisy from the
        start (some axis repeats its first value ``stuck_run`` times: a
        noise-free simulation, a quantised gyro at rest) is not checked.
        Default "auto": 0.1 s of samples (``STUCK_DURATION``), at least 5.
        Quantised gyros whose noise is about one count repeat by chance: use a
        larger value, or None (off).

    What the filter does with bad samples
    -------------------------------------
    NaN or stuck gyro: hold the last used sample, and freeze the gyro-bias
    estimate (the PI integral) while held and, after a hold of ``stuck_run``
    samples or more or a clock jump, for ``SETTLE_TIME_CONSTANTS / kp`` = 15 s
    at kp = 1 (the transient the fault left would corrupt it). Gyro spike
    (``gyro_jump``): hold.
    NaN/inf/zero accelerometer, or outside ``accel_tol``, or saturated: skip
    the accelerometer correction. Magnetometer NaN/inf/zero, parallel to
    gravity, outside the ``gate`` or saturated: skip the heading correction.
    RTK: invalid epochs and NaN values are not read; epochs outside
    ``rtk_gate`` are rejected. A gap (any sensor) is a run of such samples: the
    attitude is propagated by the gyro alone and drifts at the gyro-bias
    error. A clock jump (``max_dt``): re-initialise. Every case is counted in
    :attr:`AttitudeResult.counts`; stuck and jump samples are also flagged in
    ``faults.flags``.

    Returns
    -------
    AttitudeResult
    """
    w_ib_b, f_b, dt, full_scale_gyro, full_scale_accel = unpack(w_ib_b, f_b, dt, full_scale_gyro, full_scale_accel)
    lead, inp, screened = prepare_inputs(w_ib_b, f_b, dt, q0, m_b, heading_rtk, rtk_valid, B_n, gate, accel_tol, g,
                                         rtk_hold, rtk_gate, rtk_confirm, full_scale_gyro, full_scale_accel,
                                         full_scale_mag, gyro_jump, max_dt, stuck_run, kp)
    kp, ki = scalar(kp, "kp", positive=True, allow_zero=True), scalar(ki, "ki", positive=True, allow_zero=True)
    T, N = inp.w.shape[:2]
    q_out, bias, counts = np.empty((T, N, 4)), np.empty((T, 3)), np.zeros((T, len(COUNT_NAMES)), dtype=np.int64)
    run_trials(_kernel, T, inp, kp, ki, q_out, bias, counts)
    return attitude_result(lead, q_out, bias, counts, screened)
