"""Fuzz 68b C5, C7, C8 and the levels note of chapter 02's ``table_21`` (fix77c): each refusal comes before the
per-entry work, names its argument, and a legitimate nearby call stays accepted."""

from __future__ import annotations

import numpy as np
import pytest

from _helpers import refused_quickly


@pytest.fixture(scope="module")
def vd():
    from fusion.book.chapters.lecture_wavelets import verdicts
    return verdicts


@pytest.fixture(scope="module")
def awf():
    from fusion.scenarios.lecture_weighting import estimators as sc
    return sc.awf_study(levels=(0.0, 900.0), k_max=100, runs=5, ks=(10, 100), seed=5)


def test_sensor_conjunction_sensors_budgeted_before_any_comparison(vd) -> None:
    # fuzz 68b C5: (100, 20,000) built 20,000 Comparisons (4.1 CPU-s) before the Conjunction refused them
    rng = np.random.default_rng(0)
    a, b = rng.normal(size=(100, 20_000)), rng.normal(size=(100, 20_000))
    refused_quickly(lambda: vd.sensor_conjunction(a, b, "A", "B", "R {j}", 1), ValueError, r"a and b")


def test_sign_conjunction_sensors_budgeted_before_any_comparison(vd) -> None:
    # the same helper (_per_sensor): 5.1 CPU-s before the Conjunction refused
    rng = np.random.default_rng(1)
    a, b = rng.normal(size=(100, 20_000)), rng.normal(size=(100, 20_000))
    refused_quickly(lambda: vd.sign_conjunction(a, b, "A", "B", 1), ValueError, r"a and b")


def test_per_sensor_legitimate_calls_accepted(vd) -> None:
    rng = np.random.default_rng(2)
    a, b = rng.normal(size=(100, 4)), rng.normal(size=(100, 4)) + 1.0   # the book's shape: four sensors
    assert len(vd.sensor_conjunction(a, b, "A", "B", "R {j}", 1).parts) == 4
    assert len(vd.sign_conjunction(a, b, "A", "B", 1).parts) == 4
    a, b = rng.normal(size=(100, 500)), rng.normal(size=(100, 500))   # well within the budget (6.5 % of it)
    assert len(vd.sensor_conjunction(a, b, "A", "B", "R {j}", 1).parts) == 500


def test_check_grid_sigma_entries_checked_at_once() -> None:
    # fuzz 68b C7: 10**6 entries of sigma each went through std_scalar (4.1 CPU-s) before the memory budget refused
    from fusion.book.chapters.lecture_weighting import consistency as cs
    refused_quickly(lambda: cs.check_grid(sigma=np.ones(10**6)), ValueError, r"runs, samples and sigma")


def test_shift_weight_draws_sigma_entries_checked_at_once() -> None:
    # fuzz 68b C8: the same loop (3.8 CPU-s at 10**6) before loop_work refused draws x sigma
    from fusion.book.chapters.lecture_weighting import belief as bl
    refused_quickly(lambda: bl.shift_weight_draws(sigma=np.ones(10**6)), ValueError, r"draws and sigma")


@pytest.mark.parametrize("sigma, match", [((1.0, -1.0, 2.0), r"sigma\[1\]"), ((1.0, 2.0, 1e-80), r"sigma\[2\]"),
                                          ((1.0, 1e76, 2.0), r"sigma\[1\]"), ((0.0, 1.0, 2.0), r"sigma\[0\]")])
def test_sigma_entry_still_named(sigma, match) -> None:
    from fusion.book.chapters.lecture_weighting import belief as bl
    from fusion.book.chapters.lecture_weighting import consistency as cs
    with pytest.raises(ValueError, match=match):
        cs.check_grid(sigma=sigma)
    with pytest.raises(ValueError, match=match):
        bl.shift_weight_draws(sigma=sigma)


def test_sigma_legitimate_calls_accepted() -> None:
    from fusion.book.chapters.lecture_weighting import belief as bl
    from fusion.book.chapters.lecture_weighting import consistency as cs
    assert len(cs.check_grid(eps_factors=(1.0,), biases=(2.0,), runs=3, samples=10, sigma=(0.5, 1.0, 2.0),
                             window=(2, 6))) == 1
    assert bl.shift_weight_draws(draws=2, sigma=np.array([0.5, 1.0, 2.0, 4.0])).W.shape == (2, 201)


def test_table_21_levels_counted_before_read(awf) -> None:
    # fuzz 68b (levels note): 10**6 repeats of a level were each read and looked up (4.9 CPU-s) before distinct refused
    from fusion.book.chapters.lecture_weighting import estimators as es
    refused_quickly(lambda: es.table_21(awf, [0.0] * 10**6), ValueError, r"levels")


def test_table_21_levels_accepted_and_refused_by_entry(awf) -> None:
    from fusion.book.chapters.lecture_weighting import estimators as es
    assert set(es.table_21(awf, [900.0, 0.0]).index.get_level_values("X")) == {0, 900}
    assert len(es.table_21(awf, (0.0,))) > 0
    with pytest.raises(ValueError, match=r"levels must not repeat"):   # as many entries as levels: the old message
        es.table_21(awf, [0.0, 0.0])
    with pytest.raises(ValueError, match=r"levels\[1\]"):
        es.table_21(awf, [0.0, 100.0])
