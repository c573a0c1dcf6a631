"""Time the book: each notebook from a clean kernel, a cold `make book`, and `make test`.

Targets (issue 7): the whole book executes and builds in under 3 minutes and `make test`
runs in under 5 minutes on a 2-core machine. Results go to
`benchmarks/results/book.json`, which the status page of the book displays.

Run from the repository root after `make test` has created `.venv`:
`.venv/bin/python benchmarks/bench_book.py` (about as long as one `make book` plus one
`make test`; it deletes `_build/` to measure a cold build).
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from _results import write_results  # benchmarks/_results.py (scripts run from anywhere)

ROOT = Path(__file__).resolve().parents[1]
BIN = Path(sys.executable).parent


def timed(cmd: list[str], **kwargs: object) -> float:
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, **kwargs)
    return time.perf_counter() - t0


def main() -> None:
    env = dict(os.environ, PATH=f"{BIN}{os.pathsep}{os.environ['PATH']}")
    measurements = []
    with tempfile.TemporaryDirectory() as tmp:
        for nb in sorted((ROOT / "notebooks").glob("*.ipynb")):
            out = Path(tmp) / nb.name
            seconds = timed(
                [str(BIN / "jupyter"), "nbconvert", "--to", "notebook", "--execute", str(nb),
                 "--output", str(out), "--ExecutePreprocessor.timeout=900"],
                env=env,
            )
            measurements.append({"what": f"execute {nb.name} (nbconvert, fresh kernel)", "value": seconds, "unit": "s"})
    shutil.rmtree(ROOT / "_build", ignore_errors=True)
    measurements.append({"what": "make book, cold (no _build, no execution cache)",
                         "value": timed(["make", "book"], env=env), "unit": "s"})
    measurements.append({"what": "make book, warm (nothing changed)",
                         "value": timed(["make", "book"], env=env), "unit": "s"})
    measurements.append({"what": "make test (unit tests, nbval, browser test)",
                         "value": timed(["make", "test"], env=env), "unit": "s"})
    write_results("book", measurements)


if __name__ == "__main__":
    main()
