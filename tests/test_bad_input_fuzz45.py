"""Fuzz 45: Gaussian problems counted by the memory they hold at once (C1), a cost table's float range decided by
its largest cell before the table is built (C2), sampling instants that would repeat refused by name (C4) and
``rounded`` of a finite number below the normal floats rounded to zero (D1)."""

from __future__ import annotations

import time

import numpy as np
import pytest


def _refused_fast(f, *args, match: str, **kw) -> None:
    t = time.process_time()
    with pytest.raises(ValueError, match=match):
        f(*args, **kw)
    assert time.process_time() - t < 1.0


@pytest.mark.parametrize("runs, n, d", [(2**22, 1, 8), (10**7, 26, 1)])
def test_c1_gaussian_problems_memory_counts_the_arrays_held_at_once(runs, n, d):
    from fusion.book.chapters import chernoff_scaling as cs
    _refused_fast(cs.gaussian_problems, np.random.default_rng(0), runs, n, d,
                  match=r"runs, n and d ask for .* arrays of .* held at once")


def test_c1_gaussian_problems_edge_inside_accepted():
    from fusion._counts import MAX_ELEMENTS, allocation
    from fusion._limits import dense_work
    from fusion.book.chapters import chernoff_scaling as cs
    for d, arrays in ((1, 6), (2, 4), (8, 4)):
        runs = MAX_ELEMENTS // (arrays * d * d)
        allocation((runs, 1, d, d), "runs, n and d", cs._problem_arrays(d))  # the edge just inside: accepted
        assert dense_work(runs, d, "runs, n and d", cs._PROBLEM_CUBE_UNITS) <= 10**9
        with pytest.raises(ValueError, match="runs, n and d"):
            allocation((runs + 1, 1, d, d), "runs, n and d", cs._problem_arrays(d))
    w, m, c = cs.gaussian_problems(np.random.default_rng(0), 3, 2, 1)
    assert c.shape == (3, 2, 1, 1, 1)


def test_c2_cost_table_float_range_decided_before_the_table():
    from fusion.book.chapters import chernoff_scaling as cs
    # 30 rows x 180,000 columns, within the work budget; the last column's last cell beyond the float range
    _refused_fast(cs.cost_table, tuple(range(1, 30)) + (45,), tuple(range(1, 180_000)) + (10**7,),
                  match=r"ns\[29\] = 45 and ss\[179999\] = 10000000 give S\^N")
    t = cs.cost_table((1, 2, 45), (10**6, 2))  # the largest cell within the range: every cell is
    assert t.loc[45, "S = 1000000"] == 10**270 + 45 * 10**6


@pytest.mark.parametrize("first, period, end", [(1e6, 1e-10, 1e6 + 1e-8), (1e12, 1e-4, 1e12 + 1e-2)])
def test_c4_sample_times_refuses_a_period_that_repeats_instants(first, period, end):
    from fusion.registration import methods as reg
    _refused_fast(reg.sample_times, first, period, end, match=r"period = .* first = .* end = .* would repeat")


def test_c4_sample_times_distinct_instants_still_read():
    from fusion.registration import methods as reg
    t = reg.sample_times(1e6, 2.4e-10, 1e6 + 1e-8)  # about twice the spacing there (1.16e-10): distinct
    assert (np.diff(t) > 0).all() and t.size == 42
    assert reg.two_point(t, np.arange(t.size, dtype=float), t[:3]).shape == (3,)
    assert reg.sample_times(5.0, 1.0, 5.0).tolist() == [5.0]


@pytest.mark.parametrize("value", ["Decimal('1e-310')", "Decimal('-1e-310')", "np.longdouble('1e-310')",
                                   "Fraction(3, 10**324)", "np.array(np.longdouble('-2e-308'))"])
def test_d1_rounded_rounds_an_inexact_number_below_the_normal_floats_to_zero(value):
    """Rounded to at most 17 decimals, a number below 2.2e-308 is exactly zero; the significant-digit formatters
    still refuse it (its float is not it)."""
    from decimal import Decimal  # noqa: F401 (used by eval)
    from fractions import Fraction  # noqa: F401
    from fusion.book import tables
    v = eval(value)
    for decimals in (0, 4, 17):
        r = tables.rounded(v, decimals)
        assert r == 0.0 and str(r) == "0.0"
    with pytest.raises(ValueError, match="decimals"):
        tables.rounded(v, 18)
    with pytest.raises(ValueError, match=r"^x must be a number of magnitude at least 2\.2e-308"):
        tables.sci(v, 3)
