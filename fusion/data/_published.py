"""The container for published numbers."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from fusion._frozen import frozen_arrays
from fusion._validation import FloatArray

__all__ = ["Published", "read_only"]


@dataclass(frozen=True)
@frozen_arrays
class Published:
    """A published number or array with where it was printed.

    The package's published tables are built once, in :mod:`fusion.data`, from numbers typed off the documents and
    checked by its tests: the constructor checks nothing beyond making the arrays read-only.

    Attributes
    ----------
    values : ndarray
        The numbers as printed.
    source : str
        BibTeX key of the document.
    where : str
        Table, figure, equation or page in that document.
    unit : str
        Physical unit of ``values`` ("" when dimensionless).
    note : str
        Anything about how the numbers were read (layout, rounding).
    columns : dict of str to ndarray
        Named columns for tables with several published columns.
    """

    values: FloatArray
    source: str
    where: str
    unit: str = ""
    note: str = ""
    columns: Mapping[str, FloatArray] = field(default_factory=dict)


def read_only(a: object) -> FloatArray:
    """A read-only float array of ``a`` (published numbers must not be edited in place).

    Parameters
    ----------
    a : object
        Anything :func:`numpy.array` converts to floats.

    Returns
    -------
    ndarray
        A copy with the ``WRITEABLE`` flag cleared.
    """
    arr = np.array(a, dtype=float)
    arr.setflags(write=False)
    return arr
