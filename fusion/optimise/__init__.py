r"""Optimisers the sources propose for choosing fusion weights.

Modules:

result
    :class:`OptimumResult`, the result type every optimiser returns.
scalar
    Scalar optimisers for the covariance-intersection weight (Wang & Tang 2024).
simplex
    Minimisation over the probability simplex (SLSQP reference and a batched projected Newton).
swarm
    Particle swarm optimisation (Kennedy & Eberhart 1995; Clerc-Kennedy constriction), patent step G.
"""

from fusion.optimise.result import OptimumResult
from fusion.optimise.simplex import check_simplex, minimise_on_simplex
from fusion.optimise.scalar import *  # noqa: F403
from fusion.optimise.scalar import __all__ as _scalar_all
from fusion.optimise.swarm import (
    SwarmOptions,
    particle_swarm,
)

__all__ = [
    *_scalar_all,
    "OptimumResult", "particle_swarm", "SwarmOptions", "check_simplex", "minimise_on_simplex",
]
