"""Simulated thermocouple bank of source 001 (Figs. 1-4) and its Monte-Carlo study.

The source simulates ten thermocouples measuring a furnace at 900 °C, 100 samples each,
"with ten groups of normal random numbers", and a failure in which sensors 4 and 10 get
biases of 4 and 8 °C on samples 50-80. It does not give the noise levels; they are a
parameter here and the chapter states and varies its choice.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike

from fusion._validation import FloatArray, as_array, as_reading_rows, as_rng, count, positive_scalar, scalar
from fusion.readings.fusion_set import fuse_epochs

__all__ = [
    "DEFAULT_SIGMAS",
    "simulate",
    "inject_failure",
    "absolute_errors",
    "monte_carlo",
    "best_linear_abs_error",
]

#: Noise standard deviations (°C) of the ten simulated thermocouples used by default:
#: evenly spaced from 0.5 to 2.0 °C (our choice; the source gives none).
DEFAULT_SIGMAS: FloatArray = np.linspace(0.5, 2.0, 10)


def _sigmas(sigma: ArrayLike, n_sensors: int) -> FloatArray:
    s = np.broadcast_to(np.asarray(sigma, dtype=float), (n_sensors,)).copy()
    if not np.all(np.isfinite(s)) or np.any(s <= 0):
        raise ValueError("sigma must be finite and positive for every sensor")
    return s


def simulate(
    rng: np.random.Generator,
    n_samples: int = 100,
    sigma: ArrayLike = DEFAULT_SIGMAS,
    truth: float = 900.0,
    n_runs: int | None = None,
    n_sensors: int = 10,
) -> FloatArray:
    """Draw thermocouple readings :math:`s_i(t) = X + v_i(t)`, :math:`v_i \\sim N(0, \\sigma_i^2)`.

    Parameters
    ----------
    rng : numpy.random.Generator
        Source of randomness (pass a seeded generator for reproducibility).
    n_samples : int
        Number of sampling instants (epochs).
    sigma : array_like, shape (n_sensors,) or scalar
        Noise standard deviation of each sensor, °C (a scalar applies to all).
    truth : float
        True temperature :math:`X`, °C.
    n_runs : int, optional
        If given, draw that many independent runs at once.
    n_sensors : int
        Number of sensors (10 in the source); must match ``sigma`` if it is an array.

    Returns
    -------
    ndarray, shape (n_samples, n_sensors) or (n_runs, n_samples, n_sensors)
        Readings in °C.
    """
    as_rng(rng)
    n_sensors = count(n_sensors, "n_sensors")
    n_samples = count(n_samples, "n_samples")
    truth = scalar(truth, "truth")
    sig_in = as_array(sigma, "sigma")
    if sig_in.ndim > 1 or (sig_in.ndim == 1 and sig_in.size != n_sensors):
        raise ValueError(f"sigma must be a scalar or have n_sensors = {n_sensors} entries, got shape {sig_in.shape}")
    sig = _sigmas(sig_in, n_sensors)
    if n_samples < 1:
        raise ValueError(f"n_samples must be at least 1, got {n_samples}")
    shape: tuple[int, ...] = (n_samples, sig.size)
    if n_runs is not None:
        n_runs = count(n_runs, "n_runs")
        shape = (n_runs, *shape)
    return truth + rng.standard_normal(shape) * sig


def inject_failure(
    z: ArrayLike,
    sensors: Sequence[int] = (4, 10),
    samples: tuple[int, int] = (50, 80),
    biases: Sequence[float] = (4.0, 8.0),
) -> FloatArray:
    """Add a constant bias to some sensors on a window of samples (source 001, Fig. 3).

    Parameters
    ----------
    z : array_like, shape (..., n_samples, n_sensors)
        Readings (a copy is returned; ``z`` is not modified).
    sensors : sequence of int
        **1-based** sensor numbers, as in the source.
    samples : (int, int)
        First and last **1-based** sample numbers, inclusive (50-80 is 31 samples).
    biases : sequence of float
        Bias added to each sensor in ``sensors``, °C.

    Returns
    -------
    ndarray
        Same shape as ``z``.
    """
    out = np.array(as_array(z, "z"), dtype=float, copy=True)
    if out.ndim < 2:
        raise ValueError(f"z must have shape (..., n_samples, n_sensors), got {out.shape}")
    n_samples, n_sensors = out.shape[-2:]
    if len(sensors) != len(biases):
        raise ValueError("sensors and biases must have the same length")
    if isinstance(samples, (str, bytes)) or np.ndim(samples) != 1 or len(samples) != 2:
        raise TypeError(f"samples must be a pair (first, last) of sample numbers, got {samples!r}")
    first, last = count(samples[0], "samples[0]"), count(samples[1], "samples[1]")
    for nm, seq in (("sensors", sensors), ("biases", biases)):
        if isinstance(seq, (str, bytes)) or np.ndim(seq) != 1:
            raise TypeError(f"{nm} must be a sequence of numbers, got {seq!r}")
    if not (1 <= first <= last <= n_samples):
        raise ValueError(f"samples {samples} outside 1..{n_samples}")
    for sensor, bias in zip(sensors, biases):
        if not (1 <= sensor <= n_sensors):
            raise ValueError(f"sensor {sensor} outside 1..{n_sensors}")
        if not np.isfinite(bias):
            raise ValueError("biases must be finite")
        out[..., first - 1 : last, sensor - 1] += bias
    return out


def absolute_errors(
    z: ArrayLike, methods: dict[str, dict[str, object]], truth: float = 900.0
) -> dict[str, FloatArray]:
    """Absolute error :math:`|\\hat x(t) - X|` of each fusion method at every epoch.

    Parameters
    ----------
    z : array_like, shape (..., n_sensors)
        Readings; all leading axes are epochs.
    methods : dict
        Label -> ``{"method": name, **options}`` for :func:`fusion.readings.fuse_epochs`.
    truth : float
        True value, °C.

    Returns
    -------
    dict of str to ndarray
        Label -> errors with the leading shape of ``z``.
    """
    arr = as_array(z, "z")
    if arr.ndim < 1:
        raise ValueError(f"z must have a sensor axis, got shape {arr.shape}")
    truth = scalar(truth, "truth")
    if not isinstance(methods, dict):
        raise TypeError(f"methods must be a dict label -> options, got {type(methods).__name__}")
    flat = as_reading_rows(arr.reshape(-1, arr.shape[-1]), "z")
    out: dict[str, FloatArray] = {}
    for label, spec in methods.items():
        spec = dict(spec)
        name = str(spec.pop("method"))
        values = fuse_epochs(flat, name, **spec).values
        out[label] = np.abs(values - truth).reshape(arr.shape[:-1])
    return out


def monte_carlo(
    seed: int,
    n_runs: int,
    methods: dict[str, dict[str, object]],
    sigma: ArrayLike = DEFAULT_SIGMAS,
    n_samples: int = 100,
    failure: dict[str, object] | None = None,
    truth: float = 900.0,
    n_sensors: int = 10,
) -> dict[str, FloatArray]:
    """Repeat the source's experiment over ``n_runs`` independent draws.

    Parameters
    ----------
    seed : int
        Seed of the :class:`numpy.random.Generator` (PCG64).
    n_runs : int
        Number of independent runs.
    methods : dict
        As in :func:`absolute_errors`.
    sigma, n_samples, truth
        As in :func:`simulate`.
    failure : dict, optional
        Keyword arguments of :func:`inject_failure` (``{}`` for the source's failure).

    Returns
    -------
    dict of str to ndarray, each of shape (n_runs, n_samples)
        Absolute errors, °C.
    """
    n_runs = count(n_runs, "n_runs")
    seed = count(seed, "seed", minimum=0)
    if not isinstance(methods, dict):
        raise TypeError(f"methods must be a dict label -> options, got {type(methods).__name__}")
    rng = np.random.default_rng(seed)
    z = simulate(rng, n_samples=n_samples, sigma=sigma, truth=truth, n_runs=n_runs, n_sensors=n_sensors)
    if failure is not None:
        z = inject_failure(z, **failure)  # type: ignore[arg-type]
    return absolute_errors(z, methods, truth=truth)


def best_linear_abs_error(sigma: ArrayLike, n_sensors: int = 10) -> float:
    r"""Expected absolute error of the best unbiased fusion of independent Gaussian readings.

    With known variances the inverse-variance weighted mean is the minimum-variance
    unbiased estimator (it attains the Cramér-Rao bound),
    :math:`\sigma_\star^2 = (\sum_i \sigma_i^{-2})^{-1}`, and its error is
    :math:`N(0, \sigma_\star^2)`, so :math:`E|\hat x - X| = \sigma_\star\sqrt{2/\pi}`.
    No unbiased method that fuses one epoch at a time can do better on average, in
    mean-square terms, without a failure.

    Parameters
    ----------
    sigma : array_like, shape (n_sensors,) or scalar
        Noise standard deviations, °C.
    n_sensors : int
        Number of sensors when ``sigma`` is a scalar.

    Returns
    -------
    float
        Expected absolute error, °C.
    """
    n_sensors = count(n_sensors, "n_sensors")
    sig_in = as_array(sigma, "sigma", ndim=(0, 1))
    sig = _sigmas(sig_in, sig_in.size if sig_in.ndim == 1 else n_sensors)
    sigma_star = 1.0 / np.sqrt(np.sum(sig**-2.0))
    return float(sigma_star * np.sqrt(2.0 / np.pi))
