"""The stored character classes of the claim texts' rule (``fusion.book._claim_text_ucd``).

Speed 66b: ``_refused_class`` and ``_visible_class`` scanned all 1,114,112 code points with ``unicodedata`` at first
use, 0.08 + 0.23 CPU-s measured in every process that checks a text (each notebook kernel, test worker and child
process). They now read runs stored for the Unicode database they were derived from; these tests check that the
stored runs are exactly the derivation on this Python (the same characters accepted and refused) and that they are
the ones used.
"""

from __future__ import annotations

import time
import unicodedata

from fusion.book import _claim_text as ct
from fusion.book import _claim_text_ucd as ucd


def test_the_stored_runs_are_the_derivation_of_this_pythons_unicode_database() -> None:
    """The runs stored equal those derived from ``unicodedata`` on every code point, for the version they name, and
    that version is this Python's (else the classes are derived again at first use: correct, but 0.3 CPU-s a
    process; store the new runs with ``_claim_text._runs_text`` then)."""
    assert ucd.UNIDATA_VERSION == unicodedata.unidata_version, "store the runs of this Unicode database"
    refused, invisible = ct._refused_runs(), ct._invisible_runs()
    assert ct._stored_runs(ucd.REFUSED) == refused
    assert ct._stored_runs(ucd.INVISIBLE) == invisible
    assert ucd.REFUSED.split() == ct._runs_text(refused).split()
    assert ucd.INVISIBLE.split() == ct._runs_text(invisible).split()
    assert ct._refused_class() == "[" + "".join(f"\\U{a:08x}-\\U{b:08x}" for a, b in refused) + "]"
    assert ct._visible_class() == "[^" + "".join(f"\\U{a:08x}-\\U{b:08x}" for a, b in invisible) + "]"


def test_the_classes_are_built_without_scanning_the_code_points() -> None:
    """Building both classes (uncached) takes ~1 ms, not the 0.31 CPU-s of a scan of every code point."""
    t = time.process_time()
    ct._refused_class.__wrapped__()
    ct._visible_class.__wrapped__()
    assert time.process_time() - t < 0.05
