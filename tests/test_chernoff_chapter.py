"""Chapter 06 helpers (fusion.book.chapters.chernoff) and the Monte-Carlo helpers of the range-bearing scenario."""

from __future__ import annotations

import dataclasses
import json
import re
from pathlib import Path

import numpy as np
import pytest

from fusion.book.style import METHOD_LABELS
from fusion.book.chapters import chernoff as chc
from fusion.book.ledger import Comparison, Proposition
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
    assert np.all(toy.first_order >= toy.exact - 1e-9)       # K4: Z_FO >= Z
    assert abs(toy.exact[0]) < 1e-6 and abs(toy.exact[-1]) < 1e-6
    assert 0 < toy.w_exact < 1 and 0 < toy.w_first_order < 1 and 0 < toy.w_is < 1
    assert abs(toy.w_is - toy.w_exact) < 0.05
    g = toy.glue()
    assert g["chf_first_order_min_gap"] >= 0 and g["chf_is_err_central"] <= g["chf_is_err_end"]


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
    e2 = dist.position_sq_errors(study, "centralised_pf")
    d = study[1].estimates["centralised_pf"] - study[1].truth
    np.testing.assert_allclose(e2[1], d[:, 0] ** 2 + d[:, 2] ** 2)
    n = dist.nees_per_frame(study, "centralised_pf")
    P = study[0].covariances["centralised_pf"][3]
    e = study[0].estimates["centralised_pf"][3] - study[0].truth[3]
    assert n[0, 3] == pytest.approx(float(e @ np.linalg.solve(P, e)), rel=1e-10)
    with pytest.raises(ValueError, match="key"):
        dist.position_sq_errors(study, "nope")
    with pytest.raises(ValueError, match="key"):
        dist.nees_per_frame(study, "mean_of_local_means")


def test_method_keys_have_labels_in_the_style_registry() -> None:
    """Both studies' methods are keys with one registered label each; a key names one method in every chapter."""
    from fusion.scenarios.fusion_networks import NETWORK_METHODS

    for keys in (dist.METHODS, NETWORK_METHODS):
        assert len(set(keys)) == len(keys) and all(k in METHOD_LABELS for k in keys)
    # the two studies share a key only for the same method (one label), so the centralised filter of the tracking
    # study and the network study's exact posterior are different keys
    assert len({METHOD_LABELS[k] for k in (*dist.METHODS, *NETWORK_METHODS)}) == len(set(dist.METHODS) | set(NETWORK_METHODS))
    assert set(dist.method_keys(3, readings=True)) == set(dist.METHODS)


def test_table_and_per_run_mse_agree(study: list[dist.TrackingRun]) -> None:
    crb = chc.crb_position(TINY, study)
    assert crb.shape == (TINY.frames,) and np.all(crb > 0)
    table = chc.method_table(study, crb)
    assert len(table) == len(dist.method_keys(3)) + 1
    for key in ("chernoff_pso", "ci_gaussian"):
        rmse = np.sqrt(np.mean(chc.per_run_mse(study, key)))
        assert table.loc[METHOD_LABELS[key], "RMSE from frame 5 (m)"] == pytest.approx(rmse, abs=0.005)


def test_collapsed_flags_a_run_below_the_threshold(study: list[dist.TrackingRun]) -> None:
    # no collapse anywhere, then one node of run 2 and the centralised filter of run 3 (runs are frozen: rebuilt)
    local = [np.full_like(r.ess["local"], TINY.n_particles / 2) for r in study]
    central = [np.full_like(r.ess["centralised_pf"], TINY.n_central / 2) for r in study]
    local[1][0, 2] = 0.5 * chc.COLLAPSE_FRACTION * TINY.n_particles
    central[2][3] = 0.5 * chc.COLLAPSE_FRACTION * TINY.n_central
    runs = [dataclasses.replace(r, ess={**r.ess, "local": lo, "centralised_pf": ce})
            for r, lo, ce in zip(study, local, central)]
    assert chc.collapsed(runs, TINY.n_particles).tolist() == [False, True, False]
    assert chc.central_collapsed(runs, TINY.n_central).tolist() == [False, False, True]
    assert chc.any_collapsed(runs, TINY).tolist() == [False, True, True]
    assert chc.typical_run(runs, TINY.n_particles, TINY.n_central) == 0
    v = chc.collapse_values(runs, TINY)
    assert (v["chf_n_collapsed"], v["chf_n_central_collapsed"], v["chf_n_any_collapsed"], v["chf_runs_kept"]) == (1, 1, 2, 1)
    assert v["chf_collapse_text"].startswith("run 2, node 3, frame 1")
    runs = [dataclasses.replace(r, ess={**r.ess, "centralised_pf": np.zeros_like(r.ess["centralised_pf"])}) for r in runs]
    with pytest.raises(ValueError, match="kept"):
        chc.collapse_values(runs, TINY)


def test_chapter_evidence_builds_the_claim_files_ledger(tmp_path: Path) -> None:
    """Every record of the claim file gets its evidence from its function, reading by reading; the ledger builds."""
    from fusion.book.claims import build_ledger
    from fusion.scenarios.fusion_networks import premise_scenarios, redundancy_scenarios

    sc = dataclasses.replace(TINY, readings=True, prev_optimiser="newton")
    small = {k: dataclasses.replace(x, n_particles=40, n_samples=40, n_components=2, em_iterations=2, stages=1)
             for k, x in (premise_scenarios() | redundancy_scenarios()).items()}
    ev = chc.chapter_evidence(3, 8, sc=sc, scenarios=small, network_runs=chc.STUDY_RUNS)
    led = build_ledger(chc.BIBKEY, None, ev, values=chc.claim_values(3, 8, sc=sc, scenarios=small,
                                                                     network_runs=chc.STUDY_RUNS))
    assert sum(c.headline for c in led.claims) == 1 and next(c for c in led.claims if c.headline).claimant == "source"
    # F2 of review 5: the source's records whose formula is lost cannot be checked; the rebuild's checks are the book's
    by_id = {c.id: c for c in led.claims}
    for rid in ("chf-foa", "chf-is", "chf-pso"):
        assert by_id[rid].status == "cannot be checked" and by_id[f"{rid}-rebuild"].claimant == "book"
    assert by_id["chf-pso-rebuild"].runs == 8  # the rebuild's swarm check carries a run count: the sweep covers it
    # the tracking comparisons are the per-run MSE of the cached study, recomputed here
    plain, guarded = chc.tracking_study(3, 8, sc)
    gu = ev["chf-gain-uniform"]["primary"]
    np.testing.assert_allclose(gu.a, chc.per_run_mse(guarded, "chernoff_pso"))
    np.testing.assert_allclose(gu.b, chc.per_run_mse(guarded, "chernoff_uniform"))
    np.testing.assert_allclose(ev["chf-gain-uniform"]["plain-filters"].a, chc.per_run_mse(plain, "chernoff_pso"))
    dc = ev["chf-double-count"]
    np.testing.assert_allclose(dc["primary"].a, chc.per_run_nees(guarded, "naive_product", chc.ALL_FRAMES))
    assert np.all(np.asarray(dc["primary"].b) == chc.NEES_CONSISTENT)
    assert np.all(np.asarray(dc["chernoff-conservative"].a) == chc.NEES_CONSISTENT)
    # the network readings: the named network's per-run MSE; the sign test on the loss indicator
    nets = chc.premise_study(3, chc.STUDY_RUNS, small)
    pe = ev["chf-premise-eps"]
    np.testing.assert_allclose(pe["relay"].a, nets["relay"].mse("chernoff_pso"))
    np.testing.assert_allclose(pe["oracle-unequal"].a, chc.oracle_exponents(nets["unequal"])[1])
    loss = ev["chf-premise-mixture"]["share-of-runs"]
    st = nets["non_gaussian"]
    np.testing.assert_allclose(loss.a, (st.mse("chernoff_pso") >= st.mse("ci_gaussian")).astype(float))
    assert st.runs == chc.STUDY_RUNS and nets["relay"].runs == chc.STUDY_RUNS  # every network at 100 (review 5, m3)
    # chf-is-rebuild: independent sample sets against the first-order minimiser, which draws nothing
    isr = ev["chf-is-rebuild"]["primary"]
    np.testing.assert_allclose(isr.a, chc.is_replicates(3, 2000, 8))
    assert len(set(isr.b)) == 1 and len(isr.a) == 8
    # chf-filter-design: the whole study's collapse count and the repaired filters themselves
    fd = ev["chf-filter-design"]["primary"]
    assert [name for name, _ in fd.parts] == ["no collapse in the study", "the repaired filters usable"]
    digest = led.write(tmp_path)
    data = json.loads((tmp_path / "cn107330468b.json").read_text(encoding="utf-8"))
    assert len(digest) == 16 and len(data["claims"]) == len(led.claims)
    v = chc.ledger_values(led)
    assert v["chf_gain_uniform_lo"] <= v["chf_gain_uniform_d"] <= v["chf_gain_uniform_hi"]
    assert v["chf_source_n"] + v["chf_implied_n"] + v["chf_book_n"] == len(led.claims)
    labels = {c.link for c in led.claims} | {x for c in led.claims for x in c.critiques}
    notebook = (ROOT / "notebooks" / "06_chernoff_fusion.ipynb").read_text(encoding="utf-8")
    boxes = set(re.findall(r":name: (chf-crit-[a-z-]+)", notebook))
    assert boxes and boxes <= labels


def test_evidence_functions_refuse_bad_settings() -> None:
    with pytest.raises(ValueError, match="settings"):
        chc.ev_tracking({"a": "chernoff_pso"}, seed=1, runs=3, sc=TINY)  # b missing
    with pytest.raises(ValueError, match="settings"):
        chc.ev_tracking({"a": "chernoff_pso", "b": "nope"}, seed=1, runs=3, sc=TINY)
    with pytest.raises(ValueError, match="settings"):
        chc.ev_pso({"check": "vibes"}, seed=1, runs=3, sc=TINY)
    with pytest.raises(ValueError, match="settings"):
        chc.ev_premise({"network": "moon", "a": "chernoff_pso", "b": "ci_gaussian"}, seed=1, runs=3)
    with pytest.raises(TypeError, match="settings"):  # fuzz 52 C7: one rule, a non-mapping is a TypeError
        chc.ev_gaussian_ci([], seed=1, runs=3)
    with pytest.raises(ValueError, match="statement"):
        chc.ev_gaussian_ci({"statement": "all three"}, seed=1, runs=3)


def test_nested_gaussian_weight_is_the_chernoff_minimiser() -> None:
    """1/ln k − 1/(k−1): the numerical Chernoff weight on the sharper of N(0, I), N(0, kI), in 1-D and 3-D."""
    from fusion.estimates import chernoff as ch

    for k in (1.5, 4.0, 50.0, 1e3):
        for d in (1, 3):
            num = ch.gaussian_chernoff_weights(np.zeros((2, d)), np.stack([np.eye(d), k * np.eye(d)])).eps[0]
            assert num == pytest.approx(float(chc.nested_gaussian_weight(k)), abs=1e-6)
    w = chc.nested_gaussian_weight(np.array([2.0, 10.0, 1e6]))
    assert np.all(np.diff(w) < 0) and w[-1] < 0.1  # leans ever more to the vaguer density
    with pytest.raises(ValueError, match="k"):
        chc.nested_gaussian_weight(1.0)
    v = chc.nested_values()
    assert v["chf_nest_err"] < 1e-6


def test_oracle_exponents_minimise_the_mean_squared_error_on_the_grid() -> None:
    from fusion.scenarios.fusion_networks import redundancy_scenarios, run_network_study

    sc = dataclasses.replace(redundancy_scenarios()["overconfident"], n_particles=80, n_samples=40, n_components=2,
                             em_iterations=2)
    st = run_network_study(sc, 5, 30)
    eps, mse = chc.oracle_exponents(st, step=0.1)
    assert eps.sum() == pytest.approx(1.0) and mse.shape == (30,)
    J = np.linalg.inv(st.local_cov)

    def mean_se(e: np.ndarray) -> float:
        x = np.linalg.solve(np.einsum("n,bnij->bij", e, J), np.einsum("n,bnij,bnj->bi", e, J, st.local_mean)[..., None])
        return float(np.mean(np.sum((x[..., 0] - st.truth) ** 2, axis=-1)))
    best = mean_se(eps)
    for e in ([1 / 3, 1 / 3, 1 / 3], [0.5, 0.5, 0.0], [0.2, 0.3, 0.5], [1.0, 0.0, 0.0]):
        assert best <= mean_se(np.array(e)) + 1e-9
    with pytest.raises(ValueError, match="one exchange"):
        chc.oracle_exponents(run_network_study(dataclasses.replace(sc, frames=2), 5, 3))


def test_benchmark_cost_reads_the_committed_results() -> None:
    cost, v = chc.benchmark_cost(ROOT / "benchmarks" / "results" / "chernoff.json")
    assert (cost["ms per frame"] > 0).all()
    bench = json.loads((ROOT / "benchmarks" / "results" / "chernoff.json").read_text(encoding="utf-8"))
    if not v["chf_bench_current"]:  # a file from before the current pipeline is not read as a measurement
        assert cost.empty and v["chf_bench_text"].startswith("not measured yet")
    else:  # the words name the file they were read from: its date and its run count
        assert v["chf_bench_date"] in v["chf_bench_text"] and v["chf_bench_date"] in v["chf_pso_ratio_text"]
        assert v["chf_bench_text"].startswith(f"{int(bench['runs'])} runs ")


def test_benchmark_stage_keys_are_the_writers(monkeypatch: pytest.MonkeyPatch) -> None:
    """The stages the chapter reads by key are stages ``benchmarks/bench_chernoff.py`` writes, and the committed file
    carries the writer's keys, each with the writer's label (its stage keys once drifted from the writer's)."""
    import importlib
    monkeypatch.syspath_prepend(str(ROOT / "benchmarks"))
    stages = importlib.import_module("bench_chernoff").STAGES
    assert set(chc.BenchStage) <= set(stages) and set(chc.PATENT_STAGES) < set(chc.BenchStage)
    bench = json.loads((ROOT / "benchmarks" / "results" / "chernoff.json").read_text(encoding="utf-8"))
    for m in (m for m in bench["measurements"] if "stage" in m):
        assert m["what"].endswith(f", {stages[m['stage']]}: seconds per frame"), m


def test_benchmark_cost_reads_a_current_file(tmp_path: Path) -> None:
    """The parsed numbers follow the file: EM's share of stages B-I, the 60 s verdict for 100 runs on 2 cores."""
    S = chc.BenchStage
    stages = {(S.PARTICLE_FILTERS, "B: local particle filters (3 nodes)"): 0.01,
              (S.EM, "C: weighted EM (3 nodes)"): 0.03, (S.FIRST_ORDER, "D: first-order fusion"): 0.01,
              (S.OPTIMISER, "G: particle swarm"): 0.02, (S.REFERENCE, "SLSQP on the same samples (reference)"): 0.5}
    ms = [{"what": f"004 study, {lab}: seconds per frame", "value": x, "unit": "s", "stage": str(k)}
          for (k, lab), x in stages.items()]
    for seconds in (50.0, 70.0):
        keys = {"loop_seconds": 200.0, "study_seconds": 100.0, "study_seconds_workers": seconds,
                "loop_over_batch": 2.0, "identical": 1.0, "pso_over_slsqp": 9.0}
        ms2 = ms + [{"what": k, "value": x, "unit": "", "key": k} for k, x in keys.items()]
        path = tmp_path / "chernoff.json"
        path.write_text(json.dumps({"date": "2030-01-01", "schema": chc.BENCH_SCHEMA, "runs": 100, "workers": 2,
                                    "measurements": ms2}), encoding="utf-8")
        cost, v = chc.benchmark_cost(path)
        assert v["chf_bench_current"] and list(cost.index) == [lab for _, lab in stages]   # shown by label
        assert ("within" in v["chf_bench_text"]) == (seconds <= 60.0) and "identical" in v["chf_bench_text"]
        assert f"{0.03 / 0.07:.2f}" in v["chf_bench_stage_text"]  # EM over B, C, D and G (the reference excluded)
        assert v["chf_pso_ratio_text"].startswith("9 times")


def test_guarded_runs_equal_a_study_run_with_the_guard_and_remove_the_collapse() -> None:
    """Only collapsed runs (a node or the centralised filter) are redone, and the result is what a full guarded
    study gives; the guard of the centralised filter is applied too."""
    sc = dist.RangeBearingScenario(frames=5, n_particles=600, n_samples=100, n_central=300, em_iterations=3,
                                   sigma_r=2.0, sigma_theta=0.005)  # precise sensors: some first updates collapse
    runs = dist.monte_carlo(sc, 5, 6, all_nodes_first=True)
    bad = chc.any_collapsed(runs, sc)
    assert 0 < bad.sum() < len(runs)  # the case is informative: some runs collapse, some do not
    guarded = chc.guarded_runs(runs, sc, 5, workers=2)
    full = dist.monte_carlo(chc.guarded_scenario(sc), 5, 6, all_nodes_first=True)
    for g, f, r, b in zip(guarded, full, runs, bad):
        for key in g.estimates:
            np.testing.assert_array_equal(g.estimates[key], f.estimates[key])
        assert bool(g.guarded) == bool(b)
        assert (g.node_estimates is None) == (r.node_estimates is None)
        if not b:
            assert g is r
    assert any(i < 0 for g in guarded for _, i in g.guarded)  # the centralised filter was guarded somewhere
    assert chc.any_collapsed(guarded, sc).sum() < bad.sum()
    v = chc.guard_values(guarded, sc)
    assert v["chf_n_guarded"] == int(bad.sum()) and v["chf_guard_ess_min"] > 0 and v["chf_guard_central"] > 0


def test_premise_helpers_on_small_networks() -> None:
    """Table, glue values, records and figure of the designed networks (small networks, 100 runs).

    The studies are those of the ledger test above (``premise_study``, cached: computed once in this module's worker).
    """
    from fusion.book.figures import audit_figure
    from fusion.scenarios.fusion_networks import premise_scenarios, redundancy_scenarios

    small = {k: dataclasses.replace(sc, n_particles=40, n_samples=40, n_components=2, em_iterations=2, stages=1)
             for k, sc in (premise_scenarios() | redundancy_scenarios()).items()}
    studies = chc.premise_study(3, chc.STUDY_RUNS, small)
    assert all(st.runs == chc.STUDY_RUNS for st in studies.values())
    table = chc.premise_table(studies)
    assert list(table.columns) == list(chc.PREMISE_LABELS.values())
    v = chc.premise_values(studies)
    for k in chc.PREMISE_LABELS:
        assert v[f"chf_pr_{k}_eps_word"] in ("better", "worse", "not distinguishable", "no different beyond the margin")
        assert v[f"chf_pr_{k}_eps_lo"] <= v[f"chf_pr_{k}_eps_d"] <= v[f"chf_pr_{k}_eps_hi"]
    robust = chc.premise_robust_values(studies)
    for k, st in studies.items():  # the robust readings follow the per-run differences
        d = st.mse("chernoff_pso") - st.mse("ci_gaussian")
        assert robust[f"chf_pr_{k}_mix_win"] == pytest.approx(np.mean(d < 0), abs=1e-3)
        assert robust[f"chf_pr_{k}_mix_median"] == pytest.approx(np.median(d), abs=0.01)
        assert robust[f"chf_pr_{k}_mix_win_lo"] <= robust[f"chf_pr_{k}_mix_win"] <= robust[f"chf_pr_{k}_mix_win_hi"]
        assert 0 < robust[f"chf_pr_{k}_mix_top3"] <= 1 and 0 <= robust[f"chf_pr_{k}_mix_sign_p"] <= 1
    more = chc.premise_studies(3, 4, small, more={"non_gaussian": 6})  # the per-network run counts (few runs suffice)
    assert more["non_gaussian"].runs == 6 and all(more[k].runs == 4 for k in chc.PREMISE_LABELS if k != "non_gaussian")
    assert not audit_figure(chc.premise_figure(studies))


def test_guard_usability_ranks_the_guarded_runs_among_the_others() -> None:
    sc = dist.RangeBearingScenario(frames=5, n_particles=600, n_samples=100, n_central=300, em_iterations=3,
                                   sigma_r=3.0, sigma_theta=0.008)  # precise sensors: some first updates collapse
    plain = dist.monte_carlo(sc, 5, 10, all_nodes_first=True)
    guarded = chc.guarded_runs(plain, sc, 5, workers=1)
    v = chc.guard_usability(guarded, plain, sc)
    hit = np.array([bool(r.guarded) for r in guarded])
    assert v["chf_gu_runs"] == hit.sum() > 0
    mse = chc.per_run_mse(guarded, "chernoff_pso")
    assert v["chf_gu_mse_max"] == pytest.approx(mse[hit].max(), abs=0.01)
    assert v["chf_gu_usable"] == bool(v["chf_gu_nees_max"] <= v["chf_gu_nees_p95"] + 0.005
                                      and v["chf_gu_mse_max"] <= v["chf_gu_mse_p95"] + 0.005)
    assert v["chf_gu_own_n"] == len({(j, i) for j, r in enumerate(guarded) for _, i in r.guarded})
    assert v["chf_gu_own_usable"] == (v["chf_gu_own_ratio_max"] <= 1.0 + 0.005) and bool(guarded[v["chf_gu_worst_run"] - 1].guarded)
    # a higher threshold triggers in at least as many runs and updates
    assert v["chf_gu_thr0_runs"] <= v["chf_gu_thr1_runs"] and v["chf_gu_thr0_updates"] <= v["chf_gu_thr1_updates"]
    with pytest.raises(ValueError, match="guarded"):
        chc.guard_usability(guarded[:1] + [g for g in guarded if g.guarded], plain, sc)


def test_double_count_values_read_the_linearised_analysis(study: list[dist.TrackingRun]) -> None:
    v = chc.double_count_values(study, TINY)
    lin = dist.linearised_errors(TINY)
    assert v["chf_lin_nees_end"] == pytest.approx(lin.nees_naive[-1], abs=0.005)
    assert v["chf_lin_nees_min"] <= v["chf_lin_nees_end"] and v["chf_lin_nees_min"] <= v["chf_lin_nees_1"]
    assert v["chf_lin_noq_late"] <= v["chf_lin_nees_late"] + 0.01 and v["chf_lin_best_pct"] >= 0


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


def test_design_study_compares_the_first_update_of_the_same_runs() -> None:
    """More particles raise the first update's effective sample size; the guard lifts every node above the threshold."""
    sc = dist.RangeBearingScenario(frames=5, n_particles=600, n_samples=100, n_central=300, em_iterations=3,
                                   sigma_r=2.0, sigma_theta=0.005)
    d = chc.design_study(sc, 5, runs=6, n_initial=3000, workers=1)
    assert set(d.ess) == {"plain", "more particles", "guard"} and d.ess["plain"].shape == (6, 3)
    g = d.glue()
    assert g["chf_design_plain_collapsed"] > 0 and g["chf_design_guard_collapsed"] == 0
    assert g["chf_design_more_min"] > g["chf_design_plain_min"]
    assert g["chf_design_more_cost"] == 3000 and sc.n_particles <= g["chf_design_guard_cost"] <= 10 * sc.n_particles
    # the guard design redoes only the runs that collapse: the same as running every run with the guard
    one = dataclasses.replace(sc, frames=1, variants=False, readings=False, n_samples=50, n_central=50, em_iterations=1,
                              guard=chc.COLLAPSE_FRACTION)
    full = dist.run_tracking_batch(one, np.random.SeedSequence(5).spawn(6))
    np.testing.assert_array_equal(d.ess["guard"], np.stack([r.ess["local"][0] for r in full]))
    assert d.weighted["guard"] == pytest.approx((sc.n_particles * 18 + sum(len(r.guarded) for r in full)
                                                 * (dist.GUARD_STAGES - 1) * sc.n_particles) / 18)


def test_stopping_values_read_every_rule_from_the_traced_swarm() -> None:
    sc = dataclasses.replace(TINY, readings=True, frames=5)
    runs = dist.monte_carlo(sc, 7, 6)  # six runs: the rulebook's median interval needs them
    v = chc.stopping_values(runs, sc)
    assert v["chf_stop_frames"] == 30 and v["chf_stop_limit"] == 1020
    # the first tolerance is the recorded literal rule
    assert v["chf_stop_evals_0"] == pytest.approx(np.mean([r.evaluations["literal"] for r in runs]), abs=0.5)
    # a looser tolerance never stops later
    assert v["chf_stop_evals_0"] >= v["chf_stop_evals_1"] >= v["chf_stop_evals_2"] >= v["chf_stop_evals_3"]
    assert v["chf_stop_mse_lo"] <= v["chf_stop_mse_d"] <= v["chf_stop_mse_hi"]
    from fusion.book.figures import audit_figure
    assert not audit_figure(chc.pso_figure(runs, frame=2)[0])


def test_consistency_figure_passes_the_audit(study: list[dist.TrackingRun]) -> None:
    from fusion.book.figures import audit_figure
    assert not audit_figure(chc.consistency_figure(study, study, TINY))


def test_gm_yardstick_is_small_on_gaussian_particles(study: list[dist.TrackingRun]) -> None:
    """The mixture's gain on truly Gaussian weighted particles: positive (more parameters) and small."""
    v = chc.gm_yardstick(np.random.default_rng(4), study, TINY, sets=10)
    assert 0 < v["chf_gm_yard_late"] <= v["chf_gm_yard_late_hi"] < 0.05
    assert 0 < v["chf_gm_ess_1"] <= 1


def test_is_variance_study_can_fail_and_confirms_the_bias() -> None:
    """The bias check passes, and an estimator without bias would be many standard errors from the prediction."""
    # the chapter's study (notebook 06: isv_study(SEED), SEED = 2017, i.e. default_rng(2020) and 20,000 replicates),
    # read from the run's study cache when the notebook has computed it
    isv = chc.isv_study(2017)
    assert isv.ok and isv.power > 3
    assert isv.lo < isv.lo3 < 0.5 < isv.hi3 < isv.hi
    t = isv.table
    assert not t.loc[0.8, "3rd moment finite"] and t.loc[0.2, "3rd moment finite"]
    assert (t["bias sampled"] <= 0).all()  # Jensen: log of an unbiased estimate is biased low
    few = chc.is_variance_study(np.random.default_rng(2020), replicates=200)
    assert few.power < isv.power  # fewer replicates, a weaker test


def test_first_update_ess_does_not_depend_on_the_fusion_or_the_centralised_filter() -> None:
    """design_study and diagnostics run the fusion and the centralised filter small: the nodes' first-update
    effective sample sizes are drawn and computed before them, from the nodes' own streams."""
    one = dataclasses.replace(TINY, frames=1, variants=False)
    small = dataclasses.replace(one, n_samples=20, n_central=20, em_iterations=1)
    for sc in (one, dataclasses.replace(one, guard=chc.COLLAPSE_FRACTION)):
        a = dist.run_tracking_batch(sc, np.random.SeedSequence(3).spawn(4))
        b = dist.run_tracking_batch(dataclasses.replace(small, guard=sc.guard), np.random.SeedSequence(3).spawn(4))
        for x, y in zip(a, b):
            np.testing.assert_array_equal(x.ess["local"], y.ess["local"])


def test_referenced_keeps_only_the_glue_values_something_reads() -> None:
    keys = chc._referenced_keys()
    assert "chf_runs" in keys and "chf_gain_uniform_d" in keys  # read by the chapter's prose
    assert "chf_n_any_collapsed" in keys  # a {name} field of the claim file
    kept = chc.referenced({"chf_runs": 100, "chf_nobody_reads_this": 1})
    assert kept == {"chf_runs": 100}


def test_message_sizes_count_the_numbers_sent() -> None:
    v = chc.message_sizes(dataclasses.replace(TINY, n_components=2), d=2)
    assert v["chf_msg_gm"] == 2 * (1 + 2 + 3) and v["chf_msg_pf"] == TINY.n_particles * 3


def test_a_record_can_be_reevaluated_from_the_claim_file_with_another_seed() -> None:
    """fusion.book.claims.evaluate calls the record's evidence function with its reading's settings (a reseed sweep)."""
    from fusion.book import claims as cl

    cf = cl.load(ROOT / "book" / "claims" / "cn107330468b.yaml")
    k = chc.checks_study(11)
    for rid, holds in (("chf-gaussian-ci", k.k1 < k.tolerances[0]), ("chf-gaussian-normaliser", k.k2 < k.tolerances[1]),
                       ("chf-gaussian-z-bound", k.k3 <= 1e-12)):  # one record per statement, each its own check
        ev = cl.evaluate(cf.record(rid), "primary", seed=11, runs=chc.STUDY_RUNS)
        assert isinstance(ev, Proposition) and ev.holds == holds
    is2000 = cl.evaluate(cf.record("chf-is-rebuild"), "primary", seed=11, runs=chc.STUDY_RUNS)
    assert "R = 2000" in is2000.summary()
