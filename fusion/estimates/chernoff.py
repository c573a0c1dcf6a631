r"""Chernoff fusion of densities (patent CN107330468B, steps D-I), rebuilt.

The Chernoff fusion (generalised covariance intersection, exponential mixture density) of
densities :math:`p_1, \dots, p_N` with exponent weights :math:`\varepsilon` on the simplex
:math:`\Delta = \{\varepsilon_i \ge 0, \sum_i \varepsilon_i = 1\}` is

.. math:: p_\varepsilon(x) = \frac{\prod_i p_i(x)^{\varepsilon_i}}{Z(\varepsilon)}, \qquad
          Z(\varepsilon) = \int \prod_i p_i(x)^{\varepsilon_i}\,dx \le 1,

and the Chernoff criterion picks :math:`\varepsilon^* = \arg\min_\Delta \log Z(\varepsilon)`
(Hurley 2002). For Gaussians it is covariance intersection
(:func:`chernoff_fuse_gaussians`). For Gaussian mixtures the power of a sum is replaced by the
sum of powers, the "first-order approximation" (:func:`foa_fusion`), whose normaliser bounds
:math:`Z` from above. The patent's steps E-I (:func:`fuse_mixtures`) correct the approximation
by importance sampling and choose :math:`\varepsilon` on the samples.

Every formula of the patent's claims is missing from the source text; the equations here are
the chapter's reconstruction (labels ``eq-chf-*`` in notebook 04).

References
----------
* Chernoff, H. (1952). A measure of asymptotic efficiency for tests of a hypothesis based on
  the sum of observations. *Annals of Mathematical Statistics*, 23(4), 493-507.
* Julier, S. J., & Uhlmann, J. K. (1997). A non-divergent estimation algorithm in the presence
  of unknown correlations. *Proceedings of the 1997 American Control Conference*.
* Hurley, M. B. (2002). An information theoretic justification for covariance intersection and
  its generalization. *Proceedings of the 5th International Conference on Information Fusion*.
* Julier, S. J. (2006). An empirical study into the use of Chernoff information for robust,
  distributed fusion of Gaussian mixture models. *Proceedings of the 9th International
  Conference on Information Fusion*.
* University of Electronic Science and Technology of China (2021). Multi-sensor distributed
  data fusion method based on the Chernoff fusion criterion. Patent CN107330468B.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import minimize

from fusion._timing import LapTimer
from fusion._validation import (
    FloatArray,
    _numeric,
    as_array,
    as_callable,
    as_covariance,
    as_rng,
    count,
    gaussian_pair,
    instance_of,
    one_of,
    unit_scalar,
)
from fusion.estimates.mixtures import GaussianMixture, _logsumexp, gm_logpdf, gm_moments, gm_sample, logsumexp
from fusion.filtering.particles import effective_sample_size, weighted_moments
from fusion.optimise.result import OptimumResult
from fusion.optimise.swarm import particle_swarm

__all__ = [
    "ChernoffGaussian",
    "MixtureFusion",
    "check_simplex",
    "chernoff_fuse_gaussians",
    "gaussian_log_normaliser",
    "is_second_moment",
    "gaussian_chernoff_weights",
    "gaussian_kl",
    "log_normaliser_two_gaussians",
    "FoaMixture",
    "foa_fusion",
    "log_densities",
    "is_objective",
    "fused_weights",
    "minimise_on_simplex",
    "simplex_minimum",
    "fuse_mixtures",
]


@dataclass(frozen=True)
class ChernoffGaussian:
    """Chernoff fusion of Gaussians: the fused Gaussian and the log normaliser.

    Attributes
    ----------
    x : ndarray, shape (d,)
        Fused mean.
    P : ndarray, shape (d, d)
        Fused covariance.
    eps : ndarray, shape (N,)
        Exponent weights used (on the simplex unless fused with ``on_simplex=False``).
    log_normaliser : float
        :math:`\\log Z = \\log\\int\\prod_i \\mathcal N(x; \\mu_i, P_i)^{\\varepsilon_i}dx`
        (:math:`\\le 0` on the simplex).
    """

    x: FloatArray
    P: FloatArray
    eps: FloatArray
    log_normaliser: float


def check_simplex(eps: ArrayLike, n: int | None = None, name: str = "eps") -> FloatArray:
    r"""Validate exponent weights: finite, non-negative, summing to one (and of length n).

    Checks :math:`\varepsilon \in \Delta = \{\varepsilon_i \ge 0, \sum_i \varepsilon_i = 1\}`.
    Entries within 1e-12 below zero are clipped to zero; the sum must be one within 1e-8.

    Parameters
    ----------
    eps : array_like, shape (n,)
        Exponent weights (dimensionless).
    n : int, optional
        Required length; any length of at least one if ``None``.
    name : str
        Argument name used in error messages.

    Returns
    -------
    ndarray, shape (n,)
        The weights as floats, tiny negative round-off clipped to zero.

    Raises
    ------
    ValueError
        If the vector has the wrong shape or lies off the simplex.
    """
    if n is not None:
        n = count(n, "n")
    e = _numeric(eps, name)
    if e.ndim != 1 or e.size == 0 or (n is not None and e.size != n):
        raise ValueError(f"{name} must be a 1-D vector of length {n}, got shape {e.shape}")
    if not np.all(np.isfinite(e)) or np.any(e < -1e-12) or abs(e.sum() - 1.0) > 1e-8:
        raise ValueError(f"{name} must lie on the simplex (non-negative, summing to one), got {e}")
    return np.clip(e, 0.0, None)


def _gaussians(means: ArrayLike, covs: ArrayLike) -> tuple[FloatArray, FloatArray]:
    m = _numeric(means, "means")
    c = _numeric(covs, "covs")
    if m.ndim != 2 or m.shape[0] < 1 or c.shape != (m.shape[0], m.shape[1], m.shape[1]):
        raise ValueError(f"means must be (N, d) and covs (N, d, d); got {m.shape} and {c.shape}")
    if not np.all(np.isfinite(m)):
        raise ValueError("means contain NaN or infinite values")
    c = np.stack([as_covariance(c[i], dim=m.shape[1], name=f"covs[{i}]") for i in range(m.shape[0])])
    return m, c


def _product_terms(
    means: FloatArray, infos: FloatArray, logdets: FloatArray, eps: FloatArray
) -> tuple[FloatArray, FloatArray, FloatArray]:
    r"""Vectorised core: fused mean, covariance and log normaliser of Gaussian tuples.

    ``means`` (M, N, d), ``infos`` (M, N, d, d) = :math:`P^{-1}`, ``logdets`` (M, N) =
    :math:`\log\det(2\pi P)`, ``eps`` (N,). The means are centred on their weighted average
    before the quadratic forms, which removes the cancellation that large coordinates (metres
    from an origin) would otherwise cause; the normaliser is translation invariant.
    """
    ref = means.mean(axis=(0, 1))
    mc = means - ref
    info = np.einsum("n,mnij->mij", eps, infos)
    vec = np.einsum("n,mnij,mnj->mi", eps, infos, mc)
    P = np.linalg.inv(info)
    P = 0.5 * (P + np.swapaxes(P, 1, 2))
    mu = np.einsum("mij,mj->mi", P, vec)
    quad_in = np.einsum("mni,mnij,mnj->mn", mc, infos, mc)
    log_z = (-0.5 * (logdets + quad_in) @ eps
             + 0.5 * np.linalg.slogdet(2 * np.pi * P)[1] + 0.5 * np.einsum("mi,mi->m", mu, vec))
    return mu + ref, P, log_z


def chernoff_fuse_gaussians(
    means: ArrayLike, covs: ArrayLike, eps: ArrayLike, *, on_simplex: bool = True
) -> ChernoffGaussian:
    r"""Normalised :math:`\prod_i \mathcal N(x; \mu_i, P_i)^{\varepsilon_i}`: covariance intersection.

    .. math::
        P^{-1} &= \sum_i \varepsilon_i P_i^{-1}, \qquad
        \hat x = P\sum_i \varepsilon_i P_i^{-1}\mu_i, \\
        \log Z &= \sum_i \varepsilon_i\Bigl[-\tfrac12\log\det(2\pi P_i)
        - \tfrac12\mu_i^\top P_i^{-1}\mu_i\Bigr] \\
        &\quad + \tfrac12\log\det(2\pi P) + \tfrac12\hat x^\top P^{-1}\hat x

    (notebook 04, eqs. ``eq-chf-k1`` and ``eq-chf-lognorm``). For two Gaussians and weights
    :math:`(\omega, 1-\omega)` this is covariance intersection with weight :math:`\omega`
    (Julier & Uhlmann 1997).

    Parameters
    ----------
    means : array_like, shape (N, d)
        Means :math:`\mu_i` of the N Gaussians, in the state's units.
    covs : array_like, shape (N, d, d)
        Covariances :math:`P_i`; symmetric positive definite.
    eps : array_like, shape (N,)
        Exponent weights :math:`\varepsilon`, on the simplex unless ``on_simplex=False``
        (then any non-negative weights with a positive-definite fused information, e.g. the
        naive product :math:`\varepsilon = (1, \dots, 1)` that double counts common information).
    on_simplex : bool
        Require ``eps`` on the simplex (keyword only).

    Returns
    -------
    ChernoffGaussian
        ``.x``, ``.P``, ``.eps``, ``.log_normaliser``.

    Raises
    ------
    ValueError
        Shape mismatch, non-finite means, covariances not SPD, weights off the simplex.
        With one Gaussian, the result is that Gaussian (weight 1).

    References
    ----------
    * Julier, S. J., & Uhlmann, J. K. (1997). A non-divergent estimation algorithm in the
      presence of unknown correlations. *Proceedings of the 1997 American Control Conference*.
    * Hurley, M. B. (2002). An information theoretic justification for covariance intersection
      and its generalization. *Proceedings of the 5th International Conference on Information
      Fusion*.
    """
    m, c = _gaussians(means, covs)
    if on_simplex:
        e = check_simplex(eps, m.shape[0], name="eps")
    else:
        e = _numeric(eps, "eps")
        if e.shape != (m.shape[0],) or not np.all(np.isfinite(e)) or np.any(e < 0) or e.sum() <= 0:
            raise ValueError("eps must be finite, non-negative, not all zero and one per Gaussian")
    infos = np.linalg.inv(c)
    logdets = np.linalg.slogdet(2 * np.pi * c)[1]
    mu, P, log_z = _product_terms(m[None], infos[None], logdets[None], e)
    return ChernoffGaussian(x=mu[0], P=P[0], eps=e, log_normaliser=float(log_z[0]))


def gaussian_log_normaliser(means: ArrayLike, covs: ArrayLike, eps: ArrayLike) -> float:
    r""":math:`\log Z(\varepsilon)` for Gaussians (see :func:`chernoff_fuse_gaussians`).

    .. math:: \log Z(\varepsilon) = \log\int\prod_i \mathcal N(x; \mu_i, P_i)^{\varepsilon_i}\,dx

    Parameters
    ----------
    means : array_like, shape (N, d)
        Means of the N Gaussians.
    covs : array_like, shape (N, d, d)
        Their covariances; symmetric positive definite.
    eps : array_like, shape (N,)
        Exponent weights on the simplex.

    Returns
    -------
    float
        :math:`\log Z` in nats, :math:`\le 0`.

    Raises
    ------
    ValueError
        As :func:`chernoff_fuse_gaussians`.
    """
    return chernoff_fuse_gaussians(means, covs, eps).log_normaliser


def is_second_moment(means: ArrayLike, covs: ArrayLike, eps: ArrayLike, eps0: ArrayLike) -> float:
    r"""Second moment of the importance weights of Gaussian Chernoff fusion sampled at other exponents.

    Target :math:`p_\varepsilon = \mathcal N(\hat x_\varepsilon, P_\varepsilon)` (the normalised fusion
    at ``eps``), proposal :math:`g = p_{\varepsilon^{(0)}}` (the fusion at ``eps0``, which is the
    first-order mixture :math:`g` of step D for single Gaussians). With
    :math:`w = p_\varepsilon / g` (so :math:`\mathbb E_g w = 1`),

    .. math::

        \rho = \mathbb E_g[w^2] = \frac{|G|^{1/2}}{|P|\,|\Lambda|^{1/2}}
               \exp\Bigl(\tfrac12 h^\top\Lambda^{-1}h - a^\top P^{-1}a\Bigr),

        \Lambda = 2P^{-1} - G^{-1} = \sum_i (2\varepsilon_i - \varepsilon^{(0)}_i)P_i^{-1},

    :math:`P = P_\varepsilon`, :math:`G = P_{\varepsilon^{(0)}}`, :math:`a = \hat x_\varepsilon - \hat x_{\varepsilon^{(0)}}`,
    :math:`h = 2P^{-1}a`. The weights have finite variance iff :math:`\Lambda \succ 0`; otherwise
    :math:`\rho = \infty`. The relative variance of the estimate :math:`\hat Z` from R samples is
    :math:`(\rho - 1)/R`, and :math:`\hat J = \log\hat Z` is biased low by about
    :math:`(\rho - 1)/(2R)` (Jensen; first order in :math:`1/R`).

    Parameters
    ----------
    means : array_like, shape (N, d)
        Means of the N Gaussians.
    covs : array_like, shape (N, d, d)
        Their covariances; symmetric positive definite.
    eps : array_like, shape (N,)
        Exponents of the target, on the simplex.
    eps0 : array_like, shape (N,)
        Exponents of the proposal, on the simplex.

    Returns
    -------
    float
        :math:`\rho \ge 1` (1 when ``eps == eps0``), or ``inf`` outside the finite-variance region.

    Raises
    ------
    ValueError
        As :func:`chernoff_fuse_gaussians`; ``eps0`` not on the simplex or of the wrong length.

    References
    ----------
    * Owen, A. B. (2013). *Monte Carlo Theory, Methods and Examples*, chapter 9 (importance
      sampling). https://artowen.su.domains/mc/
    """
    target = chernoff_fuse_gaussians(means, covs, eps)
    n = np.shape(target.eps)[0]
    e0 = check_simplex(eps0, n, name="eps0")
    prop = chernoff_fuse_gaussians(means, covs, e0)
    P, G = target.P, prop.P
    Pinv, Ginv = np.linalg.inv(P), np.linalg.inv(G)
    Lam = 2.0 * Pinv - Ginv
    Lam = 0.5 * (Lam + Lam.T)
    if np.min(np.linalg.eigvalsh(Lam)) <= 1e-12 * np.max(np.abs(np.linalg.eigvalsh(2.0 * Pinv))):
        return float("inf")
    a = target.x - prop.x
    h = 2.0 * Pinv @ a
    log_rho = (0.5 * np.linalg.slogdet(G)[1] - np.linalg.slogdet(P)[1] - 0.5 * np.linalg.slogdet(Lam)[1]
               + 0.5 * h @ np.linalg.solve(Lam, h) - a @ Pinv @ a)
    return float(np.exp(log_rho))


def log_normaliser_two_gaussians(a: ArrayLike, A: ArrayLike, b: ArrayLike, B: ArrayLike, omega: float) -> float:
    r"""Closed-form :math:`\log Z(\omega)` for :math:`\mathcal N(a, A)^{\omega}\mathcal N(b, B)^{1-\omega}`.

    .. math::
        \log Z &= -\tfrac12\omega(1-\omega)(a-b)^\top[(1-\omega)A + \omega B]^{-1}(a-b) \\
                &\quad + \tfrac12\log\det P_\omega - \tfrac\omega2\log\det A - \tfrac{1-\omega}2\log\det B,

    with :math:`P_\omega = (\omega A^{-1} + (1-\omega)B^{-1})^{-1}` (notebook 04, eq. ``eq-chf-k2``;
    an independent formula used to test :func:`chernoff_fuse_gaussians`). It is :math:`\le 0`.

    Parameters
    ----------
    a, b : array_like, shape (d,)
        Means of the two Gaussians.
    A, B : array_like, shape (d, d)
        Their covariances; symmetric positive definite.
    omega : float in [0, 1]
        Exponent of the first Gaussian.

    Returns
    -------
    float
        :math:`\log Z(\omega)` in nats.

    Raises
    ------
    ValueError
        ``omega`` outside [0, 1], or covariances not SPD of size d.
    """
    omega = unit_scalar(omega, "omega")
    a, A, b, B = gaussian_pair(a, A, b, B, ("a", "A", "b", "B"))
    d = a - b
    M = (1 - omega) * A + omega * B
    Pw = np.linalg.inv(omega * np.linalg.inv(A) + (1 - omega) * np.linalg.inv(B))
    return float(-0.5 * omega * (1 - omega) * d @ np.linalg.solve(M, d) + 0.5 * np.linalg.slogdet(Pw)[1]
                 - 0.5 * omega * np.linalg.slogdet(A)[1] - 0.5 * (1 - omega) * np.linalg.slogdet(B)[1])


def gaussian_kl(m0: ArrayLike, P0: ArrayLike, m1: ArrayLike, P1: ArrayLike) -> float:
    r""":math:`\mathrm{KL}(\mathcal N(m_0, P_0)\,\|\,\mathcal N(m_1, P_1))` in nats.

    .. math:: \tfrac12\bigl[\operatorname{tr}(P_1^{-1}P_0) + (m_1-m_0)^\top P_1^{-1}(m_1-m_0) - d
              + \log\det P_1 - \log\det P_0\bigr]

    Parameters
    ----------
    m0, m1 : array_like, shape (d,)
        Means of the two Gaussians.
    P0, P1 : array_like, shape (d, d)
        Their covariances; symmetric positive definite.

    Returns
    -------
    float
        The divergence in nats, :math:`\ge 0`.

    Raises
    ------
    ValueError
        Covariances not SPD of size d.

    References
    ----------
    * Kullback, S., & Leibler, R. A. (1951). On information and sufficiency. *Annals of
      Mathematical Statistics*, 22(1), 79-86.
    """
    m0, P0, m1, P1 = gaussian_pair(m0, P0, m1, P1, ("m0", "P0", "m1", "P1"))
    dm = m1 - m0
    return float(0.5 * (np.trace(np.linalg.solve(P1, P0)) + dm @ np.linalg.solve(P1, dm) - m0.size
                        + np.linalg.slogdet(P1)[1] - np.linalg.slogdet(P0)[1]))


def minimise_on_simplex(
    f: Callable[[FloatArray], float], n: int, jac: Callable[[FloatArray], FloatArray] | None = None,
    x0: ArrayLike | None = None, ftol: float = 1e-14,
) -> OptimumResult:
    """Minimise ``f`` over the probability simplex with SLSQP (the deterministic reference).

    ``f`` is only ever called on the simplex (trial points are clipped and renormalised), so it
    may validate its argument. ``ftol`` is SLSQP's stopping tolerance on ``f``: near round-off
    (the default) the number of iterations, though not the optimum, may depend on the BLAS
    kernel and thread count; a larger one (1e-10) stops the same way on every machine.

    Parameters
    ----------
    f : callable
        Objective ``f(eps) -> float`` of a vector of shape (n,).
    n : int
        Dimension of the simplex (number of weights), at least one.
    jac : callable, optional
        Gradient ``jac(eps) -> ndarray`` of shape (n,); finite differences if ``None``.
    x0 : array_like, shape (n,), optional
        Starting point on the simplex; the uniform weights if ``None``.
    ftol : float
        SLSQP's stopping tolerance on ``f`` (positive).

    Returns
    -------
    OptimumResult
        ``x``: the minimiser, on the simplex (clipped and renormalised against round-off);
        ``fun``: ``f(x)``; ``n_evaluations``: objective evaluations used.

    Raises
    ------
    ValueError
        ``n < 1`` or ``x0`` off the simplex.
    """
    as_callable(f, "f")
    n = count(n, "n")
    if jac is not None:
        as_callable(jac, "jac")
    if n == 1:
        e = np.ones(1)
        return OptimumResult(x=e, fun=float(f(e)), n_evaluations=1)
    start = np.full(n, 1.0 / n) if x0 is None else check_simplex(x0, n, name="x0")

    def on_simplex(e: FloatArray) -> FloatArray:  # finite-difference steps may leave the simplex
        c = np.clip(e, 0.0, None)
        return c / c.sum() if c.sum() > 0 else np.full(n, 1.0 / n)

    res = minimize(lambda e: f(on_simplex(e)), start, jac=jac, method="SLSQP", bounds=[(0.0, 1.0)] * n,
                   constraints=[{"type": "eq", "fun": lambda e: e.sum() - 1.0, "jac": lambda e: np.ones_like(e)}],
                   options={"ftol": ftol, "maxiter": 300})
    e = np.clip(res.x, 0.0, None)
    e = e / e.sum()
    return OptimumResult(x=e, fun=float(f(e)), n_evaluations=int(res.nfev))


def gaussian_chernoff_weights(means: ArrayLike, covs: ArrayLike) -> ChernoffGaussian:
    r"""Chernoff-optimal fusion of Gaussians: :math:`\arg\min_\Delta \log Z(\varepsilon)`, then fuse.

    :math:`\log Z` is convex on the simplex (Hölder), so SLSQP finds the global minimum.
    At an interior optimum the fused density is equally far, in Kullback-Leibler divergence,
    from every input: :math:`\mathrm{KL}(p_{\varepsilon^*}\|p_i) = -\log Z(\varepsilon^*)`.

    Parameters
    ----------
    means : array_like, shape (N, d)
        Means of the N Gaussians.
    covs : array_like, shape (N, d, d)
        Their covariances; symmetric positive definite.

    Returns
    -------
    ChernoffGaussian
        The fused Gaussian at :math:`\varepsilon^*`.

    Raises
    ------
    ValueError
        Shape mismatch, non-finite means, covariances not SPD.

    References
    ----------
    * Hurley, M. B. (2002). An information theoretic justification for covariance intersection
      and its generalization. *Proceedings of the 5th International Conference on Information
      Fusion*.
    """
    m, c = _gaussians(means, covs)
    infos = np.linalg.inv(c)[None]
    logdets = np.linalg.slogdet(2 * np.pi * c)[1][None]

    def f(e: FloatArray) -> float:
        return float(_product_terms(m[None], infos, logdets, np.clip(e, 0.0, None))[2][0])

    e = minimise_on_simplex(f, m.shape[0]).x
    return chernoff_fuse_gaussians(m, c, e)


@dataclass(frozen=True)
class FoaMixture:
    """First-order-approximation fusion of mixtures: the fused mixture and its log normaliser.

    Attributes
    ----------
    mixture : GaussianMixture
        The fused mixture (components with normalised weight below 1e-12 pruned).
    log_z_foa : float
        :math:`\\log\\sum_{m_f}\\tilde\\alpha_{m_f}`, which is :math:`\\ge \\log Z(\\varepsilon)`
        (subadditivity of :math:`t \\mapsto t^{\\varepsilon}`), with equality for
        single-component inputs (always the full weights, even when ``simplified``).
    """

    mixture: GaussianMixture
    log_z_foa: float


def foa_fusion(gms: Sequence[GaussianMixture], eps: ArrayLike, simplified: bool = False) -> FoaMixture:
    r"""First-order-approximation Chernoff fusion of Gaussian mixtures (patent step D, rebuilt).

    :math:`(\sum_s \pi_s\mathcal N_s)^{\varepsilon} \approx \sum_s \pi_s^{\varepsilon}\mathcal N_s^{\varepsilon}`,
    so that every tuple :math:`m_f = (s_1, \dots, s_N)` of components gives one Gaussian, the
    covariance intersection of the chosen components, with weight

    .. math:: \log\tilde\alpha_{m_f} = \sum_i \varepsilon_i\log\pi_{i,s_i} + \log Z_{m_f}(\varepsilon)

    (notebook 04, eq. ``eq-chf-foa``), :math:`Z_{m_f}` the Gaussian normaliser of
    :func:`chernoff_fuse_gaussians`. With ``simplified=True`` the overlap term is dropped,
    :math:`\tilde\alpha \propto \prod_i\pi_{i,s_i}^{\varepsilon_i}`, as some public codes do.
    Computed in log space and vectorised over the :math:`M_f = \prod_i S_i` tuples.

    Parameters
    ----------
    gms : sequence of GaussianMixture
        The N mixtures, all of dimension d; mixture i has :math:`S_i` components.
    eps : array_like, shape (N,)
        Exponent weights on the simplex.
    simplified : bool
        Drop the overlap term :math:`\log Z_{m_f}` from the component weights.

    Returns
    -------
    FoaMixture
        The fused ``mixture`` and ``log_z_foa``.

    Raises
    ------
    ValueError
        No mixtures, objects that are not mixtures, mixed dimensions, ``eps`` off the simplex.

    References
    ----------
    * Julier, S. J. (2006). An empirical study into the use of Chernoff information for robust,
      distributed fusion of Gaussian mixture models. *Proceedings of the 9th International
      Conference on Information Fusion*.
    """
    _check_mixtures(gms)
    d = gms[0].dim
    e = check_simplex(eps, len(gms))
    idx = np.array(list(itertools.product(*[range(g.weights.size) for g in gms])))  # (M, N)
    cols = range(len(gms))
    means = np.stack([gms[i].means[idx[:, i]] for i in cols], axis=1)
    infos = np.stack([np.linalg.inv(gms[i].covs)[idx[:, i]] for i in cols], axis=1)
    logdets = np.stack([np.linalg.slogdet(2 * np.pi * gms[i].covs)[1][idx[:, i]] for i in cols], axis=1)
    logpi = np.stack([np.log(gms[i].weights)[idx[:, i]] for i in cols], axis=1)
    mu, P, log_zm = _product_terms(means, infos, logdets, e)
    log_alpha_full = logpi @ e + log_zm
    log_z = float(logsumexp(log_alpha_full))
    lw = logpi @ e if simplified else log_alpha_full
    w = np.exp(lw - logsumexp(lw))
    keep = w > 1e-12
    w = w[keep] / w[keep].sum()
    return FoaMixture(mixture=GaussianMixture(w, mu[keep], P[keep]), log_z_foa=log_z)


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


def log_densities(gms: Sequence[GaussianMixture], x: ArrayLike) -> FloatArray:
    """Matrix :math:`L_{ri} = \\log \\hat p_i(x^{(r)})`, shape (R, N).

    Parameters
    ----------
    gms : sequence of GaussianMixture
        The N mixtures :math:`\\hat p_i`, of dimension d.
    x : array_like, shape (R, d)
        Sample points.

    Returns
    -------
    ndarray, shape (R, N)
        Log densities in nats (per unit volume of the state).
    """
    _check_mixtures(gms)
    return np.column_stack([gm_logpdf(g, x) for g in gms])


def is_objective(L: ArrayLike, log_g: ArrayLike, eps: ArrayLike) -> FloatArray:
    r"""Importance-sampling estimate of :math:`\log Z(\varepsilon)` (patent step F, rebuilt).

    .. math:: \hat J(\varepsilon) = \log\frac1R\sum_r \exp\Bigl(\sum_i\varepsilon_i L_{ri} - \log g(x^{(r)})\Bigr)

    (notebook 04, eq. ``eq-chf-is``): a log-sum-exp of affine functions of :math:`\varepsilon`,
    hence convex.

    Parameters
    ----------
    L : array_like, shape (R, N)
        :math:`\log\hat p_i(x^{(r)})` (:func:`log_densities`).
    log_g : array_like, shape (R,)
        Log density of the proposal at the samples.
    eps : array_like, shape (N,) or (E, N)
        One exponent vector, or a whole swarm scored in one matrix product.

    Returns
    -------
    ndarray, shape () or (E,)
    """
    Lm, lg = _L_logg(L, log_g)
    E = as_array(eps, "eps", ndim=(1, 2))
    if E.shape[-1] != Lm.shape[1]:
        raise ValueError(f"eps has {E.shape[-1]} entries, L has {Lm.shape[1]} columns")
    return _is_objective(Lm, lg, E)


def _L_logg(L: ArrayLike, log_g: ArrayLike) -> tuple[FloatArray, FloatArray]:
    """Validated log-density matrix (R, N) and proposal log density (R,)."""
    Lm = as_array(L, "L", ndim=2)
    lg = as_array(log_g, "log_g", ndim=1)
    if lg.shape != (Lm.shape[0],):
        raise ValueError(f"L must be (R, N) and log_g (R,), got {Lm.shape} and {lg.shape}")
    return Lm, lg


def _is_objective(Lm: FloatArray, lg: FloatArray, eps: FloatArray) -> FloatArray:
    """Kernel of :func:`is_objective` on validated arrays (called inside the optimisers)."""
    E = np.atleast_2d(eps)
    vals = _logsumexp(_combine(Lm, E.T) - lg[:, None], axis=0) - np.log(Lm.shape[0])
    return vals if np.ndim(eps) == 2 else vals[0]


def _combine(L: FloatArray, E: FloatArray) -> FloatArray:
    """``L @ E`` for few columns of ``L``, summed term by term in a fixed order.

    Not a BLAS product: its rounding would depend on the BLAS kernel and thread count, and
    the optimisers compare these values (elementwise numpy arithmetic rounds the same way
    everywhere).
    """
    out = L[:, :1] * E[:1] if E.ndim == 2 else L[:, 0] * E[0]
    for i in range(1, L.shape[1]):
        out = out + (L[:, i : i + 1] * E[i : i + 1] if E.ndim == 2 else L[:, i] * E[i])
    return out


def _is_gradient(L: FloatArray, log_g: FloatArray, eps: FloatArray) -> FloatArray:
    lw = _combine(L, eps) - log_g
    w = np.exp(lw - _logsumexp(lw, 0))
    return np.sum(w[:, None] * L, axis=0)


def fused_weights(L: ArrayLike, log_g: ArrayLike, eps: ArrayLike) -> FloatArray:
    r"""Normalised weights of the importance samples under :math:`p_\varepsilon` (claim 2, rebuilt).

    .. math:: \tilde w^{(r)} \propto \exp\Bigl(\sum_i \varepsilon_i L_{ri} - \log g(x^{(r)})\Bigr)

    (notebook 04, eq. ``eq-chf-weights``).

    Parameters
    ----------
    L : array_like, shape (R, N)
        :math:`\log\hat p_i(x^{(r)})` (:func:`log_densities`).
    log_g : array_like, shape (R,)
        Log density of the proposal at the samples.
    eps : array_like, shape (N,)
        Exponent weights on the simplex.

    Returns
    -------
    ndarray, shape (R,)
        Non-negative weights summing to one.

    Raises
    ------
    ValueError
        ``eps`` off the simplex or of the wrong length.
    """
    Lm, lg = _L_logg(L, log_g)
    e = check_simplex(eps, Lm.shape[1])
    lw = _combine(Lm, e) - lg
    return np.exp(lw - logsumexp(lw))


def simplex_minimum(L: ArrayLike, log_g: ArrayLike) -> OptimumResult:
    r"""Minimise :func:`is_objective` on the simplex with SLSQP and its exact gradient.

    The deterministic reference for the swarm. Stops when an iteration improves :math:`\\hat J` by
    less than 1e-10 (far above round-off, so that the number of evaluations is the same with any
    BLAS kernel or thread count; far below the Monte-Carlo error of :math:`\\hat J`).

    Parameters
    ----------
    L : array_like, shape (R, N)
        :math:`\\log\\hat p_i(x^{(r)})` (:func:`log_densities`).
    log_g : array_like, shape (R,)
        Log density of the proposal at the samples.

    Returns
    -------
    OptimumResult
        ``x``: the minimiser, on the simplex; ``fun``: :math:`\\hat J(\\varepsilon)` there;
        ``n_evaluations``: objective evaluations used.
    """
    Lm, lg = _L_logg(L, log_g)
    return minimise_on_simplex(lambda e: float(_is_objective(Lm, lg, e)), Lm.shape[1],
                               jac=lambda e: _is_gradient(Lm, lg, e), ftol=1e-10)


@dataclass(frozen=True)
class MixtureFusion:
    """Result of the patent's steps D-I on one frame (see :func:`fuse_mixtures`).

    Attributes
    ----------
    x, P : ndarray, shapes (d,), (d, d)
        Claim 3: weighted mean and covariance of the fused samples at :math:`\\varepsilon^*`.
    eps : ndarray, shape (N,)
        :math:`\\varepsilon^*` found by the chosen optimiser (on the simplex).
    objective : float
        :math:`\\hat J(\\varepsilon^*)`.
    eps0 : ndarray, shape (N,)
        The exponents of the proposal (step D).
    x_eps0, P_eps0 : ndarray
        Estimate at :math:`\\varepsilon^{(0)}` (steps E and H without F-G).
    x_foa, P_foa : ndarray
        Moments of the proposal mixture :math:`g` itself (step D only).
    ess : float
        Effective sample size of the fused weights at :math:`\\varepsilon^*`.
    ess_eps0 : float
        The same at :math:`\\varepsilon^{(0)}`.
    log_z_foa : float
        Log normaliser of the first-order approximation at :math:`\\varepsilon^{(0)}`.
    n_fused_components : int
        :math:`M_f` after pruning.
    swarm : OptimumResult or None
        Convergence record when the optimiser is the swarm.
    n_evaluations : int
        Objective evaluations used by the optimiser.
    eps_reference : ndarray or None
        With ``reference=True``: SLSQP's optimum on the same samples (also
        ``objective_reference``, ``x_reference``, ``P_reference``,
        ``n_evaluations_reference``).
    x_redraw : ndarray or None
        With ``redraw=True``: the estimate from fresh samples of :math:`g(\\varepsilon^*)` (also
        ``P_redraw``, ``ess_redraw``).
    """

    x: FloatArray
    P: FloatArray
    eps: FloatArray
    objective: float
    eps0: FloatArray
    x_eps0: FloatArray
    P_eps0: FloatArray
    x_foa: FloatArray
    P_foa: FloatArray
    ess: float
    ess_eps0: float
    log_z_foa: float
    n_fused_components: int
    swarm: OptimumResult | None
    n_evaluations: int
    eps_reference: FloatArray | None = None
    objective_reference: float | None = None
    x_reference: FloatArray | None = None
    P_reference: FloatArray | None = None
    n_evaluations_reference: int | None = None
    x_redraw: FloatArray | None = None
    P_redraw: FloatArray | None = None
    ess_redraw: float | None = None


def fuse_mixtures(
    gms: Sequence[GaussianMixture],
    rng: np.random.Generator,
    n_samples: int = 2000,
    eps0: ArrayLike | None = None,
    optimiser: str = "pso",
    redraw: bool = False,
    reference: bool = False,
    swarm_options: dict[str, float] | None = None,
    timings: dict[str, float] | None = None,
) -> MixtureFusion:
    r"""The patent's steps D-I on the mixtures of all nodes, rebuilt.

    D: first-order Chernoff fusion at :math:`\varepsilon^{(0)}` (uniform by default: the patent
    gives none) is the proposal :math:`g`; E: :math:`R` samples from :math:`g`; F: the
    importance-sampling objective :func:`is_objective`; G: its minimiser on the simplex, by
    particle swarm (``"pso"``, steps G1-G6) or SLSQP (``"slsqp"``); H: fused sample weights
    (:func:`fused_weights`, claim 2); I: their mean and covariance (claim 3).

    Parameters
    ----------
    gms : sequence of GaussianMixture
        One mixture per node (step C), the local one and the received ones.
    rng : numpy.random.Generator
        Drives the sampling and the swarm.
    n_samples : int
        :math:`R`.
    eps0 : array_like, shape (N,), optional
        Exponents of the proposal.
    optimiser : {"pso", "slsqp"}
    redraw : bool
        Also (not in the patent) draw fresh samples from :math:`g(\varepsilon^*)` and weight
        them at :math:`\varepsilon^*`, instead of reusing those drawn at
        :math:`\varepsilon^{(0)}` (fields ``*_redraw``).
    reference : bool
        Also minimise the same objective with SLSQP (fields ``*_reference``).
    swarm_options : dict, optional
        Keyword arguments for :func:`fusion.optimise.swarm.particle_swarm`.
    timings : dict, optional
        If given, seconds spent per stage are added to it (keys ``"foa"``, ``"sampling"``,
        ``"densities"``, ``"optimiser"``, ``"reference"``, ``"weights"``, ``"redraw"``).

    Returns
    -------
    MixtureFusion
    """
    one_of(optimiser, ("pso", "slsqp"), "optimiser")
    _check_mixtures(gms)
    as_rng(rng)
    n_samples = count(n_samples, "n_samples", minimum=2)
    N = len(gms)
    e0 = np.full(N, 1.0 / N) if eps0 is None else check_simplex(eps0, N, name="eps0")
    clock = LapTimer(timings)
    foa = foa_fusion(gms, e0)  # D
    g, log_z_foa = foa.mixture, foa.log_z_foa
    clock.lap("foa")
    xs = gm_sample(g, rng, n_samples)  # E
    log_g = gm_logpdf(g, xs)
    clock.lap("sampling")
    L = log_densities(gms, xs)  # F
    clock.lap("densities")
    swarm: OptimumResult | None = None
    if optimiser == "pso":  # G
        swarm = particle_swarm(lambda E: -_is_objective(L, log_g, E), N, rng, **(swarm_options or {}))
        eps, obj, nev = swarm.x, -swarm.fun, swarm.n_evaluations
    else:
        opt = simplex_minimum(L, log_g)
        eps, obj, nev = opt.x, opt.fun, opt.n_evaluations
    clock.lap("optimiser")
    w0 = fused_weights(L, log_g, e0)
    w = fused_weights(L, log_g, eps)  # H
    mom, mom0, mom_f = weighted_moments(xs, w), weighted_moments(xs, w0), gm_moments(g)  # I
    x, P, x0, P0, xf, Pf = mom.mean, mom.cov, mom0.mean, mom0.cov, mom_f.mean, mom_f.cov
    clock.lap("weights")
    extra: dict[str, object] = {}
    if reference:
        ref = simplex_minimum(L, log_g)
        e_r, j_r, n_r = ref.x, ref.fun, ref.n_evaluations
        mom_r = weighted_moments(xs, fused_weights(L, log_g, e_r))
        x_r, P_r = mom_r.mean, mom_r.cov
        extra.update(eps_reference=e_r, objective_reference=j_r, x_reference=x_r, P_reference=P_r,
                     n_evaluations_reference=n_r)
        clock.lap("reference")
    if redraw:
        g_star = foa_fusion(gms, eps).mixture
        xs_h = gm_sample(g_star, rng, n_samples)
        w_h = fused_weights(log_densities(gms, xs_h), gm_logpdf(g_star, xs_h), eps)
        mom_h = weighted_moments(xs_h, w_h)
        x_h, P_h = mom_h.mean, mom_h.cov
        extra.update(x_redraw=x_h, P_redraw=P_h, ess_redraw=float(1.0 / np.sum(w_h**2)))
        clock.lap("redraw")
    return MixtureFusion(x=x, P=P, eps=eps, objective=float(obj), eps0=e0, x_eps0=x0, P_eps0=P0, x_foa=xf, P_foa=Pf,
                         ess=effective_sample_size(w), ess_eps0=effective_sample_size(w0), log_z_foa=log_z_foa,
                         n_fused_components=int(g.weights.size), swarm=swarm, n_evaluations=nev,
                         **extra)  # type: ignore[arg-type]


