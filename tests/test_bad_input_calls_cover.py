"""Every public function of the chapter layer has a valid call in one of the chapter registries (issue 35).

The main package's registry (``tests/test_bad_input.py``) leaves ``fusion.book.chapters.*`` out; the four chapter
registries ``tests/test_bad_input_calls_ch*.py`` each cover the modules of their ``PREFIXES`` (and check that they
do). This test closes the gap between them: a chapter module that no group's prefixes name (a new chapter, a renamed
module) would escape every sweep.
"""

from __future__ import annotations

import importlib
import inspect

from test_bad_input import public_callables

GROUPS = ("test_bad_input_calls_ch010307", "test_bad_input_calls_ch0204", "test_bad_input_calls_ch05",
          "test_bad_input_calls_ch06")


def test_every_public_chapter_function_is_in_one_group() -> None:
    modules = [importlib.import_module(g) for g in GROUPS]
    chapter = {k for k, v in public_callables().items()
               if k.startswith("fusion.book.chapters.") and not inspect.isclass(v)}
    owners = {k: [m.__name__ for m in modules if k.startswith(m.PREFIXES)] for k in chapter}
    nowhere = sorted(k for k, o in owners.items() if not o)
    twice = sorted(k for k, o in owners.items() if len(o) > 1)
    assert not nowhere, f"public chapter functions in no registry group's PREFIXES: {nowhere}"
    assert not twice, f"public chapter functions in two groups: {twice}"
    # each group's test_registry_covers_the_group checks that its registry() holds every name of its PREFIXES
    # but its EXCLUDED; here only the exclusions are counted (no study is built)
    excluded = sum(len(m.EXCLUDED) for m in modules)
    assert excluded <= 0.06 * len(chapter), f"{excluded} of {len(chapter)} chapter functions excluded: build their calls"
