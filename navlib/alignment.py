"""Initial alignment of a static or slowly moving IMU: levelling and magnetic heading.

One implementation of each concept, imported by every paper companion and notebook:

* :func:`level` -- pitch and roll from (mean) specific force, the accelerometer
  levelling ``pitch = atan2(f_y, hypot(f_x, f_z))``, ``roll = atan2(-f_x, f_z)``
  (right-front-up body, ``hpr`` order of :mod:`navlib`). The atan2 form is exact for any
  norm of ``f_b``, so no value of g is needed.
* :func:`magnetic_heading` -- tilt-compensated heading of a magnetometer reading, given
  pitch and roll (from :func:`level` or an INS).
* :func:`tilt_heading` -- both at once from one accelerometer + magnetometer reading,
  ``hpr``; :func:`initial_attitude` returns it as a quaternion.
* gyrocompassing of a static IMU: :func:`static_means` (robust window means with a
  :class:`StaticWindow` report; :func:`static_windows` for the stops of one record, each
  tested as :class:`StaticTests` says), :func:`triad` (analytic coarse alignment from specific force
  and Earth rate) and :func:`triad_heading`, :func:`four_position_heading` (a single gyro on a
  turntable); :func:`static_gyro_bias` (a static record's mean rate minus Earth rate).

Conventions are stated once in :mod:`navlib`: ENU navigation frame, right-front-up body,
heading clockwise from north in [0, 2 pi).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from . import _attitude, _kernels, attitude, earth
from ._records import unchecked
from ._typing import Angles, Array, ArrayLike, Dcm, Times, Vec3, Vec3Series
from ._validate import (
    MAX_GYROCOMPASS_LAT_DEG,
    Flag,
    Fraction,
    Is,
    Positive,
    as_array,
    boundary,
    broadcast,
    fields_checked,
    flag,
    imu_samples,
    indices,
    kernel_array,
    latitude,
    pitch_roll,
    same_shape,
    scalar,
    time_axis,
)
from .imu import ImuSamples, unpack
from .robust import FaultReport, longest_repeat

__all__ = [
    "level",
    "magnetic_heading",
    "tilt_heading",
    "initial_attitude",
    "MAX_LAT_DEG",
    "gyrocompass_latitude",
    "StaticWindow",
    "StaticTests",
    "static_means",
    "static_windows",
    "triad",
    "triad_heading",
    "four_position_heading",
    "static_gyro_bias",
]


def _nonzero(v: np.ndarray, name: str) -> np.ndarray:
    if np.any(np.linalg.norm(v, axis=-1) == 0):
        raise ValueError(f"{name}: expected non-zero vectors")
    return v


def level(f_b: Vec3) -> tuple[Array, Array]:
    """Pitch and roll (rad) of a static IMU from its (mean) specific force.

    Parameters
    ----------
    f_b : array_like, shape (..., 3)
        Specific force (any unit; +g up when level), e.g. a static mean.

    Returns
    -------
    pitch, roll : ndarray, shape (...)
        Pitch in [-pi/2, pi/2], roll in (-pi, pi] (rad).

    Examples
    --------
    >>> from navlib import alignment, attitude
    >>> f_b = attitude.euler_to_dcm([0.0, 0.1, -0.2]).T @ [0.0, 0.0, 9.8]   # pitch 0.1 rad, roll -0.2 rad
    >>> pitch, roll = alignment.level(f_b)
    >>> round(float(pitch), 6), round(float(roll), 6)
    (0.1, -0.2)
    """
    return _attitude.level(_nonzero(as_array(f_b, "f_b", tail=(3,)), "f_b"))


def magnetic_heading(m_b: Vec3, pitch: Angles, roll: Angles, declination: float = 0.0) -> Array:
    """Tilt-compensated heading (rad) in [0, 2 pi), clockwise from true north.

    Parameters
    ----------
    m_b : array_like, shape (..., 3)
        Magnetometer reading, right-front-up (any unit).
    pitch, roll : array_like, shape (...)
        Attitude (rad), e.g. from :func:`level` or an INS; broadcast with ``m_b``.
    declination : float
        Magnetic declination D, east of true north positive (rad); 0 gives the magnetic heading.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import alignment
    >>> m_b = [20.0 * np.sin(-0.5), 20.0 * np.cos(-0.5), -40.0]   # level, field 0.5 rad to the right of the nose
    >>> round(float(alignment.magnetic_heading(m_b, pitch=0.0, roll=0.0)), 6)
    0.5
    """
    m = _nonzero(as_array(m_b, "m_b", tail=(3,)), "m_b")
    p, r = pitch_roll(pitch, roll)
    return _attitude.magnetic_heading(m, p, r, scalar(declination, "declination"))


def tilt_heading(f_b: Vec3, m_b: Vec3, declination: float = 0.0) -> Array:
    """Heading, pitch and roll ``hpr`` (rad) from one static accelerometer and magnetometer reading.

    Parameters
    ----------
    f_b, m_b : array_like, shape (..., 3)
        Specific force and magnetic field (any units), e.g. 1-s means.
    declination : float
        D (rad, east positive); 0 gives the heading from magnetic north.

    Returns
    -------
    hpr : ndarray, shape (..., 3)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import alignment
    >>> f_b = [0.0, 0.0, 9.81]                      # level
    >>> m_b = [0.0, 20.0, -40.0]                    # field ahead and down: facing magnetic north
    >>> np.round(np.rad2deg(alignment.tilt_heading(f_b, m_b)), 6) + 0.0    # [heading, pitch, roll] in deg
    array([0., 0., 0.])
    """
    f = _nonzero(as_array(f_b, "f_b", tail=(3,)), "f_b")
    m = _nonzero(as_array(m_b, "m_b", tail=(3,)), "m_b")
    cross = np.linalg.norm(
        np.cross(f / np.linalg.norm(f, axis=-1, keepdims=True), m / np.linalg.norm(m, axis=-1, keepdims=True)), axis=-1
    )
    if np.any(cross < 1e-6):
        raise ValueError("m_b: magnetometer parallel to gravity; heading is undefined")
    pitch, roll = _attitude.level(f)
    heading = _attitude.magnetic_heading(m, pitch, roll, scalar(declination, "declination"))
    return np.stack(np.broadcast_arrays(heading, pitch, roll), -1)


def initial_attitude(f_b: Vec3, m_b: Vec3, declination: float = 0.0) -> Array:
    """Initial quaternion ``q_bn`` (..., 4) from :func:`tilt_heading` (scalar first).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import alignment, attitude
    >>> q_bn = alignment.initial_attitude([0.0, 0.0, 9.8], [0.0, 20.0, -40.0])   # level, magnetometer facing north
    >>> np.round(attitude.quat_to_euler(q_bn, deg=True), 6)
    array([0., 0., 0.])
    """
    return attitude.euler_to_quat(tilt_heading(f_b, m_b, declination))


# --------------------------------------------------------------------------
# Gyrocompassing: static means, TRIAD, four-position
# --------------------------------------------------------------------------

MAX_LAT_DEG = MAX_GYROCOMPASS_LAT_DEG
"""Largest |latitude| accepted for gyrocompassing (deg): beyond it cos(lat) < 0.0175 and the
horizontal Earth rate (< 0.26 deg/h) no longer defines north usefully."""


def gyrocompass_latitude(lat: ArrayLike, deg: bool = False) -> Array:
    """Latitude in rad, rejecting |lat| > 90 deg and near-polar |lat| > MAX_LAT_DEG.

    Examples
    --------
    >>> from navlib import alignment
    >>> float(alignment.gyrocompass_latitude(45.0, deg=True))      # rad
    0.7853981633974483
    """
    return _not_polar(latitude(lat, "lat", deg=deg, nonempty=True))


def _not_polar(lat: Array) -> Array:
    """Refuse a checked latitude (rad) beyond MAX_LAT_DEG."""
    if np.any(np.abs(lat) > np.deg2rad(MAX_LAT_DEG)):
        raise ValueError(
            f"lat: expected |lat| <= {MAX_LAT_DEG} deg for north finding (cos(lat) -> 0 near "
            f"the poles), got {np.rad2deg(np.abs(lat).max()):.4g} deg"
        )
    return lat


@dataclass(frozen=True)
class StaticWindow:
    """Averages of one static window, the samples used and what was left out (shapes (..., 3) and (...)).

    Attributes
    ----------
    w_mean, f_mean : ndarray, shape (..., 3)
        Means of the samples used (rad/s, m/s^2); NaN where the window was
        refused (``faults["window", "refused"] == 1``).
    n_samples : int
        Samples in the window (N).
    n_used_gyro, n_used_accel : ndarray of int, shape (...)
        Samples averaged.
    faults : FaultReport
        Counts of shape (...) per :class:`navlib.robust.FaultReport` key:

        * ``(sensor, "nan")``, sensor ``"gyro"`` or ``"accel"``: samples with a NaN
          component (dropouts), left out;
        * ``(sensor, "outlier")``: samples more than ``outlier_k`` robust sigmas
          (1.4826 MAD, floored at the quantisation step: see :func:`static_means`)
          from the window median in any component, left out (0 without ``outlier_k``);
        * ``(sensor, "saturated")``: samples with a component at the device rails
          (``|x| >= full_scale``);
        * ``(sensor, "stuck")``: samples in the longest run of identical readings on
          any axis, where it reached ``stuck_fraction`` of the valid samples (0
          otherwise, and without ``stuck_fraction``);
        * ``("window", "refused")``: 1 where the window was refused, 0 where accepted.

        Why a window was refused is read from the same counts (each reason refuses it,
        and more than one may hold):

        * too few samples: ``n_used_gyro`` or ``n_used_accel`` below
          ``max(2, ceil(min_fraction N))`` (dropouts and outliers left out too many);
        * saturation: ``("gyro", "saturated")`` or ``("accel", "saturated")`` > 0,
          the robot was not still or the reading is unknown;
        * a frozen sensor: ``("gyro", "stuck")`` or ``("accel", "stuck")`` > 0;
        * motion: refused with none of the three above -- the mean specific-force
          norm or the difference of the two half-window means exceeded ``accel_tol``
          (only tested when the window passed the other checks).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import alignment, trajectory
    >>> traj = trajectory.static(1.0, 0.01, [0.6, 0.2, 50.0], [0.3, 0.0, 0.0])
    >>> w_ib_b, f_b = trajectory.ideal_imu(traj)
    >>> win = alignment.static_means(w_ib_b, f_b, lat=0.6, h=50.0)
    >>> win.n_samples, np.round(win.f_mean, 4)                     # m/s^2, right-front-up
    (100, array([ 0.    , -0.    ,  9.7967]))
    """

    w_mean: np.ndarray
    f_mean: np.ndarray
    n_samples: int
    n_used_gyro: np.ndarray
    n_used_accel: np.ndarray
    faults: FaultReport


@dataclass(frozen=True)
class StaticTests:
    """The tests a static window must pass to be averaged, validated on construction: :func:`static_windows` takes
    them as one record, :func:`static_means` as keywords (the same defaults). A refusal is counted in the window's
    :class:`StaticWindow` ``faults``.

    Attributes
    ----------
    accel_tol : float
        Largest accepted deviation (m/s^2) of the mean specific-force norm from normal gravity, and of the two
        half-window means from each other. Larger deviations mean the robot was not static (refused). Default 0.2.
    min_fraction : float
        Smallest fraction of the window, in (0, 1], that must remain per sensor. Default 0.5.
    outlier_k : float, optional
        MAD outlier threshold (e.g. 6); None (default): no outlier rejection.
    full_scale_gyro, full_scale_accel : float, optional
        Device ranges (rad/s, m/s^2); None (default): no saturation check.
    stuck_fraction : float, optional
        In (0, 1]: refuse a window whose longest run of one repeated reading, on any axis, covers this fraction of
        the valid samples (0.5: most of the stop; :func:`navlib.papers.north_finding.stop_solutions` uses 0.5);
        None (default): no check.

    Examples
    --------
    >>> from navlib import alignment
    >>> tests = alignment.StaticTests(outlier_k=6.0, stuck_fraction=0.5)
    >>> tests.accel_tol, tests.min_fraction, tests.outlier_k
    (0.2, 0.5, 6.0)
    """

    accel_tol: Positive = 0.2
    min_fraction: Fraction = 0.5
    outlier_k: Positive | None = None
    full_scale_gyro: Positive | None = None
    full_scale_accel: Positive | None = None
    stuck_fraction: Fraction | None = None

    def __post_init__(self) -> None:
        fields_checked(self)


def _outliers(x: Array, valid: NDArray[np.bool_], k: float) -> NDArray[np.bool_]:
    """Samples more than ``k`` robust sigmas from the median of the valid samples (any component).

    The robust sigma is :func:`navlib._kernels.robust_sigma`, ``1.4826 max(MAD, q / 2)`` per component,
    with ``q`` the quantisation step (:func:`navlib._kernels.quant_step`): the smallest non-zero
    difference between two valid readings (0 for continuous readings, where it is far below the MAD and
    the rule is the plain 1.4826 MAD). Without the floor every sample off the median code was an
    outlier (with ``k = 5``, 1,500-2,200 of the 3,000 samples of a good stop quantised at 1.5-3
    noise sigmas; ``tests/faults/test_faults_northfinding.py``); with the quantisation noise
    q / sqrt(12) as the floor, samples two codes out still were (35-110 of 3,000).
    """
    xv = np.where(valid[..., None], x, np.nan)
    with np.errstate(all="ignore"), warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # all-NaN windows: refused for too few samples
        med = np.nanmedian(xv, axis=-2, keepdims=True)
        mad = np.nanmedian(np.abs(xv - med), axis=-2, keepdims=True)
    columns = np.moveaxis(xv, -2, -1)  # (..., k, n): one reading series per row
    q = _kernels.quant_steps(kernel_array(columns.reshape(int(np.prod(columns.shape[:-1])), columns.shape[-1])))
    q = q.reshape(columns.shape[:-1])[..., None, :]
    thresh = k * _kernels.robust_sigma(mad, q)
    return valid & np.any(np.abs(x - med) > thresh, axis=-1)


def _masked_mean(x: Array, used: NDArray[np.bool_], n_used: NDArray[np.intp]) -> Array:
    if used.all():
        return x.mean(-2)  # the fault-free path, bit-identical to a plain mean
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(used[..., None], x, 0.0).sum(-2) / n_used[..., None]


@boundary
def static_means(
    w_ib_b: Vec3Series | ImuSamples,
    f_b: Vec3Series | None = None,
    lat: ArrayLike | None = None,
    h: ArrayLike = 0.0,
    accel_tol: Positive = 0.2,
    *,
    min_fraction: Fraction = 0.5,
    outlier_k: Positive | None = None,
    full_scale_gyro: Positive | None = None,
    full_scale_accel: Positive | None = None,
    stuck_fraction: Fraction | None = None,
    strict: Flag = True,
) -> StaticWindow:
    """Average a static window of gyro and accelerometer samples (paper step 1).

    Faults, each counted in the returned :class:`StaticWindow`'s ``faults`` (a refused
    window: ``("window", "refused")``; the reason is read from the counts, see
    :class:`StaticWindow`):

    * dropouts: samples with a NaN component are left out of that sensor's
      mean (``("gyro", "nan")``, ``("accel", "nan")``); a window with fewer than
      ``max(2, min_fraction N)`` samples left is refused. A
      30-s gap in a 3-min stop leaves 150 s: the mean's white-noise std grows
      by sqrt(180/150) = 1.10.
    * outliers: with ``outlier_k``, samples more than ``outlier_k`` robust
      sigmas from the window median are left out (``(sensor, "outlier")``); the
      robust sigma is ``1.4826 max(MAD, q / 2)`` per component, ``q`` the
      quantisation step (the smallest non-zero difference between two
      readings): a quantised sensor whose MAD reads 0 keeps its good samples
      (1.4826 MAD alone made every sample off the median code an outlier).
      Without it, spikes of +-k sigma on a fraction p of the samples add
      ``k sigma sqrt(p / N)`` of noise to the mean (10x the mean's
      white-noise std for p = 1 %, k = 100), unreported.
    * frozen output: with ``stuck_fraction``, a window in which one axis
      repeats a single reading over at least that fraction of its valid
      samples (consecutive, dropouts skipped) is refused
      (``(sensor, "stuck")``): a live sensor's noise changes every reading, and a
      frozen gyro's mean is one old sample (a stop then gave a heading
      13-20 deg off, accepted). A quantised sensor whose noise is far
      below its step looks the same and is refused too (it resolves nothing
      below the step); so is noise-free simulated data (pass None).
    * saturation: with ``full_scale_gyro``/``full_scale_accel`` (device
      ranges, rad/s and m/s^2), samples at the rails are counted and the
      window is refused (``(sensor, "saturated")``): a static robot never reaches them.
    * timing: the mean does not depend on sample order; duplicated
      timestamps are removed by ``timing.sanitize`` before windows are cut
      by time (:func:`stop_solutions` with ``time``).

    Parameters
    ----------
    w_ib_b, f_b : array_like, shape (..., N, 3)
        Gyro (rad/s) and accelerometer (m/s^2) samples of one stop, N >= 2;
        NaN marks dropouts. An :class:`navlib.imu.ImuSamples` as ``w_ib_b``
        supplies ``f_b`` and the device ranges (its intervals are not used here).
    lat : float
        Latitude (rad), used for the expected gravity (required).
    h : float
        Height (m).
    accel_tol, min_fraction, outlier_k, full_scale_gyro, full_scale_accel, stuck_fraction : float or None
        The window's tests: the fields of :class:`StaticTests`, with the same defaults.
    strict : bool
        Raise ValueError for a refused window (default); ``False`` returns NaN
        means with its ``faults`` instead.

    Returns
    -------
    StaticWindow

    Raises
    ------
    ValueError
        Empty windows, inf, mismatched shapes; with ``strict``, a refused
        window (too few samples, saturated, a frozen sensor, or the robot
        evidently moving).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import alignment, trajectory
    >>> traj = trajectory.static(1.0, 0.01, [0.6, 0.2, 50.0], [0.3, 0.0, 0.0])
    >>> w_ib_b, f_b = trajectory.ideal_imu(traj)
    >>> f_b[10] = np.nan                                          # a dropout: left out of the mean
    >>> win = alignment.static_means(w_ib_b, f_b, lat=0.6, h=50.0)
    >>> int(win.n_used_accel), int(win.faults["accel", "nan"]), np.round(win.f_mean, 4)
    (99, 1, array([ 0.    , -0.    ,  9.7967]))
    """
    w, f, g, fs_g, fs_a = _static_record(w_ib_b, f_b, lat, h, full_scale_gyro, full_scale_accel)
    if w.shape[-2] < 2:
        raise ValueError(f"w_ib_b: expected a static window of at least 2 samples, got {w.shape[-2]}")
    tests = unchecked(  # the keywords are checked by @boundary
        StaticTests,
        accel_tol=accel_tol,
        min_fraction=min_fraction,
        outlier_k=outlier_k,
        full_scale_gyro=full_scale_gyro,
        full_scale_accel=full_scale_accel,
        stuck_fraction=stuck_fraction,
    )
    return _window_means(w, f, g, tests, fs_g, fs_a, strict)


@boundary
def static_windows(
    w_ib_b: Vec3Series | ImuSamples,
    f_b: Vec3Series | None = None,
    windows: ArrayLike | None = None,
    lat: ArrayLike | None = None,
    h: ArrayLike = 0.0,
    tests: Is[StaticTests] | None = None,
    *,
    time: Times | None = None,
    strict: Flag = True,
) -> tuple[StaticWindow, ...]:
    """Average several static windows (stops) of one record, each as :func:`static_means` averages one.

    For multi-position alignment: the record, the site and the tests are checked once, then each window is
    averaged and tested on its own (faults and refusals as in :func:`static_means`).

    Parameters
    ----------
    w_ib_b, f_b : array_like, shape (..., N, 3)
        Gyro (rad/s) and accelerometer (m/s^2) samples of the whole record; NaN marks dropouts. An
        :class:`navlib.imu.ImuSamples` as ``w_ib_b`` supplies ``f_b`` and the device ranges (not its ``dt``:
        windows are sample indices, or times with ``time``).
    windows : array_like, shape (S, 2)
        ``[start, end)`` of the windows, each of at least 2 samples: integer sample indices, or times (s) when
        ``time`` is given.
    lat, h : float
        Latitude (rad) and height (m) of the site, as in :func:`static_means`.
    tests : StaticTests, optional
        What each window must pass; default ``StaticTests()``.
    time : array_like, shape (N,), optional
        Strictly increasing sample times (s), e.g. from :func:`navlib.timing.sanitize` (which removes
        duplicated and out-of-order timestamps); the windows are then cut by time, so dropped samples do not
        shift them.
    strict : bool
        Raise ValueError for the first refused window (default); ``False`` returns NaN means for it instead.

    Returns
    -------
    tuple of StaticWindow
        One per window, in the order of ``windows``.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import alignment, trajectory
    >>> traj = trajectory.static(2.0, 0.01, [0.6, 0.2, 50.0], [0.3, 0.0, 0.0])
    >>> w_ib_b, f_b = trajectory.ideal_imu(traj)
    >>> f_b[140:] = np.nan                                        # the second stop's accelerometer drops out
    >>> first, second = alignment.static_windows(w_ib_b, f_b, [[0, 100], [100, 200]], lat=0.6, h=50.0, strict=False)
    >>> np.round(first.f_mean, 4), int(second.n_used_accel), int(second.faults["window", "refused"])
    (array([ 0.    , -0.    ,  9.7967]), 40, 1)
    """
    tests = StaticTests() if tests is None else tests
    w, f, g, fs_g, fs_a = _static_record(w_ib_b, f_b, lat, h, tests.full_scale_gyro, tests.full_scale_accel)
    windows = _window_indices(windows, time, w.shape[-2])
    return tuple(_window_means(w[..., a:b, :], f[..., a:b, :], g, tests, fs_g, fs_a, strict) for a, b in windows)


def _static_record(
    w_ib_b: Vec3Series | ImuSamples,
    f_b: Vec3Series | None,
    lat: ArrayLike | None,
    h: ArrayLike,
    full_scale_gyro: float | None,
    full_scale_accel: float | None,
) -> tuple[Array, Array, Array, float, float]:
    """The checked samples of a static record, the normal gravity at ``lat``, ``h`` and the device ranges (inf: none)."""
    if isinstance(w_ib_b, ImuSamples):  # samples checked by the record; no dt here: unpack's is left None and unused
        w, f, _, full_scale_gyro, full_scale_accel = unpack(w_ib_b, f_b, None, full_scale_gyro, full_scale_accel)
    elif f_b is None:
        raise ValueError("f_b: required (or pass an ImuSamples as w_ib_b)")
    else:
        w, f = imu_samples(w_ib_b, f_b)
    if lat is None:
        raise ValueError("lat: required")
    g = earth.gravity(lat, h)  # checks lat and h (an empty h fails the shape check below)
    _not_polar(np.asarray(lat, dtype=float))
    lead = w.shape[:-2]
    if np.ndim(g) > len(lead) or any(a not in (1, b) for a, b in zip(np.shape(g)[::-1], lead[::-1], strict=False)):
        raise ValueError(f"lat, h: expected one value or one per trial (trial shape {lead}), got shape {np.shape(g)}")
    fs_g = np.inf if full_scale_gyro is None else full_scale_gyro
    fs_a = np.inf if full_scale_accel is None else full_scale_accel
    return w, f, g, fs_g, fs_a


def _window_indices(windows: object, time: object, n: int) -> NDArray[np.intp]:
    """``windows`` ([start, end) sample indices, or times with ``time``) as (S, 2) sample indices into ``n`` samples."""
    if time is not None:
        t = same_shape(time_axis(time, "time"), "time", (n,), of="w_ib_b")
        tw = as_array(windows, "windows", nonempty=True)
        if tw.ndim != 2 or tw.shape[1] != 2 or np.any(tw[:, 1] <= tw[:, 0]):
            raise ValueError(f"windows: expected (S, 2) [start, end) times in s with end > start, got {tw.tolist()}")
        win = np.searchsorted(t, tw, side="left")
    else:
        win = indices(windows, "windows")
        if win.ndim != 2 or win.shape[1] != 2 or not np.issubdtype(win.dtype, np.integer):
            raise ValueError(f"windows: expected (S, 2) integer [start, end) sample indices, got {win.tolist()}")
    if np.any(win[:, 0] < 0) or np.any(win[:, 1] > n) or np.any(win[:, 1] - win[:, 0] < 2):
        raise ValueError(
            f"windows: expected (S, 2) [start, end) sample indices within {n} samples, each >= 2 long, got {win.tolist()}"
        )
    return win


def _window_means(w: Array, f: Array, g: Array, tests: StaticTests, fs_g: float, fs_a: float, strict: bool) -> StaticWindow:
    """:func:`static_means` of checked samples (..., N, 3), N >= 2, with the expected gravity ``g``, checked ``tests``
    and device ranges ``fs_g``, ``fs_a`` (inf: none; an :class:`~navlib.imu.ImuSamples`' ranges replace the tests')."""
    n = w.shape[-2]
    need = max(2, int(np.ceil(tests.min_fraction * n)))
    out = {}
    for name, x, fs in (("gyro", w, fs_g), ("accel", f, fs_a)):
        valid = np.all(np.isfinite(x), -1)
        sat = valid & np.any(np.abs(x) >= fs, -1)
        outl = _outliers(x, valid, tests.outlier_k) if tests.outlier_k is not None else np.zeros_like(valid)
        used = valid & ~outl
        n_used = used.sum(-1)
        n_stuck = np.zeros(valid.shape[:-1], dtype=int)
        if tests.stuck_fraction is not None:
            run = longest_repeat(x, valid).max(-1)
            n_stuck = np.where((run >= tests.stuck_fraction * valid.sum(-1)) & (run >= 2), run, 0)
        out[name] = (_masked_mean(x, used, n_used), n_used, n - valid.sum(-1), outl.sum(-1), sat.sum(-1), used, n_stuck)
    (w_mean, nu_g, nd_g, no_g, ns_g, _, nk_g), (f_mean, nu_a, nd_a, no_a, ns_a, used_f, nk_a) = out["gyro"], out["accel"]
    too_few = (nu_g < need) | (nu_a < need)
    saturated = ~too_few & ((ns_g > 0) | (ns_a > 0))
    frozen = ~too_few & ~saturated & ((nk_g > 0) | (nk_a > 0))
    with np.errstate(invalid="ignore"):
        dev = np.abs(np.linalg.norm(f_mean, axis=-1) - g)
        if used_f.all():
            halves = np.abs(f[..., : n // 2, :].mean(-2) - f[..., n // 2 :, :].mean(-2)).max(-1)
        else:
            u1, u2 = used_f[..., : n // 2], used_f[..., n // 2 :]
            halves = np.abs(
                _masked_mean(f[..., : n // 2, :], u1, u1.sum(-1)) - _masked_mean(f[..., n // 2 :, :], u2, u2.sum(-1))
            ).max(-1)
    moving = ~too_few & ~saturated & ~frozen & ((dev > tests.accel_tol) | ~(halves <= tests.accel_tol))
    bad = too_few | saturated | frozen | moving
    if strict and np.any(bad):
        if np.any(too_few):
            which = "w_ib_b" if np.any(nu_g < need) else "f_b"
            left = int(min(nu_g.min(), nu_a.min()))
            raise ValueError(
                f"{which}: only {left} of {n} samples left after dropouts/outliers; expected at least "
                f"{need} (min_fraction = {tests.min_fraction:g})"
            )
        if np.any(saturated):
            which = "w_ib_b" if np.any(ns_g > 0) else "f_b"
            raise ValueError(
                f"{which}: {int(ns_g.sum() + ns_a.sum())} samples at the full-scale range: the robot "
                "was not static during the stop"
            )
        if np.any(frozen):
            which, run = ("w_ib_b", nk_g) if np.any(nk_g > 0) else ("f_b", nk_a)
            raise ValueError(
                f"{which}: one reading repeated over {int(run.max())} consecutive samples of {n} "
                f"(stuck_fraction = {tests.stuck_fraction:g}): the sensor output is frozen"
            )
        if np.any(dev[moving] > tests.accel_tol):
            raise ValueError(
                f"f_b: mean specific-force norm differs from gravity by {np.nanmax(dev):.3g} m/s^2 "
                f"(> accel_tol = {tests.accel_tol:g}): the robot is not static"
            )
        raise ValueError(
            f"f_b: the two halves of the window differ by {np.nanmax(halves):.3g} m/s^2 "
            f"(> accel_tol = {tests.accel_tol:g}): the robot moved during the stop"
        )
    w_mean = np.where(bad[..., None], np.nan, w_mean)
    f_mean = np.where(bad[..., None], np.nan, f_mean)
    faults = FaultReport(
        {
            ("gyro", "nan"): nd_g,
            ("accel", "nan"): nd_a,
            ("gyro", "outlier"): no_g,
            ("accel", "outlier"): no_a,
            ("gyro", "saturated"): ns_g,
            ("accel", "saturated"): ns_a,
            ("gyro", "stuck"): nk_g,
            ("accel", "stuck"): nk_a,
            ("window", "refused"): bad.astype(int),
        }
    )
    return StaticWindow(w_mean, f_mean, n, nu_g, nu_a, faults)


def triad(f_b: Vec3, w_ib_b: Vec3, lat: ArrayLike, orthonormal: bool = True) -> Array:
    """Analytic coarse alignment with a three-axis gyro: TRIAD (paper 000, Tan & Xie, Eqs. 1-2).

    Parameters
    ----------
    f_b : array_like, shape (..., 3)
        Averaged specific force (m/s^2).
    w_ib_b : array_like, shape (..., 3)
        Averaged angular rate (rad/s).
    lat : float or array_like broadcasting with the leading axes
        Latitude (rad).
    orthonormal : bool
        Project the result onto the nearest rotation (SVD). ``False`` returns
        Eq. (2)'s raw product, which noise makes slightly non-orthonormal.

    Returns
    -------
    C_bn : ndarray, shape (..., 3, 3)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import alignment, attitude, earth
    >>> C_true = attitude.euler_to_dcm(np.deg2rad([30.0, 2.0, -1.0]))
    >>> f_b = C_true.T @ [0.0, 0.0, earth.gravity(0.6)]           # what a static IMU senses
    >>> w_ib_b = earth.earth_rate_b(C_true, 0.6)
    >>> np.round(np.rad2deg(attitude.dcm_to_euler(alignment.triad(f_b, w_ib_b, 0.6))), 6)
    array([30.,  2., -1.])
    """
    f = as_array(f_b, "f_b", tail=(3,), nonempty=True)
    w = as_array(w_ib_b, "w_ib_b", tail=(3,), nonempty=True)
    f, w = broadcast(f, w, name="w_ib_b", of="f_b, w_ib_b")
    C_bn = _attitude.triad(f, w, gyrocompass_latitude(lat), earth.WGS84)
    return attitude.orthonormalize(C_bn) if flag(orthonormal, "orthonormal") else C_bn


def triad_heading(C_bn: Dcm) -> Array:
    """Heading ``atan2(c12, c22) mod 2 pi`` (rad) of a TRIAD matrix, orthonormal or raw.

    The inverse of paper Eq. (3) for the heading; unlike
    :func:`navlib.attitude.dcm_to_euler` it accepts Eq. (2)'s raw,
    slightly non-orthonormal product. Shape (..., 3, 3) -> (...).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import alignment, attitude
    >>> C_bn = attitude.euler_to_dcm(np.deg2rad([30.0, 2.0, -1.0]))
    >>> round(float(np.rad2deg(alignment.triad_heading(C_bn))), 6)
    30.0
    """
    C = as_array(C_bn, "C_bn", tail=(3, 3), nonempty=True)
    return attitude.wrap_2pi(np.arctan2(C[..., 0, 1], C[..., 1, 1]))


def four_position_heading(w_y: ArrayLike) -> Array:
    r"""Heading from a level gyro turned to four positions 90 deg apart (turntable).

    Position k has heading ``psi + k pi/2`` (turned clockwise), so
    ``w_k = w_ie cos(lat) cos(psi + k pi/2) + b``: the bias b cancels in
    :math:`\psi = \operatorname{atan2}(w_3 - w_1,\ w_0 - w_2)`, for every :math:`\psi`.

    Parameters
    ----------
    w_y : array_like, shape (..., 4)
        Averaged gyro output at the four positions (rad/s).

    Returns
    -------
    ndarray, shape (...)
        Heading of position 0 (rad, [0, 2 pi)).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import alignment, earth
    >>> psi, b = np.deg2rad(40.0), 1e-5                           # true heading, gyro bias (rad/s)
    >>> w_y = earth.earth_rate_n(0.6)[1] * np.cos(psi + np.arange(4) * np.pi / 2) + b
    >>> round(float(np.rad2deg(alignment.four_position_heading(w_y))), 6)   # the bias cancels
    40.0
    """
    w = as_array(w_y, "w_y", tail=(4,), nonempty=True)
    return attitude.wrap_2pi(np.arctan2(w[..., 3] - w[..., 1], w[..., 0] - w[..., 2]))


# --------------------------------------------------------------------------
# Static gyro bias
# --------------------------------------------------------------------------


def static_gyro_bias(w_ib_b: Vec3Series, C_bn: Dcm, lat: float) -> Array:
    r"""Gyro bias from a static record: :math:`\bar\omega - (C_b^n)^T \omega_{ie}^n` (rad/s).

    Parameters
    ----------
    w_ib_b : array_like, shape (N, 3)
    C_bn : array_like, shape (3, 3) or (..., 3, 3)
        Attitude during the record (several: one bias each).
    lat : float  (rad)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import alignment, attitude, earth
    >>> C_bn = attitude.euler_to_dcm([0.3, 0.0, 0.0])
    >>> w_ib_b = earth.earth_rate_b(C_bn, 0.6) + [1e-4, -2e-4, 0.0] + np.zeros((100, 3))   # static, biased gyro
    >>> np.round(alignment.static_gyro_bias(w_ib_b, C_bn, 0.6), 8)
    array([ 0.0001, -0.0002,  0.    ])
    """
    w = as_array(w_ib_b, "w_ib_b", shape=(None, 3), min_ndim=1)
    return w.mean(0) - earth.earth_rate_b(C_bn, lat)
