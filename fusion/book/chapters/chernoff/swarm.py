"""The particle swarm inside the filter: its ε path, its stopping rule and the cost benchmark.

Part of :mod:`fusion.book.chapters.chernoff` (chapter 06, patent CN107330468B), which re-exports its public names."""

from __future__ import annotations

import inspect
import math
from enum import StrEnum
from pathlib import Path
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from fusion._shown import shown
from fusion._validation import is_integer, scalar
from fusion._counts import sequence
from fusion.book._json import read_argument
from fusion.book.benchmarks import _DURATION, _check_measurements
from fusion.book.ledger import Comparison
from fusion.book.style import METHOD_LABELS, new_figure
from fusion.book.tables import rounded, sci
from fusion.optimise.swarm import particle_swarm
from fusion.scenarios.range_bearing import RangeBearingScenario, TrackingRun
from fusion.book.chapters.chernoff.settings import LATE, STUDY_WORKERS, _MSE, _check_study
from fusion._counts import COUNT_CEILINGS, count, index
from fusion.book.chapters.chernoff.compare import _reason, _word
from fusion.book.chapters.chernoff.tracking import per_run_mse
from fusion.book.glue import GlueValues
from fusion._limits import LOOP_STEP, loop_work
from fusion.book.chapters._defaults import study_defaults

__all__ = ["BENCH_SCHEMA", "BenchStage", "PATENT_STAGES", "stopping_values", "eps_figure", "pso_figure", "benchmark_cost"]


def eps_figure(runs: list[TrackingRun], sc: RangeBearingScenario, show: int = 0) -> tuple[Figure, GlueValues]:
    """Figure ``fig-chf-eps`` (optimal exponents and ESS/R against frame) and its glue values.

    Parameters
    ----------
    runs : list of TrackingRun
        The Monte-Carlo runs (their ``eps["pso"]``, shape (K, N), and ``ess``).
    sc : RangeBearingScenario
        The scenario: number of nodes N, frames K, importance samples R (``n_samples``) and
        particles of the centralised filter (``n_central``).
    show : int
        0-based index of the run drawn on the left (e.g. :func:`typical_run`).

    Returns
    -------
    fig : Figure
        Left: ε* of each node against frame (run ``show + 1``, with the 10-90 % band over runs) and the
        uniform 1/N; right: mean ESS / R against frame at ε⁽⁰⁾, at ε* and redrawn, and the
        centralised filter's ESS / particles. The figure is closed (not shown by pyplot).
    values : dict of str to float
        ``chf_eps_spread`` (mean over frames and nodes of the 10-90 % band width of ε*),
        ``chf_ess_uniform``, ``chf_ess_pso``, ``chf_ess_redraw`` (mean ESS / R at ε⁽⁰⁾, at ε* with
        the samples reused, and redrawn), ``chf_ess_pso_min`` (smallest ESS at ε*, samples),
        ``chf_ess_central_1`` (mean ESS of the centralised filter at frame 1, particles),
        ``chf_ess_central_late`` (its mean ESS / particles over frames 5-K), ``chf_eps_max_mean``
        (mean over runs and frames of the largest exponent) and ``chf_eps_max_max`` (largest
        exponent); 4 decimals.

    Raises
    ------
    TypeError
        ``runs`` not a sequence of TrackingRun, ``sc`` not a RangeBearingScenario, ``show`` not an integer.
    ValueError
        ``runs`` is empty, of several scenarios or holds a run twice, ``sc`` is not the runs' scenario, or ``show``
        not a run's index, ``runs`` of fewer than 5 frames (no frame of LATE) or computed with
        ``RangeBearingScenario.variants=False`` (not a study the chapter's tables show).
    """
    runs = _check_study(runs, sc, window=True, variants=True)
    show = index(show, "show", len(runs))
    n = len(sc.sensors)
    frames = np.arange(1, sc.frames + 1)
    eps_all = np.stack([r.eps["pso"] for r in runs])  # (runs, K, N)
    fig, (ax1, ax2) = new_figure(2, 1, figsize=(7.5, 6.4))
    colors = ["#0072B2", "#D55E00", "#009E73"]
    for i in range(n):
        c = colors[i % len(colors)]
        ax1.fill_between(frames, np.percentile(eps_all[:, :, i], 10, axis=0),
                         np.percentile(eps_all[:, :, i], 90, axis=0), color=c, alpha=0.15, lw=0)
        ax1.plot(frames, eps_all[show, :, i], color=c, label=f"ε{i + 1} (sensor {i + 1}), run {show + 1}")
    ax1.axhline(1 / n, color="grey", lw=0.8, ls="--")
    ax1.set(xlabel="frame", ylabel="ε*", ylim=(0, 1))
    ax1.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0))
    for key, c, label in (("uniform", "#56B4E9", "at ε⁽⁰⁾ (uniform)"),
                          ("pso", "#0072B2", "at ε* (patent: samples reused)"),
                          ("redraw", "#009E73", "at ε*, samples redrawn")):
        ax2.plot(frames, np.mean([r.ess[key] for r in runs], axis=0) / sc.n_samples, color=c, label=label)
    ax2.plot(frames, np.mean([r.ess["centralised_pf"] for r in runs], axis=0) / sc.n_central, color="black", ls=":",
             label="centralised PF (ESS / particles)")
    ax2.set(xlabel="frame", ylabel="ESS / R (centralised:\nESS / particles)", ylim=(0, 1.05))
    ax2.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0))
    plt.close(fig)
    ess = {k: np.stack([r.ess[k] for r in runs]) for k in ("uniform", "pso", "redraw", "centralised_pf")}
    values = {
        "chf_eps_spread": np.mean(np.percentile(eps_all, 90, axis=0) - np.percentile(eps_all, 10, axis=0)),
        "chf_ess_uniform": np.mean(ess["uniform"]) / sc.n_samples,
        "chf_ess_pso": np.mean(ess["pso"]) / sc.n_samples,
        "chf_ess_pso_min": np.min(ess["pso"]),
        "chf_ess_redraw": np.mean(ess["redraw"]) / sc.n_samples,
        "chf_ess_central_1": np.mean(ess["centralised_pf"][:, 0]),
        "chf_ess_central_late": np.mean(ess["centralised_pf"][:, LATE]) / sc.n_central,
        "chf_eps_max_mean": np.mean(eps_all.max(axis=2)),
        "chf_eps_max_max": np.max(eps_all),
    }
    return fig, {k: rounded(float(x)) for k, x in values.items()}


@study_defaults("runs", "frame")  # a default the study does not fit, named by the study (fuzz 36b D1)
def pso_figure(runs: list[TrackingRun], frame: int = 10, show: int = 0) -> tuple[Figure, GlueValues]:
    """Figure ``fig-chf-pso`` (the swarm's best Ĵ against iteration in one run) and swarm-vs-SLSQP glue values.

    Parameters
    ----------
    runs : list of TrackingRun
    frame : int
        1-based frame to show.
    show : int
        0-based index of the run shown (e.g. :func:`typical_run`).

    Returns
    -------
    fig : Figure
        The swarm's best Ĵ against iteration until the stagnation rule stops (circled), the same swarm followed
        to its iteration limit with the iteration where the patent's rule (positions converge) stops
        (square; with ``readings``), and SLSQP's minimum on the same samples.
    values : dict
        ``chf_gap_obj`` and ``chf_gap_eps`` (largest absolute difference PSO - SLSQP in objective and exponents over all
        frames and runs), ``chf_evals_pso``/``chf_evals_slsqp`` (mean evaluations per frame),
        ``chf_better_pso`` (fraction of frames where the swarm's value is below SLSQP's by > 1e-9).

    Raises
    ------
    TypeError
        ``runs`` not a sequence of TrackingRun, ``frame`` or ``show`` not an integer.
    ValueError
        ``runs`` is empty, of several scenarios or holds a run twice, ``frame`` not in 1..K, or ``show`` not a run's
        index, ``runs`` computed with ``RangeBearingScenario.variants=False`` (not a study the chapter's tables show).
    """
    runs = _check_study(runs, variants=True)
    frame = count(frame, "frame")
    if frame > runs[0].truth.shape[0]:
        raise ValueError(f"frame = {frame} is beyond the runs' {runs[0].truth.shape[0]} frames")
    show = index(show, "show", len(runs))
    r0, k = runs[show], frame - 1
    n_part = inspect.signature(particle_swarm).parameters["n_particles"].default
    stop = int(r0.evaluations["pso"][k]) // n_part - 1  # the stagnation rule stopped after this iteration
    hist = -r0.swarm_history[k][:stop + 1]  # (the stored history is padded after the stop)
    fig, ax = new_figure(figsize=(7.0, 3.4))
    if r0.swarm_trace:  # the same swarm followed to its iteration limit (readings)
        full = -r0.swarm_trace["fitness"][k]
        ax.plot(np.arange(full.size), full, color="#999999", lw=1.0, label="PSO followed to its limit")
        lit = int(r0.evaluations["literal"][k]) // n_part - 1
        ax.plot([lit], [full[lit]], "s", color="#D55E00", label="positions converge (G6 as worded)")
    ax.plot(np.arange(hist.size), hist, color="#0072B2", marker=".", label="PSO: best Ĵ so far")
    ax.plot([stop], [hist[-1]], "o", color="#0072B2", ms=9, mfc="none", label="stagnation rule stops")
    ax.axhline(r0.objective["slsqp"][k], color="black", ls="--", label="SLSQP on the same samples")
    ax.set(xlabel="swarm iteration", ylabel="Ĵ(ε)")
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0))
    plt.close(fig)
    obj = {m: np.stack([r.objective[m] for r in runs]) for m in ("pso", "slsqp")}
    eps = {m: np.stack([r.eps[m] for r in runs]) for m in ("pso", "slsqp")}
    values = {
        "chf_k_show": frame,
        "chf_gap_obj": float(f"{np.max(np.abs(obj['pso'] - obj['slsqp'])):.1e}"),  # two significant digits, as shown
        "chf_gap_eps": rounded(float(np.max(np.abs(eps["pso"] - eps["slsqp"])))),
        "chf_evals_pso": rounded(float(np.mean([r.evaluations["pso"] for r in runs]))),
        "chf_evals_slsqp": rounded(float(np.mean([r.evaluations["slsqp"] for r in runs]))),
        "chf_better_pso": rounded(float(np.mean(obj["pso"] < obj["slsqp"] - 1e-9))),
    }
    return fig, values


#: Schema of ``benchmarks/results/chernoff.json`` written by ``benchmarks/bench_chernoff.py`` for the current pipeline
#: (the study configuration, loop against batch, stage costs); a file without it predates that pipeline.
BENCH_SCHEMA = 2


class BenchStage(StrEnum):
    """Keys of the stages :func:`benchmark_cost` reads (the ``stage`` of a measurement in
    ``benchmarks/results/chernoff.json``, a field of the tracking or fusion timings); each stage's display label is
    the measurement's ``what``, from the labels of ``benchmarks/bench_chernoff.py``.

    Attributes
    ----------
    PARTICLE_FILTERS, EM, FIRST_ORDER, SAMPLING, DENSITIES, OPTIMISER, WEIGHTS
        The patent's own stages B-I: the local particle filters (B), weighted EM (C), first-order fusion (D), sampling
        g (E), the densities at the samples (F), the particle swarm (G), the fused weights and estimate (H-I).
    REFERENCE
        SLSQP on the same samples (the swarm's reference).
    """

    PARTICLE_FILTERS = "particle_filters"
    EM = "em"
    FIRST_ORDER = "first_order"
    SAMPLING = "sampling"
    DENSITIES = "densities"
    OPTIMISER = "optimiser"
    WEIGHTS = "weights"
    REFERENCE = "reference"


#: The patent's own stages, B-I.
PATENT_STAGES: tuple[BenchStage, ...] = (BenchStage.PARTICLE_FILTERS, BenchStage.EM, BenchStage.FIRST_ORDER,
                                         BenchStage.SAMPLING, BenchStage.DENSITIES, BenchStage.OPTIMISER,
                                         BenchStage.WEIGHTS)


#: The study's timings that :func:`benchmark_cost` reads, by measurement ``key``.
_BENCH_KEYS = ("loop_seconds", "study_seconds", "study_seconds_workers", "identical", "pso_over_slsqp")
#: Those of them that are durations or a ratio of durations: positive whatever their unit.
_POSITIVE_KEYS = ("loop_seconds", "study_seconds", "study_seconds_workers", "pso_over_slsqp")
#: Those of them that are durations in seconds, within the plausible range of a measured duration (``_DURATION``).
_DURATION_KEYS = ("loop_seconds", "study_seconds", "study_seconds_workers")
#: The largest ``runs`` a benchmark record may give: the count ceiling of runs (rule 9 of ``fusion._validation``).
_MAX_RUNS = COUNT_CEILINGS["runs"]


def _current_measurements(bench: dict[str, Any], path: Path) -> list[dict[str, Any]]:
    """The measurements of a current benchmark record, each field :func:`benchmark_cost` reads checked, refused by a
    ValueError naming ``path`` (the measurements rule of :func:`fusion.book.benchmarks.load_benchmark` first; the
    date is optional, read as ``"undated"``)."""
    where = f"path: benchmark result {path}"
    missing = [k for k in ("measurements", "runs") if k not in bench]
    if missing:
        raise ValueError(f"{where} lacks {missing}")
    try:
        _check_measurements(bench["measurements"], path)
    except ValueError as exc:
        raise ValueError(f"path: {exc}") from exc
    if not is_integer(bench["runs"]) or isinstance(bench["runs"], bool) or bench["runs"] < 1:
        raise ValueError(f"{where}: runs must be a positive integer, got {shown(bench['runs'])}")
    if bench["runs"] > _MAX_RUNS:  # the prose's target is 60 s per 100 runs (fuzz 24b D6: 10**30 runs glued)
        raise ValueError(f"{where}: runs must be at most {_MAX_RUNS:,} (the count ceiling of runs), got "
                         f"{shown(bench['runs'])}")
    if "workers" in bench and (not is_integer(bench["workers"]) or isinstance(bench["workers"], bool)
                               or bench["workers"] < 1):  # fuzz 24b BC4: "batched with -3 worker processes"
        raise ValueError(f"{where}: workers must be a positive integer, got {shown(bench['workers'])}")
    if "load_average" in bench:  # glued in the prose (fuzz 24b BC2: [] -> IndexError, 0.5 -> TypeError)
        la = bench["load_average"]
        if not (isinstance(la, list) and la and all(isinstance(x, (int, float)) and not isinstance(x, bool)
                                                    and math.isfinite(x) and x >= 0 for x in la)):
            raise ValueError(f"{where}: load_average must be a non-empty list of non-negative numbers, got "
                             f"{shown(la)}")
    ms = bench["measurements"]
    seen: dict[str, int] = {}
    for i, m in enumerate(ms):
        if "stage" in m and not (isinstance(m["stage"], str) and isinstance(m.get("what"), str) and ", " in m["what"]
                                 and "value" in m):
            raise ValueError(f"{where}: measurements[{i}] of a stage must hold a str stage, a value and a str what "
                             f"('<study>, <label>: <unit>'), got {shown(m, 120)}")
        if "stage" in m:  # a stage is a row of the table and a divisor of the ratios (fuzz 24b BC1, BC3)
            if m["stage"] in seen:
                raise ValueError(f"{where}: measurements[{i}] measures stage {shown(m['stage'])} again (first "
                                 f"measurements[{seen[m['stage']]}]): a stage is measured once")
            seen[m["stage"]] = i
            if not _DURATION[0] <= m["value"] <= _DURATION[1]:   # whatever its unit (fuzz 37b D2: 1e300 s glued)
                raise ValueError(f"{where}: measurements[{i}].value (stage {shown(m['stage'])}, seconds per frame) "
                                 f"must lie in [{_DURATION[0]:g}, {_DURATION[1]:g}] (a measured duration), got "
                                 f"{shown(m['value'])}")
        if m.get("key") in _POSITIVE_KEYS and "value" in m and not m["value"] > 0:
            raise ValueError(f"{where}: measurements[{i}].value ({m['key']}) must be positive, got {shown(m['value'])}")
        if m.get("key") in _DURATION_KEYS and "value" in m and not _DURATION[0] <= m["value"] <= _DURATION[1]:
            raise ValueError(f"{where}: measurements[{i}].value ({m['key']}, seconds) must lie in "
                             f"[{_DURATION[0]:g}, {_DURATION[1]:g}] (a measured duration), got {shown(m['value'])}")
    stages = {m["stage"] for m in ms if "stage" in m}
    keys = {m["key"] for m in ms if "key" in m and "value" in m}
    lacks = [str(st) for st in (BenchStage.EM, BenchStage.OPTIMISER, BenchStage.REFERENCE) if st not in stages]
    lacks += [k for k in _BENCH_KEYS if k not in keys]
    if lacks:
        raise ValueError(f"{where} lacks the measurements {lacks}")
    return ms


def benchmark_cost(path: Path) -> tuple[pd.DataFrame, GlueValues]:
    """Cost per frame by stage from ``benchmarks/results/chernoff.json``, and the study's measured cost.

    Parameters
    ----------
    path : Path
        The benchmark result file.

    Returns
    -------
    table : DataFrame
        ms per frame, indexed by stage (its label, from the measurement's ``what``); empty (no rows) when the file
        predates :data:`BENCH_SCHEMA`.
    values : dict
        ``chf_bench_date`` (str), ``chf_bench_current`` (bool: the file has :data:`BENCH_SCHEMA`), and, in words for
        the prose (``"not measured yet ..."`` when the file is not current): ``chf_bench_text`` (the seconds of the
        study's runs by the per-run loop, batched in one process and with the chapter's worker processes, whether
        their results are identical, and the verdict against 60 s for 100 runs on 2 cores), ``chf_bench_stage_text``
        (EM's share of the patent's own stages B-I and the runs measured) and ``chf_pso_ratio_text`` (time of the
        swarm / time of SLSQP on the same samples, in words: "N times slower" from 2, rounded to a whole number
        (halves up),
        "1.23 times slower" between 1.01 and 2, "about as fast" within 1 % of 1, "N times faster" by the same
        rule below); the share and the ratio are of the measured seconds, not of the table's ms rounded to 0.1; a
        value below one unit of its printed decimals (seconds, ms, the stage ratio) is printed to 2 significant
        digits, never as 0.

    Raises
    ------
    TypeError
        ``path`` not a path.
    ValueError
        ``path`` not an existing file holding a JSON object, or, when it has :data:`BENCH_SCHEMA`, without what is
        read here (``runs``, a list of measurements with finite values, those of the stages of EM, the swarm and
        SLSQP, and the keys of the study's timings), naming ``path`` and the file; also when a stage is measured
        twice or a key repeats, a stage's seconds or a timing in seconds is outside [1e-9, 1e6] (a measured
        duration) or the time ratio is not positive, ``runs`` or ``workers`` is not a positive integer (``runs`` at
        most the count ceiling of runs), ``load_average`` (optional, shown as ``?`` when absent) is not a non-empty
        list of non-negative numbers, or ``schema`` is not an integer.
    """
    bench = read_argument(path, "path", "benchmark result")
    date = str(bench.get("date", bench.get("timestamp", "undated")))[:10]
    schema = bench.get("schema")
    if schema is not None and (not is_integer(schema) or isinstance(schema, bool)):  # fuzz 24b D6: 2.0 read as 2
        raise ValueError(f"path: benchmark result {path}: schema must be an integer, got {shown(schema)}")
    current = schema == BENCH_SCHEMA
    pending = "not measured yet for the current pipeline (run benchmarks/bench_chernoff.py on an idle machine)"
    if not current:
        empty = pd.DataFrame({"stage": [], "ms per frame": []}).set_index("stage")
        return empty, {"chf_bench_date": date, "chf_bench_current": False, "chf_bench_text": pending,
                       "chf_bench_stage_text": pending, "chf_pso_ratio_text": pending}
    ms = _current_measurements(bench, Path(path))
    stages = [m for m in ms if "stage" in m]
    label = {m["stage"]: m["what"].split(", ", 1)[1].rsplit(":", 1)[0] for m in stages}
    cost = pd.DataFrame({"stage": [m["stage"] for m in stages],
                         "ms per frame": [round(1000 * m["value"], 1) for m in stages]}).set_index("stage")
    key = {m["key"]: float(m["value"]) for m in ms if "key" in m}
    # the share and the ratio from the measured seconds (positive, checked), not from the table's 0.1 ms: stages
    # faster than 0.05 ms per frame round to 0 and gave a NaN share (fuzz 36b B8)
    seconds = {m["stage"]: float(m["value"]) for m in stages}
    share = seconds[BenchStage.EM] / sum(v for k, v in seconds.items() if k in PATENT_STAGES)
    runs, workers = int(bench["runs"]), int(bench.get("workers", STUDY_WORKERS))
    swarm_ms, slsqp_ms = (_fixed(1000 * seconds[s], 1) for s in (BenchStage.OPTIMISER, BenchStage.REFERENCE))
    stage_ratio = seconds[BenchStage.OPTIMISER] / seconds[BenchStage.REFERENCE]
    cost = cost.rename(index=label)
    t2 = key["study_seconds_workers"]
    target = 60.0 * runs / 100
    text = (f"{runs} runs take {_fixed(key['loop_seconds'], 0)} s by the per-run loop, "
            f"{_fixed(key['study_seconds'], 0)} s batched in one process and {_fixed(t2, 0)} s batched with {workers} "
            "worker processes, "
            f"{'within' if t2 <= target else 'over'} the target of {target:.0f} s on 2 cores; the three give "
            f"{'identical' if key['identical'] == 1.0 else 'different'} results (benchmark of {date}, load average "
            f"{bench.get('load_average', ['?'])[0]})")
    stage_text = (f"weighted EM takes a share {share:.2f} of the patent's own stages (B-I), measured over {runs} runs "
                  f"of the study on {date}")
    return cost, {"chf_bench_date": date, "chf_bench_current": True, "chf_bench_text": text,
                  "chf_bench_stage_text": stage_text,
                  "chf_pso_ratio_text": f"{_slower(key['pso_over_slsqp'])} (benchmark of {date}) on the "
                                        "static example with a duplicated input [A, B, A], whose objective has a flat "
                                        f"direction; in the study's own stage costs {_fixed(stage_ratio, 1)} times "
                                        f"({swarm_ms} against {slsqp_ms} ms per frame)"}


def _fixed(x: float, decimals: int) -> str:
    """A positive measured value at ``decimals`` decimals, or at 2 significant digits (:func:`fusion.book.tables.sci`)
    when it is below one unit of the last decimal, so that it never prints as 0 (fuzz 39b C2: "0.0 times")."""
    return f"{x:.{decimals}f}" if x >= 10.0 ** -decimals else sci(x, 2)


def _slower(ratio: float) -> str:
    """A positive time ratio (the swarm's time over SLSQP's) in words (fuzz 38b C5: 0.4 read "0 times slower"):
    "N times slower" from 2 (N rounded to a whole number, halves up, as the book quotes it; a ratio that rounds to
    2.00 is already "2 times"), two decimals between 1.01 and 2,
    "about as fast" within 1 % of 1, and below that the inverse ratio by the same rule, "times faster"."""
    if 1 / 1.01 < ratio < 1.01:
        return "about as fast"
    word, r = ("slower", ratio) if ratio > 1 else ("faster", 1 / ratio)
    r2 = math.floor(100 * r + 0.5) / 100   # halves away from zero (fuzz 39b D1: 2.5 read "2 times", 3.5 "4 times")
    return f"{math.floor(r + 0.5)} times {word}" if r2 >= 2 else f"{r2:.2f} times {word}"


#: The overhead of one tolerance of :func:`stopping_values`, in units: its loop step (a few numpy passes over the swarm
#: traces and five glue values) ran 66 us with 2 runs x 5 frames x 51 iterations (510 trace cells; 5,001 tolerances
#: 0.33 CPU-s) and 83 us with 40 runs (10,200 cells; 0.42 CPU-s): about 6,600 units of overhead and 0.18 units a
#: cell (OPENBLAS_NUM_THREADS=1, niced, the shared machine, minimum of 2; fuzz 62a C4: 10**6 tolerances ran 58.4
#: CPU-s unbudgeted). Counted as 7 loop steps plus one unit a cell (a vectorised element).
_XTOL_STEP = 7 * LOOP_STEP


def stopping_values(runs: list[TrackingRun], sc: RangeBearingScenario,
                    xtols: tuple[float, ...] = (1e-3, 3e-3, 1e-2, 3e-2)) -> GlueValues:
    """The swarm's two readings of G6 on every tracking frame, from the swarm followed to its limit (``readings``).

    The swarm's moves do not depend on its stopping rule until it stops, so the traced swarm gives what the
    patent's rule (every particle within ``xtol`` of the best) returns at any tolerance, on the same samples
    as the stagnation rule.

    Parameters
    ----------
    runs : list of TrackingRun
        The study's runs (with ``swarm_trace``, ``objective["slsqp"]`` and ``ess["pso"]``).
    sc : RangeBearingScenario
    xtols : tuple of float
        Position tolerances, at least one, each finite and positive, in any order (the chapter's first is
        ``sc.literal_xtol``, the rule recorded as ``chernoff_literal``; nothing requires it: the literal rule's MSE
        comparison ``chf_stop_mse_*`` reads the recorded ``chernoff_literal`` at ``sc.literal_xtol``, glued as
        ``chf_stop_xtol``, whatever the tolerances given); the glue is keyed by position, so a repeated tolerance
        gives the same values under two positions. A tolerance of 1 or more (the exponents' box is [0, 1]) stops the swarm at its
        first check, as 1 does.

    Returns
    -------
    dict
        ``chf_stop_frames`` (int), ``chf_stop_limit`` (evaluations at the iteration limit), ``chf_stop_xtol``;
        ``chf_stop_evals_stag`` (mean evaluations, stagnation rule); per tolerance ``j`` (0-based, in the order
        given): ``chf_stop_x{j}`` (the tolerance), ``chf_stop_atlimit_{j}`` (share of frames run to the limit),
        ``chf_stop_evals_{j}`` (mean evaluations), ``chf_stop_gap_{j}`` (largest objective above SLSQP's, nats,
        2 significant digits) and ``chf_stop_within_{j}`` (int, frames within Ĵ's sampling error of SLSQP);
        ``chf_stop_gap_stag`` and ``chf_stop_within_stag`` likewise for the stagnation rule; ``chf_stop_ratio_0``
        (evaluations of the first tolerance over the stagnation rule's, 1 decimal), ``chf_stop_within_all`` (int, the
        fewest frames within the sampling error over every rule and tolerance; ``chf_stop_within_text`` in words);
        with ``sc.readings``
        ``chf_stop_mse_d``/``_lo``/``_hi``/``_word``: the patent's method with the literal rule (at
        ``sc.literal_xtol``, not ``xtols[0]``) minus with the stagnation rule, per-run MSE from frame 5 on (m², paired
        95 % interval; the same samples).

    Raises
    ------
    TypeError
        ``runs`` not a sequence of TrackingRun, ``sc`` not a RangeBearingScenario.
    ValueError
        ``runs`` is empty, of several scenarios, holds a run twice, or is without the readings (``readings=False``),
        or ``sc`` is not the runs' scenario, or ``xtols`` empty or holding a value that is not finite and positive,
        ``runs`` of one run (a paired interval needs 2), of fewer than 5 frames (no frame of LATE) or computed with
        ``RangeBearingScenario.variants=False`` (not a study the chapter's tables show); ``len(xtols)`` x the runs'
        swarm-trace cells beyond the work budget (``fusion._limits.loop_work``, 7,000 units a tolerance plus one a
        cell: about 130,000 tolerances of 2 runs x 5 frames), by their number before any is read.
    """
    runs = _check_study(runs, sc, readings=True, window=True, variants=True, least=2, why="paired runs")
    xtols = sequence(xtols, "xtols", minimum=1)
    # rule 17 by len(xtols) before any is read (fuzz 62a C4: the loop below had no budget)
    loop_work((len(xtols),), sum(int(np.size(r.swarm_trace["spread"])) for r in runs), "xtols", step=_XTOL_STEP)
    xtols = tuple(scalar(x, f"xtols[{j}]", 0.0, lo_open=True) for j, x in enumerate(xtols))
    fit = np.stack([r.swarm_trace["fitness"] for r in runs])  # (runs, K, T + 1)
    spread = np.stack([r.swarm_trace["spread"] for r in runs])
    ref = np.stack([r.objective["slsqp"] for r in runs])
    ess = np.stack([r.ess["pso"] for r in runs])
    se = np.sqrt(np.maximum(1.0 / ess - 1.0 / sc.n_samples, 0.0))
    n_part = inspect.signature(particle_swarm).parameters["n_particles"].default
    T = fit.shape[-1] - 1
    v: dict[str, Any] = {"chf_stop_frames": int(ref.size), "chf_stop_limit": int(n_part * (T + 1)),
                         "chf_stop_xtol": sc.literal_xtol}
    stag = np.stack([r.objective["pso"] for r in runs])
    v["chf_stop_evals_stag"] = rounded(float(np.mean([r.evaluations["pso"] for r in runs])), 0)
    v["chf_stop_gap_stag"] = float(f"{np.max(stag - ref):.2g}")
    v["chf_stop_within_stag"] = int(np.sum(stag - ref < se))
    for j, xtol in enumerate(xtols):
        hit = spread[..., 1:] < xtol
        t = np.where(hit.any(axis=-1), np.argmax(hit, axis=-1) + 1, T)
        obj = -np.take_along_axis(fit, t[..., None], axis=-1)[..., 0]
        v.update({f"chf_stop_x{j}": xtol, f"chf_stop_atlimit_{j}": rounded(float(np.mean(t >= T)), 3),
                  f"chf_stop_evals_{j}": rounded(float(np.mean(n_part * (t + 1))), 0),
                  f"chf_stop_gap_{j}": float(f"{np.max(obj - ref):.2g}"),
                  f"chf_stop_within_{j}": int(np.sum(obj - ref < se))})
    v["chf_stop_ratio_0"] = rounded(float(v["chf_stop_evals_0"] / v["chf_stop_evals_stag"]), 1)
    v["chf_stop_within_all"] = min(v["chf_stop_within_stag"], *(v[f"chf_stop_within_{j}"] for j in range(len(xtols))))
    v["chf_stop_within_text"] = ("in every one of the" if v["chf_stop_within_all"] == v["chf_stop_frames"]
                                 else f"in at least {v['chf_stop_within_all']} of the")
    if sc.readings:  # the literal rule's estimate against the stagnation rule's (same samples), per-run MSE
        c = Comparison(per_run_mse(runs, "chernoff_literal"), per_run_mse(runs, "chernoff_pso"),
                       METHOD_LABELS["chernoff_literal"], METHOD_LABELS["chernoff_pso"], "less", _MSE, reason=_reason(len(runs)))
        d, lo, hi = c.interval()
        v.update(chf_stop_mse_d=rounded(d), chf_stop_mse_lo=rounded(lo), chf_stop_mse_hi=rounded(hi),
                 chf_stop_mse_word=_word(c))
    return v
