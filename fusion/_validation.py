"""Input validation shared by every public function of :mod:`fusion`.

Every check raises :class:`ValueError` with a message that names the argument and
the problem, so that bad input never turns into a silent ``nan`` further down, and
:class:`TypeError` (also naming the argument) for a value of the wrong type, such as a
string where an array or a number is expected. The checks are cheap next to the work
they guard (``benchmarks/bench_validation.py`` measures them).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.linalg.lapack import dpotrf as _potrf

FloatArray = NDArray[np.float64]


def _numeric(x: ArrayLike, name: str) -> FloatArray:
    """``np.asarray(x, dtype=float)``, with a :class:`TypeError` naming ``name`` for non-numbers."""
    if isinstance(x, (str, bytes)):
        raise TypeError(f"{name} must be numeric, got a string {x!r}")
    if isinstance(x, np.ndarray) and x.dtype == np.float64:
        return x
    try:
        return np.asarray(x, dtype=float)
    except (TypeError, ValueError) as exc:
        raise TypeError(f"{name} must be numeric (array_like of numbers): {exc}") from None


def as_array(
    x: ArrayLike,
    name: str,
    ndim: int | tuple[int, ...] | None = None,
    shape: tuple[int | None, ...] | None = None,
    *,
    finite: bool = True,
    nonempty: bool = True,
    nonnegative: bool = False,
) -> FloatArray:
    """Return ``x`` as a float array, checking dimensions, shape, emptiness and finiteness.

    Parameters
    ----------
    x : array_like
        The value to check.
    name : str
        Argument name used in error messages.
    ndim : int or tuple of int, optional
        Allowed numbers of dimensions.
    shape : tuple of int or None, optional
        Required shape; ``None`` entries match any length (implies ``ndim``).
    finite : bool
        Refuse NaN and infinity.
    nonempty : bool
        Refuse arrays with no element.
    nonnegative : bool
        Refuse negative entries.

    Raises
    ------
    TypeError
        If ``x`` is not numeric (e.g. a string).
    ValueError
        Wrong dimensions or shape, empty, NaN/inf, or negative entries.
    """
    arr = _numeric(x, name)
    if shape is not None:
        ok = arr.ndim == len(shape) and all(s is None or s == a for s, a in zip(shape, arr.shape))
        if not ok:
            want = "(" + ", ".join("n" if s is None else str(s) for s in shape) + ("," if len(shape) == 1 else "") + ")"
            raise ValueError(f"{name} must have shape {want}, got {arr.shape}")
    elif ndim is not None:
        allowed = (ndim,) if isinstance(ndim, int) else ndim
        if arr.ndim not in allowed:
            raise ValueError(f"{name} must be {' or '.join(f'{d}-D' for d in allowed)}, got shape {arr.shape}")
    if nonempty and arr.size == 0:
        raise ValueError(f"{name} is empty (shape {arr.shape})")
    if finite and not np.isfinite(arr).all():
        raise ValueError(f"{name} contains NaN or infinite values")
    if nonnegative and np.any(arr < 0):
        raise ValueError(f"{name} must be non-negative")
    return arr


def same_length(a: FloatArray, name_a: str, b: FloatArray, name_b: str, axis_a: int = 0, axis_b: int = 0) -> None:
    """Check that two paired arrays have the same length along the given axes."""
    if a.shape[axis_a] != b.shape[axis_b]:
        raise ValueError(
            f"{name_a} and {name_b} must have matching lengths, got {a.shape[axis_a]} and {b.shape[axis_b]} "
            f"(shapes {a.shape} and {b.shape})"
        )


def scalar(
    value: float,
    name: str,
    lo: float | None = None,
    hi: float | None = None,
    *,
    lo_open: bool = False,
    hi_open: bool = False,
) -> float:
    """Return ``value`` as a finite float in the interval given by ``lo`` and ``hi``.

    Raises
    ------
    TypeError
        If ``value`` is not a real number (a string, an array of more than one element, ...).
    ValueError
        If ``value`` is NaN, infinite or out of range.
    """
    if isinstance(value, (str, bytes)) or value is None:
        raise TypeError(f"{name} must be a number, got {value!r}")
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be a number, got {value!r}") from None
    if not np.isfinite(v):
        raise ValueError(f"{name} must be finite, got {value!r}")
    if lo is not None and (v < lo or (lo_open and v == lo)):
        if lo == 0.0:
            raise ValueError(f"{name} must be {'positive' if lo_open else 'non-negative'}, got {value!r}")
        raise ValueError(f"{name} must be {'>' if lo_open else '>='} {lo}, got {value!r}")
    if hi is not None and (v > hi or (hi_open and v == hi)):
        raise ValueError(f"{name} must be {'<' if hi_open else '<='} {hi}, got {value!r}")
    return v


def nonnegative_scalar(value: float, name: str) -> float:
    """Return ``value`` as a finite float >= 0."""
    return scalar(value, name, lo=0.0)


def unit_scalar(value: float, name: str) -> float:
    """Return ``value`` as a finite float in the closed interval [0, 1]."""
    return scalar(value, name, lo=0.0, hi=1.0)


def count(value: int, name: str, minimum: int = 1) -> int:
    """Return ``value`` as an int >= ``minimum`` (integral floats such as ``3.0`` are accepted).

    Raises
    ------
    TypeError
        If ``value`` is not a number (a string, ``None``, ...).
    ValueError
        If ``value`` is not integral or below ``minimum``.
    """
    if isinstance(value, (str, bytes, bool)) or value is None:
        raise TypeError(f"{name} must be an integer, got {value!r}")
    if isinstance(value, (int, np.integer)):
        v = int(value)
    else:
        try:
            f = float(value)
        except (TypeError, ValueError):
            raise TypeError(f"{name} must be an integer, got {value!r}") from None
        if not np.isfinite(f) or f != int(f):
            raise ValueError(f"{name} must be an integer, got {value!r}")
        v = int(f)
    if v < minimum:
        want = "a positive integer" if minimum == 1 else f"an integer >= {minimum}"
        raise ValueError(f"{name} must be {want}, got {value!r}")
    return v


def as_rng(rng: object, name: str = "rng") -> np.random.Generator:
    """Check that ``rng`` is a :class:`numpy.random.Generator` (TypeError otherwise)."""
    if not isinstance(rng, np.random.Generator):
        raise TypeError(f"{name} must be a numpy.random.Generator, got {type(rng).__name__}")
    return rng


def as_callable(f: object, name: str) -> object:
    """Check that ``f`` is callable (TypeError otherwise)."""
    if not callable(f):
        raise TypeError(f"{name} must be callable, got {type(f).__name__}")
    return f


def instance_of(obj: object, cls: type | tuple[type, ...], name: str) -> None:
    """Check ``isinstance(obj, cls)`` (TypeError naming ``name`` otherwise)."""
    if not isinstance(obj, cls):
        want = cls.__name__ if isinstance(cls, type) else " or ".join(c.__name__ for c in cls)
        raise TypeError(f"{name} must be a {want}, got {type(obj).__name__}")


def as_weights(w: ArrayLike, name: str, n: int | None = None) -> FloatArray:
    """Return ``w`` as a finite, non-negative 1-D float vector with a positive sum (length ``n``)."""
    arr = as_array(w, name, ndim=1, nonnegative=True)
    if n is not None and arr.size != n:
        raise ValueError(f"{name} must have length {n}, got {arr.size}")
    if not arr.sum() > 0:
        raise ValueError(f"{name} must have a positive sum")
    return arr


def as_readings(x: ArrayLike, name: str = "x") -> FloatArray:
    """Return ``x`` as a non-empty, finite, 1-D float array.

    Parameters
    ----------
    x : array_like, shape (n,)
        Simultaneous scalar readings of one quantity.
    name : str
        Argument name used in error messages.

    Raises
    ------
    ValueError
        If ``x`` is not 1-D, is empty, or contains NaN or infinity.
    """
    arr = _numeric(x, name)
    if arr.ndim != 1:
        raise ValueError(f"{name} must be a 1-D array of readings, got shape {arr.shape}")
    if arr.size == 0:
        raise ValueError(f"{name} is empty: at least one reading is needed")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} contains NaN or infinite values")
    return arr


def as_reading_rows(x: ArrayLike, name: str = "x") -> FloatArray:
    """Return ``x`` as a finite 2-D float array of shape (n_epochs, n_sensors).

    A 1-D input is treated as a single epoch (one row).

    Raises
    ------
    ValueError
        If ``x`` has more than two dimensions, has no sensor column, or is not finite.
    """
    arr = _numeric(x, name)
    if arr.ndim == 1:
        arr = arr[None, :]
    if arr.ndim != 2:
        raise ValueError(
            f"{name} must be 2-D (n_epochs, n_sensors) or 1-D (n_sensors,), got shape {arr.shape}"
        )
    if arr.shape[1] == 0 or arr.shape[0] == 0:
        raise ValueError(f"{name} is empty: got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} contains NaN or infinite values")
    return arr


def positive_scalar(value: float, name: str) -> float:
    """Return ``value`` as a float, checking that it is finite and strictly positive."""
    if isinstance(value, (str, bytes)) or value is None:
        raise TypeError(f"{name} must be a number, got {value!r}")
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be a number, got {value!r}") from None
    if not np.isfinite(v) or v <= 0.0:
        raise ValueError(f"{name} must be a finite positive number, got {value!r}")
    return v


def one_of(value: str, allowed: tuple[str, ...], name: str) -> str:
    """Check that a string option is one of ``allowed`` (TypeError if it is not a string)."""
    if not isinstance(value, str):
        raise TypeError(f"{name} must be a string, one of {allowed}, got {type(value).__name__}")
    if value not in allowed:
        raise ValueError(f"{name} must be one of {allowed}, got {value!r}")
    return value


def as_state(x: ArrayLike, name: str = "x") -> FloatArray:
    """Return ``x`` as a finite 1-D float state vector of length >= 1."""
    arr = _numeric(x, name)
    if arr.ndim == 0:
        arr = arr[None]
    if arr.ndim != 1 or arr.size == 0:
        raise ValueError(f"{name} must be a non-empty 1-D vector, got shape {arr.shape}")
    if not np.isfinite(arr).all():
        raise ValueError(f"{name} contains NaN or infinite values")
    return arr


_TINY = float(np.finfo(float).tiny)


def _finite_symmetric(arr: FloatArray, name: str, rtol: float) -> tuple[FloatArray, float]:
    """Check a square matrix for NaN/inf and asymmetry; return its symmetric part and its scale.

    One pass in the usual case: ``arr - arr.T`` is exactly zero for a finite symmetric matrix,
    and NaN or infinite as soon as any entry is (inf - inf is NaN, so a symmetric pair of
    infinities is caught too). Only a non-zero difference needs the scale of the entries.
    """
    if arr.shape[-1] == 1:
        v = float(arr.flat[0]) if arr.size == 1 else float(np.abs(arr).max())
        if not abs(v) < np.inf:
            raise ValueError(f"{name} contains NaN or infinite values")
        return arr, max(abs(v), _TINY)
    with np.errstate(invalid="ignore"):  # inf - inf is NaN: reported as non-finite just below
        asym = float(np.abs(arr - np.swapaxes(arr, -1, -2)).max())
    if asym == 0.0:
        return arr, -1.0  # exactly symmetric (and finite); scale not needed
    if not asym < np.inf:
        raise ValueError(f"{name} contains NaN or infinite values")
    scale = max(float(np.abs(arr).max()), _TINY)
    if asym > rtol * scale:
        raise ValueError(f"{name} must be symmetric")
    return 0.5 * (arr + np.swapaxes(arr, -1, -2)), scale


def as_covariance(P: ArrayLike, dim: int | None = None, name: str = "P", rtol: float = 1e-9) -> FloatArray:
    """Return ``P`` as a finite, symmetric, positive-definite (dim, dim) float matrix.

    A scalar or a 1x1 input is accepted for dimension one.

    Raises
    ------
    TypeError
        If ``P`` is not numeric.
    ValueError
        Wrong shape, NaN/inf, asymmetry beyond ``rtol`` (relative to the largest entry),
        or not positive definite (Cholesky fails).
    """
    arr = _numeric(P, name)
    if arr.ndim == 0:
        arr = arr.reshape(1, 1)
    if arr.ndim != 2 or arr.shape[0] != arr.shape[1] or arr.shape[0] == 0:
        raise ValueError(f"{name} must be a square matrix, got shape {arr.shape}")
    if dim is not None and arr.shape[0] != dim:
        raise ValueError(f"{name} must be {dim}x{dim} to match the state, got {arr.shape}")
    sym, _ = _finite_symmetric(arr, name, rtol)
    if _potrf(arr, lower=1, clean=0)[1] != 0:  # LAPACK Cholesky: info > 0 if not positive definite
        raise ValueError(f"{name} must be positive definite")
    return sym


def as_semidefinite(P: ArrayLike, dim: int, name: str = "P", rtol: float = 1e-9) -> FloatArray:
    """Return ``P`` as a finite, symmetric, positive-semidefinite (dim, dim) float matrix.

    For process noise, which is often of low rank (e.g. white acceleration).

    Raises
    ------
    ValueError
        Wrong shape, NaN/inf, asymmetry, or an eigenvalue below ``-rtol`` times the largest entry.
    """
    arr = _numeric(P, name)
    if arr.shape != (dim, dim):
        raise ValueError(f"{name} must be {dim}x{dim}, got shape {arr.shape}")
    sym, scale = _finite_symmetric(arr, name, rtol)
    if scale < 0:
        scale = max(float(np.abs(sym).max()), _TINY)
    if np.linalg.eigvalsh(sym).min() < -rtol * scale:
        raise ValueError(f"{name} must be positive semidefinite")
    return sym


def gaussian_pair(
    m0: ArrayLike, P0: ArrayLike, m1: ArrayLike, P1: ArrayLike, names: tuple[str, str, str, str]
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """Two Gaussians (means of one length, SPD covariances of that size), validated.

    ``names`` are the four argument names used in the messages.
    """
    a, b = as_state(m0, names[0]), as_state(m1, names[2])
    if a.shape != b.shape:
        raise ValueError(f"{names[0]} and {names[2]} must have the same length, got {a.size} and {b.size}")
    A = as_covariance(P0, name=names[1])
    if A.shape[0] != a.size:
        raise ValueError(f"{names[1]} must be {a.size}x{a.size} to match {names[0]}, got {A.shape}")
    B = as_covariance(P1, name=names[3])
    if B.shape[0] != a.size:
        raise ValueError(f"{names[3]} must be {a.size}x{a.size} to match {names[0]}, got {B.shape}")
    return a, A, b, B


def psd_factor(S: FloatArray) -> FloatArray:
    """A factor ``L`` with ``L @ L.T == S`` of a validated positive-semidefinite matrix.

    The Cholesky factor when ``S`` is positive definite (so results of existing callers do
    not change), otherwise the symmetric square root from the eigen-decomposition.
    """
    try:
        return np.linalg.cholesky(S)
    except np.linalg.LinAlgError:
        lam, V = np.linalg.eigh(S)
        return V * np.sqrt(np.clip(lam, 0.0, None))
