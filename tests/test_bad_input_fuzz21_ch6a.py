"""Fuzz 21b, chapter 06 helpers: classes E, O, N, K, X, A and the debatable d1.

Bad input is refused by a ValueError naming the argument (TypeError for a wrong type), a malformed file by a
ValueError naming the argument and the file; valid documented input keeps working (each class has a test that the
documented calls still give their numbers).
"""

from __future__ import annotations

import dataclasses
import json
import re
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from fusion._validation import as_covariance, as_covariances, frame_slice
from fusion.book.chapters import chernoff as chf
from fusion.book.chapters import chernoff_criteria as cc
from fusion.book.chapters import chernoff_steps as cs
from fusion.book.ledger import MIN_RUNS
from fusion.scenarios import fusion_networks as fn

ROOT = Path(__file__).resolve().parents[1]


def _names(exc: pytest.ExceptionInfo, arg: str) -> bool:
    return re.search(rf"(?<![A-Za-z0-9_]){re.escape(arg)}(?![A-Za-z0-9_])", str(exc.value)) is not None


def _refused(call, kind: type[Exception], arg: str) -> None:
    with pytest.raises(kind) as exc:
        call()
    assert _names(exc, arg), str(exc.value)


# --------------------------------------------------------------------------- E: exponent_rule's means and covs
_M = np.random.default_rng(0).normal(size=(2, 3, 2))
_P = np.tile(np.eye(2), (2, 3, 1, 1))


def _cov(entry: list) -> np.ndarray:
    P = _P.copy()
    P[0, 1] = entry
    return P


@pytest.mark.parametrize("rule, means, covs, kind, arg", [
    ("ci_gaussian", _M, _P * 0, ValueError, "covs"),                                  # E1 singular
    ("ci_gaussian", _M, _cov([[1, 2], [2, 1]]), ValueError, "covs"),                  # E2 indefinite
    ("ci_det", _M, _cov([[1, 0.5], [0, 1]]), ValueError, "covs"),                     # E3 asymmetric
    ("ci_gaussian", np.where(_M > 0, np.nan, _M), _P, ValueError, "means"),           # E4 NaN
    ("ci_det", _M, np.full_like(_P, np.inf), ValueError, "covs"),                     # E5 inf
    ("ci_gaussian", "abc", _P, TypeError, "means"),                                   # E6 text
    ("ci_gaussian", _M + 1j, _P, TypeError, "means"),                                 # E7 complex
    ("ci_gaussian", _M[:, :0], _P[:, :0], ValueError, "means"),                       # E8 M = 0
    ("ci_det", _M[:, :0], _P[:, :0], ValueError, "means"),                            # E9 M = 0
    ("ci_gaussian", _M[:, :, :0], _P[:, :, :0, :0], ValueError, "means"),             # E10 d = 0
    ("ci_gaussian", _M, _P * 1e300, ValueError, "covs"),                              # E11 beyond 1e150
    ("ci_gaussian", _M[:0], _P[:0], ValueError, "means"),                             # B = 0
    ("ci_gaussian", _M, _P[:, :2], ValueError, "covs"),                               # shapes disagree
])
def test_exponent_rule_refuses_bad_means_and_covs(rule, means, covs, kind, arg) -> None:
    with np.errstate(invalid="ignore"):
        _refused(lambda: cc.exponent_rule(rule, means, covs), kind, arg)


def test_exponent_rule_names_the_matrix_at_fault() -> None:
    with pytest.raises(ValueError, match=r"covs\[0, 1\] must be positive definite"):
        cc.exponent_rule("ci_gaussian", _M, _cov([[1, 2], [2, 1]]))


@settings(max_examples=40, deadline=None)
@given(B=st.integers(1, 3), M=st.integers(1, 4), d=st.integers(1, 3), seed=st.integers(0, 2**32 - 1),
       rule=st.sampled_from(cc.GAUSSIAN_RULES))
def test_exponent_rule_accepts_valid_covariances_and_agrees_with_the_one_by_one_rule(B, M, d, seed, rule) -> None:
    """Random SPD stacks pass the batched rule unchanged (as the one-matrix rule passes each), and the exponents lie
    on the simplex; one matrix made indefinite is refused by its index."""
    rng = np.random.default_rng(seed)
    A = rng.normal(size=(B, M, d, d))
    P = A @ np.swapaxes(A, -1, -2) + 0.5 * np.eye(d)
    P = 0.5 * (P + np.swapaxes(P, -1, -2))
    np.testing.assert_array_equal(as_covariances(P, dim=d), P)
    for idx in np.ndindex(B, M):
        np.testing.assert_array_equal(as_covariance(P[idx], dim=d), P[idx])
    e = cc.exponent_rule(rule, rng.normal(size=(B, M, d)), P)
    assert e.shape == (B, M) and np.all(np.isfinite(e))
    if rule != "naive_product":
        np.testing.assert_allclose(e.sum(axis=1), 1.0, atol=1e-6)
    b, m = int(rng.integers(B)), int(rng.integers(M))
    bad = P.copy()
    bad[b, m] = -bad[b, m]
    with pytest.raises(ValueError, match=rf"covs\[{b}, {m}\] must be positive definite"):
        as_covariances(bad, dim=d)


# --------------------------------------------------------------------------- O, N: the oracle and network_mse
@pytest.fixture(scope="module")
def study() -> fn.NetworkStudy:
    scs = fn.premise_scenarios()
    return fn.run_network_study(scs[list(scs)[0]], 1, 20)


@pytest.mark.parametrize("step, kind", [
    (0.0, ValueError), (2.0, ValueError), (float("inf"), ValueError), (float("nan"), ValueError),
    (-0.02, ValueError), ("0.02", TypeError), (0.7, ValueError), (0.3, ValueError), (True, TypeError),
    (1e-7, ValueError),                                                                  # O10: hung (a 5e13-point grid)
])
def test_oracle_exponents_refuses_a_bad_step(study, step, kind) -> None:
    _refused(lambda: chf.oracle_exponents(study, step), kind, "step")


def test_oracle_exponents_refuses_a_non_study() -> None:
    _refused(lambda: chf.oracle_exponents("x"), TypeError, "st")


@pytest.mark.parametrize("step", [1.0, 0.5, 0.25, 0.1, 0.05, 0.02, np.float64(0.02), 1 / 3,
                                  np.float32(0.1), np.float32(0.02), np.array(np.float32(0.1))])   # fuzz 22b R
def test_oracle_exponents_keeps_every_step_that_divides_one(study, step) -> None:
    """Valid steps keep working, and the exponents lie on the grid of ``step`` (0.7 used to give the grid of 1)."""
    e, mse = chf.oracle_exponents(study, step)
    n = round(1 / float(step))
    np.testing.assert_allclose(e * n, np.round(e * n), atol=1e-9)
    assert e.sum() == pytest.approx(1.0) and mse.shape == (study.runs,)


@pytest.mark.parametrize("factor, estimates, kind", [
    (np.nan, None, ValueError), (1e200, None, ValueError), (None, "x", TypeError), (np.inf, None, ValueError),
])
def test_network_mse_refuses_bad_estimates(study, factor, estimates, kind) -> None:
    e = study.estimates["exact_posterior"] * factor if estimates is None else estimates
    _refused(lambda: cc.network_mse(study, e), kind, "estimates")


def test_network_mse_is_the_study_mse(study) -> None:
    np.testing.assert_array_equal(cc.network_mse(study, study.estimates["exact_posterior"]),
                                  study.mse("exact_posterior"))


# --------------------------------------------------------------------------- K: the tracking helpers
@pytest.fixture(scope="module")
def scenario_and_truths():
    sc = chf.study_scenario()
    return sc, cs.study_truths(sc, 1, 3)


@pytest.mark.parametrize("call, kind, arg", [
    (lambda sc: chf.message_sizes(sc, -3), ValueError, "d"),
    (lambda sc: chf.message_sizes(sc, 2.5), TypeError, "d"),
    (lambda sc: chf.message_sizes(sc, 0), ValueError, "d"),
    (lambda sc: chf.message_sizes("x"), TypeError, "sc"),
    (lambda sc: chf.scenario_values("x", 100), TypeError, "sc"),
    (lambda sc: chf.guarded_scenario("x"), TypeError, "sc"),
])
def test_tracking_helpers_refuse_bad_input(scenario_and_truths, call, kind, arg) -> None:
    _refused(lambda: call(scenario_and_truths[0]), kind, arg)


def test_tracking_helpers_keep_their_values(scenario_and_truths) -> None:
    sc = scenario_and_truths[0]
    assert chf.message_sizes(sc, 2) == {"chf_msg_gm": sc.n_components * 6, "chf_msg_pf": sc.n_particles * 3,
                                        "chf_msg_d": 2, "chf_msg_s": sc.n_components}
    assert chf.scenario_values(sc, 7)["chf_runs"] == 7
    assert chf.guarded_scenario(sc).guard == chf.COLLAPSE_FRACTION


@pytest.mark.parametrize("frames, kind", [
    (slice(0, 0), ValueError), (slice(1000, None), ValueError), (slice(0, 5, 0), ValueError),
    (slice(0, "a"), TypeError), ((4, None), TypeError), (slice(5, 2), ValueError),
])
def test_single_sensor_crb_refuses_frames_that_select_nothing(scenario_and_truths, frames, kind) -> None:
    sc, truths = scenario_and_truths
    _refused(lambda: cs.single_sensor_crb(sc, truths, frames), kind, "frames")


def test_single_sensor_crb_keeps_any_window_that_selects_a_frame(scenario_and_truths) -> None:
    sc, truths = scenario_and_truths
    K = truths.shape[1]
    whole = cs.single_sensor_crb(sc, truths, slice(None))
    last = cs.single_sensor_crb(sc, truths, slice(-1, None))
    assert cs.single_sensor_crb(sc, truths, slice(K - 1, K + 10)) == last
    assert all(np.isfinite(v) and v > 0 for v in (*whole.values(), *last.values()))


@settings(max_examples=200, deadline=None)
@given(length=st.integers(0, 12), start=st.none() | st.integers(-15, 15), stop=st.none() | st.integers(-15, 15),
       step=st.none() | st.integers(-4, 4))
def test_frame_slice_refuses_exactly_the_slices_that_select_no_frame(length, start, stop, step) -> None:
    s = slice(start, stop, step)
    if step == 0:
        with pytest.raises(ValueError, match="frames"):
            frame_slice(s, "frames", length)
        return
    selected = list(range(length))[s]
    if not selected:
        with pytest.raises(ValueError, match="frames .* selects no frame"):
            frame_slice(s, "frames", length)
    else:
        assert list(frame_slice(s, "frames", length)) == selected


# --------------------------------------------------------------------------- X: files named by an argument
def _write(tmp_path: Path, name: str, text: str) -> Path:
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    return p


@pytest.mark.parametrize("content, kind", [
    (None, ValueError),                                                           # X1 missing file
    ("dir", ValueError),                                                          # X2 a directory
    ("not json", ValueError),                                                     # X3
    ('{"cells": 5}', ValueError),                                                 # X4
    ("[1, 2]", ValueError),
    ('{"cells": [{"cell_type": "markdown", "source": 5}]}', ValueError),
    ('{"cells": [5]}', ValueError),
    (5, TypeError),                                                               # X5
])
def test_appendix_referenced_refuses_a_bad_notebook(tmp_path, content, kind) -> None:
    if content is None:
        nb = tmp_path / "missing.ipynb"
    elif content == "dir":
        nb = tmp_path
    elif isinstance(content, str):
        nb = _write(tmp_path, "bad.ipynb", content)
    else:
        nb = content
    _refused(lambda: cc.appendix_referenced({"a": 1}, nb), kind, "notebook")


def test_appendix_referenced_reads_a_notebook(tmp_path) -> None:
    nb = _write(tmp_path, "ok.ipynb", json.dumps({"cells": [
        {"cell_type": "code", "source": "{glue}`b`"},
        {"cell_type": "markdown", "source": ["x {glue:text}`a:.2f` ", "{glue}`c`"]},
        {"cell_type": "markdown", "source": "and {glue}`d`"}]}))
    assert cc.appendix_referenced({"a": 1, "b": 2, "c": 3, "d": 4, "e": 5}, str(nb)) == {"a": 1, "c": 3, "d": 4}
    assert cc.appendix_referenced({"chf_crit_chain_ci_det_self": 1.0, "chf_nobody_reads_this": 2.0}) == {
        "chf_crit_chain_ci_det_self": 1.0}


_BENCH = ROOT / "benchmarks" / "results" / "chernoff.json"


def _current(**changes) -> dict:
    rec = json.loads(_BENCH.read_text(encoding="utf-8"))
    assert rec["schema"] == chf.BENCH_SCHEMA
    return rec | changes


@pytest.mark.parametrize("record", [
    None,                                                                                 # X6 missing file
    [1, 2],                                                                               # X7 a JSON list
    {"schema": chf.BENCH_SCHEMA},                                                          # X8 no measurements
    "X9",                                                                                 # a stage without what
    "no-em",                                                                              # a stage missing
    "no-key",                                                                             # a timing missing
    "runs",                                                                               # runs not an integer
    "value",                                                                              # a value not a number
])
def test_benchmark_cost_refuses_a_malformed_record(tmp_path, record) -> None:
    if record is None:
        path = tmp_path / "missing.json"
    else:
        if record == "X9":
            record = _current(measurements=[{"stage": "zz"}])
        elif record == "no-em":
            rec = _current()
            record = rec | {"measurements": [m for m in rec["measurements"] if m.get("stage") != "em"]}
        elif record == "no-key":
            rec = _current()
            record = rec | {"measurements": [m for m in rec["measurements"] if m.get("key") != "identical"]}
        elif record == "runs":
            record = _current(runs="100")
        elif record == "value":
            rec = _current()
            record = rec | {"measurements": [m | {"value": "1"} if m.get("stage") == "em" else m
                                             for m in rec["measurements"]]}
        path = _write(tmp_path, "bench.json", json.dumps(record))
    _refused(lambda: chf.benchmark_cost(path), ValueError, "path")
    _refused(lambda: chf.benchmark_cost(5), TypeError, "path")


def test_benchmark_cost_reads_the_stored_and_an_old_record(tmp_path) -> None:
    table, values = chf.benchmark_cost(_BENCH)
    assert values["chf_bench_current"] is True and len(table) > 0
    assert chf.benchmark_cost(str(_BENCH))[1] == values
    old = _write(tmp_path, "old.json", json.dumps({"schema": 1, "date": "2020-01-02"}))
    table, values = chf.benchmark_cost(old)
    assert values["chf_bench_current"] is False and len(table) == 0 and values["chf_bench_date"] == "2020-01-02"


# --------------------------------------------------------------------------- A: short studies and the reason
@pytest.fixture(scope="module")
def short_networks() -> dict:
    scs = {**fn.premise_scenarios(), **fn.redundancy_scenarios()}
    small = {k: dataclasses.replace(scs[k], n_particles=40, n_samples=40, n_components=2, em_iterations=2, stages=1)
             for k in cc.CRITERIA_NETWORKS}
    return {k: fn.run_network_study(small[k], 1, 6) for k in cc.CRITERIA_NETWORKS}


_TABLES = {"premise_table": lambda s, **kw: chf.premise_table(s, **kw),
           "premise_values": lambda s, **kw: chf.premise_values(s, **kw),
           "premise_robust_values": lambda s, **kw: chf.premise_robust_values(s, **kw),
           "premise_figure": lambda s, **kw: chf.premise_figure(s, **kw),
           "criteria_values": lambda s, **kw: cc.criteria_values(s, chf.PREMISE_LABELS, **kw),
           "baseline_table": lambda s, **kw: cc.baseline_table(s, chf.PREMISE_LABELS, **kw)}


@pytest.mark.parametrize("name", list(_TABLES))
def test_network_tables_refuse_short_studies_by_name_and_take_a_reason(short_networks, name) -> None:
    """A1-A4: the refusal names ``studies``, the minimum and the argument ``reason``, which each function takes."""
    with pytest.raises(ValueError) as exc:
        _TABLES[name](short_networks)
    msg = str(exc.value)
    assert _names(exc, "studies") and str(MIN_RUNS) in msg and "reason" in msg and "a and b" not in msg
    assert _TABLES[name](short_networks, reason="test: a small study") is not None
    _refused(lambda: _TABLES[name](short_networks, reason=5), TypeError, "reason")


# --------------------------------------------------------------------------- d1: nested_values' repeated ratios
@pytest.mark.parametrize("ks", [(2.0, 2.0), (2, 2.0), [10.0, 3.0, np.float64(10.0)]])
def test_nested_values_refuses_a_repeated_ratio(ks) -> None:
    _refused(lambda: chf.nested_values(ks), ValueError, "ks")


def test_nested_values_keeps_distinct_ratios() -> None:
    v = chf.nested_values((10.0, 2.0))
    assert v["chf_nest_k0"] == 10.0 and v["chf_nest_k1"] == 2.0 and v["chf_nest_err"] < 1e-6
