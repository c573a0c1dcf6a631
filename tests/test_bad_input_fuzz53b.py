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


# --- C4: the Kalman registrations count their per-sample loop ------------------------------------------------------

class _Ran(Exception):
    """Raised in place of the loop: the call got past its checks."""


def _stop(*args, **kwargs):
    raise _Ran


def _series(n, runs=None):
    t = np.arange(n) * 1.0
    z = 2.0 * t if runs is None else np.tile(2.0 * t, (runs, 1))
    return t, z


def test_c4_kalman_budget_edges():
    # the edge of one run: 331,674 filter steps (~9 CPU-s at 26 us a step measured), 248,447 smoothed ones
    from fusion._limits import MAX_WORK
    from fusion.registration.methods import _kalman_work
    assert _kalman_work(331_674, 1, False, "t and z") <= MAX_WORK
    with pytest.raises(ValueError, match="^t and z ask for"):
        _kalman_work(331_675, 1, False, "t and z")
    assert _kalman_work(248_447, 1, True, "t and Z") <= MAX_WORK
    with pytest.raises(ValueError, match="^t and Z ask for"):
        _kalman_work(248_448, 1, True, "t and Z")
    # each run of Z counts at each step (within the input cap the steps dominate; counted, not run)
    with pytest.raises(ValueError, match="^t and Z ask for"):
        _kalman_work(20, 3_400_000, False, "t and Z")


def _calls():
    from fusion import registration as G
    from fusion.scenarios import time_registration as TR
    t, z = _series(331_675)
    ts, zs = _series(248_448)
    return [
        ("kalman_filter", lambda: G.kalman_filter(t, z, 1.0), "t and z"),
        ("kalman_filter t_extra", lambda: G.kalman_filter(t[:200_000], z[:200_000], 1.0, t_extra=t[:140_000] + 0.5),
         "t, z and t_extra"),
        ("kalman_register", lambda: G.kalman_register(t, z, [1.5], 1.0), "t and z"),
        ("improved_register", lambda: G.improved_register(t, z, [1.5], 1.0), "t and z"),
        ("kalman_runs", lambda: G.kalman_runs(t, z, 1.0), "t and Z"),
        ("kalman_runs smooth", lambda: G.kalman_runs(ts, zs, 1.0, smooth=True), "t and Z"),
        ("kalman_runs lag_one", lambda: G.kalman_runs(ts, zs, 1.0, lag_one=True), "t and Z"),
        ("register", lambda: TR.register("reg_kalman_predict", t, z, [1.5], 1.0), "t_src and z"),
        ("register smoother", lambda: TR.register("reg_rts_smoother", ts, zs, [1.5], 1.0), "t_src and z"),
        ("register period_change", lambda: TR.register("reg_kalman_predict", t[:200_000], z[:200_000],
                                                      t[:140_000] + 0.5, 1.0, kf={"period_change": True}),
         "t_src, z and t_dst"),
    ]


@pytest.mark.parametrize("case", range(10))
def test_c4_kalman_work_beyond_the_budget_is_refused_at_once(case):
    import time
    what, call, names = _calls()[case]
    t0 = time.process_time()
    with pytest.raises(ValueError, match=f"^{names} ask for .* beyond the work budget"):
        call()  # accepted and ran 30-1,000 CPU-s before (fuzz 53b C4)
    assert time.process_time() - t0 < 1.0, what


def test_c4_just_inside_passes_the_budget(monkeypatch):
    # the edges are accepted: the call reaches the loop (stopped there, not run)
    import fusion.registration.methods as M
    from fusion.scenarios import time_registration as TR
    t, z = _series(331_674)
    monkeypatch.setattr(M, "KalmanFilter", _stop)
    with pytest.raises(_Ran):
        M.kalman_filter(t, z, 1.0)
    monkeypatch.setattr(M, "ca_transition", _stop)
    ts, zs = _series(248_447)
    with pytest.raises(_Ran):
        M.kalman_runs(ts, zs, 1.0, smooth=True)
    with pytest.raises(_Ran):
        TR.register("reg_rts_smoother", ts, zs, [1.5], 1.0)


def test_c4_the_books_kalman_calls_stay_far_inside():
    # chapter 07 filters its scenario's samples (and instants with period_change), at most thousands of runs
    from fusion._limits import MAX_WORK
    from fusion.registration.methods import _kalman_work
    from fusion.scenarios import time_registration as TR
    n1, n2 = (t.size for t in TR.instants())
    assert _kalman_work(n1 + n2, 10_000, True, "t and Z") < MAX_WORK / 100


def test_c4_smooth_and_lag_one_refused_before_the_filter(monkeypatch):
    import fusion.registration.methods as M
    monkeypatch.setattr(M, "ca_transition", _stop)  # was checked after the filter's loop
    t, z = _series(10)
    with pytest.raises(ValueError, match="smooth and lag_one"):
        M.kalman_runs(t, z, 1.0, smooth=True, lag_one=True)
