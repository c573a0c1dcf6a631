r"""Particle swarm optimisation (Kennedy & Eberhart 1995; Clerc-Kennedy constriction), patent step G.

Maximises a fitness over exponent vectors on the simplex. Positions :math:`u \in [u_{lo}, 1]^N`
are mapped to the simplex by :math:`\varepsilon = u/\sum u`; velocities follow

.. math:: v \leftarrow w v + c_1 r_1 (p_{best} - u) + c_2 r_2 (g_{best} - u),\quad |v| \le v_{max},
          \qquad u \leftarrow \mathrm{clip}(u + v).

The whole swarm is scored in one call (``fitness`` takes an (E, N) array).

References
----------
* Kennedy, J., & Eberhart, R. (1995). Particle swarm optimization. *Proceedings of the IEEE
  International Conference on Neural Networks*, 4, 1942-1948.
* Clerc, M., & Kennedy, J. (2002). The particle swarm: explosion, stability, and convergence in
  a multidimensional complex space. *IEEE Transactions on Evolutionary Computation*, 6(1),
  58-73.
* University of Electronic Science and Technology of China (2021). Multi-sensor distributed
  data fusion method based on the Chernoff fusion criterion. Patent CN107330468B.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Sequence

import numpy as np

from fusion._validation import (as_rngs, FloatArray, as_callable, as_rng, count, instance_of, nonnegative_scalar,
                                one_of, positive_scalar, scalar, work)
from fusion._objectives import finite_optimum, objective_values
from fusion._validation import argument_copy, flag, text, tolerance
from fusion._validation import LOOP_STEP, loop_work
from fusion.optimise._ties import TIE_RTOL
from fusion.optimise.result import OptimumResult, SwarmTrace

__all__ = ["particle_swarm", "particle_swarm_batch", "check_swarm_options", "SwarmOptions"]


def particle_swarm(
    fitness: Callable[[FloatArray], FloatArray],
    dim: int,
    rng: np.random.Generator,
    n_particles: int = 20,
    iterations: int = 50,
    inertia: float = 0.7298,
    c1: float = 1.49618,
    c2: float = 1.49618,
    vmax: float = 0.2,
    lo: float = 1e-6,
    tol: float = 1e-9,
    patience: int = 10,
    stop: str = "stagnation",
    xtol: float = 1e-3,
    trace: bool = False,
) -> OptimumResult:
    """Maximise ``fitness`` over the simplex of dimension ``dim`` (patent steps G1-G6).

    G3/G4 keep the *higher* fitness, so pass :math:`-\\hat J` to minimise :math:`\\hat J`.

    Parameters
    ----------
    fitness : callable
        Maps an (E, N) array of exponent vectors (rows on the simplex) to (E,) fitness values.
    dim : int
        :math:`N`.
    rng : numpy.random.Generator
        Draws initial positions, velocities and the random factors :math:`r_1, r_2`.
    n_particles, iterations : int
        Swarm size and iteration limit (G6).
    inertia, c1, c2 : float
        Clerc-Kennedy constriction values by default.
    vmax : float
        Velocity clamp.
    lo : float
        Lower bound of the positions, in (0, 1) (so that :math:`\\sum u > 0`).
    tol, patience
        G6 convergence with ``stop="stagnation"``: stop when the best fitness improved by less
        than ``tol`` over the last ``patience`` iterations.
    stop : {"stagnation", "positions"}
        G6 convergence rule: fitness stagnation (default), or the patent's wording, convergence
        of the swarm's positions: stop when every particle's exponent vector is within ``xtol``
        (largest coordinate difference) of the global best.
    xtol : float
        Position tolerance of ``stop="positions"``.
    trace : bool
        Also follow the swarm to its iteration limit after ``stop`` has stopped it, on a copy of
        ``rng`` (so ``rng`` is left where the stopped swarm leaves it, and the result is unchanged),
        recording the best fitness, the best point and the swarm's spread after every iteration
        (``trace`` of the result, :class:`~fusion.optimise.result.SwarmTrace`). The moves do not
        depend on the rule until it stops, so the trace gives what every stopping rule returns
        (:meth:`~fusion.optimise.result.SwarmTrace.stop_positions`, ``stop_stagnation``, ``at``).

    Returns
    -------
    OptimumResult
        ``x``: the best exponent vector found (on the simplex); ``fun``: its fitness (the
        maximum found); ``history``: the best fitness after the initialisation and after each
        iteration (non-decreasing); ``n_evaluations``: particles times generations scored
        (until the stop; the traced iterations after it are not counted); ``trace``: with
        ``trace=True``, the swarm to its limit.

    Raises
    ------
    ValueError
        ``dim``, ``n_particles``, ``iterations`` or ``patience`` not positive; ``stop`` unknown;
        ``xtol`` not positive; a fitness returning NaN or the wrong shape, or no finite value.
    TypeError
        A fitness returning something other than real numbers.

    References
    ----------
    * Kennedy, J., & Eberhart, R. (1995). Particle swarm optimization. *Proceedings of the IEEE
      International Conference on Neural Networks*, 4, 1942-1948.
    * Clerc, M., & Kennedy, J. (2002). The particle swarm: explosion, stability, and convergence in
      a multidimensional complex space. *IEEE Transactions on Evolutionary Computation*, 6(1),
      58-73.

    Notes
    -----
    Fitness values within ``1e-9 * max(|value|, 1)`` of each other count as equal (a particle's or the
    swarm's best changes only on a larger improvement; among equals the first particle wins), so
    round-off, which differs between BLAS builds and thread counts, never decides.
    """
    as_callable(fitness, "fitness")
    as_rng(rng)

    def batch_fitness(active: np.ndarray, eps: FloatArray) -> FloatArray:
        return objective_values(fitness(eps[0]), eps.shape[1:2], "fitness", infeasible=-np.inf)[None]

    flag(trace, "trace")
    if not trace:  # one swarm: the same moves and draws as the batch kernel, without its bookkeeping
        return _swarm_one(fitness, dim, rng, n_particles, iterations, inertia, c1, c2, vmax, lo, tol, patience, stop,
                          xtol)
    return _swarm(batch_fitness, dim, [rng], n_particles, iterations, inertia, c1, c2, vmax, lo, tol, patience, stop,
                  xtol, bool(trace))[0]


def particle_swarm_batch(
    fitness: Callable[[np.ndarray, FloatArray], FloatArray],
    dim: int,
    rngs: Sequence[np.random.Generator],
    n_particles: int = 20,
    iterations: int = 50,
    inertia: float = 0.7298,
    c1: float = 1.49618,
    c2: float = 1.49618,
    vmax: float = 0.2,
    lo: float = 1e-6,
    tol: float = 1e-9,
    patience: int = 10,
    stop: str = "stagnation",
    xtol: float = 1e-3,
    trace: bool = False,
) -> list[OptimumResult]:
    """B independent swarms advanced together (vectorised :func:`particle_swarm`).

    Problem ``b`` gives exactly what ``particle_swarm(f_b, dim, rngs[b], ...)`` gives, ``f_b`` its
    fitness: each swarm draws only from its own generator, in the same order, its updates are
    elementwise, and it stops on its own test; stopped swarms are no longer scored.

    Parameters
    ----------
    fitness : callable
        ``fitness(active, eps)``: ``active`` (b,) indices of the problems still running, ``eps``
        (b, E, N) exponent vectors (rows on the simplex); returns (b, E) fitness values.
    dim : int
        :math:`N`.
    rngs : sequence of numpy.random.Generator
        One per problem (non-empty).
        Each draws its own stream: one Generator given twice is refused.
    n_particles, iterations, inertia, c1, c2, vmax, lo, tol, patience, stop, xtol, trace
        As in :func:`particle_swarm` (with ``trace``, every problem is scored to the iteration limit).

    Returns
    -------
    list of OptimumResult, one per problem
        Entry b: the optimum found by the swarm of ``rngs[b]``, as :func:`particle_swarm` returns it.

    Raises
    ------
    ValueError
        As :func:`particle_swarm`; ``rngs`` empty.

    References
    ----------
    * Kennedy, J., & Eberhart, R. (1995). Particle swarm optimization. *Proceedings of the IEEE
      International Conference on Neural Networks*, 4, 1942-1948.
    * Clerc, M., & Kennedy, J. (2002). The particle swarm: explosion, stability, and convergence in
      a multidimensional complex space. *IEEE Transactions on Evolutionary Computation*, 6(1),
      58-73.
    """
    as_callable(fitness, "fitness")
    rngs = as_rngs(rngs, "rngs")  # its list, read once (fuzz 58b C1: a second read could differ)
    flag(trace, "trace")
    return _swarm(fitness, dim, rngs, n_particles, iterations, inertia, c1, c2, vmax, lo, tol, patience, stop,
                  xtol, bool(trace))


def _first_minimum_rows(values: FloatArray) -> np.ndarray:
    """:func:`fusion.optimise._ties.first_minimum` of each row of (B, E)."""
    lowest = np.min(values, axis=1)
    margin = TIE_RTOL * np.maximum(np.abs(lowest), 1.0)
    return np.argmax(values <= (lowest + margin)[:, None], axis=1)


def _improves_rows(candidate: FloatArray, best: FloatArray) -> np.ndarray:
    """:func:`fusion.optimise._ties.improves` elementwise."""
    finite = np.isfinite(best)
    with np.errstate(invalid="ignore"):
        margin = np.where(finite, TIE_RTOL * np.maximum(np.abs(best), 1.0), 0.0)
        return np.where(finite, candidate < best - margin, candidate < best)


def _swarm_one(fitness: Callable[[FloatArray], FloatArray], dim: int, rng: np.random.Generator, n_particles: int,
               iterations: int, inertia: float, c1: float, c2: float, vmax: float, lo: float, tol: float, patience: int,
               stop: str, xtol: float) -> OptimumResult:
    """:func:`_swarm` for one problem without a trace, on (E, N) arrays: bit for bit its result (tested).

    The same draws from ``rng`` in the same order, the same elementwise expressions in the same order,
    and the same tie rules (on scalars: the swarm's best is one number); only the batch kernel's
    gathers and scatters of the active problems, about half of its cost per iteration on a cheap
    fitness, are gone.
    """
    dim, n_particles = count(dim, "dim"), count(n_particles, "n_particles")  # the checks of _swarm
    iterations, patience = count(iterations, "iterations"), count(patience, "patience")
    # rule 17: an iteration is some thirty numpy calls over the particles (~100-300 us: 30 loop steps)
    loop_work((iterations,), n_particles * dim, "n_particles, iterations and dim", step=30 * LOOP_STEP)
    inertia, c1, c2 = nonnegative_scalar(inertia, "inertia"), nonnegative_scalar(c1, "c1"), nonnegative_scalar(c2, "c2")
    vmax, tol = positive_scalar(vmax, "vmax"), nonnegative_scalar(tol, "tol")
    lo = scalar(lo, "lo", 0.0, 1.0, lo_open=True, hi_open=True)
    stop = one_of(stop, ("stagnation", "positions"), "stop")
    xtol = tolerance(xtol, "xtol")
    u = rng.uniform(lo, 1.0, (n_particles, dim))  # G1
    v = rng.uniform(-vmax, vmax, (n_particles, dim))

    # ufuncs and array methods called directly: the functions that np.sum, np.min and np.clip call
    add, maximum, minimum, absolute, argmax = np.add.reduce, np.maximum, np.minimum.reduce, np.absolute, np.argmax

    def score(pos: FloatArray) -> FloatArray:
        return objective_values(fitness(pos / add(pos, axis=1, keepdims=True)), (n_particles,), "fitness",
                                infeasible=-np.inf)

    def first_best(values: FloatArray) -> int:  # _first_minimum_rows of -values, on one row
        neg = -values
        lowest = minimum(neg)
        return int(argmax(neg <= lowest + TIE_RTOL * maximum(absolute(lowest), 1.0)))

    f = score(u)  # G2
    pbest, pbest_f = u.copy(), f.copy()
    g = first_best(f)
    gbest, gbest_f = u[g].copy(), f[g]
    history = [float(gbest_f)]
    evals = n_particles
    positions = stop == "positions"
    for _ in range(iterations):
        r1, r2 = rng.uniform(size=(2, n_particles, dim))
        v = (inertia * v + c1 * r1 * (pbest - u) + c2 * r2 * (gbest - u)).clip(-vmax, vmax)  # G5
        u = (u + v).clip(lo, 1.0)
        f = score(u)  # G2
        evals += n_particles
        better = f > pbest_f + TIE_RTOL * maximum(absolute(pbest_f), 1.0)  # G3: higher fitness wins
        if better.any():
            pbest[better], pbest_f[better] = u[better], f[better]
        g = first_best(pbest_f)  # G4
        cand = pbest_f[g]
        best = -gbest_f
        if math.isfinite(best):  # _improves_rows(-cand, -gbest_f)
            up = -cand < best - TIE_RTOL * maximum(absolute(best), 1.0)
        else:
            up = -cand < best
        if up:
            gbest = pbest[g].copy()
            gbest_f = cand
        history.append(float(gbest_f))
        if positions:
            if _spread(u, gbest) < xtol:
                break  # G6 as the patent words it: the positions have converged
        elif len(history) > patience and history[-1] - history[-1 - patience] < tol:
            break  # G6
    finite_optimum(float(gbest_f), "fitness")
    return OptimumResult(x=gbest / gbest.sum(), fun=float(gbest_f), n_evaluations=int(evals), history=np.array(history))


def _swarm_work(problems: int, n_particles: int, iterations: int, dim: int, names: str) -> int:
    """The units of work of ``problems`` swarms (vectorised) of ``n_particles`` particles in ``dim`` coordinates
    for up to ``iterations`` generations, and a start per swarm; ValueError naming ``names`` (the caller's
    arguments) beyond the budget (rule 17, ``fusion._limits.MAX_WORK``). The one rule of
    :func:`particle_swarm_batch` and of the entries that pass ``swarm_options`` on, which check it first naming
    their own arguments (fuzz 35a C6: the inner names came after the caller's ``gms``)."""
    return loop_work((iterations + problems,), problems * n_particles * dim, names,
                     step=30 * LOOP_STEP)  # as particle_swarm, the problems vectorised, and a start per generator


def _swarm(fitness: Callable[[np.ndarray, FloatArray], FloatArray], dim: int, rngs: list[np.random.Generator],
           n_particles: int, iterations: int, inertia: float, c1: float, c2: float, vmax: float, lo: float, tol: float,
           patience: int, stop: str, xtol: float, trace: bool = False) -> list[OptimumResult]:
    """Kernel of :func:`particle_swarm` and :func:`particle_swarm_batch`.

    With ``trace``, a problem whose rule stops it keeps its result as of that iteration and goes on to
    the iteration limit on a copy of its generator (the caller's generator stays where the stop left it).
    """
    dim, n_particles = count(dim, "dim"), count(n_particles, "n_particles")
    iterations, patience = count(iterations, "iterations"), count(patience, "patience")
    _swarm_work(len(rngs), n_particles, iterations, dim, "rngs, n_particles, iterations and dim")
    inertia, c1, c2 = nonnegative_scalar(inertia, "inertia"), nonnegative_scalar(c1, "c1"), nonnegative_scalar(c2, "c2")
    vmax, tol = positive_scalar(vmax, "vmax"), nonnegative_scalar(tol, "tol")
    lo = scalar(lo, "lo", 0.0, 1.0, lo_open=True, hi_open=True)
    stop = one_of(stop, ("stagnation", "positions"), "stop")
    xtol = tolerance(xtol, "xtol")
    B = len(rngs)
    u = np.empty((B, n_particles, dim))
    v = np.empty((B, n_particles, dim))
    for b, rng in enumerate(rngs):  # G1
        u[b] = rng.uniform(lo, 1.0, (n_particles, dim))
        v[b] = rng.uniform(-vmax, vmax, (n_particles, dim))

    def score(active: np.ndarray, pos: FloatArray) -> FloatArray:
        values = fitness(argument_copy(active), pos / pos.sum(axis=2, keepdims=True))  # a copy: act is read again
        return objective_values(values, pos.shape[:2], "fitness", infeasible=-np.inf)

    act = np.arange(B)
    f = score(act, u)  # G2
    pbest, pbest_f = u.copy(), f.copy()
    g = _first_minimum_rows(-f)
    gbest, gbest_f = u[act, g].copy(), f[act, g].copy()
    history = [[float(x)] for x in gbest_f]
    evals = np.full(B, n_particles)
    rngs = list(rngs)
    final: list[OptimumResult | None] = [None] * B  # with trace: the result at the rule's stop
    if trace:  # per iteration, one row per problem (NaN once a problem has left the loop)
        t_fit, t_best, t_spread = [gbest_f.copy()], [gbest / gbest.sum(axis=1, keepdims=True)], [_spreads(u, gbest)]
    positions = stop == "positions"
    r = np.empty((B, 2, n_particles, dim))
    for _ in range(iterations):
        for j, b in enumerate(act):
            rngs[b].random(out=r[j])  # the numbers of uniform(size=(2, n, dim)): [0, 1) doubles
        r1, r2 = r[:act.size, 0], r[:act.size, 1]
        full = act.size == B  # every problem running (always, with trace): the arrays themselves, no gathers
        ua, va, pb, gb = (u, v, pbest, gbest) if full else (u[act], v[act], pbest[act], gbest[act])
        va = np.clip(inertia * va + c1 * r1 * (pb - ua) + c2 * r2 * (gb[:, None] - ua), -vmax, vmax)  # G5
        ua = np.clip(ua + va, lo, 1.0)
        if full:
            u, v = ua, va
        else:
            u[act], v[act] = ua, va
        f = score(act, ua)  # G2
        evals[act] += n_particles
        pf = pbest_f if full else pbest_f[act]
        better = f > pf + TIE_RTOL * np.maximum(np.abs(pf), 1.0)  # G3: higher fitness wins
        pb[better], pf[better] = ua[better], f[better]
        if not full:
            pbest[act], pbest_f[act] = pb, pf
        g = _first_minimum_rows(-pf)  # G4
        rows = np.arange(act.size)
        cand = pf[rows, g]
        up = _improves_rows(-cand, -gbest_f[act])
        gbest[act[up]] = pb[rows[up], g[up]]
        gbest_f[act[up]] = cand[up]
        spread = _spreads(ua, gbest[act]) if trace or positions else None
        if trace:
            t_fit.append(np.full(B, np.nan))
            t_best.append(np.full((B, dim), np.nan))
            t_spread.append(np.full(B, np.nan))
            t_fit[-1][act] = gbest_f[act]
            t_best[-1][act] = gbest[act] / gbest[act].sum(axis=1, keepdims=True)
            t_spread[-1][act] = spread
        running = np.ones(act.size, dtype=bool)
        for j, b in enumerate(act):
            if final[b] is not None:
                continue  # stopped by its rule: traced only
            h = history[b]
            h.append(float(gbest_f[b]))
            if positions:
                if spread[j] < xtol:  # type: ignore[index]
                    running[j] = False  # G6 as the patent words it: the positions have converged
            elif len(h) > patience and h[-1] - h[-1 - patience] < tol:
                running[j] = False  # G6
            if trace and not running[j]:
                finite_optimum(float(gbest_f[b]), "fitness")  # what the untraced swarm refuses when it stops here
                final[b] = OptimumResult(x=gbest[b] / gbest[b].sum(), fun=float(gbest_f[b]),
                                         n_evaluations=int(evals[b]), history=np.array(h))
                rngs[b] = _copy_generator(rngs[b])  # the trace draws from a copy: the caller's stream stops here
                running[j] = True
        act = act[running]
        if act.size == 0:
            break
    if trace:
        t_fit_a, t_best_a, t_spread_a = np.stack(t_fit, axis=1), np.stack(t_best, axis=1), np.stack(t_spread, axis=1)
    out = []
    for b in range(B):
        finite_optimum(float(gbest_f[b]), "fitness")
        res = final[b] or OptimumResult(x=gbest[b] / gbest[b].sum(), fun=float(gbest_f[b]), n_evaluations=int(evals[b]),
                                        history=np.array(history[b]))
        if trace:
            n_it = int(np.count_nonzero(~np.isnan(t_fit_a[b])))  # a problem leaves the loop only at the end
            res = dataclasses.replace(res, trace=SwarmTrace(fitness=t_fit_a[b, :n_it].copy(), best=t_best_a[b, :n_it].copy(),
                                                            spread=t_spread_a[b, :n_it].copy(), n_particles=n_particles))
        out.append(res)
    return out


def _spreads(u: FloatArray, best: FloatArray) -> FloatArray:
    """:func:`_spread` of B problems at once, ``u`` (B, n, N) and ``best`` (B, N): (B,), the same numbers."""
    return np.max(np.abs(u / u.sum(axis=2, keepdims=True) - (best / best.sum(axis=1, keepdims=True))[:, None]),
                  axis=(1, 2))


def _copy_generator(rng: np.random.Generator) -> np.random.Generator:
    """A generator in the state of ``rng`` that draws the same numbers from here on (``rng`` is left alone).

    The bit generator's state copied into a fresh one of its type: the numbers of ``copy.deepcopy(rng)``, without
    copying its seed sequence (a few microseconds instead of about a millisecond).
    """
    bg = rng.bit_generator
    fresh = type(bg)()
    fresh.state = bg.state
    return np.random.Generator(fresh)


def _spread(u: FloatArray, best: FloatArray) -> float:
    """Largest coordinate difference between the particles' points (n, N) and the best point (N,), on the simplex."""
    return float(np.max(np.abs(u / u.sum(axis=1, keepdims=True) - best / best.sum())))


@dataclasses.dataclass(frozen=True)
class SwarmOptions:
    """Settings of the particle swarm (:func:`particle_swarm_batch`) a caller may pass through ``swarm_options``.

    The defaults are those of :func:`particle_swarm` and :func:`particle_swarm_batch`. Each field is
    checked on construction: a bad value is a ValueError (or TypeError) naming the field.

    Attributes
    ----------
    n_particles : int
        Particles per swarm (default 20).
    iterations : int
        Largest number of generations (default 50).
    inertia : float
        Inertia weight :math:`w` (default 0.7298, Clerc-Kennedy constriction).
    c1, c2 : float
        Cognitive and social coefficients (default 1.49618 each).
    vmax : float
        Largest velocity per coordinate (default 0.2).
    lo : float
        Lower bound :math:`u_{lo}` of the positions, in (0, 1) (default 1e-6).
    tol : float
        Improvement of the best fitness below which a generation counts as stagnant (default 1e-9).
    patience : int
        Stagnant generations before the ``"stagnation"`` rule stops (default 10).
    stop : {"stagnation", "positions"}
        Stopping rule (default ``"stagnation"``); ``"positions"``: every particle within ``xtol`` of the best.
    xtol : float
        Tolerance of the ``"positions"`` rule on the simplex (default 1e-3).
    """

    # the swarm's size and length
    n_particles: int = 20
    iterations: int = 50
    # its moves (step G5; lo also bounds the start, G1)
    inertia: float = 0.7298
    c1: float = 1.49618
    c2: float = 1.49618
    vmax: float = 0.2
    lo: float = 1e-6
    # its stopping rule (step G6)
    tol: float = 1e-9
    patience: int = 10
    stop: str = "stagnation"
    xtol: float = 1e-3

    def __post_init__(self) -> None:
        for k in ("n_particles", "iterations", "patience"):
            object.__setattr__(self, k, count(getattr(self, k), k))
        for k in ("inertia", "c1", "c2", "tol"):
            object.__setattr__(self, k, nonnegative_scalar(getattr(self, k), k))
        object.__setattr__(self, "vmax", positive_scalar(self.vmax, "vmax"))
        object.__setattr__(self, "xtol", tolerance(self.xtol, "xtol"))
        object.__setattr__(self, "lo", scalar(self.lo, "lo", 0.0, 1.0, lo_open=True, hi_open=True))
        object.__setattr__(self, "stop", one_of(self.stop, ("stagnation", "positions"), "stop"))

    def keywords(self) -> dict[str, int | float | str]:
        """The options as keyword arguments of :func:`particle_swarm_batch` (field name -> value): the fields
        :class:`SwarmOptions` declares, whatever fields a subclass adds (fuzz 35a C5)."""
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(SwarmOptions)}


def check_swarm_options(swarm_options: object, name: str = "swarm_options") -> SwarmOptions:
    """Check a ``swarm_options`` argument passed through to :func:`particle_swarm_batch`.

    Parameters
    ----------
    swarm_options : SwarmOptions or None
        The options (``None``: the defaults).
    name : str
        The argument name used in the message.

    Returns
    -------
    SwarmOptions
        ``swarm_options``, or the defaults for ``None``. A subclass instance is read by the fields
        :class:`SwarmOptions` declares, checked again as its constructor checks them, and returned as a plain
        :class:`SwarmOptions` (a field a subclass adds is not the swarm's: it is ignored, fuzz 35a C5).

    Raises
    ------
    TypeError
        Neither a :class:`SwarmOptions` nor ``None`` (a dict of options included); a subclass instance whose
        declared field has a wrong type (named ``swarm_options.<field>``).
    ValueError
        A subclass instance whose declared field fails :class:`SwarmOptions`'s check (named
        ``swarm_options.<field>``).
    """
    name = text(name, "name")  # the label of the message below (fuzz 24a U: never checked)
    if swarm_options is None:
        return SwarmOptions()
    if not isinstance(swarm_options, SwarmOptions):
        raise TypeError(f"{name} must be a SwarmOptions or None, got {type(swarm_options).__name__}")
    if type(swarm_options) is not SwarmOptions:   # a subclass: its declared fields only, checked (fuzz 35a C5)
        try:
            return SwarmOptions(**SwarmOptions.keywords(swarm_options))
        except (TypeError, ValueError) as exc:
            raise type(exc)(f"{name}.{exc}") from None
    return swarm_options
