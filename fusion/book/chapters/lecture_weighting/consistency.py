r"""Chapter 02, §2.3 (E2.3): the consistency check + AWF with a faulty sensor: table, figure, glue and the
appendix's grid of thresholds and biases."""

from __future__ import annotations

from fusion.book._few_runs import study_runs_named
from fusion._counts import allocation, input_allocation, sequence
from fusion._limits import LOOP_STEP, work
from fusion._validation import as_array, instance_of, scalar, window as check_window
from fusion.book.chapters.lecture_weighting._common import _std_entries

from collections.abc import Sequence

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from fusion._validation import count, one_of
from fusion.book.chapters.lecture import _key, _lec_glue, _r, legend_below, sci
from fusion.book.ledger import Comparison
from fusion.book.style import METHOD_LABELS, color, new_figure
from fusion.readings import weighting as wt
from fusion.book.glue import GlueValues
from fusion.scenarios.lecture_weighting.consistency import ConsistencyStudy, FaultCase
from fusion.scenarios.lecture_weighting.estimators import CHECKED, AwfMethod
from fusion._counts import seed as check_seed

__all__ = [
    "table_23",
    "figure_23",
    "cc_log_comparison",
    "glue_23",
    "check_grid",
]


# --------------------------------------------------------------------------- 2.3
def table_23(s: ConsistencyStudy) -> pd.DataFrame:
    """Fault-window MSE of each method with and without the fault (E2.3), rounded to 4 decimals.

    Parameters
    ----------
    s : ConsistencyStudy
        E2.3 (:func:`fusion.scenarios.lecture_weighting.consistency.consistency_study`): the fault-window MSEs.

    Returns
    -------
    pandas.DataFrame
        One row per method, by its display label (the guard of the lecture's AWF in its name; the centred AWF with
        the floor), columns by the labels of the :class:`~fusion.scenarios.lecture_weighting.consistency.FaultCase`
        keys ("no fault", "fault"). Without a guard the MSE is infinite: its rows are
        sample values of an unbounded quantity, carried by a few runs.
    """
    instance_of(s, ConsistencyStudy, "s")
    tab = pd.DataFrame({METHOD_LABELS[case]: {METHOD_LABELS[nm]: float(np.mean(s.sq[case][nm])) for nm in s.names}
                        for case in FaultCase}).round(4)
    tab.index.name = f"MSE on samples {s.window[0] + 1}-{s.window[1]}"
    return tab


def figure_23(s: ConsistencyStudy) -> Figure:
    """F2.3: RMS error against time with the fault; detection probability against bias/ε.

    Parameters
    ----------
    s : ConsistencyStudy
        Result of :func:`fusion.scenarios.lecture_weighting.consistency.consistency_study`, with its RMS curves and detection rates.

    Returns
    -------
    matplotlib.figure.Figure
        Left: the RMS error (°C, log) of five methods against sample k, the fault's samples shaded; right: P(the faulty
        sensor rejected) against its bias / ε at one instant (the sensor named by ``s.fault_sensor``).
    """
    instance_of(s, ConsistencyStudy, "s")
    fig, axes = new_figure(1, 2, figsize=(7.5, 3.4))
    kk = np.arange(1, s.samples + 1)
    # (method, its colour and legend label: the arithmetic mean's; the check's colour, its own label)
    for nm, c, ls in ((AwfMethod.CURRENT_MEAN, "mean", ":"), (AwfMethod.MEAN_OF_MEANS, AwfMethod.MEAN_OF_MEANS, ":"),
                      (AwfMethod.AWF_CENTRED, AwfMethod.AWF_CENTRED, "--"),
                      (AwfMethod.CHECK_AWF_CENTRED, "check_awf", "-"),
                      (AwfMethod.AWF_LECTURE_FLOOR, AwfMethod.AWF_LECTURE_FLOOR, "--")):
        lab = METHOD_LABELS[c] if nm != AwfMethod.CHECK_AWF_CENTRED else "check + AWF (centred estimate)"
        axes[0].plot(kk, np.sqrt(np.mean((s.out[FaultCase.FAULT, nm] - s.x) ** 2, axis=0)), ls, color=color(c), label=lab)
    axes[0].axvspan(s.window[0] + 1, s.window[1], color="0.9", zorder=0)
    axes[0].set_yscale("log")
    axes[0].set_xlabel("sample k")
    axes[0].set_ylabel("RMS error (°C)")
    faulty = f"sensor {s.fault_sensor + 1}"   # the study's faulty sensor (1-based), not the default's (fuzz 26d F2)
    axes[0].set_title(f"{faulty} +{s.bias:g} °C on samples {s.window[0] + 1}-{s.window[1]} (shaded)")
    axes[1].plot(s.ratio, s.pdet, color=color("check_awf"))
    axes[1].set_xlabel(f"bias of {faulty} / ε")
    axes[1].set_ylabel(f"P({faulty} rejected)")
    axes[1].set_title(f"one instant, ε = {s.eps:.2f} °C")
    legend_below(fig, ncol=3)
    return fig


@study_runs_named("s")
def cc_log_comparison(s: ConsistencyStudy, a: AwfMethod, b: AwfMethod, case: FaultCase) -> Comparison:
    """Two methods of E2.3 on the log of the per-run MSE over the window (paired by run).

    The paired mean difference of the logs is the log of the ratio of geometric-mean MSEs: it exists
    for the unguarded lecture AWF, whose MSE does not.

    Parameters
    ----------
    s : ConsistencyStudy
        Output of :func:`fusion.scenarios.lecture_weighting.consistency.consistency_study`.
    a, b : AwfMethod
        Method keys of ``s.names``; claim: A lower than B (named by their display labels).
    case : FaultCase
        The data set (its label ends the metric's text).

    Returns
    -------
    Comparison
        ``a`` against ``b`` (claim "less"), run by run: ln of each run's MSE over the study's window (°C²) in ``case``,
        at the study's seed.
    """
    instance_of(s, ConsistencyStudy, "s")
    case = FaultCase(one_of(case, tuple(FaultCase), "case"))
    _key(case, s.sq, "case")
    a, b = _key(a, s.sq[case], "a"), _key(b, s.sq[case], "b")
    win = f"samples {s.window[0] + 1}-{s.window[1]}"
    return Comparison(np.log(s.sq[case][a]), np.log(s.sq[case][b]), METHOD_LABELS[a], METHOD_LABELS[b], "less",
                      f"ln of the MSE over {win} (°C²), {METHOD_LABELS[case]}", seed=s.seed)


@_lec_glue
@study_runs_named("s")
def glue_23(s: ConsistencyStudy) -> GlueValues:
    """Glue values of E2.3.

    Parameters
    ----------
    s : ConsistencyStudy
        Result of :func:`fusion.scenarios.lecture_weighting.consistency.consistency_study`.
    """
    instance_of(s, ConsistencyStudy, "s")
    tab = table_23(s)
    d = {"cc_eps": (s.eps, 3), "cc_bias": (s.bias, 4), "cc_pexcl_fault": (s.p_excl_fault, 4),
         "cc_pexcl_clean": (s.p_excl_clean, 5), "cc_pexcl_any_clean": (s.p_excl_any_clean, 5),
         "cc_pdet_at_1": (s.pdet[20], 4), "cc_pdet_at_05": (s.pdet[10], 4),
         "cc_pdet_at_15": (s.pdet[30], 4), "cc_pdet_at_2": (s.pdet[40], 4),
         "cc_bias_over_eps": (s.bias / s.eps, 2)}
    F, C = FaultCase.FAULT, FaultCase.NONE
    for case, key in ((F, "fault"), (C, "clean")):
        dg = s.diag[case]
        d[f"cc_allneg_{key}"] = (dg.p_all_healthy_negative, 4)
        d[f"cc_w3_{key}"] = (dg.weight_faulty, 15)
        d[f"cc_mse_healthy_{key}"] = (dg.mse_healthy_mean_of_means, 4)
    A = AwfMethod
    keys = {A.CURRENT_MEAN: "mean", A.MEAN_OF_MEANS: "mom", A.AWF_LECTURE_FLOOR: "awfl", A.CHECK_AWF_LECTURE_FLOOR: "ccl",
            A.AWF_LECTURE_ABS: "awfa", A.CHECK_AWF_LECTURE_ABS: "cca", A.AWF_CENTRED: "awfc", A.CHECK_AWF_CENTRED: "ccc",
            A.AWF_LECTURE_NONE: "awfn", A.CHECK_AWF_LECTURE_NONE: "ccn", A.AWF_LECTURE_EQUAL: "awfe",
            A.CHECK_AWF_LECTURE_EQUAL: "cce"}
    for nm, key in keys.items():
        d[f"cc_mse_{key}_fault"] = (tab.loc[METHOD_LABELS[nm], METHOD_LABELS[F]], 4)
        d[f"cc_mse_{key}_clean"] = (tab.loc[METHOD_LABELS[nm], METHOD_LABELS[C]], 4)
    da = s.diag[F]
    d.update({"cc_abs_w3": (da.abs_weight_faulty, 3), "cc_abs_wh_min": (float(np.min(da.abs_weights_healthy)), 3),
              "cc_abs_wh_max": (float(np.max(da.abs_weights_healthy)), 3), "cc_abs_var3": (da.abs_var_faulty, 0),
              "cc_abs_varh": (da.abs_var_healthy, 0), "cc_abs_var_ratio": (da.abs_var_faulty / da.abs_var_healthy, 2),
              "cc_abs_term": (da.abs_mse_faulty_term, 3), "cc_abs_mse": (da.abs_mse, 3),
              "cc_abs_share": (100 * da.abs_mse_faulty_term / da.abs_mse, 0),
              "cc_n_minus_1": (len(da.abs_weights_healthy), 0)})
    none, mm = A.AWF_LECTURE_NONE, A.MEAN_OF_MEANS
    for case, key in ((C, "clean"), (F, "fault")):
        c = cc_log_comparison(s, none, mm, case)
        m, lo, hi = c.interval()
        d[f"cc_gm_none_{key}"] = (np.exp(m), 2)
        d[f"cc_gm_lo_none_{key}"] = (np.exp(lo), 2)
        d[f"cc_gm_hi_none_{key}"] = (np.exp(hi), 2)
        c = cc_log_comparison(s, CHECKED[none], mm, case)
        m, lo, hi = c.interval()
        d[f"cc_gm_ccnone_{key}"] = (np.exp(m), 2)
        d[f"cc_gm_lo_ccnone_{key}"] = (np.exp(lo), 2)
        d[f"cc_gm_hi_ccnone_{key}"] = (np.exp(hi), 2)
    c = cc_log_comparison(s, CHECKED[none], none, F)
    m, lo, hi = c.interval()
    d["cc_gm_add"], d["cc_gm_add_lo"], d["cc_gm_add_hi"] = (np.exp(m), 2), (np.exp(lo), 2), (np.exp(hi), 2)
    idx = s.index_order
    if idx:
        sq_mm = s.sq[F][mm]
        gm = [float(np.exp(np.mean(np.log(v[F])))) for v in idx.values()]
        better = [Comparison(np.log(v[F]), np.log(sq_mm), "index order", METHOD_LABELS[mm], "less",
                             "ln MSE").status() == "reproduced" for v in idx.values()]
        d["cc_index_min"] = (min(gm), 4)
        d["cc_index_max"] = (max(gm), 4)
        d["cc_index_n"] = (len(idx), 0)
        d["cc_index_better"] = (int(sum(better)), 0)
        d["cc_gm_ccn_fault"] = (float(np.exp(np.mean(np.log(s.sq[F][CHECKED[none]])))), 4)
    out = _r(d)
    mask = s.mask[C]          # (runs, samples, sensors): reading kept
    n_inst = int(mask.shape[0] * mask.shape[1])  # instants of the runs without a fault
    out["lec_cc_n_inst_clean"] = n_inst
    out["lec_cc_n_excl_clean"] = int(round(s.p_excl_clean * n_inst))
    out["lec_cc_n_readings_clean"] = int(mask.size)
    out["lec_cc_n_excl_any_clean"] = int(np.sum(~mask.astype(bool)))
    out["lec_cc_w3_fault_text"] = sci(s.diag[F].weight_faulty, 2)
    return out


def _ci(d: np.ndarray) -> tuple[float, float, float]:
    """Mean of paired differences ``d`` with its normal 95 % interval (finite values assumed)."""
    d = np.asarray(d, dtype=float)
    m = float(d.mean())
    h = 1.96 * float(d.std(ddof=1)) / np.sqrt(d.size)
    return m, m - h, m + h


#: Units of work (``fusion._limits.work``, about 10 ns) of one (ε, bias) cell of :func:`check_grid` besides its readings
#: (two consistency fusions, their AWF, paired intervals and a row, whatever the readings), and of one bias besides its
#: cells (a copy of the draws, an AWF and the running means). Measured (fuzz 42b C4: 100,000 cells at 2 runs x 2
#: samples x 3 sensors, 6 % of the budget, ran 36 CPU-s; CPU time, minimum of 3, OPENBLAS_NUM_THREADS=1, shared
#: machine): 347 us a cell (40 factors x 25 biases) and 455 us a bias of one cell (1 x 1,000), at that size.
_GRID_CELL_WORK = 40 * LOOP_STEP
_GRID_BIAS_WORK = 10 * LOOP_STEP


def check_grid(eps_factors: tuple[float, ...] = (0.5, 1.0, 2.0), biases: tuple[float, ...] = (5.0, 10.0, 20.0, 30.0, 50.0),
               runs: int = 100, seed: int = 2305, sigma: Sequence[float] = (0.5, 1.0, 1.5, 2.0, 4.0),
               x: float = 900.0, window: tuple[int, int] = (49, 80), samples: int = 100) -> pd.DataFrame:
    """E2.3 over a grid of thresholds ε and fault sizes (review F17), paired runs.

    The sensors, level, window and faulty sensor (3) of :func:`fusion.scenarios.lecture_weighting.consistency.consistency_study`; the
    same ``runs`` noise draws in every cell; ε = f·3√2·σ_max for f in ``eps_factors``. Per cell: the share of the
    window's instants at which the check rejects sensor 3, and two paired differences of the per-run MSE over the
    window with their 95 % intervals: check + AWF (centred, floor) minus AWF (centred, floor), what the check adds;
    check + AWF (lecture, |σ̂²|) minus the mean of the running means.

    Parameters
    ----------
    eps_factors : tuple of float
        Multiples of the chapter's ε.
    biases : tuple of float
        Fault sizes (°C).
    runs : int
        Paired runs per cell (>= 2).
    seed : int
    sigma : sequence of float
        Noise SD of each sensor (°C).
    x : float
        True value (°C).
    window : (int, int)
        Fault samples, 0-based slice bounds.
    samples : int
        Instants per run.

    Returns
    -------
    pandas.DataFrame
        One row per (ε, bias).

    Raises
    ------
    TypeError
        A sequence argument not a sequence of numbers, or a count or ``seed`` not an integer.
    ValueError
        ``eps_factors`` or ``biases`` empty (no cell to show), an entry out of range, fewer than 3 sensors,
        ``window`` outside the samples; the draws (``runs`` x ``samples`` x sensors) beyond the memory budget
        (``fusion._counts.MAX_ELEMENTS``, 2 GiB), and so the consistency fusions' ``runs x samples x sensors x
        sensors`` pair arrays (eight at once), or the fusions of every cell (10 units a reading and sensor, at least
        50 a reading, and 40,000 a cell, measured) beyond the work budget (``fusion._limits.MAX_WORK``), naming
        ``biases``, ``eps_factors``, ``runs``, ``samples`` and ``sigma`` (the cells counted before any entry of
        ``biases`` or ``eps_factors`` is checked).
    """
    seed = check_seed(seed)
    from fusion.readings import consistency as cs

    runs = count(runs, "runs", minimum=2)
    samples = count(samples, "samples")
    sig = as_array(sigma, "sigma", ndim=1)
    _std_entries(sig, "sigma")   # at once, before the budgets on sig.size (fuzz 68b C7, C8)
    if sig.size < 3:
        raise ValueError(f"sigma must hold at least 3 sensors (sensor 3 is the faulty one), got {sig.size}")
    x = scalar(x, "x")
    eps_factors = sequence(eps_factors, "eps_factors", minimum=1, what="factor")
    biases = sequence(biases, "biases", minimum=1, what="fault size")
    names = "biases, eps_factors, runs, samples and sigma"
    # the cells, counted before any entry is checked (fuzz 42b C4: each cell's calls were not counted)
    work((len(biases), len(eps_factors)), names, weight=_GRID_CELL_WORK)
    eps_factors = [scalar(f, f"eps_factors[{i}]", lo=0.0, lo_open=True) for i, f in enumerate(eps_factors)]
    biases = [scalar(b, f"biases[{i}]") for i, b in enumerate(biases)]
    # every run's draws at once, before anything is drawn (fuzz 29b B3: 3e6 runs x 100 samples x 3 sensors passed the
    # work budget and drew 6.7 GiB); then the fusions of every cell
    allocation((runs, samples, sig.size), "runs, samples and sigma")
    # the readings are the input of the weighting fusions, which refuse more than MAX_INPUT_ELEMENTS (fuzz 39a D1/E4:
    # 130,666 runs were refused inside after 1.7 CPU-s, naming their argument X)
    input_allocation((runs, samples, sig.size), "runs, samples and sigma")
    # each cell's two consistency fusions hold (runs, samples, n, n) pair arrays (fuzz 41b C3: counted as runs x
    # samples x n, 1 eps x 1 bias at 40,000 runs raised a raw MemoryError after 20 CPU-s): their memory by the callee's
    # rule, before anything is drawn
    cs._pair_budget((runs, samples, sig.size), "runs, samples and sigma")
    # a reading of a cell passes the AWF, two consistency checks and their running means: 470-580 ns measured at 5
    # sensors (200 and 1,000 runs, time.process_time, shared machine; fuzz 39a E4), and the checks grow with the pairs
    # of sensors (fuzz 41b C3: 2 runs of 400 sensors, 6 % of a budget counting n, ran 63 CPU-s): one fused cell
    # measured 82 units a reading at 5 sensors (200 runs), 490 at 50 (20 runs), 1,640 at 200 (2 runs), so 10 units a
    # pair of sensors, at least 50 a reading: the edge 2,666 runs of the default grid (~10 CPU-s), 1 run at 400 sensors;
    # and each cell's and bias's own calls (fuzz 42b C4: 100,000 cells of 12 readings were counted 6e7, ran 36 CPU-s)
    cells = len(biases) * len(eps_factors)
    work((cells * (10 * runs * samples * sig.size * max(5, sig.size) + _GRID_CELL_WORK)
          + len(biases) * _GRID_BIAS_WORK,), names)
    win = slice(*check_window(window, "window", samples))
    eps0 = 3 * np.sqrt(2) * sig.max()
    clean = x + np.random.default_rng(seed).normal(size=(runs, samples, sig.size)) * sig
    rows = []
    for b in biases:
        data = clean.copy()
        data[:, win, 2] += b
        mse = {}
        mse["awfc"] = wt.awf(data, "centred").value
        mse["mm"] = wt.running_means(data).mean(axis=-1)
        sq = {k: np.mean((v[:, win] - x) ** 2, axis=1) for k, v in mse.items()}
        for f in eps_factors:
            eps = f * eps0
            cc = cs.consistency_awf(data, eps, "centred")
            cl = cs.consistency_awf(data, eps, "lecture", guard="abs")
            sq_cc = np.mean((cc.awf.value[:, win] - x) ** 2, axis=1)
            sq_cl = np.mean((cl.awf.value[:, win] - x) ** 2, axis=1)
            d1, d2 = _ci(sq_cc - sq["awfc"]), _ci(sq_cl - sq["mm"])
            rows.append({"ε (°C)": f"{eps:.2f}", "bias (°C)": f"{b:g}", "bias/ε": f"{b / eps:.2f}",
                         "sensor 3 rejected (%)": f"{100 * (1 - cc.mask[:, win, 2].mean()):.1f}",
                         "check adds, centred (°C²)": f"{d1[0]:+.4f} ({d1[1]:+.4f}, {d1[2]:+.4f})",
                         "check + AWF (|σ̂²|) − mean of means (°C²)": f"{d2[0]:+.4f} ({d2[1]:+.4f}, {d2[2]:+.4f})"})
    rows.sort(key=lambda r: float(r["ε (°C)"]))  # stable: the biases stay in their order within each ε
    return pd.DataFrame(rows).set_index(["ε (°C)", "bias (°C)"])
