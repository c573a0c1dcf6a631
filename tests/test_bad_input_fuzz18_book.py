"""Fuzz 18, classes A and B (issue 35): the rulebook, the evidence classes, claim files and the ledger store.

Each test is a reproducer of the fuzz report (``A1``-``A14``, ``B1``-``B12`` and the rulebook / claim-file items of
its "Debatable" list) with the refusal or documented result the fix gives. The rules are shared: paired runs are
checked by one function of the rulebook (``_paired_runs``) for :func:`judge_paired` and ``Comparison``, an
``infinite_mean`` by another, claim-file margins and evidence functions by ``claims._check_margin`` and
``claims._evidence_function``.
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest
import yaml

from fusion.book import claims as C
from fusion.book import exact as E
from fusion.book import ledger as L
from fusion.book import rulebook as RB

inf, nan = math.inf, math.nan
A100 = np.arange(100.0) + 1
CLAIMS = Path(__file__).resolve().parents[1] / "book" / "claims"
YANG = CLAIMS / "yang2012optimal.yaml"


# --------------------------------------------------------------------------- A1-A3: an undefined median (R3)
def test_a1_median_interval_refuses_an_undefined_median():
    with pytest.raises(ValueError, match=r"\bd\b.*no median"):
        RB.median_interval([-inf] * 3 + [inf] * 3)


def test_a1_median_interval_infinite_but_defined_median():
    # an odd count: the middle value is the median, infinite or not
    med, lo, hi = RB.median_interval([-inf] * 3 + [inf] * 4)
    assert med == inf and lo == -inf and hi == inf


@pytest.mark.parametrize("a, b", [
    ([inf] * 50 + [1.0] * 50, [1.0] * 50 + [inf] * 50),   # A2: two middle differences -inf and +inf
    ([inf] * 100, [inf] * 100),                           # debatable: both infinite in every run
    ([inf] * 96 + list(range(1, 5)), [inf] * 96 + list(range(2, 6))),  # 4 runs with a difference: < 6
])
def test_a2_undefined_median_cannot_be_checked(a, b):
    for claim in ("less", "greater", "equal"):
        j = L.Comparison(a, b, "A", "B", claim, "m").judgement()
        assert (j.status, j.rule, j.statistic, j.region) == ("cannot be checked", "R3", "median", "undecided")
        assert math.isnan(j.estimate) and math.isnan(j.low) and math.isnan(j.high)


def test_a2_undefined_median_summary_and_record():
    c = L.Comparison([inf] * 50 + [1.0] * 50, [1.0] * 50 + [inf] * 50, "A", "B", "less", "m")
    assert "median difference undefined: cannot be checked (R3)" in c.summary()
    d = c.to_dict()
    assert d["difference"] is None and d["ci_low"] is None and d["ci_high"] is None


def test_a3_judge_paired_undefined_median():
    j = RB.judge_paired([inf] * 10 + [1.0] * 10, [1.0] * 10 + [inf] * 10, "less", 0.1)
    assert j.status == "cannot be checked" and j.rule == "R3" and math.isnan(j.estimate)


def test_a3_both_infinite_runs_left_out_of_the_median():
    # 10 runs both infinite (no difference), 90 with A lower by 1: the median of the 90 decides (R3)
    a = [inf] * 10 + [1.0] * 90
    b = [inf] * 10 + [2.0] * 90
    j = RB.judge_paired(a, b, "less", 0.1)
    assert (j.status, j.rule, j.statistic, j.estimate) == ("reproduced", "R3", "median", -1.0)


def test_a3_closed_form_infinite_means_tie_is_judged_by_r3():
    # both means declared infinite, identical finite runs: R3's median (0), not R2's mean
    j = RB.judge_paired(A100, A100, "equal", 0.1, ("a", "b"))
    assert (j.status, j.rule, j.statistic, j.estimate) == ("reproduced", "R3", "median", 0.0)


def test_judgement_refuses_nan_unless_cannot_be_checked():
    j = RB.judge_paired(A100, A100 + 1, "less", 0.1)
    with pytest.raises(ValueError, match="estimate"):
        dataclasses.replace(j, estimate=nan)
    with pytest.raises(ValueError, match="runs"):
        dataclasses.replace(j, runs=-3)
    with pytest.raises(ValueError, match="status"):
        dataclasses.replace(j, status="nope")
    with pytest.raises(TypeError, match="heavy"):
        dataclasses.replace(j, heavy=1)
    assert dataclasses.replace(j, status="cannot be checked", estimate=nan).status == "cannot be checked"


# --------------------------------------------------------------------------- A4-A6: infinite_mean
@pytest.mark.parametrize("bad, exc", [(None, TypeError), (5, TypeError), ([["a"]], TypeError), ("ab", TypeError),
                                      (("c",), ValueError)])
def test_a4_a6_infinite_mean(bad, exc):
    with pytest.raises(exc, match="infinite_mean"):
        RB.judge_paired(A100, A100 + 1, "less", 0.1, bad)
    with pytest.raises(exc, match="infinite_mean"):
        L.Comparison(A100, A100 + 1, "A", "B", "less", "m", infinite_mean=bad)


def test_infinite_mean_list_accepted():
    assert L.Comparison(A100, A100 + 1, "A", "B", "less", "m", infinite_mean=["a"]).infinite_mean == ("a",)


# --------------------------------------------------------------------------- A7-A8: shape (runs,)
def test_a7_judge_paired_two_dimensional():
    with pytest.raises(ValueError, match=r"\ba must be 1-D"):
        RB.judge_paired(np.ones((4, 5)), np.zeros(20), "less", 0.1)
    with pytest.raises(ValueError, match=r"\bb must be 1-D"):
        RB.judge_paired(np.zeros(20), np.ones((4, 5)), "less", 0.1)


def test_a8_comparison_two_dimensional():
    with pytest.raises(ValueError, match=r"\ba must be 1-D"):
        L.Comparison(A100.reshape(10, 10), A100 + 1, "A", "B", "less", "m")


# --------------------------------------------------------------------------- A9-A10: counted / record_status
@pytest.mark.parametrize("bad, exc", [(-1, ValueError), ("x", TypeError), (0, ValueError)])
def test_a9_record_status_primary_runs_without_readings(bad, exc):
    with pytest.raises(exc, match="primary_runs"):
        RB.record_status("reproduced", [], bad, False)


@pytest.mark.parametrize("bad, exc", [(5, TypeError), ("nope", ValueError)])
def test_a10_counted_status(bad, exc):
    with pytest.raises(exc, match="status"):
        RB.counted("open-choice", 200, 100, bad)


def test_a10_counted_valid_status():
    assert RB.counted("open-choice", 200, 100, "cannot be checked") == (False, "cannot be checked")
    assert RB.counted("open-choice", 200, 100, None) == (True, "")


# --------------------------------------------------------------------------- A11: Hill of any magnitude
def test_a11_hill_no_overflow():
    x = np.array([1e308] * 5 + [1e-308] * 10)
    k = 10
    top = np.sort(x)[::-1][: k + 1]
    want = 1.0 / np.mean(np.log(top[:k]) - np.log(top[k]))
    assert RB.hill_tail_index(x) == pytest.approx(want, rel=1e-12)
    assert 0.0 < RB.hill_tail_index(x) < 0.01


# --------------------------------------------------------------------------- A12-A14: constructors check
def test_a12_exact_comparison_magnitude_at_construction():
    with pytest.raises(ValueError, match=r"^b "):
        E.ExactComparison(1.0, 1e200, "A", "B", "less", "m")
    with pytest.raises(ValueError, match=r"^a "):
        E.ExactComparison(-1e151, 1.0, "A", "B", "less", "m")


def test_a13_exact_comparison_claim_type():
    with pytest.raises(TypeError, match="claim"):
        E.ExactComparison(1.0, 2.0, "A", "B", np.array("less"), "m")


@pytest.mark.parametrize("field", ["a_name", "b_name", "metric"])
def test_a14_comparison_empty_names(field):
    kw = dict(a=A100, b=A100 + 1, a_name="A", b_name="B", claim="less", metric="m") | {field: " "}
    with pytest.raises(ValueError, match=field):
        L.Comparison(**kw)


def test_comparison_claim_type():
    with pytest.raises(TypeError, match="claim"):
        L.Comparison(A100, A100 + 1, "A", "B", np.array("less"), "m")


# --------------------------------------------------------------------------- debatable: margins, few runs
def test_margin_and_relative_margin_disagreeing():
    with pytest.raises(ValueError, match="margin = 1.0 and relative_margin = 0.5 disagree"):
        L.Comparison(A100, A100 + 1, "A", "B", "less", "m", margin=1.0, relative_margin=0.5)


def test_margin_and_relative_margin_agreeing():
    c = L.Comparison(A100, A100 + 1, "A", "B", "less", "m")     # a copy passes both (study_evidence does)
    copy = L.Comparison(c.a, c.b, "A", "B", "less", "m", margin=c.margin, relative_margin=c.relative_margin)
    assert copy.margin == c.margin and copy.status() == c.status()


def test_too_few_runs_names_the_arguments():
    with pytest.raises(ValueError, match=r"a and b hold 3 runs < 100: .*reason"):
        L.Comparison([1.0, 2.0, 3.0], [2.0, 3.0, 4.0], "A", "B", "less", "m")


# --------------------------------------------------------------------------- debatable: records built directly
def test_unverifiable_and_alternative_empty_texts():
    with pytest.raises(ValueError, match="reason"):
        L.Unverifiable("")
    with pytest.raises(ValueError, match="choice"):
        L.Alternative("", "r", L.Unverifiable("x"))
    with pytest.raises(ValueError, match="reading"):
        L.Alternative("c", " ", L.Unverifiable("x"))


def test_claim_repeated_critique():
    with pytest.raises(ValueError, match="critiques"):
        L.Claim("yang-x-y", "yang2012optimal", "Fig. 1", "c", "p", L.Unverifiable("x"), "lnk", critiques=("a", "a"))


def _spec(**kw):
    base = dict(id="yang-x-y", chapter="c", where="w", claim="c", claimant="source", published="p", test="paired",
                link="l")
    return C.ClaimSpec(**(base | kw))


@pytest.mark.parametrize("kw, exc, name", [
    (dict(id=5), TypeError, "id"), (dict(test="nope"), ValueError, "test"), (dict(claimant="x"), ValueError, "claimant"),
    (dict(direction="up"), ValueError, "direction"), (dict(headline=1), TypeError, "headline"),
    (dict(margin={"relative": nan}), ValueError, "margin"), (dict(margin={"both": 1.0}), ValueError, "margin"),
    (dict(critiques=["a"]), TypeError, "critiques"), (dict(critiques=("a", "a")), ValueError, "critiques"),
    (dict(readings=(5,)), TypeError, "readings"), (dict(evidence="nocolon"), ValueError, "evidence"),
    (dict(where=""), ValueError, "where"),
])
def test_claim_spec_fields(kw, exc, name):
    with pytest.raises(exc, match=name):
        _spec(**kw)


def test_reading_spec_fields():
    with pytest.raises(ValueError, match="kind"):
        C.ReadingSpec("k", "c", "r", "nope", {})
    with pytest.raises(TypeError, match="settings"):
        C.ReadingSpec("k", "c", "r", "open-choice", [])
    with pytest.raises(ValueError, match="runs"):
        C.ReadingSpec("k", "c", "r", "open-choice", {}, 0)


# --------------------------------------------------------------------------- B: claim files
def _variant(tmp_path, mutate, name="v"):
    d = yaml.safe_load(YANG.read_text(encoding="utf-8"))
    mutate(d)
    p = tmp_path / f"{name}.yaml"
    p.write_text(yaml.safe_dump(d, allow_unicode=True), encoding="utf-8")
    return p


def _paired(d):
    return [r for r in d["records"] if r.get("test") == "paired"][0]


def _with_evidence(d):
    return [r for r in d["records"] if r.get("evidence")][0]


@pytest.mark.parametrize("value", [nan, inf, 1e300])
def test_b1_b2_quantity_margin_finite(tmp_path, value):
    p = _variant(tmp_path, lambda d: d["quantities"]["mae"].__setitem__("margin", {"relative": value}))
    with pytest.raises(C.ClaimsFileError, match=r"quantity mae, field margin\.relative"):
        C.load(p)


def test_b3_record_margin_finite(tmp_path):
    p = _variant(tmp_path, lambda d: _paired(d).__setitem__("margin", {"absolute": nan}))
    with pytest.raises(C.ClaimsFileError, match=r"field margin\.absolute"):
        C.load(p)


def test_runs_ceiling(tmp_path):
    def mutate(d):
        r = [r for r in d["records"] if r.get("readings", {}).get("primary")][0]
        r["readings"]["primary"]["runs"] = 10**30
    with pytest.raises(C.ClaimsFileError, match="runs"):
        C.load(_variant(tmp_path, mutate))


@pytest.mark.parametrize("evidence", ["fusion.book.chapters.ofs:no_such_function", "os:no_such_function",
                                      "fusion.book.chapters.nomod:f"])
def test_b4_evidence_function_must_exist(tmp_path, evidence):
    p = _variant(tmp_path, lambda d: _with_evidence(d).__setitem__("evidence", evidence))
    with pytest.raises(C.ClaimsFileError, match="field evidence"):
        C.load(p)


def test_b5_evaluate_missing_evidence_function():
    spec = C.load(YANG).records[0]
    bad = dataclasses.replace(spec, evidence="fusion.book.chapters.ofs:no_such_function")
    with pytest.raises(C.ClaimsFileError, match="field evidence"):
        C.evaluate(bad, "primary", 0, 2)


def test_b6_b7_load_unreadable_path(tmp_path):
    with pytest.raises(ValueError, match="path"):
        C.load(tmp_path / "missing.yaml")
    with pytest.raises(ValueError, match="path"):
        C.load(tmp_path)
    p = tmp_path / "latin1.yaml"
    p.write_bytes("source: café".encode("latin-1"))
    with pytest.raises(ValueError, match="path .* not UTF-8"):
        C.load(p)


def test_b8_load_all_paths():
    assert set(C.load_all(str(CLAIMS))) == set(C.load_all(CLAIMS))   # a str, as load takes
    with pytest.raises(ValueError, match="directory"):
        C.load_all(CLAIMS / "missing")
    with pytest.raises(TypeError, match="directory"):
        C.load_all(5)


def test_b9_b10_margin_of_another_files_spec():
    yang, cn = C.load(YANG), C.load(CLAIMS / "cn107330468b.yaml")
    with pytest.raises(ValueError, match="spec"):
        yang.margin(cn.records[0])
    with pytest.raises(TypeError, match="spec"):
        yang.margin(5)
    assert yang.margin(yang.records[0]) is not None


def test_b11_ledger_add_type():
    with pytest.raises(TypeError, match="claim"):
        L.Ledger("yang2012optimal").add(5)


def test_b12_empty_ledger_table():
    t = L.Ledger("yang2012optimal").table()
    assert t.empty and list(t.columns) == ["where", "status", "robustness"] and t.index.name == "id"


def test_duplicate_yaml_key(tmp_path):
    p = tmp_path / "dup.yaml"
    p.write_text(YANG.read_text(encoding="utf-8") + "\nsource: yang2012optimal\n", encoding="utf-8")
    with pytest.raises(C.ClaimsFileError, match="repeated key 'source'"):
        C.load(p)


def test_duplicate_critique(tmp_path):
    p = _variant(tmp_path, lambda d: _paired(d).__setitem__("critiques", ["x", "x"]))
    with pytest.raises(C.ClaimsFileError, match="field critiques"):
        C.load(p)


@pytest.mark.parametrize("field, value", [("direction", "less"), ("quantity", "mae"), ("margin", {"relative": 0.1})])
def test_unused_fields_on_a_published_test(tmp_path, field, value):
    def mutate(d):
        r = [r for r in d["records"] if r["test"] == "published"][0]
        r[field] = value
    with pytest.raises(C.ClaimsFileError, match=f"field {field}: a published test compares nothing"):
        C.load(_variant(tmp_path, mutate))


def test_every_claim_file_still_loads():
    files = C.load_all(CLAIMS)
    assert len(files) == len(list(CLAIMS.glob("*.yaml")))
