"""Fuzz 54a C1: glue_all's rule for a container subclass printing a text of its own (fuzz 52 C5's atom rule)."""

from __future__ import annotations

import collections
import random
import types
import typing

import numpy as np
import pandas as pd
import pytest

from _helpers import glue_refused, glued


def _refused(values: dict, match: str = r"values\['k'\]") -> None:
    glue_refused(values, TypeError, match)


_glued = glued


def _text(self, *args):   # a text method printing nan (also as _repr_pretty_(p, cycle): it prints nothing)
    if args and hasattr(args[0], "text"):
        args[0].text("nan")
    return "nan"


def _named(method: str) -> type:
    """A typing.NamedTuple class defining ``method`` (a class statement: its metaclass reads the namespace)."""
    ns = {"typing": typing, "_text": _text}
    exec(f"class NT(typing.NamedTuple):\n    x: float\n    {method} = _text\n", ns)
    return ns["NT"]


_KINDS = {
    "list": lambda m: type("L", (list,), {m: _text})([1.0]),
    "tuple": lambda m: type("T", (tuple,), {m: _text})((1.0,)),
    "dict": lambda m: type("D", (dict,), {m: _text})({"a": 1.0}),
    "set": lambda m: type("S", (set,), {m: _text})({1.0}),
    "frozenset": lambda m: type("F", (frozenset,), {m: _text})({1.0}),
    "OrderedDict": lambda m: type("O", (collections.OrderedDict,), {m: _text})(a=1.0),
    "ndarray": lambda m: np.array([1.0]).view(type("A", (np.ndarray,), {m: _text})),
    "Series": lambda m: type("Ser", (pd.Series,), {m: _text})([1.0]),
    "DataFrame": lambda m: type("Df", (pd.DataFrame,), {m: _text})({"a": [1.0]}),
    "NamedTuple": lambda m: _named(m)(1.0),
    "namedtuple": lambda m: type("N", (collections.namedtuple("N", "x"),), {m: _text})(1.0),
    "ReadOnlyMapping": lambda m: type("R", (__import__("fusion._frozen", fromlist=["x"]).ReadOnlyMapping,),
                                      {m: _text})({"a": 1.0}),
}


@pytest.mark.parametrize("method", ["__repr__", "__str__", "__format__", "_repr_pretty_", "_repr_html_",
                                    "_repr_latex_", "_repr_markdown_", "_ipython_display_"])
@pytest.mark.parametrize("kind", list(_KINDS))
@pytest.mark.parametrize("place", [lambda v: v, lambda v: [v], lambda v: {"x": (v,)},
                                   lambda v: np.array([v, 1], dtype=object)[:1]], ids=["value", "list", "dict",
                                                                                       "array"])
def test_c1_a_container_subclass_printing_its_own_text_is_refused(kind: str, method: str, place) -> None:
    """C1: a subclass of a container type (or a NamedTuple) with a text method of its own (IPython printed 'nan',
    or a random number each run) was glued; refused naming values['k'] wherever a container can be."""
    v = _KINDS[kind](method)
    if isinstance(v, pd.DataFrame) and isinstance(place(v), np.ndarray):
        pytest.skip("NumPy reads a table as an array of its cells")
    _refused({"k": place(v)}, rf"values\['k'\] .*{method}")


def test_c1_random_texts_overrides_and_instance_methods_are_refused() -> None:
    """A random repr, an override of the base's entries (a dict whose items() hides a NaN its repr prints), an
    instance's display method, and a class saying it is pandas' are refused."""
    class Random(list):
        def __repr__(self):
            return str(random.random())

    class Hiding(dict):
        def items(self):
            return []

    class Plain(list):
        pass

    inst = Plain([1.0])
    inst._repr_html_ = lambda: "nan"
    shadow = type("Shadow", (dict,), {})({"a": float("nan")})   # its instance's items() hides the NaN
    shadow.items = lambda: []

    class Spoof(pd.Series):
        __module__ = "pandas"

        def __repr__(self):
            return "nan"

    for v in (Random([1.0]), Hiding({"a": float("nan")}), inst, shadow, Spoof([1.0]), [[Random([1.0])]]):
        _refused({"k": v})


def test_plain_containers_and_subclasses_without_a_text_of_their_own_are_glued(
        monkeypatch: pytest.MonkeyPatch) -> None:
    """Python's, NumPy's and pandas' containers, a NamedTuple (collections.namedtuple or typing.NamedTuple, also with
    a method of its own) and a subclass adding methods only are glued as before."""
    class NT(typing.NamedTuple):
        x: float
        y: int = 2

        def twice(self) -> float:
            return 2 * self.x

    class Adds(list):
        def first(self):
            return self[0]

    class SeriesAdds(pd.Series):
        pass

    P = collections.namedtuple("P", "a b")
    values = {"a": NT(0.5), "b": P(1, "x"), "c": [NT(0.25)], "d": Adds([1.0]), "e": collections.OrderedDict(a=1),
              "f": collections.defaultdict(int, a=1), "g": collections.Counter("ab"),
              "h": types.MappingProxyType({"a": 1.0}), "i": collections.ChainMap({"a": 1}), "j": pd.RangeIndex(3),
              "k": pd.MultiIndex.from_arrays([[1, 2], ["a", "b"]]), "l": pd.Categorical(["a"]),
              "m": pd.date_range("2020", periods=2), "n": np.rec.array([(1, 2.0)], names="a,b")[0:1], "o": SeriesAdds([1.0]),
              "p": pd.array([1, 2]), "q": frozenset({1.0}), "r": np.rec.array([(1, 2.0)], names="a,b")}
    got = _glued(monkeypatch, values)
    assert list(got) == list(values) and got["a"] is values["a"]


def test_the_packages_containers_are_glued(monkeypatch: pytest.MonkeyPatch) -> None:
    """The package's own containers print their own deterministic text and are glued (``ReadOnlyMapping``)."""
    from fusion._frozen import ReadOnlyMapping
    from fusion.book.glue import _own_text
    v = ReadOnlyMapping({"a": 0.5})
    assert _own_text(v, container=True) is None
    assert _glued(monkeypatch, {"k": v, "l": [v]})["k"] is v
