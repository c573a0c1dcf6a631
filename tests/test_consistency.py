"""Source 003 sec. 2.3: adjacent-difference consistency check + AWF."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from fusion.readings.consistency import consistency_awf, consistency_mask
from fusion.readings.weighting import awf


def test_largest_cluster_is_kept() -> None:
    np.testing.assert_array_equal(consistency_mask([1.0, 1.5, 9.0, 2.0], 1.0), [True, True, False, True])
    # tie between two clusters of two: the one holding the lower median (sorted index 1)
    np.testing.assert_array_equal(consistency_mask([0.0, 0.5, 10.0, 10.5], 1.0), [True, True, False, False])


# (no tiny readings: the shared validation refuses them below 1e-150, issue 35 rule 2)
@given(arrays(float, st.integers(1, 7), elements=st.floats(-100, 100).map(lambda v: 0.0 if abs(v) < 1e-150 else v)), st.floats(0, 50, allow_subnormal=False))
def test_mask_is_permutation_equivariant_and_nonempty(x: np.ndarray, eps: float) -> None:
    m = consistency_mask(x, eps)
    assert m.any()
    kept = np.sort(x[m])
    assert np.all(np.diff(kept) <= eps)
    if np.unique(x).size == x.size:  # ties between equal values could swap identities
        p = np.random.default_rng(0).permutation(x.size)
        np.testing.assert_array_equal(consistency_mask(x[p], eps), m[p])


def test_infinite_eps_equals_plain_awf() -> None:
    X = np.random.default_rng(1).normal(size=(2, 40, 4)) * [0.5, 1, 2, 4] + 900
    for v in ("lecture", "centred"):
        checked = consistency_awf(X, np.inf, v)  # type: ignore[arg-type]
        res, mask = checked.awf, checked.mask
        assert mask.all()
        np.testing.assert_allclose(res.value, awf(X, v).value, rtol=0, atol=1e-9)  # type: ignore[arg-type]


def test_a_large_fault_is_excluded_and_weights_renormalised() -> None:
    rng = np.random.default_rng(2)
    X = 900 + rng.normal(size=(100, 5)) * [0.5, 1, 1.5, 2, 4]
    X[50:80, 2] += 30.0
    checked = consistency_awf(X, 3 * np.sqrt(2) * 4, "centred")
    res, mask = checked.awf, checked.mask
    assert not mask[50:80, 2].any()
    np.testing.assert_allclose(res.weights.sum(axis=-1), 1.0)
    assert np.all(res.weights[50:80, 2] == 0)


def test_bad_input() -> None:
    with pytest.raises(ValueError, match="eps"):
        consistency_mask([1.0, 2.0], -1)
    with pytest.raises(ValueError, match="NaN"):
        consistency_mask([1.0, np.nan], 1)
    with pytest.raises(ValueError, match="variance"):
        consistency_awf(np.ones((4, 3)), 1.0, "x")  # type: ignore[arg-type]


def test_index_order_reading_keeps_the_largest_run_of_consecutive_sensors():
    x = np.array([[1.0, 5.0, 1.2, 1.1], [1.0, 1.1, 5.0, 5.1], [1.0, 2.0, 3.0, 4.0]])
    got = consistency_mask(x, 0.5, adjacent="index")
    assert got.tolist() == [[False, False, True, True],     # sorted order would keep 1.0 as well
                            [True, True, False, False],      # a tie: the first run
                            [True, False, False, False]]     # no two neighbours agree: one reading kept
    assert consistency_mask(x, 0.5)[0].tolist() == [True, False, True, True]
    assert consistency_mask(x, np.inf, adjacent="index").all()
    with pytest.raises(ValueError, match="adjacent"):
        consistency_mask(x, 0.5, adjacent="nearest")


# (no tiny readings: the shared validation refuses them below 1e-150, issue 35 rule 2)
@given(arrays(np.float64, (6,), elements=st.floats(-5, 5).map(lambda v: 0.0 if abs(v) < 1e-150 else v)), st.permutations(range(6)))
def test_sorted_reading_does_not_depend_on_the_numbering_and_index_reading_keeps_contiguous_runs(x, perm):
    perm = list(perm)
    assert (consistency_mask(x[perm], 1.0) == consistency_mask(x, 1.0)[perm]).all()
    kept = np.flatnonzero(consistency_mask(x, 1.0, adjacent="index"))
    assert kept.size >= 1 and np.all(np.diff(kept) == 1)                   # one run of consecutive sensors
    assert np.all(np.abs(np.diff(x[kept])) <= 1.0)


@given(arrays(bool, st.tuples(st.integers(1, 4), st.integers(0, 6))))
def test_cluster_sizes_are_the_counts_of_each_label(gaps: np.ndarray) -> None:
    """Issue 35: the cluster sizes of ``consistency_mask`` come from one bincount (linear in the readings); they are
    the number of readings carrying each label, as the pairwise comparison ``labels == c`` (n x n) counted them."""
    from fusion.readings.consistency import _label_counts

    labels = np.concatenate([np.zeros((gaps.shape[0], 1), dtype=int), np.cumsum(gaps, axis=-1)], axis=-1)  # as made
    n = labels.shape[-1]
    expected = (labels[..., :, None] == np.arange(n)).sum(axis=-2)
    got = _label_counts(labels)
    assert got.shape == labels.shape and np.array_equal(got, expected)
    assert np.array_equal(_label_counts(labels[None]), expected[None])  # a batch of batches


def test_a_long_row_is_served() -> None:
    """10**5 readings in one row (an n x n comparison would be 10**10 booleans): the cluster of the median kept."""
    x = np.concatenate([np.arange(99_990) * 1e-3, 1e3 + np.arange(10.0)])
    keep = consistency_mask(x, 0.01)
    assert keep[:99_990].all() and not keep[99_990:].any()
