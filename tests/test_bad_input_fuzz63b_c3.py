"""Fuzz 63b C3, D1: a sweep's repeats looked for after the budget that needs only its length or extremes.

``ridge_sensors.vector_study`` and ``plugin_study`` printed and hashed every scale / true value
(``distinct_printed`` with ``glue_part``) before their work budgets, which need only the number of entries: 10**7
scales were refused after 27.5 CPU-s, 9.9e6 xs after 24.7. ``correlated_sensors.estimated_covariance_study`` hashed
10**7 sizes (``distinct``) before its case budgets, 2.8 CPU-s. The budget now comes first ("length -> budget ->
entries"); the inputs (distinct when printed, as the fuzz built them) are built outside the timing, and each refusal
names the same arguments as before.
"""

from __future__ import annotations

import numpy as np
import pytest

from _helpers import refused_quickly

N = 10**7   # MAX_COUNT: the most entries a sequence argument may hold


@pytest.fixture(scope="module")
def printed_distinct() -> np.ndarray:
    """10**7 positive values, no two alike in their printed digits (fuzz 63b's input)."""
    i = np.arange(N)
    return (100000 + i % 900000) / 100000 * 10.0 ** (i // 900000 + 6)


def test_vector_study_counts_scales_before_printing_them(printed_distinct):
    """27.5 CPU-s before (every scale printed and hashed first): refused by the budget at once."""
    from fusion.scenarios import ridge_sensors as rs
    with pytest.raises(ValueError, match="scales and runs"):   # imports and caches, untimed
        rs.vector_study(runs=2, scales=printed_distinct[:10**6])
    refused_quickly(lambda: rs.vector_study(runs=2, scales=printed_distinct), ValueError, "scales and runs")


def test_plugin_study_counts_xs_before_printing_them(printed_distinct):
    """24.7 CPU-s before (9.9e6 xs in (0, 10) printed and hashed first): refused by the budget at once."""
    from fusion.scenarios import ridge_sensors as rs
    i = np.arange(N - 10**5)
    xs = (100000 + i % 900000) / 100000 * 10.0 ** -(i // 900000)
    with pytest.raises(ValueError, match="xs, deltas, m and runs"):   # imports and caches, untimed
        rs.plugin_study(xs=xs[:10**6])
    refused_quickly(lambda: rs.plugin_study(xs=xs), ValueError, "xs, deltas, m and runs")


def test_ridge_budgets_both_bounds():
    """The budgets themselves: the most scales (xs) a call may take are accepted, one more refused."""
    from fusion._limits import LOOP_STEP, MAX_WORK
    from fusion.scenarios import ridge_sensors as rs
    runs = 2   # the steps weighed by their measured cost since fix 72b (fuzz 64b C1, C2)
    edge = MAX_WORK // (2 * (130 * LOOP_STEP + 60 * runs))
    rs._vector_work(edge, runs, "scales and runs")
    with pytest.raises(ValueError, match="scales and runs"):
        rs._vector_work(edge + 1, runs, "scales and runs")
    m, runs, deltas = 5, 4000, 3
    edge = MAX_WORK // ((deltas + 3) * (14 * LOOP_STEP + (m + 5) * runs))
    rs._plugin_work(edge, deltas, m, runs, "xs, deltas, m and runs")
    with pytest.raises(ValueError, match="xs, deltas, m and runs"):
        rs._plugin_work(edge + 1, deltas, m, runs, "xs, deltas, m and runs")


def test_estimated_covariance_study_budgets_sizes_before_hashing_them():
    """2.8 CPU-s before (10**7 sizes hashed first): refused by the first case's memory budget at once."""
    from fusion.scenarios import correlated_sensors as cs
    ns = np.arange(100, N)
    with pytest.raises(ValueError, match=r"ns and reps"):   # imports and caches, untimed
        cs.estimated_covariance_study(ns=ns[:10**5])
    refused_quickly(lambda: cs.estimated_covariance_study(ns=ns), ValueError, r"reps, ns and the sensors")


def test_estimated_covariance_study_still_refuses_a_repeat():
    from fusion.scenarios import correlated_sensors as cs
    with pytest.raises(ValueError, match="ns"):
        cs.estimated_covariance_study(ns=(10, 30, 10), reps=2)


def test_ridge_study_budgets_ms_before_copying_and_hashing_them():
    """3.7 CPU-s before (10**7 ms copied to ints and hashed first; found by grep, fuzz 63b's class): refused at once."""
    from fusion.scenarios import lecture_correlated as lc
    ms = np.arange(1, N + 1)
    with pytest.raises(ValueError, match="ms and draws"):   # imports and caches, untimed
        lc.ridge_study(ms=ms[:10**5])
    refused_quickly(lambda: lc.ridge_study(ms=ms), ValueError, "ms and draws")


def test_ridge_study_still_refuses_a_repeated_m():
    from fusion.scenarios import lecture_correlated as lc
    with pytest.raises(ValueError, match="ms"):
        lc.ridge_study(ms=(1, 5, 1), draws=2)
