"""Fuzz 24c, classes MM/FA, FA1, LI, SZ, WN and the debatable q1 (issue 35, chapter 05).

* MM/FA: results of one pair (or study) set against another's, though the objects tell them apart. One rule in
  ``fusion.book.chapters.ci.checks``: the optima of :func:`weight_search` and ``fruit_fly_over_seeds`` are those of
  the pair's CI objective at their ω (``_optima_of``; ``_same_search`` where no pair is given), the two pairs of
  :func:`weight_claim_inputs` told apart by their noises, a straight leg that of its study (``_leg_of``).
* FA1: ``fig5(aniso=...)`` names the entry at fault (``aniso[0]``, a 4 x 4 expected), not the next one.
* LI: :class:`LedgerInputs` ``ir_T`` is the period of its readings and one of ``ir_sens``.
* SZ/WN: sizes refused by the shared memory, input and work budgets before any work, naming the caller's argument.
* q1 (decided, fixed): :func:`fig5_hypothesis_numbers` reads rows by position, so their labels are checked.
"""

from __future__ import annotations

import dataclasses
import re
import time
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import test_bad_input_calls_ch05 as T


@pytest.fixture(scope="module")
def o() -> dict[str, Any]:
    return T._objects()


def _valid(name: str) -> dict[str, Any]:
    return {k: a.value for k, a in T.registry()["fusion.book.chapters.ci." + name].items()}


def _ci() -> Any:
    from fusion.book.chapters import ci

    return ci


# --- MM: pairs and studies told apart by what their objects record ---

def test_weight_claim_inputs_tells_the_pairs_apart(o: dict[str, Any]) -> None:
    ci, wp, wp_an, flat = _ci(), o["wp"], o["wp_an"], o["flat"]
    assert ci.weight_claim_inputs(wp, wp_an, flat).omega_aniso == wp_an.res["closed form"].x
    with pytest.raises(ValueError, match="aniso must be a weight_pair of ANISO_R"):
        ci.weight_claim_inputs(wp_an, wp, flat)   # swapped
    with pytest.raises(ValueError, match="aniso must be a weight_pair of ANISO_R"):
        ci.weight_claim_inputs(wp, wp, flat)      # one pair twice
    with pytest.raises(ValueError, match="asym must be a weight_pair"):
        ci.weight_claim_inputs(wp_an, wp_an, flat)


def test_fig5_refuses_another_pairs_optima(o: dict[str, Any]) -> None:
    ci, wp, wp_an = _ci(), o["wp"], o["wp_an"]
    kw = _valid("fig5")
    with pytest.raises(ValueError, match=r"res\['.*'\] must be searched on the pair \(P1, P2\)"):
        ci.fig5(**dict(kw, res=wp_an.res))
    good = (wp_an.P1, wp_an.P2, wp_an.res, wp_an.fruit_fly_seeds)
    with pytest.raises(ValueError, match=r"aniso\[2\]\['.*'\] must be searched on the pair"):
        ci.fig5(**dict(kw, aniso=good[:2] + (wp.res,) + good[3:]))
    with pytest.raises(ValueError, match=r"aniso\[3\] \(its exhaustive search\) must be searched on the pair"):
        ci.fig5(**dict(kw, aniso=good[:3] + (wp.fruit_fly_seeds,)))
    with pytest.raises(ValueError, match="aniso must be another pair than"):
        ci.fig5(**dict(kw, aniso=(wp.P1, wp.P2, wp.res, wp.fruit_fly_seeds)))
    ci.fig5(**dict(kw, aniso=good))   # the valid call with its anisotropic panel
    import matplotlib.pyplot as plt

    plt.close("all")


@settings(max_examples=15, deadline=None)
@given(st.floats(1e-7, 0.5), st.sampled_from(["FOA (30 × 200)", "exhaustive, 1001 points", "scipy bounded Brent",
                                              "closed form"]))
def test_fig5_refuses_an_optimum_off_the_objective(factor: float, method: str) -> None:
    """Any recorded tr P off the pair's objective at its ω (relative 1e-9) is refused, naming ``res[method]``."""
    from fusion.optimise.result import OptimumResult

    kw = _valid("fig5")
    res = dict(kw["res"])
    r = res[method]
    res[method] = OptimumResult(x=r.x, fun=r.fun * (1 + factor), n_evaluations=r.n_evaluations)
    with pytest.raises(ValueError, match=re.escape(f"res['{method}'] must be searched on the pair")):
        _ci().fig5(**dict(kw, res=res))


def test_fig5_names_the_aniso_entry_at_fault(o: dict[str, Any]) -> None:
    wp_an = o["wp_an"]
    good = (wp_an.P1, wp_an.P2, wp_an.res, wp_an.fruit_fly_seeds)
    with pytest.raises(ValueError, match=r"aniso\[0\] must be 4x4"):
        _ci().fig5(**dict(_valid("fig5"), aniso=(np.eye(2),) + good[1:]))
    with pytest.raises(TypeError, match="aniso must be a sequence"):
        _ci().fig5(**dict(_valid("fig5"), aniso="x"))


def test_weight_search_numbers_refuses_another_pairs_optima(o: dict[str, Any]) -> None:
    kw = _valid("weight_search_numbers")
    _ci().weight_search_numbers(**kw)
    with pytest.raises(ValueError, match="fruit_fly_seeds and res must be searches of one pair"):
        _ci().weight_search_numbers(**dict(kw, res=o["wp_an"].res))


def test_rmse_numbers_refuses_another_studys_leg(o: dict[str, Any]) -> None:
    kw = _valid("rmse_numbers")
    _ci().rmse_numbers(**kw)
    leg2 = _ci().straight_leg(o["study_o"], 8.0, 150.0)
    with pytest.raises(ValueError, match=r"leg_rmse\[.*\] = .* must be study's RMSE on its straight leg"):
        _ci().rmse_numbers(kw["study"], leg2.floor, leg2.steady, leg2.rmse, leg2.causal)
    with pytest.raises(ValueError, match="legs_steady must be study's steady steps"):
        _ci().rmse_numbers(**dict(kw, legs_steady=~np.asarray(kw["legs_steady"])))


# --- LI ---

@pytest.mark.parametrize("ir_T", [123.0, 0.5])
def test_ledger_inputs_ir_T_is_the_readings_period(o: dict[str, Any], ir_T: float) -> None:
    r = o["r"]
    assert ir_T != r.ir_T
    with pytest.raises(ValueError, match="ir_T"):
        dataclasses.replace(r, ir_T=ir_T)


# --- SZ / WN: refused by the budgets, naming the caller's argument, before any work ---

def _sizes() -> list[tuple[str, Any, str]]:
    ci = _ci()

    def q() -> tuple[np.ndarray, np.ndarray]:
        Q, R1, _ = ci.printed_covariances()
        return Q, R1

    means = {k: 1.0 for k in ("azimuth (mrad)", "elevation (mrad)", "x (m)", "y (m)")}
    return [
        ("printed_weight_facts(n_grid=2e5)",
         lambda: ci.printed_weight_facts((ci.source_scenario(2024),), 2, np.arange(2), n_grid=2 * 10**5), "n_grid"),
        ("ir_study(runs=1e7)", lambda: ci.ir_study(0.1, 1, 10**7, duration=3.0), "runs"),
        ("ir_study(T=1e-6)", lambda: ci.ir_study(1e-6, 1, 3, duration=3.0), "T"),
        ("ir_readings(runs=1e6)", lambda: ci.ir_readings(0.1, 1, 10**6, duration=3.0), "runs"),
        ("split_ci_exactness(n_steps=1e7)", lambda: ci.split_ci_exactness(*q(), 1.0, 10**7), "n_steps"),
        ("nees_per_step(n_steps=1e6)",
         lambda: ci.nees_per_step(np.random.default_rng(0), *q(), q()[1] / 9, np.zeros(4), 10**6, 5), "n_steps"),
        # its edge is 10,404 seeds (10.9 CPU-s measured, fuzz 59a C1: 10**4 was refused by a charge quadratic in seeds)
        ("fruit_fly_step_study(2e4)", lambda: ci.fruit_fly_step_study(2 * 10**4, 0.8, 0), "seeds"),
        ("ir_flown_numbers(distance=1e9)", lambda: ci.ir_flown_numbers(1, 3, means, distance=1e9), "distance"),
        ("fig5_hypotheses(short_budget=1e7)",
         lambda: ci.fig5_hypotheses(**dict(_valid("fig5_hypotheses"), short_budget=10**7)), "short_budget"),
    ]


@pytest.mark.parametrize("i", range(9))
def test_sizes_refused_by_name_before_any_work(i: int) -> None:
    import inspect

    label, call, name = _sizes()[i]
    fn = getattr(_ci(), label.split("(")[0])
    start = time.process_time()
    with pytest.raises(ValueError, match=rf"^{name}\b|[ (]{name}\b") as err:
        call()
    assert time.process_time() - start < 5.0, label
    # the budget's message names the call's own arguments, and only them, before "ask for"
    msg = str(err.value)
    assert " ask for " in msg, msg
    named = set(re.findall(r"[A-Za-z_][A-Za-z_0-9]*", msg.split(" ask for ")[0])) - {"and", "with", "the", "steps",
                                                                                       "of", "s"}
    assert named <= set(inspect.signature(fn).parameters), (label, named)


def test_sizes_within_the_budgets_run() -> None:
    ci = _ci()
    Q, R1, _ = ci.printed_covariances()
    assert ci.split_ci_exactness(Q, R1, 1.0, 300)["nees_random_max"] > 0
    assert set(ci.nees_per_step(np.random.default_rng(0), Q, R1, R1 / 9, np.zeros(4), 50, 3))
    sim, _ = ci.ir_study(0.05, 1, 2, duration=3.0)
    assert sim.t.size == 61


# --- q1 (decided): fig5_hypothesis_numbers checks the labels of the rows it reads by position ---

def test_fig5_hypothesis_numbers_checks_row_labels() -> None:
    kw = _valid("fig5_hypothesis_numbers")
    _ci().fig5_hypothesis_numbers(**kw)
    with pytest.raises(ValueError, match="table must hold fig5_hypotheses' rows in its order"):
        _ci().fig5_hypothesis_numbers(**dict(kw, table=kw["table"].iloc[::-1]))
    t = kw["table"]
    swapped = t.iloc[[0, 1, 3, 2] + list(range(4, len(t)))]
    with pytest.raises(ValueError, match="row 2"):
        _ci().fig5_hypothesis_numbers(**dict(kw, table=swapped))
