"""The reseeding sweep's cost: wall time on 1 and 2 local Dask workers in one run, per-task cost by chapter,
and an estimate of the wall time on 8 and 64 workers.

Runs a sample of the sweep's tasks (every stochastic record's primary reading under ``--reseeds`` seeds at
the chapter's run count; no 10× part) twice, on a LocalCluster of one worker and of two, in one process.
The estimate for W workers is ``max(total work / W, longest batch)`` plus the measured overhead per
batch: the sweep sends one batch per (source, seed) (:func:`fusion.book.stability.batches`, whose tasks
share a worker's cached studies), so the bound is the busiest worker or the longest batch, whichever is larger.

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
    full_tasks = S.tasks(readings, S.seeds(S.RESEEDS), S.RUNS_FACTOR)
    full_batches = S.batches(full_tasks)
    cost: dict[str, list[float]] = defaultdict(list)
    for r in per_task[1]:
        cost[r.task.record].append(r.seconds)
    mean_cost = {rid: sum(c) / len(c) for rid, c in cost.items()}

    def seconds(t: S.Task) -> float:  # a task's cost from the sample: its record's mean, scaled by its runs
        base = readings[(t.source, t.record)]["primary"][1]
        return mean_cost.get(t.record, 0.0) * t.runs / base

    batch_cost = [sum(seconds(t) for t in b) for b in full_batches]
    work = sum(batch_cost)
    overhead = max(0.0, walls[1] - total) / max(1, len(S.batches(task_list)))
    m.append({"key": "work", "what": f"estimated work of the sampled records' full sweep ({len(full_tasks)} tasks in "
              f"{len(full_batches)} batches, {S.RESEEDS} reseeds, {S.RUNS_FACTOR}× primary), one worker",
              "value": work, "unit": "s"})
    for w in (8, 64):
        est = max(work / w, max(batch_cost, default=0.0)) + overhead * len(full_batches) / w
        m.append({"key": f"estimate_{w}", "what": f"estimated wall time of the sampled records' full sweep on {w} workers "
                  "(busiest worker or longest batch)", "value": est, "unit": "s"})
    write_results("stability", m, tasks=len(task_list), failed=len(failed))


if __name__ == "__main__":
    main()
