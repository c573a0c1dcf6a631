r"""Two-sensor 2-D tracking scenario of source 000 (§3.2), vectorised over Monte-Carlo runs.

State :math:`\mathbf x = [x, \dot x, y, \dot y]^\top` (m, m/s), constant-velocity model

.. math:: F = \begin{bmatrix}1&T&0&0\\0&1&0&0\\0&0&1&T\\0&0&0&1\end{bmatrix},\qquad
          H = \begin{bmatrix}1&0&0&0\\0&0&1&0\end{bmatrix},

process noise :math:`Q` on the full state as printed, measurement noise
:math:`R_j = \mathrm{diag}(\Delta_j^2, \Delta_j^2)`.

A Kalman filter's gains and covariances do not depend on the measurements, so they are
computed once with filterpy and every run is then propagated at once with numpy. The same
holds for every fusion rule here (their weights depend on covariances only).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from filterpy.kalman import KalmanFilter
from numpy.typing import ArrayLike

from fusion import estimates as es
from fusion._validation import FloatArray, as_covariance, as_semidefinite, one_of, positive_scalar

__all__ = [
    "cv_model",
    "trajectory",
    "GainSequence",
    "gain_sequence",
    "split_covariances",
    "filter_runs",
    "rmse_per_step",
    "model_truth",
    "nees",
    "LocalTrack",
    "local_track",
    "FusedTracks",
    "fuse_tracks",
    "Scenario",
    "two_sensor_scenario",
]


def cv_model(T: float) -> tuple[FloatArray, FloatArray]:
    """Constant-velocity ``F`` (4x4) and position-measurement ``H`` (2x4) for period ``T`` (s)."""
    T = positive_scalar(T, "T")
    F = np.array([[1.0, T, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, T], [0.0, 0.0, 0.0, 1.0]])
    H = np.array([[1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]])
    return F, H


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


@dataclass(frozen=True)
class GainSequence:
    """Kalman gains and covariances of one filter, independent of the data.

    Attributes
    ----------
    K : ndarray, shape (K, 4, m)
        Gains at steps 1..K-1 (``K[0]`` is unused: step 0 is the initialisation).
    P : ndarray, shape (K, 4, 4)
        Filtered covariances.
    F, H : ndarray
        Model matrices.
    """

    K: FloatArray
    P: FloatArray
    F: FloatArray
    H: FloatArray


def gain_sequence(F: ArrayLike, H: ArrayLike, Q: ArrayLike, R: ArrayLike, P0: ArrayLike, n_steps: int) -> GainSequence:
    """Run filterpy's :class:`KalmanFilter` covariance recursion once and record gains and P.

    ``Q`` may be singular (positive semidefinite); ``R`` and ``P0`` must be positive definite.
    """
    F = np.asarray(F, dtype=float)
    H = np.asarray(H, dtype=float)
    n, m = F.shape[0], H.shape[0]
    Q = as_semidefinite(Q, dim=n, name="Q")
    R = as_covariance(R, dim=m, name="R")
    P0 = as_covariance(P0, dim=n, name="P0")
    kf = KalmanFilter(dim_x=n, dim_z=m)
    kf.F, kf.H, kf.Q, kf.R, kf.P = F, H, Q, R, P0
    Ks = np.zeros((n_steps, n, m))
    Ps = np.zeros((n_steps, n, n))
    Ps[0] = P0
    for k in range(1, n_steps):
        kf.predict()
        kf.update(np.zeros(m))  # the gain and P do not depend on the measurement
        Ks[k], Ps[k] = kf.K, kf.P
    return GainSequence(K=Ks, P=Ps, F=F, H=H)


def split_covariances(gains: GainSequence, Q: ArrayLike, R: ArrayLike, P0d: ArrayLike, P0i: ArrayLike) -> tuple[FloatArray, FloatArray]:
    r"""Split each filtered covariance into a process-noise part and a measurement part.

    With :math:`A = I - K H`: :math:`P_d^+ = A(F P_d F^\top + Q)A^\top` (errors shared by every
    filter of the same target: process noise, common initial velocity) and
    :math:`P_i^+ = A F P_i F^\top A^\top + K R K^\top` (this sensor's own noise). Their sum is the
    filter's covariance (Joseph form).

    Returns
    -------
    Pd, Pi : ndarray, shape (K, 4, 4)
    """
    F, H = gains.F, gains.H
    Q = np.asarray(Q, dtype=float)
    R = np.asarray(R, dtype=float)
    n = F.shape[0]
    Pd = np.zeros_like(gains.P)
    Pi = np.zeros_like(gains.P)
    Pd[0], Pi[0] = np.asarray(P0d, float), np.asarray(P0i, float)
    for k in range(1, gains.P.shape[0]):
        A = np.eye(n) - gains.K[k] @ H
        Pd[k] = A @ (F @ Pd[k - 1] @ F.T + Q) @ A.T
        Pi[k] = A @ F @ Pi[k - 1] @ F.T @ A.T + gains.K[k] @ R @ gains.K[k].T
    return Pd, Pi


def filter_runs(z: ArrayLike, gains: GainSequence, x0: ArrayLike) -> FloatArray:
    """Propagate the filter over every run at once.

    Parameters
    ----------
    z : array_like, shape (runs, K, m)
        Measurements.
    gains : GainSequence
    x0 : array_like, shape (runs, 4)
        Initial estimates (step 0).

    Returns
    -------
    ndarray, shape (runs, K, 4)
        Filtered estimates.
    """
    zz = np.asarray(z, dtype=float)
    x = np.array(x0, dtype=float)
    runs, K, _ = zz.shape
    out = np.empty((runs, K, gains.F.shape[0]))
    out[:, 0] = x
    for k in range(1, K):
        xp = x @ gains.F.T
        x = xp + (zz[:, k] - xp @ gains.H.T) @ gains.K[k].T
        out[:, k] = x
    return out


def rmse_per_step(estimates: ArrayLike, truth: ArrayLike) -> FloatArray:
    """Root-mean-square error over runs at each step, per state component.

    Parameters
    ----------
    estimates : array_like, shape (runs, K, 4)
    truth : array_like, shape (K, 4)

    Returns
    -------
    ndarray, shape (K, 4)
    """
    e = np.asarray(estimates, dtype=float) - np.asarray(truth, dtype=float)[None]
    return np.sqrt(np.mean(e**2, axis=0))


def model_truth(rng: np.random.Generator, F: ArrayLike, Q: ArrayLike, x0: ArrayLike, n_steps: int, runs: int) -> FloatArray:
    r"""Targets that follow the model: :math:`\mathbf x_{k+1} = F\mathbf x_k + \mathbf w_k`, :math:`\mathbf w_k \sim N(0, Q)`.

    The process noise is common to every sensor watching the target, which is what makes the
    errors of two local filters correlated.

    Returns
    -------
    ndarray, shape (runs, n_steps, 4)
    """
    F = np.asarray(F, dtype=float)
    Q = as_covariance(Q, dim=F.shape[0], name="Q")
    L = np.linalg.cholesky(Q)
    out = np.empty((runs, n_steps, F.shape[0]))
    out[:, 0] = np.asarray(x0, dtype=float)
    for k in range(1, n_steps):
        out[:, k] = out[:, k - 1] @ F.T + rng.standard_normal((runs, F.shape[0])) @ L.T
    return out


def nees(errors: ArrayLike, covariances: ArrayLike) -> FloatArray:
    r"""Normalised estimation error squared :math:`e^\top P^{-1} e` for every estimate.

    Its mean over runs and steps is the state dimension for a consistent filter (smaller for a
    conservative one, larger for an overconfident one).

    Parameters
    ----------
    errors : array_like, shape (..., d)
        Estimate minus truth.
    covariances : array_like, shape (..., d, d)
        The reported covariances, broadcastable against ``errors`` (e.g. (K, d, d) shared by
        all runs of (runs, K, d) errors); symmetric positive definite.

    Returns
    -------
    ndarray, shape of ``errors`` without the last axis (after broadcasting)

    Raises
    ------
    ValueError
        Non-finite input, mismatched shapes, covariances not symmetric positive definite.
    """
    e = np.asarray(errors, dtype=float)
    P = np.asarray(covariances, dtype=float)
    if e.ndim < 1 or P.ndim < 2 or P.shape[-2:] != (e.shape[-1], e.shape[-1]):
        raise ValueError(f"errors (..., d) and covariances (..., d, d) do not match: {e.shape}, {P.shape}")
    if not (np.all(np.isfinite(e)) and np.all(np.isfinite(P))):
        raise ValueError("errors and covariances must be finite")
    if not np.allclose(P, np.swapaxes(P, -1, -2), rtol=1e-9, atol=0.0):
        raise ValueError("covariances must be symmetric")
    try:
        L = np.linalg.cholesky(P)
    except np.linalg.LinAlgError:
        raise ValueError("covariances must be positive definite") from None
    L, eb = np.broadcast_arrays(L, e[..., None])
    y = np.linalg.solve(L, eb)[..., 0]
    return np.sum(y**2, axis=-1)


@dataclass(frozen=True)
class LocalTrack:
    """One sensor's Kalman filter over every Monte-Carlo run.

    Attributes
    ----------
    z : ndarray, shape (runs, K, m)
        Measurements.
    gains : GainSequence
        Gains and filtered covariances (shared by the runs).
    est : ndarray, shape (runs, K, n)
        Filtered estimates.
    Pd, Pi : ndarray, shape (K, n, n)
        The covariance split of :func:`split_covariances` (``Pd + Pi = gains.P``).
    """

    z: FloatArray
    gains: GainSequence
    est: FloatArray
    Pd: FloatArray
    Pi: FloatArray


def local_track(
    z: ArrayLike, F: ArrayLike, H: ArrayLike, Q: ArrayLike, R: ArrayLike,
    x0: ArrayLike, P0d: ArrayLike, P0i: ArrayLike,
) -> LocalTrack:
    """Run one sensor's filter on all runs: gains (filterpy), estimates and the covariance split.

    Parameters
    ----------
    z : array_like, shape (runs, K, m)
    F, H, Q, R : array_like
        Model (``Q`` may be zero).
    x0 : array_like, shape (runs, n)
        Initial estimates.
    P0d, P0i : array_like, shape (n, n)
        Initial covariance, split into the part shared with other sensors (``P0d``, e.g. an
        unknown initial velocity) and this sensor's own part (``P0i``); their sum is ``P0``.
    """
    zz = np.asarray(z, dtype=float)
    if zz.ndim != 3 or not np.all(np.isfinite(zz)):
        raise ValueError(f"z must be a finite (runs, K, m) array, got shape {zz.shape}")
    n = np.shape(F)[0]
    x = np.asarray(x0, dtype=float)
    if x.shape != (zz.shape[0], n) or not np.all(np.isfinite(x)):
        raise ValueError(f"x0 must be a finite ({zz.shape[0]}, {n}) array, got shape {x.shape}")
    P0d = as_semidefinite(P0d, dim=n, name="P0d")
    P0i = as_semidefinite(P0i, dim=n, name="P0i")
    P0 = P0d + P0i
    g = gain_sequence(F, H, Q, R, P0, zz.shape[1])
    Pd, Pi = split_covariances(g, Q, R, P0d, P0i)
    return LocalTrack(z=zz, gains=g, est=filter_runs(zz, g, x), Pd=Pd, Pi=Pi)


@dataclass(frozen=True)
class FusedTracks:
    """Output of :func:`fuse_tracks`.

    Attributes
    ----------
    est : ndarray, shape (runs, K, n)
        Fused estimates.
    P : ndarray, shape (K, n, n), or None
        Covariance the rule reports (``None`` for fuzzy clustering, which defines none).
    omega : ndarray, shape (K,)
        Weight used at each step (``nan`` for rules without one).
    """

    est: FloatArray
    P: FloatArray | None
    omega: FloatArray


RULES = ("ci", "convex", "split", "printed", "fuzzy")


def fuse_tracks(
    a: LocalTrack, b: LocalTrack, rule: str, omega: float | ArrayLike | None = None, criterion: str = "trace",
) -> FusedTracks:
    r"""Fuse two local tracks at every step, all runs at once.

    Every rule except fuzzy clustering is linear, :math:`\hat x = W_1\hat x_1 + W_2\hat x_2`, with
    gains that depend on the covariances only; they are computed once per step and applied to
    every run.

    Parameters
    ----------
    a, b : LocalTrack
        The two sensors' tracks (same steps, runs and state).
    rule : {"ci", "convex", "split", "printed", "fuzzy"}
        Covariance intersection (:func:`fusion.estimates.covariance_intersection`), convex
        combination, split CI, split CI with source 000's eqs. 11-12 as printed (one
        :math:`\omega` for both sensors), fuzzy clustering
        (:func:`fusion.estimates.fuzzy_cluster_fusion`).
    omega : float, array_like of shape (K,), or None
        Weight for "ci", "split" and "printed": one for every step, one per step (e.g. chosen by
        an optimiser), or ``None`` to minimise ``criterion`` at each step.
    criterion : {"trace", "det"}

    Returns
    -------
    FusedTracks
    """
    one_of(rule, RULES, "rule")
    if a.est.shape != b.est.shape:
        raise ValueError(f"the tracks must have the same shape, got {a.est.shape} and {b.est.shape}")
    runs, K, n = a.est.shape
    if omega is None:
        ws = [None] * K
    else:
        w_arr = np.broadcast_to(np.asarray(omega, dtype=float), (K,))
        ws = [float(w) for w in w_arr]
    if rule == "fuzzy":
        Ps = np.stack([a.gains.P, b.gains.P], axis=1)  # (K, 2, n, n)
        X = np.stack([a.est, b.est], axis=2)  # (runs, K, 2, n)
        est = np.stack([es.fuzzy_cluster_fusion(X[:, k], Ps[k]).x for k in range(K)], axis=1)
        return FusedTracks(est=est, P=None, omega=np.full(K, np.nan))
    est = np.empty_like(a.est)
    P_out = np.empty((K, n, n))
    used = np.full(K, np.nan)
    zero = np.zeros(n)
    for k in range(K):
        P1, P2 = a.gains.P[k], b.gains.P[k]
        if rule == "ci":
            r = es.covariance_intersection(zero, P1, zero, P2, omega=ws[k], criterion=criterion)  # type: ignore[arg-type]
            W1 = r.omega * r.P @ np.linalg.inv(P1)
            W2 = (1.0 - r.omega) * r.P @ np.linalg.inv(P2)
        elif rule == "convex":
            r = es.convex_combination(zero, P1, zero, P2)
            W1, W2 = r.P @ np.linalg.inv(P1), r.P @ np.linalg.inv(P2)
        else:
            r = es.split_covariance_intersection(zero, a.Pd[k], a.Pi[k], zero, b.Pd[k], b.Pi[k], omega=ws[k],
                                                 criterion=criterion, same_omega=(rule == "printed"))  # type: ignore[arg-type]
            w2 = r.omega if rule == "printed" else 1.0 - r.omega
            W1 = r.P @ np.linalg.inv(a.Pd[k] / r.omega + a.Pi[k])
            W2 = r.P @ np.linalg.inv(b.Pd[k] / w2 + b.Pi[k])
        est[:, k] = a.est[:, k] @ W1.T + b.est[:, k] @ W2.T
        P_out[k] = r.P
        used[k] = r.omega
    return FusedTracks(est=est, P=P_out, omega=used)


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
    if runs < 1:
        raise ValueError(f"runs must be positive, got {runs}")
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
