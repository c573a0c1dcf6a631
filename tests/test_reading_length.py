"""Chapters at reading length (issue 28, item 3): each chapter's main page under 5,000 words of prose.

Prose is the text of the main notebook's markdown cells without display maths, inline maths, code, HTML
comments and directive options; a role such as ``{glue:text}`key``` counts as one word. Readings,
robustness studies and long critiques belong in the chapter's appendix notebook (``*_appendix.ipynb``),
which must exist, be listed in the table of contents under its chapter, and be linked from the chapter.
"""
from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
CHAPTERS = sorted(p for p in (ROOT / "notebooks").glob("*.ipynb") if not p.stem.endswith("_appendix"))

#: Words of prose a chapter's main page may have.
MAX_WORDS = 5000


def prose_words(text: str) -> int:
    """Words of prose in MyST markdown (see the module docstring)."""
    text = re.sub(r"<!--.*?-->", " ", text, flags=re.S)
    text = re.sub(r"\$\$.*?\$\$", " ", text, flags=re.S)
    kept, fence = [], None  # fence: None outside, "code"/"math" (dropped) or "directive" (prose kept)
    for line in text.splitlines():
        m = re.match(r"\s*(`{3,}|:{3,})\s*(\{([\w:-]+)\})?", line)
        if m and fence is None:
            name = m.group(3)
            fence = "directive" if name and name not in ("math", "code-cell", "code") else "code"
            kept.append(line.split("}", 1)[1] if fence == "directive" else "")
            continue
        if fence is not None and re.match(r"\s*(`{3,}|:{3,})\s*$", line):
            fence = None
            continue
        if fence == "code" or re.match(r"\s*:[\w-]+:", line):
            continue
        kept.append(line)
    text = "\n".join(kept)
    text = re.sub(r"\{[\w:-]+\}`[^`]*`", " role ", text)
    text = re.sub(r"(?<!\\)\$[^$\n]+\$", " ", text)
    text = re.sub(r"`[^`]*`", " code ", text)
    return len(re.findall(r"[A-Za-z0-9][\w'’.,%-]*", text))


def markdown(nb: Path) -> str:
    cells = json.loads(nb.read_text(encoding="utf-8"))["cells"]
    return "\n\n".join("".join(c["source"]) for c in cells if c["cell_type"] == "markdown")


def test_prose_words_counts_prose_only() -> None:
    assert prose_words("One two $x + y$ three.\n\n$$\na = b\n$$\n{glue:text}`k` `code`") == 5
    assert prose_words("```{fusion-in-brief} x\n:chapter: y\n```\nafter") == 2  # its argument, not its options
    assert prose_words("```{note}\nA note.\n```\n```python\nx = 1\n```\nEnd") == 3
    assert prose_words("```{math}\na = b\n```") == 0


@pytest.mark.parametrize("nb", CHAPTERS, ids=lambda p: p.stem)
def test_chapter_main_page_at_reading_length(nb: Path) -> None:
    n = prose_words(markdown(nb))
    assert n < MAX_WORDS, f"{nb.name}: {n} words of prose (at most {MAX_WORDS}); move readings to its appendix"


@pytest.mark.parametrize("nb", CHAPTERS, ids=lambda p: p.stem)
def test_chapter_has_a_linked_appendix(nb: Path) -> None:
    appendix = nb.with_name(f"{nb.stem}_appendix.ipynb")
    assert appendix.is_file(), f"{appendix.name} missing"
    toc = (ROOT / "_toc.yml").read_text(encoding="utf-8")
    assert re.search(rf"- file: notebooks/{nb.stem}\n\s+sections:\n\s+- file: notebooks/{appendix.stem}\n", toc)
    assert f"{appendix.stem}" in markdown(nb), f"{nb.name} never links to its appendix"
