r"""Scalar optimisers for the covariance-intersection weight (Wang & Tang 2024).

* :func:`fruit_fly`: the fruit fly optimisation algorithm (果蝇优化算法, FOA) of Pan (2012) as
  Wang & Tang (2024) use it (population 30, 200 iterations, step "30 × rand − 10");
* :func:`fruit_fly_batch`: the same search on many independent problems at once (one swarm and
  one generator per problem, every swarm scored in one call per generation), with the result of
  :func:`fruit_fly` on each;
* :func:`grid_search`: exhaustive search (穷举法) on an even grid;
* :func:`bounded_minimum`: :func:`scipy.optimize.minimize_scalar` (bounded Brent), the baseline.

All minimise a function of one variable on [0, 1] and report how many times they evaluated
it, the machine-independent measure of their cost. Objective values within 1e-9 of each other, relative to their
magnitude above 1 and absolute below (``1e-9 * max(|v|, 1)``), count as equal, the first one found winning: round-off, which differs
between BLAS builds and thread counts, never decides (a flat objective gives the same answer on
every machine).

References
----------
* Pan, W.-T. (2012). A new fruit fly optimization algorithm: taking the financial distress
  model as an example. *Knowledge-Based Systems*, 26, 69-74.
* Brent, R. P. (1973). *Algorithms for Minimization without Derivatives*. Prentice-Hall.
* Wang, Z., & Tang, X. (2024). Research on multi-sensor data fusion based on covariance cross
  fusion. *Electronic Measurement Technology*.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
import numpy as np
from scipy.optimize import minimize_scalar

from fusion._validation import allocation, as_array, as_callable, as_rng, as_rngs, count, scalar
from fusion._objectives import finite_optimum, objective_values
from fusion._validation import argument_copy, flag, loop_work, tolerance, value_copy
from fusion._nesting import shape_of
from fusion._shown import shown
from fusion.optimise._ties import first_minimum, first_minimum_rows, improves, improves_rows
from fusion.optimise.result import OptimumResult

__all__ = ["fruit_fly", "fruit_fly_batch", "grid_search", "bounded_minimum"]

#: Units (about 10 ns, ``fusion._limits.MAX_WORK``) of one generation's loop step of the fruit fly swarms on top of
#: its candidates' units, measured (budget35, OPENBLAS_NUM_THREADS=1): a generation of :func:`fruit_fly` costs
#: about 22 us, of :func:`fruit_fly_batch` over two problems about 31 us, so three loop steps, and the edge
#: (about 330,000 generations) is about 10 CPU-s (978,000 generations, about 22 CPU-s, were accepted).
_FLY_STEP = 3 * 1000
#: Units of one candidate's objective call when :func:`fruit_fly` calls ``f`` once a point (``vectorized=False``):
#: about 0.2 us measured, against 4 units (a vectorised element) for a vectorised call.
_FLY_CALL = 25
#: Units of one fly of one generation of :func:`fruit_fly_batch` (its two draws and its arithmetic, with a cheap
#: vectorised objective), measured (fuzz 59a C1; OPENBLAS_NUM_THREADS=1, process_time, minimum of 3 on this machine
#: shared with other jobs, 30 x 200 a problem): n = 100, 500, 1,000, 2,000 problems ran 0.037, 0.14, 0.29, 0.93 CPU-s
#: (48 to 77 ns a fly), population 120 at n = 500 0.61 CPU-s (50 ns); the book's step study (two batches, each
#: candidate recorded) 0.66 CPU-s at 1,000 seeds, 1.8 at 2,000, 4.7 at 8,000 (49 to 76 ns a fly). So about 8 units:
#: the edge of one batch of 30 x 200 is about 20,800 problems (about 1.25e8 flies, 6 to 10 CPU-s), of the step study
#: (two batches) 10,404 seeds, measured 10.9 CPU-s.
_FLY_ELEMENT = 8


def _values(f: Callable[[float], float], xs: np.ndarray, vectorized: bool) -> np.ndarray:
    """Objective at every point of ``xs``: one call if ``vectorized`` (on a copy: ``f`` may change its argument, the
    candidates are read again), else one call per point."""
    if vectorized:
        return objective_values(f(argument_copy(xs)), xs.shape, "f")
    return objective_values([value_copy(f(float(x))) for x in xs], xs.shape, "f")  # a reused buffer (fuzz 30a C5)


def _one_value(v: object) -> float:
    """One objective value as a float (TypeError naming ``f`` for a non-number or complex)."""
    arr = objective_values(v, shape_of(v, "the values returned by f"), "f")
    if arr.size != 1:
        raise ValueError(f"f must return one number per point, got shape {arr.shape}")
    return float(arr.reshape(-1)[0])


def _check(lo: float, hi: float, f: object) -> tuple[float, float]:
    as_callable(f, "f")
    lo, hi = scalar(lo, "lo"), scalar(hi, "hi")
    if hi <= lo:
        raise ValueError(f"need bounds lo < hi, got lo={lo}, hi={hi}")
    return lo, hi


def _step(step: object) -> tuple[float, float]:
    """The random step's ``(a, b)`` of ``a rand + b``: two finite real numbers, named ``step`` (fuzz 24a U1)."""
    a, b = as_array(step, "step", shape=(2,))
    return float(a), float(b)


def fruit_fly(
    f: Callable[[float], float],
    rng: np.random.Generator,
    population: int = 30,
    iterations: int = 200,
    step: tuple[float, float] = (30.0, -10.0),
    lo: float = 0.0,
    hi: float = 1.0,
    vectorized: bool = False,
) -> OptimumResult:
    r"""Fruit fly optimisation (Pan 2012) of a scalar function on [lo, hi].

    The swarm sits at :math:`(X, Y)`. Each fly flies to :math:`(X + r_1, Y + r_2)` with
    :math:`r = \text{step}_0 \cdot \mathrm{rand} + \text{step}_1` (Wang & Tang 2024: 30 rand − 10),
    its distance to the origin :math:`D = \sqrt{X_i^2 + Y_i^2}` gives the smell concentration
    judgement value :math:`S = 1/D`, the candidate; the swarm moves to the best fly found.
    Candidates outside [lo, hi] are clipped to it.

    Parameters
    ----------
    f : callable
        Objective of one float.
    rng : numpy.random.Generator
        Source of the flies' random steps.
    population, iterations : int
        Swarm size and number of generations (30 and 200 in Wang & Tang 2024).
    step : (float, float)
        Random step :math:`a\,\mathrm{rand} + b`: two finite numbers.
    lo, hi : float
        Search interval, ``lo < hi`` (finite).
    vectorized : bool
        ``True`` if ``f`` takes an array of candidates and returns an array of values: the
        whole swarm is then scored in one call per generation (same result, same random
        stream, far less interpreter overhead). The array is a copy: changing it in place does not change the search.

    Notes
    -----
    A fly replaces the swarm's best only if it is better by more than ``1e-9 * max(|best|, 1)``, and
    among flies within that tolerance of each other the first wins: on a flat objective the
    swarm stays where its first generation put it, on every machine.

    The candidate is :math:`1/D` with :math:`D` of the order of the step (tens), so with the
    source's step rule most candidates are small (a few hundredths); a minimum near 1 is reached
    only when the swarm happens to fly close to the origin.

    Returns
    -------
    OptimumResult
        Best candidate seen; ``n_evaluations = population * iterations``.

    Raises
    ------
    ValueError
        Bounds not finite or ``hi <= lo``, ``population`` or ``iterations`` not positive, ``step`` not two
        finite numbers, an objective returning NaN or the wrong shape, or infinite at every candidate;
        ``population`` and ``iterations`` beyond the work budget (``fusion._limits.MAX_WORK``, counted as
        :func:`fruit_fly_batch` counts one problem: a loop step per generation plus its evaluations).
    TypeError
        An objective returning something other than real numbers.

    References
    ----------
    * Pan, W.-T. (2012). A new fruit fly optimization algorithm: taking the financial distress
      model as an example. *Knowledge-Based Systems*, 26, 69-74.
    """
    flag(vectorized, "vectorized")
    lo, hi = _check(lo, hi, f)
    as_rng(rng)
    population, iterations = count(population, "population"), count(iterations, "iterations")
    # rule 17: what fruit_fly_batch counts for one problem, a loop step per generation on top of its evaluations
    # (population=1, iterations=10**7 was accepted as 1e7 evaluations: minutes of Python loop)
    loop_work((1 + iterations,), (4 if vectorized else _FLY_CALL) * population, "population and iterations",
              step=_FLY_STEP)
    a, b = _step(step)
    X, Y = rng.uniform(0.0, 1.0, 2) * a + b
    best_x, best_f = np.nan, np.inf
    evals = 0
    for _ in range(iterations):
        xs = X + rng.uniform(0.0, 1.0, population) * a + b
        ys = Y + rng.uniform(0.0, 1.0, population) * a + b
        with np.errstate(divide="ignore"):
            s = np.clip(1.0 / np.hypot(xs, ys), lo, hi)
        smell = _values(f, s, vectorized)
        evals += population
        k = first_minimum(smell)
        if improves(float(smell[k]), best_f):
            best_f, best_x = float(smell[k]), float(s[k])
            X, Y = xs[k], ys[k]
    finite_optimum(best_f, "f")
    return OptimumResult(x=best_x, fun=best_f, n_evaluations=evals)


def batch_budget(n: int, population: int, iterations: int, names: str) -> int:
    """The memory and work budgets of :func:`fruit_fly_batch` on ``n`` problems (rules 9 and 17), checked under
    ``names``: the batch's own arguments, or those of a caller that sets them (the seeds of a study, its
    generations), so that a caller's refusal names its own arguments before any work (fuzz 24c WN).

    Raises
    ------
    ValueError
        Every draw at once beyond the memory budget (``fusion._counts.MAX_ELEMENTS``) or the loop beyond the
        work budget (``fusion._limits.MAX_WORK``), naming ``names``.

    Returns
    -------
    int
        Its units of work, which a study that runs several batches sums at its entry.
    """
    allocation((n, 2 + 2 * population * iterations), names)  # every draw, at once
    # rule 17: a loop step per generation over every problem's swarm, each fly of each generation at _FLY_ELEMENT
    # units (its two draws, drawn at once per generator, and its arithmetic): linear in n, population and iterations
    # (the former charge, a loop of n + iterations steps of 4 * n * population units, was quadratic in n: fuzz 59a C1)
    return loop_work((iterations,), _FLY_ELEMENT * n * population, names, step=_FLY_STEP)


def fruit_fly_batch(
    f: Callable[[np.ndarray], np.ndarray],
    rngs: Sequence[np.random.Generator],
    population: int = 30,
    iterations: int = 200,
    step: tuple[float, float] = (30.0, -10.0),
    lo: float = 0.0,
    hi: float = 1.0,
) -> list[OptimumResult]:
    r"""Fruit fly optimisation (Pan 2012) of :math:`P` independent scalar problems at once.

    Problem :math:`p` runs the search of :func:`fruit_fly` with its own generator ``rngs[p]``;
    the :math:`P` swarms fly together, and each generation scores every fly of every swarm in one
    call of ``f``. The result of problem :math:`p` is the result of
    ``fruit_fly(f_p, rngs[p], population, iterations, step, lo, hi)``: the same random stream
    (each generator draws its whole stream at once, which for :meth:`numpy.random.Generator.uniform`
    gives the same numbers as drawing it generation by generation), the same arithmetic and the same
    tie rule, so the same weights to the last bit when ``f`` computes each row as ``f_p`` would.

    Parameters
    ----------
    f : callable
        Takes an array of candidates of shape (P, population), row :math:`p` for problem
        :math:`p`, and returns their objective values, same shape. It is given a copy: changing it in place does
        not change the search.
    rngs : sequence of numpy.random.Generator
        One generator per problem (P >= 1), each drawing its own stream (one Generator object given twice
        is refused: the two problems could not each give what the single call gives).
    population, iterations : int
        Swarm size and number of generations (30 and 200 in Wang & Tang 2024).
    step : (float, float)
        Random step :math:`a\,\mathrm{rand} + b`: two finite numbers.
    lo, hi : float
        Search interval, ``lo < hi`` (finite).

    Returns
    -------
    list of OptimumResult
        One per problem; ``n_evaluations = population * iterations`` each.

    Raises
    ------
    ValueError
        Bounds not finite or ``hi <= lo``, ``population`` or ``iterations`` not positive, ``step`` not two
        finite numbers, no generator or one generator's stream given for two problems, an objective returning
        NaN or the wrong shape, or infinite at every candidate of a problem.
    TypeError
        An objective returning something other than real numbers.
        ``rngs`` not a sequence of generators, ``f`` not callable.

    References
    ----------
    * Pan, W.-T. (2012). A new fruit fly optimization algorithm: taking the financial distress
      model as an example. *Knowledge-Based Systems*, 26, 69-74.
    """
    lo, hi = _check(lo, hi, f)
    rngs = as_rngs(rngs, "rngs")
    population, iterations = count(population, "population"), count(iterations, "iterations")
    a, b = _step(step)
    n = len(rngs)
    batch_budget(n, population, iterations, "rngs, population and iterations")
    draws = np.stack([g.uniform(0.0, 1.0, 2 + 2 * population * iterations) for g in rngs])
    X, Y = draws[:, 0] * a + b, draws[:, 1] * a + b
    best_x, best_f = np.full(n, np.nan), np.full(n, np.inf)
    rows = np.arange(n)
    for g in range(iterations):
        start = 2 + 2 * population * g
        xs = X[:, None] + draws[:, start:start + population] * a + b
        ys = Y[:, None] + draws[:, start + population:start + 2 * population] * a + b
        with np.errstate(divide="ignore"):
            s = np.clip(1.0 / np.hypot(xs, ys), lo, hi)
        smell = objective_values(f(argument_copy(s)), s.shape, "f")  # a copy: s is read again (best_x)
        k = first_minimum_rows(smell)
        cand = smell[rows, k]
        better = improves_rows(cand, best_f)
        best_f = np.where(better, cand, best_f)
        best_x = np.where(better, s[rows, k], best_x)
        X = np.where(better, xs[rows, k], X)
        Y = np.where(better, ys[rows, k], Y)
    evals = population * iterations
    for v in best_f:
        finite_optimum(float(v), "f")
    return [OptimumResult(x=float(x), fun=float(v), n_evaluations=evals) for x, v in zip(best_x, best_f)]


def grid_search(
    f: Callable[[float], float], n: int = 1001, lo: float = 0.0, hi: float = 1.0, vectorized: bool = False
) -> OptimumResult:
    r"""Exhaustive search on ``n`` evenly spaced points of [lo, hi].

    The grid is :math:`x_j = lo + j\,(hi - lo)/(n - 1)`, :math:`j = 0..n-1`; the first grid point whose
    value is within ``1e-9 * max(|smallest|, 1)`` of the smallest is returned (on a flat objective: ``lo``; below 1
    the margin is absolute, so an objective that varies by less than 1e-9 ties: give it in units of order one).

    Parameters
    ----------
    f : callable
        Objective of one float.
    n : int
        Number of grid points, at least 2.
    lo, hi : float
        Search interval, ``lo < hi`` (finite).
    vectorized : bool
        ``True``: ``f`` takes the whole grid (an array, a copy: changing it in place does not change the search)
        and returns its values.

    Returns
    -------
    OptimumResult
        Best grid point; ``n_evaluations = n``.

    Raises
    ------
    ValueError
        Bounds not finite or ``hi <= lo``, ``n < 2``, an objective returning NaN or the wrong
        shape, or infinite at every grid point.
    TypeError
        An objective returning something other than real numbers.
    """
    flag(vectorized, "vectorized")
    lo, hi = _check(lo, hi, f)
    n = count(n, "n", minimum=2)
    grid = np.linspace(lo, hi, n)
    values = _values(f, grid, vectorized)
    k = first_minimum(values)
    finite_optimum(float(values[k]), "f")
    return OptimumResult(x=float(grid[k]), fun=float(values[k]), n_evaluations=n)


def bounded_minimum(f: Callable[[float], float], lo: float = 0.0, hi: float = 1.0, xatol: float = 1e-8) -> OptimumResult:
    r"""Bounded Brent minimisation (scipy), plus the two end points.

    :func:`scipy.optimize.minimize_scalar` with ``method="bounded"`` never evaluates the end
    points, so they are evaluated too and kept if better (a minimum on the boundary is common
    for the covariance-intersection weight). An end point replaces Brent's answer only if it is
    lower by more than ``1e-9 * max(|value|, 1)``.

    Parameters
    ----------
    f : callable
        Objective of one float.
    lo, hi : float
        Search interval, ``lo < hi`` (finite).
    xatol : float
        Absolute tolerance on the argument: the search runs on the offset :math:`u = x - s` from the point
        :math:`s` of [lo, hi] nearest 0 and stops, as scipy's does, once the bracket is within about
        :math:`2\,(\sqrt{\epsilon}\,|u| + xatol/3)` of its midpoint (:math:`\epsilon` the float64 machine
        epsilon). :math:`|x - s| \le |x|` for every x of the interval, so the tolerance is never wider than
        scipy's on ``x`` and does not grow with the size of ``lo`` when the interval is far from 0 (fuzz 46b C4: on
        [1e8, 1e8 + 1] scipy's term :math:`\sqrt{\epsilon}\,|x|` = 1.5 stopped it at its first golden-section
        point). An interval holding 0 (the default [0, 1]) is searched as scipy's on ``x``, bit for bit; there
        the tolerance grows with :math:`|x|` only (fuzz 47 C2: an offset from ``lo`` made it grow with the
        distance from ``lo``, 0.7 off on [-1e8, 1]). An ``xatol`` as wide as the interval is met by any of its
        points: the search stops at its first golden-section point (0.382 on [0, 1]; fuzz 53b D5), which is within
        the tolerance asked for; an interval narrower than the default ``xatol`` is searched alike (fuzz 54b D1: a
        refusal of such an ``xatol`` refused valid narrow intervals at the default).

    Returns
    -------
    OptimumResult
        ``n_evaluations`` counts scipy's evaluations plus the two end points.

    Raises
    ------
    ValueError
        Bounds not finite or ``hi <= lo``; an interval so wide against ``xatol`` that scipy's 500 iterations end
        before the tolerance (about ``(hi - lo) / xatol > 1e100``); an objective returning NaN, more than one number,
        or infinite at every point tried.
    TypeError
        An objective returning something other than a real number.

    References
    ----------
    * Brent, R. P. (1973). *Algorithms for Minimization without Derivatives*. Prentice-Hall.
    """
    lo, hi = _check(lo, hi, f)
    xatol = tolerance(xatol, "xatol")
    shift = min(max(0.0, lo), hi)  # the point of [lo, hi] nearest 0: |x - shift| <= |x| on the interval

    def point(u: float) -> float:
        """The argument at offset ``u`` from ``shift``, inside [lo, hi] (``shift + u`` may round past an end)."""
        return min(max(shift + u, lo), hi)

    def checked(x: float) -> float:
        return _one_value(f(x))

    # the offset from shift, not x: scipy's relative term sqrt(eps) |x| is then sqrt(eps) |x - shift| (fuzz 46b C4,
    # fuzz 47 C2); lo and hi are at most 1e150 in magnitude (``fusion._validation.scalar``), so the bounds are finite
    with np.errstate(over="ignore", invalid="ignore"):  # scipy's parabola steps overflow on a 1e150-wide interval
        res = minimize_scalar(lambda u: checked(point(float(u))), bounds=(lo - shift, hi - shift), method="bounded",
                              options={"xatol": xatol})
    if not res.success:  # scipy's 500 iterations ran out: a golden section shrinks the interval 0.618x a step, so
        # an interval wider than about 1e100 x xatol cannot reach it (fuzz 48 C6: [-1e150, 1e150] returned 9.9e7 for 0.3)
        raise ValueError(f"lo and hi: the interval [{shown(lo)}, {shown(hi)}] is too wide for xatol = {shown(xatol)}: "
                         f"the bounded search ran out of its {res.nfev} evaluations before reaching it")
    best_x, best_f = point(float(res.x)), float(res.fun)
    for end in (lo, hi):
        v = checked(end)
        if improves(v, best_f):
            best_x, best_f = end, v
    finite_optimum(best_f, "f")
    return OptimumResult(x=best_x, fun=best_f, n_evaluations=int(res.nfev) + 2)


#: scipy's constants of the bounded Brent search (``scipy.optimize._optimize._minimize_scalar_bounded``).
_SQRT_EPS = float(np.sqrt(2.2e-16))
_GOLDEN = 0.5 * (3.0 - float(np.sqrt(5.0)))


def _bounded_brent_batch(f: Callable[[np.ndarray, np.ndarray], np.ndarray], lo: float, hi: float, n: int,
                         xatol: float = 1e-5, maxiter: int = 500) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    r"""scipy's bounded Brent search (``minimize_scalar(method="bounded")``) on ``n`` problems at once.

    ``f(idx, x)`` gives the objective of the problems ``idx`` (m,) at the points ``x`` (m,): one call per
    iteration for every problem still searching, instead of one call per point of every problem. Each
    problem follows scipy's own sequence of golden-section and parabolic steps, operation for operation
    (elementwise float64 arithmetic, the same as scipy's on scalars), and stops on scipy's test or after
    ``maxiter`` evaluations, so its result is scipy's bit for bit when ``f`` computes each problem's value
    as the scalar objective does (tested against :func:`scipy.optimize.minimize_scalar`).

    Parameters
    ----------
    f : callable
        ``f(idx, x) -> (m,)`` objective values.
    lo, hi : float
        The interval (the same for every problem), ``lo <= hi``.
    n : int
        Number of problems.
    xatol : float
        scipy's absolute tolerance on the argument.
    maxiter : int
        scipy's limit on the evaluations per problem.

    Returns
    -------
    x : ndarray, shape (n,)
        The minimisers (scipy's ``res.x``).
    fun : ndarray, shape (n,)
        Their values (``res.fun``).
    nfev : ndarray of int, shape (n,)
        Evaluations per problem (``res.nfev``).

    References
    ----------
    * Brent, R. P. (1973). *Algorithms for Minimization without Derivatives*. Prentice-Hall.
    """
    a, b = np.full(n, float(lo)), np.full(n, float(hi))
    fulc = a + _GOLDEN * (b - a)
    nfc, xf = fulc.copy(), fulc.copy()
    rat, e = np.zeros(n), np.zeros(n)
    fx = np.asarray(f(np.arange(n), xf.copy()), dtype=float)
    num = np.ones(n, dtype=int)
    ffulc, fnfc = fx.copy(), fx.copy()
    xm = 0.5 * (a + b)
    tol1 = _SQRT_EPS * np.abs(xf) + xatol / 3.0
    tol2 = 2.0 * tol1
    act = np.abs(xf - xm) > (tol2 - 0.5 * (b - a))
    while act.any():
        with np.errstate(divide="ignore", invalid="ignore"):
            para = act & (np.abs(e) > tol1)  # check for a parabolic fit
            r = (xf - nfc) * (fx - ffulc)
            q = (xf - fulc) * (fx - fnfc)
            p = (xf - fulc) * q - (xf - nfc) * r
            q = 2.0 * (q - r)
            p = np.where(q > 0.0, -p, p)
            q = np.abs(q)
            accept = para & (np.abs(p) < np.abs(0.5 * q * e)) & (p > q * (a - xf)) & (p < q * (b - xf))
            rat_p = (p + 0.0) / q
            x_p = xf + rat_p
            si = np.sign(xm - xf) + ((xm - xf) == 0)
            rat_p = np.where(((x_p - a) < tol2) | ((b - x_p) < tol2), tol1 * si, rat_p)
        golden = act & ~accept
        e_g = np.where(xf >= xm, a - xf, b - xf)
        e = np.where(golden, e_g, np.where(accept, rat, e))  # a parabolic step keeps the previous step in e
        rat = np.where(golden, _GOLDEN * e_g, np.where(accept, rat_p, rat))
        si = np.sign(rat) + (rat == 0)
        x = xf + si * np.maximum(np.abs(rat), tol1)
        idx = np.flatnonzero(act)
        fu = np.full(n, np.inf)
        fu[idx] = f(idx, x[idx])
        num[idx] += 1
        le = act & (fu <= fx)
        gt = act & ~(fu <= fx)
        first = gt & ((fu <= fnfc) | (nfc == xf))
        second = gt & ~first & ((fu <= ffulc) | (fulc == xf) | (fulc == nfc))
        a = np.where(le & (x >= xf), xf, np.where(gt & (x < xf), x, a))
        b = np.where(le & ~(x >= xf), xf, np.where(gt & ~(x < xf), x, b))
        fulc, ffulc = (np.where(le | first, nfc, np.where(second, x, fulc)),
                       np.where(le | first, fnfc, np.where(second, fu, ffulc)))
        nfc, fnfc = np.where(le, xf, np.where(first, x, nfc)), np.where(le, fx, np.where(first, fu, fnfc))
        xf, fx = np.where(le, x, xf), np.where(le, fu, fx)
        xm = 0.5 * (a + b)
        tol1 = _SQRT_EPS * np.abs(xf) + xatol / 3.0
        tol2 = 2.0 * tol1
        act = act & (num < maxiter) & (np.abs(xf - xm) > (tol2 - 0.5 * (b - a)))
    return xf, fx, num
