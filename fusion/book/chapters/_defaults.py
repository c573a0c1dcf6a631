"""Refusals of a default the caller never passed, named by the caller's argument (fuzz 34b D2).

A chapter function with a default index, label, count or window (``table_mechanism(m, labels=(0, 6))``,
``figure_26(e, sensor=3)``, ``figure_22a(s, n=3)``) checks it against the study it is given. A valid study at other
settings (fewer settings, sensors or samples) does not fit the default, and the check's refusal named the default's
parameter ("labels[1] must be an index below 1, got 6"), which the caller never passed. :func:`study_defaults`
names the study instead, and which default does not fit it.
"""

from __future__ import annotations

import functools
import inspect
import re
from collections.abc import Callable
from typing import Any, TypeVar

from fusion._shown import shown

__all__: list[str] = []  # private module: nothing public (study_defaults is imported by the chapters)

F = TypeVar("F", bound=Callable[..., Any])


def study_defaults(study: str, *names: str) -> Callable[[F], F]:
    """Decorator: a ValueError naming a parameter in ``names`` that the caller did not pass is raised naming ``study``.

    Parameters
    ----------
    study : str
        The parameter holding the study the defaults are checked against (``"m"``, ``"e"``, ``"s"``).
    *names : str
        The parameters whose defaults a valid study may not fit.

    Returns
    -------
    callable
        The decorator. A call that passes the parameter itself keeps the check's own refusal (it names the
        caller's argument); only a default left in place is re-raised as "``study`` does not fit the default
        ``name`` = ...", the check's message kept.
    """
    def decorate(fn: F) -> F:
        sig = inspect.signature(fn)
        defaults = {n: sig.parameters[n].default for n in names}

        @functools.wraps(fn)
        def wrapper(*args: Any, **kwargs: Any) -> Any:
            try:
                return fn(*args, **kwargs)
            except ValueError as exc:
                if type(exc) is not ValueError:
                    raise
                try:
                    passed = sig.bind(*args, **kwargs).arguments   # without the defaults: what the caller gave
                except TypeError:
                    raise exc from None
                message = str(exc)
                for name in names:
                    if name not in passed and re.match(rf"{re.escape(name)}(?!\w)", message):
                        raise ValueError(f"{study} does not fit {fn.__name__}'s default {name} = "
                                         f"{shown(defaults[name], 60)} ({message}): pass {name} fitting {study}") from exc
                raise
        return wrapper  # type: ignore[return-value]
    return decorate
