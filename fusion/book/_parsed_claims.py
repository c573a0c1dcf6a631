"""The parsed YAML of the claim files, kept by their text in the process (:func:`fusion.book.claims.load`).

A claim file is parsed by PyYAML's pure-Python loader, about 0.1 CPU-s for each of the book's files (88 % of a
:func:`fusion.book.claims.load`), and a test run or a notebook loads the same files many times: every worker of
``make test`` loads all five at its collection alone, twice. The document of a text that parsed and passed the
depth rule of the loader is kept here (a deep copy, so that nothing a caller does to its copy reaches it) and a
later load of the same text gets a deep copy of it (about a tenth of the parse; speed58): the same document, every
check of :func:`fusion.book.claims.load` after the parse applied to it again. Texts longer than :data:`MAX_TEXT`
characters are not kept, and at most :data:`MAX_KEPT` documents are, the least recently used dropped first.
"""

from __future__ import annotations

import collections
import copy
import threading
from typing import Any

__all__: list[str] = []

#: Documents kept (the book has five claim files).
MAX_KEPT = 8
#: Characters of the longest text kept (the book's longest claim file has about 136,000).
MAX_TEXT = 1_000_000

_KEPT: collections.OrderedDict[str, Any] = collections.OrderedDict()
_LOCK = threading.Lock()


def kept(raw: str) -> Any | None:
    """A deep copy of the document kept for the text ``raw``, or None when none is."""
    with _LOCK:
        doc = _KEPT.get(raw)
        if doc is None:
            return None
        _KEPT.move_to_end(raw)
    return copy.deepcopy(doc)


def keep(raw: str, doc: Any) -> None:
    """Keep a deep copy of ``doc``, the parsed document of the text ``raw`` (that passed the depth rule)."""
    if len(raw) > MAX_TEXT:
        return
    doc = copy.deepcopy(doc)
    with _LOCK:
        _KEPT[raw] = doc
        while len(_KEPT) > MAX_KEPT:
            _KEPT.popitem(last=False)
