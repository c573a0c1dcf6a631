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

__all__ = [
    "FusedEstimate",
    "covariance_intersection",
    "ci_objective",
    "convex_combination",
    "split_covariance_intersection",
    "ci_as_printed",
]

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
    inputs the result equals them for every ``omega``. When ``P1 = P2`` both criteria are
    constant in ``omega``: the optimum is undetermined and the interior point returned by
    the bounded search is kept.
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
        # the bounded method never evaluates the end points exactly; move there only if
        # strictly better (on a flat objective, e.g. P1 = P2, keep the interior point)
        for end in (0.0, 1.0):
            if f(end) < f(w) - 1e-12 * abs(f(w)):
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


def convex_combination(x1: ArrayLike, P1: ArrayLike, x2: ArrayLike, P2: ArrayLike) -> FusedEstimate:
    r"""Convex combination (凸组合) of two estimates with *independent* errors (source 000, eqs. 3-4).

    .. math:: P = (P_1^{-1} + P_2^{-1})^{-1}, \qquad \hat x = P(P_1^{-1}\hat x_1 + P_2^{-1}\hat x_2).

    It is the minimum-variance linear fusion when the cross-covariance is zero, and
    inconsistent (``P`` too small) when the errors are positively correlated. It is also
    the product of the two Gaussian densities ("multi-Bayesian" fusion) and the
    maximum-likelihood fusion of independent Gaussian estimates.

    Returns
    -------
    FusedEstimate
        ``omega`` is ``nan``.
    """
    x1 = as_state(x1, "x1")
    x2 = as_state(x2, "x2")
    if x1.shape != x2.shape:
        raise ValueError(f"x1 and x2 must have the same shape, got {x1.shape} and {x2.shape}")
    P1 = as_covariance(P1, dim=x1.size, name="P1")
    P2 = as_covariance(P2, dim=x1.size, name="P2")
    I1, I2 = np.linalg.inv(P1), np.linalg.inv(P2)
    P = np.linalg.inv(I1 + I2)
    P = 0.5 * (P + P.T)
    return FusedEstimate(x=P @ (I1 @ x1 + I2 @ x2), P=P, omega=float("nan"))


def split_covariance_intersection(
    x1: ArrayLike,
    P1d: ArrayLike,
    P1i: ArrayLike,
    x2: ArrayLike,
    P2d: ArrayLike,
    P2i: ArrayLike,
    omega: float | None = None,
    criterion: Criterion = "trace",
    same_omega: bool = False,
) -> FusedEstimate:
    r"""Split covariance intersection (Julier & Uhlmann 2001; what source 000's eqs. 5-12 describe).

    Each covariance is split into a part :math:`P_{j,d}` that may be correlated with the other
    estimate and an independent part :math:`P_{j,i}`. The correlated parts are inflated as in
    covariance intersection, the independent parts are not:

    .. math::

        \tilde P_1 = \frac{P_{1,d}}{\omega} + P_{1,i}, \quad
        \tilde P_2 = \frac{P_{2,d}}{1-\omega} + P_{2,i}, \quad
        P = (\tilde P_1^{-1} + \tilde P_2^{-1})^{-1}, \quad
        \hat x = P(\tilde P_1^{-1}\hat x_1 + \tilde P_2^{-1}\hat x_2).

    Parameters
    ----------
    x1, x2 : array_like, shape (n,)
    P1d, P1i, P2d, P2i : array_like, shape (n, n)
        Correlated and independent parts; symmetric positive semidefinite, with
        ``P1d + P1i`` and ``P2d + P2i`` positive definite.
    omega : float in (0, 1), optional
        If ``None``, minimise ``criterion`` over omega (bounded scalar search).
    same_omega : bool
        ``True`` reproduces source 000's eqs. 11-12 **as printed**, which divide both
        correlated parts by the same :math:`\omega`; then the search drives
        :math:`\omega \to 1` and the correlated parts are fused as if independent.

    Returns
    -------
    FusedEstimate
    """
    one_of(criterion, ("trace", "det"), "criterion")
    x1 = as_state(x1, "x1")
    x2 = as_state(x2, "x2")
    if x1.shape != x2.shape:
        raise ValueError(f"x1 and x2 must have the same shape, got {x1.shape} and {x2.shape}")
    n = x1.size
    parts = []
    for name, M in (("P1d", P1d), ("P1i", P1i), ("P2d", P2d), ("P2i", P2i)):
        A = np.asarray(M, dtype=float).reshape(n, n) if np.ndim(M) <= 2 else np.asarray(M)
        if A.shape != (n, n) or not np.all(np.isfinite(A)):
            raise ValueError(f"{name} must be a finite {n}x{n} matrix")
        if not np.allclose(A, A.T):
            raise ValueError(f"{name} must be symmetric")
        if np.linalg.eigvalsh(0.5 * (A + A.T)).min() < -1e-9 * max(1.0, np.abs(A).max()):
            raise ValueError(f"{name} must be positive semidefinite")
        parts.append(0.5 * (A + A.T))
    A1d, A1i, A2d, A2i = parts
    as_covariance(A1d + A1i, name="P1d + P1i")
    as_covariance(A2d + A2i, name="P2d + P2i")

    def fused(w: float) -> tuple[FloatArray, FloatArray]:
        w2 = w if same_omega else 1.0 - w
        T1 = A1d / w + A1i
        T2 = A2d / w2 + A2i
        I1, I2 = np.linalg.inv(T1), np.linalg.inv(T2)
        P = np.linalg.inv(I1 + I2)
        return 0.5 * (P + P.T), P @ (I1 @ x1 + I2 @ x2)

    def size(w: float) -> float:
        P, _ = fused(w)
        return float(np.trace(P)) if criterion == "trace" else float(np.linalg.slogdet(P)[1])

    eps = 1e-6
    if omega is None:
        hi = 1.0 if same_omega else 1.0 - eps
        res = minimize_scalar(size, bounds=(eps, hi), method="bounded", options={"xatol": 1e-9})
        w = float(res.x)
        if same_omega and size(1.0) <= size(w):
            w = 1.0
    else:
        w = float(omega)
        upper = 1.0 if same_omega else 1.0 - 1e-12
        if not np.isfinite(w) or not (0.0 < w <= upper):
            raise ValueError(f"omega must lie in (0, 1), got {omega!r}")
    P, x = fused(w)
    return FusedEstimate(x=x, P=P, omega=w)


def ci_as_printed(x1: ArrayLike, P1: ArrayLike, x2: ArrayLike, P2: ArrayLike, omega: float) -> FusedEstimate:
    r"""Source 000's eqs. 1-2 **exactly as printed** (for the critique only).

    Eq. 1 is covariance intersection, :math:`P^{-1} = (P_1/w_1)^{-1} + (P_2/w_2)^{-1}`, but eq. 2
    prints :math:`X = P[(P_1/w_1)X_1 + (P_2/w_2)X_2]` without the inverses. The result is not a
    weighted mean: two identical estimates are not returned unchanged.
    """
    x1 = as_state(x1, "x1")
    x2 = as_state(x2, "x2")
    P1 = as_covariance(P1, dim=x1.size, name="P1")
    P2 = as_covariance(P2, dim=x1.size, name="P2")
    if not 0.0 < omega < 1.0:
        raise ValueError(f"omega must lie in (0, 1), got {omega!r}")
    w1, w2 = omega, 1.0 - omega
    P = np.linalg.inv(np.linalg.inv(P1 / w1) + np.linalg.inv(P2 / w2))
    return FusedEstimate(x=P @ ((P1 / w1) @ x1 + (P2 / w2) @ x2), P=P, omega=omega)
