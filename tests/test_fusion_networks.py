"""The designed static networks of chapter 06 (fusion.scenarios.fusion_networks)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from fusion.scenarios import fusion_networks as fn

TINY = dict(n_particles=60, n_samples=60, n_components=2, em_iterations=3, stages=2)


def _tiny(key: str) -> fn.NetworkScenario:
    return dataclasses.replace(fn.premise_scenarios()[key], **TINY)


def test_grid_posterior_matches_the_closed_form_of_a_gaussian_likelihood() -> None:
    """Prior N(m0, s² I) times a Gaussian likelihood of the position: mean and covariance in closed form, KL 0."""
    m0 = np.array([[1000.0, 800.0], [990.0, 815.0]])
    s, z, r = 40.0, np.array([1012.0, 790.0]), np.array([6.0, 15.0])
    mean, cov, kl = fn._grid_posterior(m0, s, lambda G: -0.5 * np.sum(((G - z) / r) ** 2, axis=-1))
    P = 1.0 / (1.0 / s**2 + 1.0 / r**2)
    want = P * (m0 / s**2 + z / r**2)
    np.testing.assert_allclose(mean, want, atol=1e-6)
    np.testing.assert_allclose(np.diagonal(cov, axis1=1, axis2=2), np.broadcast_to(P, (2, 2)), rtol=1e-5)
    assert np.all(np.abs(kl) < 1e-6)
    # a bimodal likelihood is far from Gaussian
    _, _, kl2 = fn._grid_posterior(m0, s, lambda G: np.logaddexp(-0.5 * np.sum(((G - z) / 4) ** 2, axis=-1),
                                                                 -0.5 * np.sum(((G - z - 50) / 4) ** 2, axis=-1)))
    assert np.all(kl2 > 0.1)


def test_prior_log_is_the_sum_over_the_coordinates_bit_for_bit() -> None:
    rng = np.random.default_rng(4)
    G = np.concatenate([rng.normal(1000.0, 300.0, (5, 400, 2)), np.zeros((5, 3, 2)), np.full((5, 2, 2), 1e150)], axis=1)
    m0 = rng.normal(1000.0, 30.0, (5, 2))
    m0[0] = 0.0   # points at the prior mean: zero squares
    for std in (40.0, 1e-3, 1e100):
        want = -0.5 * np.sum((G - m0[:, None, :]) ** 2, axis=-1) / std**2
        got = fn._prior_log(G, m0, std)
        assert got.shape == want.shape and got.tobytes() == want.tobytes()


@pytest.mark.parametrize("block", [1, 3, 7, 50])
def test_grid_posterior_in_blocks_is_bit_for_bit_the_unblocked_one(block: int) -> None:
    """Blocks of runs give the same bits as one array of every run (each run's arithmetic is its own)."""
    rng = np.random.default_rng(block)
    m0 = rng.normal(1000.0, 30.0, (11, 2))
    z = rng.normal(0.0, 1.0, (11, 2)) * [5.0, 0.05] + [300.0, 0.7]

    def loglik(G: np.ndarray, rows: slice = slice(None)) -> np.ndarray:  # a range-bearing arc: far from Gaussian
        r, th = np.hypot(G[..., 0], G[..., 1]), np.arctan2(G[..., 1], G[..., 0])
        return -0.5 * ((z[rows, 0:1] - r + 1100.0) / 5.0) ** 2 - 0.5 * ((z[rows, 1:2] - th) / 0.05) ** 2

    whole = fn._grid_posterior(m0, 40.0, loglik)
    blocked = fn._grid_posterior_blocks(m0, 40.0, loglik, block=block)
    for a, b in zip(whole, blocked, strict=True):
        assert a.shape == b.shape and np.array_equal(a, b)


def test_local_posteriors_of_range_only_nodes_are_far_from_gaussian() -> None:
    st = fn.run_network_study(_tiny("non_gaussian"), 3, 4)
    kinds = [n.kind for n in st.scenario.nodes]
    kl = st.kl_local.mean(axis=0)
    assert kl[kinds.index("range")] > 0.3  # an arc
    assert st.kl_local.shape == (4, 3) and np.all(st.kl_local >= -1e-6)


def test_every_run_is_computed_alike_whatever_the_other_runs() -> None:
    """Run r of a study of 3 runs equals run r of a study of 2 (its streams are the r-th child of the seed)."""
    sc = _tiny("chain")
    a, b = fn.run_network_study(sc, 9, 3), fn.run_network_study(sc, 9, 2)
    for m in fn.NETWORK_METHODS:
        np.testing.assert_array_equal(a.estimates[m][:2], b.estimates[m])
        np.testing.assert_array_equal(a.covariances[m][:2], b.covariances[m])
    np.testing.assert_array_equal(a.eps[:2], b.eps)


def test_study_records_and_helpers() -> None:
    st = fn.run_network_study(_tiny("feedback"), 4, 3)
    N = len(st.scenario.nodes)
    for m in fn.NETWORK_METHODS:
        assert st.estimates[m].shape == (3, N, 2) and st.covariances[m].shape == (3, N, 2, 2)
        assert st.mse(m).shape == (3,) and np.all(st.mse(m) >= 0)
        assert np.all((st.overconfident(m) >= 0) & (st.overconfident(m) <= 1))
    assert st.eps.shape == (3, st.scenario.frames * st.scenario.rounds, N, N)
    np.testing.assert_allclose(np.nansum(st.eps, axis=3), 1.0)  # every fusion's exponents on the simplex
    with pytest.raises(ValueError, match="method"):
        st.mse("no-such-method")
    with pytest.raises(ValueError):
        st.estimates["naive_product"][0, 0, 0] = 0.0  # read-only


def test_naive_product_is_overconfident_with_feedback_and_chernoff_is_not() -> None:
    """The premise, on a small feedback study: double counting by the product, not by Chernoff fusion."""
    st = fn.run_network_study(dataclasses.replace(fn.premise_scenarios()["feedback"], n_particles=200, n_samples=200),
                              11, 20)
    assert st.overconfident("naive_product").mean() > 0.3
    assert st.overconfident("ci_gaussian").mean() < 0.15


def test_scenarios_validate_and_chains_have_neighbours() -> None:
    chain = fn.premise_scenarios()["chain"]
    assert chain.neighbours == [[0, 1], [1, 0, 2], [2, 1]]
    full = fn.premise_scenarios()["unequal"]
    assert full.neighbours[1] == [1, 0, 2]
    nodes = chain.nodes
    with pytest.raises(ValueError, match="edges"):
        fn.NetworkScenario("bad", nodes, edges=((0, 0),))
    with pytest.raises(ValueError, match="edges"):
        fn.NetworkScenario("bad", nodes, edges=((0, 5),))
    with pytest.raises(ValueError, match="nodes"):
        fn.NetworkScenario("bad", nodes[:1])
    with pytest.raises(ValueError, match="kind"):
        fn.NetworkNode((0.0, 0.0), "sonar")
    assert set(fn.premise_scenarios()) == {"unequal", "non_gaussian", "feedback", "chain"}


def test_a_relay_repeats_its_source_and_an_overconfident_node_is_sharper() -> None:
    """The relay node's local posterior is its source's (particles and mixture); a node with model_scale < 1 is sharper."""
    scs = fn.redundancy_scenarios()
    relay = dataclasses.replace(scs["relay"], n_particles=60, n_samples=60, n_components=2, em_iterations=3)
    st = fn.run_network_study(relay, 3, 4)
    np.testing.assert_array_equal(st.local_mean[:, 2], st.local_mean[:, 0])
    np.testing.assert_array_equal(st.local_cov[:, 2], st.local_cov[:, 0])
    assert not np.allclose(st.local_mean[:, 1], st.local_mean[:, 0])
    # uniform exponents on the Gaussian summaries give the naive product's mean (the relayed node counted twice)
    J = np.linalg.inv(st.local_cov)
    x = np.linalg.solve(J.sum(axis=1), np.einsum("bnij,bnj->bi", J, st.local_mean)[..., None])[..., 0]
    np.testing.assert_allclose(x, st.estimates["naive_product"][:, 0], rtol=1e-6)
    faulty = dataclasses.replace(scs["overconfident"], n_particles=200, n_samples=60, n_components=2, em_iterations=3)
    sf = fn.run_network_study(faulty, 3, 4)
    det = np.linalg.det(sf.local_cov).mean(axis=0)
    assert det[2] < det[1] / 3  # node 3's posterior far sharper than an honest node's at the same noise
    with pytest.raises(ValueError, match="relay_of"):
        fn.NetworkScenario("bad", (fn.NetworkNode((0.0, 0.0), relay_of=1), fn.NetworkNode((1.0, 0.0), relay_of=0)))
    with pytest.raises(ValueError, match="model_scale"):
        fn.NetworkNode((0.0, 0.0), model_scale=0.0)
