"""The status vocabulary of the ledger, its one-sentence definitions, and the shared text checks.

The statuses and thresholds are those of the rulebook (:mod:`fusion.book.rulebook`); this module only
re-states them for the ledger and the Verdicts page, with :func:`fmt`, the number format of every record.
"""

from __future__ import annotations

from typing import Any

from fusion._frozen import constant
from fusion._validation import sequence, shown
from fusion.book import rulebook as R
from fusion.book._claim_text import record_text as _text   # the claim files' text rule (fuzz 49b C5)
from fusion.book.tables import _significant

__all__ = [
    "STATUSES",
    "STATUS_DEFINITIONS",
    "MIN_RUNS",
    "CONFIDENCE_LEVEL",
    "DOMINANCE_SHARE",
    "fmt",
]


def _texts(value: Any, name: str) -> tuple[str, ...]:
    """A tuple of strings as a tuple of plain ``str`` (a bare string is refused: it would be split into characters;
    each entry read by the record's text rule, ``_text``, under ``name[i]``)."""
    if isinstance(value, str) or not all(isinstance(v, str) for v in sequence(value, name)):
        raise TypeError(f"{name} must be a tuple of str, got {shown(value)}")
    return tuple(_text(v, f"{name}[{i}]") for i, v in enumerate(tuple(value)))


def text_fields(obj: object, *names: str) -> None:
    """Store in each field ``names`` of the frozen dataclass ``obj`` its plain ``str`` read by the record's text rule
    (``_text``: rule 19 and the claim files' rule, no control or format character, no lone surrogate; fuzz 49b C5: a
    record's lone surrogate made ``Ledger.write`` fail after truncating the ledger file)."""
    for n in names:
        object.__setattr__(obj, n, _text(getattr(obj, n), n))

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
STATUS_DEFINITIONS: dict[str, str] = constant({
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
    "cannot be checked": "the source gives too little to compute, or compares with a method it never defines "
                         "(R7, R9); or the evidence cannot decide: a statistic undefined, or infinite without a side "
                         "of zero (R3), or a member of a group that cannot be checked (R9); the record says why",
})


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
        E.g. ``"0.1235"``, ``"1.5×10^-7"``; ``"—"`` for NaN, ``"∞"`` and ``"-∞"`` for the infinities (the rule of
        every number formatter of the book, ``fusion.book.tables.NONFINITE_RULE``).

    Raises
    ------
    TypeError
        ``x`` is text, bytes, ``None``, a bool, complex or a container, naming ``x``; ``digits`` not an integer.
    ValueError
        ``x`` an integer beyond the float range (its literal would run to hundreds of digits).
    """
    return _significant(x, digits, _caret_power)   # the rule of sci, with the ledger's ASCII exponent


def _caret_power(mantissa: str, exponent: int) -> str:
    return f"{mantissa}×10^{exponent}"
