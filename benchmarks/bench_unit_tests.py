"""What do the test suite's hypothesis savings save? The same test files with and without them, side by side (issue 37).

``tests/conftest.py`` cuts two costs of hypothesis that grow with the number of parametrised cases (the bad-input
property files run about 5,000): the function digest (the test's source read and cleaned twice per case) is
computed once per test function, and a parametrised test's settings are reset before each case (hypothesis's
pytest plugin chained one more child per case and walked the chain at every case). ``FUSION_TEST_PLAIN_HYPOTHESIS=1``
turns both off. This script runs ``pytest -n 0`` on the given files (default: the three bad-input property files)
in a subprocess per side, the sides alternating, and keeps each side's median CPU-seconds (user + system of the
subprocess): the machine's load (other jobs share its 2 cores) inflates wall time, not CPU time, and ratios are
only taken between numbers of this same run. Results go to ``benchmarks/results/unit_tests.json``.

Run: ``.venv/bin/python benchmarks/bench_unit_tests.py [--repeats N] [test files...]``
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _results import write_results  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
DEFAULT = ["tests/test_bad_input_properties.py", "tests/test_bad_input_counts.py", "tests/test_bad_input_fuzz10.py"]


def cpu_of_run(files: list[str], plain: bool) -> float:
    """CPU-seconds of one ``pytest -n 0 -q`` run of ``files`` (with ``plain``: hypothesis as installed)."""
    env = {k: v for k, v in os.environ.items() if k != "FUSION_TEST_PLAIN_HYPOTHESIS"}
    if plain:
        env["FUSION_TEST_PLAIN_HYPOTHESIS"] = "1"
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    proc = subprocess.run([sys.executable, "-m", "pytest", "-n", "0", "-q", "-p", "no:cacheprovider", *files],
                          cwd=ROOT, env=env, capture_output=True, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if proc.returncode != 0:
        raise RuntimeError(f"pytest failed (plain={plain}):\n{proc.stdout[-3000:]}\n{proc.stderr[-3000:]}")
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("files", nargs="*", default=DEFAULT)
    parser.add_argument("--repeats", type=int, default=1)
    args = parser.parse_args()
    plain, tuned = [], []
    for _ in range(args.repeats):
        plain.append(cpu_of_run(args.files, plain=True))
        tuned.append(cpu_of_run(args.files, plain=False))
    p, t = statistics.median(plain), statistics.median(tuned)
    what = ", ".join(Path(f).name for f in args.files)
    write_results("unit_tests", [
        {"what": f"pytest -n 0 {what}: hypothesis as installed", "value": p, "unit": "CPU-s"},
        {"what": f"pytest -n 0 {what}: with the conftest's savings", "value": t, "unit": "CPU-s"},
        {"what": "ratio (as installed / with the savings)", "value": p / t, "unit": "x"},
    ], repeats=args.repeats, files=args.files)


if __name__ == "__main__":
    main()
