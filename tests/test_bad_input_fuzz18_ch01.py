"""Fuzz 18's cases of the book's tables, glue and style (class C) and of chapter 01 (classes D, E, F), by class.

Each refusal is a ValueError or TypeError naming the argument (issue 35); degenerate valid input gets the
documented result. The classes:

* a result or container read without a type check (``instance_of``): a Correction, a Comparison, a Ledger, a
  PairedStudy, an IPython shell, PNG bytes;
* paired arguments that must agree: the studies and the noise SDs of the Monte-Carlo table (same labels, one SD
  per sensor), the table, the studies and the run count of its glue, a sweep and its scales, the shapes of a
  score's hypotheses;
* a mapping that must hold given keys (methods, families, the comparisons the closing paragraphs quote) and
  indices that must be in range (a correction's sensor and observation, an observation order);
* a library's message passed on (matplotlib, numpy, pandas) or an inner name (``sigma`` for ``sigmas``);
* numbers that must be printable: NaN in a 0-d array, integers beyond the float range, huge exponents;
* empties and duplicates that used to collapse silently.
"""

from __future__ import annotations

import dataclasses
import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
import pytest  # noqa: E402

from fusion.book import glue as G  # noqa: E402
from fusion.book import style as S  # noqa: E402
from fusion.book import tables as T  # noqa: E402
from fusion.book.chapters import ofs  # noqa: E402
from fusion.book.chapters import ofs_audit as oa  # noqa: E402
from fusion.book.chapters import ofs_fair as of  # noqa: E402
from fusion.book.exact import ExactComparison  # noqa: E402
from fusion.book.ledger import Comparison, Ledger, Proposition, fmt  # noqa: E402
from fusion.scenarios import thermocouples  # noqa: E402

nan, inf = float("nan"), float("inf")
A100 = np.arange(100.0) + 1
HS, EQ = thermocouples.DEFAULT_SIGMAS, 1.0           # the chapter's two noise settings: ten SDs, one for all
Z3 = 900 + np.random.default_rng(0).normal(size=(3, 20, 5))


def _two():
    """Two small studies of the chapter (unequal, then equal noise; two runs each) and their SDs."""
    return {"hs": ofs.study(0, 2), "eq": ofs.study(1, 2, "equal")}, {"hs": HS, "eq": EQ}


def _cmp(a=A100, b=A100 + 1):
    return Comparison(a, b, "A", "B", "less", "m")


def _judged():
    c = _cmp()
    return {("yang-fig4-unaffected", "equal-noise"): c, ("yang-weights-reasonable", "primary"): c,
            ("yang-weights-reasonable", "failure"): c, ("yang-membership-free", "scale"): c}


def _mc_numbers(**change):
    studies, sigmas = _two()
    args = {"mc": ofs.mc_table(studies, sigmas), "studies": studies, "sigmas": sigmas, "n_runs": 2}
    args.update(change)
    return ofs.mc_numbers(**args)


def _swapped_mc():
    studies, sigmas = _two()
    return ofs.mc_table({"hs": studies["eq"], "eq": studies["hs"]}, {"hs": sigmas["eq"], "eq": sigmas["hs"]})


CASES = [
    # ---- C: tables, glue, style
    ("C2 glue_all 0-d NaN", lambda: G.glue_all({"k": np.array(nan)}, decimals=2), ValueError, "values"),
    ("C2 glue_all 0-d NaN, no decimals", lambda: G.glue_all({"k": np.array(nan)}), ValueError, "values"),
    ("C3 use_book_tables int", lambda: T.use_book_tables(5), TypeError, "shell"),
    ("C4 new_figure unknown keyword", lambda: S.new_figure(1, 1, bogus=3), TypeError, "bogus"),
    ("C5 new_figure nrows 0", lambda: S.new_figure(0), ValueError, "nrows"),
    ("C5 new_figure huge grid", lambda: S.new_figure(10**4, 10**4), ValueError, "nrows"),
    ("C5 new_figure ncols float", lambda: S.new_figure(1, 2.0), TypeError, "ncols"),
    ("C6 png_description str", lambda: S.png_description("abc"), TypeError, "data"),
    ("E13 fmt huge int", lambda: fmt(10**400), ValueError, "x"),
    ("E13 sci huge int", lambda: T.sci(-(10**400)), ValueError, "x"),
    ("power_of_ten huge exponent", lambda: T.power_of_ten("2", 10**30), ValueError, "exponent"),
    ("side_by_side name int", lambda: T.side_by_side([1.0], [1.0], [1], name=5), TypeError, "name"),
    ("side_by_side index_name None", lambda: T.side_by_side([1.0], [1.0], [1], index_name=None), TypeError,
     "index_name"),
    ("side_by_side unhashable label", lambda: T.side_by_side([1.0], [1.0], [[1]]), TypeError, "index"),
    ("side_by_side repeated label", lambda: T.side_by_side([1.0, 2.0], [1.0, 2.0], [1, 1]), ValueError, "index"),
    # ---- D: a result or container read unchecked
    ("D1 figure_errors key not a method", lambda: ofs.figure_errors({"a": [1.0, 2.0]}), ValueError, "errors"),
    ("figure_errors empty", lambda: ofs.figure_errors({}), ValueError, "errors"),
    ("figure_errors not a mapping", lambda: ofs.figure_errors([1.0]), TypeError, "errors"),
    ("D2 describe int", lambda: oa.describe(5), TypeError, "c"),
    ("D2 describe unknown kind", lambda: oa.describe(oa.Correction(1, 1, 900.0, "typo")), ValueError, "Correction.kind"),
    ("D18 explain obs beyond Table 1",
     lambda: oa.explain(oa.Correction(1, 999, 900.0, "other value"), "correct"), ValueError, "correction.obs"),
    ("D18 explain sensor negative",
     lambda: oa.explain(oa.Correction(-5, 1, 900.0, "other value"), "correct"), ValueError,
     "Correction.sensor"),
    ("D18 explain 'none' with an observation",
     lambda: oa.explain(dataclasses.replace(oa.corrections()[0], obs=999), "correct"), ValueError,
     "Correction.obs"),
    ("D8 mc_table labels differ", lambda: ofs.mc_table({"hs": ofs.study(0, 2)}, {"eq": HS}), ValueError, "sigmas"),
    ("D9 mc_table study an int", lambda: ofs.mc_table({"hs": 5}, {"hs": HS}), TypeError, "studies"),
    ("D10 mc_numbers one study", lambda: _mc_numbers(studies={"hs": ofs.study(0, 2)}), ValueError, "studies"),
    ("D11 mc_numbers empty table", lambda: _mc_numbers(mc=pd.DataFrame()), ValueError, "mc"),
    ("mc_numbers mc not a frame", lambda: _mc_numbers(mc=5), TypeError, "mc"),
    ("D12 comparison_numbers unknown field", lambda: ofs.comparison_numbers(_cmp(), "k", ("nope",)), ValueError,
     "fields"),
    ("D13 comparison_numbers Proposition", lambda: ofs.comparison_numbers(Proposition(True, "x"), "k"), TypeError,
     "comparison"),
    ("D14 comparison_numbers ExactComparison",
     lambda: ofs.comparison_numbers(ExactComparison(1.0, 2.0, "A", "B", "less", "m"), "k"), TypeError, "comparison"),
    ("D15 ledger_numbers int", lambda: ofs.ledger_numbers(5), TypeError, "ledger"),
    ("verdict_table int", lambda: ofs.verdict_table(5), TypeError, "ledger"),
    ("D17 closing_numbers judged empty",
     lambda: ofs.closing_numbers(ofs.study(0, 2), ofs.study(1, 2, "equal"), ofs.weight_study(0, 2), {}, 0.05),
     ValueError, "judged"),
    ("closing_numbers judged entry not a Comparison",
     lambda: ofs.closing_numbers(ofs.study(0, 2), ofs.study(1, 2, "equal"), ofs.weight_study(0, 2),
                                 {**_judged(), ("yang-membership-free", "scale"): Proposition(True, "x")}, 0.05),
     TypeError, "judged"),
    ("closing_numbers weights int",
     lambda: ofs.closing_numbers(ofs.study(0, 2), ofs.study(1, 2, "equal"), 5, _judged(), 0.05), TypeError,
     "weights"),
    ("closing_numbers study_eq int",
     lambda: ofs.closing_numbers(ofs.study(0, 2), 5, ofs.weight_study(0, 2), _judged(), 0.05), TypeError,
     "study_eq"),
    ("closing_numbers margin NaN",
     lambda: ofs.closing_numbers(ofs.study(0, 2), ofs.study(1, 2, "equal"), ofs.weight_study(0, 2), _judged(), nan),
     ValueError, "relative_margin"),
    # ---- E: accepted before, giving NaN or a plausible wrong number
    ("E2 explain truth NaN", lambda: oa.explain(oa.corrections()[0], "correct", truth=nan), ValueError, "truth"),
    ("E6 mc_table three SDs for ten sensors", lambda: ofs.mc_table({"hs": ofs.study(0, 2)}, {"hs": np.ones(3)}),
     ValueError, "sigmas"),
    ("E7 mc_numbers n_runs not the studies'", lambda: _mc_numbers(n_runs=999), ValueError, "n_runs"),
    ("E8 mc_numbers mc of the studies swapped", lambda: _mc_numbers(mc=_swapped_mc()), ValueError, "mc"),
    ("E8 mc_numbers sigmas in another order", lambda: _mc_numbers(sigmas={"eq": EQ, "hs": HS}), ValueError, "sigmas"),
    ("E8 mc_numbers studies swapped with their labels",
     lambda: ofs.mc_numbers(ofs.mc_table({"eq": ofs.study(1, 2, "equal"), "hs": ofs.study(0, 2)}, {"eq": EQ, "hs": HS}),
                            {"eq": ofs.study(1, 2, "equal"), "hs": ofs.study(0, 2)}, {"eq": EQ, "hs": HS}, 2),
     ValueError, "sigmas"),
    ("E9 run_program float order",
     lambda: oa.run_program(ofs.corrected_table1().T, "correct", order=np.array([0.5, 1, 2, 3, 4, 5])), TypeError,
     "order"),
    ("E9 run_program order of another length",
     lambda: oa.run_program(ofs.corrected_table1().T, "correct", order=[0, 1, 2]), ValueError, "order"),
    ("E9 explain float order", lambda: oa.explain(oa.corrections()[0], "correct", order=[0.0, 1, 2, 3, 4, 5]),
     TypeError, "order"),
    ("E12 figure_scale default NaN", lambda: ofs.figure_scale([1.0, 2.0], {"a": [1.0, 2.0]}, nan), ValueError,
     "default"),
    ("figure_scale three cases", lambda: ofs.figure_scale([1.0, 2.0], {k: [1.0, 2.0] for k in "abc"}), ValueError,
     "sweep"),
    ("figure_scale scale 0", lambda: ofs.figure_scale([0.0, 2.0], {"a": [1.0, 2.0]}), ValueError, "scales"),
    # ---- F: a refusal naming another name, or a library's message
    ("F8 score ten observations", lambda: oa.score(np.ones((1, 10)), np.ones((1, 10))), ValueError, "mean"),
    ("F9 mc_table negative SDs", lambda: ofs.mc_table({"hs": ofs.study(0, 2)}, {"hs": -np.ones(10)}), ValueError,
     "sigmas"),
    ("F10 mc_table empty", lambda: ofs.mc_table({}, {}), ValueError, "studies"),
    ("F11 comparison_numbers infinite run",
     lambda: ofs.comparison_numbers(_cmp(np.r_[A100[:99], inf], A100), "k"), ValueError, "comparison"),
    ("F12 family_mae unknown family", lambda: ofs.family_mae(Z3, {"x": "nope"}), ValueError, "families"),
    ("family_values unknown family", lambda: ofs.family_values(Z3[0], "nope"), ValueError, "family"),
    ("F13 figure_scale sweep shorter", lambda: ofs.figure_scale([1.0, 2.0], {"a": [1.0]}), ValueError, "sweep"),
    ("F14 figure_errors 2-D errors", lambda: ofs.figure_errors({"mean": [[1.0, 1.0]]}), ValueError, "errors"),
    # ---- the same shapes elsewhere in chapter 01: a table or a study read unchecked
    ("figure_mc int", lambda: ofs.figure_mc(5), TypeError, "table"),
    ("figure_mc empty", lambda: ofs.figure_mc(pd.DataFrame()), ValueError, "table"),
    ("figure_mc one case of a setting",
     lambda: ofs.figure_mc(ofs.mc_table({"eq": ofs.study(1, 2, "equal")}, {"eq": EQ}).iloc[:1]), ValueError, "table"),
    ("fault_shapes_table int", lambda: of.fault_shapes_table(5), TypeError, "study"),
    ("fault_shapes_table empty", lambda: of.fault_shapes_table({}), ValueError, "study"),
    ("fault_shapes_table lacking methods", lambda: of.fault_shapes_table({"a": {"mean": np.ones(3)}}), ValueError,
     "study"),
    ("fault_shapes_table runs differ",
     lambda: of.fault_shapes_table({"a": {"optimal_fusion_set": np.ones(3), "mean": np.ones(2), "median": np.ones(3),
                                          "ew_variance": np.ones(3)}}), ValueError, "study"),
    # ---- debatable, settled: empties and duplicates
    ("fair_errors repeated method", lambda: of.fair_errors(Z3, np.ones(5), methods=("mean", "mean")), ValueError,
     "methods"),
    ("fair_errors no method", lambda: of.fair_errors(Z3, np.ones(5), methods=()), ValueError, "methods"),
    ("fair_study no point", lambda: of.fair_study(0, 2, 2, sizes=(), counts=(), spreads=(), opposite=()), ValueError,
     "sizes"),
    ("fair_study repeated size", lambda: of.fair_study(0, 2, 2, sizes=(1, 1.0)), ValueError, "sizes"),
    ("alpha_methods empty", lambda: ofs.alpha_methods(()), ValueError, "alphas"),
    ("eq9_readings no epoch", lambda: ofs.eq9_readings(Z3[0], 0), ValueError, "weight_epochs"),
]


@pytest.mark.parametrize("label, call, exc, name", CASES, ids=[c[0] for c in CASES])
def test_refused_by_name(label, call, exc, name):
    try:
        with pytest.raises(exc) as info:
            call()
    finally:
        plt.close("all")
    assert re.search(rf"(?<![A-Za-z0-9_]){re.escape(name)}(?![A-Za-z0-9_])", str(info.value)), str(info.value)


# ---- documented results of degenerate valid input


def test_integral_index_keeps_huge_whole_floats():
    """C1: a whole float beyond the exact integers stays a float label (it became int64 min before)."""
    out = T.integral_index(pd.DataFrame({"a": [1, 2, 3]}, index=[1.0, 1e300, -2.0 ** 53]))
    assert out.index.dtype.kind == "f" and out.index[1] == 1e300
    small = T.integral_index(pd.DataFrame({"a": [1, 2]}, index=[3.0, -20.0]))
    assert small.index.dtype.kind == "i" and list(small.index) == [3, -20]


def test_glue_all_checks_every_number_before_gluing(monkeypatch):
    glued = []
    monkeypatch.setattr("myst_nb.glue", lambda *a, **k: glued.append(a))
    with pytest.raises(ValueError, match=r"values\['bad'\]"):
        G.glue_all({"ok": 1.0, "bad": np.array(inf)})
    assert glued == []


def test_printable_integers_and_exponents():
    assert fmt(10**300) == str(10**300) and T.sci(-(10**20)) == str(-(10**20))   # within the float range: exact
    assert T.power_of_ten("2", 400) == "2×10⁴⁰⁰"
    assert T.cell_text("1e999") == "1e999"          # beyond any number's exponent: left as written


def test_eq9_readings_constant_readings_give_zero_differences():
    """E1: identical readings make every balance degree infinite; the package's limit gives equal weights."""
    r = ofs.eq9_readings(np.full((20, 5), 900.0))
    assert r == {"n_sets": 20, "form_maxdiff": 0.0, "self_maxdiff": 0.0, "self_valdiff": 0.0}


def test_eq9_readings_unchanged_on_ordinary_readings():
    z = thermocouples.simulate(np.random.default_rng(2012), n_samples=50)
    r = ofs.eq9_readings(z, weight_epochs=None)
    assert r["n_sets"] > 0 and 0 < r["self_maxdiff"] < 1 and r["form_maxdiff"] < 1e-12


def test_empty_ledger_gives_empty_table_and_no_numbers():
    """D16: an empty ledger (valid) gives a verdict table with the columns and no row, and no glue numbers."""
    t = ofs.verdict_table(Ledger("yang2012optimal"))
    assert t.empty and list(t.columns) == ["whose claim", "where", "status", "robustness"] and t.index.name == "id"
    assert ofs.ledger_numbers(Ledger("yang2012optimal")) == {}
    with pytest.raises(ValueError, match="fields"):
        ofs.ledger_numbers(Ledger("yang2012optimal"), fields={"yang-median-total": ("status",)})


def test_mc_numbers_of_matching_arguments():
    studies, sigmas = _two()
    out = _mc_numbers()
    mc = ofs.mc_table(studies, sigmas)
    assert out["ofs_n_runs"] == 2
    assert out["ofs_mc_eq_clean_ofs"] == T.rounded(mc.loc[("eq", mc.index[0][1]), mc.columns[0]], 3)


def test_mc_table_takes_one_sd_or_one_per_sensor():
    studies, _ = _two()
    one = ofs.mc_table({"eq": studies["eq"]}, {"eq": 1.0})
    ten = ofs.mc_table({"eq": studies["eq"]}, {"eq": np.ones(10)})
    pd.testing.assert_frame_equal(one, ten)


def test_comparison_numbers_keeps_finite_fields_of_an_infinite_run():
    """Only the kept numbers must be finite: the runs of a comparison with an infinite run are still glued."""
    c = _cmp(np.r_[A100[:99], inf], A100)
    assert ofs.comparison_numbers(c, "k", ("runs",)) == {"k_runs": 100}


def test_fair_study_runs_a_single_sweep():
    """An empty sweep is not run (documented): the study holds the other sweeps' points only."""
    st = of.fair_study(0, 2, 2, sizes=(), counts=(0,), spreads=(), opposite=(), methods=("mean",))
    assert list(st.mae) == [(of.COUNT, 0.0)]


def test_png_description_of_other_bytes_is_none():
    assert S.png_description(b"GIF89a") is None and S.png_description(bytearray(b"")) is None


def test_use_book_tables_without_shell_outside_ipython():
    assert T.use_book_tables() is None
