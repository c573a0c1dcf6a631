"""The claims ledger: closed vocabulary, statuses by rule, records that link to their evidence.

Unit tests of :mod:`fusion.book.ledger` and checks of every committed ledger file
(``book/ledger/*.json``): each stored status is re-derived from the stored evidence by the
same rules, every evidence link resolves to a label of the source's chapter, and every critique
box of a chapter is summarised by some record of its source.
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import stats

from fusion.book import ledger as L
from fusion.book import rulebook as R

ROOT = Path(__file__).resolve().parents[1]
LEDGER_FILES = sorted(p for p in (ROOT / "book" / "ledger").glob("*.json") if p.name != "stability.json")
LABEL = re.compile(r"^\((?P<name>[\w-]+)\)=\s*$|^:name:\s*(?P<opt>[\w-]+)\s*$", re.MULTILINE)
CRITIQUE_NAME = re.compile(r"\{admonition\}\s*Critique:[^\n]*\n(?::[^\n]*\n)*?:name:\s*(?P<name>[\w-]+)")


def _chapter_markdown(chapter: str, appendix: bool = False) -> str:
    """The markdown of a chapter's notebook (and, with ``appendix``, of its appendix notebook after it)."""
    paths = [ROOT / f"{chapter}.ipynb"] + ([ROOT / f"{chapter}_appendix.ipynb"] if appendix else [])
    texts = []
    for path in paths:
        nb = json.loads(path.read_text(encoding="utf-8"))
        texts += ["".join(c["source"]) for c in nb["cells"] if c["cell_type"] == "markdown"]
    return "\n".join(texts)


# ----------------------------------------------------------------------------- rules


def test_vocabulary_is_closed_and_defined_once() -> None:
    assert len(L.STATUSES) == len(set(L.STATUSES)) <= 6
    assert set(L.STATUS_DEFINITIONS) == set(L.STATUSES)


def test_published_values_match_at_printed_precision_only() -> None:
    assert L.PublishedValues([900.05], [900.0549], 2).status() == "reproduced"
    assert L.PublishedValues([900.05], [900.0551], 2).status() == "not reproduced"
    assert L.PublishedValues([1.0, 2.0], [1.0, float("nan")], 1).status() == "not reproduced"
    assert L.PublishedValues([1.0, 2.0], [1.0, 2.04], [1, 1]).summary() == "2 of 2 equal at the printed precision"


@given(st.integers(0, 2**32 - 1), st.floats(-2.0, 2.0), st.sampled_from(["less", "greater"]))
@settings(max_examples=40)
def test_comparison_status_follows_the_paired_t_interval_without_margin(seed: int, shift: float, claim: str) -> None:
    rng = np.random.default_rng(seed)
    b = rng.normal(5.0, 1.0, 120)
    a = b + shift + rng.normal(0.0, 1.0, 120)
    c = L.Comparison(a, b, "A", "B", claim, "error", margin=0.0)  # type: ignore[arg-type]
    ci = stats.ttest_rel(a, b).confidence_interval(0.95)
    lo, hi = ci.low, ci.high
    want = ("reproduced" if hi < 0 else "contradicted" if lo > 0 else "not distinguishable") if claim == "less" \
        else ("reproduced" if lo > 0 else "contradicted" if hi < 0 else "not distinguishable")
    assert c.status() == want
    mean, clo, chi = c.interval()
    assert clo <= mean <= chi and math.isclose(clo, lo) and math.isclose(chi, hi)


def test_the_default_margin_is_five_percent_of_the_baseline_mean() -> None:
    rng = np.random.default_rng(8)
    b = rng.normal(10.0, 1.0, 200)
    c = L.Comparison(b - 0.2 + 0.01 * rng.normal(size=200), b, "A", "B", "less", "e")
    assert math.isclose(c.margin, 0.05 * abs(np.mean(b)))
    assert c.within_margin() and c.status() == "not distinguishable"
    assert c.with_margin(0.0).status() == "reproduced"
    assert c.with_margin(relative_margin=0.01).status() == "reproduced"


def test_conjunction_holds_only_if_every_member_holds() -> None:
    rng = np.random.default_rng(3)
    b = rng.normal(size=200)
    better, tie, worse = b - 1.0, b + 0.01 * rng.normal(size=200), b + 1.0
    cmp = {k: L.Comparison(a, b, "A", "B", "less", "e") for k, a in (("better", better), ("tie", tie), ("worse", worse))}
    assert [c.status() for c in cmp.values()] == ["reproduced", "not distinguishable", "contradicted"]
    two = L.Conjunction((("s1", cmp["better"]), ("s2", cmp["better"])))
    assert two.status() == "reproduced"
    assert L.Conjunction((("s1", cmp["better"]), ("s2", cmp["tie"]))).status() == "not distinguishable"
    assert L.Conjunction((("s1", cmp["tie"]), ("s2", cmp["worse"]))).status() == "contradicted"
    assert L.Conjunction((("s1", cmp["better"]), ("p", L.Proposition(False, "no")))).status() == "contradicted"
    d = two.to_dict()
    assert d["kind"] == "conjunction" and [p["status"] for p in d["parts"]] == ["reproduced"] * 2
    assert "s1: reproduced" in two.summary() and "s2: reproduced" in two.summary()
    claim = _claim(two)
    assert claim.status == "reproduced" and claim.to_dict()["evidence"]["kind"] == "conjunction"
    with pytest.raises(ValueError, match="at least two"):
        L.Conjunction((("s1", cmp["better"]),))
    with pytest.raises(ValueError, match="distinct"):
        L.Conjunction((("s1", cmp["better"]), ("s1", cmp["tie"])))
    with pytest.raises(TypeError, match="Comparison or a Proposition"):
        L.Conjunction((("s1", cmp["better"]), ("s2", L.Unverifiable("why"))))
    with pytest.raises(TypeError, match="pairs"):
        L.Conjunction("s1")


def test_comparison_refuses_thin_or_unpaired_evidence() -> None:
    with pytest.raises(ValueError, match="runs"):
        L.Comparison(np.ones(10), np.zeros(10), "A", "B", "less", "e")
    assert L.Comparison(np.ones(10), np.zeros(10), "A", "B", "less", "e", reason="cost").status() == "contradicted"
    with pytest.raises(ValueError, match="same number"):
        L.Comparison(np.ones(100), np.zeros(101), "A", "B", "less", "e")
    with pytest.raises(ValueError, match="claim"):
        L.Comparison(np.ones(100), np.zeros(100), "A", "B", "better", "e")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="finite"):
        L.Comparison(np.full(100, np.nan), np.zeros(100), "A", "B", "less", "e")
    with pytest.raises(ValueError, match="finite"):
        L.Comparison(np.full(100, -np.inf), np.zeros(100), "A", "B", "less", "e")


def test_identical_methods_are_not_distinguishable() -> None:
    x = np.arange(100.0)
    assert L.Comparison(x, x, "A", "B", "less", "e").status() == "not distinguishable"
    assert L.Comparison(x, x, "A", "B", "equal", "e").status() == "reproduced"


def test_one_margin_decides_better_worse_and_no_effect() -> None:
    rng = np.random.default_rng(5)
    b = rng.normal(50.0, 1.0, 200)
    noise = 0.001 * rng.normal(size=200)
    small_worse, small_better, large_better = b + 0.1 + noise, b - 0.1 + noise, b - 1.0 + noise
    # without a margin the sign decides, however small the difference
    assert L.Comparison(small_worse, b, "A", "B", "less", "e", margin=0).status() == "contradicted"
    assert L.Comparison(small_better, b, "A", "B", "less", "e", margin=0).status() == "reproduced"
    for a in (small_worse, small_better):
        c = L.Comparison(a, b, "A", "B", "less", "e", margin=0.2)
        assert c.within_margin() and c.status() == "not distinguishable"
        assert "within the margin" in c.summary() and c.to_dict()["margin"] == 0.2
        # the same interval and margin make a "no effect" claim hold
        assert L.Comparison(a, b, "A", "B", "equal", "e", margin=0.2).status() == "reproduced"
    # beyond the margin the sign rule stands; "no effect" is then contradicted
    assert L.Comparison(large_better, b, "A", "B", "less", "e", margin=0.2).status() == "reproduced"
    assert L.Comparison(large_better, b, "A", "B", "equal", "e", margin=0.2).status() == "contradicted"
    assert L.Comparison(small_better, b, "A", "B", "less", "e", margin=0.05).status() == "reproduced"
    for bad in (-0.1, float("nan"), float("inf")):
        with pytest.raises(ValueError, match="margin"):
            L.Comparison(small_better, b, "A", "B", "less", "e", margin=bad)
    for wrong in (True, "0.2", np.timedelta64(1, "s")):  # a wrong type: a TypeError (rule 6 of fusion._validation)
        with pytest.raises(TypeError, match="^margin"):
            L.Comparison(small_better, b, "A", "B", "less", "e", margin=wrong)  # type: ignore[arg-type]


def _claim(evidence: L.Evidence, **kw: object) -> L.Claim:
    kw.setdefault("link", "x")
    kw.setdefault("source", "yang2012optimal")
    return L.Claim(id="t-1", where="Table 2", claim="c", published="p",
                   evidence=evidence, **kw)  # type: ignore[arg-type]


def test_assumptions_and_alternatives_qualify_reproduced() -> None:
    ok, bad = L.Proposition(True, "yes"), L.Proposition(False, "no")
    assert _claim(ok).status == "reproduced"
    assert _claim(ok, assumptions=("noise level",)).status == "reproduced under stated assumptions"
    alt = L.Alternative("guard", "none", bad)
    c = _claim(ok, alternatives=(alt,))
    assert c.status == "reproduced under stated assumptions"
    assert c.robustness == "the claim holds under 0 of 1 other readings of the source's open choices"
    # readings that are not of the source's open choices are shown apart and do not qualify the status
    c = _claim(ok, alternatives=(L.Alternative("seed", "another seed", bad, kind="reseed"),))
    assert c.status == "reproduced" and c.robustness == "shown apart: 1 reseed"
    assert _claim(bad, alternatives=(L.Alternative("guard", "floor", ok),)).status == "contradicted"
    assert _claim(L.Unverifiable("no data")).status == "cannot be checked"


def test_claim_and_ledger_refuse_bad_records(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="source"):
        L.Claim(id="a", source="nobody", where="w", claim="c", published="p", evidence=L.Proposition(True, ""), link="x")
    with pytest.raises(ValueError, match="link"):
        _claim(L.Proposition(True, ""), link=" ")  # type: ignore[arg-type]
    with pytest.raises(TypeError):
        L.Proposition("yes", "")  # type: ignore[arg-type]
    led = L.Ledger("yang2012optimal")
    led.add(_claim(L.Proposition(True, "")))
    with pytest.raises(ValueError, match="duplicate"):
        led.add(_claim(L.Proposition(True, "")))
    with pytest.raises(ValueError, match="headline"):
        led.write(tmp_path)


def test_written_file_is_stable_and_digest_follows_content(tmp_path: Path) -> None:
    led = L.Ledger("yang2012optimal")
    led.add(_claim(L.PublishedValues([1.0], [1.0 + 1e-13], 1), headline=True))
    d1 = led.write(tmp_path)
    assert d1 == led.write(tmp_path)  # same records, same text
    rec = json.loads((tmp_path / "yang2012optimal.json").read_text())["claims"][0]
    assert rec["status"] == "reproduced" and rec["evidence"]["ours"] == [1.0]


def test_fmt_gives_peoples_numbers() -> None:
    assert [L.fmt(20.0), L.fmt(3), L.fmt(-0.0), L.fmt(0.000123456)] == ["20", "3", "0", "0.0001235"]
    assert "e" not in L.fmt(1.5e-9) and L.fmt(float("nan")) == "—"  # the book's one word for NaN (tables.NONFINITE_RULE)


# ----------------------------------------------------------------------------- committed records


def _rederive(ev: dict) -> str:
    kind = ev["kind"]
    if kind == "published":
        ok = all(o is not None and round(o, d) == round(p, d) for p, o, d in zip(ev["published"], ev["ours"], ev["decimals"]))
        return "reproduced" if ok else "not reproduced"
    if kind == "comparison":
        if ev["statistic"] == "infinite mean":
            where = "higher" if (ev["difference"] is None or ev["difference"] > 0) else "lower"
        else:
            lo = -math.inf if ev["ci_low"] is None else ev["ci_low"]   # a non-finite end is stored as null
            hi = math.inf if ev["ci_high"] is None else ev["ci_high"]
            where = R.region(lo, hi, ev["margin"])
        m, step = ev["margin"], ev["resolution"]
        ends = [x for x in (ev["ci_low"], ev["ci_high"]) if x is not None]
        at_margin = m > 0 and any(abs(abs(x) - m) <= step for x in ends)
        if at_margin:  # an interval end within one stored step of the margin: its side is the unrounded one
            where = ev["region"]
        assert where == ev["region"]
        return R.status_from_region(where, ev["claim"])
    if kind == "proposition":
        return "reproduced" if ev["holds"] else "contradicted"
    if kind == "exact comparison":
        d = ev["a"] - ev["b"]
        scale = max(abs(ev["a"]), abs(ev["b"]))  # R2's scale: an end within round-off of +-m is the margin
        where = "equivalent" if d == 0.0 and ev["margin"] == 0.0 else R.region(d, d, ev["margin"], scale=scale)
        assert where == ev["region"]
        return R.status_from_region(where, ev["claim"])
    if kind == "conjunction":
        st = [_rederive(p["evidence"]) for p in ev["parts"]]
        assert st == [p["status"] for p in ev["parts"]]
        return ("contradicted" if "contradicted" in st else "reproduced" if all(x == "reproduced" for x in st)
                else "not distinguishable")
    assert kind == "unverifiable", kind
    return "cannot be checked"


def test_every_committed_record_has_a_rule_derived_status() -> None:
    for path in LEDGER_FILES:
        data = json.loads(path.read_text(encoding="utf-8"))
        assert data["source"] in L.SOURCES
        src = L.SOURCES[data["source"]]
        chapter = data.get("chapter", src.chapter)
        assert path.name == src.ledger_file(chapter), f"{path.name}: not the file of {chapter}"
        want = int(chapter == src.chapter)
        assert sum(r["headline"] for r in data["claims"]) == want, f"{path.name}: one headline per source"
        ids = [r["id"] for r in data["claims"]]
        assert len(ids) == len(set(ids)), f"{path.name}: duplicate ids"
        for r in data["claims"]:
            assert r["status"] in L.STATUSES
            assert r["claimant"] in R.CLAIMANTS and (r["claimant"] == "source" or not r["headline"]), r["id"]
            primary = _rederive(r["evidence"])
            assert r["primary_status"] == primary, r["id"]
            readings = [(a["kind"], _rederive(a["evidence"]), a["runs"]) for a in r["alternatives"]]
            assert [a["status"] for a in r["alternatives"]] == [x[1] for x in readings], r["id"]
            assert r["status"] == R.record_status(primary, readings, r["runs"], bool(r["assumptions"]))[0], r["id"]
            if r["evidence"]["kind"] == "comparison" and r["evidence"]["runs"] < L.MIN_RUNS:
                assert r["evidence"]["reason"], f"{r['id']}: fewer than {L.MIN_RUNS} runs and no reason"


@pytest.mark.parametrize("path", LEDGER_FILES, ids=lambda p: p.name)
def test_every_record_links_to_evidence_in_its_chapter(path: Path) -> None:
    data = json.loads(path.read_text(encoding="utf-8"))
    chapter = data.get("chapter", L.SOURCES[data["source"]].chapter)
    text = _chapter_markdown(chapter, appendix=True)  # evidence may sit in the chapter's appendix
    labels = {m["name"] or m["opt"] for m in LABEL.finditer(text)}
    for r in data["claims"]:
        assert r["chapter"] == chapter
        for target in (r["link"], *r["critiques"]):
            assert target in labels, f"{r['id']}: {target!r} is not a label in {chapter}"


@pytest.mark.parametrize("path", LEDGER_FILES, ids=lambda p: p.name)
def test_every_critique_box_maps_to_a_record(path: Path) -> None:
    data = json.loads(path.read_text(encoding="utf-8"))
    text = _chapter_markdown(data.get("chapter", L.SOURCES[data["source"]].chapter), appendix=True)
    covered = {r["link"] for r in data["claims"]} | {c for r in data["claims"] for c in r["critiques"]}
    boxes = set(CRITIQUE_NAME.findall(text))
    missing = sorted(boxes - covered)
    assert not missing, f"critique boxes without a ledger record: {missing}"


@pytest.mark.parametrize("key,chapter", [(k, c) for k in sorted(L.SOURCES) for c in L.SOURCES[k].chapters])
def test_chapter_opens_with_its_in_brief_box(key: str, chapter: str) -> None:
    src = L.SOURCES[key]
    assert (ROOT / "book" / "ledger" / src.ledger_file(chapter)).exists(), f"no ledger for {key} in {chapter}"
    text = _chapter_markdown(chapter)
    first_heading = text.find("\n## ")
    opening = text[: first_heading if first_heading > 0 else None]
    assert f"{{fusion-in-brief}} {key}" in opening, (
        f"{chapter} must open with the In-brief box of {key} before its first section"
    )
    if len(src.chapters) > 1:  # a source spanning several chapters: each box shows its own chapter's claims
        assert f":chapter: {chapter}" in opening, f"{chapter}: the In-brief box must name its chapter"


def test_every_source_has_one_headline_over_its_files() -> None:
    heads: dict[str, int] = {}
    for path in LEDGER_FILES:
        data = json.loads(path.read_text(encoding="utf-8"))
        heads[data["source"]] = heads.get(data["source"], 0) + sum(r["headline"] for r in data["claims"])
    assert all(n == 1 for n in heads.values()), heads


def test_multi_chapter_source_writes_one_file_per_chapter(tmp_path: Path) -> None:
    src = L.SOURCES["lecture003"]
    assert src.chapters[0] == src.chapter and len(src.chapters) == 3
    assert [src.ledger_file(c) for c in src.chapters] == ["lecture003-02.json", "lecture003-03.json",
                                                          "lecture003-04.json"]
    assert L.SOURCES["yang2012optimal"].ledger_file() == "yang2012optimal.json"
    with pytest.raises(ValueError, match="chapter"):
        src.ledger_file("notebooks/01_optimal_fusion_set")
    with pytest.raises(ValueError, match="chapter"):
        L.Ledger("lecture003", chapter="notebooks/05_covariance_intersection")
    second = L.Ledger("lecture003", chapter=src.chapters[1])
    second.add(_claim(L.PublishedValues([1.0], [1.0 + 1e-13], 1), source="lecture003"))
    second.write(tmp_path)
    data = json.loads((tmp_path / "lecture003-03.json").read_text(encoding="utf-8"))
    assert data["chapter"] == src.chapters[1]
    assert [r["chapter"] for r in data["claims"]] == [src.chapters[1]]
    # the headline of a multi-chapter source belongs to its first chapter only
    bad = L.Ledger("lecture003", chapter=src.chapters[2])
    bad.add(_claim(L.PublishedValues([1.0], [1.0 + 1e-13], 1), source="lecture003", headline=True))
    with pytest.raises(ValueError, match="headline"):
        bad.write(tmp_path)
    first = L.Ledger("lecture003")
    assert first.chapter == src.chapter
    first.add(_claim(L.PublishedValues([1.0], [1.0 + 1e-13], 1), source="lecture003"))
    with pytest.raises(ValueError, match="headline"):
        first.write(tmp_path)


def test_source_chapters_validation() -> None:
    with pytest.raises(ValueError, match="chapters"):
        L.Source("k", "K (2000)", "T", "notebooks/a", 1, ("notebooks/b",))
    with pytest.raises(ValueError, match="chapters"):
        L.Source("k", "K (2000)", "T", "notebooks/a", 1, ("notebooks/a", "notebooks/a"))
    with pytest.raises(TypeError, match="chapters"):
        L.Source("k", "K (2000)", "T", "notebooks/a", 1, ["notebooks/a"])
    assert L.Source("k", "K (2000)", "T", "notebooks/a", 1).chapters == ("notebooks/a",)


def test_summary_reports_median_share_and_runs_that_dominate() -> None:
    b = np.zeros(200)
    a = np.full(200, -0.01)
    a[0] = 1e6  # one run carries the whole mean
    c = L.Comparison(a, b, "A", "B", "less", "e", margin=0.001)
    text = c.summary()
    # one run carries the whole mean: heavy-tailed, reported with the median (R3); the mean decides (R2)
    assert "median difference -0.01" in text and "A lower in 199 of 200 runs" in text
    assert "heavy-tailed" in text and "the mean, which decides" in text
    assert c.judgement().rule == "R2" and c.judgement().heavy and c.status() == "not distinguishable"
    light = L.Comparison(np.full(200, -1.0) + np.arange(200) * 1e-3, b, "A", "B", "less", "e", margin=0.001)
    assert "heavy-tailed" not in light.summary() and light.judgement().statistic == "mean"


def test_book_extension_orders_a_multi_chapter_source_by_chapter() -> None:
    import importlib.util

    spec = importlib.util.spec_from_file_location("fusion_book_ext", ROOT / "book" / "_ext" / "fusion_book.py")
    ext = importlib.util.module_from_spec(spec)
    assert spec.loader is not None
    spec.loader.exec_module(ext)
    recs = ext._ledger(ROOT)
    orders = [L.SOURCES[r["source"]].order for r in recs]
    assert orders == sorted(orders), "sources in book order"
    lec = [r for r in recs if r["source"] == "lecture003"]
    assert lec, "no lecture ledger"
    chapters = L.SOURCES["lecture003"].chapters
    pos = [chapters.index(r["chapter"]) for r in lec]
    assert pos == sorted(pos), "a source's claims follow its chapters in reading order"
    assert set(pos) == set(range(len(chapters))), "every chapter of the lecture has claims"


# ----------------------------------------------------------------------------- stored precision


@given(st.lists(st.floats(-1e3, 1e3, allow_nan=False), min_size=3, max_size=30),
       st.floats(-50.0, 50.0, allow_nan=False), st.floats(1e-6, 1e6))
def test_the_stored_interval_rederives_the_status(noise: list[float], shift: float, scale: float) -> None:
    """Rounding to the resolution never moves an interval end across zero."""
    b = scale * (10.0 + np.arange(len(noise)))
    a = b + scale * (shift + 0.01 * np.asarray(noise))
    c = L.Comparison(a, b, "A", "B", "less", "m", reason="property test", margin=0.0)
    d = c.to_dict()
    assert _rederive(d) == c.status()
    assert d["ci_low"] <= d["difference"] <= d["ci_high"] or c.status() == "not distinguishable"


def test_round_off_of_the_runs_does_not_reach_the_stored_comparison() -> None:
    """Runs that differ at 10⁻⁹ relative (another BLAS kernel) store the same record."""
    rng = np.random.default_rng(5)
    a, b = 57.0 + rng.normal(size=100), 57.0 + rng.normal(size=100)
    c1 = L.Comparison(a, b, "A", "B", "less", "m")
    c2 = L.Comparison(a * (1 + 1e-9 * rng.normal(size=100)), b, "A", "B", "less", "m")
    assert c1.resolution() == 0.01
    assert c1.to_dict() == c2.to_dict() and c1.summary() == c2.summary()
    assert c1.to_dict()["mean_a"] == round(float(np.mean(a)), 2)


def test_equal_runs_are_ties_not_wins() -> None:
    a = np.arange(1.0, 101.0)
    c = L.Comparison(a, a + 1e-14 * (-1.0) ** np.arange(100), "A", "B", "less", "m")
    assert "A lower in 0 of 100 runs" in c.summary()


def test_round_off_differences_tie_whatever_their_sign() -> None:
    """Two methods equal to round-off in every run (the equal-weights fallback against the mean) tie: their sign
    of round-off, which moves with the BLAS kernel, never decides 'better' or 'worse'."""
    a = 0.0137 + np.random.default_rng(6).random(300)
    for eps in (-2.2e-16, 1.5e-15, 3e-17):
        c = L.Comparison(a + eps, a, "A", "B", "less", "m")
        assert c.interval() == (0.0, 0.0, 0.0) and c.status() == "not distinguishable"
    # a real difference, however uniform, still counts
    assert L.Comparison(a - 1e-6, a, "A", "B", "less", "m", margin=0.0).status() == "reproduced"


def test_ties_are_judged_run_by_run_not_against_a_heavy_tailed_mean() -> None:
    """One huge run must not turn real per-run differences of the others into ties (review 2, A10.9)."""
    b = 0.01 + 0.001 * np.random.default_rng(7).random(300)
    a = b - 0.005
    a[0] = 3e9   # a heavy tail: the mean of A is 10⁷, the typical squared error 0.005
    c = L.Comparison(a, b, "A", "B", "less", "m")
    assert "A lower in 299 of 300 runs" in c.summary()


def test_a_proposition_with_runs_is_stochastic() -> None:
    """A yes/no computed from Monte-Carlo runs carries its run count: R4 applies and the sweep covers it."""
    from fusion.book.ledger import Alternative, Proposition
    from fusion.book.ledger.evidence import _runs

    exact = Proposition(True, "holds")
    mc = Proposition(False, "fails in 3 of 100 runs", runs=100)
    assert _runs(exact) is None and _runs(mc) == 100
    assert "runs" not in exact.to_dict() and mc.to_dict()["runs"] == 100
    few = Alternative("fewer", "fewer runs", Proposition(True, "holds in 50 runs", runs=50))
    assert few.counted(100) == (False, "underpowered")
    with pytest.raises(ValueError, match="runs"):
        Proposition(True, "x", runs=0)
    with pytest.raises(TypeError, match="runs"):
        Proposition(True, "x", runs=True)


@pytest.mark.parametrize("margin", [3.3e-5, 7.17e-6, 1e-12, 0.000713, 2.53, 7.254e6])
def test_record_margin_shown_at_three_digits(margin: float) -> None:
    """A record's margin is stored as its summary prints it (three significant digits), at any scale."""
    from fusion.book.ledger import Claim, Comparison

    rng = np.random.default_rng(3)
    a = 1.0 + rng.standard_normal(100)
    ev = Comparison(a, a + 0.1, "A", "B", "less", "e", 3, margin=margin)
    c = Claim("yang-x", "yang2012optimal", "toy", "A beats B.", "qualitative", ev, "x")
    assert c.to_dict()["margin"] == float(f"{margin:.3g}")


def test_resolution_ignores_a_side_declared_infinite() -> None:
    """The finite runs of a side whose mean is infinite (R3, closed form) do not set the rounding scale."""
    from fusion.book.ledger import Comparison

    rng = np.random.default_rng(5)
    a = 2000.0 + 500.0 * rng.standard_normal(100) ** 2       # huge finite runs of an infinite-mean estimator
    b = 2.34 + 0.1 * rng.standard_normal(100)
    declared = Comparison(a, b, "A", "B", "less", "mse", 5, infinite_mean=("a",))
    plain = Comparison(a, b, "A", "B", "less", "mse", 5)
    assert declared.resolution() == 1e-3 and plain.resolution() == 1.0
    both = Comparison(a, b, "A", "B", "less", "mse", 5, infinite_mean=("a", "b"))
    assert both.resolution() == plain.resolution()


def test_published_values_with_runs_are_stochastic() -> None:
    """Published values recomputed from Monte-Carlo runs carry the run count (R4, the reseeding sweep)."""
    from fusion.book.ledger import PublishedValues
    from fusion.book.ledger.evidence import _runs

    exact = PublishedValues([0.05], [0.0962], 2)
    mc = PublishedValues([0.05], [0.0962], 2, "mrad", runs=200)
    assert _runs(exact) is None and _runs(mc) == 200 and mc.status() == exact.status() == "not reproduced"
    assert "runs" not in exact.to_dict() and mc.to_dict()["runs"] == 200
    with pytest.raises(ValueError, match="runs"):
        PublishedValues([1.0], [1.0], 0, runs=-3)


def test_a_heavy_tailed_member_of_a_conjunction_shows_median_and_share() -> None:
    """R3 for every member: a heavy-tailed comparison inside a group prints its median and share of runs won."""
    from fusion.book.ledger import Comparison, Conjunction

    rng = np.random.default_rng(11)
    d = rng.standard_cauchy(300)
    heavy = Comparison(1.0 + d, np.ones(300), "A", "B", "less", "e", 11)
    light = Comparison(rng.normal(0.0, 1.0, 300), rng.normal(1.0, 1.0, 300), "A", "B", "less", "e", 11)
    assert heavy.judgement().heavy and not light.judgement().heavy
    text = Conjunction([("first", heavy), ("second", light)]).summary()
    first, second = text.split("first: ")[1].split("; second: ")
    assert "heavy-tailed: median" in first and "of 300 runs" in first and "heavy-tailed" not in second


def test_an_exact_difference_at_round_off_is_shown_as_its_bound():
    """Two BLAS kernels give -3.638e-12 and -1.819e-12 for one round-off difference of values near 1.5e4: one text."""
    from fusion.book.exact import ExactComparison

    texts = {ExactComparison(15110.0, 15110.0 + d, "A", "B", "less", "tr P").summary() for d in (3.638e-12, 1.819e-12, 0.0)}
    assert texts == {"A 1.511×10^4 vs B 1.511×10^4 (tr P, exact); difference less than 10⁻¹² relative (round-off); "
                     "margin ±755.5; within the margin: no difference that matters"}
    assert "difference -1 (-50.0% of B)" in ExactComparison(1.0, 2.0, "A", "B", "less", "m").summary()
    assert "difference 0;" in ExactComparison(0.0, 0.0, "A", "B", "equal", "m", margin=0.1).summary()


def test_no_record_prints_round_off_digits():
    """No text of the ledger writes a number below 10⁻¹² in digits (``2.0 × 10⁻¹⁵``, ``8e-16``): such a number is
    round-off, whose digits move with the BLAS kernel (OpenBLAS's Haswell and SkylakeX kernels gave 2.0 and 1.8 ×
    10⁻¹⁵ for one residual), so the committed ledger failed on another machine; :func:`fusion.book.tables.roundoff`
    writes its bound instead."""
    import re
    from fusion.book.ledger import ledger_dir

    tiny = re.compile(r"(?:×\s?10⁻(?:1[3-9]|[2-9]\d)|\d[eE]-(?:1[3-9]|[2-9]\d)\b)")
    found = [(path.name, m.group(0)) for path in sorted(ledger_dir().glob("*.json"))
             for m in tiny.finditer(path.read_text(encoding="utf-8"))]
    assert not found, found


# --- the book's files from a working directory outside the repository (fuzz 17, class F) ----------------------------


def test_the_books_files_are_found_from_a_working_directory_outside_the_repository(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Without ``start``, the search falls back to the repository the package was imported from: the functions that
    read the claim files and the ledger work from any working directory."""
    from fusion.book import claims as C
    from fusion.book.chapters import ci, time_registration_ledger as trl
    from fusion.book.chapters.ci import constants

    import fusion

    repo = Path(fusion.__file__).resolve().parents[1]
    monkeypatch.chdir(tmp_path)
    constants.claim_file.cache_clear()            # read again, from here
    assert L.ledger_dir() == repo / "book" / "ledger"
    assert C.claims_dir() == repo / "book" / "claims"
    assert C.load_all()
    assert ci.margin_numbers()
    assert len(trl.exact_check(1.0)) > 0
    constants.claim_file.cache_clear()


def test_a_start_outside_the_repository_and_a_package_without_the_book_are_refused_by_name(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """An explicit ``start`` outside any repository is not redirected; an installed package (no ``_toc.yml`` above
    it) names what is missing."""
    from fusion.book.ledger import store

    with pytest.raises(FileNotFoundError, match=r"start: no _toc\.yml"):
        L.ledger_dir(tmp_path)
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(store, "_REPOSITORY", tmp_path / "site-packages")
    with pytest.raises(FileNotFoundError, match=r"no _toc\.yml in the working directory .* installed package"):
        L.ledger_dir()


def test_a_worktree_working_directory_wins_over_the_package(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """The working directory's repository comes first (a worktree's tests and notebooks read their own book)."""
    (tmp_path / "_toc.yml").write_text("root: intro\n", encoding="utf-8")
    (tmp_path / "sub").mkdir()
    monkeypatch.chdir(tmp_path / "sub")
    assert L.ledger_dir() == tmp_path.resolve() / "book" / "ledger"
