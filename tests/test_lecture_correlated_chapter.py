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


def test_chapter_04_records_follow_from_their_computations() -> None:
    from fusion.book.chapters import lecture_correlated as ch
    from fusion.book.ledger import Conjunction, Proposition, Unverifiable
    from fusion.readings import biased as rg
    from fusion.readings import correlated as co
    from fusion.scenarios import correlated_sensors as cs
    from fusion.scenarios import ridge_sensors as rs

    s25, s27 = sc.ridge_study(draws=100), sc.correlated_study(runs=500)
    p25 = rs.plugin_study(xs=(0.0, 0.25, 0.5, 1.0, 3.0, 10.0), runs=400, seed=3)
    x25 = ch.plugin_exact(p25)
    v25 = rs.vector_study(runs=200, scales=(3.0, 100.0))
    cpl = cs.coupling_study(runs=200)
    est = cs.estimated_covariance_study(ns=(10, 30), reps=50)
    led = ch.claims(s25, s27, p25=p25, v25=v25, cpl=cpl, x25=x25, est=est)
    by = {c.id: c for c in led.claims}
    # the scalar plug-in record is exact: one proposition per x, the reliabilities of plugin_risk
    plug = by["lec-ridge-plugin"]
    assert isinstance(plug.evidence, Conjunction)
    for lab, ev in plug.evidence.parts:
        x = float(lab.split("= ")[1])
        r = rg.plugin_risk(np.sqrt(5) * x)
        assert isinstance(ev, Proposition) and ev.holds == bool(r.reliability > r.reliability_ls)
        assert f"{float(r.reliability):.4f}" in ev.ours
    # the multi-sensor existence record: the best fixed k of each x, exact, against tr A⁻¹
    fb = by["lec-ridge-fusion-better"]
    for key, x in v25["x"].items():
        _, best = rg.best_ridge_k(v25["A"], x)
        assert f"{best / v25['tr_ls']:.3f}" in fb.evidence.ours
    assert fb.evidence.holds == all(rg.best_ridge_k(v25["A"], x)[1] < v25["tr_ls"] for x in v25["x"].values())
    fp = by["lec-ridge-fusion-plugin"]
    assert isinstance(fp.evidence, Conjunction) and len(fp.evidence.parts) == 4
    # the variance record reads a plug-in too: the exact variance crossing
    var = by["lec-ridge-variance"]
    cr = x25["known"][1.0]
    assert f"{cr['variance']:.2f}" in var.alternatives[0].evidence.ours
    assert var.alternatives[0].evidence.holds == (cr["var_peak_ratio"] < 1)
    # the Lagrange record: the scalar-weight method on a case that does not split, against GLS
    lag = by["lec-lagrange-scalar-only"]
    R = cs.oriented_covariance()
    H = np.kron(np.ones((3, 1)), np.eye(2))
    W, K = co.scalar_lagrange_weights(R, 2), co.gls_weights(H, R)
    ratio = np.trace(W @ R @ W.T) / np.trace(K @ R @ K.T)
    assert f"{ratio:.3f}" in lag.evidence.ours and lag.evidence.holds == (ratio > 1 + 1e-9)
    # E2.7's scalar twin is not counted again among the correlation structures
    cm = by["lec-correlation-matters"]
    assert len(cm.alternatives) == len(cpl["rows"]) - 1
    assert all("as E2.7" not in a.reading for a in cm.alternatives)
    assert isinstance(by["lec-reliability-measure"].evidence, Unverifiable)
    assert isinstance(by["lec-ldl-validated"].evidence, Unverifiable)
    assert "(at the price" not in by["lec-ridge-variance"].claim
    # the Cholesky / LDLᵀ count ratio is glued unrounded (from the counts, not the 2-decimal table)
    g = ch.glue_27(s27)
    oc = co.operation_counts(600, 2)
    assert g["lec_cor_flop_ratio_chol_600"] == pytest.approx(oc["cholesky"] / oc["ldl"], abs=5e-5)
    assert g["lec_cor_lowrank_exact"] == 1
    cheaper = by["lec-ldl-cheaper"]
    assert f"{oc['cholesky'] / oc['ldl']:.4f}×" in cheaper.alternatives[0].evidence.summary()
