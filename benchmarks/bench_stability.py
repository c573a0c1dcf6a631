"""The reseeding sweep's cost: wall time on 1 and 2 local Dask workers in one run, per-task cost by chapter,
and an estimate of the wall time on 8 and 64 workers.

Runs a sample of the sweep's tasks (every stochastic record's primary reading under ``--reseeds`` seeds at
the chapter's run count; no 10× part) twice, on a LocalCluster of one worker and of two, in one process.
The estimate for W workers is ``max(total task time / W, longest task)`` plus the measured overhead per
task: the work is embarrassingly parallel, so the bound is the busiest worker.

Usage: ``.venv/bin/python benchmarks/bench_stability.py [--reseeds 2] [--only ID ...]``
"""

from __future__ import annotations

import argparse
import time
from collections import defaultdict

from _results import write_results
from distributed import Client, LocalCluster

from fusion.book import stability as S
from fusion.book.ledger import SOURCES, ledger_dir


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--reseeds", type=int, default=2)
    p.add_argument("--only", nargs="*", default=())
    args = p.parse_args()
    root = ledger_dir().parent.parent
    readings = S.stochastic_readings(root)
    if args.only:
        readings = {k: v for k, v in readings.items() if k[1] in set(args.only)}
    primaries = {k: {"primary": v["primary"]} for k, v in readings.items()}
    task_list = S.tasks(primaries, S.seeds(args.reseeds), runs_factor=1)
    walls, per_task = {}, {}
    for workers in (1, 2):
        with Client(LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                 dashboard_address=None)) as client:
            client.run(lambda: None)  # workers up before the clock starts
            t0 = time.perf_counter()
            results = S.sweep(task_list, client, root, progress=False)
            walls[workers] = time.perf_counter() - t0
        per_task[workers] = results
    failed = [r for r in per_task[1] if r.status is None]
    by_chapter: dict[str, list[float]] = defaultdict(list)
    for r in per_task[1]:
        by_chapter[SOURCES[r.task.source].short].append(r.seconds)
    total = sum(r.seconds for r in per_task[1])
    longest = max((r.seconds for r in per_task[1]), default=0.0)
    overhead = max(0.0, walls[1] - total) / max(1, len(task_list))
    m = [
        {"key": "wall_1", "what": f"reseeding sample ({len(task_list)} tasks), 1 local worker", "value": walls[1],
         "unit": "s"},
        {"key": "wall_2", "what": f"reseeding sample ({len(task_list)} tasks), 2 local workers", "value": walls[2],
         "unit": "s"},
        {"key": "speedup_2", "what": "speed-up of 2 workers over 1 (same tasks, same run)",
         "value": walls[1] / walls[2], "unit": "×"},
    ]
    for chapter, secs in sorted(by_chapter.items()):
        m.append({"what": f"mean task time, {chapter} ({len(secs)} tasks)", "value": sum(secs) / len(secs),
                  "unit": "s"})
    full = len(S.tasks(readings, S.seeds(S.RESEEDS), S.RUNS_FACTOR))
    cost: dict[str, list[float]] = defaultdict(list)
    for r in per_task[1]:
        cost[r.task.record].append(r.seconds)
    # each record: its readings under K reseeds at the chapter's runs, and the primary at RUNS_FACTOR x runs
    work = sum(sum(c) / len(c) * (len(readings[k]) * S.RESEEDS + S.RUNS_FACTOR)
               for k in readings if (c := cost.get(k[1])))
    for w in (8, 64):
        est = max(work / w, longest * S.RUNS_FACTOR) + overhead * full / w
        m.append({"key": f"estimate_{w}", "what": f"estimated wall time of the full sweep ({full} tasks, "
                  f"{S.RESEEDS} reseeds, {S.RUNS_FACTOR}× primary) on {w} workers", "value": est, "unit": "s"})
    write_results("stability", m, tasks=len(task_list), failed=len(failed))


if __name__ == "__main__":
    main()
