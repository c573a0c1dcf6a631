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
  an interval wholly inside (-m, m) is *not distinguishable* (an equivalence region, as in two one-sided
  tests); an interval not wholly inside it keeps the rule above (rule R2).
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

from fusion._validation import _numeric, _real_number, count, seed as check_seed, sequence
from fusion.book import rulebook as R
from fusion.book.exact import ExactComparison


def _text(value: Any, name: str) -> str:
    """Check that a text field is a ``str`` (TypeError naming it otherwise)."""
    if not isinstance(value, str):
        raise TypeError(f"{name} must be a str, got {type(value).__name__}")
    return value


def _texts(value: Any, name: str) -> None:
    """Check a tuple of strings (a bare string is refused: it would be split into characters)."""
    if isinstance(value, str) or not all(isinstance(v, str) for v in sequence(value, name)):
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

#: The closed status vocabulary, in display order (:data:`fusion.book.rulebook.STATUSES`).
STATUSES: tuple[str, ...] = R.STATUSES

#: Minimum number of Monte-Carlo runs for a stochastic record (fewer needs a stated reason).
MIN_RUNS = R.MIN_RUNS

#: Confidence level of every paired interval.
CONFIDENCE_LEVEL = R.CONFIDENCE_LEVEL

#: A comparison is heavy-tailed when this share of its runs (at least one run) carries half of the total absolute difference.
DOMINANCE_SHARE = R.DOMINANCE_SHARE

#: One-sentence definition of each status (shown on the Verdicts page); the rules that decide them are
#: :data:`fusion.book.rulebook.RULES`.
STATUS_DEFINITIONS: dict[str, str] = {
    "reproduced": "the published number equals ours at its printed precision (R1); or the claimed difference's "
                  f"paired {CONFIDENCE_LEVEL * 100:.0f} % interval lies on the claimed side of zero and not wholly "
                  "inside the practical margin, or a 'no effect' claim's interval lies wholly inside it (R2, R3); or the "
                  "mathematical claim holds (R9)",
    "reproduced under stated assumptions": "as reproduced under the primary reading, but the record states "
                                           "assumptions, or another reading of the source's open choices does "
                                           "not reproduce it (R5)",
    "not reproduced": "our computation does not give the published number at its printed precision (R1)",
    "contradicted": f"the paired {CONFIDENCE_LEVEL * 100:.0f} % interval lies on the other side of zero and not wholly "
                    "inside the practical margin (for a 'no effect' claim: on either side of zero, not wholly inside "
                    "it), or a mean is infinite against the claim (R2, R3); or "
                    "the mathematical claim is false (R9)",
    "not distinguishable": f"the paired {CONFIDENCE_LEVEL * 100:.0f} % interval contains zero, or lies wholly "
                           "inside the practical margin for a claimed difference (too small to matter) (R2, R3)",
    "cannot be checked": "the source gives too little to compute anything, or compares with a method it never "
                         "defines; the record says why (R7, R9)",
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
    x = _real_number(x, "x")  # TypeError naming x for text, booleans, complex, None, containers
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
def _run_count(runs: Any) -> int | None:
    """A Monte-Carlo run count (an int >= 1) or None (an exact value); TypeError/ValueError naming ``runs``."""
    if runs is None:
        return None
    if isinstance(runs, (bool, np.bool_)) or not isinstance(runs, (int, np.integer)):
        raise TypeError(f"runs must be an int or None, got {type(runs).__name__}")
    if runs < 1:
        raise ValueError(f"runs must be >= 1, got {runs}")
    return int(runs)


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
    runs : int or None
        Monte-Carlo runs our values were computed from (keyword; ``None``, the default, for an exact
        computation). Values with a run count are stochastic: R4 applies and the reseeding sweep covers them.
    """

    published: tuple[float, ...]
    ours: tuple[float, ...]
    decimals: tuple[int, ...]
    unit: str = ""
    kind: str = field(default="published", init=False)
    runs: int | None = None

    def __init__(self, published: ArrayLike, ours: ArrayLike, decimals: int | Sequence[int], unit: str = "", *,
                 runs: int | None = None) -> None:
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
        object.__setattr__(self, "runs", _run_count(runs))

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

    def brief(self) -> str:
        """Our number in a few words (the In-brief boxes and the Verdicts table)."""
        return self.summary()

    def to_dict(self) -> dict[str, Any]:
        out = {"kind": self.kind, "published": list(self.published), "ours": list(self.ours),
               "decimals": list(self.decimals), "unit": self.unit, "matches": list(self.matches)}
        return out if self.runs is None else out | {"runs": self.runs}


@dataclass(frozen=True)
class Comparison:
    """A paired Monte-Carlo comparison: is method A's metric lower than B's, higher, or the same?

    The status comes from :func:`fusion.book.rulebook.judge_paired` (rules R2 and R3): the paired 95 %
    interval (of the mean, or of the median when the differences are heavy-tailed) against zero and the
    practical margin.

    Parameters
    ----------
    a, b : array_like, shape (runs,)
        Per-run metric of A and of B on the same runs (same seeds, same samples). ``+inf`` marks a run whose
        statistic is infinite; NaN is refused.
    a_name, b_name : str
    claim : {"less", "greater", "equal"}
        What the claim says of A against B ("equal": no effect, within the margin).
    metric : str
        What is compared, with its unit (e.g. "mean absolute error (°C)").
    seed : int or None
        Seed of the runs.
    reason : str
        Why fewer than :data:`MIN_RUNS` runs are enough, when they are.
    margin : float or None
        Practical margin in the metric's units (>= 0). ``None`` (the default): ``relative_margin`` times
        the absolute value of the baseline's mean (of its median when a run of b is infinite).
    relative_margin : float
        Share of the baseline's mean used when ``margin`` is None (default
        :data:`fusion.book.rulebook.DEFAULT_RELATIVE_MARGIN`).
    conditions : tuple of (str, str)
        The conditions (e.g. a stress test) under which A and B ran; R6 refuses different ones.
    infinite_mean : tuple of str
        ``"a"``, ``"b"``: methods whose population mean is infinite by a closed-form argument (R3).
    """

    a: tuple[float, ...]
    b: tuple[float, ...]
    a_name: str
    b_name: str
    claim: Literal["less", "greater", "equal"]
    metric: str
    seed: int | None = None
    reason: str = ""
    margin: float = 0.0
    relative_margin: float | None = None
    conditions: tuple[str, str] = ("", "")
    infinite_mean: tuple[str, ...] = ()
    kind: str = field(default="comparison", init=False)

    def __init__(self, a: ArrayLike, b: ArrayLike, a_name: str, b_name: str,
                 claim: Literal["less", "greater", "equal"], metric: str, seed: int | None = None,
                 reason: str = "", margin: float | None = None, relative_margin: float | None = None,
                 conditions: tuple[str, str] = ("", ""), infinite_mean: Sequence[str] = ()) -> None:
        av = _numeric(a, "a").ravel().astype(float)
        bv = _numeric(b, "b").ravel().astype(float)
        for name, v in (("a_name", a_name), ("b_name", b_name), ("metric", metric), ("reason", reason)):
            _text(v, name)
        if seed is not None:
            check_seed(seed, "seed")  # an integer (rule 11): 0.0 is not a seed
        if av.shape != bv.shape or av.size < 2:
            raise ValueError(f"a and b must hold the same number (>= 2) of paired runs, got {av.size} and {bv.size}")
        if np.any(np.isnan(av)) or np.any(np.isnan(bv)) or np.any(np.isneginf(av)) or np.any(np.isneginf(bv)):
            raise ValueError("a and b must be finite or +inf (a run whose statistic is infinite)")
        if claim not in ("less", "greater", "equal"):
            raise ValueError(f"claim must be 'less', 'greater' or 'equal', got {claim!r}")
        if av.size < MIN_RUNS and not reason:
            raise ValueError(f"{av.size} runs < {MIN_RUNS}: give more runs or a reason")
        if not (isinstance(conditions, tuple) and len(conditions) == 2 and all(isinstance(c, str) for c in conditions)):
            raise TypeError(f"conditions must be a pair of str, got {conditions!r}")
        if conditions[0] != conditions[1]:  # R6
            raise ValueError(f"conditions: A ran under {conditions[0]!r} and B under {conditions[1]!r}; a stress test "
                             "applied to one method must be applied to every compared method (rule R6)")
        inf_m = tuple(infinite_mean)
        if any(x not in ("a", "b") for x in inf_m):
            raise ValueError(f"infinite_mean must name 'a' or 'b', got {inf_m!r}")
        for name, v in (("margin", margin), ("relative_margin", relative_margin)):
            if v is not None and (isinstance(v, bool) or not isinstance(v, (int, float, np.floating, np.integer))
                                  or not math.isfinite(float(v)) or float(v) < 0):
                raise ValueError(f"{name} must be a finite number >= 0, got {v!r}")
        if margin is None:
            rel = R.DEFAULT_RELATIVE_MARGIN if relative_margin is None else float(relative_margin)
            ref = abs(float(np.mean(bv))) if np.all(np.isfinite(bv)) else abs(float(np.median(bv)))
            margin = rel * ref if math.isfinite(ref) else 0.0
        else:
            relative_margin = None
        for k, v in (("a", tuple(float(x) for x in av)), ("b", tuple(float(x) for x in bv)), ("a_name", a_name),
                     ("b_name", b_name), ("claim", claim), ("metric", metric), ("seed", seed), ("reason", reason),
                     ("margin", float(margin)), ("relative_margin", None if relative_margin is None else float(relative_margin)),
                     ("conditions", conditions), ("infinite_mean", inf_m), ("kind", "comparison")):
            object.__setattr__(self, k, v)

    def with_margin(self, margin: float | None = None, relative_margin: float | None = None) -> "Comparison":
        """The same comparison judged with another practical margin (absolute, or relative to B's mean).

        Parameters
        ----------
        margin : float, optional
            Absolute margin in the metric's units.
        relative_margin : float, optional
            Share of the baseline's mean (used when ``margin`` is None).

        Returns
        -------
        Comparison
        """
        return Comparison(self.a, self.b, self.a_name, self.b_name, self.claim, self.metric, self.seed, self.reason,
                          margin, relative_margin, self.conditions, self.infinite_mean)

    @property
    def runs(self) -> int:
        return len(self.a)

    def judgement(self) -> R.Judgement:
        """The rulebook's judgement (R2, R3), computed once."""
        cached = self.__dict__.get("_judgement")
        if cached is None:
            cached = R.judge_paired(self.a, self.b, self.claim, self.margin, self.infinite_mean)
            object.__setattr__(self, "_judgement", cached)
        return cached

    def interval(self) -> tuple[float, float, float]:
        """The deciding statistic (mean paired difference A − B, or its median under R3) and its 95 % interval."""
        j = self.judgement()
        return j.estimate, j.low, j.high

    def within_margin(self) -> bool:
        """``True`` if the whole 95 % interval lies inside (-margin, margin)."""
        return self.judgement().region == "equivalent"

    def status(self) -> str:
        return self.judgement().status

    def resolution(self) -> float:
        r"""The step every number of this comparison is rounded to when stored or shown.

        Four significant digits of the larger finite mean, :math:`10^{\lfloor\log_{10}\max(|\bar a|,|\bar b|)\rfloor-3}`
        (of the largest finite absolute value when both means are zero; a side declared to have an infinite
        mean, ``infinite_mean``, is left out unless both are), applied to the means *and* to the
        difference and its interval. A difference of two nearly equal means has far fewer significant
        digits than the means themselves: rounding it to its own significant digits would store the
        round-off of the runs (which differs between BLAS kernels) instead of the comparison.

        Returns
        -------
        float
            A power of ten; 1.0 when every value is zero.
        """
        # a side whose mean is infinite by a closed-form argument (R3) has a meaningless sample mean: its finite
        # runs would set the scale (and round the other side's mean to nothing), unless both sides are infinite
        skip = set(self.infinite_mean) if len(set(self.infinite_mean)) < 2 else set()
        fa = np.array(([x for x in self.a if math.isfinite(x)] if "a" not in skip else []) or [0.0])
        fb = np.array(([x for x in self.b if math.isfinite(x)] if "b" not in skip else []) or [0.0])
        scale = max(abs(float(np.mean(fa))), abs(float(np.mean(fb))))
        if scale == 0.0:
            scale = float(max(np.max(np.abs(fa)), np.max(np.abs(fb))))
        return 10.0 ** (math.floor(math.log10(scale)) - 3) if scale > 0 else 1.0

    def _rounded(self, x: float) -> float:
        """``x`` rounded to :meth:`resolution`; a non-zero ``x`` that would round to 0 keeps its sign.

        Such an ``x`` (an interval end closer to zero than the resolution) is given two significant
        digits instead, so that the status re-derived from the stored interval is the status.
        """
        if not math.isfinite(x):
            return x
        r = self.resolution()
        decimals = -int(round(math.log10(r)))
        v = round(x, decimals) if decimals >= 0 else round(x / r) * r
        if v == 0.0 and x != 0.0:
            return float(f"{x:.2g}")
        return v + 0.0

    def _text(self, x: float) -> str:
        """``x`` written at :meth:`resolution`: fixed decimals down to 10⁻⁴, else ``a×10^n`` with the digits it has."""
        if not math.isfinite(x):
            return fmt(x)
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

    def _mean(self, v: tuple[float, ...]) -> float:
        return float(np.mean(v)) if all(math.isfinite(x) for x in v) else math.inf

    def summary(self) -> str:
        j = self.judgement()
        t = self._text
        ma, mb = self._mean(self.a), self._mean(self.b)
        side = {"less": "lower", "greater": "higher", "equal": "lower"}[self.claim]
        wins = round(j.share * j.runs)
        what = {"mean": "mean difference", "median": "median difference",
                "infinite mean": "mean difference"}[j.statistic]
        head = (f"{self.a_name} {t(ma)} vs {self.b_name} {t(mb)} ({self.metric}, mean); "
                f"{what} {t(j.estimate)}")
        if j.statistic != "infinite mean":
            head += f", 95 % CI [{t(j.low)}, {t(j.high)}]"
        tail = ""
        if j.statistic == "infinite mean":
            tail = f"; {'A' if 'a' in self.infinite_mean or math.isinf(ma) else 'B'}'s mean is infinite (R3)"
        elif j.statistic == "median":
            tail = "; both means infinite: decided by the median (R3)"
        elif j.heavy:  # R3: reported beside the mean, which decides
            med, lo, hi = R.median_interval(np.asarray(self.a, float) - np.asarray(self.b, float))
            tail = (f"; heavy-tailed differences (tail index {fmt(j.tail_index, 2)}; a few runs carry the mean): "
                    f"median difference {t(med)} [{t(lo)}, {t(hi)}], shown beside the mean, which decides (R3)")
        margin = f"; margin ±{fmt(self.margin, 3)}" if self.margin > 0 else ""
        pairing = "runs against a constant" if len(set(self.b)) == 1 else "paired runs"   # one-sample yardstick
        return (head + f", {self.runs} {pairing}; {self.a_name} {side} in {wins} of {self.runs} runs"
                + margin + tail + ("; the interval lies within the margin: no difference that matters"
                                   if j.region == "equivalent" else ""))

    def brief(self) -> str:
        """Our number in a few words: both means and the deciding statistic with its interval."""
        j, t = self.judgement(), self._text
        if j.statistic == "infinite mean":  # the sample mean of the infinite side says nothing: name it, give medians
            inf_a = "a" in self.infinite_mean or math.isinf(self._mean(self.a))
            med, lo, hi = R.median_interval(np.subtract(np.where(np.isinf(self.a), np.inf, self.a),
                                                        np.where(np.isinf(self.b), np.inf, self.b)))
            finite = (self.b_name, self._mean(self.b)) if inf_a else (self.a_name, self._mean(self.a))
            return (f"{self.a_name if inf_a else self.b_name}: infinite mean vs {finite[0]} {t(finite[1])}; "
                    f"median difference {t(med)} [{t(lo)}, {t(hi)}], {self.runs} runs")
        stat = {"mean": "difference", "median": "median difference"}[j.statistic]
        return (f"{self.a_name} {t(self._mean(self.a))} vs {self.b_name} {t(self._mean(self.b))}; "
                f"{stat} {t(j.estimate)} [{t(j.low)}, {t(j.high)}], {self.runs} runs")

    def to_dict(self) -> dict[str, Any]:
        j = self.judgement()
        return {"kind": self.kind, "a_name": self.a_name, "b_name": self.b_name, "claim": self.claim,
                "metric": self.metric, "mean_a": self._rounded(self._mean(self.a)),
                "mean_b": self._rounded(self._mean(self.b)), "statistic": j.statistic, "rule": j.rule,
                "difference": self._rounded(j.estimate), "ci_low": self._rounded(j.low),
                "ci_high": self._rounded(j.high), "region": j.region, "share_lower": round(j.share, 4),
                "share_low": round(j.share_low, 4), "share_high": round(j.share_high, 4),
                "tail_index": None if not math.isfinite(j.tail_index) else round(j.tail_index, 3),
                "heavy_tailed": j.heavy, "resolution": self.resolution(), "runs": self.runs, "seed": self.seed,
                "reason": self.reason, "margin": self._rounded(self.margin) if self.margin else 0.0,
                "relative_margin": self.relative_margin,
                "conditions": list(self.conditions), "infinite_mean": list(self.infinite_mean)}


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
    runs : int or None
        Monte-Carlo runs the yes/no was computed from (keyword; ``None``, the default, for an exact check).
        A proposition with a run count is stochastic: R4 applies to it and the reseeding sweep covers it.
    """

    holds: bool
    ours: str
    kind: str = field(default="proposition", init=False)
    runs: int | None = field(default=None, kw_only=True)

    def __post_init__(self) -> None:
        if not isinstance(self.holds, (bool, np.bool_)):
            raise TypeError(f"holds must be a bool, got {type(self.holds).__name__}")
        _text(self.ours, "ours")
        object.__setattr__(self, "holds", bool(self.holds))
        object.__setattr__(self, "runs", _run_count(self.runs))

    def status(self) -> str:
        return "reproduced" if self.holds else "contradicted"

    def summary(self) -> str:
        return self.ours

    def brief(self) -> str:
        """Our finding in a few words: its first clause."""
        return self.ours.split("; ")[0]

    def to_dict(self) -> dict[str, Any]:
        out = {"kind": self.kind, "holds": self.holds, "ours": self.ours}
        return out if self.runs is None else out | {"runs": self.runs}


@dataclass(frozen=True)
class Conjunction:
    """A claim about every member of a group ("every sensor"), one piece of evidence per member.

    The claim holds for the group only if it holds for each member, so the status is derived from
    the members' statuses: *contradicted* if any member's is, *reproduced* if every member's is,
    otherwise (some member not distinguishable, none contradicted) *not distinguishable*.

    Parameters
    ----------
    parts : sequence of (str, Comparison, ExactComparison or Proposition)
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
            if not isinstance(ev, (Comparison, ExactComparison, Proposition)):
                raise TypeError("each part's evidence must be a Comparison, an ExactComparison or a Proposition, "
                                f"got {type(ev).__name__}")
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
        for label, ev in self.parts:
            if isinstance(ev, Comparison):
                j, t = ev.judgement(), ev._text
                stat = "median difference" if j.statistic == "median" else "difference"
                item = (f"{label}: {ev.status()}, {t(ev._mean(ev.a))} vs {t(ev._mean(ev.b))}, "
                        f"{stat} {t(j.estimate)} [{t(j.low)}, {t(j.high)}]")
                if j.heavy and j.statistic == "mean":   # R3: median and share of runs beside the mean, per member
                    med, lo, hi = R.median_interval(np.asarray(ev.a, float) - np.asarray(ev.b, float))
                    side = {"less": "lower", "greater": "higher", "equal": "lower"}[ev.claim]
                    item += (f" (heavy-tailed: median {t(med)} [{t(lo)}, {t(hi)}], A {side} in "
                             f"{round(j.share * j.runs)} of {j.runs} runs)")
                items.append(item)
            else:
                items.append(f"{label}: {ev.status()}, {ev.summary()}")
        comps = [ev for _, ev in self.parts if isinstance(ev, Comparison)]
        head = ""
        if comps and len(comps) == len(self.parts):
            c = comps[0]
            head = f"{c.a_name.split(' (')[0]} vs {c.b_name.split(' (')[0]} ({c.metric}; {c.runs} paired runs each): "
        return f"every member must hold; {head}" + "; ".join(items)

    def brief(self) -> str:
        """How many members hold."""
        k = sum(ev.status() == "reproduced" for _, ev in self.parts)
        bad = sum(ev.status() == "contradicted" for _, ev in self.parts)
        return f"holds for {k} of {len(self.parts)} members" + (f", contradicted for {bad}" if bad else "")

    @property
    def runs(self) -> int | None:
        """The smallest run count of the members' comparisons (None when no member is stochastic)."""
        r = [ev.runs for _, ev in self.parts if isinstance(ev, (Comparison, Proposition)) and ev.runs is not None]
        return min(r) if r else None

    def with_margin(self, margin: float | None = None, relative_margin: float | None = None) -> "Conjunction":
        """The same group with every member comparison judged with another margin (see :meth:`Comparison.with_margin`)."""
        return Conjunction([(lab, ev.with_margin(margin, relative_margin)
                             if isinstance(ev, (Comparison, ExactComparison)) else ev)
                            for lab, ev in self.parts])

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

    def brief(self) -> str:
        """Nothing computed."""
        return "nothing to compute"

    def to_dict(self) -> dict[str, Any]:
        return {"kind": self.kind, "reason": self.reason}


Evidence = PublishedValues | Comparison | ExactComparison | Proposition | Conjunction | Unverifiable

#: The evidence classes a record or reading may hold.
EVIDENCE_TYPES = (PublishedValues, Comparison, ExactComparison, Proposition, Conjunction, Unverifiable)


def _runs(ev: "Evidence") -> int | None:
    """Monte-Carlo runs behind a piece of evidence (None when it is not stochastic)."""
    if isinstance(ev, (Comparison, Conjunction, Proposition, PublishedValues)):
        return ev.runs
    return None


def _test_of(ev: "Evidence") -> str:
    """The kind of test a piece of evidence is (:data:`fusion.book.rulebook.TESTS`)."""
    if isinstance(ev, PublishedValues):
        return "published"
    if isinstance(ev, Comparison):
        return "equivalence" if ev.claim == "equal" else "paired"
    if isinstance(ev, Conjunction):
        kinds = {_test_of(e) for _, e in ev.parts}
        return kinds.pop() if len(kinds) == 1 else "paired"
    if isinstance(ev, Unverifiable):
        return "unverifiable"
    return "exact"


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
    """

    choice: str     # the open choice (e.g. "variance guard")
    reading: str    # this alternative (e.g. "|σ̂²|")
    evidence: Evidence
    kind: str = "open-choice"

    def __post_init__(self) -> None:
        _text(self.choice, "choice")
        _text(self.reading, "reading")
        _text(self.kind, "kind")
        if not isinstance(self.evidence, EVIDENCE_TYPES):
            raise TypeError("evidence must be PublishedValues, Comparison, ExactComparison, Proposition, Conjunction "
                            f"or Unverifiable, got {type(self.evidence).__name__}")
        if self.kind not in R.READING_KINDS or self.kind == "primary":
            raise ValueError(f"kind must be one of {R.READING_KINDS[1:]}, got {self.kind!r}")

    @property
    def runs(self) -> int | None:
        """Monte-Carlo runs of this reading (None when it is not stochastic)."""
        return _runs(self.evidence)

    def counted(self, primary_runs: int | None) -> tuple[bool, str]:
        """Whether this reading counts towards robustness (R4, R5), and why not."""
        return R.counted(self.kind, self.runs, primary_runs, self.evidence.status())

    def to_dict(self, primary_runs: int | None = None) -> dict[str, Any]:
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
        The claim under other readings.
    headline : bool
        The single most important finding of the source (only a claim the source prints: R8).
    critiques : tuple of str
        Labels of the critique boxes this record summarises.
    claimant : {"source", "implied", "book"}
        Whose claim it is: printed in the source; the book's reading of the source's purpose; the book's
        own question (R8).
    test : str
        One of :data:`fusion.book.rulebook.TESTS`; default: from the evidence's kind.
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
        for name in ("id", "source", "where", "claim", "published", "link", "bound", "claimant", "test"):
            _text(getattr(self, name), name)
        if not isinstance(self.evidence, EVIDENCE_TYPES):
            raise TypeError("evidence must be PublishedValues, Comparison, ExactComparison, Proposition, Conjunction "
                            f"or Unverifiable, got {type(self.evidence).__name__}")
        _texts(self.assumptions, "assumptions")
        _texts(self.critiques, "critiques")
        if isinstance(self.alternatives, str) or not all(isinstance(a, Alternative)
                                                         for a in sequence(self.alternatives, "alternatives")):
            raise TypeError(f"alternatives must be a tuple of Alternative, got {self.alternatives!r}")
        if not isinstance(self.headline, (bool, np.bool_)):
            raise TypeError(f"headline must be a bool, got {type(self.headline).__name__}")
        if self.source not in SOURCES:
            raise ValueError(f"source must be one of {sorted(SOURCES)}, got {self.source!r}")
        for name in ("id", "where", "claim", "link"):
            if not getattr(self, name).strip():
                raise ValueError(f"{name} must not be empty")
        if self.claimant not in R.CLAIMANTS:
            raise ValueError(f"claimant must be one of {R.CLAIMANTS}, got {self.claimant!r}")
        if self.headline and self.claimant != "source":
            raise ValueError(f"{self.id}: only a claim the source prints can be its main finding (rule R8), "
                             f"this one's claimant is {self.claimant!r}")
        if not self.test:
            object.__setattr__(self, "test", _test_of(self.evidence))
        if self.test not in R.TESTS:
            raise ValueError(f"test must be one of {R.TESTS}, got {self.test!r}")
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

    def to_dict(self) -> dict[str, Any]:
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
        if not isinstance(source, str):
            raise TypeError(f"source must be a str, got {type(source).__name__}")
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
