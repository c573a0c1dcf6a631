"""Chapter 07's bad input of fuzz 18 (classes D, E, F and its debatable items) is refused by name (issue 35).

Each reproducer of ``/work/tmp/fuzz18/report.md`` in ``fusion.book.chapters.time_registration*`` must raise a
:class:`ValueError` (a :class:`TypeError` for a wrong type) whose message names the argument, never a KeyError,
IndexError or AttributeError, nor return NaN or a plausible wrong number or label. The fixes are by class, so each
class is tested over every public function of the chapter with the same shape, not only the reproducer:

* a mapping of exact MSEs must hold the methods read, each a finite number >= 0 (``mc_table``, ``fig4_figure``,
  ``benchmark_table``, ``exact_numbers``);
* Monte-Carlo runs must hold the methods read (``fig4_figure``, ``noise_level_table``, ``benchmark_table``);
* a sequence whose entries key a table's rows or columns must not repeat one (every ``names`` of methods, every
  ``sigmas`` of noise levels, ``ratio_sweep``'s ``periods``);
* a sweep given to a figure must be its maker's output (``sigma_figure``, ``ratio_figure``);
* a scenario's own refusal names the chapter's argument (``delay_break_even``'s ``upper``, ``cost_values``'s
  ``t2_ratio``).

Degenerate valid input keeps a documented result: a closed-form table in which no pair crosses gives an empty
crossing table (fuzz 18's D30, a KeyError before), and ``named_crossings`` of no pair an empty table.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from functools import cache
from typing import Any

import numpy as np
import pandas as pd
import pytest

from fusion.book.chapters import time_registration as tr
from fusion.book.chapters import time_registration_ledger as trl
from fusion.scenarios import time_registration as sc
from fusion.scenarios.time_registration import RegMethod

nan, inf = float("nan"), float("inf")
FIG4 = (RegMethod.TWO_POINT, RegMethod.IMPROVED)


@cache
def mc4() -> sc.MonteCarlo:
    """Runs of four methods, without the improved one (fuzz 18's MC4)."""
    return sc.monte_carlo([m.value for m in sc.RegMethod][:4], 1.0, 4, 0)


@cache
def mc_all() -> sc.MonteCarlo:
    """Runs of every method."""
    return sc.monte_carlo(list(sc.METHODS), 1.0, 4, 0)


@cache
def exact_all() -> dict[str, float]:
    return {n: sc.expected(n, 1.0) for n in sc.METHODS}


def ct(b: list, g: list, idx: tuple = ("reg_two_point", "reg_improved")) -> pd.DataFrame:
    """A two-row closed-form table (fuzz 18's CT)."""
    return pd.DataFrame({tr.B_OFFSET: b, "g": g}, index=list(idx))


def closed() -> pd.DataFrame:
    return tr.closed_form_table(1.0, 1.0)


def names(exc: BaseException, arg: str) -> bool:
    return re.search(rf"(?<![A-Za-z0-9_]){re.escape(arg)}(?![A-Za-z0-9_])", str(exc)) is not None


def refused(call: Callable[[], Any], arg: str, exc: type[Exception] = ValueError) -> None:
    with pytest.raises((ValueError, TypeError)) as info:
        call()
    assert type(info.value) is exc, f"{type(info.value).__name__}: {info.value}"
    assert names(info.value, arg), f"the message does not name {arg!r}: {info.value}"


#: (fuzz 18 case id, call, the argument its refusal must name, the exception type).
CASES: list[tuple[str, Callable[[], Any], str, type[Exception]]] = [
    ("D6", lambda: trl.keep([1], {"a": 2.0}), "store", TypeError),
    ("D6 values", lambda: trl.keep({}, [("a", 2.0)]), "values", TypeError),
    ("D6 key", lambda: trl.keep({}, {1: 2.0}), "values", TypeError),
    ("D7", lambda: trl.unregistered_runs(5, np.arange(10.0), np.arange(0.5, 9, 1.5)), "m", TypeError),
    ("D7 t2 before t1", lambda: trl.unregistered_runs(mc4(), np.arange(1.0, 10.0), np.arange(0.5, 9, 1.5)), "t2",
     ValueError),
    ("D7 t1", lambda: trl.unregistered_runs(mc4(), [3.0, 1.0, 2.0], [2.0]), "t1", ValueError),
    ("D27", lambda: tr.mc_table(mc4(), {}), "exact", ValueError),
    ("D28", lambda: tr.noise_level_table({1.0: mc4()}, 1.0), "mcs", ValueError),
    ("D28 key", lambda: tr.noise_level_table({"a": mc_all()}, 1.0), "mcs", TypeError),
    ("D29", lambda: tr.fig4_figure(mc4(), {m.value: 1.0 for m in list(sc.RegMethod)[:4]}, 1.0), "mc", ValueError),
    ("D31", lambda: tr.labelled(closed(), "{0}{1}"), "template", ValueError),
    ("D32", lambda: tr.labelled(closed(), "{x}"), "template", ValueError),
    ("E5", lambda: trl.blue_whole_record(0.0), "sigma", ValueError),
    ("E5 tiny", lambda: trl.blue_whole_record(1e-200), "sigma", ValueError),
    ("E11", lambda: trl.keep({}, {"a": nan}), "values", ValueError),
    ("E11 inf", lambda: trl.keep({}, {"a": np.float64(-inf)}), "values", ValueError),
    ("E17", lambda: tr.mc_table(mc4(), {m.value: nan for m in list(sc.RegMethod)[:4]}), "exact", ValueError),
    ("E17 negative", lambda: tr.mc_table(mc4(), {m.value: -1.0 for m in list(sc.RegMethod)[:4]}), "exact",
     ValueError),
    ("E18", lambda: tr.crossing_table(ct([1.0, nan], [1.0, 2.0])), "closed", ValueError),
    ("E18 inf", lambda: tr.crossing_table(ct([1.0, inf], [1.0, 2.0])), "closed", ValueError),
    ("E18 g", lambda: tr.crossing_table(ct([1.0, 2.0], [nan, 2.0])), "closed", ValueError),
    ("E19", lambda: tr.labelled(closed(), "x"), "template", ValueError),
    ("E19 escaped", lambda: tr.labelled(closed(), "{{}}"), "template", ValueError),
    ("F1", lambda: tr.delay_break_even(1.0, np.float64(nan)), "upper", ValueError),
    ("F2", lambda: tr.delay_break_even(1.0, 1e200), "upper", ValueError),
    ("F2 beyond the flight", lambda: tr.delay_break_even(1.0, 1e50), "upper", ValueError),
    ("F2 sigma", lambda: tr.delay_break_even(-1.0), "sigma", ValueError),
    ("F4", lambda: trl.figs23_fits(nan, 30.0), "a", ValueError),
    ("F4 huge", lambda: trl.figs23_fits(1e140, 1e6), "a", ValueError),
    ("F5", lambda: trl.figs23_fits(1.0, -2.0), "end", ValueError),
    ("F5 slow onto fast", lambda: trl.figs23_fits(1.0, 9.0, "slow onto fast"), "end", ValueError),
    ("F6", lambda: trl.figs23_fits(1.0, nan), "end", ValueError),
    ("F7", lambda: trl.figs23_fits(1.0, inf), "end", ValueError),
    ("F7 huge", lambda: trl.figs23_fits(1.0, 1e12), "end", ValueError),
    ("F17", lambda: trl.cost_values(np.arange(10.0), np.arange(0.5, 9, 1.5), [1.0], 1.0), "t2_ratio", ValueError),
    ("F17 sigma", lambda: trl.cost_values(np.arange(10.0), np.arange(0.5, 9, 1.5), [12.0], nan), "sigma",
     ValueError),
    ("F23", lambda: tr.crossing_table(ct([1.0, 2.0], [1.0, 0.5], ("reg_two_point", "reg_two_point"))), "closed",
     ValueError),
    ("F23 text", lambda: tr.crossing_table(ct(["a", "b"], [1.0, 0.5])), "closed", TypeError),
    ("F24", lambda: tr.labelled(closed(), "{:d}"), "template", ValueError),
    ("ratio_sweep periods twice", lambda: tr.ratio_sweep([1.0, 1.0], 1.0, [RegMethod.TWO_POINT]), "periods",
     ValueError),
    ("ratio_sweep names twice", lambda: tr.ratio_sweep([1.0], 1.0, [RegMethod.TWO_POINT] * 2), "names", ValueError),
    ("sigma_figure empty", lambda: tr.sigma_figure(pd.DataFrame()), "sweep", ValueError),
    ("sigma_figure not a frame", lambda: tr.sigma_figure({}), "sweep", TypeError),
    ("ratio_figure empty", lambda: tr.ratio_figure(pd.DataFrame()), "ratio", ValueError),
    ("ratio_figure not a method", lambda: tr.ratio_figure(pd.DataFrame({"x": [1.0]}, index=[5.0])), "ratio",
     ValueError),
]


@pytest.mark.parametrize(("case", "call", "arg", "exc"), CASES, ids=[c[0] for c in CASES])
def test_fuzz18_case_is_refused_by_name(case: str, call: Callable[[], Any], arg: str, exc: type[Exception]) -> None:
    refused(call, arg, exc)


def test_keep_leaves_the_store_unchanged_when_it_refuses() -> None:
    store = {"x": 1.0}
    with pytest.raises(ValueError, match=r"values\['b'\]"):
        trl.keep(store, {"a": 2.0, "b": nan})
    assert store == {"x": 1.0}
    assert trl.keep(store, {"a": 2.0, "s": "text", "n": 3}) == {"a": 2.0, "s": "text", "n": 3}
    assert store == {"x": 1.0, "a": 2.0, "s": "text", "n": 3}


# ------------------------------------------------------------------ class: exact MSEs hold the methods read


EXACT_READERS: dict[str, Callable[[dict], Any]] = {
    "mc_table": lambda ex: tr.mc_table(mc_all(), ex),
    "fig4_figure": lambda ex: tr.fig4_figure(mc_all(), ex, 1.0),
    "benchmark_table": lambda ex: tr.benchmark_table(mc_all(), ex),
    "exact_numbers": lambda ex: tr.exact_numbers(ex, 1.0, sc.instants()[1]),
}


@pytest.mark.parametrize("reader", EXACT_READERS, ids=list(EXACT_READERS))
@pytest.mark.parametrize("bad", ["missing", nan, inf, -1.0, "1.0"])
def test_every_reader_of_exact_mses_refuses_a_missing_or_bad_mse(reader: str, bad: object) -> None:
    ex = dict(exact_all())
    if bad == "missing":
        del ex[RegMethod.IMPROVED]
    else:
        ex[RegMethod.IMPROVED] = bad
    refused(lambda: EXACT_READERS[reader](ex), "exact", TypeError if isinstance(bad, str) and bad != "missing"
            else ValueError)
    EXACT_READERS[reader](dict(exact_all()))  # the valid mapping is read


RUNS_READERS: dict[str, tuple[Callable[[sc.MonteCarlo], Any], str]] = {
    "fig4_figure": (lambda mc: tr.fig4_figure(mc, exact_all(), 1.0), "mc"),
    "noise_level_table": (lambda mc: tr.noise_level_table({1.0: mc}, 1.0, block=2), "mcs"),  # block within the runs
    "benchmark_table": (lambda mc: tr.benchmark_table(mc, exact_all()), "mc"),
    "mc_table": (lambda mc: tr.mc_table(mc, exact_all()), "mc"),
}


@pytest.mark.parametrize("reader", RUNS_READERS, ids=list(RUNS_READERS))
def test_every_reader_of_monte_carlo_runs_refuses_a_non_result_or_missing_runs(reader: str) -> None:
    call, arg = RUNS_READERS[reader]
    refused(lambda: call({"per_run": {}}), arg, TypeError)
    if reader != "mc_table":  # mc_table reads every method mc holds
        refused(lambda: call(mc4()), arg, ValueError)
    call(mc_all())


def test_mc_table_reads_only_the_methods_of_the_runs() -> None:
    table = tr.mc_table(mc4(), exact_all())
    assert list(table.index) == [m.value for m in list(sc.RegMethod)[:4]]
    assert not table.select_dtypes("number").isna().to_numpy().any()


# ------------------------------------------------------------------ class: keyed sequences do not repeat an entry


REPEATS: list[tuple[str, Callable[[], Any], str]] = [
    ("sigma_sweep names", lambda: tr.sigma_sweep([1.0], [RegMethod.TWO_POINT, RegMethod.TWO_POINT]), "names"),
    ("sigma_sweep sigmas", lambda: tr.sigma_sweep([1.0, 1], [RegMethod.TWO_POINT]), "sigmas"),
    ("ratio_sweep periods", lambda: tr.ratio_sweep([6.0, 6], 1.0, [RegMethod.TWO_POINT]), "periods"),
    ("transient_table names", lambda: tr.transient_table(10.0, 1.0, [RegMethod.KALMAN_PREDICT] * 2), "names"),
    ("stress_table names", lambda: trl.stress_table(1.0, [RegMethod.TWO_POINT] * 2), "names"),
    ("tuning_by_noise sigmas", lambda: tr.tuning_by_noise([0.5, 0.5], 4, 0), "sigmas"),
    ("fig4_compatibility sigmas", lambda: tr.fig4_compatibility([0.5, 0.5], 4, 0, 1.0), "sigmas"),
]


@pytest.mark.parametrize(("case", "call", "arg"), REPEATS, ids=[c[0] for c in REPEATS])
def test_a_sequence_keying_a_table_refuses_a_repeated_entry(case: str, call: Callable[[], Any], arg: str) -> None:
    refused(call, arg, ValueError)


# ------------------------------------------------------------------ figures of a sweep


def test_sweep_figures_refuse_what_their_maker_does_not_return_and_draw_its_output() -> None:
    sweep = tr.sigma_sweep([0.5, 1.0], [RegMethod.TWO_POINT, RegMethod.IMPROVED])
    assert len(tr.sigma_figure(sweep).axes[0].lines) == 2
    refused(lambda: tr.sigma_figure(tr.sigma_sweep([1.0], [RegMethod.QLS_NEXT])), "sweep")  # no figure method
    refused(lambda: tr.sigma_figure(sweep.iloc[:0]), "sweep")
    refused(lambda: tr.sigma_figure(sweep * nan), "sweep")
    refused(lambda: tr.sigma_figure(sweep.set_axis([-1.0, 1.0])), "sweep")
    ratio = tr.ratio_sweep([5.0, 6.0], 1.0, [RegMethod.TWO_POINT])
    assert len(tr.ratio_figure(ratio).axes[0].lines) == 1
    refused(lambda: tr.ratio_figure(ratio - 10.0), "ratio")  # negative MSEs


# ------------------------------------------------------------------ crossings: degenerate valid input


def test_crossing_table_without_a_crossing_is_empty_with_its_columns() -> None:
    for table in (closed().iloc[:2], ct([1.0, 2.0], [1.0, 1.0]), ct([1.0, 2.0], [1.0, 2.0])):
        out = tr.crossing_table(table)
        assert out.empty
        assert list(out.columns) == [tr.BETTER_BELOW, tr.BETTER_ABOVE, tr.SIGMA_STAR]
        assert out[tr.SIGMA_STAR].dtype == float
    # and named_crossings reads it: a named pair is missing, no pair is an empty table
    refused(lambda: tr.named_crossings(tr.crossing_table(closed().iloc[:2])), "pairs")
    assert tr.named_crossings(tr.crossing_table(closed().iloc[:2]), pairs=()).empty


def test_crossing_table_matches_the_closed_form_crossing() -> None:
    out = tr.crossing_table(ct([1.0, 4.0], [2.0, 1.0]))  # 1 + 2 s² = 4 + s²: s* = sqrt(3)
    assert out.to_dict("records") == [{tr.BETTER_BELOW: "reg_two_point", tr.BETTER_ABOVE: "reg_improved",
                                        tr.SIGMA_STAR: round(float(np.sqrt(3.0)), 2)}]
    full = tr.crossing_table(closed())
    assert len(full) > 0 and full[tr.SIGMA_STAR].is_monotonic_increasing and (full[tr.SIGMA_STAR] > 0).all()


def test_named_crossings_of_no_pair_is_empty_and_a_pair_twice_gives_its_row_twice() -> None:
    crossings = tr.crossing_table(closed())
    empty = tr.named_crossings(crossings, pairs=())
    assert empty.empty and list(empty.columns) == list(crossings.columns)
    pair = tr.NAMED_CROSSINGS[0]
    twice = tr.named_crossings(crossings, pairs=(pair, pair))
    assert len(twice) == 2 and twice.iloc[0].equals(twice.iloc[1])


# ------------------------------------------------------------------ valid templates and latencies


@pytest.mark.parametrize("template", ["{}", "{0}", "fused, {}", "{:>12}", "{!s} (m²)"])
def test_labelled_fills_a_template_with_one_field(template: str) -> None:
    out = tr.labelled(closed().iloc[:2], template)
    assert list(out.index) == [template.format(tr.METHOD_LABELS[k]) for k in closed().index[:2]]


def test_delay_break_even_accepts_latencies_up_to_sensor_1s_first_sample() -> None:
    first = float(sc.instants()[0][0])
    assert tr.delay_break_even(1.0, first) == tr.delay_break_even(1.0)  # the search finds the same change
    refused(lambda: tr.delay_break_even(1.0, np.nextafter(first, 2.0)), "upper")
    refused(lambda: tr.delay_break_even(1.0, 0.0), "upper")


def test_figs23_fits_accepts_the_shortest_records() -> None:
    assert set(trl.figs23_fits(1.0, 4.5)) == set(trl.figs23_fits(1.0, 40.0, "slow onto fast"))
    assert set(trl.figs23_fits(1.0, 9.5, "slow onto fast")) == {"fig2_before_y", "fig2_after_y", "fig3_before_y",
                                                               "fig3_after_y"}
    refused(lambda: trl.figs23_fits(1.0, 4.0), "end")
