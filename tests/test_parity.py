"""Parity of the hand-written kernels with the libraries they replace (issue 12, item 3).

Each function is kept because it is faster inside the book's inner loops or takes a seeded
Generator; these tests make sure it computes what the library computes.
"""

from __future__ import annotations

import numpy as np
import pytest
from filterpy.common import Q_continuous_white_noise, Q_discrete_white_noise
from filterpy.monte_carlo import systematic_resample as filterpy_systematic
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.special import logsumexp as scipy_logsumexp
from scipy.stats import multivariate_normal

from fusion.estimates.mixtures import gaussian_logpdf, logsumexp
from fusion.filtering.particles import effective_sample_size, ncv_model, systematic_resample
from fusion.scenarios.infrared_radar import white_acceleration


@given(st.integers(0, 10_000), st.integers(1, 6), st.integers(1, 40))
@settings(max_examples=40)
def test_logsumexp_equals_scipy(seed: int, rows: int, cols: int) -> None:
    a = np.random.default_rng(seed).normal(0.0, 50.0, (rows, cols))
    a[0, 0] = -np.inf
    for axis in (0, 1):
        np.testing.assert_allclose(logsumexp(a, axis=axis), scipy_logsumexp(a, axis=axis), rtol=1e-12, atol=1e-12)


def test_logsumexp_all_minus_inf_is_minus_inf_like_scipy() -> None:
    a = np.full((3, 2), -np.inf)
    assert np.all(np.isneginf(logsumexp(a))) and np.all(np.isneginf(scipy_logsumexp(a, axis=0)))


@given(st.integers(0, 10_000), st.integers(1, 4))
@settings(max_examples=30)
def test_gaussian_logpdf_equals_scipy(seed: int, d: int) -> None:
    rng = np.random.default_rng(seed)
    A = rng.normal(size=(d, d))
    P = A @ A.T + 0.1 * np.eye(d)
    m = rng.normal(size=d)
    x = rng.normal(size=(7, d)) * 3
    np.testing.assert_allclose(gaussian_logpdf(x, m, P), multivariate_normal(m, P).logpdf(x).reshape(-1),
                               rtol=1e-10, atol=1e-10)


def test_systematic_resample_equals_filterpy_for_the_same_offset(monkeypatch: pytest.MonkeyPatch) -> None:
    w = np.random.default_rng(3).random(50)
    w /= w.sum()
    ours = systematic_resample(w, np.random.default_rng(11))
    u = np.random.default_rng(11).uniform()  # the one offset our Generator drew
    # filterpy draws its offset from NumPy's global state: give it the same number.
    import filterpy.monte_carlo.resampling as resampling

    monkeypatch.setattr(resampling, "random", lambda *a: u)
    theirs = filterpy_systematic(w)
    np.testing.assert_array_equal(ours, theirs)


def test_motion_model_noise_is_filterpys() -> None:
    Q = ncv_model(0.7, 2.5).Q
    np.testing.assert_array_equal(Q, Q_continuous_white_noise(dim=2, dt=0.7, spectral_density=2.5, block_size=2))
    np.testing.assert_array_equal(white_acceleration(0.7, 3.0), Q_discrete_white_noise(dim=2, dt=0.7, var=9.0))


@pytest.mark.parametrize("n", [1, 5, 1000])
def test_effective_sample_size_closed_forms(n: int) -> None:
    assert effective_sample_size(np.full(n, 1.0 / n)) == pytest.approx(n)
    one_hot = np.zeros(n)
    one_hot[0] = 1.0
    assert effective_sample_size(one_hot) == pytest.approx(1.0)
    batch = np.stack([np.full(n, 1.0 / n), one_hot])
    np.testing.assert_allclose(effective_sample_size(batch, axis=1), [n, 1.0])
