"""Chapter 01 (the optimal fusion set): the ledger's numbers the prose quotes, and the verdict table."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import math

import numpy as np
import pandas as pd

from fusion._frozen import constant
from fusion._counts import sequence
from fusion._shown import shown
from fusion._validation import instance_of, text
from fusion.book.ledger import Comparison, Ledger, Unverifiable
from fusion.book.glue import GlueValues, _glue_prefix
from fusion.book.tables import rounded
from fusion.book.chapters.ofs.settings import SOURCE

__all__ = [
    "LEDGER_GLUE",
    "verdict_table",
    "ledger_numbers",
    "comparison_numbers",
]


#: The ledger numbers the chapter's prose quotes: record id -> fields (see :func:`ledger_numbers`).
LEDGER_GLUE: dict[str, tuple[str, ...]] = constant({
    "yang-totals-ranking-mean": ("status",),
    "yang-totals-ranking-support": ("status",),
    "yang-median-total": ("status",),
    "yang-obs-closer": ("status",),
    "yang-membership-free": ("status",),
    "yang-fig2-vs-mean": ("diff", "hi", "lo", "margin", "rel", "robustness", "status"),
    "yang-fig2-fluctuation": ("robustness", "status"),
    "yang-fig2-vs-support": ("hi", "lo"),
    "yang-fig2-fluctuation-support": ("a", "b"),
    "yang-fig4-vs-mean": ("hi", "lo", "robustness", "status"),
    "yang-fig4-whole-vs-mean": ("robustness",),
    "yang-fig4-fluctuation-mean": ("a", "b"),
    "yang-fig4-vs-support": ("hi", "lo"),
    "yang-fig4-whole-vs-support": ("a", "b", "diff", "hi", "lo", "margin"),
    "yang-fig4-fluctuation-support": ("b",),
    "yang-fig4-unaffected": ("a", "b", "hi", "lo", "margin", "robustness", "status"),
    "yang-weights-reasonable": ("robustness", "status", "runs"),
    "yang-weights-stability": ("a", "b", "robustness", "status"),
})


def _chapter_ledger(ledger: object) -> Ledger:
    """``ledger`` when it is the chapter's (a Ledger of :data:`SOURCE`): another chapter's would glue its records
    under this chapter's keys (fuzz 19); a TypeError/ValueError naming ``ledger`` and its source key otherwise."""
    instance_of(ledger, Ledger, "ledger")
    if ledger.source != SOURCE:  # type: ignore[attr-defined]
        raise ValueError(f"ledger must be this chapter's (source {shown(SOURCE)}), got the ledger of "
                         f"{shown(ledger.source)}")  # type: ignore[attr-defined]
    return ledger  # type: ignore[return-value]


def ledger_numbers(ledger: Ledger, prefix: str = "ofs_",
                   fields: Mapping[str, Sequence[str]] | None = None) -> GlueValues:
    """Glue-ready statuses, robustness lines and paired-comparison numbers of every record of a ledger.

    Parameters
    ----------
    ledger : Ledger
    prefix : str
        Glue-key prefix of the chapter.
    fields : mapping of record id to field names, optional
        Keep only these fields (``"status"``, ``"robustness"`` and those of :func:`comparison_numbers`) of these
        records; default every field of every record.

    Returns
    -------
    GlueValues
        For every record ``<prefix><id>_status`` and ``<prefix><id>_robustness``; for each record whose
        primary evidence is a :class:`~fusion.book.ledger.Comparison` (or, when the baseline is undefined, whose
        stand-in reading is), :func:`comparison_numbers` under ``<prefix><id>``. Dashes of the id become
        underscores. An empty ledger gives an empty mapping (and refuses ``fields`` naming any record).

    Raises
    ------
    TypeError
        ``ledger`` not a :class:`~fusion.book.ledger.Ledger`, ``prefix`` not a string, ``fields`` not a mapping of
        sequences of strings.
    ValueError
        ``ledger`` of another source than the chapter's (``ledger.source`` not :data:`SOURCE`), ``prefix`` not a glue
        key prefix (ASCII letters, digits and underscores), or ``fields`` naming a record not in the ledger or a number
        the ledger does not give.
    """
    _chapter_ledger(ledger)
    prefix = _glue_prefix(text(prefix, "prefix"), "prefix")  # its plain text (rule 19), keeping keys identifiers
    if fields is not None:
        instance_of(fields, Mapping, "fields")
        fields = {rid: [text(f, f"fields[{shown(rid)}][{i}]")
                        for i, f in enumerate(sequence(fs, f"fields[{shown(rid)}]"))] for rid, fs in fields.items()}
    out: GlueValues = {}
    for c in ledger.claims:
        key = prefix + c.id.replace("-", "_")
        out[key + "_status"] = c.status
        out[key + "_robustness"] = c.robustness
        ev = c.evidence
        if isinstance(ev, Unverifiable):
            ev = next((a.evidence for a in c.alternatives if a.kind == "stand-in"), ev)
        if isinstance(ev, Comparison):
            out.update(comparison_numbers(ev, key))
    if fields is None:
        return out
    unknown = set(fields) - {c.id for c in ledger.claims}
    if unknown:
        raise ValueError(f"fields names records not in the ledger: {sorted(unknown)}")
    want = [prefix + rid.replace("-", "_") + "_" + f for rid, fs in fields.items() for f in fs]
    missing = [k for k in want if k not in out]
    if missing:
        raise ValueError(f"fields names numbers the ledger does not give: {missing}")
    return {k: out[k] for k in want}


def comparison_numbers(comparison: Comparison, key: str,
                       fields: Sequence[str] | None = None) -> GlueValues:
    """Glue-ready numbers of one paired comparison.

    Parameters
    ----------
    comparison : Comparison
    key : str
        Glue-key stem; the keys are ``<key>_{a,b,diff,lo,hi,margin,rel}`` (means of A and B, the deciding
        statistic of the difference and its 95 % interval, the practical margin, all °C and rounded to 4
        decimals; A's mean relative to B's, minus one) and ``<key>_runs``.
    fields : sequence of str, optional
        Keep only these suffixes (default all), each one of ``a, b, diff, lo, hi, margin, rel, runs``.

    Returns
    -------
    GlueValues
        ``<key>_<suffix>`` → the comparison's rounded number (the suffixes kept by ``fields``).

    Raises
    ------
    TypeError
        ``comparison`` not a :class:`~fusion.book.ledger.Comparison` (a proposition or an exact comparison has no
        paired runs), ``key`` not a string, ``fields`` not a sequence of strings.
    ValueError
        ``key`` not a glue key prefix (``<key>_a`` not an identifier of ASCII letters, digits and underscores), a field not
        among the suffixes above, or a kept number not finite (a run with an infinite error makes a
        mean infinite: it cannot be printed), naming ``comparison``.
    """
    instance_of(comparison, Comparison, "comparison")
    key = _glue_prefix(text(key, "key"), "key")  # the rule of every glue-key prefix (fuzz 32b D1: "k\n" was glued)
    want = list(_COMPARISON_FIELDS) if fields is None else [text(f, f"fields[{i}]")
                                                           for i, f in enumerate(sequence(fields, "fields"))]
    unknown = [f for f in want if f not in _COMPARISON_FIELDS]
    if unknown:
        raise ValueError(f"fields must be among {list(_COMPARISON_FIELDS)}, got {unknown}")
    mean, lo, hi = comparison.interval()
    a, b = float(np.mean(comparison.a)), float(np.mean(comparison.b))
    with np.errstate(divide="ignore", invalid="ignore"):
        rel = float(np.float64(a) / np.float64(b) - 1)
    vals = {"a": a, "b": b, "diff": mean, "lo": lo, "hi": hi, "margin": comparison.margin, "rel": rel}
    out: GlueValues = {}
    for f in want:
        if f == "runs":
            out[f"{key}_runs"] = comparison.runs
            continue
        if not math.isfinite(vals[f]):
            raise ValueError(f"comparison's {f} is {vals[f]} (a run with an infinite or undefined value): it cannot "
                             f"be glued as {key}_{f}")
        out[f"{key}_{f}"] = rounded(vals[f], 4)
    return out


#: The suffixes of :func:`comparison_numbers`, in its key order.
_COMPARISON_FIELDS = ("a", "b", "diff", "lo", "hi", "margin", "rel", "runs")


#: Whose claim a record is (R8), in the words of the chapter's verdict table.
CLAIMANT_WORDS: dict[str, str] = {"source": "the source (printed)",
                                  "implied": "the book's reading of the source's purpose",
                                  "book": "the book's own question"}


def verdict_table(ledger: Ledger) -> pd.DataFrame:
    """The chapter's verdict table: :meth:`~fusion.book.ledger.Ledger.table` with a column saying whose claim each record is (R8).

    Only the records marked "the source (printed)" are the source's claims; the book's reading of the source's
    purpose (``implied``) and the book's own questions (``book``) are the book's questions, marked as such from the
    claim file's ``claimant``.

    Parameters
    ----------
    ledger : Ledger

    Returns
    -------
    DataFrame
        One row per record, indexed by its id; an empty ledger gives a table with the columns and no row.

    Raises
    ------
    TypeError
        ``ledger`` not a :class:`~fusion.book.ledger.Ledger`.
    ValueError
        ``ledger`` of another source than the chapter's (``ledger.source`` not :data:`SOURCE`).
    """
    _chapter_ledger(ledger)
    columns = ["whose claim", "where", "status", "robustness"]
    if not ledger.claims:
        return pd.DataFrame(columns=columns, index=pd.Index([], name="id"), dtype=object)
    t = ledger.table()
    who = {c.id: CLAIMANT_WORDS[c.claimant] for c in ledger.claims}
    return t.assign(**{"whose claim": [who[i] for i in t.index]})[columns]
