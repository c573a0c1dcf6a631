r"""Chapter 02, §2.4 (E2.4, E2.4b): belief-degree weights and their dependence on the analyst's parameter:
comparisons, tables, figure and glue."""

from __future__ import annotations

from fusion.book._few_runs import study_runs_named
from fusion._counts import allocation, sequence
from fusion._structures import within
from fusion._limits import LOOP_STEP, loop_work, work
from fusion._validation import as_array, distinct_printed, general, glue_part, instance_of, scalar, selection
from fusion.book.chapters.lecture_weighting._common import _std_entries

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from fusion._docstrings import ParameterDocs
from fusion._results import ResultSpec, array, flag, integer, number, validated_post_init
from fusion._validation import count
from fusion._limits import written_as
from fusion.book.chapters.lecture import _holds, _key, _lec_glue, _r, legend_below, sci
from fusion.book.tables import roundoff
from fusion.book.glue import GlueValues
from fusion.book.ledger import MIN_RUNS, Comparison, Unverifiable
from fusion.book.style import METHOD_LABELS, color, new_figure
from fusion.book.tables import rounded
from fusion.scenarios.lecture_weighting.belief import BeliefKind, BeliefParameterStudy, BeliefStudy
from fusion._counts import seed as check_seed
from fusion._shown import shown

K = BeliefKind

#: The Parameters entries the functions of E2.4b share (:class:`fusion._docstrings.ParameterDocs`).
_PARAMS = ParameterDocs({
    "s": "BeliefParameterStudy\n    Output of :func:`fusion.scenarios.lecture_weighting.belief.belief_parameter_study`.",
    "grid": ("(values of A's parameter, values of B's parameter), optional\n    Default: the study's primary grid for "
             "both. Both grids together at most the work budget (``fusion._limits.MAX_WORK``, 350 units a value plus "
             "one a run: about 2.2 million at 100 runs), by their lengths before any value is read."),
})

__all__ = [
    "figure_24",
    "glue_24",
    "eig_row_comparison",
    "BELIEF_GRIDS",
    "LIMIT_GRIDS",
    "belief_accuracy",
    "belief_parameter_comparison",
    "belief_objectivity",
    "table_belief_grid",
    "glue_24b",
    "table_belief_grids",
    "table_belief_limit",
    "ShiftWeightDraws",
    "shift_weight_draws",
    "table_shift_weight",
]


# --------------------------------------------------------------------------- 2.4
def figure_24(s: BeliefStudy) -> Figure:
    """F2.4: weights against the shift Δ of reading 1; eigenvector against row-sum weights.

    Parameters
    ----------
    s : BeliefStudy
        E2.4 (:func:`fusion.scenarios.lecture_weighting.belief.belief_study`): the shift sweep and the snapshot weights.

    Returns
    -------
    matplotlib.figure.Figure
        Left: each sensor's eigenvector weight against the shift Δ of sensor 1 (°C); right: the Perron eigenvector
        weight against the row-sum weight of every snapshot and sensor.
    """
    instance_of(s, BeliefStudy, "s")
    fig, axes = new_figure(1, 2, figsize=(7.5, 3.4))
    for i in range(s.W.shape[1]):
        axes[0].plot(s.deltas, s.W[:, i], color=color(f"sensor {i + 1}"),
                     label=f"sensor {i + 1}" + (" (shifted)" if i == 0 else ""))
    axes[0].set_xlabel("shift Δ of sensor 1 (°C)")
    axes[0].set_ylabel("eigenvector weight")
    axes[1].scatter(s.row_w.ravel(), s.eig_w.ravel(), s=2, alpha=0.3, color=color("sensor 1"))
    axes[1].plot([0, 0.5], [0, 0.5], color=color("published"), lw=0.8)
    axes[1].set_xlabel("row-sum (support) weight")
    axes[1].set_ylabel("Perron eigenvector weight")
    legend_below(fig, ncol=4)
    return fig


@_lec_glue
def glue_24(s: BeliefStudy) -> GlueValues:
    """Glue values of E2.4.

    Parameters
    ----------
    s : BeliefStudy
        Result of :func:`fusion.scenarios.lecture_weighting.belief.belief_study`; its offsets (``lec_bel_s4_offset``,
        ``lec_bel_fused_*``) are from its own true value ``s.x``.

    Raises
    ------
    TypeError
        ``s`` not a BeliefStudy.
    ValueError
        ``s`` of fewer than 4 sensors (``lec_bel_s4_offset`` is sensor 4's), or of fewer than rule R4's 100
        snapshots, shifted or unshifted (the paired comparisons of :func:`eig_row_comparison`), named.
    """
    instance_of(s, BeliefStudy, "s")
    _holds(range(1, s.base.size + 1), (4,), "s", "sensor", "glue_24")
    for what, n in (("shifted", int(np.sum(s.shifted))), ("unshifted", int(np.sum(~s.shifted)))):
        if n < MIN_RUNS:   # named here, not as eig_row_comparison's select (fuzz 29b B6)
            raise ValueError(f"s holds {n} {what} snapshots, fewer than the {MIN_RUNS} paired runs each comparison "
                             "of glue_24 needs: give more snapshots (belief_study(snapshots=...))")
    W = s.W
    i_peak = int(np.argmax(W[:, 0]))
    i_dip = int(np.argmin(W[:i_peak + 1, 0]))
    e1 = np.eye(W.shape[1])[0]
    fused = np.array([W[i] @ (s.base + dl * e1) for i, dl in enumerate(s.deltas)])
    near = [j for j in range(1, W.shape[1]) if j != int(np.argmax(s.base[1:])) + 1]  # the readings near the truth
    out = _r({"bel_s4_offset": (s.base[3] - s.x, 2), "bel_w_out_d0": (W[0, 0], 4),
              "bel_dip_w": (W[i_dip, 0], 4), "bel_dip_delta": (s.deltas[i_dip], 2),
              "bel_near_w_peak_max": (float(np.max(W[i_peak, near])), 3),
              "bel_fused_d0": (fused[0] - s.x, 2), "bel_fused_peak": (fused[i_peak] - s.x, 2),
              "bel_w_out_d20": (W[-1, 0], 6), "bel_peak_delta": (s.deltas[i_peak], 2),
              "bel_peak_w": (W[i_peak, 0], 4), "bel_unit_k_maxdiff": (s.unit_k_maxdiff, 12),
              "bel_unit_f_maxdiff": (s.unit_f_maxdiff, 4), "bel_unit_fconv_maxdiff": (s.unit_fconv_maxdiff, 12),
              "bel_unit_f_valdiff": (s.unit_f_valdiff, 4), "bel_rowsum_maxdiff": (s.rowsum_maxdiff, 4),
              "bel_rowsum_valdiff_rms": (s.rowsum_valdiff_rms, 4), "bel_mse_eig": (s.mse_eig, 4),
              "bel_mse_row": (s.mse_row, 4), "bel_bin_lam1": (s.bin_lam[0], 4),
              "bel_bin_lam2": (s.bin_lam[1], 4)})
    out["lec_bel_monotone"] = int(np.all(np.diff(W[:, 0]) <= 1e-15))
    # eigenvector against row sums, paired by snapshot: overall, unshifted and shifted snapshots
    for tag, sel in (("", slice(None)), ("_unshifted", ~s.shifted), ("_shifted", s.shifted)):
        c = eig_row_comparison(s, sel)
        m, lo, hi = c.interval()
        out[f"lec_bel_er_d{tag}"], out[f"lec_bel_er_lo{tag}"], out[f"lec_bel_er_hi{tag}"] = (
            rounded(m, 3), rounded(lo, 3), rounded(hi, 3))
        out[f"lec_bel_er_word{tag}"] = {"reproduced": "better", "contradicted": "worse",
                                        "not distinguishable": "not distinguishable"}[c.status()]
    out["lec_bel_er_n"] = int(s.shifted.size)
    pf = s.perron
    out["lec_bel_pf_fuzzy_gap"] = sci(pf["fuzzy, s = 0.25"].min_gap, 2)
    out["lec_bel_pf_fuzzy_gap1"] = rounded(pf["fuzzy, s = 1"].min_gap, 4)
    out["lec_bel_pf_fuzzy_minw"] = rounded(pf["fuzzy, s = 1"].min_weight, 5)
    for e in (0.5, 1, 2, 4):
        out[f"lec_bel_pf_bin_rep_{glue_part(e)}"] = rounded(100 * pf[f"binary, ε = {e:g}"].share_repeated, 1)
        out[f"lec_bel_pf_bin_zero_{glue_part(e)}"] = rounded(100 * pf[f"binary, ε = {e:g}"].share_zero_weight, 1)
    for m in (1, 2, 4):
        out[f"lec_bel_pf_tr_rep_{m}"] = rounded(100 * pf[f"truncated, m = {m:g}"].share_repeated, 1)
        out[f"lec_bel_pf_tr_zero_{m}"] = rounded(100 * pf[f"truncated, m = {m:g}"].share_zero_weight, 1)
    out["lec_bel_unit_k_text"] = roundoff(s.unit_k_maxdiff)
    out["lec_bel_unit_fconv_text"] = roundoff(s.unit_fconv_maxdiff)
    return out


def eig_row_comparison(s: BeliefStudy, select: slice | np.ndarray = slice(None)) -> Comparison:
    """E2.4(c): the Perron-eigenvector weights against the row-sum weights, squared error paired by snapshot.

    Parameters
    ----------
    s : BeliefStudy
        Output of :func:`fusion.scenarios.lecture_weighting.belief.belief_study`.
    select : slice or boolean array
        The snapshots compared (default all; ``s.shifted`` or its negation for one half): a slice, or a boolean
        mask with one entry per snapshot. An integer index array is refused: a repeated index would count one
        snapshot as several paired runs.

    Returns
    -------
    Comparison
        Eigenvector against row sums, claim "less".

    Raises
    ------
    TypeError
        ``s`` is not a BeliefStudy, or ``select`` neither a slice of integer bounds nor a boolean mask.
    ValueError
        ``select`` is a mask of another length than the snapshots', a slice of zero step, or selects fewer than
        the ledger's :data:`~fusion.book.ledger.MIN_RUNS` snapshots.
    """
    instance_of(s, BeliefStudy, "s")
    select = selection(select, "select", s.sq_eig.shape[0])
    a, b = s.sq_eig[select], s.sq_row[select]
    if a.shape[0] < MIN_RUNS:
        raise ValueError(f"select selects {a.shape[0]} of the {s.sq_eig.shape[0]} snapshots, fewer than the "
                         f"{MIN_RUNS} paired runs a comparison needs")
    return Comparison(a, b, "Perron eigenvector", "row sums", "less", "squared error of the fused value (°C²)")


#: Grids of E2.4b: (values of s, values of ε) per reading; the first is the chapter's primary grid. s is a
#: decay length and ε a cut-off, so no grid is "the same" for both: the verdict is run under several.
BELIEF_GRIDS: tuple[tuple[tuple[float, ...], tuple[float, ...]], ...] = (
    ((0.5, 1.0, 2.0, 4.0), (0.5, 1.0, 2.0, 4.0)),
    ((0.5, 1.0, 2.0, 4.0), (2.0, 4.0, 8.0, 16.0)),
    ((1.0, 2.0, 4.0, 8.0), (2.0, 4.0, 8.0, 16.0)),
    ((0.25, 0.5, 1.0, 2.0), (1.0, 2.0, 4.0, 8.0)),
    ((1.0, 2.0, 4.0, 8.0), (4.0, 8.0, 16.0, 32.0)),
)

#: The four-value grids (a factor of 8 each) of the fusion upper limit m of the truncated fuzzy belief (E2.4b; a reading of the lecture's belief).
LIMIT_GRIDS: tuple[tuple[float, ...], ...] = ((0.25, 0.5, 1.0, 2.0), (0.5, 1.0, 2.0, 4.0), (1.0, 2.0, 4.0, 8.0),
                                              (2.0, 4.0, 8.0, 16.0), (4.0, 8.0, 16.0, 32.0))

#: The parameter each kind varies, as the comparisons' metrics name it.
_PARAM = {K.FUZZY: "s", K.BINARY: "ε", K.DELETION: "ε", K.DELETION_THIRD: "ε",
          K.DELETION_ALL: "ε", K.FUZZY_LIMIT: "m"}


#: Units of work of one value of a ``grid`` of :func:`belief_parameter_comparison` (read, matched, its spread), on top
#: of one a run (fix70c).
_GRID_UNITS = 350


def _grids(s: BeliefParameterStudy, grid: object) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """``grid`` as (A's values, B's values): the study's primary grid for both when ``None``, else a pair of
    non-empty sequences of numbers (TypeError/ValueError naming ``grid``; membership in ``s.params`` is checked
    where the values are read, under ``grid``)."""
    if grid is None:
        return tuple(s.grid), tuple(s.grid)
    pair = [sequence(g, f"grid[{i}]", minimum=1, what="grid value") for i, g in enumerate(sequence(grid, "grid", 2))]
    # rule 17 by the grids' lengths before any value is read (fix70c: 2 x 10**7 values were each read, then matched
    # and their spreads taken): 4.2 us a value at 100 runs over 2 x 10**5 values (belief_parameter_comparison,
    # OPENBLAS_NUM_THREADS=1, the shared machine), counted as 350 units and one a run
    runs = next(iter(s.sq.values())).shape[0]
    work((len(pair[0]) + len(pair[1]),), "grid and s (its runs)", weight=_GRID_UNITS + runs)
    return tuple(tuple(scalar(v, f"grid[{i}][{j}]") for j, v in enumerate(g))
                 for i, g in enumerate(pair))  # type: ignore[return-value]


def _grid_text(v: tuple[float, ...] | np.ndarray) -> str:
    return "{" + ", ".join(f"{float(x):g}" for x in v) + "}"


#: Units of work of one grid value of :func:`belief_accuracy` (read and matched to ``s.params``; 3.0 us measured,
#: fix70c), on top of one unit per run for its column of squared errors.
_VALUE_UNITS = 300


@_PARAMS("s")
@study_runs_named("s")
def belief_accuracy(s: BeliefParameterStudy, kind: BeliefKind, values: tuple[float, ...]) -> Comparison:
    """E2.4b: is a belief rule, over a grid of its parameter, more accurate than the arithmetic mean?

    Parameters
    ----------
    kind : BeliefKind
        One of :data:`fusion.scenarios.lecture_weighting.belief.BELIEF_KINDS`.
    values : tuple of float
        The grid (at least one value, each one of ``s.params``).

    Returns
    -------
    Comparison
        Per snapshot, the rule's squared error averaged over the grid against the mean's (claim "less").

    Raises
    ------
    TypeError
        ``s`` not a BeliefParameterStudy, ``values`` not a sequence of numbers.
    ValueError
        ``kind`` not a kind of the study, ``values`` empty or an entry not one of ``s.params``; more ``values``
        than the work budget (``fusion._limits.MAX_WORK``, 300 units a value plus one a run: about 2.5 million at
        100 runs), by their number before any is read.
    """
    instance_of(s, BeliefParameterStudy, "s")
    kind = _key(kind, s.sq, "kind")
    params = [float(p) for p in s.params]
    items = sequence(values, "values", minimum=1, what="grid value")
    # rules 9 and 17 by len(values) before any value is read (fix70c: 10**7 values were each read and matched, then
    # a (runs, 10**7) selection of s.sq averaged): a value measured 3.0 us read and matched (10**5 values,
    # OPENBLAS_NUM_THREADS=1, minimum of 2, the shared machine), 300 units, and one unit per selected squared error
    runs = s.sq[kind].shape[0]
    allocation((runs, len(items)), "values and s (its runs)")
    work((len(items),), "values and s (its runs)", weight=_VALUE_UNITS + runs)
    idx = [params.index(_key(scalar(v, f"values[{i}]"), params, f"values[{i}]")) for i, v in enumerate(items)]
    return Comparison(np.mean(s.sq[kind][:, idx], axis=1), s.sq_mean, f"{METHOD_LABELS[kind]}, {_grid_text(values)}",
                      METHOD_LABELS["mean"], "less", "squared error averaged over the grid (°C²)", seed=s.seed)


@_PARAMS("s", "grid")
@study_runs_named("s")
def belief_parameter_comparison(s: BeliefParameterStudy, other: BeliefKind = K.DELETION,
                                grid: tuple[tuple[float, ...], tuple[float, ...]] | None = None,
                                kind: BeliefKind = K.FUZZY) -> Comparison:
    """E2.4b: per-snapshot spread of the fused value over a parameter grid, one belief against another.

    Parameters
    ----------
    other : BeliefKind
        The kind compared with (one of :data:`fusion.scenarios.lecture_weighting.belief.BELIEF_KINDS`); default the
        lecture's deletion rule.
    kind : BeliefKind
        The kind A (default the fuzzy belief, s varied).

    Returns
    -------
    Comparison
        A's spread against B's (claim "less"), paired by snapshot.
    """
    instance_of(s, BeliefParameterStudy, "s")
    from fusion.scenarios.lecture_weighting import belief_spread

    kind, other = _key(kind, _PARAM, "kind"), _key(other, _PARAM, "other")
    ga, gb = _grids(s, grid)
    pa, pb = _PARAM[kind], _PARAM[other]
    metric = (f"max − min of the fused value over {pa} ∈ {_grid_text(ga)}" +
              (f" or {pb} ∈ {_grid_text(gb)}" if (pa, tuple(ga)) != (pb, tuple(gb)) else "") + " (°C)")
    with within("grid"):  # a value not among the study's params: named by the argument it came from
        spread_a, spread_b = belief_spread(s, kind, ga), belief_spread(s, other, gb)
    return Comparison(spread_a, spread_b, METHOD_LABELS[kind], METHOD_LABELS[other], "less", metric, seed=s.seed)


def _rmse_text(c: Comparison) -> str:
    below = "below" if c.status() == "reproduced" else "not shown below"
    return f"RMSE {np.sqrt(np.mean(c.a)):.3f} °C, {below} the mean's {np.sqrt(np.mean(c.b)):.3f} °C (paired 95 % CI)"


@_PARAMS("s", "grid")
@study_runs_named("s")
def belief_objectivity(s: BeliefParameterStudy, other: BeliefKind = K.DELETION,
                       grid: tuple[tuple[float, ...], tuple[float, ...]] | None = None,
                       kind: BeliefKind = K.FUZZY) -> Comparison | Unverifiable:
    """E2.4b: the spread comparison of :func:`belief_parameter_comparison`, paired with each rule's accuracy.

    A spread alone rewards a rule that does nothing: a rule whose result is (close to) the plain mean on
    its grid has nothing left for its parameter to move. So each rule's accuracy against the arithmetic
    mean over its grid (:func:`belief_accuracy`, paired 95 % interval) is reported beside the spread
    comparison; it is information, not a gate (the rulebook judges the spread, rule R2).

    Parameters
    ----------
    other : BeliefKind
        The kind B (default the lecture's deletion rule).
    kind : BeliefKind
        The kind A (default the fuzzy belief).

    Returns
    -------
    Comparison
        The spread comparison (its metric names both rules' RMSE over their grids).
    """
    instance_of(s, BeliefParameterStudy, "s")
    kind, other = _key(kind, _PARAM, "kind"), _key(other, _PARAM, "other")
    ga, gb = _grids(s, grid)
    c = belief_parameter_comparison(s, other, (ga, gb), kind)
    with within("grid"):
        acc_a, acc_b = belief_accuracy(s, kind, ga), belief_accuracy(s, other, gb)
    acc = (f"; over its grid the {METHOD_LABELS[kind].split(' (')[0]} has {_rmse_text(acc_a)}, the "
           f"{METHOD_LABELS[other].split(' (')[0]} {_rmse_text(acc_b)}")
    bad = [name.split(' (')[0] for name, a in ((METHOD_LABELS[kind], acc_a), (METHOD_LABELS[other], acc_b))
           if a.status() != "reproduced"]
    if bad:
        acc += f" (not shown more accurate than the mean: {' and '.join(bad)}; reported, not a gate)"
    return Comparison(c.a, c.b, c.a_name, c.b_name, c.claim, c.metric + acc, seed=c.seed)


@study_runs_named("s")
def table_belief_grid(s: BeliefParameterStudy) -> pd.DataFrame:
    """RMSE of each belief fusion of E2.4b against its parameter, and the mean spread over the primary grid.

    Parameters
    ----------
    s : BeliefParameterStudy
        E2.4b, every fusion over its parameter grid (:func:`fusion.scenarios.lecture_weighting.belief.belief_parameter_study`).

    Returns
    -------
    pandas.DataFrame
        One row per kind, one column per parameter value (RMSE in °C, 3 decimals), the mean spread
        over the primary grid and the RMSE over it; the arithmetic mean's RMSE in the index name.
    """
    instance_of(s, BeliefParameterStudy, "s")
    distinct_printed([float(p) for p in s.params], "s.params", general, "labels a column")  # rebuilt (fuzz 30b)
    rows = {}
    g = tuple(float(v) for v in s.grid)
    for k in s.fused:
        rmse = np.sqrt(np.mean(s.sq[k], axis=0))
        row = {f"{float(p):g}": f"{r:.3f}" for p, r in zip(s.params, rmse)}
        row[f"mean spread over {_grid_text(g)}"] = f"{float(np.mean(s.spread[k])):.3f}"
        acc = belief_accuracy(s, k, g)
        row[f"RMSE over {_grid_text(g)}"] = (f"{np.sqrt(np.mean(acc.a)):.3f}"
                                              + ("" if acc.status() == "reproduced" else " (not below the mean's)"))
        rows[METHOD_LABELS[k]] = row
    tab = pd.DataFrame(rows).T
    tab.index.name = (f"RMSE (°C) against the parameter, {s.snapshots} snapshots (arithmetic mean: "
                      f"{np.sqrt(np.mean(s.sq_mean)):.3f})")
    return tab


@_lec_glue
@_PARAMS("s")
@study_runs_named("s")
def glue_24b(s: BeliefParameterStudy) -> GlueValues:
    """Glue values of E2.4b (keys ``lec_bp_*``)."""
    instance_of(s, BeliefParameterStudy, "s")
    d: dict[str, tuple[float, int]] = {
        "bp_n": (s.snapshots, 0), "bp_pmin": (float(np.min(s.grid)), 2), "bp_pmax": (float(np.max(s.grid)), 2),
        "bp_shift": (s.shift, 1), "bp_limit_scale": (s.limit_scale, 1),
        "bp_rmse_mean": (float(np.sqrt(np.mean(s.sq_mean))), 3)}
    keys = {K.FUZZY: "fuzzy", K.BINARY: "binary", K.DELETION: "deletion", K.DELETION_THIRD: "del13",
            K.DELETION_ALL: "del1", K.FUZZY_LIMIT: "limit"}
    for k, key in keys.items():
        d[f"bp_spread_{key}"] = (float(np.mean(s.spread[k])), 3)
        rm = np.sqrt(np.mean(s.sq[k], axis=0))
        d[f"bp_rmse_{key}_min"] = (float(rm.min()), 3)
        d[f"bp_rmse_{key}_max"] = (float(rm.max()), 3)
        d[f"bp_rmse_{key}_grid"] = (float(np.sqrt(np.mean(belief_accuracy(s, k, tuple(s.grid)).a))), 3)
    for tag, other in (("", K.DELETION), ("perron_", K.BINARY), ("del13_", K.DELETION_THIRD),
                       ("del1_", K.DELETION_ALL)):
        m, lo, hi = belief_parameter_comparison(s, other).interval()
        d[f"bp_{tag}d"], d[f"bp_{tag}lo"], d[f"bp_{tag}hi"] = (m, 3), (lo, 3), (hi, 3)
    # the arithmetic mean is what the unanimous rule returns: its share of snapshots equal to the mean on the grid
    params = [float(p) for p in s.params]
    idx = [params.index(float(v)) for v in s.grid]
    out = _r(d)
    mean_sq = s.sq_mean
    same = np.isclose(s.sq[K.DELETION_ALL][:, idx], mean_sq[:, None], rtol=1e-12, atol=1e-12)
    out["lec_bp_del1_share_mean"] = rounded(float(100 * np.mean(same)), 0)
    grids = [g for g in BELIEF_GRIDS if set(g[0]) | set(g[1]) <= set(params)]
    for other, key in ((K.BINARY, "perron"), (K.DELETION, "deletion"),
                       (K.DELETION_THIRD, "del13"), (K.DELETION_ALL, "del1")):
        st = [belief_objectivity(s, other, g).status() for g in grids]
        out[f"lec_bp_grids_{key}_better"] = int(sum(x == "reproduced" for x in st))
        out[f"lec_bp_grids_{key}_nd"] = int(sum(x == "not distinguishable" for x in st))
        out[f"lec_bp_grids_{key}_unchecked"] = int(sum(x == "cannot be checked" for x in st))
    out["lec_bp_n_grids"] = len(grids)
    fair = [belief_objectivity(s, other, g).status() for g in grids
            for other in (K.BINARY, K.DELETION, K.DELETION_THIRD, K.DELETION_ALL)]
    out["lec_bp_n_fair"] = int(sum(x != "cannot be checked" for x in fair))
    out["lec_bp_n_fair_more"] = int(sum(x == "contradicted" for x in fair))
    lim = [g for g in LIMIT_GRIDS if set(g) <= set(params)]
    st = [belief_objectivity(s, K.DELETION, (g, g), K.FUZZY_LIMIT).status() for g in lim]
    out["lec_bp_lim_n_grids"] = len(lim)
    out["lec_bp_lim_less"] = int(sum(x == "reproduced" for x in st))
    out["lec_bp_lim_more"] = int(sum(x == "contradicted" for x in st))
    out["lec_bp_lim_nd"] = int(sum(x == "not distinguishable" for x in st))
    out["lec_bp_lim_unchecked"] = int(sum(x == "cannot be checked" for x in st))
    raw = [belief_parameter_comparison(s, K.DELETION, (g, g), K.FUZZY_LIMIT).status() for g in lim]
    out["lec_bp_lim_raw_less"] = int(sum(x == "reproduced" for x in raw))
    out["lec_bp_lim_raw_more"] = int(sum(x == "contradicted" for x in raw))
    return out


_WORD_SPREAD = {"reproduced": "fuzzy less sensitive", "contradicted": "fuzzy more sensitive",
                "not distinguishable": "not distinguishable", "cannot be checked": "tests nothing"}


def _cell(ev: Comparison | Unverifiable, c: Comparison) -> str:
    """Table cell: the paired spread difference with its CI, and what the reading shows (accuracy gate applied)."""
    m, lo, hi = c.interval()
    word = _WORD_SPREAD[ev.status()]
    return f"{m:+.3f} [{lo:+.3f}, {hi:+.3f}], {word}"


@study_runs_named("s")
def table_belief_grids(s: BeliefParameterStudy) -> pd.DataFrame:
    """E2.4b's readings under every grid of :data:`BELIEF_GRIDS` and every deletion rule: fuzzy spread minus the binary one.

    Parameters
    ----------
    s : BeliefParameterStudy
        Output of :func:`fusion.scenarios.lecture_weighting.belief.belief_parameter_study` (its ``params`` must hold every grid value: a
        ValueError naming ``s`` otherwise).

    Returns
    -------
    pandas.DataFrame
        One row per grid: the paired mean difference of the spreads (°C) against the lecture's deletion
        rule (kept if trusted by at least half, a third or all of the others) and against the binary
        belief's Perron vector, each with its interval and what it shows once both rules' accuracy is
        checked (:func:`belief_objectivity`).
    """
    instance_of(s, BeliefParameterStudy, "s")
    _holds(s.params.tolist(), sorted({v for g in BELIEF_GRIDS for grid in g for v in grid}), "s", "params",
           "table_belief_grids (every grid of BELIEF_GRIDS)")   # named s, not belief_objectivity's grid (fuzz 26d W2)
    rows = []
    for g in BELIEF_GRIDS:
        row: dict[str, str] = {"s grid": _grid_text(g[0]), "ε grid": _grid_text(g[1])}
        for other, lab in ((K.DELETION, "vs deletion, ≥ ½ (primary)"),
                           (K.DELETION_THIRD, "vs deletion, ≥ ⅓"),
                           (K.DELETION_ALL, "vs deletion, all"),
                           (K.BINARY, "vs Perron-binary")):
            row[lab] = _cell(belief_objectivity(s, other, g), belief_parameter_comparison(s, other, g))
        rows.append(row)
    tab = pd.DataFrame(rows)
    tab.index = pd.Index(["primary (chapter)"] + [f"grid {i + 2}" for i in range(len(rows) - 1)], name="grid")
    return tab


@study_runs_named("s")
def table_belief_limit(s: BeliefParameterStudy) -> pd.DataFrame:
    """The truncated fuzzy belief (a reading of the lecture's belief: its fusion upper limit m varied) over every grid of :data:`LIMIT_GRIDS`.

    Parameters
    ----------
    s : BeliefParameterStudy
        Output of :func:`fusion.scenarios.lecture_weighting.belief.belief_parameter_study`, with the limit grids (its
        ``params`` must hold every value of :data:`LIMIT_GRIDS`: a ValueError naming ``s`` otherwise).

    Returns
    -------
    pandas.DataFrame
        One row per m grid: the truncated belief's RMSE over the grid (and whether it beats the mean),
        and its spread minus that of the fuzzy belief (s on the same grid) and of the deletion rule
        (ε on the same grid), each with its 95 % CI (negative: the truncated belief moves less).
    """
    instance_of(s, BeliefParameterStudy, "s")
    _holds(s.params.tolist(), sorted({v for g in LIMIT_GRIDS for v in g}), "s", "params",
           "table_belief_limit (every grid of LIMIT_GRIDS)")   # named s, not belief_accuracy's values (fuzz 26d W1)
    rows = []
    for g in LIMIT_GRIDS:
        acc = belief_accuracy(s, K.FUZZY_LIMIT, g)
        row = {"m grid": _grid_text(g),
               "RMSE over the grid": f"{np.sqrt(np.mean(acc.a)):.3f}" + ("" if acc.status() == "reproduced" else
                                                                          " (not below the mean's)")}
        for other, lab in ((K.FUZZY, "m minus s, same grid"), (K.DELETION, "m minus deletion ε, same grid")):
            c = belief_parameter_comparison(s, other, (g, g), K.FUZZY_LIMIT)
            m, lo, hi = c.interval()
            row[lab] = f"{m:+.3f} [{lo:+.3f}, {hi:+.3f}]"
        rows.append(row)
    tab = pd.DataFrame(rows).set_index("m grid")
    tab.columns.name = f"s = {s.limit_scale:g}, {s.snapshots} snapshots"
    return tab


@dataclass(frozen=True)
class ShiftWeightDraws:
    """E2.4a over many draws: the shifted reading's belief-degree weight against the shift Δ (:func:`shift_weight_draws`).

    Attributes
    ----------
    deltas : ndarray, shape (201,)
        The shifts Δ (°C).
    W : ndarray, shape (draws, 201)
        Weight of reading 1.
    mean : ndarray, shape (201,)
        Its mean over the draws.
    rebound : ndarray, shape (draws,)
        Per draw, the largest rise of the weight above its running minimum.
    n_nonmonotone : int
        Draws whose weight rises somewhere by more than 10⁻¹².
    mean_monotone : bool
        The mean curve never rises.
    mean_rebound : float
        The mean curve's largest rise above its running minimum.
    draws, seed : int
    """

    deltas: np.ndarray
    W: np.ndarray
    mean: np.ndarray
    rebound: np.ndarray
    n_nonmonotone: int
    mean_monotone: bool
    mean_rebound: float
    draws: int
    seed: int

    __result_spec__ = ResultSpec({"deltas": array("shifts", increasing=True), "W": array("draws", "shifts", bounds=(0.0, 1.0)),
                                  "mean": array("shifts", bounds=(0.0, 1.0)), "rebound": array("draws", bounds=(0.0, 1.0)),
                                  "n_nonmonotone": integer(0), "mean_monotone": flag(), "mean_rebound": number(),
                                  "draws": integer(1), "seed": integer(0)},
                                 relations=(lambda v, cls: _draws_relation(v, cls),))
    __post_init__ = validated_post_init


def _draws_relation(values: dict, cls: str) -> None:
    """``draws`` rows of weights, at most ``draws`` of them not monotone."""
    if values["W"].shape[0] != values["draws"]:
        raise ValueError(f"{cls}.draws must be the number of rows of W ({values['W'].shape[0]}), got {values['draws']}")
    if values["n_nonmonotone"] > values["draws"]:
        raise ValueError(f"{cls}.n_nonmonotone must be at most draws = {values['draws']}, got {values['n_nonmonotone']}")


#: Units of one belief-degree fusion of :func:`shift_weight_draws` (a draw at one shift, 85 us measured) on top of its
#: n x n pairs (``_SHIFT_DRAW_PAIR``).
_SHIFT_DRAW_STEP = 9 * LOOP_STEP
#: Units of one of the n x n pairs of a belief-degree fusion of n sensors (fuzz 41b C2: the sensors were counted once
#: each, so 20 draws of 300 sensors, 3.7 % of the budget, ran 38 CPU-s). ``belief_degree`` of n readings measured
#: (CPU time, minimum of 3, OPENBLAS_NUM_THREADS=1, shared machine) 87 us at n = 4, 287 us at 50, 852 us at 100,
#: 4.0 ms at 200, 9.7 ms at 300, 29 ms at 500: about 9,000 + 12 n**2 units (10 to 11.7 units per pair from 100 on).
_SHIFT_DRAW_PAIR = 12


def shift_weight_draws(draws: int = 200, seed: int = 2405, sigma: Sequence[float] = (0.5, 1.0, 2.0, 4.0),
                       x: float = 900.0) -> ShiftWeightDraws:
    """E2.4a over many draws: the shifted reading's belief-degree weight against the shift Δ (review F9).

    Each draw is a snapshot of the sensors at ``x`` (as in :func:`fusion.scenarios.lecture_weighting.belief.belief_study`,
    which shows one draw); reading 1 is shifted by Δ on the same grid, 0-20 °C in steps of 0.1, and
    weighted by :func:`fusion.readings.fusion_set.belief_degree` (s = 1).

    Parameters
    ----------
    draws : int
        Snapshots (>= 2).
    seed : int
    sigma : sequence of float
        Noise SD of each sensor (°C).
    x : float
        True value (°C).

    Returns
    -------
    ShiftWeightDraws
        Per draw and shift Δ (201 values, 0 to 20) the shifted reading's weight ``W``, its mean over draws, each draw's
        rebound and how many draws are not monotone.
    """
    seed = check_seed(seed)
    from fusion.readings.fusion_set import belief_degree

    draws = count(draws, "draws", minimum=2)
    sig = as_array(sigma, "sigma", ndim=1)
    _std_entries(sig, "sigma")   # at once, before the budgets on sig.size (fuzz 68b C7, C8)
    x = scalar(x, "x")
    # one belief-degree fusion per draw and shift, 85 us measured (4,851 draws, the edge at one loop step, ran 83
    # CPU-s; time.process_time, shared machine; fuzz 39a E4): 9 loop steps, and 12 units per pair of sensors
    # (fuzz 41b C2: its cost grows as n**2): 541 draws of 4 sensors, 4 draws of 300 the most accepted
    loop_work((draws, 201), _SHIFT_DRAW_PAIR * sig.size**2, "draws and sigma", step=_SHIFT_DRAW_STEP)
    deltas = np.linspace(0, 20, 201)
    base = x + np.random.default_rng(seed).normal(size=(draws, sig.size)) * sig
    e1 = np.eye(sig.size)[0]
    W = np.array([[belief_degree(b + d * e1).weights[0] for d in deltas] for b in base])
    rebound = np.max(W - np.minimum.accumulate(W, axis=1), axis=1)
    mean = W.mean(axis=0)
    return ShiftWeightDraws(deltas=deltas, W=W, mean=mean, rebound=rebound,
                            n_nonmonotone=int(np.sum(np.any(np.diff(W, axis=1) > 1e-12, axis=1))),
                            mean_monotone=bool(np.all(np.diff(mean) <= 1e-12)),
                            mean_rebound=float(np.max(mean - np.minimum.accumulate(mean))), draws=draws, seed=seed)


#: Units of work of one shift of :func:`table_shift_weight` (read and matched to the grid; fix70c), on top of 3 a
#: draw for its column of weights and their quartiles.
_SHIFT_UNITS = 900


def table_shift_weight(s: ShiftWeightDraws, at: tuple[float, ...] = (0.0, 1.0, 2.0, 3.0, 5.0, 8.0, 12.0, 20.0)) -> pd.DataFrame:
    """The shifted reading's weight at a few shifts: mean over draws, with the quartiles (review F9).

    Parameters
    ----------
    s : ShiftWeightDraws
        Result of :func:`shift_weight_draws`.
    at : tuple of float
        Shifts Δ (°C) on the grid of ``s.deltas``, up to round-off: a grid point as written down (a float32 0.3,
        ``0.1 * 3``; the rule of ``fusion._limits.written_as``, PublishedValues' too) is that point.

    Returns
    -------
    pandas.DataFrame
        One row per Δ: mean weight, lower quartile, median, upper quartile.

    Raises
    ------
    TypeError
        ``s`` not a ShiftWeightDraws, ``at`` not a sequence of numbers.
    ValueError
        ``at`` empty or an entry not a shift of the grid; more shifts than the work budget
        (``fusion._limits.MAX_WORK``, 900 units a shift plus 3 a draw: about 660,000 at 200 draws), by their
        number before any is read.
    """
    instance_of(s, ShiftWeightDraws, "s")
    items = sequence(at, "at", minimum=1, what="shift")
    # rules 9 and 17 by len(at) before any shift is read (fix70c: 10**7 shifts were each read and matched, then a
    # (draws, 10**7) selection of s.W copied and sorted for its quartiles): one shift measured 8.8 us at 5 draws,
    # 17.9 us at 400 (10**5 and 2 x 10**4 shifts, OPENBLAS_NUM_THREADS=1, minimum of 2, the shared machine), about
    # 880 units and 2.3 a draw, counted as 900 and 3
    draws = s.W.shape[0]
    allocation((draws, len(items)), "at and s (its draws)", arrays=2)
    work((len(items),), "at and s (its draws)", weight=_SHIFT_UNITS + 3 * draws)
    idx = []
    for i, a in enumerate(items):
        a = scalar(a, f"at[{i}]")
        j = int(np.argmin(np.abs(s.deltas - a)))
        # a grid point up to round-off, or as written down (fusion._limits.written_as: a float32 0.3 is 0.3, as in
        # PublishedValues; fuzz 26d DB7)
        if abs(s.deltas[j] - a) > 1e-9 * max(1.0, abs(a)) and not written_as(a, float(np.round(s.deltas[j], 9))):
            raise ValueError(f"at[{i}] = {shown(a)} is not a shift of the grid of s.deltas ({s.deltas[0]:g} to "
                             f"{s.deltas[-1]:g} in steps of {s.deltas[1] - s.deltas[0]:g})")
        idx.append(j)
    W = s.W[:, idx]
    q = np.quantile(W, [0.25, 0.5, 0.75], axis=0)
    return pd.DataFrame({"shift Δ (°C)": [f"{s.deltas[i]:g}" for i in idx],
                         "mean weight": [f"{v:.4f}" for v in W.mean(axis=0)],
                         "lower quartile": [f"{v:.4f}" for v in q[0]], "median": [f"{v:.4f}" for v in q[1]],
                         "upper quartile": [f"{v:.4f}" for v in q[2]]}).set_index("shift Δ (°C)")
