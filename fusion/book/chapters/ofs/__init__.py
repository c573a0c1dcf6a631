"""Chapter "The optimal fusion set" (Yang, Feng & Fan 2012): tables, figures and claims.

The notebook ``notebooks/01_optimal_fusion_set.ipynb`` calls these functions; they assemble
the published-vs-recomputed tables of the source's Tables 2-3, the audit of which printed
values can follow from Table 1, the figures of Figs. 1-4 and of the Monte-Carlo repetition,
and the claims ledger of the source.

Modules
-------
settings
    The source, the chapter, the compared methods, the seed and the noise readings.
reproduction
    The source's Tables 1-3 recomputed and audited.
figures
    The figures and the Monte-Carlo table.
readings
    The choices the source leaves open (kernel family, α, units, eq. 9).
studies
    The Monte-Carlo studies the records use.
records
    One evidence function per record of the claim file (named there as ``fusion.book.chapters.ofs:ev_*``).
verdicts
    The ledger's numbers the prose quotes and the verdict table.

References
----------
* Yang G. N., Feng X. F., Fan L. J. (2012). Multi-sensor data fusion algorithm based on
   optimal fusion set. *Journal of Software* 23(Suppl. 1), 134-140.
* Sun Y., Jing B. (2005). Consistent and reliable fusion of multi-sensor based on support
   degree. *Chinese Journal of Sensors and Actuators* 18(3), 537-539.
"""

from fusion._public import name_by_package
from fusion.book.chapters.ofs.settings import *  # noqa: F403
from fusion.book.chapters.ofs.settings import __all__ as _settings
from fusion.book.chapters.ofs.reproduction import *  # noqa: F403
from fusion.book.chapters.ofs.reproduction import __all__ as _reproduction
from fusion.book.chapters.ofs.figures import *  # noqa: F403
from fusion.book.chapters.ofs.figures import __all__ as _figures
from fusion.book.chapters.ofs.readings import *  # noqa: F403
from fusion.book.chapters.ofs.readings import __all__ as _readings
from fusion.book.chapters.ofs.studies import *  # noqa: F403
from fusion.book.chapters.ofs.studies import __all__ as _studies
from fusion.book.chapters.ofs.records import *  # noqa: F403
from fusion.book.chapters.ofs.records import __all__ as _records
from fusion.book.chapters.ofs.verdicts import *  # noqa: F403
from fusion.book.chapters.ofs.verdicts import __all__ as _verdicts
# the claim file names each record's evidence function as fusion.book.chapters.ofs:<name>
from fusion.book.chapters.ofs.records import (  # noqa: F401
    ev_fig2_vs_mean,
    ev_fig2_fluctuation,
    ev_fig2_vs_support,
    ev_fig2_fluctuation_support,
    ev_fig4_vs_mean,
    ev_fig4_whole_vs_mean,
    ev_fig4_fluctuation_mean,
    ev_fig4_vs_support,
    ev_fig4_whole_vs_support,
    ev_fig4_fluctuation_support,
    ev_fig4_unaffected,
    ev_fig4_robust,
    ev_weights_reasonable,
    ev_membership_free,
    ev_weights_stability,
    ev_def3_keeps_valid,
    ev_set_rejects_faulty,
    ev_table2_ofs,
    ev_table2_mean,
    ev_table3_support,
    ev_totals,
    ev_totals_ranking_mean,
    ev_totals_ranking_support,
    ev_median_total,
    ev_obs_closer,
    ev_eq3_5_rejects,
    ev_eq9_defined,
)

from fusion.book.chapters.ofs import readings as _readings_mod
from fusion.book.chapters.ofs import settings as _settings_mod
from fusion.book.chapters.ofs import studies as _studies_mod

# The documented constants, bound here so that the API page documents them under this package's name.
#: BibTeX key of the source.
SOURCE = _settings_mod.SOURCE
#: Docname of the chapter.
CHAPTER = _settings_mod.CHAPTER
#: The three methods of the source's comparison, as :func:`fusion.readings.fusion_set.fuse_epochs` specs.
METHODS = _settings_mod.METHODS
#: Readings of the noise levels the source does not give: the primary (unequal, evenly spaced), equal noise, and
#: geometric spreads σ_max/σ_min = r from r^-1/2 to r^1/2 °C (the fair study's spread sweep; r = 4 is 0.5-2.0 °C).
NOISE = _settings_mod.NOISE
#: Fusion-degree (membership) functions of the distance ``d = abs(s_i - s_j)`` tried in place of
#: eq. 6, each with the length scale ``h`` (°C): eq. 6 itself, a Gaussian and a Cauchy kernel.
FAMILIES = _readings_mod.FAMILIES
#: Support-degree sharpness parameters (°C⁻²) run as alternatives to the primary α = 0.25.
ALPHAS = _readings_mod.ALPHAS
#: Scales of eq. 6 swept (°C).
SCALES = _studies_mod.SCALES

__all__ = [*_settings, *_reproduction, *_figures, *_readings, *_studies, *_records, *_verdicts]

name_by_package(globals())
