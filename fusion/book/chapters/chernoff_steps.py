r"""Chapter 06 (patent CN107330468B), appendix studies of single steps: review items closed with computed evidence.

Book-side studies that the chapter's appendix runs beside its records (none of them is a record, and none changes
a record's readings):

* step H: the :math:`O(1/R)` bias of the self-normalised importance weights, by the delta method and measured
  (:func:`snis_delta_terms`, :func:`snis_bias_study`);
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
* Owen, A. B. (2013). *Monte Carlo theory, methods and examples*, ch. 9 (self-normalised importance
   sampling, its delta-method bias and variance).
* Tichavský, P., Muravchik, C. H., Nehorai, A. (1998). Posterior Cramér-Rao bounds for discrete-time
   nonlinear filtering. *IEEE Trans. Signal Processing* 46(5), 1386-1396.
* Günay, M., Orguner, U., Demirekler, M. (2014). Approximate Chernoff fusion of Gaussian mixtures using
   sigma-points. *Proceedings of the 17th International Conference on Information Fusion (FUSION 2014)*.
"""

from __future__ import annotations

from collections.abc import Mapping
import dataclasses
from dataclasses import dataclass
from fusion._results import ResultSpec, array, dict_of, instance, integer, nested, number, table, validated_post_init
from fusion._frozen import constant
from fusion.book.study_cache import study_cache
from typing import Any

import numpy as np
import pandas as pd
from numpy.typing import ArrayLike

from fusion._docstrings import with_sections
from fusion._validation import (FloatArray, as_array, count, frame_slice, instance_of, positive_scalar, text,
                                unit_scalar)
from fusion._counts import count_ceiling, counts, distinct, input_allocation, sequence
from fusion.book.rulebook import judge_paired
from fusion.book.tables import rounded, sci
from fusion.estimates import chernoff as ch
from fusion.estimates.chernoff import mixture as chm
from fusion.estimates import mixtures as mx
from fusion.scenarios import two_mixtures
from fusion.scenarios.range_bearing import RangeBearingScenario, posterior_crb, simulate_target
from fusion.book.glue import GlueValues
from fusion._counts import seed as check_seed
from fusion._shown import shown

__all__ = [
    "SnisDelta",
    "snis_delta_terms",
    "toy_reference",
    "ToyReference",
    "snis_bias_study",
    "SnisBiasStudy",
    "defensive_mixture",
    "defensive_study",
    "DefensiveStudy",
    "paired_numbers",
    "study_truths",
    "single_sensor_crb",
    "single_sensor_values",
    "DEFENSIVE_LABELS",
    "CHAPTER_R",
    "ChosenBiasStudy",
    "chosen_bias_study",
]

#: Importance samples per run in the chapter's tracking study (``RangeBearingScenario.n_samples``).
CHAPTER_R = 2000


@dataclass(frozen=True)
class SnisDelta:
    r"""Delta-method terms of the self-normalised importance-sampling mean.

    For :math:`\hat\mu_R = \sum_r w_r x_r / \sum_r w_r`, :math:`x_r \sim g` independent,
    :math:`w = \tilde p / g` with :math:`\tilde p = Z p`, the second-order expansion of the ratio gives

    .. math:: \mathbb E\hat\mu_R - \mu = \frac{c}{R} + O(R^{-2}), \qquad
              c = -\,\mathbb E_g\!\Bigl[\frac{w^2}{Z^2}(x - \mu)\Bigr] = -\int\frac{p(x)^2}{g(x)}(x - \mu)\,dx,

    .. math:: \operatorname{Cov}\hat\mu_R = \frac{V}{R} + O(R^{-2}), \qquad
              V = \int\frac{p(x)^2}{g(x)}(x - \mu)(x - \mu)^\top dx,

    so the bias is of order :math:`1/R` while the noise is of order :math:`1/\sqrt R`: their ratio
    :math:`|c| / \sqrt{R\,\operatorname{tr}V}` falls as :math:`R^{-1/2}`.

    Attributes
    ----------
    mu : ndarray, shape (d,)
        The target's mean :math:`\mu`.
    c : ndarray, shape (d,)
        Bias coefficient (the bias is :math:`c/R`).
    V : ndarray, shape (d, d)
        Variance coefficient (the covariance is :math:`V/R`).
    second_moment : float
        :math:`\mathbb E_g[w^2]/Z^2 = \int p^2/g` (:math:`1 + \chi^2(p\|g)`).
    """

    mu: FloatArray
    c: FloatArray
    V: FloatArray
    second_moment: float

    __result_spec__ = ResultSpec({"mu": array("d"), "c": array("d"), "V": array("d", "d", covariance=True),
                                  "second_moment": number(positive=True)})
    __post_init__ = validated_post_init



#: Columns that this module's bias tables write and their glue reads (issue 36: named once): the delta method's
#: |c|, R times the self-normalised bias along c with its 95 % interval, and the extra bias of choosing ω with its
#: 95 % interval.
C_NORM = "|c| (delta method)"
ALONG = "R·bias along c"
ALONG_LOW = "R·bias along c, 95 % low"
ALONG_HIGH = "R·bias along c, 95 % high"
EXTRA_LOW = "extra, 95 % low"
EXTRA_HIGH = "extra, 95 % high"


def snis_delta_terms(points: ArrayLike, log_target: ArrayLike, log_proposal: ArrayLike, cell: float) -> SnisDelta:
    r"""Bias and variance coefficients of the self-normalised IS mean, by quadrature (see :class:`SnisDelta`).

    Parameters
    ----------
    points : array_like, shape (n, d)
        Quadrature nodes (a regular grid covering the target's and the proposal's mass).
    log_target : array_like, shape (n,)
        Log of the target density up to a constant (:math:`\log\tilde p`): normalised here.
    log_proposal : array_like, shape (n,)
        Log of the (normalised) proposal density :math:`\log g`.
    cell : float
        Volume of one quadrature cell (> 0): a real number (a numpy scalar or a 0-d array included, not a bool)
        within the package's magnitudes [1e-150, 1e150].

    Returns
    -------
    SnisDelta
        The target's mean μ, the bias coefficient c (bias ≈ c/R), the covariance coefficient V (≈ V/R) and ∫p²/g.

    Raises
    ------
    TypeError
        ``cell`` not a real number (a bool included).
    ValueError
        Shapes inconsistent, non-finite values, ``cell`` not positive or outside [1e-150, 1e150], or a
        ``log_proposal`` so far below ``log_target`` (or above it) that ∫p²/g is beyond the float range (its
        terms are computed in logs: the proposal is then not a normalised density covering the target).
    """
    X = as_array(points, "points", ndim=2)
    lp = as_array(log_target, "log_target", ndim=1)
    lg = as_array(log_proposal, "log_proposal", ndim=1)
    if lp.shape != (X.shape[0],) or lg.shape != (X.shape[0],):
        raise ValueError(f"log_target and log_proposal must have shape ({X.shape[0]},), got {lp.shape}, {lg.shape}")
    cell = positive_scalar(cell, "cell")  # the shared scalar reader: numpy numbers, no bool, rule 2's magnitudes
    lp = lp - mx.logsumexp(lp) - np.log(cell)  # normalised on the grid
    p = np.exp(lp)
    mu = np.sum((p * cell)[:, None] * X, axis=0)  # elementwise sums: no BLAS, the same with any thread count
    lq = 2 * lp - lg + np.log(cell)  # log of p^2 / g times the cell
    log_m2 = float(mx.logsumexp(lq))
    with np.errstate(over="ignore", under="ignore", invalid="ignore"):  # checked below
        q = np.exp(2 * lp - lg) * cell  # p^2 / g times the cell
        if not np.all(np.isfinite(q)):  # exp(2 lp - lg) alone overflowed: the product in logs
            q = np.exp(lq)
        dx = X - mu
        c = -np.sum(q[:, None] * dx, axis=0)
        V = np.sum(q[:, None, None] * dx[:, :, None] * dx[:, None, :], axis=0)
    if not (np.isfinite(log_m2) and np.all(np.isfinite(q)) and np.all(np.isfinite(c)) and np.all(np.isfinite(V))
            and float(q.sum()) > 0.0):
        raise ValueError(f"log_proposal is too far from log_target: ∫p²/g is exp({log_m2:.4g}), outside the float "
                         "range (log_proposal must be the log of a normalised proposal density covering the target)")
    return SnisDelta(mu=mu, c=c, V=V, second_moment=float(q.sum()))


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
        undefined, which no glued number can show); ``prefix`` whose keys are not identifiers.
    TypeError
        ``prefix`` not a string.
    """
    prefix = text(prefix, "prefix")
    if not f"{prefix}_stat".isidentifier():
        raise ValueError(f"prefix must make glue keys that are identifiers (<prefix>_stat), got {shown(prefix)}")
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


# ---------------------------------------------------------------------------------------------- step H: SNIS bias


def _snis_relation(values: dict[str, Any], cls: str) -> None:
    """The table's rows are those of the exponents of ``delta`` (at the table's 4 decimals), each at the same sizes
    R: glue reads the rows of ω* and of the far exponent by key."""
    t = values["table"]
    want = sorted({rounded(float(w), 4) for w in values["delta"]})
    have = sorted(set(map(float, t["ω"])))
    if have != want:
        raise ValueError(f"{cls}.table must hold the rows of the exponents of {cls}.delta ({want}), got ω {have}")
    sizes = {w: sorted(map(int, t.loc[t["ω"] == w, "R"])) for w in want}
    if len({tuple(r) for r in sizes.values()}) > 1:
        raise ValueError(f"{cls}.table must hold every exponent at the same sizes R, got {sizes}")


#: The delta-method terms of an exponent are kept when a grid twice as wide gives them to this relative tolerance:
#: the quadrature's truncation is what a wider grid changes. The wider grids have 1201 nodes per axis (spacings
#: 0.03, 0.06, 0.12 at half-widths 18, 36, 72), whose own discretisation error on the toy's terms is at most about
#: 4e-9 (0.12 against 0.06, measured), below this tolerance; the reference grid (601 nodes on [-9, 9]², spacing
#: 0.03) and the first wider one differ by truncation alone.
_DELTA_RTOL = 1e-8
#: How often the reference grid's half-width is doubled before an exponent's ∫p²/g counts as unresolved (9 -> 72).
_DELTA_WIDENINGS = 3


def _tail_margin(gms: tuple[mx.GaussianMixture, ...], e: FloatArray, proposal: mx.GaussianMixture
                 ) -> tuple[float, float]:
    r"""The Gaussian tails' verdict on :math:`\int p_\varepsilon^2/g`: its margin and the worst direction's angle.

    Along a ray :math:`x = t u` (:math:`|u| = 1`) a mixture decays as its slowest component,
    :math:`\log\hat p_i(tu) = -\tfrac{t^2}2\min_s u^\top P_{is}u + O(t)` (:math:`P` the precisions), so
    :math:`\log(p_\varepsilon^2/g) = -\tfrac{t^2}2 h(u) + O(t)` with
    :math:`h(u) = 2\sum_i\varepsilon_i\min_s u^\top P_{is}u - \min_k u^\top P_{gk}u`: the integral is finite when
    :math:`h > 0` in every direction and infinite when :math:`h < 0` in one (for a one-component proposal, when
    :math:`2\Sigma_p^{-1} - \Sigma_g^{-1}` is not positive definite for some product of components). The minimum is
    taken over 7200 directions of the plane: a sampled minimum below zero is a true one (the sampled minimum is at
    least the true one).
    """
    th = np.linspace(0.0, np.pi, 7200, endpoint=False)
    u = np.stack([np.cos(th), np.sin(th)], axis=1)

    def slowest(gm: mx.GaussianMixture) -> FloatArray:
        keep = gm.weights > 0
        prec = np.linalg.inv(gm.covs[keep])
        return np.min(np.einsum("ui,sij,uj->us", u, prec, u), axis=1)
    h = 2 * sum(float(ei) * slowest(gm) for ei, gm in zip(e, gms)) - slowest(proposal)
    k = int(np.argmin(h))
    return float(h[k]), float(th[k])


def _toy_delta(w: float, name: str) -> SnisDelta:
    r""":func:`snis_delta_terms` of :math:`p_{(w, 1-w)}` and the chapter's proposal on the two-mixture example,
    refused by ``name`` where they do not exist or the grid cannot resolve them.

    The terms are computed on the reference grid of :func:`toy_reference` and on grids of twice, four and eight
    times its half-width (1201 nodes per axis, ``_DELTA_RTOL``); the narrowest grid whose terms a grid twice as
    wide gives to ``_DELTA_RTOL`` is kept (the reference grid wherever it resolves the integral, so those numbers
    are unchanged).

    Raises
    ------
    ValueError
        ``name`` (the exponent) where :math:`\int p^2/g` is infinite (:func:`_tail_margin`: the delta method does not
        apply) or reaches beyond the widest grid.
    """
    ref = toy_reference()
    e = np.array([w, 1 - w])
    margin, angle = _tail_margin(ref.gms, e, ref.proposal)
    if margin < 0:
        raise ValueError(f"{name} = {shown(w)}: ∫p²/g is infinite for the chapter's proposal (along the direction at "
                         f"{np.degrees(angle):.1f}°, p² decays slower than g: h = {margin:.3g} < 0), so the delta "
                         "method's c and V do not exist; choose an exponent whose ∫p²/g is finite")
    axis0 = np.unique(ref.points[:, 0])
    previous = None
    for k in range(_DELTA_WIDENINGS + 1):
        if k == 0:
            pts, L = ref.points, ref.L
            cell = ref.cell
        else:
            axis = np.linspace(-1.0, 1.0, 1201) * (float(axis0[-1]) * 2.0**k)
            X, Y = np.meshgrid(axis, axis)
            pts = np.column_stack([X.ravel(), Y.ravel()])
            L = _log_densities(list(ref.gms), pts)
            cell = float((axis[1] - axis[0]) ** 2)
        dt = snis_delta_terms(pts, L[:, 0] * e[0] + L[:, 1] * e[1], _logpdf(ref.proposal, pts), cell)
        if previous is not None and _delta_agree(previous, dt):
            return previous
        previous = dt
    limit = float(axis0[-1]) * 2.0**_DELTA_WIDENINGS
    raise ValueError(f"{name} = {shown(w)}: ∫p²/g is finite but its mass reaches beyond the widest quadrature grid "
                     f"[-{limit:g}, {limit:g}]² (the terms change by more than {_DELTA_RTOL:g} when it is widened), so "
                     "the delta method's c and V are not resolved; choose an exponent nearer the proposal's 1/2")


def _delta_agree(a: SnisDelta, b: SnisDelta) -> bool:
    """Whether two grids' delta terms agree to ``_DELTA_RTOL`` (c on the scale of its bound √(∫p²/g · tr V))."""
    scale_c = np.sqrt(b.second_moment * np.trace(b.V))
    return bool(abs(a.second_moment - b.second_moment) <= _DELTA_RTOL * b.second_moment
                and np.linalg.norm(a.c - b.c) <= _DELTA_RTOL * scale_c
                and np.linalg.norm(a.V - b.V) <= _DELTA_RTOL * np.linalg.norm(b.V)
                and np.linalg.norm(a.mu - b.mu) <= _DELTA_RTOL * (1.0 + np.linalg.norm(b.mu)))


@dataclass(frozen=True)
class SnisBiasStudy:
    r"""Step H's self-normalised mean on the two-mixture example: delta method against simulation.

    Attributes
    ----------
    table : DataFrame
        One row per exponent ω and R: the predicted :math:`R\,(c\cdot\hat c)` = :math:`|c|` and the measured
        :math:`R` times the mean error along :math:`\hat c = c/|c|`, with its 95 % interval, and the measured
        :math:`R` times the mean error across :math:`\hat c` (zero to first order). Rows identified by (ω, R), read
        by key: no key twice, the exponents those of ``delta``, each at the same sizes R.
    delta : dict
        ω -> :class:`SnisDelta`.
    total : int
        Samples per ω (split into blocks of R for every R).
    """

    table: pd.DataFrame
    delta: Mapping[float, SnisDelta]
    total: int

    __result_spec__ = ResultSpec({"table": table("ω", "R", "blocks", C_NORM, ALONG, ALONG_LOW, ALONG_HIGH,
                                                 key=("ω", "R")),
                                  "delta": dict_of(instance(SnisDelta), key=(float, int, np.number)),
                                  "total": integer(1)},
                                 relations=(lambda v, cls: _snis_relation(v, cls),))
    __post_init__ = validated_post_init


    def glue(self) -> GlueValues:
        """Glue ``chf_snis_*``: sizes, :math:`|c|` and the measurement at ω* and at the far ω, the ratio bias / SD at
        the chapter's R, and how many rows' intervals cover :math:`|c|`. Exponents are glued at the table's 4
        decimals, the precision at which the far ω must differ from ω* (fuzz 26b D1: 2 decimals glued 0.5535 as
        0.55, ω* rounded)."""
        ws = sorted(self.delta)
        star = toy_reference().omega_star
        w_star = min(ws, key=lambda w: abs(w - star))
        w_far = max(ws, key=lambda w: abs(w - star))
        d, far = self.delta[w_star], self.delta[w_far]
        t = self.table
        inside = (t[ALONG_LOW] <= t[C_NORM]) & (
            t[C_NORM] <= t[ALONG_HIGH])
        # rows read by key (fuzz 24b DR): the exponent's rows in increasing R, whatever the table's order
        first = t[t["ω"] == rounded(w_star)].sort_values("R").iloc[0]  # the smallest R: the most blocks
        last = t[t["ω"] == rounded(w_far)].sort_values("R").iloc[-1]  # the largest R
        return {"chf_snis_total": int(self.total), "chf_snis_rs": ", ".join(str(r) for r in sorted(set(t["R"]))),
                "chf_snis_omega_star": rounded(star), "chf_snis_far_omega": rounded(w_far),
                "chf_snis_c_star": rounded(float(np.linalg.norm(d.c))),
                "chf_snis_c_far": rounded(float(np.linalg.norm(far.c))),
                "chf_snis_r_first": int(first["R"]), "chf_snis_meas_star": rounded(first[ALONG]),
                "chf_snis_meas_star_lo": rounded(first[ALONG_LOW]),
                "chf_snis_meas_star_hi": rounded(first[ALONG_HIGH]),
                "chf_snis_r_last": int(last["R"]), "chf_snis_meas_far": rounded(last[ALONG]),
                "chf_snis_meas_far_lo": rounded(last[ALONG_LOW]),
                "chf_snis_meas_far_hi": rounded(last[ALONG_HIGH]),
                "chf_snis_ratio_star": rounded(float(np.linalg.norm(d.c) / np.sqrt(CHAPTER_R * np.trace(d.V))), 5),
                "chf_snis_ratio_far": rounded(float(np.linalg.norm(far.c) / np.sqrt(CHAPTER_R * np.trace(far.V))), 5),
                "chf_snis_chapter_r": CHAPTER_R,
                "chf_snis_covered": int(inside.sum()), "chf_snis_rows": int(len(t))}

    def display_table(self) -> pd.DataFrame:
        """The table, rounded to 4 decimals, indexed by ω and R."""
        t = self.table.drop(columns="blocks").set_index(["ω", "R"])
        return t.map(lambda x: rounded(float(x)))


#: The Parameters entries of a block study's pool (:func:`fusion._docstrings.with_sections`).
_on_pool = with_sections("""rng : numpy.random.Generator
    Draws the pool.
rs : tuple of int
    Block sizes R: distinct (the table is keyed by R), each >= 2, dividing ``total`` and at most ``total / 2``
    (at least two blocks, for the 95 % interval of the blocks' mean); taken in increasing order.
total : int
    Pool size.""")


def _pool_blocks(rng: np.random.Generator, rs: tuple[int, ...], total: int) -> tuple[int, tuple[int, ...]]:
    """The checked pool size ``total`` and block sizes ``rs`` of a block study (distinct, each R >= 2, dividing
    ``total`` into at least two blocks), ``rs`` sorted; ``rng`` checked to be a Generator."""
    instance_of(rng, np.random.Generator, "rng")
    total = count(total, "total")
    rs = tuple(sorted(distinct(counts(rs, "rs", minimum=2), "rs")))
    if any(total % r for r in rs):
        raise ValueError(f"rs must divide total = {total}, got {rs}")
    if rs[-1] > total // 2:
        raise ValueError(f"rs must leave at least two blocks of total = {total} (each R at most {total // 2}: the "
                         f"blocks' 95 % interval needs two), got R = {rs[-1]}")
    return total, rs


@_on_pool
def snis_bias_study(rng: np.random.Generator, rs: tuple[int, ...] = (5, 10, 20, 40, 80), total: int = 400_000,
                    far_omega: float = 0.7) -> SnisBiasStudy:
    r"""Measure the bias of step H's self-normalised mean on the two-mixture example against :math:`c/R`.

    One pool of ``total`` samples from the chapter's proposal (step D's mixture at ω = 1/2) is cut into blocks of
    R samples for every R (common random numbers); each block gives :math:`\hat\mu_R` at a fixed exponent (the
    exact :math:`\omega^*`, and ``far_omega``, far from the proposal's 1/2); the mean error over the blocks, times
    R, is compared with :math:`c` (:func:`snis_delta_terms` on the quadrature grid). The exponent is fixed here:
    choosing it on the same samples (steps F-G) adds a further term (:func:`chosen_bias_study`).

    Parameters
    ----------
    far_omega : float
        The second exponent of A, in [0, 1], other than the exact :math:`\omega^*` at the table's 4 decimals (the
        table's rows are keyed by ω), and one whose :math:`\int p_\omega^2/g` is finite and resolved: for the
        chapter's proposal the integral is infinite below ω ≈ 0.103 (along the vertical, :math:`p_\omega^2` then
        decays slower than g: the delta method's c and V do not exist), finite but reaching beyond the widest
        quadrature grid just above it (0.11, 0.12 are refused), and finite up to ω = 1, where its mass lies far
        out (|c| ≈ 2.6e29 at ω = 1, on a grid of half-width 36: the terms are computed on grids widened from the
        reference grid until two successive ones agree to 1e-8, relative).

    Returns
    -------
    SnisBiasStudy
        One row per (ω, R): blocks, the norm of c, R × bias along c with its 95 % interval and across c; the delta
        terms per ω; ``total``.

    Raises
    ------
    TypeError
        ``rng`` not a Generator, ``rs``, ``total`` not integers, ``far_omega`` not a real number.
    ValueError
        ``rs`` or ``total`` as the pool refuses them; ``far_omega`` outside [0, 1], equal to ω* at 4 decimals, or
        one whose :math:`\int p^2/g` is infinite (decided from the Gaussian components' tails) or reaches beyond
        the quadrature grid of half-width 72 (checked before any sample is drawn).
    """
    total, rs = _pool_blocks(rng, rs, total)
    far_omega = unit_scalar(far_omega, "far_omega")
    ref = toy_reference()
    if rounded(far_omega, 4) == rounded(ref.omega_star, 4):  # fuzz 24b OR2: the rows of both exponents keyed alike
        raise ValueError(f"far_omega must differ from the exact ω* = {ref.omega_star:.4f} at 4 decimals (the table's "
                         f"rows are keyed by ω), got {shown(far_omega)}")
    # the delta terms first: an exponent whose ∫p²/g is infinite or unresolved is refused before any sample
    terms = {w: _toy_delta(w, name) for w, name in ((ref.omega_star, "the exact ω*"), (far_omega, "far_omega"))}
    xs = mx.gm_sample(ref.proposal, rng, total)
    L, lg = _log_densities(list(ref.gms), xs), _logpdf(ref.proposal, xs)
    rows, delta = [], {}
    for w in (ref.omega_star, far_omega):
        e = np.array([w, 1 - w])
        dt = terms[w]
        delta[float(w)] = dt
        chat = dt.c / np.linalg.norm(dt.c)
        perp = np.array([-chat[1], chat[0]])
        lw = L[:, 0] * e[0] + L[:, 1] * e[1] - lg
        for R in rs:
            K = total // R
            err = _estimate(xs.reshape(K, R, 2), lw.reshape(K, R)) - dt.mu
            along = R * (err[:, 0] * chat[0] + err[:, 1] * chat[1])
            across = R * (err[:, 0] * perp[0] + err[:, 1] * perp[1])
            half = 1.959964 * along.std(ddof=1) / np.sqrt(K)
            rows.append({"ω": rounded(w, 4), "R": R, "blocks": K, C_NORM: float(np.linalg.norm(dt.c)),
                         ALONG: float(along.mean()), ALONG_LOW: float(along.mean() - half),
                         ALONG_HIGH: float(along.mean() + half),
                         "R·bias across c": float(across.mean())})
    return SnisBiasStudy(pd.DataFrame(rows), delta, total)


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


def _ess(lw: FloatArray) -> FloatArray:
    """ESS / R of log weights (..., R)."""
    w = np.exp(lw - lw.max(axis=-1, keepdims=True))
    return w.sum(axis=-1) ** 2 / np.sum(w**2, axis=-1) / lw.shape[-1]


def _estimate(xs: FloatArray, lw: FloatArray) -> FloatArray:
    """Self-normalised weighted mean (..., d) of points (..., R, d) with log weights (..., R)."""
    w = np.exp(lw - lw.max(axis=-1, keepdims=True))
    return np.einsum("...r,...rd->...d", w / w.sum(axis=-1, keepdims=True), xs)


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
        the input budget.
    """
    instance_of(rng, np.random.Generator, "rng")
    runs, r = count(runs, "runs", minimum=2), count(r, "r", minimum=2)
    if runs * r > count_ceiling("n"):  # the samples of every replicate are drawn at once
        raise ValueError(f"runs and r ask for {runs * r:.3g} samples at once, beyond the ceiling of a sample count "
                         f"({count_ceiling('n'):,}; fusion._validation.COUNT_CEILINGS)")
    input_allocation((runs * r, 2), "runs and r")
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
    """
    seed = check_seed(seed)
    instance_of(sc, RangeBearingScenario, "sc")
    runs = count(runs, "runs")
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
        J = posterior_crb(s, truths)
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


# ---------------------------------------------------------------------------------------------- step H: ε* chosen


def _block_minimum(L: FloatArray, lg: FloatArray, iterations: int = 60) -> FloatArray:
    r"""The minimiser ω (K,) on [0, 1] of :math:`\hat J(\omega) = \log\sum_r e^{\omega L_{r1} + (1-\omega)L_{r2} - \log g_r}`
    of each block (L (K, R, 2), lg (K, R)), by bisection on its derivative :math:`\sum_r\tilde w_r(L_{r1} - L_{r2})`
    (increasing: :math:`\hat J` is convex); 0 or 1 where the derivative has one sign on the interval."""
    D = L[..., 0] - L[..., 1]

    def slope(w: FloatArray) -> FloatArray:
        a = w[:, None] * D + L[..., 1] - lg
        e = np.exp(a - a.max(axis=1, keepdims=True))
        return np.sum(e * D, axis=1) / e.sum(axis=1)
    lo, hi = np.zeros(L.shape[0]), np.ones(L.shape[0])
    s0, s1 = slope(lo), slope(hi)
    for _ in range(iterations):
        mid = 0.5 * (lo + hi)
        up = slope(mid) > 0
        hi, lo = np.where(up, mid, hi), np.where(up, lo, mid)
    w = 0.5 * (lo + hi)
    return np.where(s0 >= 0, 0.0, np.where(s1 <= 0, 1.0, w))


@dataclass(frozen=True)
class ChosenBiasStudy:
    r"""Step H's mean with the exponent fixed at :math:`\omega^*` and chosen on the same samples (steps F-G).

    Attributes
    ----------
    table : DataFrame
        One row per R: blocks, :math:`R` times the mean error along :math:`\hat c` with the exponent fixed at the
        exact :math:`\omega^*` (with its 95 % interval: at large R the few blocks leave it wide) and with
        :math:`\hat\omega` minimising :math:`\hat J` on the block, the extra term (their paired difference, with its
        95 % interval) and the mean :math:`|\hat\omega - \omega^*|`. Rows identified by R, read by key: no R twice.
    total : int
    """

    table: pd.DataFrame
    total: int

    __result_spec__ = ResultSpec({"table": table("R", "blocks", "extra", EXTRA_LOW, EXTRA_HIGH, "mean |ω − ω*|",
                                                 key=("R",)),
                                  "total": integer(1)})
    __post_init__ = validated_post_init


    def display_table(self) -> pd.DataFrame:
        """The table, rounded to 4 decimals (block counts as integers), indexed by R."""
        t = self.table.set_index("R")
        return t.drop(columns="blocks").map(lambda x: rounded(float(x))).assign(blocks=t["blocks"].astype(int))[
            list(t.columns)]

    def glue(self) -> GlueValues:
        """Glue ``chf_chosen_*``: sizes, and at the smallest and the chapter's (largest) R the extra term with its
        interval; how many rows' intervals exclude zero."""
        t = self.table.sort_values("R")  # rows read by key (fuzz 24b DR): increasing R, whatever the table's order
        first, last = t.iloc[0], t.iloc[-1]
        out: dict[str, Any] = {"chf_chosen_total": int(self.total), "chf_chosen_rs": ", ".join(str(int(r)) for r in t["R"]),
                               "chf_chosen_rows": int(len(t)),
                               "chf_chosen_nonzero": int(np.sum((t[EXTRA_LOW] > 0) | (t[EXTRA_HIGH] < 0)))}
        for tag, row in (("first", first), ("last", last)):
            out[f"chf_chosen_r_{tag}"] = int(row["R"])
            for col, key in (("extra", "extra"), (EXTRA_LOW, "lo"), (EXTRA_HIGH, "hi"),
                             ("mean |ω − ω*|", "dw")):
                out[f"chf_chosen_{key}_{tag}"] = rounded(float(row[col]))
        return out


@_on_pool
def chosen_bias_study(rng: np.random.Generator, rs: tuple[int, ...] = (20, 80, 400, 2000), total: int = 400_000
                      ) -> ChosenBiasStudy:
    r"""The extra bias of step H when the exponent is chosen on the same samples, on the two-mixture example.

    As :func:`snis_bias_study` (one pool from the chapter's proposal, cut into blocks of R), each block gives step H's
    mean at the exact :math:`\omega^*` and at :math:`\hat\omega`, the exact minimiser of :math:`\hat J` on the same
    block (steps F-G without the swarm's error); both errors are measured from the exact mean at :math:`\omega^*`,
    along :math:`\hat c` (the fixed exponent's delta-method bias direction) and times R. The paired difference is the
    extra term of choosing the exponent.

    Returns
    -------
    ChosenBiasStudy
        One row per R: blocks, R × bias along c with ω* fixed and with ω chosen, their paired difference with its 95 %
        interval, and the mean absolute error of ω.
    """
    total, rs = _pool_blocks(rng, rs, total)
    ref = toy_reference()
    w_star = ref.omega_star
    e = np.array([w_star, 1 - w_star])
    dt = _toy_delta(w_star, "the exact ω*")
    chat = dt.c / np.linalg.norm(dt.c)
    xs = mx.gm_sample(ref.proposal, rng, total)
    L, lg = _log_densities(list(ref.gms), xs), _logpdf(ref.proposal, xs)
    rows = []
    for R in rs:
        K = total // R
        Lb, lgb, xb = L.reshape(K, R, 2), lg.reshape(K, R), xs.reshape(K, R, 2)
        w_hat = _block_minimum(Lb, lgb)
        fixed = _estimate(xb, Lb[..., 0] * e[0] + Lb[..., 1] * e[1] - lgb) - ref.mean_star
        chosen = _estimate(xb, w_hat[:, None] * Lb[..., 0] + (1 - w_hat[:, None]) * Lb[..., 1] - lgb) - ref.mean_star
        a, b = R * (fixed @ chat), R * (chosen @ chat)
        diff = b - a
        half = 1.959964 * diff.std(ddof=1) / np.sqrt(K)
        half_a = 1.959964 * a.std(ddof=1) / np.sqrt(K)  # the fixed exponent's own interval: few blocks at large R
        rows.append({"R": R, "blocks": K, "R·bias along c, ω* fixed": float(a.mean()),
                     "ω* fixed, 95 % low": float(a.mean() - half_a), "ω* fixed, 95 % high": float(a.mean() + half_a),
                     "R·bias along c, ω chosen": float(b.mean()), "extra": float(diff.mean()),
                     EXTRA_LOW: float(diff.mean() - half), EXTRA_HIGH: float(diff.mean() + half),
                     "mean |ω − ω*|": float(np.mean(np.abs(w_hat - w_star)))})
    return ChosenBiasStudy(pd.DataFrame(rows), total)
