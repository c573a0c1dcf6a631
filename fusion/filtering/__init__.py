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

from fusion.filtering.kalman import *  # noqa: F403
from fusion.filtering.kalman import __all__ as _kalman_all
from fusion.filtering.tracks import *  # noqa: F403
from fusion.filtering.tracks import __all__ as _tracks_all
from fusion.filtering.feedback import *  # noqa: F403
from fusion.filtering.feedback import __all__ as _feedback_all
from fusion.filtering.particles import *  # noqa: F403
from fusion.filtering.particles import __all__ as _particles_all

__all__ = [*_kalman_all, *_tracks_all, *_feedback_all, *(n for n in _particles_all if n not in {"wrap_angle"})]
