"""Fuzz 19, the book layer (issue 35): the rulebook (A1, A2, R1's tie rule), claims and claim files (F10, F11, the
claim-file evidence function, ``Claim``'s test and readings), the formatters' magnitude rule, the chapters' ``keep``
(D24 and the debatable silent replacement) and ``chernoff_steps.paired_numbers`` (F12).

The rules are shared: R3's infinite median in :func:`fusion.book.rulebook.judge_paired` (for ``Comparison`` too);
R1's tie rule in the ledger's ``PublishedValues``; the evidence classes a test takes in one table
(``fusion.book.ledger.evidence._KIND_OF_TEST``) for claim files and ``Claim``; one magnitude rule for every formatter
(``fusion.book.tables._printed_number``); one rule for the chapters' ``keep`` (``fusion.book.glue._checked_keep``).
"""

from __future__ import annotations

import math
from decimal import Decimal
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import yaml
from scipy import stats

from fusion.book import claims as C
from fusion.book import ledger as L
from fusion.book import rulebook as RB
from fusion.book import tables as T
from fusion.book.glue import glue_all
from fusion.book.chapters import chernoff_steps as CST
from fusion.book.chapters import lecture_correlated as LC
from fusion.book.chapters import time_registration_ledger as TRL
from fusion.book.chapters.ci import excess_text

inf, nan = math.inf, math.nan
YANG = Path(__file__).resolve().parents[1] / "book" / "claims" / "yang2012optimal.yaml"
A100 = np.arange(100.0) + 1


def _split(k: int, n: int = 100) -> tuple[np.ndarray, np.ndarray]:
    """k runs in which A is infinite (B = 1), n - k in which B is (A = 1): differences +inf k times, -inf n - k."""
    return np.r_[np.full(k, inf), np.ones(n - k)], np.r_[np.ones(k), np.full(n - k, inf)]


def _order_index(n: int) -> int:
    """The distribution-free 95 % interval's order index j (the largest with P(Bin(n, 1/2) <= j - 1) <= 0.025)."""
    return max(j for j in range(1, n // 2 + 1) if stats.binom.cdf(j - 1, n, 0.5) <= 0.025)


# --------------------------------------------------------------------------- A1, A2: an infinite median (R3)
@pytest.mark.parametrize("k", range(101))
def test_a1_every_split_of_infinite_runs(k):
    a, b = _split(k)
    j = _order_index(100)
    for direction, good, bad in (("less", "reproduced", "contradicted"), ("greater", "contradicted", "reproduced"),
                                 ("equal", "contradicted", "contradicted")):
        got = RB.judge_paired(a, b, direction, 0.1)
        assert got.status != "not distinguishable"  # R3: an infinite or undefined statistic never is
        if k in (0, 100):  # one mean infinite: the infinite mean is the higher (R3)
            assert got.statistic == "infinite mean"
            assert got.status == (bad if k == 100 else good)
        elif min(k, 100 - k) < j:  # the interval's j-th order statistics are both of the majority's sign
            assert got.statistic == "median" and got.status == (bad if k > 50 else good)
            assert got.region == ("higher" if k > 50 else "lower")
        else:  # the interval is [-inf, inf] (or the median undefined at 50/50): nothing is decided
            assert got.status == "cannot be checked" and got.region == "undecided"


def test_a1_reported_splits():
    for k in range(51, 61):  # fuzz 19 A1: 51/49 to 60/40 gave "not distinguishable"
        got = RB.judge_paired(*_split(k), "less", 0.1)
        assert got.status == "cannot be checked" and got.estimate == inf and (got.low, got.high) == (-inf, inf)
    assert RB.judge_paired(*_split(61), "less", 0.1).status == "contradicted"


def test_a1_finite_median_with_an_unbounded_interval_cannot_be_checked():
    # 45 runs +inf, 10 ties, 45 runs -inf: the median difference is 0, its interval [-inf, inf]
    a = np.r_[np.full(45, inf), np.ones(55)]
    b = np.r_[np.ones(55), np.full(45, inf)]
    got = RB.judge_paired(a, b, "less", 0.1)
    assert got.estimate == 0.0 and (got.low, got.high) == (-inf, inf) and got.status == "cannot be checked"


def test_a1_both_infinite_with_a_finite_bounded_median_still_decides():
    # both means infinite through one run each; the other runs give a clear finite median difference
    a = np.r_[inf, A100[:-2], 1.0]
    b = np.r_[1.0, A100[:-2] + 5.0, inf]
    got = RB.judge_paired(a, b, "less", 0.1)
    assert got.statistic == "median" and got.estimate == -5.0 and got.status == "reproduced"


def test_a1_rule_text_says_it():
    r3 = {r.key: r for r in RB.RULES}["R3"].text
    assert "infinite with an interval on both sides of zero" in r3 and "cannot be checked" in r3


def test_a2_comparison():
    c = L.Comparison(*_split(51), "A", "B", "less", "m")
    assert c.judgement().status == "cannot be checked" and c.status() == "cannot be checked"
    assert "not distinguishable" not in c.summary() and "cannot be checked (R3)" in c.summary()
    d = L.Comparison(*_split(70), "A", "B", "less", "m")
    assert d.status() == "contradicted" and "decided by the median (R3)" in d.summary()


# --------------------------------------------------------------------------- F12: paired_numbers
@pytest.mark.parametrize("a,b,name", [(_split(51)[0], _split(51)[1], "a"), (A100, np.r_[A100[:-1], inf], "b"),
                                      (np.r_[A100[:-1], nan], A100, "a")])
def test_f12_paired_numbers_names_the_infinite_side(a, b, name):
    with pytest.raises(ValueError, match=rf"^{name} "):
        CST.paired_numbers(a, b, "x")


def test_f12_paired_numbers_valid():
    out = CST.paired_numbers(A100, A100 + 1.0, "x")
    assert out["x_d"] == -1.0 and out["x_runs"] == 100


# --------------------------------------------------------------------------- F10, F11: build_ledger
@pytest.mark.parametrize("kw,name", [(dict(evidence=5), "evidence"), (dict(evidence={}, values=5), "values"),
                                     (dict(evidence={}, claims=5), "claims")])
def test_f10_f11_build_ledger_types(kw, name):
    with pytest.raises(TypeError, match=rf"^{name} must be"):
        C.build_ledger("lecture003", None, **kw)


def test_f10_build_ledger_empty_mapping_is_still_a_claims_file_error():
    with pytest.raises(C.ClaimsFileError, match="records without evidence"):
        C.build_ledger("lecture003", None, {})


# --------------------------------------------------------------------------- R1: ties
@pytest.mark.parametrize("published,ours,decimals,status", [
    (3.0, 2.5, 0, "reproduced"), (2.0, 2.5, 0, "reproduced"),            # an exact tie: either neighbour
    (-3.0, -2.5, 0, "reproduced"), (-2.0, -2.5, 0, "reproduced"),
    (0.13, 0.125, 2, "reproduced"), (0.12, 0.125, 2, "reproduced"),      # 0.125 is exact in binary
    (0.14, 0.125, 2, "not reproduced"),
    (0.14, 0.135, 2, "reproduced"), (0.13, 0.135, 2, "not reproduced"),  # 0.135 is 0.13500000000000000888...
    (3.0, 2.4999999, 0, "not reproduced"), (2.0, 2.5000001, 0, "not reproduced"),
    (10**20, 1e20, 17, "reproduced"),  # an int is exact; the float 1e20 cannot hold 17 decimals (fuzz 30a C2)
])
def test_r1_tie_rule(published, ours, decimals, status):
    assert L.PublishedValues([published], [ours], decimals).status() == status


def test_r1_rule_text_states_the_tie():
    assert "at an exact tie either neighbour counts" in {r.key: r for r in RB.RULES}["R1"].text


# --------------------------------------------------------------------------- Claim: readings and test
def _claim(evidence, **kw):
    return L.Claim(id="t-1", source="yang2012optimal", where="w", claim="c", published="p", evidence=evidence,
                   link="x", **kw)


def test_claim_refuses_a_repeated_reading():
    alt = L.Alternative("guard", "floor", L.Comparison(A100, A100 + 1, "A", "B", "less", "m"))
    with pytest.raises(ValueError, match="alternatives must not repeat"):
        _claim(L.Comparison(A100, A100 + 1, "A", "B", "less", "m"), alternatives=(alt, alt))
    other = L.Alternative("guard", "ceiling", alt.evidence)
    assert "of 2 other readings" in _claim(alt.evidence, alternatives=(alt, other)).robustness


@pytest.mark.parametrize("test", ["published", "exact", "count", "unverifiable"])
def test_claim_test_must_fit_the_evidence(test):
    with pytest.raises(ValueError, match=rf"test '{test}' cannot take Comparison"):
        _claim(L.Comparison(A100, A100 + 1, "A", "B", "less", "m"), test=test)


def test_claim_unverifiable_fits_every_test():  # R7: an undefined baseline
    assert _claim(L.Unverifiable("no rule"), test="paired").status == "cannot be checked"


# --------------------------------------------------------------------------- record_status and counted: plain str
def test_record_status_returns_plain_str():
    status = RB.record_status(np.str_("reproduced"), [], None, False)[0]
    assert status == "reproduced" and type(status) is str
    why = RB.counted(np.str_("reseed"), None, None)[1]
    assert why == "reseed" and type(why) is str


# --------------------------------------------------------------------------- claim files: the evidence is a function
def _variant(tmp_path, evidence):
    d = yaml.safe_load(YANG.read_text(encoding="utf-8"))
    [r for r in d["records"] if r.get("evidence")][0]["evidence"] = evidence
    p = tmp_path / "v.yaml"
    p.write_text(yaml.safe_dump(d, allow_unicode=True), encoding="utf-8")
    return p


@pytest.mark.parametrize("evidence", ["builtins:print", "fusion.book.ledger:Comparison", "math:pi"])
def test_claims_load_refuses_a_callable_that_is_not_a_function(tmp_path, evidence):
    with pytest.raises(C.ClaimsFileError, match="field evidence"):
        C.load(_variant(tmp_path, evidence))


def test_claims_load_accepts_a_decorated_function(tmp_path):
    # functools-wrapped functions unwrap to a function (the chapters' cached evidence functions)
    assert C.load(_variant(tmp_path, "fusion.book.chapters.ci:ev_headline")).records


# --------------------------------------------------------------------------- the formatters' magnitude rule
@pytest.mark.parametrize("value", [1e-320, 1e-200, 1e200, 1e300, -1e300])
def test_formatters_print_any_finite_magnitude(value):
    assert T.rounded(value) == (0.0 if abs(value) < 1e-4 else value)
    assert T.sci(value) and L.fmt(value)
    assert T.roundoff(value) == ("less than 10⁻¹²" if abs(value) < 1 else T.sci(abs(value), 2))


def test_formatters_still_refuse_non_finite_and_text():
    for f in (T.rounded, T.roundoff):
        with pytest.raises(ValueError, match="^value must be finite"):
            f(nan)
        with pytest.raises(TypeError, match="^value "):
            f("1")
    assert excess_text(1e300).endswith("above the minimum") and excess_text(1e-320).endswith("above the minimum")
    with pytest.raises(ValueError, match="^excess"):
        excess_text(-1.0)
    with pytest.raises(ValueError, match="^excess"):
        excess_text(inf)


# --------------------------------------------------------------------------- keep: one rule (D24)
@pytest.mark.parametrize("keep", [TRL.keep, LC.keep])
def test_keep_types(keep):
    with pytest.raises(TypeError, match="^store must be"):
        keep(5, {})
    with pytest.raises(TypeError, match="^values must be"):
        keep({}, 5)
    with pytest.raises(TypeError, match="^values must have str glue keys"):
        keep({}, {1: 2.0})


@pytest.mark.parametrize("keep", [TRL.keep, LC.keep])
def test_keep_refuses_a_key_that_is_not_an_identifier(keep):
    store: dict = {}
    with pytest.raises(ValueError, match="^values must have glue keys that are identifiers"):
        keep(store, {"bad key!": 1.0})
    assert store == {}


def test_keep_takes_the_new_value_of_a_key_kept_again():
    """Re-running a notebook's cell keeps its values again: the new value replaces the old (fuzz 20, K1: refusing
    a different value broke the re-run of chapter 07's figure cell); the claim texts read the store when the ledger
    is built."""
    key = sorted(LC.GLUED)[0]
    for keep, k in ((TRL.keep, "k"), (LC.keep, key)):
        store = {k: 2.5}
        keep(store, {k: 3.0})
        assert store == {k: 3.0}


@pytest.mark.parametrize("value", [np.array(nan), Decimal("nan"), Decimal("inf"), np.float32("inf")],
                         ids=["0-d", "Decimal-nan", "Decimal-inf", "float32-inf"])
def test_keep_and_glue_all_refuse_non_finite_numbers_in_any_form(value):
    """fuzz 20, K2-K4: NaN as a 0-d array or a Decimal was stored or glued."""
    with pytest.raises(ValueError, match=r"^values\['k'\]"):
        TRL.keep({}, {"k": value})
    with pytest.raises(ValueError, match=r"^values\['k'\]"):
        glue_all({"k": value})


def test_keep_refuses_non_finite():
    with pytest.raises(ValueError, match=r"^values\['k'\]"):
        TRL.keep({}, {"k": nan})


@pytest.mark.parametrize("value, text", [(5e-324, "4.9 × 10⁻³²⁴"), (-5e-324, "-4.9 × 10⁻³²⁴"), (1e-310, "1.0 × 10⁻³¹⁰"),
                                         (1.75e-300, "1.8 × 10⁻³⁰⁰")])
def test_lecture_sci_prints_subnormal_numbers(value, text):
    """fuzz 20, A: ``lecture.sci(5e-324)`` raised ZeroDivisionError (10.0**-324 underflows to 0)."""
    from fusion.book.chapters.lecture import sci

    assert sci(value) == text


def _pub_rep(column):
    return pd.DataFrame({"published a": [1.0, 2.0], "reproduced a": column})


@pytest.mark.parametrize("column", [["1.0", "two"], [True, False], pd.to_timedelta([1, 5], unit="s"),
                                    pd.Series(["1", "2"], dtype="string")], ids=["text", "bool", "timedelta", "string"])
def test_mismatches_refuses_columns_that_are_not_numbers(column):
    """fuzz 20, M1-M4: a text, bool or duration column was compared as numbers (a text cell reported a mismatch)."""
    with pytest.raises(TypeError, match=r"^table\['reproduced a'\]"):
        T.mismatches(_pub_rep(column))
    with pytest.raises(TypeError, match=r"^table\['reproduced a'\]"):
        T.highlight_mismatches(_pub_rep(column))


def test_mismatches_reads_missing_values_in_an_object_column():
    got = T.mismatches(_pub_rep(pd.Series([1.0, None], dtype=object)))
    assert list(got["reproduced a"]) == [False, True]   # a reproduced None beside a published value is a mismatch


def test_fuzz20_left_cases_are_decided():
    """fuzz 20: D1/D2 a repeated delay or level is refused (the tables are keyed by them); X1 an integer beyond the
    float range is refused citing that range, not rule 2's 1e150 (a printed number has no such bound); L1
    ``roundoff`` prints a discrepancy's size, documented."""
    from fusion.book.chapters import time_registration as tr
    from fusion.book.chapters.lecture_weighting import estimators, studies

    with pytest.raises(ValueError, match="^delays must not repeat"):
        tr.delay_table([0.0, 0.0, 0.01], [0.1, 0.3])
    with pytest.raises(ValueError, match="^sigmas must not repeat"):
        tr.delay_table([0.0, 0.01], [0.1, 0.1])
    with pytest.raises(ValueError, match="^levels must not repeat"):
        estimators.table_21(studies.study("s21"), levels=(0.0, 0.0))
    with pytest.raises(ValueError, match="float range"):
        T.rounded(10**400)
    assert T.rounded(1e200) == 1e200
    assert T.roundoff(-1.0) == T.roundoff(1.0)
