r"""Correlated-noise cases of the lecture notes' §2.7: when ignoring the correlation costs a lot.

The lecture's own experiment (E2.7 of the chapter) couples every sensor to the common environment
with the same strength; then the naive fusion (correlation ignored) is nearly as accurate as GLS.
This module adds scalar cases (:math:`x` read directly by every sensor, :math:`H = \mathbf 1`) with

.. math:: R = \mathrm{diag}(\sigma_i^2) + \sigma_e^2\,cc^\top ,

own noise SDs :math:`\sigma_i`, a common environmental noise of SD :math:`\sigma_e` and coupling
coefficients :math:`c_i`. With unequal couplings GLS can cancel the common error by giving some
sensor a *negative* weight (:math:`\sum_iK_ic_i \approx 0`), which the naive fusion cannot.

References
----------
* Aitken, A. C. (1936). On least squares and linear combination of observations.
  *Proceedings of the Royal Society of Edinburgh*, 55, 42-48.
* An explanation of multi-sensor data fusion algorithms (多传感器数据融合算法讲解).
  Lecture notes, web copy (in Chinese; author and date not stated).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from fusion._validation import as_array, count, scalar
from fusion.readings import correlated as co

__all__ = ["SCENARIOS", "covariance", "coupling_study"]

#: Named cases: own noise SDs, coupling coefficients, SD of the common environmental noise.
SCENARIOS: dict[str, dict[str, tuple[float, ...] | float]] = {
    "equal coupling (as E2.7)": {"own": (1.0, 2.0, 3.0), "coupling": (1.0, 1.0, 1.0), "env": 1.5},
    "one sensor outside the environment": {"own": (1.0, 1.0, 1.0, 1.0), "coupling": (0.0, 1.0, 1.0, 1.0), "env": 2.0},
    "unequal coupling": {"own": (0.5, 1.0, 1.5), "coupling": (1.0, 2.0, 3.0), "env": 1.0},
    "unequal coupling, strong environment": {"own": (1.0, 1.0, 1.0), "coupling": (1.0, 2.0, 3.0), "env": 3.0},
    "two sensors, couplings 1 and 2": {"own": (0.5, 0.5), "coupling": (1.0, 2.0), "env": 3.0},
}


def covariance(own: ArrayLike, coupling: ArrayLike, env: float) -> np.ndarray:
    r"""Noise covariance :math:`R = \mathrm{diag}(\sigma_i^2) + \sigma_e^2cc^\top` of scalar sensors.

    Parameters
    ----------
    own : array_like, shape (N,)
        Own noise standard deviations :math:`\sigma_i > 0` (units of x).
    coupling : array_like, shape (N,)
        Coupling coefficients :math:`c_i` to the common noise (dimensionless, any sign).
    env : float
        Standard deviation :math:`\sigma_e \ge 0` of the common environmental noise.

    Returns
    -------
    ndarray, shape (N, N)
        Symmetric positive definite covariance.

    Raises
    ------
    ValueError
        Non-finite or non-positive own SDs, lengths that differ, negative ``env``.
    """
    s = as_array(own, "own", ndim=1)
    if s.size < 1 or np.any(s <= 0):
        raise ValueError(f"own must hold positive standard deviations, got {s}")
    c = as_array(coupling, "coupling", ndim=1)
    if c.shape != s.shape:
        raise ValueError(f"coupling must have the length of own ({s.size}), got {c.size}")
    e = scalar(env, "env", lo=0.0)
    return np.diag(s**2) + e**2 * np.outer(c, c)


def _exact(R: np.ndarray) -> dict[str, Any]:
    N = R.shape[0]
    H = np.ones((N, 1))
    K = co.gls_weights(H, R)[0]
    Kn = co.gls_weights(H, np.diag(np.diag(R)))[0]
    return {"K": K, "Kn": Kn, "mse_gls": float(K @ R @ K), "mse_naive": float(Kn @ R @ Kn),
            "claimed_naive": float(1.0 / np.sum(1.0 / np.diag(R)))}


def coupling_study(
    scenarios: Mapping[str, Mapping[str, Any]] | None = None,
    runs: int = 2000,
    x: float = 1.0,
    seed: int = 2711,
    env_grid: Sequence[float] = tuple(np.linspace(0.0, 5.0, 51)),
) -> dict[str, Any]:
    r"""GLS, its LDLᵀ and eigen routes, and the naive fusion on each correlated case.

    For each case: the GLS weights and the naive weights (inverse own variances), the exact
    MSEs :math:`KRK^\top`, Monte-Carlo per-run squared errors of GLS and naive (the same noise
    draws), the largest relative difference of the LDLᵀ and eigen routes from GLS, the naive
    fusion's mean NEES (actual over claimed variance), and the exact naive/GLS MSE ratio along
    ``env_grid`` with the case's own SDs and couplings.

    Parameters
    ----------
    scenarios : mapping, optional
        Name → ``{"own": ..., "coupling": ..., "env": ...}`` (default :data:`SCENARIOS`).
    runs : int
        Monte-Carlo runs per case (>= 2; the chapter uses >= 100).
    x : float
        True value.
    seed : int
        Seed of the noise (one stream, cases in order).
    env_grid : sequence of float
        Environmental SDs of the ratio curves (>= 0).

    Returns
    -------
    dict
        ``rows``: list of dicts per case (name, N, min GLS weight, exact MSEs, ratio, Monte-Carlo
        MSEs, naive NEES, route differences); ``sq``: name → (gls, naive) per-run squared errors;
        ``weights``: name → (K, Kn); ``env_grid``; ``curves``: name → ratio along ``env_grid``;
        ``runs``, ``seed``.

    Raises
    ------
    ValueError
        Bad scenario entries, ``runs`` < 2, negative ``seed`` or grid values.
    """
    sc = SCENARIOS if scenarios is None else scenarios
    if not isinstance(sc, Mapping) or not sc:
        raise ValueError("scenarios must be a non-empty mapping of name to case")
    count(runs, "runs", minimum=2)
    xv = scalar(x, "x")
    count(seed, "seed", minimum=0)
    grid = as_array(env_grid, "env_grid", ndim=1)
    if grid.size == 0 or np.any(grid < 0):
        raise ValueError("env_grid must be a non-empty sequence of SDs >= 0")
    rng = np.random.default_rng(seed)
    rows, sq, weights, curves = [], {}, {}, {}
    for name, case in sc.items():
        R = covariance(case["own"], case["coupling"], case["env"])
        N = R.shape[0]
        H = np.ones((N, 1))
        ex = _exact(R)
        z = xv + np.linalg.cholesky(R) @ rng.normal(size=(N, runs))
        g = co.gls(H, R, z).x[0]
        n_ = co.naive_fusion(H, R, z, block=1).x[0]
        diffs = [float(np.max(np.abs(f(H, R, z).x[0] - g)) / np.max(np.abs(g)))
                 for f in (co.pseudo_measurement_fusion, co.eigen_decorrelation_fusion)]
        sg, sn = (g - xv) ** 2, (n_ - xv) ** 2
        sq[name] = (sg, sn)
        weights[name] = (ex["K"], ex["Kn"])
        curves[name] = np.array([(lambda e: e["mse_naive"] / e["mse_gls"])(
            _exact(covariance(case["own"], case["coupling"], ev))) for ev in grid])
        rows.append({"case": name, "N": N, "env SD": float(case["env"]),
                     "min GLS weight": float(ex["K"].min()), "exact MSE GLS": ex["mse_gls"],
                     "exact MSE naive": ex["mse_naive"], "naive / GLS": ex["mse_naive"] / ex["mse_gls"],
                     "MC MSE GLS": float(sg.mean()), "MC MSE naive": float(sn.mean()),
                     "naive NEES": float(np.mean(sn) / ex["claimed_naive"]),
                     "LDLᵀ vs GLS": diffs[0], "eigen vs GLS": diffs[1]})
    return {"rows": rows, "sq": sq, "weights": weights, "env_grid": grid, "curves": curves,
            "runs": int(runs), "seed": int(seed), "scenarios": {k: dict(v) for k, v in sc.items()}}
