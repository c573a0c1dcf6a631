"""Source 003 sec. 2.4: belief-degree fusion via the Perron eigenvector (fusion.readings)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from fusion.readings.fusion_set import METHODS, belief_degree, belief_matrix, fuse_epochs, perron_weights

#: Readings below 1e-150 in magnitude are refused by the shared validation (issue 35, rule 2): drawn as zero.
def _representable(v: float) -> float:
    return 0.0 if abs(v) < 1e-150 else v


readings = arrays(float, st.integers(1, 8), elements=st.floats(-50, 50).map(_representable))


@given(readings, st.floats(0.05, 20))
def test_weights_positive_sum_one_value_inside(x: np.ndarray, scale: float) -> None:
    r = belief_degree(x, scale=scale)
    # non-negative: the support exp(-a d^2) of a far reading may underflow to an exact 0 (a documented, valid weight)
    assert np.all(r.weights >= 0) and r.weights.max() > 0
    assert r.weights.sum() == pytest.approx(1.0, rel=1e-12)
    assert x.min() - 1e-9 <= r.value <= x.max() + 1e-9


@given(readings, st.integers(0, 1000))
def test_permutation_equivariant(x: np.ndarray, seed: int) -> None:
    p = np.random.default_rng(seed).permutation(x.size)
    # eigenvectors are accurate to ~ eps / gap, and gaps below PERRON_RTOL * lambda are
    # merged, so weights agree to ~ 1e-10 (measured worst over 30000 draws: 2.7e-10)
    np.testing.assert_allclose(belief_degree(x[p]).weights, belief_degree(x).weights[p], rtol=1e-9, atol=1e-9)


def test_eigenvector_agrees_with_power_iteration() -> None:
    x = np.array([20.1, 20.4, 19.8, 23.0, 20.0])
    B = belief_matrix(x)
    a = np.ones(x.size)
    for _ in range(500):
        a = B @ a
        a /= a.sum()
    np.testing.assert_allclose(perron_weights(B), a, rtol=1e-12)
    lam = (B @ a)[0] / a[0]
    assert lam == pytest.approx(np.linalg.eigvalsh(B).max(), rel=1e-12)


def test_identical_readings_give_uniform_weights_and_one_reading_weight_one() -> None:
    np.testing.assert_allclose(belief_degree([3.0, 3.0, 3.0]).weights, 1 / 3)
    assert belief_degree([7.0]).weights.tolist() == [1.0]


def test_scale_one_is_the_papers_half_factor() -> None:
    x = np.array([0.0, 1.0, 3.0])
    np.testing.assert_allclose(belief_matrix(x), np.exp(-0.5 * np.abs(x[:, None] - x[None, :])))


def test_binary_reducible_matrix_weights_the_dominant_group() -> None:
    r = belief_degree([0.0, 0.1, 0.2, 5.0, 5.1], binary_eps=0.5)
    np.testing.assert_allclose(r.weights, [1 / 3, 1 / 3, 1 / 3, 0, 0], atol=1e-12)
    # two equal groups: the eigenvalue is repeated; the projection of 1 shares the weight
    np.testing.assert_allclose(belief_degree([0.0, 0.1, 5.0, 5.1], binary_eps=0.5).weights, 0.25)


def test_registered_and_vectorised() -> None:
    assert "belief_degree" in METHODS
    X = np.random.default_rng(0).normal(size=(20, 4))
    res = fuse_epochs(X, "belief_degree", scale=2.0)
    for i in range(20):
        assert res.values[i] == pytest.approx(belief_degree(X[i], scale=2.0).value, rel=1e-12)


def test_bad_input() -> None:
    with pytest.raises(ValueError, match="scale"):
        belief_degree([1.0, 2.0], scale=0)
    with pytest.raises(ValueError, match="binary_eps"):
        belief_degree([1.0, 2.0], binary_eps=-1)
    with pytest.raises(ValueError, match="symmetric"):
        perron_weights([[1.0, 0.5], [0.1, 1.0]])
    with pytest.raises(ValueError, match="non-negative"):
        perron_weights([[1.0, -0.5], [-0.5, 1.0]])
    with pytest.raises(ValueError, match="1-D"):
        belief_degree([[1.0, 2.0]])
