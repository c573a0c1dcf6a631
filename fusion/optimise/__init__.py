r"""Optimisers the sources propose for choosing fusion weights.

Modules:

scalar
    Scalar optimisers for the covariance-intersection weight (Wang & Tang 2024).
swarm
    Particle swarm optimisation (Kennedy & Eberhart 1995; Clerc-Kennedy constriction), patent step G.
"""

from fusion.optimise.scalar import (
    ScalarOptimum,
    fruit_fly,
    grid_search,
    bounded_minimum,
)
from fusion.optimise.swarm import (
    SwarmResult,
    particle_swarm,
)

__all__ = [
    "ScalarOptimum",
    "fruit_fly",
    "grid_search",
    "bounded_minimum",
    "SwarmResult",
    "particle_swarm",
]
