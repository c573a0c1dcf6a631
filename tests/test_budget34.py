"""Work budgets of fuzz 34a (rule 17): the tracking study's is counted at entry and named by the caller's arguments."""
import numpy as np
import pytest


def _small():
    from fusion.scenarios import range_bearing as rb
    return rb, rb.RangeBearingScenario(frames=2, n_particles=60, n_samples=60, n_central=100, em_iterations=2,
                                       n_components=1)


def test_monte_carlo_refuses_hours_of_runs_by_name():
    # fuzz 34a C7: 8e6 runs (about 9 hours) were accepted; refused at entry, naming runs
    rb, sc = _small()
    with pytest.raises(ValueError, match="runs, sc.frames"):
        rb.monte_carlo(sc, 1, 8_000_000)


def test_run_tracking_batch_refuses_by_seeds():
    rb, sc = _small()
    seeds = [np.random.SeedSequence(1)] * 100_000
    with pytest.raises(ValueError, match="seeds, sc.frames"):
        rb.run_tracking_batch(sc, seeds)


def test_book_tracking_study_stays_inside():
    # chapter 06's study (100 runs of the default scenario) is well inside the budget: counted, not run
    from fusion.scenarios import range_bearing as rb
    from fusion.book.chapters.chernoff.settings import STUDY_RUNS
    assert rb._tracking_work(rb.RangeBearingScenario(), STUDY_RUNS, "runs") <= rb.TRACK_WORK / 2  # budget35's rule


def test_nees_study_step_weighs_its_measured_cost():
    # fuzz 34a C9: 82,000 steps of 2 runs (about 40 CPU-s) were accepted; a step is ~0.58 ms, so ~17,000 is the edge
    from fusion.scenarios.two_sensor.study import _nees_work
    _nees_work(15_000, 2)
    with pytest.raises(ValueError, match="runs and n_steps"):
        _nees_work(25_000, 2, "runs and n_steps")
    with pytest.raises(ValueError, match="n_steps and runs"):
        _nees_work(4_000, 1_000)


def test_run_network_study_counts_its_work_at_entry():
    # fuzz 34a C8: 6,000 default runs worked 9.4 CPU-s, then the swarm's budget named its own arguments
    import fusion.scenarios.fusion_networks as f
    nodes = (f.NetworkNode((800.0, 700.0), "bearing"), f.NetworkNode((1000.0, 1050.0), "range"))
    with pytest.raises(ValueError, match="^runs, sc.nodes"):
        f.run_network_study(f.NetworkScenario("d", nodes), 1, 6000)
