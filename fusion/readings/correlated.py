r"""Fusion with correlated measurement noise (lecture notes, §2.7).

Stacked model :math:`z = Hx + v`, :math:`\mathrm{cov}(v) = R` positive definite with non-zero
off-diagonal blocks (common environmental noise).

* :func:`gls`: the Markov (generalised least-squares) estimate
  :math:`\hat x_F = (H^\top R^{-1}H)^{-1}H^\top R^{-1}z`, :math:`P_F = (H^\top R^{-1}H)^{-1}`,
  through a Cholesky factor (``scipy.linalg.cho_factor``/``cho_solve``).
* :func:`ldl_unpivoted`, :func:`unit_lower_inverse`: the unpivoted :math:`R = LDL^\top` and the
  lecture's recursion for :math:`M = L^{-1}` (``scipy.linalg.ldl`` pivots, so it is not used).
* :func:`pseudo_measurement_fusion`: decorrelate, :math:`y = Mz = Gx + w`,
  :math:`\mathrm{cov}(w) = D`, and fuse the scalar pseudo-measurements; equals :func:`gls`.
* :func:`naive_fusion`: ignore the off-diagonal blocks (the cost of ignoring correlation).

References
----------
* Aitken, A. C. (1936). On least squares and linear combination of observations.
  *Proceedings of the Royal Society of Edinburgh*, 55, 42-48.
* Golub, G. H., & Van Loan, C. F. (2013). *Matrix Computations* (4th ed.). Johns Hopkins
  University Press (the LDL^T factorisation and triangular inversion).
* An explanation of multi-sensor data fusion algorithms (多传感器数据融合算法讲解).
  Lecture notes, web copy (in Chinese; author and date not stated).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike
from scipy.linalg import cho_factor, cho_solve, solve_triangular

from fusion._frozen import freeze_arrays
from fusion._validation import FloatArray, as_array, as_covariance, count

__all__ = ["LDLFactors", "LinearEstimate", "gls", "ldl_unpivoted", "unit_lower_inverse", "pseudo_measurement_fusion", "naive_fusion", "operation_counts"]


def _model(H: ArrayLike, R: ArrayLike, z: ArrayLike) -> tuple[FloatArray, FloatArray, FloatArray]:
    Ha = as_array(H, "H", ndim=2)
    za = as_array(z, "z", ndim=(1, 2))
    if za.shape[0] != Ha.shape[0]:
        raise ValueError(f"z must be ({Ha.shape[0]},) or ({Ha.shape[0]}, runs) to match H, got shape {za.shape}")
    Ra = as_covariance(R, dim=Ha.shape[0], name="R")
    if np.linalg.matrix_rank(Ha) < Ha.shape[1]:
        raise ValueError("H must have full column rank")
    return Ha, Ra, za


@dataclass(frozen=True)
class LinearEstimate:
    """A linear estimate from correlated readings and its covariance.

    Arrays are read-only.

    Attributes
    ----------
    x : ndarray, shape (d,) or (d, runs)
        The estimate, in the state's units.
    P : ndarray, shape (d, d)
        Its covariance (for :func:`naive_fusion`: the covariance the method *claims*).
    """

    x: FloatArray
    P: FloatArray

    __post_init__ = freeze_arrays


def gls(H: ArrayLike, R: ArrayLike, z: ArrayLike) -> LinearEstimate:
    r"""Markov (GLS) estimate and its covariance (sec. 2.7).

    Parameters
    ----------
    H : array_like, shape (Nm, d)
    R : array_like, shape (Nm, Nm)
        Positive definite noise covariance.
    z : array_like, shape (Nm,) or (Nm, runs)
        Measurements (columns: independent runs, fused at once).

    Returns
    -------
    LinearEstimate
        ``x`` and ``P``.
    """
    Ha, Ra, za = _model(H, R, z)
    c = cho_factor(Ra, lower=True)
    RiH = cho_solve(c, Ha)
    info = Ha.T @ RiH
    P = np.linalg.inv(info)
    return LinearEstimate(x=P @ (RiH.T @ za), P=0.5 * (P + P.T))


@dataclass(frozen=True)
class LDLFactors:
    r"""Unpivoted factors :math:`R = L D L^\top`.

    Arrays are read-only.

    Attributes
    ----------
    L : ndarray, shape (n, n)
        Unit lower triangular.
    d : ndarray, shape (n,)
        Diagonal of D (positive, in the units of R).
    """

    L: FloatArray
    d: FloatArray

    __post_init__ = freeze_arrays


def ldl_unpivoted(R: ArrayLike) -> LDLFactors:
    r"""Unpivoted :math:`R = LDL^\top`, L unit lower triangular, D diagonal positive.

    From the Cholesky factor :math:`R = CC^\top`: :math:`D = \mathrm{diag}(C)^2`,
    :math:`L = C\,\mathrm{diag}(C)^{-1}`; identical to the lecture's recursions
    :math:`d_i = r_{ii} - \sum_{k<i} l_{ik}^2 d_k`, :math:`l_{ij} = (r_{ij} - \sum_{k<j} d_k l_{ik} l_{jk})/d_j`.

    Parameters
    ----------
    R : array_like, shape (n, n)
        Symmetric positive-definite covariance (measurement units squared).

    Returns
    -------
    LDLFactors
        ``L`` and ``d``.

    Raises
    ------
    ValueError
        ``R`` not finite, not symmetric or not positive definite.
    """
    Ra = as_covariance(R, name="R")
    C = np.linalg.cholesky(Ra)
    c = np.diag(C)
    return LDLFactors(L=C / c[None, :], d=c**2)


def unit_lower_inverse(L: ArrayLike) -> FloatArray:
    r"""Inverse :math:`M = L^{-1}` of a unit lower-triangular matrix by the lecture's recursion.

    .. math:: m_{ii} = 1, \qquad m_{ij} = -l_{ij} - \sum_{k=j+1}^{i-1} l_{ik}m_{kj} \quad (i > j).

    Vectorised over columns: row i of M is computed from rows j < i.

    Parameters
    ----------
    L : array_like, shape (n, n)
        Unit lower-triangular matrix.

    Returns
    -------
    ndarray, shape (n, n)
        :math:`M = L^{-1}`, unit lower triangular.

    Raises
    ------
    ValueError
        ``L`` not square, not finite or not unit lower triangular.
    """
    La = as_array(L, "L", ndim=2)
    if La.shape[0] != La.shape[1]:
        raise ValueError(f"L must be square, got shape {La.shape}")
    if not (np.allclose(np.diag(La), 1.0) and np.allclose(np.triu(La, 1), 0.0)):
        raise ValueError("L must be unit lower triangular")
    n = La.shape[0]
    M = np.eye(n)
    for i in range(1, n):
        # m_ij = -l_ij - sum_{j<k<i} l_ik m_kj, and m_kj = 0 for k < j, m_jj = 1:
        # so row i = -(l_i,:i @ M[:i, :]) over columns j < i.
        M[i, :i] = -(La[i, :i] @ M[:i, :i])
    return M


def pseudo_measurement_fusion(H: ArrayLike, R: ArrayLike, z: ArrayLike) -> LinearEstimate:
    r"""Decorrelate with :math:`M = L^{-1}`, then fuse the scalar pseudo-measurements (sec. 2.7).

    :math:`y = Mz`, :math:`G = MH` with rows :math:`g_j^\top`, :math:`\mathrm{cov}(My) = D`:

    .. math:: \hat x = \Big(\sum_j \frac{g_jg_j^\top}{d_j}\Big)^{-1}\sum_j \frac{g_j y_j}{d_j}.

    Returns the same estimate and covariance as :func:`gls` (to round-off).

    Parameters
    ----------
    H : array_like, shape (Nm, d)
        Stacked observation matrix.
    R : array_like, shape (Nm, Nm)
        Noise covariance, symmetric positive definite.
    z : array_like, shape (Nm,)
        Stacked measurements.

    Returns
    -------
    LinearEstimate
        ``x``, the estimate in the state's units, and ``P``, its covariance
        :math:`(G^\top D^{-1}G)^{-1} = (H^\top R^{-1}H)^{-1}`.

    Raises
    ------
    ValueError
        As :func:`gls`.
    """
    Ha, Ra, za = _model(H, R, z)
    ldl = ldl_unpivoted(Ra)
    L, d = ldl.L, ldl.d
    y = solve_triangular(L, za, lower=True, unit_diagonal=True)  # = M z without forming M
    G = solve_triangular(L, Ha, lower=True, unit_diagonal=True)
    Gd = G / d[:, None]
    P = np.linalg.inv(G.T @ Gd)
    return LinearEstimate(x=P @ (Gd.T @ y), P=0.5 * (P + P.T))


def naive_fusion(H: ArrayLike, R: ArrayLike, z: ArrayLike, block: int) -> LinearEstimate:
    r"""GLS that ignores the correlation between sensors: R replaced by its diagonal blocks.

    Parameters
    ----------
    H, R, z
        As in :func:`gls`.
    block : int
        Rows per sensor (:math:`m`); ``Nm`` must be a multiple.

    Returns
    -------
    LinearEstimate
        ``x``, the estimate (still unbiased, but not minimum variance), and ``P``, the covariance
        the naive method *claims*, :math:`(H^\top \tilde R^{-1}H)^{-1}`.
    """
    Ha, Ra, za = _model(H, R, z)
    block = count(block, "block")
    if Ha.shape[0] % block:
        raise ValueError(f"block must divide the number of rows {Ha.shape[0]}, got {block}")
    mask = np.kron(np.eye(Ha.shape[0] // block), np.ones((block, block)))
    return gls(Ha, Ra * mask, za)


def operation_counts(N: int, d: int) -> dict[str, float]:
    r"""Leading floating-point operation counts of three GLS routes (sec. 2.7).

    For :math:`N` stacked measurement rows and :math:`d` states:

    * explicit inverse: :math:`N^3` for :math:`R^{-1}`, :math:`2N^2d` for :math:`R^{-1}H`, :math:`2Nd^2`
      for :math:`H^\top R^{-1}H`, :math:`d^3` for the small inverse;
    * Cholesky (``cho_solve``): factor once, :math:`N^3/3`, two triangular solves, :math:`2N^2d`;
    * LDLᵀ pseudo-measurements: the same factor, one unit-triangular solve, :math:`N^2d`, the
      diagonal scaling.

    A model of the leading terms, not a measurement (timings: ``benchmarks/bench_correlated.py``).

    Parameters
    ----------
    N : int
        Stacked rows, ``N >= 1``.
    d : int
        State dimension, ``d >= 1``.

    Returns
    -------
    dict
        ``{"explicit": ..., "cholesky": ..., "ldl": ...}`` in flops.
    """
    for name, v in (("N", N), ("d", d)):
        if isinstance(v, bool) or not isinstance(v, (int, np.integer)):
            raise TypeError(f"{name} must be an int, got {type(v).__name__}")
        if v < 1:
            raise ValueError(f"{name} must be >= 1, got {v}")
    common = 2 * N * d**2 + d**3
    return {"explicit": float(N**3 + 2 * N**2 * d + common),
            "cholesky": float(N**3 / 3 + 2 * N**2 * d + common),
            "ldl": float(N**3 / 3 + N**2 * d + common)}
