"""Fuzz 29a, cases C3, C4, C6 and D1 (issue 35), by class.

* C3 (a rulebook decision, R2 "round-off never decides" at the margin's edge as at zero): an interval end within
  round-off of ±m (1e-9 S, S the comparison's scale, at least m) is the margin, and an interval wholly inside the closed
  [-m, m] is equivalent, one rule in :func:`fusion.book.rulebook.region` for ``judge_paired``, the ledger's
  ``Comparison`` and ``ExactComparison``: 0.3 - 0.2 and 1.3 - 1.2 against 0.1 were reproduced and contradicted. At
  m = 0 nothing changes (no interval is equivalent).
* C4: ``fusion_study(published_omega=1e-300)`` named the inner ``omega``; it is refused by its own name.
* C6: an integer float64 cannot hold exactly (beyond 2**53) was rounded silently by ``PublishedValues`` (2**53 + 1
  against 2**53 at 0 decimals "reproduced") and ``side_by_side``; it is refused by name (``fusion._limits``).
* D1 (decided: fixed): a claim-file text holds no control or format character (NUL, a direction override, a zero-width
  space, a BOM) and a required one holds a visible character; invisible texts loaded as non-empty.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import yaml
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from fusion.book import claims as C
from fusion.book import ledger as L
from fusion.book import rulebook as R
from fusion.book.exact import ExactComparison as EC
from fusion.book.tables import side_by_side

HYP = settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])


# --- C3: the margin's edge is decided by the rule, never by the last ulp ----------------------------------------------

@pytest.mark.parametrize("a,b,m", [(0.3, 0.2, 0.1), (1.3, 1.2, 0.1), (3.0, 2.0, 1.0), (13.0, 12.0, 1.0)])
def test_c3_a_difference_equal_to_the_margin_is_equivalent_whatever_its_last_ulp(a, b, m):
    runs = 100
    for s in (1.0, -1.0):  # d = +m and d = -m
        x, y = (a, b) if s > 0 else (b, a)
        j = R.judge_paired(np.full(runs, x), np.full(runs, y), "equal", m)
        assert (j.region, j.status) == ("equivalent", "reproduced")
        assert L.Comparison(np.full(runs, x), np.full(runs, y), "A", "B", "equal", "e", margin=m).status() == "reproduced"
        for claim, want in (("equal", "reproduced"), ("less", "not distinguishable"), ("greater", "not distinguishable")):
            assert EC(x, y, "A", "B", claim, "q", margin=m).status() == want


@HYP
@given(b=st.floats(-1e3, 1e3).filter(lambda x: x == 0 or abs(x) > 1e-100), m=st.floats(1e-3, 1e2), k=st.sampled_from([1.0, 10.0, 0.1, 3.0]))
@example(b=0.2, m=0.1, k=10.0)
@example(b=1.2, m=0.1, k=1.0)
def test_c3_property_an_end_within_round_off_of_the_margin_is_the_margin(b, m, k):
    """a = b + m computed in float64 is d = m up to round-off: every comparison calls it equivalent, in any units."""
    a = b + m
    for f in (1.0, k):
        assert R.judge_paired(np.full(6, a * f), np.full(6, b * f), "equal", m * f).region == "equivalent"
        assert EC(a * f, b * f, "A", "B", "equal", "q", margin=m * f).region() == "equivalent"
    scale = max(abs(a), abs(b))
    assert R.region(m + 1e-10 * m, 2 * m, m, scale=scale) == "higher"  # within round-off: the margin, not inside
    assert R.region(-m * (1 + 1e-13), m * (1 + 1e-13), m) == "equivalent"


@pytest.mark.parametrize("m", [0.1, 1.0, 1e-6])
def test_c3_beyond_round_off_the_margin_still_decides(m):
    """Valid input keeps its status: an end more than round-off outside the margin is outside it."""
    out = m * (1 + 1e-6)
    assert R.region(out, out, m) == "higher" and R.region(-out, -out, m) == "lower"
    assert EC(out, 0.0, "A", "B", "equal", "q", margin=m).status() == "contradicted"
    assert R.region(m, m, m) == R.region(-m, m, m) == "equivalent"  # the closed interval: its ends are inside
    assert R.region(m * (1 - 1e-6), m * (1 - 1e-6), m) == "equivalent"


def test_c3_margin_zero_keeps_its_behaviour():
    """At m = 0 no interval is equivalent and no end is snapped (a tie there is undecided)."""
    assert R.region(0.0, 0.0, 0.0) == R.region(-1.0, 1.0, 0.0, scale=10.0) == "undecided"
    assert R.region(1e-12, 1.0, 0.0, scale=1.0) == "higher" and R.region(-1.0, -1e-12, 0.0, scale=1.0) == "lower"
    assert R.judge_paired(np.full(6, 1.0), np.full(6, 1.0), "equal", 0.0).status == "not distinguishable"


def test_c3_the_scale_keyword_is_validated_by_name():
    with pytest.raises(ValueError, match="scale"):
        R.region(0.0, 1.0, 0.5, scale=-1.0)
    with pytest.raises(TypeError, match="scale"):
        R.region(0.0, 1.0, 0.5, scale="1")  # type: ignore[arg-type]


# --- C4: the caller's argument is named --------------------------------------------------------------------------------

@pytest.mark.parametrize("omega", [1e-300, 1e-200, 5e-324, -1e-300])
def test_c4_fusion_study_names_published_omega(omega):
    """A tiny non-zero weight is refused as fuse_tracks refuses it as omega, but by the caller's name."""
    from fusion.scenarios.two_sensor import Scenario, fusion_study
    sc = object.__new__(Scenario)  # refused before the scenario is read
    with pytest.raises(ValueError, match="^published_omega"):
        fusion_study(sc, published_omega=omega)


# --- C6: integers float64 cannot hold --------------------------------------------------------------------------------

@pytest.mark.parametrize("big", [np.array([2**53 + 1]), [10**17 + 1], np.array([2**63 - 1], dtype=np.uint64),
                                 [2**64 + 2], np.array([-(2**53) - 1])])
def test_c6_an_integer_beyond_float64_is_refused_by_name(big):
    with pytest.raises(ValueError, match=r"^published\[0\] is an integer that float64 cannot hold"):
        L.PublishedValues(big, [1.0], 0)
    with pytest.raises(ValueError, match=r"^ours\[1\] is an integer"):
        L.PublishedValues([1, 2], [1] + list(np.atleast_1d(big).tolist()), 0)
    with pytest.raises(ValueError, match=r"^reproduced\[0\] is an integer"):
        side_by_side([1.0], big, [1], decimals=0)


@HYP
@given(k=st.integers(-(2**63), 2**63 - 1))
@example(k=2**53 + 1)
@example(k=2**53)
@example(k=2**60)
def test_c6_property_an_integer_is_compared_as_itself_or_refused(k):
    """Every int64: held exactly (then compared as itself: reproduced against itself, not against k + 1 when held) or
    refused naming published[0]."""
    pub = np.array([k], dtype=np.int64)
    if float(k) == k:
        assert L.PublishedValues(pub, pub, 0).status() == "reproduced"
        assert side_by_side(pub, pub, [1], decimals=0)["difference"].iloc[0] == 0
    else:
        with pytest.raises(ValueError, match=r"published\[0\]"):
            L.PublishedValues(pub, [float(k)], 0)


# --- D1: claim-file texts ----------------------------------------------------------------------------------------------

YANG = "yang2012optimal.yaml"
INVISIBLE = ["\u200b", "\u200d", "\u200f", "\u2060", "\ufeff", "\u0301", "\u202eabc", "a\x00b", " \u00a0", "x\u200b"]


@pytest.fixture(scope="module")
def yang() -> C.ClaimsFile:
    return C.load(C.claims_dir() / YANG)


@pytest.mark.parametrize("bad", INVISIBLE)
@pytest.mark.parametrize("field", ["where", "claim", "chapter"])
def test_d1_a_record_text_without_a_visible_character_or_with_a_control_is_refused(yang, bad, field):
    with pytest.raises(ValueError, match=f"{field} (must not be empty|holds the invisible)"):
        dataclasses.replace(yang.records[0], **{field: bad})


@pytest.mark.parametrize("bad", ["\u200b", "\u0301", "mae\u200b", "\u202eabc"])
def test_d1_quantity_keys_and_labels_follow_the_same_rule(yang, bad):
    q, entry = next(iter(yang.quantities.items()))
    with pytest.raises(C.ClaimsFileError, match="field label"):
        dataclasses.replace(yang, quantities={**yang.quantities, q: {**entry, "label": bad}})
    with pytest.raises(C.ClaimsFileError, match="quantity key"):
        dataclasses.replace(yang, quantities={bad: entry})


def test_d1_load_applies_the_rule(tmp_path):
    d = yaml.safe_load((C.claims_dir() / YANG).read_text(encoding="utf-8"))
    d["records"][0]["where"] = "\u200b"
    p = tmp_path / YANG
    p.write_text(yaml.safe_dump(d, allow_unicode=True), encoding="utf-8")
    with pytest.raises(C.ClaimsFileError, match="field where holds the invisible"):
        C.load(p)


@pytest.mark.parametrize("good", ["e\u0301t\u00e9 (°C)", "ω ≤ 1", "数据融合", "a\tb", "line one\nline two"])
def test_d1_visible_texts_in_any_script_still_load(yang, good):
    assert dataclasses.replace(yang.records[0], where=good).where == good
