r"""The experiments of chapter 02 (lecture notes, §2.1-2.4) and its readings-level benchmark.

The lecture publishes no data: every scenario here is the book's own design (see the chapter
and the design note). Each study takes its seed(s) as arguments with the chapter's defaults, so
the chapter's numbers follow from one call. Results are frozen dataclasses; their per-method entries are keyed
by method keys (:class:`~fusion.scenarios.lecture_weighting.estimators.AwfMethod`,
:class:`~fusion.scenarios.lecture_weighting.regime.RegimeMethod`,
:class:`~fusion.scenarios.lecture_weighting.readings_benchmark.BenchMethod`), whose display labels are in
:data:`fusion.book.style.METHOD_LABELS`.

Submodules, one study family each (every public name is re-exported here):

* :mod:`~fusion.scenarios.lecture_weighting.estimators` — E2.1:
  :func:`~fusion.scenarios.lecture_weighting.estimators.awf_study` (the lecture's and the centred variance estimator
  at several levels X; fused MSE against k; AWF under every variance guard),
  :func:`~fusion.scenarios.lecture_weighting.estimators.tail_study`,
  :func:`~fusion.scenarios.lecture_weighting.estimators.ar1_study`, and E2.1c:
  :func:`~fusion.scenarios.lecture_weighting.estimators.lumv_study`,
  :func:`~fusion.scenarios.lecture_weighting.estimators.symmetry_study` (linear, unbiased, minimum variance under
  each reading of the weights, on antithetic pairs; the sign-flip symmetry).
* :mod:`~fusion.scenarios.lecture_weighting.regime` — E2.1b:
  :func:`~fusion.scenarios.lecture_weighting.regime.regime_study` (a time-varying X, a change of the sensor
  variances: growing memory against forgetting and a sliding window) and
  :func:`~fusion.scenarios.lecture_weighting.regime.variance_change_study` (a constant X and one change of the noise
  SDs).
* :mod:`~fusion.scenarios.lecture_weighting.learning` — E2.2:
  :func:`~fusion.scenarios.lecture_weighting.learning.learning_study`,
  :func:`~fusion.scenarios.lecture_weighting.learning.learned_limit_check` (variance learning of sec. 2.2, its
  limit, learned and corrected weights).
* :mod:`~fusion.scenarios.lecture_weighting.consistency` — E2.3:
  :func:`~fusion.scenarios.lecture_weighting.consistency.consistency_study` (consistency check + AWF with a faulty
  sensor, and the detection curve).
* :mod:`~fusion.scenarios.lecture_weighting.belief` — E2.4:
  :func:`~fusion.scenarios.lecture_weighting.belief.belief_study`,
  :func:`~fusion.scenarios.lecture_weighting.belief.belief_parameter_study`,
  :func:`~fusion.scenarios.lecture_weighting.belief.belief_spread` (belief-degree weights against a shift; how much
  the fused value depends on the analyst's parameter).
* :mod:`~fusion.scenarios.lecture_weighting.readings_benchmark` —
  :func:`~fusion.scenarios.lecture_weighting.readings_benchmark.benchmark`,
  :func:`~fusion.scenarios.lecture_weighting.readings_benchmark.seed_stability` (every readings-level method on one
  shared setup, over seeds).

The §2.5 and §2.7 studies of chapter 04 are in :mod:`fusion.scenarios.lecture_correlated`.
"""

from __future__ import annotations

from fusion.scenarios.lecture_weighting import belief, consistency, estimators, learning, readings_benchmark, regime
from fusion.scenarios.lecture_weighting.belief import *  # noqa: F403
from fusion.scenarios.lecture_weighting.consistency import *  # noqa: F403
from fusion.scenarios.lecture_weighting.estimators import *  # noqa: F403
from fusion.scenarios.lecture_weighting.learning import *  # noqa: F403
from fusion.scenarios.lecture_weighting.readings_benchmark import *  # noqa: F403
from fusion.scenarios.lecture_weighting.regime import *  # noqa: F403

__all__ = (estimators.__all__ + regime.__all__ + learning.__all__ + consistency.__all__ + belief.__all__
           + readings_benchmark.__all__)
