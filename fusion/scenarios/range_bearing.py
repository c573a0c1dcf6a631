r"""Distributed tracking with range-bearing sensor nodes: the designed scenario of chapter 06.

The patent (CN107330468B) gives no scenario, parameters or results. This module runs the one the
chapter designs: :math:`N` range-bearing sensors around a target with nearly-constant-velocity
motion; every node runs a bootstrap particle filter (step B), fits a Gaussian mixture to its
weighted particles by weighted EM (step C) and broadcasts it; the fusion (steps D-I,
:func:`fusion.estimates.chernoff.fuse_mixtures`) is computed alongside simple baselines and a centralised
particle filter, and :func:`posterior_crb` gives the floor.

The local filters never see the fused result (no feedback: the patent is silent on it).

References
----------
* Oudjane, N., & Musso, C. (2000). Progressive correction for regularized particle filters. In
  *Proceedings of the 3rd International Conference on Information Fusion (FUSION 2000)*, Paris.
"""

from __future__ import annotations

import multiprocessing
import time
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from fusion._frozen import freeze_arrays
from fusion._timing import LapTimer
from fusion._validation import seed as check_seed
from fusion._validation import (sequence, _numeric, FloatArray, as_array, as_rng, count, instance_of, one_of, positive_scalar,
                                scalar, std_scalar)
# the batched kernels of the package (private: array-level, validated by the callers here)
from fusion.estimates.chernoff.gaussian import _ci_criterion_batch, _gaussian_chernoff_batch, _product_terms
from fusion.estimates.chernoff.mixture import _foa_minimum, _fuse_arrays, _moments_batch
from fusion.estimates.mixtures import _em_arrays, _features, _mixture_logpdf_features
from fusion.filtering.kalman import nees
from fusion.filtering.particles import _log_likelihood, _systematic_resample, ncv_model, range_bearing
from fusion.optimise.swarm import check_swarm_options

__all__ = ["GUARD_STAGES", "RUN_BLOCK", "READING_METHODS", "SimulatedTarget", "RangeBearingScenario", "TrackingRun", "METHODS", "simulate_target", "run_tracking", "run_tracking_batch", "posterior_crb", "LinearisedErrors", "linearised_errors",
           "monte_carlo", "position_sq_errors", "nees_per_frame", "min_local_ess", "method_keys"]

#: Tempering steps of the collapse guard (``RangeBearingScenario.guard``).
GUARD_STAGES = 10

#: Methods compared in the scenario: key -> display label.
METHODS: dict[str, str] = {
    "local1": "local PF, sensor 1",
    "local2": "local PF, sensor 2",
    "local3": "local PF, sensor 3",
    "mean_of_means": "mean of local means",
    "naive_product": "naive product, ε = (1, 1, 1)",
    "ci_gaussian": "CI of moment-matched Gaussians, Chernoff ε",
    "ci_det": "CI of moment-matched Gaussians, min det P",
    "ci_trace": "CI of moment-matched Gaussians, min trace P",
    "foa_uniform": "FOA mixture g at uniform ε (step D only)",
    "chernoff_uniform": "Chernoff IS at uniform ε (no steps F-G)",
    "chernoff_pso": "Chernoff-PSO (patent, steps B-I)",
    "chernoff_slsqp": "Chernoff with SLSQP (same samples)",
    "chernoff_redraw": "Chernoff-PSO, samples redrawn at ε*",
    "chernoff_prev": "Chernoff, ε⁽⁰⁾ = previous ε*",
    "chernoff_foa0": "Chernoff, ε⁽⁰⁾ = argmin Z_FOA, min Ĵ",
    "chernoff_foa": "Chernoff IS at ε = argmin Z_FOA (no swarm)",
    "chernoff_literal": "Chernoff-PSO, G6 as worded (positions converge)",
    "centralised": "centralised PF (all measurements)",
}


@dataclass(frozen=True)
class RangeBearingScenario:
    """Parameters of the designed scenario (the patent gives none).

    Units: metres, seconds, radians (``sigma_theta``). State :math:`[x, \\dot x, y, \\dot y]`.

    Attributes
    ----------
    sensors : tuple of (float, float)
        Sensor positions (m); one particle filter (node) per sensor.
    sigma_r : float
        Range noise standard deviation (m).
    sigma_theta : float
        Bearing noise standard deviation (rad; 2 degrees by default).
    T : float
        Frame period (s).
    q : float
        Acceleration power spectral density of the NCV model (m²/s³), see
        :func:`fusion.filtering.particles.ncv_model`.
    x0 : (float, float, float, float)
        True initial state (m, m/s).
    p0_std : (float, float, float, float)
        Prior standard deviations of the state; ``P0`` is their squared diagonal.
    frames : int
        Number of frames K.
    n_particles : int
        Particles per local filter.
    n_components : int
        Gaussian-mixture components fitted by EM to each local posterior.
    n_samples : int
        Importance samples of the Chernoff fusion (patent step E).
    n_central : int
        Particles of the centralised reference filter.
    em_iterations : int
        EM iteration limit.
    regularised : bool
        Jitter resampled particles (:func:`fusion.filtering.particles.regularise`).
    n_initial : int
        Particles each node draws from the prior for its first update (0: ``n_particles``). When
        larger than ``n_particles``, the node resamples (and jitters) them down to ``n_particles``
        right after the first weighting, before its mixture fit: a guard against the collapse of
        the first update, whose likelihood is much narrower than the prior (chapter 06).
    guard : float
        Collapse guard of the local filters (0: none). When a node's effective sample size after
        weighting falls below ``guard`` times its particle count, the node redoes that update by
        progressive correction (Oudjane & Musso 2000): the likelihood is applied in
        :data:`GUARD_STAGES` equal tempering steps, with systematic resampling and regularisation
        between them. A run in which no node falls below the threshold is identical to the
        unguarded one (the guard draws nothing otherwise).
    central_guard : float
        The same guard for the centralised filter (0: none), with its own generator and every sensor's
        likelihood; recorded in ``TrackingRun.guarded`` as node -1.
    variants : bool
        Compute the variants ``chernoff_slsqp``, ``chernoff_redraw`` and ``chernoff_prev`` (False:
        their records are NaN, and the run is about a third cheaper).
    prev_optimiser : {"pso", "newton"}
        Step G of the variant ``chernoff_prev`` (ε⁽⁰⁾ = the previous frame's ε*): the swarm (default), or the
        exact minimum of :math:`\\hat J` by the projected Newton method, which the swarm reaches within its
        sampling error (chapter 06, record ``chf-pso``) at a fraction of the cost. The variant draws from the
        fusion's random stream after the main fusion, so this choice (like ``variants``) moves the samples of every
        fusion method from the second frame on.
    readings : bool
        Also run two readings of steps D and F (chapter 06; off by default: not recorded):
        ``chernoff_foa0``, the initial exponents of step D chosen by minimising the first-order normaliser
        :math:`Z_{\\rm FOA}` (which needs no exponents: no circularity), then steps E-I from its own random
        stream, step G by the exact minimum of :math:`\\hat J` (projected Newton: the swarm's optimum within
        its sampling error, record ``chf-pso``, at a fraction of its cost); ``chernoff_foa``, the same fusion at those exponents without steps F-G; and,
        on the samples of the main fusion, the equal-KL rule (``eps["equal_kl"]``, NaN where it has no
        solution in the simplex); and the patent's stopping rule G6 as worded, ``chernoff_literal``: the
        main swarm is followed to its iteration limit (on a copy of its generator) and its best point
        when the positions have converged (every particle within ``literal_xtol`` of the best) is used on
        the same samples (``swarm_trace`` records the best fitness and the spread after every iteration,
        for any other tolerance). The other methods' results do not change.
    literal_xtol : float
        Position tolerance of the literal stopping rule (``readings``).
    """

    sensors: tuple[tuple[float, float], ...] = ((0.0, 0.0), (2000.0, 0.0), (1000.0, 2000.0))
    sigma_r: float = 10.0
    sigma_theta: float = float(np.deg2rad(2.0))
    T: float = 1.0
    q: float = 0.5
    x0: tuple[float, float, float, float] = (800.0, 15.0, 600.0, 10.0)
    p0_std: tuple[float, float, float, float] = (30.0, 3.0, 30.0, 3.0)
    frames: int = 30
    n_particles: int = 2000
    n_components: int = 3
    n_samples: int = 2000
    n_central: int = 10000
    em_iterations: int = 20
    regularised: bool = True
    n_initial: int = 0
    guard: float = 0.0
    variants: bool = True
    readings: bool = False
    central_guard: float = 0.0
    prev_optimiser: str = "pso"
    literal_xtol: float = 1e-3

    def __post_init__(self) -> None:
        S = _numeric(self.sensors, "sensors")
        if S.ndim != 2 or S.shape[0] < 1 or S.shape[1] != 2:
            raise ValueError(f"sensors must be N >= 1 positions (x, y), shape (N, 2), got {S.shape}")
        if not np.all(np.isfinite(S)):
            raise ValueError("sensors contains NaN or infinite values")
        for name in ("sigma_r", "sigma_theta"):
            std_scalar(getattr(self, name), name)
        for name in ("T", "q"):
            positive_scalar(getattr(self, name), name)
        as_array(self.x0, "x0", shape=(4,))
        p0 = as_array(self.p0_std, "p0_std", shape=(4,))
        if np.any(p0 <= 0):
            raise ValueError("p0_std must be positive")
        for name, least in (("frames", 1), ("n_particles", 2), ("n_components", 1), ("n_samples", 2),
                            ("n_central", 2), ("em_iterations", 1)):
            count(getattr(self, name), name, minimum=least)
        if isinstance(self.n_initial, bool) or not isinstance(self.n_initial, (int, np.integer)):
            raise TypeError(f"n_initial must be an int, got {type(self.n_initial).__name__}")
        if self.n_initial < 0:
            raise ValueError(f"n_initial must be >= 0, got {self.n_initial}")
        instance_of(self.variants, (bool, np.bool_), "variants")
        instance_of(self.readings, (bool, np.bool_), "readings")
        one_of(self.prev_optimiser, ("pso", "newton"), "prev_optimiser")
        positive_scalar(self.literal_xtol, "literal_xtol")
        for name in ("guard", "central_guard"):
            g = _numeric(getattr(self, name), name)
            if g.ndim != 0 or not np.isfinite(g) or not 0.0 <= float(g) < 1.0:
                raise ValueError(f"{name} must be a fraction in [0, 1), got {getattr(self, name)!r}")
            if float(g) != 0.0:
                scalar(float(g), name, 0.0, 1.0, hi_open=True)  # the shared magnitude rule (no subnormal)
        if self.n_components > self.n_particles:
            raise ValueError("n_components must not exceed n_particles")

    @property
    def sensor_array(self) -> FloatArray:
        return np.asarray(self.sensors, dtype=float)

    @property
    def P0(self) -> FloatArray:
        return np.diag(np.asarray(self.p0_std, dtype=float) ** 2)


@dataclass
class TrackingRun:
    """Everything one Monte-Carlo run records (arrays indexed by frame first).

    Attributes
    ----------
    truth : (K, 4)
    estimates : dict key -> (K, 4); keys of :data:`METHODS`
    covariances : dict key -> (K, 4, 4); every method except ``mean_of_means``
    eps : dict {"pso", "slsqp", "prev", "ci_gaussian", "ci_det", "ci_trace", "foa", "equal_kl", "literal"} -> (K, N)
    ess : dict {"pso", "uniform", "redraw", "prev", "foa0", "centralised"} -> (K,);
        ``"local"`` -> (K, N) (before resampling)
    objective : dict {"pso", "slsqp", "literal"} -> (K,)
    swarm_history : (K, n) best fitness after each swarm iteration (padded with the final
        value after an early stop: the swarm stopped after iteration ``evaluations["pso"] / 20 - 1``)
    evaluations : dict {"pso", "slsqp", "literal"} -> (K,)
    gm_loglik : (K, N) weighted log-likelihood of each node's particles under its mixture
    gm1_loglik : (K, N) the same for a single moment-matched Gaussian
    n_fused_components : (K,)
    node_estimates : (K, N, 4) or None, with ``all_nodes=True``: every node's own fusion
    timings : dict stage -> seconds (not deterministic; benchmarks only)
    guarded : tuple of (frame, node), 0-based: the updates redone by the collapse guard
        (``RangeBearingScenario.guard``); node -1 is the centralised filter
    swarm_trace : dict {"fitness", "spread"} -> (K, iterations + 1), or empty
        With ``readings``: the main swarm followed to its iteration limit, best fitness and spread of its
        positions (largest coordinate difference from the best point) after every iteration
        (:class:`fusion.optimise.result.SwarmTrace`)
    """

    truth: FloatArray
    estimates: dict[str, FloatArray]
    covariances: dict[str, FloatArray]
    eps: dict[str, FloatArray]
    ess: dict[str, FloatArray]
    objective: dict[str, FloatArray]
    swarm_history: FloatArray
    evaluations: dict[str, FloatArray]
    gm_loglik: FloatArray
    gm1_loglik: FloatArray
    n_fused_components: FloatArray
    node_estimates: FloatArray | None
    timings: dict[str, float] = field(default_factory=dict)
    guarded: tuple[tuple[int, int], ...] = ()
    swarm_trace: dict[str, FloatArray] = field(default_factory=dict)


@dataclass(frozen=True)
class SimulatedTarget:
    """One simulated target: true states, readings and the shared prior mean.

    Arrays are read-only.

    Attributes
    ----------
    truth : ndarray, shape (K, 4)
        True states (m, m/s).
    z : ndarray, shape (K, N, 2)
        Range (m) and bearing (rad, in (-pi, pi]) of each sensor at each frame.
    m0 : ndarray, shape (4,)
        Prior mean shared by all filters.
    """

    truth: FloatArray
    z: FloatArray
    m0: FloatArray

    __post_init__ = freeze_arrays


def simulate_target(sc: RangeBearingScenario, rng: np.random.Generator) -> SimulatedTarget:
    """Truth, measurements and the shared prior mean of one run.

    The truth starts at ``x0`` and follows the NCV model with process noise; the prior mean
    is :math:`m_0 = x_0 + P_0^{1/2}\\xi`; frame :math:`k = 1..K` is measured by every sensor with
    independent range-bearing noise.

    Parameters
    ----------
    sc : RangeBearingScenario
        The scenario.
    rng : numpy.random.Generator
        Draws the process noise, the prior mean and the measurement noise.

    Returns
    -------
    SimulatedTarget
        ``truth``, ``z`` and ``m0``.
    """
    instance_of(sc, RangeBearingScenario, "sc")
    as_rng(rng)
    model = ncv_model(sc.T, sc.q)
    F, Q = model.F, model.Q
    LQ = np.linalg.cholesky(Q)
    x = np.asarray(sc.x0, dtype=float)
    m0 = x + np.asarray(sc.p0_std) * rng.standard_normal(4)
    truth = np.empty((sc.frames, 4))
    for k in range(sc.frames):
        x = F @ x + LQ @ rng.standard_normal(4)
        truth[k] = x
    S = sc.sensor_array
    h = np.stack([range_bearing(truth, s) for s in S], axis=1)  # (K, N, 2)
    noise = rng.standard_normal(h.shape) * [sc.sigma_r, sc.sigma_theta]
    z = h + noise
    z[..., 1] = np.angle(np.exp(1j * z[..., 1]))
    return SimulatedTarget(truth=truth, z=z, m0=m0)


#: Runs advanced together by :func:`run_tracking_batch` (memory and cache; results do not depend on it).
RUN_BLOCK = 20


def run_tracking(
    sc: RangeBearingScenario,
    seed: np.random.SeedSequence,
    all_nodes: bool = False,
    swarm_options: dict[str, float] | None = None,
) -> TrackingRun:
    """One Monte-Carlo run of the scenario: local PFs, every fusion method, centralised PF.

    Independent random streams (spawned from ``seed``) drive the target, each node's filter,
    the fusion and the centralised filter, so that adding a method never changes another.

    Any number of sensors N >= 1 is handled: the local methods are ``local1`` ... ``localN``
    (:func:`method_keys`); with one sensor every fusion returns that sensor's own posterior
    (exponent weight 1). The same as ``run_tracking_batch(sc, [seed], ...)[0]``.

    Parameters
    ----------
    sc : RangeBearingScenario
    seed : numpy.random.SeedSequence
    all_nodes : bool
        Also let every node compute the patent's fusion with its own random stream (they all
        hold the same mixtures under full connectivity), recording ``node_estimates``.
    swarm_options : dict, optional
        Passed to the particle swarm (keys among :data:`~fusion.optimise.swarm.SWARM_OPTIONS`, checked
        by :func:`~fusion.optimise.swarm.check_swarm_options`).

    Returns
    -------
    TrackingRun
    """
    instance_of(sc, RangeBearingScenario, "sc")
    if not isinstance(seed, np.random.SeedSequence):
        raise ValueError("seed must be a numpy.random.SeedSequence")
    return run_tracking_batch(sc, [seed], all_nodes=[bool(all_nodes)], swarm_options=swarm_options)[0]


def run_tracking_batch(
    sc: RangeBearingScenario,
    seeds: list[np.random.SeedSequence],
    all_nodes: list[bool] | None = None,
    swarm_options: dict[str, float] | None = None,
    workers: int = 1,
) -> list[TrackingRun]:
    """Several Monte-Carlo runs advanced together, frame by frame (vectorised across runs and nodes).

    Every stage is one array computation over the runs (and nodes) of a block of :data:`RUN_BLOCK`
    runs: the particle filters, the weighted EM of every node of every run
    (quadratic-feature kernel of :mod:`fusion.estimates.mixtures`), the fusion of steps D-I with its
    swarms advanced together (:func:`fusion.estimates.chernoff.fuse_mixtures_batch`), the baselines
    and the centralised filter; only the random draws (each run's and node's own generator, in a
    fixed order), the resampling searches and the SLSQP solves loop over runs. Run ``r`` gives
    exactly what ``run_tracking(sc, seeds[r])`` gives, digit for digit (every per-run computation is
    elementwise or one small factorisation or product per run, reductions never mix runs; tested),
    whatever the other runs and the block size.

    Parameters
    ----------
    sc : RangeBearingScenario
    seeds : list of numpy.random.SeedSequence
        One per run (non-empty).
    all_nodes : list of bool, optional
        Per run, as ``all_nodes`` of :func:`run_tracking` (default: False for every run).
    swarm_options : dict, optional
        Passed to the particle swarm (keys among :data:`~fusion.optimise.swarm.SWARM_OPTIONS`, checked
        by :func:`~fusion.optimise.swarm.check_swarm_options`).
    workers : int
        Processes that share the blocks of runs (1: this process). Each block is computed as it would
        be here, so the result does not depend on it.

    Returns
    -------
    list of TrackingRun, one per seed
    """
    instance_of(sc, RangeBearingScenario, "sc")
    instance_of(seeds, (list, tuple), "seeds")
    workers = count(workers, "workers")
    if not seeds:
        raise ValueError("seeds is empty: at least one SeedSequence is needed")
    for s in seeds:
        if not isinstance(s, np.random.SeedSequence):
            raise ValueError("seeds must hold numpy.random.SeedSequence objects")
    flags = [False] * len(seeds) if all_nodes is None else [bool(f) for f in sequence(all_nodes, "all_nodes")]
    if len(flags) != len(seeds):
        raise ValueError(f"all_nodes must have {len(seeds)} entries (one per seed), got {len(flags)}")
    swarm_options = check_swarm_options(swarm_options)
    # blocks of at most RUN_BLOCK runs, as many as a multiple of the workers and of equal sizes (within one),
    # so that no worker waits for another's last block (the runs' results do not depend on the blocks)
    n_blocks = -(-len(seeds) // RUN_BLOCK)
    if workers > 1:
        n_blocks = -(-n_blocks // workers) * workers
    size = -(-len(seeds) // n_blocks)
    blocks = [(sc, list(seeds[j:j + size]), flags[j:j + size], swarm_options) for j in range(0, len(seeds), size)]
    if workers > 1 and len(blocks) > 1:
        methods = multiprocessing.get_all_start_methods()
        ctx = multiprocessing.get_context("fork" if "fork" in methods else methods[0])
        with ProcessPoolExecutor(max_workers=min(workers, len(blocks)), mp_context=ctx) as pool:
            parts = list(pool.map(_run_block, blocks))
    else:
        parts = [_run_block(b) for b in blocks]
    return [r for part in parts for r in part]


def _run_block(args: tuple[RangeBearingScenario, list[np.random.SeedSequence], list[bool], dict[str, float] | None]
               ) -> list[TrackingRun]:
    """One block of runs (a process-pool task of :func:`run_tracking_batch`)."""
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

    def __init__(self, sc: RangeBearingScenario, seeds: list[np.random.SeedSequence], flags: list[bool],
                 swarm_options: dict[str, float] | None) -> None:
        self.timings: dict[str, float] = {}
        clock = LapTimer(self.timings)
        N, B, K = len(sc.sensors), len(seeds), sc.frames
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
        for seed in seeds:
            s_target, s_nodes, s_fusion, s_central, s_extra, s_read = seed.spawn(6)  # the 6th: the readings
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
        self.cov = {k: np.empty((B, K, 4, 4)) for k in keys if k != "mean_of_means"}
        extra = ("foa", "equal_kl", "literal") if sc.readings else ()
        self.eps = {k: np.full((B, K, N), np.nan) for k in ("pso", "slsqp", "prev", "ci_gaussian", "ci_det", "ci_trace")
                    + extra}
        self.ess = {k: np.full((B, K), np.nan)
                    for k in ("pso", "uniform", "redraw", "prev") + (("foa0",) if sc.readings else ()) + ("centralised",)}
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
        return [TrackingRun(truth=self.truth[b], estimates={k: v[b].copy() for k, v in self.est.items()},
                            covariances={k: v[b].copy() for k, v in self.cov.items()},
                            eps={k: v[b].copy() for k, v in self.eps.items()},
                            ess={k: v[b].copy() for k, v in self.ess.items()},
                            objective={k: v[b].copy() for k, v in self.obj.items()},
                            swarm_history=_pad_histories(self.history[b]),
                            evaluations={k: v[b].copy() for k, v in self.evals.items()},
                            gm_loglik=self.gm_ll[b].copy(), gm1_loglik=self.gm1_ll[b].copy(),
                            n_fused_components=self.n_fused[b].copy(),
                            node_estimates=self.nodes[b].copy() if self.flags[b] else None,
                            timings={k: v / B for k, v in self.timings.items()}, guarded=tuple(self.guarded[b]),
                            swarm_trace={k: v[b].copy() for k, v in self.trace.items()})
                for b in range(B)]

    def frame(self, k: int) -> None:
        sc, N, B, F, LQ = self.sc, self.N, self.B, self.F, self.LQ
        est, cov, eps, ess = self.est, self.cov, self.eps, self.ess
        clock = LapTimer(self.timings)
        # ---- step B: predict and weight every node's particles
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
        clock.lap("particle filters")
        # ---- step C: weighted EM of every node of every run, one array problem
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
        clock.lap("EM")
        # ---- Gaussian baselines from the moment-matched local posteriors
        means = np.stack([est[f"local{i + 1}"][:, k] for i in range(N)], axis=1)
        covs = np.stack([cov[f"local{i + 1}"][:, k] for i in range(N)], axis=1)
        est["mean_of_means"][:, k] = means.mean(axis=1)
        infos, logdets = np.linalg.inv(covs), np.linalg.slogdet(2 * np.pi * covs)[1]
        nx, nP, _ = _product_terms(means[:, None], infos[:, None], logdets[:, None], np.ones((B, N)))
        est["naive_product"][:, k], cov["naive_product"][:, k] = nx[:, 0], nP[:, 0]
        e_ci = _gaussian_chernoff_batch(means, infos, logdets)
        cx, cP, _ = _product_terms(means[:, None], infos[:, None], logdets[:, None], e_ci)
        est["ci_gaussian"][:, k], cov["ci_gaussian"][:, k], eps["ci_gaussian"][:, k] = cx[:, 0], cP[:, 0], e_ci
        for crit in ("det", "trace"):  # the practitioner's covariance intersection (Julier & Uhlmann)
            e_c = _ci_criterion_batch(infos, crit)
            cx, cP, _ = _product_terms(means[:, None], infos[:, None], logdets[:, None], e_c)
            est[f"ci_{crit}"][:, k], cov[f"ci_{crit}"][:, k], eps[f"ci_{crit}"][:, k] = cx[:, 0], cP[:, 0], e_c
        clock.lap("Gaussian baselines")
        # ---- steps D-I (the patent), with SLSQP on the same samples and the redrawn variant
        fus = _fuse_arrays(logw, gmu, gP, self.rng_f, sc.n_samples, np.full((B, N), 1.0 / N), "pso", sc.variants,
                           sc.variants, self.so, self.timings, equal_kl=sc.readings,
                           literal_xtol=sc.literal_xtol if sc.readings else None)
        clock.t = time.perf_counter()
        for b, fu in enumerate(fus):
            est["chernoff_pso"][b, k], cov["chernoff_pso"][b, k] = fu.x, fu.P
            est["chernoff_uniform"][b, k], cov["chernoff_uniform"][b, k] = fu.x_eps0, fu.P_eps0
            est["foa_uniform"][b, k], cov["foa_uniform"][b, k] = fu.x_foa, fu.P_foa
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
        if sc.readings:  # step D's exponents by minimising Z_FOA (own stream); step F as the equal-KL rule
            e_foa = _foa_minimum(logw, gmu, gP)
            frs = _fuse_arrays(logw, gmu, gP, self.rng_r, sc.n_samples, e_foa, "newton", False, False, None, None)
            for b, fr in enumerate(frs):
                est["chernoff_foa0"][b, k], cov["chernoff_foa0"][b, k] = fr.x, fr.P
                est["chernoff_foa"][b, k], cov["chernoff_foa"][b, k] = fr.x_eps0, fr.P_eps0
                ess["foa0"][b, k] = fr.ess
                eps["equal_kl"][b, k] = fus[b].eps_equal_kl
            eps["foa"][:, k] = e_foa
        flagged = [b for b in range(B) if self.flags[b]]
        if flagged:  # every node fuses on its own, with its own stream
            rep = np.repeat(flagged, N)
            fn = _fuse_arrays(logw[rep], gmu[rep], gP[rep], [self.rng_x[b][i] for b in flagged for i in range(N)],
                              sc.n_samples, np.full((rep.size, N), 1.0 / N), "pso", False, False, self.so, None)
            for j, b in enumerate(rep):
                self.nodes[b, k, j % N] = fn[j].x
        clock.lap("variants")
        # ---- centralised bootstrap PF on all measurements
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
        ess["centralised"][:, k] = 1.0 / np.sum(wc**2, axis=-1)
        mc, Pc = _moments(C, wc)
        est["centralised"][:, k], cov["centralised"][:, k] = mc, Pc
        C = np.stack([C[b][_systematic_resample(wc[b], self.rng_c[b])] for b in range(B)])
        if sc.regularised:
            C = _regularise_batch(C, Pc, self.rng_c)
        self.central = C
        # ---- resampling of the local filters (after the mixture fit)
        if not resampled:
            pairs = [(b, i) for b in range(B) for i in range(N)]
            Xr = np.stack([X[b, i][_systematic_resample(w[b, i], self.rng_nodes[b][i])] for b, i in pairs])
            if sc.regularised:
                Xr = _regularise_batch(Xr, c_loc.reshape(B * N, 4, 4), [self.rng_nodes[b][i] for b, i in pairs])
            self.particles = Xr.reshape(X.shape)
        clock.lap("centralised PF and resampling")

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


#: Methods computed only with ``RangeBearingScenario.readings``.
READING_METHODS = ("chernoff_foa0", "chernoff_foa", "chernoff_literal")


def method_keys(n_sensors: int, readings: bool = False) -> list[str]:
    """Keys of :attr:`TrackingRun.estimates` for ``n_sensors`` sensors.

    Parameters
    ----------
    n_sensors : int
        Number of sensor nodes, at least one.
    readings : bool
        Include the readings of steps D, F and G6 (:data:`READING_METHODS`, ``RangeBearingScenario.readings``).

    Returns
    -------
    list of str
        One local filter per sensor (``local1`` ...), then the fusion methods and the centralised
        filter, in the order of :data:`METHODS`.
    """
    n_sensors = count(n_sensors, "n_sensors")
    instance_of(readings, (bool, np.bool_), "readings")
    return [f"local{i + 1}" for i in range(n_sensors)] + [k for k in METHODS if not k.startswith("local")
                                                           and (readings or k not in READING_METHODS)]


def _pad_histories(history: list[FloatArray]) -> FloatArray:
    """Stack swarm histories of different lengths (early stopping), repeating the final value."""
    n = max(h.size for h in history)
    return np.stack([np.pad(h, (0, n - h.size), mode="edge") for h in history])


def posterior_crb(sc: RangeBearingScenario, truths: ArrayLike) -> FloatArray:
    r"""Posterior Cramér-Rao bound of the centralised problem (Tichavský et al. 1998).

    For linear-Gaussian motion and additive Gaussian measurement noise the information
    recursion is

    .. math:: J_k = (Q + F J_{k-1}^{-1} F^\top)^{-1} + \sum_i \mathbb E\bigl[H_i(x_k)^\top R^{-1} H_i(x_k)\bigr],
              \qquad J_0 = P_0^{-1},

    with :math:`H_i` the Jacobian of sensor i's range-bearing function; the expectation is the
    average over the given true trajectories (Monte-Carlo runs).

    Parameters
    ----------
    sc : RangeBearingScenario
        Model, sensors and noise levels.
    truths : array_like, shape (runs, K, 4)
        True trajectories over which the expectation is averaged.

    Raises
    ------
    ValueError
        Bad ``truths``, or a true position exactly on a sensor (range 0: the bearing and its
        Jacobian are undefined, so the bound does not exist).

    Returns
    -------
    ndarray, shape (K, 4, 4)
        :math:`J_k^{-1}`; the position RMSE bound is
        :math:`\sqrt{[J_k^{-1}]_{00} + [J_k^{-1}]_{22}}`.

    Raises
    ------
    ValueError
        ``truths`` not of shape (runs, K, 4).

    References
    ----------
    * Tichavský, P., Muravchik, C. H., & Nehorai, A. (1998). Posterior Cramér-Rao bounds for
      discrete-time nonlinear filtering. *IEEE Transactions on Signal Processing*, 46(5),
      1386-1396.
    """
    instance_of(sc, RangeBearingScenario, "sc")
    X = as_array(truths, "truths")
    if X.ndim != 3 or X.shape[2] != 4:
        raise ValueError(f"truths must be (runs, K, 4), got {X.shape}")
    for i, s in enumerate(sc.sensor_array):
        if np.any((X[..., 0] == s[0]) & (X[..., 2] == s[1])):
            raise ValueError(f"truths: a true position coincides with sensor {i + 1}; the bearing and its "
                             "Jacobian are undefined there, so the bound does not exist")
    model = ncv_model(sc.T, sc.q)
    F, Q = model.F, model.Q
    Rinv = np.diag([sc.sigma_r**-2, sc.sigma_theta**-2])
    J = np.linalg.inv(sc.P0)
    out = np.empty((X.shape[1], 4, 4))
    for k in range(X.shape[1]):
        info = np.zeros((4, 4))
        for s in sc.sensor_array:
            dx, dy = X[:, k, 0] - s[0], X[:, k, 2] - s[1]
            r2 = dx**2 + dy**2
            r = np.sqrt(r2)
            H = np.zeros((X.shape[0], 2, 4))
            H[:, 0, 0], H[:, 0, 2] = dx / r, dy / r
            H[:, 1, 0], H[:, 1, 2] = -dy / r2, dx / r2
            info += np.einsum("rai,ab,rbj->ij", H, Rinv, H) / X.shape[0]
        J = np.linalg.inv(Q + F @ np.linalg.inv(J) @ F.T) + info
        out[k] = np.linalg.inv(J)
    return out


@dataclass(frozen=True)
class LinearisedErrors:
    r"""Exact error covariances of linearised local filters and of their naive product (per frame).

    Attributes
    ----------
    nees_naive : ndarray, shape (K,)
        Expected NEES (4-D) of the naive product: :math:`\operatorname{tr}(J C)` with
        :math:`J = \sum_i P_{ii}^{-1}` its claimed information and :math:`C` its true error covariance;
        4 for a consistent estimator.
    corr_position, corr_velocity : ndarray, shape (K,)
        Correlation of two nodes' errors, averaged over the node pairs and the two axes.
    rmse_uniform : ndarray, shape (K,)
        Position RMSE (m) of the naive product's mean (= CI of the nodes' Gaussians at uniform exponents).
    rmse_best : ndarray, shape (K,)
        Position RMSE (m) of the best linear unbiased combination of the local estimates, which knows the
        cross-covariances.
    rmse_central : ndarray, shape (K,)
        Position RMSE (m) of the linearised centralised filter.
    """

    nees_naive: FloatArray
    corr_position: FloatArray
    corr_velocity: FloatArray
    rmse_uniform: FloatArray
    rmse_best: FloatArray
    rmse_central: FloatArray

    def __post_init__(self) -> None:
        freeze_arrays(self)


def linearised_errors(sc: RangeBearingScenario, common_prior: bool = True,
                      common_process: bool = True) -> LinearisedErrors:
    r"""Cross-covariances of the nodes' errors for Kalman filters linearised at the nominal trajectory.

    Each node :math:`i` runs an extended Kalman filter linearised at the noise-free trajectory from ``sc.x0``
    (gain :math:`K_i`, :math:`A_i = I - K_iH_i`). The errors of nodes :math:`i` and :math:`j` have the exact
    cross-covariance (Bar-Shalom & Campo 1986)

    .. math:: P_{ij} \leftarrow A_i(FP_{ij}F^	op + Q)A_j^	op + \delta_{ij}K_iRK_i^	op ,
              \qquad P_{ij}(0) = P_0 ,

    since the nodes share the prior error and the target's process noise and have independent measurement
    noise. The naive product has mean :math:`J^{-1}\sum_iP_{ii}^{-1}\hat x_i`, :math:`J = \sum_iP_{ii}^{-1}`,
    and true error covariance :math:`C = J^{-1}\bigl(\sum_{ij}P_{ii}^{-1}P_{ij}P_{jj}^{-1}\bigr)J^{-1}`; its
    expected NEES is :math:`\operatorname{tr}(JC)`, 4 when the errors are independent. The counterfactual
    switches drop one shared source from the cross terms (``common_prior=False``: :math:`P_{ij}(0) = 0`;
    ``common_process=False``: :math:`Q` only for :math:`i = j`) to attribute the excess. No sampling.

    Parameters
    ----------
    sc : RangeBearingScenario
        Model, sensors, noise levels, prior and frames.
    common_prior, common_process : bool
        Whether the nodes share the prior error and the process noise (both ``True``: the scenario).

    Returns
    -------
    LinearisedErrors

    Raises
    ------
    TypeError
        ``sc`` not a :class:`RangeBearingScenario`, or a switch not a bool.

    References
    ----------
    * Bar-Shalom, Y., & Campo, L. (1986). The effect of the common process noise on the two-sensor fused-track
      covariance. *IEEE Transactions on Aerospace and Electronic Systems*, AES-22(6), 803-805.
    """
    instance_of(sc, RangeBearingScenario, "sc")
    instance_of(common_prior, bool, "common_prior")
    instance_of(common_process, bool, "common_process")
    model = ncv_model(sc.T, sc.q)
    F, Q = model.F, model.Q
    S = sc.sensor_array
    n = len(S)
    R = np.diag([sc.sigma_r**2, sc.sigma_theta**2])
    eye = np.eye(4)
    P = np.array([[sc.P0 if (i == j or common_prior) else np.zeros((4, 4)) for j in range(n)] for i in range(n)])
    Qx = np.array([[Q if (i == j or common_process) else np.zeros((4, 4)) for j in range(n)] for i in range(n)])
    Pc = sc.P0.copy()
    x = np.asarray(sc.x0, dtype=float)
    out = {k: np.empty(sc.frames) for k in ("nees", "cp", "cv", "ru", "rb", "rc")}
    iu = np.triu_indices(n, 1)
    stack = np.vstack([eye] * n)
    for k in range(sc.frames):
        x = F @ x
        Pp = np.einsum("ab,ijbc,dc->ijad", F, P, F) + Qx
        dx, dy = x[0] - S[:, 0], x[2] - S[:, 1]
        r2 = dx**2 + dy**2
        H = np.zeros((n, 2, 4))
        H[:, 0, 0], H[:, 0, 2] = dx / np.sqrt(r2), dy / np.sqrt(r2)
        H[:, 1, 0], H[:, 1, 2] = -dy / r2, dx / r2
        Kg = np.stack([Pp[i, i] @ H[i].T @ np.linalg.inv(H[i] @ Pp[i, i] @ H[i].T + R) for i in range(n)])
        A = eye - Kg @ H
        P = np.einsum("iab,ijbc,jdc->ijad", A, Pp, A)
        for i in range(n):
            P[i, i] += Kg[i] @ R @ Kg[i].T
        Hc = H.reshape(2 * n, 4)
        Pc = F @ Pc @ F.T + Q
        Kc = Pc @ Hc.T @ np.linalg.inv(Hc @ Pc @ Hc.T + np.kron(np.eye(n), R))
        Pc = (eye - Kc @ Hc) @ Pc
        Ji = np.linalg.inv(P[np.arange(n), np.arange(n)])
        Jinv = np.linalg.inv(Ji.sum(axis=0))
        C = Jinv @ np.einsum("iab,ijbc,jcd->ad", Ji, P, Ji) @ Jinv
        out["nees"][k] = np.trace(np.linalg.solve(Jinv, C))
        d = np.array([[np.diag(P[i, j]) for j in range(n)] for i in range(n)])  # (n, n, 4) variances/covariances
        corr = d[iu] / np.sqrt(d[iu[0], iu[0]] * d[iu[1], iu[1]])
        out["cp"][k] = corr[:, [0, 2]].mean()
        out["cv"][k] = corr[:, [1, 3]].mean()
        big = P.transpose(0, 2, 1, 3).reshape(4 * n, 4 * n)
        Cb = np.linalg.inv(stack.T @ np.linalg.solve(big, stack))
        out["ru"][k] = np.sqrt(C[0, 0] + C[2, 2])
        out["rb"][k] = np.sqrt(Cb[0, 0] + Cb[2, 2])
        out["rc"][k] = np.sqrt(Pc[0, 0] + Pc[2, 2])
    return LinearisedErrors(out["nees"], out["cp"], out["cv"], out["ru"], out["rb"], out["rc"])


# --------------------------------------------------------------------------- Monte-Carlo study
def _check_runs(runs: object, nonempty: bool) -> None:
    """Check that ``runs`` is a list or tuple of :class:`TrackingRun` (non-empty if asked)."""
    instance_of(runs, (list, tuple), "runs")
    if nonempty and not runs:
        raise ValueError("runs is empty: at least one TrackingRun is needed")
    for i, r in enumerate(runs):  # type: ignore[arg-type]
        instance_of(r, TrackingRun, f"runs[{i}]")


def monte_carlo(sc: RangeBearingScenario, seed: int, runs: int, all_nodes_first: bool = True,
                workers: int = 1) -> list[TrackingRun]:
    """Independent Monte-Carlo runs of :func:`run_tracking` (seeds from ``SeedSequence(seed).spawn``), batched.

    Computed by :func:`run_tracking_batch`, which gives what :func:`run_tracking` gives run by run.

    Parameters
    ----------
    sc : RangeBearingScenario
    seed : int
        Root seed; run ``r`` uses the ``r``-th child of ``numpy.random.SeedSequence(seed)``.
    runs : int
        Number of runs (>= 1).
    all_nodes_first : bool
        Let every node fuse on its own in the first run (``node_estimates`` of run 0).
    workers : int
        Processes sharing the runs (:func:`run_tracking_batch`; the result does not depend on it).

    Returns
    -------
    list of TrackingRun, length ``runs``
    """
    if isinstance(runs, bool) or not isinstance(runs, (int, np.integer)):
        raise TypeError(f"runs must be an int, got {type(runs).__name__}")
    runs = count(runs, "runs")  # >= 1 and at most MAX_COUNT
    instance_of(sc, RangeBearingScenario, "sc")
    seed = check_seed(seed)
    instance_of(all_nodes_first, (bool, np.bool_), "all_nodes_first")
    seeds = np.random.SeedSequence(seed).spawn(int(runs))
    return run_tracking_batch(sc, seeds, all_nodes=[bool(all_nodes_first) and r == 0 for r in range(len(seeds))],
                              workers=workers)


def position_sq_errors(runs: list[TrackingRun], key: str) -> FloatArray:
    """Squared position error :math:`(\\hat x - x)^2 + (\\hat y - y)^2` of one method.

    Parameters
    ----------
    runs : list of TrackingRun
    key : str
        A key of :data:`METHODS`.

    Returns
    -------
    ndarray, shape (runs, K), m²
    """
    _check_runs(runs, nonempty=True)
    one_of(key, tuple(sorted(METHODS)), "key")
    e = np.stack([r.estimates[key] - r.truth for r in runs])
    return e[..., 0] ** 2 + e[..., 2] ** 2


def nees_per_frame(runs: list[TrackingRun], key: str) -> FloatArray:
    """Normalised estimation error squared (4-D state) of one method, per run and frame.

    Parameters
    ----------
    runs : list of TrackingRun
    key : str
        A key of :data:`METHODS` other than ``"mean_of_means"`` (which has no covariance).

    Returns
    -------
    ndarray, shape (runs, K); 4 on average for a consistent estimator
    """
    _check_runs(runs, nonempty=True)
    one_of(key, tuple(sorted(k for k in METHODS if k != "mean_of_means")), "key")
    d = np.stack([r.estimates[key] - r.truth for r in runs])
    return nees(d, np.stack([r.covariances[key] for r in runs]))


def min_local_ess(runs: list[TrackingRun]) -> FloatArray:
    """Smallest effective sample size of any node's particle filter in each run (any frame).

    Parameters
    ----------
    runs : list of TrackingRun
        The Monte-Carlo runs; the minimum is taken over each run's ``ess["local"]``, shape (K, N)
        (ESS before resampling, per frame and node).

    Returns
    -------
    ndarray, shape (runs,)
        Effective particles (of ``n_particles``); empty for no runs.
    """
    _check_runs(runs, nonempty=False)
    return np.array([float(np.min(r.ess["local"])) for r in runs])
