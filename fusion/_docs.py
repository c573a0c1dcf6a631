"""Shared numpydoc fragments: parameters that several functions document the same way, written once.

A module keeps its shared parameter descriptions in one :class:`ParameterDocs`; each function names the ones it
takes (``@PARAMS("s")``) and its docstring keeps what is its own (summary, its other parameters, Returns, ...).
The API page, ``help()`` and the docstring tests read the completed ``__doc__``.
"""

from __future__ import annotations

import inspect
import re
from collections.abc import Callable, Mapping
from typing import TypeVar

_T = TypeVar("_T")
_DASHES = re.compile(r"-{3,}")


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
