"""Fuzz 21a's cases of claim files, claim records and the comparisons they hold (issue 35), by class.

* Y: a claim file of nested YAML aliases (400 bytes that expand to 10⁹ values) is refused fast, naming the file:
  each mapping or list is walked once; the book's own aliases still load.
* C: ``runs: 100.0`` (an integer to JSON Schema) is a ClaimsFileError naming the file, the record and the field.
* R: :class:`~fusion.book.claims.ClaimSpec` and :class:`~fusion.book.claims.ClaimsFile` apply ``load``'s rules
  in ``__post_init__`` (one check for both: ``dataclasses.replace`` cannot build what ``load`` refuses).
* F: the texts ``build_ledger`` fills are checked as format texts: plain ``{name}`` fields, short specs.
* E: ``evidence`` is held to the file's pattern; any failure to import it names the field.
* X: ``ExactComparison`` refuses a ``margin`` and a ``relative_margin`` that disagree, as ``Comparison`` does.
* V, U: a NumPy bool headline is stored as a bool; a source's chapters each have their own number.
* Debatable, decided: D1 (list triples), D5 (huge percentages), D7 (numpy bool ``defined``, settings keys),
  D9 (``recommend.check``), D15 (summary of runs infinite in both).
"""

from __future__ import annotations

import dataclasses
import json
import sys
import time

import numpy as np
import pytest
import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from fusion.book import claims as C
from fusion.book import ledger as L
from fusion.book import recommend as RC
from fusion.book import rulebook as R
from fusion.book.exact import ExactComparison

YANG = "yang2012optimal.yaml"
HYP = settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])


@pytest.fixture(scope="module")
def cfs() -> dict[str, C.ClaimsFile]:
    return C.load_all()


@pytest.fixture(scope="module")
def cf(cfs) -> C.ClaimsFile:
    return cfs["yang2012optimal"]


def _record(cfs, pred):
    return next((r, c) for c in cfs.values() for r in c.records if pred(r))


def _variant(tmp_path, mutate, name="v"):
    d = yaml.safe_load((C.claims_dir() / YANG).read_text(encoding="utf-8"))
    mutate(d)
    p = tmp_path / f"{name}.yaml"
    p.write_text(yaml.safe_dump(d, allow_unicode=True), encoding="utf-8")
    return p


# --- Y: aliases -----------------------------------------------------------------------------------------------

def _laughs(n: int, w: int) -> str:
    s = "a0: &a0 [x]\n"
    for i in range(1, n):
        s += f"a{i}: &a{i} [" + ",".join([f"*a{i - 1}"] * w) + "]\n"
    return s + "source: x\nrecords: []\n"


def _refused_fast(path, text: str, match: str) -> None:
    """``load`` of ``text`` written to ``path`` is a ClaimsFileError matching ``match``, in under 2 CPU-s."""
    path.write_text(text, encoding="utf-8")
    t = time.process_time()
    with pytest.raises(C.ClaimsFileError, match=match):
        C.load(path)
    assert time.process_time() - t < 2.0


@pytest.mark.parametrize(("n", "w"), [(9, 10), (30, 2)])
def test_y_alias_bomb_refused_fast(tmp_path, n, w):
    _refused_fast(tmp_path / "bomb.yaml", _laughs(n, w), "bomb.yaml.*expands")


@HYP
@given(n=st.integers(2, 40), w=st.integers(2, 12))
def test_y_any_alias_chain_is_a_named_refusal_in_linear_time(tmp_path, n, w):
    _refused_fast(tmp_path / "chain.yaml", _laughs(n, w), "chain.yaml")


def test_y_alias_inside_a_record_setting_is_refused(tmp_path):
    d = yaml.safe_load((C.claims_dir() / YANG).read_text(encoding="utf-8"))
    d["records"][0]["readings"]["primary"]["settings"] = {"x": "BOMB"}  # a free mapping: the schema looks no deeper
    bomb = ", ".join(["b0: &b0 [x]"] + [f"b{i}: &b{i} [" + ",".join([f"*b{i - 1}"] * 10) + "]" for i in range(1, 9)])
    text = yaml.safe_dump(d, allow_unicode=True).replace("BOMB", "{" + bomb + "}")
    _refused_fast(tmp_path / "inner.yaml", text, "inner.yaml: field records.0.readings: expands")


def test_y_a_list_that_contains_itself_is_refused(tmp_path):
    p = tmp_path / "self.yaml"
    p.write_text("source: yang2012optimal\nrecords: &r [*r]\n", encoding="utf-8")
    with pytest.raises(C.ClaimsFileError, match="self.yaml.*(itself|deep)"):
        C.load(p)


def test_y_depth_counts_the_path_an_alias_is_reached_by(tmp_path):
    deep = "[" * 20 + "x" + "]" * 20
    p = tmp_path / "deep.yaml"  # 20 levels under an anchor, then the alias 20 levels down: 40 deep
    p.write_text(f"source: yang2012optimal\nd: &d {deep}\nrecords: {'[' * 20}*d{']' * 20}\n", encoding="utf-8")
    with pytest.raises(C.ClaimsFileError, match="nested more than 32 deep"):
        C.load(p)


def test_y_the_books_aliases_still_load(cfs):
    text = (C.claims_dir() / "wang2024covariance.yaml").read_text(encoding="utf-8")
    assert "*id001" in text and cfs["wang2024covariance"].records


# --- C: runs: 100.0 ---------------------------------------------------------------------------------------------

def _first_primary(d):
    return next(r for r in d["records"] if "primary" in r.get("readings", {}))


@pytest.mark.parametrize("runs", [100.0, 2.5, 1e300])
def test_c_float_runs_is_a_claims_file_error(tmp_path, runs):
    rid = []

    def mutate(d):
        r = _first_primary(d)
        rid.append(r["id"])
        r["readings"]["primary"]["runs"] = runs
    p = _variant(tmp_path, mutate)
    # 100.0 passes the schema (an integral float is a JSON integer) and is refused by the record; 2.5 by the schema
    with pytest.raises(C.ClaimsFileError, match=rf"v.yaml: record {rid[0]}[:,] field readings\.primary\.runs"):
        C.load(p)


def test_c_integer_runs_still_load(tmp_path):
    p = _variant(tmp_path, lambda d: _first_primary(d)["readings"]["primary"].__setitem__("runs", 100))
    assert any(r.runs == 100 for s in C.load(p).records for r in s.readings)


# --- R: one check for load and replace ----------------------------------------------------------------------------

def test_r1_undeclared_quantity(cfs):
    spec, cfq = _record(cfs, lambda r: r.quantity and r.margin is None)
    with pytest.raises(C.ClaimsFileError, match=rf"record {spec.id}: field quantity"):
        dataclasses.replace(cfq, quantities={})


@pytest.mark.parametrize(("entry", "field"), [
    (5, "quantity"), ({"label": "x"}, "quantity"), ({"label": "", "margin": {"relative": 0.1}}, "label"),
    ({"label": "x", "margin": {"relative": -5.0}, "why": "w"}, r"margin\.relative"),
    ({"label": "x", "margin": {"relative": float("nan")}}, r"margin\.relative"),
    ({"label": "x", "margin": {"both": 1.0}}, "margin"), ({"label": "x", "margin": {"relative": 0.1}, "z": 1}, "quantity"),
])
def test_r2_quantity_entries_held_to_load(cfs, entry, field):
    spec, cfq = _record(cfs, lambda r: r.quantity and r.margin is None)
    with pytest.raises(ValueError, match=field):
        dataclasses.replace(cfq, quantities={**cfq.quantities, spec.quantity: entry})


def test_r2_a_valid_quantity_entry_is_kept(cfs):
    spec, cfq = _record(cfs, lambda r: r.quantity and r.margin is None)
    new = dataclasses.replace(cfq, quantities={**cfq.quantities, spec.quantity: {"label": "x", "margin": {"absolute": 2}}})
    assert new.margin(spec) == {"absolute": 2}


@pytest.mark.parametrize(("change", "field"), [
    (lambda cf: {"quantities": {**cf.quantities, 5: {"label": "x", "margin": {"relative": 0.1}}}}, "quantity 5"),
    (lambda cf: {"source": ""}, "source"), (lambda cf: {"source": "nosuch"}, "source"),
    (lambda cf: {"records": cf.records + cf.records[:1]}, "duplicate id"),
    (lambda cf: {"records": tuple(r for r in cf.records if not r.headline)}, "headline"),
])
def test_r3_file_rules_apply_to_replace(cf, change, field):
    with pytest.raises(ValueError, match=field):
        dataclasses.replace(cf, **change(cf))


def test_r3_chapter_outside_the_source(cf):
    spec = dataclasses.replace(cf.records[1], chapter="notebooks/02_lecture_weighting")
    with pytest.raises(C.ClaimsFileError, match=rf"record {spec.id}: field chapter"):
        dataclasses.replace(cf, records=(cf.records[0], spec))


# Each rule of load on one record, as a mutation of the file and as the same change through replace: both refuse,
# naming the same field (the drift fuzz 21 found: replace skipped what load checked).
def _first(test):
    return lambda d: next(r for r in d["records"] if r["test"] == test)


RECORD_RULES = [
    ("paired", {"quantity": ""}, lambda r: r.pop("quantity"), "quantity"),
    ("paired", {"direction": ""}, lambda r: r.pop("direction"), "direction"),
    ("paired", {"direction": "equal"}, lambda r: r.__setitem__("direction", "equal"), "direction"),
    ("paired", {"reason": "r"}, lambda r: r.__setitem__("reason", "r"), "reason"),
    ("published", {"margin": {"relative": 0.1}}, lambda r: r.__setitem__("margin", {"relative": 0.1}), "margin"),
    ("published", {"claimant": "book", "headline": True},
     lambda r: r.update(claimant="book", headline=True), "headline"),
    ("published", {"baseline": {"name": "m", "defined": False}},
     lambda r: r.__setitem__("baseline", {"name": "m", "defined": False}), r"baseline\.reason"),
    ("published", {"id": "Not An Id"}, lambda r: r.__setitem__("id", "Not An Id"), "id"),
    ("published", {"claim": "x" * 201}, lambda r: r.__setitem__("claim", "x" * 201), "claim"),
    ("published", {"claim": "value {x"}, lambda r: r.__setitem__("claim", "value {x"), "claim"),
    ("published", {"bound": "{x:>3000000000}"}, lambda r: r.__setitem__("bound", "{x:>3000000000}"), "bound"),
    ("published", {"evidence": "a b:f"}, lambda r: r.__setitem__("evidence", "a b:f"), "evidence"),
]


@pytest.mark.parametrize(("test", "change", "mutate", "field"), RECORD_RULES)
def test_r_load_and_replace_refuse_alike(tmp_path, cf, test, change, mutate, field):
    p = _variant(tmp_path, lambda d: mutate(_first(test)(d)))
    with pytest.raises(C.ClaimsFileError, match=rf"v.yaml: .*field {field}"):
        C.load(p)
    spec = next(r for r in cf.records if r.test == test)
    with pytest.raises(ValueError, match=field):
        dataclasses.replace(spec, **change)


def test_r4_undefined_baseline_without_reason(cfs):
    spec, _ = _record(cfs, lambda r: r.baseline is not None and not r.baseline["defined"])
    b = {k: v for k, v in spec.baseline.items() if k != "reason"}
    with pytest.raises(C.ClaimsFileError, match=r"field baseline\.reason"):
        dataclasses.replace(spec, baseline=b)


@pytest.mark.parametrize(("change", "field"), [
    (dict(test="unverifiable"), "reason"),
    (dict(readings=(C.ReadingSpec("k", "c", "r", "open-choice", {}), C.ReadingSpec("k", "c", "s", "open-choice", {}))),
     "duplicate key"),
    (dict(readings=(C.ReadingSpec("k", "c", "r", "open-choice", {}), C.ReadingSpec("primary", "c", "r", "primary", {}))),
     "primary"),
    (dict(readings=(C.ReadingSpec("k", "c", "r", "primary", {}),)), "primary"),
])
def test_d7_remaining_record_rules(cf, change, field):
    with pytest.raises(ValueError, match=field):
        dataclasses.replace(cf.records[0], **change)


def test_d7_numpy_bools_are_bools(cf):
    spec = dataclasses.replace(cf.records[0], baseline={"name": "m", "defined": np.False_, "reason": "r"},
                               headline=np.bool_(cf.records[0].headline))
    assert type(spec.baseline["defined"]) is bool and type(spec.headline) is bool


def test_d7_reading_settings_keys_are_texts():
    with pytest.raises(TypeError, match="settings"):
        C.ReadingSpec("k", "c", "r", "open-choice", {1: 2})
    assert C.ReadingSpec("k", "c", "r", "open-choice", {"a": 2}).settings == {"a": 2}


def test_every_record_of_the_book_passes_replace(cfs):
    for c in cfs.values():
        assert dataclasses.replace(c, records=tuple(dataclasses.replace(r) for r in c.records)) == c


# --- F: format texts ----------------------------------------------------------------------------------------------

@pytest.mark.parametrize("claim", ["value {x", "value }", "{x:>3000000000}", "{x:{y}}", "{x.real}", "{x[0]}", "{0}",
                                   "{}", "{x!r}", "{x:>100000000}", "{x:.300f}"])
def test_f_bad_format_texts_refused_naming_the_field(cf, claim):
    with pytest.raises(C.ClaimsFileError, match=rf"record {cf.records[0].id}: field claim"):
        dataclasses.replace(cf.records[0], claim=claim)


@pytest.mark.parametrize("claim", ["{x}", "{x:.2f}", "{n:d}", "{p:.1%}", "{x:>8.3g}", "{x:g}", "a {{brace}}", "{ci_lg_x}"])
def test_f_short_specs_accepted(cf, claim):
    assert dataclasses.replace(cf.records[0], claim=claim).claim == claim


def test_f_fill_names_the_record_and_field():
    with pytest.raises(C.ClaimsFileError, match="rec r1: claim"):
        C._fill("value {x", {"x": 1}, "rec r1: claim")
    with pytest.raises(C.ClaimsFileError, match="rec r1: claim"):
        C._fill("{x:d}", {"x": 1.5}, "rec r1: claim")  # a value its spec does not fit


_PIECES = st.sampled_from(["a", " ", "{", "}", "{x}", "{x:", ":", ".2f", ">9", "999999", "{y}", "!r", "d", "%", "{{"])


@HYP
@given(st.lists(_PIECES, max_size=12).map("".join))
def test_f_any_text_is_refused_by_the_record_or_filled_by_build_ledger(cf, text):
    spec = cf.records[0]
    try:
        spec = dataclasses.replace(spec, claim=text)
    except ValueError as e:  # ClaimsFileError naming the field, or the blank text's "claim must not be empty"
        assert "claim" in str(e)
        return
    try:
        out = C._fill(spec.claim, {"x": 1.25, "y": 7}, f"record {spec.id}: claim")
    except C.ClaimsFileError as e:  # a value its (short) spec does not fit, named
        assert f"record {spec.id}: claim" in str(e)
        return
    assert len(out) <= len(spec.claim) + 200


# --- E: evidence --------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("evidence", ["a b:f", ".x:f", "fusion/book:f", "x\x00:f", "a:f\n", "1a:f", "a:1f", "a:"])
def test_e2_evidence_held_to_the_file_pattern(cf, evidence):
    spec = next(r for r in cf.records if r.evidence)
    with pytest.raises(ValueError, match="evidence"):
        dataclasses.replace(spec, evidence=evidence)


def test_e1_any_import_failure_names_the_field(tmp_path, monkeypatch, cf):
    (tmp_path / "fz21_broken.py").write_text("raise RuntimeError('broken at import')\n", encoding="utf-8")
    monkeypatch.syspath_prepend(str(tmp_path))
    spec = dataclasses.replace(next(r for r in cf.records if r.evidence), evidence="fz21_broken:f")
    with pytest.raises(C.ClaimsFileError, match="field evidence.*RuntimeError"):
        C.evaluate(spec, "primary", 1, 10)
    sys.modules.pop("fz21_broken", None)
    with pytest.raises(C.ClaimsFileError, match="field evidence"):
        C.evaluate(dataclasses.replace(spec, evidence="a..b:f"), "primary", 1, 10)


# --- X: margin and relative_margin ---------------------------------------------------------------------------------

def test_x1_x3_disagreeing_margins_refused():
    x = ExactComparison(1.0, 2.0, "A", "B", "less", "mse")
    for make in (lambda: ExactComparison(1.0, 2.0, "A", "B", "less", "mse", margin=0.1, relative_margin=0.6),
                 lambda: dataclasses.replace(x, relative_margin=0.6), lambda: x.with_margin(0.1, 0.6)):
        with pytest.raises(ValueError, match="margin = .* and relative_margin = .* disagree"):
            make()


def test_x_agreeing_margins_and_copies_kept():
    x = ExactComparison(1.0, 2.0, "A", "B", "less", "mse", relative_margin=0.6)
    assert x.margin == pytest.approx(1.2) and x.status() == "not distinguishable"
    y = dataclasses.replace(x, a=1.5)  # a copy passes both (they agree); margin kept, as for Comparison
    assert (y.a, y.margin, y.relative_margin) == (1.5, x.margin, None)
    assert ExactComparison(1.0, 2.0, "A", "B", "less", "mse", margin=1.2, relative_margin=0.6).margin == 1.2


@HYP
@given(b=st.floats(0.01, 100.0), m=st.one_of(st.none(), st.floats(0.0, 10.0)), r=st.one_of(st.none(), st.floats(0.0, 1.0)))
def test_x_exact_and_paired_comparisons_share_the_margin_rule(b, m, r):
    """ExactComparison and Comparison (B constant over the runs) accept and refuse the same pairs, storing one margin."""
    def outcome(make):
        try:
            return make().margin
        except ValueError:
            return "refused"
    ex = outcome(lambda: ExactComparison(1.0, b, "A", "B", "less", "mse", margin=m, relative_margin=r))
    pa = outcome(lambda: L.Comparison(np.full(3, 1.0), np.full(3, b), "A", "B", "less", "mse", reason="a test",
                                      margin=m, relative_margin=r))
    assert ex == pa or (ex != "refused" and pa != "refused" and ex == pytest.approx(pa))


# --- V, U ---------------------------------------------------------------------------------------------------------

def test_v1_numpy_bool_headline_is_stored_as_bool(tmp_path):
    c = L.Claim("x-1", "lecture003", "§1", "a claim", "1.0", L.Proposition(True, "ok"), "https://example.org",
                headline=np.True_)
    assert type(c.headline) is bool
    led = L.Ledger("lecture003")
    led.add(c)
    led.write(tmp_path)
    assert json.loads(next(tmp_path.glob("*.json")).read_text(encoding="utf-8"))["claims"][0]["headline"] is True


@pytest.mark.parametrize("chapters", [("notebooks/01_a", "notebooks/01_b"), ("notebooks/01_a", "x"),
                                      ("notebooks/01_a", "b/"), ("notebooks/01_a", "notebooks/y_b")])
def test_u1_chapters_need_their_own_number(chapters):
    with pytest.raises(ValueError, match="chapters"):
        L.Source("k", "s", "t", "notebooks/01_a", 1, chapters)


def test_u1_valid_sources_kept():
    assert L.Source("k", "s", "t", "notebooks/x", 1).ledger_file() == "k.json"
    two = L.Source("k", "s", "t", "notebooks/01_a", 1, ("notebooks/01_a", "notebooks/02_b"))
    assert [two.ledger_file(c) for c in two.chapters] == ["k-01.json", "k-02.json"]
    assert len({s.ledger_file(c) for s in L.SOURCES.values() for c in s.chapters}) == sum(
        len(s.chapters) for s in L.SOURCES.values())


# --- debatable cases, decided ----------------------------------------------------------------------------------------

def test_d1_list_triples_are_triples():
    as_tuples = R.record_status("reproduced", [("stress", "reproduced", 100), ("open-choice", "contradicted", 100)],
                                100, False)
    as_lists = R.record_status("reproduced", [["stress", "reproduced", 100], ["open-choice", "contradicted", 100]],
                               100, False)
    assert as_lists == as_tuples and as_tuples[0] == "reproduced under stated assumptions"
    with pytest.raises(TypeError, match="readings"):
        R.record_status("reproduced", [["stress", "reproduced"]], 100, False)


def test_d5_huge_share_printed_in_the_ledgers_format():
    s = ExactComparison(1.0, 1e-160, "A", "B", "greater", "mse").summary()
    assert len(s) < 120 and "10^162%" in s
    assert "(-50.0% of B)" in ExactComparison(1.0, 2.0, "A", "B", "less", "mse").summary()
    assert "(+303610.1% of B)" in ExactComparison(3037.101, 1.0, "A", "B", "less", "mse").summary()


def test_d9_check_refuses_unknown_status_and_repeated_ids():
    with pytest.raises(ValueError, match="records.*status"):
        RC.check([{"id": "a", "status": "zz"}], [])
    with pytest.raises(ValueError, match="records.*repeat"):
        RC.check([{"id": "a", "status": "reproduced"}, {"id": "a", "status": "contradicted"}], [])
    with pytest.raises(ValueError, match="claim"):
        RC.Evidence("  ", ("reproduced",), "r")


def test_d15_runs_infinite_in_both_are_not_a_constant():
    inf = np.full(200, np.inf)
    c = L.Comparison(inf, inf, "A", "B", "less", "mse")
    assert "constant" not in c.summary() and c.status() == "cannot be checked"
    d = c.to_dict()
    assert d["heavy_tailed"] is True and d["tail_index"] is None  # documented: R3 decided, no finite difference
    assert "runs against a constant" in L.Comparison(np.linspace(0, 1, 200), np.full(200, 2.0), "A", "B", "less",
                                                     "mse").summary()


@pytest.mark.parametrize("name", ["assumptions", "critiques"])
def test_a_record_spec_refuses_a_repeated_assumption_or_critique_as_the_claim_does(cfs, name):
    """One rule for a record's spec and its built claim: an assumption or critique label stated twice is refused."""
    spec = next(r for c in cfs.values() for r in c.records if getattr(r, name))
    with pytest.raises(ValueError, match=f"{name} must not repeat"):
        dataclasses.replace(spec, **{name: getattr(spec, name) + getattr(spec, name)[:1]})
