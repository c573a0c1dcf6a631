"""Source 003 sec. 2.7: is the LDL^T pseudo-measurement fusion cheaper than the Markov (GLS) estimate?

Three kernels of the same estimate (no input validation), timed side by side on the same data
in one run: GLS with an explicit inverse of R (what the lecture's "complexity greatly reduced"
compares against), GLS with a Cholesky factor (`scipy.linalg.cho_factor`/`cho_solve`) and the
LDL^T pseudo-measurement route; plus the two validated package functions
(`fusion.readings.correlated.gls`, `fusion.readings.correlated.pseudo_measurement_fusion`). A ratio above 1 means
the LDL^T route is faster.
Records the ratios in `benchmarks/results/correlated.json`.

Run: `.venv/bin/python benchmarks/bench_correlated.py`
"""

from __future__ import annotations

import time

import numpy as np
from scipy.linalg import cho_factor, cho_solve, solve_triangular

from fusion.readings import correlated as co
from _results import write_results  # benchmarks/_results.py (scripts run from anywhere)

REPEATS = 5


def best_of(fn, repeats: int = REPEATS) -> float:
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def explicit_inverse(H: np.ndarray, R: np.ndarray, z: np.ndarray) -> np.ndarray:
    """Markov estimate with R^{-1} formed explicitly (no input validation)."""
    Ri = np.linalg.inv(R)
    return np.linalg.solve(H.T @ Ri @ H, H.T @ Ri @ z)


def cholesky_gls(H: np.ndarray, R: np.ndarray, z: np.ndarray) -> np.ndarray:
    """Markov estimate through a Cholesky factor (no input validation)."""
    c = cho_factor(R, lower=True)
    RiH = cho_solve(c, H)
    return np.linalg.solve(H.T @ RiH, RiH.T @ z)


def ldl_pseudo(H: np.ndarray, R: np.ndarray, z: np.ndarray) -> np.ndarray:
    """LDL^T pseudo-measurements y = L^{-1} z, G = L^{-1} H, scaled by 1/d (no input validation)."""
    C = np.linalg.cholesky(R)
    dg = np.diag(C)
    L = C / dg[None, :]
    y = solve_triangular(L, z, lower=True, unit_diagonal=True)
    G = solve_triangular(L, H, lower=True, unit_diagonal=True)
    Gd = G / (dg**2)[:, None]
    return np.linalg.solve(G.T @ Gd, Gd.T @ y)


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
        x_ref = co.gls(H, R, z).x
        for fn in (explicit_inverse, cholesky_gls, ldl_pseudo):
            assert np.allclose(fn(H, R, z), x_ref)
        assert np.allclose(co.pseudo_measurement_fusion(H, R, z).x, x_ref)
        t_inv = best_of(lambda: explicit_inverse(H, R, z))
        t_cho = best_of(lambda: cholesky_gls(H, R, z))
        t_ldl = best_of(lambda: ldl_pseudo(H, R, z))
        t_pkg_gls = best_of(lambda: co.gls(H, R, z))
        t_pkg_ldl = best_of(lambda: co.pseudo_measurement_fusion(H, R, z))
        Nm = 2 * n_sensors
        measurements += [
            {"what": f"Nm={Nm}: time(explicit inverse) / time(LDL^T)", "value": t_inv / t_ldl, "unit": "x"},
            {"what": f"Nm={Nm}: time(Cholesky GLS) / time(LDL^T)", "value": t_cho / t_ldl, "unit": "x"},
            {"what": f"Nm={Nm}: package gls / pseudo_measurement_fusion (validated)", "value": t_pkg_gls / t_pkg_ldl, "unit": "x"},
        ]
    write_results("correlated", measurements)


if __name__ == "__main__":
    main()
