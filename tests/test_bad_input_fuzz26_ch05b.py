"""Fuzz 26c, classes B1-B4 and the debatable q2, q3, q6, q7 (issue 35, chapter 05): mismatched inputs accepted.

One rule per class, checked on what the objects record:

* B1/q7: the two WeightPairs of :func:`paired_studies` and :func:`weight_claim_inputs` told apart by their noises
  (one shared check, ``weights._pair_noises``); for the ledger's one quoted step, also searched at the same step
  of runs at the same period.
* B2: architecture_studies' two studies told apart by the rules they record (Q's placement runs on the identical
  sensors only: ``checks._arch_pair``), in :class:`LedgerInputs`, :func:`architecture_numbers`,
  :func:`paired_numbers`.
* B3: :func:`ledger`'s ``values`` compared with ``ledger_values(r)``.
* B4: :class:`LedgerInputs`' two FOA-step tables specified by what they hold (rule labels; test minima).
* q2 (decided, fixed): a float32 period or weight that keys a row or an entry is the number it prints as.
* q3 (decided, fixed): :func:`printed_weight_facts` refuses a sensor pair given twice (its covariances counted twice).
* q6 (decided, documented): the NEES tables' plain arrays record no pairing; documented, not checkable.
"""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import test_bad_input_calls_ch05 as T


# the chapter's objects (a module fixture), the registry's valid calls and the chapter, as fuzz 24c's file has them
from test_bad_input_fuzz24_ch05b import _ci, _valid, o  # noqa: E402, F401


# --- B1/q7: the two weight pairs, by the noises (and step, period) they record ---

def test_paired_studies_tells_the_pairs_apart(o: dict[str, Any]) -> None:
    ci, wp, wp_an = _ci(), o["wp"], o["wp_an"]
    kw = _valid("paired_studies")
    assert len(ci.paired_studies(**kw).omega_u) > 0
    with pytest.raises(ValueError, match="aniso must be a weight_pair of ANISO_R"):
        ci.paired_studies(**{**kw, "unequal": wp_an, "aniso": wp})     # swapped
    with pytest.raises(ValueError, match=r"unequal must be a weight_pair .*R2 = R1 / 9"):
        ci.paired_studies(**{**kw, "unequal": wp_an})                  # the anisotropic pair twice
    with pytest.raises(ValueError, match="aniso must be a weight_pair of ANISO_R"):
        ci.paired_studies(**{**kw, "aniso": wp})                       # the unequal pair twice


def test_weight_claim_inputs_pairs_share_step_and_period(o: dict[str, Any]) -> None:
    ci, wp, flat = _ci(), o["wp"], o["flat"]
    Q = o["Q"]
    assert ci.weight_claim_inputs(wp, o["wp_an"], flat).fruit_fly_step == wp.k
    with pytest.raises(ValueError, match="aniso is searched at step 3 and asym at step 2"):
        ci.weight_claim_inputs(wp, o["wp_an_k3"], flat)
    other_T = ci.weight_pair(*ci.ANISO_R, Q, 2, seed=4, search_seed=2, fruit_fly_seeds=[3], runs=2, T=2 * T.TS)
    with pytest.raises(ValueError, match="aniso and asym are runs at other periods"):
        ci.weight_claim_inputs(wp, other_T, flat)


# --- B2: architecture_studies' two studies, by the rules they record ---

@pytest.fixture(scope="module")
def real_arch() -> dict[str, Any]:
    """architecture_studies itself, small (the rule the checks read holds for the producer, not only the fixture)."""
    ci = _ci()
    Q, R1, R2 = ci.printed_covariances()
    return ci.architecture_studies(R1, R2, Q, (1, 2), 0.0018, 2, 2, T=8.0, fixed_omegas=())


def test_architecture_studies_tells_its_studies_apart_by_their_rules(real_arch: dict[str, Any]) -> None:
    from fusion.book.chapters.ci.checks import _arch_pair, _placement_rules

    ai, an = real_arch.values()
    assert _placement_rules(ai) and not _placement_rules(an)
    _arch_pair(ai, an, ("a", "b"))
    for pair in ((an, ai), (ai, ai), (an, an)):
        with pytest.raises(ValueError, match="must be the"):
            _arch_pair(*pair, ("a", "b"))


@pytest.mark.parametrize("order", ["swapped", "identical twice", "anisotropic twice"])
def test_ledger_inputs_refuses_the_arch_studies_mixed_up(o: dict[str, Any], order: str) -> None:
    ci, p = _ci(), o["parts"]
    ai, an = p["arch"]
    arch = {"swapped": (an, ai), "identical twice": (ai, ai), "anisotropic twice": (an, an)}[order]
    with pytest.raises(ValueError, match=r"LedgerInputs\.arch\[[01]\] must be the"):
        ci.ledger_inputs(**{**p, "arch": arch})
    studies = ci.ArchInputs(arch=p["arch"], arch_seeds=p["arch_seeds"])
    assert studies.arch[0] is ai
    with pytest.raises(ValueError, match=r"ArchInputs\.arch\[[01]\] must be the"):
        ci.ArchInputs(arch=arch, arch_seeds=p["arch_seeds"])


def test_architecture_numbers_and_paired_numbers_refuse_the_wrong_study(o: dict[str, Any]) -> None:
    ci, arch = _ci(), o["arch"]
    I, N = list(arch)
    ai, an = arch.values()
    kw = _valid("architecture_numbers")
    assert ci.architecture_numbers(**kw)["ci_fb_split_d_a"]
    for bad in ({I: ai, N: ai}, {I: an, N: ai}):
        with pytest.raises(ValueError, match=r"arch\['.*'\] must be the"):
            ci.architecture_numbers(**{**kw, "arch": bad, "arch_table": ci.architecture_table(bad)})
    kp = _valid("paired_numbers")
    assert ci.paired_numbers(**kp)["ci_half_ratio_lit"] > 0
    with pytest.raises(ValueError, match="ai must be the identical-sensor study"):
        ci.paired_numbers(**{**kp, "ai": an})


# --- B3: ledger's values are ledger_values(r) ---

def test_ledger_values_must_be_those_of_r(o: dict[str, Any]) -> None:
    ci, r = _ci(), o["r"]
    values = ci.ledger_values(r)
    assert ci.ledger(r, dict(values)).claims
    with pytest.raises(ValueError, match=r"values\['ci_lg_leg_best'\] = 999.0 differs from"):
        ci.ledger(r, {**values, "ci_lg_leg_best": 999.0})
    with pytest.raises(ValueError, match="unknown keys"):
        ci.ledger(r, {**values, "ci_lg_extra": 1.0})
    other = ci.ledger_inputs(**{**o["parts"], "leg_floor": 20.0, "leg_best": 70.0})
    with pytest.raises(ValueError, match="values must be ledger_values"):
        ci.ledger(r, ci.ledger_values(other))          # another study's numbers
    with pytest.raises(TypeError, match="values must be a mapping"):
        ci.ledger(r, list(values.items()))


@settings(max_examples=20, deadline=None)
@given(key=st.integers(0, 10**6), delta=st.sampled_from([1e-9, -1.0, 1.0, 1e6]))
def test_ledger_refuses_any_edited_number(key: int, delta: float) -> None:
    ci, r = _ci(), T._objects()["r"]
    values = ci.ledger_values(r)
    numeric = sorted(k for k, v in values.items() if isinstance(v, (int, float)) and not isinstance(v, bool))
    k = numeric[key % len(numeric)]
    # an integer count edited by a float delta is a float: refused by its type class (fuzz 28b D1)
    with pytest.raises(TypeError if isinstance(values[k], int) else ValueError, match=rf"values\['{k}'\]"):
        ci.ledger(r, {**values, k: values[k] + delta})


# --- B4: the FOA-step tables, by what they hold ---

def test_ledger_inputs_foa_step_tables_by_what_they_hold(o: dict[str, Any]) -> None:
    ci, p = _ci(), o["parts"]
    study, targets = p["fruit_fly_step_study"], p["fruit_fly_step_targets"]
    with pytest.raises(ValueError, match=r"LedgerInputs\.fruit_fly_step_study must hold the rows"):
        ci.ledger_inputs(**{**p, "fruit_fly_step_study": targets})
    with pytest.raises(ValueError, match=r"LedgerInputs\.fruit_fly_step_targets must be indexed by test minima"):
        ci.ledger_inputs(**{**p, "fruit_fly_step_targets": study})
    with pytest.raises(ValueError, match=r"LedgerInputs\.fruit_fly_step_targets repeats a test minimum"):
        ci.ledger_inputs(**{**p, "fruit_fly_step_targets": pd.concat([targets, targets.iloc[:1]])})
    # read by label: the study's rows in another order give the same evidence
    before = ci.ev_foa_step(ci.ledger_inputs(**p))
    after = ci.ev_foa_step(ci.ledger_inputs(**{**p, "fruit_fly_step_study": study.iloc[::-1]}))
    assert after == before


# --- q2: a float32 period or weight key is the number it prints as ---

@settings(max_examples=15, deadline=None)
@given(extra=st.lists(st.sampled_from([0.5, 0.2, 0.1, 0.05, 0.01, 0.005]), unique=True, max_size=3))
def test_pcrb_table_float32_periods_are_the_rows_read(extra: list[float]) -> None:
    ci = _ci()
    periods = [1.0, 0.02, 0.001, *extra]
    t64 = ci.pcrb_table(np.array(periods), 150.0, 10.0)
    t32 = ci.pcrb_table(np.array(periods, dtype=np.float32), 150.0, 10.0)
    assert list(t32.index) == list(t64.index)
    from fusion.scenarios import two_sensor

    q = two_sensor.Q_READINGS[0]
    assert ci.pcrb_numbers(t32, q) == ci.pcrb_numbers(t64, q)


def test_ledger_inputs_float32_keys_are_read_as_printed(o: dict[str, Any]) -> None:
    ci, p = _ci(), o["parts"]
    r32 = ci.ledger_inputs(**{**p, "slip_weights": {np.float32(k): v for k, v in p["slip_weights"].items()}})
    assert set(r32.slip_weights) == set(p["slip_weights"])
    assert ci.ledger_values(r32) == ci.ledger_values(o["r"])
    with pytest.raises(ValueError, match="slip_weights holds two keys read as one"):
        ci.ledger_inputs(**{**p, "slip_weights": {0.0018: (1.0, 1.0), np.float32(0.0018): (1.0, 1.0),
                                                  **{k: v for k, v in p["slip_weights"].items() if k != 0.0018}}})


# --- q3: one sensor pair given twice to printed_weight_facts ---

def test_printed_weight_facts_refuses_a_pair_twice(o: dict[str, Any]) -> None:
    ci, sc = _ci(), o["sc"]
    one = ci.printed_weight_facts((sc,), 2, np.arange(2), n_grid=11)
    two = ci.printed_weight_facts((sc, o["sc_an"]), 2, np.arange(2), n_grid=11)
    assert two.steps == 2 * one.steps
    for scs in ((sc, sc), (sc, o["sc_o"]), (o["sc_an"], sc, o["sc_o"])):   # the same pair, or on other runs
        with pytest.raises(ValueError, match=r"scenarios must not repeat a sensor pair: scenarios\[\d\]"):
            ci.printed_weight_facts(scs, 2, np.arange(2), n_grid=11)


# --- q6: the NEES tables' pairing, now recorded and checked (tests/test_bad_input_swaps.py); a plain mapping is not ---

def test_nees_start_docstrings_say_a_plain_mapping_is_not_checked() -> None:
    ci = _ci()
    assert "A plain mapping records" in ci.nees_start_table.__doc__
    assert "A plain mapping is not" in ci.nees_start_numbers.__doc__


def test_dataclass_replace_keeps_the_checks(o: dict[str, Any]) -> None:
    ci, r = _ci(), o["r"]
    with pytest.raises(ValueError, match=r"LedgerInputs\.arch\[0\] must be the"):
        dataclasses.replace(r, arch=r.arch[::-1])
