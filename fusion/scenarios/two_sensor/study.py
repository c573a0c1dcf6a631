"""Every fusion rule of chapter 05 on one case, and the per-run, per-step and slip metrics of its errors."""

from __future__ import annotations

from collections.abc import Mapping
from fractions import Fraction
import math

from dataclasses import dataclass
from typing import Any
from enum import StrEnum

import numpy as np
from numpy.typing import ArrayLike

from fusion._results import NONNEGATIVE, ResultSpec, array, dict_of, mask, number, same_keys, validated_post_init
from fusion._shown import shown
from fusion._counts import broadcast
from fusion._validation import read_once
from fusion._validation import derived_inputs
from fusion._validation import (FloatArray, allocation, as_array, count, diagonal_covariance, index, instance_of,
                                nonnegative_scalar, positive_scalar, scalar, std_scalar)
from fusion.filtering.kalman import cv_model, nees, rmse_per_step
from fusion.filtering.tracks import _named_track, fuse_tracks
from fusion.scenarios.two_sensor.case import Scenario, model_truth

__all__ = ["FusionStudy", "fusion_study", "run_rmse", "NeesStudy", "nees_study", "slip_steps_band", "rmse_variants", "SLIP_STEPS",
           "SLIP_RUNS", "StudyMethod", "STUDY_METHODS", "NeesRule",
           "NEES_RULES"]


class StudyMethod(StrEnum):
    """Method keys of :func:`fusion_study` (chapter 05); display labels in :data:`fusion.book.style.METHOD_LABELS`.

    Attributes
    ----------
    SENSOR_1, SENSOR_2
        Each sensor's local Kalman filter.
    CI, CI_FRUIT_FLY, CI_GRID, CI_PUBLISHED
        Covariance intersection with the closed-form weight, the FOA's and the exhaustive search's per-step
        weights, and the source's published FOA optimum fixed.
    SPLIT_CI
        Split CI (the source's improved CI, eqs. 5-12 read as split CI).
    CONVEX
        The convex combination (eqs. 3-4; multi-Bayesian and maximum likelihood).
    FUZZY
        Fuzzy clustering.
    CENTRAL
        The centralised Kalman filter on both sensors' measurements.
    RAW_1, RAW_2
        Each sensor's raw measurements (no filter), keys of :attr:`FusionStudy.measurements`.
    """

    SENSOR_1 = "ci_sensor_1"
    SENSOR_2 = "ci_sensor_2"
    CI = "ci_closed_form"
    CI_FRUIT_FLY = "ci_fruit_fly"
    CI_GRID = "ci_grid"
    CI_PUBLISHED = "ci_published_omega"
    SPLIT_CI = "split_ci"
    CONVEX = "convex_ml"
    FUZZY = "fuzzy_clustering"
    CENTRAL = "centralised_kf"
    RAW_1 = "ci_sensor_1_raw"
    RAW_2 = "ci_sensor_2_raw"


#: The rules of :func:`fusion_study`, in table order.
STUDY_METHODS = (StudyMethod.SENSOR_1, StudyMethod.SENSOR_2, StudyMethod.CI, StudyMethod.CI_FRUIT_FLY, StudyMethod.CI_GRID,
                 StudyMethod.CI_PUBLISHED, StudyMethod.SPLIT_CI, StudyMethod.CONVEX, StudyMethod.FUZZY,
                 StudyMethod.CENTRAL)


def _study_methods(values: Mapping[str, Any], cls: str) -> None:
    """A fusion study's estimates are keyed by methods of ``STUDY_METHODS`` (the curves its consumers read)."""
    extra = [k for k in values["est"] if k not in STUDY_METHODS]
    if extra:
        raise ValueError(f"{cls}.est has keys that are not methods of STUDY_METHODS: {shown(extra, 200)}")


@dataclass(frozen=True)
class FusionStudy:
    r"""Every fusion rule of chapter 05 on one :class:`Scenario`.

    Attributes
    ----------
    t : ndarray, shape (K,)
        Times (s).
    truth : ndarray, shape (K, 4)
    est : mapping of StudyMethod to ndarray, shape (runs, K, 4)
        Estimates of each method of ``STUDY_METHODS`` that was run, keyed by method key.
    rmse : mapping of str to ndarray, shape (K, 4)
        RMSE over the runs per step and state component (m, m/s), for every method of ``est``.
    floor : ndarray, shape (K, 2)
        :math:`\sqrt{P}` of the centralised filter on x and y (m): the posterior Cramér-Rao bound
        *for targets that follow the model*; not a floor for the deterministic path simulated.
    steady : ndarray of bool, shape (K,)
        Steps after the start-up transient.
    measurements : mapping of StudyMethod to ndarray, shape (K, 2)
        RMSE over the runs per step of each sensor's raw position measurements on (x, y) (m), keyed
        ``StudyMethod.RAW_1`` and ``StudyMethod.RAW_2`` (what the source's Fig. 7 draws).
    """

    t: FloatArray
    truth: FloatArray
    est: Mapping[StudyMethod, FloatArray]
    rmse: Mapping[StudyMethod, FloatArray]
    floor: FloatArray
    steady: FloatArray
    measurements: Mapping[StudyMethod, FloatArray]

    __result_spec__ = ResultSpec(
        {"t": array("K", increasing=True), "truth": array("K", 4),
         "est": dict_of(array("runs", "K", 4), required=(StudyMethod.SENSOR_1, StudyMethod.SENSOR_2, StudyMethod.CI,
                                                         StudyMethod.SPLIT_CI, StudyMethod.CONVEX, StudyMethod.FUZZY,
                                                         StudyMethod.CENTRAL)),
         "rmse": dict_of(array("K", 4, bounds=NONNEGATIVE)), "floor": array("K", 2, bounds=NONNEGATIVE),
         "steady": mask("K"),
         "measurements": dict_of(array("K", 2, bounds=NONNEGATIVE), keys=(StudyMethod.RAW_1, StudyMethod.RAW_2))},
        relations=(same_keys("est", "rmse"), _study_methods))
    __post_init__ = validated_post_init

    def steady_rmse(self, method: str, component: int) -> float:
        """Mean over the steady steps of the per-step RMSE of ``method`` on state ``component`` (0 = x, 2 = y)."""
        return float(self.curve(method, component)[self.steady].mean())

    def curve(self, method: str, component: int) -> FloatArray:
        """Per-step RMSE of a method of ``est`` or of a sensor's raw measurements (``component`` 0 = x, 2 = y), shape (K,)."""
        if method in self.measurements:
            if component not in (0, 2):
                raise ValueError(f"measurements have positions only (component 0 or 2), got {component}")
            return self.measurements[method][:, component // 2]
        return self.rmse[method][:, component]


def fusion_study(sc: Scenario, w_fruit_fly: ArrayLike | None = None, w_grid: ArrayLike | None = None,
                 published_omega: float | None = None, t_steady: float = 20.0) -> FusionStudy:
    """Run every fusion rule of chapter 05 on the two local tracks of ``sc``.

    Parameters
    ----------
    sc : Scenario
    w_fruit_fly, w_grid : array_like, shape (K,), optional
        Per-step CI weights (:func:`per_step_weights`); the rules that use them are skipped if ``None``.
    published_omega : float, optional
        A fixed CI weight in [0, 1] (the source's published FOA optimum); skipped if ``None``. A non-zero weight
        below 1e-150 is refused, as :func:`fusion.filtering.tracks.fuse_tracks` refuses it as ``omega``.
    t_steady : float
        Start of the steady-state window (s).

    Returns
    -------
    FusionStudy
        Methods keyed as in ``STUDY_METHODS``: the sensors, CI (eqs. 1-2 corrected), split CI
        (eqs. 5-12 read as split CI), the convex combination (eqs. 3-4), fuzzy clustering and the
        centralised Kalman filter.
    """
    w_fruit_fly, w_grid = (read_once(w_fruit_fly, "w_fruit_fly"), read_once(w_grid, "w_grid"))
    instance_of(sc, Scenario, "sc")
    for w, w_name in ((w_fruit_fly, "w_fruit_fly"), (w_grid, "w_grid")):
        if w is not None:
            w_arr = as_array(w, w_name, ndim=(0, 1))
            if w_arr.ndim == 1 and w_arr.size != sc.t.size:
                raise ValueError(f"{w_name} must be a scalar or have one weight per step ({sc.t.size}), got {w_arr.size}")
            if np.any(w_arr < 0) or np.any(w_arr > 1):
                raise ValueError(f"{w_name} must lie in [0, 1]")
    if published_omega is not None:
        # the floats read (fuzz 22b, FR); rule 2 of the omega it becomes (fuse_tracks: an array entry, a tiny
        # non-zero weight refused), checked here so that the message names published_omega (fuzz 29a C4)
        published_omega = scalar(published_omega, "published_omega", 0.0, 1.0, tiny=False)
    t_steady = nonnegative_scalar(t_steady, "t_steady")
    a, b = sc.tracks
    M = StudyMethod
    est: dict[StudyMethod, FloatArray] = {M.SENSOR_1: a.est, M.SENSOR_2: b.est, M.CI: fuse_tracks(a, b, "ci").est}
    if w_fruit_fly is not None:
        est[M.CI_FRUIT_FLY] = fuse_tracks(a, b, "ci", omega=w_fruit_fly).est
    if w_grid is not None:
        est[M.CI_GRID] = fuse_tracks(a, b, "ci", omega=w_grid).est
    if published_omega is not None:
        est[M.CI_PUBLISHED] = fuse_tracks(a, b, "ci", omega=published_omega).est
    est[M.SPLIT_CI] = fuse_tracks(a, b, "split").est
    est[M.CONVEX] = fuse_tracks(a, b, "convex").est
    est[M.FUZZY] = fuse_tracks(a, b, "fuzzy").est
    est[M.CENTRAL] = sc.central.est
    rmse = {name: rmse_per_step(e, sc.truth) for name, e in est.items()}
    raw = {key: rmse_per_step(tr_j.z, sc.truth[:, [0, 2]]) for key, tr_j in ((M.RAW_1, a), (M.RAW_2, b))}
    floor = np.sqrt(sc.central.gains.P[:, [0, 2], [0, 2]])
    return FusionStudy(t=sc.t, truth=sc.truth, est=est, rmse=rmse, floor=floor, steady=sc.t >= t_steady,
                       measurements=raw)


def run_rmse(est: ArrayLike, truth: ArrayLike, steps: ArrayLike, component: int, decimals: int = 3) -> FloatArray:
    r"""Per-run RMSE over time: :math:`\sqrt{\operatorname{mean}_k e_{r,k}^2}` on one state component.

    The per-run metric of the chapter's paired comparisons (same runs for every method).

    Parameters
    ----------
    est : array_like, shape (runs, K, n)
    truth : array_like, shape (K, n) or (runs, K, n)
    steps : array_like of bool, shape (K,)
        Steps averaged over.
    component : int
        State index (0 = x, 2 = y for Wang & Tang 2024).
    decimals : int
        Rounding of the result (default 3: mm): rules that give the same estimate up to round-off give
        exactly equal metrics instead of a difference of a few ulp.

    Returns
    -------
    ndarray, shape (runs,)
        Entry r: the RMS over the selected steps of run r's error in ``component``, rounded to ``decimals``.
    """
    est, truth = (read_once(est, "est"), read_once(truth, "truth"))  # converted once (fuzz 29a C5)
    est_arr = as_array(est, "est", ndim=3)
    truth_arr = as_array(truth, "truth", ndim=(0, 1, 2, 3))
    # rules 9 and 17 on the broadcast (fuzz 57b C5): 3.0 arrays of it at tracemalloc's peak, 3.1 ns an element
    broadcast((("est", est_arr.shape), ("truth", truth_arr.shape)), arrays=3, weight=1)
    component = index(component, "component", est_arr.shape[2])
    decimals = count(decimals, "decimals", minimum=0)
    e = np.asarray(est, dtype=float) - np.asarray(truth, dtype=float)
    mask = _steps_mask(steps)
    if e.ndim != 3 or mask.shape != (e.shape[1],):
        raise ValueError(f"est must be (runs, K, n) and steps (K,), got {e.shape} and {mask.shape}")
    if not mask.any():
        raise ValueError("steps selects no step")
    return np.round(np.sqrt(np.mean(e[:, mask, component] ** 2, axis=1)), decimals)


class NeesRule(StrEnum):
    """Rule keys of :func:`nees_study` (chapter 05); display labels in :data:`fusion.book.style.METHOD_LABELS`.

    Attributes
    ----------
    LOCAL
        Sensor 1's local Kalman filter.
    CI_HALF
        CI at the fixed weight ω = 0.5.
    CONVEX
        The convex combination (eqs. 3-4).
    SPLIT
        Split CI (its trace-optimal weights).
    PRINTED
        Eqs. 11-12 as printed (one weight for both parts, trace-optimal).
    """

    LOCAL = "nees_local_sensor_1"
    CI_HALF = "nees_ci_half"
    CONVEX = "nees_convex"
    SPLIT = "nees_split"
    PRINTED = "nees_printed_same_omega"


#: The fused rules of :func:`nees_study`: (key, rule of :func:`fusion.filtering.tracks.fuse_tracks`, fixed ω or None).
NEES_RULES: tuple[tuple[NeesRule, str, float | None], ...] = (
    (NeesRule.CI_HALF, "ci", 0.5), (NeesRule.CONVEX, "convex", None), (NeesRule.SPLIT, "split", None),
    (NeesRule.PRINTED, "printed", None))


def _nees_keys(values: Mapping[str, Any], cls: str) -> None:
    """A NEES study's estimates: one per rule of its mean NEES, and the targets (``"truth"``)."""
    want = {*values["mean_nees"], "truth"}
    if set(values["est"]) != want:
        raise ValueError(f"{cls}.est must hold the rules of {cls}.mean_nees and 'truth', "
                         f"got {shown(sorted(map(str, values['est'])), 200)}")


@dataclass(frozen=True)
class NeesStudy:
    """Mean NEES of the local filter and of the fused rules on targets that follow the model (:func:`nees_study`).

    Attributes
    ----------
    mean_nees : mapping of NeesRule to float
        Mean NEES of each rule (:class:`NeesRule`, in :data:`NEES_RULES` order after the local filter).
    est : mapping of str to ndarray, shape (runs, K, 4)
        The estimates of the fused rules and the local filter by :class:`NeesRule`, with the key ``"truth"`` for
        the targets.
    """

    mean_nees: Mapping[str, float]
    est: Mapping[str, FloatArray]

    __result_spec__ = ResultSpec({"mean_nees": dict_of(number()), "est": dict_of(array("runs", "K", 4))},
                                 relations=(_nees_keys,))
    __post_init__ = validated_post_init


def _nees_work(n_steps: int, runs: int, names: str = "n_steps and runs") -> None:
    """The work budget (rule 17) of NEES runs of the two local filters and every rule of ``NEES_RULES`` (split CI's
    search among them) at each of ``n_steps`` steps over ``runs`` runs (fuzz 24c SZ), weighed by its measured cost
    (fuzz 34a C9, OPENBLAS_NUM_THREADS=1): a step costs about 0.58 ms plus 2 us per run (0.23 CPU-s for 400 steps of
    2 runs, 0.40 for 400 of 200 runs, 0.50 for 200 of 1,000), so 58 loop steps plus 250 units a run: about 17,000
    steps of 2 runs are accepted (about 10 CPU-s) and 10**5 refused by name, never run for minutes."""
    from fusion._validation import LOOP_STEP, loop_work

    loop_work((n_steps,), 250 * runs, names, step=58 * LOOP_STEP)


@derived_inputs()
def nees_study(rng: np.random.Generator, Q: ArrayLike, R1: ArrayLike, R2: ArrayLike, x_start: ArrayLike,
               n_steps: int, runs: int, T: float = 1.0, velocity_sigma: float = 100.0,
               t_steady: float = 20.0) -> NeesStudy:
    r"""Mean NEES of the local filter and of CI, convex combination, split CI and eqs. 11-12 as printed.

    Targets follow the model (:func:`model_truth`, process noise common to both sensors), so the
    two local filters' errors are correlated. NEES :math:`\mathbf e^\top P^{-1}\mathbf e` averages
    to 4 (the state dimension) for a consistent estimator.

    Parameters
    ----------
    rng : numpy.random.Generator
        Draws the targets, then sensor 1's noise, then sensor 2's.
    Q : array_like, shape (4, 4)
    R1, R2 : array_like, shape (2, 2)
        Measurement covariances (m², diagonal): sensor j's noise is drawn with standard deviations
        ``sqrt(diag(Rj))`` and its filter starts with that position variance.
    x_start : array_like, shape (4,)
        Initial true state; its velocity is the filters' initial velocity.
    n_steps, runs : int
    T : float
        Sampling period (s).
    velocity_sigma : float
        Prior velocity standard deviation (m/s), common to both sensors.
    t_steady : float
        NEES is averaged over runs and steps with ``t >= t_steady`` (s).

    Returns
    -------
    NeesStudy
        Mean NEES of each rule over the steady-state steps (``mean_nees``) and the fused estimates (``est``).
    """
    Q, R1, R2, x_start = (read_once(Q, "Q"), read_once(R1, "R1"), read_once(R2, "R2"), read_once(x_start, "x_start"))
    R1 = diagonal_covariance(R1, 2, "R1")
    R2 = diagonal_covariance(R2, 2, "R2")
    as_array(x_start, "x_start", shape=(4,))
    n_steps = count(n_steps, "n_steps")
    velocity_sigma = std_scalar(velocity_sigma, "velocity_sigma")
    t_steady = nonnegative_scalar(t_steady, "t_steady")
    n_steps, runs = count(n_steps, "n_steps"), count(runs, "runs")
    allocation((runs, n_steps, 4), "runs and n_steps")
    _nees_work(n_steps, runs, "runs and n_steps")
    T = positive_scalar(T, "T")
    if not (np.arange(n_steps) * T >= t_steady).any():
        raise ValueError(f"t_steady = {t_steady} leaves no step of the n_steps = {n_steps} steps of T = {T} "
                         f"(the last at {(n_steps - 1) * T:.6g} s): lower t_steady, or raise n_steps or T")
    model = cv_model(T)
    F, H = model.F, model.H
    x_start = np.asarray(x_start, dtype=float)
    Xm = model_truth(rng, F, Q, x_start, n_steps, runs)
    P0d = np.diag([0.0, velocity_sigma**2, 0.0, velocity_sigma**2])
    tracks = []
    for R in (R1, R2):
        z = Xm[:, :, [0, 2]] + rng.standard_normal((runs, n_steps, 2)) * np.sqrt(np.diag(R))
        x0 = np.column_stack([z[:, 0, 0], np.zeros(runs), z[:, 0, 1], np.zeros(runs)]) + x_start * [0, 1, 0, 1]
        tracks.append(_named_track("velocity_sigma", z, F, H, Q, R, x0, P0d, np.diag([R[0, 0], 0.0, R[1, 1], 0.0])))
    steady = np.arange(n_steps) * T >= t_steady
    out: dict[str, float] = {NeesRule.LOCAL: float(np.mean(nees(tracks[0].est - Xm, tracks[0].gains.P)[:, steady]))}
    est: dict[str, FloatArray] = {NeesRule.LOCAL: tracks[0].est, "truth": Xm}
    for name, rule, w in NEES_RULES:
        f = fuse_tracks(tracks[0], tracks[1], rule, omega=w)
        out[name] = float(np.mean(nees(f.est - Xm, f.P)[:, steady]))
        est[name] = f.est
    return NeesStudy(mean_nees=out, est=est)


def slip_steps_band(rmse: float, published: float, decimals: int = 0) -> tuple[int, int]:
    r"""The numbers of steps :math:`n` for which the slip :math:`\sqrt{\sum e^2}/n` rounds to a published value.

    Eq. 13 coded with the :math:`1/n` outside the root gives the per-run RMSE divided by :math:`\sqrt n`
    (:func:`rmse_variants`). If the per-run RMSE ``rmse`` does not change with the length of the run, the
    slip equals ``published`` at ``decimals`` decimals exactly when :math:`\mathrm{round}(r/\sqrt n) = p`,
    i.e. for :math:`(r/(p + h))^2 < n \le (r/(p - h))^2`, :math:`h = 10^{-d}/2`.

    Parameters
    ----------
    rmse : float
        Per-run RMSE, averaged over the runs (m), > 0.
    published : float
        The published value (m), > ``10**-decimals / 2``.
    decimals : int
        Decimals it is printed with (0: whole metres).

    Returns
    -------
    (int, int)
        The smallest and largest :math:`n` (inclusive); ``lo > hi`` if no integer fits. Integers of any size (an
        ``rmse`` of 1e150 gives 300 digits and more).

    Raises
    ------
    ValueError
        ``rmse`` not positive, ``published`` not above half a unit of its last decimal.
    """
    r = positive_scalar(rmse, "rmse")
    d = count(decimals, "decimals", minimum=0)
    half = 0.5 * 10.0 ** (-d)
    p = scalar(published, "published", half, np.inf, lo_open=True)
    lo = _floor_square(r / (p + half)) + 1      # r/sqrt(n) < p + h (the upper end rounds up)
    hi = _floor_square(r / (p - half))          # r/sqrt(n) >= p - h
    return lo, hi


def _floor_square(q: float) -> int:
    """``floor(q**2)`` of a finite float ``q``; a square beyond the float range (``q`` above about 1.3e154: an
    ``rmse`` of 1e150 over a published value just above half a unit) exactly, as an integer (fuzz 42a C9: a raw
    OverflowError)."""
    try:
        return int(np.floor(q**2))
    except OverflowError:
        return math.floor(Fraction(q) ** 2)


def rmse_variants(est: ArrayLike, truth: ArrayLike, steps: ArrayLike) -> dict[str, tuple[float, float]]:
    r"""The RMSE of Wang & Tang's (2024) eq. 13 under each reading of its undefined :math:`n`, on x and y.

    Eq. 13 is :math:`\sqrt{\frac1n\sum (y_i - x_i)^2}` with ":math:`n` the number of samples". The
    samples may be the runs at each step (then averaged over the steps), the steps of each run (then
    averaged over the runs), or the steps of the estimate averaged over the runs first, which removes
    most of the noise and keeps the bias (lag after the turns). The last two readings put the
    :math:`1/n` outside the root, :math:`\sqrt{\sum e^2}/n`, a common slip when the formula is coded
    (MATLAB's ``sqrt(sum(e.^2))/n``): that is the RMSE divided by :math:`\sqrt n`, with :math:`n` the
    steps of each run or the runs at each step.

    Parameters
    ----------
    est : array_like, shape (runs, K, 4)
        Estimates :math:`[x, \dot x, y, \dot y]`.
    truth : array_like, shape (K, 4)
        True states.
    steps : array_like of bool, shape (K,)
        Steps used (:math:`n` counts the selected steps in the slip over steps).

    Returns
    -------
    dict of str to (float, float)
        RMSE on (x, y) in m for ``"over runs, per step"``, ``"over steps, per run"``,
        ``"of the run-averaged estimate"``, ``"√(Σe²)/n over steps, per run (1/n outside the root)"`` and
        ``"√(Σe²)/n over runs, per step (1/n outside the root)"``.
    """
    e_all = as_array(est, "est", ndim=3)
    tr = as_array(truth, "truth", ndim=2)
    if e_all.shape[1:] != tr.shape or e_all.shape[2] < 3:
        raise ValueError(f"truth must have shape {e_all.shape[1:]} (K, 4) to match est, got {tr.shape}")
    mask = _steps_mask(steps)
    if mask.shape != (tr.shape[0],) or not mask.any():
        raise ValueError(f"steps must be a boolean (K,) = ({tr.shape[0]},) array selecting at least one step")
    e = (e_all - tr)[:, mask][:, :, [0, 2]]
    runs, k = e.shape[:2]
    per_step = np.sqrt(np.mean(e**2, axis=0)).mean(axis=0)
    per_run = np.sqrt(np.mean(e**2, axis=1)).mean(axis=0)
    averaged = np.sqrt(np.mean(e.mean(axis=0) ** 2, axis=0))
    slip_steps = (np.sqrt(np.sum(e**2, axis=1)) / k).mean(axis=0)
    slip_runs = (np.sqrt(np.sum(e**2, axis=0)) / runs).mean(axis=0)
    return {OVER_RUNS: (float(per_step[0]), float(per_step[1])),
            OVER_STEPS: (float(per_run[0]), float(per_run[1])),
            RUN_AVERAGED: (float(averaged[0]), float(averaged[1])),
            SLIP_STEPS: (float(slip_steps[0]), float(slip_steps[1])),
            SLIP_RUNS: (float(slip_runs[0]), float(slip_runs[1]))}


#: Keys of :func:`rmse_variants` for the slip :math:`\sqrt{\sum e^2}/n` (n = steps of a run, n = runs of a step).
SLIP_STEPS = "√(Σe²)/n over steps, per run (1/n outside the root)"
SLIP_RUNS = "√(Σe²)/n over runs, per step (1/n outside the root)"
#: Keys of :func:`rmse_variants` for the RMSE over runs per step, over steps per run, and of the run-averaged
#: estimate (issue 36: chapter 05 reads them by these names).
OVER_RUNS = "over runs, per step"
OVER_STEPS = "over steps, per run"
RUN_AVERAGED = "of the run-averaged estimate"


def _steps_mask(steps: object) -> np.ndarray:
    """``steps`` as a boolean array (its entries' truth values), any numpy conversion error naming it."""
    try:
        return np.asarray(steps, dtype=bool)
    except (TypeError, ValueError, RecursionError) as exc:
        raise TypeError(f"steps must be a boolean (K,) array: {type(exc).__name__}: {str(exc):.200}") from None
