"""The source's Fig. 3 case: the three-leg target path, the two sensors, their local filters and the centralised
filter.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from fusion._docstrings import ParameterDocs
from fusion._results import ResultSpec, array, nested, trusted, validated_post_init
from fusion._validation import read_once
from fusion._validation import derived_inputs
from fusion._validation import (FloatArray, allocation, as_array, as_rng, as_semidefinite, count, diagonal_covariance,
                                finite_result, grid_points, positive_scalar, psd_factor, std_scalar)
from fusion._validation import LOOP_STEP, loop_work, work
from fusion._limits import DENSE_CUBE, dense_work
from fusion._counts import input_allocation
from fusion.filtering.kalman import cv_model, filter_runs, gain_sequence
from fusion.filtering.tracks import LocalTrack, _named_track

__all__ = ["Trajectory", "trajectory", "model_truth", "Scenario", "two_sensor_scenario"]

#: The parameters the package's studies share, documented once (``@_PARAMS("T", "sigma")``).
_PARAMS = ParameterDocs({
    "rng": "numpy.random.Generator\n    Draws sensor 1's noise, sensor 2's noise, then the model targets and their noise.",
    "R1, R2": "array_like, shape (2, 2)\n    Measurement covariances (m², diagonal).",
    "runs, nees_runs": "int\n    Runs on the path and runs with targets that follow the model (>= 1).",
    "T": "float\n    Sampling period (s), > 0.",
    "sigma": "float\n    Measurement noise standard deviation of each sensor (m), > 0.",
    "velocity_sigma": "float\n    Prior standard deviation of each velocity component (m/s).",
    "t_steady": "float\n    Start of the averaging window (s).",
    "seeds": "array_like of int, shape (S,)\n    FOA run ``i`` uses ``numpy.random.default_rng(seeds[i])``.",
    "population, iterations": "int\n    FOA swarm size and generations (30 × 200 in the source).",
})


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

    __result_spec__ = ResultSpec({"t": array("K", increasing=True), "states": array("K", 4)})
    __post_init__ = validated_post_init


@_PARAMS("T")
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
    grid_points(total, T, "T, legs and turn_time")  # the steps k*T, checked before the fine grid is computed
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
    # steps k*T up to total, with a tolerance relative to T (an absolute one breaks in other time units)
    t = np.arange(int(np.floor(total / T + 1e-9)) + 1) * T
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


@finite_result("F, Q and x0")
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
        Process-noise covariance, symmetric positive semidefinite (it may be singular: its Cholesky
        factor when positive definite, else its symmetric square root from the eigendecomposition).
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
        ``Q`` not a symmetric positive-semidefinite matrix of the size of ``F``.
    """
    as_rng(rng)
    F = as_array(F, "F", ndim=2)
    if F.shape[0] != F.shape[1]:
        raise ValueError(f"F must be square, got shape {F.shape}")
    # rule 17 (fuzz 38a C9): Q's check and factor, 0.19 ns a n**3 measured (n = 4,800: 21 CPU-s)
    dense_work(1, F.shape[0], "F and Q", 2 * DENSE_CUBE)
    Q = as_semidefinite(Q, F.shape[0], name="Q")
    x0 = as_array(x0, "x0", shape=(F.shape[0],))
    n_steps, runs = count(n_steps, "n_steps"), count(runs, "runs")
    allocation((runs, n_steps, F.shape[0]), "runs, n_steps and F")
    # rule 17: a Python step of two small products, about 3.3 us measured (budget35: 10**7 steps, ~32 CPU-s, were
    # accepted), plus two units a run's state entry
    loop_work((n_steps,), 2 * runs * F.shape[0] ** 2, "n_steps, runs and F", step=LOOP_STEP // 3)
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

    Arrays are read-only. Built with ``dataclasses.replace`` or directly, every field is checked
    (``fusion._results``): finite, ``t`` strictly increasing, the tracks of the same runs, ``K``
    steps and state ``[x, vx, y, vy]`` (the local tracks measuring the two positions); otherwise a
    :class:`ValueError` naming the field (``Scenario.t: ...``).

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

    __result_spec__ = ResultSpec({"t": array("K", increasing=True), "truth": array("K", 4),
                                  "tracks": nested(LocalTrack, count=2, runs="runs", K="K", n=4, m=2),
                                  "central": nested(LocalTrack, runs="runs", K="K", n=4)})
    __post_init__ = validated_post_init


def _scenario_budget(runs: int, n_steps: int, names: str) -> int:
    """Rules 9 and 17 of :func:`two_sensor_scenario` on ``runs`` runs of ``n_steps`` steps, naming ``names``; its units.

    The memory of the states; the input budget of the central filter's stacked measurements ``(runs, n_steps, 4)``,
    the largest array the scenario passes on (``filter_runs`` refused it, or a local track's ``(runs, n_steps, 2)``,
    after the first track's draws and filter: 70,000 runs of 261 steps ran 3.1 CPU-s, then were refused naming every
    argument, fuzz 54a D4); the work of two local filters, their gains and the centralised filter, about 0.5 us a
    run and step measured (budget35: 1.6 CPU-s for 12,600 runs of 261 steps; with a memory budget only, 250,000 runs,
    ~33 CPU-s, ran), and each step's own cost, 12 ``LOOP_STEP`` (twice 51 us measured: 0.51 and 2.06 CPU-s for one
    run of 10,000 and 40,000 steps, ``time.process_time``, ``OPENBLAS_NUM_THREADS=1``, machine shared; audit after
    fuzz 64b: with the runs alone counted, one run of 400,000 steps, about 20 CPU-s, was accepted, its edge set by the
    local tracks' own budgets). A chapter study that runs several scenarios sums the units (fuzz 54a D4).
    """
    allocation((runs, n_steps, 4), names)
    input_allocation((runs, n_steps, 4), names)
    return work((n_steps, _SCENARIO_STEP + 50 * runs), names)


#: Units of a step of :func:`two_sensor_scenario` whatever its runs (``_scenario_budget``).
_SCENARIO_STEP = 12 * LOOP_STEP


@derived_inputs()
@finite_result("R_a, R_b, Q, T and velocity_sigma")
@_PARAMS("velocity_sigma")
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

    Returns
    -------
    Scenario
        Truth, measurements and the two local tracks of every run.

    Raises
    ------
    ValueError
        ``runs`` not positive, ``velocity_sigma`` not positive, covariances not valid.
    """
    R_a, R_b, Q = (read_once(R_a, "R_a"), read_once(R_b, "R_b"), read_once(Q, "Q"))  # converted once (fuzz 29a C5)
    as_rng(rng)
    runs = count(runs, "runs")
    traj, model = trajectory(T), cv_model(T)
    t, X, F, H = traj.t, traj.states, model.F, model.H
    _scenario_budget(runs, t.size, "runs and T")
    s2 = std_scalar(velocity_sigma, "velocity_sigma") ** 2
    tracks = []
    for name, R in (("R_a", R_a), ("R_b", R_b)):
        R = diagonal_covariance(R, 2, name)
        z = X[None, :, [0, 2]] + rng.standard_normal((runs, t.size, 2)) * np.sqrt(np.diag(R))
        x0 = np.column_stack([z[:, 0, 0], np.zeros(runs), z[:, 0, 1], np.zeros(runs)])
        tracks.append(_named_track("velocity_sigma", z, F, H, Q, R, x0, np.diag([0.0, s2, 0.0, s2]),
                                   np.diag([R[0, 0], 0.0, R[1, 1], 0.0])))
    a, b = tracks
    Hc = np.vstack([H, H])
    Rc = np.zeros((4, 4))
    Rc[:2, :2], Rc[2:, 2:] = diagonal_covariance(R_a, 2, "R_a"), diagonal_covariance(R_b, 2, "R_b")
    xc0, Pc0 = _central_start(a.est[:, 0], b.est[:, 0], a.gains.P[0], b.gains.P[0], np.diag([0.0, s2, 0.0, s2]))
    gc = gain_sequence(F, Hc, Q, Rc, Pc0, t.size)
    zc = np.concatenate([a.z, b.z], axis=2)
    # the private constructor: fields computed here from validated arguments
    central = trusted(LocalTrack, z=zc, gains=gc, est=filter_runs(zc, gc, xc0), Pd=gc.P, Pi=np.zeros_like(gc.P))
    return trusted(Scenario, t=t, truth=X, tracks=(a, b), central=central)
