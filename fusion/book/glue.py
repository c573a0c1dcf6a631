"""Glue many values into a chapter at once (myst-nb), rounded so stored outputs never flicker."""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any, TypeAlias, Union

import numpy as np
import pandas as pd
from matplotlib.figure import Figure
from pandas.io.formats.style import Styler

from fusion._validation import count
from fusion.book.tables import rounded
from fusion._shown import shown

# The type aliases below are importable but not in __all__: autodoc would file ``dict[...]`` under the module
# ``builtins`` and the source listings would link to a page that does not exist.
__all__ = ["glue_all"]

#: One value for the glue namespace: a number, a string, a figure or a table.
GlueValue: TypeAlias = Union[float, int, str, Figure, pd.DataFrame, Styler]
#: What a chapter's glue function returns: glue key → value (the keys are glue names, not method labels).
GlueValues: TypeAlias = dict[str, GlueValue]


def glue_all(values: Mapping[str, Any], decimals: int | None = None) -> None:
    """Glue every ``key: value`` pair with ``display=False``.

    Parameters
    ----------
    values : mapping of str to object
        Glue keys (prefixed with the chapter's short id) and values. Floats are rounded to
        ``decimals`` when it is given; NumPy scalars are converted to Python numbers.
        Matplotlib figures are checked by :func:`fusion.book.figures.audit_figure` (which raises
        on a figure that breaks the book's figure rules), glued, then closed.
    decimals : int, optional
        Decimals of floats (see :func:`fusion.book.tables.rounded`); unrounded if ``None``.

    Raises
    ------
    TypeError
        ``values`` not a mapping, a key not a string, ``decimals`` not an integer.
    ValueError
        A number (a float, a NumPy scalar or a 0-d array) NaN or infinite, naming ``values[key]``; checked for every
        value before any is glued, whatever ``decimals``.
    """
    if not isinstance(values, Mapping):
        raise TypeError(f"values must be a mapping of glue keys to values, got {type(values).__name__}")
    if decimals is not None:
        decimals = count(decimals, "decimals", minimum=0)
    for key, value in values.items():  # every value checked before any is glued
        if not isinstance(key, str):
            raise TypeError(f"values must have str glue keys, got the key {shown(key, 60)}")
        number = value.item() if isinstance(value, np.ndarray) and value.ndim == 0 else value  # a 0-d array: its number
        if isinstance(number, (float, np.floating)) and not math.isfinite(number):
            raise ValueError(f"values[{shown(key)}] must be finite, got {shown(value)} (a glued number is printed in the book)")
    from myst_nb import glue  # a book dependency, imported only when a chapter runs

    from fusion.book.figures import glue_figure

    for key, value in values.items():
        if isinstance(value, Figure):
            glue_figure(key, value)
            continue
        if hasattr(value, "item") and getattr(value, "ndim", 1) == 0:
            value = value.item()
        if decimals is not None and isinstance(value, float):
            value = rounded(value, decimals)
        glue(key, value, display=False)
