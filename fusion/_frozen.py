"""Read-only array fields for the package's frozen result dataclasses."""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from typing import Any, TypeVar

import numpy as np

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


def frozen_value(value: object, copy: bool = False, _copies: dict[int, np.ndarray] | None = None) -> object:
    """``value`` with nothing mutable in place: arrays read-only, dicts :class:`ReadOnlyMapping`, lists tuples.

    Recursive through dicts, lists and tuples (a named tuple keeps its type); anything else (a number, a nested
    result, which freezes itself) is returned as is.

    Parameters
    ----------
    value : object
        A field's value.
    copy : bool
        Copy the arrays before clearing their ``WRITEABLE`` flag (a caller's array is left writeable);
        otherwise they are made read-only in place (the object's own arrays). An array held twice (a study's
        default case also stored under its key) is copied once: the copies share as the originals did.

    Returns
    -------
    object
        The frozen value.
    """
    memo: dict[int, np.ndarray] = {} if _copies is None else _copies
    if isinstance(value, np.ndarray):
        if copy:
            if id(value) not in memo:
                memo[id(value)] = np.array(value)
            value = memo[id(value)]
        value.setflags(write=False)
        return value
    if isinstance(value, (dict, ReadOnlyMapping)):
        return ReadOnlyMapping({k: frozen_value(v, copy, memo) for k, v in value.items()})
    if isinstance(value, list) or type(value) is tuple:
        return tuple(frozen_value(v, copy, memo) for v in value)
    if isinstance(value, tuple) and hasattr(value, "_fields"):
        return type(value)(*(frozen_value(v, copy, memo) for v in value))
    return value


def freeze_arrays(obj: object) -> None:
    """Freeze every field of the dataclass ``obj`` (``__post_init__``): arrays read-only copies, dicts and lists
    read-only mappings and tuples (:func:`frozen_value`; the arrays they hold copied too).

    Parameters
    ----------
    obj : dataclass instance
        A frozen dataclass.
    """
    copies: dict[int, np.ndarray] = {}  # an array held by two fields is copied once
    for f in dataclasses.fields(obj):  # type: ignore[arg-type]
        value = getattr(obj, f.name)
        frozen = frozen_value(value, True, copies)
        if frozen is not value:
            object.__setattr__(obj, f.name, frozen)


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


def frozen_arrays(cls: type[T]) -> type[T]:
    """Class decorator of the package's frozen result dataclasses: every ndarray field a read-only copy.

    Sets ``__post_init__`` to :func:`freeze_arrays` and ``__setstate__`` to :func:`restore_frozen` (copies
    and unpickled objects keep read-only arrays); apply it below ``@dataclass(frozen=True)`` (so that the generated
    ``__init__`` calls it). One declaration instead of a ``__post_init__`` per class; no base class, so the API page
    shows the results' bases as before.

    Parameters
    ----------
    cls : type
        The class, not yet a dataclass.

    Returns
    -------
    type
        ``cls`` itself.

    Raises
    ------
    TypeError
        If ``cls`` defines its own ``__post_init__`` (the decorator would silently replace it).
    """
    if "__post_init__" in vars(cls):
        raise TypeError(f"frozen_arrays: {cls.__qualname__} defines its own __post_init__ (e.g. a validated result, "
                        "fusion._results), which freezes its arrays itself: remove the decorator")
    cls.__post_init__ = freeze_arrays  # type: ignore[attr-defined]
    cls.__setstate__ = restore_frozen  # type: ignore[attr-defined]
    return cls
