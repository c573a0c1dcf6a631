r"""Gaussian mixtures: densities, sampling and weighted EM (patent CN107330468B, step C).

scikit-learn's ``GaussianMixture`` accepts no sample weights, and the particles of a particle
filter are weighted, so the EM here is written for weighted samples (Dempster, Laird & Rubin
1977):

* E-step: :math:`\gamma_{qs} \propto \pi_s \mathcal N(x^{(q)}; \mu_s, P_s)`;
* M-step: :math:`\pi_s = \sum_q w_q\gamma_{qs}`, :math:`\mu_s = \sum_q w_q\gamma_{qs}x^{(q)}/\pi_s`,
  :math:`P_s = \sum_q w_q\gamma_{qs}(x^{(q)} - \mu_s)(\cdot)^\top/\pi_s + \lambda\,\mathrm{diag}(\bar P)`, the floor a
  share :math:`\lambda` of the variances of the whole weighted sample :math:`\bar P` (plus :math:`10^{-12} I`).

References
----------
* Dempster, A. P., Laird, N. M., & Rubin, D. B. (1977). Maximum likelihood from incomplete
  data via the EM algorithm. *Journal of the Royal Statistical Society, Series B*, 39(1), 1-38.
* Arthur, D., & Vassilvitskii, S. (2007). k-means++: the advantages of careful seeding.
  *Proceedings of the 18th Annual ACM-SIAM Symposium on Discrete Algorithms*.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from numpy.typing import ArrayLike
from scipy.linalg import solve_triangular

from fusion._guards import own_underflow
from fusion._covariances import asymmetric
from fusion._validation import LOOP_STEP, allocation, axis_of, loop_work, read_once, renormalised, sequence, sums_to_one, work
from fusion._frozen import frozen_arrays, restore_frozen
from fusion._validation import derived_inputs
from fusion._validation import (MAX_MAGNITUDE, _covariance_magnitude, as_rngs, _numeric, FloatArray, as_array,
                                as_covariance, as_rng, as_state, as_weights, count, instance_of, nonnegative_scalar,
                                refuse_singular, same_length)

__all__ = ["EmFit", "Moments", "GaussianMixture", "logsumexp", "gaussian_logpdf", "gm_logpdf", "gm_moments", "gm_sample", "weighted_em", "weighted_em_batch"]


def logsumexp(a: ArrayLike, axis: int = 0) -> FloatArray:
    """:math:`\\log\\sum\\exp` along ``axis``, stable for large negative entries (``-inf`` allowed).

    A lean equivalent of :func:`scipy.special.logsumexp` for real arrays (that one checks
    its input on every call, which dominates the cost inside EM and the swarm).

    .. math:: \\log\\sum_j e^{a_j} = m + \\log\\sum_j e^{a_j - m}, \\qquad m = \\max_j a_j.

    Parameters
    ----------
    a : array_like
        Real values (``-inf`` allowed; NaN and ``+inf`` are refused).
    axis : int
        Axis to reduce.

    Returns
    -------
    ndarray
        ``a`` reduced along ``axis`` (a 0-d array for 1-D input); ``-inf`` where every entry
        is ``-inf``.
    """
    arr = _numeric(a, "a")
    if arr.size == 0:
        raise ValueError(f"a is empty (shape {arr.shape})")
    if np.isnan(arr).any():
        raise ValueError("a contains NaN (-inf entries are allowed)")
    if (arr == np.inf).any():
        raise ValueError("a contains +inf: a log-weight or log-density is finite or -inf (-inf entries are allowed)")
    if not float(np.abs(np.where(arr == -np.inf, 0.0, arr)).max()) <= MAX_MAGNITUDE:  # rule 2 for the finite entries
        raise ValueError(f"a has an entry beyond the representable range (finite entries at most {MAX_MAGNITUDE:g} "
                         "in magnitude; -inf is allowed)")
    return _logsumexp(arr, axis_of(axis, "axis", arr.shape, "a"))


@own_underflow  # underflow to 0 by design (a kernel, a density or normalised weights: fuzz 33b D6)
def _logsumexp(arr: FloatArray, axis: int) -> FloatArray:
    # C order first: numpy sums a row pairwise only when it is the contiguous axis, so a batched
    # array laid out otherwise would round differently from the same row alone
    arr = np.ascontiguousarray(arr)
    m = np.maximum.reduce(arr, axis=axis, keepdims=True)  # np.max and np.sum without their Python wrappers
    fin = np.isfinite(m)
    if not fin.all():
        m = np.where(fin, m, 0.0)
    e = arr - m
    e = np.exp(e, out=e) if e.dtype.kind == "f" else np.exp(e)  # in place (a float array's own exponential)
    with np.errstate(divide="ignore"):  # all -inf along the axis gives -inf, as scipy does
        return np.squeeze(m, axis=axis) + np.log(np.add.reduce(e, axis=axis))


@dataclass(frozen=True)
class GaussianMixture:
    """A Gaussian mixture :math:`\\sum_s \\pi_s \\mathcal N(x; \\mu_s, P_s)`.

    Attributes
    ----------
    weights : ndarray, shape (S,)
        Non-negative, summing to one (within 1e-9; float32 or float16 weights within ``2 S`` times their machine
        epsilon, stored renormalised in float64).
    means : ndarray, shape (S, d)
    covs : ndarray, shape (S, d, d)
        Symmetric positive definite.
    """

    weights: FloatArray
    means: FloatArray
    covs: FloatArray

    __setstate__ = restore_frozen  # copies and unpickled objects keep read-only arrays

    def __post_init__(self) -> None:
        given = read_once(self.weights, "weights")  # converted once: checked, and its dtype read (fuzz 33a C7)
        w = as_array(given, "weights", ndim=1, subnormal=True)
        m = as_array(self.means, "means", ndim=2)
        c = as_array(self.covs, "covs", ndim=3, subnormal=True)
        if not (w.size == m.shape[0] == c.shape[0]):
            raise ValueError(f"inconsistent shapes: weights {w.shape}, means {m.shape}, covs {c.shape}")
        if c.shape[1:] != (m.shape[1], m.shape[1]):
            raise ValueError(f"covs must have shape (S, {m.shape[1]}, {m.shape[1]}), got {c.shape}")
        if np.any(w < 0) or not sums_to_one(w, given):   # within 1e-9, or float32 weights' precision
            raise ValueError("weights must be non-negative and sum to one")
        w = renormalised(w, given)  # float32/float16 weights: stored renormalised in float64, so that the
                                           # record rebuilds (dataclasses.replace)
        if asymmetric(c):  # the readers' rule, each matrix to COVARIANCE_RTOL of its scale (np.allclose's
            raise ValueError("covs must be symmetric")  # absolute 1e-8 accepted [[1e-7, 0], [9e-9, 1e-7]]: fuzz 46a C5)
        try:
            np.linalg.cholesky(c)
        except np.linalg.LinAlgError:
            raise ValueError("covs must be positive definite") from None
        _covariance_magnitude(c, "covs")  # the covariance rule: no variance below MIN_VARIANCE
        refuse_singular(c, "covs")  # the covariance rule: not singular to working precision
        for name, arr in (("weights", w), ("means", m), ("covs", c)):
            if arr.flags.writeable:  # validated copies (rule 14), read-only: an in-place write would bypass the checks
                arr.setflags(write=False)
            object.__setattr__(self, name, arr)

    @property
    def dim(self) -> int:
        return int(self.means.shape[1])


def gaussian_logpdf(x: ArrayLike, mean: ArrayLike, cov: ArrayLike) -> FloatArray:
    """Log density of :math:`\\mathcal N(\\mu, P)` at the rows of ``x`` (shape (R, d)).

    Equal to :meth:`scipy.stats.multivariate_normal.logpdf` (parity test); written with one
    Cholesky factor and a triangular solve because it is called inside EM and the swarm for every
    component, where scipy's per-call input checks and eigendecomposition dominate the cost.

    .. math:: \\log\\mathcal N(x; \\mu, P) = -\\tfrac12\\lVert L^{-1}(x - \\mu)\\rVert^2
              - \\sum_j \\log L_{jj} - \\tfrac d2\\log 2\\pi, \\qquad P = LL^\\top.

    Parameters
    ----------
    x : array_like, shape (R, d) or (d,)
        Points (one point if 1-D).
    mean : array_like, shape (d,)
        Mean :math:`\\mu`.
    cov : array_like, shape (d, d)
        Covariance :math:`P`, symmetric positive definite.

    Returns
    -------
    ndarray, shape (R,)
        Log densities in nats.

    Raises
    ------
    ValueError
        If ``x`` is not (R, d) or (d,) with the dimension of ``mean``, ``cov`` is not a
        symmetric positive-definite (d, d) matrix, or anything is NaN/inf.
    """
    P = as_covariance(cov, name="cov")
    mu = as_state(mean, "mean")
    if mu.size != P.shape[0]:
        raise ValueError(f"mean has length {mu.size} but cov is {P.shape[0]}x{P.shape[0]}")
    xx = np.atleast_2d(as_array(x, "x", ndim=(1, 2)))
    if xx.shape[1] != mu.size:
        raise ValueError(f"x must have {mu.size} columns (the dimension of mean), got shape {np.shape(x)}")
    return _logpdf(xx, mu, P)


def _logpdf(xx: FloatArray, mean: FloatArray, cov: FloatArray) -> FloatArray:
    """Kernel of :func:`gaussian_logpdf` on validated input (used inside EM's loop)."""
    L = np.linalg.cholesky(cov)
    d = xx.shape[1]
    sol = solve_triangular(L, (xx - mean).T, lower=True, check_finite=False)
    return -0.5 * np.sum(sol**2, axis=0) - np.log(np.diag(L)).sum() - 0.5 * d * np.log(2 * np.pi)


def gm_logpdf(gm: GaussianMixture, x: ArrayLike) -> FloatArray:
    """Log density of a mixture at the rows of ``x`` (shape (R, d)); returns shape (R,).

    .. math:: \\log p(x) = \\log\\sum_{s:\\,\\pi_s > 0} \\pi_s\\,\\mathcal N(x; \\mu_s, P_s)

    Parameters
    ----------
    gm : GaussianMixture
        The mixture, of dimension d.
    x : array_like, shape (R, d)
        Points.

    Returns
    -------
    ndarray, shape (R,)
        Log densities in nats.

    Raises
    ------
    TypeError
        If ``gm`` is not a :class:`GaussianMixture`.
    ValueError
        If ``x`` is not (R, d) (or (d,)) with the mixture's dimension d, or is not finite; its components x points
        beyond the memory or work budget (rules 9, 17: ``_density_work``), named ``gm and x``.
    """
    instance_of(gm, GaussianMixture, "gm")
    return _gm_logpdf(gm, _density_points([gm], x, "gm and x"))


def _density_points(gms: Sequence[GaussianMixture], x: ArrayLike, names: str) -> FloatArray:
    """``x`` as (R, d) points of the mixtures' dimension d (rule 12, naming ``x``), once the densities of ``gms`` there
    are within the memory and work budgets (``_density_work``, naming ``names``)."""
    xx = np.atleast_2d(as_array(x, "x", ndim=(1, 2)))
    if xx.shape[1] != gms[0].dim:
        raise ValueError(f"x must have {gms[0].dim} columns (the mixture's dimension), got shape {np.shape(x)}")
    _density_work(gms, xx.shape[0], names)
    return xx


#: Units (``fusion._limits.work``, about 10 ns) of one component's log density at one point of dimension ``d`` in
#: ``_gm_logpdf``: ``7 + 0.2 d + 0.003 d**2`` (the shift, the triangular solve and its squares). Measured on this
#: shared machine (CPU time, minimum of 3, unit covariances): 34-69 ns an entry at d = 1-5 (200-20,000 components,
#: 1,000-100,000 points), 89 ns at d = 20, 560 ns at d = 100, 5.1 us at d = 400. Fuzz 49b C7: 2,500 components at
#: 200,000 2-D points were unchecked, and raised a raw MemoryError (3.73 GiB) after 22 CPU-s.
_DENSITY_UNITS = (7.0, 0.2, 0.003)
#: Units of one component's Python step in ``_gm_logpdf`` (its call overhead): 18 us measured at 10 points (200,000
#: components, 3.7 CPU-s), so twice ``fusion._limits.LOOP_STEP``.
_DENSITY_STEP = 2 * LOOP_STEP


def _check_mixtures(gms: Sequence[GaussianMixture]) -> None:
    """A non-empty sequence of mixtures of one dimension (TypeError for anything else)."""
    if isinstance(gms, (str, bytes, GaussianMixture)) or not hasattr(gms, "__len__"):
        raise TypeError(f"gms must be a sequence of GaussianMixture, got {type(gms).__name__}")
    if len(gms) < 1:
        raise ValueError("gms is empty: need at least one mixture")
    for i, g in enumerate(gms):
        instance_of(g, GaussianMixture, f"gms[{i}]")
    if any(g.dim != gms[0].dim for g in gms):
        raise ValueError("gms: all mixtures must have the same dimension")


def _density_work(gms: Sequence[GaussianMixture], points: int, names: str) -> int:
    """Refuse the log densities of mixtures ``gms`` at ``points`` points beyond the memory or work budget (rules 9,
    17), naming ``names``, before any is computed.

    The kernel of :func:`gm_logpdf` computes each live component's log density at every point, then stacks them:
    two (components, points) float64 arrays at once (``tracemalloc`` peak 2.00-2.04 of one at d = 1-5, 2.2 at
    d = 20), and ``_DENSITY_UNITS`` units an entry plus ``_DENSITY_STEP`` a component (``fusion._limits.loop_work``).
    The points' own temporaries (points x d) are within the input budget of ``x``.

    Parameters
    ----------
    gms : sequence of GaussianMixture
        The mixtures evaluated (of one dimension), each at every point.
    points : int
        The number of points.
    names : str
        The arguments setting them (``"gm and x"``), named in the message.

    Returns
    -------
    int
        The units of work.

    Raises
    ------
    ValueError
        The largest mixture's two (components, points) arrays beyond the memory budget, or the work beyond the work
        budget, naming ``names``.
    """
    live = [int(np.count_nonzero(g.weights > 0)) for g in gms]
    if not live:
        return 0
    d = gms[0].dim
    allocation((max(live), points), names, arrays=2)
    a, b, c = _DENSITY_UNITS
    return loop_work((sum(live),), int(np.ceil(points * (a + b * d + c * d * d))), names, step=_DENSITY_STEP)


def _gm_logpdf(gm: GaussianMixture, xx: FloatArray) -> FloatArray:
    comps = np.stack([np.log(gm.weights[s]) + _logpdf(xx, gm.means[s], gm.covs[s])
                      for s in range(gm.weights.size) if gm.weights[s] > 0])
    return _logsumexp(comps, axis=0)


@dataclass(frozen=True)
@frozen_arrays
class Moments:
    r"""Mean and covariance of a distribution (a mixture or weighted samples).

    Arrays are read-only.

    Attributes
    ----------
    mean : ndarray, shape (d,)
        :math:`\bar\mu`.
    cov : ndarray, shape (d, d)
        :math:`\bar P`, symmetrised.
    """

    mean: FloatArray
    cov: FloatArray


def gm_moments(gm: GaussianMixture) -> Moments:
    r"""Mean (d,) and covariance (d, d) of a mixture (moment matching to one Gaussian).

    .. math:: \bar\mu = \sum_s \pi_s\mu_s, \qquad
              \bar P = \sum_s \pi_s\bigl[P_s + (\mu_s - \bar\mu)(\mu_s - \bar\mu)^\top\bigr]

    Parameters
    ----------
    gm : GaussianMixture
        The mixture, of dimension d.

    Returns
    -------
    Moments
        ``mean`` and ``cov`` of the mixture.
    """
    instance_of(gm, GaussianMixture, "gm")
    mean = gm.weights @ gm.means
    diff = gm.means - mean
    cov = np.einsum("s,sij->ij", gm.weights, gm.covs) + diff.T @ (diff * gm.weights[:, None])
    return Moments(mean=mean, cov=0.5 * (cov + cov.T))


def gm_sample(gm: GaussianMixture, rng: np.random.Generator, n: int) -> FloatArray:
    """Draw ``n`` samples (shape (n, d)).

    A component label :math:`s` is drawn with probability :math:`\\pi_s`, then
    :math:`x = \\mu_s + L_s z` with :math:`L_sL_s^\\top = P_s` and :math:`z \\sim \\mathcal N(0, I)`.

    Parameters
    ----------
    gm : GaussianMixture
        The mixture, of dimension d.
    rng : numpy.random.Generator
        Source of randomness.
    n : int
        Number of samples, at least one.

    Returns
    -------
    ndarray, shape (n, d)
        ``n`` independent draws from ``gm``, one per row.

    Raises
    ------
    TypeError
        ``gm`` not a :class:`GaussianMixture` or ``rng`` not a Generator.
    ValueError
        ``n`` not a positive integer, or ``n`` samples of ``gm`` beyond the memory or work budget (4 arrays of
        ``n x (d + 2)``; ``5 + 5 d + 0.03 d**2`` units a sample).
    """
    instance_of(gm, GaussianMixture, "gm")
    as_rng(rng)
    n = count(n, "n")
    # rules 9 and 17 (fuzz 57b C3), before any draw. Memory: the sample, its normal draws, the means of its rows and a
    # component's rows, with the labels and their order (int64): tracemalloc's peak 8.3 float64 a row at d = 1, 5.1 x 2
    # at d = 2, 3.1-3.8 x d at d = 20 to 300, within 4 arrays of (n, d + 2). Work: a row costs 5 + 5 d + 0.03 d**2
    # units (time.process_time, OPENBLAS_NUM_THREADS=1, shared machine: 64 ns a row at d = 1, 117 ns at d = 2, 266 ns
    # at d = 4, 630 ns at d = 20, 3.5 us at d = 100, 21 us at d = 300), and each component drawn a LOOP_STEP.
    _sample_budget(n, gm.dim, gm.weights.size)
    labels = rng.choice(gm.weights.size, size=n, p=gm.weights)
    L = np.linalg.cholesky(gm.covs)
    z = rng.standard_normal((n, gm.dim))
    x = gm.means[labels]
    # per component (fuzz 57b C3: ``L[labels]``, an (n, d, d) array, was a raw MemoryError of 7.45 GiB for an 80 MB
    # sample of dimension 100): the same einsum row by row, so the same bits as the stacked one
    order = np.argsort(labels, kind="stable")
    drawn, starts = np.unique(labels[order], return_index=True)  # the components drawn, at most n of them
    for k, rows in zip(drawn.tolist(), np.split(order, starts[1:])):
        x[rows] += np.einsum("ij,nj->ni", L[k], z[rows])
    return x


def _sample_budget(n: int, d: int, components: int) -> int:
    """Refuse ``n`` samples of :func:`gm_sample` from a mixture of dimension ``d`` beyond the memory or work budget (the
    measurements at its call); the units of work."""
    allocation((n, d + 2), "n and gm (its dimension d)", arrays=4)
    return work((n * (5 + 5 * d + math.ceil(0.03 * d * d)) + min(n, components) * LOOP_STEP,),
                "n and gm (its dimension d and its components)")


@dataclass(frozen=True)
@frozen_arrays
class EmFit:
    r"""A Gaussian mixture fitted by weighted EM and its log-likelihood trace.

    Arrays are read-only.

    Attributes
    ----------
    mixture : GaussianMixture
        The fitted mixture.
    loglik : ndarray
        Weighted log-likelihood :math:`\sum_q w_q \log \hat p(x^{(q)})` after each iteration
        (non-decreasing: EM's monotonicity, tested).
    """

    mixture: GaussianMixture
    loglik: FloatArray


def _check_init(init: GaussianMixture, n_components: int, dim: int, name: str) -> None:
    """Refuse a warm start ``init`` (checked a :class:`GaussianMixture`) without ``n_components`` components of
    dimension ``dim``, naming ``name``; one with fewer components is the EM's own fit whose components were dropped
    (fuzz 35a D4): the message says so and how to go on from it."""
    if init.dim != dim or init.weights.size > n_components:
        raise ValueError(f"{name} must have {n_components} components of dimension {dim}, got {init.weights.size} "
                         f"of dimension {init.dim}")
    if init.weights.size < n_components:
        raise ValueError(f"{name} must have {n_components} components, got {init.weights.size}: a fit whose "
                         f"components were dropped (vanishing weight or collapsed covariance) warm-starts only a fit "
                         f"of as many, n_components={init.weights.size}")


@derived_inputs()
def weighted_em(
    x: ArrayLike,
    w: ArrayLike,
    n_components: int,
    rng: np.random.Generator,
    max_iter: int = 50,
    tol: float = 1e-8,
    floor: float = 1e-6,
    init: GaussianMixture | None = None,
) -> EmFit:
    r"""Fit a Gaussian mixture to weighted samples by EM.

    Parameters
    ----------
    x : array_like, shape (Q, d)
        Particles.
    w : array_like, shape (Q,)
        Non-negative weights (normalised internally).
    n_components : int
        Number of components :math:`S`, between 1 and Q.
    rng : numpy.random.Generator
        Initialisation: weighted k-means++ choice of the initial means (unless ``init``).
    max_iter, tol
        Stop when the weighted log-likelihood improves by less than ``tol`` (relative).
    floor : float
        Covariance floor :math:`\lambda`: ``floor`` times the weighted variance of each
        coordinate is added to every component covariance, so that resampled duplicates
        cannot make a covariance singular. An absolute :math:`10^{-12} I` (in the samples' units squared) is
        added too, so the fit is not invariant under a change of units that brings the coordinates' variances
        near :math:`10^{-12}`: samples whose variances are below about :math:`10^{-8}` get visibly inflated
        covariances (in units of 1e-6, about twice the data's) and should be rescaled first. Kept because the
        book's recorded chapter-06 fits depend on it (every scale-relative rule tried moved the chain network's
        premise study, 663.1 to 652.8).
    init : GaussianMixture, optional
        Warm start (e.g. the previous frame's mixture, predicted); must have
        ``n_components`` components of the samples' dimension. A fit whose components were dropped (see Returns)
        has fewer and is refused as ``init`` with this ``n_components``, naming ``init`` and saying so: it
        warm-starts a fit of as many components (``n_components=fit.mixture.weights.size``); no component is
        invented to fill the gap.

    Returns
    -------
    EmFit
        The fitted ``mixture`` and the ``loglik`` trace. A component whose weight vanishes (below
        :math:`10^{-12}`) or whose covariance comes out of an M-step not positive definite (collapsed onto
        coincident samples beyond the floor's reach, e.g. ``floor=0`` or a weight-degenerate sample) is
        dropped: the mixture may have fewer than ``n_components`` components.

    Raises
    ------
    ValueError
        Shapes not (Q, d) and (Q,), non-finite samples or weights, negative or all-zero weights,
        ``n_components`` outside [1, Q], ``init`` of the wrong size (fewer components than ``n_components``: a
        fit with dropped components, named so).

    References
    ----------
    * Dempster, A. P., Laird, N. M., & Rubin, D. B. (1977). Maximum likelihood from incomplete
      data via the EM algorithm. *Journal of the Royal Statistical Society, Series B*, 39(1),
      1-38.
    """
    xx = as_array(x, "x", ndim=2)
    ww = as_weights(w, "w")
    same_length(xx, "x", ww, "w")
    n_components = count(n_components, "n_components")
    if n_components > xx.shape[0]:
        raise ValueError("n_components must be between 1 and the number of samples")
    as_rng(rng)
    max_iter = count(max_iter, "max_iter")
    _em_work(max_iter, 1, xx.shape[0], n_components, xx.shape[1])
    tol = nonnegative_scalar(tol, "tol")
    floor = nonnegative_scalar(floor, "floor")
    if init is not None:
        instance_of(init, GaussianMixture, "init")
    if init is not None:
        _check_init(init, n_components, xx.shape[1], "init")
    return _em_batch(xx[None], ww[None], n_components, [rng], max_iter, tol, floor, [init])[0]


@derived_inputs()
def weighted_em_batch(
    x: ArrayLike,
    w: ArrayLike,
    n_components: int,
    rngs: Sequence[np.random.Generator],
    max_iter: int = 50,
    tol: float = 1e-8,
    floor: float = 1e-6,
    init: Sequence[GaussianMixture | None] | None = None,
) -> list[EmFit]:
    r"""Weighted EM on B independent sample sets at once (vectorised :func:`weighted_em`).

    Problem ``b`` gives exactly what ``weighted_em(x[b], w[b], n_components, rngs[b], ...,
    init=init[b])`` gives: both run the same kernel, whose arithmetic is elementwise numpy (no
    BLAS product), so batching never changes a digit; each problem stops on its own
    convergence test and consumes only its own generator (k-means++ initial means).

    Parameters
    ----------
    x : array_like, shape (B, Q, d)
        B sets of Q particles.
    w : array_like, shape (B, Q)
        Non-negative weights of each set (normalised internally).
    n_components : int
        Number of components :math:`S`, between 1 and Q.
    rngs : sequence of numpy.random.Generator, length B
        One generator per set (used only for sets without a warm start).
        Each draws its own stream: one Generator given twice is refused.
    max_iter, tol, floor
        As in :func:`weighted_em`.
    init : sequence of GaussianMixture or None, length B, optional
        Warm starts (``None`` entries: k-means++), each as :func:`weighted_em`'s ``init`` (``n_components``
        components: a fit with dropped components is refused as ``init[b]``, saying so).

    Returns
    -------
    list of EmFit, length B
        Entry b: the fit of sample set b (``x[b]`` with weights ``w[b]`` and ``rngs[b]``), as :func:`weighted_em`
        returns it.

    Raises
    ------
    ValueError
        Shapes not (B, Q, d) and (B, Q), non-finite values, negative or all-zero weights in a
        set, ``n_components`` outside [1, Q], ``rngs`` or ``init`` of the wrong length, an
        ``init`` of the wrong size.

    References
    ----------
    * Dempster, A. P., Laird, N. M., & Rubin, D. B. (1977). Maximum likelihood from incomplete
      data via the EM algorithm. *Journal of the Royal Statistical Society, Series B*, 39(1),
      1-38.
    """
    xx = as_array(x, "x", ndim=3)
    ww = as_array(w, "w", ndim=2, subnormal=True)
    if ww.shape != xx.shape[:2]:
        raise ValueError(f"x must be (B, Q, d) and w (B, Q), got {xx.shape} and {ww.shape}")
    if np.any(ww < 0) or np.any(ww.sum(axis=1) <= 0):
        raise ValueError("w must be non-negative with a positive sum in every set")
    n_components = count(n_components, "n_components")
    if n_components > xx.shape[1]:
        raise ValueError("n_components must be between 1 and the number of samples")
    rngs = as_rngs(rngs, "rngs", xx.shape[0])  # its list, read once (fuzz 58b C1: a second read could differ)
    max_iter = count(max_iter, "max_iter")
    _em_work(max_iter, xx.shape[0], xx.shape[1], n_components, xx.shape[2])
    tol = nonnegative_scalar(tol, "tol")
    floor = nonnegative_scalar(floor, "floor")
    inits = [None] * xx.shape[0] if init is None else sequence(init, "init", xx.shape[0])  # fuzz 24a U5
    for b, g in enumerate(inits):
        if g is not None:
            instance_of(g, GaussianMixture, f"init[{b}]")
            _check_init(g, n_components, xx.shape[2], f"init[{b}]")
    return _em_batch(xx, ww, n_components, rngs, max_iter, tol, floor, inits)


#: Units of one EM iteration's Python step (its numpy calls, whatever the sizes): measured 71-87 us an iteration of one
#: set (Q = 60 to 200 points, 3 to 5 components, d = 1 to 3; time.process_time, OPENBLAS_NUM_THREADS=1, the least of
#: 3, the machine shared), 103 us of 10 sets, so twice that (fix 72f, fuzz 64b's class: uncounted, the edge of one
#: set of 200 points and 5 components, 10**6 iterations at tol = 0, would have run ~80 CPU-s; now ~9). Counted once
#: an iteration of each block of ``_EM_BLOCK`` sets (the kernel iterates block by block).
_EM_STEP = 16 * LOOP_STEP
#: Units of a set's share of an iteration's Python (its log-likelihood appended, its convergence test): an iteration
#: of a block of 16 sets of 4 points and 4 components measured 214 us (16,000 sets, 11 against 1 iteration; the
#: shared machine, fix 74b), 54 us beyond ``_EM_STEP``, ~3.4 us a set.
_EM_SET_ITER = LOOP_STEP // 2
#: Units of a set's fixed cost outside the iterations (its first k-means++ draw, its ``EmFit`` and validated
#: ``GaussianMixture``): ~107 us a set measured (weighted_em_batch of 5,000 to 20,000 sets of 4 points, 1 component,
#: max_iter = 1: 119-120 us a set, less its share of the iteration; fix 74b, fuzz 66b C4: uncounted, 200,000 sets ran
#: 37.8 CPU-s counted ~9.6e6 units).
_EM_SET = 15 * LOOP_STEP
#: Units of a k-means++ step's Python (a ``Generator.choice`` over the set with probabilities and the running
#: minimum): ~20 us measured (the sets of 4 points above, 4 components against 1: 179 against 119 us a set), plus
#: ``Q (d + 2)`` units for its vectorised passes over the points (~12 ns a point at d = 1, Q = S = 4,000: 0.43 CPU-s
#: the whole fit).
_EM_INIT_STEP = 3 * LOOP_STEP


#: Units of one step of the quadratic features' Python loop (``_features``, one ``np.multiply`` a feature and block):
#: 0.9-1.9 us measured (blocks of 1 and 16 sets of 2 points, d = 100 and 300; fix 75a, the machine shared), so 2.5 us.
_FEATURE_STEP = LOOP_STEP // 4
#: Units of a feature's entry (a set, a feature, a point) built by :func:`_features`: 1.6-2.6 ns measured while the
#: block fits the caches, 25 ns at 1.4e8 entries (1 set of 1,100 points, d = 500: 3.5 CPU-s; fix 75a, fuzz 67b C2:
#: uncounted, d = 1,000 ran 15.8 CPU-s counted 9.5e7 units), so twice the latter.
_FEATURE_ENTRY = 5
#: Units of a set's costs growing with d beyond those of an iteration: ``_SET_D2 d**2 + d**3 / 40`` (its validated
#: ``GaussianMixture``'s eigvalsh, its weighted scatter, the regularisation and copies of its (d, d) matrices):
#: measured beyond the rest of the count at max_iter = 1, 2 points and 1 component, 115 us a set at d = 25, 1.1 ms
#: at d = 100, 3.2 ms at d = 200, 14 ms at d = 400 (fix 75a, fuzz 67b C3: uncounted, 20,000 sets at d = 100 ran
#: 48.8 CPU-s counted 8.6e8 units); counted 0.1, 1.75, 8 and 40 ms.
_SET_D2 = 15


def _em_block(B: int) -> int:
    """Sets in a block of the kernel (``_em_arrays``): at most ``_EM_BLOCK``, blocks of equal sizes (within one)."""
    return -(-B // -(-B // _EM_BLOCK))


def _em_work(max_iter: int, B: int, Q: int, S: int, d: int) -> int:
    """Rule 17 for EM (fuzz 36a C3): ``max_iter`` iterations of B sets of Q points and S components in d dimensions.

    An iteration of a component costs Q (d + K/8 + 2) units, its vectorised steps and the two products with the K
    quadratic features (:func:`_n_features`, about 1.2 ns a point and feature measured, d = 4 to 500; the 2 units a
    point, fix 72f: 21 ns a point and component measured at d = 1, 31 ns at d = 4, against 10 and 50 counted before),
    plus ``d**3 / 40`` for the inverse and the Cholesky of its covariance (about 0.25 ns a ``d**3``, d = 250 to 750:
    40 points of 5,000 dimensions, about 150 CPU-s, counted only Q d before), and an iteration's Python step
    ``_EM_STEP`` for each block of ``_EM_BLOCK`` sets plus ``_EM_SET_ITER`` a set. Before the iterations, each set
    costs ``_EM_SET`` and its k-means++ initialisation S - 1 steps of ``_EM_INIT_STEP + Q (d + 2)`` units (counted
    for every set, an upper bound when some are warm-started: fix 74b, fuzz 66b C3 and C4), plus
    ``_SET_D2 d**2 + d**3 / 40`` for its (d, d) matrices; each block builds its K features of its points,
    ``_FEATURE_STEP`` a feature and ``_FEATURE_ENTRY`` a set, feature and point (fix 75a, fuzz 67b C2 and C3).

    The memory budget (``allocation``) holds a block's features, ``(b, K, Q)`` (b sets of the block), and the (d, d)
    matrices of all sets: 2 S + 2 of ``(B, d, d)`` (the fitted and returned covariances, the weighted scatter of each
    set and its regularisation; counted from the kernel: fix 75a, fuzz 67b C1, a block's (16, 501501, 100) features,
    6 GiB, raised a raw ``MemoryError``). Refused by name before any work; returns the units.
    """
    K = _n_features(d)
    nb = _em_block(B)
    allocation((nb, K, Q), "x (its points and dimension: the quadratic features of a block of sets)")
    allocation((B, d, d), "x (its sets and dimension) and n_components", arrays=2 * S + 2)
    per = Q * (d + K // 8 + 2) + d ** 3 // 40
    blocks = -(-B // nb)
    features = blocks * K * _FEATURE_STEP + B * K * Q * _FEATURE_ENTRY
    init = B * (_EM_SET + _SET_D2 * d ** 2 + d ** 3 // 40 + (S - 1) * (_EM_INIT_STEP + Q * (d + 2))) + features
    iterations = max_iter * (blocks * _EM_STEP + B * (_EM_SET_ITER + S * per))
    return work((init + iterations,), "max_iter, x and n_components")


def _wscatter(X: FloatArray, means: FloatArray, g: FloatArray) -> FloatArray:
    """Weighted scatter sum_q g_q (x_q - m)(x_q - m)^T per set and component: (B, S, d, d).

    X (B, Q, d), means (B, S, d), g (B, S, Q).
    """
    diff = X[:, None, :, :] - means[:, :, None, :]  # (B, S, Q, d)
    return np.matmul(np.swapaxes(diff * g[..., None], -1, -2), diff)


def _dot(a: FloatArray, b: FloatArray) -> FloatArray:
    """:math:`\\sum_j a_jb_j` over the last axis, term by term in a fixed order (broadcasting).

    Elementwise numpy, so every problem of a batch is computed alike wherever it sits in memory (the
    reductions of ``einsum`` take SIMD paths that depend on the alignment of the data, and a batched
    result would then differ in its last bits from the same problem computed alone).
    """
    out = a[..., 0] * b[..., 0]
    for j in range(1, a.shape[-1]):
        out += a[..., j] * b[..., j]  # the sum of the readable ``out = out + ...``, without a fresh array per term
    return out


def _matvec(A: FloatArray, x: FloatArray) -> FloatArray:
    """:math:`Ax` for stacks of matrices (..., n, m) and vectors (..., m), as :func:`_dot`."""
    return _dot(A, x[..., None, :])


def _n_features(d: int) -> int:
    """Number of quadratic features of a d-vector: 1, the d coordinates, the d(d+1)/2 products."""
    return 1 + d + d * (d + 1) // 2


def _features(x: FloatArray) -> FloatArray:
    r"""Quadratic features :math:`\phi(x) = [1, x_1, \dots, x_d, x_ix_j\ (i \le j)]` of points (..., Q, d), as (..., K, Q).

    A Gaussian log density is linear in them, :math:`\log\pi + \log\mathcal N(x; \mu, P) = c^\top\phi(x)`
    (:func:`_gaussian_coefs`), so the log densities of many points under many components are one
    matrix product, and the sufficient statistics of EM's M-step another. Centre the points
    first (near the components): the expansion of the quadratic form then loses no accuracy. Laid
    out feature by feature (K, Q), C order: both products then run in BLAS at full speed.
    """
    d = x.shape[-1]
    xT = np.swapaxes(x, -1, -2)
    out = np.empty(x.shape[:-2] + (_n_features(d), x.shape[-2]))
    out[..., 0, :] = 1.0
    out[..., 1:1 + d, :] = xT
    iu, ju, _ = _triu(d)
    for k, (i, j) in enumerate(zip(iu.tolist(), ju.tolist())):  # from the coordinate rows just written: contiguous
        np.multiply(out[..., 1 + i, :], out[..., 1 + j, :], out=out[..., 1 + d + k, :])
    return out


@lru_cache(maxsize=None)
def _triu(d: int) -> tuple[np.ndarray, np.ndarray, FloatArray]:
    """``np.triu_indices(d)`` and the quadratic coefficients' factors (-1/2 on the diagonal, -1 off it), read-only.

    Cached: the kernels ask for them at every EM iteration and objective evaluation (the same arrays).
    """
    iu, ju = np.triu_indices(d)
    half = np.where(iu == ju, -0.5, -1.0)
    for a in (iu, ju, half):
        a.flags.writeable = False
    return iu, ju, half


def _gaussian_precisions(covs: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
    r"""The mean-free parts of :func:`_gaussian_coefs`: precisions :math:`P^{-1}` (..., M, d, d), log-determinants
    :math:`\log\det P` (..., M) and the quadratic coefficients (..., M, d(d+1)/2).

    Computed once for components whose means move (:func:`_gaussian_coefs_from`), e.g. at every step of
    a search over the exponents with fixed node mixtures; per component, so a problem's values do not
    depend on the others in the batch.
    """
    d = covs.shape[-1]
    L = np.linalg.cholesky(covs)
    Linv = np.linalg.inv(L)
    A = np.matmul(np.swapaxes(Linv, -1, -2), Linv)  # P^-1
    A = 0.5 * (A + np.swapaxes(A, -1, -2))
    logdet = 2.0 * np.sum(np.log(np.diagonal(L, axis1=-2, axis2=-1)), axis=-1)
    iu, ju, half = _triu(d)
    return A, logdet, A[..., iu, ju] * half


def _gaussian_coefs_from(logw: FloatArray, means: FloatArray, A: FloatArray, logdet: FloatArray, quad: FloatArray
                         ) -> tuple[FloatArray, np.ndarray]:
    """:func:`_gaussian_coefs` from the precomputed :func:`_gaussian_precisions` (the same numbers)."""
    d = means.shape[-1]
    b = _matvec(A, means)
    dead = ~np.isfinite(logw)
    const = np.where(dead, 0.0, logw) - 0.5 * (d * np.log(2 * np.pi) + logdet) - 0.5 * _dot(means, b)
    return np.concatenate([const[..., None], b, quad], axis=-1), dead


def _gaussian_coefs(logw: FloatArray, means: FloatArray, covs: FloatArray) -> tuple[FloatArray, np.ndarray]:
    r"""Coefficients (..., M, K) with :math:`c^\top\phi(x) = \log w + \log\mathcal N(x; \mu, P)`, and the dead mask.

    ``logw`` (..., M) (``-inf`` for a dead component: its constant is set to 0 and it is flagged in the
    returned mask (..., M), to be set to ``-inf`` after the product), ``means`` (..., M, d) in the
    coordinates of the features, ``covs`` (..., M, d, d) symmetric positive definite.
    """
    return _gaussian_coefs_from(logw, means, *_gaussian_precisions(covs))


def _component_logpdf(coef: FloatArray, dead: np.ndarray, phi: FloatArray) -> FloatArray:
    """Log densities (..., M, Q) of points with features ``phi`` (..., K, Q) under coefficient rows (..., M, K)."""
    out = np.matmul(coef, phi)
    if dead.any():
        out[dead] = -np.inf
    return out


@own_underflow  # underflow to 0 by design (a kernel, a density or normalised weights: fuzz 33b D6)
def _lse_rows(a: FloatArray) -> FloatArray:
    r""":math:`\log\sum\exp` over the second-to-last axis of (..., M, Q), summed in a fixed order (M small).

    Row by row: :math:`m = \max_j a_j` (0 where not finite), then :math:`\log(e^{a_0 - m} + e^{a_1 - m} + \dots) + m`,
    in two work arrays of shape (..., Q) (the values of the same expression written with fresh temporaries).
    """
    m = a[..., 0, :].copy()
    for j in range(1, a.shape[-2]):
        np.maximum(m, a[..., j, :], out=m)
    fin = np.isfinite(m)
    if not fin.all():
        m[~fin] = 0.0
    s, t = np.empty_like(m), np.empty_like(m)
    np.subtract(a[..., 0, :], m, out=s)
    np.exp(s, out=s)
    for j in range(1, a.shape[-2]):
        np.subtract(a[..., j, :], m, out=t)
        np.exp(t, out=t)
        s += t
    with np.errstate(divide="ignore"):
        np.log(s, out=s)
    s += m
    return s


def _mixture_logpdf_features(logw: FloatArray, means: FloatArray, covs: FloatArray, phi: FloatArray) -> FloatArray:
    """Log density (..., Q) of mixtures (logw (..., M), means (..., M, d), covs (..., M, d, d)) at features (..., K, Q)."""
    coef, dead = _gaussian_coefs(logw, means, covs)
    return _lse_rows(_component_logpdf(coef, dead, phi))


#: Shifted sums :func:`_mixture_logpdf_bounded` accepts without recomputing a point with its own maximum.
_TINY, _HUGE = 1e-290, 1e290


@own_underflow  # underflow to 0 by design (a kernel, a density or normalised weights: fuzz 33b D6)
def _mixture_logpdf_bounded(logw: FloatArray, means: FloatArray, covs: FloatArray, phi: FloatArray) -> FloatArray:
    r""":func:`_mixture_logpdf_features` shifted by a bound instead of each point's largest component: (B, ..., Q).

    The shift :math:`c = \max_k(\log w_k - \tfrac12(d\log 2\pi + \log\det P_k))` of each mixture (a Gaussian log
    density is at most its value at the mean) is folded into the constant coefficient before the product, so the
    component log densities are exponentiated in place and summed: the passes for each point's maximum and the
    subtraction are gone. A point whose shifted sum is not a normal positive number (far from every component) is
    computed again with its own maximum. The values differ from :func:`_mixture_logpdf_features`' at round-off only
    (``tests/test_kernel_parity.py``). At least one leading (batch) axis.
    """
    d = means.shape[-1]
    A, logdet, quad = _gaussian_precisions(covs)
    coef, dead = _gaussian_coefs_from(logw, means, A, logdet, quad)
    peak = np.where(dead, -np.inf, logw - 0.5 * (d * np.log(2 * np.pi) + logdet))  # log w + the density's maximum
    c = np.maximum.reduce(peak, axis=-1)  # (B, ...): a mixture has a live component
    coef[..., 0] -= c[..., None]
    e = np.matmul(coef, phi)  # (B, ..., M, Q), shifted by c
    if dead.any():
        e[dead] = -np.inf
    np.exp(e, out=e)
    s = e[..., 0, :].copy()
    for j in range(1, e.shape[-2]):
        s += e[..., j, :]
    bad = ~((s >= _TINY) & (s <= _HUGE))  # NaN included
    with np.errstate(divide="ignore"):
        np.log(s, out=s)
    s += c[..., None]
    if bad.any():  # far from every component: shifted by the point's own maximum
        idx = np.nonzero(bad)
        lead, qi = idx[:-1], idx[-1]
        g = np.matmul(coef[lead], phi[(*lead, slice(None), qi)][..., None])[..., 0]  # (k, M), shifted by c
        g[dead[lead]] = -np.inf
        mm = np.maximum.reduce(g, axis=1)
        mm = np.where(np.isfinite(mm), mm, 0.0)
        with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
            s[idx] = np.log(np.add.reduce(np.exp(g - mm[:, None]), axis=1)) + mm + c[lead]
    return s


def _unpack_sym(v: FloatArray, d: int) -> FloatArray:
    """Symmetric matrices (..., d, d) from their upper triangles (..., d(d+1)/2) in ``triu_indices`` order."""
    iu, ju, _ = _triu(d)
    out = np.empty(v.shape[:-1] + (d, d))
    out[..., iu, ju] = v
    out[..., ju, iu] = v
    return out


#: Problems per block in the EM kernel, each block iterated to its end before the next (keeps a block's features and
#: temporaries in cache across its iterations; results do not depend on it).
_EM_BLOCK = 16


def _positive_definite(covs: FloatArray, live: np.ndarray) -> np.ndarray:
    """Which of the symmetric ``covs`` (..., d, d) of the ``live`` components are positive definite (the others: True).

    A component that collapsed onto a few points far from the rest (a weight-degenerate particle cloud, whose floor
    ``lambda diag(P_bar)`` is near 0) can come out of the M-step indefinite by round-off (fuzz 34a C6: a raw
    LinAlgError in one run of 1,487); the EM drops it as it drops a component whose weight vanished.
    """
    test = np.where(live[..., None, None], covs, np.eye(covs.shape[-1]))
    try:
        np.linalg.cholesky(test)
        return np.ones(live.shape, dtype=bool)
    except np.linalg.LinAlgError:   # rare: find which ones
        ok = np.ones(live.shape, dtype=bool)
        for i in zip(*np.nonzero(live)):
            try:
                np.linalg.cholesky(test[i])
            except np.linalg.LinAlgError:
                ok[i] = False
        return ok


@own_underflow  # underflow to 0 by design (a kernel, a density or normalised weights: fuzz 33b D6)
def _em_arrays(xx: FloatArray, ww: FloatArray, S: int, rngs: list[np.random.Generator], max_iter: int, tol: float,
               floor: float, inits: Sequence[tuple[FloatArray, FloatArray, FloatArray] | None]
               ) -> tuple[FloatArray, FloatArray, FloatArray, list[list[float]]]:
    """Kernel of :func:`weighted_em` and :func:`weighted_em_batch` on validated input, as arrays.

    ``inits[b]`` is None (k-means++ from ``rngs[b]``) or a warm start ``(weights, means, covs)`` of S
    components.

    Returns ``pis`` (B, S) (0 for a dead component), ``means`` (B, S, d), ``covs`` (B, S, d, d) and the
    log-likelihood trace of each problem. Each problem's arithmetic is its own (elementwise numpy and
    one matrix product per problem), so the result of a problem does not depend on the others in the
    batch, nor on how they are blocked.
    """
    B, Q, d = xx.shape
    ww = ww / ww.sum(axis=1, keepdims=True)
    mean_all = np.matmul(ww[:, None, :], xx)[:, 0]  # (B, d)
    cov_all = _wscatter(xx, mean_all[:, None], ww[:, None])[:, 0]
    diag = np.diagonal(cov_all, axis1=1, axis2=2)
    reg = floor * diag[:, :, None] * np.eye(d) + 1e-12 * np.eye(d)
    means, covs, pis = np.empty((B, S, d)), np.empty((B, S, d, d)), np.empty((B, S))
    for b in range(B):
        g0 = inits[b]
        if g0 is not None:
            pis[b], means[b], covs[b] = g0
            continue
        x1, w1, rng = xx[b], ww[b], rngs[b]  # weighted k-means++ initial means
        idx = [int(rng.choice(Q, p=w1))]
        d2 = None  # the squared distance of each point to its nearest chosen mean, kept running (fuzz 66b C3: the
        for _ in range(1, S):  # distances to all chosen means were recomputed at each step, O(Q S**2 d) uncounted);
            new = ((x1 - x1[idx[-1]]) ** 2).sum(-1)  # the same sums, and a minimum is exact: the same draws
            d2 = new if d2 is None else np.minimum(d2, new, out=d2)
            p = w1 * d2
            idx.append(int(rng.choice(Q, p=p / p.sum())) if p.sum() > 0 else int(rng.integers(Q)))
        means[b] = x1[idx]
        covs[b] = cov_all[b] / S + reg[b]
        pis[b] = 1.0 / S
    history: list[list[float]] = [[] for _ in range(B)]
    nb = _em_block(B)  # blocks of at most _EM_BLOCK problems, of equal sizes (within one)
    # work buffers of one block, reused at every iteration (no fresh temporaries)
    gam_buf, m_buf, tot_buf, t_buf = np.empty((nb, S, Q)), np.empty((nb, Q)), np.empty((nb, Q)), np.empty((nb, Q))
    for j0 in range(0, B, nb):  # block by block, each to its end: its features stay in cache across iterations
        a = np.arange(j0, min(j0 + nb, B))
        phi = _features(xx[a] - mean_all[a][:, None, :])  # centred: the quadratic expansion stays accurate
        W = ww[a]
        for _ in range(max_iter):
            n = a.size
            with np.errstate(divide="ignore"):  # a component may have died (weight 0)
                logpi = np.log(pis[a])
            coef, dead = _gaussian_coefs(logpi, means[a] - mean_all[a][:, None], covs[a])
            gam = np.matmul(coef, phi, out=gam_buf[:n])  # (b, S, Q) log responsibilities, unnormalised
            if dead.any():
                gam[dead] = -np.inf
            m, tot, t = m_buf[:n], tot_buf[:n], t_buf[:n]
            if S > 1:
                np.maximum(gam[:, 0], gam[:, 1], out=m)
                for j in range(2, S):
                    np.maximum(m, gam[:, j], out=m)
            else:
                m[...] = gam[:, 0]
            np.subtract(gam, m[:, None, :], out=gam)
            np.exp(gam, out=gam)
            if S > 1:
                np.add(gam[:, 0], gam[:, 1], out=tot)
                for j in range(2, S):
                    tot += gam[:, j]
            else:
                tot[...] = gam[:, 0]
            np.log(tot, out=t)
            t += m
            t *= W
            ll = np.add.reduce(t, axis=1)
            np.divide(W, tot, out=tot)
            gam *= tot[:, None, :]  # responsibilities times the sample weight
            stats = np.matmul(gam, np.swapaxes(phi, -1, -2))  # (b, S, K): weights, first and second moments
            nk = stats[..., 0]
            keep = nk > 1e-12
            with np.errstate(divide="ignore", invalid="ignore"):  # dead components: computed, then discarded
                m_c = stats[..., 1:1 + d] / nk[..., None]
                c_new = (_unpack_sym(stats[..., 1 + d:], d) / nk[..., None, None]
                         - m_c[..., :, None] * m_c[..., None, :] + reg[a][:, None])
            c_new = 0.5 * (c_new + np.swapaxes(c_new, -1, -2))
            keep &= _positive_definite(c_new, keep)  # collapsed below the floor: dead too (fuzz 34a C6)
            p_new = np.where(keep, nk, 0.0)
            pis[a] = p_new / p_new.sum(axis=1, keepdims=True)
            bi, si = np.nonzero(keep)
            means[a[bi], si] = m_c[bi, si] + mean_all[a[bi]]
            covs[a[bi], si] = c_new[bi, si]
            for h, v in zip((history[b] for b in a), ll.tolist()):
                h.append(v)
            done = np.array([len(history[b]) > 1 and abs(history[b][-1] - history[b][-2]) <= tol * abs(history[b][-2])
                             for b in a], dtype=bool)
            if done.all():
                break
            if done.any():  # compact the working set only when it changes
                a, phi, W = a[~done], phi[~done], W[~done]
    return pis, means, covs, history


def _em_batch(xx: FloatArray, ww: FloatArray, S: int, rngs: list[np.random.Generator], max_iter: int, tol: float,
              floor: float, inits: list[GaussianMixture | None]) -> list[EmFit]:
    """Kernel of :func:`weighted_em` and :func:`weighted_em_batch` on validated input."""
    starts = [None if g is None else (g.weights, g.means, g.covs) for g in inits]
    pis, means, covs, history = _em_arrays(xx, ww, S, rngs, max_iter, tol, floor, starts)
    out = []
    for b in range(xx.shape[0]):
        sel = pis[b] > 0
        out.append(EmFit(mixture=GaussianMixture(pis[b, sel] / pis[b, sel].sum(), means[b, sel], covs[b, sel]),
                         loglik=np.array(history[b])))
    return out
