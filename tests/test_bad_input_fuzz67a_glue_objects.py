"""Fuzz 67a C1 (an instance's ``__dict__`` a dict subclass lying about its size) and a class's own ``__dict__``
hiding an instance's attributes: ``glue_all`` reads what the dict stores, by dict's own methods."""

from __future__ import annotations

import numpy as np
import pytest

from _helpers import glued, refused_quickly


class _Lying(dict):
    """A dict that says it is empty."""

    def __len__(self) -> int:
        return 0

    def __bool__(self) -> bool:
        return False


class _Int(int):
    pass


def _with_dict(value: int, attrs: dict) -> _Int:
    out = _Int(value)
    out.__dict__ = _Lying(attrs)
    return out


def test_c1_a_lying_instance_dict_is_scanned_for_a_text_of_its_own(monkeypatch: pytest.MonkeyPatch) -> None:
    plain = _Int(1)   # its type found plain first: the second value's attributes must still be read
    hidden = _with_dict(2, {"_repr_html_": lambda: "nan"})
    with pytest.raises(TypeError, match=r"values\['k'\].*_repr_html_"):
        glued(monkeypatch, {"k": [hidden, plain]})   # walked last first


def test_c1_a_lying_instance_dict_is_charged_by_what_it_stores(monkeypatch: pytest.MonkeyPatch) -> None:
    import fusion.book._glue_meter as meter

    big = _with_dict(3, {f"a{i}": i for i in range(10**4)})
    monkeypatch.setattr(meter, "GLUE_ATTR", 10**6)   # 10**4 attributes at 10**6 units: beyond the budget
    refused_quickly(lambda: glued(monkeypatch, {"k": big}), ValueError, r"values\['k'\].*scans 10,0\d\d attributes")


def test_c1_an_honest_instance_dict_is_still_accepted(monkeypatch: pytest.MonkeyPatch) -> None:
    v = _Int(4)
    v.note = "plain data"
    assert glued(monkeypatch, {"k": [v, _with_dict(5, {"x": 1})]})["k"] is not None


def test_a_class_defining_its_own_dict_is_refused(monkeypatch: pytest.MonkeyPatch) -> None:
    class Hiding(int):
        __dict__ = property(lambda self: {})   # type: ignore[assignment]

    v = Hiding(3)
    object.__setattr__(v, "_repr_html_", lambda: "nan")   # stored in the real instance dict, read by IPython
    with pytest.raises(TypeError, match=r"values\['k'\].*__dict__"):
        glued(monkeypatch, {"k": v})


def _fields(n: int) -> np.dtype:
    return np.dtype([(f"f{i}", "f8") for i in range(n)])


def test_c3_structured_arrays_held_by_a_list_are_weighed_by_their_fields(monkeypatch: pytest.MonkeyPatch) -> None:
    held = [np.zeros(1, dtype=_fields(2_000)) for _ in range(400)]   # 8e5 fields at 2,500 units: 2e9
    refused_quickly(lambda: glued(monkeypatch, {"k": held}), ValueError, r"values\['k'\]")


def test_c3_nested_fields_count_each_time_they_occur() -> None:
    from fusion.book._glue_axes import _GLUE_FIELD, field_units

    inner = _fields(10)
    outer = np.dtype([("a", inner), ("b", inner, (3,)), ("c", "f8")])
    assert field_units(outer) == (3 + 2 * 10) * _GLUE_FIELD   # its 3 fields, then a's and b's 10 each
    assert field_units(np.dtype("f8")) == 0


def test_c3_a_few_structured_arrays_are_still_glued(monkeypatch: pytest.MonkeyPatch) -> None:
    assert glued(monkeypatch, {"k": [np.zeros(3, dtype=_fields(20)) for _ in range(20)]})["k"] is not None


def test_fuzz68a_c5_c6_an_attribute_named_by_anything_but_a_str_is_refused(monkeypatch: pytest.MonkeyPatch) -> None:
    class Float(float):
        pass

    class Name(str):
        def startswith(self, *args: object) -> bool:   # hides a display method from a text test
            return False

    odd = Float(1.5)
    odd.__dict__[1] = 2   # type: ignore[index]
    with pytest.raises(TypeError, match=r"values\['k'\].*named by a int"):
        glued(monkeypatch, {"k": odd})
    hiding = Float(2.5)
    hiding.__dict__[Name("_repr_html_")] = lambda: "<b>nan</b>"
    with pytest.raises(TypeError, match=r"values\['k'\].*named by a Name"):
        glued(monkeypatch, {"k": hiding})
