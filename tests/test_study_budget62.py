"""Chapter 02's readers that run several studies at one ``runs`` count their sum before any of them (fuzz 62a).

``lec-awf-adapts``'s readings read together (``fusion.book.chapters.lecture.evidence_at``) ran the regime study
(its own edge 2,000 runs; ~36 CPU-s at 1,800) before the variance-change study (edge 1,723) refused naming its own
``runs, samples, sigma and changes``; each E2.3 reading (``lec-awf-accuracy``, ``lec-awf-fault-tolerance``,
``lec-cc-*``) ran E2.3 at X = 900 and then at X = 0 on the same runs, each checked alone. Now
``studies._reads_budget`` sums the studies' own budget functions (``fusion.book._study_budget.studies_first``)
before any, naming ``runs``. Each test stops a call at its first draw (``numpy.random.default_rng`` raises), so an
accepted edge runs no work: the budget alone decides.
"""

from __future__ import annotations

import numpy as np
import pytest

from test_study_budget61 import Ran, _reaches_the_draw, _refused_first


@pytest.fixture
def no_draw(monkeypatch):
    import scipy.stats  # noqa: F401  (its import draws an example: imported before the patch)

    import fusion.book.chapters.lecture_weighting  # noqa: F401
    from fusion.book.chapters.lecture import _source_claims

    _source_claims()  # the claim file parsed (0.3 CPU-s) before the timed calls

    def ran(*args, **kwargs):
        raise Ran

    monkeypatch.setattr(np.random, "default_rng", ran)


def _adapts_edge() -> int:
    """The largest runs whose regime and variance-change studies (their own budget functions) fit, summed, in the
    regime study's STUDY_WORK entry."""
    from fusion._limits import REGIME_STUDY, STUDY_WORK
    from fusion.scenarios.lecture_weighting import regime as rg

    limit, fits = STUDY_WORK[REGIME_STUDY], []
    for r in range(1400, 1800):
        try:
            units = rg._draws_budget(r, 1000, 4, rg._REGIME_DRAW, "runs", limit) + rg._change_work(r, 1000, 4, 3, "runs")
        except ValueError:
            continue
        if units <= limit:
            fits.append(r)
    return max(fits)


def test_adapts_read_together_refused_before_the_regime_study(no_draw):
    from fusion.book.chapters import lecture

    msg = _refused_first(lambda: lecture.evidence_at({"lec-awf-adapts": 1800}, 1), r"records\['lec-awf-adapts'\]: ")
    assert "1,800 x 1,000 x 4" in msg
    edge = _adapts_edge()
    assert edge == 1550
    _refused_first(lambda: lecture.evidence_at({"lec-awf-adapts": edge + 1}, 1), r"records\['lec-awf-adapts'\]: ")
    _reaches_the_draw(lambda: lecture.evidence_at({"lec-awf-adapts": edge}, 1))


def test_a_later_record_refused_before_an_earlier_one_runs(no_draw):
    from fusion.book.chapters import lecture

    _refused_first(lambda: lecture.evidence_at({"lec-awf-estimated": 300, "lec-awf-adapts": 1800}, 1),
                   r"records\['lec-awf-adapts'\]: ")


def test_change_reading_names_runs(no_draw):
    import fusion.book.chapters.lecture_weighting as lw

    _refused_first(lambda: lw.ev_awf_adapts({"reading": "change-degrades"}, seed=1, runs=1800))


@pytest.mark.parametrize("rid", ["lec-awf-accuracy", "lec-awf-fault-tolerance", "lec-cc-accuracy",
                                 "lec-cc-beats-mean"])
def test_e23_readings_count_both_levels(no_draw, rid):
    import fusion.book.chapters.lecture_weighting as lw
    from fusion.scenarios.lecture_weighting import consistency as cs

    _refused_first(lambda: lw.EVIDENCE[rid]({}, seed=1, runs=4000))  # E2.3 alone accepts ~5,000 runs
    both = [r for r in (2414, 2415, 2416, 2417)
            if 2 * cs._consistency_work(r, 100, 5, 20000, "runs") <= 10**9]
    edge = max(both)
    assert edge == 2415
    _refused_first(lambda: lw.EVIDENCE[rid]({}, seed=1, runs=edge + 1))
    _reaches_the_draw(lambda: lw.EVIDENCE[rid]({}, seed=1, runs=edge))


@pytest.mark.parametrize("factor", [1, 3, 10])
def test_the_books_runs_accepted(factor):
    """Every stochastic record's readings read together at the chapter's runs and the sweep's factors (the budget
    functions alone)."""
    from fusion.book.chapters.lecture import _source_claims
    from fusion.book.chapters.lecture_weighting import records as R

    cf = _source_claims()
    for rid, runs in R.STOCHASTIC.items():
        spec = cf.record(rid)
        own = {r.key: r.runs for r in spec.readings}
        keys = ["primary"] + [r.key for r in spec.readings if r.key != "primary"]
        reads = [(k, factor * (own.get(k) or runs)) for k in keys]
        R._record_budget(rid, reads)
        for k, r in reads:
            R._record_budget(rid, [(k, r)])
