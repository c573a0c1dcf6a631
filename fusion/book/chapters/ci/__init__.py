r"""Chapter 05 (Wang & Tang 2024, covariance intersection): tables, figures and the claims ledger.

The studies themselves live in :mod:`fusion.scenarios.two_sensor` and
:mod:`fusion.scenarios.infrared_radar`; this module sets their results beside the published
numbers (:mod:`fusion.data.wang2024`), draws the chapter's figures and builds its
:class:`~fusion.book.ledger.Ledger`, one submodule per concept: the keys and settings (``constants``), the
tracking case (``tracking``), the CI weight (``weights``, ``fruit_fly_step``), bounds by period (``bounds``), the
feedback architecture (``architecture``), the printed equations (``printed``), consistency (``nees``), paired
comparisons (``paired``), the infrared + radar case (``infrared``, its trackers' readings ``infrared_readings``),
the claims' inputs and evidence (``claim_inputs``, ``claim_evidence``), the seeded studies (``studies``) and
number formatting (``text``). Every public name is re-exported here.

References
----------
* Wang Z., Tang X. (2024). Research on multi-sensor data fusion based on covariance cross
   fusion. *Electronic Measurement Technology*, DOI 10.19651/j.cnki.emt.2415396.
"""

from __future__ import annotations

from fusion._public import name_by_package
from fusion.book.chapters.ci import constants as _constants
from fusion.book.chapters.ci import text as _text
from fusion.book.chapters.ci import fruit_fly_step as _fruit_fly_step
from fusion.book.chapters.ci import bounds as _bounds
from fusion.book.chapters.ci import tracking as _tracking
from fusion.book.chapters.ci import infrared as _infrared
from fusion.book.chapters.ci import infrared_readings as _infrared_readings
from fusion.book.chapters.ci import printed as _printed
from fusion.book.chapters.ci import nees as _nees
from fusion.book.chapters.ci import records as _records
from fusion.book.chapters.ci import architecture as _architecture
from fusion.book.chapters.ci import claim_inputs as _claim_inputs
from fusion.book.chapters.ci import claim_evidence as _claim_evidence
from fusion.book.chapters.ci import weights as _weights
from fusion.book.chapters.ci import paired as _paired
from fusion.book.chapters.ci import studies as _studies
from fusion.book.chapters.ci.constants import *  # noqa: F401,F403
from fusion.book.chapters.ci.text import *  # noqa: F401,F403
from fusion.book.chapters.ci.fruit_fly_step import *  # noqa: F401,F403
from fusion.book.chapters.ci.bounds import *  # noqa: F401,F403
from fusion.book.chapters.ci.tracking import *  # noqa: F401,F403
from fusion.book.chapters.ci.infrared import *  # noqa: F401,F403
from fusion.book.chapters.ci.infrared_readings import *  # noqa: F401,F403
from fusion.book.chapters.ci.printed import *  # noqa: F401,F403
from fusion.book.chapters.ci.nees import *  # noqa: F401,F403
from fusion.book.chapters.ci.records import *  # noqa: F401,F403
from fusion.book.chapters.ci.architecture import *  # noqa: F401,F403
from fusion.book.chapters.ci.claim_inputs import *  # noqa: F401,F403
from fusion.book.chapters.ci.claim_evidence import *  # noqa: F401,F403
from fusion.book.chapters.ci.weights import *  # noqa: F401,F403
from fusion.book.chapters.ci.paired import *  # noqa: F401,F403
from fusion.book.chapters.ci.studies import *  # noqa: F401,F403

# The documented constants, bound here so that the API page documents them under this package's name.
#: "Clearly higher / above" (明显高于) read as higher by more than this share of the baseline's own error.
CLEARLY = _constants.CLEARLY
#: Architecture keys of :class:`~fusion.scenarios.two_sensor.ArchitectureStudy`.
FB, FBC, IND = _constants.FB, _constants.FBC, _constants.IND
#: The weights the source publishes for plain CI (Fig. 5): FOA's and the exhaustive search's.
W_PUB = _constants.W_PUB
#: Method keys of the fusion and paired studies (independent local filters).
IMP, CI_, CVX, FZ = _constants.IMP, _constants.CI_, _constants.CVX, _constants.FZ
#: The same rules in the infrared + radar results (:class:`~fusion.scenarios.infrared_radar.IrMethod` keys).
IR_IMP, IR_CVX, IR_FZ = _constants.IR_IMP, _constants.IR_CVX, _constants.IR_FZ
#: Fuzzy clustering's rule name in the architecture study.
FZ_N = _constants.FZ_N
#: The metric of the tracking comparisons.
METRIC = _constants.METRIC
#: Reading keys of the trackers of :data:`IR_READINGS`, in order.
IR_KEYS = _constants.IR_KEYS
#: The chapter's seed: every study's seed is this plus a fixed offset (the notebook's ``SEED``).
SEED = _constants.SEED
#: Runs of the ledger's paired, architecture and infrared + radar studies.
LEDGER_RUNS = _constants.LEDGER_RUNS
#: Runs of the source's case (§3.2: 50 Monte-Carlo runs) and its sampling period (s, our choice).
SOURCE_RUNS, SOURCE_T = _constants.SOURCE_RUNS, _constants.SOURCE_T
#: Step at which CI's weight is searched on the two pairs of ``weight_pairs``.
SEARCH_STEP = _constants.SEARCH_STEP
#: Sampling period (s) and length (s) of the infrared + radar case.
IR_T, IR_DURATION = _constants.IR_T, _constants.IR_DURATION
#: Offsets from the chapter's seed of each study's seed.
SEED_OFFSETS = _constants.SEED_OFFSETS
#: Sampling periods (s) besides :data:`SOURCE_T` at which Fig. 6's two published weights are compared (a reading).
FIG6_PERIODS = _constants.FIG6_PERIODS
#: Points of the exhaustive search at the 4 decimals the source prints its optimum to (step 10⁻⁴).
GRID_FINE = _fruit_fly_step.GRID_FINE
#: Test minima of :func:`fruit_fly_step_targets` besides the study's 0.8: the source's own optima lie near 0.
FRUIT_FLY_STEP_TARGETS = _fruit_fly_step.FRUIT_FLY_STEP_TARGETS
#: Step rules of the FOA step study: label -> (a, b) of the step a·rand + b.
FRUIT_FLY_STEP_RULES = _fruit_fly_step.FRUIT_FLY_STEP_RULES
#: Legend label of the causal straight-leg floor (registered in :data:`fusion.book.style.FIGURE_LABELS`).
CAUSAL_FLOOR_LABEL = _tracking.CAUSAL_FLOOR_LABEL
#: Label of the printed identical sensors in the architecture study and its table.
IDENTICAL_LABEL = _tracking.IDENTICAL_LABEL
#: Label and measurement covariances (m²) of the asymmetric anisotropic pair on which every rule separates.
ANISO_LABEL = _tracking.ANISO_LABEL
#: Legend label of the many-scan bound in :func:`ir_figure`.
IR_BOUND_LABEL = _infrared.IR_BOUND_LABEL
#: Azimuth conventions of the infrared + radar case: key of :func:`ir_study` -> description.
IR_AXES = _infrared_readings.IR_AXES
#: Readings of the trackers of source Figs. 9-10: label -> (tracker, factor on the process-noise variance).
#: The angle-space filters' Q is the rule of thumb σa = the path's largest angular acceleration; the
#: Cartesian filters' is white acceleration σa = 1 m/s² per axis. The first reading is the chapter's.
IR_READINGS = _infrared_readings.IR_READINGS
#: Intermediate white-acceleration levels σa (m/s²) of the Cartesian filters, readings of ``ci-fig9-angles`` only
#: (between the 1 and 10 m/s² of :data:`IR_READINGS`, where the published 0.05 mrad lies).
IR_SIGMA_A = _infrared_readings.IR_SIGMA_A
#: The σa grid (m/s²) over which the chapter reports where both angles round to the published 0.05 mrad.
IR_SIGMA_SCAN = _infrared_readings.IR_SIGMA_SCAN
#: Methods run under every reading of :data:`IR_READINGS` (the others only under the unscaled ones).
IR_ALWAYS = _infrared_readings.IR_ALWAYS
#: Column order of the per-run RMSE arrays of :func:`ir_readings`.
IR_COMPONENTS = _infrared_readings.IR_COMPONENTS
#: Methods of the y/x ratio table (keys of :attr:`IrReadings.run_rmse`), in row order.
IR_RATIO_METHODS = _infrared_readings.IR_RATIO_METHODS
#: Methods drawn in :func:`ir_figure`, in legend order.
IR_SHOWN = _infrared.IR_SHOWN
#: Names of the chapter's computed results that :func:`evidence` and :func:`ledger_values` read (:class:`LedgerInputs`).
LEDGER_INPUTS = _claim_inputs.LEDGER_INPUTS
#: The evidence functions of the chapter, in ledger order of their first record.
EVIDENCE_FUNCTIONS = _claim_evidence.EVIDENCE_FUNCTIONS

__all__ = (_constants.__all__ + _text.__all__ + _fruit_fly_step.__all__ + _bounds.__all__ + _tracking.__all__ +
           _infrared.__all__ + _infrared_readings.__all__ + _printed.__all__ + _nees.__all__ + _records.__all__ + _architecture.__all__ +
           _claim_inputs.__all__ + _claim_evidence.__all__ + _weights.__all__ + _paired.__all__ + _studies.__all__)

name_by_package(globals())
