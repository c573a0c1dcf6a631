"""Fuzz 49a's findings on glue_all's walk, fixed by fix56a: C1 (a container holding itself inside a Series was
accepted, its text recursed), C2 (a DataFrame's or Styler's cells were neither walked nor charged), C3 (a mapping's
keys were neither checked nor charged)."""

from __future__ import annotations

import collections
import time

import numpy as np
import pandas as pd
import pytest


def _refused_quickly(value: object, match: str) -> None:
    from fusion.book.glue import glue_all
    t = time.process_time()
    with pytest.raises(ValueError, match=match):
        glue_all({"a": value})
    assert time.process_time() - t < 1.0


_CYCLE = r"^values\['a'\] must not hold a container that holds itself inside a Series"


def _series_holding_itself(how: str) -> pd.Series:
    s = pd.Series([None, 1.0], dtype=object)
    s.iloc[0] = {"list": [s], "self": s, "tuple": (s,), "dict": {"k": s}}[how]
    return s


@pytest.mark.parametrize("how", ["list", "self", "tuple", "dict"])
def test_c1_a_series_holding_itself_is_refused(how: str) -> None:
    """C1: accepted as "a container that holds itself", but pandas' text has no recursion guard: a RecursionError
    in IPython's formatter, 0.8 MB of traceback, nothing glued (3.5 CPU-s)."""
    _refused_quickly(_series_holding_itself(how), _CYCLE)
    _refused_quickly([0.5, {"k": _series_holding_itself(how)}], _CYCLE)


def test_c1_every_cycle_whose_text_recurses_is_refused() -> None:
    """The same class: a cycle inside a table, an Index or an extension array's container, a list holding itself
    inside a Series (pandas prints its cells' lists three levels deep itself), a Counter holding itself (its text
    builds a new dict at each turn). A cycle of lists, dicts or object arrays outside pandas is glued as before."""
    from fusion.book.glue import _finite
    df = pd.DataFrame({"a": [None, 1.0]}, dtype=object)
    df.iat[0, 0] = [df]
    _refused_quickly(df, _CYCLE)
    _refused_quickly(df.style, _CYCLE)
    inner: list[object] = []
    idx = pd.Index([inner, "x"], dtype=object)
    inner.append(idx)
    _refused_quickly(idx, _CYCLE)
    loop: list[object] = [0.5]
    loop.append(loop)
    _refused_quickly(pd.Series([loop, 1.0], dtype=object), _CYCLE)
    _refused_quickly(pd.DataFrame({"a": [loop]}), _CYCLE)
    c: collections.Counter = collections.Counter()
    c["x"] = c   # type: ignore[assignment]
    with pytest.raises(ValueError, match=r"^values\['a'\] must not hold .* none of whose texts prints"):
        _finite(c, "a")
    d: dict[str, object] = {"x": 1.0}
    d["y"] = d
    arr = np.empty(2, dtype=object)
    arr[0], arr[1] = arr, 2.0
    for ok in (loop, d, arr, [loop, d, arr], collections.OrderedDict(d=d)):
        assert _finite(ok, "a")


def _shared(width: int) -> list:
    x: list = [0.5] * width
    for _ in range(2):
        x = [x] * width
    return x


def test_c2_a_tables_object_cells_are_walked_and_charged() -> None:
    """C2: a DataFrame was a flat 300,000 units: 3 cells holding a shared list of 1e8 printed floats ran > 36 CPU-s;
    its object cells are now walked and charged as an object Series' entries. Edge: one cell holding 99**3 printed
    floats (980,299 entries inside containers, under the 10**6 a call may print) is accepted (glued in ~4.2 CPU-s:
    checked here by the walk alone); 100**3 is refused before the work, as two such cells are."""
    from fusion.book.glue import _finite
    for make in (lambda c: pd.DataFrame({"a": c}), lambda c: pd.DataFrame({"a": c}).style,
                 lambda c: pd.Series(c, dtype=object)):
        t = time.process_time()
        assert _finite(make([_shared(99)]), "a")     # just inside
        assert time.process_time() - t < 1.0
        _refused_quickly(make([_shared(100)]), r"^values\['a'\] ask for more work")
        _refused_quickly(make([_shared(99), _shared(99)]), r"^values\['a'\] ask for more work")
    # a label prints too: a row label holding 1e6 printed floats
    _refused_quickly(pd.DataFrame({"a": [1.0]}, index=pd.Index([tuple([tuple([0.5] * 1001)] * 1000)], dtype=object)),
                     r"^values\['a'\] ask for more work")


def test_c2_a_tables_cells_follow_the_rule_of_every_container() -> None:
    """A 3000-deep list in a cell skipped the 64-level nesting check (RecursionError in the formatter, nothing
    glued); a NaN in a cell's list, a deque in a cell were glued unchecked. A table's own missing cell or non-finite
    number (in an object column as in a numeric one) is still glued: a table prints it as a word."""
    from fusion.book.glue import _finite
    deep: list = [1.0]
    for _ in range(3000):
        deep = [deep]
    _refused_quickly(pd.DataFrame({"a": [deep]}), r"^values\['a'\] must not nest containers more than 64 deep")
    _refused_quickly(pd.DataFrame({"a": [deep]}).style, r"^values\['a'\] must not nest containers")
    _refused_quickly(pd.DataFrame({"a": [[1.0, np.nan]]}), r"^values\['a'\] must be finite")
    _refused_quickly(pd.DataFrame({"a": [1.0]}, index=pd.Index([frozenset({1.0, np.nan})], dtype=object)).style,
                     r"^values\['a'\] must be finite")
    from fusion.book.glue import glue_all
    with pytest.raises(TypeError, match=r"^values\['a'\] must be a number, text"):
        glue_all({"a": pd.DataFrame({"a": [collections.deque([np.nan])]})})
    ok = pd.DataFrame({"a": [np.nan, "x", None, pd.NA, np.inf, pd.NaT, [1.0, "y"]], "b": np.nan},
                      index=pd.MultiIndex.from_tuples([(f"r{i}", np.nan if i else 1.0) for i in range(7)]))
    assert _finite(ok, "a") and _finite(ok.style, "a") and _finite(pd.DataFrame(), "a")


def test_c3_a_mappings_keys_are_checked_and_charged() -> None:
    """C3: {nan: 1.0} was glued as '{nan: 1.0}'; two values {top: 1.0}, {top: 2.0} whose frozenset key prints 2e8
    floats ran 39.6 CPU-s accepted where the same frozenset as a value was refused at once."""
    from fusion.book.glue import _finite, glue_all
    for key in (float("nan"), float("inf"), pd.NaT, (1.0, float("nan")), frozenset({np.float64("nan")})):
        _refused_quickly({key: 1.0}, r"^values\['a'\] must be finite")
        _refused_quickly([{"k": {key: 1.0}}], r"^values\['a'\] must be finite")
    with pytest.raises(TypeError, match=r"^values\['a'\] must be a number, text"):
        glue_all({"a": {object(): 1.0}})
    s = frozenset(i + 0.5 for i in range(10**5))
    top = frozenset(frozenset({s, -i - 1}) for i in range(2000))
    t = time.process_time()
    with pytest.raises(ValueError, match=r"^values\['a'\] ask for more work"):
        glue_all({"a": {top: 1.0}, "b": {top: 2.0}})
    assert time.process_time() - t < 1.0
    # keys count as entries: a dict of 500,000 keys and values is 10**6 entries (the most a call may print inside
    # containers), one more key is refused
    assert _finite({i: 0.5 for i in range(500_000)}, "a")
    with pytest.raises(ValueError, match=r"^values\['a'\] ask for more work"):
        _finite({i: 0.5 for i in range(500_001)}, "a")
    _refused_quickly([{i: 0.5 for i in range(500_000)}, {"x": 0.5}], r"^values\['a'\] ask for more work")
    assert _finite({"x": 1.0, 2: [0.5, "y"], (1, "z"): None}, "a")


def test_c2_a_table_inside_a_container_is_charged_as_a_table() -> None:
    """The same class (fix56a): a table inside a list was charged as one list entry (400 units) but printed as a
    table: ``[[df] * 300] * 300`` of a 2 x 1 DataFrame, 90,000 printed tables, ran 24.6 CPU-s accepted. Each is now
    charged ``_GLUE_TABLE`` where the walk reaches it: 2500 (7.5e8 units) accepted, 3600 refused before the work."""
    from fusion.book import glue as G
    df = pd.DataFrame({"a": [1.0, 2.0]})
    assert G._GLUE_TABLE == 300_000
    assert G._finite([[df] * 50] * 50, "a")   # (a Styler inside a container is refused since fix57b: its text is
    _refused_quickly([[df] * 60] * 60, r"^values\['a'\] ask for more work")   # its address)
    G.glue_all({"a": [df, df], "b": df})
