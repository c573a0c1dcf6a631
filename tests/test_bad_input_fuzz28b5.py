"""Fuzz 28b's bad input of chapter 05, cases C1, C2, C3 and the debatable D1 (issue 35); D2 of chapter 06.

* C1: ``_period_key`` (the chapter's float32 period rule) rebuilt a masked float32 array or scalar, dropping its
  mask (or failing on ``'--'`` with a message naming nothing): a masked value now reaches its reader unchanged,
  which refuses it by the masked-array rule (``fusion._counts.not_masked``), naming ``periods`` or ``T``;
* C2: it recursed into nested lists (a RecursionError); it now reads one level only (a flat list's entries), and
  a nested list reaches the reader, which refuses it by name;
* C3, D1: ``ledger(r, values)`` requires each value of ``values`` to be of the type class of ``ledger_values(r)``'s
  (a text, an integer, a real float): a 1-element array, a complex, a Decimal, a bool or 2.0 for the count 2
  compare equal but the texts would quote them otherwise; a TypeError naming ``values[key]``;
* D2: ``snis_bias_study``'s docstring states the code's rule for the unresolved far exponents, not a typed edge.
"""

from __future__ import annotations

import decimal
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from fusion.book.chapters import ci
from fusion.book.chapters.ci.checks import _period_key, _periods
from fusion.book.chapters.ci.claim_evidence import _values_of


def refused(fn: Any, arg: str, kind: Any = ValueError) -> str:
    """The refusal's message: ``fn()`` raises ``kind`` (a TypeError or ValueError) naming ``arg``."""
    try:
        fn()
    except (TypeError, ValueError) as e:
        assert isinstance(e, kind) and arg in str(e), f"{type(e).__name__}: {e}"
        return str(e)
    raise AssertionError(f"accepted: expected a refusal naming {arg}")


# ------------------------------------------------------------------------------------------------ C1: masked periods

@settings(max_examples=25, deadline=None)
@given(dtype=st.sampled_from([np.float16, np.float32, np.float64]),
       mask=st.lists(st.booleans(), min_size=1, max_size=4))
def test_c1_a_masked_periods_array_is_refused_by_name_whatever_its_dtype_and_mask(dtype: Any, mask: list) -> None:
    """Masked (or all-unmasked) float16/32/64 periods: the masked-array rule's TypeError, never the mask dropped."""
    periods = np.ma.masked_array((np.arange(len(mask)) + 1.0).astype(dtype) / 4, mask=mask)
    msg = refused(lambda: _periods(periods), "periods", TypeError)
    assert "masked" in msg


def test_c1_the_chapter_tables_refuse_a_masked_float32_periods_array() -> None:
    m32 = np.ma.masked_array(np.array([1.0, 0.02, 0.001], dtype=np.float32), mask=[0, 1, 0])
    refused(lambda: ci.pcrb_table(m32, 150.0, 10.0), "periods", TypeError)
    refused(lambda: ci.pcrb_table(np.ma.masked_array(m32.data), 150.0, 10.0), "periods", TypeError)
    s32 = np.ma.masked_array(np.array([0.1, 0.5], dtype=np.float32), mask=[0, 1])
    refused(lambda: ci.sensitivity_table(s32, 1, 2, duration=3.0, t_min=1.0), "periods", TypeError)


@pytest.mark.parametrize("masked", [True, False])
def test_c1_a_masked_float32_value_is_passed_on_unchanged(masked: bool) -> None:
    """A masked float32 scalar (T of weight_pair) reaches its reader as given: its rule refuses it by name."""
    T = np.ma.masked_array(np.float32(8.0), mask=masked)
    assert _period_key(T) is T
    entry = [1.0, T]
    assert _period_key(entry) is entry   # a list holding no plain narrow float is the caller's own
    refused(lambda: ci.weight_pair(np.eye(2), np.eye(2) / 9, np.eye(4) * 0.01, 2, seed=1, search_seed=2,
                                   fruit_fly_seeds=[3], runs=2, T=T), "T", TypeError)


def test_c1_float32_periods_are_still_read_as_they_print() -> None:
    """The rule of fuzz 26c q2 / 27b B2 stays: float32 periods alone, in an array, a list or a tuple."""
    assert _period_key(np.float32(0.02)) == 0.02
    assert _periods(np.array([1.0, 0.02], dtype=np.float32)).tolist() == [1.0, 0.02]
    assert _periods([np.float32(1.0), np.float32(0.02), 0.5]).tolist() == [1.0, 0.02, 0.5]
    assert _periods((np.float16(0.5), np.float32(0.02))).tolist() == [0.5, 0.02]
    assert list(ci.pcrb_table([np.float32(1.0), np.float32(0.02)], 150.0, 10.0).index[:2]) == [1.0, 0.02]


# ------------------------------------------------------------------------------------------------ C2: nested lists

@settings(max_examples=12, deadline=None)
@given(depth=st.sampled_from([2, 3, 64, 500, 1200]), narrow=st.booleans())
def test_c2_a_nested_periods_list_is_refused_by_name_without_recursion(depth: int, narrow: bool) -> None:
    x: Any = np.float32(0.5) if narrow else 0.5
    for _ in range(depth):
        x = [x]
    refused(lambda: _periods(x), "periods", (TypeError, ValueError))


def test_c2_the_chapter_tables_refuse_a_deeply_nested_list() -> None:
    x: Any = [0.5]
    for _ in range(500):
        x = [x]
    refused(lambda: ci.pcrb_table(x, 150.0, 10.0), "periods", TypeError)
    refused(lambda: ci.sensitivity_table(x, 1, 2, duration=3.0, t_min=1.0), "periods", TypeError)


# ------------------------------------------------------------------------------------------------ C3, D1: values

EXPECTED = {"ci_lg_runs": 2, "ci_lg_fig6_lo": 0.11, "ci_lg_nan": float("nan"), "ci_lg_text": "1.07 × 10⁶"}


def _edited(key: str, value: Any) -> dict:
    return {**EXPECTED, key: value}


def test_c3_ledger_values_of_their_own_type_class_are_accepted() -> None:
    _values_of(dict(EXPECTED), EXPECTED)
    _values_of(_edited("ci_lg_runs", np.int64(2)), EXPECTED)          # a NumPy integer is an integer
    _values_of(_edited("ci_lg_fig6_lo", np.float64(0.11)), EXPECTED)  # a NumPy float is a real float
    _values_of(_edited("ci_lg_nan", np.float64("nan")), EXPECTED)     # NaN equal to NaN


@pytest.mark.parametrize("key, value", [
    ("ci_lg_runs", np.array([2])), ("ci_lg_runs", np.array(2)), ("ci_lg_runs", 2.0), ("ci_lg_runs", True),
    ("ci_lg_runs", decimal.Decimal(2)), ("ci_lg_runs", complex(2, 0)), ("ci_lg_runs", np.float64(2.0)),
    ("ci_lg_fig6_lo", complex(0.11, 0)), ("ci_lg_fig6_lo", np.array([0.11])), ("ci_lg_fig6_lo", np.array([[0.11]])),
    ("ci_lg_fig6_lo", decimal.Decimal("0.11")), ("ci_lg_fig6_lo", np.complex128(0.11)),
    ("ci_lg_nan", np.array([np.nan])), ("ci_lg_nan", complex("nan")), ("ci_lg_text", 1.07e6)])
def test_c3_d1_a_value_of_another_type_class_is_refused_by_its_key(key: str, value: Any) -> None:
    """Values equal to ledger_values(r)'s but of another type class (the texts would quote ``[2]``, ``2.0``,
    ``(0.11+0j)``): a TypeError naming values[key]."""
    refused(lambda: _values_of(_edited(key, value), EXPECTED), f"values['{key}']", TypeError)


@settings(max_examples=20, deadline=None)
@given(value=st.one_of(st.integers(-5, 5), st.floats(allow_nan=False, width=64), st.text(max_size=3)))
def test_c3_a_value_of_its_class_but_another_number_is_a_value_error(value: Any) -> None:
    key = {int: "ci_lg_runs", float: "ci_lg_fig6_lo", str: "ci_lg_text"}[type(value)]
    if value == EXPECTED[key]:
        _values_of(_edited(key, value), EXPECTED)
    else:
        refused(lambda: _values_of(_edited(key, value), EXPECTED), f"values['{key}']")


# ------------------------------------------------------------------------------------------------ D2: the far exponent

def test_d2_the_finite_edge_is_the_tails_rule_of_the_docstring() -> None:
    """∫p²/g infinite below ω ≈ 0.1034, finite above (the Gaussian tails' margin changes sign there)."""
    from fusion.book.chapters.chernoff_snis import _tail_margin
    from fusion.book.chapters.chernoff_steps import toy_reference

    ref = toy_reference()
    assert _tail_margin(ref.gms, np.array([0.1033, 0.8967]), ref.proposal)[0] < 0
    assert _tail_margin(ref.gms, np.array([0.1035, 0.8965]), ref.proposal)[0] > 0


def test_d2_the_docstring_states_the_code_s_rule_for_a_resolved_exponent() -> None:
    """The resolved rule's grids and tolerance as the docstring states them are the code's (computed from its
    constants: a widening or tolerance changed in the code fails here), and no edge typed by hand beside them.
    (The edge it gives, ω ≈ 0.1381, costs 3 CPU-s to bracket: measured in fuzz 28b D2, not here.)"""
    from fusion.book.chapters import chernoff_snis as cs
    from fusion.book.chapters.chernoff_steps import toy_reference

    doc = " ".join((cs.snis_bias_study.__doc__ or "").split())
    half = float(np.unique(toy_reference().points[:, 0])[-1])
    times = [f"{2 ** k}" for k in range(1, cs._DELTA_WIDENINGS + 1)]
    assert f"the reference grid (half-width {half:g}) and on grids of {', '.join(times[:-1])} and {times[-1]} " \
           "times its half-width" in doc
    assert f"confirms to {cs._DELTA_RTOL:g}, relative".replace("e-0", "e-") + " (``_DELTA_RTOL``)" in doc
    assert f"half-widths {2 * half:g} and {4 * half:g} first agree" in doc
    assert "0.1385" not in doc and "0.138 " not in doc
