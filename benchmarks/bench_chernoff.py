"""Source 004: the cost of chapter 06's tracking study, batched against the per-run loop, and by stage.

Runs the chapter's study configuration (`fusion.book.chapters.chernoff.study_scenario`: the default scenario of
`fusion.scenarios.range_bearing`, 30 frames, 2,000 particles per node, R = 2,000 importance samples, 10,000
centralised particles, with the readings of steps D, F and G6) on the chapter's seeds and records, in one process:

* the study's runs (default 100, the chapter's) by `run_tracking` called run by run (the per-run loop), by
  `run_tracking_batch` in this process, and by `run_tracking_batch` with the chapter's two worker processes
  (issue 19: <= 60 s for 100 runs on 2 cores), and whether the three give identical results (every record, digit for
  digit);
* the seconds per frame of each stage in the batched runs (particle filters, weighted EM, the first-order fusion,
  sampling, densities, the swarm, SLSQP on the same samples, the literal stopping rule, ...): the chapter's
  cost-by-stage table;
* the swarm against SLSQP on the same importance samples (their time ratio);
* the weighted EM of one run's 3 nodes per call against 30 nodes per call.

The machine's load average before and after is stored with the results: timings taken while other
processes run are not comparable (re-run on an idle machine before committing the results). Records them in
`benchmarks/results/chernoff.json` with ``schema`` = :data:`SCHEMA`; chapter 06 reads this file and treats one without
that schema as not measured for the current pipeline.

Run: `.venv/bin/python benchmarks/bench_chernoff.py [runs]` (default 100, about 5 CPU-minutes on an idle machine);
`--tiny` runs 2 runs of a 3-frame study with few particles and writes `benchmarks/results/chernoff_tiny.json`
(a check that the script works, not a measurement to commit).
"""

from __future__ import annotations

import dataclasses
import os
import sys
import time

import numpy as np

from fusion.book.chapters.chernoff import BENCH_SCHEMA as SCHEMA
from fusion.book.chapters.chernoff import STUDY_WORKERS, study_scenario
from fusion.estimates import chernoff as ch
from fusion.estimates import mixtures as mx
from fusion.optimise.swarm import particle_swarm
from fusion.scenarios import range_bearing as dist
from fusion.scenarios import two_mixtures
from _results import write_results  # benchmarks/_results.py (scripts run from anywhere)

SEED = 2017
STAGES = {
    "particle_filters": "B: local particle filters (3 nodes)",
    "em": "C: weighted EM (3 nodes)",
    "first_order": "D: first-order fusion",
    "sampling": "E: sampling g",
    "densities": "F: log g and the local mixture densities at the samples",
    "optimiser": "G: particle swarm",
    "weights": "H-I: fused weights and estimate",
    "reference": "SLSQP on the same samples (reference)",
    "redraw": "redrawing at eps* (variant)",
    "gaussian_baselines": "Gaussian baselines (naive product, CI)",
    "variants": "variant eps0 = previous eps* and the readings of D and F (D-I again)",
    "literal_stop": "G6 as worded, read from the traced swarm",
    "centralised_pf": "centralised PF and resampling",
}


def identical(a: list[dist.TrackingRun], b: list[dist.TrackingRun]) -> bool:
    """Every record of two lists of runs equal, digit for digit (timings aside)."""
    for ra, rb in zip(a, b, strict=True):
        for f in dataclasses.fields(dist.TrackingRun):
            if f.name == "timings":
                continue
            va, vb = getattr(ra, f.name), getattr(rb, f.name)
            pairs = [(va[k], vb[k]) for k in va] if isinstance(va, dict) else [(va, vb)]
            if isinstance(va, dict) and va.keys() != vb.keys():
                return False
            if not all((x is None and y is None) or np.array_equal(x, y, equal_nan=True) for x, y in pairs):
                return False
    return True


def study_costs(sc: dist.RangeBearingScenario, runs: int, workers: int = 2
                ) -> tuple[dict[str, float], bool, dict[str, float]]:
    """Seconds for ``runs`` runs of the study: per-run loop, batched in this process, batched with ``workers``.

    Returns the three times (keys ``loop``, ``batch``, ``batch_workers``), whether the three results are identical,
    and the seconds per frame of each stage in the batched runs (this process).
    """
    def seeds() -> list[np.random.SeedSequence]:  # fresh: a SeedSequence spawns new children at every spawn
        return np.random.SeedSequence(SEED).spawn(runs)

    t0 = time.perf_counter()
    loop = [dist.run_tracking(sc, s) for s in seeds()]
    t1 = time.perf_counter()
    batch = dist.run_tracking_batch(sc, seeds())
    t2 = time.perf_counter()
    batch2 = dist.run_tracking_batch(sc, seeds(), workers=workers)
    t3 = time.perf_counter()
    total: dict[str, float] = {}
    for r in batch:
        t = r.timings           # TrackingTimings: the run's stages and the first fusion's (FusionTimings)
        stages = {f.name: getattr(t, f.name) for f in dataclasses.fields(t) if f.name != "fusion"}
        for k, v in (stages | dataclasses.asdict(t.fusion)).items():
            total[k] = total.get(k, 0.0) + v
    seconds = {"loop": t1 - t0, "batch": t2 - t1, "batch_workers": t3 - t2}
    return seconds, identical(loop, batch) and identical(batch, batch2), {k: v / (runs * sc.frames)
                                                                          for k, v in total.items()}


def pso_vs_slsqp(repeats: int = 20) -> tuple[float, float, float]:
    """Mean seconds of PSO and of SLSQP on the same toy importance samples, and their ratio."""
    rng = np.random.default_rng(SEED)
    toy = two_mixtures.toy_mixtures()
    gms = [toy.a, toy.b, toy.a]
    g = ch.first_order_fusion(gms, np.full(3, 1 / 3)).mixture
    xs = mx.gm_sample(g, rng, 2000)
    L, lg = ch.log_densities(gms, xs), mx.gm_logpdf(g, xs)
    t_pso = t_sl = 0.0
    for _ in range(repeats):
        t0 = time.perf_counter()
        particle_swarm(lambda E: -ch.is_objective(L, lg, E), 3, rng)
        t1 = time.perf_counter()
        ch.simplex_minimum(L, lg)
        t2 = time.perf_counter()
        t_pso += t1 - t0
        t_sl += t2 - t1
    return t_pso / repeats, t_sl / repeats, t_pso / t_sl


def em_batch_sizes(runs: int = 10, n: int = 2000) -> tuple[float, float]:
    """Seconds per node problem of 20 EM iterations: one run's 3 nodes per call vs all runs' nodes at once."""
    rng = np.random.default_rng(SEED)
    B = 3 * runs
    X = rng.standard_normal((B, n, 4)) * [30.0, 3.0, 30.0, 3.0]
    X[:, : n // 3, 0] += 60.0
    W = rng.uniform(size=(B, n)) ** 3

    def per_run() -> float:
        t0 = time.perf_counter()
        for j in range(runs):
            mx.weighted_em_batch(X[3 * j:3 * j + 3], W[3 * j:3 * j + 3], 3,
                                 [np.random.default_rng(b) for b in range(3)], max_iter=20, tol=0.0)
        return time.perf_counter() - t0

    def together() -> float:
        t0 = time.perf_counter()
        mx.weighted_em_batch(X, W, 3, [np.random.default_rng(b) for b in range(B)], max_iter=20, tol=0.0)
        return time.perf_counter() - t0

    a1, b1, b2, a2 = per_run(), together(), together(), per_run()  # ABBA, the smaller of each kept
    return min(a1, a2) / B, min(b1, b2) / B


def main() -> None:
    tiny = "--tiny" in sys.argv
    args = [x for x in sys.argv[1:] if not x.startswith("--")]
    runs = int(args[0]) if args else (2 if tiny else 100)
    load_before = os.getloadavg()[0]
    study = study_scenario()
    if tiny:  # a check that the script runs, not a measurement
        study = dataclasses.replace(study, frames=3, n_particles=200, n_samples=200, n_central=400, em_iterations=3)
    seconds, same, per_frame = study_costs(study, runs, workers=STUDY_WORKERS)
    t_pso, t_sl, ratio = pso_vs_slsqp(3 if tiny else 20)
    one, many = em_batch_sizes(2 if tiny else 10, 200 if tiny else 2000)
    what = f"004 study ({runs} runs of the chapter's configuration)"
    measurements = [
        {"what": f"{what}: seconds, run_tracking run by run (loop)", "value": seconds["loop"], "unit": "s",
         "key": "loop_seconds"},
        {"what": f"{what}: seconds, run_tracking_batch in one process", "value": seconds["batch"], "unit": "s",
         "key": "study_seconds"},
        {"what": f"{what}: seconds, run_tracking_batch with {STUDY_WORKERS} worker processes (the chapter's)",
         "value": seconds["batch_workers"], "unit": "s", "key": "study_seconds_workers"},
        {"what": f"{what}: time(loop) / time(batch, one process)", "value": seconds["loop"] / seconds["batch"],
         "unit": "x", "key": "loop_over_batch"},
        {"what": f"{what}: loop, batch and batch with workers identical (1 = every record)", "value": float(same),
         "unit": "", "key": "identical"},
    ]
    measurements += [{"what": f"004 study, {STAGES[name]}: seconds per frame", "value": v, "unit": "s",
                      "stage": name} for name, v in per_frame.items() if name in STAGES]
    measurements += [
        {"what": "004: time(PSO) on 2000 samples, N = 3", "value": t_pso, "unit": "s"},
        {"what": "004: time(SLSQP) on the same samples", "value": t_sl, "unit": "s"},
        {"what": "004: time(PSO) / time(SLSQP)", "value": ratio, "unit": "x", "key": "pso_over_slsqp"},
        {"what": "004: weighted EM, s per node problem, batches of one run (3 nodes)", "value": one, "unit": "s"},
        {"what": "004: weighted EM, s per node problem, 10 runs batched (30 nodes)", "value": many, "unit": "s"},
    ]
    write_results("chernoff_tiny" if tiny else "chernoff", measurements, schema=SCHEMA, runs=runs,
                  workers=STUDY_WORKERS, scenario="study_scenario()" + (" (tiny)" if tiny else ""),
                  load_average=[round(load_before, 2), round(os.getloadavg()[0], 2)],
                  blas_threads=os.environ.get("OPENBLAS_NUM_THREADS", "default"))


if __name__ == "__main__":
    main()
