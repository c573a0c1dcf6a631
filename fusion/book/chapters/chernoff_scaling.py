"""Chapter 06 appendix: the book's swarm against a convex solver as the number of nodes grows, the cost of
steps D-H in N, S and R, and the geometry of one frame with the local particle clouds.

Studies of the book's rebuild (the patent prints no swarm settings and no scenario); none is a record except the
reading ``ten-nodes`` of ``chf-pso-rebuild`` (:func:`swarm_within_se`).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any
import numpy as np
import pandas as pd
from numpy.typing import ArrayLike
from matplotlib.figure import Figure
from fusion._frozen import constant
from fusion._docstrings import with_sections
from fusion._results import ResultSpec, array, dict_of, integer, mask, tuple_of, validated_post_init
from fusion._shown import shown
from fusion._validation import FloatArray, as_rng, allocation, as_array, count, counts, distinct, instance_of, scalar
from fusion._counts import sequence
from fusion._limits import dense_work, loop_work, work
from fusion.book.style import METHOD_LABELS
from fusion.book.tables import rounded, sci
from fusion.estimates import chernoff as ch
from fusion.optimise.swarm import SwarmOptions
from fusion.scenarios.range_bearing import RangeBearingScenario
from fusion.book.chapters.chernoff_steps import paired_numbers
from fusion.book.glue import GlueValues
from fusion._counts import seed as check_seed
from fusion.book.chapters._defaults import study_defaults

__all__ = ['within_se_counts', 'gaussian_problems', 'SWARM_VARIANTS', 'SwarmStudy', 'swarm_study', 'swarm_within_se', 'box_corner', 'ScalingStudy', 'density_evaluations', 'cost_table', 'scaling_study', 'FrameClouds', 'frame_clouds', 'clouds_figure']


# ---------------------------------------------------------------------------------------------- step G: N sensors


#: Units of work of one ``d**3`` of :func:`gaussian_problems` (the einsum ``A A^T`` of a problem and node, numpy's
#: own loop, not BLAS). Measured (fuzz 44 C4: d = 5,000 was accepted and ran 66.4 CPU-s, only its memory counted;
#: CPU time, minimum of 2, OPENBLAS_NUM_THREADS=1, shared machine, runs = n = 1): 0.051 / 0.47 / 2.48 s at
#: d = 600 / 1,200 / 2,000, i.e. 0.024 / 0.027 / 0.031 units a ``d**3``, growing with d (0.053 at the fuzz's 5,000);
#: counted as 0.05, so the accepted edge (d = 2,714 at runs = n = 1) costs about 10 CPU-s.
_PROBLEM_CUBE_UNITS = 0.05


def _problem_arrays(d: int) -> int:
    """The ``(runs, n, d, d)`` arrays :func:`gaussian_problems` holds at once, rounded up (fuzz 45 C1).

    Measured (``tracemalloc`` peak over one array's bytes, shared machine): 6.00 / 4.00 / 3.56 / 3.38 / 3.16 / 3.09
    / 3.09 at d = 1 / 2 / 3 / 4 / 8 / 16 / 64 (runs x n = 1e6 .. 40), fitted exactly by ``3 d^2 + d + 2`` float64 a
    problem and node (``A``, the einsum, its quotient by d and the mean, weight and scale arrays) over ``d^2``;
    rounded up: 6 at d = 1, else 4. Only one array of the shape was counted before: runs = 2**22, n = 1, d = 8 ran
    17.6 CPU-s into a MemoryError under a 6 GiB address limit.
    """
    return -(-(3 * d * d + d + 2) // (d * d))


def gaussian_problems(rng: np.random.Generator, runs: int, n: int, d: int = 2) -> tuple[FloatArray, FloatArray,
                                                                                         FloatArray]:
    r"""Random fusion problems: ``n`` local Gaussian posteriors (one component each) per run, as mixture arrays.

    Node i's mean is :math:`\mathcal N(0, I)` and its covariance :math:`s_i^2 (AA^\top/d + I/2)` with :math:`A`
    standard normal and :math:`\log_2 s_i` uniform on [-1, 1]: nodes of unequal, differently shaped uncertainty
    that disagree, so that the exponents matter.

    Parameters
    ----------
    rng : numpy.random.Generator
    runs, n : int
        Problems and nodes per problem.
    d : int
        State dimension.

    Returns
    -------
    weights, means, covs : ndarrays of shapes (runs, n, 1), (runs, n, 1, d), (runs, n, 1, d, d)
        The arrays of :func:`fusion.estimates.chernoff.fuse_mixtures_batch`.

    Raises
    ------
    ValueError
        ``runs``, ``n`` or ``d`` below 1, or ``runs x n`` matrices of ``d x d`` beyond the memory budget (4 arrays
        of them held at once, 6 at ``d = 1``) or the work budget (``fusion._limits.dense_work``: at
        ``runs = n = 1``, ``d`` up to 2,714).
    """
    as_rng(rng)  # a Generator itself, over a numpy bit generator (fuzz 57b C1)
    runs, n, d = count(runs, "runs"), count(n, "n"), count(d, "d")
    allocation((runs, n, d, d), "runs, n and d", _problem_arrays(d))
    dense_work(runs * n, d, "runs, n and d", _PROBLEM_CUBE_UNITS)  # the A A^T of each problem and node (fuzz 44 C4)
    means = rng.standard_normal((runs, n, 1, d))
    A = rng.standard_normal((runs, n, 1, d, d))
    s2 = 4.0 ** rng.uniform(-1, 1, (runs, n, 1, 1, 1))
    covs = s2 * (np.einsum("...ij,...kj->...ik", A, A) / d + 0.5 * np.eye(d))
    return np.ones((runs, n, 1)), means, 0.5 * (covs + np.swapaxes(covs, -1, -2))


#: Swarm variants of :func:`swarm_study` at the largest N: key -> options of the swarm (the defaults first;
#: display labels in :data:`fusion.book.style.METHOD_LABELS`).
SWARM_VARIANTS: dict[str, SwarmOptions] = constant({"pso_defaults": SwarmOptions(),
                                           "pso_floor": SwarmOptions(lo=1e-12),
                                           "pso_iterations": SwarmOptions(iterations=200, patience=40)})


@dataclass(frozen=True)
class SwarmStudy:
    r"""The swarm against SLSQP on the same samples as the number of nodes grows.

    Attributes
    ----------
    gap : dict
        (N, variant) -> (runs,) :math:`\hat J` at the swarm's optimum minus at SLSQP's (nats, >= 0 up to
        SLSQP's tolerance: SLSQP minimises the same convex function).
    evaluations : dict
        (N, variant) -> (runs,) objective evaluations of the swarm; ``(N, "SLSQP")`` those of SLSQP.
    corner : dict
        (N, variant) -> (runs,) bool: the optimum found has two or more equal positive exponents, the image of a
        corner of the position box :math:`[\text{lo}, 1]^N` (several coordinates at the ceiling 1, the rest at the
        floor) under :math:`u \mapsto u/\sum_j u_j` (:func:`box_corner`); ``(N, "SLSQP")`` the same for SLSQP's.
    runs, r : int
    """

    gap: Mapping[tuple[int, str], FloatArray]
    evaluations: Mapping[tuple[int, str], FloatArray]
    corner: Mapping[tuple[int, str], np.ndarray]
    runs: int
    r: int

    __result_spec__ = ResultSpec({"gap": dict_of(array("runs"), key=tuple),
                                  "evaluations": dict_of(array("runs", bounds=(1.0, np.inf)), key=tuple),
                                  "corner": dict_of(mask("runs"), key=tuple), "runs": integer(2), "r": integer(2)},
                                 relations=(lambda v, cls: _swarm_relation(v, cls),))
    __post_init__ = validated_post_init


    def table(self) -> pd.DataFrame:
        """Per N and variant: median and mean gap, share of runs the swarm is above SLSQP by > 1e-6, evaluations."""
        rows = []
        for (n, v), g in self.gap.items():
            rows.append({"N": n, "swarm": METHOD_LABELS[v], "median gap (nats)": sci(float(np.median(g)), 3),
                         "mean gap (nats)": sci(float(np.mean(g)), 3), "share gap > 10⁻⁶": rounded(np.mean(g > 1e-6), 2),
                         "share at a box corner": rounded(np.mean(self.corner[(n, v)]), 2),
                         "swarm evaluations (median)": int(np.median(self.evaluations[(n, v)])),
                         "SLSQP evaluations (median)": int(np.median(self.evaluations[(n, "SLSQP")]))})
        return pd.DataFrame(rows).set_index(["N", "swarm"])

    def glue(self) -> GlueValues:
        """Glue ``chf_sw_*``: sizes; the gap at the smallest N (median, share above 1e-6); at the largest N the paired
        gap against zero, the share, each variant against the defaults, and the evaluations."""
        ns = sorted({n for n, _ in self.gap})
        base = next(iter(SWARM_VARIANTS))
        lo, hi = self.gap[(ns[0], base)], self.gap[(ns[-1], base)]
        v: dict[str, Any] = {"chf_sw_runs": self.runs, "chf_sw_r": self.r, "chf_sw_ns": ", ".join(map(str, ns)),
                             "chf_sw_n_max": ns[-1], "chf_sw_n_min": ns[0],
                             "chf_sw_med_min": float(f"{np.median(lo):.2g}"),
                             "chf_sw_share_min": rounded(float(np.mean(lo > 1e-6)), 2),
                             "chf_sw_share_max": rounded(float(np.mean(hi > 1e-6)), 2),
                             "chf_sw_evals_max": int(np.median(self.evaluations[(ns[-1], base)])),
                             "chf_sw_evals_slsqp": int(np.median(self.evaluations[(ns[-1], "SLSQP")])),
                             "chf_sw_corner_max": rounded(float(np.mean(self.corner[(ns[-1], base)])), 2),
                             "chf_sw_corner_slsqp": rounded(float(np.mean(self.corner[(ns[-1], "SLSQP")])), 2),
                             "chf_sw_corner_iter": rounded(float(np.mean(self.corner[(ns[-1], "pso_iterations")])),
                                                           2)}
        v.update(paired_numbers(hi, np.zeros(self.runs), "chf_sw_gap_max", 4))
        for k in ("runs", "won"):
            v.pop(f"chf_sw_gap_max_{k}")
        for j, name in enumerate(SWARM_VARIANTS):
            if j:
                v.update(paired_numbers(self.gap[(ns[-1], name)], hi, f"chf_sw_var{j}", 6))
                for k in ("runs", "won", "stat") + (("med",) if j == 2 else ()):
                    v.pop(f"chf_sw_var{j}_{k}")
        return v


#: The Parameters entries of the studies over numbers of nodes (:func:`fusion._docstrings.with_sections`).
_on_problems = with_sections("""seed : int
ns : tuple of int
    Numbers of nodes (each >= 2).
runs : int""")


def _problem_budget(n: int, runs: int, r: int, names: tuple[str, str, str], square: int) -> None:
    """The memory budget of steps D-G on ``runs`` problems of :func:`gaussian_problems` with ``n`` nodes and ``r``
    samples (fuzz 22b, class SW), checked before anything is drawn and named by the caller's arguments
    (``names``: those of n, runs and r): ``square`` float64 arrays of n × n per problem at once (measured peaks:
    SLSQP's work array, about 10.5 n², for the swarm's reference; the Newton steps' n × n matrices, about 6.5 n² per
    problem, for the scaling study) and the samples' log densities, r × n per problem, with their temporaries
    (measured: about 8)."""
    n_name, runs_name, r_name = names
    allocation((square, n, n), n_name)
    allocation((runs, r, n, 8), f"{runs_name}, {r_name} and {n_name}")


#: Units of work (``fusion._limits.work``, about 10 ns) of one problem of :func:`gaussian_problems` through the swarm
#: and its SLSQP reference on the same ``r`` samples (``_swarm_and_slsqp``, the swarm's default options): a fixed part,
#: a part per node, SLSQP's dense steps (n³), per sample and per sample and node. Measured (fuzz 42b C9; CPU time,
#: minimum of 2, OPENBLAS_NUM_THREADS=1, shared machine; swarm_within_se): 2.56 / 1.42 ms a problem at n = 2 and
#: r = 1000 / 100, 4.42 / 3.00 ms at n = 10, 15.5 / 10.0 ms at n = 40, 10.7 ms at n = 5 and r = 4000, 45.5, 275 and
#: 736 ms at n = 100, 200 and 300 (r = 100); the counts below are within 0.7x to 1.3x of each (the fuzz's 4,500 runs
#: of n = 2, three variants, 35.7 CPU-s: counted 4.4e9).
_PROBLEM_UNITS = 100_000
_NODE_UNITS = 22_000
_CUBE_UNITS = 3
_SAMPLE_UNITS = 150
_SAMPLE_NODE_UNITS = 15


def _swarm_units(n: int, r: int) -> int:
    """The units of one problem of ``n`` nodes and ``r`` samples through the swarm and SLSQP (the weights above)."""
    return _PROBLEM_UNITS + _NODE_UNITS * n + _CUBE_UNITS * n**3 + _SAMPLE_UNITS * r + _SAMPLE_NODE_UNITS * r * n


def _swarm_budget(runs: int, r: int, variants: dict[int, tuple[SwarmOptions, ...]], names: str) -> None:
    """Rule 17 at the entry of a swarm study (fuzz 42b C9: each swarm checked only itself, after the smaller N ran):
    every N's problems, once per swarm variant run on them (``variants``: N -> the options), weighed by
    :func:`_swarm_units`; and the callees' own budgets of the largest N (each swarm's loop, SLSQP's weights), all
    naming the caller's arguments ``names``."""
    from fusion.optimise.simplex import _simplex_work
    from fusion.optimise.swarm import _swarm_work

    work((sum(runs * len(opts) * _swarm_units(n, r) for n, opts in variants.items()),), names)
    for n, opts in variants.items():
        for o in opts:
            _swarm_work(runs, o.n_particles, o.iterations, n, names)
    _simplex_work(max(variants), True, names)


def _swarm_and_slsqp(w: FloatArray, m: FloatArray, c: FloatArray, seed: int, r: int,
                     swarm_options: SwarmOptions | None = None) -> list[ch.MixtureFusion]:
    """Steps E-G on the problems (w, m, c) of :func:`gaussian_problems`, the swarm and the SLSQP reference on the same
    ``r`` importance samples; problem k uses the k-th child of ``SeedSequence(seed)``."""
    rngs = [np.random.default_rng(s) for s in np.random.SeedSequence(seed).spawn(w.shape[0])]
    return ch.fuse_mixtures_batch(w, m, c, rngs, n_samples=r, optimiser="pso", reference=True,
                                  swarm_options=swarm_options)


def _swarm_relation(values: dict[str, Any], cls: str) -> None:
    """One entry per run; the same (N, variant) keys in gap and corner, plus (N, "SLSQP") for every N there in the
    evaluations and corners (the table and the glue read them)."""
    runs = values["runs"]
    for name in ("gap", "evaluations", "corner"):
        for key, arr in values[name].items():
            if arr.shape[0] != runs:
                raise ValueError(f"{cls}.{name}[{shown(key)}] must have one entry per run ({runs}), got {arr.shape[0]}")
    keys = set(values["gap"]) | {(n, "SLSQP") for n, _ in values["gap"]}
    for name in ("evaluations", "corner"):
        if set(values[name]) != keys:
            missing, extra = sorted(keys - set(values[name])), sorted(set(values[name]) - keys)
            raise ValueError(f"{cls}.{name} must have the keys of gap and (N, 'SLSQP') for each N, "
                             f"misses {shown(missing, 200)}, has extra {shown(extra, 200)}")


@_on_problems
def swarm_study(seed: int, ns: tuple[int, ...] = (2, 5, 10), runs: int = 100, r: int = 1000) -> SwarmStudy:
    r"""Steps E-G on :func:`gaussian_problems` with N nodes: the swarm's :math:`\hat J` against SLSQP's, same samples.

    For every N, ``runs`` problems run :func:`fusion.estimates.chernoff.fuse_mixtures_batch` with the swarm and the
    SLSQP reference on the same importance samples (``reference=True``); at the largest N the swarm also runs with
    each variant of :data:`SWARM_VARIANTS` on the same samples (the same generator seeds: the samples are drawn
    before the swarm). Problem k of every N and variant uses the k-th child of ``SeedSequence(seed)``.

    Parameters
    ----------
    r : int
        Importance samples per problem.

    Returns
    -------
    SwarmStudy
        Per (N, variant or "SLSQP"): Ĵ's gap swarm − SLSQP (nats), the objective evaluations and the box-corner flags,
        one entry per problem.

    Raises
    ------
    TypeError
        An argument not an integer, or ``ns`` not a sequence of integers.
    ValueError
        ``runs`` or ``r`` below 2, ``ns`` empty, an entry below 2, or an entry repeated (the study is keyed by N);
        the largest N, ``runs`` and ``r`` beyond the memory budget (the SLSQP reference needs about 10.5 N² numbers);
        every N's problems, once per swarm variant, beyond the work budget (``fusion._limits.MAX_WORK``; a problem
        weighs its measured cost, about 100,000 + 22,000 N + 3 N³ + 150 r + 15 r N units), or a swarm or SLSQP of the
        largest N beyond its own, before any work, naming ``ns``, ``runs`` and ``r``.
    """
    seed = check_seed(seed)
    runs, r = count(runs, "runs", minimum=2), count(r, "r", minimum=2)
    # fuzz 62a's class (C3): each N runs a study, a loop step at least, counted by len(ns) before any is read (10**7
    # entries were read and hashed for 4.1 CPU-s before the budget)
    ns = sequence(ns, "ns")
    loop_work((len(ns),), 0, "ns")
    ns = tuple(distinct(counts(ns, "ns", minimum=2), "ns"))
    _problem_budget(max(ns), runs, r, ("ns", "runs", "r"), square=11)
    _swarm_budget(runs, r, {n: tuple(SWARM_VARIANTS.values()) if n == max(ns) else (SwarmOptions(),) for n in ns},
                  "ns, runs and r")
    gap: dict[tuple[int, str], FloatArray] = {}
    evals: dict[tuple[int, str], FloatArray] = {}
    corner: dict[tuple[int, str], np.ndarray] = {}
    for n in ns:
        w, m, c = gaussian_problems(np.random.default_rng([seed, n]), runs, n)
        variants = SWARM_VARIANTS if n == max(ns) else dict(list(SWARM_VARIANTS.items())[:1])
        for name, opts in variants.items():
            res = _swarm_and_slsqp(w, m, c, seed, r, opts)
            gap[(n, name)] = np.array([x.objective - x.objective_reference for x in res])
            evals[(n, name)] = np.array([x.n_evaluations for x in res], dtype=float)
            evals[(n, "SLSQP")] = np.array([x.n_evaluations_reference for x in res], dtype=float)
            corner[(n, name)] = box_corner(np.stack([x.eps for x in res]))
            corner[(n, "SLSQP")] = box_corner(np.stack([x.eps_reference for x in res]))  # type: ignore[misc]
    return SwarmStudy(gap, evals, corner, runs, r)


def swarm_within_se(seed: int, n: int, runs: int = 100, r: int = 1000) -> tuple[FloatArray, FloatArray]:
    r"""The swarm's :math:`\hat J` minus SLSQP's on the same samples, and :math:`\hat J`'s own standard error, N nodes.

    The problems of :func:`swarm_study` for one N (the swarm at its defaults, ``runs`` problems of
    :func:`gaussian_problems`, importance samples drawn before either optimiser runs); the standard error is the
    delta method's :math:`\sqrt{\max(1/\mathrm{ESS} - 1/R, 0)}`, as record ``chf-pso-rebuild`` uses in the tracking
    study.

    Parameters
    ----------
    seed, n, runs, r : int
        Seed, nodes (>= 2), problems and importance samples per problem.

    Returns
    -------
    gap, se : ndarray, shape (runs,)
        Nats.

    Raises
    ------
    TypeError
        An argument not an integer.
    ValueError
        ``n``, ``runs`` or ``r`` below 2, or beyond the memory budget (the SLSQP reference needs about 10.5 n²
        numbers, the samples' densities about 8 runs × r × n) or the work budget (``fusion._limits.MAX_WORK``, the
        problems weighed as :func:`swarm_study`'s, the swarm's and SLSQP's own), naming ``n``, ``runs`` and ``r``.
    """
    seed = check_seed(seed)
    seed = count(seed, "seed", minimum=0, maximum=None)
    n, runs, r = count(n, "n", minimum=2), count(runs, "runs", minimum=2), count(r, "r", minimum=2)
    _problem_budget(n, runs, r, ("n", "runs", "r"), square=11)
    _swarm_budget(runs, r, {n: (SwarmOptions(),)}, "n, runs and r")
    res = _swarm_and_slsqp(*gaussian_problems(np.random.default_rng([seed, n]), runs, n), seed, r)
    gap = np.array([x.objective - x.objective_reference for x in res])
    se = np.sqrt(np.maximum(1.0 / np.array([x.ess for x in res]) - 1.0 / r, 0.0))
    return gap, se


#: Importance samples per problem of :func:`within_se_counts` (:func:`swarm_within_se`'s default).
_WITHIN_R = 1000


@_on_problems
def within_se_counts(seed: int, ns: tuple[int, ...] = (3, 5, 10), runs: int = 100) -> GlueValues:
    """Glue ``chf_sw_within_<N>``: problems (of ``runs``) in which the swarm is within Ĵ's standard error of SLSQP.

    The test of reading ``ten-nodes`` of ``chf-pso-rebuild`` (:func:`swarm_within_se`) at each N of ``ns``, and
    ``chf_sw_within_runs``.

    Returns
    -------
    dict
        ``chf_sw_within_<N>``: the count of problems within the standard error at each N; ``chf_sw_within_runs``:
        ``runs``.

    Raises
    ------
    TypeError
        An argument not an integer, or ``ns`` not a sequence of integers.
    ValueError
        ``runs`` below 2, ``ns`` empty, an entry below 2, or an entry repeated (the glue keys are keyed by N); every
        N's problems (1,000 importance samples each) beyond the memory or work budget (as :func:`swarm_within_se`'s),
        at entry, naming ``ns`` and ``runs``.
    """
    seed = check_seed(seed)
    out = {"chf_sw_within_runs": count(runs, "runs", minimum=2)}
    ns = sequence(ns, "ns")
    loop_work((len(ns),), 0, "ns")  # a study an N, a loop step at least, by len(ns) before any is read (fuzz 62a C3)
    ns = distinct(counts(ns, "ns", minimum=2), "ns")
    # every N at entry (fuzz 42b C9: n = 2 ran, then the largest N was refused naming r, not an argument here)
    _problem_budget(max(ns), runs, _WITHIN_R, ("ns", "runs", f"the {_WITHIN_R:,} importance samples"), square=11)
    _swarm_budget(runs, _WITHIN_R, {n: (SwarmOptions(),) for n in ns}, "ns and runs")
    for n in ns:
        gap, se = swarm_within_se(seed, n, runs, _WITHIN_R)
        out[f"chf_sw_within_{n}"] = int(np.sum(np.abs(gap) < se))
    return out


#: Tolerance of :func:`box_corner`'s simplex check: an optimiser's exponents (SLSQP's equality constraint
#: included) meet their constraints to round-off well below it.
SIMPLEX_TOL = 1e-6


def box_corner(eps: ArrayLike, tol: float = 1e-9) -> np.ndarray:
    r"""Rows (k, N) with two or more positive entries above 1e-3 that are equal within ``tol``.

    The swarm's positions live in the box :math:`[\text{lo}, 1]^N` and are mapped to the simplex by
    :math:`u \mapsto u/\sum_j u_j`: a corner of the box with m coordinates at the ceiling and the others at the
    floor maps to m exponents of (almost exactly) 1/m. An interior optimum of a continuous objective has such ties
    with probability zero.

    Parameters
    ----------
    eps : array_like, shape (k, N)
        Exponents, each row on the simplex (entries >= 0, sum 1; both within ``SIMPLEX_TOL``, 1e-6).
    tol : float
        Largest difference of two tied exponents (finite, >= 0, below 1e-3, the floor of the entries compared).

    Returns
    -------
    ndarray of bool, shape (k,)
        True for a row whose exponents above 1e-3 include two equal within ``tol`` (a box corner of the swarm).

    Raises
    ------
    TypeError
        ``eps`` or ``tol`` not numeric.
    ValueError
        ``eps`` not a finite 2-D array, a row off the simplex, or ``tol`` negative, not finite or not below 1e-3.
    """
    e = as_array(eps, "eps", ndim=2)
    tol = scalar(tol, "tol", lo=0.0, hi=1e-3, hi_open=True)  # fuzz 18 (debatable): tol = -1 or inf was accepted
    off = np.flatnonzero((e.min(axis=1) < -SIMPLEX_TOL) | (np.abs(e.sum(axis=1) - 1.0) > SIMPLEX_TOL))
    if off.size:
        k = int(off[0])
        raise ValueError(f"eps must hold exponents on the simplex (entries >= 0 summing to 1, within {SIMPLEX_TOL:g}): "
                         f"row {k} has minimum {e[k].min():.3g} and sum {e[k].sum():.6g}")
    out = np.zeros(e.shape[0], dtype=bool)
    for k, row in enumerate(e):
        big = np.sort(row[row > 1e-3])
        out[k] = big.size >= 2 and bool(np.any(np.diff(big) <= tol))
    return out


# ---------------------------------------------------------------------------------------------- scaling in R, S, N


@dataclass(frozen=True)
class ScalingStudy:
    r"""Accuracy of steps E-G in R against the exact Chernoff exponents, and the cost of steps D-F in N, S, R.

    Attributes
    ----------
    rs : tuple of int
        Importance samples per problem, increasing (the glue's smallest and largest R are its ends).
    eps_err : ndarray, shape (len(rs), runs)
        :math:`\|\hat\varepsilon^* - \varepsilon^*\|_1` per problem: the exact minimiser of :math:`\hat J` on R samples
        against the closed-form-exact minimiser of :math:`\log Z` (local Gaussians,
        :func:`fusion.estimates.chernoff.gaussian_chernoff_weights`).
    n : int
        Nodes of the accuracy problems.
    runs : int
    """

    rs: tuple[int, ...]
    eps_err: FloatArray
    n: int
    runs: int

    __result_spec__ = ResultSpec({"rs": tuple_of(integer(2)), "eps_err": array("R", "runs", bounds=(0.0, np.inf)),
                                  "n": integer(2), "runs": integer(2)},
                                 relations=(lambda v, cls: _scaling_relation(v, cls),))
    __post_init__ = validated_post_init


    def slope(self) -> float:
        """Least-squares slope of log median error against log R (-1/2 for a Monte-Carlo error)."""
        x, y = np.log(np.array(self.rs, float)), np.log(np.median(self.eps_err, axis=1))
        return float(np.sum((x - x.mean()) * (y - y.mean())) / np.sum((x - x.mean()) ** 2))

    def glue(self) -> GlueValues:
        """Glue ``chf_scale_*``: sizes, the median error at the smallest and largest R, the slope, the cost table's
        density evaluations per sample at N = 10 with S = 3 and with S = 1."""
        med = np.median(self.eps_err, axis=1)
        return {"chf_scale_runs": self.runs, "chf_scale_n": self.n, "chf_scale_rs": ", ".join(map(str, self.rs)),
                "chf_scale_r_lo": self.rs[0], "chf_scale_r_hi": self.rs[-1], "chf_scale_err_lo": rounded(med[0]),
                "chf_scale_err_hi": rounded(med[-1]), "chf_scale_slope": rounded(self.slope(), 2),
                "chf_scale_cost_10_3": density_evaluations(10, 3), "chf_scale_cost_10_1": density_evaluations(10, 1)}

    def table(self) -> pd.DataFrame:
        """Median and 90th percentile of the exponents' error per R."""
        return pd.DataFrame({"R": self.rs, "median ‖ε̂* − ε*‖₁": [rounded(x) for x in np.median(self.eps_err, 1)],
                             "90th percentile": [rounded(x) for x in np.quantile(self.eps_err, 0.9, axis=1)]}
                            ).set_index("R")


def _scaling_relation(values: dict[str, Any], cls: str) -> None:
    """One row of eps_err per R, one column per run; ``rs`` increasing (the glue reads its ends as the smallest and
    the largest R)."""
    if any(b <= a for a, b in zip(values["rs"], values["rs"][1:])):
        raise ValueError(f"{cls}.rs must be increasing (distinct sizes in order), got {values['rs']}")
    if values["eps_err"].shape != (len(values["rs"]), values["runs"]):
        raise ValueError(f"{cls}.eps_err must have shape (len(rs), runs) = ({len(values['rs'])}, {values['runs']}), "
                         f"got {values['eps_err'].shape}")


def density_evaluations(n: int, s: int) -> int:
    r"""Gaussian component densities evaluated per importance sample in steps E-F: :math:`S^N + NS`.

    Step D's first-order mixture has :math:`M_f = \prod_i S_i = S^N` components (before pruning), each evaluated at
    every sample for :math:`g`, and step F evaluates the :math:`NS` local components there; the cost of steps E-F
    is R times this, that of step G R times the swarm's evaluations times N.

    Parameters
    ----------
    n, s : int
        Nodes and components per node.

    Returns
    -------
    int
        S^N + N S, the component densities evaluated per importance sample.

    Raises
    ------
    TypeError
        ``n`` or ``s`` not an integer.
    ValueError
        ``n`` or ``s`` below 1, or S^N + N S beyond the float range (about 1.8e308, the book's bound on a
        printed number), refused before the power is computed (``S^N`` of two counts at their ceiling would run
        for minutes).
    """
    return _evaluations(count(n, "n"), count(s, "s"), "n and s")


#: The largest count :func:`density_evaluations` returns: the float range (the book prints no larger number).
_MAX_EVALUATIONS = int(np.finfo(float).max)


def _evaluations(n: int, s: int, names: str) -> int:
    """S^N + N S for checked counts, refused by ``names`` beyond :data:`_MAX_EVALUATIONS` before the power is
    computed (``n log2 s`` bounds its bits)."""
    if s > 1 and n * np.log2(s) > 1025:  # at least 2**1024 (> the float range): no exact power needed
        raise ValueError(f"{names} give S^N = {s}^{n}, about 10^{n * np.log10(s):,.0f} density evaluations, beyond "
                         f"the float range (at most about 1.8e308; the book prints no larger number)")
    total = s**n + n * s
    if total > _MAX_EVALUATIONS:
        raise ValueError(f"{names} give S^N = {s}^{n}, about 10^{n * np.log10(s):.2f} density evaluations, beyond "
                         f"the float range (at most about 1.8e308; the book prints no larger number)")
    return total


#: Units of work of :func:`cost_table`: a cell (N, S), and a column (one S) as that many cells. Measured (fuzz 44 C5:
#: ns = (1,) against 4,000,000 S was accepted and ran 45.8 CPU-s, nothing counted; CPU time, minimum of 2,
#: OPENBLAS_NUM_THREADS=1, shared machine): 9.4-9.9 us a column of one row (1e5 and 3e5 columns), 0.83 us a cell of
#: one column (3e5 rows), 1.7 us a cell of 30 x 10,000; counted as 150 units a cell and 7 cells (1,050 units) a
#: column, within 1x-1.8x of these, so the accepted edge (about 830,000 columns of one row) costs about 10 CPU-s.
_COST_CELL_UNITS, _COST_COLUMN_CELLS = 150, 7


def cost_table(ns: tuple[int, ...] = (2, 3, 5, 10), ss: tuple[int, ...] = (1, 2, 3)) -> pd.DataFrame:
    """Component densities per importance sample (:func:`density_evaluations`) for every N (rows) and S (columns).

    Parameters
    ----------
    ns, ss : tuple of int

    Returns
    -------
    DataFrame
        Index N (name ``"N"``), one column ``"S = s"`` per S: S^N + N S component densities per sample.

    Raises
    ------
    TypeError
        ``ns`` or ``ss`` is not a sequence of integers.
    ValueError
        ``ns`` or ``ss`` is empty, holds an entry below 1, or repeats an entry (the rows and columns are keyed by them);
        an entry of ``ns`` and one of ``ss`` whose S^N is beyond the float range (:func:`density_evaluations`);
        ``len(ns)`` and ``len(ss)`` beyond the work budget (``fusion._limits.work``, about 830,000 columns of one row).
    """
    # the cells counted by the lengths before any entry is read (fuzz 44 C5; fuzz 61a C1's class: 10**7 entries were
    # read and hashed first, refused after 2.8-3.2 CPU-s); the lists read once are the ones checked
    ns, ss = sequence(ns, "ns"), sequence(ss, "ss")
    work((len(ss), len(ns) + _COST_COLUMN_CELLS), "ns and ss", weight=_COST_CELL_UNITS)
    ns, ss = distinct(counts(ns, "ns"), "ns"), distinct(counts(ss, "ss"), "ss")  # each entry named (ns[0])
    # S^N + N S grows with both, so the largest cell decides the float range before any is built (fuzz 45 C2: the
    # largest S last was refused after 9.4-10.0 CPU-s of the rest of the table)
    i, j = ns.index(max(ns)), ss.index(max(ss))
    _evaluations(ns[i], ss[j], f"ns[{i}] = {ns[i]} and ss[{j}] = {ss[j]}")
    return pd.DataFrame({f"S = {s}": [_evaluations(n, s, f"ns[{i}] = {n} and ss[{j}] = {s}") for i, n in enumerate(ns)]
                         for j, s in enumerate(ss)}, index=pd.Index(list(ns), name="N"))


#: Units of work (``fusion._limits.work``, about 10 ns) of :func:`scaling_study`: a run's exact Chernoff exponents (a
#: fixed part and a part per node), an R's batch (its generators and the batch's own steps), a problem of a batch
#: (fixed and per node) and a sample and node of it. Measured (fuzz 42b C10: 4,000 sizes of 2 runs ran 54.9 CPU-s,
#: 20,000 runs of 2 sizes 27.3, only memory counted; CPU time, minimum of 2, OPENBLAS_NUM_THREADS=1, shared machine):
#: 0.98 / 3.1 ms a run at n = 3 / 10 (400 runs, rs = (2, 3)), 72 / 116 us a problem of a batch (20 against 2 sizes),
#: 1.5 ms a size (398 sizes of 2 runs), 86-96 ns a sample and node (rs = (2000, 4000), 200 runs); the counts are
#: within 0.85x-1.15x of the fuzz's two calls and of these.
_RUN_UNITS, _RUN_NODE_UNITS = 8_000, 30_000
_SIZE_UNITS = 150 * 1000
_BATCH_PROBLEM_UNITS, _BATCH_NODE_UNITS, _BATCH_SAMPLE_UNITS = 5_500, 600, 10
#: Units of a run's exact exponents and of a batch problem at a large n (fuzz 43 C2: the linear weights above, measured
#: at n = 3 and 10, counted n = 1,000 at 0.3 s a run for 9.6 CPU-s, so 30 runs, about 290 CPU-s, were accepted): each
#: grows as n² (dense n x n Newton solves and Gaussian algebra) and is counted as the largest of its linear count,
#: ``_DENSE_SQUARE_UNITS`` n² and ``_DENSE_CUBE_UNITS`` n³ (the solves' n³ beyond the measured n). Measured (CPU time,
#: minimum of 2, OPENBLAS_NUM_THREADS=1, shared machine, 2 runs): the exact exponents of a run 0.052 / 0.118 / 0.656
#: / 2.05 s and a batch problem 0.025 / 0.109 / 0.515 / 2.07 s at n = 100 / 200 / 400 / 800, i.e. 245-520 units an
#: n², 320 for both at n = 800 (0.40 an n³ there).
_DENSE_SQUARE_UNITS, _DENSE_CUBE_UNITS = 330, 0.4


def scaling_study(seed: int, rs: tuple[int, ...] = (250, 500, 1000, 2000, 4000), n: int = 3, runs: int = 100
                  ) -> ScalingStudy:
    r"""The error of step G's exponents in R, against the exact Chernoff exponents (local Gaussians).

    ``runs`` problems of :func:`gaussian_problems` with ``n`` nodes; for every R, steps D-G with the exact minimiser
    of :math:`\hat J` (``optimiser="newton"`` of :func:`fusion.estimates.chernoff.fuse_mixtures_batch`, so that the
    error is the sampling error of :math:`\hat J`, not the optimiser's) on fresh samples (problem k's generator is
    the k-th child of ``SeedSequence([seed, R])``).

    Parameters
    ----------
    seed : int
    rs : tuple of int
        Importance sample sizes R: at least two (the slope in R), distinct, each >= 2; taken in increasing order
        (problem k at size R draws from ``SeedSequence([seed, R])`` whatever the order).
    n : int
    runs : int

    Returns
    -------
    ScalingStudy
        The sample sizes R and, per R (rows) and problem (columns), the L1 error of step G's exponents against the
        exact ones.

    Raises
    ------
    ValueError
        ``rs`` with fewer than two sizes (the study's slope in R needs two) or repeating an R (the study is keyed by
        R); ``runs``, ``n`` or an R below 2; ``n``, ``runs`` and the largest R beyond the memory budget (the Newton
        steps need about 6.5 runs × n² numbers); the runs' exact exponents and every R's batch beyond the work budget
        (``fusion._limits.MAX_WORK``, weighed by their measured costs, about 330 n² units a run and a batch problem
        at a large n: at n = 1,000 one run of two sizes), before any draw, naming ``rs``, ``n`` and ``runs``.
    TypeError
        A count that is not an integer (``rs`` included, entry by entry).
    """
    seed = check_seed(seed)
    runs, n = count(runs, "runs", minimum=2), count(n, "n", minimum=2)
    rs = sequence(rs, "rs")
    loop_work((len(rs),), 0, "rs")  # a batch an R, a loop step at least, by len(rs) before any is read (fuzz 62a C3)
    rs = tuple(sorted(distinct(counts(rs, "rs", minimum=2), "rs")))  # fuzz 24b OR1: the glue's lo/hi follow R
    if len(rs) < 2:
        raise ValueError(f"rs must hold at least two sample sizes (the slope of the error in R needs two), got {rs}")
    _problem_budget(n, runs, max(rs), ("n", "runs", "rs"), square=7 * runs)
    # rule 17 (fuzz 42b C10): every run's exact exponents and every size's batch, weighed as measured above
    # and each run's and problem's dense n x n algebra at a large n (fuzz 43 C2)
    dense = max(_DENSE_SQUARE_UNITS * n * n, int(_DENSE_CUBE_UNITS * n**3))
    work((runs * max(_RUN_UNITS + _RUN_NODE_UNITS * n, dense) + len(rs) * _SIZE_UNITS
          + runs * sum(max(_BATCH_PROBLEM_UNITS + _BATCH_NODE_UNITS * n, dense) + _BATCH_SAMPLE_UNITS * r * n
                       for r in rs),),
         "rs, n and runs")
    w, m, c = gaussian_problems(np.random.default_rng([seed, n]), runs, n)
    exact = np.stack([ch.gaussian_chernoff_weights(m[k, :, 0], c[k, :, 0]).eps for k in range(runs)])
    err = np.empty((len(rs), runs))
    for j, r in enumerate(rs):
        rngs = [np.random.default_rng(s) for s in np.random.SeedSequence([seed, r]).spawn(runs)]
        res = ch.fuse_mixtures_batch(w, m, c, rngs, n_samples=r, optimiser="newton")
        err[j] = np.sum(np.abs(np.stack([x.eps for x in res]) - exact), axis=1)
    return ScalingStudy(rs, err, n, runs)


# ---------------------------------------------------------------------------------------------- the geometry of a frame


@dataclass(frozen=True)
class FrameClouds:
    """One frame of one run of the tracking study: sensors, truth, the nodes' particles and two estimates.

    Attributes
    ----------
    sensors : ndarray, shape (N, 2)
    truth : ndarray, shape (frame + 1, 4)
        The true states up to the frame.
    particles : ndarray, shape (N, n, 4)
        Each node's particles after the frame's update and resampling (equally weighted): its local posterior.
    chernoff, centralised : ndarray, shape (4,)
        The patent's fused estimate (Chernoff-PSO) and the centralised filter's at the frame.
    frame, run : int
        0-based frame and run.
    """

    sensors: FloatArray
    truth: FloatArray
    particles: FloatArray
    chernoff: FloatArray
    centralised: FloatArray
    frame: int
    run: int

    __result_spec__ = ResultSpec({"sensors": array("N", 2), "truth": array("frames", 4), "particles": array("N", "n", 4),
                                  "chernoff": array(4), "centralised": array(4), "frame": integer(0), "run": integer(0)},
                                 relations=(lambda v, cls: _frames_relation(v, cls),))
    __post_init__ = validated_post_init


def _frames_relation(values: dict[str, Any], cls: str) -> None:
    """The truth up to the frame: ``frame + 1`` states."""
    if values["truth"].shape[0] != values["frame"] + 1:
        raise ValueError(f"{cls}.truth must hold frame + 1 = {values['frame'] + 1} states, got {values['truth'].shape[0]}")


@study_defaults("sc", "frame")  # a default the study does not fit, named by the study (fuzz 34b D2)
def frame_clouds(sc: RangeBearingScenario, seed: int, runs: int, run: int = 0, frame: int = 9) -> FrameClouds:
    """Run the study's run ``run`` (of ``runs``, root ``seed``) up to ``frame`` and keep the nodes' particles.

    The run is the study's own: the same seeds and the same code (the batch runner of
    :mod:`fusion.scenarios.range_bearing`, stepped frame by frame), so its estimates are those of
    ``monte_carlo(sc, seed, runs)[run]`` at that frame.

    Parameters
    ----------
    sc : RangeBearingScenario
    seed, runs : int
        The study's root seed and runs.
    run, frame : int
        Which run (0-based) and frame (0-based, below ``sc.frames``).

    Returns
    -------
    FrameClouds
        Sensor positions, the true path up to ``frame``, the nodes' particles and the fused and centralised estimates
        there.

    Raises
    ------
    ValueError
        A bad argument, named; ``sc``'s counts and ``frame`` beyond the memory budget or the work budget
        (``fusion._validation.MAX_WORK``) of one run of ``frame + 1`` frames (set up over ``sc.frames``), before any
        work, as :func:`fusion.scenarios.range_bearing.run_tracking_batch` refuses a study. ``runs`` costs nothing:
        only run ``run``'s seed is made.
    """
    seed = check_seed(seed)
    from fusion.scenarios import range_bearing as rb

    instance_of(sc, RangeBearingScenario, "sc")
    runs = count(runs, "runs")
    run = count(run, "run", minimum=0, maximum=runs - 1)
    frame = count(frame, "frame", minimum=0, maximum=sc.frames - 1)
    # run ``run``'s seed, the child SeedSequence(seed).spawn(runs)[run] is, made alone (fuzz 54b C2a: spawning `runs`
    # children to use one took 34 CPU-s at 6,000,000); the runner of run_tracking_batch with its checks for one run
    # of frame + 1 frames, before any work (54b C2b/C2c: none were applied)
    child = np.random.SeedSequence(seed, spawn_key=(run,))
    batch = rb._run_up_to(sc, child, frame)
    return FrameClouds(sensors=sc.sensor_array.copy(), truth=batch.truth[0, :frame + 1].copy(),
                       particles=batch.particles[0].copy(), chernoff=batch.est["chernoff_pso"][0, frame].copy(),
                       centralised=batch.est["centralised_pf"][0, frame].copy(), frame=frame, run=run)


def clouds_figure(fc: FrameClouds) -> tuple[Figure, str]:
    """The geometry of one frame: sensors and true path (left), the nodes' particle clouds near the target (right).

    Both panels keep the aspect ratio (one metre is as long across as up).

    Parameters
    ----------
    fc : FrameClouds

    Returns
    -------
    fig : matplotlib.figure.Figure
        Two panels: sensors and true path (left); the nodes' particle clouds with the truth and both estimates (right).
    alt : str
        The figure's alt text.
    """
    instance_of(fc, FrameClouds, "fc")
    from fusion.book.style import METHOD_LABELS, color, new_figure

    fig, (ax1, ax2) = new_figure(1, 2, figsize=(7.5, 4.2))
    N = fc.sensors.shape[0]
    for ax in (ax1, ax2):
        ax.plot(fc.truth[:, 0], fc.truth[:, 2], color=color("truth"), lw=1.2, label="true path" if ax is ax1 else None)
    for i in range(N):
        c = color(f"sensor {i + 1}")
        ax1.plot(*fc.sensors[i], marker="^", ms=8, ls="none", color=c, label=f"sensor {i + 1}")
        ax2.plot(fc.particles[i, :, 0], fc.particles[i, :, 2], ls="none", marker=".", ms=1.5, alpha=0.35, color=c)
    cen, chf = "centralised_pf", "chernoff_pso"
    ax2.plot(fc.centralised[0], fc.centralised[2], marker="s", ms=7, ls="none", color=color(cen),
             label=METHOD_LABELS[cen])
    ax2.plot(fc.chernoff[0], fc.chernoff[2], marker="*", ms=12, ls="none", color=color(chf), mec="#000000",
             label=METHOD_LABELS[chf])
    ax2.plot(fc.truth[-1, 0], fc.truth[-1, 2], marker="o", ms=8, ls="none", mfc="none", mew=1.5,
             color=color("truth"), label="true value")
    lo, hi = fc.particles[..., [0, 2]].min(axis=(0, 1)), fc.particles[..., [0, 2]].max(axis=(0, 1))
    half = 0.55 * float(np.max(hi - lo))
    mid = 0.5 * (lo + hi)
    ax2.set_xlim(mid[0] - half, mid[0] + half)
    ax2.set_ylim(mid[1] - half, mid[1] + half)
    for ax, title in ((ax1, "sensors and true path"), (ax2, f"particles of the nodes, frame {fc.frame + 1}")):
        ax.set_aspect("equal", adjustable="box")
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        ax.set_title(title)
    fig.legend(loc="outside lower center", ncols=3)
    spread = [float(np.sqrt(np.trace(np.cov(fc.particles[i][:, [0, 2]].T)))) for i in range(N)]
    alt = (f"Two panels with equal axes. Left: the {N} sensors as triangles and the target's true path up to frame "
           f"{fc.frame + 1}. Right: near the target, each node's particle cloud in its sensor's colour (position "
           "spread " + ", ".join(f"{s:.0f} m" for s in spread) + "), with the true position, the centralised filter's estimate and the patent's fused estimate.")
    return fig, alt


