r"""Particle swarm optimisation (Kennedy & Eberhart 1995; Clerc-Kennedy constriction), patent step G.

Maximises a fitness over exponent vectors on the simplex. Positions :math:`u \in [u_{lo}, 1]^N`
are mapped to the simplex by :math:`\varepsilon = u/\sum u`; velocities follow

.. math:: v \leftarrow w v + c_1 r_1 (p_{best} - u) + c_2 r_2 (g_{best} - u),\quad |v| \le v_{max},
          \qquad u \leftarrow \mathrm{clip}(u + v).

The whole swarm is scored in one call (``fitness`` takes an (E, N) array).

References
----------
* Kennedy, J., & Eberhart, R. (1995). Particle swarm optimization. *Proceedings of the IEEE
  International Conference on Neural Networks*, 4, 1942-1948.
* Clerc, M., & Kennedy, J. (2002). The particle swarm: explosion, stability, and convergence in
  a multidimensional complex space. *IEEE Transactions on Evolutionary Computation*, 6(1),
  58-73.
* University of Electronic Science and Technology of China (2021). Multi-sensor distributed
  data fusion method based on the Chernoff fusion criterion. Patent CN107330468B.
"""

from __future__ import annotations

from collections.abc import Callable
import numpy as np

from fusion._validation import FloatArray, as_callable, as_rng, count, nonnegative_scalar, positive_scalar, scalar
from fusion.optimise._ties import TIE_RTOL, first_minimum, improves
from fusion.optimise.result import OptimumResult

__all__ = ["particle_swarm"]


def particle_swarm(
    fitness: Callable[[FloatArray], FloatArray],
    dim: int,
    rng: np.random.Generator,
    n_particles: int = 20,
    iterations: int = 50,
    inertia: float = 0.7298,
    c1: float = 1.49618,
    c2: float = 1.49618,
    vmax: float = 0.2,
    lo: float = 1e-6,
    tol: float = 1e-9,
    patience: int = 10,
    stop: str = "stagnation",
    xtol: float = 1e-3,
) -> OptimumResult:
    """Maximise ``fitness`` over the simplex of dimension ``dim`` (patent steps G1-G6).

    G3/G4 keep the *higher* fitness, so pass :math:`-\\hat J` to minimise :math:`\\hat J`.

    Parameters
    ----------
    fitness : callable
        Maps an (E, N) array of exponent vectors (rows on the simplex) to (E,) fitness values.
    dim : int
        :math:`N`.
    rng : numpy.random.Generator
        Draws initial positions, velocities and the random factors :math:`r_1, r_2`.
    n_particles, iterations : int
        Swarm size and iteration limit (G6).
    inertia, c1, c2 : float
        Clerc-Kennedy constriction values by default.
    vmax : float
        Velocity clamp.
    lo : float
        Lower bound of the positions (so that :math:`\\sum u > 0`).
    tol, patience
        G6 convergence with ``stop="stagnation"``: stop when the best fitness improved by less
        than ``tol`` over the last ``patience`` iterations.
    stop : {"stagnation", "positions"}
        G6 convergence rule: fitness stagnation (default), or the patent's wording, convergence
        of the swarm's positions: stop when every particle's exponent vector is within ``xtol``
        (largest coordinate difference) of the global best.
    xtol : float
        Position tolerance of ``stop="positions"``.

    Returns
    -------
    OptimumResult
        ``x``: the best exponent vector found (on the simplex); ``fun``: its fitness (the
        maximum found); ``history``: the best fitness after the initialisation and after each
        iteration (non-decreasing); ``n_evaluations``: particles times generations scored.

    Raises
    ------
    ValueError
        ``dim``, ``n_particles``, ``iterations`` or ``patience`` not positive; ``stop`` unknown;
        ``xtol`` not positive.

    References
    ----------
    * Kennedy, J., & Eberhart, R. (1995). Particle swarm optimization. *Proceedings of the IEEE
      International Conference on Neural Networks*, 4, 1942-1948.
    * Clerc, M., & Kennedy, J. (2002). The particle swarm: explosion, stability, and convergence in
      a multidimensional complex space. *IEEE Transactions on Evolutionary Computation*, 6(1),
      58-73.

    Notes
    -----
    Fitness values within a relative 1e-9 of each other count as equal (a particle's or the
    swarm's best changes only on a larger improvement; among equals the first particle wins), so
    round-off, which differs between BLAS builds and thread counts, never decides.
    """
    as_callable(fitness, "fitness")
    as_rng(rng)
    dim, n_particles = count(dim, "dim"), count(n_particles, "n_particles")
    iterations, patience = count(iterations, "iterations"), count(patience, "patience")
    inertia, c1, c2 = nonnegative_scalar(inertia, "inertia"), nonnegative_scalar(c1, "c1"), nonnegative_scalar(c2, "c2")
    vmax, tol = positive_scalar(vmax, "vmax"), nonnegative_scalar(tol, "tol")
    lo = scalar(lo, "lo", 0.0, 1.0, hi_open=True)
    if stop not in ("stagnation", "positions"):
        raise ValueError(f"stop must be 'stagnation' or 'positions', got {stop!r}")
    xtol = positive_scalar(xtol, "xtol")
    u = rng.uniform(lo, 1.0, (n_particles, dim))  # G1
    v = rng.uniform(-vmax, vmax, (n_particles, dim))

    def score(pos: FloatArray) -> FloatArray:
        return np.asarray(fitness(pos / pos.sum(axis=1, keepdims=True)), dtype=float)

    f = score(u)  # G2
    pbest, pbest_f = u.copy(), f.copy()
    g = first_minimum(-f)
    gbest, gbest_f = u[g].copy(), float(f[g])
    history = [gbest_f]
    evals = n_particles
    for _ in range(iterations):
        r1, r2 = rng.uniform(size=(2, n_particles, dim))
        v = np.clip(inertia * v + c1 * r1 * (pbest - u) + c2 * r2 * (gbest - u), -vmax, vmax)  # G5
        u = np.clip(u + v, lo, 1.0)
        f = score(u)  # G2
        evals += n_particles
        better = f > pbest_f + TIE_RTOL * np.maximum(np.abs(pbest_f), 1.0)  # G3: higher fitness wins
        pbest[better], pbest_f[better] = u[better], f[better]
        g = first_minimum(-pbest_f)  # G4
        if improves(-float(pbest_f[g]), -gbest_f):
            gbest, gbest_f = pbest[g].copy(), float(pbest_f[g])
        history.append(gbest_f)
        if stop == "stagnation":
            if len(history) > patience and history[-1] - history[-1 - patience] < tol:
                break  # G6
        elif np.max(np.abs(u / u.sum(axis=1, keepdims=True) - gbest / gbest.sum())) < xtol:
            break  # G6 as the patent words it: the positions have converged
    return OptimumResult(x=gbest / gbest.sum(), fun=gbest_f, n_evaluations=evals, history=np.array(history))
