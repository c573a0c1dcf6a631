"""A table header written in more than one function is named once (issue 36): a relabel must not break code far away.

The rule, checked by an AST scan of every module of ``fusion/``: a string literal that reads like a header (it holds a
space) and is used as a dict key or a subscript (also inside a tuple subscript such as ``tab.loc[row, "header"]``) in
two or more functions of the package (a module's top level counting as one) must be a named constant instead, which
the functions share. Left out: the style registry (``fusion/book/style.py``, whose keys and labels are the registry),
keys of that registry (method keys such as "closed form"), and the ledger's status words (a status is a key of its
own tables, not a header). Headers built by f-strings (``f"GLS(R̂, {n}) / GLS"``) are not seen.

The headers that still repeat are listed in :data:`PENDING`: the test fails on a new one, and on a listed one that
no longer repeats (so that the list only shrinks).
"""

from __future__ import annotations

import ast
from collections import defaultdict
from pathlib import Path

from fusion.book import style
from fusion.book.ledger.statuses import STATUSES
from _helpers import parsed

ROOT = Path(__file__).resolve().parents[1] / "fusion"
_KEYS = frozenset(style.METHOD_COLORS) | {k for t in (style.METHOD_LABELS, style.METHOD_SHORT_LABELS) for k in t}
_SKIP = _KEYS | frozenset(STATUSES)

#: Strings written in two or more functions that are not named yet (none left: chapters 01-03's case keys, which
#: were also the text a table or legend shows, have keys with labels in the style registry since issue 36).
PENDING: frozenset[str] = frozenset()


def _strings(node: ast.AST) -> list[str]:
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return [node.value]
    return [s for e in node.elts for s in _strings(e)] if isinstance(node, ast.Tuple) else []


def header_uses(tree: ast.AST, where: str = "") -> dict[str, set[str]]:
    """Header-like string literal -> the functions (``where:name``) that use it as a dict key or subscript."""
    uses: dict[str, set[str]] = defaultdict(set)

    def visit(node: ast.AST, scope: str) -> None:
        for child in ast.iter_child_nodes(node):
            inner = scope
            if scope == "<module>" and isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                inner = child.name                          # a nested function counts with its outer one
            found = (_strings(child.slice) if isinstance(child, ast.Subscript) else
                     [s for k in child.keys if k is not None for s in _strings(k)] if isinstance(child, ast.Dict)
                     else [])
            for s in found:
                if " " in s and s not in _SKIP:
                    uses[s].add(f"{where}:{inner}")
            visit(child, inner)
    visit(tree, "<module>")
    return uses


def repeated_headers() -> dict[str, set[str]]:
    """Header -> its functions across ``fusion/``, for the headers used in two or more."""
    uses: dict[str, set[str]] = defaultdict(set)
    for p in sorted(ROOT.rglob("*.py")):
        if p.name == "style.py" and p.parent.name == "book":
            continue
        for s, fns in header_uses(parsed(p), str(p.relative_to(ROOT))).items():
            uses[s] |= fns
    return {s: fns for s, fns in uses.items() if len(fns) > 1}


def test_the_scan_finds_a_header_built_in_one_function_and_read_in_another() -> None:
    src = ('def build():\n    return {"95 % CI low": 1, "n": 2}\n\n'
           'def read(t):\n    return t.loc["a", "95 % CI low"], t["n"]\n\n'
           'def once(t):\n    t["only here"] = 1\n    return t["only here"]\n')
    uses = header_uses(ast.parse(src), "m")
    assert uses["95 % CI low"] == {"m:build", "m:read"}
    assert "n" not in uses                                   # no space: a key, not a header
    assert uses["only here"] == {"m:once"}                  # one function: not repeated


def test_a_named_header_is_not_a_literal() -> None:
    src = 'CI_LOW = "95 % CI low"\n\ndef build():\n    return {CI_LOW: 1}\n\ndef read(t):\n    return t[CI_LOW]\n'
    assert header_uses(ast.parse(src), "m") == {}


def test_registry_keys_and_statuses_are_left_out() -> None:
    assert {"closed form"} <= _KEYS and "not distinguishable" in _SKIP
    src = ('def a(r):\n    return r["closed form"], r["not distinguishable"]\n\n'
           'def b():\n    return {"closed form": 1}\n')
    assert header_uses(ast.parse(src), "m") == {}


def test_no_new_header_is_retyped_across_functions() -> None:
    found = repeated_headers()
    new = {s: sorted(fns) for s, fns in found.items() if s not in PENDING}
    assert not new, new


def test_the_pending_list_only_shrinks() -> None:
    assert not PENDING - set(repeated_headers()), sorted(PENDING - set(repeated_headers()))
