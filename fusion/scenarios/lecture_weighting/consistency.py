r"""Lecture §2.3 (E2.3): the consistency check + AWF with a faulty sensor, and the detection curve."""

from __future__ import annotations

from dataclasses import dataclass
from collections.abc import Mapping, Sequence
from enum import StrEnum
from typing import Any
import numpy as np
from numpy.typing import ArrayLike

from fusion._results import (NONNEGATIVE, ResultSpec, array, dict_of, instance, integer, mask, number, same_keys, text,
                             tuple_of, validated_post_init)
from fusion._validation import read_once
from fusion._validation import derived_inputs
from fusion._validation import allocation, count, one_of, scalar, window as check_window, work
from fusion.readings import consistency as cs
from fusion.readings import weighting as wt
from fusion.scenarios._lecture_checks import _index, _seed, _sigmas
from fusion._shown import shown
from fusion.scenarios.lecture_weighting.estimators import CHECKED, LECTURE_GUARD_METHODS, AwfMethod, delete_weights

__all__ = [
    "FaultCase",
    "FaultDiagnostics",
    "ConsistencyStudy",
    "INDEX_ORDERS",
    "CC_GUARDS",
    "consistency_study",
]


# --------------------------------------------------------------------------- E2.3
class FaultCase(StrEnum):
    """Keys of E2.3's two data sets (:class:`ConsistencyStudy`; labels: :data:`fusion.book.style.METHOD_LABELS`).

    Attributes
    ----------
    NONE
        Every sensor healthy.
    FAULT
        The same readings with the bias added to the faulty sensor over the window.
    """

    NONE = "lec_no_fault"
    FAULT = "lec_fault"


#: Sensor numberings (0-based permutations of five sensors) under which the index-order reading of the
#: §2.3 check is run: as given (the faulty sensor third), the faulty sensor first, last, and reversed.
INDEX_ORDERS: tuple[tuple[int, ...], ...] = ((0, 1, 2, 3, 4), (2, 0, 1, 3, 4), (0, 1, 3, 4, 2), (4, 3, 2, 1, 0))

#: Bias-to-threshold ratios of the detection curve of :func:`consistency_study` (0 to 2).
_CURVE_RATIOS = 41

#: Guards of the lecture's AWF run in :func:`consistency_study` (:data:`fusion.readings.weighting.GUARDS`), in the
#: order of its results (method keys: :data:`fusion.scenarios.lecture_weighting.estimators.LECTURE_GUARD_METHODS`).
CC_GUARDS: tuple[str, ...] = ("none", "floor", "abs", "equal")


def _literal_check_awf(data: ArrayLike, eps: float, adjacent: str = "sorted") -> np.ndarray:
    r"""Check + the lecture's AWF with its estimates inverted as they are, NaN where the weights are undefined.

    :func:`fusion.readings.consistency.consistency_awf` with ``guard="none"`` refuses a whole batch when one
    estimate is exactly zero (the literal weights :math:`\hat\sigma_p^{-2}/\sum_q\hat\sigma_q^{-2}` are then
    undefined). An experiment must still judge the runs: here the fused value is NaN at exactly the instants
    where a kept sensor's estimate is zero or the kept inverse estimates sum to zero, and the literal value
    elsewhere (identical to the package's where it is defined; a rejected sensor never enters the weights).
    The callers give such a run an infinite error (rule R3 judges a mean with an infinite run as infinite).

    Parameters
    ----------
    data : array_like, shape (runs, K, n)
        Readings.
    eps : float
        Consistency threshold.
    adjacent : {"sorted", "index"}
        Meaning of "adjacent" in the check.

    Returns
    -------
    ndarray, shape (runs, K)
        Fused values, NaN where the literal weights are undefined.
    """
    # the estimates, the mask and the running means do not depend on the guard
    r = cs.consistency_awf(data, eps, "lecture", guard="floor", adjacent=adjacent)  # type: ignore[arg-type]
    var, kept, means = r.awf.variances, r.mask, r.awf.means
    mf = kept.astype(float)
    undefined = np.any(kept & (var == 0.0), axis=-1)
    with np.errstate(divide="ignore", invalid="ignore"):
        # the package's arithmetic (wt.inverse_variance_weights(var, guard="none") * mf, renormalised), with the
        # zero placeholder of a sensor that has no estimate yet (never kept with another) left out of the inverse
        inv = np.where(var != 0.0, 1.0 / np.where(var != 0.0, var, 1.0), 0.0)
        tot = inv.sum(axis=-1, keepdims=True)
        w = inv / tot * mf
        wsum = w.sum(axis=-1, keepdims=True)
        undefined |= (tot[..., 0] == 0.0) | (wsum[..., 0] == 0.0) | ~np.all(np.isfinite(w), axis=-1)
        value = np.einsum("...i,...i->...", w / wsum, means)
    return np.where(undefined, np.nan, value)


def _window_mse(v: np.ndarray, x: float, win: slice) -> np.ndarray:
    """Per-run MSE over ``win``; +inf for a run whose fused value is undefined (NaN) at an instant of the window."""
    m = np.mean((v[:, win] - x) ** 2, axis=1)
    return np.where(np.isnan(m), np.inf, m)


@dataclass(frozen=True)
class FaultDiagnostics:
    r"""Why the lecture's AWF fails over the fault window of E2.3, for one case (with or without the fault).

    Attributes
    ----------
    p_all_healthy_negative : float
        Fraction of instants at which every healthy sensor's (lecture) variance estimate is negative.
    weight_faulty : float
        Mean weight of the faulty sensor (floor guard).
    mse_healthy_mean_of_means : float
        MSE of the plain mean of the healthy sensors' running means (what the floored weights reduce to when all
        healthy estimates are negative).
    abs_weight_faulty : float
        Mean weight of the faulty sensor with ``|σ̂²|``.
    abs_weights_healthy : ndarray, shape (n - 1,)
        Mean weight of each healthy sensor with ``|σ̂²|``.
    abs_var_faulty, abs_var_healthy : float
        The mean estimate of the faulty sensor and the mean ``|σ̂²|`` of the healthy ones.
    abs_mse_faulty_term : float
        MSE of the faulty sensor's term :math:`W_3(\bar X_3 - X)` with ``|σ̂²|``.
    abs_mse : float
        The total MSE with ``|σ̂²|``.
    """

    p_all_healthy_negative: float
    weight_faulty: float
    mse_healthy_mean_of_means: float
    abs_weight_faulty: float
    abs_weights_healthy: np.ndarray
    abs_var_faulty: float
    abs_var_healthy: float
    abs_mse_faulty_term: float
    abs_mse: float

    __result_spec__ = ResultSpec(
        {"p_all_healthy_negative": number(bounds=(0.0, 1.0)), "weight_faulty": number(bounds=(0.0, 1.0)),
         "mse_healthy_mean_of_means": number(), "abs_weight_faulty": number(bounds=(0.0, 1.0)),
         "abs_weights_healthy": array("healthy", bounds=(0.0, 1.0)), "abs_var_faulty": number(nonnegative=False),
         "abs_var_healthy": number(), "abs_mse_faulty_term": number(), "abs_mse": number()})
    __post_init__ = validated_post_init


def _consistency_relation(values: Mapping[str, Any], cls: str) -> None:
    """A :class:`ConsistencyStudy`: its window within the samples, one fused series per (case, method) and one MSE per
    method of ``names`` in each case."""
    n = next(iter(values["mask"].values())).shape[-1]
    if values["fault_sensor"] >= n:
        raise ValueError(f"{cls}.fault_sensor must be a sensor of the study's {n}, got {values['fault_sensor']}")
    first, stop = values["window"]
    if not first < stop <= values["samples"]:
        raise ValueError(f"{cls}.window must be (start, stop) with 0 <= start < stop <= {cls}.samples = "
                         f"{values['samples']}, got {shown((first, stop))}")
    names = set(values["names"])
    for case, by_name in values["sq"].items():
        if set(by_name) != names:
            raise ValueError(f"{cls}.sq[{shown(case)}] must hold the methods of {cls}.names, got "
                             f"{shown(sorted(map(str, by_name)), 200)}")
    want = {(case, name) for case in values["sq"] for name in names}
    if set(values["out"]) != want:
        raise ValueError(f"{cls}.out must hold one series per (case, method) of {cls}.sq and {cls}.names, got "
                         f"{len(values['out'])} keys for {len(want)}")


@dataclass(frozen=True)
class ConsistencyStudy:
    r"""Experiment E2.3: consistency check + AWF with a fault on one sensor (:func:`consistency_study`).

    Attributes
    ----------
    eps : float
        The threshold :math:`\varepsilon = 3\sqrt2\,\sigma_{\max}`.
    bias, x : float
        Fault bias and true value (°C).
    window : tuple of int
        The faulty samples (0-based slice bounds).
    out : dict
        ``(case, key)`` → fused values (runs, samples) for each :class:`FaultCase` and the method keys of
        ``names`` (the lecture's AWF and check + AWF under every guard of :data:`CC_GUARDS`, the centred ones with
        the floor).
    mask : dict of FaultCase to ndarray
        ``mask[case]``, shape (runs, samples, n): the readings the check kept (lecture estimator).
    names : list of AwfMethod
        The fusions run (display labels: :data:`fusion.book.style.METHOD_LABELS`).
    sq : dict
        ``sq[case][key]``: per-run MSE over the window, shape (runs,).
    p_excl_fault, p_excl_clean, p_excl_any_clean : float
        Shares of exclusion of the faulty sensor during the fault, of it without the fault, of any sensor
        without the fault.
    ratio, pdet : ndarray
        Bias/ε grid and the detection curve (:func:`fusion.readings.consistency.rejection_probability`).
    diag : dict of FaultCase to FaultDiagnostics
        ``diag[case]``: the lecture's AWF over the window, with the floor and with ``|σ̂²|``.
    runs, samples, seed : int
    index_order : dict
        ``index_order[numbering][case]``: for each numbering (a permutation of :data:`INDEX_ORDERS`), the per-run MSE over the window of the check (lecture estimator, guard
        ``index_guard``) with "adjacent" read as the sensors' index order, for each numbering of
        :data:`INDEX_ORDERS` that fits the number of sensors (empty when none fits).
    index_guard : str
    fault_sensor : int
        The faulty sensor (0-based; :func:`consistency_study`'s ``fault_sensor``, 2 by default): the figure and
        table name it (fuzz 26d F2: they said "sensor 3" whichever sensor was faulty).
    """

    eps: float
    bias: float
    x: float
    window: tuple[int, int]
    out: Mapping[tuple[FaultCase, AwfMethod], np.ndarray]
    mask: Mapping[FaultCase, np.ndarray]
    names: tuple[AwfMethod, ...]
    sq: Mapping[FaultCase, Mapping[AwfMethod, np.ndarray]]
    p_excl_fault: float
    p_excl_clean: float
    p_excl_any_clean: float
    ratio: np.ndarray
    pdet: np.ndarray
    diag: Mapping[FaultCase, FaultDiagnostics]
    runs: int
    samples: int
    seed: int
    index_order: Mapping[tuple[int, ...], Mapping[FaultCase, np.ndarray]]
    index_guard: str
    fault_sensor: int = 2

    __result_spec__ = ResultSpec(
        {"eps": number(positive=True), "bias": number(nonnegative=False), "x": number(nonnegative=False),
         "window": tuple_of(integer(0), integer(0)), "out": dict_of(array("runs", "samples"), key=tuple),
         "mask": dict_of(mask("runs", "samples", "n")), "names": tuple_of(instance(AwfMethod)),
         "sq": dict_of(dict_of(array("runs", bounds=NONNEGATIVE))), "p_excl_fault": number(bounds=(0.0, 1.0)),
         "p_excl_clean": number(bounds=(0.0, 1.0)), "p_excl_any_clean": number(bounds=(0.0, 1.0)),
         "ratio": array("R", bounds=NONNEGATIVE), "pdet": array("R", bounds=(0.0, 1.0)),
         "diag": dict_of(instance(FaultDiagnostics)),
         "runs": integer(1, dim="runs"), "samples": integer(1, dim="samples"), "seed": integer(0),
         "index_order": dict_of(dict_of(array("runs", bounds=NONNEGATIVE)), key=tuple, nonempty=False),
         "index_guard": text(), "fault_sensor": integer(0)},
        relations=(same_keys("mask", "sq", "diag"), lambda v, cls: _consistency_relation(v, cls)))
    __post_init__ = validated_post_init


def _consistency_work(runs: int, samples: int, n: int, curve_draws: int, names: str) -> int:
    """Rule 17 of :func:`consistency_study` on checked counts (its check, unchanged): the pair-checks of every pass
    and of the detection curve at 2 units each, naming ``names``; its units (a chapter reader that runs several
    studies sums them, fuzz 62a)."""
    passes = 2 * (15 + sum(sorted(p) == list(range(n)) for p in INDEX_ORDERS))
    return work((runs * samples * passes + curve_draws * _CURVE_RATIOS, n, n), names, weight=2)


@derived_inputs()
def consistency_study(
    sigma: Sequence[float] = (0.5, 1.0, 1.5, 2.0, 4.0),
    samples: int = 100,
    runs: int = 100,
    x: float = 900.0,
    bias: float = 30.0,
    fault_sensor: int = 2,
    window: tuple[int, int] = (49, 80),
    seed: int = 2301,
    seed_curve: int = 2302,
    curve_draws: int = 20000,
    index_guard: str = "none",
) -> ConsistencyStudy:
    r"""Experiment E2.3: consistency check + AWF, with a fault on one sensor.

    Threshold :math:`\varepsilon = 3\sqrt2\,\sigma_{\max}`. The fault adds ``bias`` to sensor
    ``fault_sensor`` (0-based) on samples ``window`` (0-based slice bounds).

    Parameters
    ----------
    sigma : sequence of float
        Noise standard deviation of each sensor (°C).
    samples, runs : int
        Instants per run and Monte-Carlo runs.
    x : float
        True value (°C).
    bias : float
        Fault bias (°C).
    fault_sensor : int
        Faulty sensor (0-based).
    window : (int, int)
        Fault samples, as 0-based slice bounds.
    seed, seed_curve : int
        Seeds of the runs and of the detection curve.
    curve_draws : int
        Draws per point of the detection curve.
    index_guard : {"none", "floor", "abs", "equal"}
        Guard of the lecture's AWF in the index-order readings of the check.

    Returns
    -------
    ConsistencyStudy
        Each method's outputs and squared errors with and without the fault, exclusion rates, and the detection curve
        against bias/ε.
    """
    sigma = read_once(sigma, "sigma")  # a Sequence class read once (fuzz 31a C4)
    sig_chk = _sigmas(sigma, minimum=3)
    if sig_chk.max() <= 0:
        raise ValueError("sigma must have a positive entry")
    samples = count(samples, "samples")
    runs = count(runs, "runs")
    allocation((runs, samples, sig_chk.size), "runs, samples and sigma")
    x = scalar(x, "x")
    bias = scalar(bias, "bias")
    fault_sensor = _index(fault_sensor, sig_chk.size, "fault_sensor")
    window = check_window(window, "window", samples)  # not reversed, not empty (issue 35, class 4)
    seed = _seed(seed)
    seed_curve = _seed(seed_curve, "seed_curve")
    curve_draws = count(curve_draws, "curve_draws")
    allocation((curve_draws, sig_chk.size), "curve_draws and sigma")
    # rule 17: every pass below checks each pair of sensors at every sample of every run: two data sets, each run
    # through 15 estimators and diagnostics and one checked AWF per sensor order; the detection curve checks every
    # pair of each draw at each of its ratios; a pair-check weighs 2 units, measured (budget35: 103,000 runs, about
    # 23 CPU-s, were accepted at 1 unit)
    _consistency_work(runs, samples, sig_chk.size, curve_draws, "runs, samples, curve_draws and sigma")
    index_guard = one_of(index_guard, CC_GUARDS, "index_guard")
    sig = np.asarray(sigma, dtype=float)
    eps = 3 * np.sqrt(2) * sig.max()
    clean = x + np.random.default_rng(seed).normal(size=(runs, samples, sig.size)) * sig
    fault = clean.copy()
    win = slice(*window)
    fault[:, win, fault_sensor] += bias
    out: dict[tuple[FaultCase, AwfMethod], np.ndarray] = {}
    mask: dict[FaultCase, np.ndarray] = {}
    dele, cen = AwfMethod.AWF_LECTURE_DELETE, AwfMethod.AWF_CENTRED
    for case, data in ((FaultCase.NONE, clean), (FaultCase.FAULT, fault)):
        out[case, AwfMethod.CURRENT_MEAN] = data.mean(axis=-1)
        out[case, AwfMethod.MEAN_OF_MEANS] = wt.running_means(data).mean(axis=-1)
        for g in CC_GUARDS:
            r_g = wt.awf(data, "lecture", guard=g)  # type: ignore[arg-type]
            out[case, LECTURE_GUARD_METHODS[g]] = r_g.value
            checked = cs.consistency_awf(data, eps, "lecture", guard="floor" if g == "none" else g)  # type: ignore[arg-type]
            out[case, CHECKED[LECTURE_GUARD_METHODS[g]]] = (_literal_check_awf(data, eps) if g == "none"
                                                             else checked.awf.value)
        mask[case] = checked.mask
        # deletion: the raw estimates and running means are the same under every guard (those of the last one)
        out[case, dele] = np.einsum("...i,...i->...", delete_weights(r_g.variances), r_g.means)
        c_del = checked.awf
        out[case, CHECKED[dele]] = np.einsum(
            "...i,...i->...", delete_weights(c_del.variances, checked.mask), c_del.means)
        out[case, cen] = wt.awf(data, "centred").value
        out[case, CHECKED[cen]] = cs.consistency_awf(data, eps, "centred").awf.value
    healthy = np.arange(sig.size) != fault_sensor
    diag = {}
    for case, data in ((FaultCase.NONE, clean), (FaultCase.FAULT, fault)):
        r = wt.awf(data, "lecture")
        ra = wt.awf(data, "lecture", guard="abs")
        va = ra.variances[:, win]
        part = ra.weights[:, win, fault_sensor] * (ra.means[:, win, fault_sensor] - x)
        diag[case] = FaultDiagnostics(
            p_all_healthy_negative=float(np.all(r.variances[:, win][..., healthy] < 0, axis=-1).mean()),
            weight_faulty=float(r.weights[:, win, fault_sensor].mean()),
            mse_healthy_mean_of_means=float(np.mean((r.means[:, win][..., healthy].mean(axis=-1) - x) ** 2)),
            abs_weight_faulty=float(ra.weights[:, win, fault_sensor].mean()),
            abs_weights_healthy=ra.weights[:, win][..., healthy].mean(axis=(0, 1)),
            abs_var_faulty=float(va[..., fault_sensor].mean()),
            abs_var_healthy=float(np.abs(va[..., healthy]).mean()),
            abs_mse_faulty_term=float(np.mean(part**2)),
            abs_mse=float(np.mean((ra.value[:, win] - x) ** 2)),
        )
    names = [AwfMethod.CURRENT_MEAN, AwfMethod.MEAN_OF_MEANS]
    names += [m for g in CC_GUARDS for m in (LECTURE_GUARD_METHODS[g], CHECKED[LECTURE_GUARD_METHODS[g]])]
    names += [cen, CHECKED[cen], dele, CHECKED[dele]]
    sq = {lab: {nm: _window_mse(out[lab, nm], x, win) for nm in names} for lab in FaultCase}
    # "adjacent" read as the sensors' index order: the check then depends on how the sensors are numbered
    index_order: dict[tuple[int, ...], dict[FaultCase, np.ndarray]] = {}
    for perm in INDEX_ORDERS:
        if sorted(perm) != list(range(sig.size)):
            continue
        index_order[tuple(perm)] = {
            lab: _window_mse(_literal_check_awf(data[..., list(perm)], eps, "index") if index_guard == "none" else
                             cs.consistency_awf(data[..., list(perm)], eps, "lecture", guard=index_guard,  # type: ignore[arg-type]
                                                adjacent="index").awf.value, x, win)
            for lab, data in ((FaultCase.NONE, clean), (FaultCase.FAULT, fault))}
    ratio = np.linspace(0, 2, _CURVE_RATIOS)
    snap = x + np.random.default_rng(seed_curve).normal(size=(curve_draws, sig.size)) * sig
    pdet = cs.rejection_probability(snap, fault_sensor, ratio * eps, eps)
    return ConsistencyStudy(eps=float(eps), bias=bias, x=x, window=window, out=out, names=names, sq=sq,
                            mask=mask, p_excl_fault=float(1 - mask[FaultCase.FAULT][:, win, fault_sensor].mean()),
                            p_excl_clean=float(1 - mask[FaultCase.NONE][..., fault_sensor].mean()),
                            p_excl_any_clean=float(1 - mask[FaultCase.NONE].mean()),
                            ratio=ratio, pdet=pdet, diag=diag, runs=runs, samples=samples, seed=seed,
                            index_order=index_order, index_guard=index_guard, fault_sensor=int(fault_sensor))
