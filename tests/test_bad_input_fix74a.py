"""Fuzz 66b on ``fusion.scenarios.two_sensor``: C2 (``architecture_study``'s weights keyed by how they print) and D1
(``path_by_period``'s repeated readings), each refused by name after the budget and before any draw or filter step."""

from __future__ import annotations

import numpy as np
import pytest

from _helpers import refused_quickly

from fusion.scenarios import two_sensor
from fusion.scenarios.two_sensor import architecture, bounds

R, Q = np.diag([100.0, 1e-4]), 0.01 * np.eye(4)


class Drew(Exception):
    """The call passed its checks and reached its draws (or its first filter step)."""


def _drew(*args, **kwargs):
    raise Drew


@pytest.mark.parametrize("name, weights", [("printed_omegas", [0.5, 0.5 + 1e-12]),
                                           ("placement_omegas", [0.5, 0.5000001]),
                                           ("printed_omegas", [0.3, 0.25, 0.3000001])])
def test_architecture_study_refuses_weights_that_print_the_same(monkeypatch, name, weights):
    """C2: two weights that differ but print the same with ``:g`` key one result ("..._w0.5"), the last silently
    replacing the other (20 result keys, as for one weight): refused naming the argument, before any draw."""
    monkeypatch.setattr(architecture, "_path_and_model_measurements", _drew)
    refused_quickly(lambda: two_sensor.architecture_study(np.random.default_rng(0), R, 2 * R, Q, runs=2, nees_runs=2,
                                                          T=20.0, t_steady=0.0, **{name: weights}),
                    ValueError, f"^{name} must differ in how its entries print")


@pytest.mark.parametrize("name, weights", [("printed_omegas", [0.5, 0.500001]), ("placement_omegas", [0.5, 0.25])])
def test_architecture_study_accepts_weights_that_print_apart(monkeypatch, name, weights):
    # the other bound: weights distinct at 6 significant digits pass to the draws
    monkeypatch.setattr(architecture, "_path_and_model_measurements", _drew)
    with pytest.raises(Drew):
        two_sensor.architecture_study(np.random.default_rng(0), R, 2 * R, Q, runs=2, nees_runs=2, T=20.0,
                                      t_steady=0.0, **{name: weights})


def test_path_by_period_refuses_a_repeated_reading(monkeypatch):
    """D1: readings = Q_READINGS * 2200 ran (and counted) 6,600 readings and returned 3 a period, the repeats merged
    into one key each; now refused naming readings, after the budget, before any path is run."""
    monkeypatch.setattr(bounds, "cv_model", _drew)  # the first period's model: an accepted call stops there
    rd = two_sensor.Q_READINGS
    refused_quickly(lambda: two_sensor.path_by_period([10.0, 5.0], 10.0, 1.0, readings=(rd[0], rd[1], rd[0]),
                                                      t_steady=0.0), ValueError, "^readings must not repeat")
    refused_quickly(lambda: two_sensor.path_by_period([10.0], 10.0, 1.0, readings=rd * 2200, t_steady=0.0),
                    ValueError, "^readings must not repeat")


def test_path_by_period_accepts_distinct_readings(monkeypatch):
    # the other bound: every reading once, or one, passes to the periods' paths
    monkeypatch.setattr(bounds, "cv_model", _drew)
    for rd in (two_sensor.Q_READINGS, two_sensor.Q_READINGS[:1]):
        with pytest.raises(Drew):
            two_sensor.path_by_period([10.0, 5.0], 10.0, 1.0, readings=rd, t_steady=0.0)


def test_a_banks_path_run_step_is_counted() -> None:
    """Fuzz 66b C1: every fixed-weight bank filters every path run, but only its NEES runs' steps were counted: 8,000
    path runs, 1 NEES run, 88 printed weights (176 banks) at T = 1 counted 2.977e9 (its entry 3e9) and ran 92.0
    CPU-s. A bank's path-run step is counted (``_PATH_BANK``): that call is now beyond its entry by the count alone."""
    from fusion._limits import ARCHITECTURE_STUDY, STUDY_WORK
    from fusion.scenarios.two_sensor import architecture

    assert architecture._arch_step_units(176)[1] == architecture._RUN_STEP + 176 * architecture._PATH_BANK
    steps = 261   # T = 1 on the 260 s path
    assert architecture._arch_units(steps, 8_000, 1, 176) > STUDY_WORK[ARCHITECTURE_STUDY]
