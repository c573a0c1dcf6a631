"""Fix 72f (fuzz 64b's class in fusion/estimates, filtering, registration, optimise, readings): a loop step
weighed far below its measured cost lets the budget's edge run far beyond ~10 CPU-s."""
from __future__ import annotations

import functools

import numpy as np
import pytest

from _helpers import refused_quickly


@pytest.mark.parametrize("weighted", ["weighted_em", "weighted_em_batch"])
def test_em_counts_an_iteration_step(weighted):
    """An EM iteration of one set of 200 points and 5 components in one dimension costs ~85 us (its Python step),
    counted 5 x 200 units (10 us) before: 10**6 iterations at tol = 0 (~80 CPU-s) were accepted. The new edge,
    51,280 iterations (~4.5 CPU-s; 52,631 before fix 74b counted the set's share of an iteration and its
    initialisation), is accepted by the rule; 60,000 are refused before any work."""
    from fusion.estimates import mixtures

    mixtures._em_work(51_280, 1, 200, 5, 1)  # the edge just inside: the rule alone (the fit is not run)
    with pytest.raises(ValueError, match="max_iter, x and n_components"):
        mixtures._em_work(51_281, 1, 200, 5, 1)
    x = np.random.default_rng(2).uniform(size=(200, 1))
    w = np.full(200, 1 / 200)
    call = (functools.partial(mixtures.weighted_em, x, w, 5, np.random.default_rng(0), max_iter=60_000, tol=0.0)
            if weighted == "weighted_em" else
            functools.partial(mixtures.weighted_em_batch, x[None], w[None], 5, [np.random.default_rng(0)],
                              max_iter=60_000, tol=0.0))
    refused_quickly(call, ValueError, r"^max_iter, x and n_components ask for")


@pytest.mark.parametrize("fused", ["first_order_fusion", "fuse_mixtures"])
def test_mixture_fusions_count_a_step_a_mixture(fused):
    """A mixture costs first_order_fusion ~11-12 us of Python (reading its arrays), counted 29 units (0.3 us) before:
    10**6 one-component mixtures were accepted and ran 12 CPU-s (the edge, 3.4e7, ~400). The new edge, 395,000
    mixtures (~4.7 CPU-s), is accepted by the rule; 10**6 are refused quickly."""
    from fusion._limits import work
    from fusion.estimates.chernoff import mixture
    from fusion.estimates.chernoff._product import MIXTURE_STEP, product_size
    from fusion.estimates.mixtures import GaussianMixture

    tuples, per = product_size(1, 395_000, 1, 1, "gms", first_order=True)
    work((tuples * per + 395_000 * MIXTURE_STEP,), "gms")  # the edge just inside, the rule alone
    gm = GaussianMixture(weights=np.array([1.0]), means=np.zeros((1, 1)), covs=np.ones((1, 1, 1)))
    gms = [gm] * 10**6
    call = (functools.partial(mixture.first_order_fusion, gms, np.full(10**6, 1e-6)) if fused == "first_order_fusion"
            else functools.partial(mixture.fuse_mixtures, gms, np.random.default_rng(0), n_samples=2))
    refused_quickly(call, ValueError, r"^gms (and n_samples )?\(the product mixture's component tuples\) ask for",
                    cpu=2.0)


@pytest.mark.parametrize("feedback", ["split", "common"])
def test_printed_fusion_loop_with_feedback_weighs_its_step(feedback):
    """fusion_loop with rule "printed" and feedback costs 1.2-1.5 ms a step (n = 2, one run), counted as the split
    rules' 60 LOOP_STEP before: the edge, ~16,500 steps, ran 20-25 CPU-s. 10,000 steps are refused before any work
    (they were accepted); without feedback the printed rule keeps its weight (10,000 steps accepted by the rule)."""
    from fusion.filtering import feedback as fb
    from fusion.filtering import kalman as km

    def rule(step, K):  # fusion_loop's rule for n = 2, m = 1, one run of the printed rule
        km._steps_work(K, 1, 2, 1, step, "z1 and z2 (their steps K) and the sizes of F and H",
                       km.FUSION_LOOP_PRINTED_CUBE, km.FUSION_LOOP_SPLIT_M_CUBE, run=km.FUSION_LOOP_RUN,
                       product=km.FUSION_LOOP_PRODUCT, matrix=km.FUSION_LOOP_PRINTED_MATRIX)

    rule(km.FUSION_LOOP_SPLIT_STEP, 10_000)  # without feedback: accepted
    rule(km.FUSION_LOOP_PRINTED_FEEDBACK_STEP, 6_600)  # the new edge, just inside (~8-10 CPU-s): accepted
    K = 10_000
    z = np.zeros((1, K, 1))
    x0 = np.zeros((1, 2))
    F, H, Q, R, P0 = np.array([[1.0, 1.0], [0.0, 1.0]]), np.array([[1.0, 0.0]]), 0.01 * np.eye(2), np.eye(1), np.eye(2)
    call = functools.partial(fb.fusion_loop, z, z, x0, x0, F, H, Q, R, R, P0, P0, P0, "printed", feedback=feedback)
    refused_quickly(call, ValueError, r"^z1 and z2 \(their steps K\) and the sizes of F and H ask for")
