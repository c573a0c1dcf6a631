"""Issue 37: row-blocked kernels and the shared study cache, timed side by side with the paths they replace.

Each row times the previous path and the new one on the same input, interleaved (``REPEATS`` rounds, process CPU
time, median), checks that both give the same bytes, and records the ratio (previous / new: above 1 the new path
is faster):

* ``set_weights``, ``members``, ``support``: chapter 01's optimal-fusion-set weights, set membership and
  support-degree weights (``fusion.readings.fusion_set``) on 50,000 epochs of ten thermocouple-like readings, in
  one block (the previous code) and in cache-sized row blocks;
* ``huber``, ``biweight``: the robust baselines' IRLS updates on the whole array at once and 4,096 rows at a time;
* ``members_first``: the joint audit's members-first order, by a stable sort of every row and by table look-up;
* ``study_cache``: chapter 05's infrared + radar readings study (200 runs) computed, and loaded from the shared
  study cache (``fusion.book.study_cache``) as a second process of a run would.

Writes ``benchmarks/results/blocks.json``. Run: ``.venv/bin/python benchmarks/bench_blocks.py``
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # one BLAS thread (before numpy loads its BLAS)

import pickle  # noqa: E402
import statistics  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _results import write_results  # noqa: E402

from fusion.book import study_cache as sc  # noqa: E402
from fusion.book.chapters import ofs_audit  # noqa: E402
from fusion.readings import fusion_set as fs  # noqa: E402
from fusion.readings import robust  # noqa: E402

REPEATS = 5


def _cpu(fn):  # noqa: ANN001, ANN202
    t = time.process_time()
    out = fn()
    return time.process_time() - t, out


def side_by_side(key: str, what: str, old, new, repeats: int = REPEATS) -> dict:  # noqa: ANN001
    """Median CPU seconds of ``old`` and ``new`` (interleaved), their outputs compared byte for byte."""
    t_old, t_new = [], []
    for _ in range(repeats):
        a, ref = _cpu(old)
        b, got = _cpu(new)
        t_old.append(a)
        t_new.append(b)
    # the same bytes, compared after one round trip each (a strided view comes back contiguous, its values unchanged)
    assert pickle.dumps(pickle.loads(pickle.dumps(ref))) == pickle.dumps(pickle.loads(pickle.dumps(got))), key
    mo, mn = statistics.median(t_old), statistics.median(t_new)
    return {"key": key, "what": f"{what}: previous / new CPU time ({mo:.3f} s / {mn:.3f} s)", "value": mo / mn,
            "unit": "x"}


def _unblocked_irls(fn, s: np.ndarray, c: float) -> np.ndarray:  # noqa: ANN001
    saved = robust._IRLS_BLOCK
    robust._IRLS_BLOCK = len(s)
    try:
        return fn(s, c)
    finally:
        robust._IRLS_BLOCK = saved


def main() -> None:
    rng = np.random.default_rng(1)
    s = 900.0 + rng.normal(size=(50_000, 10)) * rng.uniform(0.5, 2.0, size=10)
    s[:, :2] += rng.choice([0.0, 3.0, 10.0], size=(len(s), 1))
    members = fs._members_rows(s, "mean")
    mem3 = rng.random((300_000, 3)) < 0.6
    rows = [
        side_by_side("set_weights", "optimal-fusion-set weights, 50,000 x 10",
                     lambda: fs._set_weights_block(s, members, 2.0, True), lambda: fs._set_weights(s, members, 2.0, True)),
        side_by_side("members", "optimal-fusion-set membership, 50,000 x 10",
                     lambda: fs._members_block(s, "mean"), lambda: fs._members_rows(s, "mean")),
        side_by_side("support", "support-degree weights, 50,000 x 10",
                     lambda: fs._support_block(s, 0.25), lambda: fs._support_weights(s, 0.25)[0]),
        side_by_side("huber", "Huber IRLS, 50,000 x 10", lambda: _unblocked_irls(robust._huber, s, 1.345),
                     lambda: robust._huber(s, 1.345)),
        side_by_side("biweight", "biweight IRLS, 50,000 x 10", lambda: _unblocked_irls(robust._biweight, s, 4.685),
                     lambda: robust._biweight(s, 4.685)),
        side_by_side("members_first", "members-first order, 300,000 x 3",
                     lambda: np.argsort(~mem3, axis=1, kind="stable"), lambda: ofs_audit._members_first(mem3)),
    ]
    from fusion.book.chapters.ci import studies as ci_studies

    study = ci_studies.ir_reading_study.__wrapped__               # the study itself, below the caches
    with tempfile.TemporaryDirectory() as root:
        os.environ[sc.ENV] = root
        stored = ci_studies.ir_reading_study
        stored(2024, 200)                                        # stored once, as by the first process of a run

        def load():  # noqa: ANN202
            stored.cache_clear()                                 # a fresh process: nothing in memory
            return stored(2024, 200)

        rows.append(side_by_side("study_cache", "chapter 05 infrared + radar study (200 runs), computed / loaded",
                                 lambda: study(2024, 200), load, repeats=3))
        del os.environ[sc.ENV]
    write_results("blocks", rows, repeats=REPEATS)


if __name__ == "__main__":
    main()
