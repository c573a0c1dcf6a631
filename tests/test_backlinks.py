"""API entries link back to the pages that name them (book/_ext/fusion_backlinks.py)."""
from __future__ import annotations

import importlib.util
import json
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
spec = importlib.util.spec_from_file_location("fusion_backlinks", ROOT / "book" / "_ext" / "fusion_backlinks.py")
B = importlib.util.module_from_spec(spec)
spec.loader.exec_module(B)  # type: ignore[union-attr]


def test_roles_are_found_in_every_form(tmp_path: Path) -> None:
    (tmp_path / "notebooks").mkdir()
    (tmp_path / "book").mkdir()
    cells = [{"cell_type": "markdown", "source": ["# Chapter X\n", "{py:func}`fusion.a.f` and {py:func}`~fusion.a.g`"]},
             {"cell_type": "code", "source": ["{py:func}`fusion.a.code_only`"]},
             {"cell_type": "markdown", "source": ["{py:class}`the class <fusion.b.C>`, {py:func}`fusion.a.f` again"]}]
    (tmp_path / "notebooks" / "01_x.ipynb").write_text(json.dumps({"cells": cells}), encoding="utf-8")
    (tmp_path / "book" / "page.md").write_text("# A page\n\n{py:mod}`fusion.a`\n", encoding="utf-8")
    found = B.named_objects(tmp_path)
    assert found == {"fusion.a.f": [("notebooks/01_x", "Chapter X")], "fusion.a.g": [("notebooks/01_x", "Chapter X")],
                     "fusion.b.C": [("notebooks/01_x", "Chapter X")], "fusion.a": [("book/page", "A page")]}


def test_a_re_export_resolves_to_its_defining_module() -> None:
    assert B.canonical("fusion.readings.optimal_fusion_set") == "fusion.readings.fusion_set.optimal_fusion_set"
    assert B.canonical("fusion.readings") == "fusion.readings"
    assert B.canonical("fusion.no_such_module.f") == "fusion.no_such_module.f"


def test_every_named_api_entry_links_back(book_html: Path) -> None:
    html = (book_html / "book" / "api.html").read_text(encoding="utf-8")
    named = {B.canonical(t) for t in B.named_objects(ROOT)}
    documented = [t for t in named if f'id="{t}"' in html]
    assert len(named) >= 7, "each chapter names the functions it derives with a {py:func} role"
    assert len(documented) >= len(named) // 2, "most named objects should be documented on the API page"
    ids = [(m.start(), m["id"]) for m in re.finditer(r'id="(?P<id>fusion\.[\w.]+)"', html)]
    for t in documented:
        start = html.index(f'id="{t}"')
        # the entry runs to the next object that is not one of its own members (a class's attributes)
        end = next((pos for pos, i in ids if pos > start and not i.startswith(t + ".")), len(html))
        assert "In the book" in html[start:end], f"{t}: no link back to the pages that name it"
    assert not re.search(r"In the book.{0,400}notebooks/[^\"]*\.ipynb", html, flags=re.S)
