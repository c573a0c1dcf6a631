"""Readable step-by-step functions against the fast kernels the book runs (issue 36).

The chapters teach with the readable functions (one equation each) and compute their studies with
vectorised kernels; these tests hold the two to the same numbers, so a change to either shows here.
"""
from __future__ import annotations

import numpy as np
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from fusion.estimates.ci import ci_objective
from fusion.optimise.scalar import fruit_fly
from fusion.readings import fusion_set as fs
from fusion.scenarios import two_sensor

readings = arrays(np.float64, st.integers(3, 9), elements=st.floats(-50.0, 50.0, allow_nan=False, allow_subnormal=False)
                  .map(lambda v: 0.0 if abs(v) < 1e-100 else v))  # data magnitudes: 0 or >= 1e-150 (shared rule)


@settings(max_examples=200, deadline=None)
@given(x=readings, scale=st.floats(0.5, 20.0), include_self=st.booleans())
def test_fusion_set_steps_compose_to_the_kernel(x: np.ndarray, scale: float, include_self: bool) -> None:
    """Eq. 5 (members), eqs. 6-7 (C), eq. 8 (mu), eq. 9 (tau), eqs. 10-11 (weights), one function each,
    give the weights and the fused value of :func:`optimal_fusion_set` (the vectorised kernel)."""
    members = fs.optimal_set_members(x)
    xs = x[members]
    C = fs.fusion_degree_matrix(xs, scale=scale)
    mu = fs.consistency_degree(C)
    tau = fs.distribution_balance(C, include_self=include_self)
    assume(np.all(np.isfinite(tau)))  # a member with S = 0 takes the limit of eq. 11 (tested elsewhere)
    omega = mu * tau  # eq. 10
    w = omega / omega.sum()  # eq. 11
    got = fs.optimal_fusion_set(x, scale=scale, include_self=include_self)
    np.testing.assert_array_equal(got.members, members)
    # eq. 9 is ill-conditioned for readings equal to within a few ulps: the deviations mu_i - c_ij carry a rounding
    # error of about m eps, so sqrt(S_i) (and the weights) one of about m eps sqrt(m) / sqrt(S_i) relative
    m = xs.size
    S_min = float(np.min(1.0 / (tau * m) ** 2))  # "left" form: tau = 1 / (sqrt(S) m)
    rtol = 1e-12 + 10 * m ** 1.5 * np.finfo(float).eps / np.sqrt(S_min)
    np.testing.assert_allclose(got.weights[members], w, rtol=rtol, atol=1e-15)
    assert np.all(got.weights[~members] == 0.0)
    np.testing.assert_allclose(got.value, float(w @ xs), rtol=rtol, atol=1e-12)


@settings(max_examples=25, deadline=None)
@given(x=arrays(np.float64, st.tuples(st.integers(1, 6), st.integers(3, 7)),
                elements=st.floats(-50.0, 50.0, allow_nan=False, allow_subnormal=False)
                .map(lambda v: 0.0 if abs(v) < 1e-100 else v)))
def test_epochs_kernel_equals_one_epoch_at_a_time(x: np.ndarray) -> None:
    batch = fs.fuse_epochs(x, "optimal_fusion_set")
    for k, row in enumerate(x):
        one = fs.optimal_fusion_set(row)
        np.testing.assert_allclose(batch.values[k], one.value, rtol=1e-13, atol=1e-12)
        np.testing.assert_allclose(batch.weights[k], one.weights, rtol=1e-13, atol=1e-15)


def test_per_step_weights_equal_fruit_fly_step_by_step() -> None:
    """Chapter 05's batched FOA (every step's swarm flies together) gives, to the last bit, the weight
    :func:`fruit_fly` finds on each step's covariances alone with that step's generator."""
    R = np.eye(2) * 2500.0
    Q = np.diag([0.0, 1.0, 0.0, 1.0])
    sc = two_sensor.two_sensor_scenario(R, R / 9, Q, np.random.default_rng(1), runs=2, T=5.0)
    a, b = sc.tracks
    seed = 7
    w_fruit_fly, _ = two_sensor.per_step_weights(a, b, seed=seed, population=10, iterations=25)
    for k in range(0, a.gains.P.shape[0], max(1, a.gains.P.shape[0] // 6)):
        P1, P2 = a.gains.P[k], b.gains.P[k]
        one = fruit_fly(lambda w, P1=P1, P2=P2: float(ci_objective(w, P1, P2)), np.random.default_rng(seed + k),
                        population=10, iterations=25)
        assert w_fruit_fly[k] == one.x, k


@given(base=st.floats(0.5, 1.0), n=st.integers(3, 9), ulps=st.lists(st.integers(0, 1), min_size=9, max_size=9), include_self=st.booleans())
def test_readings_equal_to_rounding_take_the_limit_of_eq_11(base: float, n: int, ulps: list[int],
                                                           include_self: bool) -> None:
    """Readings within an ulp of each other (at most eps apart, scale 1: every c_ij within an ulp of 1): every S_i is
    zero to rounding (below the m^3 eps^2 floor), so
    eq. 11's limit gives the weights in proportion to mu in the readable steps and in the kernel alike (not an
    arbitrary member taking all the weight because its rounding noise happened to be exactly zero)."""
    x = np.array([np.nextafter(base, np.inf) if k else base for k in ulps[:n]], dtype=float)  # base or 1 ulp above
    members = fs.optimal_set_members(x)
    C = fs.fusion_degree_matrix(x[members], scale=1.0)
    tau = fs.distribution_balance(C, include_self=include_self)
    assert np.all(np.isinf(tau))
    mu = fs.consistency_degree(C)
    got = fs.optimal_fusion_set(x, scale=1.0, include_self=include_self)
    np.testing.assert_allclose(got.weights[members], mu / mu.sum(), rtol=1e-12)
