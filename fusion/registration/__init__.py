r"""Time registration of asynchronous sensors (Shi, Suo & Ma 2023).

Modules:

methods
    Time registration (时间配准): a fast sensor's samples onto a slow sensor's instants.
"""

from fusion.registration.methods import (
    BlairEstimate,
    FilteredStates,
    AffineDecomposition,
    two_point,
    three_point,
    least_squares,
    blair_ls,
    ca_transition,
    kalman_filter,
    kalman_register,
    predict_to,
    improved_register,
    affine_decomposition,
    expected_mse,
    sample_times,
    Q_MODELS,
    INITS,
    process_noise,
    kalman_runs,
    quadratic_ls,
    spline_register,
)

__all__ = [
    "BlairEstimate",
    "FilteredStates",
    "AffineDecomposition",
    "two_point",
    "three_point",
    "least_squares",
    "blair_ls",
    "ca_transition",
    "kalman_filter",
    "kalman_register",
    "predict_to",
    "improved_register",
    "affine_decomposition",
    "expected_mse",
    "sample_times",
    "Q_MODELS",
    "INITS",
    "process_noise",
    "kalman_runs",
    "quadratic_ls",
    "spline_register",
]
