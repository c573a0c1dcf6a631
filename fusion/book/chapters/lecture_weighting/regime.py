r"""Chapter 02, §2.1 (E2.1b): the estimators in their regime (a time-varying X, a change of the variances)
and the lecture's setting with one change of the noise SDs: comparisons, tables, figure and glue."""

from __future__ import annotations

from fusion.book._few_runs import study_runs_named
from fusion._counts import count
from fusion._validation import instance_of

import re

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from fusion._docstrings import ParameterDocs
from fusion.book.chapters.lecture import _holds, _r, legend_below
from fusion.book.ledger import Comparison
from fusion.book.tables import _SUPERSCRIPT
from fusion.book.style import METHOD_LABELS, color, new_figure
from fusion.book.glue import GlueValues
from fusion.scenarios.lecture_weighting.regime import (RegimeMethod, RegimeScenario, RegimeStudy, VarianceChange,
                                                       VarianceChangeStudy)
from fusion._shown import shown
from fusion.book.chapters._defaults import study_defaults

__all__ = [
    "regime_comparisons",
    "table_regime",
    "figure_regime",
    "glue_regime",
    "change_comparisons",
    "table_changes",
    "glue_changes",
    "ESTIMATOR_ROWS",
    "table_estimators",
]

#: The Parameters entries several functions of this module share (:class:`fusion._docstrings.ParameterDocs`).
_PARAMS = ParameterDocs({
    "s": "RegimeStudy\n    Output of :func:`fusion.scenarios.lecture_weighting.regime.regime_study`.",
})
#: The Parameters entry of the functions of the one-sided variance changes.
_CHANGES = ParameterDocs({
    "s": "VarianceChangeStudy\n    Output of :func:`fusion.scenarios.lecture_weighting.regime.variance_change_study`.",
})


# --------------------------------------------------------------------------- 2.1, regime (E2.1b)
_R = RegimeMethod
_S = RegimeScenario


def _label(key: str) -> str:
    """Display label of a scenario or change key (:data:`fusion.book.style.METHOD_LABELS`; an unregistered key is its
    own label)."""
    return METHOD_LABELS.get(key, str(key))


def _scenario_label(s: RegimeStudy, scen: RegimeScenario) -> str:
    """Display label of scenario ``scen`` of study ``s``: the level scenario at the study's level (fuzz 26d F4: its
    registered label says 900, the default ``level``, whatever level the study ran)."""
    return f"slow sine at {s.level:g}" if scen == _S.SINE_LEVEL else _label(scen)

#: The curves of F2.1c: (method, the style key of its colour and legend label, line style).
_REGIME_PLOT = ((_R.ORACLE, "oracle", ":"), (_R.MEAN, "mean", ":"), (_R.SAMPLE_GROWING, "sample_variance", "-"),
                (_R.LECTURE_GROWING, "memory_growing", "-"), (_R.CENTRED_FORGETTING, "memory_forgetting", "-"),
                (_R.CENTRED_WINDOW, "memory_window", "--"))


@_PARAMS("s")
@study_runs_named("s")
def regime_comparisons(s: RegimeStudy) -> dict[str, Comparison]:
    """The paired comparisons of E2.1b (per-run MSE over the evaluation window, paired by run).

    Returns
    -------
    dict of str to Comparison
        "Weights in time" in the lecture's setting (constant X, σ swap; the lecture's AWF of running
        means as A): ``"adapts"`` against the per-sample accumulation with centred forgetting
        estimates (the same information); ``"adapts_alt"`` the same with the second forgetting
        factor; ``"adapts_blue"`` against the per-sample BLUE (true variance of every sample);
        ``"adapts_running_means"`` against the running means weighted by their true variances (the
        best fusion of running means); ``"adapts_no_change"``: against the per-sample accumulation
        without a swap. Current readings (beyond the source): ``"adapt"`` growing memory (the
        lecture's recursion, cross-moments) against forgetting after the swap under a slow sine;
        ``"adapt_window"`` the same against the sliding window; ``"adapt_constant"`` growing
        against forgetting, swap at constant X; ``"stationary"`` growing against forgetting without a
        swap (slow sine). Which estimator where: ``"sine_vs_sample"``, ``"constant_vs_sample"``
        centred cross-moments against the sample variance (slow sine, constant X);
        ``"level_vs_mean"`` the lecture's estimator against the mean under the slow sine around the
        level; ``"diff_vs_centred_sine"``, ``"diff_vs_centred_step"`` the first-difference estimator
        against the centred one (growing memories; slow sine, step); ``"diff_vs_centred_swap"`` the
        same with forgetting, slow sine with the swap, ``"diff_vs_centred_swap_const"`` constant X with the swap; ``"fast_centred_vs_diff"``,
        ``"walk_centred_vs_diff"`` centred against differences (fast sine, random walk);
        ``"as_written_sine"`` the AWF of running means against the mean of the current readings
        under the sine. Sec. 2.2: ``"ls_adapt"`` the 1/m learning against the same allocations with
        forgetting after the swap (slow sine); ``"ls_stationary"`` the same without a swap.
    """
    instance_of(s, RegimeStudy, "s")
    sq, seed = s.sq, s.seed
    win = f"MSE over samples {s.change_at + 1}-{s.samples}"

    def c(scen: RegimeScenario, a: RegimeMethod, b: RegimeMethod) -> Comparison:
        return Comparison(sq[scen][a], sq[scen][b], METHOD_LABELS[a], METHOD_LABELS[b], "less",
                          f"{win}, {_scenario_label(s, scen)}", seed=seed)

    awf = _R.AWF_AS_WRITTEN
    return {
        "adapts": c(_S.CONSTANT_SWAP, awf, _R.PER_SAMPLE_FORGETTING),
        "adapts_alt": c(_S.CONSTANT_SWAP, awf, _R.PER_SAMPLE_FORGETTING_ALT),
        "adapts_blue": c(_S.CONSTANT_SWAP, awf, _R.PER_SAMPLE_BLUE),
        "adapts_running_means": c(_S.CONSTANT_SWAP, awf, _R.RUNNING_MEANS_ORACLE),
        "adapts_no_change": c(_S.CONSTANT, awf, _R.PER_SAMPLE_FORGETTING),
        "adapt": c(_S.SINE_SWAP, _R.LECTURE_GROWING, _R.CENTRED_FORGETTING),
        "adapt_window": c(_S.SINE_SWAP, _R.LECTURE_GROWING, _R.CENTRED_WINDOW),
        "adapt_constant": c(_S.CONSTANT_SWAP, _R.LECTURE_GROWING, _R.CENTRED_FORGETTING),
        "stationary": c(_S.SINE, _R.LECTURE_GROWING, _R.CENTRED_FORGETTING),
        "sine_vs_sample": c(_S.SINE, _R.CENTRED_GROWING, _R.SAMPLE_GROWING),
        "constant_vs_sample": c(_S.CONSTANT, _R.CENTRED_GROWING, _R.SAMPLE_GROWING),
        "level_vs_mean": c(_S.SINE_LEVEL, _R.LECTURE_GROWING, _R.MEAN),
        "diff_vs_centred_sine": c(_S.SINE, _R.DIFFERENCE_GROWING, _R.CENTRED_GROWING),
        "diff_vs_centred_step": c(_S.STEP, _R.DIFFERENCE_GROWING, _R.CENTRED_GROWING),
        "diff_vs_centred_swap": c(_S.SINE_SWAP, _R.DIFFERENCE_FORGETTING, _R.CENTRED_FORGETTING),
        "diff_vs_centred_swap_const": c(_S.CONSTANT_SWAP, _R.DIFFERENCE_FORGETTING, _R.CENTRED_FORGETTING),
        "fast_centred_vs_diff": c(_S.FAST, _R.CENTRED_GROWING, _R.DIFFERENCE_GROWING),
        "walk_centred_vs_diff": c(_S.WALK, _R.CENTRED_GROWING, _R.DIFFERENCE_GROWING),
        "as_written_sine": c(_S.SINE, awf, _R.MEAN),
        "ls_adapt": c(_S.SINE_SWAP, _R.LS_GROWING, _R.LS_FORGETTING),
        "ls_stationary": c(_S.SINE, _R.LS_GROWING, _R.LS_FORGETTING),
    }


def table_regime(s: RegimeStudy) -> pd.DataFrame:
    """Mean over runs of the per-run MSE over the evaluation window, one column per scenario of E2.1b.

    Parameters
    ----------
    s : RegimeStudy
        E2.1b: :func:`fusion.scenarios.lecture_weighting.regime.regime_study`, every scenario.

    Returns
    -------
    pandas.DataFrame
        Methods (by display label) × scenarios, as text with 4 significant digits (the MSEs span 10⁻⁴ to 700);
        "—" where a method is not run (the per-sample accumulation estimates a constant X).
    """
    instance_of(s, RegimeStudy, "s")
    tab = pd.DataFrame({_scenario_label(s, scen): {METHOD_LABELS[m]: (f"{float(np.mean(s.sq[scen][m])):#.4g}" if m in s.sq[scen] else "—")
                               for m in s.methods} for scen in s.scenarios})
    tab.index.name = f"MSE, samples {s.change_at + 1}-{s.samples} ({s.runs} runs)"
    return tab   # 4 significant digits, trailing zeros kept: 12.10, 0.0006608


@_PARAMS("s")
@study_defaults("s", "scenario", "smooth")  # a default the study does not fit, named by the study (fuzz 34b D2)
def figure_regime(s: RegimeStudy, scenario: str = RegimeScenario.SINE_SWAP, smooth: int = 25) -> Figure:
    """F2.1c: MSE against k and the weight of sensor 1 against k in one scenario of E2.1b.

    Parameters
    ----------
    scenario : str
        One of ``s.scenarios`` (a :class:`~fusion.scenarios.lecture_weighting.regime.RegimeScenario` key).
    smooth : int
        Length of the moving average applied to the MSE curves (display only).

    Returns
    -------
    matplotlib.figure.Figure
        Left: each method's MSE against k (trailing ``smooth``-sample mean, log); right: its mean weight of sensor 1; a
        line marks the change.
    """
    instance_of(s, RegimeStudy, "s")
    from fusion._validation import one_of

    scenario = one_of(scenario, tuple(s.scenarios), "scenario")
    smooth = count(smooth, "smooth", maximum=s.samples)  # a moving average of 1 to s.samples samples
    fig, axes = new_figure(1, 2, figsize=(7.5, 3.6))
    k = np.arange(1, s.samples + 1)
    ker = np.ones(smooth) / smooth
    for m, key, ls in _REGIME_PLOT:
        axes[0].plot(k, [np.nan] * (smooth - 1) + np.convolve(s.curve[scenario][m], ker, mode="valid").tolist(), ls,
                     color=color(key), label=METHOD_LABELS[key])
        axes[1].plot(k, s.w_best[scenario][m], ls, color=color(key))
    for ax in axes:
        ax.axvline(s.change_at + 1, color="0.6", lw=0.8)
        ax.set_xlabel("sample k")
    axes[0].set_yscale("log")
    axes[0].set_ylabel(f"MSE (trailing {smooth}-sample mean)")
    axes[1].set_ylabel("mean weight of sensor 1")
    axes[0].set_title(_scenario_label(s, scenario))
    axes[1].set_title(f"σ₁ = {np.sqrt(s.variances[0]):g} → {np.sqrt(s.swapped[0]):g} at k = {s.change_at + 1}")
    legend_below(fig, ncol=3)
    return fig


def _prose(text: str) -> str:
    """A ledger number (``"1.07×10^-5"``) written for prose: ``"1.07 × 10⁻⁵"`` (no e-notation)."""
    return re.sub(r"×10\^(-?\d+)", lambda m: " × 10" + m.group(1).translate(_SUPERSCRIPT), text)


def _interval_prose(c: Comparison) -> tuple[str, str, str]:
    """The mean paired difference of ``c`` and its 95 % interval's ends, as the ledger writes them, for prose."""
    d, lo, hi = c.interval()
    return _prose(c.written(d)), _prose(c.written(lo)), _prose(c.written(hi))


@_PARAMS("s")
@study_runs_named("s")
def glue_regime(s: RegimeStudy) -> GlueValues:
    """Glue values of E2.1b (keys ``lec_rgm_*``): mean MSEs, paired differences and 95 % intervals.

    MSEs are glued as text at 4 significant digits, as the table prints them; differences and
    interval ends as text with the digits the ledger writes them with
    (:meth:`fusion.book.ledger.Comparison.written`). Cite text with ``{glue:text}`` and no format (``{glue:}`` would quote it).

    Returns
    -------
    GlueValues
        Glue keys (prefixed ``lec_``) and values.
    """
    instance_of(s, RegimeStudy, "s")
    sq = s.sq
    d: dict[str, tuple[float, int]] = {
        "rgm_runs": (s.runs, 0), "rgm_K": (s.samples, 0), "rgm_change": (s.change_at + 1, 0),
        "rgm_amp": (s.amplitude, 1), "rgm_period": (s.period, 0), "rgm_step": (s.step, 1),
        "rgm_lambda": (s.forgetting, 2), "rgm_lambda_alt": (s.forgetting_alt, 2),
        "rgm_mem": (1 / (1 - s.forgetting), 0), "rgm_window": (s.window, 0),
        "rgm_level": (s.level, 0), "rgm_fast_period": (s.fast_period, 0), "rgm_walk_step": (s.walk_step, 1),
        "rgm_before": (s.change_at, 0),
    }
    out: GlueValues = _r(d)
    short = {_R.ORACLE: "oracle", _R.MEAN: "mean", _R.SAMPLE_GROWING: "sample", _R.DIFFERENCE_GROWING: "diff",
             _R.DIFFERENCE_FORGETTING: "diff_forget", _R.LECTURE_GROWING: "lec", _R.CENTRED_GROWING: "cen",
             _R.CENTRED_FORGETTING: "forget", _R.CENTRED_WINDOW: "window", _R.AWF_AS_WRITTEN: "written",
             _R.RUNNING_MEANS_ORACLE: "rm_oracle", _R.PER_SAMPLE_FORGETTING: "ps", _R.PER_SAMPLE_FORGETTING_ALT: "ps_alt",
             _R.PER_SAMPLE_BLUE: "blue", _R.LS_GROWING: "lsg", _R.LS_FORGETTING: "lsf"}
    scen = {_S.CONSTANT: "const", _S.SINE: "sine", _S.SINE_LEVEL: "sine900", _S.FAST: "fast", _S.WALK: "walk",
            _S.STEP: "step", _S.CONSTANT_SWAP: "const_swap", _S.SINE_SWAP: "sine_swap"}
    for sc_name, sk in scen.items():
        for m, mk in short.items():
            if m in sq[sc_name]:
                out[f"lec_rgm_{mk}_{sk}"] = f"{float(np.mean(sq[sc_name][m])):#.4g}"
    for key, cmp in regime_comparisons(s).items():
        out[f"lec_rgm_d_{key}"], out[f"lec_rgm_lo_{key}"], out[f"lec_rgm_hi_{key}"] = _interval_prose(cmp)
        out[f"lec_rgm_wins_{key}"] = int(np.sum(np.subtract(cmp.a, cmp.b) < 0))
    ratio = float(np.mean(sq[_S.CONSTANT_SWAP][_R.AWF_AS_WRITTEN])
                  / np.mean(sq[_S.CONSTANT_SWAP][_R.PER_SAMPLE_FORGETTING]))
    out["lec_rgm_ratio_adapts"] = f"{ratio:.2f}"
    ve = s.var_est
    out["lec_rgm_sd_sample"] = f"{float(np.std(ve['sample'])):#.3g}"
    out["lec_rgm_sd_centred"] = f"{float(np.std(ve['centred'])):#.3g}"
    out["lec_rgm_sd_ratio"] = f"{float(np.std(ve['centred']) / np.std(ve['sample'])):.2f}"
    out["lec_rgm_nonpos"] = int(sum(s.n_nonpositive.values()))
    return out


@_CHANGES("s")
@study_runs_named("s")
def change_comparisons(s: VarianceChangeStudy) -> dict[tuple[str, RegimeMethod], Comparison]:
    """The lecture's AWF of running means against the per-sample fusions after each change of :func:`variance_change_study`.

    Returns
    -------
    dict
        ``(change, method)`` → the AWF as written against ``method`` (claim "less"), per-run MSE over the
        evaluation window, paired by run, for every method but the AWF itself.
    """
    instance_of(s, VarianceChangeStudy, "s")
    awf = _R.AWF_AS_WRITTEN
    win = f"MSE over samples {s.change_at + 1}-{s.samples}, constant X"
    return {(ch_, m): Comparison(s.sq[ch_][awf], s.sq[ch_][m], METHOD_LABELS[awf], METHOD_LABELS[m], "less",
                                 f"{win}, {_label(ch_)}", seed=s.seed)
            for ch_ in s.changes for m in s.methods if m != awf}


@_CHANGES("s")
@study_runs_named("s")
def table_changes(s: VarianceChangeStudy) -> pd.DataFrame:
    """E2.1b in the lecture's setting: after each change of the noise SDs, the AWF of running means against the rest.

    Returns
    -------
    pandas.DataFrame
        One row per change: the mean window MSE of the AWF as written, and its paired difference with the
        per-sample accumulation (λ as in the study), the per-sample BLUE and the running means weighted by
        their true variances, each with its 95 % interval and what it shows.
    """
    instance_of(s, VarianceChangeStudy, "s")
    word = {"reproduced": "AWF lower", "contradicted": "AWF higher", "not distinguishable": "not distinguishable"}
    cmp = change_comparisons(s)
    rows = []
    for ch_ in s.changes:
        row = {"change": _label(ch_), "AWF as written": f"{float(np.mean(s.sq[ch_][_R.AWF_AS_WRITTEN])):#.4g}"}
        for m, lab in ((_R.PER_SAMPLE_FORGETTING, f"minus per-sample, λ = {s.forgetting:g}"),
                       (_R.PER_SAMPLE_BLUE, "minus per-sample BLUE"),
                       (_R.RUNNING_MEANS_ORACLE, "minus running means, oracle")):
            c = cmp[ch_, m]
            d, lo, hi = _interval_prose(c)
            row[lab] = f"{d} [{lo}, {hi}], {word[c.status()]}"
        rows.append(row)
    tab = pd.DataFrame(rows).set_index("change")
    tab.columns.name = f"MSE, samples {s.change_at + 1}-{s.samples} ({s.runs} runs)"
    return tab


@_CHANGES("s")
@study_runs_named("s")
def glue_changes(s: VarianceChangeStudy) -> GlueValues:
    """Glue values of the one-sided variance changes (keys ``lec_chg_*``): MSEs and paired differences as text.

    Returns
    -------
    GlueValues
        ``lec_chg_<change>_<method>`` (MSE, 4 significant digits) and ``lec_chg_<d|lo|hi>_<change>_<method>``
        (as the ledger writes them), with change ``swap``, ``degrade``, ``improve`` (the study's changes of those
        :class:`~fusion.scenarios.lecture_weighting.regime.VarianceChange` keys, in any order; a change of another
        key is not glued) and method ``ps`` (per-sample, forgetting), ``blue`` or ``awf``.

    Raises
    ------
    TypeError
        ``s`` not a VarianceChangeStudy.
    ValueError
        ``s`` without one of the three changes, named.
    """
    instance_of(s, VarianceChangeStudy, "s")
    tag = {VarianceChange.SWAP: "swap", VarianceChange.DEGRADE: "degrade", VarianceChange.IMPROVE: "improve"}
    _holds(s.changes, tag, "s", "changes", "glue_changes")
    mk = {_R.PER_SAMPLE_FORGETTING: "ps", _R.PER_SAMPLE_BLUE: "blue", _R.RUNNING_MEANS_ORACLE: "rm",
          _R.PER_SAMPLE_FORGETTING_ALT: "ps_alt"}
    out: GlueValues = {}
    for ch_, ct in tag.items():
        out[f"lec_chg_{ct}_awf"] = f"{float(np.mean(s.sq[ch_][_R.AWF_AS_WRITTEN])):#.4g}"
        for (c_, m), c in change_comparisons(s).items():
            if c_ != ch_:
                continue
            out[f"lec_chg_{ct}_{mk[m]}"] = f"{float(np.mean(s.sq[ch_][m])):#.4g}"
            for name, text in zip(("d", "lo", "hi"), _interval_prose(c)):
                out[f"lec_chg_{name}_{ct}_{mk[m]}"] = text
    return out


def _change(s: VarianceChangeStudy, key: VarianceChange, name: str = 's["schg"]',
            reader: str = "the change readings") -> VarianceChange:
    """``key`` if :func:`fusion.scenarios.lecture_weighting.regime.variance_change_study` ran that change, else a
    ValueError naming ``name`` (the chapter's rule, ``_holds``)."""
    _holds(s.changes, (key,), name, "change", reader)
    return key


#: Rows of :func:`table_estimators`: the E2.1b methods that differ only in how the current readings' variances are
#: estimated (causal weights on the current readings; non-positive estimates as |σ̂²|), and the oracle.
ESTIMATOR_ROWS: tuple[RegimeMethod, ...] = (_R.SAMPLE_GROWING, _R.DIFFERENCE_GROWING, _R.DIFFERENCE_FORGETTING,
                                            _R.LECTURE_GROWING, _R.CENTRED_GROWING, _R.CENTRED_FORGETTING,
                                            _R.CENTRED_WINDOW, _R.ORACLE)


def table_estimators(s: RegimeStudy) -> pd.DataFrame:
    """The variance estimators of E2.1b side by side (review §7): the rows :data:`ESTIMATOR_ROWS` of :func:`table_regime`.

    No new computation: the same mean MSEs over the evaluation window as the regime table, for the methods that fuse the
    current readings, so that the estimators can be compared scenario by scenario.

    Parameters
    ----------
    s : RegimeStudy
        The study of :func:`fusion.scenarios.lecture_weighting.regime.regime_study`, as for :func:`table_regime`.

    Returns
    -------
    pandas.DataFrame
        Estimators × scenarios, text at 4 significant digits ("—" where not run).
    """
    instance_of(s, RegimeStudy, "s")
    tab = table_regime(s)
    return tab.loc[[METHOD_LABELS[m] for m in ESTIMATOR_ROWS if METHOD_LABELS[m] in tab.index]]
