"""Local Sphinx extension of the book.

* ``.. fusion-versions::`` renders the versions pinned in ``requirements.lock`` for the key
  packages beside those that built the book (read with :func:`importlib.metadata.version` at
  build time), and the number of pins in the lock.
* Nitpicky builds (``-n``, as in ``make test``): type phrases of numpydoc sections ("ndarray,
  shape (K, N)", "array_like", "dict {...}") become ``py:class`` references that no inventory
  can resolve (the build is offline, so no intersphinx either). Such references are ignored
  unless they name ``fusion.``; so are references to the third-party libraries (numpy, scipy,
  pandas, matplotlib, filterpy, PyWavelets), whose documentation is not part of the book. Every
  other reference (``fusion`` functions, classes and data, labels, equations, citations, glue
  keys) must resolve. The "Modules" section of the package docstrings is a napoleon custom
  section (a rubric), so the API page does not get one duplicate "modules" target per package.
* ``.. fusion-benchmarks::`` renders the last results of ``benchmarks/`` (JSON files in
  ``benchmarks/results/``).
* De-duplicates identical ``<script>`` entries: sphinx-thebe 0.3.1 registers its inline
  configuration script on every ``env-before-read-docs`` event, so pages declared
  ``const THEBE_JS_URL`` twice and the browser raised a ``SyntaxError``.
"""

from __future__ import annotations

import json
import platform
import re
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


_PIN = re.compile(r"^([A-Za-z0-9][A-Za-z0-9._-]*)==([^\s;]+)")


def _canonical(name: str) -> str:
    return re.sub(r"[-_.]+", "-", name).lower()


def locked_versions(lock: Path) -> dict[str, str]:
    """``canonical name -> version`` of the exact pins of a lock file (first pin of a name)."""
    pins: dict[str, str] = {}
    for line in lock.read_text(encoding="utf-8").splitlines():
        m = _PIN.match(line.strip())
        if m:
            pins.setdefault(_canonical(m[1]), m[2])
    return pins


class FusionVersions(SphinxDirective):
    """Table of the locked and installed versions of Python and the key packages."""

    has_content = False

    def run(self) -> list[nodes.Node]:
        lock = Path(self.env.srcdir) / "requirements.lock"
        self.env.note_dependency(str(lock))
        pins = locked_versions(lock) if lock.is_file() else {}
        rows = [("Python", ">= 3.11 (every platform)", platform.python_version())]
        for name in KEY_PACKAGES:
            try:
                installed = version(name)
            except PackageNotFoundError:
                installed = "not installed"
            locked = "the package itself" if name == "fusion-book" else pins.get(_canonical(name), "not locked")
            rows.append((name, locked, installed))
        note = nodes.paragraph(text=(
            f"requirements.lock pins {len(pins)} packages in all (make lock regenerates it from "
            "pyproject.toml); make book and make test install exactly these."))
        return [_table(rows, ("package", "locked", "built with")), note]


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


#: Targets that nitpicky builds ignore: type phrases and third-party names (see above).
NITPICK_IGNORE_REGEX = [
    ("py:class", r"(?!fusion\.).*"),
    (r"py:(func|meth|class|data|attr|mod|obj)", r"(numpy|scipy|pandas|matplotlib|filterpy|pywt)(\..*)?"),
]


def _nitpick_ignores(app, config):  # noqa: ANN001
    config.nitpick_ignore_regex = list(config.nitpick_ignore_regex) + NITPICK_IGNORE_REGEX
    sections = list(getattr(config, "napoleon_custom_sections", None) or [])
    if "Modules" not in sections:
        config.napoleon_custom_sections = [*sections, "Modules"]


def setup(app):  # noqa: ANN001, ANN201 - Sphinx entry point
    app.connect("config-inited", _nitpick_ignores)
    app.add_directive("fusion-versions", FusionVersions)
    app.add_directive("fusion-benchmarks", FusionBenchmarks)
    app.connect("html-page-context", _dedupe_scripts, priority=900)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
