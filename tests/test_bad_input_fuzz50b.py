"""Fuzz 50b: the claim files' text rule scans a text at C speed."""

from __future__ import annotations

import sys
import time
import unicodedata

import pytest

from fusion.book._claim_text import _ASCII_REFUSED, _refused, text_problem
from fusion.book.ledger import Claim


def test_c1_a_long_text_is_checked_at_c_speed() -> None:
    """A 200-million-character text took 58 CPU-s (a Python loop over its characters, 65 ns each); 20 million now
    take 0.06 (ASCII) to 0.3 CPU-s."""
    for text in ("x" * 20_000_000, "中" * 20_000_000):
        t = time.process_time()
        assert text_problem(text, required=False) is None
        assert time.process_time() - t < 0.6   # 0.06 (ASCII) and 0.3 CPU-s measured; 1.3 by the loop
    with pytest.raises(ValueError, match=r"^claim holds the invisible control or format character U\+200B"):
        Claim("c-x", "yang2012optimal", "p. 1", "x" * 1_000_000 + "\u200b", "1.0", None, "link")  # type: ignore[arg-type]


def test_the_character_classes_are_the_categories() -> None:
    """The regular expressions refuse exactly Cc (but tab and line break), Cf and Cs, every code point checked."""
    every = "".join(map(chr, range(sys.maxunicode + 1)))
    want = {i for i, c in enumerate(every) if unicodedata.category(c) in ("Cc", "Cf", "Cs") and c not in "\t\n"}
    assert {m.start() for m in _refused().finditer(every)} == want
    assert {m.start() for m in _ASCII_REFUSED.finditer(every[:128])} == {i for i in want if i < 128}
    assert text_problem("tab\tand line\nbreak, é, 中文", required=False) is None
