r"""The experiments of chapter 04 (lecture notes, §2.5 and §2.7).

Scalar ridge against least squares, convergence, centralised vs distributed (:func:`ridge_study`); LDLᵀ
pseudo-measurements against GLS and the naive fusion, with operation counts (:func:`correlated_study`). The data-driven
ridge, wavelet and correlated-noise studies are in :mod:`fusion.scenarios.ridge_sensors`,
:mod:`fusion.scenarios.wavelet_sensors` and :mod:`fusion.scenarios.correlated_sensors`.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from fusion._results import (NONNEGATIVE, ResultSpec, array, dict_of, instance, integer, number, same_keys, tuple_of,
                             real_key, validated_post_init)
from fusion._validation import read_once
from fusion._validation import derived_inputs
from fusion._validation import FloatArray, as_array, count, scalar, shown, std_scalar
from fusion._validation import allocation
from fusion._counts import input_allocation
from fusion._limits import DENSE_CUBE, dense_work
from fusion._validation import LOOP_STEP, distinct, distinct_printed, general, loop_work, work
from fusion._validation import MAX_MAGNITUDE, MIN_MAGNITUDE
from fusion.readings import biased as rg
from fusion.readings import correlated as co
from fusion.scenarios._lecture_checks import _ints, _seed, _sigmas, _values
from fusion._shown import shown

__all__ = [
    "RidgeStudy",
    "ridge_study",
    "CorrelatedStudy",
    "correlated_study",
]

#: Key of a :class:`RidgeStudy` ``rel_k`` row naming its k ("k = 0.5", ..., "k*"), which chapter 04's table and
#: evidence read by this name (issue 36: named once).
K_LABEL = "k label"


@dataclass(frozen=True)
class RidgeStudy:
    r"""Experiment E2.5: scalar ridge against least squares, convergence, centralised vs distributed (:func:`ridge_study`).

    Attributes
    ----------
    kgrid : ndarray, shape (501,)
        Ridge parameters k of the analytic curves, from 0 to 5.
    mse, rel : mapping of float to ndarray, shape (501,)
        Per true x: analytic MSE and reliability :math:`P(|\hat x-x|\le\sigma/\sqrt m)` along ``kgrid``.
    rows : tuple of mapping of str to float
        Per true x: x, k*, MSE(0), MSE(k=1), rel(0), rel(k=1), max rel, argmax rel k (the rows of a table).
    ms : ndarray of int
        Numbers of measurements m of the convergence study.
    conv : mapping of (float, float) to ndarray, shape (len(ms),)
        ``conv[(x, k)]``: Monte-Carlo mean :math:`|\hat x_{RE}-\hat x_{LS}|` against m.
    m0 : int
        Number of measurements of the analytic curves.
    sigma : float
        Noise standard deviation.
    bound_k1 : float
        :math:`\sqrt{(2m_0+1)/m_0}`.
    rel1_kelvin : float
        Reliability at k = 1 for x = 273.65 (0.5 °C in kelvin).
    cen_dist_maxdiff : float
        Largest difference between centralised and distributed ridge, vector problem, k ∈ {0, 1}.
    rel_k : tuple of mapping of str to object
        Per x of ``xs`` and ``x_far`` and k of ``ks_fixed`` and "k*": x, k label, k, rel(k), rel(0), MSE(k), MSE(0).
    ks_fixed : tuple of float
        The fixed ridge parameters of ``rel_k``.
    sd_ratio_max : float
        Largest SD(k)/SD(0) of the scalar estimate over k in (0, 5].
    var_gap_min_eig : float
        Smallest eigenvalue, over k in ``ks_fixed``, of :math:`A^{-1} - (A+kI)^{-1}A(A+kI)^{-1}` (least-squares minus
        ridge covariance of the centralised vector estimate), relative to the largest eigenvalue of :math:`A^{-1}`.
    """

    kgrid: np.ndarray
    mse: Mapping[float, np.ndarray]
    rel: Mapping[float, np.ndarray]
    rows: tuple[Mapping[str, float], ...]
    ms: np.ndarray
    conv: Mapping[tuple[float, float], np.ndarray]
    m0: int
    sigma: float
    bound_k1: float
    rel1_kelvin: float
    cen_dist_maxdiff: float
    rel_k: tuple[Mapping[str, float | str], ...]
    ks_fixed: tuple[float, ...]
    sd_ratio_max: float
    var_gap_min_eig: float

    __result_spec__ = ResultSpec(
        {"kgrid": array("K", bounds=NONNEGATIVE), "mse": dict_of(array("K", bounds=NONNEGATIVE), key=float,
                                                                          check_key=real_key()),  # true x, finite
         "rel": dict_of(array("K", bounds=(0.0, 1.0)), key=float, check_key=real_key()),
         "rows": tuple_of(instance(Mapping)), "conv": dict_of(array("M", bounds=NONNEGATIVE), key=tuple),
         "m0": integer(1),
         "sigma": number(positive=True), "bound_k1": number(positive=True), "rel1_kelvin": number(bounds=(0.0, 1.0)),
         "cen_dist_maxdiff": number(), "rel_k": tuple_of(instance(Mapping)), "ks_fixed": tuple_of(number()),
         "sd_ratio_max": number(), "var_gap_min_eig": number(nonnegative=False)},
        relations=(same_keys("mse", "rel"),))
    __post_init__ = validated_post_init


@dataclass(frozen=True)
class CorrelatedStudy:
    r"""Experiment E2.7: correlated noise, LDLᵀ pseudo-measurements, GLS and the naive fusion (:func:`correlated_study`).

    Attributes
    ----------
    R : ndarray, shape (2N, 2N)
        The noise covariance.
    mrm_offdiag : float
        Largest off-diagonal of :math:`MRM^\top`, relative to max|R|.
    rel_ldl_gls : float
        Largest relative difference of the LDLᵀ and the GLS estimates.
    eg, en : ndarray, shape (2, runs)
        Errors of GLS and of the naive fusion.
    Pg, Pn : ndarray, shape (2, 2)
        Their claimed covariances.
    sq_gls, sq_naive : ndarray, shape (runs,)
        Per-run squared errors.
    mse_gls, mse_naive, nees_gls, nees_naive : float
        Mean squared errors and mean NEES.
    nees_samples : tuple of ndarray, shape (runs,)
        Per-run NEES of GLS and of the naive fusion.
    runs : int
        Monte-Carlo runs.
    flops : tuple of mapping of str to float
        Rows of :func:`fusion.readings.correlated.operation_counts` (with ``Nm``) for each problem size.
    """

    R: np.ndarray
    mrm_offdiag: float
    rel_ldl_gls: float
    eg: np.ndarray
    en: np.ndarray
    Pg: np.ndarray
    Pn: np.ndarray
    sq_gls: np.ndarray
    sq_naive: np.ndarray
    mse_gls: float
    mse_naive: float
    nees_gls: float
    nees_naive: float
    nees_samples: tuple[np.ndarray, np.ndarray]
    runs: int
    flops: tuple[Mapping[str, float], ...]

    __result_spec__ = ResultSpec(
        {"R": array("2N", "2N", covariance=True), "mrm_offdiag": number(), "rel_ldl_gls": number(),
         "eg": array(2, "runs"), "en": array(2, "runs"), "Pg": array(2, 2, covariance=True),
         "Pn": array(2, 2, covariance=True), "sq_gls": array("runs", bounds=NONNEGATIVE),
         "sq_naive": array("runs", bounds=NONNEGATIVE),
         "mse_gls": number(), "mse_naive": number(), "nees_gls": number(), "nees_naive": number(),
         "nees_samples": tuple_of(array("runs", bounds=NONNEGATIVE), array("runs", bounds=NONNEGATIVE)),
         "runs": integer(1, dim="runs"),
         "flops": tuple_of(dict_of(instance(int, float, np.integer, np.floating)))})
    __post_init__ = validated_post_init


# --------------------------------------------------------------------------- E2.5
def _random_sensors(rng: np.random.Generator) -> tuple[list[FloatArray], list[FloatArray], list[FloatArray]]:
    r"""Three random sensors of a 2-vector, four readings each: their matrices H (4, 2), covariances
    :math:`AA^\top + 4I` (4, 4) and readings y (4,), all standard normal draws from ``rng`` (in that order)."""
    Hs = [rng.normal(size=(4, 2)) for _ in range(3)]
    Rs = []
    for _ in range(3):
        A = rng.normal(size=(4, 4))
        Rs.append(A @ A.T + 4 * np.eye(4))
    return Hs, Rs, [rng.normal(size=4) for _ in range(3)]


def ridge_study(
    xs: Sequence[float] = (0.5, 1.0, 3.0, 10.0),
    ms: Sequence[int] = (1, 5, 20, 100),
    m0: int = 5,
    sigma: float = 1.0,
    seed: int = 2501,
    seed_vector: int = 2502,
    draws: int = 2000,
    ks_fixed: Sequence[float] = (0.01, 0.1, 1.0),
    x_far: float = 273.65,
) -> RidgeStudy:
    r"""Experiment E2.5: scalar ridge against least squares, and centralised vs distributed.

    Analytic MSE and reliability :math:`P(|\hat x-x|\le\sigma/\sqrt m)` on the grid
    k ∈ [0, 5] (501 points) for ``m0`` measurements; Monte-Carlo mean
    :math:`|\hat x_{RE}-\hat x_{LS}|` against m for x ∈ {1, 10}, k ∈ {0.5, 2}; the largest
    difference between centralised and distributed ridge on a random three-sensor vector problem
    at k ∈ {0, 1}; reliability at fixed ``ks_fixed`` and at the MSE-optimal :math:`k^* = \sigma^2/x^2`
    for every x of ``xs`` and ``x_far``; the gap between the least-squares and the ridge covariance
    of the vector problem.

    Parameters
    ----------
    xs : sequence of float
        True values x (no two equal: the curves are keyed by x).
    ms : sequence of int
        Numbers of measurements m of the convergence study (no two equal; 4 x draws x sum(ms) normals, 2.5 units
        each, measured, within the work budget, ``fusion._validation.MAX_WORK``: sum(ms) up to 50,000 of 2,000 draws).
    m0 : int
        Number of measurements of the analytic curves.
    sigma : float
        Noise standard deviation.
    seed, seed_vector : int
        Seeds of the scalar Monte Carlo and of the vector problem.
    draws : int
        Monte-Carlo draws per (x, k, m).
    ks_fixed : sequence of float
        Fixed ridge parameters (> 0) of the reliability check, no two equal to 6 significant digits (their rows are
        labelled ``f"k = {k:g}"``).
    x_far : float
        A true value far from the shrinkage target (0.5 °C expressed in kelvin), not one of ``xs`` (the rows of
        ``rel_k`` are keyed by x).

    Returns
    -------
    RidgeStudy
        The curves, the convergence, the reliability at fixed and optimal k and the vector problem's checks, with
        :math:`A = \sum_i H_i^\top R_i^{-1}H_i` in ``var_gap_min_eig``.
    """
    m_arr = _ints(ms, "ms")
    m0 = count(m0, "m0")
    sigma = std_scalar(sigma, "sigma")
    xv = as_array(xs, "xs", ndim=1)
    kv = as_array(ks_fixed, "ks_fixed", ndim=1)  # fuzz 24a U7: numbers, at least one, each > 0
    if kv.min() <= 0:
        raise ValueError(f"ks_fixed must hold positive ridge parameters, got {shown(kv.tolist())}")
    # rule 17: ~100 us a row (215-246 us a row of xs x ks_fixed measured at 11-101 xs, 1-30 ks_fixed, fix 72b:
    # time.process_time, OPENBLAS_NUM_THREADS=1, shared machine; the edge ~12 CPU-s); by the sizes before the entries
    # are copied into lists (fix 72b, fuzz 64b's class: 10**7 xs were listed first, 0.4-1 CPU-s to refuse)
    loop_work((xv.size + 1, 3 + kv.size), 501, "xs and ks_fixed", step=20 * LOOP_STEP)
    xs, ks_fixed = xv.tolist(), kv.tolist()
    # the repeats looked for after the budget by their number
    # (fix70a, fuzz 62b's class: each entry hashed before a budget that needs only their number, 2.5 CPU-s a 10**7 list)
    distinct(xs, "xs")  # mse and rel are keyed by x; ms after their budgets below
    distinct_printed(ks_fixed, "ks_fixed", general)  # rel_k's rows are labelled f"k = {k:g}" (fuzz 30b)
    for i, x in enumerate(xs):
        _optimal_k_representable(x, sigma, f"xs[{i}]")
    x_far = scalar(x_far, "x_far")
    _optimal_k_representable(x_far, sigma, "x_far")
    if x_far in xs:  # fuzz 26d A9: rel_k would hold that x's rows twice
        raise ValueError(f"x_far must not be one of xs {shown(xs)} (rel_k's rows are keyed by x), got {shown(x_far)}")
    seed = _seed(seed)
    seed_vector = _seed(seed_vector, "seed_vector")
    draws = count(draws, "draws", minimum=2)
    allocation((draws, int(m_arr.max())), "ms and draws")
    # the loop below draws 4 x draws x sum(ms) normals (fuzz13 bug 1), each with its sum and mean: 16-22 ns a normal
    # measured at sum(ms) = 20,000 and 40,000 of 2,000 draws (the least of two calls, time.process_time,
    # OPENBLAS_NUM_THREADS=1, machine shared; 28.5 in fuzz 40a D2, whose 8e8 normals at one unit ran 22.8 CPU-s),
    # weighed 2.5 units: the edge, 4e8 normals, runs 6-11 CPU-s
    work((4, draws, int(m_arr.sum())), "ms and draws", weight=2.5)  # exact: at most 10**7 counts of 10**7
    # the validated values as ints (ms may be any 1-D array-like); conv's entries are keyed by m. Both after the
    # budgets, which need only the largest and the sum (fuzz 63b's class: 10**7 ms, np.arange(1, 10**7 + 1), were
    # copied and hashed first, refused after 3.7 CPU-s)
    ms = [int(m) for m in m_arr]
    distinct(ms, "ms")
    kgrid = np.linspace(0, 5, 501)
    i1 = int(np.argmin(np.abs(kgrid - 1.0)))
    delta = sigma / np.sqrt(m0)
    mse, rel, rows = {}, {}, []
    for x in xs:
        mom = rg.scalar_ridge_moments(m0, sigma, x, kgrid)
        b, s, mse[x] = mom.bias, mom.sd, mom.mse
        rel[x] = rg.reliability(b, s, delta)
        rows.append({"x": x, "k*": rg.optimal_ridge_k(sigma, x), "MSE(0)": mse[x][0], "MSE(k=1)": mse[x][i1],
                     "rel(0)": rel[x][0], "rel(k=1)": rel[x][i1], "max rel": rel[x].max(),
                     "argmax rel k": kgrid[np.argmax(rel[x])]})
    rng = np.random.default_rng(seed)
    conv = {}
    for x in (1.0, 10.0):
        for k in (0.5, 2.0):
            conv[x, k] = np.array([np.mean(np.abs(rng.normal(x, sigma, size=(draws, m)).sum(axis=1) * (1 / (m + k) - 1 / m)))
                                   for m in ms])
    Hs, Rs, ys = _random_sensors(np.random.default_rng(seed_vector))
    cd = max(float(np.max(np.abs(rg.ridge_centralised(Hs, Rs, ys, k) - rg.ridge_distributed(Hs, Rs, ys, k))))
             for k in (0.0, 1.0))
    rel_k = []
    for x in (*xs, x_far):
        mom0 = rg.scalar_ridge_moments(m0, sigma, x, 0.0)
        b0, s0, mse0 = mom0.bias, mom0.sd, mom0.mse
        rel0 = float(rg.reliability(b0, s0, delta))
        for label, k in [(f"k = {kf:g}", kf) for kf in ks_fixed] + [("k*", rg.optimal_ridge_k(sigma, x))]:
            momk = rg.scalar_ridge_moments(m0, sigma, x, k)
            b, sd, mk = momk.bias, momk.sd, momk.mse
            rel_k.append({"x": float(x), K_LABEL: label, "k": float(k), "rel(k)": float(rg.reliability(b, sd, delta)),
                          "rel(0)": rel0, "MSE(k)": float(mk), "MSE(0)": float(mse0)})
    sd_grid = rg.scalar_ridge_moments(m0, sigma, 1.0, kgrid[1:]).sd
    A = sum(H.T @ np.linalg.solve(R, H) for H, R in zip(Hs, Rs))
    P_ls = np.linalg.inv(A)
    gaps = []
    for k in ks_fixed:
        G = np.linalg.inv(A + k * np.eye(A.shape[0]))
        gaps.append(float(np.linalg.eigvalsh(P_ls - G @ A @ G).min()))
    return RidgeStudy(
        kgrid=kgrid, mse=mse, rel=rel, rows=rows, ms=np.asarray(ms), conv=conv, m0=m0, sigma=sigma,
        bound_k1=float(np.sqrt((2 * m0 + 1) / m0)),
        rel1_kelvin=float(rg.reliability(rg.scalar_ridge_moments(m0, sigma, 273.65, 1.0).bias,
                                         rg.scalar_ridge_moments(m0, sigma, 273.65, 1.0).sd, delta)),
        cen_dist_maxdiff=cd, rel_k=rel_k, ks_fixed=tuple(float(k) for k in ks_fixed),
        sd_ratio_max=float(np.max(sd_grid) * np.sqrt(m0) / sigma),
        var_gap_min_eig=min(gaps) / float(np.linalg.eigvalsh(P_ls).max()))


def _optimal_k_representable(x: float, sigma: float, name: str) -> None:
    """Refuse a true value ``x`` whose MSE-optimal ridge :math:`k^* = \\sigma^2/x^2` is not a representable number.

    ``x = 0`` has no finite :math:`k^*`; beyond [``MIN_MAGNITUDE``, ``MAX_MAGNITUDE``] the moments at
    :math:`k^*` under- or overflow. The message names ``name`` and ``sigma``.
    """
    with np.errstate(all="ignore"):
        k = sigma**2 / x**2 if x else np.inf
    if not MIN_MAGNITUDE <= k <= MAX_MAGNITUDE:
        raise ValueError(f"{name} = {shown(x)} with sigma = {shown(sigma)} gives an optimal ridge parameter k* = sigma^2/x^2 = "
                         f"{k:.3g}, outside [{MIN_MAGNITUDE:g}, {MAX_MAGNITUDE:g}] (x = 0 has no finite k*)")


# --------------------------------------------------------------------------- E2.7
#: The largest condition number of E2.7's R, and ratio sigma_env² / min(sigma²), that :func:`correlated_study` accepts:
#: GLS's relative round-off is of order eps cond(R) (2.2e-5 here), below half a unit of the 4th significant digit its
#: readers glue, and the chapter's solver self-check (structured against plain GLS, measured 0.1-0.5 eps cond(R)
#: apart) stays 10x inside its 1e-4 tolerance (fuzz 37b C5: from cond(R) ~4e12 the two valid solvers differed by more
#: than the glued precision; at sigma_env² / sigma² = 1e18 R did not hold the own variance at all).
MAX_COND = 1e11


def _conditioning(R: np.ndarray) -> float:
    """The larger of cond(R) of E2.7's R = diag(sig²) ⊗ I₂ + sigma_env² 1 1ᵀ ⊗ I₂ (by its eigenvalues; inf when it
    is not positive definite in floating point) and sigma_env² / min(sig²), the conditioning of R's split into
    D + U Uᵀ as the chapter's structured solver splits it (sigma_env² = R[0, 2], the own variances R's diagonal less
    it): a diagonal that R holds only to a relative eps sigma_env² / sig² (at 1e18 R does not hold the own SD at all,
    and the structured solver's D was not positive). One function of R for :func:`correlated_study` and its reader
    ``glue_27`` (fuzz 38b C3: the reader's recomputation from R lost ~2e-5 relative against the producer's from
    sigma, refusing accepted studies at the edge), so that every R the producer accepts its reader accepts."""
    R = np.asarray(R, dtype=float)
    ev = np.linalg.eigvalsh(R)
    cond = float(ev[-1] / ev[0]) if ev[0] > 0 else np.inf
    if R.shape[0] < 4:   # one sensor: no coupling, R = D + 0
        return cond
    env2 = float(R[0, 2])
    own = float(np.min(np.diag(R) - env2))
    return max(cond, env2 / own if own > 0 else np.inf)


def _stacked_shape(N: int, runs: int) -> tuple[int, int]:
    """The shape of :func:`correlated_study`'s stacked readings z of ``N`` two-axis sensors over ``runs`` runs: the
    one rule for the array it draws and for its entry check against its callees' input budget."""
    return (2 * N, runs)


def _correlated_budget(N: int, runs: int, names: str, dense_names: str) -> int:
    """Rules 9 and 17 of :func:`correlated_study` on N sensors and ``runs`` runs, naming ``names`` (the draws and
    the stacked readings) and ``dense_names`` (the dense algebra of R); its units (fuzz 54a C3)."""
    allocation((2 * N, runs), names)
    # the stacked readings z, (2N, runs), are the input of co.gls and its siblings, which refuse more than
    # MAX_INPUT_ELEMENTS: refused here by the same shape, naming sigma and runs (fuzz 39a C2: 480 x 70,000 was
    # refused by gls after the draws and the LDL algebra, naming every argument)
    input_allocation(_stacked_shape(N, runs), names)
    # rule 17 (fuzz 38a C5): R is 2N x 2N (LDL, GLS, Cholesky, eigvalsh), 0.5-0.9 ns a (2N)**3 measured (N = 300-2,000)
    return dense_work(1, 2 * N, dense_names, 8 * DENSE_CUBE)


@derived_inputs()
def correlated_study(
    sigma: Sequence[float] = (1.0, 2.0, 3.0),
    sigma_env: float = 1.5,
    runs: int = 20000,
    x: Sequence[float] = (1.0, -2.0),
    seed: int = 2701,
    sizes: Sequence[int] = (6, 60, 600),
) -> CorrelatedStudy:
    r"""Experiment E2.7: correlated noise, LDLᵀ pseudo-measurements, GLS and the naive fusion.

    :math:`R = \mathrm{diag}(\sigma_i^2)\otimes I_2 + \sigma_e^2\mathbf 1\mathbf 1^\top\otimes I_2`,
    :math:`H_i = I_2`.

    Parameters
    ----------
    sigma : sequence of float
        Own noise standard deviation :math:`\sigma_i` of each sensor; the study's ``2N x 2N`` algebra of ``N``
        sensors has a work budget (about 1,100 sensors, refused naming ``sigma``).
    sigma_env : float
        Standard deviation :math:`\sigma_e` of the common environmental noise (> 0). With ``sigma``, R's condition
        number must not exceed ``MAX_COND`` (1e11), nor ``sigma_env**2`` that of the smallest own variance: beyond
        either, GLS's round-off or the split of R into its own and common parts reaches the 4 digits E2.7 glues.
    runs : int
        Monte-Carlo runs.
    x : sequence of float
        True 2-D state.
    seed : int
        Seed of the noise.
    sizes : sequence of int
        Problem sizes of the operation counts (no two equal).

    Returns
    -------
    CorrelatedStudy
        Errors, claimed covariances, MSE and NEES of GLS and the naive fusion, the LDLᵀ checks and the operation
        counts for ``sizes``.
    """
    x = read_once(x, "x")  # a Sequence class read once (fuzz 31a C4)
    sig = _sigmas(sigma, minimum=1)
    sigma_env = std_scalar(sigma_env, "sigma_env")
    runs = count(runs, "runs", minimum=2)
    N = sig.size
    _correlated_budget(N, runs, "sigma and runs", "sigma")
    if as_array(x, "x", ndim=1).size != 2:
        raise ValueError("x must have length 2")
    seed = _seed(seed)
    size_arr = _ints(sizes, "sizes")  # the validated values (any 1-D array-like)
    loop_work((size_arr.size,), 0, "sizes", step=10 * LOOP_STEP)  # rule 17: a closed-form row (~40 us) per size
    # the budget by the number of sizes before they are converted to ints (fix 72b, fuzz 64b's class: 10**7 sizes
    # were listed first, refused after 1.7 CPU-s; 1.0 of them the list)
    sizes = [int(n) for n in size_arr]
    distinct(sizes, "sizes")  # one row per size: a repeated size would repeat its row; after the budget (fix70a)
    R = np.kron(np.diag(sig**2), np.eye(2)) + sigma_env**2 * np.kron(np.ones((N, N)), np.eye(2))
    if not _conditioning(R) <= MAX_COND:   # fuzz 37b C5: beyond what the chapter can glue and check
        raise ValueError(f"sigma and sigma_env must give R a condition number, and sigma_env**2 / min(sigma)**2, of at "
                         f"most {MAX_COND:g} (round-off reaches the 4 digits glued): the own SDs are too small beside "
                         "sigma_env or each other")
    H = np.kron(np.ones((N, 1)), np.eye(2))
    xt = np.asarray(x, dtype=float)
    L = co.ldl_unpivoted(R).L
    M = co.unit_lower_inverse(L)
    D = M @ R @ M.T
    z = H @ xt[:, None] + np.linalg.cholesky(R) @ np.random.default_rng(seed).normal(size=_stacked_shape(N, runs))
    gls, naive = co.gls(H, R, z), co.naive_fusion(H, R, z, block=2)
    xg, Pg, xn, Pn = gls.x, gls.P, naive.x, naive.P
    xl = co.pseudo_measurement_fusion(H, R, z).x
    eg, en = xg - xt[:, None], xn - xt[:, None]
    nees = [np.einsum("ir,ij,jr->r", e, np.linalg.inv(P), e) for e, P in ((eg, Pg), (en, Pn))]
    flops = [{"Nm": Nm, **co.operation_counts(Nm, 2)} for Nm in sizes]
    return CorrelatedStudy(
        R=R, mrm_offdiag=float(np.max(np.abs(D - np.diag(np.diag(D)))) / np.abs(R).max()),
        rel_ldl_gls=float(np.max(np.abs(xl - xg)) / np.max(np.abs(xg))),
        eg=eg, en=en, Pg=Pg, Pn=Pn,
        sq_gls=np.sum(eg**2, axis=0), sq_naive=np.sum(en**2, axis=0),
        mse_gls=float(np.mean(np.sum(eg**2, axis=0))), mse_naive=float(np.mean(np.sum(en**2, axis=0))),
        nees_gls=float(np.mean(nees[0])), nees_naive=float(np.mean(nees[1])), nees_samples=(nees[0], nees[1]),
        runs=runs, flops=flops)
