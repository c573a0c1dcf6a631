"""The moment stacks of the cross-moment variance estimators (``fusion.readings.weighting``) and their reference.

Private: the running, tracking and final estimates of :mod:`fusion.readings.weighting` and the centred moments of
:func:`fusion.readings.consistency.consistency_awf` share them.
"""

from __future__ import annotations

import numpy as np

from fusion._validation import FloatArray


def _moment_stack(A: FloatArray, estimator: str) -> FloatArray:
    r"""The stack of :math:`Y_p^2`, :math:`Y_pS`, :math:`Y_p` (:math:`S = \sum_q Y_q`) averaged for ``estimator``.

    :math:`Y = X` for the ``"lecture"`` estimator (raw moments by its definition). For the ``"centred"`` and
    ``"sample"`` estimators :math:`Y_p(k) = X_p(k) - c_p`, the readings minus each sensor's median reading
    (``_reference``): the covariances are the same mathematically, and the differences of averages
    :math:`\overline{Y_pY_q} - \bar Y_p\bar Y_q` cancel only at the scale of the readings' spread, not of their
    offset (from :math:`X` itself a common offset of :math:`10^8` on a spread of 1 gave negative sample variances).
    The estimate at k depends mathematically on readings up to k only; the reference moves only its round-off.
    """
    if estimator != "lecture":
        A = A - _reference(A)
    S = A.sum(axis=-1, keepdims=True)
    return np.concatenate([A * A, A * S, A], axis=-1)


def _reference(A: FloatArray, kept: np.ndarray | None = None) -> FloatArray:
    """Each sensor's (lower) median reading, or median kept reading, shape (..., 1, n); 0 where none is kept.

    The shift-invariant estimators take their moments relative to it: a reading of the data, robust to a gross
    fault (a first reading as reference made a spike there the offset of every later reading, fuzz 24e F4-F5).
    """
    kept = np.ones(A.shape, dtype=bool) if kept is None else kept
    c = kept.sum(axis=-2, keepdims=True)
    ref = np.take_along_axis(np.sort(np.where(kept, A, np.inf), axis=-2), np.maximum(c - 1, 0) // 2, axis=-2)
    return np.where(c > 0, ref, 0.0)


def _estimates_from(avg: FloatArray, estimator: str) -> FloatArray:
    """The estimates of ``fusion.readings.weighting._moment_estimates`` from the averaged stack of :func:`_moment_stack` for ``estimator``."""
    n = avg.shape[-1] // 3
    diag, rowsum, m = avg[..., :n], avg[..., n:2 * n], avg[..., 2 * n:]
    if estimator != "lecture":
        diag = diag - m * m
        rowsum = rowsum - m * m.sum(axis=-1, keepdims=True)
    if estimator == "sample":
        return diag
    return diag - (rowsum - diag) / (n - 1)
