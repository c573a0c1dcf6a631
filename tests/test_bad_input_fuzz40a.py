"""Fuzz 40a (entry budgets of the scenario studies): every parameter that scales a study's cost is counted, and what
a callee would refuse is refused at the caller's entry, naming the caller's arguments, before any work (C1-C6, C8,
D2, D3; the cost weights are measured, see each function's comment)."""

from __future__ import annotations

import dataclasses
import time

import numpy as np
import pytest

from fusion._limits import MAX_WORK


def _refused_fast(f, *args, match: str, **kw) -> None:
    t = time.process_time()
    with pytest.raises(ValueError, match=match):
        f(*args, **kw)
    assert time.process_time() - t < 1.0


def _unresolved_network():
    import fusion.scenarios.fusion_networks as fn

    sc = fn.premise_scenarios()[fn.Network.NON_GAUSSIAN]
    return dataclasses.replace(sc, nodes=tuple(dataclasses.replace(n, sigma_r=n.sigma_r * 0.05,
                                                                   sigma_theta=n.sigma_theta * 0.05) for n in sc.nodes))


def test_run_network_study_refuses_an_unresolved_grid_before_the_pipelines(monkeypatch):
    """C1: the grid's KL check needs only m0 and the first frame's readings; it ran after the whole study (11-15 CPU-s
    at 2,000 runs). A pipeline step that fails marks work done after the check."""
    import fusion.scenarios.fusion_networks as fn

    def no_pipeline(*args, **kw):
        raise AssertionError("the pipelines ran before the grid's check")

    monkeypatch.setattr(fn, "_local_update", no_pipeline)
    _refused_fast(fn.run_network_study, _unresolved_network(), 2, 100, match=r"^sc: the grid of the exact posterior")


def test_run_network_study_refuses_at_the_first_unresolved_block(monkeypatch):
    """C1: the check runs block by block (GRID_BLOCK runs), so an unresolved first block stops the grid there."""
    import fusion.scenarios.fusion_networks as fn

    calls = []
    grid = fn._grid_posterior
    monkeypatch.setattr(fn, "_grid_posterior", lambda *a, **kw: calls.append(1) or grid(*a, **kw))
    with pytest.raises(ValueError, match=r"^sc: the grid of the exact posterior"):
        fn.run_network_study(_unresolved_network(), 2, 20 * fn.GRID_BLOCK)
    assert len(calls) <= len(_unresolved_network().nodes)


def test_linearised_errors_counts_frames_and_sensors():
    """C2: no budget at all (100,000 frames ran 31 CPU-s); the edge of the default 3 sensors is accepted by the rule,
    one frame more refused at once, and a scenario of 1,200 sensors is refused at one frame (O(n**3) a frame)."""
    from fusion._limits import work
    from fusion.scenarios.range_bearing import RangeBearingScenario, linearised_errors
    from fusion.scenarios.range_bearing_bounds import _linearised_frame_units

    units = _linearised_frame_units(3)
    edge = MAX_WORK // units
    work((edge,), "sc", weight=units)  # accepted: about 7 CPU-s measured a frame at a time
    _refused_fast(linearised_errors, RangeBearingScenario(frames=edge + 1), match=r"^sc \(its frames and sensors\)")
    ring = tuple((5000.0 + 1000.0 * np.cos(a), 7000.0 + 1000.0 * np.sin(a))
                 for a in np.linspace(0.0, 2 * np.pi, 1200, endpoint=False))
    _refused_fast(linearised_errors, RangeBearingScenario(sensors=ring, frames=1), match=r"^sc \(its frames and sensors\)")


def test_many_scan_bound_counts_the_paths_scans():
    """C3: no budget on the path's scans K (3e6 ran 22.5 CPU-s, 1e7 a raw MemoryError); the edge is accepted by the
    rules, a longer path refused at once naming path."""
    from fusion._counts import allocation
    from fusion._limits import work
    from fusion.scenarios import _infrared_budget as ib
    from fusion.scenarios import infrared_radar as ir

    edge = min(MAX_WORK // ib._BOUND_SCAN_UNITS, (1 << 28) // (7 * 36))
    work((edge,), "path", weight=ib._BOUND_SCAN_UNITS)
    allocation((edge, 6, 6), "path", arrays=7)
    p = ir.truth(T=100.0 / (edge + 10), duration=100.0)
    assert p.t.size > edge
    _refused_fast(ir.many_scan_bound, p, 1e-4, 0.02, 5.0, match=r"^path \(its scans K\)")


def test_infrared_readers_refuse_at_entry_naming_their_arguments(monkeypatch):
    """C4, C5: rule_errors, cartesian_tracks and cartesian_errors had no budget of their own: a valid simulate() of
    110,000 runs was refused inside position ('angle_est') or fuse_tracks ('a and b') after 9-18 CPU-s. Their
    measured weights are raised here so that a small simulation reaches them: refused before any work."""
    from fusion.scenarios import _infrared_budget as ib
    from fusion.scenarios import infrared_radar as ir

    sim = ir.simulate(np.random.default_rng(1), runs=20)
    tracks = ir.cartesian_tracks(sim)
    heavy = {r: {k: MAX_WORK for k in v} for r, v in ib._READER_UNITS.items()}
    monkeypatch.setattr(ib, "_READER_UNITS", heavy)
    monkeypatch.setattr(ib, "_TRACKS_UNITS", MAX_WORK)
    _refused_fast(ir.rule_errors, sim, match=r"^sim \(its runs and scans\) and rules ask .*work")
    _refused_fast(ir.rmse_by_rule, sim, match=r"^sim \(its runs and scans\) and rules ask .*work")
    _refused_fast(ir.cartesian_tracks, sim, match=r"^sim \(its runs and scans\) ask .*work")
    _refused_fast(ir.cartesian_errors, sim, tracks, match=r"^sim and tracks \(their runs and scans\) and rules ask")


def test_infrared_reader_edges():
    """C4, C5, the bounds: rule_errors with every rule accepts up to its measured edge (work: 270 units a run and
    scan; memory: 13 arrays of 4) and refuses just beyond; a reader's check includes each rule's fuse_tracks rule and
    the (runs, K, 4) input budget of position (one rule of 2.7e6 run-scans was refused by position's after 18 CPU-s)."""
    from fusion.scenarios import _infrared_budget as ib
    from fusion.scenarios import infrared_radar as ir

    from fusion.filtering.tracks import _fuse_tracks_units

    rules = ir._rule_subset(None)
    units = 35 + 25 + 35 + 25 + 150
    fused = sum(_fuse_tracks_units(101, 0, 4, rule) for rule in rules.values())  # their steps, summed (fuzz 41a C2)
    edge = (MAX_WORK - fused) // units // 101
    ib._reader_budget("rule_errors", edge, 101, 4, rules, "sim")
    with pytest.raises(ValueError, match=r"^sim ask .*work"):
        ib._reader_budget("rule_errors", edge + 1, 101, 4, rules, "sim")
    with pytest.raises(ValueError, match=r"^sim ask .*input budget"):  # beyond position's input, inside the work
        ib._reader_budget("rule_errors", (1 << 25) // 404 + 1, 101, 4, {}, "sim")
    with pytest.raises(ValueError, match=r"^sim ask .*work"):  # fuse_tracks' own rule, fuzzy on a 6-state track
        ib._reader_budget("cartesian_errors", 10**7, 1, 6, {ir.IrMethod.FUZZY: "fuzzy"}, "sim")


def test_variance_change_study_counts_its_changes():
    """C6: 60 changes of 400 runs (12 % of the budget at 75 units a draw) ran 37.6 CPU-s: now 10 + 45 units a draw and
    change; the default 3 changes accept 1,724 runs of 1,000 samples of 4 sensors and refuse 1,725 at once."""
    from fusion._limits import work
    from fusion.scenarios.lecture_weighting import variance_change_study

    changes = tuple((f"c{i}", {0: 1.0 + i / 100}) for i in range(60))
    _refused_fast(variance_change_study, runs=400, changes=changes, match=r"^runs, samples, sigma and changes ask")
    work((1_724, 1_000, 4), "runs", weight=10 + 45 * 3)
    _refused_fast(variance_change_study, runs=1_725, match=r"^runs, samples, sigma and changes ask")


def test_late_means_counts_its_methods_and_entries():
    """The class in the scenario modules: late_means read every method's array without counting the methods (one
    array of 2**22 scans given under 8 keys ran 5 CPU-s; 20 us a method): now counted before any conversion."""
    from fusion.scenarios.infrared_radar import late_means

    t = np.linspace(0.0, 10.0, 101)
    a = np.ones((101, 4))
    _refused_fast(late_means, {f"m{i}": a for i in range(340_000)}, t, match=r"^rmse \(its methods\)")
    big = np.ones((2**22, 4))
    _refused_fast(late_means, {f"m{i}": big for i in range(30)}, np.linspace(0.0, 10.0, 2**22),
                  match=r"^rmse \(its methods and scans\)")


def _case(N: int) -> dict:
    return {"big": {"own": tuple(np.linspace(1, 3, N)), "coupling": tuple(np.linspace(0.5, 1.5, N)), "env": 1.5}}


def test_coupling_study_counts_the_sensors_and_runs():
    """C8, D3: the sensors N of a case were not counted (N = 2,000 of 2 runs ran 65 CPU-s), nor the runs (10**7 runs
    were refused by gls's input budget after 5.4 CPU-s); both refused at entry naming the caller's arguments. The
    edge: N = 1,000 with 21 SDs (3.3 CPU-s measured) is accepted by the rule."""
    from fusion._limits import work
    from fusion.scenarios import correlated_sensors as cs

    _refused_fast(cs.coupling_study, _case(2000), runs=2, match=r"^scenarios \(their sensors\), runs and env_grid ask")
    _refused_fast(cs.coupling_study, runs=10**7, match=r"^runs and the sensors of case .*input budget")
    work((cs._coupling_case_units(1000, 2, 21),), "scenarios")
    with pytest.raises(ValueError):
        work((cs._coupling_case_units(1000, 2, 51),), "scenarios")


def test_covariance_refuses_beyond_the_memory_budget():
    """C8's probe: covariance of 20,000 sensors allocated 3.2 GB for 9.3 CPU-s, of 100,000 raised MemoryError."""
    from fusion._counts import allocation
    from fusion.scenarios import correlated_sensors as cs

    allocation((9_459, 9_459), "own", arrays=3)
    _refused_fast(cs.covariance, np.ones(9_460), np.ones(9_460), 1.0, match=r"^own and coupling \(their length N\)")
    _refused_fast(cs.covariance, np.ones(100_000), np.ones(100_000), 1.0, match=r"^own and coupling")


def test_ridge_study_weighs_its_draws():
    """D2: 8e8 normals at one unit ran 22.8 CPU-s; at 2.5 units sum(ms) = 50,000 of 2,000 draws is the edge."""
    from fusion._limits import work
    from fusion.scenarios.lecture_correlated import ridge_study

    work((4, 2_000, 50_000), "ms", weight=2.5)
    _refused_fast(ridge_study, ms=(50_001,), match=r"^ms and draws ask")


def _sets(k: int, **options) -> dict:
    return {f"s{i}": {"method": "optimal_fusion_set", **options} for i in range(k)}


def test_thermocouple_studies_count_their_methods():
    """The class in the scenario modules: each method's fuse_epochs was within its own budget, but the methods were
    not counted (200,000 "mean" methods of 2 runs ran over 60 CPU-s): refused before the draws naming the caller's
    arguments. fix46: the methods are counted at their measured cost (``_EPOCH_UNITS``; fuzz 42b C6 re-measured the
    optimal set, 164 units an epoch of 10 readings, counted 190), so the edges are where the work is: monte_carlo's 10
    optimal sets of 5,000 runs count 9.5e8 (6 ran 6.5 CPU-s), 11 are refused; paired_study fuses each twice (5 sets:
    9.75e8; 6 refused)."""
    from fusion.scenarios import thermocouples as th

    names = r"^n_runs, n_samples, n_sensors and methods ask for .* units of work"
    # "mean" methods of 20 runs: 28,000 units each (8,000 a call, 2,000 epochs of 10 readings); 35,714 accepted
    means = {f"m{i}": {"method": "mean"} for i in range(36_000)}
    assert th._methods_work(20 * 100, 10, list(means.values())[:35_714], "methods") < MAX_WORK
    _refused_fast(th.monte_carlo, 1, 20, means, match=names)
    _refused_fast(th.paired_study, 1, 20, dict(list(means.items())[:18_000]), match=names)
    assert th._methods_work(5_000 * 100, 10, _sets(10), "methods") == 10 * (8_000 + 500_000 * 190)   # accepted
    _refused_fast(th.monte_carlo, 1, 5_000, _sets(11), match=names)
    _refused_fast(th.absolute_errors, np.full((5_000 * 100, 10), 900.0), _sets(11), match=r"^z and methods ask")
    inside = {**_sets(1), **{f"x{i}": {"method": "optimal_fusion_set", "include_self": False} for i in range(2)}}
    assert th._methods_work(5_000 * 100, 10, inside, "methods", fusions=2, per_reading=th._PAIRED_READING) < MAX_WORK
    assert th._methods_work(5_000 * 100, 10, _sets(5), "methods", fusions=2, per_reading=th._PAIRED_READING) < MAX_WORK
    _refused_fast(th.paired_study, 1, 5_000, _sets(6), match=names)


def test_paired_study_counts_each_method_twice_and_the_members_run():
    """fix46 (review 18, point 6): paired_study counted one fusion a method though it fuses each twice (the clean
    epochs, then those the failure changed), and not the default optimal set it runs for the members when only sets
    with options are asked; nor did it check each method's fuse_epochs limits at entry, as monte_carlo does."""
    from fusion.scenarios import thermocouples as th

    names = r"^n_runs, n_samples, n_sensors and methods ask for .* units of work"
    # 5 sets with options, and the members' default set: 6 sets fused twice, 1.17e9 units (5 of them 9.75e8)
    assert th._methods_work(5_000 * 100, 10, _sets(5), "methods", fusions=2, per_reading=th._PAIRED_READING) < MAX_WORK
    _refused_fast(th.paired_study, 1, 5_000, _sets(5, include_self=False), match=names)
    # 6 sets of 4,500 runs: 1.05e9 fused twice (5.1e8 once, as counted before)
    assert th._methods_work(4_500 * 100, 10, _sets(6), "methods") < MAX_WORK / 1.9
    _refused_fast(th.paired_study, 1, 4_500, _sets(6), match=names)
    # fuse_epochs' own limit of one method, before the draws, naming the caller's arguments (as monte_carlo)
    _refused_fast(th.paired_study, 1, 5_001, _sets(1), match=r"^n_runs, n_samples, n_sensors and methods \(10 readings")


def test_thermocouple_method_costs_cover_every_method():
    """Every method fuse_epochs takes has a measured cost in the studies' count."""
    from fusion.readings.fusion_set import METHODS
    from fusion.scenarios import thermocouples as th

    assert set(th._EPOCH_UNITS) == set(METHODS)
