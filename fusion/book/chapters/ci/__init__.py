r"""Chapter 05 (Wang & Tang 2024, covariance intersection): tables, figures and the claims ledger.

The studies themselves live in :mod:`fusion.scenarios.two_sensor` and
:mod:`fusion.scenarios.infrared_radar`; this module sets their results beside the published
numbers (:mod:`fusion.data.wang2024`), draws the chapter's figures and builds its
:class:`~fusion.book.ledger.Ledger`, one submodule per concept: the keys and settings (``constants``), the
tracking case (``tracking``), the CI weight (``weights``, ``foa_step``), bounds by period (``bounds``), the
feedback architecture (``architecture``), the printed equations (``printed``), consistency (``nees``), paired
comparisons (``paired``), the infrared + radar case (``infrared``), the claims' evidence (``claim_evidence``),
the seeded studies (``studies``) and number formatting (``text``). Every public name is re-exported here.

References
----------
* Wang Z., Tang X. (2024). Research on multi-sensor data fusion based on covariance cross
   fusion. *Electronic Measurement Technology*, DOI 10.19651/j.cnki.emt.2415396.
"""

from __future__ import annotations

from fusion.book.chapters.ci import constants as _constants
from fusion.book.chapters.ci import text as _text
from fusion.book.chapters.ci import foa_step as _foa_step
from fusion.book.chapters.ci import bounds as _bounds
from fusion.book.chapters.ci import tracking as _tracking
from fusion.book.chapters.ci import infrared as _infrared
from fusion.book.chapters.ci import printed as _printed
from fusion.book.chapters.ci import nees as _nees
from fusion.book.chapters.ci import architecture as _architecture
from fusion.book.chapters.ci import claim_evidence as _claim_evidence
from fusion.book.chapters.ci import weights as _weights
from fusion.book.chapters.ci import paired as _paired
from fusion.book.chapters.ci import studies as _studies
from fusion.book.chapters.ci.constants import *  # noqa: F401,F403
from fusion.book.chapters.ci.text import *  # noqa: F401,F403
from fusion.book.chapters.ci.foa_step import *  # noqa: F401,F403
from fusion.book.chapters.ci.bounds import *  # noqa: F401,F403
from fusion.book.chapters.ci.tracking import *  # noqa: F401,F403
from fusion.book.chapters.ci.infrared import *  # noqa: F401,F403
from fusion.book.chapters.ci.printed import *  # noqa: F401,F403
from fusion.book.chapters.ci.nees import *  # noqa: F401,F403
from fusion.book.chapters.ci.architecture import *  # noqa: F401,F403
from fusion.book.chapters.ci.claim_evidence import *  # noqa: F401,F403
from fusion.book.chapters.ci.weights import *  # noqa: F401,F403
from fusion.book.chapters.ci.paired import *  # noqa: F401,F403
from fusion.book.chapters.ci.studies import *  # noqa: F401,F403

__all__ = (_constants.__all__ + _text.__all__ + _foa_step.__all__ + _bounds.__all__ + _tracking.__all__ +
           _infrared.__all__ + _printed.__all__ + _nees.__all__ + _architecture.__all__ + _claim_evidence.__all__ +
           _weights.__all__ + _paired.__all__ + _studies.__all__)
