"""Fuzz 61b: integer arrays of numpy.longlong / numpy.ulonglong (types distinct from int64 / uint64 on Linux) missed
the vectorised path of ``seeds`` / ``counts`` and were checked entry by entry (C1), as was an int64 array up to its one
bad entry.
Report: /work/tmp/fuzz61b/report.md."""

from __future__ import annotations

import time

import numpy as np
import pytest

from fusion._counts import counts, seed_array, seeds

from _helpers import refused_quickly

_N = 10**6   # entry by entry: 1.36-1.42 CPU-s before the fix (shared machine), the fast path 0.03


@pytest.mark.parametrize("dtype", [np.longlong, np.ulonglong, np.dtype(">i8"), np.dtype("<u4"), np.uint32])
def test_integer_array_of_any_integer_type_takes_the_fast_path(dtype) -> None:
    a = np.arange(_N, dtype=dtype)
    seeds(a)   # first use outside the timing
    for call in (lambda: seeds(a), lambda: seed_array(a), lambda: counts(a + 1, "ns", maximum=None)):
        t = time.process_time()
        call()
        assert time.process_time() - t < 0.5, f"{np.dtype(dtype)}: {time.process_time() - t:.2f} CPU-s"
    assert seeds(a)[-1] == _N - 1 and type(seeds(a)[-1]) is int


def test_list_of_longlong_scalars_takes_the_fast_path() -> None:
    items = list(np.arange(1, _N + 1, dtype=np.longlong))
    refused_quickly(lambda: counts(items + [np.longlong(0)], "ns", maximum=None), ValueError, r"ns\[1000000\]")
    out = counts(items, "ns", maximum=None)
    assert out[-1] == _N and type(out[-1]) is int


@pytest.mark.parametrize("dtype", [np.int64, np.longlong])
def test_one_bad_entry_at_the_end_is_refused_by_name_at_once(dtype) -> None:
    a = np.arange(_N, dtype=dtype)
    a[-1] = -1
    refused_quickly(lambda: seeds(a), ValueError, rf"seeds\[{_N - 1}\] must be an integer >= 0")
    refused_quickly(lambda: counts(a, "ns", maximum=None), ValueError, rf"ns\[0\] must be a positive integer")
    b = np.arange(1, _N + 1, dtype=dtype)
    b[-2] = 10**7 + 1
    refused_quickly(lambda: counts(b, "ns"), ValueError, rf"ns\[{_N - 2}\] = \S*10000001\)? is beyond the ceiling")


def test_budget_of_a_caller_refuses_longlong_seeds_at_once() -> None:
    from fusion.scenarios.two_sensor.weights import fruit_fly_over_seeds
    a = np.arange(2 * 10**6, dtype=np.longlong)
    with pytest.raises(ValueError, match="seeds"):   # first use (imports) outside the timing
        fruit_fly_over_seeds(np.eye(2), 2 * np.eye(2), a, n_grid=11, population=5, iterations=5)
    refused_quickly(lambda: fruit_fly_over_seeds(np.eye(2), 2 * np.eye(2), a, n_grid=11, population=5, iterations=5),
                    ValueError, "seeds")
