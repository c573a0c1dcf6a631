r"""Exact error statistics of a linear time registration (Shi, Suo & Ma 2023; the chapter's analysis).

Every registration of :mod:`fusion.registration.methods` is affine in the measurements (the Kalman gains do not
depend on the data), so a method is its noise-free output plus its responses to unit noise on each sample
(:func:`affine_decomposition`), and its expected mean squared error under white noise follows in closed form
(:func:`expected_mse`).

References
----------
* Shi, J., Suo, X., & Ma, S. (2023). Time registration technology for heterogeneous sensors.
  *Computer Programming Skills & Maintenance*, 2023(4) (in Chinese).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from fusion._frozen import frozen_arrays
from fusion._validation import (MAX_MAGNITUDE, FloatArray, _numeric, allocation, as_array, as_callable, finite_result,
                                argument_copy, loop_work, nonnegative_scalar)

__all__ = ["AffineDecomposition", "affine_decomposition", "expected_mse"]


@dataclass(frozen=True)
@frozen_arrays
class AffineDecomposition:
    """A linear registration as noise-free values plus responses to unit noise.

    Arrays are read-only.

    Attributes
    ----------
    f0 : ndarray, shape (K,)
        Noise-free registered values.
    A : ndarray, shape (K, n)
        Columns are the responses to unit noise on each sample (superposition).
    """

    f0: FloatArray
    A: FloatArray


def _register_values(values: object, shape: tuple[int, ...] | None) -> FloatArray:
    """What ``register`` returned, checked: a finite 1-D array (of ``shape`` after the first call) within the
    magnitude rule (rule 2 of ``fusion._validation``: :func:`expected_mse` squares the values and their differences,
    so a value beyond 1e150 would overflow there); errors name ``register``."""
    v = _numeric(values, "the values returned by register")
    if v.ndim != 1 or not np.all(np.isfinite(v)) or (shape is not None and v.shape != shape):
        what = "a finite 1-D array" if shape is None else "a finite 1-D array of one length"
        raise ValueError(f"register must return {what}, got shape {v.shape}")
    top = float(np.abs(v).max()) if v.size else 0.0
    if top > MAX_MAGNITUDE:
        raise ValueError(f"register returned a value of magnitude {top:.3g}, beyond the representable range "
                         f"(at most {MAX_MAGNITUDE:g})")
    return v


def affine_decomposition(register: Callable[[FloatArray], FloatArray], z0: ArrayLike) -> AffineDecomposition:
    r"""Write a registration that is affine in the samples as :math:`f(z_0 + v) = f(z_0) + A v`.

    Parameters
    ----------
    register : callable
        Maps the samples, shape (n,), to registered values, shape (K,).
    z0 : array_like, shape (n,)
        Noise-free samples.

    Returns
    -------
    AffineDecomposition
        ``f0`` and ``A``.

    Raises
    ------
    ValueError
        ``z0`` so long that its n + 1 calls of ``register`` (each on a copy of n samples) are beyond the work
        budget, or ``A`` beyond the memory budget (rules 9 and 17 of ``fusion._validation``); ``register``
        returning anything but a finite 1-D array of one length, or a value beyond the representable range
        (magnitude above 1e150, rule 2: :func:`expected_mse` squares them).
    """
    as_callable(register, "register")
    base = as_array(z0, "z0", ndim=1)
    loop_work((base.size + 1,), base.size, "z0")  # rule 17: a call of register a sample, each on a copy of z0
    f0 = _register_values(register(argument_copy(base)), None)  # a copy: base is read again (every e below)
    allocation((f0.size, base.size), "z0 and the values returned by register")  # rule 9: A
    A = np.empty((f0.size, base.size))
    for i in range(base.size):
        e = base.copy()
        e[i] += 1.0
        fi = _register_values(register(e), f0.shape)
        A[:, i] = fi - f0
    return AffineDecomposition(f0=f0, A=A)


@finite_result("register, z0, truth_at_query and sigma")
def expected_mse(
    register: Callable[[FloatArray], FloatArray], z0: ArrayLike, truth_at_query: ArrayLike, sigma: float
) -> float:
    r"""Exact expected registration MSE under white noise of standard deviation ``sigma``.

    .. math:: E[\mathrm{MSE}] = \frac1K\sum_k \bigl(b_k^2 + \sigma^2 \lVert a_k\rVert^2\bigr),

    with :math:`b = f(z_0) - x(t_k)` the noise-free error and :math:`a_k` the rows of
    :math:`A` from :func:`affine_decomposition`. Valid when the Kalman filter's noise
    parameters are held fixed while the data vary (its gains do not depend on the data).

    Parameters
    ----------
    register : callable
        Affine map from the samples, shape (n,), to registered values, shape (K,).
    z0 : array_like, shape (n,)
        Noise-free samples (m).
    truth_at_query : array_like, shape (K,)
        True values :math:`x(t_k)` at the registration instants (m).
    sigma : float
        Noise standard deviation (m), >= 0.

    Returns
    -------
    float
        Expected mean squared error in m².

    Raises
    ------
    ValueError
        ``truth_at_query`` of the wrong shape, ``sigma`` negative or not finite, ``z0`` too long or
        ``register`` returning values beyond the representable range (:func:`affine_decomposition`); an
        expected MSE beyond the float range (``sigma`` and the responses in range, their product not).
    """
    dec = affine_decomposition(register, z0)
    f0, A = dec.f0, dec.A
    truth = as_array(truth_at_query, "truth_at_query", nonempty=False)
    if truth.shape != f0.shape:
        raise ValueError(f"truth_at_query must have shape {f0.shape}, got {truth.shape}")
    sigma = nonnegative_scalar(sigma, "sigma")
    b = f0 - truth
    return float(np.mean(b**2 + sigma**2 * np.sum(A**2, axis=1)))
