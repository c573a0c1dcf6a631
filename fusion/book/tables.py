"""Tables that set published numbers beside recomputed ones.

The book shows every published number next to ours and the difference; this module
builds those tables as :class:`pandas.DataFrame` objects with a fixed number of
decimals, so that their text is identical from run to run and machine to machine.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pandas as pd

from fusion._validation import as_array, count, scalar
from numpy.typing import ArrayLike

__all__ = ["side_by_side", "rounded"]


def rounded(value: float, decimals: int = 4) -> float:
    """Round a number for display or glue, mapping ``-0.0`` to ``0.0``.

    Parameters
    ----------
    value : float
        The number.
    decimals : int
        Decimals kept (Python's ``round``, half to even).

    Returns
    -------
    float
    """
    value = scalar(value, "value")
    decimals = count(decimals, "decimals", minimum=0)
    r = round(value, decimals)
    return 0.0 if r == 0 else r


def side_by_side(
    published: ArrayLike,
    reproduced: ArrayLike,
    index: Sequence[object],
    name: str = "",
    decimals: int = 4,
    index_name: str = "observation",
) -> pd.DataFrame:
    """Published and reproduced values with their difference (reproduced - published).

    Parameters
    ----------
    published, reproduced : array_like, shape (k,)
    index : sequence, length k
        Row labels (e.g. observation numbers).
    name : str
        Quantity name appended to the column headers ("" for plain headers).
    decimals : int
        Rounding of every column.
    index_name : str
        Name of the index (row labels).

    Returns
    -------
    pandas.DataFrame
        Columns ``published``, ``reproduced`` (each followed by ``name`` if given) and
        ``difference``.

    Raises
    ------
    ValueError
        ``published``, ``reproduced`` and ``index`` of different lengths, or not 1-D.
    """
    pub = as_array(published, "published", ndim=1)
    rep = as_array(reproduced, "reproduced", ndim=1)
    decimals = count(decimals, "decimals", minimum=0)
    if pub.shape != rep.shape or pub.ndim != 1 or len(index) != pub.size:
        raise ValueError(
            f"published {pub.shape}, reproduced {rep.shape} and index ({len(index)}) must match"
        )
    df = pd.DataFrame(
        {
            f"published {name}".strip(): pub,
            f"reproduced {name}".strip(): rep,
            "difference": rep - pub,
        },
        index=pd.Index(list(index), name=index_name),
    )
    return df.round(decimals) + 0.0  # + 0.0 turns -0.0 into 0.0
