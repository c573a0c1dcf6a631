"""The CI weight of every step searched by the fruit fly (FOA) and on a grid, over many seeds, as the source does and
as printed.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from fusion._results import NONNEGATIVE, ResultSpec, array, integers, number, validated_post_init
from fusion._validation import read_once
from fusion._validation import seed as check_seed, seed_array
from fusion._validation import LOOP_STEP, distinct, work
from fusion._validation import (FloatArray, allocation, as_array, as_covariance, as_semidefinite, count, instance_of,
                                nonnegative_scalar)
from fusion.estimates.ci import ci_objective, split_ci_objective
from fusion.scenarios.two_sensor.case import _PARAMS
from fusion.filtering.tracks import LocalTrack
from fusion.optimise.result import OptimumResult
from fusion.optimise.scalar import batch_budget, fruit_fly_batch, grid_search

__all__ = ["per_step_weights", "FruitFlySeeds", "fruit_fly_over_seeds", "printed_fruit_fly_over_seeds"]


#: Units (about 10 ns, ``fusion._limits.MAX_WORK``) of one FOA candidate and of one grid point of
#: :func:`per_step_weights` (a CI objective: an information-matrix inverse), measured (budget35).
_CANDIDATE, _GRID_POINT = 45, 35


def _weights_step_units(n_grid: int = 1001, population: int = 30, iterations: int = 200) -> int:
    """Units of one step of :func:`per_step_weights`: its FOA candidates and grid points at their measured cost and a
    heavy loop step; a caller that runs it beside other studies sums ``K`` times this (fuzz 55 C3)."""
    return _CANDIDATE * population * iterations + _GRID_POINT * n_grid + 10 * LOOP_STEP


@_PARAMS("population, iterations")
def per_step_weights(a: LocalTrack, b: LocalTrack, seed: int, n_grid: int = 1001,
                     population: int = 30, iterations: int = 200) -> tuple[FloatArray, FloatArray]:
    r"""CI weight chosen at every step by FOA and by exhaustive search (Wang & Tang 2024, Figs. 5-6).

    Both minimise :math:`\operatorname{tr}P(\omega)` of eq. (1) (:func:`fusion.estimates.ci.ci_objective`)
    on the two tracks' covariances at each step. The FOA runs of all steps fly together
    (:func:`fusion.optimise.scalar.fruit_fly_batch`), with the weights :func:`fusion.optimise.scalar.fruit_fly`
    would return step by step.

    Parameters
    ----------
    a, b : LocalTrack
        The two local tracks of one simulation (covariances ``gains.P`` of shape (K, n, n)): the same runs, steps and
        state dimension. Only the covariances are read, but tracks of different runs (3 and 2) are not a pair of one
        scenario and are refused, as by :func:`fusion.filtering.tracks.fuse_tracks`.
    seed : int
        FOA at step ``k`` uses ``numpy.random.default_rng(seed + k)``.
    n_grid : int
        Points of the exhaustive search on [0, 1].

    Returns
    -------
    w_fruit_fly, w_grid : ndarray, shape (K,)
        Weights (dimensionless, in [0, 1]).

    Raises
    ------
    ValueError
        ``a`` and ``b`` of different shapes (runs, steps, state), naming both; the steps of ``a`` with
        ``population``, ``iterations`` and ``n_grid`` beyond the work budget (``fusion._limits.MAX_WORK``, each
        candidate and grid point at its measured cost), naming them.
    """
    instance_of(a, LocalTrack, "a")
    instance_of(b, LocalTrack, "b")
    seed = check_seed(seed)
    n_grid = count(n_grid, "n_grid", minimum=2)
    population = count(population, "population")
    iterations = count(iterations, "iterations")
    allocation((a.gains.P.shape[0], 2 + 2 * population * iterations), "the steps of a, population and iterations")
    if a.est.shape != b.est.shape or a.gains.P.shape != b.gains.P.shape:  # one simulation's pair (runs included)
        raise ValueError(f"a and b must be tracks of one simulation, of the same shape (runs, steps, state), got "
                         f"a.est {a.est.shape} and b.est {b.est.shape}")
    K = a.gains.P.shape[0]
    seed = check_seed(seed, span=K - 1)   # step k's swarm: seed + k, a seed too (fuzz 55 C1)
    # rule 17, at entry under this function's names (fuzz 24c WN): the swarm's generations and memory, then each
    # candidate and grid point at its measured cost (budget35: 0.43-0.5 us a candidate, 0.34 us a grid point, for 4
    # x 4 covariances; 160,000 iterations, about 60 CPU-s, were accepted), so the edge is about 10 CPU-s
    names = "the steps of a, population, iterations and n_grid"
    batch_budget(K, population, iterations, names)
    work((K, _weights_step_units(n_grid, population, iterations)), names)
    P1s, P2s = np.asarray(a.gains.P, dtype=float), np.asarray(b.gains.P, dtype=float)
    I1s, I2s = np.linalg.inv(P1s), np.linalg.inv(P2s)

    def swarms(w: FloatArray) -> FloatArray:   # ci_objective of every step's swarm, row k on step k's pair
        info = w[..., None, None] * I1s[:, None] + (1.0 - w[..., None, None]) * I2s[:, None]
        return np.trace(np.linalg.inv(info), axis1=-2, axis2=-1)

    found = fruit_fly_batch(swarms, [np.random.default_rng(seed + k) for k in range(K)], population=population,
                            iterations=iterations)
    w_fruit_fly = np.array([r.x for r in found])
    w_grid = np.empty(K)
    for k in range(K):
        P1, P2 = P1s[k], P2s[k]

        def objective(w: ArrayLike, P1: FloatArray = P1, P2: FloatArray = P2) -> FloatArray:
            return ci_objective(w, P1, P2)

        w_grid[k] = grid_search(objective, n_grid, vectorized=True).x
    return w_fruit_fly, w_grid


@dataclass(frozen=True)
class FruitFlySeeds:
    r"""FOA repeated over seeds against one exhaustive search, on one CI objective (:func:`fruit_fly_over_seeds`).

    Attributes
    ----------
    seeds : ndarray of int, shape (S,)
        Seed of each FOA run.
    fruit_fly_x, fruit_fly_fun : ndarray, shape (S,)
        Weight found by each FOA run and its :math:`\operatorname{tr}P` (m², m²/s²).
    grid_x, grid_fun : float
        The exhaustive search's weight and :math:`\operatorname{tr}P`.
    rtol : float
        Relative tolerance under which two objective values count as equal.
    """

    seeds: FloatArray
    fruit_fly_x: FloatArray
    fruit_fly_fun: FloatArray
    grid_x: float
    grid_fun: float
    rtol: float

    __result_spec__ = ResultSpec(
        {"seeds": integers("S"), "fruit_fly_x": array("S", bounds=(0.0, 1.0)),
         "fruit_fly_fun": array("S", bounds=NONNEGATIVE), "grid_x": number(bounds=(0.0, 1.0)),
         "grid_fun": number(positive=True), "rtol": number()})
    __post_init__ = validated_post_init

    @property
    def share_reached(self) -> float:
        """Share of seeds whose FOA objective is at most the grid's (ties within ``rtol`` count as reached)."""
        return float(np.mean(self.fruit_fly_fun <= self.grid_fun + self.rtol * abs(self.grid_fun)))

    @property
    def share_better(self) -> float:
        """Share of seeds whose FOA objective is below the grid's by more than a relative ``rtol``."""
        return float(np.mean(self.fruit_fly_fun < self.grid_fun - self.rtol * abs(self.grid_fun)))

    @property
    def median_excess(self) -> float:
        """Median relative excess (FOA − grid) / grid of the objective (dimensionless)."""
        return float(np.median((self.fruit_fly_fun - self.grid_fun) / abs(self.grid_fun)))


#: Units of one call of the objective of :func:`fruit_fly_over_seeds` (``ci_objective``) and of each of its points,
#: and the same of :func:`printed_fruit_fly_over_seeds` (``split_ci_objective``), measured (budget35, 2 x 2 and 4 x 4
#: covariances): about 70 us a call and 0.3 us a point, 250 us and 1.9 us.
_CI_COSTS, _SPLIT_CI_COSTS = (7 * LOOP_STEP, 30), (25 * LOOP_STEP, 190)


def _seeds_and_budget(seeds: ArrayLike, n_grid: int, grid_minimum: int, population: int, iterations: int, n: int,
                      rtol: float, costs: tuple[int, int]) -> tuple[np.ndarray, int, int, int, float]:
    """Checked seeds, grid size, swarm size and tolerance of a FOA-over-seeds study on an n x n objective whose call
    costs ``costs[0]`` units and each of its points ``costs[1]`` more (measured, plus n**3 a point)."""
    s = seed_array(seeds, "seeds")  # integers of any size (rule 11), never a float array (2**63 + 1 would round)
    n_grid = count(n_grid, "n_grid", minimum=grid_minimum)
    population = count(population, "population")
    iterations = count(iterations, "iterations")
    allocation((len(s), 2 + 2 * population * iterations), "seeds, population and iterations")
    _over_seeds_budget(len(s), n_grid, population, iterations, n, costs, "seeds, population, iterations and n_grid")
    # a repeated seed would count one run twice among the seeds' outcomes; looked for after the budget
    # (fix70a, fuzz 62b's class: each entry hashed before a budget that needs only their number, 2.5 CPU-s a 10**7 list)
    distinct(s.tolist(), "seeds")
    return s, n_grid, population, iterations, nonnegative_scalar(rtol, "rtol")


def _over_seeds_budget(seeds: int, n_grid: int, population: int, iterations: int, n: int, costs: tuple[int, int],
                       names: str) -> int:
    """Rule 17 of a FOA-over-seeds study (``seeds`` swarms on an n x n objective of ``costs``, beside ``n_grid`` grid
    points), refused naming ``names``; its units, which a chapter study that runs it beside others sums (fuzz 59a C1:
    ``weight_pair`` summed ``batch_budget``'s units instead, without the objective's cost)."""
    # rule 17: a generator per seed, an objective call a generation over every seed's swarm, each candidate and grid
    # point at its measured cost (budget35: 320,000 generations, about 85 CPU-s, were accepted)
    call, point = costs[0], costs[1] + n ** 3
    return work((seeds * 10 * LOOP_STEP + iterations * (call + seeds * population * point) + n_grid * point,), names)


def _fly_over_seeds(objective: Callable[[ArrayLike], FloatArray], s: np.ndarray, population: int, iterations: int,
                    grid: OptimumResult, rtol: float) -> FruitFlySeeds:
    """One FOA run per seed on ``objective``, beside the grid search ``grid`` on it."""
    # every seed's swarm flies at once: the result fruit_fly gives seed by seed (fusion.optimise.scalar.fruit_fly_batch)
    runs = fruit_fly_batch(objective, [np.random.default_rng(int(seed)) for seed in s], population=population,
                           iterations=iterations)
    return FruitFlySeeds(seeds=s, fruit_fly_x=np.array([r.x for r in runs]), fruit_fly_fun=np.array([r.fun for r in runs]),
                         grid_x=float(grid.x), grid_fun=float(grid.fun), rtol=float(rtol))


@_PARAMS("seeds", "population, iterations")
def fruit_fly_over_seeds(P1: ArrayLike, P2: ArrayLike, seeds: ArrayLike, n_grid: int = 1001, population: int = 30,
                   iterations: int = 200, rtol: float = 1e-9) -> FruitFlySeeds:
    r"""Minimise :math:`\operatorname{tr}P(\omega)` of CI (Wang & Tang 2024, eq. 1) by FOA once per seed and once on a grid.

    The source's Fig. 5 compares one FOA run with one exhaustive search; FOA is stochastic, so
    the comparison is repeated here over many seeds on the same objective
    (:func:`fusion.estimates.ci.ci_objective`).

    Parameters
    ----------
    P1, P2 : array_like, shape (n, n)
        The two covariances.
    seeds : sequence of int
        One FOA run per seed (at least one, no two equal: a repeated seed would count one run twice).
    n_grid : int
        Points of the exhaustive search on [0, 1].
    rtol : float
        Relative tolerance of a tie between two objective values (the optimisers' own, 1e-9).

    Returns
    -------
    FruitFlySeeds
        The FOA runs and the grid search on :math:`\operatorname{tr}P(\omega)`, ω in [0, 1].

    Raises
    ------
    ValueError
        ``seeds`` empty, repeated or not integers, ``rtol`` negative, ``seeds``, ``population``, ``iterations``
        and ``n_grid`` beyond the work budget (``fusion._validation.MAX_WORK``, each candidate and grid point at
        its measured cost).
    """
    P1, P2 = as_covariance(P1, name="P1"), as_covariance(P2, name="P2")
    if P1.shape != P2.shape:
        raise ValueError(f"P1 and P2 must have the same shape, got {P1.shape} and {P2.shape}")
    s, n_grid, population, iterations, rtol = _seeds_and_budget(seeds, n_grid, 2, population, iterations,
                                                                P1.shape[0], rtol, _CI_COSTS)

    def objective(w: ArrayLike) -> FloatArray:
        return ci_objective(w, P1, P2)

    return _fly_over_seeds(objective, s, population, iterations, grid_search(objective, n_grid, vectorized=True), rtol)


@_PARAMS("seeds", "population, iterations")
def printed_fruit_fly_over_seeds(P1d: ArrayLike, P1i: ArrayLike, P2d: ArrayLike, P2i: ArrayLike, seeds: ArrayLike,
                           n_grid: int = 1001, population: int = 30, iterations: int = 200,
                           rtol: float = 1e-9) -> FruitFlySeeds:
    r"""FOA once per seed and an exhaustive search on the objective of Wang & Tang's (2024) eqs. 11-12 as printed.

    The source chooses its weight by FOA minimising the size of the fused covariance (§2.2). With eqs.
    11-12 as printed (one :math:`\omega` dividing both correlated parts) that objective,
    :func:`fusion.estimates.ci.split_ci_objective` with ``same_omega=True``, decreases with
    :math:`\omega` (both inflated covariances decrease in the Loewner order), so its minimum is
    :math:`\omega = 1`. This runs the source's FOA on it, seed by seed, and the grid
    :math:`k/(n-1)`, :math:`k = 1 \dots n-1` (the end 0 divides by zero).

    Parameters
    ----------
    P1d, P1i, P2d, P2i : array_like, shape (n, n)
        Correlated and independent parts of the two local covariances at one step.
    n_grid : int
        Points of the exhaustive search on [0, 1] (the point 0 left out).
    rtol : float
        Relative tolerance of a tie between two objective values.

    Returns
    -------
    FruitFlySeeds
        The FOA runs and the grid search on the printed objective, ω in (0, 1].

    Raises
    ------
    ValueError
        Bad covariance parts, ``seeds`` empty or not integers, counts not positive, ``rtol`` negative;
        ``seeds``, ``population``, ``iterations`` and ``n_grid`` beyond the work budget (as
        :func:`fruit_fly_over_seeds`).
    """
    P1d, P1i, P2d, P2i = (read_once(P1d, "P1d"), read_once(P1i, "P1i"), read_once(P2d, "P2d"), read_once(P2i, "P2i"))
    first = as_array(P1d, "P1d", ndim=2)
    parts = [as_semidefinite(M, first.shape[0], name=nm) for M, nm in ((P1d, "P1d"), (P1i, "P1i"), (P2d, "P2d"), (P2i, "P2i"))]
    split_ci_objective(1.0, *parts, same_omega=True)   # validates the sums (positive definite)
    s, n_grid, population, iterations, rtol = _seeds_and_budget(seeds, n_grid, 3, population, iterations,
                                                                first.shape[0], rtol, _SPLIT_CI_COSTS)

    def objective(w: ArrayLike) -> FloatArray:
        return split_ci_objective(np.maximum(w, 1e-12), *parts, same_omega=True)   # FOA's 1/D is never 0

    grid = grid_search(objective, n_grid - 1, lo=1.0 / (n_grid - 1), hi=1.0, vectorized=True)
    return _fly_over_seeds(objective, s, population, iterations, grid, rtol)
