"""Chapter 07's work budgets, calibrated (fuzz 30b D2): one unit is about 10 ns of one core, so that ``MAX_WORK``
(``10**9`` units) means at most about 10 CPU-s in every budgeted function (``fusion._limits``; the measured weights
are in ``fusion.scenarios._time_registration_work``).

Each test counts units at the accept edge and the refuse edge of one budget; no test runs a slow call: the work
after a budget is replaced by a stop (``_Stop``), so that an accepted call costs milliseconds.
"""

from __future__ import annotations

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
    monkeypatch.setattr(sc, "monte_carlo", _stop)
    edge = MAX_WORK // (2 * t1.size * len(studies.STUDY_METHODS) * studies._STUDY_CALLS)
    assert _accepted(lambda: studies.study(t1, t2, 1.0, edge, 0))
    assert not _accepted(lambda: studies.study(t1, t2, 1.0, edge + 1, 0))


def test_exact_sweeps_edges(monkeypatch: pytest.MonkeyPatch) -> None:
    """A Kalman filter step weighs 2 LOOP_STEP (17 us measured): 58 levels of all methods and 626 latencies of
    delay_table are accepted, 59 and 627 refused (74 and 991 were accepted, 8 and 14 CPU-s); two-point alone keeps
    its 4,748 levels (5 ns a unit)."""
    from fusion.book.chapters import time_registration as ch
    from fusion.book.chapters import time_registration_robustness as rob

    monkeypatch.setattr(sc, "expected", _stop)
    levels = lambda n: list(np.linspace(0.1, 5.0, n))  # noqa: E731
    assert _accepted(lambda: ch.sigma_sweep(levels(58), list(sc.METHODS)))
    assert not _accepted(lambda: ch.sigma_sweep(levels(59), list(sc.METHODS)))
    assert _accepted(lambda: ch.sigma_sweep(levels(4748), [R.TWO_POINT]))
    assert not _accepted(lambda: ch.sigma_sweep(levels(4749), [R.TWO_POINT]))
    delays = lambda n: list(np.linspace(-0.5, 0.5, n))  # noqa: E731
    assert _accepted(lambda: rob.delay_table(delays(626), [1.0]))
    with pytest.raises(ValueError, match=r"^delays and sigmas ask for"):
        rob.delay_table(delays(627), [1.0])


def test_monte_carlo_runs_weigh_by_method() -> None:
    """A filtered run weighs its method's RUN_WEIGHT: every method at 452,079 runs is accepted, one more refused (1e5
    ran 1.05 CPU-s; 2.4e6 were accepted); runs through weight matrices (Fig. 4) weigh 1 each."""
    n1, n2 = (t.size for t in sc.instants())
    names = list(sc.METHODS)
    tw._monte_carlo_work(names, 452079, n1, n2, "runs", "t_dst")
    with pytest.raises(ValueError, match=r"^runs ask for"):
        tw._monte_carlo_work(names, 452080, n1, n2, "runs", "t_dst")
    assert set(tw.RUN_WEIGHT) == set(sc._KALMAN) and set(tw.RUN_WEIGHT) <= set(R)
    fig4 = [R.IMPROVED, R.TWO_POINT] * 19
    edge = MAX_WORK // ((n1 + n2) * len(fig4))
    tw._monte_carlo_work(fig4, edge, n1, n2, "sigmas and runs", "sigmas", filtered=False)
    with pytest.raises(ValueError, match=r"^sigmas and runs ask for"):
        tw._monte_carlo_work(fig4, edge + 1, n1, n2, "sigmas and runs", "sigmas", filtered=False)


def test_fig4_runs_through_weight_matrices(monkeypatch: pytest.MonkeyPatch) -> None:
    """Fig. 4's levels are not filtered per run (9.4e5 runs of 19 levels, formerly accepted, still are)."""
    from fusion.book.chapters import time_registration as ch

    monkeypatch.setattr(sc, "truth", _stop)
    sigmas = list(np.round(np.arange(0.3, 1.26, 0.05), 2))
    n = sum(t.size for t in sc.instants())
    edge = MAX_WORK // (n * 2 * len(sigmas))
    assert _accepted(lambda: ch.fig4_compatibility(sigmas, edge, 0, 3.0))
    assert not _accepted(lambda: ch.fig4_compatibility(sigmas, edge + 1, 0, 3.0))


def test_a_filter_pass_is_counted_once() -> None:
    """A Kalman method's filter steps once through the instants, all runs at once: 5e5 instants of a 2-run Monte
    Carlo are refused by the times' names (the pass alone, 17 us a step, would be some 8 CPU-s), 4e5 accepted."""
    n1 = sc.instants()[0].size
    tw._monte_carlo_work([R.KALMAN_PREDICT], 2, n1, 4 * 10**5, "runs", "t_dst")
    with pytest.raises(ValueError, match=r"^t_dst ask for"):
        tw._monte_carlo_work([R.KALMAN_PREDICT], 2, n1, 5 * 10**5, "runs", "t_dst")


def test_the_notebooks_calls_stay_well_inside() -> None:
    """Chapter 07's notebook calls, at most a tenth of the budget each (no refusal of the book's requests)."""
    n1, n2 = (t.size for t in sc.instants())
    n = n1 + n2
    methods = list(sc.METHODS)
    assert 3 * 50 * 50 * 3 * LOOP_STEP < MAX_WORK / 10                              # transient_table(100.0, 1.0)
    assert tw._exact_work(methods, [n2] * 5, "sigmas and names") < MAX_WORK / 10    # sigma_sweep(SIGMAS, all)
    assert tw._exact_work((R.IMPROVED, R.TWO_POINT), [n2] * 21, "d") < MAX_WORK / 10  # delay_table 7 x 3
    assert work((10000, n, 2 * 19), "fig4") < MAX_WORK / 10                          # fig4_compatibility, 10,000 runs
    assert work((1000, n1, 15, 19), "runs", weight=2) < MAX_WORK / 10                # cached_study(SEED + 1, 1000)
    assert work((1000, n, sum(tw.RUN_WEIGHT.get(m, 1) for m in methods)), "r") < MAX_WORK / 10  # 1,000 runs, all
