"""Issue 37: the package against its peers, side by side in one process, with an agreement check per row.

Peers: Stone Soup (covariance intersection, particle filter), filterpy (Kalman filter), scikit-learn
(Gaussian-mixture EM) and pyswarms (particle swarm). They are not in the lock: install them in a side
environment, as ``crosscheck_stonesoup.py`` does for Stone Soup, and name its site-packages. It is put
*behind* this environment's on ``sys.path``, so numpy, scipy and filterpy are the locked ones for both
sides (the side environment should hold the same numpy and scipy: ``pip install numpy==<lock> ...``):

    python -m venv /tmp/peers && /tmp/peers/bin/pip install numpy==2.4.6 scipy==1.17.1 \\
        stonesoup filterpy scikit-learn pyswarms
    .venv/bin/python benchmarks/bench_peers.py --peers /tmp/peers

Timing: one BLAS/OpenMP thread for both sides (environment and threadpoolctl), process CPU time (robust
to the load of a shared machine). Every row times ours and the peer alternately, ``REPEATS`` = 9 times (the order swapped every
other repeat), and keeps the median of each; a call shorter than ~20 ms is repeated ``inner`` times per
repeat. ratio = peer time / our time (> 1: we are faster). Each row is "single" (one problem) or
"batched" (many problems, as the book runs them; ours vectorised over problems where the package has a
batch kernel, the peer in a loop).

Agreement, per row: "bitwise" (the same algorithm on the same numbers: arrays equal), "round-off" (the same
algorithm, different arithmetic: largest relative difference stated), "optimiser tolerance" (the same
optimum found by two methods), or "statistical" (random algorithms: the same quantity within its Monte
Carlo error). The particle-filter rows also record the study kernel's GFLOP/s (see ``bench_pf_kernel.py``).

Writes ``benchmarks/results/peers.json``: the common fields (``date``, ``machine``, ``measurements``) and
``rows``: one record per row with ``key``, ``what``, ``size`` ("single" or "batched"), ``peer``,
``peer_version``, ``ours_s``, ``peer_s``, ``ratio``, ``agreement`` (kind), ``agreement_value`` and
``agreement_ok``.
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):  # one thread, set before any
    os.environ.setdefault(_var, "1")  # library starts its pool (threadpoolctl limits only those loaded)

import argparse  # noqa: E402
import contextlib  # noqa: E402
import glob  # noqa: E402
import logging  # noqa: E402
import statistics  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _results import write_results  # noqa: E402  (benchmarks/_results.py)

REPEATS = 9
TARGET = 0.05  # CPU seconds per timed batch of calls (process_time ticks are coarse on some systems)


def interleaved(ours, peer, repeats: int = REPEATS) -> tuple[float, float]:
    """Median CPU time per call (s) of ``ours`` and ``peer``, timed alternately (one thread: CPU time is the
    time the call needs, without the waits for a core that other work on a shared machine adds to the wall clock)."""
    inner = {}
    for name, fn in (("ours", ours), ("peer", peer)):  # warm-up and size of the inner loop
        t0 = time.process_time()
        fn()
        dt = max(time.process_time() - t0, 1e-5)
        inner[name] = max(1, min(1000, int(TARGET / dt)))
    times = {"ours": [], "peer": []}
    for r in range(repeats):
        order = (("ours", ours), ("peer", peer)) if r % 2 == 0 else (("peer", peer), ("ours", ours))
        for name, fn in order:
            n = inner[name]
            t0 = time.process_time()
            for _ in range(n):
                fn()
            times[name].append((time.process_time() - t0) / n)
    return statistics.median(times["ours"]), statistics.median(times["peer"])


ROWS: list[dict] = []


def row(key: str, what: str, size: str, peer: str, version: str, ours_fn, peer_fn, agreement: str, value: float,
        ok: bool) -> None:
    t_ours, t_peer = interleaved(ours_fn, peer_fn)
    rec = {"key": key, "what": what, "size": size, "peer": peer, "peer_version": version, "ours_s": t_ours,
           "peer_s": t_peer, "ratio": t_peer / t_ours, "agreement": agreement, "agreement_value": float(value),
           "agreement_ok": bool(ok)}
    ROWS.append(rec)
    print(f"{key:24s} {size:8s} ours {t_ours * 1e3:9.3f} ms  {peer:12s} {t_peer * 1e3:9.3f} ms  "
          f"ratio {t_peer / t_ours:7.2f}  {agreement} {value:.2e} {'ok' if ok else 'FAIL'}", flush=True)


# ---------------------------------------------------------------- covariance intersection (Stone Soup)
def ci_rows() -> None:
    import stonesoup
    from scipy.optimize import minimize_scalar
    from stonesoup.mixturereducer.gaussianmixture import CovarianceIntersection
    from stonesoup.types.state import GaussianState

    from fusion.estimates import ci as ci_mod

    rng = np.random.default_rng(37)

    def pair():
        A1, A2 = rng.normal(size=(4, 4)), rng.normal(size=(4, 4))
        return (rng.normal(size=4), A1 @ A1.T + 0.5 * np.eye(4), rng.normal(size=4), A2 @ A2.T + 0.5 * np.eye(4))

    def ss_ci(x1, P1, x2, P2):
        """What a Stone Soup user writes: its CI merge, the weight by scipy's bounded search on tr P."""
        s1, s2 = GaussianState(x1[:, None], P1), GaussianState(x2[:, None], P2)
        merge = CovarianceIntersection.merge_components
        res = minimize_scalar(lambda w: np.trace(merge(s1, s2, weights=[w, 1.0 - w]).covar), bounds=(0.0, 1.0),
                              method="bounded", options={"xatol": 1e-8})
        return res.x, merge(s1, s2, weights=[res.x, 1.0 - res.x])

    pairs = [pair() for _ in range(100)]
    x1, P1, x2, P2 = pairs[0]
    ours = ci_mod.covariance_intersection(x1, P1, x2, P2)
    w_ss, post = ss_ci(x1, P1, x2, P2)
    # the same CI at the same weight (round-off: pinv vs inv), and the same optimal weight (two optimisers)
    at_w = CovarianceIntersection.merge_components(GaussianState(x1[:, None], P1), GaussianState(x2[:, None], P2),
                                                   weights=[ours.omega, 1.0 - ours.omega])
    d_same = max(np.abs(np.asarray(at_w.covar) - ours.P).max() / np.abs(ours.P).max(),
                 np.abs(np.asarray(at_w.state_vector).ravel() - ours.x).max() / np.abs(ours.x).max())
    row("ci_fixed_weight", "CI at a given weight (4-D)", "single", "stonesoup", stonesoup.__version__,
        lambda: ci_mod.covariance_intersection(x1, P1, x2, P2, omega=0.3),
        lambda: CovarianceIntersection.merge_components(GaussianState(x1[:, None], P1), GaussianState(x2[:, None], P2),
                                                        weights=[0.3, 0.7]),
        "round-off", d_same, d_same < 1e-10)
    d_w = abs(w_ss - ours.omega)
    row("ci_optimal", "CI with the optimal weight (tr P, 4-D)", "single", "stonesoup+scipy", stonesoup.__version__,
        lambda: ci_mod.covariance_intersection(x1, P1, x2, P2), lambda: ss_ci(x1, P1, x2, P2),
        "optimiser tolerance", d_w, d_w < 1e-6)
    dws = [abs(ss_ci(*p)[0] - ci_mod.covariance_intersection(*p).omega) for p in pairs[:20]]
    row("ci_optimal_100", "CI with the optimal weight, 100 pairs (a loop on both sides)", "batched",
        "stonesoup+scipy", stonesoup.__version__,
        lambda: [ci_mod.covariance_intersection(*p) for p in pairs], lambda: [ss_ci(*p) for p in pairs],
        "optimiser tolerance", max(dws), max(dws) < 1e-6)


# ---------------------------------------------------------------- Kalman filter (filterpy)
def kalman_rows() -> None:
    import filterpy
    from filterpy.kalman import KalmanFilter

    from fusion.filtering import kalman as km

    m = km.cv_model(1.0)
    F, H = m.F, m.H
    Q, R = np.diag([100.0] * 4), np.diag([150.0**2] * 2)  # chapter 05's two-sensor case
    P0 = np.diag([150.0**2, 1e4, 150.0**2, 1e4])
    K = 100
    rng = np.random.default_rng(5)
    truth = np.cumsum(np.full((K, 2), 10.0), axis=0)
    z = truth[None] + 150.0 * rng.standard_normal((100, K, 2))
    x0 = np.column_stack([z[:, 0, 0], np.zeros(100), z[:, 0, 1], np.zeros(100)])

    def fp(r: int) -> np.ndarray:
        kf = KalmanFilter(dim_x=4, dim_z=2)
        kf.F, kf.H, kf.Q, kf.R, kf.P, kf.x = F, H, Q, R, P0.copy(), x0[r][:, None].copy()
        out = np.empty((K, 4))
        out[0] = x0[r]
        for k in range(1, K):
            kf.predict()
            kf.update(z[r, k])
            out[k] = kf.x[:, 0]
        return out

    def ours(runs: int) -> np.ndarray:
        return km.filter_runs(z[:runs], km.gain_sequence(F, H, Q, R, P0, K), x0[:runs])

    one_same = np.array_equal(ours(1)[0], fp(0))
    all_ours = ours(100)
    all_same = all(np.array_equal(all_ours[r], fp(r)) for r in range(100))
    d1 = float(np.abs(ours(1)[0] - fp(0)).max())
    g = km.gain_sequence(F, H, Q, R, P0, K)
    fixed = next((k for k in range(2, K) if np.array_equal(g.P[k], g.P[k - 1])), None)
    at = f"fixed point of P at step {fixed}" if fixed else f"P never repeats in {K} steps"
    row("kalman_one_run", f"Kalman filter, one run of {K} steps (4-D CV, {at})", "single",
        "filterpy", filterpy.__version__, lambda: ours(1), lambda: fp(0), "bitwise", d1, one_same)
    row("kalman_100_runs", f"Kalman filter, 100 runs of {K} steps", "batched", "filterpy", filterpy.__version__,
        lambda: ours(100), lambda: [fp(r) for r in range(100)], "bitwise", float(np.abs(all_ours[-1] - fp(99)).max()),
        all_same)
    # a longer run: the recursion reaches its floating-point fixed point (step 102 here) and the rest is copied
    K3 = 300
    z3 = truth[-1] + np.cumsum(np.full((K3, 2), 10.0), axis=0)[None] + 150.0 * rng.standard_normal((1, K3, 2))

    def fp3() -> np.ndarray:
        kf = KalmanFilter(dim_x=4, dim_z=2)
        kf.F, kf.H, kf.Q, kf.R, kf.P, kf.x = F, H, Q, R, P0.copy(), x0[0][:, None].copy()
        out = np.empty((K3, 4))
        out[0] = x0[0]
        for k in range(1, K3):
            kf.predict()
            kf.update(z3[0, k])
            out[k] = kf.x[:, 0]
        return out

    ours3 = lambda: km.filter_runs(z3, km.gain_sequence(F, H, Q, R, P0, K3), x0[:1])  # noqa: E731
    g3 = km.gain_sequence(F, H, Q, R, P0, K3)
    fixed3 = next((k for k in range(2, K3) if np.array_equal(g3.P[k], g3.P[k - 1])), None)
    row("kalman_one_run_300", f"Kalman filter, one run of {K3} steps (fixed point of P at step {fixed3})", "single",
        "filterpy", filterpy.__version__, ours3, fp3, "bitwise", float(np.abs(ours3()[0] - fp3()).max()),
        np.array_equal(ours3()[0], fp3()))
    # the gain recursion with no fixed point inside the horizon (P still changing at every step)
    Qs, K2 = 1e-4 * np.eye(4), 60
    g2 = km.gain_sequence(F, H, Qs, R, 1e8 * np.eye(4), K2)
    moving = all(not np.array_equal(g2.P[k], g2.P[k - 1]) for k in range(1, K2))

    zz = z[:1, :K2]
    xx = x0[:1]

    def fp_moving() -> np.ndarray:
        kf = KalmanFilter(dim_x=4, dim_z=2)
        kf.F, kf.H, kf.Q, kf.R, kf.P, kf.x = F, H, Qs, R, 1e8 * np.eye(4), xx[0][:, None].copy()
        out = np.empty((K2, 4))
        out[0] = xx[0]
        for k in range(1, K2):
            kf.predict()
            kf.update(zz[0, k])
            out[k] = kf.x[:, 0]
        return out

    ours2 = lambda: km.filter_runs(zz, km.gain_sequence(F, H, Qs, R, 1e8 * np.eye(4), K2), xx)  # noqa: E731
    d2 = float(np.abs(ours2()[0] - fp_moving()).max())
    row("kalman_one_run_no_fixed_point", f"Kalman filter, one run of {K2} steps whose P never repeats", "single",
        "filterpy", filterpy.__version__, ours2, fp_moving, "bitwise", d2, moving and np.array_equal(ours2()[0], fp_moving()))


# ---------------------------------------------------------------- particle filter (Stone Soup)
def pf_rows() -> None:
    import stonesoup
    from stonesoup.models.measurement.nonlinear import CartesianToBearingRange
    from stonesoup.models.transition.linear import CombinedLinearGaussianTransitionModel, ConstantVelocity
    from stonesoup.predictor.particle import ParticlePredictor
    from stonesoup.resampler.particle import SystematicResampler
    from stonesoup.types.array import StateVectors
    from stonesoup.types.detection import Detection
    from stonesoup.types.hypothesis import SingleHypothesis
    from stonesoup.types.state import ParticleState
    from stonesoup.updater.particle import ParticleUpdater

    from fusion.estimates.chernoff.mixture import _moments_batch
    from fusion.filtering.particles import _log_likelihood, _systematic_resample, ncv_model
    from fusion.scenarios.range_bearing import RangeBearingScenario, _normals, simulate_target

    sc = RangeBearingScenario()
    n, K = sc.n_particles, sc.frames
    sensor = np.asarray(sc.sensors[0], float)
    model = ncv_model(sc.T, sc.q)
    LQ, L0 = np.linalg.cholesky(model.Q), np.diag(sc.p0_std)
    targets = [simulate_target(sc, np.random.default_rng(s)) for s in range(10)]
    truth = np.stack([t.truth for t in targets])
    z = np.stack([t.z[:, 0] for t in targets])  # node 1's readings (range, bearing): (runs, K, 2)
    m0 = np.stack([t.m0 for t in targets])

    def ours(runs: int, seed: int) -> np.ndarray:
        """The study's step B for one node (predict, weight, moments, systematic resampling), over runs at once."""
        rngs = [np.random.default_rng([seed, r]) for r in range(runs)]
        X = m0[:runs, None, :] + np.matmul(_normals(rngs, (n, 4)), L0.T)
        est = np.empty((runs, K, 4))
        for k in range(K):
            X = np.matmul(X, model.F.T)
            X += np.matmul(_normals(rngs, (n, 4)), LQ.T)
            lw = _log_likelihood(X, z[:runs, k], sensor, sc.sigma_r, sc.sigma_theta)
            w = np.exp(lw - lw.max(axis=-1, keepdims=True))
            w /= w.sum(axis=-1, keepdims=True)
            est[:, k] = _moments_batch(X, w)[0]
            X = np.stack([X[b][_systematic_resample(w[b], rngs[b])] for b in range(runs)])
        return est

    cv = ConstantVelocity(sc.q)
    trans = CombinedLinearGaussianTransitionModel([cv, cv])
    meas = CartesianToBearingRange(ndim_state=4, mapping=(0, 2),
                                   noise_covar=np.diag([sc.sigma_theta**2, sc.sigma_r**2]),
                                   translation_offset=sensor[:, None])
    predictor = ParticlePredictor(trans)
    updater = ParticleUpdater(meas, resampler=SystematicResampler())
    from datetime import datetime, timedelta
    t0 = datetime(2026, 1, 1)

    def peer(r: int, seed: int) -> np.ndarray:
        np.random.seed(seed * 1000 + r)  # Stone Soup draws from numpy's global state
        sv = StateVectors((m0[r][None] + np.random.standard_normal((n, 4)) @ L0.T).T)
        prior = ParticleState(sv, log_weight=np.full(n, -np.log(n)), timestamp=t0)
        est = np.empty((K, 4))
        for k in range(K):
            t = t0 + timedelta(seconds=sc.T * (k + 1))
            pred = predictor.predict(prior, timestamp=t)
            det = Detection(np.array([[z[r, k, 1]], [z[r, k, 0]]]), timestamp=t, measurement_model=meas)
            prior = updater.update(SingleHypothesis(pred, det))
            est[k] = np.asarray(prior.mean, float).ravel()
        return est

    # statistical agreement: both filters' position RMSE over 10 runs and 2 seeds, and their mean gap
    # against the Monte-Carlo spread of ours (two seeds of ours)
    e_ours = [ours(10, s) for s in (1, 2)]
    e_peer = [np.stack([peer(r, s) for r in range(10)]) for s in (1, 2)]
    pos = lambda e: np.sqrt(np.mean((e - truth)[..., [0, 2]] ** 2))  # noqa: E731
    rm_o, rm_p = np.mean([pos(e) for e in e_ours]), np.mean([pos(e) for e in e_peer])
    mc = np.sqrt(np.mean((e_ours[0] - e_ours[1])[..., [0, 2]] ** 2))  # seed-to-seed spread of one filter
    gap = np.sqrt(np.mean((np.mean(e_ours, axis=0) - np.mean(e_peer, axis=0))[..., [0, 2]] ** 2))
    ok = abs(rm_o - rm_p) / rm_p < 0.1 and gap < 2 * mc
    print(f"  particle filter: position RMSE ours {rm_o:.3f} m, Stone Soup {rm_p:.3f} m; mean gap {gap:.3f} m, "
          f"seed-to-seed spread {mc:.3f} m")
    row("pf_one_run", f"bootstrap particle filter, {n} particles x {K} frames (range-bearing)", "single", "stonesoup",
        stonesoup.__version__, lambda: ours(1, 3), lambda: peer(0, 3), "statistical", abs(rm_o - rm_p) / rm_p, ok)
    row("pf_10_runs", f"bootstrap particle filter, 10 runs of {n} particles x {K} frames", "batched", "stonesoup",
        stonesoup.__version__, lambda: ours(10, 3), lambda: [peer(r, 3) for r in range(10)], "statistical",
        abs(rm_o - rm_p) / rm_p, ok)


# ---------------------------------------------------------------- mixture EM (scikit-learn)
def em_rows() -> None:
    import sklearn
    from sklearn.mixture import GaussianMixture as SkGM

    from fusion.estimates.mixtures import GaussianMixture, weighted_em, weighted_em_batch

    rng = np.random.default_rng(11)
    Q, d, S, it = 2000, 4, 3, 20  # chapter 06's node mixtures: 2000 particles, 3 components, 20 iterations
    centres = rng.normal(scale=5.0, size=(S, d))
    sets = [np.concatenate([c + rng.normal(size=(Q // S + 1, d)) for c in centres])[:Q] + rng.normal(size=d)
            for _ in range(20)]
    w = np.full(Q, 1.0 / Q)

    def init(x: np.ndarray) -> GaussianMixture:
        idx = np.linspace(0, Q - 1, S).astype(int)
        return GaussianMixture(np.full(S, 1.0 / S), x[idx], np.stack([np.cov(x.T)] * S))

    inits = [init(x) for x in sets]

    def ours(b: int):
        return weighted_em(sets[b], w, S, np.random.default_rng(0), max_iter=it, tol=0.0, floor=0.0, init=inits[b])

    def peer(b: int):
        g = inits[b]
        sk = SkGM(S, covariance_type="full", tol=0.0, reg_covar=0.0, max_iter=it, n_init=1, weights_init=g.weights,
                  means_init=g.means, precisions_init=np.linalg.inv(g.covs), init_params="random")
        import warnings
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # "did not converge": a fixed number of iterations is asked for
            return sk.fit(sets[b])

    def diff(b: int) -> float:
        a, s = ours(b).mixture, peer(b)
        return max(np.abs(a.means - s.means_).max() / np.abs(s.means_).max(),
                   np.abs(a.covs - s.covariances_).max() / np.abs(s.covariances_).max(),
                   np.abs(a.weights - s.weights_).max())

    dd = max(diff(b) for b in range(5))
    row("em_one_set", f"Gaussian-mixture EM, {Q} points, {S} components, {it} iterations", "single", "scikit-learn",
        sklearn.__version__, lambda: ours(0), lambda: peer(0), "round-off", dd, dd < 1e-8)
    X, W = np.stack(sets), np.full((20, Q), 1.0 / Q)
    rngs = [np.random.default_rng(0) for _ in range(20)]
    row("em_20_sets", f"Gaussian-mixture EM, 20 sets of {Q} points (ours: one batch)", "batched", "scikit-learn",
        sklearn.__version__,
        lambda: weighted_em_batch(X, W, S, rngs, max_iter=it, tol=0.0, floor=0.0, init=inits),
        lambda: [peer(b) for b in range(20)], "round-off", dd, dd < 1e-8)


# ---------------------------------------------------------------- particle swarm (pyswarms)
def swarm_rows() -> None:
    import pyswarms
    import pyswarms as ps
    logging.getLogger("pyswarms").setLevel(logging.WARNING)

    from fusion.optimise.swarm import particle_swarm, particle_swarm_batch

    dim, n, it = 3, 20, 50
    target = np.array([0.5, 0.3, 0.2])

    def fit(E: np.ndarray) -> np.ndarray:  # a cheap fitness (maximised): minus the squared distance on the simplex
        return -np.sum((E - target) ** 2, axis=-1)

    def ours(seed: int):  # patience = iterations: every swarm runs its 50 iterations, as pyswarms does
        return particle_swarm(fit, dim, np.random.default_rng(seed), n_particles=n, iterations=it, patience=it)

    def peer(seed: int):
        np.random.seed(seed)
        opt = ps.single.GlobalBestPSO(n_particles=n, dimensions=dim, options={"c1": 1.49618, "c2": 1.49618, "w": 0.7298},
                                      bounds=(np.full(dim, 1e-6), np.ones(dim)), velocity_clamp=(-0.2, 0.2))
        cost, pos = opt.optimize(lambda u: -fit(u / u.sum(axis=1, keepdims=True)), iters=it, verbose=False)
        return cost, pos / pos.sum()

    # statistical: the same swarm rules (inertia, constriction, clamp) reach the optimum to the same depth
    f_ours = np.array([-ours(s).fun for s in range(30)])
    f_peer = np.array([peer(s)[0] for s in range(30)])
    lo, hi = np.median(np.log10(f_ours + 1e-300)), np.median(np.log10(f_peer + 1e-300))
    print(f"  swarm: median log10 of the final gap to the optimum over 30 seeds: ours {lo:.2f}, pyswarms {hi:.2f}")
    ok = max(f_ours.max(), f_peer.max()) < 1e-4 and abs(lo - hi) < 1.5
    row("swarm_one", f"particle swarm, {n} particles x {it} iterations, cheap fitness (3-D simplex)", "single",
        "pyswarms", pyswarms.__version__, lambda: ours(1), lambda: peer(1), "statistical", abs(lo - hi), ok)
    B = 20

    def batch_fit(active: np.ndarray, eps: np.ndarray) -> np.ndarray:
        return -np.sum((eps - target) ** 2, axis=-1)

    row("swarm_20", f"particle swarm, {B} problems (ours: one batch)", "batched", "pyswarms", pyswarms.__version__,
        lambda: particle_swarm_batch(batch_fit, dim, [np.random.default_rng(s) for s in range(B)], n_particles=n,
                                     iterations=it, patience=it),
        lambda: [peer(s) for s in range(B)], "statistical", abs(lo - hi), ok)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--peers", required=True, help="the side environment (a venv) holding the peers")
    ap.add_argument("--only", nargs="*", default=None,
                    help="ci kalman pf em swarm (default: all); a partial run replaces only its rows in peers.json")
    args = ap.parse_args()
    load = os.getloadavg()
    site = glob.glob(os.path.join(args.peers, "lib", "python*", "site-packages"))
    if not site:
        sys.exit(f"no site-packages under {args.peers}")
    sys.path.append(site[0])  # behind this environment: the locked numpy/scipy/filterpy win
    groups = {"ci": ci_rows, "kalman": kalman_rows, "pf": pf_rows, "em": em_rows, "swarm": swarm_rows}
    import threadpoolctl

    # one BLAS/OpenMP thread on both sides: on a shared 2-core machine a second thread mostly waits (a
    # scikit-learn fit then varies from 36 ms to 1 s), and the book runs one process per core
    with threadpoolctl.threadpool_limits(1), tempfile.TemporaryDirectory() as tmp, contextlib.chdir(tmp):
        for name in args.only or list(groups):  # (in a scratch folder: pyswarms writes report.log to the cwd)
            groups[name]()

    blas = [f"{p['internal_api']} {p['version']} ({p.get('architecture')}, {p['num_threads']} threads)"
            for p in threadpoolctl.threadpool_info() if p.get("user_api") == "blas"]
    rows, extra = ROWS, {}
    if args.only:  # a partial re-run: its rows replace theirs in the stored record, the other rows are kept
        rows, extra = _merged_rows(ROWS, args.only, load)
    measurements = [{"key": r["key"], "what": f"{r['what']}: peer/ours ({r['peer']})", "value": r["ratio"],
                     "unit": "x"} for r in rows]
    write_results("peers", measurements, repeats=REPEATS, statistic="median of interleaved repeats (process CPU time, one thread)", blas=blas,
                  load_average_at_start=extra.pop("load_average_at_start", load), rows=rows, **extra)


def _merged_rows(new_rows: list[dict], groups: list[str], load: tuple[float, float, float]) -> tuple[list[dict], dict]:
    """The stored rows with those of ``new_rows`` replaced (by key, in the stored order; new keys appended), and the
    record's fields to keep: the first run's load average, and ``partial_reruns`` (each re-run's groups, date and
    load average at its start), so that a reader sees which rows were timed when."""
    import datetime
    import json

    path = Path(__file__).resolve().parent / "results" / "peers.json"
    if not path.exists():
        return new_rows, {}
    old = json.loads(path.read_text(encoding="utf-8"))
    fresh = {r["key"]: r for r in new_rows}
    rows = [fresh.pop(r["key"], r) for r in old.get("rows", [])] + list(fresh.values())
    reruns = list(old.get("partial_reruns", [])) + [{"groups": list(groups), "date": datetime.date.today().isoformat(),
                                                     "load_average_at_start": list(load)}]
    return rows, {"load_average_at_start": old.get("load_average_at_start", list(load)), "partial_reruns": reruns}


if __name__ == "__main__":
    main()
