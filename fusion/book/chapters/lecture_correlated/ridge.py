r"""Section 2.5 of chapter 04, biased (ridge) estimation: E2.5's tables, figure and glue, the plug-in study and its
exact risks, the vector study.
"""

from __future__ import annotations

from fusion._results import ResultSpec, dict_of, instance, number, real_key, validated_post_init
from fusion._shown import shown
from fusion._validation import glue_part, instance_of

from dataclasses import dataclass
from collections.abc import Mapping
from typing import Any

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from fusion.book.chapters.lecture import _holds, _lec_glue, _r, legend_below
from fusion.book.style import METHOD_LABELS, METHOD_SHORT_LABELS, color, new_figure
from fusion.readings import biased as rg
from fusion.scenarios.lecture_correlated import K_LABEL, RidgeStudy
from fusion.scenarios.ridge_sensors import (
    LS,
    PLUGIN_EST,
    PLUGIN_KNOWN,
    RIDGE_CENTRALISED,
    RIDGE_DISTRIBUTED,
    PluginStudy,
    VectorStudy,
    _plugin_deltas,
    _plugin_range,
)
from fusion.book.glue import GlueValues
from fusion._docstrings import ParameterDocs, reads_results

__all__ = [
    "table_25", "table_25_display", "table_25_k", "table_25_k_display", "figure_25", "glue_25", "PluginExact", "plugin_exact",
    "table_plugin", "table_vector", "figure_plugin", "glue_plugin",
]

#: Column of :func:`table_25_k` holding k*, which :func:`table_25_k_display` rewrites (issue 36: named once).
K_STAR_VALUE = "value of k*"
#: The parameters of this module's functions, documented once.
_PARAMS = ParameterDocs({
    "s": "RidgeStudy\n    Result of :func:`fusion.scenarios.lecture_correlated.ridge_study`.",
    "p": "PluginStudy\n    Result of :func:`fusion.scenarios.ridge_sensors.plugin_study`.",
    "v": "VectorStudy\n    Result of :func:`fusion.scenarios.ridge_sensors.vector_study`.",
    "x25": "PluginExact\n    Result of :func:`plugin_exact` of ``p``: exact risks of another study (other xs, σ/√m, m or\n"
           "    tolerances) are refused naming ``x25``.",
})


@_PARAMS("s")
def table_25(s: RidgeStudy) -> pd.DataFrame:
    """Ridge against LS at m = m0 for each true x (E2.5), rounded to 4 decimals.

    Returns
    -------
    pandas.DataFrame
        Index the true x; columns k*, the MSE and reliability at k = 0 and k = 1, the largest reliability and its k.
    """
    instance_of(s, RidgeStudy, "s")
    return pd.DataFrame(s.rows).set_index("x").round(4)


def _plain(v: float, digits: int = 3) -> str:
    """``digits`` significant digits as a plain decimal (0.0000134, not 1.34e-05)."""
    return np.format_float_positional(float(v), precision=digits, unique=False, fractional=False, trim="-")


@_PARAMS("s")
def table_25_display(s: RidgeStudy) -> pd.DataFrame:
    """:func:`table_25` for the page: x as written (0.5, 1, 3, 10), values at 4 decimals, the arg-max k at 2.

    Returns
    -------
    pandas.DataFrame
        The same rows and columns as :func:`table_25`, as text.
    """
    instance_of(s, RidgeStudy, "s")
    tab = table_25(s)
    out = tab.copy().astype(object)
    for c in tab.columns:
        out[c] = [f"{v:.2f}" if c == "argmax rel k" else f"{v:.4f}" for v in tab[c]]
    out.index = pd.Index([f"{x:g}" for x in tab.index], name=tab.index.name)
    return out


@_PARAMS("s")
def table_25_k(s: RidgeStudy) -> pd.DataFrame:
    """Reliability gain of ridge at fixed k and at k* = σ²/x² over least squares (k = 0), 7 decimals.

    Returns
    -------
    pandas.DataFrame
        Rows: true value x; columns: ``LS (k = 0)`` (reliability of least squares), the gain
        (ridge minus LS reliability) for each fixed k and for ``k*``, and the value of k*.
    """
    instance_of(s, RidgeStudy, "s")
    rk = pd.DataFrame(s.rel_k)
    tab = rk.pivot(index="x", columns=K_LABEL, values="rel(k)")
    labels = [f"k = {k:g}" for k in s.ks_fixed] + ["k*"]
    rel0 = rk.groupby("x")["rel(0)"].first()
    tab = tab[labels].sub(rel0, axis=0).rename(columns=lambda c: f"{c}: gain")
    tab.insert(0, "LS (k = 0)", rel0)
    tab[K_STAR_VALUE] = rk[rk[K_LABEL] == "k*"].set_index("x")["k"]
    tab.columns.name = f"P(|error| ≤ σ/√m), m = {s.m0}"
    return tab.round(7)


@_PARAMS("s")
def table_25_k_display(s: RidgeStudy) -> pd.DataFrame:
    """:func:`table_25_k` for the page: reliabilities and gains at 7 decimals, k* at 4 significant digits (no exponent).

    Returns
    -------
    pandas.DataFrame
        The same rows and columns as :func:`table_25_k`, as strings.
    """
    instance_of(s, RidgeStudy, "s")
    tab = table_25_k(s)
    out = tab.map(lambda v: f"{v:.7f}")                      # reliabilities and gains: 7 decimals throughout
    out[K_STAR_VALUE] = [_plain(v, 4) for v in tab[K_STAR_VALUE]]  # 4 significant digits, no exponent
    return out


@_PARAMS("s")
def figure_25(s: RidgeStudy) -> Figure:
    """F2.5: MSE and reliability against k; mean ``|x̂_RE − x̂_LS|`` against m.

    Returns
    -------
    matplotlib.figure.Figure
        Three panels: MSE (log) and reliability against the ridge parameter k, one curve per true x; mean
        ``|x̂_RE − x̂_LS|`` against m (log-log) with a 1/m guide.
    """
    instance_of(s, RidgeStudy, "s")
    fig, axes = new_figure(1, 3, figsize=(7.5, 3.2))
    for j, x in enumerate(s.mse):
        axes[0].plot(s.kgrid, s.mse[x], color=color(f"sensor {j + 1}"), label=f"x = {x:g}")
        axes[1].plot(s.kgrid, s.rel[x], color=color(f"sensor {j + 1}"), label=f"x = {x:g}")
    axes[0].set_yscale("log")
    axes[0].set_xlabel("ridge parameter k")
    axes[0].set_ylabel(f"MSE (m = {s.m0}, σ = {s.sigma:g})")   # the study's σ (fuzz 26d F3)
    axes[1].set_xlabel("ridge parameter k")
    axes[1].set_ylabel("reliability P(|error| ≤ σ/√m)")
    for j, ((x, k), diffs) in enumerate(s.conv.items()):
        axes[2].loglog(s.ms, diffs, marker="o", color=color(f"sensor {j + 1}"), label=f"right panel: x = {x:g}, k = {k:g}")
    axes[2].loglog(s.ms, 10 * 2.0 / s.ms.astype(float), ":", color=color("published"), lw=0.8, label="∝ 1/m")
    axes[2].set_xlabel("measurements m")
    axes[2].set_ylabel("mean |x̂_RE − x̂_LS|")
    legend_below(fig, ncol=4)
    return fig


@_PARAMS("s")
@_lec_glue
def glue_25(s: RidgeStudy) -> GlueValues:
    """Glue values of E2.5.

    ``lec_rg_relk001_far`` is read at the study's ``x_far`` (its one true value of ``rel_k`` that is not among ``xs``).

    Raises
    ------
    TypeError
        ``s`` not a RidgeStudy.
    ValueError
        ``s`` without the true values 0.5 and 10 among its ``xs`` or the fixed k 0.01 and 0.1 among its ``ks_fixed``
        (E2.5's ``ridge_study`` has them), named.
    """
    instance_of(s, RidgeStudy, "s")
    _holds(s.mse, (0.5, 10.0), "s", "true values x", "glue_25")
    _holds(s.ks_fixed, (0.01, 0.1), "s", "fixed ridge parameters (ks_fixed)", "glue_25")
    tab = table_25(s)
    d = {"rg_bound_k1": (s.bound_k1, 3), "rg_rel1_kelvin": (s.rel1_kelvin, 6)}
    for x, key in ((0.5, "x05"), (10.0, "x10")):
        d[f"rg_rel0_{key}"] = (tab.loc[x, "rel(0)"], 4)
        d[f"rg_rel1_{key}"] = (tab.loc[x, "rel(k=1)"], 4)
        d[f"rg_mse0_{key}"] = (tab.loc[x, "MSE(0)"], 4)
        d[f"rg_mse1_{key}"] = (tab.loc[x, "MSE(k=1)"], 4)
    tk = table_25_k(s)
    far = [float(x) for x in tk.index if x not in s.mse]   # ridge_study's x_far: its one x of rel_k not among xs
    if len(far) != 1:
        raise ValueError(f"s.rel_k must hold one true value x_far beside the study's xs, got {shown(far)}")
    x_far = far[0]
    d.update({"rg_rel0": (tk["LS (k = 0)"].iloc[0], 4), "rg_relk01_x10": (tk.loc[10.0, "k = 0.1: gain"] + tk.loc[10.0, "LS (k = 0)"], 4),
              "rg_relk001_far": (tk.loc[x_far, "k = 0.01: gain"] + tk.loc[x_far, "LS (k = 0)"], 4),
              "rg_relkstar_x10": (tk.loc[10.0, "k*: gain"] + tk.loc[10.0, "LS (k = 0)"], 4),
              "rg_sd_ratio_max": (s.sd_ratio_max, 4)})
    # k* = σ²/x² minimises the MSE, not the reliability: the reliability-optimal k's gain over LS beside k*'s
    m, sig = int(s.m0), float(s.sigma)
    delta = sig / np.sqrt(m)
    rel0 = float(rg.reliability(*_bias_sd(m, sig, 1.0, 0.0), delta))
    for x in (1.0, 3.0):
        ks = np.geomspace(1e-4, 1e3, 20001) * rg.optimal_ridge_k(sig, x)
        rel = rg.reliability(*_bias_sd(m, sig, x, ks), delta)
        d[f"rg_bestk_gain_x{x:g}"] = (float(np.max(rel)) - rel0, 5)
        d[f"rg_kstar_gain_x{x:g}"] = (float(rg.reliability(*_bias_sd(m, sig, x, rg.optimal_ridge_k(sig, x)), delta))
                                      - rel0, 5)
    out = _r(d)
    out["lec_rg_m0"] = int(s.m0)
    return out


def _bias_sd(m: int, sig: float, x: float, k: Any) -> tuple[Any, Any]:
    """Bias and SD of the scalar ridge estimate (:func:`fusion.readings.biased.scalar_ridge_moments`)."""
    mo = rg.scalar_ridge_moments(m, sig, x, k)
    return mo.bias, mo.sd


# --------------------------------------------------------------------------- 2.5: data-driven k, vector case (issue 18)
#: Key types of a dict keyed by a real number (a tolerance c, a true value x).
_REAL = (float, int, np.number)

#: The crossings of :func:`~fusion.readings.biased.plugin_crossings` that the tables, figure and glue read of
#: :attr:`PluginExact.known` and :attr:`PluginExact.estimated` (required by its spec, fuzz 26d E2).
_CROSSINGS = ("reliability", "mse", "variance", "peak_theta", "peak_ratio", "var_peak_theta", "var_peak_ratio",
              "ratio_0")


@dataclass(frozen=True)
class PluginExact:
    r"""The exact risk of the scalar plug-in ridge against LS at the plug-in study's settings (:func:`plugin_exact`).

    Attributes
    ----------
    known : dict of float to dict
        For each tolerance c of the study's ``deltas`` (among them c = 1, which its readers read): the crossings of
        :func:`~fusion.readings.biased.plugin_crossings` with σ known (θ in standard errors; with the variance crossing).
    estimated : dict
        The same with σ estimated (c = 1).
    ratio_at : dict of float to float
        The exact MSE ratio (σ known) at each x of the study's ``xs``.
    theta_at : dict of float to float
        Each x in standard errors.
    at : dict of (str, float) to dict of float to PluginRisk
        ``at[(key, c)][x]``: the :class:`~fusion.readings.biased.PluginRisk` of plug-in ``key`` (``PLUGIN_KNOWN`` or
        ``PLUGIN_EST`` of :mod:`fusion.scenarios.ridge_sensors`) with tolerance c at x.
    """

    known: Mapping[float, Mapping[str, float]]
    estimated: Mapping[str, float]
    ratio_at: Mapping[float, float]
    theta_at: Mapping[float, float]
    at: Mapping[tuple[str, float], Mapping[float, Any]]

    __result_spec__ = ResultSpec(
        {"known": dict_of(dict_of(number(), required=_CROSSINGS), key=_REAL,  # tolerances c > 0 (fuzz 32b D2)
                          check_key=real_key(0.0, lo_open=True), required=(1.0,)),  # c = 1, which its readers read
         "estimated": dict_of(number(), required=_CROSSINGS),
         "ratio_at": dict_of(number(positive=True), key=_REAL, check_key=real_key()),
         "theta_at": dict_of(number(nonnegative=False), key=_REAL, check_key=real_key()),  # finite x (fuzz 32b D2)
         "at": dict_of(dict_of(instance(rg.PluginRisk), key=_REAL, check_key=real_key()), key=tuple)},
        relations=(lambda v, cls: _plugin_relation(v, cls),))
    __post_init__ = validated_post_init


def _plugin_relation(values: Mapping[str, Any], cls: str) -> None:
    """``ratio_at`` and ``theta_at`` at the same true values, every risk of ``at`` at them too."""
    xs = set(values["theta_at"])
    if set(values["ratio_at"]) != xs:
        raise ValueError(f"{cls}.ratio_at must have the keys of theta_at {shown(sorted(xs))}, "
                         f"got {shown(sorted(values['ratio_at']))}")
    for key, risks in values["at"].items():
        if set(risks) != xs:
            raise ValueError(f"{cls}.at[{shown(key)}] must have the keys of theta_at {shown(sorted(xs))}, "
                             f"got {shown(sorted(risks))}")


def _exact_of(p: PluginStudy, x25: PluginExact) -> None:
    """``x25`` :func:`plugin_exact` of ``p`` (recomputed, 0.06 CPU-s): the same true values, θ = x√m/σ, tolerances and
    σ-estimated crossings (which depend on m), else a ValueError naming ``x25`` (fuzz 22b MM4-MM5: another study's
    exact risks gave a KeyError or were glued as ``p``'s)."""
    instance_of(p, PluginStudy, "p")
    instance_of(x25, PluginExact, "x25")
    own = plugin_exact(p)
    same = (set(x25.theta_at) == set(own.theta_at) and set(x25.at) == set(own.at)
            and all(np.isclose(x25.theta_at[x], own.theta_at[x], rtol=1e-12, atol=0.0) for x in own.theta_at)
            and set(x25.estimated) == set(own.estimated)
            and all(np.isclose(x25.estimated[k], own.estimated[k], rtol=1e-9, atol=0.0, equal_nan=True)
                    for k in own.estimated))
    if not same:
        raise ValueError(f"x25 must be plugin_exact(p) (p: xs {shown(list(p.xs), 80)}, m = {p.m}, σ = {p.sigma:g}, "
                         f"tolerances {shown(list(p.deltas))}), got the exact risks of another study")


def plugin_exact(p: PluginStudy) -> PluginExact:
    """The exact risk of the scalar plug-in ridge against LS (:func:`fusion.readings.biased.plugin_risk`).

    Parameters
    ----------
    p : PluginStudy
        Result of :func:`fusion.scenarios.ridge_sensors.plugin_study` (its ``m``, ``sigma``, ``deltas``, ``xs``).

    Returns
    -------
    PluginExact
        See the class's attributes.

    Raises
    ------
    ValueError
        A study whose true values are beyond ``fusion.readings.biased.PLUGIN_RANGE`` standard errors (a
        ``dataclasses.replace`` of :func:`~fusion.scenarios.ridge_sensors.plugin_study`'s result, which refuses them),
        or tolerances ``p.deltas`` above 8 (likewise).
    """
    instance_of(p, PluginStudy, "p")
    _plugin_range(np.asarray(p.xs), p.m, p.sigma, "p.xs, p.m and p.sigma")
    _plugin_deltas(np.asarray(p.deltas), "p.deltas")
    m, sig = p.m, p.sigma
    known = {c: rg.plugin_crossings(c=c) for c in p.deltas}
    theta = {x: x * np.sqrt(m) / sig for x in p.xs}
    ratio = {x: float(rg.plugin_risk(t).mse_ratio) for x, t in theta.items()}
    at = {(key, c): {x: rg.plugin_risk(t, c, None if key == PLUGIN_KNOWN else m) for x, t in theta.items()}
          for key in (PLUGIN_KNOWN, PLUGIN_EST) for c in p.deltas}
    return PluginExact(known=known, estimated=rg.plugin_crossings(c=1.0, m=m), ratio_at=ratio, theta_at=theta, at=at)


@_PARAMS("p", "x25")
@reads_results("p", "x25")
def table_plugin(p: PluginStudy, x25: PluginExact) -> pd.DataFrame:
    """MSE over LS's and reliability of the two plug-in ridges at each true x: exact, with the Monte Carlo as a check.

    Returns
    -------
    pandas.DataFrame
        Rows: true x; columns: the exact reliability of LS (2Φ(1) − 1) and, for each plug-in, its exact MSE over
        LS's and its exact reliability (quadrature), at 4 decimals; the last column is the largest absolute
        difference between these four exact values and their Monte-Carlo estimates (``p.runs`` runs).
    """
    _exact_of(p, x25)
    rows = {}
    for x in p.xs:
        r = {"LS reliability": x25.at[PLUGIN_KNOWN, 1.0][x].reliability_ls}
        gap = 0.0
        for key, short in ((PLUGIN_KNOWN, "σ known"), (PLUGIN_EST, "σ estimated")):
            ex = x25.at[key, 1.0][x]
            mc_ratio = float(p.sq[x][key].mean() / p.sq[x][LS].mean())
            mc_rel = float(p.hit[x][key].mean())
            r[f"{short}: MSE / LS"] = float(ex.mse_ratio)
            r[f"{short}: reliability"] = float(ex.reliability)
            gap = max(gap, abs(mc_ratio - float(ex.mse_ratio)), abs(mc_rel - float(ex.reliability)))
        r["Monte Carlo − exact, largest"] = gap
        rows[x] = r
    tab = pd.DataFrame(rows).T.round(4)
    tab.index.name = f"true x (σ = {p.sigma:g}, m = {p.m}; exact; MC: {p.runs} runs)"
    return tab


@_PARAMS("v")
def table_vector(v: VectorStudy) -> pd.DataFrame:
    """MSE of LS and of ridge in the ill-conditioned vector case: exact for fixed k, Monte Carlo for the plug-ins.

    Returns
    -------
    pandas.DataFrame
        One row per true x: the exact MSE of LS (tr A⁻¹) and of the centralised ridge with the best fixed k for
        that x (:func:`fusion.readings.biased.best_ridge_k`); the Monte-Carlo MSEs of LS and of the centralised
        and distributed plug-in ridges (2 decimals); that k (text, 4 significant digits).
    """
    instance_of(v, VectorStudy, "v")
    rows = {}
    for (d, sc_), e in v.sq.items():
        k, mse = rg.best_ridge_k(v.A, v.x[d, sc_])
        rows[f"{d}, |x| = {sc_:g}"] = {"LS (exact)": round(v.tr_ls, 2), "best fixed k (exact)": round(mse, 2),
                                       **{METHOD_SHORT_LABELS[k_]: round(float(e[k_].mean()), 2) for k_ in e}, "that k": _plain(k, 4)}
    tab = pd.DataFrame(rows).T
    num = [c for c in tab.columns if c != "that k"]
    tab[num] = tab[num].astype(float)
    tab.index.name = f"true x (Monte Carlo: {v.runs} runs)"
    return tab


@_PARAMS("v")
@reads_results("p", "v", "x25")
def figure_plugin(p: PluginStudy, v: VectorStudy, x25: PluginExact) -> Figure:
    """F2.5b: plug-in ridge against LS as a function of x (exact MSE ratio and reliability); the vector case.

    Parameters
    ----------
    p : PluginStudy
        Result of :func:`fusion.scenarios.ridge_sensors.plugin_study` (its exact curves).
    x25 : PluginExact
        Result of :func:`plugin_exact` (the crossings, drawn as dotted lines).

    Returns
    -------
    matplotlib.figure.Figure
        Against √m·x/σ: the exact MSE ratio to LS and the exact reliability of the plug-in ridge (σ known and
        estimated); bars of the vector case's MSE per direction and size of x.
    """
    instance_of(v, VectorStudy, "v")
    _exact_of(p, x25)
    fig, axes = new_figure(1, 3, figsize=(7.5, 3.6))
    xs = p.curve * np.sqrt(p.m) / p.sigma
    axes[0].plot(xs, p.ratio_known, color=color("ridge_plugin_known"), label=METHOD_LABELS["ridge_plugin_known"])
    axes[0].plot(xs, p.ratio_est, "--", color=color("ridge_plugin_est"), label=METHOD_LABELS["ridge_plugin_est"])
    axes[0].axhline(1.0, color=color("ls"), lw=1, label=METHOD_LABELS["ls"])
    axes[0].axvline(x25.known[1.0]["mse"], color=color("published"), ls=":", lw=0.8)
    axes[0].set_xlabel("√m·x/σ")
    axes[0].set_ylabel("MSE / MSE of LS (exact)")
    for key, ls in ((LS, "-"), (PLUGIN_KNOWN, "-"), (PLUGIN_EST, "--")):
        axes[1].plot(xs, p.rel_curve[key], ls, color=color(key), lw=1 if key == LS else 1.5)
    axes[1].axvline(x25.known[1.0]["reliability"], color=color("published"), ls=":", lw=0.8)
    axes[1].set_xlabel("√m·x/σ")
    axes[1].set_ylabel("P(|error| ≤ σ/√m) (exact)")
    tab = table_vector(v)
    pos = np.arange(len(tab))
    for off, key in ((-0.27, LS), (0.0, RIDGE_CENTRALISED), (0.27, RIDGE_DISTRIBUTED)):
        axes[2].bar(pos + off, tab[METHOD_SHORT_LABELS[key]], width=0.27, color=color(key), label=METHOD_LABELS[key])
    axes[2].set_xticks(pos, [f"{d[0].upper()}\n{s:g}" for d, s in v.sq], fontsize=9)
    axes[2].set_xlabel("direction of x and |x|")
    axes[2].set_ylabel("MSE (vector case)")
    legend_below(fig, ncol=2)
    return fig


@_PARAMS("p", "v", "x25")
@reads_results("p", "v", "x25")
def glue_plugin(p: PluginStudy, v: VectorStudy, x25: PluginExact) -> GlueValues:
    """Glue values of the plug-in and vector studies (keys ``lec_rp_*``); every scalar value is exact.

    Returns
    -------
    GlueValues
        Scalar case (exact, quadrature): reliabilities and MSEs (σ² units) of LS and the plug-ins at each x, the
        MSE ratio, the crossings (reliability, MSE, variance) and peaks, and the plug-in minus LS reliability for
        each tolerance; vector case: the exact LS MSE, the exact MSE with the best fixed k and its ratio to LS,
        and the Monte-Carlo MSEs of the plug-ins.
    """
    instance_of(v, VectorStudy, "v")
    _exact_of(p, x25)
    d: dict[str, tuple[float, int]] = {}
    mse_ls = p.sigma ** 2 / p.m
    for x in p.xs:
        key = glue_part(x)
        for k, short in ((PLUGIN_KNOWN, "pk"), (PLUGIN_EST, "pe")):
            ex = x25.at[k, 1.0][x]
            d[f"rp_mse_{short}_{key}"] = (float(ex.mse_ratio) * mse_ls, 4)
            d[f"rp_rel_{short}_{key}"] = (float(ex.reliability), 4)
        d[f"rp_mse_ls_{key}"] = (mse_ls, 4)
        d[f"rp_rel_ls_{key}"] = (x25.at[PLUGIN_KNOWN, 1.0][x].reliability_ls, 4)
        d[f"rp_ratio_exact_{key}"] = (x25.ratio_at[x], 4)
        d[f"rp_theta_{key}"] = (x25.theta_at[x], 2)
        for c in p.deltas:
            ck = glue_part(c)
            ex = x25.at[PLUGIN_KNOWN, c][x]
            d[f"rp_dd_c{ck}_{key}"] = (float(ex.reliability) - ex.reliability_ls, 4)
    k1, ke = x25.known[1.0], x25.estimated
    d["rp_cross_rel"], d["rp_cross_mse"] = (k1["reliability"], 2), (k1["mse"], 2)
    d["rp_cross_var"], d["rp_var_max"], d["rp_var_argmax"] = (k1["variance"], 2), (k1["var_peak_ratio"], 3), (k1["var_peak_theta"], 2)
    d["rp_ratio_max"], d["rp_ratio_argmax"], d["rp_ratio_0"] = (k1["peak_ratio"], 3), (k1["peak_theta"], 2), (k1["ratio_0"], 3)
    d["rp_est_cross_rel"], d["rp_est_cross_mse"] = (ke["reliability"], 2), (ke["mse"], 2)
    d["rp_est_ratio_max"] = (ke["peak_ratio"], 3)
    d["rp_est_cross_var"], d["rp_est_var_max"] = (ke["variance"], 2), (ke["var_peak_ratio"], 3)
    for c, cr in x25.known.items():
        d[f"rp_cross_rel_c{glue_part(c)}"] = (cr["reliability"], 2)
    d["rp_rel_ls_exact"] = (float(p.rel_curve[LS][0]), 4)
    d["rp_cond"] = (v.cond, 0)
    d["rp_v_ls_exact"] = (v.tr_ls, 2)
    tv = table_vector(v)
    for (dname, s_) in v.sq:
        key = f"{'s' if dname.startswith('strong') else 'w'}{glue_part(s_)}"
        lab = f"{dname}, |x| = {s_:g}"
        for mk, short in ((LS, "ls"), (RIDGE_CENTRALISED, "cen"), (RIDGE_DISTRIBUTED, "dis")):
            d[f"rp_v_{short}_{key}"] = (tv.loc[lab, METHOD_SHORT_LABELS[mk]], 1)
        _, best = rg.best_ridge_k(v.A, v.x[dname, s_])
        d[f"rp_v_best_{key}"] = (best, 2)
        d[f"rp_v_best_ratio_{key}"] = (best / v.tr_ls, 3)
    out = _r(d)
    out["lec_rp_runs"], out["lec_rp_v_runs"] = int(p.runs), int(v.runs)
    return out
