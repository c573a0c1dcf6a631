"""Source 004: Chernoff fusion, Gaussian mixtures, weighted EM, particle swarm, the scenario."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fusion.estimates import chernoff as ch
from fusion.estimates.chernoff import gaussian as chg
from fusion.estimates.chernoff import mixture as chm
from fusion.scenarios import two_mixtures
from fusion.scenarios import range_bearing as dist
from fusion import estimates as es
from fusion.estimates import mixtures as mx
from fusion.filtering import particles as pf
from fusion.optimise import swarm
from fusion.optimise.swarm import SwarmOptions


def _spd(rng: np.random.Generator, n: int) -> np.ndarray:
    A = rng.standard_normal((n, n))
    return A @ A.T + 0.5 * np.eye(n)


def _single(m: np.ndarray, P: np.ndarray) -> mx.GaussianMixture:
    return mx.GaussianMixture(np.ones(1), m[None], P[None])


def _rel(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.max(np.abs(np.asarray(a) - np.asarray(b))) / max(1.0, float(np.max(np.abs(b)))))


# --- K1: Gaussian Chernoff fusion is covariance intersection --------------------------------

@given(seed=st.integers(0, 2**31), n=st.integers(1, 4), w=st.floats(0.0, 1.0, allow_subnormal=False))
def test_chernoff_fusion_of_two_gaussians_is_covariance_intersection(seed: int, n: int, w: float) -> None:
    rng = np.random.default_rng(seed)
    a, b = 10 * rng.normal(size=n), 10 * rng.normal(size=n)
    A, B = _spd(rng, n), _spd(rng, n)
    fused = ch.chernoff_fuse_gaussians([a, b], [A, B], [w, 1 - w])
    ci = es.covariance_intersection(a, A, b, B, omega=w)
    assert _rel(fused.x, ci.x) < 1e-10
    assert _rel(fused.P, ci.P) < 1e-10
    # K2: the general normaliser equals the independent two-Gaussian closed form
    assert fused.log_normaliser == pytest.approx(ch.log_normaliser_two_gaussians(a, A, b, B, w), abs=1e-10)
    assert fused.log_normaliser <= 1e-12  # K3 (Hölder): Z <= 1


@given(seed=st.integers(0, 2**31), n_sensors=st.integers(2, 3))
@settings(max_examples=50)
def test_first_order_with_single_components_is_exact_chernoff_fusion(seed: int, n_sensors: int) -> None:
    rng = np.random.default_rng(seed)
    means = 100 * rng.normal(size=(n_sensors, 4))
    covs = np.stack([_spd(rng, 4) for _ in range(n_sensors)])
    e = rng.dirichlet(np.ones(n_sensors))
    fused = ch.chernoff_fuse_gaussians(means, covs, e)
    first = ch.first_order_fusion([_single(m, P) for m, P in zip(means, covs)], e)
    g, log_z = first.mixture, first.log_z_first_order
    assert g.weights.size == 1
    assert _rel(g.means[0], fused.x) < 1e-10
    assert _rel(g.covs[0], fused.P) < 1e-10
    assert log_z == pytest.approx(fused.log_normaliser, abs=1e-9)


def test_normaliser_is_zero_at_vertices_and_for_identical_gaussians() -> None:
    rng = np.random.default_rng(5)
    means, covs = rng.normal(size=(3, 2)), np.stack([_spd(rng, 2) for _ in range(3)])
    for i in range(3):
        vertex = np.eye(3)[i]
        f = ch.chernoff_fuse_gaussians(means, covs, vertex)
        assert f.log_normaliser == pytest.approx(0.0, abs=1e-12)
        np.testing.assert_allclose(f.x, means[i], atol=1e-12)
    same = ch.chernoff_fuse_gaussians(np.repeat(means[:1], 3, 0), np.repeat(covs[:1], 3, 0), [0.2, 0.3, 0.5])
    assert same.log_normaliser == pytest.approx(0.0, abs=1e-12)
    np.testing.assert_allclose(same.P, covs[0], rtol=1e-12)
    one = ch.chernoff_fuse_gaussians(means[:1], covs[:1], [1.0])  # one sensor: itself
    np.testing.assert_allclose(one.x, means[0])


def test_closed_form_normaliser_matches_monte_carlo() -> None:
    rng = np.random.default_rng(1)
    a, b = np.array([0.0, 1.0]), np.array([2.0, -1.0])
    A, B = np.array([[2.0, 0.3], [0.3, 1.0]]), np.array([[1.0, -0.2], [-0.2, 3.0]])
    x = rng.multivariate_normal(a, A, 400_000)
    la, lb = mx.gaussian_logpdf(x, a, A), mx.gaussian_logpdf(x, b, B)
    w = 0.4
    est = np.log(np.mean(np.exp((1 - w) * (lb - la))))  # E_A[(p_B/p_A)^(1-w)]
    assert est == pytest.approx(ch.log_normaliser_two_gaussians(a, A, b, B, w), abs=0.01)


def test_gaussian_importance_weights_are_constant_when_the_proposal_is_exact() -> None:
    """K2 corollary: with single Gaussians, g at eps is p_eps, so the IS weights are equal,
    J-hat equals log Z with zero variance and the ESS is R."""
    rng = np.random.default_rng(6)
    gms = [_single(rng.normal(size=3), _spd(rng, 3)) for _ in range(3)]
    e = np.array([0.2, 0.5, 0.3])
    first = ch.first_order_fusion(gms, e)
    g, log_z = first.mixture, first.log_z_first_order
    xs = mx.gm_sample(g, rng, 500)
    L, lg = ch.log_densities(gms, xs), mx.gm_logpdf(g, xs)
    assert float(ch.is_objective(L, lg, e)) == pytest.approx(log_z, abs=1e-10)
    w = ch.fused_weights(L, lg, e)
    assert pf.effective_sample_size(w) == pytest.approx(500.0, rel=1e-10)


# --- K4: the first-order approximation bounds the normaliser ---------------------------------

def test_first_order_normaliser_bounds_the_exact_one_on_the_toy_mixtures() -> None:
    toy = two_mixtures.toy_mixtures()
    gA, gB = toy.a, toy.b
    omegas = np.linspace(0.0, 1.0, 41)
    E = np.column_stack([omegas, 1 - omegas])
    exact = two_mixtures.grid_log_normaliser([gA, gB], E, n=301).log_z
    first = np.array([ch.first_order_fusion([gA, gB], e).log_z_first_order for e in E])
    assert np.all(exact <= 1e-6)
    assert np.all(first >= exact - 1e-6)
    assert exact[0] == pytest.approx(0.0, abs=1e-6) and exact[-1] == pytest.approx(0.0, abs=1e-6)
    assert np.max(first - exact) > 0.01  # the bound is not tight on mixtures
    # importance sampling from g(0.5) recovers the exact curve and its minimiser
    rng = np.random.default_rng(7)
    g = ch.first_order_fusion([gA, gB], [0.5, 0.5]).mixture
    xs = mx.gm_sample(g, rng, 20_000)
    J = ch.is_objective(ch.log_densities([gA, gB], xs), mx.gm_logpdf(g, xs), E)
    central = (omegas >= 0.2) & (omegas <= 0.8)
    assert np.max(np.abs(J - exact)[central]) < 0.02
    assert np.max(np.abs(J - exact)) > 0.1  # far from the proposal's exponents it degrades
    assert abs(omegas[np.argmin(J)] - omegas[np.argmin(exact)]) <= 0.05


def test_simplified_first_order_weights_differ_from_the_full_ones_but_share_components() -> None:
    toy = two_mixtures.toy_mixtures()
    gA, gB = toy.a, toy.b
    first_full, first_simp = ch.first_order_fusion([gA, gB], [0.4, 0.6]), ch.first_order_fusion([gA, gB], [0.4, 0.6], simplified=True)
    full, lz_full, simp, lz_simp = first_full.mixture, first_full.log_z_first_order, first_simp.mixture, first_simp.log_z_first_order
    np.testing.assert_allclose(full.means, simp.means)
    assert lz_full == lz_simp
    assert np.max(np.abs(full.weights - simp.weights)) > 0.05
    assert full.weights.sum() == pytest.approx(1.0) and simp.weights.sum() == pytest.approx(1.0)


# --- K3/K5: convexity and the equal-divergence optimum ---------------------------------------

def test_is_objective_is_convex_and_fused_weights_normalised() -> None:
    rng = np.random.default_rng(2)
    L = rng.normal(size=(500, 3))
    lg = rng.normal(size=500)
    e = rng.dirichlet(np.ones(3), size=(1000, 2))
    lam = rng.uniform(size=(1000, 1))
    mid = ch.is_objective(L, lg, lam * e[:, 0] + (1 - lam) * e[:, 1])
    ends = lam[:, 0] * ch.is_objective(L, lg, e[:, 0]) + (1 - lam[:, 0]) * ch.is_objective(L, lg, e[:, 1])
    assert np.all(mid <= ends + 1e-10)
    assert np.any(mid < ends - 1e-3)  # strictly convex somewhere: the test can fail
    w = ch.fused_weights(L, lg, [0.2, 0.3, 0.5])
    assert w.sum() == pytest.approx(1.0) and np.all(w >= 0)


@pytest.mark.parametrize("seed", range(5))
def test_chernoff_optimum_is_equally_far_from_every_input(seed: int) -> None:
    rng = np.random.default_rng(seed)
    means = 2 * rng.normal(size=(3, 2))
    covs = np.stack([_spd(rng, 2) for _ in range(3)])
    opt = ch.gaussian_chernoff_weights(means, covs)
    assert opt.eps.sum() == pytest.approx(1.0) and np.all(opt.eps >= 0)
    kl = np.array([ch.gaussian_kl(opt.x, opt.P, m, P) for m, P in zip(means, covs)])
    active = opt.eps > 1e-6
    np.testing.assert_allclose(kl[active], -opt.log_normaliser, atol=1e-5)
    # KKT: an input with zero weight has E[log p_i] >= the common value, so it is *closer*
    assert np.all(kl[~active] <= -opt.log_normaliser + 1e-5)
    # and it is the minimum: random points of the simplex do no better
    for e in rng.dirichlet(np.ones(3), size=200):
        assert ch.gaussian_log_normaliser(means, covs, e) >= opt.log_normaliser - 1e-9


# --- G: the swarm against the deterministic solver ------------------------------------------

@pytest.mark.parametrize("seed", [0, 1, 2])
def test_pso_agrees_with_slsqp_on_the_chernoff_objective(seed: int) -> None:
    rng = np.random.default_rng(seed)
    gms = [mx.GaussianMixture(np.array([0.6, 0.4]), rng.normal(size=(2, 2)),
                              np.stack([_spd(rng, 2), _spd(rng, 2)])) for _ in range(3)]
    res = ch.fuse_mixtures(gms, rng, n_samples=1000, reference=True)
    assert res.eps_reference is not None and res.objective_reference is not None
    assert res.objective == pytest.approx(res.objective_reference, abs=1e-4)
    assert res.objective >= res.objective_reference - 1e-9  # SLSQP finds the global minimum
    assert np.max(np.abs(res.eps - res.eps_reference)) < 0.02
    for e in (res.eps, res.eps_reference):
        assert e.sum() == pytest.approx(1.0, abs=1e-12) and np.all(e >= 0)
    assert res.swarm is not None and np.all(np.diff(res.swarm.history) >= 0)


def test_swarm_stops_early_on_a_flat_fitness_and_validates() -> None:
    res = swarm.particle_swarm(lambda E: np.zeros(len(E)), 3, np.random.default_rng(0), iterations=100, patience=5)
    assert res.history.size == 6
    with pytest.raises(ValueError, match="positive"):
        swarm.particle_swarm(lambda E: np.zeros(len(E)), 0, np.random.default_rng(0))


# --- C: weighted EM ---------------------------------------------------------------------------

def test_weighted_em_is_monotone_and_recovers_a_mixture() -> None:
    rng = np.random.default_rng(3)
    true = mx.GaussianMixture(np.array([0.3, 0.7]), np.array([[-4.0, 0.0], [3.0, 1.0]]),
                              np.array([np.eye(2), np.diag([0.5, 2.0])]))
    x = mx.gm_sample(true, rng, 6000)
    w = np.ones(len(x))
    fit = mx.weighted_em(x, w, 2, rng)
    gm, hist = fit.mixture, fit.loglik
    assert np.all(np.diff(hist) >= -1e-9)
    order = np.argsort(gm.means[:, 0])
    np.testing.assert_allclose(gm.weights[order], true.weights, atol=0.03)
    np.testing.assert_allclose(gm.means[order], true.means, atol=0.1)
    # weights matter: weighting one cluster out removes it
    gm1 = mx.weighted_em(x, (x[:, 0] > 0).astype(float), 1, rng).mixture
    assert gm1.means[0, 0] == pytest.approx(3.0, abs=0.1)
    # a warm start from the answer stays there
    gm2 = mx.weighted_em(x, w, 2, rng, init=gm).mixture
    np.testing.assert_allclose(gm2.means, gm.means, atol=1e-3)
    with pytest.raises(ValueError, match="init"):
        mx.weighted_em(x, w, 3, rng, init=gm)


def test_mixture_moments_match_samples() -> None:
    gA = two_mixtures.toy_mixtures().a
    mom = mx.gm_moments(gA)
    m, P = mom.mean, mom.cov
    x = mx.gm_sample(gA, np.random.default_rng(8), 200_000)
    np.testing.assert_allclose(m, x.mean(axis=0), atol=0.02)
    np.testing.assert_allclose(P, np.cov(x.T), atol=0.03)


def test_regularisation_keeps_the_mean_and_adds_the_kernel_spread() -> None:
    rng = np.random.default_rng(9)
    x = np.repeat(rng.normal(size=(1, 4)), 4000, axis=0)  # fully collapsed cloud
    P = np.diag([4.0, 1.0, 9.0, 1.0])
    y = pf.regularise(x, P, rng)
    h = (4.0 / (4000 * 6)) ** (1 / 8)
    np.testing.assert_allclose(np.cov(y.T), h**2 * P, rtol=0.1, atol=0.03)
    np.testing.assert_allclose(y.mean(axis=0), x[0], atol=0.1)
    with pytest.raises(ValueError, match="particles"):
        pf.regularise(x, np.eye(3), rng)


# --- the scenario -----------------------------------------------------------------------------

SMALL = dist.RangeBearingScenario(frames=4, n_particles=300, n_samples=300, n_central=600, em_iterations=5)


def test_scenario_is_bit_identical_for_the_same_seed_and_weights_stay_on_the_simplex() -> None:
    a = dist.run_tracking(SMALL, np.random.SeedSequence(11), swarm_options=SwarmOptions(iterations=10))
    # the run's stage times: a frozen typed value, every stage it ran charged (the readings' G6 stop was not run)
    t = a.timings
    assert isinstance(t, dist.TrackingTimings) and isinstance(t.fusion, ch.FusionTimings)
    with pytest.raises(dataclasses.FrozenInstanceError):
        t.em = 0.0  # type: ignore[misc]
    ran = ("setup", "particle_filters", "em", "gaussian_baselines", "variants", "centralised_pf")
    assert all(getattr(t, k) > 0 for k in ran) and t.literal_stop == 0.0
    assert all(getattr(t.fusion, k) > 0 for k in ("first_order", "sampling", "densities", "optimiser", "weights"))
    b = dist.run_tracking(SMALL, np.random.SeedSequence(11), swarm_options=SwarmOptions(iterations=10))
    for f in dataclasses.fields(dist.TrackingRun):
        if f.name == "timings":
            continue
        va, vb = getattr(a, f.name), getattr(b, f.name)
        if isinstance(va, dict):
            assert va.keys() == vb.keys()
            for k in va:
                np.testing.assert_array_equal(va[k], vb[k])
        elif va is not None:
            np.testing.assert_array_equal(va, vb)
    c = dist.run_tracking(SMALL, np.random.SeedSequence(12), swarm_options=SwarmOptions(iterations=10))
    assert not np.array_equal(a.estimates["chernoff_pso"], c.estimates["chernoff_pso"])
    for key in ("pso", "slsqp", "prev", "ci_gaussian"):
        assert np.all(a.eps[key] >= 0)
        np.testing.assert_allclose(a.eps[key].sum(axis=1), 1.0, atol=1e-12)
    assert set(a.estimates) == set(dist.method_keys(3))
    assert np.all(a.ess["pso"] <= SMALL.n_samples + 1e-9) and np.all(a.ess["pso"] >= 1 - 1e-9)


def test_linearised_errors_against_a_monte_carlo_of_the_same_kalman_filters() -> None:
    """The exact cross-covariances match sampled errors of linearised filters that share prior and process noise."""
    sc = dist.RangeBearingScenario(frames=6, sigma_r=5.0)
    lin = dist.linearised_errors(sc)
    model = pf.ncv_model(sc.T, sc.q)
    F, Q, S, n = model.F, model.Q, sc.sensor_array, len(sc.sensors)
    R = np.diag([sc.sigma_r**2, sc.sigma_theta**2])
    rng = np.random.default_rng(3)
    M = 20000
    e = np.repeat(rng.multivariate_normal(np.zeros(4), sc.P0, size=M)[:, None], n, axis=1)  # common prior error
    P = np.array(sc.P0)
    x = np.asarray(sc.x0, float)
    Ps = [P.copy() for _ in range(n)]
    for k in range(sc.frames):
        x = F @ x
        w = rng.multivariate_normal(np.zeros(4), Q, size=M)  # one process noise for every node
        e = e @ F.T + w[:, None]
        for i in range(n):
            dx, dy = x[0] - S[i, 0], x[2] - S[i, 1]
            r2 = dx**2 + dy**2
            H = np.array([[dx / np.sqrt(r2), 0, dy / np.sqrt(r2), 0], [-dy / r2, 0, dx / r2, 0]])
            Pp = F @ Ps[i] @ F.T + Q
            K = Pp @ H.T @ np.linalg.inv(H @ Pp @ H.T + R)
            v = rng.multivariate_normal(np.zeros(2), R, size=M)
            e[:, i] = e[:, i] @ (np.eye(4) - K @ H).T - v @ K.T  # error after the update, independent noise
            Ps[i] = (np.eye(4) - K @ H) @ Pp
    J = [np.linalg.inv(p) for p in Ps]
    fused = np.einsum("ab,mb->ma", np.linalg.inv(sum(J)), sum(np.einsum("ab,mb->ma", J[i], e[:, i]) for i in range(n)))
    nees = np.mean(np.einsum("ma,ab,mb->m", fused, sum(J), fused))
    assert abs(nees - lin.nees_naive[-1]) < 0.05 * lin.nees_naive[-1]
    cv = np.mean([np.corrcoef(e[:, i, a], e[:, j, a])[0, 1] for i in range(n) for j in range(i + 1, n) for a in (1, 3)])
    assert abs(cv - lin.corr_velocity[-1]) < 0.02


def test_linearised_errors_attribute_the_excess() -> None:
    """Nothing shared: the naive product is consistent (NEES 4) and the uniform mean is the best combination."""
    sc = dist.RangeBearingScenario(frames=8)
    none = dist.linearised_errors(sc, common_prior=False, common_process=False)
    np.testing.assert_allclose(none.nees_naive, 4.0, rtol=1e-10)
    np.testing.assert_allclose(none.rmse_uniform, none.rmse_best, rtol=1e-8)
    full = dist.linearised_errors(sc)
    assert np.all(full.nees_naive > 4.0) and np.all(full.rmse_best <= full.rmse_uniform + 1e-9)
    assert np.all(full.rmse_central <= full.rmse_best + 1e-9)  # the centralised filter sees every measurement
    # each shared source alone gives a smaller excess than both together
    for part in (dist.linearised_errors(sc, common_prior=False), dist.linearised_errors(sc, common_process=False)):
        assert np.all(part.nees_naive <= full.nees_naive + 1e-9)


def test_posterior_crb_lies_below_the_prior_and_shrinks_with_more_sensors() -> None:
    rng = np.random.default_rng(10)
    truths = np.stack([dist.simulate_target(SMALL, rng).truth for _ in range(5)])
    B = dist.posterior_crb(SMALL, truths)
    one = dist.posterior_crb(dataclasses.replace(SMALL, sensors=SMALL.sensors[:1]), truths)
    model = pf.ncv_model(SMALL.T, SMALL.q)
    F, Q = model.F, model.Q
    P = SMALL.P0
    for k in range(SMALL.frames):
        P = F @ P @ F.T + Q
        assert np.all(np.linalg.eigvalsh(P - B[k]) > -1e-9)  # measurements only add information
        assert np.all(np.linalg.eigvalsh(one[k] - B[k]) > -1e-9)  # so do more sensors
        assert np.all(np.linalg.eigvalsh(B[k]) > 0)
    with pytest.raises(ValueError, match="truths"):
        dist.posterior_crb(SMALL, truths[0])


# --- bad input --------------------------------------------------------------------------------

def test_bad_input_raises() -> None:
    with pytest.raises(ValueError, match="simplex"):
        ch.check_simplex([0.5, 0.6])
    with pytest.raises(ValueError, match="simplex"):
        ch.chernoff_fuse_gaussians([[0.0], [1.0]], [[[1.0]], [[1.0]]], [0.7, 0.7])
    with pytest.raises(ValueError, match="positive definite"):
        ch.chernoff_fuse_gaussians([[0.0], [1.0]], [[[1.0]], [[-1.0]]], [0.5, 0.5])
    with pytest.raises(ValueError, match="symmetric"):
        ch.chernoff_fuse_gaussians([[0.0, 0.0]], [[[1.0, 0.5], [0.0, 1.0]]], [1.0])
    with pytest.raises(ValueError, match="means must be"):
        ch.chernoff_fuse_gaussians([[0.0, 0.0], [1.0, 1.0]], [np.eye(2)], [0.5, 0.5])
    with pytest.raises(ValueError, match="NaN"):
        ch.chernoff_fuse_gaussians([[np.nan], [1.0]], [[[1.0]], [[1.0]]], [0.5, 0.5])
    with pytest.raises(ValueError, match="positive definite"):
        mx.GaussianMixture(np.ones(1), np.zeros((1, 2)), -np.eye(2)[None])
    with pytest.raises(ValueError, match="sum to one"):
        mx.GaussianMixture(np.array([0.5]), np.zeros((1, 2)), np.eye(2)[None])
    with pytest.raises(ValueError, match="shapes"):
        mx.GaussianMixture(np.ones(2), np.zeros((1, 2)), np.eye(2)[None])
    with pytest.raises(ValueError, match="non-negative"):
        mx.weighted_em(np.zeros((5, 2)), -np.ones(5), 1, np.random.default_rng(0))
    with pytest.raises(ValueError, match="omega"):
        ch.log_normaliser_two_gaussians([0.0], [[1.0]], [0.0], [[1.0]], 1.5)
    toy = two_mixtures.toy_mixtures()
    gA, gB = toy.a, toy.b
    with pytest.raises(ValueError, match="optimiser"):
        ch.fuse_mixtures([gA, gB], np.random.default_rng(0), optimiser="newton")
    with pytest.raises(ValueError, match="eps0"):
        ch.fuse_mixtures([gA, gB], np.random.default_rng(0), eps0=[0.9, 0.9])
    with pytest.raises(ValueError, match="columns"):
        ch.is_objective(np.zeros((4, 2)), np.zeros(4), [0.2, 0.3, 0.5])
    with pytest.raises(TypeError, match="seed must be a SeedSequence, got int"):
        dist.run_tracking(SMALL, 3)
    with pytest.raises(TypeError, match=r"seeds\[1\] must be a SeedSequence, got int"):
        dist.run_tracking_batch(SMALL, [np.random.SeedSequence(0), 3])  # type: ignore[arg-type]


# --- optional cross-check against an independent implementation ------------------------------

def test_cross_check_against_stone_soup() -> None:
    """K1 against Stone Soup's covariance-intersection mixture reducer, at weights other than 0.5.

    Checks only ``stonesoup.mixturereducer.gaussianmixture.CovarianceIntersection.merge_components``
    (n-state CI with given weights) against our Chernoff fusion of Gaussians, for 2 and 3 states.
    Stone Soup's ``ChernoffUpdater`` is checked by the next test.
    """
    pytest.importorskip("stonesoup", reason="Stone Soup not installed (pip install -e '.[crosscheck]')")
    from stonesoup.mixturereducer.gaussianmixture import CovarianceIntersection
    from stonesoup.types.state import GaussianState

    rng = np.random.default_rng(13)
    for n_sensors, w in ((2, [0.3, 0.7]), (3, [0.2, 0.5, 0.3])):
        means = rng.normal(size=(n_sensors, 3))
        covs = np.stack([_spd(rng, 3) for _ in range(n_sensors)])
        ours = ch.chernoff_fuse_gaussians(means, covs, w)
        theirs = CovarianceIntersection.merge_components(
            *[GaussianState(m[:, None], P) for m, P in zip(means, covs)], weights=w)
        np.testing.assert_allclose(ours.x, np.asarray(theirs.state_vector, float).ravel(), rtol=1e-10, atol=1e-12)
        np.testing.assert_allclose(ours.P, np.asarray(theirs.covar, float), rtol=1e-10, atol=1e-12)


def test_stonesoup_check_recovers_the_chernoff_normaliser_curvature() -> None:
    """The chapter's comparison finds V = A/ω + B/(1-ω) (curvature of -log Z in a) and our fusion exactly."""
    from fusion.book.chapters.chernoff import stonesoup_check

    A, B = np.array([[2.0, 0.3], [0.3, 1.0]]), np.array([[1.0, -0.2], [-0.2, 3.0]])
    a, b = np.array([1.0, 2.0]), np.array([0.5, -1.0])
    rows = []
    for w in (0.2, 0.5, 0.8):
        f = ch.chernoff_fuse_gaussians(np.stack([a, b]), np.stack([A, B]), [w, 1 - w])
        rows.append({"omega": w, "innovation_covariance": (A / w + B / (1 - w)).tolist(),
                     "posterior_mean": f.x.tolist(), "posterior_covariance": f.P.tolist()})
    A2 = np.array([[5.0, -1.0], [-1.0, 2.5]])
    f2 = ch.chernoff_fuse_gaussians(np.stack([a, b]), np.stack([A2, B]), [0.8, 0.2])
    case = {"omega": 0.8, "detection_covariance": A2.tolist(), "innovation_covariance": (A2 / 0.8 + B / 0.2).tolist(),
            "posterior_mean": f2.x.tolist(), "posterior_covariance": f2.P.tolist()}
    rec = {"stonesoup_version": "synthetic", "measurement": {"mean": a.tolist(), "covariance": A.tolist()},
           "prediction": {"mean": b.tolist(), "covariance": B.tolist()}, "rows": rows, "detection_case": case}
    table, values = stonesoup_check(rec)
    assert values["chf_ss_det_v"] == 0.0 and values["chf_ss_det_post"] == 0.0 and values["chf_ss_det_model"] > 0.1
    assert (table.iloc[:, [0, 2, 3]] == 0.0).all(axis=None)                    # right curvature, same fusion
    assert table.loc[0.5].iloc[1] == 0.0 and table.loc[0.2].iloc[1] > 0.1      # the swap matters only off 0.5
    assert values["chf_ss_post"] == 0.0


def test_cross_check_stone_soup_chernoff_updater_live() -> None:
    """Stone Soup's ChernoffUpdater, run live, gives the outputs recorded for chapter 06 (update = our fusion)."""
    pytest.importorskip("stonesoup", reason="Stone Soup not installed (pip install stonesoup in a side environment)")
    import importlib.util
    import json
    from pathlib import Path

    from fusion.book.chapters.chernoff import STONESOUP_RECORD, stonesoup_check

    spec = importlib.util.spec_from_file_location(
        "crosscheck", Path(__file__).resolve().parents[1] / "benchmarks" / "crosscheck_stonesoup.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)  # type: ignore[union-attr]
    live = mod.run()
    stored = json.loads(STONESOUP_RECORD.read_text(encoding="utf-8"))
    for r_live, r_stored in zip(live["rows"], stored["rows"]):
        np.testing.assert_allclose(r_live["innovation_covariance"], r_stored["innovation_covariance"], rtol=1e-12)
        np.testing.assert_allclose(r_live["posterior_mean"], r_stored["posterior_mean"], rtol=1e-12)
    table, values = stonesoup_check(live)
    assert (table["posterior mean vs our fusion"] == 0.0).all()
    # the chapter's claim: the innovation covariance is the swapped form, and differs from V off ω = 0.5
    assert (table["vs the swapped A/(1−ω) + B/ω"] == 0.0).all()
    assert table.loc[0.5, "innovation covariance vs V = A/ω + B/(1−ω)"] == 0.0
    assert table.loc[0.2, "innovation covariance vs V = A/ω + B/(1−ω)"] > 0.1
    assert table.loc[0.8, "innovation covariance vs V = A/ω + B/(1−ω)"] > 0.1
    # a detection with its own covariance: the gate uses the model's noise covariance, the update the detection's
    assert values["chf_ss_det_model"] == 0.0 and values["chf_ss_det_post"] == 0.0 and values["chf_ss_det_v"] > 0.1


def test_batched_em_gives_exactly_the_per_set_fits() -> None:
    """weighted_em_batch on B sets equals weighted_em set by set, digit for digit (warm and cold starts)."""
    rng = np.random.default_rng(3)
    X = rng.normal(size=(4, 300, 2)) * [5.0, 1.0]
    X[:2, :100, 0] += 20.0  # two bimodal sets, two unimodal ones (their components may die)
    W = rng.uniform(size=(4, 300)) ** 2
    warm = mx.weighted_em(X[1], W[1], 2, np.random.default_rng(9)).mixture
    inits = [None, warm, None, None]
    batch = mx.weighted_em_batch(X, W, 2, [np.random.default_rng(b) for b in range(4)], max_iter=30, tol=1e-9,
                                 init=inits)
    for b in range(4):
        one = mx.weighted_em(X[b], W[b], 2, np.random.default_rng(b), max_iter=30, tol=1e-9, init=inits[b])
        np.testing.assert_array_equal(batch[b].loglik, one.loglik)
        np.testing.assert_array_equal(batch[b].mixture.means, one.mixture.means)
        np.testing.assert_array_equal(batch[b].mixture.covs, one.mixture.covs)
        np.testing.assert_array_equal(batch[b].mixture.weights, one.mixture.weights)
    assert len({f.loglik.size for f in batch}) > 1  # the sets stop at different iterations


def test_batched_runs_are_identical_to_the_per_run_loop() -> None:
    """run_tracking_batch on R seeds gives every record of run_tracking called run by run."""
    loop = [dist.run_tracking(SMALL, s, all_nodes=(j == 0), swarm_options=SwarmOptions(iterations=10))
            for j, s in enumerate(np.random.SeedSequence(21).spawn(3))]
    batch = dist.run_tracking_batch(SMALL, np.random.SeedSequence(21).spawn(3), all_nodes=[True, False, False],
                                    swarm_options=SwarmOptions(iterations=10))
    for a, b in zip(loop, batch):
        for f in dataclasses.fields(dist.TrackingRun):
            if f.name == "timings":
                continue
            va, vb = getattr(a, f.name), getattr(b, f.name)
            if isinstance(va, dict):
                assert va.keys() == vb.keys()
                for k in va:
                    np.testing.assert_array_equal(va[k], vb[k])
            elif va is not None:
                np.testing.assert_array_equal(va, vb)
    assert not np.array_equal(loop[0].truth, loop[1].truth)  # the runs differ from each other


REFERENCE = Path(__file__).resolve().parent / "data" / "chernoff_reference.json"


def _scenario_from(d: dict[str, object]) -> dist.RangeBearingScenario:
    kw = dict(d)
    kw["sensors"] = tuple(tuple(s) for s in kw["sensors"])  # type: ignore[union-attr]
    kw["x0"], kw["p0_std"] = tuple(kw["x0"]), tuple(kw["p0_std"])  # type: ignore[arg-type]
    return dist.RangeBearingScenario(**kw)  # type: ignore[arg-type]


#: Keys of the reference file renamed since it was recorded (issue 36: method keys unique across chapters).
_RENAMED = {"mean_of_means": "mean_of_local_means", "centralised": "centralised_pf"}


def test_vectorised_runner_reproduces_the_per_run_implementation_it_replaced() -> None:
    """Same seeds, same decisions: the outputs recorded from the per-run implementation before vectorisation.

    tests/data/chernoff_reference.json holds every record of two small cases (plain; collapse guard with
    progressive correction and an initial particle surplus) computed by the per-run code the batched
    runner replaced (commit 2f4197a). Every decision (swarm evaluations and exponents, guarded updates,
    fused component counts) is identical and every value agrees to round-off, except the CI exponents,
    which SLSQP now finds with the exact gradient instead of finite differences (to ~1e-7).
    """
    ref = json.loads(REFERENCE.read_text(encoding="utf-8"))
    for case in ref["cases"].values():
        sc = _scenario_from(case["scenario"])
        runs = dist.run_tracking_batch(sc, np.random.SeedSequence(case["root"]).spawn(len(case["runs"])),
                                       all_nodes=case["all_nodes"])
        for run, old in zip(runs, case["runs"]):
            assert [list(g) for g in run.guarded] == old["guarded"]
            np.testing.assert_array_equal(run.truth, old["truth"])
            np.testing.assert_array_equal(run.evaluations["pso"], old["evaluations"]["pso"])
            np.testing.assert_array_equal(run.n_fused_components, old["n_fused_components"])
            np.testing.assert_allclose(run.eps["pso"], old["eps"]["pso"], rtol=0, atol=1e-12)
            for field in ("estimates", "covariances", "ess", "objective"):
                for key, want_list in old[field].items():  # the records of the replaced implementation
                    value, want = getattr(run, field)[_RENAMED.get(key, key)], np.asarray(want_list, dtype=float)
                    scale = max(1.0, float(np.nanmax(np.abs(want))))
                    tol = 1e-5 if key == "ci_gaussian" else 1e-9
                    np.testing.assert_allclose(value, want, rtol=0, atol=tol * scale, err_msg=f"{field}[{key}]")
            np.testing.assert_allclose(run.gm_loglik, old["gm_loglik"], rtol=1e-10)
            np.testing.assert_allclose(run.gm1_loglik, old["gm1_loglik"], rtol=1e-10)
            if old["node_estimates"] is not None:
                np.testing.assert_allclose(run.node_estimates, old["node_estimates"], rtol=1e-9)


def test_worker_processes_give_the_same_runs() -> None:
    """run_tracking_batch with two worker processes (blocks of runs shared out) equals one process, digit for digit."""
    tiny = dist.RangeBearingScenario(frames=2, n_particles=60, n_samples=60, n_central=100, em_iterations=3)
    n = dist.RUN_BLOCK + 2  # two blocks
    one = dist.run_tracking_batch(tiny, np.random.SeedSequence(4).spawn(n), swarm_options=SwarmOptions(iterations=3))
    two = dist.run_tracking_batch(tiny, np.random.SeedSequence(4).spawn(n), swarm_options=SwarmOptions(iterations=3), workers=2)
    for a, b in zip(one, two, strict=True):
        for key in a.estimates:
            np.testing.assert_array_equal(a.estimates[key], b.estimates[key])
        np.testing.assert_array_equal(a.eps["pso"], b.eps["pso"])


def test_batched_fusion_problems_are_computed_alike_wherever_they_sit() -> None:
    """fuse_mixtures_batch: problem b equals the problem alone, digit for digit, at any offset in the batch."""
    rng = np.random.default_rng(8)
    B, N, S, d = 5, 3, 3, 4
    w = rng.dirichlet(np.ones(S), size=(B, N))
    w[1, 2, 0] = 0.0  # one node with a missing component
    w[1, 2] /= w[1, 2].sum()
    m = rng.normal(size=(B, N, S, d)) * 3 + 800
    A = rng.normal(size=(B, N, S, d, d))
    c = A @ np.swapaxes(A, -1, -2) + 5 * np.eye(d)
    full = ch.fuse_mixtures_batch(w, m, c, [np.random.default_rng(b) for b in range(B)], 300, reference=True, redraw=True,
                                  swarm_options=SwarmOptions(iterations=8))
    for b in range(B):
        one = ch.fuse_mixtures_batch(w[b:b + 1], m[b:b + 1], c[b:b + 1], [np.random.default_rng(b)], 300, reference=True,
                                     redraw=True, swarm_options=SwarmOptions(iterations=8))[0]
        for f in dataclasses.fields(ch.MixtureFusion):
            va, vb = getattr(full[b], f.name), getattr(one, f.name)
            if f.name == "swarm":
                np.testing.assert_array_equal(va.history, vb.history)
            else:
                np.testing.assert_array_equal(va, vb, err_msg=f.name)
    assert full[1].n_fused_components < S**N  # the missing component removes its tuples


def test_batched_swarms_equal_single_swarms() -> None:
    """particle_swarm_batch gives what particle_swarm gives problem by problem (own generator, own stop)."""
    centres = np.array([[0.2, 0.3, 0.5], [0.6, 0.2, 0.2], [1 / 3, 1 / 3, 1 / 3]])
    flat = np.array([1.0, 1.0, 0.0])  # the last problem is flat: stops on stagnation first

    def fit(active: np.ndarray, E: np.ndarray) -> np.ndarray:
        return -flat[active, None] * np.sum((E - centres[active, None]) ** 2, axis=-1)

    batch = swarm.particle_swarm_batch(fit, 3, [np.random.default_rng(b) for b in range(3)])
    for b in range(3):
        one = swarm.particle_swarm(lambda E, b=b: -flat[b] * np.sum((E - centres[b]) ** 2, axis=-1), 3,
                                   np.random.default_rng(b))
        np.testing.assert_array_equal(batch[b].x, one.x)
        np.testing.assert_array_equal(batch[b].history, one.history)
        assert batch[b].n_evaluations == one.n_evaluations
    assert batch[2].n_evaluations < batch[0].n_evaluations


def test_quadratic_feature_densities_equal_the_direct_ones() -> None:
    """The EM/IS kernels' log densities by quadratic features match gm_logpdf (Cholesky solves) far from the origin."""
    rng = np.random.default_rng(9)
    gm = mx.GaussianMixture(np.array([0.5, 0.3, 0.2]), rng.normal(size=(3, 4)) * 20 + [800, 15, 600, 10],
                            np.stack([_spd(rng, 4) * s for s in (1.0, 10.0, 100.0)]))
    x = gm.means[0] + rng.normal(size=(500, 4)) * 15
    centre = x.mean(axis=0)
    lp = mx._mixture_logpdf_features(np.log(gm.weights), gm.means - centre, gm.covs, mx._features(x - centre))
    np.testing.assert_allclose(lp, mx.gm_logpdf(gm, x), rtol=1e-11, atol=1e-9)
    np.testing.assert_allclose(pf.wrap_angle(np.array([0.1, np.pi + 0.1, -3 * np.pi + 0.2])),
                               [0.1, -np.pi + 0.1, -np.pi + 0.2], atol=1e-12)


def test_is_second_moment_matches_sampling_and_is_infinite_outside_its_region() -> None:
    """The closed-form E_g[w²] agrees with a large sample inside Λ ≻ 0, is 1 at eps = eps0, inf outside."""
    a, A = np.array([0.0, 0.0]), np.diag([4.0, 1.0])
    b, B = np.array([2.0, 1.0]), np.array([[1.0, 0.5], [0.5, 3.0]])
    e0 = np.array([0.5, 0.5])
    assert ch.is_second_moment([a, b], [A, B], e0, e0) == pytest.approx(1.0, abs=1e-12)
    rng = np.random.default_rng(4)
    g = ch.chernoff_fuse_gaussians([a, b], [A, B], e0)
    x = g.x + rng.standard_normal((400_000, 2)) @ np.linalg.cholesky(g.P).T
    for w in (0.3, 0.7):
        t = ch.chernoff_fuse_gaussians([a, b], [A, B], [w, 1 - w])
        lw = mx.gaussian_logpdf(x, t.x, t.P) - mx.gaussian_logpdf(x, g.x, g.P)
        assert ch.is_second_moment([a, b], [A, B], [w, 1 - w], e0) == pytest.approx(np.mean(np.exp(2 * lw)), rel=0.02)
    # ω = 1: Λ = 1.5 A⁻¹ - 0.5 B⁻¹ has a negative eigenvalue for this pair
    assert np.min(np.linalg.eigvalsh(1.5 * np.linalg.inv(A) - 0.5 * np.linalg.inv(B))) < 0
    assert ch.is_second_moment([a, b], [A, B], [1.0, 0.0], e0) == np.inf


# --- batched solvers on the simplex (issue 19) -------------------------------------------------

def _gauss_problems(rng: np.random.Generator, B: int, N: int, d: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    m = rng.normal(size=(B, N, d)) * rng.uniform(0.1, 5, size=(B, 1, 1))
    A = rng.normal(size=(B, N, d, d))
    c = (A @ np.swapaxes(A, -1, -2) + 0.1 * np.eye(d)) * rng.uniform(0.1, 10, size=(B, N, 1, 1))
    return m, np.linalg.inv(c), np.linalg.slogdet(2 * np.pi * c)[1]


def test_projected_newton_finds_the_gaussian_chernoff_minimum_slsqp_finds() -> None:
    """Interior and boundary optima alike: never worse than SLSQP, the same point to SLSQP's precision."""
    rng = np.random.default_rng(12)
    n_boundary = 0
    for N, d in ((2, 2), (3, 4), (4, 2)):
        m, infos, ld = _gauss_problems(rng, 40, N, d)
        e = chg._gaussian_chernoff_batch(m, infos, ld)
        np.testing.assert_allclose(e.sum(axis=1), 1.0, atol=1e-12)
        assert np.all(e >= 0)
        for b in range(40):
            def f(x: np.ndarray, b: int = b) -> float:
                return float(chg._product_terms(m[b][None, None], infos[b][None, None], ld[b][None, None],
                                               np.clip(x, 0, None))[2][0, 0])
            ref = ch.minimise_on_simplex(f, N).x
            assert f(e[b]) <= f(ref) + 1e-12
            np.testing.assert_allclose(e[b], ref, atol=1e-5)
            n_boundary += int(np.any(e[b] == 0))
        one = chg._gaussian_chernoff_batch(m[3:4], infos[3:4], ld[3:4])
        np.testing.assert_array_equal(one[0], e[3])  # a problem alone gives the same digits
    assert n_boundary > 0  # the case is informative: some optima lie on the boundary


def test_first_order_normaliser_derivatives_and_minimum() -> None:
    toy = two_mixtures.toy_mixtures()
    gms = [toy.a, toy.b, toy.a]
    lw, m, c = chm._mixture_arrays(gms)
    x0 = np.array([0.2, 0.5, 0.3])
    f, g, H = chm._first_order_log_normaliser_derivatives(lw[None], m[None], c[None], x0[None])
    assert f[0] == pytest.approx(ch.first_order_fusion(gms, x0).log_z_first_order, abs=1e-12)
    h = 1e-6
    for i in range(3):
        dx = np.eye(3)[i] * h
        fp = chm._first_order_log_normaliser_derivatives(lw[None], m[None], c[None], (x0 + dx)[None])
        fm = chm._first_order_log_normaliser_derivatives(lw[None], m[None], c[None], (x0 - dx)[None])
        assert (fp[0][0] - fm[0][0]) / (2 * h) == pytest.approx(g[0, i], rel=1e-5)
        np.testing.assert_allclose((fp[1][0] - fm[1][0]) / (2 * h), H[0, :, i], rtol=1e-4, atol=1e-6)
    e = chm._first_order_minimum(lw[None], m[None], c[None])[0]
    ref = ch.minimise_on_simplex(lambda x: ch.first_order_fusion(gms, x).log_z_first_order, 3).x
    np.testing.assert_allclose(e, ref, atol=1e-5)


def test_newton_and_equal_kl_on_importance_samples() -> None:
    """optimiser='newton' is SLSQP's minimum of Ĵ; the equal-KL rule is that minimum when interior, NaN on the boundary."""
    toy = two_mixtures.toy_mixtures()
    lw, m, c = chm._mixture_arrays([toy.a, toy.b])
    B = 4
    args = (np.repeat(lw[None], B, 0), np.repeat(m[None], B, 0), np.repeat(c[None], B, 0))
    fus = chm._fuse_arrays(*args, [np.random.default_rng(b) for b in range(B)], 500, np.full((B, 2), 0.5), "newton",
                          False, True, None, None, keep_samples=True, equal_kl=True)
    for f in fus:
        assert f.objective <= f.objective_reference + 1e-10
        np.testing.assert_allclose(f.eps, f.eps_reference, atol=1e-4)
        np.testing.assert_allclose(f.eps_equal_kl, f.eps_reference, atol=1e-4)  # interior optimum
        assert f.samples.shape == (500, 2) and f.weights.sum() == pytest.approx(1.0)
    # a node far more informative than the other: the minimum of Ĵ sits at a vertex, the rule has no solution
    rng = np.random.default_rng(3)
    L = rng.normal(size=(1, 2, 300))
    L[0, 1] = L[0, 0] - 30.0 + 0.1 * rng.normal(size=300)
    lg = L[0, 0][None] + 0.05 * rng.normal(size=(1, 300))
    ref = ch.simplex_minimum(L[0].T, lg[0]).x
    assert np.min(ref) < 1e-6
    assert np.all(np.isnan(chm._equal_kl(L, lg)))


def test_fusion_without_the_swarm_keeps_the_proposal_exponents() -> None:
    toy = two_mixtures.toy_mixtures()
    lw, m, c = chm._mixture_arrays([toy.a, toy.b])
    w = np.exp(lw)[None]
    e0 = np.array([0.3, 0.7])
    f = ch.fuse_mixtures_batch(w, m[None], c[None], [np.random.default_rng(1)], 300, eps0=e0, optimiser="none",
                               keep_samples=True)[0]
    np.testing.assert_array_equal(f.eps, e0)
    np.testing.assert_allclose(f.x, f.x_eps0)
    np.testing.assert_array_equal(f.weights, f.weights_eps0)


def test_readings_leave_every_other_method_unchanged() -> None:
    """readings=True adds the readings of steps D and F from their own stream: the other records are the same."""
    sc = dataclasses.replace(SMALL, frames=3)
    a = dist.run_tracking(dataclasses.replace(sc, readings=True), np.random.SeedSequence(8), swarm_options=SwarmOptions(iterations=8))
    b = dist.run_tracking(sc, np.random.SeedSequence(8), swarm_options=SwarmOptions(iterations=8))
    for key in b.estimates:
        np.testing.assert_array_equal(a.estimates[key], b.estimates[key])
    assert set(a.estimates) - set(b.estimates) == set(dist.READING_METHODS)
    np.testing.assert_allclose(a.eps["first_order"].sum(axis=1), 1.0)
    ok = np.all(np.isfinite(a.eps["equal_kl"]), axis=1)
    np.testing.assert_allclose(a.eps["equal_kl"][ok], a.eps["slsqp"][ok], atol=1e-4)


# --- the swarm followed to its limit; the practitioner's covariance intersection; the runner's readings --------------

def test_traced_swarm_changes_nothing_and_gives_every_stopping_rule() -> None:
    """trace=True leaves the result and the caller's generator as they are, and the trace gives what
    stop="positions" (any tolerance) and stop="stagnation" return on their own."""
    centre = np.array([0.2, 0.5, 0.3])

    def fit(E: np.ndarray) -> np.ndarray:
        return -np.sum((E - centre) ** 2, axis=-1)
    for seed in range(5):
        g1, g2 = np.random.default_rng(seed), np.random.default_rng(seed)
        plain = swarm.particle_swarm(fit, 3, g1)
        traced = swarm.particle_swarm(fit, 3, g2, trace=True)
        assert g1.random() == g2.random()  # the caller's stream is where the stopped swarm leaves it
        np.testing.assert_array_equal(plain.x, traced.x)
        np.testing.assert_array_equal(plain.history, traced.history)
        assert plain.n_evaluations == traced.n_evaluations and plain.trace is None
        tr = traced.trace
        assert tr.fitness.size == 51 and np.all(np.diff(tr.fitness) >= 0) and tr.best.shape == (51, 3)
        again = tr.at(tr.stop_stagnation(1e-9, 10))
        np.testing.assert_array_equal(again.x, plain.x)
        assert again.n_evaluations == plain.n_evaluations
        for xtol in (1e-3, 1e-2, 5e-2):
            lit = swarm.particle_swarm(fit, 3, np.random.default_rng(seed), stop="positions", xtol=xtol)
            got = tr.at(tr.stop_positions(xtol))
            np.testing.assert_array_equal(got.x, lit.x)
            assert got.fun == lit.fun and got.n_evaluations == lit.n_evaluations


def test_covariance_intersection_weights_by_determinant_and_trace() -> None:
    """Two estimates: the closed-form CI weight (ci_weight); three: SLSQP on the criterion; on the simplex."""
    from fusion.estimates import ci_weight
    rng = np.random.default_rng(11)
    for _ in range(20):
        P = np.stack([_spd(rng, 3) for _ in range(2)])
        for crit in ("det", "trace"):
            w = ch.covariance_intersection_weights(P, crit)
            assert w[0] == pytest.approx(ci_weight(P[0], P[1], crit), abs=1e-6)
    for _ in range(10):
        P = np.stack([_spd(rng, 4) for _ in range(3)])
        infos = np.linalg.inv(P)
        for crit in ("det", "trace"):
            def f(e: np.ndarray) -> float:
                Pf = np.linalg.inv(np.tensordot(e, infos, 1))
                return float(np.linalg.slogdet(Pf)[1] if crit == "det" else np.trace(Pf))
            w = ch.covariance_intersection_weights(P, crit)
            assert w.sum() == pytest.approx(1.0, abs=1e-12) and np.all(w >= 0)
            assert f(w) <= ch.minimise_on_simplex(f, 3).fun + 1e-9
    same = ch.covariance_intersection_weights(np.stack([np.eye(2)] * 3), "det")  # flat: any weights, stays uniform
    np.testing.assert_allclose(same, 1 / 3)
    with pytest.raises(ValueError, match="criterion"):
        ch.covariance_intersection_weights(P, "entropy")


def test_runner_readings_centralised_guard_and_newton_variant() -> None:
    """readings add the literal stopping rule (same samples: its estimate is the main fusion's at its own exponents);
    the centralised guard acts only where the centralised filter collapses; the Newton variant of ε⁽⁰⁾ = previous ε*."""
    sc = dist.RangeBearingScenario(frames=3, n_particles=200, n_samples=200, n_central=300, em_iterations=3)
    seeds = np.random.SeedSequence(8).spawn(3)
    base = dist.run_tracking_batch(sc, seeds)
    rd = dist.run_tracking_batch(dataclasses.replace(sc, readings=True), np.random.SeedSequence(8).spawn(3))
    for a, b in zip(base, rd):
        np.testing.assert_array_equal(a.estimates["chernoff_pso"], b.estimates["chernoff_pso"])  # nothing else moves
        np.testing.assert_array_equal(a.estimates["chernoff_redraw"], b.estimates["chernoff_redraw"])
        assert b.swarm_trace["fitness"].shape == (3, 51) and b.swarm_trace["spread"].shape == (3, 51)
        assert np.all(b.objective["literal"] >= b.objective["slsqp"] - 1e-9)
    cg = dist.run_tracking_batch(dataclasses.replace(sc, central_guard=0.005), np.random.SeedSequence(8).spawn(3))
    for a, c in zip(base, cg):
        if np.min(a.ess["centralised_pf"]) >= 0.005 * sc.n_central:
            np.testing.assert_array_equal(a.estimates["centralised_pf"], c.estimates["centralised_pf"])
            assert not c.guarded
        else:
            assert any(i == -1 for _, i in c.guarded) and np.min(c.ess["centralised_pf"]) > np.min(a.ess["centralised_pf"])
        np.testing.assert_array_equal(a.estimates["chernoff_pso"], c.estimates["chernoff_pso"])
    nw = dist.run_tracking_batch(dataclasses.replace(sc, prev_optimiser="newton"), np.random.SeedSequence(8).spawn(3))
    for a, c in zip(base, nw):  # frame 1 (the variant shares the fusion's stream: later frames' samples move)
        np.testing.assert_array_equal(a.estimates["chernoff_pso"][0], c.estimates["chernoff_pso"][0])
        assert np.max(np.abs(a.eps["prev"][0] - c.eps["prev"][0])) < 0.1  # the swarm's optimum within its sampling error


def test_swarm_options_defaults_are_the_swarms_own() -> None:
    """SwarmOptions() passes exactly the defaults of particle_swarm and particle_swarm_batch (one source of truth)."""
    import inspect

    opts = swarm.SwarmOptions().keywords()
    for fn in (swarm.particle_swarm, swarm.particle_swarm_batch):
        params = inspect.signature(fn).parameters
        assert {k: params[k].default for k in opts} == opts, fn.__name__
    assert set(inspect.signature(swarm.particle_swarm_batch).parameters) - set(opts) == {"fitness", "dim", "rngs", "trace"}


@pytest.mark.parametrize("field, bad", [("iterations", 0), ("n_particles", 1.5), ("lo", 1.0), ("vmax", -0.1),
                                        ("stop", "never"), ("inertia", float("nan"))])
def test_swarm_options_refuse_a_bad_field_naming_it(field: str, bad: object) -> None:
    with pytest.raises((ValueError, TypeError), match=field):
        swarm.SwarmOptions(**{field: bad})
    with pytest.raises(TypeError, match="swarm_options"):  # the options dict of before is refused
        ch.fuse_mixtures([two_mixtures.toy_mixtures().a], np.random.default_rng(0), n_samples=50,
                         swarm_options={"iterations": 3})  # type: ignore[arg-type]


def test_timed_fusion_reports_every_stage_and_changes_nothing() -> None:
    toy = two_mixtures.toy_mixtures()
    kw = dict(n_samples=300, swarm_options=SwarmOptions(iterations=5), reference=True)
    plain = ch.fuse_mixtures([toy.a, toy.b], np.random.default_rng(3), **kw)
    timed = ch.fuse_mixtures([toy.a, toy.b], np.random.default_rng(3), timed=True, **kw)
    assert plain.timings is None and isinstance(timed.timings, ch.FusionTimings)
    seconds = dataclasses.asdict(timed.timings)
    assert all(v >= 0 for v in seconds.values())
    assert seconds["redraw"] == 0.0 and seconds["reference"] > 0  # only the stages that ran take time
    np.testing.assert_array_equal(timed.eps, plain.eps)
    np.testing.assert_array_equal(timed.x, plain.x)


@settings(max_examples=15, deadline=None)
@given(n=st.integers(1, 5), junk=st.sampled_from([float("nan"), 7.0, -1.0]))
def test_minimise_on_simplex_returns_its_own_x_whatever_the_objective_writes_into_its_argument(n: int,
                                                                                               junk: float) -> None:
    """An objective that overwrites its argument changes neither x nor fun (fuzz13: x was the buffer f received)."""
    target = np.linspace(1.0, 2.0, n) / np.linspace(1.0, 2.0, n).sum()

    def clean(e: np.ndarray) -> float:
        return float(np.sum((e - target) ** 2))

    def vandal(e: np.ndarray) -> float:
        v = clean(e)
        e[:] = junk
        return v

    ref, got = ch.minimise_on_simplex(clean, n), ch.minimise_on_simplex(vandal, n)
    np.testing.assert_array_equal(got.x, ref.x)
    assert got.fun == ref.fun and np.all(got.x >= 0) and np.isclose(got.x.sum(), 1.0)
