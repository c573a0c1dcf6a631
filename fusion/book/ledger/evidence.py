"""The evidence a record holds, and the status each kind gives by rule.

:class:`PublishedValues` (rule R1), :class:`Comparison` (paired interval, rules R2-R3),
:class:`Proposition` (a computed yes/no), :class:`Conjunction` (every member of a group) and
:class:`Unverifiable` (nothing to compute); :class:`fusion.book.exact.ExactComparison` is the sixth kind.
"""

from __future__ import annotations

import math
from collections import UserList
from collections.abc import Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike

from fusion._limits import entry_dtypes, inexact_integer, integer_entries, work, written_as
from fusion._nesting import ndim_of
from fusion._validation import integer
from fusion._validation import _numeric, _real_number, count, counts, seed as check_seed
from fusion._validation import one_of, read_once, shown
from fusion._validation import text
from fusion.book import rulebook as R
from fusion.book._few_runs import FewRunsError
from fusion.book._json import JSONObject
from fusion.book.exact import ExactComparison
from fusion.book.ledger.statuses import MIN_RUNS, _text, _texts, fmt, text_fields
from fusion.book.tables import _roundings

__all__ = [
    "PublishedValues",
    "Comparison",
    "Proposition",
    "Conjunction",
    "Unverifiable",
]


# --------------------------------------------------------------------------- evidence
#: Float32/float16 ulps a published value of that dtype may lie from its printed decimal (``0.789 * 100`` in float32
#: is one float32 ulp from 78.9, fuzz 27a F1).
_SHORT_ULPS = 2


def _decimal_fault(p: float, d: int, dtype: np.dtype) -> str | None:
    """Why the published value ``p`` (of ``dtype``) is not a decimal of ``d`` decimals (R1), or None when it is.

    The rule (fuzz 24a D5, fuzz 26a D1, fuzz 27a F1/F5): ``p`` is the printed decimal ``q = round(p, d)`` up to the
    round-off of its own dtype, never a fixed relative share (a relative 2⁻²³ of 1234567.85 is 0.15, which let an
    extra decimal through above about 4e5).

    * A float32 or float16 value (an array or Series of that dtype) may lie ``_SHORT_ULPS`` ulps of its dtype from
      ``q`` (a value computed in float32 is the decimal it prints at float32 precision), but less than half a
      printed step (a value halfway between two printed decimals has an extra decimal). The dtype "cannot hold" the
      value at ``d`` decimals when its spacing there exceeds the printed step ``10**-d``: two neighbouring printed
      decimals may then round to one value of the dtype (float32 98765.4321 is 98765.4297, spacing 7.8e-3 > 1e-4;
      float16 2048, spacing 2, is also 2049 rounded), and the value is refused by name. An exact integer of the
      dtype's integer range (float32 1e7, float16 1000: spacing at most 1) holds 0 decimals (fuzz 28a C4: an
      allowance of 2 ulps reaching the neighbour refused them). At float16's largest value the spacing is infinite
      (refused, without numpy's overflow warning: fuzz 28a D3).
    * A float64 value (any dtype but an integer one) cannot hold ``d`` decimals by the same spacing rule
      (``2.0**53`` at 1 decimal, spacing 2; fuzz 30a C2). Otherwise it may lie a few float64 ulps from ``q``
      (``0.1 * 3``, ``12.3 / 100``), be the float32 nearest ``q`` (``float(np.float32(0.3))``), or be a float32
      number that the float32 rule accepts (a float32 product converted to float); anything else is "extra".
    """
    q = round(p, d)
    short = dtype.kind == "f" and dtype.itemsize < 8
    step = 10.0 ** -d
    if dtype.kind not in "iu":  # an integer array's values are exact (those float64 cannot hold: refused before)
        with np.errstate(over="ignore"):  # float16 65504: its spacing overflows to inf (refused below)
            spacing = float(np.spacing(abs((dtype if short else np.dtype(np.float64)).type(p))))
        if spacing > step:  # float64 too (fuzz 30a C2): 1234567890123456.78 at 2 decimals is ...456.75
            return "cannot hold"
    if short:
        off = abs(p - q)
        return None if off <= _SHORT_ULPS * spacing and off < step / 2 else "extra"
    if written_as(p, q):   # the package's one rule for float64 (fusion._limits.written_as)
        return None
    if float(np.float32(p)) == p and _decimal_fault(p, d, np.dtype(np.float32)) is None:
        return None
    return "extra"


#: Work units of one value of :class:`PublishedValues`: its constructor's Python-level checks (``_decimal_fault``,
#: ``integer_entries``, ``entry_dtypes``) and one ``matches`` (``_rounds_to``, computed once), at their costliest.
#: Measured (CPU time, minimum of 3, 200,000 values, shared machine with other jobs): constructor 2.2 us a value of a
#: float64 array, 3.4 us of a list of floats; ``matches`` 0.7 us a value that matches, 3.5 us one that does not
#: (``_roundings``); ``to_dict`` 0.05 us more. So 700 units (7 us): the budget's edge, 1.4e6 values, runs about
#: 4-11 CPU-s (300,000 values that do not match, from a list, with two ``status()``, a ``summary()`` and a
#: ``to_dict()``: 2.2 CPU-s; fuzz 49b C2: 2**25 values, the input ceiling, ran 82 CPU-s and 26 more for each ``status()``); a
#: published table of the book has a few dozen.
_PUBLISHED_VALUE = 700


def _length(values: Any) -> int:
    """The number of entries of a 1-D ``values`` as the budget counts them before converting it (``len``; 1 for a
    scalar): a value of another shape is refused afterwards by its own check."""
    try:
        return len(values)
    except TypeError:   # a scalar, a 0-d array
        return 1


def _run_count(runs: Any) -> int | None:
    """A Monte-Carlo run count (an int >= 1) or None (an exact value); TypeError/ValueError naming ``runs``."""
    if runs is None:
        return None
    runs = integer(runs, "runs")
    if runs < 1:
        raise ValueError(f"runs must be >= 1, got {runs}")
    return int(runs)


def _stored(x: float) -> float | None:
    """``x`` for the ledger's JSON: ``None`` for NaN (an undefined statistic, R3), which JSON cannot hold."""
    return None if math.isnan(x) else x


def _rounds_to(ours: float, published: float, decimals: int) -> bool:
    """Whether ``ours`` rounded to ``decimals`` equals ``published`` (R1); at an exact tie, either neighbour."""
    if not math.isfinite(ours):
        return False
    target = round(published, decimals)
    if round(ours, decimals) == target:
        return True
    return target in _roundings(ours, decimals)


def _printed(ours: float, published: float, decimals: int) -> str:
    """``ours`` at ``decimals`` decimals as the ledger prints it (:meth:`PublishedValues.summary`).

    Python's rounding of ``ours`` (half to even at an exact tie), except at an exact tie whose other neighbour is
    the published value: R1 accepts either neighbour, and the text shows the one that matches (0.25 beside a
    published 0.3 reads "0.3", fuzz 26a D2). A zero is printed without a sign ("0.000", never "-0.000": the rule
    of the book's formatters, ``fusion.book.tables.rounded``).
    """
    target = round(published, decimals)
    both = _roundings(ours, decimals)
    out = f"{target:.{decimals}f}" if len(both) > 1 and target in both else f"{ours:.{decimals}f}"
    return out[1:] if out.startswith("-") and float(out) == 0 else out


@dataclass(frozen=True)
class PublishedValues:
    """Published numbers beside ours; reproduced iff equal at the printed precision.

    Parameters
    ----------
    published, ours : sequence of float, same length
        ``ours`` may hold NaN where no value can be computed (counts as a mismatch); ``None`` is not NaN but no
        number, refused with a TypeError naming ``ours`` (fuzz 33a D4: numpy would read it as NaN). A value of ours
        exactly halfway between two printed values matches either (R1's tie rule: 1.5 matches a published 1 and 2).
    decimals : int or sequence of int
        Printed number of decimals of each published value: integers from 0 to 17 (the ceiling of a
        number of decimals, ``fusion._validation.COUNT_CEILINGS``), one or one per value. A published value
        has at most its printed decimals: it is the decimal ``round(p, decimals)`` up to the round-off of writing it
        down, the float32 nearest that decimal or a few float64 ulps from it (so that a float32, ``0.1 * 3`` or
        ``12.3 / 100`` is the decimal it prints to). ``1.25`` with 1 decimal is refused, since R1 would then compare
        ours with a rounding of the published value (1.2) and a slip in ``decimals`` would decide the status; so is
        ``1234567.85`` with 1 decimal (the float 1234567.875, float32 of 1234567.9, is accepted: it is that decimal).
        A float32 or float16 published array is held to its own precision (``_decimal_fault``; in a list, each
        ``np.float32``/``np.float16`` scalar to its own, a Python float beside it to float64's): a few ulps of its
        dtype, and a value its dtype cannot hold at ``decimals`` (its spacing there exceeds the printed step:
        float32 98765.4321 at 4 decimals; float64 1234567890123456.78 at 2) is refused; an exact integer of a float32 table below ``2**24`` (float16:
        below ``2**11``) holds 0 decimals. Likewise an integer that float64 cannot hold exactly (beyond 2**53 in
        magnitude, ``2**53 + 1``), in ``published`` or ``ours``, is refused: R1 would compare another number.
    unit : str
    runs : int or None
        Monte-Carlo runs our values were computed from (keyword; ``None``, the default, for an exact
        computation). Values with a run count are stochastic: R4 applies and the reseeding sweep covers them.

    Raises
    ------
    ValueError
        More values than the work budget (``fusion._limits.work``, 700 units a value: about 1.4e6 values), before any
        is read; ``published`` empty, not 1-D or not finite; ``ours`` of another shape or infinite; ``decimals`` neither
        one count nor one per value, or fewer than a published value's decimals, or more than its float32/float16
        dtype holds; an integer in ``published`` or ``ours`` that float64 cannot hold exactly; ``runs`` below 1.
    TypeError
        ``published`` or ``ours`` not numbers (``None``, a date or a duration entry included); ``decimals`` not
        integers; ``unit`` not a str.
    """

    published: tuple[float, ...]
    ours: tuple[float, ...]
    decimals: tuple[int, ...]
    unit: str = ""
    kind: str = field(default="published", init=False)
    runs: int | None = None

    def __init__(self, published: ArrayLike, ours: ArrayLike, decimals: int | Sequence[int], unit: str = "", *,
                 runs: int | None = None) -> None:
        published, ours = read_once(published, "published"), read_once(ours, "ours")  # converted once (fuzz 29a C5)
        # each value runs Python-level checks here and in ``matches`` (fuzz 49b C2: 2**25 values ran 82 + 26 CPU-s)
        work((_length(published),), "published and ours", weight=_PUBLISHED_VALUE)   # before any value is read
        pub = np.atleast_1d(_numeric(published, "published"))
        our = np.atleast_1d(_numeric(ours, "ours"))
        if pub.ndim != 1 or pub.size == 0 or not np.all(np.isfinite(pub)):
            raise ValueError("published must be a non-empty 1-D array of finite numbers")
        if our.shape != pub.shape:
            raise ValueError(f"ours has shape {our.shape}, published {pub.shape}")
        if np.any(np.isinf(our)):
            raise ValueError("ours must not be infinite (NaN marks a value that cannot be computed)")
        for name, given in (("published", published), ("ours", ours)):  # integers beyond float64 (fuzz 29a C6)
            i = inexact_integer(given)
            if i is not None:
                raise ValueError(f"{name}[{i}] is an integer that float64 cannot hold exactly (beyond 2**53 in "
                                 "magnitude): R1 would compare another number")
        # integers >= 0 up to the ceiling of a number of decimals (a float, even 2.0, is refused: rule 13)
        one = isinstance(decimals, (str, bytes)) or not hasattr(decimals, "__len__") or ndim_of(decimals, "decimals") == 0
        dec_l = [count(decimals, "decimals", minimum=0)] if one else counts(decimals, "decimals", minimum=0)
        if len(dec_l) not in (1, pub.size):
            raise ValueError(f"decimals must hold one number or one per published value ({pub.size}), got {len(dec_l)}")
        unit = _text(unit, "unit")  # the plain str (rule 19)
        dec = np.broadcast_to(np.array(dec_l, dtype=int), pub.shape)
        # a real extra decimal, not the binary round-off of the printed decimal (float32, 0.1 * 3, 12.3 / 100: fuzz 24e F1)
        exact = integer_entries(published, pub.size)  # an int given beside floats is exact (fuzz 30a C1/C2)
        dtypes = entry_dtypes(published, pub.size)  # each entry its own dtype's precision (fuzz 31a C1)
        faults = [_decimal_fault(p, d, np.dtype(np.int64) if k else dt)
                  for p, d, k, dt in zip(pub.tolist(), dec.tolist(), exact, dtypes)]
        bad = [i for i, why in enumerate(faults) if why]
        if bad:  # R1 would compare ours with the published value rounded (fuzz 24a D5)
            i = bad[0]
            if faults[i] == "cannot hold":
                held = dtypes[i] if dtypes[i].kind == "f" and dtypes[i].itemsize < 8 else "float64"
                raise ValueError(f"published[{i}] = {shown(float(pub[i]))} is a {held} that cannot hold "
                                 f"decimals[{i}] = {int(dec[i])} decimals (its spacing there exceeds the printed step: two "
                                 "neighbouring printed values round to one value of the dtype)")
            raise ValueError(f"published[{i}] = {shown(float(pub[i]))} has more decimals than decimals[{i}] = "
                             f"{int(dec[i])} (a published value has at most its printed decimals)")
        object.__setattr__(self, "published", tuple(float(v) for v in pub))
        object.__setattr__(self, "ours", tuple(float(v) for v in our))
        object.__setattr__(self, "decimals", tuple(int(d) for d in dec))
        object.__setattr__(self, "unit", unit)
        object.__setattr__(self, "kind", "published")
        object.__setattr__(self, "runs", _run_count(runs))

    @property
    def matches(self) -> tuple[bool, ...]:
        """Whether each of our values, rounded to the printed decimals, equals the published one (R1).

        At an exact tie (ours lies exactly halfway between two printed values) either neighbour is accepted:
        rounding half to even and half away from zero are both readings of "rounded to the printed decimals".
        Computed once (fuzz 49b C2: every ``status()``, ``summary()`` and ``to_dict()`` computed it again).
        """
        cached = self.__dict__.get("_matches")
        if cached is None:
            cached = tuple(_rounds_to(o, p, d) for p, o, d in zip(self.published, self.ours, self.decimals))
            object.__setattr__(self, "_matches", cached)
        return cached

    def status(self) -> str:
        return "reproduced" if all(self.matches) else "not reproduced"

    def summary(self) -> str:
        """One number: ours at the printed decimals (at an exact tie, the neighbour that matches the published
        value; a zero without a sign), or "k of n equal at the printed precision"."""
        n, k = len(self.published), sum(self.matches)
        u = f" {self.unit}" if self.unit else ""
        if n == 1:
            o = self.ours[0]
            return f"{_printed(o, self.published[0], self.decimals[0])}{u}" if math.isfinite(o) else "no value"
        return f"{k} of {n} equal at the printed precision"

    def brief(self) -> str:
        """Our number in a few words (the In-brief boxes and the Verdicts table)."""
        return self.summary()

    def to_dict(self) -> JSONObject:
        out = {"kind": self.kind, "published": list(self.published), "ours": list(self.ours),
               "decimals": list(self.decimals), "unit": self.unit, "matches": list(self.matches)}
        return out if self.runs is None else out | {"runs": self.runs}


@dataclass(frozen=True)
class Comparison:
    """A paired Monte-Carlo comparison: is method A's metric lower than B's, higher, or the same?

    The status comes from :func:`fusion.book.rulebook.judge_paired` (rules R2 and R3): the paired 95 %
    interval (of the mean, or of the median when the differences are heavy-tailed) against zero and the
    practical margin. The summary calls B "a constant" only when every run of B holds one finite value. Whenever
    R3 decides (a mean infinite), ``to_dict()`` gives ``heavy_tailed: True`` (an infinite mean is the heaviest
    tail) and ``tail_index: None`` when fewer than 11 runs have a finite difference (none when every run is
    infinite in both: the status is then "cannot be checked").

    Parameters
    ----------
    a, b : array_like, shape (runs,)
        Per-run metric of A and of B on the same runs (same seeds, same samples). ``+inf`` marks a run whose
        statistic is infinite; NaN is refused. Runs given as float32 or float16 are judged with their own round-off
        (R2's tie, as :func:`~fusion.book.rulebook.judge_paired`; kept by :meth:`with_margin`, while a record
        rebuilt from the stored floats, ``dataclasses.replace``, is judged as float64 runs).
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
        :data:`fusion.book.rulebook.DEFAULT_RELATIVE_MARGIN`). Given with ``margin``, it must give the same
        margin (a copy of a comparison passes both), else ValueError; ``margin`` is stored.
    conditions : tuple of (str, str)
        The conditions (e.g. a stress test) under which A and B ran; R6 refuses different ones. A list pair
        is accepted and stored as a tuple.
    infinite_mean : tuple of str
        ``"a"``, ``"b"``: methods whose population mean is infinite by a closed-form argument (R3).

    Raises
    ------
    ValueError
        ``a`` or ``b`` is not 1-D, they differ in length or hold fewer than 2 runs, NaN or ``-inf``; fewer
        than :data:`MIN_RUNS` runs without a ``reason``; an empty ``a_name``, ``b_name`` or ``metric``; ``b_name``
        the same as ``a_name``;
        ``claim`` is not one of its values; ``margin`` and ``relative_margin`` both given and disagreeing, or
        either negative or not finite; ``conditions`` differ (R6); an entry of ``infinite_mean`` is not ``"a"`` or ``"b"``.
    TypeError
        A name, ``metric``, ``reason`` or ``claim`` is not a str; ``seed`` is not an integer; ``conditions``
        is not a pair of str; ``infinite_mean`` is not a sequence of str (a str is refused).
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
        a, b = read_once(a, "a"), read_once(b, "b")  # converted once: checked, and their dtype read (fuzz 33a C7)
        try:
            av, bv = R._paired_runs(a, b)  # the rulebook's one check of paired runs: 1-D, same length, finite or +inf
        except ValueError:
            if (isinstance(reason, str) and not reason and np.ndim(a) == 1 and np.shape(a) == np.shape(b)
                    and np.size(a) < 2):
                # one paired run without a reason is short for rule R4 too: a FewRunsError, which a chapter function
                # renames by its caller's argument (fuzz 35b B1: "a and b ... (>= 2)" reached the caller of runs=1)
                raise FewRunsError(f"a and b hold {np.size(a)} runs < {MIN_RUNS}: give more runs or a reason (the "
                                   "argument reason: why fewer runs are enough)", int(np.size(a)), MIN_RUNS) from None
            raise
        a_name, b_name, metric, reason = (_text(v, name) for name, v in (  # plain str copies (rule 19)
            ("a_name", a_name), ("b_name", b_name), ("metric", metric), ("reason", reason)))
        for name, v in (("a_name", a_name), ("b_name", b_name), ("metric", metric)):
            if not v.strip():
                raise ValueError(f"{name} must not be empty")
        R._two_methods(a_name, b_name)
        if seed is not None:
            seed = check_seed(seed, "seed")  # an integer (rule 11): 0.0 is not a seed; stored as a plain int
        claim = text(claim, "claim")  # rule 19: matched and stored as its text
        claim = one_of(claim, ("less", "greater", "equal"), "claim")
        if av.size < MIN_RUNS and not reason:
            raise FewRunsError(f"a and b hold {av.size} runs < {MIN_RUNS}: give more runs or a reason (the argument "
                               "reason: why fewer runs are enough)", av.size, MIN_RUNS)
        if isinstance(conditions, (list, UserList)):  # a list pair is a pair (the chapter results store lists as
            conditions = tuple(conditions)             # tuples); so is any list-like (the one sequence rule)
        if not (isinstance(conditions, tuple) and len(conditions) == 2 and all(isinstance(c, str) for c in conditions)):
            raise TypeError(f"conditions must be a pair of str, got {shown(conditions)}")
        conditions = _texts(conditions, "conditions")  # plain str copies (rule 19)
        if conditions[0] != conditions[1]:  # R6
            raise ValueError(f"conditions: A ran under {shown(conditions[0])} and B under {shown(conditions[1])}; a stress test "
                             "applied to one method must be applied to every compared method (rule R6)")
        inf_m = R._infinite_mean(infinite_mean)
        R._margins(margin, relative_margin)  # one check with Conjunction.with_margin (fuzz 34a D3)
        ref = abs(float(np.mean(bv))) if np.all(np.isfinite(bv)) else abs(float(np.median(bv)))
        margin, relative_margin = R._practical_margin(margin, relative_margin, ref, "B's runs")
        for k, v in (("a", tuple(float(x) for x in av)), ("b", tuple(float(x) for x in bv)), ("a_name", a_name),
                     ("b_name", b_name), ("claim", claim), ("metric", metric), ("seed", seed), ("reason", reason),
                     ("margin", float(margin)), ("relative_margin", None if relative_margin is None else float(relative_margin)),
                     ("conditions", conditions), ("infinite_mean", inf_m), ("kind", "comparison")):
            object.__setattr__(self, k, v)
        object.__setattr__(self, "_tie", R._tie_share(a, b))  # R2's tie, from the runs' dtype as given (fuzz 30a C3)

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
        out = Comparison(self.a, self.b, self.a_name, self.b_name, self.claim, self.metric, self.seed, self.reason,
                         margin, relative_margin, self.conditions, self.infinite_mean)
        object.__setattr__(out, "_tie", self._tie)  # the runs' precision as first given (R2's tie)
        return out

    @property
    def runs(self) -> int:
        return len(self.a)

    def judgement(self) -> R.Judgement:
        """The rulebook's judgement (R2, R3), computed once."""
        cached = self.__dict__.get("_judgement")
        if cached is None:
            cached = R._judge(np.array(self.a), np.array(self.b), self.claim, self.margin, self.infinite_mean,
                              self.__dict__.get("_tie", R.ROUND_OFF_TIE))  # R2's tie of the runs as given
            object.__setattr__(self, "_judgement", cached)
        return cached

    def interval(self) -> tuple[float, float, float]:
        """The deciding statistic (mean paired difference A − B, or its median under R3) and its 95 % interval."""
        j = self.judgement()
        return j.estimate, j.low, j.high

    def within_margin(self) -> bool:
        """``True`` if the whole 95 % interval lies inside the closed [-margin, margin] (rule R2: region "equivalent",
        an end within round-off of the margin counted as the margin; never at margin 0)."""
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

    def at_resolution(self, x: float) -> float:
        """``x`` as this comparison stores and shows its numbers: rounded to :meth:`resolution` (an end closer to zero
        than it keeps two significant digits). A number derived from its runs and glued beside it (an interval end, a
        median of the differences) is rounded so too: its further digits are the runs' round-off, which differs between
        BLAS kernels (a notebook's interval end printed 9.6038 under one kernel, 9.6037 under another)."""
        return self._rounded(x)

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
            A value on this comparison's scale: a real number (NaN and the infinities are written as the book's
            words, :data:`~fusion.book.tables.NONFINITE_RULE`).

        Returns
        -------
        str

        Raises
        ------
        TypeError
            ``x`` is text, bytes, a bool, complex, ``None`` or a container (naming ``x``).
        ValueError
            ``x`` is a finite number beyond the float range, or a non-zero one below it (naming ``x``).
        """
        return self._text(_real_number(x, "x", "a real number", bound=None))  # the float range (fuzz 42b D4)

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
        elif j.statistic == "median" and math.isnan(j.estimate):
            tail = "; both means infinite and the median difference undefined: cannot be checked (R3)"
        elif j.statistic == "median" and j.status == "cannot be checked":
            tail = ("; both means infinite and the median difference's interval not on one side of zero: "
                    "cannot be checked (R3)")
        elif j.statistic == "median":
            tail = "; both means infinite: decided by the median (R3)"
        elif j.heavy:  # R3: reported beside the mean, which decides
            med, lo, hi = R.median_interval(np.asarray(self.a, float) - np.asarray(self.b, float))
            tail = (f"; heavy-tailed differences (tail index {fmt(j.tail_index, 2)}; a few runs carry the mean): "
                    f"median difference {t(med)} [{t(lo)}, {t(hi)}], shown beside the mean, which decides (R3)")
        margin = f"; margin ±{fmt(self.margin, 3)}" if self.margin > 0 else ""
        # one-sample yardstick: B one finite value in every run (an infinite B in every run is no constant)
        pairing = "runs against a constant" if len(set(self.b)) == 1 and math.isfinite(self.b[0]) else "paired runs"
        return (head + f", {self.runs} {pairing}; {self.a_name} {side} in {wins} of {self.runs} runs"
                + margin + tail + ("; the interval lies within the margin: no difference that matters"
                                   if j.region == "equivalent" else ""))

    def brief(self) -> str:
        """Our number in a few words: both means and the deciding statistic with its interval."""
        j, t = self.judgement(), self._text
        if j.statistic == "infinite mean":  # the sample mean of the infinite side says nothing: name it, give medians
            inf_a = "a" in self.infinite_mean or math.isinf(self._mean(self.a))
            finite = (self.b_name, self._mean(self.b)) if inf_a else (self.a_name, self._mean(self.a))
            head = f"{self.a_name if inf_a else self.b_name}: infinite mean vs {finite[0]} {t(finite[1])}"
            if self.runs < R.median_values_needed():   # R3 with a reason (R4) allows 2 runs; no median interval
                return f"{head}, {self.runs} runs"     # then, as summary() gives none (fuzz 40b C9)
            med, lo, hi = R.median_interval(np.subtract(np.where(np.isinf(self.a), np.inf, self.a),
                                                        np.where(np.isinf(self.b), np.inf, self.b)))
            return f"{head}; median difference {t(med)} [{t(lo)}, {t(hi)}], {self.runs} runs"
        stat = {"mean": "difference", "median": "median difference"}[j.statistic]
        return (f"{self.a_name} {t(self._mean(self.a))} vs {self.b_name} {t(self._mean(self.b))}; "
                f"{stat} {t(j.estimate)} [{t(j.low)}, {t(j.high)}], {self.runs} runs")

    def to_dict(self) -> JSONObject:
        j = self.judgement()
        return {"kind": self.kind, "a_name": self.a_name, "b_name": self.b_name, "claim": self.claim,
                "metric": self.metric, "mean_a": self._rounded(self._mean(self.a)),
                "mean_b": self._rounded(self._mean(self.b)), "statistic": j.statistic, "rule": j.rule,
                "difference": _stored(self._rounded(j.estimate)), "ci_low": _stored(self._rounded(j.low)),
                "ci_high": _stored(self._rounded(j.high)), "region": j.region, "share_lower": round(j.share, 4),
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
        text_fields(self, "ours")
        object.__setattr__(self, "holds", bool(self.holds))
        object.__setattr__(self, "runs", _run_count(self.runs))

    def status(self) -> str:
        return "reproduced" if self.holds else "contradicted"

    def summary(self) -> str:
        return self.ours

    def brief(self) -> str:
        """Our finding in a few words: its first clause."""
        return self.ours.split("; ")[0]

    def to_dict(self) -> JSONObject:
        out = {"kind": self.kind, "holds": self.holds, "ours": self.ours}
        return out if self.runs is None else out | {"runs": self.runs}


#: Work units of one member of a :class:`Conjunction` (``_MEMBER``) and of each run of a member comparison
#: (``_MEMBER_RUN``): the life of a group in the book, ``with_margin`` (each member comparison rebuilt), then its
#: ``status()``, ``summary()`` and ``to_dict()`` (each member judged: t interval, Hill index, median interval).
#: Measured (CPU time of a group of shared members, per member, minimum of 2, shared machine at load ~17), that chain
#: for a member comparison of R runs: 0.92 ms at R = 100 (1.26 ms with a Cauchy tail), 26 ms at 10,000 and 0.31 s at
#: 100,000 (heavy): about 1 ms a member and 3 us a run. So 100,000 and 300 units: the budget's edge, some 7,700
#: members of 100 runs or 33 of 100,000, runs about 7-10 CPU-s (fuzz 49b C4: 300,000 members, with_margin alone
#: 35 CPU-s); a group of the book has a handful of members.
_MEMBER = 100_000
_MEMBER_RUN = 300


@dataclass(frozen=True)
class Conjunction:
    """A claim about every member of a group ("every sensor"), one piece of evidence per member.

    The claim holds for the group only if it holds for each member, so the status is derived from
    the members' statuses (R9): *contradicted* if any member's is; otherwise *cannot be checked* if any member's
    is (an undefined statistic is never "not distinguishable", R3: the group is not decided by members the
    evidence cannot decide); otherwise *reproduced* if every member's is, else (some member not distinguishable)
    *not distinguishable*.

    Parameters
    ----------
    parts : sequence of (str, Comparison, ExactComparison or Proposition)
        Each member's label (e.g. ``"sensor 1"``) and evidence (a tuple or list pair, stored as a tuple); at least
        two, labels distinct.

    Raises
    ------
    TypeError
        ``parts`` not a sequence of (label, evidence) pairs, a label not a string or an evidence of another
        type; the message names the entry (``parts[1] label``).
    ValueError
        Fewer than two members, or a repeated label; more members than the work budget (``fusion._limits.work``:
        100,000 units a member and 300 a run of a member comparison, the work of ``with_margin`` and a status,
        summary and record of each member; about 7,700 members of 100 runs), counted before any member is read.

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
        # members may share one Comparison, so the caller pays nothing for many (fuzz 49b C4: 300,000 members made
        # with_margin run 35 CPU-s): counted before any is read, then with each comparison's runs
        work((len(parts),), "parts", weight=_MEMBER)
        out = []
        for i, p in enumerate(parts):
            if isinstance(p, list):  # a list pair is a pair (as the chapter results store lists as tuples)
                p = tuple(p)
            if not (isinstance(p, tuple) and len(p) == 2):
                raise TypeError(f"parts must hold (label, evidence) pairs, got {shown(p)}")
            label, ev = p
            label = _text(label, f"parts[{i}] label")  # the argument named, not the pair's field alone (fuzz 18, F18)
            if not isinstance(ev, (Comparison, ExactComparison, Proposition)):
                raise TypeError(f"parts[{i}] evidence must be a Comparison, an ExactComparison or a Proposition, "
                                f"got {type(ev).__name__}")
            out.append((label, ev))
        if len(out) < 2:
            raise ValueError(f"parts must hold at least two members, got {len(out)}")
        units = sum(_MEMBER + _MEMBER_RUN * (len(ev.a) if isinstance(ev, Comparison) else 0) for _, ev in out)
        work((len(out),), "parts", weight=Fraction(units, len(out)))   # each member at its runs
        if len({lab for lab, _ in out}) != len(out):
            raise ValueError("parts must have distinct labels")
        object.__setattr__(self, "parts", tuple(out))
        object.__setattr__(self, "kind", "conjunction")

    def status(self) -> str:
        st = [ev.status() for _, ev in self.parts]
        if "contradicted" in st:
            return "contradicted"
        if "cannot be checked" in st:  # R3, R9: a member the evidence cannot decide leaves the group undecided
            return "cannot be checked"
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
        """The same group with every member comparison judged with another margin (see :meth:`Comparison.with_margin`).

        Parameters
        ----------
        margin, relative_margin : float, optional
            As :meth:`Comparison.with_margin` takes them, given to each member comparison.

        Returns
        -------
        Conjunction
            Members that are not comparisons (a :class:`Proposition`, an :class:`Unverifiable`) unchanged.

        Raises
        ------
        TypeError
            ``margin`` or ``relative_margin`` is not a number or None.
        ValueError
            ``margin`` or ``relative_margin`` is not a finite number >= 0, whatever the members (fuzz 34a D3: a
            conjunction of propositions took NaN silently); or a member comparison refuses them (the message
            names the member, ``parts[i]`` and its label).
        """
        R._margins(margin, relative_margin)
        parts = []
        for i, (lab, ev) in enumerate(self.parts):
            if isinstance(ev, (Comparison, ExactComparison)):
                try:   # the member whose magnitude makes the margin impossible is named (fuzz 50b D3)
                    ev = ev.with_margin(margin, relative_margin)
                except ValueError as exc:
                    if type(exc) is not ValueError:   # a rule's own error (R4) keeps its type and text
                        raise
                    raise ValueError(f"parts[{i}] ({shown(lab, 60)}): {exc}") from None
            parts.append((lab, ev))
        return Conjunction(parts)

    def to_dict(self) -> JSONObject:
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

    Raises
    ------
    TypeError
        ``reason`` is not a str.
    ValueError
        ``reason`` is empty (or blank).
    """

    reason: str
    kind: str = field(default="unverifiable", init=False)

    def __post_init__(self) -> None:
        text_fields(self, "reason")
        if not self.reason.strip():
            raise ValueError("reason must not be empty: say why the claim cannot be checked")

    def status(self) -> str:
        return "cannot be checked"

    def summary(self) -> str:
        return self.reason

    def brief(self) -> str:
        """Nothing computed."""
        return "nothing to compute"

    def to_dict(self) -> JSONObject:
        return {"kind": self.kind, "reason": self.reason}


Evidence = PublishedValues | Comparison | ExactComparison | Proposition | Conjunction | Unverifiable

#: The evidence classes a record or reading may hold.
EVIDENCE_TYPES = (PublishedValues, Comparison, ExactComparison, Proposition, Conjunction, Unverifiable)


#: The evidence classes each kind of test (:data:`fusion.book.rulebook.TESTS`) takes: one table for the claim
#: files (``fusion.book.claims``) and for :class:`fusion.book.ledger.Claim`.
_KIND_OF_TEST = {"published": (PublishedValues,), "paired": (Comparison, Conjunction),
                 "equivalence": (Comparison, Conjunction),
                 "exact": (Proposition, ExactComparison, Conjunction, PublishedValues),
                 "count": (PublishedValues, Proposition), "unverifiable": (Unverifiable,)}


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
