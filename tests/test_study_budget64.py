"""Chapter 05's composite studies sum their parts at the entry of the public function that runs them (fuzz 57a C2-C6).

``fig6_periods`` checked its two periods one at a time (16,000 runs ran T = 0.5 s for 8.4 CPU-s, then were refused by
T = 0.2 s naming ``runs and T``); ``sensitivity_table`` checked ``rule_errors``' budget only after each simulation
(160,000 runs refused after 9.6 CPU-s naming ``sim`` and ``rules``) and never summed its periods (8 periods at 83,000
runs ran 55.9 CPU-s); ``arch_study`` / ``architecture_studies`` checked each architecture study alone (6,738 runs ran
68.9 CPU-s); ``paired_studies`` had no budget of its own (1,202 weights at 2,000 runs ran 82.5 CPU-s, 30,000 runs a
raw MemoryError). Each test stops a call at its first draw (``numpy.random.default_rng`` raises), so an accepted edge
runs no work: the budget alone decides, and a refusal comes before any draw, in under 1 CPU-s.
"""

from __future__ import annotations

import time

import pytest

from test_study_budget61 import _accepts, _edge, _reaches_the_draw, _refused_first, no_draw  # noqa: F401


def _refused_by(call, names: str) -> str:
    t0 = time.process_time()
    with pytest.raises(ValueError, match="^" + names + " ask for studies beyond the budget, refused before any study"
                       ) as e:
        call()
    assert time.process_time() - t0 < 1
    return str(e.value)


def test_fig6_periods_sums_its_periods(no_draw):
    from fusion.book._study_budget import studies_first
    from fusion.book.chapters import ci
    from fusion.book.chapters.ci import studies as S

    message = _refused_first(lambda: ci.fig6_periods(3, 16_000))   # C2: ran T = 0.5 s, then refused naming T
    assert " T " not in message.split(":")[0]
    edge = _edge(_accepts(lambda r: studies_first(S._fig6_parts(r), "runs")), hi=16_000)
    _reaches_the_draw(lambda: ci.fig6_periods(3, edge))
    _refused_first(lambda: ci.fig6_periods(3, edge + 1))
    for factor in (1, 3, 10):   # the notebook's runs and the reseeding sweep's (ci-fig6-foa-vs-grid at 10x)
        _reaches_the_draw(lambda: ci.fig6_periods(3, factor * S.LEDGER_RUNS))


def test_sensitivity_table_counts_its_readings_and_sums_its_periods(no_draw):
    from fusion.book.chapters import ci
    from fusion.book.chapters.ci import infrared as I

    names = "periods, runs and duration"
    _refused_by(lambda: ci.sensitivity_table([0.1], 1, 160_000), names)   # C3: refused by rule_errors after 9.6 s
    periods = [0.1001 + 1e-4 * i for i in range(8)]
    _refused_by(lambda: ci.sensitivity_table(periods, 1, 83_000), names)  # C4: accepted, 55.9 CPU-s
    _refused_by(lambda: ci.sensitivity_table(periods, 1, 83_000 // 8), names)   # each period within, the sum not
    edge = _edge(_accepts(lambda r: I._sensitivity_budget([0.1], r, 10.0)), hi=160_000)
    _reaches_the_draw(lambda: ci.sensitivity_table([0.1], 1, edge))
    _refused_by(lambda: ci.sensitivity_table([0.1], 1, edge + 1), names)
    # a period given in ``known`` is not simulated, so not counted
    known = {0.1: {"azimuth (mrad)": 1.0, "x (m)": 1.0, "y (m)": 1.0}}
    _reaches_the_draw(lambda: ci.sensitivity_table([0.1, 0.5], 1, edge + 1, known=known))
    # the notebook's call: four periods (0.1 s known) at the chapter's runs
    _reaches_the_draw(lambda: ci.sensitivity_table((0.02, 0.05, 0.1, 0.5), 1, ci.LEDGER_RUNS, 10.0, known=known))


def test_architecture_studies_sum_both_pairs(no_draw):
    from fusion.book.chapters import ci
    from fusion.book.chapters.ci import studies as S

    message = _refused_first(lambda: ci.arch_study(1, 6_738))   # C5: accepted, 68.9 CPU-s
    from fusion.book.chapters.ci.architecture import _arch_budget
    assert "STUDY_WORK: the reseeding sweep's primary of ci-fig4-convex-part" in message
    edge = _edge(_accepts(lambda r: _arch_budget(1.0, r, r, 2, "runs")), hi=6_738)
    _reaches_the_draw(lambda: ci.arch_study(1, edge))
    _refused_first(lambda: ci.arch_study(1, edge + 1))
    # the bare function refuses by its own arguments, its further weights counted
    Q, R1, R2 = ci.printed_covariances()
    _refused_by(lambda: ci.architecture_studies(R1, R2, Q, (1, 2), ci.W_PUB, edge + 1, edge + 1),
                "runs, nees_runs, T and fixed_omegas")
    _reaches_the_draw(lambda: ci.architecture_studies(R1, R2, Q, (1, 2), ci.W_PUB, edge, edge))
    _refused_by(lambda: ci.architecture_studies(R1, R2, Q, (1, 2), ci.W_PUB, edge, edge,
                                                fixed_omegas=(0.1, 0.5, 0.7)), "runs, nees_runs, T and fixed_omegas")
    for factor in (1, 3, 10):   # the notebook's runs and the reseeding sweep's (ci-fig4-convex-part at 10x)
        _reaches_the_draw(lambda: ci.arch_study(1, factor * S.LEDGER_RUNS))


@pytest.fixture(scope="module")
def pairs():
    from fusion.book.chapters.ci import studies as S

    return S.unequal_pair(S.SEED), S.aniso_pair(S.SEED, 100)


def test_paired_studies_has_its_own_budget(pairs, no_draw):
    from fusion.book.chapters import ci
    from fusion.book.chapters.ci import studies as S

    Q, R1, R2 = ci.printed_covariances()
    names = r"runs, fig6_omegas, T and aniso \(its runs\)"

    def call(runs, omegas=(ci.W_PUB, ci.W_GRID)):
        return ci.paired_studies(R1, R2, Q, (ci.W_PUB, ci.W_GRID), *pairs, runs=runs, seeds=(1, 2, 3), weight_seed=4,
                                 fig6_omegas=omegas)

    many = (ci.W_PUB, ci.W_GRID, *(0.01 + 0.0008 * i for i in range(1_200)))
    _refused_by(lambda: call(2_000, many), names)   # C6: accepted, 82.5 CPU-s
    _refused_by(lambda: call(30_000), names)        # C6: a raw MemoryError after 20.8 CPU-s
    _refused_by(lambda: call(15_000), names)        # C6: accepted, 30 CPU-s
    _reaches_the_draw(lambda: call(2 * S.LEDGER_RUNS))
    _reaches_the_draw(lambda: call(10 * S.LEDGER_RUNS))   # paired_study's own runs at the sweep's 10x


def test_fruit_fly_step_targets_sum_their_studies(no_draw):
    # the audit of the chapter after fuzz 57a: each rule's batch was checked alone and the targets never summed.
    # Fuzz 59a C1: batch_budget charged a loop of seeds + 200 steps of 4 x seeds x 30 units, quadratic in the seeds, so
    # the study refused 1,931 seeds (it runs ~2 CPU-s) and four targets 1,000 seeds (2.2-3.9 CPU-s). Linear now, 8 units a
    # fly and generation (measured: the study 4.7 CPU-s at 8,000 seeds), so the edges are some 10,400 and 2,600 seeds.
    from fusion.book.chapters import ci
    from fusion.book.chapters.ci.fruit_fly_step import _step_budget
    from fusion.optimise.scalar import batch_budget

    study = _edge(_accepts(lambda s: _step_budget(s, 1, "seeds")))
    four = _edge(_accepts(lambda s: _step_budget(s, 4, "targets and seeds")))
    assert 9_000 < study < 12_000 and 2_000 < four < 3_000
    batch_budget(study + 1, 30, 200, "seeds")   # each batch inside alone: its two rules' batches are summed
    _refused_by(lambda: ci.fruit_fly_step_study(study + 1, 0.8, 0), "seeds")
    _refused_by(lambda: ci.fruit_fly_step_targets(0, (0.1, 0.2, 0.3, 0.4), four + 1), "targets and seeds")
    _reaches_the_draw(lambda: ci.fruit_fly_step_study(study, 0.8, 0))
    _reaches_the_draw(lambda: ci.fruit_fly_step_targets(0, (0.1, 0.2, 0.3, 0.4), four))
    _reaches_the_draw(lambda: ci.fruit_fly_step_targets(0))   # the notebook's call: four targets, 100 seeds
    _reaches_the_draw(lambda: ci.fruit_fly_step_study(1_931, 0.8, 0))   # fuzz 59a C1: refused, ~2 CPU-s
    _reaches_the_draw(lambda: ci.fruit_fly_step_targets(0, ci.FRUIT_FLY_STEP_TARGETS, 1_000))   # refused, 2.2-3.9


def test_weight_pair_sums_its_scenario_and_searches(no_draw):
    from fusion._limits import MAX_WORK
    from fusion.book.chapters import ci
    from fusion.scenarios.two_sensor.case import _scenario_budget
    from fusion.scenarios.two_sensor.weights import _CI_COSTS, _over_seeds_budget

    Q, R1, _ = ci.printed_covariances()
    seeds, runs = list(range(1_100)), 32_000
    _refused_by(lambda: ci.weight_pair(R1, R1 / 9, Q, 2, 1, 2, seeds, runs=runs), "runs, T and fruit_fly_seeds")
    batch, scenario = _over_seeds_budget(len(seeds), 1001, 30, 200, 4, _CI_COSTS, "s"), _scenario_budget(runs, 261, "r")
    assert max(batch, scenario) < MAX_WORK < batch + scenario   # each alone inside, the sum not
    # fuzz 59a C1: the searches were counted by batch_budget, without their 4 x 4 objective: 2,500 seeds were accepted,
    # the scenario ran, then fruit_fly_over_seeds refused them
    _refused_by(lambda: ci.weight_pair(R1, R1 / 9, Q, 2, 1, 2, list(range(2_500)), runs=1_000),
                "runs, T and fruit_fly_seeds")
    _reaches_the_draw(lambda: ci.weight_pair(R1, R1 / 9, Q, 2, 1, 2, list(range(1_000)), runs=1_000))
    _reaches_the_draw(lambda: ci.weight_pair(R1, R1 / 9, Q, 2, 1, 2, list(range(100)), runs=10 * ci.LEDGER_RUNS))


def test_ir_readings_sum_what_they_run(no_draw):
    # the audit after fuzz 57a: every simulation, tracker, reader and bound of ir_readings was checked alone as it came
    # (its entry counted one study), so a later reader or tracker refused after the simulations had run
    from fusion.book.chapters import ci
    from fusion.book.chapters.ci import infrared_readings as R

    names = "T, duration, runs and scaled_axes"
    _refused_by(lambda: ci.ir_readings(0.1, 1, 6_000), names)           # every entry check passed: it ran
    _refused_by(lambda: ci.ir_readings(0.00025, 1, 1), names)           # 40,001 scans: the Cartesian tracker's refusal
    edge = _edge(_accepts(lambda r: R._readings_budget(0.1, 10.0, r, 1, names)), hi=6_000)
    _reaches_the_draw(lambda: ci.ir_readings(0.1, 1, edge))
    _refused_by(lambda: ci.ir_readings(0.1, 1, edge + 1), names)
    _refused_by(lambda: ci.ir_readings(0.1, 1, edge, scaled_axes=("x", "y")), names)   # the scaled axis counted
    for factor in (1, 3, 10):   # the notebook's runs and the reseeding sweep's (ci-fig10-x-below-y at 10x)
        _reaches_the_draw(lambda: ci.ir_reading_study(1, factor * ci.LEDGER_RUNS))


@pytest.fixture(scope="module")
def readings():
    from fusion.book.chapters import ci

    return ci.ir_readings(0.1, 1, 3)


def test_ir_sigma_band_sums_its_levels(readings, monkeypatch):
    from fusion.book.chapters import ci
    from fusion.scenarios import infrared_radar as ir
    from test_study_budget61 import Ran

    def ran(*args, **kwargs):
        raise Ran

    monkeypatch.setattr(ir, "cartesian_tracks", ran)
    names = r"scan \(with the runs and scans of readings\)"
    _refused_by(lambda: ci.ir_sigma_band(readings, [1.0 + 1e-3 * i for i in range(2_000)]), names)
    _reaches_the_draw(lambda: ci.ir_sigma_band(readings))   # the default scan: stopped at its first tracker


def test_record_evidence_sums_the_studies_it_reads(no_draw):
    # the audit after fuzz 57a: record_evidence ran its studies one by one, so 4,700 runs of ci-fig4-convex-part ran
    # both architecture studies (within their summed entry) before the paired study refused the runs
    from fusion.book.chapters import ci
    from fusion.book.chapters.ci import studies as S

    message = _refused_first(lambda: ci.record_evidence("ci-fig4-convex-part", seed=1, runs=4_700))
    assert message.count("ask for studies beyond the budget") == 1   # said once, not once a nested sum
    for rid in S._STOCHASTIC:   # the reseeding sweep's 10x of each record, and the notebook's runs
        for runs in (S.LEDGER_RUNS, 10 * S.LEDGER_RUNS):
            _reaches_the_draw(lambda: ci.record_evidence(rid, seed=1, runs=runs))


def test_table1_by_scale_weighs_its_scales(monkeypatch):
    # the audit after fuzz 57a: chapter 01's scales were looped over without a budget (69-89 us a scale measured)
    import numpy as np

    from fusion.book.chapters.ofs import reproduction
    from test_study_budget61 import Ran

    def ran(*args, **kwargs):
        raise Ran

    monkeypatch.setattr(reproduction.rd, "fuse_epochs", ran)
    _refused_by_work = time.process_time()
    with pytest.raises(ValueError, match="^scales ask for 1e"):
        reproduction.table1_by_scale(np.linspace(1.0, 2.0, 100_001))
    assert time.process_time() - _refused_by_work < 1
    with pytest.raises(Ran):   # the edge, accepted, stopped at its first scale
        reproduction.table1_by_scale(np.linspace(1.0, 2.0, 100_000))
