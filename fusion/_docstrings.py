"""Numpydoc text that several functions share, written once.

Two decorators complete a function's docstring, so that the API page, ``help()`` and the docstring tests read
the whole text: :func:`with_sections` adds Parameters, Returns, Raises or References entries given at the decoration;
:class:`ParameterDocs` keeps a module's shared parameter entries, and each function names the ones it takes
(``@PARAMS("s")``), in the order of its signature.

A private module (no ``__all__``): the package's own tool for writing its docstrings, not part of its API.
"""

from __future__ import annotations

import inspect
import re
import textwrap
from collections.abc import Callable, Mapping
from typing import Any, TypeVar

F = TypeVar("F", bound=Callable[..., Any])


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


def with_sections(parameters: str = "", returns: str = "", references: str = "", raises: str = "") -> Callable[[F], F]:
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
    raises : str
        The Raises section's entries, put after Returns, before Warns, See Also, Notes, References or Examples (or
        at the end); the docstring must then have no Raises section of its own.

    Returns
    -------
    callable
        The decorator: it sets the function's ``__doc__`` (dedented) and returns the function itself.

    Raises
    ------
    ValueError
        If every text is empty, or ``returns`` (``references``, ``raises``) is given for a docstring that has a
        Returns (References, Raises) section (raised when the decorator is applied).
    """
    if not (parameters.strip() or returns.strip() or references.strip() or raises.strip()):
        raise ValueError("parameters: give Parameters, Returns, References or Raises entries (every text is empty)")
    params, rets, refs, errs = (textwrap.dedent(t).strip("\n").splitlines()
                                for t in (parameters, returns, references, raises))

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
                                             ("raises", "Raises", errs, _AFTER_RETURNS[1:]),
                                             ("references", "References", refs, ("Examples",))):
            if entries:
                if _title_at(lines, (title,)) is not None:
                    raise ValueError(f"{name}: the docstring of {fn.__name__} has a {title} section of its own")
                lines = _insert(lines, _title_at(lines, before), [title, "-" * len(title), *entries, ""])
        fn.__doc__ = "\n".join(lines) + "\n"
        return fn

    return decorate


_T = TypeVar("_T")
_DASHES = re.compile(r"-{3,}")


def reads_results(*names: str) -> Callable[[F], F]:
    """A decorator that documents the parameters ``names`` as results of the package, checked by type.

    A function that reads a result (a study, a scenario, the inputs of a ledger) checks each with
    :func:`fusion._validation.instance_of` first in its body (issue 35, fuzz 18's class D: an object of another type
    raised an AttributeError from inside). This puts the rule in its Raises section once: a TypeError entry
    naming each parameter with the class of its annotation (``two_sensor.QScaling`` reads ``QScaling``), first in
    the docstring's Raises section, or in a Raises section made for it (as :func:`with_sections` does).

    Parameters
    ----------
    *names : str
        The parameters, each annotated by its class.

    Returns
    -------
    callable
        The decorator: it sets the function's ``__doc__`` and returns the function itself.
    """
    def decorate(fn: F) -> F:
        ann = getattr(fn, "__annotations__", {})
        kinds = []
        for n in names:
            cls = ann[n].__name__ if isinstance(ann[n], type) else str(ann[n]).rsplit(".", 1)[-1]
            kinds.append(f"``{n}`` not a{'n' if cls[:1] in 'AEIOU' else ''} {cls}")
        listed = kinds[0] if len(kinds) == 1 else f"{', '.join(kinds[:-1])} or {kinds[-1]}"
        entry = ["TypeError", f"    {listed} (a result of another kind, or not a result)."]
        lines = inspect.cleandoc(fn.__doc__ or "").splitlines()
        at = _title_at(lines, ("Raises",))
        if at is None:
            return with_sections(raises="\n".join(entry))(fn)
        fn.__doc__ = "\n".join([*lines[:at + 2], *entry, *lines[at + 2:]]) + "\n"
        return fn

    return decorate


class ParameterDocs:
    """Numpydoc entries of parameters shared by a module's functions, added to a docstring by a decorator.

    Parameters
    ----------
    entries : mapping of str to str
        Parameter name (or names, ``"seed, runs"``) → the rest of its numpydoc entry: the type, then, on
        lines indented by four spaces, the description (``"RidgeStudy\\n    Result of ..."``).

    Examples
    --------
    >>> PARAMS = ParameterDocs({"s": "float\\n    A step (s)."})
    >>> @PARAMS("s")
    ... def f(s: float) -> float:
    ...     '''Twice ``s``.
    ...
    ...     Returns
    ...     -------
    ...     float
    ...     '''
    ...     return 2 * s
    >>> print(f.__doc__)
    Twice ``s``.
    <BLANKLINE>
    Parameters
    ----------
    s : float
        A step (s).
    <BLANKLINE>
    Returns
    -------
    float
    """

    def __init__(self, entries: Mapping[str, str]) -> None:
        if not isinstance(entries, Mapping) or not all(isinstance(v, str) for v in entries.values()):
            raise ValueError("entries must be a mapping of parameter names to strings")
        self._entries = dict(entries)

    def __call__(self, *names: str) -> Callable[[_T], _T]:
        """A decorator that adds the entries of ``names``, in that order, to the Parameters section of a docstring.

        The entries join the function's own entries when its docstring has a Parameters section, else make one
        before its first section (or at its end); the section's entries follow the order of the signature.

        Parameters
        ----------
        *names : str
            Keys of the entries.

        Returns
        -------
        callable
            The decorator; it sets ``__doc__`` and returns the object itself.
        """
        unknown = [n for n in names if n not in self._entries]
        if unknown or not names:
            raise ValueError(f"names must be keys of the entries {sorted(self._entries)}, got {list(names)}")
        block = [f"{n} : {line}" if i == 0 else line
                 for n in names for i, line in enumerate(self._entries[n].splitlines())]

        def add(obj: _T) -> _T:
            order = list(inspect.signature(obj).parameters)  # type: ignore[arg-type]
            obj.__doc__ = _with_parameters(inspect.cleandoc(obj.__doc__ or ""), block, order)
            return obj

        return add


def _in_order(entries: list[str], order: list[str]) -> list[str]:
    """The lines of numpydoc parameter ``entries`` (each an unindented ``name : type`` line and its indented
    description) with the entries sorted by the position of their first name in ``order`` (stable)."""
    groups: list[list[str]] = []
    for line in entries:
        if line[:1].strip() or not groups:
            groups.append([line])
        else:
            groups[-1].append(line)

    def rank(group: list[str]) -> int:
        first = group[0].split(" : ")[0].split(",")[0].strip().lstrip("*")
        return order.index(first) if first in order else len(order)

    return [line for group in sorted(groups, key=rank) for line in group]


def _with_parameters(doc: str, block: list[str], order: list[str]) -> str:
    """``doc`` (cleaned) with the lines ``block`` added to its Parameters section (made if it has none), the
    section's entries in the order of the parameter names ``order``."""
    lines = doc.splitlines()
    heads = [i for i in range(len(lines) - 1) if lines[i].strip() and _DASHES.fullmatch(lines[i + 1].strip())]
    own = [i for i in heads if lines[i].strip() == "Parameters"]
    if own:
        later = [i for i in heads if i > own[0]]
        end = later[0] if later else len(lines)
        while end > own[0] + 2 and not lines[end - 1].strip():
            end -= 1
        return "\n".join(lines[:own[0] + 2] + _in_order(lines[own[0] + 2:end] + block, order) + lines[end:])
    section = ["Parameters", "----------", *_in_order(block, order)]
    if heads:
        return "\n".join(lines[:heads[0]] + section + [""] + lines[heads[0]:])
    return "\n".join(lines + [""] + section)
