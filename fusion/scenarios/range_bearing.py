r"""Distributed tracking with range-bearing sensor nodes: the designed scenario of chapter 06.

The patent (CN107330468B) gives no scenario, parameters or results. This module runs the one the
chapter designs: :math:`N` range-bearing sensors around a target with nearly-constant-velocity
motion; every node runs a bootstrap particle filter (step B), fits a Gaussian mixture to its
weighted particles by weighted EM (step C) and broadcasts it; the fusion (steps D-I,
:func:`fusion.estimates.chernoff.fuse_mixtures`) is computed alongside simple baselines and a centralised
particle filter, and :func:`posterior_crb` gives the floor.

The local filters never see the fused result (no feedback: the patent is silent on it).

References
----------
* Oudjane, N., & Musso, C. (2000). Progressive correction for regularized particle filters. In
  *Proceedings of the 3rd International Conference on Information Fusion (FUSION 2000)*, Paris.
"""

from __future__ import annotations

from collections.abc import Mapping
import dataclasses
import multiprocessing
import os
from concurrent.futures import ProcessPoolExecutor

import numpy as np

from fusion._validation import seed as check_seed, workers as check_workers
from fusion._validation import flag, seed_sequence
from fusion._limits import MAX_WORK, STUDY_WORK, TRACKING_STUDY
from fusion.estimates.chernoff._product import product_size
from fusion._guards import own_underflow
from fusion._validation import (FloatArray, LOOP_STEP, allocation, as_array, count, instance_of, loop_work, one_of,
                                sequence, work)
from fusion.filtering.kalman import nees
from fusion.optimise.swarm import SwarmOptions, check_swarm_options
# the module is split by concept; its names (and the batch engine's private kernels) are re-exported here
from fusion.scenarios.range_bearing_batch import _Batch, _moments, _normals, _regularise_batch, _run_block, _run_streams  # noqa: F401
from fusion.scenarios.range_bearing_batch import _equal_kl_on_mixture, _sigma_point_log_expectations  # noqa: F401
from fusion.scenarios.range_bearing_bounds import LinearisedErrors, linearised_errors, posterior_crb
from fusion.scenarios import range_bearing_scenario as _scenario
from fusion.scenarios.range_bearing_scenario import (RangeBearingScenario, SimulatedTarget, TrackingRun, TrackingTimings, method_keys,
                                                     simulate_target)
from fusion._shown import shown

# The documented constants, bound here so that the API page documents them under this module's name.
#: Tempering steps of the collapse guard (``RangeBearingScenario.guard``).
GUARD_STAGES = _scenario.GUARD_STAGES
#: Methods compared in the scenario: key -> display label.
METHODS = _scenario.METHODS
#: Methods computed only with ``RangeBearingScenario.readings``.
READING_METHODS = _scenario.READING_METHODS

__all__ = ["GUARD_STAGES", "RUN_BLOCK", "READING_METHODS", "SimulatedTarget", "RangeBearingScenario", "TrackingRun", "TrackingTimings", "METHODS", "simulate_target", "run_tracking", "run_tracking_batch", "posterior_crb", "LinearisedErrors", "linearised_errors",
           "monte_carlo", "position_sq_errors", "nees_per_frame", "min_local_ess", "method_keys"]

#: Runs advanced together by :func:`run_tracking_batch` (results do not depend on it). A larger block spreads each
#: stage's per-call overhead over more runs: the study's 100 runs on two workers are one block of 50 each, about 10 %
#: less CPU than six blocks of 17 (measured side by side, same runs); a block of 50 at the default scenario holds
#: tens of MB per array, far within the memory budget.
RUN_BLOCK = 50


def run_tracking(
    sc: RangeBearingScenario,
    seed: np.random.SeedSequence,
    all_nodes: bool = False,
    swarm_options: SwarmOptions | None = None,
) -> TrackingRun:
    """One Monte-Carlo run of the scenario: local PFs, every fusion method, centralised PF.

    Independent random streams (spawned from ``seed``) drive the target, each node's filter,
    the fusion and the centralised filter, so that adding a method never changes another.

    Any number of sensors N >= 1 is handled: the local methods are ``local1`` ... ``localN``
    (:func:`method_keys`); with one sensor every fusion returns that sensor's own posterior
    (exponent weight 1). The same as ``run_tracking_batch(sc, [seed], ...)[0]``.

    Parameters
    ----------
    sc : RangeBearingScenario
    seed : numpy.random.SeedSequence
        The run's streams are spawned from it, which advances its spawn counter (numpy semantics): a
        second call with the same object gives other streams. To repeat a run, pass a fresh
        ``SeedSequence`` of the same entropy. The package's one rule for random state (fuzz 28a D5): a
        ``SeedSequence`` or ``Generator`` object is state the call advances, as a ``Generator`` passed to any
        function is; an integer seed (``monte_carlo``'s ``seed``) repeats its runs.
    all_nodes : bool
        Also let every node compute the patent's fusion with its own random stream (they all
        hold the same mixtures under full connectivity), recording ``node_estimates``.
    swarm_options : SwarmOptions, optional
        Settings of the particle swarm (default ``SwarmOptions()``).

    Returns
    -------
    TrackingRun
        Per frame the truth, each method's estimates and covariances, exponents, ESS, objective and log-likelihoods,
        with evaluations and timings.
    """
    instance_of(sc, RangeBearingScenario, "sc")
    seed_sequence(seed, "seed")  # a wrong type: TypeError (fuzz 48 D2); a huge one: ValueError (fuzz 55 C2)
    return run_tracking_batch(sc, [seed], all_nodes=[flag(all_nodes, "all_nodes")], swarm_options=swarm_options)[0]


@own_underflow  # a far particle's weight underflows to zero by design (fuzz 31a D1)
def run_tracking_batch(
    sc: RangeBearingScenario,
    seeds: list[np.random.SeedSequence],
    all_nodes: list[bool] | None = None,
    swarm_options: SwarmOptions | None = None,
    workers: int = 1,
) -> list[TrackingRun]:
    """Several Monte-Carlo runs advanced together, frame by frame (vectorised across runs and nodes).

    Every stage is one array computation over the runs (and nodes) of a block of :data:`RUN_BLOCK`
    runs: the particle filters, the weighted EM of every node of every run
    (quadratic-feature kernel of :mod:`fusion.estimates.mixtures`), the fusion of steps D-I with its
    swarms advanced together (:func:`fusion.estimates.chernoff.fuse_mixtures_batch`), the baselines
    and the centralised filter; only the random draws (each run's and node's own generator, in a
    fixed order), the resampling searches and the SLSQP solves loop over runs. Run ``r`` gives
    exactly what ``run_tracking(sc, seeds[r])`` gives, digit for digit (every per-run computation is
    elementwise or one small factorisation or product per run, reductions never mix runs; tested),
    whatever the other runs and the block size.
    Runs under its own ``np.errstate(under="ignore")``, numpy's default: a far particle's weight underflows
    to zero by design, whatever the caller's error state (overflow and invalid operations keep it).

    Parameters
    ----------
    sc : RangeBearingScenario
    seeds : list of numpy.random.SeedSequence
        One per run (non-empty), no object twice; each is spawned from, as ``seed`` of :func:`run_tracking` (a used
        one gives other streams), in this process before any run, so that it advances the same whatever ``workers``.
    all_nodes : list of bool, optional
        Per run, as ``all_nodes`` of :func:`run_tracking` (default: False for every run).
    swarm_options : SwarmOptions, optional
        Settings of the particle swarm (default ``SwarmOptions()``).
    workers : int
        Processes that share the blocks of runs (1: this process), at most the machine's CPUs
        (the shared rule ``fusion._validation.workers``: a larger request uses them all). Each block is computed as
        it would be here, so the result does not depend on it. Inside a pytest-xdist worker
        (``PYTEST_XDIST_WORKER`` set, inherited by the notebooks nbval runs) the runs stay in this process:
        the test runner's processes already share the cores.

    Returns
    -------
    list of TrackingRun, one per seed
        Entry i: the run with ``seeds[i]``, as :func:`run_tracking` records it.
    """
    instance_of(sc, RangeBearingScenario, "sc")
    seeds = sequence(seeds, "seeds")  # any sequence (a list, a tuple, a UserList)
    workers = check_workers(workers, "workers")  # at most the machine's CPUs (rule 9)
    if not seeds:
        raise ValueError("seeds is empty: at least one SeedSequence is needed")
    node_items = [False] * len(seeds) if all_nodes is None else sequence(all_nodes, "all_nodes")
    if len(node_items) != len(seeds):
        raise ValueError(f"all_nodes must have {len(seeds)} entries (one per seed), got {len(node_items)}")
    swarm_options = check_swarm_options(swarm_options)
    # the memory and work budgets by len(seeds) before any entry is read (fuzz 62b C2: each seed was checked by
    # seed_sequence first, 3 * 10**6 seeds refused after 13.7 CPU-s, while the budget accepts about 700 runs)
    _block_allocation(sc, len(seeds), "seeds, sc.sensors and sc.n_particles")
    _tracking_work(sc, len(seeds), "seeds, sc.frames, sc.sensors, sc.n_initial, sc.n_components and sc's particle and "
                   "sample counts", swarm_options)
    for i, s in enumerate(seeds):
        seed_sequence(s, f"seeds[{i}]")  # entropy and spawn key of at most 256 bits: each spawn mixes them (fuzz 55 C2)
    flags = [flag(f, f"all_nodes[{i}]") for i, f in enumerate(node_items)]
    seen: dict[int, int] = {}
    for i, s in enumerate(seeds):
        j = seen.setdefault(id(s), i)
        if j != i:  # fuzz 53b D3: run i's streams would depend on run j's spawn (and, before, on workers)
            raise ValueError(f"seeds[{i}] is the same SeedSequence object as seeds[{j}]: each run needs its own seed "
                             "(its run is then what run_tracking gives with it), e.g. "
                             "np.random.SeedSequence(seed).spawn(n)")
    if os.environ.get("PYTEST_XDIST_WORKER"):
        workers = 1  # the test runner's worker processes already share the cores
    # blocks of at most RUN_BLOCK runs, as many as a multiple of the workers and of equal sizes (within one),
    # so that no worker waits for another's last block (the runs' results do not depend on the blocks)
    n_blocks = -(-len(seeds) // RUN_BLOCK)
    if workers > 1:
        n_blocks = -(-n_blocks // workers) * workers
    size = -(-len(seeds) // n_blocks)
    # every run's streams are spawned here, in the caller's process, before any block is dispatched: the caller's
    # SeedSequences advance as with workers=1 (fuzz 53b C2: spawned in the workers, only pickled copies advanced)
    streams = [_run_streams(s) for s in seeds]
    blocks = [(sc, streams[j:j + size], flags[j:j + size], swarm_options) for j in range(0, len(seeds), size)]
    if workers > 1 and len(blocks) > 1:
        methods = multiprocessing.get_all_start_methods()
        ctx = multiprocessing.get_context("fork" if "fork" in methods else methods[0])
        with ProcessPoolExecutor(max_workers=min(workers, len(blocks)), mp_context=ctx) as pool:
            parts = list(pool.map(_run_block, blocks))
    else:
        parts = [_run_block(b) for b in blocks]
    return [r for part in parts for r in part]

#: Arrays of a block's particle clouds, shape (runs of the block, nodes, particles, 4), that a block of
#: :func:`run_tracking_batch` holds at once: 7.6 measured (tracemalloc, first update and EM; 5.8 for a first update of
#: ``n_initial`` particles), so that :func:`~fusion._validation.allocation` checks the memory a block takes, not one
#: of its arrays (fuzz 24b SZ2: one array within the budget, the block's raised MemoryError).
_BLOCK_HELD = 8


def _block_allocation(sc: RangeBearingScenario, runs: int, names: str, frames: int | None = None,
                      frames_names: str = "sc.frames, sc.sensors and sc.n_particles") -> None:
    """Refuse (rule 9) a tracking study whose particle clouds exceed the memory budget: one run's ``frames`` frames
    (default ``sc.frames``; ``frames_names`` the arguments setting them), and the ``_BLOCK_HELD`` arrays of a block
    of ``min(runs, RUN_BLOCK)`` runs, each of ``max(n_initial, n_particles)`` particles per node; ``names`` are the
    arguments setting the block's size."""
    n0, n_nodes = max(int(sc.n_initial), int(sc.n_particles)), len(sc.sensors)
    allocation((int(sc.frames) if frames is None else int(frames), n_nodes, n0, 4), frames_names)
    allocation((_BLOCK_HELD, min(int(runs), RUN_BLOCK), n_nodes, n0, 4), names)


#: Units (about 10 ns each, ``fusion._validation.MAX_WORK``) of one frame of one run of :func:`run_tracking_batch`
#: besides its particles: the per-run loops (resampling searches, SLSQP solves, the swarm's steps), measured 2.5 ms
#: a run-frame with 60 particles (fuzz 34a C7: 0.40 CPU-s for 80 runs of 2 frames, OPENBLAS_NUM_THREADS=1).
TRACK_STEP = 250_000
#: Units of one particle-element of a run-frame (``_tracking_work``): a node's particle weighs ``1 + em_iterations x
#: n_components`` elements, a fusion sample and a centralised particle one; 3 units each fits the default scenario's
#: measured 14 ms a run-frame (6,000 particles over 3 nodes, 2,000 samples, 10,000 central particles).
TRACK_ELEMENT = 3
#: Units of one particle of a node's first frame beyond ``n_particles`` (``n_initial``, predicted, weighted and cut
#: down to ``n_particles``): measured 0.15-0.27 us (10 runs of 2 frames, ``n_initial`` 20,000 to 100,000; fuzz 35a C3).
TRACK_INITIAL = 25
#: Fusions of the nodes' product mixture (``n_components ** sensors`` component tuples, each weighed by the estimates'
#: rule ``fusion.estimates.chernoff._product``, its samples already counted as elements) in a run-frame: 12.6-14 us a
#: tuple measured at 20 and 30 components (60 particles, 60 samples, 2 runs of 2 frames), five fusions' worth at the
#: rule's 2.6 us (fuzz 35a C3b); the default scenario's 27 tuples add 2.5 %.
TRACK_FUSIONS = 5
#: Units of one generation of a run-frame's particle swarm (``_tracking_work``), besides :data:`TRACK_SWARM_PAIR` per
#: swarm particle and fusion sample: measured 1.3e-4 s a frame-generation with the default 20 particles and 60 samples,
#: 1.5e-4 s with 80 particles, 2.2e-4 s with 2,000 samples (1 run of 2 frames, 2,000-4,000 generations, ``tol=0``;
#: fuzz 36a C7). The default swarm's own generations are inside :data:`TRACK_STEP`: only the excess is counted.
TRACK_SWARM_STEP = 13_000
#: Units of one swarm particle times fusion sample of a generation (``_tracking_work``; measured 0.23-0.44).
TRACK_SWARM_PAIR = 1
#: Work budget of a tracking study (``_tracking_work``): the entry of ``fusion._limits.STUDY_WORK`` for the book's
#: largest own study (the reseeding sweep's 300 runs of the default 30-frame scenario, 1.28e10 units; chapter 06's
#: 100 runs count 4.26e9, about 45 CPU-s), twice its count: 26 x ``MAX_WORK``; a request of hours is refused.
TRACK_WORK = STUDY_WORK[TRACKING_STUDY]


#: Units of one frame of a run's set-up that ``_run_up_to`` does not step (its target simulated and its records
#: allocated over all ``sc.frames`` from the start; a stepped frame's share is inside :data:`TRACK_STEP`): measured
#: 2.9-3.6 us a frame (``_Batch`` of one run of 20,000 frames, 1 to 8 sensors; 2.6 CPU-s for ``frame_clouds`` at frame
#: 0 of 700,000 frames; OPENBLAS_NUM_THREADS=1, shared machine, minimum of two), so 400 units (fuzz 54b C2). The
#: records' memory (``_frame_records``) binds first: about 740,000 frames of three sensors.
TRACK_RECORD = 400


def _frame_records(sc: RangeBearingScenario) -> int:
    """Float64 numbers a run's records hold per frame of ``sc.frames`` (``_Batch``: each method's estimate and
    covariance, 20; exponents, ESS, log-likelihoods, node estimates and measurements, 16 a sensor; with ``readings``
    the swarm's trace, twice the default swarm's iterations + 1, and 20 a sensor): measured with tracemalloc (one run
    of 20,000 frames set up and one frame stepped) 279, 353 and 538 numbers a frame for 1, 3 and 8 sensors
    (292, 364 and 544 counted), 521 and 820 with ``readings`` for 3 and 8 sensors (586 and 866 counted)."""
    n = len(sc.sensors)
    readings = 2 * (SwarmOptions().iterations + 1) + 20 * n if sc.readings else 0
    return 20 * len(method_keys(n, bool(sc.readings))) + 16 * n + 16 + readings


def _one_run_checks(sc: RangeBearingScenario, frame: int) -> int:
    """The checks of :func:`run_tracking_batch` for one run stepped to ``frame`` (0-based) by ``_run_up_to``:
    its particle clouds (``_block_allocation`` over ``frame + 1`` frames), its records over all ``sc.frames``
    (``_frame_records``) and its work (``_tracking_work`` of ``frame + 1`` frames, held to
    ``fusion._limits.MAX_WORK``: the book's own call, one run of ten frames of the study, counts 1.4e7 units), naming
    ``sc``'s fields and ``frame``, before any work; returns the units."""
    _block_allocation(sc, 1, "sc.sensors and sc.n_particles", frames=frame + 1,
                      frames_names="frame, sc.sensors and sc.n_particles")
    allocation((int(sc.frames), _frame_records(sc)), "sc.frames, sc.sensors and sc.readings")
    return _tracking_work(sc, 1, "frame, sc.frames, sc.sensors, sc.n_initial, sc.n_components and sc's particle and "
                          "sample counts", frames=frame + 1, limit=MAX_WORK)


@own_underflow  # as run_tracking_batch: a far particle's weight underflows to zero by design
def _run_up_to(sc: RangeBearingScenario, seed: np.random.SeedSequence, frame: int) -> _Batch:
    """One run of :func:`run_tracking_batch`'s runner (its streams spawned from ``seed``), stepped to ``frame``
    (0-based, below ``sc.frames``), for a caller that reads the runner's state
    (``fusion.book.chapters.chernoff_scaling.frame_clouds``): ``_one_run_checks`` first, so that no public entry
    to the runner skips the study's checks (fuzz 54b C2: ``frame_clouds`` built the runner directly, 20-45 CPU-s
    before a refusal naming no argument, or none)."""
    _one_run_checks(sc, frame)
    batch = _Batch(sc, [_run_streams(seed)], [False], None)
    for k in range(frame + 1):
        batch.frame(k)
    return batch


def _swarm_units(sc: RangeBearingScenario, swarm_options: SwarmOptions) -> int:
    """The units of a run-frame's particle swarm under ``swarm_options`` beyond the default swarm's (which
    :data:`TRACK_STEP` holds): :data:`TRACK_SWARM_STEP` a generation plus :data:`TRACK_SWARM_PAIR` a particle and
    fusion sample, every generation (``iterations``) counted (fuzz 36a C7); 0 for settings no costlier."""
    def units(o: SwarmOptions) -> int:
        return int(o.iterations) * (TRACK_SWARM_STEP + TRACK_SWARM_PAIR * int(o.n_particles) * int(sc.n_samples))
    return max(units(swarm_options) - units(SwarmOptions()), 0)


def _tracking_work(sc: RangeBearingScenario, runs: int, names: str, swarm_options: SwarmOptions | None = None,
                   frames: int | None = None, limit: int = TRACK_WORK) -> int:
    """Refuse (rule 17) a tracking study of ``runs`` runs of ``sc`` whose work is beyond :data:`TRACK_WORK`, before
    any work: ``runs x sc.frames`` run-frames of :data:`TRACK_STEP` units plus :data:`TRACK_ELEMENT` units per
    particle-element, :data:`TRACK_FUSIONS` fusions of the nodes' product mixture, and the first frame's particles
    beyond ``n_particles`` (``n_initial``, :data:`TRACK_INITIAL` units each) spread over the frames (``names`` are the
    caller's arguments setting them; the product's memory refused naming them too), and a costlier swarm than the
    default (``swarm_options``: ``_swarm_units`` a run-frame, named with ``names``); returns the units.
    ``frames``: the frames each run steps (default ``sc.frames``; fewer for ``_run_up_to``, whose run still sets up
    its target and records over all ``sc.frames``, :data:`TRACK_RECORD` units each frame it does not step, spread over
    the stepped frames as the first frame's particles are); ``limit``: the budget (default :data:`TRACK_WORK`)."""
    sensors = len(sc.sensors)
    frames = int(sc.frames) if frames is None else int(frames)
    unstepped = TRACK_RECORD * (int(sc.frames) - frames)
    elements = (sensors * int(sc.n_particles) * (1 + int(sc.em_iterations) * int(sc.n_components))
                + int(sc.n_samples) + int(sc.n_central))
    tuples, per = product_size(min(int(runs), RUN_BLOCK), sensors, int(sc.n_components), 4, names)
    initial = TRACK_INITIAL * sensors * max(int(sc.n_initial) - int(sc.n_particles), 0)
    swarm = 0 if swarm_options is None else _swarm_units(sc, swarm_options)
    if swarm:
        names += ", swarm_options.iterations and swarm_options.n_particles"
    return work((int(runs), frames), names, limit=limit,
                weight=TRACK_STEP + TRACK_ELEMENT * elements + TRACK_FUSIONS * tuples * per
                + -(-(initial + unstepped) // frames) + swarm)


# --------------------------------------------------------------------------- Monte-Carlo study
#: The fields of a scenario that the collapse guard sets (:func:`fusion.book.chapters.chernoff.guarded_runs` mixes
#: runs with and without it in one study): a run list and a scenario are compared without them.
_GUARD_FIELDS = ("guard", "central_guard")

#: What a run of a scenario with ``readings=True`` holds, and where (the readings' helpers read these).
_READINGS = (("eps", "equal_kl_g"), ("eps", "first_order"), ("swarm_trace", "fitness"))


def _unguarded(sc: RangeBearingScenario) -> RangeBearingScenario:
    return dataclasses.replace(sc, **{f: 0.0 for f in _GUARD_FIELDS})


def _differences(a: RangeBearingScenario, b: RangeBearingScenario) -> list[str]:
    """The fields (other than the guard's) in which two scenarios differ."""
    return [f.name for f in dataclasses.fields(a) if f.name not in _GUARD_FIELDS
            and getattr(a, f.name) != getattr(b, f.name)]


#: The default of ``_check_runs``'s ``sc``: no scenario to compare (None is a wrong scenario, refused by type).
_NO_SCENARIO = object()


def _check_runs(runs: object, nonempty: bool, sc: object = _NO_SCENARIO, *, name: str = "runs",
                readings: bool = False) -> list[TrackingRun]:
    """The shared check of a run list (issue 35, fuzz 22b class TR): ``runs`` a sequence
    (``fusion._validation.sequence``) of :class:`TrackingRun` (non-empty if asked) of one scenario, and ``sc``
    (when given) that scenario.

    One scenario: the runs' recorded ``scenario`` (where set) equal but for the collapse guard's fields, and the
    same frames K (rows of ``truth``) and nodes N (columns of ``gm_loglik``) in every run. ``sc``: a
    :class:`RangeBearingScenario` equal to the runs' recorded scenario but for the guard's fields (for runs built by
    hand, without a record, as far as they show it: its frames and sensors). ``readings``: every run holds the
    readings of ``RangeBearingScenario.readings``. TypeError for a wrong type, ValueError naming ``name`` or ``sc``
    otherwise. Returns the runs as a list."""
    seq = sequence(runs, name)
    if nonempty and not seq:
        raise ValueError(f"{name} is empty: at least one TrackingRun is needed")
    if seq:  # rule 17 (fuzz 38a C8): the readers' loops over the runs, 136-146 us a run and 2 us a frame measured;
        # by len(runs) and the first run's frames before the other entries are read (fuzz 62b's class, fix70a: 10**7
        # runs were each checked first, refused after 1.9 CPU-s)
        instance_of(seq[0], TrackingRun, f"{name}[0]")
        loop_work((len(seq),), 200 * np.shape(seq[0].truth)[0], name, step=14 * LOOP_STEP)
    for i, r in enumerate(seq):  # type: ignore[arg-type]
        instance_of(r, TrackingRun, f"{name}[{i}]")
    out: list[TrackingRun] = list(seq)  # type: ignore[arg-type]
    own = next((r.scenario for r in out if r.scenario is not None), None)
    # each scenario object's unguarded copy built once, not twice a run (speed58: the runs of a study share one
    # scenario; 71,000 copies, each validated again, were a fifth of chapter 06's notebook): the same comparisons
    unguarded: dict[int, RangeBearingScenario] = {}

    def bare(s: RangeBearingScenario) -> RangeBearingScenario:
        if id(s) not in unguarded:
            unguarded[id(s)] = _unguarded(s)
        return unguarded[id(s)]

    for i, r in enumerate(out):
        if r.scenario is not None and not isinstance(r.scenario, RangeBearingScenario):
            raise TypeError(f"{name}[{i}].scenario must be a RangeBearingScenario or None, "
                            f"got {type(r.scenario).__name__}")
        if r.scenario is not None and own is not None and bare(r.scenario) != bare(own):
            raise ValueError(f"{name}[{i}] was computed with another scenario than the runs before it (they differ "
                             f"in {_differences(r.scenario, own)}): the runs must be of one scenario")
        shape = (np.shape(r.truth)[0], np.shape(r.gm_loglik)[-1])
        first = (np.shape(out[0].truth)[0], np.shape(out[0].gm_loglik)[-1])
        if shape != first:
            raise ValueError(f"{name}[{i}] has {shape[0]} frames and {shape[1]} nodes, {name}[0] {first[0]} and "
                             f"{first[1]}: the runs must be of one scenario")
        if readings:
            for where, key in _READINGS:
                if key not in getattr(r, where):
                    raise ValueError(f"{name}[{i}] holds no readings ({where} lacks {shown(key)}): the runs must be "
                                     "computed with RangeBearingScenario.readings=True")
    if sc is not _NO_SCENARIO:
        instance_of(sc, RangeBearingScenario, "sc")
        if own is not None:
            diff = _differences(sc, own)  # type: ignore[arg-type]
            if diff:
                raise ValueError(f"sc is not the scenario of {name} (it differs from the runs' in {diff})")
        elif out:
            k, n = np.shape(out[0].truth)[0], np.shape(out[0].gm_loglik)[-1]
            if (k, n) != (sc.frames, len(sc.sensors)):  # type: ignore[attr-defined]
                raise ValueError(f"sc is not the scenario of {name}: {sc.frames} frames and {len(sc.sensors)} "  # type: ignore[attr-defined]
                                 f"sensors, the runs {k} frames and {n} nodes")
    return out


def _check_size(runs: list[TrackingRun], value: object, field_name: str, name: str) -> int:
    """``value`` (argument ``name``) a count equal to the runs' recorded ``scenario.<field_name>`` where recorded."""
    value = count(value, name)
    own = next((r.scenario for r in runs if r.scenario is not None), None)
    if own is not None and getattr(own, field_name) != value:
        raise ValueError(f"{name} = {value} is not the runs' RangeBearingScenario.{field_name} "
                         f"({getattr(own, field_name)})")
    return value


def _computed(runs: list[TrackingRun], key: str, field: str) -> None:
    """Check that every run computed the method ``key`` (its ``field`` dict holds it): a documented key of
    :data:`METHODS` that a run did not compute (a variant, a reading) is refused by name, not a KeyError."""
    for i, r in enumerate(runs):
        held = getattr(r, field)
        if key not in held:
            raise ValueError(f"key: runs[{i}] did not compute the method {shown(key)} (TrackingRun.{field} holds "
                             f"{sorted(held)}; RangeBearingScenario.variants and .readings add the others)")


def monte_carlo(sc: RangeBearingScenario, seed: int, runs: int, all_nodes_first: bool = True,
                workers: int = 1) -> list[TrackingRun]:
    """Independent Monte-Carlo runs of :func:`run_tracking` (seeds from ``SeedSequence(seed).spawn``), batched.

    Computed by :func:`run_tracking_batch`, which gives what :func:`run_tracking` gives run by run.

    Parameters
    ----------
    sc : RangeBearingScenario
    seed : int
        Root seed; run ``r`` uses the ``r``-th child of ``numpy.random.SeedSequence(seed)``.
    runs : int
        Number of runs (>= 1).
    all_nodes_first : bool
        Let every node fuse on its own in the first run (``node_estimates`` of run 0).
    workers : int
        Processes sharing the runs (:func:`run_tracking_batch`; the result does not depend on it).

    Returns
    -------
    list of TrackingRun, length ``runs``
        Run r: :func:`run_tracking` with the r-th seed spawned from ``seed``.

    Raises
    ------
    ValueError
        A bad argument, named; ``runs`` and ``sc``'s counts beyond the memory or work budget, before any work; ``sc``:
        a node's particle cloud that collapses (its covariance singular to working precision, a run whose true path
        passes by a sensor) is refused at the frame it happens, after the blocks of runs before it (fuzz 40a D1: 17
        CPU-s into 400 runs with a sensor on the nominal path). Whether a cloud collapses depends on the draws of the
        run, so no check before the work can tell it; a path that reaches a sensor is refused at that frame too.
    """
    runs = count(runs, "runs")  # >= 1 and at most MAX_COUNT
    instance_of(sc, RangeBearingScenario, "sc")
    # the particles of every node drawn over the frames of a run, the particle clouds of a block of runs, and
    # the covariances kept (per method, run and frame)
    _block_allocation(sc, runs, "runs, sc.sensors and sc.n_particles")
    allocation((runs, int(sc.frames), 4, 4), "runs and sc.frames")
    _tracking_work(sc, runs, "runs, sc.frames, sc.sensors, sc.n_initial, sc.n_components and sc's particle and sample "
                   "counts")
    seed = check_seed(seed)
    flag(all_nodes_first, "all_nodes_first")
    seeds = np.random.SeedSequence(seed).spawn(int(runs))
    return run_tracking_batch(sc, seeds, all_nodes=[bool(all_nodes_first) and r == 0 for r in range(len(seeds))],
                              workers=workers)


def position_sq_errors(runs: list[TrackingRun], key: str) -> FloatArray:
    """Squared position error :math:`(\\hat x - x)^2 + (\\hat y - y)^2` of one method.

    Parameters
    ----------
    runs : list of TrackingRun
    key : str
        A key of :data:`METHODS`.

    Returns
    -------
    ndarray, shape (runs, K), m²
        Entry (r, k): the method's squared position error in run r at frame k.
    """
    _check_runs(runs, nonempty=True)
    key = one_of(key, tuple(sorted(METHODS)), "key")
    _computed(runs, key, "estimates")
    e = np.stack([r.estimates[key] - r.truth for r in runs])
    return e[..., 0] ** 2 + e[..., 2] ** 2


def nees_per_frame(runs: list[TrackingRun], key: str) -> FloatArray:
    """Normalised estimation error squared (4-D state) of one method, per run and frame.

    Parameters
    ----------
    runs : list of TrackingRun
    key : str
        A key of :data:`METHODS` other than ``"mean_of_local_means"`` (which has no covariance).

    Returns
    -------
    ndarray, shape (runs, K); 4 on average for a consistent estimator
        Entry (r, k): the NEES of the method's 4-state estimate in run r at frame k.

    Raises
    ------
    TypeError
        ``runs`` not a sequence of :class:`TrackingRun`; ``key`` not a str.
    ValueError
        ``runs`` empty, of several scenarios or without the method's estimates; ``key`` not such a key; a covariance of the method that
        cannot be inverted, naming ``runs`` and ``key``: the runs of a :class:`RangeBearingScenario` with
        ``n_central`` or ``n_samples`` at most the state dimension (4) hold singular sample covariances, which have
        no NEES (fuzz 32a C6).
    """
    _check_runs(runs, nonempty=True)
    key = one_of(key, tuple(sorted(k for k in METHODS if k != "mean_of_local_means")), "key")
    _computed(runs, key, "estimates")
    _computed(runs, key, "covariances")
    d = np.stack([r.estimates[key] - r.truth for r in runs])
    try:
        return nees(d, np.stack([r.covariances[key] for r in runs]))
    except ValueError as exc:  # the inner argument's name is not the caller's; chained: callers read the cause
        if not str(exc).startswith("covariances must be positive definite"):
            raise
        raise ValueError(f"runs: the covariances of key {shown(key)} have no NEES ({exc}); a scenario with n_central "
                         "or n_samples at most the state dimension (4) gives singular sample covariances") from exc


def min_local_ess(runs: list[TrackingRun]) -> FloatArray:
    """Smallest effective sample size of any node's particle filter in each run (any frame).

    Parameters
    ----------
    runs : list of TrackingRun
        The Monte-Carlo runs; the minimum is taken over each run's ``ess["local"]``, shape (K, N)
        (ESS before resampling, per frame and node).

    Returns
    -------
    ndarray, shape (runs,)
        Effective particles (of ``n_particles``); empty for no runs.
    """
    _check_runs(runs, nonempty=False)
    out = []
    for i, r in enumerate(runs):
        if not isinstance(r.ess, Mapping) or "local" not in r.ess:
            raise ValueError(f"runs[{i}].ess must hold the local filters' ESS under 'local'")
        ess = as_array(r.ess["local"], f"runs[{i}].ess['local']", ndim=2, nonnegative=True)
        out.append(float(np.min(ess)))
    return np.array(out)
