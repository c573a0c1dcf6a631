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

from fusion.estimates.ci import (
    FusedEstimate,
    covariance_intersection,
    ci_weight,
    ci_objective,
    split_ci_objective,
    convex_combination,
    split_covariance_intersection,
)
from fusion.estimates.fuzzy_cluster import (
    ClusterFusion,
    fuzzy_cluster_fusion,
)
from fusion.estimates.mixtures import (
    Moments,
    EmFit,
    GaussianMixture,
    logsumexp,
    gaussian_logpdf,
    gm_logpdf,
    gm_moments,
    gm_sample,
    weighted_em,
    weighted_em_batch,
)
from fusion.estimates.chernoff import (
    FirstOrderMixture,
    ChernoffGaussian,
    MixtureFusion,
    FusionTimings,
    check_simplex,
    chernoff_fuse_gaussians,
    gaussian_log_normaliser,
    is_second_moment,
    gaussian_chernoff_weights,
    gaussian_kl,
    log_normaliser_two_gaussians,
    first_order_fusion,
    log_densities,
    is_objective,
    fused_weights,
    minimise_on_simplex,
    simplex_minimum,
    fuse_mixtures,
)

__all__ = [
    "FirstOrderMixture",
    "Moments",
    "EmFit",
    "FusedEstimate",
    "covariance_intersection",
    "ci_weight",
    "ci_objective",
    "split_ci_objective",
    "convex_combination",
    "split_covariance_intersection",
    "ClusterFusion",
    "fuzzy_cluster_fusion",
    "GaussianMixture",
    "logsumexp",
    "gaussian_logpdf",
    "gm_logpdf",
    "gm_moments",
    "gm_sample",
    "weighted_em",
    "weighted_em_batch",
    "ChernoffGaussian",
    "MixtureFusion",
    "FusionTimings",
    "check_simplex",
    "chernoff_fuse_gaussians",
    "gaussian_log_normaliser",
    "is_second_moment",
    "gaussian_chernoff_weights",
    "gaussian_kl",
    "log_normaliser_two_gaussians",
    "first_order_fusion",
    "log_densities",
    "is_objective",
    "fused_weights",
    "minimise_on_simplex",
    "simplex_minimum",
    "fuse_mixtures",
]
