"""Fuzz 24c's bad input of chapter 05, classes AW, PC, SN, NEG/NG, PN, KN, IT and TB (issue 35).

Each reproducer of ``/work/tmp/fuzz24c/report.md`` for these classes must raise a :class:`ValueError` (a
:class:`TypeError` for a wrong type) whose message names the caller's argument, never a KeyError, an
AttributeError or an inner name (``value``), nor glue a Series, a text or an impossible sign; and valid input must
be accepted. The fixes are by class:

* AW: the split parts of ``fusion_loop``'s local filters are semidefinite by construction; the negative eigenvalues
  rounding leaves in them (9e-8 of the largest entry at the published weight 0.0033) are removed where they are
  formed, so every weight in (0, 1] is run; ``architecture_studies`` names ``fixed_omegas`` for a weight that repeats
  ``w_pub`` (it named ``printed_omegas``, not its argument);
* NEG/NG, PC, SN, PN: one sign rule for what cannot be negative (an RMSE, a NEES, a bound, a time): the shared
  readers of the chapter, ``_entries`` (mappings) and ``_frame`` (tables, ``nonnegative=``), and the per-step and
  per-run readers, refuse a negative value by name; ``pcrb_numbers`` refuses a row held twice, ``slip_numbers`` a
  table without the rows of Fig. 6 or of the averaging rules, ``path_numbers`` reads every cell by name;
* KN: ``sensitivity_table(known=...)`` is checked (a mapping of positive periods to the three means read);
* IT: scan times must increase (``ir_table``, ``ir_figure``);
* TB: ``timing_benchmark`` refuses a stored result without its per-step timings, naming ``results``.
"""

from __future__ import annotations

import copy
import json
import sys
from functools import cache
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings, strategies as st

from fusion.book.chapters import ci
from fusion.filtering.feedback import _semidefinite

sys.path.insert(0, str(Path(__file__).resolve().parent))
import test_bad_input_calls_ch05 as reg  # noqa: E402

RESULTS = Path(__file__).resolve().parents[1] / "benchmarks" / "results"


@cache
def valid(name: str) -> dict[str, Any]:
    """The registry's valid call of ``ci.<name>`` (fresh copies per test)."""
    return {k: a.value for k, a in reg.registry()["fusion.book.chapters.ci." + name].items()}


def kwargs(name: str, **over: Any) -> dict[str, Any]:
    return {**{k: copy.copy(v) for k, v in valid(name).items()}, **over}


def refused(fn: Any, arg: str, kind: Any = ValueError) -> str:
    with pytest.raises((ValueError, TypeError)) as e:
        fn()
    assert isinstance(e.value, kind), f"{type(e.value).__name__}: {e.value}"
    assert arg in str(e.value), str(e.value)
    return str(e.value)


# ---------------------------------------------------------------------------------------------------------------- AW
@pytest.mark.parametrize("w_pub", [0.0033, 1e-6, float(np.float32(0.0018))])
def test_architecture_studies_runs_every_valid_weight(w_pub: float) -> None:
    o = reg._objects()
    out = ci.architecture_studies(o["R1"], o["R2"], o["Q"], (1, 2), w_pub, 2, 2, T=8.0, fixed_omegas=(0.5,))
    assert set(out) == {ci.IDENTICAL_LABEL, ci.ANISO_LABEL}


def test_architecture_studies_names_a_repeated_weight() -> None:
    o = reg._objects()
    msg = refused(lambda: ci.architecture_studies(o["R1"], o["R2"], o["Q"], (1, 2), 0.5, 2, 2, T=8.0,
                                                  fixed_omegas=(0.5,)), "fixed_omegas[0]")
    assert "w_pub" in msg and "printed_omegas" not in msg
    refused(lambda: ci.architecture_studies(o["R1"], o["R2"], o["Q"], (1, 2), 0.2, 2, 2, T=8.0,
                                            fixed_omegas=(0.5, 0.5)), "fixed_omegas[1]")


@settings(max_examples=60, deadline=None)
@given(st.integers(2, 5), st.integers(1, 4), st.floats(-1e-6, 1e-6), st.floats(1e-3, 1e4), st.integers(0, 2**32 - 1))
def test_semidefinite_removes_only_rounding_negative_eigenvalues(n: int, rank: int, eps: float, scale: float,
                                                                 seed: int) -> None:
    """A semidefinite matrix of low rank, perturbed by a relative ``eps`` along its null space: the result is
    semidefinite, within that perturbation of the input, and the input itself when it had no negative eigenvalue."""
    rng = np.random.default_rng(seed)
    rank = min(rank, n - 1)
    B = rng.normal(size=(n, rank))
    M = scale * B @ B.T / np.abs(B @ B.T).max()
    null = np.linalg.svd(B.T)[2][-1]
    M = M + eps * scale * np.outer(null, null)
    out = _semidefinite(M)
    lam = np.linalg.eigh(0.5 * (M + M.T))[0]   # the decomposition _semidefinite judges by
    if lam[0] >= 0.0:
        assert out is M
    else:
        assert np.linalg.eigvalsh(out)[0] >= -1e-12 * scale
        assert np.abs(out - M).max() <= 2 * abs(lam[0]) + 1e-12 * scale


# ------------------------------------------------------------------------------------------------------ NEG/NG, PC
NEGATED = [("nees_numbers", "nees"), ("nees_table", "nees"), ("nees_start_numbers", "exact"),
           ("nees_start_numbers", "true_start"), ("paired_numbers", "paired"), ("paired_numbers", "paired_fig6"),
           ("path_numbers", "rows"), ("path_period_table", "rows"), ("printed_equation_numbers", "checks"),
           ("rmse_numbers", "leg_rmse"), ("rmse_numbers", "leg_floor"), ("rmse_figure", "floor"),
           ("slip_numbers", "variants"), ("slip_numbers", "slip"), ("variant_numbers", "variants"),
           ("variants_table", "variants"), ("timing_table", "m"), ("pcrb_numbers", "pcrb"),
           ("ir_numbers", "ir_table"), ("sensitivity_numbers", "sens_table"), ("ir_table", "rmse"),
           ("ir_figure", "rmse"), ("ir_figure", "bound")]


@pytest.mark.parametrize(("name", "arg"), NEGATED)
def test_an_impossible_sign_is_refused_by_name(name: str, arg: str) -> None:
    kw = kwargs(name)
    kw[arg] = reg._negated(kw[arg])
    msg = refused(lambda: getattr(ci, name)(**kw), arg)
    assert "non-negative" in msg


def test_pcrb_numbers_reads_numbers_held_once() -> None:
    kw = kwargs("pcrb_numbers")
    pcrb = kw["pcrb"]
    refused(lambda: ci.pcrb_numbers(pd.concat([pcrb, pcrb.iloc[:1]]), kw["q_printed"]), "pcrb")
    text = pcrb.copy()
    text[text.columns[0]] = text[text.columns[0]].astype(object)
    text.iloc[0, 0] = "12"
    refused(lambda: ci.pcrb_numbers(text, kw["q_printed"]), "pcrb", TypeError)
    assert all(isinstance(v, (float, np.floating)) for v in ci.pcrb_numbers(**kw).values())


# ------------------------------------------------------------------------------------------------------------ SN, PN
def test_slip_numbers_needs_both_groups_of_rows() -> None:
    kw = kwargs("slip_numbers")
    slip = kw["slip"]
    fig6 = slip.index.get_level_values(0).str.startswith("Fig. 6")
    for bad in (slip[fig6], slip[~fig6], slip.set_axis([str(i) for i in slip.index], axis=0)):
        refused(lambda bad=bad: ci.slip_numbers(**{**kw, "slip": bad}), "slip")


@pytest.mark.parametrize(("cell", "kind"), [(np.nan, ValueError), ("12", TypeError), (-1.0, ValueError)])
def test_path_numbers_names_the_cell(cell: Any, kind: type[Exception]) -> None:
    rows = copy.deepcopy(valid("path_numbers")["rows"])
    key = next(iter(rows))
    rows[key]["CI = average (m)"] = cell
    refused(lambda: ci.path_numbers(rows), "rows[", kind)
    refused(lambda: ci.path_period_table(rows), "rows[", kind)


# ---------------------------------------------------------------------------------------------------------------- KN
def _means() -> dict[str, float]:
    return dict(valid("sensitivity_table")["known"][0.1])


BASE = dict(periods=(0.1, 0.5), seed=1, runs=2, duration=3.0, t_min=1.0)


KNOWN = {"means empty": lambda m: {0.1: {}}, "a text": lambda m: "x", "a list": lambda m: [(0.1, m)],
         "means a text": lambda m: {0.1: "abc"}, "means none": lambda m: {0.1: None},
         "a text period": lambda m: {"a": m}, "a NaN period": lambda m: {np.nan: m},
         "a negative period": lambda m: {-0.1: m}, "an azimuth less": lambda m: reg._drop_key(m, "azimuth (mrad)")}


@pytest.mark.parametrize("label", KNOWN)
def test_sensitivity_table_checks_known(label: str) -> None:
    known = KNOWN[label](_means())
    if label == "an azimuth less":
        known = {0.1: known}
    refused(lambda: ci.sensitivity_table(**BASE, known=known), "known", (ValueError, TypeError))


@pytest.mark.parametrize("value", [np.nan, -0.1, "12"])
def test_sensitivity_table_checks_the_known_means(value: Any) -> None:
    means = {k: value for k in _means()}
    refused(lambda: ci.sensitivity_table(**BASE, known={0.1: means}), "known[0.1]", (ValueError, TypeError))


def test_sensitivity_table_uses_known_means() -> None:
    means = _means()
    table, out = ci.sensitivity_table(**BASE, known={0.1: means})
    assert out[0.1] == means


# ---------------------------------------------------------------------------------------------------------------- IT
@settings(max_examples=30, deadline=None)
@given(st.data())
def test_scan_times_must_increase(data: st.DataObject) -> None:
    kw = kwargs("ir_table")
    t = np.array(kw["t"], dtype=float)
    i = data.draw(st.integers(1, t.size - 1))
    bad = t.copy()
    bad[i] = bad[i - 1] - data.draw(st.sampled_from([0.0, 1e-3, 1.0]))
    msg = refused(lambda: ci.ir_table(kw["rmse"], bad, kw["t_min"]), "t must increase")
    assert "bound" not in msg
    f = kwargs("ir_figure")
    refused(lambda: ci.ir_figure(bad, f["rmse"], f["bound"], f["t_min"]), "t must increase")


def test_ir_table_reversed_times_refused() -> None:
    kw = kwargs("ir_table")
    refused(lambda: ci.ir_table(kw["rmse"], kw["t"][::-1].copy(), 1.0), "t")
    refused(lambda: ci.ir_table(kw["rmse"], np.zeros_like(kw["t"]), 0.0), "t")


# ---------------------------------------------------------------------------------------------------------------- TB
@pytest.mark.parametrize("per_step", [None, [1.0, 2.0]])
def test_timing_benchmark_needs_per_step(tmp_path: Path, per_step: Any) -> None:
    rec = json.loads((RESULTS / "ci.json").read_text())
    rec.pop("per_step")
    if per_step is not None:
        rec["per_step"] = per_step
    (tmp_path / "ci.json").write_text(json.dumps(rec))
    refused(lambda: ci.timing_benchmark(tmp_path), "results")
    assert ci.timing_benchmark().per_step   # the stored one holds it
