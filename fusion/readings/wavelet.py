r"""Wavelet denoising and fusion-based per-sensor reconstruction (lecture notes, §2.6).

Model: sensor j reads :math:`X_j(n) = g_jS(n) + e_j(n)`, n = 1..I (the lecture writes
:math:`g_j = 1`, which leaves its normalisation step nothing to do). Steps:

1. denoise every sensor by wavelet thresholding (:func:`denoise`, PyWavelets), giving :math:`Y_j`;
2. normalise :math:`\bar Y_j = Y_j / \mathrm{norm}_j` (the lecture: :math:`\max_n Y_j(n)`);
3. inverse-variance weights :math:`W_j \propto \hat\sigma_j^{-2}`, from the variance of the
   normalised residual :math:`(X_j - Y_j)/\mathrm{norm}_j` (our reading of the "MA model");
4. fuse :math:`\hat Y = \sum_j W_j\bar Y_j`;
5. de-normalise :math:`\hat Y_j = \hat Y\,\mathrm{norm}_j`.

Open choices exposed (the lecture fixes none of them): the wavelet family and depth, the
threshold rule (universal or BayesShrink, soft or hard) and the order of the two operations
(``order="fuse-first"`` fuses the normalised raw signals with the same weights and denoises the
fused signal once).

References
----------
* Donoho, D. L., & Johnstone, I. M. (1994). Ideal spatial adaptation by wavelet shrinkage.
  *Biometrika*, 81(3), 425-455.
* Donoho, D. L. (1995). De-noising by soft-thresholding. *IEEE Transactions on Information
  Theory*, 41(3), 613-627.
* Chang, S. G., Yu, B., & Vetterli, M. (2000). Adaptive wavelet thresholding for image
  denoising and compression. *IEEE Transactions on Image Processing*, 9(9), 1532-1546
  (BayesShrink).
* Lee, G. R., Gommers, R., Waselewski, F., Wohlfahrt, K., & O'Leary, A. (2019). PyWavelets: a
  Python package for wavelet analysis. *Journal of Open Source Software*, 4(36), 1237.
* An explanation of multi-sensor data fusion algorithms (多传感器数据融合算法讲解).
  Lecture notes, web copy (in Chinese; author and date not stated).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np
import pywt
from numpy.typing import ArrayLike

from fusion._validation import FloatArray, _numeric, as_array, count, one_of

__all__ = ["denoise", "Reconstruction", "reconstruct"]

Normaliser = Literal["max", "median", "lsq"]
Threshold = Literal["universal", "bayes"]
Order = Literal["denoise-first", "fuse-first"]


def _signals(X: ArrayLike) -> FloatArray:
    A = _numeric(X, "X")
    if A.ndim < 2 or A.shape[-2] < 2 or A.shape[-1] < 8:
        raise ValueError(f"X must be (..., n_sensors >= 2, I >= 8) signals, got shape {A.shape}")
    if not np.all(np.isfinite(A)):
        raise ValueError("X contains NaN or infinite values")
    return A


def denoise(x: ArrayLike, wavelet: str = "db4", level: int = 4, mode: Literal["soft", "hard"] = "soft",
            threshold: Threshold = "universal") -> FloatArray:
    r"""Wavelet-threshold denoising (Donoho & Johnstone 1994) of signals along the last axis.

    Noise level from the finest detail coefficients, :math:`\hat\sigma = \mathrm{median}|d_1|/0.6745`;
    all detail levels thresholded (``mode``), approximation kept; periodisation boundary handling.
    Threshold rules: ``"universal"``, :math:`\lambda = \hat\sigma\sqrt{2\ln I}` at every level
    (VisuShrink); ``"bayes"``, per level :math:`\lambda_j = \hat\sigma^2/\hat\sigma_{x,j}` with
    :math:`\hat\sigma_{x,j} = \sqrt{\max(\overline{d_j^2} - \hat\sigma^2, 0)}` (BayesShrink, Chang et al.
    2000; a level with :math:`\hat\sigma_{x,j} = 0` is set to zero).

    Parameters
    ----------
    x : array_like, shape (..., I)
        Signals, one per row, in any unit (the output has the same unit).
    wavelet : str
        PyWavelets name (default ``"db4"``).
    level : int
        Decomposition depth (default 4).
    mode : {"soft", "hard"}
        Thresholding rule: soft shrinks surviving coefficients by :math:`\lambda`, hard keeps them.
    threshold : {"universal", "bayes"}
        Threshold selection (see above).

    Returns
    -------
    ndarray, shape (..., I)
        The denoised signals.

    References
    ----------
    * Donoho, D. L., & Johnstone, I. M. (1994). Ideal spatial adaptation by wavelet shrinkage.
      *Biometrika*, 81(3), 425-455.
    """
    one_of(mode, ("soft", "hard"), "mode")
    one_of(threshold, ("universal", "bayes"), "threshold")
    a = _numeric(x, "x")
    if a.ndim < 1 or a.shape[-1] < 8 or not np.all(np.isfinite(a)):
        raise ValueError(f"x must be finite with at least 8 samples on its last axis, got shape {a.shape}")
    level = count(level, "level")
    if not isinstance(wavelet, str) or wavelet not in pywt.wavelist(kind="discrete"):
        raise ValueError(f"wavelet must be the name of a discrete wavelet known to PyWavelets, got {wavelet!r}")
    coeffs = pywt.wavedec(a, wavelet, level=int(level), mode="periodization", axis=-1)
    sigma = np.median(np.abs(coeffs[-1]), axis=-1, keepdims=True) / 0.6745
    if threshold == "universal":
        lams = [sigma * np.sqrt(2.0 * np.log(a.shape[-1]))] * (len(coeffs) - 1)
    else:
        lams = []
        for c in coeffs[1:]:
            sx = np.sqrt(np.maximum(np.mean(c**2, axis=-1, keepdims=True) - sigma**2, 0.0))
            big = np.max(np.abs(c), axis=-1, keepdims=True) + 1.0
            lams.append(np.where(sx > 0, sigma**2 / np.where(sx > 0, sx, 1.0), big))
    out = [coeffs[0]] + [pywt.threshold(c, lam, mode=mode) for c, lam in zip(coeffs[1:], lams)]
    rec = pywt.waverec(out, wavelet, mode="periodization", axis=-1)
    return rec[..., : a.shape[-1]]


@dataclass(frozen=True)
class Reconstruction:
    """Result of :func:`reconstruct` (shapes: n sensors, I samples, optional leading batch axes ``...``).

    Attributes
    ----------
    denoised : ndarray, shape (..., n, I)
        Each sensor's own denoised signal.
    norms : ndarray, shape (..., n)
        Normaliser of each sensor.
    weights : ndarray, shape (..., n)
    fused : ndarray, shape (..., I)
        Fused normalised signal (denoised, in either order).
    reconstructed : ndarray, shape (..., n, I)
        De-normalised fused signal of each sensor.
    """

    denoised: FloatArray
    norms: FloatArray
    weights: FloatArray
    fused: FloatArray
    reconstructed: FloatArray


def reconstruct(
    X: ArrayLike,
    wavelet: str = "db4",
    level: int = 4,
    normaliser: Normaliser = "max",
    mode: Literal["soft", "hard"] = "soft",
    threshold: Threshold = "universal",
    order: Order = "denoise-first",
) -> Reconstruction:
    r"""Per-sensor reconstruction by denoising, normalisation and fusion (sec. 2.6).

    Parameters
    ----------
    X : array_like, shape (..., n, I)
        One row per sensor, I samples (the estimation length); leading axes are independent
        batches (e.g. Monte-Carlo runs), processed at once.
    wavelet, level, mode, threshold
        See :func:`denoise`.
    normaliser : {"max", "median", "lsq"}
        Computed from each sensor's denoised signal :math:`Y_j`. ``"max"``: :math:`\max_n Y_j(n)`
        (the lecture); ``"median"``: :math:`\mathrm{median}_n Y_j(n)`; ``"lsq"``: the least-squares
        gain of :math:`Y_j` on the first sensor's denoised signal (relative gains only).
    order : {"denoise-first", "fuse-first"}
        ``"denoise-first"`` (the lecture): fuse the normalised denoised signals,
        :math:`\hat Y = \sum_jW_jY_j/\mathrm{norm}_j`. ``"fuse-first"``: fuse the normalised *raw*
        signals with the same weights and normalisers, :math:`\sum_jW_jX_j/\mathrm{norm}_j`, and
        denoise that single fused signal (its noise is lower, so its threshold is lower too).

    Returns
    -------
    Reconstruction

    Raises
    ------
    ValueError
        Bad shapes, non-finite input, an unknown option, or a normaliser that is not positive
        (e.g. a signal whose maximum is <= 0).
    """
    one_of(normaliser, ("max", "median", "lsq"), "normaliser")
    one_of(order, ("denoise-first", "fuse-first"), "order")
    A = _signals(X)
    Y = denoise(A, wavelet, level, mode=mode, threshold=threshold)
    if normaliser == "max":
        norms = Y.max(axis=-1)
    elif normaliser == "median":
        norms = np.median(Y, axis=-1)
    else:
        ref = Y[..., :1, :]
        norms = np.sum(Y * ref, axis=-1) / np.sum(ref * ref, axis=-1)
    if np.any(norms <= 0):
        raise ValueError("normaliser must be positive for every sensor (signal maximum/median <= 0?)")
    Ybar = Y / norms[..., None]
    resid = (A - Y) / norms[..., None]
    var = resid.var(axis=-1)
    if np.any(var <= 0):
        raise ValueError("a sensor has zero residual variance: weights undefined")
    w = (1.0 / var) / (1.0 / var).sum(axis=-1, keepdims=True)
    if order == "denoise-first":
        fused = np.einsum("...j,...jn->...n", w, Ybar)
    else:
        fused = denoise(np.einsum("...j,...jn->...n", w, A / norms[..., None]), wavelet, level, mode=mode,
                        threshold=threshold)
    return Reconstruction(denoised=Y, norms=norms, weights=w, fused=fused,
                          reconstructed=fused[..., None, :] * norms[..., None])
