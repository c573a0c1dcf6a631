r"""Claims as data: ``book/claims/<source>.yaml``, validated, and turned into ledger records.

Every checkable claim of a source is one record of its claim file, readable without Python: where it
is in the source, the claim in one sentence, the published value, whose claim it is, the kind of test,
the quantity compared and its practical margin, the readings of the source's open choices, and the
function that computes its evidence. A chapter computes the evidence and calls :func:`build_ledger`,
which takes every text from the file, applies the rulebook (:mod:`fusion.book.rulebook`) and returns
the :class:`~fusion.book.ledger.Ledger` the chapter writes. Texts that quote a computed number name a
value of the chapter's glue (``{name}`` or ``{name:.2f}``), the same value the prose uses.

File format (:data:`SCHEMA`)
----------------------------
.. code-block:: yaml

    source: yang2012optimal           # a key of fusion.book.ledger.SOURCES
    quantities:                       # one practical margin per quantity (R2)
      mae:
        label: mean absolute error (°C)
        margin: {relative: 0.05}      # or {absolute: 0.1}; why: the reason
    records:
      - id: yang-fig2-vs-mean
        chapter: notebooks/01_optimal_fusion_set
        where: Fig. 2
        claim: Without failure, the optimal fusion set's error curve lies below the mean's.
        claimant: source              # source | implied | book
        published: {value: qualitative}
        test: paired                  # published | paired | equivalence | exact | count | unverifiable
        quantity: mae                 # paired and equivalence tests
        direction: less               # less | greater (paired); equal (equivalence)
        baseline: {name: ..., defined: false, reason: ...}   # a method the source never defines (R7)
        link: ofs-fig2
        evidence: fusion.book.chapters.ofs:ev_fig2_vs_mean
        readings:
          primary: {choice: noise levels, reading: the chapter's unequal levels}
          others:
            - {key: equal, choice: noise levels, reading: equal (同质), kind: open-choice}

Unknown fields and missing required ones fail with a message naming the file, the record and the field; so
do a key repeated in one mapping (YAML would keep the last), a margin that is not a finite number of at most
1e150, a run count above 10⁷, a repeated critique label, ``quantity``/``direction``/``margin`` on a test that
compares nothing (``published``, ``count``, ``unverifiable``), ``reason`` on a test other than ``unverifiable``,
and an ``evidence`` that does not name an importable module's function (the module is imported). Whether each
critique label is a box of the chapter is checked by the book's consistency tests, which read the notebooks.
"""

from __future__ import annotations

import importlib
import inspect
import os
import string
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import yaml

from fusion._frozen import constant, freeze_arrays, frozen_value, restore_frozen
from fusion.book import rulebook as R
from fusion.book.exact import ExactComparison
from fusion.book.ledger.evidence import _KIND_OF_TEST
from fusion.book.ledger import (SOURCES, Alternative, Claim, Comparison, Conjunction, Evidence, Ledger, Unverifiable,
                                ledger_dir)
from fusion._counts import COUNT_CEILINGS
from fusion._paths import folder
from fusion._shown import shown
from fusion._validation import MAX_MAGNITUDE, count, flag, instance_of, one_of, text

__all__ = ["SCHEMA", "ClaimsFileError", "ReadingSpec", "ClaimSpec", "ClaimsFile", "claims_dir", "load",
           "load_all", "build_ledger", "evaluate"]

_TEXT = {"type": "string", "minLength": 1}
_READING = {
    "type": "object", "additionalProperties": False, "required": ["key", "choice", "reading"],
    "properties": {"key": {"type": "string", "pattern": "^[a-z0-9][a-z0-9-]*$"}, "choice": _TEXT, "reading": _TEXT,
                   "kind": {"enum": list(R.READING_KINDS[1:])}, "settings": {"type": "object"},
                   "runs": {"type": "integer", "minimum": 1, "maximum": COUNT_CEILINGS["runs"]}},
}
_MARGIN = {"type": "object", "additionalProperties": False, "minProperties": 1, "maxProperties": 1,
           "properties": {"relative": {"type": "number", "minimum": 0}, "absolute": {"type": "number", "minimum": 0}}}

#: JSON schema of a claim file.
SCHEMA: dict[str, Any] = constant({
    "type": "object", "additionalProperties": False, "required": ["source", "records"],
    "properties": {
        "source": {"enum": sorted(SOURCES)},
        "quantities": {"type": "object", "additionalProperties": {
            "type": "object", "additionalProperties": False, "required": ["label", "margin"],
            "properties": {"label": _TEXT, "margin": _MARGIN, "why": _TEXT}}},
        "records": {"type": "array", "minItems": 1, "items": {
            "type": "object", "additionalProperties": False,
            "required": ["id", "chapter", "where", "claim", "claimant", "published", "test", "link"],
            "properties": {
                "id": {"type": "string", "pattern": "^[a-z0-9]+(-[a-z0-9]+)+$"},
                "chapter": _TEXT, "where": _TEXT,
                "claim": {"type": "string", "minLength": 1, "maxLength": 200},
                "claimant": {"enum": list(R.CLAIMANTS)},
                "published": {"type": "object", "additionalProperties": False, "required": ["value"],
                              "properties": {"value": _TEXT, "unit": _TEXT, "precision": _TEXT}},
                "test": {"enum": list(R.TESTS)},
                "quantity": _TEXT,
                "direction": {"enum": ["less", "greater", "equal"]},
                "margin": _MARGIN,
                "baseline": {"type": "object", "additionalProperties": False, "required": ["name", "defined"],
                             "properties": {"name": _TEXT, "defined": {"type": "boolean"}, "reason": _TEXT,
                                            "stand_in": _TEXT}},
                "headline": {"type": "boolean"},
                "link": _TEXT,
                "critiques": {"type": "array", "items": _TEXT},
                "assumptions": {"type": "array", "items": _TEXT},
                "bound": _TEXT,
                "reason": _TEXT,
                "evidence": {"type": "string", "pattern": r"^[A-Za-z_][\w.]*:[A-Za-z_]\w*$"},
                "readings": {"type": "object", "additionalProperties": False,
                             "properties": {"primary": {"type": "object", "additionalProperties": False,
                                                        "required": ["choice", "reading"],
                                                        "properties": {"choice": _TEXT, "reading": _TEXT,
                                                                       "settings": {"type": "object"},
                                                                       "runs": {"type": "integer", "minimum": 1,
                                                                                "maximum": COUNT_CEILINGS["runs"]}}},
                                            "others": {"type": "array", "items": _READING}}},
            }}},
    },
})


def _nonempty(value: object, name: str) -> str:
    """A text field that must say something: TypeError naming ``name`` for a non-str, ValueError for ""."""
    if not text(value, name).strip():
        raise ValueError(f"{name} must not be empty")
    return value  # type: ignore[return-value]


class ClaimsFileError(ValueError):
    """A claim file is malformed; the message names the file, the record and the field.

    Attributes
    ----------
    args : tuple of str
        The message, ``"<file>: record <id>, field <field>: <what is wrong>"``.
    """


@dataclass(frozen=True)
class ReadingSpec:
    """One reading of a record: a named setting of the source's open choices.

    Attributes
    ----------
    key : str
        ``"primary"`` or the reading's key in the file.
    choice, reading : str
        The open choice and this reading of it (texts).
    kind : str
        One of :data:`fusion.book.rulebook.READING_KINDS`.
    settings : Mapping
        The settings the evidence function takes (stored read-only).
    runs : int or None
        Monte-Carlo runs, when the file states them.

    Raises
    ------
    TypeError
        A text field not a str, ``settings`` not a mapping, ``runs`` neither an integer nor None.
    ValueError
        An empty ``key``; ``kind`` not a reading kind; ``runs`` below 1. (``choice`` and ``reading`` may be
        empty: a record without readings has an implicit primary one.)
    """

    key: str
    choice: str
    reading: str
    kind: str
    settings: Mapping[str, Any]
    runs: int | None = None

    def __post_init__(self) -> None:
        _nonempty(self.key, "key")
        text(self.choice, "choice"), text(self.reading, "reading")  # "" for a record's implicit primary reading
        one_of(self.kind, R.READING_KINDS, "kind")
        instance_of(self.settings, Mapping, "settings")
        if self.runs is not None:
            count(self.runs, "runs")
        freeze_arrays(self)  # settings stored as a read-only mapping (fuzz 19: a frozen result cannot change)

    __setstate__ = restore_frozen  # copies and unpickled objects keep it read-only


@dataclass(frozen=True)
class ClaimSpec:
    """One record of a claim file, as data (see :data:`SCHEMA` for the fields).

    Attributes
    ----------
    id, chapter, where, claim, claimant, published, test, link : str
        As in the file (``published`` joined into one text: value, unit, precision).
    quantity, direction : str
        Paired and equivalence tests ("" otherwise).
    margin : Mapping or None
        The record's own margin (``{"relative": r}`` or ``{"absolute": x}``), if it declares one (stored
        read-only).
    baseline : Mapping or None
        ``{"name", "defined", "reason", "stand_in"}`` for a method the source names (``name`` and ``defined``
        required; stored read-only).
    headline : bool
    critiques, assumptions : tuple of str
    bound, reason, evidence : str
    readings : tuple of ReadingSpec
        The primary reading first when the file states it.

    Raises
    ------
    TypeError
        A text field not a str; ``headline`` not a bool; ``margin`` or ``baseline`` not a mapping; ``baseline``'s
        ``name``, ``reason`` or ``stand_in`` not a str or its ``defined`` not a bool;
        ``critiques`` or ``assumptions`` not a tuple of str; ``readings`` not a tuple of ReadingSpec.
    ValueError
        An empty ``id``, ``chapter``, ``where``, ``claim``, ``published`` or ``link``; ``claimant``, ``test``
        or ``direction`` outside its vocabulary; a margin not ``{"relative": r}`` or ``{"absolute": x}`` with
        a finite value in [0, 1e150]; a ``baseline`` without ``name`` and ``defined`` or with another key; a
        repeated critique label; ``evidence`` not ``module:function``.
    """

    id: str
    chapter: str
    where: str
    claim: str
    claimant: str
    published: str
    test: str
    link: str
    quantity: str = ""
    direction: str = ""
    margin: Mapping[str, float] | None = None
    baseline: Mapping[str, Any] | None = None
    headline: bool = False
    critiques: tuple[str, ...] = ()
    assumptions: tuple[str, ...] = ()
    bound: str = ""
    reason: str = ""
    evidence: str = ""
    readings: tuple[ReadingSpec, ...] = ()

    def __post_init__(self) -> None:
        for name in ("id", "chapter", "where", "claim", "published", "link"):
            _nonempty(getattr(self, name), name)
        one_of(self.claimant, R.CLAIMANTS, "claimant")
        one_of(self.test, R.TESTS, "test")
        for name in ("quantity", "bound", "reason", "evidence"):
            text(getattr(self, name), name)
        one_of(self.direction, ("", "less", "greater", "equal"), "direction")
        flag(self.headline, "headline")
        for name in ("margin", "baseline"):
            if getattr(self, name) is not None:
                instance_of(getattr(self, name), Mapping, name)
        if self.margin is not None:
            if set(self.margin) not in ({"relative"}, {"absolute"}):
                raise ValueError(f"margin must be {{'relative': r}} or {{'absolute': x}}, got {shown(self.margin)}")
            try:
                _check_margin(self.margin, "margin")
            except ClaimsFileError as e:
                raise ValueError(str(e)) from None
        if self.baseline is not None:
            _check_baseline(self.baseline)
        for name in ("margin", "baseline"):  # stored read-only: a frozen record's margin cannot be edited (fuzz 20)
            if getattr(self, name) is not None:
                object.__setattr__(self, name, frozen_value(getattr(self, name)))
        for name in ("critiques", "assumptions"):
            v = getattr(self, name)
            if not (isinstance(v, tuple) and all(isinstance(x, str) for x in v)):
                raise TypeError(f"{name} must be a tuple of str, got {shown(v)}")
        if len(set(self.critiques)) != len(self.critiques):
            raise ValueError(f"critiques must not repeat a label, got {shown(self.critiques)}")
        if not (isinstance(self.readings, tuple) and all(isinstance(r, ReadingSpec) for r in self.readings)):
            raise TypeError(f"readings must be a tuple of ReadingSpec, got {shown(self.readings)}")
        if self.evidence:
            mod, sep, name = self.evidence.partition(":")
            if not (sep and mod and name):
                raise ValueError(f"evidence must be 'module:function', got {shown(self.evidence)}")


@dataclass(frozen=True)
class ClaimsFile:
    """A validated claim file.

    Attributes
    ----------
    path : pathlib.Path
    source : str
    quantities : Mapping
        Quantity key → {"label", "margin", "why"} (stored read-only).
    records : tuple of ClaimSpec
        (A list is stored as a tuple.)

    Raises
    ------
    TypeError
        ``path`` not a :class:`pathlib.Path`, ``source`` not a str, ``quantities`` not a mapping, ``records``
        not a sequence of :class:`ClaimSpec`.
    """

    path: Path
    source: str
    quantities: Mapping[str, Mapping[str, Any]]
    records: tuple[ClaimSpec, ...]

    def __post_init__(self) -> None:
        instance_of(self.path, Path, "path")
        text(self.source, "source")
        instance_of(self.quantities, Mapping, "quantities")
        if not (isinstance(self.records, (tuple, list)) and all(isinstance(r, ClaimSpec) for r in self.records)):
            raise TypeError(f"records must be a tuple of ClaimSpec, got {shown(self.records)}")
        freeze_arrays(self)  # quantities a read-only mapping, records a tuple (fuzz 20: a rebuilt file is checked)

    __setstate__ = restore_frozen  # copies and unpickled objects keep it read-only

    def record(self, rid: str) -> ClaimSpec:
        """The record with id ``rid`` (ClaimsFileError if absent)."""
        for r in self.records:
            if r.id == rid:
                return r
        raise ClaimsFileError(f"{self.path.name}: no record {shown(rid)}")

    def margin(self, spec: ClaimSpec) -> Mapping[str, float]:
        """The practical margin of a record: its own, else its quantity's (R2).

        Parameters
        ----------
        spec : ClaimSpec
            A record of this file.

        Returns
        -------
        mapping
            ``{"relative": r}`` or ``{"absolute": x}``.

        Raises
        ------
        TypeError
            ``spec`` is not a :class:`ClaimSpec`.
        ValueError
            ``spec`` is not a record of this file (a record of another claim file names quantities this
            file may not declare).
        """
        instance_of(spec, ClaimSpec, "spec")
        if spec not in self.records:
            raise ValueError(f"spec: record {shown(spec.id)} is not a record of {self.path.name}")
        if spec.margin:
            return spec.margin
        if spec.quantity:
            return self.quantities[spec.quantity]["margin"]
        return {"relative": R.DEFAULT_RELATIVE_MARGIN}


def claims_dir(start: Path | str | None = None) -> Path:
    """``book/claims`` of the repository that contains ``start`` (default: the working directory's, else the package's).

    Parameters
    ----------
    start : str or os.PathLike, optional
        As in :func:`fusion.book.ledger.ledger_dir`, whose sibling this is.

    Returns
    -------
    pathlib.Path
        The ``claims`` folder beside the ledger folder found from ``start`` (``<repository>/book/claims``).

    Raises
    ------
    TypeError
        ``start`` is not a path (``str`` or ``os.PathLike``).
    ValueError
        ``start`` is not an existing folder.
    FileNotFoundError
        No ``_toc.yml`` in ``start`` or above it (see :func:`fusion.book.ledger.ledger_dir`).
    """
    return ledger_dir(start).parent / "claims"


def _where(err: Any, doc: Mapping[str, Any]) -> str:
    path = list(err.absolute_path)
    rec = ""
    if len(path) >= 2 and path[0] == "records" and isinstance(path[1], int):
        r = doc["records"][path[1]]
        rec = f"record {r.get('id', '#' + str(path[1])) if isinstance(r, dict) else '#' + str(path[1])}, "
        path = path[2:]
    field = ".".join(str(p) for p in path) or "(top level)"
    return f"{rec}field {field}"


class _UniqueKeyLoader(yaml.SafeLoader):
    """PyYAML's safe loader, refusing a key repeated in one mapping (the safe loader keeps the last silently)."""


def _unique_mapping(loader: _UniqueKeyLoader, node: yaml.MappingNode, deep: bool = False) -> dict[Any, Any]:
    seen: set[Any] = set()
    for key_node, _ in node.value:
        key = loader.construct_object(key_node, deep=deep)
        if not isinstance(key, str):  # a sequence, a number, null, a bool: every key of a claim file is a text
            raise yaml.constructor.ConstructorError(None, None, f"a key must be a text, got {shown(key)}",
                                                    key_node.start_mark)
        if key in seen:
            raise yaml.constructor.ConstructorError(None, None, f"repeated key {shown(key)}", key_node.start_mark)
        seen.add(key)
    return loader.construct_mapping(node, deep=deep)


_UniqueKeyLoader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_MAPPING_TAG, _unique_mapping)


def _bounded_int(loader: _UniqueKeyLoader, node: yaml.ScalarNode) -> int:
    """PyYAML's integer, refused (with its place in the file) beyond Python's digit limit for str -> int."""
    try:
        return loader.construct_yaml_int(node)
    except ValueError as e:
        raise yaml.constructor.ConstructorError(None, None, f"an integer too long to read ({e})",
                                                node.start_mark) from None


_UniqueKeyLoader.add_constructor("tag:yaml.org,2002:int", _bounded_int)

#: Deepest nesting of mappings and lists a claim file may have (its records are 5 deep; PyYAML and jsonschema
#: recurse, so a file nested thousands deep would end in a RecursionError).
_MAX_DEPTH = 32


def _check_depth(doc: Any, name: str) -> None:
    """ClaimsFileError naming the file and the field where ``doc`` nests deeper than ``_MAX_DEPTH``."""
    stack: list[tuple[Any, tuple[Any, ...]]] = [(doc, ())]
    while stack:
        node, where = stack.pop()
        if len(where) > _MAX_DEPTH:
            field = ".".join(str(p) for p in where[:3])
            raise ClaimsFileError(f"{name}: field {field}: nested more than {_MAX_DEPTH} deep")
        if isinstance(node, dict):
            stack.extend((v, (*where, k)) for k, v in node.items())
        elif isinstance(node, list):
            stack.extend((v, (*where, i)) for i, v in enumerate(node))

#: Tests that compare methods on a quantity, the only ones that take ``quantity``, ``direction`` and ``margin``.
_COMPARING_TESTS = ("paired", "equivalence", "exact")


def _check_margin(margin: Mapping[str, Any], where: str) -> None:
    """A margin of a claim file: its one value a finite number in [0, 1e150] (the schema checks type and sign only:
    YAML's ``.nan`` and ``.inf`` are numbers to it)."""
    for k, v in margin.items():
        # a numpy real scalar (float32, int64) is a number, as for the shared scalar reader; a bool is not
        if isinstance(v, (bool, np.bool_)) or not isinstance(v, (int, float, np.integer, np.floating)) \
                or not 0 <= (float(v) if isinstance(v, np.generic) else v) <= MAX_MAGNITUDE:  # float32 vs 1e150
            raise ClaimsFileError(f"{where}.{k}: must be a finite number in [0, {MAX_MAGNITUDE:g}], got {shown(v)}")


def _check_baseline(baseline: Mapping[str, Any]) -> None:
    """A record's baseline as the schema states it (ValueError or TypeError naming ``baseline``): a record built without
    :func:`load` (``dataclasses.replace``) is held to the file's rules."""
    keys = set(baseline)
    if not {"name", "defined"} <= keys <= {"name", "defined", "reason", "stand_in"}:
        raise ValueError(f"baseline must hold 'name' and 'defined' (and optionally 'reason', 'stand_in'), "
                         f"got {shown(baseline)}")
    for k in ("name", "reason", "stand_in"):
        if k in baseline and not isinstance(baseline[k], str):
            raise TypeError(f"baseline.{k} must be a str, got {shown(baseline[k])}")
    if not isinstance(baseline["defined"], bool):
        raise TypeError(f"baseline.defined must be a bool, got {shown(baseline['defined'])}")


def _evidence_function(evidence: str, where: str) -> Any:
    """The function a record's ``evidence`` names (``module:function``), imported; ClaimsFileError naming ``where``
    (which names the field evidence) when the module cannot be imported or has no such function."""
    mod, sep, name = evidence.partition(":")
    if not sep or not mod or not name:
        raise ClaimsFileError(f"{where}: {shown(evidence)} is not 'module:function'")
    try:
        module = importlib.import_module(mod)
    except ImportError as e:
        raise ClaimsFileError(f"{where}: module {shown(mod)} cannot be imported ({e})") from None
    fn = getattr(module, name, None)
    if not callable(fn):
        raise ClaimsFileError(f"{where}: module {mod} has no function {shown(name)}")
    if not inspect.isfunction(inspect.unwrap(fn)):  # a builtin (print) or a class is callable, not an evidence function
        raise ClaimsFileError(f"{where}: {mod}:{name} is a {type(fn).__name__}, not a function")
    return fn


def load(path: Path | str) -> ClaimsFile:
    """Read and validate one claim file.

    Parameters
    ----------
    path : path-like
        ``book/claims/<source>.yaml``.

    Returns
    -------
    ClaimsFile
        The file's path, source key, quantities and records, validated against the schema.

    Raises
    ------
    TypeError
        ``path`` is not a path.
    ValueError
        ``path`` is not a readable file (missing, a directory, unreadable) or is not UTF-8 text.
    ClaimsFileError
        The file is malformed: the message names the file, the record and the field.
    """
    import jsonschema

    if not isinstance(path, (str, os.PathLike)):
        raise TypeError(f"path must be a path (str or os.PathLike), got {type(path).__name__}")
    path = Path(path)
    try:
        raw = path.read_text(encoding="utf-8")
    except OSError as e:
        raise ValueError(f"path {shown(str(path))} is not a readable file: {e.strerror or e}") from None
    except UnicodeDecodeError as e:
        raise ValueError(f"path {shown(str(path))} is not UTF-8 text ({e.reason} at byte {e.start})") from None
    try:
        doc = yaml.load(raw, Loader=_UniqueKeyLoader)  # noqa: S506 - a SafeLoader that refuses repeated keys
    except yaml.YAMLError as e:
        raise ClaimsFileError(f"{path.name}: not valid YAML ({e})") from None
    except RecursionError:  # PyYAML composes and constructs recursively
        raise ClaimsFileError(f"{path.name}: not valid YAML (nested more than {_MAX_DEPTH} deep)") from None
    _check_depth(doc, path.name)
    errors = sorted(jsonschema.Draft202012Validator(SCHEMA).iter_errors(doc), key=lambda e: list(e.absolute_path))
    if errors:
        e = errors[0]
        raise ClaimsFileError(f"{path.name}: {_where(e, doc)}: {e.message}")
    src = SOURCES[doc["source"]]
    quantities = doc.get("quantities", {})
    for q, spec in quantities.items():
        _check_margin(spec["margin"], f"{path.name}: quantity {q}, field margin")
    specs, seen = [], set()
    for r in doc["records"]:
        rid = r["id"]
        where = f"{path.name}: record {rid}"
        if rid in seen:
            raise ClaimsFileError(f"{where}: field id: duplicate id")
        seen.add(rid)
        if r["chapter"] not in src.chapters:
            raise ClaimsFileError(f"{where}: field chapter: {shown(r['chapter'])} is not a chapter of {src.key}")
        if r["test"] in ("paired", "equivalence"):
            for f in ("quantity", "direction"):
                if f not in r:
                    raise ClaimsFileError(f"{where}: field {f}: required for a {r['test']} test")
            if r["quantity"] not in quantities:
                raise ClaimsFileError(f"{where}: field quantity: {shown(r['quantity'])} is not declared under quantities")
            if (r["test"] == "equivalence") != (r["direction"] == "equal"):
                raise ClaimsFileError(f"{where}: field direction: an equivalence test has direction 'equal', "
                                      "a paired test 'less' or 'greater'")
        if r["test"] == "unverifiable" and "reason" not in r:
            raise ClaimsFileError(f"{where}: field reason: required for an unverifiable test")
        for f in ("quantity", "direction", "margin"):
            if f in r and r["test"] not in _COMPARING_TESTS:
                raise ClaimsFileError(f"{where}: field {f}: a {r['test']} test compares nothing (only "
                                      f"{', '.join(_COMPARING_TESTS)} tests take it)")
        if "reason" in r and r["test"] != "unverifiable":
            raise ClaimsFileError(f"{where}: field reason: only an unverifiable test takes a reason "
                                  "(an undefined baseline's goes under baseline.reason)")
        if "margin" in r:
            _check_margin(r["margin"], f"{where}: field margin")
        crit = r.get("critiques", [])
        if len(set(crit)) != len(crit):
            raise ClaimsFileError(f"{where}: field critiques: a label is repeated ({crit})")
        if "evidence" in r:
            _evidence_function(r["evidence"], f"{where}: field evidence")
        if r.get("headline") and r["claimant"] != "source":
            raise ClaimsFileError(f"{where}: field headline: only a claim the source prints can be its main "
                                  f"finding (rule R8), claimant is {shown(r['claimant'])}")
        b = r.get("baseline")
        if b is not None and not b["defined"] and "reason" not in b:
            raise ClaimsFileError(f"{where}: field baseline.reason: required when the baseline is undefined")
        rd = r.get("readings", {})
        readings = []
        if "primary" in rd:
            p = rd["primary"]
            readings.append(ReadingSpec("primary", p["choice"], p["reading"], "primary", p.get("settings", {}),
                                        p.get("runs")))
        for o in rd.get("others", []):
            if o["key"] == "primary" or any(x.key == o["key"] for x in readings):
                raise ClaimsFileError(f"{where}: field readings.others: duplicate key {shown(o['key'])}")
            readings.append(ReadingSpec(o["key"], o["choice"], o["reading"], o.get("kind", "open-choice"),
                                        o.get("settings", {}), o.get("runs")))
        pub = r["published"]
        published = " ".join(x for x in (pub["value"], pub.get("unit", "")) if x) + (
            f" ({pub['precision']})" if "precision" in pub else "")
        specs.append(ClaimSpec(
            id=rid, chapter=r["chapter"], where=r["where"], claim=r["claim"], claimant=r["claimant"],
            published=published, test=r["test"], link=r["link"], quantity=r.get("quantity", ""),
            direction=r.get("direction", ""), margin=r.get("margin"), baseline=b, headline=r.get("headline", False),
            critiques=tuple(r.get("critiques", ())), assumptions=tuple(r.get("assumptions", ())),
            bound=r.get("bound", ""), reason=r.get("reason", ""), evidence=r.get("evidence", ""),
            readings=tuple(readings)))
    heads = [s for s in specs if s.headline]
    if len(heads) != 1 or heads[0].chapter != src.chapter:
        raise ClaimsFileError(f"{path.name}: field headline: exactly one record, in {src.chapter}, must be the "
                              f"headline (found {[s.id for s in heads]})")
    return ClaimsFile(path, doc["source"], quantities, tuple(specs))


def load_all(directory: Path | None = None) -> dict[str, ClaimsFile]:
    """Every claim file of ``book/claims``, by source key.

    Parameters
    ----------
    directory : path-like, optional
        Default: :func:`claims_dir`.

    Returns
    -------
    dict of str to ClaimsFile
        Source key (``"lecture003"``) → its claim file, for every ``*.yaml`` file of the folder, in name order.

    Raises
    ------
    TypeError
        ``directory`` is not a path (str or os.PathLike).
    ValueError
        ``directory`` is not an existing directory; :class:`ClaimsFileError` for a malformed file.
    """
    d = folder(directory if directory is not None else claims_dir(), "directory")
    out = {}
    for p in sorted(d.glob("*.yaml")):
        f = load(p)
        if f.source in out:
            raise ClaimsFileError(f"{p.name}: source {f.source} already has a claim file")
        out[f.source] = f
    return out


def _fill(text: str, values: Mapping[str, Any], where: str) -> str:
    """``text`` with its ``{name}`` / ``{name:spec}`` fields filled from the chapter's glue values."""
    fields = [f for _, f, _, _ in string.Formatter().parse(text) if f is not None]
    missing = [f for f in fields if f not in values]
    if missing:
        raise ClaimsFileError(f"{where}: names values {missing} that the chapter does not provide")
    try:
        return text.format_map(values)
    except (ValueError, TypeError) as e:
        raise ClaimsFileError(f"{where}: cannot format ({e})") from None


def _check_direction(ev: Evidence, spec: ClaimSpec, where: str) -> None:
    comps = [ev] if isinstance(ev, (Comparison, ExactComparison)) else \
        [e for _, e in ev.parts if isinstance(e, (Comparison, ExactComparison))] if isinstance(ev, Conjunction) else []
    for c in comps:
        if isinstance(c, ExactComparison) and spec.direction is None:
            continue  # an exact record states no direction: each comparison carries its own (R9)
        if c.claim != spec.direction:
            raise ClaimsFileError(f"{where}: the evidence compares in direction {shown(c.claim)}, the record says "
                                  f"{shown(spec.direction)}")


def _with_margin(ev: Evidence, margin: Mapping[str, float]) -> Evidence:
    if isinstance(ev, (Comparison, ExactComparison, Conjunction)):
        return ev.with_margin(margin.get("absolute"), margin.get("relative"))
    return ev


def build_ledger(source: str, chapter: str | None, evidence: Mapping[str, Mapping[str, Evidence] | Evidence],
                 values: Mapping[str, Any] | None = None, claims: ClaimsFile | None = None) -> Ledger:
    """The ledger of one chapter: every record of the claim file for it, with the chapter's evidence.

    Parameters
    ----------
    source : str
        A key of :data:`fusion.book.ledger.SOURCES`.
    chapter : str or None
        Docname of the chapter (default: the source's first).
    evidence : mapping of record id to evidence, or to a mapping of reading key to evidence
        Exactly the records of the file for this chapter; a record with readings maps ``"primary"`` and
        every reading key of the file to its evidence.
    values : mapping, optional
        The chapter's glue values, for the ``{name}`` fields of the texts.
    claims : ClaimsFile, optional
        Default: ``book/claims/<source>.yaml``.

    Returns
    -------
    Ledger
        One Claim per record of the file for ``chapter``: its texts filled from ``values``, its primary evidence and its
        readings as alternatives.

    Raises
    ------
    ClaimsFileError
        A record without evidence, evidence without a record, a reading missing or extra, evidence of the
        wrong kind or direction, or a text naming a value the chapter does not provide.
    TypeError
        ``evidence`` is not a mapping, ``values`` neither a mapping nor None, ``claims`` neither a
        :class:`ClaimsFile` nor None.
    """
    instance_of(evidence, Mapping, "evidence")
    if values is not None:
        instance_of(values, Mapping, "values")
    if claims is not None:
        instance_of(claims, ClaimsFile, "claims")
    cf = claims or load(claims_dir() / f"{source}.yaml")
    if cf.source != source:
        raise ClaimsFileError(f"{cf.path.name} holds {cf.source}, not {source}")
    led = Ledger(source, chapter)
    values = dict(values or {})
    specs = [s for s in cf.records if s.chapter == led.chapter]
    ids = {s.id for s in specs}
    extra = sorted(set(evidence) - ids)
    missing = sorted(ids - set(evidence))
    if extra or missing:
        raise ClaimsFileError(f"{cf.path.name}: evidence for records not in the file for {led.chapter}: {extra}; "
                              f"records without evidence: {missing}")
    for spec in specs:
        where = f"{cf.path.name}: record {spec.id}"
        given = evidence[spec.id]
        by_key = dict(given) if isinstance(given, Mapping) else {"primary": given}
        want = {"primary"} | {r.key for r in spec.readings if r.key != "primary"}
        if set(by_key) != want:
            raise ClaimsFileError(f"{where}: field readings: evidence for {sorted(by_key)}, the file names "
                                  f"{sorted(want)}")
        margin = cf.margin(spec)
        for k, ev in by_key.items():
            stand_ins_ok = k != "primary" and (isinstance(ev, Unverifiable) or spec.test == "unverifiable")
            if not isinstance(ev, _KIND_OF_TEST[spec.test]) and not stand_ins_ok:
                raise ClaimsFileError(f"{where}: reading {k}: a {spec.test} test cannot take "
                                      f"{type(ev).__name__} evidence")
            if spec.direction:
                _check_direction(ev, spec, f"{where}: reading {k}")
            by_key[k] = _with_margin(ev, margin)
        primary = by_key["primary"]
        alts = []
        for r in spec.readings:
            if r.key == "primary":
                continue
            alts.append(Alternative(_fill(r.choice, values, f"{where}: readings.{r.key}.choice"),
                                    _fill(r.reading, values, f"{where}: readings.{r.key}.reading"),
                                    by_key[r.key], r.kind))
        b = spec.baseline
        if b is not None and not b["defined"]:  # R7: the source's baseline is undefined
            alts.insert(0, Alternative("baseline", _fill(b.get("stand_in", f"the book's stand-in for {b['name']}"),
                                                         values, f"{where}: baseline.stand_in"), primary, "stand-in"))
            primary = Unverifiable(_fill(b["reason"], values, f"{where}: baseline.reason"))
        if spec.test == "unverifiable":
            primary = Unverifiable(_fill(spec.reason, values, f"{where}: reason"))
        led.add(Claim(
            spec.id, source, spec.where, _fill(spec.claim, values, f"{where}: claim"), spec.published, primary,
            spec.link, bound=_fill(spec.bound, values, f"{where}: bound"),
            assumptions=tuple(_fill(a, values, f"{where}: assumptions") for a in spec.assumptions),
            alternatives=tuple(alts), headline=spec.headline, critiques=spec.critiques, claimant=spec.claimant,
            test=spec.test))
    return led


def evaluate(spec: ClaimSpec, reading: str, seed: int, runs: int) -> Evidence:
    """Recompute one reading's evidence with its record's evidence function.

    The function named by the record's ``evidence`` field takes the reading's settings, a seed and a run
    count: ``fn(settings, seed=seed, runs=runs) -> Evidence``.

    Parameters
    ----------
    spec : ClaimSpec
    reading : str
        ``"primary"`` or a reading key of the record.
    seed, runs : int

    Returns
    -------
    Evidence
        What the record's evidence function returns for ``reading`` (its settings) at ``seed`` and ``runs``.

    Raises
    ------
    TypeError
        ``spec`` is not a :class:`ClaimSpec`, ``reading`` not a string, ``seed`` or ``runs`` not an integer.
    ValueError
        ``seed`` negative or ``runs`` below 1; :class:`ClaimsFileError` (a ValueError) when the record names no
        evidence function, names one that does not exist (field evidence) or has no reading ``reading``.
    """
    from fusion._validation import seed as check_seed

    instance_of(spec, ClaimSpec, "spec")
    text(reading, "reading")
    seed, runs = check_seed(seed), count(runs, "runs")  # plain ints (a 0-d array is its integer)
    if not spec.evidence:
        raise ClaimsFileError(f"record {spec.id}: names no evidence function")
    fn = _evidence_function(spec.evidence, f"record {spec.id}: field evidence")
    settings = next((r.settings for r in spec.readings if r.key == reading), None)
    if settings is None and reading != "primary":
        raise ClaimsFileError(f"record {spec.id}: no reading {shown(reading)}")
    return fn(dict(settings or {}), seed=seed, runs=runs)
