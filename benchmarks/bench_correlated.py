"""Source 003 sec. 2.7: is the LDL^T pseudo-measurement fusion cheaper than the Markov (GLS) estimate?

Three implementations of the same estimate, timed side by side on the same data in one run:
GLS with an explicit inverse of R (what the lecture's "complexity greatly reduced" compares
against), GLS with a Cholesky factor (`scipy.linalg.cho_factor`/`cho_solve`, `fusion.correlated.gls`)
and the LDL^T pseudo-measurement route (`fusion.correlated.pseudo_measurement_fusion`).
Records the ratios in `benchmarks/results/correlated.json`.

Run: `.venv/bin/python benchmarks/bench_correlated.py`
"""

from __future__ import annotations

import json
import os
import platform
import time
from datetime import date
from pathlib import Path

import numpy as np

from fusion import correlated as co

REPEATS = 5


def best_of(fn, repeats: int = REPEATS) -> float:
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def explicit_inverse(H: np.ndarray, R: np.ndarray, z: np.ndarray) -> np.ndarray:
    Ri = np.linalg.inv(R)
    return np.linalg.solve(H.T @ Ri @ H, H.T @ Ri @ z)


def problem(n_sensors: int, rng: np.random.Generator):
    sig = rng.uniform(1, 3, size=n_sensors)
    R = np.kron(np.diag(sig**2), np.eye(2)) + 1.5**2 * np.kron(np.ones((n_sensors, n_sensors)), np.eye(2))
    H = np.kron(np.ones((n_sensors, 1)), np.eye(2))
    z = H @ np.array([1.0, -2.0]) + np.linalg.cholesky(R) @ rng.normal(size=2 * n_sensors)
    return H, R, z


def main() -> None:
    rng = np.random.default_rng(0)
    measurements = []
    for n_sensors in (3, 30, 300, 1000):
        H, R, z = problem(n_sensors, rng)
        x_ref = co.gls(H, R, z)[0]
        assert np.allclose(explicit_inverse(H, R, z), x_ref) and np.allclose(co.pseudo_measurement_fusion(H, R, z)[0], x_ref)
        t_inv = best_of(lambda: explicit_inverse(H, R, z))
        t_cho = best_of(lambda: co.gls(H, R, z))
        t_ldl = best_of(lambda: co.pseudo_measurement_fusion(H, R, z))
        Nm = 2 * n_sensors
        measurements += [
            {"what": f"Nm={Nm}: explicit inverse / LDL^T", "value": t_inv / t_ldl, "unit": "x"},
            {"what": f"Nm={Nm}: Cholesky GLS / LDL^T", "value": t_cho / t_ldl, "unit": "x"},
        ]
    record = {
        "date": date.today().isoformat(),
        "machine": f"{platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}",
        "measurements": measurements,
    }
    out = Path(__file__).parent / "results" / "correlated.json"
    out.write_text(json.dumps(record, indent=2) + "\n", encoding="utf-8")
    for m in measurements:
        print(f"{m['what']:45s} {m['value']:10.3g} {m['unit']}")


if __name__ == "__main__":
    main()
