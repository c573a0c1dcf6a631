"""Fuzz 47: glue_all's meter charges a container at every path that prints it (C3); the robust baselines' own
limits checked at the entry of the readings benchmark (C4)."""

from __future__ import annotations

import copy
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


# --- C3 ------------------------------------------------------------------------------------------------------------

def test_c3_a_container_reached_again_is_charged_its_printed_entries() -> None:
    # [[[0.5] * 200] * 200] * 200 was charged 600 entries (each list once) and printed 8e6 floats: 16.8 CPU-s
    from fusion.book import glue as G
    _refused_fast(lambda: G.glue_all({"k": [[[0.5] * 200] * 200] * 200}, decimals=3), r"^values\['k'\] ask for more")
    # both bounds of the 10**6 printed entries (G._GLUE_VISITS): one list of 1,000 floats printed at 1,000 / 1,001
    # paths, checked by the meter alone (gluing the edge takes ~3.5 CPU-s)
    assert G._GLUE_VISITS == 10**6
    inner = [0.5] * 1000

    def check(k: int) -> None:
        x = [inner] * k
        G._check_finite("k", x, G._Meter(G.MAX_WORK - G._GLUE_VALUE - G._glue_work(x)), counted=True)

    check(1000)
    _refused_fast(lambda: check(1001), r"^values\['k'\] ask for more")
    _refused_fast(lambda: G.glue_all({"k": [inner] * 1001}), r"^values\['k'\] ask for more")


def test_c3_cycles_and_small_shared_containers_are_still_glued() -> None:
    from fusion.book import glue as G
    a = [0.5, 1.5]
    a.append(a)   # holds itself: printed [...] there, charged 0 again
    shared = {"x": [0.25] * 10}
    G.glue_all({"k": a, "m": [shared, shared, (shared, [shared])]}, decimals=3)


def test_c3_a_container_reached_again_deeper_is_refused_by_its_nesting() -> None:
    # a list nested 41 deep, reached first near the top, then again 32 lists deeper: its text nests 73 deep
    from fusion.book import glue as G
    deep: list = [0.5]
    for _ in range(40):
        deep = [deep]
    chain: list = [deep]
    for _ in range(30):
        chain = [chain]
    _refused_fast(lambda: G.glue_all({"k": [chain, deep]}), r"^values\['k'\] must not nest containers")
    # both bounds, as the same lists unshared: the innermost list 63 deep is accepted, 64 deep refused
    edge = chain[0][0][0][0][0][0][0][0][0]   # deep reached again at depth 23: its innermost list at 63
    G.glue_all({"k": [edge, deep]})
    G.glue_all({"k": [copy.deepcopy(edge), deep]})
    for x in ([[edge], deep], [copy.deepcopy([edge]), deep]):
        _refused_fast(lambda: G.glue_all({"k": x}), r"^values\['k'\] must not nest containers")

