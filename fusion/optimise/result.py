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

from fusion._frozen import freeze_arrays
from fusion._validation import FloatArray

__all__ = ["OptimumResult"]


@dataclass(frozen=True)
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
    """

    x: float | FloatArray
    fun: float
    n_evaluations: int
    history: FloatArray | None = None

    __post_init__ = freeze_arrays
