"""Source 003 sec. 2.5: ridge (biased) estimation fusion."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from fusion.readings import biased as rg


def _setup(seed: int = 0):
    rng = np.random.default_rng(seed)
    Hs = [rng.normal(size=(4, 2)) for _ in range(3)]
    Rs = []
    for _ in range(3):
        A = rng.normal(size=(4, 4))
        Rs.append(A @ A.T + 4 * np.eye(4))
    ys = [rng.normal(size=4) for _ in range(3)]
    return Hs, Rs, ys


def test_k_zero_is_least_squares() -> None:
    rng = np.random.default_rng(1)
    H = rng.normal(size=(10, 3))
    y = rng.normal(size=10)
    np.testing.assert_allclose(rg.ridge(H, y, 0.0), np.linalg.lstsq(H, y, rcond=None)[0], rtol=1e-12)
    assert rg.least_squares(np.ones(5), np.arange(5.0))[0] == pytest.approx(2.0, rel=1e-14)


@given(st.floats(0, 10))
def test_centralised_equals_distributed(k: float) -> None:
    Hs, Rs, ys = _setup()
    np.testing.assert_allclose(rg.ridge_centralised(Hs, Rs, ys, k), rg.ridge_distributed(Hs, Rs, ys, k), rtol=1e-9, atol=1e-12)


def test_scalar_moments_against_monte_carlo_and_optimal_k() -> None:
    m, sigma, x, k = 5, 1.0, 1.0, 2.0
    rng = np.random.default_rng(2)
    est = (x + rng.normal(size=(200_000, m))).sum(axis=1) / (m + k)
    mom = rg.scalar_ridge_moments(m, sigma, x, k)
    b, s, mse = mom.bias, mom.sd, mom.mse
    assert np.mean(est - x) == pytest.approx(b, abs=4 * s / np.sqrt(2e5))
    assert np.mean((est - x) ** 2) == pytest.approx(mse, rel=0.01)
    ks = np.linspace(0, 5, 5001)
    kstar = rg.optimal_ridge_k(sigma, x)
    assert ks[np.argmin(rg.scalar_ridge_moments(m, sigma, x, ks).mse)] == pytest.approx(kstar, abs=1e-3)


def test_ridge_beats_ls_only_below_the_derived_bound() -> None:
    m, sigma, k = 5, 1.0, 1.0
    bound = np.sqrt(sigma**2 * (2 * m + k) / (k * m))
    for x, better in ((0.9 * bound, True), (1.1 * bound, False)):
        mse_r = rg.scalar_ridge_moments(m, sigma, x, k).mse
        mse_ls = rg.scalar_ridge_moments(m, sigma, x, 0.0).mse
        assert bool(mse_r < mse_ls) is better


def test_reliability_of_unbiased_estimate() -> None:
    assert float(rg.reliability(0.0, 1.0, 1.96)) == pytest.approx(0.95, abs=1e-3)


def test_bad_input() -> None:
    with pytest.raises(ValueError, match="k must"):
        rg.ridge(np.ones(3), np.ones(3), -1)
    with pytest.raises(ValueError, match="singular"):
        rg.ridge(np.ones((3, 2)), np.ones(3), 0.0)
    Hs, Rs, ys = _setup()
    Rs[0] = -Rs[0]
    with pytest.raises(ValueError, match="positive definite"):
        rg.ridge_centralised(Hs, Rs, ys, 1.0)
