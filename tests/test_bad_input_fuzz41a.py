"""Fuzz 41a (the budgets of fuzz 40a's fixes): what a budget counts is what the function iterates, converted (never a
caller's ``len()``), summed over every loop it runs (the rules of a reader, the cases of a study), and refused before
any of that work (C2-C7; the weights measured, see each function's comment)."""

from __future__ import annotations

import time

import numpy as np
import pytest

from _helpers import ShrinkingLen as _ShrinkingLen  # one helper for fuzz 41a and 42a

from fusion._limits import MAX_WORK


def _refused_fast(f, *args, match: str, **kw) -> None:
    t = time.process_time()
    with pytest.raises(ValueError, match=match):
        f(*args, **kw)
    assert time.process_time() - t < 1.0


class _ArrayOnly:
    """An array-like with only ``__array__`` (no len, no shape)."""

    def __init__(self, a):
        self.a = np.asarray(a, dtype=float)

    def __array__(self, dtype=None, copy=None):
        return self.a if dtype is None else self.a.astype(dtype)


class _LyingLen(_ArrayOnly):
    def __init__(self, a, n):
        super().__init__(a)
        self.n = n

    def __len__(self):
        return self.n

    def __getitem__(self, i):
        return self.a[i]


def test_infrared_readers_sum_their_rules():
    """C2: each rule's fuse_tracks was checked alone, so rule_errors on 1 run of 38,901 scans (each rule just inside)
    ran 33-37 CPU-s: the rules' steps are summed, 1 run of 8,000 scans accepted by the rule, 20,000 refused by name."""
    from fusion.scenarios import _infrared_budget as ib
    from fusion.scenarios import infrared_radar as ir

    rules = ir._rule_subset(None)
    ib._reader_budget("rule_errors", 1, 8_000, 4, rules, "sim")
    with pytest.raises(ValueError, match=r"^sim ask .*work"):
        ib._reader_budget("rule_errors", 1, 20_000, 4, rules, "sim")
    with pytest.raises(ValueError, match=r"^sim ask .*work"):
        ib._reader_budget("cartesian_errors", 1, 20_000, 6, rules, "sim")
    sim = ir.simulate(np.random.default_rng(0), runs=1, duration=200.0, T=0.01)   # 20,001 scans, each rule inside
    _refused_fast(ir.rule_errors, sim, match=r"^sim \(its runs and scans\) and rules ask .*work")


def test_cartesian_tracks_counts_its_scans():
    """C3: 150 units a run and scan missed the scans' Python steps (0.22-0.26 ms a scan at 1 run): 1 run of 120,001
    scans ran 30-35 CPU-s. 1 run is accepted up to 39,761 scans by the rule, 39,762 refused; the simulation refused at
    once."""
    from fusion._limits import work
    from fusion.scenarios import _infrared_budget as ib
    from fusion.scenarios import infrared_radar as ir

    ib._tracks_budget(1, 39_761, "sim")
    with pytest.raises(ValueError, match=r"^sim ask .*work"):
        ib._tracks_budget(1, 39_762, "sim")
    work((10_000 * 101,), "runs", weight=ib._TRACKS_UNITS)   # many runs: still counted per run and scan
    sim = ir.simulate(np.random.default_rng(0), runs=1, duration=420.0, T=0.01)
    _refused_fast(ir.cartesian_tracks, sim, match=r"^sim \(its runs and scans\) ask .*work")


def test_variance_change_study_counts_the_changes_it_iterates():
    """C4: len(changes) was read again after sequence() had read it, so a len() that turned 1 counted 1 change while
    the loop ran 100 (still running after 90 s): the list sequence() returns is counted and iterated."""
    from fusion.scenarios.lecture_weighting.regime import variance_change_study

    changes = _ShrinkingLen([(f"c{i}", {0: 1.5 + i * 0.01}) for i in range(100)])
    _refused_fast(variance_change_study, sigma=[0.5, 1, 2], samples=1000, runs=1800, changes=changes, change_at=10,
                  match=r"^runs, samples, sigma and changes ask")


def test_coupling_study_takes_n_from_the_converted_own():
    """C5: N was len(case["own"]): an own with only __array__ (accepted before) raised a raw TypeError, and a __len__
    of 3 over 2,000 entries was counted as 3 (49 CPU-s)."""
    from fusion.scenarios.correlated_sensors import coupling_study

    study = coupling_study({"a": {"own": _ArrayOnly([1.0, 2, 3]), "coupling": _ArrayOnly([1.0, 1, 1]), "env": 1.0}},
                           runs=100)
    assert study.weights["a"][0].shape == (3,)
    N = 2000
    _refused_fast(coupling_study, {"a": {"own": _LyingLen(np.ones(N), 3), "coupling": _LyingLen(np.ones(N), 3),
                                         "env": 1.0}}, runs=2, match=r"^scenarios \(their sensors\), runs and env_grid")


def test_coupling_study_refuses_before_building_the_covariances():
    """C6: every case's N x N covariance was built and checked before the budget: 16 cases of N = 9,400 were refused
    after 8.5 CPU-s, 250,000 cases of N = 3 after 9-12. Counted case by case from the converted own, refused at once."""
    from fusion.scenarios.correlated_sensors import coupling_study

    cases = {f"c{i}": {"own": np.ones(9400), "coupling": np.ones(9400), "env": 1.0} for i in range(16)}
    _refused_fast(coupling_study, cases, runs=2, match=r"^scenarios \(their sensors\), runs and env_grid ask")
    cases = {f"c{i}": {"own": [1.0, 2.0, 3.0], "coupling": [1.0, 1.0, 1.0], "env": 1.0} for i in range(250_000)}
    _refused_fast(coupling_study, cases, runs=2, match=r"^scenarios \(their sensors\), runs and env_grid ask")


def test_late_means_counts_array_likes_by_their_converted_size():
    """C7: a value with only __array__ had no count before conversion and was skipped: 400 methods of (2**21, 4) were
    counted 1.2e6 units and ended in a raw MemoryError after 7.5-10.8 CPU-s. Each is converted once and counted in
    turn; a few are accepted as before."""
    from fusion.scenarios.infrared_radar import late_means

    K = 2**21
    r = _ArrayOnly(np.ones((K, 4)))
    _refused_fast(late_means, {f"m{i}": r for i in range(400)}, np.linspace(0, 10, K),
                  match=r"^rmse \(its methods and scans\) ask")
    small = late_means({"a": _ArrayOnly(np.ones((101, 4)))}, np.linspace(0, 10, 101))
    assert small["a"]["x (m)"] == 1.0


def test_fuse_tracks_counts_a_small_states_run_as_four_entries():
    """D1: a run's step of a 1- or 2-state track costs about what a 4-state one does (a strided read and write: 25-80
    ns measured at n = 1, 2, about 100 ns estimated by the fuzz at 1e6 runs), but was counted 18 ns an entry: the
    edge of 1e6 runs at n = 2, 275 steps, ran an estimated 28-30 CPU-s. Now 138 steps accepted, 139 refused; 1 run of
    a 4-state track keeps its edge (test_budget43)."""
    from fusion.filtering.tracks import _fuse_tracks_work

    for rule in ("ci", "convex", "split", "printed"):
        for n in (1, 2):
            _fuse_tracks_work(138, 10**6, n, rule, "a and b")
            with pytest.raises(ValueError, match=r"^a and b ask .*work"):
                _fuse_tracks_work(139, 10**6, n, rule, "a and b")
