r"""Sensor calibration and "characterise my IMU": ellipsoid, multi-position and Allan-deviation fits.

Magnetometer: hard and soft iron (:func:`fit_magnetometer`)
    Model :math:`m_{raw} = W m + b` with the hard-iron offset ``b`` (3,) and a symmetric positive-definite
    soft-iron matrix ``W`` (3, 3) (the model of :class:`navlib.sensors.MagnetometerModel`), corrected by
    :math:`m_{cal} = W^{-1} (m_{raw} - b)`. As the sensor turns, :math:`\lVert m_{cal} \rVert = F` (the field
    strength), so the raw samples lie on the ellipsoid :math:`(m_{raw} - b)^T A\, (m_{raw} - b) = 1` with
    :math:`A = W^{-2} / F^2`. The
    ellipsoid is fitted algebraically to the general quadric
    ``v1 x^2 + v2 y^2 + v3 z^2 + 2 v4 yz + 2 v5 xz + 2 v6 xy + 2 v7 x + 2 v8 y + 2 v9 z + v10 = 0`` by least
    squares under the ellipsoid-specific constraint ``4J - I^2 = 1`` (``I = v1 + v2 + v3``,
    ``J = v1 v2 + v2 v3 + v1 v3 - v4^2 - v5^2 - v6^2``), a generalised eigenproblem whose one positive
    eigenvalue gives the fit (Li & Griffiths 2004); the samples are centred and scaled first, which leaves
    the fitted ellipsoid unchanged. Then ``b = -A3^-1 [v7, v8, v9]`` for the quadratic part ``A3``, and
    :math:`W^{-1} = F \sqrt{A}` with the symmetric square root: of all correction matrices ``R W^-1`` (R any
    rotation) the symmetric one does not rotate the sensor frame. ``F`` and ``W`` are only determined
    together: with a known ``field_strength`` (e.g. :func:`navlib.earth.magnetic_field`) ``F`` is that
    value; without, ``F = det(A)^(-1/6)`` so that ``det W = 1`` (soft iron redistributes the field between
    axes without gaining or losing any on average; Ozyagcilar 2015). The fit needs the samples to cover
    the ellipsoid in three dimensions:
    turning about one axis only traces a plane ellipse, which does not determine the ellipsoid
    (``MIN_THICKNESS``), and a small cap of orientations determines it poorly (``MAX_MAG_CONDITION``).

Accelerometer: six or more static positions (:func:`fit_accelerometer`)
    Model ``f_cal = S (f_raw - b)``, bias ``b`` (3,) and ``S`` diagonal (scale factors) or lower
    triangular (scale factors and non-orthogonality). At rest ``|f_cal| = g`` in every orientation, so
    ``b`` and ``S`` follow from ``K >= 6`` (diagonal) or ``K >= 9`` (triangular) static mean specific
    forces by nonlinear least squares on ``|S (f_k - b)| - g`` (Skog & Haendel 2006; Fong, Ong & Nee 2008;
    the triangular form of Tedaldi, Pretto & Menegatti 2014). ``|S (f - b)|`` does not change when ``S``
    is rotated, so a full ``S`` is not observable: the triangular form fixes the calibrated x axis to the
    sensor's x axis and the calibrated x-y plane to the sensor's. The positions must point each axis up
    and down (e.g. the six faces of a cube); tilting about level leaves bias and scale of the vertical
    axis inseparable, which the condition number of the fit's Jacobian exposes.

Gyro bias at rest (:func:`gyro_bias_at_rest`)
    ``b = mean(w_ib_b) - C_bn^T w_ie_n`` (:func:`navlib.earth.earth_rate_b`) when attitude and latitude
    are known, else the mean itself (which then includes Earth rate, up to 7.3e-5 rad/s). Its standard
    error is the white-noise one, ``std(w) / sqrt(N)``.

Noise characterisation (:func:`characterise`)
    Per axis, the overlapping Allan deviation of a static record (IEEE Std 952-1997,
    :func:`navlib.analysis.allan_deviation`) is fitted with navlib's noise model
    (:func:`navlib.analysis.fit_allan`): white noise density N (angle random walk for gyros, velocity
    random walk for accelerometers), bias instability B (peak Allan deviation of a Gauss-Markov bias, with
    its correlation time T_c) and, optionally, rate random walk K. A Gauss-Markov term whose Allan peak
    ``GM_ALLAN_PEAK_TAU T_c`` lies outside the averaging times is not identifiable: below them it is white
    noise (``N^2 += 2 sigma^2 T_c``), beyond the record a rate random walk (``K^2 += 2 sigma^2 / T_c``,
    when K is fitted), and it is moved there (``sigma = B / GM_ALLAN_PEAK``).

    Each term's confidence interval comes from a parametric bootstrap of the fit: ``_REPLICATES`` (64) records
    of the fitted model (same length and interval; white noise, Gauss-Markov bias, rate random walk) are
    simulated, their Allan deviations' departures from the model's are carried to the log-terms through the
    fit's first-order sensitivity (``fit_allan``'s ``sensitivity``), and the interval is
    ``log q +- (t_{(1+c)/2}(R - 1) sd + |mean|)`` of the replicates' departures ``log q* - log q``: Student's t
    for a spread estimated from R replicates, and the replicates' mean departure (the fit's bias, from the
    skewed scatter of the log-deviation at long averaging times) widening both sides rather than moving the
    interval, since its first-order value is not reliable where the fit is far from linear (B against T_c).
    The bootstrap carries the scatter of the whole curve and the correlation between averaging times (one
    record serves them all) into every term; the deviation at one averaging time alone (the earlier
    construction) gave B 69 % coverage for a 95 % interval. The replicates' random stream is seeded from
    the measured deviation: the same record gives the same intervals.

    Model uncertainty and identifiability: an interval also spans each other model that fits the curve
    (``fit_allan``'s ``adequate``; the estimate's relative interval around its value), and starts at 0
    where the data do not need the term (its ``evidence`` at most :data:`navlib.analysis.ALLAN_EVIDENCE`:
    a model without it fits). A term left out is 0 with lower limit 0; its upper limit is ``inf`` for B
    (not identifiable; also where B's peak lies beyond the averaging times) and, for K, that of the
    largest K the longest averaging time allows (``adev(tau_max) / sqrt(tau_max / 3)``), scaled by the
    random-walk chi-square interval there: an overlapping Allan variance at cluster length ``m`` has
    ``edf = (N - 2) ((N - 1)^2 - 3 m (N - 1) + 4 m^2) / (m (N - 3)^2)`` equivalent degrees of freedom
    (``N`` = n + 1 integrated samples; Howe, Allan & Barnes 1981, as tabulated in Riley 2008, Table 5),
    1.3 at ``m = n/3``, and the deviation's interval at confidence c is
    ``[sqrt(edf / chi2_{(1+c)/2}(edf)), sqrt(edf / chi2_{(1-c)/2}(edf))]`` times the estimate (Riley 2008,
    Sec. 5.3). Coverage over 100 seeds x 6 axes of four truths (white; white + K; white + B; all three) at
    30 min and 2 h: ``data/seed_studies/allan_coverage.csv``.

References
----------
* Q. Li, J. G. Griffiths, "Least squares ellipsoid specific fitting", Proc. Geometric Modeling and
  Processing 2004, pp. 335-340.
* T. Ozyagcilar, "Calibrating an eCompass in the presence of hard- and soft-iron interference", NXP
  application note AN4246, rev. 4, 2015.
* I. Skog, P. Haendel, "Calibration of a MEMS inertial measurement unit", XVII IMEKO World Congress, 2006.
* W. T. Fong, S. K. Ong, A. Y. C. Nee, "Methods for in-field user calibration of an inertial measurement
  unit without external equipment", Meas. Sci. Technol. 19 (2008) 085202.
* D. Tedaldi, A. Pretto, E. Menegatti, "A robust and easy to implement method for IMU calibration
  without external equipments", IEEE ICRA 2014.
* IEEE Std 952-1997, Annex C (Allan variance, percentage error of the estimate).
* N. El-Sheimy, H. Hou, X. Niu, "Analysis and modeling of inertial sensors using Allan variance",
  IEEE T-IM 57(1), 2008.
* W. J. Riley, "Handbook of Frequency Stability Analysis", NIST SP 1065, 2008.
* D. A. Howe, D. W. Allan, J. A. Barnes, "Properties of signal sources and measurement methods",
  Proc. 35th Annual Symposium on Frequency Control, 1981.
"""

from __future__ import annotations

import zlib
from dataclasses import dataclass
from typing import Annotated

import numpy as np
from scipy.optimize import least_squares

from . import _noise, analysis, earth, units
from ._records import unchecked
from ._typing import Array, ArrayLike, Dcm, Interval, Vec3, Vec3Series
from ._validate import Check, Flag, Positive, as_array, boundary, imu_samples, interval, sample_intervals, scalar
from .imu import ImuSamples, unpack
from .sensors import ImuModel, TriadErrors

__all__ = [
    "MIN_THICKNESS",
    "MAX_MAG_CONDITION",
    "MAX_ACCEL_CONDITION",
    "MIN_RECORD",
    "MagCalibration",
    "fit_magnetometer",
    "AccelCalibration",
    "fit_accelerometer",
    "gyro_bias_at_rest",
    "TriadNoise",
    "NoiseCharacterisation",
    "characterise",
]

MIN_THICKNESS = 0.1
"""Smallest accepted ``sqrt(lambda_min / lambda_max)`` of the covariance of the magnetometer samples: a
full sphere of samples gives 1, one turn about a single axis (a plane circle of radius r) about ``1.4 noise / r``."""

MAX_MAG_CONDITION = 30.0
"""Largest accepted condition number of the magnetometer fit (the Jacobian of ``|m_cal| / F`` with the offset
in units of F) at the fitted ellipsoid. Samples all over the sphere give about 2, tilts within +-90 deg
(any heading) about 8, within +-60 deg about 20, within +-45 deg about 50, where the algebraic fit's
offset is already wrong by a few percent of F at 0.6 % noise."""

MAX_ACCEL_CONDITION = 100.0
"""Largest accepted condition number of the accelerometer fit's Jacobian (bias in units of g): noise in the
static means is amplified at most this much in the estimates. The six faces of a cube give 1."""

MIN_RECORD = 100
"""Fewest samples :func:`characterise` accepts (a decade of averaging times needs more; hours are usual)."""


# --------------------------------------------------------------------------
# Magnetometer: hard and soft iron
# --------------------------------------------------------------------------


def _quality(record: object, names: tuple[str, ...]) -> None:
    """A fit's quality figures: non-negative scalars, NaN when not computed, inf for a singular fit's condition."""
    for name in names:
        object.__setattr__(
            record, name, scalar(getattr(record, name), name, allow_zero=True, allow_nan=True, allow_inf=name == "condition")
        )


@dataclass(frozen=True)
class MagCalibration:
    """Hard- and soft-iron correction ``m_cal = soft_iron @ (m_raw - offset)``.

    Construct it from stored values to apply a saved calibration; :func:`fit_magnetometer` also fills the
    quality figures (NaN when unknown).

    Attributes
    ----------
    offset : ndarray, shape (3,)
        Hard-iron offset ``b`` (unit of the samples, e.g. uT).
    soft_iron : ndarray, shape (3, 3)
        The correction matrix ``W^-1``, symmetric positive definite.
    field_strength : float
        Radius ``F`` of the corrected sphere (unit of the samples): the given field strength, or the
        fitted one (``det W = 1``).
    residual : float
        RMS of ``|m_cal| - field_strength`` over the fitted samples.
    norm_spread_before, norm_spread_after : float
        Standard deviation of ``|m|`` over the fitted samples, raw and corrected.
    condition : float
        Condition number of the fit at the solution (``MAX_MAG_CONDITION``): how well the samples' coverage
        of orientations determines offset and soft iron.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import calibration
    >>> cal = calibration.MagCalibration(offset=np.array([5.0, -3.0, 1.0]), soft_iron=np.eye(3), field_strength=50.0)
    >>> cal.soft_iron @ ([5.0, 47.0, 1.0] - cal.offset)             # m_cal = W^-1 (m_raw - b)
    array([ 0., 50.,  0.])
    """

    offset: np.ndarray
    soft_iron: np.ndarray
    field_strength: float
    residual: float = np.nan
    norm_spread_before: float = np.nan
    norm_spread_after: float = np.nan
    condition: float = np.nan

    def __post_init__(self) -> None:
        object.__setattr__(self, "offset", as_array(self.offset, "offset", shape=(3,)))
        W = as_array(self.soft_iron, "soft_iron", shape=(3, 3))
        if not np.allclose(W, W.T, rtol=1e-9, atol=0.0) or np.linalg.eigvalsh(W)[0] <= 0:
            raise ValueError("soft_iron: expected a symmetric positive-definite correction matrix")
        object.__setattr__(self, "soft_iron", W)
        object.__setattr__(self, "field_strength", scalar(self.field_strength, "field_strength", positive=True))
        _quality(self, ("residual", "norm_spread_before", "norm_spread_after", "condition"))

    def apply(self, m_raw: Vec3) -> Array:
        """Corrected field ``soft_iron @ (m_raw - offset)``, shape (..., 3) like ``m_raw`` (NaN propagates)."""
        m = as_array(m_raw, "m_raw", tail=(3,), allow_nan=True)
        return (m - self.offset) @ self.soft_iron.T


def _thickness(m: np.ndarray) -> float:
    """``sqrt(lambda_min / lambda_max)`` of the sample covariance: how far the samples leave a plane."""
    ev = np.linalg.eigvalsh(np.cov(m.T))
    return float(np.sqrt(max(ev[0], 0.0) / ev[-1])) if ev[-1] > 0 else 0.0


def _quadric_li_griffiths(x: np.ndarray) -> np.ndarray:
    """Ellipsoid-specific quadric ``v`` (10,) of the module docstring through points ``x`` (N, 3) (k = 4)."""
    X, Y, Z = x.T
    D = np.stack([X * X, Y * Y, Z * Z, 2 * Y * Z, 2 * X * Z, 2 * X * Y, 2 * X, 2 * Y, 2 * Z, np.ones_like(X)])
    S = D @ D.T
    S11, S12, S22 = S[:6, :6], S[:6, 6:], S[6:, 6:]
    C = np.zeros((6, 6))
    C[:3, :3] = 1.0  # k/2 - 1 = 1 off the diagonal
    np.fill_diagonal(C[:3, :3], -1.0)
    C[3:, 3:] = -4.0 * np.eye(3)
    reduced = S11 - S12 @ np.linalg.solve(S22, S12.T)
    ev, vec = np.linalg.eig(np.linalg.solve(C, reduced))
    v1 = np.real(vec[:, np.argmax(np.real(ev))])
    return np.concatenate([v1, -np.linalg.solve(S22, S12.T @ v1)])


def _ellipsoid(v: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """Centre and normalised shape matrix ``A`` (positive definite) of a quadric, or None if not an ellipsoid."""
    A3 = np.array([[v[0], v[5], v[4]], [v[5], v[1], v[3]], [v[4], v[3], v[2]]])
    centre = -np.linalg.solve(A3, v[6:9])
    A = A3 / (centre @ A3 @ centre - v[9])
    return (centre, A) if np.linalg.eigvalsh(A)[0] > 0 else None


_UPPER = np.triu_indices(3)


def _mag_condition(m: np.ndarray, offset: np.ndarray, W_inv: np.ndarray, F: float) -> float:
    """cond of d(|W_inv (m - offset)| / F) / d(offset / F, W_inv entries): the geometric fit's Jacobian."""
    d = m - offset
    y = d @ W_inv.T
    u = y / np.linalg.norm(y, axis=-1, keepdims=True)
    dW = u[:, :, None] * d[:, None, :]
    dW = dW + np.swapaxes(dW, 1, 2) * (1 - np.eye(3))  # symmetric: W_jk = W_kj, one parameter
    return float(np.linalg.cond(np.concatenate([-u @ W_inv, dW[:, _UPPER[0], _UPPER[1]] / F], 1)))


def _sqrtm_spd(A: np.ndarray) -> np.ndarray:
    ev, V = np.linalg.eigh(A)
    return (V * np.sqrt(ev)) @ V.T


EARTH_FIELD_RANGE = (15.0, 80.0)
"""Plausible strength (uT) of the Earth's field at the surface: about 22 (South Atlantic) to 67 (near the
magnetic poles); a fitted strength outside it means the fit, the unit or the surroundings are wrong."""


def fit_magnetometer(
    m_b: Vec3Series, field_strength: float | None = None, *, field_range: tuple[float, float] | None = EARTH_FIELD_RANGE
) -> MagCalibration:
    """Hard- and soft-iron calibration by an ellipsoid fit (Li & Griffiths 2004; module docstring).

    Parameters
    ----------
    m_b : array_like, shape (N, 3)
        Raw magnetometer samples (any unit, e.g. uT), N >= 9, taken while the sensor turns through as many
        orientations as possible, away from local disturbances.
    field_strength : float, optional
        Known field strength (unit of ``m_b``), e.g. ``|earth.magnetic_field(...)|``; default: fitted,
        with ``det W = 1``.
    field_range : (float, float) or None
        Plausible fitted field strength, in the unit of ``m_b``: default :data:`EARTH_FIELD_RANGE` (uT);
        None skips the test (samples in another unit, or a field that is not the Earth's).

    Returns
    -------
    MagCalibration

    Raises
    ------
    ValueError
        Fewer than 9 samples, NaN or inf, samples (nearly) in one plane (``MIN_THICKNESS``), too small a
        range of orientations (``MAX_MAG_CONDITION``), samples that no ellipsoid fits, a fit that leaves
        ``|m|`` no more constant than it was (a degenerate fit), or a fitted field strength outside
        ``field_range``. Each message says what to record instead.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import calibration, attitude
    >>> hpr = np.deg2rad([[h, p, 0.0] for h in range(0, 360, 45) for p in (-60, 0, 60)])   # 24 orientations
    >>> d = attitude.quat_rotate(attitude.euler_to_quat(hpr), [0.0, 1.0, 0.0])   # field directions in the sensor frame
    >>> m_raw = 50.0 * d * [1.1, 0.9, 1.0] + [5.0, -3.0, 1.0]       # soft iron (scales) and hard iron (offset), uT
    >>> cal = calibration.fit_magnetometer(m_raw, field_strength=50.0)
    >>> np.round(cal.offset, 3), round(float(cal.norm_spread_after), 6)
    (array([ 5., -3.,  1.]), 0.0)
    """
    m = as_array(m_b, "m_b", shape=(None, 3))
    if m.shape[0] < 9:
        raise ValueError(f"m_b: expected at least 9 samples (an ellipsoid has 9 parameters), got {m.shape[0]}")
    F = None if field_strength is None else scalar(field_strength, "field_strength", positive=True)
    plausible = None if field_range is None else _field_range(field_range)
    thick = _thickness(m)
    if thick < MIN_THICKNESS:
        raise ValueError(
            f"m_b: the samples lie (nearly) in one plane (thickness {thick:.3g} < {MIN_THICKNESS}): "
            "turning about one axis traces an ellipse, not the ellipsoid; turn the sensor through "
            "all orientations (e.g. each axis pointing up and down, or a figure eight in 3-D)"
        )
    c0 = m.mean(0)
    s0 = float(np.sqrt(np.mean(np.sum((m - c0) ** 2, -1))))
    fit = _ellipsoid(_quadric_li_griffiths((m - c0) / s0))
    if fit is None:
        raise ValueError("m_b: no ellipsoid fits the samples (too noisy or disturbed for their coverage)")
    centre, A = c0 + s0 * fit[0], fit[1] / s0**2
    if F is None:
        F = float(np.linalg.det(A) ** (-1 / 6))
    W_inv = F * _sqrtm_spd(A)
    W_inv = (W_inv + W_inv.T) / 2
    cond = _mag_condition(m, centre, W_inv, F)
    if not cond <= MAX_MAG_CONDITION:
        raise ValueError(
            f"m_b: the orientations cover too little of the sphere to determine hard and soft iron "
            f"(condition number {cond:.3g} > {MAX_MAG_CONDITION:g}); tilt the sensor further, "
            "ideally pointing each axis up and down"
        )
    norm_raw = np.linalg.norm(m, axis=-1)
    norm_cal = np.linalg.norm((m - centre) @ W_inv.T, axis=-1)
    _refuse_degenerate(norm_raw.std(), norm_cal.std(), F, plausible if field_strength is None else None)
    return MagCalibration(
        centre, W_inv, F, float(np.sqrt(np.mean((norm_cal - F) ** 2))), float(norm_raw.std()), float(norm_cal.std()), cond
    )


def _field_range(field_range: ArrayLike) -> tuple[float, float]:
    lo, hi = as_array(field_range, "field_range", shape=(2,))
    if not 0 < lo < hi:
        raise ValueError(f"field_range: expected (low, high) with 0 < low < high, got ({lo:g}, {hi:g})")
    return float(lo), float(hi)


def _refuse_degenerate(spread_raw: float, spread_cal: float, F: float, field_range: tuple[float, float] | None) -> None:
    """A fit must make ``|m|`` more constant (unless it already is, to 1 % of the field) and, when the field
    strength was fitted, give a plausible one."""
    record = (
        "record again away from steel, cars and electronics, turning the sensor slowly through all "
        "orientations (each axis up and down)"
    )
    if spread_cal >= spread_raw and spread_cal > 0.01 * F:
        raise ValueError(
            f"m_b: the fit leaves |m| no more constant than the raw samples (spread {spread_cal:.3g} "
            f"after, {spread_raw:.3g} before): a degenerate fit; {record}"
        )
    if field_range is not None:
        lo, hi = field_range
        if not lo <= F <= hi:
            raise ValueError(
                f"m_b: fitted field strength {F:.3g} outside the plausible {lo:g}..{hi:g} (uT for the "
                f"Earth's field): a degenerate fit, a disturbed recording or another unit; {record}; "
                f"field_range=None if the samples are not in uT"
            )


# --------------------------------------------------------------------------
# Accelerometer: multi-position
# --------------------------------------------------------------------------


@dataclass(frozen=True)
class AccelCalibration:
    """Accelerometer correction ``f_cal = matrix @ (f_raw - bias)``.

    Construct it from stored values to apply a saved calibration; :func:`fit_accelerometer` also fills the
    quality figures (NaN when unknown).

    Attributes
    ----------
    bias : ndarray, shape (3,)
        Bias ``b`` (m/s^2).
    matrix : ndarray, shape (3, 3)
        Correction ``S``: diagonal (inverse scale factors) or lower triangular (with non-orthogonality).
    g : float
        Gravity the fit matched (m/s^2).
    residual : float
        RMS of ``|f_cal| - g`` over the positions (m/s^2).
    condition : float
        Condition number of the fit's Jacobian (bias in units of g); see ``MAX_ACCEL_CONDITION``.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import calibration
    >>> cal = calibration.AccelCalibration(bias=np.array([0.1, 0.0, -0.05]), matrix=np.diag([1.01, 0.99, 1.0]))
    >>> np.round(cal.matrix @ ([0.1, 0.0, 9.75665] - cal.bias), 5)   # f_cal = S (f_raw - b)
    array([0.     , 0.     , 9.80665])
    """

    bias: np.ndarray
    matrix: np.ndarray
    g: float = units.G0
    residual: float = np.nan
    condition: float = np.nan

    def __post_init__(self) -> None:
        object.__setattr__(self, "bias", as_array(self.bias, "bias", shape=(3,)))
        S = as_array(self.matrix, "matrix", shape=(3, 3))
        if np.any(np.triu(S, 1) != 0) or np.any(np.diag(S) <= 0):
            raise ValueError("matrix: expected a lower-triangular (or diagonal) matrix with a positive diagonal")
        object.__setattr__(self, "matrix", S)
        object.__setattr__(self, "g", scalar(self.g, "g", positive=True))
        _quality(self, ("residual", "condition"))

    @property
    def scale_factor(self) -> Array:
        """Scale-factor errors (fraction, (3,)): ``diag(matrix^-1) - 1``, as in ``f_raw = (I + diag(sf)) f + b``."""
        return np.diag(np.linalg.inv(self.matrix)) - 1.0

    def apply(self, f_raw: Vec3) -> Array:
        """Corrected specific force ``matrix @ (f_raw - bias)``, shape (..., 3) like ``f_raw`` (NaN propagates)."""
        f = as_array(f_raw, "f_raw", tail=(3,), allow_nan=True)
        return (f - self.bias) @ self.matrix.T


_LOWER = np.tril_indices(3)  # (0,0), (1,0), (1,1), (2,0), (2,1), (2,2)


def _unpack_params(p: np.ndarray, misalignment: bool) -> tuple[np.ndarray, np.ndarray]:
    S = np.zeros((3, 3))
    if misalignment:
        S[_LOWER] = p[3:]
    else:
        S[np.diag_indices(3)] = p[3:]
    return p[:3], S


def _accel_residual(p: np.ndarray, f: np.ndarray, g: float, misalignment: bool) -> np.ndarray:
    b, S = _unpack_params(p, misalignment)
    return np.linalg.norm((f - b) @ S.T, axis=-1) - g


def _accel_jacobian(p: np.ndarray, f: np.ndarray, g: float, misalignment: bool) -> np.ndarray:
    """d residual / d p: ``-u^T S`` for the bias, ``u_i (f - b)_j`` for ``S_ij``; u = S (f - b) / |S (f - b)|."""
    b, S = _unpack_params(p, misalignment)
    y = (f - b) @ S.T
    u = y / np.linalg.norm(y, axis=-1, keepdims=True)
    dS = u[:, :, None] * (f - b)[:, None, :]
    cols = dS[:, _LOWER[0], _LOWER[1]] if misalignment else dS[:, [0, 1, 2], [0, 1, 2]]
    return np.concatenate([-u @ S, cols], axis=1)


def _condition(p: np.ndarray, f: np.ndarray, g: float, misalignment: bool) -> float:
    J = _accel_jacobian(p, f, g, misalignment)
    J[:, :3] *= g  # bias in units of g: all parameters dimensionless
    return float(np.linalg.cond(J))


@boundary
def fit_accelerometer(f_means: Vec3Series, g: Positive = units.G0, *, misalignment: Flag = False) -> AccelCalibration:
    """Accelerometer bias and scale factors from static positions (module docstring).

    Parameters
    ----------
    f_means : array_like, shape (K, 3)
        Mean specific force (m/s^2) of each static position, e.g. from
        :func:`navlib.alignment.static_means`; K >= 6 (K >= 9 with ``misalignment``), in orientations
        that point each axis up and down.
    g : float
        Local gravity (m/s^2), e.g. :func:`navlib.earth.gravity`; default one standard gravity.
    misalignment : bool
        Fit a lower-triangular ``S`` (scale factors and the three non-orthogonality angles) instead of a
        diagonal one.

    Returns
    -------
    AccelCalibration

    Raises
    ------
    ValueError
        Too few positions, NaN or inf, a zero mean, or orientations that do not determine the unknowns
        (Jacobian condition number above ``MAX_ACCEL_CONDITION``).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import calibration
    >>> f_true = 9.80665 * np.vstack([np.eye(3), -np.eye(3)])        # each axis up, then down
    >>> f_means = f_true / [1.02, 0.98, 1.0] + [0.1, -0.2, 0.05]     # scale factors and biases
    >>> cal = calibration.fit_accelerometer(f_means)
    >>> np.round(cal.bias, 6), np.round(np.diag(cal.matrix), 6)
    (array([ 0.1 , -0.2 ,  0.05]), array([1.02, 0.98, 1.  ]))
    """
    f = as_array(f_means, "f_means", shape=(None, 3))
    need = 9 if misalignment else 6
    if f.shape[0] < need:
        raise ValueError(f"f_means: expected at least {need} static positions, got {f.shape[0]}")
    norms = np.linalg.norm(f, axis=-1)
    if np.any(norms == 0):
        raise ValueError("f_means: expected non-zero mean specific forces")
    s0 = g / norms.mean()
    p0 = np.concatenate([np.zeros(3), s0 * (np.eye(3)[_LOWER] if misalignment else np.ones(3))])
    cond = _condition(p0, f, g, misalignment)
    if not cond <= MAX_ACCEL_CONDITION:
        raise ValueError(
            f"f_means: the orientations do not determine bias and scale (condition number {cond:.3g} "
            f"> {MAX_ACCEL_CONDITION:g}); use positions that point each axis up and down, e.g. the six "
            "faces of a cube"
        )
    sol = least_squares(
        _accel_residual,
        p0,
        jac=_accel_jacobian,
        args=(f, g, misalignment),
        method="lm",
        x_scale=np.concatenate([np.full(3, g), np.abs(p0[3:]) + s0]),
    )
    b, S = _unpack_params(sol.x, misalignment)
    S = np.sign(np.diag(S))[:, None] * S  # |S (f - b)| is blind to the signs of S's rows
    residual = float(np.sqrt(np.mean(sol.fun**2)))
    return unchecked(AccelCalibration, bias=b, matrix=S, g=g, residual=residual, condition=_condition(sol.x, f, g, misalignment))


# --------------------------------------------------------------------------
# Gyro bias at rest
# --------------------------------------------------------------------------


def gyro_bias_at_rest(w_ib_b: Vec3Series, lat: float | None = None, C_bn: Dcm | None = None) -> tuple[Array, Array]:
    """Gyro bias from a static record, and its standard error (module docstring).

    Parameters
    ----------
    w_ib_b : array_like, shape (..., N, 3)
        Gyro samples (rad/s) of a static IMU, N >= 2, no NaN.
    lat : float, optional
        Geodetic latitude (rad). Give it with ``C_bn`` to remove Earth rate.
    C_bn : array_like, shape (3, 3) or (..., 3, 3), optional
        Attitude during the record (body to ENU), e.g. :func:`navlib.alignment.triad`.

    Returns
    -------
    bias : ndarray, shape (..., 3)
        ``mean(w_ib_b) - C_bn^T w_ie_n`` (rad/s); without ``lat`` and ``C_bn``, the mean (Earth rate
        included).
    std_error : ndarray, shape (..., 3)
        White-noise standard error of the mean, ``std(w_ib_b) / sqrt(N)`` (rad/s). Optimistic when the
        record is longer than the Allan-deviation minimum (bias instability then dominates).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import calibration, attitude, earth
    >>> C_bn = attitude.euler_to_dcm([0.3, 0.0, 0.0])
    >>> w = earth.earth_rate_b(C_bn, 0.6) + [1e-4, -2e-4, 0.0] + 1e-5 * np.sin(np.arange(200.0))[:, None]
    >>> bias, std_err = calibration.gyro_bias_at_rest(w, lat=0.6, C_bn=C_bn)
    >>> np.round(bias, 6), np.round(std_err * 1e7, 2)                # rad/s; standard error in 1e-7 rad/s
    (array([ 0.0001, -0.0002,  0.    ]), array([5.01, 5.01, 5.01]))
    """
    w = as_array(w_ib_b, "w_ib_b", tail=(3,), min_ndim=1)
    n = w.shape[-2]
    if n < 2:
        raise ValueError(f"w_ib_b: expected at least 2 samples, got {n}")
    mean = w.mean(-2)
    if (lat is None) != (C_bn is None):
        given, missing = ("lat", "C_bn") if C_bn is None else ("C_bn", "lat")
        raise ValueError(f"{missing}: required with {given} to remove Earth rate (give both or neither)")
    if lat is not None and C_bn is not None:
        mean = mean - earth.earth_rate_b(C_bn, lat)  # checks C_bn and lat (rad, scalar)
    return mean, w.std(-2, ddof=1) / np.sqrt(n)


# --------------------------------------------------------------------------
# Noise characterisation from a static record
# --------------------------------------------------------------------------


@dataclass(frozen=True)
class TriadNoise:
    """Allan-deviation noise terms of one triad, per axis (field names as in :class:`navlib.sensors.TriadErrors`).

    Units: rad/s for gyros, m/s^2 for accelerometers ("u" below).

    Attributes
    ----------
    noise_density : ndarray, shape (3,)
        White noise N (u/sqrt(Hz)): angle random walk (rad/sqrt(s)) or velocity random walk (m/s/sqrt(s)).
    bias_instability : ndarray, shape (3,)
        Peak Allan deviation B of the Gauss-Markov bias (u).
    correlation_time : ndarray, shape (3,)
        Gauss-Markov correlation time T_c (s); meaningless where ``bias_instability`` is 0.
    rate_random_walk : ndarray, shape (3,)
        K (u/s/sqrt(Hz)); 0 unless fitted.
    noise_density_ci, bias_instability_ci, rate_random_walk_ci : ndarray, shape (3, 2)
        Lower and upper confidence limits of each term (module docstring: a bootstrap of the fit, spanning
        every model that fits); the lower limit is 0 where the data do not need the term, the upper limit
        ``inf`` where B is not identifiable from the record.
    taus : ndarray, shape (M,)
        Averaging times (s).
    adev : ndarray, shape (M, 3)
        Measured Allan deviation (u).
    evidence : ndarray, shape (3, 2)
        Identifiability of B and K per axis (:func:`navlib.analysis.fit_allan`'s ``evidence``): the smallest
        miss, in standard errors, of the models without the term where the terms show; above
        :data:`navlib.analysis.ALLAN_EVIDENCE` the data need the term, at or below it a model without the
        term fits (its interval starts at 0); ``-inf`` for K when it is not fitted.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import calibration
    >>> rng = np.random.default_rng(0)
    >>> w_ib_b, f_b = 1e-3 * rng.standard_normal((2000, 3)), [0.0, 0.0, 9.8] + 1e-2 * rng.standard_normal((2000, 3))
    >>> noise = calibration.characterise(w_ib_b, f_b, 0.01)
    >>> gyro = noise.gyro                                            # a TriadNoise
    >>> np.round(gyro.noise_density * 1e4, 1), gyro.noise_density_ci.shape
    (array([1., 1., 1.]), (3, 2))
    """

    noise_density: np.ndarray
    bias_instability: np.ndarray
    correlation_time: np.ndarray
    rate_random_walk: np.ndarray
    noise_density_ci: np.ndarray
    bias_instability_ci: np.ndarray
    rate_random_walk_ci: np.ndarray
    taus: np.ndarray
    adev: np.ndarray
    evidence: np.ndarray

    @boundary
    def to_triad_errors(self, combine: Annotated[str, Check("choice", options=("rms", "max"))] = "rms") -> TriadErrors:
        """The :class:`navlib.sensors.TriadErrors` these terms feed (one value for the three axes).

        ``noise_density``, ``bias_instability`` and ``rate_random_walk`` are combined over the axes by
        ``combine``: ``"rms"`` (the root mean square: the same total variance) or ``"max"`` (the worst axis,
        conservative for a filter's process noise); ``correlation_time`` by the geometric mean over the axes
        with a bias instability (the default 3600 s if none has one). Turn-on bias, scale factor,
        misalignment and full scale are not observable from one static record and keep their defaults (set
        them with :meth:`navlib.sensors.ImuModel.replace`).
        """

        def one(x: np.ndarray) -> float:
            return float(np.sqrt(np.mean(x * x)) if combine == "rms" else np.max(x))

        tc = self.correlation_time[self.bias_instability > 0]
        return TriadErrors(
            noise_density=one(self.noise_density),
            bias_instability=one(self.bias_instability),
            correlation_time=float(np.exp(np.mean(np.log(tc)))) if tc.size else TriadErrors.correlation_time,
            rate_random_walk=one(self.rate_random_walk),
        )


@dataclass(frozen=True)
class NoiseCharacterisation:
    """Noise terms of a static IMU record: :func:`characterise`.

    Attributes
    ----------
    gyro, accel : TriadNoise
        Gyro (rad/s) and accelerometer (m/s^2) terms.
    dt : float
        Sample interval (s).
    n_samples : int
        Record length N.
    confidence : float
        Confidence level of the intervals.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import calibration
    >>> rng = np.random.default_rng(0)
    >>> w_ib_b, f_b = 1e-3 * rng.standard_normal((2000, 3)), [0.0, 0.0, 9.8] + 1e-2 * rng.standard_normal((2000, 3))
    >>> noise = calibration.characterise(w_ib_b, f_b, 0.01)
    >>> noise.n_samples, noise.dt, noise.confidence
    (2000, 0.01, 0.95)
    """

    gyro: TriadNoise
    accel: TriadNoise
    dt: float
    n_samples: int
    confidence: float

    @property
    def angle_random_walk(self) -> Array:
        """Gyro white noise density (rad/sqrt(s) = rad/s/sqrt(Hz)), (3,)."""
        return self.gyro.noise_density

    @property
    def velocity_random_walk(self) -> Array:
        """Accelerometer white noise density (m/s/sqrt(s) = m/s^2/sqrt(Hz)), (3,)."""
        return self.accel.noise_density

    def to_imu_model(self, name: str = "characterised", combine: str = "rms") -> ImuModel:
        """The :class:`navlib.sensors.ImuModel` for :func:`navlib.sensors.simulate_imu` and the filters.

        See :meth:`TriadNoise.to_triad_errors` for ``combine`` and what stays at its default.
        """
        return ImuModel(self.gyro.to_triad_errors(combine), self.accel.to_triad_errors(combine), name)


def _edf_random_walk(n_phase: int, m: np.ndarray) -> np.ndarray:
    """Equivalent degrees of freedom of an overlapping Allan variance of random-walk noise at cluster length ``m``
    from ``n_phase`` integrated samples (Howe, Allan & Barnes 1981; NIST SP 1065, Table 5), at least 1."""
    N = float(n_phase)
    return np.maximum((N - 2) / (m * (N - 3) ** 2) * ((N - 1) ** 2 - 3 * m * (N - 1) + 4 * m * m), 1.0)


def _interval(edf: np.ndarray, confidence: float) -> np.ndarray:
    """Factors (..., 2) scaling an Allan deviation with ``edf`` degrees of freedom to its interval."""
    from scipy.stats import chi2  # noqa: PLC0415 -- scipy.stats is slow to import; only intervals need it

    return np.stack([np.sqrt(edf / chi2.ppf((1 + confidence) / 2, edf)), np.sqrt(edf / chi2.ppf((1 - confidence) / 2, edf))], -1)


def _fold_unobserved_peaks(terms: dict, below: np.ndarray, beyond: np.ndarray) -> dict:
    """Move a Gauss-Markov term whose Allan peak lies ``below`` or ``beyond`` the averaging times into the term it mimics.

    Its Allan variance ``sigma^2 g(tau / T_c)`` is ``2 sigma^2 T_c / tau`` for ``tau >> T_c`` (white noise
    with ``N^2 = 2 sigma^2 T_c``) and ``2 sigma^2 tau / (3 T_c)`` for ``tau << T_c`` (rate random walk
    with ``K^2 = 2 sigma^2 / T_c``); B and T_c are then not identifiable, only N or K. Works on arrays of any
    shape that broadcasts with the masks (estimates (3,), bootstrap replicates (R, 3)).
    """
    tc = terms["correlation_time"]
    var = (terms["bias_instability"] / analysis.GM_ALLAN_PEAK) ** 2
    return {
        "white": np.where(below, np.sqrt(terms["white"] ** 2 + 2 * var * tc), terms["white"]),
        "bias_instability": np.where(below | beyond, 0.0, terms["bias_instability"]),
        "correlation_time": tc,
        "rate_random_walk": np.where(beyond, np.sqrt(terms["rate_random_walk"] ** 2 + 2 * var / tc), terms["rate_random_walk"]),
    }


_TERMS = ("white", "bias_instability", "correlation_time", "rate_random_walk")
_REPLICATES = 64
"""Bootstrap records per triad behind the intervals (module docstring): the interval's Student-t factor with 63
degrees of freedom (2.00 at 95 %) covers the spread estimated from them."""


def _simulate(terms: dict, n: int, dt: float, rng: np.random.Generator) -> np.ndarray:
    """A record (n, 3) of the fitted noise model: white noise, a Gauss-Markov bias where B > 0, rate random walk."""
    x = terms["white"] / np.sqrt(dt) * rng.standard_normal((n, 3))
    for k in np.flatnonzero(terms["bias_instability"] > 0):
        sigma = terms["bias_instability"][k] / analysis.GM_ALLAN_PEAK
        x[:, k] += _noise.gauss_markov((n, 1), dt, sigma, terms["correlation_time"][k], rng)[:, 0]
    if np.any(terms["rate_random_walk"] > 0):
        x += np.cumsum(terms["rate_random_walk"] * np.sqrt(dt) * rng.standard_normal((n, 3)), axis=0)
    return x


def _bootstrap(terms: dict, sensitivity: np.ndarray, taus: np.ndarray, n: int, dt: float, rng: np.random.Generator) -> dict:
    """Replicates (R, 3) of the fitted terms: records of the fitted model, their Allan deviations' departure from
    the model carried to the log-terms through the fit's ``sensitivity`` (3, 4, M)."""
    model = np.stack([_noise.theory(taus, *(terms[key][k] for key in _TERMS)) for k in range(3)], -1)
    p = np.stack([terms[key] for key in _TERMS])  # (4, 3)
    reps = np.empty((_REPLICATES, 4, 3))
    for r in range(_REPLICATES):
        _, adev = _noise.deviation(_simulate(terms, n, dt, rng), dt, _noise.cluster_lengths(n, dt, taus))
        reps[r] = p * np.exp(np.einsum("kqm,mk->qk", sensitivity, np.log(adev / model)))
    return {key: reps[:, i] for i, key in enumerate(_TERMS)}


def _bootstrap_interval(estimate: np.ndarray, replicates: np.ndarray, confidence: float) -> np.ndarray:
    """(3, 2) interval in log space: the estimate plus or minus Student's t (R - 1 degrees of freedom) times the
    replicates' spread and their mean departure (the fit's first-order bias, module docstring); [0, inf] where the
    estimate is 0."""
    from scipy.stats import t  # noqa: PLC0415 -- scipy.stats is slow to import; only intervals need it

    out = np.tile([0.0, np.inf], (estimate.size, 1))
    kept = estimate > 0
    u = np.log(replicates[:, kept] / estimate[kept])
    half = t.ppf((1 + confidence) / 2, u.shape[0] - 1) * u.std(0, ddof=1) + np.abs(u.mean(0))
    centre = np.log(estimate[kept])
    out[kept] = np.exp(np.stack([centre - half, centre + half], -1))
    return out


def _triad_noise(x: np.ndarray, dt: float, rate_random_walk: bool, confidence: float, name: str) -> TriadNoise:
    n = x.shape[0]
    taus, adev = _noise.deviation(x - x.mean(0), dt, _noise.cluster_lengths(n, dt))
    if not np.all(adev > 0):
        raise ValueError(f"{name}: an axis without noise (a constant record) has no noise terms to characterise")
    fits = [_noise.fit(taus, adev[:, k], n, dt, rate_random_walk) for k in range(3)]
    fitted = {key: np.array([f[key] for f in fits]) for key in _TERMS}
    peak = analysis.GM_ALLAN_PEAK_TAU * fitted["correlation_time"]
    below, beyond = peak < taus[0], (peak > taus[-1]) & rate_random_walk
    terms = _fold_unobserved_peaks(fitted, below, beyond)
    rng = np.random.default_rng(zlib.crc32(adev.tobytes()))  # a stream of its own per record, the same every run
    sensitivity = np.stack([f["sensitivity"] for f in fits])
    replicates = _fold_unobserved_peaks(_bootstrap(fitted, sensitivity, taus, n, dt, rng), below, beyond)
    ci = {key: _bootstrap_interval(terms[key], replicates[key], confidence) for key in _TERMS}
    for key, i in (("white", 0), ("bias_instability", 1), ("rate_random_walk", 3)):  # span every adequate model
        kept = terms[key] > 0
        others = [np.where(f["adequate"][:, i] > 0, f["adequate"][:, i], np.nan) for f in fits]
        ratio = ci[key][kept] / terms[key][kept, None]
        ci[key][kept, 0] = np.fmin(ci[key][kept, 0], np.array([np.nanmin(v, initial=np.inf) for v in others])[kept] * ratio[:, 0])
        ci[key][kept, 1] = np.fmax(ci[key][kept, 1], np.array([np.nanmax(v, initial=0.0) for v in others])[kept] * ratio[:, 1])
    K_end = adev[-1] / np.sqrt(taus[-1] / 3)  # the largest K the longest averaging time allows
    f_K = _interval(_edf_random_walk(n + 1, np.full(3, taus[-1] / dt)), confidence)
    unseen = terms["rate_random_walk"] == 0
    ci["rate_random_walk"][unseen, 1] = K_end[unseen] * f_K[unseen, 1]
    ci["bias_instability"][peak > taus[-1], 1] = np.inf  # its peak beyond the record: B not identifiable
    evidence = np.array([f["evidence"] for f in fits])
    ci["bias_instability"][evidence[:, 0] <= analysis.ALLAN_EVIDENCE, 0] = 0.0  # the data fit without it
    ci["rate_random_walk"][evidence[:, 1] <= analysis.ALLAN_EVIDENCE, 0] = 0.0
    return TriadNoise(
        terms["white"],
        terms["bias_instability"],
        terms["correlation_time"],
        terms["rate_random_walk"],
        ci["white"],
        ci["bias_instability"],
        ci["rate_random_walk"],
        taus,
        adev,
        evidence,
    )


def _fixed_interval(dt: Interval, n: int) -> float:
    """The one sample interval of ``dt`` (scalar, or per-sample intervals that agree to 1e-6)."""
    d = sample_intervals(dt, n)
    if np.ptp(d) > 1e-6 * d.mean():
        raise ValueError(
            f"dt: expected a fixed sample interval for the Allan deviation, got intervals from "
            f"{d.min():g} to {d.max():g} s (resample first by averaging, navlib.io.resample(rec, rate); "
            "interpolation changes the white-noise level)"
        )
    return interval(d.mean(), "dt")  # and not too long for the Allan deviation (its square overflows)


@boundary
def characterise(
    w_ib_b: Vec3Series | ImuSamples,
    f_b: Vec3Series | None = None,
    dt: Interval | None = None,
    *,
    rate_random_walk: Flag = False,
    confidence: Annotated[float, Check("scalar", within=(0.0, 1.0), open_ends=(True, True))] = 0.95,
) -> NoiseCharacterisation:
    """Characterise an IMU from a static record: per-axis Allan deviation and noise terms (module docstring).

    Parameters
    ----------
    w_ib_b : array_like, shape (N, 3), or ImuSamples
        Gyro samples (rad/s) of a static, temperature-stable IMU, N >= ``MIN_RECORD`` (hours are usual: the
        bias instability needs averaging times beyond its correlation time). An
        :class:`navlib.imu.ImuSamples` here supplies ``f_b`` and ``dt``.
    f_b : array_like, shape (N, 3)
        Accelerometer samples (m/s^2) of the same record.
    dt : float or array_like, shape (N,)
        Sample interval (s); per-sample intervals must all be equal.
    rate_random_walk : bool
        Also fit rate random walk K (otherwise K = 0).
    confidence : float
        Confidence level of the intervals, in (0, 1).

    Returns
    -------
    NoiseCharacterisation
        ``to_imu_model()`` gives the :class:`navlib.sensors.ImuModel` for the simulator and filters.

    Raises
    ------
    ValueError
        Wrong shapes, NaN (dropouts: the Allan deviation needs an unbroken record), too short a record,
        irregular sampling.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import calibration
    >>> rng = np.random.default_rng(0)
    >>> w_ib_b = 1e-3 * rng.standard_normal((2000, 3))                # gyro white noise, 1e-3 rad/s per sample at 100 Hz
    >>> f_b = [0.0, 0.0, 9.8] + 1e-2 * rng.standard_normal((2000, 3))
    >>> noise = calibration.characterise(w_ib_b, f_b, 0.01)
    >>> np.round(noise.gyro.noise_density * 1e4, 1)                   # 1e-3 * sqrt(0.01) = 1e-4 rad/sqrt(s)
    array([1., 1., 1.])
    """
    w, f, dt, _, _ = unpack(w_ib_b, f_b, dt)
    w, f = imu_samples(w, f, allow_nan=False, shape=(None, 3))  # one record
    n = w.shape[0]
    if n < MIN_RECORD:
        raise ValueError(f"w_ib_b: expected a static record of at least {MIN_RECORD} samples, got {n}")
    dt = _fixed_interval(dt, n)
    return NoiseCharacterisation(
        _triad_noise(w, dt, rate_random_walk, confidence, "w_ib_b"),
        _triad_noise(f, dt, rate_random_walk, confidence, "f_b"),
        dt,
        n,
        confidence,
    )
