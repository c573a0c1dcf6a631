"""Tests of chapter 04's package code (lecture notes §§2.5 and 2.7): the ridge study's tables."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from fusion.scenarios import lecture_correlated as sc


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
    assert s.sd_ratio_max == pytest.approx(5 / 5.01)
    # the LS - ridge covariance gap is positive definite and vanishes as k -> 0
    assert s.var_gap_min_eig > 0
    tiny = sc.ridge_study(draws=10, ks_fixed=(1e-9,)).var_gap_min_eig
    assert 0 < tiny < 1e-6


@pytest.fixture(scope="module")
def studies():  # noqa: ANN201
    from fusion.book.chapters import lecture_correlated as ch
    from fusion.scenarios import correlated_sensors as cs
    from fusion.scenarios import ridge_sensors as rs

    p25 = rs.plugin_study(xs=(0.0, 0.25, 0.5, 1.0, 3.0, 10.0), runs=400, seed=3)
    return ch.Studies(s25=sc.ridge_study(draws=100), s27=sc.correlated_study(runs=500), p25=p25,
                      x25=ch.plugin_exact(p25), v25=rs.vector_study(runs=200, scales=(3.0, 30.0, 100.0)),
                      v25_well=rs.vector_study(runs=200, scales=(3.0, 30.0, 100.0), spread=1.0, seed=4),
                      cpl=cs.coupling_study(runs=500), cpl_wide=cs.coupling_study({ch.WIDE: ch.WIDE_CASE}, runs=500),
                      est=cs.estimated_covariance_study(ns=(10, 30), reps=50))


def test_chapter_04_evidence_follows_from_its_computations(studies) -> None:  # noqa: ANN001
    from fusion.book.chapters import lecture_correlated as ch
    from fusion.book.exact import ExactComparison
    from fusion.book.ledger import Conjunction, Proposition, Unverifiable
    from fusion.readings import biased as rg
    from fusion.readings import correlated as co
    from fusion.scenarios import correlated_sensors as cs

    ev = ch.ledger_evidence(studies)
    # the scalar plug-in record is exact: one exact comparison per x (R9, the margin), the reliabilities of plugin_risk
    plug = ev["lec-ridge-plugin"]["primary"]
    assert isinstance(plug, Conjunction)
    for lab, e in plug.parts:
        x = float(lab.split("= ")[1])
        r = rg.plugin_risk(np.sqrt(5) * x)
        assert isinstance(e, ExactComparison) and e.claim == "greater"
        assert e.a == pytest.approx(r.reliability, rel=1e-12) and e.b == pytest.approx(r.reliability_ls, rel=1e-12)
    # the multi-sensor existence record: the best fixed k of each x, exact, against tr A⁻¹
    v25 = studies.v25
    fb = ev["lec-ridge-fusion-better"]["primary"]
    assert isinstance(fb, Conjunction) and len(fb.parts) == len(v25.x)
    for (_, e), x in zip(fb.parts, v25.x.values()):  # one exact comparison per x, judged by the margin (R9)
        assert isinstance(e, ExactComparison) and e.claim == "less"
        assert e.a == pytest.approx(rg.best_ridge_k(v25.A, x)[1], rel=1e-12) and e.b == v25.tr_ls
    fp = ev["lec-ridge-fusion-plugin"]
    assert isinstance(fp["primary"], Conjunction) and len(fp["primary"].parts) == 6
    assert {"strong-3", "weak-3", "strong-100", "weak-100", "scalar-far"} <= set(fp)
    # the variance record reads a plug-in too: it does not reduce the variance everywhere
    cr = studies.x25.known[1.0]
    assert ev["lec-ridge-variance"]["plugin-known"].a == pytest.approx(cr["var_peak_ratio"], rel=1e-12)
    # the primary, an existence statement: the largest fixed k reduces the variance beyond the margin (R9);
    # every-k: one exact comparison of the scalar variance per k of the grid
    m0, kmax = studies.s25.m0, max(studies.s25.ks_fixed)
    p1 = ev["lec-ridge-variance"]["primary"]
    assert isinstance(p1, ExactComparison) and p1.a == pytest.approx((m0 / (m0 + kmax)) ** 2) and p1.b == 1.0
    vp = ev["lec-ridge-variance"]["every-k"]
    assert isinstance(vp, Conjunction) and len(vp.parts) == len(studies.s25.ks_fixed)
    assert all(isinstance(e, ExactComparison) and e.claim == "less" and e.a < e.b for _, e in vp.parts)
    # the Lagrange record: the scalar-weight method on a case that does not split, against GLS
    R = cs.oriented_covariance()
    H = np.kron(np.ones((3, 1)), np.eye(2))
    W, K = co.scalar_lagrange_weights(R, 2), co.gls_weights(H, R)
    ratio = np.trace(W @ R @ W.T) / np.trace(K @ R @ K.T)
    lag = ev["lec-lagrange-scalar-only"]["primary"]
    assert isinstance(lag, ExactComparison) and lag.claim == "greater" and lag.b == 1.0
    assert lag.a == pytest.approx(ratio, rel=1e-12)
    # E2.7's scalar twin is not counted again among the correlation structures
    cm = ev["lec-correlation-matters"]
    assert set(cm) == {"primary", "nees", "one-outside", "unequal", "unequal-strong", "two-sensors", "equal-wide"}
    assert cm["nees"].parts[1][1].holds                   # the naive fusion's NEES is outside the interval of 2
    assert isinstance(ev["lec-reliability-measure"], Unverifiable)
    assert isinstance(ev["lec-ldl-validated"], Unverifiable)


def test_ldl_cheaper_counts_the_route_as_written(studies) -> None:  # noqa: ANN001
    from fusion.book.chapters import lecture_correlated as ch
    from fusion.readings import correlated as co

    n, d = 600, 2
    w = co.ldl_as_written_count(n, d)
    # forming M = L⁻¹ costs N³/3 on top of the factor: 2N³/3 + N²(d+1) + 2Nd² + d³
    assert w == pytest.approx(2 * n**3 / 3 + n**2 * (d + 1) + 2 * n * d**2 + d**3, rel=1e-12)
    assert co.gesv_inverse_count(n, d) - co.operation_counts(n, d)["explicit"] == pytest.approx(2 * n**3 / 3)
    # R9: exact comparisons of counts, judged with the record's margin, the factor 2 (50 % of the baseline's count)
    ev = {k: e.with_margin(relative_margin=0.5) for k, e in ch.EVIDENCE["lec-ldl-cheaper"](studies).items()}
    assert ev["primary"].status() == "reproduced" and 2.9 < co.operation_counts(n, d)["explicit"] / w < 3.1  # 3.0x
    # 1.5x fewer against the SPD inverse: a saving inside the margin
    assert ev["spd-inverse"].status() == "not distinguishable" and 1.4 < co.spd_inverse_count(n, d) / w < 1.6
    assert ev["cholesky-solve"].status() == "contradicted" and ev["solve-route"].status() == "reproduced"
    assert ch.gesv_written_ratio(n, d) == pytest.approx(co.gesv_inverse_count(n, d) / w)


def test_chapter_04_ledger_builds_from_the_claim_file(studies, tmp_path) -> None:  # noqa: ANN001
    import re

    from fusion.book.chapters import lecture_correlated as ch
    from fusion.book.claims import build_ledger, claims_dir

    text = (claims_dir() / "lecture003.yaml").read_text(encoding="utf-8")
    values = {k: 1.0 for k in re.findall(r"\{([a-z_0-9]+)(?::[^}]*)?\}", text)}
    led = build_ledger("lecture003", ch.CHAPTER, ch.ledger_evidence(studies), values=values, claims=ch.claims_file())
    assert len(led.claims) == len(ch.EVIDENCE) and led.write(tmp_path)
    # the Cholesky / LDLᵀ count ratio is glued unrounded (from the counts, not the 2-decimal table)
    g = ch.glue_27(studies.s27)
    from fusion.readings import correlated as co
    oc = co.operation_counts(600, 2)
    assert g["lec_cor_flop_ratio_chol_600"] == pytest.approx(oc["cholesky"] / oc["ldl"], abs=5e-5)


def test_evidence_functions_serve_one_reading_for_a_reseeding_sweep() -> None:
    from fusion.book.chapters import lecture_correlated as ch
    from fusion.book.claims import evaluate
    from fusion.scenarios import correlated_sensors as cs

    cf = ch.claims_file()
    spec = cf.record("lec-correlation-matters")
    a = evaluate(spec, "unequal", seed=7, runs=300)
    st = ch.cached_studies(7, 300)                       # the same cached studies
    assert a.a == tuple(st.cpl.sq[cs.CouplingCase.UNEQUAL][0]) and len(a.a) == 300
    b = evaluate(spec, "unequal", seed=8, runs=300)      # a reseed of the same reading
    assert b.a != a.a
    with pytest.raises(ValueError, match="settings"):
        ch.ev_correlation_matters({"reading": "no-such-reading"}, seed=7, runs=300)
    assert evaluate(cf.record("lec-ldl-cheaper"), "spd-inverse", seed=7, runs=300).with_margin(
        relative_margin=0.5).status() == "not distinguishable"


def test_reading_of_picks_the_asked_reading() -> None:
    """:func:`fusion.book.chapters.lecture.reading_of`, the reading picker of chapters 04 and 07: one Evidence is
    the primary only; a mapping gives the asked key; anything else names ``settings``."""
    from fusion.book.chapters.lecture import reading_of
    from fusion.book.ledger import Proposition

    one, other = Proposition(True, "one"), Proposition(False, "other")  # Evidence: a non-Evidence names ev (fuzz 21b)
    assert reading_of("r", one, None) is one and reading_of("r", one, {"reading": "primary"}) is one
    both = {"primary": one, "alt": other}
    assert reading_of("r", both, {}) is one and reading_of("r", both, {"reading": "alt"}) is other
    for ev, settings in ((one, {"reading": "alt"}), (both, {"reading": "none"})):
        with pytest.raises(ValueError, match="settings"):
            reading_of("r", ev, settings)
    with pytest.raises(TypeError, match="settings"):  # fuzz 52 C7: one rule, a non-mapping is a TypeError
        reading_of("r", both, ["reading"])  # type: ignore[arg-type]


def test_sequential_pseudo_measurements_are_the_prefix_gls() -> None:
    from fusion.book.chapters import lecture_correlated as ch

    tab = ch.table_sequential(sigma=(1.0, 2.0, 0.5, 3.0), m=3, seed=7)
    g = ch.glue_sequential(tab)
    assert g["lec_seq_n"] == g["lec_seq_zero"] == g["lec_seq_same"] == 4
    n = 12  # rows r of a dense unit lower-triangular M have r off-diagonal entries
    assert g["lec_seq_mult"] == n * (n - 1) // 2 and g["lec_seq_full"] == 3 * (n - 1) * 4
    assert list(tab["readings used"]) == ["1-3", "1-6", "1-9", "1-12"]


def test_james_stein_exact_risk() -> None:
    from fusion.book.chapters import lecture_correlated as ch

    for d in (3, 5, 10):
        assert ch.james_stein_risk(d, 0.0) == pytest.approx(2.0 / d)
        r = [ch.james_stein_risk(d, x) for x in (0.5, 2.0, 8.0)]
        assert all(a < b < 1.0 for a, b in zip(r, r[1:]))
    assert ch.james_stein_risk(2, 3.0) == 1.0
    with pytest.raises(ValueError):
        ch.james_stein_risk(1, 1.0)
    tab = ch.table_james_stein(ds=(3, 6), ratios=(0.0, 2.0), runs=20000, seed=3)
    assert (tab["Monte Carlo"] - tab["exact"]).abs().max() < 0.05
    g = ch.glue_james_stein(tab, runs=20000)
    assert g["lec_js_min_3"] == pytest.approx(0.6667, abs=1e-4) and g["lec_js_min_6"] == pytest.approx(0.3333, abs=1e-4)


def test_shrunken_ls_exact_mse() -> None:
    from fusion.book.chapters import lecture_correlated as ch
    from fusion.scenarios import ridge_sensors as rs

    v = rs.vector_study(runs=2, seed=1, scales=(3.0, 30.0))
    tab = ch.table_shrunken(v)
    assert np.allclose(tab["LS"], float(f"{v.tr_ls:.4g}"))
    assert (tab["best c·LS"] <= tab["LS"]).all() and (tab["best ridge"] <= tab["LS"]).all()
    # an isotropic information matrix makes ridge c·LS with c = a/(a + k): the two optima agree
    case = ("strong direction", 3.0)  # one case: its true value and its runs (x and sq hold the same cases)
    iso = dataclasses.replace(v, A=4.0 * np.eye(2), x={case: np.array([2.0, 1.0])}, sq={case: v.sq[case]})
    row = ch.table_shrunken(iso).iloc[0]
    assert row["best ridge"] == pytest.approx(row["best c·LS"], rel=1e-3)
    g = ch.glue_shrunken(tab)
    assert g["lec_sh_n"] == 4 and 0 < g["lec_sh_min_ratio"] < 1


def test_ridge_study_counts_every_size_of_ms_in_its_work_budget():
    """fuzz13 bug 1: ms = 1..9999 (each valid, max(ms) x draws within the memory budget) drew 4 x draws x sum(ms)
    = 4e9 normals; the budget counts sum(ms) now and refuses it by name at once."""
    from fusion._validation import MAX_WORK

    ms = tuple(range(1, 10**4))
    assert 4 * 20 * sum(ms) > MAX_WORK
    with pytest.raises(ValueError, match="ms and draws"):
        sc.ridge_study(xs=(0.5, 3.0), ms=ms, m0=5, sigma=1.0, seed=1, seed_vector=2, draws=20)
