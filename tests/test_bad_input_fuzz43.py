"""Fuzz 43: a legal ``len()`` of ``sys.maxsize`` is refused by name as any other lying ``len()`` (C3), a window
longer than the samples (C1), a producer's covariances symmetric for its reader (C4) and a super-linear run cost
counted as such (C2)."""

from __future__ import annotations

import sys
import time
from collections.abc import Mapping

import numpy as np
import pytest


def _refused_fast(f, *args, match: str, **kw) -> None:
    t = time.process_time()
    with pytest.raises(ValueError, match=match):
        f(*args, **kw)
    assert time.process_time() - t < 1.0


class _HugeLen(Mapping):
    """Two items, ``len()`` ``sys.maxsize`` (a legal length: islice's stop ``len()`` + 1 overflowed)."""

    def __len__(self):
        return sys.maxsize

    def __iter__(self):
        return iter(["a", "b"])

    def __getitem__(self, k):
        return 1


def test_c3_read_mapping_len_maxsize_is_the_documented_value_error():
    from fusion._validation import read_mapping
    _refused_fast(read_mapping, _HugeLen(), "m", match=r"m has len\(\) .* but 2 items")


def test_c3_public_caller_len_maxsize():
    from fusion.scenarios.lecture_weighting.readings_benchmark import seed_stability
    _refused_fast(seed_stability, _HugeLen(), match=r"results has len\(\) .* but 2 items")
