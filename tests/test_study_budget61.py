"""A chapter study that runs several budgeted studies counts their sum before any of them (fuzz 54a C2-C4, D4).

Each inner study checked its own budget when it started, so a ``runs`` between the chapter's loose check and an inner
study's tighter one ran the first studies and was then refused naming the inner arguments (chapter 01's studies, 8-11
CPU-s, naming ``x`` / ``z``; chapter 07's ``cached_study``, 8-10 CPU-s; chapter 05's ``paired_study``, 3.2 CPU-s,
naming seven arguments), and a ``runs`` each accepted alone ran all of them (chapter 04's ``cached_studies``: 16-27
CPU-s, once a raw MemoryError). Now ``fusion.book._study_budget.studies_first`` sums the inner studies' own budget
functions at the chapter's entry. Each test stops a call at its first draw (``numpy.random.default_rng`` raises), so
an accepted edge runs no work: the budget alone decides.
"""

from __future__ import annotations

import time
from collections.abc import Callable

import numpy as np
import pytest


class Ran(BaseException):
    """Raised at the first draw: every entry check has passed."""


@pytest.fixture
def no_draw(monkeypatch):
    import scipy.stats  # noqa: F401  (its import draws an example: imported before the patch)

    import fusion.book.chapters.ci  # noqa: F401
    import fusion.book.chapters.lecture_correlated  # noqa: F401
    import fusion.book.chapters.ofs  # noqa: F401
    import fusion.book.chapters.time_registration_ledger  # noqa: F401

    def ran(*args, **kwargs):
        raise Ran

    monkeypatch.setattr(np.random, "default_rng", ran)


def _edge(accepts: Callable[[int], bool], hi: int = 10**7) -> int:
    """The largest runs ``accepts`` accepts (it accepts 1 and refuses ``hi``)."""
    lo = 1
    assert accepts(lo) and not accepts(hi)
    while hi - lo > 1:
        mid = (lo + hi) // 2
        lo, hi = (mid, hi) if accepts(mid) else (lo, mid)
    return lo


def _accepts(budget: Callable[[int], object]) -> Callable[[int], bool]:
    def accepts(runs: int) -> bool:
        try:
            budget(runs)
        except ValueError:
            return False
        return True
    return accepts


def _refused_first(call: Callable[[], object], prefix: str = "") -> str:
    """``call`` is refused with a ValueError naming runs (after ``prefix``, a regular expression) before any draw,
    in under 1 CPU-s; its message (shared with test_study_budget62 and 63)."""
    t0 = time.process_time()
    with pytest.raises(ValueError, match="^" + prefix + r"runs ask for studies beyond the budget, refused before any "
                       "study") as e:
        call()
    assert time.process_time() - t0 < 1
    return str(e.value)


def _reaches_the_draw(call: Callable[[], object]) -> None:
    with pytest.raises(Ran):
        call()


# chapter 01 -------------------------------------------------------------------------------------------------------

def _ofs_budgets():
    from fusion._limits import MEMBERSHIP_STUDY, STUDY_WORK
    from fusion.book.chapters.ofs import studies as S

    fusions = 1 + len(S.FAMILIES)
    return {S.weight_study: lambda r: S._fused_runs(r),
            S.not_neighbourhood_share: lambda r: S._fused_runs(r),
            S.membership_study: lambda r: S._fused_runs(r, ((100, fusions), (31, fusions)), 2,
                                                        STUDY_WORK[MEMBERSHIP_STUDY], MEMBERSHIP_STUDY),
            S.faulty_member_share: lambda r: S._fused_runs(r, ((31, 1),)),
            S.healthy_dropped_share: lambda r: S._fused_runs(r, ((31, 2),))}


@pytest.mark.parametrize("name", ["weight_study", "not_neighbourhood_share", "membership_study", "faulty_member_share",
                                  "healthy_dropped_share"])
def test_ofs_studies_refuse_runs_before_the_draws(name, no_draw):
    # fuzz 54a C2: runs=268,000 passed the memory check, drew and ran 8-11 CPU-s, then fuse_epochs refused naming x/z
    from fusion.book.chapters.ofs import studies as S

    fn = getattr(S, name)
    budget = _ofs_budgets()[fn]
    _refused_first(lambda: fn(0, 268_000))
    edge = _edge(_accepts(budget), hi=268_000)
    _reaches_the_draw(lambda: fn(0, edge))          # just inside: accepted, stopped at its first draw
    _refused_first(lambda: fn(0, edge + 1))         # just outside: refused naming runs, before any draw


def test_ofs_studies_accept_the_books_runs():
    from fusion.book.chapters.ofs.settings import N_RUNS

    for budget in _ofs_budgets().values():
        for factor in (1, 3, 10):   # the chapter's runs and the reseeding sweep's scaled primaries
            budget(factor * N_RUNS)


# chapter 04 -------------------------------------------------------------------------------------------------------

def _lc_budget(runs: int) -> int:
    from fusion.book.chapters.lecture_correlated import records as R

    return R._studies_budget(dict(xs=(0.0,) * 7, m=5, sigma=1.0, runs=runs), dict(runs=runs, scales=(3.0, 30.0, 100.0)),
                             dict(sigma=(1.0, 2.0, 3.0), sigma_env=1.5, runs=runs), (None, {R.WIDE: R.WIDE_CASE}), runs)


def test_lecture_correlated_studies_count_their_sum(no_draw):
    # fuzz 54a C3: 1e6 runs ran 16 CPU-s, 2.7e6 ran 27 CPU-s to a MemoryError, 3e6 ran 11 CPU-s then were refused
    from fusion.book.chapters import lecture_correlated as lc

    for runs in (3_000_000, 2_700_000, 1_000_000 + 1_000):
        _refused_first(lambda: lc.cached_studies(7, runs))
    _refused_first(lambda: lc.ev_correlation_matters({}, seed=7, runs=3_000_000))
    edge = _edge(_accepts(_lc_budget))
    _reaches_the_draw(lambda: lc.cached_studies(7, edge))
    _refused_first(lambda: lc.cached_studies(7, edge + 1))


def test_lecture_correlated_studies_accept_the_books_runs():
    # the chapter's largest paired study (20,000 runs) at the sweep's 3x and 10x
    for runs in (20_000, 60_000, 200_000):
        _lc_budget(runs)


# chapter 05 -------------------------------------------------------------------------------------------------------

def test_ci_paired_study_counts_its_three_scenarios(no_draw):
    # fuzz 54a D4: 70,000 runs passed the first check, ran 3.2 CPU-s, then were refused naming seven arguments
    from fusion.book.chapters import ci
    from fusion.book.chapters.ci import studies as S

    message = _refused_first(lambda: ci.paired_study(1, 70_000))
    assert "R_a" not in message
    edge = _edge(_accepts(S._paired_budget))
    _reaches_the_draw(lambda: ci.paired_study(1, edge))
    _refused_first(lambda: ci.paired_study(1, edge + 1))
    for factor in (1, 3, 10):
        S._paired_budget(factor * S.LEDGER_RUNS)


def test_two_sensor_scenario_refuses_its_central_input_first():
    # its stacked (runs, steps, 4) measurements were refused by filter_runs after the draws and two filters
    from fusion.book.chapters.ci.printed import printed_covariances
    from fusion.scenarios import two_sensor

    Q, R1, R2 = printed_covariances()
    t0 = time.process_time()
    with pytest.raises(ValueError, match=r"^runs and T ask for an array of .* beyond the input budget"):
        two_sensor.two_sensor_scenario(R1, R2, Q, np.random.default_rng(1), runs=40_000)
    assert time.process_time() - t0 < 1


# chapter 07 -------------------------------------------------------------------------------------------------------

def _trl_budget(runs: int) -> int:
    from fusion.book._study_budget import studies_first
    from fusion.book.chapters.time_registration_ledger import studies as T

    t1, t2 = T.sc.instants()
    fused = [T.IMPROVED, T.TWO, T.S3, T.RegMethod.LEAST_SQUARES]
    return studies_first([lambda: T._study_work(runs, t2.size, "runs", "runs", "runs"),
                          lambda: T.sc._fusion_runs_work(fused, runs, t1.size, t2.size, "runs", "runs")], "runs")


def test_time_registration_cached_study_counts_the_fusion_runs(no_draw):
    # fuzz 54a C4: 80,000 runs passed the study's check, ran it 8-10 CPU-s, then fusion_runs refused
    from fusion.book.chapters import time_registration_ledger as trl

    _refused_first(lambda: trl.cached_study(1, 80_000))
    edge = _edge(_accepts(_trl_budget))
    _reaches_the_draw(lambda: trl.cached_study(1, edge))
    _refused_first(lambda: trl.cached_study(1, edge + 1))
    for runs in (1_000, 3_000, 10_000):   # the chapter's runs and the sweep's 3x and 10x
        _trl_budget(runs)
