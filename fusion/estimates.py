r"""Estimate-level fusion: combining state estimates :math:`(\hat x_i, P_i)` of one state.

Covariance intersection (Julier & Uhlmann 1997) fuses two estimates whose
cross-covariance is unknown:

.. math::

    P^{-1} = \omega P_1^{-1} + (1 - \omega) P_2^{-1}, \qquad
    P^{-1}\hat x = \omega P_1^{-1}\hat x_1 + (1 - \omega) P_2^{-1}\hat x_2,
    \qquad \omega \in [0, 1].

The result is consistent (:math:`P \succeq` the true error covariance) for every
cross-correlation, provided both inputs are consistent.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import minimize_scalar

from fusion._validation import FloatArray, as_covariance, as_state, one_of

__all__ = ["FusedEstimate", "covariance_intersection", "ci_objective"]

Criterion = Literal["trace", "det"]


@dataclass(frozen=True)
class FusedEstimate:
    """A fused state estimate.

    Attributes
    ----------
    x : ndarray, shape (n,)
        Fused state, in the states' units.
    P : ndarray, shape (n, n)
        Fused covariance (symmetric positive definite).
    omega : float
        Weight of the first estimate (``nan`` for methods without one).
    """

    x: FloatArray
    P: FloatArray
    omega: float


def _ci(omega: float, I1: FloatArray, I2: FloatArray) -> FloatArray:
    return omega * I1 + (1.0 - omega) * I2


def ci_objective(omega: float, P1: ArrayLike, P2: ArrayLike, criterion: Criterion = "trace") -> float:
    r"""Size of the covariance-intersection covariance for weight ``omega``.

    ``"trace"`` returns :math:`\operatorname{tr} P(\omega)`; ``"det"`` returns
    :math:`\log\det P(\omega)` (the log is monotone, so the minimiser is the same).

    Parameters
    ----------
    omega : float in [0, 1]
    P1, P2 : array_like, shape (n, n)
        Symmetric positive-definite covariances.
    criterion : {"trace", "det"}
    """
    one_of(criterion, ("trace", "det"), "criterion")
    P1 = as_covariance(P1, name="P1")
    P2 = as_covariance(P2, dim=P1.shape[0], name="P2")
    if not 0.0 <= omega <= 1.0:
        raise ValueError(f"omega must lie in [0, 1], got {omega}")
    info = _ci(omega, np.linalg.inv(P1), np.linalg.inv(P2))
    if criterion == "trace":
        return float(np.trace(np.linalg.inv(info)))
    return float(-np.linalg.slogdet(info)[1])


def covariance_intersection(
    x1: ArrayLike,
    P1: ArrayLike,
    x2: ArrayLike,
    P2: ArrayLike,
    omega: float | None = None,
    criterion: Criterion = "trace",
) -> FusedEstimate:
    r"""Covariance intersection of two estimates with unknown cross-covariance.

    .. math::

        P = \bigl(\omega P_1^{-1} + (1-\omega) P_2^{-1}\bigr)^{-1}, \qquad
        \hat x = P\bigl(\omega P_1^{-1}\hat x_1 + (1-\omega) P_2^{-1}\hat x_2\bigr).

    Parameters
    ----------
    x1, x2 : array_like, shape (n,)
        State estimates (a scalar is a 1-D state).
    P1, P2 : array_like, shape (n, n)
        Their covariances; symmetric positive definite.
    omega : float in [0, 1], optional
        Weight of the first estimate. If ``None``, it minimises ``criterion`` with
        :func:`scipy.optimize.minimize_scalar` (bounded; the objective is convex in
        :math:`\omega` for both criteria).
    criterion : {"trace", "det"}
        What to minimise when ``omega`` is ``None``.

    Returns
    -------
    FusedEstimate

    Raises
    ------
    ValueError
        Mismatched shapes, NaN/inf, non-symmetric or non-positive-definite covariances,
        ``omega`` outside [0, 1], unknown criterion.

    Notes
    -----
    With ``omega = 1`` (or 0) the result is the first (second) estimate. For identical
    inputs the result equals them for every ``omega``.
    """
    one_of(criterion, ("trace", "det"), "criterion")
    x1 = as_state(x1, "x1")
    x2 = as_state(x2, "x2")
    if x1.shape != x2.shape:
        raise ValueError(f"x1 and x2 must have the same shape, got {x1.shape} and {x2.shape}")
    n = x1.size
    P1 = as_covariance(P1, dim=n, name="P1")
    P2 = as_covariance(P2, dim=n, name="P2")
    I1, I2 = np.linalg.inv(P1), np.linalg.inv(P2)
    if omega is None:
        def f(w: float) -> float:
            info = _ci(w, I1, I2)
            if criterion == "trace":
                return float(np.trace(np.linalg.inv(info)))
            return float(-np.linalg.slogdet(info)[1])

        res = minimize_scalar(f, bounds=(0.0, 1.0), method="bounded", options={"xatol": 1e-10})
        w = float(res.x)
        # the bounded method never evaluates the end points exactly
        for end in (0.0, 1.0):
            if f(end) <= f(w):
                w = end
    else:
        w = float(omega)
        if not np.isfinite(w) or not 0.0 <= w <= 1.0:
            raise ValueError(f"omega must lie in [0, 1], got {omega!r}")
    info = _ci(w, I1, I2)
    P = np.linalg.inv(info)
    P = 0.5 * (P + P.T)
    x = P @ (w * I1 @ x1 + (1.0 - w) * I2 @ x2)
    return FusedEstimate(x=x, P=P, omega=w)
