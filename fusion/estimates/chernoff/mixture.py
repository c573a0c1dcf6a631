r"""Chernoff fusion of Gaussian mixtures (patent CN107330468B, steps D-I).

The power of a sum is replaced by the sum of powers, the "first-order approximation"
(:func:`first_order_fusion`, step D), whose normaliser bounds :math:`Z` from above. The patent's steps E-I
(:func:`fuse_mixtures`) correct the approximation by importance sampling: samples from the
approximation, the objective :func:`is_objective` on them, its minimiser over the simplex
(:func:`simplex_minimum`, or the patent's particle swarm) and the fused weights
(:func:`fused_weights`). :func:`fuse_mixtures_batch` runs many problems at once.

References
----------
* Julier, S. J. (2006). An empirical study into the use of Chernoff information for robust,
  distributed fusion of Gaussian mixture models. *Proceedings of the 9th International
  Conference on Information Fusion*.
* University of Electronic Science and Technology of China (2021). Multi-sensor distributed
  data fusion method based on the Chernoff fusion criterion. Patent CN107330468B.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Sequence
import dataclasses
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from fusion._guards import own_underflow
from fusion._frozen import frozen_arrays
from fusion._results import ResultSpec, instance, number, validated_post_init
from fusion.estimates.chernoff._timings import FusionTimings
from fusion.estimates.chernoff._sampling import _mixture_mean, _moments_batch, _sample_mixture  # noqa: F401
from fusion._timing import LapTimer
from fusion.estimates.chernoff._product import MIXTURE_STEP, product_size, sample_memory
from fusion._validation import (MAX_MAGNITUDE, FloatArray, _covariance_magnitude, _numeric, allocation, as_array, as_rng,
                                as_rngs, asymmetric, count, derived_inputs, flag, instance_of, one_of, read_once, refuse_singular,
                                renormalised, sums_to_one, work)
from fusion.estimates.mixtures import (GaussianMixture, _component_logpdf, _dot, _features, _gaussian_coefs, _logsumexp,
                                       _check_mixtures, _density_points, _lse_rows, _matvec, _mixture_logpdf_bounded, gm_logpdf, logsumexp)
from fusion.optimise.result import OptimumResult
from fusion.optimise.swarm import SwarmOptions, check_swarm_options, particle_swarm_batch, _swarm_work
from fusion.estimates.chernoff.gaussian import _chernoff_derivatives_prepare, _chernoff_derivatives_prepared, _product_combine, _product_prepare, _product_terms
from fusion.optimise.simplex import (_active_problems, _plane_newton_steps, _simplex_newton, check_simplex,
                                     minimise_on_simplex, simplex_row)

__all__ = [
    "MixtureFusion",
    "FusionTimings",
    "FirstOrderMixture",
    "first_order_fusion",
    "log_densities",
    "is_objective",
    "fused_weights",
    "simplex_minimum",
    "fuse_mixtures",
    "fuse_mixtures_batch",
]


def _first_order_log_normaliser_derivatives(logw: FloatArray, means: FloatArray, covs: FloatArray, eps: FloatArray
                                    ) -> tuple[FloatArray, FloatArray, FloatArray]:
    r""":math:`\log Z_{\rm FO}(\varepsilon)`, its gradient and Hessian for B problems (mixtures padded as in :func:`_first_order_arrays`).

    :math:`\log Z_{\rm FO} = \log\sum_m\tilde\alpha_m`, :math:`\log\tilde\alpha_m = \sum_i\varepsilon_i\log\pi_{i,s_i}
    + \log Z_m(\varepsilon)` over the component tuples :math:`m`; with :math:`\alpha_m` the normalised weights and
    :math:`v_m = \nabla\log\tilde\alpha_m`, the gradient is :math:`\sum_m\alpha_mv_m` and the Hessian
    :math:`\sum_m\alpha_m(\nabla^2\log Z_m + v_mv_m^\top) - (\sum_m\alpha_mv_m)(\cdot)^\top`: a log-sum-exp of
    convex functions, convex."""
    return _first_order_derivatives_prepared(_first_order_derivatives_prepare(logw, means, covs), eps)


def _first_order_derivatives_prepare(logw: FloatArray, means: FloatArray, covs: FloatArray) -> tuple[FloatArray, ...]:
    """The exponent-free arrays of :func:`_first_order_log_normaliser_derivatives` (the tuples' dead flags and log
    weights, and ``gaussian._chernoff_derivatives_prepare``'s arrays of every tuple), problems on the first
    axis: computed once for a search over the exponents, and a subset of problems is ``tuple(a[idx] for a in prep)``."""
    B, N, S, d = means.shape
    idx = np.array(list(itertools.product(range(S), repeat=N)), dtype=int).reshape(-1, N)
    M, cols = idx.shape[0], np.arange(N)
    alive = np.isfinite(logw)
    dead_t = ~np.all(alive[:, cols, idx], axis=-1)  # (B, M)
    logpi_t = np.where(alive, logw, 0.0)[:, cols, idx]
    infos, logdets = np.linalg.inv(covs), np.linalg.slogdet(2 * np.pi * covs)[1]
    mt = means[:, cols, idx].reshape(B * M, N, d)
    it = infos[:, cols, idx].reshape(B * M, N, d, d)
    lt = logdets[:, cols, idx].reshape(B * M, N)
    tuples = _chernoff_derivatives_prepare(mt, it, lt)  # (B M, ...) each: regrouped by problem (B, M, ...)
    return (dead_t, logpi_t) + tuple(a.reshape((B, M) + a.shape[1:]) for a in tuples)


@own_underflow  # underflow to 0 by design (a kernel, a density or normalised weights: fuzz 33b D6)
def _first_order_derivatives_prepared(prep: tuple[FloatArray, ...], eps: FloatArray
                                      ) -> tuple[FloatArray, FloatArray, FloatArray]:
    """:func:`_first_order_log_normaliser_derivatives` from :func:`_first_order_derivatives_prepare`'s arrays at
    exponents ``eps`` (B, N) (the same numbers)."""
    dead_t, logpi_t = prep[:2]
    B, M, N = logpi_t.shape
    tuples = tuple(a.reshape((B * M,) + a.shape[2:]) for a in prep[2:])
    lz, g, H = _chernoff_derivatives_prepared(tuples, np.repeat(eps, M, axis=0))
    la = np.where(dead_t, -np.inf, _dot(logpi_t, eps[:, None, :]) + lz.reshape(B, M))
    f = _logsumexp(la, axis=1)
    alpha = np.exp(la - f[:, None])  # (B, M), 0 for dead tuples
    v = np.where(dead_t[..., None], 0.0, logpi_t + g.reshape(B, M, N))
    grad = _dot(np.swapaxes(v, 1, 2), alpha[:, None, :])
    second = H.reshape(B, M, N, N) + v[..., :, None] * v[..., None, :]
    hess = _dot(np.moveaxis(second, 1, 3), alpha[:, None, None, :]) - grad[:, :, None] * grad[:, None, :]
    return f, grad, 0.5 * (hess + np.swapaxes(hess, 1, 2))


def _first_order_minimum(logw: FloatArray, means: FloatArray, covs: FloatArray) -> FloatArray:
    r"""Exponents (B, N) minimising the first-order normaliser :math:`\log Z_{\rm FO}` on the simplex (convex)."""
    B, N = logw.shape[:2]
    prep = _first_order_derivatives_prepare(logw, means, covs)  # the exponent-free arrays once
    return _simplex_newton(lambda i, e: _first_order_derivatives_prepared(tuple(a[i] for a in prep), e), B, N)


@dataclass(frozen=True)
class FirstOrderMixture:
    """First-order-approximation fusion of mixtures: the fused mixture and its log normaliser.

    Attributes
    ----------
    mixture : GaussianMixture
        The fused mixture (components with normalised weight below 1e-12 pruned).
    log_z_first_order : float
        :math:`\\log\\sum_{m_f}\\tilde\\alpha_{m_f}`, which is :math:`\\ge \\log Z(\\varepsilon)`
        (subadditivity of :math:`t \\mapsto t^{\\varepsilon}`), with equality for
        single-component inputs (always the full weights, even when ``simplified``).

    Raises
    ------
    TypeError
        ``mixture`` not a :class:`~fusion.estimates.mixtures.GaussianMixture`, ``log_z_first_order`` not a real
        number.
    ValueError
        ``log_z_first_order`` not finite. It is stored as a float (a 0-d array is read, never kept: fuzz 29a C1).
    """

    mixture: GaussianMixture
    log_z_first_order: float

    __result_spec__ = ResultSpec({"mixture": instance(GaussianMixture),
                                  "log_z_first_order": number(nonnegative=False)})
    __post_init__ = validated_post_init


def first_order_fusion(gms: Sequence[GaussianMixture], eps: ArrayLike, simplified: bool = False) -> FirstOrderMixture:
    r"""First-order-approximation Chernoff fusion of Gaussian mixtures (patent step D, rebuilt).

    :math:`(\sum_s \pi_s\mathcal N_s)^{\varepsilon} \approx \sum_s \pi_s^{\varepsilon}\mathcal N_s^{\varepsilon}`,
    so that every tuple :math:`m_f = (s_1, \dots, s_N)` of components gives one Gaussian, the
    covariance intersection of the chosen components, with weight

    .. math:: \log\tilde\alpha_{m_f} = \sum_i \varepsilon_i\log\pi_{i,s_i} + \log Z_{m_f}(\varepsilon)

    (:doc:`ch. 6 </notebooks/06_chernoff_fusion>`, eq. ``eq-chf-foa``), :math:`Z_{m_f}` the Gaussian normaliser of
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
    FirstOrderMixture
        The fused ``mixture`` and ``log_z_first_order``.

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
    flag(simplified, "simplified")
    _check_mixtures(gms)
    e = check_simplex(eps, len(gms))
    tuples, per = product_size(1, len(gms), max(g.weights.size for g in gms), gms[0].dim, "gms", first_order=True)
    work((tuples * per + len(gms) * MIXTURE_STEP,), "gms (the product mixture's component tuples)")  # fuzz 35a C7
    logw, means, covs = _mixture_arrays(gms)
    w, mu, P, log_z = _first_order_arrays(logw[None], means[None], covs[None], e[None], simplified=simplified)
    keep = w[0] > 0
    return FirstOrderMixture(mixture=GaussianMixture(w[0, keep], mu[0, keep], P[0, keep]), log_z_first_order=float(log_z[0]))


def _mixture_arrays(gms: Sequence[GaussianMixture], S: int | None = None) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Log weights (N, S), means (N, S, d), covariances (N, S, d, d) of N mixtures padded to S components.

    Padding components have log weight ``-inf``, the mixture's first mean and the identity covariance.
    """
    S = max(g.weights.size for g in gms) if S is None else S
    N, d = len(gms), gms[0].dim
    logw, means, covs = np.full((N, S), -np.inf), np.empty((N, S, d)), np.empty((N, S, d, d))
    for i, g in enumerate(gms):
        n = g.weights.size
        with np.errstate(divide="ignore"):
            logw[i, :n] = np.log(g.weights)
        means[i, :n], covs[i, :n] = g.means, g.covs
        means[i, n:], covs[i, n:] = g.means[0], np.eye(d)
    return logw, means, covs


def _first_order_arrays(logw: FloatArray, means: FloatArray, covs: FloatArray, eps: FloatArray, simplified: bool = False
                ) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """Kernel of :func:`first_order_fusion` for B problems of N mixtures padded to S components.

    ``logw`` (B, N, S) (``-inf``: no component), ``means`` (B, N, S, d), ``covs`` (B, N, S, d, d), ``eps``
    (B, N). Returns the fused weights (B, M) (0 for a tuple with a missing or pruned component, pruning
    at 1e-12 after normalisation), means (B, M, d), covariances (B, M, d, d) and log Z_FO (B,), with
    :math:`M = S^N` tuples in lexicographic order. A problem's result does not depend on the others.
    """
    return _first_order_from_prepared(_first_order_prepare(logw, means, covs), eps, simplified)


@own_underflow  # underflow to 0 by design (a kernel, a density or normalised weights: fuzz 33b D6)
def _first_order_prepare(logw: FloatArray, means: FloatArray, covs: FloatArray) -> tuple[FloatArray, ...]:
    """The exponent-free part of :func:`_first_order_arrays` (tuples' log weights, dead mask, precisions, log-determinants and
    centred quadratic terms), all with the problems on the first axis: computed once for a search over the exponents,
    and a subset of problems is ``tuple(a[idx] for a in prep)``."""
    B, N, S, d = means.shape
    idx = np.array(list(itertools.product(range(S), repeat=N)), dtype=int).reshape(-1, N)  # (M, N)
    cols = np.arange(N)
    alive = np.isfinite(logw)
    wts = np.where(alive, np.exp(np.where(alive, logw, 0.0)), 0.0)
    ref = _dot(np.swapaxes(wts, 1, 2)[..., None, :], np.moveaxis(means, 1, 3)).sum(axis=1) / N  # near the data
    infos = np.linalg.inv(covs)
    logdets = np.linalg.slogdet(2 * np.pi * covs)[1]
    logpi_t = np.where(alive, logw, 0.0)[:, cols, idx]  # (B, M, N)
    dead_t = ~np.all(alive[:, cols, idx], axis=-1)  # (B, M)
    infos_t = infos[:, cols, idx]
    t, quad_in = _product_prepare(means[:, cols, idx], infos_t, ref)
    return logpi_t, dead_t, infos_t, logdets[:, cols, idx], t, quad_in, ref


def _first_order_from_prepared(prep: tuple[FloatArray, ...], eps: FloatArray, simplified: bool = False
                       ) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """:func:`_first_order_arrays` from :func:`_first_order_prepare`'s arrays at exponents ``eps`` (B, N) (the same numbers)."""
    logpi_t, dead_t, infos_t, logdets_t, t, quad_in, ref = prep
    mu, P, log_zm = _product_combine(infos_t, logdets_t, t, quad_in, eps, ref)
    w, log_z = _first_order_weights(logpi_t, dead_t, log_zm, eps, simplified)
    return w, mu, P, log_z


@own_underflow  # underflow to 0 by design (a kernel, a density or normalised weights: fuzz 33b D6)
def _first_order_weights(logpi_t: FloatArray, dead_t: np.ndarray, log_zm: FloatArray, eps: FloatArray,
                         simplified: bool) -> tuple[FloatArray, FloatArray]:
    """The weights of :math:`g_\\varepsilon`'s components (B, M), tiny ones set to zero and the rest renormalised,
    and :math:`\\log Z` (B,), from the components' log weights ``logpi_t`` (B, M, N), their dead flags (B, M) and
    the log normalisers of their products (B, M)."""
    lp = _dot(logpi_t, eps[:, None, :])
    log_alpha = np.where(dead_t, -np.inf, lp + log_zm)
    log_z = _logsumexp(log_alpha, axis=1)
    lw = np.where(dead_t, -np.inf, lp) if simplified else log_alpha
    w = np.exp(lw - _logsumexp(lw, axis=1)[:, None])
    w = np.ascontiguousarray(np.where(w > 1e-12, w, 0.0))
    return w / w.sum(axis=1, keepdims=True), log_z


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

    Raises
    ------
    ValueError
        ``x`` not (R, d) with the mixtures' dimension d; every mixture's components x the points beyond the memory or
        work budget (rules 9, 17), named ``gms and x``, before any density is computed.
    """
    x = read_once(x, "x")  # converted once, then checked and used (fuzz 29a C5)
    _check_mixtures(gms)
    xx = _density_points(gms, x, "gms and x")  # rules 9, 17 (fuzz 49b C7): counted before any density
    return np.column_stack([gm_logpdf(g, xx) for g in gms])


def is_objective(L: ArrayLike, log_g: ArrayLike, eps: ArrayLike) -> FloatArray:
    r"""Importance-sampling estimate of :math:`\log Z(\varepsilon)` (patent step F, rebuilt).

    .. math:: \hat J(\varepsilon) = \log\frac1R\sum_r \exp\Bigl(\sum_i\varepsilon_i L_{ri} - \log g(x^{(r)})\Bigr)

    (:doc:`ch. 6 </notebooks/06_chernoff_fusion>`, eq. ``eq-chf-is``): a log-sum-exp of affine functions of :math:`\varepsilon`,
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
        The estimate of log Z(ε) at each row of ``eps`` (a 0-d array for a single ε).
    """
    Lm, lg = _L_logg(L, log_g)
    E = as_array(eps, "eps", ndim=(1, 2), subnormal=True)
    if E.shape[-1] != Lm.shape[1]:
        raise ValueError(f"eps has {E.shape[-1]} entries, L has {Lm.shape[1]} columns")
    # rules 9, 17 (fuzz 38a C2, fix43r): the (R, E) log weights, 7-13 ns each at N = 2-3, 39 at 50: 0.08 a N + 10
    rows = E.shape[0] if E.ndim == 2 else 1
    allocation((Lm.shape[0], rows), "L and eps", arrays=3)  # two at once: tracemalloc peak 2.08 (fuzz 39a D2), up
    work((Lm.shape[0], rows, Lm.shape[1] + 10), "L and eps", weight=0.08)
    return _is_objective(Lm, lg, E)


def _L_logg(L: ArrayLike, log_g: ArrayLike) -> tuple[FloatArray, FloatArray]:
    """Validated log-density matrix (R, N) and proposal log density (R,)."""
    Lm = as_array(L, "L", ndim=2)
    lg = as_array(log_g, "log_g", ndim=1)
    if lg.shape != (Lm.shape[0],):
        raise ValueError(f"L must be (R, N) and log_g (R,), got {Lm.shape} and {lg.shape}")
    return Lm, lg


def _is_objective(Lm: FloatArray, lg: FloatArray, eps: FloatArray) -> FloatArray:
    """Kernel of :func:`is_objective` on validated arrays (called inside SLSQP and the chapter's swarms).

    Elementwise arithmetic (:func:`_combine`), so that its values, and the path of the SLSQP reference
    that compares them, are the same with every BLAS kernel. The batched swarms of
    :func:`fuse_mixtures_batch` score the same objective by one matrix product (:func:`_is_values`),
    which agrees with this to round-off."""
    E = np.atleast_2d(eps)
    vals = _logsumexp(_combine(Lm, E.T) - lg[:, None], axis=0) - np.log(Lm.shape[0])
    return vals if np.ndim(eps) == 2 else vals[0]


def _augmented(LT: FloatArray, lg: FloatArray) -> FloatArray:
    """:math:`[L^\\top; -\\log g; 1]`, shape (..., N + 2, R), C order: the shifted log weights are one matrix product
    (:func:`_is_values`)."""
    return np.ascontiguousarray(np.concatenate([LT, -lg[..., None, :], np.ones_like(lg)[..., None, :]], axis=-2))


def _is_bounds(LTg: FloatArray) -> FloatArray:
    r""":math:`M_i = \max_r(L_{ri} - \log g(x^{(r)}))`, shape (..., N), from :func:`_augmented`'s ``LTg``.

    For exponents on the simplex, :math:`\sum_i\varepsilon_iM_i` bounds every log weight
    :math:`\sum_i\varepsilon_i(L_{ri} - \log g(x^{(r)}))` from above: the shift of :func:`_is_values`.
    """
    N = LTg.shape[-2] - 2
    return np.maximum.reduce(LTg[..., :N, :] + LTg[..., N:N + 1, :], axis=-1)


@own_underflow  # underflow to 0 by design (a kernel, a density or normalised weights: fuzz 33b D6)
def _is_values(LTg: FloatArray, E: FloatArray, out: FloatArray | None = None, bounds: FloatArray | None = None
               ) -> FloatArray:
    r"""Ĵ at exponent rows ``E`` (..., m, N) from ``LTg`` (..., N + 2, R) = :math:`[L^\top; -\log g; 1]`: (..., m).

    The shifted log weights :math:`\sum_i\varepsilon_iL_{ri} - \log g(x^{(r)}) - c` of all rows are one matrix
    product, ``[E, 1, -c] @ LTg`` (BLAS: one product per problem, so a problem's values do not depend on the others;
    their last bits may depend on the BLAS kernel, which the optimisers' tie rule absorbs, ``fusion.optimise._ties``),
    then exponentiated and summed along the samples of one problem, in C order: two passes over the (m, R) array
    after the product. The shift :math:`c = \sum_i\varepsilon_iM_i` (``bounds`` :math:`M`, :func:`_is_bounds`,
    computed here if not given) is at least the largest log weight for exponents on the simplex, so no term
    overflows; a row whose sum is not a normal positive number (a shift far above its largest log weight, exponents
    off the simplex, infinite log densities) is computed again shifted by its largest log weight. ``out``: a C-ordered
    buffer of shape (..., m, R) to compute in (the swarm reuses one instead of allocating fresh arrays at every
    iteration).
    """
    R = LTg.shape[-1]
    N = E.shape[-1]
    M = _is_bounds(LTg) if bounds is None else bounds
    c = _dot(E, M[..., None, :])  # (..., m), term by term
    Ea = np.empty(E.shape[:-1] + (N + 2,))
    Ea[..., :N], Ea[..., N] = E, 1.0
    np.negative(c, out=Ea[..., N + 1])
    out = np.matmul(Ea, LTg, out=out)
    with np.errstate(over="ignore"):  # only off the simplex (such rows are computed again below)
        np.exp(out, out=out)
    s = np.add.reduce(out, axis=-1)
    bad = ~((s >= _TINY) & (s <= _HUGE) & (np.abs(c) <= _HUGE))  # NaN included
    if not bad.any():
        return np.log(s) + c - np.log(R)
    lead = np.nonzero(bad)  # the rows the bound does not suit: shifted by their own largest log weight
    Eb = np.empty((lead[0].size, N + 2))
    Eb[:, :N], Eb[:, N], Eb[:, N + 1] = E[lead], 1.0, 0.0
    a = np.matmul(Eb[:, None, :], LTg[lead[:-1]])[:, 0]  # (k, R)
    m = np.maximum.reduce(a, axis=-1)
    m = np.where(np.isfinite(m), m, 0.0)
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        s[lead] = np.add.reduce(np.exp(a - m[:, None]), axis=-1)
        c[lead] = m
        return np.log(s) + c - np.log(R)


#: Sums of shifted weights accepted by :func:`_is_values` without recomputing: normal, positive, finite.
_TINY, _HUGE = 1e-290, 1e290


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


@own_underflow  # underflow to 0 by design (a kernel, a density or normalised weights: fuzz 33b D6)
def _is_gradient(L: FloatArray, log_g: FloatArray, eps: FloatArray) -> FloatArray:
    lw = _combine(L, eps) - log_g
    w = np.exp(lw - _logsumexp(lw, 0))
    return np.sum(w[:, None] * L, axis=0)


@own_underflow  # underflow to 0 by design (a kernel, a density or normalised weights: fuzz 33b D6)
def fused_weights(L: ArrayLike, log_g: ArrayLike, eps: ArrayLike) -> FloatArray:
    r"""Normalised weights of the importance samples under :math:`p_\varepsilon` (claim 2, rebuilt).

    .. math:: \tilde w^{(r)} \propto \exp\Bigl(\sum_i \varepsilon_i L_{ri} - \log g(x^{(r)})\Bigr)

    (:doc:`ch. 6 </notebooks/06_chernoff_fusion>`, eq. ``eq-chf-weights``).

    Parameters
    ----------
    L, log_g : array_like, shapes (R, N) and (R,)
        The samples' log densities under each node and under the proposal, as in :func:`is_objective`.
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
    L, log_g : array_like, shapes (R, N) and (R,)
        The samples' log densities under each node and under the proposal, as in :func:`is_objective`.

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
@frozen_arrays
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
    x_first_order, P_first_order : ndarray
        Moments of the proposal mixture :math:`g` itself (step D only).
    ess : float
        Effective sample size of the fused weights at :math:`\\varepsilon^*`.
    ess_eps0 : float
        The same at :math:`\\varepsilon^{(0)}`.
    log_z_first_order : float
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
    samples : ndarray, shape (R, d), or None
        With ``keep_samples=True`` (:func:`fuse_mixtures_batch`): the importance samples of step E, with
        ``weights`` (R,), their fused weights at :math:`\\varepsilon^*`, and ``weights_eps0`` (R,), at
        :math:`\\varepsilon^{(0)}`: the fused density as weighted particles, e.g. to fuse again.
    eps_equal_kl : ndarray, shape (N,), or None
        The equal-KL rule on the same samples (the runner of :mod:`fusion.scenarios.range_bearing` asks
        for it): exponents that make the estimated :math:`\\mathrm{KL}(p_\\varepsilon\\|\\hat p_i)` equal for
        every node (NaN where that point lies outside the simplex); ``x_equal_kl`` the estimate there.
    eps_literal : ndarray, shape (N,), or None
        The patent's stopping rule as worded (the runner asks for it): the swarm's best point when its
        positions have converged (every particle within a tolerance of the best), read from the same swarm
        followed to its iteration limit; ``objective_literal`` (:math:`\\hat J` there),
        ``n_evaluations_literal``, and the estimate ``x_literal``, ``P_literal``.
    timings : FusionTimings or None
        With ``timed=True``: seconds per stage of the whole call (shared by every problem of a batch).
    """

    x: FloatArray
    P: FloatArray
    eps: FloatArray
    objective: float
    eps0: FloatArray
    x_eps0: FloatArray
    P_eps0: FloatArray
    x_first_order: FloatArray
    P_first_order: FloatArray
    ess: float
    ess_eps0: float
    log_z_first_order: float
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
    samples: FloatArray | None = None
    weights: FloatArray | None = None
    weights_eps0: FloatArray | None = None
    eps_equal_kl: FloatArray | None = None
    x_equal_kl: FloatArray | None = None
    eps_literal: FloatArray | None = None
    objective_literal: float | None = None
    n_evaluations_literal: int | None = None
    x_literal: FloatArray | None = None
    P_literal: FloatArray | None = None
    timings: FusionTimings | None = None


@derived_inputs("gms")  # an objective beyond the range names the mixtures (fuzz 31a C5)
def fuse_mixtures(
    gms: Sequence[GaussianMixture],
    rng: np.random.Generator,
    n_samples: int = 2000,
    eps0: ArrayLike | None = None,
    optimiser: str = "pso",
    redraw: bool = False,
    reference: bool = False,
    swarm_options: SwarmOptions | None = None,
    timed: bool = False,
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
    swarm_options : SwarmOptions, optional
        Settings of the particle swarm (default ``SwarmOptions()``, the defaults of
        :func:`fusion.optimise.swarm.particle_swarm`).
    timed : bool
        Also return the seconds spent per stage (field ``timings``, a :class:`FusionTimings`).

    Returns
    -------
    MixtureFusion
        The fused mean ``x`` and covariance ``P`` at the optimised exponents ``eps``, the objective, the start and
        first-order fusions, ESS and search diagnostics.

    Raises
    ------
    ValueError
        As :func:`fuse_mixtures_batch`; mixtures whose components lie so far apart for their covariances (means
        of 1e100 at unit variances) that the objective's log-densities leave the range (beyond
        ``fusion._validation.MAX_MAGNITUDE``, 1e150, in magnitude) are refused naming ``gms``: rescale them.
    """
    flag(redraw, "redraw")
    flag(reference, "reference")
    optimiser = one_of(optimiser, ("pso", "slsqp"), "optimiser")
    _check_mixtures(gms)
    as_rng(rng)
    n_samples = count(n_samples, "n_samples", minimum=2)
    N = len(gms)
    e0 = np.full(N, 1.0 / N) if eps0 is None else check_simplex(eps0, N, name="eps0")
    tuples, per = product_size(1, N, max(g.weights.size for g in gms), gms[0].dim, "gms and n_samples", n_samples)
    work((tuples * per + N * MIXTURE_STEP,), "gms and n_samples (the product mixture's component tuples)")  # 35a C7
    sample_memory(1, tuples, gms[0].dim, n_samples, "gms and n_samples")  # fuzz 58b C2
    logw, means, covs = _mixture_arrays(gms)
    flag(timed, "timed")
    return _timed_fusion(logw[None], means[None], covs[None], [rng], n_samples, e0[None], optimiser, redraw, reference,
                         swarm_options, bool(timed))[0]


@derived_inputs("means and covs")  # an objective beyond the range names them (fuzz 31a C5)
def fuse_mixtures_batch(
    weights: ArrayLike,
    means: ArrayLike,
    covs: ArrayLike,
    rngs: Sequence[np.random.Generator],
    n_samples: int = 2000,
    eps0: ArrayLike | None = None,
    optimiser: str = "pso",
    redraw: bool = False,
    reference: bool = False,
    swarm_options: SwarmOptions | None = None,
    timed: bool = False,
    keep_samples: bool = False,
) -> list[MixtureFusion]:
    r"""The patent's steps D-I on B fusion problems at once (vectorised :func:`fuse_mixtures`).

    Problem ``b`` fuses N mixtures given as arrays padded to S components (weight 0: no component).
    It gives exactly what :func:`fuse_mixtures` gives on the same mixtures padded the same way
    (its components in the same order) with ``rngs[b]``: each problem draws only from its own
    generator, in the same order, and every stage is a per-problem computation (elementwise numpy,
    one matrix product or factorisation per problem, reductions over one problem's samples).

    Parameters
    ----------
    weights : array_like, shape (B, N, S)
        Component weights of each node's mixture; each (b, i) row non-negative, summing to one.
    means : array_like, shape (B, N, S, d)
        Component means.
    covs : array_like, shape (B, N, S, d, d)
        Component covariances; symmetric positive definite where the weight is positive (others are
        ignored but must be finite).
    rngs : sequence of numpy.random.Generator, length B
        One per problem: its samples and its swarm.
        Each draws its own stream: one Generator given twice is refused.
    n_samples : int
        :math:`R` per problem.
    eps0 : array_like, shape (B, N) or (N,), optional
        Exponents of the proposals (default uniform).
    optimiser : {"pso", "slsqp", "newton", "none"}
        As in :func:`fuse_mixtures`; ``"newton"``: the minimum of :math:`\hat J` by a projected Newton method
        with its exact gradient and Hessian, all problems at once (agrees with SLSQP; tested); ``"none"``: no
        steps F-G, the exponents stay at
        :math:`\varepsilon^{(0)}` (the fused density of steps D, E, H and I at fixed exponents).
    redraw, reference, swarm_options
        As in :func:`fuse_mixtures`, for every problem.
    timed : bool
        Also return the seconds per stage of the whole batch (field ``timings`` of every result).
    keep_samples : bool
        Return each problem's importance samples and fused weights (fields ``samples``, ``weights``,
        ``weights_eps0`` of :class:`MixtureFusion`).

    Returns
    -------
    list of MixtureFusion, one per problem
        Entry b: what :func:`fuse_mixtures` returns for problem b (its weights, means and covariances and ``rngs[b]``).

    Raises
    ------
    ValueError
        Shapes inconsistent, non-finite values, weights off the simplex, a covariance with positive
        weight not symmetric positive definite, ``rngs`` of the wrong length, ``eps0`` off the simplex; means so far
        apart for their covariances that the objective's log-densities leave the range (1e150 in magnitude),
        naming ``means`` (or ``covs``, the one at an extreme magnitude); with the swarm, ``swarm_options`` whose
        swarms (their iterations and particles, for the problems and mixtures given) are beyond the work budget,
        before any work, naming ``swarm_options.iterations and swarm_options.n_particles``; ``n_samples`` whose
        samples (their quadratic features, ``1.25 (K + d) + M**N + 32`` float64 a sample of a problem, K =
        ``1 + d + d (d + 1) / 2``) are beyond the memory budget, naming ``weights and n_samples``.

    References
    ----------
    * Julier, S. J. (2006). An empirical study into the use of Chernoff information for robust,
      distributed fusion of Gaussian mixture models. *Proceedings of the 9th International
      Conference on Information Fusion*.
    """
    flag(redraw, "redraw")
    flag(reference, "reference")
    optimiser = one_of(optimiser, ("pso", "slsqp", "newton", "none"), "optimiser")
    flag(keep_samples, "keep_samples")
    flag(timed, "timed")
    weights = read_once(weights, "weights")  # converted once: checked, and its dtype read (fuzz 33a C7)
    w = as_array(weights, "weights", ndim=3, subnormal=True)
    m = as_array(means, "means", ndim=4)
    c = as_array(covs, "covs", ndim=5, subnormal=True)
    _covariance_magnitude(c, "covs")  # the diagonals: no variance that underflows
    B, N, S = w.shape
    d = m.shape[-1]
    if m.shape != (B, N, S, d) or c.shape != (B, N, S, d, d):
        raise ValueError(f"weights must be (B, N, S), means (B, N, S, d) and covs (B, N, S, d, d); got {w.shape}, "
                         f"{m.shape}, {c.shape}")
    if np.any(w < 0) or not sums_to_one(w, weights, axis=2):   # within 1e-9, or float32 weights' precision
        raise ValueError("weights must be non-negative and sum to one over each mixture's components")
    w = renormalised(w, weights, axis=2)  # float32/float16 weights divided by their sums (the simplex rule)
    pos = w > 0
    cc = c[pos]
    if asymmetric(cc):  # the readers' rule, each matrix to its own scale (fuzz 46a C5: np.allclose's absolute 1e-8)
        raise ValueError("covs must be symmetric")
    try:
        np.linalg.cholesky(cc)
    except np.linalg.LinAlgError:
        raise ValueError("covs must be positive definite (where the weight is positive)") from None
    refuse_singular(np.where(pos[..., None, None], c, np.eye(d)), "covs")  # the covariance rule, where w > 0
    rngs = as_rngs(rngs, "rngs", B)  # its list, read once (fuzz 58b C1: a second read could differ)
    n_samples = count(n_samples, "n_samples", minimum=2)
    tuples, per = product_size(B, N, S, d, "weights and n_samples", n_samples)
    work((B, tuples), "weights and n_samples (the problems and the product mixture's component tuples)",
         weight=per)  # fuzz 35a C7
    sample_memory(B, tuples, d, n_samples, "weights and n_samples")  # fuzz 58b C2
    if eps0 is None:
        e0 = np.full((B, N), 1.0 / N)
    else:
        e = _numeric(eps0, "eps0")
        e = np.broadcast_to(e, (B, N)) if e.shape == (N,) else e
        if e.shape != (B, N):
            raise ValueError(f"eps0 must have shape ({B}, {N}) or ({N},), got {np.shape(eps0)}")
        e0 = np.stack([simplex_row(row, N, "eps0", eps0) for row in e])  # judged in eps0's precision
    with np.errstate(divide="ignore"):
        logw = np.where(pos, np.log(np.where(pos, w, 1.0)), -np.inf)
    c = np.where(pos[..., None, None], c, np.eye(d))
    return _timed_fusion(logw, m, c, rngs, n_samples, e0, optimiser, redraw, reference, swarm_options, bool(timed),
                         bool(keep_samples))


def _timed_fusion(logw: FloatArray, means: FloatArray, covs: FloatArray, rngs: list[np.random.Generator],
                  n_samples: int, eps0: FloatArray, optimiser: str, redraw: bool, reference: bool,
                  swarm_options: SwarmOptions | None, timed: bool, keep_samples: bool = False) -> list[MixtureFusion]:
    """:func:`_fuse_arrays`, its stage times as a :class:`FusionTimings` in every result when ``timed``."""
    seconds: dict[str, float] | None = {} if timed else None
    out = _fuse_arrays(logw, means, covs, rngs, n_samples, eps0, optimiser, redraw, reference, swarm_options, seconds,
                       keep_samples, in_range=True)
    if seconds is None:
        return out
    t = FusionTimings(**seconds)
    return [dataclasses.replace(r, timings=t) for r in out]


#: Problems per block when scoring swarms (keeps the (E, R) arrays in cache; results do not depend on it).
_SWARM_BLOCK = 4


def _proposal_densities(logw: FloatArray, means: FloatArray, covs: FloatArray, wg: FloatArray, mug: FloatArray,
                        Pg: FloatArray, xs: FloatArray) -> tuple[FloatArray, FloatArray]:
    """log g at the samples (B, R) and the nodes' log densities there, transposed (B, N, R)."""
    B, N, S, d = means.shape
    centre = _mixture_mean(wg, mug)  # the proposal's mean: the samples' centre
    phi = _features(xs - centre[:, None, :])
    with np.errstate(divide="ignore"):
        lgw = np.where(wg > 0, np.log(np.where(wg > 0, wg, 1.0)), -np.inf)
    lg = _mixture_logpdf_bounded(lgw, mug - centre[:, None, :], Pg, phi)  # its M^N components: shifted by a bound
    coef, dead = _gaussian_coefs(logw.reshape(B, N * S), means.reshape(B, N * S, d) - centre[:, None, :],
                                 covs.reshape(B, N * S, d, d))
    comp = _component_logpdf(coef, dead, phi).reshape(B, N, S, -1)
    return lg, _lse_rows(comp)


@own_underflow  # underflow to 0 by design (a kernel, a density or normalised weights: fuzz 33b D6)
def _fused_weights_T(LT: FloatArray, lg: FloatArray, eps: FloatArray) -> FloatArray:
    """Normalised fused weights (B, R) at exponents ``eps`` (B, N) (kernel of :func:`fused_weights`)."""
    lw = np.multiply(eps[:, 0:1], LT[:, 0], order="C")
    for i in range(1, LT.shape[1]):
        lw += eps[:, i:i + 1] * LT[:, i]
    lw -= lg
    return np.ascontiguousarray(np.exp(lw - _logsumexp(lw, axis=1)[:, None]))


def _is_derivatives(LT: FloatArray, lg: FloatArray) -> Callable[[np.ndarray, FloatArray],
                                                                tuple[FloatArray, FloatArray, FloatArray]]:
    r"""``fgh(idx, eps)``: :math:`\hat J`, its gradient :math:`\sum_r\tilde w_rL_r` and Hessian
    :math:`\sum_r\tilde w_rL_rL_r^\top - \nabla\hat J\nabla\hat J^\top` for problems ``idx`` (LT (B, N, R), lg (B, R))."""
    LTg = _augmented(LT, lg)
    bounds = _is_bounds(LTg)
    L = np.swapaxes(LT, 1, 2)  # (B, R, N)

    def fgh(idx: np.ndarray, eps: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        f = _is_values(LTg[idx], eps[:, None, :], bounds=bounds[idx])[:, 0]
        w = _fused_weights_T(LT[idx], lg[idx], eps)
        Li = L[idx]  # gathered once for its three uses (the same copy each use made)
        g = np.matmul(w[:, None, :], Li)[:, 0]
        H = np.matmul(np.swapaxes(Li * w[..., None], 1, 2), Li) - g[:, :, None] * g[:, None, :]
        return f, g, 0.5 * (H + np.swapaxes(H, 1, 2))
    return fgh


def _equal_kl(LT: FloatArray, lg: FloatArray, max_iter: int = 50) -> FloatArray:
    r"""Exponents (B, N) of the equal-KL rule on importance samples; NaN where it has no solution in the simplex.

    On the samples of step E, with fused weights :math:`\tilde w(\varepsilon)`, the estimated divergence is
    :math:`\widehat{\mathrm{KL}}(p_\varepsilon\|\hat p_i) = \sum_r\tilde w_r[\sum_j\varepsilon_jL_{rj} - \log g_r - L_{ri}] - \hat J(\varepsilon)
    + \sum_r\tilde w_r\log g_r`, so equal divergences for every node means equal
    :math:`\partial\hat J/\partial\varepsilon_i = \sum_r\tilde w_rL_{ri}`: a stationary point of :math:`\hat J` on the
    hyperplane :math:`\sum_i\varepsilon_i = 1`, found by Newton's method with the Hessian
    :math:`\sum_r\tilde w_rL_rL_r^\top - \nabla\hat J\nabla\hat J^\top` and backtracking (:math:`\hat J` is convex), without
    the sign constraints. Where the minimum of :math:`\hat J` on the simplex is interior this is that minimum
    (eq. ``eq-chf-equal-kl``); where it is on the boundary the stationary point leaves the simplex (or does
    not exist: no convergence in ``max_iter`` steps), and the rule gives no exponents (NaN).
    """
    B, N, R = LT.shape
    derivatives = _is_derivatives(LT, lg)
    e = np.full((B, N), 1.0 / N)
    active = np.ones(B, dtype=bool)
    ok = np.zeros(B, dtype=bool)
    f, g, H = derivatives(np.arange(B), e)
    for a in _active_problems(active, max_iter):
        step = _plane_newton_steps(H[a], g[a], np.ones((a.size, N), dtype=bool))  # no sign constraints
        done = -np.sum(g[a] * step, axis=1) <= 1e-14 * (1.0 + np.abs(f[a]))
        alpha = np.ones(a.size)
        for _ls in range(30):
            trial = e[a] + alpha[:, None] * step
            ft, gt, Ht = derivatives(a, trial)
            worse = ~(ft <= f[a] + 1e-13 * (1.0 + np.abs(f[a]))) & ~done
            if not worse.any():
                break
            alpha = np.where(worse, 0.5 * alpha, alpha)
        keep = ~done
        e[a[keep]], f[a[keep]], g[a[keep]], H[a[keep]] = trial[keep], ft[keep], gt[keep], Ht[keep]
        ok[a[done]] = True
        active[a[done]] = False
    inside = ok & np.all(e >= -1e-9, axis=1)
    return np.where(inside[:, None], np.clip(e, 0.0, None), np.nan)


def _fuse_arrays(logw: FloatArray, means: FloatArray, covs: FloatArray, rngs: list[np.random.Generator], n_samples: int,
                 eps0: FloatArray, optimiser: str, redraw: bool, reference: bool,
                 swarm_options: SwarmOptions | None, timings: dict[str, float] | None,
                 keep_samples: bool = False, equal_kl: bool = False, literal_xtol: float | None = None,
                 in_range: bool = False) -> list[MixtureFusion]:
    """Kernel of :func:`fuse_mixtures` and :func:`fuse_mixtures_batch` on validated arrays (see the latter).

    ``swarm_options`` is checked here (:func:`~fusion.optimise.swarm.check_swarm_options`), whichever caller;
    ``timings`` (stage -> seconds, keys the fields of :class:`FusionTimings`), if given, has each stage's seconds
    added to it.

    ``equal_kl``: also solve the equal-KL rule on the same samples (:func:`_equal_kl`; fields ``eps_equal_kl``,
    ``x_equal_kl``, NaN where the rule has no solution in the simplex). ``literal_xtol`` (with the swarm):
    follow each swarm to its iteration limit (``trace=True``, the result unchanged) and also return what
    the patent's stopping rule as worded (positions converged to ``literal_xtol``) gives on the same
    samples (fields ``eps_literal``, ``objective_literal``, ``n_evaluations_literal``, ``x_literal``,
    ``P_literal``; the trace in ``swarm.trace``). ``in_range`` (the public entries): refuse log-densities beyond
    the range (the filters' studies carry a diverged track's fusion on, unrefused).
    """
    swarm_options = check_swarm_options(swarm_options)
    B, N = eps0.shape
    if optimiser == "pso":   # before any work, naming the options (fuzz 35a C6: the inner names came after "gms")
        _swarm_work(B, swarm_options.n_particles, swarm_options.iterations, N,
                   "swarm_options.iterations and swarm_options.n_particles (with the mixtures and problems given)")
    clock = LapTimer(timings)
    wg, mug, Pg, log_z_first_order = _first_order_arrays(logw, means, covs, eps0)  # D
    clock.lap("first_order")
    chol = np.linalg.cholesky(Pg)
    xs = np.stack([_sample_mixture(wg[b], mug[b], chol[b], rngs[b], n_samples) for b in range(B)])  # E
    clock.lap("sampling")
    with np.errstate(over="ignore", invalid="ignore"):  # far components: refused just below, without numpy's warnings
        lg, LT = _proposal_densities(logw, means, covs, wg, mug, Pg, xs)  # F
    if in_range and not max(np.abs(lg).max(), np.abs(LT).max()) <= MAX_MAGNITUDE:  # the public entries (fuzz 31a C5)
        raise ValueError(f"the mixtures' log-densities at the samples leave the range (at most {MAX_MAGNITUDE:g} in "
                         "magnitude): their components lie too far apart for their covariances; rescale them")
    clock.lap("densities")
    swarms: list[OptimumResult | None] = [None] * B
    if optimiser == "pso":  # G
        LTg = _augmented(LT, lg)
        bounds = _is_bounds(LTg)
        work = np.empty((min(B, _SWARM_BLOCK), swarm_options.n_particles, n_samples))

        def fitness(active: np.ndarray, E: FloatArray) -> FloatArray:
            out = np.empty(E.shape[:2])
            for j in range(0, active.size, _SWARM_BLOCK):
                a = active[j:j + _SWARM_BLOCK]
                # a run of consecutive problems is a view of LTg (the same rows, without copying them)
                run = a[-1] - a[0] == a.size - 1 and np.all(np.diff(a) == 1)
                rows = LTg[a[0]:a[0] + a.size] if run else LTg[a]
                out[j:j + a.size] = -_is_values(rows, E[j:j + a.size], work[:a.size],
                                                bounds[a[0]:a[0] + a.size] if run else bounds[a])
            return out
        res = particle_swarm_batch(fitness, N, rngs, **swarm_options.keywords(), trace=literal_xtol is not None)
        swarms = list(res)
        eps = np.stack([r.x for r in res])
        obj = np.array([-r.fun for r in res])
        nev = [r.n_evaluations for r in res]
    elif optimiser == "newton":  # the exact minimum of the convex Ĵ, all problems at once
        eps = _simplex_newton(_is_derivatives(LT, lg), B, N)
        obj = _is_values(_augmented(LT, lg), eps[:, None, :])[:, 0]
        nev = [0] * B
    elif optimiser == "slsqp":
        opts = [simplex_minimum(LT[b].T, lg[b]) for b in range(B)]
        eps = np.stack([o.x for o in opts])
        obj = np.array([o.fun for o in opts])
        nev = [o.n_evaluations for o in opts]
    else:  # no steps F-G: the exponents of the proposal
        eps = eps0.copy()
        obj = _is_values(_augmented(LT, lg), eps[:, None, :])[:, 0]
        nev = [1] * B
    clock.lap("optimiser")
    w0 = _fused_weights_T(LT, lg, eps0)
    w = _fused_weights_T(LT, lg, eps)  # H
    x, P = _moments_batch(xs, w)  # I
    x0, P0 = _moments_batch(xs, w0)
    xf = _mixture_mean(wg, mug)
    dm = mug - xf[:, None, :]
    Pf = _dot(np.moveaxis(Pg, 1, 3), wg[:, None, None, :]) + np.matmul(np.swapaxes(dm, 1, 2), dm * wg[..., None])
    Pf = 0.5 * (Pf + np.swapaxes(Pf, 1, 2))
    ess, ess0 = 1.0 / np.sum(w**2, axis=1), 1.0 / np.sum(w0**2, axis=1)
    clock.lap("weights")
    extra: list[dict[str, object]] = [{} for _ in range(B)]
    if reference:
        refs = [simplex_minimum(LT[b].T, lg[b]) for b in range(B)]
        e_r = np.stack([r.x for r in refs])
        x_r, P_r = _moments_batch(xs, _fused_weights_T(LT, lg, e_r))
        for b, r in enumerate(refs):
            extra[b].update(eps_reference=r.x, objective_reference=r.fun, x_reference=x_r[b], P_reference=P_r[b],
                            n_evaluations_reference=r.n_evaluations)
        clock.lap("reference")
    if redraw:
        wh, muh, Ph, _ = _first_order_arrays(logw, means, covs, eps)
        cholh = np.linalg.cholesky(Ph)
        xh = np.stack([_sample_mixture(wh[b], muh[b], cholh[b], rngs[b], n_samples) for b in range(B)])
        lgh, LTh = _proposal_densities(logw, means, covs, wh, muh, Ph, xh)
        w_h = _fused_weights_T(LTh, lgh, eps)
        x_h, P_h = _moments_batch(xh, w_h)
        ess_h = 1.0 / np.sum(w_h**2, axis=1)
        for b in range(B):
            extra[b].update(x_redraw=x_h[b], P_redraw=P_h[b], ess_redraw=float(ess_h[b]))
        clock.lap("redraw")
    if literal_xtol is not None and optimiser == "pso":  # G6 as worded: the swarm's positions converge
        lit = []
        for sw in swarms:
            assert sw is not None and sw.trace is not None
            lit.append(sw.trace.at(sw.trace.stop_positions(literal_xtol)))
        e_l = np.stack([o.x for o in lit])
        x_l, P_l = _moments_batch(xs, _fused_weights_T(LT, lg, e_l))
        for b, o in enumerate(lit):
            extra[b].update(eps_literal=e_l[b], objective_literal=-o.fun, n_evaluations_literal=o.n_evaluations,
                            x_literal=x_l[b], P_literal=P_l[b])
        clock.lap("literal stop")
    if keep_samples:
        for b in range(B):
            extra[b].update(samples=xs[b], weights=w[b], weights_eps0=w0[b])
    if equal_kl:
        e_kl = _equal_kl(LT, lg)
        ok = np.all(np.isfinite(e_kl), axis=1)
        x_kl = np.full((B, xs.shape[2]), np.nan)
        if ok.any():
            x_kl[ok] = _moments_batch(xs[ok], _fused_weights_T(LT[ok], lg[ok], e_kl[ok]))[0]
        for b in range(B):
            extra[b].update(eps_equal_kl=e_kl[b], x_equal_kl=x_kl[b])
    return [MixtureFusion(x=x[b], P=P[b], eps=eps[b], objective=float(obj[b]), eps0=eps0[b], x_eps0=x0[b], P_eps0=P0[b],
                          x_first_order=xf[b], P_first_order=Pf[b], ess=float(ess[b]), ess_eps0=float(ess0[b]),
                          log_z_first_order=float(log_z_first_order[b]), n_fused_components=int(np.count_nonzero(wg[b])),
                          swarm=swarms[b], n_evaluations=int(nev[b]), **extra[b])  # type: ignore[arg-type]
            for b in range(B)]
