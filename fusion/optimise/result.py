"""The one result type of every optimiser in the package.

:func:`fusion.optimise.scalar.fruit_fly`, :func:`~fusion.optimise.scalar.grid_search`,
:func:`~fusion.optimise.scalar.bounded_minimum`, :func:`fusion.optimise.swarm.particle_swarm`,
:func:`fusion.estimates.chernoff.minimise_on_simplex` and
:func:`fusion.estimates.chernoff.simplex_minimum` all return an :class:`OptimumResult`: the
argument found, the objective there, the number of objective evaluations (the
machine-independent cost) and, for the iterative swarm, the best value after each iteration.
The names follow :class:`scipy.optimize.OptimizeResult` (``x``, ``fun``).

References
----------
* Virtanen, P., et al. (2020). SciPy 1.0: fundamental algorithms for scientific computing in
  Python. *Nature Methods*, 17, 261-272.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fusion._frozen import frozen_arrays
from fusion._validation import FloatArray

__all__ = ["OptimumResult", "SwarmTrace"]


@dataclass(frozen=True)
@frozen_arrays
class SwarmTrace:
    r"""A swarm followed to its iteration limit, past the stop of its rule (:func:`fusion.optimise.swarm.particle_swarm`, ``trace=True``).

    The swarm's moves do not depend on its stopping rule until it stops, so one swarm followed to the
    limit gives what every stopping rule would have returned: the best point and fitness at the
    iteration where that rule stops. Array fields are read-only copies.

    Attributes
    ----------
    fitness : ndarray, shape (T + 1,)
        Best fitness after the initialisation and after each of the ``T`` iterations (non-decreasing).
    best : ndarray, shape (T + 1, N)
        The best point (on the simplex) at the same moments.
    spread : ndarray, shape (T + 1,)
        Largest coordinate difference between any particle's point and the best point, after the
        initialisation and after each iteration (the quantity of the ``"positions"`` rule).
    n_particles : int
        Particles of the swarm (evaluations per iteration).
    """

    fitness: FloatArray
    best: FloatArray
    spread: FloatArray
    n_particles: int

    def stop_positions(self, xtol: float) -> int:
        """Iteration at which the ``"positions"`` rule with tolerance ``xtol`` stops (``T`` if it never does)."""
        hit = np.flatnonzero(self.spread[1:] < xtol)
        return int(hit[0]) + 1 if hit.size else int(self.spread.size - 1)

    def stop_stagnation(self, tol: float, patience: int) -> int:
        """Iteration at which the ``"stagnation"`` rule (``tol``, ``patience``) stops (``T`` if it never does)."""
        f = self.fitness
        for t in range(patience, f.size):
            if f[t] - f[t - patience] < tol:
                return t
        return int(f.size - 1)

    def at(self, t: int) -> "OptimumResult":
        """What the swarm returns when it stops after iteration ``t`` (0: right after the initialisation)."""
        return OptimumResult(x=self.best[t], fun=float(self.fitness[t]), n_evaluations=self.n_particles * (t + 1),
                             history=self.fitness[:t + 1])


@dataclass(frozen=True)
@frozen_arrays
class OptimumResult:
    """Best argument, its objective value, the evaluations used and (optionally) the history.

    Array fields are read-only copies.

    Attributes
    ----------
    x : float or ndarray, shape (N,)
        Best argument found: a float for the scalar optimisers, a point of the simplex (the
        exponent weights ``eps``) for the swarm and the simplex minimisers.
    fun : float
        Objective value at ``x``: the minimum found, or for :func:`~fusion.optimise.swarm.particle_swarm`,
        which maximises its fitness, the maximum found.
    n_evaluations : int
        Number of objective evaluations used (for the swarm: particles times generations scored).
    history : ndarray or None
        Best value after the initialisation and after each iteration (the swarm only:
        non-decreasing, at most ``iterations + 1`` long); ``None`` for the other optimisers.
    trace : SwarmTrace or None
        The swarm only, with ``trace=True``: the swarm followed to its iteration limit.
    """

    x: float | FloatArray
    fun: float
    n_evaluations: int
    history: FloatArray | None = None
    trace: SwarmTrace | None = None
