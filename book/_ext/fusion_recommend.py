"""Local Sphinx extension: the "Which method should I use?" page and the source download.

* ``.. fusion-recommendations::`` renders :data:`fusion.book.recommend.RECOMMENDATIONS`: per task
  the method to use, what to avoid, and every ledger record the advice rests on with its current
  status, our numbers and a link to the evidence. A cited record that is missing, or whose status
  left the set the advice needs, is a build warning (an error under ``-W``): the page cannot
  outlive its evidence.
* ``.. fusion-status-rules::`` renders the status vocabulary of the ledger with its constants
  (confidence level, minimum runs, dominance share), so the Verdicts page types none of them.
* When the build starts, the repository's tracked files (``git ls-files``) are packed into
  ``book/_generated/fusion-book-source.zip`` for the download link of the reproduce page, so a
  reader of the HTML alone can get the code, notebooks, lock file and tests.
"""

from __future__ import annotations

import json
import subprocess
import zipfile
from pathlib import Path

from docutils import nodes
from sphinx.util.docutils import SphinxDirective

ARCHIVE = Path("book") / "_generated" / "fusion-book-source.zip"


def _records(root: Path) -> dict[str, dict]:
    out: dict[str, dict] = {}
    for path in sorted(p for p in (root / "book" / "ledger").glob("*.json") if p.name != "stability.json"):
        for r in json.loads(path.read_text(encoding="utf-8"))["claims"]:
            out[r["id"]] = r
    return out


class FusionRecommendations(SphinxDirective):
    """One section per task: use, avoid, and the ledger evidence with live statuses."""

    has_content = False

    def _md(self, lines: list[str], node: nodes.Element) -> None:
        from docutils.statemachine import StringList

        self.state.nested_parse(StringList(lines, source="recommendations"), self.content_offset, node)

    def run(self) -> list[nodes.Node]:
        import posixpath

        from fusion.book.recommend import RECOMMENDATIONS, check

        root = Path(self.env.srcdir)
        for path in (root / "book" / "ledger").glob("*.json"):
            self.env.note_dependency(str(path))
        records = _records(root)
        out: list[nodes.Node] = []
        for problem in check(records.values()):
            out.append(self.state.document.reporter.warning(
                f"recommendation no longer supported by the ledger: {problem}", line=self.lineno))
        here = posixpath.dirname(self.env.docname) or "."
        for rec in RECOMMENDATIONS:
            box = nodes.container(classes=["recommendation"])
            chapters = ", ".join(f"{{doc}}`{posixpath.relpath(c, here)}`" for c in rec.chapters)
            lines = [f"**{rec.task}**", "",
                     f"*Use:* {rec.use} {rec.why}", "",
                     f"*Avoid:* {rec.avoid} {rec.avoid_why}", "",
                     "*Evidence* (status from the claims ledger, numbers from the chapters):", ""]
            for ev in rec.evidence:
                r = records.get(ev.claim)
                if r is None:
                    lines.append(f"- {ev.role}: record `{ev.claim}` missing")
                    continue
                lines.append(f"- {ev.role}: *{r['status']}*"
                             + (f" ({r['robustness']})" if r.get("robustness") else "")
                             + f" — {r['claim']} Ours: {r['ours_brief']}. {{ref}}`Evidence <{r['link']}>`")
            lines += ["", f"Chapters: {chapters}."]
            self._md(lines, box)
            out.append(box)
        return out


class FusionStatusRules(SphinxDirective):
    """The status vocabulary and its rules, with the constants of :mod:`fusion.book.ledger`."""

    has_content = False

    def run(self) -> list[nodes.Node]:
        from docutils.statemachine import StringList

        from fusion.book.ledger import STATUS_DEFINITIONS, STATUSES
        from fusion.book.rulebook import RULES

        lines: list[str] = ["**The statuses.**", ""]
        for st in STATUSES:
            slug = st.replace(" ", "-")
            text = STATUS_DEFINITIONS[st]
            lines += [f"[{st}]{{.status-badge .status-{slug}}}", f": {text[0].upper()}{text[1:]}.", ""]
        lines += ["**The rules** (`fusion.book.rulebook`; the same for every record, each tested on constructed "
                  "evidence in `tests/test_rulebook.py`).", ""]
        for rule in RULES:
            lines += [f"{rule.key} · {rule.title}", f": {rule.text}", ""]
        node = nodes.container(classes=["status-rules"])
        self.state.nested_parse(StringList(lines, source="ledger rules"), self.content_offset, node)
        return list(node.children)


def _pack_sources(app) -> None:  # type: ignore[no-untyped-def]
    root = Path(app.srcdir)
    target = root / ARCHIVE
    target.parent.mkdir(parents=True, exist_ok=True)
    try:
        listed = subprocess.run(["git", "ls-files", "-z"], cwd=root, check=True, capture_output=True).stdout
        files = [f for f in listed.decode("utf-8").split("\0") if f]
    except (OSError, subprocess.CalledProcessError):
        files = []
    with zipfile.ZipFile(target, "w", compression=zipfile.ZIP_DEFLATED) as zf:
        if not files:
            zf.writestr("fusion-book/README.txt", "This build was not made from a git checkout.\n")
        for name in sorted(files):
            path = root / name
            if path.is_file():
                info = zipfile.ZipInfo(f"fusion-book/{name}", date_time=(2026, 1, 1, 0, 0, 0))
                info.compress_type = zipfile.ZIP_DEFLATED
                info.external_attr = (path.stat().st_mode & 0o777) << 16
                zf.writestr(info, path.read_bytes())


def setup(app):  # type: ignore[no-untyped-def]
    app.add_directive("fusion-recommendations", FusionRecommendations)
    app.add_directive("fusion-status-rules", FusionStatusRules)
    app.connect("builder-inited", _pack_sources)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
