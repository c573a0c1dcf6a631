"""Fuzz 30a, cases C1, C2, C3, C6, C9 and D1 (issue 35), by class.

* C1: an integer float64 cannot hold exactly is refused whatever its container: each entry is checked as given, before
  the conversion (``fusion._limits.inexact_integer``): beside a float in a list, a numpy int scalar, an integral
  ``Decimal`` or ``Fraction`` (``PublishedValues``, ``side_by_side``).
* C2: a float64 published value whose spacing exceeds the printed step is refused, the float32/float16 rule
  (``_decimal_fault``'s "cannot hold") applied to float64.
* C3: R2's tie (at zero and at the margin's edge) is ``max(1e-9, 4 eps(dtype))`` of S for runs given as float32 or
  float16, in ``judge_paired``, the ledger's ``Comparison`` and ``ExactComparison``; float64 runs keep 1e-9.
* C6, D1: the precision of weights is their numbers', not their container's (``fusion._validation.given_dtype``): a list
  of ``np.float32``/``np.float16`` scalars or a pandas ``"Float32"`` Series is held to its dtype and renormalised.
* C9: ``grid_log_normaliser`` uses the exponents ``check_simplex`` returns (renormalised float16/float32 rows).
"""

from __future__ import annotations

from decimal import Decimal
from fractions import Fraction

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fusion.book import rulebook as R
from fusion.book.exact import ExactComparison as EC
from fusion.book.ledger import Comparison, PublishedValues as PV
from fusion.book.tables import side_by_side
from fusion.estimates.mixtures import GaussianMixture
from fusion.filtering.particles import effective_sample_size
from fusion.optimise.simplex import check_simplex
from fusion.scenarios.two_mixtures import grid_log_normaliser

HYP = settings(max_examples=20, deadline=None)
B = 2**53


# --- C1: each entry's exactness, before the conversion ----------------------------------------------------------------

@pytest.mark.parametrize("bad,i", [([1.0, B + 1], 1), ((2.0, B + 1), 1), ([np.int64(B + 1), 1.0], 0),
                                   ([Decimal(B + 1)], 0), ([Fraction(B + 1)], 0),
                                   ([np.nan, 1.0, B + 1], 2)])
def test_c1_an_inexact_integer_is_refused_in_any_container(bad, i):
    good = [float(2**52)] * len(bad)
    if not np.isnan(np.asarray(bad, dtype=float)).any():
        with pytest.raises(ValueError, match=rf"published\[{i}\] is an integer that float64 cannot hold"):
            PV(bad, good, 0)
        with pytest.raises(ValueError, match=rf"published\[{i}\] is an integer"):
            side_by_side(bad, good, list(range(len(bad))), decimals=0)
    with pytest.raises(ValueError, match=rf"ours\[{i}\] is an integer that float64 cannot hold"):
        PV(good, bad, 0)


@HYP
@given(st.integers(2**52, 2**60), st.sampled_from([list, tuple]), st.booleans())
def test_c1_property_refused_iff_float64_does_not_hold_it(k, box, numpy_int):
    v = np.int64(k) if numpy_int else k
    held = float(k) == k
    try:
        r = PV(box([1.0, v]), [1.0, float(k)], 0)
    except ValueError as e:
        assert not held and "published[1]" in str(e)
    else:
        assert held and r.status() == "reproduced"


def test_c1_valid_numbers_stay_accepted():
    assert PV([1.0, B, Decimal("0.5"), Fraction(1, 4)], [1.0, float(B), 0.5, 0.25], [0, 0, 1, 2]).status() == "reproduced"
    assert PV([0.5, 2**60], [0.5, 2.0**60], [1, 0]).status() == "reproduced"  # an int given is exact (C2's rule)


# --- C2: float64 spacing beyond the printed step -----------------------------------------------------------------------

@pytest.mark.parametrize("p,d", [(1234567890123456.78, 2), (2.0**53, 1), (1e20, 0), (123456789012.5, 5)])
def test_c2_a_float64_that_cannot_hold_its_decimals_is_refused(p, d):
    """1e20 at 0 decimals was accepted (fuzz 26a D1's test): 1e20 + 1 is the same float; the int 10**20 is exact."""
    with pytest.raises(ValueError, match=r"published\[0\] = .* is a float64 that cannot hold decimals\[0\]"):
        PV([p], [p], d)


@HYP
@given(st.integers(8, 17), st.integers(0, 6))
def test_c2_property_refused_iff_the_spacing_exceeds_the_step(e, d):
    p = 1.5 * 10.0**e
    try:
        PV([p], [p], d)
    except ValueError as exc:
        assert np.spacing(p) > 10.0**-d and "cannot hold" in str(exc)
    else:
        assert np.spacing(p) <= 10.0**-d


def test_c2_exact_integers_and_ordinary_values_stay_accepted():
    assert PV([10**15], [1e15], 2).status() == "reproduced"   # an integer array's value is exact
    assert PV([2.0**52, 123456.78], [2.0**52, 123456.78], [0, 2]).status() == "reproduced"


# --- C3: float32/float16 runs are decided by their own round-off --------------------------------------------------------

@pytest.mark.parametrize("dt", [np.float32, np.float16])
def test_c3_short_float_runs_at_the_margin_get_one_status(dt):
    runs = lambda v: np.full(100, v, dt)  # noqa: E731
    got = {(a, b): (R.judge_paired(runs(a), runs(b), "equal", 0.1).status,
                    Comparison(runs(a), runs(b), "A", "B", "equal", "m", margin=0.1).status(),
                    EC(dt(a), dt(b), "A", "B", "equal", "m", margin=0.1).status())
           for a, b in ((0.3, 0.2), (1.3, 1.2))}
    assert set(got.values()) == {("reproduced",) * 3}


@HYP
@given(st.floats(0.01, 1e6), st.integers(1, 3), st.sampled_from(["array", "list"]))
def test_c3_property_a_few_float32_ulps_are_a_tie(x, k, box):
    b = np.float32(x)
    a = b
    for _ in range(k):
        a = np.nextafter(a, np.float32(np.inf))
    av, bv = np.full(20, a), np.full(20, b)
    if box == "list":
        av, bv = list(av), list(bv)
    assert R.judge_paired(av, bv, "less", 0.0).status == "not distinguishable"
    c = Comparison(av, bv, "A", "B", "less", "m", reason="a test", margin=0.0)
    assert c.status() == c.with_margin(0.0).status() == "not distinguishable"
    e = EC(a, b, "A", "B", "less", "m", margin=0.0)
    assert e.status() == e.with_margin(0.0).status() == "not distinguishable" and "round-off" in e.summary()


def test_c3_float64_runs_keep_the_1e9_tie():
    b = np.full(20, 1.0)
    a = b * (1 + 1e-8)
    assert R.judge_paired(a, b, "greater", 0.0).status == "reproduced"
    assert R.judge_paired(a.astype(np.float32), b.astype(np.float32), "greater", 0.0).status == "not distinguishable"
    assert EC(1.0 + 1e-8, 1.0, "A", "B", "greater", "m", margin=0.0).status() == "reproduced"


# --- C6, D1: the numbers' precision decides, not their container ---------------------------------------------------------

@pytest.mark.parametrize("dt", [np.float32, np.float16])
def test_c6_a_list_of_short_float_scalars_is_its_array(dt):
    w = np.full(10, 0.1, dt)
    assert np.array_equal(check_simplex(list(w)), check_simplex(w))
    assert effective_sample_size(list(np.full(3, 1 / 3, dt))) == effective_sample_size(np.full(3, 1 / 3, dt)) == 3.0
    g = GaussianMixture(list(w), np.zeros((10, 1)), np.ones((10, 1, 1)))
    assert np.array_equal(g.weights, GaussianMixture(w, np.zeros((10, 1)), np.ones((10, 1, 1))).weights)


def test_c6_a_list_with_a_python_float_has_its_float32_entries_precision():
    # fuzz 31a C1 revised this case: a list's precision is its least precise numpy float entry's (given_dtype), so
    # [np.float32(0.1)] * 9 + [0.1000001] (1.1e-7 off one) is accepted at float32's tolerance (2 n eps = 2.4e-6)
    assert check_simplex([np.float32(0.1)] * 9 + [0.1000001]).sum() == pytest.approx(1.0, abs=1e-15)
    with pytest.raises(ValueError, match="eps must lie on the simplex"):
        check_simplex([np.float32(0.1)] * 9 + [0.1001])  # 1e-4 off: beyond float32's tolerance
    with pytest.raises(ValueError, match="eps must lie on the simplex"):
        check_simplex([0.1] * 9 + [0.1000001])  # Python floats only: float64's tolerance


def test_d1_pandas_float32_weights_are_float32():
    s = pd.Series(np.full(3, 1 / 3, np.float32), dtype="Float32")
    assert effective_sample_size(s) == 3.0
    assert np.array_equal(check_simplex(s), check_simplex(np.full(3, 1 / 3, np.float32)))


# --- C9: the checked exponents are the ones used -------------------------------------------------------------------------

def test_c9_grid_log_normaliser_uses_the_renormalised_exponents():
    gA = GaussianMixture(np.array([0.4, 0.6]), np.array([[0.0, 0.0], [1.0, 1.0]]), np.stack([np.eye(2), 2 * np.eye(2)]))
    gB = GaussianMixture(np.array([1.0]), np.array([[0.5, 0.0]]), np.eye(2)[None] * 1.5)
    v16 = (np.array([0.4, 0.6]).astype(np.float16) * np.float16(0.997)).astype(np.float16)
    v = v16.astype(float)
    got = grid_log_normaliser([gA, gB], v16, n=21).log_z
    assert np.allclose(got, grid_log_normaliser([gA, gB], v / v.sum(), n=21).log_z, rtol=1e-12, atol=0)
    both = grid_log_normaliser([gA, gB], np.stack([v16, v16[::-1]]), n=21).log_z
    assert both[0] == got[0]
