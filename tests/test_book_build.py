"""The book builds with warnings as errors and nitpicky references, with or without Chromium.

The build itself (``book_html`` in conftest.py: ``jupyter-book build -W -n`` from the committed
notebook outputs) fails on a missing glue key, a broken cross-reference, equation or citation;
tests/test_browser.py then opens the same build in Chromium where it is installed.
"""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml

ROOT = Path(__file__).resolve().parents[1]


def _toc_files(entry: dict) -> list[str]:
    files = [entry["file"]] if "file" in entry else []
    for key in ("chapters", "sections", "parts"):
        for child in entry.get(key, []):
            files += _toc_files(child)
    return files


def test_every_page_of_the_toc_is_built(book_html: Path) -> None:
    toc = yaml.safe_load((ROOT / "_toc.yml").read_text(encoding="utf-8"))
    files = [toc["root"]] + [f for part in toc.get("parts", []) for f in _toc_files(part)]
    assert any(f.startswith("notebooks/") for f in files)
    missing = [f for f in files if not (book_html / f"{Path(f).with_suffix('')}.html").is_file()]
    assert not missing, f"pages of _toc.yml missing from the build: {missing}"


def test_status_page_lists_the_locked_versions(book_html: Path) -> None:
    html = (book_html / "book" / "status.html").read_text(encoding="utf-8")
    lock = (ROOT / "requirements.lock").read_text(encoding="utf-8")
    numpy_pin = next(line.split("==")[1].split()[0] for line in lock.splitlines() if line.startswith("numpy=="))
    assert "requirements.lock pins" in html and numpy_pin in html


def test_source_pages_only_for_modules_with_documented_objects(book_html: Path) -> None:
    """A parallel Sphinx read (tools/build_book.py) leaves viewcode records of modules no documented object
    uses; book/_ext/fusion_book.py drops them as a serial build does: no source page for a re-exporting package or
    for the standard library."""
    modules = book_html / "_modules"
    assert (modules / "fusion" / "readings" / "fusion_set.html").is_file()
    for stray in ("pathlib.html", "fusion/book/chapters/ci.html", "fusion/book/chapters/chernoff.html",
                  "fusion/estimates/chernoff.html"):
        assert not (modules / stray).exists(), stray


def test_sphinx_jobs_from_the_environment(monkeypatch: pytest.MonkeyPatch) -> None:
    import importlib.util

    spec = importlib.util.spec_from_file_location("fusion_build_book", ROOT / "tools" / "build_book.py")
    tool = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(tool)  # type: ignore[union-attr]
    monkeypatch.setenv("FUSION_SPHINX_JOBS", "3")
    assert tool.jobs() == 3
    monkeypatch.delenv("FUSION_SPHINX_JOBS")
    assert tool.jobs() >= 1
    for bad in ("0", "-1", "two", ""):
        monkeypatch.setenv("FUSION_SPHINX_JOBS", bad)
        with pytest.raises(SystemExit, match="FUSION_SPHINX_JOBS"):
            tool.jobs()


def _book_extension():  # noqa: ANN202
    import importlib.util

    spec = importlib.util.spec_from_file_location("fusion_book_ext", ROOT / "book" / "_ext" / "fusion_book.py")
    ext = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(ext)  # type: ignore[union-attr]
    return ext


def test_work_is_shared_by_cost() -> None:
    """The parallel write and the source pages (book/_ext/fusion_book.py) give each worker about equal work."""
    balanced = _book_extension()._balanced
    items = [("api", 100), ("a", 30), ("b", 30), ("c", 25), ("d", 10), ("e", 5)]
    bins = balanced(items, 2)
    assert sorted(n for b in bins for n in b) == sorted(n for n, _ in items)
    assert all(b == sorted(b) for b in bins)
    cost = dict(items)
    assert sorted(sum(cost[n] for n in b) for b in bins) == [100, 100]
    assert balanced(items[:1], 3) == [["api"]]


def test_pages_written_by_workers_are_indexed_and_show_their_images(book_html: Path) -> None:
    """A document written by a worker (book/_ext/fusion_book.py ``_write_in_workers``) is in the search index
    under its title, and every image a page shows was copied into the build."""
    import json
    import re

    text = (book_html / "searchindex.js").read_text(encoding="utf-8")
    index = json.loads(text[text.index("(") + 1:text.rindex(")")])
    toc = yaml.safe_load((ROOT / "_toc.yml").read_text(encoding="utf-8"))
    files = [toc["root"]] + [f for part in toc.get("parts", []) for f in _toc_files(part)]
    assert sorted(index["docnames"]) == sorted(files)
    assert all(title for title in index["titles"])
    assert {"covari", "intersect"} <= set(index["terms"]), "words of the chapters are missing from the index"
    shown = 0
    for page in book_html.rglob("*.html"):
        for src in re.findall(r'<img[^>]+src="([^"]+)"', page.read_text(encoding="utf-8")):
            if "://" in src or src.startswith("data:"):
                continue
            shown += 1
            assert (page.parent / src).resolve().is_file(), f"{page.relative_to(book_html)} shows a missing {src}"
    assert shown > 10


def test_documents_without_numbered_nodes_are_told_apart() -> None:
    """Figure numbering skips a document only when nothing in it could be numbered or lead to another document."""
    from types import SimpleNamespace

    from docutils import nodes
    from sphinx import addnodes

    numbers_something = _book_extension()._numbers_something
    domain = SimpleNamespace(get_enumerable_node_type=lambda node: "figure" if isinstance(node, nodes.figure) else None)
    env = SimpleNamespace(domains={"std": domain})

    def doc(*children: nodes.Node) -> nodes.document:
        d = nodes.document(None, None)
        section = nodes.section(ids=["s"])
        section += [nodes.title(text="T"), nodes.paragraph(text="p"), *children]
        d += section
        return d

    assert not numbers_something(env, doc())
    assert not numbers_something(env, doc(nodes.figure()))          # a figure without ids gets no number
    assert numbers_something(env, doc(nodes.figure(ids=["fig-1"])))
    assert numbers_something(env, doc(addnodes.toctree()))
