r"""Chapter 02's records: evidence by record id (:data:`EVIDENCE`, :func:`evidence`), the stochastic records'
evidence at any seed, the numbers the claim texts quote, and the reseeding and robustness lines."""

from __future__ import annotations

import functools
import os
from collections import Counter
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from fusion.book._few_runs import runs_first, study_runs_named
from fusion._frozen import constant
from fusion._validation import count, one_of, read_mapping, records_of, text
from fusion.book.rulebook import STATUSES
from fusion.book.study_cache import study_cache
from fusion.book.chapters.lecture import _source_claims, evidence_at, reading_function, reading_key
from fusion.book.ledger import Comparison, Evidence, Unverifiable, ledger_dir
from fusion.book.chapters.lecture_weighting.study_evidence import (
    _ev_awf_accuracy, _ev_awf_adapts, _ev_awf_estimated, _ev_awf_fault_tolerance, ev_awf_lumv, ev_awf_lumv_fixed,
    ev_awf_no_prior, ev_awf_optimal, ev_awf_unbiased, _ev_belief_accuracy, _ev_belief_objective, ev_belief_perron,
    _ev_cc_accuracy, _ev_cc_beats_mean, ev_ls_beats_mean, ev_ls_below_every_sensor, ev_ls_diminishing,
    ev_ls_learning, ev_ls_normal, ev_ls_tracks, ev_ls_unbiased, _need)
from fusion.book.chapters.lecture_weighting.studies import SEED, SEED_OFFSETS, _reads_budget, _Studies
from fusion.book.glue import GlueValues, _glue_id_part
from fusion.scenarios.lecture_weighting.consistency import FaultCase
from fusion.scenarios.lecture_weighting.estimators import CHECKED, AwfMethod
from fusion._counts import seed as check_seed
from fusion._shown import shown
from fusion._paths import file_json


__all__ = [
    "reseeding_glue",
    "robustness_glue",
    "ev_awf_estimated",
    "ev_awf_adapts",
    "ev_awf_fault_tolerance",
    "ev_awf_accuracy",
    "ev_cc_beats_mean",
    "ev_cc_accuracy",
    "ev_belief_objective",
    "ev_belief_accuracy",
    "STOCHASTIC",
    "EVIDENCE",
    "evidence",
    "ledger_values",
]


def _keyed_records(records: object, prefix: str, keys: tuple[str, ...]) -> list[tuple[str, Mapping[str, Any]]]:
    """``records`` (ledger records holding ``keys``) each with its glue key, ``prefix`` + the id without ``lec-``,
    dashes as underscores: one check of the fields the reseeding and robustness lines read (fuzz 21b, R).

    An ``id`` is a non-empty string of ASCII letters, digits, ``-`` and ``_`` (it becomes a glue-key part,
    ``fusion.book.glue._glue_id_part``), and no two records give one glue key (a repeated id, or ``lec-a-b`` and
    ``lec-a_b``: the second line would silently replace the first); a ``status`` is one of the rulebook's
    :data:`~fusion.book.rulebook.STATUSES`, ``runs`` an integer >= 1 or ``None`` (a record without runs), a
    ``robustness`` a string or ``None``. A TypeError (wrong type) or ValueError naming ``records[i]`` otherwise."""
    records = records_of(records, "records", keys)
    out: list[tuple[str, Mapping[str, Any]]] = []
    first: dict[str, int] = {}
    for i, r in enumerate(records):
        rid = text(r["id"], f"records[{i}]['id']")
        if not rid:
            raise ValueError(f"records[{i}]['id'] must be a record id, got an empty string")
        key = prefix + _glue_id_part(rid, f"records[{i}]['id']", "lec-")   # an ASCII identifier (fuzz 36b D2)
        if key in first:
            j = first[key]
            raise ValueError(f"records[{i}] (id {shown(rid)}) gives the glue key {key} of records[{j}] (id "
                             f"{shown(records[j]['id'])}): record ids must not repeat, nor differ only by '-' and '_'")
        first[key] = i
        if "status" in r:  # the plain text the checks return (rule 19; fuzz 32b C1)
            r = {**r, "status": one_of(r["status"], STATUSES, f"records[{i}]['status']")}
        if r.get("runs") is not None:  # the int read, never the caller's object (fuzz 29a C2)
            r = {**r, "runs": count(r["runs"], f"records[{i}]['runs']", maximum=None)}
        if r.get("robustness") is not None:
            r = {**r, "robustness": text(r["robustness"], f"records[{i}]['robustness']")}
        out.append((key, r))
    return out


def reseeding_glue(records: Sequence[Mapping[str, Any]], root: Path | None = None) -> GlueValues:
    """Each stochastic record's status with what the reseeding sweep (``book/ledger/stability.json``) found.

    The status is the record's (the rulebook's, at the chapter's runs); whether it moves comes from the sweep's
    results, which the lead's ``make stability`` writes. A record the sweep flags reads "<status> at the chapter's
    n runs, a status that moves under reseeding (...)", naming every other status and how often; a record whose
    reseeds differ only by rule R5's qualifier (a reseed states no assumptions) says so; any other record reads
    "stable in k of K reseeds and at r× the runs". The scaled run reruns the primary reading only. ``k`` and
    whether the status moves are counted from the sweep's reseeds against the record's status given here (as
    ``make stability`` counts them against the status it committed), so that a ledger status that changed since
    the sweep is not read as stable.

    A task that failed in the sweep (``make stability`` writes ``null`` for its status) is counted as failed, not
    as a status: "1 of 5 reseeds failed to run" or "the run at r× the runs failed" is added in brackets, ``k``
    counts the reseeds that ran and kept the status, and a record that moved only by failed tasks reads
    "stable in k of K reseeds" with the failures named, not "a status that moves". A sweep with
    ``runs_factor`` 1 runs no scaled task (``"scaled": null``): its line has no "at r× the runs" clause.

    Parameters
    ----------
    records : sequence of mapping
        Ledger records (:meth:`fusion.book.ledger.Ledger.records`): ``id``, ``status`` and ``runs``.
    root : pathlib.Path, optional
        Where to look for the book's ledger directory, a directory in the book's repository (default: the working
        directory).

    Returns
    -------
    GlueValues
        ``lec_rs_<id without "lec-", dashes as underscores>`` → the text, for every record the sweep covers.

    Raises
    ------
    TypeError
        ``records`` not a sequence, a record not a mapping, its ``id`` or ``status`` not a string, its ``runs``
        not an integer (or ``None``); ``root`` not a path.
    ValueError
        A record without ``id`` or ``status``, an empty ``id`` or one not of ASCII letters, digits, ``-`` and
        ``_``, two records of one glue key (a repeated id, or ids that differ only by ``-`` and ``_``), a
        ``status`` not one of the rulebook's :data:`~fusion.book.rulebook.STATUSES`, ``runs`` below 1; ``root``
        not inside the book's repository; its ``book/ledger/stability.json`` (when it exists) not a regular UTF-8
        JSON file of at most 16 MB
        (``fusion._paths.file_json``: a FIFO, a device, a folder), not an object of ``records``, or a record
        that the function reads lacking ``k``, ``K``, ``reseeds``, ``scaled`` or ``flag`` or holding them
        without the sense ``make stability`` writes (a status not the rulebook's, ``K`` < 1 or not the number
        of ``reseeds``, ``k`` outside 0..K or above the reseeds that ran, a ``runs_factor`` not an integer
        >= 1; a ``null`` status is a failed task, see above): named by ``root``, the file
        and the record.
    """
    keyed = _keyed_records(records, "lec_rs_", ("id", "status"))
    if root is not None and not isinstance(root, (str, os.PathLike)):
        raise TypeError(f"root must be a pathlib.Path (or None), got {type(root).__name__}")
    try:
        path = ledger_dir(None if root is None else Path(root)) / "stability.json"
    except (FileNotFoundError, ValueError) as exc:   # no _toc.yml above it; not an existing folder (ledger_dir)
        if root is None:
            raise
        raise ValueError(f"root = {shown(str(root))} is not a folder inside the book's repository (no _toc.yml in it "
                         "or above it)") from exc
    if not path.exists():
        return {}
    data = _stability(path, "root" if root is not None else "the repository")
    default, stab = data.get("runs_factor", 10), data.get("records", {})
    out: GlueValues = {}
    for key, r in keyed:
        v = stab.get(r["id"])
        if v is None or not r.get("runs"):
            continue
        _stability_record(v, f"{'root' if root is not None else 'the repository'}: book/ledger/stability.json "
                             f"records[{shown(r['id'])}]")
        factor = v.get("runs_factor", default)   # each record keeps the factor it was swept with (--merge)
        out[key] = _reseeding_line(r["status"], int(r["runs"]), v, factor)
    return out


def _reseeding_line(status: str, runs: int, v: Mapping[str, Any], factor: int) -> str:
    """The text of one record's sweep ``v`` (checked by :func:`_stability_record`) for its ledger ``status`` at
    the chapter's ``runs``: a failed task (``null``) is named as failed, not read as a status (fuzz 38b C1); ``k``
    and the flag counted from the reseeds against ``status``, not read from the file (fuzz 39b C1)."""
    n, scaled = v["K"], v["scaled"]
    same = {"reproduced under stated assumptions": "reproduced"}   # rule R5's qualifier (stability._same)
    # k and the flag recounted against the caller's status, as make stability counts them against the status it
    # committed: the ledger may have moved since the sweep (fuzz 39b C1: a sweep of another status read as stable)
    k = sum(s is not None and same.get(s, s) == same.get(status, status) for s in v["reseeds"])
    flag = k < n or (scaled is not None and same.get(scaled, scaled) != same.get(status, status))
    failed = sum(s is None for s in v["reseeds"])
    others = Counter(s for s in v["reseeds"] if s is not None and s != status)
    parts = [f"{s} in {c} of {n} reseeds" for s, c in others.items()]
    if scaled is not None and scaled != status:
        parts.append(f"{scaled} at {factor}× the runs, the primary reading rerun")
    fails = [f"{failed} of {n} reseeds failed to run"] if failed else []
    if scaled is None and factor > 1:   # runs_factor 1 runs no scaled task; above it a null is a failed one
        fails.append(f"the run at {factor}× the runs failed")
    # the sweep flags a failed task too: the status moved only if a task that ran disagrees
    moved = flag and (k < n - failed
                           or (scaled is not None and same.get(scaled, scaled) != same.get(status, status)))
    head = f"{status} at the chapter's {runs:,} runs"
    if moved:
        return f"{head}, a status that moves under reseeding ({'; '.join(parts + fails)})"
    if parts:
        return (f"{head}, stable in {k} of {n} reseeds up to rule R5's qualifier, which a reseed does not state "
                f"({'; '.join(parts + fails)})")
    line = f"{head}, stable in {k} of {n} reseeds" + (f" and at {factor}× the runs" if scaled is not None else "")
    return line + (f" ({'; '.join(fails)})" if fails else "")


#: The fields of a record of ``book/ledger/stability.json`` that :func:`reseeding_glue` reads, and their types.
#: ``scaled`` is null where the sweep ran no scaled task (``runs_factor`` 1) or it failed.
_STABILITY_FIELDS: dict[str, type | tuple[type, ...]] = {"k": int, "K": int, "reseeds": list,
                                                          "scaled": (str, type(None)), "flag": bool}


def _stability(path: Path, where: str) -> dict[str, Any]:
    """``book/ledger/stability.json`` under ``where`` (the caller's ``root``), read by the one reader
    (``fusion._paths.file_json``) and checked as far as :func:`reseeding_glue` reads it (fuzz 35b B4): an object
    whose ``records`` is an object and whose ``runs_factor`` is an integer >= 1."""
    label = f"{where}: book/ledger/stability.json"
    data = file_json(path, label)
    if not isinstance(data, dict):
        raise ValueError(f"{label}: not a stability file (a JSON object), got a JSON {type(data).__name__}")
    if not isinstance(data.get("records", {}), dict):
        raise ValueError(f"{label}: 'records' must be an object (record id -> its sweep)")
    _runs_factor(data.get("runs_factor", 10), label)
    return data


def _runs_factor(factor: object, label: str) -> None:
    """A sweep's runs factor is what ``make stability`` writes (``fusion.book.stability.tasks``): an integer >= 1
    (fuzz 36b D3: 0 or -3 glued "at -3× the runs"), else a ValueError naming ``label``."""
    if not isinstance(factor, int) or isinstance(factor, bool) or factor < 1:
        raise ValueError(f"{label}: 'runs_factor' must be an integer >= 1 (the sweep's run multiple), got "
                         f"{shown(factor)}")


def _stability_record(v: object, label: str) -> None:
    """A record of the stability file holds the fields :func:`reseeding_glue` reads (:data:`_STABILITY_FIELDS`),
    else a ValueError naming ``label`` (the caller's ``root``, the file and the record) and the field; their sense
    as ``make stability`` writes them: statuses of the rulebook, ``K >= 1`` statuses in ``reseeds``,
    ``0 <= k <= K``, an integer ``runs_factor >= 1``."""
    if not isinstance(v, dict):
        raise ValueError(f"{label}: not a record (a JSON object), got a JSON {type(v).__name__}")
    for field, kind in _STABILITY_FIELDS.items():
        if field not in v:
            raise ValueError(f"{label} lacks the field '{field}' that reseeding_glue reads")
        if not isinstance(v[field], kind) or (kind is int and isinstance(v[field], bool)):
            what = "str or null" if field == "scaled" else kind.__name__  # type: ignore[union-attr]
            raise ValueError(f"{label}: '{field}' must be a JSON {what}")
    if not all(s is None or isinstance(s, str) for s in v["reseeds"]):
        raise ValueError(f"{label}: 'reseeds' must be a list of statuses (strings, null for a failed reseed)")
    # their sense too, as make stability writes them (fuzz 36b D3: "stable in 9 of 5 reseeds", "5 of 0" were glued)
    for i, s in enumerate([*v["reseeds"], v["scaled"]]):
        if s is not None and s not in STATUSES:
            where = f"'reseeds'[{i}]" if i < len(v["reseeds"]) else "'scaled'"
            raise ValueError(f"{label}: {where} must be one of the rulebook's statuses {STATUSES}, got {shown(s)}")
    if v["K"] < 1 or len(v["reseeds"]) != v["K"]:
        raise ValueError(f"{label}: 'K' must be the number of reseeds (>= 1, one status each in 'reseeds'), got "
                         f"K = {v['K']} with {len(v['reseeds'])} statuses")
    ran = sum(s is not None for s in v["reseeds"])
    if not 0 <= v["k"] <= ran:
        raise ValueError(f"{label}: 'k' must count the reseeds that ran and keep the status (0 <= k <= {ran}, K = "
                         f"{v['K']} with {v['K'] - ran} failed), got {v['k']}")
    if "runs_factor" in v:
        _runs_factor(v["runs_factor"], label)


def robustness_glue(records: Sequence[Mapping[str, Any]]) -> GlueValues:
    """Each record's robustness line as the ledger writes it (how many counted readings hold, what is shown apart).

    Parameters
    ----------
    records : sequence of mapping
        Ledger records (:meth:`fusion.book.ledger.Ledger.records`): ``id`` and ``robustness``.

    Returns
    -------
    GlueValues
        ``lec_rob_<id without "lec-", dashes as underscores>`` → the line, for every record that has one.

    Raises
    ------
    TypeError
        ``records`` not a sequence, a record not a mapping, its ``id`` or ``robustness`` not a string (a
        ``status`` it holds not a string, its ``runs`` not an integer).
    ValueError
        A record without ``id``, an empty ``id`` or one not of ASCII letters, digits, ``-`` and ``_``, two records
        of one glue key (a repeated id, or ids that differ only by ``-`` and ``_``), or a ``status`` it holds not
        one of the rulebook's.
    """
    return {key: r["robustness"] for key, r in _keyed_records(records, "lec_rob_", ("id",)) if r.get("robustness")}


#: The part of a record's studies a reading needs, for the records whose readings use two studies.
_PARTS: dict[str, Callable[[str], str]] = {"lec-awf-adapts": lambda k: "change" if k.startswith("change-") else "regime",
                          "lec-awf-accuracy": lambda k: "bench" if k.startswith("bench-") else "window"}


#: The keys of :func:`study` a reading of each stochastic record runs, by its part (``_PARTS``; ``None`` for a
#: record read whole): E2.3's readings run the study at X = 900 and at X = 0 (``_level_x0``).
_READS: dict[str, dict[str | None, tuple[str, ...]]] = {
    "lec-awf-estimated": {None: ("s21",)}, "lec-awf-adapts": {"regime": ("sreg",), "change": ("schg",)},
    "lec-awf-fault-tolerance": {None: ("s23", "s23x0")},
    "lec-awf-accuracy": {"window": ("s23", "s23x0"), "bench": ("bench",)},
    "lec-cc-beats-mean": {None: ("s23", "s23x0")}, "lec-cc-accuracy": {None: ("s23", "s23x0")},
    "lec-belief-objective": {None: ("s24b",)}, "lec-belief-accuracy": {None: ("bench",)}}


def _record_budget(rid: str, readings: Sequence[tuple[str, int]]) -> int:
    """Rule 17 of the readings ``readings`` ((reading key, runs)) of the stochastic record ``rid`` read together
    (:func:`fusion.book.chapters.lecture.evidence_at`): every study they run, summed, before any (fuzz 62a: the
    regime study of ``lec-awf-adapts`` ran ~36 CPU-s at 1,800 runs before its ``change-*`` readings' study refused)."""
    return _reads_budget((k, runs) for key, runs in readings
                         for k in _READS[rid][_PARTS[rid](key) if rid in _PARTS else None])


@study_cache(maxsize=32)
def _readings(rid: str, seed: int, runs: int, part: str | None) -> dict[str, Evidence]:
    """Every reading of ``rid`` (or of its ``part``) on the studies at ``seed`` and ``runs``, cached: a record's
    readings are built together, once."""
    st = _Studies(seed, runs)
    return _FROM_STUDIES[rid](st, part) if part is not None else _FROM_STUDIES[rid](st)


@functools.cache
def _claim_readings(rid: str) -> frozenset[str]:
    """The reading keys of the stochastic record ``rid`` in the claim file, ``"primary"`` included (read once)."""
    spec = _source_claims().record(rid)
    return frozenset({"primary", *(r.key for r in spec.readings)})


def _at(rid: str, settings: Mapping[str, Any], seed: int, runs: int) -> Evidence:
    """Reading ``settings["reading"]`` of the stochastic record ``rid`` on the studies at ``seed`` and ``runs``."""
    key = reading_key(settings)
    known = _claim_readings(rid)
    if key not in known:  # before the studies run: an unknown reading is named first, not a run count (fuzz 19)
        raise ValueError(f"settings: record {rid} has no reading {shown(key)}; it has {sorted(known)}")
    # every reading of these records (of a part, built together) compares ``runs`` paired runs without a reason: rule
    # R4's refusal before the studies, after the reading is named (fuzz 57c; reading_function's runs_named names it)
    runs = runs_first(runs)
    part = _PARTS[rid](key) if rid in _PARTS else None
    _reads_budget((k, runs) for k in _READS[rid][part])  # the studies it runs, summed, before any (fuzz 62a)
    ev = _readings(rid, seed, runs, part)  # checked by the entry (reading_function)
    if key not in ev:
        raise ValueError(f"settings: record {rid} has no reading {shown(key)}; it has {sorted(ev)}")
    return ev[key]


#: The stochastic records of chapter 02 (their evidence runs Monte-Carlo studies) → their run count.
STOCHASTIC: dict[str, int] = constant({
    "lec-awf-estimated": 300, "lec-awf-adapts": 100, "lec-awf-fault-tolerance": 100, "lec-awf-accuracy": 100,
    "lec-cc-beats-mean": 100, "lec-cc-accuracy": 100, "lec-belief-objective": 200, "lec-belief-accuracy": 500,
})

def _reader(rid: str, summary: str, studies: str, returns: str = "Comparison") -> Callable[..., Evidence]:
    """The evidence function of the stochastic record ``rid``, ``fn(settings, *, seed=SEED, runs=STOCHASTIC[rid])``:
    reading ``settings["reading"]`` of the record on the studies at ``seed`` and ``runs`` (:func:`_at`;
    :func:`fusion.book.chapters.lecture.reading_function`).

    One function serves the eight stochastic records, which differ only in their id and docstring
    (``summary``: what the readings compare; ``studies``: the keys of :func:`study` they run; ``returns``: the
    evidence type).
    """
    return reading_function(__name__, rid, _at, SEED, STOCHASTIC[rid], summary,
                            f"The study's base seed and run count (:func:`study`: {studies}).", returns,
                            budget=_record_budget)


ev_awf_estimated = _reader(
    "lec-awf-estimated", "the literal AWF (infinite MSE) and every guard against the mean of means at k = 100.",
    "s21")
ev_awf_adapts = _reader(
    "lec-awf-adapts", "the AWF as written against the best causal estimator after a change of the variances.",
    "sreg (the ``change-*`` readings: schg)")
ev_awf_fault_tolerance = _reader(
    "lec-awf-fault-tolerance", "E2.3 with the fault, the AWF without the check.", "s23")
ev_awf_accuracy = _reader(
    "lec-awf-accuracy", "E2.3 without a fault; the benchmark's current readings (|σ̂²|) at three seeds.",
    "s23 (the ``bench-*`` readings: bench)")
ev_cc_beats_mean = _reader(
    "lec-cc-beats-mean", "check + AWF with the fault; what the check adds; 'adjacent' as the index order.", "s23")
ev_cc_accuracy = _reader("lec-cc-accuracy", "check + AWF without a fault.", "s23")
ev_belief_objective = _reader(
    "lec-belief-objective", "spreads over the grids (gated by accuracy), deletion supports, the Perron 0/1 rule.", "s24b",
    "Comparison or Unverifiable")
ev_belief_accuracy = _reader(
    "lec-belief-accuracy", "belief (s = 1) against the mean, the oracle and robust estimates, three seeds.",
    "bench")


#: Record id → evidence function of chapter 02 (the ``evidence`` field of each record names the same function):
#: for a stochastic record (:data:`STOCHASTIC`) ``fn(settings, *, seed, runs)``, for the others ``fn(st)``.
EVIDENCE = constant({
    "lec-awf-optimal": ev_awf_optimal, "lec-awf-estimated": ev_awf_estimated, "lec-awf-unbiased": ev_awf_unbiased,
    "lec-awf-lumv-fixed": ev_awf_lumv_fixed, "lec-awf-lumv": ev_awf_lumv, "lec-awf-adapts": ev_awf_adapts,
    "lec-awf-fault-tolerance": ev_awf_fault_tolerance, "lec-awf-accuracy": ev_awf_accuracy,
    "lec-ls-below-every-sensor": ev_ls_below_every_sensor, "lec-ls-unbiased": ev_ls_unbiased,
    "lec-ls-normal": ev_ls_normal, "lec-ls-learning": ev_ls_learning, "lec-ls-beats-mean": ev_ls_beats_mean,
    "lec-ls-diminishing": ev_ls_diminishing, "lec-ls-tracks": ev_ls_tracks, "lec-awf-no-prior": ev_awf_no_prior,
    "lec-cc-beats-mean": ev_cc_beats_mean, "lec-cc-accuracy": ev_cc_accuracy,
    "lec-belief-objective": ev_belief_objective, "lec-belief-perron": ev_belief_perron,
    "lec-belief-accuracy": ev_belief_accuracy,
})

#: Record id → its evidence from precomputed studies (every reading at once).
_FROM_STUDIES: dict[str, Callable[..., Evidence | dict[str, Evidence]]] = EVIDENCE | {
    "lec-awf-estimated": _ev_awf_estimated, "lec-awf-adapts": _ev_awf_adapts,
    "lec-awf-fault-tolerance": _ev_awf_fault_tolerance, "lec-awf-accuracy": _ev_awf_accuracy,
    "lec-cc-beats-mean": _ev_cc_beats_mean, "lec-cc-accuracy": _ev_cc_accuracy,
    "lec-belief-objective": _ev_belief_objective, "lec-belief-accuracy": _ev_belief_accuracy,
}


@study_runs_named("st")
def evidence(st: Mapping[str, Any], seed: int | None = None) -> dict[str, Evidence | dict[str, Evidence]]:
    """Every record's evidence of chapter 02, by record id (for :func:`fusion.book.claims.build_ledger`).

    The deterministic records' from the precomputed studies ``st``. With ``seed``, the stochastic records'
    (:data:`STOCHASTIC`) through their evidence functions (:func:`fusion.book.chapters.lecture.evidence_at`, the
    functions the reseeding sweep calls) at that base seed and the chapter's runs; the chapter passes
    :data:`SEED`, so their studies are those it computed with :func:`study` (cached). Without ``seed``, they
    too come from ``st``.

    Parameters
    ----------
    st : dict
        The keys of :data:`STUDIES` → the outputs of :mod:`fusion.scenarios.lecture_weighting`.
    seed : int, optional

    Returns
    -------
    dict of str to Evidence or dict of str to Evidence
        Record id → its evidence (or reading key → evidence).
    """
    # the stochastic records' studies derive up to seed + 6903 ('bench'): checked before the first (fuzz 55 D1)
    seed = None if seed is None else check_seed(seed, span=max(o for offs in SEED_OFFSETS.values() for o in offs))
    out = {rid: fn(st) for rid, fn in _FROM_STUDIES.items() if seed is None or rid not in STOCHASTIC}
    if seed is not None:
        out |= evidence_at(STOCHASTIC, seed)
    return {rid: out[rid] for rid in EVIDENCE}


def ledger_values(st: Mapping[str, Any]) -> GlueValues:
    """The computed numbers the claim texts of chapter 02 quote (keys ``lec_led_*``), also glued.

    Parameters
    ----------
    st : dict
        The studies (see :data:`STUDIES`). The tail check's values are :func:`glue_tail`'s.

    Returns
    -------
    GlueValues
        ``lec_led_*`` key → the number a claim text quotes.

    Raises
    ------
    TypeError
        ``st`` not a mapping.
    ValueError
        ``st`` without ``s23``, ``sreg`` or ``s21``.
    """
    st = read_mapping(st, "st")   # read once: the studies checked are the ones read (decision 31a C2)
    _need(st, "s23", "sreg", "s21")
    s23, sreg, s21 = st["s23"], st["sreg"], st["s21"]
    fault, clean = s23.sq[FaultCase.FAULT], s23.sq[FaultCase.NONE]
    sq9 = s21.sq[900.0]
    dele, mm = AwfMethod.AWF_LECTURE_DELETE, AwfMethod.MEAN_OF_MEANS
    out: GlueValues = {
        "lec_led_eps": round(float(s23.eps), 3),
        "lec_led_reg_nonpos": int(sum(sreg.n_nonpositive.values())),
        "lec_led_del_fault": round(float(np.mean(fault[dele])), 1),
        "lec_led_del_mm": round(float(np.mean(fault[mm])), 2),
        "lec_led_del_wins": int(np.sum(fault[dele] < fault[mm])),
        "lec_led_del_check": round(float(np.mean(fault[CHECKED[dele]])), 3),
        "lec_led_del_clean": round(float(np.mean(clean[dele])), 4),
        "lec_led_del_x900": round(float(np.mean(sq9[dele])), 4),
        "lec_led_mm_x900": round(float(np.mean(sq9[mm])), 4),
        "lec_led_runs23": int(s23.runs),
    }
    if "llc" in st:  # lec-ls-learning: the random check with the practical margin (third review, F2)
        llc = st["llc"]
        out |= {"lec_led_llc_margin_pct": round(100 * float(llc.margin)), "lec_led_llc_above": int(llc.above_best),
                "lec_led_llc_sets": int(llc.sets), "lec_led_llc_above_any": int(llc.above_best_any)}
    return out
