"""Source 004: the cost of chapter 06's tracking study, batched against the per-run loop, and by stage.

Runs the designed scenario of chapter 06 (`fusion.scenarios.range_bearing`, default parameters:
30 frames, 2,000 particles per node, R = 2,000 importance samples, 10,000 centralised particles;
for the 100 runs, the chapter's study configuration `fusion.book.chapters.chernoff.study_scenario`,
which adds the readings of steps D, F and G6) and records, in one process:

* the per-run loop against the batched runner on the same seeds: seconds per run of
  `run_tracking` called run by run and of `run_tracking_batch` (ABBA order, the smaller time of
  each kept), their ratio, and whether their results are identical (every record, digit for digit);
* 100 runs of the study by `run_tracking_batch`, measured in this process and with two
  worker processes (issue 19: <= 60 s on 2 cores; the chapter runs them on two), and the seconds per frame of
  each stage in those runs (particle filters, weighted EM, the first-order fusion, sampling, densities, the
  swarm, SLSQP on the same samples, the literal stopping rule, ...);
* the swarm against SLSQP on the same importance samples (their time ratio);
* the weighted EM of one run's 3 nodes per call against 30 nodes per call.

The machine's load average before and after is stored with the results: timings taken while other
processes run are not comparable (re-run on an idle machine before committing the results).
Records them in `benchmarks/results/chernoff.json`; chapter 06 shows this file.

Run: `.venv/bin/python benchmarks/bench_chernoff.py [loop_runs] [batch_runs]` (defaults 5 and 100)
"""

from __future__ import annotations

import dataclasses
import os
import sys
import time

import numpy as np

from fusion.book.chapters.chernoff import study_scenario
from fusion.estimates import chernoff as ch
from fusion.estimates import mixtures as mx
from fusion.optimise.swarm import particle_swarm
from fusion.scenarios import range_bearing as dist
from fusion.scenarios import two_mixtures
from _results import write_results  # benchmarks/_results.py (scripts run from anywhere)

SEED = 2017
STAGES = {
    "particle filters": "B: local particle filters (3 nodes)",
    "EM": "C: weighted EM (3 nodes)",
    "foa": "D: first-order fusion",
    "sampling": "E: sampling g",
    "densities": "F: log g and the local mixture densities at the samples",
    "optimiser": "G: particle swarm",
    "weights": "H-I: fused weights and estimate",
    "reference": "SLSQP on the same samples (reference)",
    "redraw": "redrawing at eps* (variant)",
    "Gaussian baselines": "Gaussian baselines (naive product, CI)",
    "variants": "variant eps0 = previous eps* and the readings of D and F (D-I again)",
    "literal stop": "G6 as worded, read from the traced swarm",
    "centralised PF and resampling": "centralised PF and resampling",
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


def loop_vs_batch(sc: dist.RangeBearingScenario, runs: int) -> tuple[float, float, bool]:
    """Seconds per run of run_tracking run by run and of run_tracking_batch on the same seeds; identical?

    Measured in the order loop, batch, batch, loop and the smaller time of each kept, so that a
    burst of load from other processes biases neither.
    """
    out: dict[str, list[dist.TrackingRun]] = {}

    def seeds() -> list[np.random.SeedSequence]:  # fresh: a SeedSequence spawns new children at every spawn
        return np.random.SeedSequence(SEED).spawn(runs)

    def loop() -> float:
        t0 = time.perf_counter()
        out["loop"] = [dist.run_tracking(sc, s) for s in seeds()]
        return time.perf_counter() - t0

    def batch() -> float:
        t0 = time.perf_counter()
        out["batch"] = dist.run_tracking_batch(sc, seeds())
        return time.perf_counter() - t0

    a1, b1, b2, a2 = loop(), batch(), batch(), loop()
    return min(a1, a2) / runs, min(b1, b2) / runs, identical(out["loop"], out["batch"])


def hundred(sc: dist.RangeBearingScenario, runs: int, workers: int = 1) -> tuple[float, dict[str, float]]:
    """Seconds for ``runs`` runs of run_tracking_batch (``workers`` processes), and the seconds per frame of each stage."""
    t0 = time.perf_counter()
    result = dist.run_tracking_batch(sc, np.random.SeedSequence(SEED).spawn(runs), workers=workers)
    seconds = time.perf_counter() - t0
    total: dict[str, float] = {}
    for r in result:
        for k, v in r.timings.items():
            total[k] = total.get(k, 0.0) + v
    return seconds, {k: v / (runs * sc.frames) for k, v in total.items()}


def pso_vs_slsqp(repeats: int = 20) -> tuple[float, float, float]:
    """Mean seconds of PSO and of SLSQP on the same toy importance samples, and their ratio."""
    rng = np.random.default_rng(SEED)
    toy = two_mixtures.toy_mixtures()
    gms = [toy.a, toy.b, toy.a]
    g = ch.foa_fusion(gms, np.full(3, 1 / 3)).mixture
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
    loop_runs = int(sys.argv[1]) if len(sys.argv) > 1 else 5
    batch_runs = int(sys.argv[2]) if len(sys.argv) > 2 else 100
    load_before = os.getloadavg()[0]
    sc = dist.RangeBearingScenario()
    loop, batch, same = loop_vs_batch(sc, loop_runs)
    study = study_scenario()
    seconds, per_frame = hundred(study, batch_runs)
    seconds2, _ = hundred(study, batch_runs, workers=2)
    t_pso, t_sl, ratio = pso_vs_slsqp()
    one, many = em_batch_sizes()
    measurements = [
        {"what": "004 default scenario: seconds per run, run_tracking run by run (loop)", "value": loop, "unit": "s"},
        {"what": "004 default scenario: seconds per run, run_tracking_batch (same seeds)", "value": batch, "unit": "s"},
        {"what": "004 default scenario: time(loop) / time(batch)", "value": loop / batch, "unit": "x"},
        {"what": "004 default scenario: batched results identical to the loop's (1 = every record)",
         "value": float(same), "unit": ""},
        {"what": f"004 study (default scenario with the readings): {batch_runs} runs, run_tracking_batch (measured)",
         "value": seconds, "unit": "s", "key": "study_seconds"},
        {"what": f"004 study (default scenario with the readings): {batch_runs} runs, run_tracking_batch, "
                 "2 worker processes (measured)", "value": seconds2, "unit": "s", "key": "study_seconds_2"},
    ]
    measurements += [{"what": f"004 scenario, {STAGES[name]}: seconds per frame", "value": v, "unit": "s",
                      "stage": name} for name, v in per_frame.items() if name in STAGES]
    measurements += [
        {"what": "004: time(PSO) on 2000 samples, N = 3", "value": t_pso, "unit": "s"},
        {"what": "004: time(SLSQP) on the same samples", "value": t_sl, "unit": "s"},
        {"what": "004: time(PSO) / time(SLSQP)", "value": ratio, "unit": "x"},
        {"what": "004: weighted EM, s per node problem, batches of one run (3 nodes)", "value": one, "unit": "s"},
        {"what": "004: weighted EM, s per node problem, 10 runs batched (30 nodes)", "value": many, "unit": "s"},
    ]
    write_results("chernoff", measurements, runs=batch_runs, loop_runs=loop_runs,
                  load_average=[round(load_before, 2), round(os.getloadavg()[0], 2)],
                  blas_threads=os.environ.get("OPENBLAS_NUM_THREADS", "default"))


if __name__ == "__main__":
    main()
