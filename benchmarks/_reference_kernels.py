"""Reference paths of the kernels that issue 37 sped up: the code as it was, kept to check and time the new one.

Each function is the pre-issue-37 implementation, written out in full (it does not call the rewritten kernels):
``tests/test_kernel_parity.py`` checks that the package's kernels give the same numbers, bit for bit, and
``benchmarks/bench_kernels.py`` times both side by side. Not part of the package; do not import it from there.
"""

from __future__ import annotations

import itertools

import numpy as np

from fusion.readings.robust import _MAD_TO_SIGMA
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


def product_terms(means, infos, logdets, eps, ref):
    """``fusion.estimates.chernoff.gaussian._product_terms`` with ``ref`` given (one pass, no precomputed terms)."""
    N = means.shape[-2]
    mc = means - ref[..., None, None, :]
    e = np.asarray(eps, dtype=float)
    t = _matvec(infos, mc)
    quad_in = _dot(mc, t)
    info = e[..., 0, None, None, None] * infos[..., :, 0, :, :]
    vec = e[..., 0, None, None] * t[..., :, 0, :]
    s1 = e[..., 0, None] * (logdets[..., :, 0] + quad_in[..., :, 0])
    for n in range(1, N):
        info = info + e[..., n, None, None, None] * infos[..., :, n, :, :]
        vec = vec + e[..., n, None, None] * t[..., :, n, :]
        s1 = s1 + e[..., n, None] * (logdets[..., :, n] + quad_in[..., :, n])
    P = np.linalg.inv(info)
    P = 0.5 * (P + np.swapaxes(P, -1, -2))
    mu = _matvec(P, vec)
    log_z = -0.5 * s1 + 0.5 * np.linalg.slogdet(2 * np.pi * P)[1] + 0.5 * _dot(mu, vec)
    return mu + ref[..., None, :], P, log_z


def first_order_arrays(logw, means, covs, eps, simplified=False):
    """``fusion.estimates.chernoff.mixture._first_order_arrays`` (every exponent-free term recomputed at every call)."""
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
    mu, P, log_zm = product_terms(means[:, cols, idx], infos[:, cols, idx], logdets[:, cols, idx], eps, ref)
    lp = _dot(logpi_t, eps[:, None, :])
    log_alpha = np.where(dead_t, -np.inf, lp + log_zm)
    log_z = _logsumexp(log_alpha, axis=1)
    lw = np.where(dead_t, -np.inf, lp) if simplified else log_alpha
    w = np.exp(lw - _logsumexp(lw, axis=1)[:, None])
    w = np.ascontiguousarray(np.where(w > 1e-12, w, 0.0))
    return w / w.sum(axis=1, keepdims=True), mu, P, log_z


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
    """``fusion.scenarios.range_bearing_batch._equal_kl_on_mixture``: one evaluation per Jacobian column, every
    line-search round re-evaluating every problem of the iteration."""
    B, N = logw.shape[:2]
    if N == 1:
        return np.ones((B, 1))

    def resid(e, idx):
        h = sigma_point_log_expectations(logw[idx], means[idx], covs[idx], e)
        return h[:, :-1] - h[:, -1:]

    def to_simplex(e):
        e = np.clip(e, 0.0, None)
        return e / np.sum(e, axis=1, keepdims=True)

    e = np.full((B, N), 1.0 / N)
    r = resid(e, np.arange(B))
    live = np.ones(B, dtype=bool)
    delta = 1e-6
    for _ in range(max_iter):
        a = np.flatnonzero(live & (np.max(np.abs(r), axis=1) > tol))
        if a.size == 0:
            break
        J = np.empty((a.size, N - 1, N - 1))
        sgn = np.where(e[a, -1] >= delta, 1.0, -1.0)
        for j in range(N - 1):
            de = np.zeros(N)
            de[j], de[-1] = delta, -delta
            J[:, :, j] = (resid(e[a] + sgn[:, None] * de, a) - r[a]) / (sgn * delta)[:, None]
        J += 1e-12 * (1.0 + np.max(np.abs(J), axis=(1, 2)))[:, None, None] * np.eye(N - 1)
        step = np.linalg.solve(J, -r[a][..., None])[..., 0]
        full = np.concatenate([step, -np.sum(step, axis=1, keepdims=True)], axis=1)
        alpha = np.ones(a.size)
        n0 = np.max(np.abs(r[a]), axis=1)
        for _ls in range(30):
            trial = to_simplex(e[a] + alpha[:, None] * full)
            rt = resid(trial, a)
            worse = ~(np.max(np.abs(rt), axis=1) < n0)
            if not worse.any():
                break
            alpha = np.where(worse, 0.5 * alpha, alpha)
        e[a[~worse]], r[a[~worse]] = trial[~worse], rt[~worse]
        live[a[worse]] = False
    ok = np.max(np.abs(r), axis=1) <= tol
    return np.where(ok[:, None], e, np.nan)


def huber(s: np.ndarray, c: float, iterations: int = 500, tol: float = 1e-10) -> np.ndarray:
    """``fusion.readings.robust._huber`` (every row iterated to the end). Huber M-estimate of location per row, scale fixed at the normalised MAD (IRLS from the median).

    Iterates until no estimate moves by more than ``tol`` times its scale (or ``iterations``).
    """
    mu = np.median(s, axis=1)
    scale = _MAD_TO_SIGMA * np.median(np.abs(s - mu[:, None]), axis=1)
    tiny = scale <= 0.0  # half or more of the readings equal: the median is the estimate
    scale = np.where(tiny, 1.0, scale)
    r = np.empty_like(s)
    w = np.empty_like(s)
    col = scale[:, None]
    for _ in range(iterations):  # the same arithmetic as w = where(r <= c, 1, c / max(r, c)), in place
        np.subtract(s, mu[:, None], out=r)
        np.abs(r, out=r)
        np.divide(r, col, out=r)
        np.maximum(r, c, out=w)
        np.divide(c, w, out=w)
        w[r <= c] = 1.0
        wsum = w.sum(axis=1)
        np.multiply(w, s, out=w)
        new = w.sum(axis=1) / wsum
        done = np.all(np.abs(new - mu) <= tol * scale)
        mu = new
        if done:
            break
    return np.where(tiny, np.median(s, axis=1), mu)


def biweight(s: np.ndarray, c: float, iterations: int = 500, tol: float = 1e-10) -> np.ndarray:
    """``fusion.readings.robust._biweight`` (every row iterated to the end). Tukey's biweight M-estimate of location per row, scale fixed at the normalised MAD (IRLS from the median)."""
    med = np.median(s, axis=1)
    scale = _MAD_TO_SIGMA * np.median(np.abs(s - med[:, None]), axis=1)
    tiny = scale <= 0.0
    scale = np.where(tiny, 1.0, scale)
    mu = med
    cs = c * scale[:, None]
    w = np.empty_like(s)
    for _ in range(iterations):  # the same arithmetic as w = where(|u| < 1, (1 - u**2)**2, 0), in place
        np.subtract(s, mu[:, None], out=w)
        np.divide(w, cs, out=w)
        outside = np.abs(w) >= 1.0
        np.square(w, out=w)
        np.subtract(1.0, w, out=w)
        np.square(w, out=w)
        w[outside] = 0.0
        wsum = w.sum(axis=1)
        np.multiply(w, s, out=w)
        new = np.where(wsum > 0, w.sum(axis=1) / np.where(wsum > 0, wsum, 1.0), mu)
        done = np.all(np.abs(new - mu) <= tol * scale)
        mu = new
        if done:
            break
    return np.where(tiny, med, mu)


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


def sigma_point_first_order(gms, eps):
    """``fusion.book.chapters.chernoff_first_order.sigma_point_first_order`` before issue 37's second pass (one
    single-component mixture and one einsum per component)."""
    from fusion.estimates import chernoff as ch
    from fusion.estimates import mixtures as mx
    from fusion.estimates.chernoff import mixture as chm
    e = np.asarray(eps, dtype=float)
    logw, means, covs = chm._mixture_arrays(list(gms))
    N, S, d = means.shape
    wg, mug, Pg, log_z = chm._first_order_arrays(logw[None], means[None], covs[None], e[None])
    wg, mug, Pg = wg[0], mug[0], Pg[0]
    L = np.linalg.cholesky(Pg) * np.sqrt(d)
    pts = mug[:, None, :] + np.concatenate([np.swapaxes(L, -1, -2), -np.swapaxes(L, -1, -2)], axis=1)
    flat = pts.reshape(-1, d)
    idx = np.array(np.meshgrid(*[np.arange(S)] * N, indexing="ij")).reshape(N, -1).T
    logR = np.zeros(flat.shape[0])
    M = idx.shape[0]
    owner = np.repeat(np.arange(M), 2 * d)
    for i, g in enumerate(gms):
        comp = np.full((flat.shape[0], S), -np.inf)
        for s in range(g.weights.size):
            if g.weights[s] > 0:
                comp[:, s] = np.log(g.weights[s]) + mixture_logpdf_einsum(
                    mx.GaussianMixture(np.ones(1), g.means[s:s + 1], g.covs[s:s + 1]), flat)
        lse = mx.logsumexp(comp.T, axis=0)
        with np.errstate(invalid="ignore"):
            lg = comp[np.arange(flat.shape[0]), idx[owner, i]] - lse
        logR += (1.0 - e[i]) * np.where(np.isfinite(lg), lg, -np.inf)
    rbar = np.exp(logR).reshape(M, 2 * d).mean(axis=1)
    with np.errstate(divide="ignore"):
        lw = np.where((wg > 0) & (rbar > 0), np.log(np.where(wg > 0, wg, 1.0)) + np.log(np.where(rbar > 0, rbar, 1.0)),
                      -np.inf)
    top = mx.logsumexp(lw)
    w = np.exp(lw - top)
    keep = w > 1e-12
    return ch.FirstOrderMixture(mixture=mx.GaussianMixture(w[keep] / w[keep].sum(), mug[keep], Pg[keep]),
                                log_z_first_order=float(log_z[0] + top))


def simplex_newton(fgh, B: int, N: int, max_iter: int = 60, tol: float = 1e-10) -> np.ndarray:
    """``fusion.optimise.simplex._simplex_newton`` before issue 37's second pass (every problem of the batch
    evaluated at every halving of the line search, finished ones included)."""
    eps = np.full((B, N), 1.0 / N)
    if N == 1:
        return eps
    free = np.ones((B, N), dtype=bool)
    active = np.ones(B, dtype=bool)
    f, g, H = fgh(np.arange(B), eps)
    for _ in range(max_iter):
        a = np.flatnonzero(active)
        if a.size == 0:
            break
        fa, ga, Ha, fr = f[a], g[a], H[a], free[a]
        lam = np.sum(np.where(fr, ga, 0.0), axis=1) / np.maximum(fr.sum(axis=1), 1)
        fr = fr | (eps[a] <= 0.0) & (ga < lam[:, None] - 1e-12)  # free a bound coordinate that would lower log Z
        for _fix in range(N):  # a coordinate at zero whose Newton step is negative stays bound
            K = np.zeros((a.size, N + 1, N + 1))
            ridge = 1e-12 * (1.0 + np.max(np.abs(Ha), axis=(1, 2)))  # flat directions (identical inputs)
            K[:, :N, :N] = (np.where(fr[:, :, None] & fr[:, None, :], Ha, 0.0)
                            + np.where(fr, ridge[:, None], 1.0)[:, :, None] * np.eye(N))
            K[:, :N, N] = K[:, N, :N] = fr
            rhs = np.concatenate([np.where(fr, -ga, 0.0), np.zeros((a.size, 1))], axis=1)
            step = np.where(fr, np.linalg.solve(K, rhs[..., None])[..., 0][:, :N], 0.0)
            stuck = fr & (eps[a] <= 0.0) & (step < 0.0)
            if not stuck.any():
                break
            fr = fr & ~stuck
        with np.errstate(divide="ignore", invalid="ignore"):
            room = np.where(step < 0, -eps[a] / step, np.inf)
        alpha = np.minimum(1.0, np.min(room, axis=1))
        decrement = -np.sum(ga * step, axis=1)  # Newton decrement: what the step can still gain
        done = (np.max(np.abs(step), axis=1) <= tol) | (decrement <= 1e-15 * (1.0 + np.abs(fa)))
        for _ls in range(30):  # backtracking: log Z must not increase (it is convex: a short step always works)
            trial = np.clip(eps[a] + alpha[:, None] * step, 0.0, None)
            trial /= trial.sum(axis=1, keepdims=True)
            ft, gt, Ht = fgh(a, trial)
            worse = (ft > fa + 1e-13 * (1.0 + np.abs(fa))) & ~done  # round-off is no increase
            if not worse.any():
                break
            alpha = np.where(worse, 0.5 * alpha, alpha)
        keep = ~done
        hit = trial <= 1e-14
        eps[a[keep]] = np.where(hit[keep], 0.0, trial[keep])
        eps[a[keep]] /= eps[a[keep]].sum(axis=1, keepdims=True)
        free[a] = fr & ~(hit & keep[:, None])
        f[a[keep]], g[a[keep]], H[a[keep]] = ft[keep], gt[keep], Ht[keep]
        active[a[done]] = False
    return eps


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
