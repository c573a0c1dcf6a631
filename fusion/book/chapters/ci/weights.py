"""The CI weight (Figs. 5-6): FOA against the exhaustive and closed-form searches, their timings and the weight pairs."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import pandas as pd
from matplotlib.figure import Figure
from numpy.typing import ArrayLike

from fusion._counts import allocation, distinct, seed as check_seed, seeds as check_seeds, sequence
from fusion._validation import as_array, as_rng, text as text_argument
from fusion import data
from fusion._docstrings import reads_results
from fusion._results import ResultSpec, array, dict_of, instance, integer, number, text, tuple_of, validated_post_init
from fusion._shown import shown
from fusion._validation import as_covariance, count, instance_of
from fusion.book.style import color, new_figure
from fusion.book.tables import rounded, roundoff
from fusion.book.glue import GlueValues, _glue_suffix, _glued_cell
from fusion.estimates.ci import ci_objective, ci_weight, split_ci_objective, split_covariance_intersection
from fusion.estimates.ci import _split_ci_covariance, _split_parts
from fusion.optimise.result import OptimumResult
from fusion.optimise.scalar import bounded_minimum, fruit_fly, fruit_fly_batch, grid_search
from fusion.scenarios import two_sensor
from fusion.scenarios.two_sensor import FruitFlySeeds, FusionStudy, Scenario, StudyMethod
from fusion.book.chapters.ci.printed import PrintedWeightFacts, _printed_facts_budget, ml_vs_product
from fusion.book.chapters._defaults import study_defaults
from fusion.book.chapters.ci.text import _glue_doc, _sig3, excess_text, readable
from fusion.book.chapters.ci.checks import (_entries, _flat_pair_read, _counted, _frame, _indices, _objective_grid,
                                            _optima_of, _per_step, _period_key, _results, _same_search,
                                            _sensor_noises, _step_index, _study_of)

__all__ = ["weight_search_numbers", "timing_numbers", "split_fruit_fly_gap", "weight_search", "fruit_fly_table", "timing_table",
           "fig5", "fig5_hypotheses", "printed_weight_facts", "weight_numbers", "WeightPair", "weight_pair",
           "WeightClaimInputs", "weight_claim_inputs", "TimingBenchmark", "timing_benchmark", "fig5_hypothesis_numbers"]


#: Column headers of :func:`fig5_hypotheses`, which the chapter's claim evidence reads (issue 36: named once).
OMEGA_FOUND = "ω found"
TR_P = "tr P"


@reads_results("sc")
def split_fruit_fly_gap(sc: Scenario, k: int, rng: np.random.Generator) -> float:
    r"""Relative excess of FOA's minimum of :math:`\operatorname{tr}P` of split CI over the bounded search's, at step ``k``.

    FOA (30 × 200) on :math:`\omega \mapsto \operatorname{tr}P_{\text{split}}(\omega)` (eq. ci-split,
    ω clipped to [1e-6, 1 - 1e-6]) against :func:`fusion.estimates.ci.split_covariance_intersection`'s own
    bounded minimisation, on the two local tracks' covariance splits at step ``k``.

    Parameters
    ----------
    sc : Scenario
        Output of :func:`fusion.scenarios.two_sensor.two_sensor_scenario`.
    k : int
        Step (0-based).
    rng : numpy.random.Generator
        Drives the fruit fly optimisation.

    Returns
    -------
    float
        (FOA minimum − bounded minimum) / bounded minimum (dimensionless).
    """
    instance_of(sc, Scenario, "sc")
    a, b = sc.tracks
    k = _step_index(k, "k", a.Pd.shape[0])
    n = a.Pd.shape[1]
    zero = np.zeros(n)
    parts = _split_parts(a.Pd[k], a.Pi[k], b.Pd[k], b.Pi[k], n)   # validated once, not at each of FOA's 6,000 points

    def objective(w: float) -> float:   # split_covariance_intersection(..., omega=w).P's trace, bit for bit
        w = min(max(float(w), 1e-6), 1 - 1e-6)
        return float(np.trace(_split_ci_covariance(*parts, w)))

    fly = fruit_fly(objective, rng)
    best = float(np.trace(split_covariance_intersection(zero, a.Pd[k], a.Pi[k], zero, b.Pd[k], b.Pi[k]).P))
    return (fly.fun - best) / best


def _covariance_pair(P1: object, P2: object, names: tuple[str, str] = ("P1", "P2")) -> None:
    """Two covariances of one size (symmetric positive definite), checked under the caller's names."""
    first = as_covariance(P1, name=names[0])
    as_covariance(P2, first.shape[0], name=names[1])


def weight_search(P1: ArrayLike, P2: ArrayLike, rng: np.random.Generator) -> dict[str, OptimumResult]:
    r"""Minimise :math:`\operatorname{tr}P(\omega)` of CI (eq. 1) four ways (Fig. 5).

    Parameters
    ----------
    P1, P2 : array_like, shape (n, n)
        The two covariances.
    rng : numpy.random.Generator
        For FOA (30 flies × 200 generations, the source's settings).

    Returns
    -------
    dict of str to OptimumResult
        FOA, exhaustive search on 1001 points, scipy's bounded Brent and the closed form
        (:func:`fusion.estimates.ci.ci_weight`, zero evaluations).

    Raises
    ------
    TypeError
        ``P1`` or ``P2`` not numeric.
    ValueError
        ``P1`` or ``P2`` not a symmetric positive-definite matrix, or of different sizes.
    """
    _covariance_pair(P1, P2)
    P1, P2 = np.asarray(P1, dtype=float), np.asarray(P2, dtype=float)   # as given: the searches' numbers unchanged

    def objective(w: ArrayLike) -> Any:
        return ci_objective(w, P1, P2)

    res = {"FOA (30 × 200)": fruit_fly(objective, rng, vectorized=True),
           "exhaustive, 1001 points": grid_search(objective, 1001, vectorized=True),
           "scipy bounded Brent": bounded_minimum(objective)}
    w = ci_weight(P1, P2)
    res["closed form"] = OptimumResult(x=w, fun=float(objective(w)), n_evaluations=0)
    return res


def fruit_fly_table(res: Mapping[str, OptimumResult]) -> pd.DataFrame:
    """ω (4 decimals), tr P (m², m²/s², 3 decimals) and number of evaluations of each method of :func:`weight_search`.

    Parameters
    ----------
    res : mapping of str to OptimumResult
        Result of :func:`weight_search`.

    Returns
    -------
    pandas.DataFrame
        One row per method of ``res``; columns ``"ω"``, ``"tr P (m², m²/s²)"`` and ``"evaluations"``.

    Raises
    ------
    TypeError
        ``res`` is not a mapping, or an entry not an OptimumResult.
    ValueError
        ``res`` is empty.
    """
    res = _results(res, "res", OptimumResult, "weight_search")  # read once (decision 31a C2)
    t = pd.DataFrame({name: {"ω": r.x, "tr P (m², m²/s²)": r.fun, "evaluations": r.n_evaluations}
                      for name, r in res.items()}).T
    t["ω"] = t["ω"].astype(float).round(4)
    t["tr P (m², m²/s²)"] = t["tr P (m², m²/s²)"].astype(float).round(3)
    t["evaluations"] = t["evaluations"].astype(int)
    return t


#: The measurements of ``benchmarks/results/ci.json`` that :func:`timing_table` reads.
_TIMING_KEYS = ("foa_vectorised", "foa_loop", "grid_vectorised", "grid_loop", "bounded", "closed_form", "sim_ci",
                "sim_improved", "sim_convex", "sim_fuzzy", "sim_ci_foa")


def timing_table(m: Mapping[str, float]) -> pd.DataFrame:
    """Published MATLAB times (Fig. 5, Tables 1-2) beside ours from ``benchmarks/results/ci.json``.

    Parameters
    ----------
    m : mapping of str to float
        The benchmark's measurements by key (s).

    Returns
    -------
    pandas.DataFrame
        Indexed by (where, task); published (s), ours (s); 3 significant digits. No ratio: MATLAB seconds of
        unknown code on another machine cannot be set against ours.

    Raises
    ------
    TypeError
        ``m`` is not a mapping, or a measurement read here not a number.
    ValueError
        ``m`` lacks a measurement read here, or one is not finite.
    """
    m = _entries(m, "m", _TIMING_KEYS, "timing_benchmark (its measurements)", nonnegative=True)
    pub, times = data.WANG2024_FOA.columns, data.WANG2024_TIMES.columns
    timing = pd.DataFrame([
        ("Fig. 5", "ω by FOA (30 × 200)", pub["foa_time_s"][0], m["foa_vectorised"]),
        ("Fig. 5", "ω by FOA, one fly at a time", np.nan, m["foa_loop"]),
        ("Fig. 5", "ω by exhaustive search", pub["grid_time_s"][0], m["grid_vectorised"]),
        ("Fig. 5", "ω by exhaustive search, one point at a time", np.nan, m["grid_loop"]),
        ("—", "ω by bounded Brent (scipy)", np.nan, m["bounded"]),
        ("—", "ω in closed form", np.nan, m["closed_form"]),
        ("Table 1", "CI", times["ci"][0], m["sim_ci"]),
        ("Table 1, 2", "improved CI", times["improved"][0], m["sim_improved"]),
        ("Table 2", "multi-Bayesian (= convex combination)", times["multi_bayes"][0], m["sim_convex"]),
        ("Table 2", "fuzzy clustering", times["fuzzy"][0], m["sim_fuzzy"]),
        ("Table 2", "maximum likelihood (= convex combination)", times["max_likelihood"][0], m["sim_convex"]),
        ("—", "CI with FOA at every step", np.nan, m["sim_ci_foa"]),
    ], columns=["where", "task", "published, MATLAB (s)", "ours, Python (s)"]).set_index(["where", "task"])
    return timing.map(_sig3)


def fig5(P1: ArrayLike, P2: ArrayLike, res: Mapping[str, OptimumResult], m: Mapping[str, float],
         aniso: tuple[ArrayLike, ArrayLike, Mapping[str, OptimumResult], FruitFlySeeds] | None = None,
         seeds: FruitFlySeeds | None = None) -> Figure:
    """The source's Fig. 5 recomputed: tr P(ω) with where each method lands, on two pairs, and time per choice of ω.

    Parameters
    ----------
    P1, P2 : array_like, shape (n, n)
        The covariance pair of :func:`weight_search` whose optimum is the end ω = 0 (sensor 2 three times more
        precise).
    res : mapping of str to OptimumResult
        Result of :func:`weight_search` on that pair.
    m : mapping of str to float
        The benchmark's measurements by key (s).
    aniso : (P1, P2, res, FruitFlySeeds), optional
        The anisotropic pair, whose optimum is inside (0, 1): its covariances, :func:`weight_search` on them and
        :func:`fusion.scenarios.two_sensor.fruit_fly_over_seeds`; drawn in its own panel, zoomed on the optimum, with
        the weight FOA ends at for every seed.
    seeds : FruitFlySeeds, optional
        :func:`fusion.scenarios.two_sensor.fruit_fly_over_seeds` on the first pair (one point per seed).

    Returns
    -------
    matplotlib.figure.Figure
        Top: tr P(ω) with each method's landing point (and the anisotropic pair's zoom); bottom: seconds per choice of
        ω, published and ours.

    Raises
    ------
    TypeError
        ``res`` not a mapping of OptimumResult, ``m`` not a mapping, ``seeds`` (``aniso``'s last entry) not a
        FruitFlySeeds, ``aniso`` not a tuple.
    ValueError
        ``P1`` or ``P2`` not covariances of one size, ``res`` empty, ``m`` without a measurement drawn, ``aniso`` not
        four entries, its covariances not of the size of ``P1`` or the pair ``(P1, P2)`` itself, or its ``res``
        without the closed form; ``res`` or ``seeds`` (``aniso``'s) not searched on ``(P1, P2)`` (``aniso``'s pair):
        a recorded tr P not that pair's objective at the recorded ω (relative 1e-9).
    """
    _covariance_pair(P1, P2)
    res = _results(res, "res", OptimumResult, "weight_search")  # read once (decision 31a C2)
    m = _entries(m, "m", ("foa_vectorised", "grid_vectorised", "closed_form"), "timing_benchmark().measurements",
                 nonnegative=True)
    if seeds is not None:
        instance_of(seeds, FruitFlySeeds, "seeds")
    _optima_of(P1, P2, res, seeds)   # the optima marked are those of this pair's objective (fuzz 24c MM)
    if aniso is not None:
        aniso = tuple(sequence(aniso, "aniso", 4))  # (P1, P2, res, FruitFlySeeds): a tuple or a list (fuzz 24e F3)
        n = np.asarray(P1).shape[0]   # the anisotropic pair is of the same state (fuzz 24c FA1: aniso[0] named)
        as_covariance(aniso[0], n, name="aniso[0]")
        as_covariance(aniso[1], n, name="aniso[1]")
        _entries(_results(aniso[2], "aniso[2]", OptimumResult, "weight_search"), "aniso[2]", ("closed form",),
                 "weight_search", numbers=False)
        instance_of(aniso[3], FruitFlySeeds, "aniso[3]")
        _optima_of(aniso[0], aniso[1], aniso[2], aniso[3], names=("aniso[0]", "aniso[1]", "aniso[2]", "aniso[3]"))
        if np.array_equal(np.asarray(aniso[0], dtype=float), np.asarray(P1, dtype=float)) and np.array_equal(
                np.asarray(aniso[1], dtype=float), np.asarray(P2, dtype=float)):
            raise ValueError("aniso must be another pair than (P1, P2): the anisotropic pair's panel would repeat "
                             "the first pair's")
    pub = data.WANG2024_FOA.columns
    fig, _ax = new_figure(figsize=(7.5, 8.4))
    fig.delaxes(_ax)
    top, bottom = fig.subfigures(2, 1, height_ratios=[1.15, 1.0])
    ax1, ax3 = top.subplots(1, 2) if aniso is not None else (top.subplots(1, 1), None)
    grid = np.linspace(0, 1, 401)
    ax1.plot(grid, ci_objective(grid, P1, P2), "-", color="0.3", lw=1.2, label="tr P(ω), sensor 2 three times more precise")
    fruit_fly_label = "FOA (30 × 200), one point per seed"
    if seeds is not None:
        ax1.plot(seeds.fruit_fly_x, seeds.fruit_fly_fun, ".", color=color("FOA (30 × 200)"), ms=3, alpha=0.5, label=fruit_fly_label)
    for i, (name, r) in enumerate(res.items()):
        ax1.plot(r.x, r.fun, "o^sx"[i], color=color(name), ms=7, mfc="none", label=name)
    ax1.set(xlabel="ω", ylabel="tr P(ω) (m², m²/s²)", title="optimum at the end ω = 0")
    if aniso is not None and ax3 is not None:
        PC, PD, res_an, fa = aniso
        w0 = float(res_an["closed form"].x)
        half = max(0.004, 1.5 * float(np.max(np.abs(fa.fruit_fly_x - w0))))
        zoom = np.linspace(max(0.0, w0 - half), min(1.0, w0 + half), 401)
        base = float(res_an["closed form"].fun)
        ax3.plot(zoom, ci_objective(zoom, PC, PD) - base, "-", color="0.3", lw=1.2, label="tr P(ω), anisotropic pair")
        ax3.plot(fa.fruit_fly_x, fa.fruit_fly_fun - base, ".", color=color("FOA (30 × 200)"), ms=4, alpha=0.6)
        for i, (name, r) in enumerate(res_an.items()):
            ax3.plot(r.x, r.fun - base, "o^sx"[i], color=color(name), ms=7, mfc="none")
        ax3.set(xlabel="ω", ylabel="tr P(ω) − minimum (m², m²/s²)", title=f"anisotropic pair: optimum inside ({w0:.3f})")
        ax3.ticklabel_format(axis="y", style="sci", scilimits=(-3, 3))
    handles, labels = ax1.get_legend_handles_labels()
    if ax3 is not None:
        h3, l3 = ax3.get_legend_handles_labels()
        handles, labels = handles + h3, labels + l3
    top.legend(handles, labels, loc="outside lower center", ncols=2, fontsize=9)
    ax2 = bottom.subplots(1, 1)
    x = np.arange(2)
    ax2.bar(x - 0.2, [pub["foa_time_s"][0], pub["grid_time_s"][0]], 0.4, color="0.6", label="published (MATLAB)")
    ax2.bar(x + 0.2, [m["foa_vectorised"], m["grid_vectorised"]], 0.4, color=color("exhaustive, 1001 points"),
            label="ours (vectorised)")
    ax2.axhline(m["closed_form"], color=color("closed form"), ls="--", lw=1, label="ours, closed form")
    ax2.set(xticks=x, xticklabels=["FOA", "exhaustive"], yscale="log", ylim=(1e-5, 10), ylabel="time per call (s)",
            title="time to choose ω")
    bottom.legend(*ax2.get_legend_handles_labels(), loc="outside right center", fontsize=9)
    return fig


@reads_results("fruit_fly_seeds")
def fig5_hypotheses(P1: ArrayLike, P2: ArrayLike, fruit_fly_seeds: FruitFlySeeds, seed: int, short_budget: int = 23,
                    n_open: int = 300, flat_pair: tuple[ArrayLike, ArrayLike] | None = None) -> pd.DataFrame:
    r"""Hypotheses for the published Fig. 5 optima (FOA 0.0018, exhaustive search 0.0033) on a CI objective.

    On a pair whose trace-optimal CI weight is an end of [0, 1] (here ω = 0), each search's answer
    is an artefact of how it approaches that end:

    * an exhaustive search whose grid includes ω = 0 (1001 points) returns 0;
    * a grid ``k / n_open``, k = 1…n_open, that omits ω = 0 returns its first point, 1/300 = 0.0033 for 300;
    * FOA's candidates are :math:`1/D` with :math:`D` the swarm's distance from the origin; with the printed
      step rule each coordinate grows by up to 20 per generation (:math:`D` by up to :math:`20\sqrt 2`), so its
      answer falls like 1/iterations: the printed 30 × 200 (median over ``fruit_fly_seeds``) and a budget of
      ``short_budget`` generations;
    * on the source's own identical sensors (``flat_pair``) the objective is flat, and the grid ``k / n_open``
      keeping the first of tied values returns 1/300 as well: the grid hypothesis does not need an asymmetric pair.

    ``n_open = 300`` and ``short_budget = 23`` are each one parameter fitted to one published number.

    Parameters
    ----------
    P1, P2 : array_like, shape (n, n)
        The two covariances.
    fruit_fly_seeds : FruitFlySeeds
        FOA with the printed budget on the same pair (:func:`fusion.scenarios.two_sensor.fruit_fly_over_seeds`).
    seed : int
        First seed of the short-budget FOA runs (one per seed of ``fruit_fly_seeds``).
    short_budget : int
        Generations of the short-budget FOA (23: the budget whose median answer rounds to the published
        0.0018 among 20-26, a one-parameter fit to one number).
    n_open : int
        Points of the grid that omits ω = 0 (1: the one point ω = 1); the objective holds four arrays of
        ``n_open`` matrices of the size of ``P1`` at once, within the memory budget (``fusion._counts.MAX_ELEMENTS``).
    flat_pair : (array_like, array_like), optional
        Two equal covariances (the source's identical sensors) for the last hypothesis; skipped if ``None``. Its
        grid ``k / n_open`` on their size is within the memory and work budgets (a ValueError names ``flat_pair and
        n_open``), checked before any work.

    Returns
    -------
    pandas.DataFrame
        Per hypothesis: ω found (median over seeds for FOA), :math:`\operatorname{tr}P` there (FOA: median
        over seeds), the published value it is set against, and whether they agree at the published 4
        decimals.
    """
    instance_of(fruit_fly_seeds, FruitFlySeeds, "fruit_fly_seeds")
    # an integer seed (rule 11), named; the short runs use seed .. seed + len(fruit_fly_seeds.seeds) - 1 (fuzz 55 C1)
    seed = check_seed(seed, span=len(fruit_fly_seeds.seeds) - 1)
    P1, P2 = as_covariance(P1, name="P1"), as_covariance(P2, name="P2")
    short_budget, n_open = count(short_budget, "short_budget"), count(n_open, "n_open")
    # the grid's objective holds four (n_open, n, n) arrays at once (the two weighted inverses, their sum and its
    # inverse): the memory budget, named n_open before any work (fuzz 26c q9)
    allocation((n_open, 4) + P1.shape, "n_open (with the size of P1)")
    flat_pair = _flat_pair_read(flat_pair, n_open)   # read once, its grid on its size, at entry (60a C5, 61a C2)
    from fusion.optimise.scalar import batch_budget
    from fusion.scenarios.two_sensor.weights import _CI_COSTS, _over_seeds_budget

    # the short-budget batch (one swarm of 30 per seed of fruit_fly_seeds), named here (fuzz 24c WN): its memory, and
    # its work with its objective's cost on P1's size (fuzz 59a C1: batch_budget alone counts a cheap objective)
    short_names, n_short = "short_budget (with fruit_fly_seeds)", len(fruit_fly_seeds.seeds)
    batch_budget(n_short, 30, short_budget, short_names)
    _over_seeds_budget(n_short, 0, 30, short_budget, P1.shape[0], _CI_COSTS, short_names)
    pub = data.WANG2024_FOA.columns

    def objective(w: ArrayLike) -> Any:
        return ci_objective(w, P1, P2)

    open_grid = np.arange(1, n_open + 1) / n_open
    w_open = float(open_grid[int(np.argmin(objective(open_grid)))])
    short = [r.x for r in fruit_fly_batch(objective, [np.random.default_rng(seed + i) for i in range(len(fruit_fly_seeds.seeds))],
                                          iterations=short_budget)]   # fruit_fly seed by seed, flown together
    g = grid_search(objective, 1001, vectorized=True)
    short_fun = [float(objective(w)) for w in short]
    rows = [
        ("exhaustive search, 1001 points including ω = 0", g.x, g.fun, pub["grid_optimum"][0]),
        (f"exhaustive search on k/{n_open}, k = 1…{n_open} (ω = 0 omitted)", w_open, float(objective(w_open)),
         pub["grid_optimum"][0]),
        (f"FOA 30 × 200 as printed (median of {len(fruit_fly_seeds.seeds)} seeds)", float(np.median(fruit_fly_seeds.fruit_fly_x)),
         float(np.median(fruit_fly_seeds.fruit_fly_fun)), pub["foa_optimum"][0]),
        (f"FOA 30 × {short_budget} (median of {len(short)} seeds)", float(np.median(short)), float(np.median(short_fun)),
         pub["foa_optimum"][0]),
    ]
    if flat_pair is not None:   # the source's identical sensors: every ω ties, the first grid point wins
        F1, F2 = flat_pair   # the covariances read and checked at entry
        if n_open == 1:   # the one-point grid k/1 is ω = 1 (grid_search needs two points): fuzz 26c A7
            flat_x, flat_fun = 1.0, float(ci_objective(1.0, F1, F2))
        else:
            flat = grid_search(lambda w: ci_objective(w, F1, F2), n_open, lo=1.0 / n_open, hi=1.0, vectorized=True)
            flat_x, flat_fun = flat.x, flat.fun
        rows.append((f"the same grid k/{n_open} on the source's identical sensors (flat objective, first of the ties)",
                     flat_x, flat_fun, pub["grid_optimum"][0]))
    t = pd.DataFrame(rows, columns=["hypothesis", OMEGA_FOUND, TR_P, "published ω"]).set_index("hypothesis")
    t[TR_P] = t[TR_P].round(3)
    t["equal at 4 decimals"] = np.round(t[OMEGA_FOUND], 4) == np.round(t["published ω"], 4)
    t[OMEGA_FOUND] = t[OMEGA_FOUND].round(5)
    return t


def printed_weight_facts(scenarios: Sequence[Scenario], k: int, seeds: ArrayLike, n_grid: int = 200) -> PrintedWeightFacts:
    r"""What eqs. 11-12 as printed do with their own optimisation of ω (source §2.2: minimise the covariance's size).

    Parameters
    ----------
    scenarios : sequence of Scenario
        Two-sensor cases (e.g. the printed identical sensors and the anisotropic pair). At every step of each,
        the trace of the printed fusion (:func:`fusion.estimates.ci.split_ci_objective`, ``same_omega=True``) is
        evaluated on the grid :math:`j/n`, :math:`j = 1 \dots n`, all steps at once; where it falls strictly along
        the grid the trace-optimal weight is the end ω = 1 (what :func:`fusion.filtering.tracks.fuse_tracks` with
        ``"printed"`` returns, tested).
    k : int
        Step at which FOA is run on the printed objective of the first scenario.
    seeds : array_like of int
        FOA seeds (:func:`fusion.scenarios.two_sensor.printed_fruit_fly_over_seeds`, 30 × 200).
    n_grid : int
        Points of the grid on (0, 1]; every step's covariances on it are held at once, so steps × ``n_grid`` ×
        n × n must stay within the memory budget (``fusion._counts.MAX_ELEMENTS``; a ValueError names
        ``n_grid``).

    Returns
    -------
    PrintedWeightFacts
        FOA run at step ``k`` of the first scenario; the trace ratio and traces at that step.

    Raises
    ------
    TypeError
        ``scenarios`` not a sequence of Scenario, ``k``, ``n_grid`` or a seed not an integer.
    ValueError
        ``scenarios`` empty or repeating a sensor pair (two scenarios with the same local covariances: the same
        pair at the same period, whose steps would be counted twice, whatever their runs); ``k`` not a step of the
        first; ``seeds`` empty or repeating a seed; ``n_grid`` below 2 or beyond the memory budget; ``scenarios``,
        ``seeds`` and ``n_grid`` whose grids, repeat rule and searches are beyond the work budget
        (``fusion._limits.MAX_WORK``), before any seed is read.
    """
    scs = sequence(scenarios, "scenarios", minimum=1, what="Scenario")
    for i, sc in enumerate(scs):
        instance_of(sc, Scenario, f"scenarios[{i}]")
    n_grid = count(n_grid, "n_grid", minimum=2)
    seeds, n_seeds = _counted(seeds, "seeds")   # read once, counted (fuzz 68b: an __array__ object counted one)
    _printed_facts_budget([sc.tracks[0].Pd.shape for sc in scs], n_grid, n_seeds)
    for j, sc in enumerate(scs):   # the repeat rule (fuzz 26c q3): the counts read the covariances, not the runs
        parts = [x for tr in sc.tracks for x in (tr.Pd, tr.Pi)]
        for i in range(j):
            earlier = [x for tr in scs[i].tracks for x in (tr.Pd, tr.Pi)]
            if all(a.shape == b.shape and np.allclose(a, b, rtol=1e-12, atol=0.0) for a, b in zip(parts, earlier)):
                raise ValueError(f"scenarios must not repeat a sensor pair: scenarios[{j}] has the covariances of "
                                 f"scenarios[{i}] (the same pair at the same period, whatever its runs), whose steps "
                                 "would be counted twice")
    k = _step_index(k, "k", scs[0].tracks[0].Pd.shape[0])
    seeds = check_seeds(seeds, "seeds")   # the list checked is the list used (fuzz 58b C1)

    for i, sc in enumerate(scs):   # every step's covariances on the grid at once (fuzz 24c SZ: 6 GiB for 2e5)
        allocation(sc.tracks[0].Pd.shape[:1] + (n_grid,) + sc.tracks[0].Pd.shape[1:],
                   f"n_grid (with the steps of scenarios[{i}])")
    w = (np.arange(1, n_grid + 1) / n_grid)[None, :, None, None]
    ones = steps = 0
    for sc in scs:
        a, b = sc.tracks
        inv = np.linalg.inv
        info = inv(a.Pd[:, None] / w + a.Pi[:, None]) + inv(b.Pd[:, None] / w + b.Pi[:, None])
        trace = np.trace(inv(info), axis1=-2, axis2=-1)          # (K, n_grid)
        ones += int(np.sum(np.all(np.diff(trace, axis=1) < 0, axis=1)))
        steps += int(trace.shape[0])
    a, b = scs[0].tracks
    parts = (a.Pd[k], a.Pi[k], b.Pd[k], b.Pi[k])
    w_pub = float(data.WANG2024_FOA.columns["foa_optimum"][0])
    shown = (w_pub, float(data.WANG2024_FOA.columns["grid_optimum"][0]), 0.01, 0.1, 0.5, 1.0)
    return PrintedWeightFacts(ones=ones, steps=steps, fruit_fly=two_sensor.printed_fruit_fly_over_seeds(*parts, seeds),
                              monotone=ones == steps,
                              trace_ratio=float(split_ci_objective(w_pub, *parts, same_omega=True)
                                                / split_ci_objective(1.0, *parts, same_omega=True)),
                              trace={x: float(split_ci_objective(x, *parts, same_omega=True)) for x in shown})


@_glue_doc("microseconds, milliseconds, seconds or ratios, as the prose shows them")
@reads_results("bench")
def timing_numbers(bench: TimingBenchmark) -> GlueValues:
    """The numbers the prose quotes from the timing benchmark (glue keys ``ci_bench_*``, ``ci_*_us``, ...).

    Parameters
    ----------
    bench : TimingBenchmark
        :func:`timing_benchmark` (``benchmarks/results/ci.json``).
    """
    instance_of(bench, TimingBenchmark, "bench")   # its constructor checked its types and values
    for field, keys in (("measurements", _BENCH_MEASUREMENTS), ("per_step", _BENCH_PER_STEP)):
        missing = [k for k in keys if k not in getattr(bench, field)]
        if missing:
            raise ValueError(f"bench.{field} misses the keys {shown(missing, 200)} (the prose quotes them)")
    m, ps = bench.measurements, bench.per_step
    empty = [k for k in _BENCH_PER_STEP if not len(ps[k])]
    if empty:   # the prose quotes their means (fuzz 26c q5: "value must be finite, got nan")
        raise ValueError(f"bench.per_step holds empty series {shown(empty, 200)} (the prose quotes their means)")
    pub_fruit_fly, times = data.WANG2024_FOA.columns, data.WANG2024_TIMES.columns
    return {"ci_bench_machine": bench.machine, "ci_bench_date": bench.date,
            "ci_closed_us": rounded(1e6 * m["closed_form"], 2),
            "ci_target_us": rounded(1e6 * float(pub_fruit_fly["foa_time_s"][0]) / 1000, 3),
            "ci_foa_ms": rounded(1e3 * m["foa_vectorised"], 2), "ci_foa_vs_closed": rounded(m["ratio_foa_vs_closed"], 2),
            "ci_loop_vs_vector": rounded(m["ratio_loop_vs_vector"], 2),
            "ci_improved_vs_ci": rounded(m["ratio_improved_vs_ci"], 2), "ci_sim_foa_s": rounded(m["sim_ci_foa"], 2),
            "ci_sim_ci_bounded": rounded(m["sim_ci_bounded"], 2), "ci_sim_improved": rounded(m["sim_improved"], 2),
            "ci_sim_ci": rounded(m["sim_ci"], 2),
            "ci_search_ci_p": rounded(m["search_ci_printed"], 2), "ci_search_split_p": rounded(m["search_split_printed"], 2),
            "ci_search_ci_a": rounded(m["search_ci_anisotropic"], 2),
            "ci_search_split_a": rounded(m["search_split_anisotropic"], 2),
            "ci_search_ev_ci_p": rounded(float(np.mean(ps["search_ci_printed_evaluations"])), 1),
            "ci_search_ev_split_p": rounded(float(np.mean(ps["search_split_printed_evaluations"])), 1),
            "ci_search_ev_ci_a": rounded(float(np.mean(ps["search_ci_anisotropic_evaluations"])), 1),
            "ci_search_ev_split_a": rounded(float(np.mean(ps["search_split_anisotropic_evaluations"])), 1),
            "ci_t1_rem_ci": rounded(float(times["ci"][0] - pub_fruit_fly["grid_time_s"][0]), 4),
            "ci_t1_rem_imp": rounded(float(times["improved"][0] - pub_fruit_fly["foa_time_s"][0]), 4)}


@_glue_doc()
@reads_results("fruit_fly_seeds")
def weight_search_numbers(res: Mapping[str, OptimumResult], flat: ArrayLike, fruit_fly_seeds: FruitFlySeeds,
                          suffix: str = "", omit: Sequence[str] = ()) -> GlueValues:
    """The numbers the prose quotes from the weight searches (glue keys ``ci_flat_range``, ``ci_foa_*``, ...).

    Parameters
    ----------
    res : mapping
        Search -> result (:func:`weight_search`), with ``"closed form"``.
    flat : array_like
        The CI objective on identical sensors at 11 weights (finite and positive: a covariance's trace).
    fruit_fly_seeds : FruitFlySeeds
        FOA over 100 seeds (:func:`fusion.scenarios.two_sensor.fruit_fly_over_seeds`, its default 1001-point grid)
        on the pair of ``res``: its exhaustive search must end where ``res``'s does (ω, and tr P to a relative
        1e-9), else a ValueError (another pair's optima).
    suffix : str
        Appended to every key (another pair's numbers, e.g. ``"_an"``): ASCII letters, digits and underscores, the
        rule of a glue-key prefix.
    omit : sequence of str
        Keys (without the suffix) left out: those the prose does not quote for this pair.
    """
    instance_of(fruit_fly_seeds, FruitFlySeeds, "fruit_fly_seeds")
    res = _entries(_results(res, "res", OptimumResult, "weight_search"), "res", _SEARCH_METHODS, "weight_search",
                   numbers=False)
    _same_search(res, fruit_fly_seeds)   # one pair's searches (fuzz 24c MM)
    flat = _objective_grid(flat, "flat")   # ptp/mean: a zero mean was divided by (fuzz 36b B6)
    suffix = _glue_suffix(text_argument(suffix, "suffix"), "suffix")
    omit = [text_argument(o, f"omit[{i}]") for i, o in enumerate(sequence(omit, "omit"))]
    best = res["closed form"].fun
    out = {"ci_flat_range": f"{roundoff(np.ptp(flat) / abs(float(np.mean(flat))))} of its value", "ci_flat_level": readable(float(np.mean(flat)), 3), "ci_foa_evals": int(res["FOA (30 × 200)"].n_evaluations),
            "ci_scipy_evals": int(res["scipy bounded Brent"].n_evaluations),
            "ci_foa_end": excess_text(res["FOA (30 × 200)"].fun - best),
            "ci_grid_end": excess_text(res["exhaustive, 1001 points"].fun - best),
            "ci_foa_seeds": len(fruit_fly_seeds.seeds), "ci_omega_a": rounded(res["closed form"].x, 4), "ci_foa_reached": round(fruit_fly_seeds.share_reached * len(fruit_fly_seeds.seeds)),
            "ci_foa_better": round(fruit_fly_seeds.share_better * len(fruit_fly_seeds.seeds)),
            "ci_foa_median_excess": readable(fruit_fly_seeds.median_excess),
            "ci_foa_median_dw": readable(float(np.median(np.abs(fruit_fly_seeds.fruit_fly_x - res["closed form"].x)))),
            "ci_grid_dw": readable(abs(res["exhaustive, 1001 points"].x - res["closed form"].x))}
    unknown = sorted(set(omit) - set(out))
    if unknown:
        raise ValueError(f"omit: not keys of the weight-search numbers: {unknown}")
    return {k + suffix: v for k, v in out.items() if k not in omit}


@reads_results("sc", "study")
@study_defaults("sc", "steps", "split_step")  # a default the study does not fit, named by the study (fuzz 34b D2)
def weight_numbers(sc: Scenario, study: FusionStudy, w_fruit_fly: ArrayLike, w_grid: ArrayLike, rng: np.random.Generator,
                   steps: Sequence[int] = (30, 60, 120), split_step: int = 60) -> GlueValues:
    """The numbers the prose quotes on the per-step CI weights (glue keys ``ci_omega_trace``, ``ci_w_*``, ...).

    Parameters
    ----------
    sc : Scenario
        The two-sensor case of ``study``.
    study : FusionStudy
        :func:`fusion.scenarios.two_sensor.fusion_study` on ``sc``.
    w_fruit_fly, w_grid : array_like, shape (K,)
        FOA's and the grid's weight per step (:func:`fusion.scenarios.two_sensor.per_step_weights`).
    rng : numpy.random.Generator
        Drives FOA on the split-CI objective (:func:`split_fruit_fly_gap`).
    steps : sequence of int
        Steps whose closed-form weight (:func:`fusion.estimates.ci.ci_weight`) is averaged.
    split_step : int
        Step of :func:`split_fruit_fly_gap`.

    Returns
    -------
    dict
        ``ci_omega_trace``: mean closed-form ω over ``steps`` (3 decimals); ``ci_same_text``: how far CI and the
        convex combination of ``study`` differ (m); ``ci_w_foa_range``, ``ci_w_grid_range``: ``"min-max"`` of the
        weights over the steady steps; ``ci_split_gap``: :func:`split_fruit_fly_gap`.

    Raises
    ------
    TypeError
        A step not an integer, a weight not a number, ``rng`` not a Generator.
    ValueError
        If the weights do not have one finite entry in [0, 1] per step, ``steps`` is empty, a step is outside the
        scenario, or ``study`` is not ``fusion_study`` of ``sc`` (its steps, truth or local tracks differ).
    """
    _study_of(sc, study)
    w_fruit_fly = _per_step(w_fruit_fly, "w_fruit_fly", study.t.size, "step", unit=True)
    w_grid = _per_step(w_grid, "w_grid", study.t.size, "step", unit=True)
    a, b = sc.tracks
    K = a.gains.P.shape[0]
    steps = _indices(steps, "steps", K)
    split_step = _step_index(split_step, "split_step", K)
    as_rng(rng, "rng")
    omegas = [ci_weight(a.gains.P[k], b.gains.P[k]) for k in steps]
    same = np.max(np.abs(study.est[StudyMethod.CI] - study.est[StudyMethod.CONVEX]))
    steady = study.steady
    return {"ci_omega_trace": rounded(float(np.mean(omegas)), 3),
            "ci_same_text": "identical to the last digit" if same == 0 else f"largest difference {readable(same)} m",
            "ci_w_foa_range": f"{w_fruit_fly[steady].min():.3f}-{w_fruit_fly[steady].max():.3f}",
            "ci_w_grid_range": f"{w_grid[steady].min():.3f}-{w_grid[steady].max():.3f}",
            "ci_split_gap": readable(split_fruit_fly_gap(sc, split_step, rng))}


#: The methods of :func:`weight_search`, the keys of :attr:`WeightPair.res`.
_SEARCH_METHODS = ("FOA (30 × 200)", "exhaustive, 1001 points", "scipy bounded Brent", "closed form")


def _step_relation(values: Mapping[str, Any], cls: str) -> None:
    """The searched step ``k`` is a step of the scenario's tracks."""
    steps = values["sc"].tracks[0].est.shape[1]
    if values["k"] >= steps:
        raise ValueError(f"{cls}.k must be a step index in [0, {steps}) of {cls}.sc, got {values['k']}")


@dataclass(frozen=True)
class WeightPair:
    """A sensor pair on which CI's weight is searched at one step (:func:`weight_pair`).

    Attributes
    ----------
    R1, R2 : ndarray, shape (2, 2)
        Measurement covariances (m²).
    seed : int
        Seed of the scenario's runs.
    k : int
        Step of the search.
    sc : Scenario
        The two-sensor case.
    P1, P2 : ndarray, shape (4, 4)
        The local tracks' covariances at step ``k``.
    res : dict of str to OptimumResult
        :func:`weight_search` on ``(P1, P2)``.
    fruit_fly_seeds : FruitFlySeeds
        :func:`fusion.scenarios.two_sensor.fruit_fly_over_seeds` on ``(P1, P2)``.
    """

    R1: np.ndarray
    R2: np.ndarray
    seed: int
    k: int
    sc: Scenario
    P1: np.ndarray
    P2: np.ndarray
    res: Mapping[str, OptimumResult]
    fruit_fly_seeds: FruitFlySeeds

    __result_spec__ = ResultSpec({"R1": array(2, 2, covariance=True), "R2": array(2, 2, covariance=True),
                                  "seed": integer(0), "k": integer(0), "sc": instance(Scenario),
                                  "P1": array(4, 4, covariance=True), "P2": array(4, 4, covariance=True),
                                  "res": dict_of(instance(OptimumResult), keys=_SEARCH_METHODS),
                                  "fruit_fly_seeds": instance(FruitFlySeeds)},
                                 relations=(lambda v, cls: _step_relation(v, cls),))
    __post_init__ = validated_post_init

    def ml_gap(self) -> float:
        """:func:`ml_vs_product` on the two tracks' estimates and covariances at step ``k`` (m).

        Returns
        -------
        float
            The largest difference between the maximum-likelihood and the multi-Bayesian fused estimates over the runs
            (m).
        """
        a, b = self.sc.tracks
        return ml_vs_product(a.est[:, self.k], self.P1, b.est[:, self.k], self.P2)


def weight_pair(R1: ArrayLike, R2: ArrayLike, Q: ArrayLike, k: int, seed: int, search_seed: int, fruit_fly_seeds: ArrayLike,
                runs: int = 50, T: float = 1.0) -> WeightPair:
    """Run a sensor pair and search CI's weight at step ``k``: every method of :func:`weight_search`, FOA over seeds.

    Parameters
    ----------
    R1, R2 : array_like, shape (2, 2)
        Measurement covariances (m²).
    Q : array_like, shape (4, 4)
        Process-noise covariance (m², m²/s²).
    k : int
        Step of the search.
    seed : int
        Seed of the runs (:func:`fusion.scenarios.two_sensor.two_sensor_scenario`).
    search_seed : int
        Seed of :func:`weight_search`'s FOA.
    fruit_fly_seeds : array_like of int
        Seeds of :func:`fusion.scenarios.two_sensor.fruit_fly_over_seeds`.
    runs : int
        Monte-Carlo runs of the scenario.
    T : float
        Sampling period (s); a float32 one is the decimal it prints as (``_period_key``).

    Returns
    -------
    WeightPair
        The pair's noise, seed, scenario and step ``k``, both covariances there, every method's optimum and FOA's
        optimum per seed.

    Raises
    ------
    TypeError
        A seed, ``k`` or ``runs`` not an integer, a covariance not numeric.
    ValueError
        If ``k`` is not a step of the scenario, ``R1`` or ``R2`` not a diagonal 2 × 2 covariance, a seed negative or
        ``fruit_fly_seeds`` empty, repeated or beyond FOA's budgets (30 × 200 per seed); ``runs``, ``T`` and
        ``fruit_fly_seeds`` whose scenario and searches together hold or run beyond the memory or work budget, before
        the scenario.
    """
    seed = check_seed(seed)   # an integer seed (rule 11), named
    search_seed = check_seed(search_seed, "search_seed")
    # the callee's rules (integers, no repeat, the batch's budgets) named here, before the scenario (fuzz 26c A3)
    from fusion.book._study_budget import studies_first
    from fusion.scenarios.two_sensor.case import _scenario_budget
    from fusion.scenarios.two_sensor.weights import _CI_COSTS, _over_seeds_budget
    # the searches' budget by the seeds' count first (book audit 76: a 10**7 list was checked, 3.1 CPU-s, then hashed)
    fruit_fly_seeds, n_fly = _counted(fruit_fly_seeds, "fruit_fly_seeds")   # read once, counted (fuzz 68b C1's class)
    studies_first([lambda: _over_seeds_budget(n_fly, 1001, 30, 200, 4, _CI_COSTS, "fruit_fly_seeds")],
                  "runs, T and fruit_fly_seeds")
    fly = distinct(check_seeds(fruit_fly_seeds, "fruit_fly_seeds"), "fruit_fly_seeds")

    _sensor_noises(R1, R2)
    T = _period_key(T)   # the chapter's period rule
    runs, steps = count(runs, "runs"), two_sensor.trajectory(T).t.size   # type: ignore[arg-type]
    # the scenario and fruit_fly_over_seeds' printed 30 x 200 per seed (on the scenario's 4 x 4 covariances), each by
    # its own budget, summed before the scenario (the audit after fuzz 57a; fuzz 59a C1: the searches were counted
    # by batch_budget, without their objective)
    studies_first([lambda: _over_seeds_budget(len(fly), 1001, 30, 200, 4, _CI_COSTS, "fruit_fly_seeds"),
                   lambda: _scenario_budget(runs, steps, "runs and T")], "runs, T and fruit_fly_seeds")
    sc = two_sensor.two_sensor_scenario(R1, R2, Q, np.random.default_rng(seed), runs=runs,
                                        T=T)  # type: ignore[arg-type]
    a, b = sc.tracks
    k = _step_index(k, "k", a.gains.P.shape[0])
    P1, P2 = a.gains.P[k], b.gains.P[k]
    res = weight_search(P1, P2, np.random.default_rng(search_seed))
    return WeightPair(R1=np.asarray(R1, dtype=float), R2=np.asarray(R2, dtype=float), seed=seed, k=k, sc=sc, P1=P1,
                      P2=P2, res=res, fruit_fly_seeds=two_sensor.fruit_fly_over_seeds(P1, P2, fruit_fly_seeds))


#: Field specs of :class:`WeightClaimInputs` (``fusion._results``), shared with the ledger's bundles that hold them.
_WEIGHT_FIELDS = {"fruit_fly_seeds": instance(FruitFlySeeds), "fruit_fly_step": integer(1), "foa_evaluations": integer(0),
                  "ml_gap": number(), "fruit_fly_seeds_aniso": instance(FruitFlySeeds),
                  "omega_aniso": number(bounds=(0.0, 1.0)), "flat_level": number(positive=True)}


@dataclass(frozen=True)
class WeightClaimInputs:
    """The ledger's entries on the weight search (:func:`weight_claim_inputs`).

    Attributes
    ----------
    fruit_fly_seeds : FruitFlySeeds
        FOA over seeds on the pair with sensor 2 three times more precise.
    fruit_fly_step : int
        The step of that pair's search.
    foa_evaluations : int
        Objective evaluations of FOA (30 × 200) there.
    ml_gap : float
        :meth:`WeightPair.ml_gap` of that pair (m).
    fruit_fly_seeds_aniso : FruitFlySeeds
        FOA over seeds on the anisotropic pair.
    omega_aniso : float
        The closed-form ω of the anisotropic pair.
    flat_level : float
        Mean of tr P(ω) of identical sensors over the grid of ω.
    """

    fruit_fly_seeds: FruitFlySeeds
    fruit_fly_step: int
    foa_evaluations: int
    ml_gap: float
    fruit_fly_seeds_aniso: FruitFlySeeds
    omega_aniso: float
    flat_level: float

    __result_spec__ = ResultSpec(_WEIGHT_FIELDS)
    __post_init__ = validated_post_init



def _pair_noises(asym: WeightPair, aniso: WeightPair, names: tuple[str, str] = ("asym", "aniso"),
                 same_search: bool = False) -> None:
    """The two pairs of :func:`weight_claim_inputs` and :func:`paired_studies` told apart by the noises they record
    (fuzz 24c MM, fuzz 26c B1): ``aniso`` at ``ANISO_R``, ``asym`` with sensor 2 three times more precise
    (``R2 = R1 / 9``, relative 1e-12); ``names`` are the arguments' names. With ``same_search`` (fuzz 26c q7: the
    ledger quotes one step for both searches), both searched at the same step ``k`` of runs at the same period."""
    from fusion.book.chapters.ci.tracking import ANISO_R

    asym_name, aniso_name = names
    if not (np.allclose(aniso.R1, ANISO_R[0], rtol=1e-12, atol=0.0)
            and np.allclose(aniso.R2, ANISO_R[1], rtol=1e-12, atol=0.0)):
        raise ValueError(f"{aniso_name} must be a weight_pair of ANISO_R (the anisotropic pair), got R1 = "
                         f"{shown(aniso.R1.tolist(), 80)}, R2 = {shown(aniso.R2.tolist(), 80)}")
    if not np.allclose(asym.R2, asym.R1 / 9, rtol=1e-12, atol=0.0):
        raise ValueError(f"{asym_name} must be a weight_pair with sensor 2 three times more precise (R2 = R1 / 9), got "
                         f"R1 = {shown(asym.R1.tolist(), 80)}, R2 = {shown(asym.R2.tolist(), 80)}")
    if not same_search:
        return
    if aniso.k != asym.k:
        raise ValueError(f"{aniso_name} is searched at step {aniso.k} and {asym_name} at step {asym.k}: the ledger "
                         "quotes one step for both (give weight_pair the same k)")
    t_a, t_n = asym.sc.t, aniso.sc.t
    if t_a.shape != t_n.shape or not np.allclose(t_a, t_n, rtol=1e-12, atol=0.0):
        raise ValueError(f"{aniso_name} and {asym_name} are runs at other periods or of other lengths ({t_n.size} "
                         f"steps to {shown(float(t_n[-1]))} s, {t_a.size} steps to {shown(float(t_a[-1]))} s): the "
                         "ledger quotes one step for both (give weight_pair the same T)")


@reads_results("asym", "aniso")
def weight_claim_inputs(asym: WeightPair, aniso: WeightPair, flat: ArrayLike) -> WeightClaimInputs:
    """The ledger's entries on the weight search (for ``claims``): both pairs and the flat objective.

    The anisotropic pair's seed and the objective's range are entries of :func:`ledger_studies`.

    Parameters
    ----------
    asym : WeightPair
        Sensor 2 three times more precise (the optimum at the end ω = 0).
    aniso : WeightPair
        The anisotropic pair (``ANISO_R``, the optimum inside (0, 1)).
    flat : array_like
        tr P(ω) of identical sensors on a grid of ω (:func:`fusion.estimates.ci.ci_objective`; positive).

    Returns
    -------
    WeightClaimInputs
        FOA's optima per seed on both pairs, its step and evaluations, the ML gap, the anisotropic closed-form ω and
        the flat objective's mean.

    Raises
    ------
    TypeError
        ``asym`` or ``aniso`` not a WeightPair, ``flat`` not numeric.
    ValueError
        ``flat`` not a 1-D array of finite positive numbers; ``aniso`` not a pair at ``ANISO_R`` or ``asym`` not one with
        ``R2 = R1 / 9`` (the pairs swapped, or one pair twice: the ledger would read one pair's optima as the
        other's); the two searched at other steps ``k`` or on runs at other periods (the ledger quotes one step).
    """
    instance_of(asym, WeightPair, "asym")
    instance_of(aniso, WeightPair, "aniso")
    _pair_noises(asym, aniso, same_search=True)
    flat = _objective_grid(flat, "flat")   # its mean divides the range in the ledger (fuzz 36b B6)
    return WeightClaimInputs(fruit_fly_seeds=asym.fruit_fly_seeds, fruit_fly_step=asym.k,
                             foa_evaluations=asym.res["FOA (30 × 200)"].n_evaluations, ml_gap=asym.ml_gap(),
                             fruit_fly_seeds_aniso=aniso.fruit_fly_seeds, omega_aniso=aniso.res["closed form"].x,
                             flat_level=float(np.mean(flat)))


#: Measurements and per-step series of the stored timing benchmark that :func:`timing_numbers` reads.
_BENCH_MEASUREMENTS = ("closed_form", "foa_vectorised", "ratio_foa_vs_closed", "ratio_loop_vs_vector",
                      "ratio_improved_vs_ci", "sim_ci_foa", "sim_ci_bounded", "sim_improved", "sim_ci",
                      "search_ci_printed", "search_split_printed", "search_ci_anisotropic", "search_split_anisotropic")
_BENCH_PER_STEP = tuple(f"search_{m}_{c}_evaluations" for m in ("ci", "split") for c in ("printed", "anisotropic"))


@dataclass(frozen=True)
class TimingBenchmark:
    """The stored timing benchmark of the chapter (``benchmarks/results/ci.json``, :func:`timing_benchmark`).

    Attributes
    ----------
    date : str
        ISO date of the run.
    machine : str
        Description of the machine that ran it.
    measurements : dict of str to float
        Measurement key -> stored value (s, or a count).
    per_step : mapping of str to tuple of float
        Per-step series of the weight searches (times in s, or evaluation counts) by key.
    """

    date: str
    machine: str
    measurements: Mapping[str, float]
    per_step: Mapping[str, tuple[float, ...]]

    __result_spec__ = ResultSpec({"date": text(), "machine": text(),
                                  "measurements": dict_of(number()), "per_step": dict_of(tuple_of(number()))})
    __post_init__ = validated_post_init


def timing_benchmark(results: Any = None) -> TimingBenchmark:
    """The stored timing benchmark of the chapter (``benchmarks/results/ci.json``, :func:`fusion.book.benchmarks.load_benchmark`).

    Parameters
    ----------
    results : pathlib.Path, optional
        Folder of the results (default :data:`fusion.book.benchmarks.RESULTS`).

    Returns
    -------
    TimingBenchmark
        The benchmark's date and machine, its measurements by key (s) and the per-step timings.

    Raises
    ------
    TypeError
        ``results`` not a path.
    ValueError
        As :func:`fusion.book.benchmarks.load_benchmark` (naming ``results``, or the stored benchmark when it is
        None); the stored ``ci.json`` without its per-step timings (``per_step``, a mapping). A per-step series
        may be empty here (it is what the file holds); :func:`timing_numbers` refuses an empty one it quotes.
    """
    from fusion.book.benchmarks import load_benchmark

    where = "the stored benchmark" if results is None else f"results ({shown(str(results), 80)})"
    try:
        res = load_benchmark("ci", results)
    except ValueError as e:   # load_benchmark names its own `name` (fixed here to "ci"): name results (fuzz 26c q5)
        msg = str(e)
        for head in ("name and results: ", "name: "):
            if msg.startswith(head):
                raise ValueError(f"{where}: {msg[len(head):]}") from None
        raise
    per_step = res.record.get("per_step")
    if not isinstance(per_step, Mapping):   # load_benchmark checks the measurements only (fuzz 24c, TB)
        raise ValueError(f"{where}: ci.json must hold 'per_step', a mapping of key -> per-step series, got "
                         f"{'none' if per_step is None else type(per_step).__name__}")
    return TimingBenchmark(date=res.date, machine=res.machine,
                           measurements={item["key"]: item["value"] for item in res.measurements},
                           per_step=dict(per_step))


#: How the labels of :func:`fig5_hypotheses`' five rows begin, in its order (their settings follow).
_HYPOTHESIS_ROWS = ("exhaustive search, 1001 points", "exhaustive search on k/", "FOA 30 × 200 as printed", "FOA 30 × ",
                    "the same grid k/")


def _hypothesis_table(table: object, name: str, columns: tuple[str, ...]) -> None:
    """The rule of every reader of :func:`fig5_hypotheses`' table (fuzz 29b B4: ``LedgerInputs.fig5_hyp`` took any
    table, ``ev_fig5`` then a KeyError): a DataFrame holding ``columns`` and its five rows in its order, read by
    position and told apart by their labels (q1); TypeError/ValueError naming ``name``."""
    _frame(table, name, columns, maker="fig5_hypotheses")
    if len(table) < 5:  # type: ignore[arg-type]
        raise ValueError(f"{name} must be fig5_hypotheses' table (five rows or more, columns {list(columns)})")
    for i, prefix in enumerate(_HYPOTHESIS_ROWS):
        label = table.index[i]  # type: ignore[attr-defined]
        if not isinstance(label, str) or not label.startswith(prefix) or (i == 3 and "as printed" in label):
            raise ValueError(f"{name} must hold fig5_hypotheses' rows in its order: row {i} must be the hypothesis "
                             f"{shown(prefix)}…, got {shown(label, 80)}")


def fig5_hypothesis_numbers(table: pd.DataFrame, evaluations: int = 30 * 200) -> GlueValues:
    """The numbers the prose quotes from :func:`fig5_hypotheses` (glue keys ``ci_h_*``).

    Parameters
    ----------
    table : pandas.DataFrame
        :func:`fig5_hypotheses` (rows: the hypotheses in its order; column ``"ω found"``).
    evaluations : int
        Objective evaluations of one published FOA run (30 flies × 200 generations).

    Returns
    -------
    dict
        ``ci_h_open``, ``ci_h_foa200``, ``ci_h_foa23``, ``ci_h_flat``: ω of rows 1-4; ``ci_h_per_eval_us``: the
        published FOA time per evaluation (µs); ``ci_h_grid_evals``: the published grid time in such evaluations
        (both to three significant digits; an int from 100 on).

    Raises
    ------
    TypeError
        ``table`` is not a DataFrame.
    ValueError
        ``table`` lacks the column ``"ω found"`` (or holds it twice) or holds fewer than five rows, or an ω read
        there (rows 2-5, by position: the hypotheses' labels carry their settings) is not a finite number in
        [0, 1] (TypeError for a non-number), named ``table``; a row's label not the hypothesis of
        :func:`fig5_hypotheses` at its position (rows reordered).
    """
    evaluations = count(evaluations, "evaluations")
    _hypothesis_table(table, "table", (OMEGA_FOUND,))
    pub = data.WANG2024_FOA.columns
    per_eval = float(pub["foa_time_s"][0]) / evaluations
    # each ω read by the glue rule (fuzz 22b, V11): a weight, a finite number in [0, 1], named
    w = [_glued_cell(table, table.index[i], OMEGA_FOUND, "table", lo=0.0, hi=1.0) for i in range(1, 5)]
    return {"ci_h_open": rounded(w[0], 4), "ci_h_foa200": rounded(w[1], 5), "ci_h_foa23": rounded(w[2], 5),
            "ci_h_flat": rounded(w[3], 4), "ci_h_per_eval_us": _three_digits(1e6 * per_eval),
            "ci_h_grid_evals": _three_digits(float(pub["grid_time_s"][0]) / per_eval)}


def _three_digits(x: float) -> float | int:
    """``x`` to three significant digits, an int when that is a whole number of 100 or more (fuzz 26c q8: a fixed
    rounding to the hundred glued 0 evaluations for a count of 3.3): 19,883 -> 19900, 31.33 -> 31.3, 3.31 -> 3.31."""
    v = float(f"{x:.3g}")
    return int(v) if v >= 100 and v.is_integer() else v
