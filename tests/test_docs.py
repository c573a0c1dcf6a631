"""The shared numpydoc parameter entries (:class:`fusion._docstrings.ParameterDocs`) make the docstring a function would have written."""

from __future__ import annotations

import inspect

import pytest

from fusion._docstrings import ParameterDocs

DOCS = ParameterDocs({"a": "int\n    First.", "b, c": "float\n    Second and third."})


def test_section_made_before_the_first_section() -> None:
    @DOCS("a")
    def f(a: int) -> int:
        """Summary.

        More.

        Returns
        -------
        int
        """
        return a

    assert f.__doc__ == "Summary.\n\nMore.\n\nParameters\n----------\na : int\n    First.\n\nReturns\n-------\nint"


def test_section_made_at_the_end_without_sections() -> None:
    @DOCS("b, c")
    def f(b: float, c: float) -> None:
        """Summary."""

    assert f.__doc__ == "Summary.\n\nParameters\n----------\nb, c : float\n    Second and third."


def test_entries_join_the_own_section_in_signature_order() -> None:
    @DOCS("a", "b, c")
    def f(b: float, c: float, x: str, a: int) -> str:
        """Summary.

        Parameters
        ----------
        x : str
            Own.

        Returns
        -------
        str
        """
        return x

    doc = inspect.getdoc(f) or ""
    params = doc.split("Parameters\n----------\n")[1].split("\n\n")[0]
    assert params == "b, c : float\n    Second and third.\nx : str\n    Own.\na : int\n    First."
    assert doc.endswith("\n\nReturns\n-------\nstr")


def test_the_object_is_returned() -> None:
    def f(a: int) -> None:
        """Summary."""

    assert DOCS("a")(f) is f


@pytest.mark.parametrize("names", [(), ("z",), ("a", "b")])
def test_unknown_names_refused(names: tuple[str, ...]) -> None:
    with pytest.raises(ValueError, match="names"):
        DOCS(*names)


def test_entries_must_be_strings() -> None:
    with pytest.raises(ValueError, match="entries"):
        ParameterDocs({"a": 1})  # type: ignore[dict-item]
