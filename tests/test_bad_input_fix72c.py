"""Fuzz 64b's findings on ``fusion.scenarios.two_sensor`` (C3, C4, C5, C7, D1) and the audit of its loop budgets:
each loop step weighed by its measured cost, a sequence's entries read after the budget that needs only its length."""

from __future__ import annotations

import functools

import numpy as np
import pytest

from _helpers import refused_quickly

from fusion._limits import MAX_WORK
from fusion.scenarios import two_sensor
from fusion.scenarios.two_sensor import architecture, bounds, case

R, Q = 100.0 * np.eye(2), np.eye(4)


def _path_units(periods, readings):
    """The units ``path_by_period`` counts for ``periods`` and ``readings`` readings (its budget alone)."""
    Ts = np.asarray(periods, dtype=float)
    return bounds._path_units(Ts.size, float(np.sum(np.floor(260.0 / Ts) + 1.0)), readings)


def test_path_by_period_counts_each_period():
    """C3: 5,000 periods in [40, 60] s ran 34.3 CPU-s accepted (a period's own 6.4 ms not counted): refused at once;
    the edge at those periods is about 700 (about 5 CPU-s), the chapter's call far inside."""
    call = functools.partial(bounds.path_by_period, np.linspace(40, 60, 5000), 1.0, 1.0, t_steady=0.0)
    refused_quickly(call, ValueError, "periods and readings")
    assert _path_units(np.linspace(40, 60, 650), 3) <= MAX_WORK < _path_units(np.linspace(40, 60, 750), 3)
    call = functools.partial(bounds.path_by_period, np.linspace(40, 60, 750), 1.0, 1.0, t_steady=0.0)
    refused_quickly(call, ValueError, "periods and readings")
    assert _path_units([1.0, 0.1, 0.02], 2) < MAX_WORK / 3   # notebook 05's call


def test_path_by_period_names_a_period_without_straight_leg_step():
    """D1: a period whose path has no straight-leg step after t_steady was refused as an overflow of an empty mean."""
    with pytest.raises(ValueError, match=r"t_steady = 0.0 leaves no straight-leg step .* periods entry 200.0 s"):
        bounds.path_by_period(np.linspace(200, 260, 3), 1.0, 1.0, t_steady=0.0)
    with pytest.raises(ValueError, match=r"leaves no straight-leg step .* periods entry 80.0 s .its last straight-leg "
                                         r"step is at 80 s.: lower t_steady"):
        bounds.path_by_period([80.0], 1.0, 1.0, t_steady=100.0)


def test_q_scaling_study_budget_before_the_scales_are_printed():
    """C4: 10**7 scales were printed and hashed before the budget (21-26 CPU-s): refused by their number."""
    scales = np.linspace(0.1, 2.0, 10**7)
    call = functools.partial(two_sensor.q_scaling_study, np.random.default_rng(0), R, R, Q, scales, runs=1, nees_runs=1)
    refused_quickly(call, ValueError, "scales, runs, nees_runs and T")
    with pytest.raises(ValueError, match="scales must not repeat"):   # the entries still checked, after the budget
        two_sensor.q_scaling_study(np.random.default_rng(0), R, R, Q, (1.0, 1.0), runs=1, nees_runs=1, T=5.0)


def test_q_scaling_study_weighs_a_scale_step_by_its_cost():
    """C5: 700 scales at T = 1 ran 33.3 CPU-s accepted (a scale's step counted 10 us, measured 175-260 us): refused;
    the edge, about 95 scales of one run each (about 5 CPU-s), accepted by the budget, the chapter's call inside."""
    def units(scales, runs):   # with each scale's fixed cost (fix73a, fuzz 65b C2)
        return architecture._q_scaling_units(scales, 261, 2 * runs)
    assert units(90, 1) <= MAX_WORK < units(100, 1)
    assert units(5, 2000) < MAX_WORK   # notebook 05's five scales, at ten times its 200 runs
    call = functools.partial(two_sensor.q_scaling_study, np.random.default_rng(0), R, R, Q, np.linspace(0.1, 2, 100),
                             runs=1, nees_runs=1)
    refused_quickly(call, ValueError, "scales, runs, nees_runs and T")


@pytest.mark.parametrize("name", ["printed_omegas", "placement_omegas"])
def test_architecture_study_budget_before_the_omegas_are_hashed(name):
    """C7: 10**7 omegas were hashed one by one before the budget (14-16 CPU-s): refused by their number first."""
    call = functools.partial(two_sensor.architecture_study, np.random.default_rng(0), R, R, Q, runs=1, nees_runs=1,
                             **{name: np.linspace(0.01, 1.0, 10**7)})
    refused_quickly(call, ValueError, "printed_omegas, placement_omegas, runs, nees_runs and T")
    with pytest.raises(ValueError, match=f"{name} must not repeat"):
        two_sensor.architecture_study(np.random.default_rng(0), R, R, Q, runs=1, nees_runs=1, T=5.0,
                                      **{name: (0.5, 0.5)})


def test_two_sensor_scenario_counts_each_step():
    """Audit: one run of 400,000 steps (about 20 CPU-s) was accepted, a step's 51 us not counted: the edge of one run is
    now about 83,000 steps (about 4 CPU-s)."""
    assert case._scenario_budget(1, 80_000, "r") <= MAX_WORK
    with pytest.raises(ValueError, match="runs and T"):
        case._scenario_budget(1, 90_000, "runs and T")
    assert case._scenario_budget(2000, 261, "r") < MAX_WORK / 10   # chapter 05's scenarios at ten times their runs
    call = functools.partial(two_sensor.two_sensor_scenario, R, R, Q, np.random.default_rng(0), runs=1, T=260 / 99_999)
    refused_quickly(call, ValueError, "runs and T")
