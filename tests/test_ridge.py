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


# --------------------------------------------------------------------------- issue 18: plug-in ridge
def test_plugin_scalar_closed_form_and_batches() -> None:
    from fusion.readings import biased as rg

    rng = np.random.default_rng(5)
    y = 0.7 + rng.normal(size=(6, 50))
    f = rg.plugin_ridge(np.ones(6), y, sigma=1.0)
    yb = y.mean(axis=0)
    np.testing.assert_allclose(f.x[0], yb * 6 * yb**2 / (6 * yb**2 + 1.0), rtol=1e-12)
    np.testing.assert_allclose(f.k, 1.0 / yb**2, rtol=1e-12)
    one = rg.plugin_ridge(np.ones(6), y[:, 3])
    s2 = y[:, 3].var(ddof=1)
    np.testing.assert_allclose(one.x, [yb[3] * 6 * yb[3] ** 2 / (6 * yb[3] ** 2 + s2)], rtol=1e-12)
    # an exact zero LS estimate gives k = inf and the estimate 0
    z = rg.plugin_ridge(np.ones(2), np.array([1.0, -1.0]), sigma=1.0)
    assert np.isinf(z.k) and z.x[0] == 0.0
    with pytest.raises(ValueError, match="sigma"):
        rg.plugin_ridge(np.ones(1), np.array([1.0]))


def test_plugin_fusion_centralised_vs_distributed() -> None:
    from fusion.readings import biased as rg

    rng = np.random.default_rng(6)
    Hs = [rng.normal(size=(3, 2)) for _ in range(3)]
    Rs = [np.eye(3) * s for s in (1.0, 2.0, 0.5)]
    ys = [H @ np.array([1.0, -0.5])[:, None] + rng.normal(size=(3, 7)) for H in Hs]
    cen = rg.ridge_fusion_plugin(Hs, Rs, ys, "centralised")
    dis = rg.ridge_fusion_plugin(Hs, Rs, ys, "distributed")
    for r in range(7):
        k = float(cen.k[r])
        np.testing.assert_allclose(cen.x[:, r], rg.ridge_centralised(Hs, Rs, [y[:, r] for y in ys], k), rtol=1e-9)
    # distributed shrinkage is a different estimator (not the centralised one)
    assert np.max(np.abs(dis.x - cen.x)) > 1e-6
    with pytest.raises(ValueError, match="where"):
        rg.ridge_fusion_plugin(Hs, Rs, ys, "local")
    with pytest.raises(ValueError, match="Hs"):
        rg.ridge_fusion_plugin([np.ones((3, 2))] + Hs[1:], Rs, ys, "distributed")


def test_plugin_study_helps_near_zero_and_hurts_in_between() -> None:
    from fusion.scenarios import ridge_sensors as rs

    s = rs.plugin_study(xs=(0.0, 1.0), runs=3000, curve=(0.0, 1.0, 20.0), curve_runs=3000)
    assert s["sq"][0.0]["plug-in (known σ)"].mean() < s["sq"][0.0]["LS"].mean()
    assert s["sq"][1.0]["plug-in (known σ)"].mean() > s["sq"][1.0]["LS"].mean()
    assert s["ratio_known"][-1] == pytest.approx(1.0, abs=0.02)
    v = rs.vector_study(runs=300, scales=(3.0,))
    assert v["cond"] > 100
    e = v["sq"]["strong direction", 3.0]
    assert e["centralised ridge"].mean() < e["LS"].mean()
