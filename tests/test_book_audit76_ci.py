"""Book audit 76, chapter 05 (covariance intersection): the work budgets of the book layer's public functions.

Each function below looped over a caller-sized argument with no budget (or one weighed below its measured cost), so
its accepted edge ran far beyond about 10 CPU-s, or checked a long list entry by entry before the budget its length
sets. Each is now refused at once at (or beyond) its old edge, by the argument's name; a nearby call of the book's
size is still accepted.
"""

from __future__ import annotations

import numpy as np
import pytest

from _helpers import refused_quickly

from fusion.book.chapters import ci
from fusion.scenarios import two_sensor


@pytest.fixture(scope="module")
def one_run():
    """One run of the printed pair at T = 1 s (261 steps), its fusion study."""
    Q, R1, R2 = ci.printed_covariances()
    sc = two_sensor.two_sensor_scenario(R1, R2, Q, np.random.default_rng(0), runs=1, T=1.0)
    return sc, two_sensor.fusion_study(sc)


def test_fuzzy_levels_counts_its_levels_steps_and_runs(one_run):
    """No budget: 0.65 ms a level and step, so 100 levels of 261 steps ran about 17 CPU-s, and a list of 10**6 levels
    was checked entry by entry first. Refused at once by ``levels``; the paired study's three levels accepted."""
    sc, _ = one_run
    refused_quickly(lambda: ci.fuzzy_levels(sc, np.linspace(0.001, 0.999, 100)), ValueError, r"^levels")
    many = [0.5] * 10**6
    refused_quickly(lambda: ci.fuzzy_levels(sc, many), ValueError, r"^levels")
    out = ci.fuzzy_levels(sc, (0.001, 0.05, 0.1))
    assert sorted(out) == [0.001, 0.05, 0.1] and all(v.shape == (1,) for v in out.values())


def test_slip_at_weights_counts_its_weights(one_run):
    """Each weight's ``fuse_tracks`` was checked alone (95 ms each at 261 steps): 200 weights ran about 19 CPU-s,
    1,000 about 95. Refused at once by ``omegas``; the chapter's two published weights accepted."""
    sc, study = one_run
    refused_quickly(lambda: ci.slip_at_weights(sc, study, list(np.linspace(0.0, 1.0, 200))), ValueError, r"^omegas")
    many = [0.5] * 10**6
    refused_quickly(lambda: ci.slip_at_weights(sc, study, many), ValueError, r"^omegas")
    assert len(ci.slip_at_weights(sc, study)) == 2


def test_pcrb_table_counts_its_periods():
    """No budget: 4 ms a period, so 10,000 periods ran about 40 CPU-s. Refused at once by ``periods`` (float32 ones
    too, which were read one by one first); the chapter's eight periods accepted."""
    periods = np.round(np.linspace(0.01, 100.0, 10_000), 2)
    refused_quickly(lambda: ci.pcrb_table(periods, 10.0, 1.0), ValueError, r"^periods ask")
    narrow = periods.astype(np.float32)
    refused_quickly(lambda: ci.pcrb_table(narrow, 10.0, 1.0), ValueError, r"^periods ask")
    table = ci.pcrb_table([5.0, 2.0, 1.0, 0.5, 0.1, 0.02, 0.005, 0.001], 10.0, 1.0)
    assert table.shape[0] == 9


def test_ml_vs_product_counts_its_runs():
    """No budget: a ``convex_combination`` call a run, 190 us, so 10**6 runs ran about 190 CPU-s. Refused at once
    by ``x1 and x2``; the chapter's 50 runs of n = 4 accepted."""
    x = np.zeros((10**6, 1))
    refused_quickly(lambda: ci.ml_vs_product(x, np.eye(1), x, 2 * np.eye(1)), ValueError, r"^x1 and x2")
    x = np.random.default_rng(0).normal(size=(50, 4))
    assert ci.ml_vs_product(x, np.eye(4), x + 0.1, 2 * np.eye(4)) < 1e-9


def test_split_ci_exactness_weighs_its_step_as_measured():
    """At 70 loop steps a step (0.70 ms measured once), its edge of 14,285 steps ran 20.5 CPU-s; re-measured at
    1.15 ms and weighed twice it is refused at once; 300 steps accepted."""
    Q, R1, _ = ci.printed_covariances()
    refused_quickly(lambda: ci.split_ci_exactness(Q, R1, 1.0, 14_285), ValueError, r"^n_steps ask")
    assert ci.split_ci_exactness(Q, R1, 1.0, 300)["nees_random_max"] > 0


def test_printed_weight_facts_counts_its_grid_and_seeds(one_run):
    """The grid had a memory budget only: 20,000 points of 261 steps ran 20.8 CPU-s, the edge (about 64,000) about
    66; and the seeds were checked one by one before the searches' budget. Both refused at once by name; a call of
    the book's shape (two scenarios, the default grid) accepted."""
    sc, _ = one_run
    refused_quickly(lambda: ci.printed_weight_facts((sc,), 10, [1], 20_000), ValueError,
                    r"^scenarios, seeds and n_grid")
    many = list(range(10**7))
    refused_quickly(lambda: ci.printed_weight_facts((sc,), 10, many), ValueError, r"^scenarios, seeds and n_grid")
    Q, R1, _ = ci.printed_covariances()
    other = two_sensor.two_sensor_scenario(R1, R1 / 9, Q, np.random.default_rng(1), runs=1, T=1.0)
    facts = ci.printed_weight_facts((sc, other), 10, [1, 2])
    assert facts.steps == 2 * sc.t.size


def test_weight_pair_counts_its_seeds_before_reading_them():
    """A list of 10**7 FOA seeds was checked (3.1 CPU-s) and hashed before the searches' budget refused it. Now
    refused at once by ``fruit_fly_seeds``; three seeds accepted."""
    Q, R1, _ = ci.printed_covariances()
    many = list(range(10**7))
    refused_quickly(lambda: ci.weight_pair(R1, R1 / 9, Q, 10, 0, 0, many), ValueError,
                    r"^runs, T and fruit_fly_seeds ask .*: fruit_fly_seeds ask")
    pair = ci.weight_pair(R1, R1 / 9, Q, 10, 0, 0, [1, 2, 3], runs=2)
    assert len(pair.fruit_fly_seeds.seeds) == 3


def test_nees_per_step_weighs_its_own_steps():
    """Counted at ``nees_study``'s weights (58 loop steps and 250 units a run), its edge of about 17,000 steps of 2
    runs would run about 38 CPU-s (2.24 ms a step measured). Refused at once by ``n_steps and runs``; 50 steps of 3
    runs accepted."""
    Q, R1, _ = ci.printed_covariances()
    refused_quickly(lambda: ci.nees_per_step(np.random.default_rng(0), Q, R1, R1 / 9, np.zeros(4), 17_000, 2),
                    ValueError, r"^n_steps and runs ask")
    assert set(ci.nees_per_step(np.random.default_rng(0), Q, R1, R1 / 9, np.zeros(4), 50, 3))
