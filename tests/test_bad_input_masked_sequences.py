"""A masked array given for any array or sequence argument is refused by name (issue 35, found while trimming the suite).

``fusion._counts.sequence`` read a masked array item by item: its items were the values under the mask or the
masked constant, and ``thermocouples.inject_failure(biases=...)`` used them. The shared rule
(``fusion._counts.not_masked``) now refuses a masked array in :func:`sequence` as the validated arrays already did.
Checked for every array and sequence-of-numbers argument of the main registry (``tests/test_bad_input.py``), one
call each: ``tests/test_bad_input_counts.py`` draws one argument of each callable (three hypothesis examples), which
never drew ``biases``.
"""

from __future__ import annotations

import numpy as np
import pytest

from fusion._counts import sequence
from test_bad_input_counts import _names, _raised
from test_bad_input_properties import KIND, NAMES, REG

#: (callable, argument) of every argument the registry's kinds call an array or a sequence of integers.
SEQUENCE_ARGS = [(n, a) for n in NAMES for a, k in KIND[n].items()
                 if k in ("array", "int_seq", "seed_seq") and np.asarray(REG[n][a].value).dtype.kind in "iuf"]


def _masked_like(value: object) -> np.ma.MaskedArray:
    """``value`` as a masked array with its last item masked and a wild value under the mask."""
    a = np.array(value, copy=True)   # its own dtype: integer seeds and counts take another path than floats
    a = a.astype(float) if a.dtype.kind not in "iu" else a
    mask = np.zeros(a.shape, bool)
    mask.reshape(-1)[-1] = True
    a.reshape(-1)[-1] = 10**6   # what a dropped mask would let through
    return np.ma.masked_array(a, mask=mask)


def test_integer_rules_refuse_masked_arrays() -> None:
    """Fuzz 28a C2: a masked integer array took the integer fast path (its masked entry became None), and a masked
    0-d count its value under the mask."""
    from fusion._counts import count, counts, seeds

    with pytest.raises(TypeError, match="^seeds must be a plain array"):
        seeds(np.ma.array([1, 2], mask=[0, 1]), "seeds")
    with pytest.raises(TypeError, match="^ns must be a plain array"):
        counts(np.ma.array([1, 2]), "ns")
    with pytest.raises(TypeError, match="^runs must be a plain array"):
        count(np.ma.array(5, mask=True), "runs")
    assert seeds(np.array([1, 2]), "seeds") == [1, 2] and count(np.int64(5), "runs") == 5


def test_sequence_refuses_a_masked_array_and_keeps_plain_arrays() -> None:
    with pytest.raises(TypeError, match=r"^biases must be a plain array, got a masked array"):
        sequence(np.ma.masked_array([4.0, 8.0], mask=[False, True]), "biases")
    with pytest.raises(TypeError, match="biases"):   # no mask set: still a masked array, refused alike
        sequence(np.ma.masked_array([4.0, 8.0]), "biases")
    assert sequence(np.array([4.0, 8.0]), "biases") == [4.0, 8.0]


def test_every_sequence_argument_refuses_a_masked_array_by_name() -> None:
    assert len(SEQUENCE_ARGS) >= 200, SEQUENCE_ARGS   # the enumeration finds the sequence arguments
    problems = []
    for name, arg in SEQUENCE_ARGS:
        out = _raised(name, arg, _masked_like(REG[name][arg].value))
        if not isinstance(out, TypeError) or not _names(out, arg):
            problems.append(f"{name}({arg}=masked): {type(out).__name__}: {out}")
    assert not problems, "\n".join(problems)
