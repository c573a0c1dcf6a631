"""The book as one product: critique boxes, errata rows, verdict links and chapter skeleton agree."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = sorted((ROOT / "notebooks").glob("*.ipynb"))
CRITIQUE = re.compile(r"^(`{3,}|:{3,})\{admonition\}\s*Critique:(?P<title>.*)$", re.MULTILINE)
NAME = re.compile(r"^:name:\s*(?P<name>\S+)\s*$", re.MULTILINE)
TARGET = re.compile(r"^\((?P<name>[\w-]+)\)=\s*$", re.MULTILINE)
NAMED = re.compile(r"^:name:\s*(?P<name>[\w-]+)\s*$", re.MULTILINE)
REF = re.compile(r"\{ref\}`[^`<]*<(?P<name>[\w-]+)>`")
SKELETON = ("what the source claims", "derivation", "reproduc", "critique", "verdict")


def _markdown(path: Path) -> str:
    nb = json.loads(path.read_text(encoding="utf-8"))
    return "\n".join("".join(c["source"]) for c in nb["cells"] if c["cell_type"] == "markdown")


def _critique_boxes(text: str) -> list[tuple[str, str | None]]:
    """(title, :name:) of every critique admonition in a markdown text."""
    boxes = []
    for m in CRITIQUE.finditer(text):
        options = text[m.end():m.end() + 400].split("\n\n")[0]
        name = NAME.search(options)
        boxes.append((m["title"].strip(), name["name"] if name else None))
    return boxes


def _targets() -> set[str]:
    names: set[str] = set()
    for path in NOTEBOOKS:
        text = _markdown(path)
        names |= {name for _, name in _critique_boxes(text) if name}
        names |= set(TARGET.findall(text))
        names |= set(NAMED.findall(text))   # any directive's :name: (notes, figures, tables)
    return names


def test_helpers_find_boxes_and_references() -> None:
    text = "```{admonition} Critique: eq. 2\n:class: warning\n:name: x-crit\n\nbody\n```\n(x-sec)=\n## S"
    assert _critique_boxes(text) == [("eq. 2", "x-crit")]
    assert TARGET.findall(text) == ["x-sec"]
    assert REF.findall("see {ref}`box <x-crit>` and {ref}`→ <x-sec>`") == ["x-crit", "x-sec"]


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.name)
def test_every_critique_box_is_named_and_has_an_errata_row(path: Path) -> None:
    errata = (ROOT / "book" / "errata.md").read_text(encoding="utf-8")
    linked = set(REF.findall(errata))
    claimants: dict[str, set[str]] = {}  # critique box -> whose claims the ledger records summarise it
    for f in (ROOT / "book" / "ledger").glob("*.json"):
        if f.name == "stability.json":
            continue
        for r in json.loads(f.read_text(encoding="utf-8"))["claims"]:
            for box in {r["link"], *r["critiques"]}:
                claimants.setdefault(box, set()).add(r.get("claimant", "source"))
    for title, name in _critique_boxes(_markdown(path)):
        assert name, f"{path.name}: critique box '{title}' has no :name: (the errata row must link to it)"
        by = claimants.get(name, {"source"})
        if "source" not in by:  # only the book's questions (implied, book): never an erratum (rule R8)
            assert name not in linked, f"{path.name}: box {name} holds only the book's questions, yet has an errata row"
            continue
        assert name in linked, f"{path.name}: critique box '{title}' ({name}) has no row in book/errata.md"


@pytest.mark.parametrize("page", ["errata.md"])
def test_every_link_of_the_summary_pages_resolves(page: str) -> None:
    text = (ROOT / "book" / page).read_text(encoding="utf-8")
    refs = REF.findall(text)
    assert refs, f"{page} links to nothing"
    missing = sorted(set(refs) - _targets())
    assert not missing, f"{page} links to targets that no notebook defines: {missing}"


@pytest.mark.parametrize("path", [p for p in NOTEBOOKS if not p.stem.endswith("_appendix")], ids=lambda p: p.name)
def test_chapter_skeleton(path: Path) -> None:
    headings = [line.lstrip("#").strip().lower() for line in _markdown(path).splitlines() if line.startswith("## ")]
    for part in SKELETON:
        assert any(h.startswith(part) or part in h for h in headings), (
            f"{path.name}: no section for '{part}' (skeleton: {', '.join(SKELETON)})"
        )
