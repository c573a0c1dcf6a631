r"""Fusion with correlated measurement noise (source 003, sec. 2.7).

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
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike
from scipy.linalg import cho_factor, cho_solve, solve_triangular

from fusion._validation import FloatArray, as_array, as_covariance, count

__all__ = ["gls", "ldl_unpivoted", "unit_lower_inverse", "pseudo_measurement_fusion", "naive_fusion"]


def _model(H: ArrayLike, R: ArrayLike, z: ArrayLike) -> tuple[FloatArray, FloatArray, FloatArray]:
    Ha = as_array(H, "H", ndim=2)
    za = as_array(z, "z", ndim=(1, 2))
    if za.shape[0] != Ha.shape[0]:
        raise ValueError(f"z must be ({Ha.shape[0]},) or ({Ha.shape[0]}, runs) to match H, got shape {za.shape}")
    Ra = as_covariance(R, dim=Ha.shape[0], name="R")
    if np.linalg.matrix_rank(Ha) < Ha.shape[1]:
        raise ValueError("H must have full column rank")
    return Ha, Ra, za


def gls(H: ArrayLike, R: ArrayLike, z: ArrayLike) -> tuple[FloatArray, FloatArray]:
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
    x : ndarray, shape (d,) or (d, runs)
    P : ndarray, shape (d, d)
    """
    Ha, Ra, za = _model(H, R, z)
    c = cho_factor(Ra, lower=True)
    RiH = cho_solve(c, Ha)
    info = Ha.T @ RiH
    P = np.linalg.inv(info)
    return P @ (RiH.T @ za), 0.5 * (P + P.T)


def ldl_unpivoted(R: ArrayLike) -> tuple[FloatArray, FloatArray]:
    r"""Unpivoted :math:`R = LDL^\top`, L unit lower triangular, D diagonal positive.

    From the Cholesky factor :math:`R = CC^\top`: :math:`D = \mathrm{diag}(C)^2`,
    :math:`L = C\,\mathrm{diag}(C)^{-1}`; identical to the lecture's recursions
    :math:`d_i = r_{ii} - \sum_{k<i} l_{ik}^2 d_k`, :math:`l_{ij} = (r_{ij} - \sum_{k<j} d_k l_{ik} l_{jk})/d_j`.

    Returns
    -------
    L : ndarray, shape (n, n)
    d : ndarray, shape (n,)
        Diagonal of D.
    """
    Ra = as_covariance(R, name="R")
    C = np.linalg.cholesky(Ra)
    c = np.diag(C)
    return C / c[None, :], c**2


def unit_lower_inverse(L: ArrayLike) -> FloatArray:
    r"""Inverse :math:`M = L^{-1}` of a unit lower-triangular matrix by the lecture's recursion.

    .. math:: m_{ii} = 1, \qquad m_{ij} = -l_{ij} - \sum_{k=j+1}^{i-1} l_{ik}m_{kj} \quad (i > j).

    Vectorised over columns: row i of M is computed from rows j < i.
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


def pseudo_measurement_fusion(H: ArrayLike, R: ArrayLike, z: ArrayLike) -> tuple[FloatArray, FloatArray]:
    r"""Decorrelate with :math:`M = L^{-1}`, then fuse the scalar pseudo-measurements (sec. 2.7).

    :math:`y = Mz`, :math:`G = MH` with rows :math:`g_j^\top`, :math:`\mathrm{cov}(My) = D`:

    .. math:: \hat x = \Big(\sum_j \frac{g_jg_j^\top}{d_j}\Big)^{-1}\sum_j \frac{g_j y_j}{d_j}.

    Returns the same estimate and covariance as :func:`gls` (to round-off).
    """
    Ha, Ra, za = _model(H, R, z)
    L, d = ldl_unpivoted(Ra)
    y = solve_triangular(L, za, lower=True, unit_diagonal=True)  # = M z without forming M
    G = solve_triangular(L, Ha, lower=True, unit_diagonal=True)
    Gd = G / d[:, None]
    P = np.linalg.inv(G.T @ Gd)
    return P @ (Gd.T @ y), 0.5 * (P + P.T)


def naive_fusion(H: ArrayLike, R: ArrayLike, z: ArrayLike, block: int) -> tuple[FloatArray, FloatArray]:
    r"""GLS that ignores the correlation between sensors: R replaced by its diagonal blocks.

    Parameters
    ----------
    H, R, z
        As in :func:`gls`.
    block : int
        Rows per sensor (:math:`m`); ``Nm`` must be a multiple.

    Returns
    -------
    x : ndarray
        Estimate (still unbiased, but not minimum variance).
    P_nominal : ndarray, shape (d, d)
        The covariance the naive method *claims*, :math:`(H^\top \tilde R^{-1}H)^{-1}`.
    """
    Ha, Ra, za = _model(H, R, z)
    block = count(block, "block")
    if Ha.shape[0] % block:
        raise ValueError(f"block must divide the number of rows {Ha.shape[0]}, got {block}")
    mask = np.kron(np.eye(Ha.shape[0] // block), np.ones((block, block)))
    return gls(Ha, Ra * mask, za)
