r"""The one rule for every text of a claim file (``fusion.book.claims``: fuzz 29a D1, fuzz 30a C4/D3).

Kept apart from ``fusion.book.claims`` (at the package's 1,000-line limit). A text holds no control or format
character (Unicode category Cc or Cf: a NUL, a right-to-left override that reverses the displayed text, a
zero-width space that makes ``mae\u200b`` another key printed as ``mae``; a tab and a line break are whitespace,
allowed) and no lone surrogate (category Cs: not a character of any text, it cannot be written as UTF-8, and the
ledger and the book are written as UTF-8); a text that must say something holds a visible character.

Decided corner cases (fuzz 30a D3): the zero-width joiners ZWNJ (U+200C) and ZWJ (U+200D) are format characters
and stay refused, even where a script or an emoji sequence uses them: the book's texts are English, and an
invisible joiner makes two texts (two quantity keys) that print alike. The Hangul fillers (U+115F, U+1160,
U+3164, U+FFA0) and the braille blank (U+2800) are letters and a symbol by category but print as blank space:
they count as invisible, so a text of only those (and spaces) is refused as empty; beside visible characters
they are accepted, as a space is.
"""

from __future__ import annotations

import functools
import re
import string
import sys
import unicodedata

from fusion._limits import work
from fusion._shown import shown
from fusion._validation import text
from fusion.book import _claim_text_ucd as _ucd

__all__: list[str] = []  # private module

#: The longest text of a claim file or a ledger record, in characters: the scans of :func:`text_problem` take at
#: most ~330 ns a character (an invisible character beyond the Basic Multilingual Plane; 3-15 ns others), so ~3 CPU-s.
MAX_TEXT = 10_000_000
#: Units of work (``fusion._limits.work``, about 10 ns each) of one character of the texts a claim file or a record
#: holds, its scans by :func:`text_problem` and :func:`format_problem`: measured on this shared machine (CPU time,
#: minimum of 3, texts of 2e6 characters) 2.4 + 1.2 ns a character of ASCII, 12.7 + 1.1 of ``é``, 367 + 0.8 of an
#: invisible character beyond the Basic Multilingual Plane (U+F0000, the worst), so 37 units: the budget's edge,
#: 27 million characters, about 10 CPU-s at the worst, 0.4 CPU-s of ``é``. Fuzz 53a C1: one text of 7e6 characters,
#: anchored once and aliased in 300 records, was scanned 300 times (34 CPU-s) before any budget counted it. A file
#: without aliases stays inside (at most 16 MB, so at most 16 million characters).
TEXT_CHAR_WORK = 37

#: Unicode categories of characters that show nothing by themselves: controls, format characters (zero-width
#: space and joiner, direction marks and overrides, the BOM), surrogates, private-use and unassigned code points,
#: separators (spaces) and combining marks.
_INVISIBLE = ("Cc", "Cf", "Cs", "Co", "Cn", "Zs", "Zl", "Zp", "Mn", "Me")
#: Characters of other categories that print as blank space: the Hangul fillers and the braille blank (D3).
_BLANK = frozenset("\u115f\u1160\u3164\uffa0\u2800")


def text_problem(value: str, required: bool = True) -> str | None:
    """What makes ``value`` not a text of a claim file, or None: more than ``MAX_TEXT`` characters, a control or
    format character (Cc, Cf; tab and line break allowed) or a lone surrogate (Cs) anywhere, or, when ``required``,
    no visible character (only spaces, invisible characters, combining marks, Hangul fillers or the braille blank)."""
    if len(value) > MAX_TEXT:  # fuzz 52 C1: 1e8 invisible astral characters took 50 CPU-s in the regular expression
        return f"holds {len(value):,} characters, more than {MAX_TEXT:,} (a text of a claim is a sentence or a paragraph)"
    # one regular-expression scan, not a Python loop (fuzz 50b C1: 65 ns a character, a text of 200 million took 58
    # CPU-s to be accepted; now 3 ns a character of an ASCII text, 15 ns of another)
    found = (_ASCII_REFUSED if value.isascii() else _refused()).search(value)
    if found is not None:
        c = found.group()
        if unicodedata.category(c) == "Cs":
            return (f"holds the lone surrogate U+{ord(c):04X}, not a character (the text cannot be written as "
                    "UTF-8; write the character it stands for)")
        return f"holds the invisible control or format character U+{ord(c):04X} (write the text without it)"
    if required and re.search(_visible_class(), value) is None:  # a regular expression too (fuzz 51 C1: a loop to the
        return "must not be empty (it holds no visible character)"  # first visible character, 12 CPU-s after 1e8 spaces)
    return None


#: The ASCII characters :func:`text_problem` refuses (the controls but tab and line break).
_ASCII_REFUSED = re.compile("[\x00-\x08\x0b-\x1f\x7f]")


@functools.lru_cache(maxsize=1)
def _refused_class() -> str:
    """The characters :func:`text_problem` refuses, as the text of one character class: categories Cc (but tab and
    line break), Cf and Cs of the running Python's Unicode database (the runs stored for its version,
    ``fusion.book._claim_text_ucd``, about 0.1 ms; derived again for another version, 0.08 CPU-s)."""
    runs = _stored_runs(_ucd.REFUSED) if unicodedata.unidata_version == _ucd.UNIDATA_VERSION else _refused_runs()
    return "[" + "".join(f"\\U{a:08x}-\\U{b:08x}" for a, b in runs) + "]"


@functools.lru_cache(maxsize=1)
def _visible_class() -> str:
    """The visible characters of :func:`text_problem`, as the text of one character class: every character but the
    categories of ``_INVISIBLE`` and the ``_BLANK`` ones (the runs stored for the running Python's Unicode database,
    ``fusion.book._claim_text_ucd``, about 1 ms; derived again for another version, 0.23 CPU-s)."""
    runs = _stored_runs(_ucd.INVISIBLE) if unicodedata.unidata_version == _ucd.UNIDATA_VERSION else _invisible_runs()
    return "[^" + "".join(f"\\U{a:08x}-\\U{b:08x}" for a, b in runs) + "]"


def _refused_runs() -> list[list[int]]:
    """The runs of ``_refused_class`` derived from the running Python's ``unicodedata`` (every code point)."""
    return _ranges([i for i in range(sys.maxunicode + 1)
                    if unicodedata.category(chr(i)) in ("Cc", "Cf", "Cs") and chr(i) not in "\t\n"])


def _invisible_runs() -> list[list[int]]:
    """The runs ``_visible_class`` excludes, derived from the running Python's ``unicodedata``."""
    return _ranges([i for i in range(sys.maxunicode + 1)
                    if chr(i) in _BLANK or unicodedata.category(chr(i)) in _INVISIBLE])


def _stored_runs(runs: str) -> list[list[int]]:
    """Runs written by ``_runs_text`` read back."""
    return [[int(a, 16), int(b or a, 16)] for a, _, b in (r.partition("-") for r in runs.split())]


def _runs_text(runs: list[list[int]]) -> str:
    """Runs as ``fusion.book._claim_text_ucd`` stores them: ``first-last`` or one code point, in hexadecimal."""
    return " ".join(f"{a:x}" if a == b else f"{a:x}-{b:x}" for a, b in runs)


def _ranges(codes: list[int]) -> list[list[int]]:
    """Increasing code points as [first, last] runs."""
    ranges: list[list[int]] = []
    for i in codes:
        if ranges and ranges[-1][1] == i - 1:
            ranges[-1][1] = i
        else:
            ranges.append([i, i])
    return ranges


def _refused() -> re.Pattern[str]:
    """:func:`_refused_class` compiled (``re``'s own cache keeps it)."""
    return re.compile(_refused_class())


def record_text(value: object, name: str) -> str:
    """A text of a ledger record (:class:`fusion.book.ledger.Claim`, its evidence and readings;
    ``fusion.book.exact.ExactComparison``): the plain ``str`` (rule 19, ``fusion._validation.text``) that
    :func:`text_problem` accepts, the claim files' rule (fuzz 49b C5: a lone surrogate in a record's text was accepted,
    and writing the ledger then failed with an unnamed UnicodeEncodeError). Emptiness is the caller's rule (a ``bound``
    or a ``reason`` may be empty).

    Raises
    ------
    TypeError
        ``value`` is not a string (rule 19), naming ``name``.
    ValueError
        ``value`` holds more than ``MAX_TEXT`` characters, a control or format character (tab and line break
        allowed) or a lone surrogate, naming ``name``.
    """
    plain = text(value, name)
    problem = text_problem(plain, required=False)
    if problem is not None:
        raise ValueError(f"{name} {problem}")
    return plain


#: A short format spec of a text's ``{name:spec}`` field: align, sign, ``#``, ``0``, a width and a precision of at
#: most two digits each, a grouping option and a type (``{x:.2f}``, ``{n:d}``, ``{p:.1%}``, ``{x:>8.3g}``).
SHORT_SPEC = r"[<>=^]?[-+ ]?#?0?\d{0,2}[,_]?(?:\.\d{1,2})?[bcdeEfFgGnosxX%]?"
#: A field name of a text: a glue value's name (no attribute, index or position).
FIELD = r"[A-Za-z_][\w-]*"


def format_problem(value: str) -> str | None:
    """What makes ``value`` a text ``fusion.book.claims.build_ledger`` cannot fill safely, or None: ``value.format_map(values)`` of a
    text with an unterminated ``{`` raises, and a spec such as ``{x:>3000000000}`` builds a text of gigabytes."""
    try:
        fields = [(f, spec, conv) for _, f, spec, conv in string.Formatter().parse(value) if f is not None]
    except ValueError as e:
        return f"not a text with {{name}} fields ({e}; a literal brace is written {{{{ or }}}})"
    for f, spec, conv in fields:
        if not re.fullmatch(FIELD, f):
            return f"field {{{f}}} must name a value (a name, no attribute, index or position)"
        if conv is not None:
            return f"field {{{f}!{conv}...}}: no conversion (write {{{f}}} or {{{f}:spec}})"
        if not re.fullmatch(SHORT_SPEC, spec):
            return (f"field {{{f}:{shown(spec, 40)}}}: the format spec must be a short one (as .2f, d, .1%, >8.3g: a "
                    "width and a precision of at most two digits, no nested field)")
    return None


def texts_work(chars: int, names: str) -> int:
    """The units of work of scanning texts of ``chars`` characters in all (``TEXT_CHAR_WORK`` units a character:
    :func:`text_problem` and :func:`format_problem`), refused beyond the work budget (rule 17) by a ValueError naming
    ``names``, before any text is scanned."""
    return work((chars,), f"{names} ({chars:,} characters to scan)", weight=TEXT_CHAR_WORK)
