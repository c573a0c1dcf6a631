"""Fix 74b (fuzz 66b C3, C4): weighted EM's k-means++ initialisation and each set's fixed cost were outside its
budget: the initialisation recomputed every point's distance to all means chosen so far (O(Q S**2 d): 4,000 points
and components ran 105 CPU-s, counted ~0.5), and a set's initialisation steps and result (~180 us a set of 4 points)
were not counted (200,000 sets ran 37.8 CPU-s, counted ~0.1)."""
from __future__ import annotations

import time

import numpy as np
import pytest

from _helpers import refused_quickly


def test_kmeanspp_initialisation_is_linear_in_components():
    """4,000 points and as many components in one dimension, one iteration: 105 CPU-s before (the distances to all
    chosen means recomputed at every step), ~0.5 now (a running minimum); counted 1.1e8 units, accepted."""
    from fusion.estimates import mixtures

    rng = np.random.default_rng(0)
    x, w = rng.standard_normal((4000, 1)), np.ones(4000)
    t0 = time.process_time()
    fit = mixtures.weighted_em(x, w, 4000, np.random.default_rng(0), max_iter=1, tol=0.0)
    assert time.process_time() - t0 < 10.0  # ~0.5 CPU-s measured (shared machine); 105 before
    assert fit.loglik.size == 1


def test_kmeanspp_running_minimum_draws_the_same_means():
    """The running minimum gives the same squared distances (a minimum is exact, each distance summed alike), so
    the same draws: the initial means are the points the full recomputation picks, checked against it here."""
    from fusion.estimates import mixtures

    g = np.random.default_rng(5)
    for d, Q, S in ((1, 30, 30), (3, 40, 7), (9, 25, 11)):
        x = g.standard_normal((Q, d))
        x[: Q // 3] = x[0]  # coincident points: zero distances
        w = g.random(Q) + 0.01
        w1 = w / w.sum()
        rng = np.random.default_rng(d)
        idx = [int(rng.choice(Q, p=w1))]
        for _ in range(1, S):  # the former recomputation over all chosen means
            d2 = np.min(((x[:, None, :] - x[idx][None]) ** 2).sum(-1), axis=1)
            p = w1 * d2
            idx.append(int(rng.choice(Q, p=p / p.sum())) if p.sum() > 0 else int(rng.integers(Q)))
        _, means, _, _ = mixtures._em_arrays(x[None], w[None], S, [np.random.default_rng(d)], 0, 0.0, 1e-6, [None])
        assert np.array_equal(means[0], x[idx])


def test_em_batch_counts_each_set():
    """Sets of 4 points and 4 components, one iteration: ~180 us a set measured, counted ~50 units (0.5 us) before,
    so 200,000 sets (37.8 CPU-s) were accepted. Now ~25,700 units a set (with fix 75a's per-set d**2 term and the
    features' construction): the edge, 38,901 sets (~7 CPU-s), is accepted by the rule; 38,902 are refused before
    any work, naming x."""
    from fusion.estimates import mixtures

    mixtures._em_work(1, 38_901, 4, 4, 1)  # the edge just inside: the rule alone (the fits are not run)
    with pytest.raises(ValueError, match="^max_iter, x and n_components ask for"):
        mixtures._em_work(1, 38_902, 4, 4, 1)
    B = 38_902
    x = np.broadcast_to(np.arange(4.0)[:, None], (B, 4, 1))
    w = np.ones((B, 4))
    rngs = [np.random.Generator(np.random.PCG64(i)) for i in range(B)]
    refused_quickly(lambda: mixtures.weighted_em_batch(x, w, 4, rngs, max_iter=1, tol=0.0), ValueError,
                    r"^max_iter, x and n_components ask for")
