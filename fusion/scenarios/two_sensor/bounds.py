"""Readings of the source's process noise, the posterior Cramér-Rao bound, the straight-leg floor and the exact path
error by sampling period.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from fusion._validation import derived_inputs
from fusion._validation import (FloatArray, as_array, as_semidefinite, finite_result, instance_of, nonnegative_scalar,
                                one_of, positive_scalar, solve, std_scalar, step_scalar)
from fusion._validation import flag
from fusion._validation import LOOP_STEP, distinct, sequence, work
from fusion.filtering.kalman import cv_model
from fusion.scenarios.two_sensor.case import _PARAMS
from fusion.scenarios.two_sensor.case import _legs, trajectory

__all__ = ["Q_READINGS", "process_noise", "pcrb_steady", "straight_leg_floor", "path_by_period"]


#: Keys of :func:`path_by_period`'s entries that chapter 05 reads by these names (issue 36: named once): the RMSE
#: of CI as the average of the two filters (x), of the centralised filter, and the straight-leg floors.
CI_AVERAGE = "CI = average (m)"
CENTRALISED_KF = "centralised KF (m)"
STRAIGHT_LEG_FLOOR = "straight-leg floor (m)"
CAUSAL_FLOOR = "causal straight-leg floor (m)"

#: Readings of the source's process noise for :func:`pcrb_steady` (Δ₀ = 10 as printed).
Q_READINGS = ("as printed: Δ₀² I per step", "discrete white acceleration (G = [T²/2, T] per axis)",
              "continuous white acceleration (density Δ₀²)")


@finite_result("T and delta0")
def process_noise(T: float, delta0: float, reading: str) -> FloatArray:
    r"""The process-noise covariance of Wang & Tang's (2024) §3.2 under one reading of :data:`Q_READINGS`.

    As printed, :math:`Q = \Delta_0^2 I_4` per step whatever the period. With the noise gain read as the
    constant-velocity one, :math:`G = [T^2/2, T]^\top` per axis, :math:`Q = \Delta_0^2 GG^\top` per axis
    (discrete white acceleration); with continuous white acceleration of density :math:`\Delta_0^2`,
    :math:`Q = \Delta_0^2 [[T^3/3, T^2/2], [T^2/2, T]]` per axis (Bar-Shalom, Li & Kirubarajan 2001, §6.2-6.3).

    Parameters
    ----------
    T : float
        Sampling period (s), > 0 and at most ``1e150 ** (1/4)`` (its 4th power stays representable).
    delta0 : float
        :math:`\Delta_0`, > 0.
    reading : str
        One of :data:`Q_READINGS`.

    Returns
    -------
    ndarray, shape (4, 4)
        State order :math:`[x, \dot x, y, \dot y]`.

    Raises
    ------
    ValueError
        A bad argument, or ``T`` and ``delta0`` whose product overflows (named).
    """
    T = step_scalar(T, "T", 4)
    d2 = positive_scalar(delta0, "delta0") ** 2
    reading = one_of(reading, Q_READINGS, "reading")
    if reading == Q_READINGS[0]:
        return d2 * np.eye(4)
    if reading == Q_READINGS[1]:
        block = d2 * np.array([[T**4 / 4, T**3 / 2], [T**3 / 2, T**2]])
    else:
        block = d2 * np.array([[T**3 / 3, T**2 / 2], [T**2 / 2, T]])
    return np.kron(np.eye(2), block)


@_PARAMS("T", "sigma")
def pcrb_steady(T: float, sigma: float, Q: ArrayLike) -> float:
    r"""Steady-state posterior Cramér-Rao bound :math:`\sqrt{P_{xx}}` with both sensors, for targets that follow the model.

    For the linear-Gaussian model :math:`\mathbf x_{k+1} = F\mathbf x_k + \mathbf w_k`, two position sensors
    with noise ``sigma`` per axis, the PCRB is the centralised Kalman filter's filtered covariance
    (Tichavský, Muravchik & Nehorai 1998); its steady state solves the discrete algebraic Riccati
    equation (:func:`scipy.linalg.solve_discrete_are`).

    Parameters
    ----------
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


@_PARAMS("T", "sigma")
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
    flag(causal, "causal")
    turn_time = positive_scalar(turn_time, "turn_time")
    t = trajectory(T, legs=legs, turn_time=turn_time).t
    starts = np.cumsum([0.0, legs[0] + turn_time, legs[1] + turn_time])
    floor = np.full(t.size, np.nan)
    tol = 1e-9 * float(T)  # relative to the step: an absolute tolerance breaks in other time units
    for start, length in zip(starts, legs):
        on = (t >= start - tol) & (t <= start + length + tol)
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


#: Units (about 10 ns, ``fusion._limits.MAX_WORK``) of :func:`path_by_period`, twice the measured cost (fuzz 64b C3:
#: the old count, a path step x (readings + 1) x (LOOP_STEP + 64), missed the period's own cost, so 5,000 periods
#: in [40, 60] s ran 34.3 CPU-s accepted and 40,000 about 270): a period 1,300 ``LOOP_STEP`` (its trajectory, model,
#: two straight-leg floors and two error passes: 6.4 ms measured at 6 steps), a path step 14 ``LOOP_STEP`` and 1,500
#: units more a reading (58-70 us a step with one reading, 6.5 us more a reading, at T = 0.25-2 s). Measured with
#: ``time.process_time``, ``OPENBLAS_NUM_THREADS=1``, the least of three calls, machine shared.
_PERIOD_UNITS, _PATH_STEP_UNITS, _READING_STEP_UNITS = 1300 * LOOP_STEP, 14 * LOOP_STEP, 1500


def _path_units(periods: int, steps: float, readings: int) -> int:
    """The units of :func:`path_by_period` for ``periods`` periods of ``steps`` path steps in all and ``readings``
    readings (the weights above), exact for any count (a float of steps beyond 1e18 is capped there)."""
    return periods * _PERIOD_UNITS + int(min(steps, 1e18)) * (_PATH_STEP_UNITS + readings * _READING_STEP_UNITS)


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


@derived_inputs()
@finite_result("periods, sigma, delta0, velocity_sigma and t_steady")
@_PARAMS("velocity_sigma", "t_steady")
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
        Sampling periods (s), > 0, no two equal (the results are keyed by period).
    sigma : float
        Measurement noise of each sensor (m).
    delta0 : float
        :math:`\Delta_0` of the process noise (:func:`process_noise`).
    readings : tuple of str
        Readings of :data:`Q_READINGS` to run, no two equal (a singular reading gets 1e-12 on its diagonal so that the
        initial covariance stays invertible; no effect at the printed digits).

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
    delta0 = positive_scalar(delta0, "delta0")  # the floats read (fuzz 22b, FR)
    s2 = std_scalar(velocity_sigma, "velocity_sigma") ** 2
    t_steady = nonnegative_scalar(t_steady, "t_steady")
    Ts = np.atleast_1d(as_array(periods, "periods", ndim=(0, 1)))
    if np.any(Ts <= 0):
        raise ValueError("periods must be positive")
    items = sequence(readings, "readings", minimum=1, what="reading")
    # rule 17: each period's path has duration / T samples, a filter step per sample and reading; by len(readings)
    # and the periods' array before any entry is read or hashed (fuzz 62b C3: 10**7 readings were each checked by
    # one_of first, refused after 8.7-9.9 CPU-s)
    steps = float(np.sum(np.floor(float(trajectory(1.0).t[-1]) / Ts) + 1.0))
    work((1,), "periods and readings", weight=_path_units(Ts.size, steps, len(items)))
    readings = tuple(one_of(rd, Q_READINGS, "readings") for rd in items)
    distinct(Ts.tolist(), "periods")  # the results are keyed by (period, reading)
    distinct(list(readings), "readings")  # a repeat was run, counted and merged into one key (fuzz 66b D1)
    out: dict[tuple[float, str], dict[str, float]] = {}
    for Tp in (float(v) for v in Ts):
        traj, model = trajectory(Tp), cv_model(Tp)
        X, F, H = traj.states, model.F, model.H
        steady = traj.t >= t_steady
        if not steady.any():
            raise ValueError(f"t_steady = {t_steady} leaves no step of the path sampled with periods entry {Tp} s "
                             f"(its last step is at {float(traj.t[-1]):.6g} s): lower t_steady, or that entry of "
                             "periods")
        tl, on_leg, floor = straight_leg_floor(Tp, sigma)
        if not (tl[on_leg] >= t_steady).any():   # fuzz 64b D1: an empty mean was refused as an overflow
            last = (f"its last straight-leg step is at {float(tl[on_leg][-1]):.6g} s): lower t_steady, or"
                    if on_leg.any() else "no leg has two of its samples): lower")
            raise ValueError(f"t_steady = {t_steady} leaves no straight-leg step of the path sampled with periods "
                             f"entry {Tp} s ({last} that entry of periods")
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
            out[(Tp, rd)] = {CI_AVERAGE: float(ci[j, steady, 0].mean()),
                             "CI = average, y (m)": float(ci[j, steady, 1].mean()),
                             CENTRALISED_KF: float(central[j, steady].mean()),
                             STRAIGHT_LEG_FLOOR: fl, CAUSAL_FLOOR: fl_causal}
    return out
