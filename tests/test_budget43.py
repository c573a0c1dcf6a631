"""Fix43r: round-off levels that match each variance computation, budgets re-weighted, honest budget tests."""
from __future__ import annotations

import numpy as np
import pytest


# --- wavelet.py: the round-off level of a variance estimate matches how each reading computes it ---------------

def test_small_but_real_residual_spread_is_accepted_in_every_reading() -> None:
    """X about 3, a residual of relative SD 1e-6 (10**7 round-offs): not "constant up to round-off" (the batch
    level had an N-fold term of a running sum that numpy's two-pass ``var`` does not have)."""
    from fusion.readings.wavelet import fuse_denoised
    rng = np.random.default_rng(0)
    X = 3.0 + 0.1 * rng.normal(size=(2, 1024))
    Y = X - 0.01 - 1e-8 * rng.normal(size=X.shape)
    for variance in ("batch", "running", "window"):
        w = fuse_denoised(X, Y, "max-raw", variance).weights
        assert np.all(np.isfinite(w)) and np.allclose(w.sum(), 1.0)
    assert not np.allclose(fuse_denoised(X, Y, "max-raw", "batch").weights, 0.5)   # a real estimate, not a tie


@pytest.mark.parametrize("variance", ["batch", "running", "window"])
def test_constant_residual_still_refused(variance: str) -> None:
    from fusion.readings.wavelet import fuse_denoised
    X = 3.0 + 0.1 * np.random.default_rng(1).normal(size=(2, 256))
    with pytest.raises(ValueError, match="must give every sensor a residual .* not constant"):
        fuse_denoised(X, X - 0.01, "max-raw", variance)


def test_window_round_off_does_not_grow_with_the_signal_length() -> None:
    """A window variance of 1e-6 of the mean square on 10**6 samples is an estimate, not round-off (the level of
    prefix-sum differences grew as n**2/window and set 81 % of these estimates to 0)."""
    from fusion.readings.wavelet import variance_estimates
    rng = np.random.default_rng(0)
    z = 1.0 + 1e-3 * rng.normal(size=(2, 10**6))
    v = variance_estimates(z + 5.0, np.full_like(z, 5.0), np.ones(2), "window", 64)
    assert np.mean(v == 0.0) < 1e-3


# --- tracks.py: the refusal points its docstring states are the code's ------------------------------------------

@pytest.mark.parametrize(("rule", "edge"), [("ci", 71296), ("convex", 71296), ("fuzzy", 71053), ("split", 49895),
                                            ("printed", 49783)])
def test_fuse_tracks_refusal_points_match_its_docstring(monkeypatch, rule: str, edge: int) -> None:
    """One run of a 4-state track: ``edge`` steps pass the budget, one more is refused (stated in the docstring)."""
    from fusion.filtering import tracks
    assert f"{edge:,} " in " ".join(tracks.fuse_tracks.__doc__.split())

    from types import SimpleNamespace
    monkeypatch.setattr(tracks, "instance_of", lambda *args: None)   # stand-in tracks: only their shape is read
    for K, message in ((edge, "^omega"), (edge + 1, "^a and b")):     # the budget first, then omega's check
        track = SimpleNamespace(est=np.broadcast_to(np.zeros(4), (1, K, 4)))
        with pytest.raises(ValueError, match=message):
            tracks.fuse_tracks(track, track, rule, omega=[[0.5]])


# --- particles.py: regularise's Q x d x d product has weighted_moments' work budget --------------------------------

def test_regularise_counts_its_product_as_weighted_moments_does(monkeypatch) -> None:
    """Its Q x d x d product is counted as weighted_moments' (same weight) by particles, before the covariance's
    check: at the input limits (Q d = 2**25, d = 5,792; about 14 CPU-s of product) it is beyond the budget; the
    book's sizes (10**4 particles of 4 states) pass."""
    from fusion._limits import MAX_WORK
    from fusion.filtering import particles
    rng = np.random.default_rng(0)
    Q, d = 2**25 // 5792, 5792
    assert particles._MOMENTS_PRODUCT * Q * d * d > MAX_WORK
    seen = []

    def _count(shape, names, weight=1.0):
        seen.append((shape, names, weight))
        raise ValueError(f"{names} counted")

    with monkeypatch.context() as m:
        m.setattr(particles, "work", _count)
        m.setattr(particles, "as_semidefinite", lambda *a, **k: pytest.fail("the covariance was checked first"))
        with pytest.raises(ValueError, match="^particles counted"):
            particles.regularise(np.zeros((7, 3)), np.eye(3), rng)
    assert seen == [((7, 3, 3), "particles", particles._MOMENTS_PRODUCT)]
    assert particles.regularise(np.zeros((10**4, 4)), np.eye(4), rng).shape == (10**4, 4)
