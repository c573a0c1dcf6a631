"""No code in the package is keyed by a display label (issue 36): labels live only in the style registry.

An AST scan of every module of ``fusion/`` (the registry itself excepted) for a registered display label used as a
dict key, a subscript or a comparand. Every label of the registry whose text differs from its key counts, single words
and hyphenated ones ("feedback", "two-point", "causal") as well as labels with spaces, unless the text is itself a key
of the registry ("mean" labels ``lec_bench_mean`` and is the key of the arithmetic mean): such a text is a method key.
"""

from __future__ import annotations

import ast
from pathlib import Path

from fusion.book import style
from _helpers import parsed

ROOT = Path(__file__).resolve().parents[1] / "fusion"
_TABLES = (style.METHOD_LABELS, style.METHOD_SHORT_LABELS)
KEYS = frozenset(style.METHOD_COLORS) | {k for table in _TABLES for k in table}
LABELS = frozenset(lab for table in _TABLES for key, lab in table.items() if lab != key and lab not in KEYS)


def _field_specs(tree: ast.AST) -> set[int]:
    """The dicts that declare a result class's field specs (``ResultSpec({...})``): their keys are the dataclass's
    field names (identifiers, checked against the fields by ``fusion._results``), not display labels."""
    return {id(n.args[0]) for n in ast.walk(tree) if isinstance(n, ast.Call) and n.args
            and isinstance(n.args[0], ast.Dict) and getattr(n.func, "id", getattr(n.func, "attr", None)) == "ResultSpec"}


def _label_uses(tree: ast.AST, labels: frozenset[str] = LABELS) -> list[tuple[int, str]]:
    def lab(node: ast.AST | None) -> str | None:
        return node.value if isinstance(node, ast.Constant) and node.value in labels else None
    hits = []
    specs = _field_specs(tree)
    for n in ast.walk(tree):
        if id(n) in specs:
            continue
        found = ([lab(n.slice)] if isinstance(n, ast.Subscript) else [lab(k) for k in n.keys] if isinstance(n, ast.Dict)
                 else [lab(c) for c in (n.left, *n.comparators)] if isinstance(n, ast.Compare) else [])
        hits += [(n.lineno, f) for f in found if f]  # type: ignore[attr-defined]
    return hits


def _found(labels: frozenset[str] = LABELS) -> set[str]:
    return {f"{p.relative_to(ROOT)}:{line}: {lab!r}" for p in ROOT.rglob("*.py") if p.name != "style.py"
            for line, lab in _label_uses(parsed(p), labels)}


def test_the_scan_finds_a_label_used_as_a_key() -> None:
    label = style.METHOD_LABELS["split_ci"]
    src = f"a = {{{label!r}: 1}}\nb = a[{label!r}]\nc = x == {label!r}\nd = {{'split_ci': {label!r}}}\n"
    assert [line for line, _ in _label_uses(ast.parse(src))] == [1, 2, 3]


def test_the_scan_passes_over_field_names_of_a_result_spec_only() -> None:
    """A result class's spec names its fields (chapter 06's particle snapshot has a field ``centralised``); the same
    word as a key of any other dict is still found."""
    label = style.METHOD_LABELS["arch_centralised"]
    src = f"s = ResultSpec({{{label!r}: array(4)}})\nt = R.ResultSpec({{{label!r}: 1}})\nd = {{{label!r}: 1}}\n"
    assert [line for line, _ in _label_uses(ast.parse(src))] == [3]


def test_the_scan_finds_single_word_and_hyphenated_labels() -> None:
    """The plain-word labels of issue 36's second pass: a network keyed "feedback", a reading "two-point", a ridge
    option compared with "centralised", chapter 07's information classes keyed "causal" and "look-ahead"."""
    for key in ("arch_feedback", "arch_centralised", "reg_two_point", "reg_info_causal", "reg_info_look_ahead"):
        label = {**style.METHOD_LABELS, **style.METHOD_SHORT_LABELS}[key]
        assert label in LABELS and " " not in label
        src = f"a = {{{label!r}: 1}}\nb = a[{label!r}]\nif w == {label!r}:\n    pass\n"
        assert [line for line, _ in _label_uses(ast.parse(src))] == [1, 2, 3]


def test_the_scan_finds_the_coupling_cases_labels() -> None:
    """Chapter 04's correlated cases were keyed by their labels ("unequal coupling", ...) in
    ``fusion.scenarios.correlated_sensors`` and the chapter's records: their labels are registered, so the scan
    finds them as keys, subscripts and comparands, and their keys (``CouplingCase``) have a label each."""
    from fusion.scenarios.correlated_sensors import SCENARIOS, CouplingCase

    assert set(SCENARIOS) <= set(CouplingCase)
    for key in CouplingCase:
        label = style.METHOD_LABELS[key]
        assert label in LABELS
        src = f"a = {{{label!r}: 1}}\nb = a[{label!r}]\nif w == {label!r}:\n    pass\n"
        assert [line for line, _ in _label_uses(ast.parse(src))] == [1, 2, 3]


def test_the_case_keys_of_chapters_01_to_03_have_scanned_labels() -> None:
    """Chapter 01's failure case, chapter 02's fault case and chapter 03's signal were keyed by their labels ("no
    failure", "fault", "two tones", ...): each has a key type whose members have a registered label, which the scan
    finds as a key, a subscript and a comparand."""
    from fusion.book.chapters.ofs import FailureCase
    from fusion.scenarios.lecture_weighting.consistency import FaultCase
    from fusion.scenarios.wavelet_sensors import SIGNALS, Signal

    assert set(SIGNALS) == set(Signal)
    labels = {style.METHOD_LABELS[k] for keys in (FailureCase, FaultCase, Signal) for k in keys}
    assert {"no failure", "failure", "no fault", "fault", "two tones", "slow", "constant", "HeaviSine"} == labels
    for label in labels:
        assert label in LABELS
        src = f"a = {{{label!r}: 1}}\nb = a[{label!r}]\nif w == {label!r}:\n    pass\n"
        assert [line for line, _ in _label_uses(ast.parse(src))] == [1, 2, 3]


def test_labels_that_are_keys_are_left_out() -> None:
    """A label whose text is a key of the registry is a method key where code uses it ("mean", "median")."""
    assert {"mean", "median"} <= KEYS and not {"mean", "median"} & LABELS
    assert _label_uses(ast.parse("a = {'mean': 1, 'median': 2}\nb = a['mean']\n")) == []


def test_no_module_is_keyed_by_a_display_label() -> None:
    assert len(LABELS) > 100 and len({lab for lab in LABELS if " " not in lab}) >= 8
    found = _found()
    assert not found, sorted(found)
