"""Fuzz 52 C2, C5, D3: glue_all's atom rule for a Series' and an Index's labels and names, and for atom subclasses."""

from __future__ import annotations

import datetime
import enum
import pathlib
import time
from decimal import Decimal
from fractions import Fraction

import numpy as np
import pandas as pd
import pytest
from pandas.io.formats.style import Styler

from _helpers import glue_refused, glued


class _Opaque:
    """An object whose text is its address."""


_refused = glue_refused
_glued = glued


def _columns_named(label: object) -> pd.DataFrame:
    table = pd.DataFrame({"a": [1]})
    table.columns.name = label
    return table


def _multi_named(label: object) -> pd.MultiIndex:
    index = pd.MultiIndex.from_arrays([[1, 2], [3, 4]])
    index.names = ["a", label]
    return index


def _holders(label: object) -> list:
    """Every place a pandas object prints a label or a name, holding ``label``."""
    obj = pd.Index([label], dtype=object, tupleize_cols=False)
    multi = pd.MultiIndex.from_arrays([obj, [1]])
    return [pd.Series([1], index=obj), pd.Series([1], name=label), pd.Index([1], name=label),
            pd.Series([1], index=multi), pd.Series([1], index=pd.Index([1], name=label)),
            pd.Series([1, 2], index=_multi_named(label)),
            pd.DataFrame({"a": [1]}, index=pd.Index([1], name=label)),
            _columns_named(label), pd.DataFrame({"a": [1]}, index=obj).style, _columns_named(label).style,
            pd.Series(pd.Categorical(["x"], categories=["x", label])),
            pd.Categorical(["x"], categories=["x", label]), pd.CategoricalIndex(["x"], categories=["x", label])]


@pytest.mark.parametrize("where", range(13))
@pytest.mark.parametrize("label, error", [(_Opaque(), TypeError), (10**5000, ValueError),
                                          ((1.0, float("nan")), ValueError)], ids=["address", "digits", "nan"])
def test_c2_every_label_and_name_of_a_pandas_object_is_an_atom(where: int, label: object, error: type) -> None:
    """C2: a Series' index labels and name, an Index's name, MultiIndex levels and names, a table's (a Styler's)
    axis names and a categorical's categories were not walked: an address, an int of 5,001 digits (nothing glued) or
    ``(1.0, nan)`` was glued; refused as a DataFrame's labels are, naming values['k']."""
    holder = _holders(label)[where]
    _refused({"k": holder}, error)
    if not isinstance(holder, Styler):   # a Styler inside a container is refused by its type
        _refused({"k": [holder]}, error)


@pytest.mark.parametrize("missing", [float("nan"), pd.NA, pd.NaT, None])
def test_d3_a_series_missing_label_is_the_tables_own(monkeypatch: pytest.MonkeyPatch, missing: object) -> None:
    """D3: a Series' missing label (or name) is printed as a word, as a DataFrame's, and accepted by the same rule."""
    obj = pd.Index([missing, "a"], dtype=object)
    for value in (pd.Series([1, 2], index=obj), pd.DataFrame({"a": [1, 2]}, index=obj),
                  pd.Series([1, 2], name=missing)):
        assert list(_glued(monkeypatch, {"k": value})) == ["k"]


def _subclass(base: type, name: str) -> type:
    return type("Sub", (base,), {name: lambda self, *a: "nan"})


_ATOMS = [(float, (1.0,)), (int, (3,)), (str, ("a",)), (bytes, (b"a",)), (Decimal, ("1.5",)), (Fraction, (1, 3)),
          (datetime.date, (2020, 1, 2)), (datetime.datetime, (2020, 1, 2)), (datetime.timedelta, (1,)),
          (type(pathlib.Path()), ("/tmp",)), (np.float64, (1.0,)), (np.str_, ("a",)), (complex, (1, 2))]


@pytest.mark.parametrize("method", ["__repr__", "__str__", "__format__", "_repr_html_", "_repr_latex_"])
@pytest.mark.parametrize("base, args", _ATOMS, ids=[b.__name__ for b, _ in _ATOMS])
@pytest.mark.parametrize("place", [lambda v: v, lambda v: [v], lambda v: {v: 1}, lambda v: {"x": (v,)},
                                   lambda v: pd.DataFrame({"a": [v, "b"]}), lambda v: pd.Series([1], name=v),
                                   lambda v: pd.Series([1, 2], index=pd.Index([v, "b"], dtype=object)),
                                   lambda v: np.array([v], dtype=object)])
def test_c5_an_atom_subclass_printing_its_own_text_is_refused(base: type, args: tuple, method: str, place) -> None:
    """C5: a subclass of an atom type with a text method of its own (a float whose repr is 'nan', a random repr)
    was glued with its own text; refused naming values['k'] wherever an atom can be."""
    v = _subclass(base, method)(*args)
    _refused({"k": place(v)}, TypeError, rf"values\['k'\] .*{method}")


def test_c5_overrides_that_make_the_text_and_enum_members(monkeypatch: pytest.MonkeyPatch) -> None:
    """An override the base's text calls (a datetime's isoformat, an Interval's endpoint), an instance's display
    method, a 10**7-character repr and an Enum whose repr is its own are refused; an Enum member whose class adds
    methods only, a StrEnum / IntEnum / (str, Enum) member and a subclass adding no text method are glued as before."""
    class Iso(datetime.datetime):
        def isoformat(self, *a, **k):
            return "nan"

    class Long(int):
        def __repr__(self):
            return "x" * 10**7

    class Own(enum.Enum):
        A = 1

        def __repr__(self):
            return "nan"

    class Plain(float):
        pass

    inst = Plain(1.0)
    inst._repr_html_ = lambda: "nan"
    for v in (Iso(2020, 1, 2), Long(3), Own.A, inst, [Own.A]):
        _refused({"k": v}, TypeError)

    class Fine(enum.Enum):
        A = 1

        def twice(self) -> int:
            return 2 * self.value

    class S(enum.StrEnum):
        A = "a"

    class I(enum.IntEnum):
        A = 2

    class M(str, enum.Enum):
        A = "m"

    got = _glued(monkeypatch, {"a": Fine.A, "b": S.A, "c": I.A, "d": M.A, "e": Plain(0.5), "f": [S.A, Fine.A]})
    assert got["a"] is Fine.A and got["b"] == "a" and type(got["b"]) is str and got["c"] is I.A
    assert got["e"] == 0.5 and got["f"] == [S.A, Fine.A]


def test_c5_a_float_subclass_is_glued_as_itself_not_by_its_item(monkeypatch: pytest.MonkeyPatch) -> None:
    """A float subclass with an ``item`` method and ``ndim = 0`` was glued as what ``item()`` returned (any object,
    unchecked); only a NumPy scalar or 0-d array is read by its ``item``."""
    class Item(float):
        ndim = 0

        def item(self):
            return float("nan")

    got = _glued(monkeypatch, {"k": Item(0.25)})
    assert got["k"] == 0.25


def test_the_books_enums_are_atoms() -> None:
    """The package's StrEnum option types are atoms (their members glue as their text, as before)."""
    from fusion.book.glue import _own_text
    from fusion.book.chapters.chernoff.swarm import BenchStage
    from fusion.book.chapters.ofs.settings import FailureCase
    from fusion.book.chapters.time_registration import BenchClass
    from fusion.scenarios.fusion_networks import Network
    from fusion.scenarios.time_registration import Information, RegMethod
    from fusion.scenarios.wavelet_sensors import Signal
    for kind in (BenchStage, FailureCase, BenchClass, Network, Information, RegMethod, Signal):
        assert all(_own_text(m) is None for m in kind)


def test_c5_a_date_time_in_a_time_zone_of_its_own_is_refused(monkeypatch: pytest.MonkeyPatch) -> None:
    """A date-time's text prints its zone's offset and name: a tzinfo of another class than Python's, zoneinfo's,
    pytz's or dateutil's (here a random offset: a different text each run) was glued; the known zones are glued."""
    import random

    class Random(datetime.tzinfo):
        def utcoffset(self, dt):
            return datetime.timedelta(minutes=random.randint(0, 600))

        def tzname(self, dt):
            return "R"

        def dst(self, dt):
            return datetime.timedelta(0)

    for v in (datetime.datetime(2020, 1, 2, tzinfo=Random()), datetime.time(1, tzinfo=Random()),
              pd.Timestamp(datetime.datetime(2020, 1, 2, tzinfo=Random()))):
        _refused({"k": v}, TypeError, r"values\['k'\] .*time zone")
        _refused({"k": [v]}, TypeError, r"values\['k'\] .*time zone")
    known = [pd.Timestamp("2020", tz="Europe/Paris"), pd.Timestamp("2020", tz="UTC"),
             datetime.datetime(2020, 1, 2, tzinfo=datetime.timezone.utc), datetime.datetime(2020, 1, 2)]
    assert len(_glued(monkeypatch, {f"k{i}": v for i, v in enumerate(known)})) == 4


def test_c2_a_series_labels_are_counted_with_its_values() -> None:
    """An object Series' object labels are walked as its values are, and counted at ``_GLUE_OBJECT`` each with them:
    the edge of an object Series with an object index is half that of one with a RangeIndex."""
    from fusion._limits import MAX_WORK, work
    from fusion.book import glue as G
    assert (G._GLUE_VALUE, G._GLUE_OBJECT) == (10_000, 200)
    edge = (MAX_WORK - 10_000) // 400

    def make(n: int) -> pd.Series:
        return pd.Series(np.full(n, "a", dtype=object), index=pd.Index(np.full(n, "b", dtype=object)), name="s")

    assert G._glue_work(make(10)) == 200 * (10 + 10 + 1)   # its values, labels and name
    assert work((G._GLUE_VALUE + G._glue_work(make(edge - 1)),), "values") <= MAX_WORK  # just inside (not run)
    _refused({"k": make(edge + 1)}, ValueError, r"^values(\['k'\])? .*work budget")
