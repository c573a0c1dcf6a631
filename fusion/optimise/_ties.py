"""Comparisons of objective values that round-off cannot decide.

Two evaluations of one objective on two machines (or with another BLAS kernel or thread
count) may differ in the last bits. An optimiser that compares such values with ``<`` then
takes another path, and a flat objective is minimised by noise. Here values within
``rtol * max(|v|, 1)`` of each other (relative above 1, absolute below) are *ties*, broken by
order (the first one wins), and an improvement counts only when it exceeds that tolerance. A decision can still change only
if a true difference lies within round-off of the tolerance itself, which is rare.

Below 1 the tolerance is absolute, so the objective's units matter there: an objective whose values over the
region differ by less than 1e-9 ties everywhere (fuzz 46b C3: the covariance-intersection objective with both
covariances times 1e-8 ties over omega in [0.42, 0.63] and the grid returns 0.415 for 0.632; times 1e-10, 0.0).
Give objectives of order one. A margin relative to ``|v|`` alone would make the rule unit-free but changes which
point wins on the book's own objectives, whose values are below 1 (chapters 05 and 06: measured, left for a
decision with those chapters re-executed).
"""

from __future__ import annotations

import numpy as np

from fusion._validation import FloatArray

#: Difference, relative to ``max(|value|, 1)``, below which two objective values count as equal (round-off is
#: ~1e-16 relative).
TIE_RTOL = 1e-9


def _margin(reference: float, rtol: float) -> float:
    return rtol * max(abs(reference), 1.0)


def first_minimum(values: FloatArray, rtol: float = TIE_RTOL) -> int:
    """Index of the first value within ``rtol`` of the smallest (ties go to the lowest index)."""
    v = np.asarray(values, dtype=float)
    lowest = float(np.min(v))
    return int(np.flatnonzero(v <= lowest + _margin(lowest, rtol))[0])


def improves(candidate: float, best: float, rtol: float = TIE_RTOL) -> bool:
    """``candidate`` is lower than ``best`` by more than the tie tolerance (``best`` may be inf)."""
    if not np.isfinite(best):
        return bool(candidate < best)
    return bool(candidate < best - _margin(best, rtol))


def first_minimum_rows(values: FloatArray, rtol: float = TIE_RTOL) -> FloatArray:
    """:func:`first_minimum` of every row of a 2-D array (index per row, same tie rule)."""
    v = np.asarray(values, dtype=float)
    lowest = np.min(v, axis=1)
    margin = rtol * np.maximum(np.abs(lowest), 1.0)
    return np.argmax(v <= (lowest + margin)[:, None], axis=1)


def improves_rows(candidate: FloatArray, best: FloatArray, rtol: float = TIE_RTOL) -> FloatArray:
    """:func:`improves` elementwise (``best`` may hold inf)."""
    c, b = np.asarray(candidate, dtype=float), np.asarray(best, dtype=float)
    finite = np.isfinite(b)
    with np.errstate(invalid="ignore"):
        margin = rtol * np.maximum(np.abs(b), 1.0)
        return np.where(finite, c < b - margin, c < b)
