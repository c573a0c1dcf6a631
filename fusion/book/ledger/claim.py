"""One record of the ledger: a :class:`Claim`, its evidence and its :class:`Alternative` readings."""

from __future__ import annotations

import re
from dataclasses import dataclass

import numpy as np

from fusion._validation import sequence
from fusion._validation import shown
from fusion.book import rulebook as R
from fusion.book._json import JSONObject
from fusion.book.exact import ExactComparison
from fusion.book.ledger.evidence import _KIND_OF_TEST, Comparison, EVIDENCE_TYPES, Evidence, Unverifiable
from fusion.book.ledger.evidence import _runs, _test_of
from fusion.book.ledger.sources import SOURCES
from fusion.book.ledger.statuses import _texts, text_fields

__all__ = [
    "Alternative",
    "Claim",
]

#: What a record's ``id`` may be: lower-case words joined by ``-`` (one rule for a :class:`Claim` and a claim
#: file's record, ``fusion.book.claims``; matched whole, fuzz 24a D1).
_ID = r"[a-z0-9]+(?:-[a-z0-9]+)+"


@dataclass(frozen=True)
class Alternative:
    """The same claim under another reading.

    Attributes
    ----------
    choice : str
        The open choice (e.g. "variance guard").
    reading : str
        This alternative reading (e.g. ``"|σ̂²|"``).
    evidence : PublishedValues, Comparison, Proposition, Conjunction or Unverifiable
        The evidence under this reading.
    kind : str
        One of :data:`fusion.book.rulebook.READING_KINDS` other than ``"primary"`` (default
        ``"open-choice"``): only open-choice readings with enough runs count towards the record's
        robustness (rules R4, R5).

    Raises
    ------
    TypeError
        ``choice``, ``reading`` or ``kind`` not a str; ``evidence`` not an evidence class.
    ValueError
        An empty ``choice`` or ``reading``; ``kind`` not a reading kind other than ``"primary"``.
    """

    choice: str     # the open choice (e.g. "variance guard")
    reading: str    # this alternative (e.g. "|σ̂²|")
    evidence: Evidence
    kind: str = "open-choice"

    def __post_init__(self) -> None:
        text_fields(self, "choice", "reading", "kind")  # plain str copies (rule 19)
        for name in ("choice", "reading"):
            if not getattr(self, name).strip():
                raise ValueError(f"{name} must not be empty")
        if not isinstance(self.evidence, EVIDENCE_TYPES):
            raise TypeError("evidence must be PublishedValues, Comparison, ExactComparison, Proposition, Conjunction "
                            f"or Unverifiable, got {type(self.evidence).__name__}")
        if self.kind not in R.READING_KINDS or self.kind == "primary":
            raise ValueError(f"kind must be one of {R.READING_KINDS[1:]}, got {shown(self.kind)}")

    @property
    def runs(self) -> int | None:
        """Monte-Carlo runs of this reading (None when it is not stochastic)."""
        return _runs(self.evidence)

    def counted(self, primary_runs: int | None) -> tuple[bool, str]:
        """Whether this reading counts towards robustness (R4, R5), and why not."""
        return R.counted(self.kind, self.runs, primary_runs, self.evidence.status())

    def to_dict(self, primary_runs: int | None = None) -> JSONObject:
        ok, why = self.counted(primary_runs)
        return {"choice": self.choice, "reading": self.reading, "kind": self.kind, "status": self.evidence.status(),
                "ours": self.evidence.summary(), "runs": self.runs, "counted": ok, "not_counted_because": why,
                "evidence": self.evidence.to_dict()}


@dataclass(frozen=True)
class Claim:
    """One checkable claim of one source, with its evidence; the status is derived by the rulebook.

    Parameters
    ----------
    id : str
        Unique, ``<source-prefix>-<slug>``: lower-case words (letters and digits) joined by ``-``, as in a claim
        file (the ledger file and the book's links name the record by it).
    source : str
        BibTeX key, one of :data:`SOURCES`.
    where : str
        Table, figure, equation or section of the source.
    claim : str
        The claim in one English sentence.
    published : str
        The published value(s) with unit, or "qualitative".
    evidence : Evidence
        The computation under the book's primary reading.
    link : str
        Label of the section or critique box in the chapter that holds the evidence.
    bound : str
        Exact value or bound where one exists, with the model it applies to.
    assumptions : tuple of str
        Choices the source leaves open that the primary reading fixes.
    alternatives : tuple of Alternative
        The claim under other readings.
    headline : bool
        The single most important finding of the source (only a claim the source prints: R8); a NumPy bool is
        stored as a bool.
    critiques : tuple of str
        Labels of the critique boxes this record summarises.
    claimant : {"source", "implied", "book"}
        Whose claim it is: printed in the source; the book's reading of the source's purpose; the book's
        own question (R8).
    test : str
        One of :data:`fusion.book.rulebook.TESTS`; default: from the evidence's kind.

    Raises
    ------
    TypeError
        A text field not a str; ``evidence`` not an evidence class; ``assumptions`` or ``critiques`` not a
        sequence of str; ``alternatives`` not of :class:`Alternative`; ``headline`` not a bool.
    ValueError
        Unknown ``source``, ``claimant`` or ``test``; an ``id`` not of lower-case words joined by ``-`` (``"Yang X"``,
        ``"yang-x\\n"``); an empty ``where``, ``claim`` or ``link``; an empty
        or repeated critique label or assumption; a headline whose claimant is not the source (R8); ``test`` and ``evidence``
        that disagree (``"published"`` with a :class:`Comparison`: the table the claim files use;
        :class:`Unverifiable` evidence fits every test, R7); ``alternatives`` repeating a reading (the same
        choice and reading, which R5 would count twice).
    """

    id: str
    source: str
    where: str
    claim: str
    published: str
    evidence: Evidence
    link: str
    bound: str = ""
    assumptions: tuple[str, ...] = ()
    alternatives: tuple[Alternative, ...] = ()
    headline: bool = False
    critiques: tuple[str, ...] = ()
    claimant: str = "source"
    test: str = ""

    def __post_init__(self) -> None:
        text_fields(self, "id", "source", "where", "claim", "published", "link", "bound", "claimant", "test")
        if not isinstance(self.evidence, EVIDENCE_TYPES):
            raise TypeError("evidence must be PublishedValues, Comparison, ExactComparison, Proposition, Conjunction "
                            f"or Unverifiable, got {type(self.evidence).__name__}")
        for name, what in (("assumptions", "an assumption"), ("critiques", "a label")):
            items = _texts(getattr(self, name), name)
            object.__setattr__(self, name, items)  # plain str copies (rule 19)
            blank = [i for i, v in enumerate(items) if not v.strip()]  # a claim file's schema: minLength 1
            if blank:
                raise ValueError(f"{name}[{blank[0]}] must not be empty")
            if len(set(items)) != len(tuple(items)):  # stated twice, or one box listed twice (fuzz 22a D9)
                raise ValueError(f"{name} must not repeat {what}, got {shown(items)}")
        if isinstance(self.alternatives, str) or not all(isinstance(a, Alternative)
                                                         for a in sequence(self.alternatives, "alternatives")):
            raise TypeError(f"alternatives must be a tuple of Alternative, got {shown(self.alternatives)}")
        if not isinstance(self.headline, (bool, np.bool_)):
            raise TypeError(f"headline must be a bool, got {type(self.headline).__name__}")
        object.__setattr__(self, "headline", bool(self.headline))  # numpy's bool stored as a bool (json writes it)
        if self.source not in SOURCES:
            raise ValueError(f"source must be one of {sorted(SOURCES)}, got {shown(self.source)}")
        if not re.fullmatch(_ID, self.id):
            raise ValueError(f"id must be lower-case words joined by '-' (the pattern {_ID} of a claim file), "
                             f"got {shown(self.id)}")
        for name in ("where", "claim", "link"):
            if not getattr(self, name).strip():
                raise ValueError(f"{name} must not be empty")
        if self.claimant not in R.CLAIMANTS:
            raise ValueError(f"claimant must be one of {R.CLAIMANTS}, got {shown(self.claimant)}")
        if self.headline and self.claimant != "source":
            raise ValueError(f"{self.id}: only a claim the source prints can be its main finding (rule R8), "
                             f"this one's claimant is {shown(self.claimant)}")
        if not self.test:
            object.__setattr__(self, "test", _test_of(self.evidence))
        if self.test not in R.TESTS:
            raise ValueError(f"test must be one of {R.TESTS}, got {shown(self.test)}")
        if not isinstance(self.evidence, _KIND_OF_TEST[self.test] + (Unverifiable,)):  # R7: any test can be unverifiable
            raise ValueError(f"test {shown(self.test)} cannot take {type(self.evidence).__name__} evidence (evidence "
                             f"and test must agree, as in the claim files)")
        readings = [(a.choice, a.reading) for a in self.alternatives]
        if len(set(readings)) != len(readings):
            raise ValueError("alternatives must not repeat a reading (the same choice and reading twice would be "
                             f"counted twice, R5), got {shown(readings)}")
        object.__setattr__(self, "assumptions", tuple(self.assumptions))
        object.__setattr__(self, "alternatives", tuple(self.alternatives))
        object.__setattr__(self, "critiques", tuple(self.critiques))

    @property
    def runs(self) -> int | None:
        """Monte-Carlo runs of the primary reading (None when it is not stochastic)."""
        return _runs(self.evidence)

    def _decided(self) -> tuple[str, int, int]:
        return R.record_status(self.evidence.status(),
                               [(a.kind, a.evidence.status(), a.runs) for a in self.alternatives],
                               self.runs, bool(self.assumptions))

    @property
    def status(self) -> str:
        """The status by the rulebook (R5 on top of the primary reading's status)."""
        return self._decided()[0]

    @property
    def robustness(self) -> str:
        """"the claim holds under k of n other readings of the source's open choices", and what is shown apart; "" without readings.

        The status is always the primary reading's; the count is of the counted readings (R4, R5) under which
        the claim is reproduced, so that a status never reads as contradicting its own count.
        """
        if not self.alternatives:
            return ""
        _, agree, total = self._decided()
        parts = [f"the claim holds under {agree} of {total} other readings of the source's open choices"] if total else []
        apart: dict[str, int] = {}
        for a in self.alternatives:
            ok, why = a.counted(self.runs)
            if not ok:
                apart[why] = apart.get(why, 0) + 1
        if apart:
            parts.append("shown apart: " + ", ".join(f"{n} {w}" for w, n in apart.items()))
        return "; ".join(parts)

    def to_dict(self) -> JSONObject:
        src = SOURCES[self.source]
        ev = self.evidence
        margin = ev.margin if isinstance(ev, Comparison) else None
        if isinstance(ev, ExactComparison):
            margin = float(f"{ev.margin:.4g}")
        if isinstance(ev, Comparison) and margin:
            # as the summary prints it (three significant digits): the resolution of a comparison with an
            # infinite side comes from the finite runs of that side and would round the margin coarsely
            margin = float(f"{margin:.3g}")
        return {
            "id": self.id, "source": self.source, "source_short": src.short, "chapter": src.chapter,
            "where": self.where, "claim": self.claim, "claimant": self.claimant, "test": self.test,
            "published": self.published, "ours": ev.summary(), "ours_brief": ev.brief(), "bound": self.bound,
            "status": self.status,
            "primary_status": ev.status(), "robustness": self.robustness, "runs": self.runs,
            "margin": None if margin is None else margin if margin else 0.0,
            "rule": ev.judgement().rule if isinstance(ev, Comparison) else "R9" if isinstance(ev, ExactComparison)
            else None,
            "assumptions": list(self.assumptions),
            "alternatives": [a.to_dict(self.runs) for a in self.alternatives],
            "evidence": ev.to_dict(), "link": self.link, "headline": self.headline,
            "critiques": list(self.critiques),
        }
