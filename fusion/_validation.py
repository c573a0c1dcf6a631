"""Input validation shared by every public function of :mod:`fusion`.

Every check raises :class:`ValueError` with a message that names the argument and
the problem, so that bad input never turns into a silent ``nan`` further down.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

FloatArray = NDArray[np.float64]


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
    arr = np.asarray(x, dtype=float)
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
    arr = np.asarray(x, dtype=float)
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
    v = float(value)
    if not np.isfinite(v) or v <= 0.0:
        raise ValueError(f"{name} must be a finite positive number, got {value!r}")
    return v


def one_of(value: str, allowed: tuple[str, ...], name: str) -> str:
    """Check that a string option is one of ``allowed``."""
    if value not in allowed:
        raise ValueError(f"{name} must be one of {allowed}, got {value!r}")
    return value


def as_state(x: ArrayLike, name: str = "x") -> FloatArray:
    """Return ``x`` as a finite 1-D float state vector of length >= 1."""
    arr = np.asarray(x, dtype=float)
    if arr.ndim == 0:
        arr = arr[None]
    if arr.ndim != 1 or arr.size == 0:
        raise ValueError(f"{name} must be a non-empty 1-D vector, got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} contains NaN or infinite values")
    return arr


def _finite_symmetric(arr: FloatArray, name: str, rtol: float) -> tuple[FloatArray, float]:
    """Check a square matrix for NaN/inf and asymmetry; return its symmetric part and its scale."""
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} contains NaN or infinite values")
    scale = max(float(np.max(np.abs(arr))), np.finfo(float).tiny)
    if np.max(np.abs(arr - arr.T)) > rtol * scale:
        raise ValueError(f"{name} must be symmetric")
    return 0.5 * (arr + arr.T), scale


def as_covariance(P: ArrayLike, dim: int | None = None, name: str = "P", rtol: float = 1e-9) -> FloatArray:
    """Return ``P`` as a finite, symmetric, positive-definite (dim, dim) float matrix.

    A scalar or a 1x1 input is accepted for dimension one.

    Raises
    ------
    ValueError
        Wrong shape, NaN/inf, asymmetry beyond ``rtol`` (relative to the largest entry),
        or not positive definite (Cholesky fails).
    """
    arr = np.asarray(P, dtype=float)
    if arr.ndim == 0:
        arr = arr.reshape(1, 1)
    if arr.ndim != 2 or arr.shape[0] != arr.shape[1] or arr.shape[0] == 0:
        raise ValueError(f"{name} must be a square matrix, got shape {arr.shape}")
    if dim is not None and arr.shape[0] != dim:
        raise ValueError(f"{name} must be {dim}x{dim} to match the state, got {arr.shape}")
    sym, _ = _finite_symmetric(arr, name, rtol)
    try:
        np.linalg.cholesky(arr)
    except np.linalg.LinAlgError:
        raise ValueError(f"{name} must be positive definite") from None
    return sym


def as_semidefinite(P: ArrayLike, dim: int, name: str = "P", rtol: float = 1e-9) -> FloatArray:
    """Return ``P`` as a finite, symmetric, positive-semidefinite (dim, dim) float matrix.

    For process noise, which is often of low rank (e.g. white acceleration).

    Raises
    ------
    ValueError
        Wrong shape, NaN/inf, asymmetry, or an eigenvalue below ``-rtol`` times the largest entry.
    """
    arr = np.asarray(P, dtype=float)
    if arr.shape != (dim, dim):
        raise ValueError(f"{name} must be {dim}x{dim}, got shape {arr.shape}")
    sym, scale = _finite_symmetric(arr, name, rtol)
    if np.linalg.eigvalsh(sym).min() < -rtol * scale:
        raise ValueError(f"{name} must be positive semidefinite")
    return sym
