"""Fuzz 57b (fix 64b): regressions of C2 (gauss_markov_gap's draws budget), C3 (gm_sample built an (n, d, d) array),
C4 (nees copied the broadcast covariance factors; no work budget) and D2 (perron_gap and unit_lower_inverse had no
dense work budget). Report: /work/tmp/fuzz57b/report.md."""

from __future__ import annotations

import tracemalloc

import numpy as np
import pytest

from _helpers import refused_quickly


# --- C2: gauss_markov_gap ----------------------------------------------------------------------------------------

def test_c2_gauss_markov_gap_refuses_draws_beyond_the_memory_budget():
    from fusion.readings.correlated import gauss_markov_gap
    H = np.random.default_rng(1).normal(size=(100, 2))  # Z of 2e9 entries: was a raw MemoryError
    refused_quickly(lambda: gauss_markov_gap(H, np.eye(100), np.random.default_rng(0), 10**7), ValueError, r"^draws and H .*memory budget")


def test_c2_gauss_markov_gap_refuses_draws_beyond_the_work_budget():
    from fusion.readings.correlated import gauss_markov_gap
    rng = np.random.default_rng(0)  # 70,000 draws of N = d = 30: within memory, 1.1e9 units
    refused_quickly(lambda: gauss_markov_gap(np.eye(30), np.eye(30), rng, 70_000), ValueError, r"^draws and H .*work budget")
    assert rng.bit_generator.state == np.random.default_rng(0).bit_generator.state  # no draw


def test_c2_gauss_markov_gap_budget_accepts_its_edges_and_the_book_call():
    from fusion.readings import correlated as co
    co._gap_budget(63_000, 30, 30)       # the work edge (9.9e8 units)
    co._gap_budget(3 * 10**6, 10, 2)     # the memory edge (2.4e8 of 2.68e8 elements)
    with pytest.raises(ValueError, match="memory budget"):
        co._gap_budget(4 * 10**6, 10, 2)
    H = np.random.default_rng(1).normal(size=(6, 2))
    assert co.gauss_markov_gap(H, np.eye(6), np.random.default_rng(2503), 200) > -1e-12


# --- C3: gm_sample -----------------------------------------------------------------------------------------------

def _mixture(d, S=2, seed=0):
    from fusion.estimates.mixtures import GaussianMixture
    rng = np.random.default_rng(seed)
    A = rng.normal(size=(S, d, d))
    covs = A @ np.swapaxes(A, 1, 2) + np.eye(d)
    return GaussianMixture(np.full(S, 1.0 / S), rng.normal(size=(S, d)), 0.5 * (covs + np.swapaxes(covs, 1, 2)))


def test_c3_gm_sample_does_not_build_an_n_by_d_by_d_array():
    from fusion.estimates.mixtures import gm_sample
    gm, n = _mixture(100), 2000
    tracemalloc.start()
    try:
        x = gm_sample(gm, np.random.default_rng(0), n)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert x.shape == (n, 100)
    assert peak < 10 * x.nbytes  # L[labels] alone was 100 x the sample (160 MB)


@pytest.mark.parametrize("d, S, n", [(1, 1, 50), (2, 3, 1000), (4, 2, 777), (7, 5, 300)])
def test_c3_gm_sample_draws_what_the_stacked_formula_drew(d, S, n):
    from fusion.estimates.mixtures import gm_sample
    gm = _mixture(d, S, seed=d)
    rng = np.random.default_rng(n)  # the formula before fuzz 57b, with the same draws in the same order
    labels = rng.choice(S, size=n, p=gm.weights)
    z = rng.standard_normal((n, d))
    want = gm.means[labels] + np.einsum("nij,nj->ni", np.linalg.cholesky(gm.covs)[labels], z)
    assert np.array_equal(gm_sample(gm, np.random.default_rng(n), n), want)


def test_c3_gm_sample_refuses_n_beyond_the_memory_budget_and_accepts_its_edge():
    from fusion.estimates import mixtures as mx
    gm = _mixture(1000, S=1)
    refused_quickly(lambda: mx.gm_sample(gm, np.random.default_rng(0), 10**5), ValueError, r"^n and gm .*memory budget")
    mx._sample_budget(5_500_000, 10, 3)  # 4 x 5.5e6 x 12 = 2.64e8 elements (3.2e8 units)
    with pytest.raises(ValueError, match=r"^n and gm .*memory budget"):
        mx._sample_budget(5_600_000, 10, 3)
    with pytest.raises(ValueError, match=r"^n and gm .*work budget"):
        mx._sample_budget(160_000, 400, 2)  # within memory (2.57e8 elements), 1.09e9 units


# --- C4: nees ----------------------------------------------------------------------------------------------------

def test_c4_nees_does_not_copy_the_broadcast_covariances():
    from fusion.filtering.kalman import nees
    rng = np.random.default_rng(0)
    P = np.broadcast_to(2.0 * np.eye(16), (64, 16, 16)).copy()
    e = rng.normal(size=(1024, 64, 16))
    tracemalloc.start()
    try:
        out = nees(e, P)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert out.shape == (1024, 64)
    np.testing.assert_allclose(out, np.sum(e**2, axis=-1) / 2.0, rtol=1e-12)
    assert peak < 80e6  # the broadcast factors alone were 134 MB


@pytest.mark.parametrize("es, ps", [((300, 40, 3), (40,)), ((3, 1, 7, 2), (5, 1)), ((9, 4), ()), ((4,), ())])
def test_c4_nees_by_blocks_gives_the_bits_of_the_whole_solve(monkeypatch, es, ps):
    from fusion.filtering import kalman
    rng = np.random.default_rng(len(es))
    d = es[-1]
    A = rng.normal(size=ps + (d, d))
    P = A @ np.swapaxes(A, -1, -2) + np.eye(d)
    P = 0.5 * (P + np.swapaxes(P, -1, -2))
    e = 3.0 * rng.normal(size=es)
    L, eb = np.broadcast_arrays(np.linalg.cholesky(P), e[..., None])
    want = np.sum(np.linalg.solve(L, eb)[..., 0] ** 2, axis=-1)  # the formula before fuzz 57b
    monkeypatch.setattr(kalman, "_NEES_BLOCK", 7)  # blocks of one to a few matrices
    got = kalman.nees(e, P)
    assert np.array_equal(got, want) and np.shape(got) == np.shape(want)


def test_c4_nees_refuses_a_broadcast_beyond_the_work_budget_and_accepts_its_edge():
    from fusion.filtering import kalman
    P = np.broadcast_to(2.0 * np.eye(64), (1024, 64, 64)).copy()
    refused_quickly(lambda: kalman.nees(np.ones((512, 1, 64)), P), ValueError, r"^errors and covariances .*work budget")
    refused_quickly(lambda: kalman.nees(np.ones((8, 2500)), np.eye(2500)), ValueError, r"^errors and covariances .*work budget")
    kalman._nees_budget((69_000,), 64)  # 69,000 x 14,406 units (9.9e8), and one matrix of d = 4,800 (9.5e8)
    kalman._nees_budget((1,), 4800)
    with pytest.raises(ValueError, match="memory budget"):
        kalman._nees_budget((2**15, 2**14), 1)


# --- D2: perron_gap and unit_lower_inverse -----------------------------------------------------------------------

def test_d2_perron_gap_and_unit_lower_inverse_refuse_beyond_the_dense_work_budget():
    from fusion.readings.correlated import unit_lower_inverse
    from fusion.readings.fusion_set import perron_gap
    n = 4300  # 1.03e9 units at 1.3 DENSE_CUBE; perron_weights refuses the same B
    B = np.full((n, n), 0.5)
    np.fill_diagonal(B, 1.0)
    refused_quickly(lambda: perron_gap(B), ValueError, r"^B ask for .*work budget")
    del B
    refused_quickly(lambda: unit_lower_inverse(np.eye(n)), ValueError, r"^L ask for .*work budget")


def test_d2_dense_work_accepts_the_edge():
    from fusion._limits import DENSE_CUBE, dense_work
    from fusion.readings import fusion_set
    assert fusion_set._PERRON_CUBE == 1.3 * DENSE_CUBE  # perron_gap's weight is perron_weights'
    dense_work(1, 4250, "B", fusion_set._PERRON_CUBE)  # 9.98e8 units
    dense_work(1, 4250, "L", 1.3 * DENSE_CUBE)  # unit_lower_inverse's
