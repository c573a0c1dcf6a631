r"""Chapter 02, §2.1 (E2.1, E2.1c): the AWF's variance estimators, their guards, tail and AR(1) noise, and
linear-unbiased-minimum-variance under each reading of the weights: tables, figures and glue."""

from __future__ import annotations

from fusion.book._few_runs import study_runs_named
from fusion._counts import sequence
from fusion._validation import distinct, distinct_printed, glue_part, instance_of, scalar, shown

from dataclasses import dataclass

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from fusion._docstrings import ParameterDocs
from fusion._results import ResultSpec, flag, instance, text, validated_post_init
from fusion.book.chapters.lecture import _holds, _key, _lec_glue, _r, legend_below, sci
from fusion.book.ledger import Comparison
from fusion.book.style import METHOD_LABELS, color, new_figure
from fusion.book.tables import integral_index
from fusion.readings import weighting as wt
from fusion.book.glue import GlueValues
from fusion.scenarios.lecture_weighting.estimators import (LECTURE_GUARD_METHODS, AR1Study, AwfMethod, AwfStudy, LumvStudy,
                                                           SymmetryStudy, TailStudy)
from fusion.book.chapters.lecture_weighting._common import _unbiased
from fusion.book._t_interval import mean_interval, t_pvalue


__all__ = [
    "table_21",
    "figure_21a",
    "figure_21b",
    "sweep_comparisons",
    "table_sweep",
    "table_guards",
    "band_agreement_k",
    "glue_21",
    "awf_log_comparison",
    "EVEN_WEIGHTS",
    "lumv_bias",
    "LumvReading",
    "lumv_readings",
    "glue_lumv",
    "table_symmetry",
    "glue_ar1",
    "glue_tail",
]

#: The Parameters entries several functions of this module share (:class:`fusion._docstrings.ParameterDocs`).
_PARAMS = ParameterDocs({
    "s": "AwfStudy\n    Result of :func:`fusion.scenarios.lecture_weighting.estimators.awf_study`.",
    "sl": "LumvStudy\n    Output of :func:`fusion.scenarios.lecture_weighting.estimators.lumv_study`.",
})


# --------------------------------------------------------------------------- 2.1
#: The table's column of each field of :class:`~fusion.scenarios.lecture_weighting.estimators.EstimatorRow`, in order.
_COLUMNS_21 = {"X": "X", "estimator": "estimator", "k": "k", "mean_1": "mean σ̂₁²", "sd_1": "SD σ̂₁²",
               "mean_4": "mean σ̂₄²", "sd_4": "SD σ̂₄²", "p_negative": "P(σ̂² < 0)"}


def _estimates_table(s: AwfStudy) -> pd.DataFrame:
    """The rows of E2.1 as a table indexed by (X, estimator, k), rounded to 4 decimals."""
    rows = [{col: getattr(r, f) for f, col in _COLUMNS_21.items()} for r in s.rows]
    return pd.DataFrame(rows).set_index(["X", "estimator", "k"]).round(4)


@_PARAMS("s")
def table_21(s: AwfStudy, levels: tuple[float, ...] = (0.0, 100.0, 900.0)) -> pd.DataFrame:
    """Mean and SD of the variance estimates (E2.1) at the given levels, rounded to 4 decimals.

    Parameters
    ----------
    levels : tuple of float
        True values X shown (rows; at least one).

    Returns
    -------
    pandas.DataFrame
        Index (X, estimator, k) for each level; columns the mean and SD of the estimates of σ₁² and σ₄², and P(σ̂² < 0).

    Raises
    ------
    TypeError
        ``s`` not an AwfStudy (E2.1's study), or ``levels`` not a sequence (a list, tuple or 1-D array) of
        numbers.
    ValueError
        ``levels`` empty, repeating a level, or an entry not a level of the study; more entries than the study's
        levels, counted before any entry is read.
    """
    instance_of(s, AwfStudy, "s")
    tab = _estimates_table(s)
    known = tab.index.get_level_values("X").unique()
    levels = sequence(levels, "levels", minimum=1, what="level")
    if len(levels) > len(known):   # distinct levels of the study: no more than it holds, counted before any is read
        # (fuzz 68b: each entry of a long list was read and looked up before distinct refused the repeats)
        raise ValueError(f"levels must hold distinct levels of the study, at most its {len(known)} (its levels: "
                         f"{list(known)}), got {len(levels)} entries")
    for i, v in enumerate(levels):
        if scalar(v, f"levels[{i}]") not in known:
            raise ValueError(f"levels[{i}] = {shown(v)} is not a level of the study (its levels: {list(known)})")
    distinct([float(v) for v in levels], "levels")   # a repeated level would print its row twice (fuzz 20, D2)
    return integral_index(tab.loc[list(levels)])   # X = 900, not 900.0


def figure_21a(s: AwfStudy) -> Figure:
    """F2.1a: estimates of σ₁² against k, mean ± 1 SD, both estimators, X = 0 and 100.

    Parameters
    ----------
    s : AwfStudy
        E2.1 (:func:`fusion.scenarios.lecture_weighting.estimators.awf_study`); the bands at X = 0 and 100 are drawn.

    Returns
    -------
    matplotlib.figure.Figure
        Two panels, X = 0 and X = 100: each estimator's mean ± 1 SD estimate of σ₁² against k (log), with the true σ₁².

    Raises
    ------
    TypeError
        ``s`` not an AwfStudy.
    ValueError
        ``s`` without the bands at X = 0 and 100 (``awf_study(levels=...)`` without them), named.
    """
    instance_of(s, AwfStudy, "s")
    _holds(dict.fromkeys(X for X, _ in s.band), (0.0, 100.0), "s", "levels X of s.band", "figure_21a")
    fig, axes = new_figure(1, 2, figsize=(7.5, 3.4), sharey=True)
    k_axis = np.arange(1, s.k_max + 1)
    for ax, X in zip(axes, (0.0, 100.0)):
        for e, ls in (("lecture", "-"), ("centred", "--")):
            m, sd = s.band[X, e]
            key = "awf_lecture" if e == "lecture" else "awf_centred"
            c, lab = color(key), f"{e} estimate"
            ax.plot(k_axis, m, ls, color=c, label=f"{lab}: mean")
            ax.fill_between(k_axis, m - sd, m + sd, color=c, alpha=0.2, label=f"{lab}: ±1 SD")
        ax.axhline(s.variances[0], color=color("truth"), lw=1, label="true σ₁²")
        ax.set_xscale("log")
        ax.set_xlabel("samples k")
        ax.set_title(f"X = {X:g}")
        # the study's σ₁², not the default's (fuzz 26d F1): the limits scale with it ((-2.5, 3) at σ₁² = 0.25)
        ax.set_ylim(-10.0 * s.variances[0], 12.0 * s.variances[0])
    axes[0].set_ylabel(f"estimate of σ₁² (σ₁² = {s.variances[0]:g})")
    legend_below(fig, ncol=3)
    return fig


#: Line style of each curve of F2.1b (colour and label: the method key's in :mod:`fusion.book.style`).
_LINESTYLES_21 = {AwfMethod.ORACLE: "-", AwfMethod.AWF_LECTURE_FLOOR: "-", AwfMethod.AWF_CENTRED: "-",
                  AwfMethod.MEAN_OF_MEANS: ":", AwfMethod.BEST_SENSOR: "-."}


def figure_21b(s: AwfStudy) -> Figure:
    """F2.1b: fused MSE against k (log-log), X = 0 and 900, with σ²min/k.

    Parameters
    ----------
    s : AwfStudy
        Result of :func:`fusion.scenarios.lecture_weighting.estimators.awf_study`, whose MSE curves at X = 0 and 900 it plots.

    Returns
    -------
    matplotlib.figure.Figure
        Two panels, X = 0 and X = 900: each method's fused MSE against k (log-log), with σ²min/k.
    """
    instance_of(s, AwfStudy, "s")
    fig, axes = new_figure(1, 2, figsize=(7.5, 3.4), sharey=True)
    ks = s.ks
    for ax, X in zip(axes, (0.0, 900.0)):
        for key, curve in s.mse[X].items():
            ax.plot(ks, curve, _LINESTYLES_21[key], color=color(key), label=METHOD_LABELS[key],
                    marker="o" if key == AwfMethod.ORACLE else None, ms=3)
        ax.plot(ks, wt.minimum_variance(s.variances) / ks, color=color("published"), lw=0.8, label="σ²min / k")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("samples k")
        ax.set_title(f"X = {X:g}")
    axes[0].set_ylabel("mean-square error")
    legend_below(fig, ncol=3)
    return fig


#: Readers' names of the guards of non-positive variance estimates (:data:`fusion.readings.weighting.GUARDS`).
GUARD_NAMES: dict[str, str] = {"floor": "tiny floor (package default)", "abs": "|σ̂²|",
                               "equal": "equal weights if any σ̂² ≤ 0", "none": "no guard (as written)"}


def _num(v: float) -> str:
    """MSE for a table: 5 decimals, or a whole number with thousands separators from 1000 on."""
    return f"{v:,.0f}" if abs(v) >= 1000 else f"{v:.5f}"


def _pm(v: float, decimals: int = 4) -> str:
    """A signed value at fixed decimals, ``-0.0000`` written ``0.0000``."""
    t = f"{v:.{decimals}f}"
    return t[1:] if t.startswith("-") and float(t) == 0 else t


@study_runs_named("s")
def sweep_comparisons(s: AwfStudy) -> dict[tuple[float, str], Comparison]:
    """The lecture's AWF against the mean of means at every level of the sweep of E2.1.

    Parameters
    ----------
    s : AwfStudy
        Result of :func:`fusion.scenarios.lecture_weighting.estimators.awf_study`: its per-run squared errors of the sweep.

    Returns
    -------
    dict
        ``(X, "abs")``: squared error with the ``|σ̂²|`` guard against the mean of means;
        ``(X, "none")``: log of the squared error without a guard (its MSE is infinite, its mean undefined) against the
        mean of means. Claim "less", paired by run.
    """
    instance_of(s, AwfStudy, "s")
    out: dict[tuple[float, str], Comparison] = {}
    mm, ab, no = AwfMethod.MEAN_OF_MEANS, AwfMethod.AWF_LECTURE_ABS, AwfMethod.AWF_LECTURE_NONE
    for X, sq in s.sweep.items():
        out[X, "abs"] = Comparison(sq[ab], sq[mm], METHOD_LABELS[ab], METHOD_LABELS[mm],
                                   "less", f"squared error at k = {s.k_compare}, X = {X:g}", seed=s.seed)
        out[X, "none"] = Comparison(np.log(sq[no]), np.log(sq[mm]), METHOD_LABELS[no], METHOD_LABELS[mm], "less",
                                    f"ln of the squared error at k = {s.k_compare}, X = {X:g}", seed=s.seed)
    return out


@study_runs_named("s")
def table_sweep(s: AwfStudy) -> pd.DataFrame:
    """The verdict of §2.1 against the level X: paired differences with the mean of means and their 95 % CIs.

    Parameters
    ----------
    s : AwfStudy
        E2.1, with the sweep over X (:func:`fusion.scenarios.lecture_weighting.estimators.awf_study`).

    Returns
    -------
    pandas.DataFrame
        One row per level X (with X/σ of the most precise sensor); for ``|σ̂²|`` the MSE difference,
        for no guard the ratio of geometric-mean squared errors, each with its interval and verdict.
    """
    instance_of(s, AwfStudy, "s")
    word = {"reproduced": "better", "contradicted": "worse", "not distinguishable": "not distinguishable"}
    rows = []
    smin = float(np.sqrt(np.min(s.variances)))
    for (X, g), c in sweep_comparisons(s).items():
        if g != "abs":
            continue
        m, lo, hi = c.interval()
        cn = sweep_comparisons(s)[X, "none"]
        mn, lon, hin = cn.interval()
        rows.append({"X": X, "X / σ₁": X / smin,
                     "|σ̂²|: MSE difference": f"{m:+.4f}", "|σ̂²|: 95 % CI": f"[{lo:+.4f}, {hi:+.4f}]",
                     "|σ̂²|": word[c.status()],
                     "no guard: GM ratio": f"{np.exp(mn):.2f}", "no guard: 95 % CI": f"[{np.exp(lon):.2f}, {np.exp(hin):.2f}]",
                     "no guard": word[cn.status()]})
    tab = pd.DataFrame(rows).set_index("X")
    tab.columns.name = f"against the mean of means, k = {s.k_compare}, {s.runs} runs"
    tab = integral_index(tab.round({"X / σ₁": 1}))
    ratio = tab["X / σ₁"].to_numpy()
    if np.all(ratio == np.round(ratio)):                # whole numbers printed as integers
        tab["X / σ₁"] = np.round(ratio).astype(int)
    return tab


def table_guards(s: AwfStudy) -> pd.DataFrame:
    """MSE at k = ``k_compare`` of the lecture's AWF under every variance guard, and the centred AWF, at X = 0 and 900.

    Parameters
    ----------
    s : AwfStudy
        Output of :func:`fusion.scenarios.lecture_weighting.estimators.awf_study` (levels 0 and 900 included).

    Returns
    -------
    pandas.DataFrame
        One row per method, one column per level, as text: MSE at 5 decimals (a value of 1000 or
        more as a whole number with thousands separators) and mean error ± its standard error at
        4 decimals (none for the unguarded weights, whose fused error has a 1/t tail: no mean, infinite MSE).
    """
    instance_of(s, AwfStudy, "s")
    # the table's row texts (longer than the methods' registered labels: they spell out each guard)
    names = {LECTURE_GUARD_METHODS[g]: f"lecture's AWF, {GUARD_NAMES[g]}" for g in wt.GUARDS}
    names[AwfMethod.AWF_LECTURE_DELETE] = "lecture's AWF, deletion (drop σ̂² ≤ 0)"
    names[AwfMethod.GRAYBILL_DEAL] = "Graybill-Deal (own sample variances)"
    names |= {AwfMethod.AWF_CENTRED: "AWF, centred estimator",
              AwfMethod.MEAN_OF_MEANS: METHOD_LABELS[AwfMethod.MEAN_OF_MEANS], AwfMethod.ORACLE: "oracle"}
    cols = {}
    for X in (0.0, 900.0):
        cols[f"MSE, X = {X:g}"] = {lab: _num(s.sq[X][nm].mean()) for nm, lab in names.items()}
        # without a guard Σ1/σ̂² has a positive density at 0 at any level: a 1/t tail, mean undefined, MSE infinite
        cols[f"bias ± SE, X = {X:g}"] = {lab: ("no mean (1/t tail)" if nm == AwfMethod.AWF_LECTURE_NONE else
                                               f"{_pm(s.err[X][nm].mean())} ± {s.err[X][nm].std() / np.sqrt(s.runs):.4f}")
                                         for nm, lab in names.items()}
    tab = pd.DataFrame(cols)
    tab.index.name = f"k = {s.k_compare} ({s.runs} runs)"
    return tab


def band_agreement_k(s: AwfStudy, X: float = 0.0, tol: float = 0.1) -> int:
    """First k from which the lecture's and the centred estimates of σ₁² agree in mean and SD (Fig. 8's bands).

    Parameters
    ----------
    s : AwfStudy
        Output of :func:`fusion.scenarios.lecture_weighting.estimators.awf_study` (``band`` holds X = 0 and 100).
    X : float
        Level of the bands compared.
    tol : float
        Agreement: means and SDs within ``tol`` × σ₁² at that k and every later one.

    Returns
    -------
    int
        The sample count k (1-based); ``k_max + 1`` if they never agree.
    """
    instance_of(s, AwfStudy, "s")
    X = scalar(X, "X")
    tol = scalar(tol, "tol", lo=0.0)
    levels = sorted({k[0] for k in s.band})
    if (X, "lecture") not in s.band or (X, "centred") not in s.band:
        raise ValueError(f"X = {shown(X)} is not a level of the study's bands (s.band holds X in {levels})")
    (ml, sl), (mc, scn) = s.band[X, "lecture"], s.band[X, "centred"]
    bad = np.flatnonzero(np.maximum(np.abs(ml - mc), np.abs(sl - scn)) > tol * s.variances[0])
    return int(bad[-1] + 2) if bad.size else 1


@_lec_glue
@_PARAMS("s")
@study_runs_named("s")
def glue_21(s: AwfStudy) -> GlueValues:
    """Glue values of E2.1.

    Raises
    ------
    ValueError
        ``s`` without the rows the values read: the levels X = 0 and 900, k = 100 and 1000 among its ``ks``
        (the chapter's ``awf_study(k_max=1000, ...)``).
    """
    instance_of(s, AwfStudy, "s")
    tab = _estimates_table(s)
    lacking = [r for r in ((X, e, k) for X in (0.0, 900.0) for e in ("lecture", "centred") for k in (100, 1000))
               if r not in tab.index]
    if lacking:
        raise ValueError(f"s lacks the rows (X, estimator, k) {lacking} that glue_21 reads: E2.1's study has the "
                         "levels 0 and 900 and k = 100 and 1000 among its ks")
    i = s.i_compare
    V = s.variances
    bound = wt.minimum_variance(V) / s.ks[i]
    out = {
        "awf_sd_lec_x0_k100": (tab.loc[(0.0, "lecture", 100), "SD σ̂₁²"], 4),
        "awf_sd_lec_x900_k100": (tab.loc[(900.0, "lecture", 100), "SD σ̂₁²"], 4),
        "awf_sd_cen_x900_k100": (tab.loc[(900.0, "centred", 100), "SD σ̂₁²"], 4),
        "awf_sd_pred_x900_k100": (s.sd_pred_900, 4),
        "awf_pneg_lec_x0_k100": (tab.loc[(0.0, "lecture", 100), "P(σ̂² < 0)"], 4),
        "awf_pneg_lec_x900_k100": (tab.loc[(900.0, "lecture", 100), "P(σ̂² < 0)"], 4),
        "awf_pneg_lec_x900_k1000": (tab.loc[(900.0, "lecture", 1000), "P(σ̂² < 0)"], 4),
        "awf_pneg_cen_x900_k100": (tab.loc[(900.0, "centred", 100), "P(σ̂² < 0)"], 4),
        "awf_mean_lec_x900_k1000_s1": (tab.loc[(900.0, "lecture", 1000), "mean σ̂₁²"], 4),
        "awf_true_s1": (V[0], 4),
        "awf_bound_k": (bound, 5),
        "awf_oracle_reldev": (s.mse[0.0][AwfMethod.ORACLE][i] / bound - 1, 3),
        "awf_oracle_relse": (np.sqrt(2 / s.runs), 3),
    }
    for X, tag in ((0.0, "x0"), (900.0, "x900")):
        for method, key in ((AwfMethod.ORACLE, "oracle"), (AwfMethod.AWF_LECTURE_FLOOR, "lec"),
                            (AwfMethod.AWF_CENTRED, "cen"), (AwfMethod.MEAN_OF_MEANS, "mom"), (AwfMethod.BEST_SENSOR, "best")):
            out[f"awf_mse_{key}_{tag}"] = (s.mse[X][method][i], 5)
        for g in wt.GUARDS:
            out[f"awf_guard_{g}_{tag}"] = (s.sq[X][LECTURE_GUARD_METHODS[g]].mean(), 6)
            e = s.err[X][LECTURE_GUARD_METHODS[g]]
            out[f"awf_bias_{g}_{tag}"] = (e.mean(), 4)
            out[f"awf_bias_se_{g}_{tag}"] = (e.std() / np.sqrt(e.size), 4)
    out["awf_bias_oracle_x900"] = (s.err[900.0][AwfMethod.ORACLE].mean(), 4)
    gd, mm = s.sq[900.0][AwfMethod.GRAYBILL_DEAL], s.sq[900.0][AwfMethod.MEAN_OF_MEANS]
    out["awf_gd_x900"] = (gd.mean(), 5)
    out["awf_gd_ratio_oracle"] = (gd.mean() / s.sq[900.0][AwfMethod.ORACLE].mean(), 2)
    gdc = Comparison(gd, mm, METHOD_LABELS[AwfMethod.GRAYBILL_DEAL], METHOD_LABELS[AwfMethod.MEAN_OF_MEANS], "less",
                     "squared error", seed=s.seed)
    out["awf_gd_d"], out["awf_gd_lo"], out["awf_gd_hi"] = ((v, 5) for v in gdc.interval())
    lc = awf_log_comparison(s)
    d, lo, hi = lc.interval()
    a, b = s.sq[900.0][AwfMethod.AWF_LECTURE_NONE], s.sq[900.0][AwfMethod.MEAN_OF_MEANS]
    out.update({"awf_gm_ratio_none_x900": (np.exp(d), 2), "awf_gm_lo_none_x900": (np.exp(lo), 2),
                "awf_gm_hi_none_x900": (np.exp(hi), 2), "awf_med_diff_none_x900": (np.median(a - b), 4)})
    # precision of the lecture's estimator: SD and share of negative estimates at k_compare, samples needed
    for X, tag in ((0.0, "x0"), (900.0, "x900")):
        sd = s.sd_est[X, "lecture"]
        out[f"awf_prec_maxrel_{tag}"] = (float(np.max(sd / V)), 3)
    need = wt.lecture_samples_needed(900.0, V, 0.5)
    res = _r(out)
    res["lec_awf_need_s1_x900"] = sci(float(need[0]), 2)
    res["lec_awf_need_min_x900"] = sci(float(need.min()), 2)
    res["lec_awf_band_k"] = band_agreement_k(s)
    res["lec_awf_k_cmp"] = int(s.ks[i])
    res["lec_awf_nworse_none_x900"] = int(np.sum(a > b))
    res["lec_awf_runs"] = int(s.runs)
    return res


@study_runs_named("s21")
def awf_log_comparison(s21: AwfStudy, X: float = 900.0, method: AwfMethod = AwfMethod.AWF_LECTURE_NONE) -> Comparison:
    """The unguarded lecture AWF against the mean of means on the log of the per-run squared error.

    The paired difference of the logs is the log of the ratio of the geometric means of the
    squared errors; its t interval is not dominated by the few runs in which the unguarded
    inverse variance estimates nearly cancel.

    Parameters
    ----------
    s21 : AwfStudy
        Result of :func:`fusion.scenarios.lecture_weighting.estimators.awf_study`.
    X : float
        Level (0 or 900).
    method : AwfMethod
        The AWF variant compared (default: the lecture's, without a guard).

    Returns
    -------
    Comparison
        A = ``method`` (default the AWF as written, no guard), B = mean of means, claim "less", metric
        ln(squared error).
    """
    instance_of(s21, AwfStudy, "s21")
    X = scalar(X, "X")
    if X not in s21.sq:
        raise ValueError(f"X = {shown(X)} is not a level of the study (s21.sq holds X in {sorted(s21.sq)})")
    sq = s21.sq[X]
    if not isinstance(method, str):
        raise TypeError(f"method must be an AwfMethod (or its value), got {type(method).__name__}")
    if method not in sq:
        raise ValueError(f"method must be a method of the study, one of {[str(m) for m in sq]}, got {shown(method)}")
    mm = AwfMethod.MEAN_OF_MEANS
    return Comparison(np.log(sq[method]), np.log(sq[mm]), METHOD_LABELS[method], METHOD_LABELS[mm], "less",
                      f"ln of the squared error at k = {s21.k_compare}", seed=s21.seed)




def _non_inferior(sq: np.ndarray, sq_ref: np.ndarray, margin: float = 0.05) -> tuple[bool, str]:
    """One-sided paired t test that the MSE exceeds the reference's by less than ``margin`` of it (level 0.05)."""
    d = np.asarray(sq, dtype=float) - np.asarray(sq_ref, dtype=float)
    delta = margin * float(np.mean(sq_ref))
    p = t_pvalue(d, delta, "less")   # constant to round-off: decided by its side, no warning (fuzz 37b C3)
    lo, hi = mean_interval(d, 0.95)
    ratio = float(np.mean(sq) / np.mean(sq_ref))
    p_txt = "p < 0.001" if p < 0.001 else f"p = {p:.3f}"
    return bool(p < 0.05), (f"MSE {np.mean(sq):.4g} vs the oracle's {np.mean(sq_ref):.4g} (ratio {ratio:.3f}; paired "
                            f"difference 95 % CI [{lo:.3g}, {hi:.3g}]), within {margin:.0%} of it "
                            f"{'shown' if p < 0.05 else 'not shown'} ({p_txt})")


#: Readings of E2.1c whose weights are even functions of the noise (true variances; centred moments): their fused
#: error is odd, so they are unbiased for any symmetric noise (:func:`fusion.scenarios.lecture_weighting.estimators.symmetry_study`).
EVEN_WEIGHTS: tuple[AwfMethod, ...] = (AwfMethod.ORACLE, AwfMethod.AWF_CENTRED)


def _odd(sl: LumvStudy, name: AwfMethod) -> bool:
    """Whether e(V) + e(−V) is round-off in every pair of E2.1c (at most 10⁻⁶ of the largest error)."""
    return bool(sl.odd_residual[name] <= 1e-6 * float(np.max(np.abs(sl.err[name]))))


@_PARAMS("sl")
def lumv_bias(sl: LumvStudy, name: AwfMethod) -> tuple[float, float, float]:
    """Bias of one reading of E2.1c from its antithetic pairs: the mean pair-mean error and its 95 % t interval.

    Parameters
    ----------
    name : AwfMethod
        A reading (key of ``sl.pair_mean``).

    Returns
    -------
    (float, float, float)
        Mean, lower and upper end; an error that is odd in every pair gives exactly (0, 0, 0).
    """
    instance_of(sl, LumvStudy, "sl")
    name = _key(name, sl.pair_mean, "name")
    h = np.asarray(sl.pair_mean[name], dtype=float)
    if _odd(sl, name):
        return 0.0, 0.0, 0.0
    lo, hi = mean_interval(h, 0.95)
    return float(h.mean()), float(lo), float(hi)


@dataclass(frozen=True)
class LumvReading:
    """The three properties of 'linear, unbiased, minimum variance' for one reading of the weights (E2.1c).

    Attributes
    ----------
    linear : bool
        Whether the fused value is linear in the readings (fixed weights).
    unbiased : bool or None
        Whether it is unbiased; None where the mean does not exist.
    minvar : bool or None
        Whether its MSE is within 5 % of the oracle's; None where the MSE is infinite.
    text : str
        The evidence, as the ledger quotes it.
    """

    linear: bool
    unbiased: bool | None
    minvar: bool | None
    text: str

    __result_spec__ = ResultSpec({"linear": flag(), "unbiased": instance(bool, np.bool_, optional=True),
                                  "minvar": instance(bool, np.bool_, optional=True), "text": text()})
    __post_init__ = validated_post_init



def lumv_readings(sl: LumvStudy) -> dict[AwfMethod, LumvReading]:
    """The three properties of 'linear, unbiased, minimum variance' under each reading of the weights.

    Parameters
    ----------
    sl : LumvStudy
        Output of :func:`fusion.scenarios.lecture_weighting.estimators.lumv_study` (antithetic pairs).

    Returns
    -------
    dict of AwfMethod to LumvReading
        Per reading (the oracle, the lecture's AWF under every guard and deletion, the centred AWF). Unbiased: exact where the fused error is odd in the
        noise (the sign-flip proposition for :data:`EVEN_WEIGHTS`; observed in every pair otherwise),
        else the bias measured on the antithetic pairs, within ±5 % of the reading's RMSE (TOST); minimum
        variance: MSE within 5 % of the oracle's (one-sided paired t test on the pairs' mean squared errors).
    """
    instance_of(sl, LumvStudy, "sl")
    out: dict[AwfMethod, LumvReading] = {}
    pairs = int(sl.pairs)
    for name in [AwfMethod.ORACLE, *(LECTURE_GUARD_METHODS[g] for g in (*wt.GUARDS, "delete")), AwfMethod.AWF_CENTRED]:
        linear = name == AwfMethod.ORACLE
        lin_txt = "linear (fixed weights)" if linear else "not linear (weights computed from the same readings)"
        if name == AwfMethod.AWF_LECTURE_NONE:
            out[name] = LumvReading(linear=False, unbiased=None, minvar=None,
                                    text=f"{lin_txt}; the fused error has a 1/t tail (Σ1/σ̂² has a positive density at 0): its mean "
                                 "is undefined and its MSE infinite, so it is neither unbiased nor of minimum variance; median error "
                                 f"{np.median(sl.err[name]):.4g} ({sl.runs} runs)")
            continue
        rmse = float(np.sqrt(np.mean(sl.sq[name])))
        if name in EVEN_WEIGHTS and _odd(sl, name):
            ub, ub_txt = True, ("unbiased exactly: its weights are even in the noise, so the error is odd, e(−V) = −e(V) "
                                f"(|e(V) + e(−V)| below 10⁻⁶ of the largest error in all {pairs:,} antithetic pairs: "
                                "round-off), and its mean is 0 for any noise symmetric about 0 (proposition)")
        elif _odd(sl, name):
            ub, ub_txt = True, (f"mean error 0: e(V) + e(−V) = 0 in every one of the {pairs:,} antithetic pairs (not by the "
                                "proposition: here every run falls back to equal weights, the mean of means)")
        else:
            b, lo, hi = lumv_bias(sl, name)
            tost = _unbiased(sl.pair_mean[name], rmse, "mean error")
            ub = tost.holds
            ub_txt = (f"{'biased' if lo > 0 or hi < 0 else 'no bias resolved'}: mean error {b:+.5f} (95 % CI "
                      f"[{lo:+.5f}, {hi:+.5f}], from {pairs:,} antithetic pairs), {100 * abs(b) / rmse:.1f} % of the fused "
                      f"RMSE {rmse:.3f}; within ±5 % of it {'shown' if tost.holds else 'not shown'} (TOST)")
        mv, mv_txt = ((True, "the oracle itself") if name == AwfMethod.ORACLE
                      else _non_inferior(sl.pair_sq[name], sl.pair_sq[AwfMethod.ORACLE]))
        out[name] = LumvReading(linear=linear, unbiased=ub, minvar=mv, text=f"{lin_txt}; {ub_txt}; minimum variance: {mv_txt}")
    return out


@_PARAMS("sl")
def glue_lumv(sl: LumvStudy) -> GlueValues:
    """Glue values of E2.1c (keys ``lec_lumv_*``): bias, RMSE and MSE ratio to the oracle of every reading.

    Returns
    -------
    GlueValues
        Glue keys (prefixed ``lec_``) and rounded values; ``lec_lumv_n_hold_nonlinear``: readings with
        estimated weights that are unbiased and of minimum variance (linearity not required).

    Raises
    ------
    TypeError
        ``sl`` not a LumvStudy.
    ValueError
        ``sl`` whose antithetic pairs cancel exactly for the ``|σ̂²|`` reading (every pair's mean error 0, as at
        ``sl.x = 0``, where the lecture's variance estimates are even in the noise): ``lec_lumv_se_gain``, the
        standard error of the plain runs over that of the pairs, has no finite value; named.
    """
    instance_of(sl, LumvStudy, "sl")
    pm = sl.pair_mean[AwfMethod.AWF_LECTURE_ABS]
    if not np.std(pm, ddof=1) > 0:
        raise ValueError(f"sl (x = {shown(sl.x)}): every antithetic pair of the |σ̂²| reading cancels exactly, so "
                         "glue_lumv's standard-error gain of the pairs (lec_lumv_se_gain) is infinite; its values "
                         "are E2.1c's at a level whose pairs do not cancel (the chapter's x = 900)")
    r = lumv_readings(sl)
    tag = {AwfMethod.ORACLE: "oracle", AwfMethod.AWF_LECTURE_FLOOR: "floor", AwfMethod.AWF_LECTURE_ABS: "abs",
           AwfMethod.AWF_LECTURE_EQUAL: "equal", AwfMethod.AWF_CENTRED: "cen"}
    d: dict[str, tuple[float, int]] = {}
    for nm, t_ in tag.items():
        b, lo, hi = lumv_bias(sl, nm)
        rmse = float(np.sqrt(np.mean(sl.sq[nm])))
        d[f"lumv_bias_{t_}"] = (b, 5)
        d[f"lumv_bias_lo_{t_}"] = (lo, 5)
        d[f"lumv_bias_hi_{t_}"] = (hi, 5)
        d[f"lumv_rmse_{t_}"] = (rmse, 4)
        d[f"lumv_bias_pct_{t_}"] = (100 * abs(b) / rmse, 1)
        d[f"lumv_mse_{t_}"] = (float(np.mean(sl.sq[nm])), 6)
        d[f"lumv_ratio_{t_}"] = (float(np.mean(sl.sq[nm]) / np.mean(sl.sq[AwfMethod.ORACLE])), 3)
    # the plain mean of the runs, without the pairs: what 'runs / 2' independent runs would have shown
    e = sl.err[AwfMethod.AWF_LECTURE_ABS][: sl.pairs]
    lo, hi = mean_interval(e, 0.95)
    d.update({"lumv_plain_abs": (float(e.mean()), 4), "lumv_plain_lo_abs": (float(lo), 4), "lumv_plain_hi_abs": (float(hi), 4),
              "lumv_se_gain": (float(np.std(e, ddof=1) / np.std(pm, ddof=1)), 0)})
    d["lumv_bound"] = (sl.bound, 6)
    d["lumv_median_none"] = (float(np.median(sl.err[AwfMethod.AWF_LECTURE_NONE])), 4)
    out: GlueValues = _r(d)
    out["lec_lumv_runs"] = int(sl.runs)
    out["lec_lumv_pairs"] = int(sl.pairs)
    out["lec_lumv_n_hold_nonlinear"] = int(sum(bool(v.unbiased and v.minvar) for k, v in r.items() if k != AwfMethod.ORACLE))
    out["lec_lumv_n_readings"] = len(r) - 1
    for nm, t_ in tag.items():
        out[f"lec_lumv_unbiased_{t_}"] = "shown" if r[nm].unbiased else "not shown"
        out[f"lec_lumv_minvar_{t_}"] = "shown" if r[nm].minvar else "not shown"
    b, lo, hi = lumv_bias(sl, AwfMethod.AWF_LECTURE_ABS)
    out["lec_lumv_abs_biased"] = "biased" if lo > 0 or hi < 0 else "no bias resolved"
    return out


def table_symmetry(s: SymmetryStudy) -> pd.DataFrame:
    """The sign-flip check of :func:`fusion.scenarios.lecture_weighting.estimators.symmetry_study`, one row per fusion.

    Parameters
    ----------
    s : SymmetryStudy
        Output of :func:`fusion.scenarios.lecture_weighting.estimators.symmetry_study`.

    Returns
    -------
    pandas.DataFrame
        The largest |e(V) + e(−V)| (round-off printed as "< 10⁻⁶ of max |e|"), the largest |e|, and whether the error
        is odd (so the fusion unbiased for symmetric noise).
    """
    instance_of(s, SymmetryStudy, "s")
    rows = {}
    for m in s.methods:
        res, sc_ = s.residual[m], s.scale[m]
        rows[METHOD_LABELS[m]] = {"max |e(V) + e(−V)|": ("round-off (< 10⁻⁶ of max |e|)" if s.even[m] else f"{res:.4f}"),
                                  "max |e(V)|": f"{sc_:.4f}", "error odd in the noise": "yes" if s.even[m] else "no"}
    tab = pd.DataFrame(rows).T
    tab.index.name = f"X = {s.x:g} (unless stated), k = {s.k}, {s.runs} runs"
    return tab


def glue_ar1(a: AR1Study) -> GlueValues:
    """Glue values of the AR(1) study (keys ``lec_ar_*``).

    Parameters
    ----------
    a : AR1Study
        Output of :func:`fusion.scenarios.lecture_weighting.estimators.ar1_study`.

    Returns
    -------
    GlueValues
        Glue key → value.
    """
    instance_of(a, AR1Study, "a")
    return {"lec_ar_phi": round(a.phi, 2), "lec_ar_k": int(a.k), "lec_ar_runs": int(a.runs),
            "lec_ar_c": round(a.c, 2), "lec_ar_bound": round(a.bound, 5), "lec_ar_cbound": round(a.c * a.bound, 5),
            "lec_ar_oracle": round(a.mse_oracle, 5), "lec_ar_mom": round(a.mse_mean_of_means, 5),
            "lec_ar_lec_lo": round(float(np.min(a.ratio_lecture)), 3),
            "lec_ar_lec_hi": round(float(np.max(a.ratio_lecture)), 3),
            "lec_ar_cen_lo": round(float(np.min(a.ratio_centred)), 3),
            "lec_ar_cen_hi": round(float(np.max(a.ratio_centred)), 3),
            "lec_ar_one_minus_ck": round(1.0 - a.c / a.k, 3),
            "lec_ar_cen_ratio": round(a.mse_centred / a.mse_oracle, 2),
            "lec_ar_abs_ratio": round(a.mse_lecture_abs / a.mse_oracle, 2)}


def glue_tail(tl: TailStudy) -> GlueValues:
    """Glue values of the tail check of the literal AWF (keys ``lec_tail_*``; the claim texts quote them too).

    Parameters
    ----------
    tl : TailStudy
        Output of :func:`fusion.scenarios.lecture_weighting.estimators.tail_study`.

    Returns
    -------
    GlueValues
        Glue key → value.
    """
    instance_of(tl, TailStudy, "tl")
    distinct_printed([float(t) for t in tl.t], "tl.t", glue_part, "keys a glue value")  # a rebuilt study (fuzz 30b B2)
    te = np.asarray(tl.t_exceed, dtype=float)
    out: GlueValues = {"lec_tail_runs": f"{tl.runs:,}", "lec_tail_lo": round(float(te.min()), 2),
                           "lec_tail_hi": round(float(te.max()), 2), "lec_tail_tmax": f"{tl.t.max():g}",
                           "lec_tail_hill": round(float(tl.hill), 2),
                           "lec_tail_block_lo": sci(float(tl.block_mse.min()), 2),
                           "lec_tail_block_hi": sci(float(tl.block_mse.max()), 2),
                           "lec_tail_median_sq": round(float(tl.median_sq), 5)}
    for t, p in zip(tl.t, tl.exceed):
        out[f"lec_tail_p_{glue_part(float(t))}"] = round(float(p), 5)  # an identifier (fuzz 31b D4: 10.5 gave 10.5)
    return out
