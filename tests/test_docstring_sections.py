"""fusion._docstrings.with_sections: shared numpydoc entries land in the right section, in order."""

from __future__ import annotations

import pytest

from fusion._docstrings import with_sections

_R = "r : int\n    The shared parameter."


def _sections(doc: str) -> list[str]:
    lines = doc.splitlines()
    return [line for i, line in enumerate(lines[:-1]) if lines[i + 1] and set(lines[i + 1]) == {"-"}]


def test_parameters_made_before_returns() -> None:
    @with_sections(_R)
    def f(r: int) -> int:
        """Summary.

        Returns
        -------
        int
        """
        return r

    assert f.__doc__ == "Summary.\n\nParameters\n----------\nr : int\n    The shared parameter.\n\nReturns\n-------\nint\n"
    assert f(3) == 3   # the function itself, not a wrapper


def test_parameters_put_first_in_an_existing_section() -> None:
    @with_sections(_R)
    def f(r: int, s: int) -> None:
        """Summary.

        Parameters
        ----------
        s : int
            Its own.
        """

    lines = f.__doc__.splitlines()
    assert lines[lines.index("Parameters") + 2:] == ["r : int", "    The shared parameter.", "s : int", "    Its own."]


def test_returns_and_references_placed_in_numpydoc_order() -> None:
    @with_sections(returns="dict\n    Key -> value.", references="* A source.")
    def f() -> dict:
        """Summary.

        Raises
        ------
        ValueError
            Never.

        Examples
        --------
        >>> 1
        """
        return {}

    assert _sections(f.__doc__) == ["Returns", "Raises", "References", "Examples"]


def test_summary_only_gets_every_section_at_the_end() -> None:
    @with_sections(_R, "int", "* A source.")
    def f(r: int) -> int:
        """Summary."""
        return r

    assert _sections(f.__doc__) == ["Parameters", "Returns", "References"]
    assert f.__doc__.startswith("Summary.\n\nParameters\n")


def test_raises_placed_after_returns_before_notes() -> None:
    @with_sections(returns="int", raises="ValueError\n    Always.")
    def f() -> int:
        """Summary.

        Notes
        -----
        None.
        """
        return 0

    assert _sections(f.__doc__) == ["Returns", "Raises", "Notes"]
    assert "Raises\n------\nValueError\n    Always.\n\nNotes" in f.__doc__


@pytest.mark.parametrize("kw", [{"returns": "int"}, {"references": "* Another."}, {"raises": "ValueError"}])
def test_a_section_of_its_own_is_an_error(kw: dict[str, str]) -> None:
    def f() -> int:
        """Summary.

        Returns
        -------
        int

        Raises
        ------
        ValueError
            Never.

        References
        ----------
        * A source.
        """
        return 0

    with pytest.raises(ValueError, match=next(iter(kw))):
        with_sections(**kw)(f)


def test_nothing_to_add_is_an_error() -> None:
    with pytest.raises(ValueError, match="parameters"):
        with_sections()
