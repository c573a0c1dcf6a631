"""Importance sampling of the normaliser: the variance study and the replicates of the estimate.

Part of :mod:`fusion.book.chapters.chernoff` (chapter 06, patent CN107330468B), which re-exports its public names."""

from __future__ import annotations

from dataclasses import dataclass
from fusion._guards import own_underflow
from fusion._results import ResultSpec, flag, integer, number, table, validated_post_init
from fusion._counts import seed as check_seed
from fusion.book.study_cache import study_cache
from typing import Any

import numpy as np
import pandas as pd

from fusion._limits import work
from fusion._validation import FloatArray, as_rng, allocation, instance_of
from fusion.book.tables import rounded
from fusion.estimates import chernoff as ch, mixtures as mx
from fusion.book.chapters.chernoff.settings import STUDY_RUNS
from fusion.book.chapters.chernoff.mixture import toy
from fusion.book.glue import GlueValues
from fusion._counts import count, count_ceiling, input_allocation

__all__ = ["IsVarianceStudy", "is_variance_study", "is_replicates", "is_replicate_values"]


# --------------------------------------------------------------------------- importance-sampling variance
#: Columns of the importance-sampling bias table that its glue and check read (issue 36: named once): the
#: predicted bias, the sampled mean bias and its standard error.
BIAS_PREDICTED = "bias predicted"
BIAS_SAMPLED = "bias sampled"
BIAS_SE = "bias se"


def _moment_region(covs: list[FloatArray], e0: FloatArray, k: int) -> Any:
    r"""ω ↦ smallest eigenvalue of :math:`\sum_i(k\varepsilon_i - (k-1)\varepsilon^{(0)}_i)P_i^{-1}` (two Gaussians).

    The k-th moment of the weights :math:`p_\varepsilon/g` under :math:`g = p_{\varepsilon^{(0)}}` is finite iff
    this matrix is positive definite: the integrand :math:`p_\varepsilon^k/g^{k-1}` is a Gaussian kernel with
    precision :math:`kP^{-1} - (k-1)G^{-1}`.
    """
    infos = [np.linalg.inv(c) for c in covs]

    def min_eig(w: float) -> float:
        e = np.array([w, 1.0 - w])
        return float(np.min(np.linalg.eigvalsh(sum((k * e[i] - (k - 1) * e0[i]) * infos[i] for i in range(2)))))
    return min_eig


#: The exponents whose rows :meth:`IsVarianceStudy.glue` reads (by index: the table must hold them once).
_GLUED_OMEGAS = (0.2, 0.7, 0.8, 0.1)

#: The cells :func:`is_variance_study` makes finite, which the glue reads (decision 33b): the sampled bias, its
#: standard error (>= 0) and the median. ``rho`` (infinite outside the finite-variance interval) and the predicted
#: bias (NaN there) have no cell rule: an infinite or NaN value is one the producer makes.
_CELLS = {BIAS_SAMPLED: (-np.inf, np.inf, False), BIAS_SE: (0.0, np.inf, False), "median": (-np.inf, np.inf, False)}


@dataclass(frozen=True)
class IsVarianceStudy:
    """Bias of the importance-sampled objective and the finite-moment regions, on the Gaussian pair of
    :func:`criteria_example` with the proposal at ω⁽⁰⁾ = 1/2.

    Attributes
    ----------
    table : pandas.DataFrame
        One row per ω (the index; no ω twice, ω = 0.1, 0.2, 0.7 and 0.8 among them): ``rho`` (closed form :func:`fusion.estimates.chernoff.is_second_moment`, inf outside
        the region), ``rho (sampled)``, ``3rd moment finite`` (bool), ``bias predicted`` (-(ρ-1)/(2R), nats;
        NaN outside), ``bias sampled`` and ``bias se`` (mean of Ĵ - log Z over the replicates and its standard
        error), ``median`` (median of Ĵ - log Z, a typical estimate's error).
    lo, hi : float
        The finite-variance interval of ω (bisection on the smallest eigenvalue of Λ(ω), eq. ``eq-chf-is-region``).
    lo3, hi3 : float
        The interval where the weights' third moment is finite (:math:`3P^{-1} - 2G^{-1} \\succ 0`), where the
        first-order bias formula applies.
    R, replicates : int
        Samples per estimate and replicates per ω.
    ok : bool
        Where the third moment is finite (and ω ≠ ω⁽⁰⁾, where the bias is 0): sampled bias within 3 standard
        errors of the prediction; where the fourth moment is finite, sampled ρ within 5 % of the closed form;
        outside the finite-variance interval, ρ infinite.
    power : float
        The largest ``|bias predicted| / bias se`` over the rows tested: above 3, an estimator without bias
        would fail the test (the test can fail).
    """

    table: pd.DataFrame
    lo: float
    hi: float
    lo3: float
    hi3: float
    R: int
    replicates: int
    ok: bool
    power: float

    __result_spec__ = ResultSpec(
        {"table": table("rho", "3rd moment finite", BIAS_PREDICTED, BIAS_SAMPLED, BIAS_SE, "median",
                        index=_GLUED_OMEGAS, cells=_CELLS),
         **{name: number(bounds=(0.0, 1.0)) for name in ("lo", "hi", "lo3", "hi3")}, "R": integer(1),
         "replicates": integer(2), "ok": flag(), "power": number()},
        relations=(lambda v, cls: _regions_relation(v, cls),))
    __post_init__ = validated_post_init


    def glue(self) -> GlueValues:
        """Glue values ``chf_isv_*``: the intervals, R, replicates, rows of the table and the test's power."""
        t = self.table
        v: dict[str, Any] = {"chf_isv_lo": rounded(self.lo), "chf_isv_hi": rounded(self.hi),
                             "chf_isv_lo3": rounded(self.lo3), "chf_isv_hi3": rounded(self.hi3), "chf_isv_r": self.R,
                             "chf_isv_reps": self.replicates, "chf_isv_power": rounded(self.power, 1)}
        for w, key in zip(_GLUED_OMEGAS, ("02", "07", "08", "01")):
            v[f"chf_isv_bias_{key}"] = rounded(float(t.loc[w, BIAS_SAMPLED]), 5)
            v[f"chf_isv_se_{key}"] = rounded(float(t.loc[w, BIAS_SE]), 5)
            v[f"chf_isv_pred_{key}"] = rounded(float(t.loc[w, BIAS_PREDICTED]), 5)
            v[f"chf_isv_median_{key}"] = rounded(float(t.loc[w, "median"]), 5)
        v["chf_isv_rho_08"] = rounded(float(t.loc[0.8, "rho"]))
        v["chf_isv_over_08"] = rounded(100 * float(t.loc[0.8, BIAS_PREDICTED] / t.loc[0.8, BIAS_SAMPLED] - 1), 0)
        v["chf_isv_median_ratio_08"] = rounded(float(t.loc[0.8, "median"] / t.loc[0.8, BIAS_SAMPLED]), 1)
        return v


def _regions_relation(values: dict[str, Any], cls: str) -> None:
    """The finite-third-moment interval lies inside the finite-variance interval: lo <= lo3 <= hi3 <= hi."""
    lo, lo3, hi3, hi = (values[k] for k in ("lo", "lo3", "hi3", "hi"))
    if not lo <= lo3 <= hi3 <= hi:
        raise ValueError(f"{cls}.lo, lo3, hi3, hi must be ordered lo <= lo3 <= hi3 <= hi (the third moment's interval "
                         f"inside the variance's), got {lo}, {lo3}, {hi3}, {hi}")


@own_underflow  # underflow to 0 by design (a kernel, a density or normalised weights: fuzz 33b D6)
def is_variance_study(rng: np.random.Generator, R: int = 100, replicates: int = 20_000) -> IsVarianceStudy:
    """Check the bias of Ĵ and the finite-moment regions of the IS weights numerically (Gaussian pair).

    Parameters
    ----------
    rng : numpy.random.Generator
        Draws the samples from the proposal.
    R : int
        Samples per estimate of Ĵ (>= 1).
    replicates : int
        Estimates per ω, at least 2 (the standard error of the sampled bias falls as 1/sqrt(replicates): 20,000 make
        the predicted bias several standard errors from zero, so the test can fail; one gives no standard error).

    Returns
    -------
    IsVarianceStudy
        Predicted and sampled bias of Ĵ and ρ at nine values of ω, the finite-moment regions' ends and the check's
        verdict.

    Raises
    ------
    TypeError
        ``rng`` not a Generator, ``R`` or ``replicates`` not an integer.
    ValueError
        ``R`` below 1, ``replicates`` below 2, or replicates x R samples beyond the memory or input budget.
    """
    as_rng(rng)  # a Generator itself, over a numpy bit generator (fuzz 57b C1)
    R, replicates = count(R, "R"), count(replicates, "replicates", minimum=2)
    allocation((replicates, R, 2), "replicates and R")  # the samples, before they are drawn
    input_allocation((replicates * R, 2), "replicates and R")  # and as the densities' input
    a, A = np.array([0.0, 0.0]), np.diag([4.0, 1.0])
    b, B = np.array([2.0, 1.0]), np.array([[1.0, 0.5], [0.5, 3.0]])
    means, covs, e0 = [a, b], [A, B], np.array([0.5, 0.5])
    g = ch.chernoff_fuse_gaussians(means, covs, e0)

    def edge(f: Any, inside: float, outside: float) -> float:
        if f(outside) > 0:
            return outside
        for _ in range(60):
            mid = 0.5 * (inside + outside)
            inside, outside = (mid, outside) if f(mid) > 0 else (inside, mid)
        return inside
    m2, m3, m4 = (_moment_region(covs, e0, k) for k in (2, 3, 4))
    lo, hi = edge(m2, 0.5, 0.0), edge(m2, 0.5, 1.0)
    lo3, hi3 = edge(m3, 0.5, 0.0), edge(m3, 0.5, 1.0)
    x = g.x + rng.standard_normal((replicates, R, 2)) @ np.linalg.cholesky(g.P).T
    log_g = mx.gaussian_logpdf(x.reshape(-1, 2), g.x, g.P).reshape(replicates, R)
    rows = {}
    for w in (0.0, 0.1, 0.2, 0.3, 0.5, 0.7, 0.8, 0.9, 1.0):
        t = ch.chernoff_fuse_gaussians(means, covs, [w, 1 - w])
        lw = mx.gaussian_logpdf(x.reshape(-1, 2), t.x, t.P).reshape(replicates, R) - log_g
        j = mx.logsumexp(lw, axis=1) - np.log(R)  # Ĵ - log Z: the target is normalised
        rho = ch.is_second_moment(means, covs, [w, 1 - w], e0)
        rows[w] = {"rho": rho, "rho (sampled)": float(np.mean(np.exp(2 * lw))), "3rd moment finite": m3(w) > 0,
                   BIAS_PREDICTED: -(rho - 1) / (2 * R) if np.isfinite(rho) else np.nan, BIAS_SAMPLED: float(j.mean()),
                   BIAS_SE: float(j.std(ddof=1) / np.sqrt(replicates)), "median": float(np.median(j))}
    table = pd.DataFrame.from_dict(rows, orient="index")
    table.index.name = "ω"
    test = table[table["3rd moment finite"] & (table.index != e0[0])]
    fourth = [w for w in table.index if m4(w) > 0]
    outside = [w for w in table.index if w < lo or w > hi]
    ok = bool(np.all(np.abs(test[BIAS_SAMPLED] - test[BIAS_PREDICTED]) <= 3 * test[BIAS_SE])
              and np.all(np.abs(table.loc[fourth, "rho (sampled)"] / table.loc[fourth, "rho"] - 1) <= 0.05)
              and np.all(np.isinf(table.loc[outside, "rho"])))
    power = float(np.max(np.abs(test[BIAS_PREDICTED]) / test[BIAS_SE]))
    num = table.columns.drop("3rd moment finite")
    table[num] = table[num].round(5) + 0.0  # no "-0.0" in the displayed table
    return IsVarianceStudy(table=table, lo=lo, hi=hi, lo3=lo3, hi3=hi3, R=R, replicates=replicates, ok=ok,
                           power=power)


@study_cache(maxsize=4)
def _sample_sets(runs: int, r: int) -> tuple[int, int]:
    """``runs`` sets of ``r`` samples, drawn in one call: both positive counts whose product is within the ceiling
    of a sample count (fuzz 19, F6: a derived ``n`` was refused under its internal name), named."""
    runs, r = count(runs, "runs"), count(r, "r")
    ceiling = count_ceiling("samples")
    if runs * r > ceiling:
        raise ValueError(f"runs and r give runs x r = {runs * r:,} importance samples, beyond the ceiling of "
                         f"{ceiling:,} (rule 9; at r = {r:,} at most {ceiling // r:,} runs)")
    return runs, r


#: Units (``fusion._limits.MAX_WORK``'s 10 ns) of one set of :func:`is_replicates`: its SLSQP minimisation on the
#: simplex, about 1.5 ms (r = 2, runs 200 -> 2,000: 0.286 -> 2.951 CPU-s, process_time, minimum of 2,
#: OPENBLAS_NUM_THREADS=1, the shared machine loaded), weighed twice (book audit 76: no work budget, only the ceiling
#: of a sample count, so 5e6 sets of r = 2, about 2 CPU-hours, were accepted).
_IS_SET = 300_000
#: Units of one importance sample of :func:`is_replicates` (drawn, both mixtures' and the proposal's densities, the
#: objective's sums): about 1.4 us (runs = 2, r 1e5 -> 1e6: 0.214 -> 2.832 CPU-s, as above), weighed twice (book
#: audit 76: 10**7 samples, about 14 CPU-s, were accepted; ``is_replicate_values``' two calls at 500 runs, ~30).
_IS_SAMPLE = 300


def _replicates_work(runs: int, rs: tuple[int, ...], names: str) -> int:
    """Refuse :func:`is_replicates` calls of ``runs`` sets at each R of ``rs`` beyond the work budget, by ``names``."""
    return work((sum(runs * (_IS_SET + r * _IS_SAMPLE) for r in rs),), names)


#: The offset :func:`is_replicates` adds to its seed (``default_rng(seed + 100)``): the largest a chapter-06 study adds.
_IS_OFFSET = 100


def is_replicates(seed: int, r: int, runs: int = STUDY_RUNS) -> FloatArray:
    r"""Minimiser errors of importance sampling on the two-mixture example over independent sample sets.

    One stream (``default_rng(seed + 100)``) draws ``runs`` independent sets of ``r`` samples from the first-order
    mixture at ω = 0.5 (their densities evaluated in one call); each set's :math:`\hat J` (eq. ``eq-chf-is``) is
    minimised on the simplex.

    Parameters
    ----------
    seed : int
        The chapter's root seed.
    r : int
        Importance samples per replicate.
    runs : int
        Replicates (independent sample sets).

    Returns
    -------
    ndarray, shape (runs,)
        The absolute error of the importance-sampled minimiser of ω per replicate (do not modify: cached).

    Raises
    ------
    TypeError
        An argument not an integer.
    ValueError
        ``r`` or ``runs`` not positive, ``runs`` x ``r`` beyond the ceiling of a sample count, or the sets beyond
        the work budget (``fusion._limits.MAX_WORK``: about 3,300 sets of few samples, 3.3e6 samples).
    """
    runs, r = _sample_sets(runs, r)
    _replicates_work(runs, (r,), "runs and r")
    seed = check_seed(seed, span=_IS_OFFSET)   # an integer seed (rule 11), named; seed + 100 a seed too (fuzz 55 C1)
    t = toy(seed)
    gms = list(t.gms)
    g05 = ch.first_order_fusion(gms, [0.5, 0.5]).mixture
    xs = mx.gm_sample(g05, np.random.default_rng(seed + _IS_OFFSET), runs * int(r))
    L, lg = ch.log_densities(gms, xs), mx.gm_logpdf(g05, xs)
    sets = [slice(j * int(r), (j + 1) * int(r)) for j in range(runs)]
    return np.array([abs(float(ch.simplex_minimum(L[k], lg[k]).x[0]) - t.w_exact) for k in sets])


def is_replicate_values(seed: int, runs: int = STUDY_RUNS) -> GlueValues:
    """Glue ``chf_isr_*``: the importance-sampled minimiser's error over independent sample sets (record chf-is).

    Parameters
    ----------
    seed : int
        The chapter's root seed.
    runs : int
        Sample sets per R (:func:`is_replicates`).

    Returns
    -------
    dict
        ``chf_isr_runs`` (int), ``chf_isr_first_order`` (the first-order minimiser's error), ``chf_isr_err_hi`` and
        ``chf_isr_err_lo`` (mean error at R = 20 000 and 2 000), ``chf_isr_worse_lo`` (share of the sets at R = 2 000
        whose error exceeds the first-order one); 4 decimals (shares 2).

    Raises
    ------
    TypeError
        ``seed`` or ``runs`` not an integer.
    ValueError
        ``runs`` not positive, or so many that its sets of 20 000 samples pass the ceiling of a sample count, or
        both calls of :func:`is_replicates` beyond the work budget (``fusion._limits.MAX_WORK``: about 150 runs).
    """
    seed = check_seed(seed, span=_IS_OFFSET)   # is_replicates' seed + 100, checked before toy runs (fuzz 55 D1)
    runs, _ = _sample_sets(runs, 20_000)
    _replicates_work(runs, (20_000, 2_000), "runs")  # both calls at once, before the first (book audit 76)
    t = toy(seed)
    first_order = abs(t.w_first_order - t.w_exact)
    hi, lo = is_replicates(seed, 20_000, runs), is_replicates(seed, 2_000, runs)
    return {"chf_isr_runs": runs, "chf_isr_first_order": rounded(first_order), "chf_isr_err_hi": rounded(float(hi.mean())),
            "chf_isr_err_lo": rounded(float(lo.mean())), "chf_isr_worse_lo": rounded(float(np.mean(lo > first_order)), 2)}
