"""How an error message echoes a bad value: cut to a length, and never failing itself (issue 35).

A refusal must name the argument and show what it got, but the value is the caller's: its ``repr`` may be a
megabyte long (a 10**6-character option) or raise (an object whose ``__repr__`` raises, fuzz 17: the refusal of
``scale=BadRepr(-1.0)`` crashed with the object's RuntimeError instead of the package's ValueError). Every message of
the shared validation shows a value through :func:`shown`.
"""

from __future__ import annotations

__all__: list[str] = []  # private module

#: Longest echo of a bad value in an error message (:func:`shown`).
MAX_SHOWN = 80


def shown(value: object, limit: int = MAX_SHOWN) -> str:
    """``repr(value)`` for an error message, cut to ``limit`` characters (a cut repr ends with ``...`` and the
    original length); ``"a <type name>"`` when the value's own ``__repr__`` raises."""
    try:
        r = repr(value)
    except Exception:  # noqa: BLE001 - the caller's repr: any exception
        return f"a {type(value).__name__}"
    if not isinstance(r, str):
        return f"a {type(value).__name__}"
    return r if len(r) <= limit else f"{r[:limit]}... ({len(r):,} characters)"
