"""Issue 37: the sped-up kernels give the numbers of their reference paths (``benchmarks/_reference_kernels.py``,
the code as it was), bit for bit; and their prepared (exponent-free) parts give a problem's numbers whatever the
other problems of the batch."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import numpy as np
import pytest

from fusion.estimates import mixtures as mx
from fusion.estimates.chernoff import mixture as chm
from fusion.scenarios import range_bearing_batch as rbb

_SPEC = importlib.util.spec_from_file_location(
    "_reference_kernels", Path(__file__).resolve().parents[1] / "benchmarks" / "_reference_kernels.py")
assert _SPEC is not None and _SPEC.loader is not None
ref = importlib.util.module_from_spec(_SPEC)
_SPEC.loader.exec_module(ref)


def _mixtures(seed: int, B: int = 9, N: int = 3, S: int = 3, d: int = 4, dead: bool = True):
    """B problems of N mixtures of S components in d dimensions, tracking-like scales, some components dead."""
    rng = np.random.default_rng(seed)
    centre = rng.normal(scale=500.0, size=(B, 1, 1, d))
    means = centre + rng.normal(scale=30.0, size=(B, N, S, d))
    A = rng.normal(scale=8.0, size=(B, N, S, d, d))
    covs = A @ np.swapaxes(A, -1, -2) + 4.0 * np.eye(d)
    logw = np.log(rng.dirichlet(np.ones(S), size=(B, N)))
    if dead:
        logw[0, 1, 2] = logw[3, 0, 0] = -np.inf  # a dead component (padding): identity covariance
        covs[0, 1, 2] = covs[3, 0, 0] = np.eye(d)
    return logw, means, covs, rng


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_first_order_arrays_match_the_reference(seed: int) -> None:
    logw, means, covs, rng = _mixtures(seed)
    eps = rng.dirichlet(np.ones(3), size=logw.shape[0])
    for simplified in (False, True):
        new = chm._first_order_arrays(logw, means, covs, eps, simplified)
        old = ref.first_order_arrays(logw, means, covs, eps, simplified)
        for a, b in zip(new, old):
            np.testing.assert_array_equal(a, b)


@pytest.mark.parametrize("seed", [0, 1])
def test_gaussian_coefs_and_features_match_the_reference(seed: int) -> None:
    logw, means, covs, rng = _mixtures(seed)
    x = rng.normal(scale=20.0, size=(5, 50, 4))
    np.testing.assert_array_equal(mx._features(x), ref.features(x))
    for a, b in zip(mx._gaussian_coefs(logw, means, covs), ref.gaussian_coefs(logw, means, covs)):
        np.testing.assert_array_equal(a, b)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_sigma_points_match_the_reference_on_any_subset(seed: int) -> None:
    logw, means, covs, rng = _mixtures(seed)
    eps = rng.dirichlet(np.ones(3), size=logw.shape[0])
    old = ref.sigma_point_log_expectations(logw, means, covs, eps)
    np.testing.assert_array_equal(rbb._sigma_point_log_expectations(logw, means, covs, eps), old)
    prep = rbb._sigma_point_prepare(logw, means, covs)  # prepared once, used on a subset (as the Newton steps do)
    idx = np.array([4, 0, 4, 7])
    sub = rbb._sigma_points_prepared(logw[idx], means[idx], tuple(p[idx] for p in prep), eps[idx])
    np.testing.assert_array_equal(sub, old[idx])


@pytest.mark.parametrize("seed", [0, 1, 2, 3])
def test_equal_kl_on_mixture_matches_the_reference(seed: int) -> None:
    logw, means, covs, _ = _mixtures(seed, B=12)
    old = ref.equal_kl_on_mixture(logw, means, covs)
    assert np.isfinite(old).any()  # the comparison covers converged problems
    np.testing.assert_array_equal(rbb._equal_kl_on_mixture(logw, means, covs), old)


def test_equal_kl_on_mixture_line_search_matches_the_reference_at_every_chunk() -> None:
    """More problems at other scales (other step lengths, other halving counts, some without a solution): the line
    search that tries its steps in chunks stops where halving one at a time stops."""
    for seed in range(4, 12):
        logw, means, covs, _ = _mixtures(seed, B=6)
        means = means * np.float64(1.0 + 0.05 * seed)  # other scales: other step lengths
        np.testing.assert_array_equal(rbb._equal_kl_on_mixture(logw, means, covs),
                                      ref.equal_kl_on_mixture(logw, means, covs))
    assert rbb._STEP_CHUNKS[0] == (0, 1) and rbb._STEP_CHUNKS[-1][1] == rbb._STEPS.size == 30
    assert all(lo2 == hi1 for (_, hi1), (lo2, _) in zip(rbb._STEP_CHUNKS, rbb._STEP_CHUNKS[1:]))
    np.testing.assert_array_equal(rbb._STEPS, 0.5 ** np.arange(30.0))


def test_equal_kl_on_mixture_reference_differs_when_the_mixtures_do() -> None:
    """The parity above is not vacuous: other mixtures give other exponents."""
    logw, means, covs, _ = _mixtures(0, B=4)
    e0 = rbb._equal_kl_on_mixture(logw, means, covs)
    means2 = means.copy()
    means2[:, 0] += 15.0
    assert not np.array_equal(rbb._equal_kl_on_mixture(logw, means2, covs), e0)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_chapter06_appendix_logpdf_matches_the_reference(seed: int) -> None:
    """Chapter 06 appendix's elementwise mixture log density and sigma-point fusion: the einsum code's numbers."""
    from fusion.book.chapters import chernoff_first_order as csf
    from fusion.book.chapters import chernoff_steps as cs
    from fusion.estimates.chernoff import first_order_fusion

    rng = np.random.default_rng(seed)
    for _ in range(20):
        a, b = csf.random_two_mixtures(rng)
        w = float(rng.uniform())
        fused = first_order_fusion([a, b], [w, 1 - w]).mixture  # up to 9 components
        x = rng.uniform(-9.0, 9.0, size=(int(rng.integers(1, 500)), 2))
        for g in (a, b, fused):
            np.testing.assert_array_equal(cs._logpdf(g, x), ref.mixture_logpdf_einsum(g, x))
        new, old = csf.sigma_point_first_order([a, b], [w, 1 - w]), ref.sigma_point_first_order([a, b], [w, 1 - w])
        assert new.log_z_first_order == old.log_z_first_order
        for u, v in ((new.mixture.weights, old.mixture.weights), (new.mixture.means, old.mixture.means),
                     (new.mixture.covs, old.mixture.covs)):
            np.testing.assert_array_equal(u, v)
    g = mx.GaussianMixture(np.array([0.0, 1.0]), np.zeros((2, 2)), np.stack([np.eye(2), 2.0 * np.eye(2)]))
    np.testing.assert_array_equal(cs._logpdf(g, x), ref.mixture_logpdf_einsum(g, x))  # a zero weight: skipped


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_simplex_newton_matches_the_reference_with_fewer_evaluations(seed: int) -> None:
    """The projected Newton method evaluates only the halved steps of unfinished problems: the same minimisers, bit
    for bit, on the study's importance-sampled objective and on step D's first-order normaliser."""
    from fusion.optimise.simplex import _simplex_newton

    logw, means, covs, rng = _mixtures(seed, B=12)
    B, N = logw.shape[:2]
    eps0 = np.full((B, N), 1.0 / N)
    wg, mug, Pg, _ = chm._first_order_arrays(logw, means, covs, eps0)
    xs = np.stack([chm._sample_mixture(wg[b], mug[b], np.linalg.cholesky(Pg[b]), rng, 400) for b in range(B)])
    lg, LT = chm._proposal_densities(logw, means, covs, wg, mug, Pg, xs)
    problems = {"importance sampling": chm._is_derivatives(LT, lg),
                "first order": lambda i, e: chm._first_order_log_normaliser_derivatives(logw[i], means[i], covs[i], e)}
    for name, fgh in problems.items():
        counts = {"new": 0, "old": 0}

        def counted(key: str):
            def f(idx: np.ndarray, e: np.ndarray):
                counts[key] += idx.size
                return fgh(idx, e)
            return f
        new = _simplex_newton(counted("new"), B, N)
        old = ref.simplex_newton(counted("old"), B, N)
        np.testing.assert_array_equal(new, old, err_msg=name)
        assert counts["new"] < counts["old"], name


def test_triu_cache_is_read_only() -> None:
    iu, ju, half = mx._triu(4)
    np.testing.assert_array_equal(np.stack([iu, ju]), np.stack(np.triu_indices(4)))
    np.testing.assert_array_equal(half, np.where(iu == ju, -0.5, -1.0))
    with pytest.raises(ValueError):
        iu[0] = 1


def _readings(seed: int, rows: int = 3000, n: int = 10) -> np.ndarray:
    """Thermocouple-like readings: 900 °C, noise of 0.5-2 °C, a few sensors biased by up to 10 °C."""
    rng = np.random.default_rng(seed)
    s = 900.0 + rng.normal(size=(rows, n)) * rng.uniform(0.5, 2.0, size=n)
    s[:, :2] += rng.choice([0.0, 3.0, 10.0], size=(rows, 1))
    s[:5] = 900.0  # identical readings: MAD 0
    return s


@pytest.mark.parametrize("order", ["C", "F"])
@pytest.mark.parametrize("seed", [0, 1])
def test_huber_and_biweight_match_the_reference(seed: int, order: str) -> None:
    from fusion.readings import robust
    s = np.asarray(_readings(seed), order=order)
    for c in (0.5, 1.345, 3.0):
        np.testing.assert_array_equal(robust._huber(s, c), ref.huber(s, c))
    for c in (2.0, 4.685):
        np.testing.assert_array_equal(robust._biweight(s, c), ref.biweight(s, c))
    idx = np.array([7, 3, 2999, 12])  # few rows (the iterations stop with the slowest row: another count)
    np.testing.assert_array_equal(robust._huber(s[idx], 1.345), ref.huber(s[idx], 1.345))
    np.testing.assert_array_equal(robust._biweight(s[idx], 4.685), ref.biweight(s[idx], 4.685))


@pytest.mark.parametrize("block", [1, 37, 2999, 3000])
def test_huber_and_biweight_in_row_blocks_match_the_reference(block: int, monkeypatch: pytest.MonkeyPatch) -> None:
    """The IRLS updates computed a block of rows at a time (the rows set aside included) are the reference's."""
    from fusion.readings import robust
    monkeypatch.setattr(robust, "_IRLS_BLOCK", block)
    s = _readings(3)
    np.testing.assert_array_equal(robust._huber(s, 1.345), ref.huber(s, 1.345))
    np.testing.assert_array_equal(robust._biweight(s, 4.685), ref.biweight(s, 4.685))
    np.testing.assert_array_equal(robust._huber(s, 1.345, iterations=3), ref.huber(s, 1.345, iterations=3))


def test_irls_sets_rows_aside_only_at_exact_fixed_points() -> None:
    """Few iterations: the rows still moving stop where the reference stops (not at their fixed point)."""
    from fusion.readings import robust
    s = _readings(2)
    for it in (1, 2, 5, 12):
        np.testing.assert_array_equal(robust._huber(s, 1.345, iterations=it), ref.huber(s, 1.345, iterations=it))
        np.testing.assert_array_equal(robust._biweight(s, 4.685, iterations=it),
                                      ref.biweight(s, 4.685, iterations=it))
    assert not np.array_equal(robust._huber(s, 1.345, iterations=1), robust._huber(s, 1.345))


def test_runs_stay_in_process_inside_a_pytest_xdist_worker(monkeypatch: pytest.MonkeyPatch) -> None:
    """Under pytest-xdist the study's worker processes are not started (the result does not depend on them)."""
    import dataclasses

    from fusion.scenarios import range_bearing as dist

    class NoPool:
        def __init__(self, *args: object, **kwargs: object) -> None:
            raise AssertionError("a process pool was started inside a pytest-xdist worker")

    sc = dataclasses.replace(dist.RangeBearingScenario(), frames=2, n_particles=50, n_samples=50, n_central=60,
                             em_iterations=2)
    def seeds() -> list[np.random.SeedSequence]:  # fresh: a SeedSequence counts the children it has spawned
        return np.random.SeedSequence(3).spawn(4)
    monkeypatch.setattr(dist, "RUN_BLOCK", 2)  # two blocks: two workers would share them
    monkeypatch.setattr(dist, "ProcessPoolExecutor", NoPool)
    monkeypatch.setenv("PYTEST_XDIST_WORKER", "gw0")
    inside = dist.run_tracking_batch(sc, seeds(), workers=2)
    monkeypatch.delenv("PYTEST_XDIST_WORKER")
    with pytest.raises(AssertionError, match="process pool"):
        dist.run_tracking_batch(sc, seeds(), workers=2)
    alone = dist.run_tracking_batch(sc, seeds(), workers=1)
    for a, b in zip(inside, alone):
        np.testing.assert_array_equal(a.estimates["chernoff_pso"], b.estimates["chernoff_pso"])


def _is_problem(seed: int, B: int = 5, N: int = 3, R: int = 400, m: int = 20):
    """Log densities (B, N, R), proposal log densities (B, R) of tracking-like scales, and swarm rows (B, m, N)."""
    rng = np.random.default_rng(seed)
    lg = -8.0 - np.abs(rng.normal(scale=3.0, size=(B, R)))
    LT = lg[:, None, :] + rng.normal(scale=2.0, size=(B, N, R)) - rng.uniform(0.0, 30.0, size=(B, N, 1))
    E = rng.dirichlet(np.ones(N), size=(B, m))
    E[0, 0] = np.eye(N)[0]  # a vertex of the simplex
    return LT, lg, E


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_is_values_equal_the_reference_to_round_off(seed: int) -> None:
    """The swarm objective shifted by the bound sum_i eps_i M_i gives the per-row-maximum reference's values to
    round-off (its shift differs, so its last bits may), and the same values alone, blocked, or with ``out``."""
    LT, lg, E = _is_problem(seed)
    old = ref.is_values(np.concatenate([LT, -lg[:, None, :]], axis=1), E)
    LTg = chm._augmented(LT, lg)
    new = chm._is_values(LTg, E)
    np.testing.assert_allclose(new, old, rtol=1e-13, atol=0.0)
    work = np.empty(E.shape[:2] + (LT.shape[-1],))
    np.testing.assert_array_equal(chm._is_values(LTg, E, work, chm._is_bounds(LTg)), new)
    for b in range(E.shape[0]):  # a problem's values do not depend on the others
        np.testing.assert_array_equal(chm._is_values(LTg[b], E[b]), new[b])
        np.testing.assert_array_equal(chm._is_values(LTg[b:b + 2], E[b:b + 2])[0], new[b])


def test_is_values_fall_back_where_the_bound_is_far_above_the_largest_weight() -> None:
    """Where the bound exceeds a row's largest log weight by more than the exponential's range (the nodes' maxima at
    different samples), or the exponents leave the simplex, the row is shifted by its own maximum: the reference's
    value, finite, not -inf or NaN."""
    R = 6
    LT = np.full((1, 2, R), -1e4)
    LT[0, 0, 0] = LT[0, 1, 1] = 0.0  # node 1 peaks at sample 0, node 2 at sample 1: the bound is 0, the weights -5e3
    lg = np.zeros((1, R))
    E = np.array([[[0.5, 0.5], [1.0, 0.0], [1.5, -0.5]]])  # an interior point, a vertex, a point off the simplex
    old = ref.is_values(np.concatenate([LT, -lg[:, None, :]], axis=1), E)
    new = chm._is_values(chm._augmented(LT, lg), E)
    assert np.all(np.isfinite(new))
    np.testing.assert_allclose(new, old, rtol=1e-13, atol=0.0)


@pytest.mark.parametrize("seed", [0, 1])
def test_mixture_logpdf_bounded_equals_the_per_point_maximum_to_round_off(seed: int) -> None:
    """The proposal's log density shifted by the bound max_k(log w_k + max log N_k) (27 components, as the product of
    three 3-component nodes) equals the per-point-maximum kernel's to 1e-13 relative, points far from every
    component (fallback) included, dead components included; a problem's values do not depend on the others."""
    rng = np.random.default_rng(seed)
    B, M, d, Q = 3, 27, 4, 500
    logw = np.log(rng.dirichlet(np.ones(M), size=B))
    logw[0, 5] = -np.inf  # a dead component
    means = rng.standard_normal((B, M, d)) * 20.0
    a = rng.standard_normal((B, M, d, d))
    covs = np.matmul(a, np.swapaxes(a, -1, -2)) + 4.0 * np.eye(d)
    x = rng.standard_normal((B, Q, d)) * 25.0
    x[:, :3] = 1e4  # far from every component: the bound-shifted sum underflows
    phi = mx._features(x)
    old = mx._mixture_logpdf_features(logw, means, covs, phi)
    new = mx._mixture_logpdf_bounded(logw, means, covs, phi)
    assert np.all(np.isfinite(new))
    np.testing.assert_allclose(new, old, rtol=1e-13, atol=0.0)
    for b in range(B):
        np.testing.assert_array_equal(mx._mixture_logpdf_bounded(logw[b:b + 1], means[b:b + 1], covs[b:b + 1],
                                                                 phi[b:b + 1])[0], new[b])


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_first_order_and_gaussian_newton_with_prepared_terms_match_the_reference(seed: int) -> None:
    """Step D's first-order normaliser and the Gaussian Chernoff criterion with their exponent-free terms computed once
    per search: the derivatives at any exponents and subset of problems, and the minimisers, bit for bit as when every
    evaluation starts from the mixtures."""
    from fusion.estimates.chernoff import gaussian as chg

    logw, means, covs, rng = _mixtures(seed, B=12)
    B, N = logw.shape[:2]
    eps = rng.dirichlet(np.ones(N), size=B)
    idx = np.array([7, 0, 3, 11])
    prep = chm._first_order_derivatives_prepare(logw, means, covs)
    for i in (np.arange(B), idx):
        new = chm._first_order_derivatives_prepared(tuple(a[i] for a in prep), eps[i])
        old = ref.first_order_log_normaliser_derivatives(logw[i], means[i], covs[i], eps[i])
        for u, v in zip(new, old):
            np.testing.assert_array_equal(u, v)
    np.testing.assert_array_equal(chm._first_order_minimum(logw, means, covs), ref.first_order_minimum(logw, means, covs))
    m, P = means[:, :, 0], covs[:, :, 0]
    infos, logdets = np.linalg.inv(P), np.linalg.slogdet(2 * np.pi * P)[1]
    for u, v in zip(chg._chernoff_derivatives(m, infos, logdets, eps), ref.chernoff_derivatives(m, infos, logdets, eps)):
        np.testing.assert_array_equal(u, v)
    np.testing.assert_array_equal(chg._gaussian_chernoff_batch(m, infos, logdets),
                                  ref.gaussian_chernoff_batch(m, infos, logdets))
