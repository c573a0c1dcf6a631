"""The chapter's seeded studies, cached by (seed, runs), and the reseedable evidence of its stochastic records.

The stochastic records (their ledger entries carry a run count) are evaluated by
:func:`fusion.book.claims.evaluate` as ``fn(settings, *, seed, runs)`` (``settings["reading"]`` names the
reading): every Monte-Carlo study they read is computed here from (seed, runs) alone, by the cached study
functions below, so records sharing a study share its computation within a process. The notebook builds the
same studies through the same functions at :data:`SEED` and :data:`LEDGER_RUNS` (:func:`ledger_studies`).
"""

from __future__ import annotations

import dataclasses
import functools
import inspect
from collections.abc import Callable, Mapping
from typing import Any, cast

import numpy as np

from fusion.book.study_cache import process_cache, study_cache
from fusion._options import text
from fusion._validation import count
from fusion.book._few_runs import runs_first, runs_named
from fusion.book._reader_settings import reads, settings_first
from fusion.book.ledger import Evidence
from fusion.estimates.ci import ci_objective
from fusion.filtering.tracks import fuse_tracks
from fusion.scenarios import infrared_radar as ir
from fusion.scenarios import two_sensor
from fusion.scenarios.two_sensor import ArchitectureStudy, Scenario
from fusion.book.chapters.ci.architecture import _arch_banks, _arch_budget, _arch_parts, architecture_studies
from fusion.book.chapters.ci.claim_inputs import ArchInputs, IrInputs, LedgerStudies, PairedInputs, PeriodRuns
from fusion.book.chapters.ci.claim_evidence import (_vs_ci, _x_below_y,
                                                    ev_fig6, ev_ir_baselines)
from fusion.book.chapters.ci.constants import (claim_file, FIG6_PERIODS, SEED_OFFSETS, IR_DURATION, IR_T, LEDGER_RUNS, SEARCH_STEP, SEED,
                                               SOURCE_RUNS, SOURCE_T, W_GRID, W_PUB, study_seed)
from fusion.book.chapters.ci.infrared_readings import IrReadings, ir_paired, ir_readings
from fusion.book.chapters.ci.paired import PairedStudies, paired_studies
from fusion.book.chapters.ci.printed import printed_covariances
from fusion.book.chapters.ci.tracking import ANISO_R
from fusion.book.chapters.ci.weights import WeightPair, weight_pair
from fusion._counts import seed as check_seed
from fusion._shown import shown

__all__ = ["fig6_periods", "source_scenario", "step_weights", "unequal_pair", "aniso_pair", "arch_study",
           "paired_study", "ir_reading_study", "ledger_studies", "record_evidence", "ev_fig4_convex_part",
           "ev_fig7_improved_vs_ci", "ev_fig6_foa_vs_grid", "ev_fig10_x_below_y", "ev_fig10_convex_errors",
           "ev_fig10_fuzzy_errors"]


def _study_cache(fn: Any) -> Any:
    """Cache a study function of (seed[, runs]) on its arguments bound to its parameters, checked as ints.

    ``f(2024)``, ``f(seed=2024)`` and ``f()`` then share one computation (a bare :func:`functools.lru_cache` keys
    them apart).
    """
    sig = inspect.signature(fn)
    cached = study_cache(maxsize=4)(fn)

    @functools.wraps(fn)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        bound = sig.bind(*args, **kwargs)
        bound.apply_defaults()
        # each argument checked by its name before the cache key is made (rule 11 and 13): ``int()`` would read
        # 1.5 as 1, True as 1 and '3' as 3 (fuzz 17)
        return cached(*(check_seed(v, k) if k == "seed" else count(v, k) for k, v in bound.arguments.items()))

    wrapper.cache_clear = cached.cache_clear   # type: ignore[attr-defined]
    return wrapper


@_study_cache
def source_scenario(seed: int = SEED) -> Scenario:
    """The source's case under ``seed``: printed covariances, :data:`SOURCE_RUNS` runs, T = :data:`SOURCE_T` (cached).

    Parameters
    ----------
    seed : int
        Seed of the runs (the chapter's seed).

    Returns
    -------
    Scenario
        The true path and both sensors' measurements and Kalman tracks over the source's runs, from this seed.
    """
    seed = check_seed(seed)
    Q, R1, R2 = printed_covariances()
    return two_sensor.two_sensor_scenario(R1, R2, Q, np.random.default_rng(seed),
                                          runs=SOURCE_RUNS, T=SOURCE_T)


@_study_cache
def step_weights(seed: int = SEED) -> tuple[np.ndarray, np.ndarray]:
    """FOA's and the grid's weight at every step on the printed identical sensors (cached).

    :func:`fusion.scenarios.two_sensor.per_step_weights` on :func:`source_scenario`'s tracks, FOA seeded by ``seed``;
    the weights depend on the gains only, so every set of runs of the pair shares them.

    Parameters
    ----------
    seed : int
        The chapter's seed.

    Returns
    -------
    w_fruit_fly, w_grid : ndarray, shape (K,)
        CI's weight ω at each of the K steps, chosen by FOA and by the 1001-point grid.
    """
    seed = check_seed(seed)
    return two_sensor.per_step_weights(*source_scenario(seed).tracks, seed)


@_study_cache
def unequal_pair(seed: int = SEED) -> WeightPair:
    """Sensor 2 three times more precise, :data:`SOURCE_RUNS` runs, CI's weight searched at :data:`SEARCH_STEP` (cached).

    Parameters
    ----------
    seed : int
        The chapter's seed (the runs use its ``"unequal pair"`` offset, the searches the seed itself).

    Returns
    -------
    WeightPair
        The unequal pair's scenario and covariances at :data:`SEARCH_STEP`, every method's optimum of ω and FOA's over
        100 seeds.
    """
    # the fruit-fly seeds seed .. seed + 99 and the runs' seed + offset, each a seed, checked at entry (fuzz 55 D1)
    seed = check_seed(seed, span=max(99, study_seed(0, "unequal pair")))
    Q, R1, _ = printed_covariances()
    return weight_pair(R1, R1 / 9, Q, SEARCH_STEP, seed=study_seed(seed, "unequal pair"), search_seed=seed,
                       fruit_fly_seeds=[seed + i for i in range(100)], runs=SOURCE_RUNS, T=SOURCE_T)


@_study_cache
def aniso_pair(seed: int = SEED, runs: int = LEDGER_RUNS) -> WeightPair:
    """The anisotropic pair (``ANISO_R``), ``runs`` runs, CI's weight searched at :data:`SEARCH_STEP` (cached).

    Its runs serve the paired study (:func:`paired_study`) too.

    Parameters
    ----------
    seed : int
        The chapter's seed (the runs use its ``"anisotropic pair"`` offset, the searches the seed itself).
    runs : int

    Returns
    -------
    WeightPair
        The anisotropic pair's scenario and covariances at :data:`SEARCH_STEP`, every method's optimum of ω and FOA's
        over 100 seeds.
    """
    seed = check_seed(seed, span=max(99, study_seed(0, "anisotropic pair")))   # as unequal_pair's (fuzz 55 D1)
    Q = printed_covariances()[0]
    return weight_pair(*ANISO_R, Q, SEARCH_STEP, seed=study_seed(seed, "anisotropic pair"), search_seed=seed,
                       fruit_fly_seeds=[seed + i for i in range(100)], runs=count(runs, "runs"), T=SOURCE_T)


@_study_cache
def arch_study(seed: int = SEED, runs: int = LEDGER_RUNS) -> dict[str, ArchitectureStudy]:
    """:func:`architecture_studies` of both pairs at the published weight, ``runs`` runs on the path and on model targets (cached).

    Parameters
    ----------
    seed : int
        The chapter's seed (offsets ``"architecture identical"`` and ``"architecture anisotropic"``).
    runs : int

    Returns
    -------
    dict
        ``IDENTICAL_LABEL`` and ``ANISO_LABEL`` -> ArchitectureStudy.

    Raises
    ------
    ValueError
        ``runs`` whose two studies together hold or run beyond the memory or work budget (their sum, the entry of
        ``fusion._limits.STUDY_WORK`` the reseeding sweep's call serves: about 4,700 runs), before either study.
    """
    seed = check_seed(seed)
    # both studies summed at entry, named by this function's runs (fuzz 57a C5); architecture_studies checks the same
    _arch_budget(SOURCE_T, count(runs, "runs"), runs, len(_ARCH_FIXED), "runs")
    Q, R1, R2 = printed_covariances()
    seeds = (study_seed(seed, "architecture identical"), study_seed(seed, "architecture anisotropic"))
    return architecture_studies(R1, R2, Q, seeds, W_PUB, runs=runs, nees_runs=runs, T=SOURCE_T,
                                fixed_omegas=_ARCH_FIXED)


def _paired_budget(runs: int) -> int:
    """Rules 9 and 17 of :func:`paired_study` before any study, refused naming ``runs``; its units.

    What it holds at its peak (``_PAIRED_HELD`` arrays of ``(runs, K, 4)``); what it runs, each by the inner
    function's own budget, summed (``fusion.book._study_budget.studies_first``): the three scenarios of ``runs`` runs
    (the anisotropic pair's, :func:`aniso_pair`, and the identical and unequal pairs' of ``paired_studies``:
    ``case._scenario_budget``); every ``fuse_tracks`` of the three ``fusion_study`` runs and of the identical pair's
    Fig. 6 and random weights (``fuse_tracks``' own weights); the per-step weights (``per_step_weights``' own units)
    of the identical, unequal and anisotropic pairs; the rest at its measured weight (``_PAIRED_REST``). Fuzz 54a D4:
    70,000 runs ran the anisotropic pair for 3.2 CPU-s before a refusal naming seven arguments; fuzz 55 C3: only the
    three scenarios were counted, so 11,000 runs were accepted and ran 44 CPU-s.
    """
    from fusion.book._study_budget import studies_first

    return studies_first(_paired_parts(runs), "runs")


def _paired_parts(runs: int) -> list[Callable[[], int | None]]:
    """The parts of :func:`_paired_budget`, each an inner budget (``fusion.book._study_budget.studies_first``'s
    ``parts``): a chapter study that runs :func:`paired_study` beside others sums them with its own."""
    from fusion.book.chapters.ci.paired import _paired_studies_parts
    from fusion.scenarios.two_sensor.case import _scenario_budget
    from fusion.scenarios.two_sensor.weights import _weights_step_units

    steps = two_sensor.trajectory(SOURCE_T).t.size
    # paired_studies' own parts (the identical and unequal pairs' scenarios, every fusion, two per-step weights, the
    # rest) at Fig. 6's two weights, and what paired_study runs before it: aniso_pair's scenario and step_weights
    return [*_paired_studies_parts(runs, steps, runs, steps, 2, "runs"), lambda: _scenario_budget(runs, steps, "runs"),
            lambda: steps * _weights_step_units()]


@_study_cache
def paired_study(seed: int = SEED, runs: int = LEDGER_RUNS) -> PairedStudies:
    """:func:`paired_studies` on ``runs`` fresh runs of each pair, CI also at Fig. 6's two published weights (cached).

    Parameters
    ----------
    seed : int
        The chapter's seed (offsets ``"paired identical"``, ``"paired unequal"`` and ``"random weights"``; the
        per-step weights' FOA uses the seed itself).
    runs : int

    Returns
    -------
    PairedStudies
        Per rule the per-run RMSE on x after 20 s (m) of the identical, unequal and anisotropic pairs, on ``runs``
        runs.

    Raises
    ------
    ValueError
        ``runs`` whose scenarios, fusions and per-run errors together hold or run beyond the memory or work budget
        (about 2,500 runs, ~10 CPU-s), before any study.
    """
    seed = check_seed(seed)
    _paired_budget(count(runs, "runs"))
    Q, R1, R2 = printed_covariances()
    seeds = tuple(study_seed(seed, s) for s in ("paired identical", "paired unequal", "random weights"))
    return paired_studies(R1, R2, Q, step_weights(seed), unequal_pair(seed), aniso_pair(seed, runs), runs=runs,
                          seeds=seeds, weight_seed=seed, fig6_omegas=(W_PUB, W_GRID), T=SOURCE_T)


@_study_cache
def ir_reading_study(seed: int = SEED, runs: int = LEDGER_RUNS) -> IrReadings:
    """:func:`ir_readings` of the infrared + radar case (:data:`IR_T`, :data:`IR_DURATION`) on ``runs`` runs (cached).

    Parameters
    ----------
    seed : int
        The chapter's seed (offset ``"infrared + radar"``).
    runs : int

    Returns
    -------
    IrReadings
        :func:`ir_readings`.
    """
    seed = check_seed(seed)
    return ir_readings(IR_T, study_seed(seed, "infrared + radar"), count(runs, "runs"), IR_DURATION)


@process_cache(maxsize=4)
def _arch_inputs(seed: int, runs: int) -> ArchInputs:
    ai, an = arch_study(seed, runs).values()
    return ArchInputs(arch=(ai, an),
                      arch_seeds=(study_seed(seed, "architecture identical"), study_seed(seed, "architecture anisotropic")))


def _fig6_parts(runs: int) -> list[Callable[[], int]]:
    """The parts of :func:`fig6_periods` (``fusion.book._study_budget.studies_first``'s ``parts``): at each of
    :data:`FIG6_PERIODS` a scenario and CI at two weights (``two_sensor_scenario``'s and ``fuse_tracks``' own units),
    which :func:`fig6_periods` sums at its entry and :func:`ledger_studies` with its other studies."""
    from fusion.filtering.tracks import _fuse_tracks_units
    from fusion.scenarios.two_sensor.case import _scenario_budget

    def period(T: float) -> int:
        k = two_sensor.trajectory(T).t.size
        return _scenario_budget(runs, k, "runs") + 2 * _fuse_tracks_units(k, runs, 4, "ci")

    return [lambda T=T: period(T) for T in FIG6_PERIODS]


@_study_cache
def fig6_periods(seed: int = SEED, runs: int = LEDGER_RUNS) -> dict[float, PeriodRuns]:
    """CI at Fig. 5's two published weights on fresh runs of the identical sensors at each of :data:`FIG6_PERIODS` (cached).

    The printed Q (per step) and R, the same path; per-run RMSE on x over t ≥ 20 s.

    Parameters
    ----------
    seed : int
        The chapter's seed (offset ``"fig6 periods"``, plus the period's index).
    runs : int

    Returns
    -------
    dict of float to PeriodRuns
        Period (s) -> the per-run RMSE (m) at the two weights and the seed of those runs.

    Raises
    ------
    ValueError
        ``runs`` whose periods' scenarios and fusions together hold or run beyond the memory or work budget (about
        6,400 runs), before any scenario.
    """
    seed = check_seed(seed, span=study_seed(0, "fig6 periods") + len(FIG6_PERIODS) - 1)   # period i's (fuzz 55 D1)
    # the periods summed at entry (fuzz 57a C2: each period checked alone, 16,000 runs ran T = 0.5 s for 8.4 CPU-s,
    # then were refused by T = 0.2 s's scenario naming "runs and T")
    from fusion.book._study_budget import studies_first
    studies_first(_fig6_parts(count(runs, "runs")), "runs")
    Q, R1, R2 = printed_covariances()
    out: dict[float, PeriodRuns] = {}
    for i, T in enumerate(FIG6_PERIODS):
        s = study_seed(seed, "fig6 periods") + i
        sc = two_sensor.two_sensor_scenario(R1, R2, Q, np.random.default_rng(s), runs=runs, T=T)
        steady = sc.t >= 20.0
        at = {w: two_sensor.run_rmse(fuse_tracks(*sc.tracks, "ci", omega=w).est, sc.truth, steady, 0)
              for w in (W_PUB, W_GRID)}
        out[T] = PeriodRuns(seed=s, fruit_fly=at[W_PUB], grid=at[W_GRID])
    return out


@process_cache(maxsize=4)
def _paired_inputs(seed: int, runs: int) -> PairedInputs:
    a, b = source_scenario(seed).tracks
    flat = ci_objective(np.linspace(0, 1, 11), a.gains.P[SEARCH_STEP], b.gains.P[SEARCH_STEP])
    pub_grid = ci_objective(np.array([W_PUB, W_GRID]), a.gains.P[SEARCH_STEP], b.gains.P[SEARCH_STEP])
    return PairedInputs(**_shallow(paired_study(seed, runs).claim_inputs()), aniso_seed=study_seed(seed, "anisotropic pair"),
                        fig6_periods=fig6_periods(seed, runs), flat_range=float(np.ptp(flat)),
                        flat_pub_grid=(float(pub_grid[0]), float(pub_grid[1])))


@process_cache(maxsize=4)
def _ir_inputs(seed: int, runs: int) -> IrInputs:
    rd = ir_reading_study(seed, runs)
    sim = rd.sims["x"]   # the primary's simulation: Figs. 9-10's curves and means on the readings' own runs
    return IrInputs(ir_readings=rd, ir_seed=study_seed(seed, "infrared + radar"), ir_paired=ir_paired(rd),
                    ir_means=ir.late_means(ir.rmse_by_rule(sim), sim.t, rd.t_min))


def _shallow(bundle: object) -> dict[str, Any]:
    """A dataclass instance's fields by name, the values shared (:func:`dataclasses.asdict` would copy them)."""
    return {f.name: getattr(bundle, f.name) for f in dataclasses.fields(bundle)}  # type: ignore[arg-type]


#: The further fixed weights :func:`arch_study` runs (``architecture_studies``' default) and the filter banks of its two
#: ``architecture_study`` runs (``architecture._arch_banks``).
_ARCH_FIXED = (0.1, 0.5)
_ARCH_BANKS = _arch_banks(len(_ARCH_FIXED))


def _ledger_budget(runs: int) -> int:
    """Rules 9 and 17 of :func:`ledger_studies` before any study: the sum of what its studies run at ``runs``, each by
    its own budget (``fusion.book._study_budget.studies_first``), refused naming ``runs`` (fuzz 55 C4: each study
    checked only itself, so 5,000 runs were accepted and ran 110 CPU-s): :func:`arch_study`'s two architecture studies
    (``architecture_study``'s memory and units), :func:`paired_study` (``_paired_budget``'s parts),
    :func:`fig6_periods` (a scenario and CI at two weights at each period: ``two_sensor_scenario``'s and
    ``fuse_tracks``' own units) and :func:`ir_reading_study` (``ir_readings``' own checks and the parts it sums). The sum's budget
    is the entry of ``fusion._limits.STUDY_WORK`` that the notebook's call (:data:`LEDGER_RUNS`) serves."""
    from fusion._counts import grid_points
    from fusion._limits import LEDGER_STUDIES, STUDY_WORK
    from fusion.book._study_budget import studies_first
    from fusion.book.chapters.ci.infrared import _ir_budget
    from fusion.book.chapters.ci.infrared_readings import _jackknife_budget, _readings_parts
    steps = two_sensor.trajectory(SOURCE_T).t.size

    def infrared() -> int:
        _ir_budget(IR_T, IR_DURATION, runs)
        _jackknife_budget(runs, "runs")
        return 0

    # the infrared readings by what ir_readings runs (its default scaled axis, x: the audit after fuzz 57a; they had
    # been counted as one study's _ir_units)
    readings = _readings_parts(runs, grid_points(IR_DURATION, IR_T, "runs"), 1, "runs")

    return studies_first([*_arch_parts(steps, runs, runs, len(_ARCH_FIXED), "runs"),
                          *_paired_parts(runs), *_fig6_parts(runs), infrared, *readings],
                         "runs", STUDY_WORK[LEDGER_STUDIES], LEDGER_STUDIES)


def ledger_studies(seed: int = SEED, runs: int = LEDGER_RUNS) -> LedgerStudies:
    """The entries of :func:`ledger_inputs` that the chapter's Monte-Carlo studies give, at a seed and run count.

    Parameters
    ----------
    seed : int
        The chapter's seed.
    runs : int
        Runs of every study (:data:`LEDGER_RUNS` in the notebook).

    Returns
    -------
    LedgerStudies
        ``arch``, ``arch_seeds`` (:func:`arch_study`); :meth:`PairedStudies.claim_inputs` of :func:`paired_study`,
        ``aniso_seed``, ``flat_range`` (tr P(ω) of the identical sensors at :data:`SEARCH_STEP`, 11 points) and
        ``flat_pub_grid`` (CI's tr P there at Fig. 5's two published weights, FOA's and the grid's);
        ``ir_readings``, ``ir_seed``, ``ir_paired`` (:func:`ir_reading_study`). The values are shared, not copied.

    Raises
    ------
    ValueError
        ``runs`` whose studies together hold or run beyond the memory or work budget (their sum, the entry of
        ``fusion._limits.STUDY_WORK`` the notebook's call serves: about 1,400 runs), before any study.
    """
    # its studies' seeds, up to fig6_periods' seed + 51, each a seed: checked before the first study (fuzz 55 D1)
    seed = check_seed(seed, span=max(*SEED_OFFSETS.values(), study_seed(0, "fig6 periods") + len(FIG6_PERIODS) - 1))
    runs = count(runs, "runs")
    _ledger_budget(runs)
    return LedgerStudies(**_shallow(_arch_inputs(seed, runs)), **_shallow(_paired_inputs(seed, runs)),
                         **_shallow(_ir_inputs(seed, runs)))


def _fig6(r: PairedInputs) -> dict[str, Evidence]:
    return cast("dict[str, Evidence]", ev_fig6(r)["ci-fig6-foa-vs-grid"])


def _ir_record(rid: str) -> Callable[[IrInputs], dict[str, Evidence]]:
    """The evidence by reading key of one record of :func:`ev_ir_baselines`."""
    return lambda r: cast("dict[str, Evidence]", ev_ir_baselines(r)[rid])


#: Stochastic record id -> (its evidence by reading key from the typed parts of :func:`ledger_studies` it reads, those parts).
_STOCHASTIC = {"ci-fig4-convex-part": (_vs_ci, (_arch_inputs, _paired_inputs)),
               "ci-fig7-improved-vs-ci": (_vs_ci, (_arch_inputs, _paired_inputs)),
               "ci-fig6-foa-vs-grid": (_fig6, (_paired_inputs,)),
               "ci-fig10-x-below-y": (_x_below_y, (_ir_inputs,)),
               "ci-fig10-convex-errors": (_ir_record("ci-fig10-convex-errors"), (_ir_inputs,)),
               "ci-fig10-fuzzy-errors": (_ir_record("ci-fig10-fuzzy-errors"), (_ir_inputs,))}


def _record_budget(rid: str, runs: int) -> int:
    """Rules 9 and 17 of :func:`record_evidence` before any study: the studies the record ``rid`` reads at ``runs``
    (``_STOCHASTIC``'s parts: :func:`arch_study`, :func:`paired_study` with :func:`fig6_periods`,
    :func:`ir_reading_study`), each by its own summed budget, summed again (``fusion.book._study_budget.studies_first``)
    within the entry of ``fusion._limits.STUDY_WORK`` the reseeding sweep's largest call serves, refused naming
    ``runs`` (the audit after fuzz 57a: the studies were checked one by one, so 4,700 runs of ci-fig4-convex-part ran
    both architecture studies, some 40 CPU-s, before the paired study refused them)."""
    from fusion._limits import RECORD_EVIDENCE, STUDY_WORK
    from fusion.book._study_budget import studies_first
    from fusion.book.chapters.ci.infrared_readings import _jackknife_budget, _readings_budget

    def infrared() -> int:
        _jackknife_budget(runs, "runs")
        return _readings_budget(IR_T, IR_DURATION, runs, 1, "runs")

    parts: dict[object, list[Callable[[], int]]] = {
        _arch_inputs: [lambda: _arch_budget(SOURCE_T, runs, runs, len(_ARCH_FIXED), "runs")],
        _paired_inputs: [lambda: _paired_budget(runs), lambda: studies_first(_fig6_parts(runs), "runs")],
        _ir_inputs: [infrared]}
    return studies_first([p for study in _STOCHASTIC[rid][1] for p in parts[study]], "runs",
                         STUDY_WORK[RECORD_EVIDENCE], RECORD_EVIDENCE)


@process_cache(maxsize=16)
def _record(rid: str, seed: int, runs: int) -> dict[str, Evidence]:
    fn, parts = _STOCHASTIC[rid]
    return fn(*(part(seed, runs) for part in parts))


def record_evidence(rid: str, settings: Mapping[str, object] | None = None, *, seed: int = SEED,
                    runs: int = LEDGER_RUNS) -> Evidence:
    """One reading's evidence of a stochastic record, computed from (seed, runs) through the cached studies.

    Parameters
    ----------
    rid : str
        A record id of ``_STOCHASTIC``.
    settings : mapping, optional
        ``{"reading": key}`` (default the primary).
    seed : int
        The chapter's seed.
    runs : int
        Runs of the studies.

    Returns
    -------
    Evidence
        The comparison, proposition or conjunction of the reading ``settings["reading"]`` (default ``"primary"``) of
        record ``rid``.

    Raises
    ------
    TypeError
        ``settings`` neither a mapping nor None, ``rid`` or ``settings['reading']`` not a string.
    ValueError
        If the record or the reading is unknown (before any study), ``settings`` holds a key other than ``reading``,
        ``runs`` below the 100 runs rule R4 asks of a paired comparison, or ``runs`` whose studies together hold or
        run beyond the memory or work budget (their sum, the entry of ``fusion._limits.STUDY_WORK`` the reseeding
        sweep's call serves), before any study.
    """
    seed = check_seed(seed)
    settings = settings_first(settings, ("reading",))  # the one rule of the chapters' readers (fuzz 52 C7)
    rid = text(rid, "rid")   # a record id is a string (fuzz 26c A6: a list gave "unhashable type")
    if rid not in _STOCHASTIC:
        raise ValueError(f"rid: {shown(rid)} is not a stochastic record of the chapter; they are {sorted(_STOCHASTIC)}")
    _check_reading(settings, rid)
    with runs_named("runs", "the argument runs"):  # rule R4 named by the argument (fuzz 26c A5)
        # every record here is built with paired comparisons of ``runs`` runs without a reason (the IR records'
        # exact readings too: ev_ir_baselines builds them with ci-fig10-x-below-y's), so rule R4's refusal comes
        # before the studies (fuzz 57c: 9-11 CPU-s of studies at 3 runs, then the same refusal)
        runs = runs_first(runs)
        _record_budget(rid, runs)   # the studies it reads, summed before the first (the audit after fuzz 57a)
        ev = _record(rid, seed, runs)
    key = text(settings.get("reading", "primary"), "settings['reading']")
    if key not in ev:
        raise ValueError(f"settings: record {rid} has no reading {shown(key)}; it has {sorted(ev)}")
    return ev[key]


def _check_reading(settings: Mapping[str, Any], rid: str) -> None:
    """An unknown reading of ``rid`` refused before any study, by its claim file's readings (fuzz 51 C6: 9 CPU-s of
    the chapter's studies, then the refusal): the reading keys the record's evidence holds. ``settings`` already
    passed ``settings_first`` (a mapping of the key ``reading`` only: fuzz 52 C7's {'readin': 'aniso'} gave the
    primary)."""
    key = text(settings.get("reading", "primary"), "settings['reading']")
    known = {"primary"} | {r.key for r in claim_file().record(rid).readings}
    if key not in known:
        raise ValueError(f"settings: record {rid} has no reading {shown(key)}; it has {sorted(known)}")


_READER_DOC = """``{rid}``: a reading's evidence (settings ``{{"reading": key}}``){extra}.

Parameters
----------
settings : mapping
seed, runs : int

Returns
-------
Evidence
    The reading's comparison, proposition or conjunction (default reading ``"primary"``), recomputed by
    :func:`record_evidence` from the cached studies of ``seed`` and ``runs``.

Raises
------
TypeError
    ``settings`` neither a mapping nor None, ``settings['reading']`` not a string.
ValueError
    An unknown reading, or a key of ``settings`` other than ``reading``.
"""


def _reader(rid: str, extra: str = "") -> Callable[..., Evidence]:
    """The evidence function of the stochastic record ``rid``: :func:`record_evidence` of ``rid``, named
    ``ev_<id without "ci-", dashes as underscores>`` (the name the record's ``evidence`` field gives)."""
    @reads("reading")  # settings checked first, its keys declared (fuzz 52 C7)
    def fn(settings: Mapping[str, object], *, seed: int = SEED, runs: int = LEDGER_RUNS) -> Evidence:
        with runs_named("runs", "the argument runs"):  # rule R4 named by the argument (fuzz 22b A2)
            return record_evidence(rid, settings, seed=seed, runs=runs)

    fn.__name__ = fn.__qualname__ = "ev_" + rid.removeprefix("ci-").replace("-", "_")
    fn.__doc__ = _READER_DOC.format(rid=rid, extra=extra)
    return fn


ev_fig4_convex_part = _reader("ci-fig4-convex-part", " for :func:`fusion.book.claims.evaluate`")
ev_fig7_improved_vs_ci = _reader("ci-fig7-improved-vs-ci")
ev_fig6_foa_vs_grid = _reader("ci-fig6-foa-vs-grid")
ev_fig10_x_below_y = _reader("ci-fig10-x-below-y")
ev_fig10_convex_errors = _reader("ci-fig10-convex-errors")
ev_fig10_fuzzy_errors = _reader("ci-fig10-fuzzy-errors")
