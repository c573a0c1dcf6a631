"""Single-problem reference functions against the batched kernels the book's studies run (issue 36, review §3.3(b)).

The library keeps a readable function per problem (filterpy's ``KalmanFilter`` beside ``batch_filter``) and
runs its studies through batched kernels. Each test holds one pair to the same numbers: bit for bit where the
arithmetic is the same, to a tight tolerance where the kernel reorders it. (Already held elsewhere:
``weighted_em`` / ``weighted_em_batch`` and ``fuse_mixtures_batch`` problem by problem in ``test_chernoff.py``,
``error_moments`` / ``_path_error_x`` in ``test_ci_book_chapter.py``, ``fruit_fly`` / ``fruit_fly_batch`` in
``test_ci_chapter.py``, the registration methods against the chapter's dispatcher in
``test_time_registration_chapter.py`` with ``kalman_filter`` against ``kalman_runs`` there, ``blair_ls`` against ``least_squares`` in ``test_registration.py``,
``fuse_current`` against ``optimal_weights`` and ``cumulative_fusion`` in ``test_lecture_chapter.py``.)
"""
from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fusion.estimates import chernoff as ch
from fusion.estimates import mixtures as mx
from fusion.estimates.ci import ci_weight
from fusion.estimates.chernoff.gaussian import _ci_criterion_batch
from fusion.filtering import particles as pf
from fusion.readings import wavelet as wv
from fusion.scenarios import range_bearing_batch as rbb


def _spd(rng: np.random.Generator, d: int, lo: float = 0.2) -> np.ndarray:
    A = rng.normal(size=(d, d))
    return A @ A.T + lo * np.eye(d)


def _weights(rng: np.random.Generator, shape: tuple[int, ...]) -> np.ndarray:
    w = rng.exponential(size=shape) ** 3  # uneven, as importance weights are
    return w / w.sum(axis=-1, keepdims=True)


# --- covariance intersection: the N-ary weights, the two-estimate closed form, the PF's batched kernel -------------

@settings(max_examples=30, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), d=st.integers(1, 4), crit=st.sampled_from(["det", "trace"]))
def test_covariance_intersection_weights_of_two_is_the_closed_form(seed: int, d: int, crit: str) -> None:
    """N = 2: the projected Newton method on the simplex finds ci_weight's eigen-decomposition minimiser."""
    rng = np.random.default_rng(seed)
    P1, P2 = _spd(rng, d), _spd(rng, d)
    w = ch.covariance_intersection_weights(np.stack([P1, P2]), crit)
    assert w.sum() == pytest.approx(1.0, abs=1e-12)
    # the same minimum (the criterion is flat near it: compare values and, loosely, weights)
    I1, I2 = np.linalg.inv(P1), np.linalg.inv(P2)

    def f(o: float) -> float:
        P = np.linalg.inv(o * I1 + (1 - o) * I2)
        return float(np.linalg.slogdet(P)[1] if crit == "det" else np.trace(P))

    w_cf = ci_weight(P1, P2, crit)
    assert f(w[0]) == pytest.approx(f(w_cf), rel=1e-9, abs=1e-12)
    assert w[0] == pytest.approx(w_cf, abs=1e-4)


def test_covariance_intersection_weights_equal_the_batched_kernel_problem_by_problem() -> None:
    """The particle-filter study calls the kernel on all runs at once; each run's weights are those of the run alone."""
    rng = np.random.default_rng(3)
    covs = np.stack([np.stack([_spd(rng, 4) for _ in range(3)]) for _ in range(6)])  # (B=6, N=3, 4, 4)
    for crit in ("det", "trace"):
        batch = _ci_criterion_batch(np.linalg.inv(covs), crit)
        one = np.stack([ch.covariance_intersection_weights(c, crit) for c in covs])
        np.testing.assert_allclose(batch, one, rtol=0, atol=1e-12)


# --- Chernoff fusion of mixtures: the readable call and the batched one ---------------------------------------------

def test_fuse_mixtures_is_fuse_mixtures_batch_on_the_padded_arrays() -> None:
    """fuse_mixtures(gms, rng) is the batch of one on the mixtures padded the same way, digit for digit."""
    rng = np.random.default_rng(5)
    gms = [mx.GaussianMixture(weights=np.array([0.3, 0.7]), means=rng.normal(size=(2, 2)),
                              covs=np.stack([_spd(rng, 2, 0.5) for _ in range(2)])),
           mx.GaussianMixture(weights=np.array([1.0]), means=rng.normal(size=(1, 2)), covs=_spd(rng, 2, 0.5)[None])]
    w = np.zeros((1, 2, 2))
    m = np.empty((1, 2, 2, 2))
    c = np.empty((1, 2, 2, 2, 2))
    for i, g in enumerate(gms):
        n = g.weights.size
        w[0, i, :n], m[0, i, :n], c[0, i, :n] = g.weights, g.means, g.covs
        m[0, i, n:], c[0, i, n:] = g.means[0], np.eye(2)
    for opt in ("slsqp", "pso"):
        one = ch.fuse_mixtures(gms, np.random.default_rng(11), 200, optimiser=opt)
        (bat,) = ch.fuse_mixtures_batch(w, m, c, [np.random.default_rng(11)], 200, optimiser=opt)
        for field in ("x", "P", "eps", "objective", "x_eps0", "x_first_order", "P_first_order", "ess"):
            np.testing.assert_array_equal(getattr(one, field), getattr(bat, field), err_msg=f"{opt}: {field}")


# --- mixture moments: gm_moments against weighted_moments of exact sigma points -------------------------------------

@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), S=st.integers(1, 4), d=st.integers(1, 4))
def test_gm_moments_are_the_weighted_moments_of_its_sigma_points(seed: int, S: int, d: int) -> None:
    """Each component s is matched exactly by the 2d points mu_s ± sqrt(d) L_s e_k of weight pi_s / (2d); the
    mixture's moments are then the weighted moments (the particle filter's moment matching) of all 2dS points."""
    rng = np.random.default_rng(seed)
    pis = _weights(rng, (S,))
    means = rng.normal(scale=3.0, size=(S, d))
    covs = np.stack([_spd(rng, d) for _ in range(S)])
    L = np.linalg.cholesky(covs) * np.sqrt(d)  # columns: the scaled square-root directions
    pts = np.concatenate([means[:, None, :] + np.swapaxes(L, 1, 2), means[:, None, :] - np.swapaxes(L, 1, 2)], axis=1)
    wts = np.repeat(pis / (2 * d), 2 * d)
    got = mx.gm_moments(mx.GaussianMixture(weights=pis, means=means, covs=covs))
    ref = pf.weighted_moments(pts.reshape(-1, d), wts)
    np.testing.assert_allclose(got.mean, ref.mean, rtol=1e-10, atol=1e-10)
    np.testing.assert_allclose(got.cov, ref.cov, rtol=1e-10, atol=1e-10)


# --- particle helpers against what the batched particle filter runs -------------------------------------------------

@settings(max_examples=30, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), Q=st.integers(2, 60), d=st.integers(1, 4))
def test_weighted_moments_equal_the_batched_moments(seed: int, Q: int, d: int) -> None:
    rng = np.random.default_rng(seed)
    x = rng.normal(scale=5.0, size=(3, 2, Q, d))
    w = _weights(rng, (3, 2, Q))
    m, c = rbb._moments(x, w)
    for b in range(3):
        for i in range(2):
            one = pf.weighted_moments(x[b, i], w[b, i])
            np.testing.assert_allclose(m[b, i], one.mean, rtol=1e-13, atol=1e-13)
            np.testing.assert_allclose(c[b, i], one.cov, rtol=1e-12, atol=1e-12)


@settings(max_examples=30, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), Q=st.integers(2, 50), d=st.integers(1, 4))
def test_regularise_equals_the_batched_regularisation_with_the_same_generators(seed: int, Q: int, d: int) -> None:
    rng = np.random.default_rng(seed)
    x = rng.normal(size=(4, Q, d))
    cov = np.stack([_spd(rng, d, 1e-3) for _ in range(4)])
    batch = rbb._regularise_batch(x, cov, [np.random.default_rng(seed + p) for p in range(4)])
    for p in range(4):
        one = pf.regularise(x[p], cov[p], np.random.default_rng(seed + p))
        np.testing.assert_allclose(batch[p], one, rtol=1e-12, atol=1e-12)


@settings(max_examples=30, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), Q=st.integers(1, 80))
def test_resampling_and_ess_equal_the_filters_kernels(seed: int, Q: int) -> None:
    """The batched filter calls the resampling kernel per node with its generator and computes Kish's ESS inline."""
    rng = np.random.default_rng(seed)
    w = _weights(rng, (3, Q))
    for row, s in zip(w, range(3)):
        np.testing.assert_array_equal(pf.systematic_resample(row, np.random.default_rng(s)),
                                      pf._systematic_resample(row, np.random.default_rng(s), Q))
    np.testing.assert_array_equal(pf.effective_sample_size(w), 1.0 / np.sum(w**2, axis=-1))
    assert [pf.effective_sample_size(row) for row in w] == list(1.0 / np.sum(w**2, axis=-1))


@settings(max_examples=30, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), Q=st.integers(1, 40))
def test_log_likelihood_and_wrap_equal_the_broadcast_kernel(seed: int, Q: int) -> None:
    """The filter scores all runs' particles at once, (B, Q, 4) against readings (B, 2): each run as alone."""
    rng = np.random.default_rng(seed)
    x = rng.normal(scale=50.0, size=(3, Q, 4))
    z = np.column_stack([rng.uniform(1.0, 100.0, 3), rng.uniform(-np.pi, np.pi, 3)])
    sensor = np.array([10.0, -5.0])
    batch = pf._log_likelihood(x, z, sensor, 2.0, 0.05)
    for b in range(3):
        np.testing.assert_array_equal(batch[b], pf.log_likelihood(x[b], z[b], sensor, 2.0, 0.05))
    a = rng.uniform(-20.0, 20.0, size=50)
    np.testing.assert_array_equal(pf.wrap_angle(a), pf._wrap(a))
    assert np.all(np.abs(pf.wrap_angle(a)) <= np.pi) and np.allclose(np.cos(pf.wrap_angle(a)), np.cos(a))


# --- wavelet reconstruction: one run against the runs of a study at once --------------------------------------------

@pytest.mark.parametrize("normaliser", ["max", "max-raw", "median"])
def test_fuse_denoised_of_a_batch_is_each_run_alone(normaliser: str) -> None:
    """signal_study reconstructs all runs of a block in one call (leading batch axis); each run is the run alone."""
    rng = np.random.default_rng(7)
    t = np.arange(128)
    S = 2 + np.sin(2 * np.pi * t / 64)
    X = np.array([1.0, 1.5, 0.8])[:, None] * S + 0.1 * rng.normal(size=(5, 3, 128))
    Y = wv.denoise(X, level=3)
    batch = wv.fuse_denoised(X, Y, normaliser=normaliser)
    for r in range(5):
        one = wv.fuse_denoised(X[r], Y[r], normaliser=normaliser)
        np.testing.assert_allclose(batch.reconstructed[r], one.reconstructed, rtol=1e-13, atol=1e-13)
        np.testing.assert_allclose(batch.weights[r], one.weights, rtol=1e-13, atol=1e-15)
