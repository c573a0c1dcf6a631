r"""Ridge fusion of the lecture notes' §2.5 with a data-driven parameter: scalar and vector cases.

* :func:`plugin_study`: scalar :math:`y_i = x + e_i`, :math:`i = 1..m`; least squares (the mean)
  against ridge with the plug-in :math:`\hat k = \sigma^2/\bar y^2` (known σ) and with
  :math:`\hat k = s^2/\bar y^2` (σ estimated from the same readings), over a grid of true values:
  per-run squared error and our reliability indicator :math:`|\hat x - x| \le c\sigma/\sqrt m` for
  several tolerances c, and the exact curves of :func:`fusion.readings.biased.plugin_risk`.
* :func:`vector_study`: three sensors, each observing a two-dimensional x through a nearly
  collinear :math:`H_i` (an ill-conditioned problem), with x along the well-observed or the
  poorly observed direction; least squares, centralised plug-in ridge and distributed plug-in
  ridge (each sensor shrinks its own estimate).

References
----------
* Hoerl, A. E., & Kennard, R. W. (1970). Ridge regression: biased estimation for nonorthogonal
  problems. *Technometrics*, 12(1), 55-67.
* Hoerl, A. E., Kennard, R. W., & Baldwin, K. F. (1975). Ridge regression: some simulations.
  *Communications in Statistics*, 4(2), 105-123.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from fusion._results import (NONNEGATIVE, ResultSpec, array, dict_of, instance, integer, number, same_keys, tuple_of,
                             real_key, validated_post_init)
from fusion._validation import derived_inputs
from fusion._counts import input_allocation
from fusion._validation import seed as check_seed
from fusion._limits import LOOP_STEP
from fusion._validation import distinct, distinct_printed, glue_part, loop_work
from fusion._validation import allocation, as_array, count, finite_result, positive_scalar, std_scalar
from fusion.readings import biased as rg

__all__ = ["LS", "PLUGIN_KNOWN", "PLUGIN_EST", "RIDGE_CENTRALISED", "RIDGE_DISTRIBUTED", "PLUGIN_METHODS",
           "VECTOR_METHODS", "PluginStudy", "VectorStudy", "plugin_study", "vector_study"]

#: Method keys of the studies (display labels: :data:`fusion.book.style.METHOD_LABELS`, and
#: :data:`fusion.book.style.METHOD_SHORT_LABELS` in tables and ledger entries): least squares (the mean), the
#: scalar plug-in ridge with σ known and with σ estimated, the vector plug-in ridge shrunk at the centre or at each
#: sensor.
LS, PLUGIN_KNOWN, PLUGIN_EST = "ls", "ridge_plugin_known", "ridge_plugin_est"
RIDGE_CENTRALISED, RIDGE_DISTRIBUTED = "ridge_centralised", "ridge_distributed"

#: The methods of :func:`plugin_study`, in their order in its results.
PLUGIN_METHODS: tuple[str, str, str] = (LS, PLUGIN_KNOWN, PLUGIN_EST)

#: The methods of :func:`vector_study`, in their order in its results.
VECTOR_METHODS: tuple[str, str, str] = (LS, RIDGE_CENTRALISED, RIDGE_DISTRIBUTED)


def _plugin_range(xs: np.ndarray, m: int, sigma: float, names: str) -> None:
    """Refuse true values ``xs`` beyond ``PLUGIN_RANGE`` standard errors, naming ``names``: the exact risk at each x
    (chapter 04's ``plugin_exact``) is not computed there (fuzz 31b C4: plugin_study accepted them, and its reader
    refused the study naming its inner ``theta``)."""
    big = float(np.abs(np.asarray(xs, dtype=float) * np.sqrt(m) / sigma).max())
    if big > rg.PLUGIN_RANGE:
        raise ValueError(f"{names} must give true values of at most {rg.PLUGIN_RANGE:g} standard errors "
                         f"(sqrt(m) |x| / sigma), got {big:g}: beyond, the exact risk at x is not computed")


#: The largest tolerance (standard errors) of :func:`plugin_study`'s ``deltas``: chapter 04's ``plugin_exact`` finds
#: the known-σ plug-in's crossings (``fusion.readings.biased.plugin_crossings`` on θ up to 10) only up to c ≈ 8.29.
_MAX_DELTA = 8.0


def _plugin_deltas(deltas: np.ndarray, names: str) -> None:
    """Refuse tolerances beyond ``_MAX_DELTA``, naming ``names`` (fuzz 33b B1: plugin_study accepted them, and its
    reader refused the study naming the inner ``upper`` or ``c``)."""
    big = float(np.max(deltas))
    if big > _MAX_DELTA:
        raise ValueError(f"{names} must hold tolerances of at most {_MAX_DELTA:g} standard errors, got {big:g}: "
                         f"beyond, the plug-in's exact reliability crossing is not computed")


@dataclass(frozen=True)
class PluginStudy:
    r"""Scalar ridge with a plug-in parameter against least squares, by true value (:func:`plugin_study`).

    Attributes
    ----------
    sq, hit : mapping of float to mapping of str to ndarray, shape (runs,)
        Per true x: per-run squared error and reliability indicator (0/1, tolerance :math:`\sigma/\sqrt m`) of
        each method of :data:`PLUGIN_METHODS`.
    hits : mapping of float to mapping of float to mapping of str to ndarray, shape (runs,)
        ``hits[c][x]``: the indicator for the tolerance :math:`c\sigma/\sqrt m` of each c of ``deltas``.
    curve : ndarray
        True values of the exact curves.
    ratio_known, ratio_est : ndarray
        Exact MSE of each plug-in over LS along ``curve``.
    rel_curve : mapping of str to ndarray
        Exact reliabilities along ``curve``, by method key (LS included).
    m, runs, seed : int
    sigma, delta : float
        Noise SD and the tolerance :math:`\sigma/\sqrt m`.
    deltas, xs : tuple of float
    """

    sq: Mapping[float, Mapping[str, np.ndarray]]
    hit: Mapping[float, Mapping[str, np.ndarray]]
    hits: Mapping[float, Mapping[float, Mapping[str, np.ndarray]]]
    curve: np.ndarray
    ratio_known: np.ndarray
    ratio_est: np.ndarray
    rel_curve: Mapping[str, np.ndarray]
    m: int
    sigma: float
    runs: int
    seed: int
    delta: float
    deltas: tuple[float, ...]
    xs: tuple[float, ...]

    __result_spec__ = ResultSpec(
        {"sq": dict_of(dict_of(array("runs", bounds=NONNEGATIVE)), key=float, printed=glue_part,
                       check_key=real_key()),  # true values x, finite (decision 32b)
         "hit": dict_of(dict_of(array("runs", bounds=(0.0, 1.0))), key=float, check_key=real_key()),
         "hits": dict_of(dict_of(dict_of(array("runs", bounds=(0.0, 1.0))), key=float, check_key=real_key()),
                         key=float, printed=glue_part, check_key=real_key(0.0, lo_open=True)),  # tolerances c > 0
         "curve": array("C"),
         "ratio_known": array("C", bounds=NONNEGATIVE), "ratio_est": array("C", bounds=NONNEGATIVE),
         "rel_curve": dict_of(array("C", bounds=(0.0, 1.0))),
         "m": integer(1), "sigma": number(positive=True), "runs": integer(1, dim="runs"), "seed": integer(0),
         "delta": number(positive=True), "deltas": tuple_of(number(positive=True)),
         "xs": tuple_of(number(nonnegative=False))},
        relations=(same_keys("xs", "sq", "hit"), same_keys("deltas", "hits")))
    __post_init__ = validated_post_init


@dataclass(frozen=True)
class VectorStudy:
    r"""An ill-conditioned vector case: LS, centralised and distributed plug-in ridge (:func:`vector_study`).

    Attributes
    ----------
    sq : mapping of (str, float) to mapping of str to ndarray, shape (runs,)
        ``sq[(direction, scale)]``: per-run squared errors of each method of :data:`VECTOR_METHODS`.
    x : mapping of (str, float) to ndarray, shape (2,)
        The true values.
    A : ndarray, shape (2, 2)
        The total information :math:`\sum_iH_i^\top R_i^{-1}H_i`.
    cond, tr_ls : float
        Its condition number and the exact MSE of LS, :math:`\mathrm{tr}\,A^{-1}`.
    runs, seed : int
    scales : tuple of float
    """

    sq: Mapping[tuple[str, float], Mapping[str, np.ndarray]]
    x: Mapping[tuple[str, float], np.ndarray]
    A: np.ndarray
    cond: float
    tr_ls: float
    runs: int
    seed: int
    scales: tuple[float, ...]

    __result_spec__ = ResultSpec(
        {"sq": dict_of(dict_of(array("runs", bounds=NONNEGATIVE)), key=tuple, printed=glue_part),  # glue keys, rows
         "x": dict_of(array(2), key=tuple),
         "A": array(2, 2, covariance=True), "cond": number(positive=True), "tr_ls": number(positive=True),
         "runs": integer(1, dim="runs"), "seed": integer(0), "scales": tuple_of(number(positive=True))},
        relations=(same_keys("sq", "x"),))
    __post_init__ = validated_post_init


def _plugin_memory(m: int, runs: int, names: str) -> None:
    """Rule 9 of :func:`plugin_study`: the noise of every run, ``m x runs``, and the readings its estimators take
    (fuzz 39a D1, class), naming ``names``."""
    allocation((m, runs), names)
    input_allocation((m, runs), names)


def _plugin_work(n_xs: int, n_deltas: int, m: int, runs: int, names: str) -> int:
    """Rule 17 of :func:`plugin_study`: per x three estimates and a pass per tolerance, ``n_deltas + 3`` loop steps
    of ``14 x LOOP_STEP + (m + 5) x runs`` units each, naming ``names``; its units (a chapter study that runs it with
    others sums them, fuzz 54a C3).

    Measured (OPENBLAS_NUM_THREADS=1, process time, minimum of 3 on a shared 2-core machine; fuzz 64b C2: a step
    was counted ``LOOP_STEP + m x runs``, ~40 us an x at m = 2, runs = 2, and the edge of 249,003 xs would have run
    ~90 CPU-s): an x costs 0.27-0.28 ms at m = 2 to 340, runs = 2, one delta (the two validated ``plugin_ridge``
    calls), 1.0 ms with 20 deltas (~38 us a tolerance), so ~70 us a step: weighed 140 us (14 LOOP_STEP). A run
    costs ~32 ns a step at m = 2, runs = 20,000 (3.4 ms an x, one delta; 15.8 ms with 20) and ~1.1 us a step at
    m = 340, runs = 2,000 (9.1 ms an x): weighed ``(m + 5)`` units a run. The edge at m = 2, runs = 2, one delta is
    17,839 xs, ~5 CPU-s."""
    return loop_work((n_xs, n_deltas + 3), (m + 5) * runs, names, step=14 * LOOP_STEP)


def _vector_work(n_scales: int, runs: int, names: str) -> int:
    """Rule 17 of :func:`vector_study`: three fusions per scale and direction, a loop step of
    ``130 x LOOP_STEP + 60 x runs`` units, naming ``names``; its units (fuzz 54a C3).

    Measured (OPENBLAS_NUM_THREADS=1, process time, minimum of 3 on a shared 2-core machine; fuzz 64b C1: a step was
    counted ``LOOP_STEP + 60 x runs``, ~11 us at runs = 2, and the edge of 446,428 scales would have run ~14 min): a
    step (three 2 x 2 solves, two validated ``ridge_fusion_plugin`` calls) costs 0.64-0.67 ms at runs = 2 to 200,
    weighed 1.3 ms (130 LOOP_STEP); 6.4 ms at runs = 20,000 (~0.29 us a run, weighed 0.6 us). The edge at
    runs = 2 is 3,842 scales, ~5 CPU-s."""
    return loop_work((n_scales, 2), 60 * runs, names, step=130 * LOOP_STEP)


@derived_inputs()
def plugin_study(
    xs: Sequence[float] = (0.0, 0.25, 0.5, 1.0, 2.0, 3.0, 10.0),
    m: int = 5,
    sigma: float = 1.0,
    runs: int = 4000,
    seed: int = 2511,
    curve: Sequence[float] = tuple(np.round(np.linspace(0.0, 3.0, 121), 10)),
    deltas: Sequence[float] = (0.5, 1.0, 2.0),
) -> PluginStudy:
    r"""Scalar ridge with a plug-in parameter against least squares, as a function of the true x.

    Paired Monte Carlo at the true values ``xs`` (the same noise at every x) for the ledger's
    comparisons, and exact curves (:func:`fusion.readings.biased.plugin_risk`, quadrature) along ``curve``.

    Parameters
    ----------
    xs : sequence of float
        True values of the paired comparisons (no two alike in their digits ``f"{x:g}"``, 1.5 and 15 included:
        the results are keyed by x, chapter 04's glue values by those digits, ``fusion._counts.glue_part``: -1 as
        ``m1``, 1e-05 as ``1em05``); ``sqrt(m) |x| / sigma`` at most ``fusion.readings.biased.PLUGIN_RANGE``.
    m : int
        Readings per estimate (>= 2, so that σ can be estimated).
    sigma : float
        Noise SD (> 0).
    runs : int
        Monte-Carlo runs per x of ``xs`` (the same noise at every x).
    seed : int
        Seed of the noise.
    curve : sequence of float
        True values of the exact curves.
    deltas : sequence of float
        Tolerances of the reliability in standard errors :math:`\sigma/\sqrt m` (> 0 and at most 8, where the
        exact crossings are computed); 1 must be among them, no two alike in their digits (as ``xs``).

    Returns
    -------
    PluginStudy
        See the class's attributes.

    Raises
    ------
    ValueError
        Empty or non-finite ``xs`` or ``curve``, bad ``m``, ``sigma``, ``runs``, ``seed`` or ``deltas``; a ``curve``
        so long that its exact quadratures are beyond the memory or work budget; ``xs``, ``m`` and ``sigma`` giving a
        true value beyond ``fusion.readings.biased.PLUGIN_RANGE`` standard errors (its exact risk is not computed);
        ``deltas`` above 8 (the exact crossings are not computed); ``m`` above
        ``fusion.readings.biased.PLUGIN_MAX_M`` (the exact curves are not computed), before any run.
    """
    xv = as_array(xs, "xs", ndim=1)
    if xv.size == 0:
        raise ValueError("xs must not be empty")
    m = count(m, "m", minimum=2)
    sigma = std_scalar(sigma, "sigma")
    runs = count(runs, "runs", minimum=2)
    _plugin_memory(m, runs, "m and runs")
    if m > rg.PLUGIN_MAX_M:  # the exact curves' plugin_risk(m=m) refused it only after the Monte Carlo over xs
        raise ValueError(f"m must be at most {rg.PLUGIN_MAX_M} (beyond, the Gauss-Laguerre weights of the "
                         f"estimated sigma overflow in the exact curves), got {m}")
    seed = check_seed(seed)
    cv = as_array(curve, "curve", ndim=1)
    if cv.size == 0:
        raise ValueError("curve must not be empty")
    rg._risk_budget(cv.size, m, "curve and m")  # rules 9 and 17: plugin_risk's quadratures along the curve
    dv = as_array(deltas, "deltas", ndim=1)
    if dv.size == 0 or np.any(dv <= 0) or not np.any(dv == 1.0):
        raise ValueError(f"deltas must hold positive tolerances, 1 among them, got {dv}")
    _plugin_range(xv, m, sigma, "xs, m and sigma")  # what the study's reader (plugin_exact) computes
    _plugin_deltas(dv, "deltas")
    # the budget by the sizes before any entry is printed (fuzz 63b C3: 9.9e6 xs were printed and hashed first,
    # refused after 24.7 CPU-s); a repeat, refused below, is counted as its own x
    _plugin_work(xv.size, dv.size, m, runs, "xs, deltas, m and runs")
    for name, vals in (("xs", xv), ("deltas", dv)):  # the results are keyed by x and by delta, glue values by
        distinct_printed(vals.tolist(), name, glue_part)  # their digits (fuzz 30b, 31b)
    delta = sigma / np.sqrt(m)
    H = np.ones(m)
    e = np.random.default_rng(seed).normal(size=(m, runs)) * sigma
    sq, hit, hits = {}, {}, {float(c): {} for c in dv}
    for x in xv:
        y = float(x) + e
        est = {LS: y.mean(axis=0), PLUGIN_KNOWN: rg.plugin_ridge(H, y, sigma=sigma).x[0],
               PLUGIN_EST: rg.plugin_ridge(H, y).x[0]}
        sq[float(x)] = {k: np.round((v - x) ** 2, 12) for k, v in est.items()}
        for c in dv:
            hits[float(c)][float(x)] = {k: (np.abs(v - x) <= c * delta).astype(float) for k, v in est.items()}
        hit[float(x)] = hits[1.0][float(x)]
    theta = cv * np.sqrt(m) / sigma
    known, est_ = rg.plugin_risk(theta), rg.plugin_risk(theta, m=m)
    return PluginStudy(sq=sq, hit=hit, hits=hits, curve=cv, ratio_known=known.mse_ratio, ratio_est=est_.mse_ratio,
                       rel_curve={LS: np.full(cv.size, known.reliability_ls), PLUGIN_KNOWN: known.reliability,
                                  PLUGIN_EST: est_.reliability},
                       m=m, sigma=sigma, runs=int(runs), seed=int(seed), delta=float(delta),
                       deltas=tuple(float(c) for c in dv), xs=tuple(float(x) for x in xv))


@derived_inputs()
@finite_result("scales, spread and sigma")
def vector_study(
    runs: int = 2000,
    seed: int = 2512,
    scales: Sequence[float] = (3.0, 30.0, 100.0),
    spread: float = 0.05,
    sigma: Sequence[float] = (1.0, 1.5, 2.0),
) -> VectorStudy:
    r"""An ill-conditioned vector case: LS, centralised and distributed plug-in ridge.

    Sensor i reads :math:`y_i = H_ix + e_i`, :math:`H_i = \begin{pmatrix}1 & 1\\ 1 & 1 + \epsilon_i\end{pmatrix}`
    with :math:`\epsilon_i = ` ``spread`` × (1, -1, 2)[i], :math:`e_i \sim N(0, \sigma_i^2I_2)`. The
    direction :math:`(1, 1)/\sqrt2` is well observed, :math:`(1, -1)/\sqrt2` poorly. True values of
    each norm in ``scales``, along the strong and along the weak direction.

    Parameters
    ----------
    runs : int
        Monte-Carlo runs (the same noise for both true values).
    seed : int
        Seed of the noise.
    scales : sequence of float
        Norms of the true x (> 0, no two alike in their digits ``f"{scale:g}"``, 3.5 and 35 included: the results
        are keyed by scale, the chapter's tables by ``f"{scale:g}"`` and its glue values by those digits,
        ``fusion._counts.glue_part``).
    spread : float
        Collinearity parameter ε (> 0; smaller is worse conditioned).
    sigma : sequence of float
        Noise SD of the three sensors (> 0).

    Returns
    -------
    VectorStudy
        See the class's attributes.
    """
    runs = count(runs, "runs", minimum=2)
    seed = check_seed(seed)
    sc = as_array(scales, "scales", ndim=1)
    if sc.size == 0 or np.any(sc <= 0):
        raise ValueError(f"scales must hold positive norms, got {sc}")
    # the budget by the number of scales before any is printed (fuzz 63b C3: 10**7 scales were printed and hashed
    # first, refused after 27.5 CPU-s); a repeat, refused below, is counted as its own scale
    _vector_work(sc.size, runs, "scales and runs")
    distinct_printed(sc.tolist(), "scales", glue_part)  # results keyed by (direction, scale), glue keys by glue_part
    spread = positive_scalar(spread, "spread")
    sig = as_array(sigma, "sigma", ndim=1)
    if sig.size != 3 or np.any(sig <= 0):
        raise ValueError(f"sigma must hold 3 positive SDs, got {sig}")
    Hs = [np.array([[1.0, 1.0], [1.0, 1.0 + spread * f]]) for f in (1.0, -1.0, 2.0)]
    Rs = [s**2 * np.eye(2) for s in sig]
    A = sum(H.T @ np.linalg.solve(R, H) for H, R in zip(Hs, Rs))
    rng = np.random.default_rng(seed)
    noise = [s * rng.normal(size=(2, runs)) for s in sig]
    sq, xs = {}, {}
    for name, direction, scale in ((n, d, float(v)) for v in sc for n, d in
                                   (("strong direction", (1.0, 1.0)), ("weak direction", (1.0, -1.0)))):
        x = scale * np.array(direction) / np.sqrt(2.0)
        xs[name, scale] = x
        ys = [H @ x[:, None] + e for H, e in zip(Hs, noise)]
        b = sum(H.T @ np.linalg.solve(R, y) for H, R, y in zip(Hs, Rs, ys))
        ls = np.linalg.solve(A, b)
        cen = rg.ridge_fusion_plugin(Hs, Rs, ys, where=rg.ShrinkAt.CENTRALISED).x
        dis = rg.ridge_fusion_plugin(Hs, Rs, ys, where=rg.ShrinkAt.DISTRIBUTED).x
        sq[name, scale] = {k: np.round(np.sum((v - x[:, None]) ** 2, axis=0), 10)
                    for k, v in ((LS, ls), (RIDGE_CENTRALISED, cen), (RIDGE_DISTRIBUTED, dis))}
    return VectorStudy(sq=sq, x=xs, A=A, cond=float(np.linalg.cond(A)), tr_ls=float(np.trace(np.linalg.inv(A))),
                       runs=int(runs), seed=int(seed), scales=tuple(float(v) for v in sc))
