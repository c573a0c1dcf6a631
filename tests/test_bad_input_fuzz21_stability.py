"""Fuzz 21a, classes T and B and the debatable D10, D11, D14: the reseeding sweep (``fusion.book.stability``), the
stored benchmark results (``fusion.book.benchmarks``), and three helpers of the rulebook and the study cache.

Bad input is refused by a ValueError naming the argument (TypeError for a wrong type), a malformed stored file by a
ValueError naming the file and the field; valid documented input keeps working (``make stability`` itself, run end to
end on a toy repository, is the first test).
"""

from __future__ import annotations

import hashlib
import json
import os
import pickle
import subprocess
import sys
import textwrap
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from fusion._validation import MAX_COUNT, iterable
from fusion.book import benchmarks as B
from fusion.book import rulebook as R
from fusion.book import stability as S
from fusion.book import study_cache as sc
from test_stability import TOY_CLAIMS

ROOT = Path(__file__).resolve().parents[1]



def _toy_record(**changes: Any) -> dict[str, Any]:
    return {"id": "yang-toy", "status": "reproduced", "runs": 100, "evidence": {"seed": 3},
            "alternatives": [{"kind": "open-choice", "runs": 100}]} | changes  # its claim file's reading "tiny"


def _toy_repo(tmp_path: Path, records: list | None = None, body: str | None = None) -> Path:
    """A repository with the toy claim file of tests/test_stability.py and one chapter ledger file (of its record that
    reproduces: the failing one has no ledger entry, so the sweep does not run it)."""
    (tmp_path / "_toc.yml").write_text("root: x\n", encoding="utf-8")
    (tmp_path / "book" / "claims").mkdir(parents=True, exist_ok=True)
    (tmp_path / "book" / "ledger").mkdir(parents=True, exist_ok=True)
    (tmp_path / "book" / "claims" / "yang2012optimal.yaml").write_text(textwrap.dedent(TOY_CLAIMS), encoding="utf-8")
    text = body if body is not None else json.dumps({"claims": records if records is not None else [_toy_record()]})
    (tmp_path / "book" / "ledger" / "yang2012optimal-01.json").write_text(text, encoding="utf-8")
    return tmp_path


# --- T1: `make stability` runs end to end (python -m fusion.book.stability, a LocalCluster of worker processes)


def test_make_stability_runs_end_to_end(tmp_path: Path) -> None:
    """T1: ``main`` passed a set to ``seeds`` (refused), and ``python -m`` pickled ``run_batch`` by value (with a
    process_cache wrapper that cannot be pickled): the command the Makefile runs failed before any task ran."""
    pytest.importorskip("distributed")
    repo = _toy_repo(tmp_path)
    out = tmp_path / "out.json"
    env = os.environ | {"PYTHONPATH": os.pathsep.join([str(ROOT), str(ROOT / "tests")]), "OPENBLAS_NUM_THREADS": "1"}
    run = subprocess.run([sys.executable, "-m", "fusion.book.stability", "--reseeds", "1", "--runs-factor", "1",
                          "--workers", "1", "--out", str(out)], cwd=repo, env=env, capture_output=True, text=True,
                         timeout=300)
    assert run.returncode == 0, run.stderr[-3000:]
    doc = json.loads(out.read_text(encoding="utf-8"))
    # the primary reproduces and the counted open-choice reading "tiny" lies inside the margin (test_stability's
    # sweep): the rulebook's status of the record with both readings
    assert doc["readings"]["yang-toy"] == {"primary": {"kind": "primary", "runs": 100},
                                           "tiny": {"kind": "open-choice", "runs": 100}}
    assert doc["records"]["yang-toy"]["reseeds"] == ["reproduced under stated assumptions"]
    assert doc["records"]["yang-toy"]["failed"] == []
    assert not (repo / "book" / "ledger" / S.STABILITY_FILE).exists()


# --- T2, T3: seeds(avoid=...) takes any iterable of integers


@given(st.sets(st.integers(0, 2**31 - 1), max_size=20))
@settings(max_examples=30, deadline=None)
def test_seeds_avoid_any_iterable_of_integers(avoid: set[int]) -> None:
    want = S.seeds(3, S.ROOT_SEED, sorted(avoid))
    for form in (avoid, frozenset(avoid), dict.fromkeys(avoid).keys(), iter(sorted(avoid)),
                 (x for x in avoid), np.array(sorted(avoid), dtype=np.int64)):
        assert S.seeds(3, S.ROOT_SEED, form) == want
    assert not set(want) & avoid


def test_seeds_avoid_really_avoids_a_set() -> None:
    first = S.seeds(3)
    assert S.seeds(3, S.ROOT_SEED, {first[0]})[:2] == first[1:]


@pytest.mark.parametrize("avoid, exc", [(5, TypeError), ("123", TypeError), (b"1", TypeError), (None, TypeError),
                                        ({1.5}, TypeError), ({True}, TypeError)])
def test_seeds_refuses_what_is_not_an_iterable_of_integers(avoid: Any, exc: type) -> None:
    with pytest.raises(exc, match="avoid"):
        S.seeds(3, S.ROOT_SEED, avoid)


def test_iterable_refuses_an_endless_generator_and_names_a_raising_one() -> None:
    def endless():
        while True:
            yield 1

    def raising():
        yield 1
        raise RuntimeError("boom")

    with pytest.raises(ValueError, match=f"avoid has more than {MAX_COUNT}"):
        iterable(endless(), "avoid")
    with pytest.raises(TypeError, match="avoid could not be iterated.*boom"):
        iterable(raising(), "avoid")
    assert iterable({3}, "x") == [3] and iterable([1, 2], "x") == [1, 2]


# --- T6, T7: Task and TaskResult check their fields when built


GOOD_TASK = dict(source="s", record="r", reading="primary", kind="primary", seed=1, runs=10, scaled=False)


@pytest.mark.parametrize("field, value, exc", [
    ("source", 5, TypeError), ("record", None, TypeError), ("reading", [], TypeError), ("kind", {}, TypeError),
    ("kind", "zz", ValueError), ("seed", 1.5, TypeError), ("seed", -1, ValueError), ("runs", 0, ValueError),
    ("runs", -3, ValueError), ("runs", True, TypeError), ("scaled", "yes", TypeError)])
def test_a_task_refuses_a_bad_field_by_name(field: str, value: Any, exc: type) -> None:
    with pytest.raises(exc, match=f"Task.{field}"):
        S.Task(**(GOOD_TASK | {field: value}))


def test_a_task_and_its_result_keep_working() -> None:
    t = S.Task(**GOOD_TASK)
    assert pickle.loads(pickle.dumps(t)) == t and hash(t) == hash(S.Task(**GOOD_TASK))
    assert S.Task(**(GOOD_TASK | {"seed": np.int64(7)})).seed == 7
    ok, failed = S.TaskResult(t, "reproduced", 0.5), S.TaskResult(t, None, 0.0, "RuntimeError('x')")
    assert pickle.loads(pickle.dumps(ok)) == ok and failed.status is None


@pytest.mark.parametrize("args, exc, word", [
    ((5, "reproduced", 1.0), TypeError, "TaskResult.task"), ((None, "zz", 1.0), ValueError, "TaskResult.status"),
    ((None, 5, 1.0), TypeError, "TaskResult.status"), ((None, "reproduced", float("nan")), ValueError, "seconds"),
    ((None, "reproduced", -1.0), ValueError, "seconds"), ((None, "reproduced", 1.0, 7), TypeError, "error"),
    ((None, None, 1.0), ValueError, "TaskResult.error"), ((None, "reproduced", 1.0, "boom"), ValueError, "error")])
def test_a_task_result_refuses_a_bad_field_by_name(args: tuple, exc: type, word: str) -> None:
    t = S.Task(**GOOD_TASK)
    with pytest.raises(exc, match=word):
        S.TaskResult(*[t if a is None and i == 0 else a for i, a in enumerate(args)])


# --- T4, T5, T8-T11: run_task, run_batch and summarise refuse bad arguments by name


def test_run_task_and_run_batch_refuse_bad_arguments_by_name(tmp_path: Path) -> None:
    t = S.Task("nosuch", "x", "primary", "primary", 1, 10)
    with pytest.raises(ValueError, match="task.source.*nosuch"):
        S.run_task(t, str(ROOT))
    with pytest.raises(TypeError, match="task must be a Task"):
        S.run_task(5)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="root"):
        S.run_task(t, 5)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="root"):
        S.run_task(t, str(tmp_path))  # no _toc.yml there or above
    with pytest.raises(TypeError, match=r"batch\[0\] must be a Task"):
        S.run_batch([5])  # type: ignore[list-item]
    with pytest.raises(TypeError, match="batch must be a sequence"):
        S.run_batch(5)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="root"):
        S.run_batch([t], 5)  # type: ignore[arg-type]


def test_run_batch_still_reports_a_failing_task(tmp_path: Path) -> None:
    """A task whose source has no claim file is a task that fails (reported with its error), not a bad batch."""
    t = S.Task("nosuch", "x", "primary", "primary", 1, 10)
    (r,) = S.run_batch([t], str(ROOT))
    assert r.status is None and "no claim file" in r.error


def test_summarise_refuses_bad_results_and_statuses_by_name() -> None:
    t = S.Task(**GOOD_TASK)
    good = [S.TaskResult(t, "reproduced", 1.0)]
    assert S.summarise(good, [1], {"r": "reproduced"})["r"]["k"] == 1
    assert S.summarise(good, [1], {"r": None})["r"]["committed"] is None
    with pytest.raises(TypeError, match=r"results\[0\]"):
        S.summarise([5], [1], {})  # type: ignore[list-item]
    with pytest.raises(ValueError, match=r"committed\['r'\]"):
        S.summarise(good, [1], {"r": "zz"})  # T15
    with pytest.raises(ValueError, match="seed_list"):
        S.summarise(good, [1, 1], {})


# --- T13, T14: tasks


def test_tasks_refuse_an_unknown_kind_and_a_repeated_seed() -> None:
    readings = {("lecture003", "x"): {"primary": ("primary", 100)}}
    assert len(S.tasks(readings, [1, 2])) == 3
    with pytest.raises(ValueError, match="kind must be one of"):
        S.tasks({("lecture003", "x"): {"primary": ("zz", 100)}}, [1])
    with pytest.raises(ValueError, match=r"seed_list must not repeat.*seed_list\[0\] and seed_list\[1\]"):
        S.tasks(readings, [1, 1])


# --- T12, T16-T18: stochastic_readings and the ledger files it reads


def test_stochastic_readings_refuses_a_root_outside_the_repository(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="root"):
        S.stochastic_readings(tmp_path)
    with pytest.raises(TypeError, match="root"):
        S.stochastic_readings(5)  # type: ignore[arg-type]


def test_stochastic_readings_of_a_well_formed_toy_ledger(tmp_path: Path) -> None:
    repo = _toy_repo(tmp_path)
    assert S.stochastic_readings(repo) == {("yang2012optimal", "yang-toy"): {"primary": ("primary", 100),
                                                                          "tiny": ("open-choice", 100)}}
    assert S.stochastic_readings(_toy_repo(tmp_path, [_toy_record(runs=None)])) == {}


@pytest.mark.parametrize("body, field", [
    ("{}", "claims"), ("[]", "top level"), ("{bad", "not JSON"), ('{"claims": 5}', "claims"),
    ('{"claims": [5]}', r"claims\[0\]"), ('{"claims": [{"runs": 1e999}]}', "overflows"), ('{"claims": [{"runs": NaN}]}', "NaN"),
    ("[" * 100_000 + "]" * 100_000, "nested too deep")])
def test_a_malformed_ledger_file_is_refused_naming_the_file_and_the_field(tmp_path: Path, body: str, field: str) -> None:
    with pytest.raises(ValueError, match=rf"yang2012optimal-01\.json.*({field})"):
        S.stochastic_readings(_toy_repo(tmp_path, body=body))


@pytest.mark.parametrize("change, field", [
    ({"alternatives": None}, "alternatives"), ({"id": 5}, "id"), ({"status": None}, "status"),
    ({"runs": 2.5}, "runs"), ({"runs": -5}, "runs"), ({"runs": 0}, "runs"), ({"runs": True}, "runs"),
    ({"runs": "100"}, "runs"), ({"evidence": 5}, "evidence"), ({"evidence": {"seed": 1.5}}, "evidence.seed"),
    ({"alternatives": [{"runs": 100}]}, r"alternatives\[0\]"),
    ({"alternatives": [{"kind": "open-choice", "runs": 2.5}]}, r"alternatives\[0\].runs")])
def test_a_malformed_ledger_record_is_refused_naming_the_field(tmp_path: Path, change: dict, field: str) -> None:
    """T16-T18: a record without a field the sweep reads, or a run count that is not an integer >= 1 (``2.5`` was
    truncated to 2 runs, ``-5`` kept as -5 runs)."""
    record = {k: v for k, v in _toy_record(**change).items() if v is not None or k == "evidence"}
    with pytest.raises(ValueError, match=rf"yang2012optimal-01\.json: claims\[0\]\.{field}"):
        S.stochastic_readings(_toy_repo(tmp_path, [record]))


# --- B1-B8: the stored benchmark results


def test_every_stored_benchmark_result_loads_with_its_values() -> None:
    names = sorted(p.stem for p in B.RESULTS.glob("*.json"))
    assert "validation" in names
    for name in names:
        res = B.load_benchmark(name)
        assert all(np.isfinite(v) for v in res.values.values())
        assert set(res.values) == {m["key"] for m in res.measurements if "key" in m and "value" in m}
    assert B.load_benchmark("validation").values == {}  # its measurements hold several numbers, no "value"


def _bench(tmp_path: Path, body: str | bytes, name: str = "x") -> B.BenchmarkResult:
    path = tmp_path / f"{name}.json"
    path.write_bytes(body if isinstance(body, bytes) else body.encode())
    return B.load_benchmark(name, tmp_path)


GOOD_BENCH = {"date": "2026-01-01", "machine": "m", "measurements": [{"what": "w", "key": "a", "value": 1.5}]}


@pytest.mark.parametrize("body, word", [
    ("{bad", "not JSON"), ('"date machine measurements"', "top level"), (b"\xff\xfe{}", "UTF-8"),
    ("[" * 100_000 + "]" * 100_000, "nested too deep"),
    (json.dumps(GOOD_BENCH | {"measurements": 5}), "measurements must be a list"),
    (json.dumps(GOOD_BENCH | {"measurements": [5]}), r"measurements\[0\] must be an object"),
    (json.dumps(GOOD_BENCH | {"measurements": [{"key": "a", "value": "x"}]}), r"measurements\[0\].value"),
    (json.dumps(GOOD_BENCH | {"measurements": [{"key": "a", "value": True}]}), r"measurements\[0\].value"),
    (json.dumps(GOOD_BENCH | {"measurements": [{"key": 5, "value": 1}]}), r"measurements\[0\].key"),
    (json.dumps(GOOD_BENCH | {"date": 5}), "date must be a string"),
    ('{"date": "d", "machine": "m", "measurements": [{"key": "a", "value": NaN}]}', "NaN"),
    ('{"date": "d", "machine": "m", "measurements": [{"key": "a", "value": -Infinity}]}', "Infinity")])
def test_a_malformed_benchmark_result_is_refused_naming_the_file(tmp_path: Path, body: Any, word: str) -> None:
    with pytest.raises(ValueError, match=rf"x\.json.*{word}"):
        _bench(tmp_path, body)


@given(st.lists(st.fixed_dictionaries({"key": st.text(max_size=5), "what": st.text(max_size=5)},
                                      optional={"value": st.floats(allow_nan=False, allow_infinity=False)}),
                max_size=5, unique_by=lambda m: m["key"]))  # a key names one measurement (fuzz 24b D6)
@settings(max_examples=40, deadline=None)
def test_a_well_formed_benchmark_result_loads(measurements: list) -> None:
    import tempfile

    with tempfile.TemporaryDirectory() as d:
        res = _bench(Path(d), json.dumps(GOOD_BENCH | {"measurements": measurements}))
    assert res.values == {m["key"]: m["value"] for m in measurements if "value" in m}
    assert len(res.measurements) == len(measurements)


@pytest.mark.parametrize("field, value", [("name", 5), ("date", None), ("machine", ()), ("measurements", 7),
                                          ("measurements", (5,)), ("record", 8)])
def test_a_benchmark_result_refuses_a_bad_field_by_name(field: str, value: Any) -> None:
    """B8 (debatable, decided: checked): a BenchmarkResult built by hand checks its fields as the file's do."""
    good = B.load_benchmark("ci")
    import dataclasses

    with pytest.raises(TypeError, match=f"BenchmarkResult.{field}"):
        dataclasses.replace(good, **{field: value})


# --- D10, D11


def test_hill_tail_index_takes_eleven_values_and_refuses_ten() -> None:
    """D10 (decided: the code's rule n > 10, as the parameter says; the Raises text now agrees)."""
    assert np.isfinite(R.hill_tail_index(np.arange(1.0, 12.0)))
    with pytest.raises(ValueError, match="more than 10"):
        R.hill_tail_index(np.arange(1.0, 11.0))
    assert "10 values or fewer" in (R.hill_tail_index.__doc__ or "")


@pytest.mark.parametrize("package", ["/", "", str(ROOT)])
def test_source_digest_refuses_a_folder_that_is_not_a_package(package: str, tmp_path: Path,
                                                               monkeypatch: pytest.MonkeyPatch) -> None:
    """D11 (decided: refused): ``/`` or ``''`` (the working directory) would be walked file by file."""
    monkeypatch.chdir(tmp_path)
    with pytest.raises(ValueError, match="package must be a Python package"):
        sc.source_digest(package)
    assert sc.source_digest(str(ROOT / "fusion")) == sc.source_digest()


# --- D14: the disk layer of study_cache


_D14_CALLS: list = []


@sc.study_cache(maxsize=2)
def _d14_study(seed: int) -> float:
    """Module-level: only a function its module holds under its name reaches the disk (fuzz 34a D2)."""
    _D14_CALLS.append(seed)
    return seed * 2.0


@pytest.mark.parametrize("corrupt", [b"", b"\x80\x05\x95", b"not a pickle", "other key", "bare value"])
def test_a_corrupt_or_foreign_cache_file_is_a_miss(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                   corrupt: Any) -> None:
    """D14 (decided: a miss): an empty, truncated or corrupt ``<key>.pkl``, or one holding another key's result (or a
    bare value), is recomputed and rewritten instead of raising UnpicklingError/EOFError or being returned."""
    monkeypatch.setenv(sc.ENV, str(tmp_path))
    f, calls = _d14_study, _D14_CALLS
    f.cache_clear()
    calls.clear()
    assert f(3) == 6.0 and calls == [3]
    (target,) = tmp_path.glob("*.pkl")
    signed = target.read_bytes()[:sc._DIGEST]   # entries with their payload's digest (fuzz 40b C3): only their key or
    if corrupt == "other key":                   # their form makes them a miss
        corrupt = sc._entry("0" * 64, 99.0)
    elif corrupt == "bare value":
        payload = pickle.dumps(99.0)
        corrupt = hashlib.blake2b(payload, digest_size=sc._DIGEST).digest() + payload
    assert len(signed) == sc._DIGEST
    target.write_bytes(corrupt)
    f.cache_clear()
    assert f(3) == 6.0 and calls == [3, 3]          # recomputed
    f.cache_clear()
    assert f(3) == 6.0 and calls == [3, 3]          # and rewritten: loaded now


def test_fuzz49b_c1_a_claim_files_stand_in_reading_is_paired_with_its_own_ledger_entry(tmp_path: Path) -> None:
    """Every stand-in alternative was dropped before the readings were paired by position, so a claim file's own
    stand-in reading took the next reading's entry and the last readings were lost (chapter 06's chf-gain-ci:
    baseline-trace and the counted frames-1-4 were never reseeded). Only the R7 stand-in that build_ledger inserts
    first (the source's baseline undefined) is no reading of the file; a ledger that does not match the file's
    readings is refused naming the record."""
    claims = textwrap.dedent(TOY_CLAIMS).replace(
        "others: [{key: tiny, choice: shift, reading: a hundredth, settings: {shift: 0.01}}]",
        "others: [{key: alt, choice: baseline, reading: a stand-in, kind: stand-in, settings: {shift: 0.5}},\n"
        "                     {key: tiny, choice: shift, reading: a hundredth, settings: {shift: 0.01}}]")
    repo = _toy_repo(tmp_path, [_toy_record(alternatives=[{"kind": "stand-in", "runs": 100},
                                                          {"kind": "open-choice", "runs": 50}])])
    (repo / "book" / "claims" / "yang2012optimal.yaml").write_text(claims, encoding="utf-8")
    assert S.stochastic_readings(repo) == {("yang2012optimal", "yang-toy"): {
        "primary": ("primary", 100), "alt": ("stand-in", 100), "tiny": ("open-choice", 50)}}
    repo = _toy_repo(tmp_path, [_toy_record(alternatives=[{"kind": "open-choice", "runs": 50}])])
    (repo / "book" / "claims" / "yang2012optimal.yaml").write_text(claims, encoding="utf-8")
    with pytest.raises(ValueError, match="record yang-toy holds alternatives of the kinds"):
        S.stochastic_readings(repo)
