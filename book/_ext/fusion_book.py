"""Local Sphinx extension of the book.

* ``.. fusion-versions::`` renders a table of the versions of the key packages that built
  the book, read with :func:`importlib.metadata.version` at build time.
* ``.. fusion-benchmarks::`` renders the last results of ``benchmarks/`` (JSON files in
  ``benchmarks/results/``).
* De-duplicates identical ``<script>`` entries: sphinx-thebe 0.3.1 registers its inline
  configuration script on every ``env-before-read-docs`` event, so pages declared
  ``const THEBE_JS_URL`` twice and the browser raised a ``SyntaxError``.
"""

from __future__ import annotations

import json
import platform
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path

from docutils import nodes
from sphinx.util.docutils import SphinxDirective

KEY_PACKAGES = (
    "fusion-book", "numpy", "scipy", "matplotlib", "pandas", "filterpy", "PyWavelets",
    "jupyter-book", "sphinx", "myst-nb", "nbval", "pytest", "hypothesis",
)


def _table(rows: list[tuple[str, ...]], header: tuple[str, ...]) -> nodes.table:
    ncols = len(header)
    table = nodes.table()
    group = nodes.tgroup(cols=ncols)
    table += group
    for _ in range(ncols):
        group += nodes.colspec(colwidth=1)
    head = nodes.thead()
    group += head
    body = nodes.tbody()
    group += body
    for target, cells in ((head, [header]), (body, rows)):
        for cells_of_row in cells:
            row = nodes.row()
            for text in cells_of_row:
                entry = nodes.entry()
                entry += nodes.paragraph(text=text)
                row += entry
            target += row
    return table


class FusionVersions(SphinxDirective):
    """Table of the Python and package versions used for this build."""

    has_content = False

    def run(self) -> list[nodes.Node]:
        rows = [("Python", platform.python_version())]
        for name in KEY_PACKAGES:
            try:
                rows.append((name, version(name)))
            except PackageNotFoundError:
                rows.append((name, "not installed"))
        return [_table(rows, ("package", "version"))]


class FusionBenchmarks(SphinxDirective):
    """Table of the measurements stored in ``benchmarks/results/*.json``."""

    has_content = False

    def run(self) -> list[nodes.Node]:
        root = Path(self.env.srcdir)
        rows: list[tuple[str, ...]] = []
        for path in sorted((root / "benchmarks" / "results").glob("*.json")):
            self.env.note_dependency(str(path))
            record = json.loads(path.read_text(encoding="utf-8"))
            machine = record.get("machine", "")
            for item in record.get("measurements", []):
                rows.append((item["what"], f"{item['value']:.4g} {item.get('unit', '')}".strip(),
                             record.get("date", ""), machine))
        if not rows:
            return [nodes.paragraph(text="No benchmark results are stored yet.")]
        return [_table(rows, ("measurement", "value", "measured on", "machine"))]


def _dedupe_scripts(app, pagename, templatename, context, doctree):  # noqa: ANN001
    scripts = context.get("script_files")
    if not scripts:
        return
    seen: set[tuple[object, ...]] = set()
    unique = []
    for script in scripts:
        # inline scripts are registered with filename None or "" (same script)
        filename = getattr(script, "filename", script) or ""
        key = (str(filename), tuple(sorted(getattr(script, "attributes", {}).items())))
        if key in seen:
            continue
        seen.add(key)
        unique.append(script)
    context["script_files"] = unique


def setup(app):  # noqa: ANN001, ANN201 - Sphinx entry point
    app.add_directive("fusion-versions", FusionVersions)
    app.add_directive("fusion-benchmarks", FusionBenchmarks)
    app.connect("html-page-context", _dedupe_scripts, priority=900)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
