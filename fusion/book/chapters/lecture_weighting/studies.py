r"""The seeded studies of chapter 02 that its stochastic records use (:func:`study`, cached), and the
deletion-rule baseline on the benchmark's draws."""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from typing import Any, TypeAlias

import numpy as np

from fusion._frozen import constant
from fusion._counts import seed as check_seed
from fusion.book.study_cache import study_cache
from fusion._validation import count, one_of

from fusion.scenarios.lecture_weighting import (AwfStudy, BenchMethod, BeliefParameterStudy, ConsistencyStudy,
                                                RegimeStudy, VarianceChangeStudy)
from fusion._shown import shown

__all__ = [
    "SEED",
    "SEED_OFFSETS",
    "RUNS",
    "BENCH_SEEDS",
    "Study",
    "study",
]


#: Thresholds ε (°C) of the deletion-rule baselines of record lec-belief-accuracy (the primary grid of lec-belief-objective).
DELETION_EPS: tuple[float, ...] = (0.5, 1.0, 2.0, 4.0)


def _deletion_bench(seed: int, runs: int, eps: float, fault: bool, samples: int = 100) -> np.ndarray:
    """Squared error at k = K of the lecture's deletion rule (half of the others) on the benchmark's draws at X = 900.

    The draws are those of :func:`fusion.scenarios.lecture_weighting.readings_benchmark.benchmark` (the same seed, runs and samples; its default
    fault: sensor 3 +30 °C from sample 51), so the errors pair run by run with the benchmark's methods.
    """
    seed = check_seed(seed)   # an integer seed (rule 11), named
    from fusion import readings as rd
    from fusion.scenarios import lecture_weighting as sc

    sig = np.asarray(sc.BENCH_SIGMA, dtype=float)
    noise = np.random.default_rng(seed).normal(size=(runs, samples, sig.size)) * sig
    xk = 900.0 + noise[:, -1].copy()
    if fault:
        xk[:, 2] += 30.0
    return np.array([(rd.binary_deletion(x, eps, min_support=0.5).value - 900.0) ** 2 for x in xk])


#: Base seed of chapter 02's studies; each study adds its offsets (:data:`SEED_OFFSETS`), so :data:`SEED` gives the
#: chapter's seeds (2101, 2105, 2301, 2404; the benchmark's 9001-9003).
SEED = 2100

#: Seed offsets of each study of :func:`study` (the benchmark runs one setup per offset).
SEED_OFFSETS: dict[str, tuple[int, ...]] = constant({"s21": (1,), "sreg": (5,), "schg": (5,), "s23": (201,), "s23x0": (201,), "s24b": (304,),
                                            "bench": (6901, 6902, 6903)})

#: Run count of each study of :func:`study` in the chapter (E2.4b's: its snapshots).
RUNS: dict[str, int] = constant({"s21": 300, "sreg": 100, "schg": 100, "s23": 100, "s23x0": 100, "s24b": 200, "bench": 500})

#: Names of the benchmark's three setups in the reading keys (the chapter's seeds; under another base seed, the
#: first, second and third setup).
BENCH_SEEDS: tuple[str, ...] = ("9001", "9002", "9003")


#: What :func:`study` returns: one of the typed study results of :mod:`fusion.scenarios.lecture_weighting`, or the
#: benchmark's (seed, level, fault) → method key → per-run squared errors.
Study: TypeAlias = ("AwfStudy | RegimeStudy | VarianceChangeStudy | ConsistencyStudy | BeliefParameterStudy"
                    " | dict[tuple[int, float, bool], dict[BenchMethod, np.ndarray]]")


def study(key: str, seed: int = SEED, runs: int | None = None) -> Study:
    """One study of chapter 02 that its stochastic records use, at base seed ``seed`` and ``runs``, cached.

    ``s21``: E2.1 (:func:`fusion.scenarios.lecture_weighting.estimators.awf_study`, four sensors, levels 0-1000, k up to 1000);
    ``sreg`` and ``schg``: the regime and variance-change studies; ``s23``: E2.3 (X = 900, bias 30 °C);
    ``s23x0``: E2.3 at X = 0 on the same draws (the level readings of the E2.3 records);
    ``s24b``: E2.4b (``runs`` snapshots); ``bench``: the benchmark (three setups, 100 samples). At :data:`SEED`
    and the runs of :data:`RUNS` they are the chapter's own.

    Parameters
    ----------
    key : str
        A key of :data:`RUNS`.
    seed : int
        Base seed (each study adds its :data:`SEED_OFFSETS`).
    runs : int, optional
        Default: the chapter's (:data:`RUNS`).

    Returns
    -------
    Study
        The study's output (the same object on every call with the same arguments: do not modify it).
    """
    seed = check_seed(seed)
    key = one_of(key, tuple(RUNS), "key")
    return _study(key, seed, int(RUNS[key] if runs is None else count(runs, "runs")))


@study_cache(maxsize=16)
def _study(key: str, seed: int, runs: int) -> Study:
    from fusion.scenarios import lecture_weighting as sc

    sd = tuple(seed + o for o in SEED_OFFSETS[key])
    if key == "s21":
        return sc.awf_study(sigma=(0.5, 1.0, 2.0, 4.0), levels=(0.0, 10.0, 100.0, 900.0, 1000.0), k_max=1000,
                            runs=runs, seed=sd[0])
    if key == "sreg":
        return sc.regime_study(runs=runs, seed=sd[0])
    if key == "schg":
        return sc.variance_change_study(runs=runs, seed=sd[0])
    if key == "s23":
        return sc.consistency_study(x=900.0, bias=30.0, runs=runs, seed=sd[0])
    if key == "s23x0":
        return sc.consistency_study(x=0.0, bias=30.0, runs=runs, seed=sd[0])
    if key == "s24b":
        return sc.belief_parameter_study(params=(0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0, 32.0), grid=(0.5, 1.0, 2.0, 4.0),
                                         snapshots=runs, seed=sd[0])
    return sc.benchmark(seeds=sd, runs=runs, samples=100)


def _bench_seeds(bench: Mapping[tuple[int, float, bool], Any]) -> list[int]:
    """The benchmark's seeds, in its order (one per name of :data:`BENCH_SEEDS`)."""
    seeds = list(dict.fromkeys(k[0] for k in bench))
    if len(seeds) != len(BENCH_SEEDS):
        raise ValueError(f"the benchmark must have {len(BENCH_SEEDS)} setups (seeds), got {seeds}")
    return seeds


class _Studies(Mapping):
    """The studies of :func:`study` at one base seed and run count, computed when first read."""

    def __init__(self, seed: int, runs: int) -> None:
        self.seed, self.runs = seed, runs

    def __getitem__(self, key: str) -> Study:
        if key not in RUNS:
            raise KeyError(key)
        return study(key, self.seed, self.runs)

    def __iter__(self) -> Iterator[str]:
        return iter(RUNS)

    def __len__(self) -> int:
        return len(RUNS)
