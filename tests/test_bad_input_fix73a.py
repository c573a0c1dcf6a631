"""Fuzz 65b C1 and C2 on ``fusion.scenarios.two_sensor``: a loop budget counts each entry's fixed cost besides its steps'.

``architecture_study``'s fixed weights and ``q_scaling_study``'s scales were weighed by their steps only (measured at
T = 1, 261 steps), so on a path of 1-3 steps (T = 130-300) thousands of entries ran 40-50 CPU-s accepted. Each test
stops an accepted call at its first draw (a sentinel), so that a budget that lets it through fails at once."""

from __future__ import annotations

import functools

import numpy as np
import pytest

from _helpers import refused_quickly

from fusion._limits import ARCHITECTURE_STUDY, MAX_WORK, STUDY_WORK
from fusion.scenarios import two_sensor
from fusion.scenarios.two_sensor import architecture

R, Q = np.diag([100.0, 1e-4]), 0.01 * np.eye(4)
ARCH_NAMES = "printed_omegas, placement_omegas, runs, nees_runs and T"
Q_NAMES = "scales, runs, nees_runs and T"


class Drew(Exception):
    """The call passed its budget and reached its draws."""


@pytest.fixture
def no_draw(monkeypatch):
    def drew(*args, **kwargs):
        raise Drew
    monkeypatch.setattr(architecture, "_path_and_model_measurements", drew)


def _steps(T):
    return two_sensor.trajectory(T).t.size


def _arch(T, name, n, **kw):
    return functools.partial(two_sensor.architecture_study, np.random.default_rng(0), R, 2 * R, Q, runs=2,
                             nees_runs=2, T=T, t_steady=0.0, **{name: np.linspace(0.01, 1.0, n)}, **kw)


@pytest.mark.parametrize("name, T, edge", [("printed_omegas", 130.0, 4_502), ("placement_omegas", 200.0, 5_192),
                                           ("placement_omegas", 300.0, 6_132)])
def test_architecture_study_counts_each_weights_fixed_cost(no_draw, name, T, edge):
    """C1: 9,500 printed weights at T = 130 (3 steps) ran 50.0 CPU-s accepted; 4,000 placement weights at T = 200 ran
    16.2 CPU-s counted 4e8 units (a placement weight, two filter banks, was counted as one, with no fixed cost). Now a
    weight, printed or placed, counts two banks with their fixed cost: the edge (4.4-4.8 ms a weight measured at 3
    steps, so about 20 CPU-s) is accepted, one more refused before any work."""
    entry = STUDY_WORK[ARCHITECTURE_STUDY]
    assert architecture._arch_units(_steps(T), 2, 2, 2 * edge) <= entry < architecture._arch_units(_steps(T), 2, 2,
                                                                                                    2 * edge + 2)
    refused_quickly(_arch(T, name, edge + 1), ValueError, ARCH_NAMES)
    with pytest.raises(Drew):
        _arch(T, name, edge)()


def test_architecture_study_refuses_the_fuzz_calls(no_draw):
    """C1's calls: 9,500 printed weights at T = 130, 4,000 and 29,900 placement weights at T = 200 (16.2 CPU-s ran; the
    edge, about 120 CPU-s extrapolated): refused before any work, naming the weights."""
    refused_quickly(_arch(130.0, "printed_omegas", 9_500), ValueError, ARCH_NAMES)
    refused_quickly(_arch(200.0, "placement_omegas", 29_900), ValueError, ARCH_NAMES)
    # 4,000 placement weights at T = 200 (16.2 CPU-s measured) are now within the budget, counted 2.3e9 units, not 4e8
    assert 2.2e9 < architecture._arch_units(_steps(200.0), 2, 2, 8_000) < 2.4e9


def test_a_placement_weight_counts_as_much_as_a_printed_one(monkeypatch):
    """Both run two ``fusion_loop`` banks (2.6 and 2.4 ms measured at one step, 307 and 278 at 261): counted alike."""
    counted = []

    def spy(shape, names, weight=1, limit=MAX_WORK, served=None):
        counted.append(int(np.prod(shape)) * weight)
        raise Drew

    monkeypatch.setattr(architecture, "work", spy)
    for name in ("printed_omegas", "placement_omegas"):
        with pytest.raises(Drew):
            _arch(1.0, name, 3)()
    assert counted[0] == counted[1] == architecture._arch_units(261, 2, 2, 6)


def _scaling(T, n, runs=2):
    return functools.partial(two_sensor.q_scaling_study, np.random.default_rng(0), R, 2 * R, Q,
                             np.linspace(0.01, 1.0, n), runs=runs, nees_runs=runs, T=T, t_steady=0.0)


@pytest.mark.parametrize("T, edge", [(300.0, 2_270), (200.0, 2_080), (1.0, 91)])
def test_q_scaling_study_counts_each_scales_fixed_cost(no_draw, T, edge):
    """C2: 24,000 scales at T = 300 (one step) ran 38.7-48.2 CPU-s accepted, counted 0.40 ms a scale where it costs
    2.0-2.4 ms. Now a scale's fixed cost counts too (twice the measured, as its steps): the edge (about 5 CPU-s at one
    step) is accepted, one more refused before any work."""
    units = architecture._q_scaling_units
    assert units(edge, _steps(T), 4) <= MAX_WORK < units(edge + 1, _steps(T), 4)
    refused_quickly(_scaling(T, edge + 1), ValueError, Q_NAMES)
    with pytest.raises(Drew):
        _scaling(T, edge)()


def test_q_scaling_study_refuses_the_fuzz_calls(no_draw):
    """C2's calls, 24,000 scales at T = 300 and 12,000 at T = 200 (31.8 CPU-s): refused before any work; notebook 05's
    five scales at the reseeding sweep's ten times its 200 runs stay well inside."""
    refused_quickly(_scaling(300.0, 24_000), ValueError, Q_NAMES)
    refused_quickly(_scaling(200.0, 12_000), ValueError, Q_NAMES)
    assert architecture._q_scaling_units(5, 261, 4_000) < MAX_WORK
