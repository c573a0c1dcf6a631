"""Fuzz 24a, classes J and K and debatables D1 and D5 (issue 35): the rulebook's judging and the claim data.

J: :func:`fusion.book.rulebook.judge_paired` (and :class:`fusion.book.ledger.Comparison`, which it judges) used an
absolute round-off threshold, so per-run values in small units got a zero-width interval and a status decided by
noise; the tie and constant-differences tests are now the rulebook's one relative tie rule. K: the claim schema's
identifier patterns match the whole text (``$`` let a final newline through). D1: a :class:`Claim`'s ``id`` follows
the claim files' pattern. D5: a published value has at most its printed decimals.
"""

from __future__ import annotations

import copy
import functools
import json
import math
from pathlib import Path

import jsonschema
import numpy as np
import pytest
import yaml
from hypothesis import example, given, settings, strategies as st

from fusion.book import claims as C
from fusion.book import ledger as L
from fusion.book import rulebook as R

ROOT = Path(__file__).resolve().parents[1]


# --- J: judging does not depend on the units of the runs ------------------------------------------------------------

def _noise(scale: float):
    rng = np.random.default_rng(1)
    d, b = rng.normal(0, 1, 200), np.abs(rng.normal(5, 1, 200))
    return (b + d) * scale, b * scale


@pytest.mark.parametrize("scale", [1.0, 1e-6, 1e-12, 1e-13, 1e-14, 1e-20, 1e6])
def test_j_noise_is_not_distinguishable_in_any_unit(scale):
    a, b = _noise(scale)
    j = R.judge_paired(a, b, "greater", 0.0)
    assert j.status == "not distinguishable" and j.low < j.estimate < j.high
    assert R.judge_paired(np.array([1.0, 3.0] * 100) * scale, np.full(200, 2.0) * scale, "less", 0.0).status \
        == "not distinguishable"


def test_j_comparison_of_small_units_prints_an_interval():
    a, b = _noise(1e-13)
    c = L.Comparison(a, b, "A", "B", "greater", "mse", seed=1)
    j = c.judgement()
    assert j.low < j.high and c.status() == "not distinguishable"
    assert j.low / 1e-13 == pytest.approx(R.judge_paired(*_noise(1.0), "greater", 0.0).low, rel=1e-9)


@settings(max_examples=60, deadline=None)
@given(st.integers(2, 40), st.integers(0, 2**32 - 1), st.sampled_from(["noise", "constant", "tie", "two-valued"]),
       st.integers(-60, 60), st.sampled_from(["less", "greater", "equal"]), st.sampled_from([0.0, 0.05, 1.0]))
@example(2, 0, "two-valued", -43, "less", 0.0)
def test_j_status_is_invariant_under_a_change_of_units(half, seed, shape, k, direction, margin):
    rng = np.random.default_rng(seed)
    n = 2 * half
    b = rng.uniform(1.0, 10.0, n)
    d = {"noise": rng.normal(0.3, 1.0, n), "constant": np.full(n, 0.25), "tie": np.zeros(n),
         "two-valued": np.array([-1.0, 1.0] * half)}[shape]
    a = b + d
    s = 2.0 ** k  # exact: every test of the rulebook must give the same answer
    j1, j2 = R.judge_paired(a, b, direction, margin), R.judge_paired(a * s, b * s, direction, margin * s)
    assert (j2.status, j2.region, j2.statistic) == (j1.status, j1.region, j1.statistic)
    for x1, x2 in ((j1.estimate, j2.estimate), (j1.low, j2.low), (j1.high, j2.high)):
        assert x2 == pytest.approx(x1 * s, rel=1e-12, abs=0.0)


@pytest.mark.parametrize("scale", [1.0, 2.0**-45, 2.0**-70, 2.0**40])
def test_j_deterministic_differences_keep_their_zero_width_interval(scale):
    b = np.arange(1.0, 201.0) * scale
    j = R.judge_paired(b + 0.5 * scale, b, "greater", 0.0)   # the same difference in every run (exact)
    assert (j.status, j.estimate, j.low, j.high) == ("reproduced", 0.5 * scale, 0.5 * scale, 0.5 * scale)
    t = R.judge_paired(b, b.copy(), "greater", 0.0)          # every run a tie
    assert (t.status, t.estimate, t.low, t.high, t.region) == ("not distinguishable", 0.0, 0.0, 0.0, "undecided")


def test_j_differences_all_within_round_off_are_a_tie_not_a_sign():
    # every |A - B| below the tie rule's 1e-9 of the runs' magnitude, of both signs: a tie, never a decided sign
    b = np.full(200, 1.0)
    a = b + np.array([5e-10, -3e-10] * 100)
    j = R.judge_paired(a, b, "greater", 0.0)
    assert (j.status, j.estimate, j.low, j.high) == ("not distinguishable", 0.0, 0.0, 0.0)
    assert not R._runs_won(a, b, "greater").any()   # the same rule as a single run's tie


# --- K: the claim schema's identifiers match the whole text -------------------------------------------------------

@functools.cache
def _lecture003() -> dict:
    """The committed claims file, parsed once (every test below changes a deep copy)."""
    return yaml.safe_load((C.claims_dir() / "lecture003.yaml").read_text(encoding="utf-8"))


def _first_reading(doc: dict) -> dict:
    return next(r["readings"]["others"][0] for r in doc["records"] if r.get("readings", {}).get("others"))


_FIELDS = {"key": lambda doc: (_first_reading(doc), "key"),
           "id": lambda doc: (doc["records"][0], "id"),
           "evidence": lambda doc: (next(r for r in doc["records"] if "evidence" in r), "evidence")}


@pytest.mark.parametrize("field", sorted(_FIELDS))
@pytest.mark.parametrize("tail", ["\n", "\r\n", " ", "\n\n"])
def test_k_schema_refuses_an_identifier_with_a_trailing_newline(tmp_path, field, tail):
    doc = _lecture003()
    plain = json.loads(json.dumps(C.SCHEMA, default=dict))
    assert not list(jsonschema.Draft202012Validator(plain).iter_errors(doc))   # the committed file passes
    bad = copy.deepcopy(doc)
    obj, name = _FIELDS[field](bad)
    obj[name] = obj[name] + tail
    assert list(jsonschema.Draft202012Validator(plain).iter_errors(bad)), f"{field} {obj[name]!r} passes the schema"
    p = tmp_path / "lecture003.yaml"
    p.write_text(yaml.safe_dump(bad, allow_unicode=True), encoding="utf-8")
    with pytest.raises(C.ClaimsFileError, match=field):
        C.load(p)


def test_k_reading_spec_checks_its_key_whole():
    assert C.ReadingSpec("typical-run", "c", "r", "open-choice", {}).key == "typical-run"
    assert C.ReadingSpec("primary", "", "", "primary", {}).key == "primary"
    for key in ("typical-run\n", "Typical", "-run", "typical run", "typical_run"):
        with pytest.raises(ValueError, match="key"):
            C.ReadingSpec(key, "c", "r", "open-choice", {})


# --- D1: a Claim's id follows the claim files' pattern ------------------------------------------------------------

def _claim(cid: str) -> L.Claim:
    return L.Claim(cid, "yang2012optimal", "Table 1", "A is smaller", "qualitative", L.Proposition(True, "holds"),
                   "sec-x")


@pytest.mark.parametrize("cid", ["yang-x\x00", "\ufeffyang-x", "Yang X!", "yang-x\n", "\uff59\uff41\uff4e\uff47-x",
                                 "yang", "yang--x", "yang-x-", "yang_x"])
def test_d1_claim_id_outside_the_pattern_is_refused(cid):
    with pytest.raises(ValueError, match="id"):
        _claim(cid)


def test_d1_every_committed_id_fits_the_pattern():
    assert _claim("yang-x").id == "yang-x" and _claim("lec-2-b3").id == "lec-2-b3"
    for path in sorted((ROOT / "book" / "ledger").glob("*.json")):
        for r in json.loads(path.read_text(encoding="utf-8")).get("claims", []):
            assert _claim(r["id"]).id == r["id"]


# --- D5: a published value has at most its printed decimals -------------------------------------------------------

@pytest.mark.parametrize("published,decimals", [([1.25], 1), ([1.25, 2.0], [1, 1]), ([7.5], 0)])
def test_d5_published_value_longer_than_its_decimals_is_refused(published, decimals):
    with pytest.raises(ValueError, match=r"published\[0\].*decimals"):
        L.PublishedValues(published, [1.0] * len(published), decimals)


@settings(max_examples=80, deadline=None)
@given(st.integers(-10**9, 10**9), st.integers(0, 6), st.integers(0, 4))
def test_d5_a_printed_value_is_accepted_at_its_decimals_and_more(m, d, extra):
    p = float(f"{m}e-{d}")   # the number a source prints with d decimals
    assert L.PublishedValues([p], [p], d + extra).status() == "reproduced"
    assert math.isfinite(L.PublishedValues([p], [p], d).published[0])
