"""Argument rules for selections of entries: boolean masks, slices of runs or frames, sample windows.

Re-exported by ``fusion._validation`` (every public function imports them from there); kept apart by concept
(the module was over the package's 1,000-line limit).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from fusion._counts import count
from fusion._entries import entries_array
from fusion._shown import shown
from fusion._validation import _conversion_error, input_size, is_integer


def as_mask(value: object, name: str) -> NDArray[np.bool_]:
    """A boolean array argument (rule 10 mirrored): ``True``/``False`` entries only, any numpy conversion error
    (a ragged or self-containing list, an object whose ``__array__`` raises) re-raised naming ``name``.

    Raises
    ------
    TypeError
        Not convertible to an array, or not of booleans (numbers are not read as their truthiness).
    """
    input_size(value, name)  # rule 9: before any conversion
    try:
        # an object array of bools is bools, as its list is (fuzz 36b D4); no warning filter: process-global state
        # that another thread would see (fuzz 24a W)
        m = entries_array(value)
    except MemoryError:
        raise
    except (TypeError, ValueError, RecursionError) as exc:
        raise TypeError(f"{name} must be an array of bools: {type(exc).__name__}: {str(exc):.200}") from None
    except Exception as exc:  # rule 15: the argument's own exception
        raise _conversion_error(name, exc) from exc
    if m.dtype != bool:
        raise TypeError(f"{name} must be an array of bools, got dtype {m.dtype}")
    return m


def _slice_bounds(value: slice, name: str) -> None:
    """Refuse, naming ``name``, a slice bound (start, stop or step) that is neither None nor an integer (rule 13,
    :func:`fusion._validation.is_integer`): the one rule of every slice argument, so that a bool (``slice(True,
    None)``, which Python reads as 1) or a float is a TypeError wherever a slice is validated (fuzz 28b D4)."""
    for part in ("start", "stop", "step"):
        b = getattr(value, part)
        if b is not None and not is_integer(b):
            raise TypeError(f"{name} must be a slice of integer bounds, got {part} = {shown(b)}")


def selection(value: object, name: str, n: int) -> slice | NDArray[np.bool_]:
    """A selection of ``n`` paired entries (runs, snapshots): a :class:`slice` of integer (or ``None``) bounds and a
    non-zero step, or a boolean mask of length ``n`` (:func:`as_mask`). An integer index array is refused: a
    repeated index would count one entry as several paired runs (fuzz 21b: ``np.zeros(200, dtype=int)`` judged one
    snapshot repeated 200 times as 200 runs).

    Returns
    -------
    slice or ndarray of bool
        The slice, or the mask as a boolean array of shape ``(n,)``.

    Raises
    ------
    TypeError
        ``value`` is neither a slice nor booleans (an integer array, a str, ``None``), or a bound is not an integer.
    ValueError
        A mask of another length or shape, or a zero step; naming ``name``.
    """
    if isinstance(value, slice):
        _slice_bounds(value, name)
        if value.step is not None and int(value.step) == 0:
            raise ValueError(f"{name} must be a slice of non-zero step, got {shown(value)}")
        return value
    if value is None or isinstance(value, (str, bytes)):
        raise TypeError(f"{name} must be a slice or a boolean mask, got {type(value).__name__}")
    mask = as_mask(value, name)
    if mask.shape != (n,):
        raise ValueError(f"{name} must be a boolean mask of shape ({n},) (one entry per paired entry), got shape "
                         f"{mask.shape}")
    return mask


def window(value: object, name: str, length: int, *, one_based: bool = False) -> tuple[int, int]:
    """A window of samples (issue 35, class 4): a pair of integers, not reversed, not empty, inside the data.

    Parameters
    ----------
    value : (int, int)
        ``(start, stop)``: 0-based slice bounds, ``0 <= start < stop <= length``; with
        ``one_based``, first and last sample numbers, ``1 <= first <= last <= length``.
    name : str
        Argument name used in the messages.
    length : int
        Number of samples the window selects from.
    one_based : bool
        Read the pair as 1-based inclusive sample numbers.

    Returns
    -------
    (int, int)
        The pair as ints.

    Raises
    ------
    TypeError
        Not a pair of integers.
    ValueError
        Reversed, empty, or outside the data.
    """
    # an ordered pair: a sequence or a 1-D array (a set or a mapping has a length of 2 but no order, fuzz 15)
    if (isinstance(value, (str, bytes)) or not isinstance(value, (Sequence, np.ndarray))
            or (isinstance(value, np.ndarray) and value.ndim != 1) or len(value) != 2):
        raise TypeError(f"{name} must be a pair of sample indices, got {shown(value)}")
    a = count(value[0], f"{name}[0]", minimum=0, maximum=None)
    b = count(value[1], f"{name}[1]", minimum=0, maximum=None)
    if one_based:
        if not 1 <= a <= b <= length:
            raise ValueError(f"{name} = {shown(tuple(value))} must satisfy 1 <= first <= last <= {length}")
    elif not 0 <= a < b <= length:
        raise ValueError(f"{name} = {shown(tuple(value))} must satisfy 0 <= start < stop <= {length} (not reversed, not empty)")
    return a, b


def frame_slice(value: object, name: str, length: int) -> range:
    """A slice of frames (or steps) to average over: a ``slice`` that selects at least one of ``length`` (rule 4).

    A mean over no frame is NaN, and a slice of step 0 raises a ValueError naming nothing; both are refused here by
    ``name``, as a window of samples is by :func:`window`.

    Parameters
    ----------
    value : slice
        The frames, 0-based, as Python slices them (negative bounds count from the end).
    name : str
        Argument name used in the messages.
    length : int
        Number of frames the slice selects from.

    Returns
    -------
    range
        The selected frames.

    Raises
    ------
    TypeError
        Not a slice, or bounds that are not integers (a bool bound included).
    ValueError
        A step of 0, or no frame selected.
    """
    if not isinstance(value, slice):
        raise TypeError(f"{name} must be a slice of frames, got {type(value).__name__} {shown(value, 60)}")
    _slice_bounds(value, name)  # a bool bound is not a frame number (fuzz 28b D4: slice(True, None) read as 1)
    try:
        frames = range(length)[value]
    except TypeError:
        raise TypeError(f"{name} must be a slice with integer bounds, got {shown(value, 60)}") from None
    except ValueError as exc:  # "slice step cannot be zero"
        raise ValueError(f"{name}: {exc} (got {shown(value, 60)})") from None
    if not len(frames):
        raise ValueError(f"{name} = {shown(value, 60)} selects no frame of {length} (a mean over no frame is "
                         "undefined)")
    return frames
