r"""Chapter 07 (time registration, Shi, Suo & Ma 2023): the claims ledger's evidence and the values its texts quote.

Every Monte-Carlo study the ledger needs (:func:`study`, computed once per seed and run count by
:func:`cached_study`), one evidence function per record of ``book/claims/shi2023time.yaml``, and the
stress, cost and gain values the chapter glues. Tables and figures are in
:mod:`fusion.book.chapters.time_registration`.

Modules
-------
study
    The Monte-Carlo study every record reads, and the methods, noise levels and changes it runs.
evidence
    One evidence function per record of the claim file (named there as
    ``fusion.book.chapters.time_registration_ledger:ev_*``).
costs
    The operation counts of the registration methods.
values
    The tables and values the chapter glues.
"""

from fusion.book.chapters.time_registration_ledger.study import *  # noqa: F403
from fusion.book.chapters.time_registration_ledger.study import __all__ as _study
from fusion.book.chapters.time_registration_ledger.evidence import *  # noqa: F403
from fusion.book.chapters.time_registration_ledger.evidence import __all__ as _evidence
from fusion.book.chapters.time_registration_ledger.costs import *  # noqa: F403
from fusion.book.chapters.time_registration_ledger.costs import __all__ as _costs
from fusion.book.chapters.time_registration_ledger.values import *  # noqa: F403
from fusion.book.chapters.time_registration_ledger.values import __all__ as _values
# the claim file names each record's evidence function as fusion.book.chapters.time_registration_ledger:<name>
from fusion.book.chapters.time_registration_ledger.evidence import (  # noqa: F401
    ev_samples,
    ev_figs23,
    ev_eqs,
    ev_metric,
    ev_interp_vs_ls,
    ev_curve_fitting,
    ev_kalman_s3,
    ev_three_noise,
    ev_improved,
    ev_improved_fair,
    ev_simplifies,
    ev_ls_info,
    ev_validated,
    ev_fig4_axis,
    ev_few_restrictions,
    ev_fusion,
)

__all__ = [*_study, *_evidence, *_costs, *_values]
