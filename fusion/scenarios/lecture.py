r"""The experiments of the lecture chapter (lecture notes, §2.1-2.7) and its benchmark.

The lecture publishes no data: every scenario here is the book's own design (see the chapter
and the design note). Each study takes its seed(s) as arguments with the chapter's defaults, so
the chapter's numbers follow from one call. Results are plain dictionaries of NumPy arrays
(and, for tables, of Python floats) keyed as documented in each function.

The studies:

* :func:`awf_study` — E2.1: the lecture's and the centred variance estimator at several levels X;
  fused MSE against k; AWF under every variance guard.
* :func:`lumv_study`, :func:`symmetry_study` — E2.1c: linear, unbiased, minimum variance under each reading
  of the weights, on antithetic pairs; the sign-flip symmetry that makes even weights unbiased.
* :func:`variance_change_study` — E2.1b in the lecture's setting: a constant X and one change of the noise
  SDs (a swap, one sensor degrading, one improving).
* :func:`regime_study` — E2.1b: the estimators in the regime they are for (a time-varying X, a change
  of the sensor variances): growing memory (the lecture) against forgetting and a sliding window, and
  against each sensor's own sample variance.
* :func:`learning_study` — E2.2: variance learning of sec. 2.2, its limit, learned and corrected weights.
* :func:`consistency_study` — E2.3: consistency check + AWF with a faulty sensor, and the detection curve.
* :func:`belief_parameter_study` — E2.4b: how much the fused value depends on the analyst's parameter,
  fuzzy belief scale against binary threshold.
* :func:`belief_study` — E2.4: belief-degree weights against a shift, in three units, against row sums.
* :func:`ridge_study` — E2.5: scalar ridge against least squares, convergence, centralised vs distributed.
* :func:`wavelet_study` — E2.6: wavelet denoising + normalised fusion with three normalisers.
* :func:`correlated_study` — E2.7: LDLᵀ pseudo-measurements against GLS and the naive fusion; operation counts.
* :func:`benchmark`, :func:`seed_stability` — every readings-level method on one shared setup, over seeds.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from numpy.typing import ArrayLike

from fusion import readings as rd
from fusion._validation import as_array, count, one_of, scalar, sequence, window as check_window
from fusion._validation import allocation, counts as check_counts, instance_of, record, seed as V_seed, seeds as check_seeds
from fusion._validation import MAX_MAGNITUDE, MIN_MAGNITUDE, seed as check_seed
from fusion.readings import biased as rg
from fusion.readings import consistency as cs
from fusion.readings import correlated as co
from fusion.readings import wavelet as wv
from fusion.readings import weighting as wt
from fusion.readings.robust import robust_fuse

__all__ = [
    "delete_weights",
    "tail_study",
    "ar1_study",
    "INDEX_ORDERS",
    "CC_GUARDS",
    "awf_study",
    "lumv_study",
    "SYMMETRY_METHODS",
    "symmetry_study",
    "REGIME_SCENARIOS",
    "REGIME_METHODS",
    "REGIME_CONSTANT_ONLY",
    "regime_study",
    "VARIANCE_CHANGES",
    "CHANGE_METHODS",
    "variance_change_study",
    "learning_study",
    "learned_limit_check",
    "consistency_study",
    "belief_study",
    "belief_parameter_study",
    "BELIEF_KINDS",
    "DELETION_SUPPORT",
    "belief_spread",
    "ridge_study",
    "wavelet_study",
    "correlated_study",
    "BENCH_SIGMA",
    "benchmark",
    "seed_stability",
]


def _sigmas(sigma: ArrayLike, name: str = "sigma", minimum: int = 2) -> np.ndarray:
    r"""``sigma`` as a finite 1-D array of >= ``minimum`` positive noise SDs (ValueError naming it).

    Positive: every study weights its sensors by :math:`1/\sigma_i^2` (a zero SD has no weight).
    """
    sig = as_array(sigma, name, ndim=1)
    if np.any(sig <= 0):
        raise ValueError(f"{name} must hold positive noise SDs, got {sig.tolist()}")
    if sig.size < minimum:
        raise ValueError(f"{name} must hold at least {minimum} sensors, got {sig.size}")
    return sig


def _values(v: ArrayLike, name: str) -> np.ndarray:
    """A finite, non-empty 1-D array of numbers."""
    return as_array(v, name, ndim=1)


def _ints(v: ArrayLike, name: str, minimum: int = 1) -> np.ndarray:
    """A non-empty 1-D array of integers >= ``minimum`` (as floats), each entry checked by name."""
    if isinstance(v, np.ndarray) and v.ndim != 1:
        raise ValueError(f"{name} must be 1-D, got shape {v.shape}")
    return np.array(check_counts(v, name, minimum), dtype=float)


def _seed(seed: int, name: str = "seed") -> int:
    return V_seed(seed, name)


def _index(i: int, n: int, name: str) -> int:
    if isinstance(i, (bool, str)) or not isinstance(i, (int, np.integer)):
        raise TypeError(f"{name} must be an int, got {type(i).__name__}")
    if not 0 <= i < n:
        raise ValueError(f"{name} must be in [0, {n}), got {i}")
    return int(i)


# --------------------------------------------------------------------------- E2.1
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
    """
    v = as_array(estimates, "estimates")
    if v.ndim < 1:
        raise ValueError("estimates must have a sensor axis")
    if mask is None:
        m = np.ones(v.shape, dtype=bool)
    else:
        m = np.asarray(mask)
        if m.dtype != bool:
            raise ValueError(f"mask must be an array of bools, got dtype {m.dtype}")
    if m.shape != v.shape:
        raise ValueError(f"mask must have the shape of estimates {v.shape}, got {m.shape}")
    if not np.all(m.any(axis=-1)):
        raise ValueError("mask must keep at least one sensor in every row")
    keep = m & (v > 0)
    inv = np.where(keep, 1.0 / np.where(keep, v, 1.0), 0.0)
    none_left = ~keep.any(axis=-1, keepdims=True)
    w = np.where(none_left, m.astype(float), inv)
    return w / w.sum(axis=-1, keepdims=True)


def tail_study(sigma: Sequence[float] = (0.5, 1.0, 2.0, 4.0), x: float = 900.0, k: int = 100,
               runs: int = 100_000, seed: int = 2109, chunk: int = 10_000,
               thresholds: Sequence[float] = (1.0, 10.0, 100.0, 1000.0)) -> dict[str, Any]:
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
        The t (> 0).

    Returns
    -------
    dict
        ``t`` (T,); ``exceed`` (T,): share of runs with :math:`|e| > t`; ``t_exceed`` = t · exceed; ``hill``:
        Hill tail index of the absolute error (:func:`fusion.book.rulebook.hill_tail_index` is not imported here: the
        estimate uses the top √runs values); ``block_mse``: the sample MSE of each of 5 disjoint blocks of runs
        (an infinite mean shows as block means that do not settle); ``median_sq``; the parameters.
    """
    sig = _sigmas(sigma, minimum=2)
    scalar(x, "x")
    count(k, "k", minimum=2)
    count(runs, "runs", minimum=100)
    _seed(seed)
    count(chunk, "chunk")
    t = _values(thresholds, "thresholds")
    if np.any(t <= 0):
        raise ValueError("thresholds must be positive")
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
    return {"t": t, "exceed": exceed, "t_exceed": t * exceed, "hill": hill,
            "block_mse": np.array([b.mean() for b in blocks]), "median_sq": float(np.median(e**2)),
            "runs": int(runs), "k": int(k), "x": float(x), "seed": int(seed), "variances": sig**2}


def ar1_study(sigma: Sequence[float] = (0.5, 1.0, 2.0, 4.0), phi: float = 0.8, k: int = 100, runs: int = 2000,
              seed: int = 2110) -> dict[str, Any]:
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
    dict
        ``c`` (the variance factor); ``bound`` (:math:`\sigma^2_{\min}/k`); ``mse[name]`` for "oracle",
        "AWF (centred)", ``"AWF (lecture, |σ̂²|)"`` and "mean of means"; ``ratio_lecture``, ``ratio_centred``: mean
        estimate / :math:`\sigma_p^2` per sensor at k; the parameters.
    """
    sig = _sigmas(sigma, minimum=2)
    phi = scalar(phi, "phi")
    if not -1.0 < phi < 1.0:
        raise ValueError(f"phi must lie in (-1, 1), got {phi}")
    count(k, "k", minimum=2)
    count(runs, "runs", minimum=100)
    _seed(seed)
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
    fused = {"oracle": means @ wt.optimal_weights(var),
             "AWF (centred)": np.einsum("ri,ri->r", wt.inverse_variance_weights(cen), means),
             "AWF (lecture, |σ̂²|)": np.einsum("ri,ri->r", wt.inverse_variance_weights(lec, guard="abs"), means),
             "mean of means": means.mean(axis=1)}
    return {"c": c, "bound": float(wt.minimum_variance(var)) / k, "mse": {m: float(np.mean(e**2)) for m, e in fused.items()},
            "ratio_lecture": lec.mean(axis=0) / var, "ratio_centred": cen.mean(axis=0) / var,
            "phi": float(phi), "k": int(k), "runs": int(runs), "seed": int(seed), "variances": var}


def awf_study(
    sigma: Sequence[float] = (0.5, 1.0, 2.0, 4.0),
    levels: Sequence[float] = (0.0, 10.0, 100.0, 900.0, 1000.0),
    k_max: int = 1000,
    runs: int = 300,
    seed: int = 2101,
    ks: Sequence[int] = (3, 5, 10, 20, 50, 100, 200, 500, 1000),
    k_compare: int = 100,
) -> dict[str, Any]:
    r"""Experiment E2.1: variance estimators and adaptive weighted fusion at constant levels X.

    The same noise draws (``runs x k_max x n``, standard normal times ``sigma``) are used at
    every level, so only X changes.

    Parameters
    ----------
    sigma : sequence of float, shape (n,)
        Noise SDs of the sensors (readings' unit).
    levels : sequence of float
        Constant measured values X.
    k_max, runs, seed : int
    ks : sequence of int
        Sample counts at which the fused MSE is reported (each <= k_max).
    k_compare : int
        Sample count of the per-run comparisons (one of ``ks``).

    Returns
    -------
    dict
        ``variances`` (n,); ``rows``: list of table rows (X, estimator, k at 100 and k_max: mean and
        SD of σ̂₁² and σ̂₄², fraction negative); ``band[(X, e)]``: (mean, SD) of σ̂₁² against k,
        shape (k_max,), for X in {0, 100}; ``ks``; ``mse[X][name]``: fused MSE against ``ks`` for
        X in {0, 900} and the oracle, both AWFs (the lecture's with the floor guard), mean of means,
        best sensor;
        ``sweep[X][name]``: per-run squared errors at ``k_compare`` of the lecture's AWF (``|σ̂²|``, no guard)
        and the mean of means at every level of ``SWEEP_LEVELS``;
        ``sq[X][name]``: per-run squared errors at ``k_compare`` (shape (runs,)) for X in {0, 900},
        including ``"AWF (lecture, <guard>)"`` for every guard of
        :data:`fusion.readings.weighting.GUARDS` and ``"delete"`` (:func:`delete_weights`), and ``"Graybill-Deal"``
        (each sensor's mean weighted by its own sample variance over the ``k_compare`` samples, Graybill & Deal
        1959); ``err[X][name]``: the signed errors behind ``sq``; ``sd_pred_900``: predicted SD of σ̂₁² at X = 900,
        k = 100 (:func:`fusion.readings.weighting.lecture_variance_sd`); ``mean_est``: mean over
        runs of σ̂ₚ² at ``k_compare`` per (X, estimator), shape (n,); ``sd_est``, ``pneg_est``: the SD over
        runs and the share of negative estimates, same keys and shape.
    """
    _sigmas(sigma, minimum=4)
    _values(levels, "levels")
    k_max = count(k_max, "k_max", minimum=100)
    runs = count(runs, "runs")
    seed = _seed(seed)
    ks_chk = _ints(ks, "ks")
    if np.any(ks_chk > k_max):
        raise ValueError(f"ks must be <= k_max = {k_max}")
    k_compare = count(k_compare, "k_compare")
    if k_compare not in ks_chk:
        raise ValueError(f"k_compare must be one of ks, got {k_compare!r}")
    sig = np.asarray(sigma, dtype=float)
    V = sig**2
    n = sig.size
    ks_a = np.asarray(ks, dtype=int)
    i_cmp = int(np.flatnonzero(ks_a == k_compare)[0])
    noise = np.random.default_rng(seed).normal(size=(runs, k_max, n)) * sig
    rows, band, mean_est, sd_est, pneg_est = [], {}, {}, {}, {}
    for X in levels:
        for e in ("lecture", "centred"):
            est = wt.running_variances(X + noise, e)
            for k in (100, k_max):
                v = est[:, k - 1]
                rows.append({"X": float(X), "estimator": e, "k": k,
                             "mean σ̂₁²": v[:, 0].mean(), "SD σ̂₁²": v[:, 0].std(),
                             "mean σ̂₄²": v[:, 3].mean(), "SD σ̂₄²": v[:, 3].std(),
                             "P(σ̂² < 0)": (v < 0).mean()})
            mean_est[float(X), e] = est[:, k_compare - 1].mean(axis=0)
            sd_est[float(X), e] = est[:, k_compare - 1].std(axis=0)
            pneg_est[float(X), e] = (est[:, k_compare - 1] < 0).mean(axis=0)
            if X in (0.0, 100.0):
                band[float(X), e] = (est[:, :, 0].mean(axis=0), est[:, :, 0].std(axis=0))
    mse: dict[float, dict[str, np.ndarray]] = {}
    sq: dict[float, dict[str, np.ndarray]] = {}
    err: dict[float, dict[str, np.ndarray]] = {}
    for X in (0.0, 900.0):
        Xs = X + noise
        means = wt.running_means(Xs)[:, ks_a - 1]
        lec = wt.running_variances(Xs, "lecture")[:, k_compare - 1]
        curves = {
            "oracle": means @ wt.optimal_weights(V),
            "AWF (lecture, floor)": wt.awf(Xs, "lecture").value[:, ks_a - 1],
            "AWF (centred)": wt.awf(Xs, "centred").value[:, ks_a - 1],
            "mean of means": means.mean(axis=-1),
            "best sensor": means[..., 0],
        }
        mse[X] = {name: ((v - X) ** 2).mean(axis=0) for name, v in curves.items()}
        err[X] = {name: v[:, i_cmp] - X for name, v in curves.items()}
        m_cmp = means[:, i_cmp]
        for guard in wt.GUARDS:
            w = wt.inverse_variance_weights(lec, guard=guard)
            err[X][f"AWF (lecture, {guard})"] = np.einsum("ri,ri->r", w, m_cmp) - X
        err[X]["AWF (lecture, delete)"] = np.einsum("ri,ri->r", delete_weights(lec), m_cmp) - X
        # Graybill & Deal (1959): each sensor's mean weighted by its own sample variance (the classical common mean)
        inv = 1.0 / Xs[:, :k_compare].var(axis=1, ddof=1)
        err[X]["Graybill-Deal"] = np.einsum("ri,ri->r", inv / inv.sum(axis=1, keepdims=True), m_cmp) - X
        sq[X] = {name: e**2 for name, e in err[X].items()}
    # verdict against the level X/σ: the lecture's AWF (|σ̂²| and no guard) against the mean of means at k_compare,
    # on the same noise draws (only the first k_compare samples are needed)
    sweep: dict[float, dict[str, np.ndarray]] = {}
    nz = noise[:, :k_compare]
    for X in SWEEP_LEVELS:
        Xs = X + nz
        lec = wt.running_variances(Xs, "lecture")[:, -1]
        m_cmp = Xs.mean(axis=1)
        sweep[float(X)] = {"mean of means": (m_cmp.mean(axis=-1) - X) ** 2}
        for guard in ("abs", "none"):
            w = wt.inverse_variance_weights(lec, guard=guard)
            sweep[float(X)][f"AWF (lecture, {guard})"] = (np.einsum("ri,ri->r", w, m_cmp) - X) ** 2
    return {"variances": V, "rows": rows, "band": band, "ks": ks_a, "k_compare": k_compare,
            "i_compare": i_cmp, "mse": mse, "sq": sq, "err": err, "runs": runs, "k_max": k_max, "seed": seed, "sweep": sweep,
            "sd_pred_900": float(wt.lecture_variance_sd(900.0, 100, V)[0]), "mean_est": mean_est, "sd_est": sd_est,
            "pneg_est": pneg_est}


def _lumv_errors(X: np.ndarray, x: float, w_or: np.ndarray) -> dict[str, np.ndarray]:
    """Fused error of every reading of E2.1c for a batch of runs ``X`` (runs, k, n)."""
    means = X.mean(axis=1)
    est = {"oracle": means @ w_or}
    lec = wt.variance_estimates(X, "lecture")
    for g in wt.GUARDS:
        est[f"AWF (lecture, {g})"] = np.einsum("ri,ri->r", wt.inverse_variance_weights(lec, guard=g), means)  # type: ignore[arg-type]
    est["AWF (lecture, delete)"] = np.einsum("ri,ri->r", delete_weights(lec), means)
    cen = wt.variance_estimates(X, "centred")
    est["AWF (centred)"] = np.einsum("ri,ri->r", wt.inverse_variance_weights(cen), means)
    return {name: v - x for name, v in est.items()}


def lumv_study(
    sigma: Sequence[float] = (0.5, 1.0, 2.0, 4.0),
    x: float = 900.0,
    k: int = 100,
    runs: int = 20000,
    seed: int = 2107,
    chunk: int = 2500,
) -> dict[str, Any]:
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
    dict
        ``err[name]``: signed error of each run, shape (runs,), for "oracle", "AWF (lecture, <guard>)" and
        "AWF (centred)", the draws :math:`V` first and their mirror images :math:`-V` after, in the same
        order; ``sq[name]``: squared errors; ``pair_mean[name]``, ``pair_sq[name]``: the mean of the
        signed and of the squared errors of each pair, shape (runs / 2,); ``odd_residual[name]``:
        :math:`\max|e(V) + e(-V)|`; ``bound``: :math:`\sigma^2_{\min}/k`; the parameters (``pairs`` = runs / 2).
    """
    sig = _sigmas(sigma, minimum=2)
    scalar(x, "x")
    k = count(k, "k", minimum=2)
    runs = count(runs, "runs", minimum=4)
    if runs % 2:
        raise ValueError(f"runs must be even (antithetic pairs), got {runs}")
    seed = _seed(seed)
    chunk = count(chunk, "chunk")
    V = sig**2
    w_or = wt.optimal_weights(V)
    rng = np.random.default_rng(seed)
    plus: dict[str, list[np.ndarray]] = {}
    minus: dict[str, list[np.ndarray]] = {}
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
    return {"err": err, "sq": {name: e**2 for name, e in err.items()},
            "pair_mean": {name: 0.5 * (ep[name] + em[name]) for name in ep},
            "pair_sq": {name: 0.5 * (ep[name] ** 2 + em[name] ** 2) for name in ep},
            "odd_residual": {name: float(np.max(np.abs(ep[name] + em[name]))) for name in ep},
            "bound": float(wt.minimum_variance(V)) / k, "variances": V, "x": float(x), "k": int(k), "runs": int(runs),
            "pairs": int(pairs), "seed": int(seed)}


#: The fusions of :func:`symmetry_study`: (name, level of the measured value used, "awf"/"ls", estimator, guard).
SYMMETRY_METHODS: tuple[tuple[str, str, str, str], ...] = (
    ("oracle (true variances)", "oracle", "", ""),
    ("AWF, centred, floor", "awf", "centred", "floor"),
    ("AWF, centred, |σ̂²|", "awf", "centred", "abs"),
    ("AWF, centred, equal fallback", "awf", "centred", "equal"),
    ("AWF, lecture's estimator, |σ̂²|, X = 0", "awf0", "lecture", "abs"),
    ("AWF, lecture's estimator, |σ̂²|", "awf", "lecture", "abs"),
    ("AWF, lecture's estimator, floor", "awf", "lecture", "floor"),
    ("LS learning (2.2)", "ls", "", ""),
    ("LS learning, corrected (2.2)", "lsc", "", ""),
)


def symmetry_study(
    sigma: Sequence[float] = (0.5, 1.0, 2.0, 4.0),
    x: float = 900.0,
    k: int = 100,
    runs: int = 200,
    seed: int = 2108,
) -> dict[str, Any]:
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
    dict
        ``methods`` (names of :data:`SYMMETRY_METHODS`); ``residual[name]``: :math:`\max|e(V) + e(-V)|`
        over the runs; ``scale[name]``: :math:`\max|e(V)|`; ``even[name]``: whether the residual is
        round-off, at most :math:`10^{-6}` of the scale (the centred moments at a level :math:`X` cancel
        :math:`X^2`-sized terms, so their round-off is about :math:`10^{-16}X^2/\sigma^2` relative, ~10⁻⁹
        of the scale at 900 °C); the parameters.
    """
    sig = _sigmas(sigma, minimum=3)
    scalar(x, "x")
    k = count(k, "k", minimum=2)
    runs = count(runs, "runs")
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
    for name, kind, est, guard in SYMMETRY_METHODS:
        ep, em = err(kind, est, guard, noise), err(kind, est, guard, -noise)
        residual[name] = float(np.max(np.abs(ep + em)))
        scale[name] = float(np.max(np.abs(ep)))
        even[name] = bool(residual[name] <= 1e-6 * scale[name])
    return {"methods": [m[0] for m in SYMMETRY_METHODS], "residual": residual, "scale": scale, "even": even,
            "runs": int(runs), "k": int(k), "x": float(x), "seed": int(seed), "variances": sig**2}


# --------------------------------------------------------------------------- E2.1b
#: Scenarios of :func:`regime_study`: (name, signal, variances swap at ``change_at``).
REGIME_SCENARIOS: tuple[tuple[str, str, bool], ...] = (
    ("constant X", "constant", False),
    ("slow sine", "sine", False),
    ("slow sine at 900", "sine_level", False),
    ("fast sine", "fast", False),
    ("random walk", "walk", False),
    ("step in X", "step", False),
    ("constant X, σ swap", "constant", True),
    ("slow sine, σ swap", "sine", True),
)

#: Methods of :func:`regime_study`. All but the "running means" and "per-sample" ones fuse the
#: *current* readings; those estimate a constant X from every reading so far.
REGIME_METHODS: tuple[str, ...] = (
    "oracle", "mean", "sample variance, growing", "difference variance, growing",
    "difference variance, forgetting", "lecture, growing", "centred, growing",
    "centred, forgetting", "centred, window", "AWF as written (running means)",
    "running means, oracle", "per-sample, forgetting", "per-sample, forgetting (λ = 0.99)",
    "per-sample BLUE (oracle)", "LS learning, growing (1/m)", "LS learning, forgetting",
)

#: Methods of :func:`regime_study` run only where X is constant (they estimate a constant).
REGIME_CONSTANT_ONLY: tuple[str, ...] = ("per-sample, forgetting", "per-sample, forgetting (λ = 0.99)",
                                         "per-sample BLUE (oracle)")


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
) -> dict[str, Any]:
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
    dict
        ``scenarios`` (names), ``methods``; ``sq[scenario][method]``: per-run MSE over the
        evaluation window, shape (runs,) (the methods of :data:`REGIME_CONSTANT_ONLY` only where X is
        constant); ``curve[scenario][method]``: MSE over runs against k, shape (samples,);
        ``w_best[scenario][method]``: mean weight of sensor 1 against k (current-reading methods);
        ``var_est``: per-run σ̂₁² at the last sample, constant X, for ``"sample"`` and ``"centred"``;
        ``n_nonpositive[scenario]``: number of non-positive estimates of the lecture's estimator
        (growing memory) in the evaluation window, where X is constant; ``variances``; the parameters.
    """
    sig = _sigmas(sigma, minimum=3)
    samples = count(samples, "samples", minimum=20)
    runs = count(runs, "runs")
    seed = _seed(seed)
    scalar(amplitude, "amplitude")
    for name, v in (("period", period), ("fast_period", fast_period)):
        if scalar(v, name) <= 0:
            raise ValueError(f"{name} must be positive, got {v!r}")
    scalar(step, "step")
    scalar(level, "level")
    scalar(walk_step, "walk_step", lo=0.0)
    walk_seed = _seed(walk_seed, "walk_seed")
    for name, v in (("forgetting", forgetting), ("forgetting_alt", forgetting_alt)):
        if not 0.0 < scalar(v, name) < 1.0:
            raise ValueError(f"{name} must be in (0, 1), got {v!r}")
    _index(change_at, samples, "change_at")
    one_of(guard, wt.GUARDS, "guard")
    acc_guard = "abs" if guard == "none" else guard
    n, K = sig.size, samples
    k = np.arange(K)
    after = k >= change_at
    swapped = sig.copy()
    swapped[[0, -1]] = sig[[-1, 0]]
    sd_t = np.where(after[:, None], swapped, sig)  # (K, n)
    z = np.random.default_rng(seed).normal(size=(runs, K, n))
    sine = amplitude * np.sin(2 * np.pi * k / period)
    signals = {"constant": np.zeros(K), "sine": sine, "sine_level": level + sine,
               "fast": amplitude * np.sin(2 * np.pi * k / fast_period),
               "walk": np.cumsum(np.random.default_rng(walk_seed).normal(size=K)) * walk_step,
               "step": np.where(after, step, 0.0)}
    sq: dict[str, dict[str, np.ndarray]] = {}
    curve: dict[str, dict[str, np.ndarray]] = {}
    w_best: dict[str, dict[str, np.ndarray]] = {}
    var_est: dict[str, np.ndarray] = {}
    n_nonpos: dict[str, int] = {}
    for name, sigl, swap in REGIME_SCENARIOS:
        sd = sd_t if swap else np.broadcast_to(sig, (K, n))
        truth = signals[sigl]
        X = truth[:, None] + z * sd
        cen_forget = wt.tracking_variances(X, "centred", "forgetting", forgetting=forgetting)
        est = {
            "oracle": np.broadcast_to(sd**2, X.shape),
            "mean": np.ones_like(X),
            "sample variance, growing": wt.tracking_variances(X, "sample"),
            "difference variance, growing": wt.difference_variances(X),
            "difference variance, forgetting": wt.difference_variances(X, "forgetting", forgetting=forgetting),
            "lecture, growing": wt.tracking_variances(X, "lecture"),
            "centred, growing": wt.tracking_variances(X, "centred"),
            "centred, forgetting": cen_forget,
            "centred, window": wt.tracking_variances(X, "centred", "window", window=window),
        }
        if name == "constant X":
            var_est = {"sample": est["sample variance, growing"][:, -1, 0], "centred": est["centred, growing"][:, -1, 0]}
        fused, wb = {}, {}
        for m, v in est.items():
            w = wt.inverse_variance_weights(v, guard=guard)  # type: ignore[arg-type]
            fused[m] = np.sum(w * X, axis=-1)
            wb[m] = w[..., 0].mean(axis=0)
        a = wt.awf(X, "lecture", guard=guard)  # type: ignore[arg-type]
        fused["AWF as written (running means)"] = a.value
        wb["AWF as written (running means)"] = a.weights[..., 0].mean(axis=0)
        if sigl == "constant":
            n_nonpos[name] = int(np.sum(a.variances[:, after] <= 0))
        # the running means weighted by their true variance k⁻²Σσ²(i): the best fusion of the running means
        rm = a.means
        kk = np.arange(1, K + 1)[:, None]
        w = wt.inverse_variance_weights(np.broadcast_to(np.cumsum(np.asarray(sd, dtype=float) ** 2, axis=0) / kk**2, X.shape))
        fused["running means, oracle"] = np.sum(w * rm, axis=-1)
        wb["running means, oracle"] = w[..., 0].mean(axis=0)
        if sigl == "constant":
            # every sample weighted by its own (estimated or true) inverse variance, accumulated over time
            fused["per-sample, forgetting"] = wt.cumulative_fusion(X, cen_forget, guard=acc_guard)  # type: ignore[arg-type]
            fused["per-sample, forgetting (λ = 0.99)"] = wt.cumulative_fusion(
                X, wt.tracking_variances(X, "centred", "forgetting", forgetting=forgetting_alt), guard=acc_guard)  # type: ignore[arg-type]
            fused["per-sample BLUE (oracle)"] = wt.cumulative_fusion(X, est["oracle"], time_weights="precision")
        # sec. 2.2: the allocations (y − ȳ)² averaged with the lecture's 1/m recursion or with forgetting
        dev2 = (X - X.mean(axis=-1, keepdims=True)) ** 2
        for m, v in (("LS learning, growing (1/m)", wt.learned_variances(X)),
                     ("LS learning, forgetting", wt.running_average(dev2, "forgetting", forgetting=forgetting))):
            w = wt.inverse_variance_weights(v, guard=guard)  # type: ignore[arg-type]
            fused[m] = np.sum(w * X, axis=-1)
            wb[m] = w[..., 0].mean(axis=0)
        e2 = {m: (f - truth) ** 2 for m, f in fused.items()}
        sq[name] = {m: e[:, after].mean(axis=1) for m, e in e2.items()}
        curve[name] = {m: e.mean(axis=0) for m, e in e2.items()}
        w_best[name] = wb
    return {"scenarios": [s[0] for s in REGIME_SCENARIOS], "methods": list(REGIME_METHODS), "sq": sq, "curve": curve,
            "w_best": w_best, "var_est": var_est, "n_nonpositive": n_nonpos, "variances": sig**2,
            "swapped": swapped**2, "runs": runs, "samples": K, "seed": seed, "amplitude": float(amplitude),
            "period": float(period), "step": float(step), "change_at": int(change_at), "forgetting": float(forgetting),
            "forgetting_alt": float(forgetting_alt), "window": int(window), "guard": guard, "level": float(level),
            "fast_period": float(fast_period), "walk_step": float(walk_step), "walk_seed": int(walk_seed)}


#: Changes of the noise SDs of :func:`variance_change_study`: (name, {sensor index: SD after the change}).
VARIANCE_CHANGES: tuple[tuple[str, dict[int, float]], ...] = (
    ("sensors 1 and 4 swap (0.5 ↔ 4)", {0: 4.0, 3: 0.5}),
    ("sensor 1 degrades (0.5 → 4)", {0: 4.0}),
    ("sensor 4 improves (4 → 0.5)", {3: 0.5}),
)

#: Fusions of a constant X from every reading so far, run by :func:`variance_change_study`.
CHANGE_METHODS: tuple[str, ...] = ("AWF as written (running means)", "running means, oracle", "per-sample, forgetting",
                                   "per-sample, forgetting (λ = 0.99)", "per-sample BLUE (oracle)")


def variance_change_study(
    sigma: Sequence[float] = (0.5, 1.0, 2.0, 4.0),
    samples: int = 1000,
    runs: int = 100,
    seed: int = 2105,
    change_at: int = 500,
    forgetting: float = 0.98,
    forgetting_alt: float = 0.99,
    changes: Sequence[tuple[str, dict[int, float]]] = VARIANCE_CHANGES,
) -> dict[str, Any]:
    r"""E2.1b, the lecture's own setting: a constant X = 0 and one change of the sensors' noise SDs.

    The same standard-normal draws as :func:`regime_study` with the same ``seed``, ``runs``,
    ``samples`` and number of sensors, so the swap reproduces its scenario "constant X, σ swap"
    run by run. Each change sets the SDs of some sensors from sample ``change_at`` (0-based) on. The
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
        Name and ``{sensor index: new SD}`` of each change (SDs non-negative and finite).

    Returns
    -------
    dict
        ``changes`` (names), ``methods``; ``sq[change][method]``: per-run MSE over the evaluation
        window, shape (runs,); ``sd_after[change]``: SDs after the change; the parameters.
    """
    sig = _sigmas(sigma, minimum=3)
    samples = count(samples, "samples", minimum=20)
    runs = count(runs, "runs")
    seed = _seed(seed)
    _index(change_at, samples, "change_at")
    for name, v in (("forgetting", forgetting), ("forgetting_alt", forgetting_alt)):
        if not 0.0 < scalar(v, name) < 1.0:
            raise ValueError(f"{name} must be in (0, 1), got {v!r}")
    sequence(changes, "changes")
    if isinstance(changes, (str, bytes, dict)) or len(changes) == 0:
        raise ValueError(f"changes must be a non-empty sequence of (name, {{sensor: SD}}) pairs, got {changes!r}")
    n, K = sig.size, samples
    after_sd: dict[str, np.ndarray] = {}
    for item in changes:
        if not (isinstance(item, tuple) and len(item) == 2 and isinstance(item[0], str) and isinstance(item[1], dict)):
            raise ValueError(f"changes must hold (name, {{sensor: SD}}) pairs, got {item!r}")
        new = sig.copy()
        for i, v in item[1].items():
            new[_index(i, n, "changes")] = v
        after_sd[item[0]] = _sigmas(new, "changes", minimum=3)
    after = np.arange(K) >= change_at
    z = np.random.default_rng(seed).normal(size=(runs, K, n))
    sq: dict[str, dict[str, np.ndarray]] = {}
    kk = np.arange(1, K + 1)[:, None]
    for name, new in after_sd.items():
        sd = np.where(after[:, None], new, sig)
        X = z * sd
        a = wt.awf(X, "lecture", guard="abs")
        w = wt.inverse_variance_weights(np.broadcast_to(np.cumsum(sd**2, axis=0) / kk**2, X.shape))
        fused = {
            "AWF as written (running means)": a.value,
            "running means, oracle": np.sum(w * a.means, axis=-1),
            "per-sample, forgetting": wt.cumulative_fusion(
                X, wt.tracking_variances(X, "centred", "forgetting", forgetting=forgetting), guard="abs"),
            "per-sample, forgetting (λ = 0.99)": wt.cumulative_fusion(
                X, wt.tracking_variances(X, "centred", "forgetting", forgetting=forgetting_alt), guard="abs"),
            "per-sample BLUE (oracle)": wt.cumulative_fusion(X, np.broadcast_to(sd**2, X.shape), time_weights="precision"),
        }
        sq[name] = {m: (f[:, after] ** 2).mean(axis=1) for m, f in fused.items()}
    return {"changes": list(after_sd), "methods": list(CHANGE_METHODS), "sq": sq, "sd_after": after_sd,
            "variances": sig**2, "runs": int(runs), "samples": int(K), "seed": int(seed), "change_at": int(change_at),
            "forgetting": float(forgetting), "forgetting_alt": float(forgetting_alt)}


# --------------------------------------------------------------------------- E2.2
def learning_study(
    r_sets: Sequence[Sequence[float]] = ((1.0, 4.0), (1.0, 4.0, 9.0), (1.0, 2.0, 4.0, 8.0), (0.25, 1.0, 4.0, 16.0, 64.0)),
    epochs: int = 2000,
    runs: int = 200,
    x: float = 50.0,
    seed: int = 2202,
    seed_two: int = 2203,
    last: int = 200,
) -> dict[str, Any]:
    r"""Experiment E2.2: the variance-learning recursion of sec. 2.2.

    Parameters
    ----------
    r_sets : sequence of variance tuples
        True noise variances :math:`R_i` of each setting (one generator draws all settings in turn).
    epochs, runs : int
    x : float
        True value.
    seed, seed_two : int
        Seeds of the settings and of the two-sensor check (50 runs x 300 epochs, R = (1, 4)).
    last : int
        Monte-Carlo MSEs are over the last ``last`` epochs.

    Returns
    -------
    dict
        ``rows``: one per setting with ``R``, ``min Rᵢ``, ``optimal``, ``learned (limit)`` (exact
        variance with the limiting weights), ``learned (MC)``, ``corrected (MC)`` (NaN for n = 2),
        ``mean``, ``max |R̂ − limit|/limit``; ``learned[n]``: (R, mean learned variances against m,
        shape (epochs, n)); ``bias[R]``: per-run mean error of the learned fusion over the last ``last``
        epochs, shape (runs,); ``n2_maxdev``: largest deviation of the two-sensor learned weights from 1/2.
    """
    if isinstance(r_sets, (str, bytes)):
        raise TypeError("r_sets must be a sequence of variance tuples, got a string")
    sequence(r_sets, "r_sets")
    for Rt in r_sets:
        _sigmas(Rt, "r_sets")
        if np.any(np.asarray(Rt, dtype=float) <= 0):
            raise ValueError("r_sets must hold positive variances")
    epochs = count(epochs, "epochs")
    runs = count(runs, "runs")
    scalar(x, "x")
    seed = _seed(seed)
    seed_two = _seed(seed_two, "seed_two")
    last = count(last, "last")
    if last > epochs:
        raise ValueError(f"last must be <= epochs = {epochs}, got {last}")
    rng = np.random.default_rng(seed)
    rows, learned, bias = [], {}, {}
    for Rt in r_sets:
        R = np.array(Rt, dtype=float)
        n = R.size
        Y = x + rng.normal(size=(runs, epochs, n)) * np.sqrt(R)
        Rh = wt.learned_variances(Y)
        learned[n] = (R, Rh.mean(axis=0))
        limit = wt.learned_variance_limit(R)
        row = {"R": "(" + ", ".join(f"{float(r):g}" for r in R) + ")", "min Rᵢ": R.min(),
               "optimal": wt.minimum_variance(R),
               "learned (limit)": float(np.sum(wt.optimal_weights(limit) ** 2 * R)),
               "learned (MC)": float(np.mean((wt.ls_learning(Y).values[:, -last:] - x) ** 2)),
               "mean": R.sum() / n**2,
               "max |R̂ − limit|/limit": float(np.max(np.abs(Rh[:, -1].mean(axis=0) - limit) / limit))}
        row["corrected (MC)"] = (float(np.mean((wt.ls_learning(Y, corrected=True).values[:, -last:] - x) ** 2))
                                 if n >= 3 else float("nan"))
        rows.append(row)
        bias[row["R"]] = (wt.ls_learning(Y).values[:, -last:] - x).mean(axis=1)
    Y2 = x + np.random.default_rng(seed_two).normal(size=(50, 300, 2)) * np.sqrt([1.0, 4.0])
    return {"rows": rows, "learned": learned, "bias": bias, "x": x, "last": last,
            "n2_maxdev": float(np.max(np.abs(wt.ls_learning(Y2).weights - 0.5)))}


def learned_limit_check(ns: Sequence[int] = (3, 4, 5, 6, 7, 8), draws: int = 20000, seed: int = 2204,
                        log_range: float = 4.0, margin: float = 0.05) -> dict[str, Any]:
    r"""Random check of the learned weights' limit of sec. 2.2 against the mean and the best sensor.

    For every n of ``ns``, ``draws`` variance sets :math:`R_i = e^{u_i}`, :math:`u_i \sim U(-a, a)`
    (a = ``log_range``); the fused variance with the learned weights' limit
    (:func:`fusion.readings.weighting.learned_fused_variance`) against the arithmetic mean's
    :math:`\sum R_i/n^2` and the best sensor's :math:`\min R_i`.

    Parameters
    ----------
    ns : sequence of int
        Numbers of sensors (each >= 2).
    draws : int
        Variance sets per n.
    seed : int
    log_range : float
        Half-width a of the uniform log-variances (> 0).
    margin : float
        Practical margin, a share of the best sensor's variance (>= 0; rule R9: "no worse than the best sensor"
        fails only beyond it).

    Returns
    -------
    dict
        ``sets`` (total), ``above_mean`` (sets where the learned fusion exceeds the mean's variance
        by more than 10⁻¹² relative), ``above_best`` (sets where it exceeds the best sensor's by more than
        ``margin``), ``above_best_any`` (by any amount), ``max_ratio_mean`` (largest learned/mean ratio),
        ``margin``, ``ns``, ``draws``, ``seed``.
    """
    n_arr = _ints(ns, "ns", minimum=2)
    draws = count(draws, "draws")
    allocation((draws, int(n_arr.max())), "ns and draws")
    seed = _seed(seed)
    a = scalar(log_range, "log_range", lo=0.0, lo_open=True)
    m = scalar(margin, "margin", lo=0.0)
    rng = np.random.default_rng(seed)
    above_mean = above_best = above_any = 0
    worst = 0.0
    for n in n_arr.astype(int):
        R = np.exp(rng.uniform(-a, a, size=(draws, n)))
        v = wt.learned_fused_variance(R)
        mean = R.sum(axis=1) / n**2
        above_mean += int(np.sum(v > mean * (1 + 1e-12)))
        above_best += int(np.sum(v > R.min(axis=1) * (1 + m)))
        above_any += int(np.sum(v > R.min(axis=1)))
        worst = max(worst, float(np.max(v / mean)))
    return {"sets": int(draws * n_arr.size), "above_mean": above_mean, "above_best": above_best,
            "above_best_any": above_any, "max_ratio_mean": worst, "margin": m, "ns": tuple(int(n) for n in n_arr),
            "draws": draws, "seed": seed}


# --------------------------------------------------------------------------- E2.3
#: Sensor numberings (0-based permutations of five sensors) under which the index-order reading of the
#: §2.3 check is run: as given (the faulty sensor third), the faulty sensor first, last, and reversed.
INDEX_ORDERS: tuple[tuple[int, ...], ...] = ((0, 1, 2, 3, 4), (2, 0, 1, 3, 4), (0, 1, 3, 4, 2), (4, 3, 2, 1, 0))

#: Guards of the lecture's AWF run in :func:`consistency_study` (:data:`fusion.readings.weighting.GUARDS`),
#: with the names used in its results.
CC_GUARDS: dict[str, str] = {"none": "no guard", "floor": "floor", "abs": "|σ̂²|", "equal": "equal"}


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
) -> dict[str, Any]:
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
    dict
        ``eps``; ``out[(label, name)]``: fused values (runs, samples) for label in {"no fault",
        "fault"} and the names in ``names`` (the lecture's AWF and check + AWF under every guard of
        :data:`CC_GUARDS`, the centred ones with the floor), plus masks ``(label, "mask")``; ``sq[label][name]``:
        per-run MSE over the window, shape (runs,); ``p_excl_fault``, ``p_excl_clean``,
        ``p_excl_any_clean``; ``ratio`` (bias/ε grid) and ``pdet`` (detection curve,
        :func:`fusion.readings.consistency.rejection_probability`); ``diag[label]``: for the lecture's
        AWF over the window, the fraction of instants at which every healthy sensor's variance
        estimate is negative, the mean weight of the faulty sensor (floor), and the MSE of the plain
        mean of the healthy sensors' running means (what the floored weights reduce to when all
        healthy estimates are negative); with ``|σ̂²|``: the mean weight of the faulty sensor and of each
        healthy one, the mean estimate of the faulty sensor and the mean ``|σ̂²|`` of the healthy ones,
        the MSE of the faulty sensor's term :math:`W_3(\bar X_3 - X)` and the total MSE;
        ``index_order[numbering][label]``: per-run MSE over the window of the check (lecture
        estimator, guard ``index_guard``) with "adjacent" read as the sensors' index order, for each
        numbering of :data:`INDEX_ORDERS` that fits the number of sensors.
    """
    sig_chk = _sigmas(sigma, minimum=3)
    if sig_chk.max() <= 0:
        raise ValueError("sigma must have a positive entry")
    samples = count(samples, "samples")
    runs = count(runs, "runs")
    scalar(x, "x")
    scalar(bias, "bias")
    _index(fault_sensor, sig_chk.size, "fault_sensor")
    window = check_window(window, "window", samples)  # not reversed, not empty (issue 35, class 4)
    seed = _seed(seed)
    seed_curve = _seed(seed_curve, "seed_curve")
    curve_draws = count(curve_draws, "curve_draws")
    one_of(index_guard, tuple(CC_GUARDS), "index_guard")
    sig = np.asarray(sigma, dtype=float)
    eps = 3 * np.sqrt(2) * sig.max()
    clean = x + np.random.default_rng(seed).normal(size=(runs, samples, sig.size)) * sig
    fault = clean.copy()
    win = slice(*window)
    fault[:, win, fault_sensor] += bias
    out: dict[tuple[str, str], np.ndarray] = {}
    for label, data in (("no fault", clean), ("fault", fault)):
        out[label, "mean"] = data.mean(axis=-1)
        out[label, "mean of means"] = wt.running_means(data).mean(axis=-1)
        for g, gname in CC_GUARDS.items():
            r_g = wt.awf(data, "lecture", guard=g)  # type: ignore[arg-type]
            out[label, f"AWF (lecture, {gname})"] = r_g.value
            checked = cs.consistency_awf(data, eps, "lecture", guard="floor" if g == "none" else g)  # type: ignore[arg-type]
            out[label, f"check + AWF (lecture, {gname})"] = (_literal_check_awf(data, eps) if g == "none"
                                                              else checked.awf.value)
        out[label, "mask"] = checked.mask
        # deletion: the raw estimates and running means are the same under every guard (those of the last one)
        out[label, "AWF (lecture, delete)"] = np.einsum("...i,...i->...", delete_weights(r_g.variances), r_g.means)
        c_del = checked.awf
        out[label, "check + AWF (lecture, delete)"] = np.einsum(
            "...i,...i->...", delete_weights(c_del.variances, checked.mask), c_del.means)
        out[label, "AWF (centred)"] = wt.awf(data, "centred").value
        out[label, "check + AWF (centred)"] = cs.consistency_awf(data, eps, "centred").awf.value
    healthy = np.arange(sig.size) != fault_sensor
    diag = {}
    for label, data in (("no fault", clean), ("fault", fault)):
        r = wt.awf(data, "lecture")
        ra = wt.awf(data, "lecture", guard="abs")
        va = ra.variances[:, win]
        part = ra.weights[:, win, fault_sensor] * (ra.means[:, win, fault_sensor] - x)
        diag[label] = {
            "p_all_healthy_negative": float(np.all(r.variances[:, win][..., healthy] < 0, axis=-1).mean()),
            "weight_faulty": float(r.weights[:, win, fault_sensor].mean()),
            "mse_healthy_mean_of_means": float(np.mean((r.means[:, win][..., healthy].mean(axis=-1) - x) ** 2)),
            "abs_weight_faulty": float(ra.weights[:, win, fault_sensor].mean()),
            "abs_weights_healthy": ra.weights[:, win][..., healthy].mean(axis=(0, 1)),
            "abs_var_faulty": float(va[..., fault_sensor].mean()),
            "abs_var_healthy": float(np.abs(va[..., healthy]).mean()),
            "abs_mse_faulty_term": float(np.mean(part**2)),
            "abs_mse": float(np.mean((ra.value[:, win] - x) ** 2)),
        }
    names = ["mean", "mean of means"] + [f"{c}AWF (lecture, {g})" for g in CC_GUARDS.values() for c in ("", "check + ")] \
        + ["AWF (centred)", "check + AWF (centred)", "AWF (lecture, delete)", "check + AWF (lecture, delete)"]
    sq = {lab: {nm: _window_mse(out[lab, nm], x, win) for nm in names} for lab in ("no fault", "fault")}
    # "adjacent" read as the sensors' index order: the check then depends on how the sensors are numbered
    index_order: dict[str, dict[str, np.ndarray]] = {}
    for perm in INDEX_ORDERS:
        if sorted(perm) != list(range(sig.size)):
            continue
        key = "sensors in order " + ", ".join(str(j + 1) for j in perm)
        index_order[key] = {
            lab: _window_mse(_literal_check_awf(data[..., list(perm)], eps, "index") if index_guard == "none" else
                             cs.consistency_awf(data[..., list(perm)], eps, "lecture", guard=index_guard,  # type: ignore[arg-type]
                                                adjacent="index").awf.value, x, win)
            for lab, data in (("no fault", clean), ("fault", fault))}
    ratio = np.linspace(0, 2, 41)
    snap = x + np.random.default_rng(seed_curve).normal(size=(curve_draws, sig.size)) * sig
    pdet = cs.rejection_probability(snap, fault_sensor, ratio * eps, eps)
    return {"eps": float(eps), "bias": bias, "x": x, "window": window, "out": out, "names": names, "sq": sq,
            "p_excl_fault": float(1 - out["fault", "mask"][:, win, fault_sensor].mean()),
            "p_excl_clean": float(1 - out["no fault", "mask"][..., fault_sensor].mean()),
            "p_excl_any_clean": float(1 - out["no fault", "mask"].mean()),
            "ratio": ratio, "pdet": pdet, "diag": diag, "runs": runs, "samples": samples, "seed": seed,
            "index_order": index_order, "index_guard": index_guard}


# --------------------------------------------------------------------------- E2.4
def belief_study(
    sigma: Sequence[float] = (0.5, 1.0, 2.0, 4.0),
    x: float = 900.0,
    seeds: tuple[int, int, int] = (2401, 2402, 2403),
    snapshots: int = 5000,
) -> dict[str, Any]:
    r"""Experiment E2.4: belief-degree (Perron eigenvector) weights.

    Four parts: one draw of the sensors at ``x``, reading 1 shifted by Δ ∈ [0, 20]; the same
    readings (reading 1 +3) in °C, °F and K; eigenvector against row-sum weights
    (:func:`fusion.readings.fusion_set.row_sum_weights`) on ``snapshots`` draws, half with reading 1
    shifted by U(0, 10); the binary belief of (900, 900.4, 903, 903.3), ε = 1.

    Parameters
    ----------
    sigma : sequence of float
        Noise standard deviation of each sensor (°C).
    x : float
        True value (°C).
    seeds : (int, int, int)
        Seeds of the three random parts.
    snapshots : int
        Draws of the eigenvector against row-sum comparison.

    Returns
    -------
    dict
        ``base``, ``deltas``, ``W`` (weights against Δ, shape (201, n)); unit differences
        ``unit_k_maxdiff``, ``unit_f_maxdiff``, ``unit_fconv_maxdiff``, ``unit_f_valdiff``;
        ``eig_w``, ``row_w`` (snapshots, n); ``rowsum_maxdiff``, ``rowsum_valdiff_rms``,
        ``mse_eig``, ``mse_row``, and per snapshot ``sq_eig``, ``sq_row`` (squared errors) and ``shifted``
        (reading 1 shifted); ``bin_lam`` (two largest eigenvalues), ``bin_w``; ``perron[label]`` for fuzzy
        (s = 0.25, 1, 4), binary (ε = 0.5, 1, 2, 4) and truncated fuzzy (s = 1, m = 1, 2, 4) belief matrices of the same snapshots: ``min_gap``
        (smallest relative gap of :func:`fusion.readings.fusion_set.perron_gap`), ``share_repeated`` (gap at most
        ``fusion.readings.fusion_set.PERRON_RTOL``: a repeated Perron root), ``min_weight`` and
        ``share_zero_weight`` (snapshots with a reading of weight 0); ``min_lambda`` (smallest largest eigenvalue),
        ``lambda_is_modulus`` (it is the largest in modulus on every snapshot) and ``max_residual`` (largest
        ‖BA − λA‖/(λ‖A‖) for the returned weights A).
    """
    _sigmas(sigma, minimum=2)
    scalar(x, "x")
    seeds = [_seed(sd, "seeds") for sd in sequence(seeds, "seeds", 3)]
    snapshots = count(snapshots, "snapshots", minimum=2)
    sig = np.asarray(sigma, dtype=float)
    base = x + np.random.default_rng(seeds[0]).normal(size=sig.size) * sig
    deltas = np.linspace(0, 20, 201)
    e1 = np.eye(sig.size)[0]
    W = np.array([rd.belief_degree(base + d * e1).weights for d in deltas])
    snap = base + 3.0 * e1
    to_f = 1.8 * snap + 32.0
    to_k = snap + 273.15
    wc = rd.belief_degree(snap).weights
    snaps = x + np.random.default_rng(seeds[1]).normal(size=(snapshots, sig.size)) * sig
    snaps[::2, 0] += np.random.default_rng(seeds[2]).uniform(0, 10, size=snapshots // 2)
    eig_w = rd.fuse_epochs(snaps, "belief_degree").weights
    row_w = rd.row_sum_weights(rd.belief_matrices(snaps))
    xb = np.array([900.0, 900.4, 903.0, 903.3])
    lam_b = np.linalg.eigvalsh(rd.belief_matrix(xb, binary_eps=1.0))
    # the Perron-Frobenius claim: fuzzy belief matrices (positive) against binary ones (0/1), same snapshots
    perron: dict[str, dict[str, float]] = {}
    d = np.abs(snaps[:, :, None] - snaps[:, None, :])
    for kind, par in (("fuzzy", 0.25), ("fuzzy", 1.0), ("fuzzy", 4.0), ("binary", 0.5), ("binary", 1.0), ("binary", 2.0),
                      ("binary", 4.0), ("truncated", 1.0), ("truncated", 2.0), ("truncated", 4.0)):
        # truncated: the fuzzy belief (s = 1) set to 0 beyond the fusion upper limit m = par (融合上限)
        B = (np.exp(-d / (2.0 * par)) if kind == "fuzzy" else np.exp(-d / 2.0) * (d <= par) if kind == "truncated"
             else (d <= par).astype(float))
        gap = rd.perron_gap(B)
        w = rd.perron_weights(B)
        ev = np.linalg.eigvalsh(B)
        lam = ev[:, -1]
        # the claim as printed: λ > 0 of largest modulus with λA = BA for the returned A (aᵢ ≥ 0)
        res = np.linalg.norm(np.einsum("kij,kj->ki", B, w) - lam[:, None] * w, axis=1) / (lam * np.linalg.norm(w, axis=1))
        perron[f"{kind}, {'s' if kind == 'fuzzy' else 'm' if kind == 'truncated' else 'ε'} = {par:g}"] = {
            "min_gap": float(np.min(gap)), "share_repeated": float(np.mean(gap <= rd.fusion_set.PERRON_RTOL)),
            "min_weight": float(np.min(w)), "share_zero_weight": float(np.mean(np.any(w <= 0.0, axis=1))),
            "min_lambda": float(np.min(lam)), "lambda_is_modulus": bool(np.all(lam >= np.abs(ev[:, 0]))),
            "max_residual": float(np.max(res))}
    fused_eig, fused_row = np.einsum("ij,ij->i", eig_w, snaps), np.einsum("ij,ij->i", row_w, snaps)
    shifted = np.zeros(snapshots, dtype=bool)
    shifted[::2] = True
    return {
        "base": base, "deltas": deltas, "W": W,
        "unit_k_maxdiff": float(np.max(np.abs(rd.belief_degree(to_k).weights - wc))),
        "unit_f_maxdiff": float(np.max(np.abs(rd.belief_degree(to_f).weights - wc))),
        "unit_fconv_maxdiff": float(np.max(np.abs(rd.belief_degree(to_f, scale=1.8).weights - wc))),
        "unit_f_valdiff": float((rd.belief_degree(to_f).value - 32) / 1.8 - rd.belief_degree(snap).value),
        "eig_w": eig_w, "row_w": row_w,
        "rowsum_maxdiff": float(np.max(np.abs(eig_w - row_w))),
        "rowsum_valdiff_rms": float(np.sqrt(np.mean(np.einsum("ij,ij->i", eig_w - row_w, snaps) ** 2))),
        "mse_eig": float(np.mean((fused_eig - x) ** 2)),
        "mse_row": float(np.mean((fused_row - x) ** 2)),
        "sq_eig": (fused_eig - x) ** 2, "sq_row": (fused_row - x) ** 2, "shifted": shifted, "perron": perron,
        "bin_lam": (float(lam_b[-1]), float(lam_b[-2])),
        "bin_w": rd.belief_degree(xb, binary_eps=1.0).weights,
    }


#: Kinds of belief fusion of :func:`belief_parameter_study` and the analyst's parameter each varies.
BELIEF_KINDS: dict[str, str] = {"fuzzy": "scale s", "binary": "threshold ε", "binary (deletion)": "threshold ε",
                                "binary (deletion, min_support 1/3)": "threshold ε",
                                "binary (deletion, min_support 1)": "threshold ε",
                                "fuzzy, upper limit": "fusion upper limit m (融合上限)"}

#: ``min_support`` of each deletion kind of :data:`BELIEF_KINDS` (:func:`fusion.readings.fusion_set.binary_deletion`):
#: the share of the other readings that must trust a reading for it to be kept.
DELETION_SUPPORT: dict[str, float] = {"binary (deletion)": 0.5, "binary (deletion, min_support 1/3)": 1.0 / 3.0,
                                      "binary (deletion, min_support 1)": 1.0}


def belief_parameter_study(
    sigma: Sequence[float] = (0.5, 1.0, 2.0, 4.0),
    x: float = 900.0,
    params: Sequence[float] = (0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0, 32.0),
    snapshots: int = 200,
    shift: float = 10.0,
    seed: int = 2404,
    grid: Sequence[float] = (0.5, 1.0, 2.0, 4.0),
    limit_scale: float = 1.0,
) -> dict[str, Any]:
    r"""Experiment E2.4b: the fused value's dependence on the analyst's parameter, fuzzy against binary belief.

    The lecture rejects the binary belief (:math:`b_{ij} = 1` if :math:`|x_i - x_j| \le m_{ij}`, its
    "fusion upper limit" m, here ε) with its deletion rule as "too much influenced by subjective
    factors", and proposes the fuzzy exponential belief. Each needs a parameter in the readings' unit:
    the threshold ε, the scale s. On ``snapshots`` draws of the sensors at ``x`` (reading 1 shifted by
    U(0, ``shift``) in every other draw), each snapshot is fused with every value of ``params`` as s
    (fuzzy belief, Perron vector), as ε (the lecture's deletion rule,
    :func:`fusion.readings.fusion_set.binary_deletion`, with a reading kept when at least half, a third
    or all of the others trust it, :data:`DELETION_SUPPORT`; and the binary belief through its Perron
    vector, the book's construction), and as m, the fusion upper limit (融合上限): the fuzzy belief
    with scale ``limit_scale`` truncated to 0 beyond m. The spread of a snapshot's fused values over a
    grid of values measures how much the analyst's choice moves the result (:func:`belief_spread`); the
    squared errors and those of the arithmetic mean (``sq_mean``) say whether the rule does better than
    the plain average on that grid at all.

    Parameters
    ----------
    sigma : sequence of float
        Noise SDs of the sensors.
    x : float
        True value.
    params : sequence of float
        Every value of s, ε and m run (readings' unit), positive.
    snapshots : int
        Number of draws.
    shift : float
        Upper end of the uniform shift of reading 1 (every other draw).
    seed : int
    grid : sequence of float
        The primary grid (a subset of ``params``) of ``spread``.
    limit_scale : float
        Scale s of the truncated fuzzy belief.

    Returns
    -------
    dict
        ``fused[kind]`` (snapshots, len(params)) for every kind of :data:`BELIEF_KINDS`;
        ``spread[kind]`` (snapshots,): max − min over ``grid``; ``sq[kind]`` (snapshots, len(params)):
        squared errors; ``sq_mean`` (snapshots,): squared error of the arithmetic mean; ``params``, ``grid``,
        ``seed``, ``snapshots``, ``x``, ``shift``, ``limit_scale``.
    """
    sig = _sigmas(sigma, minimum=2)
    scalar(x, "x")
    vals = _values(params, "params")
    if np.any(vals <= 0):
        raise ValueError("params must be positive")
    g = _values(grid, "grid")
    if not set(g.tolist()) <= set(vals.tolist()):
        raise ValueError(f"grid must be a subset of params, got {tuple(g.tolist())}")
    snapshots = count(snapshots, "snapshots", minimum=2)
    if scalar(shift, "shift") < 0:
        raise ValueError(f"shift must be non-negative, got {shift!r}")
    seed = _seed(seed)
    ls = scalar(limit_scale, "limit_scale", lo=0.0, lo_open=True)
    rng = np.random.default_rng(seed)
    snaps = x + rng.normal(size=(snapshots, sig.size)) * sig
    snaps[::2, 0] += rng.uniform(0, shift, size=(snapshots + 1) // 2)
    fused = {
        "fuzzy": np.column_stack([rd.fuse_epochs(snaps, "belief_degree", scale=float(p)).values for p in vals]),
        "binary": np.column_stack([rd.fuse_epochs(snaps, "belief_degree", binary_eps=float(p)).values for p in vals]),
        **{kind: np.array([[rd.binary_deletion(r, float(p), min_support=q).value for p in vals] for r in snaps])
           for kind, q in DELETION_SUPPORT.items()},
        "fuzzy, upper limit": np.column_stack([rd.fuse_epochs(snaps, "belief_degree", scale=ls, limit=float(p)).values
                                               for p in vals]),
    }
    out = {"fused": fused, "sq": {k: (v - x) ** 2 for k, v in fused.items()}, "sq_mean": (snaps.mean(axis=1) - x) ** 2,
           "params": vals, "grid": g,
           "seed": seed, "snapshots": snapshots, "x": float(x), "shift": float(shift), "limit_scale": float(ls)}
    out["spread"] = {k: belief_spread(out, k, g) for k in fused}
    return out


def belief_spread(s: dict[str, Any], kind: str, values: ArrayLike) -> np.ndarray:
    r"""Per-snapshot spread (max − min) of the fused value over some of the parameter values of E2.4b.

    Parameters
    ----------
    s : dict
        Output of :func:`belief_parameter_study`.
    kind : str
        One of :data:`BELIEF_KINDS`.
    values : array_like
        Parameter values, each one of ``s["params"]`` (at least one).

    Returns
    -------
    ndarray, shape (snapshots,)
        Spread of each snapshot's fused value (readings' unit).
    """
    record(s, "s", ("fused", "params"), extra=True)  # the dict returned by belief_parameter_study
    one_of(kind, tuple(BELIEF_KINDS), "kind")
    v = _values(values, "values")
    pa = as_array(s["params"], "s['params']", ndim=1)
    fused = as_array(record(s["fused"], "s['fused']", (kind,), extra=True)[kind], f"s['fused'][{kind!r}]", ndim=2)
    if fused.shape[1] != pa.size:
        raise ValueError(f"s['fused'][{kind!r}] must have one column per s['params'] ({pa.size}), got {fused.shape}")
    params = list(pa)
    missing = [float(p) for p in v if float(p) not in params]
    if missing:
        raise ValueError(f"values must be among the study's params, got {missing}")
    idx = [params.index(float(p)) for p in v]
    return np.ptp(fused[:, idx], axis=1)


# --------------------------------------------------------------------------- E2.5
def ridge_study(
    xs: Sequence[float] = (0.5, 1.0, 3.0, 10.0),
    ms: Sequence[int] = (1, 5, 20, 100),
    m0: int = 5,
    sigma: float = 1.0,
    seed: int = 2501,
    seed_vector: int = 2502,
    draws: int = 2000,
    ks_fixed: Sequence[float] = (0.01, 0.1, 1.0),
    x_far: float = 273.65,
) -> dict[str, Any]:
    r"""Experiment E2.5: scalar ridge against least squares, and centralised vs distributed.

    Analytic MSE and reliability :math:`P(|\hat x-x|\le\sigma/\sqrt m)` on the grid
    k ∈ [0, 5] (501 points) for ``m0`` measurements; Monte-Carlo mean
    :math:`|\hat x_{RE}-\hat x_{LS}|` against m for x ∈ {1, 10}, k ∈ {0.5, 2}; the largest
    difference between centralised and distributed ridge on a random three-sensor vector problem
    at k ∈ {0, 1}; reliability at fixed ``ks_fixed`` and at the MSE-optimal :math:`k^* = \sigma^2/x^2`
    for every x of ``xs`` and ``x_far``; the gap between the least-squares and the ridge covariance
    of the vector problem.

    Parameters
    ----------
    xs : sequence of float
        True values x.
    ms : sequence of int
        Numbers of measurements m of the convergence study.
    m0 : int
        Number of measurements of the analytic curves.
    sigma : float
        Noise standard deviation.
    seed, seed_vector : int
        Seeds of the scalar Monte Carlo and of the vector problem.
    draws : int
        Monte-Carlo draws per (x, k, m).
    ks_fixed : sequence of float
        Fixed ridge parameters (> 0) of the reliability check.
    x_far : float
        A true value far from the shrinkage target (0.5 °C expressed in kelvin).

    Returns
    -------
    dict
        ``kgrid``; ``mse[x]``, ``rel[x]`` (501,); ``rows`` (x, k*, MSE(0), MSE(k=1), rel(0), rel(k=1),
        max rel, argmax rel k); ``conv[(x, k)]`` (len(ms),); ``bound_k1``; ``rel1_kelvin``;
        ``cen_dist_maxdiff``; ``rel_k``: list of dicts (x, k label, k, rel(k), rel(0), MSE(k), MSE(0))
        for x in ``xs`` + (``x_far``,) and k in ``ks_fixed`` and "k*"; ``sd_ratio_max``: largest
        SD(k)/SD(0) of the scalar estimate over k in (0, 5]; ``var_gap_min_eig``: smallest
        eigenvalue, over k in ``ks_fixed``, of :math:`A^{-1} - (A+kI)^{-1}A(A+kI)^{-1}` with
        :math:`A = \sum_i H_i^\top R_i^{-1}H_i` (least-squares minus ridge covariance of the
        centralised vector estimate), relative to the largest eigenvalue of :math:`A^{-1}`.
    """
    m_arr = _ints(ms, "ms")
    m0 = count(m0, "m0")
    s = scalar(sigma, "sigma", lo=0.0, lo_open=True)
    for i, x in enumerate(_values(xs, "xs").tolist()):
        _optimal_k_representable(x, s, f"xs[{i}]")
    _optimal_k_representable(scalar(x_far, "x_far"), s, "x_far")
    seed = _seed(seed)
    seed_vector = _seed(seed_vector, "seed_vector")
    draws = count(draws, "draws", minimum=2)
    allocation((draws, int(m_arr.max())), "ms and draws")
    kgrid = np.linspace(0, 5, 501)
    i1 = int(np.argmin(np.abs(kgrid - 1.0)))
    delta = sigma / np.sqrt(m0)
    mse, rel, rows = {}, {}, []
    for x in xs:
        mom = rg.scalar_ridge_moments(m0, sigma, x, kgrid)
        b, s, mse[x] = mom.bias, mom.sd, mom.mse
        rel[x] = rg.reliability(b, s, delta)
        rows.append({"x": x, "k*": rg.optimal_ridge_k(sigma, x), "MSE(0)": mse[x][0], "MSE(k=1)": mse[x][i1],
                     "rel(0)": rel[x][0], "rel(k=1)": rel[x][i1], "max rel": rel[x].max(),
                     "argmax rel k": kgrid[np.argmax(rel[x])]})
    rng = np.random.default_rng(seed)
    conv = {}
    for x in (1.0, 10.0):
        for k in (0.5, 2.0):
            conv[x, k] = np.array([np.mean(np.abs(rng.normal(x, sigma, size=(draws, m)).sum(axis=1) * (1 / (m + k) - 1 / m)))
                                   for m in ms])
    rngc = np.random.default_rng(seed_vector)
    Hs = [rngc.normal(size=(4, 2)) for _ in range(3)]
    Rs = []
    for _ in range(3):
        A = rngc.normal(size=(4, 4))
        Rs.append(A @ A.T + 4 * np.eye(4))
    ys = [rngc.normal(size=4) for _ in range(3)]
    cd = max(float(np.max(np.abs(rg.ridge_centralised(Hs, Rs, ys, k) - rg.ridge_distributed(Hs, Rs, ys, k))))
             for k in (0.0, 1.0))
    rel_k = []
    for x in (*xs, x_far):
        mom0 = rg.scalar_ridge_moments(m0, sigma, x, 0.0)
        b0, s0, mse0 = mom0.bias, mom0.sd, mom0.mse
        rel0 = float(rg.reliability(b0, s0, delta))
        for label, k in [(f"k = {kf:g}", kf) for kf in ks_fixed] + [("k*", rg.optimal_ridge_k(sigma, x))]:
            momk = rg.scalar_ridge_moments(m0, sigma, x, k)
            b, sd, mk = momk.bias, momk.sd, momk.mse
            rel_k.append({"x": float(x), "k label": label, "k": float(k), "rel(k)": float(rg.reliability(b, sd, delta)),
                          "rel(0)": rel0, "MSE(k)": float(mk), "MSE(0)": float(mse0)})
    sd_grid = rg.scalar_ridge_moments(m0, sigma, 1.0, kgrid[1:]).sd
    A = sum(H.T @ np.linalg.solve(R, H) for H, R in zip(Hs, Rs))
    P_ls = np.linalg.inv(A)
    gaps = []
    for k in ks_fixed:
        G = np.linalg.inv(A + k * np.eye(A.shape[0]))
        gaps.append(float(np.linalg.eigvalsh(P_ls - G @ A @ G).min()))
    return {"kgrid": kgrid, "mse": mse, "rel": rel, "rows": rows, "ms": np.asarray(ms), "conv": conv, "m0": m0,
            "bound_k1": float(np.sqrt((2 * m0 + 1) / m0)),
            "rel1_kelvin": float(rg.reliability(rg.scalar_ridge_moments(m0, sigma, 273.65, 1.0).bias, rg.scalar_ridge_moments(m0, sigma, 273.65, 1.0).sd, delta)),
            "cen_dist_maxdiff": cd, "rel_k": rel_k, "ks_fixed": tuple(float(k) for k in ks_fixed),
            "sd_ratio_max": float(np.max(sd_grid) * np.sqrt(m0) / sigma),
            "var_gap_min_eig": min(gaps) / float(np.linalg.eigvalsh(P_ls).max())}


def _optimal_k_representable(x: float, sigma: float, name: str) -> None:
    """Refuse a true value ``x`` whose MSE-optimal ridge :math:`k^* = \\sigma^2/x^2` is not a representable number.

    ``x = 0`` has no finite :math:`k^*`; beyond [``MIN_MAGNITUDE``, ``MAX_MAGNITUDE``] the moments at
    :math:`k^*` under- or overflow. The message names ``name`` and ``sigma``.
    """
    with np.errstate(all="ignore"):
        k = sigma**2 / x**2 if x else np.inf
    if not MIN_MAGNITUDE <= k <= MAX_MAGNITUDE:
        raise ValueError(f"{name} = {x!r} with sigma = {sigma!r} gives an optimal ridge parameter k* = sigma^2/x^2 = "
                         f"{k:.3g}, outside [{MIN_MAGNITUDE:g}, {MAX_MAGNITUDE:g}] (x = 0 has no finite k*)")


# --------------------------------------------------------------------------- E2.6
def wavelet_study(
    length: int = 1024,
    runs: int = 100,
    gains: Sequence[float] = (1.0, 1.5, 0.8, 2.0),
    sigma: Sequence[float] = (0.05, 0.1, 0.2, 0.4),
    seed: int = 2601,
) -> dict[str, Any]:
    r"""Experiment E2.6: wavelet denoising + normalised fusion, three normalisers.

    :math:`X_j = g_jS + e_j`, :math:`S(n) = 2 + \sin(2\pi n/256) + 0.5\sin(2\pi n/64)`.

    Parameters
    ----------
    length : int
        Samples per signal I.
    runs : int
        Monte-Carlo runs.
    gains : sequence of float
        Sensor gains :math:`g_j`.
    sigma : sequence of float
        Noise standard deviation of each sensor.
    seed : int
        Seed of the noise.

    Returns
    -------
    dict
        ``n``, ``truth`` (sensors, length), ``noise`` (runs, sensors, length); ``err[key]``: per-run
        MSE against :math:`g_jS`, shape (runs, sensors), for key in raw, denoised, max, median, lsq;
        ``gain_err`` (relative gain error of the max normaliser), ``weights`` (runs, sensors).
    """
    length = count(length, "length", minimum=16)
    runs = count(runs, "runs")
    g_chk = _values(gains, "gains")
    if np.any(g_chk <= 0):
        raise ValueError(f"gains must be positive (each normaliser divides by a sensor's gain), got {g_chk.tolist()}")
    s_chk = _sigmas(sigma, minimum=2)
    if s_chk.size != g_chk.size:
        raise ValueError(f"gains and sigma must have matching lengths, got {g_chk.size} and {s_chk.size}")
    seed = _seed(seed)
    g = np.asarray(gains, dtype=float)
    sig = np.asarray(sigma, dtype=float)
    n = np.arange(length)
    S = 2 + np.sin(2 * np.pi * n / 256) + 0.5 * np.sin(2 * np.pi * n / 64)
    truth = g[:, None] * S
    noise = np.random.default_rng(seed).normal(size=(runs, g.size, length)) * sig[:, None]
    err = {key: np.zeros((runs, g.size)) for key in ("raw", "denoised", "max", "median", "lsq")}
    gain_err = np.zeros((runs, g.size))
    weights = np.zeros((runs, g.size))
    for r in range(runs):
        X = truth + noise[r]
        err["raw"][r] = np.mean((X - truth) ** 2, axis=1)
        for nm in ("max", "median", "lsq"):
            rec = wv.reconstruct(X, normaliser=nm)
            err[nm][r] = np.mean((rec.reconstructed - truth) ** 2, axis=1)
            if nm == "max":
                weights[r] = rec.weights
                err["denoised"][r] = np.mean((rec.denoised - truth) ** 2, axis=1)
                gain_err[r] = rec.norms / (g * S.max()) - 1
    return {"n": n, "truth": truth, "noise": noise, "gains": g, "sigma": sig, "err": err,
            "gain_err": gain_err, "weights": weights, "runs": runs, "seed": seed}


# --------------------------------------------------------------------------- E2.7
def correlated_study(
    sigma: Sequence[float] = (1.0, 2.0, 3.0),
    sigma_env: float = 1.5,
    runs: int = 20000,
    x: Sequence[float] = (1.0, -2.0),
    seed: int = 2701,
    sizes: Sequence[int] = (6, 60, 600),
) -> dict[str, Any]:
    r"""Experiment E2.7: correlated noise, LDLᵀ pseudo-measurements, GLS and the naive fusion.

    :math:`R = \mathrm{diag}(\sigma_i^2)\otimes I_2 + \sigma_e^2\mathbf 1\mathbf 1^\top\otimes I_2`,
    :math:`H_i = I_2`.

    Parameters
    ----------
    sigma : sequence of float
        Own noise standard deviation :math:`\sigma_i` of each sensor.
    sigma_env : float
        Standard deviation :math:`\sigma_e` of the common environmental noise.
    runs : int
        Monte-Carlo runs.
    x : sequence of float
        True 2-D state.
    seed : int
        Seed of the noise.
    sizes : sequence of int
        Problem sizes of the operation counts.

    Returns
    -------
    dict
        ``mrm_offdiag`` (largest off-diagonal of :math:`MRM^\top`, relative to max|R|),
        ``rel_ldl_gls`` (largest relative difference of the two estimates); errors ``eg``, ``en``
        (2, runs); claimed covariances ``Pg``, ``Pn``; ``mse_gls``, ``mse_naive``, ``nees_gls``,
        ``nees_naive``, ``nees_samples`` (GLS, naive), ``sq_gls``, ``sq_naive`` (per-run squared
        error); ``flops``: rows of :func:`fusion.readings.correlated.operation_counts` for ``sizes``.
    """
    _sigmas(sigma, minimum=1)
    scalar(sigma_env, "sigma_env", lo=0.0)
    runs = count(runs, "runs", minimum=2)
    if as_array(x, "x", ndim=1).size != 2:
        raise ValueError("x must have length 2")
    seed = _seed(seed)
    _ints(sizes, "sizes")
    sig = np.asarray(sigma, dtype=float)
    N = sig.size
    R = np.kron(np.diag(sig**2), np.eye(2)) + sigma_env**2 * np.kron(np.ones((N, N)), np.eye(2))
    H = np.kron(np.ones((N, 1)), np.eye(2))
    xt = np.asarray(x, dtype=float)
    L = co.ldl_unpivoted(R).L
    M = co.unit_lower_inverse(L)
    D = M @ R @ M.T
    z = H @ xt[:, None] + np.linalg.cholesky(R) @ np.random.default_rng(seed).normal(size=(2 * N, runs))
    gls, naive = co.gls(H, R, z), co.naive_fusion(H, R, z, block=2)
    xg, Pg, xn, Pn = gls.x, gls.P, naive.x, naive.P
    xl = co.pseudo_measurement_fusion(H, R, z).x
    eg, en = xg - xt[:, None], xn - xt[:, None]
    nees = [np.einsum("ir,ij,jr->r", e, np.linalg.inv(P), e) for e, P in ((eg, Pg), (en, Pn))]
    flops = [{"Nm": Nm, **co.operation_counts(Nm, 2)} for Nm in sizes]
    return {"R": R, "mrm_offdiag": float(np.max(np.abs(D - np.diag(np.diag(D)))) / np.abs(R).max()),
            "rel_ldl_gls": float(np.max(np.abs(xl - xg)) / np.max(np.abs(xg))),
            "eg": eg, "en": en, "Pg": Pg, "Pn": Pn,
            "sq_gls": np.sum(eg**2, axis=0), "sq_naive": np.sum(en**2, axis=0),
            "mse_gls": float(np.mean(np.sum(eg**2, axis=0))), "mse_naive": float(np.mean(np.sum(en**2, axis=0))),
            "nees_gls": float(np.mean(nees[0])), "nees_naive": float(np.mean(nees[1])), "nees_samples": nees,
            "runs": runs, "flops": flops}


# --------------------------------------------------------------------------- benchmark
#: Noise SDs of the shared benchmark (°C).
BENCH_SIGMA = (0.5, 1.0, 1.5, 2.0, 4.0)


def _snapshot_errors(X: np.ndarray, truth: float, sigma: np.ndarray, eps: float) -> dict[str, np.ndarray]:
    """Squared error of each method's fusion of the readings at k = K (own weights, current readings)."""
    xK = X[:, -1]

    def current(w: np.ndarray) -> np.ndarray:
        return np.einsum("ij,ij->i", w, xK)

    est = {
        "oracle (inverse variance)": xK @ wt.optimal_weights(sigma**2),
        "mean": xK.mean(axis=1),
        # the lecture's variance estimates applied to the current readings (the benchmark compares snapshot
        # fusions at k = K); two guards for non-positive estimates, the package's floor and |σ̂²|
        "2.1 AWF (lecture, floor)": current(wt.inverse_variance_weights(wt.running_variances(X, "lecture")[:, -1])),
        "2.1 AWF (lecture, |σ̂²|)": current(wt.inverse_variance_weights(wt.running_variances(X, "lecture")[:, -1],
                                                                       guard="abs")),
        "2.1 AWF (centred)": current(wt.inverse_variance_weights(wt.running_variances(X, "centred")[:, -1])),
        "2.2 LS learning": wt.ls_learning(X).values[:, -1],
        "2.2 LS learning, corrected": wt.ls_learning(X, corrected=True).values[:, -1],
        "2.3 check + AWF (centred)": current(cs.consistency_awf(X, eps, "centred").awf.weights[:, -1]),
        "2.4 belief degree (s = 1)": rd.fuse_epochs(xK, "belief_degree").values,
        "001 optimal fusion set": rd.fuse_epochs(xK, "optimal_fusion_set").values,
        "001 ref. [11] support degree": rd.fuse_epochs(xK, "support_degree").values,
        # what a practitioner would use to resist an abnormal reading without any model (fusion.readings.robust)
        "median": robust_fuse(xK, "median"),
        "biweight (Tukey)": robust_fuse(xK, "biweight"),
    }
    return {name: (v - truth) ** 2 for name, v in est.items()}


def benchmark(
    seeds: Sequence[int] = (9001, 9002, 9003),
    runs: int = 500,
    samples: int = 100,
    levels: Sequence[float] = (0.0, 900.0),
    bias: float = 30.0,
    fault_sensor: int = 2,
    fault_from: int = 50,
    sigma: Sequence[float] = BENCH_SIGMA,
    faults: Sequence[bool] = (False, True),
) -> dict[tuple[int, float, bool], dict[str, np.ndarray]]:
    r"""Every readings-level method of chapters 01 and 02 on one shared setup.

    For each seed, level and fault flag: ``runs`` x ``samples`` readings of ``len(sigma)`` sensors
    (the same noise at both levels and with/without the fault); the fault adds ``bias`` to sensor
    ``fault_sensor`` from sample index ``fault_from`` on (still failed at k = K). The metric is the
    squared error of the value fused at k = K, each method applying its own weights (learned from
    samples 1..K where it learns) to the current readings. The consistency check uses
    :math:`\varepsilon = 3\sqrt2\,\sigma_{\max}`. The median and Tukey's biweight
    (:func:`fusion.readings.robust.robust_fuse`) are the model-free robust baselines.

    Parameters
    ----------
    seeds : sequence of int
        One setup per seed.
    runs, samples : int
        Monte-Carlo runs and instants K per run.
    levels : sequence of float
        True values (°C).
    bias : float
        Fault bias (°C).
    fault_sensor : int
        Faulty sensor (0-based).
    fault_from : int
        First faulty sample (0-based).
    sigma : sequence of float
        Noise standard deviation of each sensor (°C).
    faults : sequence of bool
        Which setups to run: without the fault (False), with it (True), or both (the default).

    Returns
    -------
    dict
        ``{(seed, level, fault): {method: per-run squared error, shape (runs,)}}``.
    """
    if isinstance(seeds, (str, bytes)):
        raise TypeError("seeds must be a sequence of ints, got a string")
    seeds = check_seeds(seeds, "seeds")
    runs = count(runs, "runs")
    samples = count(samples, "samples")
    _values(levels, "levels")
    scalar(bias, "bias")
    sig_chk = _sigmas(sigma, minimum=3)
    _index(fault_sensor, sig_chk.size, "fault_sensor")
    fault_from = count(fault_from, "fault_from", minimum=0)  # >= samples: no faulty sample (valid)
    if isinstance(faults, (str, bytes)) or len(faults) == 0 or any(not isinstance(f, (bool, np.bool_)) for f in faults):
        raise ValueError(f"faults must be a non-empty sequence of bools, got {faults!r}")
    sig = np.asarray(sigma, dtype=float)
    eps = 3 * np.sqrt(2) * sig.max()
    results = {}
    for seed in seeds:
        noise = np.random.default_rng(seed).normal(size=(runs, samples, sig.size)) * sig
        for X0 in levels:
            for fault_on in faults:
                X = X0 + noise.copy()
                if fault_on:
                    X[:, fault_from:, fault_sensor] += bias
                results[seed, float(X0), fault_on] = _snapshot_errors(X, float(X0), sig, eps)
    return results


def _benchmark_results(results: object) -> dict[tuple[int, float, bool], dict[str, np.ndarray]]:
    """The output of :func:`benchmark`, checked entry by entry (rule 12 of the shared validation).

    Keys ``(seed, level, fault)`` covering every (seed, scenario) pair; values dicts of one set of
    methods, each a non-empty 1-D array of finite squared errors.
    """
    if not isinstance(results, dict):
        raise TypeError(f"results must be a dict (from benchmark), got {type(results).__name__}")
    if not results:
        raise ValueError("results is empty")
    out, methods = {}, None
    for key, entry in results.items():
        path = f"results[{key!r}]"
        if not isinstance(key, tuple) or len(key) != 3:
            raise TypeError(f"results must be keyed by (seed, level, fault) tuples, got {key!r}")
        check_seed(key[0], f"{path}: the seed")
        scalar(key[1], f"{path}: the level")
        instance_of(key[2], (bool, np.bool_), f"{path}: the fault flag")
        if not isinstance(entry, dict) or not entry:
            raise TypeError(f"{path} must be a non-empty dict of method -> squared errors, got {type(entry).__name__}")
        if methods is None:
            methods = list(entry)
        record(entry, path, tuple(methods))
        out[key] = {m: as_array(entry[m], f"{path}[{m!r}]", ndim=1, nonnegative=True) for m in methods}
    seeds = {k[0] for k in out}
    scen = {k[1:] for k in out}
    if len(out) != len(seeds) * len(scen):
        raise ValueError(f"results must hold every (seed, scenario) pair: {len(seeds)} seeds x {len(scen)} scenarios, "
                         f"got {len(out)} entries")
    return out


def seed_stability(results: dict[tuple[int, float, bool], dict[str, np.ndarray]], n_se: float = 3.0) -> dict[str, Any]:
    r"""How stable the benchmark's orderings are over seeds.

    For each scenario (level, fault): the rank of every method by mean squared error in every seed;
    and, for the pairs of methods whose MSEs differ by more than ``n_se`` combined standard errors
    in the first seed, how many change order in the other seeds.

    Parameters
    ----------
    results : dict
        Output of :func:`benchmark`.
    n_se : float

    Returns
    -------
    dict
        ``seeds``, ``scenarios`` (list of (level, fault)), ``methods``, ``ranks[scenario]``
        (seeds, methods), ``n_stable`` (scenarios whose full ranking is identical over seeds),
        ``n_sig`` (resolved pairs), ``n_rev`` (reversals among them in the other seeds).
    """
    results = _benchmark_results(results)
    scalar(n_se, "n_se", lo=0.0, lo_open=True)
    seeds = sorted({k[0] for k in results}, key=[k[0] for k in results].index)
    scen = sorted({k[1:] for k in results})
    methods = list(results[(seeds[0], *scen[0])])
    ranks = {}
    for s in scen:
        mses = np.array([[results[(sd, *s)][m].mean() for m in methods] for sd in seeds])
        ranks[s] = np.array([np.argsort(np.argsort(row, kind="stable"), kind="stable") + 1.0 for row in mses])
    n_sig = n_rev = 0
    for s in scen:
        r0 = results[(seeds[0], *s)]
        mse0 = {m: r0[m].mean() for m in methods}
        se0 = {m: r0[m].std() / np.sqrt(r0[m].size) for m in methods}
        for i, a in enumerate(methods):
            for b in methods[i + 1:]:
                if abs(mse0[a] - mse0[b]) > n_se * np.hypot(se0[a], se0[b]):
                    n_sig += 1
                    sign = np.sign(mse0[a] - mse0[b])
                    n_rev += sum(int(np.sign(results[(sd, *s)][a].mean() - results[(sd, *s)][b].mean()) != sign)
                                 for sd in seeds[1:])
    n_stable = sum(int(np.all(ranks[s] == ranks[s][0])) for s in scen)
    return {"seeds": seeds, "scenarios": scen, "methods": methods, "ranks": ranks,
            "n_stable": n_stable, "n_sig": n_sig, "n_rev": n_rev}
