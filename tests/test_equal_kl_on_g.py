"""The equal-KL rule applied to the first-order mixture g (chapter 06, reading of record chf-equal-kl)."""

import dataclasses

import numpy as np
import pytest

from fusion.book.chapters import chernoff as C
from fusion.estimates.chernoff import chernoff_fuse_gaussians, gaussian_chernoff_weights, gaussian_kl
from fusion.scenarios.range_bearing import _equal_kl_on_mixture, _sigma_point_log_expectations


def _gaussians(rng, B, N, d, S=1):
    means = rng.normal(size=(B, N, S, d))
    A = 0.7 * rng.normal(size=(B, N, S, d, d))
    covs = A @ np.swapaxes(A, -1, -2) + 0.5 * np.eye(d)
    logw = np.log(rng.dirichlet(np.ones(S), size=(B, N))) if S > 1 else np.zeros((B, N, 1))
    return logw, means, covs


def test_sigma_points_exact_for_gaussian_nodes():
    """Single Gaussians: g is one Gaussian and E_g[log N_i] has a closed form (sigma points are exact for it)."""
    rng = np.random.default_rng(0)
    logw, means, covs = _gaussians(rng, 4, 3, 3)
    eps = rng.dirichlet(np.ones(3), size=4)
    h = _sigma_point_log_expectations(logw, means, covs, eps)
    for b in range(4):
        f = chernoff_fuse_gaussians(means[b, :, 0], covs[b, :, 0], eps[b])
        for i in range(3):
            Pi, dm = covs[b, i, 0], f.x - means[b, i, 0]
            ref = -0.5 * (np.linalg.slogdet(2 * np.pi * Pi)[1] + np.trace(np.linalg.solve(Pi, f.P))
                          + dm @ np.linalg.solve(Pi, dm))
            assert h[b, i] == pytest.approx(ref, rel=1e-9, abs=1e-9)


def test_equal_kl_on_gaussians_is_the_chernoff_optimum():
    """For Gaussians the equal-KL point is the interior Chernoff optimum; NaN exactly where that is on the boundary."""
    rng = np.random.default_rng(1)
    logw, means, covs = _gaussians(rng, 12, 3, 2)
    e = _equal_kl_on_mixture(logw, means, covs)
    found = 0
    for b in range(12):
        opt = gaussian_chernoff_weights(means[b, :, 0], covs[b, :, 0]).eps
        interior = bool(np.min(opt) > 1e-4)
        assert np.all(np.isfinite(e[b])) == interior
        if interior:
            found += 1
            np.testing.assert_allclose(e[b], opt, atol=1e-4)
            f = chernoff_fuse_gaussians(means[b, :, 0], covs[b, :, 0], e[b])
            kls = [gaussian_kl(f.x, f.P, means[b, i, 0], covs[b, i, 0]) for i in range(3)]
            assert np.ptp(kls) < 1e-7
    assert found >= 3


def test_equal_kl_on_mixtures_equalises_the_sigma_point_divergences():
    rng = np.random.default_rng(2)
    logw, means, covs = _gaussians(rng, 10, 3, 4, S=3)
    e = _equal_kl_on_mixture(logw, means, covs)
    ok = np.all(np.isfinite(e), axis=1)
    assert ok.any()
    np.testing.assert_allclose(e[ok].sum(axis=1), 1.0, atol=1e-12)
    assert np.all(e[ok] >= 0)
    h = _sigma_point_log_expectations(logw[ok], means[ok], covs[ok], e[ok])
    assert np.max(np.ptp(h, axis=1)) <= 1e-9
    # one problem's answer does not depend on the others in its batch
    j = int(np.flatnonzero(ok)[0])
    np.testing.assert_array_equal(_equal_kl_on_mixture(logw[j:j + 1], means[j:j + 1], covs[j:j + 1])[0], e[j])


def test_equal_kl_g_reading_small_study():
    """The rule on g runs on the study's frames and counts them like the primary (the appendix's description)."""
    sc = dataclasses.replace(C.study_scenario(), frames=3, n_particles=300, n_samples=300, n_central=600)
    _, rs = C.tracking_study(5, 2, sc)
    u = C.equal_kl_g_values(rs)
    assert u["chf_klg_all"] == C.readings_values(rs)["chf_rd_frames"] == 6
    assert 0 <= u["chf_klg_equal"] <= u["chf_klg_frames"] <= u["chf_klg_all"]
    with pytest.raises(ValueError):  # the rule on g is not a reading of chf-equal-kl (no test can be passed)
        C.ev_equal_kl({"fused": "g"}, seed=5, runs=2, sc=sc)
