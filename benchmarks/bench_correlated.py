"""Source 003 sec. 2.7: is the LDL^T pseudo-measurement fusion cheaper than the Markov (GLS) estimate?

Four kernels of the same estimate (no input validation), timed side by side on the same data
in one run: GLS with an explicit inverse of R (what the lecture's "complexity greatly reduced"
compares against), GLS with a Cholesky factor (`scipy.linalg.cho_factor`/`cho_solve`), the
LDL^T pseudo-measurement route, and the eigen-decorrelation route the lecture sets aside
(`numpy.linalg.eigh`); plus the two validated package functions
(`fusion.readings.correlated.gls`, `fusion.readings.correlated.pseudo_measurement_fusion`). A ratio above 1 means
the LDL^T route is faster. Beside each measured ratio the same ratio of the leading operation
counts of `fusion.readings.correlated.operation_counts` is stored (key `..._flops`), so the model
and the measurement can be compared directly. Each time is the best of REPEATS repetitions of a
loop long enough to last about LOOP_S seconds. The machine has 2 cores shared with other jobs:
ratios move by tens of per cent from run to run.
The routes are timed round-robin (one loop of each route per round, best round kept) so that a
load spike affects every route alike, with one BLAS thread (``OPENBLAS_NUM_THREADS=1``, set
before numpy is imported): on a shared 2-core machine a multi-threaded BLAS spin-waits for a busy
core and produced ratios off by two orders of magnitude.
Records the ratios in `benchmarks/results/correlated.json`.

Run: `.venv/bin/python benchmarks/bench_correlated.py`
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import time  # noqa: E402

import numpy as np  # noqa: E402
from scipy.linalg import cho_factor, cho_solve, solve_triangular

from fusion.readings import correlated as co
from _results import write_results  # benchmarks/_results.py (scripts run from anywhere)

REPEATS = 7
LOOP_S = 0.05


def round_robin(fns: dict, repeats: int = REPEATS) -> dict:
    """Best time per call of each function, timed in alternation over ``repeats`` rounds.

    Each round runs, for every function in turn, a loop of enough calls to last about LOOP_S
    seconds (the loop length is fixed per function from a first call).
    """
    loops = {}
    for k, fn in fns.items():
        t0 = time.perf_counter()
        fn()
        loops[k] = max(1, int(LOOP_S / max(time.perf_counter() - t0, 1e-7)))
    best = {k: float("inf") for k in fns}
    for _ in range(repeats):
        for k, fn in fns.items():
            t0 = time.perf_counter()
            for _ in range(loops[k]):
                fn()
            best[k] = min(best[k], (time.perf_counter() - t0) / loops[k])
    return best


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


def eigen_route(H: np.ndarray, R: np.ndarray, z: np.ndarray) -> np.ndarray:
    """Eigen-decorrelation y = Q^T z, G = Q^T H, scaled by 1/lambda (no input validation)."""
    lam, Q = np.linalg.eigh(R)
    y = Q.T @ z
    G = Q.T @ H
    Gl = G / lam[:, None]
    return np.linalg.solve(G.T @ Gl, Gl.T @ y)


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
        for fn in (explicit_inverse, cholesky_gls, ldl_pseudo, eigen_route):
            assert np.allclose(fn(H, R, z), x_ref)
        assert np.allclose(co.pseudo_measurement_fusion(H, R, z).x, x_ref)
        t = round_robin({"inv": lambda: explicit_inverse(H, R, z), "cho": lambda: cholesky_gls(H, R, z),
                         "ldl": lambda: ldl_pseudo(H, R, z), "eig": lambda: eigen_route(H, R, z),
                         "pkg_gls": lambda: co.gls(H, R, z), "pkg_ldl": lambda: co.pseudo_measurement_fusion(H, R, z)})
        t_inv, t_cho, t_ldl, t_eig, t_pkg_gls, t_pkg_ldl = (t[k] for k in ("inv", "cho", "ldl", "eig", "pkg_gls", "pkg_ldl"))
        Nm = 2 * n_sensors
        fl = co.operation_counts(Nm, 2)
        measurements += [
            {"what": f"Nm={Nm}: time(explicit inverse) / time(LDL^T)", "value": t_inv / t_ldl, "unit": "x",
             "key": f"inv_{Nm}"},
            {"what": f"Nm={Nm}: flops(explicit inverse) / flops(LDL^T)", "value": fl["explicit"] / fl["ldl"], "unit": "x",
             "key": f"inv_{Nm}_flops"},
            {"what": f"Nm={Nm}: time(Cholesky GLS) / time(LDL^T)", "value": t_cho / t_ldl, "unit": "x",
             "key": f"chol_{Nm}"},
            {"what": f"Nm={Nm}: flops(Cholesky GLS) / flops(LDL^T)", "value": fl["cholesky"] / fl["ldl"], "unit": "x",
             "key": f"chol_{Nm}_flops"},
            {"what": f"Nm={Nm}: time(eigen-decorrelation) / time(LDL^T)", "value": t_eig / t_ldl, "unit": "x",
             "key": f"eig_{Nm}"},
            {"what": f"Nm={Nm}: flops(eigen-decorrelation) / flops(LDL^T)", "value": fl["eigen"] / fl["ldl"], "unit": "x",
             "key": f"eig_{Nm}_flops"},
            {"what": f"Nm={Nm}: package gls / pseudo_measurement_fusion (validated)", "value": t_pkg_gls / t_pkg_ldl, "unit": "x",
             "key": f"pkg_{Nm}"},
        ]
    write_results("correlated", measurements, repeats=REPEATS, loop_seconds=LOOP_S,
                  blas_threads=os.environ["OPENBLAS_NUM_THREADS"])


if __name__ == "__main__":
    main()
