"""ZUPT/ZARU-aided strapdown INS with barometer and magnetometer aiding (a pedestrian or any walker).

A strapdown INS runs at all times; while the IMU stands still a 15-state error-state Kalman filter
(:mod:`navlib.filters.zupt`: states, F, ZUPT/ZARU rows) uses zero velocity and zero angular rate to
estimate and feed back the INS errors (closed loop: ``r -= dr, v -= dv, C <- (I - [dpsi x]) C,
b += db, dx = 0``); while walking the height comes from an alpha-beta tracker on the barometric height
and the heading from the tilt-compensated compass, either as direct resets ("direct binding",
``walk_aiding="reset"``) or as Kalman measurements (``"filter"``). This is the system of Wen, Xu & Yu
(2016), paper 004 (:mod:`navlib.papers.pedestrian_ins`, which holds its equations as printed and its
scenarios); its defaults (:class:`FilterConfig`) are that paper's sensors.

The filter (:func:`run_filter`, a compiled per-sample kernel) reuses navlib's
strapdown step, the block covariance prediction of :mod:`navlib.filters.zupt`
(:func:`~navlib.filters.zupt.error_state_predict_into`, which multiplies only the
non-zero blocks of the transition matrix) and :func:`navlib.kalman.update`; a step
without a measurement allocates nothing.
It holds NaN IMU samples from the last good one, rejects static updates that
fail a NIS gate (false stances), applies one ungated after repeated
rejections within a stance (a drifted INS must not lock the filter out),
optionally gates compass samples on the field's magnitude and dip (steel),
counts all of these, and warns when it never updated (no static interval).

Faults (robustness contract; tests in ``tests/faults/test_faults_pedestrian.py``;
every action is counted in ``FilterResult.counts``):

* IMU dropouts (NaN): zero-order hold of the last good sample
  (``imu_dropouts``), with the process noise inflated while holding
  (``FilterConfig.hold_*_sigma``); held samples never feed ZUPT/ZARU
  (``static_skipped``); :func:`navlib.filters.zupt.detect_static` uses the valid samples of a
  window and needs at least half of them.
* IMU spikes: with ``FilterConfig.spike_gyro`` / ``spike_accel`` set, an
  isolated sample sticking out of both neighbours is held like a dropout
  (``imu_spikes``); :func:`navlib.robust.despike` applies the same test before
  the static detector (whose variance test spikes would otherwise fail).
  Off by default (the paper's filter): then a spike in a stance fails the
  detector or the NIS gate (``zupt_rejected``) and one while walking is
  integrated.
* IMU saturation (``full_scale_gyro`` / ``full_scale_accel`` given): samples at the rails are counted
  (``imu_saturated``), integrated as measured, and excluded from ZUPT/ZARU
  (``static_skipped``).
* Barometer: NaN = no reading (the tracker coasts); spikes beyond
  ``FilterConfig.baro_gate`` are skipped (``baro_rejected``); a persistent
  jump re-initialises the tracker (``baro_reinit``).
* Magnetometer: NaN = no reading; spikes and disturbances fail the field
  magnitude / dip gate when ``B_n`` and tolerances are given (``mag_gated``).
* Timing: ``dt`` may be per-sample intervals (irregular sampling); repeated
  and out-of-order timestamps go through :func:`navlib.timing.sanitize` first.
  A time jump (an interval above ``FilterConfig.max_dt``, default 1 s, e.g. a
  clock step of an hour) is not integrated as motion: the INS and the
  barometer tracker are held over it (mechanised over a zero interval), the
  covariance grows by the process noise of the whole interval, the sample is
  never used for ZUPT/ZARU, and the filter goes on (``time_jumps``,
  ``FLAG_TIME_JUMP``).
* Free fall / dead accelerometer: a run of samples with ``|f| <
  FilterConfig.freefall_accel`` (default 2 m/s^2) lasting at least
  ``freefall_time`` (default 0.05 s) cannot be a walker (a stance reads |f| = g,
  the gait never drops below ~5 m/s^2): its accelerometer samples are held
  from the last good one like a dropout (gyro used; velocity process noise
  inflated by ``hold_accel_sigma``), never used for ZUPT/ZARU, counted
  (``imu_freefall``) and flagged (``FLAG_FREEFALL``).

Beyond the paper: the Earth-rate block ``-C^T [w_ie x]`` of H (:mod:`navlib.filters.zupt`), and an
accelerometer process noise five times the MPU-6050 density to cover the scale-factor and cross-axis
errors the 15-state model leaves out (:class:`FilterConfig`).
"""
from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np
from numba import njit

from .. import _kernels, attitude, earth, robust, trajectory
from .._deprecate import renamed_keywords
from .._kernels import radii_mn
from .._validate import as_array, as_quat, booleans, choice, flag, imu_samples, instance, integer, intervals, range_limit, scalar
from .._validate import ellipsoid as ellipsoid_
from ..imu import unpack
from ..strapdown import earth_constants
from ..units import G0
from .zupt import error_state_predict_into, zupt_zaru_rows_into, zupt_zaru_z_into

__all__ = ["FilterConfig", "FilterResult", "run_filter", "FLAG_DROPOUT", "FLAG_SPIKE", "FLAG_SATURATED",
           "FLAG_STATIC_SKIPPED", "FLAG_TIME_JUMP", "FLAG_FREEFALL", "FAULT_KEYS"]


_MAY_BE_INF = ("gate", "mag_field_tol", "mag_dip_tol", "baro_gate", "spike_gyro", "spike_accel", "max_dt",
               "freefall_time")


@dataclass(frozen=True)
class FilterConfig:
    """Noise and tuning of the ZUPT/ZARU error-state filter (SI units).

    Defaults: MPU-6050 gyro rate-noise density (datasheet); accelerometer density
    0.02 m/s^2/sqrt(Hz), five times the MPU-6050's 400 ug/sqrt(Hz), to cover
    the scale-factor and cross-axis errors (1 %, 0.67 %) that the 15-state
    model leaves out and that walking's 3 m/s^2 oscillations excite (with
    the datasheet density the NIS gate rejects the legitimate ZUPTs after a
    walk); residual biases after a static calibration (0.05 deg/s, 10 mg) as
    initial bias sigmas; BMP180 height noise 0.17 m; HMC5983 heading 2 deg.

    Attributes
    ----------
    accel_noise, gyro_noise : float
        White-noise densities (m/s^2/sqrt(Hz), rad/s/sqrt(Hz)).
    accel_bias_rw, gyro_bias_rw : float
        Bias random-walk densities (m/s^3/sqrt(Hz), rad/s^2/sqrt(Hz)).
    sigma_zupt : float
        ZUPT velocity sigma (m/s), absorbs standing sway.
    sigma_zaru : float
        ZARU rate sigma (rad/s) of a single sample; divided by sqrt(n) for
        the mean of n samples.
    update_rate : float
        ZUPT/ZARU update rate while static (Hz).
    sigma_baro : float
        Barometric height sigma (m).
    sigma_heading : float
        Magnetic heading sigma (rad).
    baro_alpha, baro_beta : float
        Gains of the alpha-beta tracker smoothing the barometric height.
    p0_pos, p0_vel, p0_tilt, p0_heading, p0_accel_bias, p0_gyro_bias : float
        Initial standard deviations (m, m/s, rad, rad, m/s^2, rad/s).
    gate : float
        NIS gate of the static update (chi-square, 6 dof; 22.5 is 99.9 %).
        Rejects false stances (a walker flagged static).
    max_rejected : int
        After this many consecutive rejections within one stance the next
        update is applied ungated, with the velocity variances widened to
        the innovation, and counted as ``zupt_forced``: a stance that keeps
        failing the gate means the INS has drifted beyond its covariance,
        and gating it forever would lock the filter out.
    mag_field_tol, mag_dip_tol : float
        Reject magnetic resets when |m| differs from the reference intensity
        by more than this (uT) or the dip by more than this (rad); inf to
        accept every sample. This is also the defence against magnetometer
        spikes (a 100-sigma spike changes |m| by tens of uT); it needs
        ``B_n`` in :func:`run_filter`.
    baro_gate : float
        Reject a barometric height that differs from the alpha-beta tracker's
        prediction by more than this (m): a spike (counted ``baro_rejected``;
        the tracker coasts over it and no aiding uses it). After
        ``max_rejected`` consecutive rejections the tracker is re-initialised
        on the measurement (counted ``baro_reinit``): the height really
        changed while the barometer was missing or the tracker diverged.
        Default 5 m: 10 BMP180 sigmas (0.5 m at 0.06 hPa), far beyond HVAC
        pressure steps (~1 m) and the tracker lag on stairs; inf disables.
    spike_gyro, spike_accel : float
        IMU spike test (rad/s, m/s^2): a sample that deviates from the line
        through its two neighbours by more than this, on any axis, and by
        more than 1.5 times the same deviation of either neighbour, is an
        isolated spike; it is held like a dropout and counted
        (``imu_spikes``). Default inf (off, the paper's filter). At 100 Hz
        on a walking shoulder 0.02 rad/s and 0.5 m/s^2 are safe (that
        deviation is a few mrad/s and cm/s^2 for the gait, noise 0.001 rad/s
        and 0.05 m/s^2 for the MPU-6050). Offline test: it looks two samples
        ahead; the first and last two samples are never tested.
    hold_gyro_sigma, hold_accel_sigma : float
        Uncertainty of a held sample (rad/s, m/s^2): while a dropout or
        spike is bridged by holding, the attitude and velocity process noise
        grow by ``sigma^2 dt`` per held sample, so the covariance admits the
        guess and the next stance's ZUPT/ZARU is not gated out.
    max_dt : float
        Longest sample interval integrated as motion (s); a longer one is a
        time jump (counted ``time_jumps``): the INS is held over it, the
        covariance grows by the process noise ``q dt`` of the whole interval
        (no hold inflation: the samples around it are real), and the sample
        is left out of ZUPT/ZARU. Default 1 s, two steps of a walker:
        up to it, one sample integrated over the interval errs by about as
        much as not moving at all (walking 1.2 m/s, gait accelerations of
        +-3 m/s^2: about a metre either way); beyond it the integrated
        sample's error grows with dt^2 (a 0.1 m/s^2 residual bias alone
        gives 650 km over a 1-h clock step, which took the latitude past
        the pole), holding's at most with dt. Independent of the sample
        rate on purpose: gaps of many samples up to 1 s are still
        integrated (``timing.intervals`` after dropped samples). inf
        disables the test; a record whose median interval exceeds it is
        refused (``dt``).
    freefall_accel, freefall_time : float
        Free-fall test (m/s^2, s): samples with ``|f| < freefall_accel``
        in a run lasting at least ``freefall_time`` (the sum of their
        intervals) have their accelerometer held from the last good sample,
        are never used for ZUPT/ZARU and are counted (``imu_freefall``).
        Defaults 2 m/s^2 and 0.05 s: a stance reads |f| = g +- 0.3 m/s^2
        (the static detector's tolerance), a walker's gait stays above ~5
        m/s^2, and a zeroed or falling MPU-6050 reads its residual bias, 0.1
        m/s^2; 0.05 s (5 samples at 100 Hz) leaves single glitches to the
        spike test. A runner's ballistic phases (~0.1 s at |f| ~ 0) would be
        held: raise ``freefall_time`` (inf disables the test) for running.
        Offline test: a run is judged on its whole length.
    """
    accel_noise: float = 0.02
    gyro_noise: float = np.deg2rad(0.005)
    accel_bias_rw: float = 1e-4
    gyro_bias_rw: float = 1e-5
    sigma_zupt: float = 0.01
    sigma_zaru: float = np.deg2rad(0.1)
    update_rate: float = 10.0
    sigma_baro: float = 0.17
    sigma_heading: float = np.deg2rad(2.0)
    baro_alpha: float = 0.2
    baro_beta: float = 0.02
    p0_pos: float = 0.01
    p0_vel: float = 0.01
    p0_tilt: float = np.deg2rad(0.5)
    p0_heading: float = np.deg2rad(2.0)
    p0_accel_bias: float = 0.01 * G0
    p0_gyro_bias: float = np.deg2rad(0.05)
    gate: float = 22.5
    max_rejected: int = 5
    mag_field_tol: float = np.inf
    mag_dip_tol: float = np.inf
    baro_gate: float = 5.0
    spike_gyro: float = np.inf
    spike_accel: float = np.inf
    hold_gyro_sigma: float = 0.1
    hold_accel_sigma: float = 1.0
    max_dt: float = 1.0
    freefall_accel: float = 2.0
    freefall_time: float = 0.05

    def __post_init__(self):
        for name, v in self.__dict__.items():
            if name != "max_rejected":
                scalar(v, name, positive=True, allow_inf=name in _MAY_BE_INF)
        integer(self.max_rejected, "max_rejected")


# counters returned by the kernel
(_N_ZUPT, _N_ZUPT_REJ, _N_ZUPT_FORCED, _N_IMU_NAN, _N_BARO, _N_MAG, _N_MAG_GATED, _N_SAT, _N_STATIC_SKIP,
 _N_BARO_REJ, _N_BARO_REINIT, _N_SPIKE, _N_JUMP, _N_FREEFALL) = range(14)
_COUNTERS = ("zupt_updates", "zupt_rejected", "zupt_forced", "imu_dropouts", "baro_aidings", "mag_aidings",
             "mag_gated", "imu_saturated", "static_skipped", "baro_rejected", "baro_reinit", "imu_spikes",
             "time_jumps", "imu_freefall")


_AIDING = {"none": 0, "reset": 1, "filter": 2}
FLAG_DROPOUT, FLAG_SPIKE, FLAG_SATURATED, FLAG_STATIC_SKIPPED, FLAG_TIME_JUMP, FLAG_FREEFALL = 1, 2, 4, 8, 16, 32
"""Bits of :attr:`FilterResult.flags`."""

FAULT_KEYS = {"imu_dropouts": ("imu", "nan"), "imu_spikes": ("imu", "spike"), "imu_saturated": ("imu", "saturated"),
              "static_skipped": ("zupt", "refused"), "zupt_rejected": ("zupt", "outlier"),
              "zupt_forced": ("zupt", "reacquired"), "baro_rejected": ("baro", "outlier"),
              "baro_reinit": ("baro", "reacquired"), "mag_gated": ("mag", "outlier"),
              "time_jumps": ("clock", "jump"), "imu_freefall": ("accel", "freefall")}
"""The fault counters of :attr:`FilterResult.counts` as ``(sensor, kind)`` keys of
:class:`navlib.robust.FaultReport` (the other counters count aiding, not faults)."""
_FLAG_KEYS = {FLAG_DROPOUT: ("imu", "nan"), FLAG_SPIKE: ("imu", "spike"), FLAG_SATURATED: ("imu", "saturated"),
              FLAG_STATIC_SKIPPED: ("zupt", "refused"), FLAG_TIME_JUMP: ("clock", "jump"),
              FLAG_FREEFALL: ("accel", "freefall")}


class _Samples(NamedTuple):
    """Per-sample inputs of :func:`_filter_kernel`: N rows each, SI units, NaN = no reading."""
    w: np.ndarray                   # (N, 3) gyro (rad/s)
    f: np.ndarray                   # (N, 3) accelerometer (m/s^2)
    dt: np.ndarray                  # (N,) interval covered by each sample (s)
    static: np.ndarray              # (N,) bool
    h_baro: np.ndarray              # (N,) barometric height (m)
    m_b: np.ndarray                 # (N, 3) magnetometer (uT)
    freefall: np.ndarray            # (N,) bool: |f| ~ 0 for at least FilterConfig.freefall_time


class _Setup(NamedTuple):
    """Initial state and tuning of :func:`_filter_kernel` (``r_*`` are variances; see :class:`FilterConfig`)."""
    lla0: np.ndarray                # (3,) rad, rad, m
    vel0: np.ndarray                # (3,) m/s ENU
    q0: np.ndarray                  # (4,)
    b0: np.ndarray                  # (6,) accelerometer then gyro bias
    declination: float
    field_ref: np.ndarray           # (2,) reference intensity (uT) and dip (rad); zeros: no gate
    zupt: bool
    aiding: int                     # _AIDING code
    every: int                      # static samples averaged per ZUPT/ZARU update
    q_rate: np.ndarray              # (15,) process-noise densities squared (Q = q_rate dt_k)
    p0_diag: np.ndarray             # (15,) initial variances
    r_zupt: float
    r_zaru: float
    r_baro: float
    r_heading: float
    alpha: float
    beta: float
    gate: float
    max_rejected: int
    field_tol: float
    dip_tol: float
    gyro_fs: float
    accel_fs: float
    baro_gate: float
    spike_gyro: float
    spike_accel: float
    hold_gyro: float
    hold_accel: float
    max_dt: float                   # longer intervals are time jumps (s)
    earth_consts: np.ndarray        # (7,) navlib.strapdown.earth_constants


def _freefall(f, dts, threshold, min_time):
    """Samples in a run of ``|f| < threshold`` whose intervals sum to at least ``min_time`` (NaN: not in a run)."""
    with np.errstate(invalid="ignore"):
        low = np.sqrt(np.sum(f * f, axis=-1)) < threshold         # NaN compares False
    if not low.any():
        return low
    edges = np.flatnonzero(np.diff(np.concatenate([[0], low.astype(np.int8), [0]])))
    out = np.zeros_like(low)
    for a, b in zip(edges[::2], edges[1::2], strict=True):
        if dts[a:b].sum() >= min_time:
            out[a:b] = True
    return out


@njit(cache=True)
def _feedback(x, lla, vel, q, b, a, e2):
    """Closed-loop correction of Eq. (3): apply dx to the INS and zero it."""
    R_M, R_N = radii_mn(lla[0], a, e2)
    lla[0] -= x[1] / (R_M + lla[2])
    lla[1] -= x[0] / ((R_N + lla[2]) * np.cos(lla[0]))
    lla[2] -= x[2]
    for i in range(3):
        vel[i] -= x[3 + i]
    d0, d1, d2, d3 = attitude.rotvec_to_quat_t(-x[6], -x[7], -x[8])     # C <- (I - [dpsi x]) C
    m0, m1, m2, m3 = attitude.quat_mult_t(d0, d1, d2, d3, q[0], q[1], q[2], q[3])
    s = np.sqrt(m0 * m0 + m1 * m1 + m2 * m2 + m3 * m3)
    q[0], q[1], q[2], q[3] = m0 / s, m1 / s, m2 / s, m3 / s
    for i in range(6):
        b[i] += x[9 + i]
    x[:] = 0.0


@njit(cache=True)
def _finite_row(x, k):
    """``np.isfinite(x[k]).all()`` without a temporary array."""
    for i in range(x.shape[1]):
        if not np.isfinite(x[k, i]):
            return False
    return True


@njit(cache=True)
def _reset_state(P, i, sigma):
    for j in range(P.shape[0]):
        P[i, j] = 0.0
        P[j, i] = 0.0
    P[i, i] = sigma * sigma


@njit(cache=True)
def _filter_kernel(samples, c):
    """Run the filter over ``samples`` (:class:`_Samples`) from the state and tuning ``c`` (:class:`_Setup`)."""
    w, f, dt, static, h_baro, m_b, freefall = samples
    a, e2, omega = c.earth_consts[0], c.earth_consts[2], c.earth_consts[6]
    n = w.shape[0]
    counts = np.zeros(14, dtype=np.int64)
    flags = np.zeros(n, dtype=np.uint8)
    lla_out, vel_out, q_out = np.empty((n + 1, 3)), np.empty((n + 1, 3)), np.empty((n + 1, 4))
    b_out, p_out = np.empty((n + 1, 6)), np.empty((n + 1, 15))
    lla, vel, q, b = c.lla0.copy().reshape(1, 3), c.vel0.copy().reshape(1, 3), c.q0.copy().reshape(1, 4), c.b0.copy()
    x, P = np.zeros(15), np.diag(c.p0_diag)
    q_k, work = np.empty(15), np.empty((2, 15, 15))       # process noise (diagonal) of a step, predict scratch
    C, C_dt, f_dt = np.empty((3, 3)), np.empty((3, 3)), np.empty(3)
    H6, z6, h6 = np.zeros((6, 15)), np.zeros(6), np.zeros(6)
    R6 = np.diag(np.array([c.r_zupt, c.r_zupt, c.r_zupt, c.r_zaru, c.r_zaru, c.r_zaru]))
    H1, z1, h1, R1 = np.zeros((1, 15)), np.zeros(1), np.zeros(1), np.zeros((1, 1))
    no_wrap6, wrap1, no_wrap1 = np.zeros(6, dtype=np.bool_), np.ones(1, dtype=np.bool_), np.zeros(1, dtype=np.bool_)
    wk, fk = np.zeros(3), np.zeros(3)
    w_last, f_last = w[0].copy(), f[0].copy()
    w_sum, n_sum, n_rejected = np.zeros(3), 0, 0
    hb, vb, hb_init, t_baro = 0.0, 0.0, False, 0.0          # alpha-beta tracker of the baro height
    n_baro_rej = 0
    w_ie = np.zeros(3)
    _store(0, lla_out, vel_out, q_out, b_out, p_out, lla[0], vel[0], q[0], b, P)
    for k in range(n):
        dtk = dt[k]
        good, held, f_held = True, False, False          # good: a real, unclipped sample, usable for ZUPT/ZARU
        jump = dtk > c.max_dt
        if jump:                                         # time jump: no motion integrated over it (held)
            counts[_N_JUMP] += 1
            flags[k] |= FLAG_TIME_JUMP
            dtk = 0.0
        if not (_finite_row(w, k) and _finite_row(f, k)):
            counts[_N_IMU_NAN] += 1                      # dropout: hold the last good sample
            flags[k] |= FLAG_DROPOUT
            good, held = False, True
        elif k > 1 and k + 2 < n and (robust.is_spike(w, k, c.spike_gyro) or robust.is_spike(f, k, c.spike_accel)):
            counts[_N_SPIKE] += 1                        # isolated spike: held like a dropout
            flags[k] |= FLAG_SPIKE
            good, held = False, True
        else:
            for i in range(3):
                w_last[i] = w[k, i]
            if freefall[k]:                              # |f| ~ 0: free fall or a dead accelerometer, held
                counts[_N_FREEFALL] += 1
                flags[k] |= FLAG_FREEFALL
                good, f_held = False, True
            else:
                for i in range(3):
                    f_last[i] = f[k, i]
            clipped = False
            for i in range(3):
                if abs(w[k, i]) >= c.gyro_fs or abs(f[k, i]) >= c.accel_fs:
                    clipped = True
            if clipped:
                good = False
                counts[_N_SAT] += 1                      # at the rails: integrated as is, no static update
                flags[k] |= FLAG_SATURATED
        if jump:
            good = False
        for i in range(3):
            wk[i] = w_last[i] - b[3 + i]
            fk[i] = f_last[i] - b[i]
        _kernels.nav_step(lla[0], vel[0], q[0], wk, fk, dtk, c.earth_consts, False)   # the shared mechanisation
        attitude.quat_to_dcm_into(C, q[0])
        f_n = _kernels.mat3_vec(C, fk)
        for i in range(3):
            f_dt[i] = f_n[i] * dtk
            for j in range(3):
                C_dt[i, j] = C[i, j] * dtk
        for i in range(15):
            q_k[i] = c.q_rate[i] * dtk
        if held:                                         # the held sample is a guess: inflate, don't trust
            for i in range(3):
                q_k[3 + i] += c.hold_accel * c.hold_accel * dtk
                q_k[6 + i] += c.hold_gyro * c.hold_gyro * dtk
        elif f_held:                                     # only the accelerometer is a guess
            for i in range(3):
                q_k[3 + i] += c.hold_accel * c.hold_accel * dtk
        # Phi = I + F dt (blocks C dt, f_n dt). x stays zero between updates (each is fed back and x reset:
        # closed loop), so x = Phi x = 0 and only P is predicted.
        error_state_predict_into(P, C_dt, f_dt, dtk, q_k, work)
        if jump:                                         # Phi = I, Q = 0 above: add the whole interval's noise
            for i in range(15):
                P[i, i] += c.q_rate[i] * dt[k]
        if static[k] and c.zupt and not good:              # held or clipped: left out of the static average
            counts[_N_STATIC_SKIP] += 1
            flags[k] |= FLAG_STATIC_SKIPPED
        # --- standing still: ZUPT + ZARU (Eq. 2) ---
        elif static[k] and c.zupt:
            for i in range(3):
                w_sum[i] += w_last[i]
            n_sum += 1
            if n_sum >= c.every:
                w_ie[1], w_ie[2] = omega * np.cos(lla[0, 0]), omega * np.sin(lla[0, 0])
                zupt_zaru_rows_into(H6, C, w_ie)
                zupt_zaru_z_into(z6, vel[0], w_sum / n_sum, b[3:6], C, w_ie)
                for i in range(3):
                    R6[3 + i, 3 + i] = c.r_zaru / n_sum
                h6[:] = 0.0                                  # H x, x = 0 between updates (closed loop)
                # a stance that keeps failing the gate means the INS, not the stance, is wrong
                forced = n_rejected >= c.max_rejected
                if forced:                                   # P was too small: widen the velocity rows
                    for i in range(3):
                        _reset_state(P, 3 + i, max(np.sqrt(P[3 + i, 3 + i]), abs(z6[i] - h6[i])))
                x, P, _, _, status = _kernels.kalman_update(x, P, z6, h6, H6, R6, no_wrap6, np.inf if forced else c.gate)
                if status == 1:
                    counts[_N_ZUPT] += 1
                    counts[_N_ZUPT_FORCED] += forced
                    n_rejected = 0
                    _feedback(x, lla[0], vel[0], q[0], b, a, e2)
                elif status == -1:
                    counts[_N_ZUPT_REJ] += 1
                    n_rejected += 1
                w_sum[:], n_sum = 0.0, 0
        elif not static[k]:
            w_sum[:], n_sum, n_rejected = 0.0, 0, 0
        # --- barometer: alpha-beta tracker always, aiding while walking ---
        use_baro = np.isfinite(h_baro[k])
        if use_baro:
            if not hb_init:
                hb, vb, hb_init = h_baro[k], 0.0, True
            else:
                r = h_baro[k] - hb
                if abs(r) > c.baro_gate and n_baro_rej < c.max_rejected:
                    counts[_N_BARO_REJ] += 1                 # spike: the tracker coasts over it
                    n_baro_rej += 1
                    use_baro = False
                elif abs(r) > c.baro_gate:                     # persistent: the tracker, not the sensor, is off
                    counts[_N_BARO_REINIT] += 1
                    hb, vb, n_baro_rej = h_baro[k], 0.0, 0
                else:
                    hb += c.alpha * r
                    vb += c.beta * r / t_baro
                    n_baro_rej = 0
        if use_baro:
            t_baro = 0.0
            if c.aiding > 0 and not static[k]:
                counts[_N_BARO] += 1
                if c.aiding == 1:                              # direct binding
                    lla[0, 2], vel[0, 2] = hb, vb
                    _reset_state(P, 2, np.sqrt(c.r_baro))
                    _reset_state(P, 5, 0.3)
                else:
                    H1[:] = 0.0
                    H1[0, 2] = 1.0
                    z1[0], h1[0], R1[0, 0] = lla[0, 2] - h_baro[k], 0.0, c.r_baro
                    x, P, _, _, status = _kernels.kalman_update(x, P, z1, h1, H1, R1, no_wrap1, np.inf)
                    _feedback(x, lla[0], vel[0], q[0], b, a, e2)
        hb += vb * dtk
        t_baro += dt[k]                                  # (dtk but for a jump, 0: keeps t_baro > 0)
        # --- magnetometer heading while walking (Eqs. 4-6) ---
        if c.aiding > 0 and not static[k] and _finite_row(m_b, k):
            m_n = C @ m_b[k]
            F_m = np.sqrt(m_n[0] ** 2 + m_n[1] ** 2 + m_n[2] ** 2)
            dip = np.arctan2(-m_n[2], np.sqrt(m_n[0] ** 2 + m_n[1] ** 2))
            if abs(F_m - c.field_ref[0]) > c.field_tol or abs(dip - c.field_ref[1]) > c.dip_tol:
                counts[_N_MAG_GATED] += 1
            else:
                pitch, roll = np.arcsin(min(1.0, max(-1.0, C[2, 1]))), np.arctan2(-C[2, 0], C[2, 2])
                alpha_h = _kernels.tilt_heading(m_b[k, 0], m_b[k, 1], m_b[k, 2], pitch, roll) + c.declination
                dh = _kernels.wrap_pi(_kernels.dcm_heading(C[0, 1], C[1, 1]) - alpha_h)
                counts[_N_MAG] += 1
                if c.aiding == 1:                          # C <- rot(z, H_hat - alpha) C
                    rz = np.array([np.cos(dh / 2), 0.0, 0.0, np.sin(dh / 2)])
                    qn = attitude.quat_normalize_1(attitude.quat_mult_1(rz, q[0]))
                    for i in range(4):
                        q[0, i] = qn[i]
                    _reset_state(P, 8, np.sqrt(c.r_heading))
                else:
                    c1 = C[:, 1]
                    hh = c1[0] ** 2 + c1[1] ** 2
                    H1[:] = 0.0
                    H1[0, 6], H1[0, 7], H1[0, 8] = c1[0] * c1[2] / hh, c1[1] * c1[2] / hh, -1.0
                    z1[0], h1[0], R1[0, 0] = dh, 0.0, c.r_heading
                    x, P, _, _, status = _kernels.kalman_update(x, P, z1, h1, H1, R1, wrap1, np.inf)
                    _feedback(x, lla[0], vel[0], q[0], b, a, e2)
        _store(k + 1, lla_out, vel_out, q_out, b_out, p_out, lla[0], vel[0], q[0], b, P)
    return lla_out, vel_out, q_out, b_out, p_out, counts, flags, P


@njit(cache=True)
def _store(k, lla_out, vel_out, q_out, b_out, p_out, lla, vel, q, b, P):
    """Row k of the outputs, element by element (cheaper than row assignments, which also compile numba's
    shape-mismatch messages: seconds of a cold start)."""
    for i in range(3):
        lla_out[k, i], vel_out[k, i] = lla[i], vel[i]
    for i in range(4):
        q_out[k, i] = q[i]
    for i in range(6):
        b_out[k, i] = b[i]
    for i in range(15):
        p_out[k, i] = P[i, i]


@dataclass(frozen=True)
class FilterResult:
    """Output of :func:`run_filter`.

    Attributes
    ----------
    nav : Trajectory
        Corrected INS solution, N + 1 epochs.
    accel_bias, gyro_bias : ndarray, shape (N + 1, 3)
        Bias estimates (m/s^2, rad/s).
    P_diag : ndarray, shape (N + 1, 15)
        Diagonal of the error covariance.
    counts : dict
        ``zupt_updates`` (accepted static updates), ``zupt_rejected`` (NIS
        gate), ``zupt_forced`` (applied ungated after repeated rejections),
        ``imu_dropouts`` (NaN IMU samples held from the last good one),
        ``imu_spikes`` (isolated spikes found by the ``spike_gyro`` /
        ``spike_accel`` test of :class:`FilterConfig`, held like dropouts),
        ``imu_saturated`` (samples with a gyro or accelerometer component at
        the rails of ``full_scale_gyro`` / ``full_scale_accel``; integrated as measured),
        ``static_skipped`` (samples flagged static but held or saturated:
        left out of the ZUPT/ZARU average),
        ``baro_aidings`` / ``mag_aidings`` (samples used while walking),
        ``mag_gated`` (magnetometer samples rejected as disturbed or spiky),
        ``baro_rejected`` (barometer samples beyond ``baro_gate`` of the
        tracker: spikes, skipped), ``baro_reinit`` (tracker re-initialised on
        the measurement after ``max_rejected`` consecutive rejections),
        ``time_jumps`` (intervals above ``FilterConfig.max_dt``: the INS held over them),
        ``imu_freefall`` (samples with ``|f| < freefall_accel`` for at least ``freefall_time``: accelerometer
        held from the last good sample).
    flags : ndarray of uint8, shape (N,)
        Per IMU sample, a bit set of what the filter did with it:
        ``FLAG_DROPOUT`` (1, NaN, held), ``FLAG_SPIKE`` (2, spike, held),
        ``FLAG_SATURATED`` (4, at the rails), ``FLAG_STATIC_SKIPPED`` (8,
        flagged static but left out of ZUPT/ZARU), ``FLAG_TIME_JUMP`` (16,
        its interval ``dt[k] > max_dt``: not integrated), ``FLAG_FREEFALL``
        (32, accelerometer held: free fall or a dead sensor). The counters
        are the sums of these bits.
    P : ndarray, shape (15, 15)
        Error covariance after the last sample (symmetric positive definite).
    faults : FaultReport
        The fault counters in navlib's one vocabulary (:data:`FAULT_KEYS`), with the per-sample
        flags of the flagged kinds, e.g. ``result.faults.flags["imu", "nan"]``,
        ``result.faults["clock", "jump"]``, ``result.faults.flags["accel", "freefall"]``.
    """
    nav: trajectory.Trajectory
    accel_bias: np.ndarray
    gyro_bias: np.ndarray
    P_diag: np.ndarray
    counts: dict
    flags: np.ndarray
    P: np.ndarray
    faults: robust.FaultReport = field(default_factory=robust.FaultReport)

    @property
    def updated(self) -> bool:
        """False when no ZUPT/ZARU update was ever applied (no static interval)."""
        return self.counts["zupt_updates"] > 0


def _field_reference(B_n):
    if B_n is None:
        return np.array([0.0, 0.0])
    D, I, F = earth.field_angles(as_array(B_n, "B_n", shape=(3,)), deg=False)
    return np.array([float(F), float(I)])


@renamed_keywords(field_n="B_n")
def run_filter(w_ib_b, f_b=None, dt=None, lla0=None, vel0=None, q0=None, static=None, *, h_baro=None, m_b=None,
               declination: float = 0.0, B_n=None, walk_aiding: str = "reset", zupt: bool = True,
               accel_bias0=(0.0, 0.0, 0.0), gyro_bias0=(0.0, 0.0, 0.0), config: FilterConfig = FilterConfig(),
               t0: float = 0.0, ellipsoid: earth.Ellipsoid = earth.WGS84, full_scale_gyro: float | None = None,
               full_scale_accel: float | None = None, full_scale=None) -> FilterResult:
    """The paper's system: strapdown INS + ZUPT/ZARU Kalman filter + walking aids.

    Parameters
    ----------
    w_ib_b, f_b : array_like, shape (N, 3)
        Gyro (rad/s) and accelerometer (m/s^2) samples (or an :class:`navlib.imu.ImuSamples` as
        ``w_ib_b``, supplying ``f_b``, ``dt`` and the ranges); NaN samples
        (dropouts) are replaced by the last good one and counted
        (``imu_dropouts``); they are never used for ZUPT/ZARU
        (``static_skipped``). The first sample must be valid.
    dt : float or array_like, shape (N,)
        IMU sample interval (s), or per-sample intervals (irregular
        sampling; ``dt[k]`` covered by sample k, e.g.
        :func:`navlib.timing.intervals`). Logs with repeated or out-of-order
        timestamps go through :func:`navlib.timing.sanitize` first. The
        static update rate uses the median interval. An interval above
        ``config.max_dt`` is a time jump: not integrated (the INS is held),
        counted and flagged (``FLAG_TIME_JUMP``).
    lla0, vel0 : array_like, shape (3,)
        Initial position (rad, rad, m) and ENU velocity (m/s).
    q0 : array_like, shape (4,)
        Initial attitude quaternion (e.g. from :func:`navlib.alignment.level` and
        :func:`magnetic_heading`).
    static : array_like of bool, shape (N,)
        Static flags, e.g. from :func:`navlib.filters.zupt.detect_static`.
    h_baro : array_like, shape (N,), optional
        Barometric height (m, same datum as ``lla0[2]``), NaN between samples.
    m_b : array_like, shape (N, 3), optional
        Magnetometer (uT), NaN between samples.
    declination : float
        Magnetic declination (rad, east positive).
    B_n : array_like, shape (3,), optional
        Reference field in ENU (uT) for the magnetic disturbance gate (the name used across navlib,
        e.g. :func:`navlib.earth.magnetic_field`).
    walk_aiding : {"reset", "filter", "none"}
        While walking: the paper's direct resets of height and heading,
        the same as Kalman measurements, or nothing.
    zupt : bool
        Apply ZUPT/ZARU updates while static (False: free INS + walking aids).
    accel_bias0, gyro_bias0 : array_like, shape (3,)
        Initial bias estimates (m/s^2, rad/s).
    config : FilterConfig
    t0 : float
        Time of the first epoch (s).
    full_scale_gyro, full_scale_accel : float, optional
        Device ranges (rad/s, m/s^2), e.g. the ``full_scale`` of the triads of
        :func:`navlib.sensors.imu_model`. A sample with any component at or
        beyond the range is at the rails: counted (``imu_saturated``),
        integrated as measured (the best estimate available), but never used
        for ZUPT/ZARU (``static_skipped``). Default: no range (nothing is
        treated as clipped).
    full_scale : (float, float), optional
        Deprecated: ``(full_scale_gyro, full_scale_accel)`` as one pair (warns; removed in navlib 0.3).
        ``field_n`` is the deprecated spelling of ``B_n`` (warns likewise).
    Returns
    -------
    FilterResult
        A ``RuntimeWarning`` is issued when ``zupt`` is on and no static
        update was ever applied (check ``result.updated``).
    """
    w_ib_b, f_b, dt, full_scale_gyro, full_scale_accel = unpack(w_ib_b, f_b, dt, full_scale_gyro, full_scale_accel)
    w, f = imu_samples(w_ib_b, f_b, shape=(None, 3))
    n = w.shape[0]
    if not (np.isfinite(w[0]).all() and np.isfinite(f[0]).all()):
        raise ValueError("w_ib_b, f_b: expected a valid first sample (dropouts are held from the last good one)")
    dts = intervals(dt, n)
    lla0 = as_array(lla0, "lla0", shape=(3,))
    if abs(lla0[0]) > np.deg2rad(89.9):
        raise ValueError("lla0: expected |lat| <= 89.9 deg (ENU mechanisation)")
    vel0 = as_array(vel0, "vel0", shape=(3,))
    q0 = as_quat(as_array(q0, "q0", shape=(4,)), "q0")
    s = booleans(static, "static", shape=(n,))
    hb = np.full(n, np.nan) if h_baro is None else as_array(h_baro, "h_baro", allow_nan=True, shape=(n,))
    mb = np.full((n, 3), np.nan) if m_b is None else as_array(m_b, "m_b", allow_nan=True, shape=(n, 3))
    if np.any(np.all(mb == 0, axis=-1)):
        raise ValueError("m_b: expected non-zero magnetometer vectors (NaN marks a missing sample)")
    choice(walk_aiding, "walk_aiding", tuple(_AIDING))
    instance(config, "config", FilterConfig, "a FilterConfig")
    ellipsoid_(ellipsoid)
    b0 = np.concatenate([as_array(accel_bias0, "accel_bias0", shape=(3,)),
                         as_array(gyro_bias0, "gyro_bias0", shape=(3,))])
    gyro_fs, accel_fs = range_limit(full_scale_gyro, "full_scale_gyro"), range_limit(full_scale_accel, "full_scale_accel")
    if full_scale is not None:                    # deprecated pair, removed in navlib 0.3
        warnings.warn("run_filter(full_scale=(gyro, accel)) is deprecated; use full_scale_gyro=, full_scale_accel=",
                      DeprecationWarning, stacklevel=2)
        fs = as_array(full_scale, "full_scale", finite=False, shape=(2,))      # (gyro rad/s, accel m/s^2)
        fs = [range_limit(v, "full_scale") for v in fs]
        if full_scale_gyro is not None or full_scale_accel is not None:
            raise ValueError("full_scale: give the ranges once, as full_scale_gyro and full_scale_accel")
        gyro_fs, accel_fs = fs
    field_ref = _field_reference(B_n)
    c = config
    if np.median(dts) > c.max_dt:
        raise ValueError(f"dt: expected a median interval below config.max_dt = {c.max_dt:g} s (longer intervals are "
                         f"time jumps, not integrated), got {np.median(dts):g} s")
    freefall = _freefall(f, dts, c.freefall_accel, c.freefall_time)
    if freefall[0]:
        raise ValueError(f"f_b: expected a valid first sample, got |f| = {np.linalg.norm(f[0]):.3g} m/s^2 "
                         f"< freefall_accel = {c.freefall_accel:g} (free fall is held from the last good one)")
    every = max(1, int(round(1.0 / (c.update_rate * float(np.median(dts))))))
    q_rate = np.concatenate([np.zeros(3), np.full(3, c.accel_noise ** 2), np.full(3, c.gyro_noise ** 2),
                             np.full(3, c.accel_bias_rw ** 2), np.full(3, c.gyro_bias_rw ** 2)])
    p0 = np.array([c.p0_pos] * 3 + [c.p0_vel] * 3 + [c.p0_tilt] * 2 + [c.p0_heading]
                  + [c.p0_accel_bias] * 3 + [c.p0_gyro_bias] * 3) ** 2
    samples = _Samples(np.ascontiguousarray(w), np.ascontiguousarray(f), dts, s, np.ascontiguousarray(hb),
                       np.ascontiguousarray(mb), freefall)
    setup = _Setup(lla0, vel0, np.ascontiguousarray(q0), b0, scalar(declination, "declination"), field_ref,
                   flag(zupt, "zupt"), _AIDING[walk_aiding], every, q_rate, p0, float(c.sigma_zupt ** 2),
                   float(c.sigma_zaru ** 2), float(c.sigma_baro ** 2), float(c.sigma_heading ** 2),
                   float(c.baro_alpha), float(c.baro_beta), float(c.gate), int(c.max_rejected), float(c.mag_field_tol),
                   float(c.mag_dip_tol), gyro_fs, accel_fs, float(c.baro_gate), float(c.spike_gyro),
                   float(c.spike_accel), float(c.hold_gyro_sigma), float(c.hold_accel_sigma), float(c.max_dt),
                   earth_constants(ellipsoid))
    out = _filter_kernel(samples, setup)
    lla, vel, q, b, p_diag, counts, flags, P = out
    t0 = scalar(t0, "t0")
    time = t0 + (dts[0] * np.arange(n + 1) if np.all(dts == dts[0]) else np.concatenate([[0.0], np.cumsum(dts)]))
    named = dict(zip(_COUNTERS, (int(x) for x in counts), strict=True))
    faults = robust.FaultReport({key: named[name] for name, key in FAULT_KEYS.items()},
                                {key: (flags & bit) > 0 for bit, key in _FLAG_KEYS.items()})
    result = FilterResult(trajectory.Trajectory(time, lla, vel, q), b[:, :3], b[:, 3:], p_diag, named, flags, P, faults)
    if zupt and not result.updated:
        warnings.warn("run_filter: no ZUPT/ZARU update was applied (no static interval detected); "
                      "the output is a free INS with walking aids only", RuntimeWarning, stacklevel=2)
    return result
