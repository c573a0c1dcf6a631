"""Checks of published numbers: can a printed value come out of the stated data at all?

These functions do not fuse anything new; they ask questions of a published table:
whether a value is a convex combination of its readings, which subsets of readings
reproduce it, and which parameter values of a method would be needed to reach it.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import brentq

from fusion._validation import within, FloatArray, as_array, as_callable, as_readings, count, nonnegative_scalar, one_of, positive_scalar, scalar
from fusion._limits import ROUND_OFF_TIE
from fusion._validation import LOOP_STEP, pairwise, shown
from fusion._objectives import objective_values
from fusion._validation import text
from fusion._results import ResultSpec, integer, number, tuple_of, validated_post_init
from fusion.readings._row_blocks import CUBIC, PAIRS
from fusion.readings.fusion_set import METHODS, fuse_epochs

__all__ = [
    "in_convex_hull",
    "SubsetMatch",
    "matching_subsets",
    "implied_sum_change",
    "parameters_matching",
]


def in_convex_hull(x: ArrayLike, value: float, tol: float = 0.0) -> bool:
    """Whether ``value`` is a convex combination of the readings ``x``.

    For scalar readings the convex hull is the interval ``[min(x), max(x)]``; no weights
    that are non-negative and sum to one can produce a value outside it.

    Parameters
    ----------
    x : array_like, shape (n,)
        Readings.
    value : float
        Published fused value, in the readings' unit.
    tol : float
        Allowance for the rounding of the published value.

    Returns
    -------
    bool
        ``min(x) - tol <= value <= max(x) + tol``.
    """
    s = as_readings(x)
    value, tol = scalar(value, "value"), nonnegative_scalar(tol, "tol")
    return bool(s.min() - tol <= value <= s.max() + tol)


@dataclass(frozen=True)
class SubsetMatch:
    """A subset of readings whose fused value matches a target.

    A result of :func:`matching_subsets`; the constructor checks its fields and stores what it read (plain ints
    and a float, never a caller's 0-d array: fuzz 29a C1).

    Attributes
    ----------
    members : tuple of int
        0-based indices of the readings in the subset.
    value : float
        Fused value of the subset.

    Raises
    ------
    TypeError
        ``members`` not a tuple (or list) of integers, ``value`` not a real number.
    ValueError
        A negative member, ``value`` not finite.
    """

    members: tuple[int, ...]
    value: float

    __result_spec__ = ResultSpec({"members": tuple_of(integer(0)), "value": number(nonnegative=False)})
    __post_init__ = validated_post_init


def matching_subsets(
    x: ArrayLike,
    target: float,
    tol: float,
    fuse: Callable[[FloatArray], float],
) -> list[SubsetMatch]:
    """All non-empty subsets of ``x`` whose fused value is within ``tol`` of ``target``.

    Parameters
    ----------
    x : array_like, shape (n,), n <= 12
    target : float
    tol : float
        Half-width of the match, e.g. half a unit of the last printed decimal.
    fuse : callable
        Maps the readings of a subset (1-D array) to a fused value (a finite real number).

    Returns
    -------
    list of SubsetMatch
        In order of subset size, then lexicographic.

    Raises
    ------
    TypeError
        If ``fuse`` returns something that is not one real number (None, complex, an array, a string).
    ValueError
        If ``fuse`` returns NaN or an infinity (which would silently match nothing).
    """
    s = as_readings(x)
    target, tol = scalar(target, "target"), nonnegative_scalar(tol, "tol")
    as_callable(fuse, "fuse")
    if s.size > 12:
        raise ValueError(f"x must hold at most 12 readings (matching_subsets enumerates the 2^n subsets), got {s.size}")
    out = []
    for k in range(1, s.size + 1):
        for idx in itertools.combinations(range(s.size), k):
            v = float(objective_values(fuse(s[list(idx)]), (), "fuse"))  # one real number, not NaN
            if not np.isfinite(v):
                raise ValueError(f"fuse returned {v} for the subset {idx}: a fused value must be finite")
            if abs(v - target) <= tol:
                out.append(SubsetMatch(members=idx, value=v))
    return out


def implied_sum_change(x: ArrayLike, published_mean: float) -> float:
    r"""Change of the sum of readings implied by a published mean: ``n * mean - sum(x)``.

    If one reading was mistyped (or changed) and the published mean was computed from the
    other value, that reading differs by exactly this amount.

    Parameters
    ----------
    x : array_like, shape (n,)
        Readings as printed.
    published_mean : float
        Published arithmetic mean, in the readings' unit.

    Returns
    -------
    float
        :math:`n\bar x_{pub} - \sum_i x_i`, in the readings' unit.
    """
    s = as_readings(x)
    published_mean = scalar(published_mean, "published_mean")
    return float(s.size * published_mean - s.sum())


# Options of fuse_epochs that are not numbers (a text choice, a flag): never solved for.
_NOT_NUMERIC = frozenset({"threshold", "include_self"})


def _option_name(method: str, name: str) -> tuple[str, str]:
    """``name`` must be an option of ``method`` (see :data:`fusion.readings.fusion_set.METHODS`); both returned as
    plain strings (rule 19 of ``fusion._validation``)."""
    method = one_of(method, tuple(METHODS), "method")
    allowed = tuple(o for o in METHODS[method][1] if o not in _NOT_NUMERIC)   # the options a root can be
    if not isinstance(name, str):   # a wrong type (a path, a number) is a TypeError (issue 35)
        raise TypeError(f"name must be an option name (a str), got {type(name).__name__}")
    name = text(name, "name")
    if name not in allowed:
        raise ValueError(f"name must be a numeric option of method {shown(method)}, one of {allowed}, got {shown(name)}")
    return method, name


def parameters_matching(
    x: ArrayLike,
    target: float,
    method: str,
    name: str,
    lo: float,
    hi: float,
    n_grid: int = 400,
    **options: object,
) -> FloatArray:
    """Values of a positive option for which the fused value equals ``target``.

    Brackets sign changes of ``fused - target`` on a log-spaced grid over ``[lo, hi]``
    and refines each with Brent's method. An empty result means the target cannot be
    reached with any value of the option in that range.

    A refined value is returned only where the fused value equals ``target`` to round-off: ``|fused - target|``
    at most ``ROUND_OFF_TIE`` (1e-9, the package's tie rule, ``fusion._limits``) times the larger of ``|target|``
    and the readings' largest magnitude. A sign change across a jump of a step option (``belief_degree``'s
    ``binary_eps`` and ``limit``: the fused value steps past the target) is refined onto the jump, where the fused
    value is not the target: not a root (fuzz 40b C4 returned 0.3 and 49.6, where it is 900.25 and 904.33, for 905).

    Parameters
    ----------
    x : array_like, shape (n,)
        Readings.
    target : float
        Published fused value to match.
    method : str
        A method of :func:`fusion.readings.fusion_set.fuse_epochs`.
    name : str
        Numeric option to solve for (e.g. ``"alpha"`` or ``"scale"``), taking positive values; not a text option
        or a flag (``"threshold"``, ``"include_self"``).
    lo, hi : float
        Search range, ``0 < lo < hi``.
    n_grid : int
        Points of the log-spaced bracketing grid.
    **options
        Other options, held fixed.

    Returns
    -------
    ndarray
        Sorted roots (possibly empty). Degenerate case: when the fused value does not depend on the option (one
        reading, or all readings equal) and equals ``target``, every grid point is a root and all are returned.

    Raises
    ------
    TypeError
        ``name`` not a str.
    ValueError
        ``name`` not a numeric option of ``method``; ``lo`` or ``hi`` not positive, ``hi <= lo``, or bad readings; readings whose pairwise kernel over the
        ``n_grid`` points is beyond the work budget.
    """
    lo = positive_scalar(lo, "lo")
    hi = positive_scalar(hi, "hi")
    if hi <= lo:
        raise ValueError("hi must exceed lo")
    s = as_readings(x)
    target = scalar(target, "target")
    n_grid = count(n_grid, "n_grid", minimum=2)
    method, name = _option_name(method, name)
    # one fusion a grid point: its kernel plus the call's own cost, ~23 us measured for 5 readings (2 loop steps;
    # budget35: 2e6 points, about 45 CPU-s, were accepted), so the edge is about 10 CPU-s
    pairwise(s.size, "x and n_grid", PAIRS[method], rows=n_grid, cubic=method in CUBIC, step=2 * LOOP_STEP)

    def g(log_p: float) -> float:
        return float(fuse_epochs(s, method, **{name: float(np.exp(log_p))}, **options).values[0] - target)

    grid = np.linspace(np.log(lo), np.log(hi), n_grid)
    vals = np.array([g(v) for v in grid])
    tie = ROUND_OFF_TIE * max(abs(target), float(np.max(np.abs(s))))   # equal to round-off (the tie rule)
    roots = []
    for a, b, fa, fb in zip(grid[:-1], grid[1:], vals[:-1], vals[1:]):
        if fa == 0.0:
            roots.append(float(np.exp(a)))
        elif fa * fb < 0.0:
            r = brentq(g, a, b, xtol=1e-12)
            if abs(g(r)) <= tie:   # a root, not a jump of a step option across the target (fuzz 40b C4)
                roots.append(float(np.exp(r)))
    if vals[-1] == 0.0:   # hi itself (each bracket checks its left end only)
        roots.append(float(np.exp(grid[-1])))
    return np.array(sorted(roots))
