r"""Chapter 02's readings-level benchmark: every method on one shared setup, over seeds; the
calibration-offset case."""

from __future__ import annotations

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from fusion._frozen import constant
from fusion.book.chapters.lecture import _lec_glue, _r, legend_below
from fusion.book.glue import GlueValues
from fusion.book.style import METHOD_LABELS, color, new_figure
from fusion.scenarios.lecture_weighting.readings_benchmark import (BenchMethod as B, SeedStability, _benchmark_results,
                                                                   seed_stability)
from fusion._docstrings import reads_results
from fusion._shown import shown
from fusion._validation import count, instance_of

__all__ = [
    "table_benchmark",
    "figure_benchmark",
    "glue_benchmark",
    "OFFSET_METHODS",
    "glue_offset",
]


# --------------------------------------------------------------------------- benchmark
def _paired(results: object, stab: object, needs: dict[tuple[float, bool], tuple[B, ...]] | None = None) -> dict:
    """``results`` (checked as :func:`~fusion.scenarios.lecture_weighting.readings_benchmark.seed_stability` checks it)
    and ``stab``, its seed stability: ``seed_stability(results)`` itself, not another benchmark's (a ValueError naming
    ``stab``, never a KeyError); with ``needs``, the scenarios and methods a caller reads (naming ``results``)."""
    instance_of(stab, SeedStability, "stab")
    results = _benchmark_results(results)
    ref = seed_stability(results)
    same = (ref.seeds, ref.scenarios, ref.methods) == (stab.seeds, stab.scenarios, stab.methods) and all(
        np.array_equal(ref.ranks[sc], stab.ranks[sc]) for sc in ref.scenarios)
    if not same:
        raise ValueError(f"stab must be seed_stability(results): it holds seeds {list(stab.seeds)} and scenarios "
                         f"{list(stab.scenarios)}, results give {list(ref.seeds)} and {list(ref.scenarios)} "
                         "(or other ranks; in results' order, whose first seed is shown)")
    for sc, methods in (needs or {}).items():
        key = (ref.seeds[0], *sc)
        lacking = [str(m) for m in methods if key not in results or m not in results[key]]
        if lacking:
            raise ValueError(f"results lacks {shown(key)} with the methods {lacking}")
    return results


def _scen_name(sc: tuple[float, bool]) -> str:
    return f"X={sc[0]:g}, {'fault' if sc[1] else 'no fault'}"


@reads_results("stab")
def table_benchmark(results: dict, stab: SeedStability, samples: int = 100) -> pd.DataFrame:
    """MSE ± SE of the first seed per scenario, and the rank range over the seeds.

    Parameters
    ----------
    results : dict
        Result of :func:`fusion.scenarios.lecture_weighting.readings_benchmark.benchmark`; the first seed's MSE ± SE.
    stab : SeedStability
        Result of :func:`fusion.scenarios.lecture_weighting.readings_benchmark.seed_stability`, for the ranks over the seeds.
    samples : int
        Instants K per run (as given to the benchmark), named in the index.

    Returns
    -------
    pandas.DataFrame
        Index the methods; per scenario a column "MSE ± SE" at the first seed (4 decimals; "± n/a" for a benchmark
        of one run, which has no standard error) and one of the rank range over the seeds ("2–3"). The index names
        ``samples`` as given (the results do not record it).

    Raises
    ------
    ValueError
        ``results`` not a benchmark's output (checked entry by entry, naming the entry), ``stab`` not
        ``seed_stability(results)`` (another benchmark's, or of the same results in another key order: the seeds'
        order is the results', whose first seed the table shows; fuzz 29b D2, deliberate); ``samples`` below 1.
    """
    results = _paired(results, stab)
    samples = count(samples, "samples")
    s0, methods = stab.seeds[0], stab.methods
    runs = next(iter(results.values()))[methods[0]].size

    def cell(v: np.ndarray) -> str:
        # one run has no standard error (fuzz 26d DB2: it printed "± 0.0000"): the cell shows the MSE alone
        return f"{v.mean():.4f} ± {v.std() / np.sqrt(runs):.4f}" if runs >= 2 else f"{v.mean():.4f} ± n/a"

    tab = pd.DataFrame({_scen_name(sc): [cell(results[(s0, *sc)][m]) for m in methods] for sc in stab.scenarios},
                       index=[METHOD_LABELS[m] for m in methods])
    for sc in stab.scenarios:
        r = stab.ranks[sc]
        tab[f"rank {_scen_name(sc)} ({len(stab.seeds)} seeds)"] = [
            f"{int(lo)}–{int(hi)}" if lo != hi else f"{int(lo)}" for lo, hi in zip(r.min(axis=0), r.max(axis=0))]
    tab.index.name = f"MSE at k = {samples} (seed {s0}, {runs} runs)"
    return tab


@reads_results("stab")
def figure_benchmark(results: dict, stab: SeedStability, samples: int = 100) -> Figure:
    """Bar chart of the benchmark MSE (first seed), one bar per scenario, log scale.

    Parameters
    ----------
    results : dict
        The per-run squared errors of :func:`fusion.scenarios.lecture_weighting.readings_benchmark.benchmark`.
    stab : SeedStability
        The seeds, methods and scenarios (:func:`fusion.scenarios.lecture_weighting.readings_benchmark.seed_stability`).
    samples : int
        Instants K per run (as given to the benchmark), for the axis label.

    Returns
    -------
    matplotlib.figure.Figure
        Bars per method, one per scenario: its mean MSE at k = ``samples`` (°C², log) at the first seed.

    Raises
    ------
    ValueError
        As :func:`table_benchmark`: bad ``results``, a ``stab`` of another benchmark, ``samples`` below 1.
    """
    results, samples = _paired(results, stab), count(samples, "samples")
    fig, ax = new_figure(figsize=(7.5, 3.8))
    methods, s0 = stab.methods, stab.seeds[0]
    pos = np.arange(len(methods))
    for j, sc in enumerate(stab.scenarios):
        ax.bar(pos + (j - 1.5) * 0.2, [results[(s0, *sc)][m].mean() for m in methods], width=0.2,
               label=_scen_name(sc), color=color(_scen_name(sc)))
    ax.set_yscale("log")
    ax.set_xticks(pos, [METHOD_LABELS[m] for m in methods], rotation=35, ha="right", fontsize=9)
    ax.set_ylabel(f"MSE at k = {samples} (°C²)")
    legend_below(fig, ncol=2)
    return fig


#: The scenarios (level, fault) and methods :func:`glue_benchmark` reads at the first seed.
_GLUED: dict[tuple[float, bool], tuple[B, ...]] = {
    (0.0, False): (B.AWF_LECTURE_FLOOR, B.MEAN, B.ORACLE, B.OPTIMAL_FUSION_SET),
    (900.0, False): (B.AWF_LECTURE_FLOOR, B.AWF_CENTRED, B.AWF_LECTURE_ABS, B.BELIEF, B.MEAN, B.ORACLE, B.MEDIAN,
                     B.BIWEIGHT),
    (0.0, True): (B.OPTIMAL_FUSION_SET, B.ORACLE, B.CHECK_AWF, B.BELIEF, B.AWF_CENTRED, B.SUPPORT_DEGREE, B.MEAN),
    (900.0, True): (B.BELIEF, B.MEAN, B.ORACLE, B.MEDIAN, B.BIWEIGHT)}


@_lec_glue
@reads_results("stab")
def glue_benchmark(results: dict, stab: SeedStability) -> GlueValues:
    """Glue values of the benchmark.

    Parameters
    ----------
    results : dict
        Result of :func:`fusion.scenarios.lecture_weighting.readings_benchmark.benchmark`.
    stab : SeedStability
        Of :func:`fusion.scenarios.lecture_weighting.readings_benchmark.seed_stability`: its first seed and its counts.

    Raises
    ------
    ValueError
        ``results`` not a benchmark's output (checked entry by entry, naming the entry), ``stab`` not
        ``seed_stability(results)`` (another benchmark's, or of the same results in another key order, as
        :func:`table_benchmark`), or ``results`` without the scenarios and methods it reads.
    """
    results = _paired(results, stab, _GLUED)
    s0 = stab.seeds[0]

    def m(sc: tuple[float, bool], name: B) -> tuple[float, int]:
        return results[(s0, *sc)][name].mean(), 4

    out = _r({"bm_awfl_0": m((0.0, False), B.AWF_LECTURE_FLOOR), "bm_awfl_900": m((900.0, False), B.AWF_LECTURE_FLOOR),
              "bm_mean_0": m((0.0, False), B.MEAN), "bm_oracle_0": m((0.0, False), B.ORACLE),
              "bm_awfc_900": m((900.0, False), B.AWF_CENTRED),
              "bm_awfa_900": m((900.0, False), B.AWF_LECTURE_ABS),
              "bm_ofs_clean": m((0.0, False), B.OPTIMAL_FUSION_SET), "bm_ofs_fault": m((0.0, True), B.OPTIMAL_FUSION_SET),
              "bm_oracle_fault": m((0.0, True), B.ORACLE),
              "bm_cc_fault": m((0.0, True), B.CHECK_AWF),
              "bm_bel_fault": m((0.0, True), B.BELIEF), "bm_awfc_fault": m((0.0, True), B.AWF_CENTRED),
              "bm_sup_fault": m((0.0, True), B.SUPPORT_DEGREE), "bm_mean_fault": m((0.0, True), B.MEAN)})
    bel = B.BELIEF
    out.update(_r({"bm_bel_clean_900": m((900.0, False), bel), "bm_mean_clean_900": m((900.0, False), B.MEAN),
                   "bm_bel_fault_900": m((900.0, True), bel), "bm_mean_fault_900": m((900.0, True), B.MEAN),
                   "bm_oracle_clean_900": m((900.0, False), B.ORACLE),
                   "bm_oracle_fault_900": m((900.0, True), B.ORACLE),
                   "bm_med_clean_900": m((900.0, False), B.MEDIAN), "bm_med_fault_900": m((900.0, True), B.MEDIAN),
                   "bm_bw_clean_900": m((900.0, False), B.BIWEIGHT),
                   "bm_bw_fault_900": m((900.0, True), B.BIWEIGHT),
                   "bm_bel_oracle_ratio": (results[(s0, 900.0, False)][bel].mean()
                                           / results[(s0, 900.0, False)][B.ORACLE].mean(), 1)}))
    out.update({"lec_bm_n_stable": int(stab.n_stable), "lec_bm_n_sig_pairs": int(stab.n_sig),
                "lec_bm_n_reversed": int(stab.n_rev), "lec_bm_n_scen": len(stab.scenarios)})
    return out


#: Methods of :func:`glue_offset` (keys of :class:`~fusion.scenarios.lecture_weighting.readings_benchmark.BenchMethod`)
#: and their glue keys.
OFFSET_METHODS: dict[B, str] = constant({B.ORACLE: "oracle", B.AWF_CENTRED: "cen", B.AWF_LECTURE_ABS: "abs", B.CHECK_AWF: "cc",
                                B.BELIEF: "bel", B.OPTIMAL_FUSION_SET: "ofs", B.MEDIAN: "med", B.BIWEIGHT: "bw",
                                B.MEAN: "mean"})


def glue_offset(results: dict) -> GlueValues:
    """Glue values of the benchmark with the fault present from the first sample (keys ``lec_bo_*``).

    Parameters
    ----------
    results : dict
        :func:`fusion.scenarios.lecture_weighting.readings_benchmark.benchmark` with ``fault_from=0``: one seed, one level
        (checked as :func:`fusion.scenarios.lecture_weighting.readings_benchmark.seed_stability` checks it: a TypeError
        or ValueError naming ``results``).

    Returns
    -------
    GlueValues
        ``lec_bo_<key>`` (MSE, 2 decimals) and ``lec_bo_<key>_se`` (its standard error) for every method of
        :data:`OFFSET_METHODS`; ``lec_bo_runs``, ``lec_bo_seed``, ``lec_bo_level``.

    Raises
    ------
    ValueError
        ``results`` not a benchmark's output, not one faulty setup, without a method of :data:`OFFSET_METHODS`, or
        of one run (a standard error needs two; glue is never NaN).
    """
    results = _benchmark_results(results)  # the benchmark's one check, entry by entry (fuzz 22b K2-6: "x" gave an IndexError)
    keys = [k for k in results if k[2]]
    if len(keys) != 1:
        raise ValueError(f"results must hold one faulty setup (one seed, one level), got {keys}")
    seed, level, _ = keys[0]
    r = results[keys[0]]
    lacking = [name for name in OFFSET_METHODS if name not in r]
    if lacking:
        raise ValueError(f"results[{shown(keys[0])}] lacks the methods {[str(m) for m in lacking]} of OFFSET_METHODS")
    runs = int(next(iter(r.values())).size)
    if runs < 2:  # fuzz 26d C1: the standard error of one run is NaN, and glue is never NaN
        raise ValueError(f"results holds {runs} run per method: the glued standard errors need at least 2 runs "
                         "(benchmark(runs=...))")
    out: GlueValues = {"lec_bo_runs": runs, "lec_bo_seed": int(seed),
                           "lec_bo_level": f"{level:g}"}
    for name, key in OFFSET_METHODS.items():
        v = np.asarray(r[name], dtype=float)
        out[f"lec_bo_{key}"] = round(float(v.mean()), 2)
        out[f"lec_bo_{key}_se"] = round(float(v.std(ddof=1) / np.sqrt(v.size)), 2)
    return out
