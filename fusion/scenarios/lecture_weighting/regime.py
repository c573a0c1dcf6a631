r"""Lecture §2.1 (E2.1b): the estimators in the regime they are for.

A time-varying X and a change of the sensor variances (:func:`regime_study`), and the lecture's setting, a constant
X with one change of the noise SDs (:func:`variance_change_study`).
"""

from __future__ import annotations

from dataclasses import dataclass
from collections.abc import Mapping, Sequence
from enum import StrEnum
from typing import Any

import numpy as np

from fusion._frozen import constant
from fusion._results import (NONNEGATIVE, ResultSpec, array, dict_of, instance, integer, number, same_keys, text,
                             tuple_of, validated_post_init)
from fusion._validation import derived_inputs
from fusion._limits import LOOP_STEP, MAX_WORK, REGIME_STUDY, STUDY_WORK
from fusion._validation import allocation, count, one_of, read_mapping, scalar, sequence, work
from fusion._validation import text as text_of
from fusion.readings import weighting as wt
from fusion.scenarios._lecture_checks import _index, _seed, _sigmas
from fusion._shown import shown

__all__ = [
    "RegimeMethod",
    "RegimeScenario",
    "VarianceChange",
    "RegimeStudy",
    "VarianceChangeStudy",
    "REGIME_SCENARIOS",
    "REGIME_METHODS",
    "REGIME_CONSTANT_ONLY",
    "regime_study",
    "VARIANCE_CHANGES",
    "CHANGE_METHODS",
    "variance_change_study",
]


# --------------------------------------------------------------------------- E2.1b
class RegimeScenario(StrEnum):
    """Scenario keys of :func:`regime_study` (labels: :data:`fusion.book.style.METHOD_LABELS`).

    Attributes
    ----------
    CONSTANT, SINE, SINE_LEVEL, FAST, WALK, STEP
        A constant X = 0; a slow sine; the slow sine around ``level``; a fast sine; a random walk; a step in X at
        ``change_at``.
    CONSTANT_SWAP, SINE_SWAP
        The constant X and the slow sine with sensors 1 and 4 swapping their noise SDs at ``change_at``.
    """

    CONSTANT = "lec_scen_constant"
    SINE = "lec_scen_sine"
    SINE_LEVEL = "lec_scen_sine_level"
    FAST = "lec_scen_fast"
    WALK = "lec_scen_walk"
    STEP = "lec_scen_step"
    CONSTANT_SWAP = "lec_scen_constant_swap"
    SINE_SWAP = "lec_scen_sine_swap"


_S = RegimeScenario

#: Name of the truth that stays at 0 among the signals of :data:`REGIME_SCENARIOS` (a name of this study's own
#: signals, not the label "constant" of chapter 03's ``Signal.CONSTANT``; named once for the label scan of issue 36).
_CONSTANT = "constant"

#: Scenarios of :func:`regime_study`: (key, signal, variances swap at ``change_at``).
REGIME_SCENARIOS: tuple[tuple[RegimeScenario, str, bool], ...] = (
    (_S.CONSTANT, _CONSTANT, False),
    (_S.SINE, "sine", False),
    (_S.SINE_LEVEL, "sine_level", False),
    (_S.FAST, "fast", False),
    (_S.WALK, "walk", False),
    (_S.STEP, "step", False),
    (_S.CONSTANT_SWAP, _CONSTANT, True),
    (_S.SINE_SWAP, "sine", True),
)

class RegimeMethod(StrEnum):
    """Method keys of :func:`regime_study` and :func:`variance_change_study` (labels: :data:`fusion.book.style.METHOD_LABELS`).

    Attributes
    ----------
    ORACLE, MEAN
        The current readings weighted by their true current variances; equally.
    SAMPLE_GROWING
        Each sensor's sample variance, growing memory.
    DIFFERENCE_GROWING, DIFFERENCE_FORGETTING
        Each sensor's first differences (:func:`fusion.readings.weighting.difference_variances`), growing memory
        and forgetting.
    LECTURE_GROWING
        The lecture's cross-moment estimator, growing memory.
    CENTRED_GROWING, CENTRED_FORGETTING, CENTRED_WINDOW
        The centred estimator with growing memory, forgetting and a sliding window.
    AWF_AS_WRITTEN
        The lecture's AWF as written: its estimates applied to the running means.
    RUNNING_MEANS_ORACLE
        The running means weighted by their true variances.
    PER_SAMPLE_FORGETTING, PER_SAMPLE_FORGETTING_ALT
        The per-sample inverse-variance accumulation with the centred forgetting estimates (the first and the
        second forgetting factor).
    PER_SAMPLE_BLUE
        The per-sample accumulation with the true variance of every sample (the per-sample BLUE).
    LS_GROWING, LS_FORGETTING
        The variance learning of sec. 2.2 with its 1/m recursion; with forgetting.
    """

    ORACLE = "lec_reg_oracle"
    MEAN = "lec_reg_mean"
    SAMPLE_GROWING = "lec_reg_sample_growing"
    DIFFERENCE_GROWING = "lec_reg_difference_growing"
    DIFFERENCE_FORGETTING = "lec_reg_difference_forgetting"
    LECTURE_GROWING = "lec_reg_lecture_growing"
    CENTRED_GROWING = "lec_reg_centred_growing"
    CENTRED_FORGETTING = "lec_reg_centred_forgetting"
    CENTRED_WINDOW = "lec_reg_centred_window"
    AWF_AS_WRITTEN = "lec_reg_awf_as_written"
    RUNNING_MEANS_ORACLE = "lec_reg_running_means_oracle"
    PER_SAMPLE_FORGETTING = "lec_reg_per_sample_forgetting"
    PER_SAMPLE_FORGETTING_ALT = "lec_reg_per_sample_forgetting_alt"
    PER_SAMPLE_BLUE = "lec_reg_per_sample_blue"
    LS_GROWING = "lec_reg_ls_growing"
    LS_FORGETTING = "lec_reg_ls_forgetting"


_R = RegimeMethod

#: Methods of :func:`regime_study`, in its order. All but the "running means" and "per-sample" ones fuse the
#: *current* readings; those estimate a constant X from every reading so far.
REGIME_METHODS: tuple[RegimeMethod, ...] = tuple(RegimeMethod)

#: Methods of :func:`regime_study` run only where X is constant (they estimate a constant).
REGIME_CONSTANT_ONLY: tuple[RegimeMethod, ...] = (_R.PER_SAMPLE_FORGETTING, _R.PER_SAMPLE_FORGETTING_ALT,
                                                  _R.PER_SAMPLE_BLUE)


#: Units (about 10 ns, ``fusion._limits.MAX_WORK``) of one draw (run x sample x sensor) of :func:`regime_study`
#: (six scenarios of a dozen variance trackers each) and of :func:`variance_change_study`, measured (budget35,
#: OPENBLAS_NUM_THREADS=1): about 5 us and 0.75 us a draw (2.1 and 0.28 CPU-s for the default 100 runs x 1,000
#: samples x 4 sensors), so that the edge is about 10 CPU-s (without a work budget, 10**7 samples of 2 runs, some
#: 400 CPU-s, were accepted); :func:`regime_study`'s budget is its entry of ``fusion._limits.STUDY_WORK`` (the
#: reseeding sweep's 1,000 runs count 2e9 units, about 20 CPU-s: 4e9).
_REGIME_DRAW = 500
#: :func:`variance_change_study`'s cost is a draw's per change (fuzz 40a C6: 60 changes of 400 runs, 12 % of the budget
#: at 75 units a draw, ran 37.6 CPU-s): 10 units a draw and 45 a draw and change, from 566, 451, 351 and 465 ns a draw
#: and change with 1, 3, 12 and 30 changes of 100 runs x 1,000 samples x 4 sensors (the least of two calls,
#: ``time.process_time``, ``OPENBLAS_NUM_THREADS=1``, machine shared with other jobs; the default 3 changes: 145 units,
#: 1.35 us a draw, so the edge is about 9 CPU-s).
_CHANGE_DRAW, _CHANGE_DRAW_EACH = 10, 45
#: Units of one change's fixed step in :func:`variance_change_study` whatever its draws (fuzz 42a C2: its checks, its
#: SDs, five fusions' Python and numpy calls): 0.69, 0.68 and 0.71 ms a change with 100, 1,000 and 4,000 changes of
#: 1 run x 20 samples x 3 sensors (the least of two calls, ``time.process_time``, ``OPENBLAS_NUM_THREADS=1``, machine
#: shared with other jobs), 70 ``LOOP_STEP``: uncounted, 50,000 changes at those draws were accepted (1.35e8 units)
#: and ran 36.9 CPU-s; now at most about 13,700 are accepted (13,500 ran 9.3 CPU-s).
_CHANGE_STEP = 70 * LOOP_STEP


def _draws(sigma: Sequence[float], samples: int, runs: int, seed: int,
           weight: int, names: str = "runs, samples and sigma",
           limit: int = MAX_WORK) -> tuple[np.ndarray, int, int, int]:
    """The checked SDs (three or more), samples (20 or more), runs and seed of a study's (runs, samples, n) draws,
    within the memory budget and the work budget (``limit``) at ``weight`` units a draw (rule 17), naming ``names``
    in the work refusal (the arguments that set ``weight`` too)."""
    sig = _sigmas(sigma, minimum=3)
    samples = count(samples, "samples", minimum=20)
    runs = count(runs, "runs")
    _draws_budget(runs, samples, sig.size, weight, names, limit)
    return sig, samples, runs, _seed(seed)


def _forgetting(value: float, name: str) -> float:
    """A forgetting factor: a real number in the open interval (0, 1), ValueError/TypeError naming ``name``."""
    v = scalar(value, name)
    if not 0.0 < v < 1.0:
        raise ValueError(f"{name} must be in (0, 1), got {shown(value)}")
    return v


# A forgetting factor in (0, 1): positive, at most 1 (bounds are closed), and below 1 (``_window_and_factors``).
_FACTOR = number(positive=True, bounds=(0.0, 1.0))


def _window_and_factors(values: Mapping[str, Any], cls: str) -> None:
    """A study's evaluation window ``[change_at, samples)`` not empty and its forgetting factors below 1."""
    if not values["change_at"] < values["samples"]:
        raise ValueError(f"{cls}.change_at must be below {cls}.samples = {values['samples']}, got {values['change_at']}")
    for name in ("forgetting", "forgetting_alt"):
        if not values[name] < 1.0:
            raise ValueError(f"{cls}.{name} must be in (0, 1), got {shown(values[name])}")


def _regime_relation(values: Mapping[str, Any], cls: str) -> None:
    """A :class:`RegimeStudy`: its window and factors; per scenario the methods of ``sq`` among ``methods``, a curve
    for each of them, a weight curve for some; non-positive counts for scenarios of the study."""
    _window_and_factors(values, cls)
    methods = set(values["methods"])
    for case, by_method in values["sq"].items():
        extra = set(by_method) - methods
        if extra:
            raise ValueError(f"{cls}.sq[{shown(case)}] must hold methods of {cls}.methods, got "
                             f"{shown(sorted(map(str, extra)), 200)}")
        if set(values["curve"][case]) != set(by_method):
            raise ValueError(f"{cls}.curve[{shown(case)}] must hold the methods of {cls}.sq[{shown(case)}]")
        if not set(values["w_best"][case]) <= set(by_method):
            raise ValueError(f"{cls}.w_best[{shown(case)}] must hold methods of {cls}.sq[{shown(case)}]")
    extra = set(values["n_nonpositive"]) - set(values["scenarios"])
    if extra:
        raise ValueError(f"{cls}.n_nonpositive must be keyed by scenarios of {cls}.scenarios, got "
                         f"{shown(sorted(map(str, extra)))}")


def _change_relation(values: Mapping[str, Any], cls: str) -> None:
    """A :class:`VarianceChangeStudy`: its window and factors; every method of ``methods`` for every change."""
    _window_and_factors(values, cls)
    methods = set(values["methods"])
    for case, by_method in values["sq"].items():
        if set(by_method) != methods:
            raise ValueError(f"{cls}.sq[{shown(case)}] must hold the methods of {cls}.methods, got "
                             f"{shown(sorted(map(str, by_method)), 200)}")


@dataclass(frozen=True)
class RegimeStudy:
    """Experiment E2.1b: the estimators in the regime they are for (:func:`regime_study`).

    Attributes
    ----------
    scenarios : tuple of RegimeScenario
        The keys of :data:`REGIME_SCENARIOS`.
    methods : tuple of RegimeMethod
        :data:`REGIME_METHODS`.
    sq : mapping
        ``sq[scenario][key]``: per-run MSE over the evaluation window, shape (runs,) (the methods of
        :data:`REGIME_CONSTANT_ONLY` only where X is constant).
    curve : mapping
        ``curve[scenario][key]``: MSE over runs against k, shape (samples,).
    w_best : mapping
        ``w_best[scenario][key]``: mean weight of sensor 1 against k (current-reading methods).
    var_est : mapping
        Per-run σ̂₁² at the last sample, constant X, for ``"sample"`` and ``"centred"``.
    n_nonpositive : mapping
        ``n_nonpositive[scenario]``: number of non-positive estimates of the lecture's estimator (growing memory)
        in the evaluation window, where X is constant.
    variances, swapped : ndarray, shape (n,)
        The noise variances before and after the swap.
    runs, samples, seed, change_at, window, walk_seed : int
    amplitude, period, step, forgetting, forgetting_alt, level, fast_period, walk_step : float
    guard : str
        The parameters of :func:`regime_study`.
    """

    scenarios: tuple[str, ...]
    methods: tuple[RegimeMethod, ...]
    sq: Mapping[str, Mapping[RegimeMethod, np.ndarray]]
    curve: Mapping[str, Mapping[RegimeMethod, np.ndarray]]
    w_best: Mapping[str, Mapping[RegimeMethod, np.ndarray]]
    var_est: Mapping[str, np.ndarray]
    n_nonpositive: Mapping[str, int]
    variances: np.ndarray
    swapped: np.ndarray
    runs: int
    samples: int
    seed: int
    amplitude: float
    period: float
    step: float
    change_at: int
    forgetting: float
    forgetting_alt: float
    window: int
    guard: str
    level: float
    fast_period: float
    walk_step: float
    walk_seed: int

    __result_spec__ = ResultSpec(
        {"scenarios": tuple_of(instance(RegimeScenario)), "methods": tuple_of(instance(RegimeMethod)),
         "sq": dict_of(dict_of(array("runs", bounds=NONNEGATIVE))),
         "curve": dict_of(dict_of(array("samples", bounds=NONNEGATIVE))), "w_best": dict_of(dict_of(array("samples"))),
         "var_est": dict_of(array("runs"), keys=("sample", "centred")), "n_nonpositive": dict_of(integer(0)),
         "variances": array("n", bounds=NONNEGATIVE), "swapped": array("n", bounds=NONNEGATIVE),
         "runs": integer(1, dim="runs"), "samples": integer(1, dim="samples"), "seed": integer(0),
         "amplitude": number(nonnegative=False), "period": number(positive=True), "step": number(nonnegative=False),
         "change_at": integer(0), "forgetting": _FACTOR, "forgetting_alt": _FACTOR, "window": integer(1),
         "guard": text(*wt.GUARDS), "level": number(nonnegative=False), "fast_period": number(positive=True),
         "walk_step": number(), "walk_seed": integer(0)},
        relations=(same_keys("scenarios", "sq", "curve", "w_best"), lambda v, cls: _regime_relation(v, cls)))
    __post_init__ = validated_post_init


def _draws_budget(runs: int, samples: int, n: int, weight: int, names: str, limit: int = MAX_WORK) -> int:
    """Rules 9 and 17 of a study's (runs, samples, n) draws (``_draws``'s, unchanged): the memory budget, then
    ``weight`` units a draw within ``limit``, naming ``names`` in the work refusal; its units (a chapter reader that
    runs several studies sums them, fuzz 62a)."""
    allocation((runs, samples, n), "runs, samples and sigma")
    return work((runs, samples, n), names, weight=weight, limit=limit)


def _change_work(runs: int, samples: int, n: int, changes: int, names: str) -> int:
    """Rule 17 of :func:`variance_change_study` on checked counts (its second check, unchanged): every draw at
    ``10 + 45 x changes`` units and each change's fixed step (fuzz 42a C2), naming ``names``; its units."""
    weight = _CHANGE_DRAW + _CHANGE_DRAW_EACH * changes
    return work((runs * samples * n * weight + changes * _CHANGE_STEP,), names)


@derived_inputs()
def regime_study(
    sigma: Sequence[float] = (0.5, 1.0, 2.0, 4.0),
    samples: int = 1000,
    runs: int = 200,
    seed: int = 2105,
    amplitude: float = 5.0,
    period: float = 400.0,
    step: float = 10.0,
    change_at: int = 500,
    forgetting: float = 0.98,
    window: int = 100,
    guard: str = "abs",
    level: float = 900.0,
    fast_period: float = 10.0,
    walk_step: float = 1.0,
    walk_seed: int = 2106,
    forgetting_alt: float = 0.99,
) -> RegimeStudy:
    r"""Experiment E2.1b: the variance estimators of sec. 2.1 where X varies and where the variances change.

    ``n`` sensors read :math:`X(k)` with noise SDs ``sigma``: a constant X = 0; a slow sine
    :math:`X(k) = A\sin(2\pi k/P)`, the same around ``level``, and a fast sine of period
    ``fast_period``; a random walk with steps of SD ``walk_step`` (one path, drawn with
    ``walk_seed``, shared by the runs); or a step of height ``step`` at ``change_at``. In the swap
    scenarios the first and last sensors exchange their noise SDs at ``change_at`` (the best
    sensor becomes the worst). The same standard-normal draws are used in every scenario.

    Methods that fuse the current readings :math:`\sum_p W_p(k)X_p(k)`, with weights from: the
    true current variances (oracle), equal weights (mean), each sensor's sample variance, each
    sensor's first differences (:func:`fusion.readings.weighting.difference_variances`, growing
    memory and forgetting), the lecture's cross-moment estimator, and the centred one with the
    lecture's growing memory, with exponential forgetting and with a sliding window
    (:func:`fusion.readings.weighting.tracking_variances`). Methods for a constant X that use every
    reading so far: the lecture's AWF as written (its estimates applied to the running means), the
    running means weighted by their true variances :math:`k^{-2}\sum_{i\le k}\sigma_p^2(i)`, and,
    where X is constant only, the per-sample inverse-variance accumulation
    (:func:`fusion.readings.weighting.cumulative_fusion`) with the centred forgetting estimates
    (``forgetting`` and ``forgetting_alt``, equal time weights) and with the true variance of every
    sample (the per-sample BLUE). Last, the variance learning of sec. 2.2 (allocations
    :math:`(y_{mi} - \bar y_m)^2`, unaffected by a varying X) averaged with its 1/m recursion
    (:func:`fusion.readings.weighting.learned_variances`) or with the forgetting factor. Every
    method but the oracles is causal (readings up to k).

    Parameters
    ----------
    sigma : sequence of float, shape (n,)
        Noise SDs, n >= 3.
    samples, runs, seed : int
    amplitude, period : float
        Sine amplitude A and period P (samples) of the slow sines.
    step : float
        Step height.
    change_at : int
        Sample (0-based) of the step and of the variance swap; the evaluation window is
        ``[change_at, samples)``.
    forgetting : float
        Forgetting factor λ of the forgetting variants.
    window : int
        Window length of the sliding-window variant.
    guard : {"floor", "abs", "equal", "none"}
        Guard of non-positive estimates (:data:`fusion.readings.weighting.GUARDS`); the per-sample
        accumulation uses ``"abs"`` when ``guard="none"``.
    level : float
        Level of the second slow sine, :math:`X(k) = \text{level} + A\sin(2\pi k/P)`.
    fast_period : float
        Period (samples) of the fast sine (amplitude A).
    walk_step : float
        SD of the random walk's steps.
    walk_seed : int
        Seed of the random walk's path.
    forgetting_alt : float
        Second forgetting factor of the per-sample accumulation.

    Returns
    -------
    RegimeStudy
        Per scenario and method the squared errors, the MSE curve and the mean weight of sensor 1 against k; the final
        σ̂₁² per run.
    """
    # the reseeding sweep's 10x reading (lec-awf-adapts) counts 2e9: its entry of fusion._limits.STUDY_WORK
    sig, samples, runs, seed = _draws(sigma, samples, runs, seed, _REGIME_DRAW, limit=STUDY_WORK[REGIME_STUDY])
    amplitude = scalar(amplitude, "amplitude")
    period, fast_period = (scalar(v, name, lo=0.0, lo_open=True)
                           for name, v in (("period", period), ("fast_period", fast_period)))
    step = scalar(step, "step")
    level = scalar(level, "level")
    walk_step = scalar(walk_step, "walk_step", lo=0.0)
    walk_seed = _seed(walk_seed, "walk_seed")
    forgetting, forgetting_alt = (_forgetting(v, name)
                                  for name, v in (("forgetting", forgetting), ("forgetting_alt", forgetting_alt)))
    change_at = _index(change_at, samples, "change_at")
    guard = one_of(guard, wt.GUARDS, "guard")
    acc_guard = "abs" if guard == "none" else guard
    n, K = sig.size, samples
    k = np.arange(K)
    after = k >= change_at
    swapped = sig.copy()
    swapped[[0, -1]] = sig[[-1, 0]]
    sd_t = np.where(after[:, None], swapped, sig)  # (K, n)
    z = np.random.default_rng(seed).normal(size=(runs, K, n))
    sine = amplitude * np.sin(2 * np.pi * k / period)
    signals = {_CONSTANT: np.zeros(K), "sine": sine, "sine_level": level + sine,
               "fast": amplitude * np.sin(2 * np.pi * k / fast_period),
               "walk": np.cumsum(np.random.default_rng(walk_seed).normal(size=K)) * walk_step,
               "step": np.where(after, step, 0.0)}
    sq: dict[str, dict[RegimeMethod, np.ndarray]] = {}
    curve: dict[str, dict[RegimeMethod, np.ndarray]] = {}
    w_best: dict[str, dict[RegimeMethod, np.ndarray]] = {}
    var_est: dict[str, np.ndarray] = {}
    n_nonpos: dict[str, int] = {}
    for name, sigl, swap in REGIME_SCENARIOS:
        sd = sd_t if swap else np.broadcast_to(sig, (K, n))
        truth = signals[sigl]
        X = truth[:, None] + z * sd
        cen_forget = wt.tracking_variances(X, "centred", "forgetting", forgetting=forgetting)
        growing = wt._tracking_estimates(X, ("sample", "lecture", "centred"))   # tracking_variances's, one pass
        est = {
            _R.ORACLE: np.broadcast_to(sd**2, X.shape),
            _R.MEAN: np.ones_like(X),
            _R.SAMPLE_GROWING: growing[0],
            _R.DIFFERENCE_GROWING: wt.difference_variances(X),
            _R.DIFFERENCE_FORGETTING: wt.difference_variances(X, "forgetting", forgetting=forgetting),
            _R.LECTURE_GROWING: growing[1],
            _R.CENTRED_GROWING: growing[2],
            _R.CENTRED_FORGETTING: cen_forget,
            _R.CENTRED_WINDOW: wt.tracking_variances(X, "centred", "window", window=window),
        }
        if name == _S.CONSTANT:
            var_est = {"sample": est[_R.SAMPLE_GROWING][:, -1, 0], "centred": est[_R.CENTRED_GROWING][:, -1, 0]}
        fused, wb = {}, {}
        for m, v in est.items():
            w = wt.inverse_variance_weights(v, guard=guard)  # type: ignore[arg-type]
            fused[m] = np.sum(w * X, axis=-1)
            wb[m] = w[..., 0].mean(axis=0)
        a = wt.awf(X, "lecture", guard=guard)  # type: ignore[arg-type]
        fused[_R.AWF_AS_WRITTEN] = a.value
        wb[_R.AWF_AS_WRITTEN] = a.weights[..., 0].mean(axis=0)
        if sigl == _CONSTANT:
            n_nonpos[name] = int(np.sum(a.variances[:, after] <= 0))
        # the running means weighted by their true variance k⁻²Σσ²(i): the best fusion of the running means
        rm = a.means
        kk = np.arange(1, K + 1)[:, None]
        w = wt.inverse_variance_weights(np.broadcast_to(np.cumsum(np.asarray(sd, dtype=float) ** 2, axis=0) / kk**2, X.shape))
        fused[_R.RUNNING_MEANS_ORACLE] = np.sum(w * rm, axis=-1)
        wb[_R.RUNNING_MEANS_ORACLE] = w[..., 0].mean(axis=0)
        if sigl == _CONSTANT:
            # every sample weighted by its own (estimated or true) inverse variance, accumulated over time
            fused[_R.PER_SAMPLE_FORGETTING] = wt.cumulative_fusion(X, cen_forget, guard=acc_guard)  # type: ignore[arg-type]
            fused[_R.PER_SAMPLE_FORGETTING_ALT] = wt.cumulative_fusion(
                X, wt.tracking_variances(X, "centred", "forgetting", forgetting=forgetting_alt), guard=acc_guard)  # type: ignore[arg-type]
            fused[_R.PER_SAMPLE_BLUE] = wt.cumulative_fusion(X, est[_R.ORACLE], time_weights="precision")
        # sec. 2.2: the allocations (y − ȳ)² averaged with the lecture's 1/m recursion or with forgetting
        dev2 = (X - X.mean(axis=-1, keepdims=True)) ** 2
        for m, v in ((_R.LS_GROWING, wt.learned_variances(X)),
                     (_R.LS_FORGETTING, wt.running_average(dev2, "forgetting", forgetting=forgetting))):
            w = wt.inverse_variance_weights(v, guard=guard)  # type: ignore[arg-type]
            fused[m] = np.sum(w * X, axis=-1)
            wb[m] = w[..., 0].mean(axis=0)
        e2 = {m: (f - truth) ** 2 for m, f in fused.items()}
        sq[name] = {m: e[:, after].mean(axis=1) for m, e in e2.items()}
        curve[name] = {m: e.mean(axis=0) for m, e in e2.items()}
        w_best[name] = wb
    return RegimeStudy(scenarios=[s[0] for s in REGIME_SCENARIOS], methods=list(REGIME_METHODS), sq=sq, curve=curve,
                       w_best=w_best, var_est=var_est, n_nonpositive=n_nonpos, variances=sig**2,
                       swapped=swapped**2, runs=runs, samples=K, seed=seed, amplitude=float(amplitude),
                       period=float(period), step=float(step), change_at=int(change_at), forgetting=float(forgetting),
                       forgetting_alt=float(forgetting_alt), window=int(window), guard=guard, level=float(level),
                       fast_period=float(fast_period), walk_step=float(walk_step), walk_seed=int(walk_seed))


class VarianceChange(StrEnum):
    """Keys of the changes of :data:`VARIANCE_CHANGES` (labels: :data:`fusion.book.style.METHOD_LABELS`).

    Attributes
    ----------
    SWAP
        Sensors 1 and 4 swap their noise SDs (0.5 and 4).
    DEGRADE
        Sensor 1's SD rises from 0.5 to 4.
    IMPROVE
        Sensor 4's SD falls from 4 to 0.5.
    """

    SWAP = "lec_chg_swap"
    DEGRADE = "lec_chg_degrade"
    IMPROVE = "lec_chg_improve"


#: Changes of the noise SDs of :func:`variance_change_study`: (key, {sensor index: SD after the change}).
VARIANCE_CHANGES: tuple[tuple[str, dict[int, float]], ...] = constant((
    (VarianceChange.SWAP, {0: 4.0, 3: 0.5}),
    (VarianceChange.DEGRADE, {0: 4.0}),
    (VarianceChange.IMPROVE, {3: 0.5}),
))

#: Fusions of a constant X from every reading so far, run by :func:`variance_change_study`.
CHANGE_METHODS: tuple[RegimeMethod, ...] = (_R.AWF_AS_WRITTEN, _R.RUNNING_MEANS_ORACLE, _R.PER_SAMPLE_FORGETTING,
                                            _R.PER_SAMPLE_FORGETTING_ALT, _R.PER_SAMPLE_BLUE)


@dataclass(frozen=True)
class VarianceChangeStudy:
    """E2.1b in the lecture's setting: a constant X and one change of the noise SDs (:func:`variance_change_study`).

    Attributes
    ----------
    changes : tuple of str
        The change keys (:class:`VarianceChange` for :data:`VARIANCE_CHANGES`).
    methods : tuple of RegimeMethod
        :data:`CHANGE_METHODS`.
    sq : mapping
        ``sq[change][key]``: per-run MSE over the evaluation window, shape (runs,).
    sd_after : mapping
        ``sd_after[change]``: SDs after the change.
    variances : ndarray, shape (n,)
    runs, samples, seed, change_at : int
    forgetting, forgetting_alt : float
        The parameters of :func:`variance_change_study`.
    """

    changes: tuple[str, ...]
    methods: tuple[RegimeMethod, ...]
    sq: Mapping[str, Mapping[RegimeMethod, np.ndarray]]
    sd_after: Mapping[str, np.ndarray]
    variances: np.ndarray
    runs: int
    samples: int
    seed: int
    change_at: int
    forgetting: float
    forgetting_alt: float

    __result_spec__ = ResultSpec(
        {"changes": tuple_of(instance(str)), "methods": tuple_of(instance(RegimeMethod)),
         "sq": dict_of(dict_of(array("runs", bounds=NONNEGATIVE))), "sd_after": dict_of(array("n", bounds=NONNEGATIVE)),
         "variances": array("n", bounds=NONNEGATIVE), "runs": integer(1, dim="runs"), "samples": integer(1),
         "seed": integer(0), "change_at": integer(0), "forgetting": _FACTOR, "forgetting_alt": _FACTOR},
        relations=(same_keys("changes", "sq", "sd_after"), lambda v, cls: _change_relation(v, cls)))
    __post_init__ = validated_post_init


@derived_inputs()
def variance_change_study(
    sigma: Sequence[float] = (0.5, 1.0, 2.0, 4.0),
    samples: int = 1000,
    runs: int = 100,
    seed: int = 2105,
    change_at: int = 500,
    forgetting: float = 0.98,
    forgetting_alt: float = 0.99,
    changes: Sequence[tuple[str, dict[int, float]]] = VARIANCE_CHANGES,
) -> VarianceChangeStudy:
    r"""E2.1b, the lecture's own setting: a constant X = 0 and one change of the sensors' noise SDs.

    The same standard-normal draws as :func:`regime_study` with the same ``seed``, ``runs``,
    ``samples`` and number of sensors, so the swap reproduces its scenario
    ``RegimeScenario.CONSTANT_SWAP`` run by run. Each change sets the SDs of some sensors from sample ``change_at`` (0-based) on. The
    fusions (:data:`CHANGE_METHODS`) estimate the constant from every reading so far: the lecture's
    AWF of running means (its estimator, growing memory, non-positive estimates as
    :math:`|\hat\sigma^2|`), the running means weighted by their true variances, the per-sample
    inverse-variance accumulation with the centred forgetting estimates (``forgetting`` and
    ``forgetting_alt``) and with the true variance of every sample (the per-sample BLUE).

    Parameters
    ----------
    sigma : sequence of float, shape (n,)
        Noise SDs before the change, n >= 3.
    samples, runs, seed : int
    change_at : int
        First sample (0-based) with the new SDs; the evaluation window is ``[change_at, samples)``.
    forgetting, forgetting_alt : float
        Forgetting factors λ in (0, 1) of the per-sample accumulation.
    changes : sequence of (str, dict)
        Key and ``{sensor index: new SD}`` of each change (SDs non-negative and finite); a key without a
        :data:`fusion.book.style.METHOD_LABELS` entry is shown as itself.

    Returns
    -------
    VarianceChangeStudy
        Per change and method the squared errors against k, with the SDs after the change.

    Raises
    ------
    ValueError
        A bad argument, named; ``runs x samples x n`` draws at ``10 + 45 x len(changes)`` units each and 70,000
        units a change (measured) beyond the work budget, naming runs, samples, sigma and changes, before any work.
    """
    # the list sequence() returns is what is counted and iterated (fuzz 41a C4: a len() that changed between reads was
    # counted as 1 change while the loop ran all 100)
    given, changes = changes, sequence(changes, "changes")
    if isinstance(given, (str, bytes, Mapping)) or len(changes) == 0:
        raise ValueError(f"changes must be a non-empty sequence of (name, {{sensor: SD}}) pairs, got {shown(given)}")
    # rule 17: every change runs the five fusions on every draw, so the changes are counted before any work
    weight = _CHANGE_DRAW + _CHANGE_DRAW_EACH * len(changes)
    sig, samples, runs, seed = _draws(sigma, samples, runs, seed, weight, "runs, samples, sigma and changes")
    # and each change's fixed step, whatever its draws (fuzz 42a C2)
    _change_work(runs, samples, sig.size, len(changes), "runs, samples, sigma and changes")
    change_at = _index(change_at, samples, "change_at")
    forgetting, forgetting_alt = (_forgetting(v, name)
                                  for name, v in (("forgetting", forgetting), ("forgetting_alt", forgetting_alt)))
    n, K = sig.size, samples
    after_sd: dict[str, np.ndarray] = {}
    for item in changes:
        if not (isinstance(item, (tuple, list)) and len(item) == 2 and isinstance(item[0], str)  # a list pair too
                and isinstance(item[1], Mapping)):
            raise ValueError(f"changes must hold (name, {{sensor: SD}}) pairs, got {shown(item)}")
        new = sig.copy()
        for i, v in read_mapping(item[1], "changes").items():  # read once, at most len() + 1 pairs (fuzz 42a D1)
            new[_index(i, n, "changes")] = v
        after_sd[text_of(item[0], "changes names")] = _sigmas(new, "changes", minimum=3)  # plain texts (rule 19)
    after = np.arange(K) >= change_at
    z = np.random.default_rng(seed).normal(size=(runs, K, n))
    sq: dict[str, dict[RegimeMethod, np.ndarray]] = {}
    kk = np.arange(1, K + 1)[:, None]
    for name, new in after_sd.items():
        sd = np.where(after[:, None], new, sig)
        X = z * sd
        a = wt.awf(X, "lecture", guard="abs")
        w = wt.inverse_variance_weights(np.broadcast_to(np.cumsum(sd**2, axis=0) / kk**2, X.shape))
        fused = {
            _R.AWF_AS_WRITTEN: a.value,
            _R.RUNNING_MEANS_ORACLE: np.sum(w * a.means, axis=-1),
            _R.PER_SAMPLE_FORGETTING: wt.cumulative_fusion(
                X, wt.tracking_variances(X, "centred", "forgetting", forgetting=forgetting), guard="abs"),
            _R.PER_SAMPLE_FORGETTING_ALT: wt.cumulative_fusion(
                X, wt.tracking_variances(X, "centred", "forgetting", forgetting=forgetting_alt), guard="abs"),
            _R.PER_SAMPLE_BLUE: wt.cumulative_fusion(X, np.broadcast_to(sd**2, X.shape), time_weights="precision"),
        }
        sq[name] = {m: (f[:, after] ** 2).mean(axis=1) for m, f in fused.items()}
    return VarianceChangeStudy(changes=list(after_sd), methods=list(CHANGE_METHODS), sq=sq, sd_after=after_sd,
                               variances=sig**2, runs=int(runs), samples=int(K), seed=int(seed),
                               change_at=int(change_at), forgetting=float(forgetting),
                               forgetting_alt=float(forgetting_alt))
