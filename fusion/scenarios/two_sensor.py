r"""The two-sensor 2-D tracking case of Wang & Tang (2024, §3.2), vectorised over runs.

A target on a three-leg path (:func:`trajectory`), two position sensors, a local
constant-velocity Kalman filter per sensor and the centralised filter on both sensors'
measurements (:func:`two_sensor_scenario`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from fusion._validation import FloatArray, as_array, as_covariance, as_rng, as_semidefinite, count, positive_scalar, psd_factor
from fusion.filtering.kalman import cv_model, filter_runs, gain_sequence
from fusion.filtering.tracks import LocalTrack, local_track

__all__ = ["trajectory", "model_truth", "Scenario", "two_sensor_scenario"]


def trajectory(
    T: float = 1.0,
    speed: float = 50.0,
    start: tuple[float, float] = (300.0, 0.0),
    legs: tuple[float, float, float] = (100.0, 30.0, 90.0),
    turn_time: float = 20.0,
) -> tuple[FloatArray, FloatArray]:
    r"""Target of source 000's Fig. 3: along +y, turn to +x, along +x, turn to +y, along +y.

    Constant speed; each turn is a coordinated 90° turn at constant rate over ``turn_time``.
    With the defaults (50 m/s, legs 100, 30 and 90 s, turns of 20 s, start (300, 0) m) the
    path stays inside the source's area [0, 3500] × [0, 12000] m.

    Returns
    -------
    t : ndarray, shape (K,)
        Sample times (s), spacing ``T``.
    states : ndarray, shape (K, 4)
        True :math:`[x, \dot x, y, \dot y]`.
    """
    T = positive_scalar(T, "T")
    speed = positive_scalar(speed, "speed")
    turn_time = positive_scalar(turn_time, "turn_time")
    # heading measured from +x; 90° = +y
    seg = [(legs[0], 0.0), (turn_time, -np.pi / 2 / turn_time), (legs[1], 0.0),
           (turn_time, np.pi / 2 / turn_time), (legs[2], 0.0)]
    total = sum(d for d, _ in seg)
    dt = min(T, 0.01)
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
    return t, states



def model_truth(rng: np.random.Generator, F: ArrayLike, Q: ArrayLike, x0: ArrayLike, n_steps: int, runs: int) -> FloatArray:
    r"""Targets that follow the model: :math:`\mathbf x_{k+1} = F\mathbf x_k + \mathbf w_k`, :math:`\mathbf w_k \sim N(0, Q)`.

    The process noise is common to every sensor watching the target, which is what makes the
    errors of two local filters correlated. ``Q`` may be singular (positive semidefinite, e.g.
    white acceleration on the velocities only); ``x0`` is one state (n,) shared by all runs.

    Returns
    -------
    ndarray, shape (runs, n_steps, 4)
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



@dataclass(frozen=True)
class Scenario:
    """Source 000's two-sensor tracking case: truth, both local tracks and the centralised filter.

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
    """Simulate source 000's §3.2 case on the path of :func:`trajectory`, vectorised over runs.

    Each filter starts at its first measurement with zero velocity; the initial covariance is
    ``diag(R[0,0], s^2, R[1,1], s^2)`` with ``s = velocity_sigma`` (m/s). The velocity part is
    common to both sensors (the same unknown target velocity), the position part is each
    sensor's own noise.

    Parameters
    ----------
    R_a, R_b : array_like, shape (2, 2)
        Measurement covariances of the two sensors (m²), diagonal.
    Q : array_like, shape (4, 4)
        Process noise used by the filters.
    rng : numpy.random.Generator
        Draws sensor a's noise for all runs, then sensor b's.
    runs : int
    T : float
        Sampling period (s).
    velocity_sigma : float
        Prior standard deviation of each velocity component (m/s).
    """
    as_rng(rng)
    runs = count(runs, "runs")
    t, X = trajectory(T)
    F, H = cv_model(T)
    s2 = positive_scalar(velocity_sigma, "velocity_sigma") ** 2
    tracks = []
    for name, R in (("R_a", R_a), ("R_b", R_b)):
        R = as_covariance(R, dim=2, name=name)
        z = X[None, :, [0, 2]] + rng.standard_normal((runs, t.size, 2)) * np.sqrt(np.diag(R))
        x0 = np.column_stack([z[:, 0, 0], np.zeros(runs), z[:, 0, 1], np.zeros(runs)])
        tracks.append(local_track(z, F, H, Q, R, x0, np.diag([0.0, s2, 0.0, s2]), np.diag([R[0, 0], 0.0, R[1, 1], 0.0])))
    a, b = tracks
    Hc = np.vstack([H, H])
    Rc = np.zeros((4, 4))
    Rc[:2, :2], Rc[2:, 2:] = as_covariance(R_a, dim=2), as_covariance(R_b, dim=2)
    Pc0 = np.linalg.inv(np.linalg.inv(a.gains.P[0]) + np.linalg.inv(b.gains.P[0]))
    gc = gain_sequence(F, Hc, Q, Rc, Pc0, t.size)
    zc = np.concatenate([a.z, b.z], axis=2)
    central = LocalTrack(z=zc, gains=gc, est=filter_runs(zc, gc, (a.est[:, 0] + b.est[:, 0]) / 2),
                         Pd=gc.P, Pi=np.zeros_like(gc.P))
    return Scenario(t=t, truth=X, tracks=(a, b), central=central)
