"""Reference paths of the kernels that issue 37 sped up: the code as it was, kept to check and time the new one.

Each function is the pre-issue-37 implementation of what the speed-up rewrote, written out in full; the blocks it
shares with the package and that the speed-up did not change (a common sub-step, the Newton step around a line
search) are the package's own helpers, called, so that only what differs is written twice.
``tests/test_kernel_parity.py`` checks that the package's kernels give the same numbers, bit for bit, and
``benchmarks/bench_kernels.py`` times both side by side. Not part of the package; do not import it from there.
"""

from __future__ import annotations

import itertools

import numpy as np

from fusion.estimates.chernoff.gaussian import _product_terms
from fusion.estimates.chernoff.mixture import _first_order_weights
from fusion.optimise.simplex import _simplex_newton
from fusion.readings import robust
from fusion.scenarios import range_bearing_batch as rbb
from fusion.estimates.mixtures import _component_logpdf, _dot, _logsumexp, _lse_rows, _matvec, _n_features


def features(x: np.ndarray) -> np.ndarray:
    """``fusion.estimates.mixtures._features`` (``np.triu_indices`` at every call)."""
    d = x.shape[-1]
    xT = np.swapaxes(x, -1, -2)
    out = np.empty(x.shape[:-2] + (_n_features(d), x.shape[-2]))
    out[..., 0, :] = 1.0
    out[..., 1:1 + d, :] = xT
    for k, (i, j) in enumerate(zip(*np.triu_indices(d))):
        np.multiply(out[..., 1 + i, :], out[..., 1 + j, :], out=out[..., 1 + d + k, :])
    return out


def gaussian_coefs(logw: np.ndarray, means: np.ndarray, covs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``fusion.estimates.mixtures._gaussian_coefs`` (precisions recomputed at every call)."""
    d = means.shape[-1]
    L = np.linalg.cholesky(covs)
    Linv = np.linalg.inv(L)
    A = np.matmul(np.swapaxes(Linv, -1, -2), Linv)
    A = 0.5 * (A + np.swapaxes(A, -1, -2))
    b = _matvec(A, means)
    logdet = 2.0 * np.sum(np.log(np.diagonal(L, axis1=-2, axis2=-1)), axis=-1)
    dead = ~np.isfinite(logw)
    const = np.where(dead, 0.0, logw) - 0.5 * (d * np.log(2 * np.pi) + logdet) - 0.5 * _dot(means, b)
    iu, ju = np.triu_indices(d)
    quad = A[..., iu, ju] * np.where(iu == ju, -0.5, -1.0)
    return np.concatenate([const[..., None], b, quad], axis=-1), dead


def mixture_logpdf_features(logw: np.ndarray, means: np.ndarray, covs: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """``fusion.estimates.mixtures._mixture_logpdf_features``."""
    coef, dead = gaussian_coefs(logw, means, covs)
    return _lse_rows(_component_logpdf(coef, dead, phi))


def first_order_arrays(logw, means, covs, eps, simplified=False):
    """``fusion.estimates.chernoff.mixture._first_order_arrays`` (every exponent-free term recomputed at every call:
    the tuples gathered and ``fusion.estimates.chernoff.gaussian._product_terms`` in one pass, not prepared once)."""
    B, N, S, d = means.shape
    idx = np.array(list(itertools.product(range(S), repeat=N)), dtype=int).reshape(-1, N)
    cols = np.arange(N)
    alive = np.isfinite(logw)
    wts = np.where(alive, np.exp(np.where(alive, logw, 0.0)), 0.0)
    ref = _dot(np.swapaxes(wts, 1, 2)[..., None, :], np.moveaxis(means, 1, 3)).sum(axis=1) / N
    infos = np.linalg.inv(covs)
    logdets = np.linalg.slogdet(2 * np.pi * covs)[1]
    logpi_t = np.where(alive, logw, 0.0)[:, cols, idx]
    dead_t = ~np.all(alive[:, cols, idx], axis=-1)
    mu, P, log_zm = _product_terms(means[:, cols, idx], infos[:, cols, idx], logdets[:, cols, idx], eps, ref)
    w, log_z = _first_order_weights(logpi_t, dead_t, log_zm, eps, simplified)   # the package's (not compared)
    return w, mu, P, log_z


def sigma_point_log_expectations(logw, means, covs, eps):
    """``fusion.scenarios.range_bearing_batch._sigma_point_log_expectations`` (everything at every call)."""
    B, N, S, d = means.shape
    wg, mug, Pg, _ = first_order_arrays(logw, means, covs, eps)
    L = np.linalg.cholesky(Pg) * np.sqrt(d)
    offsets = np.concatenate([np.swapaxes(L, -1, -2), -np.swapaxes(L, -1, -2)], axis=-2)
    pts = (mug[:, :, None, :] + offsets).reshape(B, -1, d)
    centre = np.sum(wg[..., None] * mug, axis=1)
    phi = features(pts - centre[:, None, :])
    out = np.empty((B, N))
    pw = np.repeat(wg, 2 * d, axis=1) / (2 * d)
    for i in range(N):
        lp = mixture_logpdf_features(logw[:, i], means[:, i] - centre[:, None, :], covs[:, i], phi)
        out[:, i] = np.sum(np.where(pw > 0, pw * lp, 0.0), axis=1)
    return out


def equal_kl_on_mixture(logw, means, covs, tol=1e-9, max_iter=50):
    """``fusion.scenarios.range_bearing_batch._equal_kl_on_mixture`` before issue 37: the package's Newton iteration
    with the residuals recomputed from scratch, one evaluation per Jacobian column, and every line-search round
    re-evaluating every problem of the iteration."""
    B, N = logw.shape[:2]
    if N == 1:
        return np.ones((B, 1))

    def resid(e, idx):
        h = sigma_point_log_expectations(logw[idx], means[idx], covs[idx], e)
        return h[:, :-1] - h[:, -1:]

    return rbb._equal_kl_newton(resid, B, N, tol, max_iter, jacobian_by_column, halving_one_at_a_time)


def jacobian_by_column(resid, e, r, a):
    """The forward-difference Jacobian, one evaluation of the residuals per column."""
    N, delta = e.shape[1], rbb._KL_DELTA
    J = np.empty((a.size, N - 1, N - 1))
    sgn = np.where(e[a, -1] >= delta, 1.0, -1.0)
    for j in range(N - 1):
        de = np.zeros(N)
        de[j], de[-1] = delta, -delta
        J[:, :, j] = (resid(e[a] + sgn[:, None] * de, a) - r[a]) / (sgn * delta)[:, None]
    return J


def halving_one_at_a_time(resid, e, a, full, n0):
    """Backtracking on the residual, halving the step of every problem of the iteration until none is worse."""
    alpha = np.ones(a.size)
    for _ls in range(30):
        trial = rbb._to_simplex(e[a] + alpha[:, None] * full)
        rt = resid(trial, a)
        worse = ~(np.max(np.abs(rt), axis=1) < n0)
        if not worse.any():
            break
        alpha = np.where(worse, 0.5 * alpha, alpha)
    return trial, rt, worse


def irls_every_row(update, s, mu0, par, tol, iterations):
    """``fusion.readings.robust._irls`` before issue 37: every row iterated to the end, in one block."""
    mu = mu0
    for _ in range(iterations):
        new = update(s, mu, par)
        done = np.all(np.abs(new - mu) <= tol)
        mu = new
        if done:
            break
    return mu


def huber(s: np.ndarray, c: float, iterations: int = 500, tol: float = 1e-10) -> np.ndarray:
    """``fusion.readings.robust._huber`` before issue 37: its start and update, every row iterated to the end."""
    return robust._huber(s, c, iterations, tol, irls=irls_every_row)


def biweight(s: np.ndarray, c: float, iterations: int = 500, tol: float = 1e-10) -> np.ndarray:
    """``fusion.readings.robust._biweight`` before issue 37: its start and update, every row iterated to the end."""
    return robust._biweight(s, c, iterations, tol, irls=irls_every_row)


def mixture_logpdf_einsum(gm, x: np.ndarray) -> np.ndarray:
    """``fusion.book.chapters.chernoff_steps._logpdf`` before issue 37's second pass (einsum, the public logsumexp)."""
    from fusion.estimates import mixtures as mx
    keep = gm.weights > 0
    covs, means = gm.covs[keep], gm.means[keep]
    inv = np.linalg.inv(covs)
    logdet = np.linalg.slogdet(2 * np.pi * covs)[1]
    dx = x[:, None, :] - means[None]
    q = np.einsum("nsi,sij,nsj->ns", dx, inv, dx)
    return mx.logsumexp((np.log(gm.weights[keep]) - 0.5 * (logdet + q)).T, axis=0)


def weighted_component_rows_einsum(g, x, S):
    """``fusion.book.chapters.chernoff_first_order._weighted_component_rows`` before issue 37's second pass (one
    single-component mixture and one einsum per component)."""
    from fusion.estimates import mixtures as mx
    comp = np.full((x.shape[0], S), -np.inf)
    for s in range(g.weights.size):
        if g.weights[s] > 0:
            comp[:, s] = np.log(g.weights[s]) + mixture_logpdf_einsum(
                mx.GaussianMixture(np.ones(1), g.means[s:s + 1], g.covs[s:s + 1]), x)
    return comp


def sigma_point_first_order(gms, eps):
    """``fusion.book.chapters.chernoff_first_order.sigma_point_first_order`` before issue 37's second pass: the
    package's sigma-point fusion with the components' log densities above."""
    from fusion.book.chapters import chernoff_first_order as csf
    return csf._sigma_point_fusion(gms, np.asarray(eps, dtype=float), weighted_component_rows_einsum)


def halving_all(fgh, a, eps_a, fa, step, alpha, done):
    """``fusion.optimise.simplex._halved_steps`` before issue 37's second pass: every problem of the batch
    evaluated at every halving of the line search, finished ones included."""
    for _ls in range(30):  # backtracking: log Z must not increase (it is convex: a short step always works)
        trial = np.clip(eps_a + alpha[:, None] * step, 0.0, None)
        trial /= trial.sum(axis=1, keepdims=True)
        ft, gt, Ht = fgh(a, trial)
        worse = (ft > fa + 1e-13 * (1.0 + np.abs(fa))) & ~done  # round-off is no increase
        if not worse.any():
            break
        alpha = np.where(worse, 0.5 * alpha, alpha)
    return trial, ft, gt, Ht


def simplex_newton(fgh, B: int, N: int, max_iter: int = 60, tol: float = 1e-10) -> np.ndarray:
    """``fusion.optimise.simplex._simplex_newton`` before issue 37's second pass: the package's projected Newton
    iteration with the line search above (the Newton step and the update are the package's)."""
    return _simplex_newton(fgh, B, N, max_iter, tol, search=halving_all)


def is_values(LTg: np.ndarray, E: np.ndarray, out: np.ndarray | None = None) -> np.ndarray:
    """``fusion.estimates.chernoff.mixture._is_values`` before it shifted by a bound (``LTg`` = [L'; -log g], N + 1 rows).

    Every row shifted by its own largest log weight: a pass for the maximum and one for the subtraction, besides the
    product, the exponential and the sum.
    """
    R = LTg.shape[-1]
    Ea = np.empty(E.shape[:-1] + (E.shape[-1] + 1,))
    Ea[..., :-1], Ea[..., -1] = E, 1.0
    out = np.matmul(Ea, LTg, out=out)
    m = np.maximum.reduce(out, axis=-1)
    if not np.isfinite(m).all():
        m = np.where(np.isfinite(m), m, 0.0)
    np.subtract(out, m[..., None], out=out)
    np.exp(out, out=out)
    with np.errstate(divide="ignore"):
        return np.log(np.add.reduce(out, axis=-1)) + m - np.log(R)


def chernoff_derivatives(m: np.ndarray, infos: np.ndarray, logdets: np.ndarray, eps: np.ndarray):
    """``fusion.estimates.chernoff.gaussian._chernoff_derivatives`` (the means' centre and the exponent-free terms
    recomputed at every call)."""
    B, N, d = m.shape
    x, P, lz = _product_terms(m[:, None], infos[:, None], logdets[:, None], eps)
    x, P, lz = x[:, 0], P[:, 0], lz[:, 0]
    dlt = x[:, None, :] - m
    a = _matvec(infos, dlt)
    C = np.matmul(infos, P[:, None])
    grad = -0.5 * (logdets + np.trace(C, axis1=-2, axis2=-1) + _dot(dlt, a))
    Cf = C.reshape(B, N, d * d)
    CT = np.swapaxes(C, -1, -2).reshape(B, N, d * d)
    hess = 0.5 * np.matmul(Cf, np.swapaxes(CT, 1, 2)) + np.matmul(np.matmul(a, P), np.swapaxes(a, 1, 2))
    return lz, grad, 0.5 * (hess + np.swapaxes(hess, 1, 2))


def first_order_log_normaliser_derivatives(logw, means, covs, eps):
    """``fusion.estimates.chernoff.mixture._first_order_log_normaliser_derivatives`` (the tuples, precisions and
    log-determinants recomputed at every call)."""
    B, N, S, d = means.shape
    idx = np.array(list(itertools.product(range(S), repeat=N)), dtype=int).reshape(-1, N)
    M, cols = idx.shape[0], np.arange(N)
    alive = np.isfinite(logw)
    dead_t = ~np.all(alive[:, cols, idx], axis=-1)
    logpi_t = np.where(alive, logw, 0.0)[:, cols, idx]
    infos, logdets = np.linalg.inv(covs), np.linalg.slogdet(2 * np.pi * covs)[1]
    mt = means[:, cols, idx].reshape(B * M, N, d)
    it = infos[:, cols, idx].reshape(B * M, N, d, d)
    lt = logdets[:, cols, idx].reshape(B * M, N)
    lz, g, H = chernoff_derivatives(mt, it, lt, np.repeat(eps, M, axis=0))
    la = np.where(dead_t, -np.inf, _dot(logpi_t, eps[:, None, :]) + lz.reshape(B, M))
    f = _logsumexp(la, axis=1)
    alpha = np.exp(la - f[:, None])
    v = np.where(dead_t[..., None], 0.0, logpi_t + g.reshape(B, M, N))
    grad = _dot(np.swapaxes(v, 1, 2), alpha[:, None, :])
    second = H.reshape(B, M, N, N) + v[..., :, None] * v[..., None, :]
    hess = _dot(np.moveaxis(second, 1, 3), alpha[:, None, None, :]) - grad[:, :, None] * grad[:, None, :]
    return f, grad, 0.5 * (hess + np.swapaxes(hess, 1, 2))


def first_order_minimum(logw, means, covs):
    """``fusion.estimates.chernoff.mixture._first_order_minimum`` (every evaluation from the mixtures)."""
    B, N = logw.shape[:2]
    return _simplex_newton(lambda i, e: first_order_log_normaliser_derivatives(logw[i], means[i], covs[i], e), B, N)


def gaussian_chernoff_batch(m, infos, logdets):
    """``fusion.estimates.chernoff.gaussian._gaussian_chernoff_batch`` (every evaluation from the Gaussians)."""
    return _simplex_newton(lambda idx, e: chernoff_derivatives(m[idx], infos[idx], logdets[idx], e), m.shape[0],
                           m.shape[1])
