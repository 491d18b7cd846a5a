"""Attitude from gyro, accelerometer and magnetometer with inclination and heading corrected separately, the
accelerometer low-pass filtered in an almost inertial frame, and the gyro bias estimated at rest and in motion.

The design of Laidig & Seel (2023), "VQF: Highly accurate IMU orientation estimation with bias estimation and
magnetic disturbance rejection", *Information Fusion* 91:187-204, doi:10.1016/j.inffus.2022.10.014, written
here from the paper's description of the algorithm (the defaults are the paper's except two, see
:class:`InertialLowpassSettings`); no code of the authors' ``vqf`` package is used (notebook 07 runs that
package as a peer). The attitude is a product of three parts, ``q_bn = q_head (x) q_incl (x) q_gyr``:

1. *Strapdown* (``q_gyr``, body to an almost inertial frame I): ``q_gyr <- q_gyr (x) exp((w_ib_b - b) dt / 2)``.
2. *Inclination* (``q_incl``, I to an up-aligned frame E'): the specific force is rotated into I, where it is
   nearly constant whatever the body does, and low-pass filtered there (second-order Butterworth, time constant
   ``tau_acc``): translational accelerations average out without delaying the attitude. Each sample ``q_incl``
   is corrected by the whole rotation taking the filtered direction to up.
3. *Heading* (``q_head``, a rotation about up by ``delta``): the magnetometer in E' gives the heading offset
   ``atan2(m_E, m_N)``; ``delta`` follows it with gain ``1 - exp(-dt / tau_mag)``, so a field error can turn the
   estimate about the vertical only, never tilt it.

*Gyro bias* ``b`` is one three-state Kalman filter (random-walk model: the variance grows from
``bias_sigma_init**2`` by that amount every ``bias_forget_time``): at rest (gyro and accelerometer within
``rest_gyro`` and ``rest_accel`` of their low-pass values for ``rest_time``) it measures ``b`` directly as the
low-pass gyro; in motion, the inclination correction per second is the horizontal part of the bias error seen
through the (equally low-pass filtered) rotation matrix body to E', which makes the horizontal components
observable and leaves the vertical one to the rest phases. The estimate is clipped to ``+-bias_clip``.

*Magnetic disturbances*: the field's norm and dip angle (low-pass, ``mag_current_tau``) are compared with a
reference learnt while undisturbed (``mag_ref_tau``); outside ``mag_norm_tol`` or ``mag_dip_tol`` the sample is
rejected (``faults["mag", "rejected"]``, every sample flagged) for at most ``mag_max_rejection`` seconds in a
row, after which it corrects with the gain divided by ``mag_rejection_factor``; undisturbed time earns rejection
time back ``mag_rejection_factor`` times as fast. After a rejection the field must stay undisturbed for
``mag_settle_time`` before it is used again (navlib's addition). A steady new field (norm and dip
stable for ``mag_new_time`` while turning faster than ``mag_new_min_gyro``; ``mag_new_first_time`` for the
first field) becomes the reference. The first magnetometer samples set the heading at once (gain ``1/n``).

The initial attitude is automatic (first accelerometer and magnetometer samples); ``declination`` (rad, east
positive) turns the magnetic heading into a true one. Without ``m_b`` the heading is free (6D).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import njit

from .._kernels import quat_mult_t, quat_to_dcm_t, rotvec_to_quat_t
from .._typing import Vec3Series
from .._validate import Is, Positive, Real, boundary, fields_checked
from ..imu import ImuSamples
from ..robust import FaultReport, screen
from .observations import AttitudeResult, run_trials

__all__ = ["InertialLowpassSettings", "inertial_lowpass"]

_DEG = np.pi / 180


@dataclass(frozen=True)
class InertialLowpassSettings:
    """Settings of :func:`inertial_lowpass`. Times in s, rates in rad/s, angles in rad.

    The defaults are the paper's (Laidig & Seel 2023), except the two that are navlib's own:

    * ``bias_motion_scale`` multiplies the motion measurement's variance, ``bias_sigma_motion**2`` over one
      ``tau_acc`` (the correlation time of the low-pass inclination correction), per sample. 1 follows that
      noise model literally; on BROAD's tuning trials (notebook 07) the bias learnt in motion then leaks into
      the heading as the body turns, and 100 was the best of 10, 100, 1000 there;
    * ``mag_settle_time``: after a rejected magnetometer sample the field must be back within the tolerances
      for this long before it corrects the heading again (a field swinging through the reference norm while a
      magnet moves past would otherwise pass the test now and then; on BROAD trial 33 that cost 4.6 deg).

    Examples
    --------
    >>> from navlib.filters import inertial_lowpass
    >>> settings = inertial_lowpass.InertialLowpassSettings(tau_acc=1.0)   # trust the accelerometer more
    >>> settings.tau_acc, settings.tau_mag
    (1.0, 9.0)
    """

    tau_acc: Positive = 3.0
    tau_mag: Positive = 9.0
    bias_sigma_init: Positive = 0.5 * _DEG
    bias_forget_time: Positive = 100.0
    bias_clip: Positive = 2.0 * _DEG
    bias_sigma_motion: Positive = 0.1 * _DEG
    bias_sigma_rest: Positive = 0.03 * _DEG
    bias_motion_scale: Positive = 100.0
    rest_time: Positive = 1.5
    rest_tau: Positive = 0.5
    rest_gyro: Positive = 2.0 * _DEG
    rest_accel: Positive = 0.5
    mag_current_tau: Positive = 0.05
    mag_ref_tau: Positive = 20.0
    mag_norm_tol: Positive = 0.1
    mag_dip_tol: Positive = 10.0 * _DEG
    mag_new_time: Positive = 20.0
    mag_new_first_time: Positive = 5.0
    mag_new_min_gyro: Positive = 20.0 * _DEG
    mag_max_rejection: Positive = 60.0
    mag_rejection_factor: Positive = 2.0
    mag_settle_time: Positive = 1.0

    def __post_init__(self) -> None:
        fields_checked(self)


def _butter2(tau: float, dt: float) -> np.ndarray:
    """Second-order Butterworth low-pass ``[b0, b1, b2, a1, a2]`` (bilinear transform) of cut-off
    ``sqrt(2) / (2 pi tau)``, the paper's mapping of a time constant to a cut-off frequency."""
    k = np.tan(np.pi * np.sqrt(2) / (2 * np.pi * tau) * dt)
    n = 1.0 / (1.0 + np.sqrt(2) * k + k * k)
    b0 = k * k * n
    return np.array([b0, 2 * b0, b0, 2 * (k * k - 1) * n, (1 - np.sqrt(2) * k + k * k) * n])


@njit(cache=True, inline="always")
def _lowpass(c, x, s, j):
    """One step of the Butterworth ``c`` on input ``x``, state ``s[j]`` (2 values; NaN: start at ``x``)."""
    if np.isnan(s[j, 0]):
        s[j, 0], s[j, 1] = (1 - c[0]) * x, (c[2] - c[4]) * x  # the steady state of a constant x
    y = c[0] * x + s[j, 0]
    s[j, 0], s[j, 1] = c[1] * x - c[3] * y + s[j, 1], c[2] * x - c[4] * y
    return y


@njit(cache=True, inline="always")
def _rotate(q0, q1, q2, q3, x, y, z):
    """``q (x) v (x) q*``."""
    r0, r1, r2 = quat_to_dcm_t(q0, q1, q2, q3)
    return (r0[0] * x + r0[1] * y + r0[2] * z, r1[0] * x + r1[1] * y + r1[2] * z, r2[0] * x + r2[1] * y + r2[2] * z)


@njit(cache=True, inline="always")
def _unit(q):
    q0, q1, q2, q3 = q
    s = 1.0 / np.sqrt(q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3)
    return q0 * s, q1 * s, q2 * s, q3 * s


@njit(cache=True, nogil=True)
def _kernel(t0, t1, w, f, m, dts, p, coef, q_out, bias_out, flags):
    """Trials t0 to t1 - 1; ``coef`` (2, 5): the accelerometer's and the rest detector's low-pass filters;
    ``flags`` (2, T, N): magnetometer sample rejected, sample at rest."""
    for t in range(t0, t1):
        _trial(t, w, f, m, dts, p, coef[0], coef[1], q_out, bias_out, flags[0], flags[1])


@njit(cache=True)
def _trial(t, w, f, m, dts, p, c_acc, c_rest, q_out, bias_out, rejected, rest_out):
    (
        sig_init2,
        forget,
        clip,
        r_motion,
        r_rest,
        rest_time,
        rest_gyro2,
        rest_accel2,
        k_cur,
        k_ref,
        norm_tol,
        dip_tol,
        new_time,
        new_first,
        new_gyro,
        max_reject,
        factor,
        k_mag,
        settle,
        use_mag,
    ) = p
    g0, g1, g2, g3 = 1.0, 0.0, 0.0, 0.0  # q_gyr: body -> I
    i0, i1, i2, i3 = 1.0, 0.0, 0.0, 0.0  # q_incl: I -> E'
    delta, n_mag = 0.0, 0.0  # heading correction about up (rad), samples used
    b, e, r = np.zeros(3), np.zeros(3), np.zeros(3)  # bias estimate, innovation, measurement variances
    P, H, work = np.eye(3) * sig_init2, np.empty((3, 3)), np.empty((3, 3, 3))
    lp = np.full((3 + 9 + 3 + 6, 2), np.nan)  # filter states: a_I, R, R b, rest gyro + accel
    rest_for, aligned = 0.0, False
    w_lp = np.zeros(3)  # low-pass gyro: the bias at rest
    cur = np.full(2, np.nan)  # low-pass field norm, dip
    ref = np.array([0.0, 0.0, 0.0])  # reference norm, dip, known (1) or not (0)
    cand = np.array([np.nan, np.nan, 0.0])  # candidate norm, dip, time steady (s)
    reject_for = ok_for = 0.0
    rejected_before = False
    for k in range(w.shape[1]):
        dt = dts[k]
        # 1. strapdown with the bias removed
        r0, r1, r2, r3 = rotvec_to_quat_t((w[t, k, 0] - b[0]) * dt, (w[t, k, 1] - b[1]) * dt, (w[t, k, 2] - b[2]) * dt)
        g0, g1, g2, g3 = _unit(quat_mult_t(g0, g1, g2, g3, r0, r1, r2, r3))
        # rest detection on the raw samples against their low-pass values
        dev_w = dev_f = 0.0
        for j in range(3):
            w_lp[j] = _lowpass(c_rest, w[t, k, j], lp, 15 + j)
            dev_w += (w[t, k, j] - w_lp[j]) ** 2
            dev_f += (f[t, k, j] - _lowpass(c_rest, f[t, k, j], lp, 18 + j)) ** 2 if np.isfinite(f[t, k, j]) else 0.0
        rest_for = rest_for + dt if dev_w < rest_gyro2 and dev_f < rest_accel2 else 0.0
        rest = rest_for >= rest_time
        rest_out[t, k] = rest
        # 2. inclination: specific force low-pass filtered in I, then the whole correction to up
        cx = cy = 0.0
        if np.isfinite(f[t, k, 0]) and np.isfinite(f[t, k, 1]) and np.isfinite(f[t, k, 2]):
            ax, ay, az = _rotate(g0, g1, g2, g3, f[t, k, 0], f[t, k, 1], f[t, k, 2])
            ax, ay, az = _lowpass(c_acc, ax, lp, 0), _lowpass(c_acc, ay, lp, 1), _lowpass(c_acc, az, lp, 2)
            ex, ey, ez = _rotate(i0, i1, i2, i3, ax, ay, az)
            s = 1.0 / np.sqrt(ex * ex + ey * ey + ez * ez)
            ex, ey, ez = ex * s, ey * s, ez * s
            h = np.sqrt(0.5 * (ez + 1.0)) if ez > -1.0 + 1e-12 else 1e-6
            c0, c1, c2 = h, ey / (2 * h), -ex / (2 * h)  # rotates (ex, ey, ez) onto (0, 0, 1)
            i0, i1, i2, i3 = _unit(quat_mult_t(c0, c1, c2, 0.0, i0, i1, i2, i3))
            if aligned:  # (the first sample aligns: not a drift)
                cx, cy = 2 * c1 * c0, 2 * c2 * c0  # correction angle about E' x, y (rad)
            aligned = True
        # 3. gyro bias: Kalman filter, measured at rest or through the inclination correction in motion
        a0, a1, a2, a3 = quat_mult_t(i0, i1, i2, i3, g0, g1, g2, g3)
        R = quat_to_dcm_t(a0, a1, a2, a3)  # body -> E'
        for i in range(3):
            P[i, i] += sig_init2 * dt / forget
            e[i] = _lowpass(c_acc, R[i][0] * b[0] + R[i][1] * b[1] + R[i][2] * b[2], lp, 12 + i)  # low-pass R b
            for j in range(3):
                H[i, j] = _lowpass(c_acc, R[i][j], lp, 3 + 3 * i + j)  # low-pass R
        if rest:  # measured: the low-pass gyro
            for i in range(3):
                e[i] = w_lp[i] - b[i]
                r[i] = r_rest
                for j in range(3):
                    H[i, j] = 1.0 if i == j else 0.0
            _kalman(P, H, r, e, b, work)
        elif cx != 0.0 or cy != 0.0:  # the correction per second: -LP(R) (b - b_hat)
            e[0] += -cx / dt - (H[0, 0] * b[0] + H[0, 1] * b[1] + H[0, 2] * b[2])
            e[1] += -cy / dt - (H[1, 0] * b[0] + H[1, 1] * b[1] + H[1, 2] * b[2])
            e[2] = 0.0
            r[0], r[1], r[2] = r_motion, r_motion, 1e12 * r_motion  # no vertical measurement in motion
            _kalman(P, H, r, e, b, work)
        for j in range(3):
            b[j] = min(max(b[j], -clip), clip)
        # 4. heading from the magnetometer in E', with disturbance rejection
        if use_mag and np.isfinite(m[t, k, 0]) and np.isfinite(m[t, k, 1]) and np.isfinite(m[t, k, 2]):
            mx, my, mz = _rotate(a0, a1, a2, a3, m[t, k, 0], m[t, k, 1], m[t, k, 2])
            norm = np.sqrt(mx * mx + my * my + mz * mz)
            if norm > 0.0:
                dip = np.arcsin(mz / norm)
                if np.isnan(cur[0]):
                    cur[0], cur[1] = norm, dip
                cur[0] += k_cur * (norm - cur[0])
                cur[1] += k_cur * (dip - cur[1])
                # candidate field: how long has it been steady (while turning, once a reference exists)?
                if abs(cur[0] - cand[0]) < norm_tol * cand[0] and abs(cur[1] - cand[1]) < dip_tol:
                    turning = w[t, k, 0] ** 2 + w[t, k, 1] ** 2 + w[t, k, 2] ** 2 >= new_gyro * new_gyro
                    cand[2] += dt if (turning or ref[2] == 0.0) else 0.0
                    cand[0] += k_ref * (cur[0] - cand[0])
                    cand[1] += k_ref * (cur[1] - cand[1])
                else:
                    cand[0], cand[1], cand[2] = cur[0], cur[1], 0.0
                ok = ref[2] == 1.0 and abs(cur[0] - ref[0]) < norm_tol * ref[0] and abs(cur[1] - ref[1]) < dip_tol
                ok_for = ok_for + dt if ok else 0.0
                ok = ok and (ok_for >= settle or not rejected_before)  # after a rejection: undisturbed for settle s
                if not ok and cand[2] >= (new_time if ref[2] == 1.0 else new_first):
                    ref[0], ref[1], ref[2], ok = cand[0], cand[1], 1.0, True  # a new steady field
                gain = max(k_mag, 1.0 / (n_mag + 1.0))
                if ok:
                    ref[0] += k_ref * (cur[0] - ref[0])
                    ref[1] += k_ref * (cur[1] - ref[1])
                    reject_for = max(reject_for - dt * factor, 0.0)
                elif ref[2] == 1.0:
                    rejected_before = True
                    if reject_for < max_reject:
                        reject_for += dt
                        rejected[t, k] = True
                        gain = 0.0
                    else:
                        gain = k_mag / factor
                if gain > 0.0:
                    delta += gain * _wrap(np.arctan2(mx, my) - delta)
                    n_mag += 1.0
        h0, h3 = np.cos(0.5 * delta), np.sin(0.5 * delta)
        q_out[t, k, 0], q_out[t, k, 1], q_out[t, k, 2], q_out[t, k, 3] = quat_mult_t(h0, 0.0, 0.0, h3, a0, a1, a2, a3)
        bias_out[t, k, 0], bias_out[t, k, 1], bias_out[t, k, 2] = b[0], b[1], b[2]


@njit(cache=True)
def _kalman(P, H, r, e, b, work):
    """Kalman update of ``b`` (3) with covariance ``P`` from innovation ``e`` = z - H b, noise ``diag(r)``;
    in place, allocation-free (``work``: 3 scratch 3x3 matrices)."""
    PHt, S, K = work[0], work[1], work[2]
    for i in range(3):
        for j in range(3):
            PHt[i, j] = P[i, 0] * H[j, 0] + P[i, 1] * H[j, 1] + P[i, 2] * H[j, 2]
    for i in range(3):
        for j in range(3):
            S[i, j] = H[i, 0] * PHt[0, j] + H[i, 1] * PHt[1, j] + H[i, 2] * PHt[2, j] + (r[i] if i == j else 0.0)
    c00, c01, c02 = (
        S[1, 1] * S[2, 2] - S[1, 2] * S[2, 1],
        S[0, 2] * S[2, 1] - S[0, 1] * S[2, 2],
        S[0, 1] * S[1, 2] - S[0, 2] * S[1, 1],
    )
    c10, c11, c12 = (
        S[1, 2] * S[2, 0] - S[1, 0] * S[2, 2],
        S[0, 0] * S[2, 2] - S[0, 2] * S[2, 0],
        S[0, 2] * S[1, 0] - S[0, 0] * S[1, 2],
    )
    c20, c21, c22 = (
        S[1, 0] * S[2, 1] - S[1, 1] * S[2, 0],
        S[0, 1] * S[2, 0] - S[0, 0] * S[2, 1],
        S[0, 0] * S[1, 1] - S[0, 1] * S[1, 0],
    )
    d = 1.0 / (S[0, 0] * c00 + S[0, 1] * c10 + S[0, 2] * c20)
    S[0, 0], S[0, 1], S[0, 2], S[1, 0], S[1, 1], S[1, 2], S[2, 0], S[2, 1], S[2, 2] = (
        c00 * d,
        c01 * d,
        c02 * d,
        c10 * d,
        c11 * d,
        c12 * d,
        c20 * d,
        c21 * d,
        c22 * d,
    )  # S^-1
    for i in range(3):
        for j in range(3):
            K[i, j] = PHt[i, 0] * S[0, j] + PHt[i, 1] * S[1, j] + PHt[i, 2] * S[2, j]
    for i in range(3):
        b[i] += K[i, 0] * e[0] + K[i, 1] * e[1] + K[i, 2] * e[2]
    for i in range(3):  # P <- P - K (H P) = P - K PHt^T
        for j in range(3):
            S[i, j] = P[i, j] - (K[i, 0] * PHt[j, 0] + K[i, 1] * PHt[j, 1] + K[i, 2] * PHt[j, 2])
    for i in range(3):
        for j in range(3):
            P[i, j] = 0.5 * (S[i, j] + S[j, i])


@njit(cache=True, inline="always")
def _wrap(a):
    return (a + np.pi) % (2 * np.pi) - np.pi


@boundary
def inertial_lowpass(
    imu: ImuSamples,
    m_b: Vec3Series | None = None,
    *,
    declination: Real = 0.0,
    settings: Is[InertialLowpassSettings] = InertialLowpassSettings(),
) -> AttitudeResult:
    """Attitude of every sample (module docstring), causal, with automatic initial attitude.

    Parameters
    ----------
    imu : ImuSamples
        Gyro (rad/s) and specific force (m/s^2), shape (..., N, 3) (leading axes: trials); screened once
        (:func:`navlib.robust.screen`): unusable gyro samples are held, unusable accelerometer samples skipped.
    m_b : array_like, shape (..., N, 3), optional
        Magnetometer (uT); NaN marks a missing sample. None: 6D, the heading is free (starts at 0).
    declination : float
        Magnetic declination (rad, east positive): the output's north is true north. Needs ``m_b``.
    settings : InertialLowpassSettings

    Returns
    -------
    AttitudeResult
        ``q_bn`` (..., N, 4); ``gyro_bias`` the final estimate (..., 3); ``faults``: the screen's, plus
        ``("mag", "rejected")`` for every magnetometer sample rejected as disturbed and ``("imu", "rest")``
        flags (not counted as faults) of the samples detected at rest.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude, imu, trajectory
    >>> from navlib.filters import inertial_lowpass
    >>> traj = trajectory.static(2.0, 0.01, [0.6, 0.2, 50.0], np.deg2rad([0.0, 5.0, -3.0]))
    >>> samples = imu.ImuSamples(*trajectory.ideal_imu(traj), 0.01)
    >>> res = inertial_lowpass.inertial_lowpass(samples)              # initial attitude found from the samples
    >>> np.round(np.rad2deg(attitude.quat_to_euler(res.q_bn[-1]))[1:], 2)   # pitch, roll (deg)
    array([ 5., -3.])
    """
    if declination != 0.0 and m_b is None:
        raise ValueError("declination: without m_b the heading has no north to correct")
    s = screen(imu, m_b)
    lead, N = imu.w_ib_b.shape[:-2], imu.n
    T = int(np.prod(lead))
    w = np.ascontiguousarray(s.w_ib_b.reshape(T, N, 3))
    flags = s.faults.flags
    skip_f = (flags["accel", "saturated"] | flags["accel", "freefall"] | flags["accel", "spike"]).reshape(T, N)
    f = np.where(skip_f[..., None], np.nan, imu.f_b.reshape(T, N, 3))
    use_mag = m_b is not None
    if s.m_b is not None:  # use_mag: screen returned the checked m_b
        m = np.where(flags["mag", "saturated"].reshape(T, N)[..., None], np.nan, s.m_b.reshape(T, N, 3))
    else:
        m = np.zeros((T, N, 3))
    dt = float(s.typical_dt)
    st = settings
    p = (
        st.bias_sigma_init**2,
        st.bias_forget_time,
        st.bias_clip,
        st.bias_sigma_motion**2 * st.bias_motion_scale * st.tau_acc / dt,
        st.bias_sigma_rest**2 * st.rest_time / dt,
        st.rest_time,
        st.rest_gyro**2,
        st.rest_accel**2,
        1 - np.exp(-dt / st.mag_current_tau),
        1 - np.exp(-dt / st.mag_ref_tau),
        st.mag_norm_tol,
        st.mag_dip_tol,
        st.mag_new_time,
        st.mag_new_first_time,
        st.mag_new_min_gyro,
        st.mag_max_rejection,
        st.mag_rejection_factor,
        1 - np.exp(-dt / st.tau_mag),
        st.mag_settle_time,
        use_mag,
    )
    q_out, bias = np.empty((T, N, 4)), np.empty((T, N, 3))
    flags_out = np.zeros((2, T, N), dtype=bool)
    run_trials(
        _kernel,
        T,
        w,
        np.ascontiguousarray(f),
        np.ascontiguousarray(m),
        s.dt,
        p,
        np.stack([_butter2(st.tau_acc, dt), _butter2(st.rest_tau, dt)]),
        q_out,
        bias,
        flags_out,
    )
    rejected, rest = flags_out
    if declination != 0.0:
        q_out = np.stack(quat_mult_t(np.cos(declination / 2), 0.0, 0.0, -np.sin(declination / 2), *np.moveaxis(q_out, -1, 0)), -1)
    found = dict(s.faults.flags)
    counts = dict(s.faults.counts)
    if use_mag:
        found["mag", "rejected"] = rejected.reshape(lead + (N,))
        counts["mag", "rejected"] = found["mag", "rejected"].sum(-1)
    found["imu", "rest"] = rest.reshape(lead + (N,))
    return AttitudeResult(q_out.reshape(lead + (N, 4)), bias[:, -1].reshape(lead + (3,)), FaultReport(counts, found))
