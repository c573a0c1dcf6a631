"""Fuzz 61a C3: glue_all took the largest part of a value for its input budget, not the sum, so a table of many
categorical columns passed one column at a time (16 columns of 2**25 - 10 categories accepted in 29.3 CPU-s, 40 a raw
MemoryError after 33.3 CPU-s, 1000 of 2**20 a raw MemoryError after 35.7 CPU-s); and converting two or more columns
to objects together boxed every category of each (30-36 ns a number, 0.94 us a date with a time zone)."""

import pytest

from _helpers import glue_outcome

_COLS = "pd.DataFrame({{f'c{{i}}': pd.Categorical.from_codes([0], categories={cats}) for i in range({n})}})"
_TZ = "pd.date_range('2000', periods=2**21, freq='s', tz='UTC')"
#: Glued in one child under a 3 GiB address-space limit.
_CASES = {
    "refused_16_columns": _COLS.format(cats="pd.RangeIndex(2**25 - 10)", n=16),
    "refused_40_columns": _COLS.format(cats="pd.RangeIndex(2**25 - 10)", n=40),
    "refused_1000_columns": _COLS.format(cats="pd.RangeIndex(2**20)", n=1000),
    "refused_styler": _COLS.format(cats="pd.RangeIndex(2**25 - 10)", n=2) + ".style",
    "refused_inside_list": "[" + _COLS.format(cats="pd.RangeIndex(2**24)", n=2) + "]",
    # inside the budget: 8 columns of 2**21 dates with a time zone and an object column (before: 16 M Timestamps
    # boxed, ~15.8 CPU-s); their cells are converted, not their unused categories
    "accepted_8_tz_columns": _COLS.format(cats=_TZ, n=8) + ".assign(o=pd.Series(['x'], dtype=object))",
}


@pytest.mark.parametrize("case", sorted(_CASES))
def test_c3_categorical_columns_are_summed_and_not_boxed(case: str) -> None:
    glue_outcome(_CASES, case, r"^values\['k'\] holds a (?=.*summed)(?=.*input budget)")


def test_c3_table_cells_are_the_same_without_unused_categories() -> None:
    """A categorical column's cells are read as before (its used categories; a missing one, NaN, left out as a word),
    beside an object column, in column order, then the column labels."""
    import numpy as np
    import pandas as pd

    from fusion.book import glue as G
    table = pd.DataFrame({"a": pd.Categorical.from_codes([1, -1, 1], categories=["x", "y", "z"]),
                          "n": [1.0, 2.0, 3.0], "o": pd.Series(["p", None, "q"], dtype=object),
                          "t": pd.Categorical.from_codes([0, 2, 0], categories=pd.date_range("2000", periods=3,
                                                                                             tz="UTC"))})
    stamp = pd.Timestamp("2000-01-01", tz="UTC")
    got = G._table_cells(table)
    assert got == ["y", "y", "p", "q", stamp, pd.Timestamp("2000-01-03", tz="UTC"), stamp,
                   "a", "n", "o", "t"], got
    assert G._table_cells(table.iloc[:, [1]]) == ["n"] and np.isnan(table.iloc[1, 0])
