r"""Chapter 07 (time registration, Shi, Suo & Ma 2023): tables, figure recipes and the claims ledger.

The computations live in :mod:`fusion.scenarios.time_registration` and
:mod:`fusion.registration`; this module only assembles what the chapter shows.
"""

from __future__ import annotations

import functools
from collections.abc import Mapping, Sequence

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from matplotlib.figure import Figure
from numpy.typing import ArrayLike

from fusion import data
from fusion.book.ledger import Comparison, Conjunction, Evidence, Proposition, Unverifiable
from fusion.book.style import color, new_figure
from fusion.book.tables import integral_index
from fusion.scenarios import time_registration as sc

__all__ = [
    "exact_numbers",
    "benchmark_numbers",
    "robustness_readings",
    "S3_READINGS",
    "delay_break_even",
    "delay_table",
    "fig4_reading_table",
    "TWO",
    "IMPROVED",
    "CAUSAL_IMPROVED",
    "FIG4",
    "noise_free_table",
    "axes_tables",
    "registration_figure",
    "fig4_figure",
    "mc_table",
    "sigma_sweep",
    "sigma_figure",
    "ratio_sweep",
    "ratio_figure",
    "noise_level_table",
    "study",
    "cached_study",
    "PRIMARY_SIGMA",
    "ledger_evidence",
    "cost_count",
    "cost_values",
    "manoeuvre_values",
    "latency_values",
    "gain_values",
    "blue_whole_record",
    "stress_table",
    "keep",
    "STRESS",
    "CLASSES",
    "closed_form_table",
    "crossing_table",
    "benchmark_table",
    "period_change_table",
    "fusion_table",
    "fig4_compatibility",
    "robustness_table",
]

TWO = "two-point"
IMPROVED = "improved: Kalman + three-point (§4)"
CAUSAL_IMPROVED = "causal improved: Kalman + three-point extrapolation"
#: Methods of the source's Fig. 4 (and of the headline claim).
FIG4 = (TWO, IMPROVED)
#: The six methods the noise-level figure shows (the table shows every method).
FIGURE_METHODS = (TWO, "three-point", IMPROVED, "Kalman + two-point", "Kalman, predict (§3)", "least squares")


def noise_free_table(t1: ArrayLike, t2: ArrayLike) -> pd.DataFrame:
    """Noise-free registration error (m) of two-point, least squares and three-point at each instant.

    Parameters
    ----------
    t1, t2 : array_like
        Sensor-1 sample times and registration instants (s).

    Returns
    -------
    DataFrame, index the instants, one column per method (rounded to mm) and the derived
    two-point remainder :func:`fusion.scenarios.time_registration.two_point_remainder`.
    """
    t1, t2 = np.asarray(t1, dtype=float), np.asarray(t2, dtype=float)
    x1, x2 = sc.truth(t1), sc.truth(t2)
    table = pd.DataFrame({n: sc.register(n, t1, x1, t2, 1.0) - x2 for n in (TWO, "least squares", "three-point")},
                         index=pd.Index(t2, name="sensor-2 instant (s)")).round(3) + 0.0
    table["derived two-point error"] = sc.two_point_remainder(t1, t2)
    return integral_index(table)


def axes_tables(t1: ArrayLike, t2: ArrayLike) -> tuple[pd.DataFrame, pd.DataFrame]:
    """Published sample counts and axis maxima of Figs. 2-3 beside the scenario's.

    Parameters
    ----------
    t1 : array_like
        Sample times of sensor 1 (s).
    t2 : array_like
        Sample times of sensor 2 (s), the registration instants.

    Returns
    -------
    counts : DataFrame
        Published and computed (``reproduced``: samples in the 40 s window) numbers of measurements of each
        sensor, as integers, in the shape :func:`fusion.book.tables.highlight_mismatches` reads.
    axes : DataFrame
        Published axis maximum (m) of each panel and the largest value it should show (m).
    """
    x1, x2 = sc.truth(np.asarray(t1, dtype=float)), sc.truth(np.asarray(t2, dtype=float))
    ax = data.SHI2023_AXES.columns
    counts = pd.DataFrame({"published": np.asarray(data.SHI2023_CLAIMED_SAMPLES.values).round().astype(int),
                           "reproduced": [int(np.size(t1)), int(np.size(t2))]},
                          index=pd.Index(["sensor 1", "sensor 2"],
                                         name="number of measurements (reproduced: in the 40 s window)"))
    axes = pd.DataFrame(
        {"published axis maximum (m)": [ax[k][0] for k in ("fig2_before_y", "fig2_after_y",
                                                              "fig3_before_y", "fig3_after_y")],
         "largest value in the scenario (m)": [x1.max(), x2.max(), x1.max(), x2.max()]},
        index=pd.Index(["Fig. 2 before", "Fig. 2 after", "Fig. 3 before", "Fig. 3 after"], name="panel"))
    if np.all(axes.to_numpy() == np.round(axes.to_numpy())):   # whole metres: shown as integers
        axes = axes.round().astype(int)
    return counts, axes


#: Line style of each information class in the sweep figures (solid: causal; dashed: look-ahead;
#: dotted: whole record).
_CLASS_LINE = {"causal": "-", "look-ahead": "--", "whole record": ":"}


def registration_figure(t1: ArrayLike, t2: ArrayLike, method: str, label: str) -> Figure:
    """Figs. 2-3 redrawn against time: noise-free samples before, registered values after (closed figure).

    Parameters
    ----------
    t1 : array_like
        Sample times of sensor 1 (s).
    t2 : array_like
        Registration instants (s).
    method : str
        Registration method (see :func:`fusion.scenarios.time_registration.register`).
    label : str
        Legend label of the method.

    Returns
    -------
    matplotlib.figure.Figure
        Closed (displayed by the chapter).
    """
    t1, t2 = np.asarray(t1, dtype=float), np.asarray(t2, dtype=float)
    fig, (a1, a2) = new_figure(1, 2, figsize=(7.5, 3.6))
    a1.plot(t1, sc.truth(t1), "o", ms=4, color=color("sensor 1"), label="sensor 1")
    a1.plot(t2, sc.truth(t2), "s", ms=5, color=color("sensor 2"), label="sensor 2")
    a1.set(title="before registration", xlabel="time (s)", ylabel="x (m)")
    a1.legend(loc="upper left")
    a2.plot(t2, sc.register(method, t1, sc.truth(t1), t2, 1.0), "o", ms=4, color=color("sensor 1"),
            label=f"sensor 1, {label}")
    a2.plot(t2, sc.truth(t2), "s", ms=5, mfc="none", color=color("sensor 2"), label="sensor 2")
    a2.set(title="after registration", xlabel="time (s)")
    a2.legend(loc="upper left")
    plt.close(fig)
    return fig


def fig4_figure(mc: sc.MonteCarlo, exact: Mapping[str, float], axis_max: float) -> Figure:
    """Fig. 4 redrawn: per-run MSE and running mean of two-point and improved (closed figure).

    Parameters
    ----------
    mc : MonteCarlo
        Runs holding both Fig. 4 methods.
    exact : mapping
        Exact expected MSE (m²) of each method (dotted lines).
    axis_max : float
        Top of the published y-axis (m², dashed line).

    Returns
    -------
    matplotlib.figure.Figure
        Closed (displayed by the chapter).
    """
    fig, (a1, a2) = new_figure(1, 2, figsize=(7.5, 3.3), sharey=True)
    runs = np.arange(1, mc.runs + 1)
    for name, style in zip(FIG4, ("o-", "s-")):
        a1.plot(runs, mc.per_run[name], style, ms=3, color=color(name), label=name)
        a2.plot(runs, np.cumsum(mc.per_run[name]) / runs, style, ms=3, color=color(name), label=name)
        a2.axhline(exact[name], color=color(name), lw=0.8, ls=":")
    a1.axhline(axis_max, color=color("published"), lw=0.8, ls="--")
    a1.set(title="per run (dashed: top of\nthe published axis)", xlabel="Monte-Carlo run",
           ylabel="registration MSE (m²)")
    a2.set(title="running mean (dotted:\nexact expectation)", xlabel="Monte-Carlo run")
    handles, labels = a1.get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncols=2)
    plt.close(fig)
    return fig


def mc_table(mc: sc.MonteCarlo, exact: Mapping[str, float]) -> pd.DataFrame:
    """Exact expected MSE beside the mean of genuinely simulated runs, for every method.

    Parameters
    ----------
    mc : MonteCarlo
        Simulated runs of every method.
    exact : mapping of str to float
        Exact expected MSE (m²) of each method.

    Returns
    -------
    DataFrame
        Columns: information used, exact E[MSE] (m²), Monte-Carlo mean (m²), its standard
        error, and (mean - exact) / standard error; rounded to 4 decimals.
    """
    rows = {}
    for name, v in mc.per_run.items():
        se = v.std(ddof=1) / np.sqrt(v.size)
        rows[name] = {"information": sc.METHODS[name], "exact E[MSE] (m²)": exact[name],
                      "Monte Carlo (m²)": v.mean(), "standard error": se,
                      "difference / s.e.": (v.mean() - exact[name]) / se}
    return pd.DataFrame(rows).T.infer_objects().round(4)


def sigma_sweep(sigmas: Sequence[float], names: Sequence[str]) -> pd.DataFrame:
    """Exact expected MSE (m²) of each method (columns) at each noise level (index, m).

    Parameters
    ----------
    sigmas : sequence of float
        Noise standard deviations (m).
    names : sequence of str
        Registration methods.

    Returns
    -------
    pandas.DataFrame
    """
    return pd.DataFrame({n: [sc.expected(n, s) for s in sigmas] for n in names},
                        index=pd.Index(np.asarray(sigmas, dtype=float), name="σ (m)"))


def sigma_figure(sweep: pd.DataFrame) -> Figure:
    """Log-log plot of :func:`sigma_sweep`, the methods of ``FIGURE_METHODS`` only (closed figure).

    Parameters
    ----------
    sweep : pandas.DataFrame
        Output of :func:`sigma_sweep`.

    Returns
    -------
    matplotlib.figure.Figure
        Closed (displayed by the chapter).
    """
    fig, ax = new_figure(figsize=(7.0, 6.0))
    for name in [n for n in FIGURE_METHODS if n in sweep]:
        ax.loglog(sweep.index, sweep[name], "o", ls=_CLASS_LINE[sc.METHODS[name]], ms=3, color=color(name),
                  label=f"{name} [{sc.METHODS[name]}]")
    ax.set(xlabel="measurement noise σ (m)", ylabel="expected registration MSE (m²)")
    fig.legend(loc="outside lower center", ncols=1)     # below the axes, which keep the full width
    plt.close(fig)
    return fig


def ratio_sweep(periods: Sequence[float], sigma: float, names: Sequence[str]) -> pd.DataFrame:
    """Exact expected MSE (m²) against sensor 2's period (index, s); sensor 1 keeps 2 s, least squares fits over
    one sensor-2 period, at least the source's 5 s (so that the window holds two samples).

    Parameters
    ----------
    periods : sequence of float
        Periods of sensor 2 (s).
    sigma : float
        Noise standard deviation (m).
    names : sequence of str
        Registration methods.

    Returns
    -------
    pandas.DataFrame
    """
    rows = {}
    for p2 in periods:
        t1, t2 = sc.instants(p2)
        rows[float(p2)] = {n: sc.expected(n, sigma, t1, t2, window=max(float(p2), 5.0)) for n in names}
    out = pd.DataFrame(rows).T
    out.index.name = "sensor-2 period (s)"
    return integral_index(out)


def ratio_figure(ratio: pd.DataFrame) -> Figure:
    """Plot of :func:`ratio_sweep` (closed figure).

    Parameters
    ----------
    ratio : pandas.DataFrame
        Output of :func:`ratio_sweep`.

    Returns
    -------
    matplotlib.figure.Figure
        Closed (displayed by the chapter).
    """
    fig, ax = new_figure(figsize=(7.5, 3.6))
    for name in ratio:
        ax.plot(ratio.index, ratio[name], "o", ls=_CLASS_LINE[sc.METHODS[name]], ms=3, color=color(name), label=name)
    ax.set(xlabel="sensor-2 period (s); sensor 1: 2 s", ylabel="expected MSE (m²)")
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0))
    plt.close(fig)
    return fig


def noise_level_table(mcs: Mapping[float, sc.MonteCarlo], axis_max: float, block: int = 20) -> pd.DataFrame:
    """What Fig. 4 would look like at each noise level, from simulated runs.

    Parameters
    ----------
    mcs : mapping of σ (m) to MonteCarlo
        Runs holding both Fig. 4 methods.
    axis_max : float
        Top of Fig. 4's published y-axis (m²).
    block : int
        Runs per figure (Fig. 4 shows 20).

    Returns
    -------
    DataFrame, index σ, columns: runs; fraction of runs with both methods' MSE inside
    ``[0, axis_max]``; P(improved < two-point in one run); P(all ``block`` runs so ordered)
    estimated as the fraction of disjoint blocks of ``block`` runs that are.
    """
    rows = {}
    for s, mc in sorted(mcs.items()):
        a, b = mc.per_run[IMPROVED], mc.per_run[TWO]
        wins = a < b
        nb = mc.runs // block
        rows[float(s)] = {
            "runs": mc.runs,
            "both inside the axis": float(np.mean((a <= axis_max) & (b <= axis_max))),
            "P(improved wins a run)": float(np.mean(wins)),
            f"P(all {block} runs ordered)": float(np.mean(wins[: nb * block].reshape(nb, block).all(axis=1)))
            if nb else float("nan"),
        }
    out = pd.DataFrame(rows).T
    out.index.name = "σ (m)"
    out["runs"] = out["runs"].astype(int)
    return out.round(3)


# ---------------------------------------------------------------- issue 17: closed forms, fair benchmark, C6


#: The fair benchmark's two classes, by the information each method uses at an instant.
CLASSES: dict[str, tuple[str, ...]] = {
    "real time (causal)": ("two-point extrapolation", "Kalman, predict (§3)", CAUSAL_IMPROVED, "least squares",
                           "quadratic least squares (causal)"),
    "offline (look-ahead or whole record)": (TWO, "three-point", IMPROVED, "Kalman + two-point",
                                              "quadratic least squares (past + next sample)",
                                              "local quadratic least squares (last 4 + next sample)",
                                              "fixed-lag smoother (next sample)",
                                              "RTS smoother (whole record)", "cubic spline (whole record)"),
}


def closed_form_table(sigma_filter: float, sigma: float) -> pd.DataFrame:
    r"""Closed form :math:`E[\mathrm{MSE}] = b + g\sigma^2` of every method (filter tuned for ``sigma_filter``).

    Parameters
    ----------
    sigma_filter : float
        Noise level the Kalman methods assume (m).
    sigma : float
        Noise level at which the expectation is also evaluated (m).

    Returns
    -------
    DataFrame
        Index the methods; columns information, b (m²), g, and E[MSE] at ``sigma`` (m²); rounded to 4 decimals.
    """
    rows = {}
    for n in sc.METHODS:
        b, g = sc.mse_coefficients(n, sigma_filter)
        rows[n] = {"information": sc.METHODS[n], "b (m²)": b, "g": g, f"E[MSE] at σ = {sigma:g} m (m²)": b + g * sigma**2}
    out = pd.DataFrame(rows).T.infer_objects()
    num = out.select_dtypes("number").columns
    out[num] = out[num].round(4) + 0.0
    return out


def crossing_table(closed: pd.DataFrame) -> pd.DataFrame:
    r"""Noise level at which each pair of methods changes order, :math:`\sigma^* = \sqrt{(b_B - b_A)/(g_A - g_B)}`.

    Parameters
    ----------
    closed : DataFrame
        Output of :func:`closed_form_table`.

    Returns
    -------
    DataFrame
        One row per pair that crosses at a positive level: the method better below σ*, the one
        better above, and σ* (m, 2 decimals); sorted by σ*.
    """
    names = list(closed.index)
    rows = []
    for i, a in enumerate(names):
        for bname in names[i + 1:]:
            ba, ga = closed.loc[a, "b (m²)"], closed.loc[a, "g"]
            bb, gb = closed.loc[bname, "b (m²)"], closed.loc[bname, "g"]
            if ga == gb or (bb - ba) / (ga - gb) <= 0:
                continue
            s = float(np.sqrt((bb - ba) / (ga - gb)))
            low, high = (a, bname) if ba < bb else (bname, a)
            rows.append({"better below σ*": low, "better above σ*": high, "σ* (m)": round(s, 2)})
    return pd.DataFrame(rows).sort_values("σ* (m)", kind="stable").reset_index(drop=True)


def _paired(a: np.ndarray, b: np.ndarray) -> tuple[float, float, float]:
    from scipy import stats
    res = stats.ttest_rel(a, b)
    ci = res.confidence_interval(0.95)
    return float(np.mean(a - b)), float(ci.low), float(ci.high)


def benchmark_table(mc: sc.MonteCarlo, exact: Mapping[str, float]) -> pd.DataFrame:
    """The fair benchmark: each class's methods with the paired 95 % interval against the source's method.

    In the real-time class the reference is the source's §3 Kalman method, offline it is the
    improved method of §4.

    Parameters
    ----------
    mc : MonteCarlo
        Runs holding every method of :data:`CLASSES`.
    exact : mapping
        Exact expected MSE (m²) of each method.

    Returns
    -------
    DataFrame
        Index (class, method); columns information, exact E[MSE], Monte-Carlo mean, mean
        difference from the class reference and its 95 % interval (m², 4 decimals), verdict.
    """
    rows = {}
    for cls, names in CLASSES.items():
        ref = "Kalman, predict (§3)" if cls.startswith("real") else IMPROVED
        for n in sorted(names, key=lambda m: exact[m]):
            d, lo, hi = _paired(mc.per_run[n], mc.per_run[ref]) if n != ref else (0.0, 0.0, 0.0)
            verdict = ("reference" if n == ref else "better" if hi < 0 else "worse" if lo > 0
                       else "not distinguishable")
            rows[(cls, n)] = {"information": sc.METHODS[n], "exact E[MSE] (m²)": exact[n],
                              "Monte Carlo (m²)": float(mc.per_run[n].mean()),
                              "minus reference (m²)": d, "95 % CI low": lo, "95 % CI high": hi,
                              "vs the source's method": verdict}
    out = pd.DataFrame(rows).T.infer_objects()
    out.index.names = ["class", "method"]
    num = out.select_dtypes("number").columns
    out[num] = out[num].round(4) + 0.0
    return out


def period_change_table(sigma: float) -> pd.DataFrame:
    """Exact E[MSE] (m²) of the §3 and §4 methods under each driving-noise reading and initialisation.

    Rows: the Q reading and whether the filter also steps to each registration instant (the
    source's change of the filter period); columns: method and initialisation.

    Parameters
    ----------
    sigma : float
        Noise level (m), also assumed by the filter.

    Returns
    -------
    DataFrame
        Rounded to 4 decimals.
    """
    from fusion.registration import INITS, Q_MODELS
    rows = {}
    for qm in Q_MODELS:
        for pc in (False, True):
            rows[(qm, "yes" if pc else "no")] = {
                (m, init): sc.expected(m, sigma, kf={"q_model": qm, "period_change": pc, "init": init})
                for m in ("Kalman, predict (§3)", IMPROVED) for init in INITS}
    out = pd.DataFrame(rows).T
    out.index.names = ["Q reading", "period changed at instants"]
    out.columns = pd.MultiIndex.from_tuples(
        [(m, "z₁ used twice (source)" if i == "source" else "z₁ used once") for m, i in out.columns])
    return out.round(4)


def fusion_table(fr: sc.FusionRuns) -> pd.DataFrame:
    """Mean fused MSE per configuration, with the paired 95 % interval against sensor 2 alone.

    Parameters
    ----------
    fr : FusionRuns

    Returns
    -------
    DataFrame
        Rounded to 4 decimals.
    """
    ref = fr.per_run["sensor 2 alone"]
    rows = {}
    for k, v in fr.per_run.items():
        d, lo, hi = _paired(v, ref) if k != "sensor 2 alone" else (0.0, 0.0, 0.0)
        rows[k] = {"mean MSE (m²)": float(v.mean()), "minus sensor 2 alone": d, "95 % CI low": lo, "95 % CI high": hi}
    return pd.DataFrame(rows).T.round(4) + 0.0


def fig4_compatibility(sigmas: Sequence[float], runs: int, seed: int, axis_max: float, block: int = 20) -> pd.DataFrame:
    """Which noise levels could produce a Fig. 4 like the published one (every run inside the axis).

    For each σ, ``runs`` simulated runs of the two Fig. 4 methods give the per-run probability
    ``p`` that both MSEs lie inside ``[0, axis_max]``, and that in addition the improved method
    wins; runs are independent, so a ``block``-run figure has every run inside with probability
    ``p**block``. The runs use each method's exact affine decomposition ``f0 + A z`` (the Kalman
    filter assumes the true σ), so ``runs`` can be large; the 95 % Clopper-Pearson interval of ``p``
    is raised to the power ``block`` for the interval of ``p**block``.

    Parameters
    ----------
    sigmas : sequence of float
        Noise levels (m).
    runs : int
        Runs per level.
    seed : int
        Seed of the first level (``seed + i`` for the i-th).
    axis_max : float
        Top of Fig. 4's y-axis (m²).
    block : int
        Runs per figure.

    Returns
    -------
    DataFrame
        Index σ; per-run probabilities and the ``block``-run probabilities with 95 % intervals, 3 decimals.
    """
    from scipy import stats

    from fusion.registration import affine_decomposition
    t1, t2 = sc.instants()
    x1, x2 = sc.truth(t1), sc.truth(t2)
    rows = {}
    for i, s in enumerate(sigmas):
        rng = np.random.default_rng(seed + i)
        z = x1 + float(s) * rng.standard_normal((int(runs), t1.size))
        mse = {}
        for n in (IMPROVED, TWO):
            dec = affine_decomposition(sc.registrar(n, t1, t2, float(s)), x1)
            mse[n] = np.round(np.mean((dec.f0 + (z - x1) @ dec.A.T - x2) ** 2, axis=1), 10)
        a, b = mse[IMPROVED], mse[TWO]
        inside = (a <= axis_max) & (b <= axis_max)
        k_in, k_both = int(inside.sum()), int((inside & (a < b)).sum())
        ci = stats.binomtest(k_in, int(runs)).proportion_ci(0.95, method="exact")
        p_in, p_both = k_in / runs, k_both / runs
        rows[float(s)] = {"runs": runs, "P(run inside the axis)": p_in,
                          f"P({block} runs inside)": p_in**block,
                          "95 % CI low": ci.low**block, "95 % CI high": ci.high**block,
                          "P(run inside and improved wins)": p_both,
                          f"P({block} runs inside and ordered)": p_both**block}
    out = pd.DataFrame(rows).T
    out.index.name = "σ (m)"
    out["runs"] = out["runs"].astype(int)
    return out.round(3)


def fig4_reading_table(sigmas: Sequence[float], runs: int, seed: int, axis_max: float,
                       block: int = 20) -> pd.DataFrame:
    """Fig. 4's y-axis under three readings of what it plots, against the noise level.

    Readings: (i) x-axis = Monte-Carlo run, y = that run's MSE (the chapter's primary reading;
    :func:`fig4_compatibility`); (ii) x-axis = run, y = that run's root-mean-square error;
    (iii) x-axis = the registration instant, y = the *expected* squared error at that instant
    (no randomness: the curve fits iff its maximum is inside the axis).

    Parameters
    ----------
    sigmas : sequence of float
        Noise levels (m).
    runs : int
        Runs per level for readings (i)-(ii).
    seed : int
        Seed of the first level.
    axis_max : float
        Top of Fig. 4's y-axis.
    block : int
        Runs per figure.

    Returns
    -------
    DataFrame
        Index σ; the probability that a ``block``-run figure fits under (i) and (ii), and the largest
        expected squared error per instant of each Fig. 4 method under (iii), 3 decimals.
    """
    from fusion.registration import affine_decomposition
    t1, t2 = sc.instants()
    x1, x2 = sc.truth(t1), sc.truth(t2)
    rows = {}
    for i, s in enumerate(sigmas):
        rng = np.random.default_rng(seed + i)
        z = x1 + float(s) * rng.standard_normal((int(runs), t1.size))
        mse, peak = {}, {}
        for n in (IMPROVED, TWO):
            dec = affine_decomposition(sc.registrar(n, t1, t2, float(s)), x1)
            mse[n] = np.round(np.mean((dec.f0 + (z - x1) @ dec.A.T - x2) ** 2, axis=1), 10)
            peak[n] = float(np.max((dec.f0 - x2) ** 2 + float(s) ** 2 * np.sum(dec.A**2, axis=1)))
        a, b = mse[IMPROVED], mse[TWO]
        p_mse = float(np.mean((a <= axis_max) & (b <= axis_max)))
        p_rmse = float(np.mean((np.sqrt(a) <= axis_max) & (np.sqrt(b) <= axis_max)))
        rows[float(s)] = {f"(i) run MSE: P({block} runs inside)": p_mse**block,
                          f"(ii) run RMSE: P({block} runs inside)": p_rmse**block,
                          "(iii) per instant: largest E[sq. error], improved (m²)": peak[IMPROVED],
                          "(iii) per instant: largest E[sq. error], two-point (m²)": peak[TWO]}
    out = pd.DataFrame(rows).T
    out.index.name = "σ (m)"
    return out.round(3)


def robustness_table(st: Mapping[str, object]) -> pd.DataFrame:
    """The headline (improved minus two-point, paired over the same runs) under each reading of :func:`robustness_readings`.

    Parameters
    ----------
    st : mapping
        The chapter's :func:`study` (its ``robust`` runs, ``sigma`` and ``t2``).

    Returns
    -------
    DataFrame
        Index (choice, reading); runs, mean paired difference (m²), its 95 % interval, verdict.
    """
    rows = {}
    for key, c, r, _ in robustness_readings(float(st["sigma"]), st["t2"]):  # type: ignore[arg-type]
        m = st["robust"][key]  # type: ignore[index]
        d, lo, hi = _paired(m.per_run[IMPROVED], m.per_run[TWO])
        rows[(c, r)] = {"runs": m.runs, "improved minus two-point (m²)": d, "95 % CI low": lo, "95 % CI high": hi,
                        "improved is": "better" if hi < 0 else "worse" if lo > 0 else "not distinguishable"}
    out = pd.DataFrame(rows).T.infer_objects()
    out.index.names = ["choice", "reading"]
    num = ["improved minus two-point (m²)", "95 % CI low", "95 % CI high"]
    out[num] = out[num].astype(float).round(4) + 0.0
    return out


def delay_table(delays: Sequence[float], sigmas: Sequence[float]) -> pd.DataFrame:
    """Exact E[MSE] of the improved method minus two-point interpolation under a latency of sensor 1.

    The sample stamped :math:`t_i` is taken at :math:`t_i - \\delta` (``delay``); neither method models it.

    Parameters
    ----------
    delays : sequence of float
        Latencies δ (s); negative: the sample is taken after its stamp.
    sigmas : sequence of float
        Noise levels (m), also assumed by the filter.

    Returns
    -------
    DataFrame
        Index δ (ms); one column per σ, improved minus two-point (m², 4 decimals; negative: improved better).
    """
    rows = {round(1e3 * float(d), 6): {f"σ_x = {s:g} m": sc.expected(IMPROVED, float(s), delay=float(d))
                             - sc.expected(TWO, float(s), delay=float(d)) for s in sigmas} for d in delays}
    out = pd.DataFrame(rows).T
    out.index.name = "latency δ (ms)"
    return integral_index(out.round(4) + 0.0)


def delay_break_even(sigma: float, upper: float = 0.05) -> float:
    """Smallest positive latency (s) of sensor 1 at which two-point interpolation matches the improved method.

    Parameters
    ----------
    sigma : float
        Noise level (m), also assumed by the filter.
    upper : float
        Upper end of the search (s); the difference must change sign on ``(0, upper]``.

    Returns
    -------
    float
        The latency, rounded to 0.1 ms.

    Raises
    ------
    ValueError
        No sign change on ``(0, upper]``.
    """
    from scipy.optimize import brentq

    def diff(d: float) -> float:
        return sc.expected(IMPROVED, sigma, delay=d) - sc.expected(TWO, sigma, delay=d)

    if diff(0.0) * diff(upper) > 0:
        raise ValueError(f"upper: no change of order on (0, {upper}] s at sigma = {sigma}")
    return round(float(brentq(diff, 0.0, upper, xtol=1e-6)), 4)


def robustness_readings(sigma: float, t2: ArrayLike) -> list[tuple[str, str, str, dict[str, object]]]:
    """The open choices and stress tests of the §3-4 comparison, each as (key, choice, reading, keyword
    arguments of :func:`fusion.scenarios.time_registration.monte_carlo`); the key is the reading's key in
    ``book/claims/shi2023time.yaml`` (record ``shi-improved``), the labels are the table's.

    Parameters
    ----------
    sigma : float
        Measurement noise SD (m) of the study (the "filter assumes 2σ" reading doubles it).
    t2 : array_like
        Registration instants (s) of the primary scenario (the start-up reading scores from the third).

    Returns
    -------
    list of tuple
        Sixteen readings: initial covariance, Kalman tuning, driving noise and filter period,
        initialisation, the filter's noise level, start-up, period ratio; latency and manoeuvre (stress).

    References
    ----------
    * Blair, W. D., Rice, T. R., Alouani, A. T., & Xia, P. (1991). Asynchronous data fusion for target tracking
      with a multi-task radar and optical sensor. Proc. SPIE 1482.
    """
    SIGMA = float(sigma)
    T2 = np.asarray(t2, dtype=float)
    T2_6 = sc.instants(6.0)[1]                   # integer ratio 3: instants coincide with sensor-1 samples
    return [
        ("p0-small", "initial covariance", "P0 = diag(σ², 1, 1)", dict(kf={"p0": (1.0, 1.0)})),
        ("p0-large", "initial covariance", "P0 = diag(σ², 10^4, 10^4)", dict(kf={"p0": (1e4, 1e4)})),
        ("q-small", "Kalman tuning", "q_v = 10^-4, q_a = 10^-5 per step", dict(q_v=1e-4, q_a=1e-5)),
        ("q-large", "Kalman tuning", "q_v = 1, q_a = 0.1 per step", dict(q_v=1.0, q_a=0.1)),
        ("per-step-period-changed", "filter period (out of scope)", "per-step Q, period changed at the instants",
         dict(kf={"period_change": True})),
        ("wnj-period-changed", "filter period (out of scope)", "white-noise-jerk Q(T), period changed",
         dict(kf={"q_model": "white-noise jerk", "period_change": True})),
        ("z1-once", "initialisation", "first measurement used once", dict(kf={"init": "once"})),
        ("filter-2sigma", "filter's noise level", "filter assumes 2σ", dict(sigma_filter=2 * SIGMA)),
        ("start-up", "instants scored", "from the third instant (13 s) on", dict(t_dst=T2[2:])),
        ("integer-ratio", "period ratio (out of scope)", "sensor 2 every 6 s", dict(t_dst=T2_6, window=6.0)),
        ("latency-10ms", "latency (stress)", "samples taken 10 ms before their stamps", dict(delay=0.01)),
        ("latency-20ms", "latency (stress)", "samples taken 20 ms before their stamps", dict(delay=0.02)),
        ("latency-minus-10ms", "latency (stress)", "samples taken 10 ms after their stamps", dict(delay=-0.01)),
        ("manoeuvre-stop", "manoeuvre (stress)", "acceleration 2 → 0 m/s² at 20 s", dict(a_after=0.0)),
        ("manoeuvre-reverse", "manoeuvre (stress)", "acceleration 2 → −2 m/s² at 20 s", dict(a_after=-2.0)),
        ("manoeuvre-stop-tuned", "manoeuvre (stress)", "2 → 0 m/s² at 20 s, q_v = 1, q_a = 0.1",
         dict(a_after=0.0, q_v=1.0, q_a=0.1))]


#: Readings of the §3 Kalman filter alone, compared with two-point extrapolation: (key, choice, reading, ``kf``).
S3_READINGS: tuple[tuple[str, str, str, dict[str, object]], ...] = (
    ("per-step-period-changed", "driving noise and filter period", "per-step Q, period changed at the instants",
     {"period_change": True}),
    ("wnj-period-changed", "driving noise and filter period", "white-noise-jerk Q(T), period changed at the instants",
     {"q_model": "white-noise jerk", "period_change": True}),
    ("z1-once", "initialisation", "first measurement used once", {"init": "once"}),
)


def exact_numbers(exact: Mapping[str, float], sigma: float, t2: ArrayLike) -> dict[str, float]:
    """The exact expected MSEs and noise gains chapter 07's prose quotes (glue keys ``reg_exact_*``, ``reg_gain_*``).

    Parameters
    ----------
    exact : mapping
        Method -> exact expected MSE (m²), from :func:`fusion.scenarios.time_registration.expected`.
    sigma : float
        Measurement noise SD (m).
    t2 : array_like
        Registration instants (s); the extrapolation gains use the instants from the second on.

    Returns
    -------
    dict
        Glue key -> value (m², or the dimensionless gain g of E[MSE] = b + g σ²).

    References
    ----------
    * Shi, Suo & Ma (2023), the chapter's source (see the bibliography).
    """
    SIGMA = float(sigma)
    T2 = np.asarray(t2, dtype=float)
    return {"reg_exact_two": exact[TWO], "reg_exact_impr": exact[IMPROVED],
"reg_exact_ls": exact["least squares"],
            "reg_exact_kf": exact["Kalman, predict (§3)"], "reg_exact_causal": exact[CAUSAL_IMPROVED],
            "reg_exact_extrap": exact["two-point extrapolation"],
            "reg_exact_qls": exact["quadratic least squares (past + next sample)"],
            "reg_exact_qls_causal": exact["quadratic least squares (causal)"],
            "reg_gain_three": sc.noise_gain("three-point"), "reg_gain_two": sc.noise_gain(TWO),
            "reg_gain_three_ext": sc.mse_coefficients("three-point extrapolation", SIGMA, t_dst=T2[1:])[1],
            "reg_gain_two_ext": sc.mse_coefficients("two-point extrapolation", SIGMA, t_dst=T2[1:])[1]}


def benchmark_numbers(bench: pd.DataFrame) -> dict[str, float]:
    """The numbers chapter 07's prose quotes from the benchmark table (glue keys ``reg_b_*``).

    Parameters
    ----------
    bench : pandas.DataFrame
        :func:`benchmark_table` (index: information class, method).

    Returns
    -------
    dict
        Glue key -> exact E[MSE] (m²) of the offline methods and the 95 % interval of the quadratic
        least squares and of the causal improved method (m²).

    References
    ----------
    * Shi, Suo & Ma (2023), the chapter's source (see the bibliography).
    """
    off = bench.loc["offline (look-ahead or whole record)"]
    rt_ = bench.loc["real time (causal)"]
    return {"reg_b_qls": off.loc["quadratic least squares (past + next sample)", "exact E[MSE] (m²)"],
            "reg_b_rts": off.loc["RTS smoother (whole record)", "exact E[MSE] (m²)"],
            "reg_b_spline": off.loc["cubic spline (whole record)", "exact E[MSE] (m²)"],
            "reg_b_qls_lo": off.loc["quadratic least squares (past + next sample)", "95 % CI low"],
            "reg_b_qls_hi": off.loc["quadratic least squares (past + next sample)", "95 % CI high"],
            "reg_b_causal_lo": rt_.loc[CAUSAL_IMPROVED, "95 % CI low"],
            "reg_b_causal_hi": rt_.loc[CAUSAL_IMPROVED, "95 % CI high"]}


# ---------------------------------------------------------------- the ledger's evidence (book/claims/shi2023time.yaml)
#
# Each ``_ev_*`` function computes one record's evidence from the chapter's study (:func:`study`), one
# Evidence per reading key of the claim file; every text of the record (claim, readings, assumptions,
# bound, reason) is in the claim file. The public ``ev_*`` named by the claim file take
# ``(settings, *, seed, runs)`` (:func:`fusion.book.claims.evaluate`): the reading is ``settings["reading"]``
# and the study is computed once per (seed, runs) (:func:`cached_study`).

S3 = "Kalman, predict (§3)"
EXTRAP = "two-point extrapolation"
FIXED_LAG = "fixed-lag smoother (next sample)"
QLS = "quadratic least squares (past + next sample)"
LOCAL_QLS = "local quadratic least squares (last 4 + next sample)"
MSE = "registration MSE (m²)"

#: The unmodelled changes every compared method is run under (rule R6): key -> monte_carlo keywords.
STRESS: dict[str, dict[str, object]] = {
    "manoeuvre-stop": {"a_after": 0.0},
    "manoeuvre-reverse": {"a_after": -2.0},
    "latency-10ms": {"delay": 0.01},
    "latency-minus-10ms": {"delay": -0.01},
}

#: Noise levels of the readings (m), besides the primary σ.
SIGMAS_ALT: tuple[float, ...] = (0.1, 0.3, 3.0, 10.0)

#: Methods run in every noise-level and stress study.
STUDY_METHODS: tuple[str, ...] = (TWO, IMPROVED, "three-point", "least squares", EXTRAP, S3, CAUSAL_IMPROVED,
                                  "three-point extrapolation", "Kalman + two-point", FIXED_LAG, QLS, LOCAL_QLS,
                                  "quadratic least squares (causal)", "RTS smoother (whole record)",
                                  "cubic spline (whole record)")


def _key(s: float) -> str:
    """Reading key of a noise level: ``sigma-0-1`` for 0.1 m."""
    return "sigma-" + f"{s:g}".replace(".", "-")


def _c(m: sc.MonteCarlo, a: str, b: str, claim: str = "less", metric: str = MSE, cond: str = "") -> Comparison:
    return Comparison(m.per_run[a], m.per_run[b], a, b, claim, metric, seed=m.seed,  # type: ignore[arg-type]
                      conditions=(cond, cond))


def study(t1: ArrayLike, t2: ArrayLike, sigma: float, runs: int, seed: int) -> dict[str, object]:
    """Every Monte-Carlo study the ledger needs, each reading at the primary's ``runs`` (rule R4).

    Parameters
    ----------
    t1, t2 : array_like
        Sensor-1 sample times and sensor-2 instants (s).
    sigma : float
        Primary noise level (m).
    runs : int
        Runs of the primary and of every reading.
    seed : int
        Seed of the primary runs (``seed``); the readings use ``seed + 100 + i``.

    Returns
    -------
    dict
        ``mc`` (every method of ``STUDY_METHODS``, the primary runs), ``sweep`` (σ -> runs),
        ``stress`` (key of :data:`STRESS` -> runs of every method), ``robust`` (key of :func:`robustness_readings`
        -> runs of the Fig. 4 methods), ``s3`` (key of :data:`S3_READINGS` -> runs of the §3 method and
        two-point extrapolation), ``s3_fair`` (σ -> §3 and three-point extrapolation from the second instant),
        ``s3_period`` (the §3 method with the period changed, on the primary runs), ``realtime`` (causal
        improved and two-point extrapolation from the second instant), ``stress_tuned`` (the stop of the
        acceleration with q_v = 1, q_a = 0.1), ``cv_integer`` (a constant-velocity target, sensor 2 every 6 s:
        where Blair's least squares is designed for), ``t1``, ``t2``, ``sigma``.
    """
    t1, t2 = np.asarray(t1, dtype=float), np.asarray(t2, dtype=float)
    names = list(STUDY_METHODS)
    out: dict[str, object] = {"t1": t1, "t2": t2, "sigma": float(sigma),
                              "mc": sc.monte_carlo(names, sigma, runs, seed)}
    out["sweep"] = {s: sc.monte_carlo(names, s, runs, seed + 100 + i) for i, s in enumerate(SIGMAS_ALT)}
    out["stress"] = {k: sc.monte_carlo(names, sigma, runs, seed + 110 + i, **kw)  # type: ignore[arg-type]
                     for i, (k, kw) in enumerate(STRESS.items())}
    fig4 = list(FIG4) + ["least squares"]
    out["robust"] = {k: sc.monte_carlo(fig4, sigma, runs, seed + 120 + i, **kw)  # type: ignore[arg-type]
                     for i, (k, _, _, kw) in enumerate(robustness_readings(sigma, t2))}
    out["s3"] = {k: sc.monte_carlo([S3, EXTRAP], sigma, runs, seed + 140 + i, kf=kw)
                 for i, (k, _, _, kw) in enumerate(S3_READINGS)}
    out["s3_fair"] = {s: sc.monte_carlo([S3, "three-point extrapolation"], s, runs, seed + 150 + i, t_dst=t2[1:])
                      for i, s in enumerate((0.1, float(sigma)))}
    out["s3_period"] = sc.monte_carlo([S3], sigma, runs, seed, kf={"period_change": True})
    out["realtime"] = sc.monte_carlo([CAUSAL_IMPROVED, EXTRAP], sigma, runs, seed + 160, t_dst=t2[1:])
    out["stress_tuned"] = sc.monte_carlo([IMPROVED, TWO, S3, EXTRAP, FIXED_LAG], sigma, runs, seed + 170,
                                         a_after=0.0, q_v=1.0, q_a=0.1)
    out["cv_integer"] = sc.monte_carlo([TWO, EXTRAP, "least squares"], sigma, runs, seed + 180,
                                       t_dst=sc.instants(6.0)[1], window=6.0, a_after=0.0, t_change=0.0)
    return out


def _noise_levels(st: Mapping[str, object], a: str, b: str, claim: str = "less") -> dict[str, Evidence]:
    return {_key(s): _c(m, a, b, claim) for s, m in st["sweep"].items()}  # type: ignore[attr-defined]


def _stress(st: Mapping[str, object], a: str, b: str, keys: Sequence[str] = ("manoeuvre-stop", "manoeuvre-reverse"),
            claim: str = "less") -> dict[str, Evidence]:
    return {k: _c(st["stress"][k], a, b, claim, cond=k) for k in keys}  # type: ignore[index]


def _ev_samples(st: Mapping[str, object]) -> Evidence:
    """``shi-samples``: how many samples a 5 s sensor can give in 40 s."""
    t1, t2 = st["t1"], st["t2"]
    dur, p2 = float(sc.SCENARIO["duration"]), float(sc.SCENARIO["period_2"])
    n2_max = int(np.floor(dur / p2)) + 1
    return Proposition(bool(n2_max >= data.SHI2023_CLAIMED_SAMPLES.values[1]),
                       f"at most {n2_max} samples from a {p2:g} s sensor in {dur:g} s whatever its start time "
                       f"({np.size(t2)} from 3 s); sensor 1 gives {np.size(t1)}")


def _ev_figs23(st: Mapping[str, object]) -> Evidence:
    """``shi-figs23``: do the registered positions fit under the 'after' axes?"""
    ax = data.SHI2023_AXES.columns
    after = min(float(ax["fig2_after_y"][0]), float(ax["fig3_after_y"][0]))
    x2max = float(sc.truth(st["t2"]).max())
    return Proposition(bool(x2max <= after), f"registered positions reach {x2max:.0f} m; the 'after' axes stop at "
                                             f"{ax['fig2_after_y'][0]:g} and {ax['fig3_after_y'][0]:g} m")


def _ev_eqs(st: Mapping[str, object]) -> Evidence:
    """``shi-eqs``: the equations are not in the text (the reason is in the claim file)."""
    return Unverifiable("see the record's reason")


def _ev_metric(st: Mapping[str, object]) -> dict[str, Evidence]:
    """``shi-metric``: the mean-square error (Fig. 4's axis) and, literally, the covariance of the two series."""
    t1, t2 = st["t1"], st["t2"]
    ls, x2 = sc.register("least squares", t1, sc.truth(t1), t2, 1.0), sc.truth(t2)
    cov, cov_shift = float(np.cov(ls, x2)[0, 1]), float(np.cov(ls + 100.0, x2)[0, 1])
    mse, mse_shift = float(np.mean((ls - x2) ** 2)), float(np.mean((ls + 100.0 - x2) ** 2))
    return {"primary": Proposition(bool(mse_shift > mse), f"a 100 m offset raises the MSE from {mse:.2f} to "
                                                          f"{mse_shift:.0f} m²: it measures accuracy"),
            "literal-covariance": Proposition(bool(not np.isclose(cov, cov_shift)),
                                              f"a 100 m offset leaves the covariance unchanged ({cov:.0f} m²)")}


def _ev_interp_vs_ls(st: Mapping[str, object]) -> dict[str, Evidence]:
    """``shi-interp-vs-ls``: two-point interpolation against least squares."""
    mc = st["mc"]
    t1, t2 = st["t1"], st["t2"]
    nf = {n: sc.noise_free_mse(n, t1, t2) for n in (TWO, EXTRAP, "least squares")}
    return {"primary": _c(mc, TWO, "least squares"),
            "causal-both": _c(mc, EXTRAP, "least squares"),
            "noise-free": Conjunction((("interpolation", Proposition(bool(nf[TWO] < nf["least squares"]),
                                                                     f"noise-free MSE {nf[TWO]:.4f} vs "
                                                                     f"{nf['least squares']:.4f} m²")),
                                       ("extrapolation", Proposition(bool(nf[EXTRAP] < nf["least squares"]),
                                                                     f"noise-free MSE {nf[EXTRAP]:.4f} vs "
                                                                     f"{nf['least squares']:.4f} m²")))),
            **_noise_levels(st, TWO, "least squares"),
            "quadratic-global": _c(mc, TWO, QLS),
            "quadratic-local": _c(mc, TWO, LOCAL_QLS),
            "quadratic-causal": _c(mc, EXTRAP, "quadratic least squares (causal)"),
            "integer-ratio": _c(st["robust"]["integer-ratio"], TWO, "least squares"),  # type: ignore[index]
            "cv-integer-ratio": _c(st["cv_integer"], TWO, "least squares"),
            **{f"{k}-global": _c(st["stress"][k], TWO, QLS, cond=k)  # type: ignore[index]
               for k in ("manoeuvre-stop", "manoeuvre-reverse")},
            **{f"{k}-local": _c(st["stress"][k], TWO, LOCAL_QLS, cond=k)  # type: ignore[index]
               for k in ("manoeuvre-stop", "manoeuvre-reverse")}}


def _ev_curve_fitting(st: Mapping[str, object]) -> dict[str, Evidence]:
    """``shi-curve-fitting``: a quadratic fitted by least squares against the straight line (and locally, look-ahead)."""
    mc, qc = st["mc"], "quadratic least squares (causal)"
    return {"primary": _c(mc, qc, "least squares"), "local-look-ahead": _c(mc, LOCAL_QLS, TWO),
            "manoeuvre-stop": _c(st["stress"]["manoeuvre-stop"], qc, "least squares", cond="manoeuvre-stop"),  # type: ignore[index]
            "manoeuvre-stop-local": _c(st["stress"]["manoeuvre-stop"], LOCAL_QLS, TWO,  # type: ignore[index]
                                       cond="manoeuvre-stop")}


def _ev_kalman_s3(st: Mapping[str, object]) -> dict[str, Evidence]:
    """``shi-kalman-s3``: the §3 Kalman prediction against the raw samples (both causal)."""
    out: dict[str, Evidence] = {"primary": _c(st["mc"], S3, EXTRAP), **_noise_levels(st, S3, EXTRAP)}
    for s, m in st["s3_fair"].items():  # type: ignore[attr-defined]
        out["three-point-baseline-" + _key(s)] = _c(m, S3, "three-point extrapolation")
    for k, m in st["s3"].items():  # type: ignore[attr-defined]
        out[k] = _c(m, S3, EXTRAP)
    out.update(_stress(st, S3, EXTRAP))
    out["manoeuvre-stop-tuned"] = _c(st["stress_tuned"], S3, EXTRAP, cond="manoeuvre-stop-tuned")
    return out


def _ev_three_noise(st: Mapping[str, object]) -> dict[str, Evidence]:
    """``shi-three-noise``: is three-point interpolation strongly affected by noise?"""
    mc, t1, t2 = st["mc"], st["t1"], st["t2"]
    nf = {n: sc.noise_free_mse(n, t1, t2) for n in ("three-point", TWO)}
    g = {n: sc.noise_gain(n) for n in ("three-point", TWO)}
    s = float(st["sigma"])
    g_mc = float(np.mean(mc.per_run["three-point"] - nf["three-point"])) / s**2
    se = float(np.std(mc.per_run["three-point"], ddof=1)) / np.sqrt(mc.runs) / s**2
    gx = {n: sc.mse_coefficients(n, s, t_dst=t2[1:])[1] for n in ("three-point extrapolation", EXTRAP)}
    return {"primary": _c(mc, "three-point", TWO, "greater"),
            **_noise_levels(st, "three-point", TWO, "greater"),
            "any-excess": Comparison(mc.per_run["three-point"] - nf["three-point"], mc.per_run[TWO] - nf[TWO],
                                     "three-point", TWO, "greater", "noise-added MSE (m²)", seed=mc.seed),
            "gain-above-one": Conjunction((
                ("exact", Proposition(bool(g["three-point"] > 1.0), f"noise gain g = {g['three-point']:.4f}")),
                ("Monte Carlo", Proposition(bool(g_mc - 1.96 * se > 1.0),
                                            f"g ≈ {g_mc:.3f} ± {1.96 * se:.3f} from {mc.runs} runs")))),
            "extrapolation": Conjunction((
                ("three-point", Proposition(bool(gx["three-point extrapolation"] > 1.0),
                                            f"g = {gx['three-point extrapolation']:.4f}")),
                ("against two-point", Proposition(bool(gx["three-point extrapolation"] > gx[EXTRAP]),
                                                  f"g = {gx['three-point extrapolation']:.4f} vs {gx[EXTRAP]:.4f}"))))}


def _ev_improved(st: Mapping[str, object]) -> dict[str, Evidence]:
    """``shi-improved`` (headline): the improved method against two-point interpolation."""
    out: dict[str, Evidence] = {"primary": _c(st["mc"], IMPROVED, TWO), **_noise_levels(st, IMPROVED, TWO),
                                "real-time": _c(st["realtime"], CAUSAL_IMPROVED, EXTRAP)}
    stress = {k for k, *_ in robustness_readings(float(st["sigma"]), st["t2"]) if k.startswith(("latency", "manoeuvre"))}
    for k, m in st["robust"].items():  # type: ignore[attr-defined]
        out[k] = _c(m, IMPROVED, TWO, cond=k if k in stress else "")
    return out


def _ev_improved_fair(st: Mapping[str, object]) -> dict[str, Evidence]:
    """``shi-improved-fair`` (the book's question): the improved method against the same information's best use."""
    mc = st["mc"]
    return {"primary": _c(mc, IMPROVED, FIXED_LAG),
            "quadratic-global": _c(mc, IMPROVED, QLS),
            "quadratic-local": _c(mc, IMPROVED, LOCAL_QLS),
            "rts": _c(mc, IMPROVED, "RTS smoother (whole record)"),
            "spline": _c(mc, IMPROVED, "cubic spline (whole record)"),
            "real-time-s3": _c(mc, CAUSAL_IMPROVED, S3),
            "real-time-quadratic": _c(mc, CAUSAL_IMPROVED, "quadratic least squares (causal)"),
            **_stress(st, IMPROVED, FIXED_LAG),
            **{f"{k}-global": _c(st["stress"][k], IMPROVED, QLS, cond=k)  # type: ignore[index]
               for k in ("manoeuvre-stop", "manoeuvre-reverse")},
            "manoeuvre-stop-tuned": _c(st["stress_tuned"], IMPROVED, FIXED_LAG, cond="manoeuvre-stop-tuned")}


def cost_count(t1: ArrayLike, t2: ArrayLike) -> dict[str, int]:
    """What each Kalman route computes over the record: filter steps and distinct filter periods.

    The §3 method changes the filter period at every registration instant (it steps to the instant, then on to
    the next sample); the improved method of §4 filters at the sampling period only and evaluates a three-point
    formula per instant. A step with a new period needs a new transition matrix and driving noise.

    Parameters
    ----------
    t1, t2 : array_like
        Sample times and registration instants (s).

    Returns
    -------
    dict
        ``s3_steps``, ``improved_steps`` (filter steps), ``s3_periods``, ``improved_periods`` (distinct step
        lengths, to 1e-9 s), ``three_point_evals`` (formula evaluations of the improved method).
    """
    t1, t2 = np.asarray(t1, dtype=float), np.asarray(t2, dtype=float)
    grid = np.union1d(t1, t2[(t2 > t1[0]) & (t2 < t1[-1])])
    return {"s3_steps": int(grid.size - 1), "improved_steps": int(t1.size - 1),
            "s3_periods": int(np.unique(np.round(np.diff(grid), 9)).size),
            "improved_periods": int(np.unique(np.round(np.diff(t1), 9)).size),
            "three_point_evals": int(t2.size)}


def _ev_simplifies(st: Mapping[str, object]) -> dict[str, Evidence]:
    """``shi-simplifies``: fewer filter steps and one period, and the §3 method's accuracy kept."""
    mc, cc = st["mc"], cost_count(st["t1"], st["t2"])
    simpler = Proposition(bool(cc["improved_steps"] < cc["s3_steps"] and cc["improved_periods"] < cc["s3_periods"]),
                          f"{cc['improved_steps']} filter steps at {cc['improved_periods']} period against "
                          f"{cc['s3_steps']} steps at {cc['s3_periods']} periods, plus {cc['three_point_evals']} "
                          "three-point evaluations")
    return {"primary": Conjunction((("simpler", simpler), ("keeps the accuracy", _c(mc, IMPROVED, S3)))),
            "s3-period-changed": Conjunction((("simpler", simpler), ("keeps the accuracy", Comparison(
                mc.per_run[IMPROVED], st["s3_period"].per_run[S3], IMPROVED, S3 + ", period changed", "less", MSE,
                seed=mc.seed)))),
            "real-time": Conjunction((("simpler", simpler), ("keeps the accuracy", _c(mc, CAUSAL_IMPROVED, S3))))}


def _ev_ls_info(st: Mapping[str, object]) -> dict[str, Evidence]:
    """``shi-ls-info``: least squares against two-point extrapolation (same causal information)."""
    mc, t1, t2 = st["mc"], st["t1"], st["t2"]
    nf = {n: sc.noise_free_mse(n, t1, t2) for n in ("least squares", EXTRAP)}
    return {"primary": _c(mc, "least squares", EXTRAP), **_noise_levels(st, "least squares", EXTRAP),
            "cv-integer-ratio": _c(st["cv_integer"], "least squares", EXTRAP),
            "precision-only": Comparison(mc.per_run["least squares"] - nf["least squares"],
                                         mc.per_run[EXTRAP] - nf[EXTRAP], "least squares", EXTRAP, "less",
                                         "noise-added MSE (m²)", seed=mc.seed)}


def _ev_validated(st: Mapping[str, object]) -> dict[str, Evidence]:
    """``shi-validated``: noise-free errors of both classic methods against the distance and against σ."""
    t1, t2, s = st["t1"], st["t2"], float(st["sigma"])
    x2 = sc.truth(t2)
    err = {n: float(np.abs(sc.register(n, t1, sc.truth(t1), t2, s) - x2).max()) for n in (TWO, "least squares")}
    worst = max(err.values())
    return {"primary": Proposition(bool(worst < 0.01 * float(x2.max())),
                                   f"largest noise-free errors {err[TWO]:.2f} m and {err['least squares']:.2f} m, "
                                   f"against {float(x2.max()):.0f} m covered"),
            "below-noise": Proposition(bool(worst < s), f"largest noise-free errors {err[TWO]:.2f} m and "
                                                        f"{err['least squares']:.2f} m against σ_x = {s:g} m")}


def _ev_fig4_axis(st: Mapping[str, object]) -> dict[str, Evidence]:
    """``shi-fig4-axis``: cannot be checked without the noise level (the reasons are in the claim file)."""
    why = "the noise level is not given (the reading states what the chapter computed at 1 m)"
    return {"primary": Unverifiable("see the record's reason"), "rmse": Unverifiable(why),
            "per-instant": Unverifiable(why)}


def _ev_fusion(st: Mapping[str, object]) -> dict[str, Evidence]:
    """``shi-fusion``: fusing sensor 1 registered by the improved method with sensor 2."""
    fr = st["fusion"]
    fu, m = fr.per_run, "fused MSE at sensor-2 instants (m²)"  # type: ignore[attr-defined]
    impr, two, alone = f"fused, {IMPROVED}", f"fused, {TWO}", "sensor 2 alone"

    def cmp(a: str, b: str) -> Comparison:
        return Comparison(fu[a], fu[b], a, b, "less", m, seed=fr.seed)  # type: ignore[attr-defined]

    return {"primary": cmp(impr, alone), "two-point": cmp(two, alone), "improved-vs-two-point": cmp(impr, two),
            "unregistered": cmp(impr, "fused, unregistered (last sample)")}


#: Noise level of the primary readings (m): the source gives none.
PRIMARY_SIGMA = 1.0


@functools.lru_cache(maxsize=2)
def cached_study(seed: int, runs: int) -> dict[str, object]:
    """:func:`study` of the source's scenario at :data:`PRIMARY_SIGMA`, with the fusion runs (seed ``seed + 49``),
    computed once per ``(seed, runs)``: the chapter and every evidence function share it.

    Parameters
    ----------
    seed, runs : int
        As in :func:`study`.

    Returns
    -------
    dict
        :func:`study`'s keys and ``fusion`` (:func:`fusion.scenarios.time_registration.fusion_runs` of the
        improved method, two-point interpolation and the §3 prediction).
    """
    t1, t2 = sc.instants()
    st = study(t1, t2, PRIMARY_SIGMA, runs, seed)
    st["fusion"] = sc.fusion_runs([IMPROVED, TWO, S3], PRIMARY_SIGMA, runs, seed + 49)
    return st


#: Record id -> the function that computes every reading's evidence from the study.
_RECORDS = {"shi-samples": _ev_samples, "shi-figs23": _ev_figs23, "shi-eqs": _ev_eqs, "shi-metric": _ev_metric,
            "shi-interp-vs-ls": _ev_interp_vs_ls, "shi-curve-fitting": _ev_curve_fitting,
            "shi-kalman-s3": _ev_kalman_s3, "shi-three-noise": _ev_three_noise,
            "shi-improved": _ev_improved, "shi-improved-fair": _ev_improved_fair, "shi-simplifies": _ev_simplifies,
            "shi-ls-info": _ev_ls_info, "shi-validated": _ev_validated, "shi-fig4-axis": _ev_fig4_axis,
            "shi-fusion": _ev_fusion}


def ledger_evidence(seed: int, runs: int) -> dict[str, object]:
    """The evidence of every record of chapter 07, by record id (for :func:`fusion.book.claims.build_ledger`).

    Parameters
    ----------
    seed, runs : int
        Of :func:`cached_study`.

    Returns
    -------
    dict
        Record id -> {reading key -> Evidence} (or one Evidence for a record without readings).
    """
    st = cached_study(seed, runs)
    return {rid: fn(st) for rid, fn in _RECORDS.items()}


def _reading(rid: str, settings: Mapping[str, object] | None, seed: int, runs: int) -> Evidence:
    """One reading's evidence (``settings["reading"]``, default the primary) of record ``rid``."""
    ev = _RECORDS[rid](cached_study(seed, runs))
    key = dict(settings or {}).get("reading", "primary")
    if not isinstance(ev, Mapping):
        if key != "primary":
            raise ValueError(f"settings: record {rid} has no reading {key!r}")
        return ev
    if key not in ev:
        raise ValueError(f"settings: record {rid} has no reading {key!r}; it has {sorted(ev)}")
    return ev[key]


def ev_samples(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-samples``: a reading's evidence (settings ``{"reading": key}``) for :func:`fusion.book.claims.evaluate`."""
    return _reading("shi-samples", settings, seed, runs)


def ev_figs23(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-figs23``: a reading's evidence (settings ``{"reading": key}``)."""
    return _reading("shi-figs23", settings, seed, runs)


def ev_eqs(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-eqs``: a reading's evidence (settings ``{"reading": key}``)."""
    return _reading("shi-eqs", settings, seed, runs)


def ev_metric(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-metric``: a reading's evidence (settings ``{"reading": key}``)."""
    return _reading("shi-metric", settings, seed, runs)


def ev_interp_vs_ls(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-interp-vs-ls``: a reading's evidence (settings ``{"reading": key}``)."""
    return _reading("shi-interp-vs-ls", settings, seed, runs)


def ev_curve_fitting(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-curve-fitting``: a reading's evidence (settings ``{"reading": key}``)."""
    return _reading("shi-curve-fitting", settings, seed, runs)


def ev_kalman_s3(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-kalman-s3``: a reading's evidence (settings ``{"reading": key}``)."""
    return _reading("shi-kalman-s3", settings, seed, runs)


def ev_three_noise(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-three-noise``: a reading's evidence (settings ``{"reading": key}``)."""
    return _reading("shi-three-noise", settings, seed, runs)


def ev_improved(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-improved``: a reading's evidence (settings ``{"reading": key}``)."""
    return _reading("shi-improved", settings, seed, runs)


def ev_improved_fair(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-improved-fair``: a reading's evidence (settings ``{"reading": key}``)."""
    return _reading("shi-improved-fair", settings, seed, runs)


def ev_simplifies(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-simplifies``: a reading's evidence (settings ``{"reading": key}``)."""
    return _reading("shi-simplifies", settings, seed, runs)


def ev_ls_info(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-ls-info``: a reading's evidence (settings ``{"reading": key}``)."""
    return _reading("shi-ls-info", settings, seed, runs)


def ev_validated(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-validated``: a reading's evidence (settings ``{"reading": key}``)."""
    return _reading("shi-validated", settings, seed, runs)


def ev_fig4_axis(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-fig4-axis``: a reading's evidence (settings ``{"reading": key}``)."""
    return _reading("shi-fig4-axis", settings, seed, runs)


def ev_fusion(settings: Mapping[str, object], *, seed: int, runs: int) -> Evidence:
    """``shi-fusion``: a reading's evidence (settings ``{"reading": key}``)."""
    return _reading("shi-fusion", settings, seed, runs)


def keep(store: dict[str, object], values: Mapping[str, object]) -> Mapping[str, object]:
    """Add ``values`` to ``store`` and return them: the chapter glues a dict and keeps it for the claim texts.

    Parameters
    ----------
    store : dict
        The chapter's glue values so far (changed in place).
    values : mapping
        Values to glue.

    Returns
    -------
    mapping
        ``values``.
    """
    store.update(values)
    return values


def stress_table(sigma: float, names: Sequence[str] = STUDY_METHODS) -> pd.DataFrame:
    """Exact E[MSE] (m²) of every method on the source's truth and under each unmodelled change (rule R6).

    Every method runs under the same change: the acceleration stops or reverses at 20 s, or sensor 1's
    samples are taken 10 ms before (or after) their stamps; the Kalman methods are also shown with a
    driving noise that allows for manoeuvres (q_v = 1, q_a = 0.1 per step).

    Parameters
    ----------
    sigma : float
        Noise level (m), also assumed by the filters.
    names : sequence of str
        Methods (keys of :data:`fusion.scenarios.time_registration.METHODS`).

    Returns
    -------
    DataFrame
        Index: method; columns: information used, the source's truth, each change of :data:`STRESS`, and the
        two manoeuvres with the manoeuvre tuning (Kalman methods only, else NaN); 2 decimals.
    """
    rows = {}
    for n in names:
        r: dict[str, object] = {"information": sc.METHODS[n], "source's truth": sc.expected(n, sigma)}
        for k, kw in STRESS.items():
            r[k] = sc.expected(n, sigma, **kw)  # type: ignore[arg-type]
        kal = "Kalman" in n or "smoother" in n or n.startswith("improved") or n.startswith("causal")
        for k in ("manoeuvre-stop", "manoeuvre-reverse"):
            r[k + ", q_v = 1, q_a = 0.1"] = (sc.expected(n, sigma, q_v=1.0, q_a=0.1, **STRESS[k])  # type: ignore[arg-type]
                                             if kal else float("nan"))
        rows[n] = r
    out = pd.DataFrame(rows).T.infer_objects()
    out.index.name = "method"
    num = out.select_dtypes("number").columns
    out[num] = out[num].round(2) + 0.0
    return out.sort_values(["information", "source's truth"], kind="stable")


def _true_state(t: np.ndarray, a_after: float | None, t_change: float = 20.0) -> np.ndarray:
    """True [x, v, a] (n, 3) of :func:`fusion.scenarios.time_registration.manoeuvre_truth` at times ``t``."""
    v0, a0 = float(sc.SCENARIO["v0"]), float(sc.SCENARIO["a"])
    after = (t > t_change) if a_after is not None else np.zeros(t.shape, dtype=bool)
    a = np.where(after, 0.0 if a_after is None else a_after, a0)
    v = np.where(after, v0 + a0 * t_change + a * (t - t_change), v0 + a0 * t)
    return np.column_stack([sc.manoeuvre_truth(t, a_after), v, a])


def nees_table(sigma: float, runs: int, seed: int) -> pd.DataFrame:
    r"""Filter consistency: the normalised estimation error squared (NEES) of the chapter's Kalman filter.

    At each sample :math:`\epsilon_i = \mathbf e_i^\top P_i^{-1}\mathbf e_i`, :math:`\mathbf e_i` the filtered
    state's error against the true [x, v, a]; for a consistent filter its mean over runs is 3 (the state's
    dimension) and lies in the two-sided 95 % chi-square interval :math:`[\chi^2_{3R}(0.025), \chi^2_{3R}(0.975)]/R`
    (Bar-Shalom, Li & Kirubarajan 2001, §5.4).

    Parameters
    ----------
    sigma : float
        Noise level (m), also assumed by the filter.
    runs : int
        Runs (R).
    seed : int

    Returns
    -------
    DataFrame
        Index (truth, tuning); columns: mean NEES over runs and samples, largest mean over runs at a sample,
        share of samples whose mean lies inside the 95 % interval (3 decimals).
    """
    from scipy import stats

    from fusion import registration as reg

    t1, _ = sc.instants()
    rng = np.random.default_rng(seed)
    noise = sigma * rng.standard_normal((int(runs), t1.size))
    lo, hi = (stats.chi2.ppf(q, 3 * runs) / runs for q in (0.025, 0.975))
    rows = {}
    for truth_label, a_after in (("source's truth", None), ("acceleration 2 → 0 m/s² at 20 s", 0.0)):
        x = _true_state(t1, a_after)
        for tune_label, (qv, qa) in (("q_v = 10⁻², q_a = 10⁻³", (sc.Q_V, sc.Q_A)), ("q_v = 1, q_a = 0.1", (1.0, 0.1))):
            fs = reg.kalman_runs(t1, x[:, 0] + noise, sigma, qv, qa)
            e = fs.x - x                                          # (runs, n, 3)
            eps = np.einsum("rni,nij,rnj->rn", e, np.linalg.inv(fs.P), e).mean(axis=0)
            rows[(truth_label, tune_label)] = {"mean NEES": float(eps.mean()), "largest at a sample": float(eps.max()),
                                               "share inside 95 % interval": float(np.mean((eps >= lo) & (eps <= hi)))}
    out = pd.DataFrame(rows).T
    out.index.names = ["truth", "tuning"]
    return out.round(3)


def blue_whole_record(sigma: float) -> float:
    r"""Exact E[MSE] (m²) of the best linear unbiased registration with the whole record, on the source's truth.

    The truth is one quadratic over the window, so least squares of a quadratic through every sample is the
    best linear unbiased estimate of :math:`x(t_k)` (Gauss-Markov): a lower bound for every linear unbiased
    method, whatever information it uses (the global quadratic through every past sample and the next one is the
    same bound with the improved method's information).

    Parameters
    ----------
    sigma : float
        Noise level (m), > 0.

    Returns
    -------
    float
    """
    from functools import partial

    from fusion import registration as reg

    t1, t2 = sc.instants()
    fit = partial(reg.quadratic_ls, t1, t_query=t2, lookahead=t1.size)
    return float(reg.expected_mse(fit, sc.truth(t1), sc.truth(t2), sigma))


def cost_values(t1: ArrayLike, t2: ArrayLike, t2_ratio: ArrayLike, sigma: float) -> dict[str, float]:
    """The glue values of the cost and staleness paragraph and the constant-velocity check (chapter bookkeeping).

    Parameters
    ----------
    t1, t2 : array_like
        The sensors' sample instants (s).
    t2_ratio : array_like
        Sensor 2's instants at the integer period ratio (6 s).
    sigma : float
        Measurement noise (m).

    Returns
    -------
    dict
        ``reg_cc_*`` (filter steps and periods of the §3 and §4 routes, :func:`cost_count`), ``reg_stale_min`` /
        ``reg_stale_max`` (m: the last sample taken as simultaneous), ``reg_cv_ls`` / ``reg_cv_extrap`` (exact
        E[MSE] of a constant-velocity target, m²).
    """
    t1, t2 = np.asarray(t1, dtype=float), np.asarray(t2, dtype=float)
    cc = cost_count(t1, t2)
    stale = sc.truth(t2) - sc.truth(t1[np.searchsorted(t1, t2, side="right") - 1])
    cv = {n: sc.expected(n, sigma, t_dst=t2_ratio, window=6.0, a_after=0.0, t_change=0.0)
          for n in (EXTRAP, "least squares")}
    return {"reg_cc_impr_steps": cc["improved_steps"], "reg_cc_s3_steps": cc["s3_steps"],
            "reg_cc_s3_periods": cc["s3_periods"], "reg_stale_min": float(np.abs(stale).min()),
            "reg_stale_max": float(np.abs(stale).max()), "reg_cv_ls": cv["least squares"], "reg_cv_extrap": cv[EXTRAP]}


def manoeuvre_values(manoeuvre: Mapping[float, Mapping[str, float]], sigma: float) -> dict[str, float]:
    """The glue values of the manoeuvre paragraph (chapter bookkeeping).

    Parameters
    ----------
    manoeuvre : mapping
        Acceleration after the change (m/s²) → method → exact E[MSE] (m²), as the chapter computes it.
    sigma : float
        Measurement noise (m).

    Returns
    -------
    dict
        ``reg_man_*``: the improved method, two-point and three-point when the acceleration stops, the improved
        method when it reverses, and the improved method with a manoeuvre-allowing driving noise (q_v = 1, q_a = 0.1).
    """
    return {"reg_man_impr": manoeuvre[0.0][IMPROVED], "reg_man_two": manoeuvre[0.0][TWO],
            "reg_man_three": manoeuvre[0.0]["three-point"], "reg_man_impr_neg": manoeuvre[-2.0][IMPROVED],
            "reg_man_impr_q": sc.expected(IMPROVED, sigma, a_after=0.0, q_v=1.0, q_a=0.1)}


def latency_values(be: Mapping[float, float], sigma: float) -> dict[str, float]:
    """Break-even latencies in milliseconds at ``sigma`` and over the noise levels run (chapter bookkeeping).

    Parameters
    ----------
    be : mapping
        Noise level (m) → break-even latency (s).
    sigma : float
        The chapter's noise level (a key of ``be``).

    Returns
    -------
    dict
        ``reg_be_ms``, ``reg_be_lo_ms``, ``reg_be_hi_ms``.
    """
    return {"reg_be_ms": 1e3 * be[sigma], "reg_be_lo_ms": 1e3 * min(be.values()), "reg_be_hi_ms": 1e3 * max(be.values())}


def gain_values(values: Mapping[str, float], closed: pd.DataFrame) -> dict[str, float]:
    """Three-point's noise-gain excess over two-point (%) and extrapolation's closed-form constants.

    Parameters
    ----------
    values : mapping
        The chapter's glue values so far, holding ``reg_gain_three`` and ``reg_gain_two``.
    closed : DataFrame
        The closed-form table (rows: methods; columns ``b (m²)`` and ``g``).

    Returns
    -------
    dict
        ``reg_gain_excess_pct``, ``reg_cf_extrap_b``, ``reg_cf_extrap_g``.
    """
    return {"reg_gain_excess_pct": 100 * (values["reg_gain_three"] / values["reg_gain_two"] - 1),
            "reg_cf_extrap_b": closed.loc[EXTRAP, "b (m²)"], "reg_cf_extrap_g": closed.loc[EXTRAP, "g"]}
