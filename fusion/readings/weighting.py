r"""Adaptive and least-squares weighted fusion with estimated sensor variances.

The lecture notes, §2.1-2.3. ``n`` sensors read one constant quantity
:math:`X` at times :math:`i = 1..k`: :math:`X_p(i) = X + V_p(i)`, with independent zero-mean
noise of variance :math:`\sigma_p^2`.

* :func:`optimal_weights`, :func:`minimum_variance`: the Lagrange solution (sec. 2.1),
  :math:`W_p^* = \sigma_p^{-2} / \sum_i \sigma_i^{-2}`, :math:`\sigma^2_{\min} = (\sum_p\sigma_p^{-2})^{-1}`.
* :func:`running_variances`: the variance estimates from auto- and cross-correlations of
  sec. 2.1 (``"lecture"``: :math:`\hat\sigma_p^2 = R_{pp}(k) - \bar R_p(k)`, uncentred moments)
  or the centred (covariance) estimator (``"centred"``), for every k at once. The centred form is
  Grubbs-type: Grubbs's (1948) two-instrument estimator :math:`s_{pp} - s_{pq}` averaged over the
  partners q (for three instruments Grubbs gives :math:`s_{11} - s_{12} - s_{13} + s_{23}`).
* :func:`awf`: adaptive weighted fusion of the time averages :math:`\bar X_p(k)`.
* :func:`learned_variances`, :func:`ls_learning`: the variance-learning recursion of sec. 2.2,
  as printed and with our bias correction.
* :func:`wls`: weighted least squares :math:`(H^\top W H)^{-1} H^\top W Y`.
* :func:`running_average`, :func:`tracking_variances`, :func:`fuse_current`: the same variance
  estimators with a growing memory (the lecture's 1/k recursion), exponential forgetting or a
  sliding window, plus the per-sensor sample variance, and fusion of the *current* readings with
  the estimated weights (for a time-varying quantity).
* :func:`difference_variances`: each sensor's own variance from half the mean square of its first
  differences (von Neumann 1941), which needs no other sensor and ignores a slow drift of X.
* :func:`cumulative_fusion`: per-sample inverse-variance fusion accumulated over time, the
  minimum-variance estimate of a *constant* X when the variances change from sample to sample.

Arrays of readings have shape ``(..., k, n)``: any leading axes (Monte-Carlo runs) are
broadcast, so the experiments are vectorised.

References
----------
* Grubbs, F. E. (1948). On estimating precision of measuring instruments and product
  variability. *Journal of the American Statistical Association*, 43(242), 243-264.
* von Neumann, J. (1941). Distribution of the ratio of the mean square successive difference to
  the variance. *The Annals of Mathematical Statistics*, 12(4), 367-395.
* Aitken, A. C. (1936). On least squares and linear combination of observations.
  *Proceedings of the Royal Society of Edinburgh*, 55, 42-48.
* An explanation of multi-sensor data fusion algorithms (多传感器数据融合算法讲解).
  Lecture notes, web copy (in Chinese; author and date not stated).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike

from fusion._validation import derived_inputs, finite_result, flag, integer, read_once
from fusion._frozen import frozen_arrays
from fusion._results import BATCH, RTOL as _RTOL, ResultSpec, array, trusted, validated_post_init
from fusion._validation import (_numeric, FloatArray, as_array, check_magnitude, count, one_of, positive_scalar, scalar,
                                std_scalar)
from fusion._shown import shown
from fusion._counts import broadcast
from fusion._limits import DENSE_CUBE, work
from fusion.readings._moments import _estimates_from, _moment_stack
from fusion.readings._windows import window_sums

__all__ = ["LSLearning", "optimal_weights", "minimum_variance", "inverse_variance_weights", "running_variances",
           "variance_estimates", "running_means", "AWFResult", "awf", "learned_variances", "corrected_variances",
           "ls_learning", "wls", "VARIANCE_FLOOR", "GUARDS", "lecture_variance_sd", "lecture_samples_needed",
           "learned_variance_limit", "learned_fused_variance", "MEMORIES", "running_average", "tracking_variances",
           "fuse_current", "difference_variances", "TIME_WEIGHTS", "cumulative_fusion"]

Estimator = Literal["lecture", "centred"]
Memory = Literal["growing", "forgetting", "window"]

#: How the running moments of :func:`tracking_variances` weigh the past: ``"growing"`` the
#: lecture's recursion (every sample weighs 1/k), ``"forgetting"`` exponential forgetting
#: (weight :math:`\lambda^{k-i}`, normalised), ``"window"`` the last ``window`` samples.
MEMORIES: tuple[str, ...] = ("growing", "forgetting", "window")
Guard = Literal["floor", "abs", "equal", "none"]

#: What to do with non-positive variance estimates before inverting them (the lecture says
#: nothing): ``"floor"`` raise them to a tiny relative floor (the package default, which hands
#: such a sensor almost all the weight), ``"abs"`` use :math:`|\hat\sigma^2|`, ``"equal"`` fall
#: back to equal weights for any row with a non-positive estimate, ``"none"`` the literal
#: algorithm: invert the estimates as they are (weights can be negative or huge).
GUARDS: tuple[str, ...] = ("floor", "abs", "equal", "none")

#: Relative floor applied to variance estimates before inverting them:
#: :math:`\max(\hat\sigma^2, 10^{-12}\,\overline{|\hat\sigma^2|})`. A non-positive estimate
#: therefore gets a very large (but finite) weight; the chapter counts how often it happens.
VARIANCE_FLOOR = 1e-12


def _as_sample_array(X: ArrayLike, name: str = "X", min_sensors: int = 2) -> FloatArray:
    arr = _numeric(X, name)
    if arr.ndim < 2:
        raise ValueError(f"{name} must have shape (..., k, n) (samples by sensors), got shape {arr.shape}")
    if arr.shape[-1] < min_sensors:
        raise ValueError(f"{name} needs at least {min_sensors} sensors (last axis), got {arr.shape[-1]}")
    if arr.shape[-2] == 0:
        raise ValueError(f"{name} has no samples (axis -2 is empty)")
    return check_magnitude(arr, name)


def _as_variances(variances: ArrayLike, name: str = "variances") -> FloatArray:
    v = _numeric(variances, name)
    if v.ndim < 1 or v.shape[-1] == 0:
        raise ValueError(f"{name} must be a non-empty array of variances, got shape {v.shape}")
    check_magnitude(v, name)
    if np.any(v <= 0):
        raise ValueError(f"{name} must be finite and strictly positive")
    return v


def optimal_weights(variances: ArrayLike) -> FloatArray:
    r"""Minimum-variance weights of independent unbiased sensors (sec. 2.1, Lagrange).

    .. math:: W_p^* = \frac{1}{\sigma_p^2 \sum_{i=1}^n \sigma_i^{-2}}

    Parameters
    ----------
    variances : array_like, shape (..., n)
        Noise variances :math:`\sigma_p^2` (unit²), strictly positive.

    Returns
    -------
    ndarray, shape (..., n)
        Positive weights summing to one along the last axis.
    """
    v = _as_variances(variances)
    inv = 1.0 / v
    return inv / inv.sum(axis=-1, keepdims=True)


def minimum_variance(variances: ArrayLike) -> FloatArray | float:
    r"""Error variance of the optimally weighted fusion, :math:`(\sum_p \sigma_p^{-2})^{-1}`.

    Parameters
    ----------
    variances : array_like, shape (..., n)

    Returns
    -------
    float or ndarray, shape (...)
        (Σ_p σ_p⁻²)⁻¹ over the last axis: a float for one set of variances, else one per leading index.
    """
    v = _as_variances(variances)
    out = 1.0 / (1.0 / v).sum(axis=-1)
    return float(out) if out.ndim == 0 else out


def inverse_variance_weights(estimates: ArrayLike, floor: float = VARIANCE_FLOOR, guard: Guard = "floor") -> FloatArray:
    r"""Weights :math:`\propto 1/\hat\sigma_p^2` from *estimated* variances, which may be :math:`\le 0`.

    The lecture inverts its estimates as they are; a non-positive estimate needs a guard, which
    the lecture leaves open (see :data:`GUARDS`):

    * ``"floor"`` (default): a non-positive estimate is raised to :math:`\text{floor}\cdot\overline{|\hat\sigma^2|}`
      (mean over the sensors of that row), so it gets almost all the weight; a positive estimate is used as it is,
      however small beside the mean (a sensor of huge variance leaves the others' weights exact);
    * ``"abs"``: :math:`|\hat\sigma_p^2|`, then the same floor (for exact zeros only);
    * ``"equal"``: a row with any non-positive estimate gets equal weights :math:`1/n`;
    * ``"none"``: :math:`W_p = \hat\sigma_p^{-2}/\sum_i\hat\sigma_i^{-2}` literally; weights can be
      negative and arbitrarily large.

    A row of zeros gives equal weights under every guard but ``"none"``.

    Parameters
    ----------
    estimates : array_like, shape (..., n)
        Variance estimates (unit²), finite.
    floor : float
        Relative floor (default :data:`VARIANCE_FLOOR`), finite and > 0: a floor of zero
        would give an infinite weight to an estimate <= 0, a negative floor a negative weight.
    guard : {"floor", "abs", "equal", "none"}

    Returns
    -------
    ndarray, shape (..., n)
        Weights summing to one (positive except under ``"none"``). Degenerate cases: a single sensor gets weight 1;
        identical estimates give equal weights.

    Raises
    ------
    ValueError
        Empty or non-finite estimates, ``floor`` not finite and positive, an unknown ``guard``;
        under ``"none"``, an estimate equal to zero or a row whose inverse estimates sum to zero
        (the literal weights are undefined).
    """
    guard = one_of(guard, GUARDS, "guard")
    floor = positive_scalar(floor, "floor")
    v = as_array(estimates, "estimates", nonempty=False)
    if v.ndim < 1 or v.shape[-1] == 0 or v.size == 0:
        raise ValueError(f"estimates must have a non-empty last (sensor) axis, got shape {v.shape}")
    if guard == "none":
        if np.any(v == 0.0):
            raise ValueError("estimates contain an exact zero: the unguarded weights are undefined")
        inv = 1.0 / v
        tot = inv.sum(axis=-1, keepdims=True)
        if np.any(tot == 0.0):
            raise ValueError("the inverse estimates of a row sum to zero: the unguarded weights are undefined")
        return inv / tot
    return _guarded_weights(v, guard, floor)


def _guarded_weights(v: np.ndarray, guard: str, floor: float) -> FloatArray:
    """:func:`inverse_variance_weights` of validated estimates under ``guard`` ("floor", "abs" or "equal"); also of
    the broadcast :func:`cumulative_fusion` holds to its own budget (fuzz 58b C3: the input budget named estimates)."""
    inv = 1.0 / _guarded(v, guard, floor)
    w = inv / inv.sum(axis=-1, keepdims=True)
    if guard == "equal":
        w = np.where(np.any(v <= 0.0, axis=-1, keepdims=True), 1.0 / v.shape[-1], w)
    return w


def _guarded(v: np.ndarray, guard: str, floor: float) -> np.ndarray:
    """The estimates that :func:`inverse_variance_weights` inverts under ``guard`` ("floor", "abs" or "equal"):
    ``|v|`` under "abs"; an estimate that is not positive raised to ``floor`` times its row's mean ``|v|``, and a
    row of zeros all ones (equal weights). A positive estimate is kept as it is, however far below the mean (fuzz
    37a D2: raising every estimate to the floor made the precise sensors' weights equal beside one of a huge
    variance, ``(1, 2, 4, 1e13)`` weighted as ``(1, 1, 0.6, ...)``)."""
    if guard == "abs":
        v = np.abs(v)
    scale = np.abs(v).mean(axis=-1, keepdims=True)
    zero = scale == 0.0
    return np.where(zero, 1.0, np.where(v > 0.0, v, floor * np.where(zero, 1.0, scale)))


def lecture_variance_sd(level: float, k: ArrayLike, variances: ArrayLike) -> FloatArray:
    r"""Large-:math:`|X|` standard deviation of the lecture's variance estimate (sec. 2.1).

    :math:`X_p^2 - \frac{1}{n-1}\sum_{q\ne p}X_pX_q = (X+V_p)(V_p-\bar V_{-p})`; its time average
    contains :math:`X\,\overline{(V_p-\bar V_{-p})}`, whose SD dominates for :math:`|X|\gg\sigma`:

    .. math:: \mathrm{SD}[\hat\sigma_p^2(k)] \approx |X|\sqrt{\frac1k\Big(\sigma_p^2
              + \frac{1}{(n-1)^2}\sum_{q\ne p}\sigma_q^2\Big)} .

    Parameters
    ----------
    level : float
        The constant measured quantity :math:`X` (readings' unit).
    k : array_like of float
        Number of samples (>= 1); broadcast against the sensor axis as ``k[..., None]``. A real ``k`` is the
        formula's continuous extension, the one :func:`lecture_samples_needed` inverts (it returns a real number
        of samples): an integer ``k`` is a count of samples, a non-integer one a point of that curve.
    variances : array_like, shape (n,)
        True noise variances (unit²), ``n >= 2``.

    Returns
    -------
    ndarray, shape (..., n)
        Predicted SD of each sensor's estimate (unit²).
    """
    v = _as_variances(variances)
    if v.ndim != 1 or v.size < 2:
        raise ValueError(f"variances must have shape (n,) with n >= 2, got {v.shape}")
    kk = _numeric(k, "k")
    if not np.all(np.isfinite(kk)) or np.any(kk < 1):
        raise ValueError("k must be >= 1")
    check_magnitude(kk, "k")  # rule 2: at most MAX_MAGNITUDE
    X = scalar(level, "level")
    if not np.isfinite(X):
        raise ValueError("level must be finite")
    # rules 9 and 17 on k against variances, (..., n) (fuzz 57b C5): 2.0 arrays at tracemalloc's peak, 2.3 ns each
    broadcast((("k", kk.shape + (1,)), ("variances", v.shape)), arrays=2, weight=1)
    n = v.size
    per = v + (v.sum() - v) / (n - 1) ** 2
    return abs(X) * np.sqrt(per / kk[..., None])



def lecture_samples_needed(level: float, variances: ArrayLike, rel_sd: float = 0.5) -> FloatArray:
    r"""Samples the lecture's variance estimate needs before its SD falls to ``rel_sd`` times the variance (sec. 2.1).

    Solving the large-:math:`|X|` formula of :func:`lecture_variance_sd` for :math:`k` at
    :math:`\mathrm{SD}[\hat\sigma_p^2(k)] = r\,\sigma_p^2`:

    .. math:: k_p = \frac{X^2}{(r\,\sigma_p^2)^2}\Big(\sigma_p^2 + \frac{1}{(n-1)^2}\sum_{q\ne p}\sigma_q^2\Big).

    It counts the term that grows with the level only: at ``level = 0`` it is 0, and the
    estimator's own SD (of order :math:`\sigma_p^2\sqrt{2/k}`) decides.

    Parameters
    ----------
    level : float
        The constant measured quantity :math:`X` (readings' unit).
    variances : array_like, shape (n,)
        True noise variances (unit²), ``n >= 2``.
    rel_sd : float
        Target SD as a share :math:`r` of each sensor's variance (> 0), e.g. 0.5.

    Returns
    -------
    ndarray, shape (n,)
        Samples needed per sensor (a real number; round up for a count).

    References
    ----------
    * An explanation of multi-sensor data fusion algorithms (lecture notes), sec. 2.1: the estimate
      :math:`\hat\sigma_p^2 = R_{pp}(k) - \bar R_p(k)` of uncentred moments.
    """
    r = std_scalar(rel_sd, "rel_sd")
    v = _as_variances(variances)
    if v.ndim != 1 or v.size < 2:
        raise ValueError(f"variances must have shape (n,) with n >= 2, got {v.shape}")
    sd1 = np.reshape(lecture_variance_sd(level, 1, v), v.shape)   # SD at k = 1: |X| sqrt(per), per sensor
    return (sd1 / (r * v)) ** 2


def learned_variance_limit(variances: ArrayLike) -> FloatArray:
    r"""Limit of the learned variances of sec. 2.2: :math:`(1-\frac2n)R_i + \frac1{n^2}\sum_j R_j`.

    It is :math:`E[(y_{mi}-\bar y_m)^2]`, hence the almost-sure limit of :func:`learned_variances`.

    Parameters
    ----------
    variances : array_like, shape (..., n)
        True noise variances :math:`R_i` (unit²), ``n >= 2``.

    Returns
    -------
    ndarray, shape (..., n)
        Each sensor's limit (1 − 2/n)Rᵢ + ΣR/n², in the shape of ``variances``.
    """
    R = _as_variances(variances)
    n = R.shape[-1]
    if n < 2:
        raise ValueError(f"variances must hold n >= 2 sensors (its last axis), got {n}")
    return (1 - 2 / n) * R + R.sum(axis=-1, keepdims=True) / n**2


def learned_fused_variance(variances: ArrayLike) -> FloatArray | float:
    r"""Error variance of the fusion with the limit of the learned weights of sec. 2.2.

    With :math:`L_i` = :func:`learned_variance_limit` and :math:`w_i = L_i^{-1}/\sum_j L_j^{-1}`,
    the fused variance is :math:`\sum_i w_i^2R_i`. For :math:`n \ge 3` it never exceeds the
    arithmetic mean's :math:`\frac{1}{n^2}\sum_iR_i`: :math:`w_i` decreases and :math:`w_iR_i`
    increases with :math:`R_i`, so Chebyshev's sum inequality, applied twice, gives
    :math:`\sum w_i\,(w_iR_i) \le \frac1n\sum w_i\sum w_iR_i \le \frac{1}{n^2}(\sum w_i)^2\sum R_i`,
    with equality iff all :math:`R_i` are equal (and always for n = 2, where :math:`w_i = \frac12`).

    Parameters
    ----------
    variances : array_like, shape (..., n)
        True noise variances :math:`R_i` (unit²), ``n >= 2``.

    Returns
    -------
    float or ndarray, shape (...)
        Σ wᵢ²Rᵢ with w the optimal weights of the limits: a float for one set, else one per leading index.
    """
    R = _as_variances(variances)
    w = optimal_weights(learned_variance_limit(R))
    out = np.sum(w**2 * R, axis=-1)
    return float(out) if out.ndim == 0 else out


def running_means(X: ArrayLike) -> FloatArray:
    r"""Time averages :math:`\bar X_p(k) = \frac{k-1}{k}\bar X_p(k-1) + \frac1k X_p(k)` for every k.

    Parameters
    ----------
    X : array_like, shape (..., K, n)

    Returns
    -------
    ndarray, shape (..., K, n)
        Entry [..., k − 1, p]: the mean of sensor p's first k samples.
    """
    A = _as_sample_array(X, min_sensors=1)
    k = np.arange(1, A.shape[-2] + 1, dtype=float)[:, None]
    return np.cumsum(A, axis=-2) / k


def running_variances(X: ArrayLike, estimator: Estimator = "lecture") -> FloatArray:
    r"""Variance estimates of every sensor after k = 1..K samples (sec. 2.1).

    With the running moments (the lecture's recursions, written as cumulative means)

    .. math::

        R_{pq}(k) = \frac{k-1}{k} R_{pq}(k-1) + \frac1k X_p(k) X_q(k), \qquad
        \bar R_p(k) = \frac{1}{n-1}\sum_{q\ne p} R_{pq}(k),

    the ``"lecture"`` estimator is :math:`\hat\sigma_p^2 = R_{pp}(k) - \bar R_p(k)`. It rests on
    :math:`E[X_pX_q] = E[X^2]` and :math:`E[X_p^2] = E[X^2] + \sigma_p^2`, true in expectation,
    but its sampling error contains the term :math:`X\,(\bar V_p - \bar V_q)`, which grows with
    :math:`|X|`: it uses the raw moments by the lecture's definition and is not shift invariant.

    The ``"centred"`` estimator (Grubbs-type: Grubbs's 1948 two-instrument estimator averaged over
    the partners) replaces the moments by covariances,
    :math:`C_{pq}(k) = R_{pq}(k) - \bar X_p(k)\bar X_q(k)`:
    :math:`\hat\sigma_p^2 = C_{pp}(k) - \frac1{n-1}\sum_{q\ne p} C_{pq}(k)`. It does not depend on
    :math:`X` at all (shift invariant); its mean is :math:`\frac{k-1}{k}\sigma_p^2` (1/k moments). It is
    computed from the readings minus each sensor's median reading, so that it is shift invariant in floating
    point too (the difference of moments cancels at the scale of the spread, not of an offset).

    Parameters
    ----------
    X : array_like, shape (..., K, n)
        Readings, ``n >= 2`` sensors.
    estimator : {"lecture", "centred"}

    Returns
    -------
    ndarray, shape (..., K, n)
        Estimates in unit²; they can be negative (never clipped here).
    """
    estimator = one_of(estimator, ("lecture", "centred"), "estimator")
    A = _as_sample_array(X)
    k = np.arange(1, A.shape[-2] + 1, dtype=float)[:, None]
    return _moment_estimates(A, estimator, lambda Z: np.cumsum(Z, axis=-2) / k)


def _running_estimates(X: ArrayLike) -> tuple[FloatArray, FloatArray, FloatArray]:
    """:func:`running_variances` of both estimators and :func:`running_means` of ``X``, from one pass of running
    moments (the arrays those functions return, bit for bit: each column's running average is the same cumulative
    sum, whatever the columns beside it; ``tests/test_weighting.py``).

    Returns
    -------
    lecture, centred, means : ndarray, shape (..., K, n)
    """
    A = _as_sample_array(X)
    n = A.shape[-1]
    k = np.arange(1, A.shape[-2] + 1, dtype=float)[:, None]
    avg = np.cumsum(np.concatenate([_moment_stack(A, "lecture"), _moment_stack(A, "centred")], axis=-1), axis=-2) / k
    lecture, centred = avg[..., :3 * n], avg[..., 3 * n:]
    return _estimates_from(lecture, "lecture"), _estimates_from(centred, "centred"), lecture[..., 2 * n:]


def variance_estimates(X: ArrayLike, estimator: Estimator = "lecture") -> FloatArray:
    r"""The variance estimates of :func:`running_variances` after all K samples only.

    Equal to ``running_variances(X, estimator)[..., -1, :]``, without the estimates at every k
    (for many runs of a fixed length).

    Parameters
    ----------
    X : array_like, shape (..., K, n)
        Readings, ``n >= 2`` sensors.
    estimator : {"lecture", "centred"}

    Returns
    -------
    ndarray, shape (..., n)
        Estimates in unit²; they can be negative (never clipped here).
    """
    estimator = one_of(estimator, ("lecture", "centred"), "estimator")
    A = _as_sample_array(X)
    return _moment_estimates(A, estimator, lambda Z: Z.mean(axis=-2, keepdims=True))[..., 0, :]


def _moment_estimates(A: FloatArray, estimator: str, average: Callable[[FloatArray], FloatArray]) -> FloatArray:
    r"""The cross-moment variance estimates from the averaged moments, in O(n) per sample.

    Only the diagonal :math:`R_{pp}` and the row sums :math:`\sum_q R_{pq}` of the moment matrix
    enter the estimate, and :math:`\sum_q X_pX_q = X_pS` with :math:`S = \sum_q X_q`; so the
    running averages of :math:`X_p^2`, :math:`X_pS` and :math:`X_p` (one call of ``average`` on
    their stack) replace the n x n matrix.
    """
    return _estimates_from(average(_moment_stack(A, estimator)), estimator)


def _awf_relations(v: dict, cls: str) -> None:
    """The weights of every instant sum to one and the fused value is their weighted sum of the time averages
    (to ``fusion._results.RTOL`` of the sums of magnitudes: ``guard="none"`` allows large weights of both signs)."""
    w, m = v["weights"], v["means"]
    if (np.abs(w.sum(axis=-1) - 1.0) > _RTOL * np.abs(w).sum(axis=-1)).any():
        raise ValueError(f"{cls}.weights must sum to one at every instant (over the last axis)")
    wm = w * m
    if (np.abs(wm.sum(axis=-1) - v["value"]) > _RTOL * np.abs(wm).sum(axis=-1) + np.finfo(float).tiny).any():
        raise ValueError(f"{cls}.value must be the weighted sum of {cls}.means with {cls}.weights at every instant")


@dataclass(frozen=True)
class AWFResult:
    """Result of :func:`awf`.

    Validated where it is built (``dataclasses.replace`` included; ``fusion._results``): every array finite,
    of the shapes below with the same leading batch axes, the weights of every instant summing to one and
    ``value`` their weighted sum of ``means``; a :class:`ValueError` names the field. Arrays are read-only.

    Attributes
    ----------
    value : ndarray, shape (..., K)
        Fused estimate :math:`\\hat X(k) = \\sum_p W_p(k) \\bar X_p(k)` after each sample.
    weights : ndarray, shape (..., K, n)
        Weights from the estimated variances (floored, see :func:`inverse_variance_weights`).
    variances : ndarray, shape (..., K, n)
        Raw variance estimates (may be negative).
    means : ndarray, shape (..., K, n)
        Time averages :math:`\\bar X_p(k)`.
    """

    value: FloatArray
    weights: FloatArray
    variances: FloatArray
    means: FloatArray

    __result_spec__ = ResultSpec(
        {"value": array(BATCH, "K"), "weights": array(BATCH, "K", "n"), "variances": array(BATCH, "K", "n"),
         "means": array(BATCH, "K", "n")},
        relations=(_awf_relations,))
    __post_init__ = validated_post_init


@derived_inputs()
def awf(X: ArrayLike, variance: Estimator = "lecture", guard: Guard = "floor") -> AWFResult:
    r"""Adaptive weighted fusion (sec. 2.1 and steps 1-6 of sec. 2.3), for every k.

    Steps: running moments, variance estimates (:func:`running_variances`), time averages
    (:func:`running_means`), weights :math:`W_p^* \propto 1/\hat\sigma_p^2`, estimate
    :math:`\hat X(k) = \sum_p W_p^*(k)\,\bar X_p(k)`.

    Parameters
    ----------
    X : array_like, shape (..., K, n)
        Readings of a constant quantity, ``n >= 2``.
    variance : {"lecture", "centred"}
        Variance estimator.
    guard : {"floor", "abs", "equal", "none"}
        Treatment of non-positive variance estimates (:func:`inverse_variance_weights`). The default
        ``"floor"`` is kept so that the book's numbers reproduce, not recommended: with the lecture's
        uncentred estimator at a high level it biases the fused value and hands the weight to the sensors whose
        running mean happens to be low (chapter 2, E2.1). Pass the guard explicitly; ``"none"`` is the lecture
        as written (infinite MSE), and the centred estimator rarely needs a guard.

    Returns
    -------
    AWFResult
        After each sample: the fused ``value``, the ``weights``, the raw ``variances`` estimates and the running
        ``means``.
    """
    X = read_once(X, "X")  # converted once, then checked and used (fuzz 29a C5)
    variance = one_of(variance, ("lecture", "centred"), "variance")
    return _awf_result(running_variances(X, variance), running_means(X), guard)


def _awf_result(var: FloatArray, means: FloatArray, guard: Guard) -> AWFResult:
    """:func:`awf` from its variance estimates and time averages (already computed, e.g. by :func:`_running_estimates`)."""
    w = inverse_variance_weights(var, guard=guard)
    return trusted(AWFResult, value=np.einsum("...i,...i->...", w, means), weights=w, variances=var, means=means)


def learned_variances(Y: ArrayLike) -> FloatArray:
    r"""Variance-learning recursion of sec. 2.2, for every epoch m = 1..M.

    .. math::

        \bar y_m = \frac1n\sum_i y_{mi}, \qquad R_{mi} = (y_{mi} - \bar y_m)^2, \qquad
        \hat R_{mi} = \frac{m-1}{m}\hat R_{(m-1)i} + \frac1m R_{mi}, \quad \hat R_{0i} = 0.

    (The square in :math:`R_{mi}` is restored; the print is garbled.) Its expectation is
    :math:`(1-\frac2n)R_i + \frac1{n^2}\sum_j R_j`, not :math:`R_i`; for ``n = 2`` the two
    sensors' :math:`R_{mi}` are identical, so the learned weights are always 1/2.

    Parameters
    ----------
    Y : array_like, shape (..., M, n)
        Readings, ``n >= 2`` sensors.

    Returns
    -------
    ndarray, shape (..., M, n)
        Entry [..., m − 1, i]: sensor i's mean squared deviation from the epoch's average over epochs 1..m.
    """
    A = _as_sample_array(Y, name="Y")
    dev2 = (A - A.mean(axis=-1, keepdims=True)) ** 2
    m = np.arange(1, A.shape[-2] + 1, dtype=float)[:, None]
    return np.cumsum(dev2, axis=-2) / m


def corrected_variances(learned: ArrayLike) -> FloatArray:
    r"""Bias-corrected learned variances (our option, not the lecture's), ``n >= 3``.

    Inverting :math:`E[\hat R_i] = (1-\frac2n)R_i + \frac{1}{n^2}\sum_j R_j`, with
    :math:`\sum_j R_j` estimated by :math:`S = \frac{n}{n-1}\sum_j \hat R_j`:

    .. math:: \tilde R_i = \frac{\hat R_i - S/n^2}{1 - 2/n}.

    Parameters
    ----------
    learned : array_like, shape (..., n)
        Output of :func:`learned_variances`.

    Returns
    -------
    ndarray, shape (..., n)
        Unbiased estimates (can be negative for small m).

    Raises
    ------
    ValueError
        If ``n < 3``: with two sensors the individual variances are not identifiable from the
        deviations to the mean.
    """
    R = as_array(learned, "learned")
    if R.ndim < 1:
        raise ValueError("learned must have a sensor axis")
    n = R.shape[-1]
    if n < 3:
        raise ValueError(f"learned: the correction needs n >= 3 sensors (last axis), got n = {n}")
    S = n / (n - 1) * R.sum(axis=-1, keepdims=True)
    return (R - S / n**2) / (1.0 - 2.0 / n)


@dataclass(frozen=True)
@frozen_arrays
class LSLearning:
    """Values fused with the least-squares learned weights, and those weights.

    Arrays are read-only.

    Attributes
    ----------
    values : ndarray, shape (..., M)
    weights : ndarray, shape (..., M, n)
    """

    values: FloatArray
    weights: FloatArray


@derived_inputs()
def ls_learning(Y: ArrayLike, corrected: bool = False) -> LSLearning:
    r"""Least-squares weighted fusion with variance learning (sec. 2.2), epoch by epoch.

    At epoch m the weights :math:`w_i \propto 1/\hat R_{mi}` (learned from epochs 1..m) are
    applied to the current readings: :math:`\hat x_m = \sum_i w_i y_{mi} / \sum_i w_i`.

    Parameters
    ----------
    Y : array_like, shape (..., M, n)
    corrected : bool
        Use :func:`corrected_variances` (needs n >= 3).

    Returns
    -------
    LSLearning
        ``values`` and ``weights``.
    """
    flag(corrected, "corrected")
    A = _as_sample_array(Y, name="Y")
    R = learned_variances(A)
    if corrected:
        R = corrected_variances(R)
    w = inverse_variance_weights(R)
    return LSLearning(values=np.einsum("...i,...i->...", w, A), weights=w)


@finite_result("H, W and Y")
def wls(H: ArrayLike, W: ArrayLike, Y: ArrayLike) -> FloatArray:
    r"""Weighted least squares :math:`\hat x = (H^\top W H)^{-1} H^\top W Y` (sec. 2.2).

    Parameters
    ----------
    H : array_like, shape (n, d)
        Known observation matrix (``(n,)`` is read as one column, the lecture's vector H).
    W : array_like, shape (n,) or (n, n)
        Weights (a vector is a diagonal matrix); must give a positive definite
        :math:`H^\top W H`.
    Y : array_like, shape (n,)

    Returns
    -------
    ndarray, shape (d,)
        The estimate x̂ of the d unknowns.

    Raises
    ------
    ValueError
        Shapes that differ, ``W`` negative, not symmetric or not positive semidefinite; ``H`` wider than tall (d >
        n: :math:`H^\top W H` is then singular), at once; an estimate that overflows (``H``, ``W`` and ``Y`` each in
        range, :math:`H^\top W H` not); ``H`` and ``W`` beyond the work budget (``n**2 (n + d) + n d**2 + d**3`` units
        of 0.015: n of about 4,050 for d = 1, 2,550 for d = n).
    """
    H = as_array(H, "H", ndim=(1, 2))
    if H.ndim == 1:
        H = H[:, None]
    Y = as_array(Y, "Y", ndim=1)
    W = as_array(W, "W", ndim=(1, 2))
    (n, d), (m,) = H.shape, Y.shape
    if m != n or d > n:   # d > n: refused before the d x d H^T W H is built (fuzz 60b C3: d = 12,000 ran 9.5 CPU-s)
        raise ValueError(f"H must be (n, d) and Y (n,), got {H.shape} and {Y.shape}" if m != n else f"H must have at "
                         f"least as many rows as columns, got {H.shape}: H^T W H (d x d, rank <= n < d) is singular")
    # rule 17 (fix 65a, after fuzz 57b D2: n = 5,792, the input budget, ran 20 CPU-s with H one column and 48 with H
    # square, unchecked): W's eigenvalues, H W, H^T W H, its factors: n**2 (n + d) + n d**2 + d**3 work (fix 68a:
    # 0.048-0.053 ns a unit, min of 3, n = 1,500, d = 1 to n; process_time, OPENBLAS_NUM_THREADS=1, shared; d x d <= W)
    work((n * n * (n + d) + n * d * d + d**3,), "H and W", weight=1.5 * DENSE_CUBE)
    if W.ndim == 1:
        if np.any(W < 0):
            raise ValueError("W must be non-negative")
        W = np.diag(W)
    if W.shape != (H.shape[0], H.shape[0]):
        raise ValueError(f"W must be ({H.shape[0]},) or square of that size, got {W.shape}")
    scale = max(float(np.abs(W).max()), np.finfo(float).tiny)
    if np.abs(W - W.T).max() > 1e-9 * scale:
        raise ValueError("W must be symmetric")
    if np.linalg.eigvalsh(0.5 * (W + W.T)).min() < -1e-9 * scale:
        raise ValueError("W must be positive semidefinite")
    A = H.T @ W @ H
    try:
        np.linalg.cholesky(0.5 * (A + A.T))
    except np.linalg.LinAlgError:
        raise ValueError("H^T W H is not positive definite (H rank-deficient or W not positive)") from None
    return np.linalg.solve(A, H.T @ W @ Y)


def running_average(Z: ArrayLike, memory: Memory = "growing", forgetting: float = 0.98, window: int = 100,
                    axis: int = -2) -> FloatArray:
    r"""Running average of ``Z`` along ``axis`` with a growing, forgetting or sliding memory.

    .. math::

        \bar Z(k) = \frac{\sum_{i\le k} a_{k,i} Z(i)}{\sum_{i\le k} a_{k,i}}, \qquad
        a_{k,i} = \begin{cases} 1 & \text{growing (the lecture's } \tfrac{k-1}{k}\bar Z(k-1) + \tfrac1k Z(k))\\
        \lambda^{k-i} & \text{forgetting}\\ [k - i < w] & \text{window.}\end{cases}

    Parameters
    ----------
    Z : array_like
        Values, time along ``axis``.
    memory : {"growing", "forgetting", "window"}
        See :data:`MEMORIES`.
    forgetting : float
        Forgetting factor :math:`\lambda \in (0, 1)` (``memory="forgetting"``); the effective
        memory is about :math:`1/(1-\lambda)` samples.
    window : int
        Window length :math:`w \ge 1` (``memory="window"``); shorter at the start. A window's sum is the
        difference of two cumulative sums where the a-posteriori bound of its round-off (``eps`` x its terms x
        its largest \|cumulative sum\|) is within :math:`10^{-8}` of its largest \|value\|; otherwise (a large
        value that has left the window, whose round-off the cumulative sums keep) it is summed from its own samples,
        with the round-off of a direct sum (about ``eps`` x :math:`w` x its \|values\|).
    axis : int
        Time axis.

    Returns
    -------
    ndarray
        Same shape as ``Z``.

    Raises
    ------
    ValueError
        Unknown ``memory``, ``forgetting`` outside (0, 1), ``window`` < 1, non-finite ``Z``.

    References
    ----------
    Ljung, L. & Söderström, T. (1983). *Theory and Practice of Recursive Identification*. MIT Press
    (forgetting factors).
    """
    memory = one_of(memory, MEMORIES, "memory")
    lam = scalar(forgetting, "forgetting")
    if not 0.0 < lam < 1.0:
        raise ValueError(f"forgetting must be in (0, 1), got {shown(forgetting)}")
    window = count(window, "window")
    A = as_array(Z, "Z")
    axis = integer(axis, "axis")
    if not -A.ndim <= axis < A.ndim:
        raise ValueError(f"axis must be an integer in [-{A.ndim}, {A.ndim}), got {shown(axis)}")
    A = np.moveaxis(A, axis, 0)
    K = A.shape[0]
    shape = (K,) + (1,) * (A.ndim - 1)
    if memory == "growing":
        out = np.cumsum(A, axis=0) / np.arange(1, K + 1, dtype=float).reshape(shape)
    elif memory == "window":
        c = window_sums(A, window)
        out = c / np.minimum(np.arange(1, K + 1), window).astype(float).reshape(shape)
    else:
        from scipy.signal import lfilter

        num = lfilter([1.0], [1.0, -lam], A, axis=0)
        den = lfilter([1.0], [1.0, -lam], np.ones(K))
        out = num / den.reshape(shape)
    return np.moveaxis(out, 0, axis)


@derived_inputs()
def tracking_variances(X: ArrayLike, estimator: Literal["lecture", "centred", "sample"] = "centred",
                       memory: Memory = "growing", forgetting: float = 0.98, window: int = 100) -> FloatArray:
    r"""Variance estimates of every sensor at every k, with a chosen memory (sec. 2.1, extended).

    The moments :math:`R_{pq}(k)` and means :math:`\bar X_p(k)` of :func:`running_variances` are
    averaged with :func:`running_average` instead of the lecture's growing 1/k recursion. The
    estimators: ``"lecture"`` :math:`R_{pp} - \bar R_p`; ``"centred"`` the same with
    :math:`C_{pq} = R_{pq} - \bar X_p\bar X_q`; ``"sample"`` each sensor's own sample variance
    :math:`C_{pp}`, which needs no other sensor but contains the variance of the measured quantity
    itself when that varies in time (the cross-moment estimators cancel it). With
    ``memory="growing"`` the first two equal :func:`running_variances`. The ``"centred"`` and ``"sample"``
    estimates are computed, as there, from the readings minus each sensor's median reading (shift invariant in
    floating point); the ``"lecture"`` one from the raw moments, by its definition. A sliding window's
    averages are those of :func:`running_average`: a reading that has left the window no longer counts there, to
    the round-off stated there.

    Parameters
    ----------
    X : array_like, shape (..., K, n)
        Readings, ``n >= 2`` sensors.
    estimator : {"lecture", "centred", "sample"}
    memory : {"growing", "forgetting", "window"}
    forgetting : float
        Forgetting factor in (0, 1) for ``memory="forgetting"``.
    window : int
        Window length for ``memory="window"``.

    Returns
    -------
    ndarray, shape (..., K, n)
        Estimates in unit²; the cross-moment ones can be negative (never clipped here).

    References
    ----------
    Grubbs, F. E. (1948). On estimating precision of measuring instruments and product
    variability. *Journal of the American Statistical Association*, 43(242), 243-264.
    """
    estimator = one_of(estimator, ("lecture", "centred", "sample"), "estimator")
    A = _as_sample_array(X)
    running_average(np.zeros((1, 1)), memory, forgetting, window, axis=0)  # validates the memory parameters
    return _moment_estimates(A, estimator, lambda Z: running_average(Z, memory, forgetting, window, axis=-2))


def _tracking_estimates(X: ArrayLike, estimators: tuple[str, ...], memory: Memory = "growing", forgetting: float = 0.98,
                        window: int = 100) -> tuple[FloatArray, ...]:
    """:func:`tracking_variances` of each of ``estimators`` at one memory, from one averaged stack of moments (the
    arrays that function returns, bit for bit: each estimator is arithmetic on the same averages;
    ``tests/test_weighting.py``)."""
    A = _as_sample_array(X)
    running_average(np.zeros((1, 1)), memory, forgetting, window, axis=0)  # validates the memory parameters
    kinds = tuple(dict.fromkeys("lecture" if e == "lecture" else "centred" for e in estimators))  # the stacks needed
    avg = running_average(np.concatenate([_moment_stack(A, kind) for kind in kinds], axis=-1), memory, forgetting,
                          window, axis=-2)
    n3 = 3 * A.shape[-1]
    parts = {kind: avg[..., i * n3:(i + 1) * n3] for i, kind in enumerate(kinds)}
    return tuple(_estimates_from(parts["lecture" if e == "lecture" else "centred"], e) for e in estimators)


def fuse_current(X: ArrayLike, variances: ArrayLike, guard: Guard = "abs") -> FloatArray:
    r"""Fuse the current readings with inverse-variance weights: :math:`\hat X(k) = \sum_p W_p(k) X_p(k)`.

    The instantaneous form of sec. 2.1 (the lecture fuses the time averages only for a constant
    quantity); the weights come from variance estimates available at time k, so the fusion is
    causal.

    Parameters
    ----------
    X : array_like, shape (..., K, n)
        Readings.
    variances : array_like, shape (..., K, n)
        Variance estimates at each k (e.g. :func:`tracking_variances`); broadcast against ``X``.
    guard : {"floor", "abs", "equal", "none"}
        Treatment of non-positive estimates (:data:`GUARDS`).

    Returns
    -------
    ndarray, shape (..., K)
        Fused values.

    Raises
    ------
    ValueError
        Non-finite input, or shapes that do not broadcast.

    References
    ----------
    Zhai, Y. & Dai, Y. (1998). Adaptive weighted fusion of multi-sensor data (in Chinese), as
    paraphrased by the lecture notes, sec. 2.1.
    """
    A = _as_sample_array(X)
    V = as_array(variances, "variances", ndim=tuple(range(1, 33)))  # at least one (sensor) axis
    broadcast((("X", A.shape), ("variances", V.shape)), arrays=2, weight=1)  # fuzz 57b C5: 1.5 arrays, 8.5 ns each
    w = inverse_variance_weights(V, guard=guard)
    return np.sum(w * A, axis=-1)


@derived_inputs()
def difference_variances(X: ArrayLike, memory: Memory = "growing", forgetting: float = 0.98,
                         window: int = 100) -> FloatArray:
    r"""Each sensor's variance from its first differences: :math:`\hat\sigma_p^2(k) = \overline{\Delta X_p^2}/2`.

    .. math::

        \hat\sigma_p^2(k) = \frac12\,\mathrm{avg}_{2\le i\le k}\big(X_p(i) - X_p(i-1)\big)^2,

    averaged with :func:`running_average` (growing, forgetting or window memory). With
    :math:`X_p(i) = X(i) + V_p(i)` and white noise,
    :math:`E[\Delta X_p^2/2] = \sigma_p^2 + \Delta X^2/2`: the estimate needs no other sensor and
    is unbiased for a constant X, and nearly so for one that drifts slowly compared with the
    noise (the mean square successive difference of von Neumann 1941). A signal that changes
    appreciably from one sample to the next inflates every sensor's estimate by the same
    :math:`\overline{\Delta X^2}/2`, which flattens the weights.

    Parameters
    ----------
    X : array_like, shape (..., K, n)
        Readings.
    memory : {"growing", "forgetting", "window"}
        See :data:`MEMORIES`.
    forgetting : float
        Forgetting factor in (0, 1) for ``memory="forgetting"``.
    window : int
        Window length (in differences) for ``memory="window"``.

    Returns
    -------
    ndarray, shape (..., K, n)
        Non-negative estimates (unit²); at k = 1 there is no difference yet and the estimate is 0
        (which every guard but ``"none"`` of :func:`inverse_variance_weights` turns into equal weights).

    Raises
    ------
    ValueError
        Non-finite or wrongly shaped ``X``, or an invalid memory parameter.

    References
    ----------
    von Neumann, J. (1941). Distribution of the ratio of the mean square successive difference to
    the variance. *The Annals of Mathematical Statistics*, 12(4), 367-395.
    """
    A = _as_sample_array(X, min_sensors=1)
    memory = one_of(memory, MEMORIES, "memory")
    out = np.zeros_like(A)
    if A.shape[-2] > 1:
        half = 0.5 * np.diff(A, axis=-2) ** 2
        out[..., 1:, :] = running_average(half, memory, forgetting, window, axis=-2)
    else:  # still validate the memory parameters
        running_average(np.zeros((1, 1)), memory, forgetting, window, axis=0)
    return out


#: How :func:`cumulative_fusion` weighs the instants against each other: ``"equal"`` every
#: instant's fused reading counts once (robust to noisy estimates, exact when the total precision
#: :math:`\sum_p\sigma_p^{-2}` of an instant does not change), ``"precision"`` each instant by its
#: estimated total precision :math:`\sum_p\tilde\sigma_p^{-2}(i)` (with the true variances, the
#: minimum-variance estimate; with estimated ones, a near-zero estimate makes one instant dominate).
TIME_WEIGHTS: tuple[str, ...] = ("equal", "precision")


def cumulative_fusion(X: ArrayLike, variances: ArrayLike, guard: Guard = "abs",
                      time_weights: Literal["equal", "precision"] = "equal") -> FloatArray:
    r"""Per-sample inverse-variance fusion of a constant quantity, accumulated over time.

    Each instant i is fused with the weights of the variances available at i,
    :math:`\hat X_i = \sum_p W_p(i)X_p(i)` (:func:`fuse_current`), and the instants are combined:

    .. math::

        \hat X(k) = \frac{\sum_{i\le k}\tau(i)\,\hat X_i}{\sum_{i\le k}\tau(i)}, \qquad
        \tau(i) = 1 \ (\text{"equal"}) \quad\text{or}\quad \tau(i) = \sum_p \tilde\sigma_p^{-2}(i)
        \ (\text{"precision"}),

    with :math:`\tilde\sigma_p^2` the estimates after the guard. With the true variances of every
    sample and ``"precision"`` this is the minimum-variance linear unbiased estimate of a constant
    X from all readings up to k (each reading weighted by its own inverse variance), the per-sample
    BLUE; with estimates from readings up to i only (e.g. :func:`tracking_variances` with
    forgetting) it is causal and uses the same information as the lecture's AWF of running means.

    Parameters
    ----------
    X : array_like, shape (..., K, n)
        Readings of a constant quantity.
    variances : array_like, shape (..., K, n)
        Variance of each reading, or its causal estimate; broadcast against ``X``.
    guard : {"floor", "abs", "equal"}
        Treatment of non-positive estimates (:data:`GUARDS`; ``"none"`` is refused: the
        accumulated weights could then sum to zero; ``"equal"`` only with equal time weights).
    time_weights : {"equal", "precision"}
        See :data:`TIME_WEIGHTS`.

    Returns
    -------
    ndarray, shape (..., K)
        The estimate after each sample.

    Raises
    ------
    ValueError
        Non-finite input, shapes that do not broadcast, ``guard="none"``, ``guard="equal"`` with
        ``time_weights="precision"``, or an unknown option.

    References
    ----------
    Aitken, A. C. (1936). On least squares and linear combination of observations.
    *Proceedings of the Royal Society of Edinburgh*, 55, 42-48.
    """
    guard = one_of(guard, ("floor", "abs", "equal"), "guard")
    time_weights = one_of(time_weights, TIME_WEIGHTS, "time_weights")
    if time_weights == "precision" and guard == "equal":
        raise ValueError("guard 'equal' has no precision to weigh the instants by: use time_weights='equal'")
    A = _as_sample_array(X)
    V = as_array(variances, "variances")
    if not np.all(np.isfinite(V)):
        raise ValueError("variances must be finite")
    # rules 9 and 17 on the broadcast (fuzz 57b C5: the refusal named inverse_variance_weights' "estimates"):
    # 4.6 arrays of it at tracemalloc's peak, 38 ns an element
    shape = broadcast((("X", A.shape), ("variances", V.shape)), arrays=5, weight=4)
    V = np.broadcast_to(V, shape)
    w = _guarded_weights(V, guard, VARIANCE_FLOOR)   # inverse_variance_weights' kernel: V is read and checked above
    inst = np.sum(w * A, axis=-1)
    if time_weights == "equal":
        tau = np.ones(inst.shape)
    else:  # the guarded estimates of inverse_variance_weights, before normalisation
        tau = (1.0 / _guarded(V, guard, VARIANCE_FLOOR)).sum(axis=-1)
    return np.cumsum(tau * inst, axis=-1) / np.cumsum(tau, axis=-1)
