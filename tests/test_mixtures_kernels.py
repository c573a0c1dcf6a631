"""The EM kernel and the log-sum-exp helpers of :mod:`fusion.estimates.mixtures` against their readable forms (issue 37).

The fast versions compute in reused work arrays (``out=`` ufuncs, no fresh temporaries); the readable ones
below are the code they replaced, written with fresh arrays. The study's results must not change by a bit,
so every comparison here is bitwise (``tobytes``), on batches that exercise the block boundaries, warm and
k-means++ starts, dead components, one component, early convergence and ``-inf`` entries.
"""
from __future__ import annotations

import copy

import numpy as np
import pytest

from fusion.estimates import mixtures as mx


# ---- the readable forms (the code before issue 37's speed pass) -------------------------------------------------

def _dot_readable(a, b):
    out = a[..., 0] * b[..., 0]
    for j in range(1, a.shape[-1]):
        out = out + a[..., j] * b[..., j]
    return out


def _logsumexp_readable(arr, axis):
    arr = np.ascontiguousarray(arr)
    m = np.max(arr, axis=axis, keepdims=True)
    m = np.where(np.isfinite(m), m, 0.0)
    with np.errstate(divide="ignore"):
        return np.squeeze(m, axis=axis) + np.log(np.sum(np.exp(arr - m), axis=axis))


def _lse_rows_readable(a):
    m = a[..., 0, :].copy()
    for j in range(1, a.shape[-2]):
        np.maximum(m, a[..., j, :], out=m)
    m = np.where(np.isfinite(m), m, 0.0)
    with np.errstate(divide="ignore"):
        s = np.exp(a[..., 0, :] - m)
        for j in range(1, a.shape[-2]):
            s += np.exp(a[..., j, :] - m)
        return np.log(s) + m


def _em_iterations_readable(xx, ww, S, rngs, max_iter, tol, floor, inits):
    """The EM loop of ``_em_arrays`` as it read before the work arrays (fresh temporaries at every step), from the
    kernel's own start (``max_iter=0``: the weighted k-means++ or warm start, which the speed pass did not change and
    ``test_em_start_and_one_component_step_are_the_closed_forms`` checks against numpy's weighted moments)."""
    pis, means, covs, _ = mx._em_arrays(xx, ww, S, rngs, 0, tol, floor, inits)
    B, Q, d = xx.shape
    ww = ww / ww.sum(axis=1, keepdims=True)
    mean_all = np.matmul(ww[:, None, :], xx)[:, 0]
    var = np.diagonal(mx._wscatter(xx, mean_all[:, None], ww[:, None])[:, 0], axis1=1, axis2=2)
    reg = floor * var[:, :, None] * np.eye(d) + 1e-12 * np.eye(d)
    phi_all = mx._features(xx - mean_all[:, None, :])
    history = [[] for _ in range(B)]
    act = np.arange(B)
    phi, W = phi_all, ww
    for _ in range(max_iter):
        for j0 in range(0, act.size, mx._EM_BLOCK):
            blk = slice(j0, j0 + mx._EM_BLOCK)
            a = act[blk]
            with np.errstate(divide="ignore"):
                logpi = np.log(pis[a])
            coef, dead = mx._gaussian_coefs(logpi, means[a] - mean_all[a][:, None], covs[a])
            gam = mx._component_logpdf(coef, dead, phi[blk])
            m = gam[:, 0].copy()
            for j in range(1, S):
                np.maximum(m, gam[:, j], out=m)
            gam -= m[:, None, :]
            np.exp(gam, out=gam)
            tot = gam[:, 0].copy()
            for j in range(1, S):
                tot += gam[:, j]
            ll = np.sum((np.log(tot) + m) * W[blk], axis=1)
            gam *= (W[blk] / tot)[:, None, :]
            stats = np.matmul(gam, np.swapaxes(phi[blk], -1, -2))
            nk = stats[..., 0]
            keep = nk > 1e-12
            p_new = np.where(keep, nk, 0.0)
            pis[a] = p_new / p_new.sum(axis=1, keepdims=True)
            with np.errstate(divide="ignore", invalid="ignore"):
                m_c = stats[..., 1:1 + d] / nk[..., None]
                c_new = (mx._unpack_sym(stats[..., 1 + d:], d) / nk[..., None, None]
                         - m_c[..., :, None] * m_c[..., None, :] + reg[a][:, None])
            c_new = 0.5 * (c_new + np.swapaxes(c_new, -1, -2))
            bi, si = np.nonzero(keep)
            means[a[bi], si] = m_c[bi, si] + mean_all[a[bi]]
            covs[a[bi], si] = c_new[bi, si]
            for j, b in enumerate(a):
                history[b].append(float(ll[j]))
        done = np.array([len(history[b]) > 1 and abs(history[b][-1] - history[b][-2]) <= tol * abs(history[b][-2])
                         for b in act], dtype=bool)
        if done.all():
            break
        if done.any():
            act = act[~done]
            phi, W = phi_all[act], ww[act]
    return pis, means, covs, history


# ---- helpers ----------------------------------------------------------------------------------------------------

def _same(a, b) -> bool:
    a, b = np.asarray(a), np.asarray(b)
    return a.shape == b.shape and a.dtype == b.dtype and a.tobytes() == b.tobytes()


def _problems(B: int, Q: int, d: int, S: int, seed: int, warm: str):
    """B weighted sample sets of clustered points, their generators, and warm starts (``warm``: none, all, some, dead)."""
    rng = np.random.default_rng(seed)
    centres = rng.normal(scale=4.0, size=(B, S, d))
    lab = rng.integers(S, size=(B, Q))
    xx = np.take_along_axis(centres, lab[..., None], axis=1) + rng.normal(size=(B, Q, d))
    ww = rng.uniform(0.0, 1.0, size=(B, Q)) ** 3
    rngs = [np.random.default_rng(seed * 1000 + b) for b in range(B)]
    inits = [None] * B
    if warm != "none":
        for b in range(B):
            if warm == "some" and b % 3:
                continue
            pw = np.full(S, 1.0 / S)
            if warm == "dead" and S > 1 and b % 2 == 0:  # a component already dead: weight 0 from the start
                pw[-1] = 0.0
                pw /= pw.sum()
            inits[b] = (pw, centres[b] + 0.3, np.broadcast_to(np.eye(d) * 1.5, (S, d, d)).copy())
    return xx, ww, rngs, inits


# ---- the tests --------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("B, S, warm, max_iter, tol", [
    (1, 1, "none", 6, 1e-8),
    (5, 2, "none", 8, 1e-8),
    (mx._EM_BLOCK + 7, 3, "some", 12, 1e-3),  # two blocks, problems stopping at different iterations
    (mx._EM_BLOCK + 1, 3, "dead", 10, 1e-6),
    (9, 4, "all", 15, 1e-5),
])
def test_em_kernel_equals_the_readable_loop_bitwise(B: int, S: int, warm: str, max_iter: int, tol: float) -> None:
    """``_em_arrays`` (work arrays reused across iterations) gives the readable loop's weights, means, covariances
    and log-likelihood traces to the last bit, and draws the same numbers from each generator."""
    xx, ww, rngs, inits = _problems(B, 300, 3, S, seed=B * 10 + S, warm=warm)
    r1, r2 = copy.deepcopy(rngs), copy.deepcopy(rngs)
    fast = mx._em_arrays(xx, ww, S, r1, max_iter, tol, 1e-6, inits)
    slow = _em_iterations_readable(xx, ww, S, r2, max_iter, tol, 1e-6, inits)
    for f, s in zip(fast[:3], slow[:3]):
        assert _same(f, s)
    assert fast[3] == slow[3]
    assert [g.bit_generator.state for g in r1] == [g.bit_generator.state for g in r2]


@pytest.mark.parametrize("S", [1, 3])
def test_em_start_and_one_component_step_are_the_closed_forms(S: int) -> None:
    """The start the readable loop takes from the kernel: S distinct sample points as means, the weighted covariance
    over S plus the floor as covariances, equal weights; and with one component one EM step lands on the weighted
    mean and covariance (numpy's ``average`` and ``cov`` with ``aweights``) plus the floor, whatever the start."""
    xx, ww, rngs, inits = _problems(6, 200, 3, S, seed=40 + S, warm="none")
    floor = 1e-3
    pis, means, covs, hist = mx._em_arrays(xx, ww, S, rngs, 0, 1e-8, floor, inits)
    assert hist == [[] for _ in range(6)]
    np.testing.assert_array_equal(pis, np.full((6, S), 1.0 / S))
    for b in range(6):
        cov = np.cov(xx[b].T, aweights=ww[b], bias=True)
        reg = floor * np.diag(np.diag(cov)) + 1e-12 * np.eye(3)
        assert all((xx[b] == m).all(axis=1).any() for m in means[b]) and len({m.tobytes() for m in means[b]}) == S
        np.testing.assert_allclose(covs[b], np.broadcast_to(cov / S + reg, (S, 3, 3)), rtol=1e-12)
        if S == 1:
            fit = mx.weighted_em(xx[b], ww[b], 1, np.random.default_rng(b), max_iter=1, floor=floor)
            np.testing.assert_allclose(fit.mixture.means[0], np.average(xx[b], axis=0, weights=ww[b]), rtol=1e-12)
            np.testing.assert_allclose(fit.mixture.covs[0], cov + reg, rtol=1e-10)


def test_em_kernel_case_with_early_stops_really_stops_early() -> None:
    """The two-block case above does exercise the working-set compaction (some problems stop before others)."""
    xx, ww, rngs, inits = _problems(mx._EM_BLOCK + 7, 300, 3, 3, seed=(mx._EM_BLOCK + 7) * 10 + 3, warm="some")
    hist = mx._em_arrays(xx, ww, 3, rngs, 12, 1e-3, 1e-6, inits)[3]
    assert len({len(h) for h in hist}) > 1


@pytest.mark.parametrize("shape, axis", [((7,), 0), ((4, 9), 1), ((4, 9), 0), ((3, 5, 6), 2), ((3, 5, 6), 1)])
def test_logsumexp_equals_the_readable_form_bitwise(shape: tuple[int, ...], axis: int) -> None:
    rng = np.random.default_rng(len(shape) * 7 + axis)
    a = rng.normal(scale=30.0, size=shape)
    a.flat[::4] = -np.inf  # some -inf entries, and a slice that is -inf throughout
    if a.ndim > 1:
        np.moveaxis(a, axis, -1)[0] = -np.inf
    assert _same(mx._logsumexp(a, axis), _logsumexp_readable(a, axis))
    t = np.swapaxes(a, 0, -1)  # not C-ordered
    assert _same(mx._logsumexp(t, 0), _logsumexp_readable(t, 0))


@pytest.mark.parametrize("shape", [(3, 50), (2, 4, 3, 70), (5, 1, 11)])
def test_lse_rows_equals_the_readable_form_bitwise(shape: tuple[int, ...]) -> None:
    rng = np.random.default_rng(sum(shape))
    a = rng.normal(scale=40.0, size=shape)
    a[..., 0, ::5] = -np.inf
    a[..., :, 1] = -np.inf  # a column dead in every row: -inf out
    out = mx._lse_rows(a)
    assert _same(out, _lse_rows_readable(a))
    assert np.all(out[..., 1] == -np.inf)


@pytest.mark.parametrize("shape_a, shape_b", [((6,), (6,)), ((4, 3), (4, 3)), ((2, 5, 4), (2, 1, 4)), ((3, 2), (2,))])
def test_dot_equals_the_readable_form_bitwise(shape_a: tuple[int, ...], shape_b: tuple[int, ...]) -> None:
    rng = np.random.default_rng(len(shape_a))
    a, b = rng.normal(size=shape_a), rng.normal(size=shape_b)
    assert _same(mx._dot(a, b), _dot_readable(a, b))


def _features_readable(x):
    d = x.shape[-1]
    xT = np.swapaxes(x, -1, -2)
    out = np.empty(x.shape[:-2] + (mx._n_features(d), x.shape[-2]))
    out[..., 0, :] = 1.0
    out[..., 1:1 + d, :] = xT
    for k, (i, j) in enumerate(zip(*np.triu_indices(d))):
        np.multiply(xT[..., i, :], xT[..., j, :], out=out[..., 1 + d + k, :])
    return out


@pytest.mark.parametrize("shape", [(40, 4), (3, 2, 25, 4), (7, 1), (5, 30, 3)])
def test_features_equal_the_readable_form_bitwise(shape: tuple[int, ...]) -> None:
    """The products taken from the contiguous coordinate rows equal those taken from the strided points."""
    x = np.random.default_rng(shape[-1]).normal(scale=1e3, size=shape)
    assert _same(mx._features(x), _features_readable(x))
