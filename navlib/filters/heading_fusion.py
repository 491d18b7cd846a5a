"""Heading fusion: a magnetic heading calibrated by dual-antenna RTK heading, carried through RTK outages.

The rule reconstructed for Sec. 2.5 of Zhang et al. 2023 (paper 003, :mod:`navlib.papers.mimu_mag_rtk`;
the paper gives no rule, errata E003-15, E003-16): while RTK is valid the offset
``delta = wrap(H_rtk - H_mag)`` is smoothed with ``delta += alpha wrap(delta_k - delta)`` per epoch
and the output is the RTK heading (carried between epochs by the magnetic heading's increments);
during outages the output is ``H_mag + delta`` with delta held. Validity is a flag; the value of an
invalid epoch (the paper's 0) is never used. RTK epochs are gated against the predicted heading with
re-acquisition (:func:`navlib.filters.observations.rtk_gate`), so 180 deg ambiguity flips are never
fused. :func:`rtk_at_imu_rate` places receiver epochs on the IMU time axis.

Clock jumps (an interval ``dt > max_dt``, by default ``imu.JUMP_FACTOR`` = 10 median intervals, the
rule of the attitude filters; counted ``("clock", "jump")`` and flagged): the last RTK epoch is stale
(the time since it is unknown), so its carried heading is dropped and the output is ``H_mag + delta``
until the next used epoch; the gate's run of rejections restarts; the offset ``delta`` is kept and goes
on being smoothed. Kept, not re-initialised from the next epoch, because delta is a calibration (the
declination plus the magnetic heading's slowly varying error) that a gap in time does not change, while
the magnetic heading itself may step after the jump: over a real gap the attitude filter upstream
re-initialises once a quasi-static window shows its state lost (:func:`navlib.filters.observations.relock`),
and a delta restarted from the first epoch after the jump carries such a transient into the next outage
(measured when the filters re-initialised from the jump's one sample, -4 to +7 deg off the run without the
jump in tests/faults/test_faults_ahrs.py: in an outage 30 s after the jump the RMS heading error was 2.6-2.9x
that of the run without the jump with delta restarted, 1.1-1.2x with delta kept). A real change of the
offset is still taken through the gate's re-acquisition.

Magnetic steps: with a gate, a change of the magnetic heading's increment from one sample to the next larger
than the gate (a step no motion makes: a magnetic disturbance switching on or off, a re-initialisation upstream) is
not carried to the RTK heading between epochs (counted ``("mag", "outlier")``); otherwise the carried heading would
take the step and the gate would reject the correct RTK epochs after it until ``confirm`` of them re-acquire
(tools/fault_matrix.py: a 30 deg step for 2 s cost 8-9 deg RMS with the gate, 0 without it).

Stuck sensors: the fusion takes no gyro samples (nothing to check here); a stuck gyro is found
upstream, by the screening of the attitude filter that produced ``heading_mag``, and the RTK heading is
checked by the gate.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import njit

from .._kernels import wrap_pi
from .._typing import Angles, Array, ArrayLike, Interval, Times
from .._validate import (
    Count,
    Fraction,
    Is,
    as_array,
    booleans,
    boundary,
    kernel_array,
    last_axis,
    same_shape,
    sample_intervals,
    time_axis,
)
from ..imu import SensorLimits
from ..robust import FaultReport
from .observations import RtkHeading, rtk_gate

__all__ = ["fuse_rtk_heading", "rtk_at_imu_rate", "FusionResult"]

_FAULTS = (("heading", "nan"), ("heading", "outlier"), ("heading", "reacquired"), ("mag", "outlier"))
"""What the kernel counts, in this order: the same keys as the attitude filters' RTK counts."""


@dataclass(frozen=True)
class FusionResult:
    """Output of :func:`fuse_rtk_heading`.

    Attributes
    ----------
    heading : ndarray, shape (..., N)
        Fused heading (rad, [0, 2 pi)).
    delta : ndarray, shape (..., N)
        Offset estimate ``H_rtk - H_mag`` (rad); NaN before the first used RTK epoch.
    faults : FaultReport
        Per valid epoch ``("heading", "nan")`` (NaN value), ``("heading", "outlier")`` (outside the gate,
        not fused), ``("heading", "reacquired")`` (used after ``confirm`` agreeing rejections); with a gate
        ``("mag", "outlier")`` (magnetic steps not carried, module docstring); counts of shape (...); and
        ``("clock", "jump")`` flagged per sample, shape (..., N).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.filters import heading_fusion, observations
    >>> rtk = observations.RtkHeading(np.full(10, 0.5), np.arange(10) % 5 == 0)    # an RTK epoch every 5th sample
    >>> out = heading_fusion.fuse_rtk_heading(np.full(10, 0.3), rtk, 0.01)
    >>> np.round(out.heading, 3), round(float(out.delta[-1]), 3)   # output RTK heading; delta = H_rtk - H_mag
    (array([0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5]), 0.2)
    """

    heading: np.ndarray
    delta: np.ndarray
    faults: FaultReport


@njit(cache=True)
def _fuse_kernel(h_mag, h_rtk, ok, dts, jump, alpha, rtk_par, out, delta_out, counts):
    T, N = h_mag.shape
    hold, gate, confirm = rtk_par[0], rtk_par[1], rtk_par[2]
    state = np.zeros(2)
    for t in range(T):
        delta, age, anchor_rtk, anchor_mag = np.nan, np.inf, 0.0, 0.0
        step, skipped = 0.0, 0.0  # steady magnetic increment; steps left out of the carry
        state[0] = 0.0
        for k in range(N):
            if jump[k]:  # clock jump: nothing carried over it, the gate restarts
                age, state[0] = np.inf, 0.0
            elif k > 0:
                inc = wrap_pi(h_mag[t, k] - h_mag[t, k - 1])
                if abs(inc - step) > gate:  # a magnetic step no motion makes: not carried
                    skipped += inc - step
                    counts[t, 3] += 1
                else:
                    step = inc
            age += dts[k]
            if ok[t, k]:  # RTK epoch flagged valid
                hk = h_rtk[t, k]
                if np.isnan(hk):  # valid flag without a value: dropout
                    counts[t, 0] += 1
                    code = 1
                else:
                    if age <= hold:  # predicted heading: carried RTK, held delta, or none
                        pred = anchor_rtk + wrap_pi(h_mag[t, k] - anchor_mag) - skipped
                    elif not np.isnan(delta):
                        pred = h_mag[t, k] + delta
                    else:
                        pred = hk  # first epoch: nothing to check it against
                    code = rtk_gate(hk, pred, gate, confirm, state)
                    if code == 1:
                        counts[t, 1] += 1
                    elif code == 2:
                        counts[t, 2] += 1
                if code != 1:
                    d = wrap_pi(hk - h_mag[t, k])
                    delta = d if (np.isnan(delta) or code == 2) else delta + alpha * wrap_pi(d - delta)
                    anchor_rtk, anchor_mag, age, skipped = hk, h_mag[t, k], 0.0, 0.0
            if age <= hold:  # output the RTK heading, carried between epochs
                out[t, k] = anchor_rtk + wrap_pi(h_mag[t, k] - anchor_mag) - skipped
            elif not np.isnan(delta):  # outage: hold delta
                out[t, k] = h_mag[t, k] + delta
            else:  # no RTK yet: uncalibrated magnetic heading
                out[t, k] = h_mag[t, k]
            out[t, k] = out[t, k] % (2 * np.pi)
            delta_out[t, k] = delta


@boundary
def fuse_rtk_heading(
    heading_mag: Angles, rtk: Is[RtkHeading], dt: Interval, alpha: Fraction = 0.01, max_dt: float | None = None
) -> FusionResult:
    """Fuse the magnetic heading with dual-antenna RTK heading (the rule of the module docstring).

    Parameters
    ----------
    heading_mag : array_like, shape (..., N)
        Heading of the MIMU + magnetometer filter (rad, magnetic north).
    rtk : RtkHeading
        RTK heading at the IMU rate, its validity flags (an invalid epoch's value, the paper's 0, is never
        used), hold and gate. ``rtk.hold``: how long after an epoch its heading is output (carried by the
        magnetic heading's increments) before falling back to ``H_mag + delta``. ``rtk.gate``: epochs
        further than this from the predicted heading (the carried RTK heading, else ``H_mag + delta``) are
        rejected, so 180 deg ambiguity flips are never fused; the first epoch has nothing to be checked
        against and is used. ``rtk.confirm``: the confirm-th consecutive rejected epoch agreeing with the
        previous rejected ones is used and restarts delta from it (a wrong first epoch or a real change of
        the offset is recovered from).
    dt : float or array_like, shape (N,)
        Sample interval (s), or per-sample intervals ``dt[k] = t[k] - t[k-1]``.
    alpha : float
        Smoothing of the offset per RTK epoch (0.01 at 5 Hz: a time constant of about 20 s).
    max_dt : float, optional
        Longest interval (s) before a sample that is not a clock jump. At a jump the carried RTK heading
        is dropped and the gate restarts; delta is kept (module docstring: why). Default None:
        ``imu.JUMP_FACTOR`` = 10 median intervals (none with a scalar ``dt``); inf: off.

    Returns
    -------
    FusionResult

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.filters import heading_fusion, observations
    >>> heading_mag = 0.3 + 0.001 * np.arange(10)                     # magnetic heading, turning slowly (rad)
    >>> rtk = observations.RtkHeading(np.full(10, 0.5), np.arange(10) % 5 == 0)   # RTK epochs at samples 0 and 5
    >>> out = heading_fusion.fuse_rtk_heading(heading_mag, rtk, 0.01)
    >>> np.round(out.heading, 3)                                      # RTK's 0.5 rad, carried by the magnetic increments
    array([0.5  , 0.501, 0.502, 0.503, 0.504, 0.5  , 0.501, 0.502, 0.503,
           0.504])
    """
    hm = as_array(heading_mag, "heading_mag", min_ndim=1, nonempty=True)
    hr, ok = rtk.at(hm.shape, "heading_mag")
    T, N = hr.shape
    dts = sample_intervals(dt, N)
    jump = dts > SensorLimits(max_dt=max_dt).jump_limit(float(np.median(dts)))
    out, delta, counts = np.empty((T, N)), np.empty((T, N)), np.zeros((T, len(_FAULTS)), dtype=np.int64)
    _fuse_kernel(kernel_array(hm.reshape(T, N)), hr, ok, dts, jump, alpha, rtk.params(), out, delta, counts)
    lead = hm.shape[:-1]
    found = {key: counts[:, i].reshape(lead) for i, key in enumerate(_FAULTS) if key[0] == "heading" or rtk.gate}
    found["clock", "jump"] = np.full(lead, jump.sum())
    faults = FaultReport(found, {("clock", "jump"): np.broadcast_to(jump, hm.shape)})
    return FusionResult(out.reshape(hm.shape), delta.reshape(hm.shape), faults)


@boundary
def rtk_at_imu_rate(time: Times, heading: Angles, valid: ArrayLike, step: Count) -> tuple[Array, np.ndarray]:
    """Place RTK epochs on the IMU time axis: every ``step``-th IMU sample carries an epoch.

    Parameters
    ----------
    time : array_like, shape (N,)
        IMU sample times (s).
    heading : array_like, shape (..., N)
        RTK heading at the IMU times (rad), e.g. :func:`navlib.sensors.simulate_heading`.
    valid : array_like of bool, shape (N,)
        Receiver validity at each IMU time (e.g. :func:`navlib.sensors.outage_mask`).
    step : int
        IMU samples per RTK epoch (e.g. 20 for 5 Hz RTK with a 100 Hz IMU).

    Returns
    -------
    heading : ndarray, shape (..., N)
        The heading, NaN between epochs and at invalid epochs.
    epoch_valid : ndarray of bool, shape (N,)
        True at valid epochs.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.filters import heading_fusion
    >>> time = 0.01 * np.arange(6)
    >>> heading, valid = heading_fusion.rtk_at_imu_rate(time, np.full(6, 0.5), np.ones(6, bool), step=3)
    >>> heading, valid
    (array([0.5, nan, nan, 0.5, nan, nan]), array([ True, False, False,  True, False, False]))
    """
    t = time_axis(time, "time")
    h = as_array(heading, "heading", allow_nan=True, nonempty=True)
    v = same_shape(booleans(valid, "valid"), "valid", t.shape, of="time")
    last_axis(h, "heading", t.size, of="time")
    epoch = np.zeros(t.shape, dtype=bool)
    epoch[::step] = True
    ok = epoch & v
    return np.where(ok, h, np.nan), ok
