"""Source 003 sec. 2.6: wavelet denoising and normalised fusion reconstruction."""

from __future__ import annotations

import numpy as np
import pytest

from fusion.readings.wavelet import denoise, reconstruct


def _signals(seed: int = 0):
    n = np.arange(1024)
    S = 2 + np.sin(2 * np.pi * n / 256) + 0.5 * np.sin(2 * np.pi * n / 64)
    g = np.array([1.0, 1.5, 0.8, 2.0])
    sig = np.array([0.05, 0.1, 0.2, 0.4])
    rng = np.random.default_rng(seed)
    return S, g, g[:, None] * S + sig[:, None] * rng.normal(size=(4, 1024))


def test_denoising_reduces_error() -> None:
    S, g, X = _signals()
    Y = denoise(X)
    assert np.all(np.mean((Y - g[:, None] * S) ** 2, axis=1) < np.mean((X - g[:, None] * S) ** 2, axis=1))


def test_reconstruction_identities() -> None:
    S, g, X = _signals()
    rec = reconstruct(X)
    assert rec.weights.sum() == pytest.approx(1.0)
    np.testing.assert_allclose(rec.reconstructed / rec.norms[:, None], np.tile(rec.fused, (4, 1)))
    assert rec.weights.argmax() == 0  # least noisy sensor


def test_noise_free_equal_gain_signals_are_reproduced() -> None:
    S, _, _ = _signals()
    X = np.tile(S, (3, 1)) + 1e-3 * np.random.default_rng(1).normal(size=(3, 1024))
    rec = reconstruct(X)
    assert np.max(np.abs(rec.reconstructed - S)) < 0.05


def test_bad_input() -> None:
    with pytest.raises(ValueError, match="shape"):
        reconstruct(np.ones(10))
    with pytest.raises(ValueError, match="normaliser"):
        reconstruct(-np.abs(_signals()[2]))
    with pytest.raises(ValueError, match="level"):
        denoise(np.ones(64), level=0)
