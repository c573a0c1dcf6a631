r"""Chapter 04 (the lecture notes, sections 2.5 and 2.7: biased estimation, correlated noise).

Each ``table_*``, ``figure_*`` and ``glue_*`` presents a study of :mod:`fusion.scenarios.lecture_correlated`,
:mod:`fusion.scenarios.ridge_sensors` or :mod:`fusion.scenarios.correlated_sensors`, or the stored
timings of ``benchmarks/bench_correlated.py`` (glue keys prefixed ``lec_``); the ``ev_*`` functions compute the
evidence of chapter 04's records of ``book/claims/lecture003.yaml`` (:func:`ledger_evidence`).

Submodules, one concept each:

- :mod:`fusion.book.chapters.lecture_correlated.ridge`: section 2.5, biased estimation;
- :mod:`fusion.book.chapters.lecture_correlated.correlated`: section 2.7, correlated noise, and the timings;
- :mod:`fusion.book.chapters.lecture_correlated.propositions`: the closed-form and exact checks;
- :mod:`fusion.book.chapters.lecture_correlated.records`: the studies, the records' evidence functions, the glued keys;
- :mod:`fusion.book.chapters.lecture_correlated.appendix`: sequential fusion, James-Stein, the shrunken estimate.
"""

from __future__ import annotations

from fusion.book.chapters.lecture import glue_figures
from fusion.book.chapters.lecture_correlated import ridge
from fusion.book.chapters.lecture_correlated import correlated
from fusion.book.chapters.lecture_correlated import propositions
from fusion.book.chapters.lecture_correlated import records
from fusion.book.chapters.lecture_correlated import appendix
from fusion.book.chapters.lecture_correlated.ridge import *  # noqa: F403
from fusion.book.chapters.lecture_correlated.correlated import *  # noqa: F403
from fusion.book.chapters.lecture_correlated.propositions import *  # noqa: F403
from fusion.book.chapters.lecture_correlated.records import *  # noqa: F403
from fusion.book.chapters.lecture_correlated.appendix import *  # noqa: F403

# the evidence functions the claim file names (``evidence: fusion.book.chapters.lecture_correlated:ev_*``)
from fusion.book.chapters.lecture_correlated.records import (  # noqa: F401
    ev_ridge_reliable,
    ev_ridge_plugin,
    ev_ridge_variance,
    ev_ridge_bias_known,
    ev_ls_special_cases,
    ev_gauss_markov,
    ev_james_stein,
    ev_reliability_measure,
    ev_ridge_equivalence,
    ev_ridge_converges,
    ev_ridge_fusion_better,
    ev_ridge_fusion_plugin,
    ev_ldl_unique,
    ev_ldl_equals_gls,
    ev_ldl_cheaper,
    ev_lagrange,
    ev_correlation_matters,
    ev_eigen_finite,
    ev_eigen_impractical,
    ev_ldl_validated,
)

__all__ = ["glue_figures"]
for _m in (ridge, correlated, propositions, records, appendix):
    __all__ += _m.__all__
del _m
