"""Glue many values into a chapter at once (myst-nb), rounded so stored outputs never flicker."""

from __future__ import annotations

from decimal import Decimal

import cmath
import collections
import datetime
import enum
import math
import numbers
import pathlib
import re
import sys
import types
from collections import OrderedDict, defaultdict
from collections.abc import Mapping
from fractions import Fraction
from typing import Any, TypeAlias, Union

import numpy as np
import pandas as pd
from pandas.api.extensions import ExtensionArray
from matplotlib.figure import Figure
from pandas.io.formats.style import Styler

from fusion._limits import MAX_WORK, work
from fusion.book._glue_axes import axis_units, by_type, columns_units, converted_label_sizes, entries_units, label_sizes
from fusion.book._glue_axes import field_units, keys_values, object_cells, prune_units
from fusion.book._glue_axes import object_dtype as _object_dtype
from fusion.book._glue_figure import figure_units
from fusion.book._glue_meter import GLUE_VISITS, Meter as _Meter, stored_items, stored_keys, stored_len
from fusion._validation import count, read_mapping, text
from fusion.book.tables import rounded
from fusion._shown import shown
from fusion._nesting import MAX_NESTING, nesting_error

# The type aliases below are importable but not in __all__: autodoc would file ``dict[...]`` under the module
# ``builtins`` and the source listings would link to a page that does not exist.
__all__ = ["glue_all"]

#: One value for the glue namespace: a number, a string, a figure or a table.
GlueValue: TypeAlias = Union[float, int, str, Figure, pd.DataFrame, Styler]
#: What a chapter's glue function returns: glue key → value (the keys are glue names, not method labels).
GlueValues: TypeAlias = dict[str, GlueValue]


#: A whole glue key (:func:`glue_all`): ASCII letters, digits, underscores and hyphens (every key of the book's
#: notebooks; a figure's key has hyphens), the rule of :func:`_glue_prefix` for the whole key.
_GLUE_KEY = re.compile(r"[A-Za-z0-9_-]+")


def _glue_key(key: object, name: str, many: bool = True) -> str:
    """``key`` as the plain text of a whole glue key, the one rule of every glue path (:func:`glue_all`,
    :func:`fusion.book.figures.glue_figure` and the chapters' ``glue_figures``; fuzz 36a D1, 38b C4): a str
    (TypeError naming ``name`` otherwise) of ASCII letters, digits, underscores and hyphens, not empty (ValueError
    naming ``name``: text that prints alike, ``é`` composed or decomposed, would be two keys). ``many``: ``name``
    holds the keys (a mapping), else it is the key."""
    which = "have glue keys" if many else "be a non-empty glue key"
    if not isinstance(key, str):
        raise TypeError(f"{name} must {'have str glue keys' if many else 'be a str (a glue key)'}, got "
                        f"{'the key ' if many else ''}{type(key).__name__} {shown(key, 60)}")
    key = text(key, f"{name} keys" if many else name)
    if not _GLUE_KEY.fullmatch(key):  # the prefixes' ASCII rule for the whole key (fuzz 35b D3, 36a D1)
        raise ValueError(f"{name} must {which} of ASCII letters, digits, underscores and hyphens"
                         f"{' (not empty)' if many else ''}, got {shown(key, 60)}")
    return key


def _checked_keep(store: object, values: object) -> dict[str, Any]:
    """The one rule of the chapters' ``keep(store, values)``, which store glue values for the claim texts.

    ``store`` a mutable mapping and ``values`` a mapping (TypeError naming them); every key a str (TypeError) that
    is an ASCII identifier (a ``{name}`` field of a claim text; :func:`_glue_prefix`'s rule for the whole key, as
    text that prints alike, ``é`` composed or decomposed, would be two keys: fuzz 36a D1; ValueError naming
    ``values``); a float finite (ValueError
    naming ``values[key]``, also given as a 0-d array or a :class:`~decimal.Decimal`). A key kept again takes the
    new value: re-running a notebook's cell recomputes it, and the claim texts read the store when the ledger is
    built, after every cell. Checked before ``store`` changes.

    Returns the values to keep, read once (``fusion._guards.read_mapping``: a mapping that is not a plain dict is
    read in one pass, fuzz 33b B4) with a 0-d array as its plain number (fuzz 33b D2: the store held the caller's
    array, which a later edit made NaN; the rule of fuzz 29a C1 for frozen records); ``values`` itself when it is a
    plain dict holding no 0-d array.
    """
    from collections.abc import MutableMapping

    from fusion._validation import instance_of, scalar

    instance_of(store, MutableMapping, "store"), instance_of(values, Mapping, "values")
    values = read_mapping(values, "values")
    for k, v in values.items():  # type: ignore[attr-defined]
        if not isinstance(k, str):
            raise TypeError(f"values must have str glue keys, got the key {shown(k, 60)}")
        if not (k.isascii() and k.isidentifier()):
            raise ValueError(f"values must have glue keys that are identifiers of ASCII letters, digits and "
                             f"underscores (a claim text's {{name}}), got {shown(k)}")
        _check_finite(k, v)  # glue_all's rule, the same function (fuzz 22b, KP)
        if isinstance(v, (float, np.floating, Decimal)) or (isinstance(v, np.ndarray) and v.ndim == 0):
            scalar(v, f"values[{k!r}]", tiny=True)
    if any(isinstance(v, np.ndarray) and v.ndim == 0 for v in values.values()):  # type: ignore[attr-defined]
        values = {k: v.item() if isinstance(v, np.ndarray) and v.ndim == 0 else v
                  for k, v in values.items()}  # type: ignore[attr-defined]
    return values  # type: ignore[return-value]


def _check_finite(key: str, value: object, meter: _Meter | None = None, counted: bool = False) -> None:
    """The book's finiteness rule of a glued value (:func:`glue_all` and the chapters' ``keep``): ValueError naming
    ``values[key]`` for a value :func:`_finite` refuses (TypeError naming it for a value of a type it does not take).
    ``meter`` and ``counted``: :func:`_finite`'s."""
    if not _finite(value, key, meter, counted):
        raise ValueError(f"values[{shown(key)}] must be finite, got {shown(value)} (a glued number is printed in the book)")


def _glue_prefix(prefix: object, name: str) -> str:
    """A glue-key prefix argument (the rule of every chapter function that names its glue keys after a caller's
    prefix, fuzz 18 F/E): a str (TypeError naming ``name`` otherwise) that keeps the keys identifiers (a claim text's
    ``{name}``) of ASCII letters, digits and underscores (ValueError naming ``name`` otherwise); returned unchanged.

    ASCII, not any Unicode identifier (fuzz 35b D3): a key is matched as the text it is, and non-ASCII text has
    several spellings that print alike (``é`` composed or decomposed; ``ﬁ`` and ``fi``, which Python's identifiers
    fold together by NFKC and a glue key does not); no normalisation is applied, so the caller's key is the key."""
    return _glue_key_part(prefix, name, "prefix", ("", "_x"))


def _glue_suffix(suffix: object, name: str) -> str:
    """A glue-key suffix argument (appended to a chapter's own keys, another pair's numbers): :func:`_glue_prefix`'s
    rule for the other end of the key (fuzz 36b B5), a str (TypeError naming ``name`` otherwise) of ASCII letters,
    digits and underscores, possibly empty (ValueError naming ``name`` otherwise); returned unchanged."""
    return _glue_key_part(suffix, name, "suffix", ("x", ""))


def _glue_id_part(rid: str, name: str, strip: str = "") -> str:
    """A record id made a glue-key part (``strip`` removed from its start, dashes as underscores), by
    :func:`_glue_prefix`'s rule (fuzz 36b D2): the part must keep the key an ASCII identifier, so that an id of a
    space, a dot or a brace (``"lec-a b"`` gave the key ``lec_rob_a b``), or of non-ASCII text whose composed and
    decomposed spellings print alike, is refused naming ``name`` (the caller's record), not glued under a key no
    claim text can name; returned as the part."""
    part = rid.removeprefix(strip).replace("-", "_")
    if not (part.isascii() and ("x" + part).isidentifier()):
        raise ValueError(f"{name} must be a record id of ASCII letters, digits, '-' and '_' (it becomes a glue key "
                         f"part), got {shown(rid, 60)}")
    return part


def _glue_key_part(part: object, name: str, kind: str, around: tuple[str, str]) -> str:
    """``part`` when it is a str and a key made with it (``around[0] + part + around[1]``) an ASCII identifier; else
    TypeError / ValueError naming ``name`` as a glue key ``kind`` (prefix or suffix)."""
    if not isinstance(part, str):
        raise TypeError(f"{name} must be a glue key {kind} (a str), got {type(part).__name__} {shown(part, 60)}")
    key = around[0] + part + around[1]
    if not (key.isascii() and key.isidentifier()):
        raise ValueError(f"{name} must be a glue key {kind} (ASCII letters, digits and underscores), got "
                         f"{shown(part, 60)}")
    return part


def _printed_float(value: object) -> object:
    """A NumPy float32 or float16 (a scalar or a 0-d array) as the shortest decimal that round-trips in its own dtype,
    the number it prints (``np.float32(0.654)`` -> 0.654, not its widening 0.6539999842643738; fuzz 26c q10, fuzz
    40b D2); any other value unchanged. The one rule of :func:`glue_all` and of a glued table cell."""
    v = value[()] if isinstance(value, np.ndarray) and value.ndim == 0 else value
    return float(str(v)) if isinstance(v, (np.float16, np.float32)) else value


def _longdouble_float(value: object, name: str) -> object:
    """A NumPy longdouble (a scalar or a 0-d array) as a Python float (fuzz 41b D3: ``.item()`` keeps a longdouble, so
    :func:`glue_all` glued ``np.longdouble('0.123456')`` unrounded and unconverted); ValueError naming ``name`` when
    the float would be another number, beyond float's range (``1e400`` overflows to inf, a non-zero ``1e-400``
    underflows to 0); a complex longdouble as a Python complex by the same rule on each part; any other value
    unchanged."""
    v = value[()] if isinstance(value, np.ndarray) and value.ndim == 0 else value
    if isinstance(v, np.clongdouble):
        try:
            parts = (_longdouble_float(v.real, name), _longdouble_float(v.imag, name))
        except ValueError:   # the value given shown, not its part (fuzz 43 D2)
            raise ValueError(f"{name} must be a number within float's range (a complex longdouble is glued as a "
                             f"complex), got {shown(v)}") from None
        return complex(*parts)  # type: ignore[arg-type]
    if not isinstance(v, np.longdouble):
        return value
    f = float(v)
    if np.isfinite(v) and (not math.isfinite(f) or (f == 0.0 and v != 0)):
        raise ValueError(f"{name} must be a number within float's range (a longdouble is glued as a float), got "
                         f"{shown(v)}")
    return f


def _glued_cell(table: object, row: object, column: object, name: str, lo: float | None = None,
                hi: float | None = None) -> float:
    """The cell ``table.loc[row, column]`` that a chapter glues, as a float by the glue rule (fuzz 22b, V): the row
    and the column present once each (read by label, never by position), the cell a finite number (TypeError for
    text or another non-number) within [``lo``, ``hi``] when given (an MSE, a share); errors name ``name``. A
    float32 (or float16) cell is read as the shortest decimal that prints it (0.654, not 0.6539999842643738: a
    table cast to float32 glues the numbers it shows)."""
    from fusion._validation import instance_of, scalar

    instance_of(table, pd.DataFrame, name)
    for what, labels, label in (("row", table.index, row), ("column", table.columns, column)):  # type: ignore[attr-defined]
        hits = int(np.sum(labels == label)) if label in labels else 0
        if hits != 1:
            raise ValueError(f"{name} must hold the {what} {shown(label)} once, got it {hits} times")
    cell = table.loc[row, column]  # type: ignore[attr-defined]
    cell = _printed_float(cell)   # the decimal a float32 prints (0.654), not its widening (fuzz 26c q10)
    return scalar(cell, f"{name}.loc[{shown(row)}, {shown(column)}]", lo, hi, tiny=True)


#: The atoms: what glue_all and ``keep`` take as they are, as a value, a container's entry, a mapping's key or a
#: table's cell or label alike (fix57b, fuzz 50a D1, D2), because their text is bounded and deterministic: numbers
#: (Python, NumPy, Decimal, Fraction; finite, an int of at most ``_int_digits()`` decimal digits), text, bytes,
#: None, dates, times and durations (``pd.Timestamp``, ``pd.Timedelta``), a ``pd.Period``, a ``pd.Interval`` (its
#: two endpoints are checked as numbers), an Enum member (its value is checked as an entry), a ``pathlib`` path, a
#: ``range`` (its start, stop and step checked as ints, charged by its length: pandas prints its entries), and a
#: figure. Containers are the ones :func:`_finite` looks into; anything else is refused by type (fuzz 26a G/D3: a
#: deque, array.array, dict view or generator printed ``nan`` unchecked), and so is an object whose text is
#: ``object``'s default (its address: not the same text twice), and a subclass of an atom type printing a text of
#: its own (``_own_text``, fuzz 52 C5; a table's, Series' or Index's labels and names are atoms too, fuzz 52 C2), or
#: of a container type (fuzz 54a C1).
_GLUE_LEAVES = (type(None), str, bytes, numbers.Number, np.generic, datetime.date, datetime.time, datetime.timedelta,
                pd.Period, pd.Interval, enum.Enum, pathlib.PurePath, range, Figure)
#: The containers whose entries are checked: their text prints their entries (a table: its object cells and labels,
#: ``_table_cells``; a mapping: its keys and its values, fuzz 49a C2, C3).
_GLUE_CONTAINERS = (list, tuple, set, frozenset, Mapping, pd.Series, pd.Index, np.ndarray, ExtensionArray,
                    pd.DataFrame, Styler)
#: Containers whose text restarts at each turn of a cycle (fuzz 49a C1): pandas prints its cells' containers three
#: levels deep itself (``pprint_thing``, no recursion guard), and a Series, Index or table met again is printed again
#: in full. A cycle reached while one of them is open is refused: its text would recurse (a RecursionError in the
#: kernel, 0.8 MB of traceback, nothing glued).
_GLUE_PANDAS = (pd.Series, pd.Index, ExtensionArray, pd.DataFrame, Styler)
#: The texts that print a container met again inside itself as ``[...]`` (``{...}``, ``...``): Python's list, tuple,
#: set, dict (OrderedDict, defaultdict) and NumPy's array texts. A cycle none of whose containers has one (a Counter
#: or another mapping holding itself) is refused: its text recurses.
_GUARDED_REPRS = frozenset({list.__repr__, tuple.__repr__, set.__repr__, frozenset.__repr__, dict.__repr__,
                            OrderedDict.__repr__, defaultdict.__repr__, np.ndarray.__repr__})



def _numpy_scalar_types() -> set[type]:
    """NumPy's own scalar types (``np.float64``, ``np.str_``, ``np.void``, ...): the subclasses of ``np.generic``
    that NumPy defines."""
    found, todo = set(), [np.generic]
    while todo:
        t = todo.pop()
        if t.__module__ == "numpy":
            found.add(t)
        todo += t.__subclasses__()
    return found


#: The atom types themselves (fuzz 52 C5): an atom of one of them has its own, bounded and deterministic text. A
#: subclass of one (of any class in their MROs, ``_ATOM_BASES``) is an atom when it changes none of it (``_own_text``).
_ATOM_TYPES = frozenset({type(None), bool, int, float, complex, str, bytes, Decimal, Fraction, datetime.date,
                         datetime.datetime, datetime.time, datetime.timedelta, pd.Timestamp, pd.Timedelta, pd.Period,
                         pd.Interval, range, pathlib.PurePath, pathlib.PurePosixPath, pathlib.PureWindowsPath,
                         pathlib.Path, pathlib.PosixPath, pathlib.WindowsPath, enum.Enum, enum.IntEnum, enum.StrEnum,
                         enum.Flag, enum.IntFlag, enum.ReprEnum, Figure} | _numpy_scalar_types())
_ATOM_BASES = frozenset(b for t in _ATOM_TYPES for b in t.__mro__)
#: The attributes that make an object's text (fuzz 52 C5): Python's text methods, attribute hooks (IPython looks
#: ``_repr_html_`` and the like up by ``getattr``), and an Enum member's parts of its text. Any name beginning with
#: ``_repr_`` or ``_ipython_`` too (IPython's display methods).
_TEXT_NAMES = frozenset({"__repr__", "__str__", "__format__", "__html__", "__getattr__", "__getattribute__",
                         "__class__", "_value_repr_", "_name_", "_value_"})
#: The instance attributes of an Enum member (its name, value, class and order).
_MEMBER_NAMES = frozenset({"_value_", "_name_", "__objclass__", "_sort_order_"})
#: A class's own bookkeeping, never an override of its base.
_CLASS_NAMES = frozenset({"__module__", "__qualname__", "__doc__", "__dict__", "__weakref__", "__slots__",
                          "__annotations__", "__orig_bases__", "__parameters__", "__firstlineno__",
                          "__static_attributes__", "__abstractmethods__", "_abc_impl", "__new__", "__init__",
                          "__init_subclass__"})

#: The container types of Python whose text is their entries' (fuzz 54a C1), with their MROs: a subclass of one of
#: them, or of a container of NumPy, pandas or the package (``_library_class``), is a container only when it changes
#: none of their text (``_own_text``).
_CONTAINER_BASES = frozenset(b for t in (list, tuple, set, frozenset, dict, types.MappingProxyType, OrderedDict,
                                         defaultdict, collections.Counter, collections.ChainMap,
                                         collections.UserDict) for b in t.__mro__)
#: The types :func:`_finite` needs not look at for a text of their own: no subclass, no instance attributes.
_PLAIN_CONTAINERS = frozenset({list, tuple, set, frozenset, dict, np.ndarray})
#: A ``collections.namedtuple`` class, whose generated ``__repr__`` and ``__getnewargs__`` a NamedTuple's class
#: holds (the same code): its text is its name and its fields' texts, deterministic (fuzz 54a C1).
_NAMEDTUPLE = collections.namedtuple("_NAMEDTUPLE", "a")


def _library_class(c: type) -> bool:
    """Whether the class ``c`` is an atom type's (``_ATOM_BASES``), one of Python's containers
    (``_CONTAINER_BASES``), or NumPy's, pandas' or the package's own class (fuzz 54a C1: their texts are theirs; the
    package's containers, ``ReadOnlyMapping``, its records' mappings and NamedTuples, print deterministic text):
    defined in a module of ``numpy``, ``pandas`` or ``fusion`` and found there by its qualified name (not a class
    that only says so)."""
    if c in _ATOM_BASES or c in _CONTAINER_BASES:
        return True
    module = getattr(c, "__module__", None)
    if not isinstance(module, str) or module.split(".")[0] not in ("numpy", "pandas", "fusion"):
        return False
    found: object = sys.modules.get(module)
    for part in str(getattr(c, "__qualname__", "<>")).split("."):
        found = getattr(found, part, None)
    return found is c


def _namedtuple_part(name: str, attr: object) -> bool:
    """Whether ``attr``, named ``name`` in a class, is what ``collections.namedtuple`` made (its ``__repr__``,
    ``__getnewargs__``: the same code as ``_NAMEDTUPLE``'s), not a method of the class's own."""
    made = _NAMEDTUPLE.__dict__.get(name)
    code = getattr(getattr(attr, "__func__", attr), "__code__", None)
    return code is not None and code is getattr(getattr(made, "__func__", made), "__code__", False)


def _known_zone(tz: object) -> bool:
    """Whether a date-time's ``tz`` (its ``tzinfo``) is None or a time zone of Python (``datetime.timezone``),
    ``zoneinfo``, pytz or dateutil: a date-time's text prints its zone's offset and name, which a ``tzinfo`` of
    another class computes as it likes (fuzz 52 C5's rule for the part of an atom's text: a random offset)."""
    t = type(tz)
    return tz is None or t is datetime.timezone or t.__module__.split(".")[0] in ("zoneinfo", "pytz", "dateutil")


def _own_text(v: object, plain: set[type] | None = None, container: bool = False, meter: _Meter | None = None,
              key: str = "key") -> str | None:
    """The attribute by which ``v``, an atom whose type is not one of ``_ATOM_TYPES``, would print a text of its own
    (fuzz 52 C5: a float subclass whose ``__repr__`` is ``'nan'`` glued ``nan``), or None. ``container``: ``v`` is
    a container, whose base types are Python's, NumPy's, pandas' and the package's (``_library_class``; fuzz 54a C1:
    a list, dict, ndarray, Series subclass or a NamedTuple whose ``__repr__`` or ``_repr_pretty_`` printed ``nan``
    was glued), by the same rule; what ``collections.namedtuple`` made is a NamedTuple's base text.

    Every class of its type's MRO that is no atom type's (``_ATOM_BASES``) may add attributes but not define a text
    method (``_TEXT_NAMES``) nor, but for an Enum member, override an attribute of the atom types in the MRO (a
    ``datetime`` subclass's ``isoformat`` is its ``str``); an attribute that is the atom type's own (the one Enum's
    metaclass copies into a ``(str, Enum)`` class: ``Enum.__repr__``, ``str.__format__``; an Enum's ``_value_repr_``
    None or its mixed-in type's ``__repr__``) is no override. Its instance attributes likewise (IPython finds a
    ``_repr_html_`` there). ``plain``: the types already found to pass (a cache for one call), updated; ``meter``
    (its ``plain``, and the objects whose instance attributes passed) charged each scan before it is made (fuzz 66a
    C1, C2: ``GLUE_ATTR`` an attribute), ValueError naming ``values[key]`` beyond the budget."""
    t, inst = type(v), getattr(v, "__dict__", None)
    plain = meter.plain if meter is not None else plain
    inst = None if meter is not None and id(v) in meter.scanned else inst   # that object's attributes passed
    if plain is not None and t in plain and (not stored_len(inst) or stored_keys(inst) <= _MEMBER_NAMES):
        return None
    mro = t.__mro__
    base = _library_class if container else _ATOM_BASES.__contains__
    bases = [b for b in mro if base(b)]
    member = isinstance(v, enum.Enum)
    own = [] if plain is not None and t in plain else [(c.__dict__, False) for c in mro if not base(c)]
    own += [(inst, True)] * isinstance(inst, dict)
    if meter is not None:
        meter.scan(sum(stored_len(attrs) for attrs, _ in own), key)
    for attrs, instance in own:
        for name, attr in stored_items(attrs):
            if type(name) is not str:   # fuzz 68a C5, C6: a name IPython's getattr matches but no text test reads
                return f"an attribute named by a {type(name).__name__}, not a str"
            text_name = (name.startswith(("_repr_", "_ipython_")) or name == "__html__" if instance   # an Enum
                         else name in _TEXT_NAMES or name.startswith(("_repr_", "_ipython_")))         # member's _name_
            if name == "__dict__" and not instance and not isinstance(attr, types.GetSetDescriptorType):
                return name   # a class's own ``__dict__`` hides the instance's attributes IPython reads
            if name in _CLASS_NAMES or not (text_name or (not member and any(name in b.__dict__ for b in bases)
                                                           and not (container and instance and name[:1] == "_"
                                                                    and not callable(attr)))):
                continue   # a container's private data attribute (a Series' _name) is its state, not an override
            if not instance and any(b.__dict__.get(name, _CLASS_NAMES) is attr for b in bases):   # the atom type's
                continue
            if not instance and container and _namedtuple_part(name, attr):   # a NamedTuple's own repr
                continue
            if name == "_value_repr_" and (attr is None or any(b.__dict__.get("__repr__") is attr for b in bases)):
                continue
            return name
    if plain is not None:
        plain.add(t)
    if meter is not None and stored_len(inst):
        meter.scanned[id(v)] = v
    return None


def _table_labels(labels: pd.Index) -> list[pd.Index]:
    """The indexes of labels a table prints for ``labels`` (its rows or columns): its levels for a MultiIndex (each
    value once), else itself; only those holding objects (:func:`_object_dtype`)."""
    levels = list(labels.levels) if isinstance(labels, pd.MultiIndex) else [labels]
    return [lv for lv in levels if _object_dtype(lv.dtype)]


def _axes(v: pd.Series | pd.Index | pd.DataFrame | Styler) -> tuple[list[pd.Index], list[object]]:
    """The label indexes and the names that ``v`` prints besides its values (fuzz 52 C2: a Series' index and name
    and an Index's name were not walked): a table's (a Styler's table's) row and column labels and their names; a
    Series' index labels, the index's names and its own name; an Index's names (its values are its entries). Names
    that are None (none given: not printed) are left out."""
    v = v.data if isinstance(v, Styler) else v
    if isinstance(v, pd.DataFrame):
        axes, names = [v.index, v.columns], list(v.index.names) + list(v.columns.names)
    elif isinstance(v, pd.Series):
        axes, names = [v.index], list(v.index.names) + [v.name]
    else:
        axes, names = [], list(v.names)
    return axes, [n for n in names if n is not None]


def _table_size(table: pd.DataFrame | Styler | pd.Series | pd.Index) -> int:
    """How many object cells, labels and names ``_table_cells`` gives for ``table`` (a table, a Series or an
    Index), known without visiting them."""
    table = table.data if isinstance(table, Styler) else table
    axes, names = _axes(table)
    labels = sum(len(lv) for ax in axes for lv in _table_labels(ax)) + len(names)
    if not isinstance(table, pd.DataFrame):
        return labels
    return table.shape[0] * sum(1 for d in table.dtypes if _object_dtype(d)) + labels


def _table_units(table: pd.DataFrame | Styler | pd.Series | pd.Index) -> int:
    """The units of ``_table_size``'s entries: each by its column's or labels' dtype (``atom_units``), a name at
    ``_GLUE_OBJECT`` (fuzz 63a C1: a Series' 2**22 labels with a time zone ran 34.95 CPU-s charged 200 units each)."""
    table = table.data if isinstance(table, Styler) else table
    axes, names = _axes(table)
    units = sum(entries_units(lv.dtype, len(lv), lv.to_numpy, _GLUE_OBJECT) for ax in axes for lv in _table_labels(ax))
    units += len(names) * _GLUE_OBJECT
    if isinstance(table, pd.DataFrame):
        units += columns_units(table, _GLUE_OBJECT)
    return units


def _is_missing_cell(cell: object) -> bool:
    """Whether a table cell is missing or a real number that is not finite: a table prints it as a word (NaN, inf,
    <NA>, NaT, None), in an object column as in a numeric one (not looked into). Not a complex number (fuzz 50a D3:
    ``complex(1, nan)`` prints ``1.000000+nanj`` in a Styler, ``1.0+NaNj`` in a complex column: a number with nan,
    refused as a value is)."""
    if cell is None or cell is pd.NA or cell is pd.NaT:
        return True
    if isinstance(cell, (float, np.floating)):
        return not math.isfinite(cell)
    if isinstance(cell, Decimal):  # a signalling NaN is no word: pandas cannot print it (fuzz 52 C4)
        return not cell.is_finite() and not cell.is_snan()
    return isinstance(cell, (np.datetime64, np.timedelta64)) and bool(np.isnat(cell))


def _table_cells(table: pd.DataFrame | Styler | pd.Series | pd.Index) -> list[object]:
    """The entries :func:`_finite` walks in ``table`` besides its values (a Styler: its table; fuzz 49a C2: pandas
    formats each visible object cell in full, a cell holding a list of 1e8 printed floats ran 29.5 CPU-s charged as
    one table): the cells of a table's object columns, and the object labels (row and column labels, MultiIndex
    levels) and the names (of the rows, the columns, a Series, an Index: ``_axes``, fuzz 52 C2) of a table, Series
    or Index, missing ones and non-finite real numbers of the atom types themselves left out (a table prints them as
    words, as in a numeric column; fuzz 52 D3: a Series' labels as a table's); a numeric column is not looked into."""
    table = table.data if isinstance(table, Styler) else table
    cells: list[object] = []
    if isinstance(table, pd.DataFrame):
        cols = [j for j, d in enumerate(table.dtypes) if _object_dtype(d)]
        # a categorical column of more categories than rows without its unused ones (fuzz 61a C3: 16 columns of
        # 2**25 categories boxed, 29.3 CPU-s; fuzz 62a C2: only those, charged, ``pruned_columns``)
        cells = list(object_cells(table.iloc[:, cols]).ravel(order="F")) if cols else []
    axes, names = _axes(table)
    for ax in axes:
        for lv in _table_labels(ax):
            cells += list(lv.to_numpy(dtype=object))
    cells += names
    # an Interval cell or label (``pd.cut``'s bins) is its endpoints, an infinite one printed as a word (``(2.0, inf]``)
    # as the table's own non-finite number (fix57b, fuzz 50a D1); a float (finite: a float64 too) has nothing more to
    # check, not walked (pd.cut's 10**6 bins: 1.4 CPU-s, 7.3 walking their endpoints); a subclass of an atom type is
    # walked (fuzz 52 C5: its text may be its own)
    cells = [e for c in cells for e in ((c.left, c.right) if type(c) is pd.Interval else (c,))]
    return [c for c in cells if not (c is None or c is pd.NA or c is pd.NaT
                                     or (type(c) in _ATOM_TYPES and (_is_missing_cell(c) or isinstance(c, float))))]


def _complex_table_finite(table: pd.DataFrame | Styler | pd.Series) -> bool:
    """Whether every entry of ``table``'s complex columns and complex labels (a table's or a Series') is finite (a
    complex with nan prints as a number with nan, ``1.0+NaNj``: fuzz 50a D3), checked at once (vectorised)."""
    table = table.data if isinstance(table, Styler) else table
    arrays = ([table.iloc[:, j].to_numpy() for j, d in enumerate(table.dtypes)
               if isinstance(d, np.dtype) and d.kind == "c"] if isinstance(table, pd.DataFrame) else [])
    for labels in _axes(table)[0]:
        levels = list(labels.levels) if isinstance(labels, pd.MultiIndex) else [labels]
        arrays += [lv.to_numpy() for lv in levels if isinstance(lv.dtype, np.dtype) and lv.dtype.kind == "c"]
    return all(bool(np.isfinite(a).all()) for a in arrays)


def _int_digits() -> int:
    """The most decimal digits an int glued may have: 4,300, Python's default limit of int-to-str conversion, or the
    interpreter's current limit (``sys.get_int_max_str_digits()``, 0 for none) when it is smaller. Fuzz 50a D4: an
    int of 5,000 digits glued an empty output (IPython's formatter hit the limit and swallowed the error); with the
    limit lifted, an int of 10**6 digits took 11 CPU-s to print, uncounted (the conversion is quadratic)."""
    limit = sys.get_int_max_str_digits()
    return 4300 if limit == 0 else min(4300, limit)


def _check_int(v: int, key: str) -> None:
    """ValueError naming ``values[key]`` when the int ``v`` has more decimal digits than ``_int_digits()``, told by
    its bit length (no conversion; an exact comparison only within a bit of the limit)."""
    limit, bits = _int_digits(), v.bit_length()
    if bits <= 3 * limit:   # |v| < 2**bits <= 8**limit: at most limit digits
        return
    if bits > 4 * limit + 1 or abs(v) >= 10**limit:   # |v| >= 2**(bits - 1) > 16**limit: more digits
        raise ValueError(f"values[{shown(key)}] must hold ints of at most {limit:,} decimal digits (Python's limit of "
                         f"int-to-str conversion; its text would not be printed), got an int of about "
                         f"{int(bits * math.log10(2)) + 1:,} digits")


#: The marker of :func:`_finite`'s walk after a container's entries: its printed size is then complete.
_EXIT = object()


def _add_printed(outer: list[int] | None, size: list[int]) -> None:
    """Add a child container's printed ``size`` ([entries, units, levels]) to its container's ``outer`` (None: the
    value itself, held by no container)."""
    if outer is not None:
        outer[0] += size[0]
        outer[1] += size[1]
        outer[2] = max(outer[2], size[2] + 1)


def _finite(value: object, key: str = "key", meter: _Meter | None = None, counted: bool = False) -> bool:
    """False for a number that is NaN or infinite, and for a missing-value marker (``pd.NA``, ``NaT``).

    Numbers are floats, complex numbers, NumPy scalars, Decimals (a signalling NaN included) and numeric arrays
    (every entry; a 0-d array is its number). Containers are looked into, as their text prints their entries:
    lists, tuples, sets, a mapping's keys and values (fuzz 49a C3), a Series or Index, a pandas extension array
    (``pd.array``, Categorical, SparseArray: the arrays a Series holds), an object or structured array (fuzz 22a
    D1), a DataFrame's object cells and labels and a Styler's table (fuzz 49a C2: ``_table_cells``), the labels and
    names of a Series or Index too (fuzz 52 C2) and a categorical's categories. A table's
    missing cell or non-finite real number is not refused: a table prints it as a word; what a cell holds is checked
    by the rule of every container. Atoms (``_GLUE_LEAVES``, :func:`glue_all`'s Notes) are checked alike wherever
    they are: an int's digits, an Interval's endpoints, an Enum member's value, a range's ints (fix57b); a subclass
    of an atom type or of a container type printing a text of its own is refused (``_own_text``, fuzz 52 C5, 54a
    C1).

    Raises
    ------
    TypeError
        A value, or an entry of a container, of another type (:data:`_GLUE_LEAVES`, :data:`_GLUE_CONTAINERS`):
        a deque, ``array.array``, dict view, generator, masked array (whose text prints ``--``), an object whose
        text is its address (a Styler inside a container), a subclass of an atom type or of a container type
        printing a text of its own, ..., naming ``values[key]``.
    ValueError
        An int of more decimal digits than ``_int_digits()``, naming ``values[key]``. Containers nested more than
        ``fusion._nesting.MAX_NESTING`` (64) deep, naming ``values[key]``; entries
        beyond ``meter``'s allowance (fuzz 46a C2, C3), naming ``values[key]``, when a container is reached, before
        its entries are visited; a container that holds itself where its text would recurse (fuzz 49a C1): inside
        a Series, Index, table or pandas array (``_GLUE_PANDAS``), or on a cycle none of whose containers has a
        text that prints ``[...]`` (``_GUARDED_REPRS``: a Counter holding itself), naming ``values[key]``.

    ``meter`` (a fresh one when None) is charged for the entries of every container reached (``_container_work``)
    but ``value`` itself when ``counted`` (its caller counted it: ``_glue_work``), as its text prints them: a
    container reached again by another path (not one holding itself, printed ``[...]``) is charged again its whole
    printed size, memoised (fuzz 47 C3: ``[[[0.5] * 200] * 200] * 200`` was charged 600 entries and printed 8e6), and
    refused when its nesting there would be more than ``MAX_NESTING`` deep.
    """
    meter = _Meter() if meter is None else meter
    # each value with the number of containers around it, whether its entries are already counted, and the printed
    # size of the container holding it; a container's printed [entries, units, levels] (its own entries, its child
    # containers' printed sizes, its levels of nesting) is complete when its exit marker is popped, then memoised by
    # id: a container reached again by another path is charged it (fuzz 47 C3: its text is printed at each path)
    todo: list[tuple[Any, int, bool, list[int] | None]] = [(value, 0, counted, None)]
    printed: dict[int, list[int]] = {}   # by id, the containers reached: complete, or open (their entries visited)
    open_ids: dict[int, int] = {}        # the open containers: 0 pandas, 1 text unguarded, 2 guarded ([...])
    open_stack: list[int] = []           # the open containers, outermost first (the walk is depth first)
    open_pandas = 0                      # how many of them are pandas objects (``_GLUE_PANDAS``)
    tainted: set[int] = set()            # containers whose memo counted an outer open container as [...] (fuzz 48)
    pinned: list[object] = []            # the containers reached, kept alive: no id is reused during the call
    while todo:
        v, depth, done, outer = todo.pop()
        if v is _EXIT:                   # every entry of the container ``depth`` (its id) visited
            open_pandas -= open_ids.pop(depth) == 0
            open_stack.pop()
            _add_printed(outer, printed[depth])
            continue
        if v is pd.NA or v is pd.NaT:
            return False
        if (isinstance(v, np.ma.MaskedArray) or not isinstance(v, _GLUE_LEAVES + _GLUE_CONTAINERS)
                or (type(v).__repr__ is object.__repr__ and not (v is value and isinstance(v, Styler)))):
            # an object whose text is its address (fix57b), a Styler inside a container too: only the value itself
            # is glued as its HTML
            why = " (its text is its address)" if type(v).__repr__ is object.__repr__ else ""
            raise TypeError(f"values[{shown(key)}] must be a number, text, a date or time, a Period, Interval, Enum "
                            f"member, path or range, a figure, a table or a list, tuple, set, mapping, Series, Index, "
                            f"pandas or NumPy array of them, got {type(v).__name__} {shown(v, 60)}{why}"
                            + (f" inside {type(value).__name__}" if v is not value else ""))
        if type(v) not in _ATOM_TYPES and not isinstance(v, _GLUE_CONTAINERS):
            own = _own_text(v, meter=meter, key=key)   # an atom type's subclass printing its own text (fuzz 52 C5)
            if own is not None:
                raise TypeError(f"values[{shown(key)}] must hold atoms whose text is their type's (a subclass of an "
                                f"atom type must not define {own}), got {type(v).__name__} {shown(v, 60)}"
                                + (f" inside {type(value).__name__}" if v is not value else ""))
        if isinstance(v, _GLUE_CONTAINERS) and type(v) not in _PLAIN_CONTAINERS:
            own = _own_text(v, container=True, meter=meter, key=key)   # a container subclass's own text (fuzz 54a C1)
            if own is not None:   # its type's name only: its text is not to be trusted (nor its size)
                raise TypeError(f"values[{shown(key)}] must hold containers whose text is their type's (a subclass of "
                                f"a list, tuple, set, mapping, NumPy array, Series, Index, table or pandas array must "
                                f"not define {own}), got a {type(v).__name__}"
                                + (f" inside {type(value).__name__}" if v is not value else ""))
        here = None
        if isinstance(v, _GLUE_CONTAINERS):
            if id(v) in open_ids:  # a container that holds itself: its text prints [...] there
                cycle = open_stack[open_stack.index(id(v)):]
                if open_pandas or not any(open_ids[i] == 2 for i in cycle):   # fuzz 49a C1
                    raise ValueError(f"values[{shown(key)}] must not hold a container that holds itself inside a "
                                     f"Series, Index, table or pandas array, nor a cycle of containers none of whose "
                                     f"texts prints [...] (a {type(v).__name__} here): its text would recurse")
                # the containers opened inside it print it as [...] here but in full from outside the cycle: their
                # memoised sizes hold for this path only (fuzz 48 C1, C2)
                tainted.update(cycle[1:])
                continue
            if id(v) in tainted:   # such a container reached again: its printed size depends on the path
                raise ValueError(f"values[{shown(key)}] must not reach a container of a cycle of containers by more "
                                 f"than one path: its printed size depends on the path (a {type(v).__name__} inside "
                                 f"the cycle printed [...] on one path and in full on another)")
            if id(v) in printed:   # reached again by another path, printed again in full: its memoised size
                entries, units, levels = printed[id(v)]
                if depth + levels > MAX_NESTING:  # its deepest container nested MAX_NESTING deep or more
                    raise nesting_error(f"values[{shown(key)}]", itself=False)
                meter.take(entries, units, key)
                _add_printed(outer, printed[id(v)])
                continue
            if depth >= MAX_NESTING:  # its text would recurse (fuzz 30a D4: a RecursionError in the kernel)
                raise nesting_error(f"values[{shown(key)}]", itself=False)
            if not done:   # its logical size before any conversion (fuzz 57a C1: a RangeIndex(10**10) category)
                _logical_check(v, key)
            n, units = (0, 0) if done else _container_work(v)  # done: its container counted it (a Series' array)
            # a table inside a container is printed as a table (the value itself is counted by ``_glue_work``)
            units += (_GLUE_TABLE if depth and isinstance(v, (pd.DataFrame, Styler)) else 0)
            units += 0 if done else _numeric_units(v) + axis_units(v, key)   # numeric entries (fuzz 57a C1), levels
            units += prune_units(v)   # a table's categorical columns read without unused categories (fuzz 62a C2)
            meter.take(n, units, key)  # charged before its entries are visited (fuzz 46a C2, C3)
            pinned.append(v)
            kind = 0 if isinstance(v, _GLUE_PANDAS) else 2 if type(v).__repr__ in _GUARDED_REPRS else 1
            open_ids[id(v)] = kind
            open_pandas += kind == 0
            open_stack.append(id(v))
            here = printed[id(v)] = [n, units, 1]
            todo.append((_EXIT, id(v), True, outer))
        inner = depth + 1
        if isinstance(v, int):   # (a bool, an IntEnum) its decimal text within Python's limit (fuzz 50a D4)
            _check_int(v, key)
        elif isinstance(v, numbers.Rational) and not isinstance(v, np.generic):   # a Fraction: its two ints
            _check_int(v.numerator, key), _check_int(v.denominator, key)
        elif isinstance(v, Decimal):
            if not v.is_finite():
                return False
        elif isinstance(v, pd.Interval):   # its endpoints, as numbers (fuzz 50a D1)
            if not all(math.isfinite(e) for e in (v.left, v.right) if isinstance(e, float)):
                return False
            todo += [(e, inner, False, outer) for e in (v.left, v.right) if not isinstance(e, float)]
        elif isinstance(v, enum.Enum):     # its value, printed in its text (fuzz 50a D2)
            todo.append((v._value_, inner, False, outer))   # the value its text prints, not a ``value`` property
        elif isinstance(v, range):         # its ints, then its entries as pandas prints them
            for e in (v.start, v.stop, v.step):
                _check_int(e, key)
            n = max(0, (v.stop - v.start + v.step - (1 if v.step > 0 else -1)) // v.step)
            meter.take(n, n * _GLUE_NESTED, key)
        elif isinstance(v, (datetime.datetime, datetime.time)) and not _known_zone(v.tzinfo):
            raise TypeError(f"values[{shown(key)}] must hold dates and times whose time zone is Python's, zoneinfo's, "
                            f"pytz's or dateutil's (its offset and name are printed), got one in a "
                            f"{type(v.tzinfo).__name__}")
        elif isinstance(v, (np.datetime64, np.timedelta64)):
            if np.isnat(v):
                return False
        elif isinstance(v, (pd.Series, pd.Index, pd.DataFrame, Styler)):
            # its values (a table's object cells), its labels and names, counted by ``_container_work`` (fuzz 49a
            # C2, fuzz 52 C2: a Series' index and name, an Index's name, by a table's rule)
            if not isinstance(v, pd.Index) and not _complex_table_finite(v):
                return False
            if isinstance(v, (pd.Series, pd.Index)):
                todo.append((v.to_numpy(), inner, True, here))
            todo += [(e, inner, False, here) for e in _table_cells(v)]
            if isinstance(v.dtype if not isinstance(v, (pd.DataFrame, Styler)) else None, pd.CategoricalDtype):
                todo.append((v.dtype.categories, inner, False, here))   # printed: "Categories (n, object): [...]"
        elif isinstance(v, ExtensionArray):   # its entries as objects: pd.NA, NaN, NaT, as the Series shows them
            todo.append((np.asarray(v, dtype=object), inner, True, here))
            if isinstance(v.dtype, pd.CategoricalDtype):
                todo.append((v.dtype.categories, inner, False, here))
        elif isinstance(v, np.ndarray):
            if v.dtype.names:
                todo += [(v[n], inner, True, here) for n in v.dtype.names]
            elif v.dtype.kind == "O":
                todo += [(e, inner, False, here) for e in v.flat]
            elif v.dtype.kind in "mM":
                if np.isnat(v).any():
                    return False
            elif v.dtype.kind in "fc" and not np.isfinite(v).all():
                return False
        elif isinstance(v, np.void) and v.dtype.names:   # a structured scalar: its fields, as a 0-d structured array's
            todo.append((np.asarray(v), inner, False, outer))   # (fuzz 52 C3: a NaN field was glued)
        elif isinstance(v, (float, complex, np.floating, np.complexfloating)):
            if not cmath.isfinite(v):
                return False
        elif isinstance(v, (Mapping, list, tuple, set, frozenset)):
            # a mapping's keys and values read once: its text prints both (fuzz 49a C3: a NaN key was glued)
            entries = [e for kv in v.items() for e in kv] if isinstance(v, Mapping) else v
            # its plain floats checked here, not walked one by one (~0.1 us an entry instead of ~1.5 us)
            if not all(math.isfinite(e) for e in entries if type(e) is float):
                return False
            todo += [(e, inner, False, here) for e in entries if type(e) is not float]
    return True


#: Units of work (``fusion._limits.work``, about 10 ns each) of what :func:`glue_all` checks and glues, measured outside
#: a kernel (CPU time, minimum of 3, shared machine; fuzz 45b C7: 10**6 floats were accepted and ran ~100 CPU-s).
#: A value: 54-67 us (10,000 floats, texts or 3-lists; fuzz 45b measured 103 us), weighed 100 us for a kernel's
#: display message. An entry of a list, tuple, set or dict value: 2.1 us (one list of 10**6 floats, 2.12 CPU-s; a
#: numeric array is vectorised: 10**7 entries in 0.01 s). A DataFrame: 1.0-2.7 ms (10 x 2 to 10**6 cells, its text
#: truncated). A Styler: 0.9 ms at 10 x 2, then 5.6-12.6 us a cell (10**4 cells 126 ms, 10**6 cells 5.6 s). A figure:
#: 31-34 ms (one axes, audited and saved as PNG; ``_glue_figure.figure_units``, by its drawn points). The book's
#: largest call glues 118 values (1.2e6 units). A table inside a container is printed as a table too, and charged
#: ``_GLUE_TABLE`` where :func:`_finite` reaches it (fuzz 49a, fix56a: ``[[df] * 300] * 300`` of a 2 x 1 DataFrame,
#: 90,000 printed tables at 0.27 ms, was charged as list entries and ran 24.6 CPU-s; now refused before the work).
_GLUE_VALUE, _GLUE_ENTRY, _GLUE_TABLE, _GLUE_CELL = 10_000, 300, 300_000, 1_000
#: Fuzz 46a C2, C3 (measured as above, 10**6 entries, minimum of 3, shared machine under load ~11): an entry of an
#: object array, object Series or Index, or pandas extension array (``pd.array``, Categorical; visited as objects,
#: one by one): 1.0-1.3 us visited by :func:`_finite`, 1.1-1.3 us glued (its text is truncated): 200 units. An
#: entry of a container inside a value (a list of lists): 1.7 us visited, 3.5 us glued (1000 lists of 1000 floats,
#: 3.46 CPU-s: the text prints every inner list): 400 units. A numeric array: ``_GLUE_NUMBER`` (vectorised).
#: Fuzz 49a C2: a table's object cell (and label) is such an entry, and what it holds is printed as a Series cell's:
#: one cell holding ``[[[0.5] * 99] * 99] * 99`` (980,299 printed entries, 3.9e8 units) is glued in 4.2 CPU-s as a
#: DataFrame (its text and its HTML), 2.1 CPU-s as an object Series (machine shared, load ~8).
_GLUE_OBJECT, _GLUE_NESTED = 200, 400
#: The entries :func:`_finite` may reach inside containers the caller did not count (a list of lists) in one call:
#: they are counted as they are reached, so the ones visited before a refusal cost at most 10**6 x 1.7 us, ~1.7
#: CPU-s (fuzz 46a C2: 4500 lists of 4500 floats ran 37.7 CPU-s, counted as 4500 entries). A container reached again
#: is counted again by its printed entries, not visited (fuzz 47 C3: ``[[[0.5] * 90] * 90] * 90``, 729,000 printed
#: entries, is accepted and glued in 2.5 CPU-s; at 200, 8e6 printed entries, it ran 16.8 CPU-s and is now refused in
#: 0.002 CPU-s; time.process_time, OPENBLAS_NUM_THREADS=1, machine shared). The plain floats of a list, tuple, set
#: or mapping are checked where it is reached, not walked (a list of 400,000 and a dict of 400,000: 0.03 CPU-s, 1.0
#: walked one by one), so the weights above stay upper bounds.
_GLUE_VISITS = GLUE_VISITS
#: The containers whose own entries ``_glue_work`` counts when a value is one (a dict, not any mapping).
_GLUE_COUNTED = (list, tuple, set, frozenset, dict, pd.Series, pd.Index, ExtensionArray, np.ndarray)


def _container_work(v: object) -> tuple[int, int]:
    """The entries of the container ``v`` that :func:`_finite` visits one by one and their units (``_GLUE_*``; an
    entry of a pandas dtype of costlier atoms, an Interval, a date-time with a time zone, a Period, by
    ``atom_units``, fuzz 63a C1):
    a list, tuple or set its length, a mapping its keys and values, at ``_GLUE_NESTED``; an object array, an object
    (or non-NumPy dtype) Series or Index, an extension array its size, a DataFrame or Styler its (table's) object
    cells and labels (``_table_size``), at ``_GLUE_OBJECT``, known without visiting (an Interval, Period or date-time
    of a Python container or an object dtype by its type, ``by_type``); a structured array holding
    objects at most one object per 8 bytes of an element; a numeric array 0 (its entries: ``_numeric_units``). A table inside a
    container is charged ``_GLUE_TABLE`` more by :func:`_finite`, where it reaches it."""
    if isinstance(v, (pd.Series, pd.Index)):   # its values, labels and names (fuzz 52 C2)
        n = len(v) if _object_dtype(v.dtype) else 0
        return n + _table_size(v), entries_units(v.dtype, n, v.to_numpy, _GLUE_OBJECT) + _table_units(v)
    if isinstance(v, (pd.DataFrame, Styler)):
        return _table_size(v), _table_units(v)
    if isinstance(v, Mapping):   # its keys and its values
        return 2 * len(v), by_type(2 * len(v) * _GLUE_NESTED, lambda: keys_values(v), _GLUE_NESTED, True)
    if isinstance(v, ExtensionArray):
        return len(v), entries_units(v.dtype, len(v), lambda: np.asarray(v, dtype=object).ravel(), _GLUE_OBJECT)
    if isinstance(v, np.ndarray):   # a structured one's fields each read (fuzz 67a C3)
        n = int(v.size) * max(1, v.dtype.itemsize // 8) if v.dtype.hasobject else 0
        return n, entries_units(v.dtype, n, lambda: v.flat, _GLUE_OBJECT) + field_units(v.dtype)
    return len(v), by_type(len(v) * _GLUE_NESTED, lambda: v, _GLUE_NESTED, True)  # type: ignore[arg-type]


#: Fuzz 57a C1: a numeric entry (of a numeric array, Series, Index or table column, or a numeric label) is checked
#: at once (``np.isfinite``) after its container is converted (``Index.to_numpy``, ``np.asarray``): 0.15-0.7 ns an
#: entry measured here (10**7 entries, minimum of 3, float64, a broadcast view, a float Index, a Series, a
#: DatetimeIndex, complex; time.process_time, OPENBLAS_NUM_THREADS=1, shared machine), weighed 1 unit (rounded up
#: to a whole unit) by its logical size, not by what holding it costs: a ``pd.RangeIndex(10**12)``, a
#: ``np.broadcast_to(1.0, (10**10,))`` view or a categorical's ``RangeIndex(10**10)`` categories cost nothing to
#: hold and were charged 0, then converted (a raw MemoryError, "Unable to allocate 7.28 TiB").
_GLUE_NUMBER = 1


def _logical_sizes(v: object) -> list[int]:
    """The logical sizes (entries, not bytes held) of what :func:`_finite` converts for the container ``v``: its
    values (an array's shape product, a table's cells), each axis of labels of a Series or table (a Styler's table)
    that it converts (fuzz 62a C1) and an Index itself, with a CategoricalIndex's categories and a MultiIndex's
    levels (``label_sizes``), and the
    categories of a categorical and of each categorical column of a table (fuzz 60a C1: a table has no ``dtype``,
    its columns' categories were not counted); empty for a Python container (its entries are visited, counted)."""
    v = v.data if isinstance(v, Styler) else v
    if isinstance(v, np.ndarray):   # a structured one's fields with their subarrays (fuzz 58a C1)
        return [int(np.prod(v.shape, dtype=object)) * _dtype_entries(v.dtype)]
    if not isinstance(v, (pd.Series, pd.Index, pd.DataFrame, ExtensionArray)):
        return []
    # an Index's values are its labels: counted once (``label_sizes``), not as its shape too
    sizes = [] if isinstance(v, pd.Index) else [int(np.prod(v.shape, dtype=object))]
    axes = _axes(v)[0] if isinstance(v, (pd.Series, pd.DataFrame)) else [v] if isinstance(v, pd.Index) else []
    # a Series' or table's axis only where the glue converts it (fuzz 62a C1: ``converted_label_sizes``)
    sizes += [n for ax in axes for n in (label_sizes(ax) if ax is v else converted_label_sizes(ax))]
    dtypes = list(v.dtypes) if isinstance(v, pd.DataFrame) else [v.dtype]   # not hashed: that reads the categories
    return sizes + [n for d in dtypes if isinstance(d, pd.CategoricalDtype) for n in label_sizes(d.categories)]


def _dtype_entries(dtype: np.dtype) -> int:
    """The entries of one element of an array of ``dtype`` that :func:`_finite` converts and checks: 1 for a plain
    dtype; for a structured one, each field's (nested structured fields alike) times its subarray shape's product:
    ``[('a', 'f8', (10**5,))]`` holds 10**5 (fuzz 58a C1: such a field was counted once, then ``v['a']`` of shape
    ``(N, 10**5)`` converted: a raw MemoryError, or 46.7 CPU-s accepted). Each distinct dtype is read once."""
    memo: dict[int, int] = {}     # by id, the structured dtypes read: the entries of one element
    pinned: list[np.dtype] = []   # the dtypes read, kept alive: no id is reused during the call

    def split(d: np.dtype) -> tuple[int, np.dtype]:   # a subarray field: its shape's product and its base dtype
        return (int(np.prod(d.subdtype[1], dtype=object)), d.subdtype[0]) if d.subdtype is not None else (1, d)

    todo = [split(dtype)[1]]   # without recursion: a dtype may nest thousands of levels deep
    while todo:
        d = todo[-1]
        if not d.names or id(d) in memo:
            todo.pop()
            continue
        inner = [split(d.fields[n][0]) for n in d.names]
        unread = [b for _, b in inner if b.names and id(b) not in memo]
        if unread:
            todo += unread
            continue
        todo.pop()
        pinned.append(d)
        memo[id(d)] = sum(c * (memo[id(b)] if b.names else 1) for c, b in inner)
    count, base = split(dtype)
    return count * (memo[id(base)] if base.names else 1)


def _logical_check(v: object, key: str) -> None:
    """ValueError naming ``values[key]`` when the parts of the container ``v`` that :func:`_finite` converts
    (``_logical_sizes``) hold more than ``fusion._limits.MAX_INPUT_ELEMENTS`` entries together (2**25, the input
    budget of an array argument: rule 9, read by shape before any copy or conversion), fuzz 57a C1. The parts are
    summed, not the largest taken (fuzz 61a C3: 16 categorical columns of 2**25 - 10 categories each passed, one by
    one, and were converted: 29.3 CPU-s; 40 of them a raw MemoryError)."""
    from fusion._limits import MAX_INPUT_ELEMENTS

    n = sum(_logical_sizes(v))
    if n > MAX_INPUT_ELEMENTS:
        raise ValueError(f"values[{shown(key)}] holds a {type(v).__name__} of {n:.3g} entries (its values, labels "
                         f"and categories summed, counted by their logical size), beyond the input budget (at most "
                         f"{MAX_INPUT_ELEMENTS:,}, fusion._limits.MAX_INPUT_ELEMENTS): checking it would convert "
                         "them all")


def _numeric_units(v: object) -> int:
    """The units (``_GLUE_NUMBER`` each) of the numeric entries :func:`_finite` converts and checks at once in the
    container ``v``, by their logical size: a numeric array's (a structured one's fields), a numeric Series' or
    Index's values, a table's or Series' complex columns and complex labels (``_complex_table_finite``); the object
    ones are counted by ``_container_work``, a categorical's categories where :func:`_finite` reaches them, a
    Styler's cells by ``_GLUE_CELL``; a table's other numeric columns and labels are not converted (its text is
    truncated), only their logical size is checked (``_logical_check``)."""
    if isinstance(v, np.ndarray):
        return 0 if v.dtype.hasobject and not v.dtype.names else int(v.size) * _dtype_entries(v.dtype) * _GLUE_NUMBER
    if not isinstance(v, (pd.Series, pd.Index, pd.DataFrame)):
        return 0
    n = len(v) if isinstance(v, (pd.Series, pd.Index)) and not _object_dtype(v.dtype) else 0
    if isinstance(v, pd.DataFrame):
        n = v.shape[0] * sum(1 for d in v.dtypes if isinstance(d, np.dtype) and d.kind == "c")
    if isinstance(v, (pd.Series, pd.DataFrame)):
        for ax in _axes(v)[0]:
            levels = list(ax.levels) if isinstance(ax, pd.MultiIndex) else [ax]
            n += sum(len(lv) for lv in levels if isinstance(lv.dtype, np.dtype) and lv.dtype.kind == "c")
    return n * _GLUE_NUMBER


def _glue_work(value: object, key: str = "") -> int:
    """The units of work of gluing ``value`` (``_GLUE_VALUE`` and the weights beside it), beyond ``_GLUE_VALUE``:
    a container by its own entries (``_container_work``, a list's at ``_GLUE_ENTRY``) and its numeric entries by
    their logical size (``_numeric_units``; ValueError naming ``values[key]`` for a part beyond the input budget,
    ``_logical_check``, fuzz 57a C1); what is inside them is counted as :func:`_finite` reaches it. ValueError naming
    ``values[key]`` beyond ``MAX_WORK`` units alone with its ``_GLUE_VALUE`` (fuzz 63a C1), before reading it."""
    if isinstance(value, _GLUE_CONTAINERS):
        _logical_check(value, key)
        levels = axis_units(value, key)   # fuzz 59a C2; a table's are charged where _finite reaches it (not counted)
        units = _glue_units(value) + _numeric_units(value) + (levels if isinstance(value, _GLUE_COUNTED) else 0)
        if _GLUE_VALUE + units > MAX_WORK:   # its own refusal, naming it (``work`` counts at least 1)
            work((_GLUE_VALUE + units,), f"values[{shown(key)}] ({type(value).__name__}, entries weighed by kind)")
        return units
    return figure_units(value, key) if isinstance(value, Figure) else 0   # by its drawn points (fuzz 63a C3)


def _glue_units(value: object) -> int:
    """``_glue_work``'s units of the container ``value`` but its numeric entries (a figure value: ``figure_units``)."""
    if isinstance(value, Styler):
        return _GLUE_TABLE + _GLUE_CELL * int(value.data.size)
    if isinstance(value, pd.DataFrame):
        return _GLUE_TABLE
    if isinstance(value, (list, tuple, set, frozenset)):   # an Interval, Period, date-time by its type (``by_type``)
        return by_type(_GLUE_ENTRY * len(value), lambda: value, _GLUE_ENTRY, True)
    if isinstance(value, dict):   # its keys and its values (fuzz 49a C3)
        return by_type(_GLUE_ENTRY * 2 * len(value), lambda: keys_values(value), _GLUE_ENTRY, True)
    if isinstance(value, _GLUE_COUNTED):
        return _container_work(value)[1]
    return 0


def glue_all(values: Mapping[str, Any], decimals: int | None = None) -> None:
    """Glue every ``key: value`` pair with ``display=False``.

    Parameters
    ----------
    values : mapping of str to object
        Glue keys (prefixed with the chapter's short id) and values. Floats are rounded to
        ``decimals`` when it is given; NumPy scalars are converted to Python numbers (a longdouble to a float, then
        rounded), a float32 or float16 (also a 0-d array) to the shortest decimal that round-trips in its own dtype, the number it prints
        (``np.float32(0.654)`` is glued as 0.654, not 0.6539999842643738).
        Matplotlib figures are checked by :func:`fusion.book.figures.audit_figure` (which raises
        on a figure that breaks the book's figure rules), glued, then closed.
    decimals : int, optional
        Decimals of floats (see :func:`fusion.book.tables.rounded`); unrounded if ``None``.

    Notes
    -----
    One rule for what a value, an entry of a container, a key of a mapping and a cell or label of a table may be
    besides a container (an atom): an object whose text is bounded and deterministic. These are numbers (Python,
    NumPy, Decimal, Fraction; an int of at most 4,300 decimal digits, Python's limit of int-to-str conversion, or
    the interpreter's current limit when it is smaller), text and bytes, None, dates, times and durations (also
    ``pd.Timestamp``, ``pd.Timedelta``), a ``pd.Period``, a ``pd.Interval`` (its endpoints are numbers: ``pd.cut``'s
    bins), an Enum member (its value is checked as an entry: its text prints it), a ``pathlib`` path, a ``range``
    (its start, stop and step are ints; charged by its length, as pandas prints its entries), and a figure. An
    object whose text is Python's default (its address, not the same twice; a Styler inside a container) is refused.
    A subclass of one of these types is an atom only when its text is its type's: it defines no text method
    (``__repr__``, ``__str__``, ``__format__``, ``_repr_html_`` and IPython's other ``_repr_*`` methods,
    ``__getattr__``; also as an instance attribute) and, but for an Enum member, overrides no attribute of its type
    (a ``datetime``'s ``isoformat`` makes its text), and a date-time's time zone is Python's, ``zoneinfo``'s,
    pytz's or dateutil's (its offset and name are printed); an Enum member's class may add methods, and keeps the
    ``__repr__``, ``__str__`` and ``__format__`` that ``enum.Enum``, ``StrEnum``, ``IntEnum`` or its mixed-in type
    define (the package's option types are ``StrEnum`` classes, glued as their text). A container by the same rule:
    one of Python's (``list``, ``tuple``, ``set``, ``frozenset``, ``dict``, ``OrderedDict``, ``defaultdict``,
    ``Counter``, ``ChainMap``, ``UserDict``, ``MappingProxyType``), NumPy's, pandas' or this package's containers,
    a NamedTuple whose text is the one ``collections.namedtuple`` makes, or a subclass of one of them that defines
    no text method and overrides none of their attributes (a dict whose ``items`` hides a NaN its text prints),
    also as an instance's method. A Series' and an Index's labels
    and names, a MultiIndex's levels and names, a table's (a Styler's table's) labels and the names of its rows and
    columns, and a categorical's categories are printed, and are atoms or containers by the same rule as a table's
    cells; a missing label or name (NaN, ``pd.NA``, ``NaT``, None) is printed as a word and accepted, a Series' as a
    table's.

    Raises
    ------
    TypeError
        ``values`` not a mapping, a key not a string, ``decimals`` not an integer; a value (or an entry of a
        container, a key of a mapping, a cell, label or name of a table, Series or Index) that is neither an atom
        (Notes), a DataFrame or Styler given as the value, nor one of the containers below (a deque,
        ``array.array``, dict view, generator or masked array: what it prints is not checked; an object whose text
        is its address; a subclass of an atom type or of a container type printing a text of its own, fuzz 52 C5,
        54a C1), naming ``values[key]``.
    ValueError
        A key that is not ASCII letters, digits, underscores and hyphens (``fig-chf-pso``; text that prints alike,
        ``é`` composed or decomposed, would be two keys: ``_glue_prefix``'s rule for the whole key, fuzz 36a D1).
        A number (a float, a complex number, a NumPy scalar, a Decimal, any entry of a numeric array) NaN or
        infinite, or a missing value (``pd.NA``, ``pd.NaT``, a NumPy ``NaT``), also inside a list, tuple, set,
        a mapping's keys or values, Series, Index, pandas extension array (``pd.array``, Categorical,
        SparseArray), object or structured array, or a container in a cell, label or name of a DataFrame, Styler,
        Series or Index (a table's or Series' own missing cell, label or name, or non-finite real number, also an
        Interval's endpoint, is not refused: pandas prints it as a word; a complex one is, ``1.0+NaNj``), naming
        ``values[key]``; checked for
        every value before any is glued, whatever ``decimals``. Containers nested more than 64 deep
        (``fusion._nesting.MAX_NESTING``; their text recurses), naming ``values[key]``; a container that holds
        itself is accepted (its text prints ``[...]`` there), but a container of such a cycle reached again by
        another path is refused (its text's size depends on the path), and so is a cycle inside a Series, Index,
        table or pandas array, or one of containers none of which prints ``[...]`` (a Counter holding itself):
        their text recurses. A NumPy longdouble beyond float's range (it would be glued as inf or 0), an int of more
        decimal digits than the limit in Notes (IPython would glue nothing; told by its bit length, before any
        conversion: with the limit lifted, 10**6 digits took 11 CPU-s to print), wherever an int is, naming
        ``values[key]``. More values (weighed by kind: tables by their cells, lists by their entries, a dict by its
        keys and values, object and extension arrays, object Series and Index by their size, a container they
        hold by its kind, figures) than the work
        budget glues, naming ``values``, before any is read (a numeric entry 1 unit, by its logical size: a
        ``RangeIndex``, a broadcast view, a categorical's categories); a numeric array, Series, Index, pandas array,
        table or categorical whose values, labels or categories hold more than 2**25 entries (the input budget,
        ``fusion._limits.MAX_INPUT_ELEMENTS``), wherever it is, naming ``values[key]``, before any conversion
        (fuzz 57a C1: a ``RangeIndex(10**12)`` was converted); entries of containers inside a value (a list of lists,
        a table's object cells and labels, a table inside a list) beyond the rest of the budget or beyond 10**6 in
        one call, counted as they are reached and as they are printed (a container reached by two paths twice),
        naming ``values[key]``.
    """
    if not isinstance(values, Mapping):
        raise TypeError(f"values must be a mapping of glue keys to values, got {type(values).__name__}")
    values = read_mapping(values, "values")  # its values checked and glued as one read (fuzz 31a C3)
    work((len(values),), "values", weight=_GLUE_VALUE)   # by their number, then their kinds: before any is read
    units = work((len(values) * _GLUE_VALUE + sum(_glue_work(v, k) for k, v in values.items()),), "values (their "
                 "tables, figures and containers)")
    meter = _Meter(MAX_WORK - units)  # what is inside their containers, counted as it is reached (fuzz 46a C2)
    if decimals is not None:
        decimals = count(decimals, "decimals", minimum=0)
    plain = {}  # keys and text values as their plain str (rule 19): a (str, Enum) member is glued as its text
    for key, value in values.items():  # every value checked before any is glued
        key = _glue_key(key, "values")
        v = value[()] if isinstance(value, np.ndarray) and value.ndim == 0 else value
        if isinstance(v, (np.longdouble, np.clongdouble)) and np.isfinite(v):  # a finite 1e400: refused by its range
            _longdouble_float(value, f"values[{shown(key)}]")                   # first, not as infinite (fuzz 43 D2)
        _check_finite(key, value, meter, counted=isinstance(value, _GLUE_COUNTED))
        value = _longdouble_float(value, f"values[{shown(key)}]")   # then rounded at decimals as any float
        plain[key] = text(value, f"values[{shown(key)}]") if isinstance(value, str) else value
    from myst_nb import glue  # a book dependency, imported only when a chapter runs

    from fusion.book.figures import glue_figure

    for key, value in plain.items():
        if isinstance(value, Figure):
            glue_figure(key, value)
            continue
        value = _printed_float(value)   # a float32, float16: the decimal it prints (fuzz 40b D2)
        if isinstance(value, (np.generic, np.ndarray)) and value.ndim == 0:   # not any object's item (fuzz 52 C5)
            value = value.item()
        if decimals is not None and isinstance(value, float):
            value = rounded(value, decimals)
        glue(key, value, display=False)
