"""Source 000: convex combination, split CI, the printed equations, optimisers, tracking."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from fusion import estimates as es
from fusion.data import as_printed
from fusion.optimise import scalar as opt
from fusion import filtering as tr
from fusion.scenarios import two_sensor


def _spd(rng: np.random.Generator, n: int) -> np.ndarray:
    A = rng.standard_normal((n, n))
    return A @ A.T + 0.1 * np.eye(n)


@given(seed=st.integers(0, 2**31), n=st.integers(1, 4))
def test_convex_combination_is_optimal_for_independent_errors(seed: int, n: int) -> None:
    rng = np.random.default_rng(seed)
    P1, P2 = _spd(rng, n), _spd(rng, n)
    cc = es.convex_combination(np.zeros(n), P1, np.zeros(n), P2)
    for w in (0.2, 0.5, 0.8):
        ci = es.covariance_intersection(np.zeros(n), P1, np.zeros(n), P2, omega=w)
        assert np.linalg.eigvalsh(ci.P - cc.P).min() >= -1e-9 * np.trace(ci.P)


@given(seed=st.integers(0, 2**31), n=st.integers(1, 3), rho=st.floats(0.0, 0.99))
def test_split_ci_is_consistent_when_only_the_d_parts_correlate(seed: int, n: int, rho: float) -> None:
    rng = np.random.default_rng(seed)
    P1d, P1i, P2d, P2i = (_spd(rng, n) for _ in range(4))
    L1, L2 = np.linalg.cholesky(P1d), np.linalg.cholesky(P2d)
    P12 = rho * L1 @ L2.T  # any cross-covariance of the correlated parts
    res = es.split_covariance_intersection(np.zeros(n), P1d, P1i, np.zeros(n), P2d, P2i)
    T1 = P1d / res.omega + P1i
    T2 = P2d / (1 - res.omega) + P2i
    K1 = res.P @ np.linalg.inv(T1)
    K2 = res.P @ np.linalg.inv(T2)
    true = K1 @ (P1d + P1i) @ K1.T + K2 @ (P2d + P2i) @ K2.T + K1 @ P12 @ K2.T + K2 @ P12.T @ K1.T
    assert np.linalg.eigvalsh(res.P - true).min() >= -1e-8 * np.trace(res.P)


def test_split_ci_reduces_to_ci_and_to_the_convex_combination() -> None:
    rng = np.random.default_rng(0)
    P1, P2 = _spd(rng, 2), _spd(rng, 2)
    Z = np.zeros((2, 2))
    ci = es.covariance_intersection([0.0, 1.0], P1, [1.0, 0.0], P2, omega=0.3)
    sci = es.split_covariance_intersection([0.0, 1.0], P1, Z, [1.0, 0.0], P2, Z, omega=0.3)
    np.testing.assert_allclose(sci.P, ci.P, rtol=1e-9)
    np.testing.assert_allclose(sci.x, ci.x, rtol=1e-9, atol=1e-12)
    cc = es.convex_combination([0.0, 1.0], P1, [1.0, 0.0], P2)
    sci0 = es.split_covariance_intersection([0.0, 1.0], 1e-150 * P1, P1, [1.0, 0.0], 1e-150 * P2, P2, omega=0.5)
    np.testing.assert_allclose(sci0.P, cc.P, rtol=1e-9)


def test_printed_eqs_11_12_drive_omega_to_one() -> None:
    P = np.diag([2.0, 3.0])
    res = es.split_covariance_intersection([0, 0], P, P, [1, 1], P, P, same_omega=True)
    assert res.omega == 1.0
    cc = es.convex_combination([0, 0], 2 * P, [1, 1], 2 * P)
    np.testing.assert_allclose(res.P, cc.P)


def test_printed_eq2_does_not_preserve_identical_estimates() -> None:
    P1, P2 = np.diag([4.0, 1.0]), np.diag([1.0, 4.0])
    x = np.array([1.0, 2.0])
    good = es.covariance_intersection(x, P1, x, P2, omega=0.5)
    np.testing.assert_allclose(good.x, x)
    bad = as_printed.wang2024_eqs_1_2(x, P1, x, P2, omega=0.5)
    assert np.max(np.abs(bad.x - x)) > 1.0


def test_optimisers_agree_and_count_evaluations() -> None:
    f = lambda w: (w - 0.3) ** 2 + 1.0  # noqa: E731
    a = opt.bounded_minimum(f)
    b = opt.grid_search(f, 1001)
    c = opt.fruit_fly(f, np.random.default_rng(0))
    assert a.x == pytest.approx(0.3, abs=1e-6) and b.x == pytest.approx(0.3, abs=1e-3)
    assert c.fun >= a.fun - 1e-12 and b.fun >= a.fun - 1e-12
    assert c.n_evaluations == 30 * 200 and b.n_evaluations == 1001 and a.n_evaluations < 50
    # FOA converges on a known quadratic, wherever the minimum lies (accuracy falls near 1,
    # where the candidate 1/D needs the swarm within D ~ 1 of the origin)
    for seed in range(3):
        for target, tol in ((0.05, 1e-4), (0.3, 2e-3), (0.8, 1e-2)):
            g = lambda w, m=target: (np.asarray(w) - m) ** 2  # noqa: E731
            assert opt.fruit_fly(g, np.random.default_rng(seed), vectorized=True).x == pytest.approx(target, abs=tol)
    # vectorised over the swarm / the grid: the same answer from the same random stream
    fv = lambda w: (np.asarray(w) - 0.3) ** 2 + 1.0  # noqa: E731
    assert opt.fruit_fly(fv, np.random.default_rng(0), vectorized=True) == c
    assert opt.grid_search(fv, 1001, vectorized=True) == b
    with pytest.raises(ValueError, match="bounds"):
        opt.grid_search(f, 10, lo=1.0, hi=0.0)
    with pytest.raises(ValueError, match="population"):
        opt.fruit_fly(f, np.random.default_rng(0), population=0)


def test_trajectory_stays_in_the_published_area() -> None:
    X = two_sensor.trajectory().states
    assert 0 <= X[:, 0].min() and X[:, 0].max() <= 3500
    assert 0 <= X[:, 2].min() and X[:, 2].max() <= 12000
    speed = np.hypot(X[:, 1], X[:, 3])
    np.testing.assert_allclose(speed, 50.0, rtol=1e-6)


def test_vectorised_filter_equals_filterpy_step_by_step() -> None:
    from filterpy.kalman import KalmanFilter

    model = tr.cv_model(1.0)
    F, H = model.F, model.H
    Q, R = np.diag([100.0] * 4), np.diag([150.0**2] * 2)
    P0 = np.diag([150.0**2, 1e4, 150.0**2, 1e4])
    X = two_sensor.trajectory().states
    z = X[None, :30, [0, 2]] + 150 * np.random.default_rng(1).standard_normal((2, 30, 2))
    g = tr.gain_sequence(F, H, Q, R, P0, 30)
    x0 = np.column_stack([z[:, 0, 0], np.zeros(2), z[:, 0, 1], np.zeros(2)])
    est = tr.filter_runs(z, g, x0)
    kf = KalmanFilter(dim_x=4, dim_z=2)
    kf.F, kf.H, kf.Q, kf.R, kf.P, kf.x = F, H, Q, R, P0, x0[1].copy()
    for k in range(1, 30):
        kf.predict()
        kf.update(z[1, k])
        np.testing.assert_allclose(est[1, k], kf.x, rtol=1e-9, atol=1e-6)
    split = tr.split_covariances(g, Q, R, np.diag([0, 1e4, 0, 1e4]), np.diag([150.0**2, 0, 150.0**2, 0]))
    Pd, Pi = split.Pd, split.Pi
    np.testing.assert_allclose(Pd + Pi, g.P, rtol=1e-8, atol=1e-6)


def test_bad_input_raises() -> None:
    with pytest.raises(ValueError, match="T"):
        tr.cv_model(0.0)
    with pytest.raises(ValueError, match="positive definite"):
        es.convex_combination([0.0], [[-1.0]], [0.0], [[1.0]])
    with pytest.raises(ValueError, match="semidefinite"):
        es.split_covariance_intersection([0.0], [[-1.0]], [[2.0]], [0.0], [[1.0]], [[1.0]])
    with pytest.raises(ValueError, match="omega"):
        as_printed.wang2024_eqs_1_2([0.0], [[1.0]], [0.0], [[1.0]], omega=1.0)


def test_fruit_fly_batch_equals_fruit_fly_problem_by_problem() -> None:
    """Many swarms flown together give, problem by problem, the weights fruit_fly gives alone (same stream, same ties)."""
    targets = np.array([0.05, 0.3, 0.8, 0.3])
    flat = np.array([False, False, False, True])   # the last objective is flat: the tie rule decides

    def batch(w: np.ndarray) -> np.ndarray:
        return np.where(flat[:, None], 1.0, (w - targets[:, None]) ** 2)

    got = opt.fruit_fly_batch(batch, [np.random.default_rng(10 + i) for i in range(4)], population=7, iterations=40)
    for i, r in enumerate(got):
        def one(w: np.ndarray, i: int = i) -> np.ndarray:
            return np.full_like(w, 1.0) if flat[i] else (w - targets[i]) ** 2
        assert r == opt.fruit_fly(one, np.random.default_rng(10 + i), population=7, iterations=40, vectorized=True)
    with pytest.raises(TypeError, match="rngs"):
        opt.fruit_fly_batch(batch, np.random.default_rng(0))
    with pytest.raises(ValueError, match="rngs"):
        opt.fruit_fly_batch(batch, [])
    with pytest.raises(TypeError, match=r"rngs\[1\]"):
        opt.fruit_fly_batch(batch, [np.random.default_rng(0), "seed"])
    with pytest.raises(ValueError, match="shape"):
        opt.fruit_fly_batch(lambda w: w[:, :1], [np.random.default_rng(0)], population=3, iterations=2)


@given(seed=st.integers(0, 2**31), lo=st.floats(-2.0, 0.5), width=st.floats(1e-3, 3.0),
       xatol=st.sampled_from([1e-9, 1e-5, 1e-2]))
def test_batched_bounded_brent_is_scipys_search_bit_for_bit(seed: int, lo: float, width: float, xatol: float) -> None:
    """Every problem of the batched search takes scipy's steps: the same minimiser, value and evaluation count,
    on smooth, oscillating, kinked and flat objectives searched together."""
    from scipy.optimize import minimize_scalar

    rng = np.random.default_rng(seed)
    n = 12
    c = rng.uniform(-1.0, 2.0, (n, 3))
    kind = rng.integers(0, 4, n)

    def one(k: int, x: float) -> float:
        a, b, _ = c[k]
        return [(x - a) ** 2 + b, np.sin(5.0 * x * b) + a * x, abs(x - a), 1.0][kind[k]]

    x, fun, nfev = opt._bounded_brent_batch(lambda idx, xs: np.array([one(k, v) for k, v in zip(idx, xs)]),
                                            lo, lo + width, n, xatol=xatol)
    for k in range(n):
        r = minimize_scalar(lambda v: one(k, v), bounds=(lo, lo + width), method="bounded", options={"xatol": xatol})
        assert (r.x, r.fun, r.nfev) == (x[k], fun[k], nfev[k])


@pytest.mark.parametrize("rule", ["split", "printed"])
@pytest.mark.parametrize("criterion", ["trace", "det"])
def test_fuse_tracks_searches_every_step_as_split_ci_does_alone(rule: str, criterion: str) -> None:
    """fuse_tracks's weights searched for every step at once are split_covariance_intersection's own, bit for bit,
    and so is its fused covariance at them (computed without validating the parts a second time)."""
    sc = two_sensor.two_sensor_scenario(np.diag([150.0**2] * 2), np.diag([120.0**2, 200.0**2]), np.diag([100.0] * 4),
                                        np.random.default_rng(3), runs=4)
    a, b = sc.tracks
    K, n = a.est.shape[1:]
    f = tr.fuse_tracks(a, b, rule, criterion=criterion)
    for k in range(K):
        r = es.split_covariance_intersection(np.zeros(n), a.Pd[k], a.Pi[k], np.zeros(n), b.Pd[k], b.Pi[k],
                                             criterion=criterion, same_omega=rule == "printed")
        assert f.omega[k] == r.omega and np.array_equal(f.P[k], r.P)
    fixed = tr.fuse_tracks(a, b, rule, omega=f.omega, criterion=criterion)   # the public function at every step
    assert np.array_equal(fixed.est, f.est) and np.array_equal(fixed.P, f.P)
