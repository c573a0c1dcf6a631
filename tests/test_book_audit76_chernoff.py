"""Book audit 76, chapters 06 and 07: the work budgets of the book layer's loops over caller-sized counts.

Each refusal is timed (``refused_quickly``: within 1 CPU-s, before any work) at a count the old code accepted and
ran for minutes to hours; a nearby legitimate call (small, fast) stays accepted. The measurements are in the
weights' comments.
"""
import numpy as np
import pytest

from _helpers import refused_quickly


def test_gaussian_checks_weighs_its_cases_and_triples():
    from fusion.book.chapters.chernoff.gaussian import gaussian_checks
    # no budget: 10**7 cases (~1.1 ms each, about 3 CPU-hours) were accepted
    refused_quickly(lambda: gaussian_checks(np.random.default_rng(0), cases=10**7), ValueError, "^cases and triples")
    refused_quickly(lambda: gaussian_checks(np.random.default_rng(0), triples=20_000), ValueError, "^cases and triples")
    assert gaussian_checks(np.random.default_rng(0), cases=3, triples=2).n_interior >= 0


def test_common_information_check_weighs_its_cases():
    from fusion.book.chapters.chernoff.gaussian import common_information_check
    # no budget: 10**7 cases (~1.4 ms each) were accepted
    refused_quickly(lambda: common_information_check(np.random.default_rng(0), cases=10**7), ValueError, "^cases ask")
    refused_quickly(lambda: common_information_check(np.random.default_rng(0), cases=4_000), ValueError, "^cases ask")
    assert common_information_check(np.random.default_rng(0), cases=3)[0]


def test_is_replicates_weighs_its_sets_and_samples():
    from fusion.book.chapters.chernoff.importance import is_replicate_values, is_replicates
    is_replicates(1, 2, 2)   # the toy study, cached, outside the timed calls
    # only the ceiling of a sample count: 5e6 sets of r = 2 (~1.5 ms each) and 10**7 samples (~14 CPU-s) were accepted
    refused_quickly(lambda: is_replicates(1, 2, 5 * 10**6), ValueError, "^runs and r")
    refused_quickly(lambda: is_replicates(1, 10**6, 10), ValueError, "^runs and r")
    refused_quickly(lambda: is_replicate_values(1, 500), ValueError, "^runs ask")
    assert is_replicates(1, 50, 3).shape == (3,)


def test_defensive_study_weighs_its_replicates_and_samples():
    from fusion.book.chapters.chernoff_steps import defensive_study
    # only the ceiling of a sample count: 5e6 replicates of r = 2 (~5 ms each) and 10**7 samples were accepted
    refused_quickly(lambda: defensive_study(np.random.default_rng(0), runs=5 * 10**6, r=2), ValueError, "^runs and r")
    refused_quickly(lambda: defensive_study(np.random.default_rng(0), runs=2, r=5 * 10**6), ValueError, "^runs and r")
    assert defensive_study(np.random.default_rng(0), runs=3, r=50).runs == 3


def test_study_truths_and_prior_means_weigh_their_runs():
    from fusion.book.chapters.chernoff.settings import study_scenario
    from fusion.book.chapters.chernoff_criteria import prior_means
    from fusion.book.chapters.chernoff_steps import study_truths
    from fusion.scenarios.fusion_networks import premise_scenarios
    sc, net = study_scenario(), next(iter(premise_scenarios().values()))
    # no budget: 10**7 runs (~1 ms and ~52 us each) were accepted
    refused_quickly(lambda: study_truths(sc, 1, 10**7), ValueError, "^runs ask")
    refused_quickly(lambda: prior_means(net, 1, 10**7), ValueError, "^runs ask")
    assert study_truths(sc, 1, 3).shape[0] == 3
    assert prior_means(net, 1, 3).shape == (3, 2)


def test_sigma_first_order_problem_weighs_its_grid():
    from fusion.book.chapters.chernoff_first_order import random_two_mixtures, sigma_first_order_problem
    a, b = random_two_mixtures(np.random.default_rng(3))
    # only the memory budget: n = 11,000 (1.2e8 nodes, ~0.9 us each) was accepted
    refused_quickly(lambda: sigma_first_order_problem(a, b, n=11_000), ValueError, "^n ask")
    assert 0.0 <= sigma_first_order_problem(a, b, n=101).omega_exact <= 1.0


class _Ran(Exception):
    """The call passed its budget and reached its work."""


def test_sigma_first_order_study_weighs_its_problems(monkeypatch):
    import fusion._limits as L
    import fusion.book.chapters.chernoff_first_order as cf
    # no budget: 10**7 problems (~120 ms each) were accepted; the entry serves the appendix's 100 problems
    refused_quickly(lambda: cf.sigma_first_order_study(np.random.default_rng(0), runs=10**7), ValueError,
                    "^runs ask.*STUDY_WORK: chapter 06's appendix call of sigma_first_order_study")
    refused_quickly(lambda: cf.sigma_first_order_study(np.random.default_rng(0), runs=210), ValueError, "^runs ask")
    counted = []

    def spy(shape, names, weight=1, limit=L.MAX_WORK, served=None):
        counted.append(L.work(shape, names, weight=weight, limit=10**30))
        raise _Ran
    monkeypatch.setattr(cf, "work", spy)
    with pytest.raises(_Ran):  # the appendix's call, counted: the entry is twice it, rounded up to a whole MAX_WORK
        cf.sigma_first_order_study(np.random.default_rng(0))
    entry = L.STUDY_WORK[L.SIGMA_FIRST_ORDER_STUDY]
    assert L.MAX_WORK < counted[0] <= entry and entry == -(-2 * counted[0] // L.MAX_WORK) * L.MAX_WORK
