r"""Round-off estimate of the covariance recursion of ``fusion.registration.methods``' Kalman filter (fix 57d).

The filter's covariance (Joseph form, as filterpy) loses its digits when the prior is far above the posterior and no
process noise refills it (a diffuse prior against a tiny measurement noise): it then returns a plausible wrong gain.
The same covariances are recomputed here in information form (each update
:math:`P = (P^{-1} + H^\top H/\sigma^2)^{-1}`), which rounds differently; their per-entry discrepancy, relative
to :math:`\sqrt{P_{aa}P_{bb}}`, estimates the round-off of both (the model of
``fusion.scenarios.range_bearing_bounds``' linearised errors, fix 56b).
"""

from __future__ import annotations

from collections.abc import Callable, Hashable

import numpy as np

from fusion._shown import shown
from fusion._validation import FloatArray

__all__: list[str] = []


def discrepancy(P: FloatArray, P2: FloatArray) -> FloatArray:
    """Per covariance of a stack, the largest ``|P - P2|_ab / sqrt(P2_aa P2_bb)`` (inf where not finite or where a
    variance of ``P2`` is not positive)."""
    d = np.sqrt(np.abs(np.diagonal(P2, axis1=-2, axis2=-1)))
    with np.errstate(over="ignore", under="ignore", divide="ignore", invalid="ignore"):
        r = np.abs(P - P2) / (d[..., :, None] * d[..., None, :])
        r = np.where(P == P2, 0.0, r)
    r = np.where(np.isnan(r), np.inf, r)
    return r.reshape(r.shape[0], -1).max(axis=1)


def information_form(F: FloatArray, Q: FloatArray, is_sample: np.ndarray, r2: float, P0: FloatArray,
                     update_first: bool) -> tuple[FloatArray, FloatArray]:
    """The filtered and predicted covariances at every node of the grid (``F[m]``, ``Q[m]``: the step into node
    ``m``; ``F[0]``, ``Q[0]`` unused; node 0's predicted covariance is its filtered one), each update in information
    form; inf from the first node where an inversion fails (a covariance singular to working precision)."""
    M = len(F)
    P, Pp = np.full((M, 3, 3), np.inf), np.full((M, 3, 3), np.inf)
    info = np.zeros((3, 3))
    info[0, 0] = 1.0 / r2                                   # H^T H / sigma^2 with H = [1, 0, 0]
    inv = np.linalg.inv
    try:
        Pm = np.array(P0, dtype=float)
        if update_first:
            Pm = inv(inv(Pm) + info)
        P[0] = Pp[0] = Pm
        for m in range(1, M):
            Pm = F[m] @ Pm @ F[m].T + Q[m]
            Pp[m] = Pm
            if is_sample[m]:
                Pm = inv(inv(Pm) + info)
                Pm = 0.5 * (Pm + Pm.T)
            P[m] = Pm
    except np.linalg.LinAlgError:
        pass
    return P, Pp


def smoothed(P: FloatArray, Pp: FloatArray, F: FloatArray, Q: FloatArray, lag_one: bool) -> FloatArray:
    r"""The RTS smoother's (or the lag-one smoother's) covariances from filtered ``P`` and predicted ``Pp`` at every
    node, in the form :math:`S_m = (I - C_m\Phi)P_m(I - C_m\Phi)^\top + C_m Q C_m^\top + C_m S_{m+1} C_m^\top` (equal
    in exact arithmetic to ``kalman_runs``' :math:`P_m + C_m(S_{m+1} - P^-_{m+1})C_m^\top`, without its cancellation
    of :math:`P_m` against :math:`C_m P^-_{m+1} C_m^\top`); inf where a predicted covariance is singular."""
    S = P.copy()
    M = len(P)
    eye = np.eye(3)
    with np.errstate(all="ignore"):
        for m in (range(M - 1) if lag_one else range(M - 2, -1, -1)):
            try:
                C = np.linalg.solve(Pp[m + 1].T, (P[m] @ F[m + 1].T).T).T
            except np.linalg.LinAlgError:
                S[m] = np.inf
                continue
            A = eye - C @ F[m + 1]
            S[m] = A @ P[m] @ A.T + C @ (Q[m + 1] + (P if lag_one else S)[m + 1]) @ C.T
    return S


def refuse(off: FloatArray, g: FloatArray, threshold: float, what: str, sigma: float, q_v: float, q_a: float,
           p0: tuple[float, float]) -> None:
    """Refuse, naming the caller's ``sigma``, ``q_v``, ``q_a`` and ``p0``, a covariance recursion whose round-off
    estimate ``off`` (one per node of the grid ``g``) exceeds ``threshold``; ``what`` names the two forms compared."""
    if not float(np.max(off)) <= threshold:
        m = int(np.argmax(np.where(np.isnan(off), np.inf, off)))
        raise ValueError(
            f"sigma = {shown(sigma)} m, q_v = {shown(q_v)}, q_a = {shown(q_a)} and p0 = {shown(p0)} leave the filter's "
            f"covariance recursion inaccurate (round-off: the prior far above the posterior, a measurement variance "
            f"{max(p0) / sigma**2:.1e} times below p0, and too little process noise to refill it): at t = {g[m]:g} s "
            f"{what} differ by {off[m]:.2g} of their scale sqrt(P_aa P_bb), above {threshold:g}; give q_v or q_a > 0 "
            "or a larger sigma, or a smaller p0")


#: Round-off estimates already computed, by the filter's options (its grid, noise and prior: the covariances do not
#: depend on the data, so the same options give the same covariances, bit for bit). ``expected_mse`` runs the same
#: filter on ``n + 1`` unit data sets: the estimate is computed once (the information form doubled chapter 07's
#: ``expected`` without it). Cleared when it reaches ``_CACHE_SIZE`` entries.
_CACHE: dict[Hashable, FloatArray] = {}
_CACHE_SIZE = 4096


def estimate(key: Hashable, compute: Callable[[], FloatArray]) -> FloatArray:
    """The round-off estimate of the options ``key``: ``compute()`` the first time, the stored array after."""
    off = _CACHE.get(key)
    if off is None:
        off = compute()
        off.setflags(write=False)
        if len(_CACHE) >= _CACHE_SIZE:
            _CACHE.clear()
        _CACHE[key] = off
    return off
