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

from fusion._frozen import frozen_arrays, restore_frozen
from fusion._validation import FloatArray, _numeric, as_array, instance_of, integer
from fusion._shown import shown

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


def _checked_optimum(self: OptimumResult) -> None:
    """``__post_init__`` of :class:`OptimumResult`: every field checked (a :class:`ValueError` or, for a wrong type,
    a :class:`TypeError` naming ``OptimumResult.<field>``), then the arrays stored as read-only copies."""
    x = self.x
    if isinstance(x, (bool, np.bool_)):
        raise TypeError(f"OptimumResult.x must be a float or an array of floats, got {shown(x)}")
    _numeric(x, "OptimumResult.x")
    if np.ndim(x) == 0:
        x = float(as_array(x, "OptimumResult.x", ndim=0, subnormal=True))
    else:
        x = np.array(as_array(x, "OptimumResult.x", ndim=1, subnormal=True), dtype=float)
        x.setflags(write=False)
    if isinstance(self.fun, (bool, np.bool_)):
        raise TypeError(f"OptimumResult.fun must be a float, got {shown(self.fun)}")
    fun = float(as_array(self.fun, "OptimumResult.fun", ndim=0, subnormal=True))
    n = integer(self.n_evaluations, "OptimumResult.n_evaluations")
    if n < 0:
        raise ValueError(f"OptimumResult.n_evaluations must be >= 0, got {n}")
    history = self.history
    if history is not None:
        _numeric(history, "OptimumResult.history")
        # -inf: the swarm's best fitness before any particle was feasible (scored -inf)
        history = np.array(as_array(history, "OptimumResult.history", ndim=1, finite=False), dtype=float)
        if np.isnan(history).any() or (history == np.inf).any():
            raise ValueError("OptimumResult.history must hold finite values (or -inf before a feasible point)")
        if (np.diff(history) < 0).any():
            raise ValueError("OptimumResult.history must be non-decreasing (the best value so far)")
        if history[-1] != fun:
            raise ValueError(f"OptimumResult.history must end with OptimumResult.fun = {shown(fun)}, got {shown(history[-1])}")
        history.setflags(write=False)
        # the swarm (the only optimiser with a history) returns a point of the simplex
        if isinstance(x, float) or (x < 0).any() or abs(x.sum() - 1.0) > 1e-9 * x.size:
            raise ValueError(f"OptimumResult.x must be a point of the simplex (the swarm's, which has a history), "
                             f"got {shown(x)}"[:300])
    if self.trace is not None:
        instance_of(self.trace, SwarmTrace, "OptimumResult.trace")
        if isinstance(x, float) or self.trace.best.shape[-1] != x.size:
            raise ValueError(f"OptimumResult.trace holds points of {self.trace.best.shape[-1]} weights, "
                             f"but OptimumResult.x has shape {np.shape(x)}")
    for name, value in (("x", x), ("fun", fun), ("n_evaluations", n), ("history", history)):
        object.__setattr__(self, name, value)


@dataclass(frozen=True)
class OptimumResult:
    """Best argument, its objective value, the evaluations used and (optionally) the history.

    Validated where it is built (``dataclasses.replace`` included): ``x`` a finite float or 1-D array, ``fun``
    finite, ``n_evaluations`` an integer >= 0, ``history`` non-decreasing and ending with ``fun`` (then ``x`` a point of the simplex), ``trace`` a
    :class:`SwarmTrace` of points the size of ``x``; a :class:`ValueError` (a :class:`TypeError` for a wrong
    type) names the field. Array fields are read-only copies.

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

    __post_init__ = _checked_optimum
    __setstate__ = restore_frozen
