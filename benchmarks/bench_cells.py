"""CPU seconds of every code cell of chapter notebooks, this tree beside an older revision's package, in one run.

Each notebook's code cells run in order in one IPython shell (one process per notebook and package, the study
cache off: every study is computed), timed with ``time.process_time``, so the numbers are CPU, not wall, and a
machine shared with other jobs changes them little. With ``--base REV`` the same notebooks run a second time with
the ``fusion`` package of git revision ``REV`` (``git archive`` of it with ``book/`` and ``benchmarks/results/``, which
it reads beside itself; first on ``PYTHONPATH``), and each cell's ratio
base / this tree is printed beside it (issue 37: the notebooks' CPU in ``make test`` and ``make book``).

Run from the repository root: ``.venv/bin/python benchmarks/bench_cells.py notebooks/01_optimal_fusion_set.ipynb
--base main`` (about the notebooks' own CPU time, twice). Nothing is written; the notebooks are not modified (a
cell that writes a ledger writes the same file).
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: The child: run one notebook's code cells in an IPython shell and print one JSON list of CPU seconds per cell.
_CHILD = r"""
import json, os, sys, time
os.environ.pop("FUSION_STUDY_CACHE", None)
import matplotlib
matplotlib.use("Agg")
from IPython.core.interactiveshell import InteractiveShell
nb = json.load(open(sys.argv[1], encoding="utf-8"))
shell = InteractiveShell.instance()
out = []
for cell in (c for c in nb["cells"] if c["cell_type"] == "code"):
    t = time.process_time()
    ok = shell.run_cell("".join(cell["source"]), silent=True).success
    out.append([time.process_time() - t, ok])
print("CELLS " + json.dumps(out))
"""


def cell_cpu(notebook: Path, pythonpath: str | None) -> list[tuple[float, bool]]:
    """CPU seconds and success of every code cell of ``notebook``, run in a fresh process from its folder."""
    env = dict(os.environ)
    env.pop("FUSION_STUDY_CACHE", None)
    if pythonpath:
        env["PYTHONPATH"] = pythonpath
    done = subprocess.run([sys.executable, "-c", _CHILD, str(notebook.resolve())], cwd=notebook.parent, env=env,
                          capture_output=True, text=True, check=True)
    line = next(ln for ln in done.stdout.splitlines() if ln.startswith("CELLS "))
    return [(float(t), bool(ok)) for t, ok in json.loads(line[len("CELLS "):])]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("notebooks", nargs="+", type=Path)
    parser.add_argument("--base", help="git revision whose fusion package runs the same cells for comparison")
    parser.add_argument("--min", type=float, default=0.2, help="print cells of at least this many CPU seconds")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        if args.base:
            # the package and the files it reads beside itself (claim files, ledgers, stored benchmark results)
            archive = subprocess.run(["git", "archive", args.base, "fusion", "book", "benchmarks/results"], cwd=ROOT,
                                     capture_output=True, check=True)
            subprocess.run(["tar", "-x", "-C", tmp], input=archive.stdout, check=True)
        for nb in args.notebooks:
            new = cell_cpu(nb, None)
            base = cell_cpu(nb, tmp) if args.base else None
            print(f"\n{nb.name}: CPU s per code cell" + (f" (base {args.base} | this tree | ratio)" if base else ""))
            for i, (t, ok) in enumerate(new):
                if base is None:
                    if t >= args.min or not ok:
                        print(f"  cell {i:3d} {t:8.2f}{'' if ok else '  FAILED'}")
                elif max(t, base[i][0]) >= args.min or not (ok and base[i][1]):
                    print(f"  cell {i:3d} {base[i][0]:8.2f} {t:8.2f} {base[i][0] / max(t, 1e-9):6.2f}"
                          f"{'' if base[i][1] else '  FAILED (base)'}{'' if ok else '  FAILED'}")
            total = sum(t for t, _ in new)
            if base is None:
                print(f"  total    {total:8.2f}")
            else:
                b = sum(t for t, _ in base)
                print(f"  total    {b:8.2f} {total:8.2f} {b / total:6.2f}")


if __name__ == "__main__":
    main()
