"""Issue 37: the Kalman filter's scalar path for independent axes against its readable matrix recursion and filterpy.

The scalar path (``fusion.filtering.kalman._gains_axes`` and ``_states_axes``) must give the bits of the matrix
recursion (``_gains_matrices``, ``_states_matrices``), which give filterpy's (``tests/test_parity.py``).
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fusion.filtering import kalman as km


def _block(rng: np.random.Generator, scale: float) -> np.ndarray:
    A = rng.normal(size=(2, 2))
    return scale * (A @ A.T + 0.1 * np.eye(2))


def _model(seed: int, axes: int, q: float, sign: float):
    """A model of ``axes`` independent axes: F of unit entries, block-diagonal Q and P0, diagonal R."""
    rng = np.random.default_rng(seed)
    F = np.kron(np.eye(axes), [[1.0, sign], [0.0, 1.0]])
    H = np.zeros((axes, 2 * axes))
    H[np.arange(axes), 2 * np.arange(axes)] = 1.0
    Q = np.zeros((2 * axes, 2 * axes))
    P0 = np.zeros_like(Q)
    for i in range(axes):
        s = slice(2 * i, 2 * i + 2)
        Q[s, s], P0[s, s] = _block(rng, q), _block(rng, float(rng.uniform(1.0, 1e4)))
    R = np.diag(rng.uniform(0.5, 400.0, axes))
    return F, H, Q, R, P0


@given(st.integers(0, 10_000), st.integers(1, 3), st.sampled_from([5, 40, 200]), st.sampled_from([0.0, 1e-6, 1e-2, 1.0, 100.0]),
       st.sampled_from([1.0, -1.0]))
@settings(max_examples=60, deadline=None)
def test_scalar_gains_are_the_matrix_recursion_bit_for_bit(seed: int, axes: int, n_steps: int, q: float,
                                                           sign: float) -> None:
    """gain_sequence on independent axes (the scalar path) equals the matrix recursion, bits and signs of zeros."""
    F, H, Q, R, P0 = _model(seed, axes, q, sign)
    assert km._decoupled_axes(F, H, Q, P0) == axes and km._scalar_path_ok()
    g = km.gain_sequence(F, H, Q, R, P0, n_steps)
    Km, Pm = km._gains_matrices(F, H, Q, np.broadcast_to(R, (n_steps, axes, axes)), P0, n_steps)
    assert np.array_equal(g.K.view(np.uint64), Km.view(np.uint64))
    assert np.array_equal(g.P.view(np.uint64), Pm.view(np.uint64))


@given(st.integers(0, 10_000), st.integers(1, 2), st.integers(1, 2))
@settings(max_examples=40, deadline=None)
def test_scalar_states_are_the_matrix_recursion_bit_for_bit(seed: int, axes: int, runs: int) -> None:
    """filter_runs on one or two runs of independent axes (the scalar path) equals the matrix recursion."""
    F, H, Q, R, P0 = _model(seed, axes, 1.0, 1.0)
    rng = np.random.default_rng(seed + 1)
    g = km.gain_sequence(F, H, Q, R, P0, 50)
    z = 30.0 * rng.standard_normal((runs, 50, axes)) + np.arange(50.0)[None, :, None] * 7.0
    x0 = rng.normal(scale=20.0, size=(runs, 2 * axes))
    est = km.filter_runs(z, g, x0)
    ref = km._states_matrices(z, g, x0)
    assert np.array_equal(est, ref)


def test_the_benchmark_case_is_filterpy_bit_for_bit() -> None:
    """The peers benchmark's single run (4-D CV at T = 1, no fixed point in 100 steps) gives filterpy's states."""
    from filterpy.kalman import KalmanFilter

    m = km.cv_model(1.0)
    Q, R = np.diag([100.0] * 4), np.diag([150.0**2] * 2)
    P0 = np.diag([150.0**2, 1e4, 150.0**2, 1e4])
    rng = np.random.default_rng(5)
    z = np.cumsum(np.full((100, 2), 10.0), axis=0) + 150.0 * rng.standard_normal((100, 2))
    x0 = np.array([z[0, 0], 0.0, z[0, 1], 0.0])
    g = km.gain_sequence(m.F, m.H, Q, R, P0, 100)
    est = km.filter_runs(z[None], g, x0[None])[0]
    kf = KalmanFilter(dim_x=4, dim_z=2)
    kf.F, kf.H, kf.Q, kf.R, kf.P, kf.x = m.F, m.H, Q, R, P0.copy(), x0[:, None].copy()
    for k in range(1, 100):
        kf.predict()
        kf.update(z[k])
        assert np.array_equal(est[k], kf.x[:, 0]) and np.array_equal(g.P[k], kf.P) and np.array_equal(g.K[k], kf.K)


def test_fixed_point_copy_on_the_scalar_path() -> None:
    """A converging filter on the scalar path: the tail (copied once an axis repeats) equals the computed tail."""
    m = km.cv_model(1.0)
    Q, R, P0 = 0.1 * np.diag([0.25, 1.0, 0.25, 1.0]), np.diag([4.0, 9.0]), np.diag([4.0, 10.0, 4.0, 10.0])
    g = km.gain_sequence(m.F, m.H, Q, R, P0, 300)
    Km, Pm = km._gains_matrices(m.F, m.H, Q, np.broadcast_to(R, (300, 2, 2)), P0, 300)
    assert np.array_equal(Pm[-1], Pm[-2])
    assert np.array_equal(g.K, Km) and np.array_equal(g.P, Pm)


@pytest.mark.parametrize("change", ["T", "Q", "P0", "R", "H"])
def test_models_that_couple_or_round_take_the_matrix_recursion(change: str) -> None:
    """A period other than 1, a cross-axis covariance or a non-diagonal R: not the scalar path's model, same results."""
    m = km.cv_model(0.5 if change == "T" else 1.0)
    F, H = m.F, m.H.copy()
    Q, R, P0 = np.diag([1.0, 2.0, 3.0, 4.0]), np.diag([4.0, 9.0]), np.diag([4.0, 10.0, 4.0, 10.0])
    if change == "Q":
        Q[0, 2] = Q[2, 0] = 0.5
    elif change == "P0":
        P0[1, 3] = P0[3, 1] = 1.0
    elif change == "R":
        R[0, 1] = R[1, 0] = 1.0
    elif change == "H":
        H = H[::-1].copy()
    decoupled = bool(km._decoupled_axes(F, H, Q, P0)) and np.array_equal(R, np.diag(np.diag(R)))
    assert not decoupled
    g = km.gain_sequence(F, H, Q, R, P0, 30)
    Km, Pm = km._gains_matrices(F, H, Q, np.broadcast_to(R, (30, 2, 2)), P0, 30)
    assert np.array_equal(g.K, Km) and np.array_equal(g.P, Pm)


def test_without_the_probe_the_matrix_recursion_runs(monkeypatch: pytest.MonkeyPatch) -> None:
    """When the BLAS probe fails, gain_sequence and filter_runs take the matrix recursion (the same numbers here)."""
    F, H, Q, R, P0 = _model(3, 2, 1.0, 1.0)
    z = np.random.default_rng(0).normal(size=(1, 20, 2))
    g, est = km.gain_sequence(F, H, Q, R, P0, 20), None
    est = km.filter_runs(z, g, np.zeros((1, 4)))
    called = []
    monkeypatch.setattr(km, "_PROBE", [False])
    monkeypatch.setattr(km, "_gains_axes", lambda *a: called.append(a))
    monkeypatch.setattr(km, "_states_axes", lambda *a: called.append(a))
    g2 = km.gain_sequence(F, H, Q, R, P0, 20)
    assert not called
    assert np.array_equal(g2.P, g.P) and np.array_equal(km.filter_runs(z, g2, np.zeros((1, 4))), est)
