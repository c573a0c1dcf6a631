r"""Chapter 03 (the lecture notes, section 2.6: wavelet denoising and fusion-based reconstruction).

:func:`table_26`, :func:`figure_26` and :func:`glue_26` present a study of
:func:`fusion.scenarios.lecture.wavelet_study`, the ``*_mechanism`` and ``table_sensitivity`` helpers the
study of :func:`fusion.scenarios.wavelet_sensors.mechanism_study` (glue keys prefixed ``lec_``), and :func:`claims`
builds chapter 03's part of the claims ledger of source ``lecture003``.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from fusion.book.chapters.lecture import SOURCE, _r, glue_figures, legend_below
from fusion.book.ledger import (
    Alternative,
    Claim,
    Comparison,
    Ledger,
)
from fusion.book.style import METHOD_LABELS, color, new_figure

__all__ = [
    "glue_figures",
    "table_26", "table_26_display", "figure_26", "glue_26",
    "table_mechanism", "table_sensitivity", "table_sensitivity_display", "figure_mechanism", "glue_mechanism",
    "VARIANCE_LABELS", "table_variance", "glue_variance", "variance_alternatives",
    "wavelet_alternatives", "fusion_step_claim",
    "claims",
]


# --------------------------------------------------------------------------- 2.6
def table_26(s: dict[str, Any]) -> pd.DataFrame:
    """Per-sensor MSEs and win fractions of E2.6, rounded to 5 decimals.

    Parameters
    ----------
    s : dict
        Result of :func:`fusion.scenarios.lecture.wavelet_study`.

    Returns
    -------
    pandas.DataFrame
    """
    return _table_26_exact(s).round(5)


def _table_26_exact(s: dict[str, Any]) -> pd.DataFrame:
    err, g, sig = s["err"], s["gains"], s["sigma"]
    return pd.DataFrame({f"sensor {j + 1} (g={g[j]:g}, σ={sig[j]:g})": {
        "MSE raw": err["raw"][:, j].mean(), "MSE denoised": err["denoised"][:, j].mean(),
        "MSE reconstructed (max)": err["max"][:, j].mean(),
        "MSE reconstructed (median)": err["median"][:, j].mean(),
        "MSE reconstructed (lsq)": err["lsq"][:, j].mean(),
        "P(rec < raw)": (err["max"][:, j] < err["raw"][:, j]).mean(),
        "P(rec < denoised)": (err["max"][:, j] < err["denoised"][:, j]).mean(),
        "RMS gain error of max": np.sqrt(np.mean(s["gain_err"][:, j] ** 2))} for j in range(g.size)})


def table_26_display(s: dict[str, Any]) -> pd.DataFrame:
    """:func:`table_26` for the page: MSEs ×10⁴ and fractions of runs, both at 2 decimals (text).

    Parameters
    ----------
    s : dict
        Result of :func:`fusion.scenarios.lecture.wavelet_study`.

    Returns
    -------
    pandas.DataFrame
        The rows of :func:`table_26`, MSE rows scaled by 10⁴ (relabelled) and every cell formatted.
    """
    tab = _table_26_exact(s)
    out = {}
    for row in tab.index:
        if row.startswith("MSE"):
            out[row.replace("MSE", "MSE ×10⁴", 1)] = [f"{1e4 * v:.2f}" for v in tab.loc[row]]
        else:
            out[row] = [f"{v:.2f}" if row.startswith("P(") else f"{v:.4f}" for v in tab.loc[row]]
    return pd.DataFrame(out, index=tab.columns).T


def figure_26(s: dict[str, Any], sensor: int = 3, shown: int = 300) -> Figure:
    """F2.6: raw, denoised and reconstructed signal of one sensor (run 0); MSE per sensor.

    Parameters
    ----------
    s : dict
        Result of :func:`fusion.scenarios.lecture.wavelet_study`.
    sensor : int
        Sensor shown (0-based).
    shown : int
        Number of samples shown.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from fusion.readings import wavelet as wv

    fig, axes = new_figure(1, 2, figsize=(7.5, 3.4))
    X = s["truth"] + s["noise"][0]
    rec = wv.reconstruct(X)
    sl = slice(0, shown)
    n = s["n"]
    axes[0].plot(n[sl], X[sensor, sl], color=color("raw"), lw=0.8, label=f"raw (sensor {sensor + 1})")
    axes[0].plot(n[sl], rec.denoised[sensor, sl], color=color("denoised"), label="denoised")
    axes[0].plot(n[sl], rec.reconstructed[sensor, sl], color=color("reconstructed"), label=METHOD_LABELS["reconstructed"])
    axes[0].plot(n[sl], s["truth"][sensor, sl], ":", color=color("published"), lw=1, label="true signal")
    axes[0].set_xlabel("sample n")
    pos = np.arange(s["gains"].size)
    for off, key, c in ((-0.3, "raw", "raw"), (-0.1, "denoised", "denoised"), (0.1, "max", "reconstructed"),
                        (0.3, "median", "reconstructed_median")):
        axes[1].bar(pos + off, s["err"][key].mean(axis=0), width=0.2, color=color(c),
                    label=METHOD_LABELS[c])
    axes[1].set_yscale("log")
    axes[1].set_xticks(pos, [f"sensor {j + 1}" for j in pos])
    axes[1].set_ylabel("MSE against gⱼS")
    legend_below(fig, ncol=3)
    return fig


def glue_26(s: dict[str, Any]) -> dict[str, float]:
    """Glue values of E2.6.

    Parameters
    ----------
    s : dict
        Result of :func:`fusion.scenarios.lecture.wavelet_study`.

    Returns
    -------
    dict of str to float
        Glue keys (prefixed ``lec_``) and rounded values.
    """
    tab = table_26(s)
    exact = _table_26_exact(s)
    d: dict[str, tuple[float, int]] = {}
    for j in range(tab.shape[1]):
        d[f"wv_p_beats_raw_{j + 1}"] = (tab.iloc[5, j], 4)
        d[f"wv_p_beats_den_{j + 1}"] = (tab.iloc[6, j], 4)
        d[f"wv_gainerr_{j + 1}"] = (tab.iloc[7, j], 5)
        d[f"wv_mse_den_{j + 1}"] = (1e4 * exact.iloc[1, j], 2)      # ×10⁴, as the displayed table
        d[f"wv_mse_max_{j + 1}"] = (1e4 * exact.iloc[2, j], 2)
        d[f"wv_mse_med_{j + 1}"] = (1e4 * exact.iloc[3, j], 2)
    d["wv_w1"] = (s["weights"][:, 0].mean(), 3)
    d["wv_p_med_beats_den_1"] = ((s["err"]["median"][:, 0] < s["err"]["denoised"][:, 0]).mean(), 2)
    return _r(d)


# --------------------------------------------------------------------------- 2.6 mechanism (issue 18)
def table_mechanism(m: dict[str, Any]) -> pd.DataFrame:
    """Per sensor: squared-bias share of the denoised and reconstructed errors, correlation with sensor 1 (3 decimals).

    Parameters
    ----------
    m : dict
        Result of :func:`fusion.scenarios.wavelet_sensors.mechanism_study`.

    Returns
    -------
    pandas.DataFrame
    """
    g, sig = m["gains"], m["sigma"]
    return pd.DataFrame({
        "bias² / MSE, denoised": m["bias_share"],
        "bias² / MSE, reconstructed": m["bias_share_rec"],
        "error correlation with sensor 1 (denoised)": m["corr"][0],
        "the same, bias removed": m["corr_random"][0],
    }, index=pd.Index([f"sensor {j + 1} (g={g[j]:g}, σ={sig[j]:g})" for j in range(g.size)])).round(3)


def table_sensitivity(m: dict[str, Any]) -> pd.DataFrame:
    """For each wavelet setting: sensor 1's MSE raw / denoised / reconstructed in both orders, and win fractions.

    Parameters
    ----------
    m : dict
        Result of :func:`fusion.scenarios.wavelet_sensors.mechanism_study`.

    Returns
    -------
    pandas.DataFrame
        MSEs ×10⁴ (2 decimals) and fractions of runs (2 decimals).
    """
    rows = {}
    for lab in m["labels"]:
        e = m["err"][lab]
        rows[lab] = {
            "raw ×10⁴": 1e4 * e["raw"][:, 0].mean(), "denoised ×10⁴": 1e4 * e["denoised"][:, 0].mean(),
            "reconstructed ×10⁴": 1e4 * e["denoise-first"][:, 0].mean(),
            "fuse first ×10⁴": 1e4 * e["fuse-first"][:, 0].mean(),
            "P(rec. < raw)": (e["denoise-first"][:, 0] < e["raw"][:, 0]).mean(),
            "P(rec. < denoised)": (e["denoise-first"][:, 0] < e["denoised"][:, 0]).mean(),
            "P(fuse first < rec.)": (e["fuse-first"][:, 0] < e["denoise-first"][:, 0]).mean(),
            "sensor 4: rec. ×10⁴": 1e4 * e["denoise-first"][:, 3].mean(),
            "sensor 4: fuse first ×10⁴": 1e4 * e["fuse-first"][:, 3].mean(),
        }
    tab = pd.DataFrame(rows).T.round(2)
    tab.index.name = f"sensor 1 (most accurate), {m['runs']} runs"
    return tab


def table_sensitivity_display(m: dict[str, Any]) -> pd.DataFrame:
    """:func:`table_sensitivity` for the page, every cell at 2 decimals (text, so 1 prints 1.00).

    Parameters
    ----------
    m : dict
        Result of :func:`fusion.scenarios.wavelet_sensors.mechanism_study`.

    Returns
    -------
    pandas.DataFrame
    """
    return table_sensitivity(m).map(lambda v: f"{v:.2f}")


def figure_mechanism(m: dict[str, Any], shown: int = 256) -> Figure:
    """F2.6b: relative bias of each sensor's denoised signal; sensor 1's MSE under each wavelet setting.

    Parameters
    ----------
    m : dict
        Result of :func:`fusion.scenarios.wavelet_sensors.mechanism_study`.
    shown : int
        Samples shown in the bias panel.

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, axes = new_figure(1, 2, figsize=(7.5, 3.6))
    for j in range(m["gains"].size):
        axes[0].plot(np.arange(shown), m["bias_curve"][j, :shown], color=color(f"sensor {j + 1}"), label=f"sensor {j + 1}")
    axes[0].set_xlabel("sample n")
    axes[0].set_ylabel("bias of denoised signal / gⱼ")
    tab = table_sensitivity(m)
    pos = np.arange(len(tab))
    for off, col, key in ((-0.3, "raw ×10⁴", "raw"), (-0.1, "denoised ×10⁴", "denoised"),
                          (0.1, "reconstructed ×10⁴", "reconstructed"), (0.3, "fuse first ×10⁴", "reconstructed_fuse_first")):
        axes[1].bar(pos + off, tab[col] * 1e-4, width=0.2, color=color(key), label=METHOD_LABELS[key])
    axes[1].set_yscale("log")
    short = [f"{c['wavelet']} L{c['level']} {'univ.' if c['threshold'] == 'universal' else c['threshold']} {c['mode']}"
             for c in m["configs"]]
    axes[1].set_xticks(pos, short, fontsize=9, rotation=45, ha="right")
    axes[1].set_ylabel("sensor 1: MSE against g₁S")
    legend_below(fig, ncol=4)
    return fig


def glue_mechanism(m: dict[str, Any]) -> dict[str, float]:
    """Glue values of the mechanism study (keys ``lec_wm_*``).

    Parameters
    ----------
    m : dict
        Result of :func:`fusion.scenarios.wavelet_sensors.mechanism_study`.

    Returns
    -------
    dict of str to float
    """
    d: dict[str, tuple[float, int]] = {}
    for j in range(m["gains"].size):
        d[f"wm_bias_share_{j + 1}"] = (m["bias_share"][j], 2)
        d[f"wm_bias_share_rec_{j + 1}"] = (m["bias_share_rec"][j], 2)
    d["wm_corr12"] = (m["corr"][0, 1], 2)
    d["wm_corr_mean"] = (m["mean_offdiag_corr"], 2)
    d["wm_corr_random_mean"] = (m["mean_offdiag_corr_random"], 3)
    d["wm_corr_random_maxabs"] = (float(np.max(np.abs(m["corr_random"] - np.eye(m["gains"].size)))), 3)
    tab = table_sensitivity(m)
    for i, lab in enumerate(m["labels"]):
        d[f"wm_raw_{i}"] = (tab.iloc[i]["raw ×10⁴"], 2)
        d[f"wm_den_{i}"] = (tab.iloc[i]["denoised ×10⁴"], 2)
        d[f"wm_rec_{i}"] = (tab.iloc[i]["reconstructed ×10⁴"], 2)
        d[f"wm_ff_{i}"] = (tab.iloc[i]["fuse first ×10⁴"], 2)
        d[f"wm_p_rec_den_{i}"] = (tab.iloc[i]["P(rec. < denoised)"], 2)
        d[f"wm_p_ff_{i}"] = (tab.iloc[i]["P(fuse first < rec.)"], 2)
        d[f"wm_p_rec_raw_{i}"] = (tab.iloc[i]["P(rec. < raw)"], 2)
    d["wm_p_ff_min"] = (float(tab["P(fuse first < rec.)"].min()), 2)
    # paired 95 % intervals (MSE differences ×10⁻⁴) instead of bare fractions of runs
    ff = [_wcmp(m, lab, "fuse-first", "denoise-first").interval() for lab in m["labels"]]
    counts: dict[str, int] = {}
    rd_ = [_wcmp(m, lab, "denoise-first", "denoised").interval() for lab in m["labels"]]
    d["wm_ff_d_0"], d["wm_ff_lo_0"], d["wm_ff_hi_0"] = ((ff[0][0] * 1e4, 3), (ff[0][1] * 1e4, 3), (ff[0][2] * 1e4, 3))
    counts["lec_wm_n_ff_better"] = int(sum(hi < 0 for _, _, hi in ff))
    counts["lec_wm_n_ff_tie"] = int(sum(lo <= 0 <= hi for _, lo, hi in ff))
    counts["lec_wm_n_rec_den_better"] = int(sum(hi < 0 for _, _, hi in rd_))
    counts["lec_wm_n_rec_den_worse"] = int(sum(lo > 0 for _, lo, _ in rd_))
    out = _r(d)
    out.update(counts)
    out["lec_wm_runs"] = int(m["runs"])
    out["lec_wm_n_cfg"] = len(m["labels"])
    return out


# --------------------------------------------------------------------------- 2.6 step 3: the variance "by an MA model"
#: Reader's names of the readings of step 3 (:data:`fusion.readings.wavelet.VARIANCES`).
VARIANCE_LABELS: dict[str, str] = {
    "batch": "variance of the residual over the estimation length (our default)",
    "running": "running variance of the residual, updated recursively (growing memory)",
    "window": "moving average (MA) of the residual's squared deviations over {w} samples, updated recursively",
    "measurement": "running variance of the normalised measurement itself",
    "equal": "equal weights (no variance; a reference, not a reading)",
}


def _vlabel(v: dict[str, Any], r: str) -> str:
    return VARIANCE_LABELS[r].format(w=v["window"])


def _vcmp(v: dict[str, Any], r: str, ref: str, j: int = 0) -> Comparison:
    names = {"raw": "raw", "denoised": "own denoised"}
    return Comparison(v["err"][r][:, j], v[ref][:, j], f"reconstructed, {r} variance (sensor {j + 1})",
                      f"{names[ref]} (sensor {j + 1})", "less", f"MSE against g{j + 1}S", seed=v["seed"])


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
        of the recursive readings against the batch variance with their 95 % intervals, and the
        statuses of sensor 1's two verdicts under each reading as counts.
    """
    d: dict[str, tuple[float, int]] = {"wvar_den_1": (1e4 * v["denoised"][:, 0].mean(), 2),
                                       "wvar_raw_1": (1e4 * v["raw"][:, 0].mean(), 2),
                                       "wvar_w_true_1": (v["w_true"][0], 3)}
    for r in v["readings"]:
        d[f"wvar_rec_{r}_1"] = (1e4 * v["err"][r][:, 0].mean(), 2)
        d[f"wvar_rec_{r}_4"] = (1e4 * v["err"][r][:, 3].mean(), 2)
        d[f"wvar_w1_{r}"] = (v["w_final"][r][0], 3)
        d[f"wvar_wsd_{r}"] = (v["w_spread"][r], 3)
        d[f"wvar_p_den_{r}"] = (float(np.mean(v["err"][r][:, 0] < v["denoised"][:, 0])), 2)
        d[f"wvar_p_raw_{r}"] = (float(np.mean(v["err"][r][:, 0] < v["raw"][:, 0])), 2)
        if r != "batch":
            c = Comparison(v["err"][r][:, 0], v["err"]["batch"][:, 0], r, "batch", "less", "MSE", seed=v["seed"])
            mean, lo, hi = c.interval()
            d[f"wvar_d_{r}"], d[f"wvar_lo_{r}"], d[f"wvar_hi_{r}"] = (1e4 * mean, 3), (1e4 * lo, 3), (1e4 * hi, 3)
    out = _r(d)
    readings = [r for r in v["readings"] if r != "equal"]
    st_raw = [_vcmp(v, r, "raw").status() for r in readings]
    st_den = [_vcmp(v, r, "denoised").status() for r in readings]
    out["lec_wvar_n"] = len(readings)
    out["lec_wvar_n_raw_repro"] = int(sum(s_ == "reproduced" for s_ in st_raw))
    out["lec_wvar_n_den_contra"] = int(sum(s_ == "contradicted" for s_ in st_den))
    out["lec_wvar_window"] = int(v["window"])
    out["lec_wvar_runs"] = int(v["runs"])
    return out


def variance_alternatives(v: dict[str, Any], reference: str) -> tuple[Alternative, ...]:
    """Readings of a §2.6 record on sensor 1 under each recursive reading of step 3 (not ``batch``, not ``equal``).

    Parameters
    ----------
    v : dict
        Result of :func:`fusion.scenarios.wavelet_sensors.variance_study`.
    reference : {"raw", "denoised"}
        What sensor 1's reconstruction is compared with.

    Returns
    -------
    tuple of Alternative
    """
    return tuple(Alternative("variance of the weights (step 3: 'recursively by an MA model')", _vlabel(v, r),
                             _vcmp(v, r, reference))
                 for r in v["readings"] if r not in ("batch", "equal"))


# --------------------------------------------------------------------------- claims added by issue 18
def _wcmp(m: dict[str, Any], lab: str, a: str, b: str, j: int = 0) -> Comparison:
    e = m["err"][lab]
    names = {"denoise-first": "reconstructed", "fuse-first": "fused first, then denoised", "raw": "raw",
             "denoised": "own denoised"}
    return Comparison(e[a][:, j], e[b][:, j], f"{names[a]} (sensor {j + 1})", f"{names[b]} (sensor {j + 1})", "less",
                      f"MSE against g{j + 1}S", seed=m["seed"])


def wavelet_alternatives(m: dict[str, Any], reference: str) -> tuple[Alternative, ...]:
    """Readings of a §2.6 claim on sensor 1 under every other wavelet setting and under the other order.

    Parameters
    ----------
    m : dict
        Result of :func:`fusion.scenarios.wavelet_sensors.mechanism_study`.
    reference : {"raw", "denoised"}
        What sensor 1's reconstruction is compared with.

    Returns
    -------
    tuple of Alternative
    """
    out = [Alternative("wavelet, depth, threshold rule", lab, _wcmp(m, lab, "denoise-first", reference))
           for lab in m["labels"][1:]]
    out.append(Alternative("order", f"fuse first, then denoise ({m['labels'][0]})",
                           _wcmp(m, m["labels"][0], "fuse-first", reference)))
    return tuple(out)


def fusion_step_claim(m: dict[str, Any], v: dict[str, Any] | None = None) -> Claim:
    """``lec-wavelet-fusion-helps``: the fusion step improves on denoising each sensor alone.

    Parameters
    ----------
    m : dict
        Result of :func:`fusion.scenarios.wavelet_sensors.mechanism_study`.
    v : dict, optional
        Result of :func:`fusion.scenarios.wavelet_sensors.variance_study`: the readings of step 3 as
        further alternatives.

    Returns
    -------
    Claim
        Primary: sensor 1, default wavelet; alternatives: the other sensors, settings, order and
        (with ``v``) the variance readings.
    """
    lab = m["labels"][0]
    alts = tuple(Alternative("sensor", f"sensor {j + 1}", _wcmp(m, lab, "denoise-first", "denoised", j))
                 for j in range(1, m["gains"].size)) + wavelet_alternatives(m, "denoised")
    if v is not None:
        alts += variance_alternatives(v, "denoised")
    return Claim(
        id="lec-wavelet-fusion-helps", source=SOURCE, where="§2.6, steps 3-6",
        claim="Normalising and fusing the denoised signals gives every sensor more accurate data than denoising "
              "its own measurements (the purpose the lecture gives for the fusion step).",
        published="qualitative",
        evidence=_wcmp(m, lab, "denoise-first", "denoised"),
        link="lec-wavelet-mechanism", critiques=("lec-crit-wavelet",),
        assumptions=("model Xⱼ = gⱼS + eⱼ with gains; maximum normaliser; weights from the residual variance over "
                     "the estimation length (the recursive readings of step 3 are alternatives)",
                     f"primary: sensor 1 (the most accurate) with {lab}",
                     f"mechanism: the denoising bias is shared by the sensors (relative errors correlated "
                     f"{m['mean_offdiag_corr']:.2f} on average; {m['mean_offdiag_corr_random']:.3f} once each "
                     f"sensor's bias is removed), so fusion cannot average it out"),
        alternatives=alts)


def claims(s26: dict, m26: dict | None = None, v26: dict | None = None) -> Ledger:
    r"""Chapter 03's claims of the lecture notes (source ``lecture003``, section 2.6).

    Parameters
    ----------
    s26 : dict
        Output of :func:`fusion.scenarios.lecture.wavelet_study`.
    m26 : dict, optional
        Output of :func:`fusion.scenarios.wavelet_sensors.mechanism_study` (same noise): the wavelet
        settings and the order as alternative readings, and the record ``lec-wavelet-fusion-helps``.
    v26 : dict, optional
        Output of :func:`fusion.scenarios.wavelet_sensors.variance_study` (same noise): the readings
        of step 3 ("estimate the variance recursively by an MA model") as alternatives of both records.

    Returns
    -------
    Ledger
        The claims of section 2.6 (no headline: the source's headline is in chapter 02).
    """
    L = Ledger(SOURCE, chapter="notebooks/03_lecture_wavelets")
    e26 = s26["err"]
    n_sens = e26["raw"].shape[1]

    def cmp26(j: int, ref: str = "raw") -> Comparison:
        return Comparison(e26["max"][:, j], e26[ref][:, j], f"reconstructed (sensor {j + 1})", f"{ref} (sensor {j + 1})",
                          "less", f"MSE against g{j + 1}S", seed=s26["seed"])

    L.add(Claim(
        id="lec-wavelet-better", source=SOURCE, where="§2.6",
        claim="Every sensor's reconstructed data have a smaller variance than its measurements.",
        published="qualitative",
        evidence=cmp26(0),
        link="lec-crit-wavelet", critiques=("lec-crit-wavelet",),
        assumptions=("model Xⱼ = gⱼS + eⱼ with gains (the lecture's Xⱼ = S + eⱼ leaves normalisation nothing to do)",
                     "db4, 4 levels, soft universal threshold; maximum normaliser; weights from the variance of the "
                     "normalised residual over the estimation length (step 3's recursive readings are alternatives)",
                     "primary: sensor 1, the most accurate, where the claim is hardest; every other sensor is "
                     "an alternative reading"),
        alternatives=tuple(Alternative("sensor", f"sensor {j + 1} against its raw measurements", cmp26(j))
                           for j in range(1, n_sens))
        + ((Alternative("reference", "own denoised signal (sensor 1)", cmp26(0, "denoised")),) if m26 is None
           else wavelet_alternatives(m26, "raw"))
        + (() if v26 is None else variance_alternatives(v26, "raw"))))
    if m26 is not None:
        L.add(fusion_step_claim(m26, v26))
    return L
