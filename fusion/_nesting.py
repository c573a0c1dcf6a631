"""The shape rules of a caller's nested containers (issue 35, fuzz 30a C7/C8/D4): ragged, self-containing, too deep.

A nested list whose rows differ in length has no array shape (numpy raises its own unnamed "inhomogeneous shape"
ValueError); a container that holds itself, or one nested thousands deep, makes any recursive walk (freezing a
record's settings, a ``repr`` in an error message, a glued value's text) raise a RecursionError. The package's
checks refuse all three by the argument's name, before they recurse: :func:`shape_of` for an argument whose shape
is read before its conversion, :func:`nesting_error` for the freezing of records (``fusion._frozen.frozen_value``)
and the glue check (``fusion.book.glue._finite``).
"""

from __future__ import annotations

import numpy as np

__all__: list[str] = []  # private module

#: Deepest nesting of containers (lists, tuples, mappings) accepted inside an argument: NumPy's own limit on an
#: array's dimensions (``numpy.MAXDIMS``, 64). A deeper one (or one that contains itself) is refused by name.
MAX_NESTING = 64


def nesting_error(name: str, itself: bool) -> ValueError:
    """The refusal of a container that contains itself (``itself``) or is nested deeper than :data:`MAX_NESTING`,
    naming the argument ``name`` (never showing the value: its ``repr`` would recurse)."""
    if itself:
        return ValueError(f"{name} must not hold a container that contains itself (it has no finite value)")
    return ValueError(f"{name} must not nest containers more than {MAX_NESTING} deep")


def ragged_error(name: str) -> TypeError:
    """The refusal of a nested sequence whose rows differ in length, or one holding itself (no array shape), naming
    ``name``."""
    return TypeError(f"{name} must be an array_like of numbers: its nested sequences differ in length or hold "
                     "themselves (a ragged sequence has no array shape)")


def is_ragged(exc: BaseException) -> bool:
    """Whether ``exc`` is NumPy's refusal of a ragged (or self-containing) nested sequence."""
    return isinstance(exc, ValueError) and ("inhomogeneous" in str(exc) or "array element with a sequence" in str(exc))


def shape_of(value: object, name: str) -> tuple[int, ...]:
    """``np.shape(value)`` of a caller's argument read before its conversion: a ragged nested sequence refused by
    :func:`ragged_error` naming ``name`` (numpy's own ValueError names nothing), a nesting deeper than numpy's
    limit too, and an exception of the argument's own conversion re-raised naming it (rule 15).

    Parameters
    ----------
    value : object
        The argument.
    name : str
        Its name, for the messages.

    Returns
    -------
    tuple of int
        Its shape, as :func:`numpy.shape` gives it.

    Raises
    ------
    TypeError
        A ragged or self-containing nested sequence, or a conversion that raised, naming ``name``.
    ValueError
        Nested deeper than :data:`MAX_NESTING`, naming ``name``.
    """
    try:
        return np.shape(value)
    except MemoryError:
        raise
    except RecursionError:
        raise nesting_error(name, itself=False) from None
    except ValueError as exc:
        if "maximum number of dimensions" in str(exc):  # numpy: deeper than its 64 dimensions, or holding itself
            raise nesting_error(name, itself=False) from None
        if is_ragged(exc):
            raise ragged_error(name) from None
        raise TypeError(f"{name} could not be converted to a number: it raised ValueError: {str(exc):.200}") from None
    except Exception as exc:  # noqa: BLE001 - rule 15: the argument's own exception (its __len__, __getitem__)
        raise TypeError(f"{name} could not be converted to a number: it raised {type(exc).__name__}: "
                        f"{str(exc):.200}") from exc


def ndim_of(value: object, name: str) -> int:
    """``np.ndim(value)`` of a caller's argument, with the refusals of :func:`shape_of`."""
    return len(shape_of(value, name))
