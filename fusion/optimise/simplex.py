r"""Minimisation over the probability simplex :math:`\Delta = \{\varepsilon_i \ge 0, \sum_i \varepsilon_i = 1\}`.

:func:`check_simplex` validates a weight vector, :func:`minimise_on_simplex` is the deterministic
reference (SLSQP) for one problem, and ``_simplex_newton`` minimises a batch of smooth convex problems at
once (projected Newton with an active set), the kernel of the Chernoff weights
(:mod:`fusion.estimates.chernoff`).

References
----------
* Kraft, D. (1988). A software package for sequential quadratic programming. Technical report
  DFVLR-FB 88-28, DLR German Aerospace Center.
* Bertsekas, D. P. (1982). Projected Newton methods for optimization problems with simple
  constraints. *SIAM Journal on Control and Optimization*, 20(2), 221-246.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator

import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import minimize

from fusion._validation import argument_copy, read_once, renormalised, sums_to_one, text, tolerance
from fusion._validation import _numeric, FloatArray, LOOP_STEP, as_callable, count, work
from fusion._objectives import finite_optimum, gradient_values, objective_values
from fusion.optimise.result import OptimumResult

__all__ = [
    "check_simplex",
    "minimise_on_simplex",
]


def check_simplex(eps: ArrayLike, n: int | None = None, name: str = "eps") -> FloatArray:
    r"""Validate exponent weights: finite, non-negative, summing to one (and of length n).

    Checks :math:`\varepsilon \in \Delta = \{\varepsilon_i \ge 0, \sum_i \varepsilon_i = 1\}`.
    Entries within 1e-12 below zero are clipped to zero; the sum must be one within 1e-8, or within 2 n times the
    machine epsilon of a float32 or float16 input (weights normalised in the caller's precision, at most
    ``fusion._validation.SIMPLEX_TOL_CAP`` off one), and such weights are then divided by their sum in float64
    (``fusion._validation.renormalised``: a fusion at float16 exponents summing to 0.99 would scale the fused
    information by 0.99; fuzz 28a D1). Float64 weights are returned as given.

    Parameters
    ----------
    eps : array_like, shape (n,)
        Exponent weights (dimensionless).
    n : int, optional
        Required length; any length of at least one if ``None``.
    name : str
        Argument name used in error messages.

    Returns
    -------
    ndarray, shape (n,)
        The weights as floats, tiny negative round-off clipped to zero (float32 or float16 weights renormalised).

    Raises
    ------
    ValueError
        If the vector has the wrong shape or lies off the simplex.
    """
    name = text(name, "name")  # the label of every message below (fuzz 24a U: never checked)
    if n is not None:
        n = count(n, "n")
    eps = read_once(eps, name)  # converted once: checked, and its dtype read (fuzz 33a C7)
    return simplex_row(_numeric(eps, name), n, name, eps)


def simplex_row(e: FloatArray, n: int | None, name: str, given: object) -> FloatArray:
    """:func:`check_simplex` of the float array ``e`` (a row of the caller's ``given`` weights, converted), judged in
    the precision of ``given`` (``fusion._validation.input_eps``): the rows of a float16 table, or of a list mixing
    ``np.float16`` scalars with Python floats, are float16 weights whatever their converted copy's dtype (fuzz 31a C1).

    Parameters
    ----------
    e : ndarray
        The weights, converted.
    n : int or None
        Required length (checked by the caller), or ``None``.
    name : str
        The caller's argument, for the messages.
    given : object
        The caller's weights as given (their precision).

    Returns
    -------
    ndarray
        As :func:`check_simplex`.
    """
    if e.ndim != 1 or e.size == 0 or (n is not None and e.size != n):
        length = "at least one" if n is None else n  # fuzz 33a D3: never "of length None"
        raise ValueError(f"{name} must be a 1-D vector of length {length}, got shape {e.shape}")
    # float32 or float16 weights: one in their own precision (the one simplex rule, fusion._validation.sums_to_one)
    if not np.all(np.isfinite(e)) or np.any(e < -1e-12) or not sums_to_one(e, given, floor=1e-8):
        raise ValueError(f"{name} must lie on the simplex (non-negative, summing to one), got {e}")
    return renormalised(np.clip(e, 0.0, None), given)


#: SLSQP's iteration limit in :func:`minimise_on_simplex`, and the units of one finite-difference call of its
#: objective (about 25 us measured, budget35).
_SLSQP_ITERATIONS, _FD_CALL = 300, 2500


def _simplex_work(n: int, jac: bool, names: str) -> int:
    """The work budget of one :func:`minimise_on_simplex` of ``n`` weights (with or without ``jac``), naming ``names``:
    its own rule, and that of a caller that runs it in a loop and checks it at its entry (fuzz 42b C9)."""
    return work((_SLSQP_ITERATIONS, n), names, weight=n * n // 20 + (0 if jac else _FD_CALL) + LOOP_STEP)


def minimise_on_simplex(
    f: Callable[[FloatArray], float], n: int, jac: Callable[[FloatArray], FloatArray] | None = None,
    x0: ArrayLike | None = None, ftol: float = 1e-14,
) -> OptimumResult:
    """Minimise ``f`` over the probability simplex with SLSQP (the deterministic reference).

    ``f`` is only ever called on the simplex (trial points are clipped and renormalised), so it
    may validate its argument. ``ftol`` is SLSQP's stopping tolerance on ``f``: near round-off
    (the default) the number of iterations, though not the optimum, may depend on the BLAS
    kernel and thread count; a larger one (1e-10) stops the same way on every machine.

    Parameters
    ----------
    f : callable
        Objective ``f(eps) -> float`` of a vector of shape (n,).
    n : int
        Dimension of the simplex (number of weights), at least one.
    jac : callable, optional
        Gradient ``jac(eps) -> ndarray`` of shape (n,); finite differences if ``None``.
    x0 : array_like, shape (n,), optional
        Starting point on the simplex; the uniform weights if ``None``.
    ftol : float
        SLSQP's stopping tolerance on ``f`` (positive, finite; absolute, in the units of ``f``: one larger than
        the variation of ``f`` over the simplex stops at the starting point).

    Returns
    -------
    OptimumResult
        ``x``: the minimiser, on the simplex (clipped and renormalised against round-off);
        ``fun``: ``f(x)``; ``n_evaluations``: objective evaluations used.

    Raises
    ------
    ValueError
        ``n < 1``, ``x0`` off the simplex, or ``ftol`` not positive and finite; ``f`` returning NaN or not one
        number, ``jac`` returning a gradient not of shape (n,) or not finite; ``n`` beyond the work budget
        (``fusion._limits.MAX_WORK``, counting SLSQP's 300 iterations: about 350 weights without ``jac``, 390 with it).
    TypeError
        ``f`` or ``jac`` not callable, or returning something other than real numbers.
    """
    as_callable(f, "f")
    n = count(n, "n")
    if jac is not None:
        as_callable(jac, "jac")
    # rule 17: SLSQP's dense (n + 1)-row least squares an iteration (about 0.5 ns x n**3 measured, budget35: 0.1 s
    # an iteration at n = 600) and, without jac, n finite-difference calls of f (about 25 us each); without a
    # budget n = 50,000 was accepted (hours, and gigabytes of SLSQP workspace)
    _simplex_work(n, jac is not None, "n")
    ftol = tolerance(ftol, "ftol")  # fuzz 24a U2: inf, NaN or a negative one returned the start as the minimum

    def value(e: FloatArray) -> float:  # issue 35, class 3: NaN, non-numbers and vectors refused, naming f
        v = objective_values(f(argument_copy(e)), (), "f")  # a copy: f writing into its argument cannot alter x
        return float(v)

    if n == 1:
        e = np.ones(1)
        return OptimumResult(x=e, fun=finite_optimum(value(e), "f"), n_evaluations=1)
    start = np.full(n, 1.0 / n) if x0 is None else check_simplex(x0, n, name="x0")

    def on_simplex(e: FloatArray) -> FloatArray:  # finite-difference steps may leave the simplex
        c = np.clip(e, 0.0, None)
        return c / c.sum() if c.sum() > 0 else np.full(n, 1.0 / n)

    def gradient(e: FloatArray) -> FloatArray:  # fuzz 53b C5: checked as f's values are, naming jac
        return gradient_values(jac(argument_copy(e)), n, "jac")  # type: ignore[misc]

    checked_jac = None if jac is None else gradient
    res = minimize(lambda e: value(on_simplex(e)), start, jac=checked_jac, method="SLSQP", bounds=[(0.0, 1.0)] * n,
                   constraints=[{"type": "eq", "fun": lambda e: e.sum() - 1.0, "jac": lambda e: np.ones_like(e)}],
                   options={"ftol": ftol, "maxiter": _SLSQP_ITERATIONS})
    e = np.clip(res.x, 0.0, None)
    e = e / e.sum()
    return OptimumResult(x=e, fun=finite_optimum(value(e), "f"), n_evaluations=int(res.nfev))


_Derivatives = Callable[[np.ndarray, FloatArray], tuple[FloatArray, FloatArray, FloatArray]]


def _active_problems(active: np.ndarray, max_iter: int) -> Iterator[np.ndarray]:
    """The indices of the problems still ``active``, once an iteration, for at most ``max_iter`` iterations.

    The loop of the batched Newton kernels (:func:`_simplex_newton`, ``fusion.estimates.chernoff.mixture._equal_kl``):
    every problem stops on its own (the caller clears its entry of ``active``, read again at each iteration), and
    the loop stops when none is left.
    """
    for _ in range(max_iter):
        a = np.flatnonzero(active)
        if a.size == 0:
            return
        yield a


def _plane_newton_steps(H: FloatArray, g: FloatArray, free: np.ndarray) -> FloatArray:
    r"""Newton steps (b, N) of b problems on the plane :math:`\sum_i d_i = 0`, on their ``free`` coordinates only.

    The KKT system of the Hessians ``H`` (b, N, N) and gradients ``g`` (b, N) restricted to the coordinates
    ``free`` (b, N) (a bound coordinate's step is zero), with a tiny ridge for flat directions (identical
    inputs): the step of :func:`_simplex_newton` and, every coordinate free, of the equal-KL rule
    (``fusion.estimates.chernoff.mixture._equal_kl``).
    """
    b, N = g.shape
    K = np.zeros((b, N + 1, N + 1))
    ridge = 1e-12 * (1.0 + np.max(np.abs(H), axis=(1, 2)))  # flat directions (identical inputs)
    K[:, :N, :N] = (np.where(free[:, :, None] & free[:, None, :], H, 0.0)
                    + np.where(free, ridge[:, None], 1.0)[:, :, None] * np.eye(N))
    K[:, :N, N] = K[:, N, :N] = free
    rhs = np.concatenate([np.where(free, -g, 0.0), np.zeros((b, 1))], axis=1)
    return np.where(free, np.linalg.solve(K, rhs[..., None])[..., 0][:, :N], 0.0)


def _halved_steps(fgh: _Derivatives, a: np.ndarray, eps_a: FloatArray, fa: FloatArray, step: FloatArray,
                  alpha: FloatArray, done: np.ndarray) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """The line search of :func:`_simplex_newton`: the trial points of the problems ``a`` (at ``eps_a``, values
    ``fa``) along ``step`` from lengths ``alpha`` (halved in place), and ``fgh``'s values there.

    Backtracking: a problem's value must not increase (the functions are convex: a short step always works). Only
    the halved steps of the unfinished problems (``~done``) are evaluated again; a finished problem's trial is
    not used.
    """
    N = step.shape[1]
    trial = np.clip(eps_a + alpha[:, None] * step, 0.0, None)
    trial /= trial.sum(axis=1, keepdims=True)
    ft, gt, Ht = np.empty(a.size), np.empty((a.size, N)), np.empty((a.size, N, N))
    pend = np.flatnonzero(~done)  # the steps evaluated: a finished problem's trial is not used
    for _ls in range(30):
        if pend.size == 0:
            break
        if _ls:  # only the halved steps are evaluated again (the others keep their trial and values)
            tr = np.clip(eps_a[pend] + alpha[pend, None] * step[pend], 0.0, None)
            trial[pend] = tr / tr.sum(axis=1, keepdims=True)
        ft[pend], gt[pend], Ht[pend] = fgh(a[pend], trial[pend])  # a problem's values are its own
        pend = pend[ft[pend] > fa[pend] + 1e-13 * (1.0 + np.abs(fa[pend]))]  # worse: round-off is no increase
        alpha[pend] *= 0.5
    return trial, ft, gt, Ht


def _simplex_newton(fgh: _Derivatives, B: int, N: int, max_iter: int = 60, tol: float = 1e-10,
                    search: Callable[..., tuple[FloatArray, FloatArray, FloatArray, FloatArray]] = _halved_steps
                    ) -> FloatArray:
    r"""Minimise B smooth convex functions on the simplex at once: projected Newton with an active set.

    ``fgh(idx, eps)`` returns the values (b,), gradients (b, N) and Hessians (b, N, N) of the problems
    ``idx`` at ``eps`` (b, N). Each iteration solves the Newton system on the free coordinates with the
    constraint :math:`\sum_i d_i = 0` (a KKT system per problem; bound coordinates held at zero; a tiny
    ridge for flat directions), shortens the step to stay in the simplex (a coordinate that reaches
    zero becomes bound), and backtracks until the function does not increase (beyond round-off). A
    bound coordinate is freed when its gradient is below the free coordinates' Lagrange multiplier
    (it would decrease the function) and its Newton step is positive. Every problem stops on its own,
    when its Newton step is below ``tol`` or its Newton decrement below round-off. Starts at the
    uniform weights; returns the minimisers (B, N). Matrix solves per problem and elementwise
    arithmetic only: a problem's result does not depend on the others. ``search`` is the line search
    (:func:`_halved_steps`; the parity reference in ``benchmarks/_reference_kernels.py`` passes its own).
    """
    eps = np.full((B, N), 1.0 / N)
    if N == 1:
        return eps
    free = np.ones((B, N), dtype=bool)
    active = np.ones(B, dtype=bool)
    f, g, H = fgh(np.arange(B), eps)
    for a in _active_problems(active, max_iter):
        fa, ga, Ha, fr = f[a], g[a], H[a], free[a]
        lam = np.sum(np.where(fr, ga, 0.0), axis=1) / np.maximum(fr.sum(axis=1), 1)
        fr = fr | (eps[a] <= 0.0) & (ga < lam[:, None] - 1e-12)  # free a bound coordinate that would lower log Z
        for _fix in range(N):  # a coordinate at zero whose Newton step is negative stays bound
            step = _plane_newton_steps(Ha, ga, fr)
            stuck = fr & (eps[a] <= 0.0) & (step < 0.0)
            if not stuck.any():
                break
            fr = fr & ~stuck
        with np.errstate(divide="ignore", invalid="ignore"):
            room = np.where(step < 0, -eps[a] / step, np.inf)
        alpha = np.minimum(1.0, np.min(room, axis=1))
        decrement = -np.sum(ga * step, axis=1)  # Newton decrement: what the step can still gain
        done = (np.max(np.abs(step), axis=1) <= tol) | (decrement <= 1e-15 * (1.0 + np.abs(fa)))
        trial, ft, gt, Ht = search(fgh, a, eps[a], fa, step, alpha, done)
        keep = ~done
        hit = trial <= 1e-14
        eps[a[keep]] = np.where(hit[keep], 0.0, trial[keep])
        eps[a[keep]] /= eps[a[keep]].sum(axis=1, keepdims=True)
        free[a] = fr & ~(hit & keep[:, None])
        f[a[keep]], g[a[keep]], H[a[keep]] = ft[keep], gt[keep], Ht[keep]
        active[a[done]] = False
    return eps
