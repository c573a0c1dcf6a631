"""Practitioners' baselines for fusing simultaneous readings (issue 15's fair study)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy import optimize, stats

from fusion import readings as rd
from fusion.book.chapters import ofs_fair as fair
from fusion.readings.robust import ROBUST_METHODS, robust_fuse

RNG = np.random.default_rng(11)
X = 900 + RNG.standard_normal((300, 10)) + np.where(RNG.random((300, 10)) < 0.15, 6.0, 0.0)


def test_median_and_trimmed_mean_are_scipy_and_numpy() -> None:
    np.testing.assert_array_equal(robust_fuse(X, "median"), np.median(X, axis=1))
    np.testing.assert_allclose(robust_fuse(X, "trimmed_mean", cut=0.2), stats.trim_mean(X, 0.2, axis=1))


def test_huber_matches_direct_minimisation() -> None:
    """IRLS solves the Huber problem: parity with a bounded scalar minimiser of the Huber loss."""
    c = 1.345
    est = robust_fuse(X[:60], "huber", c=c)
    for row, mu in zip(X[:60], est):
        mu, row = mu - np.median(row), row - np.median(row)  # near 0: the minimiser's tolerance is relative
        scale = np.median(np.abs(row - np.median(row))) / stats.norm.ppf(0.75)
        loss = lambda m: np.sum(np.where(np.abs((row - m) / scale) <= c, 0.5 * ((row - m) / scale) ** 2,  # noqa: E731
                                         c * np.abs((row - m) / scale) - 0.5 * c * c))
        ref = optimize.minimize_scalar(loss, bounds=(row.min(), row.max()), method="bounded",
                                       options={"xatol": 1e-10}).x
        assert mu == pytest.approx(ref, abs=1e-6)


def test_grubbs_drops_a_clear_outlier_and_keeps_clean_data() -> None:
    x = np.array([[10.0, 10.1, 9.9, 10.05, 9.95, 10.02, 30.0], [10.0, 10.1, 9.9, 10.05, 9.95, 10.02, 10.03]])
    out = robust_fuse(x, "grubbs")
    assert out[0] == pytest.approx(x[0, :6].mean())
    assert out[1] == pytest.approx(x[1].mean())


def test_inverse_variance_and_uniform_set() -> None:
    sig = np.linspace(0.5, 2.0, 10)
    w = sig**-2
    np.testing.assert_allclose(robust_fuse(X, "inverse_variance", sigma=sig), X @ w / w.sum())
    members = rd.fuse_epochs(X, "optimal_fusion_set").members
    np.testing.assert_allclose(robust_fuse(X, "uniform_set"), (X * members).sum(1) / members.sum(1))
    with pytest.raises(ValueError, match="sigma"):
        robust_fuse(X, "inverse_variance")
    with pytest.raises(ValueError, match="sigma"):
        robust_fuse(X, "inverse_variance", sigma=[1.0, 2.0])
    with pytest.raises(ValueError, match="cut"):
        robust_fuse(X, "trimmed_mean", cut=0.5)
    with pytest.raises(ValueError, match="alpha"):
        robust_fuse(X, "grubbs", alpha=1.0)


@pytest.mark.parametrize("method", [m for m in ROBUST_METHODS if m != "inverse_variance"])
def test_every_method_is_translation_equivariant_and_within_the_readings(method: str) -> None:
    a = robust_fuse(X, method)
    np.testing.assert_allclose(robust_fuse(X + 5.0, method), a + 5.0, atol=1e-9)
    assert np.all((a >= X.min(1) - 1e-9) & (a <= X.max(1) + 1e-9))


def test_fair_study_uses_common_random_numbers() -> None:
    st = fair.fair_study(3, n_runs=100, n_samples=10, sizes=(0, 4), counts=(0, 2), spreads=(1, 4))
    base = st.mae[(fair.SIZE, 0.0)]
    for key in ((fair.COUNT, 0.0), (fair.SPREAD, 1.0)):  # the same clean draws
        for m in fair.FAIR_METHODS:
            np.testing.assert_array_equal(st.mae[key][m], base[m])
    # two sensors at 4 σ in both sweeps at (size 4) and not at (2 faults, 5 σ): different
    assert not np.array_equal(st.mae[(fair.SIZE, 4.0)]["mean"], st.mae[(fair.COUNT, 2.0)]["mean"])
    # the mean's error under k faults of bias b grows towards k b / n
    assert st.mae[(fair.COUNT, 2.0)]["mean"].mean() == pytest.approx(1.0, abs=0.15)
    v = fair.verdicts(st)
    assert set(v.to_numpy().ravel()) - set(fair.WORDS.values()) <= {
        f"{st.mae[k]['optimal_fusion_set'].mean():.3f} °C" for k in st.mae}


def test_biweight_solves_its_estimating_equation_and_ignores_far_readings() -> None:
    c = 4.685
    est = robust_fuse(X[:60], "biweight", c_biweight=c)
    for row, mu in zip(X[:60], est):
        scale = np.median(np.abs(row - np.median(row))) / stats.norm.ppf(0.75)
        u = (row - mu) / (c * scale)
        psi = np.where(np.abs(u) < 1, u * (1 - u**2) ** 2, 0.0)
        assert abs(psi.sum()) < 1e-7          # the M-estimating equation holds at the estimate
    x = np.array([[10.0, 10.1, 9.9, 10.05, 9.95, 10.02, 10.03, 50.0, 55.0]])
    # readings beyond c scales get weight zero: moving them further does not move the estimate
    far = x.copy()
    far[0, -2:] += 100.0
    assert robust_fuse(far, "biweight")[0] == pytest.approx(robust_fuse(x, "biweight")[0], abs=1e-9)
    assert robust_fuse(x, "biweight")[0] == pytest.approx(10.0, abs=0.05)
    with pytest.raises(ValueError, match="c_biweight"):
        robust_fuse(X, "biweight", c_biweight=0.0)


def test_mad_rejection_is_the_mean_of_the_readings_kept() -> None:
    x = np.array([[10.0, 10.1, 9.9, 10.05, 9.95, 10.02, 30.0], [10.0, 10.1, 9.9, 10.05, 9.95, 10.02, 10.03],
                  [5.0, 5.0, 5.0, 5.0, 9.0, 5.0, 5.0]])
    out = robust_fuse(x, "mad_reject", k=3.0)
    assert out[0] == pytest.approx(x[0, :6].mean())
    assert out[1] == pytest.approx(x[1].mean())
    assert out[2] == pytest.approx(x[2].mean())   # MAD = 0: nothing can be judged far, all readings kept
    with pytest.raises(ValueError, match="k"):
        robust_fuse(X, "mad_reject", k=-1.0)
