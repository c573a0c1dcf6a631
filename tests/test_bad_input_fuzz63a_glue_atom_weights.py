"""Fuzz 63a C1: glue_all weighs the entries of a pandas dtype of costlier atoms (an Interval, a date-time with a time
zone, a Period, a categorical of them) by their measured cost, before any conversion, naming values['k']."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from _helpers import glue_refused

_ZONED = pd.Timestamp("2020-01-01", tz="Europe/Paris")


def _int_intervals(n: int) -> pd.Series:
    return pd.Series(pd.interval_range(0, n))


def _zoned_intervals(n: int) -> pd.Series:
    return pd.Series(pd.interval_range(_ZONED, periods=n, freq="h"))


def _zoned_labels(n: int) -> pd.Series:
    return pd.Series(np.ones(n), index=pd.date_range(_ZONED, periods=n, freq="s"))


def _periods(n: int) -> pd.Series:
    return pd.Series(pd.period_range("2000-01", periods=n, freq="D"))


def _zoned_column(n: int) -> pd.DataFrame:
    return pd.DataFrame({"t": pd.date_range(_ZONED, periods=n, freq="s")})


@pytest.mark.parametrize(("build", "weight"), [(_int_intervals, 2_800), (_zoned_intervals, 6_600),
                                               (_zoned_labels, 2_001), (_periods, 1_300), (_zoned_column, 2_000)])
def test_costly_atoms_are_weighed_by_kind_at_both_bounds(build, weight) -> None:
    """The budget edge (``(MAX_WORK - _GLUE_VALUE) // weight`` entries) is within the budget by the glue's own count
    (accepted: gluing it is not run, ~4-5 CPU-s measured; a label of a float Series adds its value, 1 unit); one
    entry more is refused naming values['k'] within 1 CPU-s, before any entry is converted (fuzz 63a: 4,900,000
    Intervals, charged 200 units each, ran 73.9 CPU-s; a float Series with 2**22 labels with a time zone 34.95
    CPU-s)."""
    from fusion._limits import MAX_WORK
    from fusion.book import glue as G

    table = isinstance(build(1), pd.DataFrame)
    extra = G._GLUE_TABLE if table else 0   # a table's own units
    edge = (MAX_WORK - G._GLUE_VALUE - extra) // weight
    assert G._GLUE_VALUE + G._glue_work(build(edge), "k") <= MAX_WORK
    if table:   # its cells are charged where the glue reaches them, before converting them
        assert G._container_work(build(edge + 1))[1] > MAX_WORK - G._GLUE_VALUE - extra
    glue_refused({"k": build(edge + 1)}, ValueError)


def test_a_categorical_of_intervals_weighs_twice_its_categories() -> None:
    """A categorical's entries cost twice its categories' atoms (Intervals: 21.2 us a categorical entry against
    10.9 us), refused beyond the budget naming values['k']."""
    from fusion._limits import MAX_WORK

    n = MAX_WORK // (2 * 2_800) + 1
    glue_refused({"k": pd.Series(pd.Categorical(pd.interval_range(0, n)))}, ValueError)


def test_plain_dates_and_numbers_stay_vectorised() -> None:
    """Naive dates, durations and numbers are checked at once: a Series of 10**6 of each (or labels) is not
    charged as objects (their units stay ``_GLUE_NUMBER`` an entry)."""
    from fusion.book import glue as G

    n = 10**6
    for v in (pd.Series(pd.date_range("2020", periods=n, freq="s")), pd.Series(np.ones(n)),
              pd.Series(np.ones(n), index=pd.date_range("2020", periods=n, freq="s"))):
        assert G._glue_work(v, "k") <= 2 * n
