"""Vectorised readings-level fusion against a per-epoch Python loop, side by side.

The Monte-Carlo studies fuse tens of thousands of epochs; `fusion.readings.fuse_epochs`
does all epochs in one numpy pass. This script measures both ways on the same data in
one run and records the ratio in `benchmarks/results/readings.json`.

Run: `.venv/bin/python benchmarks/bench_readings.py`
"""

from __future__ import annotations

import time

import numpy as np

from fusion import readings as rd
from fusion.scenarios import thermocouples
from _results import write_results  # benchmarks/_results.py (scripts run from anywhere)

N_EPOCHS = 20_000
REPEATS = 3


def best_of(fn, repeats: int = REPEATS) -> float:
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def main() -> None:
    z = thermocouples.simulate(np.random.default_rng(0), n_samples=N_EPOCHS)
    measurements = []
    for method, single in [("optimal_fusion_set", rd.optimal_fusion_set), ("support_degree", rd.support_degree)]:
        vec = rd.fuse_epochs(z, method).values
        loop = np.array([single(row).value for row in z])
        assert np.allclose(vec, loop, atol=1e-9), "vectorised and looped results differ"
        t_vec = best_of(lambda: rd.fuse_epochs(z, method))
        t_loop = best_of(lambda: [single(row) for row in z], repeats=1)
        measurements += [
            {"what": f"{method}: vectorised, {N_EPOCHS} epochs x 10 sensors", "value": t_vec, "unit": "s"},
            {"what": f"{method}: Python loop, same data", "value": t_loop, "unit": "s"},
            {"what": f"{method}: speed-up of vectorisation", "value": t_loop / t_vec, "unit": "x"},
        ]
    write_results("readings", measurements)


if __name__ == "__main__":
    main()
