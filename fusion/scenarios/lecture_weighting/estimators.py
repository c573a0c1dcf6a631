r"""Lecture §2.1 (E2.1, E2.1c): the AWF's variance estimators and the weights they give.

The lecture's and the centred estimator at several levels X (:func:`awf_study`), the tail of the literal AWF's error
(:func:`tail_study`), AR(1) noise (:func:`ar1_study`), and linear-unbiased-minimum-variance on antithetic pairs with
the sign-flip symmetry behind it (:func:`lumv_study`, :func:`symmetry_study`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from enum import StrEnum

import numpy as np
from numpy.typing import ArrayLike

from fusion._results import (NONNEGATIVE, ResultSpec, array, dict_of, flag, instance, integer, number, same_keys, text,
                             tuple_of, real_key, validated_post_init)
from fusion._frozen import constant
from fusion._validation import read_once
from fusion._validation import derived_inputs
from fusion._limits import AWF_STUDY, STUDY_WORK
from fusion._validation import allocation, as_array, count, finite_result, scalar, work
from fusion._counts import input_allocation
from fusion._validation import LOOP_STEP, as_mask, distinct, distinct_printed, glue_part, loop_work
from fusion.readings import weighting as wt
from fusion.scenarios._lecture_checks import _ints, _seed, _sigmas, _values
from fusion._shown import shown

__all__ = [
    "AwfMethod",
    "ConstantLevelRuns",
    "LECTURE_GUARD_METHODS",
    "CHECKED",
    "SWEEP_LEVELS",
    "TailStudy",
    "AR1Study",
    "delete_weights",
    "tail_study",
    "ar1_study",
    "EstimatorRow",
    "AwfStudy",
    "awf_study",
    "LumvStudy",
    "lumv_study",
    "SYMMETRY_METHODS",
    "SymmetryStudy",
    "symmetry_study",
]


# --------------------------------------------------------------------------- E2.1
class AwfMethod(StrEnum):
    """Method keys of the fusions of E2.1, E2.1c and E2.3 (display labels: :data:`fusion.book.style.METHOD_LABELS`).

    Attributes
    ----------
    ORACLE
        Inverse-variance weights of the true variances.
    AWF_LECTURE_FLOOR, AWF_LECTURE_ABS, AWF_LECTURE_EQUAL, AWF_LECTURE_NONE
        The AWF on the lecture's variance estimates under each guard of
        :data:`fusion.readings.weighting.GUARDS` (``"none"``: the algorithm as written).
    AWF_LECTURE_DELETE
        The AWF on the lecture's estimates with the deletion guard (:func:`delete_weights`).
    AWF_CENTRED
        The AWF on centred variance estimates (floor guard).
    MEAN_OF_MEANS
        The mean of the sensors' running means.
    BEST_SENSOR
        The most precise sensor's running mean.
    GRAYBILL_DEAL
        Each sensor's mean weighted by its own sample variance (Graybill & Deal 1959).
    CURRENT_MEAN
        The mean of the current readings (E2.3).
    CHECK_AWF_LECTURE_FLOOR, CHECK_AWF_LECTURE_ABS, CHECK_AWF_LECTURE_EQUAL, CHECK_AWF_LECTURE_NONE, \
    CHECK_AWF_LECTURE_DELETE, CHECK_AWF_CENTRED
        The §2.3 consistency check, then the AWF of the same name on the kept sensors (E2.3; :data:`CHECKED`).
    """

    ORACLE = "oracle"
    AWF_LECTURE_FLOOR = "awf_lecture"
    AWF_LECTURE_ABS = "awf_lecture_abs"
    AWF_LECTURE_EQUAL = "awf_lecture_equal"
    AWF_LECTURE_NONE = "awf_lecture_none"
    AWF_LECTURE_DELETE = "awf_lecture_delete"
    AWF_CENTRED = "awf_centred"
    MEAN_OF_MEANS = "mean_of_means"
    BEST_SENSOR = "best_sensor"
    GRAYBILL_DEAL = "graybill_deal"
    CURRENT_MEAN = "current_mean"
    CHECK_AWF_LECTURE_FLOOR = "check_awf_lecture"
    CHECK_AWF_LECTURE_ABS = "check_awf_lecture_abs"
    CHECK_AWF_LECTURE_EQUAL = "check_awf_lecture_equal"
    CHECK_AWF_LECTURE_NONE = "check_awf_lecture_none"
    CHECK_AWF_LECTURE_DELETE = "check_awf_lecture_delete"
    CHECK_AWF_CENTRED = "check_awf_centred"


#: The lecture's AWF under each guard of :data:`fusion.readings.weighting.GUARDS` and under deletion: guard → key.
LECTURE_GUARD_METHODS: dict[str, AwfMethod] = constant({
    "floor": AwfMethod.AWF_LECTURE_FLOOR,
    "abs": AwfMethod.AWF_LECTURE_ABS,
    "equal": AwfMethod.AWF_LECTURE_EQUAL,
    "none": AwfMethod.AWF_LECTURE_NONE,
    "delete": AwfMethod.AWF_LECTURE_DELETE,
})

#: Each AWF of E2.3 → the same AWF after the §2.3 consistency check.
CHECKED: dict[AwfMethod, AwfMethod] = constant({
    AwfMethod.AWF_LECTURE_FLOOR: AwfMethod.CHECK_AWF_LECTURE_FLOOR,
    AwfMethod.AWF_LECTURE_ABS: AwfMethod.CHECK_AWF_LECTURE_ABS,
    AwfMethod.AWF_LECTURE_EQUAL: AwfMethod.CHECK_AWF_LECTURE_EQUAL,
    AwfMethod.AWF_LECTURE_NONE: AwfMethod.CHECK_AWF_LECTURE_NONE,
    AwfMethod.AWF_LECTURE_DELETE: AwfMethod.CHECK_AWF_LECTURE_DELETE,
    AwfMethod.AWF_CENTRED: AwfMethod.CHECK_AWF_CENTRED,
})

#: Levels X of the sweep of :func:`awf_study` (the verdict of §2.1 against X/σ).
SWEEP_LEVELS: tuple[float, ...] = (0.0, 1.0, 3.0, 10.0, 20.0, 30.0, 50.0, 100.0, 300.0, 900.0)


def delete_weights(estimates: ArrayLike, mask: ArrayLike | None = None) -> np.ndarray:
    r"""Inverse-variance weights with the deletion guard: a sensor whose estimate is not positive is dropped.

    :math:`W_p \propto 1/\hat\sigma_p^2` over the sensors with :math:`\hat\sigma_p^2 > 0` (and kept by
    ``mask``), 0 for the others; equal weights over the kept sensors when none is left. The guard a
    practitioner reaches for first (the lecture gives none).

    Parameters
    ----------
    estimates : array_like, shape (..., n)
        Variance estimates (may be negative).
    mask : array_like of bool, shape (..., n), optional
        Sensors kept (e.g. by the consistency check); default: all.

    Returns
    -------
    ndarray, shape (..., n)
        Weights summing to 1 over the last axis.

    Raises
    ------
    ValueError
        ``estimates`` not finite, or ``mask`` of another shape or keeping no sensor somewhere.
    TypeError
        ``mask`` not an array of bools (numbers, a ragged or self-containing list).
    """
    v = as_array(estimates, "estimates")
    if v.ndim < 1:
        raise ValueError("estimates must have a sensor axis")
    if mask is None:
        m = np.ones(v.shape, dtype=bool)
    else:
        m = as_mask(mask, "mask")  # any conversion error names mask (a ragged or self-containing list)
    if m.shape != v.shape:
        raise ValueError(f"mask must have the shape of estimates {v.shape}, got {m.shape}")
    if not np.all(m.any(axis=-1)):
        raise ValueError("mask must keep at least one sensor in every row")
    keep = m & (v > 0)
    inv = np.where(keep, 1.0 / np.where(keep, v, 1.0), 0.0)
    none_left = ~keep.any(axis=-1, keepdims=True)
    w = np.where(none_left, m.astype(float), inv)
    return w / w.sum(axis=-1, keepdims=True)



#: The fields of :class:`ConstantLevelRuns`, in the specs of the studies that extend it (after their own fields).
_CONSTANT_LEVEL = {"runs": integer(1), "k": integer(1), "x": number(nonnegative=False), "seed": integer(0),
                   "variances": array("n", bounds=NONNEGATIVE)}


@dataclass(frozen=True, kw_only=True)
class ConstantLevelRuns:
    """The settings a Monte-Carlo study of a constant level reports (keyword fields, after the study's own).

    Attributes
    ----------
    runs, k : int
        Runs and samples per run.
    x : float
        The constant level.
    seed : int
    variances : ndarray, shape (n,)
        The sensors' noise variances.
    """

    runs: int
    k: int
    x: float
    seed: int
    variances: np.ndarray

    __result_spec__ = ResultSpec(_CONSTANT_LEVEL)
    __post_init__ = validated_post_init


@dataclass(frozen=True)
class TailStudy(ConstantLevelRuns):
    r"""The tail of the literal AWF's fused error (:func:`tail_study`).

    Attributes
    ----------
    t : ndarray, shape (T,)
        The thresholds t.
    exceed : ndarray, shape (T,)
        Share of runs with :math:`|e| > t`.
    t_exceed : ndarray, shape (T,)
        t · exceed (flat in t for a :math:`1/t` tail).
    hill : float
        Hill tail index of the absolute error (from the top √runs values).
    block_mse : ndarray, shape (5,)
        The sample MSE of each of 5 disjoint blocks of runs (an infinite mean shows as block means that do
        not settle).
    median_sq : float
        Median squared error.
    runs, k : int
        Monte-Carlo runs and samples per run.
    x : float
        Constant level.
    seed : int
    variances : ndarray, shape (n,)
        The sensors' noise variances.
    """

    t: np.ndarray
    exceed: np.ndarray
    t_exceed: np.ndarray
    hill: float
    block_mse: np.ndarray
    median_sq: float

    __result_spec__ = ResultSpec(
        {"t": array("T", bounds=NONNEGATIVE), "exceed": array("T", bounds=(0.0, 1.0)),
         "t_exceed": array("T", bounds=NONNEGATIVE), "hill": number(positive=True),
         "block_mse": array(5, bounds=NONNEGATIVE), "median_sq": number(), **_CONSTANT_LEVEL})


def _chunk_loop(items: int, chunk: int, units: int, step: int) -> int:
    """Refuse a loop over ``items`` runs (or pairs) in chunks of ``chunk`` whose Python steps, ``step`` units a chunk,
    and vectorised ``units`` (the readings' work, already counted) are together beyond the work budget (rule 17),
    naming runs and chunk: ``chunk = 1`` makes one step per run."""
    n = -(-items // min(chunk, items))
    return loop_work((n,), -(-units // n), "runs, chunk, k and sigma", step=step)


@derived_inputs()
@finite_result("sigma, x and thresholds")
def tail_study(sigma: Sequence[float] = (0.5, 1.0, 2.0, 4.0), x: float = 900.0, k: int = 100,
               runs: int = 100_000, seed: int = 2109, chunk: int = 10_000,
               thresholds: Sequence[float] = (1.0, 10.0, 100.0, 1000.0)) -> TailStudy:
    r"""The tail of the literal AWF's fused error: :math:`t\,P(|e| > t)` at several t.

    The unguarded weights are :math:`W_p = \hat\sigma_p^{-2}/S` with :math:`S = \sum_q\hat\sigma_q^{-2}`. S has
    a continuous density at 0 (it changes sign when an estimate does), so :math:`P(|S| < s) \approx 2f_S(0)s`
    and :math:`e = N/S` with :math:`N = \sum_p\hat\sigma_p^{-2}(\bar X_p - x)` has
    :math:`P(|e| > t) \approx 2f_S(0)E|N|/t`: a Cauchy-type tail, so :math:`E|e|` and :math:`E e^2` are
    infinite. If the tail is :math:`\propto 1/t`, :math:`t\,P(|e| > t)` is flat in t; the function measures it.

    Parameters
    ----------
    sigma : sequence of float
        Noise SDs.
    x : float
        Constant level.
    k : int
        Samples per run (>= 2).
    runs, seed, chunk : int
        Monte-Carlo runs (drawn in chunks of ``chunk``), seed.
    thresholds : sequence of float
        The t (> 0), no two alike in their digits ``f"{t:g}"``, 10.5 and 105 included (each keys a glue value
        ``lec_tail_p_`` followed by those digits, ``fusion._counts.glue_part``: 10.5 as ``105``).

    Returns
    -------
    TailStudy
        (:func:`fusion.book.rulebook.hill_tail_index` is not imported here: the Hill estimate uses the top
        √runs values.)
    """
    sig = _sigmas(sigma, minimum=2)
    x = scalar(x, "x")
    k = count(k, "k", minimum=2)
    runs = count(runs, "runs", minimum=100)
    seed = _seed(seed)  # a plain int: numpy.random.default_rng refuses a 0-d array
    chunk = count(chunk, "chunk")
    allocation((min(chunk, runs), k, sig.size), "runs, chunk, k and sigma")
    # a chunk is the input of wt.variance_estimates, which refuses more than MAX_INPUT_ELEMENTS: refused here by the
    # same shape (fuzz 39a D1: refused inside after the first chunk's draws, naming every argument)
    input_allocation((min(chunk, runs), k, sig.size), "runs, chunk, k and sigma")
    units = work((runs, k, sig.size), "runs, k and sigma")  # rule 17: chunks bound the memory, not the time
    # and each chunk is a Python step of a few numpy calls and a validated call, 33 us measured (chunk = 1, k = 2,
    # two sensors, time.process_time, shared machine): 4 LOOP_STEP, on top of the readings' units (fuzz 39a C3:
    # chunk = 1 of 2.5e8 runs, accepted, would have run about 8,000 CPU-s)
    _chunk_loop(runs, chunk, units, 4 * LOOP_STEP)
    t = _values(thresholds, "thresholds")  # a vectorised conversion (at most MAX_INPUT_ELEMENTS entries)
    # rule 17 by the length, before any entry is printed (fuzz 64b C6: 10**7 thresholds were each printed first,
    # refused after 17.6 CPU-s by a printed repeat)
    loop_work((t.size,), runs, "thresholds and runs", step=3 * LOOP_STEP)  # rule 17: a pass over the errors
    if np.any(t <= 0):
        raise ValueError("thresholds must be positive")
    distinct_printed(t.tolist(), "thresholds", glue_part, "keys a glue value")  # lec_tail_p_* (fuzz 30b B2, 31b D4)
    rng = np.random.default_rng(seed)
    errs, done = [], 0
    while done < runs:
        m = min(chunk, runs - done)
        X = x + rng.normal(size=(m, k, sig.size)) * sig
        lec = wt.variance_estimates(X, "lecture")
        inv = 1.0 / lec
        errs.append(np.einsum("ri,ri->r", inv, X.mean(axis=1) - x) / inv.sum(axis=1))
        done += m
    e = np.abs(np.concatenate(errs))
    exceed = np.array([(e > ti).mean() for ti in t])
    top = np.sort(e)[::-1][: int(np.ceil(np.sqrt(e.size))) + 1]
    hill = float(1.0 / np.mean(np.log(top[:-1] / top[-1])))
    blocks = np.array_split(e**2, 5)
    return TailStudy(t=t, exceed=exceed, t_exceed=t * exceed, hill=hill, block_mse=np.array([b.mean() for b in blocks]),
                     median_sq=float(np.median(e**2)), runs=int(runs), k=int(k), x=float(x), seed=int(seed),
                     variances=sig**2)


@dataclass(frozen=True)
class AR1Study:
    r"""AWF under stationary AR(1) noise (:func:`ar1_study`).

    Attributes
    ----------
    c : float
        The variance factor :math:`c = 1 + 2\sum_{h=1}^{k-1}(1-h/k)\phi^h` of a running mean of k samples.
    bound : float
        :math:`\sigma^2_{\min}/k`.
    mse_oracle, mse_centred, mse_lecture_abs, mse_mean_of_means : float
        Fused MSE of the oracle weights, the AWF on centred estimates, the AWF on the lecture's estimates
        (non-positive ones as ``|σ̂²|``) and the mean of means.
    ratio_lecture, ratio_centred : ndarray, shape (n,)
        Mean variance estimate / :math:`\sigma_p^2` per sensor at k, the lecture's and the centred estimator.
    phi : float
    k, runs, seed : int
    variances : ndarray, shape (n,)
    """

    c: float
    bound: float
    mse_oracle: float
    mse_centred: float
    mse_lecture_abs: float
    mse_mean_of_means: float
    ratio_lecture: np.ndarray
    ratio_centred: np.ndarray
    phi: float
    k: int
    runs: int
    seed: int
    variances: np.ndarray

    __result_spec__ = ResultSpec(
        {"c": number(positive=True), "bound": number(positive=True), "mse_oracle": number(), "mse_centred": number(),
         "mse_lecture_abs": number(), "mse_mean_of_means": number(), "ratio_lecture": array("n"),
         "ratio_centred": array("n"), "phi": number(nonnegative=False, bounds=(-1.0, 1.0)), "k": integer(1),
         "runs": integer(1), "seed": integer(0), "variances": array("n", bounds=NONNEGATIVE)})
    __post_init__ = validated_post_init


@derived_inputs()
def ar1_study(sigma: Sequence[float] = (0.5, 1.0, 2.0, 4.0), phi: float = 0.8, k: int = 100, runs: int = 2000,
              seed: int = 2110) -> AR1Study:
    r"""AWF under stationary AR(1) (coloured) noise, which the lecture's model (zero-mean stationary noise) allows.

    Each sensor's noise is :math:`V_p(t) = \phi V_p(t-1) + \sqrt{1-\phi^2}\,\sigma_p z_p(t)`, stationary with
    variance :math:`\sigma_p^2`; X = 0. A running mean of k correlated samples has variance
    :math:`\frac{\sigma_p^2}{k}c`, :math:`c = 1 + 2\sum_{h=1}^{k-1}(1-h/k)\phi^h`, so the fused MSE of the
    oracle is :math:`c\,\sigma^2_{\min}/k`, not :math:`\sigma^2_{\min}/k`. The lecture's uncentred estimate
    :math:`R_{pp} - \bar R_p` stays unbiased at X = 0 (the cross moments of independent sensors have mean 0);
    the centred one is biased low, because the sample mean carries :math:`c/k` of the variance.

    Parameters
    ----------
    sigma : sequence of float
        Stationary noise SDs.
    phi : float
        AR coefficient, in (-1, 1).
    k, runs, seed : int
        Samples per run (>= 2), runs (>= 100), seed.

    Returns
    -------
    AR1Study
        The inflation c and bound, the MSE of the oracle, the centred and lecture AWF and the mean of means, and their
        ratios.
    """
    sig = _sigmas(sigma, minimum=2)
    phi = scalar(phi, "phi")
    if not -1.0 < phi < 1.0:
        raise ValueError(f"phi must lie in (-1, 1), got {phi}")
    k = count(k, "k", minimum=2)
    runs = count(runs, "runs", minimum=100)
    allocation((runs, k, sig.size), "runs, k and sigma")
    input_allocation((runs, k, sig.size), "runs, k and sigma")  # the readings are wt's input (fuzz 39a D1, class)
    # rule 17: about 0.13 us a reading (run x sample x sensor) measured (budget35: 1.7 CPU-s for 446,000 runs x 10 x 3);
    # without a work budget 8.9e6 runs (some 35 CPU-s) were accepted
    work((runs, k, sig.size), "runs, k and sigma", weight=15)
    seed = _seed(seed)  # a plain int: numpy.random.default_rng refuses a 0-d array
    rng = np.random.default_rng(seed)
    z = rng.normal(size=(runs, k, sig.size)) * sig
    V = np.empty_like(z)
    V[:, 0] = z[:, 0]
    a = np.sqrt(1.0 - phi**2)
    for t in range(1, k):
        V[:, t] = phi * V[:, t - 1] + a * z[:, t]
    var = sig**2
    h = np.arange(1, k)
    c = float(1.0 + 2.0 * np.sum((1.0 - h / k) * phi**h))
    means = V.mean(axis=1)
    lec = wt.variance_estimates(V, "lecture")
    cen = wt.variance_estimates(V, "centred")
    def mse(fused: np.ndarray) -> float:
        return float(np.mean(fused**2))

    return AR1Study(c=c, bound=float(wt.minimum_variance(var)) / k, mse_oracle=mse(means @ wt.optimal_weights(var)),
                    mse_centred=mse(np.einsum("ri,ri->r", wt.inverse_variance_weights(cen), means)),
                    mse_lecture_abs=mse(np.einsum("ri,ri->r", wt.inverse_variance_weights(lec, guard="abs"), means)),
                    mse_mean_of_means=mse(means.mean(axis=1)), ratio_lecture=lec.mean(axis=0) / var,
                    ratio_centred=cen.mean(axis=0) / var, phi=float(phi), k=int(k), runs=int(runs), seed=int(seed),
                    variances=var)


@dataclass(frozen=True)
class EstimatorRow:
    """One (X, estimator, k) of E2.1: the variance estimates of sensors 1 and 4 over the runs (a row of
    :attr:`AwfStudy.rows`).

    Attributes
    ----------
    X : float
        The constant level.
    estimator : str
        ``"lecture"`` or ``"centred"``.
    k : int
        Samples.
    mean_1, sd_1, mean_4, sd_4 : float
        Mean and SD over the runs of σ̂₁² and σ̂₄².
    p_negative : float
        Share of negative estimates (every sensor and run).
    """

    X: float
    estimator: str
    k: int
    mean_1: float
    sd_1: float
    mean_4: float
    sd_4: float
    p_negative: float

    __result_spec__ = ResultSpec(
        {"X": number(nonnegative=False), "estimator": text("lecture", "centred"), "k": integer(1),
         "mean_1": number(nonnegative=False), "sd_1": number(), "mean_4": number(nonnegative=False), "sd_4": number(),
         "p_negative": number(bounds=(0.0, 1.0))})
    __post_init__ = validated_post_init


def _awf_relation(values: Mapping[str, object], cls: str) -> None:
    """An :class:`AwfStudy`'s compared k: at most ``k_max``, its index within the k of ``mse``."""
    n_ks = next(iter(next(iter(values["mse"].values())).values())).size  # type: ignore[attr-defined]
    if not values["i_compare"] < n_ks:  # type: ignore[operator]
        raise ValueError(f"{cls}.i_compare must index the {n_ks} k of {cls}.mse, got {values['i_compare']}")
    if values["k_compare"] > values["k_max"]:  # type: ignore[operator]
        raise ValueError(f"{cls}.k_compare must be at most {cls}.k_max = {values['k_max']}, got {values['k_compare']}")


@dataclass(frozen=True)
class AwfStudy:
    r"""Experiment E2.1: the lecture's and the centred variance estimator at several levels X (:func:`awf_study`).

    Attributes
    ----------
    variances : ndarray, shape (n,)
    rows : tuple of EstimatorRow
        Table rows (X, estimator, k at 100 and k_max: mean and SD of σ̂₁² and σ̂₄², fraction negative).
    band : mapping
        ``band[(X, e)]``: (mean, SD) of σ̂₁² against k, shape (k_max,), for X in {0, 100}.
    ks : ndarray
        The k of ``mse``.
    k_compare, i_compare : int
        The k of ``sq`` and its index in ``ks``.
    mse : mapping
        ``mse[X][key]``: fused MSE against ``ks`` for X in {0, 900}, by :class:`AwfMethod` key: the oracle, both AWFs
        (the lecture's with the floor guard), mean of means, best sensor.
    sq : mapping
        ``sq[X][key]``: per-run squared errors at ``k_compare`` (shape (runs,)) for X in {0, 900}, including the
        lecture's AWF under every guard of :data:`fusion.readings.weighting.GUARDS` and deletion
        (:data:`LECTURE_GUARD_METHODS`, :func:`delete_weights`), and ``AwfMethod.GRAYBILL_DEAL`` (each sensor's mean
        weighted by its own sample variance over the ``k_compare`` samples, Graybill & Deal 1959).
    err : mapping
        ``err[X][key]``: the signed errors behind ``sq``.
    runs, k_max, seed : int
    sweep : mapping
        ``sweep[X][key]``: per-run squared errors at ``k_compare`` of the lecture's AWF (``|σ̂²|``, no guard) and
        the mean of means at every level of :data:`SWEEP_LEVELS`. The levels X keying ``mse``, ``sq``, ``err`` and
        ``sweep`` are finite numbers of any sign (as ``awf_study``'s ``levels``); a NaN or infinite key is refused by
        the field's name, also in a result rebuilt by ``dataclasses.replace``.
    sd_pred_900 : float
        Predicted SD of σ̂₁² at X = 900, k = 100 (:func:`fusion.readings.weighting.lecture_variance_sd`).
    mean_est, sd_est, pneg_est : mapping
        Mean, SD over runs and share of negative estimates of σ̂ₚ² at ``k_compare`` per (X, estimator), shape (n,).
    """

    variances: np.ndarray
    rows: tuple[EstimatorRow, ...]
    band: Mapping[tuple[float, str], tuple[np.ndarray, np.ndarray]]
    ks: np.ndarray
    k_compare: int
    i_compare: int
    mse: Mapping[float, Mapping[AwfMethod, np.ndarray]]
    sq: Mapping[float, Mapping[AwfMethod, np.ndarray]]
    err: Mapping[float, Mapping[AwfMethod, np.ndarray]]
    runs: int
    k_max: int
    seed: int
    sweep: Mapping[float, Mapping[AwfMethod, np.ndarray]]
    sd_pred_900: float
    mean_est: Mapping[tuple[float, str], np.ndarray]
    sd_est: Mapping[tuple[float, str], np.ndarray]
    pneg_est: Mapping[tuple[float, str], np.ndarray]

    __result_spec__ = ResultSpec(
        {"variances": array("n", bounds=NONNEGATIVE), "rows": tuple_of(instance(EstimatorRow)),
         "band": dict_of(tuple_of(array("k_max"), array("k_max", bounds=NONNEGATIVE)), key=tuple),
         "k_compare": integer(1), "i_compare": integer(0),
         "mse": dict_of(dict_of(array("ks", bounds=NONNEGATIVE)), key=float, check_key=real_key()),  # levels X
         "sq": dict_of(dict_of(array("runs", bounds=NONNEGATIVE)), key=float, check_key=real_key()),  # finite
         "err": dict_of(dict_of(array("runs")), key=float, check_key=real_key()), "runs": integer(1, dim="runs"),
         "k_max": integer(1, dim="k_max"), "seed": integer(0),
         "sweep": dict_of(dict_of(array("runs", bounds=NONNEGATIVE)), key=float, check_key=real_key()),
         "sd_pred_900": number(),
         "mean_est": dict_of(array("n"), key=tuple), "sd_est": dict_of(array("n", bounds=NONNEGATIVE), key=tuple),
         "pneg_est": dict_of(array("n", bounds=(0.0, 1.0)), key=tuple)},
        relations=(same_keys("mse", "sq", "err"), same_keys("mean_est", "sd_est", "pneg_est"),
                   lambda v, cls: _awf_relation(v, cls)))
    __post_init__ = validated_post_init


#: Units of :func:`awf_study`'s work per level, run and entry of ``ks`` (fuzz 42a C7): 3.5 and 8.4 units at 4 sensors
#: (20,000 and 100,000 entries of 100 runs), 12 at 40, 6 at 400 (20,000 entries of 10 runs), over the same call with
#: one entry (``time.process_time``, ``OPENBLAS_NUM_THREADS=1``, the least of two calls, machine shared): 12 units.
_AWF_K = 12
#: Units of one level of :func:`awf_study` beyond its draws' (a pass of ``_running_estimates``, four validated
#: ``EstimatorRow`` and a few statistics): 700-750 us a level measured at 1 run x k_max 100 x 4 sensors (200 and 800
#: levels; ``time.process_time``, ``OPENBLAS_NUM_THREADS=1``, the least of two calls, machine shared), so about twice,
#: 140 ``LOOP_STEP``, within ``MAX_WORK`` (fuzz 64b's class: a step of LOOP_STEP under the study's 7e9 let 175,000
#: levels run about 120 CPU-s, accepted).
_AWF_LEVEL = 140 * LOOP_STEP


@derived_inputs()
def awf_study(
    sigma: Sequence[float] = (0.5, 1.0, 2.0, 4.0),
    levels: Sequence[float] = (0.0, 10.0, 100.0, 900.0, 1000.0),
    k_max: int = 1000,
    runs: int = 300,
    seed: int = 2101,
    ks: Sequence[int] = (3, 5, 10, 20, 50, 100, 200, 500, 1000),
    k_compare: int = 100,
) -> AwfStudy:
    r"""Experiment E2.1: variance estimators and adaptive weighted fusion at constant levels X.

    The same noise draws (``runs x k_max x n``, standard normal times ``sigma``) are used at
    every level, so only X changes.

    Parameters
    ----------
    sigma : sequence of float, shape (n,)
        Noise SDs of the sensors (readings' unit).
    levels : sequence of float
        Constant measured values X, no two equal (the estimates are keyed by X).
    k_max, runs, seed : int
    ks : sequence of int
        Sample counts at which the fused MSE is reported (each <= k_max).
    k_compare : int
        Sample count of the per-run comparisons (one of ``ks``).

    Returns
    -------
    AwfStudy
        Per level and estimator the rows and bands of the variance estimates, and per level each method's MSE against k.

    Raises
    ------
    ValueError
        A bad argument, named; before any draw: the draws beyond the memory budget or their work at every level (25
        units a draw, measured) beyond its entry of ``fusion._limits.STUDY_WORK``, or its levels' Python steps
        (1.4 ms a level, about twice the measured) beyond ``fusion._validation.MAX_WORK``; the running means at ``ks``
        (``runs x len(ks) x n``) beyond the memory budget, or their work at two levels (12 units a run and entry of
        ``ks``, measured) beyond ``fusion._validation.MAX_WORK``.
    """
    sigma = read_once(sigma, "sigma")  # a Sequence class read once (fuzz 31a C4)
    n_sig = _sigmas(sigma, minimum=4).size
    lv = _values(levels, "levels")
    levels = levels if isinstance(levels, (list, tuple)) else lv.tolist()  # iterated below: any array-like
    k_max = count(k_max, "k_max", minimum=100)
    runs = count(runs, "runs")
    allocation((runs, k_max, n_sig), "runs, k_max and sigma")
    # rule 17: per level, 25 units a draw (run x sample x sensor), measured (budget35: 1.6 CPU-s for 2 x 2 passes of
    # 3,900 runs x 100 x 4, ~3x the 8 units counted before; 78,000 runs, ~32 CPU-s, were accepted)
    # (the reseeding sweep's 10x reading, lec-awf-estimated, counts 3e9: its entry of fusion._limits.STUDY_WORK)
    loop_work((lv.size, 2), 25 * runs * k_max * n_sig, "levels, runs, k_max and sigma", limit=STUDY_WORK[AWF_STUDY])
    loop_work((lv.size,), 0, "levels", step=_AWF_LEVEL)  # its Python steps, at MAX_WORK (fuzz 64b's class)
    # the estimates are keyed by (level, estimator); the repeats looked for after the budget by their number
    # (fix70a, fuzz 62b's class: each entry hashed before a budget that needs only their number, 2.5 CPU-s a 10**7 list)
    distinct(lv.tolist(), "levels")
    seed = _seed(seed)
    ks_chk = _ints(ks, "ks")
    if np.any(ks_chk > k_max):
        raise ValueError(f"ks must be <= k_max = {k_max}")
    # rules 9 and 17 on the length of ks (fuzz 42a C7: uncounted, ks = [100] * 200,000 of 500 runs raised a raw
    # MemoryError after 17.6 CPU-s): the running means at ks, (runs, len(ks), n), and each curve at them, at two levels
    allocation((runs, ks_chk.size, n_sig), "runs, ks and sigma")
    work((2, runs, ks_chk.size), "ks and runs", weight=_AWF_K)
    k_compare = count(k_compare, "k_compare")
    if k_compare not in ks_chk:
        raise ValueError(f"k_compare must be one of ks, got {shown(k_compare)}")
    sig = np.asarray(sigma, dtype=float)
    V = sig**2
    n = sig.size
    ks_a = ks_chk.astype(int)
    i_cmp = int(np.flatnonzero(ks_a == k_compare)[0])
    noise = np.random.default_rng(seed).normal(size=(runs, k_max, n)) * sig
    rows, band, mean_est, sd_est, pneg_est = [], {}, {}, {}, {}
    moments = {}   # both estimators and the running means from one pass per level; kept for the AWF levels below
    for X in levels:
        lecture, centred, running = wt._running_estimates(X + noise)
        if float(X) in (0.0, 900.0):
            moments[float(X)] = {"lecture": lecture, "centred": centred, "means": running}
        for e, est in (("lecture", lecture), ("centred", centred)):
            for k in (100, k_max):
                v = est[:, k - 1]
                rows.append(EstimatorRow(X=float(X), estimator=e, k=k, mean_1=float(v[:, 0].mean()),
                                         sd_1=float(v[:, 0].std()), mean_4=float(v[:, 3].mean()),
                                         sd_4=float(v[:, 3].std()), p_negative=float((v < 0).mean())))
            mean_est[float(X), e] = est[:, k_compare - 1].mean(axis=0)
            sd_est[float(X), e] = est[:, k_compare - 1].std(axis=0)
            pneg_est[float(X), e] = (est[:, k_compare - 1] < 0).mean(axis=0)
            if X in (0.0, 100.0):
                band[float(X), e] = (est[:, :, 0].mean(axis=0), est[:, :, 0].std(axis=0))
    mse: dict[float, dict[AwfMethod, np.ndarray]] = {}
    sq: dict[float, dict[AwfMethod, np.ndarray]] = {}
    err: dict[float, dict[AwfMethod, np.ndarray]] = {}
    for X in (0.0, 900.0):
        Xs = X + noise
        run = moments.get(X) or dict(zip(("lecture", "centred", "means"), wt._running_estimates(Xs)))
        means = run["means"][:, ks_a - 1]
        lec = run["lecture"][:, k_compare - 1]
        curves = {   # the AWF of wt.awf (floor guard) from those estimates
            AwfMethod.ORACLE: means @ wt.optimal_weights(V),
            AwfMethod.AWF_LECTURE_FLOOR: wt._awf_result(run["lecture"], run["means"], "floor").value[:, ks_a - 1],
            AwfMethod.AWF_CENTRED: wt._awf_result(run["centred"], run["means"], "floor").value[:, ks_a - 1],
            AwfMethod.MEAN_OF_MEANS: means.mean(axis=-1),
            AwfMethod.BEST_SENSOR: means[..., 0],
        }
        mse[X] = {name: ((v - X) ** 2).mean(axis=0) for name, v in curves.items()}
        err[X] = {name: v[:, i_cmp] - X for name, v in curves.items()}
        m_cmp = means[:, i_cmp]
        for guard in wt.GUARDS:
            w = wt.inverse_variance_weights(lec, guard=guard)
            err[X][LECTURE_GUARD_METHODS[guard]] = np.einsum("ri,ri->r", w, m_cmp) - X
        err[X][AwfMethod.AWF_LECTURE_DELETE] = np.einsum("ri,ri->r", delete_weights(lec), m_cmp) - X
        # Graybill & Deal (1959): each sensor's mean weighted by its own sample variance (the classical common mean)
        inv = 1.0 / Xs[:, :k_compare].var(axis=1, ddof=1)
        err[X][AwfMethod.GRAYBILL_DEAL] = np.einsum("ri,ri->r", inv / inv.sum(axis=1, keepdims=True), m_cmp) - X
        sq[X] = {name: e**2 for name, e in err[X].items()}
    # verdict against the level X/σ: the lecture's AWF (|σ̂²| and no guard) against the mean of means at k_compare,
    # on the same noise draws (only the first k_compare samples are needed)
    sweep: dict[float, dict[AwfMethod, np.ndarray]] = {}
    nz = noise[:, :k_compare]
    for X in SWEEP_LEVELS:
        Xs = X + nz
        lec = wt.running_variances(Xs, "lecture")[:, -1]
        m_cmp = Xs.mean(axis=1)
        sweep[float(X)] = {AwfMethod.MEAN_OF_MEANS: (m_cmp.mean(axis=-1) - X) ** 2}
        for guard in ("abs", "none"):
            w = wt.inverse_variance_weights(lec, guard=guard)
            sweep[float(X)][LECTURE_GUARD_METHODS[guard]] = (np.einsum("ri,ri->r", w, m_cmp) - X) ** 2
    return AwfStudy(variances=V, rows=rows, band=band, ks=ks_a, k_compare=k_compare, i_compare=i_cmp, mse=mse, sq=sq,
                    err=err, runs=runs, k_max=k_max, seed=seed, sweep=sweep,
                    sd_pred_900=float(wt.lecture_variance_sd(900.0, 100, V)[0]), mean_est=mean_est, sd_est=sd_est,
                    pneg_est=pneg_est)


def _lumv_errors(X: np.ndarray, x: float, w_or: np.ndarray) -> dict[AwfMethod, np.ndarray]:
    """Fused error of every reading of E2.1c for a batch of runs ``X`` (runs, k, n)."""
    means = X.mean(axis=1)
    est = {AwfMethod.ORACLE: means @ w_or}
    lec = wt.variance_estimates(X, "lecture")
    for g in wt.GUARDS:
        est[LECTURE_GUARD_METHODS[g]] = np.einsum("ri,ri->r", wt.inverse_variance_weights(lec, guard=g), means)  # type: ignore[arg-type]
    est[AwfMethod.AWF_LECTURE_DELETE] = np.einsum("ri,ri->r", delete_weights(lec), means)
    cen = wt.variance_estimates(X, "centred")
    est[AwfMethod.AWF_CENTRED] = np.einsum("ri,ri->r", wt.inverse_variance_weights(cen), means)
    return {name: v - x for name, v in est.items()}


def _lumv_relation(values: Mapping[str, object], cls: str) -> None:
    """A :class:`LumvStudy`'s runs: two per antithetic pair."""
    if values["runs"] != 2 * values["pairs"]:  # type: ignore[operator]
        raise ValueError(f"{cls}.runs must be 2 * {cls}.pairs = {2 * values['pairs']} (antithetic pairs), "  # type: ignore[operator]
                         f"got {values['runs']}")


@dataclass(frozen=True)
class LumvStudy:
    r"""Linear, unbiased, minimum variance on antithetic pairs (:func:`lumv_study`).

    Attributes
    ----------
    err : mapping of AwfMethod to ndarray
        Signed error of each run, shape (runs,), for the oracle, the lecture's AWF under every guard and deletion
        (:data:`LECTURE_GUARD_METHODS`) and the centred AWF, the draws :math:`V` first and their mirror images
        :math:`-V` after, in the same order.
    sq : mapping of AwfMethod to ndarray
        Squared errors.
    pair_mean, pair_sq : mapping of AwfMethod to ndarray
        The mean of the signed and of the squared errors of each pair, shape (pairs,).
    odd_residual : mapping of AwfMethod to float
        :math:`\max|e(V) + e(-V)|`.
    bound : float
        :math:`\sigma^2_{\min}/k`.
    variances : ndarray, shape (n,)
    x : float
    k, runs, pairs, seed : int
        Samples per run, runs, pairs (runs / 2), seed.
    """

    err: Mapping[AwfMethod, np.ndarray]
    sq: Mapping[AwfMethod, np.ndarray]
    pair_mean: Mapping[AwfMethod, np.ndarray]
    pair_sq: Mapping[AwfMethod, np.ndarray]
    odd_residual: Mapping[AwfMethod, float]
    bound: float
    variances: np.ndarray
    x: float
    k: int
    runs: int
    pairs: int
    seed: int

    __result_spec__ = ResultSpec(
        {"err": dict_of(array("runs")), "sq": dict_of(array("runs", bounds=NONNEGATIVE)),
         "pair_mean": dict_of(array("pairs")), "pair_sq": dict_of(array("pairs", bounds=NONNEGATIVE)),
         "odd_residual": dict_of(number()), "bound": number(positive=True), "variances": array("n", bounds=NONNEGATIVE),
         "x": number(nonnegative=False), "k": integer(1), "runs": integer(1, dim="runs"),
         "pairs": integer(1, dim="pairs"), "seed": integer(0)},
        relations=(same_keys("err", "sq", "pair_mean", "pair_sq", "odd_residual"),
                   lambda v, cls: _lumv_relation(v, cls)))
    __post_init__ = validated_post_init


@derived_inputs()
def lumv_study(
    sigma: Sequence[float] = (0.5, 1.0, 2.0, 4.0),
    x: float = 900.0,
    k: int = 100,
    runs: int = 20000,
    seed: int = 2107,
    chunk: int = 2500,
) -> LumvStudy:
    r"""E2.1c: is the adaptive weighted fusion unbiased and of minimum variance, under each reading of its weights?

    ``runs`` runs of ``k`` samples of the E2.1 sensors at the constant ``x``, drawn as ``runs / 2``
    antithetic pairs: noise :math:`V` and :math:`-V`. The fused value :math:`\sum_pW_p\bar X_p(k)` with
    the true variances (oracle), the lecture's estimates under every guard of
    :data:`fusion.readings.weighting.GUARDS`, and the centred estimates (floor).

    Why pairs. Centred moments are even functions of the noise, so weights computed from them are
    even and the fused error :math:`\sum_pW_p(\bar X_p - x)` is odd: :math:`e(-V) = -e(V)`, and its
    mean is exactly 0 for any noise distribution symmetric about 0 (:func:`symmetry_study`). The
    pair mean :math:`\frac12(e(V) + e(-V))` has the same expectation as :math:`e(V)` (the bias) and
    no odd part, so it estimates the bias of any reading with far less noise. Every test is run on
    the pairs (independent), not on the runs (correlated within a pair). Computed in chunks of
    ``chunk`` pairs (memory).

    Parameters
    ----------
    sigma : sequence of float
        Noise SDs of the sensors.
    x : float
        The constant measured value.
    k : int
        Samples per run (>= 2).
    runs : int
        Number of runs, even (``runs / 2`` antithetic pairs, at least 2 pairs).
    seed : int
    chunk : int
        Pairs per chunk.

    Returns
    -------
    LumvStudy
        Per weighting the errors of the antithetic pairs, their means and squares, the odd residual and the variance
        bound.
    """
    sig = _sigmas(sigma, minimum=2)
    x = scalar(x, "x")
    k = count(k, "k", minimum=2)
    runs = count(runs, "runs", minimum=4)
    if runs % 2:
        raise ValueError(f"runs must be even (antithetic pairs), got {runs}")
    seed = _seed(seed)
    chunk = count(chunk, "chunk")
    allocation((min(chunk, runs // 2), k, sig.size), "runs, chunk, k and sigma")
    # rule 17: chunks bound the memory, not the time; a reading weighs 12 units, measured (budget35: ~0.12 us;
    # k = 10**7 of 6 runs, ~22 CPU-s, was accepted at 1 unit)
    units = work((runs, k, sig.size), "runs, k and sigma", weight=12)
    input_allocation((min(chunk, runs // 2), k, sig.size), "runs, chunk, k and sigma")  # wt.variance_estimates' input
    # each chunk of pairs is a Python step of two passes of _lumv_errors (some twenty numpy calls and validated
    # calls), 480 us measured (chunk = 1, k = 2, two sensors, time.process_time, shared machine): 50 LOOP_STEP, on
    # top of the readings' units (fuzz 39a C3: chunk = 1 of 2e7 runs, accepted, would have run about 4,800 CPU-s)
    _chunk_loop(runs // 2, chunk, units, 50 * LOOP_STEP)
    V = sig**2
    w_or = wt.optimal_weights(V)
    rng = np.random.default_rng(seed)
    plus: dict[AwfMethod, list[np.ndarray]] = {}
    minus: dict[AwfMethod, list[np.ndarray]] = {}
    pairs, done = runs // 2, 0
    while done < pairs:
        m = min(chunk, pairs - done)
        noise = rng.normal(size=(m, k, sig.size)) * sig
        for store, sign in ((plus, 1.0), (minus, -1.0)):
            for name, e in _lumv_errors(x + sign * noise, float(x), w_or).items():
                store.setdefault(name, []).append(e)
        done += m
    ep = {name: np.concatenate(v) for name, v in plus.items()}
    em = {name: np.concatenate(v) for name, v in minus.items()}
    err = {name: np.concatenate([ep[name], em[name]]) for name in ep}
    return LumvStudy(err=err, sq={name: e**2 for name, e in err.items()},
                     pair_mean={name: 0.5 * (ep[name] + em[name]) for name in ep},
                     pair_sq={name: 0.5 * (ep[name] ** 2 + em[name] ** 2) for name in ep},
                     odd_residual={name: float(np.max(np.abs(ep[name] + em[name]))) for name in ep},
                     bound=float(wt.minimum_variance(V)) / k, variances=V, x=float(x), k=int(k), runs=int(runs),
                     pairs=int(pairs), seed=int(seed))


#: The fusions of :func:`symmetry_study`: (method key, kind, estimator, guard). The kind is the dispatch key of
#: the fusion run: ``"oracle"``, ``"awf"`` (AWF at the level ``x``), ``"awf0"`` (AWF at X = 0), ``"ls"``
#: (LS learning) or ``"lsc"`` (corrected learning). Display labels: :data:`fusion.book.style.METHOD_LABELS`.
SYMMETRY_METHODS: tuple[tuple[str, str, str, str], ...] = (
    ("lec_sym_oracle", "oracle", "", ""),
    ("lec_sym_awf_centred_floor", "awf", "centred", "floor"),
    ("lec_sym_awf_centred_abs", "awf", "centred", "abs"),
    ("lec_sym_awf_centred_equal", "awf", "centred", "equal"),
    ("lec_sym_awf_lecture_abs_x0", "awf0", "lecture", "abs"),
    ("lec_sym_awf_lecture_abs", "awf", "lecture", "abs"),
    ("lec_sym_awf_lecture_floor", "awf", "lecture", "floor"),
    ("lec_sym_ls_learning", "ls", "", ""),
    ("lec_sym_ls_corrected", "lsc", "", ""),
)


@dataclass(frozen=True)
class SymmetryStudy(ConstantLevelRuns):
    r"""The sign-flip check of :func:`symmetry_study`, by method key (:data:`SYMMETRY_METHODS`).

    Attributes
    ----------
    methods : tuple of str
        The method keys, in the order of :data:`SYMMETRY_METHODS`.
    residual : mapping of str to float
        :math:`\max|e(V) + e(-V)|` over the runs.
    scale : mapping of str to float
        :math:`\max|e(V)|` over the runs.
    even : mapping of str to bool
        Whether the residual is round-off, at most :math:`10^{-6}` of the scale (the centred moments at a level
        :math:`X` cancel :math:`X^2`-sized terms, so their round-off is about :math:`10^{-16}X^2/\sigma^2`
        relative, ~10⁻⁹ of the scale at 900 °C).
    runs, k : int
        Runs and samples (epochs) per run.
    x : float
        The constant measured value.
    seed : int
    variances : ndarray, shape (n,)
    """

    methods: tuple[str, ...]
    residual: Mapping[str, float]
    scale: Mapping[str, float]
    even: Mapping[str, bool]

    __result_spec__ = ResultSpec(
        {"methods": tuple_of(text()), "residual": dict_of(number()), "scale": dict_of(number()),
         "even": dict_of(flag()), **_CONSTANT_LEVEL},
        relations=(same_keys("methods", "residual", "scale", "even"),))


@derived_inputs()
def symmetry_study(
    sigma: Sequence[float] = (0.5, 1.0, 2.0, 4.0),
    x: float = 900.0,
    k: int = 100,
    runs: int = 200,
    seed: int = 2108,
) -> SymmetryStudy:
    r"""The sign-flip symmetry behind the unbiasedness of the weighted fusions of secs. 2.1-2.2.

    Proposition. If the weights are even functions of the noise, :math:`W(-V) = W(V)`, and sum to
    one, the fused error :math:`e(V) = \sum_pW_p(V)\,\bar V_p` is odd, :math:`e(-V) = -e(V)`; for
    noise whose distribution is symmetric about 0 (e.g. normal) :math:`V` and :math:`-V` are equally
    likely, so :math:`E[e] = 0` whenever it exists (bounded weights). Centred moments
    :math:`C_{pq} = \overline{V_pV_q} - \bar V_p\bar V_q` and the allocations
    :math:`(y_i - \bar y)^2` of sec. 2.2 are even, hence so is any guard or correction applied to them. The
    lecture's uncentred moments are even only at :math:`X = 0`: at a level :math:`X` they contain
    :math:`X\,\overline{(V_p - \bar V_{-p})}`, which is odd.

    This study checks the identity :math:`e(V) + e(-V) = 0` run by run.

    Parameters
    ----------
    sigma : sequence of float
        Noise SDs of the sensors (n >= 3, for the corrected learning).
    x : float
        The constant measured value (the "X = 0" row uses 0).
    k : int
        Samples (epochs) per run (>= 2).
    runs, seed : int

    Returns
    -------
    SymmetryStudy
        Per method key the largest ``|e(V) + e(−V)|`` over the runs (``residual``), the largest ``|e(V)|`` and whether
        the residual is round-off.
    """
    sig = _sigmas(sigma, minimum=3)
    x = scalar(x, "x")
    k = count(k, "k", minimum=2)
    runs = count(runs, "runs")
    allocation((runs, k, sig.size), "runs, k and sigma")
    # rule 17: every method of SYMMETRY_METHODS on V and -V, about 2.4 us a reading (run x sample x sensor) measured
    # (budget35: 3.2 CPU-s for 44,000 runs x 10 x 3); without a budget 8.8e6 runs (some 640 CPU-s) were accepted
    work((runs, k, sig.size), "runs, k and sigma", weight=250)
    seed = _seed(seed)
    noise = np.random.default_rng(seed).normal(size=(runs, k, sig.size)) * sig
    w_or = wt.optimal_weights(sig**2)

    def err(kind: str, est: str, guard: str, V: np.ndarray) -> np.ndarray:
        if kind == "oracle":
            return V.mean(axis=1) @ w_or
        if kind in ("ls", "lsc"):
            return wt.ls_learning(float(x) + V, corrected=kind == "lsc").values[:, -1] - float(x)
        level = 0.0 if kind == "awf0" else float(x)
        return wt.awf(level + V, est, guard=guard).value[:, -1] - level  # type: ignore[arg-type]

    residual, scale, even = {}, {}, {}
    for key, kind, est, guard in SYMMETRY_METHODS:
        ep, em = err(kind, est, guard, noise), err(kind, est, guard, -noise)
        residual[key] = float(np.max(np.abs(ep + em)))
        scale[key] = float(np.max(np.abs(ep)))
        even[key] = bool(residual[key] <= 1e-6 * scale[key])
    return SymmetryStudy(methods=tuple(m[0] for m in SYMMETRY_METHODS), residual=residual, scale=scale, even=even,
                         runs=int(runs), k=int(k), x=float(x), seed=int(seed), variances=sig**2)
