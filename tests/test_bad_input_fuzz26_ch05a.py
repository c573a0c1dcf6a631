"""Fuzz 26c's bad input of chapter 05, classes A1-A8 and the debatable q1, q4, q5, q8, q9, q10 (issue 35).

Each reproducer of ``/work/tmp/fuzz26c/report.md`` for these classes must raise a :class:`ValueError` (a
:class:`TypeError` for a wrong type) whose message names the caller's argument, and valid input must be accepted:

* A1: the tiny-variance rule of ``as_semidefinite`` is a rule for inputs; the parts ``fusion_loop`` computes (a
  correlated part that decays, fed back at every step) are read by ``fusion._covariances.computed_part`` (a variance
  below ``MIN_VARIANCE`` is zero), so ``architecture_studies`` runs at the chapter's T = 0.5 s;
* A2: ``fruit_fly_step_targets`` refuses a repeated target (the shared repeat rule);
* A3: ``weight_pair`` names ``fruit_fly_seeds`` for the rules of its callee (repeats, FOA's budgets), up front;
* A4: the infrared tables read ``rmse``'s values as arrays (lists, DataFrames are array_like);
* A5, A6: rule R4's refusal names ``r.<field>`` (functions of LedgerInputs) or ``runs`` (``record_evidence``);
  ``record_evidence`` refuses a ``rid`` that is not a string by a TypeError naming it;
* A7: ``fig5_hypotheses(n_open=1)``: the one-point grid ω = 1;
* A8: ``ir_ratio`` refuses, by the memory budget, runs whose BCa jackknife does not fit (naming ``run_rmse``;
  ``ir_readings`` names ``runs``);
* q1 the flown distance's label; q4 the floats ``sensitivity_table`` reads from ``known``; q5 an empty per-step series
  and ``timing_benchmark``'s missing file named by ``results``; q8 three significant digits; q9 ``n_open``'s memory
  budget; q10 a float32 cell glued as the decimal it prints.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings, strategies as st


from fusion._limits import MIN_VARIANCE
from fusion._validation import as_semidefinite
from fusion.book.chapters import ci

sys.path.insert(0, str(Path(__file__).resolve().parent))
import test_bad_input_calls_ch05 as reg  # noqa: E402


# the registry's valid calls and the refusal check, shared with fuzz 24c's file (one cache of the registry per worker)
from test_bad_input_fuzz24_ch05a import kwargs, refused, valid  # noqa: E402, F401


# ------------------------------------------------------------------------------------------------ A1


def test_a1_fed_back_split_with_own_process_noise_runs_at_half_a_second() -> None:
    """The loop architecture_studies runs at T = 0.5 s (eqs. 11-12, fed back, Q in the own parts): its correlated
    part decays below MIN_VARIANCE over 521 steps; the loop runs (it refused that computed part as an input)."""
    from fusion.filtering.feedback import fusion_loop
    from fusion.scenarios.two_sensor import architecture as ar

    Q, R1, R2 = ci.printed_covariances()
    p = ar._paired_runs(np.random.default_rng(1), R1, R2, Q, 1, 1, 0.5, 100.0, 50.0)
    x0 = [np.column_stack([z[:1, 0, 0], np.zeros(1), z[:1, 0, 1], np.zeros(1)]) for z in p.z]
    P0i = [np.diag([R[0, 0], 0.0, R[1, 1], 0.0]) for R in (p.R1, p.R2)]
    r = fusion_loop(p.z[0][:1], p.z[1][:1], x0[0], x0[1], p.F, p.H, p.Q, p.R1, p.R2, p.P0d, P0i[0], P0i[1],
                    "printed", "split", "own")
    assert np.isfinite(r.P).all() and np.isfinite(r.est).all()
    assert (np.linalg.eigvalsh(r.P) > 0).all()


@settings(max_examples=60, deadline=None)
@given(st.integers(1, 6), st.integers(0, 2**32 - 1), st.floats(-170, 5))
def test_a1_computed_part(n: int, seed: int, log_scale: float) -> None:
    """A computed semidefinite part: unchanged (the same object) without a tiny variance; otherwise those rows and
    columns are zero and the rest kept, and the input rule accepts the result."""
    from fusion._validation import computed_part

    rng = np.random.default_rng(seed)
    B = rng.standard_normal((n, n))
    scale = np.where(rng.random(n) < 0.5, 10.0 ** log_scale, 1.0)
    M = scale[:, None] * (B @ B.T) * scale[None, :]
    out = computed_part(M)
    tiny = (np.abs(np.diagonal(M)) > 0) & (np.abs(np.diagonal(M)) < MIN_VARIANCE)
    if not tiny.any():
        assert out is M
    else:
        assert (out[tiny] == 0).all() and (out[:, tiny] == 0).all()
        keep = ~tiny
        assert np.array_equal(out[np.ix_(keep, keep)], M[np.ix_(keep, keep)])
    as_semidefinite(out, n, name="P")   # accepted as an input


def test_a1_inputs_keep_the_rule() -> None:
    """The tiny-variance rule still refuses an input (P0d of fusion_loop)."""
    with pytest.raises(ValueError, match="P0d has a variance below"):
        as_semidefinite(np.diag([1e-160, 1.0]), 2, name="P0d")


# ------------------------------------------------------------------------------------------------ A2, A3


def test_a2_fruit_fly_step_targets_refuses_a_repeated_target() -> None:
    refused(lambda: ci.fruit_fly_step_targets(0, (0.5, 0.5), 2), "targets")
    refused(lambda: ci.fruit_fly_step_targets(0, (0.25, 0.5, 0.25), 2), "targets[0] and targets[2]")


def test_a3_weight_pair_names_fruit_fly_seeds() -> None:
    Q, R1, _ = ci.printed_covariances()
    refused(lambda: ci.weight_pair(R1, R1 / 9, Q, 2, 1, 2, [3, 3], runs=2, T=8.0), "fruit_fly_seeds")
    msg = refused(lambda: ci.weight_pair(R1, R1 / 9, Q, 2, 1, 2, list(range(10**5)), runs=2, T=8.0),
                  "fruit_fly_seeds")
    assert "budget" in msg


# ------------------------------------------------------------------------------------------------ A4

CONVERTERS = {"list": lambda v: v.tolist(), "tuple": lambda v: tuple(map(tuple, v.tolist())),
              "DataFrame": pd.DataFrame, "float32": lambda v: v.astype(np.float32)}


@pytest.fixture(scope="module")
def ir_case() -> tuple[Any, dict[str, np.ndarray]]:
    return ci.ir_study(0.1, 1, 3, duration=3.0)


@pytest.mark.parametrize("kind", sorted(CONVERTERS))
def test_a4_ir_table_and_figure_read_rmse_as_arrays(ir_case: Any, kind: str) -> None:
    import matplotlib.pyplot as plt

    sim, rm = ir_case
    conv = {k: CONVERTERS[kind](v) for k, v in rm.items()}
    pd.testing.assert_frame_equal(ci.ir_table(conv, sim.t, 1.0), ci.ir_table(rm, sim.t, 1.0),
                                  rtol=1e-6 if kind == "float32" else 0)
    plt.close(ci.ir_figure(sim.t, conv, None, 1.0))


def test_a4_ir_reading_numbers_reads_rmse_as_arrays() -> None:
    o = reg._objects()
    base = ci.ir_reading_numbers(o["small"], o["sim"], o["ir_rmse"])
    for kind in ("list", "DataFrame"):
        conv = {k: CONVERTERS[kind](v) for k, v in o["ir_rmse"].items()}
        assert ci.ir_reading_numbers(o["small"], o["sim"], conv) == base
    refused(lambda: ci.ir_reading_numbers(o["small"], o["sim"], {**o["ir_rmse"], ci.IR_SHOWN[0]: "x"}), "rmse[",
            TypeError)


# ------------------------------------------------------------------------------------------------ A5, A6


@pytest.fixture(scope="module")
def two_run_inputs() -> Any:
    o = reg._objects()
    Q, R1, R2 = ci.printed_covariances()
    a = ci.architecture_studies(R1, R2, Q, (1, 2), 0.0018, 2, 2, T=8.0)
    return ci.ledger_inputs(**{**o["parts"], "arch": tuple(a.values()), "arch_seeds": (1, 2)})


@pytest.mark.parametrize("name", ["ledger_values", "ev_fig4_fig7", "ev_fig8", "evidence"])
def test_a5_rule_r4_names_the_field_of_r(two_run_inputs: Any, name: str) -> None:
    msg = refused(lambda: getattr(ci, name)(two_run_inputs), "r.arch")
    assert "100" in msg and "a and b" not in msg and "argument reason" not in msg


def test_a5_record_evidence_names_runs(monkeypatch: pytest.MonkeyPatch) -> None:
    """record_evidence's rule R4 refusal names its argument runs (the comparison's own message named a, b, reason)."""
    from fusion.book.chapters.ci import studies
    from fusion.book.ledger import Comparison

    def short(rid: str, seed: int, runs: int) -> dict:   # the studies' comparison of `runs` runs, without the study
        Comparison(np.ones(runs), np.ones(runs) + 1, "a", "b", "less", "RMSE")
        return {}

    monkeypatch.setattr(studies, "_record", short)
    msg = refused(lambda: ci.record_evidence("ci-fig10-x-below-y", None, seed=5, runs=3), "runs")
    assert "100" in msg and "argument reason" not in msg


@pytest.mark.parametrize("rid", [["ci-fig10-x-below-y"], 5, None, b"ci-fig10-x-below-y"])
def test_a6_record_evidence_rid_must_be_a_string(rid: Any) -> None:
    refused(lambda: ci.record_evidence(rid), "rid", TypeError)


# ------------------------------------------------------------------------------------------------ A7, q8, q9


def test_a7_fig5_hypotheses_one_point_grid() -> None:
    t = ci.fig5_hypotheses(**kwargs("fig5_hypotheses", n_open=1))
    omega = t["ω found"]
    assert omega.iloc[1] == 1.0 and omega.iloc[4] == 1.0   # the grid k/1 on the pair and on the flat pair


def test_q9_fig5_hypotheses_budgets_n_open() -> None:
    msg = refused(lambda: ci.fig5_hypotheses(**kwargs("fig5_hypotheses", n_open=10**7)), "n_open")
    assert "budget" in msg


@pytest.mark.parametrize("evaluations, evals, per_eval", [(6000, 19900, 31.3), (1, 3.31, 188000), (23, 76.2, 8170)])
def test_q8_hypothesis_numbers_keep_three_digits(evaluations: int, evals: float, per_eval: float) -> None:
    table = ci.fig5_hypotheses(**kwargs("fig5_hypotheses"))
    g = ci.fig5_hypothesis_numbers(table, evaluations=evaluations)
    assert g["ci_h_grid_evals"] == evals and g["ci_h_per_eval_us"] == per_eval
    if evaluations == 6000:   # the book's glue: an int
        assert type(g["ci_h_grid_evals"]) is int


# ------------------------------------------------------------------------------------------------ A8


def test_a8_ir_ratio_jackknife_budget() -> None:
    rng = np.random.default_rng(1)
    refused(lambda: ci.ir_ratio(rng.random((8200, 4)) + 0.1, 1), "run_rmse")
    ratio, lo, hi = ci.ir_ratio(rng.random((2000, 4)) + 0.1, 1)   # within the budget
    assert lo <= ratio <= hi


def test_a8_ir_readings_names_runs() -> None:
    msg = refused(lambda: ci.ir_readings(0.1, 1, 10**4, duration=3.0), "runs")
    assert "jackknife" in msg


# ------------------------------------------------------------------------------------------------ q1, q4


@pytest.mark.parametrize("distance, label", [(1000.0, "1 km = distance flown"), (3000.0, "3 km = distance flown")])
def test_q1_flown_label_says_the_distance(distance: float, label: str) -> None:
    g = ci.ir_flown_numbers(**kwargs("ir_flown_numbers", distance=distance))
    flown = [c for c in g["ci_tab_ir_flown"].index if "distance flown" in str(c)]
    assert len(flown) == 1 and flown[0].startswith(label), flown


def test_q4_sensitivity_table_returns_the_floats_read() -> None:
    kw = kwargs("sensitivity_table")
    means = kw["known"][0.1]
    known = {T: {k: np.array(v) for k, v in means.items()} for T in kw["periods"]}
    _, out = ci.sensitivity_table(**{**kw, "known": known})
    for T in kw["periods"]:
        for k in ("azimuth (mrad)", "x (m)", "y (m)"):
            assert type(out[T][k]) is float and out[T][k] == float(means[k])


# ------------------------------------------------------------------------------------------------ q5, q10


def test_q5_timing_numbers_refuses_an_empty_series() -> None:
    import dataclasses

    bench = ci.timing_benchmark()
    key = next(iter(k for k in bench.per_step if k.endswith("_evaluations")))
    empty = dataclasses.replace(bench, per_step={**bench.per_step, key: ()})
    refused(lambda: ci.timing_numbers(empty), "bench.per_step")


def test_q5_timing_benchmark_missing_file_names_results(tmp_path: Path) -> None:
    msg = refused(lambda: ci.timing_benchmark(tmp_path), "results")
    assert not msg.startswith("name")


def test_q10_float32_table_glues_the_printed_numbers() -> None:
    table = valid("fruit_fly_step_values")["table"]
    as32 = table.copy()
    numeric = as32.select_dtypes("number").columns
    as32[numeric] = as32[numeric].astype(np.float32)
    g64, g32 = ci.fruit_fly_step_values(table), ci.fruit_fly_step_values(as32)
    for k, v in g64.items():
        assert g32[k] == pytest.approx(v, rel=1e-6), k
        if isinstance(v, float) and v == float(f"{v:.6g}"):   # a short decimal in the table: glued as it prints
            assert g32[k] == v, (k, g32[k], v)
