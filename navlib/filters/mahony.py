r"""Mahony's nonlinear complementary filter on SO(3) with a PI correction (gyro + accelerometer + heading reference).

Mahony, Hamel, Pflimlin (2008), "Nonlinear complementary filters on the special orthogonal
group", IEEE T-AC 53(5), in the explicit form used by Zhang et al. 2023 (paper 003,
:mod:`navlib.papers.mimu_mag_rtk`), whose equation numbers are quoted:

* Eqs. (12)-(14): error ``e = a_meas x a_est + m_meas x m_est`` (measured x estimated), with
  ``m_est = C_nb [0, |h_xy|, h_z]`` and ``h = C_bn m_meas`` (:func:`navlib.filters.observations.pi_error`).
  The magnetometer term is mostly a heading correction, but not only: in the navigation frame it is
  ``h x [0, |h_xy|, h_z] = [h_z (h_y - |h_xy|), -h_x h_z, h_x |h_xy|]``, whose horizontal part grows with
  the vertical field times the heading error. A large heading error -- a magnetic disturbance -- therefore
  also tilts the estimate (13 deg on the real recording of notebook 06, where x-io's Fusion, which
  corrects heading only, stays within 0.2 deg); the field-norm and dip gate (``AttitudeGates(mag=MagGate())``) is the defence;
* Eq. (15): :math:`\omega = \omega_m + k_P e + k_I \sum e\, \Delta t` with :math:`k_P` in rad/s and
  :math:`k_I` in rad/s^2 (the full cross product, not MahonyAHRS.c's half error "twoKp");
* Eq. (17): first-order update :math:`q \leftarrow \mathrm{normalise}\big(q + \tfrac{\Delta t}{2}\, q \otimes [0, \omega]\big)`.

The heading reference is a magnetometer, a dual-antenna RTK heading, or none (gyro + accelerometer:
heading free). The samples arrive screened (:func:`navlib.robust.screen`, here or once by the caller) and are gated
in the observation step (:mod:`navlib.filters.observations`, which also says what is done with bad samples), so the
loop holds only the equations. Compiled and allocation-free per sample; leading axes of the inputs are Monte Carlo
trials, run in parallel.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from .._kernels import quat_mult_t
from .._typing import Quat, Vec3, Vec3Series
from ..imu import ImuSamples
from ..robust import Screened
from .observations import (
    AttitudeGates,
    AttitudeResult,
    RtkHeading,
    attitude_result,
    dcm_elements,
    integral_gain,
    jump_step,
    learning,
    observe,
    pack,
    pi_error,
    relock,
    rtk_north,
    run_trials,
)

__all__ = ["mahony"]


@njit(cache=True, nogil=True)
def _kernel(t0, t1, inp, kp, ki, q_out, bias_out, counts):
    """Trials t0 to t1 - 1 of ``inp`` (:class:`~navlib.filters.observations.AttitudeInputs`)."""
    for t in range(t0, t1):
        _trial(t, inp, kp, ki, q_out, bias_out, counts)


@njit(cache=True, error_model="numpy")
def _trial(t, inp, kp, ki, q_out, bias_out, counts):
    w, f, m, skip, gated, limits = inp.w, inp.f, inp.m, inp.skip, inp.gated, inp.limits
    dts, jump, fresh, long_hold, settle = inp.dts, inp.jump, inp.fresh, inp.long_hold, inp.settle
    q0, q1, q2, q3 = inp.q_init[t, 0], inp.q_init[t, 1], inp.q_init[t, 2], inp.q_init[t, 3]
    ix = iy = iz = 0.0
    rtk = np.array([0.0, 1.0, 0.0, np.inf, 0.0, 0.0])
    held, since, checking = 0.0, np.inf, False  # learning's state; relock's check under way (its state: check)
    check = np.zeros(10)
    for k in range(w.shape[1]):
        dt, gx, gy, gz = dts[k], w[t, k, 0], w[t, k, 1], w[t, k, 2]
        if jump[k]:  # clock jump: one typical interval, then check
            dt, since, checking = jump_step(inp, check, rtk), 0.0, True
        sm = skip[1, t, k]
        mx, my, mz = (m[t, k, 0], m[t, k, 1], m[t, k, 2]) if not sm else (0.0, 0.0, 0.0)  # (none where skipped)
        ax, ay, az, mx, my, mz, gate_a, gate_m = observe(
            f[t, k, 0], f[t, k, 1], f[t, k, 2], mx, my, mz, skip[0, t, k], sm, limits
        )
        if gate_a:  # unit vectors above, NaN where skipped; record the gates' drops
            gated[gate_a - 1, t, k] = True
        if gate_m:
            gated[gate_m + 1, t, k] = True
        C = dcm_elements(q0, q1, q2, q3)
        hx, hy, hz = rtk_north(inp, t, k, C, dt, rtk, counts) if inp.use_rtk else (mx, my, mz)
        ex, ey, ez = pi_error(C, ax, ay, az, hx, hy, hz)  # Eqs. (12)-(14)
        learn, held, since = learning(fresh[t, k], dt, held, since, long_hold, settle)
        if learn:  # Eq. (15), unless settling after a fault
            ix += ex * dt
            iy += ey * dt
            iz += ez * dt
        wx, wy, wz = gx + kp * ex + ki * ix, gy + kp * ey + ki * iy, gz + kp * ez + ki * iz
        d0, d1, d2, d3 = quat_mult_t(q0, q1, q2, q3, 0.0, wx, wy, wz)  # Eq. (17): q + dt/2 q (x) [0, w]
        q0, q1, q2, q3 = q0 + 0.5 * dt * d0, q1 + 0.5 * dt * d1, q2 + 0.5 * dt * d2, q3 + 0.5 * dt * d3
        s = 1.0 / np.sqrt(q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3)
        q0, q1, q2, q3 = q0 * s, q1 * s, q2 * s, q3 * s
        if checking:  # after a clock jump: re-initialised only if the state is lost
            q0, q1, q2, q3, _, since = relock(inp, t, k, q0, q1, q2, q3, (ax, ay, az, mx, my, mz), check, rtk, since)
            checking = check[0] != 0.0
        q_out[t, k, 0], q_out[t, k, 1], q_out[t, k, 2], q_out[t, k, 3] = q0, q1, q2, q3
    bias_out[t, 0], bias_out[t, 1], bias_out[t, 2] = -ki * ix, -ki * iy, -ki * iz


def mahony(
    imu: ImuSamples | Screened,
    q0: Quat,
    *,
    m_b: Vec3Series | None = None,
    rtk: RtkHeading | None = None,
    B_n: Vec3 | None = None,
    kp: float = 1.0,
    ki: float | None = None,
    gates: AttitudeGates = AttitudeGates(),
) -> AttitudeResult:
    r"""Mahony PI complementary filter (Eqs. 9-15 of Zhang et al. 2023), per sample:

    .. math::

        e &= a \times \hat a + m \times \hat m \\
        \omega &= \omega_m + k_P e + k_I \textstyle\sum e\, \Delta t \\
        q &\leftarrow \mathrm{normalise}\big(q + \tfrac{\Delta t}{2}\, q \otimes [0, \omega]\big).

    Identical to ``ahrs.filters.Mahony.updateMARG`` (AHRS 0.4.0, same frames and first-order update)
    except that ahrs skips samples whose gyro norm is exactly 0. With per-sample ``dt`` each step uses
    its own interval (integral term and quaternion update).

    Parameters
    ----------
    imu : ImuSamples or Screened
        Gyro (rad/s) and accelerometer (m/s^2) samples, shape (..., N, 3) (leading axes: trials), their
        intervals and limits, screened once here (:func:`navlib.robust.screen`); or the result of
        ``robust.screen(imu, m_b)``, used as it is (screen once, filter many:
        :func:`navlib.filters.observations.screened`). Earth rate is neglected, as in the paper.
    q0 : array_like, shape (4,) or (..., 4)
        Attitude before the first sample, e.g. :func:`navlib.alignment.initial_attitude`.
    m_b : array_like, shape (..., N, 3), optional
        Magnetometer samples (uT); with screened ``imu``, given to the screen instead. With neither ``m_b`` nor
        ``rtk`` the filter runs on gyro and accelerometer alone: tilt is corrected, the heading is free (it starts at
        ``q0``'s heading and drifts with the gyro bias about the vertical, which the accelerometer cannot observe).
    rtk : RtkHeading, optional
        Instead of ``m_b``: dual-antenna heading at the IMU rate, used as a north pseudo-vector (mode (a)
        of the paper's Fig. 4).
    B_n : array_like, shape (3,), optional
        Local field (uT, ENU); needed by a magnetometer gate.
    kp : float
        Proportional gain of Eq. (15) (rad/s).
    ki : float, optional
        Integral gain of Eq. (15) (rad/s^2); ``ki = 0`` disables gyro-bias estimation. None (default):
        0.02 with a heading reference (``m_b`` or ``rtk``), 0 without one, where the integral would learn the
        linear accelerations of the motion as bias (:func:`navlib.filters.observations.integral_gain`).
    gates : AttitudeGates
        Accelerometer-norm and magnetometer gates (default: none).

    Returns
    -------
    AttitudeResult
        With ``faults``: what was held, skipped, gated or re-initialised
        (:mod:`navlib.filters.observations`).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude, imu, trajectory
    >>> from navlib.filters import mahony
    >>> traj = trajectory.static(3.0, 0.01, [0.6, 0.2, 50.0], np.deg2rad([30.0, 0.0, 0.0]))
    >>> samples = imu.ImuSamples(*trajectory.ideal_imu(traj), 0.01)
    >>> q0 = attitude.euler_to_quat(np.deg2rad([30.0, 0.0, 5.0]))    # starts with a 5 deg roll error
    >>> res = mahony.mahony(samples, q0, kp=2.0)
    >>> np.round(np.rad2deg(attitude.quat_to_euler(res.q_bn[[0, -1]])), 1) + 0.0   # the accelerometer levels it
    array([[30. ,  0. ,  4.9],
           [30. ,  0. ,  0. ]])
    """
    lead, inp, found = pack(imu, q0, m_b, rtk, B_n, gates, kp)
    kp = float(kp)  # checked by pack
    ki = integral_gain(ki, inp.use_mag or inp.use_rtk)
    T, N = inp.w.shape[:2]
    q_out, bias, counts = np.empty((T, N, 4)), np.empty((T, 3)), np.zeros((T, 4), dtype=np.int64)
    run_trials(_kernel, T, inp, kp, ki, q_out, bias, counts)
    return attitude_result(lead, inp, q_out, bias, counts, found)
