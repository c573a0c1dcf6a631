"""The entries of a caller's array argument, read before its conversion (issue 35, fuzz 33a C1, C3, C7).

Split from ``fusion._validation`` (the house limit of 1000 lines), which re-exports :func:`given_dtype` and
:func:`input_eps`. Three rules of the shared conversion read what the caller gave, entry by entry, without converting
it:

* how many entries it holds (:func:`sequence_entries`, rule 9's input budget): a lazy ``range`` of ``10**10`` entries,
  or a list holding one, costs nothing to build but converts to 80 GB;
* whether an object array holds a date, a duration or ``None`` (:func:`non_number_entry`, rule 16): numpy reads
  ``np.datetime64("2026-01-01")`` as its count of days and ``None`` as NaN;
* the dtype whose precision its numbers have (:func:`given_dtype`, rule 16's tolerances): a float32 buffer, or a list
  of 0-d float32 arrays, is float32 numbers.
"""

from __future__ import annotations

import array as _array
import datetime as _dt
from collections import deque
from itertools import chain as _chain
from collections.abc import Iterator, Sequence

import numpy as np

from fusion._nesting import MAX_NESTING

__all__: list[str] = []  # private module

#: Every numpy integer scalar type, signed and unsigned, of every size (one rule for the fast paths that read a list's
#: entry types: ``_counts``, ``_validation``, here). Read from numpy's own type codes, not listed by name: on Linux
#: ``numpy.longlong`` (dtype ``'q'``) is a type distinct from ``numpy.int64`` of the same size, and a list missing it
#: sent such entries one by one down the slow path (fuzz 61b C1: 1.4 CPU-s for 10**6 seeds, int64 0.03).
NUMPY_INTEGERS = frozenset(np.dtype(code).type for code in np.typecodes["AllInteger"])

#: Scalar types that are numbers (the fast path of :func:`sequence_entries`: a flat list of them counts its length).
_SCALARS = frozenset({int, float, np.float64, np.float32, np.float16, bool, np.bool_}) | NUMPY_INTEGERS

#: Row types of a nested list (the second fast path of :func:`sequence_entries`).
_ROWS = frozenset({list, tuple})

#: Entries of a list, tuple or deque beyond :func:`sequence_entries`' limit whose types it still reads, so that a flat
#: one's count is exact (review 18: such a list was reported as "at least" its length): 2**23, about 0.15 CPU-s at the
#: 18 ns an entry measured for ``set(map(type, x))`` (2**25 floats: 0.59-0.66 CPU-s, shared machine). A longer one is
#: counted by its length alone, "at least" (fuzz 39a E1: its scan was the cost).
_EXACT_SCAN = 2**23


def _shaped(v: object) -> int | None:
    """The number of entries of an array or an object with an integer tuple ``shape``, else None."""
    try:
        # an ndarray's own shape, not a subclass's ``shape`` property (fuzz 70b C1: one claiming (2, 2) for 10**9)
        shape = (np.ndarray.shape.__get__(v) if isinstance(v, np.ndarray)
                 else getattr(type(v), "shape", None) and v.shape)
    except Exception:  # noqa: BLE001 (an object whose shape raises: the conversion names it)
        return None
    if not isinstance(shape, tuple) or not all(isinstance(d, (int, np.integer)) and not isinstance(d, bool)
                                               for d in shape):
        return None
    n = 1
    for d in shape:
        n *= max(int(d), 0)
    return n


def _protocol_size(v: object) -> int | None:
    """The entries of an object with NumPy's array protocols but no shape, converted once (``np.asarray``: a view
    when it gives one), or None (fuzz 70b C2: such an entry inside a list was counted 1, then NumPy copied its 10**9
    entries, a raw MemoryError, in 88 public functions)."""
    if not (hasattr(v, "__array__") or hasattr(v, "__array_interface__") or hasattr(v, "__array_struct__")):
        return None
    try:
        return int(np.asarray(v).size)
    except MemoryError:
        raise
    except Exception:  # noqa: BLE001 (a conversion that raises: the conversion of the argument names it)
        return None


def _stored_len(s: Sequence) -> int:
    """The entries ``s`` stores: a list or tuple subclass's by the base type's ``len`` (NumPy converts the stored
    entries whatever its ``len()`` or ``__iter__`` say: a list subclass whose ``len()`` was 1 passed the input budget
    with 2**25 + 1 entries, fix 77a's note), any other sequence's ``len()``."""
    t = type(s)   # not ``isinstance``: an object may fake its ``__class__`` (fuzz 70b C3)
    return list.__len__(s) if issubclass(t, list) else tuple.__len__(s) if issubclass(t, tuple) else len(s)


def _stored(s: Sequence) -> Iterator[object]:
    """The entries ``s`` stores (``_stored_len``'s rule: a list or tuple subclass's by the base type's iterator)."""
    t = type(s)
    return list.__iter__(s) if issubclass(t, list) else tuple.__iter__(s) if issubclass(t, tuple) else iter(s)


def sequence_entries(x: object, limit: int) -> float | None:
    """The number of entries the sequence ``x`` converts to, counted up to just beyond ``limit`` before any
    conversion (rule 9, fuzz 33a C1), or None if ``x`` is not a sequence (text is not).

    ``len()`` of each ``collections.abc.Sequence`` (a list, a tuple, a ``range``, a ``deque``, a user's Sequence
    class), and of the entries of a list, tuple or deque that are sequences too, recursively (down to
    ``fusion._nesting.MAX_NESTING`` levels: deeper or self-containing ones are left to the conversion, which refuses
    them by name); an entry with a ``shape`` counts its entries, anything else one. The count stops as soon as it
    passes ``limit`` (its cost is at most about ``limit`` type checks, made in C for a flat list of numbers, and
    ``_EXACT_SCAN`` more for a list beyond the limit, whose count is then exact if it is flat), the count then ending
    in ``.5`` when it is not exact (at least its integer part), and a length beyond ``sys.maxsize``
    (``range(10**20)``) counts as infinity. Only the entries of the built-in
    containers are read here (their iteration runs no caller code); a user's Sequence class counts its length (at
    least one entry each): the shared conversion reads it once into a list (``fusion._guards.read_once``), which is
    then counted in full.
    """
    if isinstance(x, np.ndarray):
        return None
    if type(x) in _ROWS and len(x) <= limit and set(map(type, x)) <= _SCALARS:  # the common case: a flat list
        return len(x)
    if not isinstance(x, Sequence) or isinstance(x, (str, bytes, bytearray, memoryview, _array.array)):
        return None
    total = 0
    stack: list[tuple[Sequence, int]] = [(x, 0)]
    while stack:
        s, depth = stack.pop()
        try:
            n = _stored_len(s)
        except OverflowError:
            return float("inf")
        except Exception:  # noqa: BLE001 (a length that raises: the conversion names the argument)
            return total
        if not isinstance(s, (list, tuple, deque)) or n + total > limit:  # a range's entries are numbers
            total += n
            if total > limit and isinstance(s, (list, tuple, deque)):
                if n > _EXACT_SCAN or not set(map(type, _stored(s))) <= _SCALARS:
                    return total + 0.5  # its entries, perhaps sequences, not read: at least this many
                return total + (0.5 if stack else 0)  # flat: its count exact (review 18); others left, at least
        else:
            try:
                types = set(map(type, _stored(s)))
                if types <= _SCALARS:  # a flat sequence of numbers: one pass in C
                    total += n
                    continue
                if types <= _ROWS:  # rows of numbers (a 2-D list): two passes in C
                    inner = sum(map(len, _stored(s)))
                    if total + inner <= limit and set(map(type, _chain.from_iterable(_stored(s)))) <= _SCALARS:
                        total += inner
                        continue
                for v in _stored(s):
                    m = _shaped(v)
                    m = _protocol_size(v) if m is None else m
                    if m is not None:
                        total += m
                    elif (isinstance(v, Sequence) and not isinstance(v, (str, bytes, bytearray))
                          and depth < MAX_NESTING):
                        stack.append((v, depth + 1))
                    else:
                        total += 1
                    if total > limit:
                        return total + 0.5  # stopped early: at least this many (marked by the half)
            except MemoryError:
                raise
            except Exception:  # noqa: BLE001 (entries that raise when read: the conversion names the argument)
                return total
        if total > limit:
            return total + (0.5 if stack else 0)  # entries left uncounted: at least this many
    return total


#: Entries of an object array that numpy would read as a number they are not: a date or a duration (its count in its
#: unit) and ``None`` (NaN).
_NON_NUMBERS = (np.datetime64, np.timedelta64, _dt.date, _dt.timedelta, type(None))


def non_number_entry(a: np.ndarray) -> str | None:
    """What the object array ``a`` holds that is not a number but would convert to one (rule 16, fuzz 33a C2, C3,
    D4), in words ("a date or duration", "None"), or None: numpy reads ``[np.datetime64("2026-01-01"), 4.0]`` as
    ``[20454.0, 4.0]`` (days since 1970: the unit is lost), ``[np.timedelta64(3, "D"), 0.5]`` as ``[3.0, 0.5]``,
    and ``None`` as NaN. An entry that is a 0-d or larger date or duration array counts too."""
    for e in a.flat:
        if e is None:
            return "None"
        if isinstance(e, _NON_NUMBERS) or (isinstance(e, np.ndarray) and e.dtype.kind in "mM"):
            return "a date or duration"
    return None


_F64_EPS = float(np.finfo(np.float64).eps)


def _buffer_dtype(x: object) -> np.dtype | None:
    """The dtype a buffer (a ``memoryview``, an ``array.array``, an object with the array interface) or an object with
    ``__array__`` converts to, or None. A buffer's is read from the buffer (no copy); an ``__array__`` object is
    converted (the callers of :func:`given_dtype` read such an argument once first, ``fusion._guards.read_once``, so
    that they pass an array here)."""
    try:
        if isinstance(x, (memoryview, _array.array)):
            return np.asarray(memoryview(x)).dtype
        if hasattr(x, "__array__") or hasattr(x, "__array_interface__") or hasattr(x, "__array_struct__"):
            return np.asarray(x).dtype
    except MemoryError:
        raise
    except Exception:  # noqa: BLE001 (a conversion that raises: the caller's conversion names the argument)
        return None
    return None


def entries_array(value: object) -> np.ndarray:
    """``np.asarray(value)``, but an object array read as the list of its entries (fuzz 36b D4): an object array
    holds the caller's numbers as they were given, so it takes the type its entries have as a list (the rule of
    :func:`given_dtype`, fuzz 35a C4). An object array of Python ints is then an integer array and one of Python
    bools a boolean one, as their lists are (``order`` of ``ofs_audit.explain`` refused the first as "dtype
    object"); an array whose entries do not convert to an array of its own shape is returned as it is (object),
    for the caller's type check to refuse. The caller bounds its size first (``input_size``)."""
    a = np.asarray(value)
    if a.dtype != object:
        return a
    try:
        b = np.asarray(a.tolist())
    except MemoryError:
        raise
    except Exception:  # noqa: BLE001 (entries that do not convert: the caller's type check names the argument)
        return a
    return b if b.shape == a.shape else a


def given_dtype(x: object) -> np.dtype | None:
    """The numpy dtype whose precision the caller's numbers ``x`` have: an array's (or Series') own dtype (an object
    array's or Series' that of its entries read as a list, fuzz 35a C4), a pandas
    extension dtype's numpy one (``"Float32"``: float32), the dtype a buffer or an ``__array__`` object converts to
    (``array.array("f", ...)``, a ``memoryview`` of float32: float32, fuzz 33a C7); for a list or tuple, the least
    precise dtype among its numpy float scalars and arrays (0-d ones included: ``[np.array(0.1, np.float32)] * 10``
    is float32, as ``[np.float32(0.1)] * 10`` and ``np.asarray`` of either give it; ``[np.float16(1/3), 1/3]``:
    float16, although its array is float64: a number has its own dtype's precision and a list its least precise
    entry's, fuzz 30a C6, D1, fuzz 31a C1, fuzz 33a C7), else the common dtype of its numpy integers, else None
    (Python numbers only: float64). An entry that is neither a number, an array nor a list gives None (the float64
    rule). The entries are not converted (no ``__float__`` is called: read once, fuzz 29a C5)."""
    dtype = getattr(x, "dtype", None)
    if isinstance(dtype, np.dtype) and dtype.kind == "O":
        # an object array (or Series) holds the caller's numbers as they were given: read as a list (fuzz 35a C4)
        try:
            entries = np.asarray(x, dtype=object).ravel().tolist()
        except MemoryError:
            raise
        except Exception:  # noqa: BLE001 (a conversion that raises: the caller's conversion names the argument)
            return None
        return given_dtype(entries)
    if isinstance(dtype, np.dtype):
        return dtype
    if isinstance(getattr(dtype, "numpy_dtype", None), np.dtype):  # pandas masked extension dtypes
        return dtype.numpy_dtype
    if not isinstance(x, (list, tuple)):
        return _buffer_dtype(x)
    kinds: set[np.dtype] = set()
    python = False
    stack = [x]
    while stack:  # iterative: a deeply nested list is read without recursion
        for v in stack.pop():
            if isinstance(v, (list, tuple)):
                stack.append(v)
            elif isinstance(v, (np.floating, np.integer)) or (isinstance(v, np.ndarray) and v.dtype.kind in "fiu"):
                kinds.add(v.dtype)
            elif type(v) in (int, float):  # a Python number: float64's precision, which a numpy float may lower
                python = True
            else:  # anything else: the float64 rule
                return None
    floats = [k for k in kinds if k.kind == "f"]
    if floats:  # the least precise float sets the precision of the whole (its entries' tolerance)
        return max(floats, key=lambda k: float(np.finfo(k).eps))
    return None if python or not kinds else np.result_type(*kinds)


def input_eps(x: object) -> float:
    """The relative precision of the caller's numbers: the machine epsilon of a floating numpy input's dtype
    (``float16``: ``9.8e-4``, ``float32``: ``1.2e-7``), float64's (``2.2e-16``) for anything else.

    The dtype is :func:`given_dtype`'s: the container does not decide, its numbers do (a list of ``np.float32``
    scalars is float32, as its array is; a pandas ``"Float32"`` Series too). A tolerance on a property of the values
    (a sum of weights equal to one) is at least ``n`` times this: weights that sum to one in float32
    (``0.4f + 0.6f``) are accepted, rounded as the caller gave them.
    """
    dtype = given_dtype(x)
    if dtype is not None and dtype.kind == "f" and dtype.itemsize < 8:
        return float(np.finfo(dtype).eps)
    return _F64_EPS
