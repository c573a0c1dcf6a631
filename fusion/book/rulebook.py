r"""The rulebook: one set of rules that turns every record's evidence into its status.

Every status of the book comes from this module, the same rules for every record of every
source. Each rule is a :class:`Rule` in :data:`RULES`; the Verdicts page prints them (the
``fusion-status-rules`` directive), and ``tests/test_rulebook.py`` tests each on constructed
evidence. The claims themselves (text, claimant, test, quantity, margin, readings) are data in
``book/claims/<source>.yaml`` (:mod:`fusion.book.claims`); the evidence comes from the chapters
(:mod:`fusion.book.ledger`'s evidence classes).

The rules in short
------------------
R1 published value
    Reproduced iff every published value equals ours rounded to its printed decimals; at an exact tie (ours
    exactly halfway between two printed values) either neighbour is ours rounded.
R2 paired comparison
    Per-run values of A and B on the same runs; the 95 % interval of the mean paired difference
    A − B (Student's t) is placed against zero and the record's practical margin m (one margin per
    quantity, :data:`DEFAULT_RELATIVE_MARGIN` of the baseline's mean unless the claim data declares
    another): *lower* if the interval lies below zero and not wholly inside [−m, m], *higher* if above
    zero and not wholly inside, *equivalent* if wholly inside the closed [−m, m] (m > 0: the margin is the
    largest difference that is practically none; at m = 0 no interval is equivalent), *undecided* otherwise.
    Round-off never decides, at zero as at the margin's edge: differences all within round-off of zero
    (1e-9 of the values' magnitude S, ``fusion._limits.ROUND_OFF_TIE``; 4 epsilons of float32 or float16 runs) are
    a tie, and an interval end within round-off of ±m (the same share of S, S at least m) is the margin. "A lower
    than B" is reproduced when lower, contradicted when higher, not distinguishable when equivalent
    or undecided; "A higher" mirrors it; "no effect" is reproduced when equivalent, contradicted when
    lower or higher, not distinguishable when undecided. The same margin decides "better", "worse"
    and "no effect".
R3 heavy tails
    A statistic that is infinite or undefined is never "not distinguishable". When a method's mean is
    infinite (a per-run value is infinite, or the evidence states a closed-form reason) and the other's
    is finite, the claim's own criterion (the mean) decides: the infinite one is higher. When both means
    are infinite, the median difference and its distribution-free 95 % interval (order statistics)
    decide, against the same margin as in R2; a run in which both are infinite has no difference and is
    left out, and when the median difference is undefined (fewer than 6 runs left, or its two middle
    values are −∞ and +∞) the claim cannot be checked on this evidence. An infinite median difference (+∞ or
    −∞) decides the claim only when its interval lies on one side of zero (the sign is then decided), and an
    interval [−∞, +∞] decides nothing: otherwise the claim cannot be checked on this evidence, never "not
    distinguishable". Otherwise the mean decides (R2), whatever the tail: a
    heavy tail (Hill tail index of the differences below :data:`HEAVY_TAIL_INDEX`, or
    :data:`DOMINANCE_SHARE` of the runs carrying half of the sum of absolute differences) is reported
    beside the status with the median difference and the share of runs in which A lies on the claimed
    side (Clopper-Pearson interval), and the reseeding sweep re-derives the status at ten times the
    runs. A tail estimate from a few hundred finite draws does not show that a variance is infinite
    (the Hill test reads an infinite variance in about a third of samples of 100 squared Gaussian errors), so it never changes the statistic
    that decides.
R4 power
    Every reading of a stochastic record runs at least as many runs as the primary reading, and at least
    :data:`MIN_RUNS`; a reading with fewer is marked underpowered and not counted.
R5 readings
    The status is the primary reading's. The robustness count ("the claim holds under k of n other
    readings") counts only readings of the source's open choices; reseeds, settings outside the claim's
    scope, stand-ins for undefined baselines, explanations of a discrepancy and readings that cannot be
    checked are reported apart. "Reproduced" becomes "reproduced under stated assumptions" when the record
    lists assumptions or a counted reading does not also reproduce the claim.
R6 stress tests
    A stress test applied to one method of a comparison is applied to every compared method: evidence whose
    methods ran under different conditions is refused.
R7 undefined baselines
    A comparison with a method the source names but never defines (the claim data marks the baseline
    ``defined: false``) cannot be checked on the source's account; the book's stand-ins are reported as
    readings of kind ``stand-in``, never counted.
R8 whose claim
    Only a claim the source prints (claimant ``source``) can be a source's main finding, appear under "the
    source claims" or in the errata; a claim of the book's reading of the source's purpose (``implied``) or
    the book's own question (``book``) appears among the book's questions.
R9 groups and exact values
    A claim about every member of a group holds iff it holds for each member (contradicted if any member's
    is contradicted, otherwise cannot be checked if any member's cannot be checked, otherwise not
    distinguishable); a mathematical claim is reproduced iff it holds; a
    claim that one method is better on a quantity computed exactly (a closed-form error, an operation
    count) is judged as R2 with a zero-width interval against the same practical margin
    (:class:`fusion.book.exact.ExactComparison`); a claim the source gives too little to compute cannot
    be checked, with the reason. A printed number that no program of the stated scenario can give, under
    any reading of its open choices, is judged here as a mathematical claim; one that some reading could
    give is judged by R1.

References
----------
* Student (1908). The probable error of a mean. *Biometrika*, 6(1), 1-25.
* Hill, B. M. (1975). A simple general approach to inference about the tail of a distribution.
  *The Annals of Statistics*, 3(5), 1163-1174.
* Schuirmann, D. J. (1987). A comparison of the two one-sided tests procedure and the power approach for
  assessing the equivalence of average bioavailability. *J. Pharmacokinetics and Biopharmaceutics*, 15(6).
* Clopper, C. J. and Pearson, E. S. (1934). The use of confidence or fiducial limits illustrated in the case
  of the binomial. *Biometrika*, 26(4), 404-413.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike
from scipy import stats

from fusion._validation import _numeric, _real_number, check_magnitude, count, scalar, sequence, shown
from fusion._validation import flag, input_eps, one_of, read_once, text, text_fields
from fusion._limits import ROUND_OFF_TIE, work
from fusion.book.tables import sci

__all__ = [
    "STATUSES",
    "CLAIMANTS",
    "TESTS",
    "READING_KINDS",
    "COUNTED_KINDS",
    "MIN_RUNS",
    "CONFIDENCE_LEVEL",
    "DEFAULT_RELATIVE_MARGIN",
    "HEAVY_TAIL_INDEX",
    "DOMINANCE_SHARE",
    "HEAVY_TAIL_MIN_RUNS",
    "Rule",
    "RULES",
    "Judgement",
    "hill_tail_index",
    "median_interval",
    "median_values_needed",
    "share_interval",
    "region",
    "status_from_region",
    "judge_paired",
    "counted",
    "record_status",
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

#: Whose claim a record is: printed in the source; the book's reading of the source's purpose; the book's own question.
CLAIMANTS: tuple[str, ...] = ("source", "implied", "book")

#: The kinds of test a record can have.
TESTS: tuple[str, ...] = ("published", "paired", "equivalence", "exact", "count", "unverifiable")

#: The kinds of reading: ``primary``; ``open-choice`` (another reading of a choice the source leaves open);
#: ``stand-in`` (the book's stand-in for a baseline the source never defines); ``reseed``; ``out-of-scope``
#: (a setting outside the claim's scope); ``explanation`` (a hypothesis that explains a discrepancy);
#: ``stress`` (a stress test, applied to every compared method).
READING_KINDS: tuple[str, ...] = ("primary", "open-choice", "stand-in", "reseed", "out-of-scope", "explanation",
                                  "stress")

#: Reading kinds that count towards a record's robustness (R5).
COUNTED_KINDS: tuple[str, ...] = ("open-choice",)

#: Minimum number of Monte-Carlo runs of any reading of a stochastic record (R4).
MIN_RUNS = 100

#: Confidence level of every interval.
CONFIDENCE_LEVEL = 0.95

#: Practical margin of a comparison, as a share of the baseline's mean, unless the claim data declares one (R2).
DEFAULT_RELATIVE_MARGIN = 0.05

#: Hill tail index below which paired differences count as heavy-tailed (their variance does not exist) (R3).
HEAVY_TAIL_INDEX = 2.0

#: Fewest runs on which R3's heavy-tail test is run (fewer runs, allowed only with a stated reason, keep R2).
HEAVY_TAIL_MIN_RUNS = 20

#: Share of the runs (at least one run) that, carrying half of the summed absolute differences, makes the differences heavy-tailed (R3).
DOMINANCE_SHARE = 0.01


@dataclass(frozen=True)
class Rule:
    """One rule of the rulebook.

    Attributes
    ----------
    key : str
        ``"R1"`` … ``"R9"``.
    title : str
        A few words.
    text : str
        The rule in full, as the Verdicts page prints it.
    """

    key: str
    title: str
    text: str


_PCT = f"{CONFIDENCE_LEVEL * 100:.0f} %"

#: Round-off of runs given as float32 or float16, in epsilons of their dtype (R2: their own round-off never decides).
_TIE_ULPS = 4

#: Every rule, in the order the Verdicts page prints them.
RULES: tuple[Rule, ...] = (
    Rule("R1", "published values",
         "A published number is reproduced iff ours, rounded to the printed decimals, equals it (at an exact tie "
         "either neighbour counts: the source does not say how it rounds); a record of several numbers is "
         "reproduced iff every one is, otherwise not reproduced."),
    Rule("R2", "paired comparisons",
         f"Both methods run on the same runs; the {_PCT} Student-t interval of the mean paired difference A − B is "
         "placed against zero and the record's practical margin m (one margin per quantity: "
         f"{DEFAULT_RELATIVE_MARGIN:.0%} of the baseline's mean unless the claim data states another). The interval "
         "is lower (below zero, not wholly inside ±m), higher (above zero, not wholly inside ±m), equivalent (wholly "
         "inside ±m, its ends included: the margin is the largest difference that is practically none; never at "
         "m = 0) or undecided. Round-off never decides, at zero as at ±m: differences all within round-off of zero "
         f"({sci(ROUND_OFF_TIE)} of the values' magnitude; "
         f"{_TIE_ULPS} epsilons of float32/float16 runs) are a tie, and an interval end within round-off of ±m is "
         "the margin. \"A is lower\" is reproduced when lower, contradicted when higher, not "
         "distinguishable when equivalent or undecided; \"A is higher\" mirrors it; \"no effect\" is reproduced when "
         "equivalent, contradicted when lower or higher, not distinguishable when undecided. The same margin decides "
         "\"better\", \"worse\" and \"no effect\"."),
    Rule("R3", "heavy tails",
         "A statistic that is infinite or undefined is never \"not distinguishable\". If one method's mean is "
         "infinite (a run gives an infinite value, or the record states the closed-form reason) and the other's "
         "is finite, the claim's own criterion decides: the infinite mean is the higher. If both means are "
         f"infinite, the median difference and its distribution-free {_PCT} interval decide against R2's margin, "
         "runs infinite in both left out; when that median is undefined (fewer than 6 runs, or middle values −∞ "
         "and +∞) or infinite with an interval on both sides of zero, the claim cannot be checked on this evidence. "
         "Otherwise the mean decides (R2), "
         "whatever the tail: a heavy tail (Hill tail index of "
         f"the differences below {HEAVY_TAIL_INDEX:g}, or {DOMINANCE_SHARE:.0%} of the runs carrying half of "
         f"Σ|A − B|; tested from {HEAVY_TAIL_MIN_RUNS} runs up) is shown beside the status with the median "
         "difference and the share of runs in which A lies on the claimed side, and the reseeding sweep "
         "re-derives the status at ten times the runs. A tail estimate never changes the statistic that decides "
         "(finite draws cannot show an infinite variance)."),
    Rule("R4", "power",
         f"Every reading of a stochastic record runs at least as many runs as its primary reading and at least "
         f"{MIN_RUNS}; a reading with fewer is marked underpowered and not counted."),
    Rule("R5", "readings",
         "The status is the primary reading's. \"The claim holds under k of n other readings\" counts only readings of the "
         "source's open choices; reseeds, settings outside the claim's scope, stand-ins for undefined "
         "baselines, explanations of a discrepancy and readings that cannot be checked are shown apart. "
         "\"Reproduced\" becomes \"reproduced under "
         "stated assumptions\" when the record states assumptions or a counted reading does not reproduce it."),
    Rule("R6", "stress tests",
         "A stress test applied to one method of a comparison is applied to every compared method; evidence in "
         "which the methods ran under different conditions is refused."),
    Rule("R7", "undefined baselines",
         "A comparison with a method the source names but never defines cannot be checked on the source's "
         "account; the book's stand-ins for it are shown as readings, never counted."),
    Rule("R8", "whose claim",
         "Only a claim the source prints can be its main finding, appear under \"the source claims\" or in the "
         "errata. The book's reading of the source's purpose (implied) and the book's own questions (book) are "
         "shown as the book's questions."),
    Rule("R9", "groups, exact values, no data",
         "A claim about every member of a group holds iff it holds for each (contradicted if any member's is, "
         "otherwise cannot be checked if any member's cannot be, otherwise not distinguishable); a mathematical "
         "claim is reproduced iff it holds, otherwise "
         "contradicted; a claim that one method is better than another on a quantity computed exactly (a "
         "closed-form error, an operation count) is judged as R2 with a zero-width interval, against the same "
         "practical margin; a claim the source gives too little to compute cannot be checked, with the reason. "
         "A printed number that no program of the stated scenario can give, under any reading of its open "
         "choices (an arithmetic impossibility), is judged as a mathematical claim here; a printed number some "
         "reading could give is judged by R1."),
)

Region = Literal["lower", "higher", "equivalent", "undecided"]
Direction = Literal["less", "greater", "equal"]


@dataclass(frozen=True)
class Judgement:
    """What the rulebook decided for one piece of paired evidence, and on what.

    Attributes
    ----------
    status : str
        One of :data:`STATUSES`.
    rule : str
        The rule that decided (``"R2"``, ``"R3"``).
    statistic : {"mean", "median", "infinite mean"}
        What was placed against the margin.
    estimate, low, high : float
        The statistic's estimate and its 95 % interval (infinite when a mean is infinite; NaN when the
        median difference is undefined under R3, with status "cannot be checked").
    margin : float
        The practical margin m (units of the quantity).
    region : str
        ``"lower"``, ``"higher"``, ``"equivalent"`` or ``"undecided"``.
    runs : int
        Paired runs.
    share : float
        Share of runs in which A lies on the claimed side of B (higher for a "greater" claim, lower
        otherwise; ties excluded from the numerator).
    share_low, share_high : float
        Clopper-Pearson 95 % interval of ``share``.
    tail_index : float
        Hill tail index of the absolute differences; ``inf`` when there is no tail to estimate: 10 or fewer
        finite differences, or degenerate runs whose top differences are all equal (``a is b``, every
        difference the same), as :func:`hill_tail_index` documents.
    heavy : bool
        Whether R3's heavy-tail diagnostic fired (shown beside the status; it does not change the statistic
        unless both means are infinite).

    Raises
    ------
    ValueError
        A field outside its vocabulary (``status``, ``rule``, ``statistic``, ``region``); ``runs`` below 2; a
        share outside [0, 1]; ``margin`` negative or not finite; a NaN ``estimate``, ``low`` or ``high``
        with another status than "cannot be checked" (an undefined statistic decides nothing, R3).
    TypeError
        A text field that is not a str, ``heavy`` not a bool, a number field that is not a real number.
    """

    status: str
    rule: str
    statistic: str
    estimate: float
    low: float
    high: float
    margin: float
    region: str
    runs: int
    share: float
    share_low: float
    share_high: float
    tail_index: float
    heavy: bool

    def __post_init__(self) -> None:
        text_fields(self, "status", among=STATUSES)  # plain texts (rule 19)
        text_fields(self, "rule", among=("R2", "R3"))
        text_fields(self, "statistic", among=("mean", "median", "infinite mean"))
        text_fields(self, "region", among=("lower", "higher", "equivalent", "undecided"))
        values: dict[str, float] = {"runs": count(self.runs, "runs", minimum=2)}
        flag(self.heavy, "heavy")
        values.update((k, _real_number(getattr(self, k), k)) for k in
                      ("estimate", "low", "high", "margin", "share", "share_low", "share_high", "tail_index"))
        for k, v in values.items():  # the plain int and floats read, never the caller's object (fuzz 29a C1: a 0-d
            if type(getattr(self, k)) is not type(v):  # array was stored, aliased and writable after the checks)
                object.__setattr__(self, k, v)
        if not (math.isfinite(values["margin"]) and values["margin"] >= 0):
            raise ValueError(f"margin must be a finite number >= 0, got {values['margin']}")
        for k in ("share", "share_low", "share_high"):
            if not 0.0 <= values[k] <= 1.0:
                raise ValueError(f"{k} must lie in [0, 1], got {values[k]}")
        undefined = [k for k in ("estimate", "low", "high") if math.isnan(values[k])]
        if undefined and self.status != "cannot be checked":
            raise ValueError(f"{undefined[0]} is NaN: an undefined statistic gives the status 'cannot be checked' "
                             f"(R3), got status {shown(self.status)}")


def hill_tail_index(x: ArrayLike) -> float:
    r"""Hill's estimate of the tail index of :math:`|x|`.

    .. math:: \hat\alpha = \Big(\frac1k\sum_{i=1}^{k}\ln\frac{x_{(i)}}{x_{(k+1)}}\Big)^{-1},

    with :math:`x_{(1)}\ge x_{(2)}\ge\dots` the ordered :math:`|x|` and :math:`k=\max(10,\lceil\sqrt n\rceil)`.
    A tail index below 2 means the variance does not exist; below 1, the mean.

    Parameters
    ----------
    x : array_like, shape (n,)
        Finite values, n > 10, of any magnitude (the estimator reads only logarithms of ratios, so the
        1e150 cap of the shared validation's rule 2 does not apply: differences of two capped values
        reach 2e150).

    Returns
    -------
    float
        :math:`\hat\alpha`; ``inf`` when the (k+1)-th largest absolute value is zero or every top value is equal (no tail).

    Raises
    ------
    ValueError
        ``x`` has 10 values or fewer (the estimate needs n > 10: k = 10 top values above the (k+1)-th), or a value
        that is not finite.

    References
    ----------
    Hill (1975), *Ann. Statist.* 3(5), 1163-1174.
    """
    v = np.abs(_numeric(x, "x").ravel())
    if v.size <= 10:
        raise ValueError(f"x must hold more than 10 values, got {v.size}")
    if not np.all(np.isfinite(v)):
        raise ValueError("x must be finite")
    k = max(10, math.ceil(math.sqrt(v.size)))
    k = min(k, v.size - 1)
    top = np.sort(v)[::-1][: k + 1]
    if top[k] <= 0.0:
        return math.inf
    with np.errstate(over="ignore"):
        ratio = top[:k] / top[k]   # exact under a power-of-two scale (the estimate is scale-free to the bit)
    if np.isfinite(ratio[0]):
        s = float(np.mean(np.log(ratio)))
    else:                          # the largest ratio overflows (1e308 over 1e-308): differences of logarithms
        s = float(np.mean(np.log(top[:k]) - np.log(top[k])))
    return math.inf if s <= 0.0 else 1.0 / s


def median_interval(d: ArrayLike, level: float = CONFIDENCE_LEVEL) -> tuple[float, float, float]:
    """Median of ``d`` and its distribution-free interval from order statistics.

    The interval is :math:`[d_{(j)}, d_{(n+1-j)}]` with j the largest index such that
    :math:`P(B \\le j-1) \\le (1-\\text{level})/2` for :math:`B\\sim\\mathrm{Bin}(n, 1/2)`: it covers the median
    with probability at least ``level`` whatever the distribution.

    Parameters
    ----------
    d : array_like, shape (n,)
        Values (infinite values allowed; NaN refused), n >= 6, and at least as many as ``level`` needs: the
        widest interval, ``[min, max]``, covers the median with probability :math:`1 - 2\\cdot 2^{-n}`, so a
        ``level`` above 0.96875 needs more than 6 values (0.99: 8; 0.999: 11; see :func:`median_values_needed`).
    level : float
        Coverage, in (0, 1).

    Returns
    -------
    median, low, high : float
        The median of ``d`` and the order statistics that bound it at ``level`` (values sorted, infinite ones kept).

    Raises
    ------
    ValueError
        ``d`` holds NaN, fewer than 6 values or fewer than ``level`` needs (no order statistic covers the median
        with probability ``level``; fuzz 40b C10: ``[min, max]`` of 6 values was returned at 0.99, coverage
        0.969), or a finite value beyond the representable range; or its
        median is undefined: n is even and the two middle values are ``-inf`` and ``+inf`` (their mean is
        not a number, and no other value is the median; :func:`judge_paired` gives such evidence the
        status "cannot be checked" under R3 instead of calling this).
    """
    v = np.sort(_numeric(d, "d").ravel())
    level = scalar(level, "level", 0.0, 1.0, lo_open=True, hi_open=True)
    need = median_values_needed(level)
    if v.size < need:
        raise ValueError(f"d must hold at least {need} values" + (f" for level {shown(level)}" if need > 6 else "")
                         + f", got {v.size}")
    if np.any(np.isnan(v)):
        raise ValueError("d must not hold NaN")
    check_magnitude(v[np.isfinite(v)], "d")  # infinite values allowed; finite ones in range (a median averages two)
    n = v.size
    alpha = (1.0 - level) / 2.0
    j = int(stats.binom.ppf(alpha, n, 0.5))  # P(B <= j) >= alpha
    while j > 0 and stats.binom.cdf(j - 1, n, 0.5) > alpha:
        j -= 1
    j = max(j, 1)   # j >= 1 holds already: n >= median_values_needed(level) gives P(B <= 0) = 2**-n <= alpha
    if _median_undefined(v):
        raise ValueError(f"d has no median: its two middle values are -inf and +inf ({n} values)")
    return float(np.median(v)), float(v[j - 1]), float(v[n - j])


def median_values_needed(level: float = CONFIDENCE_LEVEL) -> int:
    """The fewest values :func:`median_interval` takes at ``level``: at least 6, and the smallest n whose widest
    interval ``[min, max]`` covers the median with probability at least ``level`` (:math:`2^{-n} \\le
    (1 - \\text{level})/2`).

    Parameters
    ----------
    level : float
        Coverage, in (0, 1).

    Returns
    -------
    int
        6 up to ``level`` 0.96875 (the book's 0.95 included), then 7, 8 (0.99), ... 11 (0.999).

    Raises
    ------
    TypeError, ValueError
        ``level`` not a number in (0, 1).
    """
    level = scalar(level, "level", 0.0, 1.0, lo_open=True, hi_open=True)
    alpha, n = (1.0 - level) / 2.0, 6
    while 0.5 ** n > alpha:   # alpha >= 2**-54 (level < 1 is a float), so at most ~50 steps
        n += 1
    return n


def _median_undefined(v: np.ndarray) -> bool:
    """Whether the sorted values ``v`` (even count) have ``-inf`` and ``+inf`` as their two middle values."""
    n = v.size
    return n % 2 == 0 and bool(np.isneginf(v[n // 2 - 1]) and np.isposinf(v[n // 2]))


def share_interval(wins: int, runs: int, level: float = CONFIDENCE_LEVEL) -> tuple[float, float, float]:
    """Share of runs won and its Clopper-Pearson interval.

    Parameters
    ----------
    wins, runs : int
        0 <= wins <= runs, runs >= 1.
    level : float

    Returns
    -------
    share, low, high : float
        ``wins / runs`` and its two-sided Clopper-Pearson interval at ``level``, all between 0 and 1.
    """
    runs = count(runs, "runs")
    wins = count(wins, "wins", minimum=0)
    level = scalar(level, "level", 0.0, 1.0, lo_open=True, hi_open=True)
    if wins > runs:
        raise ValueError(f"wins must be <= runs, got wins={wins}, runs={runs}")
    low, high = _clopper_pearson(int(wins), int(runs), float(level))
    return wins / runs, low, high


@functools.lru_cache(maxsize=8192)
def _clopper_pearson(wins: int, runs: int, level: float) -> tuple[float, float]:
    """The exact (Clopper-Pearson) interval of ``wins`` of ``runs`` at ``level``, computed once per argument triple.

    scipy finds each bound by a root search (about 2 ms); a chapter's judgements ask for a few hundred distinct
    triples (runs is the study's run count, wins at most runs + 1 values) thousands of times (issue 37).
    """
    ci = stats.binomtest(wins, runs).proportion_ci(level, method="exact")
    return float(ci.low), float(ci.high)


def region(low: float, high: float, margin: float, *, scale: float = 0.0) -> Region:
    """Where an interval lies against zero and the practical margin (R2).

    Round-off never decides (R2), at the margin's edge as at zero: an interval end within round-off of
    ``+margin`` or ``-margin`` (``|end -/+ m| <= 1e-9 S``, ``fusion._limits.ROUND_OFF_TIE``, with S the comparison's
    scale: ``scale``, at least ``margin``) is the margin and is snapped to it. Then the margin is the largest
    difference that is practically none: for a positive margin an interval wholly inside the closed [−m, m] is
    ``"equivalent"`` (an end exactly at ±m included). At margin 0 no interval is ``"equivalent"`` and no end is
    snapped (a tie at zero is the caller's rule: :func:`judge_paired` and
    :meth:`fusion.book.exact.ExactComparison.region` judge it ``"undecided"``).

    Parameters
    ----------
    low, high : float
        The interval, low <= high (infinite ends allowed).
    margin : float
        m >= 0.
    scale : float
        The magnitude S >= 0 of the values compared (keyword; :func:`judge_paired` passes the largest finite
        magnitude of its runs, :class:`~fusion.book.exact.ExactComparison` ``max(|A|, |B|)``); S is taken as at least
        ``margin``, so the default 0 snaps the ends within a relative 1e-9 of the margin itself.

    Returns
    -------
    {"lower", "higher", "equivalent", "undecided"}
        ``"equivalent"`` inside the closed [−margin, margin] for a positive margin (after the snap), ``"lower"`` below
        0, ``"higher"`` above 0, else ``"undecided"``.
    """
    return _region(low, high, margin, scale, _TIE)


def _region(low: float, high: float, margin: float, scale: float, share: float) -> Region:
    """:func:`region` with the tie ``share`` of S (:func:`_tie_share`: 1e-9, or a few epsilons of short floats)."""
    low, high = (float(a) if a.ndim == 0 else math.nan for a in (_numeric(low, "low"), _numeric(high, "high")))
    margin = scalar(margin, "margin", 0.0)
    scale = scalar(scale, "scale", 0.0)
    if not (low <= high):
        raise ValueError(f"low and high must be numbers with low <= high, got [{low}, {high}]")
    if margin > 0:
        tie = share * max(scale, margin)  # R2: round-off never decides, at the margin's edge as at zero
        low, high = (math.copysign(margin, x) if abs(abs(x) - margin) <= tie else x for x in (low, high))
        if -margin <= low and high <= margin:
            return "equivalent"
    if high < 0:
        return "lower"
    if low > 0:
        return "higher"
    return "undecided"


def status_from_region(where: Region, direction: Direction) -> str:
    """The status of a claim ("A less", "A greater" or "equal") given the interval's region (R2).

    Parameters
    ----------
    where : {"lower", "higher", "equivalent", "undecided"}
    direction : {"less", "greater", "equal"}

    Returns
    -------
    str
        ``"reproduced"`` (the region the direction claims), ``"contradicted"`` (the opposite one) or
        ``"not distinguishable"``.
    """
    where = text(where, "where")
    direction = text(direction, "direction")
    if where not in ("lower", "higher", "equivalent", "undecided"):
        raise ValueError(f"where must be 'lower', 'higher', 'equivalent' or 'undecided', got {shown(where)}")
    if direction not in ("less", "greater", "equal"):
        raise ValueError(f"direction must be 'less', 'greater' or 'equal', got {shown(direction)}")
    if direction == "equal":
        return {"equivalent": "reproduced", "lower": "contradicted", "higher": "contradicted"}.get(
            where, "not distinguishable")
    good, bad = ("lower", "higher") if direction == "less" else ("higher", "lower")
    return "reproduced" if where == good else "contradicted" if where == bad else "not distinguishable"


def _dominated(d: np.ndarray) -> bool:
    a = np.abs(d[np.isfinite(d)])
    total = float(a.sum())
    if total == 0.0:
        return False
    top = np.cumsum(np.sort(a)[::-1])
    k = int(np.searchsorted(top, 0.5 * total)) + 1
    return k <= max(1, int(d.size * DOMINANCE_SHARE))


def _paired_runs(a: ArrayLike, b: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """``a`` and ``b`` as float arrays of paired per-run values: 1-D, the same length (>= 2), finite or ``+inf``.

    The one check of paired evidence, shared by :func:`judge_paired` and the ledger's ``Comparison``:
    ValueError naming ``a``/``b`` for a 2-D array (documented shape ``(runs,)``: a table is not ravelled into
    runs), different lengths, fewer than 2 runs, NaN, ``-inf`` or a finite value beyond the representable range.
    """
    av, bv = _numeric(a, "a"), _numeric(b, "b")
    for name, v in (("a", av), ("b", bv)):
        if v.ndim != 1:
            raise ValueError(f"{name} must be 1-D, shape (runs,), got shape {v.shape}")
    if av.shape != bv.shape or av.size < 2:
        raise ValueError(f"a and b must hold the same number (>= 2) of paired runs, got {av.size} and {bv.size}")
    for name, v in (("a", av), ("b", bv)):
        if np.any(np.isnan(v)) or np.any(np.isneginf(v)):
            raise ValueError(f"{name} must be finite or +inf (a run whose statistic is infinite), not NaN or -inf")
        check_magnitude(v[np.isfinite(v)], name)  # +inf is a run's infinite statistic (R3); finite values in range
    return av.astype(float), bv.astype(float)


def _margin_type(value: object, name: str) -> None:
    """One type rule for a comparison's ``margin`` and ``relative_margin`` (:class:`Comparison`, ``ExactComparison``,
    their ``with_margin``; fuzz 22a D3): None, an int or a float (NumPy's included); a bool, a 0-d array, a Decimal
    or text is a TypeError naming ``name``. Their values are checked by the caller."""
    from fusion._validation import is_integer
    if value is not None and not (is_integer(value) or isinstance(value, (float, np.floating))):
        raise TypeError(f"{name} must be a finite number >= 0, got {type(value).__name__} {shown(value, 60)}")


def _margins(margin: object, relative_margin: object) -> None:
    """One check of a comparison's ``margin`` and ``relative_margin`` (:class:`Comparison`, its ``with_margin``, and
    ``Conjunction.with_margin`` whatever its members; fuzz 34a D3): ``_margin_type``, then a finite number >= 0 (an
    int beyond the float range is not finite) within rule 2's range (at most 1e150, not subnormal: the judgement's
    check of the margin, fuzz 49b C3), else ValueError naming it."""
    for name, v in (("margin", margin), ("relative_margin", relative_margin)):
        _margin_type(v, name)  # a type (rule 6), one rule with ExactComparison's
        if v is None:
            continue
        try:
            f = float(v)  # type: ignore[arg-type]
        except OverflowError:
            f = math.inf
        if not math.isfinite(f) or f < 0:
            raise ValueError(f"{name} must be a finite number >= 0, got {shown(v, 60)}")
        scalar(f, name, 0.0)  # rule 2: at most 1e150, not subnormal (the judgement's own check of a margin)


def _two_methods(a_name: str, b_name: str) -> None:
    """A comparison's two names differ (:class:`Comparison`, ``ExactComparison``; fuzz 22a D4): its summary and
    verdict name A and B by them, and "A 0.0153 vs A 0.2153" says nothing of which is which."""
    if a_name.strip() == b_name.strip():
        raise ValueError(f"b_name must differ from a_name (the summary tells A from B by their names), got "
                         f"{shown(a_name)} for both")


def _practical_margin(margin: float | None, relative_margin: float | None, ref: float,
                      on: str) -> tuple[float, float | None]:
    """The margin a comparison stores and the relative margin it keeps: one rule for :class:`Comparison` and
    ``ExactComparison`` (their constructors, ``with_margin`` and :func:`dataclasses.replace`).

    ``margin`` None: ``relative_margin`` (default :data:`DEFAULT_RELATIVE_MARGIN`) times ``ref`` (0 when ``ref`` is
    not finite), ``relative_margin`` kept; a derived margin beyond 1e150, subnormal (the range the judgement
    checks) or 0 by underflow (a positive ``relative_margin`` of a finite non-zero ``ref``) is a ValueError naming
    ``relative_margin``. Both given: they must agree (a copy passes both), else
    ValueError naming both; ``margin`` stored, ``relative_margin`` dropped. The caller has checked each is a finite
    number >= 0 (or None).
    """
    rel = DEFAULT_RELATIVE_MARGIN if relative_margin is None else float(relative_margin)
    derived = rel * ref if math.isfinite(ref) else 0.0
    if margin is None:
        try:   # the judgement's check of the margin (rule 2), here naming the argument that gives it (fuzz 49b C3:
            scalar(derived, "margin", 0.0)   # 1e145 of a mean of 1e10 was stored, then every status() refused
            if derived == 0.0 and rel > 0.0 and ref != 0.0 and math.isfinite(ref):   # a product that underflowed to
                raise ValueError("underflow")                                         # 0 (fuzz 50b D4): not asked for
        except ValueError:                   # naming margin, which the caller never gave)
            raise ValueError(f"relative_margin = {shown(rel, 60)} gives the margin {derived:.3g} on {on} (whose "
                             f"magnitude is {ref:.3g}), outside the representable range (at most 1e150, not "
                             f"subnormal): give a {'smaller' if abs(derived) > 1.0 else 'larger'} relative_margin "
                             "or an absolute margin") from None   # too small by underflow: larger (fuzz 54a D2)
        return derived, relative_margin
    if relative_margin is not None and not math.isclose(float(margin), derived, rel_tol=1e-12):
        raise ValueError(f"margin = {shown(margin, 60)} and relative_margin = {shown(relative_margin, 60)} "
                         f"disagree (relative_margin gives {derived:.6g} on {on}): give one of them")
    return float(margin), None


def _infinite_mean(value: object) -> tuple[str, ...]:
    """``infinite_mean`` as a tuple of ``"a"``/``"b"``: a sequence (a list or tuple; a str is refused, ``"ab"``
    is not read as two methods), TypeError naming ``infinite_mean`` otherwise."""
    items = tuple(sequence(value, "infinite_mean"))
    if not all(isinstance(x, str) for x in items):
        raise TypeError(f"infinite_mean must hold the strings 'a' or 'b', got {shown(items)}")
    if any(x not in ("a", "b") for x in items):
        raise ValueError(f"infinite_mean must name 'a' or 'b', got {shown(items)}")
    return items


def _differences(av: np.ndarray, bv: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The paired differences A − B (0 in a run where both are infinite: undefined, a tie) and each run's scale
    (the larger finite magnitude of A and B), for the tie rule of :func:`_runs_won`."""
    both = np.isinf(av) & np.isinf(bv)
    with np.errstate(invalid="ignore"):
        d = av - bv
    scale = np.maximum(np.abs(np.where(np.isfinite(av), av, 0.0)), np.abs(np.where(np.isfinite(bv), bv, 0.0)))
    return np.where(both, 0.0, d), scale


#: Relative size of round-off: a difference within this share of the values' magnitude is a tie (the one tie rule).
_TIE = ROUND_OFF_TIE  # fusion._limits: one tie rule for the rulebook and the rankings


def _tie_share(*given: object) -> float:
    """R2's tie, as a share of the values' magnitude S: :data:`ROUND_OFF_TIE` (1e-9), or :data:`_TIE_ULPS` machine
    epsilons of the coarsest float32/float16 dtype of the values as given (``fusion._validation.input_eps``: an array's
    dtype, a list's numpy scalars'), whichever is larger, so that a one-ulp float32 difference is a tie (fuzz 30a C3).
    Every float64 value keeps 1e-9."""
    return max(_TIE, _TIE_ULPS * max(input_eps(g) for g in given))


def _round_off(x: np.ndarray | float, scale: np.ndarray | float, share: float = _TIE) -> np.ndarray | bool:
    """Whether ``x`` is within round-off of zero for values of magnitude ``scale``: |x| <= 1e-9 scale (finite ``x``).

    The one tie rule of the rulebook, relative so that no judgement depends on the data's units: a run's tie
    (:func:`_runs_won`, its own scale), and in :func:`judge_paired` every run a tie and constant differences
    (the comparison's scale, the largest finite magnitude of its runs)."""
    x = np.asarray(x)
    return np.isfinite(x) & (np.abs(x) <= share * np.asarray(scale))


def _runs_won(av: np.ndarray, bv: np.ndarray, direction: str, share: float = _TIE) -> np.ndarray:
    """Per run, whether A lies on the claimed side of B (above for ``"greater"``, else below): the numerator of the
    share of runs won (R3). A tie is never a win: a run whose difference is within round-off of zero
    (|A − B| <= 1e-9 max(|A|, |B|), finite values, :func:`_round_off`) or undefined (both infinite). The one tie
    rule of :func:`judge_paired` and of the chapters' sign tests (``fusion.book.chapters.lecture_wavelets``)."""
    d, scale = _differences(av, bv)
    tie = _round_off(d, scale, share)
    return ((d > 0) if direction == "greater" else (d < 0)) & ~tie


def judge_paired(a: ArrayLike, b: ArrayLike, direction: Direction, margin: float,
                 infinite_mean: Sequence[str] = ()) -> Judgement:
    """Judge paired per-run values of A and B by rules R2 and R3.

    When both means are infinite (R3), a run in which both values are infinite has no difference
    (``inf - inf`` is undefined) and is left out of the median; the median difference is undefined
    when fewer than 6 runs are left or the two middle differences are ``-inf`` and ``+inf``. Such evidence
    cannot decide the claim and is never "not distinguishable" (R3): the status is "cannot be checked",
    statistic "median", estimate and interval NaN, region "undecided". An infinite median difference decides
    the claim by its sign when its interval lies on one side of zero (region "higher" or "lower"); when its
    interval does not, and whenever the interval is [-inf, inf], the status is "cannot be checked" (region
    "undecided", the estimate and interval as computed).

    Round-off never decides (R2), whatever the units of ``a`` and ``b``: with S the largest finite magnitude
    of their runs, differences all within round-off of zero (``|A - B| <= 1e-9 S``, the tie rule of a single run)
    are a tie, estimate and interval 0; differences equal to each other within round-off (their range
    <= 1e-9 S) are deterministic, and the interval is the zero-width [mean, mean]. Both tests are relative to
    S, so scaling ``a``, ``b`` and ``margin`` by one factor scales the estimate and interval and leaves the
    status and region unchanged (exactly for a power of two). S is the values' magnitude, not the differences':
    the round-off of A − B grows with ``|A|`` and ``|B|``, so a common offset of ``a`` and ``b`` (differences unchanged
    mathematically) can make differences spread by less than 1e-9 S constant (zero-width interval). At the margin's
    edge as at zero: an interval end within round-off of ``+margin`` or ``-margin`` (``|end -/+ m| <= 1e-9 S``, S at
    least m) is the margin, and an interval wholly inside the closed [-m, m] is "equivalent" (:func:`region`), so
    ``0.3 - 0.2`` and ``1.3 - 1.2`` against a margin of 0.1 get one status. Runs given as float32 or float16 (an
    array, or a list of such numpy scalars) are decided by their own round-off: the tie share is then 4 epsilons of
    their dtype (4.8e-7 for float32) where larger than 1e-9 (fuzz 30a C3); float64 runs keep 1e-9.

    Parameters
    ----------
    a, b : array_like, shape (runs,)
        Per-run values on the same runs; +inf allowed (a run whose statistic is infinite), NaN refused.
    direction : {"less", "greater", "equal"}
        What the claim says of A against B.
    margin : float
        Practical margin m >= 0 in the quantity's units.
    infinite_mean : sequence of {"a", "b"}
        Methods whose population mean the evidence shows to be infinite by a closed-form argument (a list or
        tuple; a string is refused).

    Returns
    -------
    Judgement
        The status with the rule and statistic that decided it, the estimate and its interval, the margin, region, runs,
        share of runs won (with interval) and tail index.

    Raises
    ------
    ValueError
        ``a`` or ``b`` is not 1-D, they differ in length or hold fewer than 2 runs, or hold NaN, ``-inf`` or a
        value beyond the representable range; ``margin`` < 0 or not finite; ``direction`` or an entry of
        ``infinite_mean`` is not one of its values.
    TypeError
        ``direction`` is not a str; ``infinite_mean`` is not a sequence of str.
    """
    a, b = read_once(a, "a"), read_once(b, "b")  # converted once: checked, and their dtype read (fuzz 33a C7)
    av, bv = _paired_runs(a, b)
    return _judge(av, bv, direction, margin, infinite_mean, _tie_share(a, b))


def _judge(av: np.ndarray, bv: np.ndarray, direction: Direction, margin: float, infinite_mean: Sequence[str],
           tie: float) -> Judgement:
    """:func:`judge_paired` of checked runs (:func:`_paired_runs`) with the tie share ``tie`` of their dtype as given."""
    margin = scalar(margin, "margin", 0.0)
    direction = text(direction, "direction")
    if direction not in ("less", "greater", "equal"):
        raise ValueError(f"direction must be 'less', 'greater' or 'equal', got {shown(direction)}")
    infinite_mean = _infinite_mean(infinite_mean)
    n = av.size
    inf_a = "a" in infinite_mean or bool(np.any(np.isinf(av)))
    inf_b = "b" in infinite_mean or bool(np.any(np.isinf(bv)))
    both = np.isinf(av) & np.isinf(bv)  # runs whose difference is undefined (inf - inf)
    d, scale = _differences(av, bv)
    wins = int(np.sum(_runs_won(av, bv, direction, tie)))
    share, s_lo, s_hi = share_interval(wins, n)
    finite = np.isfinite(d)
    tail = hill_tail_index(d[finite]) if finite.sum() > 10 else math.inf

    def out(status: str, rule: str, stat: str, est: float, lo: float, hi: float, where: str, heavy: bool) -> Judgement:
        return Judgement(status, rule, stat, est, lo, hi, float(margin), where, n, share, s_lo, s_hi, tail, heavy)

    if inf_a != inf_b:  # R3: the claim's own criterion decides when one mean is infinite
        where: Region = "higher" if inf_a else "lower"
        est = math.inf if inf_a else -math.inf
        return out(status_from_region(where, direction), "R3", "infinite mean", est, est, est, where, True)
    scale_all = float(np.max(scale)) if scale.size else 0.0  # S: the largest finite magnitude of the runs
    if inf_a and inf_b:  # R3: both means infinite: the median and its distribution-free interval decide
        defined = np.sort(d[~both])
        if defined.size < 6 or _median_undefined(defined):  # R3: an undefined statistic is never "not distinguishable"
            return out("cannot be checked", "R3", "median", math.nan, math.nan, math.nan, "undecided", True)
        med, lo, hi = median_interval(defined)
        where = _region(lo, hi, margin, scale_all, tie)
        if (math.isinf(med) or (math.isinf(lo) and math.isinf(hi))) and where not in ("lower", "higher"):
            # R3: an infinite median decides only a sign its interval shows; [-inf, inf] decides nothing
            return out("cannot be checked", "R3", "median", med, lo, hi, "undecided", True)
        return out(status_from_region(where, direction), "R3", "median", med, lo, hi, where, True)
    if np.all(_round_off(d, scale_all, tie)):  # identical to round-off: a tie
        where = region(0.0, 0.0, margin) if margin > 0 else "undecided"
        return out(status_from_region(where, direction), "R2", "mean", 0.0, 0.0, 0.0, where, False)
    # R3: a heavy tail is reported (with the median and the share of runs won), never a switch of statistic
    heavy = n >= HEAVY_TAIL_MIN_RUNS and ((tail < HEAVY_TAIL_INDEX) or _dominated(d))
    mean = float(np.mean(d))
    if _round_off(np.ptp(d), scale_all, tie):  # differences equal to round-off: deterministic, a zero-width interval
        lo = hi = mean
    else:
        ci = stats.ttest_1samp(d, 0.0).confidence_interval(CONFIDENCE_LEVEL)
        lo, hi = float(ci.low), float(ci.high)
    where = _region(lo, hi, margin, scale_all, tie)  # R2: an end within round-off of +-m is the margin
    return out(status_from_region(where, direction), "R2", "mean", mean, lo, hi, where, heavy)


def _primary_runs(value: object) -> int | None:
    """The primary reading's run count (an integer >= 1) or None (a deterministic record); naming ``primary_runs``."""
    return None if value is None else count(value, "primary_runs")


def counted(kind: str, runs: int | None, primary_runs: int | None, status: str | None = None) -> tuple[bool, str]:
    """Whether a reading counts towards robustness (R4, R5), and why not.

    Parameters
    ----------
    kind : str
        One of :data:`READING_KINDS` (not ``"primary"``).
    runs, primary_runs : int or None
        Monte-Carlo runs of the reading and of the primary reading (None for a deterministic record).
    status : str, optional
        The reading's status: a reading that cannot be checked neither supports nor refutes the claim, so
        it is shown apart.

    Returns
    -------
    counted : bool
        True when the reading's kind counts and it has enough runs and a checkable status.
    why : str
        ``""`` when counted, else ``"underpowered"``, ``"cannot be checked"`` or the reading's kind.

    Raises
    ------
    ValueError
        ``kind`` is not a reading kind other than ``"primary"``; ``status`` is not one of :data:`STATUSES`;
        ``runs`` or ``primary_runs`` is below 1.
    TypeError
        ``kind`` or ``status`` is not a str; ``runs`` or ``primary_runs`` is neither an integer nor None.
    """
    kind = text(kind, "kind")  # the plain str (rule 19): matched and returned as its text
    if kind not in READING_KINDS or kind == "primary":
        raise ValueError(f"kind must be one of {READING_KINDS[1:]}, got {shown(kind)}")
    runs = None if runs is None else count(runs, "runs")
    primary_runs = _primary_runs(primary_runs)
    if status is not None:
        status = one_of(status, STATUSES, "status")
    if kind not in COUNTED_KINDS:
        return False, kind
    if runs is not None and runs < max(MIN_RUNS, primary_runs or 0):
        return False, "underpowered"
    if status == "cannot be checked":
        return False, "cannot be checked"
    return True, ""


#: Units of work (``fusion._limits.work``, about 10 ns each) of one reading :func:`record_status` checks and counts:
#: 6.1-6.6 us measured (CPU time, minimum of 3, 100,000 readings of each kind, shared machine), so the budget's edge
#: (1.4e6 readings) runs about 9 CPU-s (fuzz 45b C6: 10**7 readings, the sequence ceiling, ran ~70 CPU-s); a record
#: of the book has a handful.
_STATUS_READING = 700


def record_status(primary: str, readings: Sequence[tuple[str, str, int | None]], primary_runs: int | None,
                  assumptions: bool) -> tuple[str, int, int]:
    """A record's status from its primary reading's status and its other readings (R5).

    Parameters
    ----------
    primary : str
        The primary reading's status.
    readings : sequence of (kind, status, runs)
        Every other reading (a list triple, as JSON reads one back, is a triple).
    primary_runs : int or None
        Runs of the primary reading.
    assumptions : bool
        Whether the record states assumptions.

    Returns
    -------
    status : str
        ``primary``, or ``"reproduced under stated assumptions"`` when it reproduces but with assumptions or a counted
        reading that does not.
    agree : int
        Counted readings that reproduce the claim.
    total : int
        Counted readings.

    Raises
    ------
    ValueError
        ``primary`` or a reading's status is not one of :data:`STATUSES`; ``primary_runs`` is below 1 (checked
        even when there are no readings); a reading's kind or runs as :func:`counted` refuses them; more readings
        than the work budget checks (``_STATUS_READING`` units each), refused before any is read.
    TypeError
        ``readings`` is not a sequence of triples (tuples or lists); ``primary`` is not a str; ``assumptions`` is not a bool;
        ``primary_runs`` is neither an integer nor None.
    """
    flag(assumptions, "assumptions")
    primary_runs = _primary_runs(primary_runs)
    primary = text(primary, "primary")  # the plain str (rule 19): matched and returned as its text
    if primary not in STATUSES:
        raise ValueError(f"primary must be one of {STATUSES}, got {shown(primary)}")
    readings = read_once(readings, "readings")  # a Sequence class read once, as a list (fuzz 31a C4)
    items = () if isinstance(readings, (str, bytes)) else sequence(readings, "readings")
    work((len(items),), "readings", weight=_STATUS_READING)   # before any is read (fuzz 45b C6)
    if isinstance(readings, (str, bytes)) or not all(isinstance(x, (tuple, list)) and len(x) == 3 for x in items):
        raise TypeError(f"readings must be a sequence of (kind, status, runs) tuples, got {shown(readings)}")
    readings = [tuple(x) for x in readings]  # a list triple is a triple (readings read back from JSON are lists)
    if any(not isinstance(st, str) or str.__str__(st) not in STATUSES for _, st, _ in readings):
        raise ValueError(f"readings: every status must be one of {STATUSES}")
    # each text read as its plain str under its place in the caller's argument (rule 19; fuzz 32a C4)
    readings = [(text(k, f"readings[{i}][0]"), one_of(st, STATUSES, f"readings[{i}][1]"), r)
                for i, (k, st, r) in enumerate(readings)]
    good = ("reproduced", "reproduced under stated assumptions")
    flags = [counted(k, r, primary_runs, st)[0] for k, st, r in readings]
    total = sum(flags)
    agree = sum(f and s in good for f, (_, s, _) in zip(flags, readings))
    if primary == "reproduced" and (assumptions or agree < total):
        return "reproduced under stated assumptions", agree, total
    return primary, agree, total
