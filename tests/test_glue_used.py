"""Every glued value is used, and the chapter modules stay small.

A value a notebook glues but nothing references is dead weight in the stored outputs (and a
number computed on a route no reader sees). References are the ``{glue…}`` roles and directives of
the notebooks' markdown and of ``book/*.md``, and the ``{name}`` fields of the claim files'
texts (:mod:`fusion.book.claims`), which take the chapter's glue values.
"""

from __future__ import annotations

import ast
import json
import re
from pathlib import Path

import pytest

from _helpers import parsed

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = sorted((ROOT / "notebooks").glob("*.ipynb"))
ROLE = re.compile(r"\{glue(?::\w+)?\}`(?:[^`]*::)?([\w.-]+?)(?::[^`]*)?`")
DIRECTIVE = re.compile(r"[`:]{3,}\{glue(?::\w+)?\}\s+(?:[^\s]*::)?([\w.-]+)")
FIELD = re.compile(r"\{([A-Za-z_]\w*)(?:[:!][^{}]*)?\}")

#: Longest function allowed in fusion/book/chapters/ (lines, decorators and docstring included).
MAX_FUNCTION_LINES = 150


def _glued(nb: Path) -> set[str]:
    cells = json.loads(nb.read_text(encoding="utf-8"))["cells"]
    return {o["metadata"]["scrapbook"]["name"] for c in cells for o in c.get("outputs", [])
            if "scrapbook" in o.get("metadata", {})}


def _references() -> set[str]:
    refs: set[str] = set()
    texts = [p.read_text(encoding="utf-8") for p in (ROOT / "book").glob("*.md")]
    for nb in NOTEBOOKS:
        cells = json.loads(nb.read_text(encoding="utf-8"))["cells"]
        texts += ["".join(c["source"]) for c in cells if c["cell_type"] == "markdown"]
    for t in texts:
        refs |= set(ROLE.findall(t)) | set(DIRECTIVE.findall(t))
    for y in (ROOT / "book" / "claims").glob("*.yaml"):
        refs |= set(FIELD.findall(y.read_text(encoding="utf-8")))
    return refs


@pytest.mark.parametrize("nb", NOTEBOOKS, ids=lambda p: p.stem)
def test_every_glued_value_is_referenced(nb: Path) -> None:
    unused = sorted(_glued(nb) - _references())
    assert not unused, f"{nb.name} glues {len(unused)} values that nothing references, e.g. {unused[:8]}"


def test_the_reference_patterns_find_roles_directives_and_fields() -> None:
    text = ("{glue:text}`a_1:.2f` and {glue}`b` and {glue:text}`../notebooks/x.ipynb::c:d`\n"
            "```{glue:figure} fig_d\n:::{glue:md} e\n")
    assert set(ROLE.findall(text)) | set(DIRECTIVE.findall(text)) == {"a_1", "b", "c", "fig_d", "e"}
    assert set(FIELD.findall("claim: {x:.1f} of {y}, not {{z}}")) >= {"x", "y"}


def test_no_function_in_the_chapter_modules_is_over_the_limit() -> None:
    long = []
    for path in sorted((ROOT / "fusion" / "book" / "chapters").rglob("*.py")):
        for node in ast.walk(parsed(path)):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                start = min([node.lineno, *(d.lineno for d in node.decorator_list)])
                n = node.end_lineno - start + 1
                if n > MAX_FUNCTION_LINES:
                    long.append(f"{path.name}:{node.name} ({n} lines)")
    assert not long, "functions over the limit: " + ", ".join(long)
