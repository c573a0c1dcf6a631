"""Chapter 06's other criteria and known-common-information baseline (fusion.book.chapters.chernoff_criteria).

Parity with the study's own Gaussian pipelines, the prior draw repeated, the channel filter exact where the local
posteriors are exact Gaussians, the criteria's closed-form properties, and bad input.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from fusion.book.chapters import chernoff_criteria as cc
from fusion.estimates import chernoff as ch
from fusion.scenarios.fusion_networks import (NetworkNode, NetworkScenario, NetworkStudy, premise_scenarios,
                                              run_network_study)

DEG = float(np.deg2rad(1.0))


def _small(sc: NetworkScenario) -> NetworkScenario:
    return dataclasses.replace(sc, n_particles=120, n_samples=120, em_iterations=3)


@pytest.fixture(scope="module")
def chain() -> NetworkStudy:
    return run_network_study(_small(premise_scenarios()["chain"]), 5, 6)


@pytest.fixture(scope="module")
def unequal() -> NetworkStudy:
    return run_network_study(_small(premise_scenarios()["unequal"]), 6, 6)


@pytest.mark.parametrize("name", ["chain", "unequal"])
@pytest.mark.parametrize("rule", ["ci_gaussian", "naive_product"])
def test_rerun_of_the_gaussian_pipelines_equals_the_study(name: str, rule: str, request: pytest.FixtureRequest) -> None:
    """The study's own two Gaussian pipelines, recomputed from the stored first local moments, digit for digit."""
    st = request.getfixturevalue(name)
    est, cov, eps = cc.gaussian_exchange(st, rule)
    np.testing.assert_array_equal(est, st.estimates[rule])
    np.testing.assert_array_equal(cov, st.covariances[rule])
    heard = ~np.isnan(eps)
    assert np.all(heard.sum(axis=-1) == np.array([len(n) for n in st.scenario.neighbours]))


def test_prior_means_repeat_the_study_draw() -> None:
    """A node that learns almost nothing keeps the prior: its local mean lies within sampling error of prior_means."""
    vague = NetworkNode((0.0, 0.0), "range", sigma_r=1e6)
    sc = NetworkScenario("vague", (vague, vague), n_particles=400, n_samples=50, em_iterations=2, prior_std=60.0)
    st = run_network_study(sc, 3, 8)
    m0 = cc.prior_means(sc, 3, 8)
    err = np.abs(st.local_mean - m0[:, None, :])
    assert np.all(err < 5 * 60.0 / np.sqrt(400))  # 5 standard errors of a mean of 400 prior draws
    other = cc.prior_means(sc, 4, 8)  # another seed's draw is metres away (the test can fail)
    assert np.max(np.abs(st.local_mean - other[:, None, :])) > 5 * 60.0 / np.sqrt(400)


def _exact_study(sc: NetworkScenario, seed: int, runs: int) -> tuple[NetworkStudy, np.ndarray, np.ndarray]:
    """A study whose local posteriors are exact Gaussians: the prior times a linear Gaussian likelihood per node."""
    rng = np.random.default_rng(seed + 1)
    m0 = cc.prior_means(sc, seed, runs)
    N, d = len(sc.nodes), 2
    Y0 = np.eye(d) / sc.prior_std**2
    H = [np.diag([1.0 / 20.0**2, 1.0 / 5.0**2]), np.diag([1.0 / 8.0**2, 1.0 / 30.0**2]), np.array([[0.01, 0.004],
                                                                                                   [0.004, 0.003]])]
    z = rng.normal(0.0, 10.0, (runs, N, d))
    Y = np.stack([np.stack([Y0 + H[i] for i in range(N)])] * runs)
    y = m0[:, None, :] @ Y0 + np.einsum("nij,bnj->bni", np.stack(H[:N]), z)
    P = np.linalg.inv(Y)
    mean = np.einsum("bnij,bnj->bni", P, y)
    Yc = Y0 + sum(H[:N])
    central = np.linalg.solve(Yc, (m0 @ Y0 + np.einsum("nij,bnj->bi", np.stack(H[:N]), z)).T).T
    zeros = np.zeros((runs, N, d))
    est = {k: zeros for k in ("chernoff_pso", "chernoff_uniform", "ci_gaussian", "naive_product", "exact_posterior")}
    covs = {k: np.broadcast_to(np.eye(d), (runs, N, d, d)).copy() for k in est}
    st = NetworkStudy(sc, seed, np.asarray(sc.truth, dtype=float), est, covs, np.zeros((runs, 1, N)),
                      np.zeros((runs, N)), np.zeros((runs, 1, N, N)), np.zeros((runs, 1, N)), mean, P)
    return st, central, np.linalg.inv(Yc)


@pytest.mark.parametrize("edges,rounds", [(None, 1), (((0, 1), (1, 2)), 2)])
def test_channel_filter_is_the_centralised_posterior_for_exact_gaussians(edges: object, rounds: int) -> None:
    """Prior divided out on every channel: full connectivity in one round, the chain in two, give the centralised
    posterior exactly (one node's likelihood counted twice, or the prior three times, would not)."""
    node = NetworkNode((0.0, 0.0))
    sc = NetworkScenario("exact", (node, node, node), edges=edges, rounds=rounds, prior_std=60.0)
    st, central, Pc = _exact_study(sc, 9, 4)
    est, cov, not_pd = cc.channel_filter(st)
    assert not not_pd.any()
    np.testing.assert_allclose(est, np.repeat(central[:, None], 3, axis=1), rtol=0, atol=1e-6)
    np.testing.assert_allclose(cov, np.broadcast_to(Pc, cov.shape), rtol=1e-6)
    if edges is not None:  # after one round only, the chain's ends have not heard of each other: not centralised
        est1, _, _ = cc.channel_filter(dataclasses.replace(st, scenario=dataclasses.replace(sc, rounds=1)))
        assert np.max(np.abs(est1[:, 0] - central)) > 1e-3


def test_mean_free_rule_ignores_the_means_and_the_determinant_rule_picks_a_vertex() -> None:
    """Mean-free Chernoff exponents do not move with the means; nested Gaussians give 1/ln k − 1/(k−1) on the sharper;
    the determinant criterion puts all weight on a density whose covariance is inside every other's."""
    rng = np.random.default_rng(3)
    A = rng.standard_normal((5, 3, 2, 2))
    P = A @ np.swapaxes(A, -1, -2) + 0.5 * np.eye(2)
    m = rng.normal(0.0, 5.0, (5, 3, 2))
    e1 = cc.exponent_rule("ci_mean_free", m, P)
    e2 = cc.exponent_rule("ci_mean_free", m + rng.normal(0.0, 50.0, m.shape), P)
    np.testing.assert_allclose(e1, e2, atol=1e-12)
    np.testing.assert_allclose(e1.sum(axis=1), 1.0, atol=1e-12)
    with_means = cc.exponent_rule("ci_gaussian", m, P)
    assert np.max(np.abs(with_means - e1)) > 1e-3
    k = 10.0
    nested = np.stack([np.eye(2), k * np.eye(2)])[None]
    w = cc.exponent_rule("ci_mean_free", np.ones((1, 2, 2)), nested)[0, 0]
    assert w == pytest.approx(1.0 / np.log(k) - 1.0 / (k - 1.0), abs=1e-8)
    det = cc.exponent_rule("ci_det", np.zeros((1, 2, 2)), nested)[0]
    np.testing.assert_allclose(det, [1.0, 0.0], atol=1e-8)
    np.testing.assert_allclose(det, ch.covariance_intersection_weights(nested[0], "det"), atol=1e-12)
    np.testing.assert_array_equal(cc.exponent_rule("naive_product", m, P), np.ones((5, 3)))
    np.testing.assert_array_equal(cc.exponent_rule("ci_uniform", m, P), np.full((5, 3), 1.0 / 3.0))


def test_tables_pair_every_method_on_the_same_runs(chain: NetworkStudy, unequal: NetworkStudy) -> None:
    """Both tables read the one-frame networks; the glue values are the tables' numbers; the rerun is the study's."""
    nets = {k: (chain if k == "chain" else unequal) for k in cc.CRITERIA_NETWORKS}
    labels = {k: k for k in cc.CRITERIA_NETWORKS}
    with pytest.raises(ValueError, match="runs"):  # rule R4: a small study needs a stated reason
        cc.baseline_table(nets, labels)
    t1, v1 = cc.baseline_table(nets, labels, reason="test: a small study")
    t2, v2 = cc.criteria_table(nets, labels, reason="test: a small study")
    assert list(t1.columns) == list(cc.CRITERIA_NETWORKS) and list(t2.columns) == list(cc.CRITERIA_NETWORKS)
    assert v2["chf_crit_parity"] == "less than 10⁻⁹"   # the chapter's estimates again, to round-off
    d = cc.network_mse(chain, cc.channel_filter(chain)[0]) - chain.mse("chernoff_pso")
    assert v1["chf_cf_chain_chernoff_pso_d"] == pytest.approx(float(d.mean()), abs=0.051)
    assert v1["chf_cf_runs"] == chain.runs
    mid = cc.gaussian_exchange(chain, "ci_det")[2][:, -1, 1, 1].mean()
    assert v2["chf_crit_chain_ci_det_self"] == pytest.approx(mid, abs=5e-4)
    assert "chf_crit_unequal_ci_det_self" not in v2  # only a network with edges has a middle node
    assert cc.appendix_referenced({"chf_crit_chain_ci_det_self": 1.0, "chf_nobody_reads_this": 2.0}) == {
        "chf_crit_chain_ci_det_self": 1.0}


def test_bad_input_names_the_argument(unequal: NetworkStudy) -> None:
    with pytest.raises(ValueError, match="rule"):
        cc.gaussian_exchange(unequal, "median")
    three = dataclasses.replace(unequal.scenario, frames=3)
    with pytest.raises(ValueError, match="NetworkStudy.gm_gain"):  # arrays of one frame: refused when built
        dataclasses.replace(unequal, scenario=three)
    multi = dataclasses.replace(unequal, scenario=three, gm_gain=np.repeat(unequal.gm_gain, 3, axis=1),
                                ess_local=np.repeat(unequal.ess_local, 3, axis=1))
    with pytest.raises(ValueError, match="study"):
        cc.channel_filter(multi)
    with pytest.raises(ValueError, match="runs"):
        cc.prior_means(unequal.scenario, 1, 0)
    with pytest.raises(ValueError, match="means"):
        cc.exponent_rule("ci_det", np.zeros((2, 2)), np.eye(2))
    with pytest.raises(ValueError, match="estimates"):
        cc.network_mse(unequal, np.zeros((2, 2)))
    with pytest.raises(ValueError, match="studies"):
        cc.baseline_table({}, {})
