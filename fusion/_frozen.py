"""Read-only array fields for the package's frozen result dataclasses."""

from __future__ import annotations

import dataclasses
from typing import TypeVar

import numpy as np

T = TypeVar("T")


def freeze_arrays(obj: object) -> None:
    """Replace every ndarray field of the dataclass ``obj`` by a read-only copy (``__post_init__``).

    Parameters
    ----------
    obj : dataclass instance
        A frozen dataclass; its ndarray fields are copied once and their ``WRITEABLE`` flag cleared.
    """
    for f in dataclasses.fields(obj):  # type: ignore[arg-type]
        value = getattr(obj, f.name)
        if isinstance(value, np.ndarray):
            arr = np.array(value)
            arr.setflags(write=False)
            object.__setattr__(obj, f.name, arr)


def _freeze_tree(value: object) -> None:
    """Clear the ``WRITEABLE`` flag of an ndarray, and of the ndarrays in a dict, list or tuple (recursively)."""
    if isinstance(value, np.ndarray):
        value.setflags(write=False)
    elif isinstance(value, dict):
        for v in value.values():
            _freeze_tree(v)
    elif isinstance(value, (list, tuple)):
        for v in value:
            _freeze_tree(v)


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
            _freeze_tree(value)
            object.__setattr__(obj, name, value)


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
