"""Fuzz 22b's cases V, KP, NB, NS and FR (the chapter layer), by class.

Each refusal is a ValueError or TypeError naming the argument (issue 35); valid input keeps working. The classes:

* V: the bookkeeping glue functions (chapter 07's ``manoeuvre_values``/``gain_values``, chapter 05's
  ``fruit_fly_step_values``/``fig5_hypothesis_numbers``) read their table and mapping cells by the glue rule (one
  reader, ``fusion.book.glue._glued_cell``; ``scalar`` for a mapping cell): finite numbers returned as floats,
  non-negative MSEs, shares and weights in [0, 1], rows by label, a row read once;
* KP: ``time_registration_ledger.keep`` applies ``glue_all``'s finiteness rule, the same function;
* NB: ``noise_level_table`` refuses a block longer than an entry's runs (its column would be 0/0);
* NS: chapter 01's ``noise`` is text (``one_of``), named ``noise``;
* FR: a Fraction, a Decimal or a 0-d array that the scalar readers accept is computed with (and glued) as the
  float they return (``given_number`` keeps an integer type an int, as a glued value shows it).
"""

from __future__ import annotations

import math
import re
from decimal import Decimal
from fractions import Fraction

import matplotlib

matplotlib.use("Agg")
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
import pytest  # noqa: E402
from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

import fusion.book.chapters.time_registration_ledger as tl  # noqa: E402
from fusion._validation import given_number  # noqa: E402
from fusion.book.chapters import chernoff as chf  # noqa: E402
from fusion.book.chapters import ci, ofs  # noqa: E402
from fusion.book.chapters import time_registration as tr  # noqa: E402
from fusion.book.chapters.ci.fruit_fly_step import EXHAUSTIVE, FRUIT_FLY_STEP_RULES, LARGEST_ERROR, RUNS_WITHIN  # noqa: E402
from fusion.book.chapters.time_registration_ledger.values import EXTRAP  # noqa: E402
from fusion.book.chapters.time_registration_closed import B_OFFSET  # noqa: E402
from fusion.book.glue import _finite  # noqa: E402
from fusion.scenarios import time_registration as trsc  # noqa: E402

NAN, INF = float("nan"), float("inf")
IMPROVED, TWO, THREE = tr.IMPROVED, trsc.RegMethod.TWO_POINT, trsc.RegMethod.THREE_POINT


def _refused(exc: type[Exception], name: str, fn, *args, **kwargs) -> None:
    """``fn(*args, **kwargs)`` raises ``exc`` whose message names ``name`` (as a word)."""
    with pytest.raises(exc) as info:
        fn(*args, **kwargs)
    assert re.search(rf"(?<![A-Za-z0-9_]){re.escape(name)}(?![A-Za-z0-9_])", str(info.value)), str(info.value)


# ---------------------------------------------------------------- V: cells by the glue rule


def _man(v: object) -> dict:
    return {0.0: {IMPROVED: v, TWO: 1.0, THREE: 1.0}, -2.0: {IMPROVED: 1.0}}


@pytest.mark.parametrize("bad, exc", [(NAN, ValueError), (INF, ValueError), (-1.0, ValueError), ("x", TypeError),
                                      (None, TypeError), (np.array([1.0, 2.0]), TypeError)])
def test_manoeuvre_values_cells(bad, exc):
    _refused(exc, "manoeuvre", tl.manoeuvre_values, _man(bad), 1.0)


def test_manoeuvre_values_valid_cells_are_floats():
    # the cells are the exact E[MSE] at sigma (fuzz 33b D4: numbers of another noise level are refused)
    exact = {a: {n: trsc.expected(n, 1.0, a_after=a) for n in ((IMPROVED, TWO, THREE) if a == 0.0 else (IMPROVED,))}
             for a in (0.0, -2.0)}
    given = {**exact, 0.0: {**exact[0.0], IMPROVED: Decimal(repr(exact[0.0][IMPROVED]))}}
    g = tl.manoeuvre_values(given, 1.0)
    assert g["reg_man_impr"] == exact[0.0][IMPROVED] and type(g["reg_man_impr"]) is float
    _refused(ValueError, "manoeuvre", tl.manoeuvre_values, _man(0.5), 1.0)    # not the exact E[MSE] at sigma


@pytest.fixture(scope="module")
def closed():
    return tr.closed_form_table(1.0, 1.0)


_GAINS = {"reg_gain_three": 0.7, "reg_gain_two": 0.5}


@pytest.mark.parametrize("column, bad, exc", [(B_OFFSET, NAN, ValueError), (B_OFFSET, INF, ValueError),
                                              ("g", -5.0, ValueError), ("g", "x", TypeError)])
def test_gain_values_closed_cells(closed, column, bad, exc):
    c = closed.astype(object) if isinstance(bad, str) else closed.copy()
    c.loc[EXTRAP, column] = bad
    _refused(exc, "closed", tl.gain_values, _GAINS, c)


def test_gain_values_closed_row_twice(closed):
    _refused(ValueError, "closed", tl.gain_values, _GAINS, pd.concat([closed, closed.loc[[EXTRAP]]]))


def test_gain_values_valid(closed):
    g = tl.gain_values({"reg_gain_three": Decimal("0.7"), "reg_gain_two": Fraction(1, 2)}, closed)   # FR8
    assert g["reg_gain_excess_pct"] == pytest.approx(40.0)
    assert g["reg_cf_extrap_b"] == closed.loc[EXTRAP, B_OFFSET] and type(g["reg_cf_extrap_b"]) is float


@pytest.fixture(scope="module")
def step():
    return ci.fruit_fly_step_study(seeds=5, target=0.8, seed=0)


def _set(t: pd.DataFrame, row: str, column: str, value: object) -> pd.DataFrame:
    t = t.astype({column: float if not isinstance(value, str) else object})
    t.loc[row, column] = value
    return t


PRINTED, SYM = FRUIT_FLY_STEP_RULES


@pytest.mark.parametrize("row, column, bad", [
    (PRINTED, "candidates below 0.1", NAN), (PRINTED, "candidates below 0.1", 7.0),
    (PRINTED, "candidates below 0.1", -0.5), (SYM, "candidates above 0.5", INF),
    (PRINTED, "median |ω − minimum|", NAN), (PRINTED, "median |ω − minimum|", -1.0),
    (EXHAUSTIVE, LARGEST_ERROR, 0.0), (PRINTED, "runs", 2.7), (PRINTED, RUNS_WITHIN, 6.0)])
def test_fruit_fly_step_values_cells(step, row, column, bad):
    _refused(ValueError, "table", ci.fruit_fly_step_values, _set(step, row, column, bad))


def test_fruit_fly_step_values_text_and_repeats(step):
    _refused(TypeError, "table", ci.fruit_fly_step_values, _set(step, PRINTED, "candidates below 0.1", "x"))
    _refused(ValueError, "table", ci.fruit_fly_step_values, pd.concat([step, step.iloc[[0]]]))
    _refused(ValueError, "table", ci.fruit_fly_step_values, step.iloc[[0, 2]])


@pytest.mark.parametrize("order", [[1, 0, 2], [2, 1, 0], [2, 0, 1]])
def test_fruit_fly_step_values_rows_by_label(step, order):
    assert ci.fruit_fly_step_values(step.iloc[order]) == ci.fruit_fly_step_values(step)


def test_fruit_fly_step_values_of_the_study(step):
    g = ci.fruit_fly_step_values(step)
    assert g["ci_step_below"] == step.loc[PRINTED, "candidates below 0.1"]
    assert g["ci_step_sym_above"] == step.loc[SYM, "candidates above 0.5"]
    assert g["ci_step_grid_err"] == step.loc[EXHAUSTIVE, LARGEST_ERROR] and g["ci_step_runs"] == 5


#: Labels of fig5_hypotheses' rows (read by position: their labels are checked, fuzz 24c q1).
_H_LABELS = ["exhaustive search, 1001 points including ω = 0", "exhaustive search on k/300, k = 1…300",
             "FOA 30 × 200 as printed (median of 3 seeds)", "FOA 30 × 23 (median of 3 seeds)",
             "the same grid k/300 on the source's identical sensors"]


@given(st.floats(allow_nan=True, allow_infinity=True))
@settings(max_examples=60, deadline=None)
def test_fig5_hypothesis_numbers_weights(w):
    tab = pd.DataFrame({"ω found": [0.0, w, 0.001, 0.01, 0.5]}, index=_H_LABELS)
    if math.isfinite(w) and 0.0 <= w <= 1.0 and not (0.0 < w < 2.3e-308):
        assert ci.fig5_hypothesis_numbers(tab)["ci_h_open"] == round(w, 4)
    else:
        _refused(ValueError, "table", ci.fig5_hypothesis_numbers, tab)


def test_fig5_hypothesis_numbers_text():
    _refused(TypeError, "table", ci.fig5_hypothesis_numbers, pd.DataFrame({"ω found": [0.0, "x", 0.1, 0.1, 0.1]},
                                                                                 index=_H_LABELS))


# ---------------------------------------------------------------- KP: keep has glue_all's rule


@pytest.mark.parametrize("value", [complex(NAN, 0), np.array([NAN, 1.0]), pd.Series([NAN]), [NAN], (1.0, INF),
                                   Decimal("NaN"), np.float32("inf"), pd.NA])
def test_keep_refuses_what_glue_all_refuses(value):
    store = {"reg_old": 1.0}
    _refused(ValueError, "values['reg_a']", tl.keep, store, {"reg_a": value})
    assert store == {"reg_old": 1.0}
    assert not _finite(value)   # glue_all's rule, the same function


@pytest.mark.parametrize("value", [1.0, 0, "text", [1.0, 2.0], pd.Series([1.0]), np.array([1.0]),
                                   pd.DataFrame({"a": [NAN]})])
def test_keep_keeps_valid_values(value):
    store: dict = {}
    assert tl.keep(store, {"reg_a": value})["reg_a"] is value and store["reg_a"] is value


# ---------------------------------------------------------------- NB: block within the runs


def test_noise_level_table_block_beyond_runs():
    mc = trsc.monte_carlo(tr.FIG4, 3.0, 20, 1)
    _refused(ValueError, "block", tr.noise_level_table, {3.0: mc}, 10.0, block=21)
    t = tr.noise_level_table({3.0: mc}, 10.0, block=20)      # one block of all the runs: valid
    assert t["P(all 20 runs ordered)"].notna().all()


# ---------------------------------------------------------------- NS: noise is text


class _Str:
    def __str__(self) -> str:
        return "unequal"


@pytest.mark.parametrize("fn", [ofs.healthy_dropped_share, ofs.not_neighbourhood_share, ofs.faulty_member_share])
@pytest.mark.parametrize("bad", [5, None, b"unequal", ["unequal"], _Str()])
def test_noise_is_text(fn, bad):
    _refused(TypeError, "noise", fn, 1, 5, bad)


@pytest.mark.parametrize("fn", [ofs.healthy_dropped_share, ofs.not_neighbourhood_share])
def test_noise_other_text_named(fn):
    with pytest.raises(ValueError, match=r"^noise must be one of"):
        fn(1, 5, "x")


def test_noise_text_subclass_is_its_text():
    assert ofs.not_neighbourhood_share(1, 5, np.str_("equal")) == ofs.not_neighbourhood_share(1, 5, "equal")


# ---------------------------------------------------------------- FR: the reader's float is used


@pytest.mark.parametrize("target", [Fraction(4, 5), Decimal("0.8"), np.array(0.8), np.float32(0.75)])
def test_fruit_fly_step_study_target_read_as_float(target):
    out = ci.fruit_fly_step_study(2, target)
    assert out.equals(ci.fruit_fly_step_study(2, float(target)))


@pytest.mark.parametrize("k", [Decimal("3"), Fraction(3), np.array(3.0), np.int64(3)])
def test_nested_values_glues_floats(k):
    g = chf.nested_values((k, 10.0))
    assert type(g["chf_nest_k0"]) is float and g == chf.nested_values((3.0, 10.0))


def test_latency_values_read_as_floats():
    assert tl.latency_values({1.0: Decimal("0.01"), 3.0: 0.02}, 1.0) == tl.latency_values({1.0: 0.01, 3.0: 0.02}, 1.0)
    assert tl.latency_values({1.0: 0.01}, np.array(1.0))["reg_be_ms"] == 10.0
    assert tl.latency_values({1.0: 0.01}, Fraction(1))["reg_be_ms"] == 10.0


@pytest.mark.parametrize("a, end", [(Decimal("0.1"), 40.0), (0.1, Decimal("40")), (Fraction(1, 10), np.array(40.0))])
def test_figs23_fits_read_as_floats(a, end):
    assert tl.figs23_fits(a, end) == tl.figs23_fits(float(a), float(end))


@given(st.one_of(st.integers(1, 10**6), st.fractions(min_value=Fraction(1, 1000), max_value=10**6),
                 st.decimals(min_value=Decimal("0.001"), max_value=10**6, allow_nan=False, places=3)))
@settings(max_examples=60, deadline=None)
def test_given_number_plain(v):
    r = given_number(v, "v", lo=0.0, lo_open=True)
    assert type(r) is (int if isinstance(v, int) else float) and r == float(v)
    assert type(given_number(np.array(3), "v")) is int and type(given_number(np.array(3.0), "v")) is float


@pytest.mark.parametrize("period, kind", [(Fraction(1, 10), float), (Decimal("0.1"), float), (np.array(0.1), float),
                                         (1, int), (np.int64(1), int), (0.1, float)])
def test_period_glued_as_plain_number(period, kind):
    T = ci.published_numbers(period, 100)["ci_T"]
    assert type(T) is kind and T == float(period)


def test_chapter_05_mapping_entries_read_as_floats():
    """``ci.checks._entries`` returns the floats it read: a Decimal or Fraction entry computes (and glues) as its
    float, the same numbers as the float mapping."""
    from fusion.scenarios.two_sensor import NeesRule
    rules = (NeesRule.CONVEX, NeesRule.CI_HALF, NeesRule.PRINTED, NeesRule.SPLIT, NeesRule.LOCAL)
    dec = {r: Decimal("4.125") for r in rules}
    assert ci.nees_numbers(dec, 100) == ci.nees_numbers({r: 4.125 for r in rules}, 100)
    checks = {"eq2_error": Fraction(1, 8), "eq6_asym": Decimal("2.5"), "eq6_relerr": np.array(0.25)}
    assert ci.printed_equation_numbers(checks) == ci.printed_equation_numbers({k: float(v) for k, v in checks.items()})


def test_chapter_07_exact_mses_read_as_floats():
    """``time_registration._exact_mses`` returns the floats it read: ``mc_table`` computes with them."""
    mc = trsc.monte_carlo(tr.FIG4, 3.0, 20, 1)
    exact = {n: trsc.expected(n, 3.0) for n in tr.FIG4}
    dec = {n: Decimal(repr(v)) for n, v in exact.items()}
    assert tr.mc_table(mc, dec).equals(tr.mc_table(mc, exact))


@pytest.mark.parametrize("sigma", [Decimal("1"), Fraction(1), np.array(1.0)])
def test_time_registration_scenario_reads_floats(sigma):
    """The scenario's shared check (``_check_args``) returns the floats read: ``expected`` and ``monte_carlo``
    compute with them (a Decimal sigma was used raw: TypeError inside)."""
    assert trsc.expected(IMPROVED, sigma) == trsc.expected(IMPROVED, 1.0)
    assert trsc.mse_coefficients(IMPROVED, sigma) == trsc.mse_coefficients(IMPROVED, 1.0)


@pytest.mark.parametrize("be, exc", [({NAN: 0.01, 3.0: 0.02}, ValueError), ({"1.0": 0.01, 3.0: 0.02}, TypeError),
                                     ({-1.0: 0.01, 3.0: 0.02}, ValueError),
                                     ({0.1: 0.01, Decimal("0.1"): 0.02, 3.0: 0.03}, ValueError)])
def test_latency_values_noise_levels(be, exc):
    """Debatable q6, decided: the noise levels (keys) of ``be`` are standard deviations, read as such."""
    _refused(exc, "be", tl.latency_values, be, 3.0)


def test_fruit_fly_step_study_float_subclass_computed_as_read():
    """Debatable q7, decided by FR: a float subclass is computed with the value its check read."""
    class Lying(float):
        def __float__(self) -> float:
            return 0.3

    assert ci.fruit_fly_step_study(2, Lying(0.8)).equals(ci.fruit_fly_step_study(2, 0.3))
