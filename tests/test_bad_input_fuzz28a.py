"""Fuzz 28a (issue 35): regressions of the fixes of cases C3-C6 and D1, D3-D5 (report /work/tmp/fuzz28a/report.md).

C3/D1: float32/float16 weights accepted within their own precision are divided by their sum before use
(``fusion._validation.renormalised``); C4/D3: a short-float published value "cannot hold" its decimals only when
its dtype's spacing exceeds the printed step; C5: a position on a sensor and a collapsed local posterior are refused
naming ``sc``; C6: a result spec's refusal of what a public function computed names the caller's arguments; D4: the
exact comparison's round-off note is the tie rule; D5: a SeedSequence is spawned from (numpy semantics, documented).
"""

import dataclasses
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fusion.book.ledger import PublishedValues


# --- C3 / D1: short-float weights renormalised ------------------------------------------------------------------------

@pytest.mark.parametrize("w", [np.full(1000, 1 / 1000, np.float16) * np.float16(0.995), np.full(3, 1 / 3, np.float16)])
def test_c3_effective_sample_size_of_float16_weights_is_at_most_q(w):
    from fusion.filtering.particles import effective_sample_size
    ess = effective_sample_size(w)
    assert 1.0 <= ess <= w.size and ess == pytest.approx(w.size, rel=1e-12)


@settings(max_examples=40, deadline=None)
@given(st.lists(st.integers(1, 1000), min_size=6, max_size=40), st.sampled_from([np.float16, np.float32, np.float64]),
       st.floats(0.0, 1.0))
def test_c3_effective_sample_size_stays_in_its_documented_range(counts, dtype, short):
    """Weights summing to one within their accepted tolerance (float16: its capped 1 %, float64: the 1e-6 floor)."""
    from fusion.filtering.particles import effective_sample_size
    factor = 1.0 - short * (4e-3 if dtype is np.float16 else 5e-7)
    w = (np.array(counts, float) / sum(counts) * factor).astype(dtype)
    assert 1.0 <= effective_sample_size(w) <= w.size


def test_d1_short_float_exponents_are_used_summing_to_one():
    from fusion.estimates.chernoff import chernoff_fuse_gaussians, check_simplex
    e16 = np.full(6, 0.99 / 6, np.float16)   # sums to 0.99: accepted within float16's capped tolerance
    assert check_simplex(e16).sum() == pytest.approx(1.0, abs=1e-15)
    means, covs = np.zeros((6, 2)), np.stack([np.eye(2) * (i + 1) for i in range(6)])
    fused = chernoff_fuse_gaussians(means, covs, e16)
    exact = chernoff_fuse_gaussians(means, covs, np.full(6, 1 / 6))
    np.testing.assert_allclose(fused.P, exact.P, rtol=1e-12)   # not the 1 % larger covariance of sum 0.99


def test_d1_particle_weights_in_float16_are_renormalised():
    from fusion.filtering.particles import weighted_moments
    x = np.arange(12.0).reshape(6, 2)
    w16 = np.full(6, 0.99 / 6, np.float16)
    np.testing.assert_allclose(weighted_moments(x, w16).mean, x.mean(axis=0), rtol=1e-12)


# --- C4 / D3: "cannot hold" is the dtype's spacing beyond the printed step --------------------------------------------

@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2**24 - 1))
def test_c4_an_exact_float32_integer_holds_zero_decimals(n):
    assert PublishedValues(np.array([n], np.float32), [float(n)], 0).status() == "reproduced"


@pytest.mark.parametrize("n", [512, 1000, 2047])
def test_c4_an_exact_float16_integer_holds_zero_decimals(n):
    assert PublishedValues(np.array([n], np.float16), [float(n)], 0).status() == "reproduced"


@pytest.mark.parametrize("value, dtype", [(2.0**24, np.float32), (2048.0, np.float16), (65504.0, np.float16)])
def test_c4_d3_beyond_the_integer_range_the_dtype_cannot_hold_zero_decimals(value, dtype):
    with warnings.catch_warnings():
        warnings.simplefilter("error")   # D3: no numpy overflow warning before the refusal at float16's maximum
        with pytest.raises(ValueError, match=r"published\[0\].*cannot hold"):
            PublishedValues(np.array([value], dtype), [value], 0)


def test_c4_a_float32_half_at_zero_decimals_is_an_extra_decimal():
    with pytest.raises(ValueError, match=r"published\[0\].*more decimals"):
        PublishedValues(np.array([4194304.5], np.float32), [4194304.5], 0)


# --- C5 / C6: range-bearing refusals name sc --------------------------------------------------------------------------

def _sc(**kw):
    from fusion.scenarios.range_bearing import RangeBearingScenario
    small = dict(frames=2, n_particles=60, n_components=1, n_samples=60, n_central=100, em_iterations=2)
    return RangeBearingScenario(**{**small, **kw})


@pytest.mark.parametrize("x0, sensor", [((0.0, 0.0, 0.0, 0.0), 1), ((2000.0, 0.0, 0.0, 0.0), 2)])
def test_c5_linearised_errors_refuses_a_nominal_trajectory_on_a_sensor(x0, sensor):
    from fusion.scenarios.range_bearing import linearised_errors
    with pytest.raises(ValueError, match=rf"^sc: the nominal trajectory .* sensor {sensor} "):
        linearised_errors(_sc(x0=x0), True, False)


def test_c5_posterior_crb_keeps_the_shared_rule_naming_truths():
    from fusion.scenarios.range_bearing import posterior_crb
    with pytest.raises(ValueError, match=r"^truths: a true position coincides with sensor 1"):
        posterior_crb(_sc(), np.zeros((1, 2, 4)))


def test_c5_a_cloud_collapsed_near_a_sensor_is_refused_naming_sc():
    from fusion.optimise.swarm import SwarmOptions
    from fusion.scenarios.range_bearing import run_tracking
    with pytest.raises(ValueError, match=r"^sc: node 1's local posterior covariance .* near sensor 1"):
        run_tracking(_sc(x0=(0.0, 0.0, 5.0, 5.0)), np.random.SeedSequence(2), swarm_options=SwarmOptions(iterations=3))


def test_c6_a_refused_record_names_the_callers_argument():
    from fusion.scenarios.range_bearing import LinearisedErrors, linearised_errors
    with pytest.raises(ValueError, match=r"^sc gives a result that is refused: LinearisedErrors\."):
        # (sigma_r = 1e-3 m, refused here before fix 56b, was the centralised simple form's round-off; its
        # information form is within 8e-9 of a 100-digit reference there)
        linearised_errors(_sc(p0_std=(100.0,) * 4, sigma_r=1000.0, sigma_theta=1e-9, T=1000.0), True, False)
    with pytest.raises(ValueError, match=r"^LinearisedErrors\.nees_naive"):   # built by the caller: its field
        LinearisedErrors(*[np.array([np.nan])] * 6)


# --- D4: the round-off note is the tie rule ---------------------------------------------------------------------------

def test_d4_a_tie_says_round_off_and_a_difference_does_not():
    from fusion.book.exact import ExactComparison
    tie = ExactComparison(1.0, 1.0 + 5e-10, "A", "B", "less", "m", margin=0)
    assert tie.region() == "undecided" and "relative (round-off)" in tie.summary()
    beyond = ExactComparison(1.0, 1.0 + 5e-9, "A", "B", "less", "m", margin=0)
    assert beyond.region() == "lower" and "round-off" not in beyond.summary()


# --- D5: a SeedSequence is spawned from -------------------------------------------------------------------------------

def test_d5_run_tracking_spawns_from_the_callers_seed_sequence():
    from fusion.optimise.swarm import SwarmOptions
    from fusion.scenarios.range_bearing import run_tracking
    sc, opts = _sc(frames=1), SwarmOptions(iterations=3)
    ss = np.random.SeedSequence(7)
    first = run_tracking(sc, ss, swarm_options=opts)
    assert ss.n_children_spawned > 0   # documented: the caller's object advances, as a Generator would
    again = run_tracking(sc, np.random.SeedSequence(7), swarm_options=opts)
    np.testing.assert_array_equal(first.truth, again.truth)   # a fresh SeedSequence of the same entropy repeats it
