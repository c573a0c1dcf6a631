r"""Chapter 03 (the lecture notes, section 2.6: wavelet denoising and fusion-based reconstruction).

:func:`table_26`, :func:`figure_26` and :func:`glue_26` present a study of
:func:`fusion.scenarios.lecture.wavelet_study` (glue keys prefixed ``lec_``), and :func:`claims`
builds chapter 03's part of the claims ledger of source ``lecture003``.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from fusion.book.chapters.lecture import SOURCE, _r, glue_figures
from fusion.book.ledger import (
    Alternative,
    Claim,
    Comparison,
    Ledger,
)
from fusion.book.style import color, new_figure

__all__ = [
    "glue_figures",
    "table_26", "figure_26", "glue_26",
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
    err, g, sig = s["err"], s["gains"], s["sigma"]
    return pd.DataFrame({f"sensor {j + 1} (g={g[j]:g}, σ={sig[j]:g})": {
        "MSE raw": err["raw"][:, j].mean(), "MSE denoised": err["denoised"][:, j].mean(),
        "MSE reconstructed (max)": err["max"][:, j].mean(),
        "MSE reconstructed (median)": err["median"][:, j].mean(),
        "MSE reconstructed (lsq)": err["lsq"][:, j].mean(),
        "P(rec < raw)": (err["max"][:, j] < err["raw"][:, j]).mean(),
        "P(rec < denoised)": (err["max"][:, j] < err["denoised"][:, j]).mean(),
        "RMS gain error of max": np.sqrt(np.mean(s["gain_err"][:, j] ** 2))} for j in range(g.size)}).round(5)


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

    fig, axes = new_figure(1, 2, figsize=(9.0, 3.4))
    X = s["truth"] + s["noise"][0]
    rec = wv.reconstruct(X)
    sl = slice(0, shown)
    n = s["n"]
    axes[0].plot(n[sl], X[sensor, sl], color=color("raw"), lw=0.8, label=f"raw (sensor {sensor + 1})")
    axes[0].plot(n[sl], rec.denoised[sensor, sl], color=color("denoised"), label="denoised")
    axes[0].plot(n[sl], rec.reconstructed[sensor, sl], color=color("reconstructed"), label="reconstructed")
    axes[0].plot(n[sl], s["truth"][sensor, sl], ":", color=color("published"), lw=1, label=f"g{sensor + 1}S")
    axes[0].set_xlabel("sample n")
    axes[0].legend(fontsize=7)
    pos = np.arange(s["gains"].size)
    for off, key, c in ((-0.3, "raw", "raw"), (-0.1, "denoised", "denoised"), (0.1, "max", "reconstructed"),
                        (0.3, "median", "reconstructed_median")):
        axes[1].bar(pos + off, s["err"][key].mean(axis=0), width=0.2, color=color(c),
                    label=key if key in ("raw", "denoised") else f"reconstructed ({key})")
    axes[1].set_yscale("log")
    axes[1].set_xticks(pos, [f"sensor {j + 1}" for j in pos])
    axes[1].set_ylabel("MSE against gⱼS")
    axes[1].legend(fontsize=7)
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
    d: dict[str, tuple[float, int]] = {}
    for j in range(tab.shape[1]):
        d[f"wv_p_beats_raw_{j + 1}"] = (tab.iloc[5, j], 4)
        d[f"wv_p_beats_den_{j + 1}"] = (tab.iloc[6, j], 4)
        d[f"wv_gainerr_{j + 1}"] = (tab.iloc[7, j], 5)
        d[f"wv_mse_den_{j + 1}"] = (tab.iloc[1, j], 5)
        d[f"wv_mse_max_{j + 1}"] = (tab.iloc[2, j], 5)
        d[f"wv_mse_med_{j + 1}"] = (tab.iloc[3, j], 5)
    d["wv_w1"] = (s["weights"][:, 0].mean(), 3)
    d["wv_p_med_beats_den_1"] = ((s["err"]["median"][:, 0] < s["err"]["denoised"][:, 0]).mean(), 2)
    return _r(d)


def claims(s26: dict) -> Ledger:
    r"""Chapter 03's claims of the lecture notes (source ``lecture003``, section 2.6).

    Parameters
    ----------
    s26 : dict
        Output of :func:`fusion.scenarios.lecture.wavelet_study`.

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
                     "db4, 4 levels, soft universal threshold; maximum normaliser",
                     "primary: sensor 1, the most accurate, where the claim is hardest; every other sensor is "
                     "an alternative reading"),
        alternatives=tuple(Alternative("sensor", f"sensor {j + 1} against its raw measurements", cmp26(j))
                           for j in range(1, n_sens))
        + (Alternative("reference", "own denoised signal (sensor 1)", cmp26(0, "denoised")),)))
    return L
