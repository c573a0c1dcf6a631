"""A list or tuple subclass that reads its entries its own way (fix 77a's note): ``len()`` 1 passed the input budget
with 2**25 + 1 entries, and NumPy converted what ``__iter__`` gave, not what it stores."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import pytest

from _helpers import refused_quickly

from fusion._entries import sequence_entries
from fusion._validation import as_array


class _Short(list):
    def __len__(self) -> int:
        return 1


class _Other(list):
    def __iter__(self):   # type: ignore[no-untyped-def]
        return iter([0.0])


class _Plain(list):
    unit = "m"


class _Pair(NamedTuple):
    a: float
    b: float


@pytest.mark.parametrize("cls", [_Short, _Other])
def test_a_list_subclass_reading_its_own_way_is_refused_by_name(cls: type) -> None:
    refused_quickly(lambda: as_array(cls([1.0, 2.0]), "x"), ValueError, r"^x must not be a list subclass.*defines __")


def test_a_lying_length_no_longer_passes_the_input_budget() -> None:
    big = _Short([0.0] * 10)
    assert sequence_entries(big, 5) > 5   # counted by what it stores
    assert sequence_entries([big], 5) > 5   # inside a plain list too


def test_subclasses_that_read_as_their_base_are_still_arrays() -> None:
    assert as_array(_Plain([1.0, 2.0]), "x").tolist() == [1.0, 2.0]
    assert np.array_equal(as_array(_Pair(1.0, 2.0), "x"), [1.0, 2.0])


class _AsArray(list):
    def __array__(self, dtype=None, copy=None):   # type: ignore[no-untyped-def]
        return np.zeros(6_000)


class _Shapeless:
    def __init__(self, n: int) -> None:
        self.n = n

    def __array__(self, dtype=None, copy=None):   # type: ignore[no-untyped-def]
        return np.zeros(self.n)


def test_fuzz69b_c1_a_list_subclass_with_an_array_protocol_is_refused_by_name() -> None:
    refused_quickly(lambda: as_array(_AsArray([1.0]), "x"), ValueError, r"^x must not be a list subclass.*__array__")


def test_fuzz69b_d1_a_shapeless_array_like_is_measured_once_converted(monkeypatch: pytest.MonkeyPatch) -> None:
    import fusion._validation as V

    monkeypatch.setattr(V, "MAX_INPUT_ELEMENTS", 100)
    with pytest.raises(ValueError, match=r"^x has 101 entries.*beyond the input budget"):
        as_array(_Shapeless(101), "x")
    assert as_array(_Shapeless(100), "x").shape == (100,)


class _ClaimsSmall(np.ndarray):
    @property   # type: ignore[misc]
    def shape(self):   # type: ignore[no-untyped-def]
        return (2, 2)


class _Huge:
    def __array__(self, dtype=None, copy=None):   # type: ignore[no-untyped-def]
        return np.broadcast_to(1.0, (10**9,))


class _Faked:
    __class__ = property(lambda self: list)   # type: ignore[assignment]

    def __array__(self, dtype=None, copy=None):   # type: ignore[no-untyped-def]
        return np.zeros(3)


def test_fuzz70b_c1_an_ndarray_subclass_is_measured_by_its_own_shape() -> None:
    lying = np.broadcast_to(1.0, (10**9,)).view(_ClaimsSmall)
    refused_quickly(lambda: as_array(lying, "x"), ValueError, r"^x has 1e\+09 entries")


def test_fuzz70b_c2_an_array_like_inside_a_list_is_measured_converted() -> None:
    refused_quickly(lambda: as_array([_Huge()], "x"), ValueError, r"^x has at least 1e\+09 entries")


def test_fuzz70b_c3_a_faked_class_is_no_list() -> None:
    with pytest.raises(TypeError, match=r"^x must be numeric"):
        as_array(_Faked(), "x")


def test_fuzz70b_c4_an_array_protocol_set_on_the_instance_is_refused() -> None:
    x = _Plain([1.0])
    x.__array_interface__ = np.zeros(6_000).__array_interface__   # type: ignore[attr-defined]
    refused_quickly(lambda: as_array(x, "x"), ValueError, r"^x must not be a list subclass.*__array_interface__")
