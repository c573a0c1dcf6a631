"""Fuzz 61a C1's class, chapter 07: a list of noise levels whose LENGTH sets the budget is counted before any level is
read (fix69g). ``fig4_compatibility`` / ``fig4_reading_table`` read and hashed every level and then built a list of two
methods a level for the budget: 10**7 levels at 20 runs still ran at 100 s wall; ``tuning_by_noise`` likewise.
The inputs are built outside the timing.
"""

from __future__ import annotations

import numpy as np
import pytest

from _helpers import refused_quickly

N = 10**7   # MAX_COUNT: the most entries a sequence argument may hold


@pytest.fixture(scope="module")
def many() -> list[float]:
    """10**7 distinct noise levels (m), built once, outside every timing."""
    return np.linspace(0.5, 5.0, N).tolist()


@pytest.mark.parametrize("fn", ["fig4_compatibility", "fig4_reading_table"])
def test_fig4_counts_sigmas_by_length(many, fn):
    from fusion.book.chapters import time_registration as T
    refused_quickly(lambda: getattr(T, fn)(many, 20, 1, 4.0), ValueError, "sigmas")


def test_tuning_by_noise_counts_sigmas_by_length(many):
    from fusion.book.chapters import time_registration as T
    refused_quickly(lambda: T.tuning_by_noise(many, 20, 1), ValueError, "sigmas")


@pytest.mark.parametrize("filtered", [False, True])
def test_monte_carlo_work_repeat_closed_form(filtered):
    """``repeat=k`` counts k calls of the names: the fixed-weight edge the same as a list of k copies (no filter), at
    least the list's units with a filter (each call runs its own passes), and 10**7 calls refused at once."""
    import time

    from fusion.scenarios import time_registration as sc
    from fusion.scenarios.time_registration import RegMethod
    names, (n1, n2) = [RegMethod.IMPROVED, RegMethod.TWO_POINT], (t.size for t in sc.instants())

    def accepted(k: int, listed: bool) -> bool:
        try:
            sc._monte_carlo_work(names * k if listed else names, 20, n1, n2, "w", "t", filtered=filtered,
                                 **({} if listed else {"repeat": k}))
        except ValueError:
            return False
        return True

    lo, hi = 1, 4096   # the list form's edge, by bisection
    while hi - lo > 1:
        lo, hi = ((lo + hi) // 2, hi) if accepted((lo + hi) // 2, True) else (lo, (lo + hi) // 2)
    edge = lo
    assert accepted(1, False) and not accepted(edge + 1, False)
    assert accepted(edge, False) is (not filtered)
    t = time.process_time()
    assert not accepted(N, False)
    assert time.process_time() - t < 0.1


def test_book_calls_inside_budget():
    """The chapter's calls (notebook 07: 4 levels at 10,000 runs; its appendix: 3 levels at 1,000 runs) accepted."""
    from fusion.book.chapters.time_registration import TUNING_READINGS
    from fusion.book.chapters.time_registration_fig4 import _tuning_work
    from fusion.scenarios import time_registration as sc
    from fusion.scenarios.time_registration import RegMethod
    n1, n2 = (t.size for t in sc.instants())
    sc._monte_carlo_work([RegMethod.IMPROVED, RegMethod.TWO_POINT], 10000, n1, n2, "w", "t", filtered=False, repeat=4)
    _tuning_work(1000, 3 * len(TUNING_READINGS))


@pytest.mark.parametrize("n", [10**6, N])
def test_sensitivity_table_counts_periods_by_length(n):
    """3.7 CPU-s for 10**6 periods before (each read, compared and printed before the value-based budget): refused
    at once by a lower bound, their number times the cheapest valid period (three scans)."""
    from fusion.book.chapters.ci.infrared import sensitivity_table
    many = np.linspace(0.01, 4.0, n).tolist()
    refused_quickly(lambda: sensitivity_table(many, 1, 20, 10.0), ValueError, "periods, runs and duration")


def test_sensitivity_floor_below_exact_budget():
    """The lower bound never exceeds the exact budget: a period list the exact rule accepts (the longest valid
    period, many of them) is accepted by the bound; ``known`` periods are left out of the count."""
    from fusion.book.chapters.ci.infrared import _sensitivity_budget, _sensitivity_floor
    for T in (5.0, 3.0, 1.0, 0.1):
        units = _sensitivity_budget([T], 20, 10.0)
        k = max(int(1e9 // units), 1)
        _sensitivity_budget([T] * k, 20, 10.0)   # accepted by the exact rule (as a sum of equal periods)
        _sensitivity_floor([T] * k, {}, 20, 10.0)
    with pytest.raises(ValueError, match="periods, runs and duration"):
        _sensitivity_floor([0.1] * N, {}, 20, 10.0)
    _sensitivity_floor([0.1] * 2, {0.1: {}, 0.2: {}}, 10**9, 10.0)   # all known: nothing counted
