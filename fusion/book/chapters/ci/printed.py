"""Eqs. 1-12 as printed: the printed covariances, the equation checks and split CI's exactness on the case."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from fusion import data
from fusion.data import as_printed
from fusion._docstrings import reads_results
from fusion._results import ResultSpec, dict_of, flag, instance, integer, number, real_key, validated_post_init
from fusion._shown import shown
from fusion._limits import work
from fusion._validation import LOOP_STEP, as_array, as_covariance, count, instance_of, loop_work, scalar
from fusion.book.tables import rounded
from fusion.book.glue import GlueValues
from fusion.estimates.ci import convex_combination, split_covariance_intersection
from fusion.filtering.kalman import cv_model, gain_sequence, split_covariances
from fusion.scenarios.two_sensor import FruitFlySeeds
from fusion.book.chapters.ci.text import readable
from fusion.book.chapters.ci.checks import _entries, _period_key
from fusion.book.chapters.ci.records import SplitExactness

__all__ = ["split_ci_exactness", "ml_vs_product", "printed_covariances", "printed_numbers", "printed_equation_checks",
           "printed_equation_numbers", "PrintedWeightFacts"]


@dataclass(frozen=True)
class PrintedWeightFacts:
    """What eqs. 11-12 as printed do with their own optimisation of ω
    (:func:`~fusion.book.chapters.ci.printed_weight_facts`).

    Attributes
    ----------
    ones, steps : int
        Steps whose trace falls along the whole grid (optimum ω = 1), over all scenarios, and the steps in all.
    fruit_fly : FruitFlySeeds
        FOA (the fruit-fly search, 30 × 200) on the printed objective over its seeds.
    monotone : bool
        ``ones == steps``.
    trace_ratio : float
        tr P at the weight published for plain CI (0.0018) over its minimum at ω = 1, at the searched step.
    trace : dict of float to float
        tr P at a few weights there (m², m²/s²), by weight (a float32 weight read as it prints); the ledger's
        inputs (``LedgerInputs.printed``) need the published weights 0.0018 and 0.0033 and ω = 1 among them.
    """

    ones: int
    steps: int
    fruit_fly: FruitFlySeeds
    monotone: bool
    trace_ratio: float
    trace: Mapping[float, float]

    __result_spec__ = ResultSpec({"ones": integer(0), "steps": integer(1), "fruit_fly": instance(FruitFlySeeds),
                                  "monotone": flag(), "trace_ratio": number(positive=True),
                                  "trace": dict_of(number(positive=True), key=(float, int, np.number), nonempty=False,
                                                   check_key=real_key(0.0, 1.0),  # weights ω (fuzz 32b D2)
                                                   read_key=_period_key)},  # float32 as printed (fuzz 34b B2)
                                 relations=(lambda v, cls: _printed_relation(v, cls),))
    __post_init__ = validated_post_init


def _printed_relation(values: Mapping, cls: str) -> None:
    """``ones`` at most ``steps``, ``monotone`` whether they are equal."""
    if values["ones"] > values["steps"]:
        raise ValueError(f"{cls}.ones must be at most steps = {values['steps']}, got {values['ones']}")
    if values["monotone"] != (values["ones"] == values["steps"]):
        raise ValueError(f"{cls}.monotone must be ones == steps ({values['ones']} of {values['steps']}), "
                         f"got {shown(values['monotone'])}")


#: Units of a run of :func:`ml_vs_product` (its ``convex_combination`` call): twice the 190 us measured (1.91 CPU-s for
#: 10,000 runs of n = 1, 1.20 for n = 4; ``time.process_time``, minimum of 2, ``OPENBLAS_NUM_THREADS=1``, the machine
#: shared and loaded; book audit 76).
_ML_RUN = 38 * LOOP_STEP
#: Units of a run of :func:`ml_vs_product` per ``n**3`` (the run's n x n checks and inverses): twice the 1 ns measured
#: (0.089 and 0.398 CPU-s for 10 and 50 runs of n = 200, 0.62 for 10 of n = 400; book audit 76).
_ML_CUBE = 0.2


def ml_vs_product(x1: ArrayLike, P1: ArrayLike, x2: ArrayLike, P2: ArrayLike) -> float:
    r"""Largest difference between the maximum-likelihood and the multi-Bayesian fusion of two Gaussian estimates.

    Maximum likelihood: :math:`\hat x = \arg\max_x N(\hat x_1; x, P_1)\,N(\hat x_2; x, P_2)`, computed as
    the least-squares solution of the whitened stacked system :math:`L_i^{-1}x = L_i^{-1}\hat x_i`
    (:math:`P_i = L_iL_i^\top`). Multi-Bayesian: the mean of the normalised product of the densities
    :math:`N(x; \hat x_1, P_1)\,N(x; \hat x_2, P_2)`, i.e. the convex combination (Wang & Tang 2024,
    eqs. 3-4; :func:`fusion.estimates.ci.convex_combination`). The two are equal in exact arithmetic.

    Parameters
    ----------
    x1, x2 : array_like, shape (n,) or (runs, n)
        The two estimates (one per run).
    P1, P2 : array_like, shape (n, n)
        Their covariances, symmetric positive definite.

    Returns
    -------
    float
        :math:`\max |\hat x_{ML} - \hat x_{MB}|` over runs and components (unit of the state).

    Raises
    ------
    TypeError
        An estimate or a covariance not numeric.
    ValueError
        Shapes that do not match, estimates not finite, covariances not symmetric positive definite; runs and a size
        n whose fusions, one run at a time, are beyond the work budget (``fusion._limits.MAX_WORK``: about 26,000
        runs of n = 4), before the covariances are checked.
    """
    x1, x2 = np.atleast_2d(as_array(x1, "x1", ndim=(1, 2))), np.atleast_2d(as_array(x2, "x2", ndim=(1, 2)))
    if x1.shape != x2.shape or x1.ndim != 2:
        raise ValueError(f"x1 and x2 must have the same shape (n,) or (runs, n), got {x1.shape} and {x2.shape}")
    n = x1.shape[1]
    # rule 17 before the covariances' checks (book audit 76: no budget, a Python step a run; 10**6 runs of n = 1
    # ran about 190 CPU-s)
    loop_work((x1.shape[0],), math.ceil(_ML_CUBE * n**3), "x1 and x2 (their runs and size n)", step=_ML_RUN)
    P1, P2 = as_covariance(P1, dim=n, name="P1"), as_covariance(P2, dim=n, name="P2")
    W1, W2 = (np.linalg.inv(np.linalg.cholesky(P)) for P in (P1, P2))   # whitening: W P Wᵀ = I
    A = np.vstack([W1, W2])
    ml = np.linalg.lstsq(A, np.vstack([W1 @ x1.T, W2 @ x2.T]), rcond=None)[0].T
    mb = np.array([convex_combination(u, P1, v, P2).x for u, v in zip(x1, x2)])
    return float(np.max(np.abs(ml - mb)))


#: Units of one step of :func:`split_ci_exactness` (a split CI search and a few 4 x 4 products): twice the 1.15 ms
#: measured (book audit 76: 3.45 CPU-s for 3,000 steps, 0.29 for 300, and the old edge, 14,285 steps at the 0.70 ms
#: first measured, ran 20.5 CPU-s; ``time.process_time``, ``OPENBLAS_NUM_THREADS=1``, the machine shared and loaded).
_SPLIT_CI_STEP = 230 * LOOP_STEP


def split_ci_exactness(Q: ArrayLike, R: ArrayLike, T: float, n_steps: int, velocity_sigma: float = 100.0,
                       t_steady: float = 20.0) -> SplitExactness:
    r"""Is split CI exact with two identical sensors? Its reported covariance against the true one, in closed form.

    Two identical local filters (the set-up of :func:`fusion.scenarios.two_sensor.nees_study`: each starts at
    its first measurement and a common initial velocity with prior standard deviation ``velocity_sigma``)
    have the same deterministic gains, so the cross-covariance of their errors follows
    :math:`C_k = A_k(FC_{k-1}F^\top + Q)A_k^\top`, :math:`A_k = I - K_kH`: the recursion of split CI's
    shared part :math:`P_d` (:func:`fusion.filtering.kalman.split_covariances`). The two agree at every step
    when they agree at the start. That holds when the targets' initial velocity is drawn from the filters'
    prior (:math:`C_0 = P_{d,0}`). From the true velocity (the chapter's NEES runs) :math:`C_0 = 0` instead.
    For each start the true covariance :math:`\Sigma_k` of split CI's fused error
    (:math:`W_1\tilde x_1 + W_2\tilde x_2`, with the weights and :math:`\omega` it searches) is set beside
    the covariance :math:`P_k` it reports. The expected NEES :math:`\operatorname{tr}(P_k^{-1}\Sigma_k)` is
    4 at every step exactly when :math:`P_k = \Sigma_k`.

    Parameters
    ----------
    Q : array_like, shape (4, 4)
        Process-noise covariance.
    R : array_like, shape (2, 2)
        Measurement covariance of each (identical) sensor (m², diagonal).
    T : float
        Sampling period (s).
    n_steps : int
        Steps, the initial one included (at most 4,347: a split CI search per step, 1.15 ms measured, weighed twice,
        within the work budget ``fusion._validation.MAX_WORK``; a ValueError names ``n_steps``).
    velocity_sigma : float
        Prior velocity standard deviation (m/s), common to both filters.
    t_steady : float
        Start of the steady-state average (s), as in the chapter's NEES.

    Returns
    -------
    SplitExactness
        A mapping of numbers, which records the case (``Q``, ``R``, ``T``, ``velocity_sigma``, ``t_steady``,
        ``n_steps``) for :func:`~fusion.book.chapters.ci.nees_start_numbers` to check: ``rel_diff_random``: largest :math:`\|P_k - \Sigma_k\|_F / \|\Sigma_k\|_F` over the steps, random start;
        ``nees_random_min``/``nees_random_max``: the expected NEES over the steps, random start;
        ``nees_true_first``, ``nees_true_transient``, ``nees_true_steady``, ``nees_true_steady_min``: expected
        NEES from the true velocity at the first step, averaged before and after ``t_steady``, and its lowest
        value after ``t_steady``; ``omega_dev_steady``: largest :math:`|\omega - 1/2|` after ``t_steady``.

    References
    ----------
    * Julier, S. J., & Uhlmann, J. K. (2001), split covariance intersection (see the bibliography).
    * Bar-Shalom, Y., & Campo, L. (1986), the cross-covariance recursion of two track-to-track filters.
    """
    n_steps = count(n_steps, "n_steps")
    # rule 17: a Python step per step, each a split CI search (a bounded minimisation) and a few 4 x 4 products:
    # 0.70 ms measured (98,000 steps, the edge at ten loop steps, ran 68 CPU-s; time.process_time, shared machine;
    # fuzz 39a E4), then 1.15 ms (book audit 76: the edge at 70 loop steps, 14,285 steps, ran 20.5 CPU-s), weighed as
    # 230 loop steps: 4,347 steps (about 5 CPU-s measured) the most accepted
    loop_work((n_steps,), 0, "n_steps", step=_SPLIT_CI_STEP)
    T = scalar(T, "T", lo=0.0, lo_open=True)
    velocity_sigma = scalar(velocity_sigma, "velocity_sigma", lo=0.0, lo_open=True)
    t_steady = scalar(t_steady, "t_steady", lo=0.0)
    Q = as_covariance(Q, 4, "Q")
    R = as_covariance(R, 2, "R")
    steady = np.arange(n_steps) * T >= t_steady
    if not steady.any() or steady.all():
        raise ValueError(f"t_steady = {t_steady} must leave steps on both sides among the n_steps = {n_steps} steps "
                         f"(T = {T:g} s)")
    model = cv_model(T)
    P0d = np.diag([0.0, velocity_sigma**2, 0.0, velocity_sigma**2])
    P0i = np.diag([R[0, 0], 0.0, R[1, 1], 0.0])
    g = gain_sequence(model.F, model.H, Q, R, P0d + P0i, n_steps)
    carried = split_covariances(g, Q, R, P0d, P0i)             # what the filters carry (split CI's inputs)
    from_truth = split_covariances(g, Q, R, np.zeros((4, 4)), P0i)   # the true moments from the true velocity
    rel, exp_random, exp_true, dev = [], [], [], []
    for k in range(n_steps):
        Pd, Pi = carried.Pd[k], carried.Pi[k]
        r = split_covariance_intersection(np.zeros(4), Pd, Pi, np.zeros(4), Pd, Pi)
        W1 = r.P @ np.linalg.inv(Pd / r.omega + Pi)
        W2 = r.P @ np.linalg.inv(Pd / (1.0 - r.omega) + Pi)
        sig = []
        for C, S in ((Pd, Pd + Pi), (from_truth.Pd[k], from_truth.Pd[k] + from_truth.Pi[k])):  # cross, own
            sig.append(W1 @ S @ W1.T + W2 @ S @ W2.T + W1 @ C @ W2.T + W2 @ C.T @ W1.T)
        rel.append(np.linalg.norm(r.P - sig[0]) / np.linalg.norm(sig[0]))
        exp_random.append(np.trace(np.linalg.solve(r.P, sig[0])))
        exp_true.append(np.trace(np.linalg.solve(r.P, sig[1])))
        dev.append(abs(r.omega - 0.5))
    er, et = np.array(exp_random), np.array(exp_true)
    return SplitExactness(
        {"rel_diff_random": float(max(rel)), "nees_random_min": float(er.min()), "nees_random_max": float(er.max()),
         "nees_true_first": float(et[0]), "nees_true_transient": float(et[~steady].mean()),
         "nees_true_steady": float(et[steady].mean()), "nees_true_steady_min": float(et[steady].min()),
         "omega_dev_steady": float(np.array(dev)[steady].max())}, Q, R, T, velocity_sigma, t_steady, n_steps)


#: Units of a step and grid point of ``printed_weight_facts`` (three 4 x 4 inverses and a trace): twice the 4 us
#: measured (20.8 CPU-s for one scenario of 261 steps on 20,000 points, 1.11 on 2,000; ``time.process_time``,
#: ``OPENBLAS_NUM_THREADS=1``, the machine shared and loaded; book audit 76: the grid had a memory budget only, whose
#: edge, about 64,000 points, ran about 66 CPU-s).
_PRINTED_POINT = 800
#: Units of a pair of scenarios in ``printed_weight_facts``' repeat rule: four ``np.allclose`` of a step's 16
#: entries, each twice the 50 us and 0.16 us a step measured (0.07 CPU-s for 780 pairs of 261 steps; book audit 76:
#: the pairs grow as the square of the scenarios, uncounted).
_PRINTED_PAIR, _PRINTED_PAIR_STEP = 40 * LOOP_STEP, 128


def _printed_facts_budget(shapes: list[tuple[int, ...]], n_grid: int, seeds: int) -> int:
    """Rule 17 of ``printed_weight_facts`` (book audit 76), before the repeat rule and any seed is read: each
    scenario's steps on the grid, the repeat rule's pairs and ``printed_fruit_fly_over_seeds``' own budget (its
    printed 30 x 200 per seed beside its 1001-point grid), summed (``fusion.book._study_budget.studies_first``),
    refused naming ``scenarios, seeds and n_grid``; ``shapes`` are the scenarios' ``Pd`` shapes (steps, n, n)."""
    from fusion.book._study_budget import studies_first
    from fusion.scenarios.two_sensor.weights import _SPLIT_CI_COSTS, _over_seeds_budget

    names = "scenarios, seeds and n_grid"
    grid = sum(K * (n_grid * _PRINTED_POINT + LOOP_STEP) for K, *_ in shapes)
    pairs = sum(j * (_PRINTED_PAIR + _PRINTED_PAIR_STEP * K) for j, (K, *_) in enumerate(shapes))
    return studies_first([lambda: work((grid + pairs,), names),
                          lambda: _over_seeds_budget(seeds, 1001, 30, 200, shapes[0][1], _SPLIT_CI_COSTS, names)],
                         names)


def printed_covariances() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    r"""The source's noise covariances as printed (§3.2): :math:`Q = \Delta_0^2 I_4`, :math:`R_j = \Delta_j^2 I_2`.

    The process noise is printed on the full state (position and velocity of both axes, one variance per
    step), the measurement noise on the two positions (``fusion.data.WANG2024_SCENARIO``).

    Returns
    -------
    Q : ndarray, shape (4, 4)
        Process-noise covariance per step (m², m²/s²).
    R1, R2 : ndarray, shape (2, 2)
        Measurement covariances of sensors 1 and 2 (m²).
    """
    sc = data.WANG2024_SCENARIO
    return (np.diag([sc["delta0"] ** 2] * 4), np.diag([sc["delta1"] ** 2] * 2), np.diag([sc["delta2"] ** 2] * 2))


@reads_results("printed")
def printed_numbers(printed: PrintedWeightFacts) -> GlueValues:
    """The numbers the prose quotes on eqs. 11-12 with their own optimised ω (glue keys ``ci_printed_*``).

    Parameters
    ----------
    printed : PrintedWeightFacts
        :func:`~fusion.book.chapters.ci.printed_weight_facts`.

    Returns
    -------
    dict
        ``ci_printed_ones`` and ``ci_printed_steps`` (steps where tr P falls along the grid, of all),
        ``ci_printed_foa_min`` (FOA's smallest ω over its seeds, 4 decimals), ``ci_printed_foa_seeds``,
        ``ci_printed_trace_ratio`` (tr P at the published weight over its minimum) and ``ci_printed_monotone``.
    """
    instance_of(printed, PrintedWeightFacts, "printed")
    return {"ci_printed_ones": printed.ones, "ci_printed_steps": printed.steps,
            "ci_printed_foa_min": f"{float(np.min(printed.fruit_fly.fruit_fly_x)):.4f}",
            "ci_printed_foa_seeds": len(printed.fruit_fly.seeds), "ci_printed_trace_ratio": f"{printed.trace_ratio:.0f}"}


def printed_equation_checks(P1: ArrayLike, P2: ArrayLike, Pi: ArrayLike, F: ArrayLike,
                            x: ArrayLike = (1000.0, 20.0, 5000.0, 40.0)) -> dict[str, float]:
    r"""Eqs. 2 and 6 as printed, checked: eq. 2 on two identical estimates, eq. 6 against :math:`F P_i F^\top`.

    Parameters
    ----------
    P1, P2 : array_like, shape (4, 4)
        Two covariances that eq. 2 weighs (:func:`fusion.data.as_printed.wang2024_eqs_1_2`, ω = 0.5).
    Pi : array_like, shape (4, 4)
        An independent part of a local covariance, which eq. 6 predicts.
    F : array_like, shape (4, 4)
        State transition.
    x : array_like, shape (4,)
        The estimate given to both inputs of eq. 2.

    Returns
    -------
    dict
        ``eq2_error``: largest change of ``x`` by eq. 2 as printed (0 for a correct fusion of equal estimates);
        ``eq6_asym``: largest asymmetry of eq. 6 as printed, :math:`F P_i + F^\top`; ``eq6_relerr``: its
        Frobenius distance to :math:`F P_i F^\top` relative to the latter (no Q: the process noise is common,
        it belongs to the shared part).

    Raises
    ------
    TypeError
        An argument is not numeric.
    ValueError
        ``Pi`` and ``F`` are not square matrices of one shape or hold NaN or infinite entries; ``x`` is not a finite
        vector of their size; ``F`` and ``Pi`` give :math:`F P_i F^\top = 0` (``F = 0``, say), against which the
        relative error of eq. 6 is undefined; ``P1`` or ``P2`` is refused by eq. 2 (named).
    """
    Pi, F = as_array(Pi, "Pi", ndim=2, subnormal=True), as_array(F, "F", ndim=2, subnormal=True)
    if Pi.shape != F.shape or F.shape[0] != F.shape[1]:
        raise ValueError(f"Pi and F must be square matrices of one shape, got {Pi.shape} and {F.shape}")
    x = as_array(x, "x", shape=(F.shape[0],))
    eq2_error = float(np.max(np.abs(as_printed.wang2024_eqs_1_2(x, P1, x, P2, omega=0.5).x - x)))
    printed6 = F @ Pi + F.T
    correct6 = F @ Pi @ F.T
    if not np.any(correct6):
        raise ValueError("F and Pi give F Pi F^T = 0, against which the relative error of eq. 6 is undefined")
    return {"eq2_error": eq2_error, "eq6_asym": float(np.max(np.abs(printed6 - printed6.T))),
            "eq6_relerr": np.linalg.norm(printed6 - correct6) / np.linalg.norm(correct6)}


def printed_equation_numbers(checks: Mapping[str, float]) -> GlueValues:
    """The numbers the prose quotes from :func:`printed_equation_checks` (glue keys ``ci_eq2_error``, ``ci_eq6_*``).

    Parameters
    ----------
    checks : mapping
        :func:`printed_equation_checks`.

    Returns
    -------
    dict
        ``ci_eq2_error`` (readable, 3 digits), ``ci_eq6_asym`` (1 decimal), ``ci_eq6_relerr`` (2 decimals).

    Raises
    ------
    TypeError
        ``checks`` is not a mapping, or a value read here not a number.
    ValueError
        ``checks`` lacks a key read here, or a value is not finite.
    """
    checks = _entries(checks, "checks", ("eq2_error", "eq6_asym", "eq6_relerr"), "printed_equation_checks",
                      nonnegative=True)
    return {"ci_eq2_error": readable(checks["eq2_error"], 3), "ci_eq6_asym": rounded(checks["eq6_asym"], 1),
            "ci_eq6_relerr": rounded(checks["eq6_relerr"], 2)}
