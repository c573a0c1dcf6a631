"""Time the book: each notebook from a clean kernel, a cold `make book`, and `make test`.

Budgets (the developers' guide): a cold `make book` within 180 s and `make test` within 300 s on a 2-core machine;
targets of issue 37: 120 s and 240 s. Results go to `benchmarks/results/book.json`, which the status page of the
book displays (and from which `tools/execute_notebooks.py` reads each notebook's seconds to schedule the longest
first).

Each command is measured in wall seconds and in CPU seconds (its own and its child processes', from
``RUSAGE_CHILDREN``), with the machine's 1-minute load average just before it: a wall time far above CPU / cores
on a machine whose load was already above zero measured the other work too, and is not a property of the book.

Run from the root of a fresh clone after `make .venv/.installed`:
`.venv/bin/python benchmarks/bench_book.py` (about as long as one `make book` plus one `make test`; it deletes
`_build/` to measure a cold build). ``--commands-only`` skips the per-notebook executions (which the scheduler's
record needs only when a notebook's cost changed a lot).
"""

from __future__ import annotations

import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from _results import write_results  # benchmarks/_results.py (scripts run from anywhere)

ROOT = Path(__file__).resolve().parents[1]
BIN = Path(sys.executable).parent


def _children_cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def timed(cmd: list[str], **kwargs: object) -> tuple[float, float, float]:
    """(wall seconds, CPU seconds of the command and its children, 1-minute load average just before)."""
    load = os.getloadavg()[0]
    cpu0, t0 = _children_cpu(), time.perf_counter()
    subprocess.run(cmd, check=True, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, **kwargs)
    return time.perf_counter() - t0, _children_cpu() - cpu0, load


def _rows(what: str, measured: tuple[float, float, float]) -> list[dict[str, object]]:
    wall, cpu, load = measured
    return [{"what": what, "value": wall, "unit": "s", "cpu_seconds": round(cpu, 1), "load_before": round(load, 2)}]


def _stored_notebook_rows() -> list[dict[str, object]]:
    """The per-notebook rows of the stored ``book.json``, each with the date it was measured on."""
    import json

    try:
        stored = json.loads((ROOT / "benchmarks" / "results" / "book.json").read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return []
    return [{**m, "measured_on": m.get("measured_on", stored.get("date", ""))} for m in stored.get("measurements", [])
            if str(m.get("what", "")).startswith("execute ")]


def main(argv: list[str]) -> None:
    env = dict(os.environ, PATH=f"{BIN}{os.pathsep}{os.environ['PATH']}")
    measurements: list[dict[str, object]] = []
    if "--commands-only" in argv:   # keep the stored per-notebook rows (tools/execute_notebooks.py schedules by them)
        measurements += _stored_notebook_rows()
    else:
        with tempfile.TemporaryDirectory() as tmp:
            for nb in sorted((ROOT / "notebooks").glob("*.ipynb")):
                out = Path(tmp) / nb.name
                measured = timed(
                    [str(BIN / "jupyter"), "nbconvert", "--to", "notebook", "--execute", str(nb),
                     "--output", str(out), "--ExecutePreprocessor.timeout=900"],
                    env=dict(env, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1", MKL_NUM_THREADS="1"),
                )
                measurements += _rows(f"execute {nb.name} (nbconvert, fresh kernel)", measured)
    shutil.rmtree(ROOT / "_build", ignore_errors=True)
    measurements += _rows("make book, cold (no _build, no execution cache)", timed(["make", "book"], env=env))
    measurements += _rows("make book, warm (nothing changed)", timed(["make", "book"], env=env))
    measurements += _rows("make test (unit tests, nbval, book build, browser test)", timed(["make", "test"], env=env))
    write_results("book", measurements, cores=os.cpu_count())


if __name__ == "__main__":
    main(sys.argv[1:])
