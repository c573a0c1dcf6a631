"""Fuzz 19's cases of chapter 05 (``fusion.book.chapters.ci``), by class.

Each refusal is a ValueError or TypeError naming the argument (issue 35); valid input keeps working. The classes:

* a table or a mapping made by another function of the package, read without a check (class D): one shared rule
  (``fusion/book/chapters/ci/checks.py``: the mapping holds the entries read, the table the columns read, the
  results are of their class), applied to every glue and table function of the chapter that reads one;
* paired arguments that must agree (class E, F8, F9): the architecture studies, their table and run count; the
  two starts of the per-step NEES; the steps of ``steady`` and of the estimates;
* a start of the time average outside the track (F4) and the valid ``t_min = 0`` (F3, a regression: the bound,
  undefined at the first scan, is averaged over the other scans);
* the debatable empties and duplicates of the period tables, a negative ``t_min``, and ``delta0`` far beyond
  ``sigma`` (a singular system named by the public arguments).
"""

from __future__ import annotations

import re

import matplotlib

matplotlib.use("Agg")
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
import pytest  # noqa: E402

from fusion.book.chapters import ci  # noqa: E402
from fusion.scenarios import two_sensor  # noqa: E402
from fusion.scenarios.two_sensor import NeesRule  # noqa: E402


def _refused(exc: type[Exception], name: str, fn, *args, **kwargs) -> None:
    """``fn(*args, **kwargs)`` raises ``exc`` whose message names ``name`` (as a word)."""
    with pytest.raises(exc) as info:
        fn(*args, **kwargs)
    assert re.search(rf"(?<![A-Za-z0-9_]){re.escape(name)}(?![A-Za-z0-9_])", str(info.value)), str(info.value)


@pytest.fixture(scope="module")
def arch():
    """The chapter's architecture studies and their table, at the notebook's seed and runs (:data:`LEDGER_RUNS`).

    The companion checks need any valid studies, not a given run count (they pass the studies' own count and one
    that differs): the chapter's, which its notebook and ``tests/test_ci_book_chapter.py`` compute in every run
    anyway, come from the run's study cache; at 3 runs they were a computation of their own (about 7 CPU-s: the
    per-step covariance recursion does not shrink with the runs)."""
    studies = ci.arch_study()
    return studies, ci.architecture_table(studies)


@pytest.fixture(scope="module")
def nees_est():
    """``nees_study``'s estimates (5 runs) on the chapter's case."""
    Q, R1, R2 = ci.printed_covariances()
    sc = ci.source_scenario(2024)
    return two_sensor.nees_study(np.random.default_rng(1), Q, R1, R2, sc.truth[0], sc.t.size, 5, T=1.0).est


@pytest.fixture(scope="module")
def nees_steps():
    """Per-step NEES from both starts (5 runs) and split CI's exactness, as the notebook's appendix builds them."""
    Q, R1, R2 = ci.printed_covariances()
    sc = ci.source_scenario(2024)
    st = {s: ci.nees_per_step(np.random.default_rng(1), Q, R1, R2, sc.truth[0], sc.t.size, 5, T=1.0,
                              random_velocity=s) for s in (False, True)}
    return st, ci.split_ci_exactness(Q, R1, 1.0, sc.t.size)


# --------------------------------------------------------------------------- class D: tables and mappings read
@pytest.mark.parametrize("fn, arg, bad, exc", [
    (ci.timing_table, "m", {"a": 1.0}, ValueError),                                    # D2
    (ci.timing_table, "m", 5, TypeError),
    (lambda v: ci.nees_numbers(v, 3), "nees", {"a": 1.0}, ValueError),                 # D4
    (ci.fruit_fly_step_values, "table", pd.DataFrame({"zz": [1.0, 2.0]}), ValueError),  # D9
    (ci.fruit_fly_step_values, "table", pd.DataFrame(), ValueError),
    (ci.fruit_fly_step_values, "table", 5, TypeError),
    (ci.sensitivity_numbers, "sens_table", pd.DataFrame(), ValueError),                # D10
    (ci.fig5_hypothesis_numbers, "table", 5, TypeError),                               # D11
    (ci.variant_numbers, "variants", {}, ValueError),                                  # D15
    (ci.variant_numbers, "variants", {two_sensor.study.RUN_AVERAGED: (1.0, "y"),
                                      two_sensor.study.OVER_STEPS: (1.0, 2.0)}, TypeError),
    (ci.printed_equation_numbers, "checks", {}, ValueError),                           # D16
    (ci.printed_equation_numbers, "checks", {"eq2_error": 1e-16, "eq6_asym": np.nan, "eq6_relerr": 0.1}, ValueError),
    (ci.architecture_table, "studies", {"x": 1.0}, TypeError),                        # D17
    (ci.architecture_figure, "studies", {"x": 1.0}, TypeError),
    (ci.architecture_table, "studies", {}, ValueError),                                # F15
    (ci.architecture_figure, "studies", {}, ValueError),                               # F14
    (ci.fruit_fly_table, "res", {}, ValueError),                                       # D18
    (ci.fruit_fly_table, "res", {"x": 1.0}, TypeError),
    (lambda v: ci.variants_table(v, {}), "variants", 5, TypeError),                    # the same shape
    (lambda v: ci.variants_table({"a": (1.0, 2.0)}, v), "variants_all", {"b": (1.0, 2.0)}, ValueError),
    (lambda v: ci.pcrb_numbers(v, "x"), "pcrb", pd.DataFrame(), ValueError),
    (lambda v: ci.ir_table(v, [0.0, 1.0, 2.0, 3.0]), "rmse", {}, ValueError),
    (lambda v: ci.ir_table(v, [0.0, 1.0, 2.0, 3.0]), "rmse", {"a": np.ones((4, 4))}, ValueError),
    (lambda v: ci.ir_figure([0.0, 1.0], v), "rmse", {}, ValueError),
    (lambda v: ci.ir_flown_numbers(2024, 3, v), "chapter_means", {}, ValueError),
])
def test_table_or_mapping_of_another_function_refused_by_name(fn, arg, bad, exc):
    _refused(exc, arg, fn, bad)


def test_study_seed_key_refused_by_name():
    """D1: an unknown study (or another type) is refused, the offsets' keys still work."""
    _refused(ValueError, "study", ci.study_seed, 2024, "nope")
    _refused(ValueError, "study", ci.study_seed, 2024, "")
    _refused(TypeError, "study", ci.study_seed, 2024, 5)
    key = next(iter(ci.SEED_OFFSETS))
    assert ci.study_seed(2024, key) == 2024 + ci.SEED_OFFSETS[key]


def test_evidence_settings_of_another_type_refused():
    """F13: every stochastic record's evidence function names ``settings`` before any study is run."""
    _refused(TypeError, "settings", ci.ev_fig4_convex_part, 5)
    _refused(TypeError, "settings", ci.ev_fig10_x_below_y, ["reading"])


# --------------------------------------------------------------------------- E/F: companions that must agree
def test_architecture_numbers_companions_must_agree(arch):
    """E4-E6, F7, F8: the run count, the table, the steps averaged and the two studies of the architecture glue."""
    studies, table = arch
    runs = ci.LEDGER_RUNS
    assert ci.architecture_numbers(studies, table, runs, 241)["ci_arch_runs"] == runs   # the notebook's call
    _refused(ValueError, "arch_runs", ci.architecture_numbers, studies, table, 500, 50)
    # a table of other studies, same shape and labels (the two pairs' studies swapped: no third study computed)
    other = ci.architecture_table({ci.IDENTICAL_LABEL: studies[ci.ANISO_LABEL],
                                   ci.ANISO_LABEL: studies[ci.IDENTICAL_LABEL]})
    _refused(ValueError, "arch_table", ci.architecture_numbers, studies, other, runs, 50)
    _refused(TypeError, "arch_table", ci.architecture_numbers, studies, {}, runs, 50)
    _refused(ValueError, "k_steady", ci.architecture_numbers, studies, table, runs, 10**6)
    _refused(ValueError, "k_steady", ci.architecture_numbers, studies, table, runs, 0)
    _refused(ValueError, "arch", ci.architecture_numbers, dict(list(studies.items())[:1]), table, runs, 50)
    _refused(ValueError, "arch", ci.architecture_numbers, dict(reversed(list(studies.items()))), table, runs, 50)


def test_model_rmse_steady_must_select_steps_of_the_estimates(nees_est):
    """D5, E7: ``steady`` holds one bool per step and selects one at least (else the mean of nothing is NaN)."""
    K = nees_est["truth"].shape[1]
    out = ci.model_rmse(nees_est, np.arange(K) >= 20)
    assert np.isfinite([out["x"], out["y"]]).all()
    _refused(ValueError, "steady", ci.model_rmse, nees_est, np.ones(5, bool))
    _refused(ValueError, "steady", ci.model_rmse, nees_est, np.zeros(K, bool))
    _refused(TypeError, "steady", ci.model_rmse, nees_est, np.ones(K))
    _refused(ValueError, "nees_est", ci.model_rmse, {NeesRule.SPLIT: nees_est[NeesRule.SPLIT]}, np.ones(K, bool))


def test_nees_start_numbers_starts_must_cover_the_same_steps(nees_steps):
    """F9: the two starts of the per-step NEES cover the same steps and rules, and ``t_steady`` splits them."""
    st, exact = nees_steps
    assert ci.nees_start_numbers(st[False], st[True], 5, exact, 1.0)["ci_nps_runs"] == 5
    short = {k: v[:5] for k, v in st[False].items()}
    with pytest.raises(ValueError, match="true_start and random_start"):
        ci.nees_start_numbers(short, st[True], 5, exact, 1.0)
    _refused(ValueError, "true_start", ci.nees_start_table, short, {k: v[:5] for k, v in st[True].items()}, 5)
    fewer = {k: v for k, v in st[True].items() if k != NeesRule.PRINTED}
    _refused(ValueError, "random_start", ci.nees_start_numbers, st[False], fewer, 5, exact, 1.0)
    _refused(ValueError, "t_steady", ci.nees_start_table, st[False], st[True], 5, 1.0, 1e4)
    _refused(ValueError, "exact", ci.nees_start_numbers, st[False], st[True], 5, {}, 1.0)


# --------------------------------------------------------------------------- the infrared + radar readings
def test_ir_readings_t_min_zero_is_valid_and_skips_the_undefined_first_scan():
    """F3 (a regression): ``t_min = 0`` averages the RMSE over every scan and the bound over all but the first,
    where it is undefined; the other scans' bound is the same as with a start just after 0."""
    at0 = ci.ir_readings(0.1, 1, 3, duration=3.0, t_min=0.0)
    after = ci.ir_readings(0.1, 1, 3, duration=3.0, t_min=0.05)
    for axis in at0.bound:
        for s in ("both", "radar"):
            assert np.isfinite(at0.bound[axis][s]).all()
            np.testing.assert_array_equal(at0.bound[axis][s], after.bound[axis][s])
    assert at0.t_min == 0.0


@pytest.mark.parametrize("kwargs, exc, name", [
    ({"t_min": 5.0}, ValueError, "t_min"),                 # F4: after the end of the track
    ({"t_min": -1.0}, ValueError, "t_min"),
    ({"scaled_axes": ("nope",)}, ValueError, "scaled_axes"),   # E2
    ({"scaled_axes": "xy"}, TypeError, "scaled_axes"),         # E3: a str for a tuple of str
    ({"scaled_axes": (1,)}, TypeError, "scaled_axes"),
])
def test_ir_readings_bad_start_or_axes_refused_by_name(kwargs, exc, name):
    _refused(exc, name, ci.ir_readings, 0.1, 1, 3, duration=3.0, **kwargs)


# --------------------------------------------------------------------------- debatable: the period tables
@pytest.mark.parametrize("periods", [(), [1.0, 1.0], [-1.0], [0.0]])
def test_period_tables_refuse_empty_repeated_or_nonpositive_periods(periods):
    _refused(ValueError, "periods", ci.pcrb_table, periods, 1.0, 0.05)
    _refused(ValueError, "periods", ci.sensitivity_table, periods, 1, 2, duration=3.0)


def test_sensitivity_table_t_min_must_lie_on_the_track():
    _refused(ValueError, "t_min", ci.sensitivity_table, (0.1,), 1, 2, duration=3.0, t_min=-1.0)
    _refused(ValueError, "t_min", ci.sensitivity_table, (0.1,), 1, 2, duration=3.0, t_min=4.0)


def test_pcrb_table_singular_system_names_the_arguments():
    """A ``delta0`` far beyond ``sigma`` gives a singular steady-state system: named by the public arguments."""
    _refused(ValueError, "delta0", ci.pcrb_table, [1.0], 1.0, 1e12)
    assert np.isfinite(ci.pcrb_table([1.0, 0.1], 150.0, 0.05).to_numpy()).all()


def test_paired_numbers_run_count_and_methods_must_match_the_studies(arch):
    """The run count given beside the paired studies (the class of E4) and the methods their glue reads."""
    ps = ci.paired_study()   # the chapter's (the run's study cache: the notebook computes it), as arch's studies
    ai = arch[0][ci.IDENTICAL_LABEL]
    kw = dict(paired=ps.paired, paired_u=ps.paired_u, paired_random=ps.paired_random, ai=ai, ml_gap=0.1,
              rmse_avg=50.0, paired_runs=ps.runs, paired_a=ps.paired_an, omega_u=ps.omega_u)
    assert ci.paired_numbers(**kw)["ci_paired_runs"] == ps.runs == ci.LEDGER_RUNS
    _refused(ValueError, "paired_runs", ci.paired_numbers, **{**kw, "paired_runs": ps.runs + 1})
    _refused(ValueError, "paired", ci.paired_numbers, **{**kw, "paired": {}})
    _refused(TypeError, "paired_u", ci.paired_numbers, **{**kw, "paired_u": 5})
    _refused(ValueError, "paired_random", ci.paired_numbers, **{**kw, "paired_random": ps.paired_random[:2]})
