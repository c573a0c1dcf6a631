"""The "Which method should I use?" recommendations stand on the current claims ledger."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from fusion.book.ledger import STATUSES
from fusion.book.recommend import RECOMMENDATIONS, Evidence, Recommendation, check

ROOT = Path(__file__).resolve().parents[1]


def _records() -> list[dict]:
    out: list[dict] = []
    for path in sorted(p for p in (ROOT / "book" / "ledger").glob("*.json") if p.name != "stability.json"):
        out.extend(json.loads(path.read_text(encoding="utf-8"))["claims"])
    return out


def test_every_recommendation_stands_on_the_ledger():
    assert check(_records()) == []


def test_every_task_has_evidence_and_existing_chapters():
    docs = {p.with_suffix("").relative_to(ROOT).as_posix() for p in (ROOT / "notebooks").glob("*.ipynb")}
    assert len(RECOMMENDATIONS) >= 4
    for rec in RECOMMENDATIONS:
        assert rec.evidence
        assert set(rec.chapters) <= docs, rec.chapters


def test_check_reports_a_missing_record_and_a_moved_status():
    recs = [{"id": "a", "status": "contradicted"}]
    rec = Recommendation("t", "u", "w", "a", "aw", (Evidence("a", ("reproduced",), "r"),
                                                    Evidence("b", ("reproduced",), "r")), ())
    problems = check(recs, [rec])
    assert len(problems) == 2
    assert "'a' is now 'contradicted'" in problems[0] and "'b' does not exist" in problems[1]
    assert check([{"id": "a", "status": "reproduced"}, {"id": "b", "status": "reproduced"}], [rec]) == []


@pytest.mark.parametrize("expect", [(), ("fine",)])
def test_evidence_needs_ledger_statuses(expect):
    with pytest.raises(ValueError, match="expect"):
        Evidence("a", expect, "r")


def test_recommendation_needs_words_and_evidence():
    with pytest.raises(ValueError, match="use"):
        Recommendation("t", " ", "w", "a", "aw", (Evidence("a", STATUSES[:1], "r"),), ())
    with pytest.raises(ValueError, match="evidence"):
        Recommendation("t", "u", "w", "a", "aw", (), ())



@pytest.mark.parametrize("rid", [5, 5.0, None, ("a",)])
def test_check_refuses_a_record_id_that_is_not_text(rid):
    """A ledger id is a string: ``str()`` made the records 5 and '5' one id (one refused as a repeat, or one status
    read for the other)."""
    records = [{"id": rid, "status": STATUSES[0]}, {"id": "5", "status": STATUSES[0]}]
    with pytest.raises(TypeError, match="records: every id must be a string"):
        check(records, [])
