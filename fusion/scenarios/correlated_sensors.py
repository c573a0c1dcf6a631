r"""Correlated-noise cases of the lecture notes' §2.7: when ignoring the correlation costs a lot.

The lecture's own experiment (E2.7 of the chapter) couples every sensor to the common environment
with the same strength; then the naive fusion (correlation ignored) is nearly as accurate as GLS.
This module adds scalar cases (:math:`x` read directly by every sensor, :math:`H = \mathbf 1`) with

.. math:: R = \mathrm{diag}(\sigma_i^2) + \sigma_e^2\,cc^\top ,

own noise SDs :math:`\sigma_i`, a common environmental noise of SD :math:`\sigma_e` and coupling
coefficients :math:`c_i`. With unequal couplings GLS can cancel the common error by giving some
sensor a *negative* weight (:math:`\sum_iK_ic_i \approx 0`), which the naive fusion cannot.

References
----------
* Aitken, A. C. (1936). On least squares and linear combination of observations.
  *Proceedings of the Royal Society of Edinburgh*, 55, 42-48.
* An explanation of multi-sensor data fusion algorithms (多传感器数据融合算法讲解).
  Lecture notes, web copy (in Chinese; author and date not stated).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from enum import StrEnum
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from fusion._frozen import constant
from fusion._results import (NONNEGATIVE, ResultSpec, array, dict_of, instance, integer, number, same_keys, tuple_of,
                             validated_post_init)
from fusion._validation import derived_inputs, finite_result
from fusion._validation import record, sequence, within, seed as check_seed
from fusion._validation import allocation, as_array, count, scalar
from fusion._counts import input_allocation
from fusion._validation import read_mapping, read_once, text
from fusion._validation import LOOP_STEP, counts, distinct, work
from fusion.readings import correlated as co
from fusion._shown import shown

__all__ = ["CouplingCase", "SCENARIOS", "CouplingStudy", "EstimatedCovarianceStudy", "covariance", "oriented_covariance",
           "coupling_study", "estimated_covariance_study"]


#: Column headers of the studies' rows, written once: the chapter's tables show them as they are and read them by
#: these names (issue 36: a header retyped where it is read breaks when it is relabelled).
NAIVE_OVER_GLS = "naive / GLS"
ENV_SD = "env SD"
MIN_GLS_WEIGHT = "min GLS weight"
EXACT_MSE_GLS = "exact MSE GLS"
EXACT_MSE_NAIVE = "exact MSE naive"
MC_MSE_GLS = "MC MSE GLS"
MC_MSE_NAIVE = "MC MSE naive"
#: Headers of :func:`estimated_covariance_study`'s rows for n calibration vectors, templates to format with ``n``:
#: GLS with R̂ over GLS with R, naive over GLS with R̂, naive with R̂'s variances over GLS with R̂.
GLS_HAT_OVER_GLS = "GLS(R̂, {n}) / GLS"
NAIVE_OVER_GLS_HAT = "naive / GLS(R̂, {n})"
NAIVE_HAT_OVER_GLS_HAT = "naive(R̂, {n}) / GLS(R̂, {n})"
NAIVE_NEES = "naive NEES"
LDL_VS_GLS = "LDLᵀ vs GLS"
EIGEN_VS_GLS = "eigen vs GLS"
MISSTATED_OVER_GLS = "misstated / GLS"


@dataclass(frozen=True)
class CouplingStudy:
    r"""GLS against the naive fusion over the coupling cases (:func:`coupling_study`).

    Attributes
    ----------
    rows : tuple of mapping
        One per case (its key, N, min GLS weight, exact MSEs, ratio, Monte-Carlo MSEs, naive NEES, route differences).
    sq : mapping of str to tuple of ndarray
        Case key → (GLS, naive) per-run squared errors.
    weights : mapping of str to tuple of ndarray
        Case key → (K, Kn), the GLS and the naive weights.
    env_grid : ndarray
        Environment SDs of the curves.
    curves : mapping of str to ndarray
        Case key → exact naive/GLS ratio along ``env_grid``.
    far : mapping of str to float
        Case key → the ratio at ``env_far``.
    env_far : float
    runs, seed : int
    scenarios : mapping of str to mapping
        The cases run.
    """

    rows: tuple[Mapping[str, Any], ...]
    sq: Mapping[str, tuple[np.ndarray, np.ndarray]]
    weights: Mapping[str, tuple[np.ndarray, np.ndarray]]
    env_grid: np.ndarray
    curves: Mapping[str, np.ndarray]
    far: Mapping[str, float]
    env_far: float
    runs: int
    seed: int
    scenarios: Mapping[str, Mapping[str, Any]]

    __result_spec__ = ResultSpec(
        {"rows": tuple_of(instance(Mapping)),
         "sq": dict_of(tuple_of(array("runs", bounds=NONNEGATIVE), array("runs", bounds=NONNEGATIVE))),
         "weights": dict_of(tuple_of(instance(np.ndarray), instance(np.ndarray))),
         "env_grid": array("E", bounds=NONNEGATIVE),
         "curves": dict_of(array("E", bounds=NONNEGATIVE)), "far": dict_of(number(positive=True)), "env_far": number(),
         "runs": integer(1, dim="runs"), "seed": integer(0), "scenarios": dict_of(instance(Mapping))},
        relations=(same_keys("scenarios", "sq", "weights", "curves", "far"),))
    __post_init__ = validated_post_init


def _ratio_rows(values: Mapping[str, Any], cls: str) -> None:
    """An :class:`EstimatedCovarianceStudy`'s rows: one per case, its ratios of MSEs finite and positive, a ratio per
    calibration size of ``ns``."""
    for i, row in enumerate(values["rows"]):
        for n in values["ns"]:
            if GLS_HAT_OVER_GLS.format(n=n) not in row:
                raise ValueError(f"{cls}.rows[{i}] misses the ratio at n = {n} of {cls}.ns")
        for key, value in row.items():
            if key == "case":
                continue
            v = as_array(value, f"{cls}.rows[{i}][{shown(key)}]", ndim=0)
            if not v > 0:
                raise ValueError(f"{cls}.rows[{i}][{shown(key)}] must be a positive ratio of MSEs, "
                                 f"got {shown(float(v))}")


@dataclass(frozen=True)
class EstimatedCovarianceStudy:
    r"""GLS with an estimated or a misstated noise covariance (:func:`estimated_covariance_study`).

    Attributes
    ----------
    rows : list of dict
        One per case: ``case``, ``"naive / GLS"``, for each n ``"GLS(R̂, n) / GLS"`` (mean over the
        repetitions), ``"naive / GLS(R̂, n)"`` (naive with the true variances) and ``"naive(R̂, n) / GLS(R̂, n)"``
        (naive with the calibration's variances; mean MSEs over the repetitions), and ``"misstated / GLS"``
        (the larger of the two signs).
    ns : tuple of int
        Calibration sample sizes.
    reps, seed : int
    misstate : float
    """

    rows: tuple[Mapping[str, Any], ...]
    ns: tuple[int, ...]
    reps: int
    seed: int
    misstate: float

    __result_spec__ = ResultSpec({"rows": tuple_of(instance(Mapping)), "ns": tuple_of(integer(2)), "reps": integer(1),
                                  "seed": integer(0), "misstate": number(positive=True, bounds=(0.0, 1.0))},
                                 relations=(lambda v, cls: _ratio_rows(v, cls),))
    __post_init__ = validated_post_init

class CouplingCase(StrEnum):
    """Keys of the correlated cases (:data:`SCENARIOS`; labels: :data:`fusion.book.style.METHOD_LABELS`).

    Attributes
    ----------
    EQUAL
        Every sensor coupled to the environment with the same strength, own SDs 1, 2, 3 (as E2.7).
    ONE_OUTSIDE
        Four sensors, the first outside the environment (coupling 0).
    UNEQUAL, UNEQUAL_STRONG
        Couplings 1, 2, 3 with a moderate and a strong environment.
    TWO_SENSORS
        Two sensors with couplings 1 and 2.
    EQUAL_WIDE
        Equal couplings with a wider spread of own SDs than E2.7's (chapter 04's reading; not in :data:`SCENARIOS`).
    """

    EQUAL = "cpl_equal"
    ONE_OUTSIDE = "cpl_one_outside"
    UNEQUAL = "cpl_unequal"
    UNEQUAL_STRONG = "cpl_unequal_strong"
    TWO_SENSORS = "cpl_two_sensors"
    EQUAL_WIDE = "cpl_equal_wide"


#: Named cases: own noise SDs, coupling coefficients, SD of the common environmental noise.
SCENARIOS: dict[CouplingCase, dict[str, tuple[float, ...] | float]] = constant({
    CouplingCase.EQUAL: {"own": (1.0, 2.0, 3.0), "coupling": (1.0, 1.0, 1.0), "env": 1.5},
    CouplingCase.ONE_OUTSIDE: {"own": (1.0, 1.0, 1.0, 1.0), "coupling": (0.0, 1.0, 1.0, 1.0), "env": 2.0},
    CouplingCase.UNEQUAL: {"own": (0.5, 1.0, 1.5), "coupling": (1.0, 2.0, 3.0), "env": 1.0},
    CouplingCase.UNEQUAL_STRONG: {"own": (1.0, 1.0, 1.0), "coupling": (1.0, 2.0, 3.0), "env": 3.0},
    CouplingCase.TWO_SENSORS: {"own": (0.5, 0.5), "coupling": (1.0, 2.0), "env": 3.0},
})


@finite_result("own, coupling and env")
def covariance(own: ArrayLike, coupling: ArrayLike, env: float) -> np.ndarray:
    r"""Noise covariance :math:`R = \mathrm{diag}(\sigma_i^2) + \sigma_e^2cc^\top` of scalar sensors.

    Parameters
    ----------
    own : array_like, shape (N,)
        Own noise standard deviations :math:`\sigma_i > 0` (units of x).
    coupling : array_like, shape (N,)
        Coupling coefficients :math:`c_i` to the common noise (dimensionless, any sign).
    env : float
        Standard deviation :math:`\sigma_e \ge 0` of the common environmental noise.

    Returns
    -------
    ndarray, shape (N, N)
        Symmetric positive definite covariance.

    Raises
    ------
    ValueError
        Non-finite or non-positive own SDs, lengths that differ, negative ``env``; a covariance that
        overflows (``own``, ``coupling`` and ``env`` each in range, their squares not); three N x N arrays beyond the
        memory budget (N above 9,459), before any of them.
    """
    s, c, e = _case_arrays(own, coupling, env)
    # rule 9 (fuzz 40a C8's probe): the N x N diagonal, outer product and sum held at once, before any of them (20,000
    # sensors allocated 3.2 GB for 9.3 CPU-s, 100,000 raised a raw MemoryError)
    allocation((s.size, s.size), "own and coupling (their length N)", arrays=3)
    return np.diag(s**2) + e**2 * np.outer(c, c)


def _case_arrays(own: ArrayLike, coupling: ArrayLike, env: float) -> tuple[np.ndarray, np.ndarray, float]:
    """:func:`covariance`'s arguments checked and converted (each read once), without building the N x N matrix."""
    s = as_array(own, "own", ndim=1)
    if s.size < 1 or np.any(s <= 0):
        raise ValueError(f"own must hold positive standard deviations, got {s}")
    c = as_array(coupling, "coupling", ndim=1)
    if c.shape != s.shape:
        raise ValueError(f"coupling must have the length of own ({s.size}), got {c.size}")
    return s, c, scalar(env, "env", lo=0.0)


def oriented_covariance(angles: Sequence[float] = (0.0, 60.0, 120.0), sd: Sequence[float] = (1.0, 3.0),
                        env: float = 1.5) -> np.ndarray:
    r"""A vector case that does not split into scalar problems: sensors whose own errors point different ways.

    Sensor i reads the two components of x directly (:math:`H_i = I_2`); its own noise has standard
    deviations ``sd`` along axes rotated by ``angles[i]`` degrees, :math:`Q_i\,\mathrm{diag}(sd^2)\,Q_i^\top`; every
    sensor also sees the common environmental noise of E2.7, SD ``env`` on each component:
    :math:`R = \mathrm{blockdiag}(Q_i\Sigma Q_i^\top) + \sigma_e^2\,\mathbf 1\mathbf 1^\top\otimes I_2`. Its blocks are not
    multiples of :math:`I_2`, so the best fusion weights the components differently per sensor.

    Parameters
    ----------
    angles : sequence of float
        Orientation of each sensor's error ellipse, degrees (at least two sensors).
    sd : sequence of float
        The two own noise SDs along the ellipse's axes (> 0).
    env : float
        SD of the common environmental noise (>= 0).

    Returns
    -------
    ndarray, shape (2N, 2N)
        Rows ordered sensor by sensor, components within a sensor.

    Raises
    ------
    ValueError
        Fewer than two angles, non-finite values, SDs not positive or a negative ``env``; so many angles that R is
        beyond the memory budget (rule 9 of ``fusion._validation``).
    """
    a = as_array(angles, "angles", ndim=1)
    if a.size < 2:
        raise ValueError(f"angles must hold at least two sensors, got {a.size}")
    sv = as_array(sd, "sd", shape=(2,))
    if np.any(sv <= 0):
        raise ValueError(f"sd must hold two positive SDs, got {sv}")
    e = scalar(env, "env", lo=0.0)
    N = a.size
    allocation((2 * N, 2 * N), "angles")  # rule 9: R has two rows a sensor
    R = np.zeros((2 * N, 2 * N))  # e**2 kron(1 1', I_2), without the kron's temporaries
    R[0::2, 0::2] = R[1::2, 1::2] = e**2
    for i, ang in enumerate(np.radians(a)):
        c, s_ = np.cos(ang), np.sin(ang)
        Q = np.array([[c, -s_], [s_, c]])
        R[2 * i:2 * i + 2, 2 * i:2 * i + 2] += Q @ np.diag(sv**2) @ Q.T
    return R


@dataclass(frozen=True)
class _ExactRisk:
    """GLS and the naive fusion of one scalar read by every sensor, exactly (:func:`_exact`)."""

    K: np.ndarray
    Kn: np.ndarray
    mse_gls: float
    mse_naive: float
    claimed_naive: float


def _exact(R: np.ndarray) -> _ExactRisk:
    """The GLS and naive weights of a scalar read by every sensor with noise covariance ``R``, their exact MSEs and
    the naive fusion's claimed variance."""
    N = R.shape[0]
    H = np.ones((N, 1))
    K = co.gls_weights(H, R)[0]
    Kn = co.gls_weights(H, np.diag(np.diag(R)))[0]
    return _ExactRisk(K=K, Kn=Kn, mse_gls=float(K @ R @ K), mse_naive=float(Kn @ R @ Kn),
                      claimed_naive=float(1.0 / np.sum(1.0 / np.diag(R))))


@dataclass(frozen=True)
class _Case:
    """A case of a study, read once (:func:`_scenarios`): its key, its checked arrays and the case as given."""

    name: str
    own: np.ndarray
    coupling: np.ndarray
    env: float
    given: Mapping[str, Any]

    @property
    def N(self) -> int:
        """Its number of sensors, the length of its converted ``own``."""
        return self.own.size


def _scenarios(scenarios: Mapping[str, Mapping[str, Any]] | None,
               each: Callable[[_Case], None] | None = None) -> list[_Case]:
    """The cases (default :data:`SCENARIOS`), each checked through the shared rule for nested records, read ONCE.

    The mapping is read once (``fusion._validation.read_mapping``), each case's record once, and its ``own`` and
    ``coupling`` converted once (``read_once``): a caller counts its work from the arrays returned, summed over the
    cases, before building any N x N covariance, and computes with the same arrays (fuzz 42a C3: an ``own`` whose
    ``__array__`` gave 3 entries on its first call and 2,000 after was counted at N = 3 and run at 2,000, 46.5 CPU-s;
    a mapping of 1 case on its first iteration and 60 after was counted as one; C6). ``each(case)``, when given, is
    called on each case as soon as it is read, so that a caller counts the cases' work in turn and refuses a request
    beyond its budget at the first case past it (fuzz 41a C6: 250,000 cases of N = 3), not after reading them all."""
    sc = SCENARIOS if scenarios is None else read_mapping(scenarios, "scenarios")
    if not isinstance(sc, Mapping):
        raise TypeError(f"scenarios must be a mapping of name to case, got {type(sc).__name__}")
    if not sc:
        raise ValueError("scenarios must be a non-empty mapping of name to case")
    cases = []
    for name, case in sc.items():
        path = f"scenarios[{name!r}]"
        if not isinstance(name, str):
            raise TypeError(f"scenarios must be keyed by case names (str), got {shown(name)}")
        case = read_mapping(case, path)
        record(case, path, ("own", "coupling", "env"))
        with within(path):
            given = {k: read_once(v, k) if k in ("own", "coupling") else v for k, v in case.items()}
            own, coupling, env = _case_arrays(given["own"], given["coupling"], given["env"])
        cases.append(_Case(text(name, "scenarios keys"), own, coupling, env, given))  # names as plain texts (rule 19)
        if each is not None:
            each(cases[-1])  # its refusal names the caller's arguments, not the case's path
    return cases


#: The (N, runs) arrays :func:`coupling_study` holds at once for a case of N sensors (the draws, z, and the fusions'
#: temporaries): tracemalloc's peak, 4.67, 4.07 and 4.03 arrays measured at N = 3, 30 and 100 (10**6, 10**5 and 30,000
#: runs).
_COUPLING_ARRAYS = 5


def _coupling_case_units(N: int, runs: int, grid: int) -> int:
    """Units of work (rule 17) of one case of N sensors of :func:`coupling_study` with ``runs`` runs and ``grid``
    environmental SDs (fuzz 40a C8: the sensors were not counted, N = 2,000 of 2 runs ran 65 CPU-s; D3: nor the runs).

    Each SD of the grid and ``env_far`` cost an exact GLS and naive MSE (a covariance, a solve and products): 280 us,
    0.9, 9.3, 46 and 120 ms at N = 3, 100, 300, 600 and 1,000, fitted as ``28,000 + 4 N**2 + 0.016 N**3`` units;
    the case's own exact MSEs, Cholesky factor and four fusions ``30 N**2 + 0.04 N**3`` (55, 217 and 460 ms at
    N = 300, 600, 1,000); each run ``3 N + 0.08 N**2`` (100 ns, 1 and 8.2 us a run at N = 3, 30 and 100). Measured with
    ``time.process_time``, ``OPENBLAS_NUM_THREADS=1``, the least of two calls, the machine shared with other jobs:
    N = 1,000 with 21 SDs ran 3.3 CPU-s (counted 5.1e8 units), N = 1,500 with 3 SDs 3.8 (4.5e8).
    """
    return ((grid + 1) * (28_000 + 4 * N * N + (16 * N**3 + 999) // 1000) + 30 * N * N + (4 * N**3 + 99) // 100
            + runs * (3 * N + (8 * N * N + 99) // 100))


#: Units of a case's fixed step in :func:`estimated_covariance_study` (its covariance, Cholesky factor, exact MSEs and
#: the misstated pair; fuzz 42a C6): 0.76 ms a case of N = 3 (2,000 cases of 2 reps at n = 4), 0.85 ms at N = 30
#: (``time.process_time``, ``OPENBLAS_NUM_THREADS=1``, the least of two calls, machine shared with other jobs), 75
#: ``LOOP_STEP``: 2,000 cases of N = 3 with ``ns=(10, 30), reps=400`` ran 3.7 CPU-s (1.85 ms a case, counted 2.2 ms).
_ESTIMATED_CASE_STEP = 75 * LOOP_STEP
#: Units of a step of :func:`estimated_covariance_study`'s loop over ``ns`` (besides its ``reps x N x N x n``): a
#: batched product, solve and two einsums, 85-100 us a step measured at reps = 2, N = 3 (10 and 40 cases of 200 ns,
#: ``time.process_time``, ``OPENBLAS_NUM_THREADS=1``, the least of two calls, machine shared; fix 72b), weighed
#: 17 ``LOOP_STEP`` (fuzz 64b's class: weighed one ``LOOP_STEP``, the edge at 70 ns a case, 5,167 cases, would have run
#: ~44 CPU-s, 8.5 ms a case; now 761 cases, ~6.5 CPU-s).
_ESTIMATED_N_STEP = 17 * LOOP_STEP


def _estimated_case_units(N: int, reps: int, ns: Sequence[int]) -> int:
    """Units of work (rule 17) of one case of N sensors of :func:`estimated_covariance_study`: its fixed step, a loop
    step per n of ``ns`` and ``reps x N x N x n`` for each."""
    return _ESTIMATED_CASE_STEP + len(ns) * _ESTIMATED_N_STEP + reps * N * N * sum(ns)


def _coupling_case_budget(N: int, runs: int, grid: int, where: str) -> int:
    """Rules 9 and 17 of one case of :func:`coupling_study`: its N x ``runs`` draws within the input budget (z, the
    fusions' input) and the memory budget (``_COUPLING_ARRAYS`` of them), naming ``where``; its units of work
    (``_coupling_case_units``; a chapter study that runs it with others sums them, fuzz 54a C3)."""
    input_allocation((N, runs), where)
    allocation((N, runs), where, arrays=_COUPLING_ARRAYS)
    return _coupling_case_units(N, runs, grid)


@derived_inputs()
def coupling_study(
    scenarios: Mapping[str, Mapping[str, Any]] | None = None,
    runs: int = 2000,
    x: float = 1.0,
    seed: int = 2711,
    env_grid: Sequence[float] = tuple(np.linspace(0.0, 5.0, 51)),
    env_far: float = 100.0,
) -> CouplingStudy:
    r"""GLS, its LDLᵀ and eigen routes, and the naive fusion on each correlated case.

    For each case: the GLS weights and the naive weights (the inverses of the diagonal of R, each
    sensor's own plus its environmental variance, :math:`\sigma_i^2 + \sigma_e^2c_i^2`), the exact
    MSEs :math:`KRK^\top`, Monte-Carlo per-run squared errors of GLS and naive (the same noise
    draws), the largest relative difference of the LDLᵀ and eigen routes from GLS, the naive
    fusion's mean NEES (actual over claimed variance), and the exact naive/GLS MSE ratio along
    ``env_grid`` and at ``env_far`` with the case's own SDs and couplings.

    The ratio grows without bound as :math:`\sigma_e \to \infty` only when every sensor is coupled
    (:math:`c_i \ne 0`), the couplings are not all equal (so that GLS can null the common error) and
    :math:`\sum_i 1/c_i \ne 0` (so that the naive weights, which tend to :math:`\propto 1/c_i^2`, do not);
    with an uncoupled sensor the naive weights concentrate on it and the ratio returns to a finite limit.

    Parameters
    ----------
    scenarios : mapping, optional
        Case key → ``{"own": ..., "coupling": ..., "env": ...}`` (default :data:`SCENARIOS`, keyed by
        :class:`CouplingCase`).
    runs : int
        Monte-Carlo runs per case (>= 2; the chapter uses >= 100).
    x : float
        True value.
    seed : int
        Seed of the noise (one stream, cases in order).
    env_grid : sequence of float
        Environmental SDs of the ratio curves (>= 0).
    env_far : float
        A large environmental SD (> 0) at which the exact ratio is also given (``far``).

    Returns
    -------
    CouplingStudy
        See the class's attributes.

    Raises
    ------
    ValueError
        Bad scenario entries, ``runs`` < 2, negative ``seed`` or grid values; the cases' sensors N, ``runs`` and
        ``env_grid`` beyond the work budget (``(grid + 1) x (28,000 + 4 N**2 + 0.016 N**3) + 30 N**2 + 0.04 N**3 +
        runs x (3 N + 0.08 N**2)`` units a case, measured), or a case's N x ``runs`` draws beyond the input or memory
        budget, before any work.
    """
    runs = count(runs, "runs", minimum=2)
    xv = scalar(x, "x")
    seed = check_seed(seed)
    grid = as_array(env_grid, "env_grid", ndim=1)
    if grid.size == 0 or np.any(grid < 0):
        raise ValueError("env_grid must be a non-empty sequence of SDs >= 0")
    # rules 17 and 9 on every case's sensors N, runs and env_grid, before any work (fuzz 40a C8, D3), case by case
    # before any case's N x N covariance is built (fuzz 41a C6: 16 cases of N = 9,400 were refused after 8.5 CPU-s,
    # 250,000 cases of N = 3 after 9-12), N the length of its converted own (fuzz 41a C5: its len() was read, which an
    # array-like with only __array__ lacks and a lying __len__ understates)
    # (fuzz 42a C3: the mapping and each case read once, counted as converted, and run as counted)
    units = 0

    def count_case(case: _Case) -> None:
        nonlocal units
        units += _coupling_case_budget(case.N, runs, grid.size, f"runs and the sensors of case {shown(case.name)}")
        work((units,), "scenarios (their sensors), runs and env_grid")

    cases = _scenarios(scenarios, count_case)
    far_env = scalar(env_far, "env_far", lo=0.0, lo_open=True)
    rng = np.random.default_rng(seed)
    rows, sq, weights, curves, far = [], {}, {}, {}, {}
    for case in cases:
        name, own, coupling = case.name, case.own, case.coupling
        with within(f"scenarios[{name!r}]"):
            R = covariance(own, coupling, case.env)
        N = R.shape[0]
        H = np.ones((N, 1))
        ex = _exact(R)
        z = xv + np.linalg.cholesky(R) @ rng.normal(size=(N, runs))
        g = co.gls(H, R, z).x[0]
        n_ = co.naive_fusion(H, R, z, block=1).x[0]
        diffs = [float(np.max(np.abs(f(H, R, z).x[0] - g)) / np.max(np.abs(g)))
                 for f in (co.pseudo_measurement_fusion, co.eigen_decorrelation_fusion)]
        sg, sn = (g - xv) ** 2, (n_ - xv) ** 2
        sq[name] = (sg, sn)
        weights[name] = (ex.K, ex.Kn)
        curves[name] = np.array([(lambda e: e.mse_naive / e.mse_gls)(
            _exact(covariance(own, coupling, ev))) for ev in grid])
        ef = _exact(covariance(own, coupling, far_env))
        far[name] = ef.mse_naive / ef.mse_gls
        rows.append({"case": name, "N": N, ENV_SD: float(case.env),
                     MIN_GLS_WEIGHT: float(ex.K.min()), EXACT_MSE_GLS: ex.mse_gls,
                     EXACT_MSE_NAIVE: ex.mse_naive, NAIVE_OVER_GLS: ex.mse_naive / ex.mse_gls,
                     MC_MSE_GLS: float(sg.mean()), MC_MSE_NAIVE: float(sn.mean()),
                     NAIVE_NEES: float(np.mean(sn) / ex.claimed_naive),
                     LDL_VS_GLS: diffs[0], EIGEN_VS_GLS: diffs[1]})
    return CouplingStudy(rows=rows, sq=sq, weights=weights, env_grid=grid, curves=curves, far=far, env_far=far_env,
                         runs=int(runs), seed=int(seed), scenarios={c.name: c.given for c in cases})


def estimated_covariance_study(
    scenarios: Mapping[str, Mapping[str, Any]] | None = None,
    ns: Sequence[int] = (10, 30),
    reps: int = 400,
    seed: int = 2712,
    misstate: float = 0.1,
) -> EstimatedCovarianceStudy:
    r"""GLS with an estimated or a misstated noise covariance, against GLS with the true R and the naive fusion.

    For each case of :data:`SCENARIOS`: R estimated as the sample covariance of n zero-mean calibration
    vectors of the noise (:math:`\hat R = \frac1n\sum_t v_tv_t^\top`, ``reps`` repetitions), the GLS weights
    computed from :math:`\hat R` and their *exact* MSE :math:`\hat KR\hat K^\top` under the true R; and GLS
    computed with the last sensor's coupling misstated by ±``misstate`` (relative). All MSEs are exact given
    the weights (no Monte Carlo over the measurement noise). The naive fusion uses the true variances.

    Parameters
    ----------
    scenarios : mapping, optional
        Case key → ``{"own": ..., "coupling": ..., "env": ...}`` (default :data:`SCENARIOS`, keyed by
        :class:`CouplingCase`).
    ns : sequence of int
        Calibration sample sizes (each greater than the number of sensors, so that :math:`\hat R` is
        positive definite; no two equal, the columns are keyed by size).
    reps : int
        Repetitions of the calibration (>= 2).
    seed : int
        Seed of the calibration draws.
    misstate : float
        Relative error of the misstated coupling (0 < misstate < 1).

    Returns
    -------
    EstimatedCovarianceStudy
        See the class's attributes.

    Raises
    ------
    ValueError
        Bad scenario entries, an n not above the number of sensors or repeated, ``reps`` < 2, a bad
        ``misstate``, or the cases' work beyond the work budget (``fusion._validation.MAX_WORK``; 75,000 units a case,
        17,000 a case and n, and reps x sensors² x sum(ns), summed over the cases), before any case's covariance.
    """
    nv = counts(ns, "ns")  # a non-empty list, tuple or 1-D array of counts (TypeError otherwise)
    reps = count(reps, "reps", minimum=2)
    seed = check_seed(seed)
    f = scalar(misstate, "misstate", lo=0.0, lo_open=True)
    if f >= 1:
        raise ValueError(f"misstate must be below 1, got {f}")
    # rule 17 on every case, summed, as each is read and before any N x N covariance is built (fuzz 42a C6: each case
    # was counted alone, after every case's covariance was built; 20,000 cases of N = 3 ran 38.6 CPU-s, 16 of
    # N = 9,400 were refused after 6.5 CPU-s): a case's fixed step and, per n, a loop step and reps x N x N x n
    units = 0

    def count_case(case: _Case) -> None:
        nonlocal units
        name, N = case.name, case.N
        if min(nv) <= N:
            raise ValueError(f"ns must exceed the number of sensors ({N}) of case {shown(name)}, got {min(nv)}")
        allocation((reps, N, max(nv)), "reps, ns and the sensors of case " + repr(name))
        units += _estimated_case_units(N, reps, nv)
        work((units,), "scenarios (their sensors), ns and reps")

    cases = _scenarios(scenarios, count_case)
    # each row's columns are keyed by n: a repeated size would collapse two of them; looked for after the budgets,
    # which need only the sizes' sum and extremes (fuzz 63b D1: 10**7 sizes were hashed first, 2.8 CPU-s to refuse)
    distinct(nv, "ns")
    rng = np.random.default_rng(seed)
    rows = []
    for case in cases:
        name = case.name
        with within(f"scenarios[{name!r}]"):
            R = covariance(case.own, case.coupling, case.env)
        N = R.shape[0]
        ex = _exact(R)
        row = {"case": name, NAIVE_OVER_GLS: ex.mse_naive / ex.mse_gls}
        C = np.linalg.cholesky(R)
        for n in nv:
            E = C[None] @ rng.normal(size=(reps, N, n))
            Rh = E @ np.swapaxes(E, 1, 2) / n
            w = np.linalg.solve(Rh, np.ones((reps, N, 1)))[..., 0]
            K = w / w.sum(axis=1, keepdims=True)
            mse = np.einsum("ri,ij,rj->r", K, R, K)
            dv = 1.0 / np.diagonal(Rh, axis1=1, axis2=2)                   # naive weights from the same calibration
            Kn = dv / dv.sum(axis=1, keepdims=True)
            mse_n = np.einsum("ri,ij,rj->r", Kn, R, Kn)
            row[GLS_HAT_OVER_GLS.format(n=n)] = float(mse.mean() / ex.mse_gls)
            row[NAIVE_OVER_GLS_HAT.format(n=n)] = float(ex.mse_naive / mse.mean())
            row[NAIVE_HAT_OVER_GLS_HAT.format(n=n)] = float(mse_n.mean() / mse.mean())
        worst = 0.0
        for sign in (-1.0, 1.0):
            c = case.coupling.copy()
            c[-1] *= 1.0 + sign * f
            Km = _exact(covariance(case.own, c, case.env)).K
            worst = max(worst, float(Km @ R @ Km) / ex.mse_gls)
        row[MISSTATED_OVER_GLS] = worst
        rows.append(row)
    return EstimatedCovarianceStudy(rows=rows, ns=tuple(nv), reps=int(reps), seed=int(seed), misstate=f)
