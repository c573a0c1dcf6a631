"""Swaps of two same-shaped results for different roles (issue 35's class "swaps of two same-shaped results that no
object records"): each producer's result records what tells its role apart, and the reader refuses a result in
another's place (swapped, one twice, of other runs or settings), naming the argument.

Small producers' calls only (the file stays under 3 CPU-s)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from fusion.book.chapters import ci

STEPS, RUNS = 30, 3


@pytest.fixture(scope="module")
def nees_case():
    Q, R1, R2 = ci.printed_covariances()
    x0 = np.array([0.0, 10.0, 0.0, 5.0])
    st = {s: ci.nees_per_step(np.random.default_rng(1), Q, R1, R2, x0, STEPS, RUNS, random_velocity=s)
          for s in (False, True)}
    return Q, R1, R2, x0, st, ci.split_ci_exactness(Q, R1, 1.0, STEPS)


def _refused(name, f, *args):
    with pytest.raises(ValueError, match=name):
        f(*args)


def test_nees_per_step_records_its_runs(nees_case):
    Q, R1, R2, x0, st, ex = nees_case
    assert st[False].random_velocity is False and st[True].random_velocity is True
    assert st[False].runs == RUNS and st[False].stream == st[True].stream
    assert isinstance(ex, ci.SplitExactness) and ex.n_steps == STEPS
    # the pair of one study is read as before (a mapping of rule -> NEES per step)
    assert ci.nees_start_numbers(st[False], st[True], RUNS, ex)["ci_nps_runs"] == RUNS
    assert ci.nees_start_table(dict(st[False]), dict(st[True]), RUNS).shape[0] == len(st[False])


def test_nees_starts_swapped_or_twice_refused(nees_case):
    *_, st, ex = nees_case
    _refused("true_start", ci.nees_start_numbers, st[True], st[False], RUNS, ex)
    _refused("random_start", ci.nees_start_table, st[False], st[False], RUNS)
    _refused("true_start", ci.nees_start_table, st[True], st[True], RUNS)


def test_nees_runs_of_another_seed_or_setting_refused(nees_case):
    Q, R1, R2, x0, st, ex = nees_case
    other_seed = ci.nees_per_step(np.random.default_rng(2), Q, R1, R2, x0, STEPS, RUNS, random_velocity=True)
    _refused("random_start", ci.nees_start_table, st[False], other_seed, RUNS)
    other_r = ci.nees_per_step(np.random.default_rng(1), Q, R1, R2 / 9, x0, STEPS, RUNS, random_velocity=True)
    _refused("random_start.*R2", ci.nees_start_numbers, st[False], other_r, RUNS, ex)
    _refused("runs", ci.nees_start_table, st[False], st[True], RUNS + 1)
    _refused("T", ci.nees_start_table, st[False], st[True], RUNS, 0.5)


@pytest.mark.parametrize("case", [dict(T=2.0), dict(n_steps=STEPS + 1), dict(R=4.0), dict(Q=4.0), dict(t_steady=10.0)])
def test_nees_exactness_of_another_case_refused(nees_case, case):
    Q, R1, R2, x0, st, ex = nees_case
    other = dataclasses.replace(ex, **{k: (getattr(ex, k) * v if k in ("R", "Q") else v) for k, v in case.items()})
    _refused("exact", ci.nees_start_numbers, st[False], st[True], RUNS, other)


# --- chapter 01: closing_numbers' two studies, told apart by the noise levels a PairedStudy records ---

@pytest.fixture(scope="module")
def ofs_case():
    from fusion.book.chapters import ofs
    from fusion.book.ledger import Comparison

    c = Comparison(np.arange(100.0), np.arange(100.0) + 1, "A", "B", "less", "m")
    judged = {("yang-fig4-unaffected", "equal-noise"): c, ("yang-weights-reasonable", "primary"): c,
              ("yang-weights-reasonable", "failure"): c, ("yang-membership-free", "scale"): c}
    return ofs, ofs.study(0, 2), ofs.study(0, 2, "equal"), ofs.weight_study(0, 2), judged


def test_paired_study_records_its_noise(ofs_case):
    ofs, hs, eq, ws, judged = ofs_case
    assert np.array_equal(hs.sigma, np.broadcast_to(np.asarray(ofs.NOISE["unequal"], float), (10,)))
    assert np.array_equal(eq.sigma, np.ones(10))
    from fusion.book.tables import rounded

    assert ofs.closing_numbers(hs, eq, ws, judged, 0.05)["ofs_keep_hs"] == rounded(hs.set_size.mean(), 2)


def test_closing_studies_swapped_or_twice_refused(ofs_case):
    ofs, hs, eq, ws, judged = ofs_case
    _refused("study_hs", ofs.closing_numbers, eq, hs, ws, judged, 0.05)
    _refused("study_eq", ofs.closing_numbers, hs, hs, ws, judged, 0.05)
    _refused("study_hs", ofs.closing_numbers, eq, eq, ws, judged, 0.05)
    _refused("study_hs", ofs.closing_numbers, ofs.study(0, 2, "geometric-2"), eq, ws, judged, 0.05)


def test_mc_table_study_beside_another_noise_sds_refused(ofs_case):
    ofs, hs, eq, *_ = ofs_case
    sds = {"hs": np.asarray(ofs.NOISE["unequal"]), "eq": 1.0}
    assert not ofs.mc_table({"hs": hs, "eq": eq}, sds).empty
    _refused(r"sigmas\['hs'\]", ofs.mc_table, {"hs": eq, "eq": hs}, sds)
    _refused(r"sigmas\['eq'\]", ofs.mc_table, {"hs": hs, "eq": eq}, {"hs": sds["hs"], "eq": 2.0})


# --- chapter 06: two one-exchange networks under each other's key, told apart by the scenario each study records ---

def test_premise_networks_under_each_others_key_refused():
    from fusion.book.chapters import chernoff as chc
    from fusion.scenarios.fusion_networks import Network, premise_scenarios, redundancy_scenarios, run_network_study

    designed = premise_scenarios() | redundancy_scenarios()
    small = {k: dataclasses.replace(designed[k], n_particles=40, n_samples=40, n_components=2, em_iterations=2,
                                    stages=1) for k in (Network.UNEQUAL, Network.RELAY)}
    st = {k: run_network_study(sc, 3, 2) for k, sc in small.items()}
    assert "chf_pr_unequal_mix_mean" in chc.premise_robust_values(st, "two runs: a test")
    swapped = {Network.UNEQUAL: st[Network.RELAY], Network.RELAY: st[Network.UNEQUAL]}
    for f in (chc.premise_robust_values, chc.premise_values):
        _refused(r"studies\['unequal'\]", f, swapped, "two runs: a test")
    _refused(r"studies\['relay'\]", chc.premise_robust_values, {Network.RELAY: st[Network.UNEQUAL]}, "a test")


# --- chapter 06: guarded_runs' root seed, checked against the truth each run draws first from its own stream ---

def test_guarded_runs_of_another_seed_or_order_refused():
    from fusion.book.chapters import chernoff as chc
    from fusion.scenarios import range_bearing as dist

    sc = dist.RangeBearingScenario(frames=3, n_particles=40, n_samples=40, n_central=80, em_iterations=2)
    runs = dist.monte_carlo(sc, 5, 2, workers=1)
    assert len(chc.guarded_runs(runs, sc, 5, workers=1)) == 2
    _refused("seed", chc.guarded_runs, runs, sc, 6, 1)
    _refused("seed", chc.guarded_runs, runs[::-1], sc, 5, 1)


# --- decided: documented, not recorded (the reader takes a plain table) ---

def test_unrecorded_roles_are_documented():
    assert "records neither ``sigma`` nor ``delta0``" in ci.pcrb_numbers.__doc__


# --- chapter 05: paired_numbers' three pairs, told apart by the pair each PairedStudies field records ---

def test_paired_studies_fields_record_their_pair_and_swaps_are_refused():
    from fusion.scenarios import two_sensor

    Q, R1, R2 = ci.printed_covariances()
    sc = two_sensor.two_sensor_scenario(R1, R2, Q, np.random.default_rng(0), runs=3, T=8.0)
    runs = {m: np.full(3, 10.0 + i) for i, m in enumerate(two_sensor.StudyMethod)}
    ps = ci.PairedStudies(runs=3, seeds=(1, 2, 3), sc=sc, paired=runs, paired_fig6={ci.W_PUB: np.ones(3),
                          ci.W_GRID: np.ones(3)}, paired_random=np.ones(3), paired_u=runs, omega_u=(0.5,),
                          paired_an=runs)
    assert (ps.paired.role, ps.paired.seed, ps.paired_u.role, ps.paired_an.role) == ("identical", 1, "unequal", "aniso")
    args = (np.ones(3), None, 0.0, 1.0, 3)
    _refused("paired_u", ci.paired_numbers, ps.paired, ps.paired, *args, ps.paired_an, [0.5])
    _refused("paired ", ci.paired_numbers, ps.paired_u, ps.paired, *args, ps.paired_an, [0.5])
    _refused("paired_a", ci.paired_numbers, ps.paired, ps.paired_u, *args, ps.paired, [0.5])
    with pytest.raises(TypeError, match="ai"):   # the pairs in their places: the next check (ai) is reached
        ci.paired_numbers(ps.paired, ps.paired_u, *args, ps.paired_an, [0.5])


def test_premise_studies_refuses_a_designed_network_under_another_key_as_its_readers_do():
    """Fuzz 31b C2: the producer took a designed network's scenario under another network's key, and every premise
    reader then refused its result; one rule now refuses it at the producer, naming ``scenarios[key]``."""
    import dataclasses

    from fusion.book.chapters import chernoff as chc
    from fusion.scenarios.fusion_networks import Network, premise_scenarios, redundancy_scenarios
    designed = premise_scenarios() | redundancy_scenarios()
    with pytest.raises(ValueError, match=r"^scenarios\['chain'\] holds the network 'unequal'"):
        chc.premise_studies(3, 2, {**designed, Network.CHAIN: designed[Network.UNEQUAL]})
    renamed = dataclasses.replace(designed[Network.UNEQUAL], name="test: fully connected")
    chc.premise._check_scenarios({**designed, Network.CHAIN: renamed})   # a test's own scenario: not checked
