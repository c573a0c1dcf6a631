"""No code in the package is keyed by a display label (issue 36): labels live only in the style registry.

An AST scan of every module of ``fusion/`` (the registry itself excepted) for a registered display label used as a
dict key, a subscript or a comparand. Labels that are also plain identifiers ("median", "two-point") are left out:
they double as keys by design.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

from fusion.book import style

ROOT = Path(__file__).resolve().parents[1] / "fusion"
LABELS = {lab for lab in (*style.METHOD_LABELS.values(), *style.METHOD_SHORT_LABELS.values())
          if not re.fullmatch(r"[a-z0-9_-]+", lab)}


def _label_uses(tree: ast.AST) -> list[tuple[int, str]]:
    def lab(node: ast.AST | None) -> str | None:
        return node.value if isinstance(node, ast.Constant) and node.value in LABELS else None
    hits = []
    for n in ast.walk(tree):
        found = ([lab(n.slice)] if isinstance(n, ast.Subscript) else [lab(k) for k in n.keys] if isinstance(n, ast.Dict)
                 else [lab(c) for c in (n.left, *n.comparators)] if isinstance(n, ast.Compare) else [])
        hits += [(n.lineno, f) for f in found if f]  # type: ignore[attr-defined]
    return hits


def test_the_scan_finds_a_label_used_as_a_key() -> None:
    label = style.METHOD_LABELS["split_ci"]
    src = f"a = {{{label!r}: 1}}\nb = a[{label!r}]\nc = x == {label!r}\nd = {{'split_ci': {label!r}}}\n"
    assert [line for line, _ in _label_uses(ast.parse(src))] == [1, 2, 3]


def test_no_module_is_keyed_by_a_display_label() -> None:
    assert len(LABELS) > 100
    found = {f"{p.relative_to(ROOT)}:{line}: {lab!r}" for p in ROOT.rglob("*.py") if p.name != "style.py"
             for line, lab in _label_uses(ast.parse(p.read_text(encoding="utf-8")))}
    assert not found, sorted(found)
