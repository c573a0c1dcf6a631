r"""Chapter 04 (the lecture notes, sections 2.5 and 2.7: biased estimation, correlated noise).

Each ``table_*``, ``figure_*`` and ``glue_*`` presents a study of :mod:`fusion.scenarios.lecture`
(glue keys prefixed ``lec_``), and :func:`claims` builds chapter 04's part of the claims ledger
of source ``lecture003``.
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
    Ledger,
    Proposition,
)
from fusion.book.style import color, new_figure

__all__ = [
    "glue_figures",
    "table_25", "table_25_k", "figure_25", "glue_25",
    "table_27", "figure_27", "glue_27",
    "claims",
]


# --------------------------------------------------------------------------- 2.5
def table_25(s: dict[str, Any]) -> pd.DataFrame:
    """Ridge against LS at m = m0 for each true x (E2.5), rounded to 4 decimals.

    Parameters
    ----------
    s : dict
        Result of :func:`fusion.scenarios.lecture.ridge_study`.

    Returns
    -------
    pandas.DataFrame
    """
    return pd.DataFrame(s["rows"]).set_index("x").round(4)


def table_25_k(s: dict[str, Any]) -> pd.DataFrame:
    """Reliability gain of ridge at fixed k and at k* = σ²/x² over least squares (k = 0), 7 decimals.

    Parameters
    ----------
    s : dict
        Result of :func:`fusion.scenarios.lecture.ridge_study`.

    Returns
    -------
    pandas.DataFrame
        Rows: true value x; columns: ``LS (k = 0)`` (reliability of least squares), the gain
        (ridge minus LS reliability) for each fixed k and for ``k*``, and the value of k*.
    """
    rk = pd.DataFrame(s["rel_k"])
    tab = rk.pivot(index="x", columns="k label", values="rel(k)")
    labels = [f"k = {k:g}" for k in s["ks_fixed"]] + ["k*"]
    rel0 = rk.groupby("x")["rel(0)"].first()
    tab = tab[labels].sub(rel0, axis=0).rename(columns=lambda c: f"{c}: gain")
    tab.insert(0, "LS (k = 0)", rel0)
    tab["value of k*"] = rk[rk["k label"] == "k*"].set_index("x")["k"]
    tab.columns.name = f"P(|error| ≤ σ/√m), m = {s['m0']}"
    return tab.round(7)


def figure_25(s: dict[str, Any]) -> Figure:
    """F2.5: MSE and reliability against k; mean ``|x̂_RE − x̂_LS|`` against m.

    Parameters
    ----------
    s : dict
        Result of :func:`fusion.scenarios.lecture.ridge_study`.

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, axes = new_figure(1, 3, figsize=(10.0, 3.3))
    for j, x in enumerate(s["mse"]):
        axes[0].plot(s["kgrid"], s["mse"][x], color=color(f"sensor {j + 1}"), label=f"x = {x:g}")
        axes[1].plot(s["kgrid"], s["rel"][x], color=color(f"sensor {j + 1}"), label=f"x = {x:g}")
    axes[0].set_yscale("log")
    axes[0].set_xlabel("ridge parameter k")
    axes[0].set_ylabel(f"MSE (m = {s['m0']}, σ = 1)")
    axes[1].set_xlabel("ridge parameter k")
    axes[1].set_ylabel("reliability P(|error| ≤ σ/√m)")
    axes[0].legend(fontsize=8)
    for j, ((x, k), diffs) in enumerate(s["conv"].items()):
        axes[2].loglog(s["ms"], diffs, marker="o", color=color(f"sensor {j + 1}"), label=f"x={x:g}, k={k:g}")
    axes[2].loglog(s["ms"], 10 * 2.0 / s["ms"].astype(float), ":", color=color("published"), lw=0.8, label="∝ 1/m")
    axes[2].set_xlabel("measurements m")
    axes[2].set_ylabel("mean |x̂_RE − x̂_LS|")
    axes[2].legend(fontsize=7)
    return fig


def glue_25(s: dict[str, Any]) -> dict[str, float]:
    """Glue values of E2.5.

    Parameters
    ----------
    s : dict
        Result of :func:`fusion.scenarios.lecture.ridge_study`.

    Returns
    -------
    dict of str to float
        Glue keys (prefixed ``lec_``) and rounded values.
    """
    tab = table_25(s)
    d = {"rg_bound_k1": (s["bound_k1"], 3), "rg_rel1_kelvin": (s["rel1_kelvin"], 6)}
    for x, key in ((0.5, "x05"), (10.0, "x10")):
        d[f"rg_rel0_{key}"] = (tab.loc[x, "rel(0)"], 4)
        d[f"rg_rel1_{key}"] = (tab.loc[x, "rel(k=1)"], 4)
        d[f"rg_mse0_{key}"] = (tab.loc[x, "MSE(0)"], 4)
        d[f"rg_mse1_{key}"] = (tab.loc[x, "MSE(k=1)"], 4)
    tk = table_25_k(s)
    x_far = float(tk.index.max())
    d.update({"rg_rel0": (tk["LS (k = 0)"].iloc[0], 4), "rg_relk01_x10": (tk.loc[10.0, "k = 0.1: gain"] + tk.loc[10.0, "LS (k = 0)"], 4),
              "rg_relk001_far": (tk.loc[x_far, "k = 0.01: gain"] + tk.loc[x_far, "LS (k = 0)"], 4),
              "rg_relkstar_x10": (tk.loc[10.0, "k*: gain"] + tk.loc[10.0, "LS (k = 0)"], 4),
              "rg_sd_ratio_max": (s["sd_ratio_max"], 4)})
    out = _r(d)
    out["lec_rg_m0"] = int(s["m0"])
    return out


# --------------------------------------------------------------------------- 2.7
def table_27(s: dict[str, Any]) -> pd.DataFrame:
    """Operation counts of the three GLS routes, with ratios to LDLᵀ (2 decimals).

    Parameters
    ----------
    s : dict
        Result of :func:`fusion.scenarios.lecture.correlated_study`.

    Returns
    -------
    pandas.DataFrame
    """
    tab = pd.DataFrame(s["flops"]).set_index("Nm").rename(columns={
        "explicit": "explicit R⁻¹", "cholesky": "Cholesky (cho_solve)", "ldl": "LDLᵀ pseudo-measurements"})
    tab["explicit / LDLᵀ"] = tab["explicit R⁻¹"] / tab["LDLᵀ pseudo-measurements"]
    tab["Cholesky / LDLᵀ"] = tab["Cholesky (cho_solve)"] / tab["LDLᵀ pseudo-measurements"]
    tab = tab.round(2)
    counts = ["explicit R⁻¹", "Cholesky (cho_solve)", "LDLᵀ pseudo-measurements"]
    tab[counts] = tab[counts].round().astype(int)  # operation counts are shown as integers
    return tab


def figure_27(s: dict[str, Any], shown: int = 2000) -> Figure:
    """F2.7: errors with claimed 2σ ellipses; NEES histograms against χ²₂.

    Parameters
    ----------
    s : dict
        Result of :func:`fusion.scenarios.lecture.correlated_study`.
    shown : int
        Number of runs drawn in the scatter.

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, axes = new_figure(1, 2, figsize=(8.5, 3.4))
    for e, nm, c in ((s["eg"], "GLS = LDLᵀ", "gls"), (s["en"], "naive (correlation ignored)", "naive")):
        axes[0].scatter(e[0, :shown], e[1, :shown], s=2, alpha=0.3, color=color(c), label=nm)
    t = np.linspace(0, 2 * np.pi, 200)
    for P, c, ls in ((s["Pg"], "gls", "-"), (s["Pn"], "naive", "--")):
        ell = np.linalg.cholesky(P) @ np.vstack([np.cos(t), np.sin(t)]) * 2
        axes[0].plot(ell[0], ell[1], ls, color=color(c))
    axes[0].set_aspect("equal")
    axes[0].set_xlabel("error in x₁")
    axes[0].set_ylabel("error in x₂")
    axes[0].legend(fontsize=7, loc="upper left")
    axes[0].set_title("errors and claimed 2σ ellipses")
    bins = np.linspace(0, 20, 60)
    for smp, c, lab in zip(s["nees_samples"], ("gls", "naive"), ("GLS", "naive")):
        axes[1].hist(smp, bins, density=True, alpha=0.5, color=color(c), label=lab)
    axes[1].plot(bins, 0.5 * np.exp(-bins / 2), color=color("published"), lw=0.8, label="χ²₂")
    axes[1].set_xlabel("NEES")
    axes[1].legend(fontsize=8)
    return fig


def glue_27(s: dict[str, Any]) -> dict[str, float]:
    """Glue values of E2.7.

    Parameters
    ----------
    s : dict
        Result of :func:`fusion.scenarios.lecture.correlated_study`.

    Returns
    -------
    dict of str to float
        Glue keys (prefixed ``lec_``) and rounded values.
    """
    ft = table_27(s)
    out = _r({"cor_mse_gls": (s["mse_gls"], 4), "cor_tr_gls": (np.trace(s["Pg"]), 4),
              "cor_mse_naive": (s["mse_naive"], 4), "cor_tr_naive": (np.trace(s["Pn"]), 4),
              "cor_nees_gls": (s["nees_gls"], 3), "cor_nees_naive": (s["nees_naive"], 3),
              "cor_mse_ratio": (s["mse_naive"] / s["mse_gls"], 3), "cor_se_rel": (np.sqrt(2 / s["runs"]) * 2, 4),
              "cor_flop_ratio_inv_600": (ft.loc[600, "explicit / LDLᵀ"], 2),
              "cor_flop_ratio_chol_600": (ft.loc[600, "Cholesky / LDLᵀ"], 3)})
    out["lec_cor_runs"] = int(s["runs"])
    return out


def claims(s25: dict, s27: dict) -> Ledger:
    r"""Chapter 04's claims of the lecture notes (source ``lecture003``, sections 2.5 and 2.7).

    Parameters
    ----------
    s25, s27 : dict
        Outputs of :func:`fusion.scenarios.lecture.ridge_study` and ``correlated_study``.

    Returns
    -------
    Ledger
        The claims of sections 2.5 and 2.7 (no headline: the source's headline is in chapter 02).
    """
    L = Ledger(SOURCE, chapter="notebooks/04_lecture_biased_correlated")
    rk = pd.DataFrame(s25["rel_k"])

    def ridge_prop(label: str) -> Proposition:
        r = rk[rk["k label"] == label]
        ok = bool(np.all(r["rel(k)"] > r["rel(0)"]))
        fails = [f"{x:g}" for x, a, b in zip(r["x"], r["rel(k)"], r["rel(0)"]) if not a > b]
        return Proposition(ok, f"reliability P(|error| ≤ σ/√m), m = {s25['m0']}, ridge vs LS: " + ", ".join(
            f"x = {x:g}{f' (k = {k:.3g})' if label == 'k*' else ''}: {a:.7f} vs {b:.7f}"
            for x, k, a, b in zip(r["x"], r["k"], r["rel(k)"], r["rel(0)"]))
            + (f"; fails at x = {', '.join(fails)}" if fails else ""))

    x_list = ", ".join(f"{x:g}" for x in dict.fromkeys(rk["x"]))
    L.add(Claim(
        id="lec-ridge-reliable", source=SOURCE, where="§2.5",
        claim="Biased (ridge) measurement, with a suitably small ridge parameter (a small bias), is more reliable "
              "than unbiased (least-squares) measurement.",
        published="qualitative",
        evidence=ridge_prop("k*"),
        link="lec-crit-ridge", critiques=("lec-crit-ridge",),
        assumptions=("reliability = P(|x̂ − x| ≤ σ/√m) (undefined in the lecture)",
                     f"m = {s25['m0']}, σ = 1, x ∈ {{{x_list}}} (273.65: 0.5 °C in kelvin)",
                     "k = k* = σ²/x², the MSE-optimal ridge parameter (Hoerl & Kennard 1970): small for large |x|, "
                     "but it needs the unknown x, so this reading shows that a helpful k exists, not how to choose it"),
        alternatives=tuple(Alternative("ridge parameter", f"fixed {lab} for every x", ridge_prop(lab))
                           for lab in (f"k = {k:g}" for k in s25["ks_fixed"])),
        bound="for fixed k, ridge beats LS in MSE iff x² < σ²(2m + k)/(km); some k > 0 always does (k < 2σ²/x² suffices "
              "when mx² > σ²)"))
    L.add(Claim(
        id="lec-ridge-variance", source=SOURCE, where="§2.5",
        claim="Ridge estimation reduces the variance of the estimate (at the price of a known, fixed bias).",
        published="qualitative",
        evidence=Proposition(bool(s25["sd_ratio_max"] < 1 and s25["var_gap_min_eig"] > 0),
                             f"scalar: SD(k)/SD(0) = m/(m + k) ≤ {s25['sd_ratio_max']:.4f} for k ∈ [0.01, 5]; vector "
                             f"(three sensors, centralised): Cov_LS − Cov_RE(k) positive definite for k ∈ "
                             f"{{{', '.join(f'{k:g}' for k in s25['ks_fixed'])}}}, smallest eigenvalue "
                             f"{s25['var_gap_min_eig']:.2e} of the largest of Cov_LS"),
        link="lec-ridge",
        bound="Cov_RE = (A + kI)⁻¹A(A + kI)⁻¹ ≤ A⁻¹ = Cov_LS for every k > 0 (A = Σ HᵢᵀRᵢ⁻¹Hᵢ)"))
    L.add(Claim(
        id="lec-ridge-equivalence", source=SOURCE, where="§2.5",
        claim="Centralised and distributed (unbiased) fusion are equivalent.",
        published="qualitative",
        evidence=Proposition(s25["cen_dist_maxdiff"] < 1e-12, f"identical algebraically for every k; largest difference "
                                                               f"{s25['cen_dist_maxdiff']:.1e} on a random three-sensor problem"),
        link="lec-ridge"))
    conv_ok = all(bool(np.all(np.diff(v) < 0)) for v in s25["conv"].values())
    L.add(Claim(
        id="lec-ridge-converges", source=SOURCE, where="§2.5",
        claim="Biased fusion converges to unbiased fusion.",
        published="qualitative",
        evidence=Proposition(conv_ok, "|x̂_RE − x̂_LS| = k|x̂_LS|/(m + k) decreases as 1/m (Monte Carlo, 2000 draws per point)"),
        link="lec-ridge"))
    L.add(Claim(
        id="lec-ldl-equals-gls", source=SOURCE, where="§2.7",
        claim="Fusing the LDLᵀ-decorrelated pseudo-measurements gives the Markov (GLS) estimate.",
        published="qualitative",
        evidence=Proposition(s27["rel_ldl_gls"] < 1e-12 and s27["mrm_offdiag"] < 1e-12,
                             f"identical algebraically; largest relative difference {s27['rel_ldl_gls']:.1e}, "
                             f"MRMᵀ diagonal to {s27['mrm_offdiag']:.1e}"),
        link="lec-correlated"))
    ft = table_27(s27)
    r_chol = float(ft.loc[600, "Cholesky / LDLᵀ"])
    r_inv = float(ft.loc[600, "explicit / LDLᵀ"])
    L.add(Claim(
        id="lec-ldl-cheaper", source=SOURCE, where="§2.7",
        claim="The pseudo-measurement method has greatly reduced computational complexity compared with the Markov "
              "estimate computed directly from the original measurements.",
        published="qualitative",
        evidence=Proposition(r_inv >= 2.0, f"leading operation counts at Nm = 600: {r_inv:.2f}× fewer than the Markov "
                                           f"formula with an explicit R⁻¹"),
        link="lec-crit-ldl", critiques=("lec-crit-ldl",),
        assumptions=("'greatly reduced' read as at least a factor 2 in leading operation counts",
                     "the Markov estimate 'directly from the original measurements' computed as written, "
                     "(HᵀR⁻¹H)⁻¹HᵀR⁻¹z with an explicit R⁻¹"),
        alternatives=(Alternative("baseline", "GLS with a Cholesky solve (cho_solve), as any library computes it",
                                  Proposition(r_chol >= 2.0, f"{r_chol:.3f}× fewer operations at Nm = 600: LDLᵀ is a "
                                                             f"Cholesky factorisation, no gain")),)))
    return L
