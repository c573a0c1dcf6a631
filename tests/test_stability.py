"""The reseeding sweep (fusion.book.stability): seeds, tasks, statuses per reseed, a run on Dask, and coverage.

``test_stored_results_cover_every_stochastic_record`` fails when a stochastic record or reading is added
or changed without re-running ``make stability``.
"""

from __future__ import annotations

import json
import textwrap
from pathlib import Path

import numpy as np
import pytest

from fusion.book import ledger as L
from fusion.book import stability as S

ROOT = Path(__file__).resolve().parents[1]


def toy_evidence(settings: dict, *, seed: int, runs: int) -> L.Comparison:
    """Evidence function of the toy claim file below: A is better than B by ``settings['shift']``."""
    rng = np.random.default_rng(seed)
    b = rng.normal(10.0, 1.0, runs)
    a = b - settings.get("shift", 1.0) + 0.5 * rng.normal(size=runs)
    return L.Comparison(a, b, "A", "B", "less", "e", seed=seed)


def broken_evidence(settings: dict, *, seed: int, runs: int) -> L.Comparison:
    raise RuntimeError("this evidence function always fails")


#: The toy claim file of the sweep's tests: a record that reproduces, and one whose evidence always fails.
TOY_CLAIMS = """
        source: yang2012optimal
        quantities: {e: {label: error, margin: {relative: 0.05}}}
        records:
          - id: yang-toy
            chapter: notebooks/01_optimal_fusion_set
            where: toy
            claim: A beats B.
            claimant: source
            published: {value: qualitative}
            test: paired
            quantity: e
            direction: less
            headline: true
            link: x
            evidence: test_stability:toy_evidence
            readings:
              primary: {choice: shift, reading: one, settings: {shift: 1.0}}
              others: [{key: tiny, choice: shift, reading: a hundredth, settings: {shift: 0.01}}]
          - id: yang-broken
            chapter: notebooks/01_optimal_fusion_set
            where: toy
            claim: A beats B again.
            claimant: source
            published: {value: qualitative}
            test: paired
            quantity: e
            direction: less
            link: x
            evidence: test_stability:broken_evidence
    """


def test_seeds_are_distinct_reproducible_and_avoid_the_chapters() -> None:
    s = S.seeds(5)
    assert len(set(s)) == 5 and s == S.seeds(5) and all(0 <= x < 2**31 for x in s)
    assert S.seeds(5, avoid=s[:2])[:3] != s[:3] and not set(S.seeds(5, avoid=s[:2])) & set(s[:2])
    with pytest.raises(ValueError, match="k"):
        S.seeds(0)


def test_tasks_cover_every_reading_and_the_scaled_primary() -> None:
    readings = {("src", "r-1"): {"primary": ("primary", 100), "x": ("open-choice", 100)},
                ("src", "r-2"): {"primary": ("primary", 200)}}
    t = S.tasks(readings, [1, 2, 3], runs_factor=10)
    assert len(t) == 3 * 3 + 2
    assert {x.runs for x in t if x.scaled} == {1000, 2000}
    assert len(S.tasks(readings, [1, 2, 3], runs_factor=1)) == 9
    with pytest.raises(ValueError, match="runs_factor"):
        S.tasks(readings, [1], runs_factor=0)


def _result(rid: str, reading: str, kind: str, seed: int, status: str | None, scaled: bool = False) -> S.TaskResult:
    return S.TaskResult(S.Task("src", rid, reading, kind, seed, 1000 if scaled else 100, scaled), status, 0.1,
                        "" if status else "boom")


def test_a_status_that_changes_under_a_reseed_is_flagged() -> None:
    res = [_result("r-1", "primary", "primary", s, "reproduced") for s in (1, 2)]
    res += [_result("r-1", "x", "open-choice", 1, "reproduced"), _result("r-1", "x", "open-choice", 2, "contradicted")]
    res += [_result("r-1", "primary", "primary", 1, "reproduced", scaled=True)]
    res += [_result("r-2", "primary", "primary", s, "not distinguishable") for s in (1, 2)]
    res += [_result("r-2", "primary", "primary", 1, "reproduced", scaled=True)]
    out = S.summarise(res, [1, 2], {"r-1": "reproduced under stated assumptions", "r-2": "not distinguishable"})
    assert out["r-1"]["reseeds"] == ["reproduced", "reproduced under stated assumptions"]
    assert out["r-1"]["k"] == 2 and not out["r-1"]["flag"]
    assert out["r-2"]["k"] == 2 and out["r-2"]["flag"], "the 10x run changes the status"
    failed = S.summarise([_result("r-3", "primary", "primary", 1, None)], [1], {"r-3": "reproduced"})
    assert failed["r-3"]["failed"] and failed["r-3"]["k"] == 0 and failed["r-3"]["flag"]


def test_the_sweep_runs_on_dask_and_reports_failures(tmp_path: Path) -> None:
    distributed = pytest.importorskip("distributed")
    (tmp_path / "_toc.yml").write_text("root: x\n", encoding="utf-8")
    (tmp_path / "book" / "claims").mkdir(parents=True)
    (tmp_path / "book" / "claims" / "yang2012optimal.yaml").write_text(textwrap.dedent(TOY_CLAIMS), encoding="utf-8")
    readings = {("yang2012optimal", "yang-toy"): {"primary": ("primary", 100), "tiny": ("open-choice", 100)},
                ("yang2012optimal", "yang-broken"): {"primary": ("primary", 100)}}
    task_list = S.tasks(readings, [11, 12], runs_factor=2)
    with distributed.Client(processes=False, n_workers=1, threads_per_worker=2, dashboard_address=None) as client:
        results = S.sweep(task_list, client, tmp_path, progress=False)
    assert len(results) == len(task_list)
    ok = {(r.task.record, r.task.reading, r.task.seed, r.task.scaled): r.status for r in results}
    assert ok[("yang-toy", "primary", 11, False)] == "reproduced"
    assert ok[("yang-toy", "tiny", 11, False)] == "not distinguishable"   # inside the 5 % margin
    assert ok[("yang-toy", "primary", 11, True)] == "reproduced"
    bad = [r for r in results if r.task.record == "yang-broken"]
    assert bad and all(r.status is None and "always fails" in r.error for r in bad)


def test_stored_results_cover_every_stochastic_record() -> None:
    path = ROOT / "book" / "ledger" / S.STABILITY_FILE
    assert path.is_file(), "no reseeding results: run `make stability`"
    stored = json.loads(path.read_text(encoding="utf-8"))
    current = {rid: {k: {"kind": kind, "runs": runs} for k, (kind, runs) in rs.items()}
               for (_, rid), rs in S.stochastic_readings(ROOT).items()}
    assert stored["readings"] == current, ("the stored reseeding results do not cover exactly the current "
                                           "stochastic records and readings: run `make stability`")
    assert set(stored["records"]) == set(current)
    assert stored["K"] >= 5 and len(stored["seeds"]) == stored["K"]
    failed = sorted(rid for rid, v in stored["records"].items() if v["failed"] or None in v["reseeds"])
    assert not failed, f"reseeding tasks failed for {failed}: rerun `make stability` for them"
    statuses = {}
    for f in (ROOT / "book" / "ledger").glob("*.json"):
        if f.name != S.STABILITY_FILE:
            statuses |= {r["id"]: r["status"] for r in json.loads(f.read_text(encoding="utf-8"))["claims"]}
    moved = sorted(rid for rid, v in stored["records"].items() if v["committed"] != statuses[rid])
    assert not moved, f"statuses changed since the reseeding sweep ran: {moved}; rerun `make stability` for them"


def test_batches_group_by_source_seed_and_scale_and_keep_every_task() -> None:
    readings = {("a", "r1"): {"primary": ("primary", 100), "x": ("open-choice", 100)},
                ("a", "r2"): {"primary": ("primary", 200)}, ("b", "r3"): {"primary": ("primary", 100)}}
    task_list = S.tasks(readings, [1, 2], runs_factor=3)
    groups = S.batches(task_list)
    assert sorted(map(id, (t for g in groups for t in g))) == sorted(map(id, task_list))
    for g in groups:
        assert len({(t.source, t.seed, t.scaled) for t in g}) == 1
    assert len(groups) == len({(t.source, t.seed, t.scaled) for t in task_list})
