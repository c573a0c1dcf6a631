"""Fuzz 22b (chapter layer), classes MM, A2, K2 (chapter 02 parts) and the debatables q1-q8: bad input refused by
name, valid input kept (issue 35)."""

from __future__ import annotations

import re

import numpy as np
import pytest

from fusion.book.chapters import lecture_correlated as lc
from fusion.book.chapters import ofs_fair
from fusion.book.ledger import MIN_RUNS, Comparison


# --------------------------------------------------------------------------- A2: rule R4 named by the caller's argument
def _names(e: pytest.ExceptionInfo, name: str) -> bool:
    msg = str(e.value)
    return msg.startswith(f"{name} ") and str(MIN_RUNS) in msg and "a and b" not in msg


def test_a2_fair_study_too_short_is_refused_naming_study() -> None:
    fs = ofs_fair.fair_study(1, 5, 20)
    for fn in (ofs_fair.verdicts, ofs_fair.fair_numbers):
        with pytest.raises(ValueError) as e:
            fn(fs)
        assert _names(e, "study"), str(e.value)
    ofs_fair.figure_fair(fs)  # the figure compares nothing pairwise: any run count


def test_a2_lecture_correlated_ledger_evidence_names_st() -> None:
    with pytest.raises(ValueError) as e:
        lc.ledger_evidence(lc.cached_studies(2500, 5))
    assert _names(e, "st"), str(e.value)


def test_a2_reading_functions_name_runs() -> None:
    from fusion.book.chapters import lecture_weighting as lwt
    import fusion.book.chapters.lecture_wavelets.records as lwr
    for fn, runs in ((lwt.ev_cc_accuracy, 5), (lwr.ev_wavelet_weighting, 16)):
        with pytest.raises(ValueError) as e:
            fn({"reading": "primary"}, runs=runs)
        assert _names(e, "runs"), str(e.value)


def test_a2_the_ledger_keeps_its_own_message_and_reason() -> None:
    """Comparison itself still names its a, b and reason (its caller has them), and a reason still admits."""
    a, b = np.arange(5.0), np.arange(5.0) + 1
    with pytest.raises(ValueError, match=re.escape("a and b hold 5 runs")):
        Comparison(a, b, "A", "B", "less", "m")
    assert Comparison(a, b, "A", "B", "less", "m", reason="a test").reason == "a test"


# --------------------------------------------------------------------------- K2-5, K2-6: chapter 02 studies by type
@pytest.mark.parametrize("fn, key", [("ev_awf_optimal", "s21"), ("ev_awf_unbiased", "s21"), ("ev_belief_perron", "s24"),
                                     ("ev_ls_unbiased", "s22"), ("ev_ls_tracks", "s22")])
@pytest.mark.parametrize("bad", [5, "s", object(), 2.5])
def test_k2_study_evidence_names_the_study_of_the_wrong_type(fn, key, bad) -> None:
    import fusion.book.chapters.lecture_weighting.study_evidence as se
    st = {k: bad for k in se.STUDIES}
    with pytest.raises(TypeError, match=re.escape(f"st[{key!r}]")):
        getattr(se, fn)(st)


@pytest.mark.parametrize("bad, exc", [("x", TypeError), ([1], TypeError), ({}, ValueError),
                                      ({(1, 900.0, True): "x"}, TypeError)])
def test_k2_glue_offset_names_results(bad, exc) -> None:
    import fusion.book.chapters.lecture_weighting.readings_benchmark as rb
    with pytest.raises(exc, match="results"):
        rb.glue_offset(bad)


# --------------------------------------------------------------------------- MM: pairs compared by what identifies them
@pytest.fixture(scope="module")
def two_sensor_pair():
    from fusion.book.chapters import ci
    from fusion.scenarios import two_sensor
    sc = two_sensor.two_sensor_scenario(np.eye(2), 4 * np.eye(2), np.eye(4), np.random.default_rng(3), runs=4)
    w = np.full(sc.t.size, 0.5)
    return ci, sc, two_sensor.fusion_study(sc, w, w)


def test_mm_a_study_of_another_scenario_is_refused(two_sensor_pair) -> None:
    from fusion.scenarios import two_sensor
    ci, sc, study = two_sensor_pair
    other = two_sensor.two_sensor_scenario(np.eye(2), 4 * np.eye(2), np.eye(4), np.random.default_rng(4), runs=4)  # another seed only
    for call in (lambda s: ci.slip_at_weights(s, study), lambda s: ci.baseline_slip_numbers(s, study),
                 lambda s: ci.rmse_table(study, s), lambda s: ci.slip_table(study, s)):
        with pytest.raises(ValueError, match=r"study must be fusion_study of sc"):
            call(other)
        call(sc)  # its own scenario: accepted


def test_mm_plugin_exact_of_another_study_is_refused() -> None:
    from fusion.book.chapters.lecture_correlated import ridge
    from fusion.scenarios import ridge_sensors as rs
    p = rs.plugin_study(xs=(0.0, 0.5, 1.0), m=5, sigma=1.0, runs=50, seed=3)
    ridge.table_plugin(p, ridge.plugin_exact(p))
    for other in (rs.plugin_study(xs=(0.0, 0.5), m=5, sigma=1.0, runs=50, seed=3),      # other xs
                  rs.plugin_study(xs=(0.0, 0.5, 1.0), m=3, sigma=2.0, runs=50, seed=3),  # other σ/√m
                  rs.plugin_study(xs=(0.0, 0.5, 1.0), m=20, sigma=2.0, runs=50, seed=3)):  # same σ/√m, other m
        with pytest.raises(ValueError, match="x25 must be plugin_exact"):
            ridge.table_plugin(p, ridge.plugin_exact(other))


def test_mm_ir_reading_numbers_checks_sim_and_rmse() -> None:
    from fusion.book.chapters import ci
    import fusion.scenarios.infrared_radar as ir
    readings = ci.ir_readings(0.1, 1, 2)
    sim, rmse = ci.ir_study(0.1, 1, 2)
    assert ci.ir_reading_numbers(readings, sim, rmse) == ci.ir_reading_numbers(
        readings, readings.sims["x"], ir.rmse_by_rule(readings.sims["x"]))
    for other in (ci.ir_study(0.2, 1, 2), ci.ir_study(0.1, 2, 2), ci.ir_study(0.1, 1, 3)):
        with pytest.raises(ValueError, match=r"^sim must be"):
            ci.ir_reading_numbers(readings, other[0], other[1])
        with pytest.raises(ValueError, match=r"^rmse\["):
            ci.ir_reading_numbers(readings, sim, other[1])


# --------------------------------------------------------------------------- debatables q1-q8 (decided)
def test_q1_correction_value_follows_its_consumers_rule() -> None:
    """Decided: fixed. Correction.value is checked by the rule describe/explain apply (scalar), so no Correction
    is built that they refuse; numpy scalars stay accepted."""
    import dataclasses
    from fusion.book.chapters import ofs_audit as oa
    c = oa.Correction(1, 5, 889.9, "one-digit slip")
    with pytest.raises(TypeError, match=r"Correction\.value"):
        dataclasses.replace(c, value=True)
    with pytest.raises(ValueError, match=r"Correction\.value"):
        dataclasses.replace(c, value=1e308)
    for ok in (np.float32(889.5), np.int64(900), 889):
        assert oa.describe(dataclasses.replace(c, value=ok)).startswith("obs. 5, sensor 1")


def test_q2_a_methods_subset_is_for_reading_mae_and_its_consumers_refuse_it_by_name() -> None:
    """Decided: documented. fair_study runs a subset of the methods (its errors readable); the three consumers,
    which read every method, refuse it naming study."""
    fs = ofs_fair.fair_study(1, 100, 20, sizes=(0,), counts=(1,), spreads=(1,), opposite=(),
                             methods=("mean", "median"))
    assert all(set(e) == {"mean", "median"} for e in fs.mae.values())
    for fn in (ofs_fair.verdicts, ofs_fair.fair_numbers, ofs_fair.figure_fair):
        with pytest.raises(ValueError, match="study"):
            fn(fs)


@pytest.mark.parametrize("settings", ["x", 5, {"reading": 5}, {"reading": None}])
def test_q3_claim_file_settings_of_the_wrong_type_are_type_errors(settings) -> None:
    """Decided again by fuzz 52 C7 (one rule for every chapter's readers, ``fusion.book._reader_settings``): a
    reader is called with Python objects (the claim file's own content is checked when it is loaded), so settings
    or a reading key of the wrong type are a TypeError naming settings, as chapter 05's were."""
    from fusion.book.chapters import lecture_weighting as lwt
    with pytest.raises(TypeError, match="settings"):
        lwt.ev_cc_accuracy(settings)


@pytest.mark.parametrize("key, exc", [(float("nan"), ValueError), ("1.0", TypeError), (-1.0, ValueError),
                                      (float("inf"), ValueError)])
def test_q6_latency_values_checks_the_noise_levels(key, exc) -> None:
    """Decided: fixed. The keys of be (noise levels) are checked as its values are."""
    from fusion.book.chapters import time_registration_ledger as tl
    with pytest.raises(exc, match="noise level .* of be"):
        tl.latency_values({key: 0.01, 3.0: 0.02}, 3.0)
    assert tl.latency_values({np.float64(1.0): 0.01, 3.0: 0.02}, 3.0)["reg_be_lo_ms"] == pytest.approx(10.0)


def test_q7_fruit_fly_step_study_uses_the_target_it_checked() -> None:
    """Decided: fixed. A float subclass whose __float__ differs is computed with the float that was checked."""
    from fusion.book.chapters import ci

    class Lying(float):
        def __float__(self) -> float:
            return 0.3

    assert ci.fruit_fly_step_study(2, Lying(0.8)).equals(ci.fruit_fly_step_study(2, 0.3))


@pytest.fixture(scope="module")
def tiny_tracking():
    from fusion.book.chapters import chernoff as chc
    from fusion.scenarios import range_bearing as dist
    sc = dist.RangeBearingScenario(frames=6, n_particles=300, n_samples=300, n_central=600, em_iterations=5)
    runs = dist.monte_carlo(sc, 5, 3)
    return chc, sc, runs, chc.crb_position(sc, runs)


def test_q5_top_share_is_the_share_of_the_signed_sum(tiny_tracking) -> None:
    """Decided: documented. chf_top_share is 100 * the largest paired difference / their signed sum, so it can
    leave [0, 100] when the differences have mixed signs (few runs)."""
    from fusion.book.chapters.chernoff.tracking import per_run_mse
    chc, sc, runs, crb = tiny_tracking
    d = per_run_mse(runs, "chernoff_pso") - per_run_mse(runs, "chernoff_uniform")
    v = chc.review_values(runs, crb, sc, 1)
    assert v["chf_top_run"] == int(np.argmax(d)) + 1
    assert v["chf_top_share"] == pytest.approx(round(100 * d.max() / d.sum()), abs=0.5)


def test_q8_guarded_runs_refuses_another_root_seed(tiny_tracking) -> None:
    """Decided: fixed (issue 35, swaps). Each run records its stream through its truth, so another root seed is
    refused naming ``seed``; with the runs' own seed the runs that are not redone are the given ones."""
    chc, sc, runs, _ = tiny_tracking
    bad = chc.any_collapsed(runs, sc)
    out = chc.guarded_runs(runs, sc, 5)
    assert all(o is r for o, r, b in zip(out, runs, bad) if not b)
    with pytest.raises(ValueError, match="seed = 6"):
        chc.guarded_runs(runs, sc, 6)


@pytest.mark.parametrize("name", ["ev_fig2_fluctuation", "ev_membership_free", "ev_weights_stability",
                                  "ev_fig4_robust"])
def test_a2_chapter01_readers_name_runs(name) -> None:
    from fusion.book.chapters import ofs as ch
    with pytest.raises(ValueError) as e:
        getattr(ch, name)({}, seed=4, runs=5)
    assert _names(e, "runs"), str(e.value)


@pytest.mark.parametrize("module, name, seed", [("ci", "ev_fig7_improved_vs_ci", 2024),
                                                ("ci", "ev_fig10_x_below_y", 2024),
                                                ("lecture_correlated", "ev_correlation_matters", 7),
                                                ("time_registration_ledger", "ev_improved", 7),
                                                ("time_registration_ledger", "ev_ls_info", 7)])
def test_a2_chapter04_05_07_readers_name_runs(module, name, seed) -> None:
    """Too few runs (3 < MIN_RUNS). Chapter 05's readers at the chapter's seed refuse the run count before any
    study (measured: no study of (2024, 3 runs) is called)."""
    import importlib
    fn = getattr(importlib.import_module(f"fusion.book.chapters.{module}"), name)
    with pytest.raises(ValueError) as e:
        fn({}, seed=seed, runs=3)
    assert _names(e, "runs"), str(e.value)
