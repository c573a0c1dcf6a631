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

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import pandas as pd
from matplotlib.figure import Figure
from numpy.typing import ArrayLike

from fusion import data
from fusion import readings as rd
from fusion._validation import FloatArray
from fusion.book import audit
from fusion.book.chapters import ofs_audit
from scipy import stats

from fusion.book.ledger import Alternative, Claim, Comparison, Ledger, Proposition, PublishedValues, Unverifiable
from fusion.book.style import METHOD_LABELS, color, new_figure
from fusion.book.tables import rounded, side_by_side
from fusion.readings.robust import robust_fuse
from fusion.scenarios import thermocouples
from fusion.scenarios.thermocouples import PairedStudy

__all__ = [
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
    "EQUIVALENCE_MARGIN",
    "equivalence",
    "claims",
    "ledger_numbers",
]

#: BibTeX key of the source.
SOURCE = "yang2012optimal"

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


# --------------------------------------------------------------------------- claims
_NOISE = ("noise σ 0.5-2.0 °C evenly spaced over the ten sensors (the source gives none; identical "
          "thermocouples, equal σ, is the alternative reading)")
_RUNS = "runs of 100 samples; the failure case uses the same draws plus the biases"
_SUP = ("ref. [11]'s support-degree rule is not given in the source; compared here with a rebuilt "
        "substitute (Yager's power average, α = 0.25 °C⁻²)")
_FIXED = ("'randomly' (随机地) read as: biases +4 and +8 °C on sensors 4 and 10 at every sample 50-80 of "
          "every run; random bias sizes and randomly chosen samples are the alternative readings")

#: Equivalence margin of every "no effect" claim: a paired difference within ± this share of the
#: reference's mean counts as no effect (two one-sided t tests at 5 % each).
EQUIVALENCE_MARGIN = 0.05


def equivalence(a: ArrayLike, b: ArrayLike, what: str, margin: float = EQUIVALENCE_MARGIN,
                level: float = 0.05) -> Proposition:
    r"""Paired equivalence test (two one-sided t tests, TOST) of "A does not differ from B".

    The claim holds when the mean paired difference :math:`\bar d = \overline{a - b}` is shown
    to lie within :math:`\pm\delta`, :math:`\delta` = ``margin`` × mean(b): both one-sided
    tests (:func:`scipy.stats.ttest_1samp` on the differences against :math:`-\delta`,
    alternative "greater", and against :math:`+\delta`, alternative "less") reject at ``level``.

    Parameters
    ----------
    a, b : array_like, shape (n_runs,)
        Paired per-run metrics.
    what : str
        What A and B are, for the record's text.
    margin : float
        Relative margin (share of B's mean), in (0, 1).
    level : float
        Level of each one-sided test.

    Returns
    -------
    Proposition
        Holds iff equivalence is shown; the text gives both means, the relative change, the
        margin and the larger of the two p-values.

    References
    ----------
    Schuirmann, D. J. (1987). A comparison of the two one-sided tests procedure and the power
    approach for assessing the equivalence of average bioavailability. *Journal of
    Pharmacokinetics and Biopharmaceutics*, 15(6), 657-680.
    """
    x, y = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    if x.ndim != 1 or x.shape != y.shape or x.size < 2:
        raise ValueError("a and b must be paired 1-d arrays of the same length >= 2")
    if not (np.all(np.isfinite(x)) and np.all(np.isfinite(y))):
        raise ValueError("a and b must be finite")
    if not 0 < margin < 1:
        raise ValueError(f"margin must lie in (0, 1), got {margin!r}")
    if not 0 < level < 0.5:
        raise ValueError(f"level must lie in (0, 0.5), got {level!r}")
    d = x - y
    delta = margin * float(np.mean(y))
    if float(np.ptp(d)) == 0.0:
        p = 0.0 if abs(float(d[0])) < delta else 1.0
    else:
        p_lo = float(stats.ttest_1samp(d, -delta, alternative="greater").pvalue)
        p_hi = float(stats.ttest_1samp(d, delta, alternative="less").pvalue)
        p = max(p_lo, p_hi)
    ma, mb = float(np.mean(x)), float(np.mean(y))
    shown = "shown" if p < level else "not shown"
    p_txt = "p < 0.001" if p < 0.001 else f"p = {p:.3f}"
    return Proposition(bool(p < level),
                       f"{what}: {ma:.4f} vs {mb:.4f} °C ({ma / mb - 1:+.1%}); equivalence within "
                       f"±{margin:.0%} (±{delta:.4f} °C) {shown} (TOST, {p_txt}, {x.size} paired runs)")


def _cmp(study: PairedStudy, a: str, b: str, failure: bool, metric: str = "mae", whole: bool = False) -> Comparison:
    fn = study.mae if metric == "mae" else study.fluctuation
    what = ("mean absolute error" if metric == "mae" else "SD of the absolute error over samples")
    window = False if whole else None
    where = "samples 50-80" if failure and not whole else "samples 1-100"
    return Comparison(fn(a, failure, window), fn(b, failure, window), METHOD_LABELS.get(a, a),
                      METHOD_LABELS.get(b, b), "less", f"per-run {what} on {where} (°C)", seed=study.seed)


def _alpha_alts(alpha_study: PairedStudy | None, failure: bool) -> tuple[Alternative, ...]:
    """The optimal set against the support degree at every α of ``alpha_study`` (same draws)."""
    if alpha_study is None:
        return ()
    return tuple(Alternative("support-degree α", f"α = {k.split('= ')[1]} °C⁻² (primary noise, same draws)",
                             _cmp(alpha_study, "optimal_fusion_set", k, failure))
                 for k in alpha_study.clean if k.startswith("support degree, α = "))


def claims(tables: TableReproduction, study: PairedStudy, study_equal: PairedStudy,
           sum_members: ArrayLike, scales: ArrayLike, sweep_clean: ArrayLike, sweep_fail: ArrayLike,
           table1_scale_values: ArrayLike, unit: Mapping[str, float | bool],
           alpha_study: PairedStudy | None = None,
           family_clean: Mapping[str, ArrayLike] | None = None,
           family_fail: Mapping[str, ArrayLike] | None = None,
           joint: ofs_audit.AuditResult | None = None,
           support_table: pd.DataFrame | None = None,
           fair: object | None = None,
           ablation: Mapping[str, Mapping[str, ArrayLike]] | None = None,
           failure_studies: Mapping[tuple[str, str], PairedStudy] | None = None) -> Ledger:
    """The claims ledger of Yang, Feng & Fan (2012), built from the chapter's results.

    Parameters
    ----------
    tables : TableReproduction
        From :func:`reproduce_tables`.
    study, study_equal : PairedStudy
        The paired Monte-Carlo study with the default noise levels and with ten equal
        sensors (σ = 1 °C), same seed.
    sum_members : array_like of bool, shape (6, 3)
        Optimal-set members of Table 1 with eqs. 3-4 read literally as sums.
    scales : array_like, shape (k,)
        Scales of eq. 6 swept (°C).
    sweep_clean, sweep_fail : array_like, shape (k, n_runs)
        From :func:`fusion.scenarios.thermocouples.scale_sweep` without the failure (all samples)
        and with it (samples 50-80); each scale is tested for equivalence with 2 °C.
    table1_scale_values : array_like, shape (k, 6)
        Optimal-set values of Table 1 for each scale (°C).
    unit : mapping
        From :func:`unit_dependence`.
    alpha_study : PairedStudy, optional
        The primary study's draws (same seed and noise) fused by :func:`alpha_methods`: the
        support-degree comparisons at the other α are run as alternatives.
    family_clean, family_fail : mapping of label to array_like, shape (n_runs,), optional
        From :func:`family_mae` on the primary draws without failure and with it (samples
        50-80); the first label is eq. 6. Each other family is an alternative of
        ``yang-membership-free``.
    joint : AuditResult, optional
        From :func:`fusion.book.chapters.ofs_audit.joint_audit`: its full explanation (if any) is
        run as the "data and program" alternative of the Table 2 and totals records and as the
        corrected-data alternative of the ranking and support-degree records.
    support_table : DataFrame, optional
        From :func:`fusion.book.chapters.ofs_audit.support_variants`: every support-degree variant
        becomes an alternative of ``yang-table3-support``.
    fair : FairStudy, optional
        From :func:`fusion.book.chapters.ofs_fair.fair_study`: its noise-spread points become
        alternatives of ``yang-fig2-vs-mean``.
    ablation : mapping of case label to the output of :func:`weight_ablation`, optional
        The primary draws without failure (first) and with it; with ``fair``, the records of
        ``yang-weights-reasonable``.
    failure_studies : mapping of (failure mode, noise label) to PairedStudy, optional
        The same draws as ``study``/``study_equal`` under the other readings of "randomly"
        (:data:`fusion.scenarios.thermocouples.FAILURE_MODES`); alternatives of every failure record.

    Returns
    -------
    Ledger
    """
    t2, t3 = data.YANG2012_TABLE2.columns, data.YANG2012_TABLE3.columns
    tot = data.YANG2012_TOTALS.columns
    truth = data.YANG2012_TRUE_VALUE
    t1 = data.YANG2012_TABLE1.values
    led = Ledger(SOURCE)
    fe = None if joint is None else ofs_audit.full_explanation(joint)
    alt_ofs: tuple[str, ...] = ()
    alt_mean: tuple[str, ...] = ()
    alt_tot: tuple[str, ...] = ()
    alt_sup: tuple[Alternative, ...] = ()
    t1_fix = None
    if fe is not None:
        fix, prog, rule = fe
        ex = ofs_audit.explain(fix, prog, rule)
        t1_fix = t1.copy()
        t1_fix[fix.sensor - 1, fix.obs - 1] = fix.value
        fixed = ofs_audit.describe(fix)
        what = f"{fixed}; program: {ofs_audit.PROGRAMS[prog]}; set rule: {rule}"
        n_ofs = int(np.sum(np.abs(ex[("optimal set", "reconstructed")].to_numpy()[:6] - t2["optimal_set"]) < _TOL))
        n_tot = int(np.sum(np.abs(np.array([ex.loc["total", ("mean error", "reconstructed")],
                                            ex.loc["total", ("optimal-set error", "reconstructed")]])
                              - np.array([tot["mean"][0], tot["optimal_set"][0]])) < _TOL))
        expl = (f"; explanation of the discrepancy (not a reading of the source): {what} gives {{}}. Of the 26 printed "
                "values of Table 2 and the totals, 14 (absolute errors, totals) follow from the 12 fused values, "
                "8 of which Table 1 already gives; the hypothesis, chosen among "
                f"{joint.n_hypotheses:,} scored, has to account for 4")
        alt_ofs = (expl.format(f"{n_ofs} of 6 values"),)
        alt_mean = (f"; explanation of the discrepancy (not a reading of the source): {fixed} gives all 6 means (any "
                    f"change of one reading of observation {fix.obs} by the same amount does too)",)
        alt_tot = (expl.format(f"{n_tot} of 2 totals (mean, optimal set)"),)
        roots = [audit.parameters_matching(t1_fix[:, k], t3["reliability"][k], "support_degree", "alpha", 1e-6, 1e3)
                 for k in range(t1.shape[1])]
        k = fix.obs - 1
        alt_sup = (Alternative("data", f"{fixed}, α searched per observation", Proposition(
            False, f"observation {fix.obs} becomes reachable (α = {', '.join(f'{a:.3g}' for a in roots[k]) or 'none'} "
                   "°C⁻²); unreachable for every α: observations "
                   + ", ".join(str(j + 1) for j in range(len(roots)) if len(roots[j]) == 0))),)
    if support_table is not None:
        for (kern, agg), r in support_table.iterrows():
            for lab in dict.fromkeys(c[0] for c in support_table.columns):
                alt_sup = alt_sup + (Alternative(
                    "support-degree variant", f"{kern}, weights from {agg}; {lab}; α searched per observation",
                    Proposition(bool(r[(lab, "one α for all six")]),
                                f"reachable at observations {r[(lab, 'reachable observations')]}; "
                                + ("one α reaches all six" if r[(lab, "one α for all six")]
                                   else "no single α reaches all six"))),)
    hull = "every method here is a convex combination, so each fused value lies within its readings"

    led.add(Claim(
        "yang-table2-ofs", SOURCE, "Table 2, optimal fusion set",
        "The optimal fusion set fuses the six observations of Table 1 to the printed values.",
        "6 values, 4 decimals (°C)", PublishedValues(t2["optimal_set"], tables.ofs, 4, "°C"),
        "ofs-crit-tables", bound=hull + f"; observation 1's {t2['optimal_set'][0]:.2f} °C lies above its "
        f"largest reading {t1[:, 0].max():.1f} °C" + "".join(alt_ofs),
        assumptions=("eqs. 3-4 read as averages",), critiques=("ofs-crit-tables",)))
    led.add(Claim(
        "yang-table2-mean", SOURCE, "Table 2, arithmetic mean",
        "The arithmetic means of the six observations are the printed values.",
        "6 values, 4 decimals (°C)", PublishedValues(t2["mean"], tables.mean, 4, "°C"), "ofs-crit-tables",
        bound="exact: the mean of three readings" + "".join(alt_mean)))
    led.add(Claim(
        "yang-table3-support", SOURCE, "Table 3, support-degree fusion of ref. [11]",
        "The support-degree fusion of Sun & Jing (2005) gives the printed values on Table 1.",
        "6 values, 4 decimals (°C)",
        Unverifiable("the source does not give the rule of ref. [11], and that paper is not available to us; "
                     "the rebuilt substitutes below are readings, not the method"),
        "ofs-crit-tables",
        bound="no support weighting computed from the current observation alone can move below the mean when "
              "the low reading is the least supported (observations 3-4); history-based support can",
        assumptions=(_SUP,),
        alternatives=(Alternative("support-degree rule", "rebuilt substitute: Yager's power average, α = 0.25 °C⁻²",
                                  PublishedValues(t3["reliability"], tables.sup, 4, "°C")), *alt_sup)))
    our_tot = [float(np.abs(v - truth).sum()) for v in (tables.mean, tables.sup, tables.ofs)]
    led.add(Claim(
        "yang-totals", SOURCE, "Text after Table 3: total absolute errors",
        "The total absolute errors are 16.4333 (mean), 16.3089 (support degree) and 11.4500 °C (optimal set).",
        "16.4333, 16.3089, 11.4500 °C",
        PublishedValues([tot["mean"][0], tot["reliability"][0], tot["optimal_set"][0]], our_tot, 4, "°C"),
        "ofs-crit-tables", assumptions=(_SUP,), bound="exact sums of the fused values' errors" + "".join(alt_tot)))
    rank = our_tot[2] < min(our_tot[:2])
    lone = rd.fuse_epochs(t1.T, "optimal_fusion_set").members.sum(axis=1) == 1
    guard_tot = float(np.abs(np.where(lone, tables.mean, tables.ofs) - truth).sum())

    def totals(x: FloatArray, alpha: float = 0.25) -> tuple[float, float, float]:
        """Total absolute errors of the optimal set, the mean and the support degree on readings x."""
        return tuple(float(np.abs(rd.fuse_epochs(x.T, m, **o).values - truth).sum()) for m, o in
                     (("optimal_fusion_set", {}), ("mean", {}), ("support_degree", {"alpha": alpha})))

    def ranking(x: FloatArray, alpha: float, what: str) -> Proposition:
        o, m, sd = totals(x, alpha)
        return Proposition(bool(o < min(m, sd)), f"{what}: optimal set {o:.4f}, mean {m:.4f}, "
                                                 f"support degree {sd:.4f} °C")

    led.add(Claim(
        "yang-totals-ranking", SOURCE, "Text after Table 3: ranking",
        "On Table 1 the optimal fusion set has the smallest total absolute error of the three methods.",
        "qualitative",
        Proposition(bool(rank), f"recomputed totals: optimal set {our_tot[2]:.4f}, mean {our_tot[0]:.4f}, "
                                f"support degree {our_tot[1]:.4f} °C"),
        "ofs-crit-tables", assumptions=("eqs. 3-4 read as averages", _SUP,
                                        "a one-member set returns its reading (eq. 9 divides by zero there)"),
        bound="the optimal set's total does not depend on α; the support degree's does",
        alternatives=(
            Alternative("one-member guard", "a lone member falls back to the mean of all readings", Proposition(
                bool(guard_tot < min(our_tot[:2])), f"recomputed totals: optimal set {guard_tot:.4f}, mean "
                f"{our_tot[0]:.4f}, support degree {our_tot[1]:.4f} °C")),
            Alternative("support-degree total", "as printed (16.3089 °C)", Proposition(
                bool(our_tot[2] < min(our_tot[0], tot["reliability"][0])),
                f"optimal set {our_tot[2]:.4f} °C against the printed support-degree total")),
            *(Alternative("support-degree α", f"α = {a:g} °C⁻²", ranking(t1, a, "recomputed totals"))
              for a in ALPHAS),
            *(() if t1_fix is None or fe is None else (Alternative(
                "data", f"observation {fe[0].obs} corrected as the joint audit finds ({ofs_audit.describe(fe[0])}), "
                "eqs. 3-12 computed correctly, α = 0.25 °C⁻²", ranking(t1_fix, 0.25, "recomputed totals")),)))))
    obs = np.array([1, 3, 4, 5, 6])
    e_ofs, e_mean, e_sup = (np.abs(v - truth) for v in (tables.ofs, tables.mean, tables.sup))
    better = (e_ofs < e_mean) & (e_ofs < e_sup)
    pub_better = ((t2["optimal_set_abs_error"] < t2["mean_abs_error"])
                  & (t2["optimal_set_abs_error"] < t3["reliability_abs_error"]))
    led.add(Claim(
        "yang-obs-closer", SOURCE, "Text after Table 3: observations 1, 3, 4, 5, 6",
        "At observations 1, 3, 4, 5 and 6 the optimal fusion set is closer to 900 °C than both other methods.",
        "qualitative",
        Proposition(bool(better[obs - 1].all()),
                    "recomputed from Table 1, closer at observations "
                    + (", ".join(str(o) for o in np.flatnonzero(better) + 1) or "none")),
        "ofs-crit-tables", assumptions=(_SUP,),
        alternatives=(Alternative("data", "the source's own Tables 2-3", Proposition(
            bool(pub_better[obs - 1].all()), "printed errors: closer at observations "
            + ", ".join(str(o) for o in np.flatnonzero(pub_better) + 1))),)))
    sum_members_none = bool(np.all(np.asarray(sum_members, dtype=bool)))
    led.add(Claim(
        "yang-eq3-5-rejects", SOURCE, "Eqs. 3-5 (optimal fusion set)",
        "The optimal fusion set of eqs. 3-5 drops the readings that lie far from the others.",
        "qualitative",
        Proposition(bool(np.all(rd.fuse_epochs(t1.T, "optimal_fusion_set").members.sum(axis=1) < 3)),
                    "with averages, every observation of Table 1 loses at least one reading; this follows from "
                    "eq. 5 alone (the d_i - d̄ sum to zero, so the set never holds all n readings) and says "
                    "nothing about which readings are dropped: see the records on valid and faulty readings"),
        "ofs-crit-eq34", assumptions=("eqs. 3-4 read as averages, as the text names them",),
        alternatives=(Alternative("eqs. 3-4", "sums, as printed", Proposition(
            not sum_members_none, "as printed, d̄ is the sum of all d_i: no reading is ever dropped")),),
        critiques=("ofs-crit-eq34",)))
    one_member = int(np.sum(rd.fuse_epochs(t1.T, "optimal_fusion_set").members.sum(axis=1) == 1))
    led.add(Claim(
        "yang-eq9-defined", SOURCE, "Eqs. 9-11 (weights)",
        "Eqs. 9-11 give weights for every optimal fusion set.", "qualitative",
        Proposition(False, f"eq. 9 divides by zero for constant rows of C: one-member sets "
                           f"({one_member} of Table 1's 6 observations), identical readings"),
        "ofs-crit-eq9", critiques=("ofs-crit-eq9",)))
    t1v = np.asarray(table1_scale_values, dtype=float)
    sc_arr, sf_arr = np.asarray(sweep_clean, dtype=float), np.asarray(sweep_fail, dtype=float)
    grid = np.asarray(scales, dtype=float).ravel()
    ref = int(np.argmin(np.abs(grid - 2.0)))
    fam_t1 = np.stack([family_values(t1.T, f) for f in FAMILIES.values()])
    same_t1 = bool(np.ptp(t1v, axis=0).max() == 0.0 and np.ptp(fam_t1, axis=0).max() == 0.0)
    fam_tests: list[Proposition] = []
    if family_clean is not None and family_fail is not None:
        labels = list(family_clean)
        for lab in labels[1:]:
            fam_tests.append(equivalence(family_clean[lab], family_clean[labels[0]],
                                         f"{lab} vs eq. 6, no failure"))
            fam_tests.append(equivalence(family_fail[lab], family_fail[labels[0]],
                                         f"{lab} vs eq. 6, samples 50-80 under failure"))
    fam_primary = (Proposition(all(t.holds for t in fam_tests), "; ".join(t.ours for t in fam_tests))
                   if fam_tests else Unverifiable("the family study was not run"))
    scale_tests = {}
    for k, h in enumerate(grid):
        if k == ref:
            continue
        scale_tests[float(h)] = (equivalence(sc_arr[k], sc_arr[ref], f"scale {h:g} °C, no failure").holds
                                 and equivalence(sf_arr[k], sf_arr[ref], f"scale {h:g} °C, failure").holds)
    ok_sc = [f"{h:g}" for h, v in scale_tests.items() if v]
    bad_sc = [f"{h:g}" for h, v in scale_tests.items() if not v]
    led.add(Claim(
        "yang-membership-free", SOURCE, "Section 2, last paragraph",
        "The result does not depend on the choice of fusion-degree (membership) function.",
        "qualitative", fam_primary, "ofs-crit-eq6",
        assumptions=("membership functions varied by family (Gaussian, Cauchy in place of eq. 6, h = 2 °C) on the "
                     "ten-sensor simulation; the source names none of the functions it tried",
                     f"'does not depend' read as: per-run mean absolute error equivalent within ±"
                     f"{EQUIVALENCE_MARGIN:.0%} of eq. 6's (paired TOST)", _NOISE, _FIXED),
        alternatives=(
            Alternative("membership function", f"scale of eq. 6 from {grid.min():g} to {grid.max():g} °C against "
                        "the source's 2 °C, no failure and samples 50-80 under failure (paired TOST, "
                        f"±{EQUIVALENCE_MARGIN:.0%})", Proposition(
                            not bad_sc, f"equivalence shown at scales {', '.join(ok_sc) or 'none'} °C; not shown at "
                            f"{', '.join(bad_sc) or 'none'} °C ({sc_arr.shape[1]} runs per scale); in °F the fused "
                            f"value moves by up to {float(unit['f_maxdiff']):.3f} °C")),
            Alternative("data", "Table 1 (three readings)", Unverifiable(
                "vacuous: for three readings eqs. 3-5 give sets of one or two members (proved in the chapter), "
                "whose weights are equal whatever the function, so every function gives the same values"
                + (" (computed: the same)" if same_t1 else " (computed: they differ)")))),
        critiques=("ofs-crit-eq6",)))
    eq_alt = "σ = 1 °C for all ten sensors"
    fstud = dict(failure_studies or {})

    def mode_alts(make: object) -> tuple[Alternative, ...]:
        """The record under every other reading of "randomly", for both noise readings."""
        out = []
        for (mode, noise), st in fstud.items():
            reading = {"random size": "bias of each failing sensor drawn from U(0, 4) / U(0, 8) °C at each "
                                      "sample 50-80",
                       "random samples": "bias +4 / +8 °C on each sample 50-80 with probability 1/2"}[mode]
            out.append(Alternative("failure model ('randomly')", f"{reading}; {noise}, same draws",
                                   make(st)))  # type: ignore[operator]
        return tuple(out)

    sup_text = "the support-degree fusion (rebuilt substitute for ref. [11])"
    pairs = (("mean", "mean", "the arithmetic mean"), ("support", "support_degree", sup_text))
    spread_alts: tuple[Alternative, ...] = ()
    if fair is not None:
        spread_alts = tuple(
            Alternative("noise levels", f"σ geometric with spread σ_max/σ_min = {v:g} (the fair study's "
                        f"{fair.n_runs} runs × {fair.n_samples} samples)",  # type: ignore[attr-defined]
                        Comparison(e["optimal_fusion_set"], e["mean"], METHOD_LABELS["optimal_fusion_set"],
                                   METHOD_LABELS["mean"], "less", "per-run mean absolute error, no fault (°C)",
                                   seed=fair.seed))  # type: ignore[attr-defined]
            for (sw, v), e in fair.mae.items() if sw.startswith("noise spread"))  # type: ignore[attr-defined]
    for mid, base, text in pairs:
        led.add(Claim(
            f"yang-fig2-vs-{mid}", SOURCE, f"Fig. 2: error without failure, vs {text}",
            f"Without failure the optimal fusion set has a lower absolute error than {text}.", "qualitative",
            _cmp(study, "optimal_fusion_set", base, False), "ofs-beyond",
            assumptions=(_NOISE, _RUNS) + ((_SUP,) if base == "support_degree" else ()),
            alternatives=(Alternative("noise levels", eq_alt, _cmp(study_equal, "optimal_fusion_set", base, False)),
                          *(spread_alts if base == "mean" else ()),
                          Alternative("'the lowest curve'", "at every sample, not on average", Proposition(
                              study.best_share("optimal_fusion_set", False) == 1.0,
                              f"lowest at {study.best_share('optimal_fusion_set', False):.1%} of samples")),
                          *(_alpha_alts(alpha_study, False) if base == "support_degree" else ())),
            bound=f"inverse-variance mean (known σ): {thermocouples.best_linear_abs_error(thermocouples.DEFAULT_SIGMAS):.3f} °C"))
        led.add(Claim(
            "yang-fig2-fluctuation" if base == "mean" else "yang-fig2-fluctuation-support", SOURCE,
            "Fig. 2: error fluctuation" + ("" if base == "mean" else ", vs the support degree"),
            f"Without failure the optimal fusion set's error fluctuates less than that of {text}.", "qualitative",
            _cmp(study, "optimal_fusion_set", base, False, "sd"), "ofs-beyond",
            assumptions=(_NOISE, _RUNS) + ((_SUP,) if base == "support_degree" else ()),
            alternatives=(Alternative("noise levels", eq_alt,
                                      _cmp(study_equal, "optimal_fusion_set", base, False, "sd")),)))
    for mid, base, text in pairs:
        extra = (_SUP,) if base == "support_degree" else ()
        led.add(Claim(
            f"yang-fig4-vs-{mid}", SOURCE, f"Fig. 4: error under failure, vs {text}",
            f"When sensors 4 and 10 fail, the optimal fusion set has a lower error than {text} on samples 50-80.",
            "qualitative", _cmp(study, "optimal_fusion_set", base, True), "ofs-beyond", headline=(mid == "mean"),
            assumptions=(_NOISE, _RUNS, _FIXED) + extra,
            alternatives=(Alternative("noise levels", eq_alt, _cmp(study_equal, "optimal_fusion_set", base, True)),
                          *mode_alts(lambda st, b=base: _cmp(st, "optimal_fusion_set", b, True)),
                          Alternative("'the lowest curve'", "at every sample, not on average", Proposition(
                              study.best_share("optimal_fusion_set", True) == 1.0,
                              f"lowest at {study.best_share('optimal_fusion_set', True):.1%} of samples")),
                          *(_alpha_alts(alpha_study, True) if base == "support_degree" else ()))))
        led.add(Claim(
            f"yang-fig4-whole-vs-{mid}", SOURCE, f"Fig. 4: whole failure run, vs {text}",
            f"With sensors 4 and 10 failing on samples 50-80, the optimal fusion set's error over the whole run "
            f"(samples 1-100) is lower than that of {text} (the curve 'still lies lowest of the three, the "
            "overall error smallest').", "qualitative",
            _cmp(study, "optimal_fusion_set", base, True, whole=True), "ofs-beyond",
            assumptions=(_NOISE, _RUNS, _FIXED) + extra,
            alternatives=(Alternative("noise levels", eq_alt,
                                      _cmp(study_equal, "optimal_fusion_set", base, True, whole=True)),
                          *mode_alts(lambda st, b=base: _cmp(st, "optimal_fusion_set", b, True, whole=True)))))
        led.add(Claim(
            f"yang-fig4-fluctuation-{mid}", SOURCE, f"Fig. 4: error fluctuation on samples 50-80, vs {text}",
            f"On samples 50-80 under failure the optimal fusion set's error fluctuates less than that of {text}.",
            "qualitative", _cmp(study, "optimal_fusion_set", base, True, "sd"), "ofs-beyond",
            assumptions=(_NOISE, _RUNS, _FIXED) + extra,
            alternatives=(Alternative("noise levels", eq_alt,
                                      _cmp(study_equal, "optimal_fusion_set", base, True, "sd")),
                          *mode_alts(lambda st, b=base: _cmp(st, "optimal_fusion_set", b, True, "sd")))))

    def unaffected(st: PairedStudy) -> Proposition:
        return equivalence(st.mae("optimal_fusion_set", True), st.mae("optimal_fusion_set", False, window=True),
                           "optimal set's mean absolute error on samples 50-80, with vs without failure")

    led.add(Claim(
        "yang-fig4-unaffected", SOURCE, "Fig. 4: accuracy unaffected by the failure",
        "On samples 50-80 the optimal fusion set's accuracy is not affected by the failure of sensors 4 and 10.",
        "qualitative", unaffected(study), "ofs-beyond",
        assumptions=(_NOISE, _RUNS, _FIXED, f"'not affected' read as: per-run mean absolute error with failure "
                     f"equivalent to that without within ±{EQUIVALENCE_MARGIN:.0%} (paired TOST)"),
        alternatives=(Alternative("noise levels", eq_alt, unaffected(study_equal)), *mode_alts(unaffected))))

    def robust(st: PairedStudy) -> Comparison:
        d_ofs = st.mae("optimal_fusion_set", True) - st.mae("optimal_fusion_set", False, window=True)
        d_mean = st.mae("mean", True) - st.mae("mean", False, window=True)
        return Comparison(d_ofs, d_mean, METHOD_LABELS["optimal_fusion_set"], METHOD_LABELS["mean"], "less",
                          "per-run rise of the mean absolute error on samples 50-80 due to the failure (°C)",
                          seed=st.seed)

    led.add(Claim(
        "yang-fig4-robust", SOURCE, "Fig. 4: anti-interference",
        "The failure raises the optimal fusion set's error less than the arithmetic mean's.", "qualitative",
        robust(study), "ofs-beyond", assumptions=(_NOISE, _RUNS, _FIXED),
        alternatives=(Alternative("noise levels", eq_alt, robust(study_equal)), *mode_alts(robust))))

    if ablation:
        abl = list(ablation.items())

        def abl_cmp(e: Mapping[str, ArrayLike], what: str, seed: int) -> Comparison:
            return Comparison(e["optimal_fusion_set"], e["uniform_set"], "weights of eqs. 6-11",
                              METHOD_LABELS["uniform_set"], "less", f"per-run mean absolute error, {what} (°C)", seed=seed)

        fair_alts = () if fair is None else tuple(
            Alternative("scenario", f"fair study: {sw} = {v:g}",
                        abl_cmp(e, f"{sw} = {v:g}", fair.seed))  # type: ignore[attr-defined]
            for (sw, v), e in fair.mae.items())  # type: ignore[attr-defined]
        led.add(Claim(
            "yang-weights-reasonable", SOURCE, "Section 1.3 and abstract (weights 合理, reasonably, assigned)",
            "Eqs. 8-11 assign the weights of the valid readings reasonably: weighting the set by consistency "
            "and balance does better than weighting its members equally.", "qualitative",
            abl_cmp(abl[0][1], abl[0][0], study.seed), "ofs-fair",
            assumptions=(_NOISE, _RUNS, "'reasonably' read as: a lower error than equal weights on the same set"),
            alternatives=(*(Alternative("scenario", lab, abl_cmp(e, lab, study.seed)) for lab, e in abl[1:]),
                          *fair_alts)))

    def keeps_valid(st: PairedStudy) -> Proposition:
        return Proposition(bool(np.all(st.set_size == 10)), f"without faults (every reading valid) the set keeps "
                           f"{float(np.mean(st.set_size)):.2f} of 10 readings on average ({st.n_runs} runs × 100 samples)")

    led.add(Claim(
        "yang-def3-keeps-valid", SOURCE, "Definition 3 (optimal fusion set)",
        "The optimal fusion set holds all valid readings, those in the neighbourhood of the true value.",
        "qualitative", keeps_valid(study), "ofs-beyond", assumptions=(_NOISE, _RUNS),
        bound="eq. 5 never keeps all n readings unless all are equal (the d_i - d̄ sum to zero)",
        alternatives=(Alternative("noise levels", eq_alt, keeps_valid(study_equal)),)))

    def rejects(st: PairedStudy) -> Proposition:
        sh = st.failed_member_share
        return Proposition(bool(len(sh) > 0 and max(sh) == 0.0), "under the failure, sensor 4 is a member at "
                           f"{sh[0]:.1%} and sensor 10 at {sh[1]:.1%} of the epochs 50-80 ({st.n_runs} runs)"
                           if len(sh) == 2 else "not computed")

    led.add(Claim(
        "yang-set-rejects-faulty", SOURCE, "Section 2, after Fig. 4",
        "Forming the optimal fusion set screens the valid readings and rejects the faulty ones (甄别有效数据,剔除疏失数据).",
        "qualitative", rejects(study), "ofs-beyond", assumptions=(_NOISE, _RUNS, _FIXED),
        alternatives=(Alternative("noise levels", eq_alt, rejects(study_equal)),)))
    return led


def failure_rise(study: PairedStudy) -> Comparison:
    """The optimal set's error on samples 50-80 with the failure against without it, on the same draws.

    Parameters
    ----------
    study : PairedStudy
        The heterogeneous-noise study (:func:`fusion.scenarios.thermocouples.paired_study`).

    Returns
    -------
    Comparison
        A = with failure, B = without failure, per-run mean absolute error (°C); the claim
        "greater" is the direction of the rise.
    """
    return Comparison(study.mae("optimal_fusion_set", True), study.mae("optimal_fusion_set", False, window=True),
                      "with failure", "without failure", "greater",
                      "optimal set's per-run mean absolute error on samples 50-80 (°C)", seed=study.seed)


def ledger_numbers(ledger: Ledger, prefix: str = "ofs_") -> dict[str, float | str]:
    """Glue-ready numbers of every paired comparison in a ledger.

    Parameters
    ----------
    ledger : Ledger
    prefix : str
        Glue-key prefix of the chapter.

    Returns
    -------
    dict
        For each claim whose primary evidence is a :class:`~fusion.book.ledger.Comparison`, keys
        ``<prefix><id>_{a,b,diff,lo,hi}`` (means of A and B, mean paired difference, 95 % interval;
        rounded to 4 decimals) and ``<prefix><id>_runs``; for every claim ``<prefix><id>_status``.
        Dashes of the id become underscores.
    """
    out: dict[str, float | str] = {}
    for c in ledger.claims:
        key = prefix + c.id.replace("-", "_")
        out[key + "_status"] = c.status
        if isinstance(c.evidence, Comparison):
            out.update(comparison_numbers(c.evidence, key))
    return out


def comparison_numbers(comparison: Comparison, key: str) -> dict[str, float | int]:
    """Glue-ready numbers of one paired comparison.

    Parameters
    ----------
    comparison : Comparison
    key : str
        Glue-key stem; the keys are ``<key>_{a,b,diff,lo,hi}`` (rounded to 4 decimals) and
        ``<key>_runs``.

    Returns
    -------
    dict
    """
    mean, lo, hi = comparison.interval()
    vals = {"a": float(np.mean(comparison.a)), "b": float(np.mean(comparison.b)), "diff": mean, "lo": lo, "hi": hi}
    out: dict[str, float | int] = {f"{key}_{k}": rounded(v, 4) for k, v in vals.items()}
    out[key + "_runs"] = comparison.runs
    return out


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
        Glue key -> value (mean absolute errors in °C, 3 decimals; shares; the table itself as ``ofs_mc_table``).

    References
    ----------
    * Yang, Y., Feng, J., & Fan, S. (2012). Multi-sensor data fusion based on the optimal fusion set.
    """
    hs, eq = sigmas
    L = METHOD_LABELS
    mcv = {(s, f, m): rounded(mc.loc[(s, f), L[m]], 3) for s in sigmas for f in ("no failure", "failure") for m in METHODS}
    share = mc["share of epochs where the optimal set is best"]
    return {
        "ofs_n_runs": n_runs, "ofs_mc_table": mc,
        "ofs_mc_eq_clean_ofs": mcv[(eq, "no failure", "optimal_fusion_set")], "ofs_mc_eq_clean_mean": mcv[(eq, "no failure", "mean")],
        "ofs_mc_hs_clean_ofs": mcv[(hs, "no failure", "optimal_fusion_set")], "ofs_mc_hs_clean_mean": mcv[(hs, "no failure", "mean")],
        "ofs_mc_hs_clean_sup": mcv[(hs, "no failure", "support_degree")],
        "ofs_mc_hs_bound": rounded(mc.loc[(hs, "no failure"), "bound (no failure)"], 3),
        "ofs_mc_eq_bound": rounded(mc.loc[(eq, "no failure"), "bound (no failure)"], 3),
        "ofs_mc_hs_fail_ofs": mcv[(hs, "failure", "optimal_fusion_set")], "ofs_mc_hs_fail_mean": mcv[(hs, "failure", "mean")],
        "ofs_mc_hs_fail_sup": mcv[(hs, "failure", "support_degree")],
        "ofs_mc_eq_fail_ofs": mcv[(eq, "failure", "optimal_fusion_set")], "ofs_mc_eq_fail_sup": mcv[(eq, "failure", "support_degree")],
        "ofs_mc_best_share_max": rounded(share.max(), 3), "ofs_mc_best_share_min": rounded(share.min(), 3),
        "ofs_mc_eff_loss": rounded((mcv[(eq, "no failure", "optimal_fusion_set")] / mcv[(eq, "no failure", "mean")]) ** 2, 2),
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
    * Yang, Y., Feng, J., & Fan, S. (2012). Multi-sensor data fusion based on the optimal fusion set.
    """
    T1 = data.YANG2012_TABLE1.values
    t2, t3 = data.YANG2012_TABLE2.columns, data.YANG2012_TABLE3.columns
    TRUE = data.YANG2012_TRUE_VALUE
    ours = {"ofs": tabs.ofs, "mean": tabs.mean, "sup": tabs.sup}
    ok = np.abs(tabs.ofs - t2["optimal_set"]) < 5e-5
    mean_ok = np.abs(tabs.mean - t2["mean"]) < 5e-5
    OBS = np.arange(1, 7)
    return {
        **{f"ofs_our_total_{k}": rounded(np.abs(v - TRUE).sum()) for k, v in ours.items()},
        "ofs_n_reproduced": int(ok.sum()),
        "ofs_reproduced_obs": ", ".join(str(o) for o in OBS[ok]),
        "ofs_mean_bad_obs": ", ".join(str(o) for o in OBS[~mean_ok]),
        "ofs_n_mean_reproduced": int(mean_ok.sum()),
        "ofs_n_sup_reproduced": int(np.sum(np.abs(tabs.sup - t3["reliability"]) < 5e-5)),
        "ofs_guard_total": rounded(np.abs(np.where(rd.fuse_epochs(T1.T, "optimal_fusion_set").members.sum(axis=1) == 1,
                                                   tabs.mean, tabs.ofs) - TRUE).sum()),
        "ofs_rank_margin": rounded(np.abs(tabs.ofs - TRUE).sum() - np.abs(tabs.sup - TRUE).sum(), 2),
        "ofs_sup_total_by_alpha": ", ".join(
            f"{np.abs(rd.fuse_epochs(T1.T, 'support_degree', alpha=a).values - TRUE).sum():.2f} °C at α = {a:g}"
            for a in ALPHAS),
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
    * Yang, Y., Feng, J., & Fan, S. (2012). Multi-sensor data fusion based on the optimal fusion set.
    """
    T1 = data.YANG2012_TABLE1.values
    t2 = data.YANG2012_TABLE2.columns
    x5 = T1[:, 4].copy()
    x5[1] += audit.implied_sum_change(T1[:, 4], t2["mean"][4])
    return {
        "ofs_obs1_pub": float(t2["optimal_set"][0]), "ofs_obs1_pub_err": float(t2["optimal_set_abs_error"][0]),
        "ofs_obs2_pub": float(t2["optimal_set"][1]), "ofs_obs1_max": float(T1[:, 0].max()),
        "ofs_obs5_sum_change": rounded(audit.implied_sum_change(T1[:, 4], t2["mean"][4]), 3),
        "ofs_obs5_s2": float(T1[1, 4]), "ofs_obs5_s2_fixed": rounded(x5[1], 1),
        "ofs_obs5_fixed_mean": rounded(rd.arithmetic_mean(x5).value),
        "ofs_obs5_fixed_ofs": rounded(rd.optimal_fusion_set(x5).value),
        "ofs_obs5_pub": float(t2["optimal_set"][4]), "ofs_obs6_ours": rounded(tabs.ofs[5]),
        "ofs_obs1_ours": rounded(tabs.ofs[0]),
        "ofs_obs6_pub_err": float(t2["optimal_set_abs_error"][5]), "ofs_obs6_pub_mean_err": float(t2["mean_abs_error"][5]),
    }
