"""Read-only array fields for the package's frozen result dataclasses."""

from __future__ import annotations

import dataclasses

import numpy as np


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


class FrozenArrays:
    """Base of the package's frozen result dataclasses: every ndarray field is a read-only copy after construction.

    Declare a result as ``@dataclass(frozen=True) class Result(FrozenArrays)``; its generated ``__init__`` calls
    this ``__post_init__`` (:func:`freeze_arrays`). A subclass that validates its fields in its own
    ``__post_init__`` calls ``super().__post_init__()`` last.
    """

    __slots__ = ()

    def __post_init__(self) -> None:
        freeze_arrays(self)
