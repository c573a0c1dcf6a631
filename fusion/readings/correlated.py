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
* :func:`eigen_decorrelation_fusion`: the alternative the lecture sets aside, decorrelation by the
  orthogonal similarity transform :math:`R = Q\Lambda Q^\top` (``numpy.linalg.eigh``); equals :func:`gls`.
* :func:`gls_weights`: the linear weights :math:`K = P_FH^\top R^{-1}` of the Markov estimate (they
  can be negative).
* :func:`operation_counts`, :func:`ldl_as_written_count`, :func:`spd_inverse_count`: leading operation
  counts of the routes (a model, not a timing).
* :func:`ldl_recurrences`: the lecture's element recurrences for :math:`LDL^\top` (an independent route).
* :func:`lagrange_weights`: the Lagrange-multiplier best linear unbiased fusion with matrix weights
  (any state dimension); :func:`scalar_lagrange_weights`: the same method with one scalar weight per
  sensor (the form of the scalar case, applied to a vector state); :func:`gauss_markov_gap`: a numerical
  check of the Gauss-Markov bound.
* :func:`gls_low_rank`, :func:`low_rank_count`: GLS for a diagonal-plus-low-rank covariance (a common
  environment), :math:`R = \mathrm{diag}(D) + UU^\top`, by the Sherman-Morrison-Woodbury identity, without
  factorising R.

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

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike
from scipy.linalg import cho_factor, cho_solve, solve_triangular

from fusion._counts import allocation, as_rng
from fusion._limits import DENSE_CUBE, LOOP_STEP, dense_work, loop_work, work
from fusion._frozen import frozen_arrays
from fusion._covariances import column_rank_deficient, column_rank_work
from fusion._validation import read_once
from fusion._validation import derived_inputs
from fusion._validation import inverse, solve, FloatArray, as_array, as_covariance, check_invertible, count

__all__ = ["LDLFactors", "LinearEstimate", "gls", "ldl_unpivoted", "unit_lower_inverse", "pseudo_measurement_fusion",
           "naive_fusion", "eigen_decorrelation_fusion", "gls_weights", "operation_counts",
           "ldl_as_written_count", "ldl_recurrences", "lagrange_weights", "scalar_lagrange_weights",
           "gauss_markov_gap", "spd_inverse_count", "gesv_inverse_count", "gls_low_rank", "low_rank_count"]


def _model(H: ArrayLike, R: ArrayLike, z: ArrayLike, weight: float = 0.0) -> tuple[FloatArray, FloatArray, FloatArray]:
    """H, R and z validated; with ``weight``, the caller's dense work on the ``Nm x Nm`` R (``weight`` units a
    ``Nm**3``, fuzz 38a C9) is counted before R's own ``O(Nm**3)`` check, naming H and R."""
    Ha = as_array(H, "H", ndim=2)
    column_rank_work(*Ha.shape)  # rule 17 (fix 65a): H's singular values, before R's O(Nm**3) check
    if weight:
        dense_work(1, Ha.shape[0], "H and R", weight)
    za = as_array(z, "z", ndim=(1, 2))
    if za.shape[0] != Ha.shape[0]:
        raise ValueError(f"z must be ({Ha.shape[0]},) or ({Ha.shape[0]}, runs) to match H, got shape {za.shape}")
    Ra = as_covariance(R, dim=Ha.shape[0], name="R")
    if column_rank_deficient(Ha):  # whatever the units of the state (fuzz 27a N1)
        raise ValueError("H must have full column rank")
    return Ha, Ra, za


#: Units of one ``Nm**3`` of the decorrelating fusions (an LDL or eigen factor of R and its products).
_DECORRELATION_CUBE = 2 * DENSE_CUBE


@dataclass(frozen=True)
@frozen_arrays
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
    P = inverse(info, "H and R")
    return LinearEstimate(x=P @ (RiH.T @ za), P=0.5 * (P + P.T))


@dataclass(frozen=True)
@frozen_arrays
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
        ``L`` not square, not finite or not unit lower triangular, or beyond the work budget (``n`` above about
        4,250).
    """
    La = as_array(L, "L", ndim=2)
    if La.shape[0] != La.shape[1]:
        raise ValueError(f"L must be square, got shape {La.shape}")
    # rule 17 (fuzz 57b D2: n = 5,792, the input budget, ran 25.1 CPU-s unchecked): n row steps of an i x i matvec,
    # measured 0.11 ns a n**3 at n = 300, 0.063 at 1,000, 0.077 at 2,000 (time.process_time, OPENBLAS_NUM_THREADS=1,
    # shared machine) and 0.13 at 5,792 (fuzz 57b); the n Python steps (a LOOP_STEP each) are 6e6 units there
    dense_work(1, La.shape[0], "L", 1.3 * DENSE_CUBE)
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
    Ha, Ra, za = _model(H, R, z, _DECORRELATION_CUBE)  # 0.18 ns a Nm**3 measured (Nm = 4,800: 19 CPU-s)
    ldl = ldl_unpivoted(Ra)
    L, d = ldl.L, ldl.d
    y = solve_triangular(L, za, lower=True, unit_diagonal=True)  # = M z without forming M
    G = solve_triangular(L, Ha, lower=True, unit_diagonal=True)
    Gd = G / d[:, None]
    P = inverse(G.T @ Gd, "H and R")
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


def eigen_decorrelation_fusion(H: ArrayLike, R: ArrayLike, z: ArrayLike) -> LinearEstimate:
    r"""Decorrelate by the eigendecomposition :math:`R = Q\Lambda Q^\top`, then fuse (sec. 2.7's alternative).

    The lecture sets this route aside (an orthogonal similarity transform "cannot be completed in
    a finite number of steps, only approximated by iteration"). With :math:`y = Q^\top z`,
    :math:`G = Q^\top H`, :math:`\mathrm{cov}(Q^\top v) = \Lambda` diagonal, and

    .. math:: \hat x = (G^\top\Lambda^{-1}G)^{-1}G^\top\Lambda^{-1}y ,

    which equals :func:`gls` because :math:`R^{-1} = Q\Lambda^{-1}Q^\top`. The iteration of the
    symmetric eigensolver (LAPACK ``syevd`` through ``numpy.linalg.eigh``) converges to working
    precision; the route is exact to round-off, only more expensive than a Cholesky factor. The
    decomposition is that of the readings in units of their own standard deviations (:math:`R` replaced by its
    correlation matrix :math:`D^{-1/2}RD^{-1/2}`, :math:`D = \mathrm{diag}\,R`; :math:`z, H` by
    :math:`D^{-1/2}z, D^{-1/2}H`), so that the estimate does not depend on the units of each reading: the
    eigensolver resolves the small eigenvalues of :math:`R` itself only to :math:`\varepsilon` times the largest
    (10 % off :func:`gls` for readings in units 10⁴ apart, fuzz 26a U).

    Parameters
    ----------
    H : array_like, shape (Nm, d)
        Stacked observation matrix of full column rank.
    R : array_like, shape (Nm, Nm)
        Noise covariance, symmetric positive definite.
    z : array_like, shape (Nm,) or (Nm, runs)
        Stacked measurements (columns: independent runs).

    Returns
    -------
    LinearEstimate
        ``x`` and its covariance ``P`` :math:`= (H^\top R^{-1}H)^{-1}`.

    Raises
    ------
    ValueError
        As :func:`gls`.

    References
    ----------
    * Golub, G. H., & Van Loan, C. F. (2013). *Matrix Computations* (4th ed.), ch. 8 (the
      symmetric eigenvalue problem).
    """
    Ha, Ra, za = _model(H, R, z, _DECORRELATION_CUBE)  # 0.21 ns a Nm**3 measured (Nm = 4,800: 23 CPU-s)
    # the readings in units of their own standard deviations: eigh resolves R's correlation matrix (which passed the
    # covariance rule), not R, whose small eigenvalues in mixed units it resolves only to eps * the largest
    s = 1.0 / np.sqrt(np.diagonal(Ra))
    lam, Q = np.linalg.eigh(Ra * s[:, None] * s[None, :])
    y = Q.T @ (s.reshape((-1,) + (1,) * (za.ndim - 1)) * za)
    G = Q.T @ (s[:, None] * Ha)
    Gl = G / lam[:, None]
    P = inverse(G.T @ Gl, "H and R")
    return LinearEstimate(x=P @ (Gl.T @ y), P=0.5 * (P + P.T))


def gls_weights(H: ArrayLike, R: ArrayLike) -> FloatArray:
    r"""Weights :math:`K = (H^\top R^{-1}H)^{-1}H^\top R^{-1}` of the Markov estimate, :math:`\hat x_F = Kz`.

    :math:`KH = I`, so for a scalar state read directly by every sensor (:math:`H = \mathbf 1`)
    the weights sum to one; with correlated noise some can be negative (the estimate then
    subtracts a common error that two sensors see with different strengths).

    Parameters
    ----------
    H : array_like, shape (Nm, d)
        Stacked observation matrix of full column rank.
    R : array_like, shape (Nm, Nm)
        Noise covariance, symmetric positive definite.

    Returns
    -------
    ndarray, shape (d, Nm)
        The weight matrix (dimensionless when H is).

    Raises
    ------
    ValueError
        As :func:`gls`.
    """
    Ha = as_array(H, "H", ndim=2)
    column_rank_work(*Ha.shape)  # rule 17 (fix 65a): H's singular values, before R's O(Nm**3) check
    Ra = as_covariance(R, dim=Ha.shape[0], name="R")
    if column_rank_deficient(Ha):  # whatever the units of the state (fuzz 27a N1)
        raise ValueError("H must have full column rank")
    c = cho_factor(Ra, lower=True)
    RiH = cho_solve(c, Ha)
    return solve(Ha.T @ RiH, RiH.T, "H and R")


def operation_counts(N: int, d: int) -> dict[str, float]:
    r"""Leading floating-point operation counts of four GLS routes (sec. 2.7).

    For :math:`N` stacked measurement rows, :math:`d` states and one measurement vector:

    * explicit inverse by LU factors and their inversion (LAPACK ``getrf`` + ``getri``): :math:`2N^3`
      (:math:`\tfrac23N^3` for the LU factors, :math:`\tfrac43N^3` to invert them; ``numpy.linalg.inv``
      instead solves with the identity, ``gesv``, :math:`\tfrac83N^3`: :func:`gesv_inverse_count`), then
      :math:`2N^2d` for :math:`H^\top R^{-1}`, :math:`2Nd^2` for :math:`H^\top R^{-1}H`, :math:`2N^2d`
      for the right-hand side computed as :math:`(H^\top R^{-1})z` again by the formula as written
      (``H.T @ Ri @ z``), and :math:`d^3`;
    * Cholesky (``cho_factor``/``cho_solve``): :math:`N^3/3` for the factor, :math:`2N^2d` for the
      two triangular solves with the :math:`d` columns of H, :math:`2Nd^2 + d^3`;
    * LDLᵀ pseudo-measurements: the same factor, :math:`N^3/3`, one unit-triangular solve with
      the :math:`d + 1` columns of :math:`[H, z]`, :math:`N^2(d+1)`, then :math:`2Nd^2 + d^3`;
    * eigendecomposition (symmetric QR with the eigenvectors accumulated, about :math:`9N^3`,
      Golub & Van Loan 2013, §8.3), :math:`2N^2(d+1)` for :math:`Q^\top[H, z]`, :math:`2Nd^2 + d^3`.

    A model of the leading terms, not a measurement: it ignores memory traffic, blocking and the
    quality of the implementation, which decide measured times at moderate N
    (``benchmarks/bench_correlated.py`` times the same routes side by side).

    Parameters
    ----------
    N : int
        Stacked rows, ``N >= 1``.
    d : int
        State dimension, ``d >= 1``.

    Returns
    -------
    dict
        ``{"explicit": ..., "cholesky": ..., "ldl": ..., "eigen": ...}`` in flops.

    References
    ----------
    * Golub, G. H., & Van Loan, C. F. (2013). *Matrix Computations* (4th ed.). Johns Hopkins
      University Press (operation counts of LU, Cholesky, triangular inversion and the symmetric
      QR algorithm).
    """
    N, d = _rows_states(N, d)
    common = 2 * N * d**2 + d**3
    return {"explicit": float(2 * N**3 + 4 * N**2 * d + common),
            "cholesky": float(N**3 / 3 + 2 * N**2 * d + common),
            "ldl": float(N**3 / 3 + N**2 * (d + 1) + common),
            "eigen": float(9 * N**3 + 2 * N**2 * (d + 1) + common)}


def _rows_states(N: int, d: int) -> tuple[int, int]:
    """``N`` and ``d`` of the operation counts as Python ints (>= 1), by the shared count rule."""
    return count(N, "N"), count(d, "d")


def ldl_as_written_count(N: int, d: int) -> float:
    r"""Leading operation count of the LDLᵀ route as the lecture writes it, forming :math:`M = L^{-1}`.

    The lecture computes the elements :math:`m_{ij}` of :math:`M = L^{-1}` by a recursion and then the
    pseudo-measurements :math:`M[H, z]`. Counted: the factor, :math:`N^3/3`; the inverse of a unit lower
    triangular matrix, :math:`N^3/3`; the dense product :math:`M[H, z]`, :math:`N^2(d+1)` (multiply-adds of
    a triangular matrix by :math:`d + 1` columns, :math:`2\cdot\tfrac12 N^2` each); then :math:`2Nd^2 + d^3`
    as in :func:`operation_counts`. About :math:`\tfrac23N^3`: twice a Cholesky solve, a third of the
    explicit inverse.

    Parameters
    ----------
    N : int
        Stacked rows, ``N >= 1``.
    d : int
        State dimension, ``d >= 1``.

    Returns
    -------
    float
        Flops.

    References
    ----------
    * Golub, G. H., & Van Loan, C. F. (2013). *Matrix Computations* (4th ed.), §3.1 (triangular systems and
      the inverse of a triangular matrix). Johns Hopkins University Press.
    """
    N, d = _rows_states(N, d)  # Python ints: numpy integers would overflow in the formula
    return float(N**3 / 3 + N**3 / 3 + N**2 * (d + 1) + 2 * N * d**2 + d**3)


def ldl_recurrences(R: ArrayLike) -> LDLFactors:
    r"""Unpivoted :math:`R = LDL^\top` by the lecture's element recurrences (sec. 2.7), row by row.

    .. math::

        d_i = r_{ii} - \sum_{k<i} l_{ik}^2 d_k, \qquad
        l_{ij} = \Big(r_{ij} - \sum_{k<j} d_k l_{ik} l_{jk}\Big)\Big/d_j \quad (j < i).

    An independent route to the factors of :func:`ldl_unpivoted` (which derives them from a Cholesky
    factor): for a symmetric positive-definite R the factorisation with L unit lower triangular and D
    diagonal is unique, so the two must agree to round-off.

    Parameters
    ----------
    R : array_like, shape (n, n)
        Symmetric positive-definite covariance.

    Returns
    -------
    LDLFactors
        ``L`` and ``d``.

    Raises
    ------
    ValueError
        ``R`` not finite, not symmetric or not positive definite.

    References
    ----------
    * Golub, G. H., & Van Loan, C. F. (2013). *Matrix Computations* (4th ed.), §4.1 (the LDLᵀ
      factorisation and its uniqueness). Johns Hopkins University Press.
    """
    # rule 17 (fuzz 36a C2): a Python step per entry below the diagonal, 3-4 us each (time.process_time, n = 100 to
    # 2,000): half a LOOP_STEP an entry, refused by R's size before the loop and before its O(n^3) checks
    Ra = as_array(R, "R")
    n = Ra.shape[0] if Ra.ndim else 1
    loop_work((n * (n - 1) // 2,), 0, "R (its size n)", step=LOOP_STEP // 2)
    Ra = as_covariance(Ra, name="R")
    n = Ra.shape[0]
    L, d = np.eye(n), np.zeros(n)
    for i in range(n):
        for j in range(i):
            L[i, j] = (Ra[i, j] - np.sum(d[:j] * L[i, :j] * L[j, :j])) / d[j]
        d[i] = Ra[i, i] - np.sum(L[i, :i] ** 2 * d[:i])
    return LDLFactors(L=L, d=d)


def lagrange_weights(H: ArrayLike, R: ArrayLike) -> FloatArray:
    r"""Best linear unbiased fusion weights by Lagrange multipliers, for a state of any dimension.

    Minimise the total error variance :math:`\mathrm{tr}(WRW^\top)` of :math:`\hat x = Wz` subject to
    unbiasedness, :math:`WH = I_d` (for :math:`H_i = I` this is :math:`\sum_iW_i = I`, the matrix form of the
    scalar :math:`\sum_iw_i = 1`). With the multipliers :math:`\Lambda` the stationarity conditions are the
    linear (KKT) system

    .. math:: \begin{pmatrix} R & H \\ H^\top & 0 \end{pmatrix}\begin{pmatrix} W^\top \\ -\Lambda^\top
              \end{pmatrix} = \begin{pmatrix} 0 \\ I_d \end{pmatrix},

    solved here as it stands (no GLS formula is used); its solution is the Markov weight matrix
    :math:`(H^\top R^{-1}H)^{-1}H^\top R^{-1}` of :func:`gls_weights`.

    Parameters
    ----------
    H : array_like, shape (Nm, d)
        Stacked observation matrix of full column rank.
    R : array_like, shape (Nm, Nm)
        Noise covariance, symmetric positive definite.

    Returns
    -------
    ndarray, shape (d, Nm)
        The weight matrix K of x̂ = K z: KH = I, with K R Kᵀ the smallest.

    Raises
    ------
    ValueError
        As :func:`gls`.

    References
    ----------
    * Aitken, A. C. (1936). On least squares and linear combination of observations.
      *Proceedings of the Royal Society of Edinburgh*, 55, 42-48.
    """
    Ha = as_array(H, "H", ndim=2)
    column_rank_work(*Ha.shape)  # rule 17 (fix 65a): H's singular values, before R's O(Nm**3) check
    # and R's check with the (Nm + d) KKT system's LU solve, 0.03 ns a (Nm + d)**3 measured (Nm = 5,792, d = 2: 5.7
    # CPU-s; time.process_time, OPENBLAS_NUM_THREADS=1, the shared machine)
    dense_work(1, Ha.shape[0] + Ha.shape[1], "H and R", 0.3 * DENSE_CUBE)
    Ra = as_covariance(R, dim=Ha.shape[0], name="R")
    if column_rank_deficient(Ha):  # whatever the units of the state (fuzz 27a N1)
        raise ValueError("H must have full column rank")
    N, d = Ha.shape
    K = np.block([[Ra, Ha], [Ha.T, np.zeros((d, d))]])
    rhs = np.vstack([np.zeros((N, d)), np.eye(d)])
    return solve(K, rhs, "H and R")[:N].T


def scalar_lagrange_weights(R: ArrayLike, d: int) -> FloatArray:
    r"""The scalar-weight Lagrange fusion applied to a d-dimensional state read directly by every sensor.

    The earlier method the lecture cites fuses a scalar, :math:`\hat x = \sum_iw_iz_i` with
    :math:`\sum_iw_i = 1`, minimising the error variance by Lagrange multipliers. Applied as it stands to a
    vector state with :math:`H_i = I_d` (one scalar weight per sensor), it minimises the total error variance
    :math:`\mathrm{tr}\sum_{ij}w_iw_jR_{ij}` over the sensors' :math:`d\times d` noise blocks :math:`R_{ij}`, so
    :math:`w \propto S^{-1}\mathbf 1` with :math:`S_{ij} = \mathrm{tr}\,R_{ij}`. It equals the Markov (GLS)
    weights when every block is a multiple of :math:`I_d` (the problem then splits into d identical scalar
    problems, as in the chapter's E2.7), and is worse otherwise: one weight per sensor cannot weight the
    components differently.

    Parameters
    ----------
    R : array_like, shape (N d, N d)
        Stacked noise covariance of N sensors, each reading the d components, symmetric positive definite.
    d : int
        State dimension (>= 1; N d rows).

    Returns
    -------
    ndarray, shape (d, N d)
        The weight matrix :math:`w^\top \otimes I_d` (unbiased: :math:`\sum_iw_i = 1`).

    Raises
    ------
    ValueError
        ``R`` not symmetric positive definite, or its size not a multiple of ``d``, or the matrix of block traces
        :math:`S` singular to working precision (both by the package's covariance rule,
        ``fusion._covariances.SINGULAR_MARGIN``, which does not depend on the units of each component).
    """
    d = count(d, "d")
    Ra = as_covariance(R, name="R")
    if Ra.shape[0] % d:
        raise ValueError(f"R must have a multiple of d = {d} rows, got {Ra.shape[0]}")
    N = Ra.shape[0] // d
    S = np.einsum("iaja->ij", Ra.reshape(N, d, N, d))
    # R passed the package's covariance rule (as_covariance: unit-free); the matrix solved is S, checked by the same
    # rule (an absolute test on R's eigenvalues refused a positive diagonal R in mixed units, fuzz 26a U)
    check_invertible(S, "R")
    w = solve(S, np.ones(N), "R")
    w = w / w.sum()
    return np.kron(w[None, :], np.eye(d))


@derived_inputs()
def gls_low_rank(H: ArrayLike, D: ArrayLike, U: ArrayLike, z: ArrayLike) -> LinearEstimate:
    r"""GLS for :math:`R = \mathrm{diag}(D) + UU^\top` by the Sherman-Morrison-Woodbury identity.

    .. math:: R^{-1} = D^{-1} - D^{-1}U(I_r + U^\top D^{-1}U)^{-1}U^\top D^{-1},

    applied to :math:`[H, z]` without forming or factorising R: about :math:`2N(d+r)(d+r+1)` operations for
    N rows, d states and rank r, against :math:`N^3/3` for a Cholesky factor (:func:`low_rank_count`). This is
    the structure of a common environment, :math:`R = \mathrm{diag}(\sigma_i^2) + \sigma_e^2cc^\top` (r = 1 per
    state component).

    Parameters
    ----------
    H : array_like, shape (N, d)
        Observation matrix of full column rank.
    D : array_like, shape (N,)
        Diagonal part of R (> 0).
    U : array_like, shape (N, r)
        Low-rank factor (a 1-D array is one column).
    z : array_like, shape (N,) or (N, runs)
        Measurements.

    Returns
    -------
    LinearEstimate
        As :func:`gls`.

    Raises
    ------
    ValueError
        Bad shapes, non-finite values, a non-positive ``D`` or a rank-deficient ``H``, or ``H`` and ``U`` beyond the work budget
        (``4 N d**2 + N r**2 + 2 N r d`` units of 0.01, and the cubes: N = r of about 3,680 with d = 1).

    References
    ----------
    * Golub, G. H., & Van Loan, C. F. (2013). *Matrix Computations* (4th ed.), §2.1.4 (the
      Sherman-Morrison-Woodbury formula). Johns Hopkins University Press.
    """
    Ha = as_array(H, "H", ndim=2)
    Da = as_array(D, "D", shape=(Ha.shape[0],))
    if np.any(Da <= 0):
        raise ValueError("D must be positive")
    Ua = as_array(U, "U", ndim=(1, 2))
    Ua = Ua[:, None] if Ua.ndim == 1 else Ua
    if Ua.shape[0] != Ha.shape[0]:
        raise ValueError(f"U must have {Ha.shape[0]} rows to match H, got {Ua.shape}")
    allocation((Ua.shape[1], Ua.shape[1]), "U")  # rule 9 (fuzz 36a C1): the r x r core I + U^T D^-1 U
    allocation((Ha.shape[1], Ha.shape[1]), "H")  # and the d x d information H^T R^-1 H, before either is built
    # rule 17 (fix 65a, after fuzz 57b D2: H and U of 5,792 x 5,792 ran beyond 240 s unchecked): N d**2 (H's singular
    # values, H^T R^-1 H), N r d (U^T D^-1 H) and N r**2 (the core) work, and r**3 and d**3 (its solves, the inverse),
    # measured at N = 1,500 as 0.38 ns a N d**2 (U one column: 1.29 CPU-s), 0.07 ns a N r**2 (H one column: 0.24) and
    # 0.6 CPU-s more with both square (2.13): weighed 4, 1 and 2 DENSE_CUBE (time.process_time, OPENBLAS_NUM_THREADS=1)
    (N, d), r = Ha.shape, Ua.shape[1]
    work((max(N, d) * 4 * d * d + max(N, r) * r * r + 2 * N * r * d + d**3 + r**3,), "H and U", weight=DENSE_CUBE)
    za = as_array(z, "z", ndim=(1, 2))
    if za.shape[0] != Ha.shape[0]:
        raise ValueError(f"z must be ({Ha.shape[0]},) or ({Ha.shape[0]}, runs) to match H, got shape {za.shape}")
    if column_rank_deficient(Ha):  # whatever the units of the state (fuzz 27a N1)
        raise ValueError("H must have full column rank")
    one = za.ndim == 1
    Z = za[:, None] if one else za
    Di = 1.0 / Da[:, None]
    C = np.eye(Ua.shape[1]) + Ua.T @ (Di * Ua)
    def rinv(M: FloatArray) -> FloatArray:          # R^{-1} M by the identity
        DM = Di * M
        return DM - Di * (Ua @ solve(C, Ua.T @ DM, "D and U"))
    RiH = rinv(Ha)
    info = Ha.T @ RiH
    P = inverse(info, "H and R")
    x = P @ (RiH.T @ Z)
    return LinearEstimate(x=x[:, 0] if one else x, P=0.5 * (P + P.T))


def low_rank_count(N: int, d: int, r: int) -> float:
    r"""Leading operation count of :func:`gls_low_rank`: :math:`2N(d + r)(d + r + 1)` (plus O((d + r)³)).

    :math:`D^{-1}` applied to :math:`[H, z, U]` (:math:`N(d + r + 1)`), the products :math:`U^\top D^{-1}[H, z, U]`
    and :math:`H^\top R^{-1}[H, z]` (about :math:`2Nr(d + r + 1)` and :math:`2Nd(d + 1)`), bounded together by
    :math:`2N(d + r)(d + r + 1)`.

    Parameters
    ----------
    N, d, r : int
        Rows, states and rank (each >= 1).

    Returns
    -------
    float
        Flops (linear in N).
    """
    N, d = _rows_states(N, d)  # Python ints: numpy integers would overflow in the formula
    r = count(r, "r")
    return float(2 * N * (d + r) * (d + r + 1) + (d + r) ** 3)


def gauss_markov_gap(H: ArrayLike, R: ArrayLike, rng: np.random.Generator, draws: int = 200) -> float:
    r"""Smallest eigenvalue of :math:`\mathrm{cov}(Wz) - P_F` over random linear unbiased estimators W.

    Every linear unbiased W (:math:`WH = I`) is :math:`K + Z(I - HK)` with K the Markov weights
    (:func:`gls_weights`) and Z arbitrary; its covariance exceeds :math:`P_F = (H^\top R^{-1}H)^{-1}` by
    :math:`Z(I-HK)R(I-HK)^\top Z^\top \succeq 0` (Gauss-Markov, Aitken). The check draws ``draws`` such
    Z with standard normal entries.

    Parameters
    ----------
    H, R
        As :func:`gls_weights`.
    rng : numpy.random.Generator
        Draws the Z.
    draws : int
        Number of random estimators (>= 1).

    Returns
    -------
    float
        The smallest eigenvalue found, relative to the largest eigenvalue of :math:`P_F` (>= 0 up to
        round-off when the theorem holds).

    Raises
    ------
    ValueError
        As :func:`gls`, or ``draws`` < 1, or ``draws`` beyond the memory budget (four ``(draws, d, N)`` arrays: about
        3.4 x 10**6 draws of ``N = 10``, ``d = 2``) or the work budget for this ``H`` (a draw costs
        ``15 d**2 + d N + 0.05 d N**2`` units).
    TypeError
        ``rng`` not a :class:`numpy.random.Generator` itself (a subclass's draws are its own) over one of numpy's
        bit generators.
    """
    H, R = (read_once(H, "H"), read_once(R, "R"))  # converted once (fuzz 29a C5)
    as_rng(rng)  # a Generator itself (fuzz 57b C1: a subclass drawing NaN made the gap NaN)
    draws = count(draws, "draws")
    # rules 9 and 17 (fuzz 57b C2: draws held only to the count ceiling, 10**7 draws of N = 14, d = 2 a raw MemoryError
    # after 12-17 CPU-s), before any draw. Memory: Z, Z Q, W and W R, (draws, d, N) each, are held together
    # (tracemalloc's peak 3.1-3.3 arrays, N = 3 to 30). Work: a draw costs 15 d**2 + d N + 0.05 d N**2 units (the d x d
    # eigvalsh and the stack's per-matrix calls, the draws, the N x N products), measured (time.process_time,
    # OPENBLAS_NUM_THREADS=1, shared machine): 101 ns a draw at N = 3, d = 1 (18 units), 907 ns at N = 10, d = 2 (90),
    # 924 ns at N = 6, d = 3 (158), 2.5 us at N = 30, d = 3 (270), 10 us at N = 100, d = 2 (1,140), 15 us at N = 50,
    # d = 10 (3,250), 152 us at N = 200, d = 20 (50,000).
    # Both from H's shape alone, before gls_weights' O(N**3) solve (fuzz 58b C5: draws = 10**7 at N = 4,500 was
    # refused after 11.5 CPU-s of it).
    N, d = as_array(H, "H", ndim=2).shape
    _gap_budget(draws, N, d)
    K = gls_weights(H, R)
    Ha = np.asarray(H, dtype=float)
    Ra = np.asarray(R, dtype=float)
    P = K @ Ra @ K.T
    scale = float(np.linalg.eigvalsh(P).max())
    Q = np.eye(Ha.shape[0]) - Ha @ K
    Z = rng.normal(size=(draws, K.shape[0], Ha.shape[0]))
    W = K[None] + Z @ Q[None]
    C = W @ Ra[None] @ np.swapaxes(W, 1, 2) - P[None]
    C = 0.5 * (C + np.swapaxes(C, 1, 2))
    return float(np.linalg.eigvalsh(C).min() / scale)


def _gap_budget(draws: int, N: int, d: int) -> int:
    """Refuse ``draws`` estimators of :func:`gauss_markov_gap` for an ``N x d`` H beyond the memory or work budget (the
    measurements at its call); the units of work."""
    allocation((draws, d, N), "draws and H (its shape N x d)", arrays=4)
    return work((draws,), "draws and H (its shape N x d)", weight=15 * d * d + d * N + math.ceil(0.05 * d * N * N))


def spd_inverse_count(N: int, d: int) -> float:
    r"""Leading operation count of the Markov formula with an explicit inverse computed the SPD way.

    :math:`R^{-1}` from a Cholesky factor and its triangular inverse (LAPACK ``potrf`` + ``potri``),
    :math:`N^3/3 + 2N^3/3 = N^3`, then the products of the formula as written, as in
    :func:`operation_counts`' explicit route: :math:`4N^2d + 2Nd^2 + d^3`. Half the LU-based inverse of
    ``numpy.linalg.inv``.

    Parameters
    ----------
    N : int
        Stacked rows, ``N >= 1``.
    d : int
        State dimension, ``d >= 1``.

    Returns
    -------
    float
        Flops.

    References
    ----------
    * Golub, G. H., & Van Loan, C. F. (2013). *Matrix Computations* (4th ed.), §4.2 (Cholesky) and §3.1
      (triangular inversion). Johns Hopkins University Press.
    """
    N, d = _rows_states(N, d)  # Python ints: numpy integers would overflow in the formula
    return float(N**3 + 4 * N**2 * d + 2 * N * d**2 + d**3)


def gesv_inverse_count(N: int, d: int) -> float:
    r"""Leading operation count of the Markov formula with :math:`R^{-1}` formed as ``numpy.linalg.inv`` forms it.

    ``numpy.linalg.inv`` calls LAPACK ``gesv`` with an identity right-hand side: the LU factors,
    :math:`\tfrac23N^3`, then a forward and a back substitution for each of the :math:`N` columns,
    :math:`2N^3`, in all :math:`\tfrac83N^3`; then the products of the formula as written, as in
    :func:`operation_counts`' explicit route: :math:`4N^2d + 2Nd^2 + d^3`.

    Parameters
    ----------
    N : int
        Stacked rows, ``N >= 1``.
    d : int
        State dimension, ``d >= 1``.

    Returns
    -------
    float
        Flops.

    References
    ----------
    * Golub, G. H., & Van Loan, C. F. (2013). *Matrix Computations* (4th ed.), §3.2 (LU) and §3.1 (triangular
      systems). Johns Hopkins University Press.
    """
    N, d = _rows_states(N, d)  # Python ints: numpy integers would overflow in the formula
    return float(8 * N**3 / 3 + 4 * N**2 * d + 2 * N * d**2 + d**3)
