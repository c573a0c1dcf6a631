r"""Recursive estimators: linear Kalman filters vectorised over runs, track-level fusion, particle filters.

Modules:

kalman
    Linear Kalman filtering vectorised over Monte-Carlo runs.
tracks
    Track-level fusion of two local Kalman tracks, vectorised over Monte-Carlo runs.
feedback
    Two local filters and a fusion centre with or without feedback (Wang & Tang 2024, Fig. 2).
particles
    Bootstrap particle filters for range-bearing sensors (patent CN107330468B, step B), vectorised.
"""

from fusion.filtering.kalman import (
    CvModel,
    SplitCovariances,
    cv_model,
    GainSequence,
    gain_sequence,
    split_covariances,
    filter_runs,
    ErrorMoments,
    error_moments,
    rmse_per_step,
    nees,
)
from fusion.filtering.tracks import (
    RULES,
    LocalTrack,
    local_track,
    FusedTracks,
    fuse_tracks,
)
from fusion.filtering.feedback import (
    FEEDBACK_RULES,
    ARCHITECTURES,
    PROCESS_NOISE,
    FusionLoop,
    fusion_loop,
)
from fusion.filtering.particles import (
    NcvModel,
    WeightedMoments,
    ncv_model,
    range_bearing,
    log_likelihood,
    systematic_resample,
    effective_sample_size,
    weighted_moments,
    regularise,
)

__all__ = [
    "NcvModel",
    "WeightedMoments",
    "CvModel",
    "SplitCovariances",
    "cv_model",
    "GainSequence",
    "gain_sequence",
    "split_covariances",
    "filter_runs",
    "ErrorMoments",
    "error_moments",
    "rmse_per_step",
    "nees",
    "RULES",
    "LocalTrack",
    "local_track",
    "FusedTracks",
    "fuse_tracks",
    "FEEDBACK_RULES",
    "ARCHITECTURES",
    "PROCESS_NOISE",
    "FusionLoop",
    "fusion_loop",
    "ncv_model",
    "range_bearing",
    "log_likelihood",
    "systematic_resample",
    "effective_sample_size",
    "weighted_moments",
    "regularise",
]
