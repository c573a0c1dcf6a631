"""The guarded filter (its usability against the plain one) and the filter-design study.

Part of :mod:`fusion.book.chapters.chernoff` (chapter 06, patent CN107330468B), which re-exports its public names."""

from __future__ import annotations

from collections.abc import Mapping
import dataclasses
from dataclasses import dataclass
from typing import Any

import numpy as np

from fusion._results import ResultSpec, array, dict_of, integer, number, validated_post_init
from fusion._validation import FloatArray, scalar
from fusion._counts import sequence
from fusion.book.tables import rounded
from fusion.scenarios.range_bearing_scenario import simulate_target
from fusion.scenarios.range_bearing import (GUARD_STAGES, RangeBearingScenario, TrackingRun, min_local_ess,
                                            run_tracking_batch, _block_allocation)
from fusion.book.chapters.chernoff.settings import (ALL_FRAMES, COLLAPSE_FRACTION, STUDY_RUNS, STUDY_WORKERS,
                                                    _check_study, guarded_scenario)
from fusion.book.chapters.chernoff.tracking import any_collapsed, per_run_mse, per_run_nees
from fusion.book.glue import GlueValues
from fusion._counts import count, seed as check_seed, workers as check_workers
from fusion._validation import instance_of
from fusion._limits import LOOP_STEP, loop_work

__all__ = ["guard_usability", "DesignStudy", "design_study", "guarded_runs", "guard_values"]


def guarded_runs(runs: list[TrackingRun], sc: RangeBearingScenario, seed: int,
                 workers: int = STUDY_WORKERS) -> list[TrackingRun]:
    """The study's runs with the collapse guard of every filter: collapsed runs redone, others reused.

    The guard (:func:`guarded_scenario`: progressive correction of an update whose effective sample
    size falls below :data:`COLLAPSE_FRACTION` of the filter's particles, for the nodes and the
    centralised filter) draws nothing in a run where no filter falls below the threshold, so such a run is
    identical with and without it (tested); only the runs in which some filter collapses
    (:func:`any_collapsed`) are run again, from their own seeds (with ``all_nodes`` where the run had it).

    Parameters
    ----------
    runs : list of TrackingRun
        The study without guard, ``monte_carlo(sc, seed, len(runs))``.
    sc : RangeBearingScenario
        Its scenario (without guard).
    seed : int
        Its root seed. Each run records its stream through its truth (drawn first, from the run's own stream), so
        runs of another seed, or in another order, are refused naming ``seed`` (fuzz 22b q8: the redone runs came
        from ``seed``'s streams and the kept ones stayed the runs' own).
    workers : int
        Processes for the redone runs (results do not depend on it).

    Returns
    -------
    list of TrackingRun
        What ``monte_carlo(guarded_scenario(sc), seed, len(runs))`` gives.

    Raises
    ------
    TypeError
        ``runs`` not a sequence of TrackingRun, ``sc`` not a RangeBearingScenario, ``workers`` not an integer.
    ValueError
        ``runs`` empty, of several scenarios or holding a run twice, or ``sc`` not the runs' scenario (but for the guard); ``workers``
        below 1 (checked whether or not a run is redone); ``seed`` not the runs' root seed.
    """
    seed = check_seed(seed)
    runs = _check_study(runs, sc)
    workers = check_workers(workers)  # checked whether or not a run is redone (issue 35: refused on every path)
    _runs_of_seed(runs, sc, seed)
    bad = any_collapsed(runs, sc)
    seeds = np.random.SeedSequence(seed).spawn(len(runs))
    idx = np.flatnonzero(bad)
    redo = (run_tracking_batch(guarded_scenario(sc), [seeds[j] for j in idx],
                               all_nodes=[runs[j].node_estimates is not None for j in idx], workers=workers)
            if bad.any() else [])
    out, it = [], iter(redo)
    for r, b in zip(runs, bad):
        out.append(next(it) if b else r)
    return out


def _runs_of_seed(runs: list[TrackingRun], sc: RangeBearingScenario, seed: int) -> None:
    """Run ``j`` of ``monte_carlo(sc, seed, n)`` draws its truth first, from the first stream its seed spawns
    (``SeedSequence(seed, spawn_key=(j, 0))``): each run's truth is its record of the seed and of its place (issue 35,
    swaps; fuzz 22b q8). The truth costs a draw of the target's path per run, not a run."""
    for j, r in enumerate(runs):
        truth = simulate_target(sc, np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(j, 0)))).truth
        if truth.shape != r.truth.shape or not np.array_equal(truth, r.truth):
            raise ValueError(f"seed = {seed} is not the root seed of the runs: run {j} is not run {j} of "
                             "monte_carlo(sc, seed, len(runs)) (its truth differs; runs of another seed, or reordered)")


def guard_values(guarded: list[TrackingRun], sc: RangeBearingScenario) -> GlueValues:
    """Glue values of the guarded study (:func:`guarded_runs`), the study's primary design.

    Parameters
    ----------
    guarded : list of TrackingRun
        The runs with the collapse guard.
    sc : RangeBearingScenario
        The scenario (its ``n_particles`` and ``n_central`` set the collapse thresholds).

    Returns
    -------
    dict
        ``chf_guard_stages`` (int, tempering steps), ``chf_n_guarded`` (int, runs in which the guard acted),
        ``chf_guard_updates`` (int, guarded node updates), ``chf_guard_central`` (int, guarded updates of the
        centralised filter), ``chf_guard_ess_min`` (smallest ESS of any node and frame in those runs, after the
        last tempering step, 1 decimal), ``chf_guard_central_min`` (the centralised filter's, 0 decimals),
        ``chf_n_collapsed_guard`` (int, runs still collapsed, node or centralised). When the guard acted in no run
        (``chf_n_guarded`` 0) the two minima, of no run, are left out.

    Raises
    ------
    TypeError
        ``sc`` not a RangeBearingScenario or ``guarded`` not a sequence of TrackingRun.
    ValueError
        ``guarded`` holds no run, a run twice, runs of several scenarios, or runs of a scenario other than ``sc`` (the guard's
        fields aside).
    """
    guarded = _check_study(guarded, sc, name="guarded")
    hit = [r for r in guarded if r.guarded]
    v: dict[str, Any] = {"chf_guard_stages": GUARD_STAGES, "chf_n_guarded": len(hit),
                         "chf_guard_updates": sum(1 for r in hit for _, i in r.guarded if i >= 0),
                         "chf_guard_central": sum(1 for r in hit for _, i in r.guarded if i < 0)}
    if hit:  # the minima of the runs the guard acted in: none, no value (fuzz 26b GU: no 0.0 placeholder)
        v["chf_guard_ess_min"] = rounded(float(min_local_ess(hit).min()), 1)
        v["chf_guard_central_min"] = rounded(float(min(np.min(r.ess["centralised_pf"]) for r in hit)), 0)
    v["chf_n_collapsed_guard"] = int(any_collapsed(guarded, sc).sum())
    return v


#: The overhead of one threshold of :func:`guard_usability`, in units: its loop step (a comparison of the plain runs'
#: local ESS, two reductions and three glue values) ran 14.5 us with 3 runs x 6 frames x 3 nodes (54 cells; 50,001
#: thresholds 0.73 CPU-s; OPENBLAS_NUM_THREADS=1, niced, the shared machine, minimum of 2; fuzz 62a C4b: 10**5
#: thresholds 1.5 CPU-s, unbudgeted). Counted as 2 loop steps plus one unit a cell (a vectorised element).
_THRESHOLD_STEP = 2 * LOOP_STEP


def guard_usability(guarded: list[TrackingRun], plain: list[TrackingRun], sc: RangeBearingScenario,
                    thresholds: tuple[float, ...] = (0.01, 0.05)) -> GlueValues:
    """Are the guarded runs' posteriors usable, by measures the guard does not target? Glue ``chf_gu_*``.

    The guard acts on the effective sample size; usability is judged here by the local filters' consistency and
    the fused accuracy: each run in which the guard acted is placed among the runs it did not touch, by the mean
    NEES (4-D) of its local filters (over nodes and every frame) and by the patent's method's mean squared error
    (frames 5 on). The rule, fixed before reading the numbers: usable when every guarded run lies at or below the
    95th percentile of the untouched runs on both. The collapse threshold is an open choice: the updates that
    would trigger the guard at other thresholds are counted on the plain runs (not rerun).

    Parameters
    ----------
    guarded : list of TrackingRun
        The study (with the guard).
    plain : list of TrackingRun
        The same runs without the guard.
    sc : RangeBearingScenario
        Particles per node (thresholds are fractions of them).
    thresholds : tuple of float
        Other collapse thresholds (fractions of the particles) whose trigger counts are reported (empty: none); the
        glue is keyed by position, so a repeated threshold gives the same values under two positions.

    Returns
    -------
    dict
        ``chf_gu_runs`` (int, runs in which the guard acted), ``chf_gu_nees_max``/``_p95`` (largest local NEES of
        those runs / 95th percentile of the others), ``chf_gu_nees_rank`` (largest percentile rank of a guarded
        run among the others, %), the same ``chf_gu_mse_*`` (m²), ``chf_gu_usable`` (bool, the rule above);
        ``chf_gu_chance_fail`` (the chance that the rule fails on one measure even if the repaired runs were exchangeable
        with the others, 1 − 0.95^k); ``chf_gu_own_n`` (int, repaired filters: run and node, or the centralised filter), ``chf_gu_own_ratio_max``
        (largest ratio of a repaired filter's own mean NEES to the 95th percentile of the same filter in the untouched
        runs) and ``chf_gu_own_usable`` (bool, every ratio at most 1); ``chf_gu_worst_run`` (int, the repaired run with
        the largest MSE), ``chf_gu_worst_node``/``_nees`` (its node with the largest mean NEES, and that NEES) and
        ``chf_gu_worst_repaired`` (str, the filters the guard repaired in it); and
        per threshold ``j`` ``chf_gu_thr<j>`` (%), ``chf_gu_thr<j>_runs`` and ``chf_gu_thr<j>_updates`` (int:
        runs and node updates of the plain runs below it). 2 decimals (ranks and percentiles 0). When the guard acted
        in no run (``chf_gu_runs`` 0) the values of repaired runs (``chf_gu_nees_max``/``_rank``,
        ``chf_gu_mse_max``/``_rank``, ``chf_gu_own_ratio_max`` and the ``chf_gu_worst_*``) are left out, and
        ``chf_gu_usable`` and ``chf_gu_own_usable`` are True (no repaired run lies above the percentile).

    Raises
    ------
    TypeError
        ``guarded`` or ``plain`` not a sequence of TrackingRun, ``sc`` not a RangeBearingScenario, ``thresholds``
        not a sequence of numbers.
    ValueError
        ``guarded`` empty, of several scenarios or holding a run twice, ``plain`` not the same runs (as many, of the
        same scenario and truths: another seed's runs are refused), ``sc`` not their scenario, a threshold not in (0,
        1), or fewer than two runs in which the guard did not act, ``guarded`` of fewer than 5 frames (no frame of
        LATE) or of more than 3 nodes (not a study the chapter's tables show); ``len(thresholds)`` x the plain runs'
        local ESS cells beyond the work budget (``fusion._limits.loop_work``, 2,000 units a threshold plus one a cell:
        about 490,000 thresholds of 3 runs x 6 frames x 3 nodes), by their number before any is read.
    """
    thresholds = sequence(thresholds, "thresholds")
    guarded = _check_study(guarded, sc, name="guarded", window=True, nodes=True)
    plain = _check_study(plain, sc, name="plain", like=guarded, like_name="guarded")
    # rule 17 by len(thresholds) before any is read (fuzz 62a C4b: the loop at the end had no budget)
    loop_work((len(thresholds),), sum(int(np.size(r.ess["local"])) for r in plain), "thresholds",
              step=_THRESHOLD_STEP)
    thresholds = tuple(scalar(t, f"thresholds[{j}]", 0.0, 1.0, lo_open=True, hi_open=True)
                       for j, t in enumerate(thresholds))
    hit = np.array([bool(r.guarded) for r in guarded])
    if (~hit).sum() < 2:
        raise ValueError("guarded: fewer than two runs without the guard's action, nothing to compare with")
    nees = np.mean([per_run_nees(guarded, f"local{i + 1}", ALL_FRAMES) for i in range(len(sc.sensors))], axis=0)
    mse = per_run_mse(guarded, "chernoff_pso")
    v: dict[str, Any] = {"chf_gu_runs": int(hit.sum())}
    usable = True
    for tag, x in (("nees", nees), ("mse", mse)):
        others = x[~hit]
        p95 = float(np.percentile(others, 95))
        if hit.any():  # no repaired run: nothing to place, no value (fuzz 26b GU); keys in the order glued
            worst = float(x[hit].max())
            rank = float(max(np.mean(others < y) for y in x[hit]) * 100)
            usable = usable and worst <= p95
            v.update({f"chf_gu_{tag}_max": rounded(worst, 2), f"chf_gu_{tag}_p95": rounded(p95, 2),
                      f"chf_gu_{tag}_rank": rounded(rank, 0)})
        else:
            v[f"chf_gu_{tag}_p95"] = rounded(p95, 2)
    v["chf_gu_usable"] = bool(usable)
    # the rule's own false alarm: k runs exchangeable with the others all at or below a 95th percentile, on one measure
    v["chf_gu_chance_fail"] = rounded(1.0 - 0.95 ** int(hit.sum()), 2)
    # the repaired filters themselves: each repaired node's (or the centralised filter's) own mean NEES against the
    # 95th percentile of the same filter in the untouched runs (a reading added after the rule above was read)
    own = {i: per_run_nees(guarded, f"local{i + 1}" if i >= 0 else "centralised_pf", ALL_FRAMES)
           for i in range(-1, len(sc.sensors))}
    pairs = sorted({(j, i) for j, r in enumerate(guarded) for _, i in r.guarded})
    ratios = [own[i][j] / float(np.percentile(own[i][~hit], 95)) for j, i in pairs]
    if ratios:
        v["chf_gu_own_ratio_max"] = rounded(float(max(ratios)), 2)
    v["chf_gu_own_n"] = len(pairs)
    v["chf_gu_own_usable"] = bool(all(x <= 1.0 for x in ratios))
    if hit.any():  # the worst repaired run: none when the guard acted in no run (fuzz 26b GU)
        worst = int(np.flatnonzero(hit)[np.argmax(mse[hit])])
        v["chf_gu_worst_run"] = worst + 1
        v["chf_gu_worst_nees"] = rounded(float(max(own[i][worst] for i in range(len(sc.sensors)))), 2)
        v["chf_gu_worst_node"] = int(np.argmax([own[i][worst] for i in range(len(sc.sensors))])) + 1
        v["chf_gu_worst_repaired"] = ", ".join("centralised" if i < 0 else f"node {i + 1}"
                                               for i in sorted({i for _, i in guarded[worst].guarded}))
    ess = np.stack([r.ess["local"] for r in plain])  # (runs, K, N)
    for j, t in enumerate(thresholds):
        below = ess < t * sc.n_particles
        v.update({f"chf_gu_thr{j}": rounded(100 * t, 1), f"chf_gu_thr{j}_runs": int(below.any(axis=(1, 2)).sum()),
                  f"chf_gu_thr{j}_updates": int(below.sum())})
    return v


#: The designs of :func:`design_study`, the keys of :class:`DesignStudy`'s fields.
DESIGNS = ("plain", "more particles", "guard")


@dataclass(frozen=True)
class DesignStudy:
    """The first update of the local filters under three designs, on the same runs (:func:`design_study`).

    Attributes
    ----------
    ess : dict {"plain", "more particles", "guard"} -> ndarray, shape (runs, N)
        Effective particles of every node after its first update (after the last tempering step for the guard).
    weighted : dict
        Particles weighted at the first update, per node (the design's cost: 2,000; ``n_initial``; 2,000 plus
        the tempering steps where the guard acts, counted as likelihood passes × particles).
    n_initial : int
        Particles drawn from the prior by the "more particles" design (then resampled to ``n_particles``).
    threshold : float
        Effective particles below which a node counts as collapsed (:data:`COLLAPSE_FRACTION` × ``n_particles``).
    """

    ess: Mapping[str, FloatArray]
    weighted: Mapping[str, float]
    n_initial: int
    threshold: float

    __result_spec__ = ResultSpec({"ess": dict_of(array("runs", "N", bounds=(0.0, np.inf)), keys=DESIGNS),
                                  "weighted": dict_of(number(positive=True), keys=DESIGNS), "n_initial": integer(1),
                                  "threshold": number()})
    __post_init__ = validated_post_init


    def glue(self) -> GlueValues:
        """Glue values ``chf_design_*``: runs collapsed at the first update, smallest ESS and cost, per design."""
        v: dict[str, Any] = {"chf_design_n0": self.n_initial, "chf_design_runs": int(self.ess["plain"].shape[0])}
        for name, key in (("plain", "plain"), ("more particles", "more"), ("guard", "guard")):
            low = self.ess[name].min(axis=1)
            v[f"chf_design_{key}_collapsed"] = int(np.sum(low < self.threshold))
            v[f"chf_design_{key}_min"] = rounded(float(low.min()), 1)
            v[f"chf_design_{key}_cost"] = rounded(float(self.weighted[name]), 0)
        return v


#: Particles of the "more particles" design's first update at the chapter's 2,000 particles per node, and the
#: multiple of ``sc.n_particles`` it follows for a scenario of more (:func:`design_study`'s default ``n_initial``).
_N_INITIAL, _N_INITIAL_FACTOR = 10_000, 5


def _default_n_initial(sc: RangeBearingScenario) -> int:
    """:func:`design_study`'s default ``n_initial`` for ``sc``: the larger of 10,000 and 5 × ``sc.n_particles``,
    so above ``sc.n_particles`` for every scenario (fuzz 27b B1: a fixed 10,000 refused a scenario of 10,000
    particles); 10,000 at the chapter's 2,000."""
    return max(_N_INITIAL, _N_INITIAL_FACTOR * int(sc.n_particles))


def design_study(sc: RangeBearingScenario, seed: int, runs: int = STUDY_RUNS, n_initial: int | None = None,
                 workers: int = STUDY_WORKERS) -> DesignStudy:
    """Three designs of the local filters on the first update of the same runs: which one avoids collapse, at what cost.

    Every observed collapse of a node is a first update whose likelihood is much narrower than the prior (or,
    rarely, a later one). The designs: the plain bootstrap filter; *more particles* for the first update
    (``n_initial`` drawn from the prior, resampled to ``n_particles`` after weighting); and the *guard*,
    progressive correction where a node falls below :data:`COLLAPSE_FRACTION` (:func:`guarded_scenario`).
    One-frame runs of the study's seeds: the same prior means, first true states and particle draws as the
    study's runs, but not the same first readings (a run draws its measurement noise after its whole trajectory).

    Parameters
    ----------
    sc : RangeBearingScenario
        The study's scenario.
    seed : int
        Root seed (every design uses the same runs).
    runs : int
    n_initial : int, optional
        Particles of the "more particles" design's first update: more than ``sc.n_particles`` (the filter draws
        the larger of the two, so a smaller count would repeat the plain design). Default the larger of 10,000 and
        5 × ``sc.n_particles`` (10,000 at the chapter's 2,000 particles), above ``sc.n_particles`` for every scenario.
    workers : int
        Processes (results do not depend on it).

    Returns
    -------
    DesignStudy
        Per design (plain, more particles, guard) the nodes' effective sample sizes at the first update, shape (runs,
        nodes), and particle-likelihoods per node.

    Raises
    ------
    TypeError
        ``sc`` not a RangeBearingScenario; ``seed``, ``runs``, ``n_initial`` or ``workers`` not an integer.
    ValueError
        ``seed`` negative; ``runs``, ``n_initial`` or ``workers`` below 1; ``n_initial`` not above
        ``sc.n_particles``; ``runs`` and ``n_initial`` (by default ``sc.n_particles``) beyond the memory budget (the
        particle clouds of a block of runs).
    """
    instance_of(sc, RangeBearingScenario, "sc")
    seed = check_seed(seed)
    runs = count(runs, "runs")
    given = n_initial is not None
    n_initial = count(n_initial, "n_initial") if given else _default_n_initial(sc)
    if n_initial <= sc.n_particles:  # fuzz 26b DS: the pipeline draws max(n_initial, n_particles) at the first update
        raise ValueError(f"n_initial must exceed sc.n_particles = {sc.n_particles} (the 'more particles' design draws "
                         f"max(n_initial, sc.n_particles) at the first update: {n_initial} would run the plain "
                         f"design under another name), got {n_initial}")
    workers = check_workers(workers)
    # the nodes' first update is all that is read: the fusion and the centralised filter run small (they draw from
    # their own streams, after the nodes' weights are computed, so the effective sample sizes do not change)
    one = dataclasses.replace(sc, frames=1, variants=False, readings=False, n_samples=50, n_central=50, em_iterations=1)
    # the "more particles" design's first update holds n_initial particles per node of a block of runs: refused by
    # the tracking's memory rule before any run, naming this function's arguments (fuzz 24b SZ2: MemoryError)
    _block_allocation(dataclasses.replace(one, n_initial=n_initial), runs,
                      f"runs, sc.sensors and {'n_initial' if given else 'sc.n_particles (n_initial by default)'}")
    designs = {"plain": one, "more particles": dataclasses.replace(one, n_initial=n_initial),
               "guard": dataclasses.replace(one, guard=COLLAPSE_FRACTION)}
    ess, weighted = {}, {}
    plain: list[TrackingRun] = []
    for name, d in designs.items():
        seeds = np.random.SeedSequence(seed).spawn(runs)  # fresh: a SeedSequence spawns new children at every spawn
        if name == "guard":  # the guard draws nothing where no node collapses: redo only the runs that collapse
            idx = [j for j, r in enumerate(plain) if np.min(r.ess["local"][0]) < COLLAPSE_FRACTION * sc.n_particles]
            redo = run_tracking_batch(d, [seeds[j] for j in idx], workers=workers) if idx else []
            rs = list(plain)
            for j, r in zip(idx, redo):
                rs[j] = r
        else:
            rs = run_tracking_batch(d, seeds, workers=workers)
        if name == "plain":
            plain = rs
        ess[name] = np.stack([r.ess["local"][0] for r in rs])
        n_nodes = ess[name].size
        extra = sum(len(r.guarded) for r in rs) * (GUARD_STAGES - 1) * sc.n_particles
        weighted[name] = (max(d.n_initial, d.n_particles) * n_nodes + extra) / n_nodes
    return DesignStudy(ess=ess, weighted=weighted, n_initial=n_initial, threshold=COLLAPSE_FRACTION * sc.n_particles)
