"""Fuzz 68b C1, C1b, C2 and C9, C9b (fix 77a): counts read from an argument's protocol, not its claims, and budgets
by every count that sets the work.

C1/C1b/C2: chapter 05's count before conversion (``ci.checks._given_count``) counted one entry for an object with only
``__array__`` (no shape, no length) or a ``list`` subclass whose ``len()`` says 1, so ``pcrb_table`` ran 6,000 periods
(20-24 CPU-s) and ``fuzzy_levels`` 150 levels (22.5 CPU-s) under a budget of one; ``ci.checks._counted`` now reads
such an argument once and counts the array it gives, or refuses the lying length, for every caller (``pcrb_table``,
``fuzzy_levels``, ``printed_weight_facts``, ``weight_pair``). C9/C9b: ``sigma_first_order_problem`` counted its grid's
nodes only, so two mixtures of 80-100 components ran to a raw MemoryError and 60 ran 14.9 CPU-s.
"""

from __future__ import annotations

import array

import numpy as np
import pandas as pd
import pytest
from _helpers import refused_quickly

from fusion.book.chapters import ci
from fusion.book.chapters import chernoff_first_order as cf
from fusion.book.chapters.ci import bounds
from fusion.estimates import mixtures as mx


class OnlyArray:
    """An array-like with only ``__array__`` (no shape, no len): a sequence by ``fusion._counts.sequence``'s rule."""

    def __init__(self, a: np.ndarray) -> None:
        self.a = a

    def __array__(self, dtype: object = None, copy: object = None) -> np.ndarray:
        return self.a if dtype is None else self.a.astype(dtype)


class LyingList(list):
    """A list whose ``len()`` says 1."""

    def __len__(self) -> int:
        return 1


@pytest.fixture(scope="module")
def scenario() -> object:
    return ci.source_scenario(2024)


@pytest.mark.parametrize("periods", [OnlyArray(np.arange(1, 6001.0)), LyingList(np.arange(1, 6001.0).tolist()),
                                     array.array("d", range(1, 6001))], ids=["__array__", "lying len", "array.array"])
def test_pcrb_table_counts_what_it_converts(periods: object) -> None:
    refused_quickly(lambda: bounds.pcrb_table(periods, 10.0, 1.0), ValueError, "periods")


def test_pcrb_table_array_like_nearby_accepted() -> None:
    plain = bounds.pcrb_table([0.5, 1.0, 2.0], 10.0, 1.0)
    pd.testing.assert_frame_equal(bounds.pcrb_table(OnlyArray(np.array([0.5, 1.0, 2.0])), 10.0, 1.0), plain)
    # a list subclass defining its own __len__ is refused by the input budget's rule, even when it tells the truth
    refused_quickly(lambda: bounds.pcrb_table(LyingList([0.5]), 10.0, 1.0), ValueError, r"^periods must not be a list")


@pytest.mark.parametrize("make", [OnlyArray, lambda a: LyingList(a.tolist())], ids=["__array__", "lying len"])
def test_fuzzy_levels_counts_what_it_converts(scenario: object, make: object) -> None:
    levels = make(np.linspace(0.01, 0.99, 150))
    refused_quickly(lambda: ci.fuzzy_levels(scenario, levels), ValueError, "levels")


def test_fuzzy_levels_array_like_nearby_accepted(scenario: object) -> None:
    got = ci.fuzzy_levels(scenario, OnlyArray(np.array([0.01])))
    want = ci.fuzzy_levels(scenario, [0.01])
    assert list(got) == list(want) and all(np.array_equal(got[k], want[k]) for k in want)


def test_printed_weight_facts_counts_array_like_seeds(scenario: object) -> None:
    seeds = OnlyArray(np.arange(10**6))
    refused_quickly(lambda: ci.printed_weight_facts((scenario,), 2, seeds, n_grid=11), ValueError, "seeds")


def _mixture(S: int, seed: int) -> mx.GaussianMixture:
    r = np.random.default_rng(seed)
    return mx.GaussianMixture(np.ones(S) / S, r.normal(size=(S, 2)) * 2, np.tile(np.eye(2) * 0.5, (S, 1, 1)))


@pytest.mark.parametrize("S", [100, 80, 60])
def test_sigma_problem_budgets_components(S: int) -> None:
    a, b = _mixture(S, 1), _mixture(S, 2)
    refused_quickly(lambda: cf.sigma_first_order_problem(a, b, n=201), ValueError, "a, b and n")


def test_sigma_problem_components_nearby_accepted() -> None:
    out = cf.sigma_first_order_problem(_mixture(10, 1), _mixture(10, 2), n=201)
    assert 0.0 <= out.omega_exact <= 1.0
    a, b = cf.random_two_mixtures(np.random.default_rng(0))
    assert 0.0 <= cf.sigma_first_order_problem(a, b).omega_exact <= 1.0   # the default grid, the book's mixtures' size
