"""The fast paths of speed58 give what the paths they skip give (results unchanged, nothing shared)."""

from __future__ import annotations

import numpy as np
import pytest

from fusion._validation import _numeric, as_array


def _read_only(a: np.ndarray) -> np.ndarray:
    a.setflags(write=False)
    return a


@pytest.mark.parametrize("make", [lambda a: a, lambda a: a[:, ::2], lambda a: a.T, np.asfortranarray, _read_only])
def test_a_plain_float_array_is_copied_never_shared(make) -> None:  # noqa: ANN001
    a = make(np.arange(12.0).reshape(3, 4))
    out = _numeric(a, "x")
    assert out.dtype == np.float64 and out.shape == a.shape and np.array_equal(out, a)
    assert not np.shares_memory(out, a) and out.flags.writeable
    out[...] = -1.0
    assert np.array_equal(a, make(np.arange(12.0).reshape(3, 4)))


@pytest.mark.parametrize("bad, error", [
    (np.ma.masked_array([1.0, 2.0], mask=[0, 1]), TypeError),          # a subclass: not the fast path
    (np.array([1.0, np.nan]), ValueError),                            # checked after the conversion, as before
    (np.array([1.0, 1e300]), ValueError),
    (np.broadcast_to(np.float64(1.0), (2**13, 2**13)), ValueError),   # beyond the input budget, refused by its shape
])
def test_the_fast_path_keeps_every_refusal(bad, error) -> None:  # noqa: ANN001
    with pytest.raises(error, match=r"^x "):
        as_array(bad, "x")
