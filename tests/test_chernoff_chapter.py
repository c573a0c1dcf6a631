"""Chapter 06 helpers (fusion.book.chapters.chernoff) and the Monte-Carlo helpers of the range-bearing scenario."""

from __future__ import annotations

import copy
import dataclasses
import json
import re
from pathlib import Path

import numpy as np
import pytest

from fusion.book.chapters import chernoff as chc
from fusion.book.ledger import STATUSES, Comparison
from fusion.scenarios import range_bearing as dist

TINY = dist.RangeBearingScenario(frames=6, n_particles=300, n_samples=300, n_central=600, em_iterations=5)
ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def study() -> list[dist.TrackingRun]:
    return dist.monte_carlo(TINY, 5, 3)


def test_random_spd_is_symmetric_positive_definite() -> None:
    rng = np.random.default_rng(0)
    for n in (1, 2, 4):
        A = chc.random_spd(rng, n)
        np.testing.assert_array_equal(A, A.T)
        assert np.min(np.linalg.eigvalsh(A)) >= 0.5 - 1e-12


def test_gaussian_checks_meet_their_tolerances() -> None:
    c = chc.gaussian_checks(np.random.default_rng(1), cases=10, triples=5)
    assert c.ok and c.k3 <= 1e-12 and 0 <= c.n_interior <= 5
    assert set(c.glue()) == {"chf_k1", "chf_k2", "chf_k5", "chf_k5_interior"}


def test_gaussian_checks_flag_a_failed_tolerance() -> None:
    c = chc.GaussianChecks(k1=1e-3, k2=0.0, k3=0.0, kis=0.0, k5=0.0, n_interior=1)
    assert not c.ok


def test_toy_study_bounds_and_minimisers() -> None:
    toy = chc.toy_study(np.random.default_rng(2), r=4000)
    assert np.all(toy.exact <= 1e-9)                 # K3: Z <= 1
    assert np.all(toy.foa >= toy.exact - 1e-9)       # K4: Z_FOA >= Z
    assert abs(toy.exact[0]) < 1e-6 and abs(toy.exact[-1]) < 1e-6
    assert 0 < toy.w_exact < 1 and 0 < toy.w_foa < 1 and 0 < toy.w_is < 1
    assert abs(toy.w_is - toy.w_exact) < 0.05
    g = toy.glue()
    assert g["chf_foa_min_gap"] >= 0 and g["chf_is_err_central"] <= g["chf_is_err_end"]


def test_contour_distances_are_l1_distances_of_densities() -> None:
    rng = np.random.default_rng(3)
    toy = chc.toy_study(rng, r=500)
    _, v = chc.contour_figure(toy, rng, n_particles=200)
    assert 0 <= v["chf_l1_full"] <= 2 and 0 <= v["chf_l1_simple"] <= 2


def test_criteria_example_gives_different_weights() -> None:
    v = chc.criteria_example()
    assert all(0 <= x <= 1 for x in v.values())
    assert v["chf_w_chernoff"] != v["chf_w_det"]


def test_monte_carlo_uses_one_spawned_seed_per_run(study: list[dist.TrackingRun]) -> None:
    assert len(study) == 3 and study[0].node_estimates is not None and study[1].node_estimates is None
    again = dist.run_tracking(TINY, np.random.SeedSequence(5).spawn(3)[2])
    np.testing.assert_array_equal(again.estimates["chernoff_pso"], study[2].estimates["chernoff_pso"])
    with pytest.raises(ValueError, match="runs"):
        dist.monte_carlo(TINY, 5, 0)
    with pytest.raises(TypeError, match="runs"):
        dist.monte_carlo(TINY, 5, 1.5)  # type: ignore[arg-type]


def test_errors_and_nees_helpers(study: list[dist.TrackingRun]) -> None:
    e2 = dist.position_sq_errors(study, "centralised")
    d = study[1].estimates["centralised"] - study[1].truth
    np.testing.assert_allclose(e2[1], d[:, 0] ** 2 + d[:, 2] ** 2)
    n = dist.nees_per_frame(study, "centralised")
    P = study[0].covariances["centralised"][3]
    e = study[0].estimates["centralised"][3] - study[0].truth[3]
    assert n[0, 3] == pytest.approx(float(e @ np.linalg.solve(P, e)), rel=1e-10)
    with pytest.raises(ValueError, match="key"):
        dist.position_sq_errors(study, "nope")
    with pytest.raises(ValueError, match="key"):
        dist.nees_per_frame(study, "mean_of_means")


def test_table_and_per_run_mse_agree(study: list[dist.TrackingRun]) -> None:
    crb = chc.crb_position(TINY, study)
    assert crb.shape == (TINY.frames,) and np.all(crb > 0)
    table = chc.method_table(study, crb)
    assert len(table) == len(dist.method_keys(3)) + 1
    for key in ("chernoff_pso", "ci_gaussian"):
        rmse = np.sqrt(np.mean(chc.per_run_mse(study, key)))
        assert table.loc[dist.METHODS[key], "RMSE from frame 5 (m)"] == pytest.approx(rmse, abs=0.005)


def test_collapsed_flags_a_run_below_the_threshold(study: list[dist.TrackingRun]) -> None:
    runs = [copy.deepcopy(r) for r in study]
    runs[1].ess["local"] = runs[1].ess["local"].copy()
    runs[1].ess["local"][0, 2] = 0.5 * chc.COLLAPSE_FRACTION * TINY.n_particles
    base = chc.collapsed(study, TINY.n_particles)
    flags = chc.collapsed(runs, TINY.n_particles)
    assert flags[1] and np.array_equal(np.delete(flags, 1), np.delete(base, 1))
    if not base.any():
        v = chc.collapse_values(runs, TINY)
        assert (v["chf_n_collapsed"], v["chf_collapse_run"], v["chf_collapse_frame"], v["chf_collapse_node"]) == (1, 2, 1, 3)


def test_claims_ledger_is_complete_and_written(study: list[dist.TrackingRun], tmp_path: Path) -> None:
    checks = chc.gaussian_checks(np.random.default_rng(1), cases=5, triples=3)
    toy = chc.toy_study(np.random.default_rng(2), r=2000)
    led = chc.claims(checks, toy, study, TINY, 5)
    assert sum(c.headline for c in led.claims) == 1
    assert all(c.status in STATUSES for c in led.claims)
    labels = {c.link for c in led.claims} | {x for c in led.claims for x in c.critiques}
    notebook = (ROOT / "notebooks" / "06_chernoff_fusion.ipynb").read_text(encoding="utf-8")
    boxes = set(re.findall(r":name: (chf-crit-[a-z-]+)", notebook))
    assert boxes and boxes <= labels
    for c in led.claims:
        if isinstance(c.evidence, Comparison):
            assert c.evidence.runs == len(study) and c.evidence.reason
    digest = led.write(tmp_path)
    data = json.loads((tmp_path / "cn107330468b.json").read_text(encoding="utf-8"))
    assert len(digest) == 16 and len(data["claims"]) == len(led.claims)
    v = chc.ledger_values(led)
    d, lo, hi = (v[f"chf_gain_uniform_{k}"] for k in ("d", "lo", "hi"))
    assert lo <= d <= hi


def test_benchmark_cost_reads_the_committed_results() -> None:
    cost, v = chc.benchmark_cost(ROOT / "benchmarks" / "results" / "chernoff.json")
    assert (cost["ms per frame"] > 0).all() and 0 < v["chf_em_share"] < 1 and v["chf_pso_ratio"] > 0


def test_guarded_runs_equal_a_study_run_with_the_guard_and_remove_the_collapse() -> None:
    """Only collapsed runs are redone, and the result is what a full guarded study gives."""
    sc = dist.RangeBearingScenario(frames=5, n_particles=600, n_samples=100, n_central=300, em_iterations=3,
                                   sigma_r=2.0, sigma_theta=0.005)  # precise sensors: some first updates collapse
    runs = dist.monte_carlo(sc, 5, 6, all_nodes_first=False)
    bad = chc.collapsed(runs, sc.n_particles)
    assert 0 < bad.sum() < len(runs)  # the case is informative: some runs collapse, some do not
    guarded = chc.guarded_runs(runs, sc, 5)
    full = dist.monte_carlo(dataclasses.replace(sc, guard=chc.COLLAPSE_FRACTION), 5, 6, all_nodes_first=False)
    for g, f, r, b in zip(guarded, full, runs, bad):
        for key in g.estimates:
            np.testing.assert_array_equal(g.estimates[key], f.estimates[key])
        assert bool(g.guarded) == bool(b)
        if not b:
            assert g is r
    assert chc.collapsed(guarded, sc.n_particles).sum() < bad.sum()
    v = chc.guard_values(guarded, sc)
    assert v["chf_n_guarded"] == int(bad.sum()) and v["chf_guard_ess_min"] > 0


def test_premise_helpers_on_small_networks() -> None:
    """Table, glue values, records and figure of the designed networks (small networks, 100 runs)."""
    from fusion.book.figures import audit_figure
    from fusion.scenarios.fusion_networks import premise_scenarios

    small = {k: dataclasses.replace(sc, n_particles=40, n_samples=40, n_components=2, em_iterations=2, stages=1)
             for k, sc in premise_scenarios().items()}
    studies = chc.premise_studies(3, chc.STUDY_RUNS, small)
    table = chc.premise_table(studies)
    assert list(table.columns) == list(chc.PREMISE_LABELS.values())
    v = chc.premise_values(studies)
    for k in chc.PREMISE_LABELS:
        assert v[f"chf_pr_{k}_eps_word"] in ("better", "worse", "not distinguishable")
        assert v[f"chf_pr_{k}_eps_lo"] <= v[f"chf_pr_{k}_eps_d"] <= v[f"chf_pr_{k}_eps_hi"]
    recs = chc.premise_claims(studies)
    assert [r.id for r in recs] == ["chf-premise-eps", "chf-premise-mixture", "chf-premise-double-count"]
    assert all(len(r.alternatives) == 3 for r in recs)
    assert not audit_figure(chc.premise_figure(studies))


def test_common_information_is_counted_once() -> None:
    ok, err_g, err_d = chc.common_information_check(np.random.default_rng(1), cases=20)
    assert ok and err_g < 1e-10 and err_d < 1e-12


def test_readings_values_and_records() -> None:
    sc = dataclasses.replace(TINY, readings=True, frames=3)
    runs = dist.monte_carlo(sc, 7, 3)
    v = chc.readings_values(runs)
    assert v["chf_rd_frames"] == 9 and 0 <= v["chf_rd_kl_frames"] <= 9
    # the rule fails only where the minimum of Ĵ lies on the boundary of the simplex
    assert v["chf_rd_frames"] - v["chf_rd_kl_frames"] <= v["chf_rd_boundary"]
