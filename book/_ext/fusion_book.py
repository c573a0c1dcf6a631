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
* The claims ledger (``book/ledger/*.json``, written by the chapters through
  :mod:`fusion.book.ledger`) rendered for readers: ``.. fusion-verdicts-summary::`` (one line
  per source with status badges and its main finding), ``.. fusion-verdicts::`` (one section
  per source, one card per claim), ``.. fusion-in-brief:: <source key>`` (a chapter's opening
  box) and ``.. fusion-findings::`` (the introduction's findings); ``verdicts.csv`` and
  ``verdicts.json`` are generated into ``book/_generated/`` when the build starts, for download.
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
from docutils.parsers.rst import directives
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
                if "value" in item:
                    shown = f"{item['value']:.4g} {item.get('unit', '')}".strip()
                else:  # a validated call beside its kernel (bench_validation.py)
                    shown = f"{item['ratio']:.2f}× its kernel ({item['overhead_us']:.0f} µs more)"
                rows.append((item["what"], shown, record.get("date", ""), machine))
        if not rows:
            return [nodes.paragraph(text="No benchmark results are stored yet.")]
        return [_table(rows, ("measurement", "value", "measured on", "machine"))]


LEDGER_COLUMNS = ("id", "source", "source_short", "where", "claim", "published", "ours", "bound",
                  "status", "primary_status", "robustness", "assumptions", "link", "chapter", "headline")


def _ledger(root: Path) -> list[dict]:
    """Every record of ``book/ledger/*.json``, sources in book order (as :mod:`fusion.book.ledger`)."""
    from fusion.book.ledger import SOURCES

    records: list[dict] = []
    for path in sorted((root / "book" / "ledger").glob("*.json")):
        records.extend(json.loads(path.read_text(encoding="utf-8"))["claims"])

    def place(r: dict) -> tuple[int, int]:  # source in book order, then its chapters in reading order
        src = SOURCES[r["source"]]
        return src.order, src.chapters.index(r["chapter"]) if r["chapter"] in src.chapters else 0

    return sorted(records, key=place)


def _slug(status: str) -> str:
    return status.replace(" ", "-")


def _badge(status: str, count: int | None = None) -> nodes.inline:
    text = status if count is None else f"{count} {status}"
    return nodes.inline(text=text, classes=["status-badge", f"status-{_slug(status)}"])


class _LedgerDirective(SphinxDirective):
    has_content = False

    def records(self) -> list[dict]:
        root = Path(self.env.srcdir)
        for path in (root / "book" / "ledger").glob("*.json"):
            self.env.note_dependency(str(path))
        return _ledger(root)

    def markdown(self, lines: list[str], node: nodes.Element) -> None:
        from docutils.statemachine import StringList

        self.state.nested_parse(StringList(lines, source="ledger"), self.content_offset, node)

    def docpath(self, chapter: str) -> str:
        """Path of a chapter relative to the current document, for {doc}."""
        import posixpath

        here = posixpath.dirname(self.env.docname)
        return posixpath.relpath(chapter, here or ".")

    def badges(self, recs: list[dict]) -> nodes.paragraph:
        from fusion.book.ledger import STATUSES

        para = nodes.paragraph(classes=["status-badges"])
        for st in STATUSES:
            n = sum(r["status"] == st for r in recs)
            if n:
                para += _badge(st, n)
                para += nodes.Text(" ")
        return para

    def card(self, r: dict, chapter_link: bool) -> nodes.container:
        box = nodes.container(classes=["claim-card", f"status-{_slug(r['status'])}"])
        head = nodes.paragraph(classes=["claim-head"])
        head += _badge(r["status"])
        head += nodes.Text(" ")
        head += nodes.strong(text=r["where"])
        if r["robustness"]:
            head += nodes.Text(" · ")
            head += nodes.emphasis(text=r["robustness"])
        box += head
        lines = [r["claim"], ""]
        lines.append(f"**Published:** {r['published']}. **Ours:** {r['ours']}.")
        if r["bound"]:
            lines.append(f"**Exact value or bound:** {r['bound']}.")
        if r["assumptions"]:
            lines.append("**Assumes:** " + "; ".join(r["assumptions"]) + ".")
        if r["alternatives"]:
            alts = "; ".join(f"{a['reading']}: *{a['status']}*" for a in r["alternatives"])
            lines.append(f"**Other readings** ({r['robustness']}): {alts}.")
        lines.append(f"{{ref}}`Evidence <{r['link']}>`")
        self.markdown(lines, box)
        return box


class FusionVerdictsSummary(_LedgerDirective):
    """One block per source: title, status badges, the headline finding."""

    def run(self) -> list[nodes.Node]:
        from fusion.book.ledger import SOURCES

        recs = self.records()
        out = nodes.container(classes=["verdicts-summary"])
        for key, src in sorted(SOURCES.items(), key=lambda kv: kv[1].order):
            mine = [r for r in recs if r["source"] == key]
            if not mine:
                continue
            block = nodes.container(classes=["source-summary"])
            self.markdown([f"**{src.short}: {src.title}** ({{doc}}`chapter <{self.docpath(src.chapter)}>`)"], block)
            block += self.badges(mine)
            head = [r for r in mine if r["headline"]]
            if head:
                robust = f" ({head[0]['robustness']})" if head[0]["robustness"] else ""
                self.markdown([f"*Main finding:* {head[0]['claim']} → **{head[0]['status']}**{robust}. "
                               f"Ours: {head[0]['ours']}."], block)
            out += block
        return [out]


class FusionVerdicts(_LedgerDirective):
    """One section per source in book order, one card per claim."""

    def run(self) -> list[nodes.Node]:
        from fusion.book.ledger import SOURCES

        recs = self.records()
        out: list[nodes.Node] = []
        for key, src in sorted(SOURCES.items(), key=lambda kv: kv[1].order):
            mine = [r for r in recs if r["source"] == key]
            if not mine:
                continue
            sec = nodes.section(ids=[f"verdicts-{key}"], names=[f"verdicts-{key}"])
            sec += nodes.title(text=f"{src.short}: {src.title}")
            for r in mine:
                sec += self.card(r, chapter_link=True)
            out.append(sec)
        return out


class FusionInBrief(_LedgerDirective):
    """A chapter's opening box: status badges and one line per claim.

    ``.. fusion-in-brief:: <source key>`` shows every claim of the source; with
    ``:chapter: <docname>`` only the claims whose evidence is in that chapter (for a source that
    spans several chapters).
    """

    required_arguments = 1
    option_spec = {"chapter": directives.unchanged_required}

    def run(self) -> list[nodes.Node]:
        key = self.arguments[0]
        recs = [r for r in self.records() if r["source"] == key]
        if "chapter" in self.options:
            recs = [r for r in recs if r["chapter"] == self.options["chapter"].strip()]
        box = nodes.admonition(classes=["in-brief"])
        box += nodes.title(text="In brief")
        if not recs:
            box += nodes.paragraph(text="No claims recorded yet for this source.")
            return [box]
        box += self.badges(recs)
        items = nodes.bullet_list()
        for r in recs:
            item = nodes.list_item()
            robust = f" *{r['robustness']}*." if r["robustness"] else ""
            self.markdown([f"**{r['where']}**: {r['claim']}{robust} ({{ref}}`evidence <{r['link']}>`)"], item)
            first = item.next_node(nodes.paragraph)
            if first is not None:  # the badge leads the line
                first.insert(0, nodes.Text(" "))
                first.insert(0, _badge(r["status"]))
            items += item
        box += items
        return [box]


class FusionFindings(_LedgerDirective):
    """The introduction's main findings: one line per source."""

    def run(self) -> list[nodes.Node]:
        from fusion.book.ledger import SOURCES

        recs = self.records()
        items = nodes.bullet_list()
        for key, src in sorted(SOURCES.items(), key=lambda kv: kv[1].order):
            head = [r for r in recs if r["source"] == key and r["headline"]]
            if not head:
                continue
            item = nodes.list_item()
            self.markdown([f"**{src.short}** ({{doc}}`chapter <{self.docpath(src.chapter)}>`): "
                           f"{head[0]['claim']}"], item)
            para = item.next_node(nodes.paragraph)
            if para is not None:
                para += nodes.Text(" ")
                para += _badge(head[0]["status"])
            items += item
        return [items]


def _export_ledger(app) -> None:  # noqa: ANN001
    """Write ``book/_generated/verdicts.csv`` and ``.json`` from the ledger (for download)."""
    import csv

    root = Path(app.srcdir)
    recs = _ledger(root)
    out = root / "book" / "_generated"
    out.mkdir(exist_ok=True)
    (out / "verdicts.json").write_text(json.dumps(recs, ensure_ascii=False, indent=1) + "\n", encoding="utf-8")
    with (out / "verdicts.csv").open("w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow(LEDGER_COLUMNS)
        for r in recs:
            w.writerow(["; ".join(r[c]) if isinstance(r[c], list) else r[c] for c in LEDGER_COLUMNS])


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
    app.add_directive("fusion-verdicts-summary", FusionVerdictsSummary)
    app.add_directive("fusion-verdicts", FusionVerdicts)
    app.add_directive("fusion-in-brief", FusionInBrief)
    app.add_directive("fusion-findings", FusionFindings)
    app.connect("builder-inited", _export_ledger)
    app.connect("html-page-context", _dedupe_scripts, priority=900)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
