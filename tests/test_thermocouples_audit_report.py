"""Simulation of source 001's experiment, audit helpers and report tables."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from fusion.book import audit
from fusion import data
from fusion.book import tables as report
from fusion.scenarios import thermocouples
from fusion import readings as r

T1 = data.YANG2012_TABLE1.values


def test_simulate_is_reproducible_and_shaped() -> None:
    a = thermocouples.simulate(np.random.default_rng(1), n_samples=100)
    b = thermocouples.simulate(np.random.default_rng(1), n_samples=100)
    np.testing.assert_array_equal(a, b)
    assert a.shape == (100, 10)
    many = thermocouples.simulate(np.random.default_rng(1), n_runs=3, n_samples=5, sigma=1.0)
    assert many.shape == (3, 5, 10)
    with pytest.raises(ValueError, match="n_sensors"):
        thermocouples.simulate(np.random.default_rng(1), sigma=[1.0, 2.0])


def test_simulated_noise_levels() -> None:
    z = thermocouples.simulate(np.random.default_rng(7), n_samples=20000)
    np.testing.assert_allclose(z.std(axis=0), thermocouples.DEFAULT_SIGMAS, rtol=0.03)
    np.testing.assert_allclose(z.mean(axis=0), 900.0, atol=0.05)


def test_inject_failure_matches_the_source() -> None:
    z = np.zeros((100, 10))
    f = thermocouples.inject_failure(z)
    assert z.sum() == 0.0  # input untouched
    assert np.count_nonzero(f) == 2 * 31
    np.testing.assert_array_equal(f[49:80, 3], 4.0)
    np.testing.assert_array_equal(f[49:80, 9], 8.0)
    assert f[48].sum() == 0.0 and f[80].sum() == 0.0


@pytest.mark.parametrize(
    "kwargs, message",
    [
        ({"sensors": (11,), "biases": (1.0,)}, "sensor 11"),
        ({"samples": (0, 5)}, "samples"),
        ({"samples": (50, 101)}, "samples"),
        ({"sensors": (1, 2), "biases": (1.0,)}, "same length"),
        ({"sensors": (1,), "biases": (np.nan,)}, "finite"),
    ],
)
def test_inject_failure_rejects_bad_input(kwargs: dict, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        thermocouples.inject_failure(np.zeros((100, 10)), **kwargs)


def test_simulate_rejects_bad_sigma() -> None:
    with pytest.raises(ValueError, match="sigma"):
        thermocouples.simulate(np.random.default_rng(0), sigma=[1.0, -1.0], n_sensors=2)
    with pytest.raises(ValueError, match="n_samples"):
        thermocouples.simulate(np.random.default_rng(0), n_samples=0)


def test_monte_carlo_failure_hurts_the_mean_by_the_average_bias() -> None:
    methods = {"mean": {"method": "mean"}}
    clean = thermocouples.monte_carlo(3, 200, methods, sigma=1.0)
    failed = thermocouples.monte_carlo(3, 200, methods, sigma=1.0, failure={})
    window = slice(49, 80)
    # mean of 10 readings, two biased by 4 and 8: bias 1.2 °C on the window only
    # 10 sensors of sigma 1: the error of the mean is N(1.2, 0.1) on the window
    assert failed["mean"][:, window].mean() == pytest.approx(1.2, abs=0.02)
    np.testing.assert_array_equal(clean["mean"][:, :49], failed["mean"][:, :49])


def test_absolute_errors_equal_fusion_errors() -> None:
    z = thermocouples.simulate(np.random.default_rng(5), n_samples=10)
    errs = thermocouples.absolute_errors(z, {"ofs": {"method": "optimal_fusion_set"}})
    expected = [abs(r.optimal_fusion_set(row).value - 900.0) for row in z]
    np.testing.assert_allclose(errs["ofs"], expected)


def test_audit_convex_hull_and_subsets() -> None:
    pub = data.YANG2012_TABLE2.columns["optimal_set"]
    assert not audit.in_convex_hull(T1[:, 0], pub[0])
    assert audit.in_convex_hull(T1[:, 1], pub[1])
    matches = audit.matching_subsets(
        T1[:, 1], pub[1], 5e-5, lambda v: r.fusion_set_weights(v).value
    )
    assert [m.members for m in matches] == [(0, 2)]
    assert audit.implied_sum_change(T1[:, 4], data.YANG2012_TABLE2.columns["mean"][4]) == pytest.approx(-10.0, abs=1e-3)
    with pytest.raises(ValueError, match="x must hold at most 12"):
        audit.matching_subsets(np.arange(13.0), 1.0, 0.1, np.mean)


@given(n=st.integers(1, 5), bad_at=st.integers(0, 30),
       bad=st.sampled_from([float("nan"), float("inf"), -float("inf"), None, 1j, "2.5", True, (1.0, 2.0)]))
def test_matching_subsets_refuses_a_fused_value_that_is_not_one_finite_real_naming_fuse(n: int, bad_at: int,
                                                                                        bad: object) -> None:
    """fuzz13 bug 5: a fuse returning NaN or inf matched nothing (an empty list), None/complex/an array gave
    float()'s unnamed TypeError; now any such value, on whichever subset, is a ValueError/TypeError naming fuse,
    and a finite real fuse gives what it gave before."""
    x = np.arange(1.0, n + 1.0)
    calls = []

    def fuse(v: np.ndarray) -> object:
        calls.append(1)
        return bad if len(calls) - 1 == bad_at else float(np.mean(v))

    if bad_at >= 2**n - 1:  # never reached: the call is valid
        assert audit.matching_subsets(x, 2.0, 0.5, fuse) == audit.matching_subsets(x, 2.0, 0.5, np.mean)
        return
    with pytest.raises((ValueError, TypeError), match="fuse"):
        audit.matching_subsets(x, 2.0, 0.5, fuse)


def test_audit_parameters_matching_finds_roots_and_reports_impossible_targets() -> None:
    x = T1[:, 0]
    target = r.support_degree(x, alpha=0.3).value
    roots = audit.parameters_matching(x, target, "support_degree", "alpha", 1e-4, 1e2)
    assert np.any(np.abs(roots - 0.3) < 1e-6)
    # observation 3: the published value is below the mean, support weighting moves it up
    x3 = T1[:, 2]
    pub3 = data.YANG2012_TABLE3.columns["reliability"][2]
    assert audit.parameters_matching(x3, pub3, "support_degree", "alpha", 1e-6, 1e3).size == 0
    sweep = np.array([r.support_degree(x3, alpha=a).value for a in np.logspace(-6, 3, 50)])
    assert sweep.min() >= r.arithmetic_mean(x3).value - 1e-9 > pub3


def test_side_by_side_table() -> None:
    df = report.side_by_side([1.0, 2.0], [1.5, 2.0], index=[1, 2])
    assert list(df.columns) == ["published", "reproduced", "difference"]
    assert list(report.side_by_side([1.0], [1.0], index=[1], name="(°C)").columns)[0] == "published (°C)"
    np.testing.assert_allclose(df["difference"], [0.5, 0.0])
    assert str(df["difference"].iloc[1]) == "0.0"
    with pytest.raises(ValueError, match="must match"):
        report.side_by_side([1.0], [1.0, 2.0], index=[1])
    assert report.rounded(-0.00001) == 0.0


def test_best_linear_abs_error_matches_monte_carlo_of_the_weighted_mean() -> None:
    sig = thermocouples.DEFAULT_SIGMAS
    z = thermocouples.simulate(np.random.default_rng(11), n_samples=200, n_runs=200)
    w = sig**-2 / np.sum(sig**-2)
    mae = np.abs(z @ w - 900.0).mean()
    assert mae == pytest.approx(thermocouples.best_linear_abs_error(sig), rel=0.02)
    assert thermocouples.best_linear_abs_error(1.0) == pytest.approx(np.sqrt(2 / np.pi) / np.sqrt(10))


@given(st.lists(st.floats(880.0, 920.0, allow_nan=False), min_size=3, max_size=3),
       st.floats(1e-4, 1e2))
def test_support_bound_holds_on_random_triples(x: list[float], alpha: float) -> None:
    """Support weighting of one observation never falls below the mean when the low reading is least supported."""
    v = np.asarray(x)
    sup = np.exp(-alpha * (v[:, None] - v[None, :]) ** 2).sum(axis=1)
    if sup[np.argmin(v)] <= sup.min():
        assert r.support_degree(v, alpha=alpha).value >= r.arithmetic_mean(v).value - 1e-9


def test_support_bound_check_counts() -> None:
    from fusion.book.chapters import ofs as ch
    out = ch.support_bound_check(1, 2_000)
    assert out["triples"] == 2_000 and 0 < out["low_least"] < 2_000 and out["below"] == 0
