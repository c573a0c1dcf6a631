"""Work budgets weighed by their measured cost (budget35, rule 17): the edge of a count argument is about 10 CPU-s.

Each test counts, never runs the work: the function's first step of work is replaced by one that raises
:class:`Ran`, so a call the budget accepts raises it at once and a call it refuses raises a ValueError naming the
caller's argument before it. The measured costs are in /work/tmp/budget35/table.md.
"""
import numpy as np
import pytest


class Ran(Exception):
    """The call passed its budget and reached its work."""


def _ran(*args, **kwargs):
    raise Ran


X5 = np.array([10.1, 10.3, 9.9, 10.0, 12.0])


def test_parameters_matching_counts_a_fusion_per_grid_point(monkeypatch):
    # ~23 us a grid point (a fusion call), counted 5 us: 2e6 points (about 45 CPU-s) were accepted
    import fusion.book.audit as audit
    monkeypatch.setattr(audit, "fuse_epochs", _ran)
    with pytest.raises(ValueError, match="n_grid"):
        audit.parameters_matching(X5, 10.2, "support_degree", "alpha", 1e-3, 10.0, n_grid=500_000)
    with pytest.raises(Ran):  # the book's grid (400 points) and a 100,000-point one stay accepted
        audit.parameters_matching(X5, 10.2, "support_degree", "alpha", 1e-3, 10.0, n_grid=100_000)


def test_fruit_fly_counts_a_generation_and_a_call_per_candidate():
    # ~22 us a generation: 978,000 generations (about 22 CPU-s) were accepted; ~0.2 us a candidate's own call
    from fusion.optimise.scalar import fruit_fly
    with pytest.raises(ValueError, match="population and iterations"):
        fruit_fly(_ran, np.random.default_rng(0), population=5, iterations=400_000)
    with pytest.raises(ValueError, match="population and iterations"):
        fruit_fly(_ran, np.random.default_rng(0), population=1_000_000, iterations=50)
    with pytest.raises(Ran):  # vectorised, the same candidates are 4 units each
        fruit_fly(_ran, np.random.default_rng(0), population=1_000_000, iterations=50, vectorized=True)
    with pytest.raises(Ran):  # the book's 30 x 200
        fruit_fly(_ran, np.random.default_rng(0), population=30, iterations=200)


def test_fruit_fly_batch_counts_a_generation():
    # ~31 us a generation of two problems: 959,000 generations (about 30 CPU-s) were accepted
    from fusion.optimise.scalar import batch_budget
    rngs = [np.random.default_rng(0), np.random.default_rng(1)]
    from fusion.optimise.scalar import fruit_fly_batch
    with pytest.raises(ValueError, match="rngs, population and iterations"):
        fruit_fly_batch(_ran, rngs, population=5, iterations=400_000)
    batch_budget(1000, 30, 200, "seeds")  # the book's largest batches (30 x 200 a seed) stay accepted


def test_benchmark_weighs_a_reading_by_its_methods(monkeypatch):
    # ~0.43 us a reading (~20 methods): 1.5e6 runs (about 400 CPU-s) were accepted
    from fusion.scenarios.lecture_weighting import readings_benchmark as rbm
    monkeypatch.setattr(rbm, "_snapshot_errors", _ran)
    kw = dict(seeds=(1, 2), samples=20, levels=(0.0, 900.0), sigma=(0.5, 1.0, 1.5, 2.0))
    with pytest.raises(ValueError, match="^seeds, levels, faults, runs, samples and sigma"):
        rbm.benchmark(runs=120_000, **kw)  # beyond its STUDY_WORK entry (3e9; 40,000 were refused by MAX_WORK)
    with pytest.raises(Ran):  # the chapter's benchmark (3 seeds of 500 runs x 100 samples, 5 sensors)
        rbm.benchmark()


@pytest.mark.parametrize("study, runs, names", [("regime_study", 2_100, "runs, samples and sigma"),
                                                 ("variance_change_study", 4_000, "runs, samples, sigma and changes")])
def test_regime_studies_have_a_work_budget(monkeypatch, study, runs, names):
    # no work budget: 10**7 samples of 2 runs (some 400 CPU-s) were accepted; ~5 us and ~0.75 us a draw (the changes
    # of variance_change_study counted too, fuzz 40a C6); regime_study's budget is its STUDY_WORK entry (4e9: 2,000 runs
    # x 1,000 x 4 at 500 units; 700 were refused by MAX_WORK before)
    from fusion.scenarios.lecture_weighting import regime
    monkeypatch.setattr(regime.np.random, "default_rng", _ran)
    with pytest.raises(ValueError, match=f"^{names} ask for"):
        getattr(regime, study)(runs=runs, samples=1000, seed=1)
    with pytest.raises(Ran):  # the chapter's studies (200 and 100 runs x 1,000 samples x 4 sensors)
        getattr(regime, study)(runs=200, samples=1000, seed=1)


def test_per_step_weights_weighs_its_objective(monkeypatch):
    # ~0.45 us a candidate (a 4 x 4 inverse), counted 0.04 us: 160,000 iterations (about 60 CPU-s) were accepted,
    # then refused by fruit_fly_batch's names (rngs)
    from fusion.scenarios import two_sensor
    from fusion.scenarios.two_sensor import weights
    sc = two_sensor.two_sensor_scenario(np.eye(2) * 2500.0, np.eye(2) * 2500.0, np.diag([0.0, 1.0, 0.0, 1.0]),
                                        np.random.default_rng(11), runs=2)
    monkeypatch.setattr(weights, "fruit_fly_batch", _ran)
    for kw in (dict(iterations=100_000, population=3), dict(iterations=3, population=3, n_grid=200_000)):
        with pytest.raises(ValueError, match="^the steps of a, population, iterations and n_grid"):
            weights.per_step_weights(*sc.tracks, 1, **kw)
    with pytest.raises(Ran):  # the chapter's (30 x 200 and 1,001 grid points at each of the source's 261 steps)
        weights.per_step_weights(*sc.tracks, 1)


@pytest.mark.parametrize("fn", ["fruit_fly_over_seeds", "printed_fruit_fly_over_seeds"])
def test_fruit_fly_over_seeds_weighs_its_objective(monkeypatch, fn):
    # ~70 us (250 us printed) an objective call a generation, counted 10 ns: 320,000 generations of the printed
    # objective (about 85 CPU-s) were accepted; a grid of 10**7 of its points (about 24 CPU-s) too
    from fusion.scenarios.two_sensor import weights
    monkeypatch.setattr(weights, "_fly_over_seeds", _ran)
    monkeypatch.setattr(weights, "grid_search", _ran)
    P = np.diag([4.0, 1.0, 2.0, 0.5])
    args = (P[:2, :2], 2 * P[:2, :2]) if fn == "fruit_fly_over_seeds" else (P, 0.5 * P, 2 * P, P)
    grids = [dict(iterations=3, population=3, n_grid=9_000_000)] if fn.startswith("printed") else []
    for kw in [dict(iterations=200_000, population=3)] + grids:
        with pytest.raises(ValueError, match="^seeds, population, iterations and n_grid"):
            getattr(weights, fn)(*args, seeds=[0, 1], **kw)
    with pytest.raises(Ran):  # the chapter's 30 x 200 over 100 seeds (10 for the printed objective)
        getattr(weights, fn)(*args, seeds=np.arange(100 if fn == "fruit_fly_over_seeds" else 10))


def test_belief_study_has_a_work_budget(monkeypatch):
    # no work budget: 10**7 snapshots (some 260 CPU-s) were accepted; ~1.8 us a belief-matrix entry
    from fusion.scenarios.lecture_weighting import belief
    monkeypatch.setattr(belief.np.random, "default_rng", _ran)
    with pytest.raises(ValueError, match="^snapshots and sigma ask for"):
        belief.belief_study(sigma=(0.5, 1.0, 2.0, 4.0), snapshots=400_000)
    with pytest.raises(Ran):  # the chapter's 5,000 snapshots of 4 sensors
        belief.belief_study(sigma=(0.5, 1.0, 2.0, 4.0), snapshots=5000)


def test_minimise_on_simplex_has_a_work_budget():
    # no work budget: n = 50,000 was accepted (SLSQP's n**3 an iteration, hours); about 350 is the edge
    from fusion.optimise.simplex import minimise_on_simplex
    with pytest.raises(ValueError, match="^n ask for"):
        minimise_on_simplex(_ran, 2_000)
    with pytest.raises(ValueError, match="^n ask for"):
        minimise_on_simplex(_ran, 400)
    with pytest.raises(Ran):  # with its gradient, 380 weights stay accepted; the book's are 2 and 3
        minimise_on_simplex(_ran, 380, jac=_ran)




def test_architecture_study_weighs_its_runs(monkeypatch):
    # ~13 us a model run's step, counted 0.5 us: 78,000 NEES runs (about 50 CPU-s) were accepted; fuzz 42b D1: its
    # steps counted too (8.5 us a NEES run's step measured), within its STUDY_WORK entry (3e9): 70,000 are refused
    from fusion.scenarios.two_sensor import architecture
    monkeypatch.setattr(architecture, "_path_and_model_measurements", _ran)
    R = np.diag([2500.0, 900.0])
    Q = np.diag([0.0, 1.0, 0.0, 1.0])
    with pytest.raises(ValueError, match="^runs, nees_runs and T ask for"):
        architecture.architecture_study(np.random.default_rng(0), R, R, Q, runs=2, nees_runs=70_000, T=5.0)
    with pytest.raises(Ran):  # the chapter's 200 + 200 runs at T = 1 s
        architecture.architecture_study(np.random.default_rng(0), R, R, Q, runs=200, nees_runs=200, T=1.0,
                                        printed_omegas=(0.5, 0.3), placement_omegas=(0.5,))


def test_two_sensor_case_weighs_its_steps(monkeypatch):
    # model_truth: ~3.3 us a Python step, 10**7 steps (about 32 CPU-s) accepted; two_sensor_scenario: ~0.5 us a
    # run-step, 250,000 runs (about 33 CPU-s) accepted with a memory budget only
    from fusion.scenarios.two_sensor import case
    F, Q = np.eye(4), np.diag([0.0, 1.0, 0.0, 1.0])
    with pytest.raises(ValueError, match="^n_steps, runs and F ask for"):
        case.model_truth(np.random.default_rng(0), F, Q, np.zeros(4), 5_000_000, 2)
    monkeypatch.setattr(case, "psd_factor", _ran)
    with pytest.raises(Ran):  # ~17,000 steps of 2 runs, the edge of nees_study, stay accepted
        case.model_truth(np.random.default_rng(0), F, Q, np.zeros(4), 17_000, 2)
    monkeypatch.setattr(case, "std_scalar", _ran)
    R = np.eye(2) * 2500.0
    with pytest.raises(ValueError, match="^runs and T ask for"):
        case.two_sensor_scenario(R, R, Q, np.random.default_rng(0), runs=100_000)
    with pytest.raises(Ran):  # the chapter's: 200 runs at T = 0.2 s (Fig. 6's shortest period)
        case.two_sensor_scenario(R, R, Q, np.random.default_rng(0), runs=200, T=0.2)


def test_awf_study_weighs_a_draw_by_its_measured_cost(monkeypatch):
    # ~25 units a draw, counted 8: 78,000 runs (about 32 CPU-s) were accepted
    from fusion.scenarios.lecture_weighting import estimators
    monkeypatch.setattr(estimators.np.random, "default_rng", _ran)
    with pytest.raises(ValueError, match="^levels, runs, k_max and sigma ask for"):
        estimators.awf_study(levels=(0.0, 900.0), k_max=100, runs=180_000, ks=(3, 5, 10), k_compare=10)  # STUDY_WORK 7e9
    with pytest.raises(Ran):  # the chapter's (5 levels, 300 runs x 1,000 samples x 4 sensors)
        estimators.awf_study()


def test_wavelet_variance_study_has_a_work_budget(monkeypatch):
    # no work budget: 690,000 runs (about 31 CPU-s) were accepted; ~0.2 us a sample, refused before the draws
    from fusion.scenarios import wavelet_sensors as ws
    monkeypatch.setattr(ws, "check_magnitude", _ran)
    with pytest.raises(ValueError, match="^readings, runs, gains and length ask for"):  # each reading too (42a C14)
        ws.variance_study(length=128, runs=200_000, gains=(1.0, 2.0, 3.0), sigma=(1.0, 1.0, 1.0))
    with pytest.raises(Ran):  # the chapter's (window 64, 300 runs of the default case)
        ws.variance_study(window=64, runs=300)


def test_consistency_study_weighs_a_pair_check(monkeypatch):
    # ~2 units a pair-check, counted 1: 103,000 runs (about 23 CPU-s) were accepted
    from fusion.scenarios.lecture_weighting import consistency
    monkeypatch.setattr(consistency.np.random, "default_rng", _ran)
    with pytest.raises(ValueError, match="^runs, samples, curve_draws and sigma ask for"):
        consistency.consistency_study(runs=8_000, samples=100, curve_draws=100)
    with pytest.raises(Ran):  # the chapter's (x = 900, bias 30: 100 runs of the default case), and 20 times more
        consistency.consistency_study(x=900.0, bias=30.0, runs=2000)



#: Each entry of STUDY_WORK, the stability record whose sweep reading serves it and the module whose budget it is.
_SERVED = {"TRACKING_STUDY": ("chf-equal-kl", "fusion.scenarios.range_bearing"),
           "AWF_STUDY": ("lec-awf-estimated", "fusion.scenarios.lecture_weighting.estimators"),
           "REGIME_STUDY": ("lec-awf-adapts", "fusion.scenarios.lecture_weighting.regime"),
           "READINGS_BENCHMARK": ("lec-belief-accuracy", "fusion.scenarios.lecture_weighting.readings_benchmark"),
           "PREMISE_STUDY": ("chf-premise-eps", "fusion.book.chapters.chernoff.premise"),
           "ARCHITECTURE_STUDY": ("ci-fig4-convex-part", "fusion.scenarios.two_sensor.architecture"),
           "MEMBERSHIP_STUDY": ("yang-membership-free", "fusion.book._study_budget"),
           "ARCHITECTURE_STUDIES": ("ci-fig4-convex-part", "fusion.book._study_budget"),
           "IR_READINGS_STUDY": ("ci-fig10-x-below-y", "fusion.book._study_budget"),
           "RECORD_EVIDENCE": ("ci-fig4-convex-part", "fusion.book._study_budget")}


@pytest.mark.parametrize("key", sorted(_SERVED))
def test_study_work_is_twice_the_book_call_it_serves(key, monkeypatch):
    # budget35's one rule for a budget above MAX_WORK: twice the book's own call, rounded up to a whole MAX_WORK; the
    # book's calls include the reseeding sweep's scaled primaries (at the runs factor stability.json stores): the
    # served call is counted by the budget itself, stopped when it checks the entry
    import importlib
    import json

    import fusion._limits as L
    from fusion.book import claims as C
    from fusion.book import stability as S

    entry = L.STUDY_WORK[getattr(L, key)]
    rid, module = _SERVED[key]
    counted = []

    def spy(shape, names, weight=1, limit=L.MAX_WORK, served=None):
        units = real(shape, names, weight=weight, limit=10**30)
        if limit == entry and served in (None, getattr(L, key)):
            counted.append(units)
            raise Ran
        return real(shape, names, weight=weight, limit=limit, served=served)

    real = L.work
    monkeypatch.setattr(L, "work", spy)  # loop_work's
    mod = importlib.import_module(module)
    if hasattr(mod, "work"):
        monkeypatch.setattr(mod, "work", spy)
    readings = S.stochastic_readings()
    rkey = next(k for k in readings if k[1] == rid)
    root = S._ledger_dir(None).parent.parent
    factor = json.loads((root / "book" / "ledger" / S.STABILITY_FILE).read_text())["records"][rid]["runs_factor"]
    task = next(t for t in S.tasks({rkey: readings[rkey]}, [S.ROOT_SEED], factor) if t.scaled)
    spec = next(s for cf in C.load_all(C.claims_dir()).values() for s in cf.records if s.id == rid)
    with pytest.raises(Ran):
        C.evaluate(spec, task.reading, task.seed, task.runs)
    assert entry == -(-2 * counted[0] // L.MAX_WORK) * L.MAX_WORK
    assert counted[0] > L.MAX_WORK  # an entry only for a call beyond MAX_WORK
    # every entry serves a book call (a sweep reading here; chapter 05's notebook call of ledger_studies, LEDGER_STUDIES,
    # in tests/test_study_budget63.py); an entry equal to another's is named by work()'s served (the architecture
    # study and chapter 01's membership study share the readings benchmark's 3e9; chapter 05's ledger studies and
    # infrared readings the regime study's 4e9, its record evidence the AWF study's 7e9), the others by their value
    # (chapter 05's two architecture studies, 5e9 since fuzz 66b C1 counted a bank's path-run step)
    # (book audit 76: chapter 06's appendix call of sigma_first_order_study, SIGMA_FIRST_ORDER_STUDY, 5e9, in
    # tests/test_book_audit76_chernoff.py, named by served as it equals the two architecture studies')
    assert len(L.STUDY_WORK) == len(_SERVED) + 2
    assert len(set(L.STUDY_WORK.values())) == len(L.STUDY_WORK) - 6


def test_the_tracking_study_entry_refuses_beyond_it():
    from fusion._limits import STUDY_WORK, TRACKING_STUDY
    from fusion.scenarios import range_bearing as rb
    from fusion.book.chapters.chernoff.settings import STUDY_RUNS
    assert rb.TRACK_WORK == STUDY_WORK[TRACKING_STUDY]
    assert rb._tracking_work(rb.RangeBearingScenario(), STUDY_RUNS, "runs") <= rb.TRACK_WORK / 2
    with pytest.raises(ValueError, match="STUDY_WORK: chapter 06's tracking study"):
        rb.monte_carlo(rb.RangeBearingScenario(), 1, 6 * STUDY_RUNS + 20)


@pytest.mark.parametrize("study, bad, book", [
    # symmetry_study: no work budget, 8.8e6 runs (some 640 CPU-s) were accepted; ~2.4 us a reading (250 units)
    ("symmetry_study", dict(k=10, runs=200_000), dict(x=900.0, k=100, runs=200, seed=2108)),
    # ar1_study: a memory budget only, 8.9e6 runs (some 35 CPU-s) were accepted; ~0.13 us a reading (15 units)
    ("ar1_study", dict(k=10, runs=3_000_000), dict(phi=0.8, k=100, runs=2000, seed=2110)),
    # lumv_study: counted 10 ns a reading, ~0.12 us measured (12 units): k = 10**7 of 6 runs (~22 CPU-s) was accepted
    ("lumv_study", dict(k=5_000_000, runs=6), dict(x=900.0, k=100, runs=20000, seed=2107)),
])
def test_estimator_studies_weigh_a_reading(monkeypatch, study, bad, book):
    from fusion.scenarios.lecture_weighting import estimators
    monkeypatch.setattr(estimators.np.random, "default_rng", _ran)
    with pytest.raises(ValueError, match="^runs, k and sigma ask for"):
        getattr(estimators, study)(sigma=(0.5, 1.0, 2.0), **bad)
    with pytest.raises(Ran):  # the chapter's own call (4 sensors)
        getattr(estimators, study)(**book)
