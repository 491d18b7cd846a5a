r"""North finding with a single-axis optical gyro and a MEMS IMU (paper 000).

Tan C., Xie X., "Indoor mobile robot north-finding based on single-axis optical
gyroscope and MEMS IMU", Chinese Journal of Scientific Instrument
(仪器仪表学报), doi:10.19650/j.cnki.cjsi.J2412479.

Frames follow :mod:`navlib`: ENU navigation frame, right-front-up body frame
(the paper's s frame, with the optical gyro on the forward axis y), ``C_bn``
is the paper's ``C_s^n`` and heading is clockwise from north (paper Eq. 3).
Latitude is ``lat`` (the paper's L). omega_ie = 7.292115e-5 rad/s.

Equations implemented
---------------------
* TRIAD, Eqs. (1)-(2) -- :func:`navlib.alignment.triad`:

  .. math::

      C_n^s = \big[-f,\ -f \times \omega,\ (-f \times \omega) \times (-f)\big]
              \big[g^n,\ g^n \times \omega_{ie},\ (g^n \times \omega_{ie}) \times g^n\big]^{-1}

  With noisy inputs the product is not orthonormal (the paper does not say
  what it does about that); :func:`triad` projects it onto the nearest
  rotation with :func:`navlib.attitude.orthonormalize` (SVD) unless asked for
  the raw product.
* Tilt, Eqs. (4)-(6) -- :func:`pitch_roll_from_accel`: :math:`\theta = \arcsin(f_y / g)`,
  :math:`\gamma = \operatorname{atan2}(-f_x, f_z)`.
* Single-axis candidates, Eqs. (8)-(11) -- :func:`heading_candidates`:

  .. math::

      \cos\psi &= \frac{\omega_y - \omega_{ie} \sin\varphi \sin\theta}{\omega_{ie} \cos\varphi \cos\theta} \\
      \psi^{(1)} & = \alpha = \arccos\big(\mathrm{clip}(\cos\psi, -1, 1)\big), \qquad \psi^{(2)} = 2\pi - \alpha

  The clipping is reported per trial (``clipped``).
* Resolution, Eq. (12) -- :func:`resolve`: the four candidate heading changes
  ``psi2(i) - psi1(j)`` are compared with the MEMS INS heading change through
  ``wrap_pi``; the nearest one gives the heading at position 2, and the margin
  to the nearest *different* candidate is returned.
* Error theory -- Eq. (13) with its sign corrected (:func:`triad_heading_error`),
  Eq. (16) (:func:`triad_heading_std`), Eq. (20) and its full linearisation
  with the pitch (accelerometer) term (:func:`single_axis_heading_std`,
  :func:`single_axis_heading_error`); where Eq. (20) fails (near 0 and 180
  deg, E000-03) the clipped estimator's error by quadrature
  (:func:`clipped_single_axis_theory`):

  .. math::

      \delta\psi = \frac{-\delta\omega_y + \omega_{ie} (\sin\varphi \cos\theta - \cos\varphi \sin\theta \cos\psi)\, \delta\theta}
                        {\omega_{ie} \cos\varphi \cos\theta \sin\psi}, \qquad
      \delta\theta = \frac{\delta f_y}{g \cos\theta}

Extensions: :func:`pair_probabilities` (exact probability of each candidate
pair winning for a Gaussian INS error; paper's "any second position" claim),
:func:`four_position_heading` (classic turntable north finding with the same
gyro) and the Monte Carlo of Fig. 4 (:func:`simulate_static_outputs`,
:func:`monte_carlo`) vectorised over headings and trials.

Faulty data in north finding (every fault is counted; nothing is dropped silently)
----------------------------------------------------------------------------------
=================  ===========================================  ======================================
fault              what happens                                 reported by (``faults`` keys)
=================  ===========================================  ======================================
NaN dropouts       stop means: samples left out; a stop with    ``StopSolutions.faults``:
                   < ``min_fraction`` (50 %) left is refused    ``("gyro", "nan")``, ``("accel", "nan")``,
                                                                ``("window", "refused")`` per stop
                   INS change: last sample held; a run longer   ``robust.fault_report`` of the gyro
                   than ``max_gap`` (0.1 s) refuses the drive   (``"nan"``); NaN result (refused)
outliers (spikes)  stop means: ``outlier_k`` robust sigmas      ``("gyro", "outlier")``,
                   (1.4826 MAD, at least 1.4826 q/2 for a       ``("accel", "outlier")``
                   quantisation step q) from the median left
                   out (opt-in; without it the error bound is
                   ``k sigma sqrt(p/N)``)
frozen sensor      stop: refused when one axis repeats a        ``("gyro", "stuck")``,
                   reading over >= ``stuck_fraction`` (50 %)    ``("accel", "stuck")``
                   of the stop's valid samples
saturation         stop: refused (``full_scale_*``);            ``("gyro", "saturated")``, ...;
                   INS drive: refused (``full_scale_gyro``)     ``fault_report(..., full_scale=)``
timing             ``timing.sanitize`` then windows cut by      ``TimingReport``; ``dt`` arrays in
                   time (``stop_solutions(time=...)``); INS     :func:`ins_heading_change`
                   integrates per-sample intervals
=================  ===========================================  ======================================

A refused stop or drive raises ValueError (``strict=True``, the default) or
gives NaN, which :func:`resolve` rejects, so it cannot be used by mistake.

Errata corrected (ids of ``data/errata.csv``)
---------------------------------------------
* E000-01: omega_ic in Eqs. (13), (16)-(20) is omega_ie.
* E000-02: with clockwise heading, Eq. (13) has the wrong sign:
  ``psi_hat - psi = -dw_E / (w_ie cos lat)``.
* E000-03: Eq. (20) fails near 0 deg / 180 deg, where |cos psi| > 1 must be
  clipped (this is where Table 1's "180.00, 180.00" comes from).
* E000-04: Eq. (20) omits the accelerometer (pitch) term and a 1/cos^2(pitch).
* E000-07: the candidate comparison must use wrapped differences.
* E000-10: alpha, beta lie in [0, pi], not [0, 2 pi).
* E000-12: a MEMS INS started with heading 0 cannot remove the horizontal Earth
  rate correctly; :func:`ins_heading_change` removes only the vertical part
  ``w_ie sin(lat)`` by default (or none / the full, misdirected rate).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Annotated, Any

import numpy as np
from numpy.typing import NDArray
from scipy.special import ndtr

from .. import _attitude, _earth, _plots, attitude, earth, robust
from .._records import unchecked
from .._typing import Angles, Array, ArrayLike, Dcm, Interval, Times, Vec3, Vec3Series
from .._validate import (
    Check,
    Count,
    GyroLatitude,
    Limit,
    NonNegative,
    Positive,
    Rng,
    as_array,
    as_dcm,
    axes,
    boundary,
    broadcast,
    broadcast_to,
    flag,
    in_range,
    integer,
    pitch_roll,
    positive,
    sample_intervals,
    scalar,
    small_turns,
)
from ..alignment import StaticTests, StaticWindow, gyrocompass_latitude, level, static_windows, triad_heading
from ..imu import ImuSamples, unpack
from ..trajectory import Segment

if TYPE_CHECKING:
    from matplotlib.axes import Axes

__all__ = [
    "Candidates",
    "heading_candidates",
    "nearest_candidate_error",
    "Resolution",
    "resolve",
    "pitch_roll_from_accel",
    "triad_heading_error",
    "triad_heading_std",
    "single_axis_heading_std",
    "single_axis_heading_error",
    "ClippedTheory",
    "clipped_single_axis_theory",
    "simulate_static_outputs",
    "MonteCarlo",
    "monte_carlo",
    "pair_probabilities",
    "four_position_heading_std",
    "stop_and_go",
    "StopSolutions",
    "stop_solutions",
    "ins_heading_change",
    "draw_device",
    "draw_candidate_pairs",
]

OMEGA_IE = earth.OMEGA_IE


# --------------------------------------------------------------------------
# TRIAD (Eqs. 1-3)
# --------------------------------------------------------------------------


def pitch_roll_from_accel(f_b: Vec3, g: float | None = None) -> tuple[Array, Array]:
    """Pitch and roll from averaged specific force (paper Eqs. 5-6).

    ``pitch = asin(f_y / g)``, ``roll = atan2(-f_x, f_z)``. Without ``g`` the
    norm ``|f|`` stands in for g (the paper gives no value, E000-13): that is the levelling
    :func:`navlib.alignment.level`. With ``g`` the paper's arcsine is kept (its argument clipped
    to [-1, 1]): an accelerometer scale error then enters the pitch, as the error theory assumes.

    Parameters
    ----------
    f_b : array_like, shape (..., 3)  (m/s^2)
    g : float, optional
        Gravity (m/s^2).

    Returns
    -------
    pitch, roll : ndarray, shape (...)  (rad)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude
    >>> from navlib.papers import north_finding as nf
    >>> f_b = attitude.euler_to_dcm(np.deg2rad([0.0, 5.0, -3.0])).T @ [0.0, 0.0, 9.8]
    >>> np.round(np.rad2deg(nf.pitch_roll_from_accel(f_b)), 6)
    array([ 5., -3.])
    """
    pitch, roll = level(f_b)  # validates f_b
    return (pitch, roll) if g is None else (_asin_pitch(f_b, scalar(g, "g", positive=True)), roll)


def _asin_pitch(f_b: Vec3, g: ArrayLike) -> Array:
    """Eq. (5) as printed, ``asin(f_y / g)`` with the argument clipped to [-1, 1], of checked ``f_b`` and ``g``."""
    return np.arcsin(np.clip(np.asarray(f_b, dtype=float)[..., 1] / g, -1.0, 1.0))


# --------------------------------------------------------------------------
# single-axis candidates and their resolution (Eqs. 8-12)
# --------------------------------------------------------------------------


@dataclass(frozen=True)
class Candidates:
    """Two heading candidates of one stop (paper Eqs. 9-11).

    Attributes
    ----------
    pair : ndarray, shape (..., 2)
        ``[alpha, 2 pi - alpha]`` wrapped into [0, 2 pi) (rad).
    alpha : ndarray, shape (...)
        ``acos`` of the clipped cosine, in [0, pi] (E000-10).
    cos_heading : ndarray, shape (...)
        Right side of Eq. (9) before clipping.
    clipped : ndarray of bool, shape (...)
        True where |cos_heading| > 1 was clipped (noise near 0 or 180 deg).
    pitch : ndarray, shape (...)
        Pitch from Eq. (5) (rad).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import earth
    >>> from navlib.papers import north_finding as nf
    >>> lat, psi = np.deg2rad(30.0), np.deg2rad(60.0)
    >>> w_y = earth.earth_rate_n(lat)[1] * np.cos(psi)                # a level forward gyro at heading 60 deg
    >>> cand = nf.heading_candidates(w_y, [0.0, 0.0, earth.gravity(lat)], lat)
    >>> np.round(np.rad2deg(cand.pair), 6), bool(cand.clipped)        # psi and its mirror image 360 - psi
    (array([ 60., 300.]), False)
    """

    pair: np.ndarray
    alpha: np.ndarray
    cos_heading: np.ndarray
    clipped: np.ndarray
    pitch: np.ndarray

    @property
    def n_clipped(self) -> int:
        """Number of clipped stops/trials."""
        return int(np.count_nonzero(self.clipped))


def heading_candidates(w_y: ArrayLike, f_b: Vec3, lat: float, h: float = 0.0) -> Candidates:
    """Heading candidates from the forward gyro and the accelerometers (Eqs. 5, 9, 10).

    Pitch is Eq. (5) literally, ``asin(f_y / g)`` with normal gravity g at
    ``lat`` and ``h``, so that :func:`single_axis_heading_error` is its exact
    linearisation.

    Parameters
    ----------
    w_y : array_like, shape (...)
        Averaged forward (y) gyro output (rad/s).
    f_b : array_like, shape (..., 3)
        Averaged specific force (m/s^2); only pitch is used (roll is not needed).
    lat : float
        Latitude (rad), |lat| <= MAX_LAT_DEG.
    h : float
        Height (m), for normal gravity.

    Returns
    -------
    Candidates

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import earth
    >>> from navlib.papers import north_finding as nf
    >>> lat = np.deg2rad(30.0)
    >>> w_y = earth.earth_rate_n(lat)[1] * np.cos(np.deg2rad([60.0, 120.0]))   # two headings, level
    >>> cand = nf.heading_candidates(w_y, [0.0, 0.0, earth.gravity(lat)], lat)
    >>> np.round(np.rad2deg(cand.pair), 6)
    array([[ 60., 300.],
           [120., 240.]])
    """
    w_y = as_array(w_y, "w_y", nonempty=True)
    phi = gyrocompass_latitude(lat)
    level(f_b)  # checks f_b as pitch_roll_from_accel does
    height = in_range(as_array(h, "h", nonempty=True), "h", -12e3, 100e3, "m")  # earth.gravity's heights
    return _candidates(w_y, f_b, phi, height)


def _candidates(w_y: Array, f_b: Vec3, phi: Array, height: Array) -> Candidates:
    """:func:`heading_candidates` of checked values (``phi`` in rad)."""
    pitch = _asin_pitch(f_b, _earth.gravity(phi, height, earth.WGS84))
    cos_h = (w_y - OMEGA_IE * np.sin(phi) * np.sin(pitch)) / (OMEGA_IE * np.cos(phi) * np.cos(pitch))
    clipped = np.abs(cos_h) > 1.0
    alpha = np.arccos(np.clip(cos_h, -1.0, 1.0))
    pair = np.stack([alpha, _attitude.wrap_2pi(2 * np.pi - alpha)], -1)
    return Candidates(pair, alpha, cos_h, clipped, pitch)


def nearest_candidate_error(pair: ArrayLike, heading: Angles) -> Array:
    """Error of the candidate nearest the true heading, wrapped (rad).

    The single-axis error when the ambiguity is resolved correctly (Fig. 4).

    Parameters
    ----------
    pair : array_like, shape (..., 2)
        Candidate pairs (rad).
    heading : array_like, broadcasting to (...)
        True headings (rad).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.papers import north_finding as nf
    >>> round(float(np.rad2deg(nf.nearest_candidate_error(np.deg2rad([61.0, 299.0]), np.deg2rad(300.0)))), 6)
    -1.0
    """
    return _nearest_error(as_array(pair, "pair", tail=(2,), nonempty=True), as_array(heading, "heading", nonempty=True))


def _nearest_error(pair: np.ndarray, heading: np.ndarray) -> np.ndarray:
    """:func:`nearest_candidate_error` of validated arrays."""
    e = _attitude.wrap_pi(pair - heading[..., None])
    return np.take_along_axis(e, np.argmin(np.abs(e), -1)[..., None], -1)[..., 0]


@dataclass(frozen=True)
class Resolution:
    """Outcome of the candidate-pair resolution (paper Eq. 12 and step 5).

    Attributes
    ----------
    heading : ndarray, shape (...)
        Chosen heading at position 2 (rad, [0, 2 pi)).
    dpsi_candidates : ndarray, shape (..., 4)
        ``[psi2(1)-psi1(1), psi2(1)-psi1(2), psi2(2)-psi1(1), psi2(2)-psi1(2)]``
        = ``{beta-alpha, alpha+beta-2pi, 2pi-alpha-beta, alpha-beta}`` (rad).
    residuals : ndarray, shape (..., 4)
        Candidate minus INS heading change, wrapped (or not) as requested.
    index : ndarray of int, shape (...)
        Winning candidate (0..3); ``index // 2`` is position 2's candidate.
    margin : ndarray, shape (...)
        |residual| of the nearest candidate giving a *different* heading minus the winner's (rad): 0 when two
        candidates fit equally well but point position 2 in different directions (a U-turn or a straight
        drive between headings whose pairs coincide: the hypotheses cannot be separated); ``inf`` when every
        candidate gives the same heading.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.papers import north_finding as nf
    >>> res = nf.resolve(np.deg2rad([60.0, 300.0]), np.deg2rad([150.0, 210.0]), np.deg2rad(90.0))
    >>> round(float(np.rad2deg(res.heading)), 6), int(res.index)
    (150.0, 0)
    """

    heading: np.ndarray
    dpsi_candidates: np.ndarray
    residuals: np.ndarray
    index: np.ndarray
    margin: np.ndarray

    @property
    def dpsi(self) -> np.ndarray:
        """The winning candidate heading change (rad)."""
        return np.take_along_axis(self.dpsi_candidates, self.index[..., None], -1)[..., 0]


def resolve(pair1: ArrayLike, pair2: ArrayLike, dpsi_ins: Angles, wrap: bool = True) -> Resolution:
    """Pick position 2's heading with the INS heading change (Eq. 12, step 5).

    Parameters
    ----------
    pair1, pair2 : array_like, shape (..., 2)
        Candidate pairs at positions 1 and 2 (rad), e.g. ``Candidates.pair``.
    dpsi_ins : array_like, shape (...)
        Heading change measured by the MEMS INS (rad). NaN (a drive refused
        by :func:`ins_heading_change`) raises ValueError: there is nothing
        to resolve with.
    wrap : bool
        Compare ``wrap_pi(candidate - dpsi_ins)`` (default, E000-07). ``False``
        reproduces the paper's literal unwrapped comparison, for demonstration.

    Returns
    -------
    Resolution

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.papers import north_finding as nf
    >>> pair1, pair2 = np.deg2rad([60.0, 300.0]), np.deg2rad([150.0, 210.0])   # candidates at two stops
    >>> res = nf.resolve(pair1, pair2, np.deg2rad(92.0))             # the INS measured a 92 deg turn
    >>> round(float(np.rad2deg(res.heading)), 6), np.round(np.rad2deg(res.residuals), 3)
    (150.0, array([ -2., 118.,  58., 178.]))
    """
    p1 = as_array(pair1, "pair1", tail=(2,), nonempty=True)
    p2 = as_array(pair2, "pair2", tail=(2,), nonempty=True)
    p1, p2 = broadcast(p1, p2, name="pair2", of="pair1, pair2")
    ins = as_array(dpsi_ins, "dpsi_ins", nonempty=True)
    cands = (p2[..., :, None] - p1[..., None, :]).reshape(p2.shape[:-1] + (4,))
    cands, ins = np.broadcast_arrays(cands, ins[..., None])
    diff = cands - ins
    res = _attitude.wrap_pi(diff) if flag(wrap, "wrap") else diff
    score = np.abs(res)
    index = np.argmin(score, axis=-1)
    best = np.take_along_axis(score, index[..., None], -1)
    p2b = np.broadcast_to(p2, cands.shape[:-1] + (2,))
    headings = np.repeat(p2b, 2, axis=-1)  # candidate j points position 2 at p2[j // 2]
    heading = np.take_along_axis(headings, index[..., None], -1)[..., 0]
    distinct = np.abs(_attitude.wrap_pi(headings - heading[..., None])) > 1e-9
    margin = np.where(distinct, score, np.inf).min(-1) - best[..., 0]
    margin = np.where(margin < 1e-9, 0.0, margin)  # equal fits to rounding: not separable
    return Resolution(heading, cands, res, index, margin)


# --------------------------------------------------------------------------
# error theory (Eqs. 13-20, errata E000-02 and E000-04)
# --------------------------------------------------------------------------


def triad_heading_error(C_bn: Dcm, dw_b: Vec3, lat: float) -> Array:
    """TRIAD heading error caused by a gyro error, Eq. (13) with its sign corrected.

    ``psi_hat - psi = -dw_E / (w_ie cos lat)`` with ``dw_n = C_bn dw_b``
    (E000-02: the printed ``+dw_E/...`` is the error of a counter-clockwise
    azimuth).

    Parameters
    ----------
    C_bn : array_like, shape (..., 3, 3)
    dw_b : array_like, shape (..., 3)
        Gyro error (rad/s).
    lat : float  (rad)

    Returns
    -------
    ndarray, shape (...)  (rad)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude
    >>> from navlib.papers import north_finding as nf
    >>> C_bn = attitude.euler_to_dcm([0.0, 0.0, 0.0])                # facing north: body x is east
    >>> round(float(np.rad2deg(nf.triad_heading_error(C_bn, [1e-7, 0.0, 0.0], np.deg2rad(30.0)))), 4)
    -0.0907
    """
    C = as_dcm(C_bn)
    dw = as_array(dw_b, "dw_b", tail=(3,), nonempty=True)
    dw_east = np.einsum("...j,...j->...", C[..., 0, :], dw)
    return -dw_east / (OMEGA_IE * np.cos(gyrocompass_latitude(lat)))


def triad_heading_std(sigma_gyro: float, lat: float) -> Array:
    r"""Eq. (16): TRIAD heading error std :math:`\sigma / (\omega_{ie} \cos\varphi)` (rad).

    ``sigma_gyro`` (rad/s) is the std of each horizontal gyro error (equal and
    uncorrelated, as the paper assumes); independent of heading.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.papers import north_finding as nf
    >>> round(float(np.rad2deg(nf.triad_heading_std(1e-7, np.deg2rad(30.0)))), 4)   # deg, any heading
    0.0907
    """
    s = positive(sigma_gyro, "sigma_gyro", allow_zero=True, nonempty=True)
    return s / (OMEGA_IE * np.cos(gyrocompass_latitude(lat)))


def _pitch(pitch: ArrayLike) -> Array:
    return in_range(as_array(pitch, "pitch", nonempty=True), "pitch", -np.pi / 2, np.pi / 2, "rad", lo_open=True, hi_open=True)


def single_axis_heading_std(
    heading: Angles, sigma_gyro: float, lat: float, pitch: Angles = 0.0, sigma_accel: float = 0.0, g: float | None = None
) -> Array:
    r"""Single-axis heading error std (rad): Eq. (20) or its full linearisation.

    With ``pitch = 0`` and ``sigma_accel = 0`` this is Eq. (20),
    :math:`\sigma_g / (\omega_{ie} \cos\varphi\, \lvert\sin\psi\rvert)`. Otherwise the full
    linearisation of Eq. (8) (E000-04):

    .. math::

        \sigma_\psi^2 = \frac{\sigma_g^2
            + \big(\omega_{ie} (\sin\varphi \cos\theta - \cos\varphi \sin\theta \cos\psi)\, \sigma_\theta\big)^2}
                             {(\omega_{ie} \cos\varphi \cos\theta \sin\psi)^2}, \qquad
        \sigma_\theta = \frac{\sigma_a}{g \cos\theta}

    Infinite at psi = 0 and pi, where the linearisation fails (E000-03).

    Parameters
    ----------
    heading : array_like  (rad)
    sigma_gyro : float  (rad/s)
        Std of the averaged forward-gyro error.
    lat : float  (rad)
    pitch : array_like  (rad)
    sigma_accel : float  (m/s^2)
        Std of the averaged forward-accelerometer error.
    g : float, optional
        Gravity (m/s^2); normal gravity at ``lat`` by default.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.papers import north_finding as nf
    >>> np.round(np.rad2deg(nf.single_axis_heading_std(np.deg2rad([90.0, 10.0]), 1e-7, np.deg2rad(30.0))), 4)   # Eq. (20)
    array([0.0907, 0.5225])
    """
    psi = as_array(heading, "heading", nonempty=True)
    th = _pitch(pitch)
    s_g = positive(sigma_gyro, "sigma_gyro", allow_zero=True, nonempty=True)
    s_a = positive(sigma_accel, "sigma_accel", allow_zero=True, nonempty=True)
    phi = gyrocompass_latitude(lat)
    grav = _earth.gravity(phi, np.zeros(()), earth.WGS84) if g is None else positive(g, "g", nonempty=True)
    s_th = s_a / (grav * np.cos(th))
    coupling = OMEGA_IE * (np.sin(phi) * np.cos(th) - np.cos(phi) * np.sin(th) * np.cos(psi))
    with np.errstate(divide="ignore"):
        return np.sqrt(s_g**2 + (coupling * s_th) ** 2) / np.abs(OMEGA_IE * np.cos(phi) * np.cos(th) * np.sin(psi))


def single_axis_heading_error(
    heading: Angles, pitch: Angles, lat: float, dw_y: ArrayLike, df_y: ArrayLike = 0.0, g: float | None = None
) -> Array:
    """Linearised single-axis heading error for given sensor errors (rad, E000-04).

    ``d psi = [-dw_y + w_ie (sin lat cos th - cos lat sin th cos psi) d th]
    / (w_ie cos lat cos th sin psi)`` with ``d th = df_y / (g cos th)``. With
    ``pitch = df_y = 0`` it is Eq. (19) solved for d psi.

    Parameters
    ----------
    heading, pitch : array_like  (rad)
    lat : float  (rad)
    dw_y : array_like
        Forward-gyro error (rad/s).
    df_y : array_like
        Forward-accelerometer error (m/s^2).
    g : float, optional
        Gravity (m/s^2); normal gravity at ``lat`` by default.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.papers import north_finding as nf
    >>> lat = np.deg2rad(30.0)
    >>> np.round(np.rad2deg(nf.single_axis_heading_error(np.deg2rad([90.0, 10.0]), 0.0, lat, 1e-7)), 4)   # 1e-7 rad/s gyro error
    array([-0.0907, -0.5225])
    """
    psi = as_array(heading, "heading", nonempty=True)
    th = _pitch(pitch)
    dw = as_array(dw_y, "dw_y", nonempty=True)
    df = as_array(df_y, "df_y", nonempty=True)
    phi = gyrocompass_latitude(lat)
    grav = _earth.gravity(phi, np.zeros(()), earth.WGS84) if g is None else positive(g, "g", nonempty=True)
    d_th = df / (grav * np.cos(th))
    coupling = OMEGA_IE * (np.sin(phi) * np.cos(th) - np.cos(phi) * np.sin(th) * np.cos(psi))
    with np.errstate(divide="ignore", invalid="ignore"):
        return (-dw + coupling * d_th) / (OMEGA_IE * np.cos(phi) * np.cos(th) * np.sin(psi))


@dataclass(frozen=True)
class ClippedTheory:
    """Single-axis heading error with the clipped cosine of Eq. (9), by quadrature (E000-03).

    Attributes
    ----------
    rmse : ndarray
        Root-mean-square error of the candidate nearest the truth (rad).
    p_clip : ndarray
        Probability that the cosine of Eq. (9) leaves [-1, 1] and is clipped.
    rel_sd : ndarray
        Relative standard deviation of a Monte Carlo RMSE from *one* trial,
        ``sqrt(E[e^4] / E[e^2]^2 - 1) / 2``; divide by ``sqrt(n)`` for n trials
        (``1 / sqrt(2 n)`` for Gaussian errors; larger here, where clipping
        piles errors up at one value).
    sigma_cos : ndarray
        Standard deviation of the estimated cosine.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.papers import north_finding as nf
    >>> th = nf.clipped_single_axis_theory(np.deg2rad([90.0, 1.0]), sigma_gyro=1e-6, lat=np.deg2rad(30.0))
    >>> np.round(np.rad2deg(th.rmse), 3), np.round(th.p_clip, 3)      # near north the cosine is clipped half the time
    (array([0.907, 5.885]), array([0.   , 0.496]))
    """

    rmse: np.ndarray
    p_clip: np.ndarray
    rel_sd: np.ndarray
    sigma_cos: np.ndarray


@boundary
def clipped_single_axis_theory(
    heading: Angles,
    sigma_gyro: Positive,
    lat: GyroLatitude,
    pitch: Angles = 0.0,
    sigma_accel: NonNegative = 0.0,
    g: float | None = None,
    n_sigma: Positive = 12.0,
    n_grid: int = 20001,
) -> ClippedTheory:
    """Error of the single-axis estimator where Eq. (20) fails: the cosine clipped, not linearised in psi.

    The cosine of Eq. (9) is linear in the gyro noise and, to first order, in
    the pitch error, so its estimate is ``cos psi + e`` with Gaussian ``e`` of
    standard deviation ``sigma_cos`` (the gyro term ``sigma_g / (w_ie cos lat cos th)``
    and the pitch term ``(cos psi tan th - tan lat) sigma_a / (g cos th)``).
    The estimator takes ``acos(clip(cos psi + e, -1, 1))`` and its mirror and
    keeps the candidate nearest the truth (the resolution assumed correct, as
    in Fig. 4). Its moments are integrated over ``e`` on a grid of ``n_grid``
    points within ``n_sigma`` standard deviations (trapezoid rule), so the
    result holds at every heading, including 0 and pi where Eq. (20) is
    infinite; away from them it tends to :func:`single_axis_heading_std`.

    Parameters
    ----------
    heading : array_like  (rad)
    sigma_gyro : float
        Std of the averaged forward-gyro error (rad/s).
    lat : float  (rad)
    pitch : array_like  (rad)
    sigma_accel : float
        Std of the averaged forward-accelerometer error (m/s^2).
    g : float, optional
        Gravity (m/s^2); normal gravity at ``lat`` by default.
    n_sigma : float
        Half-width of the integration grid in standard deviations.
    n_grid : int
        Grid points (odd, at least 101).

    Returns
    -------
    ClippedTheory

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.papers import north_finding as nf
    >>> lat = np.deg2rad(30.0)
    >>> th = nf.clipped_single_axis_theory(np.deg2rad(1.0), sigma_gyro=1e-6, lat=lat)
    >>> round(float(np.rad2deg(th.rmse)), 3)                          # deg, 1 deg from north
    5.885
    >>> round(float(np.rad2deg(nf.single_axis_heading_std(np.deg2rad(1.0), 1e-6, lat))), 3)   # Eq. (20) there: far too large
    51.986
    """
    psi, th = np.broadcast_arrays(as_array(heading, "heading", nonempty=True), _pitch(pitch))
    phi = np.asarray(lat)
    grav = _earth.gravity(phi, np.zeros(()), earth.WGS84) if g is None else scalar(g, "g", positive=True)
    if integer(n_grid, "n_grid", minimum=101) % 2 == 0:
        raise ValueError(f"n_grid: expected an odd integer of at least 101, got {n_grid!r}")
    s_gyro_cos = sigma_gyro / (OMEGA_IE * np.cos(phi) * np.cos(th))
    s_pitch_cos = (np.cos(psi) * np.tan(th) - np.tan(phi)) * sigma_accel / (grav * np.cos(th))
    s_cos = np.hypot(s_gyro_cos, s_pitch_cos)
    z = np.linspace(-n_sigma, n_sigma, int(n_grid))
    weight = np.exp(-0.5 * z**2) / np.sqrt(2 * np.pi)
    c = np.cos(psi)[..., None] + s_cos[..., None] * z
    alpha = np.arccos(np.clip(c, -1.0, 1.0))
    err = _nearest_error(np.stack([alpha, _attitude.wrap_2pi(2 * np.pi - alpha)], -1), psi[..., None])
    m2 = np.trapezoid(weight * err**2, z, axis=-1)
    m4 = np.trapezoid(weight * err**4, z, axis=-1)
    p_clip = ndtr((np.cos(psi) - 1.0) / s_cos) + ndtr((-1.0 - np.cos(psi)) / s_cos)
    with np.errstate(divide="ignore", invalid="ignore"):
        rel_sd = np.sqrt(np.maximum(m4 / m2**2 - 1.0, 0.0)) / 2
    return ClippedTheory(np.sqrt(m2), p_clip, rel_sd, s_cos)


# --------------------------------------------------------------------------
# Monte Carlo of Fig. 4
# --------------------------------------------------------------------------


@boundary
def simulate_static_outputs(
    hpr: Angles,
    lat: GyroLatitude,
    n_trials: Count,
    sigma_gyro: NonNegative,
    sigma_accel: NonNegative,
    rng: Rng,
    gyro_bias: Vec3 = 0.0,
    accel_bias: Vec3 = 0.0,
) -> tuple[Array, Array]:
    """Averaged outputs of a static IMU plus white noise, as in the paper's Monte Carlo.

    ``w = C_nb w_ie_n + b_g + sigma_gyro n``, ``f = C_nb [0, 0, g] + b_a + sigma_accel n``
    with independent standard normal ``n`` per axis and trial (gyro and
    accelerometer from separate child streams of ``rng``).

    Parameters
    ----------
    hpr : array_like, shape (..., 3)
        True attitudes (rad).
    lat : float  (rad)
    n_trials : int
        Trials per attitude, on a new axis before the vector axis.
    sigma_gyro : float  (rad/s)
    sigma_accel : float  (m/s^2)
    rng : numpy.random.Generator
    gyro_bias, accel_bias : array_like, broadcasting to (..., n_trials, 3)
        Deterministic errors added to every trial (rad/s, m/s^2).

    Returns
    -------
    w_ib_b, f_b : ndarray, shape (..., n_trials, 3)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.papers import north_finding as nf
    >>> w, f = nf.simulate_static_outputs(np.deg2rad([30.0, 0.0, 0.0]), 0.5, 4, 1e-6, 1e-3, np.random.default_rng(0))
    >>> w.shape, np.round(f.mean(0), 2) + 0.0                              # four trials; level: f points up
    ((4, 3), array([0.  , 0.  , 9.79]))
    """
    gyro_bias, accel_bias = _bias(gyro_bias, "gyro_bias"), _bias(accel_bias, "accel_bias")
    return _static_outputs(hpr, lat, n_trials, sigma_gyro, sigma_accel, rng, gyro_bias, accel_bias)


def _static_outputs(
    hpr: Angles,
    lat: float,
    n_trials: int,
    sigma_gyro: float,
    sigma_accel: float,
    rng: np.random.Generator,
    gyro_bias: Array,
    accel_bias: Array,
) -> tuple[Array, Array]:
    """:func:`simulate_static_outputs` of checked values (``hpr`` is checked by :func:`navlib.attitude.euler_to_dcm`)."""
    C_nb = np.swapaxes(attitude.euler_to_dcm(hpr), -1, -2)
    phi = np.asarray(lat)
    r_gyro, r_accel = rng.spawn(2)
    w_true = C_nb @ _earth.earth_rate_n(phi, earth.WGS84)
    f_true = C_nb @ np.array([0.0, 0.0, float(_earth.gravity(phi, np.zeros(()), earth.WGS84))])
    shape = w_true.shape[:-1] + (int(n_trials), 3)
    w = w_true[..., None, :] + gyro_bias + sigma_gyro * r_gyro.standard_normal(shape)
    f = f_true[..., None, :] + accel_bias + sigma_accel * r_accel.standard_normal(shape)
    return w, f


def _bias(x: ArrayLike, name: str) -> Array:
    b = as_array(x, name, nonempty=True)
    return b if b.ndim == 0 else as_array(b, name, tail=(3,), nonempty=True)


@dataclass(frozen=True)
class MonteCarlo:
    """Heading errors of the Fig. 4 Monte Carlo (rad), shape (n_headings, n_trials).

    ``single`` is the error of the candidate nearest the truth (the resolution
    assumed correct, as in Fig. 4); ``triad_raw`` uses Eq. (2) without
    orthonormalisation; ``clipped`` marks trials whose cosine was clipped.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.papers import north_finding as nf
    >>> mc = nf.monte_carlo(np.deg2rad([45.0]), 0.0, 0.0, np.deg2rad(30.0), 200, 1e-6, 1e-3, np.random.default_rng(0))
    >>> mc.triad.shape, round(float(np.rad2deg(np.std(mc.triad))), 2)  # TRIAD error std (deg)
    ((1, 200), 0.9)
    """

    heading: np.ndarray
    triad: np.ndarray
    triad_raw: np.ndarray
    single: np.ndarray
    clipped: np.ndarray


@boundary
def monte_carlo(
    headings: Angles,
    pitch: Annotated[float, Check("scalar", within=(-np.pi / 2, np.pi / 2), open_ends=(True, True))],
    roll: Annotated[float, Check("scalar", within=(-np.pi, np.pi))],
    lat: GyroLatitude,
    n_trials: Count,
    sigma_gyro: NonNegative,
    sigma_accel: NonNegative,
    rng: Rng,
) -> MonteCarlo:
    """TRIAD and single-axis heading errors over a heading grid (paper Fig. 4).

    Parameters
    ----------
    headings : array_like, shape (H,)
        True headings (rad).
    pitch, roll : float
        True tilt (rad); the paper uses 5 deg each.
    lat : float  (rad)
    n_trials : int
        Trials per heading (paper: 1000).
    sigma_gyro, sigma_accel : float
        White noise on the averaged outputs (rad/s, m/s^2), paper: 0.01 deg/h, 100 ug.
    rng : numpy.random.Generator

    Returns
    -------
    MonteCarlo

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.papers import north_finding as nf
    >>> mc = nf.monte_carlo(np.deg2rad([45.0]), 0.0, 0.0, np.deg2rad(30.0), 200, 1e-6, 1e-3, np.random.default_rng(0))
    >>> round(float(np.rad2deg(nf.triad_heading_std(1e-6, np.deg2rad(30.0)))), 2)   # Eq. (16) predicts the same
    0.91
    """
    psi = as_array(headings, "headings", shape=(None,), nonempty=True)
    hpr = np.stack(np.broadcast_arrays(psi, pitch, roll), -1)
    w, f = _static_outputs(hpr, lat, n_trials, sigma_gyro, sigma_accel, rng, np.zeros(()), np.zeros(()))
    phi = np.asarray(lat)
    C_raw = _attitude.triad(f, w, phi, earth.WGS84)
    truth = psi[:, None]
    err_raw = _attitude.wrap_pi(triad_heading(C_raw) - truth)
    err_triad = _attitude.wrap_pi(triad_heading(attitude.orthonormalize(C_raw)) - truth)
    cand = _candidates(w[..., 1], f, phi, np.zeros(()))
    return MonteCarlo(psi, err_triad, err_raw, _nearest_error(cand.pair, truth), cand.clipped)


# --------------------------------------------------------------------------
# ambiguity of the resolution (extension, erratum E000-06)
# --------------------------------------------------------------------------


def pair_probabilities(heading1: Angles, heading2: Angles, sigma_ins: ArrayLike) -> Array:
    """Probability that each candidate wins the resolution, for a Gaussian INS error.

    With noise-free candidates the four heading-change candidates sit at the
    true change plus the shifts ``0`` (true pair), ``2 psi1`` (position 1
    swapped), ``-2 psi2`` (position 2 swapped) and ``-2 dpsi`` (both swapped),
    all mod 2 pi. The INS error e ~ N(0, sigma_ins^2) picks the shift nearest
    to e on the circle, so each probability is the Gaussian mass of that
    shift's Voronoi arc (exact up to the N(0, sigma) mass beyond +-3 pi).

    Parameters
    ----------
    heading1, heading2 : array_like  (rad)
        True headings at the two stops.
    sigma_ins : array_like  (rad, > 0)
        Std of the INS heading-change error.

    Returns
    -------
    ndarray, shape (..., 4)
        ``[true pair, position 1 swapped, position 2 swapped, both swapped]``;
        heading 2 is wrong in the last two (by 2 dist(psi2, {0, pi})).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.papers import north_finding as nf
    >>> np.round(nf.pair_probabilities(np.deg2rad(60.0), np.deg2rad(150.0), np.deg2rad(5.0)), 4)   # the true pair wins
    array([1., 0., 0., 0.])
    """
    p1, p2 = as_array(heading1, "heading1", nonempty=True), as_array(heading2, "heading2", nonempty=True)
    sigma = positive(sigma_ins, "sigma_ins", nonempty=True)
    p1, p2, sigma = np.broadcast_arrays(p1, p2, sigma)
    shape = p1.shape
    p1, p2, sigma = p1.ravel(), p2.ravel(), sigma.ravel()
    out = np.empty((p1.size, 4))
    for i in range(0, p1.size, _PAIR_BLOCK):  # each point on its own: blocks bound the twelve-wide temporaries
        block = slice(i, i + _PAIR_BLOCK)
        out[block] = _pair_mass(p1[block], p2[block], sigma[block])
    return out.reshape(shape + (4,))


_PAIR_BLOCK = 1 << 15
"""Points per block of :func:`pair_probabilities` (its temporaries: about 1 kB per point)."""


def _pair_mass(p1: np.ndarray, p2: np.ndarray, sigma: np.ndarray) -> np.ndarray:
    """:func:`pair_probabilities` of 1-D checked arrays of equal length: shape (n, 4)."""
    shifts = _attitude.wrap_pi(np.stack([np.zeros_like(p1), 2 * p1, -2 * p2, -2 * (p2 - p1)], -1))
    # periodic images so that every Voronoi arc is bounded on both sides
    images = np.concatenate([shifts - 2 * np.pi, shifts, shifts + 2 * np.pi], -1)
    order = np.argsort(images, axis=-1, kind="stable")
    s = np.take_along_axis(images, order, -1)
    mid = (s[..., 1:] + s[..., :-1]) / 2
    lo = np.concatenate([np.full(s.shape[:-1] + (1,), -np.inf), mid], -1)
    hi = np.concatenate([mid, np.full(s.shape[:-1] + (1,), np.inf)], -1)
    mass = ndtr(hi / sigma[..., None]) - ndtr(lo / sigma[..., None])
    owner = order % 4
    out = np.zeros(p1.shape + (4,))
    for k in range(4):
        out[..., k] = np.where(owner == k, mass, 0.0).sum(-1)
    return out


# --------------------------------------------------------------------------
# four-position north finding on a turntable (extension)
# --------------------------------------------------------------------------


def four_position_heading_std(sigma_gyro: float, lat: float) -> Array:
    r"""Four-position heading std :math:`\sigma / (\sqrt{2}\, \omega_{ie} \cos\varphi)` (rad), any heading.

    ``sigma_gyro`` (rad/s) is the std of each position's averaged output.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.papers import north_finding as nf
    >>> round(float(np.rad2deg(nf.four_position_heading_std(1e-6, np.deg2rad(30.0)))), 3)   # deg; any heading
    0.642
    """
    return triad_heading_std(sigma_gyro, lat) / np.sqrt(2.0)


# --------------------------------------------------------------------------
# the vehicle test (Table 1 stand-in)
# --------------------------------------------------------------------------


@boundary
def stop_and_go(
    headings: Angles,
    stop_duration: Positive,
    drive_duration: Annotated[float, Check("scalar", within=(30.0, np.inf, "s (accelerate, turn, brake)"))],
    speed: Positive,
    pitches: Angles,
    rolls: Angles,
) -> tuple[list[Segment], Array]:
    """Segments of a drive with stops at given headings (Table 1 stand-in).

    The vehicle starts at rest at ``headings[0]``; each drive accelerates,
    turns by ``wrap_pi(headings[k+1] - headings[k])`` while cruising and
    brakes, ramping pitch and roll to the next stop's values.

    Parameters
    ----------
    headings : array_like, shape (S,)
        Stop headings (rad).
    stop_duration, drive_duration : float
        Seconds per stop and per drive (drives >= 30 s).
    speed : float
        Cruising speed (m/s).
    pitches, rolls : array_like, shape (S,)
        Stop attitudes (rad); the first stop is level as :func:`navlib.trajectory.vehicle` starts level.

    Returns
    -------
    segments : list of Segment
        For :func:`navlib.trajectory.vehicle` with ``heading0 = headings[0]``.
    stops : ndarray, shape (S, 2)
        Start and end time of each stop (s).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib.papers import north_finding as nf
    >>> segments, stops = nf.stop_and_go(np.deg2rad([0.0, 90.0]), 10.0, 30.0, 2.0, [0.0, 0.0], [0.0, 0.0])
    >>> len(segments), stops
    (5, array([[ 0., 10.],
           [40., 50.]]))
    """
    psi = as_array(headings, "headings", shape=(None,), nonempty=True)
    if psi.size < 2:
        raise ValueError(f"headings: expected a 1-D array of >= 2 stops, got {psi.shape}")
    th, ro = pitch_roll(pitches, rolls, ("pitches", "rolls"), shape=psi.shape, of="headings: one per stop")
    ramp = 10.0
    segments = [unchecked(Segment, duration=stop_duration, speed=0.0, pitch=th[0], roll=ro[0])]
    stops = [(0.0, stop_duration)]
    t = stop_duration
    for k in range(1, psi.size):
        turn = float(_attitude.wrap_pi(psi[k] - psi[k - 1]))
        segments += [
            unchecked(Segment, duration=ramp, speed=speed),
            unchecked(Segment, duration=drive_duration - 2 * ramp, turn=turn),
            unchecked(Segment, duration=ramp, speed=0.0, pitch=th[k], roll=ro[k]),
            unchecked(Segment, duration=stop_duration),
        ]
        t += drive_duration
        stops.append((t, t + stop_duration))
        t += stop_duration
    return segments, np.array(stops)


@dataclass(frozen=True)
class StopSolutions:
    """North finding at each stop of a drive, shapes (..., S) and (..., S, 2).

    ``candidates`` are the single-axis pairs (forward gyro + accelerometers),
    ``triad`` the three-axis TRIAD headings (rad), ``clipped`` the clipping flags,
    ``f_mean`` each stop's mean specific force. ``faults`` stacks the faults of the
    stops' windows (:func:`navlib.alignment.static_means`), counts of shape (..., S):
    dropped (``"nan"``), rejected (``"outlier"``), saturated and frozen (``"stuck"``)
    samples per sensor, and ``("window", "refused")`` 1 for a refused stop, which with
    ``strict=False`` has NaN candidates and heading. ``windows`` holds each stop's
    :class:`navlib.alignment.StaticWindow`.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import trajectory
    >>> from navlib.papers import north_finding as nf
    >>> traj = trajectory.static(2.0, 0.01, [0.5, 2.0, 10.0], np.deg2rad([60.0, 0.0, 0.0]))
    >>> w_ib_b, f_b = trajectory.ideal_imu(traj)
    >>> w_ib_b += 1e-9 * np.sin(np.arange(200.0))[:, None]           # not frozen (a constant output counts as stuck)
    >>> f_b += 1e-6 * np.sin(np.arange(200.0))[:, None]
    >>> sol = nf.stop_solutions(w_ib_b, f_b, windows=[[0, 100], [100, 200]], lat=0.5, h=10.0)
    >>> sol.candidates.shape, np.round(np.rad2deg(sol.triad), 4)
    ((2, 2), array([60., 60.]))
    """

    candidates: np.ndarray
    triad: np.ndarray
    clipped: np.ndarray
    f_mean: np.ndarray
    faults: robust.FaultReport
    windows: tuple[StaticWindow, ...] = ()


def _stacked_faults(reports: list[robust.FaultReport]) -> robust.FaultReport:
    """The stops' fault reports as one, each count stacked on a last (stop) axis."""
    keys = dict.fromkeys(key for r in reports for key in r.counts)
    return robust.FaultReport({key: np.stack(np.broadcast_arrays(*(np.asarray(r[key]) for r in reports)), -1) for key in keys})


def stop_solutions(
    w_ib_b: Vec3Series | ImuSamples,
    f_b: Vec3Series | None = None,
    windows: ArrayLike | None = None,
    lat: float | None = None,
    h: float = 0.0,
    *,
    time: Times | None = None,
    strict: bool = True,
    **window_options: Any,
) -> StopSolutions:
    """Average each stop window (:func:`navlib.alignment.static_windows`) and solve it with TRIAD and the
    single-axis method.

    Parameters
    ----------
    w_ib_b, f_b : array_like, shape (..., N, 3)
        IMU samples of the whole run (rad/s, m/s^2); NaN marks dropouts. An
        :class:`navlib.imu.ImuSamples` as ``w_ib_b`` supplies ``f_b`` and the
        ``full_scale_gyro`` / ``full_scale_accel`` window options (not its ``dt``:
        windows are sample indices, or times with ``time``).
    windows : array_like, shape (S, 2)
        ``[start, end)`` of the stops: integer sample indices, or times (s)
        when ``time`` is given.
    lat, h : float
        Latitude (rad) and height (m) of the site.
    time : array_like, shape (N,), optional
        Strictly increasing sample times (s), e.g. from ``timing.sanitize``
        (which removes duplicated and out-of-order timestamps and reports
        them); the windows are then cut by time, so dropped samples do not
        shift them.
    strict : bool
        Raise for a refused stop (default) or return NaN for it (see
        :func:`navlib.alignment.static_means`).
    **window_options
        ``accel_tol``, ``min_fraction``, ``outlier_k``, ``full_scale_gyro``,
        ``full_scale_accel``, ``stuck_fraction``: the tests of each stop
        (:class:`navlib.alignment.StaticTests`).
        ``stuck_fraction`` defaults to 0.5 here: a stop in which a gyro or
        accelerometer axis repeats one reading over half of its valid samples
        is refused (``("gyro", "stuck")``; a frozen gyro otherwise passes with a
        heading error of many degrees). Pass ``stuck_fraction=None`` for
        noise-free simulated data, whose readings repeat exactly.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import trajectory
    >>> from navlib.papers import north_finding as nf
    >>> traj = trajectory.static(2.0, 0.01, [0.5, 2.0, 10.0], np.deg2rad([60.0, 0.0, 0.0]))
    >>> w_ib_b, f_b = trajectory.ideal_imu(traj)
    >>> w_ib_b += 1e-9 * np.sin(np.arange(200.0))[:, None]           # not frozen (a constant output counts as stuck)
    >>> f_b += 1e-6 * np.sin(np.arange(200.0))[:, None]
    >>> sol = nf.stop_solutions(w_ib_b, f_b, windows=[[0, 200]], lat=0.5, h=10.0)   # one stop of 2 s
    >>> np.round(np.rad2deg(sol.candidates[0]), 4), np.round(np.rad2deg(sol.triad), 4)
    (array([ 60., 300.]), array([60.]))
    """
    tests = StaticTests(**{"stuck_fraction": 0.5, **window_options})
    stats = static_windows(w_ib_b, f_b, windows, lat, h, tests, time=time, strict=strict)
    w_mean = np.stack([m.w_mean for m in stats], -2)
    f_mean = np.stack([m.f_mean for m in stats], -2)
    ok = np.all(np.isfinite(f_mean), -1)
    f_safe = np.where(ok[..., None], f_mean, [0.0, 0.0, 9.8])  # refused stops: solved on a dummy, set NaN
    w_safe = np.where(ok[..., None], w_mean, 1e-5)
    phi, height = np.asarray(lat, dtype=float), np.asarray(h, dtype=float)  # checked by static_windows
    cand = _candidates(w_safe[..., 1], f_safe, phi, height)
    heading = triad_heading(attitude.orthonormalize(_attitude.triad(f_safe, w_safe, phi, earth.WGS84)))
    pair = np.where(ok[..., None], cand.pair, np.nan)
    return StopSolutions(
        pair, np.where(ok, heading, np.nan), cand.clipped & ok, f_mean, _stacked_faults([m.faults for m in stats]), stats
    )


def _hold_last(w: Array, dts: Array) -> tuple[Array, Array, NDArray[np.bool_]]:
    """Forward-fill NaN rows along axis -2 (back-fill leading ones); the longest dropout run (s) and the
    trials without any valid row."""
    bad = ~np.all(np.isfinite(w), -1)
    n = w.shape[-2]
    empty = bad.all(-1)
    # leading dropouts take the first valid sample; a trial without any is refused (held as it is)
    filled = np.where(empty[..., None, None], w, 0.0)
    if not empty.all():
        filled[~empty] = robust.hold(w[~empty], leading="first", name="w_ib_b")[0]
    # longest run of consecutive dropouts, in seconds
    run = np.zeros(bad.shape[:-1])
    longest = np.zeros(bad.shape[:-1])
    for i in range(n):
        run = np.where(bad[..., i], run + dts[i], 0.0)
        longest = np.maximum(longest, run)
    return filled, longest, empty


@boundary
def ins_heading_change(
    w_ib_b: Vec3Series | ImuSamples,
    f_start: Vec3,
    dt: Interval | None = None,
    lat: GyroLatitude | None = None,
    earth_rate: Annotated[str, Check("choice", options=("vertical", "none", "full"))] = "vertical",
    *,
    max_gap: NonNegative = 0.1,
    full_scale_gyro: Limit | None = None,
) -> Array:
    """MEMS strapdown heading change over a drive, started with heading 0 (paper step 2).

    The attitude starts at heading 0 with pitch and roll from ``f_start``
    (Eqs. 5-6) and integrates the gyro with
    :func:`navlib.strapdown.integrate_attitude`. Since the true heading is
    unknown, the horizontal Earth rate cannot be removed correctly (E000-12):

    * ``"vertical"`` (default) removes only ``w_ie sin(lat)`` about Up, which
      does not depend on heading;
    * ``"none"`` ignores Earth rate (heading drifts by ``w_ie sin lat`` per s);
    * ``"full"`` removes ``[0, w_ie cos lat, w_ie sin lat]`` as if heading 0
      were true, i.e. the horizontal part in the wrong direction (a tilt
      error, second order in heading over a short drive).

    Faults (a refused drive gives NaN, which :func:`resolve` does not accept, so
    it cannot pass unnoticed; ``robust.fault_report(w_ib_b, "gyro",
    full_scale=full_scale_gyro)`` counts the held and saturated samples per drive):

    * dropouts: NaN gyro samples are replaced by the last valid sample
      (``"nan"``); the heading error this adds is at most the rate change
      across a gap times its length, so a drive with a run of dropouts longer
      than ``max_gap`` (default 0.1 s: <= 0.3 deg for a 3 deg/s turn starting
      inside the gap) is refused. A 30-s gap in a 60-s drive is refused.
    * saturation: with ``full_scale_gyro`` (gyro range, rad/s), a drive with
      samples at the rails is refused (``"saturated"``): the turn was faster
      than the clipped reading.
    * timing: ``dt`` may be per-sample intervals (``timing.intervals`` after
      ``timing.sanitize``). Each sample's rotation ``w_k dt_k`` is integrated
      exactly; the Earth-rate removal uses the mean interval, which is exact
      for the total and differs per step by second-order terms only.
    * outliers: a gyro spike of size s on one sample adds s dt to the heading
      change; not detected here (a turning vehicle has no static median).

    Parameters
    ----------
    w_ib_b : array_like, shape (..., N, 3), or ImuSamples
        MEMS gyro samples of the drive (rad/s); NaN marks dropouts. An
        :class:`navlib.imu.ImuSamples` here supplies ``dt`` and ``full_scale_gyro``.
    f_start : array_like, shape (..., 3)
        Averaged specific force at the start stop (m/s^2).
    dt : float or array_like, shape (N,)
        Sample interval (s), or the interval after each sample; required with arrays.
    lat : float  (rad)
    earth_rate : {"vertical", "none", "full"}
    max_gap : float
        Longest run of dropouts bridged by holding the last sample (s).
    full_scale_gyro : float, optional
        Gyro range (rad/s); None: no saturation check.

    Returns
    -------
    ndarray, shape (...)
        Heading change, wrapped into (-pi, pi] (rad); NaN for refused drives.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import trajectory
    >>> from navlib.papers import north_finding as nf
    >>> traj = trajectory.static(1.0, 0.01, [0.5, 2.0, 10.0], [0.0, 0.0, 0.0])
    >>> w_ib_b, f_b = trajectory.ideal_imu(traj)
    >>> w_ib_b[:, 2] -= np.pi / 2                                     # turning clockwise at 90 deg/s for 1 s
    >>> dpsi = nf.ins_heading_change(w_ib_b, f_b[0], 0.01, lat=0.5)
    >>> round(float(np.rad2deg(dpsi)), 3)
    90.0
    """
    if lat is None:
        raise ValueError("lat: required (rad)")
    w_ie = _earth.earth_rate_n(np.asarray(lat), earth.WGS84)
    rates = {"vertical": w_ie * [0, 0, 1], "none": np.zeros(3), "full": w_ie}
    if isinstance(w_ib_b, ImuSamples):  # samples and intervals checked by the record
        w, _, dts, full_scale_gyro, _ = unpack(w_ib_b, dt=dt, full_scale_gyro=full_scale_gyro)
    else:
        w = as_array(w_ib_b, "w_ib_b", tail=(3,), min_ndim=1, allow_nan=True)
        dts = sample_intervals(dt, w.shape[-2])
    small_turns(w, dts)
    step = float(dts[0]) if np.all(dts == dts[0]) else float(dts.mean())
    fs = np.inf if full_scale_gyro is None else full_scale_gyro
    pitch, roll = level(
        broadcast_to(
            as_array(f_start, "f_start", tail=(3,), nonempty=True), "f_start", w.shape[:-2] + (3,), of="the trials of w_ib_b"
        )
    )
    with np.errstate(invalid="ignore"):
        saturated = np.any(np.abs(w) >= fs, (-2, -1))  # NaN compares False
    if np.all(np.isfinite(w)):
        longest, empty = np.zeros(w.shape[:-2]), np.zeros(w.shape[:-2], dtype=bool)
    else:
        w, longest, empty = _hold_last(w, dts)
        w = np.where(empty[..., None, None], 0.0, w)
    if not np.all(dts == step):
        w = w * (dts / step)[:, None]  # w_k dt_k integrated exactly with the mean interval
    refused = empty | (longest > max_gap) | saturated
    q0 = attitude.euler_to_quat(np.stack([np.zeros_like(pitch), pitch, roll], -1))
    q = _attitude.integrate(_attitude.unit(q0), w, np.array([step]), rates[earth_rate])  # unit as as_quat makes it
    end = attitude.quat_to_dcm(q[..., -1, :])
    dpsi = _attitude.wrap_pi(np.arctan2(end[..., 0, 1], end[..., 1, 1]))
    if np.any(refused):
        dpsi = np.where(refused, np.nan, dpsi)
    return dpsi


# --------------------------------------------------------------------------
# the paper's schematics, redrawn (Figs. 2 and 3); matplotlib is imported only here
# --------------------------------------------------------------------------
# Not in __all__: drawing helpers for notebook 01, outside the fuzzed numerical API.

_COMPASS = "0.55"  # reference (north, east) axes
_BODY = "tab:blue"  # body / sensor frame
_GYRO = "tab:orange"  # the single optical gyro and what it senses
_MIRROR = "0.45"  # the mirror candidate


def _map_angle(heading_deg: float) -> float:
    """Plot angle (deg, counter-clockwise from +x = east) of a heading (deg, clockwise from north)."""
    return 90.0 - heading_deg


def _unit(angle_deg: float) -> np.ndarray:
    a = np.deg2rad(angle_deg)
    return np.array([np.cos(a), np.sin(a)])


def _arrow(
    ax: Axes, start: Array, end: Array, color: str, style: str = "-", width: float = 1.6, label: str | None = None
) -> None:
    ax.annotate(
        "",
        tuple(end),
        tuple(start),
        arrowprops={"arrowstyle": "-|>", "color": color, "linewidth": width, "linestyle": style, "shrinkA": 0, "shrinkB": 0},
    )
    if label is not None:
        ax.plot([], [], color=color, linestyle=style, linewidth=width, label=label)


def draw_device(ax: Axes, heading_deg: float = 30.0) -> None:
    """Paper Fig. 2 redrawn: the robot seen from above, its body frame b (= the sensor frame s of the
    calibrated MEMS IMU) and the single optical gyro along the forward axis y_s.

    The map has east to the right and north up; the robot points at ``heading_deg`` (clockwise from
    north, paper Eq. 3). The horizontal Earth rate omega_ie cos L points north; the y gyro senses its
    projection on the forward axis, ``omega_ie cos L cos psi`` (level, Eq. 8), drawn in orange.

    Parameters
    ----------
    ax : matplotlib Axes
        Drawn on with an equal aspect ratio and the axes hidden.
    heading_deg : float
        Heading of the robot (deg), any finite value (wrapped to [0, 360)).

    Examples
    --------
    >>> import matplotlib.pyplot as plt
    >>> from navlib.papers import north_finding as nf
    >>> fig, ax = plt.subplots()
    >>> nf.draw_device(ax, heading_deg=30.0)
    >>> len(ax.patches) + len(ax.lines) > 0
    True
    >>> plt.close(fig)
    """
    axes(ax)
    psi = float(scalar(heading_deg, "heading_deg")) % 360.0
    from matplotlib.patches import Polygon  # noqa: PLC0415 -- navlib imports without matplotlib

    fwd, right = _unit(_map_angle(psi)), _unit(_map_angle(psi + 90.0))

    def box(half_width: float, t0: float, t1: float, **kw: Any) -> None:  # a rectangle along the forward axis, from t0 to t1
        ax.add_patch(
            Polygon([s * half_width * right + t * fwd for s, t in ((-1, t0), (1, t0), (1, t1), (-1, t1))], closed=True, **kw)
        )

    box(0.45, -0.8, 0.8, facecolor="0.95", edgecolor="0.4", linewidth=1)  # the robot
    ax.add_patch(
        Polygon(
            [0.45 * right + 0.55 * fwd, -0.45 * right + 0.55 * fwd, 0.8 * fwd],
            closed=True,
            facecolor="0.86",
            edgecolor="0.4",
            linewidth=0.8,
        )
    )  # its nose
    _plots.plane_frame(ax, (0.0, 0.0), 0.0, ("E", "N"), 2.0, _COMPASS)
    _plots.plane_frame(ax, (0.0, 0.0), _map_angle(psi + 90.0), ("$x_b, x_s$ (right)", "$y_b, y_s$ (forward)"), 1.6, _BODY)
    box(0.07, 0.15, 0.5, facecolor=_GYRO, edgecolor="0.2", linewidth=0.8)  # the optical gyro
    ax.annotate(
        "optical gyro\n(axis $y_s$)",
        tuple(0.33 * fwd),
        tuple(0.33 * fwd - 1.25 * right),
        fontsize=8,
        color=_GYRO,
        ha="center",
        va="center",
        arrowprops={"arrowstyle": "-", "color": _GYRO, "linewidth": 0.8},
    )
    box(0.1, -0.1, 0.1, facecolor="0.3", edgecolor="0.2")  # the MEMS IMU
    ax.annotate(
        "MEMS IMU",
        (0.0, 0.0),
        tuple(-1.05 * fwd - 0.75 * right),
        fontsize=8,
        color="0.25",
        ha="center",
        va="center",
        arrowprops={"arrowstyle": "-", "color": "0.4", "linewidth": 0.8},
    )
    # the horizontal Earth rate along north and its projection on the gyro axis
    r = 1.45
    tip = r * np.cos(np.deg2rad(psi)) * fwd
    ax.plot([0.0, tip[0]], [r, tip[1]], ":", color=_GYRO, linewidth=1)
    ax.plot([0, tip[0]], [0, tip[1]], color=_GYRO, linewidth=4, alpha=0.5, solid_capstyle="butt")
    ax.plot([0.0], [r], "o", color=_COMPASS, markersize=4)
    ax.text(-0.08, r, r"$\omega_{ie}\cos L$", fontsize=9, color=_COMPASS, ha="right", va="center")
    label_at = tip + 0.15 * right
    ax.text(label_at[0], label_at[1], r"$w_y=\omega_{ie}\cos L\,\cos\psi$", fontsize=9, color=_GYRO, ha="left", va="top")
    _plots.angle_arc(ax, (0.0, 0.0), 1.0, _map_angle(psi), 90.0, r"$\psi$", "tab:red")
    ax.set(xlim=(-2.3, 2.6), ylim=(-1.5, 2.4), aspect="equal")
    ax.set_axis_off()


def draw_candidate_pairs(ax: Axes, heading1_deg: float, heading2_deg: float, dpsi_ins_error_deg: float = 0.0) -> None:
    """Paper Fig. 3 redrawn: the two mirror-image heading candidates at two stops and how the MEMS INS
    heading change picks the pair (Eqs. 10-12).

    At each stop the y gyro gives cos psi only (Eq. 9), so psi and its mirror image 2 pi - psi about
    the north axis fit equally well: alpha = arccos(cos psi1) and 2 pi - alpha at stop 1, beta and
    2 pi - beta at stop 2. The heading change measured by the MEMS INS between the stops, carried from
    stop 1's true heading (dotted green), lands next to one candidate at stop 2: that one is kept.

    Parameters
    ----------
    ax : matplotlib Axes
    heading1_deg, heading2_deg : float
        True headings at the two stops (deg, clockwise from north; wrapped to [0, 360)).
    dpsi_ins_error_deg : float
        Error of the INS heading change (deg), drawn into the green arrow.

    Examples
    --------
    >>> import matplotlib.pyplot as plt
    >>> from navlib.papers import north_finding as nf
    >>> fig, ax = plt.subplots()
    >>> nf.draw_candidate_pairs(ax, 60.0, 150.0)
    >>> len(ax.lines) > 0
    True
    >>> plt.close(fig)
    """
    axes(ax)
    psis = [float(scalar(h, name)) % 360.0 for h, name in ((heading1_deg, "heading1_deg"), (heading2_deg, "heading2_deg"))]
    err = float(scalar(dpsi_ins_error_deg, "dpsi_ins_error_deg"))
    from matplotlib.patches import Circle  # noqa: PLC0415 -- navlib imports without matplotlib

    centres = [np.array([0.0, 0.0]), np.array([3.2, 0.0])]
    for k, (c, psi, name) in enumerate(zip(centres, psis, ("α", "β"), strict=True)):
        ax.add_patch(Circle(tuple(c), 1.0, fill=False, edgecolor="0.8", linewidth=1))
        ax.plot([c[0], c[0]], [c[1] - 1.15, c[1] + 1.15], ":", color=_COMPASS, linewidth=0.8)  # the mirror axis
        ax.text(c[0], c[1] + 1.3, "N", ha="center", va="bottom", color=_COMPASS)
        ax.text(c[0], c[1] - 1.55, f"stop {k + 1}", ha="center", va="top", fontsize=10)
        a = np.rad2deg(np.arccos(np.cos(np.deg2rad(psi))))  # Eq. (10)/(11): in [0, 180]
        pair = ((psi, "-", _BODY),) if a < 1e-9 or a > 180.0 - 1e-9 else ((psi, "-", _BODY), (360.0 - psi, "--", _MIRROR))
        for cand, style, color in pair:  # at 0 and 180 deg the two candidates coincide (Eq. 10)
            _arrow(ax, c, c + 0.95 * _unit(_map_angle(cand)), color, style)
            label = (
                f"{name} = 2π − {name} = {a:.0f}°"
                if len(pair) == 1
                else f"{name} = {a:.0f}°"
                if abs(cand - a) < 1e-9
                else f"2π − {name} = {360.0 - a:.0f}°"
            )
            at = c + 1.12 * _unit(_map_angle(cand))
            ax.text(
                at[0],
                at[1],
                label,
                fontsize=8,
                color=color,
                ha="left" if np.sin(np.deg2rad(cand)) >= 0 else "right",
                va="center",
            )
        alpha_is_true = abs(psi - a) < 1e-9  # the arcs take the colour of their candidate's arrow
        _plots.angle_arc(ax, c, 0.35, _map_angle(a), 90.0, "", _BODY if alpha_is_true else _MIRROR)
        _plots.angle_arc(ax, c, 0.3, 90.0, 90.0 + a, "", _MIRROR if alpha_is_true else _BODY)
    carried = psis[0] + (psis[1] - psis[0]) + err  # psi1 + dpsi_INS
    _arrow(ax, centres[1], centres[1] + 0.75 * _unit(_map_angle(carried)), "tab:green", ":", 2.0)
    ax.annotate(
        "",
        tuple(centres[1] + [-1.15, 0.9]),
        tuple(centres[0] + [1.15, 0.9]),
        arrowprops={"arrowstyle": "-|>", "color": "tab:green", "linewidth": 1.2, "connectionstyle": "arc3,rad=-0.25"},
    )
    ax.text(1.6, 1.55, "drive: MEMS INS measures Δψ_INS", fontsize=8, color="tab:green", ha="center")
    ax.plot([], [], color=_BODY, label="true heading (the pair the INS picks)")
    ax.plot([], [], "--", color=_MIRROR, label="mirror candidate 2π − ψ")
    ax.plot([], [], ":", color="tab:green", linewidth=2.0, label="stop 1's heading + Δψ_INS")
    ax.set(xlim=(-1.9, 5.3), ylim=(-1.9, 1.9), aspect="equal")
    ax.set_axis_off()
