"""Time registration (source 002): exactness, affinity, exact statistics, bad input."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from fusion import registration as reg

T1 = reg.sample_times(1.0, 2.0, 40.0)
T2 = reg.sample_times(3.0, 5.0, 40.0)


def truth(t: np.ndarray) -> np.ndarray:
    return t + t**2  # x = v0 t + a t^2 / 2 with v0 = 1, a = 2


def test_sample_counts_of_the_scenario() -> None:
    assert T1.size == 20 and T1[0] == 1.0 and T1[-1] == 39.0
    assert T2.size == 8 and T2[-1] == 38.0


# (coefficients below 1e-140 are zero: they would give readings below 1e-150, which the shared validation
# refuses, issue 35 rule 2)
@given(c=st.lists(st.floats(-50, 50).map(lambda v: 0.0 if abs(v) < 1e-140 else v), min_size=3, max_size=3), seed=st.integers(0, 2**31))
def test_three_point_is_exact_on_quadratics(c: list[float], seed: int) -> None:
    rng = np.random.default_rng(seed)
    t = np.cumsum(rng.uniform(0.5, 3.0, 12))
    q = rng.uniform(t[0] - 2, t[-1] + 2, 30)
    f = lambda s: c[0] + c[1] * s + c[2] * s**2  # noqa: E731
    np.testing.assert_allclose(reg.three_point(t, f(t), q), f(q), rtol=1e-9, atol=1e-7)
    np.testing.assert_allclose(reg.three_point(t, f(t), q, causal=True), f(q), rtol=1e-9, atol=1e-7)


@given(c=st.lists(st.floats(-50, 50).map(lambda v: 0.0 if abs(v) < 1e-140 else v), min_size=2, max_size=2), seed=st.integers(0, 2**31))
def test_two_point_and_least_squares_are_exact_on_lines(c: list[float], seed: int) -> None:
    rng = np.random.default_rng(seed)
    t = np.cumsum(rng.uniform(0.5, 2.0, 15))
    q = np.sort(rng.uniform(t[3], t[-1], 10))
    f = lambda s: c[0] + c[1] * s  # noqa: E731
    np.testing.assert_allclose(reg.two_point(t, f(t), q), f(q), rtol=1e-9, atol=1e-7)
    np.testing.assert_allclose(reg.least_squares(t, f(t), q, window=6.0), f(q), rtol=1e-9, atol=1e-6)


def test_two_point_error_on_the_quadratic_matches_the_remainder() -> None:
    """Interpolation error (a/2)(t - t_i)(t_{i+1} - t) for x = t + t^2 (a = 2)."""
    est = reg.two_point(T1, truth(T1), T2)
    i = np.searchsorted(T1, T2, side="right") - 1
    i = np.clip(i, 0, T1.size - 2)
    derived = (T2 - T1[i]) * (T1[i + 1] - T2)  # (a/2) = 1
    np.testing.assert_allclose(est - truth(T2), derived, atol=1e-9)
    np.testing.assert_allclose(est - truth(T2), np.tile([0.0, 1.0], 4), atol=1e-9)


def test_blair_closed_form_equals_lstsq_and_its_variance() -> None:
    rng = np.random.default_rng(3)
    for n in (2, 3, 5, 8):
        z = rng.normal(size=n)
        W = np.column_stack([np.ones(n), (np.arange(1, n + 1) - n) * 0.7])
        coef, *_ = np.linalg.lstsq(W, z, rcond=None)
        est = reg.blair_ls(z, 0.7)
        assert (est.z, est.zdot) == pytest.approx(tuple(coef))
        var = np.linalg.inv(W.T @ W)[0, 0]
        assert var == pytest.approx(2 * (2 * n - 1) / (n * (n + 1)))


def test_least_squares_equals_blair_on_an_integer_ratio() -> None:
    t = np.arange(1.0, 21.0)
    z = np.random.default_rng(0).normal(size=t.size)
    for tk in (5.0, 10.0, 20.0):
        sel = (t > tk - 4) & (t <= tk)
        assert reg.least_squares(t, z, [tk], window=4.0)[0] == pytest.approx(reg.blair_ls(z[sel], 1.0).z)


@pytest.mark.parametrize("name", ["two", "three", "ls", "kf", "improved"])
def test_methods_are_affine_and_expected_mse_matches_monte_carlo(name: str) -> None:
    sigma = 1.0
    f = {
        "two": lambda z: reg.two_point(T1, z, T2),
        "three": lambda z: reg.three_point(T1, z, T2),
        "ls": lambda z: reg.least_squares(T1, z, T2, 5.0),
        "kf": lambda z: reg.kalman_register(T1, z, T2, sigma),
        "improved": lambda z: reg.improved_register(T1, z, T2, sigma),
    }[name]
    z0 = truth(T1)
    dec = reg.affine_decomposition(f, z0)
    f0, A = dec.f0, dec.A
    rng = np.random.default_rng(1)
    v = rng.normal(0, sigma, T1.size)
    np.testing.assert_allclose(f(z0 + v), f0 + A @ v, atol=1e-8)  # affine
    runs = 2000
    noise = rng.normal(0, sigma, (runs, T1.size))
    # each run registers its own noisy samples (not the decomposition whose expectation is tested)
    mse = np.array([np.mean((f(z0 + v) - truth(T2)) ** 2) for v in noise])
    expected = reg.expected_mse(f, z0, truth(T2), sigma)
    # four standard errors: a false failure has probability < 1e-4 per test
    assert abs(mse.mean() - expected) < 4 * mse.std(ddof=1) / np.sqrt(runs)


def test_registering_onto_a_sample_returns_it() -> None:
    z = truth(T1) + np.random.default_rng(2).normal(size=T1.size)
    q = T1[[0, 4, 10, 19]]
    np.testing.assert_allclose(reg.two_point(T1, z, q), z[[0, 4, 10, 19]])
    np.testing.assert_allclose(reg.three_point(T1, z, q), z[[0, 4, 10, 19]])
    xs = reg.kalman_filter(T1, z, 1.0).x
    np.testing.assert_allclose(reg.improved_register(T1, z, q, 1.0), xs[[0, 4, 10, 19], 0])
    np.testing.assert_allclose(reg.kalman_register(T1, z, q, 1.0), xs[[0, 4, 10, 19], 0])


def test_kalman_filter_matches_a_hand_written_recursion() -> None:
    z = truth(T1) + np.random.default_rng(4).normal(size=T1.size)
    kf = reg.kalman_filter(T1, z, 1.0, 1e-2, 1e-3)
    xs, Ps = kf.x, kf.P
    x = np.array([z[0], 0.0, 0.0])
    P = np.diag([1.0, 100.0, 100.0])
    H = np.array([[1.0, 0.0, 0.0]])
    Q = np.diag([0.0, 1e-2, 1e-3])
    for n in range(T1.size):
        if n:
            F = reg.ca_transition(T1[n] - T1[n - 1])
            x, P = F @ x, F @ P @ F.T + Q
        S = H @ P @ H.T + 1.0
        K = P @ H.T / S
        x = x + (K * (z[n] - x[0])).ravel()
        P = (np.eye(3) - K @ H) @ P
        np.testing.assert_allclose(xs[n], x, rtol=1e-9, atol=1e-9)
    assert np.all(np.linalg.eigvalsh(Ps[-1]) > 0)


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: reg.two_point([0.0, 1.0], [1.0], [0.5]), "equal lengths"),
        (lambda: reg.two_point([0.0, 0.0], [1.0, 2.0], [0.5]), "strictly increasing"),
        (lambda: reg.two_point([1.0, 0.0], [1.0, 2.0], [0.5]), "strictly increasing"),
        (lambda: reg.two_point([0.0], [1.0], [0.5]), "at least 2"),
        (lambda: reg.three_point([0.0, 1.0], [1.0, 2.0], [0.5]), "at least 3"),
        (lambda: reg.two_point([0.0, np.nan], [1.0, 2.0], [0.5]), "finite"),
        (lambda: reg.two_point([0.0, 1.0], [1.0, 2.0], [np.inf]), "finite"),
        (lambda: reg.two_point([[0.0, 1.0]], [[1.0, 2.0]], [0.5]), "1-D"),
        (lambda: reg.kalman_filter([0.0, 1.0], [1.0, 2.0], sigma=0.0), "sigma"),
        (lambda: reg.kalman_filter([0.0, 1.0], [1.0, 2.0], sigma=1.0, q_v=-1.0), "non-negative"),
        (lambda: reg.least_squares([0.0, 10.0], [1.0, 2.0], [5.0], window=2.0), "fewer than 2"),
        (lambda: reg.blair_ls([1.0], 1.0), "at least 2"),
        (lambda: reg.sample_times(0.0, -1.0, 10.0), "period"),
    ],
)
def test_bad_input_raises(call, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        call()
