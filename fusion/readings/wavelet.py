r"""Wavelet denoising and fusion-based per-sensor reconstruction (lecture notes, §2.6).

Model: sensor j reads :math:`X_j(n) = g_jS(n) + e_j(n)`, n = 1..I (the lecture writes
:math:`g_j = 1`, which leaves its normalisation step nothing to do). Steps:

1. denoise every sensor by wavelet thresholding (:func:`denoise`, PyWavelets), giving :math:`Y_j`;
2. normalise :math:`\bar Y_j = Y_j / \mathrm{norm}_j` (the lecture: the maximum over the estimation length,
   of the denoised signal :math:`Y_j` by its formula's symbol, of the raw measurements :math:`X_j` by its words,
   "the largest measured value", 最大测量值: ``normaliser="max"`` and ``"max-raw"``);
3. inverse-variance weights :math:`W_j \propto \hat\sigma_j^{-2}`; the lecture estimates
   :math:`\sigma_j^2` "recursively by an MA model" (采用MA模型用递归方法估计方差), which
   :func:`variance_estimates` reads five ways (``variance=``): the variance of the normalised residual
   :math:`(X_j - Y_j)/\mathrm{norm}_j` over the estimation length (the default), the same variance
   updated recursively sample by sample (growing memory) or over a moving window (a moving average
   of the squared deviations, updated recursively), the running variance of the normalised
   measurement itself, and equal weights (a reference);
4. fuse :math:`\hat Y = \sum_j W_j\bar Y_j`;
5. de-normalise :math:`\hat Y_j = \hat Y\,\mathrm{norm}_j`.

Open choices exposed (the lecture fixes none of them): the wavelet family and depth, the
threshold rule (universal or BayesShrink, soft or hard; the lecture's words, "set a threshold and
remove the wavelet coefficients below it" (设置阈值,将小于阈值的小波系数去掉), describe hard
thresholding), the transform (the decimated DWT or the translation-invariant stationary transform,
``transform="swt"``) and the order of the two operations (``order="fuse-first"`` fuses the
normalised raw signals with the same weights and normalisers, and denoises the fused signal; the
weights and normalisers still come from every sensor's own denoised signal).

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

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Literal

import numpy as np
import pywt
from numpy.typing import ArrayLike

from fusion._frozen import frozen_arrays
from fusion._validation import derived_inputs
from fusion._validation import shown
from fusion._validation import text
from fusion._validation import _numeric, FloatArray, as_array, check_magnitude, count, one_of
from fusion._validation import work

__all__ = ["denoise", "Reconstruction", "reconstruct", "fuse_denoised", "variance_estimates", "VARIANCES",
           "NORMALISERS"]

Normaliser = Literal["max", "max-raw", "median", "lsq"]
Transform = Literal["dwt", "swt"]
Threshold = Literal["universal", "bayes"]
Order = Literal["denoise-first", "fuse-first"]
Variance = Literal["batch", "running", "window", "measurement", "equal"]

#: Readings of the lecture's step 3, "estimate the variance recursively by an MA model"
#: (:func:`variance_estimates`); the first is the default.
VARIANCES: tuple[str, ...] = ("batch", "running", "window", "measurement", "equal")

#: Normalisers of :func:`reconstruct`; the first two are the two readings of the lecture's maximum.
NORMALISERS: tuple[str, ...] = ("max", "max-raw", "median", "lsq")


def _signals(X: ArrayLike) -> FloatArray:
    A = _numeric(X, "X")
    if A.ndim < 2 or A.shape[-2] < 2 or A.shape[-1] < 8:
        raise ValueError(f"X must be (..., n_sensors >= 2, I >= 8) signals, got shape {A.shape}")
    check_magnitude(A, "X")
    return A


def denoise(x: ArrayLike, wavelet: str = "db4", level: int = 4, mode: Literal["soft", "hard"] = "soft",
            threshold: Threshold = "universal", transform: Transform = "dwt") -> FloatArray:
    r"""Wavelet-threshold denoising (Donoho & Johnstone 1994) of signals along the last axis.

    Noise level from the finest detail coefficients, :math:`\hat\sigma = \mathrm{median}|d_1|/0.6745`;
    all detail levels thresholded (``mode``), approximation kept; periodisation boundary handling.
    ``transform="dwt"``: the decimated transform (``pywt.wavedec``); ``"swt"``: the stationary
    (undecimated, translation-invariant) transform (``pywt.swt`` without normalisation, so that white
    noise has the same SD at every level, and ``pywt.iswt``, which averages over the shifts: the
    cycle-spinning denoiser of Coifman & Donoho 1995); its length must be a multiple of
    :math:`2^{\mathrm{level}}`.
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
        Decomposition depth (default 4); for ``transform="dwt"`` a depth beyond ``pywt.dwt_max_level`` of the
        signal's length (short signals, long filters) is computed all the same, every coefficient then touched by
        the periodic boundary (``_wavedec_periodic``: no warning).
    mode : {"soft", "hard"}
        Thresholding rule: soft shrinks surviving coefficients by :math:`\lambda`, hard keeps them.
    threshold : {"universal", "bayes"}
        Threshold selection (see above).
    transform : {"dwt", "swt"}
        Decimated or stationary (translation-invariant) transform.

    Returns
    -------
    ndarray, shape (..., I)
        The denoised signals.

    References
    ----------
    * Donoho, D. L., & Johnstone, I. M. (1994). Ideal spatial adaptation by wavelet shrinkage.
      *Biometrika*, 81(3), 425-455.
    * Coifman, R. R., & Donoho, D. L. (1995). Translation-invariant de-noising. In *Wavelets and
      Statistics* (Lecture Notes in Statistics 103), 125-150. Springer.
    """
    mode = one_of(mode, ("soft", "hard"), "mode")
    threshold = one_of(threshold, ("universal", "bayes"), "threshold")
    transform = one_of(transform, ("dwt", "swt"), "transform")
    a = _numeric(x, "x")
    if a.ndim < 1 or a.shape[-1] < 8:
        raise ValueError(f"x must be finite with at least 8 samples on its last axis, got shape {a.shape}")
    if a.size == 0:
        raise ValueError(f"x is empty (shape {a.shape}): no signal to denoise")
    check_magnitude(a, "x")
    level = count(level, "level")
    wavelet = _wavelet_name(wavelet)
    if transform == "swt":
        if a.shape[-1] % 2 ** int(level):
            raise ValueError(f"x must have a multiple of 2**level = {2 ** int(level)} samples for transform='swt', "
                             f"got {a.shape[-1]}")
        _swt_work(a.size // a.shape[-1], a.shape[-1], int(level), wavelet, "x, level and wavelet",
                  flat=a.ndim == 1)
        coeffs = pywt.swt(a, wavelet, level=int(level), axis=-1, trim_approx=True, norm=False)
    else:
        coeffs = _wavedec_periodic(a, wavelet, int(level))
    sigma = np.median(np.abs(coeffs[-1]), axis=-1, keepdims=True) / 0.6745
    if threshold == "universal":
        lams = [sigma * np.sqrt(2.0 * np.log(a.shape[-1]))] * (len(coeffs) - 1)
    else:
        lams = []
        for c in coeffs[1:]:
            sx = np.sqrt(np.maximum(np.mean(c**2, axis=-1, keepdims=True) - sigma**2, 0.0))
            big = np.max(np.abs(c), axis=-1, keepdims=True) + 1.0
            lams.append(np.where(sx > 0, sigma**2 / np.where(sx > 0, sx, 1.0), big))
    out = [coeffs[0]] + [_shrink(c, lam, mode) for c, lam in zip(coeffs[1:], lams)]
    if transform == "swt":
        return pywt.iswt(out, wavelet, axis=-1, norm=False)
    rec = pywt.waverec(out, wavelet, mode="periodization", axis=-1)
    return rec[..., : a.shape[-1]]


def _wavelet_name(wavelet: object) -> str:
    """``wavelet`` checked as the name of a discrete wavelet of PyWavelets (a TypeError for another type, issue 35; a
    ValueError naming ``wavelet`` for an unknown name), as plain text (rule 19)."""
    if not isinstance(wavelet, str):   # a wrong type (a path, a number) is a TypeError (issue 35)
        raise TypeError(f"wavelet must be the name (a str) of a discrete wavelet, got {type(wavelet).__name__}")
    wavelet = text(wavelet, "wavelet")  # rule 19: matched by its text
    if wavelet not in pywt.wavelist(kind="discrete"):
        raise ValueError(f"wavelet must be the name of a discrete wavelet known to PyWavelets, got {shown(wavelet)}")
    return wavelet


#: Units (about 10 ns, ``fusion._validation.MAX_WORK``) of the stationary transform as :func:`denoise` runs it
#: (``pywt.swt`` then ``pywt.iswt``, PyWavelets 1.8; fuzz 61b C2: it had no budget, and a 2**17-sample signal at level
#: 17 ran 54.7 CPU-s). ``_swt_work`` counts, for ``rows`` signals of ``I`` samples at level ``J`` with a filter of
#: ``L`` taps: ``5 J`` a sample (every level's passes and ``iswt``'s strided gathers, out of cache for long signals),
#: ``0.36 L J`` a sample (the filters' taps), ``0.07`` a sample per tap of every level whose dilated filter
#: ``L 2**(j-1)`` is at least ``I`` long (``swt`` then runs over its zeros too), and per shift of the inverse's Python
#: loop (``2**J`` a call): for a 1-D signal (``iswt``) 2,440 units, for more axes (``iswtn``, reached by every
#: 2-D or 3-D array) 7,870 units plus ``1/8`` a sample, since ``iswtn`` copies the whole array at each of its
#: ``2**J`` shifts (fix69f: 4 signals of 2**18 at level 14 ran 12.3 CPU-s, one signal of 2**21 at level 10 1.7;
#: the former ``5 J**2`` a sample counted the second 1.1e9 units, refused, and the first 6.1e8). Measured
#: (``time.process_time``, ``OPENBLAS_NUM_THREADS=1``, machine shared with other jobs, min of 2): a non-negative
#: least-squares fit of relative error over 37 calls of :func:`denoise` (1-D and 1 to 16 rows, I = 2**12 to 2**21,
#: J = 4 to 16, haar, db4, db16, db38; 0.06 to 13.9 CPU-s) gave 25.4 ns, 1.78 ns, 0.34 ns, 12.2 us, 39.3 us and
#: 0.62 ns, its predictions 0.31 to 1.48 of the measured (low: 16 rows of 2**18, memory-bound ``swt``; high: 2**16
#: samples at level 16); the weights are twice the fit, so a count of MAX_WORK runs about 3.4 to 16 CPU-s.
_SWT_LEVEL, _SWT_TAP, _SWT_WIDE = 5, Fraction(36, 100), Fraction(7, 100)
_SWT_SHIFT_1D, _SWT_SHIFT_ND, _SWT_COPY = 2440, 7870, Fraction(1, 8)


def _swt_work(rows: int, samples: int, level: int, wavelet: str, names: str, calls: int = 1,
              flat: bool = False) -> int:
    """Refuse the stationary transform and its inverse of ``rows`` signals of ``samples`` samples at depth ``level``
    (``calls`` calls of :func:`denoise` between them; ``flat``: one 1-D signal a call, ``pywt.iswt``, else arrays
    of more axes, ``pywt.iswtn``) beyond the work budget, naming ``names``; the units otherwise (weights above).
    ``wavelet`` is a checked name."""
    taps = pywt.Wavelet(wavelet).dec_len
    wide = sum(taps << (j - 1) for j in range(1, level + 1) if taps << (j - 1) >= samples)
    n = rows * samples
    units = n * (_SWT_LEVEL * level + _SWT_TAP * taps * level + _SWT_WIDE * wide)
    if flat:
        units += calls * _SWT_SHIFT_1D * 2**level
    else:
        units += (calls * _SWT_SHIFT_ND + _SWT_COPY * n) * 2**level
    return work((math.ceil(units),), names)


def _wavedec_periodic(a: np.ndarray, wavelet: str, level: int) -> list[np.ndarray]:
    """``pywt.wavedec(a, wavelet, level=level, mode="periodization", axis=-1)`` bit for bit, by its own loop of
    single-level ``pywt.dwt``, without its UserWarning for a level beyond ``pywt.dwt_max_level`` (every coefficient
    then sees the periodic boundary: a valid transform, which a caller's ``warnings.simplefilter("error")`` turned
    into an exception; fuzz 37b C3). ``a``, ``wavelet`` and ``level`` are the caller's, already checked."""
    details = []
    for _ in range(level):
        a, d = pywt.dwt(a, wavelet, mode="periodization", axis=-1)
        details.append(d)
    return [a, *details[::-1]]


#: The round-off factor of a variance estimate (``_round_off``): an estimate at most this many units of round-off
#: is zero.
_ROUND_OFF_UNITS = 8.0


def _round_off(z: FloatArray, raw: FloatArray, memory: str, m2: FloatArray, window: int) -> FloatArray:
    r"""The round-off level of each variance estimate of ``z`` (shape (..., n, I)), below which it is zero (fuzz 37a
    D3: a constant residual gave variance estimates of 1e-21 set by round-off, whose ratios set the weights and
    changed with the input's scale while ``"batch"`` refused the same data).

    ``raw`` is the normalised raw signal the residual was computed from: each residual sample carries an error of
    about :math:`\epsilon\max|raw|` (the cancellation of ``X - Y``), so a variance below :math:`(8\epsilon\max|raw|)^2`
    is round-off. The rest matches how each ``memory`` computes its variance (``m2``: its mean of :math:`z^2`):
    ``"batch"`` is numpy's two-pass ``var`` (the mean removed first), exact to a few :math:`\epsilon` of
    :math:`\max|z|^2`, whatever the length; ``"growing"`` subtracts :math:`\bar z^2` from a prefix sum of
    :math:`N` terms, exact to :math:`8\epsilon N` times ``m2``; ``"window"`` does so from the window's own sums
    (``_window_mean``, at most ``window`` terms each), exact to :math:`8\epsilon` ``window`` times ``m2`` however
    long the signal (fix43r: an N-fold batch term refused a residual of relative SD 1e-6). Scale-free: a rescaled
    input scales it as its estimates.
    """
    eps = _ROUND_OFF_UNITS * np.finfo(float).eps
    cancel = (eps * np.abs(raw).max(axis=-1, keepdims=True)) ** 2
    if memory == "batch":
        return cancel + (eps * np.abs(z).max(axis=-1, keepdims=True)) ** 2
    n = np.arange(1, z.shape[-1] + 1, dtype=float)
    return cancel + eps * (n if memory == "growing" else np.minimum(n, window)) * m2


def _window_mean(z: FloatArray, window: int) -> FloatArray:
    """The mean of the last ``window`` samples of ``z`` along its last axis (shorter at the start), as
    :func:`fusion.readings.weighting.running_average` ``(memory="window")`` but summed from the window's own
    samples (a block's prefix plus the previous block's suffix), not as a difference of prefix sums whose
    round-off grows with the signal's length. A ``window`` beyond the ``I`` samples is taken as ``I``: the same
    numbers to the bit (one block either way, its first ``I`` prefix sums and the divisors ``1..I``), without padding
    each row to ``window`` samples (fuzz 43 C1: ``window=10**7`` over 64 samples allocated rows x 10**7 floats, a raw
    MemoryError at 100 rows, 6.5 CPU-s at 8)."""
    from fusion.readings._windows import block_sums

    I = z.shape[-1]
    window = min(window, max(I, 1))
    return block_sums(z, window) / np.minimum(np.arange(1, I + 1), window)


@derived_inputs()
def variance_estimates(X: ArrayLike, Y: ArrayLike, norms: ArrayLike, variance: Variance = "batch",
                       window: int = 64) -> FloatArray:
    r"""The variance behind each sensor's weight at every sample (sec. 2.6, step 3), five readings.

    The lecture says only "estimate the variance recursively with an MA model"
    (采用MA模型用递归方法估计方差) and, earlier, "a recursive variance estimator built on the basic
    definition of the variance". With the normalised residual :math:`r_j(n) = (X_j(n) - Y_j(n))/\mathrm{norm}_j`
    (raw minus denoised, i.e. the noise that denoising removed) and
    :math:`\widehat{\mathrm{var}}_{\mathcal W}(z) = \overline{z^2}_{\mathcal W} - (\bar z_{\mathcal W})^2`
    over a set :math:`\mathcal W` of samples:

    * ``"batch"``: :math:`\hat\sigma_j^2 = \widehat{\mathrm{var}}_{1..I}(r_j)`, one value for the whole
      estimation length I (constant weights; the default);
    * ``"running"``: :math:`\hat\sigma_j^2(n) = \widehat{\mathrm{var}}_{1..n}(r_j)`, the running variance from its
      basic definition with the recursions :math:`\bar z(n) = \bar z(n-1) + (z(n) - \bar z(n-1))/n` for
      :math:`z = r, r^2` (growing memory, causal); at n = I it equals ``"batch"``;
    * ``"window"``: :math:`\hat\sigma_j^2(n) = \widehat{\mathrm{var}}_{n-L+1..n}(r_j)`, the moving average (MA)
      of the last :math:`L` = ``window`` samples, updated recursively,
      :math:`\bar z(n) = \bar z(n-1) + (z(n) - z(n-L))/L` (shorter windows at the start);
    * ``"measurement"``: the running variance of the normalised *measurement*
      :math:`X_j(n)/\mathrm{norm}_j` itself (growing memory), the "variance of the measured values" of the
      lecture's motivation; it contains the variance of the signal, common to all sensors;
    * ``"equal"``: all ones (equal weights; not a reading of the lecture, a reference).

    Parameters
    ----------
    X : array_like, shape (..., n, I)
        Raw signals.
    Y : array_like, shape (..., n, I)
        Denoised signals (same unit).
    norms : array_like, shape (..., n)
        Normaliser of each sensor (> 0).
    variance : {"batch", "running", "window", "measurement", "equal"}
        The reading (:data:`VARIANCES`).
    window : int
        Window length :math:`L \ge 2` of ``"window"`` (default 64 samples); one longer than the samples gives the
        numbers of a window of all of them.

    Returns
    -------
    ndarray, shape (..., n, I)
        Variance estimates in normalised units² at every sample (constant along the last axis for
        ``"batch"`` and ``"equal"``). The first sample of the recursive readings is 0 (one sample
        has no spread); :func:`reconstruct` then uses equal weights. An estimate at or below the round-off of its
        own computation (about :math:`8\epsilon` of the raw signal's maximum, squared; plus, for ``"batch"``, the
        same of the residual's maximum; for the running readings, :math:`8\epsilon N` of the mean of :math:`z^2`
        over the :math:`N` samples summed: the prefix for ``"running"``, the window's own for ``"window"``) is 0: a residual that is constant (in
        value) has zero variance in every reading, whatever the input's scale.

    Raises
    ------
    ValueError
        Mismatched shapes, non-positive normalisers, an unknown reading or a window below 2.

    References
    ----------
    * Welford, B. P. (1962). Note on a method for calculating corrected sums of squares and
      products. *Technometrics*, 4(3), 419-420 (running variance).
    * An explanation of multi-sensor data fusion algorithms (多传感器数据融合算法讲解), sec. 2.6,
      step 3. Lecture notes, web copy (in Chinese; author and date not stated).
    """
    from fusion.readings.weighting import running_average

    variance = one_of(variance, VARIANCES, "variance")
    A = _signals(X)
    D = _numeric(Y, "Y")
    if D.shape != A.shape:
        raise ValueError(f"Y must be finite with the shape of X {A.shape}, got {D.shape}")
    check_magnitude(D, "Y")
    nrm = _numeric(norms, "norms")
    if nrm.shape == A.shape[:-1]:
        check_magnitude(nrm, "norms")
    if nrm.shape != A.shape[:-1] or np.any(nrm <= 0):
        raise ValueError(f"norms must be positive and finite with shape {A.shape[:-1]}, got {nrm.shape}")
    L = count(window, "window", minimum=2)
    if variance == "equal":
        return np.ones_like(A)
    z = (A if variance == "measurement" else A - D) / nrm[..., None]
    raw = A / nrm[..., None]
    if variance == "batch":
        v = z.var(axis=-1, keepdims=True)
        return np.broadcast_to(np.where(v <= _round_off(z, raw, "batch", v, L), 0.0, v), z.shape).copy()
    memory = "window" if variance == "window" else "growing"
    if memory == "window":
        m1, m2 = _window_mean(z, L), _window_mean(z * z, L)
    else:
        m1 = running_average(z, memory, window=L, axis=-1)
        m2 = running_average(z * z, memory, window=L, axis=-1)
    v = m2 - m1 * m1                       # the difference of two running means can round below 0, or just above
    return np.where(v <= _round_off(z, raw, memory, m2, L), 0.0, v)


@dataclass(frozen=True)
@frozen_arrays
class Reconstruction:
    """Result of :func:`reconstruct` (shapes: n sensors, I samples, optional leading batch axes ``...``).

    Attributes
    ----------
    denoised : ndarray, shape (..., n, I)
        Each sensor's own denoised signal.
    norms : ndarray, shape (..., n)
        Normaliser of each sensor.
    weights : ndarray, shape (..., n)
        Weights at the last sample (for ``variance="batch"``, the weights of every sample).
    weight_path : ndarray, shape (..., n, I)
        Weights applied at each sample (constant along I for ``"batch"`` and ``"equal"``: then a
        read-only view).
    variances : ndarray, shape (..., n, I)
        The variance estimates behind them (:func:`variance_estimates`; a read-only view for the
        constant readings).
    fused : ndarray, shape (..., I)
        Fused normalised signal (denoised, in either order).
    reconstructed : ndarray, shape (..., n, I)
        De-normalised fused signal of each sensor.
    """

    denoised: FloatArray
    norms: FloatArray
    weights: FloatArray
    weight_path: FloatArray
    variances: FloatArray
    fused: FloatArray
    reconstructed: FloatArray


def _shrink(c: FloatArray, lam: FloatArray, mode: str) -> FloatArray:
    r"""``pywt.threshold(c, lam, mode)``, with a zero threshold leaving ``c`` unchanged.

    PyWavelets' soft rule is :math:`c\,\max(1 - \lambda/|c|, 0)`, which is ``0/0 = NaN`` for a zero
    coefficient under a zero threshold (a signal whose finest coefficients are mostly zero, such
    as a constant one, has :math:`\hat\sigma = 0`); the limit there is ``c`` itself. Other
    rows keep PyWavelets' numbers bit for bit.
    """
    with np.errstate(invalid="ignore", divide="ignore"):   # the 0/0 of a zero threshold, replaced below
        out = pywt.threshold(c, lam, mode=mode)
    zero = lam == 0
    if mode == "soft" and np.any(zero):
        out = np.where(zero, c, out)
    return out


@derived_inputs()
def reconstruct(
    X: ArrayLike,
    wavelet: str = "db4",
    level: int = 4,
    normaliser: Normaliser = "max",
    mode: Literal["soft", "hard"] = "soft",
    threshold: Threshold = "universal",
    order: Order = "denoise-first",
    variance: Variance = "batch",
    window: int = 64,
    transform: Transform = "dwt",
) -> Reconstruction:
    r"""Per-sensor reconstruction by denoising, normalisation and fusion (sec. 2.6).

    Parameters
    ----------
    X : array_like, shape (..., n, I)
        One row per sensor, I samples (the estimation length); leading axes are independent
        batches (e.g. Monte-Carlo runs), processed at once (in blocks of runs, which gives the
        same numbers as one run at a time and keeps the arrays small enough for the cache).
    wavelet, level, mode, threshold, transform
        See :func:`denoise`. The lecture's "remove the coefficients below the threshold" is
        ``mode="hard"``; the default stays ``"soft"`` (the usual choice with the universal threshold),
        and the book's chapter runs hard thresholding as its primary reading.
    normaliser : {"max", "max-raw", "median", "lsq"}
        ``"max"``: :math:`\max_n Y_j(n)` of each sensor's *denoised* signal (the symbol :math:`Y_j` of the
        lecture's formula); ``"max-raw"``: :math:`\max_n X_j(n)` of its *raw* measurements (the lecture's words,
        "the largest measured value", 最大测量值); ``"median"``: :math:`\mathrm{median}_n Y_j(n)`; ``"lsq"``: the
        least-squares gain of :math:`Y_j` on the first sensor's denoised signal (relative gains only).
    order : {"denoise-first", "fuse-first"}
        ``"denoise-first"`` (the lecture): fuse the normalised denoised signals,
        :math:`\hat Y = \sum_jW_jY_j/\mathrm{norm}_j`. ``"fuse-first"``: fuse the normalised *raw*
        signals with the same weights and normalisers, :math:`\sum_jW_jX_j/\mathrm{norm}_j`, and
        denoise that single fused signal (its noise is lower, so its threshold is lower too). The
        weights and normalisers still come from every sensor's denoised signal, so this order denoises
        every sensor as well, plus the fused signal: it costs one denoising more, not fewer.
    variance : {"batch", "running", "window", "measurement", "equal"}
        How :math:`\sigma_j^2` of the weights is estimated (step 3; :func:`variance_estimates`). With
        the recursive readings the weights change along the signal,
        :math:`W_j(n) \propto \hat\sigma_j^{-2}(n)`, and a sample at which some estimate is 0 (the first, or
        one at round-off level) gets equal weights. A sensor whose residual (raw minus denoised) is constant over
        the whole signal, to round-off, has no inverse-variance weight under ``"batch"``, ``"running"`` or
        ``"window"`` alike: refused.
    window : int
        Window of ``variance="window"``.

    Returns
    -------
    Reconstruction
        For the constant readings (``"batch"``, ``"equal"``) ``weight_path`` and ``variances`` are
        read-only views that repeat one value along I.

    Raises
    ------
    ValueError
        Bad shapes, non-finite input, an unknown option, or a normaliser that is not positive
        (e.g. a signal whose maximum is <= 0).
    """
    normaliser = one_of(normaliser, NORMALISERS, "normaliser")
    order = one_of(order, ("denoise-first", "fuse-first"), "order")
    variance = one_of(variance, VARIANCES, "variance")
    window = count(window, "window", minimum=2)
    A = _signals(X)
    kw = {"wavelet": wavelet, "level": level, "normaliser": normaliser, "mode": mode, "threshold": threshold,
          "order": order, "variance": variance, "window": window, "transform": transform}
    lead, (n, size) = A.shape[:-2], A.shape[-2:]
    flat = A.reshape(-1, n, size)
    runs = flat.shape[0]
    block = max(1, _BLOCK_SAMPLES // (n * size))
    if one_of(transform, ("dwt", "swt"), "transform") == "swt":  # every block's transforms, counted at once (fuzz 61b C2)
        fused = order == "fuse-first"                            # its fused signal denoised too
        _swt_work(runs * (n + fused), size, count(level, "level"), _wavelet_name(wavelet), "X, level and wavelet",
                  calls=-(-runs // block) * (1 + fused))
    constant = variance in ("batch", "equal")
    out: dict[str, np.ndarray] = {}
    for i in range(0, runs, block):
        part = _reconstruct(flat[i:i + block], **kw)
        for f in ("denoised", "norms", "weights", "weight_path", "variances", "fused", "reconstructed"):
            v = getattr(part, f)
            if f not in out:
                out[f] = np.empty((runs, *v.shape[1:]))
            out[f][i:i + block] = v
    for f, v in out.items():
        v = v.reshape(*lead, *v.shape[1:])
        if constant and f in ("weight_path", "variances"):          # (..., n, 1): repeat along I as a view
            v = np.broadcast_to(v, (*lead, n, size))
        out[f] = v
    return Reconstruction(**out)


#: Samples (sensors × I per run) processed at once by :func:`reconstruct`.
_BLOCK_SAMPLES = 1 << 18


def _reconstruct(A: FloatArray, wavelet: str, level: int, normaliser: str, mode: str, threshold: str, order: str,
                 variance: str, window: int, transform: str) -> Reconstruction:
    """:func:`reconstruct` of validated signals of shape (runs, n, I); constant readings keep (runs, n, 1)."""
    Y = denoise(A, wavelet, level, mode=mode, threshold=threshold, transform=transform)
    rec = _fuse(A, Y, normaliser, variance, window, A if order == "fuse-first" else None)
    if order == "denoise-first":
        return rec
    fused = denoise(rec.fused, wavelet, level, mode=mode, threshold=threshold, transform=transform)
    return Reconstruction(denoised=Y, norms=rec.norms, weights=rec.weights, weight_path=rec.weight_path,
                          variances=rec.variances, fused=fused, reconstructed=fused[..., None, :] * rec.norms[..., None])


def _fuse(A: FloatArray, Y: FloatArray, normaliser: str, variance: str, window: int,
          source: FloatArray | None = None, names: str = "X", residual: str = "X") -> Reconstruction:
    """Steps 2-5 from the raw ``A`` and denoised ``Y`` (validated); fuses ``source`` (default ``Y``) normalised.

    ``names``: the arguments the signals come from, named when a normaliser is not positive; ``residual``: those the
    residual ``A - Y`` comes from, named when it is constant.
    """
    if normaliser == "max":
        norms = Y.max(axis=-1)
    elif normaliser == "max-raw":
        norms = A.max(axis=-1)
    elif normaliser == "median":
        norms = np.median(Y, axis=-1)
    else:
        ref = Y[..., :1, :]
        norms = np.sum(Y * ref, axis=-1) / np.sum(ref * ref, axis=-1)
    if np.any(norms <= 0):
        what = {"max": "maximum of the denoised", "max-raw": "maximum of the raw", "median": "median of the denoised",
                "lsq": "gain on the first sensor of the denoised"}[normaliser]
        raise ValueError(f"{names} must give a positive normaliser for every sensor: the {what} signal "
                         f"(normaliser={shown(normaliser)}) is <= 0 for sensor(s) "
                         f"{sorted(set(np.nonzero(norms <= 0)[-1].tolist()))}")
    constant = variance in ("batch", "equal")
    if variance in ("batch", "running", "window"):   # one rule for a residual of zero variance (fuzz 37a D3)
        z = (A - Y) / norms[..., None]
        var = (A - Y).var(axis=-1, keepdims=True) / norms[..., None] ** 2      # the normalised residual's variance
        flat = var <= _round_off(z, A / norms[..., None], "batch", var, window)
        if np.any(flat):
            raise ValueError(f"{residual} must give every sensor a residual (raw minus denoised) that is not "
                             f"constant: sensor(s) {sorted(set(np.nonzero(flat)[-2].tolist()))} have zero residual "
                             f"variance up to round-off, so the inverse-variance weights (variance={shown(variance)}) "
                             "are undefined")
    if variance == "equal":
        var = np.ones((*A.shape[:-1], 1))
    elif variance != "batch":
        var = variance_estimates(A, Y, norms, variance, window)
    ok = np.all(var > 0, axis=-2, keepdims=True)                  # (..., 1, I or 1)
    inv = np.where(ok, 1.0 / np.where(ok, var, 1.0), 1.0)          # equal weights where some estimate is 0
    w = inv / inv.sum(axis=-2, keepdims=True)                      # (..., n, I or 1)
    src = Y if source is None else source
    if constant:                                                   # Σⱼ (Wⱼ/normⱼ) srcⱼ: no normalised copy
        fused = np.einsum("...j,...jn->...n", w[..., 0] / norms, src)
    else:
        fused = np.sum(w * (src / norms[..., None]), axis=-2)
    return Reconstruction(denoised=Y, norms=norms, weights=w[..., -1].copy(), weight_path=w, variances=var,
                          fused=fused, reconstructed=fused[..., None, :] * norms[..., None])


@derived_inputs()
def fuse_denoised(X: ArrayLike, Y: ArrayLike, normaliser: Normaliser = "max", variance: Variance = "batch",
                  window: int = 64) -> Reconstruction:
    r"""Steps 2-5 of sec. 2.6 (the lecture's order) for signals already denoised: normalise, weight, fuse, de-normalise.

    :func:`reconstruct` is :func:`denoise` followed by this function; a study that tries several
    normalisers or variance readings on the same denoised signals calls it directly and denoises once.

    Parameters
    ----------
    X : array_like, shape (..., n, I)
        Raw signals (leading axes: independent batches).
    Y : array_like, shape (..., n, I)
        The same signals denoised (same unit), e.g. by :func:`denoise`.
    normaliser, variance, window
        As :func:`reconstruct`.

    Returns
    -------
    Reconstruction
        ``denoised`` is ``Y``; ``weight_path`` and ``variances`` have a last axis of length 1 for the
        constant readings (``"batch"``, ``"equal"``) and of length I otherwise.

    Raises
    ------
    ValueError
        Mismatched shapes, non-finite input, an unknown option, or a normaliser that is not positive.
    """
    normaliser = one_of(normaliser, NORMALISERS, "normaliser")
    variance = one_of(variance, VARIANCES, "variance")
    window = count(window, "window", minimum=2)
    A = _signals(X)
    D = _numeric(Y, "Y")
    if D.shape != A.shape:
        raise ValueError(f"Y must be finite with the shape of X {A.shape}, got {D.shape}")
    check_magnitude(D, "Y")
    return _fuse(A, D, normaliser, variance, window, names="X" if normaliser == "max-raw" else "Y",
                 residual="X and Y")
