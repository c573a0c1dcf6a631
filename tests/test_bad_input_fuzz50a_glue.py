"""Fuzz 50a's findings on glue_all's walk, fixed by fix57b by one rule for what an atom (a value, an entry of a
container, a key of a mapping, a cell or label of a table besides a container) may be: an object whose text is
bounded and deterministic. D1 (a table of Interval or Period cells or labels, a range in a cell, refused since the
walk looked into tables), D2 (an Enum member or a path as a key or label, refused since keys are walked), D3 (a
complex with nan in a table accepted as a missing word, printed ``1.0+NaNj``), D4 (an int beyond Python's 4,300-digit
text limit glued an empty output; with the limit lifted, 10**6 digits printed uncounted in 11 CPU-s)."""

from __future__ import annotations

import enum
import numbers
import pathlib
import sys
import time
from fractions import Fraction

import numpy as np
import pandas as pd
import pytest


class Colour(enum.Enum):
    RED = 1
    BLUE = (0.5, 2.0)


class Odd(enum.Enum):
    ADDRESS = object()   # its text prints the object's address
    NAN = float("nan")


class Opaque(numbers.Number):
    """A number whose text is Python's default, its address."""

    __hash__ = object.__hash__


def _glued(value: object) -> None:
    from fusion.book.glue import glue_all
    glue_all({"a": value})


def _refused_quickly(value: object, error: type[Exception], match: str) -> None:
    t = time.process_time()
    with pytest.raises(error, match=match):
        _glued(value)
    assert time.process_time() - t < 1.0


_S = pd.Series([1.0, 2.0, 3.0, 4.0])
_TABLES = {
    "cut column": pd.DataFrame({"bin": pd.cut([1.0, 2.0, 3.0], 2), "v": [1.0, 2.0, 3.0]}),
    "interval index": pd.DataFrame({"v": [1.0, 2.0]}, index=pd.IntervalIndex.from_breaks([0.0, 1.0, 2.0])),
    "groupby on cut": _S.groupby(pd.cut(_S, 2), observed=False).mean().to_frame(),
    "cut with infinite bins": pd.DataFrame({"v": [1.0, 2.0, 3.0]},
                                           index=pd.cut([1.0, 2.0, 3.0], [-np.inf, 2.0, np.inf])),
    "period column": pd.DataFrame({"p": pd.period_range("2020", periods=3, freq="M"), "v": [1.0, 2.0, 3.0]}),
    "range cell": pd.DataFrame({"o": [range(3), "x"]}),
    "enum index": pd.DataFrame({"v": [1.0, 2.0]}, index=[Colour.RED, Colour.BLUE]),
    "path cell": pd.DataFrame({"o": [pathlib.PurePosixPath("a/b")]}),
    "complex column": pd.DataFrame({"c": np.array([1 + 2j]), "f": [np.nan]}),
}


@pytest.mark.parametrize("name", sorted(_TABLES))
def test_d1_tables_of_pandas_scalars_ranges_enums_and_paths_are_glued(name: str) -> None:
    """D1: ordinary book tables (``pd.cut`` bins, a groupby on them, a period range; an Interval's infinite endpoint
    is printed as a word, as a table's own inf) were refused by TypeError by the walk of fix56a."""
    _glued(_TABLES[name])
    _glued(_TABLES[name].style)


def test_d2_enum_members_paths_and_pandas_scalars_are_atoms_everywhere() -> None:
    """D2: a dict keyed by an Enum member or a path was refused by TypeError since keys are walked; the same atoms
    as list entries and values."""
    _glued({Colour.RED: 1.0, Colour.BLUE: 2.0, pathlib.Path("x"): 3.0})
    _glued([Colour.RED, pathlib.PurePosixPath("y"), pd.Period("2020-01", "M"), pd.Interval(0.0, 1.0),
            pd.Timestamp("2020-01-01"), pd.Timedelta(1, "s"), range(5)])
    _glued(Colour.BLUE)
    _glued(pd.Series(pd.cut([1.0, 2.0, 3.0], 2)))


@pytest.mark.parametrize("value", [[Opaque()], {Opaque(): 1.0}, pd.DataFrame({"o": [Opaque()]}),
                                   [Odd.ADDRESS], {Odd.ADDRESS: 1.0}],
                         ids=["entry", "key", "cell", "enum value entry", "enum value key"])
def test_an_atom_whose_text_is_its_address_is_refused(value: object) -> None:
    """The other side: an object whose text is Python's default (its address, another text at every run) is refused
    by TypeError naming values['a'], also as an Enum member's value."""
    _refused_quickly(value, TypeError, r"^values\['a'\] must be a number, text, .*its text is its address")


def test_a_styler_inside_a_container_is_refused() -> None:
    """A Styler inside a list prints ``<pandas.io.formats.style.Styler at 0x...>``: refused by the same rule (fix56a
    charged it as a table and glued it); a Styler given as the value is glued (its HTML)."""
    df = pd.DataFrame({"a": [1.0]})
    _refused_quickly([df.style], TypeError, r"^values\['a'\] must be .*Styler.*its text is its address")
    _refused_quickly({"k": df.style}, TypeError, r"^values\['a'\] must be .*its text is its address")
    _glued(df.style)


@pytest.mark.parametrize("value", [[pd.Interval(0.0, np.inf)], {Odd.NAN: 1.0}, [Colour.RED, Odd.NAN],
                                   pd.Series([pd.Interval(-np.inf, 0.0)])],
                         ids=["interval entry", "enum key", "enum entry", "interval series"])
def test_atoms_printing_a_non_finite_number_are_refused_outside_a_table(value: object) -> None:
    """An Interval's endpoints and an Enum member's value are checked as numbers where they are: a NaN or infinite
    one outside a table is refused like the number itself (its text prints it)."""
    _refused_quickly(value, ValueError, r"^values\['a'\] must be finite")


@pytest.mark.parametrize("cell", [complex(1.0, np.nan), complex(np.nan, np.nan), np.complex128(complex(np.inf, 0))])
def test_d3_a_non_finite_complex_cell_is_refused(cell: complex) -> None:
    """D3: ``complex(1, nan)`` in an object column was accepted as a missing word, but a Styler prints
    ``1.000000+nanj`` (and a complex column ``1.0+NaNj``): refused as the value is, in an object or complex column
    or label; a real NaN cell is still glued as a word."""
    obj = pd.DataFrame({"o": [cell, 1.0]}, dtype=object)
    col = pd.DataFrame({"c": np.array([cell, 1 + 1j])})
    lab = pd.DataFrame({"v": [1.0, 2.0]}, index=np.array([cell, 1 + 1j]))
    for table in (obj, obj.style, col, col.style, lab):
        _refused_quickly(table, ValueError, r"^values\['a'\] must be finite")
    _glued(pd.DataFrame({"o": [np.nan, None, 1.0, 2 + 1j]}, dtype=object))


_BIG = 10**4300   # 4,301 digits: one more than Python's limit of int-to-str conversion


@pytest.mark.parametrize("where", ["value", "entry", "key", "cell", "label", "series", "fraction", "range",
                                   "enum", "interval"])
def test_d4_an_int_beyond_the_text_limit_is_refused_wherever_it_is(where: str) -> None:
    """D4: an int of 5,000 digits glued an empty output (IPython's formatter hit the 4,300-digit limit and swallowed
    the error). Refused naming values['a'] wherever an int can be; 4,300 digits (either sign) accepted."""
    def put(n: int) -> object:
        return {"value": lambda: n, "entry": lambda: [1.0, n], "key": lambda: {n: 1.0},
                "cell": lambda: pd.DataFrame({"o": [n]}),
                "label": lambda: pd.DataFrame({"v": [1.0]}, index=pd.Index([n], dtype=object)),
                "series": lambda: pd.Series([n], dtype=object), "fraction": lambda: [Fraction(n, 3)],
                "range": lambda: [range(n, n)], "enum": lambda: [enum.Enum("Big", {"A": n}).A],
                "interval": lambda: [pd.Interval(min(0, n), max(0, n))]}[where]()
    _glued(put(_BIG - 1))
    _glued(put(-(_BIG - 1)))
    _refused_quickly(put(_BIG), ValueError, r"^values\['a'\] must hold ints of at most 4,300 decimal digits")
    _refused_quickly(put(-_BIG), ValueError, r"^values\['a'\] must hold ints of at most 4,300 decimal digits")


def test_d4_the_interpreters_limit_is_followed_down_not_up() -> None:
    """With the limit lifted (0), an int of 10**6 digits printed in 11 CPU-s uncounted: refused at 4,300 digits, by
    its bit length (< 1 s); with a lower limit, that limit."""
    old = sys.get_int_max_str_digits()
    try:
        sys.set_int_max_str_digits(0)
        _refused_quickly([10**(10**6)], ValueError, r"^values\['a'\] must hold ints of at most 4,300 decimal")
        sys.set_int_max_str_digits(1000)
        _glued([10**1000 - 1])
        _refused_quickly([10**1000], ValueError, r"^values\['a'\] must hold ints of at most 1,000 decimal digits")
    finally:
        sys.set_int_max_str_digits(old)


def test_a_range_is_charged_by_its_length() -> None:
    """A range in a table cell is printed as its entries by pandas: charged as many list entries, so a range of
    10**8 is refused before the work; a range of 1,000 glued."""
    _glued(pd.DataFrame({"o": [range(1000)]}))
    _refused_quickly(pd.DataFrame({"o": [range(10**8)]}), ValueError, r"^values\['a'\] ask for more work")
