r"""Chapter 06 (patent CN107330468B, distributed Chernoff fusion): checks, studies, tables, figures, claims.

Everything the chapter's notebook computes beyond calling the package: the exact checks K1-K5 on
random Gaussians, the static two-mixture example, the tables and figures of the tracking study
(:mod:`fusion.scenarios.range_bearing`) and the evidence of the claim file ``book/claims/cn107330468b.yaml``
(functions ``ev_*``, one per record, called by :func:`chapter_evidence` with each reading's settings; the studies
behind them cached, so that the notebook computes each once). The notebook only
calls these functions and glues their values.

One submodule per concept: keys and settings (``settings``), the exact Gaussian checks (``gaussian``), the
two-mixture example (``mixture``), the Stone Soup cross-check (``peers``), the tracking study's tables
(``tracking``), importance sampling (``importance``), the paired comparisons (``compare``), the guarded filter and
its design (``guard``), the swarm and its stopping rule (``swarm``), the tracking study's reviews (``review``), the
designed networks (premise) (``premise``), the cached studies (``studies``), the records' evidence ``ev_*``
(``evidence``), the ledger and glue values (``glue``). Every public name is re-exported here.

References
----------
.. [1] Julier, S. J., Uhlmann, J. K. (1997). A non-divergent estimation algorithm in the presence of
   unknown correlations. *Proc. American Control Conference*, 2369-2373.
.. [2] Hurley, M. B. (2002). An information theoretic justification for covariance intersection and
   its generalization. *Proc. FUSION 2002*, 505-511.
.. [3] Julier, S. J. (2006). An empirical study into the use of Chernoff information for robust,
   distributed fusion of Gaussian mixture models. *Proc. FUSION 2006*.
.. [4] Tichavský, P., Muravchik, C. H., Nehorai, A. (1998). Posterior Cramér-Rao bounds for
   discrete-time nonlinear filtering. *IEEE Trans. Signal Processing* 46(5), 1386-1396.
"""

from __future__ import annotations

from fusion._public import name_by_package
from fusion.book.chapters.chernoff.settings import *  # noqa: F403
from fusion.book.chapters.chernoff.settings import __all__ as _all_settings
from fusion.book.chapters.chernoff.gaussian import *  # noqa: F403
from fusion.book.chapters.chernoff.gaussian import __all__ as _all_gaussian
from fusion.book.chapters.chernoff.mixture import *  # noqa: F403
from fusion.book.chapters.chernoff.mixture import __all__ as _all_mixture
from fusion.book.chapters.chernoff.peers import *  # noqa: F403
from fusion.book.chapters.chernoff.peers import __all__ as _all_peers
from fusion.book.chapters.chernoff.tracking import *  # noqa: F403
from fusion.book.chapters.chernoff.tracking import __all__ as _all_tracking
from fusion.book.chapters.chernoff.importance import *  # noqa: F403
from fusion.book.chapters.chernoff.importance import __all__ as _all_importance
from fusion.book.chapters.chernoff.compare import *  # noqa: F403
from fusion.book.chapters.chernoff.compare import __all__ as _all_compare
from fusion.book.chapters.chernoff.guard import *  # noqa: F403
from fusion.book.chapters.chernoff.guard import __all__ as _all_guard
from fusion.book.chapters.chernoff.swarm import *  # noqa: F403
from fusion.book.chapters.chernoff.swarm import __all__ as _all_swarm
from fusion.book.chapters.chernoff.review import *  # noqa: F403
from fusion.book.chapters.chernoff.review import __all__ as _all_review
from fusion.book.chapters.chernoff.premise import *  # noqa: F403
from fusion.book.chapters.chernoff.premise import __all__ as _all_premise
from fusion.book.chapters.chernoff.studies import *  # noqa: F403
from fusion.book.chapters.chernoff.studies import __all__ as _all_studies
from fusion.book.chapters.chernoff.evidence import *  # noqa: F403
from fusion.book.chapters.chernoff.evidence import __all__ as _all_evidence
from fusion.book.chapters.chernoff.glue import *  # noqa: F403
from fusion.book.chapters.chernoff.glue import __all__ as _all_glue
# the claim file names each record's evidence function as fusion.book.chapters.chernoff:<name>
from fusion.book.chapters.chernoff.evidence import (  # noqa: F401
    ev_tracking,
    ev_pso,
    ev_formulas,
    ev_common_once,
    ev_gaussian_ci,
    ev_first_order,
    ev_is,
    ev_is_variance,
    ev_equal_kl,
    ev_filter_design,
    ev_peer,
    ev_premise,
)
from fusion.book.chapters.chernoff.glue import _referenced_keys  # noqa: F401  (the notebook checks the keys read)

from fusion.book.chapters.chernoff import compare as _compare_mod
from fusion.book.chapters.chernoff import glue as _glue_mod
from fusion.book.chapters.chernoff import peers as _peers_mod
from fusion.book.chapters.chernoff import premise as _premise_mod
from fusion.book.chapters.chernoff import settings as _settings_mod
from fusion.book.chapters.chernoff import swarm as _swarm_mod

# The documented constants, bound here so that the API page documents them under this package's name.
#: BibTeX key of the source.
BIBKEY = _settings_mod.BIBKEY
#: Frames 5 to the last (0-based slice; frames 5-30 in the study scenario): the frames over which errors are averaged.
LATE = _settings_mod.LATE
#: Frames 1-4 (0-based slice), where the shared prior still weighs most.
EARLY = _settings_mod.EARLY
#: Every frame.
ALL_FRAMES = _settings_mod.ALL_FRAMES
#: A run is *collapsed* when some node's filter keeps fewer effective particles than this fraction of its
#: particles (10 of the default 2,000), or the centralised filter fewer than this fraction of its own (50 of 10,000).
COLLAPSE_FRACTION = _settings_mod.COLLAPSE_FRACTION
#: Monte-Carlo runs of the chapter's study (the house minimum for a comparison).
STUDY_RUNS = _settings_mod.STUDY_RUNS
#: Worker processes of the study (:func:`fusion.scenarios.range_bearing.run_tracking_batch`; results do not depend on it).
STUDY_WORKERS = _settings_mod.STUDY_WORKERS
#: Why a comparison has fewer than :data:`STUDY_RUNS` runs (the runs kept when the collapsed ones are excluded).
STUDY_REASON = _settings_mod.STUDY_REASON
#: Schema of ``benchmarks/results/chernoff.json`` written by ``benchmarks/bench_chernoff.py`` for the current pipeline
#: (the study configuration, loop against batch, stage costs); a file without it predates that pipeline.
BENCH_SCHEMA = _swarm_mod.BENCH_SCHEMA
#: The patent's own stages, B-I.
PATENT_STAGES = _swarm_mod.PATENT_STAGES
#: The designed networks in the chapter's order (of their seeds, table columns and figure rows).
PREMISE_NETWORKS = _premise_mod.PREMISE_NETWORKS
#: The networks' labels in the chapter's table and figure, by key (in the order of :data:`PREMISE_NETWORKS`).
PREMISE_LABELS = _premise_mod.PREMISE_LABELS
#: Networks run with more than :data:`STUDY_RUNS` runs: none. The range-only network ran 400 times until the fourth
#: review showed that count was chosen after its 100-run result was seen; the relay network ran 400 times from the
#: commit that added it, with no record that the count was fixed before its outcome was read (review 5, m3). Every
#: network now runs the count every network had before any outcome was read; the reseeding sweep reruns every
#: primary at more runs.
PREMISE_MORE_RUNS = _premise_mod.PREMISE_MORE_RUNS
#: Networks with one exchange of fully connected nodes: their MSE oracle is a fixed exponent vector.
ORACLE_NETWORKS = _premise_mod.ORACLE_NETWORKS
#: NEES of a consistent estimator of a 4-D state (its expected value).
NEES_CONSISTENT = _compare_mod.NEES_CONSISTENT
#: Docname of the chapter.
SOURCE_CHAPTER = _glue_mod.SOURCE_CHAPTER
#: Stone Soup's ChernoffUpdater outputs, recorded by ``benchmarks/crosscheck_stonesoup.py`` in a side environment.
STONESOUP_RECORD = _peers_mod.STONESOUP_RECORD

__all__ = [*_all_settings, *_all_gaussian, *_all_mixture, *_all_peers, *_all_tracking, *_all_importance, *_all_compare,
           *_all_guard, *_all_swarm, *_all_review, *_all_premise, *_all_studies, *_all_evidence, *_all_glue]

name_by_package(globals())
