r"""The two-sensor 2-D tracking case of Wang & Tang (2024, §3.2), vectorised over runs.

A target on a three-leg path (:func:`trajectory`), two position sensors, a local
constant-velocity Kalman filter per sensor and the centralised filter on both sensors'
measurements (:func:`two_sensor_scenario`), in ``case``; the CI weight searches (``weights``), the fusion
study and its metrics (``study``), the feedback architecture and Q scaling (``architecture``) and the bounds
(``bounds``) in their own submodules. Every public name is re-exported here.
"""

from __future__ import annotations

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

__all__ = (_case.__all__ + _weights.__all__ + _study.__all__ + _bounds.__all__ + _architecture.__all__)
