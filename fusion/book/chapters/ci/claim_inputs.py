"""Chapter 05's claims ledger: the inputs its evidence functions read (``LedgerInputs`` and its bundles)."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, fields, is_dataclass
from typing import Any

import numpy as np
import pandas as pd

from fusion._results import (ResultSpec, array, dict_of, instance, integer, number, shared_post_init, table, text,
                             tuple_of, validated_post_init)
from fusion._shown import shown
from fusion._limits import recorded_as
from fusion._validation import FloatArray, glue_part
from fusion.scenarios.two_sensor import ArchitectureStudy, NeesRule, FusionStudy, QScaling
from fusion.book.chapters.ci.checks import _arch_pair
from fusion.book.chapters.ci.constants import W_GRID, W_PUB
from fusion.book.chapters.ci.fruit_fly_step import (CANDIDATES_ABOVE, CANDIDATES_BELOW, EXHAUSTIVE,
                                                     FRUIT_FLY_STEP_RULES, LARGEST_ERROR, MEDIAN_ERROR, RUNS_WITHIN)
from fusion.book.chapters.ci.infrared_readings import IR_READINGS, IrReadings
from fusion.book.chapters.ci.paired import (_PAIRED_CLAIM_FIELDS, _REAL, _RUNS, PERIOD_KEY, WEIGHT_KEY, PairedClaimInputs,
                                            _real_keyed, _runs_relation)
from fusion.book.chapters.ci.printed import PrintedWeightFacts
from fusion.book.chapters.ci.tracking import _LEG_FIELDS, LegClaimInputs
from fusion.book.chapters.ci.weights import _WEIGHT_FIELDS, OMEGA_FOUND, TR_P, WeightClaimInputs, _hypothesis_table

__all__ = ["ArchInputs", "PeriodRuns", "PairedInputs", "IrInputs", "LedgerStudies", "LedgerInputs", "LEDGER_INPUTS",
           "ledger_inputs"]


# --------------------------------------------------------------------------- claims
#: Field specs of :class:`ArchInputs` (fusion._results), shared with the bundles that hold them.
_ARCH_FIELDS = {"arch": tuple_of(instance(ArchitectureStudy), count=2), "arch_seeds": tuple_of(integer(0), count=2)}


def _arch_relation(values: Mapping[str, Any], cls: str) -> None:
    """``arch`` holds architecture_studies' identical-sensor then anisotropic-pair study, told apart by the rules
    they record (fuzz 26c B2: swapped, or one study twice, the ledger read one pair's rules as the other's)."""
    _arch_pair(*values["arch"], (f"{cls}.arch[0]", f"{cls}.arch[1]"))


@dataclass(frozen=True)
class ArchInputs:
    """The ledger's entries of the two architecture studies (:func:`ledger_studies`).

    Attributes
    ----------
    arch : tuple of ArchitectureStudy
        The identical-sensor and the anisotropic pair's studies (:func:`arch_study`), in that order (told apart by
        the rules they record, else a ValueError when built: architecture_studies runs Q's placement on the
        identical sensors only).
    arch_seeds : tuple of int
        Their seeds, in the same order.
    """

    arch: tuple[ArchitectureStudy, ArchitectureStudy]
    arch_seeds: tuple[int, int]

    __result_spec__ = ResultSpec(_ARCH_FIELDS, relations=(lambda v, cls: _arch_relation(v, cls),))
    __post_init__ = validated_post_init


@dataclass(frozen=True)
class PeriodRuns:
    """CI at Fig. 5's two published weights on the identical sensors at one period of :data:`FIG6_PERIODS`.

    Attributes
    ----------
    seed : int
        Seed of the runs.
    fruit_fly : ndarray
        Per-run RMSE on x (m) at the fruit fly's published weight ``W_PUB``, shape (runs,).
    grid : ndarray
        The same at the grid's published weight ``W_GRID``, on the same runs.
    """

    seed: int
    fruit_fly: FloatArray
    grid: FloatArray

    __result_spec__ = ResultSpec({"seed": integer(0), "fruit_fly": _RUNS, "grid": _RUNS})
    __post_init__ = validated_post_init


#: Field specs of the ledger's inputs (fusion._results), by the class that declares the fields: every class that
#: holds them (PairedInputs, IrInputs, LedgerStudies, LedgerInputs) checks them when built.
_PAIRED_FIELDS = {**_PAIRED_CLAIM_FIELDS,
                  "aniso_seed": integer(0), "fig6_periods": _real_keyed(instance(PeriodRuns), glue_part, meaning=PERIOD_KEY),
                  "flat_range": number(), "flat_pub_grid": tuple_of(number(positive=True), count=2)}
_IR_FIELDS = {"ir_readings": instance(IrReadings), "ir_seed": integer(0),
              "ir_paired": dict_of(array("ir_runs", bounds=(0.0, np.inf))), "ir_means": dict_of(dict_of(number()))}
_PAIR = tuple_of(number(), count=2)
#: Columns of :func:`fruit_fly_step_study`'s and :func:`fruit_fly_step_targets`' tables that the ledger reads.
_FOA_STEP_COLUMNS = (CANDIDATES_BELOW, CANDIDATES_ABOVE, MEDIAN_ERROR, LARGEST_ERROR, RUNS_WITHIN, "runs")
#: The cells :func:`fruit_fly_step_study` makes there (fuzz 33b B2): shares and errors of ω in [0, 1], whole counts of
#: runs (at least one run; floats in :func:`fruit_fly_step_targets`' transposed table).
_FOA_STEP_CELLS = {CANDIDATES_BELOW: (0.0, 1.0, False), CANDIDATES_ABOVE: (0.0, 1.0, False),
                   MEDIAN_ERROR: (0.0, 1.0, False), LARGEST_ERROR: (0.0, 1.0, False),
                   RUNS_WITHIN: (0.0, np.inf, True), "runs": (1.0, np.inf, True)}


def _trace_relation(values: Mapping[str, Any], cls: str) -> None:
    """``printed.trace`` must hold the weights ``ledger_values`` and ``evidence`` read (fuzz 34b B2)."""
    missing = [w for w in (W_PUB, W_GRID, 1.0) if w not in values["printed"].trace]
    if missing:
        raise ValueError(f"{cls}.printed.trace misses the weights {shown(missing)} (the ledger reads tr P there)")


def _ir_scaled_relation(values: Mapping[str, Any], cls: str) -> None:
    """``ir_readings`` must hold the x axis's scaled readings (``ledger_values`` reads them; the default)."""
    missing = [("x", label) for label, (_, factor) in IR_READINGS.items()
               if factor != 1.0 and ("x", label) not in values["ir_readings"].run_rmse]
    if missing:
        raise ValueError(f"{cls}.ir_readings misses the scaled readings {shown(missing, 200)} of the x axis (the ledger "
                         "reads them: ir_readings with 'x' in scaled_axes)")
def _ir_period_relation(values: Mapping[str, Any], cls: str) -> None:
    """``ir_T`` is the period of the readings and one of ``ir_sens`` (fuzz 24c LI): the ledger glues it as the
    readings' period and compares the other periods of ``ir_sens`` with it, so another number would be glued as
    the period, or the readings' own period compared as "another period"."""
    T = float(values["ir_T"])
    periods = [float(k) for k in values["ir_sens"]]
    if not any(recorded_as(T, p) for p in periods):
        raise ValueError(f"{cls}.ir_T = {shown(T)} must be a period of ir_sens (the readings' own period), got the "
                         f"periods {shown(sorted(periods), 120)}")
    for axis, sim in values["ir_readings"].sims.items():
        if sim.t.size > 1 and not np.isclose(float(sim.t[1] - sim.t[0]), T, rtol=1e-9, atol=0.0):
            raise ValueError(f"{cls}.ir_T = {shown(T)} must be the period of ir_readings (its {shown(axis)} runs are at "
                             f"{shown(float(sim.t[1] - sim.t[0]))} s)")


#: The cells :func:`fig5_hypotheses` makes: tr P (m²) finite and positive, the weights ω found in [0, 1].
_FIG5_CELLS = {TR_P: (0.0, np.inf, False), OMEGA_FOUND: (0.0, 1.0, False)}
_LEDGER_FIELDS = {
    "study": instance(FusionStudy), "model_rmse": dict_of(number(), required=("x", "y")), "nees": dict_of(number()),
    "nees_runs": integer(1), "eq2_error": number(), "eq6_asym": number(), "bench": dict_of(number()),
    "bench_date": text(), "bench_per_step": dict_of(tuple_of(number())), "fig5_hyp": table(TR_P, OMEGA_FOUND, cells=_FIG5_CELLS),
    "rmse_variants": dict_of(_PAIR), "rmse_variants_all": dict_of(_PAIR),
    "ir_sens": _real_keyed(dict_of(number()), meaning=PERIOD_KEY),
    "ir_T": number(positive=True), "pcrb": dict_of(number(), required=("T1", "limit")), "q_scaling": instance(QScaling),
    "slip_all": dict_of(_PAIR), "slip_weights": _real_keyed(_PAIR, meaning=WEIGHT_KEY, required=(W_PUB, W_GRID)),
    "slip_band": dict_of(tuple_of(integer(0), count=2)), "printed": instance(PrintedWeightFacts), "exact_rmse": _PAIR,
    "fruit_fly_step_study": table(*_FOA_STEP_COLUMNS, index=(*FRUIT_FLY_STEP_RULES, EXHAUSTIVE), cells=_FOA_STEP_CELLS),
    "fruit_fly_step_targets": table(*_FOA_STEP_COLUMNS, cells=_FOA_STEP_CELLS)}


def _foa_targets_relation(values: Mapping[str, Any], cls: str) -> None:
    """``fruit_fly_step_targets`` is indexed by its test minima, distinct numbers in (0, 1) (fuzz 26c B4: the
    study's table of rules in its place was read as minima; the ledger reads both tables by what they hold)."""
    index = values["fruit_fly_step_targets"].index
    bad = [t for t in index if not isinstance(t, _REAL) or isinstance(t, (bool, np.bool_)) or not 0.0 < float(t) < 1.0]
    if bad or len(index) == 0:
        raise ValueError(f"{cls}.fruit_fly_step_targets must be indexed by test minima in (0, 1) (fruit_fly_step_targets"
                         f"), got the rows {shown(list(index), 200)}")
    if not index.is_unique:
        raise ValueError(f"{cls}.fruit_fly_step_targets repeats a test minimum: "
                         f"{shown(list(index[index.duplicated()]), 80)}")
    for name in ("fruit_fly_step_study", "fruit_fly_step_targets"):  # counts of runs (fuzz 33b B2)
        t = values[name]
        over = t[RUNS_WITHIN].to_numpy(dtype=float) > t["runs"].to_numpy(dtype=float)
        if over.any():
            raise ValueError(f"{cls}.{name} counts more runs within 0.05 than its runs in the row "
                             f"{shown(t.index[int(np.argmax(over))], 80)}")


@dataclass(frozen=True)
class PairedInputs(PairedClaimInputs):
    """The ledger's entries of the paired studies (:func:`ledger_studies`): :class:`PairedClaimInputs` and these.

    Attributes
    ----------
    aniso_seed : int
        Seed of the anisotropic pair.
    fig6_periods : dict of float to PeriodRuns
        :func:`fig6_periods`: period (s) -> the runs at the two published weights (no two periods alike in their
        digits, 1.5 and 15 included: each keys a glue value ``ci_fig6_d_*`` by them, ``fusion._counts.glue_part``).
    flat_range : float
        Range of tr P(ω) of the identical sensors at :data:`SEARCH_STEP` over 11 weights in [0, 1].
    flat_pub_grid : tuple of float
        CI's tr P there at Fig. 5's two published weights, FOA's and the grid's (m²).
    """

    aniso_seed: int
    fig6_periods: Mapping[float, PeriodRuns]
    flat_range: float
    flat_pub_grid: tuple[float, float]

    __result_spec__ = ResultSpec(_PAIRED_FIELDS, relations=(lambda v, cls: _runs_relation(v, cls),))
    __post_init__ = shared_post_init  # the studies' values shared, not copied


@dataclass(frozen=True)
class IrInputs:
    """The ledger's entries of the infrared + radar readings (:func:`ledger_studies`).

    Attributes
    ----------
    ir_readings : IrReadings
        :func:`ir_reading_study`.
    ir_seed : int
        Their seed.
    ir_paired : dict of str to ndarray
        :func:`ir_paired` of those readings: method -> per-run azimuth RMSE (mrad).
    ir_means : dict of str to dict
        Method -> {quantity -> late mean of the primary reading's RMSE}.
    """

    ir_readings: IrReadings
    ir_seed: int
    ir_paired: Mapping[str, np.ndarray]
    ir_means: Mapping[str, Mapping[str, float]]

    __result_spec__ = ResultSpec(_IR_FIELDS, relations=(lambda v, cls: _ir_scaled_relation(v, cls),))
    __post_init__ = shared_post_init  # the studies' values shared, not copied


@dataclass(frozen=True)
class LedgerStudies(IrInputs, PairedInputs, ArchInputs):
    """The entries of :class:`LedgerInputs` that the chapter's Monte-Carlo studies give (:func:`ledger_studies`).

    Attributes
    ----------
    arch
        As in :class:`ArchInputs`.
    arch_seeds
        As in :class:`ArchInputs`.
    paired
        As in :class:`PairedInputs`.
    paired_runs
        As in :class:`PairedInputs`.
    paired_seed
        As in :class:`PairedInputs`.
    paired_unequal
        As in :class:`PairedInputs`.
    unequal_seed
        As in :class:`PairedInputs`.
    paired_random
        As in :class:`PairedInputs`.
    random_seed
        As in :class:`PairedInputs`.
    paired_aniso
        As in :class:`PairedInputs`.
    paired_fig6
        As in :class:`PairedInputs`.
    fuzzy_levels
        As in :class:`PairedInputs`.
    aniso_seed
        As in :class:`PairedInputs`.
    fig6_periods
        As in :class:`PairedInputs`.
    flat_range
        As in :class:`PairedInputs`.
    flat_pub_grid
        As in :class:`PairedInputs`.
    ir_readings
        As in :class:`IrInputs`.
    ir_seed
        As in :class:`IrInputs`.
    ir_paired
        As in :class:`IrInputs`.
    ir_means
        As in :class:`IrInputs`.
    """

    __result_spec__ = ResultSpec({**_ARCH_FIELDS, **_PAIRED_FIELDS, **_IR_FIELDS},
                                 relations=(lambda v, cls: _runs_relation(v, cls),
                                            lambda v, cls: _ir_scaled_relation(v, cls),
                                            lambda v, cls: _arch_relation(v, cls)))
    __post_init__ = shared_post_init  # the studies' values shared, not copied


@dataclass(frozen=True)
class LedgerInputs(LedgerStudies, WeightClaimInputs, LegClaimInputs):
    """The chapter's computed results that :func:`evidence` and :func:`ledger_values` read (:func:`ledger_inputs`).

    Besides the attributes of :class:`LedgerStudies` (the Monte-Carlo studies), :class:`WeightClaimInputs` (the weight
    search) and :class:`LegClaimInputs` (the straight leg's floors):

    Attributes
    ----------
    study : FusionStudy
        The chapter's study (50 runs, T = 1 s).
    model_rmse : dict of str to float
        Split CI on targets that follow the model: ``"x"``, ``"y"`` (m).
    nees : dict of NeesRule to float
        Mean NEES of each rule.
    nees_runs : int
        Runs of those NEES.
    eq2_error : float
        Largest change of two identical estimates under eq. 2.
    eq6_asym : float
        Largest asymmetry of eq. 6's matrix as extracted.
    bench : dict of str to float
        ``benchmarks/results/ci.json``'s measurements by key (s, or a count).
    bench_date : str
        Its date.
    bench_per_step : dict of str to list
        Its per-step timings and evaluation counts.
    fig5_hyp : pandas.DataFrame
        :func:`fig5_hypotheses` (its five rows in its order, columns ``tr P`` and ``ω found``: the rows and columns
        the ledger reads; another table is refused, naming the field).
    rmse_variants : dict of str to tuple
        Readings of eq. 13 -> (x, y) RMSE (m), over the steady steps.
    rmse_variants_all : dict of str to tuple
        The same over every step.
    ir_sens : dict of float to dict
        Infrared + radar: period (s) -> quantity -> late mean of the improved CI.
    ir_T : float
        The infrared + radar case's period (s): the period of ``ir_readings`` and one of ``ir_sens`` (else a
        ValueError when built).
    pcrb : dict of str to float
        The bound at ``"T1"`` and in the ``"limit"`` (m).
    q_scaling : QScaling
        The study of scaled Q.
    slip_all : dict of str to tuple
        :func:`slip_all`.
    slip_weights : dict of float to tuple
        :func:`slip_at_weights` at (at least) the published weights 0.0018 and 0.0033, which its readers read.
    slip_band : dict of str to tuple
        :func:`slip_band`.
    printed : PrintedWeightFacts
        :func:`printed_weight_facts` (its ``trace`` at least at the weights 0.0018, 0.0033 and 1, which are read).
    exact_rmse : tuple of float
        Exact RMSE of CI = the average on the path, (x, y) (m).
    fruit_fly_step_study : pandas.DataFrame
        :func:`fruit_fly_step_study`: its rows the step rules and the exhaustive search, read by label (a table
        without them, the targets' table for one, is a ValueError when built).
    fruit_fly_step_targets : pandas.DataFrame
        :func:`fruit_fly_step_targets`: its rows indexed by distinct test minima in (0, 1) (else a ValueError when
        built).
    """

    study: FusionStudy
    model_rmse: Mapping[str, float]
    nees: Mapping[NeesRule, float]
    nees_runs: int
    eq2_error: float
    eq6_asym: float
    bench: Mapping[str, float]
    bench_date: str
    bench_per_step: Mapping[str, tuple[float, ...]]
    fig5_hyp: pd.DataFrame
    rmse_variants: Mapping[str, tuple[float, float]]
    rmse_variants_all: Mapping[str, tuple[float, float]]
    ir_sens: Mapping[float, Mapping[str, float]]
    ir_T: float
    pcrb: Mapping[str, float]
    q_scaling: QScaling
    slip_all: Mapping[str, tuple[float, float]]
    slip_weights: Mapping[float, tuple[float, float]]
    slip_band: Mapping[str, tuple[int, int]]
    printed: PrintedWeightFacts
    exact_rmse: tuple[float, float]
    fruit_fly_step_study: pd.DataFrame
    fruit_fly_step_targets: pd.DataFrame

    __result_spec__ = ResultSpec({**_ARCH_FIELDS, **_PAIRED_FIELDS, **_IR_FIELDS, **_WEIGHT_FIELDS, **_LEG_FIELDS,
                                  **_LEDGER_FIELDS}, relations=(lambda v, cls: _runs_relation(v, cls),
                                                                lambda v, cls: _trace_relation(v, cls),
                                                                lambda v, cls: _ir_scaled_relation(v, cls),
                                                                lambda v, cls: _ir_period_relation(v, cls),
                                                                lambda v, cls: _arch_relation(v, cls),
                                                                lambda v, cls: _foa_targets_relation(v, cls),
                                                                # the rows and columns ev_fig5 reads (fuzz 29b B4)
                                                                lambda v, cls: _hypothesis_table(
                                                                    v["fig5_hyp"], f"{cls}.fig5_hyp",
                                                                    (TR_P, OMEGA_FOUND))))
    __post_init__ = shared_post_init  # the studies' values shared, not copied


#: Names of the chapter's computed results that :func:`evidence` and :func:`ledger_values` read (:class:`LedgerInputs`).
LEDGER_INPUTS = tuple(f.name for f in fields(LedgerInputs))


def ledger_inputs(*bundles: object, **parts: Any) -> LedgerInputs:
    """The chapter's computed results that the ledger reads, checked for completeness.

    Parameters
    ----------
    *bundles
        Typed parts whose attributes are entries (:class:`LedgerStudies`, :class:`WeightClaimInputs`,
        :class:`LegClaimInputs`, ...); their values are shared, not copied.
    **parts
        The other entries of :data:`LEDGER_INPUTS` by name (:class:`LedgerInputs` documents each). The entries of the
        Monte-Carlo studies the stochastic records read come from :func:`ledger_studies` (the functions the
        reseeding sweep calls).

    Returns
    -------
    LedgerInputs
        Every field of the bundles and of ``parts`` by name (studies, weight-search and straight-leg inputs).

    Raises
    ------
    ValueError
        If a bundle is not a dataclass instance, or an entry is missing, unknown or given twice.
    """
    entries: dict[str, Any] = {}
    twice: list[str] = []
    for i, b in enumerate(bundles):
        if not is_dataclass(b) or isinstance(b, type):
            raise ValueError(f"bundles: item {i} is not a dataclass instance ({type(b).__name__})")
        for f in fields(b):
            if f.name in entries:
                twice.append(f.name)
            entries[f.name] = getattr(b, f.name)
    twice += [k for k in parts if k in entries]
    entries.update(parts)
    missing = [k for k in LEDGER_INPUTS if k not in entries]
    extra = sorted(set(entries) - set(LEDGER_INPUTS))
    if missing or extra or twice:
        raise ValueError(f"parts: missing {missing}, unknown {extra}, given twice {sorted(set(twice))}")
    return LedgerInputs(**entries)
