"""Fuzz 21b's bad input of chapters 05, 07 and 01 (classes C, I, U, V, T, Z, M and debatables d2, d3, d5, Z3) (issue 35).

Each reproducer of ``/work/tmp/fuzz21b/report.md`` for these classes must raise a :class:`ValueError` (a
:class:`TypeError` for a wrong type) whose message names the caller's argument, never a KeyError, an
AttributeError or a callee's argument, nor return NaN or a plausible wrong number. The fixes are by class:

* C: ``slip_band`` checks ``variants_all`` with the check of its sibling ``slip_pair_band`` (one helper);
  ``ir_rms`` and ``ir_ratio`` scale each column by an exact power of two before squaring (no underflow to 0,
  bit-identical results otherwise) and ``ir_ratio`` refuses an undefined (NaN) bootstrap interval by name;
* I, U: ``scan``, ``levels``, ``omegas`` and ``names`` go through the sequence rule and, where they key the result,
  the repeat rule; entries are named by position;
* V: ``printed_equation_checks`` refuses F Pi F^T = 0 (a NaN relative error) and names ``x``;
* T: ``transient_end`` checks the table's instants and cells, the period against them, and refuses a steady state
  that a horizon too short cannot confirm;
* Z, Z3: the chapter 07 helpers of instants refuse an extrapolation as ``cost_count`` does (one record check) and
  name ``t2`` for a least-squares window without two samples;
* M: ``margin_sensitivity`` checks the nested records of a stored ledger as it reads them.

Debatables: d2 (``named_crossings`` of a repeated pair) is kept as documented (the rows are numbered, not keyed by
pair: nothing collapses); d3 (negative ``g`` or ``b`` in ``crossing_table``) and d5 (a huge label width in
``labelled``) are refused.
"""

from __future__ import annotations

import copy
import json
import re
from collections.abc import Callable
from functools import cache
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings, strategies as st
from hypothesis.extra.numpy import arrays

from fusion import data
from fusion.book.chapters import ci, ofs_fair
from fusion.book.chapters import time_registration as ch
from fusion.scenarios import time_registration as sc
from fusion.scenarios import two_sensor
from fusion.scenarios.time_registration import RegMethod

nan, inf = float("nan"), float("inf")
LEDGERS = Path(__file__).resolve().parents[1] / "book" / "ledger"
S = two_sensor.SLIP_STEPS
Z = np.abs(np.random.default_rng(0).normal(size=(50, 4)))
P1, P2 = np.diag([100.0, 1.0, 100.0, 1.0]), np.diag([50.0, 2.0, 50.0, 2.0])
T1, T2 = sc.instants()


@cache
def _transient(h: float = 100.0) -> pd.DataFrame:
    return ch.transient_table(h, 1.0)


def transient(h: float = 100.0) -> pd.DataFrame:
    return _transient(h).copy()


@cache
def scenario() -> Any:
    return ci.source_scenario(2024)


@cache
def study() -> Any:
    return two_sensor.fusion_study(scenario(), *ci.step_weights(2024), published_omega=0.0018)


@cache
def readings() -> Any:
    return ci.ir_readings(0.1, 1, 4)


@cache
def _ledger() -> dict:
    return json.loads((LEDGERS / "yang2012optimal.json").read_text())


def comparison_index() -> int:
    return next(k for k, r in enumerate(_ledger()["claims"]) if r["evidence"].get("kind") == "comparison")


def mutated(f: Callable[[dict], object]) -> dict:
    led = copy.deepcopy(_ledger())
    f(led)
    return led


def _inf_cell() -> pd.DataFrame:
    t = transient()
    t.iloc[5, 2] = inf
    return t


def _zero_y() -> np.ndarray:
    r = Z.copy()
    r[:, 3] = 0.0
    return r


def _same_instants() -> pd.DataFrame:
    t = transient()
    t.index = t.index * 0
    return t


CASES: list[tuple[str, Callable[[], Any], str]] = [
    # C: slip_band checks variants_all as slip_pair_band checks its mappings (one helper)
    ("C1 slip_band empty", lambda: ci.slip_band({}, 261), "variants_all"),
    ("C2 slip_band nan", lambda: ci.slip_band({S: (nan, 1.0)}, 261), "variants_all"),
    ("C2 slip_band negative", lambda: ci.slip_band({S: (1.0, -1.0)}, 261), "variants_all"),
    ("C2 slip_band zero", lambda: ci.slip_band({S: (0.0, 1.0)}, 261), "variants_all"),
    ("C2 slip_band huge", lambda: ci.slip_band({S: (1e300, 1.0)}, 261), "variants_all"),
    ("C3 slip_band one slip", lambda: ci.slip_band({S: (1.0,)}, 261), "variants_all"),
    ("C3 slip_band three slips", lambda: ci.slip_band({S: (1.0, 1.0, 1.0)}, 261), "variants_all"),
    ("C4 slip_band text", lambda: ci.slip_band({S: "ab"}, 261), "variants_all"),
    ("C5 slip_band list", lambda: ci.slip_band([1, 2], 261), "variants_all"),
    ("C slip_pair_band inf", lambda: ci.slip_pair_band({ci.W_GRID: (inf, 1.0)}, {ci.IMP: (3.3, 3.4)}, 261),
     "slip_weights"),
    ("C slip_pair_band zero", lambda: ci.slip_pair_band({ci.W_GRID: (4.7, 4.8)}, {ci.IMP: (0.0, 3.4)}, 261),
     "slip_all"),
    ("C6 ir_ratio constant runs", lambda: ci.ir_ratio(np.ones((20, 4)), 1), "run_rmse"),
    ("C7 ir_ratio y all zero", lambda: ci.ir_ratio(_zero_y(), 1), "run_rmse"),
    # I: ir_sigma_band's scan under the sequence rule, entries named
    ("I1 scan int", lambda: ci.ir_sigma_band(readings(), 5), "scan"),
    ("I2 scan str", lambda: ci.ir_sigma_band(readings(), "ab"), "scan"),
    ("I3 scan nan", lambda: ci.ir_sigma_band(readings(), [1.0, nan]), "scan[1]"),
    ("I3 scan zero", lambda: ci.ir_sigma_band(readings(), [0.0]), "scan[0]"),
    ("I4 scan generator", lambda: ci.ir_sigma_band(readings(), (x for x in [1.0])), "scan"),
    # U: sequences keying a result refuse a repeat; errors name the caller's argument
    ("U1 fuzzy_levels repeat", lambda: ci.fuzzy_levels(scenario(), [0.5, 0.5]), "levels"),
    ("U2 fuzzy_levels t_steady", lambda: ci.fuzzy_levels(scenario(), [0.5], 1e9), "t_steady"),
    ("U2 fuzzy_levels t_steady nan", lambda: ci.fuzzy_levels(scenario(), [0.5], nan), "t_steady"),
    ("U3 fuzzy_levels zero", lambda: ci.fuzzy_levels(scenario(), [0.0]), "levels[0]"),
    ("U3 fuzzy_levels one", lambda: ci.fuzzy_levels(scenario(), [0.5, 1.0]), "levels[1]"),
    ("U fuzzy_levels text", lambda: ci.fuzzy_levels(scenario(), "ab"), "levels"),
    ("U4 slip_at_weights repeat", lambda: ci.slip_at_weights(scenario(), study(), (0.0018, 0.0018)), "omegas"),
    ("U slip_at_weights out of range", lambda: ci.slip_at_weights(scenario(), study(), (0.5, 1.5)), "omegas[1]"),
    ("U slip_at_weights generator", lambda: ci.slip_at_weights(scenario(), study(), (w for w in [0.5])), "omegas"),
    ("U5 slip_all repeat", lambda: ci.slip_all(study(), (two_sensor.StudyMethod.CI,) * 2), "names"),
    ("U slip_all generator", lambda: ci.slip_all(study(), (n for n in [two_sensor.StudyMethod.CI])), "names"),
    # V: printed_equation_checks
    ("V1 F = 0", lambda: ci.printed_equation_checks(P1, P2, P1 * 0.1, np.zeros((4, 4))), "F"),
    ("V1 Pi = 0", lambda: ci.printed_equation_checks(P1, P2, np.zeros((4, 4)), np.eye(4)), "Pi"),
    ("V2 x short", lambda: ci.printed_equation_checks(P1, P2, P1 * 0.1, np.eye(4), (1.0, 2.0)), "x"),
    ("V3 x text", lambda: ci.printed_equation_checks(P1, P2, P1 * 0.1, np.eye(4), "abcd"), "x"),
    ("V x nan", lambda: ci.printed_equation_checks(P1, P2, P1 * 0.1, np.eye(4), (1.0, nan, 1.0, 1.0)), "x"),
    ("V F text", lambda: ci.printed_equation_checks(P1, P2, P1 * 0.1, "F"), "F"),
    # T: transient_end
    ("T1 horizon 5", lambda: ch.transient_end(transient(5.0)), "table"),
    ("T1 horizon 12", lambda: ch.transient_end(transient(12.0)), "table"),
    ("T2 horizon 40", lambda: ch.transient_end(transient(40.0)), "table"),
    ("T2 horizon 50", lambda: ch.transient_end(transient(50.0)), "table"),
    ("T3 inf cell", lambda: ch.transient_end(_inf_cell()), "table"),
    ("T4 descending instants", lambda: ch.transient_end(transient().iloc[::-1]), "table"),
    ("T5 repeated instants", lambda: ch.transient_end(_same_instants()), "table"),
    ("T6 period beyond the span", lambda: ch.transient_end(transient(), 0.01, 1e9), "period"),
    ("T7 period off the pattern", lambda: ch.transient_end(transient(), 0.01, 7.0), "period"),
    # Z, Z3: instants outside the record (an extrapolation) and a short least-squares window, named t2
    ("Z1 noise_free_table extrapolation", lambda: ch.noise_free_table(T1, T2 + 1000.0), "t2"),
    ("Z2 noise_free_table t2 = t1", lambda: ch.noise_free_table(T1, T1), "t2[0]"),
    ("Z3 registration_figure extrapolation", lambda: ch.registration_figure(T1, T2 + 1000.0, ch.TWO, "x"), "t2"),
    ("Z3 registration_figure before the record", lambda: ch.registration_figure(T1, T2 - 10.0, ch.TWO, "x"), "t2"),
    ("Z registration_figure least-squares window",
     lambda: ch.registration_figure(T1, T1, RegMethod.LEAST_SQUARES, "x"), "t2[0]"),
    ("Z3 axes_tables extrapolation", lambda: ch.axes_tables(T1, T2 + 1000.0), "t2"),
    # d3, d5: refused
    ("d3 negative g", lambda: ch.crossing_table((c := ch.closed_form_table(1.0, 1.0)).assign(g=-c["g"])), "closed['g']"),
    ("d3 negative b", lambda: ch.crossing_table((c := ch.closed_form_table(1.0, 1.0)).assign(**{ch.B_OFFSET: -1.0})),
     "closed"),
    ("d5 width 5e6", lambda: ch.labelled(ch.closed_form_table(1.0, 1.0), "{:>5000000}"), "template"),
    ("d5 width 1e9", lambda: ch.labelled(ch.closed_form_table(1.0, 1.0), "fused, {:*^999999999}"), "template"),
    # M: margin_sensitivity's nested records
    ("M1 evidence text", lambda: ofs_fair.margin_sensitivity(mutated(lambda l: l["claims"][0].__setitem__("evidence", "x"))),
     "ledger"),
    ("M2 no ci_low", lambda: ofs_fair.margin_sensitivity(
        mutated(lambda l: l["claims"][comparison_index()]["evidence"].pop("ci_low"))), "ledger"),
    ("M3 mean_b text", lambda: ofs_fair.margin_sensitivity(
        mutated(lambda l: l["claims"][comparison_index()]["evidence"].__setitem__("mean_b", "x"))), "ledger"),
    ("M4 conjunction without parts", lambda: ofs_fair.margin_sensitivity(
        mutated(lambda l: l["claims"][0].__setitem__("evidence", {"kind": "conjunction"}))), "ledger"),
    ("M4 conjunction part text", lambda: ofs_fair.margin_sensitivity(
        mutated(lambda l: l["claims"][0].__setitem__("evidence", {"kind": "conjunction", "parts": ["x"]}))), "ledger"),
    ("M5 alternative int", lambda: ofs_fair.margin_sensitivity(
        mutated(lambda l: l["claims"][0].__setitem__("alternatives", [1]))), "ledger"),
    ("M6 alternative without reading", lambda: ofs_fair.margin_sensitivity(
        mutated(lambda l: l["claims"][0].__setitem__("alternatives", [{"counted": True}]))), "ledger"),
    ("M7 ci_low nan", lambda: ofs_fair.margin_sensitivity(
        mutated(lambda l: l["claims"][comparison_index()]["evidence"].__setitem__("ci_low", nan))), "ledger"),
    ("M7 one end null", lambda: ofs_fair.margin_sensitivity(
        mutated(lambda l: l["claims"][comparison_index()]["evidence"].__setitem__("ci_high", None))), "ledger"),
]


def _names(message: str, arg: str) -> bool:
    return re.search(rf"(?<![A-Za-z0-9_]){re.escape(arg)}(?![A-Za-z0-9_])", message) is not None


@pytest.mark.parametrize(("case", "call", "arg"), CASES, ids=[c[0] for c in CASES])
def test_fuzz21b_case_is_refused_by_name(case: str, call: Callable[[], Any], arg: str) -> None:
    with pytest.raises((ValueError, TypeError)) as info:
        call()
    assert _names(str(info.value), arg), f"{case}: {info.value!r} does not name {arg}"


# --- C: scaling before squaring; valid input unchanged ---------------------------------------------------------------

@settings(max_examples=40, deadline=None)
@given(arrays(np.float64, st.tuples(st.integers(2, 12), st.just(4)), elements=st.floats(0.01, 100.0)),
       st.integers(-600, 400))
def test_ir_rms_is_exact_under_a_power_of_two_and_does_not_underflow(run_rmse: np.ndarray, k: int) -> None:
    direct = np.sqrt(np.mean(run_rmse ** 2, axis=0))
    assert np.array_equal(ci.ir_rms(run_rmse), direct)            # the scaling changes no bit of a normal input
    assert np.array_equal(ci.ir_rms(run_rmse * 2.0 ** k), direct * 2.0 ** k)   # squares of 2**-600 underflowed to 0


def test_ir_ratio_of_tiny_errors_is_the_ratio_of_the_errors() -> None:
    ratio = ci.ir_ratio(Z, 1)
    assert np.allclose(ci.ir_ratio(Z * 1e-200, 1), ratio, rtol=1e-12)   # was (nan, nan, nan)
    assert np.allclose(ci.ir_rms(Z * 1e-200) / 1e-200, ci.ir_rms(Z), rtol=1e-12)   # was all 0
    assert ratio[1] < ratio[0] < ratio[2]


def test_slip_band_reads_a_valid_variants_entry_as_before() -> None:
    band = ci.slip_band({S: (3.3, 3.4), "other": "ignored"}, 261)
    pub = float(data.WANG2024_RMSE.columns["improved"][0])
    expect = {ax: two_sensor.slip_steps_band(v * np.sqrt(261), pub, 0) for ax, v in zip("xy", (3.3, 3.4))}
    assert band == expect


def test_printed_equation_checks_of_valid_input_is_finite() -> None:
    out = ci.printed_equation_checks(P1, P2, P1 * 0.1, np.eye(4))
    assert all(np.isfinite(v) for v in out.values())


# --- T: transient_end -------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("horizon", [55.0, 100.0, 160.0])
def test_transient_end_of_a_long_enough_horizon_is_the_same(horizon: float) -> None:
    assert ch.transient_end(transient(horizon)) == 28.0


@settings(max_examples=25, deadline=None)
@given(st.floats(0.5, 90.0).filter(lambda p: abs(p / 5.0 - round(p / 5.0)) > 1e-6))
def test_transient_end_refuses_a_period_that_is_not_the_instants_pattern(period: float) -> None:
    with pytest.raises(ValueError, match="period"):
        ch.transient_end(transient(), 0.01, period)


# --- Z: valid instants keep working -----------------------------------------------------------------------------------

def test_instant_helpers_accept_the_chapter_instants() -> None:
    assert len(ch.noise_free_table(T1, T2)) == len(T2)
    assert ch.axes_tables(T1, T2)[0].shape == (2, 2)
    ch.registration_figure(T1, T2, RegMethod.LEAST_SQUARES, "least squares")
    ch.registration_figure(T1, T1, ch.TWO, "two-point")     # the instants at samples: only least squares needs two


# --- debatables ---------------------------------------------------------------------------------------------------------

def test_named_crossings_gives_a_repeated_pair_its_row_twice_as_documented() -> None:
    # d2, kept: the rows are numbered 0, 1, ... (not keyed by pair), so a repeat collapses nothing
    crossings = ch.crossing_table(ch.closed_form_table(1.0, 1.0))
    pair = (RegMethod.THREE_POINT, RegMethod.TWO_POINT)
    out = ch.named_crossings(crossings, [pair, pair])
    assert list(out.index) == [0, 1] and out.iloc[0].equals(out.iloc[1])


@pytest.mark.parametrize(("width", "ok"), [(99, True), (100, False)])
def test_labelled_accepts_widths_of_two_digits(width: int, ok: bool) -> None:   # the shared template rule
    closed = ch.closed_form_table(1.0, 1.0)
    if ok:
        assert all(len(k) == width for k in ch.labelled(closed, f"{{:>{width}}}").index)
    else:
        with pytest.raises(ValueError, match="template"):
            ch.labelled(closed, f"{{:>{width}}}")


def test_crossing_table_accepts_zero_offsets() -> None:
    closed = ch.closed_form_table(1.0, 1.0)
    assert (closed[ch.B_OFFSET] >= 0).all() and (closed[ch.B_OFFSET] == 0).any()
    assert len(ch.crossing_table(closed)) > 0


# --- M: a stored ledger with no interval (infinite means) ------------------------------------------------------------

def test_margin_sensitivity_reads_a_ledger_whose_comparison_has_no_interval() -> None:
    led = json.loads((LEDGERS / "lecture003-02.json").read_text())
    out = ofs_fair.margin_sensitivity(led)         # a TypeError (abs(None)) before
    assert len(out) > 0 and out.index.names == ["record", "reading"]
    assert len(ofs_fair.margin_sensitivity(_ledger())) == 20
