"""The sigma-point first-order fusion of chapter 06's appendix (fusion.book.chapters.chernoff_first_order)."""

import numpy as np
import pytest

from fusion.book.chapters import chernoff_first_order as csf
from fusion.book.chapters import chernoff_snis as csn
from fusion.book.chapters import chernoff_steps as cst
from fusion.estimates import chernoff as ch
from fusion.estimates.mixtures import GaussianMixture
from fusion.scenarios import two_mixtures


def test_single_gaussians_equal_step_d():
    """One component per node: every responsibility is 1, so the sigma-point fusion is step D's exactly."""
    rng = np.random.default_rng(3)
    gms = [GaussianMixture(np.ones(1), rng.normal(size=(1, 2)), np.eye(2)[None] * (0.5 + i)) for i in range(3)]
    e = [0.2, 0.5, 0.3]
    sp, first = csf.sigma_point_first_order(gms, e), ch.first_order_fusion(gms, e)
    assert sp.log_z_first_order == pytest.approx(first.log_z_first_order, abs=1e-12)
    np.testing.assert_allclose(sp.mixture.means, first.mixture.means, atol=1e-12)
    np.testing.assert_allclose(sp.mixture.covs, first.mixture.covs, atol=1e-12)


def test_vertex_gives_the_node_back():
    """At ε = (1, 0) the responsibilities of B sum to one at every sigma point: the fusion is A, Z = 1."""
    toy = two_mixtures.toy_mixtures()
    sp = csf.sigma_point_first_order([toy.a, toy.b], [1.0, 0.0])
    assert sp.log_z_first_order == pytest.approx(0.0, abs=1e-12)
    x = np.random.default_rng(0).normal(size=(50, 2))
    np.testing.assert_allclose(cst._logpdf(sp.mixture, x), cst._logpdf(toy.a, x), atol=1e-10)


def test_normaliser_below_step_d():
    """R_m <= 1, so the sigma-point normaliser never exceeds step D's upper bound Z_FO."""
    rng = np.random.default_rng(4)
    for _ in range(5):
        a, b = csf.random_two_mixtures(rng)
        for w in (0.1, 0.5, 0.9):
            assert csf.sigma_point_first_order([a, b], [w, 1 - w]).log_z_first_order <= ch.first_order_fusion([a, b], [w, 1 - w]).log_z_first_order + 1e-12


def test_problem_exact_omega_matches_reference():
    toy = two_mixtures.toy_mixtures()
    v = csf.sigma_first_order_problem(toy.a, toy.b)
    assert v.omega_exact == pytest.approx(cst.toy_reference().omega_star, abs=1e-4)
    assert v.logz_first_order >= 0  # step D's normaliser is an upper bound
    for tv in (v.tv_first_order, v.tv_sp):
        assert 0 <= tv <= 1


def test_study_sizes_and_validation():
    st = csf.sigma_first_order_study(np.random.default_rng(1), runs=3)
    assert len(st.runs) == 3 and st.glue()["chf_sp_runs"] == 3
    assert st.table().shape[0] == 4
    with pytest.raises(ValueError, match="eps"):
        csf.sigma_point_first_order([two_mixtures.toy_mixtures().a], [0.5, 0.5])
    with pytest.raises(ValueError, match="runs"):
        csf.sigma_first_order_study(np.random.default_rng(1), runs=0)


def test_block_minimum_matches_grid_search():
    """The bisection minimiser of Ĵ on a block equals a fine grid search (Ĵ convex in ω)."""
    ref = cst.toy_reference()
    xs = cst.mx.gm_sample(ref.proposal, np.random.default_rng(5), 6 * 50)
    L, lg = cst._log_densities(list(ref.gms), xs), cst._logpdf(ref.proposal, xs)
    w = csn._block_minimum(L.reshape(6, 50, 2), lg.reshape(6, 50))
    grid = np.linspace(0, 1, 20001)
    for k in range(6):
        Lk, gk = L[k * 50:(k + 1) * 50], lg[k * 50:(k + 1) * 50]
        J = [cst.mx.logsumexp(g * Lk[:, 0] + (1 - g) * Lk[:, 1] - gk) for g in grid]
        assert w[k] == pytest.approx(grid[int(np.argmin(J))], abs=1e-4)


def test_chosen_bias_study_fixed_column_matches_snis_study():
    """With the same pool, the fixed-exponent column is the SNIS study's measurement at ω*."""
    st = cst.chosen_bias_study(np.random.default_rng(7), rs=(20, 40), total=4000)
    sn = cst.snis_bias_study(np.random.default_rng(7), rs=(20, 40), total=4000)
    star = sn.table[sn.table["ω"] == sn.table["ω"].iloc[0]]
    np.testing.assert_allclose(st.table["R·bias along c, ω* fixed"], star["R·bias along c"], rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(st.table["extra"], st.table["R·bias along c, ω chosen"] - st.table["R·bias along c, ω* fixed"],
                               atol=1e-12)
    with pytest.raises(ValueError, match="rs"):
        cst.chosen_bias_study(np.random.default_rng(7), rs=(30,), total=4000)
