r"""Why the reconstruction wins or loses (:func:`fusion.scenarios.wavelet_sensors.mechanism_study`): bias,
correlation, the wavelet settings and the order of the steps.
"""

from __future__ import annotations

from fusion._counts import count, distinct, index, sequence
from fusion._docstrings import with_sections
from fusion._validation import instance_of

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from fusion._validation import one_of
from fusion.book.chapters.lecture import _holds, _lec_glue, _r, legend_below
from fusion.book.ledger import Conjunction
from fusion.book.style import METHOD_LABELS, METHOD_SHORT_LABELS, color, new_figure
from fusion.book.chapters.lecture_wavelets.verdicts import (
    PRIMARY,
    _METRIC,
    _e26_case,
    _same_setup,
    sensor_conjunction,
    status_text,
)
from fusion.scenarios.wavelet_sensors import MechanismStudy, SignalStudy
from fusion.book.glue import GlueValues
from fusion.book._few_runs import studies_runs_named
from fusion._docstrings import ParameterDocs
from fusion.book.chapters._defaults import study_defaults

__all__ = ["table_mechanism", "table_sensitivity", "table_sensitivity_display", "figure_mechanism", "glue_mechanism"]

#: Columns of :func:`table_mechanism` that its figure and glue read (issue 36: named once): the mean MSE (×10⁴) of
#: the raw, the denoised, the reconstructed and the fused-first estimate.
RAW_E4 = "raw ×10⁴"
DENOISED_E4 = "denoised ×10⁴"
RECONSTRUCTED_E4 = "reconstructed ×10⁴"
FUSE_FIRST_E4 = "fuse first ×10⁴"

#: The parameter of this module's functions, documented once.
_PARAMS = ParameterDocs({"m": "MechanismStudy\n    Result of :func:`fusion.scenarios.wavelet_sensors.mechanism_study`."})

#: The Raises section of the functions that judge the runs of ``m`` and ``e26`` (written once).
_RAISES = with_sections(raises="""TypeError
    ``m`` not a MechanismStudy, ``e26`` neither None nor a SignalStudy.
ValueError
    ``m`` or ``e26`` of fewer than :data:`~fusion.book.rulebook.MIN_RUNS` runs (rule R4: the verdicts compare
    runs), named; ``e26`` of another setup than ``m`` (other gains, sigma or signal length); ``m`` without a
    hard or a soft setting (its ``h`` keys hold the first hard one, its ``s`` keys the first soft one).""")


@_PARAMS("m")
@study_defaults("m", "labels")  # a default the study does not fit, named by the study (fuzz 34b D2)
def table_mechanism(m: MechanismStudy, labels: tuple[int, ...] = (0, 6)) -> pd.DataFrame:
    """Per sensor and setting: squared-bias share of the denoised and reconstructed errors, correlation with sensor 1.

    Parameters
    ----------
    labels : tuple of int
        Indices of the settings shown (default: the primary, hard, and the same with soft thresholding); at least
        one, distinct, each below the study's settings (a study of fewer than 7 settings needs other ``labels``:
        left at the default, the refusal names ``m`` and the default that does not fit it).

    Returns
    -------
    pandas.DataFrame
        Rows (setting, sensor), 3 decimals.

    Raises
    ------
    TypeError
        ``m`` not a MechanismStudy, ``labels`` not a sequence or an entry not an integer.
    ValueError
        ``labels`` empty, an entry not an index of the study's settings (negative included) or repeated.
    """
    instance_of(m, MechanismStudy, "m")
    labels = distinct([index(i, f"labels[{k}]", len(m.labels))
                       for k, i in enumerate(sequence(labels, "labels", minimum=1, what="setting"))], "labels")
    g, sig = m.gains, m.sigma
    frames = []
    for i in labels:
        st = m.stats[m.labels[i]]
        frames.append(pd.DataFrame({
            "RMS relative bias, denoised": st["rms_bias"],
            "bias² / MSE, denoised": st["bias_share"],
            "bias² / MSE, reconstructed": st["bias_share_rec"],
            "error correlation with sensor 1 (denoised)": st["corr"][0],
            "the same, bias removed": st["corr_random"][0],
        }, index=pd.MultiIndex.from_product([[m.labels[i]], [f"sensor {j + 1} (g={g[j]:g}, σ={sig[j]:g})"
                                                                   for j in range(g.size)]])))
    return pd.concat(frames).round(3)


_PRIMARY_CONFIG = {"wavelet": "db4", "level": 4, "threshold": "universal", "mode": "hard"}


_E26_NAMES = {"denoise-first": "reconstructed", "fuse-first": "fuse-first", "denoised": "denoised", "raw": "raw"}


def _is_primary(m: MechanismStudy, lab: str, e26: SignalStudy | None) -> bool:
    """Whether setting ``lab`` of the mechanism study is the primary reading, which E2.6 decides (the first read of
    ``e26`` by every function of this module: TypeError naming it if it is neither None nor a SignalStudy)."""
    if e26 is not None:
        instance_of(e26, SignalStudy, "e26")
        # fuzz 26d B: both studies record their setup; E2.6 read beside another one's numbers is refused
        _same_setup(e26, m.gains, m.sigma, int(m.bias_curve.shape[-1]), "m")
    if e26 is None or m.kind != PRIMARY[0]:
        return False
    cfg = m.configs[m.labels.index(lab)]
    return cfg.get("transform", "dwt") == "dwt" and {k: cfg[k] for k in _PRIMARY_CONFIG} == _PRIMARY_CONFIG


def _wconj(m: MechanismStudy, lab: str, a: str, b: str, metric: str = "mse",
           e26: SignalStudy | None = None) -> Conjunction:
    if _is_primary(m, lab, e26):
        c = _e26_case(e26, "max", "e26")
        key = "mse" if metric == "mse" else "evar"
        return sensor_conjunction(c[_E26_NAMES[a]][key], c[_E26_NAMES[b]][key], METHOD_SHORT_LABELS[a],
                                  METHOD_SHORT_LABELS[b], _METRIC[metric],
                                  e26.seed)
    src = m.err if metric == "mse" else m.evar
    e = src[lab]
    return sensor_conjunction(e[a], e[b], METHOD_SHORT_LABELS[a], METHOD_SHORT_LABELS[b], _METRIC[metric], m.seed)


@_PARAMS("m")
def table_sensitivity(m: MechanismStudy) -> pd.DataFrame:
    """For each wavelet setting: sensor 1's MSE raw / denoised / reconstructed in both orders (×10⁴, 2 decimals).

    Returns
    -------
    pandas.DataFrame
        Numeric columns (sensor 1, the most accurate, and sensor 4, the noisiest).

    Raises
    ------
    TypeError
        ``m`` not a MechanismStudy.
    ValueError
        ``m`` of fewer than 4 sensors (no sensor 4 to show), named.
    """
    instance_of(m, MechanismStudy, "m")
    return _sensitivity(m, "table_sensitivity")


def _hard_soft(m: MechanismStudy, reader: str) -> tuple[int, int]:
    """The places in ``m.configs`` of the first hard and the first soft setting, which ``reader`` draws or glues as
    "hard" and "soft" (fuzz 34b B1, D1: keyed by the setting, not by its place; a study without one of them is
    refused by name, never a StopIteration)."""
    modes = [c["mode"] for c in m.configs]
    _holds(dict.fromkeys(modes), ("hard", "soft"), "m", "threshold modes (m.configs)", reader)
    return modes.index("hard"), modes.index("soft")


def _sensitivity(m: MechanismStudy, reader: str, sensor4: bool = True) -> pd.DataFrame:
    """:func:`table_sensitivity` as read by ``reader``; without ``sensor4``, sensor 1's columns only (all that the
    figure and the glue read: a study of 3 sensors is theirs too)."""
    if sensor4:
        _holds(range(1, m.gains.size + 1), (4,), "m", "sensor", reader)
    rows = {}
    for lab in m.labels:
        e = m.err[lab]
        rows[lab] = {
            RAW_E4: 1e4 * e["raw"][:, 0].mean(), DENOISED_E4: 1e4 * e["denoised"][:, 0].mean(),
            RECONSTRUCTED_E4: 1e4 * e["denoise-first"][:, 0].mean(),
            FUSE_FIRST_E4: 1e4 * e["fuse-first"][:, 0].mean(),
        }
        if sensor4:
            rows[lab] |= {"sensor 4: denoised ×10⁴": 1e4 * e["denoised"][:, 3].mean(),
                          "sensor 4: rec. ×10⁴": 1e4 * e["denoise-first"][:, 3].mean()}
    tab = pd.DataFrame(rows).T.round(2)
    tab.index.name = f"sensor 1 (most accurate) unless named, {m.runs} runs"
    return tab


@_PARAMS("m")
@_RAISES
@studies_runs_named("m", "e26")  # rule R4 named by the study argument
def table_sensitivity_display(m: MechanismStudy, e26: SignalStudy | None = None, part: str = "all") -> pd.DataFrame:
    """:func:`table_sensitivity` at 2 decimals (text), with the verdicts for every sensor under each setting.

    A study ``m`` of fewer than 4 sensors is refused as by :func:`table_sensitivity` (ValueError naming ``m``).

    Parameters
    ----------
    e26 : SignalStudy, optional
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
    instance_of(m, MechanismStudy, "m")
    tab = _sensitivity(m, "table_sensitivity_display").map(lambda v: f"{v:.2f}")
    tab["runs (verdicts)"] = [f"{e26.runs} (E2.6: reading more-runs)" if _is_primary(m, lab, e26) else str(m.runs)
                              for lab in m.labels]
    tab["every sensor: rec. < raw"] = [status_text(_wconj(m, lab, "denoise-first", "raw", e26=e26)) for lab in m.labels]
    tab["every sensor: rec. < own denoised"] = [status_text(_wconj(m, lab, "denoise-first", "denoised", e26=e26))
                                                for lab in m.labels]
    tab["every sensor: lecture's order < fuse first"] = [status_text(_wconj(m, lab, "denoise-first", "fuse-first",
                                                                            e26=e26))
                                                         for lab in m.labels]
    part = one_of(part, ("all", "numbers", "verdicts"), "part")
    num = list(_sensitivity(m, "table_sensitivity_display").columns)
    return tab if part == "all" else tab[num] if part == "numbers" else tab.drop(columns=num)


@study_defaults("m", "shown")  # a default the study does not fit, named by the study (fuzz 34b D2)
def figure_mechanism(m: MechanismStudy, shown: int = 256) -> Figure:
    """F2.6b: relative bias of each sensor's denoised signal (hard and soft); sensor 1's MSE under each setting.

    Parameters
    ----------
    m : MechanismStudy
        Result of :func:`fusion.scenarios.wavelet_sensors.mechanism_study` (its first hard setting and its
        first soft one are drawn in the left panel; a study without both is refused).
    shown : int
        Samples shown in the bias panel (1 to the study's signal length).

    Returns
    -------
    matplotlib.figure.Figure
        Left: each sensor's relative bias over the first ``shown`` samples (solid hard, dotted soft); right: sensor 1's
        raw, denoised, reconstructed and fuse-first MSE per setting (log).

    Raises
    ------
    TypeError
        ``m`` not a MechanismStudy or ``shown`` not an integer.
    ValueError
        ``shown`` below 1 or above the study's signal length; ``m`` without a hard or a soft setting.
    """
    instance_of(m, MechanismStudy, "m")
    shown = count(shown, "shown", maximum=int(m.stats[m.labels[0]]["bias_curve"].shape[1]))
    hard, soft = (m.labels[i] for i in _hard_soft(m, "figure_mechanism"))
    fig, axes = new_figure(1, 2, figsize=(7.5, 3.8))
    for j in range(m.gains.size):
        axes[0].plot(np.arange(shown), m.stats[hard]["bias_curve"][j, :shown],
                     color=color(f"sensor {j + 1}"), label=f"sensor {j + 1}")
        axes[0].plot(np.arange(shown), m.stats[soft]["bias_curve"][j, :shown], ":", lw=1,
                     color=color(f"sensor {j + 1}"))
    axes[0].set_xlabel("sample n")
    axes[0].set_ylabel("bias of denoised signal / gⱼ")
    axes[0].set_title("solid: hard, dotted: soft", fontsize=9)
    tab = _sensitivity(m, "figure_mechanism", sensor4=False)
    pos = np.arange(len(tab))
    for off, col, key in ((-0.3, RAW_E4, "raw"), (-0.1, DENOISED_E4, "denoised"),
                          (0.1, RECONSTRUCTED_E4, "reconstructed"), (0.3, FUSE_FIRST_E4, "reconstructed_fuse_first")):
        axes[1].bar(pos + off, tab[col] * 1e-4, width=0.2, color=color(key), label=METHOD_LABELS[key])
    axes[1].set_yscale("log")
    short = [f"{c['wavelet']} L{c['level']} {'univ.' if c['threshold'] == 'universal' else c['threshold']} {c['mode']}"
             + (" TI" if c.get("transform") == "swt" else "") for c in m.configs]
    axes[1].set_xticks(pos, short, fontsize=9, rotation=45, ha="right")
    axes[1].set_ylabel("sensor 1: MSE against g₁S")
    legend_below(fig, ncol=4)
    return fig


@_PARAMS("m")
@_lec_glue
@_RAISES
@studies_runs_named("m", "e26")  # rule R4 named by the study argument
def glue_mechanism(m: MechanismStudy, e26: SignalStudy | None = None) -> GlueValues:
    """Glue values of the mechanism study (keys ``lec_wm_*``).

    Parameters
    ----------
    e26 : SignalStudy, optional
        E2.6: the primary setting's verdicts and its fuse-first interval come from it.
    """
    instance_of(m, MechanismStudy, "m")
    d: dict[str, tuple[float, int]] = {}
    hard, soft = _hard_soft(m, "glue_mechanism")
    for tag, i in (("h", hard), ("s", soft)):
        st = m.stats[m.labels[i]]
        for j in range(m.gains.size):
            d[f"wm_{tag}_rms_bias_{j + 1}"] = (st["rms_bias"][j], 4)
            d[f"wm_{tag}_rms_bias_rec_{j + 1}"] = (st["rms_bias_rec"][j], 4)
            d[f"wm_{tag}_curve_gap_{j + 1}"] = (float(np.sqrt(np.mean((st["bias_curve"][j] - st["bias_curve"][0]) ** 2))
                                                     / st["rms_bias"][0]), 2)
            d[f"wm_{tag}_bias_share_{j + 1}"] = (st["bias_share"][j], 2)
            d[f"wm_{tag}_bias_share_rec_{j + 1}"] = (st["bias_share_rec"][j], 2)
        d[f"wm_{tag}_corr12"] = (st["corr"][0, 1], 2)
        d[f"wm_{tag}_corr_mean"] = (st["mean_offdiag_corr"], 2)
        d[f"wm_{tag}_corr_random_mean"] = (st["mean_offdiag_corr_random"], 3)
        d[f"wm_{tag}_corr_random_maxabs"] = (float(np.max(np.abs(st["corr_random"] - np.eye(m.gains.size)))), 3)
    for k, (period, share) in enumerate(m.bias_spectrum[:2]):
        d[f"wm_spec_period_{k}"] = (period, 1)
        d[f"wm_spec_share_{k}"] = (share, 2)
    d["wm_spec_share_64"] = (m.bias_share_period[64], 3)
    d["wm_band_64_d4"] = (m.tone_bands[64][1], 3)
    d["wm_band_256_a4"] = (m.tone_bands[256][0], 3)
    tab = _sensitivity(m, "glue_mechanism", sensor4=False)
    for i, lab in enumerate(m.labels):
        d[f"wm_raw_{i}"] = (tab.iloc[i][RAW_E4], 2)
        d[f"wm_den_{i}"] = (tab.iloc[i][DENOISED_E4], 2)
        d[f"wm_rec_{i}"] = (tab.iloc[i][RECONSTRUCTED_E4], 2)
        d[f"wm_ff_{i}"] = (tab.iloc[i][FUSE_FIRST_E4], 2)
    ff = _wconj(m, m.labels[0], "fuse-first", "denoise-first", e26=e26)
    for j, (_, ev) in enumerate(ff.parts):
        mean, lo, hi = ev.interval()
        d[f"wm_ff_d_{j + 1}"], d[f"wm_ff_lo_{j + 1}"], d[f"wm_ff_hi_{j + 1}"] = (1e4 * mean, 2), (1e4 * lo, 2), (1e4 * hi, 2)
    out = _r(d)
    order = [_wconj(m, lab, "denoise-first", "fuse-first", e26=e26).status() for lab in m.labels]
    helps = [_wconj(m, lab, "denoise-first", "denoised", e26=e26).status() for lab in m.labels]
    better = [_wconj(m, lab, "denoise-first", "raw", e26=e26).status() for lab in m.labels]
    for name, st in (("order", order), ("helps", helps), ("better", better)):
        for s_, short in (("reproduced", "r"), ("contradicted", "c"), ("not distinguishable", "n")):
            out[f"lec_wm_n_{name}_{short}"] = int(sum(x == s_ for x in st))
    out["lec_wm_runs"] = int(m.runs)
    out["lec_wm_n_cfg"] = len(m.labels)
    return out
