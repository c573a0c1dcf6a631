"""Source 004: cost of the patent's pipeline by stage, and the swarm against SLSQP.

Runs the designed scenario of chapter 06 (`fusion.scenarios.range_bearing`) for a few Monte-Carlo runs and
records the mean wall time per frame of each stage (local particle filters, weighted EM, the
first-order fusion, sampling, mixture densities, the swarm, SLSQP on the same samples, ...), plus
the ratio time(PSO) / time(SLSQP) measured side by side on the same importance samples.
Also (issue 19) the per-run loop against the batched runner in the same process: seconds per run
of `run_tracking` called run by run and of `run_tracking_batch` on the same seeds (their results are
identical, tests/test_chernoff.py), for the default scenario and the chapter's study scenario, the
100-run cost extrapolated from them, and the weighted EM of many runs' nodes batched at once
against one run's nodes at a time (the kernel is memory-bound: large batches are slower).
Records them in `benchmarks/results/chernoff.json`; chapter 06 shows this file.

Run: `.venv/bin/python benchmarks/bench_chernoff.py [runs]`
"""

from __future__ import annotations

import os
import sys
import time

import numpy as np

from fusion.estimates import chernoff as ch
from fusion.scenarios import two_mixtures
from fusion.scenarios import range_bearing as dist
from fusion.estimates import mixtures as mx
from fusion.optimise.swarm import particle_swarm
from fusion.book.chapters.chernoff import study_scenario
from _results import write_results  # benchmarks/_results.py (scripts run from anywhere)

SEED = 2017
STAGES = {
    "particle filters": "B: local particle filters (3 nodes)",
    "EM": "C: weighted EM (3 nodes)",
    "foa": "D: first-order fusion",
    "sampling": "E: sampling g and evaluating log g",
    "densities": "F: local mixture densities at the samples",
    "optimiser": "G: particle swarm",
    "weights": "H-I: fused weights and estimate",
    "reference": "SLSQP on the same samples (reference)",
    "redraw": "redrawing at eps* (variant)",
    "Gaussian baselines": "Gaussian baselines (naive product, CI)",
    "variants": "variant eps0 = previous eps* (D-I again)",
    "centralised PF and resampling": "centralised PF and resampling",
}


def stage_times(runs: int) -> dict[str, float]:
    sc = dist.RangeBearingScenario()
    total: dict[str, float] = {}
    for r in range(runs):
        run = dist.run_tracking(sc, np.random.SeedSequence([SEED, 10_000 + r]))
        for k, v in run.timings.items():
            total[k] = total.get(k, 0.0) + v
    return {k: v / (runs * sc.frames) for k, v in total.items()}


def pso_vs_slsqp(repeats: int = 20) -> tuple[float, float, float]:
    """Mean seconds of PSO and of SLSQP on the same toy importance samples, and their ratio."""
    rng = np.random.default_rng(SEED)
    toy = two_mixtures.toy_mixtures()
    gA, gB = toy.a, toy.b
    gms = [gA, gB, gA]
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


def loop_vs_batch(sc: dist.RangeBearingScenario, runs: int) -> tuple[float, float]:
    """Seconds per run: run_tracking run by run, and run_tracking_batch on the same seeds.

    Measured in the order loop, batch, batch, loop and the smaller time of each kept, so that a
    burst of load from other processes on the shared machine biases neither.
    """
    def loop() -> float:
        t0 = time.perf_counter()
        for s in np.random.SeedSequence(SEED).spawn(runs):
            dist.run_tracking(sc, s)
        return time.perf_counter() - t0

    def batch() -> float:
        t0 = time.perf_counter()
        dist.run_tracking_batch(sc, np.random.SeedSequence(SEED).spawn(runs))
        return time.perf_counter() - t0

    a1, b1, b2, a2 = loop(), batch(), batch(), loop()
    return min(a1, a2) / runs, min(b1, b2) / runs


def em_batch_sizes(runs: int = 10, n: int = 2000) -> tuple[float, float]:
    """Seconds per node problem of 20 EM iterations: one run's 3 nodes per batch vs all runs' nodes at once."""
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
    runs = int(sys.argv[1]) if len(sys.argv) > 1 else 5
    per_frame = stage_times(runs)
    t_pso, t_sl, ratio = pso_vs_slsqp()
    measurements = [{"what": f"004 scenario, {STAGES[name]}: seconds per frame", "value": v, "unit": "s",
                     "stage": name} for name, v in per_frame.items() if name in STAGES]
    measurements += [
        {"what": "004: time(PSO) on 2000 samples, N = 3", "value": t_pso, "unit": "s"},
        {"what": "004: time(SLSQP) on the same samples", "value": t_sl, "unit": "s"},
        {"what": "004: time(PSO) / time(SLSQP)", "value": ratio, "unit": "x"},
    ]
    for label, sc in (("default scenario", dist.RangeBearingScenario()), ("study scenario of chapter 06", study_scenario())):
        loop, batch = loop_vs_batch(sc, runs)
        measurements += [
            {"what": f"004 {label}: seconds per run, run_tracking run by run (loop)", "value": loop, "unit": "s"},
            {"what": f"004 {label}: seconds per run, run_tracking_batch (same seeds)", "value": batch, "unit": "s"},
            {"what": f"004 {label}: time(loop) / time(batch)", "value": loop / batch, "unit": "x"},
            {"what": f"004 {label}: 100 runs, batched (extrapolated)", "value": 100 * batch, "unit": "s"},
        ]
    one, many = em_batch_sizes()
    measurements += [
        {"what": "004: weighted EM, s per node problem, batches of one run (3 nodes)", "value": one, "unit": "s"},
        {"what": "004: weighted EM, s per node problem, 10 runs batched (30 nodes)", "value": many, "unit": "s"},
    ]
    write_results("chernoff", measurements, runs=runs)


if __name__ == "__main__":
    main()
