r"""Biased (ridge) estimation fusion (lecture notes, §2.5; Hoerl & Kennard 1970).

The lecture gives only the least-squares starting point; everything else is reconstructed.

* :func:`least_squares`, :func:`ridge`: :math:`(H^\top H + kI)^{-1}H^\top y`.
* :func:`ridge_centralised`, :func:`ridge_distributed`: the multi-sensor forms with noise
  covariances :math:`R_i`; equal at ``k = 0`` (the "equivalence" the lecture cites) and, in
  general, also at ``k > 0``.
* :func:`scalar_ridge_moments`, :func:`optimal_ridge_k`, :func:`reliability`: the scalar case
  :math:`H = \mathbf 1_m`, where :math:`\hat x_{RE} = \sum_i y_i/(m+k)`.
* :func:`plugin_ridge`: a data-driven ridge parameter, the Hoerl-Kennard-Baldwin plug-in
  :math:`\hat k = d\hat\sigma^2/\lVert\hat x_{LS}\rVert^2` (known or estimated noise level),
  vectorised over runs.
* :func:`plugin_risk`, :func:`plugin_crossings`: the exact MSE and reliability of the scalar
  plug-in against least squares (quadrature, no Monte Carlo) and where it stops helping.
* :func:`ridge_risk`, :func:`best_ridge_k`: the exact MSE of the multi-sensor (centralised) ridge with a fixed k,
  and the k that minimises it at a given true value.
* :func:`james_stein`: the James-Stein estimate (nonlinear, d >= 3), for comparison.
* :func:`ridge_fusion_plugin`: centralised shrinkage (the centre shrinks the fused estimate) and
  distributed shrinkage (each sensor shrinks its own estimate, the centre fuses them as if they
  were unbiased), each with plug-in parameters.

References
----------
* Hoerl, A. E., & Kennard, R. W. (1970). Ridge regression: biased estimation for nonorthogonal
  problems. *Technometrics*, 12(1), 55-67.
* Hoerl, A. E., Kennard, R. W., & Baldwin, K. F. (1975). Ridge regression: some simulations.
  *Communications in Statistics*, 4(2), 105-123.
* Aitken, A. C. (1936). On least squares and linear combination of observations. *Proceedings
  of the Royal Society of Edinburgh*, 55, 42-48.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from enum import StrEnum
from fractions import Fraction
from functools import lru_cache

import numpy as np
from numpy.typing import ArrayLike
from scipy.stats import norm

from fusion._covariances import column_rank_deficient, information_singular
from fusion._frozen import frozen_arrays
from fusion._validation import derived_inputs, finite_result
from fusion._validation import LOOP_STEP, allocation, loop_work, work
from fusion._limits import DENSE_CUBE, dense_work
from fusion._counts import broadcast
from fusion._validation import (FloatArray, as_array, as_covariance, count, nonnegative_scalar, one_of, positive_scalar,
                                scalar, solve, std_scalar)
from fusion._shown import shown

__all__ = [
    "RidgeMoments",
    "least_squares",
    "ridge",
    "ridge_centralised",
    "ridge_distributed",
    "scalar_ridge_moments",
    "optimal_ridge_k",
    "reliability",
    "RidgeFit",
    "plugin_ridge",
    "ShrinkAt",
    "ridge_fusion_plugin",
    "PluginRisk",
    "plugin_risk",
    "plugin_crossings",
    "ridge_risk",
    "best_ridge_k",
    "james_stein",
]


def _k(k: float) -> float:
    return nonnegative_scalar(k, "k")


def _Hy(H: ArrayLike, y: ArrayLike, hname: str = "H", yname: str = "y") -> tuple[FloatArray, FloatArray]:
    Ha = as_array(H, hname, ndim=(1, 2))
    if Ha.ndim == 1:
        Ha = Ha[:, None]
    allocation((Ha.shape[1], Ha.shape[1]), hname)  # rule 9: H^T H is d x d (fuzz 36a C1), before it is built
    ya = as_array(y, yname, ndim=1)
    if ya.shape != (Ha.shape[0],):
        raise ValueError(f"{hname} must be (m, d) and {yname} (m,), got {Ha.shape} and {ya.shape}")
    return Ha, ya


def ridge(H: ArrayLike, y: ArrayLike, k: float) -> FloatArray:
    r"""Ridge estimate :math:`\hat x_{RE}(k) = (H^\top H + kI)^{-1}H^\top y`.

    Parameters
    ----------
    H : array_like, shape (m, d)
        Observation matrix (a 1-D array is one column).
    y : array_like, shape (m,)
        Measurements, in the units of :math:`Hx`.
    k : float
        Ridge parameter, ``k >= 0``; ``k = 0`` is least squares and needs full column rank.

    Returns
    -------
    ndarray, shape (d,)
        The estimate, in the state's units.

    Raises
    ------
    ValueError
        Shapes not (m, d) and (m,), non-finite entries, ``k`` negative or not finite, or
        :math:`H^\top H + kI` singular.; an ``H`` beyond the work budget (``max(m, d) d**2`` units of 0.015,
        0.03 at ``k = 0``: a square H of about 4,050, 3,200 at ``k = 0``).

    References
    ----------
    * Hoerl, A. E., & Kennard, R. W. (1970). Ridge regression: biased estimation for
      nonorthogonal problems. *Technometrics*, 12(1), 55-67.
    """
    Ha, ya = _Hy(H, y)
    kk = _k(k)
    # rule 17 (fix 65a, after fuzz 57b D2: a square H of 5,792, the input budget, ran 27 CPU-s at k = 1 unchecked):
    # H^T H, its factor and solve, and at k = 0 H's singular values, max(m, d) d**2 work, 0.14 ns per unit at k > 0
    # and 0.26 ns at k = 0 measured (d = m = 1,500; time.process_time, OPENBLAS_NUM_THREADS=1, the shared machine)
    work((max(Ha.shape), Ha.shape[1], Ha.shape[1]), "H", weight=(3 if kk == 0.0 else 1.5) * DENSE_CUBE)
    A = Ha.T @ Ha + kk * np.eye(Ha.shape[1])
    # unit-free at every k (fuzz 27a N1, fuzz 28a C1: matrix_rank's absolute tolerance refused diag(1, 1e16) at k > 0)
    if column_rank_deficient(Ha) if kk == 0.0 else information_singular(A):
        raise ValueError("H^T H + k I is singular to working precision: H is rank-deficient and k is 0 or too small "
                         "to make up for it")
    return np.linalg.solve(A, Ha.T @ ya)


def least_squares(H: ArrayLike, y: ArrayLike) -> FloatArray:
    r"""Least squares :math:`(H^\top H)^{-1}H^\top y` (the mean when :math:`H = \mathbf 1`).

    The lecture notes' starting point (§2.5); :func:`ridge` with ``k = 0``.

    Parameters
    ----------
    H : array_like, shape (m, d)
        Observation matrix of full column rank (a 1-D array is one column).
    y : array_like, shape (m,)
        Measurements.

    Returns
    -------
    ndarray, shape (d,)
        The estimate, in the state's units.

    Raises
    ------
    ValueError
        Bad shapes, non-finite entries or rank-deficient ``H``.
    """
    return ridge(H, y, 0.0)


#: Units of one sensor block's Python step (checks, products) in the ridge fusions, measured on 3 x 2 blocks: 60-67 us
#: distributed (fused per sensor), 32-35 us centralised.
_BLOCK_STEP = 7 * LOOP_STEP
_CENTRAL_BLOCK_STEP = 4 * LOOP_STEP


#: Units of one sensor block's dense work, a term of ``m**3 + m**2 d + m d**2 + d**3`` for its (m, d) H: R's check
#: (``as_covariance``) and its solves against H and y, H^T R^-1 H and the d x d inverses. Measured (one block, min of 2,
#: time.process_time, OPENBLAS_NUM_THREADS=1, the shared machine): 0.096-0.142 ns a term at d = 1 (m = 1,500 and
#: 2,500), 0.08-0.10 at d = 300 and 1,500 (m = 1,500), both fusions; fuzz 59b C3 measured 0.144 (m = 3,000).
_BLOCK_CUBE = 1.5 * DENSE_CUBE


def _blocks_work(dims: Sequence[tuple[int, int]], step: int, names: str = "Hs, Rs and ys") -> int:
    """Refuse sensor blocks of H shapes ``dims`` ((m_i, d) each) whose dense work and Python steps, summed over the
    blocks, are beyond the work budget (rule 17, fuzz 59b C3: each block was checked alone, so 10 blocks of m = 3,000
    ran about 40 CPU-s), naming ``names``; called once every H is read, before the first R's ``O(m**3)`` check."""
    cubes = sum(m**3 + m * m * d + m * d * d + d**3 for m, d in dims)
    units = math.ceil(Fraction(cubes) * Fraction(_BLOCK_CUBE)) + len(dims) * int(step)
    return work((units,), names)


def _blocks(Hs: Sequence[ArrayLike], Rs: Sequence[ArrayLike], ys: Sequence[ArrayLike], step: int = _BLOCK_STEP):
    for nm, seq in (("Hs", Hs), ("Rs", Rs), ("ys", ys)):
        if isinstance(seq, (str, bytes)) or not hasattr(seq, "__len__"):
            raise TypeError(f"{nm} must be a sequence of arrays, got {type(seq).__name__}")
    if not (len(Hs) == len(Rs) == len(ys)) or len(Hs) == 0:
        raise ValueError("Hs, Rs and ys must be non-empty sequences of equal length")
    loop_work((len(Hs),), 0, "Hs, Rs and ys", step=step)  # rule 17 (fuzz 38a C8): a Python step a block
    Hys = []
    d = None
    for i, (H, y) in enumerate(zip(Hs, ys)):
        Ha, ya = _Hy(H, y, f"Hs[{i}]", f"ys[{i}]")
        if d is None:
            d = Ha.shape[1]
        elif Ha.shape[1] != d:
            raise ValueError(f"sensor {i}: H has {Ha.shape[1]} columns, expected {d}")
        Hys.append((Ha, ya))
    _blocks_work([Ha.shape for Ha, _ in Hys], step)   # the blocks' summed dense work, before the first R's check
    return [(Ha, as_covariance(R, dim=Ha.shape[0], name=f"Rs[{i}]"), ya)
            for i, ((Ha, ya), R) in enumerate(zip(Hys, Rs))]


def ridge_centralised(Hs: Sequence[ArrayLike], Rs: Sequence[ArrayLike], ys: Sequence[ArrayLike], k: float) -> FloatArray:
    r"""Centralised ridge fusion :math:`(\sum_i H_i^\top R_i^{-1}H_i + kI)^{-1}\sum_i H_i^\top R_i^{-1}y_i`.

    Parameters
    ----------
    Hs, Rs, ys : sequences of arrays, shapes (m_i, d), (m_i, m_i), (m_i,)
        Observation matrix, noise covariance and measurements of each sensor.
    k : float
        Ridge parameter (``k = 0``: generalised least squares).

    Returns
    -------
    ndarray, shape (d,)
        The fused estimate, in the state's units.

    Raises
    ------
    ValueError
        Sequences empty or of unequal length, bad shapes, non-finite entries, a covariance not
        symmetric positive definite, ``k`` negative or not finite, or ``k = 0`` with stacked ``Hs``
        that are rank-deficient (the system is singular).
    """
    kk = _k(k)
    blocks = _blocks(Hs, Rs, ys, _CENTRAL_BLOCK_STEP)
    d = blocks[0][0].shape[1]
    A = kk * np.eye(d)
    b = np.zeros(d)
    for H, R, y in blocks:
        A += H.T @ np.linalg.solve(R, H)
        b += H.T @ np.linalg.solve(R, y)
    if kk == 0.0 and information_singular(A):
        raise ValueError("sum of H_i^T R_i^-1 H_i + k I is singular: the stacked Hs are rank-deficient and k = 0")
    return solve(A, b, "Hs (with k = 0)")


def ridge_distributed(Hs: Sequence[ArrayLike], Rs: Sequence[ArrayLike], ys: Sequence[ArrayLike], k: float) -> FloatArray:
    r"""Distributed ridge fusion from local least-squares estimates.

    Each sensor sends :math:`\hat x_i = P_iH_i^\top R_i^{-1}y_i` and
    :math:`P_i = (H_i^\top R_i^{-1}H_i)^{-1}`; the centre computes
    :math:`(\sum_i P_i^{-1} + kI)^{-1}\sum_i P_i^{-1}\hat x_i`. Each :math:`H_i` needs full column
    rank. Algebraically identical to :func:`ridge_centralised` for every ``k``.

    Parameters
    ----------
    Hs, Rs, ys : sequences of arrays, shapes (m_i, d), (m_i, m_i), (m_i,)
        Observation matrix, noise covariance and measurements of each sensor.
    k : float
        Ridge parameter, ``k >= 0``.

    Returns
    -------
    ndarray, shape (d,)
        The fused estimate, in the state's units.

    Raises
    ------
    ValueError
        As :func:`ridge_centralised`, and when some :math:`H_i` lacks full column rank.
    """
    kk = _k(k)
    blocks = _blocks(Hs, Rs, ys)
    d = blocks[0][0].shape[1]
    A = kk * np.eye(d)
    b = np.zeros(d)
    for i, (H, R, y) in enumerate(blocks):
        info = H.T @ np.linalg.solve(R, H)
        if information_singular(info):
            raise ValueError(f"sensor {i}: H_i has no full column rank, no local estimate exists")
        P = np.linalg.inv(info)
        xi = P @ (H.T @ np.linalg.solve(R, y))
        Pinv = np.linalg.inv(P)
        A += Pinv
        b += Pinv @ xi
    return np.linalg.solve(A, b)


@dataclass(frozen=True)
@frozen_arrays
class RidgeMoments:
    """Bias, standard deviation and mean squared error of the scalar ridge estimate.

    Arrays are read-only.

    Attributes
    ----------
    bias : ndarray
        Of the broadcast shape of ``x`` and ``k``, in the units of ``x``.
    sd : ndarray
        Standard deviation, same shape and units.
    mse : ndarray
        Mean squared error ``bias**2 + sd**2``, in squared units.
    """

    bias: FloatArray
    sd: FloatArray
    mse: FloatArray


def scalar_ridge_moments(m: int, sigma: float, x: ArrayLike, k: ArrayLike) -> RidgeMoments:
    r"""Bias, standard deviation and MSE of the scalar ridge estimate :math:`\sum_i y_i/(m+k)`.

    With :math:`y_i = x + e_i`, :math:`e_i \sim N(0, \sigma^2)` independent:

    .. math::

        b = -\frac{kx}{m+k}, \qquad s^2 = \frac{m\sigma^2}{(m+k)^2}, \qquad
        \mathrm{MSE} = \frac{m\sigma^2 + k^2x^2}{(m+k)^2}.

    Parameters
    ----------
    m : int
        Number of measurements (>= 1).
    sigma : float
        Noise standard deviation (> 0).
    x, k : array_like
        True value and ridge parameter(s) (``k >= 0``), broadcast together.

    Returns
    -------
    RidgeMoments
        ``bias``, ``sd`` and ``mse``.

    Raises
    ------
    ValueError
        ``m`` not a positive integer, ``sigma`` not positive, ``k`` negative or non-finite
        values.
    """
    m = count(m, "m")
    sigma = std_scalar(sigma, "sigma")
    xa = as_array(x, "x")
    ka = as_array(k, "k", nonnegative=True)
    # rules 9 and 17 on the broadcast (fuzz 57b C5): 6.0 arrays of it at tracemalloc's peak, 6.7 ns an element
    broadcast((("x", xa.shape), ("k", ka.shape)), arrays=6, weight=1)
    bias = -ka * xa / (m + ka)
    sd = np.sqrt(m) * sigma / (m + ka) * np.ones_like(xa)
    return RidgeMoments(bias=bias, sd=sd, mse=bias**2 + sd**2)


def optimal_ridge_k(sigma: float, x: float) -> float:
    r"""MSE-minimising ridge parameter of the scalar case, :math:`k^* = \sigma^2/x^2` (inf for x = 0).

    Setting the derivative of :math:`\mathrm{MSE}(k) = (m\sigma^2 + k^2x^2)/(m+k)^2` (see
    :func:`scalar_ridge_moments`) to zero gives :math:`k^*`, independent of :math:`m`.

    Parameters
    ----------
    sigma : float
        Noise standard deviation, in the units of ``x``.
    x : float
        True value.

    Returns
    -------
    float
        :math:`k^*` (dimensionless); ``inf`` when ``x == 0`` (shrinking to zero is then exact).

    References
    ----------
    * Hoerl, A. E., & Kennard, R. W. (1970). Ridge regression: biased estimation for
      nonorthogonal problems. *Technometrics*, 12(1), 55-67.
    """
    sigma = std_scalar(sigma, "sigma")
    x = scalar(x, "x")
    if x == 0:
        return float("inf")
    if sigma / abs(x) > 1e150:  # sigma^2 / x^2 overflows (or x^2 underflows to zero): refused by name
        raise ValueError(f"x = {shown(x)} is too small next to sigma = {shown(sigma)}: k* = sigma^2 / x^2 overflows")
    return float(sigma) ** 2 / float(x) ** 2


def reliability(bias: ArrayLike, sd: ArrayLike, delta: float) -> FloatArray:
    r"""Our definition of "reliability" (the lecture has none): :math:`P(|\hat x - x| \le \delta)`.

    For a Gaussian error with mean ``bias`` and standard deviation ``sd``:
    :math:`\Phi(\frac{\delta-b}{s}) - \Phi(\frac{-\delta-b}{s})`.

    Parameters
    ----------
    bias : array_like
        Mean error :math:`b`, in the measurement's units.
    sd : array_like
        Standard deviation :math:`s` of the error (> 0), broadcast with ``bias``.
    delta : float
        Tolerance :math:`\delta > 0`, in the same units.

    Returns
    -------
    ndarray
        Probabilities in [0, 1], of the broadcast shape.

    Raises
    ------
    ValueError
        ``delta`` not positive or ``sd`` not positive.
    """
    delta = positive_scalar(delta, "delta")
    b = as_array(bias, "bias")
    s = as_array(sd, "sd")
    if np.any(s <= 0):
        raise ValueError("sd must be positive")
    # rules 9 and 17 on the broadcast (fuzz 57b C5): 6.25 arrays of it at tracemalloc's peak, 36 ns an element
    broadcast((("bias", b.shape), ("sd", s.shape)), arrays=7, weight=4)
    return norm.cdf((delta - b) / s) - norm.cdf((-delta - b) / s)


@dataclass(frozen=True)
@frozen_arrays
class RidgeFit:
    """A ridge estimate with a data-driven parameter, for one or many runs.

    Arrays are read-only.

    Attributes
    ----------
    x : ndarray, shape (d,) or (d, runs)
        The estimate, in the state's units.
    k : ndarray, shape () or (runs,)
        The ridge parameter used (``inf`` where the least-squares estimate is exactly 0, which
        then shrinks the estimate to 0).
    """

    x: FloatArray
    k: FloatArray


def _ridge_eig(A: FloatArray, b: FloatArray, k: FloatArray) -> FloatArray:
    """(A + k I)^{-1} b for a symmetric positive semidefinite A, b (d, runs), k (runs,) (inf -> 0)."""
    lam, V = np.linalg.eigh(A)
    c = V.T @ b
    with np.errstate(divide="ignore", invalid="ignore"):
        f = np.where(np.isinf(k)[None, :], 0.0, 1.0 / (lam[:, None] + np.where(np.isinf(k), 0.0, k)[None, :]))
    return V @ (f * c)


def plugin_ridge(H: ArrayLike, y: ArrayLike, sigma: float | None = None) -> RidgeFit:
    r"""Ridge with the Hoerl-Kennard-Baldwin plug-in parameter :math:`\hat k = d\hat\sigma^2/\lVert\hat x_{LS}\rVert^2`.

    The MSE-optimal :math:`k^* = \sigma^2/x^2` of the scalar case needs the unknown :math:`x`; the
    plug-in replaces it by the least-squares estimate (and, when ``sigma`` is not given, the
    noise variance by the residual variance :math:`\lVert y - H\hat x_{LS}\rVert^2/(m-d)`). For
    :math:`H = \mathbf 1_m` and known :math:`\sigma` this is
    :math:`\hat x = \bar y\, m\bar y^2/(m\bar y^2 + \sigma^2)`.

    Information used: the measurements and the model :math:`H`; with ``sigma`` also the noise
    level (known), without it nothing else.

    Parameters
    ----------
    H : array_like, shape (m, d)
        Observation matrix of full column rank (a 1-D array is one column).
    y : array_like, shape (m,) or (m, runs)
        Measurements; columns are independent runs (fitted at once).
    sigma : float, optional
        Known noise standard deviation (> 0). Without it, ``m > d`` is required.

    Returns
    -------
    RidgeFit
        ``x`` and the ``k`` used per run.

    Raises
    ------
    ValueError
        Bad shapes, non-finite entries, rank-deficient ``H``, ``sigma`` not positive, or
        ``m <= d`` without ``sigma``. An ``H`` beyond the work budget (``max(m, d) d**2`` units of
        0.05: a square H of about 2,700).

    References
    ----------
    * Hoerl, A. E., Kennard, R. W., & Baldwin, K. F. (1975). Ridge regression: some simulations.
      *Communications in Statistics*, 4(2), 105-123.
    """
    Ha = as_array(H, "H", ndim=(1, 2))
    if Ha.ndim == 1:
        Ha = Ha[:, None]
    allocation((Ha.shape[1], Ha.shape[1]), "H")  # rule 9: H^T H is d x d (fuzz 36a C1), before it is built
    # rule 17 (fix 65a, after fuzz 57b D2: a square H of 5,792 ran beyond 240 s unchecked): H^T H, H's singular
    # values and the solves, max(m, d) d**2 work, 0.47 ns per unit measured (d = m = 1,500, 1.57 CPU-s;
    # time.process_time, OPENBLAS_NUM_THREADS=1, the shared machine)
    work((max(Ha.shape), Ha.shape[1], Ha.shape[1]), "H", weight=5 * DENSE_CUBE)
    ya = as_array(y, "y", ndim=(1, 2))
    if ya.shape[0] != Ha.shape[0]:
        raise ValueError(f"y must be ({Ha.shape[0]},) or ({Ha.shape[0]}, runs) to match H, got {ya.shape}")
    one = ya.ndim == 1
    Y = ya[:, None] if one else ya
    m, d = Ha.shape
    A = Ha.T @ Ha
    if column_rank_deficient(Ha):  # whatever the units of the state (fuzz 27a N1)
        raise ValueError("H must have full column rank")
    x_ls = np.linalg.solve(A, Ha.T @ Y)
    if sigma is None:
        if m <= d:
            raise ValueError(f"sigma must be given when m <= d (m = {m}, d = {d}): no residual variance")
        s2 = np.sum((Y - Ha @ x_ls) ** 2, axis=0) / (m - d)
    else:
        s2 = np.full(Y.shape[1], std_scalar(sigma, "sigma") ** 2)
    nrm = np.sum(x_ls**2, axis=0)
    with np.errstate(divide="ignore"):
        k = np.where(nrm > 0, d * s2 / np.where(nrm > 0, nrm, 1.0), np.inf)
    x = _ridge_eig(A, Ha.T @ Y, k)
    return RidgeFit(x=x[:, 0] if one else x, k=np.asarray(k[0]) if one else k)


class ShrinkAt(StrEnum):
    """Where :func:`ridge_fusion_plugin` shrinks: keys of its ``where`` option.

    Attributes
    ----------
    CENTRALISED
        The centre shrinks the fused least-squares estimate.
    DISTRIBUTED
        Each sensor shrinks its own estimate; the centre fuses them as if unbiased.
    """

    CENTRALISED = "centralised"
    DISTRIBUTED = "distributed"


def ridge_fusion_plugin(Hs: Sequence[ArrayLike], Rs: Sequence[ArrayLike], ys: Sequence[ArrayLike],
                        where: ShrinkAt | str = ShrinkAt.CENTRALISED) -> RidgeFit:
    r"""Multi-sensor ridge fusion with plug-in parameters, shrinking at the centre or at each sensor.

    In whitened units (:math:`R_i` known, so :math:`\sigma = 1`): :math:`A_i = H_i^\top R_i^{-1}H_i`,
    :math:`b_i = H_i^\top R_i^{-1}y_i`, :math:`A = \sum_iA_i`, :math:`b = \sum_ib_i`.

    * ``ShrinkAt.CENTRALISED``: :math:`\hat x_{LS} = A^{-1}b`, :math:`\hat k = d/\lVert\hat x_{LS}\rVert^2`
      (plug-in in the metric of the whitened problem), :math:`\hat x = (A + \hat kI)^{-1}b`.
    * ``ShrinkAt.DISTRIBUTED``: each sensor shrinks its own least-squares estimate,
      :math:`\hat x_i = (A_i + \hat k_iI)^{-1}b_i` with :math:`\hat k_i = d/\lVert A_i^{-1}b_i\rVert^2`,
      and the centre fuses these as if they were unbiased, :math:`A^{-1}\sum_iA_i\hat x_i`
      (each :math:`H_i` needs full column rank). At :math:`\hat k_i = 0` both forms are the GLS
      estimate (the lecture's equivalence); with shrinkage they differ.

    Parameters
    ----------
    Hs, Rs, ys : sequences of arrays, shapes (m_i, d), (m_i, m_i), (m_i,) or (m_i, runs)
        Observation matrix, noise covariance and measurements of each sensor (all ys with the
        same number of runs).
    where : ShrinkAt or {"centralised", "distributed"}
        Where the shrinkage is applied.

    Returns
    -------
    RidgeFit
        ``x`` and ``k`` (centralised: the one parameter per run; distributed: the mean of the
        sensors' parameters per run).

    Raises
    ------
    ValueError
        Sequences empty or of unequal length, bad shapes, non-finite entries, a covariance not
        symmetric positive definite, an unknown ``where``, a rank-deficient total information or
        (distributed) a sensor whose :math:`H_i` lacks full column rank.
    """
    where = one_of(where, tuple(map(str, ShrinkAt)), "where")
    for nm, seq in (("Hs", Hs), ("Rs", Rs), ("ys", ys)):
        if isinstance(seq, (str, bytes)) or not hasattr(seq, "__len__"):
            raise TypeError(f"{nm} must be a sequence of arrays, got {type(seq).__name__}")
    if not (len(Hs) == len(Rs) == len(ys)) or len(Hs) == 0:
        raise ValueError("Hs, Rs and ys must be non-empty sequences of equal length")
    step = _CENTRAL_BLOCK_STEP if where == ShrinkAt.CENTRALISED else _BLOCK_STEP
    loop_work((len(Hs),), 0, "Hs, Rs and ys", step=step)
    As, bs, runs, d, one, read = [], [], None, None, True, []
    for i, (H, y) in enumerate(zip(Hs, ys)):
        Ha = as_array(H, f"Hs[{i}]", ndim=(1, 2))
        Ha = Ha[:, None] if Ha.ndim == 1 else Ha
        ya = as_array(y, f"ys[{i}]", ndim=(1, 2))
        if ya.shape[0] != Ha.shape[0]:
            raise ValueError(f"ys[{i}] must have {Ha.shape[0]} rows to match Hs[{i}], got {ya.shape}")
        one = one and ya.ndim == 1
        Y = ya[:, None] if ya.ndim == 1 else ya
        if runs is None:
            runs, d = Y.shape[1], Ha.shape[1]
        elif Y.shape[1] != runs or Ha.shape[1] != d:
            raise ValueError(f"Hs[{i}] and ys[{i}] of shapes {Ha.shape} and {ya.shape} do not match those of "
                             "sensor 0 (Hs[0], ys[0]): every sensor needs the same state size and runs")
        read.append((Ha, Y))
    _blocks_work([Ha.shape for Ha, _ in read], step)   # fuzz 59b C3's class: summed, before the first R's check
    for i, ((Ha, Y), R) in enumerate(zip(read, Rs)):
        Ra = as_covariance(R, dim=Ha.shape[0], name=f"Rs[{i}]")
        RiH = np.linalg.solve(Ra, Ha)
        As.append(Ha.T @ RiH)
        bs.append(RiH.T @ Y)
    A, b = sum(As), sum(bs)
    if information_singular(A):
        raise ValueError("Hs: the total information is singular, no least-squares estimate exists")
    if where == ShrinkAt.CENTRALISED:
        x_ls = np.linalg.solve(A, b)
        nrm = np.sum(x_ls**2, axis=0)
        k = np.where(nrm > 0, d / np.where(nrm > 0, nrm, 1.0), np.inf)
        x = _ridge_eig(A, b, k)
    else:
        acc = np.zeros((d, runs))
        ks = []
        for i, (Ai, bi) in enumerate(zip(As, bs)):
            if information_singular(Ai):
                raise ValueError(f"Hs[{i}] has no full column rank: the sensor has no local estimate to shrink")
            xi_ls = np.linalg.solve(Ai, bi)
            nrm = np.sum(xi_ls**2, axis=0)
            ki = np.where(nrm > 0, d / np.where(nrm > 0, nrm, 1.0), np.inf)
            ks.append(ki)
            acc += Ai @ _ridge_eig(Ai, bi, ki)
        x = np.linalg.solve(A, acc)
        k = np.mean(ks, axis=0)
    return RidgeFit(x=x[:, 0] if one else x, k=np.asarray(k[0]) if one else k)


# --------------------------------------------------------------------------- exact risk of the scalar plug-in
@dataclass(frozen=True)
@frozen_arrays
class PluginRisk:
    r"""Exact MSE and reliability of the scalar plug-in ridge against least squares, in standard-error units.

    Arrays are read-only, of the shape of ``theta``.

    Attributes
    ----------
    theta : ndarray
        True value in standard errors of the mean, :math:`\theta = \sqrt m\,x/\sigma`.
    mse_ratio : ndarray
        MSE of the plug-in over that of least squares (which is 1 in these units).
    bias : ndarray
        :math:`E\hat\theta - \theta`, in standard errors.
    var_ratio : ndarray
        Variance of the plug-in over that of least squares, :math:`\mathrm{Var}\,\hat\theta` (1 for least
        squares); ``mse_ratio = var_ratio + bias**2``.
    reliability : ndarray
        :math:`P(|\hat\theta - \theta| \le c)` of the plug-in.
    reliability_ls : float
        The same for least squares, :math:`2\Phi(c) - 1` (independent of θ).
    """

    theta: FloatArray
    mse_ratio: FloatArray
    bias: FloatArray
    var_ratio: FloatArray
    reliability: FloatArray
    reliability_ls: float


def _plugin_inverse(y: FloatArray, u: FloatArray) -> FloatArray:
    r"""The real root z of :math:`z^3/(z^2 + u) = y` (unique: the map is increasing for u > 0), by Cardano."""
    q = -2.0 * y**3 / 27.0 - u * y
    disc = u * y**4 / 27.0 + u**2 * y**2 / 4.0
    r = np.sqrt(disc)
    return np.cbrt(-q / 2.0 + r) + np.cbrt(-q / 2.0 - r) + y / 3.0


@lru_cache(maxsize=16)
def _quadrature(nodes: int, m: int | None) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """Gauss-Hermite nodes and weights for N(0, 1), and the nodes and weights of u (1 for known σ); read-only
    (cached: a caller's edit would reach every later call)."""
    zn, wz = np.polynomial.hermite_e.hermegauss(nodes)
    wz = wz / np.sqrt(2.0 * np.pi)
    if m is None:
        out = (zn, wz, np.array([1.0]), np.array([1.0]))
    else:
        from scipy.special import gammaln, roots_genlaguerre

        k = (m - 1) / 2.0                       # u ~ Gamma(shape k, scale 1/k)
        v, wv = roots_genlaguerre(nodes, k - 1.0)
        out = (zn, wz, v / k, wv / np.exp(gammaln(k)))
    for a in out:
        a.flags.writeable = False
    return out


def _risk_budget(size: int, m: int | None, names: str, nodes: int = 120) -> None:
    """Rules 9 and 17 for :func:`plugin_risk` of ``size`` values of theta (``nodes``: its default): one quadrature
    of u nodes (1 for known σ, ``nodes`` for an estimated one) x ``nodes`` z nodes a value, some 8 passes each.
    A caller passing a grid of true values names that grid in ``names``."""
    shape = (int(size), 1 if m is None else int(nodes), int(nodes))
    allocation(shape, names)
    work(shape + (8,), names)


#: Largest |theta| and c (standard errors) of :func:`plugin_risk`: theta + c keeps c to about 1e-8.
PLUGIN_RANGE = 1e8
#: Largest ``m`` of :func:`plugin_risk`: beyond 343, ``Gamma((m - 1)/2)`` and the Gauss-Laguerre weights overflow.
PLUGIN_MAX_M = 340


def plugin_risk(theta: ArrayLike, c: float = 1.0, m: int | None = None, nodes: int = 120) -> PluginRisk:
    r"""Exact MSE ratio, bias, variance and reliability of the scalar plug-in ridge :func:`plugin_ridge` (:math:`H = \mathbf 1_m`).

    In units of the standard error :math:`\sigma/\sqrt m` the mean is :math:`Z \sim N(\theta, 1)` and the
    plug-in estimate is :math:`\hat\theta = Z^3/(Z^2 + u)`, with :math:`u = 1` when σ is known and
    :math:`u = s^2/\sigma^2 \sim \chi^2_{m-1}/(m-1)`, independent of Z, when σ is estimated from the same
    m readings. Because :math:`z \mapsto z^3/(z^2 + u)` is increasing, the reliability is exact in closed form
    given u, :math:`\Phi(z_+ - \theta) - \Phi(z_- - \theta)` with :math:`z_\pm` its inverse at :math:`\theta \pm c`;
    the MSE :math:`E(\hat\theta - \theta)^2` and the bias :math:`E\hat\theta - \theta` are Gauss-Hermite quadratures
    over Z (the integrands are smooth), and the expectation over u a generalised Gauss-Laguerre quadrature. No
    Monte Carlo. The variance follows, MSE minus squared bias: the map :math:`z \mapsto z^3/(z^2+1)` has slope
    :math:`(z^4 + 3z^2)/(z^2 + 1)^2`, above 1 for :math:`|z| > 1`, so away from 0 the plug-in *stretches* the noise and
    its variance exceeds that of least squares.

    Parameters
    ----------
    theta : array_like
        True values in standard errors, :math:`\sqrt m\,x/\sigma` (finite, :math:`|\theta| \le 10^8`:
        beyond, :math:`\theta \pm c` does not resolve c in double precision).
    c : float
        Tolerance in standard errors (> 0 and at most :math:`10^8`; the chapter's
        :math:`\delta = \sigma/\sqrt m` is c = 1).
    m : int, optional
        Readings per estimate (2 to ``PLUGIN_MAX_M`` = 340) when σ is estimated; None for known σ.
    nodes : int
        Quadrature nodes, 20 to 200 (default 120: the known-σ MSE ratio to about 10⁻⁸, the
        estimated-σ one to about 3 × 10⁻⁵, the reliabilities to 10⁻⁷).

    Returns
    -------
    PluginRisk
        At each ``theta``: the MSE ratio to least squares, bias, variance ratio, and the reliability of the plug-in
        ridge and of LS.

    Raises
    ------
    ValueError
        Non-finite ``theta``, ``c`` not positive, either beyond ``PLUGIN_RANGE`` (1e8), ``m`` < 2 or
        beyond ``PLUGIN_MAX_M``, or too few ``nodes``.

    References
    ----------
    * Hoerl, A. E., Kennard, R. W., & Baldwin, K. F. (1975). Ridge regression: some simulations.
      *Communications in Statistics*, 4(2), 105-123.
    """
    th = as_array(theta, "theta")
    c = positive_scalar(c, "c")
    for name, big in (("theta", float(np.abs(th).max())), ("c", c)):
        if big > PLUGIN_RANGE:  # theta + c loses the tolerance c, and Cardano's y**4 overflows beyond
            raise ValueError(f"{name} must be at most {PLUGIN_RANGE:g} in magnitude (standard errors), got {big:g}: "
                             "beyond, theta +- c is not resolved in double precision")
    nodes = count(nodes, "nodes", minimum=20)
    if nodes > 200:
        raise ValueError(f"nodes must be at most 200 (the Gauss-Hermite weights underflow beyond), got {nodes}")
    if m is not None:
        m = count(m, "m", minimum=2)
        if m > PLUGIN_MAX_M:  # Gamma((m - 1)/2) overflows: the Gauss-Laguerre weights are inf/inf = NaN
            raise ValueError(f"m must be at most {PLUGIN_MAX_M} (beyond, the Gauss-Laguerre weights of the "
                             f"estimated sigma overflow; sigma is then estimated to about 4 %: use m=None), got {m}")
    _risk_budget(th.size, m, "theta, m and nodes", nodes)
    zn, wz, u, wu = _quadrature(nodes, m)
    t = th[..., None, None]
    z = t + zn[None, :] if th.ndim == 0 else t + zn
    uu = u[:, None]
    est = z**3 / (z**2 + uu)
    w = wu[:, None] * wz
    mse = np.sum(w * (est - t) ** 2, axis=(-2, -1))
    bias = np.sum(w * (est - t), axis=(-2, -1))
    tt = th[..., None]
    rel_u = norm.cdf(_plugin_inverse(tt + c, u) - tt) - norm.cdf(_plugin_inverse(tt - c, u) - tt)
    rel = np.sum(wu * rel_u, axis=-1)
    return PluginRisk(theta=th, mse_ratio=np.asarray(mse), bias=np.asarray(bias), var_ratio=np.asarray(mse - bias**2),
                      reliability=np.asarray(rel), reliability_ls=float(2.0 * norm.cdf(c) - 1.0))


@derived_inputs()
def plugin_crossings(c: float = 1.0, m: int | None = None, upper: float = 10.0) -> dict[str, float]:
    r"""Where the scalar plug-in ridge stops beating least squares, exactly (:func:`plugin_risk`).

    Parameters
    ----------
    c : float
        Tolerance of the reliability in standard errors (> 0).
    m : int, optional
        Readings per estimate when σ is estimated (2 to ``PLUGIN_MAX_M`` = 340); None for known σ.
    upper : float
        Largest θ searched (> 1).

    Returns
    -------
    dict
        ``"reliability"``: the smallest θ > 0 at which the plug-in's reliability falls to that of least
        squares; ``"mse"``: the smallest θ at which its MSE ratio rises to 1; ``"peak_theta"`` and
        ``"peak_ratio"``: the largest MSE ratio on (0, ``upper``] and where it is; ``"ratio_0"``: the ratio at θ = 0;
        ``"variance"``: the smallest θ at which the variance ratio rises to 1, ``"var_peak_theta"`` and
        ``"var_peak_ratio"``: its largest value on (0, ``upper``] and where it is. θ in standard errors,
        :math:`\sqrt m\,x/\sigma`.

    Raises
    ------
    ValueError
        ``c`` not positive, ``upper`` <= 1, or no crossing below ``upper``.
    """
    from scipy.optimize import brentq, minimize_scalar

    c = positive_scalar(c, "c")
    upper = scalar(upper, "upper", lo=1.0, lo_open=True)
    grid = np.linspace(1e-6, upper, 121)
    r = plugin_risk(grid, c, m)
    out = {}
    for key, f in (("reliability", lambda t: float(plugin_risk(t, c, m).reliability) - r.reliability_ls),
                   ("mse", lambda t: float(plugin_risk(t, c, m).mse_ratio) - 1.0),
                   ("variance", lambda t: float(plugin_risk(t, c, m).var_ratio) - 1.0)):
        # the plug-in is better (reliability above LS's, MSE or variance ratio below 1) from θ = 0 up to the crossing
        sign = {"reliability": r.reliability > r.reliability_ls, "mse": r.mse_ratio < 1.0,
                "variance": r.var_ratio < 1.0}[key]
        idx = np.nonzero(sign[:-1] & ~sign[1:])[0]
        if idx.size == 0:
            raise ValueError(f"upper = {upper:g}: no {key} crossing below it")
        i = int(idx[0])
        out[key] = float(brentq(f, grid[i], grid[i + 1], xtol=1e-10))
    for key, attr in (("peak", "mse_ratio"), ("var_peak", "var_ratio")):
        i = int(np.argmax(getattr(r, attr)))
        lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, grid.size - 1)]
        opt = minimize_scalar(lambda t, a=attr: -float(getattr(plugin_risk(t, c, m), a)), bounds=(lo, hi),
                              method="bounded", options={"xatol": 1e-8})
        out[f"{key}_theta"], out[f"{key}_ratio"] = float(opt.x), float(-opt.fun)
    out["ratio_0"] = float(plugin_risk(0.0, c, m).mse_ratio)
    return out


@finite_result("A, x and k")
def ridge_risk(A: ArrayLike, x: ArrayLike, k: ArrayLike) -> FloatArray:
    r"""Exact MSE of the centralised ridge fusion with a fixed k, :math:`\hat x = (A + kI)^{-1}b`, at a true x.

    With :math:`A = \sum_iH_i^\top R_i^{-1}H_i` and :math:`b = \sum_iH_i^\top R_i^{-1}y_i` (so that
    :math:`\mathrm{cov}\,b = A`), and :math:`B = (A + kI)^{-1}`:

    .. math:: \mathrm{MSE}(k) = \mathrm{tr}(BAB) + k^2x^\top B^2x ,

    :math:`\mathrm{tr}\,A^{-1}` (least squares) at k = 0, with derivative :math:`-2\,\mathrm{tr}\,A^{-2} < 0` there for
    every x: some k > 0 always lowers the MSE (Hoerl & Kennard 1970), but the best k depends on x.

    Parameters
    ----------
    A : array_like, shape (d, d)
        Total information, symmetric positive definite.
    x : array_like, shape (d,)
        True value.
    k : array_like
        Ridge parameter(s) (>= 0).

    Returns
    -------
    ndarray, the shape of ``k``
        MSE(k) = tr(BAB) + k²xᵀB²x at each entry of ``k`` (tr A⁻¹, least squares, at k = 0).

    Raises
    ------
    ValueError
        ``A`` beyond the work budget (``d**3`` units of 0.022: d of about 3,560), ``k`` and ``A`` beyond the memory
        budget (5 float64 arrays of ``k.size x d``: ``k.size x d`` of at most about 5.4e7), not symmetric positive
        definite (or singular to working precision where ``k`` holds 0),
        ``x`` of the wrong length, ``k`` negative or non-finite; a risk that overflows (``A``, ``x``
        and ``k`` each in range, their products not).

    References
    ----------
    * Hoerl, A. E., & Kennard, R. W. (1970). Ridge regression: biased estimation for nonorthogonal
      problems. *Technometrics*, 12(1), 55-67.
    """
    Aa = as_array(A, "A", subnormal=True)  # a covariance: as_covariance's rule for tiny entries and shapes applies
    # rule 17 (fix 65a, after fuzz 57b D2: d = 5,792, the input budget, ran 37 CPU-s unchecked): A's check and eigh,
    # 0.19-0.21 ns a d**3 measured (d = 1,500 and 5,792; time.process_time, OPENBLAS_NUM_THREADS=1, the shared machine)
    d = Aa.shape[0] if Aa.ndim else 1
    dense_work(1, d, "A", 2.2 * DENSE_CUBE)
    ka = as_array(k, "k", nonnegative=True)
    # rules 9 and 17 (fuzz 59b C2: k of 10**7 against d = 1,000 was a raw MemoryError for 74.5 GiB): each k meets A's
    # d eigenvalues in (k.size, d) arrays, before A's check and eigh. tracemalloc's peak measured 4.0-4.2 such arrays
    # (d = 100 and 1,000), 4.5 at d = 2 and 5.0 at d = 1 (k's own copy): 5 held; 8-23 ns a (k, d) element measured
    # (d = 1,000 to 1: min of 3, time.process_time, OPENBLAS_NUM_THREADS=1, the shared machine): 3 units
    allocation((ka.size, d), "k and A", arrays=5)
    work((ka.size, d), "k and A", weight=3)
    Aa = as_covariance(Aa, name="A")
    xa = as_array(x, "x", shape=(Aa.shape[0],))
    lam, V = np.linalg.eigh(Aa)
    if np.any(ka == 0) and lam[0] <= lam[-1] * lam.size * np.finfo(float).eps:  # rule 5: a singular system
        raise ValueError(f"A is singular to working precision (eigenvalues {lam[0]:.3g} .. {lam[-1]:.3g}): "
                         "the least-squares risk at k = 0 is unbounded")
    c2 = (V.T @ xa) ** 2
    kk = ka[..., None]
    f = 1.0 / (lam + kk)
    return np.sum(lam * f**2 + kk**2 * c2 * f**2, axis=-1)


#: The largest condition number of ``A`` that :func:`best_ridge_k` accepts for d = 1, ``1 / eps`` (float64); for
#: a (d, d) matrix the limit is ``MAX_RIDGE_CONDITION / d`` (the rule of :func:`ridge_risk` at k = 0).
MAX_RIDGE_CONDITION = 1.0 / float(np.finfo(float).eps)


@derived_inputs()
def best_ridge_k(A: ArrayLike, x: ArrayLike) -> tuple[float, float]:
    r"""The fixed k that minimises :func:`ridge_risk` at a true x, and that MSE (bounded search over log k).

    Parameters
    ----------
    A : array_like, shape (d, d)
        Total information, symmetric positive definite, with condition number at most
        :math:`1/(d\,\varepsilon)` (``4.5e15 / d``, with ε the float64
        machine epsilon): beyond it the smallest eigenvalue is rounding noise (a singular A leaves its zero
        eigenvalue at about ``1e-17``), and the ridge path over k, which starts from ``A^{-1}`` at k = 0, is
        meaningless.
    x : array_like, shape (d,)
        True value (not zero: at x = 0 the MSE falls towards 0 as k grows).

    Returns
    -------
    tuple of float
        ``(k, mse)``.

    Raises
    ------
    ValueError
        As :func:`ridge_risk`, ``x`` zero, or ``A`` numerically singular (condition number beyond
        :math:`1/(d\,\varepsilon)`).
    """
    from scipy.optimize import minimize_scalar

    Aa = as_array(A, "A", ndim=2, subnormal=True)  # a covariance: as_covariance's rule for tiny entries applies
    # rule 17 (fuzz 38a C9): an eigh of A at each of the bounded search's evaluations, 1.45 ns a d**3 measured
    dense_work(1, Aa.shape[0], "A", 15 * DENSE_CUBE)
    Aa = as_covariance(Aa, name="A")
    xa = as_array(x, "x", shape=(Aa.shape[0],))
    if not np.any(xa):
        raise ValueError("x must not be zero (the MSE then decreases for every k)")
    if not 0.0 < float(xa @ xa) < np.inf:  # |x|^2 underflows or overflows: the search interval is undefined
        raise ValueError("x is too small or too large: |x|^2 is not a positive finite number")
    lam = np.linalg.eigvalsh(Aa)
    limit = MAX_RIDGE_CONDITION / Aa.shape[0]
    if lam[0] <= lam[-1] / limit:  # cond(A) >= 1/(d eps): the rule of ridge_risk at k = 0
        raise ValueError(f"A is numerically singular (eigenvalues {lam[0]:.3g} .. {lam[-1]:.3g}): its condition "
                         f"number is beyond 1/(d eps) = {limit:.3g}, the smallest eigenvalue is rounding noise")
    lo, hi = np.log(1e-8 / float(xa @ xa)), np.log(1e4 * lam.max() + 1.0 / float(xa @ xa))
    grid = np.linspace(lo, hi, 400)
    r = ridge_risk(Aa, xa, np.exp(grid))
    i = int(np.argmin(r))
    opt = minimize_scalar(lambda t: float(ridge_risk(Aa, xa, np.exp(t))), bounds=(grid[max(i - 1, 0)],
                          grid[min(i + 1, grid.size - 1)]), method="bounded", options={"xatol": 1e-10})
    return float(np.exp(opt.x)), float(opt.fun)


def james_stein(y: ArrayLike, sigma: float) -> FloatArray:
    r"""The James-Stein estimate of a normal mean, :math:`\hat x = \big(1 - (d-2)\sigma^2/\lVert y\rVert^2\big)\,y`.

    For :math:`y \sim N(x, \sigma^2 I_d)` with :math:`d \ge 3` it has a smaller total MSE than :math:`y`
    itself for every x (James & Stein 1961). It is *not* a linear estimator: the shrinkage factor depends on
    :math:`\lVert y\rVert`, so :math:`\hat x(ay) \ne a\,\hat x(y)` in general (ridge with a fixed k is linear).

    Parameters
    ----------
    y : array_like, shape (d,) or (d, runs)
        Observations, d >= 3 (columns: independent runs).
    sigma : float
        Known noise SD (> 0), in the units of y.

    Returns
    -------
    ndarray, the shape of y
        The estimate of x: each column of ``y`` shrunk by its own factor 1 − (d − 2)σ²/‖y‖².

    Raises
    ------
    ValueError
        d < 3, non-finite values, a zero column or ``sigma`` not positive.

    References
    ----------
    * James, W., & Stein, C. (1961). Estimation with quadratic loss. *Proceedings of the Fourth Berkeley
      Symposium on Mathematical Statistics and Probability*, 1, 361-379.
    """
    ya = as_array(y, "y", ndim=(1, 2))
    sigma = std_scalar(sigma, "sigma")
    d = ya.shape[0]
    if d < 3:
        raise ValueError(f"y must have dimension d >= 3 for the James-Stein estimate, got d = {d}")
    nrm = np.sum(ya**2, axis=0)
    if np.any(nrm == 0):
        raise ValueError("y must not be zero (the shrinkage factor is undefined)")
    return (1.0 - (d - 2) * sigma**2 / nrm) * ya
