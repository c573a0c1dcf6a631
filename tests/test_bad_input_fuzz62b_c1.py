"""Fuzz 62b C1-C3: a sequence whose LENGTH alone sets the budget is counted by len() before any entry is read.

Each function below checked every entry of a long sequence (``_check_name``, ``seed_sequence``, ``one_of``) before
the work budget, which refuses it by the number of entries alone: 10**7 entries (the input ceiling,
``fusion._counts.MAX_COUNT``) were refused only after 5-14 CPU-s. The budget now comes first ("length -> budget ->
entries"); the inputs are built outside the timing. Each refusal names the same arguments as before.
"""

from __future__ import annotations

import numpy as np
import pytest

from _helpers import refused_quickly

N = 10**7   # MAX_COUNT: the most entries a sequence argument may hold


@pytest.fixture(scope="module")
def names() -> list[str]:
    return ["reg_two_point"] * N


def test_monte_carlo_counts_names_by_length(names):
    """7.1-9.3 CPU-s before (every name checked by the unknown-list and _check_name): refused at once."""
    from fusion.scenarios import time_registration as tr
    tr.monte_carlo(["reg_two_point"], 1.0, 2, 0)   # imports and caches, untimed
    refused_quickly(lambda: tr.monte_carlo(names, 1.0, 2, 0), ValueError, "names, t_src and t_dst")


def test_fusion_runs_counts_names_by_length(names):
    """5.2 CPU-s before: refused at once, naming names."""
    from fusion.scenarios import time_registration as tr
    tr.fusion_runs(["reg_two_point"], 1.0, 2, 0)
    refused_quickly(lambda: tr.fusion_runs(names, 1.0, 2, 0), ValueError, "names")


def test_monte_carlo_counts_each_name():
    """Each entry of names weighs MC_NAME_UNITS (a Kalman method on its filtered states, 22-25 us a name measured):
    before, 400,000 names of reg_kalman_predict at 2 runs were within the budget (about 8.9 million were); now
    refused at once, and 300,000 (about 7 CPU-s) accepted by the same budget."""
    from fusion.scenarios import time_registration as tr
    t1, t2 = tr.instants()
    tr._monte_carlo_work(["reg_kalman_predict"] * 300_000, 2, t1.size, t2.size, "runs", "names",
                         name_units=tr.MC_NAME_UNITS)
    many = ["reg_kalman_predict"] * 400_000
    refused_quickly(lambda: tr.monte_carlo(many, 1.0, 2, 0), ValueError, "names, t_src and t_dst")


def test_time_registration_entry_checks_kept():
    """The entries are still read after the budget: an unknown name and a non-text entry refused by name."""
    from fusion.scenarios import time_registration as tr
    with pytest.raises(ValueError, match="unknown"):
        tr.monte_carlo(["reg_two_point", "nope"], 1.0, 2, 0)
    with pytest.raises(ValueError, match=r"names\[1\]"):
        tr.fusion_runs(["reg_two_point", "nope"], 1.0, 2, 0)
    with pytest.raises(TypeError, match=r"names\[0\]"):
        tr.fusion_runs([3], 1.0, 2, 0)


def test_run_tracking_batch_counts_seeds_by_length():
    """4.2 CPU-s at 10**6 seeds and 13.7 at 3 * 10**6 before (each checked by seed_sequence; the budget accepts
    about 700 runs of the default scenario): refused at once, naming the seeds."""
    from fusion.scenarios import range_bearing as rb
    sc = rb.RangeBearingScenario()
    seeds = [np.random.SeedSequence(1)] * (3 * 10**6)
    refused_quickly(lambda: rb.run_tracking_batch(sc, seeds), ValueError, "seeds, sc.frames")


def test_run_tracking_batch_entry_checks_kept():
    """A bad seed, a bad all_nodes entry, a length mismatch and a repeated seed object are still refused by name."""
    from fusion.scenarios import range_bearing as rb
    sc = rb.RangeBearingScenario()
    s = np.random.SeedSequence(1)
    with pytest.raises(TypeError, match=r"seeds\[1\]"):
        rb.run_tracking_batch(sc, [s, 3])
    with pytest.raises(ValueError, match="all_nodes must have 2 entries"):
        rb.run_tracking_batch(sc, [s, np.random.SeedSequence(2)], all_nodes=[True])
    with pytest.raises((TypeError, ValueError), match=r"all_nodes\[1\]"):
        rb.run_tracking_batch(sc, [s, np.random.SeedSequence(2)], all_nodes=[True, "x"])
    with pytest.raises(ValueError, match=r"seeds\[1\] is the same SeedSequence object"):
        rb.run_tracking_batch(sc, [s, s])


def test_path_by_period_counts_readings_by_length():
    """8.7-9.9 CPU-s before (one_of on every reading): refused at once, naming periods and readings."""
    from fusion.scenarios.two_sensor import bounds
    readings = [bounds.Q_READINGS[0]] * N
    refused_quickly(lambda: bounds.path_by_period([1.0], 1.0, 1.0, readings=readings), ValueError,
                    "periods and readings")


def test_path_by_period_entry_checks_kept():
    """An unknown reading and a repeated period are still refused by name."""
    from fusion.scenarios.two_sensor import bounds
    with pytest.raises(ValueError, match="readings"):
        bounds.path_by_period([1.0], 1.0, 1.0, readings=("nope",))
    with pytest.raises(ValueError, match="periods"):
        bounds.path_by_period([1.0, 1.0], 1.0, 1.0)


def test_tracking_run_readers_count_runs_by_length():
    """The run readers (position_sq_errors, nees_per_frame, min_local_ess: ``_check_runs``) checked every entry's type
    before their loop budget, which needs only len(runs) and the first run's frames: 1.9 CPU-s at 10**7 runs
    (fix70a, the class of fuzz 62b); now refused at once, and a wrong entry after the first still named."""
    from fusion.scenarios import range_bearing as rb
    sc = rb.RangeBearingScenario(frames=3, n_particles=50, n_samples=50, n_initial=50)
    r = rb.run_tracking_batch(sc, [np.random.SeedSequence(1)])[0]
    runs = [r] * N
    refused_quickly(lambda: rb.min_local_ess(runs), ValueError, "runs ask for", cpu=0.5)
    with pytest.raises(TypeError, match=r"runs\[1\]"):
        rb.min_local_ess([r, 3])
    with pytest.raises(TypeError, match=r"runs\[0\]"):
        rb.min_local_ess([3, r])


@pytest.fixture(scope="module")
def floats() -> list[float]:
    """10**7 distinct positive floats, built once, outside every timing."""
    return np.arange(1, N + 1, dtype=float).tolist()


@pytest.mark.parametrize("call, match, cpu", [
    # 8.2 CPU-s before (params hashed twice and printed before loop_work); 1.8 after, most of it the conversion
    (lambda v: __import__("fusion.scenarios.lecture_weighting.belief", fromlist=["x"]).belief_parameter_study(
        params=v, grid=[1.0]), "params and snapshots", 4.0),
    # 3.2 CPU-s before (levels hashed before loop_work); 1.2 after
    (lambda v: __import__("fusion.scenarios.lecture_weighting.estimators", fromlist=["x"]).awf_study(levels=v),
     "levels, runs, k_max and sigma", 2.5),
    # 3.7 CPU-s before (xs hashed before loop_work); 1.1 after
    (lambda v: __import__("fusion.scenarios.lecture_correlated", fromlist=["x"]).ridge_study(xs=v),
     "xs and ks_fixed", 2.5),
], ids=["belief_parameter_study", "awf_study", "ridge_study"])
def test_sweeps_hashed_after_budget(floats, call, match, cpu):
    """The same class found by grep (fix70a): a sweep's repeats looked for (distinct, 2.5 CPU-s for 10**7 entries)
    before a budget that needs only its number; now after it (the array conversion stays first)."""
    refused_quickly(lambda: call(floats), ValueError, match, cpu=cpu)


def test_sweep_repeats_still_refused():
    """A repeated entry is still refused by name after the budget."""
    from fusion.scenarios import lecture_correlated as lc
    from fusion.scenarios.lecture_weighting import estimators
    with pytest.raises(ValueError, match="xs"):
        lc.ridge_study(xs=[1.0, 1.0])
    with pytest.raises(ValueError, match="levels"):
        estimators.awf_study(levels=[1.0, 1.0], runs=2, k_max=100)
    with pytest.raises(ValueError, match="sizes"):
        lc.correlated_study(sizes=[2, 2])
