"""Fuzz 46b C1/C2: a sliding window's sum as a difference of cumulative sums kept the round-off of a large value
that had left the window (``running_average``/``difference_variances``/``tracking_variances``, ``memory="window"``).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from fusion.readings import weighting as wt
from fusion.readings._windows import WINDOW_RTOL, _trailing_max, window_sums


def test_c1_a_large_value_that_left_the_window_does_not_count() -> None:
    got = wt.running_average(np.array([1e16] + [3.0] * 50), "window", window=10, axis=0)
    assert got[-1] == 3.0  # was 4.0
    got = wt.running_average(np.array([1e15] * 1000 + [1.0] * 20), "window", window=10, axis=0)
    assert got[-1] == 1.0  # was 0.0


def test_c2_a_spike_does_not_make_a_perfect_sensor() -> None:
    rng = np.random.default_rng(0)
    X = 20.0 + rng.normal(size=(200, 3)) * [0.01, 0.02, 0.03]
    clean = wt.difference_variances(X, "window", window=50)[-1]
    X[0, 0] += 1e7
    spiked = wt.difference_variances(X, "window", window=50)[-1]  # sensor 0's estimate was 0.0
    np.testing.assert_allclose(spiked, clean, rtol=1e-9)
    X[0] += 1e8 * np.array([1.0, -3.0, 7.0])
    got = wt.tracking_variances(X, "sample", "window", window=50)[-1]
    np.testing.assert_allclose(got, np.var(X[-50:], axis=0), rtol=1e-9)


@pytest.mark.parametrize("seed", range(20))
def test_window_sums_match_exact_sums_to_the_stated_round_off(seed: int) -> None:
    rng = np.random.default_rng(seed)
    for _ in range(10):
        K, w = int(rng.integers(1, 80)), int(rng.integers(1, 30))
        A = rng.normal(size=(K, 2)) * 10.0 ** rng.integers(-3, 3, size=(K, 1))
        A[rng.integers(K)] *= 10.0 ** rng.integers(8, 17)
        got = window_sums(A, w)
        for k in range(K):
            for j in range(2):
                win = A[max(0, k - w + 1):k + 1, j]
                tol = WINDOW_RTOL * np.abs(win).max() + 2 * w * np.finfo(float).eps * np.abs(win).sum()
                assert abs(got[k, j] - math.fsum(win)) <= tol


@pytest.mark.parametrize("window", [1, 2, 3, 7, 10])
def test_trailing_max_is_the_window_maximum(window: int) -> None:
    a = np.random.default_rng(window).random((23, 2))
    want = np.array([a[max(0, k - window + 1):k + 1].max(axis=0) for k in range(23)])
    np.testing.assert_array_equal(_trailing_max(a, window), want)


def test_book_like_windows_keep_the_cumulative_sum_difference_bit_for_bit() -> None:
    # the regime study's stack (notebook 02): 1000 samples, 100-sample windows, positive squares and signed means
    rng = np.random.default_rng(3)
    Y = rng.normal(size=(1000, 40, 4)) * [0.5, 1.0, 2.0, 3.0]
    A = np.concatenate([Y**2, Y * Y.sum(axis=-1, keepdims=True), Y], axis=-1)
    c = np.cumsum(A, axis=0)
    c[100:] = c[100:] - c[:-100]
    np.testing.assert_array_equal(window_sums(A, 100), c)
    got = wt.running_average(A, "window", window=100, axis=0)
    np.testing.assert_array_equal(got, c / np.minimum(np.arange(1, 1001), 100).reshape(-1, 1, 1))
