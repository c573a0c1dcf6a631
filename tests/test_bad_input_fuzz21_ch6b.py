"""Fuzz 21b's cases of chapter 06's appendix studies (issue 35), by class.

``chernoff_steps``, ``chernoff_scaling``, ``chernoff_first_order`` and the chernoff package's ``toy_study`` and
``is_variance_study``. Each refusal is a ValueError or TypeError naming the argument; valid input keeps working:

* P: ``paired_numbers``'s ``prefix`` is a string making identifier glue keys (the rule of the ledger's numbers);
* S: ``snis_delta_terms``'s ``cell`` goes through the shared scalar reader (numpy scalars and 0-d arrays are
  numbers, a bool is not, rule 2's magnitudes), and ``exp(2 lp - lg)`` is taken in logs, its overflow refused by
  ``log_proposal``;
* D: ``density_evaluations``' S^N is bounded by the float range before the power is computed;
* F: ``sigma_first_order_problem``'s grid within the memory budget; ``defensive_mixture``'s ``local`` a sequence;
* Q: the block studies' repeated ``rs`` refused (their results are keyed by R), ``toy_study``'s ``base`` typed;
* Y: arguments that could only give NaN in a result whose own ``glue()`` then fails are refused by the producer
  (at least two blocks per R, two sizes for a slope, two runs, two replicates), the smallest valid ones accepted.
"""

from __future__ import annotations

import math
import time
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from fusion.book.chapters import chernoff as chf
from fusion.book.chapters import chernoff_first_order as fo
from fusion.book.chapters import chernoff_scaling as csc
from fusion.book.chapters import chernoff_steps as cs

FLOAT_MAX = int(np.finfo(float).max)


def _refused(exc: type[Exception], name: str, f, *args, **kwargs) -> str:
    with pytest.raises(exc) as info:
        f(*args, **kwargs)
    msg = str(info.value)
    assert name in msg, msg
    return msg


# ------------------------------------------------------------------------------------------------ P: prefix
_A = np.random.default_rng(2).normal(1, 0.1, 50)
_B = _A + np.random.default_rng(3).normal(0.05, 0.01, 50)


@pytest.mark.parametrize("prefix", [5, None, b"x", 1.5, ("x",)])
def test_paired_numbers_prefix_must_be_a_string(prefix):
    _refused(TypeError, "prefix", cs.paired_numbers, _A, _B, prefix)


@pytest.mark.parametrize("prefix", ["a b", "x-y", "a.b"])
def test_paired_numbers_prefix_must_make_identifier_keys(prefix):
    _refused(ValueError, "prefix", cs.paired_numbers, _A, _B, prefix)


def test_paired_numbers_valid_prefix():
    out = cs.paired_numbers(_A, _B, "chf_x")
    assert set(out) == {f"chf_x_{k}" for k in ("stat", "d", "lo", "hi", "med", "won", "runs")}
    assert all(k.isidentifier() for k in out)


# ------------------------------------------------------------------------------------------------ S: cell, overflow
_G = np.linspace(-5, 5, 201)
_X = _G[:, None]
_CELL = float(_G[1] - _G[0])
_LP = -0.5 * _G**2
_LG = -0.5 * (_G / 2) ** 2 - np.log(2 * np.sqrt(2 * np.pi))


@pytest.mark.parametrize("cell", [np.float64(_CELL), np.array(_CELL), np.float32(0.05), Fraction(1, 20),
                                  np.int64(1), 1])
def test_cell_numbers_are_accepted_as_their_float(cell):
    got = cs.snis_delta_terms(_X, _LP, _LG, cell)
    ref = cs.snis_delta_terms(_X, _LP, _LG, float(cell))
    assert got.second_moment == ref.second_moment and np.array_equal(got.c, ref.c)


@pytest.mark.parametrize("cell", [True, False, np.bool_(True), "0.05", None, 1j])
def test_cell_non_numbers_refused(cell):
    _refused(TypeError, "cell", cs.snis_delta_terms, _X, _LP, _LG, cell)


@settings(max_examples=40, deadline=None)
@given(st.one_of(st.floats(min_value=5e-324, max_value=9.99e-151), st.floats(min_value=1.01e150, max_value=1e308),
                 st.floats(max_value=0.0), st.sampled_from([math.inf, math.nan])))
def test_cell_outside_the_magnitudes_refused(cell):
    _refused(ValueError, "cell", cs.snis_delta_terms, _X, _LP, _LG, cell)


@pytest.mark.parametrize("shift", [-1000.0, 1000.0, -2000.0])
def test_second_moment_beyond_the_float_range_refused_by_log_proposal(shift):
    _refused(ValueError, "log_proposal", cs.snis_delta_terms, _X, _LP, _LG + shift, _CELL)


def test_second_moment_beyond_the_magnitude_rule_is_refused():
    # p = 1 / (2 cell) at both nodes; g = p e^-400: exp(2 lp - lg) overflows and, times a cell >= 1e-150 (the
    # magnitude rule), the terms stay beyond 1e150: refused by SnisDelta's field spec, not returned as inf
    cell = 1e-150
    lp = np.zeros(2)
    lg = np.full(2, np.log(0.5 / cell) - 400.0)
    with pytest.raises(ValueError, match="beyond the representable range"):
        cs.snis_delta_terms(np.array([[0.0], [1.0]]), lp, lg, cell)


# ------------------------------------------------------------------------------------------------ D: S^N
@settings(max_examples=60, deadline=None)
@given(st.integers(1, 2000), st.integers(1, 60))
def test_density_evaluations_within_the_float_range_exactly(n, s):
    total = s**n + n * s
    if total <= FLOAT_MAX:
        assert csc.density_evaluations(n, s) == total
        str(csc.density_evaluations(n, s))  # printable
    else:
        _refused(ValueError, "n and s", csc.density_evaluations, n, s)


def test_density_evaluations_bound_edges():
    assert csc.density_evaluations(1023, 2) == 2**1023 + 2046
    _refused(ValueError, "n and s", csc.density_evaluations, 1024, 2)
    assert csc.density_evaluations(10**7, 1) == 1 + 10**7


@pytest.mark.parametrize("n, s", [(10**7, 10**7), (10**6, 10**4), (10000, 50)])
def test_density_evaluations_refused_before_the_power(n, s):
    t = time.process_time()
    _refused(ValueError, "n and s", csc.density_evaluations, n, s)
    assert time.process_time() - t < 0.5  # refused, not computed (10**6, 10**4) took 1.3 s to compute


def test_cost_table_names_the_entries():
    msg = _refused(ValueError, "ns[1]", csc.cost_table, (2, 10**6), (1, 3))
    assert "ss[1]" in msg
    assert csc.cost_table().loc[10, "S = 3"] == 3**10 + 30


# ------------------------------------------------------------------------------------------------ F
_MA, _MB = fo.random_two_mixtures(np.random.default_rng(0))


@pytest.mark.parametrize("n", [10**7, 20_000])
def test_sigma_first_order_problem_grid_within_the_memory_budget(n):
    _refused(ValueError, "n", fo.sigma_first_order_problem, _MA, _MB, n)


@pytest.mark.parametrize("local", [lambda: (g for g in [_MA, _MB]), lambda: _MA, lambda: {"a": _MA},
                                   lambda: None, lambda: iter([_MA])])
def test_defensive_mixture_local_must_be_a_sequence(local):
    _refused(TypeError, "local", cs.defensive_mixture, _MA, local(), 0.2)


def test_defensive_mixture_local_entries_and_valid_sequences():
    _refused(TypeError, "local[1]", cs.defensive_mixture, _MA, [_MB, "x"], 0.2)
    _refused(ValueError, "local", cs.defensive_mixture, _MA, (), 0.2)
    a = cs.defensive_mixture(_MA, [_MA, _MB], 0.2)
    b = cs.defensive_mixture(_MA, (_MA, _MB), 0.2)
    assert np.array_equal(a.weights, b.weights) and np.array_equal(a.means, b.means)


# ------------------------------------------------------------------------------------------------ Q
@pytest.mark.parametrize("study", [cs.snis_bias_study, cs.chosen_bias_study])
@pytest.mark.parametrize("rs", [(5, 5), (10, 20, 10), np.array([4, 4])])
def test_block_studies_refuse_repeated_rs(study, rs):
    _refused(ValueError, "rs", study, np.random.default_rng(3), rs, 4000)


@pytest.mark.parametrize("study", [cs.snis_bias_study, cs.chosen_bias_study])
def test_block_studies_take_rs_in_increasing_order(study):
    a = study(np.random.default_rng(3), (40, 20), 4000).table
    b = study(np.random.default_rng(3), (20, 40), 4000).table
    assert a.equals(b)


@pytest.mark.parametrize("base", ["x", 5, object()])
def test_toy_study_base_must_be_a_toy_study(base):
    _refused(TypeError, "base", chf.toy_study, np.random.default_rng(3), 300, base=base)


# ------------------------------------------------------------------------------------------------ Y
@pytest.mark.parametrize("study, rs, total", [(cs.chosen_bias_study, (2000,), 2000), (cs.snis_bias_study, (10,), 10),
                                              (cs.snis_bias_study, (5, 10), 10), (cs.chosen_bias_study, (4, 6), 6)])
def test_block_studies_refuse_a_single_block(study, rs, total):
    _refused(ValueError, "rs", study, np.random.default_rng(3), rs, total)


@pytest.mark.parametrize("study", [cs.snis_bias_study, cs.chosen_bias_study])
def test_block_studies_two_blocks_are_enough_for_the_glue(study):
    r = study(np.random.default_rng(3), (10,), 20)
    assert not r.table.isna().any().any()
    v = r.glue()
    assert all(not isinstance(x, float) or math.isfinite(x) for x in v.values())
    r.display_table()


def test_scaling_study_needs_two_sizes():
    _refused(ValueError, "rs", csc.scaling_study, 1, (250,), 3, 3)
    v = csc.scaling_study(1, (100, 200), 2, 2).glue()
    assert math.isfinite(v["chf_scale_slope"])


def test_sigma_first_order_study_needs_two_runs():
    _refused(ValueError, "runs", fo.sigma_first_order_study, np.random.default_rng(3), 1)
    v = fo.sigma_first_order_study(np.random.default_rng(3), 2).glue()
    assert v["chf_sp_eps_stat"] in ("mean", "median") and math.isfinite(v["chf_sp_eps_d"])


def test_is_variance_study_needs_two_replicates():
    _refused(ValueError, "replicates", chf.is_variance_study, np.random.default_rng(3), 10, 1)
    _refused(TypeError, "rng", chf.is_variance_study, 3, 10, 20)
    _refused(ValueError, "replicates and R", chf.is_variance_study, np.random.default_rng(3), 10**5, 10**5)
    v = chf.is_variance_study(np.random.default_rng(3), 10, 2).glue()
    assert all(not isinstance(x, float) or math.isfinite(x) for x in v.values())
