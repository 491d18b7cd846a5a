r"""Simulated sensors: IMU, magnetometer, barometer, GNSS, dual-antenna heading.

IMU error model (per axis, applied to the ideal outputs :math:`x` of
:func:`navlib.trajectory.ideal_imu`), clipped at :math:`\pm` ``full_scale``:

.. math:: y = M x + b_{on} + b_{gm}(t) + b_{rrw}(t) + n(t)

* ``M = I + diag(scale) + misalignment``: scale-factor errors on the
  diagonal, small-angle misalignments off it (drawn once per run).
* ``b_on``: turn-on bias, constant within a run.
* ``b_gm``: first-order Gauss-Markov bias, :math:`b_{k+1} = \phi\, b_k + w_k` with
  :math:`\phi = e^{-\Delta t / T_c}` and :math:`\mathrm{var}(w) = \sigma^2 (1 - \phi^2)`, started from its
  stationary distribution. Its standard deviation ``sigma`` therefore does not
  depend on the sample rate. ``sigma = B / GM_ALLAN_PEAK`` so that the Allan
  deviation of the bias peaks at the datasheet bias instability B
  (see :mod:`navlib.analysis`).
* ``b_rrw``: rate random walk with density K.
* ``n``: white noise of density N (ARW for gyros, VRW for accelerometers);
  per-sample sigma :math:`N / \sqrt{\Delta t}`.

Each error component draws from its own child stream of ``rng`` (via
``Generator.spawn``), so switching one component on or off leaves the
realisation of the others unchanged, and gyro and accelerometer are
independent.

Presets for the papers' devices are read from ``navlib/data/sensor_presets.csv``
(package data, so an installed navlib has them), which gives every number with
its source.
"""

from __future__ import annotations

import csv
import functools
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass, field, fields, replace
from importlib import resources
from importlib.resources.abc import Traversable
from typing import Any

import numpy as np
from numba import njit

from . import _atmosphere, _earth, _noise, atmosphere, attitude, earth, units
from ._typing import Angles, Array, ArrayLike, Quat, Times, Vec3, Vec3Series
from ._validate import (
    Count,
    Is,
    Limit,
    NonNegative,
    Positive,
    Real,
    Rng,
    Step,
    Text,
    as_array,
    as_quat,
    booleans,
    boundary,
    broadcast,
    fields_checked,
    imu_samples,
    in_range,
    integer,
    last_axis,
    positive,
    same_shape,
    scalar,
    time_axis,
)
from .analysis import GM_ALLAN_PEAK

__all__ = [
    "TriadErrors",
    "ImuModel",
    "ImuOutput",
    "window_mean_std",
    "simulate_imu",
    "simulate_imu_batches",
    "imu_model",
    "preset",
    "devices",
    "MagnetometerModel",
    "simulate_magnetometer",
    "magnetic_disturbances",
    "BarometerModel",
    "simulate_barometer",
    "outage_mask",
    "simulate_gnss_position",
    "simulate_heading",
    "gauss_markov",
]

PRESETS_CSV = resources.files("navlib") / "data" / "sensor_presets.csv"
"""The device presets, shipped inside the package (read with ``importlib.resources``)."""


# --------------------------------------------------------------------------
# IMU
# --------------------------------------------------------------------------


@dataclass(frozen=True)
class TriadErrors:
    """Error parameters of one sensor triad (gyro or accelerometer), SI units.

    Rates for gyros (rad/s), specific force for accelerometers (m/s^2).

    Attributes
    ----------
    noise_density : float
        White noise N (rad/s/sqrt(Hz) = ARW; m/s^2/sqrt(Hz) = VRW).
    bias : float
        Turn-on bias sigma (rad/s or m/s^2).
    bias_instability : float
        Peak Allan deviation B of the Gauss-Markov bias (rad/s or m/s^2).
    correlation_time : float
        Gauss-Markov correlation time T_c (s).
    rate_random_walk : float
        Random-walk density K of the bias (rad/s^2/sqrt(Hz) or m/s^3/sqrt(Hz)).
    scale_factor : float
        Scale-factor error sigma (fraction).
    misalignment : float
        Misalignment sigma (rad), independent for each off-diagonal element.
    full_scale : float
        Saturation limit (rad/s or m/s^2); ``inf`` for none.

    Examples
    --------
    >>> from navlib import sensors, units
    >>> gyro = sensors.TriadErrors(noise_density=units.deg_per_sqrt_h(0.15), bias=units.deg_per_h(10.0))
    >>> round(float(gyro.noise_density), 8), round(float(gyro.bias), 8)            # SI: rad/s/sqrt(Hz), rad/s
    (4.363e-05, 4.848e-05)
    """

    noise_density: NonNegative = 0.0
    bias: NonNegative = 0.0
    bias_instability: NonNegative = 0.0
    correlation_time: Positive = 3600.0
    rate_random_walk: NonNegative = 0.0
    scale_factor: NonNegative = 0.0
    misalignment: NonNegative = 0.0
    full_scale: Limit = np.inf

    def __post_init__(self) -> None:
        fields_checked(self)

    @property
    def gauss_markov_sigma(self) -> float:
        """Stationary sigma of the Gauss-Markov bias, ``B / GM_ALLAN_PEAK``."""
        return self.bias_instability / GM_ALLAN_PEAK


@dataclass(frozen=True)
class ImuModel:
    """Gyro and accelerometer error models of one IMU.

    Examples
    --------
    >>> from navlib import sensors
    >>> model = sensors.ImuModel(gyro=sensors.TriadErrors(noise_density=1e-4), name="my gyro")
    >>> model.name, model.gyro.noise_density, model.accel.noise_density   # accelerometer error-free
    ('my gyro', 0.0001, 0.0)
    """

    gyro: Is[TriadErrors] = field(default_factory=TriadErrors)
    accel: Is[TriadErrors] = field(default_factory=TriadErrors)
    name: Text = "custom"

    def __post_init__(self) -> None:
        fields_checked(self)

    def replace(self, gyro: dict[str, Any] | None = None, accel: dict[str, Any] | None = None) -> ImuModel:
        """Copy with some parameters changed, e.g. ``m.replace(gyro={"bias": 0.0})``."""
        return ImuModel(replace(self.gyro, **(gyro or {})), replace(self.accel, **(accel or {})), self.name)


@dataclass(frozen=True)
class ImuOutput:
    """Simulated IMU output and the error realisation behind it.

    Attributes
    ----------
    w_ib_b, f_b : ndarray, shape (..., N, 3)
        Measured angular rate (rad/s) and specific force (m/s^2).
    gyro_bias, accel_bias : ndarray, shape (..., N, 3)
        True total bias (turn-on + Gauss-Markov + random walk) per sample.
    gyro_matrix, accel_matrix : ndarray, shape (..., 3, 3)
        True ``I + scale + misalignment`` matrices.
    gyro_saturated, accel_saturated : int
        Number of clipped samples (all axes and trials).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import sensors
    >>> w_ib_b, f_b = np.zeros((100, 3)), np.tile([0.0, 0.0, 9.81], (100, 1))
    >>> out = sensors.simulate_imu(w_ib_b, f_b, 0.01, sensors.imu_model("MPU-6050"), np.random.default_rng(1))
    >>> out.gyro_bias.shape, out.gyro_matrix.shape, out.gyro_saturated   # the error realisation behind the samples
    ((100, 3), (3, 3), 0)
    """

    w_ib_b: np.ndarray
    f_b: np.ndarray
    gyro_bias: np.ndarray
    accel_bias: np.ndarray
    gyro_matrix: np.ndarray
    accel_matrix: np.ndarray
    gyro_saturated: int
    accel_saturated: int


@boundary
def gauss_markov(shape: tuple[int, ...], dt: Step, sigma: NonNegative, correlation_time: Positive, rng: Rng) -> Array:
    """First-order Gauss-Markov sequences, stationary from the first sample.

    Parameters
    ----------
    shape : tuple
        ``(..., N, k)``; time runs along axis -2.
    dt : float
        Sample interval (s).
    sigma : float
        Stationary standard deviation; independent of ``dt``.
    correlation_time : float
        Correlation time (s).
    rng : numpy.random.Generator

    Returns
    -------
    ndarray of ``shape``

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import sensors
    >>> x = sensors.gauss_markov((20000, 1), 0.01, sigma=2.0, correlation_time=1.0, rng=np.random.default_rng(0))
    >>> x.shape, round(float(x.std()), 1)                             # stationary: std close to sigma
    ((20000, 1), 2.1)
    """
    if not isinstance(shape, (tuple, list)) or len(shape) < 2:  # type: ignore[redundant-expr]  # the caller's argument, checked
        raise ValueError(f"shape: expected a tuple (..., N, k) of positive integers, got {shape!r}")
    return _noise.gauss_markov(tuple(integer(n, "shape") for n in shape), dt, sigma, correlation_time, rng)


def _error_matrix(errors: TriadErrors, lead: tuple[int, ...], rng: np.random.Generator) -> Array:
    M = np.broadcast_to(np.eye(3), lead + (3, 3)).copy()
    M += errors.misalignment * rng.standard_normal(lead + (3, 3)) * (1 - np.eye(3))
    M += errors.scale_factor * rng.standard_normal(lead + (3,))[..., None] * np.eye(3)
    return M


def _corrupt(x: Array, dt: float, errors: TriadErrors, rng: np.random.Generator) -> tuple[Array, Array, Array, int]:
    """Apply a triad error model to ideal samples ``x`` (..., N, 3): ``(y, bias, M, clipped count)``."""
    lead, n = x.shape[:-2], x.shape[-2]
    (y, bias, M, n_clipped), *_ = _corrupt_batches(x.reshape(-1, n, 3), dt, errors, rng, max(1, int(np.prod(lead))))
    return y.reshape(x.shape), bias.reshape(x.shape), M.reshape(lead + (3, 3)), n_clipped


def _corrupt_batches(
    x: Array, dt: float, errors: TriadErrors, rng: np.random.Generator, batch: int
) -> Iterator[tuple[Array, Array, Array, int]]:
    """:func:`_corrupt` of ``x`` (T, N, 3), ``batch`` trials at a time: one ``(y, bias, M, clipped)`` per batch.

    Each of the five streams is drawn in trial order, the per-trial constants (matrix, turn-on bias,
    Gauss-Markov start) for all trials first: the batches together are the bits of one batch of T trials.
    """
    r_matrix, r_on, r_gm, r_rrw, r_white = rng.spawn(5)
    n_trials, n = x.shape[0], x.shape[1]
    M = _error_matrix(errors, (n_trials,), r_matrix)
    turn_on = errors.bias * r_on.standard_normal((n_trials, 1, 3))
    sigma, tc = float(errors.gauss_markov_sigma), float(errors.correlation_time)
    if errors.bias_instability > 0:
        x0 = sigma * r_gm.standard_normal((n_trials, 1, 3))
    for i in range(0, max(n_trials, 1), batch):
        trials = slice(i, min(i + batch, n_trials))
        shape = (trials.stop - i, n, 3)
        if errors.bias_instability > 0:  # turn-on + Gauss-Markov, added in place (addition commutes: same bits)
            bias = _noise.gauss_markov_from(x0[trials], shape, dt, sigma, tc, r_gm)
            bias += turn_on[trials]
        else:
            bias = np.broadcast_to(turn_on[trials], shape).copy()
        if errors.rate_random_walk > 0:
            bias += np.cumsum(errors.rate_random_walk * np.sqrt(dt) * r_rrw.standard_normal(shape), axis=-2)
        y = r_white.standard_normal(shape) if errors.noise_density > 0 else np.empty(shape)  # the white noise
        scale = errors.noise_density / np.sqrt(dt)
        n_clipped = _apply_errors(M[trials], x[trials], bias, scale, errors.full_scale, y)
        yield y, bias, M[trials], int(n_clipped)


@njit(cache=True)
def _apply_errors(M, x, bias, scale, full_scale, y):
    """``y = M x + bias + scale * y`` clipped to ``+-full_scale``, in place (``y`` holds the white noise on
    entry; ``scale == 0`` ignores it); returns the clipped count.

    Rounded as the former ``np.einsum("...ij,...nj->...ni", M, x) + bias`` followed by ``y += scale * white``
    and ``np.clip`` (numpy's einsum sums the three products as ``(p0 + p2) + p1``), without their temporaries.
    """
    n_clipped = 0
    for t in range(y.shape[0]):
        for n in range(y.shape[1]):
            x0, x1, x2 = x[t, n, 0], x[t, n, 1], x[t, n, 2]
            for i in range(3):
                v = (M[t, i, 0] * x0 + M[t, i, 2] * x2) + M[t, i, 1] * x1 + bias[t, n, i]
                if scale != 0.0:
                    v = v + scale * y[t, n, i]
                if abs(v) > full_scale:
                    n_clipped += 1
                    v = full_scale if v > 0 else -full_scale
                y[t, n, i] = v
    return n_clipped


@boundary
def window_mean_std(errors: Is[TriadErrors], duration: Positive, dt: Step) -> float:
    r"""Std of one axis's error averaged over a static window (white + bias terms).

    .. math::

        \sigma^2 = \frac{N^2}{T} + b^2 + 2 \sigma_{gm}^2 \frac{\tau}{T} \Big[1 - \frac{\tau}{T}\big(1 - e^{-T/\tau}\big)\Big]

    for white noise density N, turn-on bias and a Gauss-Markov bias of std
    sigma_gm and correlation time tau (rate random walk and scale factor are
    not included): the error left in a static average of a real sensor, e.g. the
    "total gyro error" the north-finding error theory of paper 000 needs instead of white noise.

    Parameters
    ----------
    errors : TriadErrors
    duration : float
        Averaging time T (s).
    dt : float
        Sample interval (s), for the discrete white-noise mean ``N / sqrt(n dt)``.

    Examples
    --------
    >>> from navlib import sensors
    >>> gyro = sensors.TriadErrors(noise_density=1e-4)              # white noise only
    >>> round(sensors.window_mean_std(gyro, duration=100.0, dt=0.01), 8)   # N / sqrt(T)
    1e-05
    """
    n = max(int(round(duration / dt)), 1)
    r = errors.correlation_time / duration
    gm = errors.gauss_markov_sigma**2 * 2 * r * (1 - r * (1 - np.exp(-1 / r)))
    return float(np.sqrt(errors.noise_density**2 / (n * dt) + errors.bias**2 + gm))


@boundary
def simulate_imu(
    w_ib_b: Vec3Series, f_b: Vec3Series, dt: Step, model: Is[ImuModel], rng: Rng, n_trials: Count | None = None
) -> ImuOutput:
    """Corrupt ideal IMU samples with an :class:`ImuModel`.

    Parameters
    ----------
    w_ib_b, f_b : array_like, shape (..., N, 3)
        Ideal angular rate (rad/s) and specific force (m/s^2), e.g. from
        :func:`navlib.trajectory.ideal_imu`.
    dt : float
        Sample interval (s).
    model : ImuModel
    rng : numpy.random.Generator
        Source of all randomness; gyro and accelerometer use independent
        child streams.
    n_trials : int, optional
        Draw this many independent realisations on a new leading axis: the
        output has shape (n_trials, ..., N, 3).

    Returns
    -------
    ImuOutput

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import sensors
    >>> w_ib_b, f_b = np.zeros((1000, 3)), np.tile([0.0, 0.0, 9.81], (1000, 1))   # 10 s at rest, level
    >>> out = sensors.simulate_imu(w_ib_b, f_b, 0.01, sensors.imu_model('MPU-6050'), np.random.default_rng(1))
    >>> out.w_ib_b.shape, out.f_b.shape
    ((1000, 3), (1000, 3))
    """
    w, f = imu_samples(w_ib_b, f_b, allow_nan=False)
    if n_trials is not None:
        w = np.broadcast_to(w, (n_trials,) + w.shape)
        f = np.broadcast_to(f, (n_trials,) + f.shape)
    r_gyro, r_accel = rng.spawn(2)
    gw, gb, gM, gs = _corrupt(w, dt, model.gyro, r_gyro)
    af, ab, aM, as_ = _corrupt(f, dt, model.accel, r_accel)
    return ImuOutput(gw, af, gb, ab, gM, aM, gs, as_)


@boundary
def simulate_imu_batches(
    w_ib_b: Vec3Series, f_b: Vec3Series, dt: Step, model: Is[ImuModel], rng: Rng, n_trials: Count, batch: Count
) -> Iterator[ImuOutput]:
    """:func:`simulate_imu` with ``n_trials`` realisations, ``batch`` trials at a time, bit for bit.

    The realisations of ``simulate_imu(w_ib_b, f_b, dt, model, rng, n_trials=n_trials)`` in order, trials
    ``[0, batch)`` first, with the memory of ``batch`` trials: a Monte Carlo that reduces each batch before
    the next never holds all of them (its result does not depend on ``batch``).

    Parameters
    ----------
    w_ib_b, f_b : array_like, shape (N, 3)
        Ideal angular rate (rad/s) and specific force (m/s^2), the same for every trial.
    dt, model, rng :
        As for :func:`simulate_imu`.
    n_trials, batch : int
        Realisations in all and per batch (the last batch may hold fewer).

    Returns
    -------
    iterator of ImuOutput
        One per batch: arrays of shape (trials of the batch, N, 3); ``*_saturated`` counts of the batch.
        The arguments are checked at the call.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import sensors
    >>> w, f, model = np.zeros((100, 3)), np.tile([0.0, 0.0, 9.8], (100, 1)), sensors.imu_model("MPU-6050")
    >>> every = sensors.simulate_imu(w, f, 0.01, model, np.random.default_rng(1), n_trials=5).w_ib_b
    >>> batches = sensors.simulate_imu_batches(w, f, 0.01, model, np.random.default_rng(1), 5, 2)
    >>> parts = [b.w_ib_b for b in batches]
    >>> [p.shape[0] for p in parts], bool(np.array_equal(np.concatenate(parts), every))
    ([2, 2, 1], True)
    """
    w, f = imu_samples(w_ib_b, f_b, allow_nan=False, shape=(None, 3))  # one ideal record for every trial
    r_gyro, r_accel = rng.spawn(2)  # here, as simulate_imu does, not when the first batch is asked for
    gyro = _corrupt_batches(np.broadcast_to(w, (n_trials,) + w.shape), dt, model.gyro, r_gyro, batch)
    accel = _corrupt_batches(np.broadcast_to(f, (n_trials,) + f.shape), dt, model.accel, r_accel, batch)
    return (ImuOutput(gw, af, gb, ab, gM, aM, gs, as_) for (gw, gb, gM, gs), (af, ab, aM, as_) in zip(gyro, accel, strict=True))


# --------------------------------------------------------------------------
# Presets
# --------------------------------------------------------------------------


def _preset_parameters() -> dict[str, set[str]]:
    """The parameters a preset row may name, per sensor (the fields of the model it feeds)."""
    triad = {f.name for f in fields(TriadErrors)}
    return {
        "gyro": triad,
        "accel": triad,
        "mag": {f.name for f in fields(MagnetometerModel)},
        "baro": {f.name for f in fields(BarometerModel)} | {"noise_ultra_low_power"},
        "heading": {"noise"},
        "gnss": {"rtk_horizontal", "single_point_horizontal"},
    }


def _read_presets(path: Traversable) -> dict[str, dict[tuple[str, str], tuple[float, str, str]]]:
    """Parse a presets CSV strictly: an unknown sensor or parameter, a repeated row or a bad
    value raises ``ValueError`` naming the line (a typo must not silently give a noise-free sensor)."""
    known = _preset_parameters()
    table: dict[str, dict[tuple[str, str], tuple[float, str, str]]] = {}
    with path.open(encoding="utf-8") as fh:
        lines = [(n, line) for n, line in enumerate(fh, 1) if line.strip() and not line.startswith("#")]
    rows = csv.DictReader(line for _, line in lines)
    for (n, _), r in zip(lines[1:], rows, strict=False):
        where = f"{path.name} line {n}"
        sensor, par = r["sensor"], r["parameter"]
        if sensor not in known:
            raise ValueError(f"{where}: unknown sensor {sensor!r}; known: {sorted(known)}")
        if par not in known[sensor]:
            raise ValueError(f"{where}: unknown {sensor} parameter {par!r}; known: {sorted(known[sensor])}")
        if (sensor, par) in table.get(r["device"], {}):
            raise ValueError(f"{where}: {r['device']} {sensor} {par} given twice")
        try:
            value = float(units.to_si(float(r["value"]), r["unit"]))
        except (TypeError, ValueError) as exc:
            raise ValueError(f"{where}: bad value or unit {r['value']!r} {r['unit']!r} ({exc})") from None
        table.setdefault(r["device"], {})[(sensor, par)] = (value, r["unit"], r["source"])
    return table


@functools.cache
def _preset_table() -> dict[str, dict[tuple[str, str], tuple[float, str, str]]]:
    return _read_presets(PRESETS_CSV)


def devices() -> list[str]:
    """Names of the devices in ``navlib/data/sensor_presets.csv``.

    Examples
    --------
    >>> from navlib import sensors
    >>> "MPU-6050" in sensors.devices(), "BMP180" in sensors.devices()
    (True, True)
    """
    return sorted(_preset_table())


def preset(device: str) -> dict[tuple[str, str], float]:
    """SI parameters of a device, keyed by ``(sensor, parameter)``.

    Example: ``preset("BMP180")[("baro", "noise")]`` is 2.0 Pa.

    Examples
    --------
    >>> from navlib import sensors
    >>> sensors.preset("BMP180")[("baro", "noise")]                  # Pa
    2.0
    """
    table = _preset_table()
    if not isinstance(device, str) or device not in table:  # type: ignore[redundant-expr]  # the caller's argument, checked
        raise ValueError(f"device: unknown device {device!r}; known: {devices()}")
    return {k: v[0] for k, v in table[device].items()}


def _preset_fields(device: str, sensor: str, names: set[str], what: str) -> dict[str, float]:
    """The parameters ``names`` of one sensor of a preset device; ``what`` names the sensor in the error."""
    kw = {par: v for (s, par), v in preset(device).items() if s == sensor and par in names}
    if not kw:
        raise ValueError(f"device: {device!r} has no {what} preset")
    return kw


def imu_model(device: str) -> ImuModel:
    """:class:`ImuModel` of a preset device (``NAV-FOG``, ``MTi-100``, ``ADIS16475-1``, ``MPU-6050``).

    Examples
    --------
    >>> from navlib import sensors, units
    >>> model = sensors.imu_model("MPU-6050")
    >>> model.name, round(float(units.to_deg_per_s_sqrt_hz(model.gyro.noise_density)), 4)   # deg/s/sqrt(Hz)
    ('MPU-6050', 0.005)
    """
    names = {f.name for f in fields(TriadErrors)}
    gyro, accel = (TriadErrors(**_preset_fields(device, sensor, names, sensor)) for sensor in ("gyro", "accel"))
    return ImuModel(gyro, accel, device)


# --------------------------------------------------------------------------
# Magnetometer
# --------------------------------------------------------------------------


@dataclass(frozen=True)
class MagnetometerModel:
    """Magnetometer errors (uT).

    ``m_b = S C_nb (B_n + d_n) + h + n``: soft-iron matrix ``S = I + E`` with
    elements of E drawn with sigma ``soft_iron`` (symmetric), hard-iron offset
    h with sigma ``hard_iron`` (constant per run), white noise n with sigma
    ``noise``, and an optional external disturbance field ``d_n``.

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import sensors
    >>> model = sensors.MagnetometerModel(noise=0.5, hard_iron=3.0)   # uT
    >>> q_bn = np.tile([1.0, 0.0, 0.0, 0.0], (5, 1))
    >>> out = sensors.simulate_magnetometer(q_bn, [0.0, 20.0, -40.0], model, np.random.default_rng(0))
    >>> out.m_b.shape
    (5, 3)
    """

    noise: NonNegative = 0.0
    hard_iron: NonNegative = 0.0
    soft_iron: NonNegative = 0.0
    full_scale: Limit = np.inf

    def __post_init__(self) -> None:
        fields_checked(self)

    @classmethod
    def from_preset(cls, device: str) -> MagnetometerModel:
        """Model of a preset magnetometer (e.g. ``"HMC5983"``)."""
        return cls(**_preset_fields(device, "mag", {f.name for f in fields(cls)}, "magnetometer"))


@dataclass(frozen=True)
class MagnetometerOutput:
    """Simulated magnetometer samples ``m_b`` (..., N, 3) in uT and the true errors."""

    m_b: np.ndarray
    hard_iron: np.ndarray
    soft_iron: np.ndarray


@boundary
def simulate_magnetometer(
    q_bn: Quat, B_n: Vec3, model: Is[MagnetometerModel], rng: Rng, disturbance_n: Vec3Series | None = None
) -> MagnetometerOutput:
    """Magnetometer readings along an attitude history.

    Parameters
    ----------
    q_bn : array_like, shape (..., N, 4)
        True attitude quaternions.
    B_n : array_like, shape (3,) or (..., N, 3)
        Local field in ENU (uT), e.g. from :func:`navlib.earth.magnetic_field`.
    model : MagnetometerModel
    rng : numpy.random.Generator
    disturbance_n : array_like, shape (..., N, 3), optional
        Extra field in ENU (uT), e.g. from :func:`magnetic_disturbances`.

    Returns
    -------
    MagnetometerOutput

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import attitude, sensors
    >>> q_bn = np.tile(attitude.euler_to_quat(np.deg2rad([90.0, 0.0, 0.0])), (3, 1))   # facing east
    >>> out = sensors.simulate_magnetometer(q_bn, [0.0, 20.0, -40.0], sensors.MagnetometerModel(), np.random.default_rng(0))
    >>> np.round(out.m_b, 6) + 0.0                                    # error-free: north is to the left (-x)
    array([[-20.,   0., -40.],
           [-20.,   0., -40.],
           [-20.,   0., -40.]])
    """
    q = as_quat(q_bn, "q_bn", min_ndim=1)
    B = as_array(B_n, "B_n", tail=(3,))
    if disturbance_n is not None:
        B, D = broadcast(B, as_array(disturbance_n, "disturbance_n", tail=(3,)), name="disturbance_n", of="B_n, disturbance_n")
        B = B + D
    broadcast(q[..., 1:], B, name="B_n", of="q_bn, B_n")
    C_nb = np.swapaxes(attitude.quat_to_dcm(q), -1, -2)
    m_true = np.einsum("...ij,...j->...i", C_nb, B)
    lead = m_true.shape[:-2]
    r_soft, r_hard, r_noise = rng.spawn(3)
    E = model.soft_iron * r_soft.standard_normal(lead + (3, 3))
    S = np.eye(3) + (E + np.swapaxes(E, -1, -2)) / 2
    h = model.hard_iron * r_hard.standard_normal(lead + (3,))
    m = np.einsum("...ij,...nj->...ni", S, m_true) + h[..., None, :]
    m = m + model.noise * r_noise.standard_normal(m.shape)
    return MagnetometerOutput(np.clip(m, -model.full_scale, model.full_scale), h, S)


@boundary
def magnetic_disturbances(
    time: Times,
    rng: Rng,
    rate: NonNegative,
    amplitude: tuple[float, float] = (5.0, 10.0),
    duration: tuple[float, float] = (2.0, 5.0),
) -> Array:
    """Localised magnetic disturbances (steel structures, passing cars).

    Events arrive as a Poisson process; each is a Hann-shaped bump of random
    direction, amplitude and duration.

    Parameters
    ----------
    time : array_like, shape (N,)  (s)
    rng : numpy.random.Generator
    rate : float
        Mean number of events per second.
    amplitude : (float, float)
        Range of peak amplitudes (uT), drawn uniformly.
    duration : (float, float)
        Range of durations (s), drawn uniformly.

    Returns
    -------
    d_n : ndarray, shape (N, 3)
        Disturbance field in ENU (uT).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import sensors
    >>> d = sensors.magnetic_disturbances(np.arange(0.0, 60.0, 0.1), np.random.default_rng(0), rate=0.1)
    >>> d.shape, bool(np.abs(d).max() > 0)                           # ENU disturbance (uT), (N, 3)
    ((600, 3), True)
    """
    t = time_axis(time)
    for name, pair in (("amplitude", amplitude), ("duration", duration)):
        lo, hi = positive(pair, name, shape=(2,))
        if hi < lo:
            raise ValueError(f"{name}: expected (low, high) with low <= high, got ({lo}, {hi})")
    n_events = rng.poisson(rate * (t[-1] - t[0]))
    d = np.zeros((t.size, 3))
    for _ in range(n_events):
        t0 = rng.uniform(t[0], t[-1])
        T = rng.uniform(*duration)
        a = rng.uniform(*amplitude)
        u = rng.standard_normal(3)
        u /= np.linalg.norm(u)
        s = (t - t0) / T
        bump = np.where((s >= 0) & (s <= 1), np.sin(np.pi * s) ** 2, 0.0)
        d += a * bump[:, None] * u
    return d


# --------------------------------------------------------------------------
# Barometer
# --------------------------------------------------------------------------


@dataclass(frozen=True)
class BarometerModel:
    """Barometer errors (Pa): white ``noise`` sigma, constant ``bias`` sigma,
    and a deterministic weather ``drift_rate`` (Pa/s).

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import sensors
    >>> model = sensors.BarometerModel(noise=2.0, bias=10.0, drift_rate=0.01)   # Pa, Pa, Pa/s
    >>> p = sensors.simulate_barometer(np.zeros(3), np.array([0.0, 100.0, 200.0]), model, np.random.default_rng(0))
    >>> p.shape
    (3,)
    """

    noise: NonNegative = 0.0
    bias: NonNegative = 0.0
    drift_rate: Real = 0.0

    def __post_init__(self) -> None:
        fields_checked(self)

    @classmethod
    def from_preset(cls, device: str = "BMP180") -> BarometerModel:
        """Model of a preset barometer."""
        return cls(**_preset_fields(device, "baro", {"noise", "bias", "drift_rate"}, "barometer"))


@boundary
def simulate_barometer(h: ArrayLike, time: Times, model: Is[BarometerModel], rng: Rng, p0: Positive = atmosphere.P0) -> Array:
    """Barometric pressure (Pa) at heights ``h`` (m) with the ISA as truth.

    Parameters
    ----------
    h : array_like, shape (..., N)
        True height (m).
    time : array_like, shape (N,)
        Sample times (s); the drift is ``drift_rate * (time - time[0])``.
    model : BarometerModel
    rng : numpy.random.Generator
    p0 : float
        Sea-level (reference) pressure of the day (Pa).

    Returns
    -------
    ndarray, shape (..., N)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import sensors
    >>> model = sensors.BarometerModel(drift_rate=0.01)               # weather drift only: 0.01 Pa/s
    >>> np.round(sensors.simulate_barometer(np.zeros(3), np.array([0.0, 100.0, 200.0]), model, np.random.default_rng(0)), 3)
    array([101325., 101326., 101327.])
    """
    t = time_axis(time)
    h = in_range(last_axis(as_array(h, "h"), "h", t.size, of="time"), "h", _atmosphere.H_MIN, _atmosphere.H_MAX, "m")
    p = _atmosphere.isa_pressure(h, p0)
    r_bias, r_noise = rng.spawn(2)
    p = p + model.bias * r_bias.standard_normal(p.shape[:-1] + (1,))
    p = p + model.drift_rate * (t - t[0])
    return p + model.noise * r_noise.standard_normal(p.shape)


# --------------------------------------------------------------------------
# GNSS position and dual-antenna heading
# --------------------------------------------------------------------------


def outage_mask(time: Times, outages: Sequence[ArrayLike]) -> np.ndarray:
    """Validity flags: False inside any ``[start, end)`` outage interval.

    Parameters
    ----------
    time : array_like, shape (N,)  (s)
    outages : sequence of (float, float)
        Start and end times (s) of each outage.

    Returns
    -------
    valid : ndarray of bool, shape (N,)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import sensors
    >>> sensors.outage_mask(np.arange(6.0), [(2.0, 4.0)])
    array([ True,  True, False, False,  True,  True])
    """
    t = time_axis(time)
    valid = np.ones(t.shape, dtype=bool)
    if isinstance(outages, (str, bytes)) or not isinstance(outages, Iterable):
        raise ValueError(f"outages: expected a sequence of (start, end) pairs, got {outages!r:.40}")
    for pair in outages:
        iv = as_array(pair, "outages", shape=(2,))
        if not iv[1] > iv[0]:
            raise ValueError(f"outages: expected (start, end) pairs with end > start, got {iv!r}")
        valid &= ~((t >= iv[0]) & (t < iv[1]))
    return valid


@boundary
def simulate_gnss_position(
    lla: Vec3Series,
    rng: Rng,
    sigma_horizontal: NonNegative,
    sigma_vertical: float | None = None,
    valid: ArrayLike | None = None,
) -> Array:
    """GNSS positions: truth plus white noise in metres, NaN during outages.

    Parameters
    ----------
    lla : array_like, shape (..., N, 3)
        True ``[lat (rad), lon (rad), h (m)]``.
    rng : numpy.random.Generator
    sigma_horizontal : float
        Noise sigma per horizontal axis (m).
    sigma_vertical : float, optional
        Vertical noise sigma (m); default ``1.5 * sigma_horizontal``.
    valid : array_like of bool, shape (N,), optional
        Validity flags (e.g. from :func:`outage_mask`); invalid epochs are NaN.

    Returns
    -------
    lla_meas : ndarray, shape (..., N, 3)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import sensors
    >>> lla = np.tile([0.6, 0.2, 50.0], (4, 1))
    >>> gnss = sensors.simulate_gnss_position(lla, np.random.default_rng(0), 2.0, valid=np.array([True, True, False, True]))
    >>> np.isnan(gnss[:, 0])                                          # no fix during the outage
    array([False, False,  True, False])
    """
    lla = as_array(lla, "lla", tail=(3,), min_ndim=1)
    in_range(lla[..., 0], "lla[..., 0] (lat)", -np.pi / 2, np.pi / 2, "rad")
    sv = 1.5 * sigma_horizontal if sigma_vertical is None else scalar(sigma_vertical, "sigma_vertical", allow_zero=True)
    R_M, R_N = _earth.radii(lla[..., 0], earth.WGS84)
    e = rng.standard_normal(lla.shape)
    out = lla.copy()
    out[..., 0] += sigma_horizontal * e[..., 1] / (R_M + lla[..., 2])
    out[..., 1] += sigma_horizontal * e[..., 0] / ((R_N + lla[..., 2]) * np.cos(lla[..., 0]))
    out[..., 2] += sv * e[..., 2]
    if valid is not None:
        valid = same_shape(np.asarray(valid, dtype=bool), "valid", lla.shape[-2:-1])
        out[..., ~valid, :] = np.nan
    return out


@boundary
def simulate_heading(heading: Angles, rng: Rng, sigma: NonNegative, valid: ArrayLike | None = None) -> tuple[Array, np.ndarray]:
    """Dual-antenna heading: truth plus white noise, wrapped to [0, 2 pi).

    Parameters
    ----------
    heading : array_like, shape (..., N)
        True heading (rad, clockwise from true north).
    rng : numpy.random.Generator
    sigma : float
        Noise sigma (rad).
    valid : array_like of bool, shape (N,), optional
        Validity flags; invalid epochs are NaN (never a fused zero).

    Returns
    -------
    heading_meas : ndarray, shape (..., N)
    valid : ndarray of bool, shape (N,)

    Examples
    --------
    >>> import numpy as np
    >>> from navlib import sensors
    >>> heading, valid = sensors.simulate_heading(np.full(4, 6.28), np.random.default_rng(0), 0.01)
    >>> bool(((heading >= 0) & (heading < 2 * np.pi)).all()), valid  # wrapped into [0, 2 pi)
    (True, array([ True,  True,  True,  True]))
    """
    h = as_array(heading, "heading", min_ndim=1)
    out = attitude.wrap_2pi(h + sigma * rng.standard_normal(h.shape))
    v = (
        np.ones(h.shape[-1:], dtype=bool)
        if valid is None
        else same_shape(booleans(valid, "valid"), "valid", h.shape[-1:], of="the last axis of heading")
    )
    out[..., ~v] = np.nan
    return out, v
