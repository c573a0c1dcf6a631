r"""Chapter 02, §2.2 (E2.2): variance learning, its limit and the learned weights' random check: tables,
figures and glue."""

from __future__ import annotations

from fusion._counts import sequence
from fusion._limits import LOOP_STEP, work
from fusion._validation import count, instance_of, scalar

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from fusion._docstrings import ParameterDocs, reads_results
from fusion.book.chapters.lecture import _holds, _key, _lec_glue, _r, legend_below
from fusion.book.tables import roundoff
from fusion.book.glue import GlueValues
from fusion.book.style import METHOD_LABELS, color, new_figure
from fusion.book.tables import rounded
from fusion.readings import weighting as wt
from fusion.scenarios.lecture_weighting.learning import (LearnedLimitCheck, LearningStudy, _CHECK_NS,
                                                         _limit_check_units)
from fusion._counts import seed as check_seed
from fusion.book.chapters._defaults import study_defaults

__all__ = [
    "table_22",
    "table_22_display",
    "figure_22a",
    "figure_22b",
    "glue_22",
    "glue_learning_check",
    "learning_settling",
    "spread_check",
]

#: The Parameters entries several functions of this module share (:class:`fusion._docstrings.ParameterDocs`).
_PARAMS = ParameterDocs({
    "s": "LearningStudy\n    Result of :func:`fusion.scenarios.lecture_weighting.learning.learning_study`.",
    "s22": "LearningStudy\n    Output of :func:`fusion.scenarios.lecture_weighting.learning.learning_study`.",
})


# --------------------------------------------------------------------------- 2.2
#: Headers of table 2.2 that this module's glue and the chapter's evidence read (issue 36: named once): the best
#: single sensor's MSE and the learned weights' limit MSE.
MIN_R = "min Rᵢ"
LEARNED_LIMIT = "learned (limit)"
#: The table's column of each field of :class:`~fusion.scenarios.lecture_weighting.learning.LearningRow`, in order.
_COLUMNS_22 = {"R": "R", "min_r": MIN_R, "optimal": "optimal", "learned_limit": LEARNED_LIMIT,
               "learned_mc": "learned (MC)", "mean": "mean", "max_rel_limit_dev": "max |R̂ − limit|/limit",
               "corrected_mc": "corrected (MC)"}


def table_22(s: LearningStudy) -> pd.DataFrame:
    """E2.2 table (numbers rounded to 4 decimals), indexed by R.

    Parameters
    ----------
    s : LearningStudy
        E2.2 (:func:`fusion.scenarios.lecture_weighting.learning.learning_study`), one row a setting.

    Returns
    -------
    pandas.DataFrame
        Index R (the true variances); columns min Rᵢ, optimal, learned (limit and MC), corrected (MC) and mean fused
        variances, and the largest ``|R̂ − limit|/limit``.
    """
    instance_of(s, LearningStudy, "s")
    rows = [{col: getattr(r, f) for f, col in _COLUMNS_22.items()} for r in s.rows]
    return pd.DataFrame(rows).set_index("R").round(4)


@_PARAMS("s")
def table_22_display(s: LearningStudy) -> pd.DataFrame:
    """E2.2 table as displayed: formatted, "n/a (n = 2)" where the correction does not apply.

    Returns
    -------
    pandas.DataFrame
        :func:`table_22`'s columns as strings with 4 decimals.
    """
    instance_of(s, LearningStudy, "s")
    tab = table_22(s)[[MIN_R, "optimal", LEARNED_LIMIT, "learned (MC)", "corrected (MC)", "mean"]]
    return tab.map(lambda v: "n/a (n = 2)" if pd.isna(v) else f"{v:.4f}")


@_PARAMS("s")
@study_defaults("s", "n")  # a default the study does not fit, named by the study (fuzz 34b D2)
def figure_22a(s: LearningStudy, n: int = 3) -> Figure:
    """F2.2a: learned variances against m for the setting with ``n`` sensors, true and limit lines.

    Parameters
    ----------
    n : int
        Number of sensors of the setting shown; one of the study's settings (a study without a 3-sensor setting
        needs another ``n``: left at the default, the refusal names ``s``, the default and the settings it holds).

    Returns
    -------
    matplotlib.figure.Figure
        Each sensor's learned variance R̂ against epoch m (log), with its true Rᵢ (dotted) and the derived limit
        (dashed).
    """
    instance_of(s, LearningStudy, "s")
    R, Rh = s.learned[_key(n, s.learned, "n")]
    limit = wt.learned_variance_limit(R)
    fig, ax = new_figure(figsize=(7.0, 3.4))
    m_axis = np.arange(1, Rh.shape[0] + 1)
    for i, r in enumerate(R):
        c = color(f"sensor {i + 1}")
        ax.plot(m_axis, Rh[:, i], color=c, label=f"R̂ sensor {i + 1}")
        ax.axhline(r, color=c, ls=":", lw=1)
        ax.axhline(limit[i], color=c, ls="--", lw=1)
    ax.set_xscale("log")
    ax.set_xlabel("epoch m")
    ax.set_ylabel("learned variance")
    ax.set_title(f"R = ({', '.join(f'{r:g}' for r in R)}): dotted = true Rᵢ, dashed = derived limit")
    legend_below(fig, ncol=3)
    return fig


def figure_22b(s: LearningStudy) -> Figure:
    """F2.2b: fused variance per setting: best sensor, optimal, corrected, learned, mean.

    Parameters
    ----------
    s : LearningStudy
        Result of :func:`fusion.scenarios.lecture_weighting.learning.learning_study`: the settings' fused variances.

    Returns
    -------
    matplotlib.figure.Figure
        Bars per setting (n sensors, log): fused variance of the best sensor, optimal weights, corrected and learned
        (MC), and the mean.
    """
    instance_of(s, LearningStudy, "s")
    tab = table_22(s)
    fig, ax = new_figure(figsize=(7.5, 3.4))
    # (table column, method key: colour and legend label; the oracle's weights are labelled "optimal weights" here)
    cols = [(MIN_R, "best_sensor"), ("optimal", "oracle"), ("corrected (MC)", "ls_corrected"),
            ("learned (MC)", "ls_learning"), ("mean", "mean")]
    pos = np.arange(len(tab))
    for j, (col, c) in enumerate(cols):
        lab = "optimal weights" if c == "oracle" else METHOD_LABELS[c]
        ax.bar(pos + (j - 2) * 0.16, tab[col].fillna(0.0), width=0.16, label=lab, color=color(c))
    ax.set_yscale("log")
    ax.set_xticks(pos, [f"n = {len(row.R.split(','))}" for row in s.rows])
    ax.set_ylabel("fused variance")
    legend_below(fig, ncol=3)
    return fig


@_lec_glue
@_PARAMS("s")
def glue_22(s: LearningStudy) -> GlueValues:
    """Glue values of E2.2.

    ``lec_ls_r5_*`` and ``lec_ls_r2_*`` are those of the study's settings of 5 and of 2 sensors, whatever their order
    in ``r_sets``; the other values are taken over every setting.

    Raises
    ------
    TypeError
        ``s`` not a LearningStudy.
    ValueError
        ``s`` without a setting of 5 or of 2 sensors (E2.2's have both), named.
    """
    instance_of(s, LearningStudy, "s")
    tab = table_22(s)
    by_n = {len(R.split(",")): R for R in tab.index}  # R: the setting's variances; the sizes differ (learned[n])
    _holds(by_n, (5, 2), "s", "settings of n sensors", "glue_22")
    r5, r2 = tab.loc[by_n[5]], tab.loc[by_n[2]]
    out = _r({"ls_limit_maxrel": (tab["max |R̂ − limit|/limit"].max(), 4),
              "ls_r5_min": (r5[MIN_R], 4), "ls_r5_learned": (r5[LEARNED_LIMIT], 4),
              "ls_r5_opt": (r5["optimal"], 4), "ls_r2_learned": (r2[LEARNED_LIMIT], 4),
              "ls_r2_min": (r2[MIN_R], 4), "ls_n2_maxdev": (s.n2_maxdev, 12)})
    out["lec_ls_n2_maxdev_text"] = roundoff(s.n2_maxdev)
    # "no worse than the best sensor" fails only beyond the practical margin (rule R9, the mse quantity's 5 %)
    out["lec_ls_n_fail_learned"] = int((tab[LEARNED_LIMIT] > tab[MIN_R] * (1 + LS_MARGIN)).sum())
    out["lec_ls_n_far_opt"] = int((tab[LEARNED_LIMIT] > 1.1 * tab["optimal"]).sum())
    out["lec_ls_max_ratio_opt"] = rounded(float((tab[LEARNED_LIMIT] / tab["optimal"]).max()), 2)
    out["lec_ls_n_sets"] = len(tab)
    return out


@_PARAMS("s22")
@reads_results("llc", "s22")
def glue_learning_check(llc: LearnedLimitCheck, s22: LearningStudy) -> GlueValues:
    """Glue values of the learned weights' random check and of the learning's settling (keys ``lec_llc_*``).

    Parameters
    ----------
    llc : LearnedLimitCheck
        Output of :func:`fusion.scenarios.lecture_weighting.learning.learned_limit_check`.

    Returns
    -------
    GlueValues
        Glue keys (prefixed ``lec_``) and values; ``lec_llc_settle_max`` the latest settling epoch of the settings
        of 3 or more sensors.

    Raises
    ------
    TypeError
        ``llc`` not a LearnedLimitCheck, ``s22`` not a LearningStudy.
    ValueError
        ``s22`` without a setting of 3 or more sensors, named.
    """
    instance_of(llc, LearnedLimitCheck, "llc")
    instance_of(s22, LearningStudy, "s22")
    settle = learning_settling(s22)
    if not any(n >= 3 for n in settle):
        raise ValueError(f"s22 lacks a setting of 3 or more sensors that glue_learning_check reads (lec_llc_settle_max; "
                         f"it holds settings of {sorted(settle)} sensors)")
    factor = max(float(np.max(wt.learned_variance_limit(R) / R)) for R, _ in s22.learned.values())
    return {"lec_llc_sets": int(llc.sets), "lec_llc_above_mean": int(llc.above_mean),
            "lec_llc_above_best": int(llc.above_best),
            "lec_llc_above_best_pct": rounded(100 * llc.above_best / llc.sets, 0),
            "lec_llc_margin_pct": rounded(100 * llc.margin, 0),
            "lec_llc_max_ratio": rounded(llc.max_ratio_mean, 4), "lec_llc_n_lo": int(llc.ns[0]),
            "lec_llc_n_hi": int(llc.ns[-1]),
            "lec_llc_settle_max": int(max(v for k, v in settle.items() if k >= 3)),
            "lec_llc_limit_factor": rounded(factor, 1)}


@_PARAMS("s22")
def learning_settling(s22: LearningStudy, tol: float = 0.05) -> dict[int, int]:
    """Epoch after which the mean learned variances of E2.2 stay within ``tol`` of their limit, per setting.

    Parameters
    ----------
    tol : float
        Relative tolerance: a finite number > 0.

    Returns
    -------
    dict of int to int
        Number of sensors n of each setting → the first epoch m (1 to ``epochs``) from which
        :math:`\\max_i |\\bar R_i(m)/L_i - 1| \\le` ``tol`` holds for every later epoch of the study;
        ``epochs + 1`` (one past the study's last epoch) when it does not hold at the last epoch: the variances
        have not settled within the study.

    Raises
    ------
    TypeError
        ``s22`` not a LearningStudy, ``tol`` not a real number.
    ValueError
        ``tol`` NaN, infinite or not > 0.
    """
    instance_of(s22, LearningStudy, "s22")
    tol = scalar(tol, "tol", 0.0, lo_open=True)  # fuzz 21b, J: NaN read every epoch as settled
    out = {}
    for n, (R, Rh) in s22.learned.items():
        dev = np.max(np.abs(Rh / wt.learned_variance_limit(R) - 1), axis=1)
        bad = np.flatnonzero(dev > tol)
        out[int(n)] = int(bad[-1] + 2) if bad.size else 1
    return out


#: Practical margin of "no worse than" in record lec-ls-learning: the mse quantity's 5 % of the bar (rule R9).
LS_MARGIN = 0.05

#: Units of one half-width of :func:`spread_check` besides its check's own (book audit 76: a half-width of one draw,
#: counted 6,264 units, cost 1.1 ms, its check's six draws and its row: 1,000 half-widths 1.12 CPU-s, 100 0.13;
#: time.process_time, OPENBLAS_NUM_THREADS=1, minimum of 2, shared 2-core machine; 159,000 half-widths were
#: accepted, about 180 CPU-s): 220 * LOOP_STEP, about twice.
_SPREAD_ROW = 220 * LOOP_STEP


def spread_check(log_ranges: tuple[float, ...] = (0.5, 1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 6.0),
                 draws: int = 20000, seed: int = 2204) -> pd.DataFrame:
    """§2.2's random check at several spreads of the variances (review F7).

    :func:`fusion.scenarios.lecture_weighting.learning.learned_limit_check` (n = 3-8, ``draws`` sets per n) with log-variances
    U(−a, a) for each a of ``log_ranges``; a = 4 at the default ``draws`` and ``seed`` is the chapter's own check.

    Parameters
    ----------
    log_ranges : tuple of float
        Half-widths a (> 0, at most ``MAX_LOG_RANGE`` of ``fusion.scenarios.lecture_weighting.learning``, about 345:
        the variances e^u stay within the package's numeric range); the largest variance ratio in a set is at most
        e^(2a).
    draws : int
        Variance sets per n.
    seed : int

    Returns
    -------
    pandas.DataFrame
        One row per a: e^(2a), sets, % of sets where the learned fusion's variance exceeds the best sensor's by more
        than the 5 % margin, % by any amount, % above the mean's variance.

    Raises
    ------
    TypeError
        ``log_ranges`` not a sequence of numbers, ``draws`` or ``seed`` not an integer.
    ValueError
        ``log_ranges`` empty (no row to show) or an entry not finite and positive, or beyond ``MAX_LOG_RANGE``; every
        half-width's check together (``draws`` x 33 variances, 8 units each, and 226,000 units, per half-width)
        beyond the work budget
        (``fusion._limits.MAX_WORK``), counted before any entry is checked, naming ``log_ranges`` and ``draws``.
    """
    seed = check_seed(seed)
    from fusion.scenarios import lecture_weighting as sc

    ranges = sequence(log_ranges, "log_ranges", minimum=1, what="half-width")
    # rule 17: each half-width runs a whole check, counted before any entry is checked (fuzz 42b C8: 5 half-widths at
    # 3.7e6 draws, each within the check's own budget, ran 46 CPU-s)
    work((len(ranges), _limit_check_units(_CHECK_NS, count(draws, "draws")) + _SPREAD_ROW), "log_ranges and draws")
    ranges = [scalar(a, f"log_ranges[{i}]", lo=0.0, lo_open=True, hi=sc.learning.MAX_LOG_RANGE)
              for i, a in enumerate(ranges)]
    rows = []
    for a in ranges:
        r = sc.learned_limit_check(draws=draws, seed=seed, log_range=a)
        rows.append({"half-width a": f"{a:g}", "largest ratio e^(2a)": f"{np.exp(2 * a):,.0f}",
                     "sets": f"{r.sets:,d}",
                     "above best sensor by > 5 % (%)": f"{100 * r.above_best / r.sets:.1f}",
                     "above best sensor (%)": f"{100 * r.above_best_any / r.sets:.1f}",
                     "above the mean (%)": f"{100 * r.above_mean / r.sets:.1f}"})
    return pd.DataFrame(rows).set_index("half-width a")
