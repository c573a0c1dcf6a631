"""Fuzz 24b, chapter 06 (first half): classes SS, CC, TV, BC, SZ and the debatable D2, D6.

Bad input is refused by a ValueError naming the argument (TypeError for a wrong type), by its place in a record or
file; valid documented input keeps working and gives the numbers its definition gives (an exact reference where a
closed form lost them to rounding, results independent of the units).
"""

from __future__ import annotations

import copy
import json
import re
from fractions import Fraction
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from fusion.book.chapters import chernoff as chc
from fusion.book.chapters import chernoff_first_order as cfo
from fusion.estimates import chernoff as ch

ROOT = Path(__file__).resolve().parents[1]
REC = json.loads(chc.STONESOUP_RECORD.read_text(encoding="utf-8"))


def _refused(call: Any, kind: type[Exception], arg: str) -> None:
    with pytest.raises(kind) as exc:
        call()
    assert re.search(rf"(?<![A-Za-z0-9_]){re.escape(arg)}", str(exc.value)), str(exc.value)


def _rec(change: Any) -> dict[str, Any]:
    r = copy.deepcopy(REC)
    change(r)
    return r


# --------------------------------------------------------------------------- SS: stonesoup_check's record
def _set(path: tuple, value: Any) -> Any:
    def change(r: dict[str, Any]) -> None:
        for k in path[:-1]:
            r = r[k]
        r[path[-1]] = value
    return change


_INDEFINITE = [[1.0, 2.0], [2.0, 1.0]]


@pytest.mark.parametrize(("change", "kind", "arg"), [
    (lambda r: r.update(rows=[x for x in r["rows"] if x["omega"] != 0.8]), ValueError, "record['rows']"),  # SS1
    (lambda r: r.update(rows=iter(r["rows"])), TypeError, "record['rows']"),                                # SS7
    (lambda r: r.update(rows=np.array(r["rows"])), TypeError, "record['rows']"),
    (_set(("stonesoup_version",), None), TypeError, "record['stonesoup_version']"),                         # SS6
    (_set(("stonesoup_version",), float("nan")), TypeError, "record['stonesoup_version']"),
    (_set(("stonesoup_version",), ["1.9"]), TypeError, "record['stonesoup_version']"),
    (_set(("stonesoup_version",), " "), ValueError, "record['stonesoup_version']"),
    (_set(("measurement", "covariance"), _INDEFINITE), ValueError, "record['measurement']['covariance']"),  # SS5
    (_set(("prediction", "covariance"), _INDEFINITE), ValueError, "record['prediction']['covariance']"),
    (_set(("detection_case", "detection_covariance"), _INDEFINITE), ValueError,
     "record['detection_case']['detection_covariance']"),
])
def test_stonesoup_check_refuses_a_record_by_the_place_of_its_fault(change: Any, kind: type, arg: str) -> None:
    _refused(lambda: chc.stonesoup_check(_rec(change)), kind, arg)


def _consistent_record(scale: float, omegas: list[float]) -> dict[str, Any]:
    """A record whose 'Stone Soup' outputs are exact: V = A/ω + B/(1−ω) and our fusion, in units of ``scale``."""
    A = np.array([[2.0, 0.3], [0.3, 1.0]]) * scale**2
    B = np.array([[1.0, -0.2], [-0.2, 3.0]]) * scale**2
    a, b = np.array([1.0, 2.0]) * scale, np.array([0.5, -1.0]) * scale
    rows = []
    for w in omegas:
        f = ch.chernoff_fuse_gaussians(np.stack([a, b]), np.stack([A, B]), [w, 1 - w])
        rows.append({"omega": w, "innovation_covariance": (A / w + B / (1 - w)).tolist(),
                     "posterior_mean": f.x.tolist(), "posterior_covariance": f.P.tolist()})
    return {"stonesoup_version": "synthetic", "measurement": {"mean": a.tolist(), "covariance": A.tolist()},
            "prediction": {"mean": b.tolist(), "covariance": B.tolist()}, "rows": rows}


@settings(max_examples=30, deadline=None)
@given(e=st.integers(-60, 60), w=st.floats(1e-12, 1 - 1e-9))
def test_stonesoup_check_finds_the_curvature_in_any_units_and_at_any_omega(e: int, w: float) -> None:
    """SS2/SS3: the finite-difference step follows the scale, so V is found (difference 0.0 at 3 digits) whatever
    the units (an absolute step of 1e-3 gave 0.449 instead of 0.491 at ×3e3, LinAlgError at ×1e4 and at ω 1e-12)."""
    table, _ = chc.stonesoup_check(_consistent_record(10.0**e, [0.8, w]))
    assert (table.iloc[:, 0] == 0.0).all(), table


def test_stonesoup_check_with_zero_means_gives_a_finite_difference() -> None:
    """SS4: our fused mean 0 against a recorded non-zero one is a relative difference of 1 (to the larger norm),
    not inf; two zero means differ by 0."""
    def zero(r: dict[str, Any]) -> None:
        r["measurement"]["mean"] = [0.0, 0.0]
        r["prediction"]["mean"] = [0.0, 0.0]
    _, v = chc.stonesoup_check(_rec(zero))
    assert v["chf_ss_post"] == 1.0 and v["chf_ss_det_post"] == 1.0
    rec = _consistent_record(1.0, [0.8])
    rec["measurement"]["mean"] = rec["prediction"]["mean"] = rec["rows"][0]["posterior_mean"] = [0.0, 0.0]
    assert chc.stonesoup_check(rec)[1]["chf_ss_post"] == 0.0


def test_stonesoup_check_keeps_valid_records() -> None:
    """Rows as a tuple and a version string stay valid; the stored record gives its numbers."""
    _, v = chc.stonesoup_check(_rec(lambda r: r.update(rows=tuple(r["rows"]))))
    assert v["chf_ss_version"] == REC["stonesoup_version"] and v["chf_ss_v_08"] > 0.1


# --------------------------------------------------------------------------- CC: nested_gaussian_weight near 1
_G = [Fraction(1)]
for _j in range(1, 41):
    _G.append(-sum(_G[_j - m] * Fraction((-1) ** m, m + 1) for m in range(1, _j + 1)))


def _exact_weight(k: float) -> float:
    """1/ln k − 1/(k−1) at the float k, by Gregory's series in exact fractions (40 terms: error below u^40)."""
    u = Fraction(k) - 1
    return float(sum(_G[n] * u ** (n - 1) for n in range(1, 41)))


@settings(max_examples=200, deadline=None)
@given(u=st.floats(2.2e-16, 0.05))
def test_nested_gaussian_weight_is_exact_near_one(u: float) -> None:
    """CC1: k = 1 + 2.2e-16 gave 1.0 and 1 + 1e-15 gave 0.375 (exact 0.5): the closed form cancelled."""
    k = 1.0 + u
    if k == 1.0:
        return
    got = float(chc.nested_gaussian_weight(k))
    assert abs(got - _exact_weight(k)) <= 1e-13, (k, got, _exact_weight(k))


def test_nested_values_near_one_glue_the_exact_weight() -> None:
    v = chc.nested_values((1 + 1e-15, 2.0))
    assert v["chf_nest_w0"] == 0.5 and v["chf_nest_err"] < 1e-3


# --------------------------------------------------------------------------- TV: impossible RMSEs
@pytest.fixture(scope="module")
def table() -> Any:
    from test_bad_input_calls_ch06 import _o
    return _o()["table"]


def test_table_values_refuses_zero_and_negative_rmses(table: Any) -> None:
    _refused(lambda: chc.table_values(table * 0), ValueError, "table")                          # TV1
    neg = table.mask(np.zeros(table.shape, bool) | (np.arange(table.shape[0])[:, None] == 1), -5.0)
    _refused(lambda: chc.table_values(neg), ValueError, "table")                                # TV2
    import pandas as pd
    with pytest.raises(ValueError, match="more than once"):
        chc.table_values(pd.concat([table.iloc[:1], table]))
    assert chc.table_values(table)["chf_ratio_local"] > 0                                        # valid: still read


def _read_cells(table: Any) -> list[tuple[Any, Any]]:
    """The cells table_values reads: every method's late RMSE, the CRB's, and the NEES of its NEES rows."""
    from fusion.book.chapters.chernoff import tracking as tr
    from fusion.book.style import METHOD_LABELS
    cells = [(METHOD_LABELS[k], tr.RMSE_LATE) for k in tr.METHODS if METHOD_LABELS[k] in table.index]
    # the late NEES column and the naive row are labelled from the study (its frames and nodes: fuzz 27b D3)
    late = next(c for c in table.columns if str(c).startswith("mean NEES (4-D), frame"))
    nodes = sum(METHOD_LABELS[k] in table.index for k in tr.METHODS if k.startswith("local"))
    return cells + [(tr.CRB_ROW, tr.RMSE_LATE)] + [(tr._row_label(k, nodes), late) for k in tr._NEES_KEYS]


@settings(max_examples=25, deadline=None)
@given(i=st.integers(0, 10**6), x=st.sampled_from([0.0, -0.0, -1e-300, -3.0]))
def test_table_values_refuses_a_non_positive_cell_it_reads(table: Any, i: int, x: float) -> None:
    cells = _read_cells(table)
    row, col = cells[i % len(cells)]
    t = table.copy()
    t.loc[row, col] = x
    _refused(lambda: chc.table_values(t), ValueError, "table")


# --------------------------------------------------------------------------- BC, D6: the benchmark file
BENCH = json.loads((ROOT / "benchmarks" / "results" / "chernoff.json").read_text(encoding="utf-8"))


def _stage(d: dict[str, Any], stage: str) -> dict[str, Any]:
    return next(m for m in d["measurements"] if m.get("stage") == stage)


def _key(d: dict[str, Any], key: str) -> dict[str, Any]:
    return next(m for m in d["measurements"] if m.get("key") == key)


@pytest.mark.parametrize("change", [
    lambda d: d["measurements"].append(dict(_stage(d, "em"))),                  # BC1 a stage twice
    lambda d: d["measurements"].append({**_key(d, "identical"), "value": 0}),   # D6 a key twice
    lambda d: d.update(load_average=[]),                                        # BC2
    lambda d: d.update(load_average=0.5),
    lambda d: d.update(load_average="high"),
    lambda d: d.update(load_average=[-1.0]),
    lambda d: _stage(d, "reference").update(value=0.0),                         # BC3
    lambda d: _stage(d, "em").update(value=-5.0),
    lambda d: _key(d, "loop_seconds").update(value=-154.0),
    lambda d: _key(d, "pso_over_slsqp").update(value=0.0),
    lambda d: d.update(workers=0),                                              # BC4
    lambda d: d.update(workers=-3),
    lambda d: d.update(runs=10**30),                                            # D6
    lambda d: d.update(schema=float(d["schema"])),
])
def test_benchmark_cost_refuses_a_file_whose_numbers_it_would_glue_as_nonsense(change: Any, tmp_path: Path) -> None:
    d = copy.deepcopy(BENCH)
    change(d)
    p = tmp_path / "chernoff.json"
    p.write_text(json.dumps(d), encoding="utf-8")
    _refused(lambda: chc.benchmark_cost(p), ValueError, "path")


def test_benchmark_cost_keeps_the_stored_file_and_an_absent_load_average(tmp_path: Path) -> None:
    _, v = chc.benchmark_cost(ROOT / "benchmarks" / "results" / "chernoff.json")
    assert v["chf_bench_current"] and "load average" in v["chf_bench_text"]
    d = {k: x for k, x in BENCH.items() if k not in ("load_average", "workers")}
    p = tmp_path / "chernoff.json"
    p.write_text(json.dumps(d), encoding="utf-8")
    assert "load average ?" in chc.benchmark_cost(p)[1]["chf_bench_text"]


def test_every_stored_benchmark_file_passes_the_shared_measurement_rule() -> None:
    """D6/BC3's shared rule (no repeated key, positive durations) refuses none of the stored results."""
    from fusion.book.benchmarks import load_benchmark
    for f in sorted((ROOT / "benchmarks" / "results").glob("*.json")):
        load_benchmark(f.stem)


# --------------------------------------------------------------------------- SZ: arrays held at once
@pytest.fixture(scope="module")
def study() -> Any:
    from test_bad_input_calls_ch06 import _o
    return _o()


def test_sizes_beyond_the_memory_budget_are_refused_by_name(study: Any) -> None:
    """SZ1/SZ2: one array within the budget but the several held at once beyond it raised MemoryError."""
    _refused(lambda: chc.gm_yardstick(np.random.default_rng(0), study["guarded"], study["sc"], 10**6), ValueError, "sets")
    _refused(lambda: chc.design_study(study["sc"], 1, 2, 10**7, 1), ValueError, "n_initial")


def test_the_book_sizes_stay_within_the_budget() -> None:
    """The chapter's own scenario, runs and design sizes are not refused by the held-arrays rule."""
    from fusion.scenarios.range_bearing import RUN_BLOCK, _block_allocation
    sc = chc.study_scenario()
    _block_allocation(sc, RUN_BLOCK, "runs")
    import dataclasses
    _block_allocation(dataclasses.replace(sc, n_initial=10_000), RUN_BLOCK, "runs")


# --------------------------------------------------------------------------- D2: a coarse quadrature grid
def test_sigma_first_order_problem_coarse_grid_is_valid_and_converges() -> None:
    """D2 (decided: documented): n = 2 stays valid (a resolution the function cannot judge) and returns a valid
    result; the quadrature's ω* settles as the grid is refined, which is what "exact" means in the docstring."""
    a, b = cfo.random_two_mixtures(np.random.default_rng(5))
    coarse = cfo.sigma_first_order_problem(a, b, 2)
    assert 0.0 <= coarse.omega_exact <= 1.0
    w = [cfo.sigma_first_order_problem(a, b, n).omega_exact for n in (201, 401)]
    assert abs(w[0] - w[1]) < 1e-3, w
