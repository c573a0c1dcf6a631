"""Fuzz 46a's findings on glue_all's work budget, fixed by fix54b: C2 (containers inside a value were not counted),
C3 (object arrays, object Series / Index and pandas extension arrays were counted 0 units)."""

import time

import numpy as np
import pandas as pd
import pytest


def _refused_quickly(values: dict, match: str) -> None:
    from fusion.book import glue as G
    t = time.process_time()
    with pytest.raises(ValueError, match=match):
        G.glue_all(values, decimals=3)
    assert time.process_time() - t < 1.0


def test_c2_entries_inside_a_value_are_counted_as_they_are_reached() -> None:
    """C2: {"k": [[0.5] * 4500] * 4500} was counted by its 4500 outer entries and ran 37.7 CPU-s; now every entry
    inside is counted as ``_finite`` reaches it, up to ``_GLUE_VISITS`` entries (and the budget's units)."""
    from fusion._limits import MAX_WORK
    from fusion.book import glue as G
    edge = 10**6   # G._GLUE_VISITS, checked below
    _refused_quickly({"k": [[0.5] * (edge + 1)]}, r"^values\['k'\] ask for more work")
    assert G._GLUE_VISITS == edge
    G._Meter().charge(edge, G._GLUE_NESTED, "k")   # just inside: accepted (not run: ~3.5 CPU-s)
    with pytest.raises(ValueError, match=r"^values\['k'\] ask for more work"):
        G._Meter().charge(edge + 1, G._GLUE_NESTED, "k")
    _refused_quickly({"a": [0.5] * 10, "k": ({"x": [0.5] * (edge // 2)}, [[0.5] * (edge // 2 + 1)])},
                     r"^values\['k'\] ask for more work")
    # the units of the budget too: a table uses most of it, then a small list of lists is beyond
    cells = (MAX_WORK - 3 * G._GLUE_VALUE - G._GLUE_TABLE) // G._GLUE_CELL - 10
    table = pd.DataFrame(np.zeros((cells, 1))).style
    _refused_quickly({"t": table, "k": [[0.5] * 100]}, r"^values\['k'\] ask for more work")
    G.glue_all({"k": [[0.5] * 1000 for _ in range(10)], "m": {"a": [1.0, 2.0], "b": (3, [4.0])}}, decimals=3)


@pytest.mark.parametrize(("make", "weight"), [(lambda n: np.full(n, 0.5, dtype=object), 900),
                                              (lambda n: pd.Series(np.full(n, 0.5, dtype=object)), 900),
                                              (lambda n: pd.Index(np.full(n, 0.5, dtype=object)), 900),
                                              (lambda n: pd.array(np.full(n, 0.5), dtype="Float64"), 200),
                                              (lambda n: pd.Categorical(np.arange(n) % 7), 200)])
def test_c3_object_arrays_are_counted_by_their_size(make, weight) -> None:
    """C3: np.full(4e7, 0.5, dtype=object) was counted 0 units and ran 69.9 CPU-s; an object array, object Series
    or Index and an extension array are now counted by their size at ``_GLUE_OBJECT`` units an entry, at entry
    (naming values) and inside a container (naming values[key]); a NumPy object dtype's entries by their type since
    fuzz 65a C2 (a float there, 3.7-4.2 us measured, ``_glue_axes._OBJECT_ANY``: 900 units)."""
    from fusion._limits import MAX_WORK, work
    from fusion.book import glue as G
    edge = (MAX_WORK - 10_000) // weight   # (MAX_WORK - _GLUE_VALUE) // its weight, checked below
    _refused_quickly({"k": make(edge + 1)}, r"^values(\['k'\])? .*work budget")
    _refused_quickly({"k": [make(10**6 + 1)]}, r"^values\['k'\] ask for more work")
    assert (G._GLUE_VALUE, G._GLUE_OBJECT) == (10_000, 200)
    assert work((G._GLUE_VALUE + G._glue_work(make(edge)),), "values") <= MAX_WORK  # just inside (not run)
    G.glue_all({"k": make(1000), "j": [make(10)]}, decimals=3)


def test_numeric_arrays_are_counted_by_logical_size() -> None:
    """A numeric array, Series or Index is checked vectorised (~1 ns an entry): counted ``_GLUE_NUMBER`` (1) unit an
    entry by its logical size since fuzz 57a C1 (0 before: a RangeIndex(10**12) was converted), still glued."""
    from fusion.book import glue as G
    big = np.full(2 * 10**7, 0.5)
    assert G._GLUE_NUMBER == 1
    assert G._glue_work(big) == G._glue_work(pd.Series(big)) == G._glue_work(pd.Index(big)) == 2 * 10**7
    G.glue_all({"k": big, "j": [pd.Series(big)]}, decimals=3)
