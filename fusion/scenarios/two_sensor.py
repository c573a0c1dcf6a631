r"""The two-sensor 2-D tracking case of Wang & Tang (2024, §3.2), vectorised over runs.

A target on a three-leg path (:func:`trajectory`), two position sensors, a local
constant-velocity Kalman filter per sensor and the centralised filter on both sensors'
measurements (:func:`two_sensor_scenario`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from fusion._frozen import freeze_arrays
from fusion._validation import seed as check_seed, seeds as check_seeds
from fusion._validation import (FloatArray, allocation, as_array, as_covariance, as_rng, as_semidefinite, count,
                                diagonal_covariance, index, instance_of, nonnegative_scalar, one_of, positive_scalar,
                                psd_factor, scalar, solve, std_scalar)
from fusion.estimates.ci import ci_objective, split_ci_objective
from fusion.filtering.kalman import cv_model, filter_runs, gain_sequence, nees, rmse_per_step
from fusion.filtering.tracks import LocalTrack, fuse_tracks, local_track
from fusion.optimise.scalar import fruit_fly, fruit_fly_batch, grid_search

__all__ = ["Trajectory", "trajectory", "model_truth", "Scenario", "two_sensor_scenario", "per_step_weights", "FoaSeeds",
           "foa_over_seeds", "printed_foa_over_seeds", "FusionStudy", "fusion_study", "run_rmse", "nees_study", "floor_by_period",
           "ARCH_RULES", "ArchitectureStudy", "architecture_study", "Q_READINGS", "process_noise", "pcrb_steady",
           "straight_leg_floor", "slip_steps_band", "rmse_variants", "SLIP_STEPS", "SLIP_RUNS", "QScaling", "q_scaling_study",
           "path_by_period"]


@dataclass(frozen=True)
class Trajectory:
    r"""Sample times and true states of the two-sensor target.

    Arrays are read-only.

    Attributes
    ----------
    t : ndarray, shape (K,)
        Sample times (s), spacing ``T``.
    states : ndarray, shape (K, 4)
        True :math:`[x, \dot x, y, \dot y]`.
    """

    t: FloatArray
    states: FloatArray

    __post_init__ = freeze_arrays


def trajectory(
    T: float = 1.0,
    speed: float = 50.0,
    start: tuple[float, float] = (300.0, 0.0),
    legs: tuple[float, float, float] = (100.0, 30.0, 90.0),
    turn_time: float = 20.0,
) -> Trajectory:
    r"""Target of Wang & Tang's (2024) Fig. 3: along +y, turn to +x, along +x, turn to +y, along +y.

    Constant speed; each turn is a coordinated 90° turn at constant rate over ``turn_time``.
    With the defaults (50 m/s, legs 100, 30 and 90 s, turns of 20 s, start (300, 0) m) the
    path stays inside the source's area [0, 3500] × [0, 12000] m.

    Parameters
    ----------
    T : float
        Sampling period (s), > 0.
    speed : float
        Constant speed (m/s), > 0.
    start : (float, float)
        Initial position (m), finite.
    legs : (float, float, float)
        Durations of the three straight legs (s), finite and >= 0 (a leg of length 0: the turns
        follow each other).
    turn_time : float
        Duration of each 90° turn (s), > 0.

    Returns
    -------
    Trajectory
        ``t`` and ``states``.

    Raises
    ------
    ValueError
        ``T``, ``speed`` or ``turn_time`` not positive; ``start`` not two finite numbers; ``legs``
        not three finite non-negative numbers; a path too long to sample.
    TypeError
        ``start`` or ``legs`` not numeric.
    """
    T = positive_scalar(T, "T")
    speed = positive_scalar(speed, "speed")
    turn_time = positive_scalar(turn_time, "turn_time")
    start = _start(start)
    legs = _legs(legs)
    # heading measured from +x; 90° = +y
    seg = [(legs[0], 0.0), (turn_time, -np.pi / 2 / turn_time), (legs[1], 0.0),
           (turn_time, np.pi / 2 / turn_time), (legs[2], 0.0)]
    total = sum(d for d, _ in seg)
    dt = min(T, 0.01)
    allocation((4, int(round(total / dt)) + 1), "T, legs and turn_time")
    n_fine = int(round(total / dt))
    heading = np.empty(n_fine + 1)
    heading[0] = np.pi / 2
    bounds = np.cumsum([0.0] + [d for d, _ in seg])
    fine_t = np.arange(n_fine + 1) * dt
    rate = np.zeros(n_fine + 1)
    for (d, r), a, b in zip(seg, bounds[:-1], bounds[1:]):
        rate[(fine_t >= a) & (fine_t < b)] = r
    heading[1:] = np.pi / 2 + np.cumsum(rate[:-1]) * dt
    vx, vy = speed * np.cos(heading), speed * np.sin(heading)
    x = start[0] + np.concatenate([[0.0], np.cumsum(0.5 * (vx[1:] + vx[:-1]) * dt)])
    y = start[1] + np.concatenate([[0.0], np.cumsum(0.5 * (vy[1:] + vy[:-1]) * dt)])
    t = np.arange(0.0, total + 1e-9, T)
    states = np.column_stack([np.interp(t, fine_t, v) for v in (x, vx, y, vy)])
    return Trajectory(t=t, states=states)


def _start(start: object, name: str = "start") -> tuple[float, float]:
    """A start point: two finite numbers (issue 35, class 7)."""
    a = as_array(start, name, shape=(2,))
    return float(a[0]), float(a[1])


def _legs(legs: object, name: str = "legs") -> tuple[float, float, float]:
    """Durations of the three straight legs: three finite numbers >= 0 (issue 35, class 7)."""
    a = as_array(legs, name, shape=(3,), nonnegative=True)
    return float(a[0]), float(a[1]), float(a[2])


def _path_and_model_measurements(rng: np.random.Generator, X: FloatArray, F: FloatArray, Q: FloatArray,
                                 R1: FloatArray, R2: FloatArray, runs: int, nees_runs: int
                                 ) -> tuple[list[FloatArray], FloatArray]:
    """Both sensors' position measurements: ``runs`` runs of the deterministic path ``X``, then ``nees_runs``
    runs of targets that follow the model (:func:`model_truth`), drawn in that order from ``rng``.

    Returns the measurements of sensor 1 and 2, each of shape (runs + nees_runs, K, 2), and the model
    targets, shape (nees_runs, K, 4).
    """
    K = X.shape[0]
    z_path = [X[None, :, [0, 2]] + rng.standard_normal((runs, K, 2)) * np.sqrt(np.diag(R)) for R in (R1, R2)]
    Xm = model_truth(rng, F, Q, X[0], K, nees_runs)
    z_model = [Xm[:, :, [0, 2]] + rng.standard_normal((nees_runs, K, 2)) * np.sqrt(np.diag(R)) for R in (R1, R2)]
    return [np.concatenate([zp, zm]) for zp, zm in zip(z_path, z_model)], Xm


def model_truth(rng: np.random.Generator, F: ArrayLike, Q: ArrayLike, x0: ArrayLike, n_steps: int, runs: int) -> FloatArray:
    r"""Targets that follow the model: :math:`\mathbf x_{k+1} = F\mathbf x_k + \mathbf w_k`, :math:`\mathbf w_k \sim N(0, Q)`.

    The process noise is common to every sensor watching the target, which is what makes the
    errors of two local filters correlated. ``Q`` may be singular (positive semidefinite, e.g.
    white acceleration on the velocities only); ``x0`` is one state (n,) shared by all runs.

    Parameters
    ----------
    rng : numpy.random.Generator
        Draws the process noise.
    F : array_like, shape (4, 4)
        State transition.
    Q : array_like, shape (4, 4)
        Process-noise covariance, symmetric positive definite (it is Cholesky-factored).
    x0 : array_like, shape (4,)
        Initial state (m, m/s), the same in every run.
    n_steps : int
        Number of steps, including the initial state.
    runs : int
        Number of independent runs.

    Returns
    -------
    ndarray, shape (runs, n_steps, 4)
        True states.

    Raises
    ------
    ValueError
        ``Q`` not a symmetric positive-definite matrix of the size of ``F``.
    """
    as_rng(rng)
    F = as_array(F, "F", ndim=2)
    if F.shape[0] != F.shape[1]:
        raise ValueError(f"F must be square, got shape {F.shape}")
    Q = as_semidefinite(Q, F.shape[0], name="Q")
    x0 = as_array(x0, "x0", shape=(F.shape[0],))
    n_steps, runs = count(n_steps, "n_steps"), count(runs, "runs")
    L = psd_factor(Q)
    out = np.empty((runs, n_steps, F.shape[0]))
    out[:, 0] = x0
    for k in range(1, n_steps):
        out[:, k] = out[:, k - 1] @ F.T + rng.standard_normal((runs, F.shape[0])) @ L.T
    return out



def _central_start(x1: FloatArray, x2: FloatArray, P1: FloatArray, P2: FloatArray,
                   P12: FloatArray) -> tuple[FloatArray, FloatArray]:
    r"""The best linear combination of two initial estimates with cross-covariance ``P12`` (Bar-Shalom & Campo 1986).

    The centralised filter's start: each local filter starts from its sensor's first measurement with
    the *same* zero-velocity prior, so ``P12`` is that common part and it is counted once (fusing the
    two starts as independent would count the velocity prior twice). Returns ``(x, P)``, ``x`` of shape
    (runs, n).
    """
    C = P1 - P12
    D = P1 + P2 - P12 - P12.T
    G = C @ np.linalg.pinv(0.5 * (D + D.T), hermitian=True)
    P = P1 - G @ C.T
    return x1 + (x2 - x1) @ G.T, 0.5 * (P + P.T)


@dataclass(frozen=True)
class Scenario:
    """Wang & Tang's (2024) two-sensor tracking case: truth, both local tracks and the centralised filter.

    Attributes
    ----------
    t : ndarray, shape (K,)
    truth : ndarray, shape (K, 4)
    tracks : tuple of two LocalTrack
    central : LocalTrack
        The centralised Kalman filter on both sensors' measurements (its ``Pd``/``Pi`` are
        not meaningful and set to its covariance and zero); ``central.gains.P`` is the
        posterior Cramér-Rao bound for targets that follow the model.
    """

    t: FloatArray
    truth: FloatArray
    tracks: tuple[LocalTrack, LocalTrack]
    central: LocalTrack



def two_sensor_scenario(
    R_a: ArrayLike, R_b: ArrayLike, Q: ArrayLike, rng: np.random.Generator, runs: int = 50,
    T: float = 1.0, velocity_sigma: float = 100.0,
) -> Scenario:
    """Simulate Wang & Tang's (2024) §3.2 case on the path of :func:`trajectory`, vectorised over runs.

    Each filter starts at its first measurement with zero velocity; the initial covariance is
    ``diag(R[0,0], s^2, R[1,1], s^2)`` with ``s = velocity_sigma`` (m/s). The velocity part is
    common to both sensors (the same unknown target velocity), the position part is each
    sensor's own noise. The centralised filter starts from the best linear combination of the two
    starts given that common part: the positions weighted by their inverse variances, the velocity
    prior counted once.

    Parameters
    ----------
    R_a, R_b : array_like, shape (2, 2)
        Measurement covariances of the two sensors (m²), diagonal.
    Q : array_like, shape (4, 4)
        Process noise used by the filters.
    rng : numpy.random.Generator
        Draws sensor a's noise for all runs, then sensor b's.
    runs : int
        Number of Monte-Carlo runs, >= 1.
    T : float
        Sampling period (s).
    velocity_sigma : float
        Prior standard deviation of each velocity component (m/s).

    Returns
    -------
    Scenario
        Truth, measurements and the two local tracks of every run.

    Raises
    ------
    ValueError
        ``runs`` not positive, ``velocity_sigma`` not positive, covariances not valid.
    """
    as_rng(rng)
    runs = count(runs, "runs")
    traj, model = trajectory(T), cv_model(T)
    t, X, F, H = traj.t, traj.states, model.F, model.H
    s2 = std_scalar(velocity_sigma, "velocity_sigma") ** 2
    tracks = []
    for name, R in (("R_a", R_a), ("R_b", R_b)):
        R = diagonal_covariance(R, 2, name)
        z = X[None, :, [0, 2]] + rng.standard_normal((runs, t.size, 2)) * np.sqrt(np.diag(R))
        x0 = np.column_stack([z[:, 0, 0], np.zeros(runs), z[:, 0, 1], np.zeros(runs)])
        tracks.append(local_track(z, F, H, Q, R, x0, np.diag([0.0, s2, 0.0, s2]), np.diag([R[0, 0], 0.0, R[1, 1], 0.0])))
    a, b = tracks
    Hc = np.vstack([H, H])
    Rc = np.zeros((4, 4))
    Rc[:2, :2], Rc[2:, 2:] = diagonal_covariance(R_a, 2, "R_a"), diagonal_covariance(R_b, 2, "R_b")
    xc0, Pc0 = _central_start(a.est[:, 0], b.est[:, 0], a.gains.P[0], b.gains.P[0], np.diag([0.0, s2, 0.0, s2]))
    gc = gain_sequence(F, Hc, Q, Rc, Pc0, t.size)
    zc = np.concatenate([a.z, b.z], axis=2)
    central = LocalTrack(z=zc, gains=gc, est=filter_runs(zc, gc, xc0), Pd=gc.P, Pi=np.zeros_like(gc.P))
    return Scenario(t=t, truth=X, tracks=(a, b), central=central)



def per_step_weights(a: LocalTrack, b: LocalTrack, seed: int, n_grid: int = 1001,
                     population: int = 30, iterations: int = 200) -> tuple[FloatArray, FloatArray]:
    r"""CI weight chosen at every step by FOA and by exhaustive search (Wang & Tang 2024, Figs. 5-6).

    Both minimise :math:`\operatorname{tr}P(\omega)` of eq. (1) (:func:`fusion.estimates.ci.ci_objective`)
    on the two tracks' covariances at each step. The FOA runs of all steps fly together
    (:func:`fusion.optimise.scalar.fruit_fly_batch`), with the weights :func:`fusion.optimise.scalar.fruit_fly`
    would return step by step.

    Parameters
    ----------
    a, b : LocalTrack
        The two local tracks (covariances ``gains.P`` of shape (K, n, n)).
    seed : int
        FOA at step ``k`` uses ``numpy.random.default_rng(seed + k)``.
    n_grid : int
        Points of the exhaustive search on [0, 1].
    population, iterations : int
        FOA swarm size and generations (30 × 200 in the source).

    Returns
    -------
    w_foa, w_grid : ndarray, shape (K,)
        Weights (dimensionless, in [0, 1]).
    """
    instance_of(a, LocalTrack, "a")
    instance_of(b, LocalTrack, "b")
    seed = check_seed(seed)
    n_grid = count(n_grid, "n_grid", minimum=2)
    population = count(population, "population")
    iterations = count(iterations, "iterations")
    if a.gains.P.shape != b.gains.P.shape:
        raise ValueError(f"the tracks must have the same covariance shape, got {a.gains.P.shape} and {b.gains.P.shape}")
    K = a.gains.P.shape[0]
    P1s, P2s = np.asarray(a.gains.P, dtype=float), np.asarray(b.gains.P, dtype=float)
    I1s, I2s = np.linalg.inv(P1s), np.linalg.inv(P2s)

    def swarms(w: FloatArray) -> FloatArray:   # ci_objective of every step's swarm, row k on step k's pair
        info = w[..., None, None] * I1s[:, None] + (1.0 - w[..., None, None]) * I2s[:, None]
        return np.trace(np.linalg.inv(info), axis1=-2, axis2=-1)

    found = fruit_fly_batch(swarms, [np.random.default_rng(seed + k) for k in range(K)], population=population,
                            iterations=iterations)
    w_foa = np.array([r.x for r in found])
    w_grid = np.empty(K)
    for k in range(K):
        P1, P2 = P1s[k], P2s[k]

        def objective(w: ArrayLike, P1: FloatArray = P1, P2: FloatArray = P2) -> FloatArray:
            return ci_objective(w, P1, P2)

        w_grid[k] = grid_search(objective, n_grid, vectorized=True).x
    return w_foa, w_grid


@dataclass(frozen=True)
class FoaSeeds:
    r"""FOA repeated over seeds against one exhaustive search, on one CI objective (:func:`foa_over_seeds`).

    Attributes
    ----------
    seeds : ndarray of int, shape (S,)
        Seed of each FOA run.
    foa_x, foa_fun : ndarray, shape (S,)
        Weight found by each FOA run and its :math:`\operatorname{tr}P` (m², m²/s²).
    grid_x, grid_fun : float
        The exhaustive search's weight and :math:`\operatorname{tr}P`.
    rtol : float
        Relative tolerance under which two objective values count as equal.
    """

    seeds: FloatArray
    foa_x: FloatArray
    foa_fun: FloatArray
    grid_x: float
    grid_fun: float
    rtol: float

    @property
    def share_reached(self) -> float:
        """Share of seeds whose FOA objective is at most the grid's (ties within ``rtol`` count as reached)."""
        return float(np.mean(self.foa_fun <= self.grid_fun + self.rtol * abs(self.grid_fun)))

    @property
    def share_better(self) -> float:
        """Share of seeds whose FOA objective is below the grid's by more than a relative ``rtol``."""
        return float(np.mean(self.foa_fun < self.grid_fun - self.rtol * abs(self.grid_fun)))

    @property
    def median_excess(self) -> float:
        """Median relative excess (FOA − grid) / grid of the objective (dimensionless)."""
        return float(np.median((self.foa_fun - self.grid_fun) / abs(self.grid_fun)))


def foa_over_seeds(P1: ArrayLike, P2: ArrayLike, seeds: ArrayLike, n_grid: int = 1001, population: int = 30,
                   iterations: int = 200, rtol: float = 1e-9) -> FoaSeeds:
    r"""Minimise :math:`\operatorname{tr}P(\omega)` of CI (Wang & Tang 2024, eq. 1) by FOA once per seed and once on a grid.

    The source's Fig. 5 compares one FOA run with one exhaustive search; FOA is stochastic, so
    the comparison is repeated here over many seeds on the same objective
    (:func:`fusion.estimates.ci.ci_objective`).

    Parameters
    ----------
    P1, P2 : array_like, shape (n, n)
        The two covariances.
    seeds : array_like of int, shape (S,)
        FOA run ``i`` uses ``numpy.random.default_rng(seeds[i])``.
    n_grid : int
        Points of the exhaustive search on [0, 1].
    population, iterations : int
        FOA swarm size and generations (30 × 200 in the source).
    rtol : float
        Relative tolerance of a tie between two objective values (the optimisers' own, 1e-9).

    Returns
    -------
    FoaSeeds

    Raises
    ------
    ValueError
        ``seeds`` empty or not integers, ``rtol`` negative.
    """
    P1, P2 = as_covariance(P1, name="P1"), as_covariance(P2, name="P2")
    if P1.shape != P2.shape:
        raise ValueError(f"P1 and P2 must have the same shape, got {P1.shape} and {P2.shape}")
    s = np.array(check_seeds(seeds, "seeds"))  # integers of any size (rule 11): a float array would round 2**53 + 1
    n_grid = count(n_grid, "n_grid", minimum=2)
    population = count(population, "population")
    iterations = count(iterations, "iterations")
    rtol = nonnegative_scalar(rtol, "rtol")

    def objective(w: ArrayLike) -> FloatArray:
        return ci_objective(w, P1, P2)

    # every seed's swarm flies at once: the result fruit_fly gives seed by seed (fusion.optimise.scalar.fruit_fly_batch)
    runs = fruit_fly_batch(objective, [np.random.default_rng(int(seed)) for seed in s], population=population,
                           iterations=iterations)
    grid = grid_search(objective, n_grid, vectorized=True)
    return FoaSeeds(seeds=s, foa_x=np.array([r.x for r in runs]), foa_fun=np.array([r.fun for r in runs]),
                    grid_x=float(grid.x), grid_fun=float(grid.fun), rtol=float(rtol))


def printed_foa_over_seeds(P1d: ArrayLike, P1i: ArrayLike, P2d: ArrayLike, P2i: ArrayLike, seeds: ArrayLike,
                           n_grid: int = 1001, population: int = 30, iterations: int = 200,
                           rtol: float = 1e-9) -> FoaSeeds:
    r"""FOA once per seed and an exhaustive search on the objective of Wang & Tang's (2024) eqs. 11-12 as printed.

    The source chooses its weight by FOA minimising the size of the fused covariance (§2.2). With eqs.
    11-12 as printed (one :math:`\omega` dividing both correlated parts) that objective,
    :func:`fusion.estimates.ci.split_ci_objective` with ``same_omega=True``, decreases with
    :math:`\omega` (both inflated covariances decrease in the Loewner order), so its minimum is
    :math:`\omega = 1`. This runs the source's FOA on it, seed by seed, and the grid
    :math:`k/(n-1)`, :math:`k = 1 \dots n-1` (the end 0 divides by zero).

    Parameters
    ----------
    P1d, P1i, P2d, P2i : array_like, shape (n, n)
        Correlated and independent parts of the two local covariances at one step.
    seeds : array_like of int, shape (S,)
        FOA run ``i`` uses ``numpy.random.default_rng(seeds[i])``.
    n_grid : int
        Points of the exhaustive search on [0, 1] (the point 0 left out).
    population, iterations : int
        FOA swarm size and generations (30 × 200 in the source).
    rtol : float
        Relative tolerance of a tie between two objective values.

    Returns
    -------
    FoaSeeds

    Raises
    ------
    ValueError
        Bad covariance parts, ``seeds`` empty or not integers, counts not positive, ``rtol`` negative.
    """
    first = as_array(P1d, "P1d", ndim=2)
    parts = [as_semidefinite(M, first.shape[0], name=nm) for M, nm in ((P1d, "P1d"), (P1i, "P1i"), (P2d, "P2d"), (P2i, "P2i"))]
    split_ci_objective(1.0, *parts, same_omega=True)   # validates the sums (positive definite)
    s = np.array(check_seeds(seeds, "seeds"))  # integers of any size (rule 11): a float array would round 2**53 + 1
    n_grid = count(n_grid, "n_grid", minimum=3)
    population, iterations = count(population, "population"), count(iterations, "iterations")
    rtol = nonnegative_scalar(rtol, "rtol")

    def objective(w: ArrayLike) -> FloatArray:
        return split_ci_objective(np.maximum(w, 1e-12), *parts, same_omega=True)   # FOA's 1/D is never 0

    runs = fruit_fly_batch(objective, [np.random.default_rng(int(seed)) for seed in s], population=population,
                           iterations=iterations)
    grid = grid_search(objective, n_grid - 1, lo=1.0 / (n_grid - 1), hi=1.0, vectorized=True)
    return FoaSeeds(seeds=s, foa_x=np.array([r.x for r in runs]), foa_fun=np.array([r.fun for r in runs]),
                    grid_x=float(grid.x), grid_fun=float(grid.fun), rtol=float(rtol))


#: Display names of the rules of :func:`fusion_study` (chapter 05), in table order.
STUDY_METHODS = (
    "sensor 1", "sensor 2", "CI (closed-form ω)", "CI, ω by FOA", "CI, ω by exhaustive search",
    "CI, ω = published FOA optimum", "improved CI (split CI)", "convex comb. = multi-Bayesian = ML",
    "fuzzy clustering", "centralised KF",
)


@dataclass(frozen=True)
class FusionStudy:
    r"""Every fusion rule of chapter 05 on one :class:`Scenario`.

    Attributes
    ----------
    t : ndarray, shape (K,)
        Times (s).
    truth : ndarray, shape (K, 4)
    est : dict of str to ndarray, shape (runs, K, 4)
        Estimates of each method of ``STUDY_METHODS`` that was run.
    rmse : dict of str to ndarray, shape (K, 4)
        RMSE over the runs per step and state component (m, m/s), for every method of ``est``.
    floor : ndarray, shape (K, 2)
        :math:`\sqrt{P}` of the centralised filter on x and y (m): the posterior Cramér-Rao bound
        *for targets that follow the model*; not a floor for the deterministic path simulated.
    steady : ndarray of bool, shape (K,)
        Steps after the start-up transient.
    measurements : dict of str to ndarray, shape (K, 2)
        RMSE over the runs per step of each sensor's raw position measurements on (x, y) (m), keyed
        ``"sensor 1 measurements"`` and ``"sensor 2 measurements"`` (what the source's Fig. 7 draws).
    """

    t: FloatArray
    truth: FloatArray
    est: dict[str, FloatArray]
    rmse: dict[str, FloatArray]
    floor: FloatArray
    steady: FloatArray
    measurements: dict[str, FloatArray]

    def steady_rmse(self, method: str, component: int) -> float:
        """Mean over the steady steps of the per-step RMSE of ``method`` on state ``component`` (0 = x, 2 = y)."""
        return float(self.curve(method, component)[self.steady].mean())

    def curve(self, method: str, component: int) -> FloatArray:
        """Per-step RMSE of a method of ``est`` or of a sensor's raw measurements (``component`` 0 = x, 2 = y), shape (K,)."""
        if method in self.measurements:
            if component not in (0, 2):
                raise ValueError(f"measurements have positions only (component 0 or 2), got {component}")
            return self.measurements[method][:, component // 2]
        return self.rmse[method][:, component]


def fusion_study(sc: Scenario, w_foa: ArrayLike | None = None, w_grid: ArrayLike | None = None,
                 published_omega: float | None = None, t_steady: float = 20.0) -> FusionStudy:
    """Run every fusion rule of chapter 05 on the two local tracks of ``sc``.

    Parameters
    ----------
    sc : Scenario
    w_foa, w_grid : array_like, shape (K,), optional
        Per-step CI weights (:func:`per_step_weights`); the rules that use them are skipped if ``None``.
    published_omega : float, optional
        A fixed CI weight (the source's published FOA optimum); skipped if ``None``.
    t_steady : float
        Start of the steady-state window (s).

    Returns
    -------
    FusionStudy
        Methods named as in ``STUDY_METHODS``: the sensors, CI (eqs. 1-2 corrected), split CI
        (eqs. 5-12 read as split CI), the convex combination (eqs. 3-4), fuzzy clustering and the
        centralised Kalman filter.
    """
    instance_of(sc, Scenario, "sc")
    for w, w_name in ((w_foa, "w_foa"), (w_grid, "w_grid")):
        if w is not None:
            w_arr = as_array(w, w_name, ndim=(0, 1))
            if w_arr.ndim == 1 and w_arr.size != sc.t.size:
                raise ValueError(f"{w_name} must be a scalar or have one weight per step ({sc.t.size}), got {w_arr.size}")
            if np.any(w_arr < 0) or np.any(w_arr > 1):
                raise ValueError(f"{w_name} must lie in [0, 1]")
    if published_omega is not None:
        scalar(published_omega, "published_omega", 0.0, 1.0)
    nonnegative_scalar(t_steady, "t_steady")
    a, b = sc.tracks
    est: dict[str, FloatArray] = {"sensor 1": a.est, "sensor 2": b.est,
                                  "CI (closed-form ω)": fuse_tracks(a, b, "ci").est}
    if w_foa is not None:
        est["CI, ω by FOA"] = fuse_tracks(a, b, "ci", omega=w_foa).est
    if w_grid is not None:
        est["CI, ω by exhaustive search"] = fuse_tracks(a, b, "ci", omega=w_grid).est
    if published_omega is not None:
        est["CI, ω = published FOA optimum"] = fuse_tracks(a, b, "ci", omega=published_omega).est
    est["improved CI (split CI)"] = fuse_tracks(a, b, "split").est
    est["convex comb. = multi-Bayesian = ML"] = fuse_tracks(a, b, "convex").est
    est["fuzzy clustering"] = fuse_tracks(a, b, "fuzzy").est
    est["centralised KF"] = sc.central.est
    rmse = {name: rmse_per_step(e, sc.truth) for name, e in est.items()}
    raw = {f"sensor {j + 1} measurements": rmse_per_step(tr_j.z, sc.truth[:, [0, 2]]) for j, tr_j in enumerate((a, b))}
    floor = np.sqrt(sc.central.gains.P[:, [0, 2], [0, 2]])
    return FusionStudy(t=sc.t, truth=sc.truth, est=est, rmse=rmse, floor=floor, steady=sc.t >= t_steady,
                       measurements=raw)


def run_rmse(est: ArrayLike, truth: ArrayLike, steps: ArrayLike, component: int, decimals: int = 3) -> FloatArray:
    r"""Per-run RMSE over time: :math:`\sqrt{\operatorname{mean}_k e_{r,k}^2}` on one state component.

    The per-run metric of the chapter's paired comparisons (same runs for every method).

    Parameters
    ----------
    est : array_like, shape (runs, K, n)
    truth : array_like, shape (K, n) or (runs, K, n)
    steps : array_like of bool, shape (K,)
        Steps averaged over.
    component : int
        State index (0 = x, 2 = y for Wang & Tang 2024).
    decimals : int
        Rounding of the result (default 3: mm): rules that give the same estimate up to round-off give
        exactly equal metrics instead of a difference of a few ulp.

    Returns
    -------
    ndarray, shape (runs,)
    """
    est_arr = as_array(est, "est", ndim=3)
    truth_arr = as_array(truth, "truth", ndim=(0, 1, 2, 3))
    try:
        np.broadcast_shapes(est_arr.shape, truth_arr.shape)
    except ValueError:
        raise ValueError(f"truth of shape {truth_arr.shape} does not match est of shape {est_arr.shape}") from None
    component = index(component, "component", est_arr.shape[2])
    decimals = count(decimals, "decimals", minimum=0)
    e = np.asarray(est, dtype=float) - np.asarray(truth, dtype=float)
    mask = np.asarray(steps, dtype=bool)
    if e.ndim != 3 or mask.shape != (e.shape[1],):
        raise ValueError(f"est must be (runs, K, n) and steps (K,), got {e.shape} and {mask.shape}")
    if not mask.any():
        raise ValueError("steps selects no step")
    return np.round(np.sqrt(np.mean(e[:, mask, component] ** 2, axis=1)), decimals)


def nees_study(rng: np.random.Generator, Q: ArrayLike, R1: ArrayLike, R2: ArrayLike, x_start: ArrayLike,
               n_steps: int, runs: int, T: float = 1.0, velocity_sigma: float = 100.0,
               t_steady: float = 20.0) -> tuple[dict[str, float], dict[str, FloatArray]]:
    r"""Mean NEES of the local filter and of CI, convex combination, split CI and eqs. 11-12 as printed.

    Targets follow the model (:func:`model_truth`, process noise common to both sensors), so the
    two local filters' errors are correlated. NEES :math:`\mathbf e^\top P^{-1}\mathbf e` averages
    to 4 (the state dimension) for a consistent estimator.

    Parameters
    ----------
    rng : numpy.random.Generator
        Draws the targets, then sensor 1's noise, then sensor 2's.
    Q : array_like, shape (4, 4)
    R1, R2 : array_like, shape (2, 2)
        Measurement covariances (m², diagonal): sensor j's noise is drawn with standard deviations
        ``sqrt(diag(Rj))`` and its filter starts with that position variance.
    x_start : array_like, shape (4,)
        Initial true state; its velocity is the filters' initial velocity.
    n_steps, runs : int
    T : float
        Sampling period (s).
    velocity_sigma : float
        Prior velocity standard deviation (m/s), common to both sensors.
    t_steady : float
        NEES is averaged over runs and steps with ``t >= t_steady`` (s).

    Returns
    -------
    mean_nees : dict of str to float
    est : dict of str to ndarray, shape (runs, K, 4)
        The estimates of the fused rules and the local filter, with the key ``"truth"`` for the targets.
    """
    R1 = diagonal_covariance(R1, 2, "R1")
    R2 = diagonal_covariance(R2, 2, "R2")
    as_array(x_start, "x_start", shape=(4,))
    n_steps = count(n_steps, "n_steps")
    velocity_sigma = std_scalar(velocity_sigma, "velocity_sigma")
    t_steady = nonnegative_scalar(t_steady, "t_steady")
    n_steps, runs = count(n_steps, "n_steps"), count(runs, "runs")
    if not (np.arange(n_steps) * positive_scalar(T, "T") >= t_steady).any():
        raise ValueError(f"t_steady = {t_steady} leaves no step of the {n_steps} steps")
    model = cv_model(T)
    F, H = model.F, model.H
    x_start = np.asarray(x_start, dtype=float)
    Xm = model_truth(rng, F, Q, x_start, n_steps, runs)
    P0d = np.diag([0.0, velocity_sigma**2, 0.0, velocity_sigma**2])
    tracks = []
    for R in (R1, R2):
        z = Xm[:, :, [0, 2]] + rng.standard_normal((runs, n_steps, 2)) * np.sqrt(np.diag(R))
        x0 = np.column_stack([z[:, 0, 0], np.zeros(runs), z[:, 0, 1], np.zeros(runs)]) + x_start * [0, 1, 0, 1]
        tracks.append(local_track(z, F, H, Q, R, x0, P0d, np.diag([R[0, 0], 0.0, R[1, 1], 0.0])))
    steady = np.arange(n_steps) * T >= t_steady
    out = {"local filter (sensor 1)": float(np.mean(nees(tracks[0].est - Xm, tracks[0].gains.P)[:, steady]))}
    est = {"local filter (sensor 1)": tracks[0].est, "truth": Xm}
    for name, rule, w in [("CI, ω = 0.5", "ci", 0.5), ("convex combination", "convex", None),
                          ("split CI (eq. ci-split)", "split", None), ("eqs. 11-12 as printed (same ω)", "printed", None)]:
        f = fuse_tracks(tracks[0], tracks[1], rule, omega=w)
        out[name] = float(np.mean(nees(f.est - Xm, f.P)[:, steady]))
        est[name] = f.est
    return out, est


def floor_by_period(periods: ArrayLike, Q: ArrayLike, sigma: float, velocity_sigma: float = 100.0,
                    t_steady: float = 20.0) -> dict[float, dict[str, float]]:
    r"""Time-averaged :math:`\sqrt{P_{xx}}` of the centralised filter against the sampling period.

    :math:`P` is the centralised Kalman filter's covariance on both sensors (noise ``sigma`` per
    axis each) on the path of :func:`trajectory`, with the process noise ``Q`` as printed and with
    none. It is the posterior Cramér-Rao bound *for targets that follow that model*; it is not a
    floor for the deterministic path, on which the filters can do better.

    Parameters
    ----------
    periods : array_like of float
        Sampling periods (s).
    Q : array_like, shape (4, 4)
    sigma : float
        Measurement noise standard deviation of each sensor (m).
    velocity_sigma : float
        Prior velocity standard deviation (m/s).
    t_steady : float
        Average over ``t >= t_steady`` (s).

    Returns
    -------
    dict of float to dict
        Per period: ``"bound √P, printed Q (m)"`` and ``"bound √P, no process noise (m)"``.
    """
    sigma = std_scalar(sigma, "sigma")
    if np.any(as_array(periods, "periods", ndim=(0, 1)) <= 0):
        raise ValueError("periods must be positive")
    std_scalar(velocity_sigma, "velocity_sigma")
    nonnegative_scalar(t_steady, "t_steady")
    rows = {}
    for Tp in np.atleast_1d(np.asarray(periods, dtype=float)):
        tp = trajectory(float(Tp)).t
        model_p = cv_model(float(Tp))
        Fp, Hp = model_p.F, model_p.H
        Hc, Rc = np.vstack([Hp, Hp]), np.diag([sigma**2] * 4)
        P0 = np.diag([sigma**2 / 2, velocity_sigma**2, sigma**2 / 2, velocity_sigma**2])
        steady = tp >= t_steady
        if not steady.any():
            raise ValueError(f"t_steady = {t_steady} leaves no step of the path (period {float(Tp)} s)")
        gc = gain_sequence(Fp, Hc, Q, Rc, P0, tp.size)
        gq = gain_sequence(Fp, Hc, np.zeros((4, 4)), Rc, P0, tp.size)
        rows[float(Tp)] = {"bound √P, printed Q (m)": float(np.sqrt(gc.P[steady, 0, 0]).mean()),
                           "bound √P, no process noise (m)": float(np.sqrt(gq.P[steady, 0, 0]).mean())}
    return rows


#: Configurations of :func:`architecture_study`: (rule key, display name, process-noise reading).
ARCH_RULES = (
    ("convex", "convex comb. (eqs. 3-4)", "shared"),
    ("ci", "CI (closed-form ω)", "shared"),
    ("split", "split CI, Q in shared part", "shared"),
    ("split", "split CI, Q in own part", "own"),
    ("printed", "eqs. 11-12 as printed, Q in shared part", "shared"),
    ("printed", "eqs. 11-12 as printed, Q in own part", "own"),
    ("bsc", "Bar-Shalom–Campo", "shared"),
    ("lossless", "lossless (fed-back prior removed once)", "shared"),
)


@dataclass(frozen=True)
class ArchitectureStudy:
    r"""Every rule of :data:`ARCH_RULES` with and without feedback, and the centralised filter (:func:`architecture_study`).

    Attributes
    ----------
    run_rmse : dict of (str, str) to ndarray, shape (runs,)
        Per-run RMSE on x over the steady steps on the chapter's path (m, rounded to mm), keyed by
        (architecture, rule name); architecture ``"independent"``, ``"feedback"`` (the rule's own fused
        split fed back), ``"feedback, fused covariance common"`` (split CI only: the fused covariance
        fed back as the common part) or ``"centralised"``.
    nees : dict of (str, str) to float
        Mean NEES over the model-following runs and the steady steps (4 for a consistent rule); every
        key of ``run_rmse`` but fuzzy clustering, which reports no covariance.
    reported : dict of (str, str) to float
        Time-averaged :math:`\sqrt{P_{xx}}` the rule reports over the steady steps (m); the keys of ``nees``.
    model_rmse : dict of (str, str) to ndarray, shape (nees_runs,)
        Per-run RMSE on x over the steady steps of the model-following runs (m, rounded to mm).
    runs, nees_runs : int
        Runs on the path and runs with targets that follow the model.
    local_gain : dict of (str, str) to float
        Time-averaged position gain of sensor 1's local filter over the steady steps,
        :math:`K_{xx} = P^+_{xx}/R_{1,xx}` (1: the filter returns its measurement); every rule run through
        :func:`fusion.filtering.feedback.fusion_loop`.
    """

    run_rmse: dict[tuple[str, str], FloatArray]
    nees: dict[tuple[str, str], float]
    reported: dict[tuple[str, str], float]
    model_rmse: dict[tuple[str, str], FloatArray]
    runs: int
    nees_runs: int
    local_gain: dict[tuple[str, str], float] = field(default_factory=dict)


def architecture_study(rng: np.random.Generator, R1: ArrayLike, R2: ArrayLike, Q: ArrayLike, runs: int = 200,
                       nees_runs: int = 100, T: float = 1.0, velocity_sigma: float = 100.0,
                       t_steady: float = 20.0, printed_omegas: ArrayLike = (),
                       placement_omegas: ArrayLike = ()) -> ArchitectureStudy:
    r"""The source's Fig. 2 feedback architecture beside independent local filters, every rule.

    Two sets of runs share each rule's covariance recursion (:func:`fusion.filtering.feedback.fusion_loop`):
    ``runs`` on the deterministic path of :func:`trajectory` (RMSE) and ``nees_runs`` with targets that
    follow the model, :func:`model_truth` from the path's first state with the process noise common to
    both sensors (NEES). Every filter starts at its sensor's first measurement with zero velocity,
    covariance ``diag(R[0,0], s^2, R[1,1], s^2)``, the velocity part common to both sensors.

    Parameters
    ----------
    rng : numpy.random.Generator
        Draws sensor 1's noise, sensor 2's noise, then the model targets and their noise.
    R1, R2 : array_like, shape (2, 2)
        Measurement covariances (m²), diagonal.
    Q : array_like, shape (4, 4)
        Process noise of the filters (and of the model targets).
    runs, nees_runs : int
        Number of runs of each kind (>= 1).
    T : float
        Sampling period (s).
    velocity_sigma : float
        Prior standard deviation of each velocity component (m/s).
    t_steady : float
        Start of the averaging window (s).
    printed_omegas : array_like of float in (0, 1], optional
        Fixed weights with which eqs. 11-12 as printed are run as well, without and with feedback, Q in the
        shared part (e.g. the source's published FOA optimum 0.0018); named
        ``"eqs. 11-12 as printed, ω = <w>, Q in shared part"``.
    placement_omegas : array_like of float in (0, 1], optional
        Fixed weights with which eqs. 11-12 as printed are also fed back with Q in each sensor's own part
        (``"eqs. 11-12 as printed, ω = <w>, Q in own part"``) and fed back with the fused covariance as the
        common part (architecture ``"feedback, fused covariance common"``, Q in the shared part): where Q
        enters the split and what is fed back, for those weights.

    Returns
    -------
    ArchitectureStudy
        Every rule of :data:`ARCH_RULES` (``"lossless"`` with feedback only: without it the common prior is
        unknown), the fixed-weight readings, fuzzy clustering with independent filters (it reports no
        covariance to feed back) and the centralised filter.

    Raises
    ------
    ValueError
        Covariances not valid, counts not positive, ``t_steady`` beyond the path, a weight outside (0, 1].
    """
    from fusion.filtering.feedback import fusion_loop

    omegas = [scalar(w, "printed_omegas", 0.0, 1.0, lo_open=True)
              for w in np.atleast_1d(as_array(printed_omegas, "printed_omegas", ndim=(0, 1), nonempty=False))]
    placed = [scalar(w, "placement_omegas", 0.0, 1.0, lo_open=True)
              for w in np.atleast_1d(as_array(placement_omegas, "placement_omegas", ndim=(0, 1), nonempty=False))]

    as_rng(rng)
    runs, nees_runs = count(runs, "runs"), count(nees_runs, "nees_runs")
    R1, R2 = diagonal_covariance(R1, 2, "R1"), diagonal_covariance(R2, 2, "R2")
    s2 = std_scalar(velocity_sigma, "velocity_sigma") ** 2
    traj, model = trajectory(T), cv_model(T)
    t, X, F, H = traj.t, traj.states, model.F, model.H
    Q = as_semidefinite(Q, 4, name="Q")
    steady = t >= nonnegative_scalar(t_steady, "t_steady")
    if not steady.any():
        raise ValueError(f"t_steady = {t_steady} leaves no step of the path")
    K = t.size
    z, Xm = _path_and_model_measurements(rng, X, F, Q, R1, R2, runs, nees_runs)
    x0 = [np.column_stack([zj[:, 0, 0], np.zeros(runs + nees_runs), zj[:, 0, 1], np.zeros(runs + nees_runs)])
          for zj in z]
    P0d = np.diag([0.0, s2, 0.0, s2])
    P0i = [np.diag([R[0, 0], 0.0, R[1, 1], 0.0]) for R in (R1, R2)]
    truth = np.concatenate([np.broadcast_to(X, (runs, K, 4)), Xm])
    out_rmse: dict[tuple[str, str], FloatArray] = {}
    out_nees: dict[tuple[str, str], float] = {}
    out_rep: dict[tuple[str, str], float] = {}
    out_model: dict[tuple[str, str], FloatArray] = {}
    out_gain: dict[tuple[str, str], float] = {}

    def record(key: tuple[str, str], est: FloatArray, P: FloatArray, local_P: FloatArray | None = None) -> None:
        e = est - truth
        out_rmse[key] = run_rmse(e[:runs], 0.0, steady, 0)
        out_nees[key] = round(float(np.mean(nees(e[runs:], P)[:, steady])), 4)
        out_rep[key] = round(float(np.sqrt(P[steady, 0, 0]).mean()), 4)
        out_model[key] = run_rmse(e[runs:], 0.0, steady, 0)
        if local_P is not None:
            out_gain[key] = round(float(np.mean(local_P[steady, 0, 0])) / float(R1[0, 0]), 4)

    fixed = [("printed", f"eqs. 11-12 as printed, ω = {w:g}, Q in shared part", "shared", w) for w in omegas]
    for arch, fb in (("independent", "none"), ("feedback", "split"), ("feedback, fused covariance common", "common")):
        for rule, name, reading, w in [(*rule_, None) for rule_ in ARCH_RULES] + fixed:
            if fb == "common" and (rule != "split" or w is not None):
                continue   # the other rules do not use the split (eqs. 11-12 drive ω to 1): the same as "feedback"
            if fb == "none" and rule == "lossless":
                continue   # without feedback the common prior is unknown (it is Bar-Shalom–Campo's job)
            r = fusion_loop(z[0], z[1], x0[0], x0[1], F, H, Q, R1, R2, P0d, P0i[0], P0i[1], rule, fb, reading, omega=w)
            record((arch, name), r.est, r.P, r.local_P)
    for w in placed:   # eqs. 11-12 at a fixed weight: Q in the sensors' own parts, and the fused covariance as common
        for arch, fb, reading in (("feedback", "split", "own"), ("feedback, fused covariance common", "common", "shared")):
            r = fusion_loop(z[0], z[1], x0[0], x0[1], F, H, Q, R1, R2, P0d, P0i[0], P0i[1], "printed", fb, reading,
                            omega=w)
            record((arch, f"eqs. 11-12 as printed, ω = {w:g}, Q in {reading} part"), r.est, r.P, r.local_P)
    Hc = np.vstack([H, H])
    Rc = np.zeros((4, 4))
    Rc[:2, :2], Rc[2:, 2:] = R1, R2
    # fuzzy clustering reports no covariance: independent local filters only, and no NEES or reported P
    local = [local_track(z[j], F, H, Q, R, x0[j], P0d, P0i[j]) for j, R in enumerate((R1, R2))]
    e_fz = fuse_tracks(local[0], local[1], "fuzzy").est - truth
    out_rmse[("independent", "fuzzy clustering")] = run_rmse(e_fz[:runs], 0.0, steady, 0)
    out_model[("independent", "fuzzy clustering")] = run_rmse(e_fz[runs:], 0.0, steady, 0)
    xc0, Pc0 = _central_start(x0[0], x0[1], P0d + P0i[0], P0d + P0i[1], P0d)   # the velocity prior counted once
    gc = gain_sequence(F, Hc, Q, Rc, Pc0, K)
    record(("centralised", "centralised KF"), filter_runs(np.concatenate(z, axis=2), gc, xc0), gc.P)
    return ArchitectureStudy(run_rmse=out_rmse, nees=out_nees, reported=out_rep, model_rmse=out_model, runs=runs,
                             nees_runs=nees_runs, local_gain=out_gain)


#: Readings of the source's process noise for :func:`pcrb_steady` (Δ₀ = 10 as printed).
Q_READINGS = ("as printed: Δ₀² I per step", "discrete white acceleration (G = [T²/2, T] per axis)",
              "continuous white acceleration (density Δ₀²)")


def process_noise(T: float, delta0: float, reading: str) -> FloatArray:
    r"""The process-noise covariance of Wang & Tang's (2024) §3.2 under one reading of :data:`Q_READINGS`.

    As printed, :math:`Q = \Delta_0^2 I_4` per step whatever the period. With the noise gain read as the
    constant-velocity one, :math:`G = [T^2/2, T]^\top` per axis, :math:`Q = \Delta_0^2 GG^\top` per axis
    (discrete white acceleration); with continuous white acceleration of density :math:`\Delta_0^2`,
    :math:`Q = \Delta_0^2 [[T^3/3, T^2/2], [T^2/2, T]]` per axis (Bar-Shalom, Li & Kirubarajan 2001, §6.2-6.3).

    Parameters
    ----------
    T : float
        Sampling period (s), > 0.
    delta0 : float
        :math:`\Delta_0`, > 0.
    reading : str
        One of :data:`Q_READINGS`.

    Returns
    -------
    ndarray, shape (4, 4)
        State order :math:`[x, \dot x, y, \dot y]`.
    """
    T = positive_scalar(T, "T")
    d2 = positive_scalar(delta0, "delta0") ** 2
    one_of(reading, Q_READINGS, "reading")
    if reading == Q_READINGS[0]:
        return d2 * np.eye(4)
    if reading == Q_READINGS[1]:
        block = d2 * np.array([[T**4 / 4, T**3 / 2], [T**3 / 2, T**2]])
    else:
        block = d2 * np.array([[T**3 / 3, T**2 / 2], [T**2 / 2, T]])
    return np.kron(np.eye(2), block)


def pcrb_steady(T: float, sigma: float, Q: ArrayLike) -> float:
    r"""Steady-state posterior Cramér-Rao bound :math:`\sqrt{P_{xx}}` with both sensors, for targets that follow the model.

    For the linear-Gaussian model :math:`\mathbf x_{k+1} = F\mathbf x_k + \mathbf w_k`, two position sensors
    with noise ``sigma`` per axis, the PCRB is the centralised Kalman filter's filtered covariance
    (Tichavský, Muravchik & Nehorai 1998); its steady state solves the discrete algebraic Riccati
    equation (:func:`scipy.linalg.solve_discrete_are`).

    Parameters
    ----------
    T : float
        Sampling period (s), > 0.
    sigma : float
        Measurement noise standard deviation of each sensor (m), > 0.
    Q : array_like, shape (4, 4)
        Process-noise covariance (positive semidefinite, stabilising).

    Returns
    -------
    float
        :math:`\sqrt{P_{xx}}` (m).

    References
    ----------
    * Tichavský, P., Muravchik, C. H., & Nehorai, A. (1998). Posterior Cramér-Rao bounds for
      discrete-time nonlinear filtering. *IEEE Transactions on Signal Processing*, 46(5), 1386-1396.
    """
    from scipy.linalg import solve_discrete_are

    model = cv_model(positive_scalar(T, "T"))
    sigma = std_scalar(sigma, "sigma")
    Q = as_semidefinite(Q, 4, name="Q")
    Hc = np.vstack([model.H, model.H])
    Rc = sigma**2 * np.eye(4)
    try:  # issue 35, class 5: a Riccati equation that cannot be solved is named, not a LinAlgError
        Pm = solve_discrete_are(model.F.T, Hc.T, Q, Rc)
        S = Hc @ Pm @ Hc.T + Rc
        P = Pm - Pm @ Hc.T @ solve(S, Hc @ Pm, "sigma and Q")
    except (np.linalg.LinAlgError, ValueError) as exc:
        if "sigma" in str(exc):
            raise
        raise ValueError(f"the steady-state bound has no solution for T = {T}, sigma = {sigma} and this Q "
                         f"(the Riccati equation is too ill-conditioned: {exc})") from None
    if not np.isfinite(P[0, 0]) or P[0, 0] < 0:
        raise ValueError(f"the steady-state bound is not finite for T = {T}, sigma = {sigma} and this Q")
    return float(np.sqrt(P[0, 0]))


def straight_leg_floor(T: float, sigma: float, legs: tuple[float, float, float] = (100.0, 30.0, 90.0),
                       turn_time: float = 20.0, causal: bool = False) -> tuple[FloatArray, FloatArray, FloatArray]:
    r"""Floor on the straight legs of :func:`trajectory` for an estimator that knows where the legs are.

    On a straight leg the position is :math:`a + bt` on each axis. An estimator told where the legs
    begin and end can fit that line to both sensors' measurements of the leg by least squares. Its
    error standard deviation at time :math:`t` is
    :math:`\sigma\sqrt{\mathbf h_t^\top (X^\top X)^{-1}\mathbf h_t / 2}`, :math:`\mathbf h = [1, t]`, with the
    rows of :math:`X` the leg's steps used: every step of the leg (``causal=False``: a smoother, which
    uses the leg's future), or the leg's steps up to :math:`t` (``causal=True``: a filter; at the leg's
    first step only the position is identified, :math:`\sigma/\sqrt 2`). Either is the Cramér-Rao bound
    of *unbiased* estimators of the line from those data, the causal one the right comparison for
    causal filters. It is not a bound for every estimator: a biased one (a filter with small gains) or
    one that carries information across the turns or uses the constant speed can beat it.

    Parameters
    ----------
    T : float
        Sampling period (s), > 0.
    sigma : float
        Measurement noise standard deviation of each sensor (m), > 0.
    legs : (float, float, float)
        Durations of the straight legs (s), as for :func:`trajectory`.
    turn_time : float
        Duration of each turn (s).
    causal : bool
        Fit each step with the leg's measurements up to that step only (a filter) instead of the whole
        leg (a smoother).

    Returns
    -------
    t : ndarray, shape (K,)
        The times of :func:`trajectory`.
    on_leg : ndarray of bool, shape (K,)
        Steps on a straight leg (the ends of a leg included).
    floor : ndarray, shape (L,)
        Error standard deviation per axis (m) at the ``L = on_leg.sum()`` straight-leg steps.

    Raises
    ------
    ValueError
        ``T``, ``sigma`` or ``turn_time`` not positive; ``legs`` not three finite numbers >= 0.
    TypeError
        ``legs`` not numeric, ``causal`` not a bool.
    """
    sigma = std_scalar(sigma, "sigma")
    legs = _legs(legs)
    instance_of(causal, (bool, np.bool_), "causal")
    t = trajectory(T, legs=legs, turn_time=positive_scalar(turn_time, "turn_time")).t
    starts = np.cumsum([0.0, legs[0] + turn_time, legs[1] + turn_time])
    floor = np.full(t.size, np.nan)
    for start, length in zip(starts, legs):
        on = (t >= start - 1e-9) & (t <= start + length + 1e-9)
        if on.sum() < 2:
            continue
        X = np.column_stack([np.ones(on.sum()), t[on] - start])
        if not causal:
            C = np.linalg.inv(X.T @ X)
            floor[on] = sigma * np.sqrt(np.einsum("ij,jk,ik->i", X, C, X) / 2.0)
            continue
        # the leg's steps up to each one: the information X[:j+1]^T X[:j+1] grows by one row per step
        S0, S1, S2 = np.cumsum(X[:, 0]), np.cumsum(X[:, 1]), np.cumsum(X[:, 1] ** 2)
        u = X[:, 1]
        det = S0 * S2 - S1**2
        with np.errstate(divide="ignore", invalid="ignore"):
            var = (S2 - 2.0 * u * S1 + u**2 * S0) / det    # h^T (X^T X)^{-1} h, h = [1, u]
        var[0] = 1.0                                         # first step: the position alone, one row
        floor[on] = sigma * np.sqrt(var / 2.0)
    on_leg = np.isfinite(floor)
    return t, on_leg, floor[on_leg]


def slip_steps_band(rmse: float, published: float, decimals: int = 0) -> tuple[int, int]:
    r"""The numbers of steps :math:`n` for which the slip :math:`\sqrt{\sum e^2}/n` rounds to a published value.

    Eq. 13 coded with the :math:`1/n` outside the root gives the per-run RMSE divided by :math:`\sqrt n`
    (:func:`rmse_variants`). If the per-run RMSE ``rmse`` does not change with the length of the run, the
    slip equals ``published`` at ``decimals`` decimals exactly when :math:`\mathrm{round}(r/\sqrt n) = p`,
    i.e. for :math:`(r/(p + h))^2 < n \le (r/(p - h))^2`, :math:`h = 10^{-d}/2`.

    Parameters
    ----------
    rmse : float
        Per-run RMSE, averaged over the runs (m), > 0.
    published : float
        The published value (m), > ``10**-decimals / 2``.
    decimals : int
        Decimals it is printed with (0: whole metres).

    Returns
    -------
    (int, int)
        The smallest and largest :math:`n` (inclusive); ``lo > hi`` if no integer fits.

    Raises
    ------
    ValueError
        ``rmse`` not positive, ``published`` not above half a unit of its last decimal.
    """
    r = positive_scalar(rmse, "rmse")
    d = count(decimals, "decimals", minimum=0)
    half = 0.5 * 10.0 ** (-d)
    p = scalar(published, "published", half, np.inf, lo_open=True)
    lo = int(np.floor((r / (p + half)) ** 2)) + 1      # r/sqrt(n) < p + h (the upper end rounds up)
    hi = int(np.floor((r / (p - half)) ** 2))          # r/sqrt(n) >= p - h
    return lo, hi


def rmse_variants(est: ArrayLike, truth: ArrayLike, steps: ArrayLike) -> dict[str, tuple[float, float]]:
    r"""The RMSE of Wang & Tang's (2024) eq. 13 under each reading of its undefined :math:`n`, on x and y.

    Eq. 13 is :math:`\sqrt{\frac1n\sum (y_i - x_i)^2}` with ":math:`n` the number of samples". The
    samples may be the runs at each step (then averaged over the steps), the steps of each run (then
    averaged over the runs), or the steps of the estimate averaged over the runs first, which removes
    most of the noise and keeps the bias (lag after the turns). The last two readings put the
    :math:`1/n` outside the root, :math:`\sqrt{\sum e^2}/n`, a common slip when the formula is coded
    (MATLAB's ``sqrt(sum(e.^2))/n``): that is the RMSE divided by :math:`\sqrt n`, with :math:`n` the
    steps of each run or the runs at each step.

    Parameters
    ----------
    est : array_like, shape (runs, K, 4)
        Estimates :math:`[x, \dot x, y, \dot y]`.
    truth : array_like, shape (K, 4)
        True states.
    steps : array_like of bool, shape (K,)
        Steps used (:math:`n` counts the selected steps in the slip over steps).

    Returns
    -------
    dict of str to (float, float)
        RMSE on (x, y) in m for ``"over runs, per step"``, ``"over steps, per run"``,
        ``"of the run-averaged estimate"``, ``"√(Σe²)/n over steps, per run (1/n outside the root)"`` and
        ``"√(Σe²)/n over runs, per step (1/n outside the root)"``.
    """
    e_all = as_array(est, "est", ndim=3)
    tr = as_array(truth, "truth", ndim=2)
    if e_all.shape[1:] != tr.shape or e_all.shape[2] < 3:
        raise ValueError(f"truth must have shape {e_all.shape[1:]} (K, 4) to match est, got {tr.shape}")
    mask = np.asarray(steps, dtype=bool)
    if mask.shape != (tr.shape[0],) or not mask.any():
        raise ValueError(f"steps must be a boolean (K,) = ({tr.shape[0]},) array selecting at least one step")
    e = (e_all - tr)[:, mask][:, :, [0, 2]]
    runs, k = e.shape[:2]
    per_step = np.sqrt(np.mean(e**2, axis=0)).mean(axis=0)
    per_run = np.sqrt(np.mean(e**2, axis=1)).mean(axis=0)
    averaged = np.sqrt(np.mean(e.mean(axis=0) ** 2, axis=0))
    slip_steps = (np.sqrt(np.sum(e**2, axis=1)) / k).mean(axis=0)
    slip_runs = (np.sqrt(np.sum(e**2, axis=0)) / runs).mean(axis=0)
    return {"over runs, per step": (float(per_step[0]), float(per_step[1])),
            "over steps, per run": (float(per_run[0]), float(per_run[1])),
            "of the run-averaged estimate": (float(averaged[0]), float(averaged[1])),
            SLIP_STEPS: (float(slip_steps[0]), float(slip_steps[1])),
            SLIP_RUNS: (float(slip_runs[0]), float(slip_runs[1]))}


#: Keys of :func:`rmse_variants` for the slip :math:`\sqrt{\sum e^2}/n` (n = steps of a run, n = runs of a step).
SLIP_STEPS = "√(Σe²)/n over steps, per run (1/n outside the root)"
SLIP_RUNS = "√(Σe²)/n over runs, per step (1/n outside the root)"


@dataclass(frozen=True)
class QScaling:
    r"""CI with local filters whose process noise is scaled, no split and no feedback (:func:`q_scaling_study`).

    Attributes
    ----------
    scales : tuple of float
        Factors :math:`c` of the filters' :math:`cQ`.
    run_rmse : dict of float to ndarray, shape (runs,)
        Per-run RMSE on x over the steady steps on the path (m, rounded to mm), same noise for every scale.
    model_rmse : dict of float to ndarray, shape (nees_runs,)
        The same for targets that follow the model with the unscaled :math:`Q`.
    nees : dict of float to float
        Mean NEES of the fused estimate on those targets (4 if consistent).
    runs, nees_runs : int
    """

    scales: tuple[float, ...]
    run_rmse: dict[float, FloatArray]
    model_rmse: dict[float, FloatArray]
    nees: dict[float, float]
    runs: int
    nees_runs: int


def q_scaling_study(rng: np.random.Generator, R1: ArrayLike, R2: ArrayLike, Q: ArrayLike, scales: ArrayLike,
                    runs: int = 200, nees_runs: int = 100, T: float = 1.0, velocity_sigma: float = 100.0,
                    t_steady: float = 20.0) -> QScaling:
    r"""A control for the feedback gains: CI of two independent local filters that run :math:`cQ` instead of :math:`Q`.

    Split CI fed back (Wang & Tang 2024, Fig. 2) reports a covariance smaller than the truth, which gives
    the local filters smaller gains. Whether that alone explains its lower error on a path smoother than
    :math:`Q` allows is checked by giving smaller gains to CI without any split or feedback: the local
    filters run :math:`cQ`, the fusion rule is unchanged (:func:`fusion.filtering.tracks.fuse_tracks`,
    closed-form trace-optimal ω). Every scale sees the same measurement noise (paired runs), on the path of
    :func:`trajectory` and on targets that follow the model with the unscaled :math:`Q`.

    Parameters
    ----------
    rng : numpy.random.Generator
        Draws sensor 1's noise, sensor 2's noise, then the model targets and their noise.
    R1, R2 : array_like, shape (2, 2)
        Measurement covariances (m², diagonal).
    Q : array_like, shape (4, 4)
        The model's process noise (of the model targets; the filters run ``c Q``).
    scales : array_like of float, shape (S,)
        Factors :math:`c > 0`.
    runs, nees_runs : int
        Runs on the path and runs with targets that follow the model.
    T : float
        Sampling period (s).
    velocity_sigma : float
        Prior standard deviation of each velocity component (m/s).
    t_steady : float
        Start of the averaging window (s).

    Returns
    -------
    QScaling

    Raises
    ------
    ValueError
        Covariances not valid, counts or scales not positive, ``t_steady`` beyond the path.
    """
    as_rng(rng)
    runs, nees_runs = count(runs, "runs"), count(nees_runs, "nees_runs")
    R1, R2 = diagonal_covariance(R1, 2, "R1"), diagonal_covariance(R2, 2, "R2")
    Q = as_semidefinite(Q, 4, name="Q")
    cs = tuple(positive_scalar(c, "scales") for c in np.atleast_1d(as_array(scales, "scales", ndim=(0, 1))))
    s2 = std_scalar(velocity_sigma, "velocity_sigma") ** 2
    traj, model = trajectory(T), cv_model(T)
    t, X, F, H = traj.t, traj.states, model.F, model.H
    steady = t >= nonnegative_scalar(t_steady, "t_steady")
    if not steady.any():
        raise ValueError(f"t_steady = {t_steady} leaves no step of the path")
    K = t.size
    z, Xm = _path_and_model_measurements(rng, X, F, Q, R1, R2, runs, nees_runs)
    truth = np.concatenate([np.broadcast_to(X, (runs, K, 4)), Xm])
    P0d = np.diag([0.0, s2, 0.0, s2])
    out_path: dict[float, FloatArray] = {}
    out_model: dict[float, FloatArray] = {}
    out_nees: dict[float, float] = {}
    for c in cs:
        tracks = []
        for zj, R in zip(z, (R1, R2)):
            x0 = np.column_stack([zj[:, 0, 0], np.zeros(runs + nees_runs), zj[:, 0, 1], np.zeros(runs + nees_runs)])
            tracks.append(local_track(zj, F, H, c * Q, R, x0, P0d, np.diag([R[0, 0], 0.0, R[1, 1], 0.0])))
        f = fuse_tracks(tracks[0], tracks[1], "ci")
        e = f.est - truth
        out_path[c] = run_rmse(e[:runs], 0.0, steady, 0)
        out_model[c] = run_rmse(e[runs:], 0.0, steady, 0)
        out_nees[c] = round(float(np.mean(nees(e[runs:], f.P)[:, steady])), 4)
    return QScaling(scales=cs, run_rmse=out_path, model_rmse=out_model, nees=out_nees, runs=runs, nees_runs=nees_runs)


def _path_error(F: FloatArray, H: FloatArray, Qs: FloatArray, R: FloatArray, P0: FloatArray, X: FloatArray,
                mean0: FloatArray, cov0: FloatArray, components: tuple[int, ...] = (0, 2)) -> tuple[FloatArray, FloatArray]:
    r"""Mean and variance of the error of Kalman filters on the path, one per process noise of ``Qs`` (B, n, n).

    The Riccati recursion of :func:`fusion.filtering.kalman.gain_sequence` (Joseph form, as filterpy) and the
    error recursion of :func:`fusion.filtering.kalman.error_moments` in one loop, for a stack of filters that
    differ only in :math:`Q` (the same measurement noise ``R`` for the filter and the data). Returns arrays of
    shape (B, K, C) for the state ``components``; equal to those two functions to round-off (tested), faster on
    long paths.
    """
    B, n = Qs.shape[0], F.shape[0]
    comp = list(components)
    eye = np.eye(n)
    P = np.broadcast_to(P0, (B, n, n)).copy()
    b = np.broadcast_to(mean0, (B, n)).copy()
    C = np.broadcast_to(cov0, (B, n, n)).copy()
    K = X.shape[0]
    mx, vx = np.empty((B, K, len(comp))), np.empty((B, K, len(comp)))
    mx[:, 0], vx[:, 0] = b[:, comp], C[:, comp, comp]
    for k in range(1, K):
        Pm = F @ P @ F.T + Qs
        S = H @ Pm @ H.T + R
        G = np.swapaxes(np.linalg.solve(S, H @ Pm), 1, 2)
        A = eye - G @ H
        GRG = G @ R @ np.swapaxes(G, 1, 2)
        P = A @ Pm @ np.swapaxes(A, 1, 2) + GRG
        AF = A @ F
        b = np.einsum("bij,bj->bi", AF, b) - np.einsum("bij,j->bi", A, X[k] - F @ X[k - 1])
        C = AF @ C @ np.swapaxes(AF, 1, 2) + GRG
        mx[:, k], vx[:, k] = b[:, comp], C[:, comp, comp]
    return mx, vx


def _path_error_x(F: FloatArray, H: FloatArray, Qs: FloatArray, R: FloatArray, P0: FloatArray, X: FloatArray,
                  mean0: FloatArray, cov0: FloatArray) -> tuple[FloatArray, FloatArray]:
    """:func:`_path_error` on x only, arrays of shape (B, K)."""
    m, v = _path_error(F, H, Qs, R, P0, X, mean0, cov0, (0,))
    return m[..., 0], v[..., 0]


def path_by_period(periods: ArrayLike, sigma: float, delta0: float, readings: tuple[str, ...] = Q_READINGS,
                   velocity_sigma: float = 100.0, t_steady: float = 20.0) -> dict[tuple[float, str], dict[str, float]]:
    r"""On the simulated path: the RMSE of CI and of the centralised filter, and the straight-leg floor, against the period.

    Two identical sensors (noise ``sigma`` per axis); CI's closed-form weight is then 1/2 and CI returns the
    average of the two local filters. The RMSE over infinitely many runs is computed exactly from the
    filters' error mean and covariance on the path (:func:`fusion.filtering.kalman.error_moments`: lag plus
    noise, no Monte Carlo), at every step, then averaged over the steps with ``t >= t_steady``, as the
    chapter's "RMSE over runs per step". The straight-leg floor (:func:`straight_leg_floor`) is averaged over
    the straight-leg steps with ``t >= t_steady``.

    Parameters
    ----------
    periods : array_like of float
        Sampling periods (s), > 0.
    sigma : float
        Measurement noise of each sensor (m).
    delta0 : float
        :math:`\Delta_0` of the process noise (:func:`process_noise`).
    readings : tuple of str
        Readings of :data:`Q_READINGS` to run (a singular reading gets 1e-12 on its diagonal so that the
        initial covariance stays invertible; no effect at the printed digits).
    velocity_sigma : float
        Prior standard deviation of each velocity component (m/s).
    t_steady : float
        Start of the averaging window (s).

    Returns
    -------
    dict of (float, str) to dict
        Per (period, reading): ``"CI = average (m)"``, ``"CI = average, y (m)"``, ``"centralised KF (m)"`` (RMSE
        on x, or y) and the straight-leg floors, ``"straight-leg floor (m)"`` (the smoother's) and
        ``"causal straight-leg floor (m)"``.

    Raises
    ------
    ValueError
        Periods not positive, unknown reading, ``t_steady`` beyond the path.
    """
    sigma = std_scalar(sigma, "sigma")
    positive_scalar(delta0, "delta0")
    s2 = std_scalar(velocity_sigma, "velocity_sigma") ** 2
    nonnegative_scalar(t_steady, "t_steady")
    Ts = np.atleast_1d(as_array(periods, "periods", ndim=(0, 1)))
    if np.any(Ts <= 0):
        raise ValueError("periods must be positive")
    for rd in readings:
        one_of(rd, Q_READINGS, "readings")
    out: dict[tuple[float, str], dict[str, float]] = {}
    for Tp in (float(v) for v in Ts):
        traj, model = trajectory(Tp), cv_model(Tp)
        X, F, H = traj.states, model.F, model.H
        steady = traj.t >= t_steady
        if not steady.any():
            raise ValueError(f"t_steady = {t_steady} leaves no step of the path (period {Tp} s)")
        tl, on_leg, floor = straight_leg_floor(Tp, sigma)
        fl = float(floor[tl[on_leg] >= t_steady].mean())
        fl_causal = float(straight_leg_floor(Tp, sigma, causal=True)[2][tl[on_leg] >= t_steady].mean())
        Qs = []
        for rd in readings:
            Qp = process_noise(Tp, delta0, rd)
            Qs.append(Qp + 1e-12 * np.eye(4) if np.linalg.matrix_rank(Qp) < 4 else Qp)
        mean0 = np.array([0.0, -X[0, 1], 0.0, -X[0, 3]])   # first measurement as position, zero velocity
        Hc = np.vstack([H, H])
        # CI = the average of two identical filters: the same lag, half the noise covariance (independent sensors)
        b, c = _path_error(F, H, np.stack(Qs), sigma**2 * np.eye(2), np.diag([sigma**2, s2, sigma**2, s2]), X, mean0,
                           np.diag([sigma**2, 0.0, sigma**2, 0.0]))
        ci = np.sqrt(b**2 + c / 2)
        bc, cc = _path_error(F, Hc, np.stack(Qs), sigma**2 * np.eye(4), np.diag([sigma**2 / 2, s2, sigma**2 / 2, s2]),
                             X, mean0, np.diag([sigma**2 / 2, 0.0, sigma**2 / 2, 0.0]), (0,))
        central = np.sqrt(bc[..., 0]**2 + cc[..., 0])
        for j, rd in enumerate(readings):
            out[(Tp, rd)] = {"CI = average (m)": float(ci[j, steady, 0].mean()),
                             "CI = average, y (m)": float(ci[j, steady, 1].mean()),
                             "centralised KF (m)": float(central[j, steady].mean()),
                             "straight-leg floor (m)": fl, "causal straight-leg floor (m)": fl_causal}
    return out
