r"""The claims ledger: one record per checkable claim of a source, with a status derived by rule.

Every verdict of the book is a :class:`Claim` whose status is *computed* from its evidence,
never typed. A chapter builds its claims when it executes and writes them with
:meth:`Ledger.write` to ``book/ledger/<source>.json``; the Verdicts page, each chapter's
"In brief" box, the introduction's findings and the downloadable ``verdicts.csv`` /
``verdicts.json`` are rendered from those files by the book's Sphinx extension.

Status vocabulary (closed, :data:`STATUSES`)
--------------------------------------------
reproduced
    A published number equals ours at its printed precision; a comparative claim's paired 95 %
    confidence interval excludes zero in the claimed direction; a mathematical claim holds.
reproduced under stated assumptions
    As *reproduced*, but only under a choice the source leaves open (the record states the
    assumption), or not under every alternative reading that was run.
not reproduced
    A published number that our computation does not give at its printed precision.
contradicted
    A comparative claim whose interval excludes zero in the opposite direction, or a
    mathematical claim shown false.
not distinguishable
    A comparative claim whose interval contains zero, or lies wholly inside the practical margin
    the record states (a difference too small to matter, whatever its sign).
cannot be checked
    The source gives too little to compute anything (the record says why).

Rules
-----
* :class:`PublishedValues` — reproduced iff every published value equals ours rounded to the
  published number of decimals.
* :class:`Comparison` — per-run metric of method A and of method B on the *same* runs; the 95 %
  interval of the mean paired difference A - B is Student's t interval of
  :func:`scipy.stats.ttest_rel`; the claim is "A is lower than B" (``claim="less"``) or "higher"
  (``claim="greater"``). With a practical ``margin`` m > 0 (tied by the record to the claimed effect),
  an interval inside (-m, m) is *not distinguishable* (an equivalence region, as in two one-sided
  tests); an interval that reaches beyond it keeps the rule above.
* :class:`Proposition` — a computed yes/no (reproduced or contradicted).
* :class:`Conjunction` — a claim about every member of a group ("every sensor"): one comparison
  or proposition per member; contradicted if any member's is, reproduced if every member's is,
  otherwise not distinguishable.
* :class:`Unverifiable` — cannot be checked.
* A :class:`Claim` takes its primary evidence's status; *reproduced* becomes *reproduced under
  stated assumptions* when the claim lists assumptions or when any :class:`Alternative` reading
  does not also give *reproduced*. The statuses under every alternative are kept.

References
----------
* Student (1908). The probable error of a mean. *Biometrika*, 6(1), 1-25.
* Rougier, N. P. et al. (2017). Sustainable computational science: the ReScience
  initiative. *PeerJ Computer Science*, 3, e142.
"""

from __future__ import annotations

import hashlib
import json
import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Literal

import numpy as np
import pandas as pd
from numpy.typing import ArrayLike
from scipy import stats

from fusion._validation import _numeric, count


def _text(value: Any, name: str) -> str:
    """Check that a text field is a ``str`` (TypeError naming it otherwise)."""
    if not isinstance(value, str):
        raise TypeError(f"{name} must be a str, got {type(value).__name__}")
    return value


def _texts(value: Any, name: str) -> None:
    """Check a tuple of strings (a bare string is refused: it would be split into characters)."""
    if isinstance(value, str) or not all(isinstance(v, str) for v in value):
        raise TypeError(f"{name} must be a tuple of str, got {value!r}")

__all__ = [
    "STATUSES",
    "STATUS_DEFINITIONS",
    "MIN_RUNS",
    "CONFIDENCE_LEVEL",
    "DOMINANCE_SHARE",
    "Source",
    "SOURCES",
    "PublishedValues",
    "Comparison",
    "Proposition",
    "Conjunction",
    "Unverifiable",
    "Alternative",
    "Claim",
    "Ledger",
    "fmt",
    "ledger_dir",
]

#: The closed status vocabulary, in display order.
STATUSES: tuple[str, ...] = (
    "reproduced",
    "reproduced under stated assumptions",
    "not reproduced",
    "contradicted",
    "not distinguishable",
    "cannot be checked",
)

#: Minimum number of Monte-Carlo runs for a stochastic record (fewer needs a stated reason).
MIN_RUNS = 100

#: Confidence level of every paired interval.
CONFIDENCE_LEVEL = 0.95

#: A comparison warns when this share of its runs (at least one run) carries half of the total absolute difference.
DOMINANCE_SHARE = 0.01

#: One-sentence definition of each status (shown on the Verdicts page).
STATUS_DEFINITIONS: dict[str, str] = {
    "reproduced": "the published number equals ours at its printed precision; or the claimed "
                  f"difference's paired {CONFIDENCE_LEVEL * 100:.0f} % confidence interval (Student's t, "
                  f"scipy.stats.ttest_rel, the same runs for both methods, at least {MIN_RUNS} runs) "
                  "excludes zero in the claimed direction; or the mathematical claim holds",
    "reproduced under stated assumptions": "as reproduced, but only under a choice the source "
                                           "leaves open (the record names it), or not under every "
                                           "alternative reading that was run (the record lists "
                                           "each reading's status)",
    "not reproduced": "our computation does not give the published number at its printed precision",
    "contradicted": f"the paired {CONFIDENCE_LEVEL * 100:.0f} % interval excludes zero in the opposite "
                    "direction, or the mathematical claim is false",
    "not distinguishable": f"the paired {CONFIDENCE_LEVEL * 100:.0f} % interval of the difference contains zero, "
                           "or lies wholly inside the practical margin the record states (too small to matter)",
    "cannot be checked": "the source gives too little to compute anything; the record says why",
}



def fmt(x: float, digits: int = 4) -> str:
    """Format a number for the ledger: ``digits`` significant digits, no ``e+00``, ``-0`` → ``0``.

    Parameters
    ----------
    x : float
        The number (integers are printed exactly).
    digits : int
        Significant digits of a float.

    Returns
    -------
    str
        E.g. ``"0.1235"``, ``"1.5×10^-7"``, ``"n/a"`` for NaN, ``"∞"`` for infinity.
    """
    count(digits, "digits")
    if isinstance(x, (int, np.integer)) and not isinstance(x, bool):
        return str(int(x))
    if isinstance(x, (str, bytes)):
        raise TypeError(f"x must be a number, got {x!r}")
    x = float(x)
    if not math.isfinite(x):
        return "n/a" if math.isnan(x) else ("∞" if x > 0 else "-∞")
    if x == 0:
        return "0"
    s = f"{x:.{digits}g}"
    if "e" in s:
        mant, exp = s.split("e")
        s = f"{mant}×10^{int(exp)}"
    return s


@dataclass(frozen=True)
class Source:
    """One of the five source documents.

    Attributes
    ----------
    key : str
        BibTeX key.
    short : str
        Author-year citation, as readers see it.
    title : str
        English title of the chapter's subject.
    chapter : str
        Docname of the chapter (without suffix).
    order : int
        Position in the book.
    chapters : tuple of str, optional
        Docnames of every chapter on the source, in reading order, when it spans several; the
        first must be ``chapter`` (which holds the source's headline). Default: ``(chapter,)``.
    """

    key: str        # BibTeX key
    short: str      # author-year, as readers see it
    title: str      # English title
    chapter: str    # docname of the (first) chapter (without suffix)
    order: int      # position in the book
    chapters: tuple[str, ...] = ()  # every chapter on the source, in reading order

    def __post_init__(self) -> None:
        for name in ("key", "short", "title", "chapter"):
            _text(getattr(self, name), name)
        count(self.order, "order")
        if not isinstance(self.chapters, tuple):
            raise TypeError(f"chapters must be a tuple of str, got {type(self.chapters).__name__}")
        if not self.chapters:
            object.__setattr__(self, "chapters", (self.chapter,))
        for c in self.chapters:
            _text(c, "chapters")
        if self.chapters[0] != self.chapter or len(set(self.chapters)) != len(self.chapters):
            raise ValueError(f"chapters must start with chapter {self.chapter!r} and not repeat, got {self.chapters!r}")

    def ledger_file(self, chapter: str | None = None) -> str:
        """Name of the ledger file of one of the source's chapters (default: the first).

        ``<key>.json`` for a source with one chapter, ``<key>-<NN>.json`` (``NN`` the chapter's
        number, the prefix of its file name) for a source that spans several.

        Parameters
        ----------
        chapter : str, optional
            Docname, one of :attr:`chapters`.

        Returns
        -------
        str
            The file name in ``book/ledger``.

        Raises
        ------
        ValueError
            ``chapter`` is not one of the source's chapters.
        """
        chapter = self.chapter if chapter is None else chapter
        if chapter not in self.chapters:
            raise ValueError(f"chapter must be one of {list(self.chapters)}, got {chapter!r}")
        if len(self.chapters) == 1:
            return f"{self.key}.json"
        return f"{self.key}-{chapter.rsplit('/', 1)[-1].split('_', 1)[0]}.json"


#: The five sources in book order.
SOURCES: dict[str, Source] = {s.key: s for s in (
    Source("yang2012optimal", "Yang, Feng & Fan (2012)", "Optimal fusion set",
           "notebooks/01_optimal_fusion_set", 1),
    Source("lecture003", "Lecture notes (sections 2.1-2.7)", "Classic fusion algorithms",
           "notebooks/02_lecture_weighting", 2,
           ("notebooks/02_lecture_weighting", "notebooks/03_lecture_wavelets",
            "notebooks/04_lecture_biased_correlated")),
    Source("wang2024covariance", "Wang & Tang (2024)", "Covariance intersection",
           "notebooks/05_covariance_intersection", 5),
    Source("cn107330468b", "Chernoff-fusion patent CN107330468B (2021)", "Distributed Chernoff fusion",
           "notebooks/06_chernoff_fusion", 6),
    Source("shi2023time", "Shi, Suo & Ma (2023)", "Time registration",
           "notebooks/07_time_registration", 7),
)}


# --------------------------------------------------------------------------- evidence
@dataclass(frozen=True)
class PublishedValues:
    """Published numbers beside ours; reproduced iff equal at the printed precision.

    Parameters
    ----------
    published, ours : sequence of float, same length
        ``ours`` may hold NaN where no value can be computed (counts as a mismatch).
    decimals : int or sequence of int
        Printed number of decimals of each published value.
    unit : str
    """

    published: tuple[float, ...]
    ours: tuple[float, ...]
    decimals: tuple[int, ...]
    unit: str = ""
    kind: str = field(default="published", init=False)

    def __init__(self, published: ArrayLike, ours: ArrayLike, decimals: int | Sequence[int], unit: str = "") -> None:
        pub = np.atleast_1d(_numeric(published, "published"))
        our = np.atleast_1d(_numeric(ours, "ours"))
        if pub.ndim != 1 or pub.size == 0 or not np.all(np.isfinite(pub)):
            raise ValueError("published must be a non-empty 1-D array of finite numbers")
        if our.shape != pub.shape:
            raise ValueError(f"ours has shape {our.shape}, published {pub.shape}")
        if np.any(np.isinf(our)):
            raise ValueError("ours must not be infinite (NaN marks a value that cannot be computed)")
        dec_f = _numeric(decimals, "decimals")
        if not np.all(np.isfinite(dec_f)) or np.any(dec_f != np.round(dec_f)):
            raise ValueError(f"decimals must be integers, got {decimals!r}")
        _text(unit, "unit")
        dec = np.broadcast_to(dec_f.astype(int), pub.shape)
        if np.any(dec < 0):
            raise ValueError("decimals must be non-negative")
        object.__setattr__(self, "published", tuple(float(v) for v in pub))
        object.__setattr__(self, "ours", tuple(float(v) for v in our))
        object.__setattr__(self, "decimals", tuple(int(d) for d in dec))
        object.__setattr__(self, "unit", unit)
        object.__setattr__(self, "kind", "published")

    @property
    def matches(self) -> tuple[bool, ...]:
        """Whether each of our values, rounded to the printed decimals, equals the published one."""
        return tuple(bool(math.isfinite(o) and round(o, d) == round(p, d))
                     for p, o, d in zip(self.published, self.ours, self.decimals))

    def status(self) -> str:
        return "reproduced" if all(self.matches) else "not reproduced"

    def summary(self) -> str:
        n, k = len(self.published), sum(self.matches)
        u = f" {self.unit}" if self.unit else ""
        if n == 1:
            o = self.ours[0]
            return f"{o:.{self.decimals[0]}f}{u}" if math.isfinite(o) else "no value"
        return f"{k} of {n} equal at the printed precision"

    def to_dict(self) -> dict[str, Any]:
        return {"kind": self.kind, "published": list(self.published), "ours": list(self.ours),
                "decimals": list(self.decimals), "unit": self.unit, "matches": list(self.matches)}


@dataclass(frozen=True)
class Comparison:
    """A paired Monte-Carlo comparison: is method A's metric lower (or higher) than B's?

    Parameters
    ----------
    a, b : array_like, shape (runs,)
        Per-run metric of A and of B on the same runs (same seeds, same samples).
    a_name, b_name : str
    claim : {"less", "greater"}
        What the source claims of A against B.
    metric : str
        What is compared, with its unit (e.g. "mean absolute error (°C)").
    seed : int or None
        Seed of the runs.
    reason : str
        Why fewer than :data:`MIN_RUNS` runs are enough, when they are.
    margin : float
        Practical margin (units of the metric, >= 0): a difference whose whole 95 % interval lies inside
        (-margin, margin) is too small to matter and the status is "not distinguishable" whatever its sign.
        0 (the default) keeps the sign rule alone. The record says what the margin is tied to (e.g. 10 % of
        the published difference).
    """

    a: tuple[float, ...]
    b: tuple[float, ...]
    a_name: str
    b_name: str
    claim: Literal["less", "greater"]
    metric: str
    seed: int | None = None
    reason: str = ""
    margin: float = 0.0
    kind: str = field(default="comparison", init=False)

    def __init__(self, a: ArrayLike, b: ArrayLike, a_name: str, b_name: str,
                 claim: Literal["less", "greater"], metric: str, seed: int | None = None, reason: str = "",
                 margin: float = 0.0) -> None:
        av = _numeric(a, "a").ravel()
        bv = _numeric(b, "b").ravel()
        for name, v in (("a_name", a_name), ("b_name", b_name), ("metric", metric), ("reason", reason)):
            _text(v, name)
        if seed is not None:
            count(seed, "seed", minimum=0)
        if av.shape != bv.shape or av.size < 2:
            raise ValueError(f"a and b must hold the same number (>= 2) of paired runs, got {av.size} and {bv.size}")
        if not (np.all(np.isfinite(av)) and np.all(np.isfinite(bv))):
            raise ValueError("a and b must be finite")
        if claim not in ("less", "greater"):
            raise ValueError(f"claim must be 'less' or 'greater', got {claim!r}")
        if av.size < MIN_RUNS and not reason:
            raise ValueError(f"{av.size} runs < {MIN_RUNS}: give more runs or a reason")
        if isinstance(margin, bool) or not isinstance(margin, (int, float, np.floating, np.integer)) \
                or not math.isfinite(float(margin)) or float(margin) < 0:
            raise ValueError(f"margin must be a finite number >= 0, got {margin!r}")
        for k, v in (("a", tuple(float(x) for x in av)), ("b", tuple(float(x) for x in bv)), ("a_name", a_name),
                     ("b_name", b_name), ("claim", claim), ("metric", metric), ("seed", seed), ("reason", reason),
                     ("margin", float(margin)), ("kind", "comparison")):
            object.__setattr__(self, k, v)

    @property
    def runs(self) -> int:
        return len(self.a)

    def interval(self) -> tuple[float, float, float]:
        """Mean paired difference A - B and its 95 % t interval (``scipy.stats.ttest_rel``), computed once.

        Two methods that agree to round-off (every ``|A - B|`` at most 10⁻¹⁰ of the largest ``|A|`` or ``|B|``) tie:
        the difference and its interval are exactly 0, so a round-off sign never decides a status.
        """
        cached = self.__dict__.get("_interval")
        if cached is None:
            cached = self._compute_interval()
            object.__setattr__(self, "_interval", cached)
        return cached

    def _compute_interval(self) -> tuple[float, float, float]:
        d = np.subtract(self.a, self.b)
        mean = float(np.mean(d))
        scale = max(float(np.max(np.abs(self.a))), float(np.max(np.abs(self.b))))
        if np.max(np.abs(d)) <= 1e-10 * scale:  # A and B identical up to round-off in every run: a tie, not a sign
            return 0.0, 0.0, 0.0
        if np.ptp(d) <= 1e-12 * max(1.0, abs(mean)):  # no spread beyond round-off: the interval is the point
            return mean, mean, mean
        ci = stats.ttest_rel(self.a, self.b).confidence_interval(CONFIDENCE_LEVEL)
        return mean, float(ci.low), float(ci.high)

    def within_margin(self) -> bool:
        """``True`` if a practical margin is set and the whole 95 % interval lies inside (-margin, margin)."""
        _, lo, hi = self.interval()
        return self.margin > 0 and -self.margin < lo and hi < self.margin

    def status(self) -> str:
        _, lo, hi = self.interval()
        if self.within_margin():
            return "not distinguishable"
        better, worse = (hi < 0, lo > 0) if self.claim == "less" else (lo > 0, hi < 0)
        if better:
            return "reproduced"
        if worse:
            return "contradicted"
        return "not distinguishable"

    def resolution(self) -> float:
        r"""The step every number of this comparison is rounded to when stored or shown.

        Four significant digits of the larger mean, :math:`10^{\lfloor\log_{10}\max(|\bar a|,|\bar b|)\rfloor-3}`
        (of the largest absolute value when both means are zero), applied to the means *and* to the
        difference and its interval. A difference of two nearly equal means has far fewer significant
        digits than the means themselves: rounding it to its own significant digits would store the
        round-off of the runs (which differs between BLAS kernels) instead of the comparison.

        Returns
        -------
        float
            A power of ten; 1.0 when every value is zero.
        """
        scale = max(abs(float(np.mean(self.a))), abs(float(np.mean(self.b))))
        if scale == 0.0:
            scale = float(max(np.max(np.abs(self.a)), np.max(np.abs(self.b))))
        return 10.0 ** (math.floor(math.log10(scale)) - 3) if scale > 0 else 1.0

    def _rounded(self, x: float) -> float:
        """``x`` rounded to :meth:`resolution`; a non-zero ``x`` that would round to 0 keeps its sign.

        Such an ``x`` (an interval end closer to zero than the resolution) is given two significant
        digits instead, so that the status re-derived from the stored interval is the status.
        """
        r = self.resolution()
        decimals = -int(round(math.log10(r)))
        v = round(x, decimals) if decimals >= 0 else round(x / r) * r
        if v == 0.0 and x != 0.0:
            return float(f"{x:.2g}")
        return v + 0.0

    def _text(self, x: float) -> str:
        """``x`` written at :meth:`resolution`: fixed decimals down to 10⁻⁴, else ``a×10^n`` with the digits it has."""
        r = self.resolution()
        decimals = -int(round(math.log10(r)))
        v = self._rounded(x)
        if v == 0.0:
            return "0"
        if abs(v) < r:  # an interval end kept at two significant digits (see _rounded)
            return fmt(v, 2)
        if 0 <= decimals <= 4:
            return f"{v:.{decimals}f}"
        return fmt(v, max(1, math.floor(math.log10(abs(v))) + decimals + 1))

    def written(self, x: float) -> str:
        """``x`` (a mean, the difference or an interval end) as this comparison writes it in the ledger.

        For prose that quotes a record: the same digits as the record's summary (see :meth:`resolution`).

        Parameters
        ----------
        x : float
            A value on this comparison's scale.

        Returns
        -------
        str
        """
        return self._text(float(x))

    def summary(self) -> str:
        mean, lo, hi = self.interval()
        ma, mb = float(np.mean(self.a)), float(np.mean(self.b))
        d = np.subtract(self.a, self.b)
        # a run whose |A - B| is below 10^-9 of its own larger |A| or |B| is a tie, not a win; per run, because a
        # tolerance scaled to the means would swallow real differences where a few runs carry a heavy-tailed mean
        tie = 1e-9 * np.maximum(np.abs(self.a), np.abs(self.b))
        wins = int(np.sum(d < -tie)) if self.claim == "less" else int(np.sum(d > tie))
        t = self._text
        return (f"{self.a_name} {t(ma)} vs {self.b_name} {t(mb)} ({self.metric}); "
                f"difference {t(mean)}, 95 % CI [{t(lo)}, {t(hi)}], {self.runs} paired runs; "
                f"median difference {t(float(np.median(d)))}, {self.a_name} {'lower' if self.claim == 'less' else 'higher'} in {wins} of {self.runs} runs"
                + self.dominance_note()
                + (f"; the whole interval lies within the practical margin ±{fmt(self.margin, 3)}: not distinguishable "
                   "in practice" if self.within_margin() else ""))

    def dominance_note(self) -> str:
        r"""A warning when a few runs carry the mean difference (heavy tails make the t interval wide).

        Returns
        -------
        str
            ``"; N runs carry half of the total |difference|"`` when at most 1 % of the runs (at
            least one) carry half of :math:`\sum|d|`, else ``""``.
        """
        d = np.abs(np.subtract(self.a, self.b))
        total = float(d.sum())
        if total == 0.0:
            return ""
        top = np.cumsum(np.sort(d)[::-1])
        k = int(np.searchsorted(top, 0.5 * total)) + 1
        return f"; {k} run{'s' if k > 1 else ''} carr{'y' if k > 1 else 'ies'} half of the total |difference|" if k <= max(1, int(self.runs * DOMINANCE_SHARE)) else ""

    def to_dict(self) -> dict[str, Any]:
        mean, lo, hi = self.interval()
        return {"kind": self.kind, "a_name": self.a_name, "b_name": self.b_name, "claim": self.claim,
                "metric": self.metric, "mean_a": self._rounded(float(np.mean(self.a))),
                "mean_b": self._rounded(float(np.mean(self.b))), "difference": self._rounded(mean),
                "ci_low": self._rounded(lo), "ci_high": self._rounded(hi), "resolution": self.resolution(),
                "runs": self.runs, "seed": self.seed,
                "reason": self.reason} | ({"margin": self.margin} if self.margin > 0 else {})


@dataclass(frozen=True)
class Proposition:
    """A computed yes/no check of a mathematical or exact claim.

    Attributes
    ----------
    holds : bool
        Whether the proposition holds (status "reproduced", else "contradicted").
    ours : str
        What we computed, in words.
    kind : str
        ``"proposition"`` (not an argument).
    """

    holds: bool
    ours: str
    kind: str = field(default="proposition", init=False)

    def __post_init__(self) -> None:
        if not isinstance(self.holds, (bool, np.bool_)):
            raise TypeError(f"holds must be a bool, got {type(self.holds).__name__}")
        _text(self.ours, "ours")
        object.__setattr__(self, "holds", bool(self.holds))

    def status(self) -> str:
        return "reproduced" if self.holds else "contradicted"

    def summary(self) -> str:
        return self.ours

    def to_dict(self) -> dict[str, Any]:
        return {"kind": self.kind, "holds": self.holds, "ours": self.ours}


@dataclass(frozen=True)
class Conjunction:
    """A claim about every member of a group ("every sensor"), one piece of evidence per member.

    The claim holds for the group only if it holds for each member, so the status is derived from
    the members' statuses: *contradicted* if any member's is, *reproduced* if every member's is,
    otherwise (some member not distinguishable, none contradicted) *not distinguishable*.

    Parameters
    ----------
    parts : sequence of (str, Comparison or Proposition)
        Each member's label (e.g. ``"sensor 1"``) and evidence; at least two, labels distinct.

    Attributes
    ----------
    parts : tuple of (str, Comparison or Proposition)
    kind : str
        ``"conjunction"``.
    """

    parts: tuple[tuple[str, Comparison | Proposition], ...]
    kind: str = field(default="conjunction", init=False)

    def __init__(self, parts: Sequence[tuple[str, Comparison | Proposition]]) -> None:
        if isinstance(parts, (str, bytes)) or not hasattr(parts, "__len__"):
            raise TypeError(f"parts must be a sequence of (label, evidence) pairs, got {type(parts).__name__}")
        out = []
        for p in parts:
            if not (isinstance(p, tuple) and len(p) == 2):
                raise TypeError(f"parts must hold (label, evidence) pairs, got {p!r}")
            label, ev = p
            _text(label, "label")
            if not isinstance(ev, (Comparison, Proposition)):
                raise TypeError(f"each part's evidence must be a Comparison or a Proposition, got {type(ev).__name__}")
            out.append((label, ev))
        if len(out) < 2:
            raise ValueError(f"parts must hold at least two members, got {len(out)}")
        if len({lab for lab, _ in out}) != len(out):
            raise ValueError("parts must have distinct labels")
        object.__setattr__(self, "parts", tuple(out))
        object.__setattr__(self, "kind", "conjunction")

    def status(self) -> str:
        st = [ev.status() for _, ev in self.parts]
        if "contradicted" in st:
            return "contradicted"
        if all(s == "reproduced" for s in st):
            return "reproduced"
        return "not distinguishable"

    def summary(self) -> str:
        items = []
        comps = [ev for _, ev in self.parts if isinstance(ev, Comparison)]
        same = len(comps) == len(self.parts) and len({(c.a_name.split(" (")[0], c.b_name.split(" (")[0], c.metric, c.runs)
                                                       for c in comps}) == 1
        for label, ev in self.parts:
            if isinstance(ev, Comparison):
                mean, lo, hi = ev.interval()
                t = ev._text
                items.append(f"{label}: {ev.status()}, {t(float(np.mean(ev.a)))} vs {t(float(np.mean(ev.b)))}, "
                             f"difference {t(mean)} [{t(lo)}, {t(hi)}]" + ev.dominance_note())
            else:
                items.append(f"{label}: {ev.status()}, {ev.summary()}")
        head = ""
        if same:
            c = comps[0]
            head = (f"{c.a_name.split(' (')[0]} vs {c.b_name.split(' (')[0]} ({c.metric}; mean, paired difference and "
                    f"its 95 % CI; {c.runs} paired runs each): ")
        return f"every member must hold; {head}" + "; ".join(items)

    def to_dict(self) -> dict[str, Any]:
        return {"kind": self.kind, "parts": [{"label": lab, "status": ev.status(), "evidence": ev.to_dict()}
                                             for lab, ev in self.parts]}


@dataclass(frozen=True)
class Unverifiable:
    """Nothing can be computed: the reason.

    Attributes
    ----------
    reason : str
        Why the claim cannot be checked (status "cannot be checked").
    kind : str
        ``"unverifiable"`` (not an argument).
    """

    reason: str
    kind: str = field(default="unverifiable", init=False)

    def __post_init__(self) -> None:
        _text(self.reason, "reason")

    def status(self) -> str:
        return "cannot be checked"

    def summary(self) -> str:
        return self.reason

    def to_dict(self) -> dict[str, Any]:
        return {"kind": self.kind, "reason": self.reason}


Evidence = PublishedValues | Comparison | Proposition | Conjunction | Unverifiable


@dataclass(frozen=True)
class Alternative:
    """The same claim under another reading of an open choice.

    Attributes
    ----------
    choice : str
        The open choice (e.g. "variance guard").
    reading : str
        This alternative reading (e.g. ``"|σ̂²|"``).
    evidence : PublishedValues, Comparison, Proposition, Conjunction or Unverifiable
        The evidence under this reading.
    """

    choice: str     # the open choice (e.g. "variance guard")
    reading: str    # this alternative (e.g. "|σ̂²|")
    evidence: Evidence

    def __post_init__(self) -> None:
        _text(self.choice, "choice")
        _text(self.reading, "reading")
        if not isinstance(self.evidence, (PublishedValues, Comparison, Proposition, Conjunction, Unverifiable)):
            raise TypeError(f"evidence must be PublishedValues, Comparison, Proposition, Conjunction or Unverifiable, "
                            f"got {type(self.evidence).__name__}")

    def to_dict(self) -> dict[str, Any]:
        return {"choice": self.choice, "reading": self.reading, "status": self.evidence.status(),
                "ours": self.evidence.summary(), "evidence": self.evidence.to_dict()}


@dataclass(frozen=True)
class Claim:
    """One checkable claim of one source, with its evidence; the status is derived by rule.

    Parameters
    ----------
    id : str
        Unique, ``<source-prefix>-<slug>``.
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
        The claim under other readings of those choices.
    headline : bool
        The single most important finding of the source.
    critiques : tuple of str
        Labels of the critique boxes this record summarises.
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

    def __post_init__(self) -> None:
        for name in ("id", "source", "where", "claim", "published", "link", "bound"):
            _text(getattr(self, name), name)
        if not isinstance(self.evidence, (PublishedValues, Comparison, Proposition, Conjunction, Unverifiable)):
            raise TypeError(f"evidence must be PublishedValues, Comparison, Proposition, Conjunction or Unverifiable, "
                            f"got {type(self.evidence).__name__}")
        _texts(self.assumptions, "assumptions")
        _texts(self.critiques, "critiques")
        if isinstance(self.alternatives, str) or not all(isinstance(a, Alternative) for a in self.alternatives):
            raise TypeError(f"alternatives must be a tuple of Alternative, got {self.alternatives!r}")
        if not isinstance(self.headline, (bool, np.bool_)):
            raise TypeError(f"headline must be a bool, got {type(self.headline).__name__}")
        if self.source not in SOURCES:
            raise ValueError(f"source must be one of {sorted(SOURCES)}, got {self.source!r}")
        for name in ("id", "where", "claim", "link"):
            if not getattr(self, name).strip():
                raise ValueError(f"{name} must not be empty")
        object.__setattr__(self, "assumptions", tuple(self.assumptions))
        object.__setattr__(self, "alternatives", tuple(self.alternatives))
        object.__setattr__(self, "critiques", tuple(self.critiques))

    @property
    def status(self) -> str:
        """The status by the rules of this module."""
        s = self.evidence.status()
        if s == "reproduced" and (self.assumptions or any(a.evidence.status() != "reproduced"
                                                           for a in self.alternatives)):
            return "reproduced under stated assumptions"
        return s

    @property
    def robustness(self) -> str:
        """"primary reading; other readings hold in k of n" when alternatives were run, else "".

        The status is always the primary reading's; this counts the *other* readings under which the
        claim holds (reproduced, with or without stated assumptions), so that a status never reads as
        contradicting its own count.
        """
        if not self.alternatives:
            return ""
        good = ("reproduced", "reproduced under stated assumptions")
        k = sum(a.evidence.status() in good for a in self.alternatives)
        return f"primary reading; other readings hold in {k} of {len(self.alternatives)}"

    def to_dict(self) -> dict[str, Any]:
        src = SOURCES[self.source]
        return {
            "id": self.id, "source": self.source, "source_short": src.short, "chapter": src.chapter,
            "where": self.where, "claim": self.claim, "published": self.published,
            "ours": self.evidence.summary(), "bound": self.bound, "status": self.status,
            "primary_status": self.evidence.status(), "robustness": self.robustness,
            "assumptions": list(self.assumptions), "alternatives": [a.to_dict() for a in self.alternatives],
            "evidence": self.evidence.to_dict(), "link": self.link, "headline": self.headline,
            "critiques": list(self.critiques),
        }


def ledger_dir(start: Path | None = None) -> Path:
    """``book/ledger`` of the repository that contains ``start`` (default: the working directory).

    Parameters
    ----------
    start : pathlib.Path, optional
        Where to start looking upwards for ``_toc.yml``.

    Returns
    -------
    pathlib.Path
        The ledger directory (it may not exist yet).

    Raises
    ------
    FileNotFoundError
        No ``_toc.yml`` in ``start`` or above it.
    """
    if start is not None and not isinstance(start, (str, Path)):
        raise TypeError(f"start must be a pathlib.Path, got {type(start).__name__}")
    here = Path(start or Path.cwd()).resolve()
    for p in (here, *here.parents):
        if (p / "_toc.yml").is_file():
            return p / "book" / "ledger"
    raise FileNotFoundError(f"no _toc.yml above {here}: not inside the book's repository")


def _clean(x: Any) -> Any:
    """JSON-ready copy with floats rounded to 7 significant digits.

    Ten digits were not enough: a particle-filter study gives values that differ in the ninth digit
    between 1 and 2 BLAS threads, and the stored file (and its digest) must not depend on that.
    """
    if isinstance(x, float):
        return float(f"{x:.7g}") if math.isfinite(x) else None
    if isinstance(x, dict):
        return {k: _clean(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_clean(v) for v in x]
    return x


class Ledger:
    """The claims of one source's chapter, filled by the chapter and written to ``book/ledger``.

    A source with one chapter writes ``<source>.json``; a source whose claims span several
    chapters (:attr:`Source.chapters`) writes one file per chapter, ``<source>-<NN>.json``, each
    record's ``chapter`` naming the chapter that holds its evidence. The source's headline claim
    lives in its first chapter.

    Parameters
    ----------
    source : str
        A key of :data:`SOURCES`.
    chapter : str, optional
        Docname of the chapter filling this ledger, one of the source's chapters (default: its
        first).

    Attributes
    ----------
    source : str
        The source's key.
    chapter : str
        Docname of the chapter.
    claims : list of Claim
        Claims added so far, in order.

    Raises
    ------
    ValueError
        Unknown ``source``, or ``chapter`` not one of its chapters.
    """

    def __init__(self, source: str, chapter: str | None = None) -> None:
        if source not in SOURCES:
            raise ValueError(f"source must be one of {sorted(SOURCES)}, got {source!r}")
        src = SOURCES[source]
        if chapter is None:
            chapter = src.chapter
        if chapter not in src.chapters:
            raise ValueError(f"chapter must be one of {list(src.chapters)}, got {chapter!r}")
        self.source = source
        self.chapter = chapter
        self.claims: list[Claim] = []

    def add(self, claim: Claim) -> Claim:
        """Add a claim of this ledger's source (ids must be unique)."""
        if claim.source != self.source:
            raise ValueError(f"claim {claim.id} is of {claim.source}, this ledger holds {self.source}")
        if any(c.id == claim.id for c in self.claims):
            raise ValueError(f"duplicate claim id {claim.id!r}")
        self.claims.append(claim)
        return claim

    def records(self) -> list[dict[str, Any]]:
        """JSON-ready records of the claims, each naming this ledger's chapter."""
        return [_clean({**c.to_dict(), "chapter": self.chapter}) for c in self.claims]

    def table(self) -> pd.DataFrame:
        """One row per claim: where, status, robustness (what the chapter displays)."""
        return pd.DataFrame([{"id": c.id, "where": c.where, "status": c.status, "robustness": c.robustness}
                             for c in self.claims]).set_index("id")

    @property
    def filename(self) -> str:
        """The ledger file's name: ``<source>.json``, or ``<source>-<NN>.json`` for a multi-chapter source."""
        return SOURCES[self.source].ledger_file(self.chapter)

    def write(self, directory: Path | None = None) -> str:
        """Write :attr:`filename` and return the SHA-256 of its text (shown by the chapter).

        The digest is part of the chapter's stored output, so a change of any record makes the
        notebook test fail until the notebook is re-executed and the file committed. The source's
        first chapter must hold exactly one headline claim, its other chapters none.
        """
        if not self.claims:
            raise ValueError("the ledger is empty")
        want = int(self.chapter == SOURCES[self.source].chapter)
        if sum(c.headline for c in self.claims) != want:
            raise ValueError("exactly one claim per source must be the headline, in the source's first chapter")
        d = directory or ledger_dir()
        d.mkdir(parents=True, exist_ok=True)
        head = {"source": self.source}
        if len(SOURCES[self.source].chapters) > 1:
            head["chapter"] = self.chapter
        text = json.dumps({**head, "claims": self.records()}, ensure_ascii=False, indent=1) + "\n"
        (d / self.filename).write_text(text, encoding="utf-8")
        return hashlib.sha256(text.encode("utf-8")).hexdigest()[:16]
