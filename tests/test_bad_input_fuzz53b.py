"""Fuzz 53b (issue 35, fix 59b): regressions of C2 / D3 (run_tracking_batch's seeds do not depend on ``workers``) and
C4 (the Kalman registrations' work budget). Report: /work/tmp/fuzz53b/report.md."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest


def _sc():
    from fusion.optimise.swarm import SwarmOptions
    from fusion.scenarios.range_bearing import RangeBearingScenario
    sc = RangeBearingScenario(frames=1, n_particles=60, n_components=1, n_samples=60, n_central=60, em_iterations=1,
                              variants=False)
    return sc, SwarmOptions(iterations=3)


def _arrays(run):
    return [(f.name, getattr(run, f.name)) for f in dataclasses.fields(run) if isinstance(getattr(run, f.name), np.ndarray)]


def _same(a, b):
    return all(np.array_equal(x, y, equal_nan=True) for (_, x), (_, y) in zip(_arrays(a), _arrays(b)))


# --- C2: the caller's SeedSequences advance, and the runs are the same, whatever workers --------------------------

def test_c2_run_tracking_batch_spawns_the_callers_seeds_whatever_workers(monkeypatch):
    from fusion.scenarios.range_bearing import run_tracking_batch
    monkeypatch.delenv("PYTEST_XDIST_WORKER", raising=False)  # else the runs stay in this process
    sc, opts = _sc()
    out, spawned = {}, {}
    for w in (1, 2):  # two seeds on two workers: two blocks, one per process
        seeds = [np.random.SeedSequence(7), np.random.SeedSequence(8)]
        first = run_tracking_batch(sc, seeds, swarm_options=opts, workers=w)
        spawned[w] = [s.n_children_spawned for s in seeds]
        again = run_tracking_batch(sc, seeds, swarm_options=opts, workers=w)  # a used seed gives other streams
        out[w] = (first, again)
        assert not _same(first[0], again[0])  # was equal with workers=2: the workers spawned from copies
    assert spawned[1] == spawned[2] and min(spawned[2]) > 0  # workers=2 left them at 0
    for a, b in zip(out[1][0] + out[1][1], out[2][0] + out[2][1]):
        assert _same(a, b)


# --- D3: one SeedSequence object given twice is refused ----------------------------------------------------------

@pytest.mark.parametrize("workers", [1, 2])
def test_d3_run_tracking_batch_refuses_one_seed_sequence_twice(workers):
    from fusion.scenarios.range_bearing import run_tracking_batch
    sc, opts = _sc()
    ss = np.random.SeedSequence(7)
    with pytest.raises(ValueError, match=r"^seeds\[2\] is the same SeedSequence object as seeds\[0\]"):
        run_tracking_batch(sc, [ss, np.random.SeedSequence(8), ss], swarm_options=opts, workers=workers)
    assert ss.n_children_spawned == 0  # refused before any spawn
