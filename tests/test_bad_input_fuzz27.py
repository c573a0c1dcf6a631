"""Fuzz 27b (issue 35): regressions of the hour's chapter-layer fixes, B1-B5 and the debatable D1, D3.

* B1: the design study's default ``n_initial`` follows the scenario (the larger of 10,000 and 5 × n_particles), so
  ``design`` / ``ev_filter_design`` accept a valid scenario of 10,000 particles; the design is built only for the
  readings that read it.
* B2 (and D1): a float32 period is the decimal it prints as, as an entry of a list or tuple too (pcrb_table,
  sensitivity_table) and as weight_pair's T.
* B3: a singular covariance of valid runs: per_run_nees and ev_tracking's NEES follow method_table's rule (undefined
  NEES), refused by name only where the window holds it.
* B4, B5: too few runs refused by the caller's argument ``runs`` before any study (ev_premise, ev_pso,
  ev_filter_design).
* D3: method_table's labels from the study (nodes of the naive row, the window's last frame).
"""

from __future__ import annotations

import dataclasses
import functools
from typing import Any

import numpy as np
import pytest

from fusion.book.chapters import chernoff as chc
from fusion.book.chapters.chernoff import evidence as chev
from fusion.book.chapters.chernoff.settings import ALL_FRAMES
from fusion.scenarios import range_bearing as dist
from fusion.scenarios.fusion_networks import premise_scenarios, redundancy_scenarios

#: The chapter-06 registry's small tracking scenario (tests/test_bad_input_calls_ch06.py), 5 frames.
SC5 = dist.RangeBearingScenario(frames=5, n_particles=60, n_samples=60, n_central=100, em_iterations=2,
                                n_components=2, readings=True, prev_optimiser="newton")


class _StudyRan(Exception):
    """Raised by the patched studies: the call got past its argument checks."""


@pytest.fixture
def no_study(monkeypatch: pytest.MonkeyPatch) -> None:
    """The chapter's studies replaced by a tripwire: a refusal must come before any of them runs."""
    def trip(*a: Any, **k: Any) -> Any:
        raise _StudyRan("a study ran before the arguments were checked")
    for name in ("tracking_study", "premise_study", "design"):
        monkeypatch.setattr(chev, name, trip)


# --------------------------------------------------------------------------- B1: n_initial follows the scenario
BIG = dist.RangeBearingScenario(frames=5, n_particles=10_000, n_samples=60, n_central=100, em_iterations=2,
                                n_components=2)


def test_design_of_a_scenario_of_10000_particles() -> None:
    d = chc.design(1, 1, BIG)
    assert d.n_initial == 50_000 > BIG.n_particles
    assert d.glue()["chf_design_more_cost"] == 50_000
    sc = dataclasses.replace(SC5, n_particles=2000)
    assert chc.design_study(sc, 1, 1, workers=1).n_initial == 10_000  # the chapter's 10,000 kept


@pytest.mark.parametrize("reading", ["study-plain", "runs"])
def test_ev_filter_design_builds_no_design_for_readings_without_it(reading: str,
                                                                    monkeypatch: pytest.MonkeyPatch) -> None:
    def trip(*a: Any, **k: Any) -> Any:
        raise _StudyRan("the design study was built for a reading that does not read it")
    monkeypatch.setattr(chev, "design", trip)
    assert chc.ev_filter_design({"reading": reading}, seed=1, runs=3, sc=SC5).runs == 3


# --------------------------------------------------------------------------- B2, D1: float32 periods in sequences
def test_pcrb_table_list_of_float32_periods() -> None:
    from fusion.book.chapters import ci
    from fusion.scenarios import two_sensor

    t = ci.pcrb_table([1.0, np.float32(0.02), np.float32(0.001)], 150.0, 10.0)
    assert 0.02 in t.index and 0.001 in t.index
    arr = ci.pcrb_table(np.array([1.0, 0.02, 0.001], dtype=np.float32), 150.0, 10.0)
    assert ci.pcrb_numbers(t, two_sensor.Q_READINGS[0]) == ci.pcrb_numbers(arr, two_sensor.Q_READINGS[0])
    assert list(ci.pcrb_table((np.float32(0.02),), 150.0, 10.0).index)[0] == 0.02


def test_sensitivity_table_tuple_of_float32_periods_reads_known() -> None:
    from fusion.book.chapters import ci

    _, known = ci.sensitivity_table((0.1, 0.5), 1, 2, duration=3.0, t_min=1.0)
    table, means = ci.sensitivity_table((np.float32(0.1), 0.5), 1, 2, duration=3.0, t_min=1.0,
                                        known={0.1: {k: v + 1.0 for k, v in known[0.1].items()}, 0.5: known[0.5]})
    assert list(table.index) == [0.1, 0.5]
    assert means[0.1] == {k: v + 1.0 for k, v in known[0.1].items()}  # taken from known, not simulated again


def test_weight_pair_float32_period_is_the_printed_one() -> None:
    from fusion.book.chapters import ci

    Q, R1, _ = ci.printed_covariances()
    kw = {"seed": 1, "search_seed": 2, "fruit_fly_seeds": [3], "runs": 2}
    a = ci.weight_pair(R1, R1 / 9, Q, 2, T=np.float32(0.3), **kw)
    b = ci.weight_pair(R1, R1 / 9, Q, 2, T=0.3, **kw)
    assert np.array_equal(a.sc.t, b.sc.t)


# --------------------------------------------------------------------------- B3: a singular covariance, one rule
@functools.cache
def _singular() -> tuple[Any, Any]:
    sc = dataclasses.replace(SC5, frames=6, n_particles=10)
    return sc, chc.tracking_study(1, 3, sc)


def test_per_run_nees_follows_method_tables_rule() -> None:
    from fusion.book.chapters.chernoff.settings import LATE
    from fusion.book.chapters.chernoff.tracking import _defined_nees

    sc, (p, g) = _singular()
    table = chc.method_table(g, chc.crb_position(sc, g), p)
    undefined = np.isnan(_defined_nees(g, "chernoff_prev"))   # the table's rule: singular to working precision
    assert undefined[:, ALL_FRAMES].any()   # 10 particles: singular somewhere
    # which late frames are singular is round-off (it differs between BLAS kernels): a window is defined, per run,
    # exactly when none of its run-frames is undefined, else refused naming the run and the frame
    for frames in (LATE, ALL_FRAMES):
        if not undefined[:, frames].any():
            assert np.isfinite(chc.per_run_nees(g, "chernoff_prev", frames)).all()
            continue
        with pytest.raises(ValueError, match=r"runs\[\d\].*'chernoff_prev'.*singular.*frame \d") as exc:
            chc.per_run_nees(g, "chernoff_prev", frames)
        assert "positive definite" not in str(exc.value)
    assert table.shape[0] > 0


def test_ev_tracking_nees_of_a_singular_covariance_named_by_the_setting() -> None:
    sc, _ = _singular()
    with pytest.raises(ValueError, match=r"settings\['a'\] = 'chernoff_prev'.*singular"):
        chc.ev_tracking({"a": "chernoff_prev", "b": "consistent", "metric": "nees", "window": "all",
                         "claim": "greater"}, seed=1, runs=3, sc=sc)


# --------------------------------------------------------------------------- B4, B5: too few runs, named `runs`
_SMALL = {k: dataclasses.replace(x, n_particles=40, n_samples=40, n_components=2, em_iterations=2, stages=1)
          for k, x in (premise_scenarios() | redundancy_scenarios()).items()}


@pytest.mark.parametrize("settings_", [
    {"network": "unequal", "a": "chernoff_pso", "b": "chernoff_uniform"},
    {"network": "unequal", "a": "oracle", "b": "naive_product"},
    {"network": "unequal", "a": "chernoff_pso", "b": "nominal", "test": "over"},
    {"network": "unequal", "a": "chernoff_pso", "b": "chernoff_uniform", "test": "losses"},
])
def test_ev_premise_few_runs_named_runs_before_the_study(settings_: dict[str, str], no_study: None) -> None:
    with pytest.raises(ValueError, match=r"^runs gives paired comparisons of 2 runs.*100") as exc:
        chc.ev_premise(settings_, seed=3, runs=2, scenarios=_SMALL)
    assert "a and b" not in str(exc.value) and "argument reason" not in str(exc.value)


@pytest.mark.parametrize(("fn", "settings_"), [
    (chc.ev_pso, {"check": "literal-mse"}), (chc.ev_pso, {"check": "gap-mse"}),
    (chc.ev_pso, {"check": "within-se-and-cost"}),
    (chc.ev_filter_design, {"reading": "guard"}), (chc.ev_filter_design, {"reading": "runs"}),
])
def test_one_run_refused_by_runs_before_the_study(fn: Any, settings_: dict[str, str], no_study: None) -> None:
    with pytest.raises(ValueError, match=r"^runs must be an integer >= 2"):
        fn(settings_, seed=1, runs=1, sc=SC5)


# --------------------------------------------------------------------------- D3: method_table's labels
def test_method_table_labels_follow_the_study() -> None:
    sc = dataclasses.replace(SC5, sensors=SC5.sensors[:2])
    p, g = chc.tracking_study(1, 2, sc)
    t = chc.method_table(g, chc.crb_position(sc, g), p)
    assert any(str(r).startswith("naive product") and "(1, 1)" in str(r) for r in t.index), list(t.index)
    assert not any("(1, 1, 1)" in str(r) for r in t.index)
    assert "mean NEES (4-D), frame 5" in t.columns and not any("5-30" in str(c) for c in t.columns)
    v = chc.table_values(t)  # read by the study's labels
    assert v["chf_nees_naive_product"] == t.loc["naive product, ε = (1, 1)", "mean NEES (4-D), frame 5"]
