"""The source's tracking case (Fig. 3, Figs. 4 and 7): RMSE tables and figures, the straight-leg floor and the eq. 13
slip.
"""

from __future__ import annotations

import inspect
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import pandas as pd
from matplotlib.figure import Figure
from numpy.typing import ArrayLike

from fusion._results import ResultSpec, array, dict_of, mask, number, validated_post_init
from fusion._frozen import constant
from fusion import data
from fusion._docstrings import reads_results
from fusion._counts import distinct, sequence
from fusion._limits import LOOP_STEP, work
from fusion._validation import (as_array, count, distinct_printed, general, given_number, record, scalar, std_scalar,
                               instance_of)
from fusion.book.style import METHOD_LABELS, color, new_figure
from fusion.book.tables import rounded
from fusion.book.glue import GlueValues
from fusion.estimates.fuzzy_cluster import fuzzy_cluster_fusion
from fusion.filtering.kalman import rmse_per_step
from fusion.filtering.tracks import fuse_tracks
from fusion.scenarios import two_sensor
from fusion.scenarios.two_sensor import FusionStudy, Scenario, StudyMethod
from fusion.scenarios.two_sensor.study import OVER_STEPS, RUN_AVERAGED
from fusion.book.chapters.ci.constants import IMP, W_GRID, W_PUB, claim_file
from fusion.book.chapters.ci.text import _glue_doc
from fusion.book.chapters.ci.checks import (_every_method, _entries, _exact_keys, _frame, _counted, _leg_of,
                                           _per_step, _steps, _study_of)
from fusion._counts import index
from fusion._structures import mapping_of
from fusion._structures import same_keys
from fusion._shown import shown
from fusion.book.chapters._defaults import study_defaults

__all__ = ["published_numbers", "rmse_numbers", "fig3", "figure_rows", "rmse_table", "rmse_figure", "slip_table",
           "slip_numbers", "slip_band", "CAUSAL_FLOOR_LABEL", "IDENTICAL_LABEL", "ANISO_LABEL", "ANISO_R",
           "StraightLeg", "straight_leg", "variants_table", "variant_numbers", "slip_all", "slip_at_weights",
           "slip_pair_band", "path_noise_limit", "margin_numbers", "baseline_slip_numbers", "fuzzy_levels",
           "LegClaimInputs"]


@reads_results("sc")
def fig3(sc: Scenario, run: int = 0) -> Figure:
    """The source's Fig. 3 on our reading: the true path and one run of sensor 1's measurements (m).

    Parameters
    ----------
    sc : Scenario
        Output of :func:`fusion.scenarios.two_sensor.two_sensor_scenario`.
    run : int
        Run whose measurements are drawn (0-based).

    Returns
    -------
    matplotlib.figure.Figure
        One panel, y against x (m): the true path as a line and sensor 1's measurements of run ``run`` as dots.

    Raises
    ------
    TypeError
        ``sc`` not a Scenario, ``run`` not an integer.
    ValueError
        ``run`` not a run of ``sc``.
    """
    instance_of(sc, Scenario, "sc")
    run = index(run, "run", sc.tracks[0].z.shape[0])
    fig, ax = new_figure(figsize=(6.0, 5.0))
    ax.plot(sc.truth[:, 0], sc.truth[:, 2], "-", color=color("truth"), lw=1.5, label="true path")
    z = sc.tracks[0].z
    ax.plot(z[run, :, 0], z[run, :, 1], ".", color=color(StudyMethod.SENSOR_1), ms=2, alpha=0.5,
            label=f"sensor 1 (run {run + 1})")
    ax.set(xlabel="x (m)", ylabel="y (m)", xlim=(-500, 4000), ylim=(-500, 12500), aspect="equal")
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0))
    return fig


def figure_rows() -> dict[str, list[tuple[StudyMethod, str, float]]]:
    """The curves of the source's Figs. 4, 6, 7 and 8: (our method's key, the source's name, published RMSE in m).

    Returns
    -------
    dict of str to list of (StudyMethod, str, float)
        Keyed by figure; the published RMSE is NaN where the source quotes none.
    """
    pub = data.WANG2024_RMSE.columns
    M = StudyMethod
    return {
        "Fig. 4": [(M.CI, "CI without convex part", pub["ci"][0]), (M.SPLIT_CI, "CI with convex part", pub["ci_convex"][0])],
        "Fig. 6": [(M.CI_GRID, "exhaustive search", pub["ci_grid"][0]), (M.CI_FRUIT_FLY, "FOA", pub["improved"][0])],
        "Fig. 7": [(M.RAW_1, "sensor 1 (its raw data, 实际数据)", np.nan), (M.RAW_2, "sensor 2 (its raw data)", np.nan),
                   (M.SENSOR_1, "— (sensor 1's local filter)", np.nan), (M.SENSOR_2, "— (sensor 2's local filter)", np.nan),
                   (M.CI, "before improvement", pub["ci"][0]), (M.SPLIT_CI, "improved CI", pub["improved"][0])],
        "Fig. 8": [(M.CONVEX, "multi-Bayesian", pub["multi_bayes"][0]), (M.FUZZY, "fuzzy clustering", pub["fuzzy"][0]),
                   (M.CONVEX, "maximum likelihood", pub["max_likelihood"][0]),
                   (M.SPLIT_CI, "improved CI", pub["improved"][0])],
    }


#: Reader-facing names of the study's method keys in tables where they differ from :data:`METHOD_LABELS`.
#: Headers that :func:`rmse_table` and :func:`slip_table` both write (issue 36: named once): the source's name of a
#: curve, our method and the published RMSE.
SOURCE_METHOD = "source's method"
OUR_METHOD = "our method"
PUBLISHED_M = "published (m)"
_READABLE = {StudyMethod.CONVEX: "convex combination (eqs. 3-4)"}

#: Legend labels of the curves of :func:`rmse_figure` that are not fusion rules (registered figure labels).
_CURVE_LABELS = {StudyMethod.SENSOR_1: "sensor 1, local filter", StudyMethod.SENSOR_2: "sensor 2, local filter",
                 StudyMethod.RAW_1: "sensor 1, raw measurements"}


def _run_se(study: FusionStudy, method: str) -> float:
    """Monte-Carlo standard error of the mean per-run RMSE on x over the steady steps (m); NaN for raw measurements."""
    if method not in study.est:
        return float("nan")
    v = two_sensor.run_rmse(study.est[method], study.truth, study.steady, 0)
    return float(np.std(v, ddof=1) / np.sqrt(v.size))


@reads_results("study")
def rmse_table(study: FusionStudy, sc: Scenario | None = None) -> pd.DataFrame:
    r"""Published RMSE beside the steady-state RMSE of our method for every curve of :func:`figure_rows`.

    Parameters
    ----------
    study : FusionStudy
        From :func:`fusion.scenarios.two_sensor.fusion_study` with every method run.
    sc : Scenario, optional
        The study's scenario: when given, Fig. 6 also gets CI at the two weights Fig. 5 publishes, fixed
        (the ledger's primary reading of Fig. 6), on the same runs. A study of another scenario (other steps, truth or
        local tracks: another seed or runs) is refused, naming ``study`` and ``sc``.

    Returns
    -------
    pandas.DataFrame
        Indexed by (figure, the source's method); columns our method, published (m), reproduced (m,
        x: the coordinate the source's figures compare; mean over the steady steps of the RMSE per
        step), reproduced, y (m), the Monte-Carlo standard error of the mean per-run RMSE on x (m; the runs'
        spread over √runs), reproduced / published (on x). Rounded to 2 decimals, NaN where a
        figure prints no value (shown "—" by :func:`fusion.book.tables.highlight_mismatches`). A last row,
        ``("reference", ...)``, is the centralised Kalman filter, which the source does not run.

    Raises
    ------
    TypeError
        ``study`` not a FusionStudy.
    ValueError
        ``study`` lacks a rule (a weight left out of ``fusion_study``) or holds one run (no Monte-Carlo standard
        error); ``sc`` not the study's scenario.
    """
    _every_method(study, "rmse_table", min_runs=2)
    if sc is not None:
        _study_of(sc, study)
    rows = []
    pub = data.WANG2024_RMSE.columns
    for fig_name, entries in figure_rows().items():
        for method, label, published in entries:
            artefact = method in (StudyMethod.CI_FRUIT_FLY, StudyMethod.CI_GRID)
            rows.append({"figure": fig_name, SOURCE_METHOD: label,
                         OUR_METHOD: _READABLE.get(method, METHOD_LABELS[method]),
                         PUBLISHED_M: published, "reproduced (m)": study.steady_rmse(method, 0),
                         "reproduced, y (m)": study.steady_rmse(method, 2),
                         "Monte-Carlo s.e., x (m)": _run_se(study, method),
                         "note": ("weights of each search run at every step, set by a tie rule on a flat objective "
                                  "(the ledger's reading per-step-searches)" if artefact else "")})
        if fig_name == "Fig. 6" and sc is not None:
            for w, label, published in ((W_GRID, "exhaustive search, its published ω fixed", pub["ci_grid"][0]),
                                        (W_PUB, "FOA, its published ω fixed", pub["improved"][0])):
                est = fuse_tracks(*sc.tracks, "ci", omega=w).est
                per_step = [float(np.sqrt(np.mean((est[..., c] - study.truth[..., c]) ** 2, axis=0))[study.steady].mean())
                            for c in (0, 2)]
                v = two_sensor.run_rmse(est, study.truth, study.steady, 0)
                rows.append({"figure": fig_name, SOURCE_METHOD: label, OUR_METHOD: f"CI, ω = {w:g}",
                             PUBLISHED_M: published, "reproduced (m)": per_step[0], "reproduced, y (m)": per_step[1],
                             "Monte-Carlo s.e., x (m)": float(np.std(v, ddof=1) / np.sqrt(v.size)),
                             "note": "the ledger's primary reading of Fig. 6 ('将…最优解代入协方差交叉融合算法')"})
    rows.append({"figure": "reference", SOURCE_METHOD: "— (not in the source)",
                 OUR_METHOD: "centralised Kalman filter (both sensors' measurements)", PUBLISHED_M: np.nan,
                 "reproduced (m)": study.steady_rmse(StudyMethod.CENTRAL, 0),
                 "reproduced, y (m)": study.steady_rmse(StudyMethod.CENTRAL, 2),
                 "Monte-Carlo s.e., x (m)": _run_se(study, StudyMethod.CENTRAL), "note": ""})
    table = pd.DataFrame(rows).set_index(["figure", SOURCE_METHOD])
    table.insert(len(table.columns) - 1, "reproduced / published", table["reproduced (m)"] / table[PUBLISHED_M])
    return table.round(2)


@reads_results("study")
def slip_table(study: FusionStudy, sc: Scenario | None = None) -> pd.DataFrame:
    r"""Every published curve of source Figs. 4-8 under eq. 13 coded as :math:`\sqrt{\sum e^2}/n` (the 1/n outside the root).

    That statistic is the RMSE divided by :math:`\sqrt n`. With :math:`n` the steps of a run (all of them, as
    a program that does not cut a transient would use, or those after 20 s) or the runs of a step, it is set
    beside the published value and our RMSE (x).

    Parameters
    ----------
    study : FusionStudy
        From :func:`fusion.scenarios.two_sensor.fusion_study` with every method run.
    sc : Scenario, optional
        The study's scenario: with it, two rows more (figure ``"Fig. 6, published ω"``), plain CI at the two weights
        the source publishes (Fig. 5) and puts into CI (Fig. 6). A study of another scenario (other steps, truth or
        local tracks: another seed or runs) is refused, naming ``study`` and ``sc``.

    Returns
    -------
    pandas.DataFrame
        Indexed by (figure, the source's method), the curves with a published value; columns our method,
        published (m), RMSE (m; over runs per step, t ≥ 20 s), and the slip over all steps, over the steps
        after 20 s and over the runs (m, x). Rounded to 2 decimals.

    Raises
    ------
    TypeError
        ``study`` not a FusionStudy.
    ValueError
        ``study`` lacks a rule (a weight left out of ``fusion_study``); ``sc`` not the study's
        scenario.
    """
    _every_method(study, "slip_table")
    if sc is not None:
        _study_of(sc, study)
    every = np.ones(study.t.size, dtype=bool)
    rows = []
    pub = data.WANG2024_RMSE.columns
    entries_all = [(fig_name, method, label, published, study.est[method])
                   for fig_name, entries in figure_rows().items() for method, label, published in entries
                   if np.isfinite(published)]
    if sc is not None:
        a, b = sc.tracks
        entries_all += [("Fig. 6, published ω", f"CI, ω = {w:g}", label, p, fuse_tracks(a, b, "ci", omega=w).est)
                        for w, label, p in ((W_PUB, "FOA's optimum put into CI", pub["improved"][0]),
                                            (W_GRID, "exhaustive search's optimum put into CI", pub["ci_grid"][0]))]
    for fig_name, method, label, published, est in entries_all:
            v_all = two_sensor.rmse_variants(est, study.truth, every)
            v_st = two_sensor.rmse_variants(est, study.truth, study.steady)
            steady_x = float(np.mean(rmse_per_step(est - study.truth, np.zeros(study.truth.shape[-2:]))[study.steady, 0]))
            rows.append({"figure": fig_name, SOURCE_METHOD: label,
                         OUR_METHOD: _READABLE.get(method, METHOD_LABELS.get(method, method)),
                         PUBLISHED_M: published, "RMSE (m)": steady_x,
                         f"√Σe²/n, n = all {study.t.size} steps (m)": v_all[two_sensor.SLIP_STEPS][0],
                         f"√Σe²/n, n = {int(study.steady.sum())} steps after 20 s (m)": v_st[two_sensor.SLIP_STEPS][0],
                         f"√Σe²/n, n = {est.shape[0]} runs (m)": v_st[two_sensor.SLIP_RUNS][0]})
    return pd.DataFrame(rows).set_index(["figure", SOURCE_METHOD]).round(2)


@reads_results("study")
def rmse_figure(study: FusionStudy, on_leg: ArrayLike, floor: ArrayLike) -> Figure:
    """The source's Figs. 4, 6, 7 and 8 recomputed, one row each, x and y columns (log scale).

    Solid: RMSE per step over the runs; dotted, same colour: the value the source quotes for each of its
    curves (a curve of ours that stands for two of the source's, as the convex combination for both the
    multi-Bayesian and the maximum-likelihood baselines, carries both published lines); dashed: the floor on
    the straight legs for a causal estimator that knows where the legs are
    (:func:`fusion.scenarios.two_sensor.straight_leg_floor` with ``causal=True``: a reference for the causal
    filters, not a floor for them, since they are biased and use the path across the turns). Source Fig. 7's sensor curves are the sensors' raw data: sensor 1's measurements are
    drawn in grey (sensor 2's coincide with them), beside the two local filters. One legend under each row (a
    subfigure each, so that the legends do not squeeze the columns).

    Parameters
    ----------
    study : FusionStudy
        Output of :func:`fusion.scenarios.two_sensor.fusion_study` with its weights given (the published ω may be
        left out).
    on_leg, floor : array_like, shapes (K,) and (L,)
        The straight-leg steps of the study and the causal floor there (m), from
        :func:`fusion.scenarios.two_sensor.straight_leg_floor` at the study's period.

    Returns
    -------
    matplotlib.figure.Figure
        Four rows (source Figs. 4, 6, 7, 8), columns x and y: each method's RMSE per step (m, log scale), the published
        values, the causal floor.

    Raises
    ------
    TypeError
        ``study`` not a FusionStudy, ``on_leg`` not bools, ``floor`` not numeric.
    ValueError
        ``study`` lacks a rule (a weight left out of ``fusion_study``), ``on_leg`` not one bool per step of
        ``study``, ``floor`` not one finite non-negative number per step it
        selects.
    """
    _every_method(study, "rmse_figure")
    on_leg = _steps(on_leg, "on_leg", study.t.size)
    floor = _per_step(floor, "floor", int(on_leg.sum()), "straight-leg step of on_leg", nonnegative=True)
    full = np.full(study.t.size, np.nan)   # gaps in the turns, for the plot only
    full[on_leg] = floor
    fig, _ = new_figure(figsize=(7.5, 13.0))
    fig.delaxes(_)
    rows = fig.subfigures(4, 1, height_ratios=[1.0, 1.0, 1.15, 1.0])
    for sub, (fig_name, entries) in zip(rows, figure_rows().items()):
        axes = sub.subplots(1, 2, sharey=True)
        for ax, comp, lab in zip(axes, (0, 2), ("x", "y")):
            drawn: list[str] = []
            for method, _label, published in entries:
                colour = "0.6" if method == StudyMethod.RAW_1 else color(method)
                if method != StudyMethod.RAW_2 and method not in drawn:   # sensor 2's data lie on sensor 1's
                    ax.plot(study.t, study.curve(method, comp), lw=1.0, color=colour,
                            label=_CURVE_LABELS.get(method, METHOD_LABELS[method]))
                    drawn.append(method)
                if np.isfinite(published):   # every published value, also a second one on a shared curve
                    ax.axhline(published, color=colour, lw=1.0, ls=":")
            ax.plot(study.t, full, "--", color=color("floor"), lw=1.0, label=CAUSAL_FLOOR_LABEL)
            ax.set(title=f"source {fig_name}: RMSE on {lab}", yscale="log", ylim=(2, 400), xlabel="time (s)")
        axes[0].set_ylabel("RMSE (m)")
        handles, labels = axes[0].get_legend_handles_labels()
        sub.legend(handles, labels, loc="outside lower center", ncols=3 if len(labels) > 4 else 2, fontsize=9)
    return fig


#: Legend label of the causal straight-leg floor (registered in :data:`fusion.book.style.FIGURE_LABELS`).
CAUSAL_FLOOR_LABEL = "floor: causal straight-leg least squares"


#: Units of a level's step of :func:`fuzzy_levels` (a ``fuzzy_cluster_fusion`` call on every run at once): twice the
#: 0.65 ms measured (0.167 CPU-s for one level of one run's 261 steps, 0.864 for five; ``time.process_time``, minimum
#: of 2, ``OPENBLAS_NUM_THREADS=1``, the machine shared and loaded; book audit 76).
_FUZZY_STEP = 130 * LOOP_STEP
#: Units of a level's step of :func:`fuzzy_levels` per run: twice the 1.5 us measured (0.93 CPU-s for one level of
#: 2,000 runs of 261 steps, against 0.16 for 50 runs; book audit 76).
_FUZZY_RUN_STEP = 300


@study_defaults("sc", "t_steady")  # a default the study does not fit, named by the study (fuzz 36b D1)
@reads_results("sc")
def fuzzy_levels(sc: Scenario, levels: ArrayLike, t_steady: float = 20.0) -> dict[float, np.ndarray]:
    """Per-run RMSE on x of fuzzy-clustering fusion of the two local tracks at each λ-cut level.

    Parameters
    ----------
    sc : Scenario
        The two-sensor runs (:func:`fusion.scenarios.two_sensor.two_sensor_scenario`).
    levels : array_like
        λ-cut levels in (0, 1) (the chapter's default is 0.01).
    t_steady : float
        Start of the averaging window (s).

    Returns
    -------
    dict of float to ndarray, shape (runs,)
        Rounded per-run RMSE (m), as :func:`fusion.scenarios.two_sensor.run_rmse`.

    Raises
    ------
    TypeError
        ``sc`` is not a :class:`~fusion.scenarios.two_sensor.Scenario`, or ``levels`` or ``t_steady`` not numeric.
    ValueError
        ``levels`` is empty, not a number or 1-D, holds an entry outside (0, 1) (named by its position) or repeats one
        to 6 significant digits (the result and the ledger's readings are keyed by level); ``t_steady`` is not
        finite, negative or after the last step; so many ``levels`` that their fusions of ``sc``'s steps and runs
        are beyond the work budget (``fusion._limits.MAX_WORK``), before any level is read.

    References
    ----------
    :func:`fusion.estimates.fuzzy_cluster.fuzzy_cluster_fusion`.
    """
    instance_of(sc, Scenario, "sc")
    from fusion.scenarios.two_sensor import run_rmse

    a, b = sc.tracks
    # rule 17, before any level is converted or checked (book audit 76: no budget; a level ran 0.65 ms a step, one
    # run, and 1.5 us more a run and step, so 100 levels of the chapter's 261 steps ran about 17 CPU-s, 10**5 levels
    # hours, and a 10**5-long list was checked entry by entry first)
    levels, n_levels = _counted(levels, "levels")   # read once, counted (fuzz 68b C2: an __array__ object counted one)
    work((n_levels, a.est.shape[1], _FUZZY_STEP + _FUZZY_RUN_STEP * a.est.shape[0]),
         "levels (with the steps and runs of sc)")
    Ps = np.stack([a.gains.P, b.gains.P], axis=1)
    X = np.stack([a.est, b.est], axis=2)
    lams = distinct_printed([scalar(lam, f"levels[{i}]", 0.0, 1.0, lo_open=True, hi_open=True)
                             for i, lam in enumerate(np.atleast_1d(as_array(levels, "levels", ndim=(0, 1))))],
                            "levels", general)   # the evidence keys each level's reading by f"{level:g}" (fuzz 30b B3)
    steady = sc.t >= scalar(t_steady, "t_steady", 0.0)
    if not steady.any():
        raise ValueError(f"t_steady = {shown(t_steady)} s is after the last step ({float(sc.t[-1]):g} s): "
                         "no step to average over")
    out = {}
    for lam in lams:
        est = np.stack([fuzzy_cluster_fusion(X[:, k], Ps[k], lam).x for k in range(sc.t.size)], axis=1)
        out[lam] = run_rmse(est, sc.truth, steady, 0)
    return out


#: Units of a weight's step of :func:`slip_at_weights` (a CI ``fuse_tracks`` step and its slip): twice the 0.35 ms
#: measured (0.166 CPU-s for two weights of one run's 261 steps, 1.95 for 20; 1.74 for two of 2,601 steps;
#: ``time.process_time``, minimum of 2, ``OPENBLAS_NUM_THREADS=1``, the machine shared and loaded; book audit 76).
_SLIP_STEP = 70 * LOOP_STEP
#: Units of a weight's step of :func:`slip_at_weights` per run: twice the 0.23 us measured (2.57 CPU-s for two weights
#: of 20,000 runs of 261 steps; book audit 76).
_SLIP_RUN_STEP = 46


@reads_results("sc", "study")
def slip_at_weights(sc: Scenario, study: FusionStudy, omegas: Sequence[float] = (W_PUB, W_GRID)
                    ) -> dict[float, tuple[float, float]]:
    r"""Plain CI at fixed weights (the source's published optima) under the slip :math:`\sqrt{\sum e^2}/n`, n = all steps.

    Parameters
    ----------
    sc : Scenario
        The chapter's scenario (its local tracks).
    study : FusionStudy
        :func:`fusion.scenarios.two_sensor.fusion_study` of ``sc`` (its truth and steps).
    omegas : sequence of float
        Weights in [0, 1].

    Returns
    -------
    dict
        Weight -> (x, y) slip (m), averaged over the runs.

    Raises
    ------
    TypeError
        ``sc`` or ``study`` of the wrong type, ``omegas`` not a sequence or an entry not a number.
    ValueError
        ``omegas`` empty, an entry outside [0, 1] or repeated to 6 significant digits (the result is keyed by
        weight); ``study`` not ``fusion_study`` of ``sc`` (its steps, truth or local tracks differ: another seed,
        runs or scenario); so many ``omegas`` that their fusions of ``sc``'s steps and runs are beyond the work budget
        (``fusion._limits.MAX_WORK``), before any weight is read.
    """
    _study_of(sc, study)
    items = sequence(omegas, "omegas", minimum=1, what="weight")
    a, b = sc.tracks
    # rule 17, before any weight is checked (book audit 76: each weight's fuse_tracks was checked alone, so 1,000
    # weights of the chapter's 261 steps ran about 95 CPU-s)
    work((len(items), a.est.shape[1], _SLIP_STEP + _SLIP_RUN_STEP * a.est.shape[0]),
         "omegas (with the steps and runs of sc)")
    ws = distinct_printed([scalar(w, f"omegas[{i}]", 0.0, 1.0) for i, w in enumerate(items)],
                          "omegas", general)  # ledger keys print (fuzz 30b)
    every = np.ones(study.t.size, dtype=bool)
    out = {}
    for w in ws:
        est = fuse_tracks(a, b, "ci", omega=w).est
        out[w] = tuple(float(v) for v in two_sensor.rmse_variants(est, study.truth, every)[two_sensor.SLIP_STEPS])
    return out


def _slip_pair(value: object, name: str, key: str) -> tuple[float, float]:
    """The (x, y) pair of slips ``value[key]`` (m), checked: a mapping holding ``key`` whose entry is two standard
    deviations (finite, positive, squares representable: the band squares them); errors name ``name`` and the key."""
    record(value, name, (key,), extra=True)
    entry = value[key]
    if isinstance(entry, (str, bytes)) or not hasattr(entry, "__len__") or len(entry) != 2:
        raise ValueError(f"{name}[{shown(key)}] must be an (x, y) pair of slips, got {shown(entry, 80)}")
    return std_scalar(entry[0], f"{name}[{key!r}][0]"), std_scalar(entry[1], f"{name}[{key!r}][1]")


def slip_pair_band(slip_weights: Mapping[float, tuple[float, float]], slip_all: Mapping[str, tuple[float, float]],
                   n_all: int) -> tuple[int, int]:
    r"""Step counts n for which the slip gives CI at the exhaustive optimum 5 m and the improved CI 3 m, on x and y.

    Parameters
    ----------
    slip_weights : mapping
        :func:`slip_at_weights` over ``n_all`` steps (reads the grid optimum ``W_GRID`` of the printed weight table).
    slip_all : mapping
        :func:`slip_all` over ``n_all`` steps (reads the improved CI).
    n_all : int
        Steps of a run.

    Returns
    -------
    (int, int)
        Smallest and largest n (``lo > hi`` when none fits).

    Raises
    ------
    TypeError
        ``slip_weights`` or ``slip_all`` is not a mapping, or ``n_all`` not an integer.
    ValueError
        ``slip_weights`` lacks the grid optimum ``W_GRID`` or ``slip_all`` the improved CI, or their entries are not
        pairs of slips (finite positive numbers whose squares are representable); ``n_all`` below 1.
    """
    pairs = {name: _slip_pair(value, name, key)
             for name, value, key in (("slip_weights", slip_weights, W_GRID), ("slip_all", slip_all, IMP))}
    n_all = count(n_all, "n_all")
    pub = data.WANG2024_RMSE.columns
    bands = [two_sensor.slip_steps_band(v * np.sqrt(n_all), float(p), 0)
             for vals, p in ((pairs["slip_weights"], pub["ci"][0]), (pairs["slip_all"], pub["improved"][0]))
             for v in vals]
    return max(b[0] for b in bands), min(b[1] for b in bands)


@_glue_doc("rounded as the prose shows it")
@reads_results("study")
def rmse_numbers(study: FusionStudy, leg_floor: ArrayLike, legs_steady: ArrayLike, leg_rmse: Mapping[str, float],
                 leg_causal: ArrayLike | None = None) -> GlueValues:
    """The numbers the prose quotes from the two-sensor RMSE study (glue keys ``ci_rmse_*``, ``ci_leg_*``, ``ci_fuzzy_*``).

    Parameters
    ----------
    study : FusionStudy
        :func:`fusion.scenarios.two_sensor.fusion_study` with every method run.
    leg_floor : array_like
        Straight-leg floor per step (m), :func:`fusion.scenarios.two_sensor.straight_leg_floor`.
    legs_steady : array_like of bool
        Straight-leg steps after the start-up transient.
    leg_rmse : mapping
        Method -> RMSE on those steps (m), for exactly the methods the study ran (as :func:`straight_leg` gives).
    leg_causal : array_like, optional
        The causal straight-leg floor on the same steps (``straight_leg_floor(..., causal=True)``).

    Raises
    ------
    TypeError
        ``study`` not a FusionStudy, ``legs_steady`` not bools, ``leg_rmse`` not a mapping, a floor not numeric.
    ValueError
        ``study`` lacks a rule (a weight or the published ω left out of ``fusion_study``) or holds one run (no
        Monte-Carlo standard error), ``leg_floor`` (``leg_causal``) not one finite non-negative number per straight-leg step, ``legs_steady`` not
        one bool per straight-leg step or selecting none, ``leg_rmse`` empty or not of finite non-negative numbers,
        holding a method the study did not run or lacking one it ran;
        the leg not that of ``study`` (:func:`straight_leg` on it): another count of straight-leg steps, other steady
        steps, or a method's RMSE of ``leg_rmse`` not the study's mean there (relative 1e-9).
    """
    _every_method(study, "rmse_numbers", published=True, min_runs=2)
    leg_floor = as_array(leg_floor, "leg_floor", ndim=1, nonnegative=True)
    legs_steady = _steps(legs_steady, "legs_steady", leg_floor.size, "straight-leg step of leg_floor")
    if not legs_steady.any():
        raise ValueError("legs_steady selects no straight-leg step: the floors' mean would be of nothing")
    mapping_of(leg_rmse, "leg_rmse", "RMSE (m)", maker="straight_leg")
    leg_rmse = _entries(leg_rmse, "leg_rmse", list(leg_rmse), "straight_leg", nonnegative=True)
    _exact_keys(leg_rmse, "leg_rmse", list(study.rmse), "straight_leg(study, ...).rmse")
    if leg_causal is not None:
        leg_causal = _per_step(leg_causal, "leg_causal", leg_floor.size, "straight-leg step of leg_floor",
                               nonnegative=True)
    _leg_of(study, leg_floor, legs_steady, leg_rmse)   # the leg of this study (fuzz 24c MM)

    from fusion.estimates.fuzzy_cluster import fuzzy_cluster_fusion as _fcf

    level = inspect.signature(_fcf).parameters["level"].default
    return {"ci_fuzzy_level": level, "ci_fuzzy_gate": 100 * (1 - level),
            "ci_rmse_local": rounded(study.steady_rmse(StudyMethod.SENSOR_1, 0), 1),
            "ci_rmse_ci": rounded(study.steady_rmse(StudyMethod.CI, 0), 1),
            "ci_rmse_ci_se": rounded(_run_se(study, StudyMethod.CI), 2),
            "ci_rmse_ci_pub": rounded(study.steady_rmse(StudyMethod.CI_PUBLISHED, 0), 1),
            "ci_rmse_foa": rounded(study.steady_rmse(StudyMethod.CI_FRUIT_FLY, 0), 1),
            "ci_rmse_grid": rounded(study.steady_rmse(StudyMethod.CI_GRID, 0), 1),
            "ci_rmse_fuzzy": rounded(study.steady_rmse(StudyMethod.FUZZY, 0), 1),
            "ci_rmse_central": rounded(study.steady_rmse(StudyMethod.CENTRAL, 0), 1),
            "ci_leg_floor": rounded(float(leg_floor[legs_steady].mean()), 1),
            **({"ci_leg_causal": rounded(float(np.asarray(leg_causal, dtype=float)[legs_steady].mean()), 1),
                "ci_leg_best_over_causal": rounded(min(leg_rmse.values())
                                                   / float(np.asarray(leg_causal, dtype=float)[legs_steady].mean()), 1)}
               if leg_causal is not None else {}),
            "ci_leg_best": rounded(min(leg_rmse.values()), 1),
            "ci_rmse_min": rounded(min(study.steady_rmse(name, c) for name in study.est for c in (0, 2)), 1)}


#: Label of the printed identical sensors in the architecture study and its table.
IDENTICAL_LABEL = "identical sensors (printed)"

#: Label and measurement covariances (m²) of the asymmetric anisotropic pair on which every rule separates.
ANISO_LABEL = "anisotropic pair (R₁ = diag(150², 50²), R₂ = 80² I)"
ANISO_R = constant((np.diag([150.0**2, 50.0**2]), 80.0**2 * np.eye(2)))


def slip_numbers(variants: Mapping[str, tuple[float, float]], variants_all: Mapping[str, tuple[float, float]],
                 slip: pd.DataFrame, n_all: int | None = None) -> GlueValues:
    """The numbers the prose quotes on the eq. 13 slip √(Σe²)/n (glue keys ``ci_slip_*``).

    Parameters
    ----------
    variants, variants_all : mapping
        :func:`fusion.scenarios.two_sensor.rmse_variants` of the improved CI over the steps after 20 s and over all.
    slip : pandas.DataFrame
        :func:`slip_table`.
    n_all : int, optional
        Steps of a run; with it, the band of step counts for which the slip rounds to the published 3 m
        (:func:`slip_band`, glue keys ``ci_slip_n_*``).

    Returns
    -------
    dict
        Glue key -> value (m, 2 decimals; step counts).

    Raises
    ------
    TypeError
        ``variants`` or ``variants_all`` not a mapping, ``slip`` not a DataFrame.
    ValueError
        ``variants`` or ``variants_all`` lacking a reading read here or one not two finite non-negative numbers;
        ``slip`` without the slip over all steps or with a value there that is not finite and non-negative, or
        without the rows of Fig. 6 or those of the averaging rules.
    """
    S, SR = two_sensor.SLIP_STEPS, two_sensor.SLIP_RUNS
    variants = _entries(variants, "variants", (S, SR), "two_sensor.rmse_variants", width=2, nonnegative=True)
    variants_all = _entries(variants_all, "variants_all", (S,), "two_sensor.rmse_variants", width=2,
                            nonnegative=True)
    _frame(slip, "slip", (), maker="slip_table")
    col_all = next((c for c in slip.columns if isinstance(c, str) and c.startswith("√Σe²/n, n = all")), None)
    if col_all is None:
        raise ValueError("slip lacks the column of the slip over all steps ('√Σe²/n, n = all ... steps (m)', a "
                         "result of slip_table holds it)")
    _frame(slip, "slip", (col_all,), nonnegative=(col_all,), maker="slip_table")
    in_fig6 = np.array([isinstance(r, str) and r.startswith("Fig. 6") for r in slip.index.get_level_values(0)])
    if in_fig6.all() or not in_fig6.any():
        raise ValueError(f"slip must hold the rows of the averaging rules and those of Fig. 6 (its first index level, "
                         f"as slip_table makes it), got {'only' if in_fig6.all() else 'none of'} the rows of Fig. 6")
    avg, fig6 = slip[~in_fig6], slip[in_fig6]
    return {"ci_slip_all_x": rounded(variants_all[S][0], 2), "ci_slip_all_y": rounded(variants_all[S][1], 2),
            "ci_slip_st_x": rounded(variants[S][0], 2), "ci_slip_st_y": rounded(variants[S][1], 2),
            "ci_slip_runs_x": rounded(variants[SR][0], 2), "ci_slip_runs_y": rounded(variants[SR][1], 2),
            # the rules that average the two filters; Fig. 6's CI with tie-rule weights (one sensor nearly dropped) apart
            "ci_slip_min": rounded(float(avg[col_all].min()), 2), "ci_slip_max": rounded(float(avg[col_all].max()), 2),
            "ci_slip_fig6_lo": rounded(float(fig6[col_all].min()), 2), "ci_slip_fig6_hi": rounded(float(fig6[col_all].max()), 2),
            **({f"ci_slip_n_{k}": v for k, v in _band_numbers(slip_band(variants_all, n_all)).items()}
               if n_all is not None else {})}


def slip_band(variants_all: Mapping[str, tuple[float, float]], n_all: int) -> dict[str, tuple[int, int]]:
    r"""The step counts :math:`n` for which the slip :math:`\sqrt{\sum e^2}/n` of the improved CI rounds to the published 3 m.

    The slip over all steps is the per-run RMSE divided by :math:`\sqrt n`; the per-run RMSE is recovered as
    slip × √``n_all`` and held fixed (:func:`fusion.scenarios.two_sensor.slip_steps_band`).

    Parameters
    ----------
    variants_all : mapping
        :func:`fusion.scenarios.two_sensor.rmse_variants` of the improved CI over all ``n_all`` steps.
    n_all : int
        Steps of a run (261 with the chapter's assumptions).

    Returns
    -------
    dict
        ``"x"`` and ``"y"``: (smallest n, largest n).

    Raises
    ------
    TypeError
        ``variants_all`` is not a mapping, or ``n_all`` not an integer.
    ValueError
        ``variants_all`` lacks the slip (``SLIP_STEPS``) or its entry is not an (x, y) pair of slips (finite positive
        numbers whose squares are representable), as :func:`slip_pair_band` checks its mappings; ``n_all`` below 1.
    """
    slip = _slip_pair(variants_all, "variants_all", two_sensor.SLIP_STEPS)
    n_all = count(n_all, "n_all")
    pub = float(data.WANG2024_RMSE.columns["improved"][0])
    return {ax: two_sensor.slip_steps_band(v * np.sqrt(n_all), pub, 0) for ax, v in zip(("x", "y"), slip)}


def _band_numbers(band: Mapping[str, tuple[int, int]]) -> dict[str, int]:
    """``x_lo``, ``x_hi``, ``y_lo``, ``y_hi`` and the common ``lo``, ``hi`` of :func:`slip_band`."""
    return {"x_lo": band["x"][0], "x_hi": band["x"][1], "y_lo": band["y"][0], "y_hi": band["y"][1],
            "lo": max(band["x"][0], band["y"][0]), "hi": min(band["x"][1], band["y"][1])}


@_glue_doc()
def published_numbers(period: float, runs: int) -> GlueValues:
    """The source's printed numbers the prose quotes (glue keys ``ci_pub_*``), with our period and run count.

    Parameters
    ----------
    period : float
        Our sampling period T (s); glued as given, a numpy scalar or 0-d array as the Python number it holds.
    runs : int
        Monte-Carlo runs of the source's scenario.

    Raises
    ------
    TypeError
        ``period`` is not a number or ``runs`` not an integer.
    ValueError
        ``period`` is not finite and positive, or ``runs`` below 1.
    """
    # checked; glued as the plain number given (an int stays an int; a Fraction, a Decimal, a numpy scalar or a
    # 0-d array as the float read: the glue holds plain numbers, fuzz 22b FR)
    T = given_number(period, "period", lo=0.0, lo_open=True)
    RUNS = count(runs, "runs")
    SC = data.WANG2024_SCENARIO
    pub_rmse, pub_fruit_fly, pub_times = data.WANG2024_RMSE.columns, data.WANG2024_FOA.columns, data.WANG2024_TIMES.columns
    return {"ci_T": T, "ci_runs": RUNS, "ci_delta": SC["delta1"], "ci_pub_rmse": pub_rmse["improved"][0],
            "ci_pub_ci": pub_rmse["ci"][0], "ci_pub_mb": pub_rmse["multi_bayes"][0], "ci_pub_fuzzy": pub_rmse["fuzzy"][0],
            "ci_pub_ml": pub_rmse["max_likelihood"][0], "ci_pub_max": data.WANG2024_RMSE.values.max(),
            "ci_pub_min": data.WANG2024_RMSE.values.min(), "ci_pub_t_ci": pub_times["ci"][0],
            "ci_pub_t_imp": pub_times["improved"][0], "ci_pub_foa_s": pub_fruit_fly["foa_time_s"][0],
            "ci_pub_grid_s": pub_fruit_fly["grid_time_s"][0], "ci_pub_foa": pub_fruit_fly["foa_optimum"][0],
            "ci_pub_grid": pub_fruit_fly["grid_optimum"][0]}


#: Field specs of :class:`LegClaimInputs` (``fusion._results``), shared with the ledger's bundles that hold them.
_LEG_FIELDS = {"leg_floor": number(), "leg_best": number(), "leg_floor_causal": number()}


@dataclass(frozen=True)
class LegClaimInputs:
    """The ledger's entries of :class:`StraightLeg` (:meth:`StraightLeg.claim_inputs`), m.

    Attributes
    ----------
    leg_floor : float
        The smoother's floor averaged over the steady straight-leg steps.
    leg_best : float
        The smallest method RMSE of :attr:`StraightLeg.rmse`.
    leg_floor_causal : float
        The causal floor averaged over the same steps.
    """

    leg_floor: float
    leg_best: float
    leg_floor_causal: float

    __result_spec__ = ResultSpec(_LEG_FIELDS)
    __post_init__ = validated_post_init



def _leg_relation(values: Mapping[str, Any], cls: str) -> None:
    """One floor per straight-leg step (``L`` = the steps of ``on_leg``), at least one steady step (the floors are
    averaged over them)."""
    n_leg = int(values["on_leg"].sum())
    if values["floor"].shape[0] != n_leg:
        raise ValueError(f"{cls}.floor must have one value per straight-leg step of on_leg ({n_leg}), "
                         f"got {values['floor'].shape[0]}")
    if not values["steady"].any():
        raise ValueError(f"{cls}.steady must hold at least one steady straight-leg step (the floors' average)")


@dataclass(frozen=True)
class StraightLeg:
    """The straight-leg floors of :func:`fusion.scenarios.two_sensor.straight_leg_floor` set beside a fusion study.

    Attributes
    ----------
    on_leg : ndarray of bool, shape (K,)
        Steps on a straight leg.
    floor, causal : ndarray, shape (L,)
        The smoother's (whole leg) and the causal (the leg's measurements so far) floor at the ``L``
        straight-leg steps (m).
    steady : ndarray of bool, shape (L,)
        Which of the straight-leg steps lie after the start-up transient (``study.steady[on_leg]``).
    rmse : dict of str to float
        Method -> mean RMSE on x over the straight-leg steps after the transient (m).
    """

    on_leg: np.ndarray
    floor: np.ndarray
    causal: np.ndarray
    steady: np.ndarray
    rmse: Mapping[str, float]

    __result_spec__ = ResultSpec({"on_leg": mask("K"), "floor": array("L", bounds=(0.0, np.inf)),
                                  "causal": array("L", bounds=(0.0, np.inf)), "steady": mask("L"),
                                  "rmse": dict_of(number())}, relations=(lambda v, cls: _leg_relation(v, cls),))
    __post_init__ = validated_post_init


    def claim_inputs(self) -> LegClaimInputs:
        """The ledger's entries ``leg_floor``, ``leg_best`` and ``leg_floor_causal`` (m), for ``claims``.

        Returns
        -------
        LegClaimInputs
            The floor and the causal floor averaged over the steady straight-leg steps, and the smallest method RMSE
            there (m).
        """
        return LegClaimInputs(leg_floor=float(self.floor[self.steady].mean()), leg_best=min(self.rmse.values()),
                              leg_floor_causal=float(self.causal[self.steady].mean()))


@reads_results("study")
def straight_leg(study: FusionStudy, T: float, sigma: float) -> StraightLeg:
    """Both straight-leg floors on the path of ``study`` and every method's RMSE on the same steps.

    Parameters
    ----------
    study : FusionStudy
        :func:`fusion.scenarios.two_sensor.fusion_study` on the path of
        :func:`fusion.scenarios.two_sensor.trajectory` at period ``T``.
    T : float
        Sampling period (s), > 0.
    sigma : float
        Measurement noise standard deviation of each sensor (m), > 0.

    Returns
    -------
    StraightLeg
        The straight-leg steps, both floors per step (m), which of them are steady, and every method's mean RMSE on x
        there (m).

    Raises
    ------
    ValueError
        If the path at period ``T`` does not have the steps of ``study``.
    """
    instance_of(study, FusionStudy, "study")
    _, on_leg, floor = two_sensor.straight_leg_floor(T, sigma)
    causal = two_sensor.straight_leg_floor(T, sigma, causal=True)[2]
    if on_leg.shape != study.steady.shape:
        raise ValueError(f"T: the path at this period has {on_leg.size} steps, study has {study.steady.size}")
    rmse = {name: float(r[on_leg & study.steady, 0].mean()) for name, r in study.rmse.items()}
    return StraightLeg(on_leg=on_leg, floor=floor, causal=causal, steady=study.steady[on_leg], rmse=rmse)


def variants_table(variants: Mapping[str, tuple[float, float]],
                   variants_all: Mapping[str, tuple[float, float]]) -> pd.DataFrame:
    """Eq. 13's readings of the RMSE side by side: after the start-up transient and over all steps (m, 2 decimals).

    Parameters
    ----------
    variants, variants_all : mapping
        :func:`fusion.scenarios.two_sensor.rmse_variants` on the steps ``t ≥ 20 s`` and on every step:
        reading -> (x, y) in m.

    Returns
    -------
    pandas.DataFrame
        One row per reading; columns (steps, axis).

    Raises
    ------
    TypeError
        ``variants`` or ``variants_all`` not a mapping, or a reading not two numbers.
    ValueError
        ``variants`` empty, ``variants_all`` not of its readings, or a reading not two finite numbers (x, y).
    """
    if isinstance(variants, Mapping) and not variants:
        raise ValueError("variants is empty (it must map each reading of two_sensor.rmse_variants to (x, y))")
    variants = _entries(variants, "variants", list(variants) if isinstance(variants, Mapping) else (),
             "two_sensor.rmse_variants", width=2, nonnegative=True)
    same_keys(variants_all, "variants_all", variants, "variants")
    variants_all = _entries(variants_all, "variants_all", list(variants), "two_sensor.rmse_variants", width=2,
                            nonnegative=True)
    return pd.concat({"t ≥ 20 s": pd.DataFrame(variants, index=["x (m)", "y (m)"]).T,
                      "all steps": pd.DataFrame(variants_all, index=["x (m)", "y (m)"]).T}, axis=1).round(2)


def variant_numbers(variants: Mapping[str, tuple[float, float]]) -> GlueValues:
    """The numbers the prose quotes from eq. 13's readings (glue keys ``ci_var_*``, m, 1 decimal).

    Parameters
    ----------
    variants : mapping
        :func:`fusion.scenarios.two_sensor.rmse_variants` after the start-up transient.

    Returns
    -------
    dict
        ``ci_var_avg_x``, ``ci_var_avg_y``: RMSE of the run-averaged estimate on x and y;
        ``ci_var_run_x``: RMSE over steps per run on x.

    Raises
    ------
    TypeError
        ``variants`` is not a mapping.
    ValueError
        ``variants`` lacks a reading read here, or one is not two finite numbers (x, y).
    """
    variants = _entries(variants, "variants", (RUN_AVERAGED, OVER_STEPS), "two_sensor.rmse_variants", width=2,
                        nonnegative=True)
    return {"ci_var_avg_x": rounded(variants[RUN_AVERAGED][0], 1),
            "ci_var_avg_y": rounded(variants[RUN_AVERAGED][1], 1),
            "ci_var_run_x": rounded(variants[OVER_STEPS][0], 1)}


@reads_results("study")
def slip_all(study: FusionStudy, names: Sequence[StudyMethod] = (StudyMethod.CI, StudyMethod.SPLIT_CI,
                                                                  StudyMethod.CONVEX, StudyMethod.FUZZY)
             ) -> dict[StudyMethod, tuple[float, float]]:
    """The slip reading √(Σe²)/n over all steps, per run (x, y in m), of the rules ``names`` (for ``claims``).

    Parameters
    ----------
    study : FusionStudy
        :func:`fusion.scenarios.two_sensor.fusion_study`.
    names : sequence of StudyMethod
        Method keys of ``study.est``, in the order the ledger lists them.

    Returns
    -------
    dict
        Rule -> :func:`fusion.scenarios.two_sensor.rmse_variants`' ``SLIP_STEPS`` reading on every step.

    Raises
    ------
    TypeError
        ``study`` is not a :class:`~fusion.scenarios.two_sensor.FusionStudy`, or ``names`` not a sequence.
    ValueError
        ``names`` empty, a name not a rule of ``study``, or one repeated (the result is keyed by rule).
    """
    instance_of(study, FusionStudy, "study")
    names = distinct(sequence(names, "names", minimum=1, what="rule"), "names")
    missing = [n for n in names if n not in study.est]
    if missing:
        raise ValueError(f"names: not rules of the study: {missing}")
    every = np.ones(study.t.size, dtype=bool)
    return {name: two_sensor.rmse_variants(study.est[name], study.truth, every)[two_sensor.SLIP_STEPS] for name in names}


def path_noise_limit(sigma: float, delta0: float) -> float:
    r"""The averaging rules' error on a deterministic path as the period goes to 0, with Q as printed (m).

    With :math:`Q = \Delta_0^2 I` per step, whatever the period, the local filters' gains do not shrink as
    :math:`T \to 0`: :math:`F \to I`, the position is a random walk of variance :math:`q = \Delta_0^2` per step
    seen with variance :math:`r = \sigma^2`, and the steady-state gain is :math:`K = x/(x + r)` with
    :math:`x^2 - qx - qr = 0`. On a path the filter follows exactly (no lag as :math:`T \to 0`), its error is the
    measurement noise it lets through, :math:`e_k = (1-K)e_{k-1} + Kv_k`, of variance :math:`Kr/(2-K)`; the
    average of two filters with independent noise has half that variance.

    Parameters
    ----------
    sigma : float
        Measurement noise of each sensor per axis (m), > 0.
    delta0 : float
        Process-noise standard deviation per step (m), > 0.

    Returns
    -------
    float
        RMS error per axis of the average of the two filters (m).
    """
    sigma, delta0 = std_scalar(sigma, "sigma"), std_scalar(delta0, "delta0")  # their squares are variances
    q, r = float(delta0) ** 2, float(sigma) ** 2
    x = (q + np.sqrt(q * q + 4 * q * r)) / 2
    k = x / (x + r)
    return float(np.sqrt(k * r / (2 - k) / 2))


def margin_numbers() -> GlueValues:
    """The practical margins the claim file declares (glue keys ``ci_margin_*``).

    Returns
    -------
    dict
        ``ci_margin_rmse`` (m, the tracking RMSE), ``ci_margin_clearly_pct`` (% of the baseline's error, the
        infrared + radar comparisons) and ``ci_margin_xy`` (m, x against y).
    """
    q = claim_file().quantities
    return {"ci_margin_rmse": float(q["rmse-x"]["margin"]["absolute"]),
            "ci_margin_clearly_pct": round(100 * float(q["azimuth"]["margin"]["relative"])),
            "ci_margin_xy": float(q["x-against-y"]["margin"]["absolute"])}


@reads_results("sc", "study")
def baseline_slip_numbers(sc: Scenario, study: FusionStudy) -> GlueValues:
    r"""A hypothesis about the undefined baselines under the slip :math:`\sqrt{\sum e^2}/n` (glue keys ``ci_slip8_*``).

    The raw two-sensor average of the measurements and one sensor's raw measurements, under the slip with
    :math:`n` all the steps of a run, beside the published 6 m (multi-Bayesian) and 9 m (maximum likelihood);
    and the step counts :math:`n` for which CI at the published weight 0.0033 (5 m), the improved CI (3 m), the
    raw average (6 m) and one sensor (9 m) all round to the published values on both axes, the per-run RMSE
    held fixed (:func:`fusion.scenarios.two_sensor.slip_steps_band`).

    Parameters
    ----------
    sc : Scenario
        The chapter's scenario (its measurements, ``LocalTrack.z``).
    study : FusionStudy
        :func:`fusion.scenarios.two_sensor.fusion_study` of ``sc``.
        Another scenario's study (other steps, truth or local tracks) is refused, naming ``study`` and ``sc``.

    Returns
    -------
    dict
        ``ci_slip8_avg_x``, ``_avg_y``, ``_one_x``, ``_one_y`` (m, 2 decimals), ``ci_slip8_lo``, ``ci_slip8_hi``
        (``lo > hi`` when no n fits).
    """
    _study_of(sc, study)
    pub = data.WANG2024_RMSE.columns
    every = np.ones(study.t.size, dtype=bool)
    n_all = int(study.t.size)
    z1, z2 = (np.asarray(tr.z, dtype=float) for tr in sc.tracks)

    def as_est(z: np.ndarray) -> np.ndarray:
        est = np.zeros(z.shape[:2] + (4,))
        est[..., 0], est[..., 2] = z[..., 0], z[..., 1]
        return est

    slip = {name: two_sensor.rmse_variants(est, study.truth, every)[two_sensor.SLIP_STEPS]
            for name, est in (("avg", as_est((z1 + z2) / 2)), ("one", as_est(z1)))}
    ci_grid = slip_at_weights(sc, study, (W_GRID,))[W_GRID]
    imp = two_sensor.rmse_variants(study.est[IMP], study.truth, every)[two_sensor.SLIP_STEPS]
    bands = [two_sensor.slip_steps_band(v * np.sqrt(n_all), float(p), 0)
             for vals, p in ((ci_grid, pub["ci"][0]), (imp, pub["improved"][0]), (slip["avg"], pub["multi_bayes"][0]),
                             (slip["one"], pub["max_likelihood"][0]))
             for v in vals]
    return {"ci_slip8_avg_x": rounded(slip["avg"][0], 2), "ci_slip8_avg_y": rounded(slip["avg"][1], 2),
            "ci_slip8_one_x": rounded(slip["one"][0], 2), "ci_slip8_one_y": rounded(slip["one"][1], 2),
            "ci_slip8_lo": max(b[0] for b in bands), "ci_slip8_hi": min(b[1] for b in bands)}
