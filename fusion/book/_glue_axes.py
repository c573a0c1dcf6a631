"""The units of gluing the labels of a MultiIndex, by its levels (fuzz 59a C2), and the logical sizes of an axis of
labels (fuzz 60a C1; fuzz 62a C1: only the labels the glue converts), for :mod:`fusion.book.glue`."""

from __future__ import annotations

import collections
import datetime
import enum
import pathlib
from collections.abc import Callable, Iterable, Mapping

import numpy as np
import pandas as pd
from pandas.api.extensions import ExtensionArray
from pandas.io.formats.style import Styler

from fusion._limits import MAX_WORK
from fusion._shown import shown

__all__: list[str] = []

#: Units (``fusion._limits.work``, about 10 ns each) of one level of a MultiIndex of a table's rows or columns or of
#: a Series' index, printed by the glued text and HTML (fuzz 59a C2: 400,000 levels of a one-row table's index,
#: counted as one row, ran 39.9 CPU-s). Measured by ``glue_all`` (time.process_time, OPENBLAS_NUM_THREADS=1,
#: minimum of 2, machine shared with other helpers), one row: a table's index 126 us a level at 10**4 levels, 93-100
#: us at 2-4 x 10**5; its columns 92 us; a Series' index 28 us; a Styler's table 45 us. Rows are truncated by the
#: text (at most 60 printed): 1000 levels, 0.18 CPU-s at one row, 0.24 at 100 rows, 10**6 rows of 2 levels 0.23
#: CPU-s; so a level is weighed 200 us, its rows included.
_GLUE_LEVEL = 20_000
#: A MultiIndex glued as the value itself (or inside a container): its text is quadratic in its levels (one row:
#: 0.38 CPU-s at 1000 levels, 3.17 at 3000, 36.7 at 10**4; 3.7e-7 s a pair of levels), weighed 40 units a pair.
_GLUE_LEVEL_PAIR = 40


def axis_units(v: object, key: str) -> int:
    """The units of printing the MultiIndex labels of ``v`` (a DataFrame, Styler, Series or Index) by their levels:
    ``_GLUE_LEVEL`` a level of each MultiIndex axis (a table's rows and columns, a Series' index), and for a
    MultiIndex itself ``_GLUE_LEVEL`` a level and ``_GLUE_LEVEL_PAIR`` a pair of levels; 0 for anything else.

    Raises
    ------
    ValueError
        Beyond ``fusion._limits.MAX_WORK`` units, naming ``values[key]``, before any text is made.
    """
    v = v.data if isinstance(v, Styler) else v
    if isinstance(v, pd.MultiIndex):
        units = v.nlevels * _GLUE_LEVEL + v.nlevels**2 * _GLUE_LEVEL_PAIR
    elif isinstance(v, (pd.DataFrame, pd.Series)):
        axes = [v.index, v.columns] if isinstance(v, pd.DataFrame) else [v.index]
        units = sum(ax.nlevels for ax in axes if isinstance(ax, pd.MultiIndex)) * _GLUE_LEVEL
    else:
        return 0
    if units > MAX_WORK:
        raise ValueError(f"values[{shown(key)}] holds a {type(v).__name__} whose MultiIndex labels would print "
                         f"{units:.3g} units of work (their levels counted), beyond the work budget (at most "
                         f"{MAX_WORK:.3g} units, fusion._limits.MAX_WORK, about 10 CPU-s)")
    return units


def label_sizes(labels: pd.Index) -> list[int]:
    """The logical sizes (entries, not bytes held) of the index of labels ``labels`` that the glue may convert: its
    length, a CategoricalIndex's categories, each level of a MultiIndex (``levels[i].size``), and so on inside them
    (a level that is a CategoricalIndex: its categories). Fuzz 60a C1: a CategoricalIndex of ``RangeIndex(10**10)``
    categories as a table's rows or columns or a Series' index, and a MultiIndex of one row with a level of 10**10
    entries, cost nothing to hold and were counted by their length alone, then converted (a raw MemoryError,
    "Unable to allocate 74.5 GiB"). Read without converting anything."""
    sizes: list[int] = []
    todo = [labels]   # without recursion
    while todo:
        ax = todo.pop()
        sizes.append(int(ax.size))
        if isinstance(ax, pd.MultiIndex):
            todo += list(ax.levels)
        elif isinstance(ax, pd.CategoricalIndex):
            todo.append(ax.categories)
    return sizes


def object_dtype(dtype: object) -> bool:
    """Whether a Series, Index or table column of ``dtype`` holds objects that the glue visits one by one (an object
    or non-NumPy dtype: its cells print as their own text), not numbers checked at once."""
    return not (isinstance(dtype, np.dtype) and dtype.kind != "O")


def converted_label_sizes(labels: pd.Index) -> list[int]:
    """The logical sizes (``label_sizes``) of a Series' or table's axis of labels ``labels`` that the glue converts,
    one rule for every kind of index: a MultiIndex (a table's text formats each of its levels whole: fuzz 60a C1,
    a level of ``RangeIndex(10**7)`` 0.30 CPU-s) and an axis holding objects (``object_dtype``: converted to
    objects, a CategoricalIndex with its categories) or complex numbers (checked at once); an axis of real numbers,
    dates or times is neither converted nor counted (its text is truncated). Fuzz 62a C1: a Series of 2 x 10**7
    floats with a DatetimeIndex or a float Index, summed with its labels, was refused; glued without the count it
    takes 0.08 / 0.01 CPU-s (process_time, OPENBLAS_NUM_THREADS=1, machine shared)."""
    dtype = labels.dtype
    converted = (isinstance(labels, pd.MultiIndex) or object_dtype(dtype)
                 or (isinstance(dtype, np.dtype) and dtype.kind == "c"))
    return label_sizes(labels) if converted else []


#: Units of reading one categorical column of a table without its unused categories
#: (``Series.cat.remove_unused_categories``) before its cells are converted to objects (fuzz 62a C2), measured by
#: ``glue_all`` on one-row tables of 10**4 and 3 x 10**4 such columns (time.process_time, OPENBLAS_NUM_THREADS=1,
#: minimum of 2, machine shared with other helpers): 203-214 us a column in all, 144-154 us of it the pruning (the
#: same tables of one category a column, not pruned: 53-80 us); weighed 250 us, the whole column's glue.
_GLUE_PRUNE = 25_000


def pruned_columns(table: pd.DataFrame) -> list[int]:
    """The positions of the categorical columns of ``table`` read without their unused categories before its object
    cells are converted: those whose categories outnumber its rows (converting two or more columns to objects
    together boxes every category of each, fuzz 61a C3: 30-36 ns a number, 0.94 us a date with a time zone; a column
    of at most as many categories as rows boxes no more of them than it has cells, each charged as an object cell).
    Fuzz 62a C2: pruning every categorical column cost ~300 us a column, uncharged (10**5 one-row columns 32.2
    CPU-s); now only these are pruned, each charged ``_GLUE_PRUNE`` (``prune_units``). Read from the dtypes alone."""
    rows = table.shape[0]
    return [j for j, d in enumerate(table.dtypes) if isinstance(d, pd.CategoricalDtype) and len(d.categories) > rows]


def prune_units(v: object) -> int:
    """The units of pruning the categorical columns of the table (or a Styler's table) ``v``: ``_GLUE_PRUNE`` each
    of ``pruned_columns``; 0 for anything else."""
    v = v.data if isinstance(v, Styler) else v
    return len(pruned_columns(v)) * _GLUE_PRUNE if isinstance(v, pd.DataFrame) else 0


def object_cells(part: pd.DataFrame) -> np.ndarray:
    """The cells of the table ``part`` (its object columns) as a 2-D object array, each column of
    ``pruned_columns`` read without its unused categories (its cells are the same)."""
    prune = pruned_columns(part)
    if not prune:
        return part.to_numpy(dtype=object)
    out = np.empty(part.shape, dtype=object)
    keep = sorted(set(range(part.shape[1])) - set(prune))
    if keep:
        out[:, keep] = part.iloc[:, keep].to_numpy(dtype=object)
    for j in prune:
        out[:, j] = part.iloc[:, j].cat.remove_unused_categories().to_numpy(dtype=object)
    return out


#: Units (``fusion._limits.work``, about 10 ns each) of one entry of a Series, Index, table column or pandas array
#: whose dtype holds atoms that cost more to check and print than ``glue._GLUE_OBJECT`` (200 units, ~2 us), known
#: from the dtype before any conversion (fuzz 63a C1: 4,900,000 Intervals of ints, charged 200 units each, accepted
#: after 73.9 CPU-s). Measured by ``glue_all`` on Series of 2**17 entries (time.process_time, OPENBLAS_NUM_THREADS=1,
#: minimum of 2, machine shared with other helpers; fuzz 63a's 2**18 in brackets), weighed twice the largest: an
#: Interval of numbers 10.9 us (8-14), as an IntervalIndex of labels 10.7 us: 2,800 units; an Interval of dates and
#: times 15.8-17.9 us (33 with a time zone): 6,600; a date-time with a time zone 6.6 us as values, 7.9 us as
#: labels (7-10): 2,000; a Period 6.1-6.4 us: 1,300; a categorical of any of them twice its categories' (Intervals
#: 21.2 us, 23): numbers, naive dates and durations are checked at once (0.01 us, ``_GLUE_NUMBER``).
_ATOM_INTERVAL, _ATOM_INTERVAL_TIME, _ATOM_ZONED, _ATOM_PERIOD = 2_800, 6_600, 2_000, 1_300


def atom_units(dtype: object, plain: int) -> int:
    """The units of one object entry of ``dtype`` (a Series', Index's, table column's or pandas array's) that the
    glue checks and prints: by the atoms it holds (``_ATOM_*``), else ``plain`` (``glue._GLUE_OBJECT``)."""
    if isinstance(dtype, pd.CategoricalDtype):   # of plain atoms: plain (measured as such, fuzz 46a)
        inner = atom_units(dtype.categories.dtype, plain)
        return plain if inner == plain else 2 * inner
    if isinstance(dtype, pd.IntervalDtype):
        sub = dtype.subtype
        timed = isinstance(sub, pd.DatetimeTZDtype) or (isinstance(sub, np.dtype) and sub.kind in "mM")
        return _ATOM_INTERVAL_TIME if timed else _ATOM_INTERVAL
    if isinstance(dtype, pd.DatetimeTZDtype):
        return _ATOM_ZONED
    if isinstance(dtype, pd.PeriodDtype):
        return _ATOM_PERIOD
    return plain


#: Units of one atom held by an object container (a list, tuple, set or mapping, an object array, Series, Index or
#: table column), known only from each entry's type (round 63's remainder: 4,900,000 Intervals in an object Series were
#: charged 200 units each; fuzz 65a C2: 4,900,000 Enum members in an object array, 43.9 CPU-s accepted). Measured by
#: ``glue_all`` on 2**17 entries of one type, in a list, an object array and an object Series (time.process_time,
#: OPENBLAS_NUM_THREADS=1, minimum of 3, machine shared with the test suite and two helpers), us an entry: an Interval
#: 7.5-9.0 (of dates with a time zone 11.2-11.8): ``_ATOM_INTERVAL``; an Enum member 7.3-7.6: 1,600 units; a
#: date-time 5.1-6.8, a date 4.5-4.8, a time 4.8-5.2, a duration (Python's, pandas', NumPy's) 3.7-5.4, a NumPy
#: date-time 4.9-6.1, a Period 4.6-5.1, a path 4.3-5.5, a range 5.6-5.8: 1,300 units; any other atom (an int, str,
#: bytes, complex, None, bool, Decimal, Fraction, NumPy number; a float of an object array, Series or Index) 2.8-5.4:
#: 900 units (each about twice its measured cost). A float of a list, tuple, set or mapping is checked at once with
#: its siblings (0.12 us: its container's plain weight); a container held by its kind (``_HOLDER_UNITS``).
_OBJECT_ATOMS = ((pd.Interval, _ATOM_INTERVAL), (enum.Enum, 1_600),
                 ((datetime.date, datetime.time, datetime.timedelta, np.datetime64, np.timedelta64, pd.Period,
                   pathlib.PurePath, range), 1_300))
_OBJECT_ANY = 900
#: Units of a container held by an object container (an entry of a list, tuple, set, mapping, object array, Series
#: or Index, a table's object cell or label), its own fixed cost besides its entries (charged where they are
#: reached), weighed with its holder (fuzz 66a C5: 400,000 distinct empty Series in a list, charged 300 units each
#: as list entries, ran 37.1 CPU-s accepted; 10**6 empty lists 11.4). Measured by ``glue_all`` on a list of 2**15
#: distinct empty ones (time.process_time, OPENBLAS_NUM_THREADS=1, minimum of 2, machine shared with other
#: helpers), us an entry: a Series 76 (of objects 87), an Index 52, a pandas array 47, a Categorical 103: 20,000
#: units; a NumPy array 14.4: 3,000; a list 8.4, a set 8.5, a dict 9.9: 2,000 (about twice the largest). A table is
#: charged ``glue._GLUE_TABLE`` where it is reached.
_HOLDER_UNITS = (((pd.DataFrame, Styler), 0), ((pd.Series, pd.Index, ExtensionArray), 20_000), (np.ndarray, 3_000),
                 ((list, tuple, set, frozenset, Mapping), 2_000))


def _type_units(t: type, python: bool) -> int:
    """The units of one entry of type ``t`` of an object container (``_OBJECT_ATOMS``, a container
    ``_HOLDER_UNITS``; a Python container's float: 0, ``python``)."""
    if python and t is float:
        return 0
    w = next((w for base, w in _OBJECT_ATOMS + _HOLDER_UNITS if issubclass(t, base)), None)
    return w if w is not None else _OBJECT_ANY


def keys_values(m: Mapping) -> Iterable[object]:
    """The keys and the values of the mapping ``m`` (its text prints both), read once through ``items()``."""
    return (e for kv in m.items() for e in kv)


def by_type(units: int, entries: Callable[[], Iterable[object]], plain: int, python: bool = False) -> int:
    """``units`` (``plain`` units an entry of an object container) plus what its atoms cost beyond ``plain`` by type
    (``_OBJECT_ATOMS``, ``_OBJECT_ANY``; ``python``: a list's, tuple's, set's or mapping's, whose floats are checked
    at once), counted by the entries' types (``map(type)``, about 30 ns an entry, no entry visited in Python);
    ``entries`` is read only when ``units`` is within ``MAX_WORK`` (beyond, the plain weight alone is refused). A
    held structured array's fields (``field_units``, each distinct dtype read once) are counted here too, so a list
    of them is refused before any is read (fuzz 67a C3), and again where each is reached (an upper bound)."""
    if units > MAX_WORK:
        return units
    types = collections.Counter(map(type, entries()))
    for t, k in types.items():
        units += k * max(0, _type_units(t, python) - plain)
    if units <= MAX_WORK and any(issubclass(t, np.ndarray) for t in types):
        fields: dict[int, tuple[np.dtype, int]] = {}   # by id, each dtype read (kept alive) and its fields' units
        for e in entries():
            if isinstance(e, np.ndarray) and e.dtype.names:
                units += fields.setdefault(id(e.dtype), (e.dtype, field_units(e.dtype)))[1]
    return units


def entries_units(dtype: object, n: int, entries: Callable[[], Iterable[object]], plain: int) -> int:
    """The units of ``n`` entries of ``dtype`` (a Series', Index's, pandas or NumPy array's): a NumPy object dtype's
    by their types (``by_type``; ``entries`` gives them), else by the dtype's atoms (``atom_units``); a structured
    dtype holding objects ``plain`` an entry."""
    if isinstance(dtype, np.dtype) and dtype.fields is not None:
        return n * plain
    # a pandas array of objects (``NumpyEADtype``, ``SparseDtype``) by its NumPy dtype
    inner = dtype.subtype if isinstance(dtype, pd.SparseDtype) else getattr(dtype, "numpy_dtype", dtype)
    return by_type(n * plain, entries, plain) if inner == object else n * atom_units(dtype, plain)


def columns_units(table: pd.DataFrame, plain: int) -> int:
    """The units of the cells of ``table``'s object columns (``object_dtype``): a pandas dtype's by its atoms
    (``atom_units``), NumPy object columns' by their cells' types (``by_type``, read at once)."""
    dtypes = list(table.dtypes)
    units = table.shape[0] * sum(atom_units(d, plain) for d in dtypes if object_dtype(d) and d != object)
    cols = [j for j, d in enumerate(dtypes) if d == object]
    if cols:
        units += by_type(table.shape[0] * len(cols) * plain, lambda: table.iloc[:, cols].to_numpy().ravel(), plain)
    return units


#: Units of one field of a structured array (or scalar) :func:`fusion.book.glue._finite` reads: each field is taken as
#: an array of its own (``v[name]``) and checked, a nested structured field's fields alike (fuzz 67a C3: a list of
#: structured arrays was weighed a fixed 3,000 units an array whatever its fields; 35.4 CPU-s accepted). Measured by
#: ``glue_all`` (time.process_time, OPENBLAS_NUM_THREADS=1, minimum of 2, machine shared with the test suite): a list
#: of K one-row arrays of F float fields, (F, K) = (10, 2000) 14.9 us a field, (100, 200) 12.6, (1000, 20) 9.9;
#: one array of 10**4 and 4 x 10**4 fields 10.6-15.2 us (50 rows); 100 fields of 100 nested fields 10.4 us: weighed
#: 25 us, about twice.
_GLUE_FIELD = 2_500


def field_units(dtype: np.dtype) -> int:
    """The units of reading the fields of an array of ``dtype``: ``_GLUE_FIELD`` each field, a nested structured
    field's own fields counted each time it occurs (each is read), read without recursion (a dtype may nest thousands
    of levels deep), each distinct dtype once; 0 for a plain dtype."""
    memo: dict[int, int] = {}     # by id, the structured dtypes read: their fields, nested ones included
    pinned: list[np.dtype] = []   # kept alive: no id is reused during the call

    def base(d: np.dtype) -> np.dtype:
        return d.subdtype[0] if d.subdtype is not None else d

    todo = [base(dtype)]
    while todo:
        d = todo[-1]
        if not d.names or id(d) in memo:
            todo.pop()
            continue
        inner = [base(d.fields[n][0]) for n in d.names]
        unread = [b for b in inner if b.names and id(b) not in memo]
        if unread:
            todo += unread
            continue
        todo.pop()
        pinned.append(d)
        memo[id(d)] = sum(1 + memo.get(id(b), 0) for b in inner)
    return memo.get(id(base(dtype)), 0) * _GLUE_FIELD
