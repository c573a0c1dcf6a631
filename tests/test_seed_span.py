"""Derived seeds and SeedSequence arguments are checked at entry (fuzz 55 C1, C2, D1).

A function that derives seeds up to ``seed + span`` refuses, at entry and naming its own ``seed``, a seed whose
derived seeds would pass ``SEED_MAX`` (it refused inside, after minutes of work, or naming an inner argument); a
SeedSequence argument of huge entropy is refused by bit length before any spawn.
"""

import importlib
import time

import numpy as np
import pytest

from fusion._counts import SEED_MAX, SEED_WORDS, seed, seed_sequence


def test_seed_span_edges():
    assert seed(SEED_MAX - 213, span=213) == SEED_MAX - 213
    assert seed(SEED_MAX) == SEED_MAX
    with pytest.raises(ValueError, match=r"seed must be at most 2\*\*256 - 1 - 213: this function derives seeds up to "
                                         r"seed \+ 213.*got seed = 2\*\*256 - 1 - 212"):
        seed(SEED_MAX - 212, span=213)


def _no_work(*args, **kwargs):
    raise AssertionError("a generator was seeded: the refusal came after work")


def _ledger_study(s):
    from fusion.scenarios import time_registration as sc
    t1, t2 = sc.instants()
    return "fusion.book.chapters.time_registration_ledger.studies", "study", (t1, t2, 1.0, 50, s), {}


# (module, function, span, arguments given the seed)
CASES = [
    ("fusion.book.chapters.chernoff.studies", "premise_study", 15, lambda s: ((s,), {"runs": 300})),
    ("fusion.book.chapters.chernoff.studies", "premise_mixture_scaled", None, lambda s: ((s,), {})),
    ("fusion.book.chapters.chernoff.studies", "common_study", 5, lambda s: ((s,), {})),
    ("fusion.book.chapters.chernoff.studies", "isv_study", 3, lambda s: ((s,), {})),
    ("fusion.book.chapters.chernoff.glue", "chapter_evidence", 100, lambda s: ((s,), {})),
    ("fusion.book.chapters.chernoff.glue", "claim_values", 15, lambda s: ((s,), {})),
    ("fusion.book.chapters.chernoff.evidence", "ev_is", 100, lambda s: (({},), {"seed": s, "runs": 300})),
    ("fusion.book.chapters.chernoff.importance", "is_replicate_values", 100, lambda s: ((s,), {})),
    ("fusion.book.chapters.chernoff.premise", "premise_studies", 5, lambda s: ((s,), {})),
    ("fusion.book.chapters.chernoff.mixture", "toy", 1, lambda s: ((s,), {})),
    ("fusion.book.chapters.chernoff.importance", "is_replicates", 100, lambda s: ((s, 50), {})),
    ("fusion.book.chapters.time_registration_fig4", "fig4_compatibility", 2, lambda s: (((0.1, 1.0, 3.0), 50, s, 10.0), {})),
    ("fusion.book.chapters.ci.fruit_fly_step", "fruit_fly_step_study", 4, lambda s: ((), {"seeds": 5, "seed": s})),
    ("fusion.book.chapters.ci.studies", "unequal_pair", 99, lambda s: ((s,), {})),
    ("fusion.book.chapters.ci.studies", "aniso_pair", 99, lambda s: ((s,), {})),
    ("fusion.book.chapters.ci.studies", "fig6_periods", None, lambda s: ((s,), {})),
    ("fusion.book.chapters.ci.studies", "ledger_studies", 51, lambda s: ((s,), {})),
    ("fusion.book.chapters.ci.constants", "study_seed", 23, lambda s: ((s, "anisotropic pair"), {})),
    ("fusion.book.chapters.lecture_weighting.studies", "study", 6903, lambda s: (("bench", s), {})),
    ("fusion.book.chapters.lecture_weighting.records", "evidence", 6903, lambda s: (({},), {"seed": s})),
    ("fusion.book.chapters.lecture_correlated.records", "cached_studies", 213, lambda s: ((s,), {})),
    ("fusion.book.chapters.lecture_correlated.appendix", "table_james_stein", 10, lambda s: ((), {"seed": s})),
    ("fusion.book.chapters.time_registration_ledger.studies", "cached_study", None, lambda s: ((s, 15000), {})),
    ("fusion.book.chapters.time_registration", "tuning_by_noise", None, lambda s: (((0.5, 1.0), 50, s), {})),
]


@pytest.mark.parametrize("module, name, span, args", CASES, ids=[c[1] for c in CASES])
def test_derived_seed_refused_at_entry(monkeypatch, module, name, span, args):
    f = getattr(importlib.import_module(module), name)
    monkeypatch.setattr(np.random, "default_rng", _no_work)
    monkeypatch.setattr(np.random, "SeedSequence", _no_work)
    top = SEED_MAX - (span or 0)   # the first refused seed when span is known; else the largest seed
    a, kw = args(top + 1 if span else SEED_MAX)
    t = time.process_time()
    with pytest.raises(ValueError, match=r"^seed must be at most 2\*\*256 - 1 - [\d,]+: this function derives seeds"):
        f(*a, **kw)
    assert time.process_time() - t < 1.0


def test_study_refused_at_entry(monkeypatch):
    monkeypatch.setattr(np.random, "default_rng", _no_work)
    module, name, a, kw = _ledger_study(SEED_MAX - 179)
    with pytest.raises(ValueError, match=r"^seed must be at most 2\*\*256 - 1 - 180: this function derives seeds"):
        getattr(importlib.import_module(module), name)(*a, **kw)
    module, name, a, kw = _ledger_study(SEED_MAX - 180)   # the edge: accepted, its first run seeded
    with pytest.raises(AssertionError, match="a generator was seeded"):
        getattr(importlib.import_module(module), name)(*a, **kw)


def _tiny():
    from fusion.scenarios.range_bearing_scenario import RangeBearingScenario
    return RangeBearingScenario(frames=2, n_particles=50, n_samples=50, n_central=100, em_iterations=2)


@pytest.mark.parametrize("which", ["run_tracking", "run_tracking_batch"])
def test_huge_seed_sequence_refused_before_spawn(monkeypatch, which):
    from fusion.scenarios import range_bearing

    huge = np.random.SeedSequence(1 << 10**5)   # 0.04 CPU-s to build; each spawn would mix it again
    t = time.process_time()
    if which == "run_tracking":
        with pytest.raises(ValueError, match=r"^seed entropy must be a seed of at most 256 bits.*100,001 bits"):
            range_bearing.run_tracking(_tiny(), huge)
    else:
        with pytest.raises(ValueError, match=r"^seeds\[1\] entropy must be a seed of at most 256 bits"):
            range_bearing.run_tracking_batch(_tiny(), [np.random.SeedSequence(1), huge])
    assert time.process_time() - t < 1.0


def test_seed_sequence_bounds():
    ok = np.random.SeedSequence(SEED_MAX, spawn_key=tuple(range(SEED_WORDS)), pool_size=SEED_WORDS)
    assert seed_sequence(ok) is ok
    assert seed_sequence(np.random.SeedSequence([SEED_MAX >> 128, 5])) is not None
    with pytest.raises(ValueError, match="at most 8 32-bit words of entropy"):
        seed_sequence(np.random.SeedSequence([SEED_MAX, 1]))
    with pytest.raises(ValueError, match="at most 8 32-bit words of spawn_key"):
        seed_sequence(np.random.SeedSequence(1, spawn_key=tuple(range(SEED_WORDS + 1))))
    with pytest.raises(ValueError, match="a pool of at most 8 words"):
        seed_sequence(np.random.SeedSequence(1, pool_size=SEED_WORDS + 1))
    with pytest.raises(ValueError, match=r"seed spawn_key\[1\] must be a seed of at most 256 bits"):
        seed_sequence(np.random.SeedSequence(1, spawn_key=(0, 1 << 300)))
    with pytest.raises(TypeError, match="^seed must be a SeedSequence, got int"):
        seed_sequence(5)


def test_per_step_weights_and_fig5_hypotheses_spans(monkeypatch):
    # per_step_weights: step k's swarm seeds seed + k; fig5_hypotheses: seed .. seed + len(fruit_fly_seeds.seeds) - 1
    from fusion.book.chapters import ci
    from fusion.scenarios import two_sensor
    from fusion.scenarios.two_sensor import weights
    sc = two_sensor.two_sensor_scenario(np.eye(2) * 2500.0, np.eye(2) * 2500.0, np.diag([0.0, 1.0, 0.0, 1.0]),
                                        np.random.default_rng(11), runs=2)
    K = sc.tracks[0].gains.P.shape[0]
    ffs = weights.FruitFlySeeds(seeds=np.arange(3), fruit_fly_x=np.full(3, 0.5), fruit_fly_fun=np.ones(3),
                                grid_x=0.5, grid_fun=1.0, rtol=1e-6)
    monkeypatch.setattr(np.random, "default_rng", _no_work)
    with pytest.raises(ValueError, match=rf"^seed must be at most 2\*\*256 - 1 - {K - 1}: this function derives"):
        weights.per_step_weights(*sc.tracks, SEED_MAX - K + 2, population=3, iterations=3)
    with pytest.raises(AssertionError, match="a generator was seeded"):   # the edge: accepted
        weights.per_step_weights(*sc.tracks, SEED_MAX - K + 1, population=3, iterations=3)
    P = np.eye(4)
    with pytest.raises(ValueError, match=r"^seed must be at most 2\*\*256 - 1 - 2: this function derives"):
        ci.fig5_hypotheses(P, 2 * P, ffs, SEED_MAX - 1, short_budget=3, n_open=3)
    with pytest.raises(AssertionError, match="a generator was seeded"):
        ci.fig5_hypotheses(P, 2 * P, ffs, SEED_MAX - 2, short_budget=3, n_open=3)


def test_fuzz56_a_seed_sequence_subclass_or_a_spent_counter_is_refused_before_spawn():
    """Fuzz 56 C2: a subclass whose ``entropy`` reported 1 passed while numpy mixed 10**6 bits (43 CPU-s); C1: a
    spawn counter of 2**32 - 6 made ``spawn(6)`` never return (102 CPU-s, then a MemoryError)."""
    from fusion._counts import SPAWNED_MAX
    from fusion.scenarios import range_bearing

    class Reports(np.random.SeedSequence):
        entropy = 1

    t = time.process_time()
    with pytest.raises(TypeError, match="^seed must be a numpy.random.SeedSequence itself, not a subclass"):
        range_bearing.run_tracking(_tiny(), Reports(1 << 10**4))
    spent = np.random.SeedSequence(1, n_children_spawned=2**32 - 6)
    with pytest.raises(ValueError, match=r"^seeds\[0\] must be a SeedSequence that has spawned at most"):
        range_bearing.run_tracking_batch(_tiny(), [spent])
    assert time.process_time() - t < 1.0
    edge = np.random.SeedSequence(1, n_children_spawned=SPAWNED_MAX)
    assert seed_sequence(edge) is edge
    with pytest.raises(ValueError, match="spawned at most 2,147,483,648 children"):
        seed_sequence(np.random.SeedSequence(1, n_children_spawned=SPAWNED_MAX + 1))


def test_fuzz57b_d1_a_huge_entropy_is_refused_without_reading_it_whole():
    """Fuzz 57b D1: ``_words`` converted the whole entropy to an object array before counting: ``np.arange(10**8)``
    was refused after 4.4 CPU-s (10**7 words: 0.44). Now its first entries only are read."""
    huge = np.random.SeedSequence(np.arange(10**7, dtype=np.uint32))   # ~0.3 CPU-s to build
    nested = np.random.SeedSequence([np.arange(10**7, dtype=np.uint32)])
    for ss in (huge, nested):
        t = time.process_time()
        with pytest.raises(ValueError, match="^seed must be a SeedSequence of at most 8 32-bit words of entropy"):
            seed_sequence(ss)
        assert time.process_time() - t < 0.05
    # the bound itself is unchanged: 8 words of entropy pass, nested or flat, and their entries are still checked
    assert seed_sequence(np.random.SeedSequence([[1, 2], np.arange(3, 9)])) is not None
    with pytest.raises(ValueError, match=r"^seed entropy\[1\] must be a seed of at most 256 bits"):
        seed_sequence(np.random.SeedSequence([1, [1 << 300]]))
    empties = np.random.SeedSequence([[] for _ in range(100)] + [1])   # no word until the last entry
    with pytest.raises(ValueError, match="^seed must be a SeedSequence of at most 8 32-bit words of entropy, got more "
                                         "than 64 nested items"):
        seed_sequence(empties)
