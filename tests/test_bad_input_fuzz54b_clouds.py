"""Fuzz 54b C2: ``chernoff_scaling.frame_clouds`` applies the batch runner's checks, for one run of ``frame + 1``
frames, before any work, naming its arguments, and makes only the seed of the run it shows."""

from __future__ import annotations

import time

import numpy as np
import pytest

from fusion.book.chapters import chernoff_scaling as csc
from fusion.scenarios import range_bearing as rb

from _helpers import refused_quickly


def _toy(**kw: object) -> rb.RangeBearingScenario:
    base = dict(frames=3, n_particles=60, n_samples=60, n_central=100, em_iterations=2)
    base.update(kw)
    return rb.RangeBearingScenario(**base)


def test_frame_clouds_makes_only_the_seed_of_its_run() -> None:
    # C2a: runs = 6,000,000 spawned six million SeedSequences to use one (34 CPU-s for a run of 3 frames)
    t = time.process_time()
    fc = csc.frame_clouds(_toy(), 0, 6_000_000, run=0, frame=0)
    assert time.process_time() - t < 1.0
    assert fc.run == 0 and fc.frame == 0


@pytest.mark.parametrize("seed, runs, run", [(0, 1, 0), (123, 5, 3), (2**200 + 5, 40, 39)])
def test_frame_clouds_seed_is_the_spawned_child(seed: int, runs: int, run: int) -> None:
    """The run's streams are those of ``SeedSequence(seed).spawn(runs)[run]``, bit for bit."""
    sc = _toy()
    child = np.random.SeedSequence(seed).spawn(runs)[run]
    batch = rb._Batch(sc, [rb._run_streams(child)], [False], None)
    batch.frame(0)
    batch.frame(1)
    fc = csc.frame_clouds(sc, seed, runs, run=run, frame=1)
    np.testing.assert_array_equal(fc.particles, batch.particles[0])
    np.testing.assert_array_equal(fc.truth, batch.truth[0, :2])
    np.testing.assert_array_equal(fc.chernoff, batch.est["chernoff_pso"][0, 1])
    np.testing.assert_array_equal(fc.centralised, batch.est["centralised_pf"][0, 1])


def test_frame_clouds_memory_budget_names_the_scenario() -> None:
    # C2b: 3,000,000 particles a node ran 20 CPU-s, then a result's check named no argument
    refused_quickly(lambda: csc.frame_clouds(rb.RangeBearingScenario(n_particles=3_000_000, frames=2), 0, 1, frame=0),
             ValueError, r"^sc\.sensors and sc\.n_particles ask for an array")
    # the edge: the block's 8 arrays of a run (3 nodes x n x 4) at 2**28 numbers, by the memory check alone
    rb._block_allocation(rb.RangeBearingScenario(n_particles=2**28 // 96, frames=2), 1, "sc", frames=1)
    refused_quickly(lambda: csc.frame_clouds(rb.RangeBearingScenario(n_particles=2**28 // 96 + 1, frames=2), 0, 1,
                                               frame=0),
             ValueError, r"^sc\.sensors and sc\.n_particles ask for an array")


def test_frame_clouds_work_budget_counts_the_frames_it_steps() -> None:
    # C2c: beyond run_tracking_batch's budgets; frame 199 accepted and ran 42 CPU-s
    sc = rb.RangeBearingScenario(frames=1000, n_particles=50000, n_samples=20000, n_central=100000)
    refused_quickly(lambda: csc.frame_clouds(sc, 0, 1, run=0, frame=199), ValueError, r"^frame, sc\.frames.* units of work")
    per = rb._one_run_checks(sc, 0)  # one frame's units (and the unstepped frames' set-up)
    edge = next(f for f in range(1, 1000) if _units(sc, f) > 10**9) - 1
    assert per < 10**9 and rb._one_run_checks(sc, edge) <= 10**9  # accepted by the budget alone (about 7 CPU-s)
    refused_quickly(lambda: csc.frame_clouds(sc, 0, 1, frame=edge + 1), ValueError, r"^frame, sc\.frames.* units of work")


def _units(sc: rb.RangeBearingScenario, frame: int) -> int:
    try:
        return rb._one_run_checks(sc, frame)
    except ValueError:
        return 10**9 + 1


def test_frame_clouds_counts_the_set_up_of_every_frame_of_the_scenario() -> None:
    # frame 0 of a scenario of many frames: the runner simulates the target and allocates records over all of them
    # (3-4 us and 353 numbers a frame measured, 364 counted); 10,000,000 frames would need 28 GB
    refused_quickly(lambda: csc.frame_clouds(_toy(frames=10_000_000), 0, 1, frame=0), ValueError, r"^sc\.frames, sc\.sensors and sc")
    assert rb._frame_records(_toy()) >= 353
    edge = 2**28 // rb._frame_records(_toy())
    assert rb._one_run_checks(_toy(frames=edge), 0) < 10**9  # the edge, by the budget alone (about 2.7 CPU-s, 2 GB)
    refused_quickly(lambda: csc.frame_clouds(_toy(frames=edge + 1), 0, 1, frame=0),
             ValueError, r"^sc\.frames, sc\.sensors and sc\.readings ask for an array")
    # with readings (521 numbers a frame measured)
    assert rb._frame_records(_toy(readings=True)) >= 521
    edge = 2**28 // rb._frame_records(_toy(readings=True))
    assert rb._one_run_checks(_toy(frames=edge, readings=True), 0) < 10**9
    refused_quickly(lambda: csc.frame_clouds(_toy(frames=edge + 1, readings=True), 0, 1, frame=0),
             ValueError, r"^sc\.frames, sc\.sensors and sc\.readings ask for an array")
    # the set-up of the frames not stepped is counted: one stepped frame of 2 costs the set-up of the other
    assert rb._one_run_checks(_toy(frames=2), 0) == rb._one_run_checks(_toy(frames=1), 0) + rb.TRACK_RECORD
