r"""Consistency check followed by adaptive weighted fusion (lecture notes, §2.3).

The lecture keeps the readings :math:`X_1..X_m` of one instant if "adjacent" readings differ
by at most a threshold :math:`\varepsilon` set from the sensor accuracy,
:math:`|X_{j+1} - X_j| \le \varepsilon`, then runs the adaptive weighted fusion of sec. 2.1
(steps 1-6). It defines neither "adjacent" nor what happens to a reading that fails. Our
reading (documented choices):

* adjacent means adjacent **in sorted order**; the sorted readings are split into clusters at
  every gap larger than :math:`\varepsilon` and the largest cluster is kept (ties: the cluster
  that holds the lower median reading);
* a rejected reading does not update its sensor's statistics (moments and time average);
* the weights are renormalised over the sensors kept at the current instant.

References
----------
* An explanation of multi-sensor data fusion algorithms (多传感器数据融合算法讲解).
  Lecture notes, web copy (in Chinese; author and date not stated).
* Grubbs, F. E. (1948). On estimating precision of measuring instruments and product
  variability. *Journal of the American Statistical Association*, 43(242), 243-264.
"""

from __future__ import annotations

from dataclasses import dataclass

from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from fusion._validation import LOOP_STEP, allocation, integer, loop_work, work
from fusion._results import ResultSpec, nested, trusted, validated_post_init
from fusion._validation import derived_inputs
from fusion._validation import _numeric, _real_number, FloatArray, as_array, check_magnitude, one_of, scalar
from fusion.readings._moments import _reference
from fusion.readings.weighting import AWFResult, _as_sample_array, inverse_variance_weights
from fusion._shown import shown

__all__ = ["ConsistentAWF", "consistency_mask", "consistency_awf", "rejection_probability"]


#: Arrays of the pairs' shape ``(..., K, n, n)`` that :func:`consistency_awf` holds at once: ``tracemalloc``'s peak
#: over one such array's bytes measured 5.1-6.2 (``"lecture"``) and 7.0-7.6 (``"centred"``) on (2000, 100, 5),
#: (20, 100, 50) and (2, 50, 400) readings (fuzz 41b C3: the memory rule counted one, so (40000, 100, 5) readings
#: raised a raw MemoryError after 12 CPU-s).
_PAIR_ARRAYS = 8
#: Units of work (``fusion._limits.work``, about 10 ns) of one element of the pairs' shape in :func:`consistency_awf`:
#: 2.2-4.1 (``"lecture"``) and 3.3-5.5 (``"centred"``) units measured on the same readings (CPU time, minimum of 2,
#: OPENBLAS_NUM_THREADS=1, shared machine), rounded up.
_PAIR_WORK = 6


def _pair_budget(shape: tuple[int, ...], names: str, fusions: int = 1, fusion_names: str | None = None) -> None:
    """Refuse, before any work, ``fusions`` calls of :func:`consistency_awf` on readings of ``shape`` (..., K, n) whose
    ``(..., K, n, n)`` pair arrays (``_PAIR_ARRAYS`` of them at once) exceed the memory budget or whose work
    (``_PAIR_WORK`` units a pair element, each call) exceeds the work budget: ValueError naming ``names`` (the work
    refusal naming ``fusion_names`` when given: the arguments that set ``fusions`` too). The one rule of the function
    and of a caller that runs it (``check_grid`` of chapter 02, the readings benchmark's keys, at their entry)."""
    pairs = tuple(int(d) for d in shape) + (int(shape[-1]),)
    allocation(pairs, names, arrays=_PAIR_ARRAYS)
    work((int(fusions),) + pairs, fusion_names or names, weight=_PAIR_WORK)


def _label_counts(labels: NDArray[np.int_]) -> NDArray[np.int_]:
    """The size of each cluster ``c = 0..n-1`` in each row of ``labels`` (..., n) of cluster numbers in [0, n).

    One ``bincount`` of every row's labels offset by n times the row's index: linear in the readings (a comparison
    ``labels[..., :, None] == arange(n)`` held n x n booleans a row, a ``MemoryError`` for a long ``x``).
    """
    n = labels.shape[-1]
    offset = labels.reshape(-1, n) + n * np.arange(labels.size // n)[:, None]
    return np.bincount(offset.ravel(), minlength=labels.size).reshape(labels.shape)


def consistency_mask(x: ArrayLike, eps: float, adjacent: Literal["sorted", "index"] = "sorted") -> NDArray[np.bool_]:
    r"""Readings that pass the adjacent-difference check, row by row.

    Parameters
    ----------
    x : array_like, shape (..., n)
        Readings of one instant in each row.
    eps : float
        Threshold :math:`\varepsilon` in the readings' unit (``np.inf`` keeps everything).
    adjacent : {"sorted", "index"}
        What "adjacent" means (the lecture does not say): neighbours in sorted order (the default:
        clusters of close readings, independent of how the sensors are numbered), or neighbours in
        the sensors' index order :math:`|X_{j+1} - X_j| \le \varepsilon` as written (runs of consecutive
        sensors; the result then depends on the numbering).

    Returns
    -------
    ndarray of bool, shape (..., n)
        True for the readings of the kept (largest) cluster; with ``"index"`` the largest run of
        consecutive sensors (ties: the first).
    """
    adjacent = one_of(adjacent, ("sorted", "index"), "adjacent")
    s = as_array(x, "x", nonempty=False)
    if s.ndim < 1 or s.shape[-1] == 0:
        raise ValueError(f"x must have a non-empty last axis of readings, got shape {s.shape}")
    e = _real_number(eps, "eps")  # TypeError for a string, a bool, a complex number, None, ...
    if np.isnan(e) or e < 0:
        raise ValueError(f"eps must be non-negative (inf keeps everything), got {shown(eps)}")
    if np.isfinite(e):
        e = scalar(e, "eps", lo=0.0)  # the shared magnitude rule: no subnormal or huge threshold
    n = s.shape[-1]
    if s.size == 0:  # an empty batch (shape (0, n)): nothing to mark, and nothing sized by n to allocate
        return np.zeros(s.shape, dtype=bool)
    if adjacent == "index":
        labels = np.concatenate([np.zeros(s.shape[:-1] + (1,), dtype=int),
                                 np.cumsum(np.abs(np.diff(s, axis=-1)) > e, axis=-1)], axis=-1)
        return labels == np.argmax(_label_counts(labels), axis=-1)[..., None]
    order = np.argsort(s, axis=-1, kind="stable")
    srt = np.take_along_axis(s, order, axis=-1)
    gaps = np.diff(srt, axis=-1) > e
    labels = np.concatenate([np.zeros(s.shape[:-1] + (1,), dtype=int), np.cumsum(gaps, axis=-1)], axis=-1)
    counts = _label_counts(labels)  # (..., n) size of cluster c
    best = counts.max(axis=-1, keepdims=True)
    candidates = counts == best
    median_label = labels[..., (n - 1) // 2]
    med_ok = np.take_along_axis(candidates, median_label[..., None], axis=-1)[..., 0]
    first = np.argmax(candidates, axis=-1)
    chosen = np.where(med_ok, median_label, first)
    keep_sorted = labels == chosen[..., None]
    mask = np.empty_like(keep_sorted)
    np.put_along_axis(mask, order, keep_sorted, axis=-1)
    return mask


def _checked_mask(self: ConsistentAWF) -> None:
    """``__post_init__`` of :class:`ConsistentAWF`: the nested fusion by the spec, then the mask (boolean, the
    fusion's shape, no weight on a rejected reading), stored as a read-only copy."""
    validated_post_init(self)
    mask, w = self.mask, self.awf.weights
    if not isinstance(mask, np.ndarray) or mask.dtype != np.bool_:
        raise TypeError(f"ConsistentAWF.mask must be a boolean array, got {getattr(mask, 'dtype', type(mask).__name__)}")
    if mask.shape != w.shape:
        raise ValueError(f"ConsistentAWF.mask must have the shape of ConsistentAWF.awf.weights {w.shape}, got {mask.shape}")
    if (w[~mask] != 0.0).any():
        raise ValueError("ConsistentAWF.mask: a rejected reading has a non-zero weight in ConsistentAWF.awf")


@dataclass(frozen=True)
class ConsistentAWF:
    """Adaptive weighted fusion after the consistency check, and the readings it kept.

    Validated where it is built (``dataclasses.replace`` included): ``awf`` an :class:`AWFResult` (itself
    validated), ``mask`` a boolean array of its shape with no weight on a rejected reading. Arrays are read-only.

    Attributes
    ----------
    awf : AWFResult
        Weights are zero for the sensors rejected at that instant.
    mask : ndarray of bool, shape (..., K, n)
        Kept readings.
    """

    awf: AWFResult
    mask: NDArray[np.bool_]

    __result_spec__ = ResultSpec({"awf": nested(AWFResult)})
    __post_init__ = _checked_mask


@derived_inputs()
def consistency_awf(
    X: ArrayLike, eps: float, variance: Literal["lecture", "centred"] = "lecture",
    guard: Literal["floor", "abs", "equal", "none"] = "floor", adjacent: Literal["sorted", "index"] = "sorted",
) -> ConsistentAWF:
    r"""Consistency check at every instant, then adaptive weighted fusion (sec. 2.3).

    With the kept-reading indicator :math:`m_p(i)`, the moments use only instants where the
    readings involved were kept:

    .. math::

        R_{pq}(k) = \frac{\sum_{i\le k} m_p(i)m_q(i)X_p(i)X_q(i)}{\sum_{i\le k} m_p(i)m_q(i)},
        \qquad \bar X_p(k) = \frac{\sum_{i\le k} m_p(i)X_p(i)}{\sum_{i\le k} m_p(i)},

    and :math:`\hat\sigma_p^2` as in :func:`fusion.readings.weighting.running_variances` (the average over
    :math:`q \ne p` runs over the partners with at least one shared kept instant; the
    ``"centred"`` form subtracts the pairwise means, from the readings minus each sensor's median kept reading:
    shift invariant in floating point too, and independent of rejected readings). The estimate at k combines the sensors
    kept at k: :math:`\hat X(k) = \sum_{p\,\text{kept}} W_p\bar X_p(k)`, weights renormalised.
    A sensor without any partner yet gets the variance estimate 0 (hence, after the floor, a
    large weight); so does, with the centred estimator, a sensor whose first kept reading shares only the current
    instant with its partners (a centred moment of one instant is 0): a sensor re-admitted late can take nearly all
    the weight (not changed here, so that the book's numbers reproduce). With ``eps = inf`` the result equals
    :func:`fusion.readings.weighting.awf`. The default ``guard="floor"`` is kept for the same reason and is not a
    recommendation (see :func:`fusion.readings.weighting.awf`).

    Parameters
    ----------
    X : array_like, shape (..., K, n)
    eps : float
        Consistency threshold (readings' unit).
    variance : {"lecture", "centred"}
    guard : {"floor", "abs", "equal", "none"}
        Treatment of non-positive variance estimates before inverting them
        (:data:`fusion.readings.weighting.GUARDS`; the lecture says nothing). With ``"none"`` the
        weights of the kept sensors can sum to (nearly) zero, and the estimate is then unbounded.
    adjacent : {"sorted", "index"}
        Meaning of "adjacent" in the check (:func:`consistency_mask`).

    Returns
    -------
    ConsistentAWF
        The fusion ``awf`` and the ``mask`` of kept readings.

    Raises
    ------
    ValueError
        Before any work, naming ``X``: its pairs of sensors at every instant, ``(..., K, n, n)`` arrays (eight held
        at once), beyond the memory budget (``fusion._counts.MAX_ELEMENTS``, 2 GiB) or their work (6 units an
        element, about 60 ns) beyond the work budget (``fusion._limits.MAX_WORK``).
    """
    variance = one_of(variance, ("lecture", "centred"), "variance")
    guard = one_of(guard, ("floor", "abs", "equal", "none"), "guard")
    A = _as_sample_array(X)
    _pair_budget(A.shape, "X")  # rules 9 and 17: the moments of every pair of sensors, (..., k, n, n), fuzz 41b C3
    mask = consistency_mask(A, eps, adjacent)
    n = A.shape[-1]
    mf = mask.astype(float)
    pair = mf[..., :, None] * mf[..., None, :]
    N = np.cumsum(pair, axis=-3)
    safe = np.where(N > 0, N, 1.0)
    # centred: the moments of the kept readings minus each sensor's median kept reading (the same covariances,
    # computed at the scale of the spread, not of the offset, nor of a rejected reading: ``_moment_stack`` of
    # ``fusion.readings._moments``); lecture: raw moments
    Y = np.where(mask, A - _reference(A, mask), 0.0) if variance == "centred" else A
    R = np.cumsum(pair * Y[..., :, None] * Y[..., None, :], axis=-3) / safe
    if variance == "centred":
        Sp = np.cumsum(pair * Y[..., :, None], axis=-3) / safe  # mean of X_p over shared instants (minus c_p)
        R = R - Sp * np.swapaxes(Sp, -1, -2)
    valid = (N > 0) & ~np.eye(n, dtype=bool)
    nvalid = valid.sum(axis=-1)
    diag = np.diagonal(R, axis1=-2, axis2=-1)
    off = np.where(valid, R, 0.0).sum(axis=-1) / np.where(nvalid > 0, nvalid, 1)
    var = np.where(nvalid > 0, diag - off, 0.0)
    Np = np.cumsum(mf, axis=-2)
    means = np.cumsum(mf * A, axis=-2) / np.where(Np > 0, Np, 1.0)
    w = inverse_variance_weights(var, guard=guard) * mf
    w = w / w.sum(axis=-1, keepdims=True)
    value = np.einsum("...i,...i->...", w, means)
    return trusted(ConsistentAWF, awf=trusted(AWFResult, value=value, weights=w, variances=var, means=means), mask=mask)


def rejection_probability(snapshots: ArrayLike, sensor: int, biases: ArrayLike, eps: float) -> FloatArray:
    r"""Probability that the check rejects one sensor's reading, against that sensor's bias.

    For each bias :math:`b` the reading of ``sensor`` in every snapshot is shifted by :math:`b`
    and :func:`consistency_mask` is applied; the result is the fraction of snapshots in which
    that reading is rejected (the detection curve of sec. 2.3).

    Parameters
    ----------
    snapshots : array_like, shape (N, n)
        Simultaneous readings without fault (N snapshots, n >= 2 sensors).
    sensor : int
        Index (0-based) of the biased sensor.
    biases : array_like, shape (B,)
        Biases added to that sensor (readings' unit).
    eps : float
        Consistency threshold (readings' unit).

    Returns
    -------
    ndarray, shape (B,)
        Rejection probability for each bias.
    """
    S = _numeric(snapshots, "snapshots")
    if S.ndim != 2 or S.shape[1] < 2 or S.shape[0] == 0:
        raise ValueError(f"snapshots must have shape (N, n) with N >= 1, n >= 2, got {S.shape}")
    check_magnitude(S, "snapshots")
    sensor = integer(sensor, "sensor")
    if not 0 <= sensor < S.shape[1]:
        raise ValueError(f"sensor must be in [0, {S.shape[1]}), got {sensor}")
    b = np.atleast_1d(_numeric(biases, "biases"))
    if b.ndim != 1 or b.size == 0 or not np.all(np.isfinite(b)):
        raise ValueError("biases must be a non-empty 1-D array of finite numbers")
    check_magnitude(b, "biases")
    eps = scalar(eps, "eps", lo=0.0)  # the float read (fuzz 22b, FR)
    # rule 17: one consistency mask per bias (~10 loop steps of numpy calls over N x n x n)
    loop_work((b.size,), S.size * S.shape[1], "biases and snapshots", step=10 * LOOP_STEP)
    shift = np.zeros(S.shape[1])
    out = np.empty(b.size)
    for i, bias in enumerate(b):
        shift[sensor] = bias
        out[i] = 1.0 - consistency_mask(S + shift, eps)[:, sensor].mean()
    return out
