"""Covariance intersection: consistency for every cross-correlation, optimality, bad input."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from fusion.estimates.ci import ci_objective, covariance_intersection


def _spd(rng: np.random.Generator, n: int) -> np.ndarray:
    A = rng.standard_normal((n, n))
    return A @ A.T + 0.1 * np.eye(n)


@given(seed=st.integers(0, 2**32 - 1), n=st.integers(1, 4), rho=st.floats(-0.99, 0.99))
def test_ci_is_consistent_for_every_cross_correlation(seed: int, n: int, rho: float) -> None:
    """P_CI - E[e e^T] is positive semidefinite whatever the cross-covariance P12."""
    rng = np.random.default_rng(seed)
    P1, P2 = _spd(rng, n), _spd(rng, n)
    L1, L2 = np.linalg.cholesky(P1), np.linalg.cholesky(P2)
    # a valid cross-covariance: P12 = rho * L1 Q L2^T with Q orthogonal
    Q, _ = np.linalg.qr(rng.standard_normal((n, n)))
    P12 = rho * L1 @ Q @ L2.T
    for omega in (None, 0.0, 0.3, 0.7, 1.0):
        res = covariance_intersection(np.zeros(n), P1, np.zeros(n), P2, omega=omega)
        I1, I2 = np.linalg.inv(P1), np.linalg.inv(P2)
        K1 = res.P @ (res.omega * I1)
        K2 = res.P @ ((1 - res.omega) * I2)
        true = K1 @ P1 @ K1.T + K2 @ P2 @ K2.T + K1 @ P12 @ K2.T + K2 @ P12.T @ K1.T
        assert np.linalg.eigvalsh(res.P - true).min() >= -1e-9 * np.trace(res.P)


@given(seed=st.integers(0, 2**32 - 1), n=st.integers(1, 4))
def test_optimal_omega_minimises_the_criterion(seed: int, n: int) -> None:
    rng = np.random.default_rng(seed)
    P1, P2 = _spd(rng, n), _spd(rng, n)
    for criterion in ("trace", "det"):
        res = covariance_intersection(np.zeros(n), P1, np.ones(n), P2, criterion=criterion)
        best = ci_objective(res.omega, P1, P2, criterion)
        grid = [ci_objective(w, P1, P2, criterion) for w in np.linspace(0, 1, 101)]
        assert best <= min(grid) + 1e-7 * (1 + abs(min(grid)))


def test_scalar_ci_with_equal_variances_is_the_midpoint() -> None:
    res = covariance_intersection(1.0, 2.0, 3.0, 2.0, omega=0.5)
    assert res.x[0] == pytest.approx(2.0)
    assert res.P[0, 0] == pytest.approx(2.0)


def test_end_points_return_an_input() -> None:
    P1 = np.diag([1.0, 4.0])
    P2 = np.diag([2.0, 0.5])
    res = covariance_intersection([1.0, 2.0], P1, [3.0, 5.0], P2, omega=1.0)
    np.testing.assert_allclose(res.x, [1.0, 2.0])
    np.testing.assert_allclose(res.P, P1)


def test_dominating_estimate_gets_all_the_weight() -> None:
    res = covariance_intersection([0.0], [[1.0]], [5.0], [[100.0]])
    assert res.omega == 1.0
    assert res.x[0] == 0.0


@pytest.mark.parametrize(
    "args, message",
    [
        (([0.0, 0.0], np.eye(2), [0.0], np.eye(1)), "same shape"),
        (([0.0, np.nan], np.eye(2), [0.0, 0.0], np.eye(2)), "NaN"),
        (([0.0, 0.0], [[1.0, 0.5], [0.0, 1.0]], [0.0, 0.0], np.eye(2)), "symmetric"),
        (([0.0, 0.0], [[1.0, 2.0], [2.0, 1.0]], [0.0, 0.0], np.eye(2)), "positive definite"),
        (([0.0, 0.0], np.zeros((2, 2)), [0.0, 0.0], np.eye(2)), "positive definite"),
        (([0.0, 0.0], np.eye(3), [0.0, 0.0], np.eye(2)), "2x2"),
    ],
)
def test_bad_input_raises(args: tuple, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        covariance_intersection(*args)


def test_bad_omega_and_criterion_raise() -> None:
    with pytest.raises(ValueError, match="omega"):
        covariance_intersection(0.0, 1.0, 1.0, 1.0, omega=1.5)
    with pytest.raises(ValueError, match="criterion"):
        covariance_intersection(0.0, 1.0, 1.0, 1.0, criterion="max")


def test_nees_matches_the_quadratic_form_and_rejects_bad_covariances() -> None:
    from fusion import filtering as tr
    from fusion.scenarios import two_sensor

    rng = np.random.default_rng(21)
    A = rng.normal(size=(5, 3, 3))
    P = A @ np.swapaxes(A, 1, 2) + np.eye(3)
    e = rng.normal(size=(4, 5, 3))
    want = np.einsum("rki,kij,rkj->rk", e, np.linalg.inv(P), e)
    np.testing.assert_allclose(tr.nees(e, P), want, rtol=1e-10)
    with pytest.raises(ValueError, match="positive definite"):
        tr.nees(e, -P)
    with pytest.raises(ValueError, match="finite"):
        tr.nees(np.full((5, 3), np.nan), P)
    with pytest.raises(ValueError, match="match"):
        tr.nees(e, P[:, :2, :2])


@given(seed=st.integers(0, 2**32 - 1), n=st.integers(1, 5))
def test_closed_form_weight_matches_a_dense_grid_and_the_reduced_objective(seed: int, n: int) -> None:
    """ci_weight (generalised eigenvalues + root of the slope) against brute force on the matrices."""
    from fusion.estimates.ci import ci_weight

    rng = np.random.default_rng(seed)
    P1, P2 = _spd(rng, n), _spd(rng, n)
    grid = np.linspace(0.0, 1.0, 2001)
    for criterion in ("trace", "det"):
        w = ci_weight(P1, P2, criterion)
        values = ci_objective(grid, P1, P2, criterion)
        assert 0.0 <= w <= 1.0
        assert ci_objective(w, P1, P2, criterion) <= values.min() + 1e-9 * (1 + abs(values.min()))
        assert abs(w - grid[np.argmin(values)]) <= 1e-3 + 1e-9


def test_vectorised_objective_equals_the_scalar_one() -> None:
    rng = np.random.default_rng(5)
    P1, P2 = _spd(rng, 3), _spd(rng, 3)
    ws = np.array([0.0, 0.2, 0.9, 1.0])
    for criterion in ("trace", "det"):
        many = ci_objective(ws, P1, P2, criterion)
        assert many.shape == ws.shape
        np.testing.assert_allclose(many, [ci_objective(float(w), P1, P2, criterion) for w in ws], rtol=1e-12)
    with pytest.raises(ValueError, match="omega"):
        ci_objective(np.array([0.5, np.nan]), P1, P2)


def test_equal_covariances_give_the_symmetric_weight() -> None:
    """P1 = P2: the criterion is flat, the documented answer is omega = 0.5 (and the midpoint)."""
    from fusion.estimates.ci import ci_weight

    P = np.diag([2.0, 3.0, 1.0, 5.0])
    assert ci_weight(P, P) == 0.5 and ci_weight(P, P, "det") == 0.5
    res = covariance_intersection(np.zeros(4), P, 2 * np.ones(4), P)
    np.testing.assert_allclose(res.x, np.ones(4))
    np.testing.assert_allclose(res.P, P)


def test_fuzzy_cluster_fusion_keeps_the_consistent_majority() -> None:
    from fusion.estimates.fuzzy_cluster import fuzzy_cluster_fusion

    P = np.stack([np.eye(2)] * 3)
    res = fuzzy_cluster_fusion([[0.0, 0.0], [0.5, 0.0], [30.0, 30.0]], P)
    np.testing.assert_array_equal(res.members, [True, True, False])
    np.testing.assert_allclose(res.x, [0.25, 0.0])
    # the similarity is a fuzzy equivalence: reflexive, symmetric, max-min transitive
    R = res.similarity
    np.testing.assert_allclose(np.diag(R), 1.0)
    np.testing.assert_allclose(R, R.T)
    assert np.all(np.max(np.minimum(R[:, :, None], R[None, :, :]), axis=1) <= R + 1e-15)


@given(seed=st.integers(0, 2**32 - 1), N=st.integers(1, 5), n=st.integers(1, 3))
def test_fuzzy_cluster_fusion_is_a_convex_combination_of_the_estimates(seed: int, N: int, n: int) -> None:
    from fusion.estimates.fuzzy_cluster import fuzzy_cluster_fusion

    rng = np.random.default_rng(seed)
    xs = rng.normal(scale=3.0, size=(4, N, n))
    Ps = np.stack([_spd(rng, n) for _ in range(N)])
    res = fuzzy_cluster_fusion(xs, Ps)
    assert res.x.shape == (4, n) and res.members.any(axis=-1).all()
    lo, hi = xs.min(axis=1), xs.max(axis=1)
    assert np.all(res.x >= lo - 1e-12) and np.all(res.x <= hi + 1e-12)
    want = np.einsum("ri,ria->ra", res.members, xs) / res.members.sum(axis=1, keepdims=True)
    np.testing.assert_allclose(res.x, want)
    if N == 1:
        np.testing.assert_allclose(res.x, xs[:, 0])


def test_fuzzy_cluster_fusion_rejects_bad_input() -> None:
    from fusion.estimates.fuzzy_cluster import fuzzy_cluster_fusion

    P = np.stack([np.eye(2)] * 2)
    with pytest.raises(ValueError, match="Ps must have shape"):
        fuzzy_cluster_fusion(np.zeros((2, 2)), np.stack([np.eye(2)] * 3))
    with pytest.raises(ValueError, match="finite"):
        fuzzy_cluster_fusion([[0.0, np.nan], [0.0, 0.0]], P)
    with pytest.raises(ValueError, match="positive definite"):
        fuzzy_cluster_fusion(np.zeros((2, 2)), np.stack([np.eye(2), -np.eye(2)]))
    with pytest.raises(ValueError, match="level"):
        fuzzy_cluster_fusion(np.zeros((2, 2)), P, level=1.0)
    with pytest.raises(ValueError, match="shape"):
        fuzzy_cluster_fusion(np.zeros(2), P)


def test_rmse_per_step_accepts_one_truth_per_run() -> None:
    from fusion.filtering.kalman import rmse_per_step

    rng = np.random.default_rng(5)
    truth = rng.normal(size=(6, 5, 2))
    est = truth + 2.0
    np.testing.assert_allclose(rmse_per_step(est, truth), np.full((5, 2), 2.0))
    np.testing.assert_allclose(rmse_per_step(est - truth, np.zeros((5, 2))), np.full((5, 2), 2.0))
    with pytest.raises(ValueError, match="truth"):
        rmse_per_step(est, truth[:, :4])
