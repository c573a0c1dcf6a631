r"""Benchmark results for the chapters: loaded with their date, and kept out of nbval's comparison.

The scripts in ``benchmarks/`` store their measurements in ``benchmarks/results/<name>.json``
(``date``, ``machine``, ``measurements``: a list of ``{"what", "value", "unit"[, "key"]}``).
Timings change with every run and every machine, so a chapter cell that shows them must not be
part of the outputs that nbval compares exactly. The rule of the book:

* a cell that reads a benchmark result carries the ``nbval-ignore-output`` tag, and
* it shows the benchmark's date and machine beside the numbers (:attr:`BenchmarkResult.caption`).

Then re-running a benchmark never makes a stored notebook output stale; re-executing the
notebook (``make notebooks``) only refreshes the numbers it shows.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from fusion.book._json import read_object
from fusion._results import ReadOnlyMapping, ResultSpec, instance, text as text_field, tuple_of, validated_post_init
from fusion._validation import text
from fusion._shown import shown

__all__ = ["RESULTS", "BenchmarkResult", "load_benchmark", "IGNORE_OUTPUT_TAG"]

#: Folder of the stored results (``benchmarks/results`` of the repository).
RESULTS = Path(__file__).resolve().parents[2] / "benchmarks" / "results"

#: The nbval tag that a cell showing benchmark results must carry.
IGNORE_OUTPUT_TAG = "nbval-ignore-output"


@dataclass(frozen=True)
class BenchmarkResult:
    """One stored benchmark run.

    A result of :func:`load_benchmark`, which checks the file it reads: the constructor checks nothing (a record
    built by hand is the caller's; the package reads none back).

    Attributes
    ----------
    name : str
        File stem (``"ci"`` for ``benchmarks/results/ci.json``).
    date : str
        ISO date of the run.
    machine : str
        Description of the machine that ran it.
    measurements : tuple of dict
        The stored measurements, in file order.
    record : Mapping
        The whole JSON record (read-only), for fields particular to one benchmark.

    Raises
    ------
    TypeError
        A field of another type (checked when built, as :func:`load_benchmark` checks the file), naming
        ``BenchmarkResult.field``.
    """

    name: str
    date: str
    machine: str
    measurements: tuple[Mapping[str, Any], ...]
    record: Mapping[str, Any]

    __result_spec__ = ResultSpec({"name": text_field(), "date": text_field(), "machine": text_field(),
                                  "measurements": tuple_of(instance(Mapping)), "record": instance(Mapping)})
    __post_init__ = validated_post_init

    @property
    def values(self) -> dict[str, float]:
        """``key -> value`` of the measurements that have both a ``key`` and a ``value`` (a measurement of several
        numbers, such as ``validation.json``'s ``validated_s`` and ``kernel_s``, is read from :attr:`measurements`)."""
        return {m["key"]: float(m["value"]) for m in self.measurements if "key" in m and "value" in m}

    @property
    def caption(self) -> str:
        """``"benchmarks/<name>: measured on <date>, <machine>"``, to show beside the numbers."""
        return f"benchmarks/{self.name}: measured on {self.date}, {self.machine}"


#: A benchmark result's file stem: a short name without a path separator (``ci``, ``bench_validation``).
_STEM = re.compile(r"[A-Za-z0-9_][A-Za-z0-9_.-]{0,99}")


def _check_record(record: Mapping[str, Any], path: Path) -> None:
    """The fields :class:`BenchmarkResult` reads, each refused by a ValueError naming the file and the field."""
    for k in ("date", "machine"):
        if not isinstance(record[k], str):
            raise ValueError(f"benchmark result {path}: {k} must be a string, got {shown(record[k])}")
    _check_measurements(record["measurements"], path)


def _check_measurements(ms: object, path: Path) -> None:
    """A record's ``measurements``: a list of objects, each ``key`` (where given) a string held by no other
    measurement (a reader looks a value up by its key: with two, which one it reads is arbitrary; fuzz 24b D6) and
    each ``value`` (where given) a finite number, within [1e-9, 1e6] where its ``unit`` is seconds (``"s"``,
    ``"CPU-s"``: a measured duration; fuzz 24b BC3, fuzz 37b D2); refused by a ValueError naming the file and the
    field."""
    if not isinstance(ms, list):
        raise ValueError(f"benchmark result {path}: measurements must be a list, got {shown(ms)}")
    seen: dict[str, int] = {}
    for i, m in enumerate(ms):
        if not isinstance(m, dict):
            raise ValueError(f"benchmark result {path}: measurements[{i}] must be an object, got {shown(m)}")
        if "key" in m and not isinstance(m["key"], str):
            raise ValueError(f"benchmark result {path}: measurements[{i}].key must be a string, got {shown(m['key'])}")
        if "key" in m:
            if m["key"] in seen:
                raise ValueError(f"benchmark result {path}: measurements[{i}].key {shown(m['key'])} repeats "
                                 f"measurements[{seen[m['key']]}].key (a key names one measurement)")
            seen[m["key"]] = i
        v = m.get("value")
        if "value" in m and (not isinstance(v, (int, float)) or isinstance(v, bool) or not math.isfinite(v)):
            raise ValueError(f"benchmark result {path}: measurements[{i}].value must be a finite number, got {shown(v)}")
        if "value" in m and m.get("unit") in _SECONDS and not _DURATION[0] <= v <= _DURATION[1]:
            raise ValueError(f"benchmark result {path}: measurements[{i}].value is a duration ({m['unit']}) and must "
                             f"lie in [{_DURATION[0]:g}, {_DURATION[1]:g}] s (a nanosecond timer's step to 11 days), "
                             f"got {shown(v)}")


#: Units of a measured duration, whose values :func:`_check_measurements` requires within :data:`_DURATION`.
_SECONDS = ("s", "CPU-s")
#: The plausible range of a measured duration in seconds (fuzz 37b D2: 1e300 s glued a 300-digit number of ms,
#: 1e-320 s "0.0 against 0.0 ms"): from a nanosecond, the step of the timers, to a million seconds (11 days); the
#: stored benchmarks measure 4.6e-5 to 218 s.
_DURATION = (1e-9, 1e6)


def load_benchmark(name: str, results: Path | None = None) -> BenchmarkResult:
    """Load ``benchmarks/results/<name>.json``.

    Parameters
    ----------
    name : str
        File stem, e.g. ``"ci"`` or ``"chernoff"``.
    results : pathlib.Path, optional
        Folder of the results (default :data:`RESULTS`).

    Returns
    -------
    BenchmarkResult
        The run's ``name``, ``date`` and ``machine``, its ``measurements`` (read-only mappings) and the whole JSON
        ``record``.

    Raises
    ------
    ValueError
        If ``name`` is not a plain file stem or no such result is stored; naming the file, if it is not a JSON object
        (not UTF-8, not JSON, nested beyond the recursion limit, holding ``NaN`` or ``Infinity``) or the record lacks
        ``date``, ``machine`` or ``measurements``, or these are not two strings and a list of objects whose ``key``
        (where given) is a string and whose ``value`` (where given) is a finite number.
    """
    name = text(name, "name")
    if not _STEM.fullmatch(name) or name.endswith(".json"):  # a short plain stem: no path, no NUL, no 10**6 characters
        raise ValueError(f"name must be a file stem such as 'ci' (letters, digits, '_', '-', '.'; at most 100 "
                         f"characters), got {shown(name, 80)}")
    if results is not None and not isinstance(results, (str, Path)):
        raise TypeError(f"results must be a pathlib.Path, got {type(results).__name__}")
    path = (RESULTS if results is None else Path(results)) / f"{name}.json"
    if not path.is_file():
        raise ValueError(f"{'name' if results is None else 'name and results'}: no stored benchmark result {path}")
    record = read_object(path, "benchmark result")
    missing = [k for k in ("date", "machine", "measurements") if k not in record]
    if missing:
        raise ValueError(f"name: {path.name} lacks {missing}")
    _check_record(record, path)
    return BenchmarkResult(
        name=name, date=record["date"], machine=record["machine"],
        measurements=tuple(ReadOnlyMapping(m) for m in record["measurements"]),
        record=ReadOnlyMapping(record),
    )
