"""Source 004: cost of the patent's pipeline by stage, and the swarm against SLSQP.

Runs the designed scenario of chapter 06 (`fusion.scenarios.range_bearing`) for a few Monte-Carlo runs and
records the mean wall time per frame of each stage (local particle filters, weighted EM, the
first-order fusion, sampling, mixture densities, the swarm, SLSQP on the same samples, ...), plus
the ratio time(PSO) / time(SLSQP) measured side by side on the same importance samples.
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
    write_results("chernoff", measurements, runs=runs)


if __name__ == "__main__":
    main()
