"""Vectorised readings-level fusion against a per-epoch Python loop, side by side.

The Monte-Carlo studies fuse tens of thousands of epochs; `fusion.readings.fuse_epochs`
does all epochs in one numpy pass. This script measures both ways on the same data in
one run and records the ratio in `benchmarks/results/readings.json`.

Run: `.venv/bin/python benchmarks/bench_readings.py`
"""

from __future__ import annotations

import json
import os
import platform
import time
from datetime import date
from pathlib import Path

import numpy as np

from fusion import readings as rd
from fusion.scenarios import thermocouples

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
    record = {
        "date": date.today().isoformat(),
        "machine": f"{platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}",
        "measurements": measurements,
    }
    out = Path(__file__).parent / "results" / "readings.json"
    out.write_text(json.dumps(record, indent=2) + "\n", encoding="utf-8")
    for m in measurements:
        print(f"{m['what']:60s} {m['value']:10.4g} {m['unit']}")


if __name__ == "__main__":
    main()
