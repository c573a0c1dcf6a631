"""fusion.book.benchmarks, and the rule that benchmark results never enter nbval's comparison."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from fusion.book.benchmarks import IGNORE_OUTPUT_TAG, RESULTS, load_benchmark

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = sorted((ROOT / "notebooks").glob("*.ipynb"))
READS_BENCHMARKS = ("load_benchmark", '"benchmarks"', "benchmarks/results")

# Chapters whose benchmark cells their own helpers tag (issue 14 hands them the rule). Strict:
# once a chapter follows the rule this marker fails, and must be removed.
PENDING: set[str] = set()


def test_every_stored_result_loads_with_its_date() -> None:
    names = sorted(p.stem for p in RESULTS.glob("*.json"))
    assert names, "no stored benchmark results"
    for name in names:
        result = load_benchmark(name)
        assert result.date and result.machine and result.measurements
        assert result.date in result.caption and name in result.caption


def test_values_by_key(tmp_path: Path) -> None:
    record = {"date": "2026-01-02", "machine": "m", "measurements": [
        {"key": "a", "what": "A", "value": 1.5, "unit": "s"}, {"what": "no key", "value": 2.0}]}
    (tmp_path / "x.json").write_text(json.dumps(record), encoding="utf-8")
    result = load_benchmark("x", tmp_path)
    assert result.values == {"a": 1.5}
    assert result.caption == "benchmarks/x: measured on 2026-01-02, m"
    with pytest.raises(TypeError):
        result.record["date"] = "changed"  # type: ignore[index]


@pytest.mark.parametrize("name", ["", "../ci", "ci.json", "no_such_benchmark"])
def test_bad_names_raise(name: str) -> None:
    with pytest.raises(ValueError, match="name"):
        load_benchmark(name)


def test_record_without_date_raises(tmp_path: Path) -> None:
    (tmp_path / "x.json").write_text(json.dumps({"machine": "m", "measurements": []}), encoding="utf-8")
    with pytest.raises(ValueError, match="date"):
        load_benchmark("x", tmp_path)


def _violations(notebook: Path) -> list[str]:
    cells = json.loads(notebook.read_text(encoding="utf-8"))["cells"]
    bad = []
    for i, cell in enumerate(cells):
        source = "".join(cell["source"])
        if cell["cell_type"] != "code" or not any(s in source for s in READS_BENCHMARKS):
            continue
        if IGNORE_OUTPUT_TAG not in cell.get("metadata", {}).get("tags", []):
            bad.append(f"cell {i}: reads benchmark results without the {IGNORE_OUTPUT_TAG} tag")
        if "date" not in source and "caption" not in source:
            bad.append(f"cell {i}: shows benchmark results without their date")
    return bad


def test_the_rule_checker_sees_an_untagged_cell(tmp_path: Path) -> None:
    nb = {"cells": [{"cell_type": "code", "metadata": {}, "source": ["r = load_benchmark('ci')\n"]},
                    {"cell_type": "code", "metadata": {"tags": [IGNORE_OUTPUT_TAG]},
                     "source": ["r = load_benchmark('ci')\n", "glue('d', r.date)"]}]}
    path = tmp_path / "x.ipynb"
    path.write_text(json.dumps(nb), encoding="utf-8")
    assert _violations(path) == ["cell 0: reads benchmark results without the nbval-ignore-output tag",
                                 "cell 0: shows benchmark results without their date"]


@pytest.mark.parametrize("notebook", [
    pytest.param(p, id=p.name, marks=pytest.mark.xfail(
        p.name in PENDING, strict=True, reason="benchmark cells not tagged yet (chapter helpers)"))
    for p in NOTEBOOKS])
def test_cells_showing_benchmarks_are_not_compared_and_show_the_date(notebook: Path) -> None:
    assert _violations(notebook) == []


PEER_ROWS = {"ci_fixed_weight", "ci_optimal", "ci_optimal_100", "kalman_one_run", "kalman_100_runs",
             "kalman_one_run_no_fixed_point", "kalman_one_run_300", "pf_one_run", "pf_10_runs", "em_one_set", "em_20_sets", "swarm_one",
             "swarm_20"}
AGREEMENTS = {"bitwise", "round-off", "optimiser tolerance", "statistical"}


def test_peers_result_has_its_schema() -> None:
    """benchmarks/bench_peers.py: one row per shared algorithm and size, its ratio and its agreement check."""
    result = load_benchmark("peers")
    rows = result.record["rows"]
    assert {r["key"] for r in rows} == PEER_ROWS
    assert {r["size"] for r in rows} == {"single", "batched"}
    for r in rows:
        assert set(r) == {"key", "what", "size", "peer", "peer_version", "ours_s", "peer_s", "ratio", "agreement",
                          "agreement_value", "agreement_ok"}
        assert r["ours_s"] > 0 and r["peer_s"] > 0
        assert r["ratio"] == pytest.approx(r["peer_s"] / r["ours_s"])
        assert r["agreement"] in AGREEMENTS and isinstance(r["agreement_ok"], bool) and r["peer_version"]
        if r["agreement"] == "bitwise":
            assert r["agreement_value"] == 0.0
    assert result.values == {r["key"]: pytest.approx(r["ratio"]) for r in rows}
    assert result.record["repeats"] >= 9 and "median" in result.record["statistic"]


def test_pf_kernel_result_has_its_schema() -> None:
    """benchmarks/bench_pf_kernel.py: the kernel's GFLOP/s, the peak it is measured against, and the options."""
    result = load_benchmark("pf_kernel")
    v = result.values
    for key in ("pf_kernel_frame_s", "pf_kernel_gflops", "dgemm_gflops", "pf_kernel_fraction_of_dgemm",
                "option_fused_predict_speedup", "option_fused_predict_max_rel_diff", "option_bulk_draws_speedup"):
        assert key in v and v[key] > 0
    assert v["pf_kernel_fraction_of_dgemm"] == pytest.approx(v["pf_kernel_gflops"] / v["dgemm_gflops"])
    assert 0 < v["pf_kernel_fraction_of_dgemm"] < 1
    assert sum(v[k] for k in v if k.startswith("share_")) == pytest.approx(1.0)
    assert result.record["landed"] is False


def test_study_result_has_its_schema() -> None:
    """benchmarks/bench_study.py: chapter 06's study at its default scenario, wall and CPU time, GFLOP/s and peak."""
    result = load_benchmark("study")
    v = result.values
    for key in ("study_wall_seconds", "study_cpu_seconds", "study_idle_wall_seconds", "kernel_seconds",
                "kernel_gflops", "dgemm_gflops", "kernel_fraction_of_peak"):
        assert key in v and v[key] > 0
    workers = result.record["workers"]
    assert v["study_idle_wall_seconds"] == pytest.approx(v["study_cpu_seconds"] / workers)
    assert v["kernel_fraction_of_peak"] == pytest.approx(v["kernel_gflops"] / v["dgemm_gflops"])
    assert 0 < v["kernel_fraction_of_peak"] < 1
    assert result.record["runs"] >= 1 and "study_scenario()" in result.record["scenario"]
