"""fusion: the algorithms, simulations and published data of *fusion-book*.

Subpackages
-----------
readings
    Fusion of simultaneous readings of one quantity: optimal fusion set, support and belief
    degree, adaptive weighting, consistency check, biased estimation, wavelets, correlated noise.
estimates
    Fusion of state estimates: covariance intersection and its variants, fuzzy clustering,
    Gaussian mixtures and Chernoff fusion.
filtering
    Kalman filters vectorised over runs, track-level fusion, particle filters.
optimise
    The weight optimisers the sources propose (fruit fly, grid, bounded, particle swarm).
registration
    Time registration of asynchronous sensors.
scenarios
    Simulated cases, one module each (thermocouple bank, two-sensor tracking, infrared + radar,
    range-bearing network, two mixtures). Scenarios import algorithms; algorithms never import
    scenarios or ``book``.
data
    Numbers published by the sources, with provenance, and misprinted equations as printed.
book
    Helpers for the book only: figure style registry, tables, audits of published values.
"""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("fusion-book")
except PackageNotFoundError:  # pragma: no cover - running from a source tree
    __version__ = "0.0.0"

__all__ = ["__version__"]
