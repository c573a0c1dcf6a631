"""Fuzz 62a C1, C2 (regressions of the summed input budget, fuzz 61a C3): glue_all summed a Series' DatetimeIndex or
float Index with its values although it never converts them (a Series of 2 x 10**7 floats refused; a RangeIndex was
an exception); and it read every categorical column of a table without its unused categories, ~300 us a column
uncharged (10**5 one-row columns accepted in 32.2 CPU-s)."""

import numpy as np
import pandas as pd
import pytest

from _helpers import glue_outcome

_SERIES = "pd.Series(np.zeros(2 * 10**7), index={})"
_COLS = "pd.DataFrame({{f'c{{i}}': pd.Categorical.from_codes([0], categories=pd.RangeIndex({k})) for i in range({n})}})"
#: Glued in one child under a 3 GiB address-space limit.
_CASES = {
    "accepted_datetime_index": _SERIES.format("pd.date_range('2000', periods=2 * 10**7, freq='s')"),
    "accepted_float_index": _SERIES.format("pd.Index(np.arange(2 * 10**7, dtype=float))"),
    "accepted_int_index": _SERIES.format("pd.Index(np.arange(2 * 10**7))"),
    "accepted_timedelta_index": _SERIES.format("pd.to_timedelta(np.arange(2 * 10**7), unit='s')"),
    # 5 x 10**4 one-row columns of 2 categories: each pruned, charged before the work (before: ~16 CPU-s accepted)
    "refused_pruned_columns": _COLS.format(k=2, n=5 * 10**4),
}


@pytest.mark.parametrize("case", sorted(_CASES))
def test_c1_c2_outcome(case: str) -> None:
    glue_outcome(_CASES, case, r"^values\['k'\] ask for more work than the work budget allows")


def test_c1_only_converted_labels_are_summed() -> None:
    """One rule for every kind of index: an axis of real numbers or dates adds nothing; one the glue converts (objects,
    dates with a time zone, complex numbers, a MultiIndex, a CategoricalIndex with its categories) is summed."""
    from fusion._limits import MAX_INPUT_ELEMENTS
    from fusion.book import glue as G

    n = 10
    values = np.zeros(n)
    for index in (pd.RangeIndex(n), pd.Index(np.arange(n, dtype=float)), pd.date_range("2000", periods=n),
                  pd.to_timedelta(np.arange(n), unit="s"), pd.Index(np.arange(n, dtype=np.uint8))):
        assert sum(G._logical_sizes(pd.Series(values, index=index))) == n, index
        assert sum(G._logical_sizes(pd.DataFrame({"a": values}, index=index))) == n + 1, index   # its object label
    codes = np.zeros(n, int)
    for index, extra in ((pd.date_range("2000", periods=n, tz="UTC"), n), (pd.Index([str(i) for i in range(n)]), n),
                         (pd.Index(np.arange(n) + 1j), n),
                         (pd.CategoricalIndex(pd.Categorical.from_codes(codes, categories=range(30))), n + 30),
                         (pd.MultiIndex.from_arrays([np.arange(n), np.arange(n)]), 3 * n)):
        assert sum(G._logical_sizes(pd.Series(values, index=index))) == n + extra, index
    # the edge: a Series view of 2**24 values with a tz-aware index of as many (converted), 2**25 in all, is
    # accepted, one more of each refused, before anything is converted
    assert MAX_INPUT_ELEMENTS == 2**25
    for m, ok in ((2**24, True), (2**24 + 1, False)):
        s = pd.Series(np.broadcast_to(0.0, (m,)), index=pd.DatetimeIndex(np.broadcast_to(np.datetime64(0, "ns"), (m,)))
                      .tz_localize("UTC"), copy=False)
        if ok:
            G._logical_check(s, "k")
        else:
            with pytest.raises(ValueError, match=r"^values\['k'\] holds a Series of .* input budget"):
                G._logical_check(s, "k")


def test_c2_only_columns_of_more_categories_than_rows_are_pruned_and_charged() -> None:
    from fusion._limits import MAX_WORK
    from fusion.book import _glue_axes as A

    table = pd.DataFrame({"few": pd.Categorical.from_codes([0, 1], categories=["x", "y"]),
                          "many": pd.Categorical.from_codes([0, 0], categories=["x", "y", "z"]),
                          "o": pd.Series(["p", "q"], dtype=object), "n": [1.0, 2.0]})
    assert A.pruned_columns(table) == [1]
    assert A.prune_units(table) == A.prune_units(table.style) == A._GLUE_PRUNE
    assert A.object_cells(table.iloc[:, [0, 1, 2]]).tolist() == [["x", "x", "p"], ["y", "x", "q"]]
    # the budget: ~40,000 pruned columns at most (measured ~200 us each, ~8 CPU-s), a fifth more refused
    assert 39_000 * A._GLUE_PRUNE < MAX_WORK < 41_000 * A._GLUE_PRUNE
