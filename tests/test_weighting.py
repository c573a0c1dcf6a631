"""Source 003 secs. 2.1-2.2: optimal weights, variance estimators, AWF, LS learning."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from fusion.readings import weighting as W
from fusion.readings import weighting as wt

variances = arrays(float, st.integers(1, 8), elements=st.floats(1e-3, 1e3))


@given(variances)
def test_optimal_weights_sum_to_one_and_reach_the_minimum(v: np.ndarray) -> None:
    w = W.optimal_weights(v)
    assert np.all(w > 0)
    assert w.sum() == pytest.approx(1.0, rel=1e-12)
    fused_var = float(np.sum(w**2 * v))
    assert fused_var == pytest.approx(W.minimum_variance(v), rel=1e-10)
    # below every sensor, and below the mean of the sensors (AM-HM)
    assert W.minimum_variance(v) <= v.min() * (1 + 1e-12)
    assert W.minimum_variance(v) <= v.sum() / v.size**2 * (1 + 1e-12)


@given(variances, st.integers(0, 10_000))
def test_any_other_convex_weights_do_worse(v: np.ndarray, seed: int) -> None:
    u = np.random.default_rng(seed).dirichlet(np.ones(v.size))
    assert np.sum(u**2 * v) >= W.minimum_variance(v) * (1 - 1e-12)


def test_running_variances_match_recursions() -> None:
    rng = np.random.default_rng(1)
    X = 5 + rng.normal(size=(50, 3)) * [1.0, 2.0, 3.0]
    k = X.shape[0]
    Rpp = np.zeros(3)
    Rpq = np.zeros((3, 3))
    for i in range(1, k + 1):  # the lecture's recursions, literally
        Rpp = (i - 1) / i * Rpp + X[i - 1] ** 2 / i
        Rpq = (i - 1) / i * Rpq + np.outer(X[i - 1], X[i - 1]) / i
    Rbar = (Rpq.sum(axis=1) - np.diag(Rpq)) / 2
    np.testing.assert_allclose(W.running_variances(X)[-1], Rpp - Rbar, rtol=1e-12)


def test_centred_estimator_is_shift_invariant_and_lecture_is_not() -> None:
    rng = np.random.default_rng(2)
    X = rng.normal(size=(100, 4))
    c0, c1 = W.running_variances(X, "centred"), W.running_variances(X + 900.0, "centred")
    np.testing.assert_allclose(c0, c1, atol=1e-8)
    l0, l1 = W.running_variances(X, "lecture"), W.running_variances(X + 900.0, "lecture")
    assert np.max(np.abs(l0 - l1)) > 1.0


def test_both_estimators_unbiased_within_mc_error() -> None:
    rng = np.random.default_rng(3)
    sig2 = np.array([0.25, 1.0, 4.0, 16.0])
    k, runs = 50, 4000
    X = 10.0 + rng.normal(size=(runs, k, 4)) * np.sqrt(sig2)
    lec = W.running_variances(X, "lecture")[:, -1]
    cen = W.running_variances(X, "centred")[:, -1]
    se_l = lec.std(axis=0) / np.sqrt(runs)
    se_c = cen.std(axis=0) / np.sqrt(runs)
    assert np.all(np.abs(lec.mean(axis=0) - sig2) < 4 * se_l)
    assert np.all(np.abs(cen.mean(axis=0) - (k - 1) / k * sig2) < 4 * se_c)
    assert np.all(cen.std(axis=0) < lec.std(axis=0))  # X = 10 inflates the lecture's spread


def test_awf_with_oracle_like_data_reaches_min_variance_over_k() -> None:
    rng = np.random.default_rng(4)
    sig2 = np.array([0.25, 1.0, 4.0, 16.0])
    k, runs = 200, 3000
    X = rng.normal(size=(runs, k, 4)) * np.sqrt(sig2)
    oracle = (W.running_means(X)[:, -1] @ W.optimal_weights(sig2))
    mse = np.mean(oracle**2)
    target = W.minimum_variance(sig2) / k
    assert abs(mse - target) < 4 * target * np.sqrt(2 / runs)


def test_learned_variances_converge_to_the_derived_limit_not_to_R() -> None:
    rng = np.random.default_rng(5)
    R = np.array([1.0, 4.0, 9.0])
    n = R.size
    Y = 50 + rng.normal(size=(400, 500, n)) * np.sqrt(R)
    Rh = W.learned_variances(Y)[:, -1].mean(axis=0)
    limit = (1 - 2 / n) * R + R.sum() / n**2
    np.testing.assert_allclose(Rh, limit, rtol=0.02)
    assert abs(Rh[0] - R[0]) > 0.3
    np.testing.assert_allclose(W.corrected_variances(Rh), R, rtol=0.05)


def test_two_sensors_learned_weights_are_always_one_half() -> None:
    rng = np.random.default_rng(6)
    Y = rng.normal(size=(30, 2)) * [1.0, 5.0]
    w = W.ls_learning(Y).weights
    np.testing.assert_allclose(w, 0.5, rtol=1e-12)
    with pytest.raises(ValueError, match="n >= 3"):
        W.corrected_variances(W.learned_variances(Y))


def test_wls_is_the_weighted_mean_for_a_column_of_ones() -> None:
    w = np.array([1.0, 2.0, 3.0])
    y = np.array([4.0, 5.0, 7.0])
    assert W.wls(np.ones(3), w, y)[0] == pytest.approx(w @ y / w.sum(), rel=1e-14)


def test_negative_variance_estimates_give_finite_weights() -> None:
    w = W.inverse_variance_weights(np.array([-1.0, 1.0, 2.0]))
    assert np.all(np.isfinite(w)) and w.sum() == pytest.approx(1.0)
    assert w[0] > 0.999
    np.testing.assert_allclose(W.inverse_variance_weights(np.zeros(3)), 1 / 3)


def test_bad_input() -> None:
    with pytest.raises(ValueError, match="positive"):
        W.optimal_weights([1.0, 0.0])
    with pytest.raises(ValueError, match="at least 2 sensors"):
        W.running_variances(np.ones((5, 1)))
    with pytest.raises(ValueError, match="NaN"):
        W.awf(np.array([[1.0, np.nan]]))
    with pytest.raises(ValueError, match="estimator"):
        W.running_variances(np.ones((5, 2)), "bogus")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="shape"):
        W.awf(np.ones(4))


@pytest.mark.parametrize("shape", [(7, 50, 4), (30, 3), (2, 5, 20, 2)])
def test_running_estimates_of_both_estimators_are_the_public_functions_bit_for_bit(shape: tuple[int, ...]) -> None:
    # one pass of running moments for the lecture's and the centred estimator and the running means (awf_study's)
    X = 900.0 + np.random.default_rng(len(shape)).normal(size=shape) * np.linspace(0.5, 4.0, shape[-1])
    lecture, centred, means = wt._running_estimates(X)
    for got, want in ((lecture, wt.running_variances(X, "lecture")), (centred, wt.running_variances(X, "centred")),
                      (means, wt.running_means(X))):
        assert got.tobytes() == want.tobytes() and got.shape == want.shape
    for var, e in ((lecture, "lecture"), (centred, "centred")):
        for guard in ("floor", "abs", "equal"):   # "none" refuses the zero estimates at k = 1
            got, want = wt._awf_result(var, means, guard), wt.awf(X, e, guard)
            for f in ("value", "weights", "variances", "means"):
                assert getattr(got, f).tobytes() == getattr(want, f).tobytes()


@pytest.mark.parametrize("memory", ["growing", "forgetting", "window"])
def test_tracking_estimates_from_one_pass_are_tracking_variances_bit_for_bit(memory: str) -> None:
    X = np.sin(np.arange(120) / 9.0)[:, None] + np.random.default_rng(2).normal(size=(6, 120, 4)) * [0.5, 1, 2, 4]
    got = wt._tracking_estimates(X, ("sample", "lecture", "centred"), memory, forgetting=0.95, window=30)
    for g, e in zip(got, ("sample", "lecture", "centred"), strict=True):
        want = wt.tracking_variances(X, e, memory, forgetting=0.95, window=30)
        assert g.shape == want.shape and g.tobytes() == want.tobytes()
