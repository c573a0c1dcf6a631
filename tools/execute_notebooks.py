"""Execute the book's notebooks on every core, into jupyter-book's execution cache.

``make book`` runs this before ``jupyter-book build``. Jupyter-book 1.x (myst-nb) executes the
notebooks of a cold build one after the other, while Sphinx reads them; here jupyter-cache's
parallel executor runs them over a pool of one process per core, into the cache the build then
reads (``_build/.jupyter_cache``: myst-nb's default beside the HTML output). A notebook whose code
has not changed since it was cached is not executed again, as in the build itself; a notebook that
fails is left for the build, which re-executes it and reports the error (``-W``: the build fails).

Usage: ``python tools/execute_notebooks.py CACHE_DIR NOTEBOOK...``. A chapter's appendix
(``*_appendix.ipynb``) runs after its own chapter, which it may read (the ledger its chapter writes
in ``book/ledger``, the studies it leaves in the study cache), and no longer waits for the other
chapters. Whenever a core is free it takes, of the notebooks whose chapter has finished, the one
with the longest chain still ahead of it (its own time plus its appendix's, from the times of
``benchmarks/results/book.json`` when present), so the longest chain starts first and no core
idles while another runs a chain that could have been split (:func:`next_notebook`).

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


def chapter_of(nb: Path) -> Path | None:
    """The chapter an appendix belongs to (``X_appendix.ipynb`` -> ``X.ipynb`` beside it); None for a chapter."""
    stem = nb.stem
    return nb.with_name(stem[: -len("_appendix")] + nb.suffix) if stem.endswith("_appendix") else None


def next_notebook(waiting: list[Path], running: set[Path], seconds: dict[str, float]) -> Path | None:
    """The notebook a free core runs next, or None if every waiting one waits for its chapter.

    Parameters
    ----------
    waiting : list of Path
        Notebooks not yet started.
    running : set of Path
        Notebooks started and not finished.
    seconds : dict
        Measured seconds by file name (missing: 0).

    Returns
    -------
    Path or None
        Of the waiting notebooks that are chapters or appendices whose chapter is neither waiting nor running,
        the one with the longest chain ahead: its seconds plus, for a chapter whose appendix is waiting, the
        appendix's; ties by name.
    """
    pending = set(waiting)

    def chain(nb: Path) -> float:
        appendix = nb.with_name(nb.stem + "_appendix" + nb.suffix)
        return seconds.get(nb.name, 0.0) + (seconds.get(appendix.name, 0.0) if appendix in pending else 0.0)

    ready = [nb for nb in waiting if (ch := chapter_of(nb)) is None or (ch not in pending and ch not in running)]
    return min(ready, key=lambda nb: (-chain(nb), nb.name)) if ready else None


def _execute(argv: list[str]) -> int:
    from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait

    from jupyter_cache import get_cache
    from jupyter_cache.executors import load_executor
    from jupyter_cache.executors.basic import ExecutionWorkerLocalMProc, ProcessData

    cache = get_cache(Path(argv[0]))
    seconds = _measured_seconds()
    notebooks = sorted(Path(p).resolve() for p in argv[1:])
    # a notebook without code (a prose-only appendix) has nothing to execute, and all such notebooks share one
    # cache key: executed in parallel they would collide in the cache, so the build handles them (one by one)
    notebooks = [nb for nb in notebooks if _has_code(nb)]
    for nb in notebooks:
        cache.add_nb_to_project(str(nb))
    executor = load_executor("local-parallel", cache)
    records = {Path(r.uri): r for r in executor.get_records([str(nb) for nb in notebooks], clear_tracebacks=True)}
    waiting = [nb for nb in notebooks if nb in records]
    worker, outcome, futures = ExecutionWorkerLocalMProc(), {}, {}
    with ProcessPoolExecutor(max_workers=_cores()) as pool:
        while waiting or futures:
            while len(futures) < _cores() and (nb := next_notebook(waiting, set(futures.values()), seconds)):
                waiting.remove(nb)
                data = ProcessData(records[nb].pk, records[nb].uri, cache, 600, False)
                futures[pool.submit(worker, data)] = nb
            finished, _ = wait(futures, return_when=FIRST_COMPLETED)
            for fut in finished:
                outcome[futures.pop(fut)] = fut.result()[0]
    for nb, code in outcome.items():
        if code:
            kind = "excepted" if code == 1 else "errored"
            print(f"execute_notebooks: {nb.name} {kind}; the book build will re-execute it and report why",
                  file=sys.stderr)
    executed = sum(code == 0 for code in outcome.values())
    print(f"execute_notebooks: {executed} executed, {len(notebooks) - len(outcome)} already cached", file=sys.stderr)
    return 0


def _cores() -> int:
    """Processes: one per core this process may use."""
    return max(1, len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1))


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
