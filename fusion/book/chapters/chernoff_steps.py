r"""Chapter 06 (patent CN107330468B), appendix studies of single steps: review items closed with computed evidence.

Book-side studies that the chapter's appendix runs beside its records (none of them is a record, and none changes
a record's readings):

* step H: the :math:`O(1/R)` bias of the self-normalised importance weights, by the delta method and measured,
  with the exponent fixed and chosen on the same samples (:mod:`fusion.book.chapters.chernoff_snis`, whose public
  names are importable from here as well);
* step E: a defensive mixture proposal beside the first-order mixture and beside redrawing at
  :math:`\varepsilon^*` (:func:`defensive_mixture`, :func:`defensive_study`);
* the local filters: single-sensor posterior Cramér-Rao bounds beside the centralised one
  (:func:`single_sensor_crb`);
* step D: a sigma-point first-order fusion (after Günay et al. 2014) against the mixture of powers and the exact
  answer (:mod:`fusion.book.chapters.chernoff_first_order`).

The two-mixture example is :func:`fusion.scenarios.two_mixtures.toy_mixtures`; its exact references (the
minimiser :math:`\omega^*` of :math:`\log Z`, the fused mean) come from quadrature on the grid of
:func:`fusion.scenarios.two_mixtures.grid_log_normaliser`.

References
----------
* Hesterberg, T. (1995). Weighted average importance sampling and defensive mixture distributions.
   *Technometrics*, 37(2), 185-194.
* Tichavský, P., Muravchik, C. H., Nehorai, A. (1998). Posterior Cramér-Rao bounds for discrete-time
   nonlinear filtering. *IEEE Trans. Signal Processing* 46(5), 1386-1396.
* Günay, M., Orguner, U., Demirekler, M. (2014). Approximate Chernoff fusion of Gaussian mixtures using
   sigma-points. *Proceedings of the 17th International Conference on Information Fusion (FUSION 2014)*.
"""

from __future__ import annotations

from collections.abc import Mapping
import dataclasses
from dataclasses import dataclass
from fusion._guards import own_underflow
from fusion._results import ResultSpec, array, dict_of, instance, integer, nested, number, validated_post_init
from fusion._frozen import constant
from fusion.book.study_cache import study_cache
from typing import Any

import numpy as np
import pandas as pd
from numpy.typing import ArrayLike

from fusion._validation import (FloatArray, as_rng, as_array, count, frame_slice, instance_of, positive_scalar, text,
                                unit_scalar)
from fusion._counts import count_ceiling, input_allocation, sequence
from fusion._limits import work
from fusion.book.rulebook import judge_paired
from fusion.book.tables import rounded, sci
from fusion.estimates import chernoff as ch
from fusion.estimates.chernoff import mixture as chm
from fusion.estimates import mixtures as mx
from fusion.scenarios import two_mixtures
from fusion.scenarios.range_bearing import RangeBearingScenario, posterior_crb, simulate_target
from fusion.book.glue import GlueValues, _glue_prefix
from fusion._counts import seed as check_seed
from fusion._shown import shown

__all__ = [
    "toy_reference",
    "ToyReference",
    "defensive_mixture",
    "defensive_study",
    "DefensiveStudy",
    "paired_numbers",
    "study_truths",
    "single_sensor_crb",
    "single_sensor_values",
    "DEFENSIVE_LABELS",
    "CHAPTER_R",
]

#: Step H's names, which live in :mod:`fusion.book.chapters.chernoff_snis` (split off by concept when this module
#: passed the house limit of 1,000 lines): still importable from here, looked up there on first use. That module
#: reads this one's toy references and kernels, so a plain import of it here would be circular.
_STEP_H = frozenset({"SnisDelta", "snis_delta_terms", "SnisBiasStudy", "snis_bias_study", "ChosenBiasStudy",
                     "chosen_bias_study", "C_NORM", "ALONG", "ALONG_LOW", "ALONG_HIGH", "EXTRA_LOW", "EXTRA_HIGH"})


def __getattr__(name: str) -> Any:
    """Step H's names (``_STEP_H``), from :mod:`fusion.book.chapters.chernoff_snis` (PEP 562)."""
    if name in _STEP_H:
        from fusion.book.chapters import chernoff_snis
        return getattr(chernoff_snis, name)
    raise AttributeError(f"module {__name__} has no attribute {shown(name)}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | _STEP_H)

#: Importance samples per run in the chapter's tracking study (``RangeBearingScenario.n_samples``).
CHAPTER_R = 2000


@dataclass(frozen=True)
class ToyReference:
    """Exact references of the two-mixture example by quadrature.

    Attributes
    ----------
    gms : tuple of GaussianMixture
        A and B (:func:`fusion.scenarios.two_mixtures.toy_mixtures`).
    points : ndarray, shape (n², 2)
        The grid of :func:`fusion.scenarios.two_mixtures.grid_log_normaliser` (its defaults).
    cell : float
        Area of a grid cell.
    L : ndarray, shape (n², 2)
        :math:`\\log\\hat p_i` on the grid.
    omega_star : float
        Exact minimiser of :math:`\\log Z(\\omega, 1-\\omega)`.
    mean_star : ndarray, shape (2,)
        Mean of :math:`p_{\\varepsilon^*}`.
    proposal : GaussianMixture
        Step D's first-order mixture at uniform exponents (the chapter's proposal).
    """

    gms: tuple[mx.GaussianMixture, mx.GaussianMixture]
    points: FloatArray
    cell: float
    L: FloatArray
    omega_star: float
    mean_star: FloatArray
    proposal: mx.GaussianMixture

    __result_spec__ = ResultSpec({"gms": nested(mx.GaussianMixture, count=2), "points": array("n", 2),
                                  "cell": number(positive=True), "L": array("n", 2), "omega_star": number(bounds=(0.0, 1.0)),
                                  "mean_star": array(2), "proposal": instance(mx.GaussianMixture)})
    __post_init__ = validated_post_init


    @own_underflow  # underflow to 0 by design (a kernel, a density or normalised weights: fuzz 33b D6)
    def fused_mean(self, omega: ArrayLike) -> FloatArray:
        """Exact mean (k, 2) of :math:`p_{(\\omega, 1-\\omega)}` for each ``omega`` (k,) in [0, 1]."""
        w = np.atleast_1d(as_array(omega, "omega"))
        if np.any((w < 0) | (w > 1)):
            raise ValueError("omega must lie in [0, 1]")
        a = self.L[:, 0, None] * w + self.L[:, 1, None] * (1 - w)  # (n², k)
        a = np.exp(a - a.max(axis=0))
        a /= a.sum(axis=0)
        return np.stack([np.sum(a[:, j, None] * self.points, axis=0) for j in range(w.size)])


@study_cache(maxsize=1)
@own_underflow  # underflow to 0 by design (a kernel, a density or normalised weights: fuzz 33b D6)
def toy_reference() -> ToyReference:
    """The two-mixture example's exact references (cached; do not modify).

    Returns
    -------
    ToyReference
        The two mixtures, the quadrature grid, its cell and log densities, the exact ω* and fused mean there, and step
        D's proposal at ω = 1/2.
    """
    toy = two_mixtures.toy_mixtures()
    gms = (toy.a, toy.b)
    import inspect
    pars = inspect.signature(two_mixtures.grid_log_normaliser).parameters
    n, limit = pars["n"].default, pars["limit"].default
    axis = np.linspace(-limit, limit, n)
    X, Y = np.meshgrid(axis, axis)
    pts = np.column_stack([X.ravel(), Y.ravel()])
    L = _log_densities(list(gms), pts)
    cell = float((axis[1] - axis[0]) ** 2)

    def f(e: FloatArray) -> float:
        return float(mx.logsumexp(L[:, 0] * e[0] + L[:, 1] * e[1]))

    def g(e: FloatArray) -> FloatArray:
        a = L[:, 0] * e[0] + L[:, 1] * e[1]
        return np.sum(np.exp(a - mx.logsumexp(a))[:, None] * L, axis=0)
    w = float(ch.minimise_on_simplex(f, 2, jac=g, ftol=1e-12).x[0])
    ref = ToyReference(gms, pts, cell, L, w, np.zeros(2), ch.first_order_fusion(list(gms), [0.5, 0.5]).mixture)
    return dataclasses.replace(ref, mean_star=ref.fused_mean([w])[0])


#: The chapter's practical margin for paired comparisons, as a share of the compared method's mean (rule R2).
MARGIN = 0.05


def paired_numbers(a: ArrayLike, b: ArrayLike, prefix: str, decimals: int = 4,
                   relative_margin: float | None = None) -> GlueValues:
    """Paired summary of per-run values ``a`` against ``b`` (lower is better), as glue values.

    The deciding statistic of the rulebook's paired rule (mean difference, or median under heavy tails) with its
    95 % interval (:func:`fusion.book.rulebook.judge_paired`, no margin), beside the median difference and the
    share of runs in which ``a`` is lower. No status: these studies are not records.

    Parameters
    ----------
    a, b : array_like, shape (runs,)
        Per-run values of the two methods on the same runs.
    prefix : str
        Key prefix: ``<prefix>_stat`` must be an identifier (a glue key).
    decimals : int
        Rounding of the values.
    relative_margin : float, optional
        The chapter's practical margin as a share of b's mean (0.05): then ``<prefix>_region`` is the interval's
        region under rule R2 with that margin ("lower", "higher", "equivalent", "undecided", ...).

    Returns
    -------
    dict
        ``<prefix>_stat`` ("mean" or "median"), ``<prefix>_d``, ``<prefix>_lo``, ``<prefix>_hi``,
        ``<prefix>_med`` (median difference), ``<prefix>_won`` (share of runs with a < b), ``<prefix>_runs``, and
        ``<prefix>_region`` with ``relative_margin``. The statistic and its interval follow the rulebook's one tie
        rule (relative round-off, ``fusion.book.rulebook``): differences within round-off of the values' magnitude
        are ties, so values offset far beyond their differences (1e12 + x against 1e12 + x + 0.3) give
        ``_d = _lo = _hi = 0`` beside the raw ``_med`` and ``_won``; a shift far from the data is not unit-free.

    Raises
    ------
    ValueError
        ``a`` or ``b`` as :func:`fusion.book.rulebook.judge_paired` refuses them, or holding an infinite run:
        the glued summary is finite numbers (an infinite run makes a mean or median difference infinite or
        undefined, which no glued number can show); ``prefix`` whose keys are not identifiers of ASCII letters,
        digits and underscores.
    TypeError
        ``prefix`` not a string.
    """
    prefix = _glue_prefix(text(prefix, "prefix"), "prefix")  # the one rule of a glue-key prefix (ASCII identifiers)
    j = judge_paired(a, b, "less", 0.0)  # the shared check of paired runs, naming a or b
    av, bv = np.asarray(a, float), np.asarray(b, float)
    for name, v in (("a", av), ("b", bv)):
        if not np.all(np.isfinite(v)):
            raise ValueError(f"{name} must hold finite per-run values: a paired summary glued as numbers cannot "
                             "show an infinite run (judge such evidence with fusion.book.rulebook.judge_paired)")
    extra: dict[str, Any] = {}
    if relative_margin is not None:
        m = positive_scalar(relative_margin, "relative_margin") * abs(float(np.mean(bv)))
        extra[f"{prefix}_region"] = judge_paired(av, bv, "less", m).region
    return extra | {f"{prefix}_stat": j.statistic, f"{prefix}_d": rounded(j.estimate, decimals),
            f"{prefix}_lo": rounded(j.low, decimals), f"{prefix}_hi": rounded(j.high, decimals),
            f"{prefix}_med": rounded(float(np.median(av - bv)), decimals),
            f"{prefix}_won": rounded(float(np.mean(av < bv)), 2), f"{prefix}_runs": int(av.size)}


# ---------------------------------------------------------------------------------------------- step E: defensive


def defensive_mixture(proposal: mx.GaussianMixture, local: list[mx.GaussianMixture] | tuple[mx.GaussianMixture, ...],
                      alpha: float) -> mx.GaussianMixture:
    r"""Defensive proposal for step E: :math:`g_\alpha = (1-\alpha)\,g + \alpha\,\frac1N\sum_i\hat p_i`.

    By the weighted arithmetic-geometric mean inequality
    :math:`\prod_i\hat p_i^{\varepsilon_i} \le \sum_i\varepsilon_i\hat p_i \le N\cdot\frac1N\sum_i\hat p_i`, so the
    unnormalised weights :math:`\prod_i\hat p_i^{\varepsilon_i}/g_\alpha` are at most :math:`N/\alpha` for every
    :math:`\varepsilon` on the simplex: finite variance everywhere, where the first-order mixture alone has it only
    in a region around its own exponents (Hesterberg 1995's defensive mixture, with the nodes' own mixtures as the
    defensive component: the same information the patent's proposal is built from).

    Parameters
    ----------
    proposal : GaussianMixture
        Step D's first-order mixture :math:`g`.
    local : sequence of GaussianMixture
        The nodes' mixtures :math:`\hat p_i` (same dimension).
    alpha : float
        Defensive share, in (0, 1].

    Returns
    -------
    GaussianMixture
        The components of ``proposal`` weighted 1 − α followed by every local mixture's weighted α/N, weights
        normalised.

    Raises
    ------
    ValueError
        ``alpha`` outside (0, 1], no local mixture, or dimensions that differ.
    TypeError
        ``local`` not a sequence (a single mixture, a generator) or holding a non-mixture.
    """
    instance_of(proposal, mx.GaussianMixture, "proposal")
    alpha = unit_scalar(alpha, "alpha")
    if alpha <= 0:
        raise ValueError(f"alpha must lie in (0, 1], got {alpha}")
    local = sequence(local, "local", minimum=1, what="mixture")  # a sequence, named (not a generator or a mixture)
    d = proposal.means.shape[1]
    for i, gm in enumerate(local):
        instance_of(gm, mx.GaussianMixture, f"local[{i}]")
        if gm.means.shape[1] != d:
            raise ValueError(f"local[{i}] has dimension {gm.means.shape[1]}, the proposal {d}")
    N = len(local)
    w = np.concatenate([(1 - alpha) * proposal.weights] + [alpha / N * gm.weights for gm in local])
    return mx.GaussianMixture(w / w.sum(), np.concatenate([proposal.means] + [gm.means for gm in local]),
                              np.concatenate([proposal.covs] + [gm.covs for gm in local]))


#: The proposals of :func:`defensive_study`, the keys of :class:`DefensiveStudy`'s fields.
DEFENSIVE_METHODS = ("patent", "redraw", "defensive")


def _defensive_relation(values: dict[str, Any], cls: str) -> None:
    """One value per run (``runs``) in every method's arrays."""
    for name in ("omega_err", "sq_err", "ess", "ess_vertex"):
        for key, arr in values[name].items():
            if arr.shape[0] != values["runs"]:
                raise ValueError(f"{cls}.{name}[{shown(key)}] must have one entry per run ({values['runs']}), "
                                 f"got {arr.shape[0]}")


@dataclass(frozen=True)
class DefensiveStudy:
    """Step E's proposals on the two-mixture example, run by run (paired: run k of each method is the same replicate).

    Attributes
    ----------
    omega_err : dict
        Method -> (runs,) :math:`|\\hat\\omega^* - \\omega^*|`.
    sq_err : dict
        Method -> (runs,) squared error of the fused mean :math:`\\hat x` against the exact mean at :math:`\\omega^*`.
    ess : dict
        Method -> (runs,) ESS / R of the estimate's weights.
    ess_vertex : dict
        Method -> (runs,) the smaller ESS / R of the weights at the two vertices ω = 0 and ω = 1.
    runs, r : int
    alpha : float
    """

    omega_err: Mapping[str, FloatArray]
    sq_err: Mapping[str, FloatArray]
    ess: Mapping[str, FloatArray]
    ess_vertex: Mapping[str, FloatArray]
    runs: int
    r: int
    alpha: float

    __result_spec__ = ResultSpec({"omega_err": dict_of(array("runs", bounds=(0.0, 1.0)), keys=DEFENSIVE_METHODS),
                                  "sq_err": dict_of(array("runs", bounds=(0.0, np.inf)), keys=DEFENSIVE_METHODS),
                                  **{name: dict_of(array("runs", bounds=(0.0, 1.0)), keys=DEFENSIVE_METHODS)
                                     for name in ("ess", "ess_vertex")},
                                  "runs": integer(2), "r": integer(2), "alpha": number(positive=True, bounds=(0.0, 1.0))},
                                 relations=(lambda v, cls: _defensive_relation(v, cls),))
    __post_init__ = validated_post_init


    def table(self) -> pd.DataFrame:
        """Medians and means per method (4 significant digits)."""
        rows = {}
        for k in self.omega_err:
            rows[DEFENSIVE_LABELS[k]] = {
                "median |ω̂* − ω*|": np.median(self.omega_err[k]), "mean |ω̂* − ω*|": np.mean(self.omega_err[k]),
                "median squared error of x̂": np.median(self.sq_err[k]),
                "mean squared error of x̂": np.mean(self.sq_err[k]),
                "median ESS / R at ω̂*": np.median(self.ess[k]),
                "median ESS / R, worse vertex": np.median(self.ess_vertex[k])}
        return pd.DataFrame(rows).T.map(lambda x: float(f"{x:.4g}"))

    def glue(self) -> GlueValues:
        """Glue ``chf_def_*``: sizes, the paired comparisons (defensive against the patent's and the redraw)."""
        v: dict[str, Any] = {"chf_def_runs": self.runs, "chf_def_r": self.r, "chf_def_alpha": rounded(self.alpha, 2),
                             "chf_def_bound": rounded(2 / self.alpha, 2)}
        for other in ("patent", "redraw"):
            v.update(paired_numbers(self.sq_err["defensive"], self.sq_err[other], f"chf_def_sq_{other}", 6, MARGIN))
        v.update(paired_numbers(self.omega_err["defensive"], self.omega_err["patent"], "chf_def_om_patent", 5, MARGIN))
        for k in ("chf_def_sq_patent_runs", "chf_def_sq_redraw_runs", "chf_def_om_patent_runs"):
            v.pop(k)  # the runs are chf_def_runs
        for k in self.ess:
            v[f"chf_def_ess_{k}"] = rounded(float(np.median(self.ess[k])), 3)
            v[f"chf_def_essv_{k}"] = rounded(float(np.median(self.ess_vertex[k])), 3)
        return v


#: Display label of each proposal of :func:`defensive_study`.
DEFENSIVE_LABELS = constant({"patent": "first-order mixture at ω = 1/2 (patent)",
                    "redraw": "redraw at ω̂* (R more samples)", "defensive": "defensive mixture"})


def _logpdf(gm: mx.GaussianMixture, x: FloatArray) -> FloatArray:
    r"""Log density (n,) of one mixture at points (n, d), by elementwise arithmetic (no BLAS call).

    The same values as :func:`fusion.estimates.mixtures.gm_logpdf` to round-off (tested); written out here because
    its triangular solves are slow when many small ones compete for two cores. Each component's quadratic form
    :math:`\sum_{ij}(\Delta_i P^{-1}_{ij})\Delta_j` is summed term by term in the order ``einsum("nsi,sij,nsj->ns")``
    sums it (the code before issue 37: the same numbers, bit for bit, tested), on contiguous coordinate rows, and the
    components' log terms are laid out (S, n) for the log-sum-exp (the input is a valid mixture at finite points, so
    the public ``logsumexp``'s checks are skipped).
    """
    return mx._logsumexp(_component_terms(gm, x), 0)


def _component_terms(gm: mx.GaussianMixture, x: FloatArray) -> FloatArray:
    r""":math:`\log\pi_s - \tfrac12(\log\det 2\pi P_s + q_s(x))` of the kept components (weight > 0), shape (S, n)."""
    keep = gm.weights > 0
    return _gaussian_rows(np.log(gm.weights[keep]), gm.means[keep], gm.covs[keep], x)


def _gaussian_rows(logw: FloatArray, means: FloatArray, covs: FloatArray, x: FloatArray) -> FloatArray:
    r""":math:`\log w_s - \tfrac12(\log\det 2\pi P_s + q_s(x))` (S, n) of S Gaussians at points x (n, d), elementwise.

    :math:`q_s(x) = \sum_{ij}(\Delta_iP^{-1}_{s,ij})\Delta_j`, :math:`\Delta = x - \mu_s`, summed term by term in
    the order of ``einsum("nsi,sij,nsj->ns")`` (the same numbers, bit for bit), on contiguous coordinate rows.
    """
    inv = np.linalg.inv(covs)
    logdet = np.linalg.slogdet(2 * np.pi * covs)[1]
    n, d = x.shape
    xs = [np.ascontiguousarray(x[:, i]) for i in range(d)]
    out = np.empty((means.shape[0], n))
    dx = [np.empty(n) for _ in range(d)]
    t = np.empty(n)
    for s in range(means.shape[0]):
        for i in range(d):
            np.subtract(xs[i], means[s, i], out=dx[i])
        q = out[s]
        for i in range(d):
            for j in range(d):
                np.multiply(dx[i], inv[s, i, j], out=t)
                t *= dx[j]
                if i == j == 0:
                    q[...] = t
                else:
                    q += t
        q += logdet[s]
        q *= -0.5
        q += logw[s]
    return out


def _log_densities(gms: list[mx.GaussianMixture], x: FloatArray) -> FloatArray:
    """:math:`L_{ri} = \\log\\hat p_i(x_r)`, shape (n, N) (:func:`fusion.estimates.chernoff.log_densities`)."""
    return np.column_stack([_logpdf(g, x) for g in gms])


@own_underflow  # underflow to 0 by design (a kernel, a density or normalised weights: fuzz 33b D6)
def _ess(lw: FloatArray) -> FloatArray:
    """ESS / R of log weights (..., R), clipped to [1/R, 1] (the bounds of the exact share).

    Equal weights (the redraw samples from the target itself, its log weights constant up to round-off) give
    1 + 2^-52 unclipped, which the result's bounds refused (fuzz 35b B2); the clip moves a value by round-off
    only, as :func:`fusion.filtering.particles.effective_sample_size` clips to [1, Q].
    """
    w = np.exp(lw - lw.max(axis=-1, keepdims=True))
    r = lw.shape[-1]
    return np.clip(w.sum(axis=-1) ** 2 / np.sum(w**2, axis=-1) / r, 1.0 / r, 1.0)


@own_underflow  # underflow to 0 by design (a kernel, a density or normalised weights: fuzz 33b D6)
def _estimate(xs: FloatArray, lw: FloatArray) -> FloatArray:
    """Self-normalised weighted mean (..., d) of points (..., R, d) with log weights (..., R)."""
    w = np.exp(lw - lw.max(axis=-1, keepdims=True))
    return np.einsum("...r,...rd->...d", w / w.sum(axis=-1, keepdims=True), xs)


#: Units (``fusion._limits.MAX_WORK``'s 10 ns) of one replicate of :func:`defensive_study`: two SLSQP minimisations
#: and the redraw's mixture, samples and densities, about 5 ms (r = 2, runs 200 -> 2,000: 0.881 -> 10.05 CPU-s,
#: process_time, minimum of 2, OPENBLAS_NUM_THREADS=1, the shared machine loaded), weighed twice (book audit 76: only
#: the ceiling of a sample count, so 5e6 replicates of r = 2, about 7 CPU-hours, were accepted).
_DEFENSIVE_RUN = 1_000_000
#: Units of one of the ``runs`` x ``r`` samples of :func:`defensive_study` (three proposals' draws and densities):
#: about 4.7 us (runs = 2, r 1e5 -> 1e6: 0.504 -> 4.709 CPU-s, as above), weighed twice (book audit 76: 10**7
#: samples, about 47 CPU-s, were accepted).
_DEFENSIVE_SAMPLE = 1_000


def defensive_study(rng: np.random.Generator, runs: int = 100, r: int = CHAPTER_R, alpha: float = 0.2
                    ) -> DefensiveStudy:
    r"""Step E with three proposals on the two-mixture example, ``runs`` independent replicates each.

    Every replicate runs steps E-I with R samples: the patent's proposal (step D's mixture at ω = 1/2), the
    defensive mixture (:func:`defensive_mixture`) and the chapter's redraw (the patent's :math:`\hat\omega^*`, then
    R fresh samples from step D's mixture at :math:`\hat\omega^*` for the estimate). :math:`\hat\omega^*` minimises
    :math:`\hat J` of eq. ``eq-chf-is`` (SLSQP, :func:`fusion.estimates.chernoff.simplex_minimum`); the estimate is
    the weighted mean of eq. ``eq-chf-estimate``. The references (exact :math:`\omega^*`, exact fused mean) are by
    quadrature (:func:`toy_reference`).

    Parameters
    ----------
    rng : numpy.random.Generator
    runs : int
        Replicates (>= 2).
    r : int
        Importance samples per proposal and replicate.
    alpha : float
        Defensive share.

    Returns
    -------
    DefensiveStudy
        Per proposal (patent, redraw, defensive) and replicate: the absolute error of ω̂, the squared error of the
        mean, the ESS and the ESS at the simplex's vertices.

    Raises
    ------
    TypeError
        ``rng`` not a Generator, ``runs`` or ``r`` not an integer.
    ValueError
        ``runs`` or ``r`` below 2, or ``runs`` × ``r`` samples (drawn at once) beyond the sample count's ceiling or
        the input budget, or the replicates beyond the work budget (``fusion._limits.MAX_WORK``: about 1,000
        replicates, or 1e6 samples).
    """
    as_rng(rng)  # a Generator itself, over a numpy bit generator (fuzz 57b C1)
    runs, r = count(runs, "runs", minimum=2), count(r, "r", minimum=2)
    if runs * r > count_ceiling("n"):  # the samples of every replicate are drawn at once
        raise ValueError(f"runs and r ask for {runs * r:.3g} samples at once, beyond the ceiling of a sample count "
                         f"({count_ceiling('n'):,}; fusion._validation.COUNT_CEILINGS)")
    input_allocation((runs * r, 2), "runs and r")
    work((runs, _DEFENSIVE_RUN + r * _DEFENSIVE_SAMPLE), "runs and r")  # before the first draw (book audit 76)
    ref = toy_reference()
    gms = list(ref.gms)
    gdef = defensive_mixture(ref.proposal, gms, alpha)
    V = np.array([[0.0, 1.0], [1.0, 0.0]])  # ω = 0 and ω = 1
    out: dict[str, dict[str, FloatArray]] = {k: {} for k in ("om", "sq", "ess", "essv")}
    omegas = {}
    for key, g in (("patent", ref.proposal), ("defensive", gdef)):
        xs = mx.gm_sample(g, rng, runs * r)
        L, lg = _log_densities(gms, xs).reshape(runs, r, 2), _logpdf(g, xs).reshape(runs, r)
        om = np.array([ch.simplex_minimum(L[k], lg[k]).x[0] for k in range(runs)])
        omegas[key] = om
        lw = L[..., 0] * om[:, None] + L[..., 1] * (1 - om[:, None]) - lg
        x = _estimate(xs.reshape(runs, r, 2), lw)
        out["om"][key] = np.abs(om - ref.omega_star)
        out["sq"][key] = np.sum((x - ref.mean_star) ** 2, axis=1)
        out["ess"][key] = _ess(lw)
        out["essv"][key] = np.min(_ess(np.einsum("krn,vn->kvr", L, V) - lg[:, None, :]), axis=1)
    # the chapter's redraw: the patent's ω̂*, then R fresh samples of step D's mixture there
    om = omegas["patent"]
    x_h, ess_h, essv_h = np.empty((runs, 2)), np.empty(runs), np.empty(runs)
    for k in range(runs):
        gh = ch.first_order_fusion(gms, [om[k], 1 - om[k]]).mixture
        xh = mx.gm_sample(gh, rng, r)
        Lh, lgh = _log_densities(gms, xh), _logpdf(gh, xh)
        lw = Lh[:, 0] * om[k] + Lh[:, 1] * (1 - om[k]) - lgh
        x_h[k], ess_h[k] = _estimate(xh, lw), _ess(lw)
        essv_h[k] = min(_ess(Lh[:, 0] - lgh), _ess(Lh[:, 1] - lgh))
    out["om"]["redraw"] = out["om"]["patent"]
    out["sq"]["redraw"] = np.sum((x_h - ref.mean_star) ** 2, axis=1)
    out["ess"]["redraw"], out["essv"]["redraw"] = ess_h, essv_h
    order = ("patent", "redraw", "defensive")
    return DefensiveStudy({k: out["om"][k] for k in order}, {k: out["sq"][k] for k in order},
                          {k: out["ess"][k] for k in order}, {k: out["essv"][k] for k in order}, runs, r, float(alpha))


# ---------------------------------------------------------------------------------------------- local filters: PCRB


#: Units of one run of :func:`study_truths` (a SeedSequence spawn and a simulated target): about 1 ms (runs 200 ->
#: 2,000: 0.146 -> 1.992 CPU-s, process_time, minimum of 2, the shared machine loaded), weighed twice (book audit 76:
#: no budget, so 10**7 runs, about 3 CPU-hours, were accepted).
_TRUTH_RUN = 200_000


def study_truths(sc: RangeBearingScenario, seed: int, runs: int) -> FloatArray:
    """The true trajectories (runs, K, 4) of ``monte_carlo(sc, seed, runs)``, without running the filters.

    Run ``r``'s target is drawn from the first of the six streams spawned from the ``r``-th child of
    ``SeedSequence(seed)`` (:func:`fusion.scenarios.range_bearing.run_tracking_batch`), so these are the study's
    truths digit for digit.

    Parameters
    ----------
    sc : RangeBearingScenario
    seed : int
    runs : int

    Returns
    -------
    ndarray, shape (runs, K, 4)
        Per run the target's true state (x, vx, y, vy) at each of the K frames, as the study drew it.

    Raises
    ------
    ValueError
        ``runs`` below 1 or beyond the work budget (``fusion._limits.MAX_WORK``: about 5,000 runs).
    """
    seed = check_seed(seed)
    instance_of(sc, RangeBearingScenario, "sc")
    runs = count(runs, "runs")
    work((runs,), "runs", weight=_TRUTH_RUN)  # before the first spawn (book audit 76)
    seeds = np.random.SeedSequence(seed).spawn(runs)
    return np.stack([simulate_target(sc, np.random.default_rng(s.spawn(6)[0])).truth for s in seeds])


def single_sensor_crb(sc: RangeBearingScenario, truths: ArrayLike, frames: slice = slice(4, None)) -> dict[str, float]:
    r"""Root-mean-square position PCRB over ``frames`` of each single sensor, and of all sensors together.

    Sensor i's bound is :func:`fusion.scenarios.range_bearing.posterior_crb` of the scenario with sensor i alone:
    the floor of a filter that sees only that sensor's readings (the local filter of node i). Per frame the position
    bound is :math:`[J^{-1}]_{xx} + [J^{-1}]_{yy}`; the value returned is the root of its mean over ``frames``, as
    the chapter's table reports the centralised bound.

    Parameters
    ----------
    sc : RangeBearingScenario
    truths : array_like, shape (runs, K, 4)
        True trajectories (:func:`study_truths`).
    frames : slice
        Frames averaged (default: from frame 5 on, the chapter's window).

    Returns
    -------
    dict
        ``"sensor<i>"`` (1-based) and ``"all"`` -> bound (m).

    Raises
    ------
    TypeError
        ``sc`` not a RangeBearingScenario, ``frames`` not a slice.
    ValueError
        ``truths`` not (runs, K, 4), or ``frames`` of step 0 or selecting none of the K frames.
    """
    instance_of(sc, RangeBearingScenario, "sc")
    X = as_array(truths, "truths")
    if X.ndim != 3 or X.shape[2] != 4:
        raise ValueError(f"truths must be (runs, K, 4), got {X.shape}")
    frame_slice(frames, "frames", X.shape[1])

    def rms(s: RangeBearingScenario) -> float:
        J = posterior_crb(s, X)   # the truths read once (fuzz 61a C4's class)
        return float(np.sqrt(np.mean((J[:, 0, 0] + J[:, 2, 2])[frames])))
    out = {f"sensor{i + 1}": rms(dataclasses.replace(sc, sensors=(sc.sensors[i],))) for i in range(len(sc.sensors))}
    out["all"] = rms(sc)
    return out


def single_sensor_values(sc: RangeBearingScenario, seed: int, runs: int) -> GlueValues:
    """Glue ``chf_pcrb_*``: each single sensor's position PCRB from frame 5 on, and all sensors' (m, 4 decimals).

    Parameters
    ----------
    sc : RangeBearingScenario
        The study's scenario.
    seed, runs : int
        The study's root seed and runs: the bound's expectation is over the study's own truths
        (:func:`study_truths`).

    Returns
    -------
    dict
        ``chf_pcrb_sensor<i>``, ``chf_pcrb_all``, ``chf_pcrb_runs``, ``chf_pcrb_gain_min`` and ``chf_pcrb_gain_max``
        (the smallest and largest ratio of a single sensor's bound to all sensors' bound).
    """
    seed = check_seed(seed)
    runs = count(runs, "runs")
    b = single_sensor_crb(sc, study_truths(sc, seed, runs))
    ratios = [b[k] / b["all"] for k in b if k != "all"]
    return {**{f"chf_pcrb_{k}": rounded(v) for k, v in b.items()}, "chf_pcrb_runs": runs,
            "chf_pcrb_gain_min": rounded(min(ratios), 2), "chf_pcrb_gain_max": rounded(max(ratios), 2)}
