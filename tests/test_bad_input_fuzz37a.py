"""Fuzz 36a's input-shape budgets (fix37a): arrays and work that a function builds from its INPUT SHAPES (a state
dimension times the steps, the number of sensors, Gaussians or tracks, a state or factor dimension) are refused by
name before any work (rules 9 and 17), and the range-bearing tracking budget counts ``swarm_options.iterations``.
Inputs are small (at most 2e5 entries); the refusal comes before anything of the counted size is built."""
from __future__ import annotations

import numpy as np
import pytest

BUDGET = "beyond the memory budget"


def test_gain_sequence_counts_steps_times_state():
    from fusion.filtering.kalman import gain_sequence
    n = 100
    with pytest.raises(ValueError, match=f"n_steps and the sizes of F and H .*{BUDGET}"):
        gain_sequence(np.eye(n), np.eye(n)[:1], 0.1 * np.eye(n), np.eye(1), np.eye(n), 100000)


def test_local_track_counts_steps_times_state():
    from fusion.filtering.tracks import local_track
    n = 100
    P0 = np.eye(n)
    with pytest.raises(ValueError, match=f"z and the sizes of F and H .*{BUDGET}"):
        local_track(np.zeros((1, 100000, 1)), np.eye(n), np.eye(n)[:1], 0.1 * P0, np.eye(1), np.zeros((1, n)),
                    0.5 * P0, 0.5 * P0)


def test_fusion_loop_counts_steps_times_state():
    from fusion.filtering.feedback import fusion_loop
    n = 100
    P0, z, x0 = np.eye(n), np.zeros((1, 100000, 1)), np.zeros((1, n))
    with pytest.raises(ValueError, match=f"z1 and the sizes of F and H .*{BUDGET}"):
        fusion_loop(z, z + 0.1, x0, x0, np.eye(n), np.eye(n)[:1], 0.1 * P0, np.eye(1), 2 * np.eye(1), 0.5 * P0,
                    0.5 * P0, 0.5 * P0, "split", "split")


def test_consistency_awf_counts_sensor_pairs():
    from fusion.readings.consistency import consistency_awf
    with pytest.raises(ValueError, match=f"^X ask .*{BUDGET}"):
        consistency_awf(np.random.default_rng(0).normal(size=(8, 25000)), 3.0)


@pytest.mark.parametrize("name", ["ridge", "least_squares", "plugin_ridge"])
def test_ridge_family_counts_state_dimension(name):
    from fusion.readings import biased
    rng = np.random.default_rng(0)
    H, y = rng.normal(size=(3, 66666)), rng.normal(size=3)
    args = (H, y, 0.1) if name == "ridge" else (H, y)
    with pytest.raises(ValueError, match=f"^H ask .*{BUDGET}"):
        getattr(biased, name)(*args)


def test_gls_low_rank_counts_factor_rank():
    from fusion.readings.correlated import gls_low_rank
    rng = np.random.default_rng(0)
    with pytest.raises(ValueError, match=f"^U ask .*{BUDGET}"):
        gls_low_rank(np.eye(6)[:, :2], np.ones(6), rng.normal(size=(6, 33332)), np.zeros(6))


def test_fuzzy_cluster_fusion_counts_tracks_cubed():
    from fusion.estimates.fuzzy_cluster import fuzzy_cluster_fusion
    N = 2000
    xs = np.random.default_rng(0).normal(size=(N, 2))
    with pytest.raises(ValueError, match=f"^xs and Ps ask .*{BUDGET}"):
        fuzzy_cluster_fusion(xs, np.broadcast_to(np.eye(2), (N, 2, 2)).copy(), 0.01)


@pytest.mark.parametrize("N, budget", [(20000, BUDGET), (5000, "beyond the work budget")])
def test_chernoff_weights_count_gaussians(N, budget):
    from fusion.estimates.chernoff import covariance_intersection_weights, gaussian_chernoff_weights
    rng = np.random.default_rng(0)
    covs = (1.0 + rng.random(N))[:, None, None]
    with pytest.raises(ValueError, match=f"^means and covs ask .*{budget}"):
        gaussian_chernoff_weights(rng.normal(size=(N, 1)), covs)
    with pytest.raises(ValueError, match=f"^covs ask .*{budget}"):
        covariance_intersection_weights(covs)


def test_chernoff_weights_keep_many_small_gaussians():
    """Valid input well inside the budget still works (N = 50 scalar Gaussians)."""
    from fusion.estimates.chernoff import covariance_intersection_weights
    w = covariance_intersection_weights((1.0 + np.arange(50.0))[:, None, None])
    assert w.shape == (50,) and np.isclose(w.sum(), 1.0)


def _tiny_scenario(frames):
    from fusion.scenarios import range_bearing as rb
    return rb.RangeBearingScenario(frames=frames, n_particles=60, n_samples=60, n_central=100, em_iterations=2,
                                   n_components=1)


def test_tracking_budget_counts_swarm_iterations():
    """Fuzz 36a C7: 200 frames at 33,000 swarm generations (~1,600 CPU-s) are refused at entry, naming the options."""
    from fusion.optimise.swarm import SwarmOptions
    from fusion.scenarios import range_bearing as rb
    with pytest.raises(ValueError, match="swarm_options.iterations .*beyond the work budget"):
        rb.run_tracking_batch(_tiny_scenario(200), np.random.SeedSequence(1).spawn(1),
                              swarm_options=SwarmOptions(iterations=33000, tol=0.0))


def test_tracking_budget_default_swarm_unchanged():
    """The default swarm (inside TRACK_STEP) adds nothing, so chapter 06's own study keeps its count; a longer swarm
    adds its generations to every run-frame."""
    from fusion.optimise.swarm import SwarmOptions
    from fusion.scenarios import range_bearing as rb
    sc = _tiny_scenario(2)
    base = rb._tracking_work(sc, 1, "runs")
    assert rb._tracking_work(sc, 1, "runs", SwarmOptions()) == base
    assert rb._tracking_work(sc, 1, "runs", SwarmOptions(iterations=20000)) > base + 2 * 19950 * rb.TRACK_SWARM_STEP


def test_filter_runs_counts_runs_times_state():
    """The estimates (runs, K, n) of an n-state model from z of m < n readings (z within the input budget)."""
    from fusion.filtering.kalman import filter_runs, gain_sequence
    n = 200
    g = gain_sequence(np.eye(n), np.eye(n)[:1], 0.1 * np.eye(n), np.eye(1), np.eye(n), 10)
    with pytest.raises(ValueError, match=f"^z and gains ask .*{BUDGET}"):  # refused before x0 is read
        filter_runs(np.zeros((200000, 10, 1)), g, np.zeros((1, n)))
