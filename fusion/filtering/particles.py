r"""Bootstrap particle filters for range-bearing sensors (source 004, step B), vectorised.

Nearly-constant-velocity target :math:`[x, \dot x, y, \dot y]`; a sensor at :math:`s` measures
:math:`z = [\lVert p - s\rVert, \operatorname{atan2}(p_y - s_y, p_x - s_x)] + v`,
:math:`v \sim N(0, \mathrm{diag}(\sigma_r^2, \sigma_\theta^2))`.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from fusion._validation import (
    FloatArray,
    _numeric,
    as_array,
    as_callable,
    as_rng,
    as_semidefinite,
    as_weights,
    positive_scalar,
    psd_factor,
)

__all__ = ["ncv_model", "range_bearing", "log_likelihood", "systematic_resample", "bootstrap_step", "effective_sample_size",
           "weighted_moments", "regularise"]


def ncv_model(T: float, q: float) -> tuple[FloatArray, FloatArray]:
    r"""NCV transition and process covariance :math:`q\,I_2\otimes[[T^3/3, T^2/2],[T^2/2, T]]`."""
    T = positive_scalar(T, "T")
    q = positive_scalar(q, "q")
    F1 = np.array([[1.0, T], [0.0, 1.0]])
    Q1 = q * np.array([[T**3 / 3, T**2 / 2], [T**2 / 2, T]])
    return np.kron(np.eye(2), F1), np.kron(np.eye(2), Q1)


def range_bearing(states: ArrayLike, sensor: ArrayLike) -> FloatArray:
    """Noise-free range (m) and bearing (rad) of states (…, 4) from a sensor position (2,).

    A state exactly on the sensor has range 0 and, by the ``arctan2`` convention, bearing 0:
    the bearing is undefined there (documented, not refused: it has probability zero for
    particles, and the likelihood stays finite).
    """
    s = as_array(states, "states")
    if s.ndim < 1 or s.shape[-1] != 4:
        raise ValueError(f"states must have shape (..., 4) (x, vx, y, vy), got {s.shape}")
    sensor = as_array(sensor, "sensor", shape=(2,))
    return _range_bearing(s, sensor)


def _range_bearing(s: FloatArray, sensor: FloatArray) -> FloatArray:
    dx = s[..., 0] - sensor[0]
    dy = s[..., 2] - sensor[1]
    return np.stack([np.hypot(dx, dy), np.arctan2(dy, dx)], axis=-1)


def log_likelihood(particles: ArrayLike, z: ArrayLike, sensor: ArrayLike, sigma_r: float, sigma_theta: float) -> FloatArray:
    """Log-likelihood of one range-bearing measurement for each particle (bearing wrapped).

    ``particles`` (Q, 4), ``z`` (2,) = (range, bearing), ``sensor`` (2,), noise standard
    deviations ``sigma_r`` (m) and ``sigma_theta`` (rad) finite and positive.
    """
    x = as_array(particles, "particles", shape=(None, 4))
    z = as_array(z, "z", shape=(2,))
    sigma_r = positive_scalar(sigma_r, "sigma_r")
    sigma_theta = positive_scalar(sigma_theta, "sigma_theta")
    h = range_bearing(x, sensor)
    dr = (z[0] - h[:, 0]) / sigma_r
    db = np.angle(np.exp(1j * (z[1] - h[:, 1]))) / sigma_theta
    return -0.5 * (dr**2 + db**2)


def _normalised(weights: ArrayLike, name: str = "weights") -> FloatArray:
    """Finite, non-negative 1-D weights summing to one (within 1e-6)."""
    w = as_weights(weights, name)
    if abs(w.sum() - 1.0) > 1e-6:
        raise ValueError(f"{name} must be normalised (sum to one), got sum {w.sum()!r}")
    return w


def systematic_resample(weights: ArrayLike, rng: np.random.Generator) -> FloatArray:
    """Indices of a systematic resampling of normalised weights (finite, >= 0, summing to one)."""
    w = _normalised(weights)
    as_rng(rng)
    n = w.size
    positions = (rng.uniform() + np.arange(n)) / n
    return np.minimum(np.searchsorted(np.cumsum(w), positions), n - 1)


def weighted_moments(x: ArrayLike, w: ArrayLike) -> tuple[FloatArray, FloatArray]:
    r"""Mean (d,) and covariance (d, d) of particles ``x`` (Q, d) with normalised weights ``w`` (Q,).

    .. math:: \hat x = \sum_q w_q x^{(q)}, \qquad \hat P = \sum_q w_q (x^{(q)} - \hat x)(x^{(q)} - \hat x)^\top
    """
    xx = as_array(x, "x", ndim=2)
    ww = _normalised(w, "w")
    if ww.shape != (xx.shape[0],):
        raise ValueError(f"x must be (Q, d) and w (Q,), got {xx.shape} and {ww.shape}")
    mean = ww @ xx
    d = xx - mean
    cov = d.T @ (d * ww[:, None])
    return mean, 0.5 * (cov + cov.T)


def regularise(particles: ArrayLike, cov: ArrayLike, rng: np.random.Generator) -> FloatArray:
    r"""Regularised resampling: jitter resampled particles with a Gaussian kernel (Musso et al. 2001).

    .. math:: x^{(q)} \leftarrow x^{(q)} + h\,\hat P^{1/2}\xi^{(q)}, \qquad
              h = \Bigl(\frac{4}{Q(d+2)}\Bigr)^{1/(d+4)},

    :math:`\hat P` the weighted covariance before resampling and :math:`h` the optimal
    bandwidth of a Gaussian kernel. Without it a bootstrap filter whose first update keeps a
    handful of distinct particles never recovers their diversity (chapter 04 shows it).

    Parameters
    ----------
    particles : (Q, d) resampled, equally weighted
    cov : (d, d) symmetric positive semi-definite; a tiny diagonal floor is added
    """
    x = as_array(particles, "particles", ndim=2)
    as_rng(rng)
    P = _numeric(cov, "cov")
    if P.shape != (x.shape[1], x.shape[1]):
        raise ValueError(f"particles must be (Q, d) and cov (d, d), got {x.shape} and {P.shape}")
    P = as_semidefinite(P, x.shape[1], name="cov")
    n, d = x.shape
    h = (4.0 / (n * (d + 2))) ** (1.0 / (d + 4))
    floor = 1e-9 * max(float(np.trace(P)) / d, 1e-12)
    L = np.linalg.cholesky(0.5 * (P + P.T) + floor * np.eye(d))
    return x + h * rng.standard_normal(x.shape) @ L.T


def effective_sample_size(weights: ArrayLike) -> float:
    """:math:`1/\\sum w^2` for normalised weights (between 1 and the number of weights)."""
    w = _normalised(weights)
    return float(1.0 / np.sum(w**2))


def bootstrap_step(
    particles: ArrayLike,
    F: ArrayLike,
    Q: ArrayLike,
    loglik: FloatArray,
    rng: np.random.Generator,
    predict: bool = True,
) -> tuple[FloatArray, FloatArray]:
    """Propagate equally weighted particles (optional) and weight them by a log-likelihood.

    Parameters
    ----------
    particles : (Q, d) equally weighted particles.
    F, Q : (d, d) transition and process covariance (positive semidefinite).
    loglik : callable (Q, d) -> (Q,)

    Returns
    -------
    particles : (Q, d)
    weights : (Q,), normalised

    Raises
    ------
    ValueError
        Bad particles, ``F`` or ``Q``; a log-likelihood of the wrong shape, containing NaN or
        +inf, or ``-inf`` for every particle (no particle explains the measurement: the weights
        would be 0/0).
    """
    x = as_array(particles, "particles", ndim=2)
    as_callable(loglik, "loglik")
    as_rng(rng)
    if predict:
        d = x.shape[1]
        Fa = as_array(F, "F", shape=(d, d))
        Qa = as_semidefinite(Q, d, name="Q")
        L = psd_factor(Qa)
        x = x @ Fa.T + rng.standard_normal(x.shape) @ L.T
    lw = np.asarray(loglik(x), dtype=float)
    if lw.shape != (x.shape[0],):
        raise ValueError(f"loglik must return shape ({x.shape[0]},), got {lw.shape}")
    if np.isnan(lw).any() or np.isposinf(lw).any():
        raise ValueError("loglik returned NaN or +inf")
    if not np.isfinite(lw.max()):
        raise ValueError("loglik is -inf for every particle: no particle explains the measurement")
    w = np.exp(lw - lw.max())
    return x, w / w.sum()
