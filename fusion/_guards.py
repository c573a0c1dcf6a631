"""Guards on what a public function returns and raises (the shared rules of :mod:`fusion._validation`).

:func:`finite_result` refuses a non-finite result that in-range inputs produced (naming the inputs), and
:func:`derived_inputs` re-raises an error about an internal array under the public argument that caused it.
Both are re-exported by :mod:`fusion._validation`, where the package imports them from.
"""

from __future__ import annotations

import array as _array
from collections.abc import Mapping as _Mapping
from collections.abc import Sequence as _Sequence

import dataclasses as _dataclasses
import functools as _functools
import inspect as _inspect
import re as _re
from itertools import islice as _islice
from collections.abc import Callable
from math import isfinite as _isfinite

import numpy as np

from fusion._limits import MAX_MAGNITUDE


def _first_nonfinite(out: object, path: str = "", depth: int = 0) -> str | None:
    """The path of a non-finite float in a result (arrays, floats, dataclasses, tuples, lists, dicts), or ``None``."""
    if isinstance(out, (float, np.floating)):
        return None if _isfinite(out) else (path or ".")
    if isinstance(out, np.ndarray):
        return None if out.dtype.kind not in "fc" or np.isfinite(out).all() else (path or ".")
    if depth > 4:
        return None
    if _dataclasses.is_dataclass(out) and not isinstance(out, type):
        items = ((f.name, getattr(out, f.name)) for f in _dataclasses.fields(out))
    elif isinstance(out, (tuple, list)):
        items = ((f"[{i}]", v) for i, v in enumerate(out))
    elif isinstance(out, _Mapping):  # a dict, or a frozen result's read-only mapping
        items = ((f"[{k!r}]", v) for k, v in out.items())
    else:
        return None
    for key, v in items:
        found = _first_nonfinite(v, f"{path}.{key}" if not key.startswith("[") else path + key, depth + 1)
        if found is not None:
            return found
    return None


def finite_result(names: str) -> Callable[[Callable[..., object]], Callable[..., object]]:
    """Decorate a public function whose result is finite for every valid input (rule 2, issue 35 class 5).

    Each argument may be within the accepted range while a product of them is not (``F`` with
    entries ``1e150`` propagated through ``F P F^T``): the result then holds NaN or infinity. This
    checks the result once at the end of the public entry and refuses it with a :class:`ValueError`
    naming the arguments it is computed from, instead of returning non-finite numbers. An
    :class:`OverflowError` or :class:`numpy.linalg.LinAlgError` from the same cause becomes the
    same :class:`ValueError`. Results are unchanged otherwise.

    Parameters
    ----------
    names : str
        The arguments the result is computed from (``"F, H, Q and R"``), named in the message.

    Returns
    -------
    callable
        A decorator: the wrapped function returns what ``fn`` returns, or raises a :class:`ValueError` naming
        ``names`` where that result is not finite (or an OverflowError/LinAlgError escaped).
    """
    def wrap(fn: Callable[..., object]) -> Callable[..., object]:
        @_functools.wraps(fn)
        def call(*args: object, **kwargs: object) -> object:
            try:
                with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
                    out = fn(*args, **kwargs)
            except (OverflowError, np.linalg.LinAlgError) as exc:
                raise ValueError(f"{names} give a result that is not representable ({type(exc).__name__}: {exc}): "
                                 "the inputs are each within range, their combination is not") from None
            where = _first_nonfinite(out)
            if where is not None:
                raise ValueError(f"{names} give a non-finite result (in {where}): the inputs are each within range, "
                                 "but a product of them overflows or underflows")
            return out
        return call
    return wrap


#: An argument whose magnitude is beyond the square root of the range (``1e75``, or non-zero below
#: ``1e-75``) is the likely cause of a derived quantity out of range: its square already is.
_EXTREME = MAX_MAGNITUDE ** 0.5


def _extreme(value: object) -> bool:
    """Whether a numeric argument holds a magnitude whose square leaves the range (see :data:`_EXTREME`)."""
    if isinstance(value, (bool, np.bool_, str, bytes)) or value is None:
        return False
    try:  # the size first: a range(10**7) or a zero-stride array is not converted to floats for an error message
        n = value.size if isinstance(value, np.ndarray) else len(value)  # type: ignore[arg-type]
    except Exception:  # noqa: BLE001 (no length: a scalar, or the argument's own exception)
        n = 0
    if n > 10**6:
        return False
    try:
        a = np.abs(np.asarray(value, dtype=float))
    except Exception:  # noqa: BLE001 (an argument's own exception, rule 15: not the culprit of a derived quantity)
        return False
    if a.size == 0 or a.size > 10**6:
        return False
    with np.errstate(invalid="ignore"):
        nz = a[a > 0]
        return bool(nz.size and (float(nz.max()) > _EXTREME or float(nz.min()) < 1.0 / _EXTREME))


def _join(names: list[str]) -> str:
    return names[0] if len(names) == 1 else ", ".join(names[:-1]) + " and " + names[-1]


def derived_inputs(names: str | None = None) -> Callable[[Callable[..., object]], Callable[..., object]]:
    """Decorate a public entry whose inner steps validate arrays derived from its arguments (issue 35).

    A study simulates ``X = x + sigma * noise`` and passes ``X`` to a validated reading function: with
    ``sigma = 1e150`` (within the range of a scalar) the inner check refuses ``X`` by its internal name
    (``X has an entry of magnitude 1e+300``), which names no argument of the entry. This turns such a
    :class:`ValueError` (a :class:`numpy.linalg.LinAlgError` or :class:`OverflowError` included) into
    a :class:`ValueError` naming the public arguments it comes from: those among ``names`` whose
    magnitude is extreme (beyond ``1e75`` or non-zero below ``1e-75``: their squares leave the range),
    or all of ``names`` if none is; the inner message follows. A message that already starts with an
    argument of the entry passes unchanged, unless that argument is not extreme and another one is (an
    internal ``x`` derived from ``sigma``); a :class:`TypeError` passes unchanged. No cost on success.

    Parameters
    ----------
    names : str, optional
        The arguments the derived quantities come from (``"sigma, x and bias"``); all parameters of
        the entry by default.

    Returns
    -------
    callable
        A decorator: the wrapped entry returns what it returned; a :class:`ValueError` about a derived array
        is re-raised naming the public argument(s) at an extreme magnitude.
    """
    def wrap(fn: Callable[..., object]) -> Callable[..., object]:
        sig = _inspect.signature(fn)
        params = tuple(sig.parameters)
        listed = tuple(params if names is None else
                       (n.strip() for n in _re.split(r",|\band\b", names) if n.strip()))
        own = _re.compile(r"^(?:" + "|".join(map(_re.escape, params)) + r")(?![A-Za-z0-9_])") if params else None

        @_functools.wraps(fn)
        def call(*args: object, **kwargs: object) -> object:
            try:
                return fn(*args, **kwargs)
            except (ValueError, OverflowError) as exc:
                msg = str(exc)
                m = own.match(msg) if own is not None and type(exc) is ValueError else None
                try:
                    bound = sig.bind(*args, **kwargs)
                    bound.apply_defaults()
                    culprits = [n for n in listed if n in bound.arguments and _extreme(bound.arguments[n])]
                except TypeError:
                    culprits = []
                if m is not None and (not culprits or m.group(0) in culprits):
                    raise  # the message names the argument at fault already
                who = _join(culprits or list(listed))
                verb = "gives" if len(culprits or listed) == 1 else "give"
                inner = msg if len(msg) <= 300 else msg[:300] + "..."
                raise ValueError(f"{who} {verb} a derived quantity that is refused: {inner}") from None
        return call
    return wrap


def own_underflow(fn: Callable[..., object]) -> Callable[..., object]:
    """Decorate a function whose numerics underflow by design: it runs under ``np.errstate(under="ignore")``.

    numpy's default error state ignores underflow; a particle filter relies on it (the weight of a far particle,
    ``exp`` of a log-weight thousands below the best, is an intended zero, and so are its products). A caller's
    ``np.errstate(all="raise")`` turned that zero into a ``FloatingPointError`` (fuzz 31a D1: ``run_network_study``).
    Such a function sets its own underflow state for its whole call; overflow, division by zero and invalid
    operations keep the caller's. Elsewhere the package runs under the caller's error state. The rule (fuzz 33b
    D6) marks every function that computes such an intended zero: a public entry, or the function where the
    ``exp`` is (a log-sum-exp, normalised weights, a Gaussian or exponential kernel, a density on a grid), so
    that every entry that reaches it is covered.

    Parameters
    ----------
    fn : callable
        The entry.

    Returns
    -------
    callable
        ``fn``, run under ``np.errstate(under="ignore")``.
    """
    @_functools.wraps(fn)
    def call(*args: object, **kwargs: object) -> object:
        with np.errstate(under="ignore"):
            return fn(*args, **kwargs)
    return call


def argument_copy(x: np.ndarray) -> np.ndarray:
    """The array a caller's callable (an objective, a registration, a fitness) is given: a copy of the package's own.

    One rule for every callable the package calls with an array it reads again afterwards (fuzz 29a C7): a callable
    may change its argument in place (``s *= 10`` after using it), and, given the package's own candidates, it
    would move the point the package then reads back (:func:`~fusion.optimise.scalar.grid_search` returned an
    ``x`` outside ``[lo, hi]`` with the ``fun`` of another point). A copy costs a few microseconds for the
    package's candidate arrays (hundreds to thousands of floats), far below one call of the callable.

    Parameters
    ----------
    x : ndarray
        The package's array.

    Returns
    -------
    ndarray
        A writeable copy (the callable may change it; nothing reads it afterwards).
    """
    return np.array(x, copy=True)


def value_copy(v: object) -> object:
    """What a caller's callable returned, kept as it was when returned: an array copied as it is received.

    The sibling of :func:`argument_copy` for what the package keeps (fuzz 30a C5): a callable may return one
    buffer it overwrites at each call (a 0-d array filled in place), and values collected call by call
    (``[f(x) for x in xs]``, converted after the loop) were then all that buffer, the last value
    (:func:`~fusion.optimise.scalar.grid_search` returned ``x = 0`` with the ``fun`` of ``x = 1``). Every
    optimiser reads each objective value through this (or converts it at once, ``objective_values``).

    Parameters
    ----------
    v : object
        What the callable returned.

    Returns
    -------
    object
        A copy of ``v`` if it is an ndarray (its subclass kept: a masked array is refused afterwards by name),
        else ``v`` itself (numbers are immutable; anything else is refused by the checks that follow).
    """
    return v.copy() if isinstance(v, np.ndarray) else v


#: Arguments read as they are, any number of times: arrays (their subclasses too: a masked array is refused by the
#: checks that follow, by name), lists, tuples, numbers, strings, None and mappings give the same values at each read.
_STABLE = (np.ndarray, list, tuple, int, float, complex, np.generic, str, bytes, bytearray, type(None), _Mapping)


class _LengthLie(ValueError):
    """A sequence whose ``len()`` disagrees with its items, or is beyond the input budget (raised by :func:`_items`,
    passed on as it is)."""


def _items(x: _Sequence, name: str) -> list:
    """The items of the sequence ``x``, at most ``len(x)`` + 1 of them read (fuzz 42a C1): a ``__len__`` that lies
    (3, over a ``__getitem__`` answering up to index ``10**8``, or never raising IndexError) is refused by name after
    one item past it, as ``fusion._validation.sequence`` does, never read in full (24 CPU-s) or for ever. A ``len()``
    beyond the input budget
    (``fusion._limits.MAX_INPUT_ELEMENTS``) is refused by name before any item is read (fuzz 44 C1: a mapping of
    ``len()`` ``sys.maxsize`` whose items never end was read without bound; such a ``len()`` had overflowed
    ``islice``'s stop before, fuzz 43 C3), so at most that budget + 1 items are ever read."""
    from fusion._limits import MAX_INPUT_ELEMENTS

    n = len(x)
    if n > MAX_INPUT_ELEMENTS:
        raise _LengthLie(f"{name} has len() {n:.3g}, beyond the input budget (at most {MAX_INPUT_ELEMENTS:,} "
                         "entries, fusion._validation.MAX_INPUT_ELEMENTS)")
    out = list(_islice(iter(x), n + 1))
    if len(out) != n:
        raise _LengthLie(f"{name} has len() {n} but {'more' if len(out) > n else len(out)} items (a sequence's "
                         "len() must count its items)")
    return out


def _materialised(x: _Sequence, budget: list[int], depth: int = 0, name: str = "x") -> list:
    """A sequence argument (not a list, tuple, array or text) as the list of its entries, read in one pass; its
    entries that are such sequences too, likewise (down to ``fusion._nesting.MAX_NESTING`` levels; deeper ones are
    left to the checks, which refuse them by name). ``budget`` (a one-entry list) is the number of entries that may
    still be read: a nested sequence longer than what is left is not read (fuzz 33a C1: ``deque([range(10**7)] * 5)``),
    and the input budget then refuses the whole by its lengths (``fusion._validation.input_size``). Each sequence is
    read by :func:`_items`: at most its ``len()`` + 1 items, a ``len()`` that disagrees with them refused naming
    ``name`` (fuzz 42a C1)."""
    out = _items(x, name)
    for i, v in enumerate(out):
        if depth < 64 and isinstance(v, _Sequence) and not isinstance(v, _STABLE) and not _array_like(v):
            if len(v) > budget[0]:  # beyond the budget with the entries read so far: left unread, refused by length
                break
            out[i] = _materialised(v, budget, depth + 1, f"{name}[{i}]")
        else:
            budget[0] -= 1
    return out


def _array_like(x: object) -> bool:
    """Whether ``x`` converts through numpy's array protocols (``__array__``, the array interface, a buffer)."""
    return (hasattr(x, "__array__") or hasattr(x, "__array_interface__") or hasattr(x, "__array_struct__")
            or isinstance(x, (memoryview, _array.array)))


def read_mapping(m: object, name: str) -> object:
    """A mapping argument read once, at the entry of a function that checks its values and then reads them again
    (fuzz 31a C2, C3): a ``collections.abc.Mapping`` that is not a plain ``dict`` becomes the plain dict of its
    items, read in one pass, so that its values are checked and used as one read (a mapping whose ``__getitem__``
    gives another value at each call made a function check one value and compute with another: NaN means, a NaN
    glued). A plain ``dict`` (its values fixed) and anything that is not a mapping (refused by the function's own
    checks, by name) are returned as they are. The values themselves are not converted: the function checks them
    and computes with what its checks return.

    Parameters
    ----------
    m : object
        The argument.
    name : str
        Its name, for the message.

    Returns
    -------
    object
        ``m`` itself, or the dict of its items.

    Raises
    ------
    TypeError
        Reading its items raised (the argument's own exception, rule 15), naming ``name``.
    ValueError
        Its ``len()`` is beyond the input budget (refused before reading, fuzz 44 C1) or disagrees with its items
        (at most ``len()`` + 1 of them read, fuzz 42a C1), naming ``name``.
    """
    if type(m) is dict or not isinstance(m, _Mapping):
        return m
    try:
        return dict(_items(m.items(), name))
    except MemoryError:
        raise
    except _LengthLie as exc:  # a plain ValueError for the caller
        raise ValueError(str(exc)) from None
    except Exception as exc:  # noqa: BLE001 (rule 15: the argument's own exception, named and chained)
        raise TypeError(f"{name} could not be read as a mapping: it raised {type(exc).__name__}: "
                        f"{str(exc):.200}") from exc


def read_once(x: object, name: str) -> object:
    """An array-like argument converted once, at the entry of a function that reads it more than once (fuzz 29a C5).

    A function that checks an argument through one function and computes with it in another converts it twice; an
    object whose conversion is not a fixed value (an ``__array__`` that gives other numbers, or one entry more, at
    each call; a buffer the caller changes between the reads) was then checked as one array and computed with as
    another (NaN results, an ``IndexError``, an inner argument named). Any argument but those of ``_STABLE``
    (an object with ``__array__``, a pandas object, a buffer, an ``array.array``) is converted here to the ndarray
    it gives, its dtype kept, and that array is what the function's checks and computations read. A
    ``collections.abc.Sequence`` without those protocols (a ``range``, a ``deque``, a user's Sequence class; not a
    list, tuple, text or array, which are read as they are at no cost) is read once into the list of its entries
    (nested such sequences too), which the checks then convert like any list (fuzz 31a C4). Its shape (or length)
    is checked against the input budget before the conversion (``fusion._validation.input_size``).

    Parameters
    ----------
    x : object
        The argument.
    name : str
        Its name, for the messages.

    Returns
    -------
    object
        ``x`` itself if it is of a ``_STABLE`` type (or neither array-like nor a sequence: the checks refuse it by
        name), else the ndarray it converts to (the list of its entries for a sequence).

    Raises
    ------
    TypeError
        The conversion raised (the argument's own exception, rule 15), naming ``name``.
    ValueError
        A shape beyond the input budget (rule 9), or a sequence whose ``len()`` disagrees with its items (at most
        ``len()`` + 1 of them read, fuzz 42a C1), naming ``name``.
    """
    if isinstance(x, _STABLE):
        return x
    array_like = _array_like(x)
    if not array_like and not isinstance(x, _Sequence):
        return x
    from fusion._limits import MAX_INPUT_ELEMENTS
    from fusion._validation import input_size  # (a cycle at import: fusion._validation imports this module)

    input_size(x, name)
    try:
        if not array_like:  # a sequence without numpy's protocols (a range, a deque, a Sequence class): its entries
            n = len(x)      # read in one pass, as the list they make (fuzz 31a C4)
            if n <= MAX_INPUT_ELEMENTS:
                out = _materialised(x, [MAX_INPUT_ELEMENTS], name=name)
        else:
            return np.asarray(x)
    except MemoryError:
        raise
    except _LengthLie as exc:  # a plain ValueError for the caller
        raise ValueError(str(exc)) from None
    except Exception as exc:  # noqa: BLE001 (rule 15: the argument's own exception, named and chained)
        raise TypeError(f"{name} could not be converted to an array: it raised {type(exc).__name__}: "
                        f"{str(exc):.200}") from exc
    if n <= MAX_INPUT_ELEMENTS:
        input_size(out, name)  # its nested lengths, now read (fuzz 33a C1)
        return out
    raise ValueError(f"{name} has {n:.3g} entries, beyond the input budget (at most {MAX_INPUT_ELEMENTS:,}, "
                     "fusion._validation.MAX_INPUT_ELEMENTS)")
