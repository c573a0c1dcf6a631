"""The chapter's keys and settings: the source, the frame windows, the study's run count and scenario.

Part of :mod:`fusion.book.chapters.chernoff` (chapter 06, patent CN107330468B), which re-exports its public names."""

from __future__ import annotations

import dataclasses
import inspect

import numpy as np

from fusion._shown import shown
from fusion._validation import FloatArray, as_array, instance_of
from fusion.optimise.swarm import particle_swarm
from fusion.scenarios.range_bearing import METHODS, RangeBearingScenario, TrackingRun, _NO_SCENARIO, _check_runs
from fusion.book.glue import GlueValues

__all__ = ["BIBKEY", "LATE", "COLLAPSE_FRACTION", "pso_defaults", "STUDY_RUNS", "STUDY_WORKERS", "STUDY_REASON",
           "EARLY", "ALL_FRAMES", "study_scenario", "guarded_scenario"]


#: BibTeX key of the source.
BIBKEY = "cn107330468b"


#: Frames 5 to the last (0-based slice; frames 5-30 in the study scenario): the frames over which errors are averaged.
LATE = slice(4, None)


#: Frames 1-4 (0-based slice), where the shared prior still weighs most.
EARLY = slice(0, 4)


#: Every frame.
ALL_FRAMES = slice(None)


#: A run is *collapsed* when some node's filter keeps fewer effective particles than this fraction of its
#: particles (10 of the default 2,000), or the centralised filter fewer than this fraction of its own (50 of 10,000).
COLLAPSE_FRACTION = 0.005


_MSE = "per-run mean squared position error from frame 5 on (m²)"


#: Monte-Carlo runs of the chapter's study (the house minimum for a comparison).
STUDY_RUNS = 100


#: Worker processes of the study (:func:`fusion.scenarios.range_bearing.run_tracking_batch`; results do not depend on it).
STUDY_WORKERS = 2


#: Why a comparison has fewer than :data:`STUDY_RUNS` runs (the runs kept when the collapsed ones are excluded).
STUDY_REASON = "the runs kept of the study's 100 when the runs with a collapsed filter are excluded"


def study_scenario() -> RangeBearingScenario:
    """The scenario of the chapter's 100-run study: the defaults of :class:`RangeBearingScenario`, with the readings.

    30 frames, 2,000 particles per node, R = 2,000 importance samples, 10,000 centralised particles; the
    readings of steps D, F and G6 (``readings=True``) and the variant with ε⁽⁰⁾ = the previous ε*
    optimised by the projected Newton method (``prev_optimiser="newton"``, the swarm's optimum within its
    sampling error, record ``chf-pso``). Without collapse guard: :func:`guarded_runs` adds it.

    Returns
    -------
    RangeBearingScenario
        The default scenario with ``readings=True`` and ``prev_optimiser="newton"``, no collapse guard.
    """
    return dataclasses.replace(RangeBearingScenario(), readings=True, prev_optimiser="newton")


def guarded_scenario(sc: RangeBearingScenario) -> RangeBearingScenario:
    """``sc`` with the collapse guard of every filter (nodes and centralised) at :data:`COLLAPSE_FRACTION`.

    Parameters
    ----------
    sc : RangeBearingScenario

    Returns
    -------
    RangeBearingScenario
        ``guard`` and ``central_guard`` set to :data:`COLLAPSE_FRACTION`.

    Raises
    ------
    TypeError
        ``sc`` not a RangeBearingScenario.
    """
    instance_of(sc, RangeBearingScenario, "sc")
    return dataclasses.replace(sc, guard=COLLAPSE_FRACTION, central_guard=COLLAPSE_FRACTION)


def pso_defaults() -> GlueValues:
    """Default settings of :func:`fusion.optimise.swarm.particle_swarm`, as glue values ``chf_pso_*``.

    Read from the function's signature, so the prose quotes the defaults the study actually used.

    Returns
    -------
    dict
        ``chf_pso_inertia`` (inertia weight), ``chf_pso_c1`` (cognitive coefficient),
        ``chf_pso_n`` (particles), ``chf_pso_iter`` (largest number of iterations),
        ``chf_pso_tol`` (stagnation tolerance on the best fitness) and ``chf_pso_patience``
        (iterations of stagnation before stopping); values unrounded, as in the signature.
    """
    p = inspect.signature(particle_swarm).parameters
    names = {"inertia": "inertia", "c1": "c1", "n": "n_particles", "iter": "iterations", "tol": "tol",
             "patience": "patience"}
    return {f"chf_pso_{k}": p[v].default for k, v in names.items()}


#: The nodes the chapter's tables and figures show: the local filters of ``METHODS`` (``local1`` ... ``local3``).
_TABLE_NODES = sum(k.startswith("local") for k in METHODS)


#: The variants of ``RangeBearingScenario.variants`` (NaN records when it is False).
_VARIANTS = ("chernoff_slsqp", "chernoff_redraw", "chernoff_prev")


def _check_window(runs: list[TrackingRun], name: str = "runs") -> None:
    """``runs`` (checked by ``_check_runs``) hold a frame of :data:`LATE`, the window the chapter averages (fuzz 26b
    class FW): ValueError naming ``name`` for runs of fewer than 5 frames, whose averages would be of no frame."""
    k = int(np.shape(runs[0].truth)[0])
    if not range(k)[LATE]:
        raise ValueError(f"{name} has {k} frames: the chapter averages frames {LATE.start + 1} on (LATE), so its runs "
                         f"need at least {LATE.start + 1} (RangeBearingScenario.frames >= {LATE.start + 1})")


def _check_study(runs: object, sc: object = _NO_SCENARIO, *, name: str = "runs", readings: bool = False,
                 like: list[TrackingRun] | None = None, like_name: str = "runs", window: bool = False,
                 nodes: bool = False, variants: bool = False, least: int = 1, why: str = "") -> list[TrackingRun]:
    """The chapter's one check of a run list (issue 35, fuzz 22b class TR, fuzz 24b class PR), applied by every
    helper over runs: ``fusion.scenarios.range_bearing._check_runs`` (a non-empty sequence of TrackingRun of one
    scenario, ``sc`` that scenario, the readings where asked), no run twice (two runs of one truth: a repeated run
    would count as an independent replicate), and with ``like`` (another list of the same study: the runs with and
    without the guard) the same runs but for the guard: as many, of the same scenario, and the same truths (a run
    and its unguarded twin share the seed, so the truth; another seed's runs differ). Runs are identified by their
    truth; the runs of ``like``'s truths are returned in ``like``'s order (a reordered list pairs as given in
    order). Returns the runs as a list.

    What the chapter's tables and figures can show (fuzz 26b, classes FW, NS, VA, R1), asked by each helper for what
    it reads, ValueError naming ``name``: with ``window`` (a helper averaging frames 5 on) a frame of :data:`LATE`
    (``_check_window``); with ``nodes`` (a helper showing every node) at most the 3 nodes of ``METHODS`` (a fourth
    node's filter, ``local4``, has no row or key: it would be left out silently); with ``variants`` the records of
    ``RangeBearingScenario.variants`` (NaN when False), as ``readings`` asks for the readings; at least ``least``
    runs (``why`` says what needs them: paired runs)."""
    out = _check_runs(runs, True, sc, name=name, readings=readings)
    if len(out) < least:
        raise ValueError(f"{name} holds {len(out)} run{'s' if len(out) != 1 else ''}: at least {least} are needed "
                         f"({why})")
    if window:
        _check_window(out, name)
    if nodes:
        n = int(np.shape(out[0].gm_loglik)[-1])
        if n > _TABLE_NODES:
            raise ValueError(f"{name} has {n} nodes: the chapter's tables and figures show at most {_TABLE_NODES} "
                             f"(METHODS holds local1-local{_TABLE_NODES}; RangeBearingScenario.sensors with at most "
                             f"{_TABLE_NODES} sensors)")
    if variants:
        for i, r in enumerate(out):
            for key in _VARIANTS:
                if key in r.estimates and not np.all(np.isfinite(r.estimates[key])):
                    raise ValueError(f"{name}[{i}] holds no variants (estimates[{shown(key)}] is NaN): the runs must be "
                                     "computed with RangeBearingScenario.variants=True")
    seen: dict[bytes, int] = {}
    for i, r in enumerate(out):
        j = seen.setdefault(np.asarray(r.truth, dtype=float).tobytes(), i)
        if j != i:
            raise ValueError(f"{name}[{i}] repeats {name}[{j}] (the same truth): each run must appear once, a repeated "
                             "run is not an independent replicate")
    if like is not None:
        if len(out) != len(like):
            raise ValueError(f"{name} holds {len(out)} runs, {like_name} {len(like)}: the same study's runs are needed")
        _check_runs(list(like) + out, True, name=f"{like_name} + {name}")
        order = []
        for i, r in enumerate(like):
            j = seen.get(np.asarray(r.truth, dtype=float).tobytes())
            if j is None:
                raise ValueError(f"{name} holds no run with the truth of {like_name}[{i}]: the same study's runs are "
                                 f"needed (the runs of one seed with and without the guard), not another seed's")
            order.append(out[j])
        out = order
    return out


def _check_crb(crb_pos: object, runs: list[TrackingRun]) -> FloatArray:
    """``crb_pos`` (:func:`crb_position` of the runs): finite, non-negative, one entry per frame of ``runs``; a
    mismatch names both (the bound of another scenario, or runs of another one)."""
    out = as_array(crb_pos, "crb_pos", ndim=1, nonnegative=True)
    k = int(np.shape(runs[0].truth)[0])
    if out.shape != (k,):
        raise ValueError(f"crb_pos must hold one bound per frame of runs ({k} frames), got shape {out.shape}: "
                         "crb_position of these runs' scenario gives it")
    return out
