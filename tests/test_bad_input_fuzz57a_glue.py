"""Fuzz 57a C1: glue_all charged a numeric container that is cheap to hold but large once converted 0 units, then
converted it (``pd.RangeIndex(10**12)``: a raw MemoryError, "Unable to allocate 7.28 TiB"). Every container the walk
converts is now checked by its logical size (values, labels, categories) against the input budget, and its numeric
entries charged ``_GLUE_NUMBER`` units each, before any conversion."""

import numpy as np
import pandas as pd
import pytest

from _helpers import glued_in_child

#: Each case builds a container costing nothing to hold, glued in a child under a 3 GiB address-space limit: a
#: conversion of any of them raises MemoryError there (or takes minutes), a refusal is a ValueError naming the key.
_CASES = {
    "range_index": "pd.RangeIndex(10**12)",
    "range_index_1e9": "pd.RangeIndex(10**9, 2 * 10**9)",
    "broadcast": "np.broadcast_to(np.float64(1.0), (10**10,))",
    "as_strided": "np.lib.stride_tricks.as_strided(np.zeros(1), shape=(10**5, 10**5), strides=(0, 0))",
    "categories": "pd.Categorical.from_codes([0], categories=pd.RangeIndex(10**10))",
    "categorical_index": "pd.CategoricalIndex(pd.Categorical.from_codes([0], categories=pd.RangeIndex(10**10)))",
    "categorical_series": "pd.Series(pd.Categorical.from_codes([0], categories=pd.RangeIndex(10**10)))",
    "series_view": "pd.Series(np.broadcast_to(np.float64(1.0), (10**10,)), copy=False)",
    # fuzz 62a C1: a table's numeric labels are never converted (its text is truncated): glued, not refused
    "accepted_table_index": "pd.DataFrame(index=pd.RangeIndex(10**10))",
    "sparse": ("pd.arrays.SparseArray._simple_new(np.array([], dtype=float), IntIndex(10**10, np.array([], "
               "dtype=np.int32)), pd.SparseDtype(float, 0.0))"),
    "inside_list": "[1.0, pd.RangeIndex(10**10)]",
    "inside_dict": "{'a': np.broadcast_to(np.float64(1.0), (10**10,))}",
}

@pytest.mark.parametrize("case", sorted(_CASES))
def test_c1_cheap_containers_are_refused_by_logical_size_before_conversion(case: str) -> None:
    out = glued_in_child(tuple(_CASES.items()))[case]
    assert out[0] == ("ACCEPTED" if case.startswith("accepted") else "ValueError"), out
    assert float(out[1]) < 1.0, out
    assert case.startswith("accepted") or out[2].startswith("values['k'] holds a ") and "input budget" in out[2], out


def test_c1_logical_size_edge() -> None:
    """The input budget's edge by the checks alone (nothing converted): 2**25 entries accepted, 2**25 + 1 refused,
    for a view's values, an Index and a categorical's categories; its numeric entries charged 1 unit each."""
    from fusion._limits import MAX_INPUT_ELEMENTS, MAX_WORK, work
    from fusion.book import glue as G
    assert MAX_INPUT_ELEMENTS == 2**25
    # the parts summed (fuzz 61a C3): the categorical's one code counts too
    for extra, make in ((0, lambda n: np.broadcast_to(np.float64(1.0), (n,))), (0, pd.RangeIndex),
                        (1, lambda n: pd.Categorical.from_codes([0], categories=pd.RangeIndex(n)))):
        G._logical_check(make(MAX_INPUT_ELEMENTS - extra), "k")
        with pytest.raises(ValueError, match=r"^values\['k'\] holds a .* input budget"):
            G._logical_check(make(MAX_INPUT_ELEMENTS - extra + 1), "k")
    view = np.broadcast_to(np.float64(1.0), (MAX_INPUT_ELEMENTS,))
    assert G._glue_work(view) == G._glue_work(pd.RangeIndex(MAX_INPUT_ELEMENTS)) == MAX_INPUT_ELEMENTS
    # summed over values: 29 such views are inside the work budget (not run), 30 are refused before any is read
    inside = {f"k{i}": view for i in range(29)}
    assert work((29 * G._GLUE_VALUE + sum(G._glue_work(v, k) for k, v in inside.items()),), "values") <= MAX_WORK
    with pytest.raises(ValueError, match="^values .*work budget"):
        G.glue_all({f"k{i}": view for i in range(30)})


def test_c1_small_numeric_containers_still_glued() -> None:
    """Valid numeric containers well inside are glued as before."""
    from fusion.book.glue import glue_all
    glue_all({"a": pd.RangeIndex(1000), "b": np.broadcast_to(np.float64(1.0), (10, 10)),
              "c": pd.Categorical.from_codes([0, 1], categories=pd.RangeIndex(100)),
              "d": pd.DataFrame({"x": [1.0, 2.0]}, index=pd.RangeIndex(2)), "e": [pd.Series([1.0, 2.0])]},
             decimals=3)
