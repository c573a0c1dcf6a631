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
