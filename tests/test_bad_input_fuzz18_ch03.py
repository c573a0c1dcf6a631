"""Fuzz 18's cases in the lecture chapters (02-04), chapter 05's text helpers and the ledger's Conjunction (issue 35).

Fuzz 18 (an independent fuzz of the tree) found, in ``fusion.book.chapters.lecture*``, ``lecture_wavelets``,
``lecture_correlated``, ``lecture_weighting``, ``ci`` and the verdicts, KeyErrors, AttributeErrors and
IndexErrors (class D: a non-result object, a study of another case, an empty mapping or grid, an index out of
range), accepted input giving a plausible wrong number or text (class E) and refusals that name an internal name
(class F). Each reproducer must now raise :class:`ValueError` or :class:`TypeError` whose message names the
argument; the valid neighbours of each (a documented result: round-off below the minimum, a 0-d period, a table
that records its draws) give that result.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import Any

import numpy as np
import pandas as pd
import pytest

from fusion.book.chapters import chernoff_scaling as csc, ci, lecture
from fusion.book.chapters.lecture_correlated import appendix as lca, correlated as lcc, propositions as lcp
from fusion.book.chapters.lecture_correlated import records as lcr
from fusion.book.chapters.lecture_wavelets import appendix as wa, e26, mechanism, records as lwr, verdicts
from fusion.book.chapters.lecture_weighting import belief, consistency, estimators, learning, studies
from fusion.book.ledger import Comparison, Conjunction, Proposition

#: These tests build a short length study (I = 64, cheaper than the appendix's 256-4096) whose level-4 decomposition
#: PyWavelets flags as boundary-bound; the study is valid input (length >= 16) and the warning is not what is checked.
pytestmark = pytest.mark.filterwarnings("ignore:Level value of .* is too high:UserWarning")

nan, inf = float("nan"), float("inf")


def _e26() -> Any:
    return lwr.study("e26", 2601, 3)


def _m26() -> Any:
    return lwr.study("m26", 2601, 3)


def _len64() -> Any:
    return wa.length_study(64)


def _props() -> tuple[Proposition, Proposition]:
    return Proposition(True, "x"), Proposition(True, "y")


def _comparison() -> Comparison:
    a = np.arange(100.0) + 1
    return Comparison(a, a + 1, "A", "B", "less", "m")


#: (case id, call, the argument its refusal must name); ids are fuzz 18's where the case is its own.
CASES: list[tuple[str, Callable[[], Any], str]] = [
    # class D: a non-result object, a study of another case, an empty grid or mapping, an index out of range
    ("D3 status_text of an int", lambda: verdicts.status_text(5), "c"),
    ("D4 spread_check empty", lambda: learning.spread_check((), draws=10), "log_ranges"),
    ("D5 check_grid eps_factors empty", lambda: consistency.check_grid(eps_factors=(), runs=2), "eps_factors"),
    ("check_grid biases empty", lambda: consistency.check_grid(biases=(), runs=2), "biases"),
    ("D19 table_lengths of an int", lambda: wa.table_lengths({64: 5}), "studies"),
    ("table_lengths empty", lambda: wa.table_lengths({}), "studies"),
    ("table_lengths not a mapping", lambda: wa.table_lengths([_len64()]), "studies"),
    ("table_lengths float key", lambda: wa.table_lengths({64.0: _len64()}), "studies"),
    ("D20 figure_26 of the length study", lambda: e26.figure_26(_len64()), "e"),
    ("D21 glue_equal_gains of the length study", lambda: e26.glue_equal_gains(_len64()), "e1"),
    ("D22 figure_26 sensor 4", lambda: e26.figure_26(_e26(), sensor=4), "sensor"),
    ("figure_26 sensor -1", lambda: e26.figure_26(_e26(), sensor=-1), "sensor"),
    ("D23 table_seeds sensor 99", lambda: e26.table_seeds(_len64(), sensors=(99,)), "sensors"),
    ("table_seeds sensor repeated", lambda: e26.table_seeds(_len64(), sensors=(1, 1)), "sensors"),
    ("table_seeds ss of an int", lambda: e26.table_seeds(_len64(), ss=5), "ss"),
    ("D24 table_mechanism label 99", lambda: mechanism.table_mechanism(_m26(), labels=(0, 99)), "labels"),
    ("table_mechanism label -1", lambda: mechanism.table_mechanism(_m26(), labels=(-1,)), "labels"),
    ("D25 table_typical empty", lambda: wa.table_typical({}), "ev"),
    ("table_typical record without readings", lambda: wa.table_typical({"r": {}}), "ev"),
    ("table_typical reading of an int", lambda: wa.table_typical({"r": {"primary": 5}}), "ev"),
    ("D26 typical_run of an int", lambda: wa.typical_run(5), "ev"),
    ("typical_run of propositions", lambda: wa.typical_run(Conjunction([("a", _props()[0]), ("b", _props()[1])])),
     "ev"),
    ("D33 ledger_evidence of an int", lambda: lcr.ledger_evidence(5), "st"),
    # class E: accepted, giving NaN or a plausible wrong number or text
    ("E3 excess_text negative", lambda: ci.excess_text(-1.0), "excess"),
    ("E4 excess_text NaN", lambda: ci.excess_text(nan), "excess"),
    ("excess_text inf", lambda: ci.excess_text(inf), "excess"),
    ("E10 reading_key int reading", lambda: lecture.reading_key({"reading": 5}), "settings"),
    ("reading_key not a mapping", lambda: lecture.reading_key(5), "settings"),
    ("E14 table_lengths of another length", lambda: wa.table_lengths({64: wa.length_study(128)}), "studies"),
    ("E15 glue_26 spike NaN", lambda: e26.glue_26(_len64(), nan), "spike"),
    ("glue_26 spike negative", lambda: e26.glue_26(_len64(), -1.0), "spike"),
    ("E16 figure_26 shown -5", lambda: e26.figure_26(_e26(), shown=-5), "shown"),
    ("figure_26 shown 0", lambda: e26.figure_26(_e26(), shown=0), "shown"),
    ("figure_26 shown past the length", lambda: e26.figure_26(_e26(), shown=10**6), "shown"),
    ("figure_mechanism shown 0", lambda: mechanism.figure_mechanism(_m26(), shown=0), "shown"),
    ("figure_27 shown -1", lambda: lcc.figure_27(lcr.cached_studies(1, 3).s27, -1), "shown"),
    ("E20 glue_james_stein runs of another table",
     lambda: lca.glue_james_stein(lca.table_james_stein(runs=100), runs=20000), "runs"),
    ("glue_james_stein a table without its runs",
     lambda: lca.glue_james_stein(pd.DataFrame(lca.table_james_stein(runs=100))), "runs"),
    # class F: a refusal naming another (internal) name
    ("F3 gesv_written_ratio n -1", lambda: lcc.gesv_written_ratio(np.int64(-1), 2), "n"),
    ("gesv_written_ratio d 0", lambda: lcc.gesv_written_ratio(600, 0), "d"),
    ("F15 sensor_conjunction one sensor",
     lambda: verdicts.sensor_conjunction(np.ones((100, 1)), np.ones((100, 1)) + 0.1, "A", "B", "m", 0), "a"),
    ("sign_conjunction one sensor",
     lambda: verdicts.sign_conjunction(np.ones((100, 1)), np.ones((100, 1)) + 0.1, "A", "B", 0), "a"),
    ("F16 excess_text bool", lambda: ci.excess_text(np.True_), "excess"),
    ("F18 Conjunction label of an int", lambda: Conjunction([(1, _props()[0]), ("b", _props()[1])]), "parts"),
    ("Conjunction evidence of an int", lambda: Conjunction([("a", 5), ("b", _props()[1])]), "parts"),
    ("F19 glue_26 first 0", lambda: e26.glue_26(_len64(), first=0), "first"),
    ("F20 table_seeds block 7", lambda: e26.table_seeds(_len64(), block=7), "block"),
    ("glue_seeds block 7", lambda: e26.glue_seeds(_len64(), block=7), "block"),
    ("F21 table_mechanism no label", lambda: mechanism.table_mechanism(_m26(), labels=()), "labels"),
    ("F22 figure_mechanism shown 10**6", lambda: mechanism.figure_mechanism(_m26(), shown=10**6), "shown"),
    ("F25 plugin_conjunction no x", lambda: lcp.plugin_conjunction(lcr.cached_studies(1, 3).p25, xs=()), "xs"),
    ("plugin_conjunction one x", lambda: lcp.plugin_conjunction(lcr.cached_studies(1, 3).p25, xs=(0.3,)), "xs"),
    ("plugin_conjunction repeated x",
     lambda: lcp.plugin_conjunction(lcr.cached_studies(1, 3).p25, xs=(0.5, 0.5)), "xs"),
    # fuzz 18's debatable empties and box_corner: an empty grid is refused, as counts() refuses one
    ("table_21 no level", lambda: estimators.table_21(studies.study("s21", 1, 3), ()), "levels"),
    ("table_shift_weight no shift", lambda: belief.table_shift_weight(belief.shift_weight_draws(5), ()), "at"),
    ("belief_accuracy no value",
     lambda: belief.belief_accuracy(studies.study("s24b", 1, 3), list(studies.study("s24b", 1, 3).sq)[0], ()),
     "values"),
    ("table_james_stein no ratio", lambda: lca.table_james_stein(ratios=(), runs=100), "ratios"),
    ("box_corner tol -1", lambda: csc.box_corner(np.array([[0.5, 0.5]]), tol=-1.0), "tol"),
    ("box_corner tol inf", lambda: csc.box_corner(np.array([[0.5, 0.5]]), tol=inf), "tol"),
    ("box_corner eps off the simplex", lambda: csc.box_corner(np.array([[0.5, 0.6]])), "eps"),
    ("box_corner eps negative", lambda: csc.box_corner(np.array([[1.5, -0.5]])), "eps"),
]


def _names(exc: BaseException, arg: str) -> bool:
    return re.search(rf"(?<![A-Za-z0-9_]){re.escape(arg)}(?![A-Za-z0-9_])", str(exc)) is not None


@pytest.mark.parametrize("call, arg", [pytest.param(c, a, id=i) for i, c, a in CASES])
def test_reproducer_is_refused_by_name(call: Callable[[], Any], arg: str) -> None:
    with pytest.raises((ValueError, TypeError)) as info:
        call()
    assert _names(info.value, arg), f"{type(info.value).__name__} does not name {arg!r}: {info.value}"


def test_excess_text_round_off_below_the_minimum_is_at_the_minimum() -> None:
    """Documented: a negative excess above -10⁻¹² is round-off, "at the minimum"; a positive one is printed."""
    assert ci.excess_text(0.0) == ci.excess_text(-1e-13) == "at the minimum"
    assert ci.excess_text(0.44) == "0.44 above the minimum"
    with pytest.raises(ValueError, match="excess"):
        ci.excess_text(-1e-11)


def test_published_numbers_glues_a_plain_number() -> None:
    """A numpy scalar or 0-d array period is glued as the Python number it holds (fuzz 18, debatable)."""
    for period in (np.array(1.0), np.float64(1.0)):
        out = ci.published_numbers(period, np.int64(10))
        assert type(out["ci_T"]) is float and out["ci_T"] == 1.0 and type(out["ci_runs"]) is int
    assert ci.published_numbers(1, 10)["ci_T"] == 1   # a plain number is still glued as given


def test_james_stein_glue_reads_the_runs_its_table_records() -> None:
    tab = lca.table_james_stein(ds=(3,), ratios=(0.0, 1.0), runs=100)
    assert tab.attrs["runs"] == 100
    assert lca.glue_james_stein(tab)["lec_js_runs"] == lca.glue_james_stein(tab, runs=100)["lec_js_runs"] == 100
    bare = pd.DataFrame(tab)
    bare.attrs.clear()
    assert lca.glue_james_stein(bare, runs=100)["lec_js_runs"] == 100   # a table without the record: as given


def test_reading_key_of_valid_settings() -> None:
    assert lecture.reading_key(None) == lecture.reading_key({}) == "primary"
    assert lecture.reading_key({"reading": "x"}) == "x"


def test_valid_neighbours_still_work() -> None:
    """The valid inputs next to the refused ones: the edges of each new range give the documented result."""
    e = _e26()
    assert e26.figure_26(e, sensor=e.gains.size - 1, shown=int(e.length)) is not None
    assert mechanism.figure_mechanism(_m26(), shown=1) is not None
    assert lcc.figure_27(lcr.cached_studies(1, 3).s27, 10**6) is not None   # more runs than drawn: all of them
    assert list(wa.table_lengths({64: _len64()}).index) == [64]
    tab = mechanism.table_mechanism(_m26(), labels=(len(_m26().labels) - 1,))
    assert len(tab) == _m26().gains.size
    assert len(lcp.plugin_conjunction(lcr.cached_studies(1, 3).p25, xs=(0.3, 0.7)).parts) == 2
    assert e26.glue_26(_len64(), spike=0.0)["lec_wv_spike"] == 0.0
    np.testing.assert_array_equal(csc.box_corner(np.array([[0.5, 0.5, 0.0], [0.4, 0.35, 0.25]]), tol=0.0),
                                  [True, False])
    # an optimiser's round-off off the simplex (entries -1e-12, sums 1 + 1e-8) is within its tolerance
    np.testing.assert_array_equal(csc.box_corner(np.array([[0.5, 0.5 - 1e-12, -1e-12], [0.5, 0.5 + 1e-8, 0.0]])),
                                  [True, False])
    assert verdicts.status_text(verdicts.sensor_conjunction(np.ones((100, 2)), np.ones((100, 2)) + 0.1, "A", "B",
                                                            "m", 0)) == "reproduced"
    assert wa.typical_run(_comparison()).claim == "greater"


#: The modules of this file's cases (the lecture chapters and chapter 05), swept by class below.
_MODULES = ["fusion.book.chapters.lecture"] + [f"fusion.book.chapters.{p}.{m}" for p, ms in {
    "lecture_wavelets": ("appendix", "e26", "mechanism", "records", "signals", "variance", "verdicts"),
    "lecture_correlated": ("appendix", "correlated", "propositions", "records", "ridge"),
    "lecture_weighting": ("belief", "consistency", "estimators", "learning", "readings_benchmark", "records", "regime",
                          "studies", "study_evidence"),
    "ci": ("architecture", "bounds", "claim_evidence", "constants", "fruit_fly_step", "infrared", "nees", "paired",
           "printed", "studies", "text", "tracking", "weights")}.items() for m in ms]


def _result_readers() -> list[tuple[str, Callable[..., Any], list[str], int]]:
    """Every public function of :data:`_MODULES` with a parameter annotated by a class of the package (a result,
    a study, a scenario; enums excluded): (id, function, those parameters, required positional parameters)."""
    import enum
    import importlib
    import inspect
    import typing

    functions = [(f"{name.rsplit('.', 1)[1]}.{fn_name}", getattr(mod, fn_name)) for name in _MODULES
                 for mod in [importlib.import_module(name)] for fn_name in getattr(mod, "__all__", ())]
    out = []
    for label, fn in filter(lambda item: inspect.isfunction(item[1]), functions):
        hints, params = typing.get_type_hints(fn), inspect.signature(fn).parameters
        results = [p for p in params if isinstance(hints.get(p), type) and hints[p].__module__.startswith("fusion")
                   and not issubclass(hints[p], enum.Enum)]
        required = sum(p.default is p.empty and p.kind == p.POSITIONAL_OR_KEYWORD for p in params.values())
        if results:
            out.append((label, fn, results, required))
    return out


@pytest.mark.parametrize("fn, results, required", [pytest.param(f, r, n, id=i) for i, f, r, n in _result_readers()])
def test_a_result_argument_of_another_type_is_refused_by_name(fn: Callable[..., Any], results: list[str],
                                                               required: int) -> None:
    """Fuzz 18's class D by class: a function that reads a result checks its type (``instance_of``) first, so an int
    in its place is a TypeError naming a result parameter, never an AttributeError from inside."""
    with pytest.raises(TypeError) as info:
        fn(*[5] * required)
    assert any(_names(info.value, p) for p in results), f"names none of {results}: {info.value}"
