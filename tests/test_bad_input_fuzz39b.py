"""Fuzz 39b (chapter layer): a reader given a valid producer output at other documented settings refuses it by name,
never a raw KeyError (C4, C6-C8); one-run studies refused by name (C5); the default T named when it misfits (C3);
benchmark_cost's printed ratios (C2, D1); a stale stability sweep (C1)."""

from __future__ import annotations

import warnings
from functools import cache

import numpy as np
import pytest


@cache
def _scenario(runs: int):
    from fusion.book.chapters import ci
    from fusion.scenarios import two_sensor

    Q, R1, R2 = ci.printed_covariances()
    return two_sensor.two_sensor_scenario(R1, R2, Q, np.random.default_rng(5), runs=runs, T=1.0)


@cache
def _study(runs: int, given: tuple[str, ...]):
    from fusion.scenarios import two_sensor

    sc = _scenario(runs)
    w = np.full(sc.t.size, 0.5)
    return two_sensor.fusion_study(sc, *[w for g in given if g == "w"], published_omega=0.5 if "p" in given else None)


@pytest.mark.parametrize("given", [(), ("w",), ("w", "p"), ("w", "w")])
@pytest.mark.parametrize("reader", ["rmse_figure", "rmse_table", "slip_table", "rmse_numbers"])
def test_ch05_readers_refuse_a_study_without_its_optional_rules(reader, given):
    """C4: fusion_study without the weights or the published ω is valid; the readers of every curve refuse it when
    they read the rule left out (the published ω: rmse_numbers only; the figures and tables draw the weights)."""
    from fusion.book.chapters import ci

    study = _study(2, given)
    n = study.t.size
    calls = {"rmse_figure": lambda: ci.rmse_figure(study, np.ones(n, bool), np.ones(n)),
             "rmse_table": lambda: ci.rmse_table(study), "slip_table": lambda: ci.slip_table(study),
             "rmse_numbers": lambda: ci.rmse_numbers(study, np.ones(3), np.ones(3, bool), {"x": 1.0})}
    if given == ("w", "w") and reader != "rmse_numbers":   # both weights given: accepted (the published ω is
        out = calls[reader]()                                # rmse_numbers' only)
        assert out is not None and (not hasattr(out, "__len__") or len(out) > 0)
        if reader == "rmse_figure":
            import matplotlib.pyplot as plt
            plt.close(out)
        return
    with pytest.raises(ValueError, match="^study lacks the rules"):
        calls[reader]()


@pytest.mark.parametrize("reader", ["rmse_table", "rmse_numbers"])
def test_ch05_standard_error_readers_refuse_one_run(reader):
    """C5: a one-run study has no Monte-Carlo standard error: refused naming study, with no numpy warning."""
    from fusion.book.chapters import ci

    study = _study(1, ("w", "w", "p"))
    leg = ci.straight_leg(study, 1.0, 150.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(ValueError, match="^study holds 1 run"):
            if reader == "rmse_table":
                ci.rmse_table(study)
            else:
                ci.rmse_numbers(study, leg.floor, leg.steady, leg.rmse, leg.causal)


def test_identical_study_check_refuses_an_architecture_study_at_other_weights():
    """C6: architecture_study at other printed/placement weights is valid; the identical-sensor study check that
    paired_numbers and architecture_numbers run refuses it naming the argument (a raw KeyError in paired_numbers
    before), and accepts the published weight's study."""
    from fusion.book.chapters.ci.checks import _identical_study
    from fusion.book.chapters.ci.constants import W_PUB
    from fusion.scenarios import two_sensor

    def study(w):
        return two_sensor.architecture_study(np.random.default_rng(1), np.eye(2) * 2500.0, np.eye(2) * 900.0,
                                             np.eye(4), runs=2, nees_runs=2, T=5.0, printed_omegas=np.array([w]),
                                             placement_omegas=np.array([w]))

    with pytest.raises(ValueError, match="^ai lacks the fed-back runs"):
        _identical_study(study(0.5), "ai")
    _identical_study(study(W_PUB), "ai")


def test_correlated_readers_label_another_case_key_as_given():
    """C7: the producers accept any case key; the readers label a key without a registered label by the key."""
    import matplotlib.pyplot as plt

    from fusion.book.chapters.lecture_correlated import correlated as co
    from fusion.scenarios import correlated_sensors as cs

    sc = {"c": {"own": (1.0, 2.0), "coupling": (1.0, 2.0), "env": 1.0}}
    s = cs.coupling_study(sc, runs=5, x=1.0, seed=1, env_grid=(0.0, 1.0), env_far=50.0)
    assert list(co.table_coupling(s).index) == ["c"]
    fig = co.figure_coupling(s)
    assert "c" in [t.get_text() for t in fig.legends[0].get_texts()] + [
        t.get_text() for ax in fig.axes if ax.get_legend() for t in ax.get_legend().get_texts()]
    plt.close(fig)
    e = cs.estimated_covariance_study(sc, ns=(5, 8), reps=3, seed=1, misstate=0.1)
    assert list(co.table_estimated(e).index) == ["c"]


@pytest.mark.parametrize("readings", [("batch", "window"), ("window",), ("equal", "window")])
def test_glue_weighting_refuses_a_study_without_batch_or_equal(readings):
    """C8: variance_study at other readings is valid; glue_weighting reads batch and equal and refuses naming v."""
    from fusion.book.chapters.lecture_wavelets import variance as va
    from fusion.scenarios import wavelet_sensors as ws

    v = ws.variance_study(length=128, runs=3, gains=(1.0, 1.5, 0.8), sigma=(0.05, 0.1, 0.2), seed=1, window=8,
                          readings=readings, mode="hard", normaliser="max")
    with pytest.raises(ValueError, match="^v lacks the readings"):
        va.glue_weighting(v)


@pytest.mark.parametrize("reader", ["nees_start_table", "nees_start_numbers"])
def test_nees_start_readers_name_the_default_T_before_a_valid_t_steady(reader):
    """C3: runs at T = 8 s with T left at its default and a valid t_steady: the refusal names the default T (by
    true_start), not the caller's t_steady."""
    from fusion.book.chapters import ci

    Q, R1, R2 = ci.printed_covariances()
    x0 = np.array([0.0, 0.0, 10.0, 5.0])
    st = {s: ci.nees_per_step(np.random.default_rng(1), Q, R1, R2, x0, 12, 2, T=8.0, random_velocity=s)
          for s in (False, True)}
    with pytest.raises(ValueError, match="^true_start does not fit .*default T = 1"):
        getattr(ci, reader)(st[False], st[True], 2, *([{}] if reader == "nees_start_numbers" else []), t_steady=40.0)
    ci.nees_start_table(st[False], st[True], 2, T=8.0, t_steady=40.0)   # T given: accepted


def test_benchmark_cost_never_prints_a_positive_value_as_zero(tmp_path):
    """C2: an optimiser stage of 4e-5 s against SLSQP's 1.4 ms, and a loop of 0.3 s, print with significant digits."""
    import copy
    import json
    from pathlib import Path

    import fusion
    from fusion.book.chapters.chernoff import swarm

    src = json.loads((Path(fusion.__file__).resolve().parents[1] / "benchmarks/results/chernoff.json").read_text())
    if src.get("schema") != swarm.BENCH_SCHEMA:
        pytest.skip("the stored benchmark predates the current schema")
    d = copy.deepcopy(src)
    for m in d["measurements"]:
        if m.get("stage") == swarm.BenchStage.OPTIMISER:
            m["value"] = 4e-5
        if m.get("key") == "loop_seconds":
            m["value"] = 0.3
    p = tmp_path / "b.json"
    p.write_text(json.dumps(d))
    values = swarm.benchmark_cost(p)[1]
    part = values["chf_pso_ratio_text"].split("stage costs ")[1]
    assert not part.startswith("0.0 ") and "(0.04 against" in part
    assert "take 0.3 s by the per-run loop" in values["chf_bench_text"]


@pytest.mark.parametrize("ratio, words", [(2.5, "3 times slower"), (3.5, "4 times slower"), (0.4, "3 times faster"),
                                          (1.995, "2 times slower"), (1.5, "1.50 times slower")])
def test_slower_rounds_halves_away_from_zero(ratio, words):
    """D1: "N times" rounds halves up (2.5 read "2 times" before), and a ratio rounding to 2.00 reads "2 times"."""
    from fusion.book.chapters.chernoff.swarm import _slower

    assert _slower(ratio) == words


@pytest.mark.parametrize("swept, now", [("reproduced", "contradicted"), ("contradicted", "reproduced")])
def test_reseeding_glue_counts_a_stale_sweep_against_the_ledger_status(tmp_path, swept, now):
    """C1: a sweep made when the ledger said ``swept``, read for a record that now says ``now``: every reseed gave
    another status, so the status moves (it read "stable in 5 of 5 reseeds" before); the same status stays stable."""
    import json

    from fusion.book import stability as S
    from fusion.book.chapters.lecture_weighting import records as RS

    rid, seeds = "lec-awf-estimated", [11, 12, 13, 14, 15]
    res = [S.TaskResult(S.Task("lec", rid, "primary", "primary", s, 300), swept, 1.0) for s in seeds]
    res.append(S.TaskResult(S.Task("lec", rid, "primary", "primary", 11, 3000, scaled=True), swept, 1.0))
    recs = S.summarise(res, seeds, {rid: swept})
    for v in recs.values():
        v.update(commit="abc", runs_factor=10)
    (tmp_path / "book/ledger").mkdir(parents=True)
    (tmp_path / "_toc.yml").write_text("format: jb-book\n")
    (tmp_path / "book/ledger/stability.json").write_text(json.dumps(
        {"root_seed": 1, "K": 5, "runs_factor": 10, "readings": {}, "records": recs}) + "\n")
    line = RS.reseeding_glue([{"id": rid, "status": now, "runs": 300}], tmp_path)["lec_rs_awf_estimated"]
    assert "a status that moves under reseeding" in line and f"{swept} in 5 of 5 reseeds" in line
    line = RS.reseeding_glue([{"id": rid, "status": swept, "runs": 300}], tmp_path)["lec_rs_awf_estimated"]
    assert "stable in 5 of 5 reseeds and at 10× the runs" in line
