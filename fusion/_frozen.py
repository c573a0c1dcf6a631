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


def frozen_arrays(cls: type[T]) -> type[T]:
    """Class decorator of the package's frozen result dataclasses: every ndarray field a read-only copy.

    Sets ``__post_init__`` to :func:`freeze_arrays`; apply it below ``@dataclass(frozen=True)`` (so that the generated
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
    return cls
