"""The tracking study's scenario, tables, error and NEES per run, collapsed filters and the readings' values.

Part of :mod:`fusion.book.chapters.chernoff` (chapter 06, patent CN107330468B), which re-exports its public names."""

from __future__ import annotations

from typing import Any

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from fusion._validation import FloatArray, count, frame_slice, instance_of
from fusion._shown import shown
from fusion.book.style import METHOD_LABELS, new_figure
from fusion.filtering.kalman import nees
from fusion.book.tables import _cell_number, _frame, rounded
from fusion.scenarios.range_bearing import (GUARD_STAGES, METHODS, RangeBearingScenario, TrackingRun, min_local_ess,
                                            nees_per_frame, position_sq_errors, posterior_crb)
from fusion.book.chapters.chernoff.settings import COLLAPSE_FRACTION, EARLY, LATE, _check_crb, _check_study, _check_window
from fusion.scenarios.range_bearing import _check_runs, _check_size
from fusion.book.glue import GlueValues
from fusion.book.chapters._defaults import study_defaults

__all__ = ["central_collapsed", "scenario_values", "scenario_table", "crb_position", "method_table", "rmse_figure",
           "per_run_mse", "per_run_nees", "typical_run", "gain_values", "collapsed", "any_collapsed",
           "collapse_values", "readings_values", "equal_kl_g_values", "table_values", "message_sizes"]


# --------------------------------------------------------------------------- tracking study
#: The RMSE column and the bound's row of :func:`rmse_table`, which its glue reads (issue 36: named once).
RMSE_LATE = "RMSE from frame 5 (m)"
CRB_ROW = "posterior CRB (floor)"


def scenario_values(sc: RangeBearingScenario, runs: int) -> GlueValues:
    """Glue values of the scenario's sizes (``chf_runs``, ``chf_frames``, ``chf_n``, ...).

    Parameters
    ----------
    sc : RangeBearingScenario
        The tracking scenario.
    runs : int
        Number of Monte-Carlo runs of the study (a count, >= 1).

    Returns
    -------
    dict of str to int
        ``chf_runs`` (runs), ``chf_frames`` (frames K), ``chf_n`` (nodes N), ``chf_q_particles``
        (particles per node filter), ``chf_s`` (mixture components per node), ``chf_r``
        (importance samples R), ``chf_central`` (particles of the centralised filter), ``chf_mf``
        (components of the first-order fused mixture, :math:`S^N`) and ``chf_mf_10``
        (:math:`3^{10}`: the count for ten nodes of three components each, the appendix's fixed example, whatever
        ``sc.n_components``; fuzz 26b D8: the prose beside it states the three).

    Raises
    ------
    TypeError
        ``sc`` not a RangeBearingScenario, ``runs`` not an integer.
    ValueError
        ``runs`` below 1.
    """
    instance_of(sc, RangeBearingScenario, "sc")
    runs = count(runs, "runs")  # issue 35: a glued run count is a count, not whatever was given
    n = len(sc.sensors)
    return {"chf_runs": runs, "chf_frames": sc.frames, "chf_n": n, "chf_q_particles": sc.n_particles,
            "chf_s": sc.n_components, "chf_r": sc.n_samples, "chf_central": sc.n_central,
            "chf_mf": sc.n_components**n, "chf_mf_10": 3**10}  # the prose's example: ten nodes of S = 3, not sc's


def message_sizes(sc: RangeBearingScenario, d: int = 4) -> GlueValues:
    """What a node sends per frame: its mixture's parameters (step C) against its particles. Glue ``chf_msg_*``.

    Parameters
    ----------
    sc : RangeBearingScenario
        Its ``n_components`` and ``n_particles``.
    d : int
        State dimension.

    Returns
    -------
    dict
        ``chf_msg_gm`` (numbers of a mixture: S × (1 weight + d mean + d(d+1)/2 covariance)), ``chf_msg_pf`` (numbers
        of the weighted particles: Q × (d + 1)), ``chf_msg_d`` and ``chf_msg_s`` (int).

    Raises
    ------
    TypeError
        ``sc`` not a RangeBearingScenario, ``d`` not an integer.
    ValueError
        ``d`` below 1.
    """
    instance_of(sc, RangeBearingScenario, "sc")
    d = count(d, "d", minimum=1)
    return {"chf_msg_gm": sc.n_components * (1 + d + d * (d + 1) // 2), "chf_msg_pf": sc.n_particles * (d + 1),
            "chf_msg_d": d, "chf_msg_s": sc.n_components}


def scenario_table(sc: RangeBearingScenario) -> pd.DataFrame:
    """The scenario's choices, one row per item (the patent states none of them).

    Parameters
    ----------
    sc : RangeBearingScenario
        The tracking scenario.

    Returns
    -------
    DataFrame
        Ten rows indexed by ``item`` (sensors, measurement, motion, truth, shared prior, local
        filters, mixtures, fusion, centralised PF, feedback and topology) with one text column
        ``choice``; units in the text (m, m/s, °, s, m²/s³).

    Raises
    ------
    TypeError
        ``sc`` not a RangeBearingScenario.
    """
    instance_of(sc, RangeBearingScenario, "sc")
    return pd.DataFrame(
        [
            ("sensors (m)", "; ".join(f"({x:.0f}, {y:.0f})" for x, y in sc.sensors)),
            ("measurement", f"range σ = {sc.sigma_r:.0f} m, bearing σ = {np.rad2deg(sc.sigma_theta):.0f}°, every frame"),
            ("motion", f"nearly constant velocity, T = {sc.T:.0f} s, q = {sc.q} m²/s³"),
            ("truth", f"x0 = {sc.x0} (m, m/s), {sc.frames} frames, process noise"),
            ("shared prior", f"N(x0 + P0^½ξ, P0), P0^½ = diag{sc.p0_std}"),
            ("local filters", f"bootstrap PF, {sc.n_particles} particles, systematic resampling + regularisation"
                              + (f"; collapse guard: progressive correction in {GUARD_STAGES} steps below "
                                 f"{sc.guard * 100:g} % effective particles" if sc.guard > 0 else "")),
            ("mixtures (C)", f"weighted EM, {sc.n_components} full-covariance components, warm start, "
                             f"≤ {sc.em_iterations} iterations"),
            ("fusion (D-I)", f"ε⁽⁰⁾ uniform, R = {sc.n_samples} samples, PSO 20 × 50"),
            ("centralised PF", f"{sc.n_central} particles, all measurements"
                               + ("; the same collapse guard" if sc.central_guard > 0 else "")),
            ("feedback, topology", "none; fully connected"),
        ],
        columns=["item", "choice"],
    ).set_index("item")


def crb_position(sc: RangeBearingScenario, runs: list[TrackingRun]) -> FloatArray:
    r"""Root of the posterior CRB of the position, :math:`\sqrt{J^{-1}_{xx} + J^{-1}_{yy}}`, per frame.

    The expectation of the bound's recursion is averaged over the true trajectories of ``runs``
    (:func:`fusion.scenarios.range_bearing.posterior_crb`).

    Parameters
    ----------
    sc : RangeBearingScenario
        Model, sensors and noise levels.
    runs : list of TrackingRun
        Monte-Carlo runs; only their ``truth`` (shape (K, 4)) is used.

    Returns
    -------
    ndarray, shape (K,)
        Lower bound on the position RMSE at frames 1..K (m).

    Raises
    ------
    TypeError
        ``sc`` not a RangeBearingScenario, or ``runs`` not a sequence of TrackingRun.
    ValueError
        ``runs`` holds no run, a run twice or runs of several scenarios, or ``sc`` is another scenario than theirs (the bound
        would be of other frames, sensors or noise).
    """
    runs = _check_study(runs, sc)
    crb = posterior_crb(sc, np.stack([r.truth for r in runs]))
    return np.sqrt(crb[:, 0, 0] + crb[:, 2, 2])


def _defined_nees(runs: list[TrackingRun], key: str) -> FloatArray:
    """``nees_per_frame(runs, key)`` with NaN where the method's covariance is singular to working precision (fuzz
    26b SP: a fused covariance of valid runs with few particles can be): its NEES is undefined there, so the
    window's mean is too, and :func:`method_table` shows "—" rather than refusing the other methods' values."""
    try:
        return nees_per_frame(runs, key)
    except ValueError as e:  # nees_per_frame names runs and key, chaining the NEES's own error (fuzz 32a C6)
        if not str(e.__cause__).startswith("covariances must be positive definite"):
            raise
    out = np.empty((len(runs), int(np.shape(runs[0].truth)[0])))
    for j, r in enumerate(runs):
        for k in range(out.shape[1]):
            try:
                out[j, k] = nees(r.estimates[key][k] - r.truth[k], r.covariances[key][k])
            except ValueError as e:
                if not str(e).startswith("covariances must be positive definite"):
                    raise
                out[j, k] = np.nan
    return out


def method_table(runs: list[TrackingRun], crb_pos: FloatArray, plain: list[TrackingRun] | None = None) -> pd.DataFrame:
    """Table of every method: RMSE over frames 5-K (m) and mean NEES (4-D), with the CRB as floor (2 decimals).

    Parameters
    ----------
    runs : list of TrackingRun
        The Monte-Carlo runs (every method of :data:`~fusion.scenarios.range_bearing.METHODS` recorded).
    crb_pos : ndarray, shape (K,)
        Root of the posterior CRB of the position per frame (m), from :func:`crb_position`.
    plain : list of TrackingRun, optional
        The same runs without the collapse guard: adds the column ``"RMSE, no guard (m)"``.

    Returns
    -------
    DataFrame
        One row per method (indexed by its display label, :data:`fusion.book.style.METHOD_LABELS`, the naive
        product's ε one 1 per node of the study) plus ``"posterior CRB (floor)"``;
        columns ``"RMSE from frame 5 (m)"`` (root of the squared position error averaged over runs
        and frames 5-K; for the CRB the root mean square of ``crb_pos`` over the same frames),
        ``"RMSE, no guard (m)"`` (with ``plain``), ``"NEES, frames 1-4"`` and ``"mean NEES (4-D), frames 5-K"`` (K the
        study's last frame, 30 in the chapter; ``"frame 5"`` when K = 5; NaN for the mean of local means, which has
        no covariance, and for the CRB row; NaN, shown "—", also for a
        method whose covariance is singular to working precision in some run and frame of the window, where its
        NEES is undefined: the other columns and methods keep their values); 2 decimals.

    Raises
    ------
    TypeError
        ``runs`` or ``plain`` not a sequence of TrackingRun.
    ValueError
        ``runs`` is empty, of several scenarios or holds a run twice, not a study the table shows (fewer than 5
        frames, more than 3 nodes, or computed with ``RangeBearingScenario.variants=False``), ``plain`` not the same
        runs (as many, of the same scenario and truths: another seed's runs are refused), or ``crb_pos``
        not finite and non-negative with one entry per frame.
    """
    runs = _check_study(runs, window=True, nodes=True, variants=True)
    if plain is not None:
        plain = _check_study(plain, name="plain", like=runs, variants=True)
    crb_pos = _check_crb(crb_pos, runs)
    n_nodes, late_nees = int(np.shape(runs[0].gm_loglik)[-1]), _late_nees(int(np.shape(runs[0].truth)[0]))
    rows = {}
    for key in METHODS:
        label = _row_label(key, n_nodes)
        if key not in runs[0].estimates:  # a reading not computed (RangeBearingScenario.readings)
            continue
        has_cov = key != "mean_of_local_means"
        rows[label] = {RMSE_LATE: np.sqrt(position_sq_errors(runs, key)[:, LATE].mean())}
        if plain is not None:
            rows[label]["RMSE, no guard (m)"] = np.sqrt(position_sq_errors(plain, key)[:, LATE].mean())
        nees_k = _defined_nees(runs, key) if has_cov else None
        rows[label]["NEES, frames 1-4"] = nees_k[:, EARLY].mean() if nees_k is not None else np.nan
        rows[label][late_nees] = nees_k[:, LATE].mean() if nees_k is not None else np.nan
    rows[CRB_ROW] = {k: np.nan for k in next(iter(rows.values()))}
    rows[CRB_ROW][RMSE_LATE] = np.sqrt(np.mean(crb_pos[LATE] ** 2))
    return pd.DataFrame(rows).T.round(2)


#: The NEES column :func:`table_values` reads at the chapter's 30 frames, and the methods whose NEES it glues.
_NEES_LATE = "mean NEES (4-D), frames 5-30"
_NEES_KEYS = ("naive_product", "chernoff_pso", "ci_gaussian", "centralised_pf", "local1", "first_order_uniform")


def _late_nees(k: int) -> str:
    """:func:`method_table`'s column of the mean NEES over :data:`LATE` for runs of ``k`` frames, named by the
    study's frames (fuzz 27b D3: "frames 5-30" whatever the study): ``_NEES_LATE`` at the chapter's 30."""
    first = LATE.start + 1
    return f"mean NEES (4-D), frames {first}-{k}" if k > first else f"mean NEES (4-D), frame {first}"


def _row_label(key: str, n_nodes: int) -> str:
    """:func:`method_table`'s row of the method ``key`` in a study of ``n_nodes`` nodes: its
    :data:`~fusion.book.style.METHOD_LABELS` label, the naive product's exponents one per node (fuzz 27b D3:
    "ε = (1, 1, 1)" whatever the study; the label itself at the chapter's 3 nodes)."""
    if key == "naive_product":
        return f"naive product, ε = ({', '.join(['1'] * n_nodes)})"
    return METHOD_LABELS[key]


def table_values(table: pd.DataFrame) -> GlueValues:
    """Glue values read from :func:`method_table`: ``chf_rmse_<key>``, ``chf_nees_<key>``, ratios.

    Parameters
    ----------
    table : DataFrame
        The table of :func:`method_table` (rows labelled by :data:`fusion.book.style.METHOD_LABELS` plus the CRB row;
        the naive product's row and the late NEES column named by the study's nodes and frames, as it names them).

    Returns
    -------
    dict of str to float
        ``chf_rmse_<key>`` for every key of ``METHODS`` and ``chf_rmse_crb`` (m);
        ``chf_ratio_local`` (RMSE of local PF 1 / RMSE of Chernoff-PSO; ``chf_ratio_local_min`` the smallest such
        ratio over the local filters); ``chf_pct_central`` (how
        much larger, in %, Chernoff-PSO's RMSE is than the centralised filter's);
        ``chf_nees_<key>`` for the naive product, Chernoff-PSO, CI of Gaussians, the centralised
        filter and local PF 1, and ``chf_nees_first_order`` (first-order mixture at uniform ε); 4 decimals.

    Raises
    ------
    TypeError
        ``table`` not a DataFrame.
    ValueError
        ``table`` lacks a row or column of :func:`method_table` that it reads, holds one twice, or a cell read is not
        a finite positive number (an RMSE or a NEES: 0 or a negative one is impossible for a noisy filter).
    """
    # the study's NEES column and naive row (method_table names them by its frames and nodes: _late_nees, _row_label)
    late = next((c for c in (table.columns if isinstance(table, pd.DataFrame) else ())
                 if isinstance(c, str) and c.startswith("mean NEES (4-D), frame")), _NEES_LATE)
    _frame(table, "table", (RMSE_LATE, late), maker="method_table")
    n_nodes = sum(METHOD_LABELS[k] in table.index for k in METHODS if k.startswith("local"))

    def label(key: str) -> str:
        return _row_label(key, n_nodes)
    rows = [CRB_ROW, *(label(k) for k in ("chernoff_pso", "centralised_pf", "local1", *_NEES_KEYS))]
    missing = [r for r in rows if r not in table.index]
    if missing:
        raise ValueError(f"table lacks the rows {missing} (a result of method_table holds them)")

    def t(key: str, col: str = RMSE_LATE) -> float:
        return _cell_number(table, label(key), col, "table", positive=True)
    v: dict[str, float] = {f"chf_rmse_{k}": rounded(t(k)) for k in METHODS if label(k) in table.index}
    v["chf_rmse_crb"] = rounded(_cell_number(table, CRB_ROW, RMSE_LATE, "table", positive=True))
    v["chf_ratio_local"] = rounded(t("local1") / t("chernoff_pso"))
    v["chf_ratio_local_min"] = rounded(min(t(k) for k in METHODS if k.startswith("local") and METHOD_LABELS[k] in table.index)
                                       / t("chernoff_pso"))
    v["chf_pct_central"] = rounded(100 * (t("chernoff_pso") / t("centralised_pf") - 1))
    for k in _NEES_KEYS:
        v[f"chf_nees_{k}"] = rounded(t(k, late))
    v["chf_nees_first_order"] = v.pop("chf_nees_first_order_uniform")
    return v


_STYLE = {
    "local1": ("#999999", "-"), "local2": ("#999999", "--"), "local3": ("#999999", ":"),
    "mean_of_local_means": ("#E69F00", "-"), "naive_product": ("#CC79A7", "--"), "ci_gaussian": ("#009E73", "-"),
    "chernoff_uniform": ("#56B4E9", "-"), "chernoff_pso": ("#0072B2", "-"), "centralised_pf": ("#000000", "-"),
}


def rmse_figure(runs: list[TrackingRun], crb_pos: FloatArray) -> Figure:
    """Figure ``fig-chf-rmse``: position RMSE over runs against frame, log scale (the bound is compared in the text).

    Parameters
    ----------
    runs : list of TrackingRun
        The Monte-Carlo runs.
    crb_pos : ndarray, shape (K,)
        Root of the posterior CRB of the position per frame (m), from :func:`crb_position`; its
        length sets the frames shown (1..K).

    Returns
    -------
    Figure
        One panel: RMSE over runs (m, log scale) against frame for the local filters, the mean of
        local means, the naive product, CI, Chernoff with uniform and optimised exponents, the
        centralised filter (the CRB is not drawn: Monte-Carlo error lets the centralised RMSE dip below it at
        some frames; see :func:`review_values`). The figure is closed (not shown by pyplot).

    Raises
    ------
    TypeError
        ``runs`` not a sequence of TrackingRun.
    ValueError
        ``runs`` is empty, of several scenarios or holds a run twice, or ``crb_pos`` not finite and non-negative with
        one entry per frame, ``runs`` of more than 3 nodes (not a study the chapter's tables show).
    """
    runs = _check_study(runs, nodes=True)
    crb_pos = _check_crb(crb_pos, runs)
    frames = np.arange(1, crb_pos.size + 1)
    fig, ax = new_figure(figsize=(7.5, 4.8))
    for key, (c, ls) in _STYLE.items():
        if key not in runs[0].estimates:  # a node the runs do not have (fewer than 3 sensors): every node is drawn
            continue
        rmse = np.sqrt(position_sq_errors(runs, key).mean(axis=0))
        ax.plot(frames, rmse, color=c, ls=ls, lw=2.0 if key == "chernoff_pso" else 1.2, label=METHOD_LABELS[key])
    # the posterior CRB is not drawn: with 100 runs the centralised filter's RMSE falls below it at some
    # frames (Monte-Carlo error); the chapter compares the two with an interval instead (review_values)
    ax.set(xlabel="frame", ylabel="position RMSE (m)", yscale="log")
    ax.legend(ncol=2, loc="upper center", bbox_to_anchor=(0.5, -0.18))
    plt.close(fig)
    return fig


def per_run_mse(runs: list[TrackingRun], key: str) -> FloatArray:
    r"""Mean squared position error of one method over frames 5-K, per run.

    Parameters
    ----------
    runs : list of TrackingRun
        The Monte-Carlo runs.
    key : str
        A key of :data:`~fusion.scenarios.range_bearing.METHODS`.

    Returns
    -------
    ndarray, shape (runs,)
        :math:`(\hat x - x)^2 + (\hat y - y)^2` averaged over frames 5-K (:data:`LATE`), m²,
        rounded to :math:`10^{-4}` m²: some estimates (those reached through BLAS products, such as the
        quadratic-feature densities of the mixtures) move in their last digits with the BLAS kernel, and
        the paired differences of the claims ledger must not.
        One entry per run of ``runs``, in its order (a run given twice gives its entry twice).

    Raises
    ------
    ValueError
        ``key`` is not a key of ``METHODS``, or ``runs`` is empty or of fewer than 5 frames (no frame of
        :data:`LATE`).
    """
    _check_window(_check_runs(runs, True))  # no NaN average of an empty window (fuzz 26b FW1), as per_run_nees
    return np.round(position_sq_errors(runs, key)[:, LATE].mean(axis=1), 4)


@study_defaults("runs", "frames")  # a default the study does not fit, named by the study (fuzz 36b D1)
def per_run_nees(runs: list[TrackingRun], key: str, frames: slice = LATE) -> FloatArray:
    """Mean NEES (4-D) of one method over a window of frames, per run.

    Parameters
    ----------
    runs : list of TrackingRun
        The Monte-Carlo runs.
    key : str
        A key of :data:`~fusion.scenarios.range_bearing.METHODS` other than ``"mean_of_local_means"``
        (which has no covariance).
    frames : slice
        The window (0-based): :data:`LATE` (frames 5-K, default), :data:`EARLY` (1-4) or :data:`ALL_FRAMES`.

    Returns
    -------
    ndarray, shape (runs,)
        Normalised estimation error squared of the 4-D state averaged over the window, dimensionless; 4 on
        average for a consistent estimator; rounded to 10⁻⁴ (see :func:`per_run_mse`). One entry per run of
        ``runs``, in its order.

    Raises
    ------
    TypeError
        ``frames`` not a slice.
    ValueError
        ``key`` is not a method with a covariance, ``runs`` is empty, ``frames`` of step 0 or selecting no frame,
        or the method's covariance is singular to working precision in a run and frame of the window (its NEES is
        undefined there, as :func:`method_table` shows it).
    """
    return _window_nees(runs, key, frames)


def _window_nees(runs: list[TrackingRun], key: str, frames: slice, name: str = "runs",
                 method: str = "key") -> FloatArray:
    """:func:`per_run_nees`: the NEES of :func:`_defined_nees` (method_table's rule: undefined where the covariance
    is singular to working precision) averaged over ``frames``; where it is undefined in the window a per-run mean
    has no value, so ValueError naming ``name`` (the runs), ``method`` (the argument holding ``key``), the run and
    the frame (fuzz 27b B3: per_run_nees and ev_tracking raised the NEES's own "covariances must be positive
    definite")."""
    nees = _defined_nees(runs, key)
    frame_slice(frames, "frames", nees.shape[1])
    window = nees[:, frames]
    bad = np.argwhere(np.isnan(window))
    if bad.size:
        j, i = (int(x) for x in bad[0])
        k = range(nees.shape[1])[frames][i]
        raise ValueError(f"{name}[{j}]: the covariance of {method} = {shown(key)} is singular to working precision at "
                         f"frame {k + 1}, so its NEES is undefined there ({len(bad)} run-frames of the window; "
                         "method_table shows '—'): no per-run mean NEES over the window")
    return np.round(window.mean(axis=1), 4)  # see per_run_mse


def gain_values(runs: list[TrackingRun]) -> GlueValues:
    """Paired per-run MSE differences (m²): mean and standard error, as glue values.

    The ledger's 95 % intervals are in :func:`ledger_values`.

    Parameters
    ----------
    runs : list of TrackingRun
        The Monte-Carlo runs (same seeds for every method, so the differences are paired).

    Returns
    -------
    dict
        ``chf_gain_uni`` (patent minus uniform exponents), ``chf_gain_ci`` (patent minus CI of
        Gaussians), ``chf_gain_prev`` (ε⁽⁰⁾ = previous ε* minus patent): means over runs of the
        per-run MSE difference (frames 5-K, m², 4 decimals; negative means the first is more
        accurate), each with ``_se`` (standard error, ``ddof=1``; left out for a single run, which has
        none); ``chf_n_worse_uni`` (int: runs in which the patent's method has the larger MSE
        than uniform exponents).

    Raises
    ------
    TypeError
        ``runs`` not a sequence of TrackingRun.
    ValueError
        ``runs`` is empty, of several scenarios or holds a run twice, ``runs`` of fewer than 5 frames (no frame of
        LATE) or computed with ``RangeBearingScenario.variants=False`` (not a study the chapter's tables show).
    """
    runs = _check_study(runs, window=True, variants=True)
    mse = {k: per_run_mse(runs, k) for k in ("chernoff_pso", "chernoff_uniform", "ci_gaussian", "chernoff_prev")}
    diffs = {"uni": mse["chernoff_pso"] - mse["chernoff_uniform"], "ci": mse["chernoff_pso"] - mse["ci_gaussian"],
             "prev": mse["chernoff_prev"] - mse["chernoff_pso"]}
    v: dict[str, Any] = {}
    for name, d in diffs.items():
        v[f"chf_gain_{name}"] = rounded(float(d.mean()))
        if d.size > 1:  # one run has no standard error: no value rather than a NaN (fuzz 26b R1c)
            v[f"chf_gain_{name}_se"] = rounded(float(d.std(ddof=1) / np.sqrt(d.size)))
    v["chf_n_worse_uni"] = int(np.sum(diffs["uni"] > 0))
    return v


def collapsed(runs: list[TrackingRun], n_particles: int) -> np.ndarray:
    """Runs in which some node's particle filter collapses.

    A run is collapsed when, at some frame, some node keeps fewer than
    :data:`COLLAPSE_FRACTION` × ``n_particles`` effective particles.

    Parameters
    ----------
    runs : list of TrackingRun
        The Monte-Carlo runs (their ``ess["local"]``, shape (K, N), is used).
    n_particles : int
        Particles of each node's filter (``RangeBearingScenario.n_particles``).

    Returns
    -------
    ndarray of bool, shape (runs,)
        True for a collapsed run; empty for no runs.

    Raises
    ------
    TypeError
        ``runs`` not a sequence of TrackingRun, ``n_particles`` not an integer.
    ValueError
        ``runs`` of several scenarios, ``n_particles`` below 1 or not the runs' ``RangeBearingScenario.n_particles``.
    """
    runs = _check_runs(runs, False)
    n_particles = _check_size(runs, n_particles, "n_particles", "n_particles")
    return min_local_ess(runs) < COLLAPSE_FRACTION * n_particles


def central_collapsed(runs: list[TrackingRun], n_central: int) -> np.ndarray:
    """Runs in which the centralised filter collapses (fewer than :data:`COLLAPSE_FRACTION` × ``n_central``
    effective particles at some frame).

    Parameters
    ----------
    runs : list of TrackingRun
        The Monte-Carlo runs (their ``ess["centralised_pf"]``, shape (K,)).
    n_central : int
        Particles of the centralised filter (``RangeBearingScenario.n_central``).

    Returns
    -------
    ndarray of bool, shape (runs,)
        True for a run whose centralised filter's effective sample size falls below the threshold at some frame;
        empty for no runs.

    Raises
    ------
    TypeError
        ``n_central`` not an integer, or ``runs`` not a sequence of TrackingRun.
    ValueError
        ``n_central`` below 1 or other than the ``n_central`` of the runs' recorded scenario, or ``runs`` of
        several scenarios.
    """
    runs = _check_runs(runs, False)
    n_central = _check_size(runs, n_central, "n_central", "n_central")
    return np.array([float(np.min(r.ess["centralised_pf"])) < COLLAPSE_FRACTION * n_central for r in runs], dtype=bool)


def any_collapsed(runs: list[TrackingRun], sc: RangeBearingScenario) -> np.ndarray:
    """Runs in which some node's filter (:func:`collapsed`) or the centralised filter (:func:`central_collapsed`) collapses.

    Parameters
    ----------
    runs : list of TrackingRun
    sc : RangeBearingScenario
        Its ``n_particles`` and ``n_central`` set the thresholds.

    Returns
    -------
    ndarray of bool, shape (runs,)
        True for a run in which a node's filter or the centralised filter collapses at some frame.

    Raises
    ------
    TypeError
        ``runs`` not a sequence of TrackingRun, ``sc`` not a RangeBearingScenario.
    ValueError
        ``runs`` is empty, of several scenarios or holds a run twice, or ``sc`` is not the runs' scenario.
    """
    runs = _check_study(runs, sc)
    return collapsed(runs, sc.n_particles) | central_collapsed(runs, sc.n_central)


def typical_run(runs: list[TrackingRun], n_particles: int, n_central: int | None = None) -> int:
    """Index of the first run in which no filter collapses (the run the chapter's figures show).

    Parameters
    ----------
    runs : list of TrackingRun
    n_particles : int
        Particles per node (sets the collapse threshold of :func:`collapsed`).
    n_central : int, optional
        Particles of the centralised filter; when given, its collapse (:func:`central_collapsed`) counts too.

    Returns
    -------
    int
        0-based index; 0 when every run collapses.

    Raises
    ------
    TypeError
        ``runs`` not a sequence of TrackingRun, ``n_particles`` or ``n_central`` not an integer.
    ValueError
        ``runs`` is empty, of several scenarios or holds a run twice, ``n_particles`` or ``n_central`` not the runs' own.
    """
    runs = _check_study(runs)
    bad = collapsed(runs, n_particles)
    if n_central is not None:
        bad = bad | central_collapsed(runs, n_central)
    return int(np.argmin(bad)) if not np.all(bad) else 0


def collapse_values(plain: list[TrackingRun], sc: RangeBearingScenario) -> GlueValues:
    """Where the filters collapse without the guard, and what the collapsed runs do to the study.

    Parameters
    ----------
    plain : list of TrackingRun
        The runs without collapse guard (``monte_carlo(sc, ...)``).
    sc : RangeBearingScenario
        The scenario; its ``n_particles`` and ``n_central`` set the collapse thresholds.

    Returns
    -------
    dict
        Glue values: ``chf_n_collapsed`` (runs in which some node collapses), ``chf_n_central_collapsed`` (runs in
        which the centralised filter collapses), ``chf_n_both_collapsed`` (both in the same run),
        ``chf_n_any_collapsed`` and ``chf_runs_kept`` (int counts); ``chf_collapse_text`` (every node collapse:
        run, node, frame and effective particles, in words) and ``chf_collapse_late`` (int, those after frame 1;
        ``chf_collapse_late_text`` in words, with run and frame); ``chf_ess_next`` (smallest ESS of any node in the
        runs kept, effective particles, 0 decimals); ``chf_central_ess_min`` (smallest ESS of the centralised
        filter, 1 decimal) and ``chf_central_ess_next`` (its smallest in the runs kept, 0 decimals);
        ``chf_rmse_chernoff_pso_plain``, ``chf_rmse_centralised_plain`` and their ``_kept`` versions (position
        RMSE, frames 5-K, m), ``chf_pct_central_plain`` / ``_kept`` (how much larger, in %, the patent's RMSE is
        than the centralised filter's), ``chf_nees_naive_plain`` / ``_kept`` (naive product's mean NEES over
        every frame) and ``chf_nees_naive_plain_max`` (its largest per-run mean, 0 decimals). 4 decimals unless
        stated.

    Raises
    ------
    TypeError
        ``plain`` not a sequence of TrackingRun, ``sc`` not a RangeBearingScenario.
    ValueError
        ``plain`` is empty, of several scenarios or holds a run twice, ``sc`` is not its scenario, every run of
        ``plain`` collapses (no run is kept), or ``plain`` has fewer than 5 frames (no frame of LATE: not a study the
        chapter's tables show).
    """
    plain = _check_study(plain, sc, name="plain", window=True)
    bad, cbad = collapsed(plain, sc.n_particles), central_collapsed(plain, sc.n_central)
    anyb = bad | cbad
    keep = [r for r, b in zip(plain, anyb) if not b]
    if not keep:
        raise ValueError(f"plain: every one of its {len(plain)} runs collapses (a node below "  # fuzz 26b D7: named
                         f"{COLLAPSE_FRACTION} x sc.n_particles or the centralised filter below {COLLAPSE_FRACTION} x "
                         "sc.n_central effective particles), so no run is kept to compare")
    events, late, late_at = [], 0, []
    for j in np.flatnonzero(bad):
        ess = plain[j].ess["local"]
        for k, i in zip(*np.nonzero(ess < COLLAPSE_FRACTION * sc.n_particles)):
            events.append(f"run {j + 1}, node {i + 1}, frame {k + 1}: {ess[k, i]:.1f}")
            late += int(k > 0)
            if k > 0:
                late_at.append(f"run {j + 1}, frame {k + 1}")
    words = {0: "no node collapse comes", 1: "one node collapse comes"}
    late_text = (words.get(late, f"{late} node collapses come") + " later"
                 + (f" ({'; '.join(late_at)})" if late_at else ""))
    v: dict[str, Any] = {"chf_n_collapsed": int(bad.sum()), "chf_n_central_collapsed": int(cbad.sum()),
                         "chf_n_both_collapsed": int((bad & cbad).sum()), "chf_n_any_collapsed": int(anyb.sum()),
                         "chf_runs_kept": len(keep), "chf_collapse_text": "; ".join(events) if events else "none",
                         "chf_collapse_late": late, "chf_collapse_late_text": late_text,
                         "chf_ess_next": rounded(float(np.min(min_local_ess(keep))), 0),
                         "chf_central_ess_min": rounded(float(min(np.min(r.ess["centralised_pf"]) for r in plain)), 1),
                         "chf_central_ess_next": rounded(float(min(np.min(r.ess["centralised_pf"]) for r in keep)), 0)}

    def rmse(rs: list[TrackingRun], key: str) -> float:
        return float(np.sqrt(position_sq_errors(rs, key)[:, LATE].mean()))
    for tag, rs in (("plain", plain), ("kept", keep)):
        v[f"chf_rmse_chernoff_pso_{tag}"] = rounded(rmse(rs, "chernoff_pso"))
        v[f"chf_rmse_centralised_{tag}"] = rounded(rmse(rs, "centralised_pf"))
        v[f"chf_pct_central_{tag}"] = rounded(100 * (rmse(rs, "chernoff_pso") / rmse(rs, "centralised_pf") - 1))
        v[f"chf_nees_naive_{tag}"] = rounded(float(nees_per_frame(rs, "naive_product").mean()))
    v["chf_nees_naive_plain_max"] = rounded(float(np.max(nees_per_frame(plain, "naive_product").mean(axis=1))), 0)
    return v


def readings_values(runs: list[TrackingRun]) -> GlueValues:
    """Glue values of the readings of steps D and F (``readings=True``): ``chf_rd_*`` (4 decimals unless stated).

    Parameters
    ----------
    runs : list of TrackingRun
        The study's runs.

    Returns
    -------
    dict
        ``chf_rd_first_order_eps_diff`` (mean absolute difference of the exponents argmin Z_FO from uniform),
        ``chf_rd_kl_frames`` (int, frames where the equal-KL rule has a solution in the simplex),
        ``chf_rd_frames`` (int, all frames), ``chf_rd_kl_gap`` (largest absolute difference of its exponents
        from SLSQP's minimum of Ĵ on the same samples, where it has one), ``chf_rd_boundary`` (int, frames where
        SLSQP's minimum has an exponent below 1e-6).

    Raises
    ------
    TypeError
        ``runs`` not a sequence of TrackingRun.
    ValueError
        ``runs`` is empty, of several scenarios, holds a run twice, or is without the readings (``readings=False``),
        ``runs`` computed with ``RangeBearingScenario.variants=False`` (not a study the chapter's tables show).
    """
    runs = _check_study(runs, readings=True, variants=True)
    first_order = np.stack([r.eps["first_order"] for r in runs])
    kl = np.stack([r.eps["equal_kl"] for r in runs])
    sl = np.stack([r.eps["slsqp"] for r in runs])
    ok = np.all(np.isfinite(kl), axis=2)
    return {"chf_rd_first_order_eps_diff": rounded(float(np.mean(np.abs(first_order - 1.0 / first_order.shape[2])))),
            "chf_rd_kl_frames": int(ok.sum()), "chf_rd_frames": int(ok.size),
            "chf_rd_kl_gap": float(f"{np.max(np.abs(kl[ok] - sl[ok])) if ok.any() else float('nan'):.1e}"),
            "chf_rd_boundary": int(np.sum(np.min(sl, axis=2) < 1e-6))}


def equal_kl_g_values(runs: list[TrackingRun]) -> GlueValues:
    """Glue values of the equal-KL rule applied to the first-order mixture g (``eps["equal_kl_g"]``): ``chf_klg_*``.

    Parameters
    ----------
    runs : list of TrackingRun
        The study's runs (``readings=True``).

    Returns
    -------
    dict
        ``chf_klg_frames`` (int, frames where the rule on g has a solution in the simplex), ``chf_klg_all`` (int,
        all frames), ``chf_klg_equal`` (int, of those, frames within ``chf_klg_tol`` of SLSQP's minimum of Ĵ in
        every exponent; ``chf_klg_tol`` is the primary's agreement, ``chf_rd_kl_gap`` of :func:`readings_values`:
        how closely SLSQP reproduces an exact solution), ``chf_klg_gap_max``, ``chf_klg_gap_median`` (largest and median over those frames of
        the largest absolute exponent difference from SLSQP's minimum; 4 decimals; NaN when no frame has a
        solution).

    Raises
    ------
    TypeError
        A run that is not a TrackingRun, or ``runs`` not a sequence.
    ValueError
        ``runs`` holds no run, a run twice, runs of several scenarios, or runs of a scenario without ``readings``
        (their ``eps`` has no ``equal_kl_g``), ``runs`` computed with ``RangeBearingScenario.variants=False`` (not a
        study the chapter's tables show).
    """
    runs = _check_study(runs, readings=True, variants=True)
    klg = np.stack([r.eps["equal_kl_g"] for r in runs])
    sl = np.stack([r.eps["slsqp"] for r in runs])
    ok = np.all(np.isfinite(klg), axis=2)
    gap = np.max(np.abs(klg - sl), axis=2)[ok]
    tol = readings_values(runs)["chf_rd_kl_gap"]
    return {"chf_klg_frames": int(ok.sum()), "chf_klg_all": int(ok.size), "chf_klg_tol": tol,
            "chf_klg_equal": int(np.sum(gap <= tol)),
            "chf_klg_gap_max": rounded(float(np.max(gap))) if gap.size else float("nan"),
            "chf_klg_gap_median": rounded(float(np.median(gap))) if gap.size else float("nan")}

