"""Fix 75a (fuzz 67b C1-C3): weighted EM's budget missed what grows with the dimension d: a block's quadratic
features (K = (d+1)(d+2)/2 rows of each set's points, built by a Python loop of K multiplies; 16 sets of 100 points at
d = 1,000 allocated 6 GiB, a raw MemoryError; 1,100 points at d = 1,000 ran 15.8 CPU-s counted 9.5e7 units) and each
set's (d, d) matrices (20,000 sets of 2 points at d = 100 ran 48.8 CPU-s counted 8.6e8). The edges below come from
``_em_work`` alone (the fits are not run: the edge ones ran 3.9 and 5.7 CPU-s on the shared machine)."""
from __future__ import annotations

import numpy as np
import pytest

from _helpers import refused_quickly

WORK = r"^max_iter, x and n_components ask for"
REFUSED = r"^(max_iter, )?x .*(beyond the memory budget|beyond the work budget)"


def test_em_counts_the_features_construction():
    """One set of Q points at d = 500 (K = 125,751 features), one component: the features cost 5 units an entry
    (25 ns measured at 1,100 points). 1,486 points are accepted by the rule, 1,487 refused (before: Q K / 8 units,
    ~1.5e7 at the edge, so ~60,000 points would have been accepted)."""
    from fusion.estimates import mixtures

    mixtures._em_work(1, 1, 1_486, 1, 500)
    with pytest.raises(ValueError, match=WORK):
        mixtures._em_work(1, 1, 1_487, 1, 500)


def test_em_counts_each_sets_dimension():
    """Sets of 2 points at d = 100, one component, one iteration: ~1.9 ms a set measured, ~0.43 ms counted before.
    2,855 sets are accepted by the rule (5.7 CPU-s measured at 2,500), 2,856 refused."""
    from fusion.estimates import mixtures

    mixtures._em_work(1, 2_855, 2, 1, 100)
    with pytest.raises(ValueError, match=WORK):
        mixtures._em_work(1, 2_856, 2, 1, 100)


def test_fuzz67b_c1_features_beyond_memory_refused_quickly():
    """16 sets of 100 points at d = 1,000: a block's features (16, 501501, 100) are 6 GiB: refused naming x."""
    from fusion.estimates import mixtures

    B, Q, d = 16, 100, 1000
    x = np.random.default_rng(0).normal(size=(B, Q, d))
    rngs = [np.random.default_rng(i) for i in range(B)]
    refused_quickly(lambda: mixtures.weighted_em_batch(x, np.ones((B, Q)), 1, rngs, max_iter=1), ValueError,
                    r"^x \(its points and dimension.*beyond the memory budget")


def test_fuzz67b_c2_one_set_in_1000_dimensions_refused_quickly():
    """1,100 points at d = 1,000 (15.8 CPU-s before, counted ~1): refused naming x."""
    from fusion.estimates import mixtures

    x = np.random.default_rng(0).normal(size=(1_100, 1_000))
    refused_quickly(lambda: mixtures.weighted_em(x, np.ones(1_100), 1, np.random.default_rng(1), max_iter=1),
                    ValueError, REFUSED)


def test_fuzz67b_c3_many_sets_in_100_dimensions_refused_quickly():
    """20,000 sets of 2 points at d = 100 (48.8 CPU-s before, counted 8.6e8 units): refused naming x."""
    from fusion.estimates import mixtures

    B, Q, d = 20_000, 2, 100
    x = np.random.default_rng(0).normal(size=(B, Q, d))
    rngs = [np.random.default_rng(i) for i in range(B)]
    refused_quickly(lambda: mixtures.weighted_em_batch(x, np.ones((B, Q)), 1, rngs, max_iter=1), ValueError,
                    REFUSED)
