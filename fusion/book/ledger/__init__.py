r"""The claims ledger: one record per checkable claim of a source, with a status derived by rule.

Every verdict of the book is a :class:`Claim` whose status is *computed* from its evidence,
never typed. A chapter builds its claims when it executes and writes them with
:meth:`Ledger.write` to ``book/ledger/<source>.json``; the Verdicts page, each chapter's
"In brief" box, the introduction's findings and the downloadable ``verdicts.csv`` /
``verdicts.json`` are rendered from those files by the book's Sphinx extension.

Status vocabulary (closed, :data:`STATUSES`)
--------------------------------------------
reproduced
    A published number equals ours at its printed precision; a comparative claim's paired 95 %
    confidence interval excludes zero in the claimed direction; a mathematical claim holds.
reproduced under stated assumptions
    As *reproduced*, but only under a choice the source leaves open (the record states the
    assumption), or not under every alternative reading that was run.
not reproduced
    A published number that our computation does not give at its printed precision.
contradicted
    A comparative claim whose interval excludes zero in the opposite direction, or a
    mathematical claim shown false.
not distinguishable
    A comparative claim whose interval contains zero, or lies wholly inside the practical margin
    the record states (a difference too small to matter, whatever its sign).
cannot be checked
    The source gives too little to compute anything (the record says why), or the evidence cannot decide
    the claim (an undefined or infinite statistic, R3; a member of a group that cannot be checked, R9).

Rules
-----
* :class:`PublishedValues` — reproduced iff every published value equals ours rounded to the
  published number of decimals.
* :class:`Comparison` — per-run metric of method A and of method B on the *same* runs; the 95 %
  interval of the mean paired difference A - B is Student's t interval of
  :func:`scipy.stats.ttest_rel`; the claim is "A is lower than B" (``claim="less"``) or "higher"
  (``claim="greater"``). With a practical ``margin`` m > 0 (tied by the record to the claimed effect),
  an interval wholly inside the closed [-m, m] is *not distinguishable* (an equivalence region, as in two one-sided
  tests; an end within round-off of ±m is the margin); an interval not wholly inside it keeps the rule above
  (rule R2).
* :class:`Proposition` — a computed yes/no (reproduced or contradicted).
* :class:`Conjunction` — a claim about every member of a group ("every sensor"): one comparison
  or proposition per member; contradicted if any member's is, otherwise cannot be checked if any
  member's is, reproduced if every member's is, otherwise not distinguishable.
* :class:`Unverifiable` — cannot be checked.
* A :class:`Claim` takes its primary evidence's status; *reproduced* becomes *reproduced under
  stated assumptions* when the claim lists assumptions or when any :class:`Alternative` reading
  does not also give *reproduced*. The statuses under every alternative are kept.

Modules
-------
statuses
    The status vocabulary, its definitions and the number format :func:`fmt`.
sources
    The sources the book checks (:data:`SOURCES`).
evidence
    The kinds of evidence and the status each gives by rule.
claim
    One record (:class:`Claim`) and its alternative readings (:class:`Alternative`).
store
    The ledger of one source (:class:`Ledger`), written to ``book/ledger``.

References
----------
* Student (1908). The probable error of a mean. *Biometrika*, 6(1), 1-25.
* Rougier, N. P. et al. (2017). Sustainable computational science: the ReScience
  initiative. *PeerJ Computer Science*, 3, e142.
"""

from fusion._public import name_by_package
from fusion.book.ledger.statuses import *  # noqa: F403
from fusion.book.ledger.statuses import __all__ as _statuses_all
from fusion.book.ledger.sources import *  # noqa: F403
from fusion.book.ledger.sources import __all__ as _sources_all
from fusion.book.ledger.evidence import *  # noqa: F403
from fusion.book.ledger.evidence import __all__ as _evidence_all
from fusion.book.ledger.evidence import EVIDENCE_TYPES, Evidence  # noqa: F401 (the evidence union, for annotations)
from fusion.book.ledger.claim import *  # noqa: F403
from fusion.book.ledger.claim import __all__ as _claim_all
from fusion.book.ledger.store import *  # noqa: F403
from fusion.book.ledger.store import __all__ as _store_all

from fusion.book.ledger import sources as _sources_mod
from fusion.book.ledger import statuses as _statuses_mod

# The documented constants, bound here so that the API page documents them under this package's name.
#: The closed status vocabulary, in display order (:data:`fusion.book.rulebook.STATUSES`).
STATUSES = _statuses_mod.STATUSES
#: Minimum number of Monte-Carlo runs for a stochastic record (fewer needs a stated reason).
MIN_RUNS = _statuses_mod.MIN_RUNS
#: Confidence level of every paired interval.
CONFIDENCE_LEVEL = _statuses_mod.CONFIDENCE_LEVEL
#: A comparison is heavy-tailed when this share of its runs (at least one run) carries half of the total absolute difference.
DOMINANCE_SHARE = _statuses_mod.DOMINANCE_SHARE
#: One-sentence definition of each status (shown on the Verdicts page); the rules that decide them are
#: :data:`fusion.book.rulebook.RULES`.
STATUS_DEFINITIONS = _statuses_mod.STATUS_DEFINITIONS
#: The five sources in book order.
SOURCES = _sources_mod.SOURCES

__all__ = [*_statuses_all, *_sources_all, *_evidence_all, *_claim_all, *_store_all]

name_by_package(globals())
