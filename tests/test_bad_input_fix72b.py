"""Fuzz 64b C1, C2: ridge_sensors' loop steps weighed by their measured cost.

``vector_study`` counted a (scale, direction) step ``LOOP_STEP + 60 x runs`` units (~11 us at runs = 2) for a step of
three 2 x 2 solves and two validated ``ridge_fusion_plugin`` calls (0.64-1 ms): 20,000 scales at runs = 2 were
accepted and ran 32.9 CPU-s, and the budget's edge (446,428 scales) ~14 min. ``plugin_study`` counted ``LOOP_STEP +
m x runs`` a step (3 + len(deltas) steps an x) for ~0.28 ms an x at m = 2, runs = 2: 80,000 xs ran 28.9 CPU-s, the
edge (249,003 xs) ~90. Each step is now weighed about twice its measured cost (the budgets' docstrings), so that the
edges run ~6 CPU-s. Also: ``plugin_study`` with ``m`` above ``PLUGIN_MAX_M`` ran its whole Monte Carlo over the xs
before the exact curves refused ``m``.
"""

from __future__ import annotations

import functools

import numpy as np
import pytest

from _helpers import refused_quickly


def test_vector_study_edge_by_its_measured_step():
    from fusion._limits import MAX_WORK
    from fusion.scenarios import ridge_sensors as rs
    for runs in (2, 2000):
        edge = MAX_WORK // (2 * (130_000 + 60 * runs))
        rs._vector_work(edge, runs, "scales and runs")        # just inside: accepted (~6.6 CPU-s at runs = 2)
        with pytest.raises(ValueError, match="scales and runs"):
            rs._vector_work(edge + 1, runs, "scales and runs")
    assert MAX_WORK // (2 * (130_000 + 120)) < 4_000


def test_vector_study_refuses_the_fuzz_call_quickly():
    """20,000 scales at runs = 2: accepted before, 32.9 CPU-s."""
    from fusion.scenarios import ridge_sensors as rs
    call = functools.partial(rs.vector_study, runs=2, scales=np.arange(1, 20_001) * 1.0)
    with pytest.raises(ValueError, match="scales and runs"):   # imports, untimed
        call()
    refused_quickly(call, ValueError, "scales and runs")


def test_plugin_study_edge_by_its_measured_step():
    from fusion._limits import MAX_WORK
    from fusion.scenarios import ridge_sensors as rs
    for m, runs, deltas in ((2, 2, 1), (5, 4000, 3)):
        edge = MAX_WORK // ((deltas + 3) * (14_000 + (m + 5) * runs))
        rs._plugin_work(edge, deltas, m, runs, "xs, deltas, m and runs")   # just inside (~5.8 CPU-s at m = runs = 2)
        with pytest.raises(ValueError, match="xs, deltas, m and runs"):
            rs._plugin_work(edge + 1, deltas, m, runs, "xs, deltas, m and runs")
    assert MAX_WORK // (4 * (14_000 + 14)) < 20_000


def test_plugin_study_refuses_the_fuzz_call_quickly():
    """80,000 xs at m = 2, runs = 2, one delta: accepted before, 28.9 CPU-s."""
    from fusion.scenarios import ridge_sensors as rs
    call = functools.partial(rs.plugin_study, xs=np.arange(80_000) / 80_000, m=2, runs=2, curve=(0.0,),
                             deltas=(1.0,))
    with pytest.raises(ValueError, match="xs, deltas, m and runs"):   # imports, untimed
        call()
    refused_quickly(call, ValueError, "xs, deltas, m and runs")


def test_plugin_study_refuses_m_beyond_the_exact_curves_before_the_runs():
    from fusion.readings.biased import PLUGIN_MAX_M
    from fusion.scenarios import ridge_sensors as rs
    call = functools.partial(rs.plugin_study, xs=np.linspace(0.0, 0.01, 10_000), m=PLUGIN_MAX_M + 1, runs=2,
                             curve=(0.0,), deltas=(1.0,))
    with pytest.raises(ValueError, match="^m must be at most"):   # imports, untimed
        call()
    refused_quickly(call, ValueError, "^m must be at most")
    rs.plugin_study(xs=(0.0, 0.01), m=PLUGIN_MAX_M, runs=2, curve=(0.0,), deltas=(1.0,))   # the largest m: accepted


def test_the_books_ridge_calls_stay_accepted():
    from fusion.scenarios import ridge_sensors as rs
    for runs in (2000, 20_000):           # the chapter's vector runs, and the sweep's 10x
        rs._vector_work(3, runs, "runs")
    for runs in (4000, 40_000):           # the chapter's plug-in runs, and the sweep's 10x
        rs._plugin_work(7, 3, 5, runs, "runs")


# the audit of the class in correlated_sensors and lecture_correlated (fix 72b) ------------------------------------

_CASE = {"own": (1.0, 2.0, 3.0), "coupling": (1.0, 1.0, 1.0), "env": 1.5}
_NS = tuple(range(4, 74))   # 70 sizes a case: the most CPU-s a unit the old weight allowed


def test_estimated_covariance_study_weighs_its_n_step():
    """A step over ns was weighed one LOOP_STEP (10 us) for 85-100 us measured: 5,167 cases of 70 ns (reps = 2) were
    inside the budget, ~44 CPU-s; now 761, ~6.5 CPU-s."""
    from fusion._limits import MAX_WORK
    from fusion.scenarios import correlated_sensors as cs
    per = cs._estimated_case_units(3, 2, _NS)
    assert 760 * per <= 761 * per <= MAX_WORK < 762 * per           # just inside and just outside, by the rule
    assert MAX_WORK // per < 1_000
    call = functools.partial(cs.estimated_covariance_study, {f"c{i}": _CASE for i in range(5_167)}, ns=_NS, reps=2)
    with pytest.raises(ValueError, match=r"scenarios \(their sensors\), ns and reps"):   # imports, untimed
        call()
    refused_quickly(call, ValueError, r"scenarios \(their sensors\), ns and reps")
    cs.estimated_covariance_study(ns=(10, 30), reps=400)             # the chapter's call: accepted


def test_ridge_study_budgets_xs_and_ks_fixed_before_listing_them():
    """10**7 xs (ks_fixed) were copied into a list before the budget that needs only their number: 0.36-0.96 CPU-s."""
    from fusion.scenarios import lecture_correlated as lc
    big = np.linspace(0.5, 3.0, 10**7)
    for name, call in (("xs", functools.partial(lc.ridge_study, xs=big)),
                       ("ks_fixed", functools.partial(lc.ridge_study, ks_fixed=big))):
        with pytest.raises(ValueError, match="xs and ks_fixed"):   # imports, untimed
            call()
        refused_quickly(call, ValueError, "xs and ks_fixed", cpu=0.2)


def test_correlated_study_budgets_sizes_before_converting_them():
    """10**7 sizes were converted to ints before the budget that needs only their number: refused after 1.7 CPU-s."""
    from fusion.scenarios import lecture_correlated as lc
    call = functools.partial(lc.correlated_study, runs=2, sizes=np.arange(1, 10**7))
    with pytest.raises(ValueError, match="^sizes ask for"):   # imports, untimed
        call()
    refused_quickly(call, ValueError, "^sizes ask for")
