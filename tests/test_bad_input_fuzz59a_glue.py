"""Fuzz 59a C2: glue_all charged a table whose index or columns is a MultiIndex of many levels (one row) by its rows,
one table: 400,000 levels were accepted and glued in 39.9 CPU-s (the glued text and HTML print every level). Each
MultiIndex axis is now charged by its levels (``_GLUE_LEVEL`` a level), a MultiIndex itself also by its pairs of
levels (its text is quadratic), refused naming values['k'] before any text is made."""

import time

import pandas as pd
import pytest

from fusion._limits import MAX_WORK
from fusion.book._glue_axes import _GLUE_LEVEL, _GLUE_LEVEL_PAIR, axis_units
from fusion.book.glue import glue_all


def _levels(n: int) -> pd.MultiIndex:
    return pd.MultiIndex(levels=[pd.Index([0])] * n, codes=[[0]] * n)


_OUT = MAX_WORK // _GLUE_LEVEL + 1000   # just beyond the budget by its levels alone
_KINDS = {
    "table_index": lambda mi: pd.DataFrame({"a": [1.0]}, index=mi),
    "table_columns": lambda mi: pd.DataFrame([[1.0]], columns=mi),
    "series_index": lambda mi: pd.Series([1.0], index=mi),
    "styler": lambda mi: pd.DataFrame({"a": [1.0]}, index=mi).style,
    "table_in_list": lambda mi: [pd.DataFrame({"a": [1.0]}, index=mi)],
    "series_in_dict": lambda mi: {"s": pd.Series([1.0], index=mi)},
}


@pytest.fixture(scope="module")
def many_levels() -> pd.MultiIndex:
    return _levels(_OUT)


@pytest.mark.parametrize("kind", sorted(_KINDS))
def test_many_levels_refused_before_the_text(kind: str, many_levels: pd.MultiIndex) -> None:
    value = _KINDS[kind](many_levels)
    t = time.process_time()
    with pytest.raises(ValueError, match=r"values\['k'\]"):
        glue_all({"k": value})
    assert time.process_time() - t < 1.0


def test_multiindex_value_refused_by_its_pairs_of_levels() -> None:
    n = 5000   # 40 * 5000**2 + 20,000 * 5000 = 1.1e9 units (its text ~9 CPU-s at 3.7e-7 s a pair)
    for value in (_levels(n), [_levels(n)]):
        t = time.process_time()
        with pytest.raises(ValueError, match=r"values\['k'\]"):
            glue_all({"k": value})
        assert time.process_time() - t < 1.0


def test_edge_accepted_by_the_budget() -> None:
    edge = MAX_WORK // _GLUE_LEVEL
    assert axis_units(pd.Series([1.0], index=_levels(edge)), "k") == edge * _GLUE_LEVEL
    n = max(m for m in range(1, 6000) if m * _GLUE_LEVEL + m * m * _GLUE_LEVEL_PAIR <= MAX_WORK)
    assert axis_units(_levels(n), "k") <= MAX_WORK
    with pytest.raises(ValueError, match=r"values\['k'\]"):
        axis_units(_levels(n + 1), "k")


def test_few_levels_glued() -> None:
    mi = pd.MultiIndex.from_arrays([[1, 2], ["a", "b"]], names=["x", "y"])
    glue_all({"k": pd.DataFrame({"a": [1.0, 2.0]}, index=mi), "s": pd.Series([1.0, 2.0], index=mi), "m": mi})
