"""Fuzz 69b C2 and C3 (chapter 06's sigma-point first-order fusion): a sigma-point fusion whose mixtures, padded to
the larger one's components, ask for too many sigma-point densities is refused by its own arguments before any array
is built, and a nearby legitimate call of the same sizes' order accepted."""

from __future__ import annotations

import numpy as np
from _helpers import refused_quickly

from fusion.book.chapters import chernoff_first_order as cfo
from fusion.estimates import mixtures as mx


def _gm(s: int, seed: int = 0) -> mx.GaussianMixture:
    """A 2-D mixture of ``s`` equal-weight components (the fuzz round's ``gm``)."""
    r = np.random.default_rng(seed)
    return mx.GaussianMixture(np.full(s, 1.0 / s), r.normal(size=(s, 2)) * 3.0,
                              np.tile(np.eye(2) * (0.3 + r.random((s, 1, 1))), (1, 1, 1)))


def test_problem_budget_counts_the_padded_tuples() -> None:
    # C2: 1 x 200 was budgeted as 200 tuples but built 40,000 (45 CPU-s); 1 x 1500 a raw MemoryError (101 GiB)
    for s_a, s_b in ((1, 200), (200, 1), (2, 150), (1, 1500)):
        refused_quickly(lambda: cfo._problem_budget(s_a, s_b, 2), ValueError, "a, b and n")
    cfo._problem_budget(1, 100, 2)  # 1 x 100 runs about 3 CPU-s
    cfo._problem_budget(100, 100, 2)  # 100 x 100 about 4 CPU-s (the equal-size budget, unchanged in its order)


def test_problem_refused_by_its_arguments() -> None:
    a, b = _gm(1), _gm(300, 1)
    # C3b: refused only by the inner logsumexp, naming its argument ``a`` for 1.08e8 entries
    refused_quickly(lambda: cfo.sigma_first_order_problem(a, b, n=2), ValueError, "a, b and n")
    refused_quickly(lambda: cfo.sigma_first_order_problem(b, a, n=2), ValueError, "a, b and n")


def test_sigma_point_fusion_refused_naming_gms() -> None:
    # C3: 250 x 250 was refused by an inner logsumexp naming ``a`` after 3 CPU-s
    gms = [_gm(250), _gm(250, 1)]
    refused_quickly(lambda: cfo.sigma_point_first_order(gms, [0.5, 0.5]), ValueError, r"^gms \(the sigma points")
    refused_quickly(lambda: cfo.sigma_point_first_order([_gm(1), _gm(400, 1)], [0.5, 0.5]), ValueError, "^gms")


def test_nearby_calls_accepted() -> None:
    small, big = _gm(1), _gm(40, 1)
    p = cfo.sigma_first_order_problem(small, big, n=2)
    assert 0.0 <= p.omega_sp <= 1.0 and np.isfinite(p.logz_sp)
    fused = cfo.sigma_point_first_order([_gm(100), _gm(100, 1)], [0.5, 0.5])
    assert np.isfinite(fused.log_z_first_order) and fused.mixture.weights.size > 0
