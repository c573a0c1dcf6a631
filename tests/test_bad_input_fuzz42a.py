"""Fuzz 42a (the package outside the book layer): a caller's ``len()`` bounds what is read (C1), a budget counts every
loop a function runs, weighted by its measured cost (C2-C7), a valid producer's output is a valid reader's input (C8),
and an in-range input never raises a raw OverflowError (C9)."""

from __future__ import annotations

import time
from collections.abc import Mapping, Sequence

import numpy as np
import pytest

from fusion._limits import MAX_WORK


def _refused_fast(f, *args, match: str, **kw) -> None:
    t = time.process_time()
    with pytest.raises(ValueError, match=match):
        f(*args, **kw)
    assert time.process_time() - t < 1.0


class _Lying(Sequence):
    """``len()`` is 3; ``__getitem__`` answers up to index ``n`` (never raising for ``n=None``)."""

    def __init__(self, n):
        self.n = n

    def __len__(self):
        return 3

    def __getitem__(self, i):
        if self.n is not None and i >= self.n:
            raise IndexError(i)
        return 1.0


@pytest.mark.parametrize("n", [10**8, None])
def test_lying_sequence_read_at_most_one_past_its_len(n):
    """C1: read_once read a Sequence whose len() is 3 through its __getitem__ until IndexError (1e8 entries, 24 CPU-s;
    an endless one for ever); now one entry past len() is read and the call refused naming the argument."""
    from fusion.readings.fusion_set import fuse_epochs
    from fusion.scenarios import infrared_radar

    _refused_fast(infrared_radar.late_means, {"a": np.ones((3, 4))}, _Lying(n), match=r"^t has len\(\) 3 but more")
    _refused_fast(fuse_epochs, _Lying(n), "mean", match=r"^x has len\(\) 3 but more")


def test_honest_and_short_sequences():
    """C1: an honest Sequence is read as its list; one with fewer items than its len() is refused by name."""
    from fusion.readings.fusion_set import fuse_epochs

    assert fuse_epochs(_Lying(3), "mean").values.tolist() == [1.0]
    _refused_fast(fuse_epochs, _Lying(2), "mean", match=r"^x has len\(\) 3 but 2 items")


def test_lying_mapping_read_at_most_one_past_its_len():
    """C1: read_mapping read a Mapping's items until its iterator ended (an endless one for ever)."""
    from fusion._guards import read_mapping

    class Endless(Mapping):
        def __len__(self):
            return 1

        def __iter__(self):
            i = 0
            while True:
                yield i
                i += 1

        def __getitem__(self, k):
            return 1.0

    _refused_fast(read_mapping, Endless(), "scenarios", match=r"^scenarios has len\(\) 1 but more")


def test_variance_change_study_counts_each_change_step():
    """C2: a change's fixed ~0.7 ms step was not counted: 50,000 changes at the smallest draws (1 run x 20 samples x 3
    sensors) were accepted and ran 36.9 CPU-s. Now 14,000 are refused at once; 13,500 (9.3 CPU-s) pass the budget
    and reach the next check (a change_at outside the samples, named)."""
    from fusion.scenarios.lecture_weighting.regime import variance_change_study

    def changes(c):
        return [(f"c{i}", {0: 2.0}) for i in range(c)]

    kw = dict(sigma=(1.0, 1.0, 1.0), samples=20, runs=1)
    _refused_fast(variance_change_study, changes=changes(14_000), change_at=10, **kw,
                  match=r"^runs, samples, sigma and changes ask for 1.02e\+09 units")
    _refused_fast(variance_change_study, changes=changes(13_500), change_at=20, **kw, match=r"^change_at")
