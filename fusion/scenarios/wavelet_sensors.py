r"""The mechanism of the lecture notes' §2.6 reconstruction: shared denoising bias, order, choices.

Same case as :func:`fusion.scenarios.lecture.wavelet_study` (same seed gives the same noise):
:math:`X_j = g_jS + e_j`, :math:`S(n) = 2 + \sin(2\pi n/256) + 0.5\sin(2\pi n/64)`. Here the
reconstruction is run for every Monte-Carlo run at once (:func:`fusion.readings.wavelet.reconstruct`
takes leading batch axes), and the study measures

* the **bias** of each sensor's denoised signal (the mean over runs of its error, per sample) and
  its share of the MSE;
* the **cross-sensor correlation** of the denoised signals' relative errors
  :math:`(Y_j - g_jS)/g_j`: a shared error that fusion cannot average out;
* the two **orders**, denoise-then-fuse (the lecture) and fuse-then-denoise;
* the **sensitivity** to the wavelet family, the depth and the threshold rule;
* the **variance estimate** of the weights, the lecture's step 3 "recursively by an MA model", under
  each reading of :data:`fusion.readings.wavelet.VARIANCES` (:func:`variance_study`).

References
----------
* Donoho, D. L., & Johnstone, I. M. (1994). Ideal spatial adaptation by wavelet shrinkage.
  *Biometrika*, 81(3), 425-455.
* Chang, S. G., Yu, B., & Vetterli, M. (2000). Adaptive wavelet thresholding for image
  denoising and compression. *IEEE Transactions on Image Processing*, 9(9), 1532-1546.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from fusion._validation import as_array, count
from fusion.readings import wavelet as wv

__all__ = ["CONFIGS", "config_label", "signal", "mechanism_study", "variance_study"]

#: Wavelet settings of the sensitivity study; the first is the chapter's default.
CONFIGS: tuple[dict[str, Any], ...] = (
    {"wavelet": "db4", "level": 4, "threshold": "universal", "mode": "soft"},
    {"wavelet": "haar", "level": 4, "threshold": "universal", "mode": "soft"},
    {"wavelet": "sym8", "level": 4, "threshold": "universal", "mode": "soft"},
    {"wavelet": "coif3", "level": 4, "threshold": "universal", "mode": "soft"},
    {"wavelet": "db4", "level": 2, "threshold": "universal", "mode": "soft"},
    {"wavelet": "db4", "level": 6, "threshold": "universal", "mode": "soft"},
    {"wavelet": "db4", "level": 4, "threshold": "universal", "mode": "hard"},
    {"wavelet": "db4", "level": 4, "threshold": "bayes", "mode": "soft"},
)


def config_label(cfg: dict[str, Any]) -> str:
    """``"db4, 4 levels, universal soft"`` for a configuration of :data:`CONFIGS`.

    Parameters
    ----------
    cfg : dict
        Keys ``wavelet``, ``level``, ``threshold``, ``mode``.

    Returns
    -------
    str

    Raises
    ------
    TypeError
        ``cfg`` is not a mapping.
    ValueError
        A key is missing.
    """
    if not isinstance(cfg, dict):
        raise TypeError(f"cfg must be a dict, got {type(cfg).__name__}")
    missing = [k for k in ("wavelet", "level", "threshold", "mode") if k not in cfg]
    if missing:
        raise ValueError(f"cfg lacks {missing}")
    return f"{cfg['wavelet']}, {cfg['level']} levels, {cfg['threshold']} {cfg['mode']}"


def signal(length: int = 1024) -> np.ndarray:
    r"""The test signal :math:`S(n) = 2 + \sin(2\pi n/256) + 0.5\sin(2\pi n/64)`, n = 0..length-1.

    Parameters
    ----------
    length : int
        Number of samples (>= 16).

    Returns
    -------
    ndarray, shape (length,)
    """
    n = np.arange(count(length, "length", minimum=16))
    return 2 + np.sin(2 * np.pi * n / 256) + 0.5 * np.sin(2 * np.pi * n / 64)


def mechanism_study(
    length: int = 1024,
    runs: int = 100,
    gains: Sequence[float] = (1.0, 1.5, 0.8, 2.0),
    sigma: Sequence[float] = (0.05, 0.1, 0.2, 0.4),
    seed: int = 2601,
    configs: Sequence[dict[str, Any]] = CONFIGS,
) -> dict[str, Any]:
    r"""Bias, cross-sensor error correlation, order and wavelet choices of the §2.6 reconstruction.

    Parameters
    ----------
    length : int
        Samples per signal I (>= 16).
    runs : int
        Monte-Carlo runs (>= 2).
    gains : sequence of float
        Sensor gains :math:`g_j` (> 0).
    sigma : sequence of float
        Noise SD of each sensor (> 0), same length as ``gains``.
    seed : int
        Seed of the noise (as :func:`fusion.scenarios.lecture.wavelet_study`).
    configs : sequence of dict
        Wavelet settings (keys ``wavelet``, ``level``, ``threshold``, ``mode``); the first is the
        reference of the bias and correlation measurements.

    Returns
    -------
    dict
        ``labels`` (one per config); ``err[label]``: dict of per-run MSE against :math:`g_jS`,
        shape (runs, sensors), for ``raw``, ``denoised``, ``denoise-first``, ``fuse-first``;
        ``bias_share`` (sensors,): squared bias over MSE of each sensor's denoised signal (first
        config); ``bias_share_rec``: the same for the reconstruction; ``corr`` (sensors,
        sensors): correlation of the denoised signals' relative errors pooled over runs and
        samples; ``corr_random``: the same after removing each sensor's bias;
        ``mean_offdiag_corr``, ``mean_offdiag_corr_random``; ``bias_curve`` (sensors, length):
        the relative bias of each denoised signal; ``runs``, ``seed``, ``gains``, ``sigma``.

    Raises
    ------
    ValueError
        Bad lengths or values, an empty ``configs`` or a config with unknown options.
    """
    count(runs, "runs", minimum=2)
    g = as_array(gains, "gains", ndim=1)
    sig = as_array(sigma, "sigma", ndim=1)
    if g.size < 2 or np.any(g <= 0):
        raise ValueError(f"gains must hold >= 2 positive gains, got {g}")
    if sig.shape != g.shape or np.any(sig <= 0):
        raise ValueError(f"sigma must hold {g.size} positive SDs, got {sig}")
    count(seed, "seed", minimum=0)
    if isinstance(configs, (str, dict)) or not hasattr(configs, "__len__") or len(configs) == 0:
        raise ValueError("configs must be a non-empty sequence of dicts")
    for c in configs:
        config_label(c)
    S = signal(length)
    truth = g[:, None] * S
    noise = np.random.default_rng(seed).normal(size=(runs, g.size, length)) * sig[:, None]
    X = truth + noise
    raw = np.mean(noise**2, axis=-1)
    labels, err = [], {}
    for i, cfg in enumerate(configs):
        kw = {k: cfg[k] for k in ("wavelet", "level", "threshold", "mode")}
        df = wv.reconstruct(X, normaliser="max", **kw)
        ff = wv.reconstruct(X, normaliser="max", order="fuse-first", **kw)
        lab = config_label(cfg)
        labels.append(lab)
        err[lab] = {"raw": raw, "denoised": np.mean((df.denoised - truth) ** 2, axis=-1),
                    "denoise-first": np.mean((df.reconstructed - truth) ** 2, axis=-1),
                    "fuse-first": np.mean((ff.reconstructed - truth) ** 2, axis=-1)}
        if i == 0:
            rel = (df.denoised - truth) / g[:, None]          # (runs, sensors, length)
            bias = rel.mean(axis=0)                            # (sensors, length)
            mse_rel = np.mean(rel**2, axis=(0, 2))
            bias_share = np.mean(bias**2, axis=-1) / mse_rel
            relr = (df.reconstructed - truth) / g[:, None]
            bias_r = relr.mean(axis=0)
            bias_share_rec = np.mean(bias_r**2, axis=-1) / np.mean(relr**2, axis=(0, 2))
            flat = np.moveaxis(rel, 1, 0).reshape(g.size, -1)
            corr = np.corrcoef(flat)
            flat_r = np.moveaxis(rel - bias[None], 1, 0).reshape(g.size, -1)
            corr_r = np.corrcoef(flat_r)
    off = ~np.eye(g.size, dtype=bool)
    return {"labels": labels, "err": err, "bias_share": bias_share, "bias_share_rec": bias_share_rec,
            "corr": corr, "corr_random": corr_r, "mean_offdiag_corr": float(corr[off].mean()),
            "mean_offdiag_corr_random": float(corr_r[off].mean()), "bias_curve": bias,
            "runs": int(runs), "seed": int(seed), "gains": g, "sigma": sig, "configs": [dict(c) for c in configs]}


def variance_study(
    length: int = 1024,
    runs: int = 100,
    gains: Sequence[float] = (1.0, 1.5, 0.8, 2.0),
    sigma: Sequence[float] = (0.05, 0.1, 0.2, 0.4),
    seed: int = 2601,
    window: int = 64,
    readings: Sequence[str] = wv.VARIANCES,
) -> dict[str, Any]:
    r"""The §2.6 reconstruction under each reading of its step 3 (the variance behind the weights).

    The lecture estimates each sensor's variance "recursively by an MA model"; the readings are
    those of :func:`fusion.readings.wavelet.variance_estimates` (default wavelet: db4, 4 levels,
    soft universal threshold; maximum normaliser; the lecture's order). Same case and noise as
    :func:`mechanism_study` (same seed).

    Parameters
    ----------
    length, runs : int
        Samples per signal I (>= 16) and Monte-Carlo runs (>= 2).
    gains, sigma : sequence of float
        Sensor gains and noise SDs (> 0, same length).
    seed : int
        Seed of the noise.
    window : int
        Window of the moving-average reading (>= 2 samples).
    readings : sequence of str
        Readings of :data:`fusion.readings.wavelet.VARIANCES`, the first the reference.

    Returns
    -------
    dict
        ``readings``; ``err[reading]``: per-run MSE of each sensor's reconstruction against
        :math:`g_jS`, shape (runs, sensors); ``raw`` and ``denoised`` (the same for every reading);
        ``w_final[reading]``: mean over runs of the weights at the last sample, shape (sensors,);
        ``w_spread[reading]``: mean over runs of the SD along the signal of sensor 1's weight;
        ``w_true``: the inverse-variance weights of the true noise of the normalised signals,
        :math:`\propto (g_j/\sigma_j)^2`; ``window``, ``runs``, ``seed``, ``gains``, ``sigma``.

    Raises
    ------
    ValueError
        Bad lengths or values, an empty or unknown ``readings``.
    """
    count(runs, "runs", minimum=2)
    g = as_array(gains, "gains", ndim=1)
    sig = as_array(sigma, "sigma", ndim=1)
    if g.size < 2 or np.any(g <= 0):
        raise ValueError(f"gains must hold >= 2 positive gains, got {g}")
    if sig.shape != g.shape or np.any(sig <= 0):
        raise ValueError(f"sigma must hold {g.size} positive SDs, got {sig}")
    count(seed, "seed", minimum=0)
    count(window, "window", minimum=2)
    if isinstance(readings, str) or not hasattr(readings, "__len__") or len(readings) == 0:
        raise ValueError("readings must be a non-empty sequence of names")
    for r in readings:
        if r not in wv.VARIANCES:
            raise ValueError(f"readings must be among {wv.VARIANCES}, got {r!r}")
    S = signal(length)
    truth = g[:, None] * S
    noise = np.random.default_rng(seed).normal(size=(runs, g.size, length)) * sig[:, None]
    X = truth + noise
    err: dict[str, np.ndarray] = {}
    w_final: dict[str, np.ndarray] = {}
    w_spread: dict[str, float] = {}
    denoised = None
    for r in readings:
        rec = wv.reconstruct(X, normaliser="max", variance=r, window=window)
        err[r] = np.mean((rec.reconstructed - truth) ** 2, axis=-1)
        w_final[r] = rec.weights.mean(axis=0)
        w1 = rec.weight_path[:, 0, :]
        w_spread[r] = float(np.mean(np.std(w1 - w1[:, -1:], axis=-1)))   # exactly 0 for constant weights
        if denoised is None:
            denoised = np.mean((rec.denoised - truth) ** 2, axis=-1)
    w_true = (g / sig) ** 2 / np.sum((g / sig) ** 2)
    return {"readings": list(readings), "err": err, "raw": np.mean(noise**2, axis=-1), "denoised": denoised,
            "w_final": w_final, "w_spread": w_spread, "w_true": w_true, "window": int(window), "runs": int(runs),
            "seed": int(seed), "gains": g, "sigma": sig}
