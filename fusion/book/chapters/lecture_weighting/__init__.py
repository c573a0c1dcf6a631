r"""Chapter 02 (the lecture notes, sections 2.1-2.4, and the readings-level benchmark).

Each ``table_*`` assembles a display table from a study of :mod:`fusion.scenarios.lecture_weighting`,
each ``figure_*`` draws one of the chapter's figures, each ``glue_*`` returns the chapter's
glued values (keys prefixed ``lec_``, rounded as the prose prints them), and the ``ev_*`` functions
compute the evidence of chapter 02's records of ``book/claims/lecture003.yaml`` (:func:`evidence`).

Submodules (every public name is re-exported here):

* :mod:`~fusion.book.chapters.lecture_weighting.estimators` — §2.1, E2.1 and E2.1c: the variance estimators,
  guards, tail, AR(1) noise, linear-unbiased-minimum-variance.
* :mod:`~fusion.book.chapters.lecture_weighting.regime` — §2.1, E2.1b: the regime and variance-change studies.
* :mod:`~fusion.book.chapters.lecture_weighting.learning` — §2.2: variance learning.
* :mod:`~fusion.book.chapters.lecture_weighting.consistency` — §2.3: the consistency check.
* :mod:`~fusion.book.chapters.lecture_weighting.belief` — §2.4: belief-degree weights.
* :mod:`~fusion.book.chapters.lecture_weighting.readings_benchmark` — the readings-level benchmark.
* :mod:`~fusion.book.chapters.lecture_weighting.study_evidence` — the records' evidence from precomputed studies.
* :mod:`~fusion.book.chapters.lecture_weighting.studies` — the seeded, cached studies of the stochastic records.
* :mod:`~fusion.book.chapters.lecture_weighting.records` — evidence by record id, at any seed; ledger values.
"""

from __future__ import annotations

from fusion.book.chapters.lecture import glue_figures
from fusion.book.chapters.lecture_weighting import (belief, consistency, estimators, learning, readings_benchmark, records,
                                                    regime, studies, study_evidence)
from fusion.book.chapters.lecture_weighting.belief import *  # noqa: F403
from fusion.book.chapters.lecture_weighting.consistency import *  # noqa: F403
from fusion.book.chapters.lecture_weighting.estimators import *  # noqa: F403
from fusion.book.chapters.lecture_weighting.learning import *  # noqa: F403
from fusion.book.chapters.lecture_weighting.readings_benchmark import *  # noqa: F403
from fusion.book.chapters.lecture_weighting.records import *  # noqa: F403
from fusion.book.chapters.lecture_weighting.regime import *  # noqa: F403
from fusion.book.chapters.lecture_weighting.studies import *  # noqa: F403
from fusion.book.chapters.lecture_weighting.study_evidence import *  # noqa: F403

__all__ = ["glue_figures", *estimators.__all__, *regime.__all__, *learning.__all__, *consistency.__all__, *belief.__all__,
           *readings_benchmark.__all__, *study_evidence.__all__, *studies.__all__, *records.__all__]
