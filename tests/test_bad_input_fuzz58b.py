"""Fuzz 58b (fix 66a): regressions of C1 (as_rngs' list discarded, the raw rngs read again), C2 (fuse_mixtures built an
(n_samples, d, d) array), C3 (cumulative_fusion's broadcast refused naming the inner "estimates"), C4 (an entropy
ndarray subclass's ``flat`` hid its words from seed_sequence) and C5 (gauss_markov_gap's draws budget after its
O(N**3) solve). Report: /work/tmp/fuzz58b/report.md."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pytest

from _helpers import refused_quickly


# --- C1: the list as_rngs checked is the list used -----------------------------------------------------------------

class _Flip(Sequence):
    """A sequence of generators whose first iteration gives ``good`` and every later read ``bad``."""

    def __init__(self, good, bad):
        self.good, self.bad, self.reads = good, bad, 0

    def __len__(self):
        return len(self.good)

    def __getitem__(self, i):
        return (self.good if self.reads <= 1 else self.bad)[i]

    def __iter__(self):
        self.reads += 1
        return iter(self.good if self.reads <= 1 else self.bad)


def _pair():
    return [np.random.Generator(np.random.PCG64(1)), np.random.Generator(np.random.PCG64(2))]


def _shared():
    g = np.random.Generator(np.random.PCG64(1))
    return [g, g]


def test_c1_particle_swarm_batch_uses_the_generators_it_checked():
    from fusion.optimise.swarm import particle_swarm_batch
    f = lambda b, X: np.sum((X - 0.3) ** 2, axis=-1)  # noqa: E731
    got = particle_swarm_batch(f, 2, _Flip(_pair(), _shared()), n_particles=5, iterations=5)
    ref = particle_swarm_batch(f, 2, _pair(), n_particles=5, iterations=5)
    for a, b in zip(got, ref):
        np.testing.assert_array_equal(a.x, b.x)


def test_c1_weighted_em_batch_uses_the_generators_it_checked():
    from fusion.estimates.mixtures import weighted_em_batch
    x = np.random.default_rng(0).normal(size=(2, 40, 2))
    got = weighted_em_batch(x, np.ones((2, 40)), 2, _Flip(_pair(), _shared()))
    ref = weighted_em_batch(x, np.ones((2, 40)), 2, _pair())
    for a, b in zip(got, ref):
        np.testing.assert_array_equal(a.mixture.means, b.mixture.means)


def test_c1_fuse_mixtures_batch_uses_the_generators_it_checked():
    from fusion.estimates.chernoff.mixture import fuse_mixtures_batch
    r = np.random.default_rng(3)
    w, m = np.full((2, 2, 1), 1.0), r.normal(size=(2, 2, 1, 2))
    c = np.broadcast_to(np.eye(2), (2, 2, 1, 2, 2)).copy()
    got = fuse_mixtures_batch(w, m, c, _Flip(_pair(), _shared()), n_samples=200, optimiser="slsqp")
    ref = fuse_mixtures_batch(w, m, c, _pair(), n_samples=200, optimiser="slsqp")
    for a, b in zip(got, ref):
        np.testing.assert_array_equal(a.x, b.x)


# --- C2: fuse_mixtures' samples ------------------------------------------------------------------------------------

def _gms(d, n=2):
    from fusion.estimates.mixtures import GaussianMixture
    return [GaussianMixture(np.ones(1), np.full((1, d), float(j)), (1.0 + j) * np.eye(d)[None]) for j in range(n)]


def test_c2_fuse_mixtures_refuses_samples_beyond_the_memory_budget_by_name():
    from fusion.estimates.chernoff.mixture import fuse_mixtures
    rng = np.random.default_rng(0)   # was a raw MemoryError of 6.7 GiB, (10**6, 30, 30), after 0.5 CPU-s
    refused_quickly(lambda: fuse_mixtures(_gms(30), rng, n_samples=10**6), ValueError, r"^gms and n_samples .*memory budget")
    assert rng.bit_generator.state == np.random.default_rng(0).bit_generator.state  # no draw


def test_c2_fuse_mixtures_batch_refuses_samples_beyond_the_memory_budget_by_name():
    from fusion.estimates.chernoff.mixture import fuse_mixtures_batch
    d = 30
    w, m = np.ones((1, 2, 1)), np.zeros((1, 2, 1, d))
    c = np.broadcast_to(np.eye(d), (1, 2, 1, d, d)).copy()
    refused_quickly(lambda: fuse_mixtures_batch(w, m, c, [np.random.default_rng(0)], n_samples=10**6), ValueError,
             r"^weights and n_samples .*memory budget")


def test_c2_sample_memory_edges():
    from fusion.estimates.chernoff._product import sample_memory
    per = 658 + 1 + 32              # d = 30, one tuple: 1.25 (K + d) + 1 + 32 float64 a sample
    sample_memory(1, 1, 30, 2**28 // per, "n_samples")   # the edge, accepted
    with pytest.raises(ValueError, match="^n_samples"):
        sample_memory(1, 1, 30, 2**28 // per + 1, "n_samples")
    sample_memory(1, 4, 2, 2000, "n_samples")            # the book's size


def test_c2_mixture_sampling_is_the_stacked_formula_bit_for_bit():
    from fusion.estimates.chernoff._sampling import _sample_mixture
    from fusion.estimates.mixtures import _matvec
    for d, M, n in [(1, 3, 50), (2, 4, 301), (5, 2, 7), (17, 3, 100)]:
        r = np.random.default_rng(d)
        w = np.r_[0.0, r.random(M - 1)]
        w /= w.sum()
        mu, A = r.normal(size=(M, d)), r.normal(size=(M, d, d))
        L = np.linalg.cholesky(A @ np.swapaxes(A, 1, 2) + np.eye(d))
        g = np.random.default_rng(7)   # the former formula: labels, draws, then mu[lab] + _matvec(L[lab], z)
        kept = np.flatnonzero(w > 0)
        lab = kept[g.choice(kept.size, size=n, p=w[kept])]
        z = g.standard_normal((n, d))
        np.testing.assert_array_equal(_sample_mixture(w, mu, L, np.random.default_rng(7), n),
                                      mu[lab] + _matvec(L[lab], z))


# --- C3: cumulative_fusion's broadcast -----------------------------------------------------------------------------

def test_c3_cumulative_fusion_runs_a_broadcast_beyond_the_input_budget():
    from fusion._limits import MAX_INPUT_ELEMENTS
    from fusion.readings.weighting import cumulative_fusion
    X, V = np.ones((1, 2**13, 2)), np.ones((2**11 + 1, 1, 2))   # a broadcast of 2**25 + 2**14 entries (~4 CPU-s)
    assert max(X.size, V.size) < MAX_INPUT_ELEMENTS < (2**11 + 1) * X.size < 2**28 // 5
    out = cumulative_fusion(X, V)   # was a ValueError naming "estimates", not an argument of cumulative_fusion
    assert out.shape == (2**11 + 1, 2**13)
    np.testing.assert_array_equal(out, 1.0)


def test_c3_cumulative_fusion_unchanged_on_a_small_broadcast():
    from fusion.readings.weighting import cumulative_fusion, fuse_current
    r = np.random.default_rng(2)
    X, V = r.normal(size=(3, 50, 4)), r.normal(size=(1, 50, 4))   # negative estimates too: the guards
    for guard in ("floor", "abs", "equal"):
        inst = fuse_current(X, V, guard=guard)
        np.testing.assert_allclose(cumulative_fusion(X, V, guard=guard), np.cumsum(inst, axis=-1) / np.arange(1, 51),
                                   rtol=1e-12)


# --- C4: an entropy ndarray subclass -------------------------------------------------------------------------------

class _Liar(np.ndarray):
    @property
    def flat(self):
        return iter([np.uint32(7)])


def test_c4_seed_sequence_refuses_an_entropy_ndarray_subclass_by_name():
    from fusion._counts import seed_sequence
    big = np.arange(10**6, dtype=np.uint32).view(_Liar)   # a one-word flat over 10**6 words numpy mixes
    refused_quickly(lambda: seed_sequence(np.random.SeedSequence(big), "seeds[0]"), TypeError, r"^seeds\[0\] .*subclass")
    seed_sequence(np.random.SeedSequence(np.arange(8, dtype=np.uint32)), "seed")   # a plain array of 8 words: kept
    with pytest.raises(ValueError, match="^seed "):
        seed_sequence(np.random.SeedSequence(np.arange(9, dtype=np.uint32)), "seed")


# --- C5: gauss_markov_gap's draws before its solve -----------------------------------------------------------------

def test_c5_gauss_markov_gap_refuses_draws_before_the_gls_solve():
    from fusion.readings.correlated import gauss_markov_gap
    N = 3000   # gls_weights' solve alone: 3.5 CPU-s before the draws were refused
    refused_quickly(lambda: gauss_markov_gap(np.ones((N, 1)), np.eye(N) + 0.1, np.random.default_rng(0), 10**7),
             ValueError, r"^draws and H .*memory budget")
