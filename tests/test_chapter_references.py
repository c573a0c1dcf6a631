"""Chapter and notebook numbers named in the package's docstrings and comments point at the right notebook.

A docstring once sent readers to "notebook 04" for the Chernoff chapter, which is notebook 06 since the
chapters were renumbered. Every "chapter NN", "notebook NN", "ch. N" and ``notebooks/NN_name`` in
``fusion/`` must name a notebook that exists, and a sentence that names a chapter by number and also by
its topic (a word found in that chapter's notebook title and in no other chapter's title) must name the
chapter whose title holds that word.
"""

from __future__ import annotations

import ast
import io
import json
import re
import tokenize
from functools import cache
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = ROOT / "notebooks"

#: "chapter 06", "chapters 03 and 04", "notebook 4", "ch. 6", "Chapter 07", "Appendix to chapter 2".
NUMBER = re.compile(r"\b(?:chapters?|notebooks?|ch\.)\s+(\d{1,2})((?:\s*(?:,|and|-|to)\s*\d{1,2})*)\b", re.IGNORECASE)
#: ``notebooks/06_chernoff_fusion`` (a path or a :doc: target).
PATH = re.compile(r"notebooks/(\d{2})_([a-z0-9_]+)")
#: Characters either side of a chapter number in which a chapter's title word ties the sentence to that chapter.
WINDOW = 60


def _title(path: Path) -> str:
    """The first level-1 heading of a notebook."""
    for cell in json.loads(path.read_text())["cells"]:
        if cell["cell_type"] == "markdown":
            for line in "".join(cell["source"]).splitlines():
                if line.startswith("# "):
                    return line[2:]
    raise AssertionError(f"{path.name} has no title")


@cache
def chapters() -> dict[int, tuple[str, str]]:
    """Chapter number -> (main notebook's file stem, its title)."""
    out = {}
    for p in sorted(NOTEBOOKS.glob("[0-9][0-9]_*.ipynb")):
        if not p.stem.endswith("_appendix"):
            out[int(p.stem[:2])] = (p.stem, _title(p))
    return out


@cache
def labels() -> dict[str, frozenset[int]]:
    """Label or record name defined in a notebook (``eq-chf-foa``, ``fig-...``, a ``(name)=`` target) -> chapters."""
    out: dict[str, set[int]] = {}
    for p in NOTEBOOKS.glob("[0-9][0-9]_*.ipynb"):
        src = "\n".join("".join(c["source"]) for c in json.loads(p.read_text())["cells"])
        for name in re.findall(r"\(([A-Za-z][\w-]*-[\w-]+)\)=|:(?:label|name):\s*([A-Za-z][\w-]*)", src):
            out.setdefault(name[0] or name[1], set()).add(int(p.stem[:2]))
    return {k: frozenset(v) for k, v in out.items()}


@cache
def topic_words() -> dict[int, frozenset[str]]:
    """Chapter number -> the words of its notebook's file name and title that no other chapter's have (6+ letters)."""
    def words(n: int) -> set[str]:
        stem, title = chapters()[n]
        return {w.lower().rstrip("s") for w in re.findall(r"[A-Za-z]{6,}", stem.replace("_", " "))} & \
            {w.lower().rstrip("s") for w in re.findall(r"[A-Za-z]{6,}", title)}
    mine = {n: words(n) for n in chapters()}
    return {n: frozenset(w - set().union(*(o for m, o in mine.items() if m != n))) for n, w in mine.items()}


def _about(sentence: str, near: str) -> dict[int, list[str]]:
    """Chapters a sentence is about: by the labels it names, and by the chapters' title words ``near`` the number."""
    out: dict[int, list[str]] = {}
    labs = labels()
    for tok in re.findall(r"[A-Za-z][\w-]*-[\w-]*\*?", sentence):
        hits = ({n for k, v in labs.items() if k.startswith(tok[:-1]) for n in v} if tok.endswith("*")
                else labs.get(tok, frozenset()))
        for n in hits:
            out.setdefault(n, []).append(tok)
    said = {w.lower().rstrip("s") for w in re.findall(r"[A-Za-z]{6,}", near)}
    for n, t in topic_words().items():
        for w in said & t:
            out.setdefault(n, []).append(w)
    return out


def _prose(text: str) -> str:
    """``text`` without its references section and bibliography lines (other works' chapters are not ours)."""
    text = re.split(r"\n\s*References\n\s*-+\n", text)[0]
    return "\n".join(line for line in text.splitlines() if not re.match(r"\s*\*.*\(\d{4}\)", line))


def mismatches(text: str) -> list[str]:
    """Every chapter reference of ``text`` that names no notebook, or the wrong one for its sentence's topic.

    A sentence is about a chapter when it names one of the chapter's labels (``eq-chf-foa``, or a pattern
    ``eq-chf-*``) or a word only that chapter's notebook name and title hold ("Chernoff", "registration").

    Parameters
    ----------
    text : str
        A docstring or comment.

    Returns
    -------
    list of str
        One message per bad reference (empty when all are right).
    """
    known, out = chapters(), []
    text = _prose(text)
    stems = {s for s, _ in known.values()} | {s + "_appendix" for s, _ in known.values()}
    for m in PATH.finditer(text):
        if f"{m.group(1)}_{m.group(2)}" not in stems:
            out.append(f"{m.group(0)!r}: no such notebook")
    for sentence in re.split(r"(?<=[.;])\s+(?=[A-Z(])|\n\s*\n", text):
        named, near = set(), []
        for m in [*NUMBER.finditer(sentence), *PATH.finditer(sentence)]:
            near.append(sentence[max(0, m.start() - WINDOW):m.end() + WINDOW])
        for m in NUMBER.finditer(sentence):
            nums = [int(m.group(1))] + [int(x) for x in re.findall(r"\d{1,2}", m.group(2))]
            for n in nums:
                if n not in known:
                    out.append(f"{m.group(0)!r}: there is no notebook {n:02d}")
                named.add(n)
        named |= {int(m.group(1)) for m in PATH.finditer(sentence)}
        about = _about(sentence, " ".join(near))
        if named and about and not set(about) & named:
            out.append(f"{' '.join(sentence.split())[:120]!r} names chapter(s) {sorted(named)} but is about "
                       f"{ {n: sorted(set(v)) for n, v in sorted(about.items())} }")
    return out


def _texts(path: Path) -> list[tuple[int, str]]:
    """(line, text) of every docstring and comment of a module."""
    src = path.read_text()
    out = []
    for node in ast.walk(ast.parse(src)):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
            doc = ast.get_docstring(node, clean=False)
            if doc:
                out.append((node.body[0].lineno, doc))
    for tok in tokenize.generate_tokens(io.StringIO(src).readline):
        if tok.type == tokenize.COMMENT:
            out.append((tok.start[0], tok.string))
    return out


MODULES = sorted((ROOT / "fusion").rglob("*.py"))


def test_chapters_found() -> None:
    """The check sees every chapter, and every chapter's title has words of its own to recognise it by."""
    assert sorted(chapters()) == list(range(1, len(chapters()) + 1))
    assert all(topic_words()[n] for n in chapters())


@pytest.mark.parametrize("text", [
    # the docstring this test was written for (before the fix): the Chernoff chapter is 06
    "the chapter's reconstruction (labels ``eq-chf-*`` in notebook 04).\n\nChernoff fusion of Gaussians.",
    "Chernoff fusion of Gaussian mixtures, as notebook 04 shows.",
    "See :doc:`ch. 6 </notebooks/04_chernoff_fusion>`.",
    "Time registration of asynchronous sensors: chapter 12.",
])
def test_wrong_reference_is_caught(text: str) -> None:
    """A reference to a missing notebook, or to a chapter other than its sentence's topic, is reported."""
    assert mismatches(text)


@pytest.mark.parametrize("text", [
    "The Chernoff fusion of chapter 06 (:doc:`ch. 6 </notebooks/06_chernoff_fusion>`).",
    "Time registration (chapter 07), asynchronous sensors.",
    "Chapters 03 and 04 of the lecture notes: wavelet denoising and correlated noise.",
])
def test_right_reference_passes(text: str) -> None:
    """A reference that matches its sentence's topic is not reported."""
    assert mismatches(text) == []


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(ROOT)))
def test_docstring_chapter_references(path: Path) -> None:
    """Every chapter or notebook number a docstring or comment of ``fusion/`` names is that topic's notebook."""
    bad = [f"line {line}: {msg}" for line, text in _texts(path) for msg in mismatches(text)]
    assert not bad, "\n".join(bad)
