r"""Helpers shared by the three chapters on the lecture notes (source ``lecture003``).

Chapters 02 (:mod:`fusion.book.chapters.lecture_weighting`, sections 2.1-2.4), 03
(:mod:`fusion.book.chapters.lecture_wavelets`, section 2.6) and 04
(:mod:`fusion.book.chapters.lecture_correlated`, sections 2.5 and 2.7) each build their part of
the source's claims ledger; this module holds the source key and the glue helpers they share.
"""

from __future__ import annotations

import functools
import os
import re
from collections.abc import Callable, Collection, Mapping
from pathlib import Path
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from matplotlib.figure import Figure, SubFigure

from fusion._docstrings import with_sections
from fusion.book._few_runs import paired_runs, runs_named
from fusion.book._reader_settings import reads, settings_first
from fusion.book.glue import GlueValues
from fusion.book.study_cache import process_cache
from fusion.book.ledger import (EVIDENCE_TYPES, Comparison, Conjunction, Evidence,  # noqa: F401 (readings' return hints)
                                Unverifiable, ledger_dir)
from fusion.book.tables import _SUPERSCRIPT, _exact_significant, _frame, _nonfinite_word, rounded  # noqa: F401 (_frame: the chapters' table rule)
from fusion._counts import count, seed as check_seed
from fusion._options import text
from fusion._paths import file_text, notebook_markdown
from fusion._structures import within
from fusion._validation import _real_number, as_callable, instance_of, mapping_of
from fusion._shown import shown

__all__ = ["SOURCE", "glue_figures", "legend_below", "sci", "book_words", "referenced", "reading_key",
           "evidence_at", "reading_function", "reading_of"]

SOURCE = "lecture003"

#: The Returns section of a glue function whose keys are ``lec_`` + a key and whose values are rounded
#: (:func:`fusion._docstrings.with_sections`).
_lec_glue = with_sections(returns="GlueValues\n    Glue keys (prefixed ``lec_``) and rounded values.")


def _r(d: dict[str, tuple[float, int]]) -> GlueValues:
    """``{key: (value, decimals)}`` → ``{"lec_" + key: rounded value}``."""
    return {f"lec_{k}": rounded(v, dec) for k, (v, dec) in d.items()}


def glue_figures(figures: dict[str, Figure]) -> None:
    """Glue each figure under its key (not displayed) and close it, so the page shows it once.

    Parameters
    ----------
    figures : dict of str to matplotlib Figure
        Glue keys and figures; each figure is closed after gluing.

    Raises
    ------
    TypeError
        ``figures`` not a mapping, or a value not a matplotlib Figure.
    ValueError
        ``figures`` empty, or a key empty or not of ASCII letters, digits, underscores and hyphens (the whole-key
        rule of :func:`fusion.book.glue.glue_all`).
    """
    from fusion.book.figures import glue_figure
    from fusion.book.glue import _glue_key

    mapping_of(figures, "figures", "figure", values=Figure)
    keys = [_glue_key(key, "figures") for key in figures]  # every key checked before the first figure is glued
    for key, fig in zip(keys, figures.values()):
        glue_figure(key, fig)   # checks the book's figure rules, glues, closes



def legend_below(fig: Figure, ncol: int = 3) -> None:
    """One legend for the whole figure, below the axes (never over data), 9 pt.

    Collects the labelled artists of every axes (each label once, in drawing order) and places a
    figure legend under the figure's bottom edge, so it can cover neither data nor axis labels.

    Parameters
    ----------
    fig : matplotlib Figure
        The finished figure (a :class:`~matplotlib.figure.Figure` or a :class:`~matplotlib.figure.SubFigure`).
    ncol : int
        Number of legend columns, >= 1. Columns beyond the number of legend entries would be empty and take no
        room: the legend has ``min(ncol, entries)`` columns (so that ``ncol = 10**9`` does not lay out a billion
        empty columns).

    Raises
    ------
    TypeError
        ``fig`` is not a Figure, or ``ncol`` not an integer.
    ValueError
        ``ncol`` is below 1 (or beyond the ceiling of a count).
    """
    instance_of(fig, (Figure, SubFigure), "fig")
    ncol = count(ncol, "ncol")
    handles, labels = [], []
    for ax in fig.axes:
        for h, lab in zip(*ax.get_legend_handles_labels()):
            if lab not in labels:
                handles.append(h)
                labels.append(lab)
        if ax.get_legend() is not None:
            ax.get_legend().remove()
    if handles:
        fig.legend(handles, labels, loc="upper center", bbox_to_anchor=(0.5, 0.0), ncol=min(ncol, len(handles)),
                   fontsize=9, frameon=False)


def sci(value: float, digits: int = 2) -> str:
    """A number for the reader in ``a × 10ⁿ`` form (no ``e`` notation); 0 is written ``0``.

    Parameters
    ----------
    value : float
        The number.
    digits : int
        Significant digits of the mantissa.

    Returns
    -------
    str
        E.g. ``sci(1.75e11, 3) == "1.75 × 10¹¹"``; ``"—"`` for NaN, ``"∞"`` and ``"-∞"`` for the infinities (the
        rule of every number formatter of the book, ``fusion.book.tables.NONFINITE_RULE``; it printed ``nan``).

    Raises
    ------
    TypeError
        ``value`` is text (``"1"``), bytes, ``None``, a bool, complex or a container, naming ``value``.
    """
    v = _real_number(value, "value", bound=None)  # a printed number: the float range its only bound (fuzz 42b D4)
    digits = count(digits, "digits")  # 1 to 17 (a float64 holds 17 significant digits)
    word = _nonfinite_word(v)
    if word is not None:
        return word
    if v == 0.0:
        return "0"  # also for -0.0: "0 is written 0", as ledger.fmt and tables.sci print it (fuzz 19, E8)
    v = _exact_significant(value, v, digits)  # a Decimal or Fraction rounded as it is (fuzz 46b D3)
    e = int(np.floor(np.log10(abs(v))))
    # 10.0**e underflows to 0 below 1e-323 (a subnormal value: 5e-324): scale up first (fuzz 20, A)
    m = round(v / 10.0**e, digits - 1) if e > -300 else round((v * 1e300) / 10.0 ** (e + 300), digits - 1)
    if abs(m) >= 10:
        m, e = m / 10, e + 1
    return f"{m:.{digits - 1}f} × 10{str(e).translate(_SUPERSCRIPT)}"


def _key(value: object, keys: Collection[Any], name: str) -> Any:
    """``value`` when it is one of ``keys`` (a key of a study's mapping: a method, a level, a case), else a
    ValueError naming ``name`` with the keys (TypeError for an unhashable value): the lookup's KeyError never escapes."""
    try:
        ok = value in keys
    except TypeError:
        raise TypeError(f"{name} must be one of {shown(list(keys), 200)}, got an unhashable {type(value).__name__}") from None
    if not ok:
        raise ValueError(f"{name} must be one of {shown(list(keys), 200)}, got {shown(value, 80)}")
    return value


def _holds(held: Collection[Any], needed: Collection[Any], name: str, what: str, reader: str) -> None:
    """The rule of a chapter function that reads a study's entries by key (fuzz 26d, class A): ``name`` holds every
    entry of ``needed`` (a level, a case, a sensor, a setting) among ``held``, else a ValueError naming ``name``, the
    ``what`` it lacks and ``reader``, the function that reads them: never a KeyError or IndexError from inside, nor
    another entry's number read in place of a missing one (a study made at other valid settings)."""
    held = list(held)
    lacking = [k for k in needed if k not in held]
    if lacking:
        raise ValueError(f"{name} lacks the {what} {shown(lacking, 200)} that {reader} reads (it holds "
                         f"{shown(held, 200)})")


def _members(parts: Collection[tuple[str, Any]], name: str, what: str, reader: str) -> Conjunction:
    """The Conjunction of ``parts`` that ``reader`` builds from the ``what`` of a study ``name`` (fuzz 34b B8): a
    study at other valid settings with fewer than two of them is refused naming ``name`` and what it lacks, never
    under the Conjunction's own ``parts``."""
    if len(parts) < 2:
        raise ValueError(f"{name} must hold at least two {what}, which {reader} reads as a conjunction, got "
                         f"{len(parts)}")
    return Conjunction(tuple(parts))


_WORD = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


def book_words(root: Path | None = None) -> frozenset[str]:
    """Every identifier-like word of the book's texts: notebook markdown, ``book/**/*.md``, ``book/claims/*.yaml``.

    A glue key is referenced when it is one of these words (``{glue:text}`key```, ``nb::key``, ``{key}``).

    Parameters
    ----------
    root : pathlib.Path, optional
        The repository (default: the one that holds the working directory).

    Returns
    -------
    frozenset of str
        The distinct identifier-like words (letters, digits and ``_``, not starting with a digit) of all those texts.

    Raises
    ------
    TypeError
        ``root`` not a path.
    ValueError
        ``root`` not a folder holding ``book/``; one of those files not a readable regular UTF-8 file of at most
        16 MB (a FIFO, a device, a folder named ``*.md``: ``fusion._paths.file_text``), or a notebook that is not
        one (no list of cells with a ``cell_type`` and a text ``source``), naming ``root`` and the file.
    """
    if root is not None:
        if not isinstance(root, (str, os.PathLike)):
            raise TypeError(f"root must be a path (the repository), got {type(root).__name__}")
        if not (Path(root) / "book").is_dir():
            raise ValueError(f"root must be the repository (a directory holding book/), got {shown(str(root), 80)}")
    base = Path(root) if root is not None else ledger_dir().parent.parent
    where = "root" if root is not None else "the repository"

    def label(p: Path) -> str:
        return f"{where}: {shown(p.relative_to(base).as_posix(), 80)}"

    texts = [file_text(p, label(p)) for p in sorted((base / "book").rglob("*.md"))]
    texts += [file_text(p, label(p)) for p in sorted((base / "book" / "claims").glob("*.yaml"))]
    for nb in sorted((base / "notebooks").glob("*.ipynb")):
        texts += notebook_markdown(nb, label(nb))
    return frozenset(_WORD.findall("\n".join(texts)))


def referenced(values: Mapping[str, Any], words: frozenset[str] | None = None) -> GlueValues:
    """The glue values the book references (see :func:`book_words`); the others are not glued.

    Parameters
    ----------
    values : mapping
        Glue key → value (a ``glue_*`` function's output).
    words : frozenset of str, optional
        The words of the book's prose (a set or another collection of strings, matched whole). Default:
        :func:`book_words` of the repository. A single ``str`` is refused: it would be read as its substrings
        (``"ab" in "xaby"``).

    Returns
    -------
    GlueValues
        The referenced items, in their order.

    Raises
    ------
    ValueError
        ``values`` is not a mapping.
    TypeError
        ``words`` is a string, not a collection, or holds a non-string.
    """
    if not isinstance(values, Mapping):
        raise ValueError(f"values must be a mapping of glue keys, got {type(values).__name__}")
    if words is not None:
        if isinstance(words, (str, bytes)) or not isinstance(words, Collection):
            raise TypeError(f"words must be a set of words (str), not a {type(words).__name__}: a string would be "
                            "matched by its substrings")
        bad = next((x for x in words if not isinstance(x, str)), None)
        if bad is not None:
            raise TypeError(f"words must hold strings only, got {shown(bad)}")
    w = book_words() if words is None else words
    return {k: v for k, v in values.items() if k in w}


def reading_key(settings: Mapping[str, Any] | None) -> str:
    """The reading a record's evidence function is asked for: ``settings["reading"]``, default ``"primary"``.

    Parameters
    ----------
    settings : mapping or None
        A reading's ``settings`` in the claim file.

    Returns
    -------
    str
        ``"primary"`` or the reading key the settings give.

    Raises
    ------
    TypeError
        ``settings`` neither a mapping nor None, or its ``"reading"`` not a string (a key is never converted: ``5``
        is not the reading ``"5"``): the one rule of every chapter's readers (``fusion.book._reader_settings``).
    ValueError
        A key other than ``"reading"`` (a misspelt setting is never silently ignored).
    """
    settings = settings_first(settings, ("reading",))  # fuzz 19, fuzz 52 C7: one rule for every chapter's readers
    return text(settings.get("reading", "primary"), "settings['reading']")  # fuzz 18, E10


def reading_of(rid: str, ev: Evidence | Mapping[str, Evidence], settings: Mapping[str, Any] | None) -> Evidence:
    """The reading ``settings["reading"]`` (:func:`reading_key`) of record ``rid`` from the record's evidence ``ev``.

    Parameters
    ----------
    rid : str
        The record id (named in the error).
    ev : Evidence or mapping of str to Evidence
        One Evidence (a record without readings: only ``"primary"``) or reading key → Evidence.
    settings : mapping or None
        A reading's ``settings`` in the claim file.

    Returns
    -------
    Evidence
        ``ev`` itself for the primary of a record without readings, else ``ev[key]``.

    Raises
    ------
    TypeError
        ``settings`` not a mapping or its ``"reading"`` not a string (:func:`reading_key`); ``ev`` neither an
        Evidence (one of the ledger's evidence classes) nor a mapping, a key of the mapping
        not a str, or a value of it not an Evidence (naming ``ev`` and the key): a record's evidence function that
        returns anything else is refused here, not where the ledger reads it.
    ValueError
        If the record has no such reading, or ``settings`` holds a key other than ``"reading"`` (naming
        ``settings``).
    """
    rid = text(rid, "rid")
    key = reading_key(settings)
    if not isinstance(ev, Mapping):
        if not isinstance(ev, EVIDENCE_TYPES):  # fuzz 21b, H: a non-Evidence was returned as the evidence
            raise TypeError(f"ev must be an Evidence or a mapping of reading keys to Evidence (record {rid}), "
                            f"got {type(ev).__name__}")
        if key != "primary":
            raise ValueError(f"settings: record {rid} has no reading {shown(key)}")
        return ev
    for k, v in ev.items():
        if not isinstance(k, str):
            raise TypeError(f"ev: the reading keys of record {rid} must be strings, got {type(k).__name__} {shown(k, 60)}")
        if not isinstance(v, EVIDENCE_TYPES):
            raise TypeError(f"ev[{shown(k)}] must be an Evidence (record {rid}), got {type(v).__name__}")
    if key not in ev:
        raise ValueError(f"settings: record {rid} has no reading {shown(key)}; it has {sorted(ev)}")
    return ev[key]


_READING_DOC = """``{rid}``, one reading: {summary}

Parameters
----------
settings : mapping
    ``{{"reading": key}}``: ``"primary"`` (the default) or a reading key of the claim file.
seed, runs : int
    {seed_runs} A reading that compares runs pairwise needs at least
    :data:`~fusion.book.ledger.MIN_RUNS` of them (rule R4; the function takes no ``reason``): fewer are refused
    naming ``runs`` (fewer than 2 as an integer below 2).

Returns
-------
{returns}
    The reading's evidence.
"""


def reading_function(module: str, rid: str, at: Callable[[str, Mapping[str, Any], int, int], Evidence], seed: int,
                     runs: int, summary: str, seed_runs: str, returns: str = "Comparison",
                     budget: Callable[[str, list[tuple[str, int]]], object] | None = None) -> Callable[..., Evidence]:
    """The evidence function of a record with readings, ``fn(settings, *, seed=seed, runs=runs)``: ``at(rid, settings,
    seed, runs)``, the reading ``settings["reading"]`` of record ``rid`` on the studies at ``seed`` and ``runs``.

    One function serves the records whose evidence functions differ only in their record and docstring; it is named
    ``ev_<rid without "lec-", dashes as underscores>``, the name the record's ``evidence`` field gives, and has a
    numpydoc docstring for the API page.

    Parameters
    ----------
    module : str
        The ``__name__`` of the chapter module that defines the function (its ``__module__``).
    rid : str
        The record id.
    at : callable
        ``at(rid, settings, seed, runs)``: the chapter's reading of a record.
    seed, runs : int
        The defaults of the function's ``seed`` and ``runs``.
    summary : str
        What the readings compare (the docstring's summary after ``"``rid``, one reading: "``).
    seed_runs : str
        The docstring's description of ``seed`` and ``runs``.
    returns : str
        The evidence type, as the docstring names it (``"Comparison or Conjunction"``).
    budget : callable, optional
        ``budget(rid, [(reading key, runs), ...])``: the work of the record's readings read together, refused by a
        ValueError naming ``runs`` before any study; kept as ``fn.budget`` (one argument, the list), which
        :func:`evidence_at` calls for every record before any reading (fuzz 62a).

    Returns
    -------
    callable
        ``fn``, named ``ev_<rid>`` in ``module`` with a numpydoc docstring; it returns the reading's Evidence.
    """
    module, rid, summary, seed_runs, returns = (text(v, n) for v, n in (
        (module, "module"), (rid, "rid"), (summary, "summary"), (seed_runs, "seed_runs"), (returns, "returns")))
    if not rid:
        raise ValueError("rid must be a record id, got an empty string")
    as_callable(at, "at")
    seed, runs = check_seed(seed), paired_runs(runs)

    @reads("reading")  # settings checked first, its keys declared (fuzz 52 C7)
    def fn(settings: Mapping[str, Any], *, seed: int = seed, runs: int = runs) -> Evidence:
        seed, n = check_seed(seed), paired_runs(runs)  # the record's entry: 1.5 is not seed 1; 1 run pairs nothing
        with runs_named("runs", f"runs={n}; the record's own run count is {runs}"):  # rule R4 named (fuzz 22b A2)
            return at(rid, settings, seed, n)

    fn.__name__ = fn.__qualname__ = "ev_" + rid.removeprefix("lec-").replace("-", "_")
    fn.__module__ = module
    fn.__doc__ = _READING_DOC.format(rid=rid, summary=summary, seed_runs=seed_runs, returns=returns)
    fn.__annotations__["return"] = returns.replace(" or ", " | ")
    if budget is not None:
        as_callable(budget, "budget")
        fn.budget = functools.partial(budget, rid)  # type: ignore[attr-defined]
    return fn


@process_cache(maxsize=4)
def _load_claims(path: Path, mtime_ns: int, size: int) -> Any:
    from fusion.book import claims as cl

    return cl.load(path)


def _source_claims() -> Any:
    """``book/claims/lecture003.yaml`` (:func:`fusion.book.claims.load`), read once per version of the file: the
    YAML parse costs about 0.3 CPU-s, and each stochastic record's evidence function and :func:`evidence_at` read
    the file (keyed by path, modification time and size, so an edited file is read again)."""
    from fusion.book import claims as cl

    path = cl.claims_dir() / f"{SOURCE}.yaml"
    try:
        st = path.stat()
    except OSError:
        return cl.load(path)  # its own refusal of a missing file
    return _load_claims(path, st.st_mtime_ns, st.st_size)


def evidence_at(records: Mapping[str, int], seed: int) -> dict[str, dict[str, Evidence]]:
    """Every reading's evidence of ``records`` through their evidence functions (:func:`fusion.book.claims.evaluate`).

    Each reading runs at its own run count where the claim file states one (a reading's ``runs``), else at its
    record's; the studies are cached by the chapter modules, so a chapter that computed them at the same seed and
    runs computes nothing again.

    Parameters
    ----------
    records : mapping
        Record id of ``book/claims/lecture003.yaml`` → the record's run count.
    seed : int

    Returns
    -------
    dict
        Record id → {reading key → Evidence}, ``"primary"`` included.

    Raises
    ------
    TypeError
        ``records`` not a mapping, a record id not a string, a run count not an integer.
    ValueError
        A record id not in the claim file, a run count below 1 or below rule R4's minimum, naming
        ``records[id]``.
    """
    if not isinstance(records, Mapping):
        raise TypeError(f"records must be a mapping of record ids to run counts, got {type(records).__name__}")
    seed = check_seed(seed)
    checked: dict[str, int] = {}
    for rid, runs in records.items():  # every entry checked before the claim file is read
        path = f"records[{shown(rid)}]"
        with within(path):
            checked[text(rid, "the record id")] = count(runs, "runs")
    if not checked:
        return {}
    from fusion.book import claims as cl

    cf = _source_claims()
    plan: dict[str, tuple[Any, list[tuple[str, int]]]] = {}
    for rid, runs in checked.items():
        path = f"records[{shown(rid)}]"
        try:
            spec = cf.record(rid)
        except cl.ClaimsFileError:
            raise ValueError(f"{path}: no such record in {SOURCE}.yaml") from None
        keys = ["primary"] + [r.key for r in spec.readings if r.key != "primary"]
        own = {r.key: r.runs for r in spec.readings}
        plan[rid] = spec, [(k, own.get(k) or runs) for k in keys]
    # rule 17 before any reading: each record's readings read together, by the studies they run (fuzz 62a: the
    # regime study of lec-awf-adapts ran ~36 CPU-s at 1,800 runs before its change-* readings' study refused)
    for rid, (spec, reads) in plan.items():
        if not isinstance(spec.evidence, str) or not spec.evidence:
            continue
        try:   # a record without a callable evidence function is refused by evaluate, in its turn, as before
            budget = getattr(cl._evidence_function(spec.evidence, f"record {rid}: field evidence"), "budget", None)
        except cl.ClaimsFileError:
            continue
        if budget is not None:
            with within(f"records[{shown(rid)}]"):
                budget(reads)
    out: dict[str, dict[str, Evidence]] = {}
    for rid, (spec, reads) in plan.items():
        with within(f"records[{shown(rid)}]"):  # too few runs for rule R4 is named by the record's entry
            out[rid] = {k: cl.evaluate(spec, k, seed, r) for k, r in reads}
    return out
