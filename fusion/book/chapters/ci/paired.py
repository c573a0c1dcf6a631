"""Paired comparisons of the fusion rules on the same runs (identical, unequal and random-weight sensors)."""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from fusion._results import (ResultSpec, array, dict_of, instance, integer, number, shared_post_init, tuple_of,
                             validated_post_init)
from fusion import data
from fusion._docstrings import reads_results
from fusion._validation import as_array, count, general, instance_of, scalar, unit_scalar
from fusion._counts import distinct, seed as check_seed, seeds as check_seeds, sequence
from fusion.book.tables import rounded
from fusion.book.glue import GlueValues
from fusion.estimates.ci import ci_weight
from fusion.filtering.tracks import fuse_tracks
from fusion.scenarios import two_sensor
from fusion.scenarios.two_sensor import ArchitectureStudy, FusionStudy, Scenario, StudyMethod
from fusion.book.chapters.ci.records import PairRuns
from fusion.book.chapters.ci.checks import (LEVEL_KEY, PERIOD_KEY, WEIGHT_KEY, _entries, _identical_study, _period_key,
                                            _sensor_noises)
from fusion.book.chapters.ci.constants import CVX_N, FB, LIT, PRINTED, SPLIT_S, W_GRID, W_PUB
from fusion.book.chapters.ci.text import _glue_doc, paired_text, readable
from fusion.book.chapters.ci.tracking import fuzzy_levels
from fusion.book.chapters.ci.weights import WeightPair, _pair_noises
from fusion._shown import shown

__all__ = ["paired_numbers", "PairedClaimInputs", "PairedStudies", "paired_studies"]

#: Float64 arrays of shape (runs, K, 4) that ``studies.paired_study`` holds at its peak (the three pairs' scenarios, the
#: fused tracks of every rule of the pair being studied, their errors): ``tracemalloc``'s peak measured at 400 and
#: 1,200 runs, 57.5 and 57.2 arrays (183 and 547 MiB), rounded up (fuzz 55 C3: 25,542 runs ended in a raw
#: MemoryError after 34 CPU-s).
_PAIRED_HELD = 58
#: Units a run and step of ``studies.paired_study`` beyond what its inner functions' own budgets count (their per-run
#: RMSEs, ``fusion_study``'s per-step RMSEs and copies): its slope, 935 units a run and step (2.44 ms a run of 261
#: steps: 2.99 and 6.33 CPU-s for ``paired_study``, 0.31 and 0.63 for ``aniso_pair``, at 500 and 2,000 runs, after the
#: cached per-step weights; OPENBLAS_NUM_THREADS=1, the shared machine, minimum of 2), less the inner budgets' 551.
_PAIRED_REST = 384
#: The rules ``fusion_study`` runs on each pair (CI plain, at FOA's and at the grid's weights; split CI, the convex
#: combination, fuzzy clustering); the identical pair runs CI at each of Fig. 6's weights and at random weights too.
_STUDY_RULES = ("ci", "ci", "ci", "split", "convex", "fuzzy")


def _paired_studies_parts(runs: int, steps: int, aniso_runs: int, aniso_steps: int, omegas: int, names: str
                          ) -> list[Callable[[], int | None]]:
    """What :func:`paired_studies` holds and runs, each part by the inner function's own budget
    (``fusion.book._study_budget.studies_first``'s ``parts``), refused naming ``names``: ``_PAIRED_HELD`` arrays of
    ``(runs, steps, 4)`` (the larger pair's runs and steps); the identical and unequal pairs' scenarios
    (``case._scenario_budget``); every ``fuse_tracks`` of the three ``fusion_study`` runs (the anisotropic pair's on
    its own ``aniso_runs`` and ``aniso_steps``), of the ``omegas`` fixed weights and of the random weights (its own
    weights); the unequal and anisotropic pairs' per-step weights (``per_step_weights``' own units); the rest at its
    measured weight (``_PAIRED_REST``). Fuzz 57a C6: these were counted only by the cached ``studies.paired_study``,
    so 1,202 weights at 2,000 runs ran 82.5 CPU-s and 30,000 runs a raw MemoryError after 20.8 CPU-s."""
    from fusion._counts import allocation
    from fusion.filtering.tracks import _fuse_tracks_units
    from fusion.scenarios.two_sensor.case import _scenario_budget
    from fusion.scenarios.two_sensor.weights import _weights_step_units

    # the fixed and random weights' CI fusions in closed form, ``omegas + 1`` times one (fuzz 61a C1: a sum over a
    # tuple of one entry per weight was built for 10**7 weights)
    return [lambda: allocation((max(runs, aniso_runs), max(steps, aniso_steps), 4), names, arrays=_PAIRED_HELD),
            *[lambda: _scenario_budget(runs, steps, names)] * 2,
            lambda: (sum(_fuse_tracks_units(steps, runs, 4, rule) for rule in 2 * _STUDY_RULES)
                     + (omegas + 1) * _fuse_tracks_units(steps, runs, 4, "ci")),
            lambda: sum(_fuse_tracks_units(aniso_steps, aniso_runs, 4, rule) for rule in _STUDY_RULES),
            lambda: (steps + aniso_steps) * _weights_step_units(),
            lambda: runs * steps * _PAIRED_REST]


@_glue_doc("paired differences as text with their 95 % intervals, ratios")
def _per_run(values: object, name: str, runs: int) -> None:
    """Per-run RMSE of a paired study: ``runs`` finite values (``paired_runs``, the run count beside them)."""
    arr = as_array(values, name, ndim=1, nonnegative=True)
    if arr.size != runs:
        raise ValueError(f"{name} holds {arr.size} runs, but paired_runs = {runs}: the arrays and the run count "
                         "must come from the same paired studies")


#: The pair whose runs each argument of :func:`paired_numbers` must hold (``PairRuns.role``).
_ROLES = {"paired": "identical", "paired_u": "unequal", "paired_a": "aniso"}


def _pair_role(runs_by: object, name: str) -> None:
    """A :class:`PairRuns` (a :class:`PairedStudies` field) records its pair: refuse another pair's runs under
    ``name`` (issue 35, swaps). A plain mapping records none and is not checked."""
    role = getattr(runs_by, "role", None) if isinstance(runs_by, PairRuns) else None
    if role is not None and role != _ROLES[name]:
        other = next(k for k, v in _ROLES.items() if v == role)
        raise ValueError(f"{name} must be the runs of the {_ROLES[name]} pair, got those of the {role} pair (the "
                         f"PairedStudies field of {other}: two swapped?)")


@reads_results("ai")
def paired_numbers(paired: Mapping[str, np.ndarray], paired_u: Mapping[str, np.ndarray], paired_random: np.ndarray,
                   ai: ArchitectureStudy, ml_gap: float, rmse_avg: float, paired_runs: int,
                   paired_a: Mapping[str, np.ndarray], omega_u: ArrayLike,
                   paired_fig6: Mapping[float, np.ndarray] | None = None) -> GlueValues:
    """The numbers the prose quotes from the paired studies (glue keys ``ci_u_*``, ``ci_a_*``, ``ci_rnd_*``, ``ci_ratio_*``, ...).

    Parameters
    ----------
    paired, paired_u, paired_a : mapping
        Method -> per-run RMSE (m) on identical sensors, with sensor 2 three times more precise (R₂ = R₁/9) and
        on the anisotropic pair (``ANISO_R``), independent local filters. The fields of a :class:`PairedStudies` (:class:`PairRuns`) record
        their pair, and one pair's runs in another's place are refused; plain mappings record none and are not
        checked.
    paired_random : ndarray
        Per-run RMSE (m) of CI with a weight drawn at random at every step.
    ai : ArchitectureStudy
        The identical-sensor architecture study.
    ml_gap : float
        Largest difference between maximum likelihood and the product of Gaussians.
    rmse_avg : float
        RMSE of CI with the closed-form weight (m): the exact value on the path (infinitely many runs), against
        which the published values' ratios are taken.
    paired_runs : int
        Runs of the paired studies.
    omega_u : array_like
        CI's trace-optimal weight at each steady step of the R₁/9 pair.
    paired_fig6 : mapping of float to ndarray, optional
        Per-run RMSE (m) of CI at the two weights the source publishes (FOA's, the exhaustive search's), on the
        runs of ``paired``.

    Returns
    -------
    dict
        Glue key -> value.

    Raises
    ------
    TypeError
        ``paired``, ``paired_u`` or ``paired_a`` not a mapping; ``paired_runs`` not an integer.
    ValueError
        ``ai`` not the identical-sensor study (it lacks the runs with Q's placement that architecture_studies
        makes on the identical sensors only); a mapping lacks a method (``paired_fig6`` a published weight) read
        here, or an array of per-run RMSE does
        not hold ``paired_runs`` finite values (the run count of another study); ``ml_gap`` negative, ``rmse_avg``
        not positive, ``omega_u`` not weights in [0, 1] (each not finite); ``paired``, ``paired_u`` or ``paired_a``
        a :class:`PairRuns` of another pair.
    """
    for name, runs_by in (("paired", paired), ("paired_u", paired_u), ("paired_a", paired_a)):
        _pair_role(runs_by, name)   # first: one pair's runs in another's place, named before any other check
    instance_of(ai, ArchitectureStudy, "ai")
    _identical_study(ai, "ai")   # by the rules it records (fuzz 26c B2): not the anisotropic pair's study
    M = StudyMethod
    paired_runs = count(paired_runs, "paired_runs")
    for name, runs_by, read in (("paired", paired, (M.CI, M.SPLIT_CI)),
                                ("paired_u", paired_u, (M.CI, M.SPLIT_CI, M.CONVEX, M.CI_GRID, M.CI_FRUIT_FLY,
                                                        M.SENSOR_2)),
                                ("paired_a", paired_a, (M.CI, M.SPLIT_CI, M.CONVEX, M.CI_FRUIT_FLY, M.CI_GRID,
                                                        M.FUZZY))):
        _entries(runs_by, name, read, "paired_studies", numbers=False)
        for k in read:
            _per_run(runs_by[k], f"{name}[{shown(k)}]", paired_runs)
    _per_run(paired_random, "paired_random", paired_runs)
    ml_gap = scalar(ml_gap, "ml_gap", 0.0, tiny=True)
    rmse_avg = scalar(rmse_avg, "rmse_avg", 0.0, lo_open=True)
    w = as_array(omega_u, "omega_u", ndim=1, nonnegative=True)
    if (w > 1.0).any():
        raise ValueError(f"omega_u must hold CI weights in [0, 1], got {shown(float(w.max()))}")
    if paired_fig6 is not None:
        p6 = _entries(paired_fig6, "paired_fig6", _FIG6_WEIGHTS, "paired_studies", numbers=False)
        for k in _FIG6_WEIGHTS:
            _per_run(p6[k], f"paired_fig6[{shown(k)}]", paired_runs)
    cvx_fb = float(np.mean(ai.run_rmse[(FB, CVX_N)]))   # one architecture (R6)
    return {"ci_paired_runs": paired_runs, "ci_ml_gap": readable(ml_gap),
            "ci_u_imp_ci": paired_text(paired_u[M.CI], paired_u[M.SPLIT_CI], 3),
            "ci_u_imp_cvx": paired_text(paired_u[M.SPLIT_CI], paired_u[M.CONVEX], 3),
            "ci_u_foa_grid": paired_text(paired_u[M.CI_GRID], paired_u[M.CI_FRUIT_FLY], 2),
            "ci_u_ci_is_s2": ("identical to the last digit" if np.array_equal(paired_u[M.CI], paired_u[M.SENSOR_2])
                              else f"within {readable(float(np.max(np.abs(paired_u[M.CI] - paired_u[M.SENSOR_2]))))} m"),
            "ci_u_omega_max": readable(float(np.max(w))),
            "ci_a_imp_ci": paired_text(paired_a[M.CI], paired_a[M.SPLIT_CI], 3),
            "ci_a_imp_cvx": paired_text(paired_a[M.SPLIT_CI], paired_a[M.CONVEX], 3),
            "ci_a_foa_grid": paired_text(paired_a[M.CI_FRUIT_FLY], paired_a[M.CI_GRID], 2),
            "ci_a_fuzzy_d": paired_text(paired_a[M.FUZZY], paired_a[M.CI], 3),
            "ci_rnd_ci": rounded(float(np.mean(paired_random)), 1),
            "ci_rnd_imp": rounded(float(np.mean(paired[M.SPLIT_CI])), 1),
            "ci_rnd_d": paired_text(paired_random, paired[M.SPLIT_CI], 3),
            "ci_half_ratio": rounded(float(np.mean(ai.run_rmse[(FB, PRINTED)]))
                                     / cvx_fb, 2),
            "ci_half_ratio_lit": rounded(float(np.mean(ai.run_rmse[(FB, LIT)])) / cvx_fb, 2),
            "ci_half_ratio_rep": rounded(float(np.mean(ai.run_rmse[(FB, SPLIT_S)])) / cvx_fb, 2),
            "ci_ratio_lo": rounded(rmse_avg / float(data.WANG2024_RMSE.values.max()), 1),
            "ci_ratio_hi": rounded(rmse_avg / float(data.WANG2024_RMSE.values.min()), 1),
            **(_fig6_numbers(paired_fig6, paired[M.CI]) if paired_fig6 is not None else {})}


#: The two published weights of source Fig. 5 (FOA's, the grid's): the keys of ``paired_fig6``.
_FIG6_WEIGHTS = tuple(float(data.WANG2024_FOA.columns[k][0]) for k in ("foa_optimum", "grid_optimum"))


def _fig6_numbers(p6: Mapping[float, np.ndarray], half: np.ndarray) -> GlueValues:
    """Glue values of source Fig. 6 read as the two published weights put into CI (``ci_fig6_*``)."""
    w_fruit_fly, w_grid = _FIG6_WEIGHTS
    d = np.asarray(p6[w_fruit_fly]) - np.asarray(p6[w_grid])
    return {"ci_fig6_foa": rounded(float(np.mean(p6[w_fruit_fly])), 2), "ci_fig6_grid": rounded(float(np.mean(p6[w_grid])), 2),
            "ci_fig6_d": paired_text(p6[w_fruit_fly], p6[w_grid], 3), "ci_fig6_foa_lower": int(np.sum(d < 0)),
            "ci_fig6_runs": int(d.size), "ci_fig6_half": rounded(float(np.mean(half)), 2),
            "ci_fig6_vs_half": rounded(float(np.mean(p6[w_grid]) - np.mean(half)), 1)}


#: Key types of a dict keyed by a real number (a period, a weight, a significance level).
_REAL = (float, int, np.number)


def _real_keyed(value: Any, printed: Any = general, *, meaning: Any, **kw: Any) -> Any:
    """Spec of a dict keyed by real numbers (periods, weights, levels: ``meaning``, ``PERIOD_KEY``, ...,
    whose bounds each key must keep), each key read by the chapter's one rule
    (``_period_key``: a float32 key is the number it prints as, so that its readers find it; fuzz 26c q2), no two
    keys alike to 6 significant digits (the evidence keys its readings by ``f"{key:g}"``: two such keys would share
    one reading, the last silently replacing the other; fuzz 30b B3); ``printed`` ``glue_part`` for a dict whose
    keys also key glue values (no two alike in their digits: 1.5 and 15 share a glue key; fuzz 31b C1)."""
    return dict_of(value, key=_REAL, read_key=_period_key, printed=printed, check_key=meaning, **kw)

#: A per-run RMSE (m, or mrad): one non-negative value per run.
_RUNS = array("runs", bounds=(0.0, np.inf))
#: Field specs of :class:`PairedClaimInputs` (``fusion._results``), shared with the ledger's bundles of
#: ``fusion.book.chapters.ci.claim_evidence`` that hold them.
_PAIRED_CLAIM_FIELDS = {
    "paired": dict_of(_RUNS), "paired_runs": integer(1), "paired_seed": integer(0), "paired_unequal": dict_of(_RUNS),
    "unequal_seed": integer(0), "paired_random": _RUNS, "random_seed": integer(0), "paired_aniso": dict_of(_RUNS),
    "paired_fig6": _real_keyed(_RUNS, meaning=WEIGHT_KEY, required=(W_PUB, W_GRID)),
    "fuzzy_levels": _real_keyed(_RUNS, meaning=LEVEL_KEY)}


def _runs_relation(values: Mapping[str, Any], cls: str) -> None:
    """Every paired study's per-run RMSE holds ``paired_runs`` values (one per run)."""
    if "paired_random" in values and values["paired_random"].shape[0] != values["paired_runs"]:
        raise ValueError(f"{cls}.paired_runs must be the number of runs of the paired studies "
                         f"({values['paired_random'].shape[0]}), got {shown(values['paired_runs'])}")


@dataclass(frozen=True)
class PairedClaimInputs:
    """The ledger's entries of :class:`PairedStudies` (:meth:`PairedStudies.claim_inputs`).

    Attributes
    ----------
    paired : dict of str to ndarray
        Method -> per-run RMSE on x (m) on the printed identical sensors' runs.
    paired_runs : int
        Runs of every paired study.
    paired_seed : int
        Seed of the identical sensors' runs.
    paired_unequal : dict of str to ndarray
        Method -> per-run RMSE on x (m), sensor 2 three times more precise.
    unequal_seed : int
        Seed of those runs.
    paired_random : ndarray
        Per-run RMSE on x (m) of CI at a random weight (identical sensors).
    random_seed : int
        Seed of the random weights.
    paired_aniso : dict of str to ndarray
        Method -> per-run RMSE on x (m) on the anisotropic pair's runs.
    paired_fig6 : dict of float to ndarray
        Weight -> per-run RMSE on x (m) of CI at that fixed weight (identical sensors).
    fuzzy_levels : dict of float to ndarray
        Significance level λ -> per-run RMSE on x (m) of fuzzy clustering (identical sensors).
    """

    paired: Mapping[str, np.ndarray]
    paired_runs: int
    paired_seed: int
    paired_unequal: Mapping[str, np.ndarray]
    unequal_seed: int
    paired_random: np.ndarray
    random_seed: int
    paired_aniso: Mapping[str, np.ndarray]
    paired_fig6: Mapping[float, np.ndarray]
    fuzzy_levels: Mapping[float, np.ndarray]

    __result_spec__ = ResultSpec(_PAIRED_CLAIM_FIELDS, relations=(lambda v, cls: _runs_relation(v, cls),))
    __post_init__ = shared_post_init  # the study's values shared, not copied



def _studies_relation(values: Mapping[str, Any], cls: str) -> None:
    """``runs`` is the number of runs of the identical and the unequal sensors' per-run RMSEs."""
    if values["paired_random"].shape[0] != values["runs"]:
        raise ValueError(f"{cls}.runs must be the number of runs of the paired studies "
                         f"({values['paired_random'].shape[0]}), got {shown(values['runs'])}")


@dataclass(frozen=True)
class PairedStudies:
    """The ledger's paired Monte-Carlo studies (:func:`paired_studies`): per-run RMSE on x (m) of every rule.

    Attributes
    ----------
    runs : int
        Runs of the identical sensors and of sensor 2 three times more precise.
    seeds : (int, int, int)
        Seeds of those two sets of runs and of the random weights.
    sc : Scenario
        The identical sensors' runs.
    paired : PairRuns of str to ndarray, shape (runs,)
        Every rule of :func:`fusion.scenarios.two_sensor.fusion_study` on ``sc`` (a mapping recording its pair,
        ``"identical"``, and seed; so are ``paired_u``, ``"unequal"``, and ``paired_an``, ``"aniso"``).
    paired_fig6 : dict of float to ndarray
        CI at each of the source's two published weights (Fig. 6), on ``sc``.
    paired_random : ndarray, shape (runs,)
        CI with the weight drawn from U(0, 1) once per step (the source's traditional CI), on ``sc``.
    paired_u : dict of str to ndarray
        Every rule with sensor 2 three times more precise, on fresh runs.
    omega_u : list of float
        The closed-form weight of those runs at each steady step.
    paired_an : dict of str to ndarray
        Every rule on the anisotropic pair's runs.
    """

    runs: int
    seeds: tuple[int, int, int]
    sc: Scenario
    paired: Mapping[str, np.ndarray]
    paired_fig6: Mapping[float, np.ndarray]
    paired_random: np.ndarray
    paired_u: Mapping[str, np.ndarray]
    omega_u: tuple[float, ...]
    paired_an: Mapping[str, np.ndarray]

    __result_spec__ = ResultSpec(
        {"runs": integer(1), "seeds": tuple_of(integer(0), count=3), "sc": instance(Scenario), "paired": dict_of(_RUNS),
         "paired_fig6": _real_keyed(_RUNS, meaning=WEIGHT_KEY, required=(W_PUB, W_GRID)), "paired_random": _RUNS,
         "paired_u": dict_of(_RUNS), "omega_u": tuple_of(number(bounds=(0.0, 1.0))),
         "paired_an": dict_of(array("aniso_runs", bounds=(0.0, np.inf)))},
        relations=(lambda v, cls: _studies_relation(v, cls),))

    def __post_init__(self) -> None:
        validated_post_init(self)
        for name, role, seed in (("paired", "identical", self.seeds[0]), ("paired_u", "unequal", self.seeds[1]),
                                 ("paired_an", "aniso", None)):   # each pair's runs record the pair (issue 35, swaps)
            object.__setattr__(self, name, PairRuns(getattr(self, name), role, seed))

    __post_init__.__wrapped__ = validated_post_init  # type: ignore[attr-defined]  # the spec's checks, then the records


    def claim_inputs(self, levels: ArrayLike = (0.001, 0.05, 0.1)) -> PairedClaimInputs:
        """The ledger's entries of the paired studies (for ``claims``).

        Parameters
        ----------
        levels : array_like
            Significance levels of fuzzy clustering run on the identical sensors' runs (``fuzzy_levels`` of this module).

        Returns
        -------
        PairedClaimInputs
            The per-run RMSEs of the three pairs, of the Fig. 6 weights and of random weights, their seeds and runs,
            and the fuzzy rule's levels.
        """
        seed, unequal_seed, random_seed = self.seeds
        return PairedClaimInputs(paired=self.paired, paired_runs=self.runs, paired_seed=seed, paired_unequal=self.paired_u,
                                 unequal_seed=unequal_seed, paired_random=self.paired_random, random_seed=random_seed,
                                 paired_aniso=self.paired_an, paired_fig6=self.paired_fig6,
                                 fuzzy_levels=fuzzy_levels(self.sc, levels))

    def numbers(self, ai: ArchitectureStudy, ml_gap: float, rmse_avg: float) -> GlueValues:
        """:func:`paired_numbers` of these studies.

        Parameters
        ----------
        ai : ArchitectureStudy
            The identical-sensor architecture study.
        ml_gap : float
            :func:`ml_vs_product` (m).
        rmse_avg : float
            Exact RMSE of CI = the average on the path (m).

        Returns
        -------
        dict
            Glue key -> value.
        """
        return paired_numbers(self.paired, self.paired_u, self.paired_random, ai, ml_gap, rmse_avg, self.runs,
                              self.paired_an, self.omega_u, self.paired_fig6)


@reads_results("unequal", "aniso")
def paired_studies(R1: ArrayLike, R2: ArrayLike, Q: ArrayLike, weights: tuple[ArrayLike, ArrayLike], unequal: WeightPair,
                   aniso: WeightPair, runs: int, seeds: Sequence[int], weight_seed: int,
                   fig6_omegas: Sequence[float], T: float = 1.0) -> PairedStudies:
    """The ledger's paired studies: every rule on fresh runs of three sensor pairs, per-run RMSE on x after 20 s.

    Parameters
    ----------
    R1, R2 : array_like, shape (2, 2)
        Measurement covariances of the identical sensors (m²).
    Q : array_like, shape (4, 4)
        Process-noise covariance (m², m²/s²).
    weights : (array_like, array_like)
        FOA's and the grid's per-step weights on those sensors (:func:`fusion.scenarios.two_sensor.per_step_weights`;
        they depend on the gains only, so any runs of the pair share them).
    unequal : WeightPair
        Sensor 2 three times more precise: its covariances are run again on ``runs`` fresh runs, its tracks give
        the per-step weights.
    aniso : WeightPair
        The anisotropic pair: the rules run on its own runs, with its per-step weights.
    runs : int
        Runs of the identical and the unequal sensors (≥ 100 for the ledger's comparisons).
    seeds : (int, int, int)
        Seeds of the identical sensors' runs, of the unequal sensors' runs and of the random weights.
    weight_seed : int
        Seed of :func:`fusion.scenarios.two_sensor.per_step_weights` on ``unequal`` and ``aniso``.
    fig6_omegas : sequence of float
        Fixed CI weights run on the identical sensors: the source's two published optima of Fig. 6 (``W_PUB`` and
        ``W_GRID``, which :meth:`PairedStudies.numbers` and the ledger read), and any others.
    T : float
        Sampling period (s).

    Returns
    -------
    PairedStudies
        Per rule the per-run RMSE on x after 20 s (m) for the identical, unequal and anisotropic pairs, at the Fig. 6
        and random weights.

    Raises
    ------
    ValueError
        If ``seeds`` does not hold three seeds, ``runs`` is not a positive count, an entry of ``fig6_omegas`` is not a
        weight in [0, 1] (named ``fig6_omegas[i]``), two entries are equal, or it misses one of the two published
        weights; ``runs``, ``fig6_omegas``, ``T`` and ``aniso``'s runs whose scenarios, fusions and
        per-run errors together hold or run beyond the memory or work budget (about 2,500 runs at the book's two
        weights), before any scenario; ``aniso`` not a pair at ``ANISO_R`` or ``unequal`` not one with ``R2 = R1 / 9`` (the
        pairs swapped, or one pair twice: each pair's rules would run on the other's noises).
    """
    instance_of(unequal, WeightPair, "unequal")
    instance_of(aniso, WeightPair, "aniso")
    _pair_noises(unequal, aniso, ("unequal", "aniso"))   # by the noises they record, as weight_claim_inputs (fuzz 26c B1)
    _sensor_noises(R1, R2)
    seeds = tuple(check_seeds(seeds, "seeds"))
    weight_seed = check_seed(weight_seed, "weight_seed")
    weights = sequence(weights, "weights", 2)
    if len(seeds) != 3:
        raise ValueError(f"seeds must hold three seeds (identical, unequal, random weights), got {shown(seeds)}")
    runs = count(runs, "runs")
    omega_items = sequence(fig6_omegas, "fig6_omegas")
    # rules 9 and 17 before any scenario: every part summed, named by the arguments that set them (fuzz 57a C6), by
    # len(fig6_omegas) before any entry is read (fuzz 61a C1: 10**7 weights were converted and hashed first, refused
    # after 47.5 CPU-s; a repeat, which the reading below refuses, is counted here as its own weight)
    from fusion.book._study_budget import studies_first
    a_runs, a_steps = aniso.sc.tracks[0].est.shape[:2]
    studies_first(_paired_studies_parts(runs, two_sensor.trajectory(T).t.size, a_runs, a_steps, len(omega_items),
                                        "runs, fig6_omegas, T and aniso (its runs)"),
                  "runs, fig6_omegas, T and aniso (its runs)")
    # each entry read as a CI weight (fuse_tracks' omega, [0, 1]) and distinct at entry (fuzz 60a C2, D1: an array
    # entry reached numpy's raw truth-value error, 1.5 was refused naming omega after 1.7 CPU-s of scenarios, a
    # repeat was counted twice by the budget and kept once in paired_fig6)
    fig6_omegas = tuple(distinct([unit_scalar(w, f"fig6_omegas[{i}]") for i, w in enumerate(omega_items)],
                                 "fig6_omegas"))
    if W_PUB not in fig6_omegas or W_GRID not in fig6_omegas:
        raise ValueError(f"fig6_omegas must hold the source's two published weights {W_PUB} and {W_GRID} (Fig. 6), "
                         f"got {shown(fig6_omegas)}")
    seed, unequal_seed, random_seed = seeds
    w_fruit_fly, w_grid = weights
    sc_p = two_sensor.two_sensor_scenario(R1, R2, Q, np.random.default_rng(seed), runs=runs, T=T)
    for i, w in enumerate(weights):   # a weight for every step, or one (fusion_study's rule), named here
        w = as_array(w, f"weights[{i}]", ndim=(0, 1))
        if w.ndim == 1 and w.size != sc_p.t.size:
            raise ValueError(f"weights[{i}] must be a weight or one per step ({sc_p.t.size}), got {w.size}")
    study_p = two_sensor.fusion_study(sc_p, w_fruit_fly, w_grid)

    def per_run(est: np.ndarray, sc: Scenario, study: FusionStudy) -> np.ndarray:
        return two_sensor.run_rmse(est, sc.truth, study.steady, 0)

    paired = {name: per_run(est, sc_p, study_p) for name, est in study_p.est.items()}
    paired_fig6 = {w: per_run(fuse_tracks(*sc_p.tracks, "ci", omega=w).est, sc_p, study_p) for w in fig6_omegas}
    w_random = np.random.default_rng(random_seed).uniform(size=sc_p.t.size)
    paired_random = per_run(fuse_tracks(*sc_p.tracks, "ci", omega=w_random).est, sc_p, study_p)
    w_fruit_fly_u, w_grid_u = two_sensor.per_step_weights(*unequal.sc.tracks, weight_seed)
    sc_u = two_sensor.two_sensor_scenario(unequal.R1, unequal.R2, Q, np.random.default_rng(unequal_seed), runs=runs, T=T)
    study_u = two_sensor.fusion_study(sc_u, w_fruit_fly_u, w_grid_u)
    paired_u = {name: per_run(est, sc_u, study_u) for name, est in study_u.est.items()}
    omega_u = [ci_weight(sc_u.tracks[0].gains.P[j], sc_u.tracks[1].gains.P[j]) for j in np.flatnonzero(study_u.steady)]
    w_fruit_fly_an, w_grid_an = two_sensor.per_step_weights(*aniso.sc.tracks, weight_seed)
    study_an = two_sensor.fusion_study(aniso.sc, w_fruit_fly_an, w_grid_an)
    paired_an = {name: per_run(est, aniso.sc, study_an) for name, est in study_an.est.items()}
    return PairedStudies(runs=runs, seeds=seeds, sc=sc_p, paired=paired, paired_fig6=paired_fig6,
                         paired_random=paired_random, paired_u=paired_u, omega_u=omega_u, paired_an=paired_an)
