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


def _filterpy_gains(F, H, Q, Rk, P0, n_steps):
    """filterpy's KalmanFilter run step by step (what gain_sequence used to call): gains and covariances."""
    from filterpy.kalman import KalmanFilter

    n, m = F.shape[0], H.shape[0]
    kf = KalmanFilter(dim_x=n, dim_z=m)
    kf.F, kf.H, kf.Q, kf.R, kf.P = F, H, Q, Rk[0], P0
    Ks, Ps = np.zeros((n_steps, n, m)), np.zeros((n_steps, n, n))
    Ps[0] = P0
    for k in range(1, n_steps):
        kf.R = Rk[k]
        kf.predict()
        kf.update(np.zeros(m))
        Ks[k], Ps[k] = kf.K, kf.P
    return Ks, Ps


@given(st.integers(0, 10_000), st.sampled_from([5, 40, 200]), st.booleans(), st.sampled_from([1e-6, 1e-2, 1.0, 100.0]))
@settings(max_examples=40, deadline=None)
def test_gain_sequence_is_filterpy_bit_for_bit(seed: int, n_steps: int, per_step: bool, q: float) -> None:
    """The hand-written recursion (and its copy of the fixed point) gives filterpy's bits, constant or per-step R."""
    from fusion.filtering.kalman import cv_model, gain_sequence

    rng = np.random.default_rng(seed)
    m = cv_model(float(rng.uniform(0.1, 5.0)))
    A = rng.normal(size=(4, 4))
    Q = q * (A @ A.T)
    R = np.diag(rng.uniform(1.0, 400.0, 2))
    if per_step:  # R changes for the first steps, then stays (the fixed point may still be reached)
        Rk = np.stack([R * (1.0 + (k < n_steps // 2) * rng.uniform()) for k in range(n_steps)])
    else:
        Rk = np.broadcast_to(R, (n_steps, 2, 2))
    P0 = np.diag(rng.uniform(1.0, 1e4, 4))
    g = gain_sequence(m.F, m.H, Q, Rk if per_step else R, P0, n_steps)
    Ks, Ps = _filterpy_gains(m.F, m.H, Q, Rk, P0, n_steps)
    np.testing.assert_array_equal(g.K, Ks)
    np.testing.assert_array_equal(g.P, Ps)


def test_gain_sequence_fixed_point_is_reached_and_copied() -> None:
    """A converging filter: the copied tail of the sequence equals filterpy's computed tail."""
    from fusion.filtering.kalman import cv_model, gain_sequence

    m = cv_model(1.0)
    Q, R, P0 = 0.1 * np.diag([0.25, 1.0, 0.25, 1.0]), 4.0 * np.eye(2), np.diag([4.0, 10.0, 4.0, 10.0])
    g = gain_sequence(m.F, m.H, Q, R, P0, 300)
    Ks, Ps = _filterpy_gains(m.F, m.H, Q, np.broadcast_to(R, (300, 2, 2)), P0, 300)
    assert np.array_equal(Ps[-1], Ps[-2])  # filterpy's own recursion has reached the fixed point
    np.testing.assert_array_equal(g.K, Ks)
    np.testing.assert_array_equal(g.P, Ps)


@pytest.mark.parametrize("runs", [1, 2, 7, 100])
def test_filter_runs_states_are_filterpy_bit_for_bit(runs: int) -> None:
    """filter_runs gives filterpy's states (x = x + K(z - Hx) after x = Fx) for one run and for many."""
    from filterpy.kalman import KalmanFilter

    from fusion.filtering.kalman import cv_model, filter_runs, gain_sequence

    m = cv_model(1.0)
    Q, R, P0 = 0.1 * np.diag([0.25, 1.0, 0.25, 1.0]), 4.0 * np.eye(2), np.diag([4.0, 10.0, 4.0, 10.0])
    rng = np.random.default_rng(runs)
    z = 2.0 * rng.standard_normal((runs, 60, 2)) + np.arange(60)[None, :, None]
    x0 = rng.normal(size=(runs, 4))
    est = filter_runs(z, gain_sequence(m.F, m.H, Q, R, P0, 60), x0)
    for r in {0, runs - 1}:
        kf = KalmanFilter(dim_x=4, dim_z=2)
        kf.F, kf.H, kf.Q, kf.R, kf.P, kf.x = m.F, m.H, Q, R, P0, x0[r][:, None].copy()
        for k in range(1, 60):
            kf.predict()
            kf.update(z[r, k])
            np.testing.assert_array_equal(est[r, k], kf.x[:, 0])


@given(st.integers(0, 10_000), st.integers(0, 3), st.sampled_from(["stagnation", "positions"]),
       st.sampled_from([1e-9, 1e-6, 0.1]))  # lo in (0, 1): the swarm refuses 0 (issue 35, class 8)
@settings(max_examples=40, deadline=None)
def test_one_swarm_kernel_is_the_batch_kernel_bit_for_bit(seed: int, kind: int, stop: str, lo: float) -> None:
    """particle_swarm's one-problem kernel: the batch kernel's result, history, count and generator state, bit for bit.

    Smooth, flat (ties everywhere), plateaued and partly infinite fitnesses."""
    from fusion.optimise import swarm

    rng = np.random.default_rng(seed)
    dim = int(rng.integers(1, 6))
    c, scale = rng.dirichlet(np.ones(dim)), 10 ** rng.uniform(-3, 3)
    fit = [lambda E: -scale * np.sum((E - c) ** 2, axis=-1), lambda E: np.zeros(len(E)),
           lambda E: -np.round(np.abs(E - c).max(axis=-1), 2),
           lambda E: np.where(E[:, 0] > 0.5, -np.inf, -np.sum((E - c) ** 2, axis=-1))][kind]
    kw = dict(n_particles=int(rng.integers(1, 30)), iterations=int(rng.integers(1, 80)),
              patience=int(rng.integers(1, 15)), stop=stop, lo=lo, xtol=float(rng.choice([1e-3, 0.05])),
              tol=float(rng.choice([0.0, 1e-9, 1e-3])))
    g1, g2 = np.random.default_rng(seed + 1), np.random.default_rng(seed + 1)
    with np.errstate(invalid="ignore"):
        one = swarm.particle_swarm(fit, dim, g1, **kw)
        (batch,) = swarm.particle_swarm_batch(lambda act, eps: np.stack([fit(e) for e in eps]), dim, [g2], **kw)
    np.testing.assert_array_equal(one.x, batch.x)
    np.testing.assert_array_equal(one.history, batch.history)
    assert (one.fun, one.n_evaluations) == (batch.fun, batch.n_evaluations)
    assert g1.bit_generator.state == g2.bit_generator.state


def test_one_swarm_rejects_a_fitness_of_the_wrong_shape() -> None:
    from fusion.optimise import swarm

    with pytest.raises(ValueError, match="fitness returned values of shape"):
        swarm.particle_swarm(lambda E: 0.0, 3, np.random.default_rng(0))


def test_normals_filled_in_place_are_the_stacked_draws() -> None:
    """range_bearing._normals: each generator's numbers in its slot, as np.stack of separate draws gave them;
    the generators are left in the same state (the study's streams go on unchanged)."""
    from fusion.scenarios.range_bearing import _normals, _regularise_batch

    a = [np.random.default_rng([7, i]) for i in range(5)]
    b = [np.random.default_rng([7, i]) for i in range(5)]
    np.testing.assert_array_equal(_normals(a, (300, 4)), np.stack([g.standard_normal((300, 4)) for g in b]))
    assert all(x.bit_generator.state == y.bit_generator.state for x, y in zip(a, b))
    x = np.random.default_rng(1).normal(size=(5, 300, 4))
    cov = np.stack([np.diag([4.0, 1.0, 9.0, 2.0])] * 5)
    got = _regularise_batch(x, cov, a)
    n, d = 300, 4  # the formula as it was written before the in-place fill
    h = (4.0 / (n * (d + 2))) ** (1.0 / (d + 4))
    P = 0.5 * (cov + np.swapaxes(cov, -1, -2))
    floor = 1e-9 * np.maximum(np.trace(P, axis1=-2, axis2=-1) / d, 1e-12)
    L = np.linalg.cholesky(P + floor[:, None, None] * np.eye(d))
    want = x + np.matmul(np.stack([h * g.standard_normal((n, d)) for g in b]), np.swapaxes(L, -1, -2))
    np.testing.assert_array_equal(got, want)
