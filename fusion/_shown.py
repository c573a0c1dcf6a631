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
    original length); ``"a <type name>"`` when the value's own ``__repr__`` raises (a RecursionError of a list
    nested thousands deep too). A list or tuple of more than ``limit`` entries is shown by its first ``limit``
    entries and its length (its whole repr is never built: fuzz 30a C8)."""
    try:
        if type(value) in (list, tuple) and len(value) > limit:  # type: ignore[arg-type]
            r = repr(type(value)(value[:limit]))  # type: ignore[index, call-arg]
            return f"{r[:limit]}... ({len(value):,} entries)"  # type: ignore[arg-type]
        r = repr(value)
    except Exception:  # noqa: BLE001 - the caller's repr: any exception
        return f"a {type(value).__name__}"
    if not isinstance(r, str):
        return f"a {type(value).__name__}"
    return r if len(r) <= limit else f"{r[:limit]}... ({len(r):,} characters)"
