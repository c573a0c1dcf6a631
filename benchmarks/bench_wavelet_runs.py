"""Source 003 sec. 2.6: do chapter 03's verdicts survive other seeds and more runs for the other readings?

The per-run difference MSE(reconstruction) - MSE(own denoised signal) of the noisier sensors has a
heavy right tail (a run whose maximum sits on a kept noise spike), so the paired t interval of its
mean needs many runs; the rulebook (rule R3) then judges by the median. The chapter runs every reading
with 300 runs of seed 2601 and repeats its primary reading (E2.6) with 2000 runs, showing there how often
disjoint blocks of 100 and of 1000 of those runs decide it. This script reruns, outside the book, with the
rulebook's judgement (the key ``..._mean_..`` holds the deciding statistic, the mean or the median):

* the primary question (two tones, hard threshold, maximum normaliser: reconstruction < own
  denoised signal for every sensor) under four other seeds with the chapter's 3000 runs, and with
  the first 1000 of them (`fusion.scenarios.wavelet_sensors.seed_study`);
* the signal x threshold-rule table and the wavelet settings with 1000 runs (seed 2601; the primary
  cell, as in the chapter, from E2.6's 3000 runs): how many cells and settings reproduce, contradict
  or leave undecided each question.

No timing is stored: the values are Monte-Carlo results, identical on any machine. Writes
`benchmarks/results/wavelet_runs.json`. Takes about a minute on 2 cores.

Run: `.venv/bin/python benchmarks/bench_wavelet_runs.py`
"""

from __future__ import annotations

from _results import write_results  # benchmarks/_results.py (scripts run from anywhere)

from fusion.book.chapters import lecture_wavelets as ch
from fusion.scenarios import wavelet_sensors as ws

SEEDS = (2602, 2603, 2604, 2605)
RUNS = 3000     # E2.6 had 3000 runs; the chapter now repeats its primary with 2000
FIRST = 1000    # the first block of each seed; the runs of the other readings here (the chapter: 300)


def primary_rows(label: str, key: str, rec, den, seed: int) -> list[dict]:
    """Per sensor: mean paired difference and 95 % interval (x1e-4); 1 if the reading holds for every sensor."""
    conj = ch.sensor_conjunction(rec, den, "rec", "den", "MSE", seed)
    out = []
    for name, ev in conj.parts:
        mean, lo, hi = ev.interval()
        stat = ev.judgement().statistic  # "mean", or "median" where rule R3 finds the differences heavy-tailed
        for what, v in (("mean", mean), ("lo", lo), ("hi", hi)):
            text = {"mean": stat, "lo": f"{stat}, 95 % interval low", "hi": f"{stat}, 95 % interval high"}[what]
            out.append({"what": f"{label}, {name}: rec - own denoised, {text}", "value": round(1e4 * v, 2),
                        "unit": "1e-4", "key": f"{key}_{what}_{name[-1]}"})
    out.append({"what": f"{label}: reproduced for every sensor (1 = yes)", "value": int(conj.status() == "reproduced"),
                "unit": "", "key": f"{key}_r"})
    return out


def main() -> None:
    meas: list[dict] = [
        {"what": "runs per seed (the chapter's E2.6)", "value": RUNS, "unit": "runs", "key": "runs"},
        {"what": "runs of each seed's first block", "value": FIRST, "unit": "runs", "key": "first"},
    ]
    ss = ws.seed_study(seeds=SEEDS, runs=RUNS)
    for v, cs in ss.cases.items():
        rec, den = cs["reconstructed"]["mse"], cs["denoised"]["mse"]
        meas += primary_rows(f"seed {v}, {RUNS} runs", f"s{v}", rec, den, v)
        meas += primary_rows(f"seed {v}, first {FIRST} runs", f"f{v}", rec[:FIRST], den[:FIRST], v)
    for short, label in (("s", f"{RUNS} runs"), ("f", f"first {FIRST} runs")):
        meas.append({"what": f"other seeds, {label} each: reproduced for every sensor",
                     "value": sum(m["value"] for m in meas if m["key"].startswith(short + "26") and m["key"].endswith("_r")),
                     "unit": f"of {len(SEEDS)}", "key": f"seeds_{short}_r"})
    del ss
    e26 = ws.signal_study(signals=("two tones",), modes=("hard",), normalisers=("max",), runs=RUNS)
    sg = ws.signal_study(normalisers=("max",), runs=FIRST)
    g = ch.glue_signals(sg, e26)
    for qid, col, *_ in ch.QUESTIONS:
        for short, word in (("r", "reproduced"), ("c", "contradicted"), ("n", "not distinguishable")):
            meas.append({"what": f"signal table, {FIRST} runs (primary cell {RUNS}): '{col}' {word} "
                                 f"(cells of {g['lec_ws_n_cells']})",
                         "value": g[f"lec_ws_n_{qid}_{short}"], "unit": "cells",
                         "key": f"sig_{qid}_{short}"})
    del sg
    m = ws.mechanism_study(runs=FIRST)
    gm = ch.glue_mechanism(m, e26)
    for name in ("better", "helps", "order"):
        for short, word in (("r", "reproduced"), ("c", "contradicted"), ("n", "not distinguishable")):
            meas.append({"what": f"wavelet settings, {FIRST} runs (primary setting {RUNS}): {name} {word} "
                                 f"(of {gm['lec_wm_n_cfg']})",
                         "value": gm[f"lec_wm_n_{name}_{short}"], "unit": "settings",
                         "key": f"cfg_{name}_{short}"})
    write_results("wavelet_runs", meas, seeds=[2601, *SEEDS])


if __name__ == "__main__":
    main()
