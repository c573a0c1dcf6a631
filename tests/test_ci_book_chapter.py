"""Chapter 03's package code: per-step weights, the fusion study, paired metrics, floors, tables and the ledger."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import numpy as np
import pytest

from fusion import data
from fusion import estimates as es
from fusion.book.chapters import ci as chapter
from fusion.scenarios import infrared_radar as ir
from fusion.scenarios import two_sensor

Q = np.diag([100.0] * 4)
R = np.diag([150.0**2] * 2)


@pytest.fixture(scope="module")
def sc() -> two_sensor.Scenario:
    return two_sensor.two_sensor_scenario(R, R, Q, np.random.default_rng(0), runs=6, T=2.0)


@pytest.fixture(scope="module")
def study(sc: two_sensor.Scenario) -> two_sensor.FusionStudy:
    w = np.full(sc.t.size, 0.5)
    return two_sensor.fusion_study(sc, w, w, published_omega=0.5)


def test_per_step_weights_shapes_and_asymmetric_optimum() -> None:
    s = two_sensor.two_sensor_scenario(R, R / 9, Q, np.random.default_rng(1), runs=2, T=5.0)
    w_foa, w_grid = two_sensor.per_step_weights(*s.tracks, seed=3, population=5, iterations=10)
    assert w_foa.shape == w_grid.shape == s.t.shape
    assert np.all((w_foa >= 0) & (w_foa <= 1)) and np.all((w_grid >= 0) & (w_grid <= 1))
    a, b = s.tracks
    for k in (5, 20):  # the grid lands within its spacing of the closed-form optimum
        assert abs(w_grid[k] - es.ci_weight(a.gains.P[k], b.gains.P[k])) <= 1e-3 + 1e-12


def test_fusion_study_identical_sensors(study: two_sensor.FusionStudy) -> None:
    assert set(study.est) == set(two_sensor.STUDY_METHODS)
    # identical sensors, ω = 0.5: CI, split CI and the convex combination give one estimate
    ref = study.est["CI (closed-form ω)"]
    for name in ("improved CI (split CI)", "convex comb. = multi-Bayesian = ML", "CI, ω by FOA"):
        np.testing.assert_allclose(study.est[name], ref, atol=1e-6)
    assert study.steady_rmse("CI (closed-form ω)", 0) == pytest.approx(float(study.rmse["CI (closed-form ω)"][study.steady, 0].mean()))
    assert study.floor.shape == (study.t.size, 2) and np.all(study.floor > 0)


def test_run_rmse_closed_form_and_validation() -> None:
    est = np.zeros((2, 3, 4))
    est[0, :, 0] = [3.0, 4.0, 0.0]
    truth = np.zeros((3, 4))
    got = two_sensor.run_rmse(est, truth, np.array([True, True, False]), 0)
    np.testing.assert_allclose(got, [np.sqrt(12.5), 0.0], atol=5e-4)  # rounded to mm
    with pytest.raises(ValueError):
        two_sensor.run_rmse(est, truth, np.zeros(3, bool), 0)
    with pytest.raises(ValueError):
        two_sensor.run_rmse(est[0], truth, np.ones(3, bool), 0)


def test_nees_study_local_filter_is_consistent() -> None:
    traj = two_sensor.trajectory(1.0)
    t, X = traj.t, traj.states
    nees, est = two_sensor.nees_study(np.random.default_rng(5), Q, R, R, X[0], 120, 200)
    assert 3.5 < nees["local filter (sensor 1)"] < 4.5       # consistent filter: mean NEES ≈ 4
    assert nees["convex combination"] > nees["split CI (eq. ci-split)"]  # independence assumed: too small a P
    assert est["truth"].shape == (200, 120, 4)


def test_floor_by_period_orders() -> None:
    rows = two_sensor.floor_by_period([0.5, 2.0], Q, 150.0)
    for r in rows.values():
        assert r["bound √P, no process noise (m)"] < r["bound √P, printed Q (m)"]
    assert rows[0.5]["bound √P, printed Q (m)"] < rows[2.0]["bound √P, printed Q (m)"]
    with pytest.raises(ValueError):
        two_sensor.floor_by_period([1.0], Q, -1.0)


def test_tables_and_figures(study: two_sensor.FusionStudy, sc: two_sensor.Scenario) -> None:
    t = chapter.rmse_table(study)
    assert t.shape[0] == sum(len(v) for v in chapter.figure_rows().values()) + 1
    assert t.loc[("Fig. 4", "CI without convex part"), "published (m)"] == data.WANG2024_RMSE.columns["ci"][0]
    for fig in (chapter.rmse_figure(study), chapter.fig3(sc)):
        assert len(fig.axes) >= 1
    P1, P2 = sc.tracks[0].gains.P[10], sc.tracks[1].gains.P[10] / 9
    res = chapter.weight_search(P1, P2, np.random.default_rng(0))
    best = res["closed form (eq. ci-closed)"].fun
    assert all(r.fun >= best - 1e-9 * best for r in res.values())
    assert list(chapter.foa_table(res)["evaluations"])[-1] == 0
    m = dict.fromkeys(["foa_vectorised", "foa_loop", "grid_vectorised", "grid_loop", "bounded", "closed_form",
                       "sim_ci", "sim_improved", "sim_convex", "sim_fuzzy", "sim_ci_foa"], 0.01)
    assert chapter.timing_table(m).shape == (12, 3)
    assert chapter.split_foa_gap(sc, 10, np.random.default_rng(0)) >= -1e-9
    with pytest.raises(ValueError):
        chapter.split_foa_gap(sc, 10_000, np.random.default_rng(0))


def test_ir_helpers() -> None:
    sim, rmse = chapter.ir_study(0.5, seed=1, runs=4, duration=5.0)
    assert set(rmse) == {"infrared alone", "radar alone", *ir.RULES, ir.PER_SCAN}
    means = ir.late_means(rmse, sim.t)
    assert means["infrared alone"]["azimuth (mrad)"] < means["radar alone"]["azimuth (mrad)"]
    with pytest.raises(ValueError):
        ir.late_means(rmse, sim.t, t_min=1e6)
    table = chapter.ir_table(rmse, sim.t)
    assert "published: improved CI (Figs. 9-10)" in table.index
    fig, inside = chapter.fig11(sim)
    assert 0.0 <= inside <= 1.0


def test_claims_ledger(study: two_sensor.FusionStudy) -> None:
    rng = np.random.default_rng(0)
    names = ["improved CI (split CI)", "CI (closed-form ω)", "convex comb. = multi-Bayesian = ML", "fuzzy clustering",
             "CI, ω by FOA", "CI, ω by exhaustive search"]
    paired = {n: 50 + rng.standard_normal(100) for n in names}
    sq = es.ci_objective(0.5, np.eye(2), np.eye(2))
    from fusion.optimise.result import OptimumResult
    res = {"FOA (30 × 200)": OptimumResult(0.1, 2.0, 6000), "exhaustive, 1001 points": OptimumResult(0.0, 1.0, 1001)}
    means = {n: {"azimuth (mrad)": 0.1, "elevation (mrad)": 0.1, "x (m)": 2.0, "y (m)": 1.0} for n in names}
    ledger = chapter.claims({
        "study": study, "paired": paired, "paired_runs": 100, "paired_seed": 1, "model_rmse": {"x": 60.0, "y": 60.0},
        "nees": {"eqs. 11-12 as printed (same ω)": 6.0, "split CI (eq. ci-split)": 4.0}, "nees_runs": 50,
        "eq2_error": 1.0, "eq6_asym": 1.0, "flat_range": float(sq * 0), "search": res,
        "bench": {"foa_vectorised": 1.0, "grid_vectorised": 0.1, "ratio_improved_vs_ci": 1.5}, "bench_date": "today",
        "ir_means": means, "ir_sens": {0.1: means[names[0]], 0.5: means[names[0]]}, "ir_T": 0.1,
        "ir_paired": paired, "ir_seed": 2})
    assert sum(c.headline for c in ledger.claims) == 1
    labels = {c.link for c in ledger.claims} | {x for c in ledger.claims for x in c.critiques}
    for box in ("ci-crit-eq2", "ci-crit-eq679", "ci-crit-eq1112", "ci-crit-gq", "ci-crit-foa", "ci-crit-rmse",
                "ci-crit-baselines", "ci-crit-times", "ci-crit-irradar"):
        assert box in labels
    rec = {c.id: c for c in ledger.claims}
    assert rec["ci-fig5-foa-optimum"].status == "contradicted"       # FOA's tr P above the grid's
    assert rec["ci-fig10-x-below-y"].status == "contradicted"        # x 2 m > y 1 m
    assert rec["ci-rmse-3m"].status == "not reproduced"              # ours far from 3 m
    assert "bound" not in rec["ci-rmse-3m"].claim
