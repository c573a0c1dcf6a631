r"""Fusion of state estimates (mean and covariance) of one state.

Modules:

ci
    Estimate-level fusion: combining state estimates :math:`(\hat x_i, P_i)` of one state.
fuzzy_cluster
    Fuzzy-relation clustering of estimates: the baseline of Wang & Tang (2024, §3.2).
mixtures
    Gaussian mixtures: densities, sampling and weighted EM (patent CN107330468B, step C).
chernoff
    Chernoff fusion of densities (patent CN107330468B, steps D-I), rebuilt.
"""

from fusion.estimates.ci import *  # noqa: F403
from fusion.estimates.ci import __all__ as _ci_all
from fusion.estimates.fuzzy_cluster import (
    ClusterFusion,
    fuzzy_cluster_fusion,
)
from fusion.estimates.mixtures import *  # noqa: F403
from fusion.estimates.mixtures import __all__ as _mixtures_all
from fusion.estimates.chernoff import *  # noqa: F403
from fusion.estimates.chernoff import __all__ as _chernoff_all

__all__ = [
    *_ci_all,
    *_mixtures_all,
    *(n for n in _chernoff_all if n not in {"covariance_intersection_weights", "fuse_mixtures_batch"}),
    "ClusterFusion", "fuzzy_cluster_fusion",
]
