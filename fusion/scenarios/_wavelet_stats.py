"""The bias and correlation statistics of ``fusion.scenarios.wavelet_sensors.mechanism_study``, accumulated block by
block (moved out of that module, at its 1,000-line limit)."""

from __future__ import annotations

import numpy as np


def _accumulate_rec(sl: slice, est: dict[str, np.ndarray], truth: np.ndarray, g: np.ndarray,
                    acc: dict[str, np.ndarray]) -> None:
    """First-pass sums of the reconstruction's relative errors (for its bias share)."""
    rel = (est["denoise-first"] - truth) / g[:, None]
    acc["sum"] += rel.sum(axis=0)
    acc["sq"] += np.sum(rel**2, axis=(0, 2))


def _error_stats(den: np.ndarray, rec_acc: dict[str, np.ndarray], truth: np.ndarray, g: np.ndarray,
                 blocks: list[slice]) -> dict[str, np.ndarray | float]:
    """Bias and cross-sensor correlation of the relative errors (Y − gS)/g, accumulated block by block.

    ``den`` holds the denoised signals of every run; ``rec_acc`` the sums of the reconstruction's relative
    errors and of their squares (:func:`_accumulate_rec`). The correlations pool runs and samples, as
    ``numpy.corrcoef`` of the flattened errors would.
    """
    R_, n, size = den.shape
    dsum, dsq = np.zeros((n, size)), np.zeros(n)
    S, s1 = np.zeros((n, n)), np.zeros(n)
    for sl in blocks:
        rel = (den[sl] - truth) / g[:, None]
        dsum += rel.sum(axis=0)
        dsq += np.sum(rel**2, axis=(0, 2))
        S += np.einsum("rjn,rkn->jk", rel, rel)
        s1 += rel.sum(axis=(0, 2))
    N = R_ * size
    bias, bias_rec = dsum / R_, rec_acc["sum"] / R_
    cov = (S - np.outer(s1, s1) / N) / (N - 1)
    cov_r = (S - R_ * bias @ bias.T) / (N - 1)          # after removing each sensor's bias (its pooled mean is 0)
    corr = cov / np.sqrt(np.outer(np.diag(cov), np.diag(cov)))
    corr_r = cov_r / np.sqrt(np.outer(np.diag(cov_r), np.diag(cov_r)))
    off = ~np.eye(n, dtype=bool)
    return {"bias_share": np.mean(bias**2, axis=-1) / (dsq / N),
            "bias_share_rec": np.mean(bias_rec**2, axis=-1) / (rec_acc["sq"] / N),
            "corr": corr, "corr_random": corr_r, "mean_offdiag_corr": float(corr[off].mean()),
            "mean_offdiag_corr_random": float(corr_r[off].mean()), "bias_curve": bias,
            "rms_bias": np.sqrt(np.mean(bias**2, axis=-1)), "rms_bias_rec": np.sqrt(np.mean(bias_rec**2, axis=-1))}
