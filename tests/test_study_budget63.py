"""Chapter 05's composite studies count what they run before any draw (fuzz 55 C3, C4).

``paired_study``'s budget counted only its three scenarios, not the fusion of every rule on three pairs, the Fig. 6
and random weights, the per-step weights or the memory they hold: 11,000 runs were accepted and ran 44 CPU-s, 25,542
(its edge) ended in a raw MemoryError after 34 CPU-s. ``ledger_studies`` ran the architecture, paired and infrared
studies at one ``runs`` with no summed check: 5,000 runs ran 110 CPU-s. Each test stops a call at its first draw
(``numpy.random.default_rng`` raises), so an accepted edge runs no work: the budget alone decides.
"""

from __future__ import annotations

import pytest

from test_study_budget61 import _accepts, _edge, _reaches_the_draw, _refused_first, no_draw  # noqa: F401


def test_ci_paired_study_counts_what_it_runs(no_draw):
    from fusion.book.chapters import ci
    from fusion.book.chapters.ci import studies as S

    for runs in (11_000, 25_542):   # fuzz 55 C3: accepted (44 CPU-s), the old edge (a raw MemoryError)
        _refused_first(lambda: ci.paired_study(1, runs))
    edge = _edge(_accepts(S._paired_budget), hi=25_542)
    _reaches_the_draw(lambda: ci.paired_study(1, edge))   # just inside: accepted, stopped at its first draw
    _refused_first(lambda: ci.paired_study(1, edge + 1))  # just outside: refused naming runs, before any draw


def test_ci_paired_study_accepts_the_books_runs():
    from fusion.book.chapters.ci import studies as S

    for factor in (1, 3, 10):   # the chapter's runs and the reseeding sweep's scaled primaries (ci-fig4 at 10x)
        S._paired_budget(factor * S.LEDGER_RUNS)


def test_ci_ledger_studies_counts_its_studies(no_draw):
    from fusion.book.chapters import ci
    from fusion.book.chapters.ci import studies as S

    _refused_first(lambda: ci.ledger_studies(1, 5_000))   # fuzz 55 C4: accepted, 110 CPU-s
    edge = _edge(_accepts(S._ledger_budget), hi=5_000)
    _reaches_the_draw(lambda: ci.ledger_studies(1, edge))
    message = _refused_first(lambda: ci.ledger_studies(1, edge + 1))
    assert "STUDY_WORK: chapter 05's notebook call of ledger_studies" in message


def test_ci_ledger_studies_accept_the_books_runs():
    # the notebook's call (LEDGER_RUNS) and the test suite's smaller ones; the sweep reads the studies through
    # record_evidence, not ledger_studies
    from fusion.book.chapters.ci import studies as S

    for runs in (3, 100, S.LEDGER_RUNS, 3 * S.LEDGER_RUNS):
        S._ledger_budget(runs)


def test_ledger_studies_entry_is_twice_the_notebooks_call():
    # budget35's one rule for an entry above MAX_WORK: twice the book's own call, rounded up to a whole MAX_WORK
    import fusion._limits as L
    from fusion.book._study_budget import studies_first
    from fusion.book.chapters.ci import studies as S

    counted = S._ledger_budget(S.LEDGER_RUNS)
    assert counted > L.MAX_WORK
    assert L.STUDY_WORK[L.LEDGER_STUDIES] == -(-2 * counted // L.MAX_WORK) * L.MAX_WORK
    assert studies_first([lambda: counted], "runs", L.STUDY_WORK[L.LEDGER_STUDIES]) == counted


@pytest.mark.parametrize("identical", [True, False])
def test_architecture_units_are_what_architecture_study_counts(identical, monkeypatch):
    # ledger_studies sums arch_study by architecture_study's own weights: the units equal the study's own count
    import numpy as np

    import fusion._limits as L
    from fusion.book.chapters.ci import studies as S
    from fusion.book.chapters.ci.constants import W_PUB
    from fusion.book.chapters.ci.printed import printed_covariances
    from fusion.book.chapters.ci.tracking import ANISO_R
    from fusion.scenarios.two_sensor import architecture as A

    class Counted(BaseException):
        pass

    counted = []

    def spy(shape, names, weight=1, limit=L.MAX_WORK, served=None):
        counted.append(L.work(shape, names, weight=weight, limit=10**30))
        raise Counted

    monkeypatch.setattr(A, "work", spy)
    Q, R1, R2 = printed_covariances()
    kw = (dict(printed_omegas=(W_PUB, 0.1, 0.5), placement_omegas=(W_PUB,)) if identical
          else dict(printed_omegas=(W_PUB,)))
    pair = (R1, R2) if identical else ANISO_R
    with pytest.raises(Counted):
        A.architecture_study(np.random.default_rng(1), *pair, Q, runs=300, nees_runs=300, **kw)
    banks = S._ARCH_BANKS[0 if identical else 1]
    assert counted == [A._architecture_units(261, 300, 300, banks, "runs")]
