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

from fusion.readings.fusion_set import *  # noqa: F403
from fusion.readings.fusion_set import __all__ as _fusion_set_all
from fusion.readings.weighting import *  # noqa: F403
from fusion.readings.weighting import __all__ as _weighting_all
from fusion.readings.consistency import *  # noqa: F403
from fusion.readings.consistency import __all__ as _consistency_all
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
    ShrinkAt,
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
    *_fusion_set_all,
    *(n for n in _weighting_all if n not in {"MEMORIES", "TIME_WEIGHTS"}),
    *_consistency_all,
    "LinearEstimate", "LDLFactors", "RidgeMoments", "least_squares", "ridge", "ridge_centralised",
    "ridge_distributed", "scalar_ridge_moments", "optimal_ridge_k", "reliability", "gls", "ldl_unpivoted",
    "unit_lower_inverse", "pseudo_measurement_fusion", "naive_fusion", "eigen_decorrelation_fusion", "gls_weights",
    "operation_counts", "ldl_as_written_count", "RidgeFit", "plugin_ridge", "ShrinkAt", "ridge_fusion_plugin",
    "denoise",
    "Reconstruction", "reconstruct",
]
