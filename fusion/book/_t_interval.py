"""Student's t interval and one-sample t test of a mean, without scipy's "precision loss" warning (fuzz 37b C3).

``scipy.stats.ttest_1samp`` warns (``RuntimeWarning``: "Precision loss occurred in moment calculation due to
catastrophic cancellation") when its data equal their mean to within ``10 eps`` of it: a constant paired difference
(``a`` and ``a + 0.5``) or runs equal up to round-off, legitimate inputs of the chapters' readings, which a caller's
``warnings.simplefilter("error")`` turned into an exception. Such data are treated here as the constant they are to
round-off, scipy's own answer for exactly constant data: the zero-width interval at their mean, and a test decided by
the side of the tested value the mean lies on. Every other input gets scipy's numbers bit for bit.
"""

from __future__ import annotations

import math

import numpy as np

__all__: list[str] = []


def constant_to_round_off(x: np.ndarray) -> bool:
    """Whether the entries of ``x`` equal their mean exactly or to within ``10 eps`` of it: scipy's precision-loss
    criterion (``scipy.stats._stats_py._demean``), under which its variance is round-off."""
    x = np.asarray(x, dtype=float)
    mean = x.mean()
    dev = float(np.max(np.abs(x - mean)))
    return dev == 0.0 or dev < 10 * np.finfo(float).eps * abs(float(mean))


def mean_interval(x: np.ndarray, level: float = 0.95) -> tuple[float, float]:
    """``(low, high)``: Student's t interval of the mean of ``x`` at ``level`` (``scipy.stats.ttest_1samp``), the
    zero-width interval at the mean for data constant to round-off (:func:`constant_to_round_off`)."""
    x = np.asarray(x, dtype=float)
    if constant_to_round_off(x):
        m = float(x.mean())
        return m, m
    from scipy import stats

    ci = stats.ttest_1samp(x, 0.0).confidence_interval(level)
    return float(ci.low), float(ci.high)


def t_pvalue(x: np.ndarray, popmean: float, alternative: str) -> float:
    """The p-value of the one-sample t test of ``x``'s mean against ``popmean`` (``alternative`` ``"less"`` or
    ``"greater"``, ``scipy.stats.ttest_1samp``); for data constant to round-off, as scipy gives for exactly constant
    data (an infinite t): 0 when the mean lies strictly on the alternative's side, 1 on the other, NaN at ``popmean``."""
    x = np.asarray(x, dtype=float)
    if constant_to_round_off(x):
        diff = float(x.mean()) - float(popmean)
        if diff == 0.0:
            return math.nan
        return 0.0 if (diff < 0) == (alternative == "less") else 1.0
    from scipy import stats

    return float(stats.ttest_1samp(x, popmean, alternative=alternative).pvalue)
