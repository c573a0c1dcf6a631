r"""The two-sensor 2-D tracking case of Wang & Tang (2024, §3.2), vectorised over runs.

A target on a three-leg path (:func:`trajectory`), two position sensors, a local
constant-velocity Kalman filter per sensor and the centralised filter on both sensors'
measurements (:func:`two_sensor_scenario`), in ``case``; the CI weight searches (``weights``), the fusion
study and its metrics (``study``), the feedback architecture and Q scaling (``architecture``) and the bounds
(``bounds``) in their own submodules. Every public name is re-exported here.
"""

from __future__ import annotations

from fusion._public import name_by_package
from fusion.scenarios.two_sensor import case as _case
from fusion.scenarios.two_sensor import weights as _weights
from fusion.scenarios.two_sensor import study as _study
from fusion.scenarios.two_sensor import bounds as _bounds
from fusion.scenarios.two_sensor import architecture as _architecture
from fusion.scenarios.two_sensor.case import *  # noqa: F401,F403
from fusion.scenarios.two_sensor.weights import *  # noqa: F401,F403
from fusion.scenarios.two_sensor.study import *  # noqa: F401,F403
from fusion.scenarios.two_sensor.bounds import *  # noqa: F401,F403
from fusion.scenarios.two_sensor.architecture import *  # noqa: F401,F403

# The documented constants, bound here so that the API page documents them under this package's name.
#: The rules of :func:`fusion_study`, in table order.
STUDY_METHODS = _study.STUDY_METHODS
#: Keys of :func:`rmse_variants` for the slip :math:`\sqrt{\sum e^2}/n` (n = steps of a run, n = runs of a step).
SLIP_STEPS = _study.SLIP_STEPS
#: The fused rules of :func:`nees_study`: (key, rule of :func:`fusion.filtering.tracks.fuse_tracks`, fixed ω or None).
NEES_RULES = _study.NEES_RULES
#: Configurations of :func:`architecture_study`: (rule key, rule of :func:`fusion.filtering.feedback.fusion_loop`,
#: process-noise reading).
ARCH_RULES = _architecture.ARCH_RULES
#: Readings of the source's process noise for :func:`pcrb_steady` (Δ₀ = 10 as printed).
Q_READINGS = _bounds.Q_READINGS

__all__ = (_case.__all__ + _weights.__all__ + _study.__all__ + _bounds.__all__ + _architecture.__all__)

name_by_package(globals())
