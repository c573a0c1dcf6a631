"""Fuzz 62a C3, C4, C4b, D1: a sequence whose LENGTH sets the budget is counted before any entry is read or looped.

C3: ``stability.tasks`` read, checked and hashed every seed before the budget, which needs only
``len(seed_list)`` (10**7 seeds refused after 6.9-9.0 CPU-s). C4, C4b: chapter 06's ``stopping_values`` and
``guard_usability`` looped over every tolerance (threshold) with no budget (10**6 tolerances ran 58.4 CPU-s). D1:
``alpha_methods`` read and printed every alpha before its repeat check. The inputs are built outside the timing.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from _helpers import refused_quickly

N = 10**7   # MAX_COUNT: the most entries a sequence argument may hold


@pytest.fixture(scope="module")
def many_seeds() -> list[int]:
    return list(range(N))


def test_tasks_counts_seed_list_by_length(many_seeds):
    """6.9 CPU-s before (every seed checked and hashed first): refused at once by the book's readings x seeds."""
    from fusion.book import stability as S
    r = S.stochastic_readings()
    refused_quickly(lambda: S.tasks(r, many_seeds), ValueError, "readings and seed_list")
    refused_quickly(lambda: S.tasks(r, np.arange(N)), ValueError, "readings and seed_list")


@pytest.fixture(scope="module")
def many_sizes() -> list[int]:
    """10**7 distinct counts >= 2 (below the ceiling of a count), built once, outside every timing."""
    return list(range(2, N + 2 - 4))


@pytest.fixture(scope="module")
def many_fractions() -> list[float]:
    return np.linspace(0.001, 0.999, N).tolist()


@pytest.fixture(scope="module")
def stop_runs():
    """The fuzz's fixture: 2 runs of a 5-frame READ scenario."""
    from fusion.scenarios import range_bearing as dist
    tiny = dist.RangeBearingScenario(frames=6, n_particles=300, n_samples=300, n_central=600, em_iterations=5)
    read = dataclasses.replace(tiny, readings=True, frames=5)
    return dist.monte_carlo(read, 7, 2), read


def test_stopping_values_counts_xtols(stop_runs, many_fractions):
    """No budget before (10**6 tolerances ran 58.4 CPU-s): refused by len(xtols) at once; the edge by the budget
    function alone (its loop step and the runs' trace cells), the book's four tolerances accepted."""
    from fusion._limits import MAX_WORK, loop_work
    from fusion.book.chapters import chernoff as chc
    from fusion.book.chapters.chernoff.swarm import _XTOL_STEP
    runs, read = stop_runs
    refused_quickly(lambda: chc.stopping_values(runs, read, xtols=many_fractions), ValueError, "xtols")
    cells = sum(r.swarm_trace["spread"].size for r in runs)
    edge = MAX_WORK // (_XTOL_STEP + cells)
    assert loop_work((edge,), cells, "xtols", step=_XTOL_STEP) <= MAX_WORK
    with pytest.raises(ValueError, match="xtols"):
        loop_work((edge + 1,), cells, "xtols", step=_XTOL_STEP)
    refused_quickly(lambda: chc.stopping_values(runs, read, xtols=[1e-3] * (edge + 1)), ValueError, "xtols")
    assert "chf_stop_x3" in chc.stopping_values(runs, read)


def test_guard_usability_counts_thresholds(many_fractions):
    """No budget before (10**5 thresholds 1.5 CPU-s, linear): refused by len(thresholds) at once; the edge by the
    budget function alone."""
    from fusion._limits import MAX_WORK, loop_work
    from fusion.book.chapters import chernoff as chc
    from fusion.book.chapters.chernoff.guard import _THRESHOLD_STEP
    from test_chernoff_chapter import TINY
    from fusion.scenarios import range_bearing as dist
    runs = dist.monte_carlo(TINY, 5, 3)
    refused_quickly(lambda: chc.guard_usability(runs, runs, TINY, thresholds=many_fractions), ValueError,
                    "thresholds")
    cells = sum(r.ess["local"].size for r in runs)
    edge = MAX_WORK // (_THRESHOLD_STEP + cells)
    assert loop_work((edge,), cells, "thresholds", step=_THRESHOLD_STEP) <= MAX_WORK
    refused_quickly(lambda: chc.guard_usability(runs, runs, TINY, thresholds=[0.01] * (edge + 1)), ValueError,
                    "thresholds")
    assert "chf_gu_thr1" in chc.guard_usability(runs, runs, TINY)


def test_alpha_methods_stops_at_the_first_repeat():
    """2.2 million alphas (within the budget) whose first two print the same: refused after 6.7 CPU-s before (every
    alpha read and printed first), now at the second."""
    from fusion.book.chapters.ofs.readings import alpha_methods
    xs = [0.5, 0.5000001] + np.linspace(1.0, 2.0, 2_200_000 - 2).tolist()
    refused_quickly(lambda: alpha_methods(xs), ValueError, r"alphas\[0\] and alphas\[1\] print the same", cpu=0.5)
    with pytest.raises(ValueError, match=r"alphas\[0\] and alphas\[3\] are both 0.5"):  # an exact repeat as such
        alpha_methods([0.5, 0.7, 0.9, 0.5])
    assert len(alpha_methods([0.1, 0.2])) == 3


@pytest.mark.parametrize("call", ["swarm_study", "within_se_counts", "scaling_study", "snis_bias_study"])
def test_chapter06_sizes_counted_by_length(call, many_sizes):
    """Each N (R) runs a study (a batch): 10**7 entries were read by counts() and hashed by distinct() for 4.1 CPU-s
    before the budget; now refused by their number at once."""
    from fusion.book.chapters import chernoff_scaling as cs, chernoff_snis as sn
    calls = {"swarm_study": (lambda: cs.swarm_study(1, ns=many_sizes, runs=2, r=10), "ns"),
             "within_se_counts": (lambda: cs.within_se_counts(1, ns=many_sizes, runs=2), "ns"),
             "scaling_study": (lambda: cs.scaling_study(1, rs=many_sizes, runs=2), "rs"),
             "snis_bias_study": (lambda: sn.snis_bias_study(np.random.default_rng(0), rs=many_sizes), "rs")}
    f, name = calls[call]
    refused_quickly(f, ValueError, name)
