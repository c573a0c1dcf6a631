"""Tests of chapter 04's package code (lecture notes §§2.5 and 2.7): the ridge study's tables."""

from __future__ import annotations

import numpy as np
import pytest

from fusion.scenarios import lecture as sc


def test_ridge_study_reliability_readings_and_variance_gap():
    from fusion.book.chapters import lecture_correlated as ch
    from fusion.readings import biased as rg

    s = sc.ridge_study(draws=50, ks_fixed=(0.01, 1.0))
    tab = ch.table_25_k(s)
    assert list(tab.columns) == ["LS (k = 0)", "k = 0.01: gain", "k = 1: gain", "k*: gain", "value of k*"]
    # k* = sigma^2 / x^2 improves the reliability at every x; a fixed k = 1 fails at x = 10
    assert np.all(tab["k*: gain"] > 0)
    assert tab.loc[10.0, "k = 1: gain"] < 0
    np.testing.assert_allclose(tab["value of k*"], 1.0 / np.asarray(tab.index) ** 2, rtol=1e-6, atol=1e-7)
    m1, m0 = rg.scalar_ridge_moments(5, 1.0, 3.0, 0.01), rg.scalar_ridge_moments(5, 1.0, 3.0, 0.0)
    b, sd = m1.bias, m1.sd
    rel0 = float(rg.reliability(m0.bias, m0.sd, 1 / np.sqrt(5)))
    assert tab.loc[3.0, "k = 0.01: gain"] == pytest.approx(float(rg.reliability(b, sd, 1 / np.sqrt(5))) - rel0, abs=2e-7)
    # SD ratio m/(m + k) at the smallest k > 0 of the grid (0.01)
    assert s["sd_ratio_max"] == pytest.approx(5 / 5.01)
    # the LS - ridge covariance gap is positive definite and vanishes as k -> 0
    assert s["var_gap_min_eig"] > 0
    tiny = sc.ridge_study(draws=10, ks_fixed=(1e-9,))["var_gap_min_eig"]
    assert 0 < tiny < 1e-6
