"""Readings-level fusion (source 001): published values, invariants and bad input."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from fusion import data
from fusion import readings as r

T1 = data.YANG2012_TABLE1.values
TABLE2 = data.YANG2012_TABLE2.columns
TABLE3 = data.YANG2012_TABLE3.columns

SINGLE = {
    "mean": lambda x: r.arithmetic_mean(x),
    "optimal_fusion_set": lambda x: r.optimal_fusion_set(x),
    "optimal_fusion_set_sum": lambda x: r.optimal_fusion_set(x, threshold="sum"),
    "optimal_fusion_set_noself": lambda x: r.optimal_fusion_set(x, include_self=False),
    "support_degree": lambda x: r.support_degree(x),
    "fusion_set_weights": lambda x: r.fusion_set_weights(x),
}

# Temperatures around 900 °C with realistic spreads, 1 to 12 sensors.
readings = st.integers(1, 12).flatmap(
    lambda n: arrays(
        np.float64, n, elements=st.floats(880.0, 920.0, allow_nan=False, allow_infinity=False)
    )
)


# --- published values -----------------------------------------------------------------


@pytest.mark.parametrize("obs", [2, 3, 4])
def test_table2_optimal_set_reproduced(obs: int) -> None:
    """Observations 2-4 of Table 2 follow from Table 1 (sensors 1 and 3 form the set)."""
    res = r.optimal_fusion_set(T1[:, obs - 1])
    assert res.value == pytest.approx(TABLE2["optimal_set"][obs - 1], abs=5e-5)
    np.testing.assert_array_equal(res.members, [True, False, True])
    np.testing.assert_allclose(res.weights, [0.5, 0.0, 0.5])


@pytest.mark.parametrize("obs", [1, 2, 3, 4, 6])
def test_table2_mean_column_reproduced(obs: int) -> None:
    assert r.arithmetic_mean(T1[:, obs - 1]).value == pytest.approx(
        TABLE2["mean"][obs - 1], abs=5e-5
    )


def test_table2_mean_observation5_is_inconsistent_by_one_reading_of_10() -> None:
    """The published mean of observation 5 needs the readings to sum to 10 °C less."""
    x = T1[:, 4]
    assert r.arithmetic_mean(x).value - TABLE2["mean"][4] == pytest.approx(10 / 3, abs=1e-4)
    x_fixed = x.copy()
    x_fixed[0] -= 10.0  # sensor 1: 899.9 -> 889.9, the joint audit's correction
    assert r.arithmetic_mean(x_fixed).value == pytest.approx(TABLE2["mean"][4], abs=5e-5)


def test_table2_observation1_is_not_a_convex_combination() -> None:
    x = T1[:, 0]
    assert TABLE2["optimal_set"][0] > x.max()


def test_published_totals_are_sums_of_published_errors() -> None:
    t = data.YANG2012_TOTALS.columns
    assert TABLE2["mean_abs_error"].sum() == pytest.approx(t["mean"][0], abs=1e-4)
    assert TABLE3["reliability_abs_error"].sum() == pytest.approx(t["reliability"][0], abs=1e-4)
    assert TABLE2["optimal_set_abs_error"].sum() == pytest.approx(t["optimal_set"][0], abs=1e-4)


def test_published_data_is_read_only() -> None:
    with pytest.raises(ValueError):
        data.YANG2012_TABLE1.values[0, 0] = 0.0


# --- invariants (hypothesis) ------------------------------------------------------------


@pytest.mark.parametrize("name", sorted(SINGLE))
@given(x=readings)
def test_weights_are_a_convex_combination(name: str, x: np.ndarray) -> None:
    res = SINGLE[name](x)
    assert res.weights.shape == x.shape
    assert np.all(res.weights >= 0.0)
    assert res.weights.sum() == pytest.approx(1.0, abs=1e-12)
    assert np.all(res.weights[~res.members] == 0.0)
    assert res.members.any()
    span = x.max() - x.min()
    assert x.min() - 1e-9 * (1 + span) <= res.value <= x.max() + 1e-9 * (1 + span)
    assert res.value == pytest.approx(float(res.weights @ x), abs=1e-9)


@pytest.mark.parametrize("name", sorted(SINGLE))
@given(x=readings, seed=st.integers(0, 2**32 - 1))
def test_permutation_invariance(name: str, x: np.ndarray, seed: int) -> None:
    perm = np.random.default_rng(seed).permutation(x.size)
    a, b = SINGLE[name](x), SINGLE[name](x[perm])
    assert b.value == pytest.approx(a.value, abs=1e-9)
    np.testing.assert_allclose(b.weights, a.weights[perm], atol=1e-9)
    np.testing.assert_array_equal(b.members, a.members[perm])


@pytest.mark.parametrize("name", sorted(SINGLE))
@given(x=readings, shift=st.floats(-500.0, 500.0))
def test_translation_equivariance(name: str, x: np.ndarray, shift: float) -> None:
    """Only differences between readings enter the weights."""
    a, b = SINGLE[name](x), SINGLE[name](x + shift)
    assert b.value == pytest.approx(a.value + shift, abs=1e-8)


@given(x=readings, k=st.floats(0.1, 10.0))
def test_optimal_set_is_unit_free_only_if_scale_follows_the_unit(x: np.ndarray, k: float) -> None:
    """Changing unit by factor k gives the same fusion only if eq. 6's scale is k times larger."""
    a = r.optimal_fusion_set(x, scale=2.0)
    b = r.optimal_fusion_set(k * x, scale=2.0 * k)
    assert b.value == pytest.approx(k * a.value, rel=1e-9, abs=1e-9)
    np.testing.assert_array_equal(a.members, b.members)


def test_unit_dependence_with_fixed_scale() -> None:
    """With the source's fixed factor 1/2, °F readings give a different fusion than °C."""
    x = np.array([899.0, 900.0, 900.4, 901.5, 903.0, 899.7, 900.9])
    res_c = r.optimal_fusion_set(x)
    assert res_c.members.sum() >= 3
    x_f = x * 9 / 5 + 32
    back = (r.optimal_fusion_set(x_f).value - 32) * 5 / 9
    assert abs(back - res_c.value) > 1e-4
    # Kelvin differences equal Celsius differences: identical fusion
    assert r.optimal_fusion_set(x + 273.15).value - 273.15 == pytest.approx(res_c.value, abs=1e-9)


@given(x=readings)
def test_batch_matches_single(x: np.ndarray) -> None:
    rows = np.vstack([x, x[::-1], x + 1.0])
    for method in ("mean", "optimal_fusion_set", "support_degree"):
        batch = r.fuse_epochs(rows, method)
        single = [SINGLE[method](row).value for row in rows]
        np.testing.assert_allclose(batch.values, single, atol=1e-9)


@given(x=readings)
def test_sum_threshold_keeps_every_distinct_reading(x: np.ndarray) -> None:
    assume(np.ptp(x) > 0)
    assume(x.size >= 2)
    assert r.optimal_fusion_set(x, threshold="sum").members.all()


def test_eq9_parenthesisations_give_identical_weights() -> None:
    x = np.array([899.1, 900.2, 900.9, 898.7, 901.6, 900.0])
    C = r.fusion_degree_matrix(x)
    mu = r.consistency_degree(C)
    w = {}
    for form in ("left", "right", "root"):
        omega = mu * r.distribution_balance(C, form=form)
        w[form] = omega / omega.sum()
    np.testing.assert_allclose(w["left"], w["right"], rtol=1e-12)
    np.testing.assert_allclose(w["left"], w["root"], rtol=1e-12)
    tau_left = r.distribution_balance(C, form="left")
    tau_right = r.distribution_balance(C, form="right")
    np.testing.assert_allclose(tau_right / tau_left, x.size**2)


def test_include_self_changes_the_weights() -> None:
    x = np.array([899.1, 900.2, 900.9, 898.7, 901.6, 900.0])
    a = r.fusion_set_weights(x, include_self=True)
    b = r.fusion_set_weights(x, include_self=False)
    assert np.max(np.abs(a.weights - b.weights)) > 1e-3


def test_members_follow_eq5() -> None:
    x = np.array([0.0, 1.0, 2.0, 10.0])
    md = r.mean_distances(x)
    d, d_bar = md.d, md.d_bar
    np.testing.assert_array_equal(r.optimal_set_members(x), d < d_bar)
    np.testing.assert_allclose(r.distance_matrix(x), np.abs(x[:, None] - x[None, :]))
    md_sum = r.mean_distances(x, threshold="sum")
    d_sum, d_bar_sum = md_sum.d, md_sum.d_bar
    np.testing.assert_allclose(d_sum, d * x.size)
    assert d_bar_sum == pytest.approx(d_bar * x.size**2)


def test_outlier_is_rejected() -> None:
    x = np.array([900.1, 899.8, 900.3, 899.9, 930.0])
    res = r.optimal_fusion_set(x)
    assert not res.members[-1]
    assert res.weights[-1] == 0.0


# --- degenerate cases -----------------------------------------------------------------


@pytest.mark.parametrize("name", sorted(SINGLE))
def test_single_reading(name: str) -> None:
    res = SINGLE[name](np.array([901.3]))
    assert res.value == 901.3
    np.testing.assert_array_equal(res.weights, [1.0])


@pytest.mark.parametrize("name", sorted(SINGLE))
@pytest.mark.parametrize("n", [2, 3, 7])
def test_identical_readings(name: str, n: int) -> None:
    res = SINGLE[name](np.full(n, 900.0))
    assert res.value == pytest.approx(900.0, abs=1e-9)
    np.testing.assert_allclose(res.weights, np.full(n, 1.0 / n))
    assert np.all(np.isfinite(res.weights))


def test_two_readings_give_the_midpoint() -> None:
    for scale in (0.1, 2.0, 50.0):
        res = r.optimal_fusion_set([899.0, 905.0], scale=scale)
        assert res.value == pytest.approx(902.0)
        assert res.members.all()


def test_one_member_set_takes_all_the_weight() -> None:
    res = r.optimal_fusion_set(T1[:, 0])  # observation 1: only sensor 2 is central
    np.testing.assert_array_equal(res.members, [False, True, False])
    np.testing.assert_array_equal(res.weights, [0.0, 1.0, 0.0])
    assert res.value == T1[1, 0]


def test_distribution_balance_is_infinite_for_constant_rows() -> None:
    tau = r.distribution_balance(np.ones((3, 3)))
    assert np.all(np.isinf(tau))


# --- bad input ------------------------------------------------------------------------


@pytest.mark.parametrize("name", sorted(SINGLE))
@pytest.mark.parametrize(
    "bad, message",
    [
        ([], "empty"),
        ([900.0, np.nan], "NaN"),
        ([900.0, np.inf], "NaN or infinite"),
        ([[900.0, 901.0]], "1-D"),
        (900.0, "1-D"),
    ],
)
def test_bad_readings_raise(name: str, bad: object, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        SINGLE[name](bad)


@pytest.mark.parametrize(
    "kwargs, message",
    [
        ({"scale": 0.0}, "scale"),
        ({"scale": -1.0}, "scale"),
        ({"scale": np.nan}, "scale"),
        ({"threshold": "median"}, "threshold"),
    ],
)
def test_bad_options_raise(kwargs: dict, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        r.optimal_fusion_set([1.0, 2.0, 3.0], **kwargs)


def test_bad_alpha_and_method_raise() -> None:
    with pytest.raises(ValueError, match="alpha"):
        r.support_degree([1.0, 2.0], alpha=0.0)
    with pytest.raises(ValueError, match="unknown method"):
        r.fuse_epochs([[1.0, 2.0]], "median")
    with pytest.raises(ValueError, match="unknown option"):
        r.fuse_epochs([[1.0, 2.0]], "mean", scale=2.0)
    with pytest.raises(ValueError, match="2-D"):
        r.fuse_epochs(np.zeros((2, 2, 2)), "mean")


def test_fusion_degree_matrix_validation() -> None:
    with pytest.raises(ValueError, match="square"):
        r.consistency_degree(np.ones((2, 3)))
    with pytest.raises(ValueError, match="symmetric"):
        r.distribution_balance(np.array([[1.0, 0.2], [0.3, 1.0]]))
    with pytest.raises(ValueError, match="form"):
        r.distribution_balance(np.ones((2, 2)), form="middle")


# --------------------------------------------------------------------------- published vs reproduced tables
def test_mismatches_flags_exactly_the_values_outside_the_printed_precision():
    import pandas as pd

    from fusion.book.tables import highlight_mismatches, mismatches, side_by_side

    t = side_by_side([1.0, 2.0, 3.0], [1.00004, 2.0002, 3.0], [1, 2, 3], decimals=4)
    t.iloc[2, 1] = float("nan")                   # a value we cannot compute
    m = mismatches(t, decimals=4)
    assert m["reproduced"].tolist() == [False, True, True]
    assert m["difference"].tolist() == [False, True, True]
    assert not m["published"].any()
    grouped = pd.concat({"a": t, "b": side_by_side([1.0, 2.0, 3.0], [1.0, 2.0, 3.0], [1, 2, 3])}, axis=1)
    assert int(mismatches(grouped, 4).to_numpy().sum()) == 4
    html = highlight_mismatches(t, 4, uuid="x").to_html()
    assert "1 of 3 values reproduced" in html and html == highlight_mismatches(t, 4, uuid="x").to_html()
    with pytest.raises(ValueError, match="published"):
        mismatches(pd.DataFrame({"x": [1.0]}))


def test_integral_index_prints_whole_numbers_as_integers_and_leaves_fractions():
    import pandas as pd

    from fusion.book.tables import integral_index

    t = pd.DataFrame({"v": [0.5, 1.0, 1.5]}, index=pd.Index([-20.0, 0.0, 15.0], name="δ (ms)"))
    out = integral_index(t)
    assert out.index.tolist() == [-20, 0, 15] and out.index.dtype.kind == "i" and out.index.name == "δ (ms)"
    assert out["v"].tolist() == [0.5, 1.0, 1.5] and t.index.dtype.kind == "f"     # values and input untouched
    frac = pd.DataFrame({"v": [1.0, 2.0]}, index=pd.Index([0.1, 1.0]))
    assert integral_index(frac).index.dtype.kind == "f"
    multi = pd.DataFrame({"v": [1, 2]}, index=pd.MultiIndex.from_tuples([("a", 3.0), ("b", 8.0)]))
    assert integral_index(multi).index.levels[1].dtype.kind == "i"
    with pytest.raises(TypeError, match="table"):
        integral_index([1.0])


def test_binary_deletion_keeps_the_readings_most_others_trust_and_averages_them():
    from fusion.readings import binary_deletion

    r = binary_deletion([900.0, 900.5, 901.0, 910.0], 2.0)
    assert r.members.tolist() == [True, True, True, False] and r.value == pytest.approx(900.5)
    assert r.weights.sum() == pytest.approx(1.0)
    # "only a few": with min_support = 1 a reading must be trusted by every other one
    assert binary_deletion([0.0, 1.0, 2.0], 1.0, min_support=1.0).members.tolist() == [False, True, False]
    # nobody trusted: nothing would be left, so every reading is kept (documented)
    assert binary_deletion([1.0, 5.0, 9.0], 1.0).members.all()
    with pytest.raises(ValueError, match="at least two"):
        binary_deletion([1.0], 1.0)
    with pytest.raises(ValueError, match="min_support"):
        binary_deletion([1.0, 2.0], 1.0, min_support=1.5)
