"""Source 003 sec. 2.7: GLS (Markov) estimate and LDL^T pseudo-measurement fusion."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from fusion.readings import correlated as co


def _R(seed: int, n: int = 6) -> np.ndarray:
    A = np.random.default_rng(seed).normal(size=(n, n))
    return A @ A.T + n * np.eye(n)


@given(st.integers(0, 10_000), st.integers(1, 9))
def test_recursion_inverse_and_diagonalisation(seed: int, n: int) -> None:
    R = _R(seed, n)
    ldl = co.ldl_unpivoted(R)
    L, d = ldl.L, ldl.d
    M = co.unit_lower_inverse(L)
    np.testing.assert_allclose(M, np.linalg.inv(L), rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(L @ np.diag(d) @ L.T, R, rtol=1e-12, atol=1e-12 * np.abs(R).max())
    D = M @ R @ M.T
    off = D - np.diag(np.diag(D))
    assert np.abs(off).max() <= 1e-12 * np.abs(R).max()
    np.testing.assert_allclose(np.diag(D), d, rtol=1e-10)


@given(st.integers(0, 10_000))
def test_pseudo_measurement_fusion_equals_gls(seed: int) -> None:
    rng = np.random.default_rng(seed)
    H = rng.normal(size=(6, 2))
    R = _R(seed)
    z = rng.normal(size=(6, 3))
    g, p = co.gls(H, R, z), co.pseudo_measurement_fusion(H, R, z)
    x1, P1, x2, P2 = g.x, g.P, p.x, p.P
    np.testing.assert_allclose(x2, x1, rtol=1e-9, atol=1e-12 * np.abs(x1).max())
    np.testing.assert_allclose(P2, P1, rtol=1e-9)


def test_mc_error_matches_trace_P_and_naive_is_worse() -> None:
    rng = np.random.default_rng(7)
    sig, se = np.array([1.0, 2.0, 3.0]), 1.5
    R = np.kron(np.diag(sig**2), np.eye(2)) + se**2 * np.kron(np.ones((3, 3)), np.eye(2))
    H = np.kron(np.ones((3, 1)), np.eye(2))
    runs = 20_000
    v = np.linalg.cholesky(R) @ rng.normal(size=(6, runs))
    est = co.gls(H, R, H @ np.array([1.0, -2.0])[:, None] + v)
    x, P = est.x, est.P
    err = x - np.array([1.0, -2.0])[:, None]
    mse = np.mean(np.sum(err**2, axis=0))
    assert mse == pytest.approx(np.trace(P), rel=4 * np.sqrt(2 / runs) * 1.5)
    xn = co.naive_fusion(H, R, H @ np.array([1.0, -2.0])[:, None] + v, block=2).x
    assert np.mean(np.sum((xn - np.array([1.0, -2.0])[:, None]) ** 2, axis=0)) >= mse


def test_bad_input() -> None:
    with pytest.raises(ValueError, match="positive definite"):
        co.gls(np.eye(2), -np.eye(2), np.ones(2))
    with pytest.raises(ValueError, match="unit lower"):
        co.unit_lower_inverse(2 * np.eye(3))
    with pytest.raises(ValueError, match="full column rank"):
        co.gls(np.ones((3, 2)), np.eye(3), np.ones(3))
    with pytest.raises(ValueError, match="block"):
        co.naive_fusion(np.eye(3), np.eye(3), np.ones(3), block=2)


# --------------------------------------------------------------------------- issue 18: eigen route, weights, cases
@given(st.integers(0, 10_000))
def test_eigen_decorrelation_equals_gls(seed: int) -> None:
    rng = np.random.default_rng(seed)
    H = rng.normal(size=(6, 2))
    R = _R(seed)
    z = rng.normal(size=(6, 3))
    g, e = co.gls(H, R, z), co.eigen_decorrelation_fusion(H, R, z)
    np.testing.assert_allclose(e.x, g.x, rtol=1e-8, atol=1e-11 * np.abs(g.x).max())
    np.testing.assert_allclose(e.P, g.P, rtol=1e-8)


@given(st.integers(0, 10_000))
def test_gls_weights_reproduce_the_estimate_and_are_unbiased(seed: int) -> None:
    rng = np.random.default_rng(seed)
    H = rng.normal(size=(6, 2))
    R = _R(seed)
    z = rng.normal(size=6)
    K = co.gls_weights(H, R)
    np.testing.assert_allclose(K @ H, np.eye(2), atol=1e-9)
    np.testing.assert_allclose(K @ z, co.gls(H, R, z).x, rtol=1e-8, atol=1e-10)


def test_gls_weight_is_negative_exactly_when_the_two_sensor_formula_says_so() -> None:
    # two scalar sensors with correlation rho: w2 ∝ s1² − rho s1 s2, negative iff rho s2 > s1
    s1, s2 = 1.0, 2.0
    for rho in (0.3, 0.49, 0.51, 0.9):
        R = np.array([[s1**2, rho * s1 * s2], [rho * s1 * s2, s2**2]])
        w = co.gls_weights(np.ones((2, 1)), R)[0]
        assert w.sum() == pytest.approx(1.0)
        assert (w[1] < 0) == (rho * s2 > s1)


def test_operation_counts_new_model() -> None:
    c = co.operation_counts(6, 2)
    # explicit: 2N³ + 4N²d + 2Nd² + d³; Cholesky: N³/3 + 2N²d + ...; LDL: N³/3 + N²(d+1) + ...; eigen 9N³ + 2N²(d+1) + ...
    assert c == {"explicit": 776.0, "cholesky": 272.0, "ldl": 236.0, "eigen": 2216.0}
    big = co.operation_counts(10**5, 2)
    assert big["eigen"] / big["ldl"] == pytest.approx(27.0, rel=1e-3)


def test_coupling_cases_naive_cost_and_negative_weights() -> None:
    from fusion.scenarios import correlated_sensors as cs

    s = cs.coupling_study(runs=400, env_grid=(0.0, 1.0, 3.0))
    rows = {r["case"]: r for r in s.rows}
    for r in rows.values():
        # Gauss-Markov: the naive weights can never beat GLS in exact MSE
        assert r["exact MSE naive"] >= r["exact MSE GLS"] * (1 - 1e-12)
        assert r["LDLᵀ vs GLS"] < 1e-12 and r["eigen vs GLS"] < 1e-12
    C = cs.CouplingCase
    assert rows[C.EQUAL]["min GLS weight"] > 0
    assert rows[C.UNEQUAL]["min GLS weight"] < 0
    assert rows[C.TWO_SENSORS]["naive / GLS"] > 5
    # with no environment R is diagonal: naive = GLS
    for c in s.curves.values():
        assert c[0] == pytest.approx(1.0)
    # the exact MSE agrees with Monte Carlo
    for name, (sg, _) in s.sq.items():
        assert sg.mean() == pytest.approx(rows[name]["exact MSE GLS"], rel=6 * np.sqrt(2 / 400))
    with pytest.raises(ValueError, match="coupling"):
        cs.covariance((1.0, 2.0), (1.0,), 1.0)
    with pytest.raises(ValueError, match="own"):
        cs.covariance((1.0, -2.0), (1.0, 1.0), 1.0)


# --------------------------------------------------------------------------- review of chapter 04: §2.7 side claims
@given(st.integers(0, 10_000), st.integers(1, 8))
def test_lecture_recurrences_give_the_unique_ldl(seed: int, n: int) -> None:
    R = _R(seed, n)
    a, b = co.ldl_recurrences(R), co.ldl_unpivoted(R)
    np.testing.assert_allclose(a.L, b.L, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(a.d, b.d, rtol=1e-10)
    assert np.all(a.d > 0)


@given(st.integers(0, 10_000))
def test_lagrange_matrix_weights_are_the_markov_weights(seed: int) -> None:
    rng = np.random.default_rng(seed)
    H = rng.normal(size=(6, 2))
    R = _R(seed)
    W = co.lagrange_weights(H, R)
    np.testing.assert_allclose(W, co.gls_weights(H, R), rtol=1e-8, atol=1e-10)
    np.testing.assert_allclose(W @ H, np.eye(2), atol=1e-10)


def test_gauss_markov_gap_is_non_negative_and_sees_a_worse_reference() -> None:
    H = np.kron(np.ones((3, 1)), np.eye(2))
    R = _R(3)
    assert co.gauss_markov_gap(H, R, np.random.default_rng(0), 100) > -1e-12
    # the gap is the excess of a random unbiased estimator: never below zero, usually well above
    assert co.gauss_markov_gap(H, R, np.random.default_rng(1), 1) > 0
    with pytest.raises(TypeError, match="rng"):
        co.gauss_markov_gap(H, R, 1, 10)  # type: ignore[arg-type]


def test_spd_inverse_count_is_between_the_cholesky_solve_and_the_lu_inverse() -> None:
    for N in (6, 60, 600):
        oc = co.operation_counts(N, 2)
        spd = co.spd_inverse_count(N, 2)
        assert oc["cholesky"] < spd < oc["explicit"]
    oc = co.operation_counts(600, 2)
    assert co.spd_inverse_count(600, 2) / oc["ldl"] == pytest.approx(3.0, abs=0.02)
    assert co.spd_inverse_count(600, 2) / co.ldl_as_written_count(600, 2) == pytest.approx(1.5, abs=0.02)


def test_estimated_covariance_never_beats_the_true_one_and_costs_less_with_more_samples() -> None:
    from fusion.scenarios import correlated_sensors as cs

    e = cs.estimated_covariance_study(ns=(10, 200), reps=200)
    for r in e.rows:
        # an estimated R never beats the true one (Gauss-Markov); more calibration samples cost less
        assert r["GLS(R̂, 10) / GLS"] > r["GLS(R̂, 200) / GLS"] > 1.0
        assert r["misstated / GLS"] >= 1.0
        for n in (10, 200):
            assert r[f"naive / GLS(R̂, {n})"] == pytest.approx(r["naive / GLS"] / r[f"GLS(R̂, {n}) / GLS"])
    with pytest.raises(ValueError, match="ns"):
        cs.estimated_covariance_study(ns=(3,), reps=5)


def test_unbounded_ratio_needs_every_sensor_coupled_and_unequal_couplings() -> None:
    from fusion.scenarios import correlated_sensors as cs

    s = cs.coupling_study(runs=50, env_grid=(0.0, 1.0), env_far=1000.0)
    far = s.far
    C = cs.CouplingCase
    assert far[C.EQUAL] < 1.01 and far[C.ONE_OUTSIDE] < 1.01
    for name in (C.UNEQUAL, C.UNEQUAL_STRONG, C.TWO_SENSORS):
        assert far[name] > 1e5


# --------------------------------------------------------------------------- second review: Lagrange scalar weights, structured GLS
def test_scalar_lagrange_weights_are_the_best_scalar_weights_and_reach_gls_only_when_the_problem_splits() -> None:
    from fusion.scenarios import correlated_sensors as cs

    H = np.kron(np.ones((3, 1)), np.eye(2))
    Rs = np.diag([1.0, 4.0, 9.0]) + 2.25
    W = co.scalar_lagrange_weights(np.kron(Rs, np.eye(2)), 2)
    np.testing.assert_allclose(W, co.gls_weights(H, np.kron(Rs, np.eye(2))), atol=1e-12)
    R = cs.oriented_covariance()
    assert not np.allclose(R[:2, :2], R[0, 0] * np.eye(2))           # the blocks are not multiples of I
    W = co.scalar_lagrange_weights(R, 2)
    np.testing.assert_allclose(W @ H, np.eye(2), atol=1e-12)        # unbiased
    mse = float(np.trace(W @ R @ W.T))
    K = co.gls_weights(H, R)
    assert mse > float(np.trace(K @ R @ K.T)) * (1 + 1e-6)
    # no other scalar weights summing to one do better
    rng = np.random.default_rng(0)
    for _ in range(200):
        w = W[0, ::2] + 0.1 * rng.normal(size=3)
        w = w / w.sum()
        Ww = np.kron(w[None, :], np.eye(2))
        assert float(np.trace(Ww @ R @ Ww.T)) >= mse - 1e-12
    with pytest.raises(ValueError, match="multiple of d"):
        co.scalar_lagrange_weights(np.eye(5), 2)


@given(st.integers(0, 10_000))
def test_gls_low_rank_equals_gls(seed: int) -> None:
    rng = np.random.default_rng(seed)
    N, d, r = 7, 2, 2
    H = rng.normal(size=(N, d))
    D = rng.uniform(0.5, 3.0, N)
    U = rng.normal(size=(N, r))
    z = rng.normal(size=(N, 3))
    a, b = co.gls_low_rank(H, D, U, z), co.gls(H, np.diag(D) + U @ U.T, z)
    np.testing.assert_allclose(a.x, b.x, rtol=1e-9, atol=1e-10)
    np.testing.assert_allclose(a.P, b.P, rtol=1e-9, atol=1e-12)
    assert co.low_rank_count(600, 2, 2) < co.operation_counts(600, 2)["ldl"] / 1000


def test_estimated_covariance_naive_with_the_calibration_variances() -> None:
    from fusion.scenarios import correlated_sensors as cs

    case = {"c": {"own": (1.0, 2.0, 3.0), "coupling": (1.0, 1.5, 2.0), "env": 1.0}}
    e = cs.estimated_covariance_study(scenarios=case, ns=(8,), reps=50, seed=4)
    # the same calibration draws, recomputed by hand
    R = cs.covariance(**case["c"])
    C = np.linalg.cholesky(R)
    E = C[None] @ np.random.default_rng(4).normal(size=(50, 3, 8))
    Rh = E @ np.swapaxes(E, 1, 2) / 8
    w = np.linalg.solve(Rh, np.ones((50, 3, 1)))[..., 0]
    K = w / w.sum(1, keepdims=True)
    dv = 1 / np.diagonal(Rh, axis1=1, axis2=2)
    Kn = dv / dv.sum(1, keepdims=True)
    mg = np.einsum("ri,ij,rj->r", K, R, K)
    mn = np.einsum("ri,ij,rj->r", Kn, R, Kn)
    r = e.rows[0]
    assert r["naive(R̂, 8) / GLS(R̂, 8)"] == pytest.approx(mn.mean() / mg.mean(), rel=1e-12)
    # both are linear unbiased fusions: by Gauss-Markov neither beats GLS with the true R, run by run
    gls = float(1 / (np.ones(3) @ np.linalg.solve(R, np.ones(3))))
    assert np.all(mg >= gls - 1e-12) and np.all(mn >= gls - 1e-12)
