"""Shared validation of nested structures and singular systems (issue 35, rules 5 and 12).

Split from :mod:`fusion._validation` (which re-exports every name here) to keep modules short:

* :func:`record` checks a dict read by key, :func:`within` prefixes the errors of a nested entry
  with its path, so that a bad entry deep inside a structure is a ``ValueError``/``TypeError``
  naming the argument, never a ``KeyError`` or ``AttributeError``;
* :func:`singular_system` (and :func:`singular_error` for hot functions that catch inline) turn a
  :class:`numpy.linalg.LinAlgError` from a covariance singular to working precision into a
  ``ValueError`` naming the covariances.
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Iterator, Mapping
from contextlib import contextmanager

import numpy as np


def record(value: object, name: str, required: tuple[str, ...], optional: tuple[str, ...] = (),
           *, extra: bool = False) -> Mapping:
    """A dict read by key (rule 12): a mapping holding every ``required`` key.

    Parameters
    ----------
    value : object
        The mapping (an options dict, a scenario entry, a study's result).
    name : str
        Argument name (or path, ``scenarios['a']``) used in the messages.
    required, optional : tuple of str
        Keys that must, and keys that may, be present.
    extra : bool
        Accept other keys (a study's result read for some of its entries); by default an
        unknown key is refused (a misspelt option must not be silently ignored).

    Raises
    ------
    TypeError
        Not a mapping.
    ValueError
        A required key missing, or an unknown key (unless ``extra``).
    """
    if not isinstance(value, Mapping):
        raise TypeError(f"{name} must be a dict with keys {list(required)}, got {type(value).__name__}")
    missing = [k for k in required if k not in value]
    if missing:
        raise ValueError(f"{name} lacks the keys {missing} (it must hold {list(required)})")
    if not extra:
        unknown = [k for k in value if k not in required and k not in optional]
        if unknown:
            raise ValueError(f"{name} has unknown keys {unknown} (allowed: {list(required) + list(optional)})")
    return value


@contextmanager
def within(name: str) -> Iterator[None]:
    """Validate an entry of a nested structure (rule 12): its errors are prefixed with the path ``name``.

    ``with within("scenarios['a']"): covariance(case["own"], ...)`` turns ``own must be ...`` into
    ``scenarios['a']: own must be ...``, so that the message names the argument the caller passed.
    Only :class:`ValueError` and :class:`TypeError` are rewritten (same type, same traceback cause).
    """
    try:
        yield
    except (ValueError, TypeError) as exc:
        if isinstance(exc, np.linalg.LinAlgError):
            raise ValueError(f"{name}: {exc}") from None
        raise type(exc)(f"{name}: {exc}") from None


def singular_system(names: str) -> Callable[[Callable[..., object]], Callable[..., object]]:
    """Decorate a public function whose covariances are inverted (rule 5), naming them on a singular system.

    The covariance validators accept any matrix whose Cholesky factorisation succeeds, which keeps
    ill-conditioned but valid input (condition numbers up to ``1e16``, documented and tested) working; a
    matrix that is singular to working precision (e.g. all entries equal, a rank-one matrix whose last
    pivot is rounding noise) can still pass and then make :func:`numpy.linalg.inv` fail. The decorated
    function turns that :class:`numpy.linalg.LinAlgError` into a :class:`ValueError` naming ``names``;
    results are unchanged otherwise (same call, no extra work).

    Parameters
    ----------
    names : str
        The arguments whose matrices are inverted (``"P1 and P2"``), named in the message.
    """
    def wrap(fn: Callable[..., object]) -> Callable[..., object]:
        @functools.wraps(fn)
        def call(*args: object, **kwargs: object) -> object:
            try:
                return fn(*args, **kwargs)
            except np.linalg.LinAlgError as exc:
                raise singular_error(names, exc) from None
        return call
    return wrap


def singular_error(names: str, exc: Exception) -> ValueError:
    """The :class:`ValueError` of :func:`singular_system`, for a hot function that catches inline (no wrapper call)."""
    return ValueError(f"{names} give a numerically singular system ({exc}): "
                      "a covariance is singular to working precision")
