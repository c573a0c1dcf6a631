"""The values an optimiser's objective returns, checked (rule 3 of :mod:`fusion`'s validation).

Split from ``fusion._validation`` (the house limit of 1000 lines), which the optimisers share: an objective's values of
the wrong shape, NaN, or the infinity that would make the optimum unbounded are refused naming the objective, and an
optimum with no finite value is refused naming it, not the result's field.
"""
from __future__ import annotations

from math import isfinite as _isfinite

import numpy as np

from fusion._limits import MAX_MAGNITUDE
from fusion._validation import FloatArray, _numeric

__all__: list[str] = []


def objective_values(values: object, shape: tuple[int, ...], name: str, infeasible: float = np.inf) -> FloatArray:
    """The values an objective ``name`` returned for candidates of ``shape``, checked (rule 3).

    Parameters
    ----------
    values : object
        What the objective returned.
    shape : tuple of int
        The shape it must have.
    name : str
        The objective's argument name (``"f"``, ``"fitness"``), named in the messages.
    infeasible : float
        The infinity that marks an infeasible point (``inf`` for a minimiser, ``-inf`` for a
        maximiser); the other one would be an unbounded optimum and is refused.

    Returns
    -------
    ndarray
        The values as floats; ``infeasible`` is allowed, NaN and the opposite infinity are not.

    Raises
    ------
    TypeError
        Values that are not real numbers (strings, complex, ...).
    ValueError
        Wrong shape, or NaN.
    """
    what = f"the values returned by {name}"
    v = _numeric(values, what)
    if v.shape != shape:
        raise ValueError(f"{name} returned values of shape {v.shape} for candidates of shape {shape}")
    if np.isnan(v).any():
        raise ValueError(f"{name} returned NaN")
    if (v == -infeasible).any():
        raise ValueError(f"{name} returned {-infeasible}: the optimum would be unbounded")
    return v


def gradient_values(values: object, n: int, name: str) -> FloatArray:
    """The gradient an optimiser's derivative callable ``name`` returned at a point of ``n`` coordinates, checked.

    A gradient must be ``n`` finite real numbers: SLSQP given NaN, an infinity, a scalar or a vector of another
    length stopped at once and its start was returned as the minimiser, and a string, ``None`` or a complex number
    raised scipy's own error (fuzz 53b C5).

    Parameters
    ----------
    values : object
        What the callable returned.
    n : int
        The number of coordinates.
    name : str
        The callable's argument name (``"jac"``), named in the messages.

    Returns
    -------
    ndarray, shape (n,)
        The gradient as floats.

    Raises
    ------
    TypeError
        Values that are not real numbers (strings, complex, ``None``, ...).
    ValueError
        Not of shape (n,), or not finite.
    """
    g = _numeric(values, f"the values returned by {name}")
    if g.shape != (n,):
        raise ValueError(f"{name} returned a gradient of shape {g.shape} for a point of shape ({n},)")
    if not np.isfinite(g).all():
        raise ValueError(f"{name} returned a gradient that is not finite (NaN or infinite)")
    return g


def finite_optimum(value: float, name: str) -> float:
    """Refuse an optimum whose objective value is not finite (rule 3): ``name`` took no finite value.

    Raises
    ------
    ValueError
        If ``value`` is infinite or NaN, or beyond :data:`MAX_MAGNITUDE` in magnitude (the result could not hold
        it): naming the objective ``name``, not the result's field (fuzz 24a T1).
    """
    if not _isfinite(value):
        raise ValueError(f"{name} took no finite value at the points tried (best value {value}): "
                         "the objective is infinite everywhere the optimiser looked")
    if abs(value) > MAX_MAGNITUDE:
        raise ValueError(f"{name} returned a value of magnitude {abs(value):.3g} at its best point, beyond the "
                         f"representable range (at most {MAX_MAGNITUDE:g} in magnitude): rescale the objective")
    return value
