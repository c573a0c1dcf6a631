"""Helpers that several test modules share (not a test module: pytest collects only ``test_*.py``).

- :func:`bounded`: run a call under a wall-clock alarm and classify its outcome (the bad-input tests).
- :func:`arrays`: the arrays in a result, in order; :func:`one_computation`: whether two results come from one
  study-cache entry (the chapters' tests).
- :func:`cached_study`, :data:`CACHE_CALLS`, :func:`study_entry`: a tiny study behind the study cache and its entry
  on disk (the cache's damaged-entry tests).
- :func:`parsed`: a source file's syntax tree, parsed once per process (the source-scanning tests).
- :func:`glue_refused`, :func:`glued`: ``glue_all`` refusing a mapping quickly, or what it hands to ``myst_nb.glue``
  (the glue tests); :func:`glued_in_child`: cases glued in one child under a memory limit.
"""

from __future__ import annotations

import ast
import dataclasses
import functools
import json
import signal
import subprocess
import sys
import textwrap
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from fusion.book.study_cache import study_cache


#: Syntax trees by source text (:func:`parsed`).
_PARSED: dict[str, ast.Module] = {}


def parsed(path: Path | str) -> ast.Module:
    """``ast.parse`` of the UTF-8 text of the file at ``path``, read at every call and parsed once per process per text.

    Nine source-scanning tests (error messages, seed checks, headers, labels, caches, dataclasses, glue, specs) walk
    the modules of ``fusion/``; each parsed all of them again (about 1.7 CPU-s for the package). The tree depends on
    the text only, so a file whose text is unchanged gives the tree parsed before: the same tree ``ast.parse`` gives.
    The trees are shared: a caller reads them and must not change them (none does: they walk and compare).
    """
    text = Path(path).read_text(encoding="utf-8")
    tree = _PARSED.get(text)
    if tree is None:
        tree = _PARSED[text] = ast.parse(text)
    return tree


class _Timeout(Exception):
    pass


def _on_alarm(*_: Any) -> None:
    raise _Timeout


def bounded(call: Callable[[], Any], seconds: int, late: str) -> tuple[str, Any]:
    """Run ``call`` under a wall-clock alarm of ``seconds``: ("ok", result) or ("raised", exception); past the
    alarm the test fails with the message ``late``."""
    old = signal.signal(signal.SIGALRM, _on_alarm)
    signal.alarm(seconds)
    try:
        return "ok", call()
    except _Timeout:
        pytest.fail(late)
    except Exception as exc:  # noqa: BLE001 - classified by the caller
        return "raised", exc
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)


def arrays(value: object) -> list[np.ndarray]:
    """The arrays in a result (dataclass fields, mappings, sequences), in order."""
    if isinstance(value, np.ndarray):
        return [value]
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return [a for f in dataclasses.fields(value) for a in arrays(getattr(value, f.name))]
    if isinstance(value, Mapping):
        return [a for v in value.values() for a in arrays(v)]
    if isinstance(value, (list, tuple)):
        return [a for v in value for a in arrays(v)]
    return []


def one_computation(a: object, b: object) -> bool:
    """Two results come from one cache entry: a cached result with a mutable part (a dict) is copied for each caller
    (fusion/book/study_cache.py), each caller's arrays new objects over the kept read-only memory (its ``bytes``
    base, fuzz 37a C1); a second computation would have memory of its own."""
    xs, ys = arrays(a), arrays(b)
    return len(xs) == len(ys) > 0 and all(x is y or (x.base is not None and x.base is y.base) for x, y in zip(xs, ys))


# --- a tiny study behind the study cache (the cache's damaged-entry tests) -------------------------------------------

#: The ``n`` of every computation of :func:`cached_study` (a hit adds nothing).
CACHE_CALLS: list[int] = []


def _tiny_study(n: int) -> np.ndarray:
    CACHE_CALLS.append(n)
    return np.arange(n) * 1.5


#: :func:`_tiny_study` behind the study cache (a module-level function: only such a function reaches the disk).
cached_study = study_cache(maxsize=4)(_tiny_study)


def study_entry(tmp_path: Any, monkeypatch: pytest.MonkeyPatch) -> Any:
    """Point the study cache at ``tmp_path``, compute ``cached_study(5)`` once and return its entry file (the
    in-memory layer cleared, so that the next call reads the disk)."""
    from fusion.book import study_cache as sc

    monkeypatch.setenv(sc.ENV, str(tmp_path))
    cached_study.cache_clear()
    CACHE_CALLS.clear()
    assert np.array_equal(cached_study(5), np.arange(5) * 1.5) and CACHE_CALLS == [5]
    (entry,) = tmp_path.glob("*.pkl")
    cached_study.cache_clear()
    return entry


class ShrinkingLen(Sequence):
    """A Sequence whose ``len()`` is truthful on its first two calls, then 1; the items never change (a caller that
    counts by a second ``len()`` counts one item: fuzz 41a, 42a)."""

    def __init__(self, items):
        self.items, self.calls = list(items), 0

    def __len__(self):
        self.calls += 1
        return len(self.items) if self.calls <= 2 else 1

    def __getitem__(self, i):
        return self.items[i]


def refused_quickly(call: Callable[[], Any], error: type[BaseException], match: str, cpu: float = 1.0) -> None:
    """``call()`` raises ``error`` matching ``match`` within ``cpu`` CPU-s of its own: a refusal before any work.

    Garbage collection is off during the call (a collection of a full run's heap inside a timed call cost 1.12 CPU-s
    late in a worker, 0.12-0.17 in a fresh process), and not forced before it (a ``gc.collect()`` of a full run's heap
    at each call cost 33 CPU-s over one file). A first use that imports or builds caches belongs outside, untimed.
    """
    import gc
    import time

    gc.disable()
    try:
        t = time.process_time()
        with pytest.raises(error, match=match):
            call()
        assert time.process_time() - t < cpu, f"refused after {time.process_time() - t:.2f} CPU-s"
    finally:
        gc.enable()


def glue_refused(values: dict, error: type, match: str = r"values\['k'\]") -> None:
    """``glue_all(values)`` raises ``error`` matching ``match`` within 1 CPU-s (a refusal before any work)."""
    import time

    from fusion.book.glue import glue_all
    with pytest.raises(error, match=match):   # the first use imports IPython's formatters and builds the type
        glue_all(values)                      # caches (a make test run found 1.02 CPU-s): untimed
    t = time.process_time()
    with pytest.raises(error, match=match):
        glue_all(values)
    assert time.process_time() - t < 1.0


def glued(monkeypatch: pytest.MonkeyPatch, values: dict) -> dict:
    """What ``glue_all(values)`` hands to ``myst_nb.glue``, by key (``myst_nb.glue`` replaced for the test)."""
    import myst_nb

    from fusion.book.glue import glue_all
    got: dict = {}
    monkeypatch.setattr(myst_nb, "glue", lambda k, v, display=True: got.__setitem__(k, v))
    glue_all(values)
    return got


#: The child of :func:`glued_in_child`: each case's value built by its expression, glued, timed, then dropped.
_GLUE_CHILD = textwrap.dedent("""
    import json, resource, sys, time
    resource.setrlimit(resource.RLIMIT_AS, (3 << 30, 3 << 30))
    import numpy as np, pandas as pd
    from pandas._libs.sparse import IntIndex
    from fusion.book.glue import glue_all
    glue_all({"k": 0.5})   # imports (IPython's formatters) outside the timing
    out = {}
    for name, expr in json.loads(sys.stdin.read()).items():
        value = eval(expr)
        t = time.process_time()
        try:
            glue_all({"k": value})
            out[name] = ["ACCEPTED", time.process_time() - t, ""]
        except BaseException as e:
            out[name] = [type(e).__name__, time.process_time() - t, str(e)[:300]]
        del value
    print(json.dumps(out))
""")


@functools.cache
def glued_in_child(cases: tuple[tuple[str, str], ...]) -> dict[str, list]:
    """Glue each case's value (a Python expression over ``np``, ``pd`` and pandas' ``IntIndex``) in ONE child process
    under a 3 GiB address-space limit (a conversion the glue should have refused raises MemoryError there instead of
    taking the machine), once per process: by case name, [outcome, CPU-s of the call, the message's first 300
    characters], the outcome ``"ACCEPTED"`` or the exception's type name. One child for all cases: each child's import
    of the book layer costs 1-2 CPU-s."""
    run = subprocess.run([sys.executable, "-c", _GLUE_CHILD], input=json.dumps(dict(cases)), capture_output=True,
                         text=True, timeout=600)
    assert run.returncode == 0, run.stderr[-2000:]
    return json.loads(run.stdout)


def glue_outcome(cases: Mapping[str, str], case: str, refused: str) -> None:
    """Case ``case`` of ``cases`` (name -> expression, all glued in one child by :func:`glued_in_child`) ends within
    1 CPU-s: accepted if its name starts with ``accepted``, else a ValueError whose message (its first 300
    characters) matches the regular expression ``refused`` (``re.search``, dot matching line breaks)."""
    import re

    out = glued_in_child(tuple(cases.items()))[case]
    assert float(out[1]) < 1.0, out
    if case.startswith("accepted"):
        assert out[0] == "ACCEPTED", out
    else:
        assert out[0] == "ValueError", out
        assert re.search(refused, out[2], re.S), out


def figure_axes() -> tuple[Any, Any]:
    """A figure and its one axes, limits (0, 1) x (0, 1): the glue figure tests' canvas."""
    import matplotlib.pyplot as plt

    fig = plt.figure()
    ax = fig.add_subplot()
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1)
    return fig, ax


def figure_refused(fig: Any, match: str = r"values\['k'\]") -> None:
    """``fig`` is refused within 1 CPU-s by its weight (``figure_units``, fast on an old weigher too: the count
    first), and by glue_all, naming values['k'] (and ``match``); closed after."""
    import matplotlib.pyplot as plt

    from fusion.book import _glue_figure as F
    try:
        refused_quickly(lambda: F.figure_units(fig, "k"), ValueError, match)
        glue_refused({"k": fig}, ValueError, match)
    finally:
        plt.close(fig)


def figure_glued(monkeypatch: pytest.MonkeyPatch, fig: Any) -> None:
    """glue_all glues ``fig`` (audited and rendered; ``myst_nb.glue`` replaced for the test); closed after."""
    import matplotlib.pyplot as plt

    try:
        glued(monkeypatch, {"k": fig})
    finally:
        plt.close(fig)
