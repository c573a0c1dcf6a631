r"""An exact comparison: two values of a quantity computed in closed form, judged by the practical margin.

Rule R9 of :mod:`fusion.book.rulebook`: a claim that one method is better than another on a quantity the
book computes exactly (a closed-form mean-square error, an operation count, a probability) is judged as a
paired comparison (R2) whose interval has zero width: the difference :math:`d = A - B` is placed against
zero and the record's practical margin :math:`m`. "A is lower" is reproduced when :math:`d < -m`, not
distinguishable when :math:`|d| \le m`, contradicted when :math:`d > m`; "no effect" is reproduced when
:math:`|d| \le m`. Round-off never decides (R2's one tie rule, ``fusion._limits.ROUND_OFF_TIE``): a difference
within :math:`10^{-9} \max(|A|, |B|)` of zero is a tie, :math:`d = 0`, whatever the margin (at :math:`m = 0`
too: one ulp between two closed forms is not "lower"), judged as R2 judges a tie of Monte-Carlo runs: equivalent
for a positive margin, undecided at :math:`m = 0` (no interval is wholly inside :math:`\pm 0`; fuzz 27a D7).
At the margin's edge likewise: a difference within :math:`10^{-9} \max(|A|, |B|, m)` of :math:`\pm m` is the
margin, :math:`|d| = m`, equivalent (R2, :func:`fusion.book.rulebook.region`). The same margin that decides a Monte-Carlo comparison of the quantity decides its
exact value, so a gain of :math:`10^{-6}` is not "better" in one record while a 4 % gain is "no
difference" in another.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Literal

import numpy as np

from fusion._validation import _real_number, check_magnitude, one_of, scalar
from fusion._validation import shown
from fusion._validation import text
from fusion.book import rulebook as R
from fusion.book._claim_text import record_text
from fusion.book._json import JSONObject
from fusion.book.tables import roundoff

__all__ = ["ExactComparison"]


def _value(v: object, name: str) -> float:
    x = _real_number(v, name, "a real number")  # booleans (numpy's too), complex, text: TypeError naming it
    if not math.isfinite(x):
        raise ValueError(f"{name} must be finite, got {x}")
    # rule 2 at construction, naming the value (the margin and the region derived from it later would not)
    check_magnitude(np.array([x]), name, subnormal=False)
    return x


def _text(v: object, name: str) -> str:
    if not isinstance(v, str) or not v.strip():
        raise ValueError(f"{name} must be a non-empty string, got {shown(v)}")
    return record_text(v, name)  # the plain str (rule 19) by the records' text rule (fuzz 49b C5)


def _percent(share: float) -> str:
    """``share`` as a signed percentage: ``{:+.1%}`` below 10⁸ %, else the ledger's number format (no 160 digits);
    a share that rounds to zero reads ``0.0%`` (never ``-0.0%``)."""
    if abs(share) < 1e6:  # at most "+99999999.9%": the ledger holds +303610.1% of B (chapter 04)
        out = f"{share:+.1%}"
        return "0.0%" if float(out[:-1]) == 0 else out
    from fusion.book.ledger.statuses import fmt  # the ledger's formatter (imported here: the ledger imports this module)
    return f"{'+' if share > 0 else ''}{fmt(100.0 * share)}%"


@dataclass(frozen=True, init=False)
class ExactComparison:
    """Two exactly computed values of one quantity, A against B, under rule R9 (R2 with a zero-width interval).

    Parameters
    ----------
    a, b : float
        The values of A and of B (finite, the metric's units).
    a_name, b_name : str
    claim : {"less", "greater", "equal"}
        What the claim says of A against B ("equal": no effect, within the margin).
    metric : str
        What is compared, with its unit, and how it is computed ("exact MSE", "operations").
    margin : float or None
        Practical margin in the metric's units (>= 0); ``None``: ``relative_margin`` times :math:`|B|`.
    relative_margin : float or None
        Share of :math:`|B|` (default :data:`fusion.book.rulebook.DEFAULT_RELATIVE_MARGIN`). Given with ``margin``,
        it must give the same margin (a copy passes both, as ``dataclasses.replace`` does), else ValueError;
        ``margin`` is stored (as for :class:`~fusion.book.ledger.Comparison`).

    Raises
    ------
    ValueError
        ``a`` or ``b`` not finite or beyond the representable range (magnitude above 1e150, checked here, not
        when the status is asked); an empty name or ``metric``; ``b_name`` the same as ``a_name``; ``claim`` not one of its values; a negative or
        non-finite margin; ``margin`` and ``relative_margin`` that disagree (also in :meth:`with_margin` and
        ``dataclasses.replace``).
    TypeError
        ``a`` or ``b`` not a real number; a name, ``metric`` or ``claim`` not a str; ``margin`` or
        ``relative_margin`` neither None, an int nor a float (a 0-d array or a Decimal included, as for
        :class:`~fusion.book.ledger.Comparison`).

    Notes
    -----
    ``margin`` and ``relative_margin`` given together agree when equal to 12 significant digits: a float32
    ``relative_margin`` (``np.float32(0.05)`` is 0.0500000007) next to the float64 margin it stands for disagrees,
    as in :class:`~fusion.book.ledger.Comparison`.
    """

    a: float
    b: float
    a_name: str
    b_name: str
    claim: Literal["less", "greater", "equal"]
    metric: str
    margin: float
    relative_margin: float | None
    kind: str = field(default="exact comparison", init=False)

    def __init__(self, a: float, b: float, a_name: str, b_name: str, claim: Literal["less", "greater", "equal"],
                 metric: str, margin: float | None = None, relative_margin: float | None = None) -> None:
        av, bv = _value(a, "a"), _value(b, "b")
        a_name, b_name, metric = (_text(v, name) for name, v in (("a_name", a_name), ("b_name", b_name),
                                                                  ("metric", metric)))
        R._two_methods(a_name, b_name)
        claim = text(claim, "claim")  # rule 19: matched and stored as its text (a 0-d array is not text)
        claim = one_of(claim, ("less", "greater", "equal"), "claim")
        R._margin_type(margin, "margin"), R._margin_type(relative_margin, "relative_margin")  # Comparison's rule
        margin = None if margin is None else scalar(margin, "margin", 0.0)
        relative_margin = None if relative_margin is None else scalar(relative_margin, "relative_margin", 0.0)
        m, relative_margin = R._practical_margin(margin, relative_margin, abs(bv), "B")  # as Comparison's
        for k, v in (("a", av), ("b", bv), ("a_name", a_name), ("b_name", b_name), ("claim", claim), ("metric", metric),
                     ("margin", float(m)), ("relative_margin", None if relative_margin is None else float(relative_margin)),
                     ("kind", "exact comparison")):
            object.__setattr__(self, k, v)
        object.__setattr__(self, "_tie", R._tie_share(a, b))  # R2's tie, from the values' dtype as given (fuzz 30a C3)

    def with_margin(self, margin: float | None = None, relative_margin: float | None = None) -> ExactComparison:
        """The same values judged with another practical margin (absolute, or relative to :math:`|B|`)."""
        out = ExactComparison(self.a, self.b, self.a_name, self.b_name, self.claim, self.metric, margin,
                              relative_margin)
        object.__setattr__(out, "_tie", self._tie)  # the values' precision as first given (R2's tie)
        return out

    @property
    def difference(self) -> float:
        return self.a - self.b

    def region(self) -> str:
        r"""``"lower"``, ``"higher"``, ``"equivalent"`` or ``"undecided"`` (R2 with a zero-width interval).

        A tie, :math:`|A - B| \le 10^{-9} \max(|A|, |B|)` (R2's one tie rule, as :func:`fusion.book.rulebook.judge_paired`
        applies it to a run), is :math:`d = 0`: ``"equivalent"`` for a positive margin, ``"undecided"`` at margin 0,
        as :func:`fusion.book.rulebook.judge_paired` judges runs that all tie (R2: equivalent is wholly inside
        :math:`\pm m`; fuzz 27a D7). At the margin's edge likewise: a difference within :math:`10^{-9} \max(|A|, |B|, m)`
        of :math:`\pm m` is :math:`\pm m`, and :math:`|d| \le m` is ``"equivalent"`` (:func:`fusion.book.rulebook.region`),
        so 0.3 against 0.2 and 1.3 against 1.2 with a margin of 0.1 get one region. Values given as float32 or
        float16 are decided by their own round-off: the share :math:`10^{-9}` is then 4 epsilons of their dtype
        (as in :func:`fusion.book.rulebook.judge_paired`; kept by :meth:`with_margin`, not by ``dataclasses.replace``,
        which rebuilds from the stored floats).
        """
        d, scale = self.difference, max(abs(self.a), abs(self.b))
        share = self.__dict__.get("_tie", R.ROUND_OFF_TIE)  # float32/float16 values: their own round-off (R2)
        if R._round_off(d, scale, share):  # R2's one tie rule: round-off never decides
            d = 0.0  # a tie is d = 0, judged as judge_paired judges tied runs (fuzz 27a D7)
        return R._region(d, d, self.margin, scale, share)  # and a d within round-off of +-m is the margin (R2)

    def status(self) -> str:
        return R.status_from_region(self.region(), self.claim)  # type: ignore[arg-type]

    def _t(self, x: float) -> str:
        """The ledger's number format (:func:`fusion.book.ledger.fmt`: 4 digits, ``1.5×10^-7``, ``-0`` -> ``0``)."""
        from fusion.book.ledger.statuses import fmt  # imported here: the ledger imports this module
        return fmt(x)

    def summary(self) -> str:
        """One line for the ledger: the two values, their difference (its size only, when it is round-off) and the
        margin.

        A tie (R2's one tie rule, ``fusion._limits.ROUND_OFF_TIE``, as :meth:`region` applies it: at most
        :math:`10^{-9}` of the larger value's magnitude, zero included) is round-off, and says so: its relative size
        is printed by the book's round-off rule (:func:`fusion.book.tables.roundoff`: below :math:`10^{-12}`,
        :data:`fusion.book.tables.ROUNDOFF_EXPONENT`, its digits move with the BLAS kernel, so the text gives the
        bound, ``"difference less than 10⁻¹² relative (round-off)"``; a tie of ``5e-10`` reads ``"difference
        5×10⁻¹⁰ relative (round-off)"``; fuzz 28a D4: the note used its own ``1e-12`` and a tie of ``5e-10`` read
        as a difference against a margin of 0); two zeros give ``"difference 0"``. The difference as a share of B reads ``+4.0%`` below
        10⁸ %, and beyond that in the ledger's number format (``+1×10^162%`` for A = 1 against B = 1e-160).
        """
        d, scale = self.difference, max(abs(self.a), abs(self.b))
        if scale == 0.0:
            diff = "difference 0"
        elif R._round_off(d, scale, self.__dict__.get("_tie", R.ROUND_OFF_TIE)):  # region()'s tie: one rule
            diff = f"difference {roundoff(d / scale)} relative (round-off)"
        else:
            diff = f"difference {self._t(d)}" + (f" ({_percent(d / self.b)} of B)" if self.b != 0 else "")
        return (f"{self.a_name} {self._t(self.a)} vs {self.b_name} {self._t(self.b)} ({self.metric}, exact); "
                f"{diff}; margin ±{self._t(self.margin)}"
                + ("; within the margin: no difference that matters" if self.region() == "equivalent" else ""))

    def brief(self) -> str:
        return f"{self.a_name} {self._t(self.a)} vs {self.b_name} {self._t(self.b)} (exact)"

    def to_dict(self) -> JSONObject:
        r = lambda x: float(f"{x:.10g}")  # noqa: E731 - stored to 10 significant digits (BLAS-independent)
        return {"kind": self.kind, "a_name": self.a_name, "b_name": self.b_name, "claim": self.claim,
                "metric": self.metric, "a": r(self.a), "b": r(self.b),
                "margin": r(self.margin), "region": self.region()}
