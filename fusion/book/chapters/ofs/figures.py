"""Chapter 01 (the optimal fusion set): the figures and the Monte-Carlo table.

Figs. 1-4 of the source and the Monte-Carlo repetition.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import pandas as pd
from matplotlib.figure import Figure
from numpy.typing import ArrayLike

from fusion._counts import count, sequence
from fusion._validation import as_array, scalar, window as check_window
from fusion.book.style import METHOD_LABELS, color, new_figure
from fusion.book.tables import rounded
from fusion.scenarios import thermocouples
from fusion.scenarios.thermocouples import PairedStudy
from fusion.book.chapters.ofs.settings import METHODS, FailureCase
from fusion.book.glue import GlueValues

__all__ = [
    "mc_numbers",
    "figure_readings",
    "figure_errors",
    "mc_table",
    "figure_mc",
    "figure_scale",
]

#: Columns of the Monte-Carlo table that its figure and glue read (issue 36: named once): the best linear
#: estimator's error bound without a failure, and the share of epochs in which the optimal set is the best method.
BOUND_CLEAN = "bound (no failure)"
OFS_BEST_SHARE = "share of epochs where the optimal set is best"


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
    z = as_array(readings, "readings", ndim=2)
    hl = [count(h, f"highlight[{i}]", maximum=z.shape[1]) for i, h in enumerate(sequence(highlight, "highlight"))]
    if hl:
        check_window(window, "window", z.shape[0], one_based=True)
    truth = scalar(truth, "truth")
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
        Rows (noise, case: the label of a :class:`~fusion.book.chapters.ofs.FailureCase`); one column per method (°C, 3 decimals), the bound without failure
        (``NaN`` with failure) and the share of epochs at which the optimal set is best.
    """
    rows = {}
    for label, st in studies.items():
        for case in FailureCase:
            failure = case is FailureCase.FAILURE
            row: dict[str, float] = {METHOD_LABELS[m]: float(st.errors(m, failure).mean()) for m in st.clean}
            row[BOUND_CLEAN] = (np.nan if failure else thermocouples.best_linear_abs_error(sigmas[label]))
            row[OFS_BEST_SHARE] = st.best_share("optimal_fusion_set", failure)
            rows[(label, METHOD_LABELS[case])] = row                # the case's label
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
    cases = [METHOD_LABELS[c] for c in FailureCase]               # the table's rows are labelled by them
    fig, axes = new_figure(1, len(settings), figsize=(7.5, 4.0), sharey=True)
    axes = np.atleast_1d(axes)
    for ax, s_label in zip(axes, settings):
        xpos = np.arange(len(cases))
        for j, m in enumerate(METHODS):
            ax.bar(xpos + (j - 1) * 0.26, [table.loc[(s_label, c), METHOD_LABELS[m]] for c in cases], 0.26,
                   color=color(m), label=METHOD_LABELS[m])
        ax.hlines(table.loc[(s_label, cases[0]), BOUND_CLEAN], -0.45, 0.45, color=color("bound"),
                  lw=2, label="bound (inverse-variance mean)")
        ax.set_xticks(xpos, [f"{cases[0]}\n(all samples)", f"{cases[1]}\n(samples 50-80)"])
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


def mc_numbers(mc: pd.DataFrame, studies: Mapping[str, PairedStudy], sigmas: Mapping[str, object],
               n_runs: int) -> GlueValues:
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
    GlueValues
        Glue key -> value (mean absolute errors in °C, 3 decimals; shares; the direct mean-square-error ratio).

    References
    ----------
    * Yang G. N., Feng X. F., Fan L. J. (2012). Multi-sensor data fusion algorithm based on optimal fusion set.
    """
    hs, eq = sigmas
    L = METHOD_LABELS
    C, F = FailureCase.NONE, FailureCase.FAILURE
    mcv = {(s, f, m): rounded(mc.loc[(s, L[f]), L[m]], 3) for s in sigmas for f in FailureCase for m in METHODS}
    share = mc[OFS_BEST_SHARE]
    return {
        "ofs_n_runs": n_runs,
        "ofs_mc_eq_clean_ofs": mcv[(eq, C, "optimal_fusion_set")], "ofs_mc_eq_clean_mean": mcv[(eq, C, "mean")],
        "ofs_mc_hs_clean_ofs": mcv[(hs, C, "optimal_fusion_set")], "ofs_mc_hs_clean_mean": mcv[(hs, C, "mean")],
        "ofs_mc_hs_clean_sup": mcv[(hs, C, "support_degree")],
        "ofs_mc_eq_bound": rounded(mc.loc[(eq, L[C]), BOUND_CLEAN], 3),
        "ofs_mc_hs_fail_ofs": mcv[(hs, F, "optimal_fusion_set")], "ofs_mc_hs_fail_mean": mcv[(hs, F, "mean")],
        "ofs_mc_hs_fail_sup": mcv[(hs, F, "support_degree")],
        "ofs_mc_eq_fail_ofs": mcv[(eq, F, "optimal_fusion_set")], "ofs_mc_eq_fail_sup": mcv[(eq, F, "support_degree")],
        "ofs_mc_best_share_max": rounded(share.max(), 3), "ofs_mc_best_share_min": rounded(share.min(), 3),
        "ofs_mc_mse_ratio": rounded(float(np.mean(studies[eq].clean["optimal_fusion_set"] ** 2)
                                          / np.mean(studies[eq].clean["mean"] ** 2)), 3),
        "ofs_set_size_hs": rounded(studies[hs].set_size.mean(), 2), "ofs_set_size_eq": rounded(studies[eq].set_size.mean(), 2),
    }
