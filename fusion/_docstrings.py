"""Numpydoc sections that several functions share, written once (:func:`with_sections`)."""

from __future__ import annotations

import inspect
import textwrap
from collections.abc import Callable
from typing import Any, TypeVar

F = TypeVar("F", bound=Callable[..., Any])

__all__ = ["with_sections"]

#: Numpydoc section titles that follow Returns, in order (a Returns section given goes before the first of them).
_AFTER_RETURNS = ("Raises", "Warns", "See Also", "Notes", "References", "Examples")


def _title_at(lines: list[str], titles: tuple[str, ...]) -> int | None:
    """Index of the first line that is one of ``titles`` underlined with dashes, or None."""
    for i, line in enumerate(lines[:-1]):
        if line in titles and set(lines[i + 1]) == {"-"}:
            return i
    return None


def _insert(lines: list[str], at: int | None, block: list[str]) -> list[str]:
    """``block`` (a section and a blank line) before line ``at``, or at the end after a blank line."""
    if at is None:
        return [*lines, "", *block[:-1]]
    return [*lines[:at], *block, *lines[at:]]


def with_sections(parameters: str = "", returns: str = "", references: str = "") -> Callable[[F], F]:
    """A decorator that completes a function's docstring with numpydoc entries several functions share.

    Parameters
    ----------
    parameters : str
        Parameters entries (``name : type`` lines, each description indented by four spaces), put first in the
        docstring's Parameters section; a Parameters section is made for them (before Returns, or whatever section
        comes first) if the docstring has none.
    returns : str
        The Returns section's entries, put before Raises, See Also, Notes, References or Examples (or at the end);
        the docstring must then have no Returns section of its own.
    references : str
        The References section's entries, put before Examples (or at the end); the docstring must then have no
        References section of its own.

    Returns
    -------
    callable
        The decorator: it sets the function's ``__doc__`` (dedented) and returns the function itself.

    Raises
    ------
    ValueError
        If every text is empty, or ``returns`` (``references``) is given for a docstring that has a Returns
        (References) section (raised when the decorator is applied).
    """
    if not (parameters.strip() or returns.strip() or references.strip()):
        raise ValueError("parameters: give Parameters, Returns or References entries (every text is empty)")
    params, rets, refs = (textwrap.dedent(t).strip("\n").splitlines() for t in (parameters, returns, references))

    def decorate(fn: F) -> F:
        lines = inspect.cleandoc(fn.__doc__ or "").splitlines()
        if params:
            at = _title_at(lines, ("Parameters",))
            if at is not None:
                lines = [*lines[:at + 2], *params, *lines[at + 2:]]
            else:
                first = _title_at(lines, ("Returns", "Yields", *_AFTER_RETURNS))
                lines = _insert(lines, first, ["Parameters", "----------", *params, ""])
        for name, title, entries, before in (("returns", "Returns", rets, _AFTER_RETURNS),
                                             ("references", "References", refs, ("Examples",))):
            if entries:
                if _title_at(lines, (title,)) is not None:
                    raise ValueError(f"{name}: the docstring of {fn.__name__} has a {title} section of its own")
                lines = _insert(lines, _title_at(lines, before), [title, "-" * len(title), *entries, ""])
        fn.__doc__ = "\n".join(lines) + "\n"
        return fn

    return decorate
