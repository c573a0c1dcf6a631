"""Execute the book's notebooks on every core, into jupyter-book's execution cache.

``make book`` runs this before ``jupyter-book build``. Jupyter-book 1.x (myst-nb) executes the
notebooks of a cold build one after the other, while Sphinx reads them; here jupyter-cache's
parallel executor runs them over a pool of one process per core, into the cache the build then
reads (``_build/.jupyter_cache``: myst-nb's default beside the HTML output). A notebook whose code
has not changed since it was cached is not executed again, as in the build itself; a notebook that
fails is left for the build, which re-executes it and reports the error (``-W``: the build fails).

Usage: ``python tools/execute_notebooks.py CACHE_DIR NOTEBOOK...``. The notebooks are queued
longest first (the times of ``benchmarks/results/book.json`` when present), so the longest one does
not start last while a core idles. A chapter's appendix (``*_appendix.ipynb``) runs after the chapters:
it may read what its chapter wrote (the ledger in ``book/ledger``).

The kernels share one study cache (``FUSION_STUDY_CACHE``, :mod:`fusion.book.study_cache`) in a temporary
directory created for this run (unless the caller set one) and deleted at its end.
"""
from __future__ import annotations

import json
import os
import re
import shutil
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
#: The shared study cache's environment variable (``fusion.book.study_cache.ENV``): a fresh directory per run.
STUDY_CACHE_ENV = "FUSION_STUDY_CACHE"


def _measured_seconds() -> dict[str, float]:
    """Seconds per notebook from the last benchmark of the book (``benchmarks/bench_book.py``)."""
    path = ROOT / "benchmarks" / "results" / "book.json"
    try:
        found = json.loads(path.read_text(encoding="utf-8"))["measurements"]
    except (OSError, KeyError, ValueError):
        return {}
    out = {}
    for m in found:
        name = re.match(r"execute (\S+\.ipynb)", str(m.get("what", "")))
        if name:
            out[name[1]] = float(m["value"])
    return out


def _has_code(nb: Path) -> bool:
    cells = json.loads(nb.read_text(encoding="utf-8"))["cells"]
    return any(c["cell_type"] == "code" and "".join(c["source"]).strip() for c in cells)


def main(argv: list[str]) -> int:
    if len(argv) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    if os.environ.get(STUDY_CACHE_ENV):
        return _execute(argv)
    # the run's shared study cache (fusion/book/study_cache.py): the kernels inherit it, so a study two notebooks
    # need (chapter 06's networks in the chapter and its appendix) is computed once; removed when the run ends
    study_dir = tempfile.mkdtemp(prefix="fusion-study-cache-")
    os.environ[STUDY_CACHE_ENV] = study_dir
    try:
        return _execute(argv)
    finally:
        del os.environ[STUDY_CACHE_ENV]
        shutil.rmtree(study_dir, ignore_errors=True)


def _execute(argv: list[str]) -> int:
    from jupyter_cache import get_cache
    from jupyter_cache.executors import load_executor

    cache = get_cache(Path(argv[0]))
    seconds = _measured_seconds()
    notebooks = sorted((Path(p).resolve() for p in argv[1:]), key=lambda p: (-seconds.get(p.name, 0.0), p.name))
    # a notebook without code (a prose-only appendix) has nothing to execute, and all such notebooks share one
    # cache key: executed in parallel they would collide in the cache, so the build handles them (one by one)
    notebooks = [nb for nb in notebooks if _has_code(nb)]
    for nb in notebooks:
        cache.add_nb_to_project(str(nb))
    executed = ran = 0
    for phase in ([nb for nb in notebooks if not nb.stem.endswith("_appendix")],
                  [nb for nb in notebooks if nb.stem.endswith("_appendix")]):
        if not phase:
            continue
        result = load_executor("local-parallel", cache).run_and_cache(
            filter_uris=[str(nb) for nb in phase], timeout=600, allow_errors=False)
        for kind in ("excepted", "errored"):
            for uri in getattr(result, kind):
                print(f"execute_notebooks: {Path(uri).name} {kind}; the book build will re-execute it and report "
                      "why", file=sys.stderr)
        executed += len(result.succeeded)
        ran += len(result.all())
    print(f"execute_notebooks: {executed} executed, {len(notebooks) - ran} already cached", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
