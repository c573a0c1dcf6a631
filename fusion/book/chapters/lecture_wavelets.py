r"""Chapter 03 (the lecture notes, section 2.6: wavelet denoising and fusion-based reconstruction).

The chapter's studies come from :mod:`fusion.scenarios.wavelet_sensors`: :func:`~fusion.scenarios.wavelet_sensors.signal_study`
(E2.6, the primary reading with more runs, and the signal × threshold-rule verdicts), :func:`~fusion.scenarios.wavelet_sensors.mechanism_study` (bias,
correlation, wavelet settings, order) and :func:`~fusion.scenarios.wavelet_sensors.variance_study` (the lecture's
step 3). Each ``table_*``, ``figure_*`` and ``glue_*`` presents one of them (glue keys prefixed ``lec_``), and
:func:`evidence` computes the evidence of chapter 03's records of ``book/claims/lecture003.yaml``.

Every claim of section 2.6 is about *every* sensor, so each reading is scored as a
:class:`fusion.book.ledger.Conjunction` of the four sensors' paired comparisons. The primary reading
(:data:`PRIMARY`) is decided by E2.6, which has more runs than the other readings (its verdict hangs on
rare runs, see :func:`glue_26`); wherever a table shows the primary reading's verdict it takes it from
E2.6 (:func:`cell`).
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Mapping
from typing import Any

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from scipy import stats

from fusion._validation import count, one_of
from fusion.book import rulebook as R
from fusion.book.chapters.lecture import _r, evidence_at, glue_figures, legend_below, reading_key
from fusion.book.ledger import (
    Comparison,
    Conjunction,
)
from fusion.book.style import METHOD_LABELS, color, new_figure

__all__ = [
    "glue_figures", "PRIMARY", "SIGNAL_TEXT", "sensor_conjunction", "sign_conjunction", "status_text", "cell",
    "table_seeds", "glue_seeds", "mean_only_status", "glue_runs_benchmark",
    "table_26", "table_26_display", "figure_26", "glue_26", "glue_equal_gains",
    "QUESTIONS", "table_signals", "glue_signals",
    "table_mechanism", "table_sensitivity", "table_sensitivity_display", "figure_mechanism", "glue_mechanism",
    "VARIANCE_LABELS", "table_variance", "glue_variance",
    "CONFIG_KEYS", "SIGNAL_KEYS", "VARIANCE_READINGS", "STUDIES", "SEED", "RUNS", "N_RUNS", "study",
    "COMMON_READINGS", "ev_wavelet_better", "ev_wavelet_accurate",
    "ev_wavelet_fusion_helps", "ev_wavelet_weighting", "EVIDENCE", "evidence", "ledger_values",
    "typical_run", "table_typical", "glue_typical", "LENGTHS", "length_study", "table_lengths", "glue_lengths",
]

#: The primary reading of every record: (signal, threshold rule, normaliser), with db4, 4 levels,
#: the universal threshold and the batch residual variance of the weights.
PRIMARY: tuple[str, str, str] = ("two tones", "hard", "max")

#: Short descriptions of the signals of :data:`fusion.scenarios.wavelet_sensors.SIGNALS` (for the ledger).
SIGNAL_TEXT: dict[str, str] = {"two tones": "2 + sin(2πn/256) + 0.5 sin(2πn/64)", "slow": "2 + sin(2πn/256)",
                               "constant": "a steady measurand, 2", "HeaviSine": "piecewise smooth, Donoho-Johnstone"}

_NAMES = {"raw": "raw", "denoised": "own denoised", "reconstructed": "reconstructed", "denoise-first": "reconstructed",
          "fuse-first": "fused first, then denoised"}


def sensor_conjunction(a: np.ndarray, b: np.ndarray, a_name: str, b_name: str, metric: str, seed: int,
                       claim: str = "less") -> Conjunction:
    """One paired comparison per sensor (columns of ``a`` and ``b``), joined: the claim is about every sensor.

    Parameters
    ----------
    a, b : ndarray, shape (runs, sensors)
        Per-run metric of A and of B.
    a_name, b_name : str
        What A and B are (the sensor is appended).
    metric : str
        What is compared ("{j}" is replaced by the sensor's number).
    seed : int
        Seed of the runs.
    claim : {"less", "greater"}
        What the source claims of A against B.

    Returns
    -------
    fusion.book.ledger.Conjunction
    """
    return Conjunction(tuple((f"sensor {j + 1}", Comparison(a[:, j], b[:, j], f"{a_name} (sensor {j + 1})",
                                                            f"{b_name} (sensor {j + 1})", claim,
                                                            metric.format(j=j + 1), seed=seed))
                             for j in range(a.shape[1])))


def status_text(c: Conjunction) -> str:
    """``"reproduced"``, or the status with the sensors that decide it (``"not distinguishable: sensor 4"``).

    Parameters
    ----------
    c : fusion.book.ledger.Conjunction

    Returns
    -------
    str
    """
    st = c.status()
    if st == "reproduced":
        return st
    bad = [lab.replace("sensor ", "") for lab, ev in c.parts if ev.status() == st]
    return f"{st}: sensor{'s' if len(bad) > 1 else ''} {', '.join(bad)}"


def sign_conjunction(a: np.ndarray, b: np.ndarray, a_name: str, b_name: str, seed: int) -> Conjunction:
    """Per sensor: is A better than B in more than half of the runs (the median paired difference below 0)?

    A sign test written as a paired comparison: the indicator of ``A < B`` in each run against one
    half, so that the ledger's interval is the normal (Wald) interval of the fraction of runs won. It
    reads the claim by the *typical* run, where :func:`sensor_conjunction` reads it by the mean, which a
    few runs with a large loss can carry.

    Parameters
    ----------
    a, b : ndarray, shape (runs, sensors)
        Per-run metric of A and of B.
    a_name, b_name : str
        What A and B are.
    seed : int
        Seed of the runs.

    Returns
    -------
    fusion.book.ledger.Conjunction
    """
    return Conjunction(tuple((f"sensor {j + 1}", Comparison((a[:, j] < b[:, j]).astype(float), np.full(a.shape[0], 0.5),
                                                            f"fraction of runs in which {a_name} beats {b_name} "
                                                            f"(sensor {j + 1})", "one half", "greater",
                                                            "fraction of runs won (sign test)", seed=seed))
                             for j in range(a.shape[1])))


def cell(sg: dict[str, Any], e26: dict[str, Any] | None, key: tuple[str, str, str]) -> dict[str, Any]:
    """The case ``key`` = (signal, rule, normaliser): from E2.6 (more runs) when it holds it, else from ``sg``.

    Parameters
    ----------
    sg : dict
        :func:`fusion.scenarios.wavelet_sensors.signal_study` over the signals and rules.
    e26 : dict or None
        The same study for the primary signal and rule only, with more runs (E2.6).
    key : tuple of str

    Returns
    -------
    dict
        The case (``"raw"``, ``"denoised"``, ``"reconstructed"``, ... as in ``signal_study``), with
        ``"runs"`` and ``"seed"`` of the study it comes from.
    """
    src = e26 if e26 is not None and key in e26["cases"] else sg
    return {**src["cases"][key], "runs": src["runs"], "seed": src["seed"]}


# --------------------------------------------------------------------------- E2.6 (primary reading)
def _e26_case(e: dict[str, Any], nm: str) -> dict[str, Any]:
    return e["cases"][e["signals"][0], e["modes"][0], nm]


def _table_26_exact(e: dict[str, Any]) -> pd.DataFrame:
    g, sig = e["gains"], e["sigma"]
    c = {nm: _e26_case(e, nm) for nm in e["normalisers"]}
    mx = c["max"]
    rows = {}
    for j in range(g.size):
        r = {"MSE raw": mx["raw"]["mse"][:, j].mean(), "MSE denoised": mx["denoised"]["mse"][:, j].mean()}
        for nm in e["normalisers"]:
            r[f"MSE reconstructed ({nm})"] = c[nm]["reconstructed"]["mse"][:, j].mean()
        r["P(rec < raw)"] = np.mean(mx["reconstructed"]["mse"][:, j] < mx["raw"]["mse"][:, j])
        r["P(rec < denoised)"] = np.mean(mx["reconstructed"]["mse"][:, j] < mx["denoised"]["mse"][:, j])
        r["RMS gain error of max"] = np.sqrt(np.mean(mx["gain_err"][:, j] ** 2))
        if "max-raw" in c:
            r["RMS gain error of max (raw data)"] = np.sqrt(np.mean(c["max-raw"]["gain_err"][:, j] ** 2))
        rows[f"sensor {j + 1} (g={g[j]:g}, σ={sig[j]:g})"] = r
    return pd.DataFrame(rows)


def table_26(e: dict[str, Any]) -> pd.DataFrame:
    """Per-sensor MSEs, win fractions and the maximum's gain error of E2.6, rounded to 5 decimals.

    Parameters
    ----------
    e : dict
        Result of :func:`fusion.scenarios.wavelet_sensors.signal_study` with one signal, one rule and
        the normalisers ``("max", "median", "lsq")``.

    Returns
    -------
    pandas.DataFrame
    """
    return _table_26_exact(e).round(5)


def table_26_display(e: dict[str, Any]) -> pd.DataFrame:
    """:func:`table_26` for the page: MSEs ×10⁴ and fractions of runs at 2 decimals, gain errors at 4 (text).

    Parameters
    ----------
    e : dict
        As :func:`table_26`.

    Returns
    -------
    pandas.DataFrame
        The rows of :func:`table_26`, MSE rows scaled by 10⁴ (relabelled) and every cell formatted.
    """
    tab = _table_26_exact(e)
    out = {}
    for row in tab.index:
        if row.startswith("MSE"):
            out[row.replace("MSE", "MSE ×10⁴", 1)] = [f"{1e4 * v:.2f}" for v in tab.loc[row]]
        else:
            out[row] = [f"{v:.2f}" if row.startswith("P(") else f"{v:.4f}" for v in tab.loc[row]]
    return pd.DataFrame(out, index=tab.columns).T


def figure_26(e: dict[str, Any], sensor: int = 3, shown: int = 300) -> Figure:
    """F2.6: raw, denoised and reconstructed signal of one sensor (run 0); MSE per sensor.

    Parameters
    ----------
    e : dict
        As :func:`table_26`.
    sensor : int
        Sensor shown (0-based).
    shown : int
        Number of samples shown.

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, axes = new_figure(1, 2, figsize=(7.5, 3.4))
    kind = e["signals"][0]
    mx = _e26_case(e, "max")
    n = np.arange(e["length"])
    sl = slice(0, shown)
    axes[0].plot(n[sl], e["raw0"][kind][sensor, sl], color=color("raw"), lw=0.8, label=f"raw (sensor {sensor + 1})")
    axes[0].plot(n[sl], mx["example"]["denoised"][sensor, sl], color=color("denoised"), label="denoised")
    axes[0].plot(n[sl], mx["example"]["reconstructed"][sensor, sl], color=color("reconstructed"),
                 label=METHOD_LABELS["reconstructed"])
    axes[0].plot(n[sl], e["truth"][kind][sensor, sl], ":", color=color("published"), lw=1, label="true signal")
    axes[0].set_xlabel("sample n")
    pos = np.arange(e["gains"].size)
    med = _e26_case(e, "median")
    for off, vals, c in ((-0.3, mx["raw"]["mse"], "raw"), (-0.1, mx["denoised"]["mse"], "denoised"),
                         (0.1, mx["reconstructed"]["mse"], "reconstructed"),
                         (0.3, med["reconstructed"]["mse"], "reconstructed_median")):
        axes[1].bar(pos + off, vals.mean(axis=0), width=0.2, color=color(c), label=METHOD_LABELS[c])
    axes[1].set_yscale("log")
    axes[1].set_xticks(pos, [f"sensor {j + 1}" for j in pos])
    axes[1].set_ylabel("MSE against gⱼS")
    legend_below(fig, ncol=3)
    return fig


def glue_26(e: dict[str, Any], spike: float = 0.04, first: int | None = None) -> dict[str, float]:
    """Glue values of E2.6 (keys ``lec_wv_*``): MSEs, intervals, and how rare runs carry the mean.

    Parameters
    ----------
    e : dict
        As :func:`table_26` (the primary reading with its runs; normalisers ``"max"``, ``"max-raw"``,
        ``"median"``, ``"lsq"``).
    spike : float
        A relative gain error of a sensor's maximum above which a run counts as one whose maximum
        landed on a noise spike.
    first : int, optional
        If given (and below the runs), the interval of the paired difference reconstructed − own denoised is
        also given for the first ``first`` runs only (the same noise stream; keys ``lec_wv_first_*``), to show
        how the verdict depends on the run count (:func:`table_seeds` shows every block).

    Returns
    -------
    dict of str to float
        Glue keys (prefixed ``lec_``) and rounded values. Per sensor j: MSEs ×10⁴ (raw, denoised, each
        normaliser), win fractions, RMS gain error, the paired difference reconstructed − own denoised
        (×10⁴) and its interval, its median, the fraction of runs won with a Clopper-Pearson 95 % interval,
        the sum of the 1 % largest differences over the sum of all (``wv_top_share_j``: above 1 means those
        runs carry more than the whole mean difference) and the mean without them, the number of runs
        lost and of those lost with a spiked maximum; the same interval over the first ``first`` runs, if given.
    """
    from scipy.stats import binomtest

    tab = _table_26_exact(e)
    mx = _e26_case(e, "max")
    runs = int(e["runs"])
    d: dict[str, tuple[float, int]] = {}
    for j in range(tab.shape[1]):
        col = tab.iloc[:, j]
        d[f"wv_p_beats_raw_{j + 1}"] = (col["P(rec < raw)"], 2)
        d[f"wv_p_beats_den_{j + 1}"] = (col["P(rec < denoised)"], 2)
        d[f"wv_gainerr_{j + 1}"] = (col["RMS gain error of max"], 4)
        d[f"wv_mse_raw_{j + 1}"] = (1e4 * col["MSE raw"], 2)
        d[f"wv_mse_den_{j + 1}"] = (1e4 * col["MSE denoised"], 2)
        for nm in e["normalisers"]:
            d[f"wv_mse_{nm.replace('-', '')}_{j + 1}"] = (1e4 * col[f"MSE reconstructed ({nm})"], 2)
        if "max-raw" in e["normalisers"]:
            d[f"wv_gainerr_raw_{j + 1}"] = (float(np.sqrt(np.mean(_e26_case(e, "max-raw")["gain_err"][:, j] ** 2))), 4)
    d["wv_w1"] = (mx["weights"][:, 0].mean(), 3)
    for j in range(tab.shape[1]):
        d[f"wv_ff_{j + 1}"] = (1e4 * float(mx["fuse-first"]["mse"][:, j].mean()), 2)
    rec, den = mx["reconstructed"]["mse"], mx["denoised"]["mse"]
    c = sensor_conjunction(rec, den, "rec", "den", "MSE", e["seed"])
    out: dict[str, float] = {}
    top = max(1, runs // 100)
    for j, (_, ev) in enumerate(c.parts):
        mean, lo, hi = ev.interval()
        k = j + 1
        d[f"wv_den_d_{k}"], d[f"wv_den_lo_{k}"], d[f"wv_den_hi_{k}"] = (1e4 * mean, 2), (1e4 * lo, 2), (1e4 * hi, 2)
        dif = rec[:, j] - den[:, j]
        d[f"wv_den_med_{k}"] = (1e4 * float(np.median(dif)), 2)
        wins = int(np.sum(dif < 0))
        ci = binomtest(wins, runs).proportion_ci(0.95)
        d[f"wv_win_{k}"], d[f"wv_win_lo_{k}"], d[f"wv_win_hi_{k}"] = (wins / runs, 3), (ci.low, 3), (ci.high, 3)
        worst = np.sort(dif)[::-1][:top]
        d[f"wv_top_share_{k}"] = (float(worst.sum() / abs(dif.sum())), 2)
        d[f"wv_mean_wo_top_{k}"] = (1e4 * float(np.sort(dif)[:-top].mean()), 2)
        ge = np.abs(mx["gain_err"][:, j])
        d[f"wv_gain_max_{k}"] = (float(ge.max()), 3)
        out[f"lec_wv_n_worse_{k}"] = int(np.sum(dif > 0))
        out[f"lec_wv_n_spike_worse_{k}"] = int(np.sum((ge > spike) & (dif > 0)))
        out[f"lec_wv_n_spike_{k}"] = int(np.sum(ge > spike))
    out["lec_wv_helps_status"] = status_text(c)
    if first is not None and runs > first:
        cf = sensor_conjunction(rec[:first], den[:first], "rec", "den", "MSE", e["seed"])
        out["lec_wv_first_status"] = status_text(cf)
        for j, (_, ev) in enumerate(cf.parts):
            mean, lo, hi = ev.interval()
            d[f"wv_first_d_{j + 1}"], d[f"wv_first_lo_{j + 1}"], d[f"wv_first_hi_{j + 1}"] = (
                (1e4 * mean, 2), (1e4 * lo, 2), (1e4 * hi, 2))
    out.update(_r(d))
    out["lec_wv_spike"] = spike
    out["lec_wv_runs"] = runs
    out["lec_wv_top"] = top
    if first is not None:
        out["lec_wv_first"] = int(first)
    return out


def glue_equal_gains(e1: dict[str, Any]) -> dict[str, float]:
    """Glue values of the lecture's own model, equal gains (keys ``lec_wg1_*``).

    Parameters
    ----------
    e1 : dict
        Result of :func:`fusion.scenarios.wavelet_sensors.signal_study` with gains (1, 1, 1, 1), one
        signal, one rule and the maximum normaliser.

    Returns
    -------
    dict of str to float
        Per sensor: the paired MSE difference reconstructed − own denoised (×10⁴) and its 95 % interval,
        and the RMS gain error of the maximum; the number of sensors for which the reconstruction is better; the runs.
    """
    c = _e26_case(e1, "max")
    conj = sensor_conjunction(c["reconstructed"]["mse"], c["denoised"]["mse"], "rec", "den", "MSE", e1["seed"])
    d: dict[str, tuple[float, int]] = {}
    for j, (_, ev) in enumerate(conj.parts):
        mean, lo, hi = ev.interval()
        d[f"wg1_d_{j + 1}"], d[f"wg1_lo_{j + 1}"], d[f"wg1_hi_{j + 1}"] = (1e4 * mean, 2), (1e4 * lo, 2), (1e4 * hi, 2)
        d[f"wg1_gain_{j + 1}"] = (float(np.sqrt(np.mean(c["gain_err"][:, j] ** 2))), 4)
    out = _r(d)
    wins = [str(j + 1) for j, (_, ev) in enumerate(conj.parts) if ev.status() == "reproduced"]
    out["lec_wg1_n_better"] = len(wins)
    out["lec_wg1_better_sensors"] = ", ".join(wins[:-1]) + (" and " if len(wins) > 1 else "") + (wins[-1] if wins else "none")
    out["lec_wg1_runs"] = int(e1["runs"])
    # the lecture's model with the maximum of the denoised signal (the accuracy records' primary, keys lec_wp_*) and
    # of the raw data (the reading lecture-raw-max, keys lec_wl_*): each sensor's reconstruction against its raw data
    # and against its own denoised signal (MSE ×10⁴)
    for pre, nm in (("wp", "max"), ("wl", "max-raw")):
        c = _e26_case(e1, nm)
        for tag, b in (("raw", "raw"), ("den", "denoised")):
            conj = sensor_conjunction(c["reconstructed"]["mse"], c[b]["mse"], "rec", b, "MSE", e1["seed"])
            for j, (_, ev) in enumerate(conj.parts):
                mean, lo, hi = ev.interval()
                out[f"lec_{pre}_{tag}_d_{j + 1}"] = round(1e4 * mean, 1)
                out[f"lec_{pre}_{tag}_lo_{j + 1}"] = round(1e4 * lo, 1)
                out[f"lec_{pre}_{tag}_hi_{j + 1}"] = round(1e4 * hi, 1)
                out[f"lec_{pre}_{tag}_a_{j + 1}"] = round(1e4 * float(np.mean(c["reconstructed"]["mse"][:, j])), 1)
                out[f"lec_{pre}_{tag}_b_{j + 1}"] = round(1e4 * float(np.mean(c[b]["mse"][:, j])), 1)
            out[f"lec_{pre}_{tag}_n_worse"] = int(sum(ev.status() == "contradicted" for _, ev in conj.parts))
            out[f"lec_{pre}_{tag}_status"] = status_text(conj)
    return out


def _seed_rows(e26: dict[str, Any], block: int = 100,
               ss: dict[str, Any] | None = None) -> list[tuple[str, Conjunction]]:
    """(label, conjunction rec < own denoised) for each block of ``block`` runs of E2.6, each seed of ``ss``, all of E2.6.

    E2.6's runs are independent draws of one stream, so its disjoint blocks of runs are as many independent
    repetitions of a ``block``-run study: at no cost they show how often that run count decides the verdict.
    """
    mx = _e26_case(e26, "max")
    rec, den = mx["reconstructed"]["mse"], mx["denoised"]["mse"]
    runs = int(e26["runs"])
    block = count(block, "block", minimum=2)
    if block > runs:
        raise ValueError(f"block must be at most the runs of e26 ({runs}), got {block}")
    rows = [(f"runs {i + 1}-{i + block}", sensor_conjunction(rec[i:i + block], den[i:i + block], "rec", "den", "MSE",
                                                             e26["seed"]))
            for i in range(0, runs - block + 1, block)]
    for v, c in (ss or {"cases": {}})["cases"].items():
        rows.append((f"seed {v}, {ss['runs']} runs", sensor_conjunction(c["reconstructed"]["mse"],
                                                                         c["denoised"]["mse"], "rec", "den", "MSE", v)))
    rows.append((f"all {runs} runs (E2.6, a reading)", sensor_conjunction(rec, den, "rec", "den", "MSE", e26["seed"])))
    return rows


def table_seeds(e26: dict[str, Any], block: int = 100, ss: dict[str, Any] | None = None,
                sensors: tuple[int, ...] = (2, 3)) -> pd.DataFrame:
    """The primary reading's "MSE < own denoised" on disjoint blocks of E2.6's runs: intervals and verdict.

    Parameters
    ----------
    e26 : dict
        E2.6 (:func:`fusion.scenarios.wavelet_sensors.signal_study`, primary signal and rule, its seed).
    block : int
        Runs per block (>= 2, at most E2.6's runs); E2.6's runs are cut into disjoint blocks of this size.
    ss : dict, optional
        :func:`fusion.scenarios.wavelet_sensors.seed_study` of the same case: one more row per seed.
    sensors : tuple of int
        Sensors (0-based) whose interval is shown (the verdict column covers all of them).

    Returns
    -------
    pandas.DataFrame
        One row per block (then per seed of ``ss``, then all of E2.6's runs): the paired difference
        reconstructed − own denoised ×10⁴ with its 95 % interval for the chosen sensors (text, 1 decimal) and
        the verdict for all four sensors at once.

    Raises
    ------
    ValueError
        ``block`` not a count >= 2 or larger than E2.6's runs.
    """
    rows = {}
    for lab, conj in _seed_rows(e26, block, ss):
        r = {}
        for j in sensors:
            name, ev = conj.parts[j]
            mean, lo, hi = ev.interval()
            r[f"{name} ×10⁴"] = f"{1e4 * mean:.1f} [{1e4 * lo:.1f}, {1e4 * hi:.1f}]"
        r["every sensor"] = status_text(conj)
        rows[lab] = r
    tab = pd.DataFrame(rows).T
    tab.index.name = "runs of E2.6"
    return tab


def mean_only_status(a: np.ndarray, b: np.ndarray, relative_margin: float = R.DEFAULT_RELATIVE_MARGIN) -> str:
    """The status of "A lower than B" by the mean's paired t interval alone (rule R2 without R3's heavy-tail test).

    What the chapter's readings gave before the rulebook judged heavy-tailed differences by the median: shown to
    count how often a run count decides the *mean*.

    Parameters
    ----------
    a, b : ndarray, shape (runs,)
        Paired per-run values (runs >= 2, finite).
    relative_margin : float
        Practical margin as a share of B's mean.

    Returns
    -------
    str
    """
    d = np.asarray(a, dtype=float) - np.asarray(b, dtype=float)
    if d.ndim != 1 or d.size < 2 or not np.all(np.isfinite(d)):
        raise ValueError("a and b must be finite paired runs of the same length >= 2")
    ci = stats.ttest_1samp(d, 0.0).confidence_interval(R.CONFIDENCE_LEVEL)
    margin = relative_margin * abs(float(np.mean(b)))
    return R.status_from_region(R.region(float(ci.low), float(ci.high), margin), "less")


def glue_seeds(e26: dict[str, Any], block: int = 100, key: str = "wsd") -> dict[str, float]:
    """Glue values of the block check (keys ``lec_<key>_*``): how often ``block`` runs decide the primary verdict.

    Parameters
    ----------
    e26, block
        As :func:`table_seeds`.
    key : str
        Glue key prefix after ``lec_`` (one per block size: the chapter uses ``"wsd"`` for blocks of 100 runs
        and ``"wsdk"`` for blocks of 1000).

    Returns
    -------
    dict of str to float
        ``lec_<key>_runs`` (runs per block), ``lec_<key>_n`` (blocks), ``lec_<key>_n_r`` (blocks under which the
        reconstruction beats every sensor's own denoised signal on average), ``lec_<key>_n_n`` (not
        distinguishable), ``lec_<key>_n_c`` (contradicted), ``lec_<key>_n_typ`` (blocks under which it beats
        it in the typical run for every sensor: :func:`sign_conjunction` reproduced) and ``lec_<key>_n_mean_r``
        (blocks that the mean's t interval alone reproduces for every sensor, :func:`mean_only_status`).
    """
    rows = _seed_rows(e26, block)[:-1]
    st = [c.status() for _, c in rows]
    mx = _e26_case(e26, "max")
    rec, den = mx["reconstructed"]["mse"], mx["denoised"]["mse"]
    typ = [sign_conjunction(rec[i:i + block], den[i:i + block], "rec", "den", e26["seed"]).status()
           for i in range(0, len(rows) * block, block)]
    by_mean = [all(mean_only_status(rec[i:i + block, j], den[i:i + block, j]) == "reproduced" for j in range(rec.shape[1]))
               for i in range(0, len(rows) * block, block)]
    return {f"lec_{key}_runs": int(block), f"lec_{key}_n": len(rows), f"lec_{key}_n_mean_r": int(sum(by_mean)),
            f"lec_{key}_n_r": int(sum(x == "reproduced" for x in st)),
            f"lec_{key}_n_n": int(sum(x == "not distinguishable" for x in st)),
            f"lec_{key}_n_c": int(sum(x == "contradicted" for x in st)),
            f"lec_{key}_n_typ": int(sum(x == "reproduced" for x in typ))}


def glue_runs_benchmark(b: Any) -> dict[str, float]:
    """Glue values of ``benchmarks/bench_wavelet_runs.py`` (keys ``lec_wbr_<key>``): the verdicts with more runs.

    Parameters
    ----------
    b : fusion.book.benchmarks.BenchmarkResult
        ``load_benchmark("wavelet_runs")``.

    Returns
    -------
    dict of str to float
        Every keyed measurement (integers for the counts and flags, 2 decimals for the intervals ×10⁴) and
        ``lec_wbr_n_seeds``, the number of other seeds.
    """
    out: dict[str, float] = {}
    for k, v in b.values.items():
        out[f"lec_wbr_{k}"] = int(v) if float(v).is_integer() and not k.split("_")[-2:-1] in (["mean"], ["lo"], ["hi"]) \
            else round(float(v), 2)
    out["lec_wbr_n_seeds"] = len(b.record.get("seeds", ())) - 1
    return out


# --------------------------------------------------------------------------- the open choices: signal, rule
#: The four questions of the signal table, one per record: (short id, column, A, B, metric).
QUESTIONS: tuple[tuple[str, str, str, str, str], ...] = (
    ("better", "variance < raw", "reconstructed", "raw", "evar"),
    ("accurate", "MSE < raw", "reconstructed", "raw", "mse"),
    ("helps", "MSE < own denoised", "reconstructed", "denoised", "mse"),
    ("order", "lecture's order < fuse first", "reconstructed", "fuse-first", "mse"),
)

_METRIC = {"mse": "MSE against g{j}S", "evar": "ensemble error variance (bias excluded)",
           "tvar": "temporal variance of the data (constant measurand)"}


def _q(sg: dict[str, Any], key: tuple[str, str, str], a: str, b: str, metric: str,
       e26: dict[str, Any] | None = None) -> Conjunction:
    c = cell(sg, e26, key)
    return sensor_conjunction(c[a][metric], c[b][metric], _NAMES[a], _NAMES[b], _metric_label(sg, metric), c["seed"])


def _metric_label(study_: dict[str, Any], metric: str) -> str:
    """The metric's label; the MSE is against S on the lecture's model (equal gains), against gⱼS otherwise."""
    if metric == "mse" and np.allclose(np.asarray(study_.get("gains", ()), dtype=float), 1.0):
        return "MSE against S"
    return _METRIC[metric]


#: Columns of :func:`table_signals` shown by ``part="normalisers"`` (the others, with the runs, are ``"verdicts"``).
_NORM_COLUMNS = ("RMS gain error of max, sensor 3", "median normaliser: MSE < own denoised",
                 "max of the raw data: MSE < own denoised", "data variance over time < raw and < own denoised")


def table_signals(sg: dict[str, Any], e26: dict[str, Any] | None = None, part: str = "all") -> pd.DataFrame:
    """Verdict of each question for every sensor at once, under each signal and threshold rule (max normaliser).

    Parameters
    ----------
    sg : dict
        Result of :func:`fusion.scenarios.wavelet_sensors.signal_study` (normalisers ``("max", ...)``,
        and ``"median"`` among them; ``"max-raw"`` adds a column).
    e26 : dict, optional
        E2.6, the primary signal and rule with more runs: its row is taken from it (:func:`cell`).
    part : {"all", "verdicts", "normalisers"}
        Every column, or one of the two halves that fit the page: the runs and the questions of
        :data:`QUESTIONS`, or the columns about the normaliser and the spread over time.

    Returns
    -------
    pandas.DataFrame
        Rows (signal, rule); the runs; one column per question of :data:`QUESTIONS` (status, and the sensors
        that decide it), the temporal variance of the data against the raw and the denoised data for the
        constant measurand, the RMS gain error of the maximum for sensor 3, and the question "MSE <
        own denoised" with the median normaliser and with the maximum of the raw data instead.
    """
    rows = {}
    for kind in sg["signals"]:
        for mode in sg["modes"]:
            key = (kind, mode, "max")
            n = cell(sg, e26, key)["runs"]
            r = {"runs": f"{n} (E2.6: reading more-runs)" if n != sg["runs"] else str(n)}
            r.update({col: status_text(_q(sg, key, a, b, m, e26)) for _, col, a, b, m in QUESTIONS})
            r["data variance over time < raw and < own denoised"] = (
                "; ".join(status_text(_q(sg, key, "reconstructed", ref, "tvar", e26)) for ref in ("raw", "denoised"))
                if kind == "constant" else "(signal varies)")
            r["RMS gain error of max, sensor 3"] = f"{np.sqrt(np.mean(cell(sg, e26, key)['gain_err'][:, 2] ** 2)):.4f}"
            r["median normaliser: MSE < own denoised"] = status_text(
                _q(sg, (kind, mode, "median"), "reconstructed", "denoised", "mse", e26))
            if "max-raw" in sg["normalisers"]:
                r["max of the raw data: MSE < own denoised"] = status_text(
                    _q(sg, (kind, mode, "max-raw"), "reconstructed", "denoised", "mse", e26))
            rows[kind, mode] = r
    tab = pd.DataFrame(rows).T
    tab.index.names = ["signal", "threshold"]
    one_of(part, ("all", "verdicts", "normalisers"), "part")
    if part == "all":
        return tab
    norm = [c for c in _NORM_COLUMNS if c in tab.columns]
    return tab[norm] if part == "normalisers" else tab.drop(columns=norm)


def glue_signals(sg: dict[str, Any], e26: dict[str, Any] | None = None) -> dict[str, float]:
    """Glue values of the signal × rule study (keys ``lec_ws_*``).

    Parameters
    ----------
    sg, e26 : dict
        As :func:`table_signals`.

    Returns
    -------
    dict of str to float
        For every signal and rule (tags ``th`` = two tones, hard; ``ss`` = slow, soft; ...): MSEs ×10⁴ of
        every sensor raw / denoised / reconstructed, their error and temporal variances ×10⁴, the RMS
        gain errors of the maximum (and of the median and the raw maximum) and the reconstruction's MSE with
        those normalisers; counts of (signal, rule) cells in which each question holds.
    """
    d: dict[str, tuple[float, int]] = {}
    short = {"two tones": "t", "slow": "s", "constant": "c", "HeaviSine": "h"}
    for kind in sg["signals"]:
        for mode in sg["modes"]:
            c = cell(sg, e26, (kind, mode, "max"))
            tag = f"{short[kind]}{mode[0]}"
            for j in range(len(sg["gains"])):
                for k in ("raw", "denoised", "reconstructed"):
                    d[f"ws_{tag}_{k[:3]}_{j + 1}"] = (1e4 * c[k]["mse"][:, j].mean(), 2)
                    d[f"ws_{tag}_v{k[:3]}_{j + 1}"] = (1e4 * c[k]["evar"][:, j].mean(), 2)
                    if "tvar" in c[k]:
                        d[f"ws_{tag}_t{k[:3]}_{j + 1}"] = (1e4 * c[k]["tvar"][:, j].mean(), 2)
                d[f"ws_{tag}_gain_{j + 1}"] = (float(np.sqrt(np.mean(c["gain_err"][:, j] ** 2))), 4)
                for nm, short_nm in (("median", "med"), ("max-raw", "rawmax")):
                    if (kind, mode, nm) in sg["cases"]:
                        cm = cell(sg, e26, (kind, mode, nm))
                        d[f"ws_{tag}_gain{short_nm}_{j + 1}"] = (float(np.sqrt(np.mean(cm["gain_err"][:, j] ** 2))), 4)
                        d[f"ws_{tag}_{short_nm}_{j + 1}"] = (1e4 * cm["reconstructed"]["mse"][:, j].mean(), 2)
                        d[f"ws_{tag}_{short_nm}_raw_{j + 1}"] = (1e4 * cm["raw"]["mse"][:, j].mean(), 2)
                        d[f"ws_{tag}_{short_nm}_den_{j + 1}"] = (1e4 * cm["denoised"]["mse"][:, j].mean(), 2)
    out = _r(d)
    for qid, _, a, b, m in QUESTIONS:
        st = [_q(sg, (kind, mode, "max"), a, b, m, e26).status() for kind in sg["signals"] for mode in sg["modes"]]
        for s_, short_s in (("reproduced", "r"), ("contradicted", "c"), ("not distinguishable", "n")):
            out[f"lec_ws_n_{qid}_{short_s}"] = int(sum(x == s_ for x in st))
    out["lec_ws_n_cells"] = len(sg["signals"]) * len(sg["modes"])
    out["lec_ws_runs"] = int(sg["runs"])
    return out


# --------------------------------------------------------------------------- mechanism and wavelet settings
def table_mechanism(m: dict[str, Any], labels: tuple[int, ...] = (0, 6)) -> pd.DataFrame:
    """Per sensor and setting: squared-bias share of the denoised and reconstructed errors, correlation with sensor 1.

    Parameters
    ----------
    m : dict
        Result of :func:`fusion.scenarios.wavelet_sensors.mechanism_study`.
    labels : tuple of int
        Indices of the settings shown (default: the primary, hard, and the same with soft thresholding).

    Returns
    -------
    pandas.DataFrame
        Rows (setting, sensor), 3 decimals.
    """
    g, sig = m["gains"], m["sigma"]
    frames = []
    for i in labels:
        st = m["stats"][m["labels"][i]]
        frames.append(pd.DataFrame({
            "RMS relative bias, denoised": st["rms_bias"],
            "bias² / MSE, denoised": st["bias_share"],
            "bias² / MSE, reconstructed": st["bias_share_rec"],
            "error correlation with sensor 1 (denoised)": st["corr"][0],
            "the same, bias removed": st["corr_random"][0],
        }, index=pd.MultiIndex.from_product([[m["labels"][i]], [f"sensor {j + 1} (g={g[j]:g}, σ={sig[j]:g})"
                                                                   for j in range(g.size)]])))
    return pd.concat(frames).round(3)


_PRIMARY_CONFIG = {"wavelet": "db4", "level": 4, "threshold": "universal", "mode": "hard"}
_E26_NAMES = {"denoise-first": "reconstructed", "fuse-first": "fuse-first", "denoised": "denoised", "raw": "raw"}


def _is_primary(m: dict[str, Any], lab: str, e26: dict[str, Any] | None) -> bool:
    """Whether setting ``lab`` of the mechanism study is the primary reading, which E2.6 decides."""
    if e26 is None or m["kind"] != PRIMARY[0]:
        return False
    cfg = m["configs"][m["labels"].index(lab)]
    return cfg.get("transform", "dwt") == "dwt" and {k: cfg[k] for k in _PRIMARY_CONFIG} == _PRIMARY_CONFIG


def _wconj(m: dict[str, Any], lab: str, a: str, b: str, metric: str = "mse",
           e26: dict[str, Any] | None = None) -> Conjunction:
    if _is_primary(m, lab, e26):
        c = _e26_case(e26, "max")
        key = "mse" if metric == "mse" else "evar"
        return sensor_conjunction(c[_E26_NAMES[a]][key], c[_E26_NAMES[b]][key], _NAMES[a], _NAMES[b], _METRIC[metric],
                                  e26["seed"])
    src = m["err"] if metric == "mse" else m["evar"]
    e = src[lab]
    return sensor_conjunction(e[a], e[b], _NAMES[a], _NAMES[b], _METRIC[metric], m["seed"])


def table_sensitivity(m: dict[str, Any]) -> pd.DataFrame:
    """For each wavelet setting: sensor 1's MSE raw / denoised / reconstructed in both orders (×10⁴, 2 decimals).

    Parameters
    ----------
    m : dict
        Result of :func:`fusion.scenarios.wavelet_sensors.mechanism_study`.

    Returns
    -------
    pandas.DataFrame
        Numeric columns (sensor 1, the most accurate, and sensor 4, the noisiest).
    """
    rows = {}
    for lab in m["labels"]:
        e = m["err"][lab]
        rows[lab] = {
            "raw ×10⁴": 1e4 * e["raw"][:, 0].mean(), "denoised ×10⁴": 1e4 * e["denoised"][:, 0].mean(),
            "reconstructed ×10⁴": 1e4 * e["denoise-first"][:, 0].mean(),
            "fuse first ×10⁴": 1e4 * e["fuse-first"][:, 0].mean(),
            "sensor 4: denoised ×10⁴": 1e4 * e["denoised"][:, 3].mean(),
            "sensor 4: rec. ×10⁴": 1e4 * e["denoise-first"][:, 3].mean(),
        }
    tab = pd.DataFrame(rows).T.round(2)
    tab.index.name = f"sensor 1 (most accurate) unless named, {m['runs']} runs"
    return tab


def table_sensitivity_display(m: dict[str, Any], e26: dict[str, Any] | None = None, part: str = "all") -> pd.DataFrame:
    """:func:`table_sensitivity` at 2 decimals (text), with the verdicts for every sensor under each setting.

    Parameters
    ----------
    m : dict
        Result of :func:`fusion.scenarios.wavelet_sensors.mechanism_study`.
    e26 : dict, optional
        E2.6: the verdicts of the primary setting are taken from its runs (the MSE columns stay the
        mechanism study's).
    part : {"all", "numbers", "verdicts"}
        Every column, or one of the two halves that fit the page: the MSEs of :func:`table_sensitivity`, or
        the runs and the verdicts.

    Returns
    -------
    pandas.DataFrame
        The columns of :func:`table_sensitivity`, the runs behind the verdicts and, for all four sensors at
        once (paired 95 % intervals): reconstructed MSE < raw, reconstructed MSE < own denoised, lecture's
        order < fuse first.
    """
    tab = table_sensitivity(m).map(lambda v: f"{v:.2f}")
    tab["runs (verdicts)"] = [f"{e26['runs']} (E2.6: reading more-runs)" if _is_primary(m, lab, e26) else str(m["runs"])
                              for lab in m["labels"]]
    tab["every sensor: rec. < raw"] = [status_text(_wconj(m, lab, "denoise-first", "raw", e26=e26)) for lab in m["labels"]]
    tab["every sensor: rec. < own denoised"] = [status_text(_wconj(m, lab, "denoise-first", "denoised", e26=e26))
                                                for lab in m["labels"]]
    tab["every sensor: lecture's order < fuse first"] = [status_text(_wconj(m, lab, "denoise-first", "fuse-first",
                                                                            e26=e26))
                                                         for lab in m["labels"]]
    one_of(part, ("all", "numbers", "verdicts"), "part")
    num = list(table_sensitivity(m).columns)
    return tab if part == "all" else tab[num] if part == "numbers" else tab.drop(columns=num)


def figure_mechanism(m: dict[str, Any], shown: int = 256) -> Figure:
    """F2.6b: relative bias of each sensor's denoised signal (hard and soft); sensor 1's MSE under each setting.

    Parameters
    ----------
    m : dict
        Result of :func:`fusion.scenarios.wavelet_sensors.mechanism_study` (its first setting and the
        first soft one are drawn in the left panel).
    shown : int
        Samples shown in the bias panel.

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, axes = new_figure(1, 2, figsize=(7.5, 3.8))
    soft = next(lab for lab, c in zip(m["labels"], m["configs"]) if c["mode"] == "soft")
    for j in range(m["gains"].size):
        axes[0].plot(np.arange(shown), m["stats"][m["labels"][0]]["bias_curve"][j, :shown],
                     color=color(f"sensor {j + 1}"), label=f"sensor {j + 1}")
        axes[0].plot(np.arange(shown), m["stats"][soft]["bias_curve"][j, :shown], ":", lw=1,
                     color=color(f"sensor {j + 1}"))
    axes[0].set_xlabel("sample n")
    axes[0].set_ylabel("bias of denoised signal / gⱼ")
    axes[0].set_title("solid: hard, dotted: soft", fontsize=9)
    tab = table_sensitivity(m)
    pos = np.arange(len(tab))
    for off, col, key in ((-0.3, "raw ×10⁴", "raw"), (-0.1, "denoised ×10⁴", "denoised"),
                          (0.1, "reconstructed ×10⁴", "reconstructed"), (0.3, "fuse first ×10⁴", "reconstructed_fuse_first")):
        axes[1].bar(pos + off, tab[col] * 1e-4, width=0.2, color=color(key), label=METHOD_LABELS[key])
    axes[1].set_yscale("log")
    short = [f"{c['wavelet']} L{c['level']} {'univ.' if c['threshold'] == 'universal' else c['threshold']} {c['mode']}"
             + (" TI" if c.get("transform") == "swt" else "") for c in m["configs"]]
    axes[1].set_xticks(pos, short, fontsize=9, rotation=45, ha="right")
    axes[1].set_ylabel("sensor 1: MSE against g₁S")
    legend_below(fig, ncol=4)
    return fig


def glue_mechanism(m: dict[str, Any], e26: dict[str, Any] | None = None) -> dict[str, float]:
    """Glue values of the mechanism study (keys ``lec_wm_*``).

    Parameters
    ----------
    m : dict
        Result of :func:`fusion.scenarios.wavelet_sensors.mechanism_study`.
    e26 : dict, optional
        E2.6: the primary setting's verdicts and its fuse-first interval come from it.

    Returns
    -------
    dict of str to float
    """
    d: dict[str, tuple[float, int]] = {}
    soft = next(i for i, c in enumerate(m["configs"]) if c["mode"] == "soft")
    for tag, i in (("h", 0), ("s", soft)):
        st = m["stats"][m["labels"][i]]
        for j in range(m["gains"].size):
            d[f"wm_{tag}_rms_bias_{j + 1}"] = (st["rms_bias"][j], 4)
            d[f"wm_{tag}_rms_bias_rec_{j + 1}"] = (st["rms_bias_rec"][j], 4)
            d[f"wm_{tag}_curve_gap_{j + 1}"] = (float(np.sqrt(np.mean((st["bias_curve"][j] - st["bias_curve"][0]) ** 2))
                                                     / st["rms_bias"][0]), 2)
            d[f"wm_{tag}_bias_share_{j + 1}"] = (st["bias_share"][j], 2)
            d[f"wm_{tag}_bias_share_rec_{j + 1}"] = (st["bias_share_rec"][j], 2)
        d[f"wm_{tag}_corr12"] = (st["corr"][0, 1], 2)
        d[f"wm_{tag}_corr_mean"] = (st["mean_offdiag_corr"], 2)
        d[f"wm_{tag}_corr_random_mean"] = (st["mean_offdiag_corr_random"], 3)
        d[f"wm_{tag}_corr_random_maxabs"] = (float(np.max(np.abs(st["corr_random"] - np.eye(m["gains"].size)))), 3)
    for k, (period, share) in enumerate(m["bias_spectrum"][:2]):
        d[f"wm_spec_period_{k}"] = (period, 1)
        d[f"wm_spec_share_{k}"] = (share, 2)
    d["wm_spec_share_64"] = (m["bias_share_period"][64], 3)
    d["wm_band_64_d4"] = (m["tone_bands"][64][1], 3)
    d["wm_band_256_a4"] = (m["tone_bands"][256][0], 3)
    tab = table_sensitivity(m)
    for i, lab in enumerate(m["labels"]):
        d[f"wm_raw_{i}"] = (tab.iloc[i]["raw ×10⁴"], 2)
        d[f"wm_den_{i}"] = (tab.iloc[i]["denoised ×10⁴"], 2)
        d[f"wm_rec_{i}"] = (tab.iloc[i]["reconstructed ×10⁴"], 2)
        d[f"wm_ff_{i}"] = (tab.iloc[i]["fuse first ×10⁴"], 2)
    ff = _wconj(m, m["labels"][0], "fuse-first", "denoise-first", e26=e26)
    for j, (_, ev) in enumerate(ff.parts):
        mean, lo, hi = ev.interval()
        d[f"wm_ff_d_{j + 1}"], d[f"wm_ff_lo_{j + 1}"], d[f"wm_ff_hi_{j + 1}"] = (1e4 * mean, 2), (1e4 * lo, 2), (1e4 * hi, 2)
    out = _r(d)
    order = [_wconj(m, lab, "denoise-first", "fuse-first", e26=e26).status() for lab in m["labels"]]
    helps = [_wconj(m, lab, "denoise-first", "denoised", e26=e26).status() for lab in m["labels"]]
    better = [_wconj(m, lab, "denoise-first", "raw", e26=e26).status() for lab in m["labels"]]
    for name, st in (("order", order), ("helps", helps), ("better", better)):
        for s_, short in (("reproduced", "r"), ("contradicted", "c"), ("not distinguishable", "n")):
            out[f"lec_wm_n_{name}_{short}"] = int(sum(x == s_ for x in st))
    out["lec_wm_runs"] = int(m["runs"])
    out["lec_wm_n_cfg"] = len(m["labels"])
    return out


# --------------------------------------------------------------------------- 2.6 step 3: the variance "by an MA model"
#: Reader's names of the readings of step 3 (:data:`fusion.readings.wavelet.VARIANCES`, and the oracle).
VARIANCE_LABELS: dict[str, str] = {
    "batch": "variance of the residual over the estimation length (our default)",
    "running": "running variance of the residual, updated recursively (growing memory)",
    "window": "moving average (MA) of the residual's squared deviations over {w} samples, updated recursively",
    "measurement": "running variance of the normalised measurement itself",
    "equal": "equal weights (no variance; a reference, not a reading)",
    "oracle": "the true noise variances (not available in practice; a reference, not a reading)",
}


def _vlabel(v: dict[str, Any], r: str) -> str:
    return VARIANCE_LABELS[r].format(w=v["window"])


def table_variance(v: dict[str, Any]) -> pd.DataFrame:
    """Each reading of step 3: the reconstruction's MSE (×10⁴) for sensors 1 and 4, sensor 1's weight, win fraction.

    Parameters
    ----------
    v : dict
        Result of :func:`fusion.scenarios.wavelet_sensors.variance_study`.

    Returns
    -------
    pandas.DataFrame
        One row per reading (text, fixed decimals): MSE ×10⁴ of the reconstruction of sensor 1 (the
        most accurate) and sensor 4 (the noisiest), 2 decimals; sensor 1's mean weight at the last
        sample and the SD of its weight along the signal, 3 decimals; the fraction of runs in which
        sensor 1's reconstruction beats its own denoised signal, 2 decimals. The first two rows
        give the raw and denoised MSEs for reference.
    """
    last = v["gains"].size - 1
    c1, c4 = "sensor 1 ×10⁴", f"sensor {last + 1} ×10⁴"
    cw, cs, cp = "W₁ at the end", "SD of W₁ along the signal", "P(rec. < denoised), sensor 1"
    rows: dict[str, dict[str, str]] = {}
    for name, e in (("raw", v["raw"]), ("own denoised", v["denoised"])):
        rows[name] = {c1: f"{1e4 * e[:, 0].mean():.2f}", c4: f"{1e4 * e[:, last].mean():.2f}", cw: "", cs: "", cp: ""}
    for r in v["readings"]:
        e = v["err"][r]
        rows[f"reconstructed: {r}"] = {c1: f"{1e4 * e[:, 0].mean():.2f}", c4: f"{1e4 * e[:, last].mean():.2f}",
                                       cw: f"{v['w_final'][r][0]:.3f}", cs: f"{v['w_spread'][r]:.3f}",
                                       cp: f"{np.mean(e[:, 0] < v['denoised'][:, 0]):.2f}"}
    tab = pd.DataFrame(rows).T
    tab.index.name = f"MSE against gⱼS, {v['runs']} runs"
    return tab


def _vconj(v: dict[str, Any], r: str, ref: str, metric: str = "mse") -> Conjunction:
    a = v["err"][r] if metric == "mse" else v["evar"][r]
    if ref == "equal-weights":
        b, b_name = (v["err"]["equal"] if metric == "mse" else v["evar"]["equal"]), "reconstructed, equal weights"
    else:
        b = {("raw", "mse"): v["raw"], ("denoised", "mse"): v["denoised"], ("raw", "evar"): v["raw_evar"],
             ("denoised", "evar"): v["denoised_evar"]}[ref, metric]
        b_name = _NAMES[ref]
    return sensor_conjunction(a, b, f"reconstructed, {r} variance", b_name, _metric_label(v, metric), v["seed"])


def glue_variance(v: dict[str, Any]) -> dict[str, float]:
    """Glue values of the step-3 study (keys ``lec_wvar_*``).

    Parameters
    ----------
    v : dict
        Result of :func:`fusion.scenarios.wavelet_sensors.variance_study`.

    Returns
    -------
    dict of str to float
        Sensor 1's MSE ×10⁴ under each reading, its final weight, the paired differences (×10⁴)
        of the recursive readings against the batch variance with their 95 % intervals, the oracle
        weights' difference from the sensor's own denoised signal, and the statuses (every sensor) of
        the records under each reading as counts.
    """
    d: dict[str, tuple[float, int]] = {"wvar_den_1": (1e4 * v["denoised"][:, 0].mean(), 2),
                                       "wvar_raw_1": (1e4 * v["raw"][:, 0].mean(), 2),
                                       "wvar_w_true_1": (v["w_true"][0], 3)}
    for r in v["readings"]:
        d[f"wvar_rec_{r}_1"] = (1e4 * v["err"][r][:, 0].mean(), 2)
        d[f"wvar_rec_{r}_4"] = (1e4 * v["err"][r][:, 3].mean(), 2)
        d[f"wvar_w1_{r}"] = (v["w_final"][r][0], 3)
        d[f"wvar_wsd_{r}"] = (v["w_spread"][r], 3)
        if r != "batch":
            c = Comparison(v["err"][r][:, 0], v["err"]["batch"][:, 0], r, "batch", "less", "MSE", seed=v["seed"])
            mean, lo, hi = c.interval()
            d[f"wvar_d_{r}"], d[f"wvar_lo_{r}"], d[f"wvar_hi_{r}"] = (1e4 * mean, 3), (1e4 * lo, 3), (1e4 * hi, 3)
    for j in range(v["gains"].size):
        d[f"wvar_w_oracle_{j + 1}"] = (v["w_final"]["oracle"][j], 3)
        d[f"wvar_w_batch_{j + 1}"] = (v["w_final"]["batch"][j], 3)
    out = _r(d)
    readings = [r for r in v["readings"] if r not in ("equal", "oracle")]
    out["lec_wvar_n"] = len(readings)
    for name, ref in (("raw", "raw"), ("den", "denoised")):
        st = [_vconj(v, r, ref).status() for r in readings]
        for s_, short in (("reproduced", "r"), ("contradicted", "c"), ("not distinguishable", "n")):
            out[f"lec_wvar_n_{name}_{short}"] = int(sum(x == s_ for x in st))
    out["lec_wvar_window"] = int(v["window"])
    out["lec_wvar_runs"] = int(v["runs"])
    return out


def _weighting(v: dict[str, Any], r: str = "batch") -> Comparison:
    """The fused normalised signal's MSE against S/max S (×10⁻⁴): inverse-variance weights of reading ``r`` vs equal."""
    return Comparison(1e4 * np.asarray(v["fused_mse"][r]), 1e4 * np.asarray(v["fused_mse"]["equal"]),
                      f"fused Ŷ, weights from the {r} variance", "fused Ŷ, equal weights", "less",
                      "MSE of Ŷ against S/max S, ×10⁻⁴", seed=v["seed"])


def glue_weighting(v: dict[str, Any], key: str = "wwt") -> dict[str, float]:
    """Glue values of the weighting claim (keys ``lec_<key>_*``): credibility weights against equal weights.

    Parameters
    ----------
    v : dict
        Result of :func:`fusion.scenarios.wavelet_sensors.variance_study` (``"batch"`` and ``"equal"`` among
        its readings).
    key : str
        Glue prefix (``"wwt"``: the record's primary, the lecture's model; ``"wwb"``: the book's model).

    Returns
    -------
    dict of str to float
        The fused signal's MSE ×10⁴ under both weightings and their paired difference with its 95 %
        interval (×10⁴, 3 decimals); per sensor, the reconstruction's paired difference (×10⁴, 2 decimals),
        its interval, its median (×10⁴), the share of runs in which the credibility weights win and the tail
        index (R3); the number of sensors whose reconstruction is better with the credibility weights.
    """
    c = _weighting(v)
    mean, lo, hi = c.interval()
    d: dict[str, tuple[float, int]] = {"fused_batch": (1e4 * float(np.mean(v["fused_mse"]["batch"])), 3),
                                       "fused_equal": (1e4 * float(np.mean(v["fused_mse"]["equal"])), 3),
                                       "d": (mean, 3), "lo": (lo, 3), "hi": (hi, 3)}
    conj = _vconj(v, "batch", "equal-weights")
    for j, (_, ev) in enumerate(conj.parts):
        m_, l_, h_ = ev.interval()
        d[f"d_{j + 1}"], d[f"lo_{j + 1}"], d[f"hi_{j + 1}"] = (1e4 * m_, 2), (1e4 * l_, 2), (1e4 * h_, 2)
        jd = ev.judgement()
        d[f"med_{j + 1}"] = (1e4 * float(np.median(v["err"]["batch"][:, j] - v["err"]["equal"][:, j])), 2)
        d[f"win_{j + 1}"] = (float(jd.share), 3)
        d[f"tail_{j + 1}"] = (float(jd.tail_index) if np.isfinite(jd.tail_index) else float("nan"), 2)
    out = _r({f"{key}_{k}": x for k, x in d.items()})
    out[f"lec_{key}_n_better"] = int(sum(ev.status() == "reproduced" for _, ev in conj.parts))
    out[f"lec_{key}_n_worse"] = int(sum(ev.status() == "contradicted" for _, ev in conj.parts))
    return out


# --------------------------------------------------------------------------- evidence (book/claims/lecture003.yaml)
#: Reading key of each wavelet setting of the mechanism study that the signal table does not already run.
CONFIG_KEYS: dict[str, str] = {
    "haar, 4 levels, universal hard": "cfg-haar", "sym8, 4 levels, universal hard": "cfg-sym8",
    "coif3, 4 levels, universal hard": "cfg-coif3", "db4, 2 levels, universal hard": "cfg-level-2",
    "db4, 6 levels, universal hard": "cfg-level-6", "db4, 4 levels, bayes soft": "cfg-bayes-soft",
    "db4, 4 levels, universal hard, translation-invariant": "cfg-ti-hard",
    "db4, 4 levels, universal soft, translation-invariant": "cfg-ti-soft",
}

#: Reading keys of the signal × rule cells (the primary cell excluded).
SIGNAL_KEYS: dict[tuple[str, str], str] = {(k, m): f"sig-{k.lower().replace(' ', '-')}-{m}"
                                           for k in ("two tones", "slow", "constant", "HeaviSine")
                                           for m in ("hard", "soft") if (k, m) != PRIMARY[:2]}

#: Readings of step 3 (the variance of the weights) run as readings.
VARIANCE_READINGS: tuple[str, ...] = ("running", "window", "measurement")

#: The studies the evidence functions take: ``sg`` (signal table, every reading's run count), ``m26``, ``v26``,
#: ``g1`` (equal gains), ``v1`` and ``v1r`` (the variance study on equal gains, the denoised and the raw maximum) with
#: the same runs; ``e26`` (E2.6, more runs of the same noise stream).
STUDIES: tuple[str, ...] = ("sg", "m26", "v26", "g1", "e26", "v1", "v1r")


def _need(st: dict[str, Any]) -> int:
    """The common run count of the readings (that of the signal table); ValueError if a study is missing or has fewer."""
    missing = [k for k in STUDIES if st.get(k) is None]
    if missing:
        raise ValueError(f"st must hold the studies {missing}")
    runs = int(st["sg"]["runs"])
    short = [k for k in ("m26", "v26", "g1", "v1", "v1r") if int(st[k]["runs"]) < runs]
    if short:
        raise ValueError(f"st: the studies {short} have fewer runs than the signal table's {runs}")
    return runs


#: Seed of every study of chapter 03 (the scenarios' default).
SEED = 2601

#: Run count of each study of the chapter (:func:`study`): every reading's 300, E2.6's 2000 (the ``more-runs``
#: reading, whose claim-file entry states its runs).
RUNS: dict[str, int] = {"sg": 300, "m26": 300, "v26": 300, "g1": 300, "e26": 2000, "v1": 300, "v1r": 300}

#: The records' run count (the ledger's ``runs``): the default of the evidence functions.
N_RUNS = 300


def study(key: str, seed: int = SEED, runs: int | None = None) -> dict[str, Any]:
    """One study of the chapter (a key of :data:`STUDIES`) at ``seed`` and ``runs``, cached.

    ``sg``: the signal table (every signal and rule; normalisers max, max-raw, median); ``m26``: the mechanism
    study; ``v26``: the variance study (window 64); ``g1``: equal gains (normalisers max and max-raw); ``v1``, ``v1r``:
    the variance study on equal gains with the maximum of the denoised (``v1``) and of the raw signal (``v1r``);
    ``e26``: E2.6 (normalisers max, median, lsq). At :data:`SEED` and the runs of :data:`RUNS` they are the chapter's own.

    Parameters
    ----------
    key : str
        A key of :data:`STUDIES`.
    seed : int
    runs : int, optional
        Default: the chapter's (:data:`RUNS`).

    Returns
    -------
    dict
        The output of :mod:`fusion.scenarios.wavelet_sensors`'s study function (the same object on every call
        with the same arguments: do not modify it).
    """
    one_of(key, tuple(RUNS), "key")
    return _study(str(key), int(seed), int(RUNS[key] if runs is None else count(runs, "runs")))


@functools.lru_cache(maxsize=12)
def _study(key: str, seed: int, runs: int) -> dict[str, Any]:
    from fusion.scenarios import wavelet_sensors as ws

    one = {"signals": ("two tones",), "modes": ("hard",), "runs": runs, "seed": seed}
    if key == "sg":
        return ws.signal_study(normalisers=("max", "max-raw", "median"), runs=runs, seed=seed)
    if key == "m26":
        return ws.mechanism_study(runs=runs, seed=seed)
    if key == "v26":
        return ws.variance_study(window=64, runs=runs, seed=seed)
    if key == "g1":
        return ws.signal_study(normalisers=("max", "max-raw"), gains=(1, 1, 1, 1), **one)
    if key in ("v1", "v1r"):
        return ws.variance_study(window=64, runs=runs, seed=seed, gains=(1, 1, 1, 1),
                                 normaliser="max" if key == "v1" else "max-raw")
    return ws.signal_study(normalisers=("max", "median", "lsq"), **one)


_SIGNAL_CELLS = {v: k for k, v in SIGNAL_KEYS.items()}
_CONFIG_LABELS = {v: k for k, v in CONFIG_KEYS.items()}

#: Reading keys common to the three accuracy records (signals × rules, the raw maximum, equal gains, the wavelet
#: settings, step 3's variances, E2.6's extra runs), in the claim file's order.
COMMON_READINGS: tuple[str, ...] = (("book-model",) + tuple(SIGNAL_KEYS.values()) + ("raw-max", "lecture-raw-max")
                                    + tuple(CONFIG_KEYS.values())
                                    + tuple(f"var-{r}" for r in VARIANCE_READINGS) + ("more-runs",))

#: The accuracy records: record id → (a, b, metric) of their comparison, and their own extra reading.
_ACCURACY: dict[str, tuple[tuple[str, str, str], tuple[str, str, tuple[str, str, str]] | None]] = {
    "lec-wavelet-better": (("reconstructed", "raw", "evar"), ("temporal-variance", "tvar", ("constant", "hard", "max"))),
    "lec-wavelet-accurate": (("reconstructed", "raw", "mse"), None),
    "lec-wavelet-fusion-helps": (("reconstructed", "denoised", "mse"), ("metric-evar", "evar", PRIMARY)),
}

_Get = Callable[[str], dict[str, Any]]


def _accuracy_reading(rid: str, key: str, get: _Get) -> Conjunction:
    """One reading of an accuracy record; ``get`` gives a study by its key (of :data:`STUDIES`)."""
    (a, b, metric), extra = _ACCURACY[rid]
    if extra is not None and key == extra[0]:
        return _q(get("sg"), extra[2], a, b, extra[1])
    if key == "primary":  # the lecture's model Xⱼ = S + eⱼ and its formula: this set's (the denoised Yⱼ's) maximum
        return _q(get("g1"), PRIMARY, a, b, metric)
    if key == "book-model":  # the book's gains (1, 1.5, 0.8, 2) and the denoised maximum (the former primary)
        return _q(get("sg"), PRIMARY, a, b, metric)
    if key in _SIGNAL_CELLS:
        return _q(get("sg"), (*_SIGNAL_CELLS[key], "max"), a, b, metric)
    if key == "raw-max":
        return _q(get("sg"), (PRIMARY[0], PRIMARY[1], "max-raw"), a, b, metric)
    if key == "lecture-raw-max":  # the lecture's model with the maximum of the raw measurements
        return _q(get("g1"), (PRIMARY[0], PRIMARY[1], "max-raw"), a, b, metric)
    if key in _CONFIG_LABELS:
        return _wconj(get("m26"), _CONFIG_LABELS[key], "denoise-first" if a == "reconstructed" else a, b, metric)
    if key.startswith("var-") and key[4:] in VARIANCE_READINGS:
        return _vconj(get("v26"), key[4:], b, metric)
    if key == "more-runs":
        return _q(get("e26"), PRIMARY, a, b, metric)
    raise ValueError(f"settings: record {rid} has no reading {key!r}")


def _weighting_reading(key: str, get: _Get) -> Comparison | Conjunction:
    """One reading of ``lec-wavelet-weighting``: the fused Ŷ with inverse-variance weights against equal weights.

    The primary and ``every-sensor`` run the lecture's model (equal gains, the denoised maximum: ``v1``);
    ``book-model`` the book's gains (``v26``), ``lecture-raw-max`` equal gains with the raw maximum (``v1r``); the
    step-3 variance readings vary the book model, like those of the accuracy records.
    """
    if key == "primary":
        return _weighting(get("v1"))
    if key == "every-sensor":
        return _vconj(get("v1"), "batch", "equal-weights")
    if key == "book-model":
        return _weighting(get("v26"))
    if key == "lecture-raw-max":
        return _weighting(get("v1r"))
    if key.startswith("var-") and key[4:] in VARIANCE_READINGS:
        return _weighting(get("v26"), key[4:])
    raise ValueError(f"settings: record lec-wavelet-weighting has no reading {key!r}")


def _reading(rid: str, key: str, get: _Get) -> Comparison | Conjunction:
    return _weighting_reading(key, get) if rid == "lec-wavelet-weighting" else _accuracy_reading(rid, key, get)


def _keys(rid: str) -> tuple[str, ...]:
    """Every reading key of a record, ``"primary"`` first (the claim file's)."""
    if rid == "lec-wavelet-weighting":
        return ("primary", "every-sensor", "book-model", "lecture-raw-max") + tuple(f"var-{r}" for r in VARIANCE_READINGS)
    extra = _ACCURACY[rid][1]
    return ("primary",) + COMMON_READINGS + ((extra[0],) if extra else ())


def _at(rid: str, settings: Mapping[str, Any], seed: int, runs: int) -> Comparison | Conjunction:
    """Reading ``settings["reading"]`` of ``rid`` on the studies at ``seed`` and ``runs`` (:func:`study`)."""
    return _reading(rid, reading_key(settings), lambda k: study(k, seed, runs))


def ev_wavelet_better(settings: Mapping[str, Any], *, seed: int = SEED, runs: int = N_RUNS) -> Conjunction:
    """``lec-wavelet-better``: every reconstruction's error variance below its raw data's, one reading.

    Parameters
    ----------
    settings : mapping
        ``{"reading": key}``: ``"primary"`` (the default) or a reading key of the claim file.
    seed, runs : int
        The studies' seed and run count (:func:`study`; the ``more-runs`` reading is E2.6 at ``runs``).

    Returns
    -------
    Conjunction
        The reading's evidence.
    """
    return _at("lec-wavelet-better", settings, seed, runs)


def ev_wavelet_accurate(settings: Mapping[str, Any], *, seed: int = SEED, runs: int = N_RUNS) -> Conjunction:
    """``lec-wavelet-accurate``: every reconstruction's MSE below its raw data's, one reading.

    Parameters
    ----------
    settings : mapping
        ``{"reading": key}``: ``"primary"`` (the default) or a reading key of the claim file.
    seed, runs : int
        The studies' seed and run count (:func:`study`).

    Returns
    -------
    Conjunction
        The reading's evidence.
    """
    return _at("lec-wavelet-accurate", settings, seed, runs)


def ev_wavelet_fusion_helps(settings: Mapping[str, Any], *, seed: int = SEED, runs: int = N_RUNS) -> Conjunction:
    """``lec-wavelet-fusion-helps``: every reconstruction's MSE below the sensor's own denoised signal's, one reading.

    Parameters
    ----------
    settings : mapping
        ``{"reading": key}``: ``"primary"`` (the default) or a reading key of the claim file.
    seed, runs : int
        The studies' seed and run count (:func:`study`).

    Returns
    -------
    Conjunction
        The reading's evidence.
    """
    return _at("lec-wavelet-fusion-helps", settings, seed, runs)


def ev_wavelet_weighting(settings: Mapping[str, Any], *, seed: int = SEED,
                         runs: int = N_RUNS) -> Comparison | Conjunction:
    """``lec-wavelet-weighting``: the fused Ŷ with inverse-variance weights against equal weights, one reading.

    Parameters
    ----------
    settings : mapping
        ``{"reading": key}``: ``"primary"`` (the default) or a reading key of the claim file.
    seed, runs : int
        The variance study's seed and run count (:func:`study`).

    Returns
    -------
    Comparison or Conjunction
        The reading's evidence.
    """
    return _at("lec-wavelet-weighting", settings, seed, runs)


#: Record id → evidence function of chapter 03 (the ``evidence`` field of each record names the same function).
EVIDENCE = {"lec-wavelet-better": ev_wavelet_better, "lec-wavelet-accurate": ev_wavelet_accurate,
            "lec-wavelet-fusion-helps": ev_wavelet_fusion_helps, "lec-wavelet-weighting": ev_wavelet_weighting}


def evidence(st: dict[str, Any] | None = None, seed: int | None = None) -> dict[str, dict[str, Any]]:
    """Every record's evidence of chapter 03, by record id (for :func:`fusion.book.claims.build_ledger`).

    With ``seed``, every reading through its record's evidence function (:func:`fusion.book.chapters.lecture.evidence_at`:
    the functions the reseeding sweep calls) at that seed and the chapter's runs; the chapter passes :data:`SEED`,
    so the studies are those it computed with :func:`study` (cached). Without it, from the studies ``st``.

    Parameters
    ----------
    st : dict, optional
        The studies, keys :data:`STUDIES` (any run counts; those of ``m26``, ``v26`` and ``g1`` at least
        ``sg``'s). Required without ``seed``.
    seed : int, optional

    Returns
    -------
    dict
        Record id → {reading key → evidence}.
    """
    if seed is not None:
        return evidence_at({rid: N_RUNS for rid in EVIDENCE}, seed)
    _need(st or {})
    assert st is not None
    return {rid: {k: _reading(rid, k, st.__getitem__) for k in _keys(rid)} for rid in EVIDENCE}


def ledger_values(st: dict[str, Any]) -> dict[str, Any]:
    """The computed numbers the claim texts of chapter 03 quote (keys ``lec_wled_*``), also glued.

    Parameters
    ----------
    st : dict
        The chapter's studies, keys :data:`STUDIES`.

    Returns
    -------
    dict
        See the summary line.
    """
    runs = _need(st)
    n = int(np.asarray(st["sg"]["gains"]).size)
    # a claim about every sensor is contradicted if one sensor's interval lies wholly above 0: with no difference at
    # all, each does so with probability (1 − level)/2, so the group with probability 1 − (1 − (1 − level)/2)^n
    fwer = 1.0 - (1.0 - (1.0 - R.CONFIDENCE_LEVEL) / 2.0) ** n
    # the weights' exponent (illegible): the fused noise variance Σ Wⱼ²σⱼ² under Wⱼ ∝ σⱼ^(−p), p = 2 (the minimum,
    # what the lecture's 'least mean square' fusion asks for) and p = 1
    sig = np.asarray(st["sg"]["sigma"], dtype=float)
    fused = {p: float(np.sum((sig ** -p / np.sum(sig ** -p)) ** 2 * sig ** 2)) for p in (1, 2)}
    return {"lec_wled_runs": runs, "lec_wled_e26_runs": int(st["e26"]["runs"]), "lec_wled_fwer": round(fwer, 3),
            "lec_wled_sensors": n, "lec_wled_fvar_p2": round(1e4 * fused[2], 2), "lec_wled_fvar_p1": round(1e4 * fused[1], 2),
            "lec_wled_fvar_ratio": round(fused[1] / fused[2], 3)}


# --------------------------------------------------------------------------- appendix: the typical run, the length I
def typical_run(ev: Comparison | Conjunction) -> Comparison | Conjunction:
    """The sign-test form of a reading's evidence: is A better than B in more than half of the runs?

    Each paired comparison (each sensor's, for a :class:`~fusion.book.ledger.Conjunction`) becomes the indicator
    of "A beats B" in each run against one half, judged by the rulebook like every comparison (as
    :func:`sign_conjunction`): the reading's claim by the *typical* run, where the ledger reads it by the mean.

    Parameters
    ----------
    ev : Comparison or Conjunction
        A reading's evidence (:func:`evidence`), every comparison's claim "less" or "greater".

    Returns
    -------
    Comparison or Conjunction
        The same structure, each comparison replaced by its sign test.

    Raises
    ------
    ValueError
        A comparison whose claim is "equal" (no winner to count).
    """
    if isinstance(ev, Conjunction):
        return Conjunction(tuple((lab, typical_run(p)) for lab, p in ev.parts))
    if ev.claim not in ("less", "greater"):
        raise ValueError(f"a sign test needs a claim 'less' or 'greater', got {ev.claim!r}")
    a, b = np.asarray(ev.a, dtype=float), np.asarray(ev.b, dtype=float)
    won = (a < b) if ev.claim == "less" else (a > b)
    return Comparison(won.astype(float), np.full(a.size, 0.5), f"fraction of runs in which {ev.a_name} beats "
                      f"{ev.b_name}", "one half", "greater", "fraction of runs won (sign test)", seed=ev.seed)


def _least_share(ev: Comparison | Conjunction) -> float:
    """The smallest fraction of runs won over the comparisons of a sign-test evidence (:func:`typical_run`)."""
    parts = [p for _, p in ev.parts] if isinstance(ev, Conjunction) else [ev]
    return min(float(np.mean(p.a)) for p in parts)


def table_typical(ev: Mapping[str, Mapping[str, Comparison | Conjunction]]) -> pd.DataFrame:
    """Every reading of chapter 03's records by the mean (the ledger's status) and by the typical run (sign test).

    Parameters
    ----------
    ev : mapping
        Record id → {reading key → evidence}, as :func:`evidence` returns.

    Returns
    -------
    pandas.DataFrame
        One row per (record, reading): ``runs``, ``by the mean`` (the reading's status in the ledger, with the
        sensors that decide it), ``typical run (sign test)`` (:func:`typical_run`'s status, likewise) and
        ``least share of runs won`` (over the sensors, 3 decimals).
    """
    rows = []
    for rid, readings in ev.items():
        for key, e in readings.items():
            t = typical_run(e)
            txt = status_text if isinstance(e, Conjunction) else (lambda c: c.status())
            first = e.parts[0][1] if isinstance(e, Conjunction) else e
            rows.append({"record": rid, "reading": key, "runs": len(first.a), "by the mean": txt(e),
                         "typical run (sign test)": txt(t), "least share of runs won": round(_least_share(t), 3)})
    return pd.DataFrame(rows).set_index(["record", "reading"])


def glue_typical(tab: pd.DataFrame) -> dict[str, float]:
    """Counts of :func:`table_typical` (keys ``lec_wtyp_*``): where the typical run and the mean agree.

    Parameters
    ----------
    tab : pandas.DataFrame
        :func:`table_typical`'s table.

    Returns
    -------
    dict
        ``lec_wtyp_n`` (readings), ``lec_wtyp_agree`` (same status both ways), ``lec_wtyp_typ_only`` (reproduced
        by the typical run, not by the mean), ``lec_wtyp_mean_only`` (reproduced by the mean, not by the typical
        run), ``lec_wtyp_typ_r`` and ``lec_wtyp_mean_r`` (reproduced by each), ``lec_wtyp_typ_c`` (contradicted
        by the typical run).
    """
    mean = tab["by the mean"].str.split(":").str[0]
    typ = tab["typical run (sign test)"].str.split(":").str[0]
    rep_m, rep_t = mean == "reproduced", typ == "reproduced"
    return {"lec_wtyp_n": len(tab), "lec_wtyp_agree": int((mean == typ).sum()),
            "lec_wtyp_typ_only": int((rep_t & ~rep_m).sum()), "lec_wtyp_mean_only": int((rep_m & ~rep_t).sum()),
            "lec_wtyp_typ_r": int(rep_t.sum()), "lec_wtyp_mean_r": int(rep_m.sum()),
            "lec_wtyp_typ_c": int((typ == "contradicted").sum())}


#: Estimation lengths I of :func:`table_lengths` (the chapter's is 1024).
LENGTHS: tuple[int, ...] = (256, 1024, 4096)


def length_study(length: int, seed: int = SEED, runs: int = N_RUNS) -> dict[str, Any]:
    """The primary's case (the lecture's model: equal gains, two tones, hard threshold, the denoised maximum) at length I.

    Parameters
    ----------
    length : int
        Samples per signal I (>= 16).
    seed, runs : int
        As the chapter's studies (:func:`study`); at I = 1024 the runs are those of ``study("g1")``.

    Returns
    -------
    dict
        :func:`fusion.scenarios.wavelet_sensors.signal_study` of that one case.
    """
    from fusion.scenarios import wavelet_sensors as ws

    return ws.signal_study(signals=(PRIMARY[0],), modes=(PRIMARY[1],), normalisers=(PRIMARY[2],),
                           gains=(1.0, 1.0, 1.0, 1.0), length=count(length, "length", minimum=16), runs=runs, seed=seed)


def table_lengths(studies: Mapping[int, dict[str, Any]]) -> pd.DataFrame:
    """The three accuracy records' primary verdict at each estimation length I (by the mean, as the ledger).

    Parameters
    ----------
    studies : mapping
        I → :func:`length_study` at that I.

    Returns
    -------
    pandas.DataFrame
        One row per I: ``runs``, each accuracy record's status (with the sensors that decide it), the fusion
        step's status by the typical run (:func:`typical_run`) and the RMS relative error of sensor 4's normaliser
        (its maximum; 4 decimals).
    """
    rows = {}
    for n_, st in studies.items():
        r: dict[str, Any] = {"runs": int(st["runs"])}
        for rid, ((a, b, metric), _) in _ACCURACY.items():
            r[rid] = status_text(_q(st, PRIMARY, a, b, metric))
        helps = _q(st, PRIMARY, *_ACCURACY["lec-wavelet-fusion-helps"][0])
        r["lec-wavelet-fusion-helps, typical run"] = status_text(typical_run(helps))  # type: ignore[arg-type]
        ge = st["cases"][PRIMARY]["gain_err"][:, -1]
        r["RMS gain error, sensor 4"] = round(float(np.sqrt(np.mean(ge ** 2))), 4)
        rows[int(n_)] = r
    tab = pd.DataFrame(rows).T
    tab.index.name = "estimation length I"
    return tab


def glue_lengths(tab: pd.DataFrame) -> dict[str, Any]:
    """Glue values of :func:`table_lengths` (keys ``lec_wlen_*``).

    Parameters
    ----------
    tab : pandas.DataFrame
        :func:`table_lengths`'s table, with a row at the chapter's I = 1024.

    Returns
    -------
    dict
        ``lec_wlen_n`` (lengths), ``lec_wlen_min``, ``lec_wlen_ref`` (1024) and ``lec_wlen_max`` (I),
        ``lec_wlen_same`` (lengths at which all three records keep the status they have at I = 1024),
        ``lec_wlen_other_r`` (lengths at which ``lec-wavelet-better`` and ``lec-wavelet-accurate`` are both
        reproduced), and for each I ``lec_wlen_gain_<I>`` (sensor 4's RMS gain error), ``lec_wlen_helps_<I>`` and
        ``lec_wlen_helps_typ_<I>`` (the fusion step's status by the mean and by the typical run).

    Raises
    ------
    ValueError
        No row at I = 1024.
    """
    if 1024 not in tab.index:
        raise ValueError("tab must hold the chapter's I = 1024")
    recs = list(_ACCURACY)
    head = tab[recs].apply(lambda c: c.str.split(":").str[0])
    ref = tuple(head.loc[1024])
    out: dict[str, Any] = {"lec_wlen_n": len(tab), "lec_wlen_min": int(tab.index.min()), "lec_wlen_ref": 1024,
                           "lec_wlen_max": int(tab.index.max()),
                           "lec_wlen_same": int(sum(tuple(head.loc[i]) == ref for i in tab.index)),
                           "lec_wlen_other_r": int(((head[recs[0]] == "reproduced")
                                                    & (head[recs[1]] == "reproduced")).sum())}
    for i in tab.index:
        out[f"lec_wlen_gain_{int(i)}"] = float(tab.loc[i, "RMS gain error, sensor 4"])
        out[f"lec_wlen_helps_{int(i)}"] = str(tab.loc[i, "lec-wavelet-fusion-helps"])
        out[f"lec_wlen_helps_typ_{int(i)}"] = str(tab.loc[i, "lec-wavelet-fusion-helps, typical run"])
    return out
