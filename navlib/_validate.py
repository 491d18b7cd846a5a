"""Input validation shared by navlib's public functions.

Every check raises ``ValueError`` whose message starts with the offending
argument's name and states what was expected (``"<arg>: expected ..."``), so
that bad input fails loudly at the boundary instead of producing a
plausible-looking wrong number deep inside a filter. A value of the wrong
kind -- a string, complex, object, boolean or date where real numbers are
expected -- raises :class:`InputTypeError`, which is both a ``TypeError`` and
a ``ValueError``. Magnitudes beyond :data:`MAX_MAGNITUDE` (whose square overflows
float64) are refused too, except where a function is exact at any magnitude.
tools/fuzz.py calls every public function with such values.
"""

from __future__ import annotations

import dataclasses
import functools
import inspect
import os
import sys
import typing
from collections.abc import Callable
from pathlib import Path
from typing import Annotated, Any, ParamSpec, TypeVar

import numpy as np
from numpy.typing import NDArray

from ._threads import run_chunks
from ._typing import Array, ArrayLike

_S = TypeVar("_S", bound=np.generic)  # the element type of an array checked and returned as it is
_F = TypeVar("_F", float, Array)  # a float or float array checked and returned as it is


class InputTypeError(TypeError, ValueError):
    """Wrong kind of value (string, complex, object, boolean, ...) for a real argument.

    A ``TypeError`` as Python convention asks, and a ``ValueError`` too, so
    that ``except ValueError`` -- navlib's documented "bad input" error --
    still catches it (as numpy's ``AxisError`` is both a ``ValueError`` and an
    ``IndexError``).
    """


# numpy dtype kinds that are not real numbers: bool, complex, object, bytes,
# str, void (records), datetime64, timedelta64.
_NOT_REAL = {
    "b": "a boolean",
    "c": "a complex",
    "O": "an object",
    "S": "a bytes",
    "U": "a string",
    "V": "a record",
    "M": "a datetime",
    "m": "a timedelta",
}


def real(x: object, name: str) -> Array:
    """Return ``x`` as a float64 array, rejecting values that are not real numbers.

    Strings (also numeric ones such as ``"1.5"``), complex values (numpy would
    silently drop the imaginary part), object arrays, booleans, records and
    dates raise :class:`InputTypeError` naming the argument.
    """
    if isinstance(x, (str, bytes)):
        raise InputTypeError(f"{name}: expected a real numeric array, got {type(x).__name__} {x!r:.40}")
    arr = _asarray(x, name, "a real numeric array")
    kind = _NOT_REAL.get(arr.dtype.kind)
    if kind is not None:
        raise InputTypeError(
            f"{name}: expected a real numeric array, got {kind} {'array' if arr.ndim else 'value'} (dtype {arr.dtype})"
        )
    return arr.astype(float, copy=False)


def _asarray(x: object, name: str, expected: str) -> NDArray[Any]:
    """``np.asarray(x)``; a ragged nested sequence, which no array holds, raises :class:`InputTypeError` naming ``name``."""
    try:
        return np.asarray(x)
    except (TypeError, ValueError) as exc:
        raise InputTypeError(f"{name}: expected {expected}, got a ragged {type(x).__name__}") from exc


MAX_MAGNITUDE = 1e150
"""Largest magnitude :func:`as_array` accepts: beyond it a square (a norm, a variance, a product of two such
values) overflows float64, so a result would be inf or NaN, or finite but wrong. Almost always a unit or
scaling error; the few functions exact at any magnitude (quaternion normalisation, rotation-vector angles,
unit conversions) opt out with ``huge=True`` or check their own limit."""


def as_array(
    x: object,
    name: str,
    *,
    tail: tuple[int, ...] = (),
    finite: bool = True,
    allow_nan: bool = False,
    min_ndim: int = 0,
    shape: tuple[int | None, ...] | None = None,
    huge: bool = False,
    of: str = "",
    nonempty: bool = False,
) -> Array:
    """Return ``x`` as a float64 array whose trailing shape is ``tail``.

    Parameters
    ----------
    x : array_like
        Input value.
    name : str
        Argument name used in error messages.
    tail : tuple of int
        Required trailing shape, e.g. ``(3,)`` for vectors or ``(3, 3)`` for
        matrices. Leading axes are free (they broadcast).
    finite : bool
        Reject NaN and infinity.
    allow_nan : bool
        With ``finite=True``, still accept NaN (used for sensor dropouts) but
        reject infinity.
    min_ndim : int
        Minimum number of leading axes in addition to ``tail``.
    shape : tuple of int or None, optional
        Required exact shape; a ``None`` entry takes any length, e.g. ``(None,)``
        for a 1-D array.
    huge : bool
        Accept finite values beyond :data:`MAX_MAGNITUDE` (refused otherwise, also with ``finite=False``).
    of : str
        The argument(s) that set the sizes in ``shape``, named in the message (e.g. ``"x"`` for ``P``).
    nonempty : bool
        Reject empty arrays (as ``min_ndim > 0`` does), for arguments that must hold at least one value.

    The array's min and max are taken first: within +-MAX_MAGNITUDE they prove every value finite (NaN
    aside where it is accepted) and not huge, and the element-wise checks that name the fault are skipped.
    """
    arr = real(x, name)
    if shape is not None:  # first: the exact shape is the more telling message
        same_shape(arr, name, shape, of)
    if tail and arr.shape[arr.ndim - len(tail) :] != tail or arr.ndim < len(tail) + min_ndim:
        raise ValueError(f"{name}: expected shape {_shape_text(('...', *tail))}, got {arr.shape}")
    if arr.size == 0 and (nonempty or min_ndim > 0):
        raise ValueError(f"{name}: expected a non-empty array, got shape {arr.shape}")
    if _within_limits(arr, ignore_nan=allow_nan or not finite):
        return arr
    if finite and (np.isinf(arr) if allow_nan else ~np.isfinite(arr)).any():
        raise ValueError(f"{name}: contains {'infinite' if allow_nan else 'non-finite (NaN or inf)'} values")
    if not huge:
        _magnitude(arr, name)
    return arr


_PARALLEL_SIZE = 1 << 22
"""Arrays of at least this many values (a batch of Monte Carlo records) are reduced in chunks on threads."""


def _within_limits(arr: Array, ignore_nan: bool) -> bool:
    """True if every value lies within +-MAX_MAGNITUDE (two reductions, no temporaries); a NaN makes it
    False unless ``ignore_nan``. An empty array is within them. A large contiguous array is reduced in chunks on
    :func:`navlib._threads.run_chunks`'s threads (numpy's reductions release the GIL; min and max are exact, so the
    result does not depend on the chunks)."""
    lowest, highest = (np.fmin, np.fmax) if ignore_nan else (np.minimum, np.maximum)
    if arr.size >= _PARALLEL_SIZE and arr.flags.c_contiguous:
        flat, step = arr.reshape(-1), _PARALLEL_SIZE // 8
        parts = run_chunks(
            lambda i0, i1: (
                lowest.reduce(flat[i0 * step : i1 * step], initial=0.0),
                highest.reduce(flat[i0 * step : i1 * step], initial=0.0),
            ),
            -(-flat.size // step),
        )
        lo, hi = lowest.reduce([p[0] for p in parts]), highest.reduce([p[1] for p in parts])
    else:
        lo, hi = lowest.reduce(arr, axis=None, initial=0.0), highest.reduce(arr, axis=None, initial=0.0)
    return bool(-MAX_MAGNITUDE <= lo and hi <= MAX_MAGNITUDE)


def _magnitude(arr: Array, name: str) -> None:
    """Refuse finite values beyond :data:`MAX_MAGNITUDE`."""
    big = np.abs(arr) > MAX_MAGNITUDE
    if big.any() and np.isfinite(arr[big]).any():
        raise ValueError(
            f"{name}: expected magnitudes up to {MAX_MAGNITUDE:g}, got {np.abs(arr[big & np.isfinite(arr)]).max():g} "
            f"(its square overflows float64; wrong units or scaling?)"
        )


def same_shape(arr: NDArray[_S], name: str, shape: tuple[int | None, ...], of: str = "") -> NDArray[_S]:
    """Return ``arr`` if its shape is ``shape``; a ``None`` entry takes any length, e.g. ``(None, 3)``; ``of`` names
    the argument(s) that set the sizes, for the message."""
    if arr.ndim != len(shape) or any(s not in (None, n) for s, n in zip(shape, arr.shape, strict=True)):
        raise ValueError(f"{name}: expected shape {_shape_text(shape)}{f' (sizes from {of})' if of else ''}, got {arr.shape}")
    return arr


def _shape_text(dims: tuple[int | str | None, ...]) -> str:
    """A shape as messages write it: ``(N, 3)`` (``None`` reads N), ``(..., 3)``, ``(5,)``."""
    return "(" + ", ".join("N" if d is None else str(d) for d in dims) + ("," if len(dims) == 1 else "") + ")"


def booleans(x: object, name: str, *, shape: tuple[int | None, ...] | None = None, of: str = "") -> NDArray[np.bool_]:
    """Return ``x`` as a boolean array (validity flags, masks), optionally of exact ``shape`` (as in :func:`as_array`).

    Only booleans are accepted: numbers (``0``/``1``, NaN) are refused with
    :class:`InputTypeError`, so a mask is never guessed from values.
    """
    arr = _asarray(x, name, "booleans")
    if arr.dtype != bool:
        raise InputTypeError(f"{name}: expected booleans, got dtype {arr.dtype}")
    return arr if shape is None else same_shape(arr, name, shape, of)


def in_range(arr: _F, name: str, lo: float, hi: float, unit: str = "", *, lo_open: bool = False, hi_open: bool = False) -> _F:
    """Check ``lo <= arr <= hi`` (with optional open ends) elementwise."""
    ok_lo = arr > lo if lo_open else arr >= lo
    ok_hi = arr < hi if hi_open else arr <= hi
    if not np.all(ok_lo & ok_hi):
        raise ValueError(
            f"{name}: expected values in {'(' if lo_open else '['}{lo:g}, {hi:g}{')' if hi_open else ']'}"
            f"{' ' + unit if unit else ''}, got min {np.nanmin(arr):g}, max {np.nanmax(arr):g}"
        )
    return arr


def pitch_roll(pitch: object, roll: object, names: tuple[str, str] = ("pitch", "roll"), **shape: Any) -> tuple[Array, Array]:
    """Pitch within [-pi/2, pi/2] and roll within [-pi, pi] (rad); outside, degrees were most likely passed. ``shape``
    takes the shape options of :func:`as_array` (``shape``, ``of``, ...), for both."""
    return _radians(pitch, names[0], np.pi / 2, **shape), _radians(roll, names[1], np.pi, **shape)


def _radians(x: object, name: str, limit: float, **shape: Any) -> Array:
    """``x`` as angles within +-``limit`` (rad)."""
    a = as_array(x, name, **shape)
    if np.any(np.abs(a) > limit + 1e-12):
        raise ValueError(
            f"{name}: expected radians within [{-limit:.4g}, {limit:.4g}], got max |{name}| "
            f"{np.max(np.abs(a)):g} (degrees? convert with np.deg2rad)"
        )
    return a


def euler_angles(hpr: object, name: str = "hpr", **shape: Any) -> Array:
    """``[heading, pitch, roll]`` (..., 3) in rad, its pitch and roll checked by :func:`pitch_roll`; ``shape`` takes
    the shape options of :func:`as_array` (``shape``, ``of``, ``nonempty``, ...)."""
    a = as_array(hpr, name, tail=(3,), **shape)
    pitch_roll(a[..., 1], a[..., 2], (f"{name}[..., 1] (pitch)", f"{name}[..., 2] (roll)"))
    return a


def positive(x: object, name: str, *, allow_zero: bool = False, **shape: Any) -> Array:
    """Return ``x`` as a finite float array that is > 0 (or >= 0); ``shape`` takes the shape options of
    :func:`as_array` (``tail``, ``shape``, ``min_ndim``, ``nonempty``, ``of``)."""
    arr = as_array(x, name, **shape)
    if not np.all(arr >= 0 if allow_zero else arr > 0):
        raise ValueError(f"{name}: expected {'non-negative' if allow_zero else 'positive'} values, got {arr.min():g}")
    return arr


def latitude(lat: object, name: str = "lat", deg: bool = False, *, nonempty: bool = False) -> Array:
    """Validate a geodetic latitude (rad, or deg with ``deg``) and return it in radians; ``nonempty`` as in
    :func:`as_array`."""
    arr = as_array(lat, name, nonempty=nonempty)
    if flag(deg, "deg"):
        return np.deg2rad(in_range(arr, name, -90.0, 90.0, "deg"))
    return in_range(arr, name, -np.pi / 2, np.pi / 2, "rad")


def longitude(lon: object, name: str = "lon", deg: bool = False) -> Array:
    """A longitude (rad, or deg with ``deg``), non-empty, returned in degrees."""
    arr = as_array(lon, name, nonempty=True)
    return arr if flag(deg, "deg") else np.rad2deg(arr)


def lat_lon(lat: object, lon: object, deg: bool = False, names: tuple[str, str] = ("lat", "lon")) -> list[Array]:
    """Latitude (returned in rad, as :func:`latitude`) and longitude (returned in deg, as :func:`longitude`),
    non-empty and broadcast against each other."""
    lat_rad = latitude(lat, names[0], deg=deg, nonempty=True)
    return broadcast(lat_rad, longitude(lon, names[1], deg), name=", ".join(names))


def zone_offset(l_deg: Array, limit: float, width: int) -> Array:
    """Longitude offsets ``l_deg`` from a zone's central meridian (deg), wrapped into [-180, 180) and refused beyond
    ``limit`` (deg) for zones ``width`` degrees wide (navlib.geodesy's projections)."""
    offset = max(l_deg.max(initial=0.0), -l_deg.min(initial=0.0))  # max |l_deg|, without a temporary
    if offset > 180.0:  # only then is the (slower) wrap needed
        l_deg = np.mod(l_deg + 180.0, 360.0) - 180.0
        offset = np.abs(l_deg).max(initial=0.0)
    if offset > limit:
        raise ValueError(
            f"lon: expected longitudes within {limit:g}° of the central meridian (zone width {width}°; pass "
            f"max_offset_deg to allow more), got offsets up to {np.abs(l_deg).max():.4g}°"
        )
    return l_deg


def time_axis(t: object, name: str = "time", *, increasing: bool = True, min_samples: int = 2) -> Array:
    """Return a 1-D time vector (s) of at least ``min_samples`` samples, strictly increasing unless ``increasing=False``."""
    arr = as_array(t, name)
    if arr.ndim != 1 or arr.size < min_samples:
        raise ValueError(
            f"{name}: expected a 1-D array of at least {min_samples} sample{'s' * (min_samples > 1)}, got shape {arr.shape}"
        )
    if increasing and np.any(np.diff(arr) <= 0):
        raise ValueError(f"{name}: expected strictly increasing times (run navlib.timing.sanitize first)")
    return arr


ORTHO_TOL = 1e-6
"""Largest ``|C^T C - I|`` accepted for a rotation matrix."""


def as_dcm(C: object, name: str = "C_bn", **shape: Any) -> Array:
    """Return ``C`` as float rotation matrices, shape (..., 3, 3): orthonormal to ``ORTHO_TOL``, det +1.

    ``shape`` takes the shape options of :func:`as_array`, e.g. ``shape=(3, 3)`` for one matrix."""
    C = as_array(C, name, tail=(3, 3), **shape)
    err = np.abs(np.swapaxes(C, -1, -2) @ C - np.eye(3)).max(initial=0.0)
    if err > ORTHO_TOL or np.any(np.linalg.det(C) < 0):
        raise ValueError(f"{name}: expected proper rotation matrices (orthonormal, det +1); max |C^T C - I| = {err:.2e}")
    return C


QUAT_MIN_NORM = 1e-12
"""Smallest quaternion norm :func:`as_quat` accepts: a zero quaternion is no rotation."""


def as_quat(q: object, name: str = "q", *, normalize: bool = True, **shape: Any) -> Array:
    """Return ``q`` as unit quaternions, shape (..., 4), scalar first; a zero quaternion raises.

    Quaternions of any finite magnitude are normalised exactly. With ``normalize=False`` the values are
    returned unchanged (for functions defined for any non-zero quaternion, e.g. the quadratic measurement
    model and its Jacobian, which finite differences evaluate off the unit sphere). ``shape`` takes the
    shape options of :func:`as_array` (``min_ndim``, ``nonempty``, ...).
    """
    q = as_array(q, name, tail=(4,), huge=normalize, **shape)
    if normalize:
        big = np.abs(q).max(axis=-1, keepdims=True)
        if np.any(big > MAX_MAGNITUDE):  # |q|^2 would overflow: scale first (exact, a power of two)
            q = q / np.exp2(np.floor(np.log2(np.where(big > MAX_MAGNITUDE, big, 1.0))))
    n = np.linalg.norm(q, axis=-1, keepdims=True)
    if np.any(n < QUAT_MIN_NORM):
        raise ValueError(f"{name}: expected non-zero quaternions (|q| >= {QUAT_MIN_NORM:g}), got |q| = {n.min():g}")
    return q / n if normalize else q


def scalar(
    x: object,
    name: str,
    *,
    positive: bool = False,
    allow_zero: bool = False,
    allow_inf: bool = False,
    huge: bool = False,
    allow_nan: bool = False,
    within: tuple[float, float] | tuple[float, float, str] | None = None,
    open_ends: tuple[bool, bool] = (False, False),
) -> float:
    """Return ``x`` as a Python float; optionally > 0 (or >= 0 with ``allow_zero``); inf only if ``allow_inf``.

    ``allow_nan``: NaN is accepted as such (a figure that was not computed). ``within``: the bounds
    ``(lo, hi)`` of :func:`in_range` (or ``(lo, hi, unit)``), open at the ends flagged in ``open_ends``.
    """
    arr = as_array(x, name, finite=not allow_inf, allow_nan=allow_nan, huge=huge)
    if within is not None:
        in_range(arr, name, *within, lo_open=open_ends[0], hi_open=open_ends[1])
    if arr.ndim != 0:
        raise ValueError(f"{name}: expected a scalar, got shape {arr.shape}")
    value = float(arr)
    if allow_nan and np.isnan(value):
        return value
    if np.isnan(value) or (positive or allow_zero) and not (value >= 0 if allow_zero else value > 0):
        raise ValueError(
            f"{name}: expected a {'non-negative' if allow_zero else 'positive' if positive else 'non-NaN'} value, got {value!r}"
        )
    return value


def indices(x: object, name: str) -> NDArray[Any]:
    """``x`` as an array (of sample indices or trial ids, checked by the caller), a ragged sequence refused by name."""
    return _asarray(x, name, "an array of integer indices")


def integer(x: object, name: str, *, minimum: int | None = 1) -> int:
    """Return ``x`` as an int >= ``minimum`` (any int with ``minimum=None``). ``bool`` is refused (``True`` is not a count)."""
    if isinstance(x, (bool, np.bool_)) or not isinstance(x, (int, np.integer)) or minimum is not None and x < minimum:
        raise ValueError(f"{name}: expected an integer{'' if minimum is None else f' >= {minimum}'}, got {x!r}")
    return int(x)


def flag(x: object, name: str) -> bool:
    """Return ``x`` as a bool; only ``True``/``False`` (also numpy's) are accepted."""
    if not isinstance(x, (bool, np.bool_)):
        raise ValueError(f"{name}: expected True or False, got {x!r}")
    return bool(x)


def choice(x: Any, name: str, options: tuple[Any, ...]) -> Any:
    """Return ``x`` if it is one of ``options`` (strings, or e.g. the allowed integer settings); arrays are refused."""
    a_bool = isinstance(x, (bool, np.bool_))  # True is not 1 unless the options are booleans
    try:  # an array, even 0-d (which compares like its element), is refused
        ok = not isinstance(x, np.ndarray) and x in options and (not a_bool or any(isinstance(o, bool) for o in options))
    except (TypeError, ValueError):  # a value that does not compare
        ok = False
    if not ok:
        raise ValueError(f"{name}: expected one of {tuple(options)}, got {x!r}")
    return x


def text(x: Any, name: str, *, empty: bool = True) -> str:
    """Return ``x`` if it is a string (non-empty unless ``empty``): names, labels, titles, sources."""
    if not isinstance(x, str) or not empty and not x.strip():
        raise ValueError(f"{name}: expected a {'' if empty else 'non-empty '}string, got {x!r:.60}")
    return x


def file_path(x: Any, name: str) -> Path:
    """``x`` as a :class:`pathlib.Path` if it names a file or folder (a string or a path-like object)."""
    return Path(instance(x, name, (str, os.PathLike), "a file system path (str or pathlib.Path)"))


def axes(ax: Any, name: str = "ax") -> Any:
    """Return ``ax`` if it is a matplotlib Axes (duck-typed: it plots and annotates)."""
    if not hasattr(ax, "plot") or not hasattr(ax, "annotate"):
        raise ValueError(f"{name}: expected a matplotlib Axes, got {type(ax).__name__}")
    return ax


def instance(x: Any, name: str, cls: type | tuple[type, ...], what: str, *, error: type[Exception] = ValueError) -> Any:
    """Return ``x`` if it is an instance of ``cls``; else raise ``error`` saying ``what`` was expected (e.g. "an ImuModel")."""
    if not isinstance(x, cls):
        raise error(f"{name}: expected {what}, got {type(x).__name__}")
    return x


def last_axis(arr: NDArray[_S], name: str, n: int, of: str = "") -> NDArray[_S]:
    """Return ``arr`` if its last axis holds ``n`` samples (those of argument ``of``, when given, for the message).

    For series of shape (..., N) that go with a time axis of N samples.
    """
    if arr.shape[-1:] != (n,):
        raise ValueError(f"{name}: expected a last axis of length {n}{f' (that of {of})' if of else ''}, got shape {arr.shape}")
    return arr


def broadcast(*arrays: Array, name: str, of: str = "") -> list[Array]:
    """Return ``arrays`` broadcast against each other (``np.broadcast_arrays``); ``name`` is blamed if they do not.

    ``of`` names the arrays in the message when ``name`` does not (e.g. ``name="f_b", of="w_ib_b, f_b"``).
    """
    try:
        return list(np.broadcast_arrays(*arrays))
    except ValueError:
        shapes = ", ".join(str(np.shape(a)) for a in arrays)
        raise ValueError(f"{name}: shapes {shapes}{f' (of {of})' if of else ''} do not broadcast") from None


def broadcast_to(arr: NDArray[_S], name: str, shape: tuple[int, ...], of: str = "") -> NDArray[_S]:
    """``np.broadcast_to(arr, shape)``, blaming ``name`` when ``arr`` does not broadcast to ``shape`` (set by ``of``)."""
    try:
        return np.broadcast_to(arr, shape)
    except ValueError:
        raise ValueError(
            f"{name}: expected a shape that broadcasts to {tuple(shape)}{f' (that of {of})' if of else ''}, got {np.shape(arr)}"
        ) from None


def range_limit(x: object, name: str) -> float:
    """A device's full-scale range (same unit as its samples): a positive value, or ``None``/inf for no limit."""
    return np.inf if x is None else scalar(x, name, positive=True, allow_inf=True)


MIN_INTERVAL = 1e-9
"""Shortest sample interval (s) :func:`sample_intervals` accepts."""


def interval(dt: object, name: str = "dt") -> float:
    """A fixed sample interval (s): a positive scalar of at least :data:`MIN_INTERVAL`."""
    return float(sample_intervals(scalar(dt, name), 1, name)[0])


MAX_TURN_PER_SAMPLE = 1.0
"""Largest rotation (rad) a gyro may report within one integrated interval (:func:`small_turns`): first-order
attitude updates and linearised transitions are meaningless beyond it (2000 deg/s at 100 Hz is 0.35 rad)."""


def small_turns(w: Array, dts: Array, name: str = "dt") -> None:
    """Refuse intervals ``dts`` (N,) over which the gyro ``w`` (..., N, 3) turns more than :data:`MAX_TURN_PER_SAMPLE`."""
    if dts.size:  # a bound from two reductions settles the common case
        peak = max(-np.fmin.reduce(w, axis=None, initial=0.0), np.fmax.reduce(w, axis=None, initial=0.0))
        if np.sqrt(3.0) * peak * dts.max() <= MAX_TURN_PER_SAMPLE:
            return
    refuse_turn(float(np.nanmax(np.linalg.norm(w, axis=-1) * dts, initial=0.0)), name)


def refuse_turn(largest: float, name: str = "dt") -> None:
    """Refuse ``largest``, the largest gyro turn within one interval (rad), above :data:`MAX_TURN_PER_SAMPLE`."""
    if largest > MAX_TURN_PER_SAMPLE:
        raise ValueError(
            f"{name}: the gyro turns up to {largest:.3g} rad within one interval; integrating it "
            f"needs less than {MAX_TURN_PER_SAMPLE:g} rad per sample (is {name} in seconds?)"
        )


def sample_intervals(dt: object, n: int, name: str = "dt") -> Array:
    """Per-sample intervals of shape (n,) from a positive scalar or an (n,) array of positive intervals (s).

    This is navlib's one reading of ``dt``: every filter accepts a fixed interval
    or per-sample intervals (e.g. :func:`navlib.timing.intervals` of the epoch times).
    """
    arr = as_array(dt, name, huge=True)  # an interval too long to integrate over is refused by small_turns
    if arr.ndim == 0:
        arr = np.full(n, scalar(arr, name, positive=True, huge=True))
    elif arr.shape != (n,):  # (a filled scalar has the shape and sign: no second pass over n values)
        raise ValueError(f"{name}: expected a positive scalar or per-sample intervals of shape ({n},), got {arr.shape}")
    elif not np.all(arr > 0):
        raise ValueError(f"{name}: expected positive intervals, got min {arr.min():g} (run timing.sanitize first)")
    if arr.min() < MIN_INTERVAL:
        raise ValueError(
            f"{name}: expected intervals of at least {MIN_INTERVAL:g} s (no IMU samples faster than "
            f"1 GHz; is {name} in seconds?), got {arr.min():g}"
        )
    return kernel_array(arr)


def kernel_array(x: ArrayLike, dtype: Any = None) -> np.ndarray:
    """``x`` as a C-contiguous, writable array: the form every compiled kernel takes.

    numba types a read-only array (a broadcast view, a pandas column) differently from a writable one and
    compiles the kernel again for it (up to tens of seconds for a filter); a read-only ``x`` is copied.
    """
    arr = np.ascontiguousarray(x, dtype=dtype)
    return arr if arr.flags.writeable else arr.copy()


def imu_samples(
    w_ib_b: object, f_b: object, *, allow_nan: bool = True, shape: tuple[int | None, ...] | None = None
) -> tuple[Array, Array]:
    """Gyro and accelerometer samples, each (..., N, 3) with the same shape; NaN marks a dropout.

    ``shape`` fixes the shape exactly (as in :func:`as_array`), e.g. ``(None, 3)`` for one record;
    ``f_b`` is blamed when its shape differs from that of ``w_ib_b``.
    """
    w = as_array(w_ib_b, "w_ib_b", tail=(3,), min_ndim=1, allow_nan=allow_nan, shape=shape)
    f = as_array(f_b, "f_b", tail=(3,), min_ndim=1, allow_nan=allow_nan)
    return w, same_shape(f, "f_b", w.shape, of="w_ib_b")


class Check:
    """What a parameter's annotation asks of its argument (``typing.Annotated`` metadata), checked by
    :func:`navlib._validate.boundary` before the function runs: a function of :mod:`navlib._validate`, by name, and
    its options, e.g. ``Annotated[float, Check("scalar", within=(0.0, 1.0))]``. ``Check("instance")`` asks for an
    instance of the annotated class (``what``: how the message names it)."""

    __slots__ = ("validator", "options")

    def __init__(self, validator: str, **options: Any) -> None:
        self.validator = validator
        self.options = options

    def __repr__(self) -> str:
        return f"Check({self.validator!r}{''.join(f', {k}={v!r}' for k, v in self.options.items())})"


_T = TypeVar("_T")

# Checked parameter kinds: annotations that @boundary checks.
Real = Annotated[float, Check("scalar")]
"""A finite real number."""
Positive = Annotated[float, Check("scalar", positive=True)]
"""A finite number > 0."""
NonNegative = Annotated[float, Check("scalar", allow_zero=True)]
"""A finite number >= 0."""
Count = Annotated[int, Check("integer")]
"""An integer >= 1 (not a bool)."""
Flag = Annotated[bool, Check("flag")]
"""``True`` or ``False``."""
Rng = Annotated[np.random.Generator, Check("instance", what="a numpy.random.Generator")]
"""A ``numpy.random.Generator`` (no legacy global state)."""
Text = Annotated[str, Check("text")]
"""A string."""
Limit = Annotated[float, Check("scalar", positive=True, allow_inf=True)]
"""A positive limit; inf for none (e.g. a full-scale range)."""
Step = Annotated[float, Check("interval")]
"""A fixed sample interval (s), at least 1 ns."""
Fraction = Annotated[float, Check("scalar", within=(0.0, 1.0), open_ends=(True, False))]
"""A fraction in (0, 1]."""
Is = Annotated[_T, Check("instance")]
"""``Is[Cls]``: an instance of ``Cls``."""
FilePath = Annotated[Path, Check("file_path")]
"""A file or folder named by a string or path-like object, passed on as a :class:`pathlib.Path`."""
MAX_GYROCOMPASS_LAT_DEG = 89.0
"""Largest |latitude| (deg) at which gyrocompassing finds north (:data:`navlib.alignment.MAX_LAT_DEG`)."""
_GYRO_LAT = np.deg2rad(MAX_GYROCOMPASS_LAT_DEG)
GyroLatitude = Annotated[float, Check("scalar", within=(-_GYRO_LAT, _GYRO_LAT, "rad (|lat| <= 89 deg: no north near the poles)"))]
"""A latitude (rad) where gyrocompassing finds north, as :func:`navlib.alignment.gyrocompass_latitude` takes."""


_KINDS = {"Check", "Annotated"} | {k for k, v in list(globals().items()) if typing.get_origin(v) is Annotated}
"""Names whose absence from an annotation's module is a mistake, not a name only the type checker sees."""

_P = ParamSpec("_P")
_R = TypeVar("_R")


def boundary(fn: Callable[_P, _R]) -> Callable[_P, _R]:
    """Check the arguments whose annotation carries a :class:`Check` (``Positive``, ``Count``,
    ``Rng``, ``Is[Cls]``, ...) before ``fn`` runs, and pass on what the check returns (e.g. a float).

    Each check names its parameter in the error, as if the function had called it first thing. Defaults are checked
    once (when the function is first called, so that annotations may name classes defined later in the module).
    """
    params = list(inspect.signature(fn).parameters.values())

    @functools.cache
    def plan() -> list[tuple[int, str, Callable[[Any], Any], Any]]:
        found = []
        for i, p in enumerate(params):
            check = _annotated_check(p.annotation, fn.__globals__, p.name)
            if check is not None:
                default = p.default if p.default is p.empty else check(p.default)
                at = i if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD) else len(params)
                found.append((at, p.name, check, default))
        if not found:
            raise TypeError(f"{fn.__qualname__}: @boundary without a checked parameter")
        return found

    @functools.wraps(fn)
    def checked(*args: _P.args, **kwargs: _P.kwargs) -> _R:
        given = list(args)
        for at, name, check, default in plan():
            if at < len(given):
                given[at] = check(given[at])
            elif name in kwargs:
                kwargs[name] = check(kwargs[name])
            elif default is not inspect.Parameter.empty:
                kwargs[name] = default
        return fn(*given, **kwargs)  # type: ignore[arg-type]  # the same arguments, checked

    return checked


def fields_checked(record: Any) -> None:
    """Check the fields of a dataclass ``record`` annotated with a checked kind (as :func:`boundary` checks
    parameters): a record's ``__post_init__``."""
    for name, check in _field_checks(type(record)):  # type: ignore[arg-type]  # a class is Hashable; mypy reads type[Any] as not
        check(getattr(record, name))


@functools.cache
def _field_checks(cls: type) -> list[tuple[str, Callable[[Any], Any]]]:
    """The checks of ``cls``'s annotated fields, found once per record class."""
    namespace = vars(sys.modules[cls.__module__])
    found = ((f.name, _annotated_check(f.type, namespace, f.name)) for f in dataclasses.fields(cls))
    return [(name, check) for name, check in found if check is not None]


def _annotated_check(annotation: Any, namespace: dict[str, Any], name: str) -> Callable[[Any], Any] | None:
    """The check an annotation asks for (``Annotated[..., Check(...)]``, optionally ``| None``), bound to ``name``."""
    if isinstance(annotation, str):  # from __future__ import annotations
        try:
            annotation = eval(annotation, namespace)
        except NameError as exc:  # a name imported for the type checker only: not a checked kind
            if exc.name in _KINDS:
                raise TypeError(f"{name}: the checked kind {exc.name} is not imported where {annotation!r} is written") from None
            return None
    members = typing.get_args(annotation) if typing.get_origin(annotation) in (typing.Union, type(int | None)) else ()
    optional = type(None) in members
    if optional and len(members) == 2:
        annotation = next(m for m in members if m is not type(None))
    marks = [m for m in getattr(annotation, "__metadata__", ()) if isinstance(m, Check)]
    if not marks:
        return None
    mark, base = marks[0], typing.get_args(annotation)[0]
    base = typing.get_origin(base) or base  # Is[dict[str, int]]: a dict
    if mark.validator == "instance":
        what = mark.options.get("what") or f"{'an' if base.__name__[0] in 'AEIOU' else 'a'} {base.__name__}"

        def check(x: Any) -> Any:
            return instance(x, name, base, what, error=InputTypeError)

    else:
        validator = globals()[mark.validator]

        def check(x: Any) -> Any:
            return validator(x, name, **mark.options)

    return (lambda x: None if x is None else check(x)) if optional else check
