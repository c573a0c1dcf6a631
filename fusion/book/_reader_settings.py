"""One rule for the ``settings`` of every chapter's record readers (fuzz 52 C7): a mapping, of known keys only.

A record reader ``ev_*(settings, *, seed, runs)`` computes a claim record's evidence for one reading of the claim
file (:func:`fusion.book.claims.evaluate`). Before this rule each chapter checked its settings its own way: chapter
01's readers ignored a misspelt key (``{'sensor': (1, 10)}`` gave the halves comparison, ``{'alph': 2.0}`` the
evidence at α = 0.25), chapters 02-04 and 07 refused a non-mapping by a ValueError, chapter 05 by a TypeError, and
chapters 04 and 07 checked the settings only after their studies. :func:`settings_first` is the one check, and
:func:`reads` applies it to a reader before anything else, each reader declaring the keys it reads.

Why a TypeError for a non-mapping: a reader is called with a Python object, never with the file's text. The claim
file's own content is checked when it is loaded (a reading whose settings are not a mapping is refused there, as
the file's error, and :class:`fusion.book.claims.ReadingSpec` refuses a non-mapping ``settings`` by a TypeError);
what reaches a reader as a list or a string comes from a Python caller, and the package's rule for an argument of
the wrong type is a TypeError naming it. A key the reader does not read is a wrong value of a right type: a
ValueError naming ``settings`` and the key, listing the keys it reads.
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Iterable, Mapping
from typing import Any, TypeVar

from fusion._shown import shown

__all__: list[str] = []

_F = TypeVar("_F", bound=Callable[..., Any])


def settings_first(settings: object, allowed: Iterable[str]) -> Mapping[str, Any]:
    """A reader's ``settings`` checked before any study: a mapping (or None, no settings) of keys among ``allowed``.

    Parameters
    ----------
    settings : mapping or None
        A reading's settings (the claim file's ``settings`` of the reading).
    allowed : iterable of str
        The keys the reader reads.

    Returns
    -------
    Mapping
        ``settings`` itself, or an empty dict for None.

    Raises
    ------
    TypeError
        ``settings`` neither a mapping nor None.
    ValueError
        ``settings`` holding a key not in ``allowed`` (a misspelt setting is never silently ignored), named with
        the keys the reader reads.
    """
    if settings is None:
        return {}
    if not isinstance(settings, Mapping):
        raise TypeError(f"settings must be a mapping (a reading's settings) or None, got {type(settings).__name__}")
    keys = tuple(allowed)
    # a key's own text compared, not its __eq__ (fuzz 54a D1: a str subclass equal to everything passed as known)
    unknown = [k for k in settings if not (isinstance(k, str) and str.__str__(k) in keys)]
    if unknown:
        takes = f"only {shown(sorted(keys), 200)}" if keys else "no settings"
        raise ValueError(f"settings: unknown {shown(unknown, 120)} (this record's reader takes {takes})")
    return settings


def reads(*keys: str) -> Callable[[_F], _F]:
    """Decorator: a reader ``fn(settings, *args, **kwargs)`` whose ``settings`` pass :func:`settings_first` with
    ``keys`` before ``fn`` runs (so before any study); the keys are kept as ``fn.settings_keys`` (a frozenset) for
    a check of the claim files' readings without their studies. Signature and docstring kept.

    Parameters
    ----------
    *keys : str
        The settings keys the reader reads.

    Returns
    -------
    callable
        The decorator.
    """
    def decorate(fn: _F) -> _F:
        @functools.wraps(fn)
        def checked(settings: object, *args: Any, **kwargs: Any) -> Any:
            return fn(settings_first(settings, keys), *args, **kwargs)

        checked.settings_keys = frozenset(keys)  # type: ignore[attr-defined]
        return checked  # type: ignore[return-value]
    return decorate
