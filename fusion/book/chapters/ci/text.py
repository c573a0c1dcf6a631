"""Number formatting for chapter 05's prose and tables: readable powers of ten, paired differences, NEES bands."""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy.stats import chi2
from numpy.typing import ArrayLike

from fusion._docstrings import with_sections
from fusion._shown import shown
from fusion._validation import as_array, count
from fusion.book.ledger import Comparison, fmt
from fusion.book.tables import _SUPERSCRIPT, ROUNDOFF_EXPONENT, _printed_number

__all__ = ["readable", "paired_text", "nees_band", "excess_text"]


def _glue_doc(values: str = "") -> Any:
    """The docstring sections a glue function of the chapter shares (:func:`fusion._docstrings.with_sections`):
    Returns ``dict``, glue key -> value (``values``: what the values are, in parentheses), and References, the
    chapter's source."""
    return with_sections(returns=f"dict\n    Glue key -> value{f' ({values})' if values else ''}.",
                         references="* Wang, W., & Tang, Y. (2024), the chapter's source (see the bibliography).")


def readable(x: float, digits: int = 2) -> str:
    """A number for prose: ``digits`` significant digits, powers of ten written "1.8 × 10⁻¹²".

    Parameters
    ----------
    x : float
        The number.
    digits : int
        Significant digits.

    Returns
    -------
    str
        E.g. ``"0.12"``, ``"1.75 × 10¹¹"``, ``"0"``; ``"—"`` for NaN, ``"∞"`` and ``"-∞"`` for the infinities
        (``fusion.book.tables.NONFINITE_RULE``, through :func:`fusion.book.ledger.fmt`).

    Raises
    ------
    TypeError
        ``x`` is text or another non-number, naming ``x``.

    References
    ----------
    The book's house rules on numbers in prose (book/api.md).
    """
    s = fmt(x, digits)
    if "×10^" in s:
        mant, exp = s.split("×10^")
        s = f"{mant} × 10{exp.translate(_SUPERSCRIPT)}"
    return s


def paired_text(a: ArrayLike, b: ArrayLike, digits: int = 2) -> str:
    """Mean paired difference A - B with its 95 % interval, for prose: "1.9 (95 % CI 1.8 to 2.0)".

    Parameters
    ----------
    a, b : array_like, shape (runs,)
        Per-run metrics of the two methods on the same runs.
    digits : int
        Significant digits.

    Returns
    -------
    str
        The mean of ``a - b`` and the ends of its 95 % interval, each with ``digits`` significant digits
        (:func:`readable`).

    Raises
    ------
    TypeError
        ``a`` or ``b`` not numeric.
    ValueError
        ``a`` or ``b`` not a 1-D array of finite numbers, or of different lengths.

    References
    ----------
    :meth:`fusion.book.ledger.Comparison.interval` (paired t interval, scipy.stats.ttest_rel).
    """
    a = as_array(a, "a", ndim=1)
    b = as_array(b, "b", ndim=1)
    if a.shape != b.shape:
        raise ValueError(f"a and b must hold the same runs (paired), got {a.size} and {b.size}")
    mean, lo, hi = Comparison(a, b, "A", "B", "less", "metric", reason="prose only").interval()
    return f"{readable(mean, digits)} (95 % CI {readable(lo, digits)} to {readable(hi, digits)})"


def nees_band(runs: int, n: int = 4) -> float:
    """Upper 97.5 % point of one step's NEES averaged over ``runs`` runs of a consistent estimator.

    Parameters
    ----------
    runs : int
        Number of independent runs averaged.
    n : int
        State dimension.

    Returns
    -------
    float
        ``chi2.ppf(0.975, n * runs) / runs``: the mean of ``runs`` independent chi-square(n) variables.

    References
    ----------
    Bar-Shalom, Li & Kirubarajan (2001), *Estimation with Applications to Tracking and Navigation*, §5.4.2.
    """
    runs, n = count(runs, "runs"), count(n, "n")
    return float(chi2.ppf(0.975, n * runs) / runs)


def excess_text(excess: float) -> str:
    """Where a search ends relative to the minimum, for prose.

    Parameters
    ----------
    excess : float
        Objective value found minus the minimum (>= 0 up to round-off: a negative excess above
        :math:`-10^{e}`, :data:`fusion.book.tables.ROUNDOFF_EXPONENT`, is round-off).

    Returns
    -------
    str
        "at the minimum" when the excess is zero or a negative round-off, else "<excess> above the minimum".

    Raises
    ------
    TypeError
        ``excess`` is text (``"1"`` is not read as 1) or another non-number (a bool included), naming ``excess``.
    ValueError
        ``excess`` not finite, or negative beyond round-off (a search cannot end below the minimum): a residual
        of a search, refused rather than printed as a word (as ``fusion.book.tables.roundoff``).

    References
    ----------
    The book's house rules on numbers in prose.
    """
    excess = _printed_number(excess, "excess")  # any finite magnitude: the formatters' one rule (fuzz 19)
    if excess < -(10.0 ** ROUNDOFF_EXPONENT):  # fuzz 18, E3, E4 and F16
        raise ValueError(f"excess must be >= {-(10.0 ** ROUNDOFF_EXPONENT)} (a search cannot end below the minimum "
                         f"beyond round-off), got {shown(excess)}")
    if excess <= 0.0:
        return "at the minimum"
    return f"{readable(excess)} above the minimum"


def _sig3(v: float) -> Any:
    return float(f"{v:.3g}") if np.isfinite(v) else "—"
