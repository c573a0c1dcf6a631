"""Input validation shared by every public function of :mod:`fusion`.

Every check raises :class:`ValueError` with a message that names the argument and
the problem, so that bad input never turns into a silent ``nan`` further down, and
:class:`TypeError` (also naming the argument) for a value of the wrong type, such as a
string where an array or a number is expected. The checks are cheap next to the work
they guard (``benchmarks/bench_validation.py`` measures them).

Rules shared by every validated argument (issue 35, one rule per class of bad input):

1. *Real numbers only*: a complex array or number is refused with a :class:`TypeError`
   (it used to be cast silently to its real part).
2. *Representable magnitudes*: finite non-zero entries must lie within [:data:`MIN_MAGNITUDE`,
   :data:`MAX_MAGNITUDE`] = [``1e-150``, ``1e150``], so that a product of two entries, a square or
   a variance, stays a finite normal float; subnormals and tiny normals below it lose precision and
   their reciprocals overflow. Weight vectors (:func:`as_weights`), belief and fusion-degree
   matrices and the off-diagonal entries of covariances may hold such tiny entries: they are
   computed values (``exp`` of a large negative number) that are numerically zero next to the
   others, and nothing divides by them.
3. *Objectives*: optimisers refuse an objective that returns NaN, a non-number or the wrong
   shape, and one that is infinite everywhere (``fusion._objectives.objective_values``).
5. *Singular systems*: linear solves go through :func:`solve`, which names the argument
   whose matrix is singular instead of letting :class:`numpy.linalg.LinAlgError` escape.
6. *Types and keys*: ``bool`` is not a number; options dicts are checked against the keys
   their consumer accepts (:func:`options`); indices are checked (:func:`index`). A ``**options``
   keyword that no variant takes (a misspelling) is a :class:`TypeError` naming it, as Python's for an
   unexpected keyword (:func:`keywords`).
9. *Sizes*: every count has a ceiling by its kind (:data:`COUNT_CEILINGS`: runs, samples,
   particles, iterations, grid points, dimensions, decomposition levels, decimals, workers; the
   kind is read from the argument's name by :func:`count_kind`), so that a count at its ceiling
   sizes at most a vector of ``10**7`` float64 (80 MB) and a loop of ``10**7`` steps: nothing with
   a finite count runs unboundedly. A cost that grows as a product of counts (runs x particles x
   steps) is checked at the function's entry by :func:`allocation` against the memory budget
   :data:`MAX_ELEMENTS` (``2**28`` float64, 2 GiB). A pairwise kernel of n readings (n x n distances,
   beliefs or supports) declares its n x n arrays to the reading conversion (``pairs`` of :func:`as_readings`
   and :func:`as_reading_rows`), whose :func:`pairwise` checks their memory and work (rule 17) before any of
   it: a long 1-D ``x`` is refused by name. Both refusals are a :class:`ValueError` naming
   the argument(s) and the ceiling, never a :class:`MemoryError`, a timeout or a NaN (``10**9``
   decimals). An array argument holds at most :data:`MAX_INPUT_ELEMENTS` entries, checked on its
   shape before any copy or conversion (:func:`input_size`: a zero-stride view of ``10**10`` entries
   costs 8 bytes but would convert to 80 GB). Seeds and indices have no ceiling (the caller passes ``maximum=None``). A number of
   worker processes is capped at the machine's CPUs (:func:`workers`): the result never depends on it.
10. *Booleans are not numbers*: a boolean array, or a sequence holding ``True``/``False``, passed
    where numbers are expected is refused with a :class:`TypeError` naming the argument (numpy
    would read it as 0/1); an argument documented as a mask takes booleans through :func:`as_mask`.
11. *Seeds are integers*: a seed is an ``int`` (any size, non-negative), a numpy integer or a 0-d integer array
    (the integer it holds, as for a count and for :func:`numpy.random.default_rng`), and a generator argument a
    :class:`numpy.random.Generator`; a float, even ``3.0``, is refused (:func:`seed`, :func:`as_rng`).
13. *Counts are integers*: a count (a size, a number of runs or iterations, a level, a number of
    decimals, an index) is a Python ``int`` or a numpy integer (a 0-d integer array included:
    anything :func:`operator.index` accepts); a ``bool`` is refused, and so is a float, a
    :class:`~decimal.Decimal` or a :class:`~fractions.Fraction`, *even an integral one* such as
    ``np.float64(100.0)`` or ``Decimal(100)``: a :class:`TypeError` naming the argument
    (:func:`count`, :func:`integer`). A :class:`numpy.timedelta64` is a numpy integer subclass but a
    duration, not an integer: refused too (:func:`is_integer` is the shared test of an integer
    scalar). One rule with seeds (rule 11): a number that is not an integer type is not silently
    truncated or rounded into one.
12. *Nested structures*: sequences of arrays are validated entry by entry, naming the entry
    (``Hs[1]``); a dict of records is checked against the keys and types its consumer reads
    (:func:`record`), so that a wrong entry is a :class:`TypeError`/:class:`ValueError` naming the
    argument, never a :class:`KeyError` or :class:`AttributeError` from deep inside.
14. *Results own their data*: a validated array is never the caller's own buffer. An input that is
    already a float64 array (or a view of one: a pandas Series, a buffer, an object's ``__array__``)
    is copied once by the shared conversion, so that a result storing it (a track's ``z``, a gain
    sequence's ``F``, a mixture's weights) does not change when the caller later edits its input in
    place. A list or a non-float array is converted into a new array anyway: no second copy.
15. *An argument's own exception*: an object whose ``__float__``, ``__index__`` or ``__array__`` raises
    (a :class:`RuntimeError` or anything else but :class:`MemoryError`) while it is converted is
    refused with a :class:`TypeError` naming the argument, chained to that exception
    (``raise ... from exc``), in the shared scalar, count and array conversions.
16. *Numeric dtypes only*: an array whose dtype has no numeric kind (structured or void records,
    text, anything but integers, floats and object arrays of numbers) is refused with a
    :class:`TypeError` naming the argument: a one-field ``f8`` structured array is not read as its field. So is an
    entry of a list that numpy would read as a number it is not (fuzz 33a C2, C3, D4): a date or a duration (as
    its count in its unit: ``[np.datetime64("2026-01-01"), 4.0]``) or ``None`` (as NaN; NaN itself is a float).
    A float32 or float16 input is its values; a tolerance on them (weights summing to one) is at
    least ``2 n`` times its own machine epsilon (:func:`input_eps`).
17. *Work*: valid counts whose product is huge (runs x steps, problems x particles x iterations x
    dimension) fit in memory but would run for hours. A function whose loops grow as such a product
    calls :func:`work` at its entry with the counts, and a product beyond the work budget
    :data:`MAX_WORK` (``10**9`` units of about 10 ns each, at most about 10 CPU-s; a Python-level
    loop step weighs :data:`LOOP_STEP` units, :func:`loop_work`) is refused with a :class:`ValueError`
    naming the arguments and the budget, before any work. A loop over the entries of a sequence argument
    (seeds, sizes, a grid of scales) counts its length, or the sum of its entries when they are sizes.
18. *Flags are booleans*: a parameter documented ``bool`` takes ``True``/``False`` (or a numpy
    ``bool_``) only (:func:`flag`): the string ``'False'``, ``None`` or an int 0/1 is refused with a
    :class:`TypeError` naming it, never read as its truthiness (``'False'`` is truthy).
19. *Text options are their text* (fuzz 17): :func:`one_of` matches a plain copy of the option (``str.__str__``)
    with ``str``'s own equality and returns that copy; a ``str`` subclass whose own ``==`` or ``hash`` raises or
    disagrees with its text is refused with a :class:`TypeError` naming the argument. A template argument (a label
    or metric with ``{}``/``{j}`` fields) is checked by :func:`template`: its fields name the values its caller
    fills in, and hold a width of at most two digits (fuzz 21b: ``"{j:>999999999}"`` padded each label to a
    gigabyte).
20. *A number is what its conversion reads* (fuzz 17): the shared scalar reader reads a ``float`` subclass through
    ``float()``, that is its ``__float__``, the rule numpy follows for an array of them (``np.asarray([x])``); the
    read value, never the caller's object, is what the computation uses (a frozen dataclass stores it:
    :func:`store_read`), so that the result does not depend on the path an argument takes.
"""

from __future__ import annotations

import dataclasses as _dataclasses
import datetime as _dt
import decimal as _decimal
import functools as _functools
import importlib
import inspect as _inspect
import re as _re
from math import isfinite as _isfinite
from operator import index as _index

import numpy as np
from collections.abc import Callable, Sequence
from numpy.typing import ArrayLike, NDArray
from scipy.linalg.lapack import dpotrf as _potrf

from fusion._counts import (  # noqa: F401 (re-exported: the rules on counts, seeds and sequences)
    BY_KIND, COUNT_CEILINGS, COUNT_KINDS, MAX_COUNT, MAX_ELEMENTS, _bool_error, _complex_error, _integer, allocation,
    count, count_ceiling, count_kind, counts, distinct, distinct_printed, general, glue_part, grid_points, index,
    iterable, machine_workers, not_masked, PAIR_WORK, pairwise, seed, seed_array, seed_sequence, seeds, sequence, workers,
    as_rng, as_rngs)
from fusion._structures import (  # noqa: F401 (re-exported)
    derived, inverse, mapping_of, psd_factor, record, records_of, singular_error, singular_system, within)
from fusion._guards import derived_inputs, finite_result  # noqa: F401 (re-exported: guards on results, errors)
from fusion._guards import argument_copy, read_mapping, read_once, value_copy  # noqa: F401 (re-exported: what callables and checks are given)
from fusion._limits import LOOP_STEP, MAX_INPUT_ELEMENTS, MAX_MAGNITUDE, MAX_WORK, MIN_MAGNITUDE, MIN_NORMAL, MIN_VARIANCE  # noqa: F401
from fusion._limits import loop_work, work  # noqa: F401
from fusion._shown import MAX_SHOWN, shown  # noqa: F401 (re-exported: the echo of a bad value)
from fusion._nesting import MAX_NESTING, is_ragged, ndim_of, ragged_error, shape_of  # noqa: F401 (re-exported)
from fusion._entries import _F64_EPS, NUMPY_INTEGERS, given_dtype, input_eps, non_number_entry, sequence_entries  # noqa: F401
from fusion._options import (  # noqa: F401 (re-exported: rules 6, 18, 19)
    _plain_text, _safe_repr, flag, keywords, one_of, options, template, text, text_fields, texts)

FloatArray = NDArray[np.float64]


def _numeric(x: ArrayLike, name: str) -> FloatArray:
    """``np.asarray(x, dtype=float)``, with a :class:`TypeError` naming ``name`` for non-numbers.

    Refused: complex input (rule 1: a cast drops the imaginary part), a masked array (its mask would be dropped),
    dates and durations (unit unknown). A plain float64 ndarray within the input budget is just copied (speed58).
    """
    if type(x) is np.ndarray and x.dtype == np.float64 and x.size <= MAX_INPUT_ELEMENTS:
        return x.copy()  # rule 14: never the caller's own buffer
    if not isinstance(x, (list, tuple, range, str, bytes, bytearray, np.ndarray)) and isinstance(x, Sequence):
        x = read_once(x, name)  # a deque or a user's Sequence class: read once into a list, counted (fuzz 33a C1)
    input_size(x, name)  # rule 9: before any copy or conversion
    not_masked(x, name)
    if isinstance(x, np.ndarray) and type(x) is not np.ndarray:  # np.matrix and other subclasses: their indexing
        x = np.asarray(x)  # and products differ from an array's; the same numbers as a plain array
    if isinstance(x, np.ndarray):
        if x.dtype == np.float64:
            return x.copy()  # rule 14: never the caller's own buffer
        if x.dtype.kind in "mM":
            raise TypeError(f"{name} must be numeric, got {x.dtype} (convert dates or durations to seconds first)")
        if x.dtype.kind == "c":
            raise _complex_error(name)
        if x.dtype.kind == "b":
            raise _bool_error(name)
        if x.dtype.kind not in _NUMERIC_KINDS + "US":  # text: its own message below
            raise _dtype_error(name, x.dtype)
    elif isinstance(x, (str, bytes)):
        raise TypeError(f"{name} must be numeric, got a string {shown(x)}")
    elif x is None or isinstance(x, (dict, bool, np.bool_)):
        raise TypeError(f"{name} must be numeric (array_like of numbers), got {type(x).__name__}")
    elif isinstance(x, (complex, np.complexfloating)):
        raise _complex_error(name)
    a = None  # read by the handler below (a signalling NaN entry)
    try:
        a = x if isinstance(x, np.ndarray) else np.asarray(x)
        if a is not x:   # an object with no shape or length (only ``__array__``) is measured once converted (fuzz 69b D1)
            input_size(a, name)
        if a.dtype.kind in "US" or (a.dtype.kind == "O" and _holds_text(a)):
            raise TypeError(f"{name} must be numeric (array_like of numbers), got text")
        if a.dtype.kind == "c" or (a.dtype.kind == "O" and _holds_complex(a)):  # np.complex128 entries would
            raise _complex_error(name)  # convert with a ComplexWarning, dropping the imaginary part
        if a.dtype.kind in "mM":
            raise TypeError(f"{name} must be numeric, got {a.dtype} (convert dates or durations to seconds first)")
        odd = non_number_entry(a) if a.dtype.kind == "O" else None  # numpy reads a date as its count, None as NaN
        if odd is not None:
            raise TypeError(f"{name} must be numeric (array_like of numbers), got an entry that is {odd}"
                            + (" (convert dates or durations to seconds first)" if odd != "None" else ""))
        if a.dtype.kind == "b" or (a.dtype.kind == "O" and _holds_bool(a)) or (a is not x and _holds_bool(x)):
            raise _bool_error(name)
        if a.dtype.kind not in _NUMERIC_KINDS:
            raise _dtype_error(name, a.dtype)
        wide = a.dtype.kind == "O" or (a.dtype.kind == "f" and a.dtype.itemsize > 8)  # longdouble, float128
        with np.errstate(over="ignore"):  # a longdouble beyond the float range: refused just below, by name
            out = np.asarray(a, dtype=float)
        if wide and _beyond_float_range(a, out):  # np.longdouble('1e4000') or Decimal('1e400') -> inf
            raise ValueError(f"{name} must be within the float range: it holds a finite number beyond it (at "
                             f"most {MAX_MAGNITUDE:g} in magnitude)")
        if wide and ((out == 0) & (a != 0)).any():  # Fraction(1, 10**400), np.longdouble('1e-4000') -> 0.0
            raise ValueError(f"{name} must be within the float range: it holds a non-zero number "
                             f"below it (at least {MIN_MAGNITUDE:g} in magnitude, or zero)")
        if out is a and not isinstance(x, (list, tuple)):  # a view of the caller's data (a Series, a buffer,
            out = out.copy()  # an object's __array__): rule 14, a private copy
        return out
    except OverflowError:  # Python ints beyond the float range
        raise ValueError(f"{name} holds a number beyond the float range (at most {MAX_MAGNITUDE:g} in magnitude)") \
            from None
    except (TypeError, ValueError) as exc:
        if str(exc).startswith((name + " must be", name + " has ")):   # ours (the input budget: fuzz 69b D1)
            raise
        if "complex" in str(exc):
            raise _complex_error(name) from None
        if is_ragged(exc):  # numpy's message names nothing: the one rule of a ragged or self-containing list
            raise ragged_error(name) from None
        if _holds_snan(a):  # a Decimal('sNaN') entry is a NaN, a bad value (fuzz 49a D1), told by
            # the entry, not by the message (fuzz 50a D6: an object whose __float__ raised ValueError('signaling NaN'))
            raise ValueError(f"{name} contains NaN or infinite values (a signalling NaN)") from None
        raise TypeError(f"{name} must be numeric (array_like of numbers): {exc}") from None
    except MemoryError:
        raise
    except Exception as exc:  # rule 15: the argument's own exception (its __array__ or __float__ raised)
        raise _conversion_error(name, exc) from exc


def _holds_snan(a: object) -> bool:
    """Whether ``a`` is an object array holding a ``Decimal`` signalling NaN (which ``float()`` refuses)."""
    return (isinstance(a, np.ndarray) and a.dtype.kind == "O"
            and any(isinstance(e, _decimal.Decimal) and e.is_snan() for e in a.flat))


def _beyond_float_range(a: np.ndarray, out: FloatArray) -> bool:
    """Whether an entry of the wide or object array ``a`` is finite but became an infinity in its float copy ``out``."""
    lost = np.isinf(out)
    if not lost.any():
        return False
    return bool((a[lost] != out[lost]).any())  # an infinite entry equals its copy; np.longdouble('1e4000') does not


def input_size(x: object, name: str) -> None:
    """Refuse an array argument of more than :data:`MAX_INPUT_ELEMENTS` entries by its shape, before any work (rule 9).

    Reads only the ``shape`` of an array or an array-like object (a pandas object, anything with an integer
    tuple ``shape``): nothing is copied or converted, so that a zero-stride view of ``10**10`` entries or an
    honest stack of ``10**8`` rows is refused at once. A sequence (a list, a tuple, a lazy ``range`` or ``deque``, a
    user's Sequence class) is measured by the lengths of its nested sequences before it is built
    (``fusion._entries.sequence_entries``, fuzz 33a C1: ``range(10**10)``, or ``[range(10**9)]``, costs nothing to
    build but converts to 80 GB).

    Parameters
    ----------
    x : object
        The argument.
    name : str
        Its name, for the message.

    Raises
    ------
    ValueError
        If its shape holds more than :data:`MAX_INPUT_ELEMENTS` entries, or it is a list or tuple subclass defining
        its own ``__len__``, ``__iter__`` or ``__getitem__``, or an array protocol (``__array__``, the array
        interface: NumPy reads it by them, not by what it stores; fuzz 69b C1), naming ``name``.
    """
    base = list if issubclass(type(x), list) else tuple if issubclass(type(x), tuple) else None   # fuzz 70b C3
    if base is not None and type(x) is not base:   # fix 77a's note: len() 1 passed the budget with 2**25 + 1 entries
        own = [m for m in ("__len__", "__iter__", "__getitem__") if getattr(type(x), m) is not getattr(base, m)]
        own += [m for m in ("__array__", "__array_interface__", "__array_struct__") if hasattr(x, m)]   # fuzz 70b C4
        if own:   # NumPy reads it by these, the budget by what it stores: the two may disagree (a plain wrong array)
            raise ValueError(f"{name} must not be a {base.__name__} subclass that reads its entries its own way "
                             f"({type(x).__name__} defines {', '.join(own)}): its length or entries may not be what "
                             f"it stores; pass a plain {base.__name__} or an array")
    n = sequence_entries(x, MAX_INPUT_ELEMENTS)
    if n is not None and n > MAX_INPUT_ELEMENTS:  # a lazy range, or a list holding one, counted before it is built
        raise ValueError(f"{name} has {entries_text(n)} entries, beyond the input budget (at most "
                         f"{MAX_INPUT_ELEMENTS:,}, fusion._validation.MAX_INPUT_ELEMENTS; counted from the lengths of "
                         "its sequences)")
    shape = _given_shape(x)
    if shape is None:
        return
    n = 1
    for d in shape:
        n *= max(int(d), 0)
    if n > MAX_INPUT_ELEMENTS:
        dims = " x ".join(f"{int(d):,}" for d in shape)
        raise ValueError(f"{name} has {n:.3g} entries ({dims}), beyond the input budget (at most "
                         f"{MAX_INPUT_ELEMENTS:,}, fusion._validation.MAX_INPUT_ELEMENTS)")


def _given_shape(x: object) -> tuple[int, ...] | None:
    """The integer ``shape`` of an array or array-like object, read without converting it (None: no such shape)."""
    try:
        shape = np.ndarray.shape.__get__(x) if isinstance(x, np.ndarray) else getattr(type(x), "shape", None) and x.shape
    except Exception:  # noqa: BLE001 (an object whose shape raises: the conversion names it)
        return None
    if not isinstance(shape, tuple) or not all(is_integer(d) for d in shape):
        return None
    return shape


def entries_text(n: float) -> str:
    """A count of :func:`given_entries` as text: ``3.36e+07``, ``at least 7`` (counted up to a limit), ``more than``
    the input budget (a length beyond ``sys.maxsize``)."""
    if n == float("inf"):
        return f"more than {MAX_INPUT_ELEMENTS:,}"
    return f"{n:.3g}" if n == int(n) else f"at least {int(n):.3g}"


def given_entries(x: object, limit: int) -> float | None:
    """The entries of the argument ``x`` before any copy or conversion, counted up to just beyond ``limit`` (rule 9,
    as :func:`input_size`): a sequence's by the lengths of its nested sequences, an array's (or array-like's) by its
    shape; None for anything else. A caller whose argument has a known small shape (an order of six observations)
    refuses a larger one by this count, before converting it (fuzz 39a E1: ``ofs_audit.explain`` converted an
    order of 2**25 entries, 1.7-2.2 CPU-s, before its shape check)."""
    n = sequence_entries(x, limit)
    if n is not None:
        return n
    shape = _given_shape(x)
    if shape is None:
        return None
    out = 1
    for d in shape:
        out *= max(int(d), 0)
    return out


#: dtype kinds that convert to float64 by value: integers, floats, and object arrays (checked entry by entry).
_NUMERIC_KINDS = "iufO"


def _dtype_error(name: str, dtype: np.dtype) -> TypeError:
    """Rule 16: a structured, void, text or other non-numeric dtype is refused (a one-field structured array
    would otherwise be read as its field)."""
    return TypeError(f"{name} must be numeric, got an array of dtype {dtype} (not a number type)")


def _conversion_error(name: str, exc: BaseException) -> TypeError:
    """Rule 15: an exception raised by the argument itself while it is converted, re-raised naming it."""
    return TypeError(f"{name} could not be converted to a number: it raised {type(exc).__name__}: {str(exc):.200}")


def _holds_bool(x: object) -> bool:
    """Whether a (nested) list, tuple or object array holds a ``bool``: numpy reads ``True`` as ``1.0`` (rule 10)."""
    if isinstance(x, (bool, np.bool_)):
        return True
    if isinstance(x, np.ndarray):
        return x.dtype.kind == "b" or (x.dtype.kind == "O" and any(_holds_bool(e) for e in x.flat))
    if isinstance(x, (list, tuple)):
        if set(map(type, x)) <= _PLAIN_NUMBERS:  # a flat list of numbers: one pass in C (10**6 entries in ms)
            return False
        return any(_holds_bool(e) for e in x)
    return False


#: Scalar types that are numbers and never booleans (the fast path of :func:`_holds_bool`).
_PLAIN_NUMBERS = frozenset({int, float, np.float64, np.float32}) | NUMPY_INTEGERS


def _holds_complex(a: np.ndarray) -> bool:
    """Whether the object array ``a`` holds a complex number (checked before the conversion, so that no warning filter,
    a process-global state that threads would share, is needed to catch numpy's ComplexWarning)."""
    return any(isinstance(e, (complex, np.complexfloating)) for e in a.flat)


def _holds_text(x: object) -> bool:
    """Whether an array or (nested) sequence holds a string: numpy would parse ``"1"`` as a number."""
    if isinstance(x, (str, bytes)):
        return True
    if isinstance(x, np.ndarray):
        return x.dtype.kind in "US" or (x.dtype.kind == "O" and any(_holds_text(e) for e in x.flat))
    if isinstance(x, (list, tuple)):
        return any(_holds_text(e) for e in x)
    return False


def _magnitude_problem(arr: FloatArray, subnormal: bool = True) -> str | None:
    """Why the finite entries of ``arr`` are outside the representable range (rule 2), or ``None``.

    Also reports NaN and infinity (one pass finds both: ``max`` of an array holding NaN is NaN).
    """
    if arr.size == 0:
        return None
    m = np.abs(arr)
    top = float(m.max())
    if not top <= MAX_MAGNITUDE:
        if not np.isfinite(top) or not np.isfinite(m).all():
            return "contains NaN or infinite values"
        return f"has an entry of magnitude {top:.3g}, beyond the representable range (at most {MAX_MAGNITUDE:g})"
    if subnormal and float(m.min()) < MIN_MAGNITUDE:  # zeros or tiny entries: look closer (rare for data)
        if ((m > 0) & (m < MIN_MAGNITUDE)).any():  # 0 < |x| < MIN_MAGNITUDE
            return (f"has a tiny entry (non-zero but below {MIN_MAGNITUDE:g} in magnitude: "
                    "products of entries underflow)")
    return None


def check_magnitude(arr: FloatArray, name: str, subnormal: bool = True) -> FloatArray:
    """Refuse NaN, infinity, magnitudes above :data:`MAX_MAGNITUDE` and subnormal entries (rule 2).

    Parameters
    ----------
    arr : ndarray
        Float array (already converted by the caller).
    name : str
        Argument name used in the message.
    subnormal : bool
        Also refuse subnormal entries (weights may hold them: pass ``False``).

    Returns
    -------
    ndarray
        ``arr`` itself.

    Raises
    ------
    ValueError
        Naming ``name``.
    """
    problem = _magnitude_problem(arr, subnormal)
    if problem is not None:
        raise ValueError(f"{name} {problem}")
    return arr


def _lost_in_cast(value: object, v: float) -> bool:
    """Whether the finite ``value`` became the infinity ``v`` on its conversion to a float (it lies beyond the float
    range: a Decimal, a longdouble or float128); an infinite ``value`` compares equal to ``v``."""
    if _isfinite(v) or v != v:
        return False
    try:
        return not bool(value == v)
    except Exception:  # an argument whose comparison fails: its conversion is all there is to judge
        return False


def _real_number(value: object, name: str, what: str = "a number", bound: float | None = MAX_MAGNITUDE) -> float:
    """``float(value)`` for a real number; TypeError naming ``name`` otherwise (bool and complex included). A number
    beyond the float range is refused naming ``bound``, the caller's (rule 2's :data:`MAX_MAGNITUDE`), or the float
    range itself when None (the printing formatters, which apply no rule-2 bound: fuzz 42b D4). With None, a value
    ``float()`` may not hold exactly (a Decimal, Fraction or longdouble) below float's normal numbers (2.2e-308) is
    refused naming ``name`` (fuzz 44 C3: it was printed as its float on the subnormal grid); a float is exact there."""
    if isinstance(value, (str, bytes, bool, np.bool_)) or value is None:
        raise TypeError(f"{name} must be {what}, got {shown(value)}")
    if isinstance(value, (complex, np.complexfloating)) or (isinstance(value, np.ndarray) and value.dtype.kind == "c"):
        raise _complex_error(name)
    if isinstance(value, np.ma.MaskedArray):  # np.ma.masked included: its mask would be dropped
        raise TypeError(f"{name} must be {what}, got a masked value (its mask would be ignored)")
    if isinstance(value, (np.datetime64, np.timedelta64, _dt.date, _dt.timedelta)):
        raise TypeError(f"{name} must be {what}, got a date or duration {shown(value)} (convert it to seconds first)")
    if isinstance(value, np.ndarray) and value.dtype.kind not in "fiu":  # an object array: arithmetic on it is Python's
        raise TypeError(f"{name} must be {what}, got an array of dtype {value.dtype}")
    if isinstance(value, _decimal.Decimal) and value.is_snan():  # float() refuses a signalling NaN: it is a NaN
        return float("nan")   # (a bad value, the callers' finiteness rule names it; fuzz 49a D1: it was a TypeError)
    try:
        v = float(value)  # type: ignore[arg-type]
        if _lost_in_cast(value, v):  # Decimal('1e400') or np.longdouble('1e4000') -> inf
            raise OverflowError
        if bound is None and abs(v) < MIN_NORMAL and not _float_exact(value) and (v != 0.0 or _nonzero(value)):
            # the printing formatters (bound None) apply no rule-2 bound (fuzz 43 D1); a Fraction, Decimal or
            # longdouble below float's normal numbers becomes a float on the subnormal grid (Decimal('3e-324') printed
            # as 4.94e-324, fuzz 44 C3) or zero: refused, a Python float (exact) printed as it is
            raise ValueError(f"{name} must be {what} of magnitude at least {MIN_NORMAL:.2g} (or zero), the float "
                             f"range's normal numbers, got a non-zero value below them: {shown(value, 60)}")
        if v == 0.0 and not isinstance(value, (float, int)) and _nonzero(value):
            # a Fraction, Decimal or longdouble below the float range (Fraction(1, 10**400)) would become an exact zero
            raise ValueError(f"{name} must be {what} of magnitude at least {MIN_MAGNITUDE:g} (or zero), got a non-zero "
                             f"value below the float range: {shown(value, 60)}")
        return v
    except OverflowError:  # a Python int or Fraction beyond the float range
        if bound is None:
            raise ValueError(f"{name} must be {what} of magnitude within the float range (at most "
                             f"{float(np.finfo(float).max):.3g}), got one beyond it") from None
        raise ValueError(f"{name} must be {what} of magnitude at most {bound:g}, got one beyond the float "
                         "range") from None
    except (TypeError, ValueError) as exc:
        if str(exc).startswith(f"{name} must be {what} of magnitude"):
            raise
        raise TypeError(f"{name} must be {what}, got {_safe_repr(value)}") from None
    except MemoryError:
        raise
    except Exception as exc:  # rule 15: the argument's own exception (its __float__ raised)
        raise _conversion_error(name, exc) from exc


def _float_exact(value: object) -> bool:
    """Whether ``value`` is a float, an integer or a numpy float (scalar or array) of at most 64 bits: ``float()``
    holds it exactly, its subnormals included (a Decimal, Fraction or longdouble may not be held)."""
    if isinstance(value, (float, int, np.integer)):
        return True
    dtype = getattr(value, "dtype", None) if isinstance(value, (np.generic, np.ndarray)) else None
    return dtype is not None and dtype.kind in "fiu" and dtype.itemsize <= 8


def _nonzero(value: object) -> bool:
    """Whether ``value``, which converts to the float 0.0, is not zero: an integer given by ``__index__`` is its
    index (an object with only ``__index__`` compares by identity: fuzz 31b C6), any other number its ``!= 0``."""
    try:
        return _index(value) != 0
    except TypeError:  # not an integer (a Fraction, a Decimal, a float array)
        return bool(value != 0)


def is_integer(value: object) -> bool:
    """Whether ``value`` is an integer scalar (rule 13): an ``int`` or a numpy integer, not a ``bool`` and not a
    :class:`numpy.timedelta64` (a numpy integer subclass: a duration, whose ``int()`` fails or depends on its unit)."""
    return isinstance(value, (int, np.integer)) and not isinstance(value, (bool, np.bool_, np.timedelta64))


def integer(value: object, name: str) -> int:
    """``value`` as an int when it is an integer type (rule 13), without a range: an axis, an exponent, an index
    checked by the caller. A ``bool``, a float (even integral), a :class:`~decimal.Decimal`, a string, a duration
    (:class:`numpy.timedelta64`, a numpy integer subclass) and an object whose ``__index__`` raises are refused with
    a :class:`TypeError` naming ``name``.
    """
    return _integer(value, name)


def axis_of(value: object, name: str, shape: tuple[int, ...], array: str) -> int:
    """``value`` as an axis of an array of ``shape`` (named ``array`` in the message): an integer type
    (:func:`integer`) in ``-ndim .. ndim - 1``, returned non-negative (fuzz 24a U3: an axis past the end was an
    IndexError). A 0-d array has one axis, as numpy's reductions read it.

    Raises
    ------
    TypeError
        ``value`` not an integer, naming ``name``.
    ValueError
        ``value`` outside the array's axes, naming ``name``.
    """
    v = integer(value, name)
    nd = max(len(shape), 1)
    if not -nd <= v < nd:
        raise ValueError(f"{name} = {shown(value)} is out of range for {array} of shape {shape} (an axis in "
                         f"{-nd} .. {nd - 1})")
    return v % nd


def _check_scalar_magnitude(v: float, name: str, value: object, scale: bool = True, tiny: bool = False) -> None:
    """Rule 2 for a scalar, the rule of an array entry: magnitude at most :data:`MAX_MAGNITUDE`, and a
    non-zero value at least :data:`MIN_MAGNITUDE` (a scalar often becomes an entry of the data: a start
    angle, a change time); ``tiny`` lowers that bound to :data:`MIN_NORMAL` for a value that is only
    compared (a margin), never divided by or multiplied. ``scale`` (a positive standard deviation,
    period or threshold) only words the message."""
    if abs(v) > MAX_MAGNITUDE:
        raise ValueError(f"{name} = {shown(value)} is beyond the representable range (magnitude at most {MAX_MAGNITUDE:g})")
    if 0.0 < abs(v) < (MIN_NORMAL if tiny else MIN_MAGNITUDE):
        if not tiny:
            raise ValueError(f"{name} = {shown(value)} is too small (non-zero but below {MIN_MAGNITUDE:g}: "
                             "its products and reciprocals are not representable)")
        raise ValueError(f"{name} = {shown(value)} is subnormal (non-zero but below {MIN_NORMAL:.3g} in magnitude)")


def as_array(
    x: ArrayLike,
    name: str,
    ndim: int | tuple[int, ...] | None = None,
    shape: tuple[int | None, ...] | None = None,
    *,
    finite: bool = True,
    nonempty: bool = True,
    nonnegative: bool = False,
    subnormal: bool = False,
) -> FloatArray:
    """Return ``x`` as a float array, checking dimensions, shape, emptiness and finiteness.

    Parameters
    ----------
    x : array_like
        The value to check.
    name : str
        Argument name used in error messages.
    ndim : int or tuple of int, optional
        Allowed numbers of dimensions.
    shape : tuple of int or None, optional
        Required shape; ``None`` entries match any length (implies ``ndim``).
    finite : bool
        Refuse NaN and infinity.
    nonempty : bool
        Refuse arrays with no element.
    nonnegative : bool
        Refuse negative entries.
    subnormal : bool
        Accept subnormal entries (weights); by default they are refused with the other
        unrepresentable magnitudes when ``finite`` is set (see :func:`check_magnitude`).

    Raises
    ------
    TypeError
        If ``x`` is not numeric (e.g. a string) or complex.
    ValueError
        Wrong dimensions or shape, empty, NaN/inf, magnitudes beyond :data:`MAX_MAGNITUDE`,
        subnormal entries, or negative entries.
    """
    arr = _numeric(x, name)
    if shape is not None:
        ok = arr.ndim == len(shape) and all(s is None or s == a for s, a in zip(shape, arr.shape))
        if not ok:
            want = "(" + ", ".join("n" if s is None else str(s) for s in shape) + ("," if len(shape) == 1 else "") + ")"
            raise ValueError(f"{name} must have shape {want}, got {arr.shape}")
    elif ndim is not None:
        allowed = (ndim,) if isinstance(ndim, int) else ndim
        if arr.ndim not in allowed:
            raise ValueError(f"{name} must be {' or '.join(f'{d}-D' for d in allowed)}, got shape {arr.shape}")
    if nonempty and arr.size == 0:
        raise ValueError(f"{name} is empty (shape {arr.shape})")
    if finite:
        check_magnitude(arr, name, subnormal=not subnormal)
    if nonnegative and np.any(arr < 0):
        raise ValueError(f"{name} must be non-negative")
    return arr


def as_times(t: ArrayLike, name: str, min_len: int = 1) -> FloatArray:
    """Sample times (s): a finite 1-D float array of at least ``min_len`` strictly increasing entries.

    The magnitude rule (rule 2) applies: a time of ``1e-300`` s next to ``0`` gives a step whose
    reciprocal overflows, so non-zero times below :data:`MIN_MAGNITUDE` are refused by name.

    Raises
    ------
    TypeError
        Not numeric (booleans and complex included).
    ValueError
        Not 1-D, too short, NaN/inf, magnitudes out of range, or not strictly increasing.
    """
    arr = as_array(t, name, ndim=1)
    if arr.size < min_len:
        raise ValueError(f"{name} must hold at least {min_len} samples, got {arr.size}")
    if arr.size > 1 and not (arr[1:] > arr[:-1]).all():
        raise ValueError(f"{name} must be strictly increasing (sample times)")
    return arr


def same_length(a: FloatArray, name_a: str, b: FloatArray, name_b: str, axis_a: int = 0, axis_b: int = 0) -> None:
    """Check that two paired arrays have the same length along the given axes."""
    if a.shape[axis_a] != b.shape[axis_b]:
        raise ValueError(
            f"{name_a} and {name_b} must have matching lengths, got {a.shape[axis_a]} and {b.shape[axis_b]} "
            f"(shapes {a.shape} and {b.shape})"
        )


def scalar(
    value: float,
    name: str,
    lo: float | None = None,
    hi: float | None = None,
    *,
    lo_open: bool = False,
    hi_open: bool = False,
    tiny: bool | None = None,
) -> float:
    """Return ``value`` as a finite float in the interval given by ``lo`` and ``hi``.

    A non-zero value below :data:`MIN_MAGNITUDE` in magnitude is refused (rule 2), as an array
    entry would be (a signed scalar such as a start angle or a change time becomes one), unless
    ``tiny``: then only subnormals are refused. ``tiny`` defaults to true for a non-negative
    quantity whose zero is valid (``lo=0`` closed: a weight, a ridge parameter, a margin), where a
    tiny value is numerically that zero, and to false otherwise (positive scales included).

    Raises
    ------
    TypeError
        If ``value`` is not a real number (a string, a bool, a complex number, an array of more
        than one element, ...).
    ValueError
        If ``value`` is NaN, infinite, out of range, beyond :data:`MAX_MAGNITUDE` or subnormal.
    """
    v = _real_number(value, name)
    if not np.isfinite(v):
        raise ValueError(f"{name} must be finite, got {shown(value)}")
    _check_scalar_magnitude(v, name, value, scale=lo == 0.0 and lo_open,
                            tiny=(lo == 0.0 and not lo_open) if tiny is None else tiny)
    if lo is not None and (v < lo or (lo_open and v == lo)):
        if lo == 0.0:
            raise ValueError(f"{name} must be {'positive' if lo_open else 'non-negative'}, got {shown(value)}")
        raise ValueError(f"{name} must be {'>' if lo_open else '>='} {lo}, got {shown(value)}")
    if hi is not None and (v > hi or (hi_open and v == hi)):
        raise ValueError(f"{name} must be {'<' if hi_open else '<='} {hi}, got {shown(value)}")
    # a bounded value's signed zero is its zero: -0.0 passed `lo = 0` and then reached numpy as a negative
    # upper end (``rng.uniform(0, -0.0)``: "high - low < 0", fuzz 15)
    return v + 0.0 if lo is not None or hi is not None else v


def given_number(value: object, name: str, lo: float | None = None, hi: float | None = None, **kw: bool) -> int | float:
    """``value`` checked by :func:`scalar` (same bounds and keywords), as the plain number a glued value shows:
    an ``int`` for an integer type (a Python or NumPy integer, a 0-d integer array: printed without a decimal
    point, as given), else the float :func:`scalar` returns, never the caller's object (fuzz 22b, FR: a
    :class:`~fractions.Fraction`, a :class:`~decimal.Decimal` or a 0-d array checked, then used or glued raw)."""
    v = scalar(value, name, lo, hi, **kw)  # type: ignore[arg-type]
    if is_integer(value) or (isinstance(value, np.ndarray) and value.dtype.kind in "iu"):
        return int(value)  # type: ignore[call-overload]
    return v


def store_read(obj: object, name: str, read: object) -> None:
    """Store in the frozen dataclass ``obj``'s field ``name`` the value its validation ``read`` (rule 20), unless
    the caller gave a plain ``int``, ``float`` or ``str``, which are what they read as: a ``float`` subclass whose
    ``__float__`` disagrees with its stored value would otherwise be validated as one number and computed with as
    the other, and a ``str`` subclass matched by its own ``==``."""
    if type(getattr(obj, name)) not in (int, float, str):
        object.__setattr__(obj, name, read)


def nonnegative_scalar(value: float, name: str) -> float:
    """Return ``value`` as a finite float >= 0."""
    return scalar(value, name, lo=0.0)


def tolerance(value: float, name: str) -> float:
    """Return a stopping tolerance ``value`` as a finite float > 0: only compared, never divided by or multiplied,
    so a tiny one (``ftol=1e-300``: run to the iteration limit) is valid down to the smallest normal float."""
    return scalar(value, name, lo=0.0, lo_open=True, tiny=True)


def unit_scalar(value: float, name: str) -> float:
    """Return ``value`` as a finite float in the closed interval [0, 1]."""
    return scalar(value, name, lo=0.0, hi=1.0)


#: The largest tolerance :func:`sums_to_one` allows a short float's ``2 n eps`` to reach (fuzz 27a F4): ten float16
#: epsilons. A float16 vector normalised in its own precision sums to one within about eps/2 of its total (each
#: weight's rounding is relative), whatever n; uncapped, ``2 n eps(float16)`` reaches 1 at n = 512 and 600 float16
#: weights summing to 0.06 passed as a simplex.
SIMPLEX_TOL_CAP = 1e-2


def sums_to_one(w: FloatArray, given: object, axis: int = -1, floor: float = 1e-9) -> bool:
    """Whether the weights ``w`` (floats) sum to one along ``axis``: the package's one simplex rule for the sum.

    The tolerance is ``floor`` (the check's own, for float64 weights) or ``2 n`` times the machine epsilon of the
    caller's ``given`` weights (:func:`input_eps`), whichever is larger, but never more than ``SIMPLEX_TOL_CAP``
    (1e-2): weights normalised in float32 or float16 (``0.4f + 0.6f``) sum to one in their own precision and are
    accepted, while weights that sum to 0.06 or 1.9 are refused at every n; accepted short floats are then used
    divided by their sum (:func:`renormalised`, at every caller of this rule).

    The floors differ by what the weights come from, and each is kept: 1e-9 for weights a caller states
    (``GaussianMixture``, the fused mixtures, grid normalisers), 1e-8 for a simplex an optimiser returns
    (``fusion.optimise.simplex.check_simplex``: its iterates carry its solver's round-off), 1e-6 for particle
    weights (``fusion.filtering.particles``: weights normalised after many likelihood products). Unifying them
    would change which weights the chapters' filters and optimisers accept (fuzz 27a D1: not re-run, so kept).
    """
    tol = max(floor, min(2.0 * w.shape[axis] * input_eps(given), SIMPLEX_TOL_CAP))
    return bool(np.all(np.abs(w.sum(axis=axis) - 1.0) <= tol))


def renormalised(w: FloatArray, given: object, axis: int = -1) -> FloatArray:
    """The weights ``w`` (floats that :func:`sums_to_one` accepted) as they are used: divided by their sum along
    ``axis`` (in float64) when the caller gave them in float32 or float16, as given otherwise.

    The simplex rule's second half (fuzz 28a C3, D1): a short float's sum is one only within its own precision
    (up to ``SIMPLEX_TOL_CAP``, 1 % for float16), and weights used as given would carry that error into what
    they weigh (an effective sample size above the particle count, a fused information 1 % small); float64
    weights are within the check's own floor and are used as the caller gave them (unchanged results)."""
    if input_eps(given) > _F64_EPS:
        return w / w.sum(axis=axis, keepdims=True)
    return w


def solve(A: FloatArray, b: FloatArray, name: str, *, assume: str = "gen") -> FloatArray:
    """``numpy.linalg.solve(A, b)`` with a ValueError naming ``name`` for a singular or non-finite system (rule 5).

    Parameters
    ----------
    A : ndarray, shape (..., n, n)
        The matrix.
    b : ndarray
        Right-hand side(s).
    name : str
        The argument (or arguments) the matrix is made of, named in the message.
    assume : str
        Unused: kept for the call sites' documentation of the matrix kind.

    Raises
    ------
    ValueError
        If ``A`` is singular to working precision or the solution is not finite.
    """
    try:
        with np.errstate(all="ignore"):
            x = np.linalg.solve(A, b)
    except np.linalg.LinAlgError:
        raise ValueError(f"{name} gives a singular system (the matrix to invert is singular)") from None
    if not np.isfinite(x).all():
        raise ValueError(f"{name} gives a numerically singular system (the solution overflows)")
    return x


def as_callable(f: object, name: str) -> object:
    """Check that ``f`` is callable (TypeError otherwise)."""
    if not callable(f):
        raise TypeError(f"{name} must be callable, got {type(f).__name__}")
    return f


def instance_of(obj: object, cls: type | tuple[type, ...], name: str) -> None:
    """Check ``isinstance(obj, cls)`` (TypeError naming ``name`` otherwise)."""
    if not isinstance(obj, cls):
        want = cls.__name__ if isinstance(cls, type) else " or ".join(c.__name__ for c in cls)
        raise TypeError(f"{name} must be a {want}, got {type(obj).__name__}")


def as_weights(w: ArrayLike, name: str, n: int | None = None) -> FloatArray:
    """Return ``w`` as a finite, non-negative 1-D float vector with a positive sum (length ``n``)."""
    arr = as_array(w, name, ndim=1, nonnegative=True, subnormal=True)
    if n is not None and arr.size != n:
        raise ValueError(f"{name} must have length {n}, got {arr.size}")
    if not arr.sum() > 0:
        raise ValueError(f"{name} must have a positive sum")
    return arr


def as_readings(x: ArrayLike, name: str = "x", pairs: int = 0) -> FloatArray:
    """Return ``x`` as a non-empty, finite, 1-D float array.

    Parameters
    ----------
    x : array_like, shape (n,)
        Simultaneous scalar readings of one quantity.
    name : str
        Argument name used in error messages.
    pairs : int
        The n x n float64 arrays the caller's pairwise kernel holds at once (0: no pairwise kernel); its
        memory and work are checked by :func:`pairwise` (rules 9 and 17) before any of it.

    Raises
    ------
    ValueError
        If ``x`` is not 1-D, is empty, or contains NaN or infinity, or its pairwise kernel is beyond the budgets.
    """
    arr = _numeric(x, name)
    if arr.ndim != 1:
        raise ValueError(f"{name} must be a 1-D array of readings, got shape {arr.shape}")
    if arr.size == 0:
        raise ValueError(f"{name} is empty: at least one reading is needed")
    if pairs:
        pairwise(arr.size, name, pairs)
    return check_magnitude(arr, name)


def as_reading_rows(x: ArrayLike, name: str = "x", pairs: int = 0, cubic: bool = False) -> FloatArray:
    """Return ``x`` as a finite 2-D float array of shape (n_epochs, n_sensors).

    A 1-D input is treated as a single epoch (one row).

    Parameters
    ----------
    x : array_like, shape (n_epochs, n_sensors) or (n_sensors,)
        Readings, one epoch a row.
    name : str
        Argument name used in error messages.
    pairs : int
        The n_sensors x n_sensors float64 arrays the caller's pairwise kernel holds at once, computed row after
        row (0: no pairwise kernel); with ``cubic``, each row's matrix is also decomposed. Checked by
        :func:`pairwise` (rules 9 and 17) before any of it.
    cubic : bool
        See ``pairs``.

    Raises
    ------
    ValueError
        If ``x`` has more than two dimensions, has no sensor column, or is not finite, or its pairwise kernel is
        beyond the budgets.
    """
    arr = _numeric(x, name)
    if arr.ndim == 1:
        arr = arr[None, :]
    if arr.ndim != 2:
        raise ValueError(
            f"{name} must be 2-D (n_epochs, n_sensors) or 1-D (n_sensors,), got shape {arr.shape}"
        )
    if arr.shape[1] == 0 or arr.shape[0] == 0:
        raise ValueError(f"{name} is empty: got shape {arr.shape}")
    if pairs:
        pairwise(arr.shape[1], name, pairs, rows=arr.shape[0], cubic=cubic)
    return check_magnitude(arr, name)


def positive_scalar(value: float, name: str) -> float:
    """Return ``value`` as a float, checking that it is finite and strictly positive."""
    v = _real_number(value, name)
    if not np.isfinite(v) or v <= 0.0:
        raise ValueError(f"{name} must be a finite positive number, got {shown(value)}")
    _check_scalar_magnitude(v, name, value)
    return v


def as_state(x: ArrayLike, name: str = "x") -> FloatArray:
    """Return ``x`` as a finite 1-D float state vector of length >= 1."""
    arr = _numeric(x, name)
    if arr.ndim == 0:
        arr = arr[None]
    if arr.ndim != 1 or arr.size == 0:
        raise ValueError(f"{name} must be a non-empty 1-D vector, got shape {arr.shape}")
    return check_magnitude(arr, name)


#: Smallest standard deviation accepted by :func:`std_scalar`: its square, a variance, is at least
#: :data:`MIN_VARIANCE` (the covariance rule), so that the noise covariance it makes is accepted.
MIN_STD = float(np.sqrt(MIN_VARIANCE))
#: Largest standard deviation accepted by :func:`std_scalar`: its square, a variance, stays within
#: :data:`MAX_MAGNITUDE` (``1e75``).
MAX_STD = float(np.sqrt(MAX_MAGNITUDE))


def std_scalar(value: float, name: str) -> float:
    """A standard deviation: finite, positive, and with a square that is a valid variance (rule 2).

    A filter or a simulation squares it into a noise covariance, which the covariance rule bounds to
    [:data:`MIN_VARIANCE`, :data:`MAX_MAGNITUDE`]: the documented bound of a standard deviation is
    therefore [:data:`MIN_STD`, :data:`MAX_STD`] (about ``1.2e-77`` to ``1e75``), so that a study
    refuses ``sigma = 1e150`` by name rather than through the variance it derives from it.

    Raises
    ------
    TypeError
        Not a real number.
    ValueError
        Not finite, not positive, above :data:`MAX_STD`, or below :data:`MIN_STD`.
    """
    v = positive_scalar(value, name)
    if v < MIN_STD:
        raise ValueError(f"{name} = {shown(value)} is too small: its square, a variance, is below {MIN_VARIANCE:.3g} "
                         f"(at least {MIN_STD:.3g})")
    if v > MAX_STD:
        raise ValueError(f"{name} = {shown(value)} is too large: its square, a variance, is beyond {MAX_MAGNITUDE:g} "
                         f"(at most {MAX_STD:.3g})")
    return v


def step_scalar(value: float, name: str, power: int, *, zero: bool = False) -> float:
    """A step (a time step, a period) that the model raises to powers up to ``power`` (rule 2).

    A white-acceleration process noise holds ``T**4 / 4``, a white-jerk one ``T**5 / 20``: a step
    inside the range of a scalar (``T = 1e150``) would overflow there. The documented bound is the
    one the model can honour: ``T**power`` stays within :data:`MAX_MAGNITUDE`, that is
    ``T <= MAX_MAGNITUDE ** (1 / power)`` (``1e37.5`` for the 4th power); below, the rule of
    :func:`scalar` (a non-zero step at least :data:`MIN_MAGNITUDE`; its powers may underflow to
    zero, a step without noise).

    Parameters
    ----------
    value : float
        The step.
    name : str
        Argument name used in the messages.
    power : int
        The highest power of the step the model forms.
    zero : bool
        Accept a zero step (``dt >= 0``); otherwise the step must be positive.

    Returns
    -------
    float
        The step, a float at most ``MAX_MAGNITUDE ** (1 / power)``.

    Raises
    ------
    TypeError
        Not a real number.
    ValueError
        Not finite, negative (or zero unless ``zero``), or beyond ``MAX_MAGNITUDE ** (1 / power)``.
    """
    v = nonnegative_scalar(value, name) if zero else positive_scalar(value, name)
    top = MAX_MAGNITUDE ** (1.0 / power)
    if v > top:
        raise ValueError(f"{name} = {shown(value)} is too large: the model forms {name}**{power}, which must stay within "
                         f"{MAX_MAGNITUDE:g} ({name} at most {top:.3g})")
    return v


# The selection rules (masks, slices, windows) live in fusion._selections and the covariance rules in
# fusion._covariances; both use the rules above and are re-exported here lazily (PEP 562), so that either module can
# be imported first: an eager import here made ``import fusion._covariances`` (and every module importing it before
# this one, e.g. fusion.scenarios.range_bearing_batch) fail on the import cycle.
_REEXPORTED = {
    "fusion._selections": ("as_mask", "frame_slice", "selection", "window"),
    "fusion._covariances": ("_SMALL_PAIR", "_TINY", "_covariance_magnitude", "_finite_symmetric", "as_covariance",
                            "as_covariances", "as_semidefinite", "check_invertible", "computed_part",
                            "refuse_singular", "covariance_pair", "diagonal_covariance", "gaussian_pair",
                            "COVARIANCE_RTOL", "asymmetric"),
}


def __getattr__(name: str) -> object:
    """The selection and covariance rules, from the modules that define them (imported on first use)."""
    for module, names in _REEXPORTED.items():
        if name in names:
            return getattr(importlib.import_module(module), name)
    raise AttributeError(f"module 'fusion._validation' has no attribute '{name}'")
