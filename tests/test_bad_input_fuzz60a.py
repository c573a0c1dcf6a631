"""Fuzz 60a: glue_all's logical size missed a table's categorical columns, a CategoricalIndex axis and a MultiIndex's
levels (C1: a raw MemoryError, "Unable to allocate 74.5 GiB"); ``delay_table`` built a list of ``len(delays) x
len(sigmas)`` counts before its budget refused it (C3: 15.4 CPU-s at 20,000 x 20,000, a raw MemoryError at 100,000 x
100,000)."""

import time

import numpy as np
import pandas as pd
import pytest

from _helpers import glued_in_child

_CAT = "pd.Categorical.from_codes([0], categories=pd.RangeIndex(10**10))"
_LEVEL = "pd.MultiIndex(levels=[{}, pd.Index([0])], codes=[[0], [0]], verify_integrity=False)"
#: Fuzz 60a C1: containers costing nothing to hold whose categories or level hold 10**10 entries; glued in one child
#: under a 3 GiB address-space limit (converting any of them raised MemoryError there).
_C1_CASES = {
    "categorical_column": f"pd.DataFrame({{'a': {_CAT}}})",
    "categorical_column_styler": f"pd.DataFrame({{'a': {_CAT}}}).style",
    "categorical_rows": f"pd.DataFrame({{'a': [1.0]}}, index=pd.CategoricalIndex({_CAT}))",
    "categorical_columns": f"pd.DataFrame([[1.0]], columns=pd.CategoricalIndex({_CAT}))",
    "categorical_series_index": f"pd.Series([1.0], index=pd.CategoricalIndex({_CAT}))",
    "multiindex_level": _LEVEL.format("pd.RangeIndex(10**10)"),
    "multiindex_categorical_level": _LEVEL.format(f"pd.CategoricalIndex({_CAT})"),
    "table_multiindex_level": f"pd.DataFrame({{'a': [1.0]}}, index={_LEVEL.format('pd.RangeIndex(10**10)')})",
    "inside_list": f"[pd.Series([1.0], index=pd.CategoricalIndex({_CAT}))]",
}


@pytest.mark.parametrize("case", sorted(_C1_CASES))
def test_c1_categories_and_levels_are_counted_before_conversion(case: str) -> None:
    out = glued_in_child(tuple(_C1_CASES.items()))[case]
    assert out[0] == "ValueError", out
    assert float(out[1]) < 1.0, out
    assert out[2].startswith("values['k'] holds a ") and "input budget" in out[2], out


def test_c1_logical_size_edge() -> None:
    """At the input budget's edge by the check alone (nothing converted): categories or a level of 2**25 entries
    accepted, one more refused, for a table's categorical column, a CategoricalIndex axis, a MultiIndex's level."""
    from fusion._limits import MAX_INPUT_ELEMENTS
    from fusion.book import glue as G

    def values(n: int) -> list:
        cat = pd.Categorical.from_codes([0], categories=pd.RangeIndex(n))
        level = pd.MultiIndex(levels=[pd.RangeIndex(n), pd.Index([0])], codes=[[0], [0]], verify_integrity=False)
        axis = pd.CategoricalIndex(cat)
        return [pd.DataFrame({"a": cat}), pd.DataFrame({"a": cat}).style, pd.DataFrame([[1.0]], columns=axis),
                pd.Series([1.0], index=axis), level, pd.DataFrame({"a": [1.0]}, index=level)]

    # the parts summed (fuzz 61a C3): what each holds besides its n categories or level entries counts too
    extras = [sum(G._logical_sizes(v)) - 1 for v in values(1)]
    assert extras == [2, 2, 2, 2, 2, 4]   # e.g. a one-cell table: its cell and column label (its RangeIndex rows
    # are counted by its cells)
    for i, extra in enumerate(extras):
        G._logical_check(values(MAX_INPUT_ELEMENTS - extra)[i], "k")
        with pytest.raises(ValueError, match=r"^values\['k'\] holds a .* input budget"):
            G._logical_check(values(MAX_INPUT_ELEMENTS - extra + 1)[i], "k")


def test_c1_small_categorical_table_still_glued(monkeypatch: pytest.MonkeyPatch) -> None:
    """A table with a categorical column and CategoricalIndex rows of a few categories is glued as before."""
    from _helpers import glued
    table = pd.DataFrame({"a": pd.Categorical(["x", "y"])}, index=pd.CategoricalIndex(["p", "q"]))
    assert list(glued(monkeypatch, {"k": table})) == ["k"]


def _delay_table_call(n_delays: int, n_sigmas: int) -> tuple[str, float]:
    from fusion.book.chapters.time_registration_robustness import delay_table
    d, s = list(np.linspace(-0.5, 0.5, n_delays)), list(np.linspace(0.1, 10.0, n_sigmas))
    t = time.process_time()
    with pytest.raises(ValueError) as e:
        delay_table(d, s)
    return str(e.value), time.process_time() - t


@pytest.mark.parametrize("n", [20_000, 100_000])
def test_c3_delay_table_product_refused_before_any_list(n: int) -> None:
    """The cells are counted in closed form by the two lengths, before any entry is read: refused at once (was 15.4
    CPU-s at 20,000 x 20,000 and a raw MemoryError at 100,000 x 100,000)."""
    message, cpu = _delay_table_call(n, n)
    assert message.startswith("delays and sigmas ask for ") and "work budget" in message, message
    assert cpu < 1.0, cpu


def test_c3_delay_table_budget_edge() -> None:
    """The budget's edge (592 cells) by the rule alone (the edge call is not run), counted in closed form as by the
    list it replaced; 593 cells (e.g. 593 x 1) refused by the call before any exact MSE."""
    from fusion._limits import MAX_WORK
    from fusion.scenarios import time_registration as sc
    pair, n2 = (sc.RegMethod.IMPROVED, sc.RegMethod.TWO_POINT), sc.instants()[1].size
    edge = sc._exact_work(pair, {n2: 592}, "delays and sigmas", period_change=False)
    assert edge == sc._exact_work(pair, [n2] * 592, "delays and sigmas", period_change=False) <= MAX_WORK
    with pytest.raises(ValueError, match="^delays and sigmas ask for"):
        sc._exact_work(pair, {n2: 593}, "delays and sigmas", period_change=False)
    message, cpu = _delay_table_call(593, 1)
    assert message.startswith("delays and sigmas ask for "), message
    assert cpu < 1.0, cpu
