"""Draws from and moments of the mixtures of :mod:`fusion.estimates.chernoff.mixture` (moved out of it: its size)."""

from __future__ import annotations

import numpy as np

from fusion._validation import FloatArray
from fusion.estimates.mixtures import _dot, _matvec


def _sample_mixture(w: FloatArray, mu: FloatArray, chol: FloatArray, rng: np.random.Generator, n: int) -> FloatArray:
    """``n`` draws (n, d) from one mixture with weights ``w`` (M,) (zeros skipped), means, Cholesky factors."""
    kept = np.flatnonzero(w > 0)
    lab = kept[rng.choice(kept.size, size=n, p=w[kept])]
    z = rng.standard_normal((n, mu.shape[-1]))
    x = mu[lab]
    # per component (fuzz 58b C2: ``chol[lab]``, an (n, d, d) array, was a raw MemoryError of 6.7 GiB for 10**6 draws
    # of dimension 30), as gm_sample: the same elementwise products row by row, so the same bits as the stacked one
    order = np.argsort(lab, kind="stable")
    drawn, starts = np.unique(lab[order], return_index=True)  # the components drawn, at most n of them
    for k, rows in zip(drawn.tolist(), np.split(order, starts[1:])):
        x[rows] += _matvec(chol[k], z[rows])
    return x


def _mixture_mean(w: FloatArray, mu: FloatArray) -> FloatArray:
    """Mean (B, d) of mixtures with weights (B, M) and means (B, M, d), summed in a fixed order."""
    return _dot(np.swapaxes(mu, 1, 2), w[:, None, :])


def _moments_batch(x: FloatArray, w: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Weighted mean (B, d) and covariance (B, d, d) of points (B, R, d) with normalised weights (B, R)."""
    mean = np.matmul(w[:, None, :], x)[:, 0]
    dx = x - mean[:, None, :]
    cov = np.matmul(np.swapaxes(dx, 1, 2), dx * w[..., None])
    return mean, 0.5 * (cov + np.swapaxes(cov, 1, 2))
