"""Chapter "The optimal fusion set" (Yang, Feng & Fan 2012): tables, figures and claims.

The notebook ``notebooks/01_optimal_fusion_set.ipynb`` calls these functions; they assemble
the published-vs-recomputed tables of the source's Tables 2-3, the audit of which printed
values can follow from Table 1, the figures of Figs. 1-4 and of the Monte-Carlo repetition,
and the claims ledger of the source.

References
----------
* Yang G. N., Feng X. F., Fan L. J. (2012). Multi-sensor data fusion algorithm based on
   optimal fusion set. *Journal of Software* 23(Suppl. 1), 134-140.
* Sun Y., Jing B. (2005). Consistent and reliable fusion of multi-sensor based on support
   degree. *Chinese Journal of Sensors and Actuators* 18(3), 537-539.
"""

from __future__ import annotations

import importlib
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
import pandas as pd
from matplotlib.figure import Figure
from numpy.typing import ArrayLike

from fusion import data
from fusion import readings as rd
from fusion._validation import FloatArray
from fusion.book import audit
from fusion.book.chapters import ofs_audit, ofs_fair
from fusion.book.claims import ClaimsFile, ReadingSpec, claims_dir
from fusion.book.claims import load as load_claims
from fusion.book.exact import ExactComparison
from fusion.book.ledger import Comparison, Conjunction, Ledger, Proposition, PublishedValues, Unverifiable
from fusion.book.style import METHOD_LABELS, color, new_figure
from fusion.book.tables import rounded, side_by_side
from fusion.readings.robust import robust_fuse
from fusion.scenarios import thermocouples
from fusion.scenarios.thermocouples import PairedStudy

__all__ = [
    "closing_numbers",
    "verdict_table",
    "not_neighbourhood_share",
    "SOURCE",
    "mc_numbers",
    "table_numbers",
    "observation_numbers",
    "METHODS",
    "TableReproduction",
    "reproduce_tables",
    "figure_readings",
    "figure_errors",
    "mc_table",
    "figure_mc",
    "figure_scale",
    "unit_dependence",
    "eq9_readings",
    "table1_by_scale",
    "FAMILIES",
    "family_values",
    "ALPHAS",
    "alpha_methods",
    "family_mae",
    "weight_ablation",
    "SEED",
    "N_RUNS",
    "NOISE",
    "SCALES",
    "CHAPTER",
    "tables",
    "joint",
    "support_table",
    "corrected_table1",
    "study",
    "alpha_study",
    "MembershipStudy",
    "membership_study",
    "fair",
    "table1_totals",
    "WeightStudy",
    "weight_study",
    "evidence",
    "claim_values",
    "ledger_numbers",
    "comparison_numbers",
]

#: BibTeX key of the source.
SOURCE = "yang2012optimal"

#: Docname of the chapter.
CHAPTER = "notebooks/01_optimal_fusion_set"

#: The three methods of the source's comparison, as :func:`fusion.readings.fusion_set.fuse_epochs` specs.
METHODS: dict[str, dict[str, object]] = {
    "optimal_fusion_set": {"method": "optimal_fusion_set"},
    "mean": {"method": "mean"},
    "support_degree": {"method": "support_degree"},
}

_TOL = 5e-5  # half a unit of the 4th printed decimal


def _fuse_subset(v: FloatArray) -> float:
    """Eqs. 6-12 applied to a given set of readings (no selection step)."""
    return rd.fusion_set_weights(v).value


@dataclass(frozen=True)
class TableReproduction:
    """Tables 2-3 of the source recomputed from its Table 1.

    Attributes
    ----------
    ofs, mean, sup : ndarray, shape (6,)
        Fused values (°C) of the optimal fusion set, the mean and the rebuilt support degree.
    table2, table3 : DataFrame
        Published beside recomputed values (:func:`fusion.book.tables.side_by_side`).
    totals : DataFrame
        Published totals, sums of the published error columns, totals recomputed from Table 1.
    audit : DataFrame
        Per observation: readings, whether the published optimal-set value is within them, the
        subsets reproducing it, and the change of the readings' sum implied by the published mean.
    alpha : DataFrame
        Per observation: the support-degree parameters α (°C⁻²) reproducing Table 3's value.
    """

    ofs: FloatArray
    mean: FloatArray
    sup: FloatArray
    table2: pd.DataFrame
    table3: pd.DataFrame
    totals: pd.DataFrame
    audit: pd.DataFrame
    alpha: pd.DataFrame


def reproduce_tables(alpha_range: tuple[float, float] = (1e-6, 1e3)) -> TableReproduction:
    """Recompute Tables 2-3 of Yang, Feng & Fan (2012) from their Table 1 and audit them.

    Parameters
    ----------
    alpha_range : (float, float)
        Range (°C⁻²) searched for support-degree parameters reproducing Table 3.

    Returns
    -------
    TableReproduction
    """
    t1 = data.YANG2012_TABLE1.values  # (3 sensors, 6 observations), °C
    t2, t3 = data.YANG2012_TABLE2.columns, data.YANG2012_TABLE3.columns
    totals = data.YANG2012_TOTALS.columns
    truth = data.YANG2012_TRUE_VALUE
    obs = np.arange(1, t1.shape[1] + 1)
    ofs = rd.fuse_epochs(t1.T, "optimal_fusion_set").values
    mean = rd.fuse_epochs(t1.T, "mean").values
    sup = rd.fuse_epochs(t1.T, "support_degree").values
    table2 = pd.concat({"optimal fusion set (°C)": side_by_side(t2["optimal_set"], ofs, obs),
                        "arithmetic mean (°C)": side_by_side(t2["mean"], mean, obs)}, axis=1)
    table3 = pd.concat({"support degree (°C)": side_by_side(t3["reliability"], sup, obs)}, axis=1)
    tot = pd.DataFrame(
        {"published total": [totals["optimal_set"][0], totals["mean"][0], totals["reliability"][0]],
         "sum of published errors": [t2["optimal_set_abs_error"].sum(), t2["mean_abs_error"].sum(),
                                     t3["reliability_abs_error"].sum()],
         "recomputed from Table 1": [np.abs(v - truth).sum() for v in (ofs, mean, sup)]},
        index=pd.Index(["optimal fusion set", "arithmetic mean", "support degree (rebuilt)"], name="method"),
    ).round(4)
    audit_rows, alpha_rows = [], []
    for k in range(t1.shape[1]):
        x = t1[:, k]
        matches = audit.matching_subsets(x, t2["optimal_set"][k], _TOL, _fuse_subset)
        audit_rows.append({
            "readings (°C)": ", ".join(f"{v:.1f}" for v in x),
            "published optimal set": t2["optimal_set"][k],
            "within the readings?": audit.in_convex_hull(x, t2["optimal_set"][k]),
            "subsets reproducing it": "; ".join(str(tuple(i + 1 for i in m.members)) for m in matches) or "none",
            "sum change implied by the published mean": rounded(audit.implied_sum_change(x, t2["mean"][k]), 3),
        })
        roots = audit.parameters_matching(x, t3["reliability"][k], "support_degree", "alpha", *alpha_range)
        alpha_rows.append({
            "published": t3["reliability"][k],
            "mean of readings": rounded(x.mean()),
            "ours (α = 0.25)": rounded(sup[k]),
            "α reproducing it (°C⁻²)": ", ".join(f"{a:.4g}" for a in roots) or "none",
        })
    idx = pd.Index(obs, name="observation")
    return TableReproduction(ofs=ofs, mean=mean, sup=sup, table2=table2, table3=table3, totals=tot,
                             audit=pd.DataFrame(audit_rows, index=idx), alpha=pd.DataFrame(alpha_rows, index=idx))


# --------------------------------------------------------------------------- figures
def figure_readings(readings: ArrayLike, highlight: Sequence[int] = (), window: tuple[int, int] = (50, 80),
                    truth: float = 900.0) -> Figure:
    """The source's Figs. 1 and 3: every sensor's readings against the sample number.

    Parameters
    ----------
    readings : array_like, shape (n_samples, n_sensors)
        Readings, °C.
    highlight : sequence of int
        1-based sensors drawn bold and labelled (the failing ones); the window is shaded then.
    window : (int, int)
        1-based failure window, shaded when ``highlight`` is given.
    truth : float
        True value drawn as a dotted line, °C.

    Returns
    -------
    matplotlib.figure.Figure
    """
    z = np.asarray(readings, dtype=float)
    t = np.arange(1, z.shape[0] + 1)
    fig, ax = new_figure(figsize=(7.0, 3.4))
    emphasis = ("#D55E00", "#0072B2", "#009E73", "#CC79A7")   # failing sensors, Okabe-Ito
    k = 0
    for i in range(z.shape[1]):
        emph = (i + 1) in highlight
        colour = emphasis[k % len(emphasis)] if emph else "0.55"
        k += emph
        ax.plot(t, z[:, i], lw=1.4 if emph else 0.7, alpha=1.0 if emph else 0.7, color=colour,
                label=f"sensor {i + 1}" if emph else None)
    ax.axhline(truth, color=color("truth"), lw=0.8, ls=":")
    ax.set(xlabel="sample", ylabel="reading (°C)")
    if highlight:
        ax.axvspan(*window, color="0.9", zorder=0)
        ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return fig


def figure_errors(errors: Mapping[str, ArrayLike]) -> Figure:
    """The source's Figs. 2 and 4: absolute error of each method against the sample number.

    Parameters
    ----------
    errors : mapping of method name to array_like, shape (n_samples,)
        Absolute errors, °C; keys are method names of :data:`METHODS`.

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, ax = new_figure(figsize=(7.0, 3.4))
    for name, e in errors.items():
        e = np.asarray(e, dtype=float)
        ax.plot(np.arange(1, e.size + 1), e, color=color(name), label=METHOD_LABELS[name])
    ax.set(xlabel="sample", ylabel="absolute error (°C)")
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.2), ncols=2)
    return fig


def mc_table(studies: Mapping[str, PairedStudy], sigmas: Mapping[str, ArrayLike]) -> pd.DataFrame:
    """Mean absolute error of each method over runs and samples, per noise setting and case.

    Parameters
    ----------
    studies : mapping of noise label to PairedStudy
    sigmas : mapping of noise label to array_like
        Noise standard deviations (°C) of each setting, for the bound of
        :func:`fusion.scenarios.thermocouples.best_linear_abs_error`.

    Returns
    -------
    DataFrame
        Rows (noise, case); one column per method (°C, 3 decimals), the bound without failure
        (``NaN`` with failure) and the share of epochs at which the optimal set is best.
    """
    rows = {}
    for label, st in studies.items():
        for case, failure in (("no failure", False), ("failure", True)):
            row: dict[str, float] = {METHOD_LABELS[m]: float(st.errors(m, failure).mean()) for m in st.clean}
            row["bound (no failure)"] = (np.nan if failure else thermocouples.best_linear_abs_error(sigmas[label]))
            row["share of epochs where the optimal set is best"] = st.best_share("optimal_fusion_set", failure)
            rows[(label, case)] = row
    out = pd.DataFrame(rows).T.round(3)
    out.index.names = ["noise", "case (failure: samples 50-80)"]
    return out


def figure_mc(table: pd.DataFrame) -> Figure:
    """Bar chart of :func:`mc_table`: one panel per noise setting, bars per method and case.

    Parameters
    ----------
    table : DataFrame
        Output of :func:`mc_table`.

    Returns
    -------
    matplotlib.figure.Figure
    """
    settings = list(dict.fromkeys(table.index.get_level_values(0)))
    cases = ["no failure", "failure"]
    fig, axes = new_figure(1, len(settings), figsize=(7.5, 4.0), sharey=True)
    axes = np.atleast_1d(axes)
    for ax, s_label in zip(axes, settings):
        xpos = np.arange(len(cases))
        for j, m in enumerate(METHODS):
            ax.bar(xpos + (j - 1) * 0.26, [table.loc[(s_label, c), METHOD_LABELS[m]] for c in cases], 0.26,
                   color=color(m), label=METHOD_LABELS[m])
        ax.hlines(table.loc[(s_label, "no failure"), "bound (no failure)"], -0.45, 0.45, color=color("bound"),
                  lw=2, label="bound (inverse-variance mean)")
        ax.set_xticks(xpos, ["no failure\n(all samples)", "failure\n(samples 50-80)"])
        ax.set_title(s_label)
    axes[0].set_ylabel("mean absolute error (°C)")
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncols=2)
    return fig


def figure_scale(scales: ArrayLike, sweep: Mapping[str, ArrayLike], default: float = 2.0) -> Figure:
    """Mean absolute error of the optimal fusion set against the scale of eq. 6.

    Parameters
    ----------
    scales : array_like, shape (k,)
        Scales of eq. 6, °C.
    sweep : mapping of case label to array_like, shape (k,) or (k, n_runs)
        Mean absolute error per scale (averaged over runs when 2-D), °C.
    default : float
        The source's scale (factor 1/2 → 2 °C), marked by a dotted line.

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, ax = new_figure(figsize=(6.0, 3.2))
    for (label, values), style in zip(sweep.items(), ["-o", "--s"]):
        v = np.asarray(values, dtype=float)
        ax.semilogx(scales, v.mean(axis=1) if v.ndim == 2 else v, style, color=color("optimal_fusion_set"),
                    label=label, base=2)
    ax.axvline(default, color=color("truth"), lw=0.8, ls=":")
    ax.set(xlabel="scale of eq. 6 (°C)", ylabel="mean absolute error (°C)")
    ax.legend()
    return fig


# --------------------------------------------------------------------------- critiques
def unit_dependence(z: ArrayLike) -> dict[str, float | bool]:
    """How the optimal fusion set changes when the same readings are given in °F or K.

    Parameters
    ----------
    z : array_like, shape (n_epochs, n_sensors)
        Readings in °C.

    Returns
    -------
    dict
        ``f_maxdiff``, ``f_meandiff``: largest and mean absolute change (°C) of the fused value
        when fused in °F and converted back; ``k_maxdiff``: the same in kelvin (°C);
        ``members_same``: whether the optimal fusion set is the same in °C and °F.
    """
    z = np.asarray(z, dtype=float)
    fc = rd.fuse_epochs(z, "optimal_fusion_set")
    ff = rd.fuse_epochs(z * 9 / 5 + 32, "optimal_fusion_set")
    v_f = (ff.values - 32) * 5 / 9
    v_k = rd.fuse_epochs(z + 273.15, "optimal_fusion_set").values - 273.15
    return {"f_maxdiff": float(np.max(np.abs(v_f - fc.values))),
            "f_meandiff": float(np.mean(np.abs(v_f - fc.values))),
            "k_maxdiff": float(np.max(np.abs(v_k - fc.values))),
            "members_same": bool(np.array_equal(fc.members, ff.members))}


def eq9_readings(z: ArrayLike, weight_epochs: int | None = 200) -> dict[str, float | int]:
    """Effect of the open choices of eq. 9 on the weights and fused values.

    Parameters
    ----------
    z : array_like, shape (n_epochs, n_sensors)
        Readings, °C; epochs whose optimal fusion set has fewer than 3 members are skipped for
        the weight comparisons (their weights are 1/2 or 1 under every reading).
    weight_epochs : int, optional
        Only the first ``weight_epochs`` epochs enter the weight comparisons (a Python loop);
        ``None`` for all. The fused-value change uses every epoch.

    Returns
    -------
    dict
        ``n_sets``: number of sets compared; ``form_maxdiff``: largest weight difference
        between the three parenthesisations of eq. 9; ``self_maxdiff``: largest weight
        difference between including and excluding :math:`j = i`; ``self_valdiff``: largest
        change of the fused value (°C) over all epochs from that choice.
    """
    z = np.asarray(z, dtype=float)
    diffs, self_diffs = [], []
    for row in z[:weight_epochs]:
        sel = rd.optimal_set_members(row)
        if sel.sum() < 3:
            continue
        C = rd.fusion_degree_matrix(row[sel])
        mu = rd.consistency_degree(C)
        w = {}
        for form in ("left", "right", "root"):
            om = mu * rd.distribution_balance(C, form=form)
            w[form] = om / om.sum()
        diffs.append(max(np.max(np.abs(w["left"] - w["right"])), np.max(np.abs(w["left"] - w["root"]))))
        om = mu * rd.distribution_balance(C, include_self=False)
        self_diffs.append(np.max(np.abs(w["left"] - om / om.sum())))
    v_self = rd.fuse_epochs(z, "optimal_fusion_set").values
    v_noself = rd.fuse_epochs(z, "optimal_fusion_set", include_self=False).values
    return {"n_sets": len(diffs), "form_maxdiff": float(max(diffs, default=0.0)),
            "self_maxdiff": float(max(self_diffs, default=0.0)),
            "self_valdiff": float(np.max(np.abs(v_self - v_noself)))}


def table1_by_scale(scales: ArrayLike) -> FloatArray:
    """Optimal-set values of the source's Table 1 for each scale of eq. 6.

    Parameters
    ----------
    scales : array_like, shape (k,)
        Scales of eq. 6, °C (the source's factor 1/2 is scale 2).

    Returns
    -------
    ndarray, shape (k, 6)
        Fused values, °C.
    """
    t1 = data.YANG2012_TABLE1.values
    return np.stack([rd.fuse_epochs(t1.T, "optimal_fusion_set", scale=float(s)).values
                     for s in np.asarray(scales, dtype=float).ravel()])


#: Fusion-degree (membership) functions of the distance ``d = abs(s_i - s_j)`` tried in place of
#: eq. 6, each with the length scale ``h`` (°C): eq. 6 itself, a Gaussian and a Cauchy kernel.
FAMILIES: dict[str, str] = {
    "eq. 6, exp(-|d|/h)": "laplace",
    "Gaussian, exp(-d²/(2h²))": "gauss",
    "Cauchy, 1/(1 + (d/h)²)": "cauchy",
}


def _kernel(d: FloatArray, family: str, scale: float) -> FloatArray:
    if family == "laplace":
        return np.exp(-d / scale)
    if family == "gauss":
        return np.exp(-0.5 * (d / scale) ** 2)
    if family == "cauchy":
        return 1.0 / (1.0 + (d / scale) ** 2)
    raise ValueError(f"family must be one of {sorted(set(FAMILIES.values()))}, got {family!r}")


def family_values(z: ArrayLike, family: str = "laplace", scale: float = 2.0) -> FloatArray:
    r"""Optimal-fusion-set values with another fusion-degree function in place of eq. 6.

    The selection (eqs. 3-5) and eqs. 7-12 are those of
    :func:`fusion.readings.fusion_set.fuse_epochs`; only :math:`c_{ij}` changes. Degenerate
    rows of eq. 9 (a member with :math:`S_i = 0`) are resolved as the package does: those
    members share the weight in proportion to :math:`\mu_i`.

    Parameters
    ----------
    z : array_like, shape (n_epochs, n_sensors)
        Readings, °C.
    family : {"laplace", "gauss", "cauchy"}
        :math:`\exp(-|d|/h)` (eq. 6), :math:`\exp(-d^2/2h^2)` or :math:`1/(1 + (d/h)^2)`.
    scale : float
        Length scale :math:`h`, °C (eq. 6's factor 1/2 is 2 °C).

    Returns
    -------
    ndarray, shape (n_epochs,)
        Fused values, °C.

    References
    ----------
    Yang G. N., Feng X. F., Fan L. J. (2012), eqs. 3-12.
    """
    s = np.atleast_2d(np.asarray(z, dtype=float))
    if s.ndim != 2 or not np.all(np.isfinite(s)):
        raise ValueError("z must be a finite array of shape (n_epochs, n_sensors)")
    if not (np.isfinite(scale) and scale > 0):
        raise ValueError(f"scale must be positive, got {scale!r}")
    members = rd.fuse_epochs(s, "optimal_fusion_set").members
    mf = members.astype(float)
    m = mf.sum(axis=1, keepdims=True)
    pair = mf[:, :, None] * mf[:, None, :]
    C = _kernel(np.abs(s[:, :, None] - s[:, None, :]), family, float(scale)) * pair
    mu = C.sum(axis=2) / m
    S = ((mu[:, :, None] - C) ** 2 * pair).sum(axis=2)
    infinite = members & (S == 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        om = np.where(members, mu / np.sqrt(S), 0.0)
    om = np.where(infinite.any(axis=1, keepdims=True), np.where(infinite, mu, 0.0), om)
    return np.einsum("ij,ij->i", om / om.sum(axis=1, keepdims=True), s)


#: Support-degree sharpness parameters (°C⁻²) run as alternatives to the primary α = 0.25.
ALPHAS: tuple[float, ...] = (0.05, 0.1, 0.5, 1.0, 2.0)


def alpha_methods(alphas: Sequence[float] = ALPHAS) -> dict[str, dict[str, object]]:
    """:data:`METHODS`-style specs: the optimal fusion set and the support degree at each α.

    Parameters
    ----------
    alphas : sequence of float
        Support-degree parameters, °C⁻².

    Returns
    -------
    dict
        ``"optimal_fusion_set"`` and ``"support degree, α = <a>"`` for each α, for
        :func:`fusion.scenarios.thermocouples.paired_study` (same seed: the same draws as the
        primary study).
    """
    out: dict[str, dict[str, object]] = {"optimal_fusion_set": {"method": "optimal_fusion_set"}}
    for a in alphas:
        out[f"support degree, α = {a:g}"] = {"method": "support_degree", "alpha": float(a)}
    return out


def family_mae(z: ArrayLike, families: Mapping[str, str] = FAMILIES, scale: float = 2.0,
               window: tuple[int, int] | None = None, truth: float = 900.0) -> dict[str, FloatArray]:
    """Per-run mean absolute error of the optimal fusion set under each fusion-degree family.

    Parameters
    ----------
    z : array_like, shape (n_runs, n_samples, n_sensors)
        Readings, °C (e.g. :func:`fusion.scenarios.thermocouples.simulate` with ``n_runs``).
    families : mapping of label to family
        See :data:`FAMILIES` and :func:`family_values`.
    scale : float
        Length scale of every family, °C.
    window : (int, int), optional
        1-based first and last sample averaged (default all samples).
    truth : float
        True value, °C.

    Returns
    -------
    dict of label to ndarray, shape (n_runs,)
        Mean absolute error, °C.
    """
    arr = np.asarray(z, dtype=float)
    if arr.ndim != 3:
        raise ValueError(f"z must have shape (n_runs, n_samples, n_sensors), got {arr.shape}")
    part = slice(None) if window is None else slice(window[0] - 1, window[1])
    out = {}
    for label, fam in families.items():
        v = family_values(arr.reshape(-1, arr.shape[-1]), fam, scale).reshape(arr.shape[:2])
        out[label] = np.abs(v - truth)[:, part].mean(axis=1)
    return out


def weight_ablation(z: ArrayLike, window: tuple[int, int] | None = None,
                    truth: float = 900.0) -> dict[str, FloatArray]:
    """Per-run mean absolute error of the optimal fusion set with the weights of eqs. 6-11 and with equal weights.

    Both use the same set (eqs. 3-5); only the weights inside it differ.

    Parameters
    ----------
    z : array_like, shape (n_runs, n_samples, n_sensors)
        Readings, °C.
    window : (int, int), optional
        1-based first and last sample averaged (default all samples).
    truth : float
        True value, °C.

    Returns
    -------
    dict
        ``"optimal_fusion_set"`` and ``"uniform_set"`` -> ndarray, shape (n_runs,), °C.

    References
    ----------
    Yang G. N., Feng X. F., Fan L. J. (2012), eqs. 3-12.
    """
    arr = np.asarray(z, dtype=float)
    if arr.ndim != 3 or not np.all(np.isfinite(arr)):
        raise ValueError(f"z must be a finite array of shape (n_runs, n_samples, n_sensors), got {arr.shape}")
    part = slice(None) if window is None else slice(window[0] - 1, window[1])
    flat = arr.reshape(-1, arr.shape[-1])
    out = {"optimal_fusion_set": rd.fuse_epochs(flat, "optimal_fusion_set").values,
           "uniform_set": robust_fuse(flat, "uniform_set")}
    return {k: np.round(np.abs(v - truth).reshape(arr.shape[:2])[:, part].mean(axis=1), 9) for k, v in out.items()}


# --------------------------------------------------------------------------- studies (cached)
#: Seed and Monte-Carlo runs of the chapter's primary readings.
SEED, N_RUNS = 2012, 500

#: Readings of the noise levels the source does not give: the primary (unequal, evenly spaced), equal noise, and
#: geometric spreads σ_max/σ_min = r from r^-1/2 to r^1/2 °C (the fair study's spread sweep; r = 4 is 0.5-2.0 °C).
NOISE: dict[str, object] = {"unequal": thermocouples.DEFAULT_SIGMAS, "equal": 1.0,
                            **{f"geometric-{r}": np.geomspace(r ** -0.5, r ** 0.5, 10) for r in (2, 4, 8, 16)}}


def _noise(settings: Mapping[str, object]) -> str:
    noise = str(settings.get("noise", "unequal"))
    if noise not in NOISE:
        raise ValueError(f"settings['noise'] must be one of {sorted(NOISE)}, got {noise!r}")
    return noise


@lru_cache(maxsize=1)
def tables() -> TableReproduction:
    """:func:`reproduce_tables`, computed once."""
    return reproduce_tables()


@lru_cache(maxsize=1)
def joint() -> ofs_audit.AuditResult:
    """:func:`fusion.book.chapters.ofs_audit.joint_audit`, computed once."""
    return ofs_audit.joint_audit()


@lru_cache(maxsize=1)
def support_table() -> pd.DataFrame:
    """:func:`fusion.book.chapters.ofs_audit.support_variants`, computed once."""
    return ofs_audit.support_variants()


def corrected_table1() -> FloatArray:
    """Table 1 with the joint audit's one correction (sensor 1 of observation 5).

    Returns
    -------
    ndarray, shape (3, 6)
        Readings (°C), sensors by observations.

    Raises
    ------
    ValueError
        When the joint audit finds no full explanation.
    """
    fe = ofs_audit.full_explanation(joint())
    if fe is None:
        raise ValueError("the joint audit finds no full explanation")
    t1 = np.array(data.YANG2012_TABLE1.values, dtype=float)
    t1[fe[0].sensor - 1, fe[0].obs - 1] = fe[0].value
    return t1


def study(seed: int, runs: int, noise: str = "unequal", failure: str = "fixed", include_self: bool = True) -> PairedStudy:
    """The paired study of the three methods (:func:`fusion.scenarios.thermocouples.paired_study`), cached.

    Parameters
    ----------
    seed, runs : int
    noise : {"unequal", "equal"}
        A key of :data:`NOISE`.
    failure : str
        One of :data:`fusion.scenarios.thermocouples.FAILURE_MODES` (the readings of "randomly").
    include_self : bool
        Whether eq. 9's sum over j includes j = i (the package's default, True); False fuses the optimal set
        and the mean only (the reading of eq. 9 without j = i).

    Returns
    -------
    PairedStudy
    """
    return _study(int(seed), int(runs), _noise({"noise": noise}), str(failure), bool(include_self))


@lru_cache(maxsize=16)
def _study(seed: int, runs: int, noise: str, failure: str, include_self: bool = True) -> PairedStudy:
    # the geometric spreads and eq. 9 without j = i are readings of the records against the mean only
    methods = METHODS if noise in ("unequal", "equal") and include_self else {k: METHODS[k] for k in
                                                                                ("optimal_fusion_set", "mean")}
    if not include_self:
        methods = {**methods, "optimal_fusion_set": {"method": "optimal_fusion_set", "include_self": False}}
    return thermocouples.paired_study(seed, runs, methods, sigma=NOISE[noise], failure_mode=failure)


def alpha_study(seed: int, runs: int) -> PairedStudy:
    """The primary draws fused by the support degree at every α of :data:`ALPHAS` (cached).

    Parameters
    ----------
    seed, runs : int
        As in :func:`study` (the same seed gives the same draws).

    Returns
    -------
    PairedStudy
    """
    return _alpha_study(int(seed), int(runs))


@lru_cache(maxsize=4)
def _alpha_study(seed: int, runs: int) -> PairedStudy:
    return thermocouples.paired_study(seed, runs, alpha_methods())


@dataclass(frozen=True)
class MembershipStudy:
    """The membership-function study on the primary draws: scales of eq. 6, families, equal weights.

    Attributes
    ----------
    scales : ndarray, shape (k,)
        Scales of eq. 6 (°C); the source's factor 1/2 is 2 °C.
    sweep : dict
        ``"no failure"`` / ``"failure"`` -> per-run MAE of each scale, shape (k, runs) (samples 50-80 under failure).
    family : dict
        ``"no failure"`` / ``"failure"`` -> :func:`family_mae`.
    ablation : dict
        ``"no failure"`` / ``"failure"`` -> :func:`weight_ablation`.
    """

    scales: FloatArray
    sweep: dict[str, FloatArray]
    family: dict[str, dict[str, FloatArray]]
    ablation: dict[str, dict[str, FloatArray]]


#: Scales of eq. 6 swept (°C).
SCALES: tuple[float, ...] = (0.125, 0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0, 32.0)


def membership_study(seed: int, runs: int) -> MembershipStudy:
    """Scale sweep, membership families and the equal-weight ablation on the primary draws (cached).

    Parameters
    ----------
    seed, runs : int
        As in :func:`study` (the same seed gives the same draws).

    Returns
    -------
    MembershipStudy
    """
    return _membership_study(int(seed), int(runs))


@lru_cache(maxsize=4)
def _membership_study(seed: int, runs: int) -> MembershipStudy:
    sc = np.array(SCALES)
    z = thermocouples.simulate(np.random.default_rng(seed), n_runs=runs)
    zf = thermocouples.inject_failure(z, **data.YANG2012_FAILURE)
    return MembershipStudy(
        scales=sc,
        sweep={"no failure": thermocouples.scale_sweep(seed, runs, sc),
               "failure": thermocouples.scale_sweep(seed, runs, sc, failure={}, window=(50, 80))},
        family={"no failure": family_mae(z), "failure": family_mae(zf, window=(50, 80))},
        ablation={"no failure": weight_ablation(z), "failure": weight_ablation(zf, window=(50, 80))})


def fair(seed: int, runs: int = 100) -> ofs_fair.FairStudy:
    """:func:`fusion.book.chapters.ofs_fair.fair_study` with its default sweeps (cached).

    Parameters
    ----------
    seed : int
    runs : int
        Runs of 100 samples per sweep point.

    Returns
    -------
    FairStudy
    """
    return _fair(int(seed), int(runs))


@lru_cache(maxsize=4)
def _fair(seed: int, runs: int) -> ofs_fair.FairStudy:
    return ofs_fair.fair_study(seed, n_runs=runs)


# --------------------------------------------------------------------------- evidence of the records
_LABEL = {"optimal_fusion_set": "optimal fusion set", "mean": "arithmetic mean",
          "support_degree": "support degree (rebuilt, α = 0.25 °C⁻²)"}
_CASES = {"clean": (False, None, "samples 1-100, no failure"), "window": (True, None, "samples 50-80 under failure"),
          "whole": (True, False, "samples 1-100 under failure")}


def _pair(base: str, case: str, metric: str, settings: Mapping[str, object], seed: int, runs: int) -> Comparison:
    """The optimal set against ``base`` on the study the settings name (noise, failure reading, α)."""
    failure, window, where = _CASES[case]
    mode = str(settings.get("failure", "fixed"))
    if "alpha" in settings:
        if base != "support_degree":
            raise ValueError("settings['alpha'] applies to the support degree only")
        st, b = alpha_study(seed, runs), f"support degree, α = {float(settings['alpha']):g}"  # type: ignore[arg-type]
        name = f"support degree (rebuilt, α = {float(settings['alpha']):g} °C⁻²)"  # type: ignore[arg-type]
    else:
        st, b, name = study(seed, runs, _noise(settings), mode, bool(settings.get("include_self", True))), base, _LABEL[base]
    fn = st.mae if metric == "mae" else st.fluctuation
    what = "mean absolute error" if metric == "mae" else "SD of the absolute error over samples"
    return Comparison(fn("optimal_fusion_set", failure, window), fn(b, failure, window), _LABEL["optimal_fusion_set"],
                      name, "less", f"per-run {what}, {where} (°C)", seed=seed)


def ev_fig2_vs_mean(settings: Mapping[str, object], *, seed: int = SEED, runs: int = N_RUNS) -> Comparison:
    """Fig. 2: per-run MAE of the optimal set against the mean, no failure (settings: ``noise``)."""
    return _pair("mean", "clean", "mae", settings, seed, runs)


def ev_fig2_fluctuation(settings: Mapping[str, object], *, seed: int = SEED, runs: int = N_RUNS) -> Comparison:
    """Fig. 2: per-run SD of the error, optimal set against the mean, no failure."""
    return _pair("mean", "clean", "sd", settings, seed, runs)


def ev_fig2_vs_support(settings: Mapping[str, object], *, seed: int = SEED, runs: int = N_RUNS) -> Comparison:
    """Fig. 2: per-run MAE against the rebuilt support degree (settings: ``noise`` or ``alpha``)."""
    return _pair("support_degree", "clean", "mae", settings, seed, runs)


def ev_fig2_fluctuation_support(settings: Mapping[str, object], *, seed: int = SEED,
                                runs: int = N_RUNS) -> Comparison:
    """Fig. 2: per-run SD of the error against the rebuilt support degree."""
    return _pair("support_degree", "clean", "sd", settings, seed, runs)


def ev_fig4_vs_mean(settings: Mapping[str, object], *, seed: int = SEED, runs: int = N_RUNS) -> Comparison:
    """Fig. 4: per-run MAE on samples 50-80 against the mean (settings: ``noise``, ``failure``)."""
    return _pair("mean", "window", "mae", settings, seed, runs)


def ev_fig4_whole_vs_mean(settings: Mapping[str, object], *, seed: int = SEED, runs: int = N_RUNS) -> Comparison:
    """Fig. 4: per-run MAE over the whole failure run against the mean."""
    return _pair("mean", "whole", "mae", settings, seed, runs)


def ev_fig4_fluctuation_mean(settings: Mapping[str, object], *, seed: int = SEED, runs: int = N_RUNS) -> Comparison:
    """Fig. 4: per-run SD of the error on samples 50-80 against the mean."""
    return _pair("mean", "window", "sd", settings, seed, runs)


def ev_fig4_vs_support(settings: Mapping[str, object], *, seed: int = SEED, runs: int = N_RUNS) -> Comparison:
    """Fig. 4: per-run MAE on samples 50-80 against the rebuilt support degree."""
    return _pair("support_degree", "window", "mae", settings, seed, runs)


def ev_fig4_whole_vs_support(settings: Mapping[str, object], *, seed: int = SEED, runs: int = N_RUNS) -> Comparison:
    """Fig. 4: per-run MAE over the whole failure run against the rebuilt support degree."""
    return _pair("support_degree", "whole", "mae", settings, seed, runs)


def ev_fig4_fluctuation_support(settings: Mapping[str, object], *, seed: int = SEED,
                                runs: int = N_RUNS) -> Comparison:
    """Fig. 4: per-run SD of the error on samples 50-80 against the rebuilt support degree."""
    return _pair("support_degree", "window", "sd", settings, seed, runs)


def ev_fig4_unaffected(settings: Mapping[str, object], *, seed: int = SEED, runs: int = N_RUNS) -> Comparison:
    """Fig. 4: the optimal set's per-run MAE on samples 50-80 with the failure against without it ("equal")."""
    st = study(seed, runs, _noise(settings), str(settings.get("failure", "fixed")))
    return Comparison(st.mae("optimal_fusion_set", True), st.mae("optimal_fusion_set", False, window=True),
                      "with failure", "without failure", "equal",
                      "optimal set's per-run mean absolute error on samples 50-80 (°C)", seed=seed)


def ev_fig4_robust(settings: Mapping[str, object], *, seed: int = SEED, runs: int = N_RUNS) -> Comparison:
    """Fig. 4: the rise of the per-run MAE on samples 50-80 due to the failure, optimal set against the mean."""
    st = study(seed, runs, _noise(settings), str(settings.get("failure", "fixed")))
    rise = {m: st.mae(m, True) - st.mae(m, False, window=True) for m in ("optimal_fusion_set", "mean")}
    return Comparison(rise["optimal_fusion_set"], rise["mean"], _LABEL["optimal_fusion_set"], _LABEL["mean"], "less",
                      "per-run rise of the mean absolute error on samples 50-80 due to the failure (°C)", seed=seed)


def ev_weights_reasonable(settings: Mapping[str, object], *, seed: int = SEED, runs: int = N_RUNS) -> Comparison:
    """Weights of eqs. 6-11 against equal weights on the same set (settings: ``case``, or ``sweep`` and ``value``)."""
    if "sweep" in settings:
        e = fair(seed, runs).mae[(str(settings["sweep"]), float(settings["value"]))]  # type: ignore[arg-type]
        what = f"{settings['sweep']} = {float(settings['value']):g}"  # type: ignore[arg-type]
    else:
        case = str(settings.get("case", "no failure"))
        e = membership_study(seed, runs).ablation[case]
        what = "primary noise, " + ("samples 1-100, no failure" if case == "no failure" else "samples 50-80 under failure")
    return Comparison(e["optimal_fusion_set"], e["uniform_set"], "weights of eqs. 6-11", METHOD_LABELS["uniform_set"],
                      "less", f"per-run mean absolute error, {what} (°C)", seed=seed)


def ev_membership_free(settings: Mapping[str, object], *, seed: int = SEED, runs: int = N_RUNS) -> Conjunction:
    """Each other membership function against eq. 6, "equal" (settings ``vary``: family, scale or table1)."""
    vary = str(settings.get("vary", "family"))
    if vary == "table1":
        t1 = data.YANG2012_TABLE1.values.T
        parts_t1 = []
        for fam in ("gauss", "cauchy"):
            diff = float(np.max(np.abs(family_values(t1, fam) - family_values(t1, "laplace"))))
            parts_t1.append((f"Table 1, {fam} vs eq. 6", Proposition(
                diff == 0.0, f"largest difference from eq. 6 over the six observations: {diff:.1g} °C")))
        return Conjunction(parts_t1)
    ms = membership_study(seed, runs)
    parts = []
    for case in ("no failure", "failure"):
        if vary == "family":
            fam = ms.family[case]
            ref = next(iter(fam))
            parts += [(f"{lab}, {case}", Comparison(v, fam[ref], lab, ref, "equal", "per-run mean absolute error (°C)",
                                                    seed=seed)) for lab, v in fam.items() if lab != ref]
        else:
            sw, k0 = ms.sweep[case], int(np.argmin(np.abs(ms.scales - 2.0)))
            parts += [(f"scale {h:g} °C, {case}", Comparison(sw[k], sw[k0], f"scale {h:g} °C", "scale 2 °C", "equal",
                                                             "per-run mean absolute error (°C)", seed=seed))
                      for k, h in enumerate(ms.scales) if k != k0]
    return Conjunction(parts)


@dataclass(frozen=True)
class WeightStudy:
    """How the weights of eqs. 8-11 treat each sensor of the primary draws, without failure.

    Attributes
    ----------
    relative : ndarray, shape (runs, n_sensors)
        Per run, each sensor's weight relative to an equal share of its set (weight × set size; 1 = equal
        weights), averaged over the epochs at which it is a member.
    member : ndarray, shape (n_sensors,)
        Share of all epochs at which each sensor is a member of the set.
    """

    relative: FloatArray
    member: FloatArray


def weight_study(seed: int, runs: int, include_self: bool = True) -> WeightStudy:
    """:class:`WeightStudy` of the primary draws (unequal noise, no failure), cached.

    Parameters
    ----------
    seed, runs : int
        As in :func:`study` (the same seed gives the same draws).
    include_self : bool
        Whether eq. 9's sum includes j = i (as in :func:`study`).

    Returns
    -------
    WeightStudy
    """
    return _weight_study(int(seed), int(runs), bool(include_self))


@lru_cache(maxsize=4)
def _weight_study(seed: int, runs: int, include_self: bool = True) -> WeightStudy:
    z = thermocouples.simulate(np.random.default_rng(seed), n_runs=runs)
    f = rd.fuse_epochs(z.reshape(-1, z.shape[-1]), "optimal_fusion_set", include_self=include_self)
    w, m = f.weights.reshape(z.shape), f.members.reshape(z.shape)
    rel = np.where(m, w * m.sum(axis=2, keepdims=True), 0.0).sum(axis=1) / np.maximum(m.sum(axis=1), 1)
    return WeightStudy(relative=rel, member=m.mean(axis=(0, 1)))


def ev_weights_stability(settings: Mapping[str, object], *, seed: int = SEED, runs: int = N_RUNS) -> Comparison:
    """Section 1.3: the weights of the more stable sensors against the less stable ones.

    Settings ``sensors``: ``"halves"`` (default: the mean relative weight of sensors 1-5, σ 0.5-1.17 °C, against
    that of sensors 6-10, σ 1.33-2 °C, per run) or a pair (1-based) of sensors.
    """
    ws = weight_study(seed, runs, bool(settings.get("include_self", True)))
    if settings.get("sensors", "halves") == "halves":
        k = ws.relative.shape[1] // 2
        return Comparison(ws.relative[:, :k].mean(axis=1), ws.relative[:, k:].mean(axis=1), f"sensors 1-{k}",
                          f"sensors {k + 1}-{ws.relative.shape[1]}", "greater", "per-run weight relative to an equal "
                          "share of the set, averaged over the sensors of each half (epochs at which each is a member)",
                          seed=seed)
    a, b = (int(k) for k in settings["sensors"])  # type: ignore[union-attr]
    if not (1 <= a <= ws.relative.shape[1] and 1 <= b <= ws.relative.shape[1]):
        raise ValueError(f"settings['sensors'] must name two sensors in 1..{ws.relative.shape[1]}, got {(a, b)}")
    return Comparison(ws.relative[:, a - 1], ws.relative[:, b - 1], f"sensor {a}", f"sensor {b}", "greater",
                      "per-run weight relative to an equal share of the set, epochs at which the sensor is a member",
                      seed=seed)


def ev_def3_keeps_valid(settings: Mapping[str, object], *, seed: int = SEED, runs: int = N_RUNS) -> Proposition:
    """Definition 3: without faults (every reading valid) the set keeps all ten readings."""
    st = study(seed, runs, _noise(settings))
    off = not_neighbourhood_share(int(seed), int(runs), _noise(settings))
    return Proposition(bool(np.all(st.set_size == 10)), f"without faults (every reading valid) the set keeps "
                       f"{float(np.mean(st.set_size)):.2f} of 10 readings on average ({st.n_runs} runs × 100 samples); "
                       f"at {off:.1%} of the epochs a dropped reading lies closer to 900 °C than a kept one, so no "
                       "neighbourhood of the true value, of any width, holds exactly the set", runs=st.n_runs)


@lru_cache(maxsize=8)
def not_neighbourhood_share(seed: int, runs: int, noise: str = "unequal") -> float:
    """Share of the epochs, without failure, at which the set is no neighbourhood set of the true value 900 °C.

    The set of eq. 5 is the set of the readings within some neighbourhood of X (Definition 3) only if every kept
    reading is closer to X than every dropped one; at the other epochs no neighbourhood width, however chosen,
    gives the set. The draws are those of :func:`study` (same seed).

    Parameters
    ----------
    seed, runs : int
    noise : str
        A key of :data:`NOISE`.

    Returns
    -------
    float
    """
    rng = np.random.default_rng(int(seed))
    z = thermocouples.simulate(rng, sigma=NOISE[_noise({"noise": noise})], n_runs=int(runs)).reshape(-1, 10)
    m = rd.fuse_epochs(z, "optimal_fusion_set").members
    dist = np.abs(z - 900.0)
    kept_far = np.where(m, dist, -np.inf).max(axis=1)
    dropped_near = np.where(~m, dist, np.inf).min(axis=1)
    return float(np.mean(dropped_near < kept_far))


def faulty_member_share(seed: int, runs: int, noise: str = "unequal", failure: str = "fixed") -> dict[str, object]:
    """Share of the epochs 50-80 at which each failing sensor is a member of the set, at its *faulty* epochs.

    A failing sensor's reading counts as faulty at an epoch when the bias added to it there exceeds twice its
    noise σ (under "fixed" every epoch 50-80; under the random readings of 随机地 only some: a random bias can be
    zero or tiny, and keeping such a reading is correct). The draws are those of :func:`study` (same seed).

    Parameters
    ----------
    seed, runs : int
    noise : str
        A key of :data:`NOISE`.
    failure : str
        One of :data:`fusion.scenarios.thermocouples.FAILURE_MODES`.

    Returns
    -------
    dict
        ``"share"``: per failing sensor (4, 10), the member share over its faulty epochs; ``"all"``: over all
        epochs 50-80; ``"faulty"``: the share of the epochs 50-80 that are faulty.
    """
    sig = np.broadcast_to(np.asarray(NOISE[_noise({"noise": noise})], float), (10,))
    rng = np.random.default_rng(int(seed))
    z = thermocouples.simulate(rng, sigma=NOISE[_noise({"noise": noise})], n_runs=int(runs))
    zf = thermocouples.random_failure(z, rng, str(failure))
    cols = np.array([3, 9])
    win = zf[:, 49:80]
    m = rd.fuse_epochs(win.reshape(-1, 10), "optimal_fusion_set").members.reshape(win.shape)[..., cols]
    faulty = np.abs(zf - z)[:, 49:80][..., cols] > 2.0 * sig[cols]
    share = [float(m[..., k][faulty[..., k]].mean()) if faulty[..., k].any() else 0.0 for k in range(2)]
    return {"share": share, "all": [float(m[..., k].mean()) for k in range(2)],
            "faulty": [float(faulty[..., k].mean()) for k in range(2)]}


def ev_set_rejects_faulty(settings: Mapping[str, object], *, seed: int = SEED, runs: int = N_RUNS) -> Proposition:
    """Section 2: under the failure, sensors 4 and 10 are never members of the set at their faulty epochs 50-80.

    Settings: ``noise``, ``failure`` (a reading of "randomly"). Under the random readings only the epochs at which
    a sensor's bias exceeds twice its σ are judged (:func:`faulty_member_share`); a zero-tolerance proposition
    ("rejects" = never a member), the share shown.
    """
    fm = faulty_member_share(seed, runs, _noise(settings), str(settings.get("failure", "fixed")))
    sh, al, fa = fm["share"], fm["all"], fm["faulty"]
    extra = ("" if str(settings.get("failure", "fixed")) in ("fixed", "opposite signs") else
             f"; over all epochs 50-80, faulty or not, {al[0]:.1%} and {al[1]:.1%}")  # type: ignore[index]
    return Proposition(bool(max(sh) == 0.0), f"under the failure, sensor 4 is a member at {sh[0]:.1%} and sensor 10 "  # type: ignore[index, arg-type]
                       f"at {sh[1]:.1%} of their faulty epochs 50-80 (bias above twice the sensor's σ: {fa[0]:.0%} and "  # type: ignore[index]
                       f"{fa[1]:.0%} of the epochs; {runs} runs){extra}", runs=int(runs))  # type: ignore[index]


def _explained() -> pd.DataFrame:
    """The joint audit's full explanation, value by value (:func:`fusion.book.chapters.ofs_audit.explain`)."""
    fe = ofs_audit.full_explanation(joint())
    if fe is None:
        raise ValueError("the joint audit finds no full explanation")
    return ofs_audit.explain(*fe)


def ev_table2_ofs(settings: Mapping[str, object], *, seed: int = SEED, runs: int = N_RUNS) -> PublishedValues:
    """Table 2's optimal-set column against Table 1 fused (settings ``explanation``: the joint audit's)."""
    pub = data.YANG2012_TABLE2.columns["optimal_set"]
    if settings.get("explanation"):
        return PublishedValues(pub, _explained()[("optimal set", "reconstructed")].to_numpy()[:6], 4, "°C")
    return PublishedValues(pub, tables().ofs, 4, "°C")


def ev_table2_mean(settings: Mapping[str, object], *, seed: int = SEED, runs: int = N_RUNS) -> PublishedValues:
    """Table 2's mean column against the means of Table 1 (settings ``data``: ``"corrected"``)."""
    t1 = corrected_table1() if settings.get("data") == "corrected" else data.YANG2012_TABLE1.values
    return PublishedValues(data.YANG2012_TABLE2.columns["mean"], np.mean(t1, axis=0), 4, "°C")


#: Grid of α searched for the closest single α of a support-degree variant.
_ALPHA_GRID = np.logspace(-6, 3, 600)


def ev_table3_support(settings: Mapping[str, object], *, seed: int = SEED, runs: int = N_RUNS) -> PublishedValues:
    """Table 3's support-degree column against a rebuilt rule on Table 1.

    Settings: none (Yager's power average, α = 0.25 °C⁻²), or ``kernel``, ``weights`` (keys of
    :data:`fusion.book.chapters.ofs_audit.SUPPORT_KERNELS` / ``SUPPORT_AGGREGATIONS``) and ``data``
    (``"printed"`` or ``"corrected"``): the variant at the single α of the grid that reproduces the
    most printed values (then the smallest largest error).
    """
    pub = data.YANG2012_TABLE3.columns["reliability"]
    if "kernel" not in settings:
        return PublishedValues(pub, tables().sup, 4, "°C")
    t1 = corrected_table1() if settings.get("data") == "corrected" else np.array(data.YANG2012_TABLE1.values, float)
    v = ofs_audit.support_values(t1.T, str(settings["kernel"]), str(settings["weights"]), _ALPHA_GRID)
    err = np.abs(v - pub)
    best = int(np.lexsort((err.max(axis=1), -(err < _TOL).sum(axis=1)))[0])
    return PublishedValues(pub, v[best], 4, "°C")


def table1_totals(t1: ArrayLike, alpha: float = 0.25, guard: bool = False, rule: str = "averages") -> dict[str, float]:
    """Total absolute errors (°C) on a table of readings: optimal set, mean, rebuilt support degree, median.

    Parameters
    ----------
    t1 : array_like, shape (n_sensors, n_obs)
        Readings (°C), as Table 1.
    alpha : float
        Sharpness of the rebuilt support degree (°C⁻²).
    guard : bool
        If true, a one-member optimal set falls back to the mean of all readings.
    rule : {"averages", "sums"}
        Eqs. 3-4 read as averages (as the text names them) or as the sums they print.

    Returns
    -------
    dict
        ``"ofs"``, ``"mean"``, ``"median"``, ``"sup"`` -> total absolute error against 900 °C (°C).
    """
    x = np.asarray(t1, dtype=float).T
    truth = data.YANG2012_TRUE_VALUE
    if rule not in ("averages", "sums"):
        raise ValueError(f"rule must be 'averages' or 'sums', got {rule!r}")
    ofs = (rd.fuse_epochs(x, "optimal_fusion_set", threshold="sum") if rule == "sums"
           else rd.fuse_epochs(x, "optimal_fusion_set"))
    vals = {"ofs": ofs.values, "mean": x.mean(axis=1), "median": np.median(x, axis=1),
            "sup": rd.fuse_epochs(x, "support_degree", alpha=alpha).values}
    if guard:
        vals["ofs"] = np.where(ofs.members.sum(axis=1) == 1, vals["mean"], vals["ofs"])
    return {k: float(np.abs(v - truth).sum()) for k, v in vals.items()}


def ev_totals(settings: Mapping[str, object], *, seed: int = SEED, runs: int = N_RUNS) -> PublishedValues:
    """The printed totals of the mean and the optimal set (settings ``explanation``: the joint audit's)."""
    tot = data.YANG2012_TOTALS.columns
    pub = [tot["mean"][0], tot["optimal_set"][0]]
    if settings.get("explanation"):
        ex = _explained()
        return PublishedValues(pub, [ex.loc["total", ("mean error", "reconstructed")],
                                     ex.loc["total", ("optimal-set error", "reconstructed")]], 4, "°C")
    t = table1_totals(data.YANG2012_TABLE1.values)
    return PublishedValues(pub, [t["mean"], t["ofs"]], 4, "°C")


def _ranking(a: str, b: str, settings: Mapping[str, object]) -> ExactComparison:
    t1 = corrected_table1() if settings.get("data") == "corrected" else data.YANG2012_TABLE1.values
    t = table1_totals(t1, float(settings.get("alpha", 0.25)), settings.get("guard") == "mean",  # type: ignore[arg-type]
                      str(settings.get("rule", "averages")))
    if settings.get("total") == "printed":
        t["sup"] = float(data.YANG2012_TOTALS.columns["reliability"][0])
    names = {"ofs": "optimal set", "mean": "mean", "sup": "support degree", "median": "median"}
    # R9: an exact comparison of totals, judged by the practical margin (5 % of the baseline's total)
    return ExactComparison(float(t[a]), float(t[b]), names[a], names[b], "less", "total absolute error over Table 1, °C")


def ev_totals_ranking_mean(settings: Mapping[str, object], *, seed: int = SEED, runs: int = N_RUNS) -> ExactComparison:
    """Table 1: the optimal set's total absolute error below the mean's (settings ``guard``, ``data``)."""
    return _ranking("ofs", "mean", settings)


def ev_totals_ranking_support(settings: Mapping[str, object], *, seed: int = SEED, runs: int = N_RUNS) -> ExactComparison:
    """Table 1: the optimal set's total below the rebuilt support degree's (settings ``alpha``, ``data``, ``total``)."""
    return _ranking("ofs", "sup", settings)


def ev_median_total(settings: Mapping[str, object], *, seed: int = SEED, runs: int = N_RUNS) -> ExactComparison:
    """Table 1: the plain median's total absolute error below the optimal set's (settings ``data``, ``guard``)."""
    return _ranking("median", "ofs", settings)


def ev_obs_closer(settings: Mapping[str, object], *, seed: int = SEED, runs: int = N_RUNS) -> Conjunction:
    """At observations 1, 3, 4, 5, 6 the optimal set is closer to 900 °C (settings ``values``: printed or recomputed).

    One exact comparison (R9) per observation and method compared: the optimal set's absolute error against the
    other's, judged by the chapter's practical margin (5 % of the other's error); the claim holds for the group
    only if it holds at every observation.
    """
    obs = (1, 3, 4, 5, 6)
    t2, t3 = data.YANG2012_TABLE2.columns, data.YANG2012_TABLE3.columns
    if settings.get("values", "printed") == "printed":
        e_ofs, e_mean = np.asarray(t2["optimal_set_abs_error"], float), np.asarray(t2["mean_abs_error"], float)
        src = "printed"
    else:
        tb = tables()
        e_ofs = np.abs(tb.ofs - data.YANG2012_TRUE_VALUE)
        e_mean = np.abs(tb.mean - data.YANG2012_TRUE_VALUE)
        src = "recomputed"
    others = {"mean": e_mean}
    if settings.get("against") == "both":
        others["support degree (printed)"] = np.asarray(t3["reliability_abs_error"], float)
    parts = [(f"observation {k}, against the {name}" if len(others) > 1 else f"observation {k}",
              ExactComparison(float(e_ofs[k - 1]), float(e[k - 1]), "optimal set", name, "less",
                              f"{src} absolute error at observation {k}, °C"))
             for k in obs for name, e in others.items()]
    return Conjunction(parts)


def ev_eq3_5_rejects(settings: Mapping[str, object], *, seed: int = SEED, runs: int = N_RUNS) -> Proposition:
    """Eq. 5 drops exactly the readings farthest from the others (settings ``rule``: averages or sums)."""
    rng = np.random.default_rng(seed)
    triples = 900.0 + rng.normal(size=(runs, 3)) * rng.uniform(0.1, 10.0, size=(runs, 1))
    z = np.concatenate([data.YANG2012_TABLE1.values.T, triples])
    if settings.get("rule", "averages") == "sums":
        members = rd.fuse_epochs(data.YANG2012_TABLE1.values.T, "optimal_fusion_set", threshold="sum").members
        return Proposition(bool(not members.all()), "as printed, d̄ is the sum of all d_i: on Table 1 every reading "
                           f"is kept ({int(members.sum())} of {members.size}), none is dropped")
    d = np.abs(z[:, :, None] - z[:, None, :]).mean(axis=2)
    m = rd.fuse_epochs(z, "optimal_fusion_set").members
    far = np.all(np.where(m, d, -np.inf).max(axis=1) < np.where(~m, d, np.inf).min(axis=1))
    drop = bool(np.all(m.sum(axis=1) < z.shape[1]))
    return Proposition(bool(far and drop), f"on Table 1 and {len(z) - 6} simulated triples every dropped reading has a "
                       "larger mean distance to the others than every kept one, and every epoch drops at least one",
                       runs=int(runs))


def ev_eq9_defined(settings: Mapping[str, object], *, seed: int = SEED, runs: int = N_RUNS) -> Proposition:
    """Eqs. 9-11 give weights for every set: false when a row of C is constant (one-member sets)."""
    one = int(np.sum(rd.fuse_epochs(data.YANG2012_TABLE1.values.T, "optimal_fusion_set").members.sum(axis=1) == 1))
    return Proposition(False, f"eq. 9 divides by zero for constant rows of C: one-member sets ({one} of Table 1's 6 "
                       "observations), identical readings")


# --------------------------------------------------------------------------- the ledger
def evidence(seed: int = SEED, runs: int = N_RUNS, claims: ClaimsFile | None = None) -> dict[str, dict[str, object]]:
    """The evidence of every record of the chapter, every reading, from the functions the claim file names.

    Parameters
    ----------
    seed, runs : int
        Seed and Monte-Carlo runs of the stochastic readings (a reading that states its own ``runs`` in
        the claim file, e.g. the fair study's, runs that many).
    claims : ClaimsFile, optional
        Default ``book/claims/yang2012optimal.yaml``.

    Returns
    -------
    dict
        Record id -> reading key -> evidence, for :func:`fusion.book.claims.build_ledger`.
    """
    cf = claims or load_claims(claims_dir() / f"{SOURCE}.yaml")
    out: dict[str, dict[str, object]] = {}
    for spec in cf.records:
        if spec.chapter != CHAPTER:
            continue
        if not spec.evidence:
            raise ValueError(f"record {spec.id} names no evidence function")
        mod, name = spec.evidence.split(":")
        fn = getattr(importlib.import_module(mod), name)
        readings = spec.readings or (ReadingSpec("primary", "", "", "primary", {}),)
        if all(r.key != "primary" for r in readings):
            readings = (ReadingSpec("primary", "", "", "primary", {}),) + tuple(readings)
        out[spec.id] = {r.key: fn(dict(r.settings), seed=seed, runs=r.runs or runs) for r in readings}
    return out


def claim_values(seed: int = SEED, runs: int = N_RUNS) -> dict[str, object]:
    """The computed numbers the claim file's texts quote (``{name}`` fields), glued by the chapter too.

    Parameters
    ----------
    seed, runs : int

    Returns
    -------
    dict
        Glue key -> value.
    """
    t1 = data.YANG2012_TABLE1.values
    fe = ofs_audit.full_explanation(joint())
    sup = [table1_totals(t1, a)["sup"] for a in (*ALPHAS, 0.25)]
    return {
        "ofs_claim_obs1_pub": float(data.YANG2012_TABLE2.columns["optimal_set"][0]), "ofs_claim_obs1_max": float(t1[:, 0].max()),
        "ofs_claim_joint_n_hyp": f"{joint().n_hypotheses:,}",
        "ofs_claim_fix_text": "none" if fe is None else ofs_audit.describe(fe[0]),
        "ofs_claim_fix_program": "none" if fe is None else ofs_audit.PROGRAMS[fe[1]],
        "ofs_claim_our_total_ofs": rounded(table1_totals(t1)["ofs"]),
        "ofs_claim_sup_total_min": rounded(min(sup), 2), "ofs_claim_sup_total_max": rounded(max(sup), 2),
        "ofs_claim_pub_total_rel": float(data.YANG2012_TOTALS.columns["reliability"][0]),
        "ofs_claim_sup_col_sum": rounded(float(np.sum(data.YANG2012_TABLE3.columns["reliability_abs_error"])), 4),
        "ofs_claim_inv_var_bound": rounded(thermocouples.best_linear_abs_error(thermocouples.DEFAULT_SIGMAS), 3),
        "ofs_claim_def3_off": rounded(not_neighbourhood_share(int(seed), int(runs)), 4),
    }



#: The ledger numbers the chapter's prose quotes: record id -> fields (see :func:`ledger_numbers`).
LEDGER_GLUE: dict[str, tuple[str, ...]] = {
    "yang-totals-ranking-mean": ("status",),
    "yang-totals-ranking-support": ("status",),
    "yang-median-total": ("status",),
    "yang-obs-closer": ("status",),
    "yang-membership-free": ("status",),
    "yang-fig2-vs-mean": ("diff", "hi", "lo", "margin", "rel", "robustness", "status"),
    "yang-fig2-fluctuation": ("robustness", "status"),
    "yang-fig2-vs-support": ("hi", "lo"),
    "yang-fig2-fluctuation-support": ("a", "b"),
    "yang-fig4-vs-mean": ("hi", "lo", "robustness", "status"),
    "yang-fig4-whole-vs-mean": ("robustness",),
    "yang-fig4-fluctuation-mean": ("a", "b"),
    "yang-fig4-vs-support": ("hi", "lo"),
    "yang-fig4-whole-vs-support": ("a", "b", "diff", "hi", "lo", "margin"),
    "yang-fig4-fluctuation-support": ("b",),
    "yang-fig4-unaffected": ("a", "b", "hi", "lo", "margin", "robustness", "status"),
    "yang-weights-reasonable": ("robustness", "status", "runs"),
    "yang-weights-stability": ("a", "b", "robustness", "status"),
}


def ledger_numbers(ledger: Ledger, prefix: str = "ofs_",
                   fields: Mapping[str, Sequence[str]] | None = None) -> dict[str, float | str]:
    """Glue-ready statuses, robustness lines and paired-comparison numbers of every record of a ledger.

    Parameters
    ----------
    ledger : Ledger
    prefix : str
        Glue-key prefix of the chapter.
    fields : mapping of record id to field names, optional
        Keep only these fields (``"status"``, ``"robustness"`` and those of :func:`comparison_numbers`) of these
        records; default every field of every record.

    Returns
    -------
    dict
        For every record ``<prefix><id>_status`` and ``<prefix><id>_robustness``; for each record whose
        primary evidence is a :class:`~fusion.book.ledger.Comparison` (or, when the baseline is undefined, whose
        stand-in reading is), :func:`comparison_numbers` under ``<prefix><id>``. Dashes of the id become
        underscores.
    """
    out: dict[str, float | str] = {}
    for c in ledger.claims:
        key = prefix + c.id.replace("-", "_")
        out[key + "_status"] = c.status
        out[key + "_robustness"] = c.robustness
        ev = c.evidence
        if isinstance(ev, Unverifiable):
            ev = next((a.evidence for a in c.alternatives if a.kind == "stand-in"), ev)
        if isinstance(ev, Comparison):
            out.update(comparison_numbers(ev, key))
    if fields is None:
        return out
    unknown = set(fields) - {c.id for c in ledger.claims}
    if unknown:
        raise ValueError(f"fields names records not in the ledger: {sorted(unknown)}")
    want = [prefix + rid.replace("-", "_") + "_" + f for rid, fs in fields.items() for f in fs]
    missing = [k for k in want if k not in out]
    if missing:
        raise ValueError(f"fields names numbers the ledger does not give: {missing}")
    return {k: out[k] for k in want}


def comparison_numbers(comparison: Comparison, key: str,
                       fields: Sequence[str] | None = None) -> dict[str, float | int]:
    """Glue-ready numbers of one paired comparison.

    Parameters
    ----------
    comparison : Comparison
    key : str
        Glue-key stem; the keys are ``<key>_{a,b,diff,lo,hi,margin,rel}`` (means of A and B, the deciding
        statistic of the difference and its 95 % interval, the practical margin, all °C and rounded to 4
        decimals; A's mean relative to B's, minus one) and ``<key>_runs``.
    fields : sequence of str, optional
        Keep only these suffixes (default all).

    Returns
    -------
    dict
    """
    mean, lo, hi = comparison.interval()
    vals = {"a": float(np.mean(comparison.a)), "b": float(np.mean(comparison.b)), "diff": mean, "lo": lo, "hi": hi,
            "margin": comparison.margin}
    out: dict[str, float | int] = {f"{key}_{k}": rounded(v, 4) for k, v in vals.items()}
    out[key + "_rel"] = rounded(float(np.mean(comparison.a)) / float(np.mean(comparison.b)) - 1, 4)
    out[key + "_runs"] = comparison.runs
    return out if fields is None else {f"{key}_{f}": out[f"{key}_{f}"] for f in fields}


def mc_numbers(mc: pd.DataFrame, studies: Mapping[str, PairedStudy], sigmas: Mapping[str, object],
               n_runs: int) -> dict[str, object]:
    """The numbers chapter 01's prose quotes from the Monte-Carlo table (glue keys ``ofs_mc_*``).

    Parameters
    ----------
    mc : pandas.DataFrame
        :func:`mc_table` of ``studies``.
    studies : mapping
        Noise label -> :class:`~fusion.scenarios.thermocouples.PairedStudy` (unequal noise first, then equal).
    sigmas : mapping
        The same labels -> noise SD (°C), in the same order.
    n_runs : int
        Runs of each study.

    Returns
    -------
    dict
        Glue key -> value (mean absolute errors in °C, 3 decimals; shares; the direct mean-square-error ratio).

    References
    ----------
    * Yang G. N., Feng X. F., Fan L. J. (2012). Multi-sensor data fusion algorithm based on optimal fusion set.
    """
    hs, eq = sigmas
    L = METHOD_LABELS
    mcv = {(s, f, m): rounded(mc.loc[(s, f), L[m]], 3) for s in sigmas for f in ("no failure", "failure") for m in METHODS}
    share = mc["share of epochs where the optimal set is best"]
    return {
        "ofs_n_runs": n_runs,
        "ofs_mc_eq_clean_ofs": mcv[(eq, "no failure", "optimal_fusion_set")], "ofs_mc_eq_clean_mean": mcv[(eq, "no failure", "mean")],
        "ofs_mc_hs_clean_ofs": mcv[(hs, "no failure", "optimal_fusion_set")], "ofs_mc_hs_clean_mean": mcv[(hs, "no failure", "mean")],
        "ofs_mc_hs_clean_sup": mcv[(hs, "no failure", "support_degree")],
        "ofs_mc_eq_bound": rounded(mc.loc[(eq, "no failure"), "bound (no failure)"], 3),
        "ofs_mc_hs_fail_ofs": mcv[(hs, "failure", "optimal_fusion_set")], "ofs_mc_hs_fail_mean": mcv[(hs, "failure", "mean")],
        "ofs_mc_hs_fail_sup": mcv[(hs, "failure", "support_degree")],
        "ofs_mc_eq_fail_ofs": mcv[(eq, "failure", "optimal_fusion_set")], "ofs_mc_eq_fail_sup": mcv[(eq, "failure", "support_degree")],
        "ofs_mc_best_share_max": rounded(share.max(), 3), "ofs_mc_best_share_min": rounded(share.min(), 3),
        "ofs_mc_mse_ratio": rounded(float(np.mean(studies[eq].clean["optimal_fusion_set"] ** 2)
                                          / np.mean(studies[eq].clean["mean"] ** 2)), 3),
        "ofs_set_size_hs": rounded(studies[hs].set_size.mean(), 2), "ofs_set_size_eq": rounded(studies[eq].set_size.mean(), 2),
    }


def table_numbers(tabs: TableReproduction) -> dict[str, object]:
    """The numbers chapter 01's prose quotes from Tables 2-3 reproduced (glue keys ``ofs_our_total_*``, ...).

    Parameters
    ----------
    tabs : TableReproduction
        The result of :func:`reproduce_tables`.

    Returns
    -------
    dict
        Glue key -> value: our total absolute errors (°C), which observations are reproduced at the
        printed precision, the total under the one-member guard, the ranking margin, and the support
        degree's total at each α.

    References
    ----------
    * Yang G. N., Feng X. F., Fan L. J. (2012). Multi-sensor data fusion algorithm based on optimal fusion set.
    """
    T1 = data.YANG2012_TABLE1.values
    t2, t3 = data.YANG2012_TABLE2.columns, data.YANG2012_TABLE3.columns
    TRUE = data.YANG2012_TRUE_VALUE
    ours = {"ofs": tabs.ofs, "mean": tabs.mean, "sup": tabs.sup}
    ok = np.abs(tabs.ofs - t2["optimal_set"]) < 5e-5
    mean_ok = np.abs(tabs.mean - t2["mean"]) < 5e-5
    OBS = np.arange(1, 7)
    return {
        **{f"ofs_our_total_{k}": rounded(np.abs(v - TRUE).sum()) for k, v in ours.items() if k != "sup"},
        "ofs_n_reproduced": int(ok.sum()),
        "ofs_reproduced_obs": ", ".join(str(o) for o in OBS[ok]),
        "ofs_mean_bad_obs": ", ".join(str(o) for o in OBS[~mean_ok]),
        "ofs_guard_total": rounded(np.abs(np.where(rd.fuse_epochs(T1.T, "optimal_fusion_set").members.sum(axis=1) == 1,
                                                   tabs.mean, tabs.ofs) - TRUE).sum()),
        "ofs_sup_total_by_alpha": ", ".join(
            f"{np.abs(rd.fuse_epochs(T1.T, 'support_degree', alpha=a).values - TRUE).sum():.2f} °C at α = {a:g}"
            for a in sorted((*ALPHAS, 0.25))),
    }


def observation_numbers(tabs: TableReproduction) -> dict[str, object]:
    """The numbers chapter 01's prose quotes about observations 1, 2, 5 and 6 of Table 2 (glue keys ``ofs_obs*``).

    Parameters
    ----------
    tabs : TableReproduction
        The result of :func:`reproduce_tables`.

    Returns
    -------
    dict
        Glue key -> value: published and reproduced fused values (°C), the change of observation 5's
        sum implied by the published mean, the corrected reading and the fused values after it.

    References
    ----------
    * Yang G. N., Feng X. F., Fan L. J. (2012). Multi-sensor data fusion algorithm based on optimal fusion set.
    """
    T1 = data.YANG2012_TABLE1.values
    t2 = data.YANG2012_TABLE2.columns
    return {
        "ofs_obs1_pub": float(t2["optimal_set"][0]), "ofs_obs1_pub_err": float(t2["optimal_set_abs_error"][0]),
        "ofs_obs2_pub": float(t2["optimal_set"][1]), "ofs_obs1_max": float(T1[:, 0].max()),
        "ofs_obs5_sum_change": rounded(audit.implied_sum_change(T1[:, 4], t2["mean"][4]), 3),
        "ofs_obs5_pub": float(t2["optimal_set"][4]),
        "ofs_obs1_ours": rounded(tabs.ofs[0]),
        "ofs_obs6_pub_err": float(t2["optimal_set_abs_error"][5]), "ofs_obs6_pub_mean_err": float(t2["mean_abs_error"][5]),
    }


def closing_numbers(study_hs: PairedStudy, study_eq: PairedStudy, weights: object,
                    judged: Mapping[tuple[str, str], Comparison], relative_margin: float) -> dict[str, object]:
    """The glue values of the chapter's verdict paragraphs that are not records' numbers (chapter bookkeeping).

    Parameters
    ----------
    study_hs, study_eq : PairedStudy
        The failure study with the primary (unequal) noise levels and with equal noise.
    weights : WeightStudy
        :func:`weight_study` at the chapter's seed and runs (its ``member`` shares).
    judged : mapping
        (record id, reading key) → the reading's comparison with the claim file's margin applied.
    relative_margin : float
        The claim file's margin of the MAE quantity.

    Returns
    -------
    dict
        Glue key → value (rounded as the prose prints them).
    """
    unaff = judged[("yang-fig4-unaffected", "equal-noise")]
    return {"ofs_margin": relative_margin,
            "ofs_member_s1": rounded(weights.member[0], 3), "ofs_member_s10": rounded(weights.member[-1], 3),
            "ofs_fig4_unaffected_eq_status": unaff.status(),
            **{f"ofs_abl_uni_{k}_rel": rounded(float(np.mean(c.b)) / float(np.mean(c.a)) - 1, 4)
               for k, c in (("clean", judged[("yang-weights-reasonable", "primary")]),
                            ("fail", judged[("yang-weights-reasonable", "failure")]))},
            "ofs_abl_fail_won": int(np.sum(np.asarray(judged[("yang-weights-reasonable", "failure")].a)
                                           < np.asarray(judged[("yang-weights-reasonable", "failure")].b))),
            "ofs_scale_all_equiv": judged[("yang-membership-free", "scale")].status() == "reproduced",
            "ofs_keep_hs": rounded(study_hs.set_size.mean(), 2), "ofs_keep_eq": rounded(study_eq.set_size.mean(), 2),
            "ofs_member4_hs": rounded(study_hs.failed_member_share[0], 3),
            "ofs_member10_hs": rounded(study_hs.failed_member_share[1], 3),
            "ofs_member4_eq": rounded(study_eq.failed_member_share[0], 3),
            "ofs_whole_eq_ofs": rounded(study_eq.mae("optimal_fusion_set", True, window=False).mean()),
            "ofs_whole_eq_sup": rounded(study_eq.mae("support_degree", True, window=False).mean())}


#: Whose claim a record is (R8), in the words of the chapter's verdict table.
CLAIMANT_WORDS: dict[str, str] = {"source": "the source (printed)",
                                  "implied": "the book's reading of the source's purpose",
                                  "book": "the book's own question"}


def verdict_table(ledger: Ledger) -> pd.DataFrame:
    """The chapter's verdict table: :meth:`~fusion.book.ledger.Ledger.table` with a column saying whose claim each record is (R8).

    Only the records marked "the source (printed)" are the source's claims; the book's reading of the source's
    purpose (``implied``) and the book's own questions (``book``) are the book's questions, marked as such from the
    claim file's ``claimant``.

    Parameters
    ----------
    ledger : Ledger

    Returns
    -------
    DataFrame
    """
    t = ledger.table()
    who = {c.id: CLAIMANT_WORDS[c.claimant] for c in ledger.claims}
    return t.assign(**{"whose claim": [who[i] for i in t.index]})[["whose claim", "where", "status", "robustness"]]


# --------------------------------------------------------------------------- open points of the 2026-12-05 review
def healthy_dropped_share(seed: int, runs: int, noise: str = "unequal") -> dict[str, float]:
    """Share of the healthy sensors' readings the set drops at the epochs 50-80, with and without the failure.

    The draws are those of :func:`faulty_member_share` under the "fixed" failure (same seed): sensors 4 and 10
    are biased by +4 and +8 °C at samples 50-80, the other eight are healthy. The same epochs without the
    failure give the rate at which the set drops valid readings anyway.

    Parameters
    ----------
    seed, runs : int
    noise : str
        A key of :data:`NOISE`.

    Returns
    -------
    dict
        ``"failure"``, ``"clean"``: share of the eight healthy sensors' readings outside the set over the
        epochs 50-80; ``"epochs"``: number of epochs judged.
    """
    rng = np.random.default_rng(int(seed))
    z = thermocouples.simulate(rng, sigma=NOISE[_noise({"noise": noise})], n_runs=int(runs))
    zf = thermocouples.random_failure(z, rng, "fixed")
    healthy = np.setdiff1d(np.arange(10), [3, 9])
    out: dict[str, float] = {}
    for key, arr in (("failure", zf), ("clean", z)):
        m = rd.fuse_epochs(arr[:, 49:80].reshape(-1, 10), "optimal_fusion_set").members
        out[key] = float(1.0 - m[:, healthy].mean())
    out["epochs"] = float(int(runs) * 31)
    return out


def support_bound_check(seed: int, n: int = 100_000, alpha: float = 0.25) -> dict[str, int]:
    """Check on random triples that support weighting cannot fall below the mean when the low reading is least supported.

    For three readings with gaps g1 (low to middle) >= g2 (middle to high) the low reading has the smallest
    support of :func:`fusion.readings.support_degree`, and the fused value is then at least the mean (the
    structural reason observations 3 and 4 of source Table 3 are out of reach). Readings are drawn uniform on
    [890, 910] °C.

    Parameters
    ----------
    seed : int
    n : int
        Number of random triples.
    alpha : float
        Support sharpness (°C⁻²).

    Returns
    -------
    dict
        ``"triples"``: triples drawn; ``"low_least"``: triples whose low reading is the least supported;
        ``"below"``: of those, triples whose fused value lies below the mean by more than 1e-9 °C.
    """
    x = np.random.default_rng(int(seed)).uniform(890.0, 910.0, (int(n), 3))
    fused = rd.fuse_epochs(x, "support_degree", alpha=float(alpha)).values
    sup = np.exp(-float(alpha) * (x[:, :, None] - x[:, None, :]) ** 2).sum(axis=2)
    low = np.argmin(x, axis=1)
    least = np.take_along_axis(sup, low[:, None], axis=1)[:, 0] <= sup.min(axis=1)
    below = fused < x.mean(axis=1) - 1e-9
    return {"triples": int(n), "low_least": int(least.sum()), "below": int((least & below).sum())}
