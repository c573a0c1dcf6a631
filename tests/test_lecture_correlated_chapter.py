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


def test_chapter_04_claims_after_review() -> None:
    from fusion.book.chapters import lecture_correlated as ch
    from fusion.book.ledger import Conjunction, Unverifiable
    from fusion.scenarios import correlated_sensors as cs
    from fusion.scenarios import ridge_sensors as rs

    s25, s27 = sc.ridge_study(draws=100), sc.correlated_study(runs=500)
    p25 = rs.plugin_study(xs=(0.0, 0.25, 0.5, 1.0, 3.0, 10.0), runs=400, seed=3)
    x25 = ch.plugin_exact(p25)
    v25 = rs.vector_study(runs=200, scales=(3.0, 100.0))
    cpl = cs.coupling_study(runs=200)
    led = ch.claims(s25, s27, p25=p25, v25=v25, cpl=cpl, x25=x25)
    by = {c.id: c for c in led.claims}
    # the lecture's claim is an existence statement (reproduced with k matched to x); the computable k is its own record
    assert by["lec-ridge-reliable"].evidence.status() == "reproduced"
    plug = by["lec-ridge-plugin"]
    assert isinstance(plug.evidence, Conjunction) and plug.status == "contradicted"
    assert "1.02" in plug.bound and "1.45" in plug.bound and "1.252" in plug.bound
    # every true x at once in the ill-conditioned vector case
    fb = by["lec-ridge-fusion-better"]
    assert isinstance(fb.evidence, Conjunction) and len(fb.evidence.parts) == 4
    for rid in ("lec-ridge-bias-known", "lec-james-stein-linear", "lec-lagrange-scalar-only", "lec-eigen-impractical"):
        assert by[rid].status == "contradicted", rid
    for rid in ("lec-eigen-finite", "lec-ldl-unique", "lec-ridge-variance"):
        assert by[rid].status == "reproduced", rid
    assert isinstance(by["lec-reliability-measure"].evidence, Unverifiable)
    assert isinstance(by["lec-ldl-validated"].evidence, Unverifiable)
    assert "(at the price" not in by["lec-ridge-variance"].claim
    # the Cholesky / LDLᵀ count ratio is glued unrounded (1.0049, not 1.00 from the 2-decimal table)
    g = ch.glue_27(s27)
    assert g["lec_cor_flop_ratio_chol_600"] == pytest.approx(1.0049, abs=1e-4)
    cheaper = by["lec-ldl-cheaper"]
    assert "1.0049×" in cheaper.alternatives[0].evidence.summary()
    assert [a.evidence.status() for a in cheaper.alternatives].count("reproduced") == 2
