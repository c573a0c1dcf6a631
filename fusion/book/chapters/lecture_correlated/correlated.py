r"""Section 2.7 of chapter 04, correlated noise: E2.7, the coupling cases, the estimated covariance and the stored
timings of ``benchmarks/bench_correlated.py``.
"""

from __future__ import annotations

from fusion._validation import count, instance_of
from fusion._shown import shown

from collections.abc import Mapping
from typing import Any

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from fusion.book.chapters.lecture import _holds, _lec_glue, _r, legend_below
from fusion.book.style import METHOD_LABELS, color, new_figure
from fusion.book.tables import rounded
from fusion.readings import correlated as co
from fusion.scenarios import correlated_sensors as cs
from fusion.scenarios.correlated_sensors import CouplingStudy, EstimatedCovarianceStudy
from fusion.scenarios.lecture_correlated import MAX_COND as _MAX_COND, _conditioning
from fusion.scenarios.lecture_correlated import CorrelatedStudy
from fusion.book.glue import GlueValues
from fusion._docstrings import ParameterDocs

__all__ = [
    "table_27", "figure_27", "glue_27", "table_coupling", "figure_coupling", "glue_coupling", "table_timings",
    "glue_timings", "table_estimated", "glue_estimated", "gesv_written_ratio",
]

#: The parameters of this module's functions, documented once: the study of E2.7, that of the coupling cases, and
#: the others.
_CORRELATED = ParameterDocs({
    "s": "CorrelatedStudy\n    Result of :func:`fusion.scenarios.lecture_correlated.correlated_study`."})
_COUPLING = ParameterDocs({"s": "CouplingStudy\n    Result of :func:`fusion.scenarios.correlated_sensors.coupling_study`."})
_PARAMS = ParameterDocs({
    "bench": "fusion.book.benchmarks.BenchmarkResult\n    ``load_benchmark(\"correlated\")``.",
    "est": "EstimatedCovarianceStudy\n    Result of :func:`fusion.scenarios.correlated_sensors.estimated_covariance_study`.",
})


@_CORRELATED("s")
def table_27(s: CorrelatedStudy) -> pd.DataFrame:
    """Operation counts of the four GLS routes, with ratios to LDLᵀ (2 decimals).

    Returns
    -------
    pandas.DataFrame
        Index ``Nm``; the four routes' operation counts (integers) and the explicit, Cholesky and eigen counts over the
        LDLᵀ count.
    """
    instance_of(s, CorrelatedStudy, "s")
    tab = pd.DataFrame(s.flops).set_index("Nm")  # columns: the routes' keys of co.operation_counts
    counts = ["explicit", "cholesky", "ldl", "eigen"]
    for key, short in (("explicit", "explicit"), ("cholesky", "Cholesky"), ("eigen", "eigen")):
        tab[f"{short} / LDLᵀ"] = tab[key] / tab["ldl"]
    tab = tab.round(2)
    tab[counts] = tab[counts].round().astype(int)  # operation counts are shown as integers
    return tab.rename(columns={"explicit": "explicit R⁻¹", "cholesky": "Cholesky (cho_solve)",
                               "ldl": "LDLᵀ pseudo-measurements", "eigen": METHOD_LABELS["eigen"]})


@_CORRELATED("s")
def figure_27(s: CorrelatedStudy, shown: int = 2000) -> Figure:
    """F2.7: errors with claimed 2σ ellipses; NEES histograms against χ²₂.

    Parameters
    ----------
    shown : int
        Number of runs drawn in the scatter (>= 1; all of them when the study has fewer).

    Returns
    -------
    matplotlib.figure.Figure
        Left: the GLS and naive errors of the first ``shown`` runs with their claimed 2σ ellipses; right: both NEES
        histograms and the χ²₂ density.

    Raises
    ------
    TypeError
        ``s`` not a CorrelatedStudy or ``shown`` not an integer.
    ValueError
        ``shown`` below 1.
    """
    instance_of(s, CorrelatedStudy, "s")
    shown = count(shown, "shown")  # a negative count would drop runs from the end (fuzz 18, E16)
    fig, axes = new_figure(1, 2, figsize=(7.5, 3.4))
    for e, c in ((s.eg, "gls"), (s.en, "naive")):
        axes[0].scatter(e[0, :shown], e[1, :shown], s=2, alpha=0.3, color=color(c), label=METHOD_LABELS[c])
    t = np.linspace(0, 2 * np.pi, 200)
    for P, c, ls in ((s.Pg, "gls", "-"), (s.Pn, "naive", "--")):
        ell = np.linalg.cholesky(P) @ np.vstack([np.cos(t), np.sin(t)]) * 2
        axes[0].plot(ell[0], ell[1], ls, color=color(c))
    axes[0].set_aspect("equal")
    axes[0].set_xlabel("error in x₁")
    axes[0].set_ylabel("error in x₂")
    axes[0].set_title("errors and claimed 2σ ellipses")
    bins = np.linspace(0, 20, 60)
    for smp, c in zip(s.nees_samples, ("gls", "naive")):
        axes[1].hist(smp, bins, density=True, alpha=0.5, color=color(c), label=METHOD_LABELS[c])
    axes[1].plot(bins, 0.5 * np.exp(-bins / 2), color=color("published"), lw=0.8, label="χ²₂")
    axes[1].set_xlabel("NEES")
    legend_below(fig, ncol=3)
    return fig


@_CORRELATED("s")
@_lec_glue
def glue_27(s: CorrelatedStudy) -> GlueValues:
    """Glue values of E2.7.

    The structured baseline (Sherman-Morrison-Woodbury on R = D + UUᵀ) is checked against GLS on
    ``s.R`` to a relative round-off of ``100 eps cond(R)`` (at least 1e-12, at most 1e-4); a one-sensor study has no
    coupling between sensors to read, and its R is split as D + 0. cond(R) must not exceed ``correlated_study``'s
    limit ``fusion.scenarios.lecture_correlated.MAX_COND`` (1e11).

    Raises
    ------
    TypeError
        ``s`` not a CorrelatedStudy.
    ValueError
        ``s`` without the problem size Nm = 600 among its ``sizes`` (E2.7's ``correlated_study`` has it), or with an R
        conditioned (or split into own and common variances) beyond ``correlated_study``'s limit, named.
    """
    instance_of(s, CorrelatedStudy, "s")
    ft = table_27(s)
    _holds(ft.index, (600,), "s", "problem sizes Nm (correlated_study's sizes)", "glue_27")
    out = _r({"cor_mse_gls": (s.mse_gls, 4), "cor_tr_gls": (np.trace(s.Pg), 4),
              "cor_mse_naive": (s.mse_naive, 4), "cor_tr_naive": (np.trace(s.Pn), 4),
              "cor_nees_gls": (s.nees_gls, 3), "cor_nees_naive": (s.nees_naive, 3),
              "cor_mse_ratio": (s.mse_naive / s.mse_gls, 3), "cor_se_rel": (np.sqrt(2 / s.runs) * 2, 4),
              "cor_flop_ratio_inv_600": (ft.loc[600, "explicit / LDLᵀ"], 2)})
    written, oc = co.ldl_as_written_count(600, 2), co.operation_counts(600, 2)
    spd = co.spd_inverse_count(600, 2)
    # the Cholesky / LDLᵀ ratio from the unrounded counts (the table shows 2 decimals)
    out.update(_r({"cor_flop_ratio_chol_600": (oc["cholesky"] / oc["ldl"], 4),
                   "cor_flop_written_inv_600": (oc["explicit"] / written, 2),
                   "cor_flop_written_chol_600": (written / oc["cholesky"], 2),
                   "cor_flop_spd_600": (spd / oc["ldl"], 2), "cor_flop_spd_written_600": (spd / written, 2)}))
    out["lec_cor_runs"] = int(s.runs)
    # the structured baseline: R = diag + σₑ²(1 1ᵀ ⊗ I₂) by Sherman-Morrison-Woodbury, checked against GLS on E2.7
    R, N = s.R, s.R.shape[0]
    H = np.kron(np.ones((N // 2, 1)), np.eye(2))
    # σₑ²: the coupling of sensors 1 and 2, component 1; one sensor has no coupling to read (fuzz 36b B3): its R is
    # split as D + 0, and the check still compares the two solvers on it
    env2 = float(R[0, 2]) if N >= 4 else 0.0
    D = np.diag(R - env2 * np.kron(np.ones((N // 2, N // 2)), np.eye(2)))
    U = np.sqrt(env2) * np.kron(np.ones((N // 2, 1)), np.eye(2))
    cond = float(np.linalg.cond(R))
    # correlated_study's own test of its R (fuzz 38b C3): what it accepts is glued; one built otherwise is named
    if not _conditioning(R) <= _MAX_COND:
        raise ValueError(f"s must have an R with a condition number, and a common over smallest own variance, of at most "
                         f"{_MAX_COND:g} (correlated_study's limit): beyond it round-off reaches the 4 digits glued")
    z = np.random.default_rng(2705).normal(size=(N, 50))
    a, b = co.gls_low_rank(H, D, U, z).x, co.gls(H, R, z).x
    # both solvers are backward stable: they differ by round-off of order eps·cond(R), which a study whose own SDs
    # are far below σₑ makes large (fuzz 36b B4: σₑ = 300 differs by 7e-12, a fixed 1e-12 refused a valid study)
    # at most 1e-4, finer than the 4 significant digits glued: the check never becomes vacuous at a huge cond(R)
    tol = min(1e-4, max(1e-12, 100 * np.finfo(float).eps * cond))
    if not float(np.max(np.abs(a - b)) / np.max(np.abs(b))) < tol:
        raise RuntimeError("the structured (Sherman-Morrison-Woodbury) GLS does not equal GLS on E2.7")
    out.update(_r({"cor_flop_lowrank_600": (oc["ldl"] / co.low_rank_count(600, 2, 2), 0)}))
    ratio, _, ratio27 = _lagrange_numbers(s)
    out.update(_r({"cor_lag_ratio": (ratio, 3), "cor_lag_ratio27": (ratio27, 4)}))
    return out


def _case_label(key: object) -> str:
    """A case's label: :data:`fusion.book.style.METHOD_LABELS` of a standard
    :class:`~fusion.scenarios.correlated_sensors.CouplingCase` key, the key itself for another case the producers
    accept (fuzz 39b C7: a raw KeyError before; a key that is another method's key, ``"gls"``, is its own label)."""
    return METHOD_LABELS[key] if key in _CASE_KEYS else str(key)


_CASE_KEYS = frozenset(str(c) for c in cs.CouplingCase)


def _case_labels(keys: list[object], name: str) -> list[str]:
    """The labels of a study's cases (:func:`_case_label`), one per case: a caller's case key that reads as another
    case's label (``"unequal coupling"`` beside ``cpl_unequal``) would give two rows, bars or curves one label, so
    it is refused, naming ``name`` and both keys (fuzz 39a E3)."""
    labels = [_case_label(k) for k in keys]
    seen: dict[str, object] = {}
    for k, lab in zip(keys, labels):
        if lab in seen:
            raise ValueError(f"{name} has the cases {shown(str(seen[lab]))} and {shown(str(k))} with one label "
                             f"{shown(lab)}: a case key must not read as another case's label (rename the case)")
        seen[lab] = k
    return labels


@_COUPLING("s")
def table_coupling(s: CouplingStudy) -> pd.DataFrame:
    """One row per correlated case: GLS and naive weights' exact MSE, ratio, Monte Carlo, NEES (4 decimals).

    Rows are labelled by the cases' labels (:data:`fusion.book.style.METHOD_LABELS` of their
    :class:`~fusion.scenarios.correlated_sensors.CouplingCase` keys; another case key as given). The case's parameters (own SDs, couplings, environmental SD) are written as given (text).

    Returns
    -------
    pandas.DataFrame
        Index the cases' labels; columns the own SDs, the couplings, the environmental SD and the study's exact,
        Monte-Carlo and NEES columns.
    """
    instance_of(s, CouplingStudy, "s")
    tab = pd.DataFrame(s.rows).set_index("case")
    tab = tab.drop(columns=[cs.LDL_VS_GLS, cs.EIGEN_VS_GLS])
    tab.insert(1, "own SDs", [", ".join(f"{v:g}" for v in s.scenarios[c]["own"]) for c in tab.index])
    tab.insert(2, "couplings", [", ".join(f"{v:g}" for v in s.scenarios[c]["coupling"]) for c in tab.index])
    tab.index = pd.Index(_case_labels(list(tab.index), "s"), name=tab.index.name)  # the cases' labels
    tab[cs.ENV_SD] = [f"{v:g}" for v in tab[cs.ENV_SD]]  # as the SDs beside it: 1.5, 2, not 2.0
    return tab.round(4)


@_COUPLING("s")
def figure_coupling(s: CouplingStudy) -> Figure:
    """F2.7b: naive/GLS MSE ratio against the environmental SD; GLS and naive weights per case.

    Returns
    -------
    matplotlib.figure.Figure
        Left: the exact naive/GLS MSE ratio against σₑ (log), a dot at each case's own σₑ (labelled as in
        :func:`table_coupling`); right: bars of each sensor's
        GLS and naive weights, per case.
    """
    instance_of(s, CouplingStudy, "s")
    fig, axes = new_figure(1, 2, figsize=(7.5, 3.6))
    names = list(s.curves)
    labels = _case_labels(names, "s")
    for j, nm in enumerate(names):
        c = color(f"sensor {j % 4 + 1}") if j < 4 else color("truth")
        axes[0].semilogy(s.env_grid, s.curves[nm], color=c, ls=("-", "--", "-.", ":", "-")[j % 5],
                         label=labels[j])
        env = s.scenarios[nm]["env"]
        axes[0].plot([env], [s.rows[j][cs.NAIVE_OVER_GLS]], "o", color=c)
    axes[0].set_xlabel("SD of the common environmental noise σₑ")
    axes[0].set_ylabel("MSE naive / MSE GLS (exact)")
    width = 0.38
    pos = 0.0
    ticks, labels = [], []
    for j, nm in enumerate(names):
        K, Kn = s.weights[nm]
        x = pos + np.arange(K.size)
        axes[1].bar(x - width / 2, K, width, color=color("gls"), label=METHOD_LABELS["gls"] if j == 0 else None)
        axes[1].bar(x + width / 2, Kn, width, color=color("naive"), label=METHOD_LABELS["naive"] if j == 0 else None)
        ticks += list(x)
        labels += [f"{j + 1}.{i + 1}" for i in range(K.size)]
        pos += K.size + 1.0
    axes[1].axhline(0.0, color=color("truth"), lw=0.8)
    axes[1].set_xticks(ticks, labels, fontsize=9, rotation=90)
    axes[1].set_xlabel("case.sensor (cases in the order of the left legend)")
    axes[1].set_ylabel("weight")
    legend_below(fig, ncol=2)
    return fig


@_COUPLING("s")
@_lec_glue
def glue_coupling(s: CouplingStudy) -> GlueValues:
    """Glue values of the correlated cases (keys ``lec_cc2_*``).

    A case's keys are numbered by its place in :data:`fusion.scenarios.correlated_sensors.SCENARIOS` (``_1`` the
    equal coupling, ..., ``_5`` the two sensors), whatever the study's order; ``lec_cc2_nees_min``/``_max``,
    ``lec_cc2_ratio_max_curve`` and ``lec_cc2_n`` are taken over every case of the study.

    Raises
    ------
    TypeError
        ``s`` not a CouplingStudy.
    ValueError
        ``s`` without one of the cases of ``SCENARIOS``, named.
    """
    instance_of(s, CouplingStudy, "s")
    cases = list(cs.SCENARIOS)
    _holds(s.scenarios, cases, "s", "coupling cases", "glue_coupling")
    row = {r.get("case"): r for r in s.rows}
    _holds(row, cases, "s", "rows of the coupling cases", "glue_coupling")
    d: dict[str, tuple[float, int]] = {}
    for j, r in enumerate(row[c] for c in cases):
        d[f"cc2_ratio_{j + 1}"] = (r[cs.NAIVE_OVER_GLS], 2)
        d[f"cc2_minw_{j + 1}"] = (r[cs.MIN_GLS_WEIGHT], 3)
        d[f"cc2_nees_{j + 1}"] = (r[cs.NAIVE_NEES], 2)
        d[f"cc2_mse_gls_{j + 1}"] = (r[cs.MC_MSE_GLS], 3)
        d[f"cc2_mse_naive_{j + 1}"] = (r[cs.MC_MSE_NAIVE], 3)
    d["cc2_nees_min"] = (min(r[cs.NAIVE_NEES] for r in s.rows), 2)
    d["cc2_nees_max"] = (max(r[cs.NAIVE_NEES] for r in s.rows), 2)
    d["cc2_ratio_max_curve"] = (max(float(c.max()) for c in s.curves.values()), 1)
    d["cc2_env_max"] = (float(s.env_grid.max()), 1)
    for j, nm in enumerate(cases):
        c = s.curves[nm]
        d[f"cc2_peak_{j + 1}"] = (float(c.max()), 2)
        d[f"cc2_peak_env_{j + 1}"] = (float(s.env_grid[int(np.argmax(c))]), 1)
        d[f"cc2_far_{j + 1}"] = (s.far[nm], 4 if s.far[nm] < 10 else 0)
    d["cc2_env_far"] = (s.env_far, 0)
    out = _r(d)
    out["lec_cc2_runs"] = int(s.runs)
    out["lec_cc2_n"] = len(s.rows)
    return out


@_PARAMS("bench")
def table_timings(bench: Any) -> pd.DataFrame:
    """Measured time ratios beside the operation-count ratios (to LDLᵀ), per problem size (2 decimals).

    Returns
    -------
    pandas.DataFrame
        Rows Nm; columns (route, "measured" / "counted"); the caption is the benchmark's date.
    """
    v = _timings(bench)
    sizes = sorted({int(k.split("_")[1]) for k in v if k.startswith("inv_") and k.split("_")[1].isdigit()})
    missing = [f"{key}_{n}{tail}" for n in sizes for key in ("inv", "chol", "eig") for tail in ("", "_flops")
               if f"{key}_{n}{tail}" not in v]
    if not sizes or missing:
        raise ValueError(f"bench must hold the inv/chol/eig ratios and their _flops per size (bench_correlated.py); "
                         f"missing {missing[:6] if sizes else 'every size'}")
    cols = {}
    for key, name in (("inv", "explicit R⁻¹"), ("chol", "Cholesky GLS"), ("eig", METHOD_LABELS["eigen"])):
        cols[(name, "measured")] = [v[f"{key}_{n}"] for n in sizes]
        cols[(name, "counted")] = [v[f"{key}_{n}_flops"] for n in sizes]
    tab = pd.DataFrame(cols, index=pd.Index(sizes, name="Nm")).round(2)
    tab.columns.names = ["time or flops / LDLᵀ", ""]   # the cell prints the benchmark's date above the table
    return tab


@_PARAMS("bench")
@_lec_glue
def glue_timings(bench: Any) -> GlueValues:
    """Glue values of the measured and counted ratios (keys ``lec_tm_*``, 2 decimals)."""
    return {f"lec_tm_{k}": rounded(val, 2) for k, val in _timings(bench).items()}


def _timings(bench: object) -> Mapping[str, float]:
    """The keyed values of ``bench``, a :class:`~fusion.book.benchmarks.BenchmarkResult` (TypeError naming it
    otherwise): what :func:`table_timings` and :func:`glue_timings` read."""
    from fusion.book.benchmarks import BenchmarkResult

    instance_of(bench, BenchmarkResult, "bench")
    return bench.values  # type: ignore[attr-defined]


@_PARAMS("est")
def table_estimated(est: EstimatedCovarianceStudy) -> pd.DataFrame:
    """GLS with an estimated or misstated R against exact GLS and the naive fusion, per case (3 decimals).

    Returns
    -------
    pandas.DataFrame
        Rows: cases (their labels; a case key without one as given); columns: exact MSE ratios (naive over GLS; GLS with R̂ from n calibration vectors over
        GLS with the true R, mean over the repetitions; naive over GLS with R̂; GLS with one coupling misstated
        over GLS), as text at 3 decimals.
    """
    instance_of(est, EstimatedCovarianceStudy, "est")
    tab = pd.DataFrame(est.rows).set_index("case")
    tab.index = pd.Index(_case_labels(list(tab.index), "est"))  # the cases' labels
    tab.index.name = f"exact MSE ratios ({est.reps} calibrations per n)"
    return tab.map(lambda v: f"{v:.3f}")


@_PARAMS("est")
def glue_estimated(est: EstimatedCovarianceStudy) -> GlueValues:
    """Glue values of the estimated-R study (keys ``lec_ce_*``): ranges over the unequal-coupling cases, reversals.

    Returns
    -------
    GlueValues
        For each n: the smallest and largest loss of GLS with R̂ (ratio to exact GLS) and its gain over the
        naive fusion (with the true variances, and with the calibration's own variances), over the cases whose
        naive/GLS ratio exceeds 2; each case's naive/GLS(R̂) ratios (``ce_rev_<i>_<n>`` with the true variances,
        ``ce_fair_<i>_<n>`` with the calibration's, i the case's position from 1); the number of cases in which
        the naive fusion is the more accurate (``lec_ce_n_rev_<n>``, ``lec_ce_n_fair_<n>``); the equal-coupling
        case's ratios; the largest ratio with a misstated coupling.
    """
    instance_of(est, EstimatedCovarianceStudy, "est")
    rows = est.rows
    big = [r for r in rows if r[cs.NAIVE_OVER_GLS] > 2.0]
    d: dict[str, tuple[float, int]] = {}
    for n in est.ns:
        loss_h, gain_h, fair_h = (t.format(n=n) for t in (cs.GLS_HAT_OVER_GLS, cs.NAIVE_OVER_GLS_HAT,
                                                           cs.NAIVE_HAT_OVER_GLS_HAT))
        loss = [r[loss_h] for r in big]
        gain = [r[gain_h] for r in big]
        fair = [r[fair_h] for r in big]
        d[f"ce_loss_min_{n}"], d[f"ce_loss_max_{n}"] = (min(loss), 3), (max(loss), 3)
        d[f"ce_gain_min_{n}"], d[f"ce_gain_max_{n}"] = (min(gain), 2), (max(gain), 2)
        d[f"ce_fairgain_min_{n}"], d[f"ce_fairgain_max_{n}"] = (min(fair), 2), (max(fair), 2)
        d[f"ce_eq_loss_{n}"] = (rows[0][loss_h], 3)
        d[f"ce_eq_gain_{n}"] = (rows[0][gain_h], 3)
        for i, r in enumerate(rows):
            d[f"ce_rev_{i + 1}_{n}"] = (r[gain_h], 3)
            d[f"ce_fair_{i + 1}_{n}"] = (r[fair_h], 3)
    d["ce_eq_naive"] = (rows[0][cs.NAIVE_OVER_GLS], 3)
    d["ce_mis_max"] = (max(r[cs.MISSTATED_OVER_GLS] for r in rows), 3)
    out = _r(d)
    for n in est.ns:
        out[f"lec_ce_n_rev_{n}"] = len(_reversals(est, n, fair=False))
        out[f"lec_ce_n_fair_{n}"] = len(_reversals(est, n, fair=True))
    out["lec_ce_n_big"] = len(big)
    out["lec_ce_reps"] = int(est.reps)
    out["lec_ce_mis_pct"] = int(round(100 * est.misstate))
    return out


def _reversals(est: EstimatedCovarianceStudy, n: int, fair: bool) -> list[tuple[str, float]]:
    """Cases where the naive fusion beats GLS with R estimated from n calibration vectors (ratio below 1)."""
    col = (cs.NAIVE_HAT_OVER_GLS_HAT if fair else cs.NAIVE_OVER_GLS_HAT).format(n=n)
    return [(r["case"], r[col]) for r in est.rows if r[col] < 1.0]


def _lagrange_numbers(s27: CorrelatedStudy) -> tuple[float, float, float]:
    """MSE ratio of the scalar-weight Lagrange fusion to GLS on the non-separable case; the matrix-weight KKT
    solution's relative difference from GLS there; the scalar-weight ratio on E2.7."""
    R = cs.oriented_covariance()
    N = R.shape[0] // 2
    H = np.kron(np.ones((N, 1)), np.eye(2))
    K = co.gls_weights(H, R)
    Ws = co.scalar_lagrange_weights(R, 2)
    ratio = float(np.trace(Ws @ R @ Ws.T) / np.trace(K @ R @ K.T))
    lag = co.lagrange_weights(H, R)
    lag_diff = float(np.max(np.abs(lag - K)) / np.max(np.abs(K)))
    R27 = s27.R
    H27 = np.kron(np.ones((R27.shape[0] // 2, 1)), np.eye(2))
    K27 = co.gls_weights(H27, R27)
    W27 = co.scalar_lagrange_weights(R27, 2)
    ratio27 = float(np.trace(W27 @ R27 @ W27.T) / np.trace(K27 @ R27 @ K27.T))
    return ratio, lag_diff, ratio27


def gesv_written_ratio(n: int, d: int) -> float:
    """Operation count of the Markov formula with ``numpy.linalg.inv``'s R⁻¹ over that of the route as written.

    Parameters
    ----------
    n, d : int
        Stacked rows and state dimension (>= 1 each).

    Returns
    -------
    float
        ``gesv_inverse_count(n, d)`` over ``ldl_as_written_count(n, d)``: above 1 when the route as written needs fewer
        operations.

    Raises
    ------
    TypeError
        ``n`` or ``d`` not an integer.
    ValueError
        ``n`` or ``d`` below 1 or beyond the ceiling of its kind.
    """
    n, d = count(n, "n"), count(d, "d")  # named here: the counts below name them N and d (fuzz 18, F3)
    return co.gesv_inverse_count(n, d) / co.ldl_as_written_count(n, d)
