r"""Fusion of simultaneous readings of one quantity by several sensors.

Modules:

fusion_set
    Readings-level fusion: simultaneous scalar readings of one quantity.
weighting
    Adaptive and least-squares weighted fusion with estimated sensor variances.
consistency
    Consistency check followed by adaptive weighted fusion (lecture notes, §2.3).
biased
    Biased (ridge) estimation fusion (lecture notes, §2.5; Hoerl & Kennard 1970).
correlated
    Fusion with correlated measurement noise (lecture notes, §2.7).
wavelet
    Wavelet denoising and fusion-based per-sensor reconstruction (lecture notes, §2.6).
"""

from fusion.readings.fusion_set import (
    MeanDistances,
    ReadingsFusion,
    EpochFusion,
    arithmetic_mean,
    optimal_fusion_set,
    support_degree,
    fusion_set_weights,
    fuse_epochs,
    distance_matrix,
    mean_distances,
    optimal_set_members,
    fusion_degree_matrix,
    consistency_degree,
    distribution_balance,
    METHODS,
    belief_matrix,
    belief_matrices,
    row_sum_weights,
    perron_weights,
    belief_degree,
    binary_deletion,
)
from fusion.readings.weighting import (
    LSLearning,
    optimal_weights,
    minimum_variance,
    inverse_variance_weights,
    running_variances,
    running_means,
    AWFResult,
    awf,
    learned_variances,
    corrected_variances,
    ls_learning,
    wls,
    VARIANCE_FLOOR,
    GUARDS,
    lecture_variance_sd,
    learned_variance_limit,
)
from fusion.readings.consistency import (
    ConsistentAWF,
    consistency_mask,
    consistency_awf,
    rejection_probability,
)
from fusion.readings.biased import (
    RidgeMoments,
    least_squares,
    ridge,
    ridge_centralised,
    ridge_distributed,
    scalar_ridge_moments,
    optimal_ridge_k,
    reliability,
    RidgeFit,
    plugin_ridge,
    ridge_fusion_plugin,
)
from fusion.readings.correlated import (
    LinearEstimate,
    LDLFactors,
    gls,
    ldl_unpivoted,
    unit_lower_inverse,
    pseudo_measurement_fusion,
    naive_fusion,
    eigen_decorrelation_fusion,
    gls_weights,
    operation_counts,
    ldl_as_written_count,
)
from fusion.readings.wavelet import (
    denoise,
    Reconstruction,
    reconstruct,
)

__all__ = [
    "LSLearning",
    "MeanDistances",
    "LinearEstimate",
    "LDLFactors",
    "ConsistentAWF",
    "RidgeMoments",
    "ReadingsFusion",
    "EpochFusion",
    "arithmetic_mean",
    "optimal_fusion_set",
    "support_degree",
    "fusion_set_weights",
    "fuse_epochs",
    "distance_matrix",
    "mean_distances",
    "optimal_set_members",
    "fusion_degree_matrix",
    "consistency_degree",
    "distribution_balance",
    "METHODS",
    "belief_matrix",
    "belief_matrices",
    "row_sum_weights",
    "perron_weights",
    "belief_degree",
    "binary_deletion",
    "optimal_weights",
    "minimum_variance",
    "inverse_variance_weights",
    "running_variances",
    "running_means",
    "AWFResult",
    "awf",
    "learned_variances",
    "corrected_variances",
    "ls_learning",
    "wls",
    "VARIANCE_FLOOR",
    "GUARDS",
    "lecture_variance_sd",
    "learned_variance_limit",
    "consistency_mask",
    "consistency_awf",
    "rejection_probability",
    "least_squares",
    "ridge",
    "ridge_centralised",
    "ridge_distributed",
    "scalar_ridge_moments",
    "optimal_ridge_k",
    "reliability",
    "gls",
    "ldl_unpivoted",
    "unit_lower_inverse",
    "pseudo_measurement_fusion",
    "naive_fusion",
    "eigen_decorrelation_fusion",
    "gls_weights",
    "operation_counts",
    "ldl_as_written_count",
    "RidgeFit",
    "plugin_ridge",
    "ridge_fusion_plugin",
    "denoise",
    "Reconstruction",
    "reconstruct",
]
