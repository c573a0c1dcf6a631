r"""Chapter 03 (the lecture notes, section 2.6: wavelet denoising and fusion-based reconstruction).

The chapter's studies come from :mod:`fusion.scenarios.wavelet_sensors`: :func:`~fusion.scenarios.wavelet_sensors.signal_study`
(E2.6, the primary reading with more runs, and the signal × threshold-rule verdicts), :func:`~fusion.scenarios.wavelet_sensors.mechanism_study` (bias,
correlation, wavelet settings, order) and :func:`~fusion.scenarios.wavelet_sensors.variance_study` (the lecture's
step 3). Each ``table_*``, ``figure_*`` and ``glue_*`` presents one of them (glue keys prefixed ``lec_``), and
:func:`evidence` computes the evidence of chapter 03's records of ``book/claims/lecture003.yaml``.

Every claim of section 2.6 is about *every* sensor, so each reading is scored as a
:class:`fusion.book.ledger.Conjunction` of the four sensors' paired comparisons. The primary reading
(:data:`PRIMARY`) is decided by E2.6, which has more runs than the other readings (its verdict hangs on
rare runs, see :func:`glue_26`); wherever a table shows the primary reading's verdict it takes it from
E2.6 (:func:`cell`).

Submodules, one concept each:

- :mod:`fusion.book.chapters.lecture_wavelets.verdicts`: scoring a claim about every sensor;
- :mod:`fusion.book.chapters.lecture_wavelets.e26`: E2.6, its seeds and the run-count benchmark;
- :mod:`fusion.book.chapters.lecture_wavelets.signals`: the signal × threshold-rule verdicts;
- :mod:`fusion.book.chapters.lecture_wavelets.mechanism`: bias, correlation, wavelet settings, order;
- :mod:`fusion.book.chapters.lecture_wavelets.variance`: step 3, the variance of the weights;
- :mod:`fusion.book.chapters.lecture_wavelets.records`: the studies and the records' evidence functions;
- :mod:`fusion.book.chapters.lecture_wavelets.appendix`: the typical run and the signal length.
"""

from __future__ import annotations

from fusion.book.chapters.lecture import glue_figures
from fusion.book.chapters.lecture_wavelets import verdicts
from fusion.book.chapters.lecture_wavelets import e26
from fusion.book.chapters.lecture_wavelets import signals
from fusion.book.chapters.lecture_wavelets import mechanism
from fusion.book.chapters.lecture_wavelets import variance
from fusion.book.chapters.lecture_wavelets import records
from fusion.book.chapters.lecture_wavelets import appendix
from fusion.book.chapters.lecture_wavelets.verdicts import *  # noqa: F403
from fusion.book.chapters.lecture_wavelets.e26 import *  # noqa: F403
from fusion.book.chapters.lecture_wavelets.signals import *  # noqa: F403
from fusion.book.chapters.lecture_wavelets.mechanism import *  # noqa: F403
from fusion.book.chapters.lecture_wavelets.variance import *  # noqa: F403
from fusion.book.chapters.lecture_wavelets.records import *  # noqa: F403
from fusion.book.chapters.lecture_wavelets.appendix import *  # noqa: F403

__all__ = ["glue_figures"]
for _m in (verdicts, e26, signals, mechanism, variance, records, appendix):
    __all__ += _m.__all__
del _m
