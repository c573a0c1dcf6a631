r"""Every readings-level method of the lecture on one shared setup, over seeds (chapter 02's benchmark)."""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from enum import StrEnum
from typing import Any

import numpy as np

from fusion._results import ResultSpec, array, dict_of, instance, integer, number, same_keys, tuple_of
from fusion._results import flag as flag_spec, validated_post_init  # flag: the argument check of _validation
from fusion import readings as rd
from fusion._validation import read_mapping, read_once
from fusion._validation import derived_inputs
from fusion._validation import flag
from fusion._validation import LOOP_STEP, distinct, distinct_printed, general, loop_work, sequence, work
from fusion._validation import allocation, as_array, count, scalar
from fusion._validation import instance_of, record, seeds as check_seeds
from fusion._validation import seed as check_seed
from fusion._limits import READINGS_BENCHMARK, ROUND_OFF_TIE, STUDY_WORK
from fusion.readings import consistency as cs
from fusion.readings import weighting as wt
from fusion.readings.robust import _robust_limit, robust_fuse
from fusion.scenarios._lecture_checks import _index, _sigmas, _values
from fusion._shown import shown

__all__ = [
    "BENCH_SIGMA",
    "BenchMethod",
    "SeedStability",
    "benchmark",
    "seed_stability",
]


# --------------------------------------------------------------------------- benchmark
#: Noise SDs of the shared benchmark (°C).
BENCH_SIGMA = (0.5, 1.0, 1.5, 2.0, 4.0)
#: Units (about 10 ns, ``fusion._limits.MAX_WORK``) of one reading (run x sample x sensor) of one setup of
#: :func:`benchmark`: its ~20 methods cost about 0.43 us a reading, measured (budget35, OPENBLAS_NUM_THREADS=1:
#: 2.1 CPU-s for 8 setups of 7,679 runs x 20 samples x 4 sensors), so 45 units; the chapter's 12 setups of 500 x
#: 100 x 5 readings count about 1.4e8 units (about 1.4 CPU-s); its budget is its entry of ``fusion._limits.STUDY_WORK``
#: (the reseeding sweep's 5,000 runs count 1.35e9 units: 3e9).
_BENCH_READING = 45
#: Units of one key (seed, level, fault) of :func:`benchmark` beyond its readings' (its ~20 methods' validated calls):
#: 1.6-2.3 ms a key measured at 1 run x 2 samples and 2 x 10 x 5 sensors (20 and 80 keys; ``time.process_time``,
#: ``OPENBLAS_NUM_THREADS=1``, the least of two calls, machine shared), so about twice, 400 ``LOOP_STEP``, within
#: ``MAX_WORK`` (fuzz 64b's class: 100 under the study's 3e9 let 29,866 keys run about 60 CPU-s, accepted).
_BENCH_KEY = 400 * LOOP_STEP
#: The methods of :func:`fusion.readings.robust.robust_fuse` the benchmark applies to the readings at k = K (median,
#: biweight): their own limits are checked at its entry.
_BENCH_ROBUST = ("median", "biweight")


class BenchMethod(StrEnum):
    """Method keys of :func:`benchmark`, in its order (display labels: :data:`fusion.book.style.METHOD_LABELS`).

    Attributes
    ----------
    ORACLE
        Inverse-variance weights of the true variances.
    MEAN
        Arithmetic mean of the current readings.
    AWF_LECTURE_FLOOR
        §2.1 AWF, the lecture's variance estimates, non-positive ones floored.
    AWF_LECTURE_ABS
        §2.1 AWF, the lecture's variance estimates, non-positive ones as ``|σ̂²|``.
    AWF_CENTRED
        §2.1 AWF, centred variance estimates.
    LS_LEARNING
        §2.2 least-squares variance learning.
    LS_CORRECTED
        §2.2 learning, corrected for the mean's share.
    CHECK_AWF
        §2.3 consistency check + AWF (centred).
    BELIEF
        §2.4 belief degree, scale 1.
    OPTIMAL_FUSION_SET
        Chapter 01's optimal fusion set.
    SUPPORT_DEGREE
        Chapter 01's support degree of ref. [11].
    MEDIAN
        Median of the current readings.
    BIWEIGHT
        Tukey's biweight of the current readings.
    """

    ORACLE = "lec_bench_oracle"
    MEAN = "lec_bench_mean"
    AWF_LECTURE_FLOOR = "lec_bench_awf_lecture_floor"
    AWF_LECTURE_ABS = "lec_bench_awf_lecture_abs"
    AWF_CENTRED = "lec_bench_awf_centred"
    LS_LEARNING = "lec_bench_ls_learning"
    LS_CORRECTED = "lec_bench_ls_corrected"
    CHECK_AWF = "lec_bench_check_awf"
    BELIEF = "lec_bench_belief"
    OPTIMAL_FUSION_SET = "lec_bench_optimal_fusion_set"
    SUPPORT_DEGREE = "lec_bench_support_degree"
    MEDIAN = "lec_bench_median"
    BIWEIGHT = "lec_bench_biweight"


def _snapshot_errors(X: np.ndarray, truth: float, sigma: np.ndarray, eps: float) -> dict[BenchMethod, np.ndarray]:
    """Squared error of each method's fusion of the readings at k = K (own weights, current readings)."""
    xK = X[:, -1]

    def current(w: np.ndarray) -> np.ndarray:
        return np.einsum("ij,ij->i", w, xK)

    est = {
        BenchMethod.ORACLE: xK @ wt.optimal_weights(sigma**2),
        BenchMethod.MEAN: xK.mean(axis=1),
        # the lecture's variance estimates applied to the current readings (the benchmark compares snapshot
        # fusions at k = K); two guards for non-positive estimates, the package's floor and |σ̂²|
        BenchMethod.AWF_LECTURE_FLOOR: current(wt.inverse_variance_weights(wt.running_variances(X, "lecture")[:, -1])),
        BenchMethod.AWF_LECTURE_ABS: current(wt.inverse_variance_weights(wt.running_variances(X, "lecture")[:, -1],
                                                                         guard="abs")),
        BenchMethod.AWF_CENTRED: current(wt.inverse_variance_weights(wt.running_variances(X, "centred")[:, -1])),
        BenchMethod.LS_LEARNING: wt.ls_learning(X).values[:, -1],
        BenchMethod.LS_CORRECTED: wt.ls_learning(X, corrected=True).values[:, -1],
        BenchMethod.CHECK_AWF: current(cs.consistency_awf(X, eps, "centred").awf.weights[:, -1]),
        BenchMethod.BELIEF: rd.fuse_epochs(xK, "belief_degree").values,
        BenchMethod.OPTIMAL_FUSION_SET: rd.fuse_epochs(xK, "optimal_fusion_set").values,
        BenchMethod.SUPPORT_DEGREE: rd.fuse_epochs(xK, "support_degree").values,
        # what a practitioner would use to resist an abnormal reading without any model (fusion.readings.robust)
        BenchMethod.MEDIAN: robust_fuse(xK, _BENCH_ROBUST[0]),
        BenchMethod.BIWEIGHT: robust_fuse(xK, _BENCH_ROBUST[1]),
    }
    return {name: (v - truth) ** 2 for name, v in est.items()}


@derived_inputs()
def benchmark(
    seeds: Sequence[int] = (9001, 9002, 9003),
    runs: int = 500,
    samples: int = 100,
    levels: Sequence[float] = (0.0, 900.0),
    bias: float = 30.0,
    fault_sensor: int = 2,
    fault_from: int = 50,
    sigma: Sequence[float] = BENCH_SIGMA,
    faults: Sequence[bool] = (False, True),
) -> dict[tuple[int, float, bool], dict[BenchMethod, np.ndarray]]:
    r"""Every readings-level method of chapters 01 and 02 on one shared setup.

    For each seed, level and fault flag: ``runs`` x ``samples`` readings of ``len(sigma)`` sensors
    (the same noise at both levels and with/without the fault); the fault adds ``bias`` to sensor
    ``fault_sensor`` from sample index ``fault_from`` on (still failed at k = K). The metric is the
    squared error of the value fused at k = K, each method applying its own weights (learned from
    samples 1..K where it learns) to the current readings. The consistency check uses
    :math:`\varepsilon = 3\sqrt2\,\sigma_{\max}`. The median and Tukey's biweight
    (:func:`fusion.readings.robust.robust_fuse`) are the model-free robust baselines.

    Parameters
    ----------
    seeds : sequence of int
        One setup per seed (no two equal: the results are keyed by seed, level and fault).
    runs, samples : int
        Monte-Carlo runs and instants K per run.
    levels : sequence of float
        True values (°C), no two equal to 6 significant digits (the chapter labels each ``f"X={X:g}"``).
    bias : float
        Fault bias (°C).
    fault_sensor : int
        Faulty sensor (0-based).
    fault_from : int
        First faulty sample (0-based).
    sigma : sequence of float
        Noise standard deviation of each sensor (°C).
    faults : sequence of bool
        Which setups to run: without the fault (False), with it (True), or both (the default), no two equal.

    Returns
    -------
    dict
        ``{(seed, level, fault): {method key (:class:`BenchMethod`): per-run squared error, shape (runs,)}}``.

    Raises
    ------
    ValueError
        A bad argument, named; before any work: the readings of every (seed, level, fault) key beyond the work budget
        (45 units a reading, measured, and a step a key; its entry of ``fusion._limits.STUDY_WORK``) or the keys' own
        steps (4 ms a key, about twice the measured) beyond ``fusion._validation.MAX_WORK``, the checked AWF's
        eight ``(runs, samples, n, n)`` pair arrays beyond the memory budget (naming runs, samples and sigma), or their
        work at every key (6 units a pair element, measured) beyond ``fusion._validation.MAX_WORK``, or the
        ``(runs, len(sigma))`` readings at k = K beyond what :func:`fusion.readings.robust.robust_fuse` takes for the
        median and the biweight (its worst case: 344,655 runs of 3 sensors), naming runs and sigma.
    """
    sigma = read_once(sigma, "sigma")  # a Sequence class read once (fuzz 31a C4)
    if isinstance(seeds, (str, bytes)):
        raise TypeError("seeds must be a sequence of ints, got a string")
    seed_items = sequence(seeds, "seeds")   # counted by its length below, before any seed is read (fuzz 62b D1)
    runs = count(runs, "runs")
    samples = count(samples, "samples")
    lv = _values(levels, "levels")
    levels = levels if isinstance(levels, (list, tuple)) else lv.tolist()  # iterated below: any array-like
    bias = scalar(bias, "bias")
    sig_chk = _sigmas(sigma, minimum=3)
    allocation((runs, samples, sig_chk.size), "runs, samples and sigma")
    fault_sensor = _index(fault_sensor, sig_chk.size, "fault_sensor")
    fault_from = count(fault_from, "fault_from", minimum=0)  # >= samples: no faulty sample (valid)
    fault_items = sequence(faults, "faults", minimum=1, what="flag")  # fuzz 24a U8: one rule for a sequence argument
    # rule 17: ~20 methods per key, a reading weighing its measured cost (budget35: ~0.43 us, 45 units; 1.5e6 runs,
    # about 400 CPU-s, were accepted), so the edge is about 30 CPU-s (STUDY_WORK); by the lengths, before any seed,
    # flag or level label is read (fuzz 62b D1: 10**6 faults were each read as a flag first, 0.5 CPU-s, ~5 at 10**7;
    # a repeated key, refused below, counted as its own)
    loop_work((len(seed_items), lv.size, len(fault_items)), _BENCH_READING * runs * samples * sig_chk.size,
              "seeds, levels, faults, runs, samples and sigma", step=100 * LOOP_STEP,
              limit=STUDY_WORK[READINGS_BENCHMARK])  # the reseeding sweep's 10x (lec-belief-accuracy): 1.35e9
    loop_work((len(seed_items), lv.size, len(fault_items)), 0, "seeds, levels and faults", step=_BENCH_KEY)
    seeds = check_seeds(seed_items, "seeds")
    faults = [flag(f, f"faults[{i}]") for i, f in enumerate(fault_items)]  # then each flag
    # the results are keyed by (seed, level, fault): a repeated entry would collapse two of them
    distinct(list(seeds), "seeds"), distinct([bool(f) for f in faults], "faults")
    distinct_printed(lv.tolist(), "levels", general, "labels a column")  # the chapter's f"X={X:g}" (fuzz 30b)
    # the checked AWF's (runs, samples, n, n) pair arrays, at entry by the callee's own rule (named here, not as X):
    # their memory, and their work at every key (fuzz 42a C4: one key's was counted, so 12 keys of 1 run x 3,300
    # samples x 100 sensors, 1.8e8 units by the readings, ran 32.8 CPU-s). A key of the benchmark measured the checked
    # AWF's cost (2.7-5.9 units a pair element) and about 15-30 units a reading more (2,000 x 100 x 5, 200 x 100 x 10
    # and 20, 50 x 100 x 40, 1 x 3,300 x 100, 1 x 1,000 x 180, 2 x 500 x 150: 0.11 to 1.4 CPU-s a key, the least of
    # three, time.process_time, OPENBLAS_NUM_THREADS=1, machine shared), within the 45 units a reading and the
    # callee's 6 a pair element counted; the sweep's 10x (12 keys of 5,000 x 100 x 5) counts 9e8 pair units
    cs._pair_budget((runs, samples, sig_chk.size), "runs, samples and sigma",
                    fusions=len(seeds) * lv.size * len(faults),
                    fusion_names="seeds, levels, faults, runs, samples and sigma")
    # each robust baseline's own refusal of the (runs, n) readings it fuses at k = K, at entry (fuzz 47 C4: the
    # biweight's worst-case IRLS limit refused 344,656 runs x 3 sensors after ~10 CPU-s of the other methods)
    for m in _BENCH_ROBUST:
        _robust_limit(runs, sig_chk.size, m, "runs and sigma (the readings at k = K fused by the median and the "
                      "biweight)")
    sig = np.asarray(sigma, dtype=float)
    eps = 3 * np.sqrt(2) * sig.max()
    results = {}
    for seed in seeds:
        noise = np.random.default_rng(seed).normal(size=(runs, samples, sig.size)) * sig
        for X0 in levels:
            for fault_on in faults:
                X = X0 + noise.copy()
                if fault_on:
                    X[:, fault_from:, fault_sensor] += bias
                results[seed, float(X0), fault_on] = _snapshot_errors(X, float(X0), sig, eps)
    return results


def _benchmark_results(results: object, count: Callable[[int, int, int], None] | None = None,
                       ) -> dict[tuple[int, float, bool], dict[str, np.ndarray]]:
    """The output of :func:`benchmark`, checked entry by entry (rule 12 of the shared validation).

    Keys ``(seed, level, fault)`` covering every (seed, scenario) pair; values dicts of one set of
    methods, each a non-empty 1-D array of finite squared errors. The mapping is read once; its keys and methods are
    checked first and ``count(seeds, scenarios, methods)``, when given, called before any array is converted (a
    caller's work budget, fuzz 42a C10).
    """
    results = read_mapping(results, "results")
    if not isinstance(results, Mapping):  # any mapping, as the package's other checks (a read-only one included)
        raise TypeError(f"results must be a mapping (a dict from benchmark), got {type(results).__name__}")
    if not results:
        raise ValueError("results is empty")
    methods: list | None = None
    for key, entry in results.items():
        path = f"results[{key!r}]"
        if not isinstance(key, tuple) or len(key) != 3:
            raise TypeError(f"results must be keyed by (seed, level, fault) tuples, got {shown(key)}")
        check_seed(key[0], f"{path}: the seed")
        scalar(key[1], f"{path}: the level")
        flag(key[2], f"{path}: the fault flag")
        if not isinstance(entry, Mapping) or not entry:
            raise TypeError(f"{path} must be a non-empty mapping of method -> squared errors, got {type(entry).__name__}")
        if methods is None:
            methods = list(entry)
        record(entry, path, tuple(methods))
    seeds = {k[0] for k in results}
    scen = {k[1:] for k in results}
    if len(results) != len(seeds) * len(scen):
        raise ValueError(f"results must hold every (seed, scenario) pair: {len(seeds)} seeds x {len(scen)} scenarios, "
                         f"got {len(results)} entries")
    if count is not None:
        count(len(seeds), len(scen), len(methods or ()))
    return {key: {m: as_array(entry[m], f"results[{key!r}][{m!r}]", ndim=1, nonnegative=True) for m in methods or ()}
            for key, entry in results.items()}


def _stability_relation(values: Mapping[str, Any], cls: str) -> None:
    """A :class:`SeedStability`: ranks of shape (seeds, methods), each at most the number of methods; counts of
    scenarios at most the scenarios, reversals at most one per resolved pair and later seed."""
    n_seeds, n_methods = len(values["seeds"]), len(values["methods"])
    for key, r in values["ranks"].items():
        if r.shape != (n_seeds, n_methods):
            raise ValueError(f"{cls}.ranks[{shown(key)}] must have shape ({n_seeds}, {n_methods}) (the seeds and "
                             f"methods of {cls}.seeds and {cls}.methods), got {r.shape}")
        if np.any(r > n_methods):
            raise ValueError(f"{cls}.ranks[{shown(key)}] must hold ranks 1..{n_methods}, got {shown(float(r.max()))}")
    if values["n_stable"] > len(values["scenarios"]):
        raise ValueError(f"{cls}.n_stable must be at most the {len(values['scenarios'])} scenarios, "
                         f"got {values['n_stable']}")
    pairs = len(values["scenarios"]) * n_methods * (n_methods - 1) // 2
    if values["n_sig"] > pairs:
        raise ValueError(f"{cls}.n_sig must be at most the {pairs} pairs of methods of the scenarios, "
                         f"got {values['n_sig']}")
    if values["n_rev"] > values["n_sig"] * (n_seeds - 1):
        raise ValueError(f"{cls}.n_rev must be at most {cls}.n_sig x the {n_seeds - 1} later seeds = "
                         f"{values['n_sig'] * (n_seeds - 1)}, got {values['n_rev']}")


@dataclass(frozen=True)
class SeedStability:
    """How stable the benchmark's orderings are over seeds (:func:`seed_stability`).

    Attributes
    ----------
    seeds : tuple of int
        The benchmark's seeds, in its order.
    scenarios : tuple of (float, bool)
        The (level, fault) setups, sorted.
    methods : tuple of str
        The method keys (:class:`BenchMethod`), in the benchmark's order.
    ranks : mapping
        Scenario → ndarray, shape (seeds, methods): each method's rank by MSE in each seed (1 = best).
    n_stable : int
        Scenarios whose full ranking is identical over the seeds.
    n_sig : int
        Pairs of methods resolved in the first seed (MSEs apart by more than ``n_se`` combined standard errors).
    n_rev : int
        Reversals of those pairs in the other seeds.
    """

    seeds: tuple[int, ...]
    scenarios: tuple[tuple[float, bool], ...]
    methods: tuple[str, ...]
    ranks: Mapping[tuple[float, bool], np.ndarray]
    n_stable: int
    n_sig: int
    n_rev: int

    __result_spec__ = ResultSpec(
        {"seeds": tuple_of(integer(0)), "scenarios": tuple_of(tuple_of(number(nonnegative=False), flag_spec())),
         "methods": tuple_of(instance(str)),
         # the chapter labels each scenario f"X={X:g}, fault": two printing alike would share a column (fuzz 30b)
         "ranks": dict_of(array("seeds", "methods", bounds=(1.0, np.inf)), key=tuple, printed=general),
         "n_stable": integer(0), "n_sig": integer(0), "n_rev": integer(0)},
        relations=(same_keys("scenarios", "ranks"), lambda v, cls: _stability_relation(v, cls)))
    __post_init__ = validated_post_init


#: (m, m) arrays of m methods :func:`seed_stability` holds at once (a seed's ranks and pairs: the differences, the
#: masks, the signs; fuzz 42a C10), and its units per scenario and seed: 3 a pair of methods, 1,000 a method (its mean
#: and SE), a step. Measured (``time.process_time``, ``OPENBLAS_NUM_THREADS=1``, the least of two calls, machine
#: shared; the conversion of the arrays apart): 3.0, 2.2 and 1.8 units a pair at 3,500 methods of 2 seeds, 1,000 of 20
#: seeds x 2 scenarios and 2,000 of 3 x 2; 4 us a method and 20 us a seed at 50 methods of 2,000 seeds and 2 of 80,000.
_SEED_PAIR_ARRAYS, _SEED_PAIR, _SEED_METHOD, _SEED_STEP = 6, 3, 1000, 2 * LOOP_STEP


def _tied_ranks(values: np.ndarray) -> np.ndarray:
    """Rank 1 for the smallest value; values tied up to round-off (``fusion._limits.ROUND_OFF_TIE``, the
    rulebook's tie rule) share the best rank of the tie (1, 1, 3): the order of two methods that are one estimator
    on a scenario is not decided by round-off."""
    v = np.asarray(values, dtype=float)
    lower = v[None, :] < v[:, None]
    tied = np.abs(v[None, :] - v[:, None]) <= ROUND_OFF_TIE * np.maximum(np.abs(v[None, :]), np.abs(v[:, None]))
    return 1.0 + np.sum(lower & ~tied, axis=1)


def seed_stability(results: dict[tuple[int, float, bool], dict[str, np.ndarray]], n_se: float = 3.0) -> SeedStability:
    r"""How stable the benchmark's orderings are over seeds.

    For each scenario (level, fault): the rank of every method by mean squared error in every seed (methods
    whose MSEs are equal up to round-off, the rulebook's tie rule, share the better rank);
    and, for the pairs of methods whose MSEs differ by more than ``n_se`` combined standard errors
    in the first seed, how many change order in the other seeds.

    Parameters
    ----------
    results : mapping
        Output of :func:`benchmark` (a dict; any mapping of the same entries, a read-only one included).
    n_se : float

    Returns
    -------
    SeedStability
        Per scenario each method's rank at every seed, how many scenarios keep one ranking, and how many pairs resolved
        at the first seed reverse.

    Raises
    ------
    ValueError
        A bad entry of ``results``, named; its scenarios x seeds x (3 methods² + 1,000 methods + 2,000) units (measured)
        beyond the work budget, or six (methods, methods) arrays beyond the memory budget, before any array is read.
    """
    n_se = scalar(n_se, "n_se", lo=0.0, lo_open=True)

    def count(n_seeds: int, n_scen: int, m: int) -> None:
        # rules 9 and 17 before any array is converted (fuzz 42a C10: no budget; 3,500 methods of 2 seeds ran 51.4
        # CPU-s in a Python loop over the pairs, now vectorised): each (scenario, seed) ranks and compares every pair
        allocation((m, m), "results (its methods)", arrays=_SEED_PAIR_ARRAYS)
        work((n_scen * n_seeds * (_SEED_PAIR * m * m + _SEED_METHOD * m + _SEED_STEP),),
             "results (its scenarios, seeds and methods)")

    results = _benchmark_results(results, count)
    seeds = list(dict.fromkeys(k[0] for k in results))  # in order of first appearance, in linear time (fuzz 42a C10)
    scen = sorted({k[1:] for k in results})
    methods = list(results[(seeds[0], *scen[0])])
    ranks = {}
    n_sig = n_rev = 0
    upper = np.triu(np.ones((len(methods),) * 2, dtype=bool), k=1)  # each pair (a, b) once, a before b
    for s in scen:
        mses = np.array([[results[(sd, *s)][m].mean() for m in methods] for sd in seeds])
        ranks[s] = np.array([_tied_ranks(row) for row in mses])
        r0 = results[(seeds[0], *s)]
        se0 = np.array([r0[m].std() / np.sqrt(r0[m].size) for m in methods])
        sign = np.sign(mses[0][:, None] - mses[0][None, :])
        resolved = upper & (np.abs(mses[0][:, None] - mses[0][None, :]) > n_se * np.hypot(se0[:, None], se0[None, :]))
        n_sig += int(resolved.sum())
        for row in mses[1:]:
            n_rev += int((resolved & (np.sign(row[:, None] - row[None, :]) != sign)).sum())
    n_stable = sum(int(np.all(ranks[s] == ranks[s][0])) for s in scen)
    return SeedStability(seeds=tuple(seeds), scenarios=tuple(scen), methods=tuple(methods), ranks=ranks, n_stable=n_stable, n_sig=n_sig,
                         n_rev=n_rev)
