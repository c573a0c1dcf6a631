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
    52,631 iterations (~4.5 CPU-s), is accepted by the rule; 60,000 are refused before any work."""
    from fusion.estimates import mixtures

    mixtures._em_work(52_631, 1, 200, 5, 1)  # the edge just inside: the rule alone (the fit is not run)
    with pytest.raises(ValueError, match="max_iter, x and n_components"):
        mixtures._em_work(52_632, 1, 200, 5, 1)
    x = np.random.default_rng(2).uniform(size=(200, 1))
    w = np.full(200, 1 / 200)
    call = (functools.partial(mixtures.weighted_em, x, w, 5, np.random.default_rng(0), max_iter=60_000, tol=0.0)
            if weighted == "weighted_em" else
            functools.partial(mixtures.weighted_em_batch, x[None], w[None], 5, [np.random.default_rng(0)],
                              max_iter=60_000, tol=0.0))
    refused_quickly(call, ValueError, r"^max_iter, x and n_components ask for")
