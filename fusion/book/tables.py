"""Tables that set published numbers beside recomputed ones.

The book shows every published number next to ours and the difference; this module
builds those tables as :class:`pandas.DataFrame` objects with a fixed number of
decimals, so that their text is identical from run to run and machine to machine.
"""

from __future__ import annotations

import decimal
import fractions
import math
import re
from collections.abc import Callable, Collection, Sequence
from typing import Any

import numpy as np
import pandas as pd

from fusion._limits import MIN_NORMAL, inexact_integer
from fusion._validation import integer, is_integer
from fusion._validation import text as text_argument
from fusion._validation import _real_number, as_array, count, distinct, sequence
from numpy.typing import ArrayLike
from fusion._shown import shown

__all__ = ["side_by_side", "rounded", "mismatches", "highlight_mismatches", "integral_index", "power_of_ten",
           "sci", "roundoff", "ROUNDOFF_EXPONENT", "NONFINITE_RULE", "cell_text", "tidy_table_html", "use_book_tables"]


#: The largest finite float64 (about 1.8e308): the only bound on a number the book prints.
_FLOAT_MAX = float(np.finfo(np.float64).max)


def _printed_number(value: object, name: str) -> float:
    """A finite number to print or round for print: any finite double, whatever its magnitude.

    The one magnitude rule of the book's formatters (:func:`rounded`, :func:`roundoff`, :func:`sci`,
    :func:`fusion.book.ledger.fmt`, ``fusion.book.chapters.ci.excess_text``): rule 2's bounds (1e-150 to 1e150)
    guard computations, whose products and reciprocals must stay representable; printing or rounding a number
    computes neither, so a subnormal or a 1e300 is printed (or rounded) as it is. TypeError naming ``name`` for a
    non-number (the shared reader); ValueError naming ``name`` for NaN or an infinity (the callers that print those
    as words, :data:`NONFINITE_RULE`, test for them first).
    """
    if is_integer(value) and abs(int(value)) > _FLOAT_MAX:   # not rule 2's 1e150: a printed number has no such bound
        raise ValueError(f"{name} must be a number within the float range (magnitude at most {_FLOAT_MAX:.3g}), "
                         "got an integer beyond it")
    v = _real_number(value, name, bound=None)  # beyond the float range named as such (fuzz 42b D4)
    if not math.isfinite(v):
        raise ValueError(f"{name} must be finite, got {shown(value)}")
    return v


def rounded(value: float, decimals: int = 4) -> float:
    """Round a number for display or glue, mapping ``-0.0`` to ``0.0``.

    Parameters
    ----------
    value : float
        The number.
    decimals : int
        Decimals kept (Python's ``round``, half to even; a ``Decimal`` or ``Fraction`` is rounded as it is, not
        through its float: ``Decimal("2.675")`` to 2.68).

    Returns
    -------
    float
        ``value`` rounded to ``decimals`` decimals; ``0.0`` for any zero, never ``-0.0``.

    Raises
    ------
    TypeError
        ``value`` not a real number, ``decimals`` not an integer.
    ValueError
        ``value`` NaN or infinite; ``decimals`` negative or above 17. Any finite magnitude is rounded (a subnormal
        to 0.0), the one rule of the book's formatters (``_printed_number``); a ``Decimal``, ``Fraction`` or
        ``longdouble`` below float's normal numbers (2.2e-308), which those formatters refuse (its float is not
        it), is rounded exactly: to 0.0 at any decimals accepted.
    """
    given = value
    try:
        value = _printed_number(value, "value")
    except ValueError:
        if not _below_normal_floats(value):
            raise
        count(decimals, "decimals", minimum=0)
        return 0.0  # |value| < 2.2e-308 < half of 10**-17 (the most decimals accepted): exactly zero (fuzz 45 D1)
    decimals = count(decimals, "decimals", minimum=0)
    # the exact value only once the float range is checked: a Decimal of exponent 1e7 is a Fraction of ten million
    # digits (fuzz 47 C1: 6.1 CPU-s before its refusal); within the range and above 1e-20 it is a few hundred at most
    r = round(value, decimals) if abs(value) < 1e-20 else _rounded_exact(given, value, decimals)
    return 0.0 if r == 0 else r


#: The exact number types the formatters round as they are, not through their nearest float (fuzz 46b D3:
#: ``rounded(Decimal("2.675"), 2)`` gave 2.67, the rounding of the float 2.67499999999999982236431605997495353221893310546875).
_EXACT_TYPES = (decimal.Decimal, fractions.Fraction)


def _rounded_exact(given: object, value: float, decimals: int) -> float:
    """``given`` rounded half to even to ``decimals`` decimals as it is when it is a finite ``Decimal`` (by
    ``quantize``: linear in its digits, where a Fraction of 200,000 digits took a CPU-second) or ``Fraction``,
    else its float ``value`` by Python's ``round``; ``given`` within the float range (its float ``value`` finite)."""
    if isinstance(given, decimal.Decimal) and given.is_finite():
        ctx = decimal.Context(prec=400, rounding=decimal.ROUND_HALF_EVEN)  # 309 integer digits + 17 decimals fit
        step = decimal.Decimal((0, (1,), -decimals))  # 10**-decimals exactly, whatever the caller's context (fuzz 48 C5)
        return float(given.quantize(step, context=ctx))
    exact = _exact(given)
    return round(value, decimals) if exact is None else float(round(exact, decimals))


def _exact(value: object) -> fractions.Fraction | None:
    """``value`` as a Fraction when it is a finite ``Decimal`` or ``Fraction`` (exactly), else None."""
    if not isinstance(value, _EXACT_TYPES):
        return None
    try:
        return fractions.Fraction(value)
    except (ValueError, OverflowError, ArithmeticError):  # NaN or an infinity: the callers' finiteness rule decides
        return None


def _exact_significant(value: object, x: float, digits: int) -> float:
    """A finite nonzero ``x = float(value)``, or, for an exact ``value`` and ``digits`` <= 15 (float's decimal
    digits: the float of a ``digits``-digit decimal prints back as it), the float of ``value`` rounded exactly, half to
    even, to ``digits`` significant digits (``x`` again when that rounding leaves the float range)."""
    if digits > 15 or not isinstance(value, _EXACT_TYPES):
        return x
    ctx = decimal.Context(prec=digits, rounding=decimal.ROUND_HALF_EVEN, Emax=decimal.MAX_EMAX, Emin=decimal.MIN_EMIN)
    if isinstance(value, decimal.Decimal):  # rounded as it is, linear in its digits (a Fraction of them is not)
        r = float(ctx.plus(value)) if value.is_finite() else x
        return r if math.isfinite(r) else x
    q = _exact(value)
    if q is None:
        return x
    # exact half-to-even rounding at the digits' place, by the Fraction's own round (a Decimal division of its
    # numerator and denominator was superlinear: Fraction(3**N + 1, 3**N) at N = 2.5e6 took 39 CPU-s, fuzz 48 C3);
    # the place from the float x, exact but at a power of ten, where :g's digits decide alike
    place = digits - 1 - math.floor(math.log10(abs(x)))
    r = float(round(q, place))
    return r if math.isfinite(r) else x


def _below_normal_floats(value: object) -> bool:
    """Whether ``value`` is a finite ``Decimal``, ``Fraction`` or numpy float (0-d array included) of magnitude below
    float's normal numbers, compared exactly (not through its float)."""
    if not isinstance(value, (decimal.Decimal, fractions.Fraction, np.floating, np.ndarray)):
        return False
    try:
        return bool(math.isfinite(value) and abs(value) < MIN_NORMAL)  # type: ignore[arg-type,operator]
    except (TypeError, ValueError, ArithmeticError):  # a signalling NaN, an array of more than one number
        return False


def _roundings(ours: float, decimals: int) -> tuple[float, ...]:
    """``ours`` rounded to ``decimals`` (R1): one value, or at an exact tie (``ours`` exactly halfway between two
    printed values) both neighbours, the one Python's ``round`` gives (half to even) first.

    Rounding half to even and half away from zero are both readings of "rounded to the printed decimals", and
    they do not give every neighbour between them (1.5 -> 2 both ways): the tie rule accepts the floor and the
    ceiling of the scaled value, whichever way the source rounds (fuzz 26a T). The one rounding rule of R1, of
    ``fusion.book.ledger.PublishedValues`` and of :func:`side_by_side`.
    """
    r = round(ours, decimals)
    # exact for any double (at most 767 significant digits) times 10**17, whatever the caller's context (fuzz 48 C5)
    with decimal.localcontext(decimal.Context(prec=2000, Emax=decimal.MAX_EMAX, Emin=decimal.MIN_EMIN)):
        x = decimal.Decimal(ours).scaleb(decimals)
        if abs(x % 1) != decimal.Decimal("0.5"):  # not a tie: the ordinary rounding decides
            return (r,)
        lo = x.to_integral_value(rounding=decimal.ROUND_FLOOR)
        both = [float(v.scaleb(-decimals)) for v in (lo, lo + 1)]
    return (r,) + tuple(v for v in both if v != r)


def _rounded_against(value: float, published: float, decimals: int) -> float:
    """``value`` rounded to ``decimals`` as R1 reads it beside ``published``: :func:`rounded` (correctly rounded,
    half to even, never ``-0.0``), except at an exact tie whose other neighbour is ``published`` rounded, which is
    then shown (R1 accepts either neighbour)."""
    both = _roundings(value, decimals)
    target = round(published, decimals)
    return (target if len(both) > 1 and target in both else both[0]) + 0.0  # + 0.0 turns -0.0 into 0.0


def side_by_side(
    published: ArrayLike,
    reproduced: ArrayLike,
    index: Sequence[object],
    name: str = "",
    decimals: int = 4,
    index_name: str = "observation",
) -> pd.DataFrame:
    """Published and reproduced values with their difference (reproduced - published).

    Parameters
    ----------
    published, reproduced : array_like, shape (k,)
    index : sequence, length k
        Row labels (e.g. observation numbers): hashable and distinct (two NaN labels are repeated). A tuple is one
        label (the index is flat, not a MultiIndex, whatever the labels).
    name : str
        Quantity name appended to the column headers ("" for plain headers).
    decimals : int
        Rounding of the shown values, the book's rule (:func:`rounded`: correctly rounded, so that 0.15, stored as
        0.1499999..., shows 0.1, and never ``-0.0``): at an exact tie, R1 reads either neighbour as the reproduced
        value rounded (``fusion.book.ledger.PublishedValues``), and the one equal to the published value is shown
        (1374.5 beside a published 1375 shows 1375).
    index_name : str
        Name of the index (row labels).

    Returns
    -------
    pandas.DataFrame
        Columns ``published``, ``reproduced`` (each followed by ``name`` if given) and
        ``difference``: the difference of the two shown values (0 exactly when they are equal), so that
        :func:`mismatches` of the table flags a row iff the ledger's R1 does not reproduce its value.

    Raises
    ------
    TypeError
        ``name`` or ``index_name`` not a string, or a row label unhashable.
    ValueError
        ``published``, ``reproduced`` and ``index`` of different lengths, or not 1-D; a row label repeated (a row
        must be found by its label); ``published`` or ``reproduced`` holding NaN or an infinity, or an integer that
        float64 cannot hold exactly (beyond 2**53 in magnitude, as R1 refuses it). A row without a
        published value has no difference to show: leave it out of the table (:func:`mismatches` and
        :func:`highlight_mismatches` skip a missing published value in a table built otherwise).
    """
    pub = as_array(published, "published", ndim=1)
    rep = as_array(reproduced, "reproduced", ndim=1)
    for arg, given in (("published", published), ("reproduced", reproduced)):  # R1's rule (fuzz 29a C6)
        i = inexact_integer(given)
        if i is not None:
            raise ValueError(f"{arg}[{i}] is an integer that float64 cannot hold exactly (beyond 2**53 in magnitude): "
                             "the table would show another number")
    decimals = count(decimals, "decimals", minimum=0)
    name = text_argument(name, "name")  # plain texts (rule 19): an Enum member prints its name
    index_name = text_argument(index_name, "index_name")
    index = sequence(index, "index")  # row labels: any values, but a sequence of them
    for i, label in enumerate(index):
        try:
            hash(label)
        except TypeError:
            raise TypeError(f"index[{i}] must be a hashable row label, got {type(label).__name__}") from None
    distinct(index, "index")
    if pub.shape != rep.shape or pub.ndim != 1 or len(index) != pub.size:
        raise ValueError(
            f"published {pub.shape}, reproduced {rep.shape} and index ({len(index)}) must match"
        )
    shown_pub = np.array([rounded(p, decimals) for p in pub.tolist()], dtype=float)
    shown_rep = np.array([_rounded_against(r, p, decimals) for r, p in zip(rep.tolist(), pub.tolist())], dtype=float)
    diff = np.array([rounded(d, decimals) for d in (shown_rep - shown_pub).tolist()], dtype=float)
    return pd.DataFrame(
        {
            f"published {name}".strip(): shown_pub,
            f"reproduced {name}".strip(): shown_rep,
            "difference": diff,
        },
        index=pd.Index(list(index), name=index_name, tupleize_cols=False),  # tuple labels: one label each
    )


def _pairs(columns: pd.Index) -> list[tuple[object, object, object | None]]:
    """(published, reproduced, difference) column triples of a side-by-side table."""
    def last(c: object) -> str:
        return str(c[-1] if isinstance(c, tuple) else c)

    def group(c: object) -> tuple:
        return tuple(c[:-1]) if isinstance(c, tuple) else ()

    out = []
    for c in columns:
        if last(c).startswith("published"):
            suffix = last(c)[len("published"):]
            rep = [d for d in columns if group(d) == group(c) and last(d) == "reproduced" + suffix]
            diff = [d for d in columns if group(d) == group(c) and last(d) == "difference"]
            if rep:
                out.append((c, rep[0], diff[0] if diff else None))
    return out


def _number_column(table: pd.DataFrame, column: object) -> np.ndarray:
    """A compared column as floats: numbers, and ``None``/NaN/``pd.NA`` for a missing value (as a nullable column's
    ``<NA>``); a TypeError naming
    ``table[column]`` for text, booleans, durations or dates (a text cell is not a mismatch: it is not a number)."""
    col = table[column]
    kind = col.dtype.kind
    if kind in "iuf":
        return col.to_numpy(dtype=float)
    if kind == "O":
        bad = [v for v in col if not (v is None or v is pd.NA or (isinstance(v, (int, float, np.integer, np.floating))
                                                                  and not isinstance(v, (bool, np.bool_))))]
        if not bad:
            return np.array([np.nan if v is None or v is pd.NA else float(v) for v in col], dtype=float)
        raise TypeError(f"table[{shown(column)}] must hold numbers (None, NaN or pd.NA where missing), got "
                        f"{shown(bad[0])}")
    raise TypeError(f"table[{shown(column)}] must hold numbers, got the dtype {col.dtype}")


def mismatches(table: pd.DataFrame, decimals: int = 4) -> pd.DataFrame:
    """Which reproduced values differ from the published ones at the printed precision.

    Parameters
    ----------
    table : pandas.DataFrame
        A table with ``published ...`` / ``reproduced ...`` column pairs (as from
        :func:`side_by_side`, possibly concatenated under a column group).
    decimals : int
        Printed decimals of the published values: a pair matches when
        ``|reproduced - published| <= 0.5 * 10**-decimals``.

    Returns
    -------
    pandas.DataFrame of bool
        Same shape as ``table``; True on the reproduced and difference cells of a mismatch (a
        reproduced NaN beside a published value is a mismatch; a row without a published value is not
        compared), False elsewhere. A missing value is ``None``, NaN or ``pd.NA``, in an object column as in a
        nullable one.

    Raises
    ------
    TypeError
        ``table`` is not a DataFrame, or a compared column holds text, booleans, durations or dates, naming
        ``table[column]``.
    ValueError
        If ``table`` holds no published/reproduced pair, or repeats a column name.
    """
    if not isinstance(table, pd.DataFrame):
        raise TypeError(f"table must be a pandas DataFrame, got {type(table).__name__}")
    if not table.columns.is_unique:   # a repeated header makes table[name] a frame, not a column
        raise ValueError(f"table has repeated column names: {sorted({str(c) for c in table.columns[table.columns.duplicated()]})}")
    decimals = count(decimals, "decimals", minimum=0)
    pairs = _pairs(table.columns)
    if not pairs:
        raise ValueError("table must hold 'published ...' and 'reproduced ...' columns")
    mask = pd.DataFrame(False, index=table.index, columns=table.columns)
    tol = 0.5 * 10.0 ** (-decimals) * (1 + 1e-9)
    for pub, rep, diff in pairs:
        p, r = _number_column(table, pub), _number_column(table, rep)
        bad = ~np.isnan(p) & ~(np.abs(r - p) <= tol)      # rows without a published value are not compared
        mask[rep] = bad
        if diff is not None:
            mask[diff] = bad
    return mask


def highlight_mismatches(table: pd.DataFrame, decimals: int = 4, uuid: str = "t",  # type: ignore[no-untyped-def]
                         precision: int | None = None):
    """The table styled for the page: mismatching reproduced values bold on an orange tint.

    Parameters
    ----------
    table : pandas.DataFrame
        As for :func:`mismatches`.
    decimals : int
        Printed decimals (also the displayed precision).
    uuid : str
        Fixed HTML id prefix, so the stored output is identical run to run: an HTML and CSS identifier (an ASCII
        letter, then ASCII letters, digits, ``-`` or ``_``), e.g. ``"ofs-table3"``.
    precision : int, optional
        Displayed decimals of every number (default ``decimals``), e.g. 2 for measured values beside
        published values read off a figure to whole metres.

    Returns
    -------
    pandas.io.formats.style.Styler
        Displays as HTML; a caption says what the highlight means.

    Raises
    ------
    TypeError
        ``uuid`` not a string.
    ValueError
        ``uuid`` not an identifier: it is written into the page's HTML ids and CSS selectors, where a space loses
        the highlight and a quote or ``>`` writes markup (fuzz 22a H).
    """
    decimals = count(decimals, "decimals", minimum=0)  # the int read: shown in the caption and the format
    mask = mismatches(table, decimals)
    uuid = text_argument(uuid, "uuid")   # a wrong type is a TypeError (issue 35)
    if not re.fullmatch(r"[A-Za-z][A-Za-z0-9_-]*", uuid):
        raise ValueError(f"uuid must be an HTML id prefix (an ASCII letter, then letters, digits, '-' or '_'), "
                         f"got {shown(uuid)}")
    css = "font-weight: bold; background-color: #F9D9C2"
    places = decimals if precision is None else count(precision, "precision", minimum=0)
    styler = table.style.format(precision=places, na_rep="—").set_uuid(uuid)
    styler = styler.apply(lambda _: np.where(mask, css, ""), axis=None)
    pairs = _pairs(table.columns)
    n = int(mask[[rep for _, rep, _ in pairs]].to_numpy().sum())
    total = int(sum(pd.to_numeric(table[pub], errors="coerce").notna().sum() for pub, _, _ in pairs))
    return styler.set_caption(f"{total - n} of {total} values reproduced at {decimals} decimals; "
                              "highlighted: reproduced value differs from the published one")


#: Floats below this magnitude (2⁵³) are integers exactly when whole (:func:`integral_index`).
_EXACT_INTEGERS = 2.0 ** 53


def integral_index(table: pd.DataFrame) -> pd.DataFrame:
    """The table with every float index level that holds only whole numbers shown as integers.

    A period of 3 s or a latency of -20 ms is printed "3" and "-20", not "3.0" and "-20.0"
    (the book's rule for people's numbers). Levels with any fractional value, or with a whole value of magnitude
    2⁵³ or more (beyond the integers a float holds exactly: ``1e300`` stays ``1e300``, not an overflowed int64),
    are left as they are.

    Parameters
    ----------
    table : pandas.DataFrame
        Any table; its values are not changed.

    Returns
    -------
    pandas.DataFrame
        A copy with the integral float index levels cast to ``int``.

    Raises
    ------
    TypeError
        If ``table`` is not a DataFrame.

    References
    ----------
    * Wickham, H. (2014). Tidy data. *Journal of Statistical Software*, 59(10).
    """
    if not isinstance(table, pd.DataFrame):
        raise TypeError(f"table must be a pandas DataFrame, got {type(table).__name__}")

    def fix(level: pd.Index) -> pd.Index:
        if level.dtype.kind == "f":
            v = level.to_numpy()
            if np.all(np.isfinite(v)) and np.all(np.abs(v) < _EXACT_INTEGERS) and np.all(v == np.round(v)):
                return pd.Index(np.round(v).astype(int), name=level.name)
        return level

    out = table.copy()
    if isinstance(out.index, pd.MultiIndex):
        out.index = out.index.set_levels([fix(lv) for lv in out.index.levels])
    else:
        out.index = fix(out.index)
    return out


# --------------------------------------------------------------------------- how a cell reads

#: The book's one notation for powers of ten: ``1.5×10⁻⁷`` (a times sign and superscript digits),
#: never ``1.5e-07`` or ``1.5×10^-7``.
_SUPERSCRIPT = str.maketrans("0123456789-+", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻⁺")

#: What a table cell shows instead of a raw missing, infinite or boolean value.
MISSING, INFINITE, YES, NO = "—", "∞", "yes", "no"

#: The rule every number formatter of the book follows (:func:`sci`, :func:`fusion.book.ledger.fmt`,
#: :func:`fusion.book.chapters.ci.readable`, ``fusion.book.chapters.lecture.sci``): the number is read by the
#: shared scalar reader (a string, bytes, ``None``, a complex number or a container is a :class:`TypeError` naming
#: the argument), and a non-finite one is printed as a word, never as ``nan`` or ``inf``: ``—`` for NaN (a missing
#: value), ``∞`` and ``-∞`` for the infinities. :func:`roundoff` (a check's residual) and
#: :func:`fusion.book.chapters.ci.excess_text` (a search's distance to the minimum) print quantities that are finite
#: by definition: they refuse non-finite ones by name, as a word would hide a failed check. Every one of them, and
#: :func:`rounded`, prints any finite magnitude (a subnormal, 1e300): rule 2's bounds guard computations, not print.
NONFINITE_RULE = "NaN -> MISSING, ±inf -> ±INFINITE; text and other non-numbers: TypeError naming the argument"


def _display_labels(labels: dict[str, str], name: str) -> None:
    """Labels of a table for display, by what each labels (fuzz 30b D3): each a text of the claim files' rule
    (``fusion.book.claims``: a visible character, no control or format character) and no two the same (their rows
    or columns would merge, "distinct as printed"); a ValueError naming ``name`` otherwise."""
    from fusion._counts import _first_repeat
    from fusion.book.claims import _text_problem

    for key, label in labels.items():
        if _text_problem(label) is not None:
            raise ValueError(f"{name} makes a label that {_text_problem(label)} (of {key})")
    repeat = _first_repeat(labels.values())
    if repeat is not None:
        keys = list(labels)
        raise ValueError(f"{name} gives {keys[repeat[0]]} and {keys[repeat[1]]} the same label {shown(repeat[2])} "
                         "(each labels a row or column, which would merge)")


def _nonfinite_word(x: float) -> str | None:
    """The book's word for a non-finite float (:data:`NONFINITE_RULE`), ``None`` for a finite one."""
    if math.isnan(x):
        return MISSING
    if math.isinf(x):
        return INFINITE if x > 0 else "-" + INFINITE
    return None


# A mantissa as power_of_ten takes it (ASCII digits, a sign, a decimal point between digits), one rule for both.
_MANTISSA = r"[-+−]?[0-9]+(?:\.[0-9]+)?"
_E_NUMBER = re.compile(rf"(?<![\w.])(?P<m>{_MANTISSA})[eE](?P<e>[-+]?[0-9]+)(?![\w.])")


#: Largest power of ten :func:`power_of_ten` writes (a float's decimal exponents lie within [-324, 308]).
_MAX_EXPONENT = 400


def power_of_ten(mantissa: str, exponent: int) -> str:
    """``mantissa×10ᵉ`` in the book's notation (``"1"`` as mantissa gives ``10ᵉ`` alone).

    Parameters
    ----------
    mantissa : str
        Digits of the mantissa, e.g. ``"1.5"`` or ``"-2.952"``.
    exponent : int
        Power of ten, within [-400, 400] (a float's decimal exponents lie within [-324, 308]).

    Returns
    -------
    str
        E.g. ``power_of_ten("1.5", -7) == "1.5×10⁻⁷"``, ``power_of_ten("1", 9) == "10⁹"``.

    Raises
    ------
    TypeError
        ``mantissa`` not a string, ``exponent`` not an integer.
    ValueError
        ``exponent`` outside [-400, 400]: no number the book prints has it; ``mantissa`` not the digits of a finite
        number (an optional sign, ASCII digits, optionally a decimal point followed by digits), e.g. ``""``,
        ``"nan"`` or ``"1.5×10²"``.
    """
    exponent = integer(exponent, "exponent")
    if abs(exponent) > _MAX_EXPONENT:
        raise ValueError(f"exponent must lie within [-{_MAX_EXPONENT}, {_MAX_EXPONENT}] (a printed number's power of "
                         f"ten), got {shown(exponent)}")
    if not isinstance(mantissa, str):
        raise TypeError(f"mantissa must be a str of digits, got {type(mantissa).__name__}")
    mantissa = text_argument(mantissa, "mantissa")  # its plain text (rule 19)
    if not re.fullmatch(_MANTISSA, mantissa):
        raise ValueError(f"mantissa must be the digits of a finite number (e.g. '1.5' or '-2.952'), got {shown(mantissa)}")
    sup = str(int(exponent)).translate(_SUPERSCRIPT)
    m = mantissa.replace("−", "-")
    if m in ("1", "+1"):
        return f"10{sup}"
    if m == "-1":
        return f"-10{sup}"
    return f"{m}×10{sup}"


def _printable_integer(x: object, name: str) -> int:
    """``int(x)`` for an integer the book prints exactly: one within the float range (about 1.8×10³⁰⁸ in magnitude).
    Beyond it, a ValueError naming ``name``: its literal would run to hundreds of digits where every float of that
    size is printed as a power of ten."""
    v = int(x)  # type: ignore[call-overload]
    if abs(v) > _FLOAT_MAX:
        raise ValueError(f"{name} = {shown(v)} is beyond the float range (about 1.8×10³⁰⁸): not a printable "
                         "number")
    return v


# The largest finite float, as an integer bound of _printable_integer.
_FLOAT_MAX = int(np.finfo(float).max)


def sci(x: float, digits: int = 4) -> str:
    """A number with ``digits`` significant digits, powers of ten written ``1.5×10⁻⁷``.

    The notation of every number the book prints (tables here; :func:`fusion.book.ledger.fmt`
    should write its powers of ten with :func:`power_of_ten` too). Missing values read ``—``,
    infinities ``∞`` and ``-∞``, booleans ``yes`` and ``no``, integers exactly.

    Parameters
    ----------
    x : float
        The number.
    digits : int
        Significant digits of a float (``{:g}`` rules: plain below 10⁴ᵈ, else a power of ten); a ``Decimal`` or
        ``Fraction`` is rounded as it is (half to even), not through its float, up to 15 digits.

    Returns
    -------
    str
        NaN and ``None`` (a missing cell) read ``—``, the infinities ``∞`` and ``-∞`` (:data:`NONFINITE_RULE`).

    Raises
    ------
    TypeError
        ``x`` is text, bytes, complex or a container (naming ``x``), ``digits`` not an integer.
    ValueError
        ``x`` an integer beyond the float range (its literal would run to hundreds of digits).
    """
    digits = count(digits, "digits")
    if isinstance(x, (bool, np.bool_)):
        return YES if x else NO
    if x is None or x is pd.NA:
        return MISSING
    return _significant(x, digits, power_of_ten)


def _significant(x: Any, digits: int, power: Callable[[str, int], str]) -> str:
    """The number rule shared by :func:`sci` and ``fusion.book.ledger.fmt``: ``{:g}`` digits, exact integers.

    Parameters
    ----------
    x : float or int
        The number (not a bool or a missing value: the callers decide those).
    digits : int
        Significant digits of a float.
    power : callable
        ``power(mantissa, exponent)`` writes a power of ten (:func:`power_of_ten` for the pages).

    Returns
    -------
    str
        An integer's exact digits, ``"0"``, the word of :data:`NONFINITE_RULE`, plain ``{:g}`` digits or
        ``power(mantissa, exponent)``.

    Raises
    ------
    TypeError
        ``x`` is text, bytes, complex, a bool, ``None`` or a container (naming ``x``); ``digits`` not an integer.
    ValueError
        ``x`` an integer beyond the float range.
    """
    digits = count(digits, "digits")
    if is_integer(x):
        return str(_printable_integer(x, "x"))
    given = x
    x = _real_number(x, "x", bound=None)  # TypeError naming x for text, complex, containers; the float range
    word = _nonfinite_word(x)  # the rule of every number formatter (NONFINITE_RULE)
    if word is not None:
        return word
    if x == 0:
        return "0"
    x = _exact_significant(given, x, digits)  # a Decimal or Fraction rounded as it is (fuzz 46b D3)
    text = f"{x:.{digits}g}"
    if "e" in text:
        mant, exp = text.split("e")
        return power(mant, int(exp))
    return text


#: Below this relative or absolute difference, a check's residual is round-off (:func:`roundoff`).
ROUNDOFF_EXPONENT = -12


def roundoff(value: float, exponent: int = ROUNDOFF_EXPONENT) -> str:
    """A round-off-sized difference for prose, tables or the ledger, the same on every machine.

    Round-off moves with the BLAS kernel that OpenBLAS picks for the processor and with the thread count, so its
    digits are never printed: below :math:`10^{e}` the text is ``"less than 10ᵉ"``; a larger value (a check that
    failed) is printed with :func:`sci` to two digits.

    Parameters
    ----------
    value : float
        A finite difference (absolute or relative); its magnitude is compared and printed (the size of a
        discrepancy: the sign of a round-off residual is itself round-off, so ``roundoff(-3.1e-9)`` is
        ``"3.1×10⁻⁹"``, as the prose around it says "differ by").
    exponent : int
        The power of ten it is compared with (default :data:`ROUNDOFF_EXPONENT`, -12).

    Returns
    -------
    str
        E.g. ``roundoff(1.7e-15) == "less than 10⁻¹²"``, ``roundoff(3.1e-9) == "3.1×10⁻⁹"``.

    Raises
    ------
    ValueError
        ``value`` not finite (a residual is finite by definition: a NaN means the check failed, and a word such as
        the formatters' ``—`` would hide it; the one exception to :data:`NONFINITE_RULE`), or ``exponent`` outside
        [-300, 300].
    TypeError
        ``value`` not a real number (text included), ``exponent`` not an integer.
    """
    exponent = count(exponent, "exponent", minimum=-300, maximum=300)  # 10.0**exponent within the float range
    v = abs(_printed_number(value, "value"))  # finite, any magnitude (the formatters' one rule)
    if v < 10.0 ** exponent:
        return f"less than {power_of_ten('1', exponent)}"
    return sci(v, 2)


def cell_text(text: str) -> str:
    """The text of one table cell as the book prints it.

    A whole cell reading ``NaN``, ``nan``, ``<NA>``, ``None`` or ``NaT`` becomes ``—``; ``inf`` becomes
    ``∞`` (``-inf``: ``-∞``); ``True`` / ``False`` become ``yes`` / ``no``; and every number in
    e-notation inside the text (``1e-09``, ``-2.952e+05``) is rewritten ``10⁻⁹``, ``-2.952×10⁵``.

    Parameters
    ----------
    text : str
        The cell's text as pandas printed it.

    Returns
    -------
    str
        ``text`` with a whole-cell NaN, None, infinity, True or False replaced by the book's mark, and e-notation as
        powers of ten.
    """
    text = text_argument(text, "text")
    core = text.strip()
    whole = {"NaN": MISSING, "nan": MISSING, "<NA>": MISSING, "&lt;NA&gt;": MISSING, "None": MISSING,
             "NaT": MISSING, "inf": INFINITE, "Infinity": INFINITE, "-inf": "-" + INFINITE,
             "-Infinity": "-" + INFINITE, "True": YES, "False": NO}
    if core in whole:
        return text.replace(core, whole[core])
    return _E_NUMBER.sub(lambda m: power_of_ten(m["m"], int(m["e"])) if abs(int(m["e"])) <= _MAX_EXPONENT
                         else m[0], text)


_CELL_OPEN = re.compile(r"<t[dh]\b")  # a cell's opening tag starts so and ends at the next ">"
_CELL_CLOSE = re.compile(r"</t[dh]>")


def _split_tags(text: str) -> list[str]:
    """``re.split(r"(<[^>]*>)", text)`` in one pass: texts and tags alternate, a tag being ``<`` up to the next ``>``.

    The regular expression scans to the end of ``text`` from every ``<`` that no ``>`` follows (quadratic work on
    ``"<" * n``, fuzz 22a Q3); a ``<`` without a ``>`` after it starts no tag, and neither does any later one.
    """
    parts, pos = [], 0
    while (start := text.find("<", pos)) >= 0 and (end := text.find(">", start)) >= 0:
        parts += [text[pos:start], text[start:end + 1]]
        pos = end + 1
    return parts + [text[pos:]]


def tidy_table_html(html: str) -> str:
    """An HTML table (pandas or a Styler) with every cell's text passed through :func:`cell_text`.

    Only the text between tags inside ``<td>`` and ``<th>`` changes; styles, ids and attributes do not. A cell
    spans its opening tag to the first closing ``</td>`` or ``</th>`` after it; an opening tag that no closing tag
    follows leaves the rest of ``html`` as it is. The work is linear in the length of ``html``.

    Parameters
    ----------
    html : str

    Returns
    -------
    str
        ``html`` with the text of every ``<td>`` and ``<th>`` cell passed through :func:`cell_text`; tags unchanged.
    """
    html = text_argument(html, "html")
    parts, pos = [], 0  # one pass (the regular expression <t[dh]...>(.*?)</t[dh]> was quadratic, fuzz 22a Q3)
    while (opening := _CELL_OPEN.search(html, pos)) is not None:
        end = html.find(">", opening.end())
        closing = _CELL_CLOSE.search(html, end + 1) if end >= 0 else None
        if closing is None:  # no cell can close after here
            break
        inner = "".join(p if p.startswith("<") else cell_text(p) for p in _split_tags(html[end + 1:closing.start()]))
        parts += [html[pos:end + 1], inner, closing[0]]
        pos = closing.end()
    return "".join(parts) + html[pos:]


def use_book_tables(shell: object | None = None) -> None:
    """Show every DataFrame and Styler of a notebook through :func:`tidy_table_html`.

    Called by :func:`fusion.book.style.use_book_style` (once at the top of every chapter), so
    tables built anywhere (the chapter helpers, a cell) print ``—``, ``∞``, ``yes``/``no`` and
    ``1.5×10⁻⁷``, never NaN, inf, True/False or e-notation. Outside IPython it does nothing.

    Parameters
    ----------
    shell : IPython.core.interactiveshell.InteractiveShell, optional
        The running shell (default: ``IPython.get_ipython()``).

    Raises
    ------
    TypeError
        ``shell`` given but not an IPython shell (it has no ``display_formatter`` with an HTML formatter).
    """
    if shell is not None and not hasattr(getattr(getattr(shell, "display_formatter", None), "formatters", None),
                                         "get"):
        raise TypeError(f"shell must be an IPython InteractiveShell (with a display_formatter), got "
                        f"{type(shell).__name__}")
    if shell is None:
        try:
            from IPython import get_ipython
        except ImportError:  # pragma: no cover - IPython is a book dependency
            return
        shell = get_ipython()
        if shell is None:
            return
    from pandas.io.formats.style import Styler

    fmt = shell.display_formatter.formatters["text/html"]  # type: ignore[attr-defined]

    def html(obj: object) -> str | None:
        raw = obj._repr_html_()  # type: ignore[attr-defined]
        return None if raw is None else tidy_table_html(raw)

    for kind in (pd.DataFrame, Styler):
        fmt.for_type(kind, html)


def _plain(key: object) -> object:
    """A row key as the caller wrote it: a numpy scalar as its Python value (``0``, not ``np.int64(0)``), also
    within a tuple (a MultiIndex row)."""
    if isinstance(key, tuple):
        return tuple(_plain(k) for k in key)
    return key.item() if isinstance(key, np.generic) else key


def _is_real(v: object) -> bool:
    """Whether a table cell is a real number by the package's one rule for scalars (``fusion._validation``'s
    ``_real_number``: ints, floats, numpy's, ``Decimal`` and ``Fraction``; not bools, text or complex numbers)."""
    try:
        _real_number(v, "cell")
    except (TypeError, ValueError):
        return False
    return True


def _frame(tab: object, name: str, columns: Collection[str], index: Collection[str] = (), maker: str = "",
           finite: Collection[str] = (), texts: Collection[str] = (), nonnegative: Collection[str] = (), *,
           unique: bool = False, rows: Collection[object] | Callable[[object], bool] | None = None,
           rows_are: str = "") -> Any:
    """The rule of every chapter function that reads a table another function made (fuzz 18/19, class D): ``tab``
    when it is a DataFrame holding ``columns`` (and the index levels ``index``), not empty; TypeError/ValueError
    naming ``name`` (and ``maker``, the function that makes it), never a KeyError or AttributeError from inside.

    The columns ``finite`` the caller computes with hold finite real numbers (not bools, not text; a ``Decimal``
    or ``Fraction`` is a number, as for the array reader), the columns
    ``texts`` it reads as text (statuses, labels it parses) hold strings in every row (issue 35: a NaN cell gave a
    NaN glue value, a missing cell was read as no status): a TypeError (wrong type) or ValueError (NaN, inf) naming
    ``name[column]`` and the row. The columns ``nonnegative`` hold finite numbers that are non-negative as well (an
    RMSE, a bound, a time: fuzz 24c, NEG).

    A column read (``columns``, ``finite``, ``texts``, ``nonnegative``) held twice is refused (fuzz 24d T: numpy's
    errors from inside, or one of the two read silently). ``unique``: the rows are keys (a method, a length, a
    record) and a repeated one is refused, naming ``name`` and the row (a row twice was counted twice, or drawn as a
    sequence). ``rows``: the row keys the maker gives (a collection, or a test of one key), described by
    ``rows_are``; a row that is not one is refused, naming it (an unknown method was listed as a method). A column of
    non-native byte order (``'>f8'`` here) is refused, naming it: pandas does not read one (fuzz 29b D1)."""
    if not isinstance(tab, pd.DataFrame):
        raise TypeError(f"{name} must be a DataFrame{f' (the result of {maker})' if maker else ''}, got "
                        f"{type(tab).__name__}")
    missing = [c for c in columns if c not in tab.columns] + [i for i in index if i not in tab.index.names]
    if missing:
        raise ValueError(f"{name} lacks the columns or index levels {missing}{f' (a result of {maker} holds them)' if maker else ''}")
    if tab.empty:
        raise ValueError(f"{name} is empty")
    made = f" (as {maker} makes it)" if maker else ""
    foreign = next((c for c, d in tab.dtypes.items() if isinstance(d, np.dtype) and not d.isnative), None)
    if foreign is not None:  # pandas reads native byte order only (fuzz 29b D1: its unnamed error, a false "differs")
        raise ValueError(f"{name}[{shown(foreign)}] holds numbers of non-native byte order ({tab[foreign].dtype.str}), "
                         f"which pandas does not read: give it in native order{made} (.astype(float))")
    twice = [c for c in dict.fromkeys((*columns, *finite, *texts, *nonnegative)) if c in tab.columns
             and isinstance(tab[c], pd.DataFrame)]
    if twice:
        raise ValueError(f"{name} has more than one column {shown(twice[0])}{made}")
    if unique and tab.index.has_duplicates:
        again = _plain(tab.index[tab.index.duplicated()][0])
        raise ValueError(f"{name} holds the row {shown(again)} more than once{made}: one row each")
    if rows is not None:
        known = rows if callable(rows) else rows.__contains__
        odd = next((r for r in tab.index if not known(r)), None)
        if odd is not None:
            raise ValueError(f"{name} holds the row {shown(_plain(odd))}, which is not "
                             f"{rows_are or 'a row it makes'}{made}")
    for c in dict.fromkeys((*finite, *nonnegative)):
        if c not in tab.columns:
            raise ValueError(f"{name} lacks the column {shown(c)}{made}")
        col = tab[c]
        if isinstance(col, pd.DataFrame):
            raise ValueError(f"{name} has more than one column {shown(c)}{made}")
        odd = next(((i, v) for i, v in zip(col.index, col.to_numpy()) if not _is_real(v)), None)
        if odd is not None:
            raise TypeError(f"{name}[{shown(c)}] must hold numbers{made}, got {shown(odd[1])} in row {shown(odd[0])}")
        bad = ~np.isfinite(col.to_numpy(dtype=float))
        if bad.any():
            raise ValueError(f"{name}[{shown(c)}] must be finite, got {shown(col.to_numpy()[bad][0])} in row "
                             f"{shown(col.index[bad][0])}")
        neg = col.to_numpy(dtype=float) < 0 if c in nonnegative else bad
        if neg.any():
            raise ValueError(f"{name}[{shown(c)}] must be non-negative, got {shown(col.to_numpy()[neg][0])} in row "
                             f"{shown(col.index[neg][0])}")
    for c in texts:
        if c not in tab.columns:
            raise ValueError(f"{name} lacks the column {shown(c)}{made}")
        odd = next(((i, v) for i, v in zip(tab.index, tab[c]) if not isinstance(v, str)), None)
        if odd is not None:
            raise TypeError(f"{name}[{shown(c)}] must hold a text in every row{made}, got {shown(odd[1])} in row "
                            f"{shown(odd[0])}")
    return tab


def _cell_number(tab: pd.DataFrame, row: object, column: object, name: str, positive: bool = False) -> float:
    """The number in cell (``row``, ``column``) of a table another function made (issue 35): a finite real number,
    else a ValueError naming ``name`` and the cell, never a message naming an inner argument (``value``) or a
    TypeError from ``float``. Call after :func:`_frame` (the column is there) and a check of the rows read.
    ``positive``: the cell holds a quantity that is positive by its definition (an RMSE, a NEES of a noisy
    filter; fuzz 24b TV), so 0 or a negative number is refused too (a ratio of them would divide by 0 or flip)."""
    x = tab.loc[row, column]
    if isinstance(x, (pd.Series, pd.DataFrame)):  # a repeated row or column label: which one is meant is unknown
        raise ValueError(f"{name} holds row {shown(row, 60)} or column {shown(column, 60)} more than once")
    ok = isinstance(x, (int, float, np.integer, np.floating)) and not isinstance(x, (bool, np.bool_))
    if not ok or not np.isfinite(x):
        raise ValueError(f"{name}[{shown(column, 60)}] at row {shown(row, 60)} must be a finite number, "
                         f"got {shown(x, 60)}")
    if positive and not x > 0:
        raise ValueError(f"{name}[{shown(column, 60)}] at row {shown(row, 60)} must be positive (an RMSE or a NEES), "
                         f"got {shown(x, 60)}")
    return float(x)
