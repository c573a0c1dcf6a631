"""Fuzz 26a (issue 35), numerical classes: U, W, RB, B, F32, G and D3.

* U: covariances in mixed units (a diagonal change of units of the state) -- ``is_second_moment``,
  ``scalar_lagrange_weights`` and ``eigen_decorrelation_fusion`` decided or computed by an absolute condition
  test; now by the package's covariance rule (``fusion._covariances.SINGULAR_MARGIN``, unit-free);
* W: ``fruit_fly``'s work budget counts what ``fruit_fly_batch`` counts (a loop step per generation);
* RB: ``RangeBearingScenario`` stores tuples of floats (no alias of the caller's list or array) and applies the
  magnitude rule to ``sensors``;
* B: ``belief_study`` with an odd number of snapshots (one independent shift per shifted snapshot);
* F32: float32 weights that sum to one in float32 (``fusion._validation.sums_to_one``, the one simplex rule);
* G, D3: ``glue_all`` checks what it takes (pandas extension arrays looked into) and refuses other types by name.
"""

from __future__ import annotations

import array
import collections
import dataclasses

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fusion.estimates.chernoff import fuse_mixtures_batch, is_second_moment
from fusion.estimates.mixtures import GaussianMixture
from fusion.optimise.scalar import fruit_fly
from fusion.readings import correlated as cr
from fusion.scenarios.range_bearing import RangeBearingScenario

# ---------------------------------------------------------------- U: per-component units

_R0 = np.array([[2.0, 0.5, 0.3, 0.1], [0.5, 1.0, 0.2, 0.4], [0.3, 0.2, 3.0, 0.6], [0.1, 0.4, 0.6, 1.5]])


@settings(max_examples=40, deadline=None)
@given(st.lists(st.integers(-6, 6), min_size=2, max_size=2), st.sampled_from([(0.5, 0.5), (0.3, 0.7), (0.9, 0.1)]),
       st.sampled_from([(0.5, 0.5), (0.3, 0.7)]))
def test_u_is_second_moment_is_invariant_to_each_components_units(powers, eps, eps0):
    """rho is invariant to a change of units of each state component (a linear map of the state)."""
    C = np.array([[1.0, 0.3], [0.3, 2.0]])
    covs = np.stack([C, np.diag([2.0, 0.5])])
    means = np.array([[0.0, 1.0], [0.5, -0.5]])
    t = 10.0 ** np.array(powers, dtype=float)
    ref = is_second_moment(means, covs, eps, eps0)
    got = is_second_moment(means * t, covs * t[:, None] * t[None, :], eps, eps0)
    assert got == pytest.approx(ref, rel=1e-9)


def test_u_is_second_moment_is_one_at_eps0_in_mixed_units():
    C = np.diag([1e-6, 1e6])
    assert is_second_moment(np.zeros((2, 2)), np.stack([C, 2 * C]), [0.5, 0.5], [0.5, 0.5]) == pytest.approx(1.0)


def test_u_is_second_moment_outside_the_finite_variance_region_is_still_inf():
    """Lambda = 2 P^-1 - G^-1 not positive definite: inf, in any units."""
    for s in (1.0, 1e6):
        C = np.diag([1 / s, s])
        assert is_second_moment(np.zeros((2, 2)), np.stack([C, 100 * C]), [0.0, 1.0], [1.0, 0.0]) == np.inf


@settings(max_examples=30, deadline=None)
@given(st.lists(st.integers(-6, 6), min_size=6, max_size=6))
def test_u_scalar_lagrange_weights_accepts_a_positive_diagonal_R_in_any_units(powers):
    R = np.diag(10.0 ** np.array(powers, dtype=float))
    w = cr.scalar_lagrange_weights(R, 2)
    assert w.shape == (2, 6) and np.isfinite(w).all()
    assert w[0, ::2].sum() == pytest.approx(1.0)


def test_u_scalar_lagrange_weights_still_refuses_a_singular_R_by_name():
    with pytest.raises(ValueError, match=r"^R\b"):
        cr.scalar_lagrange_weights(np.ones((4, 4)), 2)


@settings(max_examples=30, deadline=None)
@given(st.lists(st.integers(-6, 6), min_size=4, max_size=4))
def test_u_eigen_decorrelation_fusion_equals_gls_in_mixed_units(powers):
    H = np.kron(np.ones((2, 1)), np.eye(2))
    t = 10.0 ** np.array(powers, dtype=float)
    R = R0 = _R0 * t[:, None] * t[None, :]
    z = t * np.array([1.0, 2.0, 1.5, 2.5])
    g, e = cr.gls(H, R0, z), cr.eigen_decorrelation_fusion(H, R, z)
    # compared in units of each estimated component's own standard deviation
    sd = np.sqrt(np.diag(g.P))
    assert np.allclose(e.x / sd, g.x / sd, rtol=0, atol=1e-8)
    assert np.allclose(e.P / np.outer(sd, sd), g.P / np.outer(sd, sd), rtol=0, atol=1e-8)


def test_u_eigen_decorrelation_fusion_of_several_runs_equals_gls():
    H = np.kron(np.ones((2, 1)), np.eye(2))
    z = np.random.default_rng(0).normal(size=(4, 3))
    assert np.allclose(cr.eigen_decorrelation_fusion(H, _R0, z).x, cr.gls(H, _R0, z).x, atol=1e-12)


# ---------------------------------------------------------------- W: fruit_fly's work budget

@pytest.mark.parametrize("population, iterations", [(1, 10**7), (100, 10**7), (1000, 10**6)])
def test_w_fruit_fly_counts_its_generations(population, iterations):
    with pytest.raises(ValueError, match=r"^population and iterations ask for .*work budget"):
        fruit_fly(lambda w: (w - 0.3) ** 2, np.random.default_rng(0), population=population, iterations=iterations)


def test_w_fruit_fly_book_size_runs():
    r = fruit_fly(lambda w: (w - 0.3) ** 2, np.random.default_rng(0), population=30, iterations=200)
    assert r.n_evaluations == 6000


# ---------------------------------------------------------------- RB: RangeBearingScenario stores what it checked

def test_rb_scenario_keeps_no_alias_of_the_callers_array_or_list():
    S = np.array([[0.0, 0.0], [2000.0, 0.0]])
    x0 = np.array([800.0, 15.0, 600.0, 10.0])
    sc = RangeBearingScenario(sensors=S, x0=x0)
    S *= 1.5
    x0 *= 2.0
    assert sc.sensors == ((0.0, 0.0), (2000.0, 0.0)) and sc.x0 == (800.0, 15.0, 600.0, 10.0)
    lst = [[0, 0], [2000, 0]]
    sc2 = RangeBearingScenario(sensors=lst, p0_std=[30, 3, 30, 3])
    lst.append([5000, 0])
    assert isinstance(sc2.sensors, tuple) and len(sc2.sensors) == 2 and isinstance(sc2.p0_std, tuple)
    assert hash(sc2) == hash(RangeBearingScenario(sensors=((0.0, 0.0), (2000.0, 0.0))))
    assert sc2 == RangeBearingScenario(sensors=((0.0, 0.0), (2000.0, 0.0)))


def test_rb_default_scenario_is_unchanged():
    sc = RangeBearingScenario()
    assert sc.sensors == ((0.0, 0.0), (2000.0, 0.0), (1000.0, 2000.0))
    assert dataclasses.replace(sc) == sc


@pytest.mark.parametrize("sensors", [((1e200, 0.0),), ((1e-200, 0.0),), ((0.0, 0.0), (0.0, 1e-320))])
def test_rb_sensors_follow_the_magnitude_rule(sensors):
    with pytest.raises(ValueError, match=r"^sensors\b"):
        RangeBearingScenario(sensors=sensors)


# ---------------------------------------------------------------- B: belief_study's snapshots

@pytest.mark.parametrize("snapshots", [3, 5, 7])
def test_b_belief_study_odd_snapshots_draw_one_shift_each(snapshots):
    from fusion.scenarios.lecture_weighting.belief import belief_study

    from fusion import readings as rd

    r = belief_study(snapshots=snapshots)
    assert r.shifted.sum() == (snapshots + 1) // 2 and r.eig_w.shape[0] == snapshots
    # each shifted snapshot has its own draw of the shift (at 3 the two shared one): rebuilt from the seeds
    sig = np.array([0.5, 1.0, 2.0, 4.0])
    snaps = 900.0 + np.random.default_rng(2402).normal(size=(snapshots, 4)) * sig
    snaps[::2, 0] += np.random.default_rng(2403).uniform(0, 10, size=(snapshots + 1) // 2)
    assert np.allclose(r.eig_w, rd.fuse_epochs(snaps, "belief_degree").weights, rtol=0, atol=1e-12)


# ---------------------------------------------------------------- F32: one simplex rule

def test_f32_gaussian_mixture_accepts_float32_weights_and_rebuilds():
    for w in ([0.4, 0.6], [1 / 3] * 3):
        w32 = np.array(w, np.float32)
        g = GaussianMixture(w32, np.zeros((len(w), 2)), np.stack([np.eye(2)] * len(w)))
        assert g.weights.dtype == np.float64 and abs(g.weights.sum() - 1.0) <= 1e-12
        assert np.array_equal(dataclasses.replace(g).weights, g.weights)
    with pytest.raises(ValueError, match=r"^weights must"):
        GaussianMixture(np.array([0.4, 0.7], np.float32), np.zeros((2, 2)), np.stack([np.eye(2)] * 2))
    with pytest.raises(ValueError, match=r"^weights must"):   # float64 keeps its own tolerance
        GaussianMixture(np.array([0.4, 0.6], np.float32).astype(float), np.zeros((2, 2)), np.stack([np.eye(2)] * 2))


def test_f32_fuse_mixtures_batch_accepts_float32_weights_and_eps0():
    w = np.array([[[0.4, 0.6], [0.3, 0.7]]], np.float32)
    m = np.zeros((1, 2, 2, 2))
    m[0, :, 1] = 1
    c = np.broadcast_to(np.eye(2), (1, 2, 2, 2, 2)).copy()
    a = fuse_mixtures_batch(w, m, c, [np.random.default_rng(0)], n_samples=50, optimiser="none",
                            eps0=np.array([0.4, 0.6], np.float32))
    assert len(a) == 1
    with pytest.raises(ValueError, match=r"^weights must"):
        fuse_mixtures_batch(w * 1.01, m, c, [np.random.default_rng(0)], n_samples=50, optimiser="none")


def test_f32_grid_log_normaliser_accepts_float32_eps():
    from fusion.scenarios.two_mixtures import grid_log_normaliser

    gA = GaussianMixture(np.array([0.5, 0.5]), np.array([[0.0, 0.0], [1.0, 0.0]]), np.stack([np.eye(2)] * 2))
    gB = GaussianMixture(np.array([1.0]), np.array([[0.5, 0.5]]), np.eye(2)[None])
    e32 = np.array([0.4, 0.6], np.float32)
    a = grid_log_normaliser([gA, gB], e32, limit=6.0, n=41)
    b = grid_log_normaliser([gA, gB], e32.astype(float) / e32.astype(float).sum(), limit=6.0, n=41)
    assert np.allclose(a.log_z, b.log_z, rtol=0, atol=1e-6)   # eps differ by float32 round-off
    with pytest.raises(ValueError, match=r"^eps must"):
        grid_log_normaliser([gA, gB], np.array([0.4, 0.7], np.float32), limit=6.0, n=41)


@settings(max_examples=60, deadline=None)
@given(st.lists(st.floats(0.01, 1.0), min_size=1, max_size=8), st.sampled_from([np.float32, np.float16]))
def test_f32_low_precision_weights_normalised_in_their_precision_are_accepted(raw, dtype):
    from fusion._validation import sums_to_one

    w = np.array(raw, dtype=dtype)
    w = (w / w.sum()).astype(dtype)
    assert sums_to_one(w.astype(float), w)
    assert not sums_to_one(w.astype(float) * 1.05, (w * 1.05).astype(dtype))   # beyond 2 n eps (n <= 8)


# ---------------------------------------------------------------- G, D3: glue_all's one rule

def _glue(monkeypatch, value):
    import myst_nb

    from fusion.book.glue import glue_all

    seen = {}
    monkeypatch.setattr(myst_nb, "glue", lambda k, v, display: seen.__setitem__(k, v))
    glue_all({"k": value})
    return seen


@pytest.mark.parametrize("value", [pd.array([1.0, None], dtype="Float64"), pd.array([1, None], dtype="Int64"),
                                   pd.Categorical([np.nan, 1.0]), pd.arrays.SparseArray([np.nan, 1.0]),
                                   [pd.array([1.0, np.nan], dtype="Float64")]])
def test_g_pandas_extension_arrays_are_looked_into(monkeypatch, value):
    with pytest.raises(ValueError, match=r"^values\['k'\] must be finite"):
        _glue(monkeypatch, value)


@pytest.mark.parametrize("value", [pd.array([1.0, 2.0], dtype="Float64"), pd.Categorical(["a", "b"]),
                                   pd.arrays.SparseArray([0.0, 1.0]), 1.5, 3, True, None, "nan", np.float32(2.0),
                                   [1.0, (2, {"a": 3.0})], range(3)])
def test_g_finite_values_are_still_glued(monkeypatch, value):
    assert "k" in _glue(monkeypatch, value)


@pytest.mark.parametrize("value", [collections.deque([float("nan")]), collections.deque([1.0]), array.array("d", [1.0]),
                                   {"a": 1.0}.values(), {"a": 1.0}.keys(), (x for x in [1.0]),
                                   np.ma.masked_invalid([1.0, np.nan]), np.ma.array([1.0, 2.0]), [collections.deque([1.0])],
                                   object()])
def test_d3_other_containers_are_refused_by_type(monkeypatch, value):
    # (a range is glued since fix57b, fuzz 50a D1: an atom of ints, its text ``range(0, 3)`` bounded; it holds no NaN)
    with pytest.raises(TypeError, match=r"^values\['k'\] must be"):
        _glue(monkeypatch, value)
