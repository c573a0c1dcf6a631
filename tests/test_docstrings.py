"""Every public name of the package has a complete numpydoc docstring.

"Public" means listed in the ``__all__`` of the module that defines it (subpackages re-export
names; each is checked once, where it is defined). A function needs a one-line summary, a
``Parameters`` section naming every parameter of its signature (when it has any) and a
``Returns`` (or ``Yields``) section when it is annotated to return something, each entry of which
(an unindented type line) has an indented description saying what the value is (numpydoc's RT03;
issue 36: the bare ``Returns / matplotlib.figure.Figure / Raises`` skeletons repeated across the
book's functions were what ``duplicates --change`` listed). A class needs a summary and an
``Attributes`` or ``Parameters`` section. Each algorithm module (readings,
estimates, filtering, optimise, registration) cites the original literature in a
``References`` section, in its module docstring or in a public docstring.
"""

from __future__ import annotations

import importlib
import inspect
import pkgutil
import re
from types import ModuleType

import pytest

import fusion

ALGORITHM_PACKAGES = ("readings", "estimates", "filtering", "optimise", "registration")


def _modules() -> list[ModuleType]:
    names = [m.name for m in pkgutil.walk_packages(fusion.__path__, prefix="fusion.")]
    return [importlib.import_module(name) for name in sorted(names)]


MODULES = _modules()


def _public(module: ModuleType) -> list[tuple[str, object]]:
    out = []
    for name in getattr(module, "__all__", ()):
        obj = getattr(module, name)
        if (inspect.isfunction(obj) or inspect.isclass(obj)) and obj.__module__ == module.__name__:
            out.append((f"{module.__name__}.{name}", obj))
    return out


PUBLIC = [item for module in MODULES for item in _public(module)]


def _sections(doc: str) -> dict[str, list[str]]:
    """Numpydoc sections of ``doc``: title -> its lines (a title is underlined with dashes)."""
    lines = doc.splitlines()
    sections: dict[str, list[str]] = {}
    current = None
    for i, line in enumerate(lines):
        if i + 1 < len(lines) and re.fullmatch(r"-{3,}", lines[i + 1].strip()) and line.strip():
            current = line.strip()
            sections[current] = []
            continue
        if current is not None and not re.fullmatch(r"-{3,}", line.strip()):
            sections[current].append(line)
    return sections


def _documented_names(lines: list[str]) -> set[str]:
    """Names in a Parameters section: unindented lines ``a, b : type`` (or just ``a``)."""
    names: set[str] = set()
    for line in lines:
        if line and not line[0].isspace():
            head = line.split(" : ")[0].strip()
            names.update(part.strip().lstrip("*") for part in head.split(","))
    return names


def _undescribed(lines: list[str]) -> list[str]:
    """Entries of a Returns (or Yields) section, unindented lines, not followed by an indented description line."""
    bare = []
    for i, line in enumerate(lines):
        if line and not line[0].isspace():
            following = lines[i + 1] if i + 1 < len(lines) else ""
            if not (following.strip() and following[0].isspace()):
                bare.append(line.strip())
    return bare


def _returns_something(obj: object) -> bool:
    annotation = inspect.signature(obj).return_annotation  # type: ignore[arg-type]
    return annotation not in (inspect.Signature.empty, None, "None")


def test_undescribed_finds_bare_entries() -> None:
    # the check itself: a bare entry (last, or followed by another entry or a blank line) is found, a described one not
    lines = ["fig : Figure", "    The figure.", "ax : Axes", "", "float", "str"]
    assert _undescribed(lines) == ["ax : Axes", "float", "str"]
    assert _undescribed(["Figure", "    Left: x against y."]) == []


def test_public_names_found() -> None:
    # guards against the enumeration silently finding nothing
    assert len(PUBLIC) > 100
    assert {m.__name__.split(".")[1] for m in MODULES} >= set(ALGORITHM_PACKAGES)


@pytest.mark.parametrize(("qualname", "obj"), PUBLIC, ids=[q for q, _ in PUBLIC])
def test_docstring_complete(qualname: str, obj: object) -> None:
    doc = inspect.getdoc(obj) or ""
    summary = doc.strip().split("\n\n")[0]
    assert summary.strip(), f"{qualname}: no summary line"
    sections = _sections(doc)
    if inspect.isclass(obj):
        assert "Attributes" in sections or "Parameters" in sections, f"{qualname}: no Attributes section"
        return
    params = [p for p in inspect.signature(obj).parameters.values()]  # type: ignore[arg-type]
    if params:
        assert "Parameters" in sections, f"{qualname}: no Parameters section"
        missing = {p.name for p in params} - _documented_names(sections["Parameters"])
        assert not missing, f"{qualname}: parameters not documented: {sorted(missing)}"
    if _returns_something(obj):
        assert "Returns" in sections or "Yields" in sections, f"{qualname}: no Returns section"
    bare = [entry for title in ("Returns", "Yields") for entry in _undescribed(sections.get(title, []))]
    assert not bare, f"{qualname}: Returns entries without a description (RT03): {bare}"


ALGORITHM_MODULES = [
    m for m in MODULES if m.__name__.split(".")[1] in ALGORITHM_PACKAGES and getattr(m, "__all__", None) and _public(m)
]


@pytest.mark.parametrize("module", ALGORITHM_MODULES, ids=[m.__name__ for m in ALGORITHM_MODULES])
def test_algorithm_module_cites_references(module: ModuleType) -> None:
    docs = [inspect.getdoc(module) or ""] + [inspect.getdoc(obj) or "" for _, obj in _public(module)]
    assert any("References" in _sections(doc) for doc in docs), f"{module.__name__}: no References section"
