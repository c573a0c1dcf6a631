r"""Gaussian mixtures: densities, sampling and weighted EM (patent CN107330468B, step C).

scikit-learn's ``GaussianMixture`` accepts no sample weights, and the particles of a particle
filter are weighted, so the EM here is written for weighted samples (Dempster, Laird & Rubin
1977):

* E-step: :math:`\gamma_{qs} \propto \pi_s \mathcal N(x^{(q)}; \mu_s, P_s)`;
* M-step: :math:`\pi_s = \sum_q w_q\gamma_{qs}`, :math:`\mu_s = \sum_q w_q\gamma_{qs}x^{(q)}/\pi_s`,
  :math:`P_s = \sum_q w_q\gamma_{qs}(x^{(q)} - \mu_s)(\cdot)^\top/\pi_s + \lambda I`.

References
----------
* Dempster, A. P., Laird, N. M., & Rubin, D. B. (1977). Maximum likelihood from incomplete
  data via the EM algorithm. *Journal of the Royal Statistical Society, Series B*, 39(1), 1-38.
* Arthur, D., & Vassilvitskii, S. (2007). k-means++: the advantages of careful seeding.
  *Proceedings of the 18th Annual ACM-SIAM Symposium on Discrete Algorithms*.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike
from scipy.linalg import solve_triangular

from fusion._frozen import freeze_arrays
from fusion._validation import (
    FloatArray,
    _numeric,
    as_array,
    as_covariance,
    as_rng,
    as_state,
    as_weights,
    count,
    instance_of,
    nonnegative_scalar,
    same_length,
)

__all__ = ["EmFit", "Moments", "GaussianMixture", "logsumexp", "gaussian_logpdf", "gm_logpdf", "gm_moments", "gm_sample", "weighted_em"]


def logsumexp(a: ArrayLike, axis: int = 0) -> FloatArray:
    """:math:`\\log\\sum\\exp` along ``axis``, stable for large negative entries (``-inf`` allowed).

    A lean equivalent of :func:`scipy.special.logsumexp` for real arrays (that one checks
    its input on every call, which dominates the cost inside EM and the swarm).

    .. math:: \\log\\sum_j e^{a_j} = m + \\log\\sum_j e^{a_j - m}, \\qquad m = \\max_j a_j.

    Parameters
    ----------
    a : array_like
        Real values (``-inf`` allowed, ``nan`` propagates).
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
    return _logsumexp(arr, axis)


def _logsumexp(arr: FloatArray, axis: int) -> FloatArray:
    m = np.max(arr, axis=axis, keepdims=True)
    m = np.where(np.isfinite(m), m, 0.0)
    with np.errstate(divide="ignore"):  # all -inf along the axis gives -inf, as scipy does
        return np.squeeze(m, axis=axis) + np.log(np.sum(np.exp(arr - m), axis=axis))


@dataclass(frozen=True)
class GaussianMixture:
    """A Gaussian mixture :math:`\\sum_s \\pi_s \\mathcal N(x; \\mu_s, P_s)`.

    Attributes
    ----------
    weights : ndarray, shape (S,)
        Non-negative, summing to one.
    means : ndarray, shape (S, d)
    covs : ndarray, shape (S, d, d)
        Symmetric positive definite.
    """

    weights: FloatArray
    means: FloatArray
    covs: FloatArray

    def __post_init__(self) -> None:
        w = as_array(self.weights, "weights", ndim=1)
        m = as_array(self.means, "means", ndim=2)
        c = as_array(self.covs, "covs", ndim=3)
        if not (w.size == m.shape[0] == c.shape[0]):
            raise ValueError(f"inconsistent shapes: weights {w.shape}, means {m.shape}, covs {c.shape}")
        if c.shape[1:] != (m.shape[1], m.shape[1]):
            raise ValueError(f"covs must have shape (S, {m.shape[1]}, {m.shape[1]}), got {c.shape}")
        if np.any(w < 0) or abs(w.sum() - 1.0) > 1e-9:
            raise ValueError("weights must be non-negative and sum to one")
        if not np.allclose(c, np.swapaxes(c, 1, 2)):
            raise ValueError("covs must be symmetric")
        try:
            np.linalg.cholesky(c)
        except np.linalg.LinAlgError:
            raise ValueError("covs must be positive definite") from None
        object.__setattr__(self, "weights", w)
        object.__setattr__(self, "means", m)
        object.__setattr__(self, "covs", c)

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
        If ``x`` is not (R, d) (or (d,)) with the mixture's dimension d, or is not finite.
    """
    instance_of(gm, GaussianMixture, "gm")
    xx = np.atleast_2d(as_array(x, "x", ndim=(1, 2)))
    if xx.shape[1] != gm.dim:
        raise ValueError(f"x must have {gm.dim} columns (the mixture's dimension), got shape {np.shape(x)}")
    return _gm_logpdf(gm, xx)


def _gm_logpdf(gm: GaussianMixture, xx: FloatArray) -> FloatArray:
    comps = np.stack([np.log(gm.weights[s]) + _logpdf(xx, gm.means[s], gm.covs[s])
                      for s in range(gm.weights.size) if gm.weights[s] > 0])
    return _logsumexp(comps, axis=0)


@dataclass(frozen=True)
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

    __post_init__ = freeze_arrays


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

    Raises
    ------
    TypeError
        ``gm`` not a :class:`GaussianMixture` or ``rng`` not a Generator.
    ValueError
        ``n`` not a positive integer.
    """
    instance_of(gm, GaussianMixture, "gm")
    as_rng(rng)
    n = count(n, "n")
    labels = rng.choice(gm.weights.size, size=n, p=gm.weights)
    L = np.linalg.cholesky(gm.covs)
    z = rng.standard_normal((n, gm.dim))
    return gm.means[labels] + np.einsum("nij,nj->ni", L[labels], z)


@dataclass(frozen=True)
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

    __post_init__ = freeze_arrays


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
        cannot make a covariance singular.
    init : GaussianMixture, optional
        Warm start (e.g. the previous frame's mixture, predicted); must have
        ``n_components`` components of the samples' dimension.

    Returns
    -------
    EmFit
        The fitted ``mixture`` and the ``loglik`` trace.

    Raises
    ------
    ValueError
        Shapes not (Q, d) and (Q,), non-finite samples or weights, negative or all-zero weights,
        ``n_components`` outside [1, Q], ``init`` of the wrong size.

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
    tol = nonnegative_scalar(tol, "tol")
    floor = nonnegative_scalar(floor, "floor")
    if init is not None:
        instance_of(init, GaussianMixture, "init")
    ww = ww / ww.sum()
    d = xx.shape[1]
    mean_all = ww @ xx
    cov_all = (xx - mean_all).T @ ((xx - mean_all) * ww[:, None])
    reg = floor * np.diag(np.diag(cov_all)) + 1e-12 * np.eye(d)
    if init is not None:
        if init.weights.size != n_components or init.dim != d:
            raise ValueError(f"init must have {n_components} components of dimension {d}")
        means, covs, pis = init.means.copy(), init.covs.copy(), init.weights.copy()
    else:  # weighted k-means++ initial means
        idx = [int(rng.choice(xx.shape[0], p=ww))]
        for _ in range(1, n_components):
            d2 = np.min(((xx[:, None, :] - xx[idx][None]) ** 2).sum(-1), axis=1)
            p = ww * d2
            idx.append(int(rng.choice(xx.shape[0], p=p / p.sum())) if p.sum() > 0 else int(rng.integers(xx.shape[0])))
        means = xx[idx].copy()
        covs = np.repeat((cov_all / n_components + reg)[None], n_components, axis=0)
        pis = np.full(n_components, 1.0 / n_components)
    history = []
    for _ in range(max_iter):
        with np.errstate(divide="ignore"):  # a component may have died (weight 0)
            logpi = np.log(pis)
        logr = np.stack([logpi[s] + _logpdf(xx, means[s], covs[s]) for s in range(n_components)], axis=1)
        lse = _logsumexp(logr, axis=1)
        history.append(float(ww @ lse))
        gamma = np.exp(logr - lse[:, None]) * ww[:, None]  # (Q, S), includes the sample weight
        nk = gamma.sum(axis=0)
        keep = nk > 1e-12
        pis = np.where(keep, nk, 0.0)
        pis = pis / pis.sum()
        for s in np.flatnonzero(keep):
            means[s] = gamma[:, s] @ xx / nk[s]
            diff = xx - means[s]
            covs[s] = diff.T @ (diff * gamma[:, s][:, None]) / nk[s] + reg
            covs[s] = 0.5 * (covs[s] + covs[s].T)
        if len(history) > 1 and abs(history[-1] - history[-2]) <= tol * abs(history[-2]):
            break
    sel = pis > 0
    return EmFit(mixture=GaussianMixture(pis[sel] / pis[sel].sum(), means[sel], covs[sel]), loglik=np.array(history))
