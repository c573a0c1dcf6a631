"""Fuzz 24d, classes C, W, T, M and the debatables D1-D4 (issue 35; chapters 01-04 and 07).

* C (catastrophic cancellation): the scenario's closed forms and runs evaluate the true positions
  :math:`x(t) = v_0 t + a t^2/2` at the times given; at t + 1e8 s they are rounded to 2 m and the two-point E[MSE]
  came out 0.0 (1.25 m² unshifted). One rule (``fusion.scenarios.time_registration._precise_times``), in the
  scenario's entries and in the chapter's time reader ``_record_times``: times whose positions lose the precision
  are refused, naming the time arguments (``t_src``/``t_dst``, ``t1``/``t2``); accepted times give the unshifted
  numbers.
* W: ``time_registration_ledger.study`` refused through ``monte_carlo``'s 14 names (``t_query``); it names ``t1``
  and ``t2`` and documents that ``t2`` needs three instants within the scenario's record.
* T: a table read with a row or a column read twice, or a row the maker never gives, is refused by the shared reader
  ``fusion.book.tables._frame`` (``unique``, ``rows``), naming the table.
* M: ``latency_values`` refuses a negative break-even latency; its docstring says noise levels > 0.
* D1/D2 (decided, documented): an exact-MSE mapping does not record its noise level; pairing it is the caller's
  (``mc_table``, ``benchmark_table``, ``fig4_figure``, ``exact_numbers``), and it is shown as given.
* D3 (fixed): ``exact_numbers`` refuses instants outside the scenario's record, naming ``t2``.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fusion.book.chapters import ofs
from fusion.book.chapters import time_registration as tr
from fusion.book.chapters import time_registration_ledger as trl
from fusion.book.chapters.lecture_wavelets import appendix as wa
from fusion.book.chapters.lecture_wavelets import verdicts
from fusion.book.tables import _frame
from fusion.scenarios import thermocouples
from fusion.scenarios import time_registration as sc

TWO, THREE = sc.RegMethod.TWO_POINT, sc.RegMethod.THREE_POINT
T1, T2 = sc.instants()


# ---- C: times far from the flight's start -------------------------------------------------------------------------

@settings(max_examples=25, deadline=None)
@given(st.floats(0.0, 1e10), st.sampled_from([TWO, THREE]))
def test_expected_at_shifted_times_is_the_unshifted_value_or_refused_by_name(offset: float, name: str) -> None:
    """Two- and three-point E[MSE] depend on time differences only (the truth's acceleration is constant): shifted
    times give the unshifted value, or are refused naming t_src and t_dst (at +1e8 s it was 0.0 instead of 1.25)."""
    want = sc.expected(name, 1.0)
    try:
        got = sc.expected(name, 1.0, t_src=T1 + offset, t_dst=T2 + offset)
    except ValueError as exc:
        assert str(exc).startswith("t_src and t_dst"), exc
        return
    assert got == pytest.approx(want, rel=1e-4)


@pytest.mark.parametrize("call", [
    lambda off: sc.expected(TWO, 1.0, t_src=T1 + off, t_dst=T2 + off),
    lambda off: sc.mse_coefficients(TWO, 1.0, t_src=T1 + off, t_dst=T2 + off),
    lambda off: sc.noise_free_mse(TWO, T1 + off, T2 + off),
    lambda off: sc.monte_carlo([TWO], 1.0, 2, 0, t_src=T1 + off, t_dst=T2 + off),
], ids=["expected", "mse_coefficients", "noise_free_mse", "monte_carlo"])
@pytest.mark.parametrize("offset", [1e8, 1e9])
def test_scenario_entries_refuse_imprecise_times_by_name(call, offset: float) -> None:
    with pytest.raises(ValueError, match=r"^t_src and t_dst reach .* from the flight's start"):
        call(offset)


@pytest.mark.parametrize("call", [
    lambda off: trl.noise_gain_by_instant(T1 + off, T2 + off),
    lambda off: trl.cost_count(T1 + off, T2 + off),
    lambda off: tr.noise_free_table(T1 + off, T2 + off),
    lambda off: trl.unregistered_runs(sc.monte_carlo([TWO], 1.0, 2, 0), T1 + off, T2 + off),
    lambda off: trl.study(T1 + off, T2 + off, 1.0, 2, 0),
], ids=["noise_gain_by_instant", "cost_count", "noise_free_table", "unregistered_runs", "study"])
@pytest.mark.parametrize("offset", [1e8, 1e9])
def test_chapter_functions_refuse_imprecise_times_naming_t1_t2(call, offset: float) -> None:
    """C1, C2: the gains were 0.0 and the excess NaN at +1e8 s."""
    with pytest.raises(ValueError, match=r"^t1 and t2 reach"):
        call(offset)


def test_noise_gain_by_instant_shift_within_precision() -> None:
    """Valid shifted times keep working, with the unshifted gains."""
    g0, g = trl.noise_gain_by_instant(T1, T2), trl.noise_gain_by_instant(T1 + 1e4, T2 + 1e4)
    np.testing.assert_allclose(g[["g three-point", "g two-point"]].to_numpy(float),
                               g0[["g three-point", "g two-point"]].to_numpy(float), rtol=1e-6)


# ---- W: the arguments of study named ------------------------------------------------------------------------------

@pytest.mark.parametrize("t1, t2, match", [
    (T1, T2[:1], r"^t2 must hold at least 3 instants"),
    (T1, T2[:2], r"^t2 must hold at least 3 instants"),
    (T1 * 1e-6, T2 * 1e-6, r"^t2 must lie within the record of the scenario's sensor-1 samples"),
    (T1 + 1e9, T2 + 1e9, r"^t1 and t2 reach"),
], ids=["one-instant", "two-instants", "scaled", "shifted"])
def test_study_names_t1_t2(t1, t2, match: str) -> None:
    with pytest.raises(ValueError, match=match) as info:
        trl.study(t1, t2, 1.0, 2, 0)
    assert "t_query" not in str(info.value) and "t_src" not in str(info.value)


# ---- T: tables with a repeated or unknown row, a repeated column --------------------------------------------------

@pytest.fixture(scope="module")
def mct() -> pd.DataFrame:
    studies = {"hs": ofs.study(0, 2), "eq": ofs.study(1, 2, "equal")}
    return ofs.mc_table(studies, {"hs": thermocouples.DEFAULT_SIGMAS, "eq": 1.0})


def test_figure_mc_refuses_a_repeated_row(mct: pd.DataFrame) -> None:
    with pytest.raises(ValueError, match=r"^table holds the row .* more than once"):
        ofs.figure_mc(pd.concat([mct.iloc[:1], mct]))


def test_figure_mc_refuses_a_repeated_column(mct: pd.DataFrame) -> None:
    with pytest.raises(ValueError, match=r"^table has more than one column"):
        ofs.figure_mc(pd.concat([mct, mct.iloc[:, :1]], axis=1))


@pytest.fixture(scope="module")
def lengths() -> pd.DataFrame:
    return wa.table_lengths({64: wa.length_study(64, runs=100), 1024: wa.length_study(1024, runs=100)})


def test_glue_lengths_refuses_a_row_not_a_length(lengths: pd.DataFrame) -> None:
    with pytest.raises(ValueError, match=r"^tab holds the row 'x', which is not an estimation length"):
        wa.glue_lengths(pd.concat([lengths, lengths.iloc[:1].set_axis(["x"], axis=0)]))


def test_glue_lengths_refuses_a_repeated_row(lengths: pd.DataFrame) -> None:
    with pytest.raises(ValueError, match=r"^tab holds the row"):
        wa.glue_lengths(pd.concat([lengths, lengths.iloc[:1]]))


def test_glue_typical_refuses_a_repeated_record() -> None:
    """T4: each record twice doubled every count."""
    cj = verdicts.sign_conjunction(np.ones((100, 4)), np.ones((100, 4)) + 0.1, "A", "B", 0)
    tt = wa.table_typical({"r": {"primary": cj}})
    assert wa.glue_typical(tt)["lec_wtyp_n"] == 1
    with pytest.raises(ValueError, match=r"^tab holds the row .* more than once"):
        wa.glue_typical(pd.concat([tt, tt]))


def test_crossing_table_refuses_a_row_not_a_method() -> None:
    cl = tr.closed_form_table(1.0, 1.0)
    tr.crossing_table(cl)
    with pytest.raises(ValueError, match=r"^closed holds the row '__extra', which is not a method"):
        tr.crossing_table(pd.concat([cl, cl.iloc[:1].set_axis(["__extra"], axis=0)]))


@settings(max_examples=40, deadline=None)
@given(st.lists(st.integers(0, 5), min_size=1, max_size=6), st.booleans())
def test_frame_unique_refuses_exactly_the_repeated_rows(keys: list[int], unique: bool) -> None:
    """The shared reader: with ``unique`` a table is accepted iff its row keys are distinct, and the refusal names
    the table and a repeated row; without it, rows are not judged."""
    tab = pd.DataFrame({"v": np.arange(len(keys), dtype=float)}, index=keys)
    repeated = len(set(keys)) < len(keys)
    if unique and repeated:
        with pytest.raises(ValueError, match=r"^tab holds the row \d+ more than once"):
            _frame(tab, "tab", ("v",), unique=unique)
    else:
        assert _frame(tab, "tab", ("v",), unique=unique) is tab


@settings(max_examples=40, deadline=None)
@given(st.lists(st.integers(0, 9), min_size=1, max_size=6, unique=True))
def test_frame_rows_refuses_exactly_an_unknown_row(keys: list[int]) -> None:
    tab = pd.DataFrame({"v": np.zeros(len(keys))}, index=keys)
    allowed = range(5)
    if all(k in allowed for k in keys):
        assert _frame(tab, "tab", ("v",), rows=allowed, rows_are="a key") is tab
    else:
        with pytest.raises(ValueError, match=r"^tab holds the row \d+, which is not a key"):
            _frame(tab, "tab", ("v",), rows=allowed, rows_are="a key")


def test_frame_refuses_a_read_column_twice() -> None:
    tab = pd.DataFrame([[1.0, 2.0]], columns=["v", "v"])
    with pytest.raises(ValueError, match=r"^tab has more than one column 'v'"):
        _frame(tab, "tab", ("v",))


# ---- M: latency_values --------------------------------------------------------------------------------------------

def test_latency_values_refuses_a_negative_latency() -> None:
    with pytest.raises(ValueError, match=r"^be\[1\.0\] must be non-negative"):
        trl.latency_values({0.3: 0.01, 1.0: -0.02}, 1.0)
    assert trl.latency_values({0.3: 0.01, 1.0: 0.0}, 1.0)["reg_be_ms"] == 0.0


def test_latency_values_noise_level_positive_as_documented() -> None:
    assert "a finite number > 0" in trl.latency_values.__doc__
    with pytest.raises(ValueError, match=r"^the noise level 0\.0 of be"):
        trl.latency_values({0.0: 0.01, 1.0: 0.02}, 1.0)


# ---- D: exact mappings and instants of exact_numbers --------------------------------------------------------------

def test_exact_numbers_refuses_instants_outside_the_record() -> None:
    """D3: t2 1e6 s past the record glued an extrapolation gain of 9.4e22."""
    ex = {n: sc.expected(n, 1.0) for n in sc.METHODS}
    with pytest.raises(ValueError, match=r"^t2 must lie within the record"):
        tr.exact_numbers(ex, 1.0, T2 + 1e6)
    with pytest.raises(ValueError, match=r"^t2 must hold at least 2 instants"):
        tr.exact_numbers(ex, 1.0, T2[:1])


def test_exact_mapping_is_quoted_as_given() -> None:
    """D1/D2 (decided): the mapping's noise level is the caller's; it is shown as given (documented)."""
    ex2 = {n: sc.expected(n, 2.0) for n in sc.METHODS}
    assert tr.exact_numbers(ex2, 1.0, T2)["reg_exact_two"] == ex2[TWO]
    mc = sc.monte_carlo([TWO, THREE], 1.0, 4, 0)
    assert tr.mc_table(mc, ex2).loc[TWO, tr.EXACT_MSE] == pytest.approx(round(ex2[TWO], 4))
    for fn in (tr.mc_table, tr.benchmark_table, tr.fig4_figure, tr.exact_numbers):
        assert "caller's" in fn.__doc__
