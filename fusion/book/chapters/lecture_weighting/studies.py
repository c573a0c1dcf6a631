r"""The seeded studies of chapter 02 that its stochastic records use (:func:`study`, cached), and the
deletion-rule baseline on the benchmark's draws."""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator, Mapping
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
    seed = check_seed(seed, span=max(SEED_OFFSETS[key]))   # its studies' seed + offset, each a seed (fuzz 55 D1)
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


def _counted(key: str, runs: int) -> Callable[[], int]:
    """The own budget of :func:`study` ``(key, runs)`` as ``_study`` calls it (the scenario's defaults, read
    from its signature), for ``fusion.book._study_budget.studies_first``: the regime study's draws within its
    ``STUDY_WORK`` entry, the variance-change study's draws and changes, E2.3's pair-checks (fuzz 62a)."""
    import inspect

    from fusion._limits import REGIME_STUDY, STUDY_WORK
    from fusion.scenarios.lecture_weighting import consistency as cs
    from fusion.scenarios.lecture_weighting import regime as rg

    fn = {"sreg": rg.regime_study, "schg": rg.variance_change_study}.get(key, cs.consistency_study)
    d = {k: v.default for k, v in inspect.signature(fn).parameters.items()}
    n, samples = len(d["sigma"]), d["samples"]
    if key == "sreg":
        return lambda: rg._draws_budget(runs, samples, n, rg._REGIME_DRAW, "runs", STUDY_WORK[REGIME_STUDY])
    if key == "schg":
        changes = len(d["changes"])

        def change() -> int:  # its two checks in its order; the second's units hold the first's draws
            rg._draws_budget(runs, samples, n, rg._CHANGE_DRAW + rg._CHANGE_DRAW_EACH * changes, "runs")
            return rg._change_work(runs, samples, n, changes, "runs")
        return change
    return lambda: cs._consistency_work(runs, samples, n, d["curve_draws"], "runs")


#: The studies ``_reads_budget`` counts: those a reader runs with another at one ``runs`` (the regime and
#: variance-change studies of ``lec-awf-adapts``, E2.3 at X = 900 and X = 0 of the E2.3 records).
_COUNTED: tuple[str, ...] = ("sreg", "schg", "s23", "s23x0")


def _reads_budget(reads: Iterable[tuple[str, int]]) -> int:
    """Rule 17 of a chapter 02 reader that runs several studies of :func:`study`: each (key, runs) of ``reads`` by
    its own budget (``_counted``) and their sum, before any study, refused naming ``runs``.

    One reading of ``lec-awf-accuracy`` ran E2.3 at X = 900 and then at X = 0 on the same runs, each checked alone,
    and ``lec-awf-adapts``'s readings (:func:`fusion.book.chapters.lecture.evidence_at`) ran the regime study (2,000
    runs its edge, ~36 CPU-s at 1,800) before the variance-change study (edge 1,723) refused naming its own
    ``runs, samples, sigma and changes`` (fuzz 62a). The sum's budget is the one rule of fix61a
    (``fusion.book._study_budget.studies_first``): ``MAX_WORK``, or the ``STUDY_WORK`` entry of a study it counts
    that has one (the regime study's, which the book's 10x call of that record serves). A key outside
    ``_COUNTED`` is left to its own check, at its start (the benchmark's own pair-work check refuses above 5,555
    runs, above E2.3's summed edge of 2,415; the others are read alone)."""
    from fusion._limits import MAX_WORK, REGIME_STUDY, STUDY_WORK
    from fusion.book._study_budget import studies_first

    reads = sorted({(k, r) for k, r in reads if k in _COUNTED})
    regime = any(k == "sreg" for k, _ in reads)
    return studies_first([_counted(k, r) for k, r in reads], "runs",
                         STUDY_WORK[REGIME_STUDY] if regime else MAX_WORK, REGIME_STUDY if regime else None)


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
