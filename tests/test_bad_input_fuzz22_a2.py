"""Fuzz 22a's bad input of the shared readers and the book layer (classes L, C, Q, S and debatables) (issue 35).

Each reproducer of ``/work/tmp/fuzz22a/report.md`` for these classes must raise a :class:`ValueError` (a
:class:`TypeError` for a wrong type) whose message names the argument, or run in time linear in its input. The fixes
are by class:

* L: the shared array and scalar readers of ``fusion._validation`` refuse, by name and without a RuntimeWarning, a
  value that does not survive its conversion to float64 (a ``np.longdouble`` or Decimal beyond the float range would
  become an infinity, a non-zero one below it an exact 0); the book's formatters read numbers through them;
* C: ``Comparison.written`` reads ``x`` by the shared real-number reader;
* Q: ``recommend.check``'s repeated ids, a claim record's reading keys, ``Ledger.add``'s ids and
  ``tidy_table_html`` are linear (a Counter, sets, one pass);
* S: ``stability.summarise`` refuses two results of one task and a result of a seed outside ``seed_list``.

Debatables decided: D1 ``glue_all`` looks into lists, tuples, sets, mappings, Series, object and structured arrays
(refused: NaN printed in the book); D2 ``seed_stability`` takes any mapping; D3 ``ExactComparison`` takes the margin
types ``Comparison`` takes (a 0-d array or a Decimal is a TypeError; a float32 relative margin next to a float64
margin disagrees, documented); D4 one name for both methods is refused; D6 a longdouble below the float range is
refused, as a Decimal is (class L); D9 an empty or repeated assumption or critique label is refused.
"""

from __future__ import annotations

import dataclasses
import re
import time
import types
import warnings
from decimal import Decimal

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings, strategies as st

from fusion._frozen import ReadOnlyMapping
from fusion._validation import _numeric, _real_number
from fusion.book import glue, rulebook as R, stability as S, tables as T
from fusion.book import ledger as L
from fusion.book.exact import ExactComparison
from fusion.book.recommend import check

nan = float("nan")
WIDE = np.finfo(np.longdouble).max > np.finfo(np.float64).max
wide = pytest.mark.skipif(not WIDE, reason="np.longdouble is float64 on this platform")


def _named(exc: type[Exception], name: str) -> object:
    return pytest.raises(exc, match=rf"(?<![\w.]){re.escape(name)}(?![\w])")


def _ld(text: str) -> np.longdouble:
    return np.longdouble(text)


# --- L: a number that does not survive the cast to float64 -------------------------------------------------------

beyond = st.builds(lambda m, e, s: _ld(f"{s}{m}e{e}"), st.integers(1, 9), st.integers(309, 4900), st.sampled_from("+-"))
below = st.builds(lambda m, e, s: _ld(f"{s}{m}e-{e}"), st.integers(1, 9), st.integers(330, 4900), st.sampled_from("+-"))


@wide
@settings(max_examples=60, deadline=None)
@given(beyond | below, st.sampled_from(["longdouble", "object"]))
def test_l_array_reader_refuses_a_longdouble_outside_the_float_range(v: np.longdouble, kind: str) -> None:
    a = np.array([1.0, v, 2.0], dtype=np.longdouble if kind == "longdouble" else object)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no "overflow encountered in cast" from the package
        with _named(ValueError, "x") as info:
            _numeric(a, "x")
    assert "float range" in str(info.value)


@wide
@settings(max_examples=60, deadline=None)
@given(beyond | below)
def test_l_scalar_reader_and_the_formatters_refuse_it(v: np.longdouble) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for f, name in ((lambda: _real_number(v, "x"), "x"), (lambda: T.sci(v), "x"), (lambda: L.fmt(v), "x"),
                        (lambda: T.rounded(v), "value")):
            if abs(v) < 1 and name == "value":  # rounded to decimals, one below the float range is exactly 0.0
                assert f() == 0.0  # (fuzz 45 D1)
                continue
            with _named(ValueError, name) as info:
                f()
            assert "float range" in str(info.value) and "finite" not in str(info.value)


@wide
def test_l_a_longdouble_inside_the_float_range_or_not_finite_reads_as_before() -> None:
    assert _real_number(_ld("1.5"), "x") == 1.5 and T.sci(_ld("1.5e10")) == T.sci(1.5e10)
    assert T.sci(_ld("inf")) == T.sci(float("inf")) and T.sci(_ld("nan")) == T.sci(nan)
    out = _numeric(np.array([_ld("1.5"), _ld("inf"), _ld("0")]), "x")
    assert out.dtype == np.float64 and out[0] == 1.5 and out[1] == np.inf and out[2] == 0.0
    assert _numeric(np.array([Decimal("Infinity"), 2], dtype=object), "x")[0] == np.inf


def test_l_an_object_array_with_a_decimal_beyond_the_float_range_is_refused() -> None:
    with _named(ValueError, "x"):
        _numeric(np.array([Decimal("1e400"), 1.0], dtype=object), "x")


@wide
def test_l_the_rulebook_and_comparison_refuse_it_by_name() -> None:
    big = np.full(200, _ld("1e4000"))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with _named(ValueError, "a"):
            R.judge_paired(big, np.ones(200), "less", 0.1)
        with _named(ValueError, "d"):
            R.median_interval(big[:20])
        with _named(ValueError, "a"):
            L.Comparison(big, np.ones(200), "A", "B", "less", "mse", seed=1)
        with _named(ValueError, "a"):
            ExactComparison(_ld("1e4000"), 2.0, "A", "B", "less", "m")


# --- C: Comparison.written ---------------------------------------------------------------------------------------

def _cmp() -> L.Comparison:
    a = np.random.default_rng(0).normal(size=200)
    return L.Comparison(a, a + 0.2, "A", "B", "less", "mse", seed=1)


@pytest.mark.parametrize("x", ["abc", None, [1.0], 1 + 2j, np.array([1.0, 2.0]), b"1", True, np.bool_(False)])
def test_c_written_refuses_a_non_number_naming_x(x: object) -> None:
    with _named(TypeError, "x"):
        _cmp().written(x)


@pytest.mark.parametrize("x", [10**400, Decimal("1e400")] + ([_ld("1e4000"), _ld("1e-4000")] if WIDE else []))
def test_c_written_refuses_a_number_outside_the_float_range_naming_x(x: object) -> None:
    with _named(ValueError, "x"):
        _cmp().written(x)


def test_c_written_keeps_numbers_and_the_words_for_non_finite() -> None:
    c = _cmp()
    assert c.written(0.2) == c.written(np.float64(0.2)) == c.written(np.array(0.2)) != ""
    assert c.written(1) == c.written(1.0)
    assert c.written(nan) == L.fmt(nan) and c.written(float("inf")) == L.fmt(float("inf"))


# --- Q: linear checks --------------------------------------------------------------------------------------------

def _cpu(f: object) -> float:
    t = time.process_time()
    try:
        f()  # type: ignore[operator]
    except ValueError:
        pass
    return time.process_time() - t


def test_q_recommend_check_is_linear_in_the_records() -> None:
    recs = [{"id": f"r-{i}", "status": "reproduced"} for i in range(100_000)] + [{"id": "r-0", "status": "reproduced"}]
    with pytest.raises(ValueError, match=r"^records must not repeat an id, got \['r-0'\]"):
        check(recs)
    assert _cpu(lambda: check(recs)) < 5.0  # 0.03 CPU-s; a count per id took 17 s at 40 000 records


def test_q_claim_record_readings_are_checked_in_linear_time() -> None:
    from fusion.book import claims as C
    cf = C.load_all()["lecture003"]
    spec = next(s for s in cf.records if len(s.readings) > 1)
    r1 = spec.readings[1]
    rs = (spec.readings[0],) + tuple(dataclasses.replace(r1, key=f"k-{i}") for i in range(48_000))
    assert _cpu(lambda: dataclasses.replace(spec, readings=rs)) < 5.0  # 0.01 CPU-s; a scan per key took ~15 s
    with pytest.raises(ValueError, match="duplicate key"):
        dataclasses.replace(spec, readings=rs + (rs[-1],))


def test_q_ledger_add_is_linear_and_still_refuses_a_repeated_id() -> None:
    c = L.Claim(id="t-0", source="yang2012optimal", where="w", claim="c", published="p",
                evidence=L.Proposition(True, "yes"), link="x")
    cs = [dataclasses.replace(c, id=f"t-{i}") for i in range(20_000)]
    led = L.Ledger("yang2012optimal")

    def add_all() -> None:
        for x in cs:
            led.add(x)

    assert _cpu(add_all) < 3.0  # 0.01 CPU-s; a scan per add is 2·10⁸ comparisons
    with pytest.raises(ValueError, match="duplicate claim id 't-7'"):
        led.add(cs[7])
    other = L.Ledger("yang2012optimal")
    other.claims.append(cs[0])  # the public list changed directly: still seen
    with pytest.raises(ValueError, match="duplicate claim id 't-0'"):
        other.add(cs[0])
    other.add(cs[1])
    assert [x.id for x in other.claims] == ["t-0", "t-1"]


_CELL = re.compile(r"(<t[dh]\b[^>]*>)(.*?)(</t[dh]>)", re.S)
_TAG = re.compile(r"(<[^>]*>)")


def _tidy_reference(html: str) -> str:
    """The former regular-expression implementation (quadratic on unclosed cells): the meaning to keep."""
    def cell(m: re.Match[str]) -> str:
        return m[1] + "".join(p if p.startswith("<") else T.cell_text(p) for p in _TAG.split(m[2])) + m[3]
    return _CELL.sub(cell, html)


ATOMS = ["<td>", "</td>", '<th class="x">', "</th>", "<", ">", "1e-5", " 2.5e+07 ", "-", "abc", "\n", "<td", "</t",
         "d>", "<b>", "</b>", "nan", "1.0e3", "<tr>", "-0.0"]


@settings(max_examples=300, deadline=None)
@given(st.lists(st.sampled_from(ATOMS), max_size=40))
def test_q_tidy_table_html_keeps_its_meaning(parts: list[str]) -> None:
    html = "".join(parts)
    assert T.tidy_table_html(html) == _tidy_reference(html)


def test_q_tidy_table_html_is_linear_on_unclosed_cells() -> None:
    df = pd.DataFrame({"a": [1e-5, 2.5e7, nan], "b": ["x", "1e5", "-3"]})
    for html in (df.to_html(), df.style.to_html()):
        assert T.tidy_table_html(html) == _tidy_reference(html)
    for html in ("<td>" * 100_000, "<td" * 100_000, "<td>" + "<" * 100_000 + "</td>"):
        assert _cpu(lambda: T.tidy_table_html(html)) < 2.0  # 0.00 CPU-s; '<td>' * 40 000 took 27 s


# --- S: stability.summarise ------------------------------------------------------------------------------------

SEEDS = [11, 22]


def _task(seed: int, scaled: bool = False) -> S.Task:
    return S.Task("lecture003", "rec", "primary", R.READING_KINDS[0], seed, 100, scaled)


def test_s_summarise_reads_one_result_per_task() -> None:
    rs = [S.TaskResult(_task(s), "reproduced", 1.0) for s in SEEDS] + [S.TaskResult(_task(11, True), "reproduced", 1.0)]
    out = S.summarise(rs, SEEDS, {"rec": "reproduced"})["rec"]
    assert out["reseeds"] == ["reproduced", "reproduced"] and out["k"] == 2 and not out["flag"]


def test_s_summarise_refuses_two_results_of_one_task() -> None:
    r, r2 = S.TaskResult(_task(11), "reproduced", 1.0), S.TaskResult(_task(11), "contradicted", 1.0)
    for pair in ([r, r2], [r2, r], [r, r]):
        with pytest.raises(ValueError, match=r"^results\[1\] and results\[0\] are two results of one task"):
            S.summarise(pair, SEEDS, {"rec": "reproduced"})


def test_s_summarise_refuses_a_result_of_another_seed() -> None:
    with pytest.raises(ValueError, match=r"^results\[0\] is of seed 33, which is not in seed_list"):
        S.summarise([S.TaskResult(_task(33), "reproduced", 1.0)], SEEDS, {"rec": "reproduced"})


# --- debatables ------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("value", [[1.0, nan], (1.0, nan), [[nan]], {"a": nan}, {1.0, nan},
                                   np.array([nan], dtype=object), pd.Series([nan]), pd.Index([1.0, nan]),
                                   np.array([(1.0, nan)], dtype=[("a", "f8"), ("b", "f8")]), [pd.NA], (Decimal("NaN"),)])
def test_d1_glue_all_refuses_nan_inside_a_container(value: object) -> None:
    with pytest.raises(ValueError, match=r"^values\['k'\] must be finite"):
        glue.glue_all({"k": value})


def test_d1_finite_containers_and_tables_with_missing_cells_pass_the_check() -> None:
    loop: list[object] = [1.0]
    loop.append(loop)
    for v in ([1.0, "x", (2, 3)], pd.Series([1.0, 2.0]), pd.DataFrame({"a": [nan]}), loop, {"a": 1},
              np.array([1, "x"], dtype=object)):
        assert glue._finite(v)


def test_d2_seed_stability_takes_any_mapping() -> None:
    from fusion.scenarios.lecture_weighting import benchmark, seed_stability
    bench = benchmark(seeds=(1, 2), runs=2, samples=20, fault_from=10)
    want = seed_stability(bench)
    for m in (ReadOnlyMapping(bench), types.MappingProxyType(bench),
              {k: types.MappingProxyType(v) for k, v in bench.items()}):
        got = seed_stability(m)
        assert (got.n_stable, got.n_sig, got.n_rev) == (want.n_stable, want.n_sig, want.n_rev)
    with _named(TypeError, "results"):
        seed_stability([1, 2])


@pytest.mark.parametrize("margin", [np.array(0.1), Decimal("0.1"), True, "0.1"])
def test_d3_exact_comparison_takes_comparison_margin_types(margin: object) -> None:
    e = ExactComparison(1.0, 2.0, "A", "B", "less", "m")
    with _named(TypeError, "margin"):
        e.with_margin(margin)
    with _named(TypeError, "relative_margin"):
        e.with_margin(None, margin)
    a = np.random.default_rng(0).normal(size=200)
    with _named(TypeError, "margin"):
        L.Comparison(a, a + 1, "A", "B", "less", "m", margin=margin)


def test_d3_numpy_floats_are_margins_and_a_float32_relative_margin_disagrees() -> None:
    e = ExactComparison(1.0, 2.0, "A", "B", "less", "m")
    assert e.with_margin(np.float64(0.1)).margin == 0.1 and e.with_margin(1).margin == 1.0
    with pytest.raises(ValueError, match="disagree"):  # np.float32(0.05) is 0.0500000007: documented
        ExactComparison(1.0, 2.0, "A", "B", "less", "m", margin=np.float64(0.1), relative_margin=np.float32(0.05))


def test_d4_one_name_for_both_methods_is_refused() -> None:
    a = np.random.default_rng(0).normal(size=200)
    with _named(ValueError, "b_name"):
        L.Comparison(a, a + 1, "A", "A", "less", "m")
    with _named(ValueError, "b_name"):
        ExactComparison(1.0, 2.0, "A", " A ", "less", "m")
    assert L.Comparison(a, a + 1, "A", "a", "less", "m").b_name == "a"


@pytest.mark.parametrize("kw, name", [(dict(critiques=("",)), "critiques[0]"), (dict(assumptions=("a", " ")), "assumptions[1]"),
                                      (dict(assumptions=("a", "a")), "assumptions"), (dict(critiques=("x", "x")), "critiques")])
def test_d9_claim_refuses_empty_or_repeated_assumptions_and_critiques(kw: dict[str, object], name: str) -> None:
    with _named(ValueError, name):
        L.Claim(id="t-1", source="yang2012optimal", where="w", claim="c", published="p",
                evidence=L.Proposition(True, "yes"), link="x", **kw)  # type: ignore[arg-type]
    ok = L.Claim(id="t-1", source="yang2012optimal", where="w", claim="c", published="p",
                 evidence=L.Proposition(True, "yes"), link="x", assumptions=("a", "b"), critiques=("x",))
    assert ok.assumptions == ("a", "b")
