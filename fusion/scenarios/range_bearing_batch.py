"""The batch engine of :func:`fusion.scenarios.range_bearing.run_tracking_batch`: a block of runs, frame by frame.

:class:`_Batch` holds a block's random streams, particles and records as arrays over runs; its
:meth:`_Batch.frame` runs one frame as step functions (the local filters, their mixtures, the Gaussian
baselines, the fusion, the centralised filter, the local resampling), each vectorised across runs and nodes.
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable, Mapping

import numpy as np

from fusion._guards import own_underflow
from fusion._covariances import singular_mask
from fusion._results import trusted
from fusion._timing import LapTimer
from fusion._validation import FloatArray
# the batched kernels of the package (private: array-level, validated by the callers)
from fusion.estimates.chernoff.gaussian import _ci_criterion_batch, _gaussian_chernoff_batch, _product_terms
from fusion.estimates.chernoff.mixture import (FusionTimings, _first_order_from_prepared, _first_order_minimum, _first_order_prepare,
                                              _fuse_arrays, _moments_batch)
from fusion.estimates.mixtures import (_component_logpdf, _em_arrays, _features, _gaussian_coefs_from, _gaussian_precisions,
                                      _lse_rows, _mixture_logpdf_features)
from fusion.optimise.swarm import SwarmOptions
from fusion.filtering.particles import _log_likelihood, _systematic_resample, ncv_model
from fusion.scenarios.range_bearing_scenario import (GUARD_STAGES, RangeBearingScenario, TrackingRun, TrackingTimings,
                                                     method_keys, simulate_target)

__all__: list[str] = []  # public home: fusion.scenarios.range_bearing

_FUSION_STAGES = frozenset(f.name for f in dataclasses.fields(FusionTimings))


def _tracking_timings(seconds: Mapping[str, float], runs: int) -> TrackingTimings:
    """A block's stage seconds (lap keys: the fields of :class:`TrackingTimings` and of :class:`FusionTimings`, and the
    fusion kernel's ``"literal stop"``), shared equally by its ``runs`` runs."""
    per = {k.replace(" ", "_"): v / runs for k, v in seconds.items()}
    fusion = FusionTimings(**{k: v for k, v in per.items() if k in _FUSION_STAGES})
    return TrackingTimings(fusion=fusion, **{k: v for k, v in per.items() if k not in _FUSION_STAGES})


def _sigma_point_log_expectations(logw: FloatArray, means: FloatArray, covs: FloatArray, eps: FloatArray) -> FloatArray:
    r"""Expected log density of every node under the first-order mixture :math:`g_\varepsilon` of step D, by sigma points.

    :math:`h_i(\varepsilon) = \mathbb E_{g_\varepsilon}[\log\hat p_i(x)]`, each Gaussian component of
    :math:`g_\varepsilon` (:func:`fusion.estimates.chernoff.first_order_fusion`) replaced by its :math:`2d` symmetric
    sigma points :math:`\mu\pm\sqrt d\,L e_j` of equal weight (exact for a quadratic integrand: a Gaussian
    :math:`\hat p_i` gives the closed form). Deterministic: no random draws.

    Parameters
    ----------
    logw : ndarray, shape (B, N, S)
        Log weights of the nodes' mixtures (``-inf``: no component).
    means : ndarray, shape (B, N, S, d)
    covs : ndarray, shape (B, N, S, d, d)
    eps : ndarray, shape (B, N)
        Exponents on the simplex.

    Returns
    -------
    ndarray, shape (B, N)
        :math:`h_i(\varepsilon)`, nats.
    """
    return _sigma_points_prepared(logw, means, _sigma_point_prepare(logw, means, covs), eps)


def _sigma_point_prepare(logw: FloatArray, means: FloatArray, covs: FloatArray) -> tuple[FloatArray, ...]:
    """The exponent-free arrays of :func:`_sigma_point_log_expectations` (first-order fusion's tuples, every node's
    precisions), problems on the first axis: a subset of problems is ``tuple(a[idx] for a in prep)``."""
    N = means.shape[1]
    nodes = [a for i in range(N) for a in _gaussian_precisions(covs[:, i])]  # (A, logdet, quad) of each node
    return _first_order_prepare(logw, means, covs) + tuple(nodes)


def _sigma_points_prepared(logw: FloatArray, means: FloatArray, prep: tuple[FloatArray, ...], eps: FloatArray
                           ) -> FloatArray:
    """:func:`_sigma_point_log_expectations` from :func:`_sigma_point_prepare`'s arrays (the same numbers)."""
    B, N, S, d = means.shape
    wg, mug, Pg, _ = _first_order_from_prepared(prep[:-3 * N], eps)  # (B, M), (B, M, d), (B, M, d, d)
    L = np.linalg.cholesky(Pg) * np.sqrt(d)
    offsets = np.concatenate([np.swapaxes(L, -1, -2), -np.swapaxes(L, -1, -2)], axis=-2)  # (B, M, 2d, d)
    pts = (mug[:, :, None, :] + offsets).reshape(B, -1, d)  # (B, M 2d, d)
    centre = np.sum(wg[..., None] * mug, axis=1)
    phi = _features(pts - centre[:, None, :])  # (B, K, Q)
    out = np.empty((B, N))
    pw = np.repeat(wg, 2 * d, axis=1) / (2 * d)  # (B, Q)
    nodes = prep[-3 * N:]
    for i in range(N):
        coef, dead = _gaussian_coefs_from(logw[:, i], means[:, i] - centre[:, None, :], *nodes[3 * i:3 * i + 3])
        lp = _lse_rows(_component_logpdf(coef, dead, phi))
        out[:, i] = np.sum(np.where(pw > 0, pw * lp, 0.0), axis=1)
    return out


#: The steps of :func:`_equal_kl_on_mixture`'s line search, 1, 1/2, ..., 2^-29 (exact powers of two), tried in
#: chunks of growing size (one evaluation per chunk: most steps are taken at once, a few need up to 30 halvings).
_STEPS = np.ldexp(1.0, -np.arange(30))
_STEP_CHUNKS = ((0, 1), (1, 2), (2, 5), (5, 13), (13, 30))


def _equal_kl_on_mixture(logw: FloatArray, means: FloatArray, covs: FloatArray, tol: float = 1e-9,
                        max_iter: int = 50, accept: float = 1e-6) -> FloatArray:
    r"""The equal-KL rule applied to the first-order mixture :math:`g_\varepsilon` (as public codes do).

    Exponents :math:`\varepsilon` on the simplex with :math:`\mathrm{KL}(g_\varepsilon\|\hat p_i)` equal for every
    node, i.e. equal :math:`h_i(\varepsilon)` (:func:`_sigma_point_log_expectations`; the entropy term is common):
    the :math:`N-1` equations :math:`h_i - h_N = 0` in the free coordinates
    :math:`\varepsilon_1, \dots, \varepsilon_{N-1}`, solved by Newton's method with a forward-difference Jacobian
    and backtracking on the residual, iterates kept on the simplex (clipped and renormalised). No random draws.

    Parameters
    ----------
    logw, means, covs : ndarray
        The nodes' mixtures, shapes (B, N, S), (B, N, S, d), (B, N, S, d, d).
    tol : float
        Largest absolute residual (nats) at which Newton's method stops.
    max_iter : int
        Newton iterations.
    accept : float
        Largest absolute residual (nats) counted as a solution. Newton stops at ``tol`` or where its line search
        finds no descent, which round-off can cause just above ``tol``: in chapter 06's study one frame ended at
        1.2e-9 under OpenBLAS's Haswell kernel and below 1e-9 under its SkylakeX kernel, while every problem without
        a solution in the simplex ends above 1e-4. Counted against ``tol``, that frame's existence depended on the
        machine; against ``accept``, far inside the gap, it does not.

    Returns
    -------
    ndarray, shape (B, N)
        The exponents; NaN where no solution in the simplex was found (the residual stays above ``accept``).
    """
    B, N = logw.shape[:2]
    if N == 1:
        return np.ones((B, 1))
    return _equal_kl_newton(_prepared_residuals(logw, means, covs), B, N, tol, max_iter, _jacobian_at_once,
                            _search_in_chunks, accept)


#: Residuals of the equal-KL equations: ``resid(e, idx)`` -> (len(idx), N - 1), the values of problems ``idx`` at
#: exponents ``e`` (one row of ``e`` per entry of ``idx``).
Residuals = Callable[[FloatArray, np.ndarray], FloatArray]


def _prepared_residuals(logw: FloatArray, means: FloatArray, covs: FloatArray) -> Residuals:
    """:math:`h_i - h_N` of :func:`_sigma_point_log_expectations`, its exponent-free arrays computed once."""
    prep = _sigma_point_prepare(logw, means, covs)

    def resid(e: FloatArray, idx: np.ndarray) -> FloatArray:
        h = _sigma_points_prepared(logw[idx], means[idx], tuple(p[idx] for p in prep), e)
        return h[:, :-1] - h[:, -1:]
    return resid


def _to_simplex(e: FloatArray) -> FloatArray:
    """Rows clipped at zero and renormalised to sum to one."""
    e = np.clip(e, 0.0, None)
    return e / np.sum(e, axis=1, keepdims=True)


def _jacobian_at_once(resid: Residuals, e: FloatArray, r: FloatArray, a: np.ndarray) -> FloatArray:
    """Forward-difference Jacobian of the residuals of problems ``a`` (the N - 1 differences in one evaluation)."""
    N = e.shape[1]
    J = np.empty((a.size, N - 1, N - 1))
    sgn = np.where(e[a, -1] >= _KL_DELTA, 1.0, -1.0)  # the difference stays on the simplex
    des = np.zeros((N - 1, N))
    des[:, -1] = -_KL_DELTA
    des[np.arange(N - 1), np.arange(N - 1)] = _KL_DELTA
    # a problem's values do not depend on the others in the batch
    rj = resid((e[a][None] + sgn[None, :, None] * des[:, None, :]).reshape(-1, N), np.tile(a, N - 1))
    for j in range(N - 1):
        J[:, :, j] = (rj[j * a.size:(j + 1) * a.size] - r[a]) / (sgn * _KL_DELTA)[:, None]
    return J


def _search_in_chunks(resid: Residuals, e: FloatArray, a: np.ndarray, full: FloatArray, n0: FloatArray,
                      ) -> tuple[FloatArray, FloatArray, np.ndarray]:
    """Backtracking on the residual: the first step of 1, 1/2, ..., 2^-29 that lowers the largest residual below
    ``n0``, several steps of every pending problem per evaluation. Returns (trial, its residuals, worse)."""
    N = e.shape[1]
    trial, rt, worse = np.empty((a.size, N)), np.empty((a.size, N - 1)), np.ones(a.size, dtype=bool)
    pend = np.arange(a.size)  # the problems whose step is still being halved (the others keep their trial)
    for lo, hi in _STEP_CHUNKS:
        # the steps _STEPS[lo:hi] of every pending problem in one evaluation: the first that is not worse is where
        # halving one at a time stops
        k, P = hi - lo, pend.size
        tr = _to_simplex((e[a[pend]][:, None, :] + _STEPS[None, lo:hi, None] * full[pend][:, None, :]).reshape(-1, N))
        rh = resid(tr, np.repeat(a[pend], k)).reshape(P, k, N - 1)
        ok = np.max(np.abs(rh), axis=2) < n0[pend, None]
        found = ok.any(axis=1)
        first = np.argmax(ok, axis=1)[found]
        sel = pend[found]
        trial[sel], rt[sel], worse[sel] = tr.reshape(P, k, N)[found, first], rh[found, first], False
        pend = pend[~found]
        if pend.size == 0:
            break
    return trial, rt, worse


#: The forward-difference step of :func:`_equal_kl_on_mixture`'s Jacobian.
_KL_DELTA = 1e-6


def _equal_kl_newton(resid: Residuals, B: int, N: int, tol: float, max_iter: int,
                     jacobian: Callable[[Residuals, FloatArray, FloatArray, np.ndarray], FloatArray],
                     search: Callable[..., tuple[FloatArray, FloatArray, np.ndarray]],
                     accept: float | None = None) -> FloatArray:
    """Newton's method on the N - 1 equal-KL residuals of B problems from the simplex's centre (the iteration of
    :func:`_equal_kl_on_mixture`, with its Jacobian and line search passed in: the parity references pass theirs);
    a solution is a residual at most ``accept`` (default ``tol``)."""
    e = np.full((B, N), 1.0 / N)
    r = resid(e, np.arange(B))
    live = np.ones(B, dtype=bool)
    for _ in range(max_iter):
        a = np.flatnonzero(live & (np.max(np.abs(r), axis=1) > tol))
        if a.size == 0:
            break
        J = jacobian(resid, e, r, a)
        J += 1e-12 * (1.0 + np.max(np.abs(J), axis=(1, 2)))[:, None, None] * np.eye(N - 1)
        step = np.linalg.solve(J, -r[a][..., None])[..., 0]
        full = np.concatenate([step, -np.sum(step, axis=1, keepdims=True)], axis=1)
        trial, rt, worse = search(resid, e, a, full, np.max(np.abs(r[a]), axis=1))
        e[a[~worse]], r[a[~worse]] = trial[~worse], rt[~worse]
        live[a[worse]] = False  # no descent: a boundary point, no solution in the simplex
    ok = np.max(np.abs(r), axis=1) <= (tol if accept is None else accept)
    return np.where(ok[:, None], e, np.nan)


#: The streams of one run, spawned from its seed in this order: the target, the nodes, the fusion, the centralised
#: filter, the extra node fusions and the readings.
_RUN_STREAMS = 6


def _run_streams(seed: np.random.SeedSequence) -> list[np.random.SeedSequence]:
    """A run's :data:`_RUN_STREAMS` streams, spawned from its seed (which advances the seed's spawn counter).

    :func:`run_tracking_batch` spawns them in the caller's process before any block is dispatched, so the caller's
    ``SeedSequence`` advances the same whatever ``workers`` (fuzz 53b C2: spawned in a worker process, the spawn
    advanced a pickled copy and a second call repeated the first)."""
    return seed.spawn(_RUN_STREAMS)


def _run_block(args: tuple[RangeBearingScenario, list[list[np.random.SeedSequence]], list[bool], SwarmOptions]
               ) -> list[TrackingRun]:
    """One block of runs (a process-pool task of :func:`run_tracking_batch`): each run's streams
    (:func:`_run_streams`), its flag and the swarm options."""
    return _Batch(*args).run()


def _normals(rngs: list[np.random.Generator], shape: tuple[int, ...]) -> FloatArray:
    """One draw of standard normals of ``shape`` from each generator, stacked: (len(rngs), *shape).

    The numbers of ``np.stack([r.standard_normal(shape) for r in rngs])`` (each generator fills its own
    slot in place, in the same order), without the per-generator arrays and the copy into the stack.
    """
    out = np.empty((len(rngs),) + shape)
    for r, slot in zip(rngs, out):
        r.standard_normal(out=slot)
    return out


def _regularise_batch(x: FloatArray, cov: FloatArray, rngs: list[np.random.Generator]) -> FloatArray:
    """:func:`fusion.filtering.particles.regularise` of P sets (P, Q, d) with covariances (P, d, d), one generator each."""
    n, d = x.shape[-2:]
    h = (4.0 / (n * (d + 2))) ** (1.0 / (d + 4))
    P = 0.5 * (cov + np.swapaxes(cov, -1, -2))
    floor = 1e-9 * np.maximum(np.trace(P, axis1=-2, axis2=-1) / d, 1e-12)
    L = np.linalg.cholesky(P + floor[:, None, None] * np.eye(d))
    z = _normals(rngs, (n, d))
    z *= h  # h * each draw, as before, in place
    return x + np.matmul(z, np.swapaxes(L, -1, -2))


def _moments(x: FloatArray, w: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Weighted mean (..., d) and covariance (..., d, d) of particles (..., Q, d) with normalised weights (..., Q)."""
    lead = x.shape[:-2]
    m, c = _moments_batch(x.reshape((-1,) + x.shape[-2:]), w.reshape((-1, w.shape[-1])))
    return m.reshape(lead + m.shape[-1:]), c.reshape(lead + c.shape[-2:])


class _Batch:
    """A block of runs of :func:`run_tracking_batch`: their streams, particles and records, as arrays over runs."""

    def __init__(self, sc: RangeBearingScenario, streams: list[list[np.random.SeedSequence]], flags: list[bool],
                 swarm_options: SwarmOptions) -> None:
        self.timings: dict[str, float] = {}
        clock = LapTimer(self.timings)
        N, B, K = len(sc.sensors), len(streams), sc.frames
        self.sc, self.so, self.N, self.B = sc, swarm_options, N, B
        model = ncv_model(sc.T, sc.q)
        self.F, self.Q = model.F, model.Q
        self.LQ = np.linalg.cholesky(self.Q)
        L0 = np.linalg.cholesky(sc.P0)
        self.S = sc.sensor_array
        self.rng_nodes: list[list[np.random.Generator]] = []
        self.rng_f: list[np.random.Generator] = []
        self.rng_c: list[np.random.Generator] = []
        self.rng_x: list[list[np.random.Generator]] = []
        self.rng_r: list[np.random.Generator] = []
        truth, z, m0 = [], [], []
        for run in streams:  # each run's streams, spawned from its seed by _run_streams
            s_target, s_nodes, s_fusion, s_central, s_extra, s_read = run  # the 6th: the readings
            target = simulate_target(sc, np.random.default_rng(s_target))
            truth.append(target.truth), z.append(target.z), m0.append(target.m0)
            self.rng_nodes.append([np.random.default_rng(s) for s in s_nodes.spawn(N)])
            self.rng_f.append(np.random.default_rng(s_fusion))
            self.rng_c.append(np.random.default_rng(s_central))
            self.rng_x.append([np.random.default_rng(s) for s in s_extra.spawn(N)])
            self.rng_r.append(np.random.default_rng(s_read))
        self.truth, self.z, m0a = np.stack(truth), np.stack(z), np.stack(m0)
        keys = method_keys(N, sc.readings)
        self.est = {k: np.empty((B, K, 4)) for k in keys}
        self.cov = {k: np.empty((B, K, 4, 4)) for k in keys if k != "mean_of_local_means"}
        extra = ("first_order", "equal_kl", "equal_kl_g", "literal") if sc.readings else ()
        self.eps = {k: np.full((B, K, N), np.nan) for k in ("pso", "slsqp", "prev", "ci_gaussian", "ci_det", "ci_trace")
                    + extra}
        self.ess = {k: np.full((B, K), np.nan)
                    for k in ("pso", "uniform", "redraw", "prev") + (("first_order_start",) if sc.readings else ()) + ("centralised_pf",)}
        self.ess["local"] = np.empty((B, K, N))
        self.obj = {k: np.empty((B, K)) for k in ("pso", "slsqp") + (("literal",) if sc.readings else ())}
        self.evals = {k: np.empty((B, K)) for k in ("pso", "slsqp") + (("literal",) if sc.readings else ())}
        self.trace: dict[str, FloatArray] = {}
        self.gm_ll, self.gm1_ll = np.empty((B, K, N)), np.empty((B, K, N))
        self.n_fused = np.empty((B, K))
        self.flags = flags
        self.nodes = np.full((B, K, N, 4), np.nan)
        self.history: list[list[FloatArray]] = [[] for _ in range(B)]
        self.guarded: list[list[tuple[int, int]]] = [[] for _ in range(B)]
        n0 = max(sc.n_initial, sc.n_particles)
        draws = _normals([g for row in self.rng_nodes for g in row], (n0, 4)).reshape(B, N, n0, 4)
        self.particles = m0a[:, None, None, :] + np.matmul(draws, L0.T)  # (B, N, n0, 4)
        self.weights = np.empty(self.particles.shape[:-1])
        draws = _normals(self.rng_c, (sc.n_central, 4))
        self.central = m0a[:, None, :] + np.matmul(draws, L0.T)
        self.gm: tuple[FloatArray, FloatArray, FloatArray] | None = None  # weights, means, covs (B, N, S, ...)
        self.prev_eps = np.full((B, N), 1.0 / N)
        clock.lap("setup")

    def run(self) -> list[TrackingRun]:
        for k in range(self.sc.frames):
            self.frame(k)
        B = self.B
        return [trusted(TrackingRun, truth=self.truth[b].copy(), estimates={k: v[b].copy() for k, v in self.est.items()},
                            covariances={k: v[b].copy() for k, v in self.cov.items()},
                            eps={k: v[b].copy() for k, v in self.eps.items()},
                            ess={k: v[b].copy() for k, v in self.ess.items()},
                            objective={k: v[b].copy() for k, v in self.obj.items()},
                            swarm_history=_pad_histories(self.history[b]),
                            evaluations={k: v[b].copy() for k, v in self.evals.items()},
                            gm_loglik=self.gm_ll[b].copy(), gm1_loglik=self.gm1_ll[b].copy(),
                            n_fused_components=self.n_fused[b].copy(),
                            node_estimates=self.nodes[b].copy() if self.flags[b] else None,
                            timings=_tracking_timings(self.timings, B), guarded=tuple(self.guarded[b]),
                            swarm_trace={k: v[b].copy() for k, v in self.trace.items()}, scenario=self.sc)
                for b in range(B)]

    def frame(self, k: int) -> None:
        """Frame ``k`` of every run of the block: steps B-I of every method, the baselines and the centralised filter.

        The steps run in this order (each draws from its own generators in a fixed order, so the order is
        part of the result): the local filters (step B), their mixtures (step C), the Gaussian baselines,
        the fusion with its variants (steps D-I), the centralised filter, the local filters' resampling.
        """
        clock = LapTimer(self.timings)
        X, w, m_loc, c_loc, resampled = self._local_filters(k)
        clock.lap("particle_filters")
        logw, gmu, gP = self._mixtures(k, X, w, m_loc, c_loc, resampled)
        clock.lap("em")
        self._gaussian_baselines(k)
        clock.lap("gaussian_baselines")
        self._fusion(k, logw, gmu, gP, clock)
        clock.lap("variants")
        self._centralised(k)
        if not resampled:
            self._resample_local(X, w, c_loc)
        clock.lap("centralised_pf")

    @own_underflow  # underflow to 0 by design (a kernel, a density or normalised weights: fuzz 33b D6)
    def _local_filters(self, k: int) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray, bool]:
        """Step B: predict and weight every node's particles (collapse guard, moments, the n_initial cut).

        Returns the particles (B, N, n, 4) and normalised weights (B, N, n) the mixtures are fitted to, the
        local moments before any cut, and whether the particles were already resampled (the n_initial cut).
        """
        sc, N, B, F, LQ = self.sc, self.N, self.B, self.F, self.LQ
        est, cov, ess = self.est, self.cov, self.ess
        X = self.particles
        n = X.shape[2]
        draws = _normals([g for row in self.rng_nodes for g in row], (n, 4)).reshape(B, N, n, 4)
        X = np.matmul(X, F.T)
        X += np.matmul(draws, LQ.T)  # the same sum, without a third array
        lw = np.stack([_log_likelihood(X[:, i], self.z[:, k, i], self.S[i], sc.sigma_r, sc.sigma_theta)
                       for i in range(N)], axis=1)  # (B, N, n)
        w = np.exp(lw - lw.max(axis=-1, keepdims=True))
        w /= w.sum(axis=-1, keepdims=True)
        if sc.guard > 0:
            low = 1.0 / np.sum(w**2, axis=-1) < sc.guard * n
            for b, i in zip(*np.nonzero(low)):
                X[b, i], w[b, i] = self._progressive_correction(X[b, i], k, int(b), int(i))
                self.guarded[b].append((k, int(i)))
        ess["local"][:, k] = 1.0 / np.sum(w**2, axis=-1)
        m_loc, c_loc = _moments(X, w)
        for i in range(N):
            est[f"local{i + 1}"][:, k], cov[f"local{i + 1}"][:, k] = m_loc[:, i], c_loc[:, i]
        resampled = n > sc.n_particles
        if resampled:  # the guard of n_initial: down to n_particles before the mixture fit
            Q = sc.n_particles
            pairs = [(b, i) for b in range(B) for i in range(N)]
            idx = [_systematic_resample(w[b, i], self.rng_nodes[b][i], Q) for b, i in pairs]
            Xr = np.stack([X[b, i][j] for (b, i), j in zip(pairs, idx)])
            if sc.regularised:
                Xr = _regularise_batch(Xr, c_loc.reshape(B * N, 4, 4), [self.rng_nodes[b][i] for b, i in pairs])
            X, w = Xr.reshape(B, N, Q, 4), np.full((B, N, Q), 1.0 / Q)
        self.particles, self.weights = X, w
        return X, w, m_loc, c_loc, resampled

    def _mixtures(self, k: int, X: FloatArray, w: FloatArray, m_loc: FloatArray, c_loc: FloatArray,
                  resampled: bool) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Step C: the weighted EM of every node of every run, one array problem; its fit's log-likelihoods.

        Returns the mixtures' log-weights (B, N, S), means (B, N, S, 4) and covariances (B, N, S, 4, 4).
        """
        sc, N, B, F = self.sc, self.N, self.B, self.F
        S = sc.n_components
        inits: list[tuple[FloatArray, FloatArray, FloatArray] | None] = []
        if self.gm is None:
            inits = [None] * (B * N)
        else:
            gw, gmu, gP = self.gm
            full = np.all(gw > 0, axis=-1)
            mu_p = np.matmul(gmu, F.T)
            P_p = np.matmul(np.matmul(F, gP), F.T) + self.Q
            inits = [(gw[b, i], mu_p[b, i], P_p[b, i]) if full[b, i] else None for b in range(B) for i in range(N)]
        Q = X.shape[2]
        pis, mus, Ps, _ = _em_arrays(X.reshape(B * N, Q, 4), w.reshape(B * N, Q), S,
                                     [r for rs in self.rng_nodes for r in rs], sc.em_iterations, 1e-6, 1e-6, inits)
        alive = pis > 0
        gw = np.where(alive, pis / np.sum(np.where(alive, pis, 0.0), axis=1, keepdims=True), 0.0).reshape(B, N, S)
        gmu, gP = mus.reshape(B, N, S, 4), Ps.reshape(B, N, S, 4, 4)
        self.gm = (gw, gmu, gP)
        with np.errstate(divide="ignore"):
            logw = np.where(gw > 0, np.log(np.where(gw > 0, gw, 1.0)), -np.inf)
        m1, P1 = (_moments(X, w) if resampled else (m_loc, c_loc))
        phi = _features(X - m1[:, :, None, :])
        lp = _mixture_logpdf_features(logw, gmu - m1[:, :, None, :], gP, phi)
        self.gm_ll[:, k] = np.sum(w * lp, axis=-1)
        # one moment-matched Gaussian: sum_q w_q log N(x_q; m1, P1) = -(d log 2 pi + log det P1 + d) / 2 exactly
        self.gm1_ll[:, k] = -0.5 * (4 * np.log(2 * np.pi) + np.linalg.slogdet(P1)[1] + 4)
        return logw, gmu, gP

    def _gaussian_baselines(self, k: int) -> None:
        """Gaussian baselines from the moment-matched local posteriors (mean of means, naive product, CI)."""
        N, B = self.N, self.B
        est, cov, eps = self.est, self.cov, self.eps
        means = np.stack([est[f"local{i + 1}"][:, k] for i in range(N)], axis=1)
        covs = np.stack([cov[f"local{i + 1}"][:, k] for i in range(N)], axis=1)
        est["mean_of_local_means"][:, k] = means.mean(axis=1)
        # fuzz 27a N2, fuzz 28a C5: a collapsed particle cloud, or a target near a sensor where the bearing turns
        # across the cloud, refused by name where the Gaussian baselines cannot be computed (numpy's LinAlgError from
        # an inverse), not by the stricter SINGULAR_MARGIN: the chapter's design study runs collapsing clouds on
        # purpose (a local covariance of correlation condition number 1e15, which LAPACK inverts, stays a valid run)
        try:
            infos = np.linalg.inv(covs)
            logdets = np.linalg.slogdet(2 * np.pi * covs)[1]
            nx, nP, _ = _product_terms(means[:, None], infos[:, None], logdets[:, None], np.ones((B, N)))
            est["naive_product"][:, k], cov["naive_product"][:, k] = nx[:, 0], nP[:, 0]
            e_ci = _gaussian_chernoff_batch(means, infos, logdets)
            cx, cP, _ = _product_terms(means[:, None], infos[:, None], logdets[:, None], e_ci)
            est["ci_gaussian"][:, k], cov["ci_gaussian"][:, k], eps["ci_gaussian"][:, k] = cx[:, 0], cP[:, 0], e_ci
            for crit in ("det", "trace"):  # the practitioner's covariance intersection (Julier & Uhlmann)
                e_c = _ci_criterion_batch(infos, crit)
                cx, cP, _ = _product_terms(means[:, None], infos[:, None], logdets[:, None], e_c)
                est[f"ci_{crit}"][:, k], cov[f"ci_{crit}"][:, k], eps[f"ci_{crit}"][:, k] = cx[:, 0], cP[:, 0], e_c
        except np.linalg.LinAlgError:
            bad = np.argwhere(singular_mask(covs))   # the node whose cloud collapsed, when SINGULAR_MARGIN sees it
            i = int(bad[0][1]) if bad.size else None
            who = (f"node {i + 1}'s local posterior covariance" if i is not None
                   else "a local posterior's covariance, or their fusion,")
            near = ("near sensor {} at ({:g}, {:g})".format(i + 1, *self.sc.sensor_array[i]) if i is not None
                    else "near a sensor")
            raise ValueError(f"sc: {who} at frame {k} is singular to working precision (its particles collapsed "
                             f"onto too few points): sc.n_particles = {self.sc.n_particles} particles cannot resolve a "
                             f"likelihood this narrow (sc.sigma_theta = {self.sc.sigma_theta:g}, sc.sigma_r = "
                             f"{self.sc.sigma_r:g}), or the target is {near}, where the bearing turns across the "
                             "cloud; use more particles, less precise sensors or a target away from the "
                             "sensors") from None

    def _fusion(self, k: int, logw: FloatArray, gmu: FloatArray, gP: FloatArray, clock: LapTimer) -> None:
        """Steps D-I (the patent), with SLSQP on the same samples, the redrawn and previous-ε variants, the
        readings' variants and every node's own fusion; ``clock`` restarts after the first fusion (whose
        stages record their own timings)."""
        sc, N, B = self.sc, self.N, self.B
        est, cov, eps, ess = self.est, self.cov, self.eps, self.ess
        fus = _fuse_arrays(logw, gmu, gP, self.rng_f, sc.n_samples, np.full((B, N), 1.0 / N), "pso", sc.variants,
                           sc.variants, self.so, self.timings, equal_kl=sc.readings,
                           literal_xtol=sc.literal_xtol if sc.readings else None)
        clock.t = time.perf_counter()
        for b, fu in enumerate(fus):
            est["chernoff_pso"][b, k], cov["chernoff_pso"][b, k] = fu.x, fu.P
            est["chernoff_uniform"][b, k], cov["chernoff_uniform"][b, k] = fu.x_eps0, fu.P_eps0
            est["first_order_uniform"][b, k], cov["first_order_uniform"][b, k] = fu.x_first_order, fu.P_first_order
            eps["pso"][b, k], self.obj["pso"][b, k], self.evals["pso"][b, k] = fu.eps, fu.objective, fu.n_evaluations
            ess["pso"][b, k], ess["uniform"][b, k] = fu.ess, fu.ess_eps0
            self.n_fused[b, k] = fu.n_fused_components
            assert fu.swarm is not None
            self.history[b].append(fu.swarm.history)
            if sc.variants:
                est["chernoff_slsqp"][b, k], cov["chernoff_slsqp"][b, k] = fu.x_reference, fu.P_reference
                est["chernoff_redraw"][b, k], cov["chernoff_redraw"][b, k] = fu.x_redraw, fu.P_redraw
                eps["slsqp"][b, k], self.obj["slsqp"][b, k] = fu.eps_reference, fu.objective_reference
                self.evals["slsqp"][b, k], ess["redraw"][b, k] = fu.n_evaluations_reference, fu.ess_redraw
        if sc.readings:  # G6 as worded, from the same swarm followed to its limit
            T1 = max(fu.swarm.trace.fitness.size for fu in fus if fu.swarm is not None and fu.swarm.trace is not None)
            if not self.trace:
                self.trace = {key: np.full((B, sc.frames, T1), np.nan) for key in ("fitness", "spread")}
            for b, fu in enumerate(fus):
                est["chernoff_literal"][b, k], cov["chernoff_literal"][b, k] = fu.x_literal, fu.P_literal
                eps["literal"][b, k], self.obj["literal"][b, k] = fu.eps_literal, fu.objective_literal
                self.evals["literal"][b, k] = fu.n_evaluations_literal
                tr = fu.swarm.trace  # type: ignore[union-attr]
                self.trace["fitness"][b, k, :tr.fitness.size] = tr.fitness
                self.trace["spread"][b, k, :tr.spread.size] = tr.spread
        if sc.variants:
            fps = _fuse_arrays(logw, gmu, gP, self.rng_f, sc.n_samples, self.prev_eps, sc.prev_optimiser, False, False,
                               self.so, None)
            for b, fp in enumerate(fps):
                est["chernoff_prev"][b, k], cov["chernoff_prev"][b, k] = fp.x, fp.P
                eps["prev"][b, k], ess["prev"][b, k] = fp.eps, fp.ess
            self.prev_eps = np.stack([fp.eps for fp in fps])
        else:
            for key in ("chernoff_slsqp", "chernoff_redraw", "chernoff_prev"):
                est[key][:, k], cov[key][:, k] = np.nan, np.nan
            eps["slsqp"][:, k] = eps["prev"][:, k] = np.nan
            self.obj["slsqp"][:, k] = self.evals["slsqp"][:, k] = ess["redraw"][:, k] = ess["prev"][:, k] = np.nan
        if sc.readings:  # step D's exponents by minimising Z_FO (own stream); step F as the equal-KL rule
            e_first_order = _first_order_minimum(logw, gmu, gP)
            frs = _fuse_arrays(logw, gmu, gP, self.rng_r, sc.n_samples, e_first_order, "newton", False, False, None, None)
            for b, fr in enumerate(frs):
                est["chernoff_first_order_start"][b, k], cov["chernoff_first_order_start"][b, k] = fr.x, fr.P
                est["chernoff_first_order"][b, k], cov["chernoff_first_order"][b, k] = fr.x_eps0, fr.P_eps0
                ess["first_order_start"][b, k] = fr.ess
                eps["equal_kl"][b, k] = fus[b].eps_equal_kl
            eps["first_order"][:, k] = e_first_order
            eps["equal_kl_g"][:, k] = _equal_kl_on_mixture(logw, gmu, gP)  # on g (no random draws)
        flagged = [b for b in range(B) if self.flags[b]]
        if flagged:  # every node fuses on its own, with its own stream
            rep = np.repeat(flagged, N)
            fn = _fuse_arrays(logw[rep], gmu[rep], gP[rep], [self.rng_x[b][i] for b in flagged for i in range(N)],
                              sc.n_samples, np.full((rep.size, N), 1.0 / N), "pso", False, False, self.so, None)
            for j, b in enumerate(rep):
                self.nodes[b, k, j % N] = fn[j].x

    @own_underflow  # underflow to 0 by design (a kernel, a density or normalised weights: fuzz 33b D6)
    def _centralised(self, k: int) -> None:
        """The centralised bootstrap PF on all measurements: predict, weight, guard, moments, resample."""
        sc, N, B, F, LQ = self.sc, self.N, self.B, self.F, self.LQ
        est, cov, ess = self.est, self.cov, self.ess
        draws = _normals(self.rng_c, (sc.n_central, 4))
        C = np.matmul(self.central, F.T)
        C += np.matmul(draws, LQ.T)
        lw = _log_likelihood(C, self.z[:, k, 0], self.S[0], sc.sigma_r, sc.sigma_theta)
        for i in range(1, N):
            lw = lw + _log_likelihood(C, self.z[:, k, i], self.S[i], sc.sigma_r, sc.sigma_theta)
        wc = np.exp(lw - lw.max(axis=-1, keepdims=True))
        wc /= wc.sum(axis=-1, keepdims=True)
        if sc.central_guard > 0:
            for b in np.flatnonzero(1.0 / np.sum(wc**2, axis=-1) < sc.central_guard * sc.n_central):
                C[b], wc[b] = self._progressive_correction(C[b], k, int(b), -1)
                self.guarded[b].append((k, -1))
        ess["centralised_pf"][:, k] = 1.0 / np.sum(wc**2, axis=-1)
        mc, Pc = _moments(C, wc)
        est["centralised_pf"][:, k], cov["centralised_pf"][:, k] = mc, Pc
        C = np.stack([C[b][_systematic_resample(wc[b], self.rng_c[b])] for b in range(B)])
        if sc.regularised:
            C = _regularise_batch(C, Pc, self.rng_c)
        self.central = C

    def _resample_local(self, X: FloatArray, w: FloatArray, c_loc: FloatArray) -> None:
        """Systematic resampling of every node's particles after the mixture fit (and regularisation)."""
        sc, N, B = self.sc, self.N, self.B
        pairs = [(b, i) for b in range(B) for i in range(N)]
        Xr = np.stack([X[b, i][_systematic_resample(w[b, i], self.rng_nodes[b][i])] for b, i in pairs])
        if sc.regularised:
            Xr = _regularise_batch(Xr, c_loc.reshape(B * N, 4, 4), [self.rng_nodes[b][i] for b, i in pairs])
        self.particles = Xr.reshape(X.shape)

    @own_underflow  # underflow to 0 by design (a kernel, a density or normalised weights: fuzz 33b D6)
    def _progressive_correction(self, x: FloatArray, k: int, b: int, i: int) -> tuple[FloatArray, FloatArray]:
        """Node ``i``'s update of run ``b`` at frame ``k`` in GUARD_STAGES tempering steps (Oudjane & Musso 2000).

        ``i = -1``: the centralised filter (every sensor's likelihood, its own generator).
        """
        sc = self.sc
        rng = self.rng_c[b] if i < 0 else self.rng_nodes[b][i]
        sensors = range(self.N) if i < 0 else (i,)
        for stage in range(GUARD_STAGES):
            lw = sum(_log_likelihood(x, self.z[b, k, j], self.S[j], sc.sigma_r, sc.sigma_theta)
                     for j in sensors) / GUARD_STAGES
            w = np.exp(lw - lw.max())
            w /= w.sum()
            if stage == GUARD_STAGES - 1:
                break
            cov_w = _moments(x, w)[1]
            x = x[_systematic_resample(w, rng)]
            if sc.regularised:
                x = _regularise_batch(x[None], cov_w[None], [rng])[0]
        return x, w


def _pad_histories(history: list[FloatArray]) -> FloatArray:
    """Stack swarm histories of different lengths (early stopping), repeating the final value."""
    n = max(h.size for h in history)
    return np.stack([np.pad(h, (0, n - h.size), mode="edge") for h in history])

