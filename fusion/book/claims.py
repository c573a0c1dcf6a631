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
import itertools
import os
import re
import string
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import yaml

from fusion.book._claim_text import text_problem as _text_problem  # the text rule (fuzz 29a D1, 30a C4/D3)
from fusion.book._claim_text import format_problem as _format_problem, texts_work  # fuzz 53a C1: texts' budget
from fusion.book._claim_yaml import _UniqueKeyLoader  # PyYAML's safe loader, refusing repeated keys
from fusion._frozen import constant, freeze_arrays, frozen_value, restore_frozen
from fusion.book import _parsed_claims, rulebook as R
from fusion.book.exact import ExactComparison
from fusion.book.ledger.claim import _ID  # a record's id: the schema's pattern, ClaimSpec's and Claim's check
from fusion.book.ledger.evidence import _KIND_OF_TEST
from fusion.book.ledger import (SOURCES, Alternative, Claim, Comparison, Conjunction, Evidence, Ledger, Unverifiable,
                                ledger_dir)
from fusion._counts import COUNT_CEILINGS, MAX_COUNT
from fusion._paths import file_bytes, folder
from fusion._shown import shown
from fusion._validation import MAX_MAGNITUDE, count, flag, instance_of, one_of, text, text_fields

__all__ = ["SCHEMA", "ClaimsFileError", "ReadingSpec", "ClaimSpec", "ClaimsFile", "claims_dir", "load",
           "load_all", "build_ledger", "evaluate"]

_TEXT = {"type": "string", "minLength": 1}
#: What a record's ``evidence`` field may hold: ``module:function`` (the schema's pattern and ClaimSpec's check).
_EVIDENCE = r"[A-Za-z_][\w.]*:[A-Za-z_]\w*"
#: What a reading's ``key`` may be (the schema's pattern and ReadingSpec's check): lower-case letters, digits and
#: ``-``, not starting with ``-``.
_KEY = r"[a-z0-9][a-z0-9-]*"


def _whole(pattern: str) -> str:
    """The schema's pattern of an identifier: ``pattern`` matching the whole text. jsonschema applies a pattern
    with :func:`re.search`, where ``$`` also matches before a final newline (``"typical-run\\n"`` would pass,
    fuzz 24a K1): the end is ``\\Z``. One rule for every identifier of the schema (``id``, ``evidence``, a
    reading's ``key``), checked again with :func:`re.fullmatch` by the dataclasses."""
    return rf"^(?:{pattern})\Z"


_READING = {
    "type": "object", "additionalProperties": False, "required": ["key", "choice", "reading"],
    "properties": {"key": {"type": "string", "pattern": _whole(_KEY)}, "choice": _TEXT, "reading": _TEXT,
                   "kind": {"enum": list(R.READING_KINDS[1:])}, "settings": {"type": "object"},
                   "runs": {"type": "integer", "minimum": 1, "maximum": COUNT_CEILINGS["runs"]}},
}
_MARGIN = {"type": "object", "additionalProperties": False, "minProperties": 1, "maxProperties": 1,
           "properties": {"relative": {"type": "number", "minimum": 0}, "absolute": {"type": "number", "minimum": 0}}}

# The schema as jsonschema and json take it (plain dicts and lists: jsonschema's type checker takes a dict for an
# object, so a read-only mapping as a subschema is silently skipped, fuzz 22a K2); never handed out, load's only.
_PLAIN_SCHEMA: dict[str, Any] = {
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
                "id": {"type": "string", "pattern": _whole(_ID)},
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
                "evidence": {"type": "string", "pattern": _whole(_EVIDENCE)},
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
}
#: JSON schema of a claim file, read-only (a read-only mapping of read-only mappings and tuples, shared by every
#: caller). For jsonschema or ``json.dumps``, which take plain dicts and lists only, use
#: ``json.loads(json.dumps(SCHEMA, default=dict))``.
SCHEMA: Mapping[str, Any] = constant(_PLAIN_SCHEMA)


def _nonempty(value: object, name: str, required: bool = True) -> str:
    """A text field: TypeError naming ``name`` for a non-str, ValueError for a text :func:`_text_problem` refuses
    (one without a visible character when ``required``)."""
    problem = _text_problem(plain := text(value, name), required)
    if problem is not None:
        raise ValueError(f"{name} {problem}")
    return plain  # the plain str (rule 19)


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
        A text field not a str, ``settings`` not a mapping with str keys, ``runs`` neither an integer nor None
        (``100.0`` is not a run count).
    ValueError
        An empty ``key`` or one not of lower-case letters, digits and ``-`` (a claim file's pattern, matching the
        whole key: ``"typical-run\\n"`` is refused); ``kind`` not a reading kind; ``runs`` below 1; ``choice`` or
        ``reading`` not a text :func:`build_ledger` can fill (see :class:`ClaimSpec`); ``settings`` holding a
        container that contains itself, or containers nested more than 64 deep. (``choice`` and ``reading`` may be
        empty: a record without readings has an implicit primary one.)
    """

    key: str
    choice: str
    reading: str
    kind: str
    settings: Mapping[str, Any]
    runs: int | None = None

    def __post_init__(self) -> None:
        if not re.fullmatch(_KEY, text_fields(self, "key") or _nonempty(self.key, "key")):
            raise ValueError(f"key must be lower-case letters, digits and '-' (the pattern {_KEY} of a claim file), "
                             f"got {shown(self.key)}")
        for name in ("choice", "reading"):  # "" for a record's implicit primary reading
            object.__setattr__(self, name, _format_text(_nonempty(getattr(self, name), name, required=False), name))
        text_fields(self, "kind", among=R.READING_KINDS)
        instance_of(self.settings, Mapping, "settings")
        for k in self.settings:
            if not isinstance(k, str):  # a claim file's keys are texts (load refuses any other)
                raise TypeError(f"settings keys must be str, got {shown(k)}")
        if self.runs is not None:
            object.__setattr__(self, "runs", count(self.runs, "runs"))  # the plain int (fuzz 29a C1/C2)
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
        An ``id``, ``chapter``, ``where``, ``claim``, ``published``, ``link``, critique or assumption without a visible
        character (a Hangul filler or the braille blank is not one); any text holding a control or format character
        (Unicode Cc or Cf: NUL, a direction override, a zero-width space or joiner; tab and line break allowed) or a
        lone surrogate (Cs, which cannot be written as UTF-8; ``fusion.book._claim_text``); ``claimant``, ``test``
        or ``direction`` outside its vocabulary; a margin not ``{"relative": r}`` or ``{"absolute": x}`` with
        a finite value in [0, 1e150]; a ``baseline`` without ``name`` and ``defined`` or with another key; a
        repeated critique label or assumption (checked before the texts are scanned); texts of more characters in all
        than the work budget scans (``fusion.book._claim_text.texts_work``: about 27 million, checked first); ``evidence`` not ``module:function`` (the file's pattern); and
        (:class:`ClaimsFileError`, naming the record and the field) every other rule :func:`load` applies to
        one record, so a record rebuilt with ``dataclasses.replace`` is held to them too: ``id`` not
        lower-case words joined by ``-``; a ``claim`` over 200 characters; a paired or equivalence test without
        ``quantity`` and ``direction``; ``direction`` not ``"equal"`` for an equivalence test and only for it;
        ``quantity``, ``direction`` or ``margin`` on a test that compares nothing; ``reason`` missing on an
        unverifiable test or given on another; a headline whose claimant is not the source (R8); an undefined
        baseline without a reason; two readings with one key, or a primary reading that is not first; a text
        :func:`build_ledger` fills (``claim``, ``bound``, ``reason``, ``assumptions``, the baseline's texts and
        the readings') that is not a format text with plain ``{name}`` fields and short specs
        (``{name:.2f}``, at most two digits of width and of precision): an unterminated ``{``, a nested,
        positional or attribute field, a conversion, or a spec such as ``{x:>3000000000}`` (write a brace as
        ``{{`` or ``}}``).
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
        lists = [v for v in (self.critiques, self.assumptions) if isinstance(v, tuple)]  # before any scan (fuzz 53a C1)
        texts_work(sum(str.__len__(x) for x in (*vars(self).values(), *(x for v in lists for x in v))
                       if isinstance(x, str)), "the record's texts (critiques and assumptions included)")
        for name in ("id", "chapter", "where", "claim", "published", "link"):
            object.__setattr__(self, name, _nonempty(getattr(self, name), name))  # plain texts (rule 19)
        text_fields(self, "claimant", among=R.CLAIMANTS), text_fields(self, "test", among=R.TESTS)
        for name in ("quantity", "bound", "reason", "evidence"):
            object.__setattr__(self, name, _nonempty(getattr(self, name), name, required=False))
        text_fields(self, "direction", among=("", "less", "greater", "equal"))
        object.__setattr__(self, "headline", flag(self.headline, "headline"))  # a NumPy bool stored as a bool
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
            object.__setattr__(self, "baseline", _check_baseline(self.baseline))
        for name in ("margin", "baseline"):  # stored read-only: a frozen record's margin cannot be edited (fuzz 20)
            if getattr(self, name) is not None:
                object.__setattr__(self, name, frozen_value(getattr(self, name), name=name))
        for name in ("critiques", "assumptions"):
            v = getattr(self, name)
            if not (isinstance(v, tuple) and all(isinstance(x, str) for x in v)):
                raise TypeError(f"{name} must be a tuple of str, got {shown(v)}")
            for i, x in enumerate(v):  # rule 19 before the repeats are hashed: a str whose hash disagrees is refused
                text(x, f"{name}[{i}]")
        for name, what in (("critiques", "a label"), ("assumptions", "an assumption")):  # as Claim's own check, before
            if len(set(getattr(self, name))) != len(getattr(self, name)):          # the scans (fuzz 53a C1)
                raise ValueError(f"{name} must not repeat {what}, got {shown(getattr(self, name))}")
            for i, x in enumerate(getattr(self, name)):
                _nonempty(x, f"{name}[{i}]")
        if not (isinstance(self.readings, tuple) and all(isinstance(r, ReadingSpec) for r in self.readings)):
            raise TypeError(f"readings must be a tuple of ReadingSpec, got {shown(self.readings)}")
        if self.evidence and not re.fullmatch(_EVIDENCE, self.evidence):
            raise ValueError(f"evidence must be 'module:function' (the pattern {_EVIDENCE} of a claim file), "
                             f"got {shown(self.evidence)}")
        _record_rules(self, f"record {self.id}")


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
    ClaimsFileError
        (a ValueError naming the file, the record and the field) a rule :func:`load` applies to the whole file,
        so a file rebuilt with ``dataclasses.replace`` is held to them too: ``source`` not a key of
        :data:`fusion.book.ledger.SOURCES`; a quantity key not a non-empty str, or its entry not ``{"label",
        "margin"[, "why"]}`` with a non-empty label and a margin as :class:`ClaimSpec` takes it; a repeated
        record id; a record whose chapter is not one of the source's or whose quantity is not declared under
        ``quantities``; not exactly one headline record, in the source's first chapter.
    """

    path: Path
    source: str
    quantities: Mapping[str, Mapping[str, Any]]
    records: tuple[ClaimSpec, ...]

    def __post_init__(self) -> None:
        instance_of(self.path, Path, "path")
        text_fields(self, "source")
        instance_of(self.quantities, Mapping, "quantities")
        if not (isinstance(self.records, (tuple, list)) and all(isinstance(r, ClaimSpec) for r in self.records)):
            raise TypeError(f"records must be a tuple of ClaimSpec, got {shown(self.records)}")
        _file_rules(self)
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


#: Deepest nesting of mappings and lists a claim file may have (its records are 5 deep; PyYAML and jsonschema
#: recurse, so a file nested thousands deep would end in a RecursionError).
_MAX_DEPTH = 32


#: Most values (mappings, lists and scalars) a claim file may expand to, its aliases expanded (the book's largest
#: expands to a few thousand; a 400-byte file of nested aliases expands to 10⁹, which every later step would walk).
_MAX_VALUES = 1_000_000


def _check_depth(doc: Any, name: str) -> None:
    """ClaimsFileError naming the file and the field where ``doc`` nests deeper than ``_MAX_DEPTH``, or expands (its
    YAML aliases written out) to more than ``_MAX_VALUES`` values, or to texts (keys and values) whose scans are beyond
    the work budget (``fusion.book._claim_text.texts_work``; fuzz 53a C1: an alias of a long text was scanned again
    for every use), before any text is scanned.

    Each mapping or list is walked once (by identity): a YAML alias is the same object as its anchor, so a file of
    aliases of aliases costs its own size here, not the size it expands to. A mapping or list that contains itself
    (``&a [*a]``) is nested infinitely deep.
    """
    depth: dict[int, int] = {}  # id(container) -> how many levels below it its deepest value lies
    size: dict[int, int] = {}   # id(container) -> values it expands to, itself included
    chars: dict[int, int] = {}  # id(container) -> characters of the texts (keys and values) it expands to
    on_path: set[int] = set()
    stack: list[tuple[Any, tuple[Any, ...], bool]] = [(doc, (), False)]

    def children(node: Any) -> list[tuple[Any, Any]]:
        return list(node.items()) if isinstance(node, dict) else list(enumerate(node))

    def too(where: tuple[Any, ...], what: str) -> ClaimsFileError:
        field = ".".join(str(p) for p in where[:3]) or "(top level)"
        return ClaimsFileError(f"{name}: field {field}: {what}")

    while stack:
        node, where, done = stack.pop()
        if not isinstance(node, (dict, list)):
            continue
        key = id(node)
        if done:
            kids = [v for _, v in children(node) if isinstance(v, (dict, list))]
            depth[key] = max((1 + depth[id(v)] for v in kids), default=1 if len(node) else 0)
            size[key] = 1 + len(node) + sum(size[id(v)] - 1 for v in kids)
            chars[key] = sum((len(k) if isinstance(k, str) else 0) + (chars[id(v)] if isinstance(v, (dict, list))
                                 else len(v) if isinstance(v, str) else 0) for k, v in children(node))
            on_path.discard(key)
            if len(where) + depth[key] > _MAX_DEPTH:
                raise too(where, f"nested more than {_MAX_DEPTH} deep")
            if size[key] > _MAX_VALUES:
                raise too(where, f"expands (its aliases written out) to more than {_MAX_VALUES:,} values")
            try:
                texts_work(chars[key], "its texts with the YAML aliases written out")
            except ValueError as exc:
                raise too(where, str(exc)) from None
            continue
        if key in on_path:
            raise too(where, f"contains itself (nested infinitely deep, more than {_MAX_DEPTH})")
        if key in depth:
            if len(where) + depth[key] > _MAX_DEPTH:
                raise too(where, f"nested more than {_MAX_DEPTH} deep")
            continue
        if len(where) > _MAX_DEPTH:
            raise too(where, f"nested more than {_MAX_DEPTH} deep")
        on_path.add(key)
        stack.append((node, where, True))
        stack.extend((v, (*where, k), False) for k, v in children(node))

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


def _check_baseline(baseline: Mapping[str, Any]) -> dict[str, Any]:
    """A record's baseline as the schema states it (ValueError or TypeError naming ``baseline``): a record built without
    :func:`load` (``dataclasses.replace``) is held to the file's rules. Returned as a dict, ``defined`` a bool (a NumPy
    bool is one)."""
    keys = set(baseline)
    if not {"name", "defined"} <= keys <= {"name", "defined", "reason", "stand_in"}:
        raise ValueError(f"baseline must hold 'name' and 'defined' (and optionally 'reason', 'stand_in'), "
                         f"got {shown(baseline)}")
    for k in ("name", "reason", "stand_in"):
        if k in baseline and not isinstance(baseline[k], str):
            raise TypeError(f"baseline.{k} must be a str, got {shown(baseline[k])}")
        if k in baseline:
            _nonempty(baseline[k], f"baseline.{k}")
    return {**baseline, "defined": flag(baseline["defined"], "baseline.defined")}


def _format_text(value: str, name: str) -> str:
    """``value``, or ValueError naming ``name`` when :func:`build_ledger` could not fill it (``_format_problem``)."""
    problem = _format_problem(value)
    if problem is not None:
        raise ValueError(f"{name}: {problem}")
    return value


def _record_rules(spec: ClaimSpec, where: str) -> None:
    """The rules :func:`load` applies to one record beyond the schema's types: one check, used by :class:`ClaimSpec`
    (so by :func:`load` and by a record rebuilt with ``dataclasses.replace``). ClaimsFileError naming ``where``
    (``record <id>``) and the field."""
    def bad(field: str, what: str) -> ClaimsFileError:
        return ClaimsFileError(f"{where}: field {field}: {what}")

    if not re.fullmatch(_ID, spec.id):
        raise bad("id", f"{shown(spec.id)} is not lower-case words joined by '-' (the pattern {_ID})")
    if len(spec.claim) > 200:
        raise bad("claim", f"{len(spec.claim)} characters, at most 200 (one sentence)")
    if spec.test in ("paired", "equivalence"):
        for f in ("quantity", "direction"):
            if not getattr(spec, f):
                raise bad(f, f"required for a {spec.test} test")
        if (spec.test == "equivalence") != (spec.direction == "equal"):
            raise bad("direction", "an equivalence test has direction 'equal', a paired test 'less' or 'greater'")
    if spec.test == "unverifiable" and not spec.reason:
        raise bad("reason", "required for an unverifiable test")
    for f in ("quantity", "direction", "margin"):
        if getattr(spec, f) and spec.test not in _COMPARING_TESTS:
            raise bad(f, f"a {spec.test} test compares nothing (only {', '.join(_COMPARING_TESTS)} tests take it)")
    if spec.reason and spec.test != "unverifiable":
        raise bad("reason", "only an unverifiable test takes a reason (an undefined baseline's goes under "
                            "baseline.reason)")
    if spec.headline and spec.claimant != "source":
        raise bad("headline", f"only a claim the source prints can be its main finding (rule R8), claimant is "
                              f"{shown(spec.claimant)}")
    b = spec.baseline
    if b is not None and not b["defined"] and "reason" not in b:
        raise bad("baseline.reason", "required when the baseline is undefined")
    keys: set[str] = set()  # a set: a scan of the keys before each reading was quadratic (fuzz 22a Q2)
    for i, r in enumerate(spec.readings):
        if r.key in keys:
            raise bad("readings.others", f"duplicate key {shown(r.key)}")
        keys.add(r.key)
        if (r.key == "primary") != (r.kind == "primary") or (r.key == "primary" and i):
            raise bad(f"readings.{r.key}", "the reading with key 'primary' comes first and it alone has kind 'primary'")
    texts = [("claim", spec.claim), ("bound", spec.bound), ("reason", spec.reason)]
    texts += [(f"assumptions.{i}", a) for i, a in enumerate(spec.assumptions)]
    if b is not None:
        texts += [(f"baseline.{k}", b[k]) for k in ("reason", "stand_in") if k in b]
        if not b["defined"] and "stand_in" not in b:  # the default stand-in text quotes the name
            texts.append(("baseline.name", b["name"]))
    for field, value in texts:
        problem = _format_problem(value)
        if problem is not None:
            raise bad(field, problem)


def _file_rules(cf: ClaimsFile) -> None:
    """The rules :func:`load` applies to a whole file: one check, used by :class:`ClaimsFile` (so by :func:`load` and
    by a file rebuilt with ``dataclasses.replace``). ClaimsFileError naming the file, the record and the field."""
    name = cf.path.name
    if cf.source not in SOURCES:
        raise ClaimsFileError(f"{name}: field source: {shown(cf.source)} is not one of {sorted(SOURCES)}")
    src = SOURCES[cf.source]
    # counted, and their texts' characters too, before any is scanned (fuzz 53a C1's class: one long label aliased)
    n_q = sum(1 for _ in itertools.islice(iter(cf.quantities), MAX_COUNT + 1))
    if n_q > MAX_COUNT:
        raise ClaimsFileError(f"{name}: field quantities: more than {MAX_COUNT:,} (rule 9: entries are a size)")
    try:
        texts_work(sum(str.__len__(x) for q, e in itertools.islice(cf.quantities.items(), n_q)
                       for x in (q, *((e.get("label"), e.get("why")) if isinstance(e, Mapping) else ()))
                       if isinstance(x, str)), "quantities")
    except ValueError as exc:
        raise ClaimsFileError(f"{name}: field {exc}") from None
    for q, entry in itertools.islice(cf.quantities.items(), n_q):
        where = f"{name}: quantity {q if isinstance(q, str) else shown(q)}"
        if not isinstance(q, str) or _text_problem(q) is not None:  # one rule for every text (fuzz 29a D1)
            raise ClaimsFileError(f"{where}: a quantity key must be a non-empty text of visible characters")
        if not isinstance(entry, Mapping) or not {"label", "margin"} <= set(entry) <= {"label", "margin", "why"}:
            raise ClaimsFileError(f"{where}: must be a mapping of 'label', 'margin' and optionally 'why', got "
                                  f"{shown(entry)}")
        for k in ("label", "why"):
            v = entry.get(k, "-")
            problem = _text_problem(v) if isinstance(v, str) else f"must be a non-empty text, got {shown(v)}"
            if problem is not None:
                raise ClaimsFileError(f"{where}, field {k}: {problem}")
        m = entry["margin"]
        if not isinstance(m, Mapping) or set(m) not in ({"relative"}, {"absolute"}):
            raise ClaimsFileError(f"{where}, field margin: must be {{'relative': r}} or {{'absolute': x}}, got "
                                  f"{shown(m)}")
        _check_margin(m, f"{where}, field margin")
    seen: set[str] = set()
    for r in cf.records:
        where = f"{name}: record {r.id}"
        if r.id in seen:
            raise ClaimsFileError(f"{where}: field id: duplicate id")
        seen.add(r.id)
        if r.chapter not in src.chapters:
            raise ClaimsFileError(f"{where}: field chapter: {shown(r.chapter)} is not a chapter of {src.key}")
        if r.quantity and r.quantity not in cf.quantities:
            raise ClaimsFileError(f"{where}: field quantity: {shown(r.quantity)} is not declared under quantities")
    heads = [s for s in cf.records if s.headline]
    if len(heads) != 1 or heads[0].chapter != src.chapter:
        raise ClaimsFileError(f"{name}: field headline: exactly one record, in {src.chapter}, must be the "
                              f"headline (found {[s.id for s in heads]})")


def _evidence_function(evidence: str, where: str) -> Any:
    """The function a record's ``evidence`` names (``module:function``), imported; ClaimsFileError naming ``where``
    (which names the field evidence) when the module cannot be imported or has no such function."""
    mod, sep, name = evidence.partition(":")
    if not sep or not mod or not name:
        raise ClaimsFileError(f"{where}: {shown(evidence)} is not 'module:function'")
    try:
        module = importlib.import_module(mod)
    except Exception as e:  # ImportError, and importlib's TypeError for '.x', a module that fails while importing
        raise ClaimsFileError(f"{where}: module {shown(mod)} cannot be imported ({type(e).__name__}: {e})") from None
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
        ``path`` is not a readable file (missing, a directory, unreadable, a FIFO or a device, larger than 16 MB)
        or is not UTF-8 text.
    ClaimsFileError
        The file is malformed: the message names the file, the record and the field. Also (before any text is scanned)
        a file whose texts, its YAML aliases written out, hold more characters than the work budget scans (about 27
        million: an alias of a long text is scanned once for each use), naming the file and the field.
    """
    import jsonschema

    if not isinstance(path, (str, os.PathLike)):
        raise TypeError(f"path must be a path (str or os.PathLike), got {type(path).__name__}")
    path = Path(path)
    try:   # a regular file of at most MAX_FILE_BYTES, by name before reading (fuzz 34a C3, C4, C5)
        raw = file_bytes(path, f"path {shown(str(path))}").decode("utf-8")
        raw = raw.replace("\r\n", "\n").replace("\r", "\n")   # universal newlines, as read_text
    except UnicodeDecodeError as e:
        raise ValueError(f"path {shown(str(path))} is not UTF-8 text ({e.reason} at byte {e.start})") from None
    doc = _parsed_claims.kept(raw)  # a text parsed before: a copy of its document (speed58)
    if doc is None:
        try:
            doc = yaml.load(raw, Loader=_UniqueKeyLoader)  # noqa: S506 - a SafeLoader that refuses repeated keys
        except yaml.YAMLError as e:
            raise ClaimsFileError(f"{path.name}: not valid YAML ({e})") from None
        except RecursionError:  # PyYAML composes and constructs recursively
            raise ClaimsFileError(f"{path.name}: not valid YAML (nested more than {_MAX_DEPTH} deep)") from None
        _check_depth(doc, path.name)
        _parsed_claims.keep(raw, doc)
    errors = sorted(jsonschema.Draft202012Validator(_PLAIN_SCHEMA).iter_errors(doc), key=lambda e: list(e.absolute_path))
    if errors:
        e = errors[0]
        raise ClaimsFileError(f"{path.name}: {_where(e, doc)}: {e.message}")
    quantities = doc.get("quantities", {})
    specs = []
    for r in doc["records"]:  # the record rules are ClaimSpec's, the file rules ClaimsFile's: one check for both
        rid = r["id"]
        where = f"{path.name}: record {rid}"
        rd = r.get("readings", {})
        given = ([("primary", rd["primary"], "primary")] if "primary" in rd else []) + [
            (o["key"], o, o.get("kind", "open-choice")) for o in rd.get("others", [])]
        readings = []
        for key, o, kind in given:
            try:
                readings.append(ReadingSpec(key, o["choice"], o["reading"], kind, o.get("settings", {}), o.get("runs")))
            except (TypeError, ValueError) as e:  # runs: 100.0 (JSON Schema's integer), a text that cannot be filled
                raise ClaimsFileError(f"{where}: field readings.{key}.{e}") from None
        pub = r["published"]
        published = " ".join(x for x in (pub["value"], pub.get("unit", "")) if x) + (
            f" ({pub['precision']})" if "precision" in pub else "")
        try:
            spec = ClaimSpec(
                id=rid, chapter=r["chapter"], where=r["where"], claim=r["claim"], claimant=r["claimant"],
                published=published, test=r["test"], link=r["link"], quantity=r.get("quantity", ""),
                direction=r.get("direction", ""), margin=r.get("margin"), baseline=r.get("baseline"),
                headline=r.get("headline", False), critiques=tuple(r.get("critiques", ())),
                assumptions=tuple(r.get("assumptions", ())), bound=r.get("bound", ""), reason=r.get("reason", ""),
                evidence=r.get("evidence", ""), readings=tuple(readings))
        except ClaimsFileError as e:  # names the record and the field
            raise ClaimsFileError(f"{path.name}: {e}") from None
        except (TypeError, ValueError) as e:  # names the field
            raise ClaimsFileError(f"{where}: field {e}") from None
        if spec.evidence:
            _evidence_function(spec.evidence, f"{where}: field evidence")
        specs.append(spec)
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
    problem = _format_problem(text)  # the record's own check (ClaimSpec), here for a text built in build_ledger
    if problem is not None:
        raise ClaimsFileError(f"{where}: {problem}")
    fields = [f for _, f, _, _ in string.Formatter().parse(text) if f is not None]
    missing = [f for f in fields if f not in values]
    if missing:
        raise ClaimsFileError(f"{where}: names values {missing} that the chapter does not provide")
    try:
        return text.format_map(values)
    except (ValueError, TypeError, KeyError, IndexError, AttributeError) as e:  # a value its spec does not fit
        raise ClaimsFileError(f"{where}: cannot format ({type(e).__name__}: {e})") from None


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
    # at most one key past the file's records is read (fuzz 53a C2's class: a lazy mapping of 6e7 keys was walked)
    keys = list(itertools.islice(iter(evidence), len(ids) + 1))
    extra = sorted(set(keys) - ids)
    missing = sorted(ids - set(keys))
    if extra or missing:
        raise ClaimsFileError(f"{cf.path.name}: evidence for records not in the file for {led.chapter}: {extra}"
                              f"{' (among others)' if len(keys) > len(ids) else ''}; records without evidence: "
                              f"{missing}")
    for spec in specs:
        where = f"{cf.path.name}: record {spec.id}"
        given = evidence[spec.id]
        want = {"primary"} | {r.key for r in spec.readings if r.key != "primary"}
        by_key = ({k: given[k] for k in itertools.islice(iter(given), len(want) + 1)}  # one key past want at most
                  if isinstance(given, Mapping) else {"primary": given})
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
            try:
                by_key[k] = _with_margin(ev, margin)
            except ValueError as exc:   # a margin the file allows that this evidence cannot take (fuzz 49b C3)
                field = (f"{where}, field margin" if spec.margin else f"{cf.path.name}: quantity {spec.quantity}, "
                         "field margin")
                raise ClaimsFileError(f"{field} (reading {k}): {exc}") from None
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
    count: ``fn(settings, seed=seed, runs=runs) -> Evidence``. A record whose function cannot be called so (its
    signature does not bind these arguments: a deterministic record's evidence function, which takes a chapter's
    studies, as ``ev_awf_optimal(st)``) is refused before the call (fuzz 40b C5: a raw TypeError naming nothing).

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
        evidence function, names one that does not exist or cannot take ``(settings, seed=, runs=)`` (field
        evidence) or has no reading ``reading``.
    """
    from fusion._validation import seed as check_seed

    instance_of(spec, ClaimSpec, "spec")
    reading = text(reading, "reading")
    seed, runs = check_seed(seed), count(runs, "runs")  # plain ints (a 0-d array is its integer)
    if not spec.evidence:
        raise ClaimsFileError(f"record {spec.id}: names no evidence function")
    fn = _evidence_function(spec.evidence, f"record {spec.id}: field evidence")
    try:   # the one test of what evaluate calls: the function's own signature (fuzz 40b C5)
        inspect.signature(fn).bind({}, seed=seed, runs=runs)
    except TypeError:
        raise ClaimsFileError(f"record {spec.id}: field evidence: {shown(spec.evidence)} takes "
                              f"({', '.join(inspect.signature(fn).parameters)}), not "
                              "(settings, *, seed, runs): a deterministic record's evidence is not recomputed by "
                              "evaluate") from None
    settings = next((r.settings for r in spec.readings if r.key == reading), None)
    if settings is None and reading != "primary":
        raise ClaimsFileError(f"record {spec.id}: no reading {shown(reading)}")
    return fn(dict(settings or {}), seed=seed, runs=runs)
