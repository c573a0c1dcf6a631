"""Fuzz 33a, cases C1, C2, C3, C7, D3 and D4 (issue 35), by class.

* C1: the input budget counts the entries of any sequence before it is built (``fusion._entries.sequence_entries``,
  from ``fusion._validation.input_size`` and ``fusion._guards.read_once``): a lazy ``range``, a list or deque holding
  ranges, a user's Sequence class are refused by name beyond ``MAX_INPUT_ELEMENTS``, never a MemoryError.
* C2, C3, D4: an entry of a list (or object array) that numpy would read as a number it is not, a date or duration
  (its count in its unit) or ``None`` (NaN), is refused by the shared conversion naming the argument (an array
  argument's name, or the objective's), ``fusion._entries.non_number_entry``; NaN itself stays valid where documented.
* C7: ``given_dtype`` reads the dtype of what the caller gave in every form the conversion accepts: 0-d arrays in a
  list, a ``memoryview``, an ``array.array``, an ``__array__`` object (read once by its function).
* D3: ``check_simplex`` of a 2-D array says "of length at least one", not "None".
"""

from __future__ import annotations

import array
from collections import deque
from collections.abc import Sequence

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import fusion._guards
import fusion._limits
import fusion._validation
from fusion._validation import as_array, given_dtype

HYP = settings(max_examples=25, deadline=None)
LIMIT = 1000  # the input budget, lowered for the tests: the rule is the same at every limit


class Seq(Sequence):
    """A user's Sequence class (no numpy protocol), counting its full reads."""

    def __init__(self, items):
        self.items, self.reads = list(items), 0

    def __len__(self):
        return len(self.items)

    def __getitem__(self, i):
        if isinstance(i, slice):
            return self.items[i]
        if i == 0:
            self.reads += 1
        return self.items[i]


class ArrayObj:
    """An object with ``__array__`` only, counting its conversions."""

    def __init__(self, a):
        self.a, self.calls = a, 0

    def __array__(self, dtype=None, copy=None):
        self.calls += 1
        return self.a


@pytest.fixture
def small_budget(monkeypatch):
    for mod in (fusion._limits, fusion._validation):
        monkeypatch.setattr(mod, "MAX_INPUT_ELEMENTS", LIMIT)


# --- C1: sequences measured before they are built ---------------------------------------------------------------

def _wrap(kind: str, rows: list):
    return {"list": list, "tuple": tuple, "deque": deque, "seq": Seq}[kind](rows)


@given(kind=st.sampled_from(["list", "tuple", "deque", "seq"]), n=st.integers(1, 40), m=st.integers(1, 60))
@HYP
def test_c1_nested_ranges_counted_against_the_budget(kind, n, m):
    """Rows of lazy ranges, in every container kind: refused by name iff n x m passes the budget, else the array."""
    import unittest.mock as um
    with um.patch.object(fusion._limits, "MAX_INPUT_ELEMENTS", LIMIT), \
            um.patch.object(fusion._validation, "MAX_INPUT_ELEMENTS", LIMIT):
        x = _wrap(kind, [range(m)] * n)
        if n * m > LIMIT:
            with pytest.raises(ValueError, match=r"^x has .*entries, beyond the input budget"):
                as_array(x, "x")
        else:
            np.testing.assert_array_equal(as_array(x, "x"), np.tile(np.arange(m, dtype=float), (n, 1)))


def test_c1_huge_lazy_ranges_refused_by_name_at_once():
    from fusion.readings.fusion_set import arithmetic_mean
    from fusion.scenarios import time_registration as tr
    with pytest.raises(ValueError, match=r"^x has 1e\+12 entries, beyond the input budget"):
        arithmetic_mean(range(10**12))
    for t in ([range(10**12)], (range(10**12),), deque([range(10**12)]), Seq([range(10**12)])):
        with pytest.raises(ValueError, match=r"^t has .*entries, beyond the input budget"):
            tr.truth(t)
    with pytest.raises(ValueError, match=r"^x has more than .* entries, beyond the input budget"):
        as_array(range(10**20), "x")  # its len overflows: not "ragged"


def test_c1_read_once_counts_what_it_reads(small_budget):
    """A deque of rows each within the budget, together beyond it: refused before its rows are built; a user's
    Sequence is read once."""
    with pytest.raises(ValueError, match=r"^x has .*entries, beyond the input budget"):
        fusion._guards.read_once(deque([range(600)] * 2), "x")
    with pytest.raises(ValueError, match=r"^x has .*entries, beyond the input budget"):
        fusion._guards.read_once(Seq([Seq([0.0] * 600), Seq([0.0] * 600)]), "x")
    s = Seq([1.0, 2.0])
    assert fusion._guards.read_once(s, "x") == [1.0, 2.0] and s.reads == 1
    s = Seq([1.0, 2.0])
    np.testing.assert_array_equal(as_array(s, "x"), [1.0, 2.0])
    assert s.reads == 1


# --- C2, C3, D4: dates, durations and None are not numbers ------------------------------------------------------

ODD = [np.datetime64("2026-01-01"), np.timedelta64(2, "D"), np.timedelta64(0, "s"), np.array(np.timedelta64(3, "D")),
       None]  # (datetime.timedelta and datetime.datetime entries were refused already: float() fails on them)


@pytest.mark.parametrize("odd", ODD, ids=range(len(ODD)))
def test_c3_date_duration_or_none_entry_refused_naming_the_argument(odd):
    from fusion.readings.fusion_set import arithmetic_mean
    with pytest.raises(TypeError, match=r"^x must be numeric"):
        arithmetic_mean([odd, 4.0])
    with pytest.raises(TypeError, match=r"^x must be numeric"):
        arithmetic_mean(np.array([4.0, odd], dtype=object))
    with pytest.raises(TypeError, match=r"^x must be numeric"):
        as_array([[1.0, 2.0], [odd, 4.0]], "x")


def test_c3_published_values_name_their_argument():
    from fusion.book.ledger import PublishedValues
    with pytest.raises(TypeError, match=r"^published must be numeric"):
        PublishedValues([np.timedelta64(2, "D"), 1.5], [2.0, 1.5], 1)
    with pytest.raises(TypeError, match=r"^ours must be numeric"):
        PublishedValues([1.5, 2.5], [1.5, np.datetime64("2026-01-01")], 1)


def test_d4_none_in_ours_refused_nan_kept():
    from fusion.book.ledger import PublishedValues
    with pytest.raises(TypeError, match=r"^ours must be numeric .*None"):
        PublishedValues([1.5, 2.5], [None, 2.5], 1)
    p = PublishedValues([1.5, 2.5], [float("nan"), 2.5], 1)  # documented: NaN marks a value not computed
    assert np.isnan(p.ours[0]) and p.ours[1] == 2.5


@pytest.mark.parametrize("odd", [np.timedelta64(0, "s"), np.timedelta64(3, "D"), np.datetime64(0, "s"), None])
def test_c2_objective_values_mixing_durations_refused_naming_the_objective(odd):
    from fusion.optimise.scalar import grid_search
    with pytest.raises(TypeError, match=r"^the values returned by f must be numeric"):
        grid_search(lambda x: 0.5 if x < 0.15 else odd, 11)
    assert grid_search(lambda x: (x - 0.3) ** 2, 11).x == pytest.approx(0.3)  # numbers: unchanged


# --- C7: the dtype of what the caller gave, in every form -------------------------------------------------------

def _forms(values: np.ndarray) -> list:
    """The same float32 (or float16) numbers in every form the shared conversion accepts."""
    out = [values, list(values), [np.array(v) for v in values], memoryview(values), ArrayObj(values)]
    if values.dtype == np.float32:
        out.append(array.array("f", values.tolist()))
    return out


@given(dtype=st.sampled_from([np.float32, np.float16]), n=st.integers(1, 6))
@HYP
def test_c7_given_dtype_reads_every_form(dtype, n):
    v = np.full(n, 0.1, dtype)
    for form in _forms(v):
        assert given_dtype(form) == dtype, type(form).__name__
    assert given_dtype([np.array(0.1, np.float32), np.array(0.1, np.float16), 1.0]) == np.float16
    assert given_dtype([np.array(0.1), 1.0]) == np.float64
    assert given_dtype(memoryview(np.ones(3))) == np.float64


def test_c7_statuses_and_simplex_do_not_depend_on_the_form():
    from fusion.book.rulebook import judge_paired
    from fusion.filtering.particles import effective_sample_size
    from fusion.optimise.simplex import check_simplex
    a, b = np.full(100, 0.3, np.float32), np.full(100, 0.2, np.float32)
    statuses = {judge_paired(fa, fb, "equal", 0.1).status for fa, fb in zip(_forms(a), _forms(b))}
    assert statuses == {judge_paired(a, b, "equal", 0.1).status}
    w = np.full(10, 0.1, np.float32)
    for form in _forms(w):
        np.testing.assert_allclose(check_simplex(form), np.full(10, 0.1), rtol=0, atol=1e-15)
    for form in _forms(np.full(3, 1 / 3, np.float16)):
        assert effective_sample_size(form) == pytest.approx(3.0)
    obj = ArrayObj(a)
    judge_paired(obj, b, "equal", 0.1)
    assert obj.calls == 1  # read once: checked, and its dtype read from that one array
    with pytest.raises(ValueError, match="eps must lie on the simplex"):
        check_simplex(array.array("d", [0.1 + 1e-7] * 10))  # float64's tolerance: 1e-6 off one is refused


# --- D3 -----------------------------------------------------------------------------------------------------------

def test_d3_check_simplex_length_message():
    from fusion.optimise.simplex import check_simplex
    with pytest.raises(ValueError, match=r"^eps must be a 1-D vector of length at least one, got shape \(2, 3\)$"):
        check_simplex(np.ones((2, 3)) / 3)
    with pytest.raises(ValueError, match=r"^eps must be a 1-D vector of length 4, got shape \(3,\)$"):
        check_simplex(np.ones(3) / 3, 4)
