"""Fuzz 47: the robust baselines' own limits checked at the entry of the readings benchmark (C4)."""

from __future__ import annotations

import time

import numpy as np
import pytest


def _refused_fast(f, match: str, limit: float = 1.0) -> None:
    t0 = time.process_time()
    with pytest.raises(ValueError, match=match):
        f()
    assert time.process_time() - t0 < limit


def _not_drawn(*args, **kwargs):
    raise AssertionError("drawn")


# --- C4 ------------------------------------------------------------------------------------------------------------

def test_c4_benchmark_checks_the_biweight_limit_at_entry(monkeypatch):
    # 344,656 runs x 10 samples x 3 sensors passed the benchmark's own budget, then robust_fuse(xK, "biweight")
    # refused its worst-case IRLS passes after ~10 CPU-s of the other methods; now refused before the draws
    from fusion.scenarios.lecture_weighting.readings_benchmark import benchmark
    monkeypatch.setattr(np.random, "default_rng", _not_drawn)
    one = dict(seeds=(1,), samples=10, levels=(0.0,), faults=(False,), sigma=(1.0, 1.0, 1.0))
    _refused_fast(lambda: benchmark(runs=344_656, **one), r"^runs and sigma")
    # the edge: accepted at entry (it reaches the draws)
    with pytest.raises(AssertionError, match="drawn"):
        benchmark(runs=344_655, **one)

