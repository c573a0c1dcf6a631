"""Chapter 05's keys and settings: the rule, architecture and reading keys of its studies, the source's published
weights, its claim file, and the seeds, runs and periods of its studies.
"""

from __future__ import annotations

from fusion._frozen import constant
from fusion import data
from fusion.book.claims import ClaimsFile, claims_dir
from fusion.book.claims import load as load_claims
from fusion.book.study_cache import process_cache
from fusion.scenarios import infrared_radar as ir
from fusion.scenarios.two_sensor import Architecture, ArchRule, StudyMethod, fixed_weight_rule
from fusion._counts import seed as check_seed
from fusion._shown import shown

__all__ = ["FIG6_PERIODS", "BIBKEY", "CLEARLY", "IR_KEYS", "W_PUB", "W_GRID", "METRIC", "claim_file", "SEED",
           "LEDGER_RUNS", "SOURCE_RUNS", "SOURCE_T", "SEARCH_STEP", "IR_T", "IR_DURATION", "SEED_OFFSETS",
           "study_seed", "FB", "FBC", "IND", "SPLIT_S", "SPLIT_O", "CI_N", "CVX_N", "PRINTED", "PRINTED_OWN", "LIT",
           "LIT_OWN", "IMP", "CI_", "CVX", "FZ", "IR_IMP", "IR_CVX", "IR_FZ", "FZ_N", "BSC_N",
           "LOSSLESS_N"]


BIBKEY = "wang2024covariance"

#: "Clearly higher / above" (明显高于) read as higher by more than this share of the baseline's own error.
CLEARLY = 0.1

#: Architecture keys of :class:`~fusion.scenarios.two_sensor.ArchitectureStudy`.
FB, FBC, IND = Architecture.FEEDBACK, Architecture.FEEDBACK_COMMON, Architecture.INDEPENDENT

#: Rule keys of the architecture study (:class:`~fusion.scenarios.two_sensor.ArchRule`).
SPLIT_S, SPLIT_O, CI_N, CVX_N = ArchRule.SPLIT_SHARED, ArchRule.SPLIT_OWN, ArchRule.CI, ArchRule.CONVEX
BSC_N, LOSSLESS_N = ArchRule.BSC, ArchRule.LOSSLESS

#: The weights the source publishes for plain CI (Fig. 5): FOA's and the exhaustive search's.
W_PUB = float(data.WANG2024_FOA.columns["foa_optimum"][0])
W_GRID = float(data.WANG2024_FOA.columns["grid_optimum"][0])
PRINTED, PRINTED_OWN = ArchRule.PRINTED_SHARED, ArchRule.PRINTED_OWN
#: Eqs. 11-12 at the published FOA weight, Q in the shared and in the own parts (architecture-study rule keys).
LIT, LIT_OWN = fixed_weight_rule("shared", W_PUB), fixed_weight_rule("own", W_PUB)

#: Method keys of the fusion and paired studies (independent local filters).
IMP, CI_, CVX, FZ = StudyMethod.SPLIT_CI, StudyMethod.CI, StudyMethod.CONVEX, StudyMethod.FUZZY
#: The same rules in the infrared + radar results (:class:`~fusion.scenarios.infrared_radar.IrMethod` keys).
IR_IMP, IR_CVX, IR_FZ = ir.IrMethod.SPLIT_CI, ir.IrMethod.CONVEX, ir.IrMethod.FUZZY
#: Fuzzy clustering's rule key in the architecture study.
FZ_N = ArchRule.FUZZY

#: The metric of the tracking comparisons.
METRIC = "per-run RMSE on x over t ≥ 20 s (m)"

#: Reading keys of the trackers of :data:`IR_READINGS`, in order.
IR_KEYS = ("angle", "angle-q-0-01", "angle-q-100", "cartesian", "cartesian-q-0-01", "cartesian-q-100")


@process_cache(maxsize=1)
def claim_file() -> ClaimsFile:
    """``book/claims/wang2024covariance.yaml``, validated, read once per session (:func:`fusion.book.claims.load`).

    Returns
    -------
    ClaimsFile
        The chapter's claim file (each call its own copy of the cached one: its mappings can be edited).
    """
    return load_claims(claims_dir() / f"{BIBKEY}.yaml")


#: The chapter's seed: every study's seed is this plus a fixed offset (the notebook's ``SEED``).
SEED = 2024

#: Runs of the ledger's paired, architecture and infrared + radar studies.
LEDGER_RUNS = 200

#: Runs of the source's case (§3.2: 50 Monte-Carlo runs) and its sampling period (s, our choice).
SOURCE_RUNS, SOURCE_T = int(data.WANG2024_SCENARIO["runs"]), 1.0

#: Step at which CI's weight is searched on the two pairs of ``weight_pairs``.
SEARCH_STEP = 60

#: Sampling period (s) and length (s) of the infrared + radar case.
IR_T, IR_DURATION = 0.1, 10.0

#: Offsets from the chapter's seed of each study's seed.
SEED_OFFSETS = constant({"unequal pair": 1, "paired identical": 20, "paired unequal": 21, "random weights": 22,
                "anisotropic pair": 23, "infrared + radar": 30, "architecture identical": 40,
                "architecture anisotropic": 41, "fig6 periods": 50})

#: Sampling periods (s) besides :data:`SOURCE_T` at which Fig. 6's two published weights are compared (a reading).
FIG6_PERIODS = (0.5, 0.2)


def study_seed(seed: int, study: str) -> int:
    """The seed of a study under the chapter's seed.

    Parameters
    ----------
    seed : int
        The chapter's seed (:data:`SEED` in the notebook).
    study : str
        A key of :data:`SEED_OFFSETS`.

    Returns
    -------
    int
        ``seed`` plus the study's offset in :data:`SEED_OFFSETS`.

    Raises
    ------
    TypeError
        ``study`` is not a str.
    ValueError
        ``study`` is not a key of :data:`SEED_OFFSETS`.
    """
    seed = check_seed(seed)
    if not isinstance(study, str):
        raise TypeError(f"study must be a str (a key of SEED_OFFSETS), got {type(study).__name__}")
    if study not in SEED_OFFSETS:
        raise ValueError(f"study must be a key of SEED_OFFSETS ({sorted(SEED_OFFSETS)}), got {shown(study, 80)}")
    return check_seed(seed, span=SEED_OFFSETS[study]) + SEED_OFFSETS[study]   # seed + offset a seed (fuzz 55 D1)
