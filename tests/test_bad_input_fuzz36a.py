"""Fuzz 35a (issue 35), fixed in fix36a: the study cache's views, object arrays' precision, swarm options.

* C1/D2: a cached result never shares memory with anything a caller can write: an array that does not own its
  data (a view of an argument, a column of a local array) is kept as a read-only copy (in process and on disk).
"""

from __future__ import annotations

import numpy as np
import pytest

from fusion.book import study_cache as sc_mod
from fusion.book.study_cache import study_cache


@study_cache(8)
def _tail(x):
    return x[1:]


@study_cache(8)
def _first_col(n):
    a = np.arange(float(2 * n)).reshape(n, 2)
    return {"col": a[:, 0], "t": [a.T]}


@pytest.mark.parametrize("disk", [False, True])
def test_c1_a_view_of_the_argument_is_not_shared_with_the_caller(tmp_path, monkeypatch, disk):
    monkeypatch.delenv(sc_mod.LOG_ENV, raising=False)
    if disk:
        monkeypatch.setenv(sc_mod.ENV, str(tmp_path / "c"))
    else:
        monkeypatch.delenv(sc_mod.ENV, raising=False)
    _tail.cache_clear()
    x = np.array([1.0, 2.0, 3.0])
    _tail(x)
    x[1] = 99.0                                # the caller's own array stays writeable, its edit stays its own
    again = _tail(np.array([1.0, 2.0, 3.0]))
    assert again.tolist() == [2.0, 3.0] and not again.flags.writeable
    assert not np.shares_memory(again, x)
    if disk:
        _tail.cache_clear()                    # loaded from the disk: the values computed
        assert _tail(np.array([1.0, 2.0, 3.0])).tolist() == [2.0, 3.0]


def test_d2_the_base_of_a_returned_view_is_not_writeable_through_the_result(monkeypatch):
    monkeypatch.delenv(sc_mod.ENV, raising=False)
    _first_col.cache_clear()
    for _ in range(3):   # each caller writes through what it was given (the first gets the function's own dict)
        r = _first_col(3)
        for arr in (r["col"], r["t"][0]):
            for owner in (arr, arr.base):
                if owner is not None and owner.flags.writeable:
                    owner.flat[0] = -1.0
        assert _first_col(3)["col"].tolist() == [0.0, 2.0, 4.0]
