"""API entries link back to the chapters: "In the book" under every object a chapter's prose names.

A chapter names a function in its prose with a role (``{py:func}`fusion.readings.fusion_set.optimal_fusion_set```,
also ``{py:class}``, ``{py:mod}``, ``~`` and ``title <target>`` forms). At ``builder-inited`` this extension reads
every notebook's markdown cells and every ``book/*.md`` page for such roles; when autodoc documents an object
so named, its docstring gets an "In the book" rubric listing the pages (chapter first, then its appendix) that
name it, each linked with ``:doc:``. The link from the equation to the code (the role) and back (the rubric)
come from the same text, so they cannot drift apart.
"""
from __future__ import annotations

import json
import re
from pathlib import Path

ROLE = re.compile(r"\{py:(?:func|class|mod|meth|data|obj)\}`~?(?:[^`<]*<)?~?(?P<target>fusion\.[\w.]+)>?`")


def named_objects(root: Path) -> dict[str, list[tuple[str, str]]]:
    """``{object: [(docname, title), ...]}`` for every fusion object a page names with a Python role."""
    found: dict[str, list[tuple[str, str]]] = {}

    def note(docname: str, title: str, text: str) -> None:
        for m in ROLE.finditer(text):
            pages = found.setdefault(m["target"], [])
            if (docname, title) not in pages:
                pages.append((docname, title))

    for nb in sorted((root / "notebooks").glob("*.ipynb")):
        cells = json.loads(nb.read_text(encoding="utf-8"))["cells"]
        text = "\n".join("".join(c["source"]) for c in cells if c["cell_type"] == "markdown")
        m = re.search(r"^# (.+)$", text, flags=re.M)
        note(f"notebooks/{nb.stem}", m[1].strip() if m else nb.stem, text)
    for md in sorted((root / "book").glob("*.md")):
        text = md.read_text(encoding="utf-8")
        m = re.search(r"^# (.+)$", text, flags=re.M)
        note(f"book/{md.stem}", m[1].strip() if m else md.stem, text)
    return found


def canonical(target: str) -> str:
    """``module.qualname`` of the object a dotted name imports (a re-export names its defining module)."""
    import importlib

    parts = target.split(".")
    for i in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:i]))
        except ImportError:
            continue
        try:
            for attr in parts[i:]:
                obj = getattr(obj, attr)
        except AttributeError:
            return target
        mod, qual = getattr(obj, "__module__", None), getattr(obj, "__qualname__", None)
        return f"{mod}.{qual}" if mod and qual and i < len(parts) else target
    return target


def _collect(app) -> None:  # noqa: ANN001
    merged: dict[str, list[tuple[str, str]]] = {}
    for target, pages in named_objects(Path(app.srcdir)).items():
        into = merged.setdefault(canonical(target), [])
        into += [p for p in pages if p not in into]
    app.env.fusion_backlinks = merged


def _rubric(app, what, name, obj, options, lines) -> None:  # noqa: ANN001
    pages = getattr(app.env, "fusion_backlinks", {}).get(name)
    if not pages:
        return
    titles = [re.sub(r"[`*_]", "", title) for _, title in pages]
    lines += ["", ".. rubric:: In the book", ""]
    lines += [f"- :doc:`{t} </{doc}>`" for (doc, _), t in zip(pages, titles)]
    lines.append("")


def setup(app):  # noqa: ANN001, ANN201 - Sphinx entry point
    app.connect("builder-inited", _collect)
    app.connect("autodoc-process-docstring", _rubric, priority=900)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
