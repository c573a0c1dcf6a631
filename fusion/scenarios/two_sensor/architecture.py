"""The source's Fig. 2 feedback architecture beside independent local filters, every rule, and the process-noise
scaling control.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping

from dataclasses import dataclass, field
from enum import StrEnum
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from fusion._results import NONNEGATIVE, ResultSpec, array, dict_of, integer, number, same_keys, tuple_of
from fusion._results import real_key, validated_post_init
from fusion._validation import check_magnitude, derived_inputs, distinct_printed, general
from fusion._validation import (FloatArray, allocation, as_array, as_rng, as_semidefinite, count, diagonal_covariance,
                                nonnegative_scalar, one_of, positive_scalar, scalar, std_scalar, work)
from fusion.filtering.kalman import cv_model, filter_runs, gain_sequence, nees
from fusion.scenarios.two_sensor.case import _PARAMS
from fusion.filtering.tracks import _named_track, fuse_tracks
from fusion.scenarios.two_sensor.case import _central_start, _path_and_model_measurements, trajectory
from fusion.scenarios.two_sensor.study import run_rmse
from fusion._shown import shown
from fusion._limits import ARCHITECTURE_STUDY, LOOP_STEP, MAX_WORK, STUDY_WORK

__all__ = ["Architecture", "ArchRule", "ARCH_RULES", "fixed_weight_rule", "ArchitectureStudy", "architecture_study",
           "QScaling", "q_scaling_study"]


class Architecture(StrEnum):
    """Architecture keys of :class:`ArchitectureStudy`; labels in :data:`fusion.book.style.METHOD_LABELS` (legends)
    and :data:`fusion.book.style.METHOD_SHORT_LABELS` (tables).

    Attributes
    ----------
    INDEPENDENT
        Independent local filters, fused without feedback.
    FEEDBACK
        The source's Fig. 2: the rule's own fused split fed back to the local filters.
    FEEDBACK_COMMON
        Fig. 2 with the fused covariance fed back as the common part (split CI and eqs. 11-12 only).
    CENTRALISED
        The centralised Kalman filter on both sensors' measurements.
    """

    INDEPENDENT = "arch_independent"
    FEEDBACK = "arch_feedback"
    FEEDBACK_COMMON = "arch_feedback_common"
    CENTRALISED = "arch_centralised"


class ArchRule(StrEnum):
    """Rule keys of :class:`ArchitectureStudy`; labels in :data:`fusion.book.style.METHOD_LABELS`.

    Eqs. 11-12 at a fixed weight are keyed by :func:`fixed_weight_rule` instead.

    Attributes
    ----------
    CONVEX, CI
        The convex combination (eqs. 3-4) and CI with the closed-form weight.
    SPLIT_SHARED, SPLIT_OWN
        Split CI with the process noise in the shared part or in each sensor's own part.
    PRINTED_SHARED, PRINTED_OWN
        Eqs. 11-12 as printed (one weight for both parts), Q shared or own.
    BSC, LOSSLESS
        Bar-Shalom–Campo, and the lossless information fusion (the fed-back prior removed once).
    FUZZY, CENTRALISED_KF
        Fuzzy clustering (independent filters only) and the centralised Kalman filter.
    """

    CONVEX = "arch_convex"
    CI = "arch_ci"
    SPLIT_SHARED = "arch_split_shared"
    SPLIT_OWN = "arch_split_own"
    PRINTED_SHARED = "arch_printed_shared"
    PRINTED_OWN = "arch_printed_own"
    BSC = "arch_bsc"
    LOSSLESS = "arch_lossless"
    FUZZY = "arch_fuzzy"
    CENTRALISED_KF = "arch_centralised_kf"


#: Configurations of :func:`architecture_study`: (rule key, rule of
#: :func:`fusion.filtering.feedback.fusion_loop`, process-noise reading).
ARCH_RULES = (
    (ArchRule.CONVEX, "convex", "shared"),
    (ArchRule.CI, "ci", "shared"),
    (ArchRule.SPLIT_SHARED, "split", "shared"),
    (ArchRule.SPLIT_OWN, "split", "own"),
    (ArchRule.PRINTED_SHARED, "printed", "shared"),
    (ArchRule.PRINTED_OWN, "printed", "own"),
    (ArchRule.BSC, "bsc", "shared"),
    (ArchRule.LOSSLESS, "lossless", "shared"),
)


def fixed_weight_rule(reading: str, omega: float) -> str:
    """Rule key of eqs. 11-12 as printed at a fixed weight: ``"arch_printed_<reading>_w<omega:g>"``.

    Parameters
    ----------
    reading : {"shared", "own"}
        Where the process noise enters the split.
    omega : float
        The fixed weight, in (0, 1].

    Returns
    -------
    str
        The key, e.g. ``"arch_printed_shared_w0.0018"`` (``ArchRule.PRINTED_SHARED`` with the weight).

    Raises
    ------
    ValueError
        ``reading`` not ``"shared"`` or ``"own"``, ``omega`` outside (0, 1].
    """
    reading = one_of(reading, ("shared", "own"), "reading")  # the plain text (rule 19): an Enum prints its name
    return f"arch_printed_{reading}_w{scalar(omega, 'omega', 0.0, 1.0, lo_open=True):g}"


def _rules_run(values: Mapping[str, Any], cls: str) -> None:
    """The NEES, reported SDs and local gains of an architecture study are of rules whose RMSE it holds."""
    for name in ("nees", "local_gain"):
        extra = [k for k in values[name] if k not in values["run_rmse"]]
        if extra:
            raise ValueError(f"{cls}.{name} has keys without a run in {cls}.run_rmse: {shown(extra, 200)}")


@dataclass(frozen=True)
class ArchitectureStudy:
    r"""Every rule of :data:`ARCH_RULES` with and without feedback, and the centralised filter (:func:`architecture_study`).

    Attributes
    ----------
    run_rmse : mapping of (Architecture, str) to ndarray, shape (runs,)
        Per-run RMSE on x over the steady steps on the chapter's path (m, rounded to mm), keyed by
        (architecture, rule key): an :class:`ArchRule` or, for eqs. 11-12 at a fixed weight,
        :func:`fixed_weight_rule`.
    nees : mapping of (Architecture, str) to float
        Mean NEES over the model-following runs and the steady steps (4 for a consistent rule); every
        key of ``run_rmse`` but fuzzy clustering, which reports no covariance.
    reported : mapping of (Architecture, str) to float
        Time-averaged :math:`\sqrt{P_{xx}}` the rule reports over the steady steps (m); the keys of ``nees``.
    model_rmse : mapping of (Architecture, str) to ndarray, shape (nees_runs,)
        Per-run RMSE on x over the steady steps of the model-following runs (m, rounded to mm).
    runs, nees_runs : int
        Runs on the path and runs with targets that follow the model.
    local_gain : mapping of (Architecture, str) to float
        Time-averaged position gain of sensor 1's local filter over the steady steps,
        :math:`K_{xx} = P^+_{xx}/R_{1,xx}` (1: the filter returns its measurement); every rule run through
        :func:`fusion.filtering.feedback.fusion_loop`.
    """

    run_rmse: Mapping[tuple[Architecture, str], FloatArray]
    nees: Mapping[tuple[Architecture, str], float]
    reported: Mapping[tuple[Architecture, str], float]
    model_rmse: Mapping[tuple[Architecture, str], FloatArray]
    runs: int
    nees_runs: int
    local_gain: Mapping[tuple[Architecture, str], float] = field(default_factory=dict)

    __result_spec__ = ResultSpec(
        {"run_rmse": dict_of(array("runs", bounds=NONNEGATIVE), key=tuple),
         "nees": dict_of(number(), key=tuple), "reported": dict_of(number(), key=tuple),
         "model_rmse": dict_of(array("nees_runs", bounds=NONNEGATIVE), key=tuple),
         "runs": integer(1, dim="runs"), "nees_runs": integer(1, dim="nees_runs"),
         "local_gain": dict_of(number(), key=tuple, nonempty=False)},
        relations=(same_keys("run_rmse", "model_rmse"), same_keys("nees", "reported"), _rules_run))
    __post_init__ = validated_post_init


class _PairedRuns(NamedTuple):
    """The validated inputs and the measurements shared by :func:`architecture_study` and :func:`q_scaling_study`."""

    runs: int
    nees_runs: int
    R1: FloatArray
    R2: FloatArray
    Q: FloatArray
    F: FloatArray
    H: FloatArray
    P0d: FloatArray       # the velocity prior, common to both sensors: diag(0, s², 0, s²)
    steady: np.ndarray    # the steps averaged (t >= t_steady)
    z: FloatArray         # the two sensors' measurements: path runs first, then model-following runs
    truth: FloatArray     # the true states of those runs


#: Units (about 10 ns, ``fusion._limits.MAX_WORK``) of :func:`architecture_study` (fuzz 42b D1, re-measured: the
#: steps' own cost, 6.3-6.6 ms a step whatever the runs, was not counted, so 261 steps of 2 runs ran 1.7 CPU-s and 26,100
#: would run about 170): a step 700 ``LOOP_STEP``; a step of a path run 350 units, of a model-following (NEES) run 850
#: (3.3 and 8.3 us); 3.5 ms a step and 3 us a NEES run's step more with the 8 filter banks of chapter 05's identical pair
#: (10.1 ms and 11.3 us; they were counted as 7 banks of 50), so 44 ``LOOP_STEP`` a bank's step and 44 units a bank's
#: NEES run step. Measured at T = 1 (261 steps), 2 and 402 runs, the least of two calls, ``time.process_time``,
#: ``OPENBLAS_NUM_THREADS=1``, machine shared; chapter 05's identical pair at 2,000 and 2,000 runs ran 10.9 CPU-s, its
#: anisotropic pair 9.0. A filter bank is one ``fusion_loop`` run of a fixed weight: a printed weight runs two (without
#: and with feedback), a placement weight two (Q own; the fused covariance common). Fuzz 65b C1: a bank was counted by
#: its steps only, and a placement weight as one bank, so 9,500 printed weights at T = 130 (3 steps) ran 50.0 CPU-s
#: accepted and 4,000 placement weights at T = 200 ran 16.2 CPU-s counted 4e8 units. Measured (fix73a, 2 path and 2
#: NEES runs, the least of two calls, the machine shared and about 1.4 times slower than above: 9.2 ms a step without a
#: bank), a printed / placement weight (two banks) costs 2.6 / 2.4 ms at 1 step (T = 300), 4.4 / 4.8 at 3 (T = 130),
#: 17.5 / 15.1 at 14 (T = 20), 307 / 278 at 261 (T = 1): 1.1-1.2 ms a step (0.8 at the speed above) and about 1.4 ms
#: whatever the steps (0.7 ms a bank), so a bank's own fixed cost is counted 200 ``LOOP_STEP``, about three times
#: that: its steps are counted 0.88 ms a weight's step against 1.1-1.2 measured here (2,000 placement weights at T = 200
#: ran 10.9 CPU-s, counted 7.5e8 units without it), and its edge must hold on the loaded machine. The call's own fixed
#: cost, 5,000 ``LOOP_STEP`` (60 ms at one step without a bank).
_ARCH_CALL, _BANK_CALL = 5000 * LOOP_STEP, 200 * LOOP_STEP
_ARCH_STEP, _BANK_STEP, _RUN_STEP, _NEES_RUN_STEP, _NEES_BANK = 700 * LOOP_STEP, 44 * LOOP_STEP, 350, 850, 44
#: Units of a bank's step of a path run (fuzz 66b C1: not counted, yet every bank runs every run, so 8,000 path runs
#: and 1 NEES run with 176 banks at T = 1, counted 2.98e9, ran 92.0 CPU-s accepted): measured by fix74a at T = 1, one
#: NEES run, 0 and 20 banks, ``time.process_time``, ``OPENBLAS_NUM_THREADS=1``, the machine shared (load 4-7): a bank
#: 0.16 s at 20 and 1,000 runs, 0.21 at 3,000, 0.23 at 6,000, 0.29-0.38 at 4,000, 0.42 at 8,000 (the report's call),
#: 6-13 units a bank's path-run step; counted 20 (a bank's NEES-run step measured 56 the same way, counted 44).
_PATH_BANK = 20


def _arch_step_units(banks: int) -> tuple[int, int, int]:
    """The units of :func:`architecture_study` with ``banks`` fixed-weight filter banks: a step, a step of a path run,
    a step of a model run (the weights above)."""
    return _ARCH_STEP + banks * _BANK_STEP, _RUN_STEP + banks * _PATH_BANK, _NEES_RUN_STEP + banks * _NEES_BANK


def _arch_units(steps: int, runs: int, nees_runs: int, banks: int) -> int:
    """The units of :func:`architecture_study`: the call's and each bank's fixed cost, plus every step's (above)."""
    step, run, nees = _arch_step_units(banks)
    return _ARCH_CALL + banks * _BANK_CALL + steps * (step + run * runs + nees * nees_runs)


def _architecture_units(steps: int, runs: int, nees_runs: int, banks: int, names: str) -> int:
    """Rule 9 of :func:`architecture_study` (``_HELD`` values a run and step) and its units of work, without the work
    refusal: a chapter study that runs it beside others sums the units (fuzz 55 C4), refused naming ``names``."""
    allocation((runs + nees_runs, steps, _HELD), names)
    return _arch_units(steps, runs, nees_runs, banks)


#: Units of :func:`q_scaling_study`'s loop over scales, twice the measured cost (fuzz 64b C5: a (scale, path step)
#: was counted ``LOOP_STEP`` + 16 a run, about 10 us, where it costs 175-260 us with 2 runs and 0.45 us more a run,
#: so 700 scales at T = 1 ran 33.3 CPU-s accepted and the edge, 3,712, about 175): a (scale, step) 40 ``LOOP_STEP``, a
#: run's step of it 90 units (45, 67 ms a scale at 5 and 20 scales of 2 runs, 76 and 146 at 5 scales of 200 and 800
#: runs; T = 1, 261 steps; ``time.process_time``, ``OPENBLAS_NUM_THREADS=1``, the least of two calls, machine shared),
#: and a scale whatever its steps 400 ``LOOP_STEP`` (fuzz 65b C2: it was not counted, so 24,000 scales at T = 300, one
#: step, counted 0.40 ms each, ran 38.7-48.2 CPU-s accepted; measured by fix73a at 2 path and 2 NEES runs: 2.07, 2.28,
#: 4.67 and 55.6 ms a scale at 1, 3, 14 and 261 steps, about 1.9 ms fixed and 0.21 ms a step).
_SCALE_CALL, _SCALE_STEP, _SCALE_RUN_STEP = 400 * LOOP_STEP, 40 * LOOP_STEP, 90


def _q_scaling_units(scales: int, steps: int, runs: int) -> int:
    """The units of :func:`q_scaling_study`'s ``scales`` filter banks on ``steps`` steps of ``runs`` runs (path and
    NEES runs together): each scale's fixed cost plus each of its steps' (the weights above)."""
    return scales * (_SCALE_CALL + steps * (_SCALE_STEP + _SCALE_RUN_STEP * runs))


#: Float64 values per run and step that the run studies hold at once at their peak (the measurements, truths, both
#: local tracks, the fused track, its errors and the NEES's stacked factors): measured with ``tracemalloc`` at 38 and
#: 53 (:func:`q_scaling_study`, path runs and model runs), 47 and 62 (:func:`architecture_study`), so that
#: :func:`~fusion._validation.allocation` checks the memory the study takes, not one of its arrays.
_HELD = 64


def _paired_runs(rng: np.random.Generator, R1: ArrayLike, R2: ArrayLike, Q: ArrayLike, runs: int, nees_runs: int,
                 T: float, velocity_sigma: float, t_steady: float, scales: int | None = None,
                 banks: int | None = None, names: str = "runs, nees_runs and T",
                 limit: int = MAX_WORK, served: str | None = None,
                 entries: Callable[[], object] | None = None) -> _PairedRuns:
    """Validate the run studies' common arguments and draw their measurements on the path of :func:`trajectory`
    and on targets that follow the model (:func:`_path_and_model_measurements`); ``scales``: the number of filter
    banks :func:`q_scaling_study` runs on them, ``banks``: the fixed-weight filter banks :func:`architecture_study` runs
    beside its rules, checked against the work budget (rule 17, each bank's fixed cost and its steps') before anything
    is drawn; ``entries``: the caller's checks of its sequences' entries, run after the budget (which needs only their
    number) and before
    the draws (length -> budget -> entries, fuzz 64b C4 and C7)."""
    as_rng(rng)
    runs, nees_runs = count(runs, "runs"), count(nees_runs, "nees_runs")
    R1, R2 = diagonal_covariance(R1, 2, "R1"), diagonal_covariance(R2, 2, "R2")
    Q = as_semidefinite(Q, 4, name="Q")
    s2 = std_scalar(velocity_sigma, "velocity_sigma") ** 2
    traj, model = trajectory(T), cv_model(T)
    t, X = traj.t, traj.states
    steady = t >= nonnegative_scalar(t_steady, "t_steady")
    if not steady.any():
        raise ValueError(f"t_steady = {t_steady} leaves no step of the path sampled with T = {T} "
                         f"(its last step is at {float(t[-1]):.6g} s): lower t_steady, or T")
    allocation((runs + nees_runs, t.size, _HELD), "runs, nees_runs and T")  # every array the study holds at once
    if scales is not None:
        # rule 17: one filter bank per scale, its fixed cost and a loop step per sample over every run's 4-state filter
        work((_q_scaling_units(scales, t.size, runs + nees_runs),), "scales, runs, nees_runs and T")
    if banks is not None:
        # rule 17: the study's architectures, rules and ``banks`` fixed-weight filter banks at their measured cost
        # (the call's and each bank's fixed cost, a step, a step of a path run and of a model run), before the draws,
        # naming ``names``, within ``limit``
        work((_arch_units(t.size, runs, nees_runs, banks),), names, limit=limit, served=served)
    if entries is not None:
        entries()
    z, Xm = _path_and_model_measurements(rng, X, model.F, Q, R1, R2, runs, nees_runs)
    truth = np.concatenate([np.broadcast_to(X, (runs, t.size, 4)), Xm])
    return _PairedRuns(runs, nees_runs, R1, R2, Q, model.F, model.H, np.diag([0.0, s2, 0.0, s2]), steady, z, truth)


def _unit_weights(value: ArrayLike, name: str) -> np.ndarray:
    """Weights in (0, 1], checked in one vectorised pass; that no two print the same (the results are keyed by
    ``f"{w:g}"``) is checked by ``distinct_printed`` once the budget, which needs only their number, has passed (fuzz
    64b C7: 10**7 weights were read entry by entry first, refused after 14-16 CPU-s)."""
    w = np.atleast_1d(as_array(value, name, ndim=(0, 1), nonempty=False))
    bad = ~((w > 0) & (w <= 1))
    if bad.any():
        raise ValueError(f"{name} must lie in (0, 1], got {shown(float(w[bad][0]))} at index {int(np.argmax(bad))}")
    return w


@derived_inputs()
@_PARAMS("rng", "R1, R2", "runs, nees_runs", "T", "velocity_sigma", "t_steady")
def architecture_study(rng: np.random.Generator, R1: ArrayLike, R2: ArrayLike, Q: ArrayLike, runs: int = 200,
                       nees_runs: int = 100, T: float = 1.0, velocity_sigma: float = 100.0,
                       t_steady: float = 20.0, printed_omegas: ArrayLike = (),
                       placement_omegas: ArrayLike = ()) -> ArchitectureStudy:
    r"""The source's Fig. 2 feedback architecture beside independent local filters, every rule.

    Two sets of runs share each rule's covariance recursion (:func:`fusion.filtering.feedback.fusion_loop`):
    ``runs`` on the deterministic path of :func:`trajectory` (RMSE) and ``nees_runs`` with targets that
    follow the model, :func:`model_truth` from the path's first state with the process noise common to
    both sensors (NEES). Every filter starts at its sensor's first measurement with zero velocity,
    covariance ``diag(R[0,0], s^2, R[1,1], s^2)``, the velocity part common to both sensors.

    Parameters
    ----------
    Q : array_like, shape (4, 4)
        Process noise of the filters (and of the model targets).
    printed_omegas : array_like of float in (0, 1], optional, no two printing the same (6 significant digits)
        Fixed weights with which eqs. 11-12 as printed are run as well, without and with feedback, Q in the
        shared part (e.g. the source's published FOA optimum 0.0018); keyed ``fixed_weight_rule("shared", w)``.
    placement_omegas : array_like of float in (0, 1], optional, no two printing the same (6 significant digits)
        Fixed weights with which eqs. 11-12 as printed are also fed back with Q in each sensor's own part
        (``fixed_weight_rule("own", w)``) and fed back with the fused covariance as the common part
        (:data:`Architecture.FEEDBACK_COMMON`, Q in the shared part): where Q
        enters the split and what is fed back, for those weights.

    Returns
    -------
    ArchitectureStudy
        Every rule of :data:`ARCH_RULES` (``ArchRule.LOSSLESS`` with feedback only: without it the common prior is
        unknown), the fixed-weight readings, fuzzy clustering with independent filters (it reports no
        covariance to feed back) and the centralised filter.

    Raises
    ------
    ValueError
        Covariances not valid, counts not positive, ``t_steady`` beyond the path, a weight outside (0, 1];
        the steps of ``T``, each run's step and the fixed-weight filter banks beyond the work budget (its entry of
        ``fusion._limits.STUDY_WORK``, 3e9 units: 5e6 a call and 200,000 a bank whatever the steps, 700,000 a step,
        44,000 more a bank; 350 a step of a path run, 850 and 44 a bank a step of a model run, measured; a
        printed or placement weight is two banks), before any draw.
    """
    from fusion.filtering.feedback import fusion_loop

    w_printed, w_placed = (_unit_weights(w, nm) for w, nm in ((printed_omegas, "printed_omegas"),
                                                               (placement_omegas, "placement_omegas")))
    weights: dict[str, list[float]] = {}

    def distinct_weights() -> None:   # after the budget, before the draws (length -> budget -> entries)
        # each weight keys its results by f"{w:g}" (fixed_weight_rule): two that print the same would share a key, the
        # last silently replacing the other (fuzz 66b C2: [0.5, 0.5 + 1e-12] returned one weight's keys)
        for w, nm in ((w_printed, "printed_omegas"), (w_placed, "placement_omegas")):
            weights[nm] = distinct_printed(w.tolist(), nm, general, "keys a rule's results")

    # rule 17 before the draws: the call, every step, every run's step, and two filter banks (fusion_loop runs) per
    # printed and per placement omega, each with its fixed cost, at their measured cost (fuzz 65b C1) (78,000 NEES runs, ~50 CPU-s, were accepted: budget35; the steps: fuzz 42b D1); the
    # budget is its entry of fusion._limits.STUDY_WORK (the reseeding sweep's 10x reading of chapter 05, 1.08e9)
    banks = 2 * (w_printed.size + w_placed.size)
    p = _paired_runs(rng, R1, R2, Q, runs, nees_runs, T, velocity_sigma, t_steady,
                     banks=banks,
                     names="runs, nees_runs and T" if not banks else
                     "printed_omegas, placement_omegas, runs, nees_runs and T",
                     limit=STUDY_WORK[ARCHITECTURE_STUDY], served=ARCHITECTURE_STUDY, entries=distinct_weights)
    omegas, placed = weights["printed_omegas"], weights["placement_omegas"]
    runs, nees_runs, R1, R2, Q, F, H, steady, z, truth = (p.runs, p.nees_runs, p.R1, p.R2, p.Q, p.F, p.H, p.steady,
                                                          p.z, p.truth)
    x0 = [np.column_stack([zj[:, 0, 0], np.zeros(runs + nees_runs), zj[:, 0, 1], np.zeros(runs + nees_runs)])
          for zj in z]
    P0d = p.P0d
    P0i = [np.diag([R[0, 0], 0.0, R[1, 1], 0.0]) for R in (R1, R2)]
    out_rmse: dict[tuple[Architecture, str], FloatArray] = {}
    out_nees: dict[tuple[Architecture, str], float] = {}
    out_rep: dict[tuple[Architecture, str], float] = {}
    out_model: dict[tuple[Architecture, str], FloatArray] = {}
    out_gain: dict[tuple[Architecture, str], float] = {}
    A = Architecture

    def record(key: tuple[Architecture, str], est: FloatArray, P: FloatArray, local_P: FloatArray | None = None) -> None:
        e = est - truth
        out_rmse[key] = run_rmse(e[:runs], 0.0, steady, 0)
        out_nees[key] = round(float(np.mean(nees(e[runs:], P)[:, steady])), 4)
        out_rep[key] = round(float(np.sqrt(P[steady, 0, 0]).mean()), 4)
        out_model[key] = run_rmse(e[runs:], 0.0, steady, 0)
        if local_P is not None:
            out_gain[key] = round(float(np.mean(local_P[steady, 0, 0])) / float(R1[0, 0]), 4)

    fixed = [(fixed_weight_rule("shared", w), "printed", "shared", w) for w in omegas]
    for arch, fb in ((A.INDEPENDENT, "none"), (A.FEEDBACK, "split"), (A.FEEDBACK_COMMON, "common")):
        for name, rule, reading, w in [(*rule_, None) for rule_ in ARCH_RULES] + fixed:
            if fb == "common" and (rule != "split" or w is not None):
                continue   # the other rules do not use the split (eqs. 11-12 drive ω to 1): the same as "feedback"
            if fb == "none" and rule == "lossless":
                continue   # without feedback the common prior is unknown (it is Bar-Shalom–Campo's job)
            r = fusion_loop(z[0], z[1], x0[0], x0[1], F, H, Q, R1, R2, P0d, P0i[0], P0i[1], rule, fb, reading, omega=w)
            record((arch, name), r.est, r.P, r.local_P)
    for w in placed:   # eqs. 11-12 at a fixed weight: Q in the sensors' own parts, and the fused covariance as common
        for arch, fb, reading in ((A.FEEDBACK, "split", "own"), (A.FEEDBACK_COMMON, "common", "shared")):
            r = fusion_loop(z[0], z[1], x0[0], x0[1], F, H, Q, R1, R2, P0d, P0i[0], P0i[1], "printed", fb, reading,
                            omega=w)
            record((arch, fixed_weight_rule(reading, w)), r.est, r.P, r.local_P)
    Hc = np.vstack([H, H])
    Rc = np.zeros((4, 4))
    Rc[:2, :2], Rc[2:, 2:] = R1, R2
    # fuzzy clustering reports no covariance: independent local filters only, and no NEES or reported P
    local = [_named_track("velocity_sigma", z[j], F, H, Q, R, x0[j], P0d, P0i[j]) for j, R in enumerate((R1, R2))]
    e_fz = fuse_tracks(local[0], local[1], "fuzzy").est - truth
    out_rmse[(A.INDEPENDENT, ArchRule.FUZZY)] = run_rmse(e_fz[:runs], 0.0, steady, 0)
    out_model[(A.INDEPENDENT, ArchRule.FUZZY)] = run_rmse(e_fz[runs:], 0.0, steady, 0)
    xc0, Pc0 = _central_start(x0[0], x0[1], P0d + P0i[0], P0d + P0i[1], P0d)   # the velocity prior counted once
    gc = gain_sequence(F, Hc, Q, Rc, Pc0, steady.size)
    record((A.CENTRALISED, ArchRule.CENTRALISED_KF), filter_runs(np.concatenate(z, axis=2), gc, xc0), gc.P)
    return ArchitectureStudy(run_rmse=out_rmse, nees=out_nees, reported=out_rep, model_rmse=out_model, runs=runs,
                             nees_runs=nees_runs, local_gain=out_gain)


#: The key rule of :class:`QScaling`'s dicts: a factor c > 0 of the filters' cQ (decision 32b).
_SCALE = real_key(0.0, lo_open=True)


@dataclass(frozen=True)
class QScaling:
    r"""CI with local filters whose process noise is scaled, no split and no feedback (:func:`q_scaling_study`).

    Attributes
    ----------
    scales : tuple of float
        Factors :math:`c` of the filters' :math:`cQ`.
    run_rmse : mapping of float to ndarray, shape (runs,)
        Per-run RMSE on x over the steady steps on the path (m, rounded to mm), same noise for every scale.
    model_rmse : mapping of float to ndarray, shape (nees_runs,)
        The same for targets that follow the model with the unscaled :math:`Q`.
    nees : mapping of float to float
        Mean NEES of the fused estimate on those targets (4 if consistent).
    runs, nees_runs : int
    """

    scales: tuple[float, ...]
    run_rmse: Mapping[float, FloatArray]
    model_rmse: Mapping[float, FloatArray]
    nees: Mapping[float, float]
    runs: int
    nees_runs: int

    __result_spec__ = ResultSpec(
        {"scales": tuple_of(number(positive=True)),
         "run_rmse": dict_of(array("runs", bounds=NONNEGATIVE), key=float, printed=general,  # rows f"{c:g} Q"
                             check_key=_SCALE),
         "model_rmse": dict_of(array("nees_runs", bounds=NONNEGATIVE), key=float, check_key=_SCALE),
         "nees": dict_of(number(), key=float, check_key=_SCALE), "runs": integer(1, dim="runs"),
         "nees_runs": integer(1, dim="nees_runs")},
        relations=(same_keys("scales", "run_rmse", "model_rmse", "nees"),))
    __post_init__ = validated_post_init


@derived_inputs()
@_PARAMS("rng", "R1, R2", "runs, nees_runs", "T", "velocity_sigma", "t_steady")
def q_scaling_study(rng: np.random.Generator, R1: ArrayLike, R2: ArrayLike, Q: ArrayLike, scales: ArrayLike,
                    runs: int = 200, nees_runs: int = 100, T: float = 1.0, velocity_sigma: float = 100.0,
                    t_steady: float = 20.0) -> QScaling:
    r"""A control for the feedback gains: CI of two independent local filters that run :math:`cQ` instead of :math:`Q`.

    Split CI fed back (Wang & Tang 2024, Fig. 2) reports a covariance smaller than the truth, which gives
    the local filters smaller gains. Whether that alone explains its lower error on a path smoother than
    :math:`Q` allows is checked by giving smaller gains to CI without any split or feedback: the local
    filters run :math:`cQ`, the fusion rule is unchanged (:func:`fusion.filtering.tracks.fuse_tracks`,
    closed-form trace-optimal ω). Every scale sees the same measurement noise (paired runs), on the path of
    :func:`trajectory` and on targets that follow the model with the unscaled :math:`Q`.

    Parameters
    ----------
    Q : array_like, shape (4, 4)
        The model's process noise (of the model targets; the filters run ``c Q``).
    scales : array_like of float, shape (S,)
        Factors :math:`c > 0`, distinct to 6 significant digits.

    Returns
    -------
    QScaling
        Per scale c: each run's fused RMSE on x (m) on the path and on model targets, and the mean steady-state NEES.

    Raises
    ------
    ValueError
        Covariances not valid, counts or scales not positive, ``scales`` repeating an entry to 6 significant digits
        (each keys a result and a table row, printed ``f"{c:g}"``), ``t_steady`` beyond the path; the scales' filter
        banks beyond the work budget (400,000 units a scale whatever the steps, 40,000 a scale and step, 90 more a
        run's step, measured) by their number
        before any entry is printed or any draw.
    """
    sv = np.atleast_1d(as_array(scales, "scales", ndim=(0, 1)))
    if not np.all(sv > 0):  # one vectorised pass (10**6 scales are refused by the work budget at once)
        raise ValueError(f"scales must be positive, got {shown(float(sv[~(sv > 0)][0]))} at index {int(np.argmin(sv > 0))}")
    check_magnitude(sv, "scales")  # rule 2, as positive_scalar entry by entry
    keyed: list[tuple[float, ...]] = []
    # f"{c:g} Q" (fuzz 30b), read after the budget, which needs only their number (fuzz 64b C4: 10**7 scales were
    # printed and hashed first, refused after 21-26 CPU-s)
    p = _paired_runs(rng, R1, R2, Q, runs, nees_runs, T, velocity_sigma, t_steady, scales=sv.size,
                     entries=lambda: keyed.append(tuple(distinct_printed(sv.tolist(), "scales", general,
                                                                         "keys a result and a row"))))
    cs = keyed[0]
    runs, nees_runs, R1, R2, Q, F, H, steady, z, truth = (p.runs, p.nees_runs, p.R1, p.R2, p.Q, p.F, p.H, p.steady,
                                                          p.z, p.truth)
    P0d = p.P0d
    out_path: dict[float, FloatArray] = {}
    out_model: dict[float, FloatArray] = {}
    out_nees: dict[float, float] = {}
    for c in cs:
        tracks = []
        for zj, R in zip(z, (R1, R2)):
            x0 = np.column_stack([zj[:, 0, 0], np.zeros(runs + nees_runs), zj[:, 0, 1], np.zeros(runs + nees_runs)])
            tracks.append(_named_track("velocity_sigma", zj, F, H, c * Q, R, x0, P0d,
                                       np.diag([R[0, 0], 0.0, R[1, 1], 0.0])))
        f = fuse_tracks(tracks[0], tracks[1], "ci")
        e = f.est - truth
        out_path[c] = run_rmse(e[:runs], 0.0, steady, 0)
        out_model[c] = run_rmse(e[runs:], 0.0, steady, 0)
        out_nees[c] = round(float(np.mean(nees(e[runs:], f.P)[:, steady])), 4)
    return QScaling(scales=cs, run_rmse=out_path, model_rmse=out_model, nees=out_nees, runs=runs, nees_runs=nees_runs)
