"""Chapter 07's work budgets, calibrated (fuzz 30b D2): one unit is about 10 ns of one core, so that ``MAX_WORK``
(``10**9`` units) means at most about 10 CPU-s in every budgeted function (``fusion._limits``; the measured weights
are in ``fusion.scenarios._time_registration_work``).

Each test counts units at the accept edge and the refuse edge of one budget; no test runs a slow call: the work
after a budget is replaced by a stop (``_Stop``), so that an accepted call costs milliseconds.
"""

from __future__ import annotations

import functools

import numpy as np
import pytest

from fusion._limits import LOOP_STEP, MAX_WORK, work
from fusion.scenarios import time_registration as sc
from fusion.scenarios import _time_registration_work as tw

R = sc.RegMethod


class _Stop(Exception):
    """Raised in place of the work after a budget: the call was accepted."""


def _stop(*args: object, **kwargs: object) -> None:
    raise _Stop


def _accepted(call) -> bool:
    """True when ``call`` passes its budget (reaches the stop), False when the budget refuses it."""
    try:
        call()
    except _Stop:
        return True
    except ValueError as exc:
        assert "work budget" in str(exc), exc
        return False
    raise AssertionError("the call neither reached its work nor was refused")


def test_a_weight_multiplies_the_units() -> None:
    assert work((10, 10), "n", weight=3) == 300
    assert work((MAX_WORK // 4,), "n", weight=4) == MAX_WORK // 4 * 4
    with pytest.raises(ValueError, match=r"^runs ask for .* units each\)"):
        work((MAX_WORK // 4 + 1,), "runs", weight=4)


def test_transient_table_edge(monkeypatch: pytest.MonkeyPatch) -> None:
    """Three methods: 333 samples (666 s) are accepted, 334 (667 s) refused: 24 us a step measured, 3 units of 10 us
    (1,100 s, 550 samples, was accepted and ran some 35 CPU-s)."""
    from fusion.book.chapters import time_registration_closed as cl

    monkeypatch.setattr(np, "arange", _stop)
    assert _accepted(lambda: cl.transient_table(666.0, 1.0))
    with pytest.raises(ValueError, match=r"^horizon and names ask for"):
        cl.transient_table(667.0, 1.0)
    assert cl._TRANSIENT_STEP == 3 * LOOP_STEP


def test_study_runs_edge(monkeypatch: pytest.MonkeyPatch) -> None:
    """About 8.8e4 runs (1e5 ran 10.4 CPU-s; 1.7e5 were accepted)."""
    from fusion.book.chapters.time_registration_ledger import studies

    t1, t2 = sc.instants()
    # the stop keeps monte_carlo's signature: the study's readings check their options against it (fix63a's entry)
    monkeypatch.setattr(sc, "monte_carlo", functools.wraps(sc.monte_carlo)(lambda *a, **k: _stop()))
    edge = MAX_WORK // (2 * t1.size * len(studies.STUDY_METHODS) * studies._STUDY_CALLS)
    assert _accepted(lambda: studies.study(t1, t2, 1.0, edge, 0))
    assert not _accepted(lambda: studies.study(t1, t2, 1.0, edge + 1, 0))


def test_exact_sweeps_edges(monkeypatch: pytest.MonkeyPatch) -> None:
    """A Kalman method's registration counts its filter by the filter's own rule (3 LOOP_STEP a step and 15 units a
    run, 4 LOOP_STEP and 25 smoothed, over the samples: these sweeps pass no kf, no period change; fix60a, it was the
    chapter's 2 LOOP_STEP over samples and instants, 17 us measured, below the filter's 26 us) and 6 units an
    instant: 54 levels of all methods and 592 latencies of delay_table are accepted, 55 and 593 refused (58 and 626
    before; 74 and 991 were accepted, 8 and 14 CPU-s); two-point alone keeps its 4,748 levels (5 ns a unit)."""
    from fusion.book.chapters import time_registration as ch
    from fusion.book.chapters import time_registration_robustness as rob

    monkeypatch.setattr(sc, "expected", _stop)
    levels = lambda n: list(np.linspace(0.1, 5.0, n))  # noqa: E731
    assert _accepted(lambda: ch.sigma_sweep(levels(54), list(sc.METHODS)))
    assert not _accepted(lambda: ch.sigma_sweep(levels(55), list(sc.METHODS)))
    assert _accepted(lambda: ch.sigma_sweep(levels(4748), [R.TWO_POINT]))
    assert not _accepted(lambda: ch.sigma_sweep(levels(4749), [R.TWO_POINT]))
    delays = lambda n: list(np.linspace(-0.5, 0.5, n))  # noqa: E731
    assert _accepted(lambda: rob.delay_table(delays(592), [1.0]))
    with pytest.raises(ValueError, match=r"^delays and sigmas ask for"):
        rob.delay_table(delays(593), [1.0])


def test_monte_carlo_runs_weigh_by_method() -> None:
    """A filtered run weighs its method's RUN_WEIGHT and the filter's passes their own rule: every method at 411,870
    runs is accepted, one more refused (415,154 before fix71a counted the products through the weight matrices,
    452,079 before fix60a, whose filter passes weighed less than the filter's own budget; 1e5 ran 1.05 CPU-s; 2.4e6
    were accepted); runs through weight matrices (Fig. 4) weigh 1 each and 0.01 a multiply-add (fix71a)."""
    n1, n2 = (t.size for t in sc.instants())
    names = list(sc.METHODS)
    tw._monte_carlo_work(names, 411870, n1, n2, "runs", "t_dst")
    with pytest.raises(ValueError, match=r"^runs ask for"):
        tw._monte_carlo_work(names, 411871, n1, n2, "runs", "t_dst")
    assert set(tw.RUN_WEIGHT) == set(sc._KALMAN) and set(tw.RUN_WEIGHT) <= set(R)
    fig4 = [R.IMPROVED, R.TWO_POINT] * 19
    edge = 100 * MAX_WORK // (len(fig4) * (100 * (n1 + n2) + n1 * n2))
    tw._monte_carlo_work(fig4, edge, n1, n2, "sigmas and runs", "sigmas", filtered=False)
    with pytest.raises(ValueError, match=r"^sigmas and runs ask for"):
        tw._monte_carlo_work(fig4, edge + 1, n1, n2, "sigmas and runs", "sigmas", filtered=False)


def test_fig4_runs_through_weight_matrices(monkeypatch: pytest.MonkeyPatch) -> None:
    """Fig. 4's levels are not filtered per run: a run weighs its samples and instants and 0.01 a multiply-add through
    each weight matrix (fix71a: 8.9e5 runs of 19 levels accepted, 9.4e5 before; the book runs 1e4)."""
    from fusion.book.chapters import time_registration as ch

    monkeypatch.setattr(sc, "truth", _stop)
    sigmas = list(np.round(np.arange(0.3, 1.26, 0.05), 2))
    n = sum(t.size for t in sc.instants())
    n1, n2 = (t.size for t in sc.instants())
    edge = 100 * MAX_WORK // (2 * len(sigmas) * (100 * n + n1 * n2))
    assert _accepted(lambda: ch.fig4_compatibility(sigmas, edge, 0, 3.0))
    assert not _accepted(lambda: ch.fig4_compatibility(sigmas, edge + 1, 0, 3.0))


def test_a_filter_pass_is_counted_once() -> None:
    """A Kalman method's filter steps once through the instants, all runs at once, by the filter's own rule (3
    LOOP_STEP and 15 units a run a step): 329,577 instants of a 2-run Monte Carlo are accepted, one more refused by
    the call's names (4e5 were accepted before fix60a, beyond the filter's own edge with ``period_change``); the
    steps alone beyond the budget are refused by the times' names."""
    n1 = sc.instants()[0].size
    tw._monte_carlo_work([R.KALMAN_PREDICT], 2, n1, 329_577, "runs", "t_dst")
    with pytest.raises(ValueError, match=r"^runs ask for"):
        tw._monte_carlo_work([R.KALMAN_PREDICT], 2, n1, 329_578, "runs", "t_dst")
    with pytest.raises(ValueError, match=r"^t_dst ask for"):
        tw._monte_carlo_work([R.KALMAN_PREDICT], 2, n1, 5 * 10**5, "runs", "t_dst")


def test_the_notebooks_calls_stay_well_inside() -> None:
    """Chapter 07's notebook calls, at most a tenth of the budget each (no refusal of the book's requests)."""
    n1, n2 = (t.size for t in sc.instants())
    n = n1 + n2
    methods = list(sc.METHODS)
    assert 3 * 50 * 50 * 3 * LOOP_STEP < MAX_WORK / 10                              # transient_table(100.0, 1.0)
    assert tw._exact_work(methods, [n2] * 5, "sigmas and names", False) < MAX_WORK / 10  # sigma_sweep(SIGMAS, all)
    assert tw._exact_work((R.IMPROVED, R.TWO_POINT), [n2] * 21, "d", False) < MAX_WORK / 10  # delay_table 7 x 3
    assert work((10000, n, 2 * 19), "fig4") < MAX_WORK / 10                          # fig4_compatibility, 10,000 runs
    assert work((1000, n1, 15, 19), "runs", weight=2) < MAX_WORK / 10                # cached_study(SEED + 1, 1000)
    assert work((1000, n, sum(tw.RUN_WEIGHT.get(m, 1) for m in methods)), "r") < MAX_WORK / 10  # 1,000 runs, all


# --- fix60a: the chapter's budget counts at least each of its Kalman filter calls' own budget -----------------------

def _inner_accepts(names: list[str], runs: int, steps: int) -> bool:
    """Whether every ``kalman_runs`` pass of ``names`` (filtered, smoothed, lag-one) passes the filter's own budget
    (``fusion.registration.methods._kalman_work``) at ``runs`` runs and ``steps`` grid steps."""
    from fusion.registration.methods import _kalman_work

    passes = {sc._STATES.get(n, "filtered") for n in names if n in sc._KALMAN}
    try:
        for p in passes:
            _kalman_work(steps, runs, p != "filtered", "t and Z")
    except ValueError:
        return False
    return True


@pytest.mark.parametrize("names", [[R.RTS_SMOOTHER], [R.FIXED_LAG], [R.KALMAN_PREDICT], list(sc._KALMAN),
                                   list(sc.METHODS)])
@pytest.mark.parametrize(("runs", "n_dst"), [(2, 10**3), (2, 3 * 10**5), (10**5, 8), (2 * 10**6, 8), (3 * 10**6, 8),
                                             (5 * 10**4, 2000), (10**3, 2 * 10**5)])
def test_the_chapters_rule_counts_at_least_the_filters(names: list[str], runs: int, n_dst: int) -> None:
    """Whenever monte_carlo's, fusion_runs' or a registration's count accepts, each filter pass it runs (at most every
    sample and instant, with ``period_change``) passes the filter's own budget: its refusal, naming ``t and Z``, the
    caller never passed, cannot come first (fix60a: the smoother alone at 2 and 3 million runs passed the chapter's
    count, 10 units a run, and was refused inside, 25 a run)."""
    n1 = sc.instants()[0].size
    for call, r, steps in (
            (lambda: tw._monte_carlo_work(names, runs, n1, n_dst, "runs", "t_dst"), runs, n1 + n_dst),
            (lambda: tw._fusion_runs_work(names, runs, n1, n_dst, "runs and names", "names"), runs, n1),  # no kf
            (lambda: tw._registration_work(names, n1, n_dst, 1, "t1 and t2"), 1, n1 + n_dst),
            (lambda: tw._registration_work(names, n1, n_dst, 1, "t1", period_change=False), 1, n1)):
        try:
            call()
        except ValueError as exc:
            assert "work budget" in str(exc)
            continue
        assert _inner_accepts(names, r, steps), (names, runs, n_dst)


def test_the_smoothers_monte_carlo_edge_is_the_chapters() -> None:
    """The smoother alone: 1,322,603 runs pass the chapter's count and the smoother's own budget (checked by the
    budget functions alone, not run); one more is refused at once naming monte_carlo's arguments (it was accepted,
    drew its noise and was refused inside as ``t and Z`` from about 2.0 million runs)."""
    import time

    n1, n2 = (t.size for t in sc.instants())
    edge = 1_322_603
    tw._monte_carlo_work([R.RTS_SMOOTHER], edge, n1, n2, "runs", "t_dst")
    assert _inner_accepts([R.RTS_SMOOTHER], edge, n1 + n2)
    t0 = time.process_time()
    with pytest.raises(ValueError, match=r"^runs, names, t_src and t_dst ask for .* beyond the work budget"):
        sc.monte_carlo([R.RTS_SMOOTHER], 1.0, edge + 1, 0)
    assert time.process_time() - t0 < 1.0


def test_the_period_change_monte_carlo_edge_is_the_chapters() -> None:
    """With ``period_change`` the filter steps through every instant too: 329,577 instants of a 2-run Monte Carlo of
    a Kalman method pass the chapter's count and the filter's own budget (not run); one more is refused at once
    naming monte_carlo's arguments (from about 330,000 it was refused inside as ``t, Z and t_extra``)."""
    import time

    t1 = sc.instants()[0]
    edge = 329_577
    tw._monte_carlo_work([R.KALMAN_PREDICT], 2, t1.size, edge, "runs", "t_dst")
    assert _inner_accepts([R.KALMAN_PREDICT], 2, t1.size + edge)
    t_dst = np.linspace(t1[0] + 0.25, t1[-1] - 0.25, edge + 1)
    t0 = time.process_time()
    with pytest.raises(ValueError, match=r"^runs, names, t_src and t_dst ask for .* beyond the work budget"):
        sc.monte_carlo([R.KALMAN_PREDICT], 1.0, 2, 0, t_dst=t_dst, kf={"period_change": True})
    assert time.process_time() - t0 < 1.0


def test_nees_table_counts_its_filter_passes(monkeypatch: pytest.MonkeyPatch) -> None:
    """nees_table's four filter passes by the filter's own rule and its NEES (12 units a run, sample and pass):
    462,851 runs are accepted (stopped at the draw), one more refused at once naming ``runs`` (it had no budget: from
    3.3 million runs it was refused inside as ``t and Z``)."""
    import time

    from fusion.book.chapters.time_registration_ledger import values as lg

    t0 = time.process_time()
    with pytest.raises(ValueError, match=r"^runs ask for .* beyond the work budget"):
        lg.nees_table(1.0, 462_852, 0)
    assert time.process_time() - t0 < 1.0
    monkeypatch.setattr(np.random, "default_rng", _stop)
    assert _accepted(lambda: lg.nees_table(1.0, 462_851, 0))
