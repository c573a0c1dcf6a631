"""Fuzz 27a (issue 35): regressions of this hour's fixes (report /work/tmp/fuzz27a/report.md).

F1/F5: a published value is held to its own dtype's precision (float32 products accepted, a float32 that cannot
hold its decimals refused by name); F2: the network study's KL tolerance absorbs only round-off; F3: seeds beyond
int64 are never converted to float; F4: the simplex tolerance is capped; N1: H's rank test is unit-free; N2: a
collapsed particle cloud is refused naming ``sc``.
"""

import dataclasses

import numpy as np
import pytest

from fusion.book.ledger import PublishedValues


# --- F1 / F5 ----------------------------------------------------------------------------------------------------------

def test_f1_a_float32_table_scaled_in_float32_is_its_decimals():
    pct = np.array([0.123, 0.456, 0.789], dtype=np.float32) * np.float32(100)
    assert PublishedValues(pct, [12.3, 45.6, 78.9], decimals=1).status() == "reproduced"


def test_f1_a_float32_product_converted_to_float_is_its_decimal():
    p = float(np.float32(17527) * np.float32(0.1))
    assert PublishedValues([p], [1752.7], decimals=1).status() == "reproduced"
    with pytest.raises(ValueError, match=r"published\[0\].*more decimals"):  # a real extra decimal in float64
        PublishedValues([1234567.85], [1234567.85], 1)


@pytest.mark.parametrize("value, d", [(98765.4321, 4), (123456789.123, 3), (16777217.0, 0)])
def test_f5_a_float32_that_cannot_hold_its_decimals_is_refused_by_name(value, d):
    with pytest.raises(ValueError, match=r"published\[0\].*float32 that cannot hold"):
        PublishedValues(np.array([value], np.float32), [value], decimals=d)


# --- F2 ---------------------------------------------------------------------------------------------------------------

def _scaled_network(factor):
    import fusion.scenarios.fusion_networks as fn
    sc = fn.premise_scenarios()[fn.Network.NON_GAUSSIAN]
    return dataclasses.replace(sc, nodes=tuple(dataclasses.replace(n, sigma_r=n.sigma_r * factor,
                                                                   sigma_theta=n.sigma_theta * factor)
                                               for n in sc.nodes))


def test_f2_a_grid_that_cannot_resolve_the_kl_is_refused_not_stored_as_zero():
    from fusion.scenarios.fusion_networks import run_network_study
    with pytest.raises(ValueError, match=r"^sc: the grid"):
        run_network_study(_scaled_network(0.05), 2, 2)


def test_f2_a_non_finite_resolution_is_said_so():
    from fusion.scenarios.fusion_networks import run_network_study
    with pytest.raises(ValueError, match=r"^sc: .*") as e:
        run_network_study(_scaled_network(0.002), 1, 2)
    assert "inf nats" not in str(e.value)


# --- F3 ---------------------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("seeds", [(2**63, 1), np.array([2**63, 5], dtype=np.uint64)])
def test_f3_seeds_beyond_int64_are_kept_exactly(seeds):
    from fusion.scenarios.two_sensor import fruit_fly_over_seeds
    out = fruit_fly_over_seeds(np.eye(2), np.diag([1.0, 0.2]), seeds, n_grid=11, population=3, iterations=3)
    assert [int(s) for s in out.seeds] == [int(s) for s in seeds]


def test_f3_seed_array_never_rounds():
    from fusion._validation import seed_array
    s = seed_array([2**63 + 1, 1])
    assert s.dtype == object and s.tolist() == [2**63 + 1, 1]
    assert seed_array([3, 1]).dtype == np.int64


# --- F4 ---------------------------------------------------------------------------------------------------------------

def _w16(total_of_one):
    if total_of_one:
        w = np.zeros(600, dtype=np.float16)
        w[0] = 1.9
        return w
    return np.full(600, 1e-4, dtype=np.float16)


@pytest.mark.parametrize("one", [False, True])
def test_f4_float16_weights_far_from_one_are_refused_at_any_n(one):
    from fusion.estimates.mixtures import GaussianMixture
    from fusion.filtering.particles import effective_sample_size
    from fusion.optimise.simplex import check_simplex
    w = _w16(one)
    with pytest.raises(ValueError):
        effective_sample_size(w)
    with pytest.raises(ValueError):
        check_simplex(w, 600)
    with pytest.raises(ValueError):
        GaussianMixture(w, np.zeros((600, 1)), np.ones((600, 1, 1)))
    assert effective_sample_size((np.ones(600) / 600).astype(np.float16)) > 500  # float16-normalised: accepted


# --- N1 ---------------------------------------------------------------------------------------------------------------

def test_n1_the_rank_of_h_does_not_depend_on_units():
    from fusion.readings.correlated import gls
    from fusion.readings.biased import least_squares
    assert np.allclose(gls(np.diag([1.0, 1e16]), np.eye(2), np.array([1.0, 1.0])).x, [1.0, 1e-16])
    rng = np.random.default_rng(0)
    H, y = rng.normal(size=(6, 2)), rng.normal(size=6)
    x = least_squares(H, y)
    assert np.allclose(least_squares(H @ np.diag([1.0, 1e8]), y), x * [1.0, 1e-8])
    Hd = np.array([[1.0, 2.0], [2.0, 4.0], [3.0, 6.0]])  # rank deficient in any units: still refused
    with pytest.raises(ValueError, match="full column rank"):
        gls(Hd, np.eye(3), np.ones(3))
    with pytest.raises(ValueError, match="rank"):
        least_squares(Hd @ np.diag([1.0, 1e8]), np.ones(3))


# --- N2 ---------------------------------------------------------------------------------------------------------------

def test_n2_a_collapsed_particle_cloud_is_refused_naming_sc():
    from fusion.optimise.swarm import SwarmOptions
    from fusion.scenarios.range_bearing import RangeBearingScenario, run_tracking
    sc = RangeBearingScenario(sigma_theta=1e-4, frames=2, n_particles=60, n_samples=60, n_central=100,
                              em_iterations=2)
    with pytest.raises(ValueError, match=r"^sc: .*sc.n_particles"):
        run_tracking(sc, np.random.SeedSequence(1), swarm_options=SwarmOptions(iterations=3))


# --- D7 ---------------------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("a, b", [(100.0, 100.0000001), (5.0, 5.0)])
@pytest.mark.parametrize("claim", ["equal", "less", "greater"])
def test_d7_exact_and_monte_carlo_agree_on_a_tie_at_margin_zero(a, b, claim):
    from fusion.book.exact import ExactComparison
    from fusion.book.ledger import Comparison
    exact = ExactComparison(a, b, "A", "B", claim, "m", margin=0)
    runs = Comparison(np.full(100, a), np.full(100, b), "A", "B", claim, "m", seed=1, margin=0)
    assert exact.status() == runs.status()
    assert exact.region() == runs.judgement().region


# --- D5 ---------------------------------------------------------------------------------------------------------------

def test_d5_the_producer_never_emits_a_bearing_of_minus_pi(monkeypatch):
    import fusion.scenarios.range_bearing_scenario as rbs
    from fusion.scenarios.range_bearing import RangeBearingScenario
    sc = RangeBearingScenario(frames=2)
    real = np.angle
    monkeypatch.setattr(rbs.np, "angle", lambda z: np.full(np.shape(z), -np.pi))  # the wrap's own output at -pi
    try:
        t = rbs.simulate_target(sc, np.random.default_rng(1))
    finally:
        monkeypatch.setattr(rbs.np, "angle", real)
    assert np.all(t.z[..., 1] == np.pi)
    dataclasses.replace(t, z=t.z.copy())  # the producer's target rebuilds under its spec


# --- D6 ---------------------------------------------------------------------------------------------------------------

def test_d6_a_short_study_inside_a_read_only_mapping_is_named_by_its_field():
    import types
    from fusion.book._few_runs import _short_fields

    @dataclasses.dataclass(frozen=True)
    class Record:
        studies: object

    short = types.SimpleNamespace(runs=2)
    assert _short_fields(Record(types.MappingProxyType({"a": short})), 10) == ["studies"]


def test_c1_fuzz28a_ridge_decides_singularity_without_units_at_every_k():
    """Fuzz 28a C1: at k > 0 ridge kept matrix_rank's absolute tolerance, so diag(1, 1e16) was refused (with a
    message saying k = 0) where k = 0 and least_squares gave [1, 1]; a rank-deficient H is still refused at a k too
    small to make up for it, and solved at a k that does."""
    from fusion.readings.biased import ridge

    for k in (1e-10, 1e-300):   # a ridge this small leaves the exact solution [1, 1] (k = 1 gives [0.5, 1])
        np.testing.assert_allclose(ridge(np.diag([1.0, 1e16]), [1.0, 1e16], k), [1.0, 1.0], rtol=1e-9)
    np.testing.assert_allclose(ridge(np.diag([1.0, 1e16]), [1.0, 1e16], 1.0), [0.5, 1.0], rtol=1e-9)
    H = np.ones((2, 2))
    for k in (0.0, 1e-300):
        with pytest.raises(ValueError, match="rank-deficient"):
            ridge(H, [1.0, 1.0], k)
    np.testing.assert_allclose(ridge(H, [1.0, 1.0], 1.0), [0.4, 0.4])
