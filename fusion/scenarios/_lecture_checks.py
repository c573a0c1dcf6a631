r"""Argument checks shared by the lecture chapters' scenario modules (chapters 02 and 04)."""

from __future__ import annotations


import numpy as np
from numpy.typing import ArrayLike

from fusion._shown import shown
from fusion._validation import integer
from fusion._validation import as_array, count_ceiling
from fusion._validation import counts as check_counts, seed as V_seed


def _sigmas(sigma: ArrayLike, name: str = "sigma", minimum: int = 2) -> np.ndarray:
    r"""``sigma`` as a finite 1-D array of >= ``minimum`` positive noise SDs (ValueError naming it).

    Positive: every study weights its sensors by :math:`1/\sigma_i^2` (a zero SD has no weight). At most
    the ceiling of a count of sensors (a dimension, ``fusion._validation.COUNT_CEILINGS``).
    """
    sig = as_array(sigma, name, ndim=1)
    if sig.size > count_ceiling("sensors"):  # rule 9: one SD per sensor, a count of sensors is a dimension
        raise ValueError(f"{name} holds {sig.size} sensors, beyond the ceiling of a count of dimension "
                         f"({count_ceiling('sensors'):,}; fusion._validation.COUNT_CEILINGS)")
    if np.any(sig <= 0):  # by its length first, then the first bad entry shown (fix72e: 10**7 negative SDs were all
        # printed, a message of 60 million characters built in 1.6 CPU-s, before the ceiling refused their number)
        i = int(np.argmax(sig <= 0))
        raise ValueError(f"{name} must hold positive noise SDs, got {name}[{i}] = {shown(float(sig[i]))} "
                         f"(of {sig.size} entries: {shown(sig.tolist()) if sig.size <= 20 else 'not shown'})")
    if sig.size < minimum:
        raise ValueError(f"{name} must hold at least {minimum} sensors, got {sig.size}")
    return sig


def _values(v: ArrayLike, name: str) -> np.ndarray:
    """A finite, non-empty 1-D array of numbers."""
    return as_array(v, name, ndim=1)


def _ints(v: ArrayLike, name: str, minimum: int = 1) -> np.ndarray:
    """A non-empty 1-D array of integers >= ``minimum`` (as floats), each entry checked by name."""
    if isinstance(v, np.ndarray) and v.ndim != 1:
        raise ValueError(f"{name} must be 1-D, got shape {v.shape}")
    return np.array(check_counts(v, name, minimum), dtype=float)


def _seed(seed: int, name: str = "seed") -> int:
    return V_seed(seed, name)


def _index(i: int, n: int, name: str) -> int:
    i = integer(i, name)
    if not 0 <= i < n:
        raise ValueError(f"{name} must be in [0, {n}), got {i}")
    return int(i)

