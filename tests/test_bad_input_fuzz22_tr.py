"""Fuzz 22b's cases of chapter 06's helpers over runs and sizes (issue 35), by class.

* TR: every helper over a list of :class:`TrackingRun` applies one check (``_check_runs`` of
  ``fusion.scenarios.range_bearing``, through the chapter's ``_check_study``): a non-empty sequence of TrackingRun
  of one scenario, the scenario argument the runs' own (recorded in ``TrackingRun.scenario``, compared but for the
  collapse guard's fields; for a run built by hand, its frames and nodes), the readings where a helper reads them,
  ``n_particles``/``n_central`` the runs' own, ``crb_pos`` one finite non-negative entry per frame; refusals name
  the argument. Valid input (the notebook's calls: guarded runs against the unguarded scenario) keeps working.
* K2 (chapter 06): ``scenario_table``, ``objective_figure``, ``contour_figure`` and ``ledger_values`` type their
  arguments; ``contour_figure`` names ``n_particles``.
* SW: chapter 06's sizes are checked against the memory and input budgets at the entry, by the caller's names.
"""

from __future__ import annotations

import dataclasses
import re

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings, strategies as st

from fusion.book.chapters import chernoff as chc
from fusion.book.chapters import chernoff_scaling as csc
from fusion.book.chapters import chernoff_steps as cs
from fusion.scenarios import range_bearing as dist

TINY = dist.RangeBearingScenario(frames=6, n_particles=300, n_samples=300, n_central=600, em_iterations=5)
READ = dataclasses.replace(TINY, readings=True, frames=5)


@pytest.fixture(scope="module")
def runs():
    return dist.monte_carlo(TINY, 5, 3)


@pytest.fixture(scope="module")
def runs_r():
    return dist.monte_carlo(READ, 7, 2)


def _refused(exc: type[Exception], name: str, f, *args, **kwargs) -> str:
    """Call ``f``; it must raise ``exc`` with ``name`` in the message (returned)."""
    with pytest.raises(exc, match=re.escape(name)) as info:
        f(*args, **kwargs)
    return str(info.value)


# Every helper of the class, as a function of (runs, sc, crb); the argument checked is "runs".
HELPERS = {
    "crb_position": lambda r, sc, crb: chc.crb_position(sc, r),
    "method_table": lambda r, sc, crb: chc.method_table(r, crb),
    "rmse_figure": lambda r, sc, crb: chc.rmse_figure(r, crb),
    "gain_values": lambda r, sc, crb: chc.gain_values(r),
    "any_collapsed": lambda r, sc, crb: chc.any_collapsed(r, sc),
    "typical_run": lambda r, sc, crb: chc.typical_run(r, sc.n_particles, sc.n_central),
    "collapse_values": lambda r, sc, crb: chc.collapse_values(r, sc),
    "readings_values": lambda r, sc, crb: chc.readings_values(r),
    "equal_kl_g_values": lambda r, sc, crb: chc.equal_kl_g_values(r),
    "gm_yardstick": lambda r, sc, crb: chc.gm_yardstick(np.random.default_rng(4), r, sc, sets=5),
    "consistency_figure": lambda r, sc, crb: chc.consistency_figure(r, r, sc),
    "double_count_values": lambda r, sc, crb: chc.double_count_values(r, sc),
    "diagnostics": lambda r, sc, crb: chc.diagnostics(r, sc, 1),
    "review_values": lambda r, sc, crb: chc.review_values(r, crb, sc, 1),
    "eps_figure": lambda r, sc, crb: chc.eps_figure(r, sc),
    "pso_figure": lambda r, sc, crb: chc.pso_figure(r, frame=2),
    "stopping_values": lambda r, sc, crb: chc.stopping_values(r, sc),
    "guarded_runs": lambda r, sc, crb: chc.guarded_runs(r, sc, 5),
    "guard_values": lambda r, sc, crb: chc.guard_values(r, sc),
    "guard_usability": lambda r, sc, crb: chc.guard_usability(r, r, sc),
}
#: The helpers that take the scenario.
WITH_SC = ("crb_position", "any_collapsed", "collapse_values", "gm_yardstick", "consistency_figure",
           "double_count_values", "diagnostics", "review_values", "eps_figure", "stopping_values", "guarded_runs",
           "guard_values", "guard_usability")
#: The helpers that read the readings (``readings=True``).
READINGS = ("readings_values", "equal_kl_g_values", "stopping_values")
_NAME = {"collapse_values": "plain", "guard_values": "guarded", "guard_usability": "guarded"}


# --------------------------------------------------------------------------------------------------- TR: runs
@pytest.mark.parametrize("key", sorted(HELPERS))
@pytest.mark.parametrize("bad", ["x", 5, None, {"a": 1}])
def test_runs_not_a_sequence_is_refused_by_name(key, bad, runs):
    _refused(TypeError, _NAME.get(key, "runs"), HELPERS[key], bad, TINY, chc.crb_position(TINY, runs))


@pytest.mark.parametrize("key", sorted(HELPERS))
def test_empty_runs_refused_by_name(key, runs):
    _refused(ValueError, _NAME.get(key, "runs"), HELPERS[key], [], TINY, chc.crb_position(TINY, runs))


@pytest.mark.parametrize("key", sorted(HELPERS))
def test_a_run_that_is_not_a_tracking_run_is_refused_by_name(key, runs):
    msg = _refused(TypeError, f"{_NAME.get(key, 'runs')}[1]", HELPERS[key], [runs[0], 5], TINY,
                   chc.crb_position(TINY, runs))
    assert "TrackingRun" in msg


@pytest.mark.parametrize("key", [k for k in sorted(HELPERS) if k in WITH_SC])
@pytest.mark.parametrize("bad", ["x", 5, None])
def test_sc_not_a_scenario_is_refused_by_name(key, bad, runs, runs_r):
    r = runs_r if key in READINGS else runs
    _refused(TypeError, "sc", HELPERS[key], r, bad, chc.crb_position(TINY, runs))


_OTHER = {"frames": st.integers(7, 9), "n_particles": st.integers(301, 400), "n_central": st.integers(601, 700),
          "n_samples": st.integers(301, 400), "em_iterations": st.integers(6, 9),
          "sensors": st.just(((0.0, 0.0), (2000.0, 0.0))), "sigma_r": st.floats(11.0, 20.0)}


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(key=st.sampled_from([k for k in WITH_SC if k not in READINGS]),
       change=st.sampled_from(sorted(_OTHER)).flatmap(lambda f: st.tuples(st.just(f), _OTHER[f])))
def test_a_scenario_other_than_the_runs_is_refused_naming_sc(key, change, runs):
    """TR11: another scenario gave plausible wrong numbers (collapse flags, ESS) or an unnamed IndexError."""
    field, value = change
    other = dataclasses.replace(TINY, **{field: value})
    msg = _refused(ValueError, "sc", HELPERS[key], runs, other, chc.crb_position(TINY, runs))
    assert field in msg


@pytest.mark.parametrize("key", [k for k in WITH_SC if k not in ("guarded_runs", "guard_usability")])
def test_the_runs_own_scenario_with_a_guard_is_accepted(key, runs, runs_r):
    """The notebook passes the unguarded scenario with the guarded runs (some redone with the guard)."""
    r, sc = (runs_r, READ) if key in READINGS else (runs, TINY)
    mixed = [dataclasses.replace(r[0], scenario=chc.guarded_scenario(sc)), *r[1:]]
    HELPERS[key](mixed, sc, chc.crb_position(sc, r))


def test_runs_of_two_scenarios_are_refused_by_name(runs):
    other = dataclasses.replace(runs[1], scenario=dataclasses.replace(TINY, n_particles=301))
    msg = _refused(ValueError, "runs[1]", chc.gain_values, [runs[0], other, runs[2]])
    assert "n_particles" in msg


def test_runs_built_by_hand_are_compared_by_frames_and_nodes(runs):
    bare = [dataclasses.replace(r, scenario=None) for r in runs]
    assert chc.any_collapsed(bare, TINY).shape == (3,)
    _refused(ValueError, "sc", chc.any_collapsed, bare, dataclasses.replace(TINY, frames=7))
    _refused(ValueError, "sc", chc.double_count_values, bare, dataclasses.replace(TINY, sensors=((0.0, 0.0),) * 2))


def test_runs_of_other_frames_are_refused_by_name(runs_r, runs):
    bare = [dataclasses.replace(r, scenario=None) for r in (runs[0], runs_r[0])]
    _refused(ValueError, "runs[1]", chc.gain_values, bare)


@pytest.mark.parametrize("key", READINGS)
def test_runs_without_readings_are_refused_by_name(key, runs):
    """TR6-TR8: a KeyError ('equal_kl_g', 'first_order', 'fitness')."""
    msg = _refused(ValueError, "runs[0]", HELPERS[key], runs, TINY, None)
    assert "readings" in msg


def test_readings_helpers_accept_runs_with_readings(runs_r):
    assert chc.readings_values(runs_r)["chf_rd_frames"] == 2 * READ.frames
    assert chc.equal_kl_g_values(runs_r)["chf_klg_all"] == 2 * READ.frames
    assert chc.stopping_values(runs_r, READ)["chf_stop_frames"] == 2 * READ.frames


@pytest.mark.parametrize("f, name, field", [(chc.collapsed, "n_particles", "n_particles"),
                                            (chc.central_collapsed, "n_central", "n_central")])
def test_particle_counts_must_be_the_runs_own(f, name, field, runs):
    """TR11: ``collapsed(runs, 2000)`` on runs of 300 particles flagged other runs."""
    own = getattr(TINY, field)
    assert f(runs, own).shape == (3,)
    _refused(ValueError, name, f, runs, own + 1)
    _refused(TypeError, name, f, runs, "x")
    assert f([], own).shape == (0,)  # documented: empty for no runs


def test_typical_run_checks_its_counts(runs):
    assert 0 <= chc.typical_run(runs, TINY.n_particles, TINY.n_central) < 3
    _refused(ValueError, "n_central", chc.typical_run, runs, TINY.n_particles, 10_000)


def test_plain_must_be_the_same_studys_runs(runs):
    crb = chc.crb_position(TINY, runs)
    _refused(ValueError, "plain", chc.method_table, runs, crb, runs[:2])
    _refused(ValueError, "plain", chc.consistency_figure, runs, runs[:2], TINY)
    assert "RMSE, no guard (m)" in chc.method_table(runs, crb, runs).columns


def test_review_values_needs_two_runs(runs):
    crb = chc.crb_position(TINY, runs)
    _refused(ValueError, "runs", chc.review_values, runs[:1], crb, TINY, 1)
    assert "chf_top_share" in chc.review_values(runs[:2], crb, TINY, 1)


def test_a_tuple_of_runs_is_accepted_everywhere(runs):
    """The minor item of TR: guard_values refused a tuple that the other helpers took."""
    assert chc.guard_values(tuple(runs), TINY)["chf_n_guarded"] >= 0
    assert chc.gain_values(tuple(runs))["chf_n_worse_uni"] >= 0


# ----------------------------------------------------------------------------------------- K2-4: crb_pos
@pytest.mark.parametrize("f", [lambda r, c: chc.method_table(r, c), lambda r, c: chc.rmse_figure(r, c),
                               lambda r, c: chc.review_values(r, c, TINY, 1)])
def test_crb_pos_is_checked_by_name(f, runs):
    crb = chc.crb_position(TINY, runs)
    for bad in (crb * np.nan, crb[:3], -crb, np.stack([crb, crb])):
        _refused(ValueError, "crb_pos", f, runs, bad)
    f(runs, list(crb))  # any array_like of the right shape


# ------------------------------------------------------------------------------------ TR: frame, show, options
def test_pso_and_eps_figure_check_frame_and_show(runs):
    _refused(ValueError, "frame", chc.pso_figure, runs, frame=TINY.frames + 1)
    _refused(ValueError, "frame", chc.pso_figure, runs, frame=0)
    _refused(ValueError, "show", chc.pso_figure, runs, frame=2, show=3)
    _refused(ValueError, "show", chc.eps_figure, runs, TINY, show=3)
    _refused(TypeError, "frame", chc.pso_figure, runs, frame=2.0)
    _refused(TypeError, "frame", chc.pso_figure, runs, frame=True)
    _refused(TypeError, "show", chc.eps_figure, runs, TINY, show=True)
    chc.pso_figure(runs, frame=TINY.frames, show=2)


@pytest.mark.parametrize("xtols, exc, name", [((), ValueError, "xtols"), ((np.nan,), ValueError, "xtols[0]"),
                                              ((1e-3, -1.0), ValueError, "xtols[1]"), (("a",), TypeError, "xtols[0]"),
                                              (1e-3, TypeError, "xtols")])
def test_stopping_values_checks_xtols(xtols, exc, name, runs_r):
    _refused(exc, name, chc.stopping_values, runs_r, READ, xtols)


def test_stopping_values_keys_tolerances_by_position(runs_r):
    """TR13's repeated tolerance: kept (documented), each under its own position's keys."""
    v = chc.stopping_values(runs_r, READ, (1e-3, 1e-3))
    assert v["chf_stop_x0"] == v["chf_stop_x1"] == 1e-3 and v["chf_stop_evals_0"] == v["chf_stop_evals_1"]


@pytest.mark.parametrize("thr, exc, name", [((np.nan,), ValueError, "thresholds[0]"), ((0.0,), ValueError, "thresholds[0]"),
                                            ((0.01, 1.5), ValueError, "thresholds[1]"), ("x", TypeError, "thresholds")])
def test_guard_usability_checks_thresholds(thr, exc, name, runs):
    _refused(exc, name, chc.guard_usability, runs, runs, TINY, thr)


# ----------------------------------------------------------------------------------------------------- K2
def test_chapter_06_arguments_are_typed():
    _refused(TypeError, "sc", chc.scenario_table, 5)
    _refused(TypeError, "toy", chc.objective_figure, 5)
    _refused(TypeError, "toy", chc.contour_figure, 5, np.random.default_rng(1))
    _refused(TypeError, "led", chc.ledger_values, 5)
    assert len(chc.scenario_table(TINY)) == 10


def test_contour_figure_names_n_particles():
    toy = chc.toy_study(np.random.default_rng(3), 200)
    _refused(ValueError, "n_particles", chc.contour_figure, toy, np.random.default_rng(1), 0)
    _refused(TypeError, "rng", chc.contour_figure, toy, 1)
    _refused(TypeError, "rng", chc.toy_study, 1, 200)


# ------------------------------------------------------------------------------------------------------ SW
@pytest.mark.parametrize("f, name", [
    (lambda: csc.swarm_within_se(1, 10_000, 2, 100), "n "),
    (lambda: csc.swarm_within_se(1, 100_000, 2, 100), "n "),
    (lambda: csc.swarm_within_se(1, 3, 2, 10**7), "runs, r and n"),
    (lambda: csc.swarm_study(1, (2, 10_000), 2, 100), "ns "),
    (lambda: csc.scaling_study(1, (250, 500), 10**4, 2), "n "),
    (lambda: chc.toy_study(np.random.default_rng(1), 10**7), "r "),
    (lambda: chc.is_variance_study(np.random.default_rng(1), 10, 10**7), "replicates and R"),
    (lambda: chc.is_variance_study(np.random.default_rng(1), 10**7, 10), "replicates and R"),
    (lambda: cs.defensive_study(np.random.default_rng(1), 2, 10**7), "runs and r"),
    (lambda: cs.defensive_study(np.random.default_rng(1), 2, 10**7 // 3 * 2), "runs and r"),
])
def test_sizes_beyond_the_budgets_are_refused_by_the_callers_names(f, name):
    """SW: MemoryError (7.8 GiB), or an internal name (dim, x, n for r), before."""
    with pytest.raises(ValueError) as info:
        f()
    assert str(info.value).startswith(name), str(info.value)


def test_sizes_within_the_budgets_still_run():
    gap, se = csc.swarm_within_se(1, 3, 2, 50)
    assert gap.shape == se.shape == (2,)
    assert csc.scaling_study(1, (20, 40), 3, 2).eps_err.shape == (2, 2)
    assert chc.toy_study(np.random.default_rng(1), 100).r == 100
