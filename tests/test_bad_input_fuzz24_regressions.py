"""Fuzz 24e (issue 35): regressions of this session's bad-input fixes, valid input refused or valid results changed.

F4-F5: the shift-invariant centred and sample variance estimates took their moments relative to each sensor's first
reading, so a spike there (rejected by the consistency check, or out of a sliding window) became the offset of every
later reading and brought the cancellation back. The reference is now each sensor's median (kept) reading; the
estimates are checked against an exact reference in fractions on readings of a 1/64 grid with a spike at the first
reading (the spiked readings are exact in float64).

F1: ``PublishedValues`` refuses a published value with more decimals than printed, judged up to float32 round-off:
a float32, ``0.1 * 3`` or ``12.3 / 100`` is the decimal it prints to; 1.25 at 1 decimal is still refused.

F2-F3: an argument documented as a tuple (``fig5_hypotheses(flat_pair=(P, P))``, ``fig5(aniso=(P1, P2, res,
seeds))``) takes a list too, by the package's sequence rule (``fusion._counts.sequence``: only a frozen record's
tuple fields are tuple-only). Every chapter registry's valid call is swept with each tuple argument as a list.
"""

from __future__ import annotations

import importlib
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fusion.readings import consistency as cs
from fusion.readings import weighting as wt

_X0 = np.round(np.random.default_rng(0).normal(0, 1, (60, 3)) * np.array([1.0, 2.0, 3.0]) * 64) / 64
_OFFSETS = st.builds(lambda m, e: m * 10.0**e, st.sampled_from([0.0, 1.0, -1.0, 3.0, -7.0]), st.integers(0, 8))


def _exact_masked(X: np.ndarray, kept: np.ndarray, estimator: str) -> np.ndarray:
    """The estimate from the kept readings, in fractions: each pair's covariance over the instants where both are
    kept (with the means over those instants); centred (Grubbs-type, averaged over the partners) or sample."""
    rows = [[Fraction(float(v)) for v in row] for row in X]
    n = X.shape[1]

    def cov(p: int, q: int) -> Fraction:
        idx = [i for i in range(len(rows)) if kept[i, p] and kept[i, q]]
        mp = sum(rows[i][p] for i in idx) / len(idx)
        mq = sum(rows[i][q] for i in idx) / len(idx)
        return sum((rows[i][p] - mp) * (rows[i][q] - mq) for i in idx) / len(idx)

    if estimator == "sample":
        return np.array([float(cov(p, p)) for p in range(n)])
    return np.array([float(cov(p, p) - sum(cov(p, q) for q in range(n) if q != p) / (n - 1)) for p in range(n)])


def _close(got: np.ndarray, exact: np.ndarray) -> None:
    """Within 1e-9 of the largest exact variance (the round-off of the spread's scale)."""
    np.testing.assert_allclose(got, exact, rtol=0, atol=1e-9 * float(np.abs(exact).max()))


@settings(max_examples=25, deadline=None)
@given(c=_OFFSETS, e=st.integers(3, 8), sign=st.sampled_from([1.0, -1.0]), sensor=st.integers(0, 2))
def test_f4_consistency_awf_ignores_a_rejected_spike_at_the_first_reading(c: float, e: int, sign: float,
                                                                         sensor: int) -> None:
    X = _X0 + c
    X[0, sensor] += sign * 10.0**e
    r = cs.consistency_awf(X, 20.0, "centred")
    kept = np.ones(X.shape, dtype=bool)
    kept[0, sensor] = False
    np.testing.assert_array_equal(r.mask, kept)  # only the spike is rejected
    _close(r.awf.variances[-1], _exact_masked(_X0, kept, "centred"))


@settings(max_examples=25, deadline=None)
@given(c=_OFFSETS, e=st.integers(3, 5), estimator=st.sampled_from(["centred", "sample"]), window=st.integers(2, 40))
def test_f5_window_estimates_forget_a_spike_at_the_first_reading(c: float, e: int, estimator: str,
                                                                 window: int) -> None:
    X = _X0 + c
    X[0] += 10.0**e * np.array([1.0, -3.0, 7.0])  # squares exact in float64 up to e = 5 (a larger spike leaves the
    # round-off of its square in the window's cumulative sums, documented in tracking_variances)
    got = wt.tracking_variances(X, estimator=estimator, memory="window", window=window)[-1]
    last = _X0[-window:]
    _close(got, _exact_masked(last, np.ones(last.shape, dtype=bool), estimator))


def test_f5_the_reference_is_a_median_kept_reading() -> None:
    A = np.array([[1e8, 5.0], [1.0, 6.0], [2.0, 7.0], [3.0, 8.0]])
    np.testing.assert_array_equal(wt._moment_stack(A, "sample")[..., 4:], A - np.array([2.0, 6.0]))
    kept = np.array([[False, True], [True, True], [True, False], [True, False]])
    from fusion.readings._moments import _reference
    np.testing.assert_array_equal(_reference(A, kept), [[2.0, 5.0]])
    np.testing.assert_array_equal(_reference(A, np.zeros(A.shape, dtype=bool)), [[0.0, 0.0]])


# ---------------------------------------------------------------------------------------------- F1
@settings(max_examples=60, deadline=None)
@given(m=st.integers(-10**6, 10**6), d=st.integers(0, 6), how=st.sampled_from(["float32", "sum", "percent"]))
def test_f1_a_printed_decimal_in_binary_is_accepted(m: int, d: int, how: str) -> None:
    from fusion.book.ledger.evidence import PublishedValues

    exact = m / 10**d
    if how == "float32":
        if abs(m) > 2**24:  # float32's integer precision: the value would lose printed digits
            return
        p = np.float32([exact])
    elif how == "sum":
        p = [exact / 3 + exact / 3 + exact / 3]
    else:
        p = [(m / 10**d * 100) / 100]
    r = PublishedValues(p, [exact], d, "m")
    assert r.matches == (True,)


@pytest.mark.parametrize(("p", "d"), [(1.25, 1), (0.1000001, 1), (2.5, 0), (0.125, 2), (123.45, 1)])
def test_f1_a_real_extra_decimal_is_still_refused(p: float, d: int) -> None:
    from fusion.book.ledger.evidence import PublishedValues

    with pytest.raises(ValueError, match=r"published\[0\].*decimals"):
        PublishedValues([p], [p], d, "m")


# ---------------------------------------------------------------------------------------------- F2-F3
_CHAPTER_REGISTRIES = ("test_bad_input_calls_ch010307", "test_bad_input_calls_ch0204", "test_bad_input_calls_ch05",
                       "test_bad_input_calls_ch06")


@pytest.mark.parametrize("module", _CHAPTER_REGISTRIES)
def test_f2_f3_a_tuple_argument_is_accepted_as_a_list(module: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    m = importlib.import_module(module)
    reg, calls = m.registry(), m.CALLABLES
    refused, swept = [], 0
    for name, spec in reg.items():
        for arg, a in spec.items():
            if not isinstance(a.value, tuple) or hasattr(a.value, "_fields"):
                continue
            kwargs = {k: v.value for k, v in spec.items()}
            kwargs[arg] = list(a.value)
            swept += 1
            try:
                calls[name](**kwargs)
            except (ValueError, TypeError) as exc:
                refused.append(f"{name}({arg}=list): {type(exc).__name__}: {str(exc)[:120]}")
            finally:
                plt.close("all")
    assert swept > 0
    assert not refused, "\n".join(refused)


def test_f3_fig5_aniso_and_flat_pair_lists_give_the_tuples_results() -> None:
    m = importlib.import_module("test_bad_input_calls_ch05")
    spec = m.registry()["fusion.book.chapters.ci.fig5_hypotheses"]
    kwargs = {k: v.value for k, v in spec.items()}
    as_tuple = m.CALLABLES["fusion.book.chapters.ci.fig5_hypotheses"](**kwargs)
    kwargs["flat_pair"] = list(kwargs["flat_pair"])
    as_list = m.CALLABLES["fusion.book.chapters.ci.fig5_hypotheses"](**kwargs)
    assert as_tuple.equals(as_list)


# ---------------------------------------------------------------------------------------------- minor decisions
@pytest.mark.parametrize("tol", [1e-300, 1e-200, 2.3e-308])
def test_a_tiny_stopping_tolerance_is_valid(tol: float) -> None:
    """A tolerance is only compared (fusion._validation.tolerance): a tiny one runs to the iteration limit."""
    from fusion.optimise.scalar import bounded_minimum
    from fusion.optimise.simplex import minimise_on_simplex
    from fusion.optimise.swarm import SwarmOptions

    r = minimise_on_simplex(lambda x: float((x[0] - 0.3) ** 2), 2, ftol=tol)
    np.testing.assert_allclose(r.x, [0.3, 0.7], atol=1e-6)
    assert abs(bounded_minimum(lambda x: (x - 0.25) ** 2, xatol=tol).x - 0.25) < 1e-6
    assert SwarmOptions(xtol=tol).xtol == tol


@pytest.mark.parametrize("tol", [0.0, -1e-3, float("nan"), float("inf"), 1e-320])
def test_a_stopping_tolerance_is_still_positive_finite_and_normal(tol: float) -> None:
    from fusion.optimise.simplex import minimise_on_simplex

    with pytest.raises(ValueError, match="ftol"):
        minimise_on_simplex(lambda x: float(x[0]), 2, ftol=tol)


def test_a_decimal_or_fraction_table_cell_is_a_number() -> None:
    import decimal

    import pandas as pd

    from fusion.book.tables import _frame

    tab = pd.DataFrame({"v": [decimal.Decimal("1.5"), Fraction(1, 3), 2, np.float32(0.5)]}, dtype=object)
    assert _frame(tab, "tab", ["v"], finite=["v"]) is tab
    for bad in (True, "1.5", 1 + 2j):
        with pytest.raises(TypeError, match=r"tab\['v'\] must hold numbers"):
            _frame(pd.DataFrame({"v": [1.0, bad]}, dtype=object), "tab", ["v"], finite=["v"])


def test_judge_paireds_constant_differences_test_is_on_the_values_scale() -> None:
    """Documented: the round-off scale S is the values' magnitude, so an offset of a and b common to both (the
    differences unchanged) turns differences spread by less than 1e-9 S into constant ones (zero-width interval)."""
    from fusion.book import rulebook as R

    assert "common offset" in " ".join(R.judge_paired.__doc__.split())
    x = np.linspace(0.0, 1.0, 20)
    d = 0.5 + 1e-7 * np.sin(np.arange(20))  # spread 2e-7: above 1e-9 S at S ~ 1, below it at S ~ 1e4
    for c, zero_width in ((0.0, False), (1e4, True)):
        j = R.judge_paired(c + x + d, c + x, "greater", 0.1)
        assert (j.high - j.low == 0.0) is zero_width
