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
