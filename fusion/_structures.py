"""Shared validation of nested structures and singular systems (issue 35, rules 5 and 12).

Split from :mod:`fusion._validation` (which re-exports every name here) to keep modules short:

* :func:`record` checks a dict read by key, :func:`within` prefixes the errors of a nested entry
  with its path, so that a bad entry deep inside a structure is a ``ValueError``/``TypeError``
  naming the argument, never a ``KeyError`` or ``AttributeError``;
* :func:`singular_system` (and :func:`singular_error` for hot functions that catch inline) turn a
  :class:`numpy.linalg.LinAlgError` from a covariance singular to working precision into a
  ``ValueError`` naming the covariances, and :func:`inverse` does the same for an inverse
  (:func:`psd_factor`, a factor of a validated semidefinite matrix, lives here too);
* :func:`derived` names the arguments a derived quantity comes from when it is refused inside
  (a covariance that a transition matrix makes singular, a signal whose normaliser is zero).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Iterator, Mapping, Sequence
from contextlib import contextmanager

import numpy as np

from fusion._counts import sequence
from fusion._shown import shown


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
    if not extra:  # a set of the allowed keys: linear in the keys (fuzz 42a C10: 5,000 methods took 0.1 s a record)
        allowed = set(required) | set(optional)
        unknown = [k for k in value if k not in allowed]
        if unknown:
            raise ValueError(f"{name} has unknown keys {shown(unknown)} (allowed: {list(required) + list(optional)})")
    return value


def same_keys(value: object, name: str, like: Mapping, like_name: str, *, ordered: bool = False) -> Mapping:
    """A mapping paired with another (rule 12): ``value`` holds exactly the keys of ``like`` (in its order
    when ``ordered``), so that a label of one without its companion in the other is a ValueError naming
    ``name``, never a :class:`KeyError` or a silently dropped entry.

    Parameters
    ----------
    value : object
        The mapping checked (noise SDs by setting, the same labels as the studies).
    name, like_name : str
        Argument names of ``value`` and of ``like`` used in the messages.
    like : Mapping
        The mapping whose keys ``value`` must hold (already checked to be a mapping).
    ordered : bool
        The keys must also come in the same order (a function reading them by position).

    Returns
    -------
    Mapping
        ``value`` unchanged.

    Raises
    ------
    TypeError
        ``value`` not a mapping.
    ValueError
        A key of one missing from the other, or (``ordered``) the keys in another order.
    """
    if not isinstance(value, Mapping):
        raise TypeError(f"{name} must be a dict with the keys of {like_name}, got {type(value).__name__}")
    missing = [k for k in like if k not in value]
    extra = [k for k in value if k not in like]
    if missing or extra:
        raise ValueError(f"{name} must hold exactly the keys of {like_name}: it lacks {missing} and adds {extra}")
    if ordered and list(value) != list(like):
        raise ValueError(f"{name} must hold the keys of {like_name} in the same order, got {list(value)} "
                         f"for {list(like)}")
    return value


def mapping_of(value: object, name: str, what: str, *, values: type | tuple[type, ...] | None = None,
               maker: str = "") -> Mapping:
    """A mapping another function of the package made, read by its items (fuzz 19, class D): a mapping holding at
    least one entry, each value (when ``values`` is given) an instance of ``values``, so that a chapter function
    given another object fails with a TypeError/ValueError naming ``name``, never an AttributeError,
    StopIteration or IndexError from inside.

    Parameters
    ----------
    value : object
        The mapping (studies by key, evidence by record).
    name, what : str
        Argument name, and what one entry is (``"study"``), used in the messages.
    values : type or tuple of type, optional
        The class (classes) of every value.
    maker : str
        The function that makes such a mapping, named in the messages.

    Returns
    -------
    Mapping
        The same object, once checked.

    Raises
    ------
    TypeError
        ``value`` is no mapping, or one of its values is of another class (the message names its key).
    ValueError
        ``value`` holds no entry.
    """
    made = f" (the result of {maker})" if maker else ""
    if not isinstance(value, Mapping):
        raise TypeError(f"{name} must be a mapping (each value a {what}){made}, got {type(value).__name__}")
    if not value:
        raise ValueError(f"{name} must hold at least one {what}{made}, got an empty mapping")
    if values is not None:
        for k, v in value.items():
            if not isinstance(v, values):
                want = values.__name__ if isinstance(values, type) else " or ".join(c.__name__ for c in values)
                raise TypeError(f"{name}[{shown(k)}] must be a {want}{made}, got {type(v).__name__}")
    return value


def records_of(value: object, name: str, keys: tuple[str, ...] = ()) -> list[Mapping]:
    """A sequence of records (mappings read by key, fuzz 19 D22/F16): a list or tuple whose every item is a mapping
    holding ``keys``; TypeError/ValueError naming ``name`` (and the item's position), never an AttributeError.

    Parameters
    ----------
    value : object
        The records (a sequence of mappings, not text).
    name : str
        Argument name used in the messages.
    keys : tuple of str
        Keys every record must hold.

    Returns
    -------
    list of Mapping
        The records.

    Raises
    ------
    TypeError
        Not a sequence (or text), or an item not a mapping.
    ValueError
        A record without one of ``keys``; more than ``fusion._counts.MAX_COUNT`` records, or a ``len()`` that
        disagrees with them.
    """
    if not isinstance(value, Sequence) or isinstance(value, (str, bytes)):
        raise TypeError(f"{name} must be a sequence (a list) of records, got {type(value).__name__}")
    # read once, by the one sequence rule: the records checked are the ones returned (fuzz 57a D1's class), their
    # len() checked against MAX_COUNT before any copy and never trusted to preallocate (fuzz 58a C2: list() of
    # range(10**12), or of a Sequence whose __len__ said 2**60, raised a raw MemoryError)
    records = sequence(value, name)
    for i, r in enumerate(records):
        if not isinstance(r, Mapping):
            raise TypeError(f"{name}[{i}] must be a mapping (a record), got {type(r).__name__}")
        missing = [k for k in keys if k not in r]
        if missing:
            raise ValueError(f"{name}[{i}] lacks the keys {missing}")
    return records


@contextmanager
def within(name: str) -> Iterator[None]:
    """Validate an entry of a nested structure (rule 12): its errors are prefixed with the path ``name``.

    ``with within("scenarios['a']"): covariance(case["own"], ...)`` turns ``own must be ...`` into
    ``scenarios['a']: own must be ...``, so that the message names the argument the caller passed.
    Only :class:`ValueError` and :class:`TypeError` are rewritten (same type and attributes, same traceback cause).
    """
    try:
        yield
    except (ValueError, TypeError) as exc:
        if isinstance(exc, np.linalg.LinAlgError):
            raise ValueError(f"{name}: {exc}") from None
        new = type(exc)(f"{name}: {exc}")
        new.__dict__.update(exc.__dict__)  # e.g. a FewRunsError's runs and minimum, which a caller may rename
        raise new from None


@contextmanager
def derived(names: str, what: str) -> Iterator[None]:
    """Run a computation on a quantity derived from the arguments ``names`` (issue 35, round 3).

    Valid arguments can combine into a derived quantity that an inner step refuses: a transition
    matrix ``F = 0`` and a low-rank ``Q`` make a local covariance singular, an all-zero signal has
    no positive normaliser. The inner step names its own (internal) variable; this turns its
    :class:`ValueError` (:class:`numpy.linalg.LinAlgError` included) into a :class:`ValueError`
    naming the public arguments, ``"F and Q give {what} that is refused: <inner message>"``.
    A :class:`TypeError` (a wrong type is the caller's, and named already) passes unchanged.

    Parameters
    ----------
    names : str
        The public arguments the quantity comes from (``"F, H and Q"``).
    what : str
        The derived quantity (``"a local covariance at step 3"``).
    """
    try:
        yield
    except ValueError as exc:
        verb = "gives" if " and " not in names and "," not in names else "give"
        raise ValueError(f"{names} {verb} {what} that is refused: {exc}") from None


def singular_system(names: str, finite: bool = False) -> Callable[[Callable[..., object]], Callable[..., object]]:
    """Decorate a public function whose covariances are inverted (rule 5), naming them on a singular system.

    The covariance validators refuse a matrix singular to working precision (the rule of
    ``fusion._covariances.SINGULAR_MARGIN``) and keep ill-conditioned but valid input working; a matrix
    computed from valid inputs can still be singular to working precision and make :func:`numpy.linalg.inv`
    fail. The decorated
    function turns that :class:`numpy.linalg.LinAlgError` into a :class:`ValueError` naming ``names``,
    and so, with ``finite``, does a float or float-array result that is not finite (a log-determinant
    of ``-inf``, an inverse that overflows: the same near-singular matrix, caught later); results are
    unchanged otherwise (same call, at most one finiteness check of the result).

    Parameters
    ----------
    names : str
        The arguments whose matrices are inverted (``"P1 and P2"``), named in the message.
    finite : bool
        Also refuse a float result that is not finite (for a function whose result is finite for
        every valid input; not for one that documents ``inf``).
    """
    def wrap(fn: Callable[..., object]) -> Callable[..., object]:
        @functools.wraps(fn)
        def call(*args: object, **kwargs: object) -> object:
            try:
                out = fn(*args, **kwargs)
            except np.linalg.LinAlgError as exc:
                raise singular_error(names, exc) from None
            if finite and ((isinstance(out, float) and not math.isfinite(out)) or (
                    isinstance(out, np.ndarray) and out.dtype.kind == "f" and not np.isfinite(out).all())):
                raise singular_error(names, "the result is not finite")
            return out
        return call
    return wrap


def singular_error(names: str, exc: Exception | str) -> ValueError:
    """The :class:`ValueError` of :func:`singular_system`, for a hot function that catches inline (no wrapper call)."""
    return ValueError(f"{names} give a numerically singular system ({exc}): "
                      "a covariance is singular to working precision")


def psd_factor(S: np.ndarray) -> np.ndarray:
    """A factor ``L`` with ``L @ L.T == S`` of a validated positive-semidefinite matrix.

    The Cholesky factor when ``S`` is positive definite (so results of existing callers do
    not change), otherwise the symmetric square root from the eigen-decomposition.
    """
    try:
        return np.linalg.cholesky(S)
    except np.linalg.LinAlgError:
        lam, V = np.linalg.eigh(S)
        return V * np.sqrt(np.clip(lam, 0.0, None))


def inverse(A: np.ndarray, name: str) -> np.ndarray:
    """``numpy.linalg.inv(A)`` with a ValueError naming ``name`` for a singular or overflowing inverse (rule 5).

    The same numbers as :func:`numpy.linalg.inv` when it succeeds with a finite result.

    Raises
    ------
    ValueError
        If ``A`` is singular to working precision or its inverse is not finite.
    """
    try:
        with np.errstate(all="ignore"):
            Ai = np.linalg.inv(A)
    except np.linalg.LinAlgError:
        raise ValueError(f"{name} give a singular system (the matrix to invert is singular)") from None
    if not np.isfinite(Ai).all():
        raise ValueError(f"{name} give a numerically singular system (the inverse overflows)")
    return Ai
