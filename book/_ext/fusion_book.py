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
  per source with status badges and its main finding), ``.. fusion-verdicts::`` (one table row
  per claim, filterable by source, status and claimant, details collapsed), ``.. fusion-in-brief::
  <source key>`` (a chapter's opening box: the headline and a few key findings) and
  ``.. fusion-findings::`` (the introduction's findings, with our number and what to use instead);
  every status badge carries its definition as a tooltip; ``verdicts.csv`` and
  ``verdicts.json`` are generated into ``book/_generated/`` when the build starts, for download.
* De-duplicates identical ``<script>`` entries: sphinx-thebe 0.3.1 registers its inline
  configuration script on every ``env-before-read-docs`` event, so pages declared
  ``const THEBE_JS_URL`` twice and the browser raised a ``SyntaxError``.
* The sidebar's global toctree (``titles_only``, drawn on each of the ~90 pages, the ``[source]`` pages
  included) copies every document's table of contents and then keeps only its title and sub-toctrees.
  The API page's table of contents is ~90 % of all (one entry per documented object), so that copy was
  a quarter of the build. :func:`titles_only_toctree` copies such a document's title only: the same
  HTML (a document whose table of contents holds a toctree is copied in full, as before).
* The write phase of a parallel build (``tools/build_book.py``) runs in the workers: Sphinx 7.4 resolves every
  document (references, post-transforms) and feeds the search index in the main process, warms up by writing the
  first document (the API page, the largest) there too, and leaves the forked workers only the HTML translation,
  so on two cores one core resolved while the other mostly waited. :func:`_write_in_workers` gives each worker
  whole documents to resolve, index and write, and merges their search-index entries and images back in document
  order. ``sphinx.ext.viewcode``'s ``[source]`` pages are highlighted and written by the workers too
  (:func:`_viewcode_pages_in_workers`; Sphinx does them one after the other when the build ends).
* Figure numbers (``numfig``, on in jupyter-book) are assigned in the main process after reading, by unpickling
  and walking every document; the API page is half of all pickled pages and numbers nothing.
  :func:`_note_unnumbered` records, while each document is read (in the workers), whether it holds a node that
  could be numbered or a toctree; :func:`_figure_numbers_skip_unnumbered` lets the walk skip the others (walking
  them registers nothing and moves no counter, so the numbers are the same).
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
                    if "cpu_seconds" in item:  # a command of bench_book.py: its CPU and the machine's load before it
                        shown += f" ({item['cpu_seconds']:.0f} CPU-s; load {item['load_before']:.1f} before)"
                else:  # a validated call beside its kernel (bench_validation.py)
                    shown = f"{item['ratio']:.2f}× its kernel ({item['overhead_us']:.0f} µs more)"
                rows.append((item["what"], shown, item.get("measured_on", record.get("date", "")), machine))
        if not rows:
            return [nodes.paragraph(text="No benchmark results are stored yet.")]
        return [_table(rows, ("measurement", "value", "measured on", "machine"))]


LEDGER_COLUMNS = ("id", "source", "source_short", "where", "claim", "claimant", "test", "published", "ours",
                  "ours_brief", "bound", "status", "primary_status", "robustness", "runs", "margin", "rule",
                  "assumptions", "link", "chapter", "headline")

#: The reseeding sweep's results in book/ledger (fusion.book.stability.STABILITY_FILE).
STABILITY_FILE = "stability.json"

#: How many items an In-brief box shows at most (the headline first).
IN_BRIEF_ITEMS = 5

#: Order in which an In-brief box picks the source's claims after the headline: the findings a reader most needs.
_BRIEF_ORDER = ("contradicted", "not reproduced", "cannot be checked", "not distinguishable",
                "reproduced under stated assumptions", "reproduced")

#: Words of "ours" shown in a table row or a brief line (the whole text is in the row's details).
_BRIEF_WORDS = 28


def _ledger(root: Path) -> list[dict]:
    """Every record of ``book/ledger/*.json``, sources in book order (as :mod:`fusion.book.ledger`)."""
    from fusion.book.ledger import SOURCES

    records: list[dict] = []
    for path in sorted((root / "book" / "ledger").glob("*.json")):
        if path.name == STABILITY_FILE:
            continue
        records.extend(json.loads(path.read_text(encoding="utf-8"))["claims"])
    stab = root / "book" / "ledger" / STABILITY_FILE
    if stab.is_file():  # the reseeding sweep's results (make stability), per stochastic record
        sweep = json.loads(stab.read_text(encoding="utf-8"))
        for r in records:
            v = sweep["records"].get(r["id"])
            if v is not None:
                r["stability"] = {"k": v["k"], "K": v["K"], "flag": v["flag"], "scaled": v["scaled"],
                                  "runs_factor": v.get("runs_factor", sweep["runs_factor"])}

    def place(r: dict) -> tuple[int, int]:  # source in book order, then its chapters in reading order
        src = SOURCES[r["source"]]
        return src.order, src.chapters.index(r["chapter"]) if r["chapter"] in src.chapters else 0

    return sorted(records, key=place)


def _slug(status: str) -> str:
    return status.replace(" ", "-")


def _badge(status: str, count: int | None = None) -> nodes.raw:
    """A status badge whose tooltip gives the status's definition (the legend where the status appears)."""
    import html

    from fusion.book.ledger import STATUS_DEFINITIONS

    text = status if count is None else f"{count} {status}"
    tip = html.escape(STATUS_DEFINITIONS.get(status, ""), quote=True)
    return nodes.raw("", f'<span class="status-badge status-{_slug(status)}" title="{tip}">{html.escape(text)}</span>',
                     format="html")


def _count(n: int, noun: str) -> str:
    """"1 claim", "3 claims"."""
    return f"{n} {noun}" + ("" if n == 1 else "s")


def _short(text: str, words: int = _BRIEF_WORDS) -> str:
    parts = text.split()
    return text if len(parts) <= words else " ".join(parts[:words]) + " …"


def _stability(v: dict) -> str:
    """"stable in k/K reseeds", and whether the status changes at the scaled run count.

    A stable record (not flagged: every reseed and the scaled run agree, up to R5's qualifier) gets the short form;
    a record that moves gets the scaled run's status, named as the primary reading's.
    """
    text = f"stable in {v['k']}/{v['K']} reseeds"   # k/K: one word, on every stochastic row of the Verdicts page
    if not v["flag"]:
        return text + (f" and at {v['runs_factor']}× runs" if v["scaled"] is not None else "")
    if v["scaled"] is not None:
        text += f"; the primary reading at {v['runs_factor']}× the runs: {v['scaled']}"
    return text + " (flagged)"


def _whose(r: dict) -> str:
    return {"source": "", "implied": "the book's reading of the source's purpose",
            "book": "the book's own question"}[r.get("claimant", "source")]


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

    def verdicts_uri(self, key: str) -> str:
        """Relative URI of the Verdicts table filtered to one source."""
        import posixpath

        here = posixpath.dirname(self.env.docname)
        return posixpath.relpath("book/verdicts", here or ".") + f".html#verdicts-{key}"

    def badges(self, recs: list[dict]) -> nodes.paragraph:
        from fusion.book.ledger import STATUSES

        para = nodes.paragraph(classes=["status-badges"])
        for st in STATUSES:
            n = sum(r["status"] == st for r in recs)
            if n:
                para += _badge(st, n)
                para += nodes.Text(" ")
        return para

    def lead_badge(self, node: nodes.Element, status: str) -> None:
        """Put a status badge at the start of the first paragraph of ``node``."""
        first = node.next_node(nodes.paragraph)
        if first is not None:
            first.insert(0, nodes.Text(" "))
            first.insert(0, _badge(status))


class FusionVerdictsSummary(_LedgerDirective):
    """One block per source: title, status badges, the main finding with our number."""

    def run(self) -> list[nodes.Node]:
        from fusion.book.ledger import SOURCES

        recs = self.records()
        out = nodes.container(classes=["verdicts-summary"])
        for key, src in sorted(SOURCES.items(), key=lambda kv: kv[1].order):
            mine = [r for r in recs if r["source"] == key]
            if not mine:
                continue
            block = nodes.container(classes=["source-summary"])
            own = [r for r in mine if r.get("claimant", "source") == "source"]
            self.markdown([f"**{src.short}: {src.title}** ({{doc}}`chapter <{self.docpath(src.chapter)}>`): "
                           f"{_count(len(own), 'claim')} of the source:"], block)
            block += self.badges(own)
            if len(mine) > len(own):
                self.markdown([f"and {_count(len(mine) - len(own), 'question')} of the book:"], block)
                block += self.badges([r for r in mine if r not in own])
            head = [r for r in mine if r["headline"]]
            if head:
                item = nodes.container()
                self.markdown([f"*Main finding:* {head[0]['claim']} Ours: {head[0]['ours_brief']}."], item)
                self.lead_badge(item, head[0]["status"])
                block += item
            out += block
        return [out]


class FusionVerdicts(_LedgerDirective):
    """Every claim as one row of one table, filterable by source, status and claimant; details on demand."""

    def row(self, r: dict) -> nodes.row:
        from fusion.book.ledger import SOURCES

        row = nodes.row(classes=["verdict-row", f"src-{r['source']}", f"st-{_slug(r['status'])}",
                                 f"by-{r.get('claimant', 'source')}"])
        src = SOURCES[r["source"]]
        cells = [
            [f"{src.short.split(' (')[0]}, {r['where']}"],
            [r["claim"] + (f" *({_whose(r)})*" if _whose(r) else "")],
            [],
            [_short(r["ours_brief"]) + f" ({{ref}}`evidence <{r['link']}>`)"],
        ]
        for i, lines in enumerate(cells):
            entry = nodes.entry()
            if i == 2:
                para = nodes.paragraph()
                para += _badge(r["status"])
                entry += para
                if r["robustness"]:   # "the claim holds under k of n ..." (R5), in the table's short form
                    entry += nodes.paragraph(text=re.sub(r"^the claim holds under", "holds under", r["robustness"]),
                                             classes=["verdict-robustness"])
                if "stability" in r:
                    entry += nodes.paragraph(text=_stability(r["stability"]),
                                             classes=["verdict-robustness"] + (["verdict-flag"] if r["stability"]["flag"] else []))
            else:
                self.markdown(lines, entry)
            if i == 3:
                self.details(r, entry)
            row += entry
        return row

    def details(self, r: dict, entry: nodes.entry) -> None:
        """The record's published value, full evidence, bound, assumptions and readings, collapsed."""
        lines = [f"**Published:** {r['published']}.", "", f"**Ours:** {r['ours']}."]
        if r.get("margin"):
            lines += ["", f"**Practical margin:** ±{r['margin']:g} (rule {r.get('rule') or 'R2'})."]
        if r["bound"]:
            lines += ["", f"**Exact value or bound:** {r['bound']}."]
        if r["assumptions"]:
            lines += ["", "**Assumes:** " + "; ".join(r["assumptions"]) + "."]
        for a in r["alternatives"]:
            runs = f", {a['runs']} runs" if a.get("runs") else ""
            tag = "" if a.get("counted", True) else f" *(shown apart: {a.get('not_counted_because', '')})*"
            lines += ["", f"- {a['choice']}: {a['reading']} → **{a['status']}**{runs}{tag}"]
        entry += nodes.raw("", '<details class="verdict-details"><summary>details</summary>', format="html")
        self.markdown(lines, entry)
        entry += nodes.raw("", "</details>", format="html")

    def controls(self) -> nodes.raw:
        import html

        from fusion.book.ledger import SOURCES, STATUSES

        src = "".join(f'<option value="src-{k}">{html.escape(s.short)}</option>'
                      for k, s in sorted(SOURCES.items(), key=lambda kv: kv[1].order))
        st = "".join(f'<option value="st-{_slug(s)}">{html.escape(s)}</option>' for s in STATUSES)
        anchors = "".join(f'<span id="verdicts-{k}" class="verdict-anchor"></span>' for k in SOURCES)
        return nodes.raw("", (
            anchors + '<div class="verdict-filters" role="search">'
            f'<label>Source <select data-filter="src"><option value="">all</option>{src}</select></label> '
            f'<label>Status <select data-filter="st"><option value="">all</option>{st}</select></label> '
            '<label>Whose claim <select data-filter="by"><option value="">all</option>'
            '<option value="by-source">printed in the source</option>'
            '<option value="by-implied">the book\'s reading of its purpose</option>'
            '<option value="by-book">the book\'s own question</option></select></label> '
            '<span class="verdict-count" aria-live="polite"></span></div>'), format="html")

    def run(self) -> list[nodes.Node]:
        recs = self.records()
        table = nodes.table(classes=["verdicts-table", "colwidths-given"])
        group = nodes.tgroup(cols=4)
        table += group
        for w in (14, 40, 14, 32):
            group += nodes.colspec(colwidth=w)
        head = nodes.thead()
        hrow = nodes.row()
        for h in ("where", "claim", "status", "ours"):
            e = nodes.entry()
            e += nodes.paragraph(text=h)
            hrow += e
        head += hrow
        group += head
        body = nodes.tbody()
        for r in recs:
            body += self.row(r)
        group += body
        return [self.controls(), table]


class FusionInBrief(_LedgerDirective):
    """A chapter's opening box: the headline first, a few key findings with our numbers, a link to all claims.

    ``.. fusion-in-brief:: <source key>`` shows the source's claims; with ``:chapter: <docname>`` only
    those whose evidence is in that chapter. At most :data:`IN_BRIEF_ITEMS` items: the source's main
    finding (marked), then the source's own claims in the order of :data:`_BRIEF_ORDER`.
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
        own = [r for r in recs if r.get("claimant", "source") == "source"]
        head = [r for r in own if r["headline"]]
        rest = sorted((r for r in own if not r["headline"]), key=lambda r: _BRIEF_ORDER.index(r["status"]))
        pick = (head + rest)[:IN_BRIEF_ITEMS]
        items = nodes.bullet_list()
        for r in pick:
            item = nodes.list_item()
            mark = "**Main finding.** " if r["headline"] else ""
            self.markdown([f"{mark}{r['claim']} Ours: {_short(r['ours_brief'])} "
                           f"({r['where']}; {{ref}}`evidence <{r['link']}>`)"], item)
            self.lead_badge(item, r["status"])
            items += item
        box += items
        moved = [r for r in recs if r.get("stability", {}).get("flag")]
        if moved:  # issue 34: a status that moves under reseeding or at more runs is named in its chapter
            lines = ["**Under reseeding** (the same rules on fresh seeds and at more runs) these statuses move: "
                     + "; ".join(f"{r['where']} (record `{r['id']}`, {r['status']}: {_stability(r['stability'])}; {{ref}}`readings <"
                                 f"{'readings-' + r['id'] if r['alternatives'] else r['link']}>`)" for r in moved) + "."]
            note = nodes.container(classes=["in-brief-moved"])
            self.markdown(lines, note)
            box += note
        para = nodes.paragraph(classes=["in-brief-more"])
        para += nodes.Text(f"This chapter checks {_count(len(own), 'claim')} of the source (")
        para += self.badges(own).children
        para += nodes.Text(f") and asks {_count(len(recs) - len(own), 'question')} of its own; ")
        para += nodes.reference("", "all of them in the Verdicts table", refuri=self.verdicts_uri(key),
                                internal=True)
        para += nodes.Text(".")
        box += para
        return [box]


class FusionFindings(_LedgerDirective):
    """The introduction's findings: per source, its main finding, our number and what to use instead."""

    def run(self) -> list[nodes.Node]:
        from fusion.book.ledger import SOURCES
        from fusion.book.recommend import RECOMMENDATIONS

        recs = self.records()
        items = nodes.bullet_list(classes=["findings"])
        for key, src in sorted(SOURCES.items(), key=lambda kv: kv[1].order):
            head = [r for r in recs if r["source"] == key and r["headline"]]
            if not head:
                continue
            h = head[0]
            use = next((rec.use for rec in RECOMMENDATIONS if src.chapter in rec.chapters), "")
            use = re.split(r"(?<=[a-z)])[:.] | \(", use, maxsplit=1)[0].rstrip(".") + "." if use else ""
            ours = _short(h["ours_brief"], 14)
            item = nodes.list_item()
            self.markdown([f"{{doc}}`{src.short} <{self.docpath(src.chapter)}>`: {h['claim']} "
                           f"*Ours:* {ours}" + ("" if ours.endswith("…") else ".")
                           + (f" *Use instead:* {use}" if use else "")],
                          item)
            self.lead_badge(item, h["status"])
            items += item
        return [items]


class FusionReadings(_LedgerDirective):
    """A chapter appendix's readings: per record, the claim, its status and every reading with our number.

    ``.. fusion-readings:: <source key>`` with ``:chapter: <docname>`` (the main chapter whose records to
    show) and optionally ``:records: id id ...`` (only those, in that order). Each record gets a target
    ``readings-<record id>`` the main chapter links to with ``{ref}``; its readings are a list (not a
    table, so it reads on a phone): the open choice, the reading, the status, our number, the runs, and
    why a reading is shown apart when the rulebook does not count it.
    """

    required_arguments = 1
    option_spec = {"chapter": directives.unchanged_required, "records": directives.unchanged}

    def run(self) -> list[nodes.Node]:
        key = self.arguments[0]
        recs = [r for r in self.records() if r["source"] == key]
        if "chapter" in self.options:
            recs = [r for r in recs if r["chapter"] == self.options["chapter"].strip()]
        if self.options.get("records"):
            by = {r["id"]: r for r in recs}
            want = self.options["records"].split()
            missing = [w for w in want if w not in by]
            if missing:
                raise self.error(f"fusion-readings: no record {missing} in {key}")
            recs = [by[w] for w in want]
        out = nodes.container(classes=["fusion-readings"])
        for r in recs:
            if not r["alternatives"]:
                continue
            block = nodes.container(classes=["readings-record"])
            target = f"readings-{r['id']}"
            runs = f", {r['runs']} runs" if r.get("runs") else ""
            lines = [f"({target})=", "", f"**{r['where']}.** {r['claim']}" + (f" *({_whose(r)})*" if _whose(r) else ""),
                     "", f"Primary reading: {r['ours']}{runs} ({{ref}}`in the chapter <{r['link']}>`)."]
            if r["robustness"]:
                lines += ["", f"*{r['robustness']}.*"]
            if "stability" in r:
                lines += ["", f"*Reseeding: {_stability(r['stability'])}.*"]
            for a in r["alternatives"]:
                runs_a = f", {a['runs']} runs" if a.get("runs") else ""
                tag = "" if a.get("counted", True) else f" *(shown apart: {a.get('not_counted_because', '')})*"
                ours = f" Ours: {a['ours']}{runs_a}." if a.get("ours") else ""
                lines += ["", f"- {a['choice']}: {a['reading']} → **{a['status']}**.{ours}{tag}"]
            self.markdown(lines, block)
            self.lead_badge(block, r["status"])
            out += block
        return [out]


class FusionStability(SphinxDirective):
    """The reseeding sweep on the status page: when, how, what it covered and which records moved."""

    has_content = False

    def run(self) -> list[nodes.Node]:
        root = Path(self.env.srcdir)
        path = root / "book" / "ledger" / STABILITY_FILE
        if not path.is_file():
            return [nodes.paragraph(text="No reseeding results are stored yet: run make stability.")]
        self.env.note_dependency(str(path))
        sweep = json.loads(path.read_text(encoding="utf-8"))
        recs = sweep["records"]
        factors = sorted({v.get("runs_factor", sweep["runs_factor"]) for v in recs.values()})
        flagged = sorted(rid for rid, v in recs.items() if v["flag"])
        failed = sorted(rid for rid, v in recs.items() if v.get("failed"))
        rows = [("stochastic records re-derived", str(len(recs))),
                ("fresh seeds per reading (K)", f"{sweep['K']} (root seed {sweep['root_seed']})"),
                ("primary reading also at", " and ".join(f"{f}×" for f in factors) + " the chapter's runs"),
                ("records stable under every reseed and at the scaled runs", str(len(recs) - len(flagged))),
                ("records whose status moves (named in their chapters)", ", ".join(flagged) or "none"),
                ("tasks that failed", ", ".join(failed) or "none"),
                ("wall time of the stored sweep", f"{sweep['wall_seconds']:.0f} s ({sweep['machine']})"),
                ("date, evidence commit", f"{sweep['date']}, {sweep['commit'][:10]}")]
        return [_table(rows, ("reseeding sweep (book/ledger/stability.json)", "value"))]


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
            w.writerow(["; ".join(r[c]) if isinstance(r.get(c), list) else r.get(c, "") for c in LEDGER_COLUMNS])


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


def titles_only_toctree(global_toctree_for_doc):  # noqa: ANN001, ANN201 - wraps Sphinx's function
    """``global_toctree_for_doc`` that, for ``titles_only``, copies a toctree-free document's title only.

    Sphinx copies each entry's table of contents to the document's ``tocdepth`` (unlimited by default),
    and ``titles_only`` then deletes all but its top-level titles and the sub-toctrees found in it. For a
    document with no sub-toctree that is exactly its copy at ``tocdepth`` 1, set here for the call only.
    """
    from sphinx import addnodes

    def wrapper(env, docname, builder, collapse=False, includehidden=True, maxdepth=0, titles_only=False):  # noqa: ANN001, ANN202
        if not titles_only:
            return global_toctree_for_doc(env, docname, builder, collapse=collapse, includehidden=includehidden,
                                          maxdepth=maxdepth, titles_only=titles_only)
        flat = getattr(env, "_fusion_toctree_free", None)
        if flat is None or flat[0] is not env.tocs:
            flat = env._fusion_toctree_free = (env.tocs, [d for d, toc in env.tocs.items()
                                                          if next(toc.findall(addnodes.toctree), None) is None])
        saved = {d: env.metadata[d].get("tocdepth") for d in flat[1] if d in env.metadata}
        try:
            for d in saved:
                env.metadata[d]["tocdepth"] = 1
            return global_toctree_for_doc(env, docname, builder, collapse=collapse, includehidden=includehidden,
                                          maxdepth=maxdepth, titles_only=titles_only)
        finally:
            for d, depth in saved.items():
                if depth is None:
                    env.metadata[d].pop("tocdepth", None)
                else:
                    env.metadata[d]["tocdepth"] = depth

    wrapper.__wrapped__ = global_toctree_for_doc
    return wrapper


def _install_titles_only_toctree(app) -> None:  # noqa: ANN001
    """Wrap the two references Sphinx's HTML builder and ``TocTree.get_toctree_for`` call (once)."""
    import sphinx.builders.html as html
    from sphinx.environment.adapters import toctree

    for module in (html, toctree):
        if not hasattr(module.global_toctree_for_doc, "__wrapped__"):
            module.global_toctree_for_doc = titles_only_toctree(module.global_toctree_for_doc)


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


#: Extensions jupyter-book loads that do not declare whether Sphinx may read in parallel (Sphinx then warns, which
#: ``-W`` makes an error, and reads serially). Both are safe: ``sphinx_multitoc_numbering`` only replaces
#: ``TocTreeCollector.assign_section_numbers``, which Sphinx calls in the main process once the parallel readers'
#: environments are merged; ``sphinx_jupyterbook_latex`` adds per-document transforms that keep no state in the
#: environment (its ``builder-inited`` set-up runs for the LaTeX builder only).
PARALLEL_SAFE_UNDECLARED = ("sphinx_multitoc_numbering", "sphinx_jupyterbook_latex")


def _declare_parallel_safe(app) -> None:  # noqa: ANN001
    """Declare :data:`PARALLEL_SAFE_UNDECLARED` safe for parallel reading and writing (``tools/build_book.py``).

    Only an extension that declares nothing is changed (``tools/build_book.py`` runs Sphinx on every core).
    """
    for name in PARALLEL_SAFE_UNDECLARED:
        ext = app.extensions.get(name)
        if ext is not None:
            if ext.parallel_read_safe is None:
                ext.parallel_read_safe = True
            if ext.parallel_write_safe is None:
                ext.parallel_write_safe = True


def _drop_unused_viewcode_modules(app, env) -> None:  # noqa: ANN001
    """Forget ``sphinx.ext.viewcode``'s modules that no documented object uses, as a serial build does.

    viewcode records a module when an object's signature names it and drops it again, in ``env-purge-doc``, while
    the next document is read, if no object of it was found. A parallel reader's last document has no next one,
    so its empty records survive the merge and become source pages of re-exporting packages (even ``pathlib``).
    Dropping them after the merge gives the serial build's pages.
    """
    modules = getattr(env, "_viewcode_modules", {})
    for modname, entry in list(modules.items()):
        if entry and not entry[2]:
            del modules[modname]


def _balanced(items: list[tuple[str, int]], bins: int) -> list[list[str]]:
    """``items`` (name, cost) in ``bins`` lists of about equal total cost (largest first), each in name order."""
    loads = [[0, i, []] for i in range(bins)]
    for name, cost in sorted(items, key=lambda item: (-item[1], item[0])):
        least = min(loads)
        least[0] += cost
        least[2].append(name)
    return [sorted(names) for _, _, names in loads if names]


#: The search index's per-document records (``sphinx.search.IndexBuilder.feed``) a worker sends back.
_INDEX_RECORDS = ("_titles", "_filenames", "_all_titles", "_index_entries")
_INDEX_WORDS = ("_mapping", "_title_mapping")


def _write_in_workers(builder, docnames, nproc) -> None:  # noqa: ANN001
    """``Builder._write_parallel`` that resolves, indexes and writes each document in a worker (see above).

    One small document is written first in the main process, as Sphinx does, so that the forked workers inherit
    its compiled templates; the others are shared among ``app.parallel`` workers by the size of their pickled
    doctree. Each worker returns the search-index entries and the images of its documents, merged back in
    document order (the index's ``freeze`` sorts documents, and its word sets are sets).
    """
    import os

    from sphinx.util import logging
    from sphinx.util.build_phase import BuildPhase
    from sphinx.util.parallel import ParallelTasks

    env, app = builder.env, builder.app

    def size(docname: str) -> int:
        try:
            return os.path.getsize(os.path.join(builder.doctreedir, docname + ".doctree"))
        except OSError:
            return 0

    def write(docname: str) -> None:
        app.phase = BuildPhase.RESOLVING
        doctree = env.get_and_resolve_doctree(docname, builder)
        app.phase = BuildPhase.WRITING
        builder.write_doc_serialized(docname, doctree)
        builder.write_doc(docname, doctree)

    costs = [(d, size(d)) for d in docnames]
    first = min(costs, key=lambda item: (item[1], item[0]))[0]
    write(first)
    indexer = builder.indexer

    def work(docs: list[str]) -> tuple[dict, dict]:
        images_before = dict(builder.images)
        for docname in docs:
            write(docname)
        index: dict[str, dict] = {}
        if indexer is not None:
            for docname in docs:
                if docname not in indexer._titles:
                    continue
                record = {attr: getattr(indexer, attr).get(docname) for attr in _INDEX_RECORDS}
                for attr in _INDEX_WORDS:
                    record[attr] = [w for w, where in getattr(indexer, attr).items() if docname in where]
                index[docname] = record
        images = {k: v for k, v in builder.images.items() if images_before.get(k) != v}
        return images, index

    results: dict[int, tuple[dict, dict]] = {}
    chunks = _balanced([c for c in costs if c[0] != first], max(1, nproc))
    tasks = ParallelTasks(len(chunks))
    for i, chunk in enumerate(chunks):
        tasks.add_task(work, chunk, lambda _arg, result, i=i: results.__setitem__(i, result))
    tasks.join()
    merged_index: dict[str, dict] = {}
    for i in range(len(chunks)):
        images, index = results[i]
        builder.images.update(images)
        merged_index.update(index)
    if indexer is not None:
        for docname in sorted(merged_index):
            record = merged_index[docname]
            for attr in _INDEX_RECORDS:
                if record[attr] is not None:
                    getattr(indexer, attr)[docname] = record[attr]
            for attr in _INDEX_WORDS:
                mapping = getattr(indexer, attr)
                for word in record[attr]:
                    mapping.setdefault(word, set()).add(docname)
    logging.getLogger(__name__).info("")


def _install_write_in_workers(app) -> None:  # noqa: ANN001
    """Use :func:`_write_in_workers` for a parallel HTML build."""
    import types

    from sphinx.builders.html import StandaloneHTMLBuilder

    if isinstance(app.builder, StandaloneHTMLBuilder) and app.parallel > 1:
        app.builder._write_parallel = types.MethodType(
            lambda builder, docnames, nproc: _write_in_workers(builder, docnames, app.parallel), app.builder)


def _viewcode_pages_in_workers(app):  # noqa: ANN001, ANN201 - an html-collect-pages handler
    """``sphinx.ext.viewcode``'s source pages, highlighted and written by ``app.parallel`` workers.

    Each worker runs viewcode's own page generator with the modules of the others blanked out (viewcode skips
    an empty record, and still sees every module name, for the links to parent packages) and writes the pages
    it yields. The main process then yields viewcode's module index, which needs no highlighting.
    """
    from sphinx.ext import viewcode
    from sphinx.util.parallel import ParallelTasks

    env = app.builder.env
    modules = getattr(env, "_viewcode_modules", None)
    if app.parallel <= 1 or not modules:
        yield from viewcode.collect_pages(app)
        return
    index = viewcode.OUTPUT_DIRNAME + "/index"

    def work(part: list[str]) -> None:
        env._viewcode_modules = {m: (entry if m in part else False) for m, entry in modules.items()}
        for pagename, context, template in viewcode.collect_pages(app):
            if pagename != index:
                app.builder.handle_page(pagename, context, template)

    costs = [(m, len(entry[0])) for m, entry in modules.items() if entry]
    tasks = ParallelTasks(app.parallel)
    for part in _balanced(costs, app.parallel):
        tasks.add_task(work, part)
    tasks.join()
    saved = env._viewcode_modules
    env._viewcode_modules = dict.fromkeys(modules, False)
    try:
        yield from viewcode.collect_pages(app)
    finally:
        env._viewcode_modules = saved


def _install_viewcode_pages_in_workers(app) -> None:  # noqa: ANN001
    """Replace viewcode's ``html-collect-pages`` handler by :func:`_viewcode_pages_in_workers` (same priority)."""
    from sphinx.ext import viewcode

    for listener in list(app.events.listeners.get("html-collect-pages", [])):
        if listener.handler is viewcode.collect_pages:
            app.disconnect(listener.id)
            app.connect("html-collect-pages", _viewcode_pages_in_workers, priority=listener.priority)


def _numbers_something(env, doctree) -> bool:  # noqa: ANN001
    """Whether Sphinx's figure numbering could number a node of ``doctree`` or follow a toctree from it.

    The test of ``TocTreeCollector.assign_figure_numbers`` without its caption check (so it errs towards True):
    a toctree, or an element other than a section with ids that a domain calls enumerable.
    """
    from sphinx import addnodes

    for node in doctree.findall(nodes.Element):
        if isinstance(node, addnodes.toctree):
            return True
        if node["ids"] and not isinstance(node, nodes.section) and any(
                domain.get_enumerable_node_type(node) for domain in env.domains.values()):
            return True
    return False


def _note_unnumbered(app, doctree) -> None:  # noqa: ANN001 - doctree-read
    unnumbered = app.env.__dict__.setdefault("fusion_unnumbered", set())
    unnumbered.discard(app.env.docname)
    if not _numbers_something(app.env, doctree):
        unnumbered.add(app.env.docname)


def _purge_unnumbered(app, env, docname) -> None:  # noqa: ANN001 - env-purge-doc
    env.__dict__.get("fusion_unnumbered", set()).discard(docname)


def _merge_unnumbered(app, env, docnames, other) -> None:  # noqa: ANN001 - env-merge-info
    mine = env.__dict__.setdefault("fusion_unnumbered", set())
    mine |= {d for d in other.__dict__.get("fusion_unnumbered", set()) if d in docnames}


def _figure_numbers_skip_unnumbered(assign_figure_numbers):  # noqa: ANN001, ANN201 - wraps Sphinx's method
    """``TocTreeCollector.assign_figure_numbers`` that does not unpickle a document :func:`_note_unnumbered` cleared."""
    from docutils import nodes as docnodes

    def wrapper(self, env):  # noqa: ANN001, ANN202
        skip = env.__dict__.get("fusion_unnumbered", set())
        get_doctree = env.get_doctree
        env.get_doctree = lambda docname: docnodes.Element() if docname in skip else get_doctree(docname)
        try:
            return assign_figure_numbers(self, env)
        finally:
            del env.get_doctree

    wrapper.__wrapped__ = assign_figure_numbers
    return wrapper


def _install_figure_numbers_skip(app) -> None:  # noqa: ANN001
    from sphinx.environment.collectors.toctree import TocTreeCollector

    if not hasattr(TocTreeCollector.assign_figure_numbers, "__wrapped__"):
        TocTreeCollector.assign_figure_numbers = _figure_numbers_skip_unnumbered(TocTreeCollector.assign_figure_numbers)


def setup(app):  # noqa: ANN001, ANN201 - Sphinx entry point
    app.connect("config-inited", _nitpick_ignores)
    app.connect("builder-inited", _declare_parallel_safe)
    app.connect("env-updated", _drop_unused_viewcode_modules)
    app.add_css_file("verdicts.css")
    app.add_js_file("verdicts.js")
    app.add_directive("fusion-versions", FusionVersions)
    app.add_directive("fusion-benchmarks", FusionBenchmarks)
    app.add_directive("fusion-verdicts-summary", FusionVerdictsSummary)
    app.add_directive("fusion-verdicts", FusionVerdicts)
    app.add_directive("fusion-in-brief", FusionInBrief)
    app.add_directive("fusion-findings", FusionFindings)
    app.add_directive("fusion-readings", FusionReadings)
    app.add_directive("fusion-stability", FusionStability)
    app.connect("builder-inited", _export_ledger)
    app.connect("builder-inited", _install_titles_only_toctree)
    app.connect("builder-inited", _install_write_in_workers)
    app.connect("builder-inited", _install_viewcode_pages_in_workers)
    app.connect("builder-inited", _install_figure_numbers_skip)
    app.connect("doctree-read", _note_unnumbered)
    app.connect("env-purge-doc", _purge_unnumbered)
    app.connect("env-merge-info", _merge_unnumbered)
    app.connect("html-page-context", _dedupe_scripts, priority=900)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
