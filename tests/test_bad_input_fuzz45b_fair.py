"""Fuzz 45b (the book layer): the equal-weight optimal set's n x n membership counted (C5), the fair study's methods
weighed by their own cost (C4), the designed networks read once (C1) and a refusal caused by ``more`` naming it (C3)."""

from __future__ import annotations

import time

import numpy as np
import pytest

from fusion.book.chapters import ofs_fair
from fusion.readings.robust import robust_fuse


def _refused_fast(f, match: str, limit: float = 1.0) -> None:
    t0 = time.process_time()
    with pytest.raises(ValueError, match=match):
        f()
    assert time.process_time() - t0 < limit


# --- C5 ------------------------------------------------------------------------------------------------------------

def test_c5_uniform_set_kernel_refused_by_x_before_any_pair():
    # one epoch: its n x n distances, PAIR_WORK units a pair (7,071 readings inside, 7,072 beyond); 100,000 readings
    # asked for a 74.5 GiB array (a MemoryError), 30,000 for 6.7 GiB
    for n in (7_072, 30_000, 100_000):
        _refused_fast(lambda: robust_fuse(np.arange(float(n)), "uniform_set"), r"^x \(.*n x n pairs")
    robust_fuse(np.arange(1000.0), "uniform_set")  # (the edge, 7,071, takes ~1 CPU-s: checked by the budget below)
    from fusion.readings.robust import _robust_limit
    _robust_limit(1, 7_071, "uniform_set", "x")
    with pytest.raises(ValueError, match="^x"):
        _robust_limit(1, 7_072, "uniform_set", "x")
    z = 900 + np.random.default_rng(0).standard_normal((1, 1, 30_000))
    _refused_fast(lambda: ofs_fair.fair_errors(z, np.ones(30_000), methods=("uniform_set",)), r"^z \(")


def test_c5_fair_study_refuses_the_n_squared_kernel_at_entry(monkeypatch):
    # fuzz 45b C5b: 10,000 sensors x 80 runs counted 2.4e6 linear units and ran 16 CPU-s; refused before the draws
    def no_draws(*a, **k):
        raise AssertionError("drawn before the refusal")
    monkeypatch.setattr(np.random, "default_rng", no_draws)
    for method in ("uniform_set", "optimal_fusion_set"):
        _refused_fast(lambda: ofs_fair.fair_study(0, n_runs=80, n_samples=1, n_sensors=10_000, sizes=(1.0,), counts=(),
                                                  spreads=(), opposite=(), methods=(method,)), r"^n_runs, n_samples")
    # the pairs counted at their measured weight: 1,000 sensors, one point, is accepted at 50 runs, not at 51
    ofs_fair._budget((50, 1, 1000), 1, ("uniform_set",), ("a", "b"))
    with pytest.raises(ValueError, match="^b"):
        ofs_fair._budget((51, 1, 1000), 1, ("uniform_set",), ("a", "b"))


# --- C4 ------------------------------------------------------------------------------------------------------------

def test_c4_fair_study_weighs_each_method_by_its_cost(monkeypatch):
    # huber at the edge of the average weight (333 points x 1,000 runs: 9.99e8 units at 3 a reading) ran 72 CPU-s;
    # its own weight refuses it before the draws, and accepts 100 runs (7.3 CPU-s measured)
    sizes = tuple(float(s) / 10 for s in range(330))
    pts = len(sizes) + 3
    monkeypatch.setattr(np.random, "default_rng", lambda *a, **k: (_ for _ in ()).throw(AssertionError("drawn")))
    _refused_fast(lambda: ofs_fair.fair_study(0, n_runs=1000, n_samples=100, sizes=sizes, counts=(2,), spreads=(2,),
                                              opposite=(2,), methods=("huber",)), r"^n_runs, n_samples")
    ofs_fair._budget((100, 100, 10), pts, ("huber",), ("a", "b"))
    with pytest.raises(ValueError, match="^b"):
        ofs_fair._budget((101, 100, 10), pts, ("huber",), ("a", "b"))
    # a cheap method keeps a larger edge than the average gave (mean: 2 units a reading)
    ofs_fair._budget((20_000, 100, 10), 23, ("mean",), ("a", "b"))


def test_c4_the_books_fair_studies_stay_inside():
    from fusion.book.chapters.ofs import studies
    from fusion.book.chapters.ofs.settings import N_RUNS
    pts = sum(studies._FAIR_POINTS.values())
    ofs_fair._budget((100, 100, 10), pts, ofs_fair.FAIR_METHODS, ("runs", "runs"))  # the notebook's fair(SEED)
    ofs_fair._budget((N_RUNS, 100, 10), pts - studies._FAIR_POINTS["opposite"], studies._WEIGHT_METHODS,
                     ("runs", "runs"))  # the ledger's fair_weights at the chapter's runs


# --- C1, C3 --------------------------------------------------------------------------------------------------------

def _designed():
    from fusion.scenarios.fusion_networks import premise_scenarios, redundancy_scenarios
    return premise_scenarios() | redundancy_scenarios()


def test_c1_premise_studies_runs_the_networks_it_counted(monkeypatch):
    # a Mapping whose __getitem__ gave the designed networks to the entry's count (9e6 units at 2 runs) and 400-frame
    # copies to the run (2.4e9 units, ~70 CPU-s): read once at entry, what it gave is what is counted and run
    import dataclasses
    from collections.abc import Mapping
    from fusion.book.chapters.chernoff import premise as P
    from fusion.book.chapters.chernoff import studies as S

    small = _designed()
    big = {k: dataclasses.replace(v, frames=400) for k, v in small.items()}

    class Lying(Mapping):
        reads = 0

        def __getitem__(self, k):
            Lying.reads += 1
            return small[k] if Lying.reads <= len(small) else big[k]

        def __iter__(self):
            return iter(small)

        def __len__(self):
            return len(small)

    ran = []
    monkeypatch.setattr(P, "_network_study", lambda sc, *a, **k: ran.append(sc.frames))
    P.premise_studies(0, 2, scenarios=Lying())
    assert ran == [small[k].frames for k in P.PREMISE_NETWORKS]
    Lying.reads = 0
    cached = []
    monkeypatch.setattr(S, "_premise", lambda seed, runs, scs: cached.append(scs))
    S.premise_study(0, 2, scenarios=Lying())   # the cached entry: its networks are those counted
    assert [sc.frames for _, sc in cached[0]] == [small[k].frames for k, _ in cached[0]]


def test_c3_a_refusal_caused_by_more_names_more():
    from fusion.book.chapters.chernoff.premise import Network, premise_studies
    for runs in (7_000, 200_000):   # the work budget's refusal, then the memory budget's
        _refused_fast(lambda: premise_studies(0, 2, more={Network.FEEDBACK: runs}), r"^runs, scenarios and more[ (]")
    with pytest.raises(ValueError, match=r"^runs and scenarios[ (]"):   # runs alone asked for it
        premise_studies(0, 10**6)
