r"""Verdicts that survive reseeding: every stochastic record re-derived under fresh seeds, on Dask.

``make stability`` runs :func:`main`. For every stochastic record of the claim files (a record whose
committed ledger entry has a run count) and every one of its readings, the record's evidence
function (:func:`fusion.book.claims.evaluate`) is called under :data:`RESEEDS` fresh seeds at the
chapter's run count, and the primary reading once more at :data:`RUNS_FACTOR` times the runs; each
result is judged by the same rulebook (:mod:`fusion.book.rulebook`) and each reseed's record status
by rule R5. The seeds derive from one stated root seed (:data:`ROOT_SEED`) with
:class:`numpy.random.SeedSequence` and are disjoint from the seeds the chapters use.

The tasks, one per (record, reading, seed, runs), run on Dask distributed in batches of one source and one
seed (:func:`batches`: the tasks of a batch share the studies a worker caches): a
:class:`~distributed.LocalCluster` on this machine by default, or the scheduler named by
``--scheduler ADDRESS`` (or Dask's own configuration), unchanged. A failed task is retried
(:data:`RETRIES` times); one that still fails is reported by record, reading and seed, stored in the
results, and makes the run exit non-zero: never silently dropped.

Results go to ``book/ledger/stability.json``: the date, root seed, K, run counts, package versions,
the commit of the evidence code, and every record's status under every reseed and at 10× runs. The
Verdicts page shows "stable in k/K reseeds" for each stochastic record and flags a record whose
status changes; ``tests/test_stability.py`` fails when the stored results do not cover exactly the
current stochastic records and readings.
"""

from __future__ import annotations

import argparse
import datetime as _dt
import itertools
import json
import platform
import subprocess
import sys
import time
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import asdict, dataclass
from importlib.metadata import version
from pathlib import Path
from typing import Any

import numpy as np

from fusion.book._json import JSONObject, read_object
from fusion._results import ResultSpec, flag, instance, integer, number, text, validated_post_init
from fusion._counts import COUNT_CEILINGS, MAX_COUNT
from fusion._limits import MAX_WORK, work
from fusion._validation import is_integer
from fusion._validation import count, distinct, instance_of, iterable, seed as check_seed, seeds as check_seeds, sequence
from fusion.book import claims as C
from fusion.book import rulebook as R
from fusion.book.exact import ExactComparison
from fusion.book.study_cache import process_cache
from fusion.book.ledger import Comparison, Conjunction, Evidence, ledger_dir
from fusion._shown import shown
from fusion._paths import file_json, folder, write_file_text

#: The command line's description (the docstring's first line; kept here, as ``python -OO`` strips docstrings).
_DESCRIPTION = "Verdicts that survive reseeding: every stochastic record re-derived under fresh seeds, on Dask."

__all__ = ["ROOT_SEED", "RESEEDS", "RUNS_FACTOR", "RETRIES", "Task", "TaskResult", "stochastic_readings", "seeds",
           "tasks", "run_task", "run_batch", "batches", "summarise", "sweep", "main", "STABILITY_FILE"]

#: Root of the reseeding sweep's seeds (stated; the chapters never use the seeds it derives).
ROOT_SEED = 20261205

#: Fresh seeds per reading (K).
RESEEDS = 5
#: Largest number of reseeds ``seeds`` derives (each is a full run of the stochastic records).
MAX_SEEDS = 10**4

#: The derived seeds are below this (31 bits: a ``uint32`` state shifted right by one, :func:`seeds`).
_SEED_END = 2**31

#: The primary reading is also run at this many times the chapter's runs.
RUNS_FACTOR = 10

#: Units of work (``fusion._limits.work``, about 10 ns each) of one :class:`Task` that :func:`tasks` builds and checks:
#: 15-17 us measured on this shared machine (CPU time, minimum of 3; 153,650 tasks of 300 seeds in 2.4 CPU-s), so the
#: budget's edge, 500,000 tasks (about 980 seeds of the book's 512 readings), builds in about 8-9 CPU-s (fuzz 40b C7:
#: ``seeds(10_000)`` built 5.1e6 tasks in 101 CPU-s). The book's sweep, 5 seeds, is 2,560 tasks.
TASK_WORK = 2000
#: Units of work of one reading (a ``(kind, runs)`` entry of a record) that :func:`tasks` checks before building any
#: task: 7.2-8.0 us measured on this shared machine (CPU time, minimum of 3, 200,000 one-reading records), so 1,000
#: units (fuzz 41b C1: 2,000,000 readings at one seed were checked for 19 CPU-s before the task budget refused them).
#: :func:`tasks` counts the readings (by iterating each record, not by its ``len()``, fuzz 42b C3) before checking any.
READING_WORK = 1000
#: Units of work of one record (a ``(source, record)`` key) that :func:`tasks` counts and checks, with or without
#: readings (fuzz 42b D3: 5e6 records without readings were checked for 6.4 CPU-s, counted 0): 0.95 us measured on
#: this shared machine (CPU time, minimum of 3, 10**6 records without readings at one seed), so 100 units.
RECORD_WORK = 100

#: Units of work of one result that :func:`summarise` checks, groups and judges (rule R5 over its record's readings at
#: its seed, or its failure's record): 6.4-7.1 us measured on this shared machine (CPU time, minimum of 3: 100,000
#: seeds of one primary result each 0.71 s, one record of 200,000 readings 1.34 s, 200,000 failed results 1.27 s), so
#: 1,000 units; the budget's edge, 10**6 results, about 7 CPU-s. Fuzz 49b C6: the results were grouped by a scan of the
#: record's results per seed, quadratic (60,000 seeds of one result each ran 99 CPU-s); they are now grouped once.
SUMMARY_RESULT_WORK = 1000
#: Units of work of one record at one seed of ``seed_list`` in :func:`summarise` (a seed without a result of the record
#: is a None status): 0.18 us measured on this shared machine (CPU time, minimum of 3: 1,000 records x 5,000 seeds with
#: one result each, 0.89 s), so 20 units; the budget's edge, 5e7 cells, about 9 CPU-s.
SUMMARY_CELL_WORK = 20
#: Units of work of one entry of :func:`summarise`'s ``committed`` (its status checked): 12-51 ns measured on this
#: shared machine (CPU time, minimum of 3, a dict of 10**6 ids, None or a status each), so 5 units. ``committed`` is
#: counted by iterating its keys (not by its ``len()``), at most ``MAX_COUNT`` (10**7, rule 9) of them, before any
#: entry is read (fuzz 53a C2: a lazy mapping of 6e7 ids was walked for 33 CPU-s and entered no budget).
SUMMARY_COMMITTED_WORK = 5

#: Retries of a failed task before it is reported as failed.
RETRIES = 2

#: Name of the results file in ``book/ledger``.
STABILITY_FILE = "stability.json"


def _sweep_seed(v: Mapping[str, Any], label: str) -> None:
    """A :class:`Task`'s seed is one :func:`seeds` derives, below 2**31 (fuzz 53a C3's class: :func:`batches` and
    :func:`summarise` hash each task's seed, 0.5 ms for one of 10**7 bits)."""
    if v["seed"] >= _SEED_END:
        raise ValueError(f"{label}.seed must be a seed of the sweep, below 2**31 (seeds() derives 31-bit seeds), got an "
                         f"integer of {int(v['seed']).bit_length():,} bits")


@dataclass(frozen=True)
class Task:
    """One unit of the sweep: a reading of a record under one seed and run count.

    Attributes
    ----------
    source, record, reading : str
        Claim file's source key, record id and reading key (``"primary"`` or a reading's key).
    kind : str
        The reading's kind (:data:`fusion.book.rulebook.READING_KINDS`).
    seed, runs : int
        A seed of the sweep (in ``[0, 2**31)``, as :func:`seeds` derives) and a run count (>= 1).
    scaled : bool
        Whether this is the primary reading at :data:`RUNS_FACTOR` times the runs.

    Raises
    ------
    TypeError, ValueError
        A field of another type or out of range, naming ``Task.field`` (checked when built, as every record the sweep
        consumes).
    """

    source: str
    record: str
    reading: str
    kind: str
    seed: int
    runs: int
    scaled: bool = False

    __result_spec__ = ResultSpec({"source": text(), "record": text(), "reading": text(), "kind": text(*R.READING_KINDS),
                                  "seed": integer(0), "runs": integer(1), "scaled": flag()},
                                 relations=(_sweep_seed,))
    __post_init__ = validated_post_init


def _outcome(v: Mapping[str, Any], label: str) -> None:
    """A :class:`TaskResult`'s status is one of the rulebook's, or None with the error that stands for it."""
    if v["status"] is None:
        if not v["error"]:
            raise ValueError(f"{label}.error must say why the task failed (status is None)")
    elif v["status"] not in R.STATUSES:
        raise ValueError(f"{label}.status must be one of {R.STATUSES} or None, got {shown(v['status'])}")
    elif v["error"]:
        raise ValueError(f"{label}.error must be empty when the task gave a status, got {shown(v['error'])}")


@dataclass(frozen=True)
class TaskResult:
    """What one task gave: the reading's status (or the error) and its cost.

    Attributes
    ----------
    task : Task
    status : str or None
        The reading's status by the rulebook; None when the task failed.
    seconds : float
        Time the task took in its worker.
    error : str
        The failure, when the task failed (not empty then; empty when ``status`` is given).

    Raises
    ------
    TypeError, ValueError
        A field of another type, a status outside :data:`fusion.book.rulebook.STATUSES`, a negative or non-finite
        ``seconds``, or a failure without its error (or an error with a status), naming ``TaskResult.field``.
    """

    task: Task
    status: str | None
    seconds: float
    error: str = ""

    __result_spec__ = ResultSpec({"task": instance(Task), "status": instance(str, optional=True),
                                  "seconds": number(), "error": text()},
                                 relations=(_outcome,))
    __post_init__ = validated_post_init


def stochastic_readings(root: Path | None = None) -> dict[tuple[str, str], dict[str, tuple[str, int]]]:
    """Every stochastic record and its readings, from the claim files and the committed ledger.

    A record is stochastic when its committed primary evidence has a run count; a reading, when its
    committed evidence has one.

    Parameters
    ----------
    root : pathlib.Path, optional
        The repository, or a folder inside it (default: found from the working directory).

    Returns
    -------
    dict
        ``{(source, record id): {reading key: (kind, runs)}}``.

    Raises
    ------
    TypeError
        ``root`` is not a path.
    ValueError
        ``root`` is not an existing folder, or not inside the book's repository (no ``_toc.yml`` in it or above
        it); or a ledger file is malformed or not a readable file, naming the file and the field (see
        ``_ledger_records``).
    FileNotFoundError
        Without ``root``: the working directory is not inside the repository, nor is the imported package
        (:func:`fusion.book.ledger.ledger_dir`).
    """
    d = _ledger_dir(root)
    built = {r["id"]: r for r in _ledger_records(d)}
    out: dict[tuple[str, str], dict[str, tuple[str, int]]] = {}
    for key, cf in C.load_all(d.parent / "claims").items():
        for spec in cf.records:
            r = built.get(spec.id)
            if r is None or r.get("runs") is None:
                continue
            readings = {"primary": ("primary", r["runs"])}
            others = [x for x in spec.readings if x.key != "primary"]
            alternatives = _reading_alternatives(spec, r, others, d)
            for x, a in zip(others, alternatives):
                if a.get("runs") is not None:
                    readings[x.key] = (x.kind, a["runs"])
            out[(key, spec.id)] = readings
    return out


def _reading_alternatives(spec: C.ClaimSpec, record: dict, others: list, folder: Path) -> list:
    """The ledger alternatives of a record's claim-file readings ``others``, in their order.

    ``build_ledger`` writes one alternative per non-primary reading, in the claim file's order, and for a baseline
    the source leaves undefined (rule R7) first the stand-in it inserts, which is no reading of the file. Any other
    ``kind: stand-in`` alternative is a reading of the file and is paired with it (fuzz 49b C1: every stand-in was
    dropped, so chapter 06's chf-gain-ci paired its reading baseline-determinant with frames-1-4's entry and lost
    baseline-trace and frames-1-4). A ledger whose alternatives do not match the file's readings, in number or in
    kind, is refused naming the file and the record: it was built from another claim file.
    """
    alternatives = list(record["alternatives"])
    b = spec.baseline
    if b is not None and not b["defined"] and alternatives and alternatives[0].get("kind") == "stand-in":
        alternatives = alternatives[1:]  # the R7 stand-in build_ledger inserts (fusion.book.claims.build_ledger)
    kinds = [x.kind for x in others]
    stored = [a.get("kind") for a in alternatives]
    if stored != kinds:
        raise ValueError(f"ledger {folder}: record {spec.id} holds alternatives of the kinds {shown(stored, 200)}, "
                         f"its claim file's readings are of the kinds {shown(kinds, 200)}: the ledger was built from "
                         "another claim file (rebuild it)")
    return alternatives


def _ledger_dir(root: object) -> Path:
    """``book/ledger`` of the repository containing ``root``; a ``root`` outside any is refused by name."""
    if root is None:
        return ledger_dir()
    root = folder(root, "root")   # a file or a missing folder is refused naming root, not ledger_dir's start
    try:
        return ledger_dir(root)
    except FileNotFoundError as exc:
        raise ValueError(f"root: {exc}") from exc


def _runs_field(value: object, where: str) -> int | None:
    """A stored run count: None (a deterministic record) or an integer >= 1, never truncated from a float."""
    if value is None:
        return None
    if not is_integer(value) or isinstance(value, bool):
        raise ValueError(f"{where} must be an integer run count or null, got {shown(value)}")
    if value < 1:
        raise ValueError(f"{where} must be at least 1, got {shown(value)}")
    return int(value)


def _ledger_records(d: Path) -> list[dict[str, Any]]:
    """Every record of the chapter ledger files in ``d`` (not the sweep's own results), the fields the sweep reads
    checked: a malformed file is refused by a ValueError naming the file and the field, not a KeyError or a
    TypeError from deep inside, and a run count is an integer (``2.5`` is refused, not truncated to 2)."""
    out = []
    for f in sorted(d.glob("*.json")):
        if f.name == STABILITY_FILE:
            continue
        doc = read_object(f, "ledger file")
        claims = doc.get("claims")
        if not isinstance(claims, list):
            raise ValueError(f"ledger file {f}: claims must be a list of records, got {shown(claims)}")
        for i, r in enumerate(claims):
            where = f"ledger file {f}: claims[{i}]"
            if not isinstance(r, dict):
                raise ValueError(f"{where} must be an object, got {shown(r)}")
            for k, kinds in (("id", str), ("status", str), ("alternatives", list)):
                if not isinstance(r.get(k), kinds):
                    raise ValueError(f"{where}.{k} must be a {kinds.__name__}, got {shown(r.get(k))}")
            if r.get("evidence") is not None and not isinstance(r["evidence"], dict):
                raise ValueError(f"{where}.evidence must be an object or null, got {shown(r['evidence'])}")
            seed = r["evidence"].get("seed") if r.get("evidence") else None
            if seed is not None and (not is_integer(seed) or isinstance(seed, bool)):
                raise ValueError(f"{where}.evidence.seed must be an integer or null, got {shown(seed)}")
            r = r | {"runs": _runs_field(r.get("runs"), f"{where}.runs"), "alternatives": []}
            for j, a in enumerate(claims[i]["alternatives"]):
                if not (isinstance(a, dict) and isinstance(a.get("kind"), str)):
                    raise ValueError(f"{where}.alternatives[{j}] must be an object with a kind, got {shown(a)}")
                r["alternatives"].append(a | {"runs": _runs_field(a.get("runs"), f"{where}.alternatives[{j}].runs")})
            out.append(r)
    return out


def seeds(k: int = RESEEDS, root_seed: int = ROOT_SEED, avoid: Iterable[int] = ()) -> list[int]:
    """``k`` seeds derived from ``root_seed``, none of them in ``avoid`` (the chapters' seeds).

    Parameters
    ----------
    k : int
        How many.
    root_seed : int
    avoid : iterable of int
        Any iterable of integers (a list, a set, dict keys, a generator, ...); its order does not matter. An integer
        outside ``[0, 2**31)`` (a negative one: :func:`main` enters -1 for a chapter without a seed; or one of 32 bits
        or more, a chapter may use any seed) can never be a derived seed: it is skipped, never hashed (fuzz 53a C3:
        ``[1 << 10**7] * 60_000`` was hashed item by item for 34 CPU-s).

    Returns
    -------
    list of int
        Distinct 31-bit seeds (in ``[0, 2**31)``).

    Raises
    ------
    TypeError
        ``k`` or ``root_seed`` not an integer, ``avoid`` not an iterable or holding a non-integer.
    ValueError
        ``k`` below 1 or above ``MAX_SEEDS``, ``root_seed`` negative, ``avoid`` of more than 10**7 items.
    """
    k = count(k, "k", maximum=MAX_SEEDS)
    root_seed = check_seed(root_seed, "root_seed")
    items = iterable(avoid, "avoid")
    for v in items:  # integers (a chapter without a seed is entered as -1): a float 3.0 would silently miss 3
        if not is_integer(v):
            raise TypeError(f"avoid must hold integer seeds, got {shown(v)}")
    avoid = {int(v) for v in items if 0 <= v < _SEED_END}  # a comparison reads an int's size, not its digits
    out: list[int] = []
    ss = np.random.SeedSequence(root_seed)
    while len(out) < k:
        for child in ss.spawn(k):
            s = int(child.generate_state(1, dtype=np.uint32)[0] >> 1)
            if s not in avoid and s not in out:
                out.append(s)
            if len(out) == k:
                break
    return out


def tasks(readings: Mapping[tuple[str, str], Mapping[str, tuple[str, int]]], seed_list: Sequence[int],
          runs_factor: int = RUNS_FACTOR) -> list[Task]:
    """Every (record, reading, seed, runs) task of the sweep, and the primary readings at ``runs_factor``× runs.

    Parameters
    ----------
    readings : mapping
        From :func:`stochastic_readings`.
    seed_list : sequence of int
        From :func:`seeds`: distinct seeds below 2**31 (a repeated seed would run the same tasks twice and count as two
        reseeds; a larger one is refused before any is hashed).
    runs_factor : int
        >= 1; 1 runs no scaled task.

    Returns
    -------
    list of Task
        One task per reading and seed of ``seed_list``, by record; then, if ``runs_factor`` > 1, each primary at the
        first seed with that many times the runs.

    Raises
    ------
    ValueError
        Before any task is built (fuzz 40b C6, C7): ``runs_factor`` times a primary reading's runs beyond the ceiling
        of a run count (``10**7``: its task would be refused only on a worker, after the sweep), naming
        ``runs_factor``; more readings and tasks (seeds x readings, plus the scaled primaries) than the work budget
        checks and builds in about 10 CPU-s (``READING_WORK`` units a reading and ``RECORD_WORK`` a record, counted by
        iterating them before any is checked, whatever their ``len()`` says, and ``TASK_WORK`` units a task: about
        330,000 readings at one seed, 500,000 tasks of the book's 512 readings; ``seed_list`` counted by its length
        before any seed is read), naming ``readings`` and ``seed_list``;
        a ``readings`` that yields more records or readings when read than when counted; a ``seed_list`` entry of
        2**31 or more (checked before any seed is hashed), naming ``seed_list[i]``.
    """
    runs_factor = count(runs_factor, "runs_factor")
    seed_list = sequence(seed_list, "seed_list")  # its length only: the seeds are read once the budget has passed
    instance_of(readings, Mapping, "readings")
    # counted before any reading is checked (fuzz 41b C1), from what iterating them yields (fuzz 42b C3: a Mapping whose
    # __len__ lies), every record too (D3); _readings then reads no more than was counted; the seeds by len(seed_list)
    # before any is read (fuzz 62a C3: they were checked and hashed first, 6.9-9.0 CPU-s for 10**7)
    n_records, n_readings = _reading_count(readings, len(seed_list), runs_factor > 1)
    seed_list = _seed_list(seed_list)
    readings = _readings(readings, runs_factor, (n_records, n_readings))
    if runs_factor > 1 and readings:
        top = max(rs["primary"][1] for rs in readings.values())
        if top * runs_factor > COUNT_CEILINGS["runs"]:
            raise ValueError(f"runs_factor x a primary reading's runs must be at most {COUNT_CEILINGS['runs']:.0e} (the "
                             f"ceiling of a run count), got runs_factor = {runs_factor} x {top} runs")
    out = []
    for (src, rid), rs in sorted(readings.items()):
        for key, (kind, runs) in rs.items():
            out += [Task(src, rid, key, kind, s, runs) for s in seed_list]
        if runs_factor > 1:
            kind, runs = rs["primary"]
            out.append(Task(src, rid, "primary", kind, seed_list[0], runs * runs_factor, scaled=True))
    return out


def _seed_list(seed_list: object) -> list[int]:
    """The sweep's seeds (rule 12): distinct seeds each below ``_SEED_END`` (2**31, the seeds :func:`seeds` derives), a
    larger one refused naming ``seed_list[i]`` by a comparison (which reads an int's size, not its digits) before any is
    hashed or compared with another (fuzz 53a C3's class: 2,000 copies of ``1 << 10**7`` were compared and hashed for
    1.1 CPU-s before the repeat was refused; 60,000, about 33 CPU-s)."""
    items = sequence(seed_list, "seed_list")
    for i, v in enumerate(items):
        if is_integer(v) and v >= _SEED_END:
            raise ValueError(f"seed_list[{i}] must be a seed of the sweep, below 2**31 (seeds() derives 31-bit seeds), "
                             f"got an integer of {int(v).bit_length():,} bits")
    return distinct(check_seeds(items, "seed_list"), "seed_list")


def _judged(ev: Evidence, margin: Mapping[str, float]) -> Evidence:
    if isinstance(ev, (Comparison, ExactComparison, Conjunction)):
        return ev.with_margin(margin.get("absolute"), margin.get("relative"))
    return ev


@process_cache(maxsize=16)
def _claims_file(path: str, mtime_ns: int) -> C.ClaimsFile:
    """A claim file read once per worker process (and again only when it changes)."""
    return C.load(path)


def run_task(task: Task, root: str | None = None) -> TaskResult:
    """Run one task: the record's evidence function under the task's seed and runs, judged by the rulebook.

    Parameters
    ----------
    task : Task
    root : str, optional
        The repository (default: the working directory's).

    Returns
    -------
    TaskResult
        Failures of the evidence function raise (Dask retries the task, then reports it).

    Raises
    ------
    TypeError
        ``task`` is not a :class:`Task`, ``root`` not a path.
    ValueError
        ``root`` is not inside the book's repository, or it has no claim file for ``task.source``.
    """
    instance_of(task, Task, "task")
    t0 = time.perf_counter()
    path = _ledger_dir(root).parent / "claims" / f"{task.source}.yaml"
    if not path.is_file():
        raise ValueError(f"task.source: no claim file {path} for the source {shown(task.source)}")
    cf = _claims_file(str(path), path.stat().st_mtime_ns)
    spec = cf.record(task.record)
    ev = _judged(C.evaluate(spec, task.reading, task.seed, task.runs), cf.margin(spec))
    return TaskResult(task, ev.status(), time.perf_counter() - t0)


def summarise(results: Sequence[TaskResult], seed_list: Sequence[int],
              committed: Mapping[str, str]) -> dict[str, JSONObject]:
    """Each record's status under every reseed (rule R5 over its readings) and at the scaled run count.

    Parameters
    ----------
    results : sequence of TaskResult
        At most one result per task (record, reading, seed and whether scaled), each of a seed of ``seed_list``.
    seed_list : sequence of int
        Distinct seeds below 2**31, as given to :func:`tasks`.
    committed : mapping
        Record id → the status committed in the ledger: one of :data:`fusion.book.rulebook.STATUSES`, or None.

    Returns
    -------
    dict
        Record id → {"committed", "reseeds": [status per seed], "scaled", "stable", "k", "flag", "failed"}.

    Raises
    ------
    TypeError
        ``results`` not of :class:`TaskResult`, ``committed`` not a mapping, a committed status not text.
    ValueError
        Two results of one task, a result of a seed not in ``seed_list``, a repeated seed or one of 2**31 or more
        (``seed_list[i]``, checked before any is hashed), a committed status not
        one of the rulebook's; ``committed`` of more than 10**7 entries (counted by iterating its keys before any
        entry is read), or yielding more entries when read than when counted (then read once: its entries are
        checked and used as that one read, fuzz 57a D1); ``results``, ``seed_list`` and
        ``committed`` beyond the work budget (rule 17: their results and committed entries, then their records x
        seeds, counted before any is read or judged).

    Notes
    -----
    A reseed's status is rule R5 over the readings the sweep reruns, without the record's stated
    assumptions (they are text, not rerun): where the record states assumptions, a reseed's "reproduced"
    agrees with the committed "reproduced under stated assumptions" (:func:`_same`). ``scaled`` is the
    primary reading's own status at the scaled run count (no other reading is rerun there).
    """
    by: dict[str, list[TaskResult]] = {}
    seed_list = sequence(seed_list, "seed_list")  # its length: read once the budget has passed (fuzz 62a C3)
    instance_of(committed, Mapping, "committed")
    n_committed = sum(1 for _ in itertools.islice(iter(committed), MAX_COUNT + 1))  # keys only, none read (53a C2)
    if n_committed > MAX_COUNT:
        raise ValueError(f"committed has more than {MAX_COUNT:,} entries (rule 9: the entries of a mapping argument "
                         "are a size; the ledger holds a few hundred records)")
    results = sequence(results, "results")  # its length, before any result is read (fuzz 53a: walked before budget)
    # rule 17 (fuzz 49b C6): the results and committed first (at least one record if any), then, once grouped (which
    # their units pay for), every record x seed cell
    _summary_work(len(results), min(1, len(results)), len(seed_list), n_committed)
    seed_list = _seed_list(seed_list)
    given, committed = committed, {}   # read once into a plain dict, checked and used as that one read (fuzz 57a D1)
    for j, (rid, status) in enumerate(given.items()):
        if j >= n_committed:
            raise ValueError(f"committed yielded more than the {n_committed:,} entries counted before they were read "
                             "(a mapping whose items change while it is read)")
        committed[rid] = status
        if status is not None and not isinstance(status, str):
            raise TypeError(f"committed[{shown(rid)}] must be a status (str), got {shown(status)}")
        if status is not None and status not in R.STATUSES:
            raise ValueError(f"committed[{shown(rid)}] must be one of {R.STATUSES} or None, got {shown(status)}")
    seen: dict[tuple[str, str, int, bool], int] = {}
    known = set(seed_list)
    results = _tasks(results, "results", TaskResult)
    cells: dict[str, dict[int, list[TaskResult]]] = {}  # record -> seed -> its unscaled results, in results' order
    for i, r in enumerate(results):
        t = r.task
        if t.seed not in known:  # a result of another sweep would be dropped without a word
            raise ValueError(f"results[{i}] is of seed {t.seed}, which is not in seed_list")
        key = (t.record, t.reading, t.seed, t.scaled)
        if key in seen:  # which of the two counted would depend on their order
            raise ValueError(f"results[{i}] and results[{seen[key]}] are two results of one task (record "
                             f"{shown(t.record)}, reading {shown(t.reading)}, seed {t.seed}"
                             f"{', scaled' if t.scaled else ''})")
        seen[key] = i
        by.setdefault(t.record, []).append(r)
        if not t.scaled:
            cells.setdefault(t.record, {}).setdefault(t.seed, []).append(r)
    _summary_work(len(results), len(by), len(seed_list), n_committed)
    out: dict[str, dict[str, Any]] = {}
    for rid, rs in sorted(by.items()):
        failed = [asdict(r.task) | {"error": r.error} for r in rs if r.status is None]
        statuses = []
        mine_by_seed = cells.get(rid, {})
        for s in seed_list:
            mine = mine_by_seed.get(s, [])
            prim = next((r for r in mine if r.task.reading == "primary"), None)
            if prim is None or prim.status is None or any(r.status is None for r in mine):
                statuses.append(None)
                continue
            readings = [(r.task.kind, r.status, r.task.runs) for r in mine if r.task.reading != "primary"]
            statuses.append(R.record_status(prim.status, readings, prim.task.runs, False)[0])
        scaled = next((r.status for r in rs if r.task.scaled), None)
        want = committed.get(rid)
        k = sum(s is not None and _same(s, want) for s in statuses)
        out[rid] = {"committed": want, "reseeds": statuses, "scaled": scaled, "k": k, "K": len(seed_list),
                    "flag": k < len(seed_list) or (scaled is not None and not _same(scaled, want)),
                    "failed": failed}
    return out


def _summary_work(results: int, records: int, seeds: int, committed: int = 0) -> int:
    """The units of :func:`summarise`: ``results`` checked, grouped and judged, ``SUMMARY_RESULT_WORK`` units each,
    ``records x seeds`` statuses, ``SUMMARY_CELL_WORK`` units each (``seeds`` by ``len(seed_list)``, before any seed is
    read: fuzz 62a C3), and ``committed`` entries checked,
    ``SUMMARY_COMMITTED_WORK`` units each; refused beyond the work budget (rule 17) naming ``results``, ``seed_list``
    and ``committed``."""
    return work((results * SUMMARY_RESULT_WORK + records * seeds * SUMMARY_CELL_WORK
                 + committed * SUMMARY_COMMITTED_WORK,),
                f"results and seed_list and committed ({results:,} results, {SUMMARY_RESULT_WORK:,} units each, "
                f"{records:,} records x {seeds:,} seeds, {SUMMARY_CELL_WORK:,} units a record's seed, and "
                f"{committed:,} committed entries, {SUMMARY_COMMITTED_WORK:,} units each)")


def _same(status: str | None, committed: str | None) -> bool:
    """Whether a reseed's status agrees with the committed one (assumptions are not re-run: R5's qualifier aside)."""
    q = "reproduced under stated assumptions"
    norm = {q: "reproduced"}
    return status is not None and norm.get(status, status) == norm.get(committed or "", committed)


def _versions() -> dict[str, str]:
    return {p: version(p) for p in ("numpy", "scipy", "dask", "distributed", "fusion-book")}


def _commit(root: Path) -> str:
    try:
        return subprocess.run(["git", "rev-parse", "HEAD"], cwd=root, check=True, capture_output=True,
                              text=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def run_batch(batch: Sequence[Task], root: str | None = None) -> list[TaskResult]:
    """Run tasks that share a source and a seed in one worker, so that they share its cached studies.

    The chapters' evidence functions cache the studies they run (a network study serves every record and
    reading that reads it at that seed); one batch per (source, seed, run count) lets a worker compute each
    study once instead of once per task. Each task is tried :data:`RETRIES` + 1 times; one that still fails
    comes back as a result with its error, so a failure is reported by record, reading and seed.

    Parameters
    ----------
    batch : sequence of Task
    root : str, optional
        The repository (default: the working directory's).

    Returns
    -------
    list of TaskResult
        In the order of ``batch``.

    Raises
    ------
    TypeError
        ``batch`` is not a sequence of :class:`Task`, ``root`` not a path (bad arguments are refused, never turned
        into failed tasks).
    ValueError
        ``root`` is not inside the book's repository.
    """
    batch = _tasks(batch, "batch")
    if root is not None:
        _ledger_dir(root)
    out = []
    for task in batch:
        error = ""
        for _ in range(RETRIES + 1):
            t0 = time.perf_counter()
            try:
                out.append(run_task(task, root))
                break
            except Exception as exc:  # noqa: BLE001 - reported with the task, never dropped
                error = repr(exc)
        else:
            out.append(TaskResult(task, None, time.perf_counter() - t0, error))
    return out


def _reading_count(readings: Mapping, seeds: int, scaled: bool) -> tuple[int, int]:
    """The records and readings of ``readings`` as iterating it yields them (never its ``len()``, which a Mapping may
    state falsely: fuzz 42b C3), refused by :func:`tasks`' work budget (rule 17, naming ``readings`` and ``seed_list``)
    as soon as their count passes it, before any is checked: a record weighs ``RECORD_WORK`` units (and a scaled task's
    ``TASK_WORK``), a reading ``READING_WORK`` plus a task's per seed."""
    per_record = RECORD_WORK + (TASK_WORK if scaled else 0)
    per_reading = READING_WORK + seeds * TASK_WORK
    # the keys first, one past the budget at most (iterating them reads no value: 10**7 records in well under 1 CPU-s)
    records = sum(1 for _ in itertools.islice(iter(readings), MAX_WORK // per_record + 1))
    n = 0
    units = records * per_record
    for rs in itertools.islice(readings.values(), records if units <= MAX_WORK else 0):
        if isinstance(rs, Mapping):  # one that is not is refused by _readings
            left = max(0, (MAX_WORK - units) // per_reading + 1)  # the readings past the budget: one is enough
            k = sum(1 for _ in itertools.islice(iter(rs), left))
            n += k
            units += k * per_reading
        if units > MAX_WORK:
            break
    over = records * per_record > MAX_WORK  # the keys past the budget: no reading was counted
    work((units,), f"readings and seed_list ({'at least ' if units > MAX_WORK and not over else ''}{n:,} readings, "
         f"{READING_WORK:,} units each to check, x {seeds:,} seeds, {TASK_WORK:,} units a task, in "
         f"{'at least ' if over else ''}{records:,} records, {RECORD_WORK:,} units each)")
    return records, n


def _readings(readings: object, runs_factor: int, counted: tuple[int, int] | None = None) -> dict:
    """Check the mapping of :func:`stochastic_readings` (rule 12): ``(source, record) -> {reading: (kind, runs)}``;
    ``counted``: the records and readings :func:`_reading_count` counted, beyond which nothing is read (a mapping
    that yields more on a second pass is refused)."""
    instance_of(readings, Mapping, "readings")
    checked: dict = {}
    records = n = 0
    for key, rs in readings.items():
        records += 1
        if counted is not None and records > counted[0]:
            raise ValueError(f"readings yielded more than the {counted[0]:,} records counted before they were read (a "
                             "mapping whose items change while it is read)")
        where = f"readings[{key!r}]"
        if not (isinstance(key, tuple) and len(key) == 2 and all(isinstance(x, str) for x in key)):
            raise TypeError(f"readings: every key must be a (source, record) pair of str, got {shown(key)}")
        instance_of(rs, Mapping, where)
        if runs_factor > 1 and "primary" not in rs:
            raise ValueError(f"{where} lacks the 'primary' reading that runs_factor = {runs_factor} scales")
        for name, v in rs.items():
            n += 1
            if counted is not None and n > counted[1]:
                raise ValueError(f"readings yielded more than the {counted[1]:,} readings counted before they were "
                                 "read (a mapping whose items change while it is read)")
            if not (isinstance(name, str) and isinstance(v, (tuple, list)) and len(v) == 2 and isinstance(v[0], str)):
                raise TypeError(f"{where}[{shown(name)}] must be a (kind, runs) pair, got {shown(v)}")
            if v[0] not in R.READING_KINDS:
                raise ValueError(f"{where}[{shown(name)}] kind must be one of {R.READING_KINDS}, got {shown(v[0])}")
            checked.setdefault(key, {})[name] = (v[0], count(v[1], f"{where}[{name!r}] runs"))  # the int read
    return checked


def _tasks(task_list: object, name: str, cls: type = Task) -> list:
    """A sequence of :class:`Task` (or :class:`TaskResult`), each entry checked by name (rule 12)."""
    items = sequence(task_list, name)
    for i, t in enumerate(items):
        instance_of(t, cls, f"{name}[{i}]")
    return items


def batches(task_list: Sequence[Task]) -> list[list[Task]]:
    """The tasks grouped by (source, seed, scaled): the unit of work sent to a worker (:func:`run_batch`).

    Parameters
    ----------
    task_list : sequence of Task

    Returns
    -------
    list of list of Task
        Longest batch first (more tasks first), the tasks of a batch in ``task_list`` order.
    """
    groups: dict[tuple[str, int, bool], list[Task]] = {}
    for t in _tasks(task_list, "task_list"):
        groups.setdefault((t.source, t.seed, t.scaled), []).append(t)
    return sorted(groups.values(), key=lambda g: (-sum(t.runs for t in g), g[0].source, g[0].seed))


def sweep(task_list: Sequence[Task], client: Any, root: Path, progress: bool = True,
          on_result: Callable[[TaskResult], None] | None = None) -> list[TaskResult]:
    """Run ``task_list`` on a Dask ``client``, in batches (:func:`batches`); failures come back with an error.

    Parameters
    ----------
    task_list : sequence of Task
    client : distributed.Client
    root : pathlib.Path
        The repository, passed to every task.
    progress : bool
        Show Dask's progress bar (one step per batch).
    on_result : callable, optional
        Called with each result as it arrives.

    Returns
    -------
    list of TaskResult
        In the order of ``task_list``.
    """
    from distributed import as_completed
    from distributed import progress as bar

    groups = batches(task_list)
    futures = client.map(run_batch, groups, root=str(root), retries=RETRIES, pure=False)
    index = {f.key: i for i, f in enumerate(futures)}
    if progress:
        bar(futures, interval="2s")
    position = {id(t): i for i, t in enumerate(task_list)}
    out: list[TaskResult | None] = [None] * len(task_list)
    for f in as_completed(futures):
        group = groups[index[f.key]]
        if f.status == "error":  # the worker itself failed (retried by Dask first)
            got = [TaskResult(t, None, 0.0, repr(f.exception())) for t in group]
        else:
            got = f.result()
        for t, r in zip(group, got):
            out[position[id(t)]] = r
            if on_result is not None:
                on_result(r)
    return [r for r in out if r is not None]


def main(argv: Sequence[str] | None = None) -> int:
    """``make stability``: run the sweep and write ``book/ledger/stability.json``.

    Parameters
    ----------
    argv : sequence of str, optional
        Command-line arguments (default: ``sys.argv[1:]``); ``--help`` lists them.

    Returns
    -------
    int
        0 when every task ran; 1 when a task failed (named on stderr and in the file).
    """
    p = argparse.ArgumentParser(prog="python -m fusion.book.stability", description=_DESCRIPTION)
    p.add_argument("--scheduler", help="address of an existing Dask scheduler (default: a LocalCluster here)")
    p.add_argument("--workers", type=int, default=2, help="local workers (default 2)")
    p.add_argument("--reseeds", type=int, default=RESEEDS, help=f"K, fresh seeds per reading (default {RESEEDS})")
    p.add_argument("--runs-factor", type=int, default=RUNS_FACTOR,
                   help=f"the primary reading also at this many times the runs (default {RUNS_FACTOR})")
    p.add_argument("--root-seed", type=int, default=ROOT_SEED)
    p.add_argument("--only", nargs="*", default=(), help="record ids (default: every stochastic record)")
    p.add_argument("--out", type=Path, help="results file (default book/ledger/stability.json)")
    p.add_argument("--merge", action="store_true",
                   help="keep the stored results of the records not run now (same root seed and K; each record "
                        "keeps the runs factor it was run with)")
    args = p.parse_args(argv)
    from distributed import Client, LocalCluster

    root = ledger_dir().parent.parent
    readings = stochastic_readings(root)
    if args.only:
        readings = {k: v for k, v in readings.items() if k[1] in set(args.only)}
    ledger = _ledger_records(ledger_dir(root))
    chapter_seeds = {int(r["evidence"].get("seed") or -1) for r in ledger if isinstance(r.get("evidence"), dict)}
    seed_list = seeds(args.reseeds, args.root_seed, chapter_seeds)
    task_list = tasks(readings, seed_list, args.runs_factor)
    print(f"{len(readings)} stochastic records, {len(task_list)} tasks, seeds {seed_list}", file=sys.stderr)
    t0 = time.perf_counter()
    if args.scheduler:
        client = Client(args.scheduler)
    else:
        import dask

        # non-daemonic workers: an evidence function may run its own process pool (chapter 06's tracking study)
        dask.config.set({"distributed.worker.daemon": False})
        client = Client(LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True,
                                     dashboard_address=None))
    with client:
        results = sweep(task_list, client, root)
        workers = len(client.scheduler_info()["workers"])
    wall = time.perf_counter() - t0
    committed = {r["id"]: r["status"] for r in ledger}
    records = summarise(results, seed_list, committed)
    fresh = set(records)
    failed = [r for r in results if r.status is None]
    doc = {
        "date": _dt.date.today().isoformat(), "root_seed": args.root_seed, "K": args.reseeds, "seeds": seed_list,
        "runs_factor": args.runs_factor, "versions": _versions(), "commit": _commit(root),
        "machine": f"{platform.machine()}, {workers} workers, Python {platform.python_version()}",
        "wall_seconds": round(wall, 1),
        "readings": {rid: {k: {"kind": kind, "runs": runs} for k, (kind, runs) in rs.items()}
                     for (_, rid), rs in sorted(readings.items())},
        "task_seconds": {rid: round(sum(r.seconds for r in results if r.task.record == rid), 2)
                         for (_, rid) in sorted(readings)},
        "records": records,
    }
    out = args.out or ledger_dir(root) / STABILITY_FILE
    if args.merge and out.is_file():
        old = file_json(out, f"--merge: {out}")   # the chapter layer's one reader (regular UTF-8 JSON, bounded)
        if not isinstance(old, dict) or not {"root_seed", "K", "runs_factor", "records", "readings"} <= set(old):
            raise SystemExit(f"--merge: {out} is not a stability file (an object of root_seed, K, runs_factor, "
                             "records and readings)")
        same = (old["root_seed"], old["K"]) == (args.root_seed, args.reseeds)
        if not same:
            raise SystemExit(f"--merge: {out} was run with another root seed or K")
        current = stochastic_readings(root)
        keep = {rid for (_, rid) in current} - set(records)
        for rid in keep & set(old["records"]):
            records[rid] = old["records"][rid]
            doc["readings"][rid] = old["readings"][rid]
            doc["task_seconds"][rid] = old["task_seconds"].get(rid, 0.0)
        doc["records"] = dict(sorted(records.items()))
        doc["readings"] = dict(sorted(doc["readings"].items()))
        doc["wall_seconds"] = round(old.get("wall_seconds", 0.0) + wall, 1)
    for rid in records:
        records[rid].setdefault("commit", doc["commit"])
        records[rid].setdefault("runs_factor", old["runs_factor"] if args.merge and out.is_file()
                                and rid not in fresh else args.runs_factor)
    try:   # whole or not at all: a failed write keeps the committed file (fuzz 49b C5, the ledger's writer)
        write_file_text(Path(out), json.dumps(doc, ensure_ascii=False, indent=1) + "\n", "--out")
    except ValueError as exc:
        raise SystemExit(str(exc)) from None
    for r in failed:
        print(f"FAILED: {r.task.record} reading {r.task.reading} seed {r.task.seed} runs {r.task.runs}: {r.error}",
              file=sys.stderr)
    flagged = [rid for rid, v in records.items() if v["flag"]]
    print(f"wrote {out} in {wall:.0f} s; {len(flagged)} records change status under reseeding or at "
          f"{args.runs_factor}× runs: {flagged}", file=sys.stderr)
    return 1 if failed else 0


if __name__ == "__main__":
    # ``python -m`` runs this file as ``__main__``: take main from the imported module, so that the functions sent
    # to the workers (run_batch) are pickled by reference to fusion.book.stability, not by value with this
    # module's globals (a process_cache wrapper cannot be pickled by value: "Could not serialize _MapExpr")
    from fusion.book.stability import main as _main

    raise SystemExit(_main())
