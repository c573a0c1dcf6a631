"""Read-only array fields for the package's frozen result dataclasses."""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from typing import Any, TypeVar

import numpy as np

from fusion._nesting import MAX_NESTING, nesting_error

T = TypeVar("T")


class ReadOnlyMapping(Mapping):
    """A read-only mapping that survives :func:`copy.copy`, :func:`copy.deepcopy` and pickle (issue 35).

    The role of a ``mappingproxy`` (no item assignment, no ``update``) for a field of a public
    result, which a ``mappingproxy`` could not fill: it can be neither deep-copied nor pickled. A copy or an
    unpickled object is again a :class:`ReadOnlyMapping` of equal items (a deep copy of them for
    ``deepcopy`` and pickle); it compares equal to any mapping of the same items.
    """

    __slots__ = ("_items",)

    def __init__(self, items: Mapping[Any, Any] = ()) -> None:
        object.__setattr__(self, "_items", dict(items))

    def __getitem__(self, key: Any) -> Any:
        return self._items[key]

    def __iter__(self) -> Any:
        return iter(self._items)

    def __len__(self) -> int:
        return len(self._items)

    def __repr__(self) -> str:
        return f"ReadOnlyMapping({self._items!r})"

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError(f"{type(self).__name__} is read-only")

    def __reduce__(self) -> tuple[type, tuple[dict[Any, Any]]]:
        return (type(self), (self._items,))

    def copy(self) -> dict[Any, Any]:
        """A plain (mutable) dict of the items, as ``mappingproxy.copy`` gives."""
        return dict(self._items)

    def __or__(self, other: Any) -> Any:   # ``mapping | dict``: a plain dict, as for a mappingproxy
        return dict(self._items) | other if isinstance(other, Mapping) else NotImplemented

    def __ror__(self, other: Any) -> Any:
        return dict(other) | self._items if isinstance(other, Mapping) else NotImplemented


class FrameField:
    """Descriptor of a :class:`pandas.DataFrame` field of a frozen result (fuzz 19 G1-G3): stored as the object's
    private copy, handed out as a copy on each read.

    A DataFrame has no read-only flag, so a "frozen" result holding one could be edited in place after its checks
    (``j.full.drop(columns=['kind'], inplace=True)``, ``t.table2.iloc[0, 0] = x``) and its consumers would fail or
    compute with values the field spec refuses. With this descriptor an in-place edit changes the caller's copy,
    never the object: the value lives in the instance ``__dict__`` under the field's name (so ``copy``,
    ``deepcopy``, pickle and ``dataclasses.replace`` work as before) and a data descriptor takes precedence over it.
    A read costs one ``DataFrame.copy`` (tens of microseconds for the book's tables). Installed by
    :func:`protect_frames` (``fusion._results.ResultSpec`` for its ``table`` fields, :func:`frozen_arrays` for
    fields annotated as a DataFrame).
    """

    __slots__ = ("name", "default")

    def __init__(self, name: str, default: object = dataclasses.MISSING) -> None:
        self.name = name
        self.default = default

    def __get__(self, obj: object, owner: type | None = None) -> Any:
        if obj is None:  # class access: the field's default, as the dataclass machinery reads it
            if self.default is dataclasses.MISSING:
                raise AttributeError(self.name)
            return self.default
        try:
            value = obj.__dict__[self.name]
        except KeyError:
            raise AttributeError(self.name) from None
        return value.copy() if hasattr(value, "copy") and _is_frame(value) else value

    def __set__(self, obj: object, value: object) -> None:  # the frozen dataclass's __init__ (object.__setattr__)
        obj.__dict__[self.name] = value.copy() if _is_frame(value) else value


def _is_frame(value: object) -> bool:
    """A pandas DataFrame or Series (pandas imported only if the value is one)."""
    module = type(value).__module__
    if not module.startswith("pandas"):
        return False
    import pandas as pd

    return isinstance(value, (pd.DataFrame, pd.Series))


def protect_frames(cls: type, names: Any) -> None:
    """Install a :class:`FrameField` on ``cls`` for each field name in ``names`` (before ``@dataclass`` runs: the
    descriptor gives the class attribute's default, if any, to the dataclass machinery).

    Parameters
    ----------
    cls : type
        The class being defined.
    names : iterable of str
        Its DataFrame fields.
    """
    for name in names:
        current = cls.__dict__.get(name, dataclasses.MISSING)
        if isinstance(current, FrameField):
            continue
        setattr(cls, name, FrameField(name, current))


def frozen_value(value: object, copy: bool = False, _copies: dict[int, np.ndarray] | None = None, *,
                 name: str = "value", _open: list[int] | None = None) -> object:
    """``value`` with nothing mutable in place: arrays read-only, mappings :class:`ReadOnlyMapping`, lists tuples.

    Recursive through mappings, lists and tuples (a named tuple keeps its type); anything else (a number, a nested
    result, which freezes itself) is returned as is. Every :class:`~collections.abc.Mapping` is copied into a
    :class:`ReadOnlyMapping` of its items, not only a ``dict``: a caller's ``mappingproxy``, ``ChainMap`` or
    other mapping is a view of data it can still change (and a ``mappingproxy`` cannot be pickled). A container
    that contains itself, or containers nested more than ``fusion._nesting.MAX_NESTING`` (64) deep, are refused
    naming ``name`` (fuzz 30a C8: a RecursionError before).

    Parameters
    ----------
    value : object
        A field's value.
    copy : bool
        Copy the arrays before clearing their ``WRITEABLE`` flag (a caller's array is left writeable);
        otherwise they are made read-only in place (the object's own arrays), but for a 0-d array, always copied
        (a scalar field given as a caller's 0-d array is never stored aliased, fuzz 29a C1). An array held twice
        (a study's default case also stored under its key) is copied once: the copies share as the originals did.
    name : str
        The argument (field) that holds ``value``, named in the refusals.

    Returns
    -------
    object
        The frozen value.

    Raises
    ------
    ValueError
        A container holding itself, or nested more than 64 deep, naming ``name``.
    """
    memo: dict[int, np.ndarray] = {} if _copies is None else _copies
    if isinstance(value, np.ndarray):
        if copy or value.ndim == 0:  # a 0-d array is a scalar's value: never kept by reference (fuzz 29a C1)
            if id(value) not in memo:
                memo[id(value)] = np.array(value)
            value = memo[id(value)]
        value.setflags(write=False)
        return value
    if not isinstance(value, (Mapping, list, tuple)):
        return value
    open_ = [] if _open is None else _open  # the ids of the containers around value (fuzz 30a C8)
    if id(value) in open_ or len(open_) >= MAX_NESTING:
        raise nesting_error(name, itself=id(value) in open_)
    open_.append(id(value))
    try:
        if isinstance(value, Mapping):  # every mapping, not only a dict: a caller's view is copied (fuzz 29b B2)
            return ReadOnlyMapping({k: frozen_value(v, copy, memo, name=name, _open=open_) for k, v in value.items()})
        frozen = (frozen_value(v, copy, memo, name=name, _open=open_) for v in value)
        if isinstance(value, list) or type(value) is tuple:
            return tuple(frozen)
        if hasattr(value, "_fields"):  # a named tuple keeps its type
            return type(value)(*frozen)
        return value
    finally:
        open_.pop()


#: Field values with nothing to freeze (:func:`freeze_arrays` skips them).
_ATOMS = frozenset({int, float, bool, str, complex, type(None), np.float64, np.int64, np.bool_})


def freeze_arrays(obj: object) -> None:
    """Freeze every field of the dataclass ``obj`` (``__post_init__``): arrays read-only copies, dicts and lists
    read-only mappings and tuples (:func:`frozen_value`; the arrays they hold copied too).

    Parameters
    ----------
    obj : dataclass instance
        A frozen dataclass.
    """
    copies: dict[int, np.ndarray] = {}  # an array held by two fields is copied once
    for name in obj.__dataclass_fields__:  # type: ignore[attr-defined]  (dataclasses.fields, without its cost)
        value = getattr(obj, name)
        kind = type(value)
        if kind in _ATOMS:  # nothing to freeze (the common fields of a small result: cheap)
            continue
        if kind is np.ndarray:  # the common case inline (a small result is built in a study's inner loop)
            frozen = copies.get(id(value))
            if frozen is None:
                frozen = copies[id(value)] = np.array(value)
                frozen.flags.writeable = False
        else:
            frozen = frozen_value(value, True, copies, name=name)
        if frozen is not value:
            object.__setattr__(obj, name, frozen)


def freeze_shared(obj: object) -> None:
    """``__post_init__`` of a bundle of other results' values (:func:`frozen_arrays` with ``shared=True``): every field
    frozen without copying (arrays made read-only in place, dicts and lists read-only mappings and tuples of the same
    items), so that the bundle shares its study's data (one computation, one copy in memory).

    Parameters
    ----------
    obj : dataclass instance
        A frozen dataclass.
    """
    for name in obj.__dataclass_fields__:  # type: ignore[attr-defined]
        value = getattr(obj, name)
        frozen = frozen_value(value, name=name)
        if frozen is not value:
            object.__setattr__(obj, name, frozen)


def fresh(cls: type[T], **fields: Any) -> T:
    """Build a ``frozen_arrays`` result from freshly computed values without copying them (the private constructor).

    For the package's own producers whose small results are built in a study's inner loop (a fusion set per epoch):
    the arrays must be owned by the new object (computed there, not a caller's argument); they are made read-only in
    place, dicts and lists frozen as :func:`freeze_arrays` does. The public constructor copies (about 5 µs for two
    small arrays, 10 % of :func:`fusion.readings.fusion_set.belief_degree`).

    Parameters
    ----------
    cls : type
        A frozen dataclass declared with :func:`frozen_arrays`.
    **fields
        Every field without a default.

    Returns
    -------
    object
        The new instance.
    """
    obj = object.__new__(cls)
    fs = _FIELDS.get(cls)
    if fs is None:
        fs = _FIELDS[cls] = dataclasses.fields(cls)  # type: ignore[arg-type]
    for f in fs:
        if f.name in fields:
            value = fields[f.name]
        elif f.default is not dataclasses.MISSING:
            value = f.default
        elif f.default_factory is not dataclasses.MISSING:
            value = f.default_factory()
        else:
            raise TypeError(f"fresh({cls.__name__}) misses the field {f.name}")
        kind = type(value)
        if kind is np.ndarray:
            value.flags.writeable = False
        elif kind not in _ATOMS:
            value = frozen_value(value)
        object.__setattr__(obj, f.name, value)
    return obj


#: The fields of the classes :func:`fresh` has built (``dataclasses.fields`` once per class).
_FIELDS: dict[type, tuple[dataclasses.Field, ...]] = {}  # type: ignore[type-arg]


def restore_frozen(obj: object, state: object) -> None:
    """``__setstate__`` of a result with read-only arrays: restore its fields, then make its arrays read-only again.

    ``copy.deepcopy`` and :mod:`pickle` rebuild an object without ``__init__`` (numpy restores an array
    writeable), so without this a copy of a frozen result would have writeable arrays. The arrays set here
    are the copy's own (deep-copied or unpickled); a shallow :func:`copy.copy` shares the original's,
    already read-only.

    Parameters
    ----------
    obj : object
        The new instance.
    state : dict or tuple
        Its ``__dict__`` (or ``(__dict__, slots)``), as :mod:`pickle` gives it.
    """
    fields, slots = state if isinstance(state, tuple) else (state, None)
    for values in (fields, slots):
        for name, value in (values or {}).items():
            object.__setattr__(obj, name, frozen_value(value))


def frozen_arrays(cls: type[T] | None = None, *, shared: bool = False) -> Any:
    """Class decorator of the package's frozen result dataclasses: every ndarray field a read-only copy.

    Dicts and lists become read-only mappings and tuples (:func:`freeze_arrays`), and a field annotated as a
    DataFrame is protected by a :class:`FrameField` (a private copy, a copy on each read).

    Sets ``__post_init__`` to :func:`freeze_arrays` and ``__setstate__`` to :func:`restore_frozen` (copies
    and unpickled objects keep read-only arrays); apply it below ``@dataclass(frozen=True)`` (so that the generated
    ``__init__`` calls it). One declaration instead of a ``__post_init__`` per class; no base class, so the API page
    shows the results' bases as before.

    Parameters
    ----------
    cls : type
        The class, not yet a dataclass.
    shared : bool
        A bundle of other results' values (``@frozen_arrays(shared=True)``): ``__post_init__`` is
        :func:`freeze_shared` (the values frozen in place, not copied).

    Returns
    -------
    type
        ``cls`` itself (the decorator, if called with ``shared`` only).

    Raises
    ------
    TypeError
        If ``cls`` defines its own ``__post_init__`` (the decorator would silently replace it).
    """
    if cls is None:
        return lambda c: frozen_arrays(c, shared=shared)
    if "__post_init__" in vars(cls):
        raise TypeError(f"frozen_arrays: {cls.__qualname__} defines its own __post_init__ (e.g. a validated result, "
                        "fusion._results), which freezes its arrays itself: remove the decorator")
    protect_frames(cls, [n for n, hint in vars(cls).get("__annotations__", {}).items() if "DataFrame" in str(hint)])
    cls.__post_init__ = freeze_shared if shared else freeze_arrays  # type: ignore[attr-defined]
    cls.__setstate__ = restore_frozen  # type: ignore[attr-defined]
    return cls


def constant(value: T) -> T:
    """``value`` made read-only all the way down: the one rule for a public constant of the package (issue 35).

    A module's public constant (a registry of labels, a published scenario, a default array) is shared by every
    caller in the process, so that one caller must not change it for the next: a dict (any mapping) becomes a
    :class:`ReadOnlyMapping`, a list a tuple, a set a frozenset, an array read-only (the same array: it may be
    shared), each of their items made constant in turn; a tuple keeps its type (a named tuple stays one). Other
    values (numbers, strings, enums, frozen dataclasses, functions) are returned as they are.
    """
    if isinstance(value, np.ndarray):
        if value.dtype == object:
            raise TypeError("an object array cannot be made a constant (its items stay mutable)")
        value.flags.writeable = False
        return value
    if isinstance(value, Mapping):
        return ReadOnlyMapping({k: constant(v) for k, v in value.items()})  # type: ignore[return-value]
    if isinstance(value, (list, tuple)):
        items = [constant(x) for x in value]
        if isinstance(value, list):
            return tuple(items)  # type: ignore[return-value]
        if all(a is b for a, b in zip(items, value)):
            return value
        return type(value)(*items) if hasattr(value, "_fields") else type(value)(items)  # type: ignore[return-value]
    if isinstance(value, (set, frozenset)):
        return frozenset(constant(x) for x in value)  # type: ignore[return-value]
    return value
